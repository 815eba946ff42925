//! # Forward dynamics
//!
//! The motion of the platform under given cable tensions: ẍ = M⁻¹ (W t + w_ext + w_g − b),
//! integrated from a pose and a twist. The state is (u, q, ẋ): the position u, a unit
//! quaternion q for the orientation (q̇ = ½ [0; ω] ⊗ q, renormalised after every step, so the
//! orientation stays on SO(3)) and the twist ẋ = [v; ω]. Components a motion pattern lacks
//! stay zero (planar: rotation about z only).
//!
//! Drives: tensions held constant, a tension profile t(t) interpolated linearly in time, or
//! elastic cables with commanded unstrained lengths l₀: t_i = max(0, k_i (l_i − l₀ᵢ) + c_i l̇_i)
//! with k_i = E S_i / l₀ᵢ (a slack cable pulls nothing; damping c_i acts on taut cables only).
//!
//! Integrators: classical fixed-step Runge–Kutta 4, and the adaptive Dormand–Prince 5(4) pair
//! with its error estimate on every state component, steps no longer than dt and landing on
//! every output time. A state that stops being finite, or a pose where the kinematics fail
//! (a cable of zero length), stops the run with [`DynamicsError::Diverged`] at that time.
//!
//! ## References
//! - Hairer, Nørsett & Wanner 1993, *Solving ODEs I*, §II.1 (RK4), §II.5 (Dormand–Prince
//!   5(4), Table 5.2) and §II.4 (step-size control, eq. (4.12)).
//! - Barrette & Gosselin 2005: the platform's equations of motion under cable tensions.
//! - Diebel 2006, *Representing attitude*, eq. (109): the quaternion kinematics.

use crate::error::bad;
use crate::rigid_body::pattern_components;
use crate::{DynamicsError, RigidBody};
use cdpr_kinematics::{MotionPattern, Pose, PoseKinematics, Robot};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3, Vector6};

/// What pulls on the platform.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Drive {
    /// Tensions held constant (N), one per cable.
    Tensions(Vec<f64>),
    /// Tensions given at times (s), interpolated linearly (held at the ends).
    Profile {
        /// Times, strictly increasing (s).
        times: Vec<f64>,
        /// Tensions per time (N), one per cable each.
        tensions: Vec<Vec<f64>>,
    },
    /// Elastic cables with commanded unstrained lengths l₀ (m).
    Elastic {
        /// l₀ per cable (m).
        unstrained_lengths: Vec<f64>,
        /// E S per cable (N).
        axial_stiffness: Vec<f64>,
        /// c per cable (N·s/m), acting on taut cables.
        damping: Vec<f64>,
    },
}

/// The integration scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Integrator {
    /// Classical Runge–Kutta 4 at the fixed step dt.
    Rk4,
    /// Dormand–Prince 5(4), adaptive, relative and absolute tolerance `tolerance`.
    Rk45 {
        /// Local error tolerance per step (mixed absolute/relative).
        tolerance: f64,
    },
}

/// The platform's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// u (m).
    pub position: Vector3<f64>,
    /// The orientation as a unit quaternion.
    pub orientation: UnitQuaternion<f64>,
    /// ẋ = [v; ω] (m/s, rad/s).
    pub twist: Vector6<f64>,
}

impl State {
    /// At `pose` with twist `twist` (pattern components placed in a 6-vector).
    pub fn new(pose: &Pose, twist: Vector6<f64>) -> Self {
        Self {
            position: pose.position,
            orientation: UnitQuaternion::from_rotation_matrix(&pose.rotation),
            twist,
        }
    }

    /// The pose.
    pub fn pose(&self) -> Pose {
        Pose::new(self.position, self.orientation.to_rotation_matrix())
    }
}

/// The derivative of a state: (u̇, q̇, ẍ).
#[derive(Debug, Clone, Copy)]
struct Rate {
    position: Vector3<f64>,
    orientation: Quaternion<f64>,
    twist: Vector6<f64>,
}

/// A simulated motion: one entry per output time.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// t (s).
    pub t: Vec<f64>,
    /// States.
    pub states: Vec<State>,
    /// ẍ = [v̇; ω̇] at each output time.
    pub accelerations: Vec<Vector6<f64>>,
    /// Cable tensions (N) at each output time, n per entry, flat.
    pub tensions: Vec<f64>,
    /// Integration steps taken (RK45: accepted ones).
    pub steps: usize,
    /// RK45: rejected steps.
    pub rejected: usize,
}

/// The simulator: a robot, its body, a drive and a constant external wrench.
#[derive(Debug, Clone)]
pub struct Simulator<'a> {
    robot: &'a Robot,
    body: RigidBody,
    drive: Drive,
    external: Vector6<f64>,
    kin: PoseKinematics,
    tensions: Vec<f64>,
    mask: [bool; 6],
    /// I_G⁻¹ (platform axes; zero unless spatial).
    inertia_inverse: Matrix3<f64>,
}

impl<'a> Simulator<'a> {
    /// A simulator; `external` is w_ext (DOF numbers, N and N·m, constant) on top of gravity.
    pub fn new(
        robot: &'a Robot,
        body: RigidBody,
        drive: Drive,
        external: &[f64],
    ) -> Result<Self, DynamicsError> {
        let motion = robot.motion();
        let n = robot.cable_count();
        let check = |what: &'static str, v: &[f64]| -> Result<(), DynamicsError> {
            if v.len() != n {
                return Err(DynamicsError::DimensionMismatch {
                    what,
                    expected: n,
                    found: v.len(),
                });
            }
            Ok(())
        };
        match &drive {
            Drive::Tensions(t) => {
                check("tensions (one per cable)", t)?;
                finite("tensions", t)?;
            }
            Drive::Profile { times, tensions } => {
                if times.is_empty() || times.len() != tensions.len() {
                    return Err(DynamicsError::DimensionMismatch {
                        what: "tension profile entries (one per time)",
                        expected: times.len(),
                        found: tensions.len(),
                    });
                }
                for (k, t) in tensions.iter().enumerate() {
                    check("tensions (one per cable)", t)?;
                    finite("tensions", t)?;
                    if k > 0
                        && times[k].partial_cmp(&times[k - 1]) != Some(std::cmp::Ordering::Greater)
                    {
                        return Err(bad(
                            format!("t[{k}]"),
                            times[k],
                            "profile times must increase strictly",
                        ));
                    }
                }
            }
            Drive::Elastic {
                unstrained_lengths,
                axial_stiffness,
                damping,
            } => {
                check("unstrained lengths (one per cable)", unstrained_lengths)?;
                check("axial_stiffness (one per cable)", axial_stiffness)?;
                check("damping (one per cable)", damping)?;
                for (i, &l) in unstrained_lengths.iter().enumerate() {
                    if !(l.is_finite() && l > 0.0) {
                        return Err(bad(format!("unstrained-lengths[{i}]"), l, "must be > 0"));
                    }
                }
                for (i, &e) in axial_stiffness.iter().enumerate() {
                    if !(e.is_finite() && e > 0.0) {
                        return Err(bad(format!("axial_stiffness[{i}]"), e, "must be > 0"));
                    }
                }
                for (i, &c) in damping.iter().enumerate() {
                    if !(c.is_finite() && c >= 0.0) {
                        return Err(bad(format!("damping[{i}]"), c, "must be ≥ 0"));
                    }
                }
            }
        }
        if external.len() != motion.dof() {
            return Err(DynamicsError::DimensionMismatch {
                what: "external wrench",
                expected: motion.dof(),
                found: external.len(),
            });
        }
        finite("external wrench", external)?;
        let mut mask = [false; 6];
        let mut ext = Vector6::zeros();
        for (&i, &w) in pattern_components(motion).iter().zip(external) {
            mask[i] = true;
            ext[i] = w;
        }
        Ok(Self {
            robot,
            body,
            drive,
            external: ext,
            kin: PoseKinematics::for_robot(robot),
            tensions: vec![0.0; n],
            mask,
            inertia_inverse: if motion == MotionPattern::Spatial {
                body.inertia
                    .try_inverse()
                    .ok_or_else(|| bad("inertia", body.inertia.determinant(), "is singular"))?
            } else {
                Matrix3::zeros()
            },
        })
    }

    /// The motion pattern.
    pub fn motion(&self) -> MotionPattern {
        self.robot.motion()
    }

    /// The tensions of the last evaluation (N).
    pub fn tensions(&self) -> &[f64] {
        &self.tensions
    }

    /// ẍ at time t and state x (writes the tensions used into [`Simulator::tensions`]).
    pub fn acceleration(&mut self, t: f64, x: &State) -> Result<Vector6<f64>, DynamicsError> {
        let rotation = x.orientation.to_rotation_matrix();
        let r = *rotation.matrix();
        let c = r * self.body.centre_of_mass;
        let pose = Pose::new(x.position, rotation);
        self.robot
            .update_kinematics(&pose, &mut self.kin)
            .map_err(|e| DynamicsError::Diverged {
                time: t,
                why: e.to_string(),
            })?;
        let v = x.twist.fixed_rows::<3>(0).into_owned();
        let w = x.twist.fixed_rows::<3>(3).into_owned();
        match &self.drive {
            Drive::Tensions(ts) => self.tensions.copy_from_slice(ts),
            Drive::Profile { times, tensions } => {
                let k = times.partition_point(|&c| c <= t);
                if k == 0 {
                    self.tensions.copy_from_slice(&tensions[0]);
                } else if k == times.len() {
                    self.tensions.copy_from_slice(&tensions[k - 1]);
                } else {
                    let s = (t - times[k - 1]) / (times[k] - times[k - 1]);
                    for (o, (a, b)) in self
                        .tensions
                        .iter_mut()
                        .zip(tensions[k - 1].iter().zip(&tensions[k]))
                    {
                        *o = a + s * (b - a);
                    }
                }
            }
            Drive::Elastic {
                unstrained_lengths,
                axial_stiffness,
                damping,
            } => {
                for (i, c) in self.kin.cables().iter().enumerate() {
                    let l0 = unstrained_lengths[i];
                    let stretch = c.length - l0;
                    self.tensions[i] = if stretch > 0.0 {
                        let rate = -c.unit.dot(&(v + w.cross(&c.attachment)));
                        (axial_stiffness[i] / l0 * stretch + damping[i] * rate).max(0.0)
                    } else {
                        0.0
                    };
                }
            }
        }
        // ẍ = M⁻¹ (W t + w_ext + w_g − b) by the block structure of M: with [f; τ] the right-hand
        // side, α = I_G'⁻¹ (τ − c × f) (I_G' = R I_G Rᵀ, the Schur complement of m 1) and
        // a = f / m + c × α; I_G⁻¹ is inverted once.
        let body = &self.body;
        let (f, tau) = self.applied_wrench(&r, &c, &w);
        let m = body.mass;
        let acc = match self.motion() {
            MotionPattern::Point2 | MotionPattern::Point3 => {
                let a = f / m;
                Vector6::new(a.x, a.y, a.z, 0.0, 0.0, 0.0)
            }
            MotionPattern::Planar => {
                let izz = (r.row(2) * body.inertia * r.row(2).transpose())[0];
                let alpha = (tau.z - c.cross(&f).z) / izz;
                Vector6::new(
                    f.x / m + alpha * c.y,
                    f.y / m - alpha * c.x,
                    0.0,
                    0.0,
                    0.0,
                    alpha,
                )
            }
            MotionPattern::Spatial => {
                let alpha = r * (self.inertia_inverse * (r.transpose() * (tau - c.cross(&f))));
                let a = f / m + c.cross(&alpha);
                Vector6::new(a.x, a.y, a.z, alpha.x, alpha.y, alpha.z)
            }
        };
        if acc.iter().any(|a| !a.is_finite()) {
            return Err(DynamicsError::Diverged {
                time: t,
                why: "the acceleration is not finite".into(),
            });
        }
        Ok(acc)
    }

    fn rate(&mut self, t: f64, x: &State) -> Result<Rate, DynamicsError> {
        let acc = self.acceleration(t, x)?;
        let w = x.twist.fixed_rows::<3>(3);
        let omega = Quaternion::new(0.0, w[0], w[1], w[2]);
        Ok(Rate {
            position: x.twist.fixed_rows::<3>(0).into_owned(),
            orientation: omega * x.orientation.into_inner() * 0.5,
            twist: acc,
        })
    }

    /// [f; τ] = W t + w_ext + w_g − b at orientation r (c = R c̄) and angular velocity ω, with
    /// the tensions of the last evaluation; components the pattern lacks are zero.
    fn applied_wrench(
        &self,
        r: &Matrix3<f64>,
        c: &Vector3<f64>,
        w: &Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let body = &self.body;
        let weight = body.mass * body.gravity;
        let mut f = self.external.fixed_rows::<3>(0) + weight;
        let mut tau = self.external.fixed_rows::<3>(3) + c.cross(&weight);
        for (cable, &ti) in self.kin.cables().iter().zip(&self.tensions) {
            let pull = ti * cable.unit;
            f += pull;
            tau += cable.attachment.cross(&pull);
        }
        if self.motion().has_orientation() {
            // b = [m ω × (ω × c); ω × (I_P ω)], I_P ω = R I_G Rᵀ ω − m c × (c × ω).
            let ip_w = r * (body.inertia * (r.transpose() * w)) - body.mass * c.cross(&c.cross(w));
            f -= body.mass * w.cross(&w.cross(c));
            tau -= w.cross(&ip_w);
        }
        for i in 0..3 {
            if !self.mask[i] {
                f[i] = 0.0;
            }
            if !self.mask[i + 3] {
                tau[i] = 0.0;
            }
        }
        (f, tau)
    }

    /// One classical RK4 step of length h from (t, x).
    pub fn rk4_step(&mut self, t: f64, x: &State, h: f64) -> Result<State, DynamicsError> {
        let k1 = self.rate(t, x)?;
        let k2 = self.rate(t + 0.5 * h, &advance(x, &[(0.5 * h, &k1)]))?;
        let k3 = self.rate(t + 0.5 * h, &advance(x, &[(0.5 * h, &k2)]))?;
        let k4 = self.rate(t + h, &advance(x, &[(h, &k3)]))?;
        let h6 = h / 6.0;
        let next = advance(x, &[(h6, &k1), (2.0 * h6, &k2), (2.0 * h6, &k3), (h6, &k4)]);
        check_state(t + h, &next)?;
        Ok(next)
    }

    /// Integrates from `start` (at t = 0) for `duration` s, output every `dt` s.
    pub fn run(
        &mut self,
        start: State,
        duration: f64,
        dt: f64,
        integrator: Integrator,
    ) -> Result<Simulation, DynamicsError> {
        if !(duration.is_finite() && duration > 0.0) {
            return Err(bad("duration", duration, "must be a finite number > 0"));
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err(bad("dt", dt, "must be a finite number > 0"));
        }
        let steps = (duration / dt - 1e-9).ceil();
        if steps > 1e7 {
            return Err(bad("dt", dt, "makes more than 10 000 000 steps"));
        }
        if let Integrator::Rk45 { tolerance } = integrator
            && !(tolerance.is_finite() && tolerance > 0.0)
        {
            return Err(bad("tolerance", tolerance, "must be a finite number > 0"));
        }
        let steps = steps as usize;
        let n = self.robot.cable_count();
        let mut sim = Simulation {
            t: Vec::with_capacity(steps + 1),
            states: Vec::with_capacity(steps + 1),
            accelerations: Vec::with_capacity(steps + 1),
            tensions: Vec::with_capacity((steps + 1) * n),
            steps: 0,
            rejected: 0,
        };
        check_state(0.0, &start)?;
        let mut x = start;
        let mut t = 0.0;
        let mut h_try = dt;
        for k in 0..=steps {
            let acc = self.acceleration(t, &x)?;
            sim.t.push(t);
            sim.states.push(x);
            sim.accelerations.push(acc);
            sim.tensions.extend_from_slice(&self.tensions);
            if k == steps {
                break;
            }
            let target = if k + 1 == steps {
                duration
            } else {
                (k + 1) as f64 * dt
            };
            match integrator {
                Integrator::Rk4 => {
                    x = self.rk4_step(t, &x, target - t)?;
                    sim.steps += 1;
                }
                Integrator::Rk45 { tolerance } => {
                    while t < target {
                        let h = h_try.min(target - t);
                        let (next, err) = self.dopri_step(t, &x, h, tolerance)?;
                        if err <= 1.0 {
                            x = next;
                            t += h;
                            if target - t < 1e-12 * dt {
                                t = target;
                            }
                            sim.steps += 1;
                        } else {
                            sim.rejected += 1;
                        }
                        // Hairer, Nørsett & Wanner eq. (4.13): fac = 0.9, bounds 0.2…5.
                        let fac = (0.9 * err.max(1e-10).powf(-0.2)).clamp(0.2, 5.0);
                        h_try = (h * fac).min(dt);
                        if h_try < 1e-14 * dt.max(t) {
                            return Err(DynamicsError::Diverged {
                                time: t,
                                why: format!("the step size fell to {h_try:e} s"),
                            });
                        }
                    }
                }
            }
            t = target;
        }
        Ok(sim)
    }

    /// One Dormand–Prince 5(4) step: the 5th-order state and the scaled error norm.
    fn dopri_step(
        &mut self,
        t: f64,
        x: &State,
        h: f64,
        tol: f64,
    ) -> Result<(State, f64), DynamicsError> {
        // Hairer, Nørsett & Wanner 1993, Table 5.2.
        const C: [f64; 6] = [0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
        const A: [&[f64]; 6] = [
            &[0.2],
            &[3.0 / 40.0, 9.0 / 40.0],
            &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
            &[
                19372.0 / 6561.0,
                -25360.0 / 2187.0,
                64448.0 / 6561.0,
                -212.0 / 729.0,
            ],
            &[
                9017.0 / 3168.0,
                -355.0 / 33.0,
                46732.0 / 5247.0,
                49.0 / 176.0,
                -5103.0 / 18656.0,
            ],
            &[
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
            ],
        ];
        // 5th-order weights minus 4th-order weights (the error estimate).
        const E: [f64; 7] = [
            71.0 / 57600.0,
            0.0,
            -71.0 / 16695.0,
            71.0 / 1920.0,
            -17253.0 / 339200.0,
            22.0 / 525.0,
            -1.0 / 40.0,
        ];
        let mut k = [self.rate(t, x)?; 7];
        for s in 0..6 {
            let terms: Vec<(f64, &Rate)> = A[s].iter().zip(&k).map(|(&a, r)| (h * a, r)).collect();
            let xs = advance(x, &terms);
            k[s + 1] = self.rate(t + C[s] * h, &xs)?;
        }
        let next = advance(
            x,
            &A[5]
                .iter()
                .zip(&k)
                .map(|(&a, r)| (h * a, r))
                .collect::<Vec<_>>(),
        );
        check_state(t + h, &next)?;
        // Error estimate h Σ e_i k_i, scaled by tol (1 + |x|) per component.
        let mut err: f64 = 0.0;
        let mut p = Vector3::zeros();
        let mut q = Quaternion::new(0.0, 0.0, 0.0, 0.0);
        let mut v = Vector6::zeros();
        for (e, r) in E.iter().zip(&k) {
            p += r.position * (h * e);
            q += r.orientation * (h * e);
            v += r.twist * (h * e);
        }
        for i in 0..3 {
            err = err.max(p[i].abs() / (tol * (1.0 + next.position[i].abs())));
        }
        err = err.max(q.coords.amax() / tol);
        for i in 0..6 {
            err = err.max(v[i].abs() / (tol * (1.0 + next.twist[i].abs())));
        }
        Ok((next, err))
    }
}

/// x + Σ h_j k_j, the quaternion renormalised.
fn advance(x: &State, terms: &[(f64, &Rate)]) -> State {
    let mut p = x.position;
    let mut q = x.orientation.into_inner();
    let mut v = x.twist;
    for (h, r) in terms {
        p += r.position * *h;
        q += r.orientation * *h;
        v += r.twist * *h;
    }
    State {
        position: p,
        orientation: UnitQuaternion::new_normalize(q),
        twist: v,
    }
}

fn check_state(t: f64, x: &State) -> Result<(), DynamicsError> {
    let finite = x.position.iter().all(|v| v.is_finite())
        && x.twist.iter().all(|v| v.is_finite())
        && x.orientation.coords.iter().all(|v| v.is_finite());
    if finite {
        Ok(())
    } else {
        Err(DynamicsError::Diverged {
            time: t,
            why: "the state is no longer finite".into(),
        })
    }
}

fn finite(what: &str, v: &[f64]) -> Result<(), DynamicsError> {
    match v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        Some((i, &x)) => Err(bad(format!("{what}[{i}]"), x, "must be finite")),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use cdpr_wrench::Platform;
    use nalgebra::Matrix3;

    /// The IPAnema-1-like 8-cable robot (frame 4 × 3 × 2 m).
    fn robot8() -> Robot {
        cdpr_kinematics::reference_robots::ipanema_like_8()
    }

    fn body(com: Vector3<f64>, gravity: Vector3<f64>) -> RigidBody {
        let p = Platform {
            mass: 2.0,
            centre_of_mass: com,
            gravity,
        };
        RigidBody::new(
            &p,
            Matrix3::new(0.05, 0.004, -0.002, 0.004, 0.03, 0.001, -0.002, 0.001, 0.02),
        )
        .unwrap()
    }

    /// Free fall with slack cables: z = z₀ − g t²/2 to round-off (RK4 integrates quadratics
    /// exactly), with an initial horizontal velocity kept.
    #[test]
    fn free_fall() {
        let robot = robot8();
        let b = body(Vector3::new(0.0, 0.0, 0.05), cdpr_wrench::STANDARD_GRAVITY);
        let mut sim = Simulator::new(&robot, b, Drive::Tensions(vec![0.0; 8]), &[0.0; 6]).unwrap();
        let start = State::new(
            &Pose::point(0.0, 0.0, 1.0),
            Vector6::new(0.1, 0.0, 0.0, 0.0, 0.0, 0.0),
        );
        let run = sim.run(start, 0.4, 1e-3, Integrator::Rk4).unwrap();
        let g = 9.80665;
        for (t, s) in run.t.iter().zip(&run.states) {
            assert_relative_eq!(s.position.z, 1.0 - 0.5 * g * t * t, epsilon = 1e-12);
            assert_relative_eq!(s.position.x, 0.1 * t, epsilon = 1e-13);
            assert_relative_eq!(s.twist[2], -g * t, epsilon = 1e-12);
            assert!(s.twist.fixed_rows::<3>(3).norm() < 1e-12);
        }
        assert_eq!(run.t.len(), 401);
        assert_relative_eq!(*run.t.last().unwrap(), 0.4);
    }

    /// A torque-free asymmetric body spinning about no principal axis keeps its angular
    /// momentum I_P ω (base axes) and its energy ½ ωᵀ I_P ω to 10⁻⁶ over 2 s at dt = 1 ms, with
    /// RK4 and with RK45.
    #[test]
    fn torque_free_body_conserves_momentum_and_energy() {
        let robot = robot8();
        let b = body(Vector3::zeros(), Vector3::zeros());
        for integrator in [Integrator::Rk4, Integrator::Rk45 { tolerance: 1e-10 }] {
            let mut sim =
                Simulator::new(&robot, b, Drive::Tensions(vec![0.0; 8]), &[0.0; 6]).unwrap();
            let start = State::new(
                &Pose::spatial(Vector3::new(0.0, 0.0, 1.0), 0.2, -0.1, 0.4),
                Vector6::new(0.0, 0.0, 0.0, 3.0, -2.0, 5.0),
            );
            let run = sim.run(start, 2.0, 1e-3, integrator).unwrap();
            let momentum = |s: &State| {
                let r = s.orientation.to_rotation_matrix();
                let ip = r.matrix() * b.inertia * r.matrix().transpose();
                let w = s.twist.fixed_rows::<3>(3).into_owned();
                (ip * w, 0.5 * w.dot(&(ip * w)))
            };
            let (h0, e0) = momentum(&run.states[0]);
            for s in &run.states {
                let (h, e) = momentum(s);
                assert!((h - h0).norm() < 1e-6, "{integrator:?}: {h} vs {h0}");
                assert!((e - e0).abs() < 1e-6, "{integrator:?}: {e} vs {e0}");
                assert_relative_eq!(s.orientation.norm(), 1.0, epsilon = 1e-14);
            }
            // The body did tumble (ω changed direction in base axes).
            let w_end = run
                .states
                .last()
                .unwrap()
                .twist
                .fixed_rows::<3>(3)
                .into_owned();
            assert!((w_end - Vector3::new(3.0, -2.0, 5.0)).norm() > 0.1);
        }
    }

    /// Stiff cables and a coarse step make RK4 unstable (ω dt ≫ 2.8): the run stops with a
    /// divergence that names the time it happened, before the end.
    #[test]
    fn divergence_reports_its_time() {
        let robot = robot8();
        let b = body(Vector3::zeros(), cdpr_wrench::STANDARD_GRAVITY);
        let pose = Pose::point(0.0, 0.0, 1.0);
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let drive = Drive::Elastic {
            unstrained_lengths: kin.lengths().map(|l| 0.999 * l).collect(),
            axial_stiffness: vec![1e9; 8],
            damping: vec![0.0; 8],
        };
        let mut sim = Simulator::new(&robot, b, drive, &[0.0; 6]).unwrap();
        let start = State::new(&Pose::point(0.001, 0.0, 1.0), Vector6::zeros());
        match sim.run(start, 10.0, 0.01, Integrator::Rk4) {
            Err(DynamicsError::Diverged { time, .. }) => assert!(time > 0.0 && time < 10.0),
            Err(e) => panic!("{e}"),
            Ok(run) => panic!("no divergence over {} steps", run.steps),
        }
    }

    /// Tensions of the static equilibrium at `pose` (ℓ2, 10…1000 N) and the unstrained lengths
    /// that produce them with E S per cable: l₀ = l E S / (E S + t).
    fn elasto_static(robot: &Robot, b: &RigidBody, pose: &Pose, es: f64) -> (Vec<f64>, Vec<f64>) {
        use cdpr_tension::{Method, TensionBounds, TensionOutcome, TensionProblem, TensionSolver};
        let kin = robot.inverse_kinematics(pose).unwrap();
        let w = kin.wrench_matrix();
        let g = b.gravity_wrench6(pose.rotation.matrix());
        let g = nalgebra::DVector::from_column_slice(g.as_slice());
        let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
        let TensionOutcome::Feasible(s) = TensionSolver::new(Method::L2)
            .solve(&TensionProblem::new(&w, &g, &bounds))
            .unwrap()
        else {
            panic!("infeasible")
        };
        let t: Vec<f64> = s.tensions.iter().copied().collect();
        let l0 = kin
            .lengths()
            .zip(&t)
            .map(|(l, t)| l * es / (es + t))
            .collect();
        (t, l0)
    }

    /// Released at rest at its elasto-static pose, an elastic robot stays there.
    #[test]
    fn elastic_equilibrium_stays() {
        let robot = robot8();
        let b = body(Vector3::new(0.0, 0.0, -0.05), cdpr_wrench::STANDARD_GRAVITY);
        let pose = Pose::spatial(Vector3::new(0.2, -0.1, 0.9), 0.05, 0.0, 0.1);
        let (t, l0) = elasto_static(&robot, &b, &pose, 6e4);
        let drive = Drive::Elastic {
            unstrained_lengths: l0,
            axial_stiffness: vec![6e4; 8],
            damping: vec![5.0; 8],
        };
        let mut sim = Simulator::new(&robot, b, drive, &[0.0; 6]).unwrap();
        let run = sim
            .run(
                State::new(&pose, Vector6::zeros()),
                1.0,
                1e-3,
                Integrator::Rk4,
            )
            .unwrap();
        for (k, s) in run.states.iter().enumerate() {
            assert!((s.position - pose.position).norm() < 1e-9, "{}", s.position);
            assert!(
                (s.orientation.to_rotation_matrix().matrix() - pose.rotation.matrix()).amax()
                    < 1e-9
            );
            for (a, b) in run.tensions[k * 8..(k + 1) * 8].iter().zip(&t) {
                assert_relative_eq!(a, b, max_relative = 1e-7);
            }
        }
    }

    /// Small oscillations about the elasto-static pose follow the linear model
    /// M δẍ = −K δx with K the stiffness matrix of `cdpr-wrench` (k_i = E S / l₀ᵢ): δx(t) =
    /// cos(√(M⁻¹K) t) δx₀, whose frequencies are √eig(M⁻¹K). The matrix cosine is summed as
    /// its power series Σ (−1)ᵏ (M⁻¹K t²)ᵏ / (2k)!.
    #[test]
    fn small_oscillations_follow_the_stiffness_matrix() {
        let robot = robot8();
        let b = body(Vector3::zeros(), cdpr_wrench::STANDARD_GRAVITY);
        let pose = Pose::point(0.1, 0.2, 1.1);
        let es = 6e4;
        let (t, l0) = elasto_static(&robot, &b, &pose, es);
        let kin = robot.inverse_kinematics(&pose).unwrap();
        // stiffness_matrix uses k_i = E S / l_i: pass E S · l_i / l₀ᵢ for k_i = E S / l₀ᵢ.
        let es_eff: Vec<f64> = kin.lengths().zip(&l0).map(|(l, l0)| es * l / l0).collect();
        let k = cdpr_wrench::stiffness_matrix(&kin, &t, &es_eff).unwrap();
        let (m6, _) = b.spatial_terms(pose.rotation.matrix(), &Vector3::zeros());
        let m = nalgebra::DMatrix::from_column_slice(6, 6, m6.as_slice());
        let a = m.clone().lu().solve(&k).unwrap();
        // Frequencies √eig(M⁻¹K) (rad/s): real and positive at a stable equilibrium.
        let eig = a.complex_eigenvalues();
        for e in eig.iter() {
            assert!(e.re > 0.0 && e.im.abs() < 1e-6 * e.re, "{e}");
        }
        let drive = Drive::Elastic {
            unstrained_lengths: l0,
            axial_stiffness: vec![es; 8],
            damping: vec![0.0; 8],
        };
        let mut sim = Simulator::new(&robot, b, drive, &[0.0; 6]).unwrap();
        let eps = 1e-7;
        let dx0 = nalgebra::DVector::from_vec(vec![1.0, -0.5, 0.8, 2.0, -1.0, 1.5]) * eps;
        let rot0 = nalgebra::Rotation3::new(Vector3::new(dx0[3], dx0[4], dx0[5]));
        let start = State::new(
            &Pose::new(pose.position + dx0.fixed_rows::<3>(0), rot0 * pose.rotation),
            Vector6::zeros(),
        );
        let run = sim.run(start, 0.02, 1e-4, Integrator::Rk4).unwrap();
        let cosine = |t: f64| {
            let x = &a * (t * t);
            let mut term = nalgebra::DMatrix::<f64>::identity(6, 6);
            let mut sum = term.clone();
            for j in 1..80 {
                term = -&term * &x / ((2 * j - 1) as f64 * (2 * j) as f64);
                sum += &term;
            }
            sum
        };
        for k in (0..run.t.len()).step_by(20) {
            let s = &run.states[k];
            let dp = s.position - pose.position;
            // The rotation vector of R R₀ᵀ from its skew part (exact to O(ε³); the angle from
            // the trace would lose half the digits).
            let d =
                s.orientation.to_rotation_matrix().matrix() * pose.rotation.matrix().transpose();
            let dr = 0.5
                * Vector3::new(
                    d[(2, 1)] - d[(1, 2)],
                    d[(0, 2)] - d[(2, 0)],
                    d[(1, 0)] - d[(0, 1)],
                );
            let got = nalgebra::DVector::from_vec(vec![dp.x, dp.y, dp.z, dr.x, dr.y, dr.z]);
            let want = cosine(run.t[k]) * &dx0;
            assert!(
                (&got - &want).amax() < 2e-3 * eps,
                "t = {}: {:?} vs {:?}",
                run.t[k],
                got.as_slice(),
                want.as_slice()
            );
        }
    }

    /// The block (Schur complement) solve of the simulator equals M⁻¹ (W t + w − b) with M and
    /// b of `RigidBody::pattern_terms` solved by Cholesky, spatial and planar, offset centre of
    /// mass, spinning platform.
    #[test]
    fn block_solve_matches_the_mass_matrix() {
        let b = body(
            Vector3::new(0.03, -0.02, 0.04),
            cdpr_wrench::STANDARD_GRAVITY,
        );
        let spatial = robot8();
        let planar = cdpr_kinematics::reference_robots::thesis_four_cable();
        for robot in [&spatial, &planar] {
            let motion = robot.motion();
            let keep = pattern_components(motion);
            let tensions: Vec<f64> = (0..robot.cable_count())
                .map(|i| 20.0 + 7.0 * i as f64)
                .collect();
            let mut sim = Simulator::new(
                robot,
                b,
                Drive::Tensions(tensions.clone()),
                &vec![0.5; motion.dof()],
            )
            .unwrap();
            let pose = match motion {
                MotionPattern::Spatial => {
                    Pose::spatial(Vector3::new(0.1, -0.2, 1.0), 0.2, -0.3, 0.5)
                }
                _ => Pose::planar(0.05, -0.02, 0.3),
            };
            let twist =
                crate::rigid_body::embed(motion, &[0.3, -0.2, 0.5, 1.1, -0.7, 2.0][..motion.dof()]);
            let x = State::new(&pose, twist);
            let acc = sim.acceleration(0.0, &x).unwrap();
            let kin = robot.inverse_kinematics(&pose).unwrap();
            let wt = kin.wrench_matrix() * nalgebra::DVector::from_vec(tensions);
            let g = b.gravity_wrench6(pose.rotation.matrix());
            let (m6, b6) = b.pattern_terms(motion, pose.rotation.matrix(), &twist);
            let d = keep.len();
            let m = nalgebra::DMatrix::from_fn(d, d, |i, j| m6[(keep[i], keep[j])]);
            let rhs = nalgebra::DVector::from_fn(d, |i, _| wt[i] + 0.5 + g[keep[i]] - b6[keep[i]]);
            let want = m.cholesky().unwrap().solve(&rhs);
            for i in 0..d {
                assert_relative_eq!(acc[keep[i]], want[i], epsilon = 1e-10);
            }
            for i in (0..6).filter(|i| !keep.contains(i)) {
                assert_eq!(acc[i], 0.0);
            }
        }
    }

    /// Bad settings name their key.
    #[test]
    fn bad_settings() {
        let robot = robot8();
        let b = body(Vector3::zeros(), Vector3::zeros());
        assert!(Simulator::new(&robot, b, Drive::Tensions(vec![0.0; 7]), &[0.0; 6]).is_err());
        let mut sim = Simulator::new(&robot, b, Drive::Tensions(vec![0.0; 8]), &[0.0; 6]).unwrap();
        let s = State::new(&Pose::point(0.0, 0.0, 1.0), Vector6::zeros());
        for (d, dt, key) in [
            (-1.0, 0.1, "duration"),
            (1.0, 0.0, "dt"),
            (1.0, f64::NAN, "dt"),
        ] {
            match sim.run(s, d, dt, Integrator::Rk4) {
                Err(DynamicsError::BadSetting { key: k, .. }) => assert_eq!(k, key),
                other => panic!("{other:?}"),
            }
        }
    }
}

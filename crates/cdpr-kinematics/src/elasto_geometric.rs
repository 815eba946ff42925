//! # Elasto-geometric forward kinematics
//!
//! From the cables' *unstrained* lengths L0 (what the winches paid out) to the platform pose,
//! with elastic or heavy elastic cables (Irvine's elastic catenary, module [`crate::catenary`]).
//! The pose is no longer fixed by geometry alone: it is the platform's equilibrium under the
//! cable forces and the external wrench (its weight, a payload),
//!
//! ```text
//!   g(x) = Σ_i [f_i(x); a_i × f_i(x)] + w_ext(x) = 0,     f_i = −(F_x,i ê_h,i + F_z,i ê_up),
//! ```
//!
//! where (F_x,i, F_z,i) is the end force of cable i's catenary of unstrained length L0_i across
//! the span from its frame point to the attachment at pose x
//! ([`crate::ElasticCatenary::solve_for_length`], warm-started from the previous iterate). g
//! has one equation per DOF: with n ≥ DOF cables the problem is square and the tensions are
//! outputs (Pott 2018, §6.4; Kozak, Zhou & Wang 2006).
//!
//! ## Newton's step: the stiffness matrix
//! ∂g/∂x = −K, K the platform's stiffness matrix with these cables (Behzadipour & Khajepour
//! 2006). Per cable, with the span d = B − A, its horizontal part of length x_h along ê_h, the
//! vertical ê_up and the in-plane stiffness K_c = (∂(x_B, z_B)/∂(F_x, F_z))⁻¹ (the inverse
//! of the catenary's flexibility matrix, Kozak, Zhou & Wang 2006, eq. (8)),
//!
//! ```text
//!   S_i = ∂f_i/∂B = −[ê_h ê_up] K_c [ê_h ê_up]ᵀ − (F_x/x_h) (I − ê_h ê_hᵀ − ê_up ê_upᵀ)
//! ```
//!
//! (for a weightless cable S_i = −(EA/L0) u uᵀ − (T/l)(I − u uᵀ)), and for a twist
//! (δp, δφ), δB = δp − [a]× δφ:
//!
//! ```text
//!   ∂g_i/∂(δp, δφ) = [ S_i            −S_i [a]×
//!                      [a]× S_i    [f_i]× [a]× − [a]× S_i [a]× ],
//! ```
//!
//! restricted to the motion pattern's rows and columns. A pose-dependent external wrench
//! (weight with an offset centre of mass, springs) enters by forward differences. The iteration
//! is Levenberg–Marquardt on ½‖D g‖² (D divides moments by ℓ, the robot's length scale):
//! μ = 0 is Newton's step, a step that raises the cost is rejected and μ raised (Nielsen's
//! rule).
//!
//! A weightless cable longer than its chord is *slack*: it pulls nothing (reported, tension 0;
//! Newton's step keeps its taut axial stiffness so that a start with slack cables moves towards
//! the pose where they tighten). An inextensible heavy cable shorter than its chord cannot
//! reach: such a trial pose is rejected.
//!
//! Every answer is certified by its residual max |D g| (N) recomputed at the returned pose.
//! Newton's method converges from a start near the equilibrium: `cdpr forward` starts from
//! the straight cables' pose for the unstrained lengths ([`crate::ForwardKinematics`]).
//!
//! ## References
//! - Pott, *Cable-Driven Parallel Robots*, Springer 2018, §6.4 (elasto-geometric models).
//! - Kozak, Zhou & Wang 2006, "Static analysis of cable-driven manipulators with non-negligible
//!   cable mass", IEEE T-RO 22(3), eqs. (6)–(8).
//! - Behzadipour & Khajepour 2006, "Stiffness of cable-based parallel manipulators with
//!   application to stability analysis", J. Mech. Design 128(1).
//! - Irvine, *Cable Structures*, MIT Press 1981, §2.3.
//! - Nielsen 1999 (damping update).

use crate::catenary::{ElasticCatenary, RobotCatenaries, SaggingCable, plane_span};
use crate::forward_kinematics::displaced;
use crate::{KinematicsError, MotionPattern, Pose, PoseKinematics, Robot};
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// Settings of [`ElastoGeometricForward`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElastoGeometricSettings {
    /// The pose is an equilibrium when max |g_j| ≤ `tolerance` × max(1, ‖w_ext‖∞, max T_B)
    /// plus 10⁻¹¹ × max EA (moments divided by the length scale; the second term is the noise
    /// floor of the catenary solves, a pose error of about 10⁻¹¹ × the cable length).
    pub tolerance: f64,
    /// Largest number of iterations (accepted or rejected steps).
    pub max_iterations: usize,
}

impl Default for ElastoGeometricSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-9,
            max_iterations: 100,
        }
    }
}

/// How an elasto-geometric forward-kinematics solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ElastoGeometricStatus {
    /// The residual is within the tolerance: a certified equilibrium.
    Equilibrium,
    /// The iteration stopped (stationary point or iteration limit) with a larger residual.
    NotConverged,
}

impl ElastoGeometricStatus {
    /// The name used in JSON output and messages.
    pub fn name(self) -> &'static str {
        match self {
            Self::Equilibrium => "equilibrium",
            Self::NotConverged => "did not converge",
        }
    }
}

/// An elasto-geometric forward-kinematics answer; the cables' states at the pose are
/// [`ElastoGeometricForward::cables`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElastoGeometricSolution {
    /// The pose found (the best one, whatever the status).
    pub pose: Pose,
    /// max |g_j| (N; moments in N·m divided by the length scale ℓ, m) at `pose`.
    pub residual: f64,
    /// Iterations taken (accepted and rejected steps).
    pub iterations: usize,
    /// How the solve ended.
    pub status: ElastoGeometricStatus,
    /// Number of slack cables at `pose`.
    pub slack_count: usize,
}

/// One cable's state at a trial pose, what the residual and the Jacobian need.
#[derive(Debug, Clone, Copy, Default)]
struct CableForce {
    /// Force on the platform (N, base frame).
    force: Vector3<f64>,
    /// ∂force/∂B (N/m).
    stiffness: Matrix3<f64>,
    /// (F_x, F_z) of the plane solution, the warm start of the next solve.
    plane_force: (f64, f64),
    slack: bool,
}

/// A pose-dependent external wrench: writes its DOF components at a pose.
pub type PoseLoad<'l> = dyn FnMut(&Pose, &mut [f64]) -> Result<(), KinematicsError> + 'l;

/// The external wrench: one for every pose, or a function of the pose.
enum Load<'l, 'f> {
    Constant(&'l [f64]),
    Posed(&'l mut PoseLoad<'f>),
}

/// Indices of a motion pattern's wrench and twist components in the spatial 6-vectors.
fn components(motion: MotionPattern) -> &'static [usize] {
    match motion {
        MotionPattern::Point2 => &[0, 1],
        MotionPattern::Planar => &[0, 1, 5],
        MotionPattern::Point3 => &[0, 1, 2],
        MotionPattern::Spatial => &[0, 1, 2, 3, 4, 5],
    }
}

/// The cross-product matrix [v]×.
fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// A reusable elasto-geometric forward-kinematics solver for one robot and cable model: no
/// allocation per solve.
///
/// ```
/// use cdpr_kinematics::nalgebra::{DMatrix, DVector, Vector3};
/// use cdpr_kinematics::catenary::write_sagging_wrench_matrix;
/// use cdpr_kinematics::reference_robots::ipanema_like_8;
/// use cdpr_kinematics::{ElastoGeometricForward, ElastoGeometricStatus, Pose, RobotCatenaries};
/// let robot = ipanema_like_8();
/// let model = RobotCatenaries::new(&[0.02; 8], &[6e4; 8], &Vector3::new(0.0, 0.0, -9.81)).unwrap();
/// // The unstrained lengths that hold the platform at `truth` with tensions t (N) ...
/// let truth = Pose::spatial(Vector3::new(0.2, -0.1, 1.0), 0.02, 0.0, 0.05);
/// let t = [120.0, 90.0, 150.0, 100.0, 110.0, 130.0, 95.0, 140.0];
/// let kin = robot.inverse_kinematics(&truth).unwrap();
/// let mut cables = Vec::new();
/// model.with_tensions(&kin, &t, &mut cables).unwrap();
/// let l0: Vec<f64> = cables.iter().map(|c| c.unstrained_length).collect();
/// // ... and the wrench they balance, W t + w_ext = 0.
/// let mut w = DMatrix::zeros(0, 0);
/// write_sagging_wrench_matrix(&kin, &cables, &mut w);
/// let w_ext = -(w * DVector::from_column_slice(&t));
/// // Back: the equilibrium pose and the tensions from the unstrained lengths.
/// let mut fk = ElastoGeometricForward::new(&robot, &model, Default::default()).unwrap();
/// let guess = Pose::spatial(Vector3::new(0.21, -0.1, 1.0), 0.0, 0.0, 0.05);
/// let sol = fk.solve(&l0, w_ext.as_slice(), &guess).unwrap();
/// assert_eq!(sol.status, ElastoGeometricStatus::Equilibrium);
/// assert!((sol.pose.position - truth.position).norm() < 1e-9);
/// assert!((fk.cables()[2].platform_end_tension - 150.0).abs() < 1e-6);
/// ```
#[derive(Debug, Clone)]
pub struct ElastoGeometricForward<'a> {
    robot: &'a Robot,
    model: &'a RobotCatenaries,
    settings: ElastoGeometricSettings,
    kin: PoseKinematics,
    trial_kin: PoseKinematics,
    forces: Vec<CableForce>,
    trial: Vec<CableForce>,
    cables: Vec<SaggingCable>,
}

impl<'a> ElastoGeometricForward<'a> {
    /// A solver for `robot` with the cables of `model`. Errors on invalid settings, a model
    /// with another number of cables, fewer cables than DOF, a heavy cable over a pulley (not
    /// modelled; weightless elastic cables over pulleys are), or a weightless cable of infinite
    /// stiffness (a rigid straight cable: use [`crate::ForwardKinematics`]).
    pub fn new(
        robot: &'a Robot,
        model: &'a RobotCatenaries,
        settings: ElastoGeometricSettings,
    ) -> Result<Self, KinematicsError> {
        if !(settings.tolerance.is_finite() && settings.tolerance > 0.0) {
            return Err(KinematicsError::InvalidSetting {
                what: "elasto-geometric tolerance (relative, finite and > 0)",
                value: settings.tolerance,
            });
        }
        if settings.max_iterations == 0 {
            return Err(KinematicsError::InvalidSetting {
                what: "elasto-geometric iteration limit (must be ≥ 1)",
                value: 0.0,
            });
        }
        let n = robot.cable_count();
        if model.cables().len() != n {
            return Err(KinematicsError::WrongCableCount {
                what: "cable models".into(),
                cables: n,
                found: model.cables().len(),
            });
        }
        if n < robot.dof() {
            return Err(KinematicsError::TooFewCables {
                cables: n,
                dof: robot.dof(),
            });
        }
        model.check_pulleys(|i| robot.cables()[i].pulley.is_some())?;
        if let Some(c) = model
            .cables()
            .iter()
            .find(|c| c.weight() == 0.0 && c.axial_stiffness().is_infinite())
        {
            return Err(KinematicsError::InvalidSetting {
                what: "axial stiffness of a weightless cable (must be finite: a rigid straight cable fixes the pose by geometry, use forward kinematics)",
                value: c.axial_stiffness(),
            });
        }
        Ok(Self {
            robot,
            model,
            settings,
            kin: PoseKinematics::for_robot(robot),
            trial_kin: PoseKinematics::for_robot(robot),
            forces: vec![CableForce::default(); n],
            trial: vec![CableForce::default(); n],
            cables: Vec::with_capacity(n),
        })
    }

    /// Each cable's catenary at the last solve's pose: unstrained length, platform- and
    /// frame-end tensions (N), sag; a slack cable has zero tensions.
    pub fn cables(&self) -> &[SaggingCable] {
        &self.cables
    }

    /// Whether cable `i` was slack at the last solve's pose.
    pub fn is_slack(&self, i: usize) -> bool {
        self.forces.get(i).is_some_and(|f| f.slack)
    }

    fn check(&self, l0: &[f64], guess: &Pose) -> Result<(), KinematicsError> {
        let n = self.robot.cable_count();
        if l0.len() != n {
            return Err(KinematicsError::WrongCableCount {
                what: "unstrained cable lengths".into(),
                cables: n,
                found: l0.len(),
            });
        }
        if let Some((i, &v)) = l0.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(KinematicsError::NotFinite {
                what: format!("unstrained length of cable {}", i + 1),
                value: v,
            });
        }
        if let Some((cable, &value)) = l0.iter().enumerate().find(|(_, v)| **v <= 0.0) {
            return Err(KinematicsError::NegativeLength { cable, value });
        }
        if let Some(&v) = guess
            .position
            .iter()
            .chain(guess.rotation.matrix().iter())
            .find(|v| !v.is_finite())
        {
            return Err(KinematicsError::NotFinite {
                what: "guess pose".into(),
                value: v,
            });
        }
        Ok(())
    }

    /// The equilibrium pose with unstrained lengths `l0` (m) under the constant external wrench
    /// `w_ext` (DOF numbers: N, N·m), iterated from `guess`.
    ///
    /// Errors only on bad input (and a guess at which a cable cannot reach); a pose that is not
    /// an equilibrium within the tolerance is the status
    /// [`ElastoGeometricStatus::NotConverged`].
    pub fn solve(
        &mut self,
        l0: &[f64],
        w_ext: &[f64],
        guess: &Pose,
    ) -> Result<ElastoGeometricSolution, KinematicsError> {
        let dof = self.robot.dof();
        if w_ext.len() != dof {
            return Err(KinematicsError::WrongDimension {
                what: "external wrench".into(),
                motion: self.robot.motion().name(),
                expected: dof,
                found: w_ext.len(),
            });
        }
        if let Some(&v) = w_ext.iter().find(|v| !v.is_finite()) {
            return Err(KinematicsError::NotFinite {
                what: "external wrench".into(),
                value: v,
            });
        }
        self.check(l0, guess)?;
        self.iterate(l0, &mut Load::Constant(w_ext), *guess)
    }

    /// As [`ElastoGeometricForward::solve`] with an external wrench that depends on the pose
    /// (`load(pose, out)` writes its DOF components: the platform's weight with an offset centre
    /// of mass, springs); its derivative enters Newton's step by forward differences.
    pub fn solve_with_load(
        &mut self,
        l0: &[f64],
        load: &mut PoseLoad<'_>,
        guess: &Pose,
    ) -> Result<ElastoGeometricSolution, KinematicsError> {
        self.check(l0, guess)?;
        self.iterate(l0, &mut Load::Posed(load), *guess)
    }

    /// Without a guess: the equilibria reached from the straight cables' poses for the
    /// unstrained lengths ([`crate::ForwardKinematics::solve_multistart`] on all the cables
    /// and, with n > DOF, on every set leaving one cable out — a cable that hangs far below its
    /// chord misleads the straight model), the best returned and its cable states kept:
    /// certified equilibria first, among them the fewest slack cables, then the smallest
    /// largest tension (a heuristic for the physical, hanging equilibrium: a fixed set of
    /// starts can miss it; give a guess near it); without an equilibrium, the smallest
    /// residual.
    pub fn solve_multistart_with_load(
        &mut self,
        l0: &[f64],
        load: &mut PoseLoad<'_>,
    ) -> Result<ElastoGeometricSolution, KinematicsError> {
        let n = self.robot.cable_count();
        self.check(l0, &Pose::point(0.0, 0.0, 0.0))?;
        let mut starts = Vec::new();
        let geometric = |robot: &Robot, lengths: &[f64], starts: &mut Vec<Pose>| {
            let settings = crate::ForwardSettings::default();
            if let Ok(mut fk) = crate::ForwardKinematics::new(robot, settings)
                && let Ok(sols) = fk.solve_multistart(lengths)
            {
                starts.extend(sols.iter().map(|s| s.pose));
            }
        };
        geometric(self.robot, l0, &mut starts);
        if n > self.robot.dof() {
            let mut lengths = Vec::with_capacity(n - 1);
            for skip in 0..n {
                let keep: Vec<usize> = (0..n).filter(|&i| i != skip).collect();
                lengths.clear();
                lengths.extend(keep.iter().map(|&i| l0[i]));
                if let Ok(sub) = self.robot.permuted(&keep) {
                    geometric(&sub, &lengths, &mut starts);
                }
            }
        }
        let rank = |s: &ElastoGeometricSolution, t_max: f64| {
            (
                s.status != ElastoGeometricStatus::Equilibrium,
                if s.status == ElastoGeometricStatus::Equilibrium {
                    (s.slack_count as f64, t_max)
                } else {
                    (0.0, s.residual)
                },
            )
        };
        let mut best: Option<(ElastoGeometricSolution, f64)> = None;
        for start in &starts {
            let Ok(sol) = self.solve_with_load(l0, load, start) else {
                continue;
            };
            let t_max = self
                .cables
                .iter()
                .fold(0.0f64, |m, c| m.max(c.platform_end_tension));
            let better = match &best {
                None => true,
                Some((b, bt)) => {
                    rank(&sol, t_max).partial_cmp(&rank(b, *bt)) == Some(std::cmp::Ordering::Less)
                }
            };
            if better {
                best = Some((sol, t_max));
            }
        }
        let Some((sol, _)) = best else {
            return Err(KinematicsError::InvalidSetting {
                what: "elasto-geometric start (no straight-cable pose for these lengths reaches an equilibrium start; give a guess)",
                value: f64::NAN,
            });
        };
        // The cable states of the best solution.
        let again = self.solve_with_load(l0, load, &sol.pose)?;
        Ok(ElastoGeometricSolution {
            iterations: sol.iterations,
            ..again
        })
    }

    /// Every cable's force and stiffness at the pose of `kin` into `out`, each solve started
    /// from the plane force `out` holds; `None` when a cable cannot reach (inextensible and too
    /// short) or its solve fails.
    fn evaluate(&self, kin: &PoseKinematics, l0: &[f64], out: &mut [CableForce]) -> Option<()> {
        let up = self.model.up();
        for (i, (model, c)) in self.model.cables().iter().zip(kin.cables()).enumerate() {
            out[i] = cable_force(model, c, kin.pulley(i), &up, l0[i], out[i].plane_force)?;
        }
        Some(())
    }

    /// g(x) into `g` (spatial components), the external wrench included.
    fn residual(
        &self,
        kin: &PoseKinematics,
        forces: &[CableForce],
        load: &mut Load,
        pose: &Pose,
        g: &mut Vector6<f64>,
    ) -> Result<(), KinematicsError> {
        let idx = components(self.robot.motion());
        *g = Vector6::zeros();
        match load {
            Load::Constant(w) => {
                for (&k, &v) in idx.iter().zip(w.iter()) {
                    g[k] = v;
                }
            }
            Load::Posed(f) => {
                let mut w = [0.0; 6];
                f(pose, &mut w[..idx.len()])?;
                for (&k, &v) in idx.iter().zip(&w) {
                    g[k] = v;
                }
            }
        }
        for (f, c) in forces.iter().zip(kin.cables()) {
            let m = c.attachment.cross(&f.force);
            for k in 0..3 {
                g[k] += f.force[k];
                g[k + 3] += m[k];
            }
        }
        Ok(())
    }

    /// The scaled cost ½‖D g‖² and max |D g| over the motion's components.
    fn measure(&self, g: &Vector6<f64>) -> (f64, f64) {
        let scale = self.robot.length_scale();
        let (mut cost, mut max) = (0.0, 0.0f64);
        for &k in components(self.robot.motion()) {
            let v = if k >= 3 { g[k] / scale } else { g[k] };
            cost += 0.5 * v * v;
            max = max.max(v.abs());
        }
        (cost, max)
    }

    fn iterate(
        &mut self,
        l0: &[f64],
        load: &mut Load,
        mut x: Pose,
    ) -> Result<ElastoGeometricSolution, KinematicsError> {
        let motion = self.robot.motion();
        let idx = components(motion);
        let d = idx.len();
        let scale = self.robot.length_scale();
        self.robot.update_kinematics(&x, &mut self.kin)?;
        let mut forces = std::mem::take(&mut self.forces);
        let mut trial = std::mem::take(&mut self.trial);
        for f in &mut forces {
            f.plane_force = (0.0, 0.0);
        }
        if self.evaluate(&self.kin, l0, &mut forces).is_none() {
            self.forces = forces;
            self.trial = trial;
            return Err(KinematicsError::InvalidSetting {
                what: "starting pose (a cable cannot reach it with its unstrained length; give another guess)",
                value: f64::NAN,
            });
        }
        let mut g = Vector6::zeros();
        self.residual(&self.kin, &forces, load, &x, &mut g)?;
        let (mut cost, mut max) = self.measure(&g);
        let (mut mu, mut nu) = (0.0, 2.0);
        let mut iterations = 0;
        // A pose that moves less than this (m) has converged at the precision of the forces.
        let step_tolerance = 1e-14 * scale;
        let mut gt = Vector6::zeros();
        while iterations < self.settings.max_iterations {
            if max <= 1e-15 * self.force_scale(&forces, load) {
                break;
            }
            // J = ∂g/∂twist (spatial), then restricted and scaled: rows k ≥ 3 by 1/ℓ (moments
            // in N), columns k ≥ 3 by 1/ℓ (the unknown ℓ δφ: rotation steps in metres).
            let mut j = self.jacobian(&forces);
            if let Load::Posed(_) = load {
                self.load_jacobian(load, &x, &g, &forces, &mut j)?;
            }
            let mut js = Matrix6::<f64>::zeros();
            let mut gs = Vector6::<f64>::zeros();
            for (r, &kr) in idx.iter().enumerate() {
                let row = if kr >= 3 { 1.0 / scale } else { 1.0 };
                gs[r] = g[kr] * row;
                for (c, &kc) in idx.iter().enumerate() {
                    let col = if kc >= 3 { 1.0 / scale } else { 1.0 };
                    js[(r, c)] = j[(kr, kc)] * row * col;
                }
            }
            // (JᵀJ + μ diag(JᵀJ)) δ = −Jᵀ g (the unused block of the 6 × 6 is the identity).
            let jtj = js.transpose() * js;
            let jtg = js.transpose() * gs;
            let diag_max = (0..d).map(|k| jtj[(k, k)]).fold(0.0, f64::max);
            if diag_max == 0.0 || !diag_max.is_finite() {
                break;
            }
            let mut a = Matrix6::<f64>::identity();
            let mut rhs = Vector6::<f64>::zeros();
            for r in 0..d {
                for c in 0..d {
                    a[(r, c)] = jtj[(r, c)];
                }
                a[(r, r)] += mu * jtj[(r, r)].max(1e-12 * diag_max);
                rhs[r] = -jtg[r];
            }
            iterations += 1;
            let Some(step) = a.cholesky().map(|ch| ch.solve(&rhs)) else {
                mu = if mu == 0.0 { 1e-6 } else { mu * nu };
                nu *= 2.0;
                continue;
            };
            let mut delta = [0.0; 6];
            for (r, &k) in idx.iter().enumerate() {
                delta[r] = if k >= 3 { step[r] / scale } else { step[r] };
            }
            let size = (0..d).fold(0.0f64, |m, r| m.max(step[r].abs()));
            let candidate = displaced(motion, &x, &delta[..d]);
            for (t, f) in trial.iter_mut().zip(&forces) {
                t.plane_force = f.plane_force;
            }
            let accepted = match self
                .robot
                .update_kinematics(&candidate, &mut self.trial_kin)
            {
                Ok(()) if self.evaluate(&self.trial_kin, l0, &mut trial).is_some() => {
                    self.residual(&self.trial_kin, &trial, load, &candidate, &mut gt)?;
                    let (c, m) = self.measure(&gt);
                    // Equal cost is accepted: on a plateau of slack cables the step still
                    // moves towards the pose where they tighten.
                    if c <= cost {
                        (cost, max) = (c, m);
                        true
                    } else {
                        false
                    }
                }
                _ => false,
            };
            if accepted {
                x = candidate;
                g = gt;
                std::mem::swap(&mut forces, &mut trial);
                std::mem::swap(&mut self.kin, &mut self.trial_kin);
                mu /= 3.0;
                nu = 2.0;
                if size <= step_tolerance {
                    break;
                }
            } else {
                // A rejected step at the noise floor of the catenary solves: certified already.
                if size <= step_tolerance
                    || max <= 1e-3 * self.certified_residual(self.force_scale(&forces, load))
                {
                    break;
                }
                mu = if mu == 0.0 { 1e-6 } else { mu * nu };
                nu *= 2.0;
                if mu > 1e12 {
                    break;
                }
            }
        }
        // The certificate, recomputed at x.
        self.robot.update_kinematics(&x, &mut self.kin)?;
        let ok = self.evaluate(&self.kin, l0, &mut forces).is_some();
        self.residual(&self.kin, &forces, load, &x, &mut g)?;
        let (_, residual) = self.measure(&g);
        let force_scale = self.force_scale(&forces, load);
        let status = if ok && residual <= self.certified_residual(force_scale) {
            ElastoGeometricStatus::Equilibrium
        } else {
            ElastoGeometricStatus::NotConverged
        };
        self.write_cables(l0, &forces);
        let slack_count = forces.iter().filter(|f| f.slack).count();
        self.forces = forces;
        self.trial = trial;
        Ok(ElastoGeometricSolution {
            pose: x,
            residual,
            iterations,
            status,
            slack_count,
        })
    }

    /// The largest residual (N) of a certified equilibrium: `tolerance` × `force_scale` plus
    /// the noise floor of the catenary solves (each meets its span to 10⁻¹³ × chord, a force
    /// error of about 10⁻¹² EA: 10⁻¹¹ × the largest finite EA).
    fn certified_residual(&self, force_scale: f64) -> f64 {
        let ea = self
            .model
            .cables()
            .iter()
            .map(|c| c.axial_stiffness())
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        self.settings.tolerance * force_scale + 1e-11 * ea
    }

    /// max(1, ‖w_ext‖∞, max ‖f_i‖) (N): what the residual is relative to.
    fn force_scale(&self, forces: &[CableForce], load: &Load) -> f64 {
        let w = match load {
            Load::Constant(w) => w.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            Load::Posed(_) => 0.0,
        };
        forces.iter().fold(w.max(1.0), |m, f| m.max(f.force.amax()))
    }

    /// ∂g/∂(δp, δφ) of the cables (spatial 6 × 6, module docs).
    fn jacobian(&self, forces: &[CableForce]) -> Matrix6<f64> {
        let mut j = Matrix6::zeros();
        for (f, c) in forces.iter().zip(self.kin.cables()) {
            let ax = skew(&c.attachment);
            let s = f.stiffness;
            let s_ax = s * ax;
            let bottom_left = ax * s;
            let bottom_right = skew(&f.force) * ax - ax * s_ax;
            for r in 0..3 {
                for k in 0..3 {
                    j[(r, k)] += s[(r, k)];
                    j[(r, k + 3)] -= s_ax[(r, k)];
                    j[(r + 3, k)] += bottom_left[(r, k)];
                    j[(r + 3, k + 3)] += bottom_right[(r, k)];
                }
            }
        }
        j
    }

    /// Adds the forward-difference derivative of a pose-dependent load to `j`.
    fn load_jacobian(
        &self,
        load: &mut Load,
        x: &Pose,
        g: &Vector6<f64>,
        forces: &[CableForce],
        j: &mut Matrix6<f64>,
    ) -> Result<(), KinematicsError> {
        let Load::Posed(f) = load else { return Ok(()) };
        let idx = components(self.robot.motion());
        let d = idx.len();
        // The load alone at x: g minus the cables' wrench.
        let mut base = *g;
        for (cf, c) in forces.iter().zip(self.kin.cables()) {
            let m = c.attachment.cross(&cf.force);
            for k in 0..3 {
                base[k] -= cf.force[k];
                base[k + 3] -= m[k];
            }
        }
        let scale = self.robot.length_scale();
        let h = 1e-7 * scale;
        let mut w = [0.0; 6];
        for (col, &kc) in idx.iter().enumerate() {
            let mut delta = [0.0; 6];
            delta[col] = if kc >= 3 { h / scale } else { h };
            let xp = displaced(self.robot.motion(), x, &delta[..d]);
            f(&xp, &mut w[..d])?;
            for (r, &kr) in idx.iter().enumerate() {
                j[(kr, kc)] += (w[r] - base[kr]) / delta[col];
            }
        }
        Ok(())
    }

    /// The reported cable states at the final pose.
    fn write_cables(&mut self, l0: &[f64], forces: &[CableForce]) {
        let up = self.model.up();
        self.cables.clear();
        for (i, (model, c)) in self
            .model
            .cables()
            .iter()
            .zip(self.kin.cables())
            .enumerate()
        {
            let (a, b) = (c.attachment_point + c.vector, c.attachment_point);
            let (x, z, e) = plane_span(&a, &b, &up);
            let (fx, fz) = forces[i].plane_force;
            // With a pulley (a weightless cable: the tension is the same along it) the free
            // segment's share of L0 is l_f/l.
            let free = kin_free_share(&self.kin, i) * l0[i];
            let sol = crate::CatenarySolution {
                unstrained_length: free,
                horizontal_force: fx,
                vertical_force: fz,
                frame_end_tension: model.frame_end_tension(l0[i], fx, fz),
                platform_end_tension: fx.hypot(fz),
                iterations: 0,
            };
            let mut cable = SaggingCable::from_solution(model, &sol, x, z, &e, &up);
            if let Some(p) = self.kin.pulley(i) {
                cable.wrapped_length = (c.length - p.free_length).max(0.0);
                cable.unstrained_length = l0[i];
            }
            self.cables.push(cable);
        }
    }
}

/// l_f/l of cable `i` at the pose of `kin`: 1 without a pulley.
fn kin_free_share(kin: &PoseKinematics, i: usize) -> f64 {
    kin.pulley(i)
        .map_or(1.0, |p| p.free_length / kin.cables()[i].length)
}

/// One cable's force on the platform and its derivative with respect to the attachment point;
/// `state.vector` = A − B (from the platform attachment to the frame point, with a pulley to
/// the tangent point), `start` a warm start of the plane solve (F_x ≤ 0: none).
///
/// A weightless cable over a pulley (`pulley`, frictionless: one tension along the cable)
/// stretches over its whole length l = ρ β + l_f: T = EA (l/L0 − 1), pulling along the free
/// segment u. With ∂l/∂B = −uᵀ and the pulley stiffness
/// ∂u/∂B = −(1/l_f) (I − u uᵀ − (s_C/s) e_n e_nᵀ) ([`crate::PulleyState::swivel_ratio`]),
/// S = −(EA/L0) u uᵀ − (T/l_f) (I − u uᵀ − (s_C/s) e_n e_nᵀ).
fn cable_force(
    model: &ElasticCatenary,
    state: &crate::CableState,
    pulley: Option<&crate::PulleyState>,
    up: &Vector3<f64>,
    l0: f64,
    start: (f64, f64),
) -> Option<CableForce> {
    if let Some(p) = pulley {
        return Some(pulley_cable_force(model, state, p, up, l0));
    }
    let vector = &state.vector;
    let chord = vector.norm();
    let d = -vector;
    let z = d.dot(up);
    let h = d - up * z;
    let x = h.norm();
    if model.weight() == 0.0 {
        // Elastic straight cable (Hooke): T = EA (l/L0 − 1), taut at l ≥ L0.
        let ea = model.axial_stiffness();
        let u = vector / chord;
        let t = ea * (chord / l0 - 1.0);
        let uu = u * u.transpose();
        if t < 0.0 {
            // Slack: no force. Newton's step keeps the taut side's axial stiffness, so that a
            // start with slack cables moves towards the pose where they tighten.
            return Some(CableForce {
                force: Vector3::zeros(),
                stiffness: -(ea / l0) * uu,
                plane_force: (0.0, 0.0),
                slack: true,
            });
        }
        let stiffness = -(ea / l0) * uu - (t / chord) * (Matrix3::identity() - uu);
        return Some(CableForce {
            force: u * t,
            stiffness,
            plane_force: (t * x / chord, t * z / chord),
            slack: false,
        });
    }
    let vertical = x <= 1e-12 * chord;
    let e = if vertical { Vector3::zeros() } else { h / x };
    let warm = (start.0 > 0.0).then_some(start);
    let sol = model.solve_for_length_from(x, z, l0, warm).ok()?;
    let (fx, fz) = (sol.horizontal_force, sol.vertical_force);
    let jac = model.jacobian(l0, fx, fz);
    let flex = nalgebra::Matrix2::new(jac[(0, 0)], jac[(0, 1)], jac[(1, 0)], jac[(1, 1)]);
    let k = flex.try_inverse()?;
    let basis = nalgebra::Matrix3x2::from_columns(&[e, *up]);
    let mut stiffness = -(basis * k * basis.transpose());
    if !vertical {
        stiffness -= (fx / x) * (Matrix3::identity() - e * e.transpose() - up * up.transpose());
    }
    Some(CableForce {
        force: -(e * fx + up * fz),
        stiffness,
        plane_force: (fx, fz),
        slack: false,
    })
}

/// [`cable_force`] of a weightless elastic cable over a pulley.
fn pulley_cable_force(
    model: &ElasticCatenary,
    state: &crate::CableState,
    p: &crate::PulleyState,
    up: &Vector3<f64>,
    l0: f64,
) -> CableForce {
    let ea = model.axial_stiffness();
    let (u, free) = (state.unit, p.free_length);
    let t = ea * (state.length / l0 - 1.0);
    let uu = u * u.transpose();
    if t < 0.0 {
        return CableForce {
            force: Vector3::zeros(),
            stiffness: -(ea / l0) * uu,
            plane_force: (0.0, 0.0),
            slack: true,
        };
    }
    let lateral =
        Matrix3::identity() - uu - p.swivel_ratio * p.plane_normal * p.plane_normal.transpose();
    // (F_x, F_z): the tension at B along C → B in the vertical plane (the warm start of
    // `cable_force`'s convention; unused by weightless cables but reported).
    let along = -u;
    let z = along.dot(up);
    let x = (along - up * z).norm();
    CableForce {
        force: u * t,
        stiffness: -(ea / l0) * uu - (t / free) * lateral,
        plane_force: (t * x, t * z),
        slack: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catenary::write_sagging_wrench_matrix;
    use crate::reference_robots::ipanema_like_8;
    use crate::{Cable, ForwardKinematics, ForwardSettings};
    use nalgebra::{DMatrix, DVector, Vector2};

    /// CoGiRo's geometry (WireCenter's CoGiRo.wcrfx, pulleys left out): 15 × 11 m, suspended.
    fn cogiro_like() -> Robot {
        let frame = [
            [-7.175, -5.244, 5.462],
            [-7.316, -5.103, 5.472],
            [-7.303, 5.236, 5.476],
            [-7.161, 5.373, 5.485],
            [7.182, 5.348, 5.488],
            [7.323, 5.206, 5.499],
            [7.302, -5.133, 5.489],
            [7.161, -5.27, 5.497],
        ];
        let platform = [
            [0.503, -0.493, 0.0],
            [-0.51, 0.351, 0.998],
            [-0.503, -0.27, 0.0],
            [0.496, 0.356, 1.0],
            [-0.503, 0.493, 0.0],
            [0.5, -0.34, 0.999],
            [0.502, 0.275, 0.0],
            [-0.505, -0.346, 0.998],
        ];
        let cables = frame
            .iter()
            .zip(&platform)
            .map(|(f, p)| Cable::spatial(Vector3::from(*f), Vector3::from(*p)))
            .collect();
        Robot::new(MotionPattern::Spatial, cables).unwrap()
    }

    fn gravity() -> Vector3<f64> {
        Vector3::new(0.0, 0.0, -9.81)
    }

    /// Unstrained lengths and the external wrench that tensions `t` balance at `pose`.
    fn inverse(
        robot: &Robot,
        model: &RobotCatenaries,
        pose: &Pose,
        t: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let kin = robot.inverse_kinematics(pose).unwrap();
        let mut cables = Vec::new();
        model.with_tensions(&kin, t, &mut cables).unwrap();
        let mut w = DMatrix::zeros(0, 0);
        write_sagging_wrench_matrix(&kin, &cables, &mut w);
        let w_ext = -(w * DVector::from_column_slice(t));
        (
            cables.iter().map(|c| c.unstrained_length).collect(),
            w_ext.as_slice().to_vec(),
        )
    }

    #[test]
    fn round_trip_cogiro_catenary() {
        let robot = cogiro_like();
        // WireCenter's CoGiRo cable: 0.023 kg/m, E·S = 1.244e7 N.
        let model = RobotCatenaries::new(&[0.023; 8], &[1.244e7; 8], &gravity()).unwrap();
        let truth = Pose::spatial(Vector3::new(1.5, -1.0, 2.5), 0.05, -0.03, 0.1);
        let t = [80.0, 120.0, 60.0, 150.0, 90.0, 110.0, 70.0, 130.0];
        let (l0, w_ext) = inverse(&robot, &model, &truth, &t);
        let mut fk = ElastoGeometricForward::new(&robot, &model, Default::default()).unwrap();
        // The start of `cdpr forward`: the straight cables' pose for the unstrained lengths
        // (multi-start; here about 0.5 mm from the truth).
        let mut geometric = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
        let guess = geometric.solve_multistart(&l0).unwrap()[0].pose;
        // And from 1 cm and 0.01 rad off.
        let near = Pose::spatial(
            truth.position + Vector3::new(0.01, -0.01, 0.01),
            0.06,
            -0.02,
            0.11,
        );
        for start in [guess, near] {
            let sol = fk.solve(&l0, &w_ext, &start).unwrap();
            assert_eq!(sol.status, ElastoGeometricStatus::Equilibrium, "{sol:?}");
            assert!(
                (sol.pose.position - truth.position).norm() < 1e-9,
                "{:?}",
                sol.pose.position - truth.position
            );
            // ‖R − R_truth‖_F ≈ √2 × their angle (`angle_to`, an acos, is 1e-8 at best).
            assert!((sol.pose.rotation.matrix() - truth.rotation.matrix()).norm() < 1e-9);
            for (c, &ti) in fk.cables().iter().zip(&t) {
                assert!((c.platform_end_tension - ti).abs() < 1e-6 * ti, "{c:?}");
                assert!(c.frame_end_tension > c.platform_end_tension);
            }
            assert_eq!(sol.slack_count, 0);
        }
    }

    #[test]
    fn straight_limit_is_forward_kinematics_of_the_stretched_lengths() {
        // Weightless elastic cables: the chord is L0 (1 + T/EA) (Hooke), and the pose is the
        // geometric forward kinematics of those lengths (an independent solver).
        let robot = ipanema_like_8();
        let ea = 2e4;
        let model = RobotCatenaries::elastic(&[ea; 8]).unwrap();
        let truth = Pose::spatial(Vector3::new(0.2, -0.1, 1.0), 0.02, 0.01, 0.05);
        let t = [120.0, 90.0, 150.0, 100.0, 110.0, 130.0, 95.0, 140.0];
        let (l0, w_ext) = inverse(&robot, &model, &truth, &t);
        let mut fk = ElastoGeometricForward::new(&robot, &model, Default::default()).unwrap();
        let guess = Pose::spatial(Vector3::new(0.0, 0.0, 1.0), 0.0, 0.0, 0.0);
        let sol = fk.solve(&l0, &w_ext, &guess).unwrap();
        assert_eq!(sol.status, ElastoGeometricStatus::Equilibrium);
        let stretched: Vec<f64> = fk
            .cables()
            .iter()
            .map(|c| c.unstrained_length * (1.0 + c.platform_end_tension / ea))
            .collect();
        for (c, l) in fk.cables().iter().zip(&stretched) {
            assert!((c.chord_length - l).abs() < 1e-12, "{c:?}");
            assert!(c.max_sag == 0.0 && c.frame_end_tension == c.platform_end_tension);
        }
        let mut geometric = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
        let g = geometric.solve(&stretched, &guess).unwrap();
        assert!((g.pose.position - sol.pose.position).norm() < 1e-10);
        assert!((sol.pose.position - truth.position).norm() < 1e-9);
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let robot = cogiro_like();
        let model = RobotCatenaries::new(&[0.5; 8], &[1e5; 8], &gravity()).unwrap();
        let pose = Pose::spatial(Vector3::new(0.5, 0.8, 2.0), 0.1, -0.05, 0.2);
        jacobian_check(&robot, &model, &pose, &[50.0; 8], None);
    }

    /// Elastic cables over pulleys: the stiffness from ∂l/∂B = −uᵀ and the pulley's
    /// ∂u/∂B = −(1/l_f)(I − u uᵀ − (s_C/s) e_n e_nᵀ) against central differences of the cables'
    /// wrench, at a pose where every pulley swivels off its frame axes.
    #[test]
    fn pulley_jacobian_matches_finite_differences() {
        let robot = crate::reference_robots::ipanema_like_8_pulleys();
        let model = RobotCatenaries::elastic(&[6e4; 8]).unwrap();
        let pose = Pose::spatial(Vector3::new(0.3, -0.2, 1.2), 0.1, -0.05, 0.2);
        let t = [120.0, 90.0, 150.0, 100.0, 110.0, 130.0, 95.0, 140.0];
        // Absolute (N/m, N, N·m): the axial terms EA/L0 ≈ 3·10⁴ N/m dwarf the swivel term
        // (s_C/s) T/l_f ≈ 1 N/m, which a relative tolerance would not see.
        jacobian_check(&robot, &model, &pose, &t, Some(1e-3));
    }

    /// The analytic ∂g/∂twist against central differences at `pose`, within `tolerance`
    /// (absolute) or else 10⁻⁵ of its largest entry.
    fn jacobian_check(
        robot: &Robot,
        model: &RobotCatenaries,
        pose: &Pose,
        t: &[f64],
        tolerance: Option<f64>,
    ) {
        let pose = *pose;
        let (l0, _) = inverse(robot, model, &pose, t);
        let mut fk = ElastoGeometricForward::new(robot, model, Default::default()).unwrap();
        let wrench = |fk: &ElastoGeometricForward, x: &Pose| {
            let kin = robot.inverse_kinematics(x).unwrap();
            let mut f = vec![CableForce::default(); 8];
            fk.evaluate(&kin, &l0, &mut f).unwrap();
            let mut g = Vector6::zeros();
            fk.residual(&kin, &f, &mut Load::Constant(&[0.0; 6]), x, &mut g)
                .unwrap();
            (g, f, kin)
        };
        let (g0, f0, kin0) = wrench(&fk, &pose);
        fk.kin = kin0;
        let j = fk.jacobian(&f0);
        let h = 1e-6;
        for k in 0..6 {
            let mut d = [0.0; 6];
            d[k] = h;
            let (gp, _, _) = wrench(&fk, &displaced(MotionPattern::Spatial, &pose, &d));
            d[k] = -h;
            let (gm, _, _) = wrench(&fk, &displaced(MotionPattern::Spatial, &pose, &d));
            let fd = (gp - gm) / (2.0 * h);
            let err = (fd - j.column(k)).amax();
            assert!(
                err < tolerance.unwrap_or(1e-5 * j.amax()),
                "column {k}: {err}"
            );
        }
        assert!(g0.amax() > 0.0);
    }

    #[test]
    fn pose_dependent_weight_is_balanced_by_the_catenary_forces() {
        // 40 kg with its centre of mass 0.2 m off the origin: the weight's moment turns with
        // the platform. The certificate is recomputed independently from the lengths.
        let robot = cogiro_like();
        let model = RobotCatenaries::new(&[0.023; 8], &[1.244e7; 8], &gravity()).unwrap();
        let start = Pose::spatial(Vector3::new(0.0, 0.0, 2.5), 0.0, 0.0, 0.0);
        let (l0, _) = inverse(&robot, &model, &start, &[200.0; 8]);
        let weight = |p: &Pose| {
            let f = Vector3::new(0.0, 0.0, -40.0 * 9.81);
            let m = (p.rotation * Vector3::new(0.2, 0.0, 0.0)).cross(&f);
            [f.x, f.y, f.z, m.x, m.y, m.z]
        };
        let mut load = |p: &Pose, out: &mut [f64]| {
            out.copy_from_slice(&weight(p));
            Ok(())
        };
        let mut fk = ElastoGeometricForward::new(&robot, &model, Default::default()).unwrap();
        let sol = fk.solve_with_load(&l0, &mut load, &start).unwrap();
        assert_eq!(sol.status, ElastoGeometricStatus::Equilibrium, "{sol:?}");
        let kin = robot.inverse_kinematics(&sol.pose).unwrap();
        let mut cables = Vec::new();
        model.with_lengths(&kin, &l0, &mut cables).unwrap();
        let mut w = DMatrix::zeros(0, 0);
        write_sagging_wrench_matrix(&kin, &cables, &mut w);
        let t = DVector::from_iterator(8, cables.iter().map(|c| c.platform_end_tension));
        let r = w * t + DVector::from_row_slice(&weight(&sol.pose));
        assert!(r.amax() < 1e-4, "{r}");
        assert!(
            (sol.pose.position - start.position).norm() > 1e-7,
            "it moved"
        );
    }

    #[test]
    fn slack_cable_pulls_nothing() {
        // A point in a vertical plane (gravity −y) on three elastic cables; the lower one is
        // paid out beyond its chord: slack, the two upper cables carry 10 N.
        let cable = |x: f64, y: f64| Cable::point2(Vector2::new(x, y));
        let robot = Robot::new(
            MotionPattern::Point2,
            vec![cable(-1.0, 1.0), cable(1.0, 1.0), cable(0.0, -1.0)],
        )
        .unwrap();
        let model =
            RobotCatenaries::new(&[0.0; 3], &[1e4; 3], &Vector3::new(0.0, -9.81, 0.0)).unwrap();
        let s = 2f64.sqrt();
        let l = s / (1.0 + 10.0 / s / 1e4);
        let mut fk = ElastoGeometricForward::new(&robot, &model, Default::default()).unwrap();
        let sol = fk
            .solve(&[l, l, 1.5], &[0.0, -10.0], &Pose::point(0.01, 0.02, 0.0))
            .unwrap();
        assert_eq!(sol.status, ElastoGeometricStatus::Equilibrium, "{sol:?}");
        assert_eq!(sol.slack_count, 1);
        assert!(fk.is_slack(2) && !fk.is_slack(0));
        assert_eq!(fk.cables()[2].platform_end_tension, 0.0);
        // Symmetric: each upper cable at 10/√2 N, the point on the y axis.
        assert!(sol.pose.position.x.abs() < 1e-12 && sol.pose.position.y.abs() < 1e-9);
        assert!((fk.cables()[0].platform_end_tension - 10.0 / s).abs() < 1e-9);
    }

    #[test]
    fn bad_input_is_an_error() {
        let robot = ipanema_like_8();
        let model = RobotCatenaries::elastic(&[1e4; 8]).unwrap();
        let mut fk = ElastoGeometricForward::new(&robot, &model, Default::default()).unwrap();
        let guess = Pose::spatial(Vector3::new(0.0, 0.0, 1.0), 0.0, 0.0, 0.0);
        let w = [0.0, 0.0, -10.0, 0.0, 0.0, 0.0];
        assert!(matches!(
            fk.solve(&[1.0; 7], &w, &guess),
            Err(KinematicsError::WrongCableCount { .. })
        ));
        let mut l = [1.5; 8];
        l[3] = f64::NAN;
        assert!(matches!(
            fk.solve(&l, &w, &guess),
            Err(KinematicsError::NotFinite { .. })
        ));
        l[3] = -1.0;
        assert!(matches!(
            fk.solve(&l, &w, &guess),
            Err(KinematicsError::NegativeLength { cable: 3, .. })
        ));
        assert!(matches!(
            fk.solve(&[1.5; 8], &w[..3], &guess),
            Err(KinematicsError::WrongDimension { .. })
        ));
        let rigid = RobotCatenaries::elastic(&[f64::INFINITY; 8]).unwrap();
        assert!(ElastoGeometricForward::new(&robot, &rigid, Default::default()).is_err());
        // Elastic cables over pulleys are modelled, heavy ones are not.
        let pulleys = crate::reference_robots::ipanema_like_8_pulleys();
        assert!(ElastoGeometricForward::new(&pulleys, &model, Default::default()).is_ok());
        let heavy = RobotCatenaries::new(&[0.01; 8], &[1e4; 8], &gravity()).unwrap();
        assert!(matches!(
            ElastoGeometricForward::new(&pulleys, &heavy, Default::default()),
            Err(KinematicsError::UnsupportedPulley { cable: 0, .. })
        ));
        // Every cable far too long: no equilibrium, reported (not a panic).
        let sol = fk.solve(&[10.0; 8], &w, &guess).unwrap();
        assert_eq!(sol.status, ElastoGeometricStatus::NotConverged);
        assert!(sol.residual.is_finite());
    }
}

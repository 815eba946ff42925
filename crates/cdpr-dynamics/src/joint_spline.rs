//! # CASPR joint-space spline trajectories
//!
//! The trajectories of CASPR's `NAME_trajectories.xml` (Lau et al. 2016): points q_k at times
//! t_k, joined segment by segment by a spline of one of five kinds, sampled every `time_step`
//! seconds. The joint coordinates q are cdpr's motion-pattern coordinates (CASPR's
//! `SPATIAL_EULER_XYZ` q = (x, y, z, α, β, γ) with R = R_x(α) R_y(β) R_z(γ), `PLANAR_XY`
//! (x, y, θ), `T_XYZ`, `P_XY`), q̇ and q̈ their time derivatives (Euler rates for the angles).
//!
//! On a segment [t_a, t_e] of length T, with s = t − t_a, Δ = q_e − q_a and τ = s / T, each
//! coordinate follows
//!
//! | kind (CASPR element) | q(s) | boundary data |
//! |---|---|---|
//! | linear (`linear_spline_trajectory`) | q_a + Δ τ (q̇ = Δ/T, q̈ = 0) | q |
//! | cubic (`cubic_spline_trajectory`) | q_a + V_a τ + (3Δ − 2V_a − V_e) τ² + (−2Δ + V_a + V_e) τ³ | q, q̇ (V = q̇ T) |
//! | quintic (`quintic_spline_trajectory`) | q_a + V_a τ + A_a τ²/2 + c₃ τ³ + c₄ τ⁴ + c₅ τ⁵ | q, q̇, q̈ (A = q̈ T²) |
//! | cubic, average velocity (`cubic_spline_average_velocity_trajectory`) | the cubic with q̇_k = ½ ((q_k − q_{k−1})/(t_k − t_{k−1}) + (q_{k+1} − q_k)/(t_{k+1} − t_k)) at interior points | q; q̇ at the first and last point |
//! | parabolic blend (`parabolic_blend_trajectory`) | q_a + a s²/2 for s < t_b; line of speed a t_b; q_e − a (T − s)²/2 for s ≥ T − t_b; a = Δ / (t_b (T − t_b)) | q; t_b per segment (2 t_b < T) |
//!
//! with the quintic's c₃ = 10Δ − 6V_a − 4V_e − 1.5A_a + 0.5A_e, c₄ = −15Δ + 8V_a + 7V_e + 1.5A_a
//! − A_e, c₅ = 6Δ − 3V_a − 3V_e − 0.5A_a + 0.5A_e (Biagiotti & Melchiorri 2008, eqs. (2.3),
//! (2.5)): the cubic with zero end velocities has q(T/2) = q_a + Δ/2 and q̇(T/2) = 1.5 Δ/T, the
//! parabolic blend stops at every point.
//!
//! **Orientations.** CASPR does not interpolate Euler angles: its `SphericalEulerXYZ` joint
//! moves along the shortest rotation R(t) = R_a · Rot(k, θ(t)) from R_a to R_e = R_a Rot(k, θ_e),
//! θ ∈ [0, π], with θ(t) the same kind of spline from 0 to θ_e at rest at both ends (its
//! cubic and quintic refuse non-zero orientation rates). Then ω = R_a k θ̇ and ω̇ = R_a k θ̈
//! exactly. cdpr does the same wherever the file's orientation rates (and, for the quintic,
//! accelerations) at both ends of a segment are zero — every CASPR trajectory CASPR can run.
//! Where they are not (CASPR stops there; so does a cubic-average segment whose Euler angles
//! change at an interior point), cdpr splines the three Euler angles φ = (α, β, γ) like the
//! other coordinates and turns their rates into twists: ω = H(φ) φ̇ and ω̇ = H φ̈ + Ḣ φ̇
//! ([`crate::twist_from_euler_rates`]).
//!
//! **Sampling** (CASPR's `t_a:time_step:t_e`). Segment k is sampled at t_k + j·time_step for
//! j = 0 … n_k = ⌊(t_{k+1} − t_k)/time_step⌋; the first sample of every segment but the first is
//! dropped (it repeats the previous segment's last). When the segment's length is not a multiple
//! of `time_step`, CASPR fits the spline on [t_k, t_k + n_k·time_step] — the point is reached
//! at the last sample, and the platform rests there until t_{k+1} — and so does cdpr.
//!
//! ## References
//! - Lau, Eden, Tan & Oetomo 2016, *CASPR: a comprehensive cable-robot analysis and simulation
//!   platform for the research of cable-driven parallel robots*, IROS (its `JointTrajectory`,
//!   `Spline` and `SphericalEulerXYZ` classes define these trajectories).
//! - Biagiotti & Melchiorri 2008, *Trajectory Planning for Automatic Machines and Robots*, §2.1
//!   (cubic and quintic polynomials, eqs. (2.3), (2.5)); Craig 2005, §7.3 (parabolic blends).

use crate::DynamicsError;
use crate::error::bad;
use crate::rigid_body::{embed, twist_from_euler_rates};
use crate::time_law::TimedSample;
use cdpr_kinematics::{MotionPattern, Pose};
use nalgebra::{Rotation3, Unit, Vector3, Vector6};

/// The five spline kinds of CASPR's joint trajectories.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum SplineKind {
    /// `linear_spline_trajectory`.
    Linear,
    /// `cubic_spline_trajectory` (q̇ at every point).
    Cubic,
    /// `quintic_spline_trajectory` (q̇ and q̈ at every point).
    Quintic,
    /// `cubic_spline_average_velocity_trajectory` (q̇ at the first and last points).
    CubicAverageVelocity,
    /// `parabolic_blend_trajectory` (blend time per segment).
    ParabolicBlend,
}

impl SplineKind {
    /// All kinds.
    pub const ALL: [SplineKind; 5] = [
        Self::Linear,
        Self::Cubic,
        Self::Quintic,
        Self::CubicAverageVelocity,
        Self::ParabolicBlend,
    ];

    /// CASPR's element name.
    pub const fn element(self) -> &'static str {
        match self {
            Self::Linear => "linear_spline_trajectory",
            Self::Cubic => "cubic_spline_trajectory",
            Self::Quintic => "quintic_spline_trajectory",
            Self::CubicAverageVelocity => "cubic_spline_average_velocity_trajectory",
            Self::ParabolicBlend => "parabolic_blend_trajectory",
        }
    }

    /// The kind of a CASPR element name.
    pub fn from_element(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.element() == name)
    }

    /// Whether every point needs q̇ (cubic, quintic).
    pub const fn needs_velocities(self) -> bool {
        matches!(self, Self::Cubic | Self::Quintic)
    }
}

/// One point of a CASPR trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct SplinePoint {
    /// Absolute time (s).
    pub time: f64,
    /// Joint coordinates q (motion-pattern coordinates: m, rad).
    pub q: Vec<f64>,
    /// q̇ (m/s, rad/s; Euler rates for spatial angles), where given.
    pub q_dot: Option<Vec<f64>>,
    /// q̈ (m/s², rad/s²), where given.
    pub q_ddot: Option<Vec<f64>>,
    /// Parabolic blend: the blend time t_b (s) of the segment that ends here.
    pub blend_time: Option<f64>,
}

/// How one coordinate moves on a segment (τ-polynomial coefficients, or a parabolic blend).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    Poly([f64; 6]),
    Blend { q0: f64, q1: f64, tb: f64 },
}

impl Shape {
    /// The coordinate between q0 (velocity v0, acceleration a0) and q1 (v1, a1) over T.
    fn new(kind: SplineKind, span: f64, e: [f64; 6], tb: f64) -> Self {
        let [q0, q1, v0, v1, a0, a1] = e;
        let d = q1 - q0;
        let (v0, v1) = (v0 * span, v1 * span);
        let (a0, a1) = (a0 * span * span, a1 * span * span);
        Self::Poly(match kind {
            SplineKind::Linear => [q0, d, 0.0, 0.0, 0.0, 0.0],
            SplineKind::Cubic | SplineKind::CubicAverageVelocity => [
                q0,
                v0,
                3.0 * d - 2.0 * v0 - v1,
                -2.0 * d + v0 + v1,
                0.0,
                0.0,
            ],
            SplineKind::Quintic => [
                q0,
                v0,
                0.5 * a0,
                10.0 * d - 6.0 * v0 - 4.0 * v1 - 1.5 * a0 + 0.5 * a1,
                -15.0 * d + 8.0 * v0 + 7.0 * v1 + 1.5 * a0 - a1,
                6.0 * d - 3.0 * v0 - 3.0 * v1 - 0.5 * a0 + 0.5 * a1,
            ],
            SplineKind::ParabolicBlend => return Self::Blend { q0, q1, tb },
        })
    }

    /// q, q̇, q̈ at s ∈ [0, T].
    fn at(&self, span: f64, s: f64) -> [f64; 3] {
        match *self {
            Self::Poly(c) => {
                let t = s / span;
                let q = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
                let dq =
                    c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])));
                let ddq = 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]));
                [q, dq / span, ddq / (span * span)]
            }
            // CASPR's `Spline.ParabolicBlend`: the later branch at the switching instants.
            Self::Blend { q0, q1, tb } => {
                let a = (q1 - q0) / (tb * (span - tb));
                if s < tb {
                    [q0 + 0.5 * a * s * s, a * s, a]
                } else if s < span - tb {
                    [q0 + 0.5 * a * tb * tb + a * tb * (s - tb), a * tb, 0.0]
                } else {
                    let r = span - s;
                    [q1 - 0.5 * a * r * r, a * r, -a]
                }
            }
        }
    }
}

/// The orientation of a spatial segment.
#[derive(Debug, Clone, PartialEq)]
enum Orientation {
    /// Not a spatial pattern (every coordinate is splined).
    Coordinates,
    /// The shortest rotation R_a Rot(k, θ(s)), θ from 0 to θ_e at rest (CASPR).
    Geodesic {
        from: Rotation3<f64>,
        axis: Option<(Unit<Vector3<f64>>, f64)>,
        shape: Shape,
    },
    /// The Euler angles splined like the other coordinates (non-zero end rates).
    Euler,
}

#[derive(Debug, Clone, PartialEq)]
struct Segment {
    start: f64,
    /// The fitted length: n·time_step (or the nominal length when it is a multiple).
    span: f64,
    /// Samples after the start: n.
    steps: usize,
    /// One shape per coordinate (the spatial angles' are unused on a geodesic).
    shapes: Vec<Shape>,
    orientation: Orientation,
}

/// A CASPR joint-space spline trajectory, ready to sample (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct JointSpline {
    motion: MotionPattern,
    kind: SplineKind,
    time_step: f64,
    segments: Vec<Segment>,
}

/// Whether a key of [`JointSpline::new`]'s errors is about point k: `points[k].field`.
///
/// ```
/// assert_eq!(cdpr_dynamics::joint_spline::point_of_key("points[3].time"), Some((3, "time")));
/// assert_eq!(cdpr_dynamics::joint_spline::point_of_key("time_step"), None);
/// ```
pub fn point_of_key(key: &str) -> Option<(usize, &str)> {
    let rest = key.strip_prefix("points[")?;
    let (k, field) = rest.split_once("].")?;
    Some((k.parse().ok()?, field))
}

fn vector_len(what: &'static str, v: &[f64], dof: usize) -> Result<(), DynamicsError> {
    if v.len() != dof {
        return Err(DynamicsError::DimensionMismatch {
            what,
            expected: dof,
            found: v.len(),
        });
    }
    Ok(())
}

impl JointSpline {
    /// The trajectory of `points` (absolute, strictly increasing times) for `motion`.
    ///
    /// `blend_default` is the parabolic blend's `blend_time_default` (s), for the segments whose
    /// end point has no `blend_time`. Errors name the setting as `time_step`,
    /// `blend_time_default` or `points[k].FIELD` (k from 0; see [`point_of_key`]): a
    /// non-positive time step, times not increasing, a segment shorter than a time step, a
    /// missing q̇ / q̈ the kind needs, a blend time with 2 t_b ≥ T, more than 10 000 000
    /// samples; vectors of the wrong size are [`DynamicsError::DimensionMismatch`].
    ///
    /// ```
    /// use cdpr_dynamics::joint_spline::{JointSpline, SplineKind, SplinePoint};
    /// use cdpr_kinematics::MotionPattern;
    /// let p = |t: f64, x: f64| SplinePoint {
    ///     time: t, q: vec![x, 0.0], q_dot: Some(vec![0.0, 0.0]), q_ddot: None, blend_time: None,
    /// };
    /// let s = JointSpline::new(MotionPattern::Point2, SplineKind::Cubic, 0.5,
    ///     &[p(0.0, 0.0), p(2.0, 1.0)], None).unwrap();
    /// let mid = s.at(1.0);
    /// assert!((mid.pose.position.x - 0.5).abs() < 1e-15);
    /// assert!((mid.twist[0] - 1.5 * 1.0 / 2.0).abs() < 1e-15);   // 1.5 Δ/T
    /// assert_eq!(s.samples().len(), 5);                         // 0, 0.5, 1, 1.5, 2 s
    /// ```
    pub fn new(
        motion: MotionPattern,
        kind: SplineKind,
        time_step: f64,
        points: &[SplinePoint],
        blend_default: Option<f64>,
    ) -> Result<Self, DynamicsError> {
        if !(time_step.is_finite() && time_step > 0.0) {
            return Err(bad("time_step", time_step, "must be a finite number > 0"));
        }
        if points.len() < 2 {
            return Err(DynamicsError::DimensionMismatch {
                what: "trajectory points (at least)",
                expected: 2,
                found: points.len(),
            });
        }
        let dof = motion.dof();
        for (k, p) in points.iter().enumerate() {
            vector_len("point q", &p.q, dof)?;
            if let Some(v) = &p.q_dot {
                vector_len("point q_dot", v, dof)?;
            }
            if let Some(v) = &p.q_ddot {
                vector_len("point q_ddot", v, dof)?;
            }
            let end = k == 0 || k + 1 == points.len();
            let needs_v =
                kind.needs_velocities() || (kind == SplineKind::CubicAverageVelocity && end);
            if needs_v && p.q_dot.is_none() {
                return Err(bad(
                    format!("points[{k}].q_dot"),
                    f64::NAN,
                    format!("the {} needs q_dot here", kind.element()),
                ));
            }
            if kind == SplineKind::Quintic && p.q_ddot.is_none() {
                return Err(bad(
                    format!("points[{k}].q_ddot"),
                    f64::NAN,
                    "the quintic spline needs q_ddot at every point",
                ));
            }
            if !p.time.is_finite() || (k > 0 && p.time <= points[k - 1].time) {
                return Err(bad(
                    format!("points[{k}].time"),
                    p.time,
                    format!(
                        "point times must increase strictly (the previous point is at {} s)",
                        if k > 0 { points[k - 1].time } else { f64::NAN }
                    ),
                ));
            }
        }
        let velocities = Self::velocities(kind, points);
        let mut segments = Vec::with_capacity(points.len() - 1);
        let mut total = 0usize;
        for k in 0..points.len() - 1 {
            let (a, b) = (&points[k], &points[k + 1]);
            let nominal = b.time - a.time;
            let steps = (nominal / time_step + 1e-9).floor();
            if steps < 1.0 {
                return Err(bad(
                    format!("points[{}].time", k + 1),
                    b.time,
                    format!(
                        "the segment from {} s is shorter than time_step = {time_step} s",
                        a.time
                    ),
                ));
            }
            total += steps as usize;
            if total > 10_000_000 {
                return Err(bad(
                    "time_step",
                    time_step,
                    "makes more than 10 000 000 samples",
                ));
            }
            let steps = steps as usize;
            let fitted = steps as f64 * time_step;
            let span = if (fitted - nominal).abs() <= 1e-9 * time_step {
                nominal
            } else {
                fitted
            };
            let tb = match kind {
                SplineKind::ParabolicBlend => {
                    let (tb, key) = match b.blend_time {
                        Some(tb) => (tb, format!("points[{}].blend_time", k + 1)),
                        None => (
                            blend_default.unwrap_or(f64::NAN),
                            "blend_time_default".to_string(),
                        ),
                    };
                    if !(tb.is_finite() && tb > 0.0 && 2.0 * tb < span) {
                        return Err(bad(
                            key,
                            tb,
                            format!(
                                "must be > 0 and less than half the segment ending at point {} ({span} s long)",
                                k + 1
                            ),
                        ));
                    }
                    tb
                }
                _ => 0.0,
            };
            let zero = vec![0.0; dof];
            let ends = |i: usize| -> [f64; 6] {
                let acc = |p: &SplinePoint| p.q_ddot.as_ref().unwrap_or(&zero)[i];
                [
                    a.q[i],
                    b.q[i],
                    velocities[k][i],
                    velocities[k + 1][i],
                    acc(a),
                    acc(b),
                ]
            };
            let shapes: Vec<Shape> = (0..dof)
                .map(|i| Shape::new(kind, span, ends(i), tb))
                .collect();
            let orientation = if motion == MotionPattern::Spatial {
                let rest = (3..6).all(|i| {
                    let e = ends(i);
                    e[2] == 0.0
                        && e[3] == 0.0
                        && (kind != SplineKind::Quintic || (e[4] == 0.0 && e[5] == 0.0))
                });
                if rest {
                    let pose = |p: &SplinePoint| Pose::from_coordinates(motion, &p.q);
                    let (ra, rb) = (pose(a)?.rotation, pose(b)?.rotation);
                    let axis = (ra.inverse() * rb).axis_angle();
                    let theta = axis.map_or(0.0, |(_, t)| t);
                    Orientation::Geodesic {
                        from: ra,
                        axis,
                        shape: Shape::new(kind, span, [0.0, theta, 0.0, 0.0, 0.0, 0.0], tb),
                    }
                } else {
                    Orientation::Euler
                }
            } else {
                Orientation::Coordinates
            };
            segments.push(Segment {
                start: a.time,
                span,
                steps,
                shapes,
                orientation,
            });
        }
        Ok(Self {
            motion,
            kind,
            time_step,
            segments,
        })
    }

    /// q̇ at every point: the file's, or (cubic average velocity) the mean of the neighbouring
    /// segments' slopes at interior points; zeros for the kinds that take none (linear, blend:
    /// CASPR ignores a q_dot there).
    fn velocities(kind: SplineKind, points: &[SplinePoint]) -> Vec<Vec<f64>> {
        let dof = points[0].q.len();
        let n = points.len();
        (0..n)
            .map(|k| {
                if kind == SplineKind::CubicAverageVelocity && k > 0 && k + 1 < n {
                    let (p, c, x) = (&points[k - 1], &points[k], &points[k + 1]);
                    (0..dof)
                        .map(|i| {
                            0.5 * ((c.q[i] - p.q[i]) / (c.time - p.time)
                                + (x.q[i] - c.q[i]) / (x.time - c.time))
                        })
                        .collect()
                } else if matches!(kind, SplineKind::Linear | SplineKind::ParabolicBlend) {
                    vec![0.0; dof]
                } else {
                    points[k].q_dot.clone().unwrap_or_else(|| vec![0.0; dof])
                }
            })
            .collect()
    }

    /// The motion pattern.
    pub fn motion(&self) -> MotionPattern {
        self.motion
    }

    /// The spline kind.
    pub fn kind(&self) -> SplineKind {
        self.kind
    }

    /// The sampling period (s).
    pub fn time_step(&self) -> f64 {
        self.time_step
    }

    /// The time at which each point is reached (s): t_0, then each segment's fitted end.
    pub fn waypoint_times(&self) -> Vec<f64> {
        let mut t = vec![self.segments[0].start];
        t.extend(self.segments.iter().map(|s| s.start + s.span));
        t
    }

    /// First and last sample time (s).
    pub fn time_span(&self) -> (f64, f64) {
        let last = self.segments.last().expect("at least one segment");
        (self.segments[0].start, last.start + last.span)
    }

    /// The sample at time t (clamped to the time span; at rest at a point between a segment's
    /// fitted end and the next segment's start).
    pub fn at(&self, t: f64) -> TimedSample {
        let (start, end) = self.time_span();
        let t = t.clamp(start, end);
        let k = self.segments.partition_point(|s| s.start <= t).max(1) - 1;
        let seg = &self.segments[k];
        self.evaluate(seg, t, (t - seg.start).min(seg.span))
    }

    /// CASPR's samples: every `time_step` along each segment (see the module documentation).
    pub fn samples(&self) -> Vec<TimedSample> {
        let total: usize = self.segments.iter().map(|s| s.steps).sum();
        let mut out = Vec::with_capacity(total + 1);
        for (k, seg) in self.segments.iter().enumerate() {
            let first = if k == 0 { 0 } else { 1 };
            for j in first..=seg.steps {
                let s = if j == seg.steps {
                    seg.span
                } else {
                    j as f64 * self.time_step
                };
                out.push(self.evaluate(seg, seg.start + s, s));
            }
        }
        out
    }

    fn evaluate(&self, seg: &Segment, t: f64, s: f64) -> TimedSample {
        let dof = self.motion.dof();
        let mut q = [0.0; 6];
        let mut qd = [0.0; 6];
        let mut qdd = [0.0; 6];
        for i in 0..dof {
            [q[i], qd[i], qdd[i]] = seg.shapes[i].at(seg.span, s);
        }
        let (pose, twist, twist_rate) = match &seg.orientation {
            Orientation::Coordinates => (
                Pose::from_coordinates(self.motion, &q[..dof]).expect("finite coordinates"),
                embed(self.motion, &qd[..dof]),
                embed(self.motion, &qdd[..dof]),
            ),
            Orientation::Euler => {
                let (tw, tr) = twist_from_euler_rates(&q, &qd, &qdd);
                (
                    Pose::from_coordinates(self.motion, &q).expect("finite coordinates"),
                    tw,
                    tr,
                )
            }
            Orientation::Geodesic { from, axis, shape } => {
                let [theta, dtheta, ddtheta] = shape.at(seg.span, s);
                let (rotation, w) = match axis {
                    Some((k, _)) => (
                        from * Rotation3::from_axis_angle(k, theta),
                        from * k.into_inner(),
                    ),
                    None => (*from, Vector3::zeros()),
                };
                let (wv, wa) = (w * dtheta, w * ddtheta);
                (
                    Pose::new(Vector3::new(q[0], q[1], q[2]), rotation),
                    Vector6::new(qd[0], qd[1], qd[2], wv.x, wv.y, wv.z),
                    Vector6::new(qdd[0], qdd[1], qdd[2], wa.x, wa.y, wa.z),
                )
            }
        };
        TimedSample {
            t,
            pose,
            twist,
            twist_rate,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn point(time: f64, q: &[f64]) -> SplinePoint {
        SplinePoint {
            time,
            q: q.to_vec(),
            q_dot: None,
            q_ddot: None,
            blend_time: None,
        }
    }

    fn rest(time: f64, q: &[f64]) -> SplinePoint {
        SplinePoint {
            q_dot: Some(vec![0.0; q.len()]),
            q_ddot: Some(vec![0.0; q.len()]),
            ..point(time, q)
        }
    }

    fn one_d(kind: SplineKind, pts: &[SplinePoint], dt: f64, blend: Option<f64>) -> JointSpline {
        JointSpline::new(MotionPattern::Point2, kind, dt, pts, blend).unwrap()
    }

    /// Hand values of each kind on x ∈ [1, 3] over T = 2 s (Δ = 2).
    #[test]
    fn hand_values_of_each_kind() {
        let (a, b) = (rest(0.0, &[1.0, 0.0]), rest(2.0, &[3.0, 0.0]));
        let x = |s: &JointSpline, t: f64| {
            let p = s.at(t);
            [p.pose.position.x, p.twist[0], p.twist_rate[0]]
        };
        // Linear: q = 1 + t, q̇ = Δ/T = 1.
        let lin = one_d(
            SplineKind::Linear,
            &[point(0.0, &[1.0, 0.0]), point(2.0, &[3.0, 0.0])],
            0.1,
            None,
        );
        assert_eq!(x(&lin, 0.5), [1.5, 1.0, 0.0]);
        // Cubic at rest: q(T/2) = mid, q̇(T/2) = 1.5 Δ/T, q̈(0) = 6 Δ/T².
        let cub = one_d(SplineKind::Cubic, &[a.clone(), b.clone()], 0.1, None);
        assert_relative_eq!(x(&cub, 1.0)[0], 2.0, epsilon = 1e-15);
        assert_relative_eq!(x(&cub, 1.0)[1], 1.5, epsilon = 1e-15);
        assert_relative_eq!(x(&cub, 0.0)[2], 6.0 * 2.0 / 4.0, epsilon = 1e-15);
        // Quintic at rest: q̇(T/2) = 1.875 Δ/T, q(T/4) = 1 + Δ (10/64 − 15/256 + 6/1024).
        let qui = one_d(SplineKind::Quintic, &[a.clone(), b.clone()], 0.1, None);
        assert_relative_eq!(x(&qui, 1.0)[1], 1.875, epsilon = 1e-14);
        let s = 10.0 / 64.0 - 15.0 / 256.0 + 6.0 / 1024.0;
        assert_relative_eq!(x(&qui, 0.5)[0], 1.0 + 2.0 * s, epsilon = 1e-15);
        // Cubic with end velocities v_a = 1, v_e = −1 over T = 2: q(1) = 1 + 1 + (6 − 4 + 2)/4
        // − (−4 + 2 − 2)/8 … by the τ-polynomial: V = (2, −2), c₂ = 6 − 4 + 2 = 4,
        // c₃ = −4 + 2 − 2 = −4: q(½) = 1 + 1 + 1 − 0.5 = 2.5, q̇(½) = (2 + 4 − 3)/2 = 1.5.
        let mut va = point(0.0, &[1.0, 0.0]);
        va.q_dot = Some(vec![1.0, 0.0]);
        let mut ve = point(2.0, &[3.0, 0.0]);
        ve.q_dot = Some(vec![-1.0, 0.0]);
        let cv = one_d(SplineKind::Cubic, &[va, ve], 0.1, None);
        assert_relative_eq!(x(&cv, 1.0)[0], 2.5, epsilon = 1e-15);
        assert_relative_eq!(x(&cv, 1.0)[1], 1.5, epsilon = 1e-15);
        assert_relative_eq!(x(&cv, 0.0)[1], 1.0, epsilon = 1e-15);
        assert_relative_eq!(x(&cv, 2.0)[1], -1.0, epsilon = 1e-15);
        // Parabolic blend t_b = 0.5: a = Δ/(t_b (T − t_b)) = 8/3, cruise a t_b = 4/3.
        let pb = one_d(
            SplineKind::ParabolicBlend,
            &[point(0.0, &[1.0, 0.0]), point(2.0, &[3.0, 0.0])],
            0.1,
            Some(0.5),
        );
        assert_relative_eq!(
            x(&pb, 0.25)[0],
            1.0 + 0.5 * 8.0 / 3.0 / 16.0,
            epsilon = 1e-15
        );
        assert_relative_eq!(x(&pb, 1.0)[1], 4.0 / 3.0, epsilon = 1e-15);
        assert_relative_eq!(x(&pb, 1.0)[0], 2.0, epsilon = 1e-15);
        assert_relative_eq!(x(&pb, 1.8)[2], -8.0 / 3.0, epsilon = 1e-15);
        assert_relative_eq!(x(&pb, 2.0)[0], 3.0, epsilon = 1e-15);
        assert_eq!(x(&pb, 2.0)[1], 0.0);
    }

    /// Quintic with non-zero boundary velocities and accelerations meets all six conditions.
    #[test]
    fn quintic_meets_its_boundary_conditions() {
        let mut a = point(0.5, &[0.2, -1.0]);
        a.q_dot = Some(vec![0.3, 1.0]);
        a.q_ddot = Some(vec![-2.0, 0.5]);
        let mut b = point(2.0, &[1.1, 0.4]);
        b.q_dot = Some(vec![-0.7, 0.0]);
        b.q_ddot = Some(vec![1.5, -3.0]);
        let s = one_d(SplineKind::Quintic, &[a.clone(), b.clone()], 0.05, None);
        for (p, t) in [(&a, 0.5), (&b, 2.0)] {
            let x = s.at(t);
            let v = p.q_dot.as_ref().unwrap();
            let acc = p.q_ddot.as_ref().unwrap();
            for i in 0..2 {
                assert_relative_eq!(x.pose.position[i], p.q[i], epsilon = 1e-13);
                assert_relative_eq!(x.twist[i], v[i], epsilon = 1e-13);
                assert_relative_eq!(x.twist_rate[i], acc[i], epsilon = 1e-12);
            }
        }
    }

    /// Cubic average velocity: the interior velocity is the mean of the neighbouring slopes
    /// (CASPR's example: (0.3, 0.5) → (0.4, 0.3) at 2 s → (0.7, 0.5) at 5 s).
    #[test]
    fn cubic_average_velocity_at_interior_points() {
        let mut a = point(0.0, &[0.3, 0.5]);
        a.q_dot = Some(vec![0.0, 0.0]);
        let m = point(2.0, &[0.4, 0.3]);
        let mut b = point(5.0, &[0.7, 0.5]);
        b.q_dot = Some(vec![0.0, 0.0]);
        let s = one_d(SplineKind::CubicAverageVelocity, &[a, m, b], 0.01, None);
        let mid = s.at(2.0);
        assert_relative_eq!(mid.twist[0], 0.5 * (0.1 / 2.0 + 0.3 / 3.0), epsilon = 1e-14);
        assert_relative_eq!(
            mid.twist[1],
            0.5 * (-0.2 / 2.0 + 0.2 / 3.0),
            epsilon = 1e-14
        );
        assert_relative_eq!(mid.pose.position.x, 0.4, epsilon = 1e-15);
        // Velocity continuous across the point (both cubics end/start with it).
        let (l, r) = (s.at(2.0 - 1e-9), s.at(2.0 + 1e-9));
        assert_relative_eq!(l.twist[0], r.twist[0], epsilon = 1e-8);
        assert_eq!(s.samples().len(), 501);
        // A missing end velocity is an error naming the point.
        let mut no_v = point(5.0, &[0.7, 0.5]);
        no_v.q_dot = None;
        let mut a = point(0.0, &[0.3, 0.5]);
        a.q_dot = Some(vec![0.0, 0.0]);
        let err = JointSpline::new(
            MotionPattern::Point2,
            SplineKind::CubicAverageVelocity,
            0.01,
            &[a, no_v],
            None,
        )
        .unwrap_err();
        assert!(
            matches!(err, DynamicsError::BadSetting { ref key, .. } if key == "points[1].q_dot"),
            "{err}"
        );
    }

    /// CASPR's sampling: `t_a:dt:t_e` per segment, the shared point once; a segment that is
    /// not a multiple of dt ends at its last sample.
    #[test]
    fn sampling_follows_caspr_time_vectors() {
        let pts = [
            rest(0.0, &[0.0, 0.0]),
            rest(1.0, &[1.0, 0.0]),
            rest(2.0, &[1.0, 1.0]),
        ];
        let s = one_d(SplineKind::Quintic, &pts, 0.1, None);
        let samples = s.samples();
        assert_eq!(samples.len(), 21);
        assert_relative_eq!(samples[10].t, 1.0, epsilon = 1e-15);
        assert_relative_eq!(samples[10].pose.position.x, 1.0, epsilon = 1e-15);
        assert_eq!(samples[20].pose.position.y, 1.0);
        // 0.25 s in steps of 0.1: samples at 0, 0.1, 0.2 and the point is reached at 0.2 s.
        let pts = [
            rest(0.0, &[0.0, 0.0]),
            rest(0.25, &[1.0, 0.0]),
            rest(0.5, &[2.0, 0.0]),
        ];
        let s = one_d(SplineKind::Quintic, &pts, 0.1, None);
        let t: Vec<f64> = s.samples().iter().map(|p| p.t).collect();
        assert_eq!(t.len(), 5);
        assert_relative_eq!(t[2], 0.2, epsilon = 1e-15);
        assert_relative_eq!(t[3], 0.35, epsilon = 1e-15);
        assert_relative_eq!(s.samples()[2].pose.position.x, 1.0, epsilon = 1e-15);
        assert_relative_eq!(s.waypoint_times()[1], 0.2, epsilon = 1e-15);
        // Resting at the point between 0.2 s and 0.25 s.
        assert_relative_eq!(s.at(0.23).pose.position.x, 1.0, epsilon = 1e-15);
        assert_eq!(s.at(0.23).twist, Vector6::zeros());
    }

    /// Central differences of the sampled poses give the twists and their rates: geodesic
    /// orientations (zero end rates) and Euler-rate segments (non-zero end rates, ω = H φ̇).
    #[test]
    fn twists_match_finite_differences_of_the_rotation() {
        let q0 = [0.1, -0.2, 0.5, 0.2, -0.4, 0.1];
        let q1 = [0.4, 0.1, 0.7, 0.3, 0.0, -0.2];
        let q2 = [0.6, 0.3, 0.6, -0.1, 0.3, 0.4];
        let mut mid = rest(1.0, &q1);
        mid.q_dot = Some(vec![0.1, 0.0, -0.2, 0.3, -0.5, 0.2]);
        mid.q_ddot = Some(vec![0.0, 0.4, 0.0, -1.0, 0.5, 0.3]);
        for kind in SplineKind::ALL {
            let pts = [rest(0.0, &q0), mid.clone(), rest(2.5, &q2)];
            let s = JointSpline::new(MotionPattern::Spatial, kind, 0.01, &pts, Some(0.3)).unwrap();
            let euler = |k: usize| s.segments[k].orientation == Orientation::Euler;
            // Linear and blend ignore rates (geodesic); the others use the given/average ones.
            assert_eq!(
                euler(0),
                !matches!(kind, SplineKind::Linear | SplineKind::ParabolicBlend),
                "{kind:?}"
            );
            let h = 1e-6;
            for &t in &[0.37, 0.8, 1.45, 2.35] {
                let (a, b, c) = (s.at(t - h), s.at(t), s.at(t + h));
                let v = (c.pose.position - a.pose.position) / (2.0 * h);
                let rdot = (c.pose.rotation.matrix() - a.pose.rotation.matrix()) / (2.0 * h);
                let wx = rdot * b.pose.rotation.matrix().transpose();
                let w = Vector3::new(wx[(2, 1)], wx[(0, 2)], wx[(1, 0)]);
                for i in 0..3 {
                    assert_relative_eq!(b.twist[i], v[i], epsilon = 1e-6);
                    assert_relative_eq!(b.twist[i + 3], w[i], epsilon = 1e-6);
                }
                let acc = (c.twist - a.twist) / (2.0 * h);
                assert_relative_eq!(b.twist_rate, acc, epsilon = 1e-5);
            }
            // The ends are the points' poses.
            let samples = s.samples();
            let first = samples[0].pose.coordinates(MotionPattern::Spatial);
            let last = samples
                .last()
                .unwrap()
                .pose
                .coordinates(MotionPattern::Spatial);
            for i in 0..6 {
                assert_relative_eq!(first[i], q0[i], epsilon = 1e-12);
                assert_relative_eq!(last[i], q2[i], epsilon = 1e-12);
            }
        }
    }

    /// A geodesic orientation segment is CASPR's: the rotation angle from R_a follows the
    /// quintic law and the axis stays fixed.
    #[test]
    fn geodesic_follows_the_scalar_law() {
        let (q0, q1) = ([0.0; 6], [0.0, 0.0, 0.0, 0.6, 0.0, 0.0]);
        let s = JointSpline::new(
            MotionPattern::Spatial,
            SplineKind::Quintic,
            0.01,
            &[rest(0.0, &q0), rest(2.0, &q1)],
            None,
        )
        .unwrap();
        let p = s.at(0.5);
        let sigma = 10.0 / 64.0 - 15.0 / 256.0 + 6.0 / 1024.0;
        let c = p.pose.coordinates(MotionPattern::Spatial);
        assert_relative_eq!(c[3], 0.6 * sigma, epsilon = 1e-15);
        assert_relative_eq!(s.at(1.0).twist[3], 1.875 * 0.6 / 2.0, epsilon = 1e-14);
    }

    #[test]
    fn bad_trajectories_name_their_key() {
        let key = |r: Result<JointSpline, DynamicsError>| match r {
            Err(DynamicsError::BadSetting { key, .. }) => key,
            other => panic!("{other:?}"),
        };
        let p = [rest(0.0, &[0.0, 0.0]), rest(1.0, &[1.0, 0.0])];
        let mk = |kind, dt, pts: &[SplinePoint], b| {
            JointSpline::new(MotionPattern::Point2, kind, dt, pts, b)
        };
        assert_eq!(key(mk(SplineKind::Quintic, 0.0, &p, None)), "time_step");
        assert_eq!(
            key(mk(SplineKind::Quintic, f64::NAN, &p, None)),
            "time_step"
        );
        assert_eq!(
            key(mk(SplineKind::Quintic, 2.0, &p, None)),
            "points[1].time"
        );
        let back = [
            rest(0.0, &[0.0, 0.0]),
            rest(1.0, &[1.0, 0.0]),
            rest(1.0, &[2.0, 0.0]),
        ];
        assert_eq!(
            key(mk(SplineKind::Quintic, 0.1, &back, None)),
            "points[2].time"
        );
        assert_eq!(
            key(mk(SplineKind::ParabolicBlend, 0.1, &p, Some(0.5))),
            "blend_time_default"
        );
        assert_eq!(
            key(mk(SplineKind::ParabolicBlend, 0.1, &p, None)),
            "blend_time_default"
        );
        let mut q = p.clone();
        q[1].blend_time = Some(0.6);
        assert_eq!(
            key(mk(SplineKind::ParabolicBlend, 0.1, &q, Some(0.2))),
            "points[1].blend_time"
        );
        let mut q = p.clone();
        q[0].q_ddot = None;
        assert_eq!(
            key(mk(SplineKind::Quintic, 0.1, &q, None)),
            "points[0].q_ddot"
        );
        assert!(mk(SplineKind::Linear, 0.1, &q, None).is_ok());
        let short = [rest(0.0, &[0.0])];
        assert!(matches!(
            mk(SplineKind::Linear, 0.1, &short, None),
            Err(DynamicsError::DimensionMismatch { .. })
        ));
        let wrong = [rest(0.0, &[0.0]), rest(1.0, &[1.0])];
        assert!(matches!(
            mk(SplineKind::Linear, 0.1, &wrong, None),
            Err(DynamicsError::DimensionMismatch { .. })
        ));
        assert_eq!(key(mk(SplineKind::Linear, 1e-8, &p, None)), "time_step");
    }
}

//! # Time laws
//!
//! A timed trajectory through waypoints: the path of [`cdpr_kinematics::Path`] (positions along
//! straight segments, orientations along the shortest rotation, i.e. slerp) run with a time law
//! σ(t) ∈ [0, 1] per segment, at rest at every waypoint:
//!
//! | law | σ(τ), τ = t / T | peak σ̇ · T / Δ | peak σ̈ · T² / Δ |
//! |---|---|---|---|
//! | linear | τ | 1 | 0 (the velocity jumps at the waypoints) |
//! | cubic | 3τ² − 2τ³ | 1.5 | 6 |
//! | quintic | 10τ³ − 15τ⁴ + 6τ⁵ | 1.875 | 10/√3 ≈ 5.7735 (τ = ½ − √3/6) |
//! | trapezoid | constant acceleration a, cruise v, constant deceleration | v | a |
//!
//! The parabolic blend (linear segments in the motion-pattern coordinates joined by parabolas of
//! a blend time t_b centred on the interior waypoints, from and to rest at the ends: Craig 2005,
//! §7.3) does not stop at the interior waypoints and passes near them, not through them; its
//! spatial orientations are interpolated in XYZ Euler angles and turned into twists by
//! ω = H φ̇. (CASPR's own parabolic blend stops at every point and moves orientations along the
//! shortest rotation: [`crate::joint_spline`].)
//!
//! Segment durations: per-waypoint times, or a total duration shared in proportion to the pose
//! distance √(‖Δu‖² + θ²) of each segment, or (trapezoid without a duration) each segment's
//! shortest time under the limits. Limits and distances are in the path's pose-distance units
//! (m, with 1 rad counting as 1 m), per second and per second squared.
//!
//! ## References
//! - Biagiotti & Melchiorri 2008, *Trajectory Planning for Automatic Machines and Robots*,
//!   §2.1 (cubic, quintic: eqs. (2.2), (2.5)), §3.2 (trapezoidal velocity profile, eq. (3.8)).
//! - Craig 2005, *Introduction to Robotics*, 3rd ed., §7.3: linear segments with parabolic blends.
//! - CASPR's `JointTrajectory` and `Spline` (Lau et al. 2016): its joint trajectories, read by
//!   [`crate::joint_spline`].

use crate::DynamicsError;
use crate::error::bad;
use crate::rigid_body::{embed, twist_from_euler_rates};
use cdpr_kinematics::{MotionPattern, Pose};
use nalgebra::{Rotation3, Unit, Vector3, Vector6};
use std::fmt;
use std::str::FromStr;

/// A time law (see the module table).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum TimeLaw {
    /// Constant speed on each segment.
    Linear,
    /// Cubic rest-to-rest.
    Cubic,
    /// Quintic rest-to-rest (zero acceleration at the ends too).
    Quintic,
    /// Trapezoidal velocity (bounded acceleration and velocity).
    Trapezoid,
    /// Linear segments with parabolic blends (does not stop at interior waypoints).
    ParabolicBlend,
}

impl TimeLaw {
    /// All laws.
    pub const ALL: [TimeLaw; 5] = [
        Self::Linear,
        Self::Cubic,
        Self::Quintic,
        Self::Trapezoid,
        Self::ParabolicBlend,
    ];

    /// The CLI name.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Linear => "linear",
            Self::Cubic => "cubic",
            Self::Quintic => "quintic",
            Self::Trapezoid => "trapezoid",
            Self::ParabolicBlend => "parabolic-blend",
        }
    }

    /// σ(τ), dσ/dτ and d²σ/dτ² of the normalised rest-to-rest laws (linear, cubic, quintic),
    /// τ ∈ [0, 1] (Biagiotti & Melchiorri 2008, eqs. (2.2), (2.5)). `None` for the others.
    ///
    /// ```
    /// use cdpr_dynamics::TimeLaw;
    /// let [s, ds, dds] = TimeLaw::Quintic.normalised(0.5).unwrap();
    /// assert_eq!((s, ds, dds), (0.5, 1.875, 0.0));
    /// ```
    pub fn normalised(self, tau: f64) -> Option<[f64; 3]> {
        let t = tau.clamp(0.0, 1.0);
        Some(match self {
            Self::Linear => [t, 1.0, 0.0],
            Self::Cubic => [t * t * (3.0 - 2.0 * t), 6.0 * t * (1.0 - t), 6.0 - 12.0 * t],
            Self::Quintic => {
                let t2 = t * t;
                [
                    t2 * t * (10.0 - 15.0 * t + 6.0 * t2),
                    30.0 * t2 * (1.0 - 2.0 * t + t2),
                    60.0 * t * (1.0 - 3.0 * t + 2.0 * t2),
                ]
            }
            _ => return None,
        })
    }

    /// Peak dσ/dτ and |d²σ/dτ²| of the normalised laws.
    fn peaks(self) -> (f64, f64) {
        match self {
            Self::Linear => (1.0, 0.0),
            Self::Cubic => (1.5, 6.0),
            _ => (1.875, 10.0 / 3f64.sqrt()),
        }
    }
}

impl fmt::Display for TimeLaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for TimeLaw {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|l| l.name() == s)
            .ok_or_else(|| {
                format!(
                    "unknown time law {s:?} (expected one of: {})",
                    Self::ALL.map(|l| l.name()).join(", ")
                )
            })
    }
}

/// How to time a path.
#[derive(Debug, Clone, PartialEq)]
pub struct TimingSettings {
    /// The law.
    pub law: TimeLaw,
    /// Total duration T (s); exclusive with `waypoint_times`.
    pub duration: Option<f64>,
    /// The time of each waypoint (s), strictly increasing.
    pub waypoint_times: Option<Vec<f64>>,
    /// Largest pose-distance speed (m/s, rad/s).
    pub max_velocity: Option<f64>,
    /// Largest pose-distance acceleration (m/s², rad/s²).
    pub max_acceleration: Option<f64>,
    /// Parabolic blend: the blend time t_b (s); default a quarter of the shortest segment.
    pub blend_time: Option<f64>,
}

impl TimingSettings {
    /// A law run over `duration` seconds.
    pub fn with_duration(law: TimeLaw, duration: f64) -> Self {
        Self {
            law,
            duration: Some(duration),
            waypoint_times: None,
            max_velocity: None,
            max_acceleration: None,
            blend_time: None,
        }
    }
}

/// One sample of a timed trajectory: the time, the pose, the twist ẋ = [v; ω] and its
/// derivative ẍ = [v̇; ω̇], as 6-vectors (base axes; components a motion pattern lacks are 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimedSample {
    /// t (s).
    pub t: f64,
    /// The pose.
    pub pose: Pose,
    /// ẋ = [v (m/s); ω (rad/s)].
    pub twist: Vector6<f64>,
    /// ẍ = [v̇ (m/s²); ω̇ (rad/s²)].
    pub twist_rate: Vector6<f64>,
}

impl TimedSample {
    /// The pattern's components of a 6-vector, in its order.
    pub fn components(motion: MotionPattern, v: &Vector6<f64>) -> Vec<f64> {
        crate::rigid_body::pattern_components(motion)
            .iter()
            .map(|&i| v[i])
            .collect()
    }
}

/// Rest-to-rest progress along one segment.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Progress {
    Normalised(TimeLaw),
    /// Distance L, cruise speed v, acceleration time t_a (a = v / t_a).
    Trapezoid {
        length: f64,
        speed: f64,
        ramp: f64,
    },
    Still,
}

#[derive(Debug, Clone, PartialEq)]
struct Segment {
    start: f64,
    duration: f64,
    from: Pose,
    delta_u: Vector3<f64>,
    /// Rotation axis in platform axes and angle of from⁻¹ · to.
    axis: Option<(Unit<Vector3<f64>>, f64)>,
    progress: Progress,
}

impl Segment {
    /// σ, σ̇, σ̈ at local time τ_t ∈ [0, T].
    fn sigma(&self, local: f64) -> [f64; 3] {
        let t = local.clamp(0.0, self.duration);
        match self.progress {
            Progress::Still => [0.0, 0.0, 0.0],
            Progress::Normalised(law) => {
                let d = self.duration;
                let [s, ds, dds] = law.normalised(t / d).expect("normalised law");
                [s, ds / d, dds / (d * d)]
            }
            Progress::Trapezoid {
                length,
                speed,
                ramp,
            } => {
                let a = speed / ramp;
                let end = self.duration;
                let (d, v, acc) = if t < ramp {
                    (0.5 * a * t * t, a * t, a)
                } else if t <= end - ramp {
                    (speed * (t - 0.5 * ramp), speed, 0.0)
                } else {
                    let r = end - t;
                    (length - 0.5 * a * r * r, a * r, -a)
                };
                [d / length, v / length, acc / length]
            }
        }
    }

    fn sample(&self, t: f64) -> TimedSample {
        let [s, ds, dds] = self.sigma(t - self.start);
        let position = self.from.position + s * self.delta_u;
        let (rotation, w) = match self.axis {
            Some((k, theta)) => (
                self.from.rotation * Rotation3::from_axis_angle(&k, s * theta),
                self.from.rotation * (k.into_inner() * theta),
            ),
            None => (self.from.rotation, Vector3::zeros()),
        };
        let v = ds * self.delta_u;
        let a = dds * self.delta_u;
        TimedSample {
            t,
            pose: Pose::new(position, rotation),
            twist: Vector6::new(v.x, v.y, v.z, ds * w.x, ds * w.y, ds * w.z),
            twist_rate: Vector6::new(a.x, a.y, a.z, dds * w.x, dds * w.y, dds * w.z),
        }
    }
}

/// Linear segments with parabolic blends in coordinates (Craig 2005, §7.3).
#[derive(Debug, Clone, PartialEq)]
struct Blend {
    times: Vec<f64>,
    q: Vec<Vec<f64>>,
    blend: f64,
    /// Per segment: the line L_k(t) = q_ref + v (t − t_ref).
    lines: Vec<(f64, Vec<f64>, Vec<f64>)>,
}

impl Blend {
    fn new(times: Vec<f64>, q: Vec<Vec<f64>>, blend: f64) -> Result<Self, DynamicsError> {
        let n = times.len() - 1;
        let dim = q[0].len();
        let tb = blend;
        let mut lines = Vec::with_capacity(n);
        for k in 0..n {
            let dt = times[k + 1] - times[k];
            let (first, last) = (k == 0, k + 1 == n);
            let room = match (first, last) {
                (true, true) => dt - 2.0 * tb,
                (true, false) | (false, true) => dt - 1.5 * tb,
                (false, false) => dt - tb,
            };
            if !(tb > 0.0 && tb.is_finite()) || room < -1e-12 * dt {
                return Err(bad(
                    "blend-time",
                    tb,
                    format!(
                        "must be positive and leave the blends room on segment {} ({dt} s long)",
                        k + 1
                    ),
                ));
            }
            let span = match (first, last) {
                (true, true) => dt - tb,
                (true, false) | (false, true) => dt - 0.5 * tb,
                (false, false) => dt,
            };
            let v: Vec<f64> = (0..dim).map(|i| (q[k + 1][i] - q[k][i]) / span).collect();
            let (t_ref, q_ref) = if first {
                (times[0] + 0.5 * tb, q[0].clone())
            } else if last {
                (times[n] - 0.5 * tb, q[n].clone())
            } else {
                (times[k], q[k].clone())
            };
            lines.push((t_ref, q_ref, v));
        }
        Ok(Self {
            times,
            q,
            blend,
            lines,
        })
    }

    /// q, q̇, q̈ at t.
    fn at(&self, t: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let n = self.times.len() - 1;
        let tb = self.blend;
        let t = t.clamp(self.times[0], self.times[n]);
        let dim = self.q[0].len();
        let line = |k: usize, t: f64| -> (Vec<f64>, Vec<f64>) {
            let (tr, qr, v) = &self.lines[k];
            (
                (0..dim).map(|i| qr[i] + v[i] * (t - tr)).collect(),
                v.clone(),
            )
        };
        if t <= self.times[0] + tb {
            let r = t - self.times[0];
            let v0 = &self.lines[0].2;
            let q = (0..dim)
                .map(|i| self.q[0][i] + 0.5 * v0[i] / tb * r * r)
                .collect();
            let qd = (0..dim).map(|i| v0[i] / tb * r).collect();
            let qdd = (0..dim).map(|i| v0[i] / tb).collect();
            return (q, qd, qdd);
        }
        if t >= self.times[n] - tb {
            let r = self.times[n] - t;
            let v = &self.lines[n - 1].2;
            let q = (0..dim)
                .map(|i| self.q[n][i] - 0.5 * v[i] / tb * r * r)
                .collect();
            let qd = (0..dim).map(|i| v[i] / tb * r).collect();
            let qdd = (0..dim).map(|i| -v[i] / tb).collect();
            return (q, qd, qdd);
        }
        for k in 1..n {
            let tk = self.times[k];
            if (t - tk).abs() <= 0.5 * tb {
                let (prev, vp) = line(k - 1, t);
                let vn = &self.lines[k].2;
                let r = t - tk + 0.5 * tb;
                let q = (0..dim)
                    .map(|i| prev[i] + 0.5 * (vn[i] - vp[i]) / tb * r * r)
                    .collect();
                let qd = (0..dim).map(|i| vp[i] + (vn[i] - vp[i]) / tb * r).collect();
                let qdd = (0..dim).map(|i| (vn[i] - vp[i]) / tb).collect();
                return (q, qd, qdd);
            }
        }
        let k = self.times.partition_point(|&c| c <= t).clamp(1, n) - 1;
        let (q, v) = line(k, t);
        (q, v, vec![0.0; dim])
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    Segments(Vec<Segment>),
    Blend(Blend),
}

/// A timed trajectory through waypoints.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    motion: MotionPattern,
    kind: Kind,
    start: f64,
    end: f64,
}

fn positive(key: &str, v: f64) -> Result<f64, DynamicsError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(bad(key, v, "must be a finite number > 0"))
    }
}

impl Trajectory {
    /// Times the polyline through `waypoints` (at least two) with `settings`.
    ///
    /// Errors (naming the setting and its value): a non-positive or non-finite duration, limit or
    /// blend time; waypoint times not strictly increasing (or not one per waypoint); a duration
    /// and waypoint times both or neither given (the trapezoid may omit both: shortest time); a
    /// law whose peaks exceed the given limits.
    ///
    /// ```
    /// use cdpr_dynamics::{TimeLaw, Trajectory, TimingSettings};
    /// use cdpr_kinematics::{MotionPattern, Pose};
    /// let path = [Pose::point(0.0, 0.0, 0.0), Pose::point(1.0, 0.0, 0.0)];
    /// let traj = Trajectory::new(MotionPattern::Point3, &path,
    ///     &TimingSettings::with_duration(TimeLaw::Quintic, 2.0)).unwrap();
    /// let mid = traj.at(1.0);
    /// assert!((mid.pose.position.x - 0.5).abs() < 1e-15);
    /// assert!((mid.twist[0] - 1.875 * 1.0 / 2.0).abs() < 1e-15);   // peak ṡ = 1.875 Δ/T
    /// ```
    pub fn new(
        motion: MotionPattern,
        waypoints: &[Pose],
        settings: &TimingSettings,
    ) -> Result<Self, DynamicsError> {
        if waypoints.len() < 2 {
            return Err(DynamicsError::DimensionMismatch {
                what: "waypoints (at least)",
                expected: 2,
                found: waypoints.len(),
            });
        }
        let law = settings.law;
        let vmax = settings
            .max_velocity
            .map(|v| positive("max-velocity", v))
            .transpose()?;
        let amax = settings
            .max_acceleration
            .map(|v| positive("max-acceleration", v))
            .transpose()?;
        if let Some(tb) = settings.blend_time {
            positive("blend-time", tb)?;
            if law != TimeLaw::ParabolicBlend {
                return Err(bad(
                    "blend-time",
                    tb,
                    "applies to the parabolic-blend law only",
                ));
            }
        }
        let lengths: Vec<f64> = waypoints
            .windows(2)
            .map(|w| {
                let du = (w[1].position - w[0].position).norm_squared();
                let th = w[0].rotation.angle_to(&w[1].rotation);
                (du + th * th).sqrt()
            })
            .collect();
        let total: f64 = lengths.iter().sum();
        // Waypoint times: given, shared from a duration, or (trapezoid) the shortest.
        let times: Option<Vec<f64>> = match (&settings.waypoint_times, settings.duration) {
            (Some(_), Some(d)) => {
                return Err(bad(
                    "duration",
                    d,
                    "give either --duration or per-waypoint `time`, not both",
                ));
            }
            (Some(ts), None) => {
                if ts.len() != waypoints.len() {
                    return Err(DynamicsError::DimensionMismatch {
                        what: "waypoint times (one per waypoint)",
                        expected: waypoints.len(),
                        found: ts.len(),
                    });
                }
                for (k, &t) in ts.iter().enumerate() {
                    if !t.is_finite() {
                        return Err(bad(format!("waypoints[{k}].time"), t, "must be finite"));
                    }
                    if k > 0 && t <= ts[k - 1] {
                        return Err(bad(
                            format!("waypoints[{k}].time"),
                            t,
                            format!(
                                "waypoint times must increase strictly (waypoints[{}].time = {})",
                                k - 1,
                                ts[k - 1]
                            ),
                        ));
                    }
                }
                Some(ts.clone())
            }
            (None, Some(d)) => {
                let d = positive("duration", d)?;
                let n = lengths.len() as f64;
                let mut ts = vec![0.0];
                for l in &lengths {
                    let share = if total > 0.0 { l / total } else { 1.0 / n };
                    ts.push(ts.last().expect("non-empty") + share * d);
                }
                *ts.last_mut().expect("non-empty") = d;
                Some(ts)
            }
            (None, None) if law == TimeLaw::Trapezoid => None,
            (None, None) => {
                return Err(bad(
                    "duration",
                    f64::NAN,
                    "give --duration or per-waypoint `time`",
                ));
            }
        };
        if law == TimeLaw::ParabolicBlend {
            if let Some(v) = vmax {
                return Err(bad(
                    "max-velocity",
                    v,
                    "applies to the rest-to-rest laws, not parabolic-blend",
                ));
            }
            if let Some(a) = amax {
                return Err(bad(
                    "max-acceleration",
                    a,
                    "applies to the rest-to-rest laws, not parabolic-blend",
                ));
            }
            let times = times.expect("given for every law but the trapezoid");
            let shortest = times
                .windows(2)
                .map(|w| w[1] - w[0])
                .fold(f64::INFINITY, f64::min);
            let tb = settings.blend_time.unwrap_or(0.25 * shortest);
            let q = waypoints.iter().map(|p| p.coordinates(motion)).collect();
            let (start, end) = (times[0], *times.last().expect("non-empty"));
            return Ok(Self {
                motion,
                kind: Kind::Blend(Blend::new(times, unwrap_angles(motion, q), tb)?),
                start,
                end,
            });
        }
        let mut segments = Vec::with_capacity(lengths.len());
        let mut clock = times.as_ref().map_or(0.0, |t| t[0]);
        for (k, w) in waypoints.windows(2).enumerate() {
            let length = lengths[k];
            let given = times.as_ref().map(|t| t[k + 1] - t[k]);
            let (duration, progress) = if length == 0.0 {
                (given.unwrap_or(0.0), Progress::Still)
            } else if law == TimeLaw::Trapezoid {
                trapezoid(length, given, vmax, amax)?
            } else {
                let d = given.expect("given for every law but the trapezoid");
                let (pv, pa) = law.peaks();
                if let Some(v) = vmax
                    && pv * length / d > v * (1.0 + 1e-12)
                {
                    return Err(bad(
                        "max-velocity",
                        v,
                        format!(
                            "the {law} law needs {} on segment {} ({length} long in {d} s)",
                            pv * length / d,
                            k + 1
                        ),
                    ));
                }
                if let Some(a) = amax
                    && pa * length / (d * d) > a * (1.0 + 1e-12)
                {
                    return Err(bad(
                        "max-acceleration",
                        a,
                        format!(
                            "the {law} law needs {} on segment {} ({length} long in {d} s)",
                            pa * length / (d * d),
                            k + 1
                        ),
                    ));
                }
                (d, Progress::Normalised(law))
            };
            let relative = w[0].rotation.inverse() * w[1].rotation;
            segments.push(Segment {
                start: clock,
                duration,
                from: w[0],
                delta_u: w[1].position - w[0].position,
                axis: relative.axis_angle(),
                progress,
            });
            clock += duration;
        }
        let start = segments[0].start;
        let end = match &times {
            Some(t) => *t.last().expect("non-empty"),
            None => clock,
        };
        if end <= start {
            return Err(bad(
                "duration",
                end - start,
                "the path does not move: give a duration",
            ));
        }
        Ok(Self {
            motion,
            kind: Kind::Segments(segments),
            start,
            end,
        })
    }

    /// The motion pattern.
    pub fn motion(&self) -> MotionPattern {
        self.motion
    }

    /// First and last time (s).
    pub fn time_span(&self) -> (f64, f64) {
        (self.start, self.end)
    }

    /// The time of each waypoint (s); the parabolic blend passes near, not through, the
    /// interior ones.
    pub fn waypoint_times(&self) -> Vec<f64> {
        match &self.kind {
            Kind::Segments(segs) => {
                let mut t: Vec<f64> = segs.iter().map(|s| s.start).collect();
                t.push(self.end);
                t
            }
            Kind::Blend(b) => b.times.clone(),
        }
    }

    /// The sample at time t (clamped to the time span).
    pub fn at(&self, t: f64) -> TimedSample {
        let t = t.clamp(self.start, self.end);
        match &self.kind {
            Kind::Segments(segs) => {
                let k = segs
                    .partition_point(|s| s.start + s.duration <= t)
                    .min(segs.len() - 1);
                segs[k].sample(t)
            }
            Kind::Blend(b) => {
                let (q, qd, qdd) = b.at(t);
                let pose = Pose::from_coordinates(self.motion, &q)
                    .expect("finite coordinates of the right size");
                let (twist, twist_rate) = if self.motion == MotionPattern::Spatial {
                    let arr = |v: &[f64]| -> [f64; 6] { v.try_into().expect("6 numbers") };
                    twist_from_euler_rates(&arr(&q), &arr(&qd), &arr(&qdd))
                } else {
                    (embed(self.motion, &qd), embed(self.motion, &qdd))
                };
                TimedSample {
                    t,
                    pose,
                    twist,
                    twist_rate,
                }
            }
        }
    }

    /// Samples every `dt` seconds from the start, plus the end time (error naming `dt` if it
    /// is not positive, or if it would make more than 10 000 000 samples).
    pub fn sample(&self, dt: f64) -> Result<Vec<TimedSample>, DynamicsError> {
        let dt = positive("dt", dt)?;
        let span = self.end - self.start;
        let steps = (span / dt + 1e-9).floor();
        if steps > 1e7 {
            return Err(bad(
                "dt",
                dt,
                format!("makes more than 10 000 000 samples over {span} s"),
            ));
        }
        let steps = steps as usize;
        let mut out: Vec<TimedSample> = (0..=steps)
            .map(|k| self.at(self.start + k as f64 * dt))
            .collect();
        if self.end - (self.start + steps as f64 * dt) > 1e-9 * dt {
            out.push(self.at(self.end));
        }
        Ok(out)
    }
}

/// Angles of consecutive waypoints unwrapped (no jump of 2π between them).
fn unwrap_angles(motion: MotionPattern, mut q: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let angles: &[usize] = match motion {
        MotionPattern::Planar => &[2],
        MotionPattern::Spatial => &[3, 5],
        _ => &[],
    };
    for k in 1..q.len() {
        for &i in angles {
            let tau = std::f64::consts::TAU;
            let d = q[k][i] - q[k - 1][i];
            q[k][i] -= tau * (d / tau).round();
        }
    }
    q
}

/// The trapezoid on a segment of length L: (duration, progress).
fn trapezoid(
    length: f64,
    duration: Option<f64>,
    vmax: Option<f64>,
    amax: Option<f64>,
) -> Result<(f64, Progress), DynamicsError> {
    let (duration, speed, ramp) = match (duration, amax) {
        (Some(t), Some(a)) => {
            // a t_a² − a T t_a + L = 0 with t_a ≤ T/2: needs a T² ≥ 4 L (Biagiotti & Melchiorri
            // 2008, eq. (3.10)).
            let disc = a * a * t * t - 4.0 * a * length;
            if disc < 0.0 {
                return Err(bad(
                    "max-acceleration",
                    a,
                    format!(
                        "too small to cover {length} in {t} s (needs at least {})",
                        4.0 * length / (t * t)
                    ),
                ));
            }
            let v = 0.5 * (a * t - disc.sqrt());
            if let Some(vm) = vmax
                && v > vm * (1.0 + 1e-12)
            {
                return Err(bad(
                    "max-velocity",
                    vm,
                    format!("covering {length} in {t} s at acceleration {a} needs speed {v}"),
                ));
            }
            (t, v, v / a)
        }
        (Some(t), None) => {
            let Some(v) = vmax else {
                return Err(bad(
                    "max-acceleration",
                    f64::NAN,
                    "the trapezoid needs --max-acceleration or --max-velocity",
                ));
            };
            // Cruise at v: t_a = T − L / v, which must lie in (0, T/2].
            let ramp = t - length / v;
            if !(ramp > 0.0 && ramp <= 0.5 * t * (1.0 + 1e-12)) {
                return Err(bad(
                    "max-velocity",
                    v,
                    format!(
                        "covering {length} in {t} s needs a cruise speed between {} and {}",
                        length / t,
                        2.0 * length / t
                    ),
                ));
            }
            (t, v, ramp.min(0.5 * t))
        }
        (None, Some(a)) => {
            let v = vmax.unwrap_or(f64::INFINITY);
            if length <= v * v / a {
                let ramp = (length / a).sqrt();
                (2.0 * ramp, a * ramp, ramp)
            } else {
                (length / v + v / a, v, v / a)
            }
        }
        (None, None) => {
            return Err(bad(
                "max-acceleration",
                f64::NAN,
                "the trapezoid without --duration needs --max-acceleration (and --max-velocity)",
            ));
        }
    };
    Ok((
        duration,
        Progress::Trapezoid {
            length,
            speed,
            ramp,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn line(d: f64) -> [Pose; 2] {
        [Pose::point(0.0, 0.0, 0.0), Pose::point(d, 0.0, 0.0)]
    }

    /// Quintic rest-to-rest peaks: ṡ = 1.875 Δ/T at τ = ½, s̈ = 5.7735 Δ/T² at τ = 0.21132.
    #[test]
    fn quintic_peaks() {
        let (delta, t) = (0.8, 2.5);
        let traj = Trajectory::new(
            MotionPattern::Point3,
            &line(delta),
            &TimingSettings::with_duration(TimeLaw::Quintic, t),
        )
        .unwrap();
        assert_relative_eq!(
            traj.at(0.5 * t).twist[0],
            1.875 * delta / t,
            epsilon = 1e-14
        );
        let tau = 0.5 - 3f64.sqrt() / 6.0;
        assert_relative_eq!(tau, 0.21132, epsilon = 1e-5);
        let peak = traj.at(tau * t).twist_rate[0];
        assert_relative_eq!(peak, 5.7735 * delta / (t * t), max_relative = 1e-5);
        // It is the maximum: the sampled profile never exceeds it.
        let samples = traj.sample(1e-3).unwrap();
        let top = samples.iter().map(|s| s.twist_rate[0]).fold(0.0, f64::max);
        assert!(top <= peak * (1.0 + 1e-12));
        assert_eq!(samples[0].twist[0], 0.0);
        assert_eq!(samples.last().unwrap().twist[0], 0.0);
    }

    /// Velocities and accelerations are the derivatives of the poses (central differences),
    /// rotations included, for every law.
    #[test]
    fn derivatives_match_finite_differences() {
        let wp = [
            Pose::spatial(Vector3::new(0.0, 0.1, 0.5), 0.1, -0.2, 0.3),
            Pose::spatial(Vector3::new(0.4, -0.1, 0.7), 0.3, 0.1, -0.2),
            Pose::spatial(Vector3::new(0.6, 0.2, 0.6), -0.1, 0.2, 0.4),
        ];
        for law in TimeLaw::ALL {
            let mut s = TimingSettings::with_duration(law, 3.0);
            if law == TimeLaw::Trapezoid {
                s.max_acceleration = Some(2.0);
            }
            let traj = Trajectory::new(MotionPattern::Spatial, &wp, &s).unwrap();
            let h = 1e-6;
            for &t in &[0.37, 1.1, 1.6, 2.45] {
                let (a, b, c) = (traj.at(t - h), traj.at(t), traj.at(t + h));
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
        }
    }

    /// The trapezoid: shortest time 2√(L/a) when v is never reached, L/v + v/a otherwise.
    #[test]
    fn trapezoid_times() {
        let mut s = TimingSettings::with_duration(TimeLaw::Trapezoid, 0.0);
        s.duration = None;
        s.max_acceleration = Some(2.0);
        let t = Trajectory::new(MotionPattern::Point3, &line(0.5), &s).unwrap();
        assert_relative_eq!(t.time_span().1, 2.0 * (0.25f64).sqrt(), epsilon = 1e-15);
        s.max_velocity = Some(0.5);
        let t = Trajectory::new(MotionPattern::Point3, &line(2.0), &s).unwrap();
        assert_relative_eq!(t.time_span().1, 2.0 / 0.5 + 0.5 / 2.0, epsilon = 1e-15);
        assert_relative_eq!(t.at(2.0).twist[0], 0.5, epsilon = 1e-15);
        assert_relative_eq!(t.at(0.1).twist_rate[0], 2.0, epsilon = 1e-15);
        assert_relative_eq!(t.at(t.time_span().1).pose.position.x, 2.0, epsilon = 1e-15);
    }

    /// The parabolic blend: straight at the constant segment speed between blends, at rest at
    /// the ends, ending at the last waypoint.
    #[test]
    fn parabolic_blend_profile() {
        let wp = [
            Pose::point(0.0, 0.0, 0.0),
            Pose::point(1.0, 0.0, 0.0),
            Pose::point(1.0, 2.0, 0.0),
        ];
        let mut s = TimingSettings::with_duration(TimeLaw::ParabolicBlend, 0.0);
        s.duration = None;
        s.waypoint_times = Some(vec![0.0, 2.0, 4.0]);
        s.blend_time = Some(0.4);
        let t = Trajectory::new(MotionPattern::Point3, &wp, &s).unwrap();
        // First segment line through (0.2 s, 0) and (2 s, 1): v = 1 / 1.8.
        assert_relative_eq!(t.at(1.0).twist[0], 1.0 / 1.8, epsilon = 1e-15);
        assert_relative_eq!(t.at(1.0).pose.position.x, 0.8 / 1.8, epsilon = 1e-15);
        assert_eq!(t.at(0.0).twist, Vector6::zeros());
        assert_relative_eq!(t.at(4.0).pose.position.y, 2.0, epsilon = 1e-15);
        assert_relative_eq!(t.at(4.0).twist.norm(), 0.0, epsilon = 1e-15);
        s.blend_time = Some(1.5);
        assert!(matches!(
            Trajectory::new(MotionPattern::Point3, &wp, &s),
            Err(DynamicsError::BadSetting { key, .. }) if key == "blend-time"
        ));
    }

    #[test]
    fn bad_settings_name_their_key() {
        let key = |r: Result<Trajectory, DynamicsError>| match r {
            Err(DynamicsError::BadSetting { key, .. }) => key,
            other => panic!("{other:?}"),
        };
        let p = line(1.0);
        let mk = |s: &TimingSettings| Trajectory::new(MotionPattern::Point3, &p, s);
        assert_eq!(
            key(mk(&TimingSettings::with_duration(TimeLaw::Cubic, -1.0))),
            "duration"
        );
        let mut s = TimingSettings::with_duration(TimeLaw::Cubic, 1.0);
        s.max_velocity = Some(1.0); // needs 1.5
        assert_eq!(key(mk(&s)), "max-velocity");
        let mut s = TimingSettings::with_duration(TimeLaw::Trapezoid, 1.0);
        s.max_acceleration = Some(3.0); // needs 4
        assert_eq!(key(mk(&s)), "max-acceleration");
        let mut s = TimingSettings::with_duration(TimeLaw::Cubic, 1.0);
        s.duration = None;
        s.waypoint_times = Some(vec![1.0, 1.0]);
        assert_eq!(key(mk(&s)), "waypoints[1].time");
        let t = mk(&TimingSettings::with_duration(TimeLaw::Cubic, 1.0)).unwrap();
        assert!(matches!(t.sample(0.0), Err(DynamicsError::BadSetting { key, .. }) if key == "dt"));
        assert!(t.sample(f64::NAN).is_err());
        assert_eq!(t.sample(0.3).unwrap().len(), 5); // 0, 0.3, 0.6, 0.9 and 1
    }
}

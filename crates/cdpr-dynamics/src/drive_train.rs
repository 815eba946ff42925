//! # Drive train: winches, motor speeds and motor torques
//!
//! Each cable is wound on a drum of radius r driven through a gear of ratio G (motor turns per
//! drum turn) by a motor of rotor inertia J_m (kg·m², the drum's inertia reflected to the motor
//! shaft included). With θ_m the motor angle, positive when the drum winds the cable in,
//! l̇ = −(r/G) θ̇_m, so along a timed trajectory
//!
//! - motor speed ω_m = −(G/r) l̇ (rad/s),
//! - motor torque τ = (r/G) t − J_m (G/r) l̈ (N·m): the motor's equation J_m θ̈_m = τ − (r/G) t
//!   with θ̈_m = −(G/r) l̈ (the cable tension t loads the drum by r t, the gear divides it by G),
//! - mechanical power P = τ ω_m (W, positive when the motor drives),
//!
//! their peaks and root-mean-square values over time (the RMS torque is what heats a motor),
//! checked against each winch's `max_torque` (N·m) and `max_speed` (rad/s): "can these motors do
//! it?". The drum's friction and the gear's efficiency are not modelled.
//!
//! ## References
//! - Pott 2018, *Cable-Driven Parallel Robots: Theory and Application*, Springer (winches:
//!   drum, gear and motor); WireCenter's `<winch>` (`<drum r_drum>`, `<motor gear_ratio inertia
//!   angular_velocity>`) holds the same parameters.

use crate::DynamicsError;
use crate::DynamicsProfile;
use crate::error::bad;

/// One cable's winch: drum, gear and motor (the robot file's `winch = { … }`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Winch {
    /// Drum radius r (m), > 0.
    pub drum_radius: f64,
    /// Gear ratio G (motor turns per drum turn), > 0; 1 for a direct drive.
    pub gear_ratio: f64,
    /// Rotor inertia J_m at the motor shaft (kg·m²), ≥ 0.
    pub motor_inertia: f64,
    /// Largest motor torque (N·m), if known.
    pub max_torque: Option<f64>,
    /// Largest motor speed (rad/s), if known.
    pub max_speed: Option<f64>,
    /// Cable diameter d (m), if known: the cable then winds on a single-layer helical drum
    /// of pitch d ([`Winch::payout_radius`]); without it the cable is a line on the drum's
    /// surface (ρ = r).
    pub cable_diameter: Option<f64>,
}

impl Winch {
    /// A winch, checked: r and G finite and positive, J_m finite and non-negative, limits
    /// finite and positive. Errors name the robot-file key.
    ///
    /// ```
    /// use cdpr_dynamics::Winch;
    /// let w = Winch::new(0.05, 10.0, 1e-4, Some(2.0), Some(300.0)).unwrap();
    /// // Winding in at 0.5 m/s: ω_m = (G/r)·0.5 = 100 rad/s.
    /// assert!((w.motor_speed(-0.5) - 100.0).abs() < 1e-12);
    /// assert!(Winch::new(0.0, 10.0, 1e-4, None, None).is_err());
    /// ```
    pub fn new(
        drum_radius: f64,
        gear_ratio: f64,
        motor_inertia: f64,
        max_torque: Option<f64>,
        max_speed: Option<f64>,
    ) -> Result<Self, DynamicsError> {
        let positive = |key: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(bad(
                    format!("winch.{key}"),
                    v,
                    "must be a finite positive number",
                ))
            }
        };
        positive("drum_radius", drum_radius)?;
        positive("gear_ratio", gear_ratio)?;
        if !(motor_inertia.is_finite() && motor_inertia >= 0.0) {
            return Err(bad(
                "winch.motor_inertia",
                motor_inertia,
                "must be a finite non-negative number (kg·m²)",
            ));
        }
        if let Some(v) = max_torque {
            positive("max_torque", v)?;
        }
        if let Some(v) = max_speed {
            positive("max_speed", v)?;
        }
        Ok(Self {
            drum_radius,
            gear_ratio,
            motor_inertia,
            max_torque,
            max_speed,
            cable_diameter: None,
        })
    }

    /// The winch with the cable diameter d (m, finite and > 0; `None` leaves it out): the
    /// robot file's `winch.cable_diameter`.
    pub fn with_cable_diameter(mut self, diameter: Option<f64>) -> Result<Self, DynamicsError> {
        if let Some(d) = diameter
            && !(d.is_finite() && d > 0.0)
        {
            return Err(bad(
                "winch.cable_diameter",
                d,
                "must be a finite positive number (m)",
            ));
        }
        self.cable_diameter = diameter;
        Ok(self)
    }

    /// ρ, the cable length paid out per radian of drum (m/rad). A single-layer helical drum
    /// whose turns touch (pitch p = d): the cable's centre line is a helix of radius r + d/2
    /// and pitch d, so one turn holds √((2π(r + d/2))² + d²) of cable and
    /// ρ = √((r + d/2)² + (d/2π)²): the arc length of the helix per radian. The grooved
    /// single-layer drum is the winch of the IPAnema robots (Pott 2018, *Cable-Driven Parallel
    /// Robots*, winch design); the helix itself is plain geometry. A multi-layer drum (radius
    /// growing by about d per layer) is not modelled. Without a cable diameter, ρ = r.
    ///
    /// ```
    /// use cdpr_dynamics::Winch;
    /// let w = Winch::new(0.05, 10.0, 1e-4, None, None).unwrap();
    /// assert_eq!(w.payout_radius(), 0.05);
    /// let w = w.with_cable_diameter(Some(0.004)).unwrap();
    /// let rho = (0.052f64.powi(2) + (0.004 / std::f64::consts::TAU).powi(2)).sqrt();
    /// assert!((w.payout_radius() - rho).abs() < 1e-15);
    /// ```
    pub fn payout_radius(&self) -> f64 {
        match self.cable_diameter {
            None => self.drum_radius,
            Some(d) => (self.drum_radius + 0.5 * d).hypot(d / std::f64::consts::TAU),
        }
    }

    /// The drum angle φ = L/ρ (rad) that pays out the cable length `length` (m) from the drum,
    /// counted from the angle where no cable is paid out.
    pub fn drum_angle(&self, length: f64) -> f64 {
        length / self.payout_radius()
    }

    /// Motor speed ω_m = −(G/r) l̇ (rad/s) for the cable speed l̇ (m/s); positive winds in
    /// (r the [`Winch::payout_radius`]).
    pub fn motor_speed(&self, cable_speed: f64) -> f64 {
        -self.gear_ratio / self.payout_radius() * cable_speed
    }

    /// Motor torque τ = (r/G) t − J_m (G/r) l̈ (N·m) for the tension t (N) and the cable
    /// acceleration l̈ (m/s²); positive winds in.
    pub fn motor_torque(&self, tension: f64, cable_acceleration: f64) -> f64 {
        let r = self.payout_radius();
        r / self.gear_ratio * tension
            - self.motor_inertia * self.gear_ratio / r * cable_acceleration
    }
}

/// Motor speeds, torques and powers along a timed trajectory, with their peaks, RMS values
/// and the limit check. Per-sample quantities are flat, n per sample (as in
/// [`DynamicsProfile`]); torques and powers are NaN where the sample is infeasible.
#[derive(Debug, Clone, PartialEq)]
pub struct DriveTrainProfile {
    /// Number of motors n (one per cable).
    pub motors: usize,
    /// ω_m (rad/s), n per sample.
    pub motor_speeds: Vec<f64>,
    /// τ (N·m), n per sample, NaN where infeasible.
    pub motor_torques: Vec<f64>,
    /// P = τ ω_m (W), n per sample, NaN where infeasible.
    pub motor_powers: Vec<f64>,
    /// Per motor, max |ω_m| (rad/s).
    pub peak_speed: Vec<f64>,
    /// Per motor, max |τ| over the feasible samples (N·m; NaN when no sample is feasible).
    pub peak_torque: Vec<f64>,
    /// Per motor, max P over the feasible samples (W).
    pub peak_power: Vec<f64>,
    /// Per motor, √(1/T ∫ ω_m² dt) (rad/s, trapezoidal rule).
    pub rms_speed: Vec<f64>,
    /// Per motor, √(1/T ∫ τ² dt) (N·m); `None` when a sample is infeasible (τ unknown there).
    pub rms_torque: Vec<Option<f64>>,
    /// Max over time of the summed power Σ_i P_i (W): what the power supply must deliver.
    pub peak_total_power: f64,
    /// Every exceeded limit, e.g. "motor 3: |τ| = 2.41 N·m > max_torque = 2 N·m at t = 0.35 s"
    /// (the first sample where it happens).
    pub violations: Vec<String>,
    /// Can these motors do it? `Some(true)` when every sample is feasible and within every
    /// given limit, `Some(false)` when a limit is exceeded, `None` when no limit is given or
    /// infeasible samples leave the torque unknown (and no limit is exceeded elsewhere).
    pub within_limits: Option<bool>,
}

/// The drive train along `profile` (from [`inverse_dynamics`](crate::inverse_dynamics())), one
/// winch per cable.
///
/// ```
/// use cdpr_dynamics::{DynamicsProfile, Winch, drive_train};
/// use nalgebra::DVector;
/// // One cable holding 100 N, winding in at 0.5 m/s and accelerating its winding at 2 m/s².
/// let profile = DynamicsProfile {
///     cables: 1, dof: 1, t: vec![0.0, 1.0],
///     tensions: vec![Some(DVector::from_element(1, 100.0)); 2],
///     reasons: vec![None, None], inertial_wrench: vec![0.0; 2],
///     cable_lengths: vec![1.0, 0.5], cable_speeds: vec![-0.5; 2],
///     cable_accelerations: vec![-2.0; 2],
/// };
/// let w = Winch::new(0.05, 10.0, 1e-4, Some(1.0), None).unwrap();
/// let d = drive_train(&[w], &profile).unwrap();
/// // τ = (r/G) t − J (G/r) l̈ = 0.005·100 + 1e-4·200·2 = 0.54 N·m; ω = 200·0.5 = 100 rad/s.
/// assert!((d.motor_torques[0] - 0.54).abs() < 1e-12);
/// assert!((d.motor_powers[0] - 54.0).abs() < 1e-9);
/// assert_eq!(d.within_limits, Some(true));
/// ```
pub fn drive_train(
    winches: &[Winch],
    profile: &DynamicsProfile,
) -> Result<DriveTrainProfile, DynamicsError> {
    let n = profile.cables;
    if winches.len() != n {
        return Err(DynamicsError::DimensionMismatch {
            what: "winches (one per cable)",
            expected: n,
            found: winches.len(),
        });
    }
    let count = profile.t.len();
    let mut out = DriveTrainProfile {
        motors: n,
        motor_speeds: vec![f64::NAN; count * n],
        motor_torques: vec![f64::NAN; count * n],
        motor_powers: vec![f64::NAN; count * n],
        peak_speed: vec![0.0; n],
        peak_torque: vec![0.0; n],
        peak_power: vec![f64::NEG_INFINITY; n],
        rms_speed: vec![0.0; n],
        rms_torque: vec![None; n],
        peak_total_power: f64::NEG_INFINITY,
        violations: Vec::new(),
        within_limits: None,
    };
    let mut first_over_torque: Vec<Option<(f64, f64)>> = vec![None; n];
    let mut first_over_speed: Vec<Option<(f64, f64)>> = vec![None; n];
    for k in 0..count {
        let mut total = 0.0;
        let mut total_known = true;
        for (i, w) in winches.iter().enumerate() {
            let j = k * n + i;
            let speed = w.motor_speed(profile.cable_speeds[j]);
            out.motor_speeds[j] = speed;
            if speed.is_finite() {
                out.peak_speed[i] = out.peak_speed[i].max(speed.abs());
                if let Some(max) = w.max_speed
                    && speed.abs() > max
                    && first_over_speed[i].is_none()
                {
                    first_over_speed[i] = Some((profile.t[k], speed));
                }
            }
            let Some(t) = profile.tensions[k].as_ref() else {
                total_known = false;
                continue;
            };
            let tau = w.motor_torque(t[i], profile.cable_accelerations[j]);
            out.motor_torques[j] = tau;
            out.motor_powers[j] = tau * speed;
            if tau.is_finite() {
                out.peak_torque[i] = out.peak_torque[i].max(tau.abs());
                out.peak_power[i] = out.peak_power[i].max(tau * speed);
                total += tau * speed;
                if let Some(max) = w.max_torque
                    && tau.abs() > max
                    && first_over_torque[i].is_none()
                {
                    first_over_torque[i] = Some((profile.t[k], tau));
                }
            } else {
                total_known = false;
            }
        }
        if total_known {
            out.peak_total_power = out.peak_total_power.max(total);
        }
    }
    let span = match (profile.t.first(), profile.t.last()) {
        (Some(a), Some(b)) if b > a => b - a,
        _ => 0.0,
    };
    for i in 0..n {
        out.rms_speed[i] = rms(&profile.t, |k| out.motor_speeds[k * n + i], span).unwrap_or(0.0);
        out.rms_torque[i] = rms(&profile.t, |k| out.motor_torques[k * n + i], span);
        if out.peak_power[i] == f64::NEG_INFINITY {
            // No feasible sample: the torque (and so its peak) is unknown.
            out.peak_power[i] = f64::NAN;
            out.peak_torque[i] = f64::NAN;
        }
    }
    if out.peak_total_power == f64::NEG_INFINITY {
        out.peak_total_power = f64::NAN;
    }
    for (i, w) in winches.iter().enumerate() {
        if let (Some(max), Some((t, tau))) = (w.max_torque, first_over_torque[i]) {
            out.violations.push(format!(
                "motor {}: |τ| = {:.6} N·m > max_torque = {max} N·m at t = {t} s",
                i + 1,
                tau.abs()
            ));
        }
        if let (Some(max), Some((t, speed))) = (w.max_speed, first_over_speed[i]) {
            out.violations.push(format!(
                "motor {}: |ω| = {:.6} rad/s > max_speed = {max} rad/s at t = {t} s",
                i + 1,
                speed.abs()
            ));
        }
    }
    let limited = winches
        .iter()
        .any(|w| w.max_torque.is_some() || w.max_speed.is_some());
    let torques_known = profile.tensions.iter().all(Option::is_some);
    out.within_limits = if !out.violations.is_empty() {
        Some(false)
    } else if limited && torques_known {
        Some(true)
    } else {
        None
    };
    Ok(out)
}

/// √(1/T ∫ f² dt) by the trapezoidal rule over the samples at `t` (the plain root mean square
/// for a single sample or a zero span); `None` if a value is not finite.
fn rms(t: &[f64], f: impl Fn(usize) -> f64, span: f64) -> Option<f64> {
    let count = t.len();
    if count == 0 {
        return None;
    }
    if (0..count).any(|k| !f(k).is_finite()) {
        return None;
    }
    if span <= 0.0 {
        let s: f64 = (0..count).map(|k| f(k) * f(k)).sum();
        return Some((s / count as f64).sqrt());
    }
    let integral: f64 = (1..count)
        .map(|k| 0.5 * (f(k - 1).powi(2) + f(k).powi(2)) * (t[k] - t[k - 1]))
        .sum();
    Some((integral / span).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;

    fn profile(tensions: Vec<Option<f64>>, speeds: Vec<f64>, accs: Vec<f64>) -> DynamicsProfile {
        let count = tensions.len();
        DynamicsProfile {
            cables: 1,
            dof: 1,
            t: (0..count).map(|k| k as f64 * 0.5).collect(),
            reasons: tensions
                .iter()
                .map(|t| t.is_none().then(|| "infeasible".to_string()))
                .collect(),
            tensions: tensions
                .into_iter()
                .map(|t| t.map(|t| DVector::from_element(1, t)))
                .collect(),
            inertial_wrench: vec![0.0; count],
            cable_lengths: vec![1.0; count],
            cable_speeds: speeds,
            cable_accelerations: accs,
        }
    }

    #[test]
    fn hand_derived_torque_speed_power() {
        // r = 0.1 m, G = 5, J = 2e-3 kg m²: r/G = 0.02 m, G/r = 50 1/m.
        let w = Winch::new(0.1, 5.0, 2e-3, Some(3.0), Some(60.0)).unwrap();
        // Paying out at 1 m/s (l̇ > 0): the motor turns backwards at −50 rad/s.
        assert_eq!(w.motor_speed(1.0), -50.0);
        // τ = 0.02·120 − 2e-3·50·(−4) = 2.4 + 0.4 = 2.8 N·m.
        assert!((w.motor_torque(120.0, -4.0) - 2.8).abs() < 1e-12);
        let p = profile(
            vec![Some(120.0), Some(120.0), Some(100.0)],
            vec![1.0, 1.0, 0.0],
            vec![-4.0, -4.0, 0.0],
        );
        let d = drive_train(&[w], &p).unwrap();
        assert!((d.motor_torques[0] - 2.8).abs() < 1e-12);
        assert!((d.motor_torques[2] - 2.0).abs() < 1e-12);
        assert!((d.motor_powers[0] - 2.8 * -50.0).abs() < 1e-9);
        assert_eq!(d.peak_speed, vec![50.0]);
        assert!((d.peak_torque[0] - 2.8).abs() < 1e-12);
        // Trapezoid over t = 0, 0.5, 1: ∫τ² = 0.25(2.8² + 2.8²) + 0.25(2.8² + 2²), T = 1.
        let expected = (0.25 * (3.0 * 2.8f64.powi(2) + 4.0)).sqrt();
        assert!((d.rms_torque[0].unwrap() - expected).abs() < 1e-12);
        let expected_speed = (0.25 * 3.0 * 2500.0f64).sqrt();
        assert!((d.rms_speed[0] - expected_speed).abs() < 1e-9);
        // The motor is braking (P < 0) while paying out; at rest P = 0.
        assert_eq!(d.peak_power[0], 0.0);
        assert_eq!(d.within_limits, Some(true));
    }

    #[test]
    fn limits_are_checked_and_named() {
        let w = Winch::new(0.1, 5.0, 2e-3, Some(2.5), Some(40.0)).unwrap();
        let p = profile(
            vec![Some(100.0), Some(120.0)],
            vec![0.0, 1.0],
            vec![0.0, -4.0],
        );
        let d = drive_train(&[w], &p).unwrap();
        assert_eq!(d.within_limits, Some(false));
        assert_eq!(d.violations.len(), 2, "{:?}", d.violations);
        assert!(d.violations[0].contains("max_torque = 2.5 N·m at t = 0.5 s"));
        assert!(d.violations[1].contains("max_speed = 40 rad/s"));
    }

    #[test]
    fn infeasible_samples_leave_torque_unknown() {
        let w = Winch::new(0.1, 5.0, 0.0, Some(100.0), None).unwrap();
        let p = profile(vec![Some(10.0), None], vec![0.0, 0.0], vec![0.0, 0.0]);
        let d = drive_train(&[w], &p).unwrap();
        assert!(d.motor_torques[1].is_nan());
        assert_eq!(d.rms_torque[0], None);
        assert!((d.peak_torque[0] - 0.2).abs() < 1e-12);
        // No feasible sample at all: no peak either.
        let p = profile(vec![None, None], vec![0.0, 0.0], vec![0.0, 0.0]);
        let d = drive_train(&[w], &p).unwrap();
        assert!(d.peak_torque[0].is_nan() && d.peak_power[0].is_nan());
        assert!(d.peak_total_power.is_nan());
        assert_eq!(d.within_limits, None);
        let none = Winch::new(0.1, 5.0, 0.0, None, None).unwrap();
        let p = profile(vec![Some(10.0)], vec![0.0], vec![0.0]);
        assert_eq!(drive_train(&[none], &p).unwrap().within_limits, None);
    }

    #[test]
    fn bad_winches_name_their_key() {
        let e = Winch::new(0.1, -1.0, 0.0, None, None).unwrap_err();
        assert!(e.to_string().starts_with("winch.gear_ratio = -1"), "{e}");
        let e = Winch::new(0.1, 1.0, f64::NAN, None, None).unwrap_err();
        assert!(e.to_string().contains("winch.motor_inertia"), "{e}");
        let e = Winch::new(0.1, 1.0, 0.0, Some(0.0), None).unwrap_err();
        assert!(e.to_string().contains("winch.max_torque"), "{e}");
        let p = profile(vec![Some(1.0)], vec![0.0], vec![0.0]);
        assert!(drive_train(&[], &p).is_err());
    }
}

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
//! r in these equations is the payout radius ρ, the cable paid out per drum radian: the drum
//! radius, the single-layer helix of a `cable_diameter` ([`Winch::payout_radius`]), or on a
//! multi-layer drum ([`DrumLayers`]) the ρ_k of the layer the cable leaves at its current
//! paid-out length ([`Winch::payout_radius_at`]); within a layer the equations hold as they
//! stand, and ρ steps from layer to layer.
//!
//! ## References
//! - Pott 2018, *Cable-Driven Parallel Robots: Theory and Application*, Springer (winches:
//!   drum, gear and motor); WireCenter's `<winch>` (`<drum r_drum>`, `<motor gear_ratio inertia
//!   angular_velocity>`) holds the same parameters.
//! - Multi-layer spooling: Wire Rope Technical Board, *Wire Rope Users Manual* (drums with
//!   multiple layers: each layer above the first lies in the valleys between the turns below,
//!   and crosses over once or twice a turn); the LeBus counterbalanced grooving (F. LeBus,
//!   1950s) makes every layer nest that way.

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
    /// Multi-layer winding (needs the cable diameter): `None` is the single-layer drum.
    pub layers: Option<DrumLayers>,
}

/// A multi-layer drum: the robot file's `winch.turns_per_layer` and `winch.cable_length`.
///
/// Layer k = 0, 1, 2, … has its cable's centre at R_k = r + d/2 + k d: the layers are assumed
/// stacked straight on each other. Nested layers (each turn in the valley between two turns
/// below, as on LeBus-grooved drums) sit closer, about k·d·√3/2 (close-packed circles), and
/// alternate nested layers hold about N − 1 turns: this model overstates the radius of the upper
/// layers by up to (1 − √3/2) k d ≈ 0.13 k d (see the module's references). Each layer holds N
/// turns, and a turn of layer k holds 2π ρ_k of cable with ρ_k = √(R_k² + (d/2π)²), the
/// single-layer helix of [`Winch::payout_radius`] at radius R_k (one layer with N large is
/// that drum exactly). Φ(W), the drum angle that winds the length W onto the empty drum
/// ([`Winch::winding_angle`]), is piecewise linear with slope 1/ρ_k on layer k:
/// Φ(W) = 2πN k + (W − S_k)/ρ_k for S_k ≤ W ≤ S_{k+1}, S_k = 2πN Σ_{j<k} ρ_j.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrumLayers {
    /// N, the turns that fit across the drum's width (≥ 1).
    pub turns_per_layer: u32,
    /// C (m, > 0): the cable's whole length on the winch, all of it wound on the drum when the
    /// paid-out length L is 0.
    pub cable_length: f64,
}

impl DrumLayers {
    /// 2πN (rad): the drum angle of one full layer.
    fn layer_angle(&self) -> f64 {
        std::f64::consts::TAU * f64::from(self.turns_per_layer)
    }
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
            layers: None,
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
        if let (None, Some(l)) = (diameter, self.layers) {
            return Err(bad(
                "winch.turns_per_layer",
                f64::from(l.turns_per_layer),
                "needs winch.cable_diameter (the layers are d thick)",
            ));
        }
        self.cable_diameter = diameter;
        Ok(self)
    }

    /// The winch with multi-layer winding ([`DrumLayers`]): `turns_per_layer` N ≥ 1 and
    /// `cable_length` C (m, finite and > 0), both or neither (neither leaves the single-layer
    /// drum), and only with a cable diameter. Errors name the robot-file key.
    ///
    /// ```
    /// use cdpr_dynamics::Winch;
    /// let w = Winch::new(0.05, 10.0, 1e-4, None, None).unwrap();
    /// assert!(w.with_layers(Some(20), Some(30.0)).is_err()); // no cable_diameter
    /// let w = w.with_cable_diameter(Some(0.004)).unwrap();
    /// let e = w.with_layers(Some(20), None).unwrap_err();
    /// assert!(e.to_string().contains("winch.cable_length"), "{e}");
    /// let w = w.with_layers(Some(20), Some(30.0)).unwrap();
    /// // One full layer is 20 turns of the drum.
    /// let layer = 20.0 * std::f64::consts::TAU * w.payout_radius();
    /// let phi = w.winding_angle(layer).unwrap();
    /// assert!((phi - 40.0 * std::f64::consts::PI).abs() < 1e-12);
    /// ```
    pub fn with_layers(
        mut self,
        turns_per_layer: Option<u32>,
        cable_length: Option<f64>,
    ) -> Result<Self, DynamicsError> {
        if let Some(n) = turns_per_layer
            && n == 0
        {
            return Err(bad(
                "winch.turns_per_layer",
                0.0,
                "must be an integer ≥ 1 (turns across the drum's width)",
            ));
        }
        if let Some(c) = cable_length
            && !(c.is_finite() && c > 0.0)
        {
            return Err(bad(
                "winch.cable_length",
                c,
                "must be a finite positive number (m)",
            ));
        }
        self.layers = match (turns_per_layer, cable_length) {
            (None, None) => None,
            (Some(n), None) => {
                return Err(bad(
                    "winch.turns_per_layer",
                    f64::from(n),
                    "needs winch.cable_length too (give both or neither)",
                ));
            }
            (None, Some(c)) => {
                return Err(bad(
                    "winch.cable_length",
                    c,
                    "needs winch.turns_per_layer too (give both or neither)",
                ));
            }
            (Some(n), Some(c)) => {
                if self.cable_diameter.is_none() {
                    return Err(bad(
                        "winch.turns_per_layer",
                        f64::from(n),
                        "needs winch.cable_diameter (the layers are d thick)",
                    ));
                }
                Some(DrumLayers {
                    turns_per_layer: n,
                    cable_length: c,
                })
            }
        };
        Ok(self)
    }

    /// ρ_k = √(R_k² + (d/2π)²), R_k = r + d/2 + k d (m/rad): the payout radius of layer k
    /// ([`DrumLayers`]); ρ_0 is the single-layer helix, and without a cable diameter ρ = r.
    pub fn layer_payout_radius(&self, layer: usize) -> f64 {
        match self.cable_diameter {
            None => self.drum_radius,
            Some(d) => {
                (self.drum_radius + 0.5 * d + layer as f64 * d).hypot(d / std::f64::consts::TAU)
            }
        }
    }

    /// ρ, the cable length paid out per radian of drum (m/rad). A single-layer helical drum
    /// whose turns touch (pitch p = d): the cable's centre line is a helix of radius r + d/2
    /// and pitch d, so one turn holds √((2π(r + d/2))² + d²) of cable and
    /// ρ = √((r + d/2)² + (d/2π)²): the arc length of the helix per radian. The grooved
    /// single-layer drum is the winch of the IPAnema robots (Pott 2018, *Cable-Driven Parallel
    /// Robots*, winch design); the helix itself is plain geometry. Without a cable diameter,
    /// ρ = r. A multi-layer drum ([`DrumLayers`]) is ignored here: this is the first layer's
    /// ρ_0; [`Winch::payout_radius_at`] gives the radius at a paid-out length.
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
    /// counted from the angle where no cable is paid out; ρ the [`Winch::payout_radius`], so a
    /// multi-layer drum is ignored ([`Winch::drum_angle_at`] takes it into account).
    pub fn drum_angle(&self, length: f64) -> f64 {
        length / self.payout_radius()
    }

    /// Φ(W) (rad): the drum angle that winds the length W (m, finite, ≥ 0) onto the empty
    /// drum. On a multi-layer drum Φ(W) = 2πN k + (W − S_k)/ρ_k on layer k
    /// ([`DrumLayers`]; W may exceed C, the layers continue); otherwise W/ρ. Continuous and
    /// strictly increasing; the cost grows with the number of layers W fills.
    pub fn winding_angle(&self, wound: f64) -> Result<f64, DynamicsError> {
        if !(wound.is_finite() && wound >= 0.0) {
            return Err(bad(
                "wound length",
                wound,
                "must be a finite non-negative number (m)",
            ));
        }
        let Some(layers) = self.layers else {
            return Ok(wound / self.payout_radius());
        };
        let turn = layers.layer_angle();
        let (mut k, mut rest) = (0usize, wound);
        loop {
            let rho = self.layer_payout_radius(k);
            let hold = turn * rho;
            if rest <= hold {
                return Ok(k as f64 * turn + rest / rho);
            }
            rest -= hold;
            k += 1;
        }
    }

    /// Φ⁻¹(φ) (m): the length wound onto the empty drum by the drum angle φ (rad, finite,
    /// ≥ 0), the inverse of [`Winch::winding_angle`]: on layer k = ⌊φ/2πN⌋,
    /// W = S_k + (φ − 2πN k) ρ_k.
    pub fn wound_length(&self, angle: f64) -> Result<f64, DynamicsError> {
        if !(angle.is_finite() && angle >= 0.0) {
            return Err(bad(
                "drum angle",
                angle,
                "must be a finite non-negative number (rad)",
            ));
        }
        let Some(layers) = self.layers else {
            return Ok(angle * self.payout_radius());
        };
        let turn = layers.layer_angle();
        let (mut k, mut rest, mut wound) = (0usize, angle, 0.0);
        while rest > turn {
            wound += turn * self.layer_payout_radius(k);
            rest -= turn;
            k += 1;
        }
        Ok(wound + rest * self.layer_payout_radius(k))
    }

    /// The multi-layer drum and its check of the paid-out length L (m): 0 ≤ L ≤ C.
    fn layered(&self, length: f64) -> Result<Option<DrumLayers>, DynamicsError> {
        let Some(layers) = self.layers else {
            return Ok(None);
        };
        if !(length.is_finite() && (0.0..=layers.cable_length).contains(&length)) {
            return Err(DynamicsError::PaidOutLength {
                cable: None,
                time: None,
                length,
                cable_length: layers.cable_length,
            });
        }
        Ok(Some(layers))
    }

    /// The layer k of the outermost turn when W (m) is wound, S_k < W ≤ S_{k+1} (k = 0 for
    /// W = 0), and S_k (m).
    fn top_layer(&self, layers: DrumLayers, wound: f64) -> (usize, f64) {
        let turn = layers.layer_angle();
        let (mut k, mut below) = (0usize, 0.0);
        loop {
            let hold = turn * self.layer_payout_radius(k);
            if wound <= below + hold {
                return (k, below);
            }
            below += hold;
            k += 1;
        }
    }

    /// The drum angle (rad) that pays out the length L (m) from the full winch, counted from
    /// the angle where no cable is paid out. On a multi-layer drum with C on the winch it is
    /// Φ(C) − Φ(C − L) ([`Winch::winding_angle`]), summed layer by layer from the top so that
    /// a payout within one layer is L/ρ_k exactly; L must lie in [0, C]
    /// ([`DynamicsError::PaidOutLength`] otherwise). Without layers, L/ρ as
    /// [`Winch::drum_angle`] (any L).
    ///
    /// ```
    /// use cdpr_dynamics::Winch;
    /// use std::f64::consts::TAU;
    /// let w = Winch::new(0.05, 10.0, 1e-4, None, None).unwrap()
    ///     .with_cable_diameter(Some(0.004)).unwrap();
    /// let (rho0, rho1) = (w.layer_payout_radius(0), w.layer_payout_radius(1));
    /// // 10 turns per layer, 1.5 layers' worth of cable: the top half layer pays out at ρ_1.
    /// let c = 10.0 * TAU * rho0 + 5.0 * TAU * rho1;
    /// let w = w.with_layers(Some(10), Some(c)).unwrap();
    /// assert!((w.drum_angle_at(0.1).unwrap() - 0.1 / rho1).abs() < 1e-15);
    /// assert!((w.drum_angle_at(c).unwrap() - 15.0 * TAU).abs() < 1e-12);
    /// assert!(w.drum_angle_at(c + 0.01).is_err()); // the drum would be empty
    /// ```
    pub fn drum_angle_at(&self, length: f64) -> Result<f64, DynamicsError> {
        let Some(layers) = self.layered(length)? else {
            return Ok(self.drum_angle(length));
        };
        let (mut k, mut below) = self.top_layer(layers, layers.cable_length);
        let (mut top, mut rest, mut angle) = (layers.cable_length, length, 0.0);
        loop {
            let rho = self.layer_payout_radius(k);
            let here = top - below;
            if rest <= here || k == 0 {
                return Ok(angle + rest / rho);
            }
            angle += here / rho;
            rest -= here;
            k -= 1;
            top = below;
            below = (below - layers.layer_angle() * self.layer_payout_radius(k)).max(0.0);
        }
    }

    /// dL/dφ (m/rad) at the paid-out length L (m): on a multi-layer drum the ρ_k of the layer
    /// the cable leaves, k the layer of the outermost turn with C − L wound (S_k < C − L ≤
    /// S_{k+1}; L in [0, C], [`DynamicsError::PaidOutLength`] otherwise); ρ steps by about d
    /// from layer to layer. Without layers the constant [`Winch::payout_radius`] (any L).
    pub fn payout_radius_at(&self, length: f64) -> Result<f64, DynamicsError> {
        let Some(layers) = self.layered(length)? else {
            return Ok(self.payout_radius());
        };
        let (k, _) = self.top_layer(layers, layers.cable_length - length);
        Ok(self.layer_payout_radius(k))
    }

    /// Motor speed ω_m = −(G/r) l̇ (rad/s) for the cable speed l̇ (m/s); positive winds in
    /// (r the [`Winch::payout_radius`]: a multi-layer drum is ignored, see
    /// [`Winch::motor_speed_at`]).
    pub fn motor_speed(&self, cable_speed: f64) -> f64 {
        speed_with(self.payout_radius(), self.gear_ratio, cable_speed)
    }

    /// Motor torque τ = (r/G) t − J_m (G/r) l̈ (N·m) for the tension t (N) and the cable
    /// acceleration l̈ (m/s²); positive winds in (r the [`Winch::payout_radius`]: a
    /// multi-layer drum is ignored, see [`Winch::motor_torque_at`]).
    pub fn motor_torque(&self, tension: f64, cable_acceleration: f64) -> f64 {
        self.torque_with(self.payout_radius(), tension, cable_acceleration)
    }

    /// [`Winch::motor_speed`] at the paid-out length L (m): r = [`Winch::payout_radius_at`].
    pub fn motor_speed_at(&self, length: f64, cable_speed: f64) -> Result<f64, DynamicsError> {
        Ok(speed_with(
            self.payout_radius_at(length)?,
            self.gear_ratio,
            cable_speed,
        ))
    }

    /// [`Winch::motor_torque`] at the paid-out length L (m): r = [`Winch::payout_radius_at`].
    pub fn motor_torque_at(
        &self,
        length: f64,
        tension: f64,
        cable_acceleration: f64,
    ) -> Result<f64, DynamicsError> {
        Ok(self.torque_with(self.payout_radius_at(length)?, tension, cable_acceleration))
    }

    /// τ = (r/G) t − J_m (G/r) l̈ with the payout radius r.
    fn torque_with(&self, r: f64, tension: f64, cable_acceleration: f64) -> f64 {
        r / self.gear_ratio * tension
            - self.motor_inertia * self.gear_ratio / r * cable_acceleration
    }
}

/// ω_m = −(G/r) l̇ with the payout radius r.
fn speed_with(r: f64, gear_ratio: f64, cable_speed: f64) -> f64 {
    -gear_ratio / r * cable_speed
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
/// winch per cable. On a multi-layer drum the payout radius of each sample is
/// [`Winch::payout_radius_at`] the profile's cable length l, the only length a
/// [`DynamicsProfile`] holds (the geometric length from the anchor, taken as the length paid
/// out); an l beyond the winch's `cable_length` is a [`DynamicsError::PaidOutLength`] naming
/// the cable and the time.
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
            let length = profile.cable_lengths[j];
            // Where the kinematics failed (l NaN) the cable's rates are unknown as well.
            let rho = match w.layers {
                Some(_) if length.is_nan() => f64::NAN,
                _ => w.payout_radius_at(length).map_err(|e| match e {
                    DynamicsError::PaidOutLength {
                        length,
                        cable_length,
                        ..
                    } => DynamicsError::PaidOutLength {
                        cable: Some(i + 1),
                        time: Some(profile.t[k]),
                        length,
                        cable_length,
                    },
                    e => e,
                })?,
            };
            let speed = speed_with(rho, w.gear_ratio, profile.cable_speeds[j]);
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
            let tau = w.torque_with(rho, t[i], profile.cable_accelerations[j]);
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

    /// r = 5 cm, d = 4 mm, G = 10, J_m = 1e-4 kg·m², `n` turns per layer, `c` m of cable.
    fn layered(n: u32, c: f64) -> Winch {
        Winch::new(0.05, 10.0, 1e-4, None, None)
            .unwrap()
            .with_cable_diameter(Some(0.004))
            .unwrap()
            .with_layers(Some(n), Some(c))
            .unwrap()
    }

    /// ρ_k by hand: R_k = 0.05 + 0.002 + 0.004 k, pitch term d/2π.
    fn rho(k: f64) -> f64 {
        ((0.052 + 0.004 * k).powi(2) + (0.004 / TAU).powi(2)).sqrt()
    }

    use std::f64::consts::TAU;

    #[test]
    fn one_full_layer_is_2_pi_n_of_drum_angle() {
        let w = layered(7, 100.0);
        // Layer k holds 7 turns of 2π ρ_k.
        let (l0, l1, l2) = (
            7.0 * TAU * rho(0.0),
            7.0 * TAU * rho(1.0),
            7.0 * TAU * rho(2.0),
        );
        for (k, r) in [rho(0.0), rho(1.0), rho(2.0)].into_iter().enumerate() {
            assert!((w.layer_payout_radius(k) - r).abs() < 1e-15, "layer {k}");
        }
        assert!((w.winding_angle(l0).unwrap() - 7.0 * TAU).abs() < 1e-12);
        assert!((w.winding_angle(l0 + l1).unwrap() - 14.0 * TAU).abs() < 1e-12);
        assert!((w.winding_angle(l0 + l1 + l2).unwrap() - 21.0 * TAU).abs() < 1e-12);
        // Half way up layer 1: 7 turns plus half a layer at ρ_1.
        let phi = w.winding_angle(l0 + 0.5 * l1).unwrap();
        assert!((phi - 10.5 * TAU).abs() < 1e-12, "{phi}");
        // Paying a full layer out of the drum (C two and a half layers) turns it 2πN.
        let w = layered(7, l0 + l1 + 0.5 * l2);
        let a = w.drum_angle_at(0.5 * l2 + l1).unwrap();
        assert!((a - 10.5 * TAU).abs() < 1e-12, "{a}");
        // Across layers: the top 0.5 l2 at ρ_2, layer 1 whole, 0.1 m of layer 0 at ρ_0.
        let a = w.drum_angle_at(0.5 * l2 + l1 + 0.1).unwrap();
        assert!((a - (10.5 * TAU + 0.1 / rho(0.0))).abs() < 1e-12, "{a}");
        // Within the top layer the payout is L/ρ_2 exactly; and Φ(C) − Φ(C − L) elsewhere.
        assert_eq!(
            w.drum_angle_at(0.2).unwrap(),
            0.2 / w.layer_payout_radius(2)
        );
        let c = l0 + l1 + 0.5 * l2;
        for l in [0.0, 0.3, 1.0, 2.0, 3.0, c] {
            let expected = w.winding_angle(c).unwrap() - w.winding_angle(c - l).unwrap();
            assert!(
                (w.drum_angle_at(l).unwrap() - expected).abs() < 1e-12,
                "L = {l}"
            );
        }
    }

    #[test]
    fn the_payout_radius_jumps_by_d_across_a_layer_boundary() {
        let l1 = 7.0 * TAU * rho(1.0);
        // C = layer 0 and half of layer 1: after 0.5 l1 paid out the cable leaves layer 0.
        let w = layered(7, 7.0 * TAU * rho(0.0) + 0.5 * l1);
        let (before, after) = (
            w.payout_radius_at(0.5 * l1 - 1e-9).unwrap(),
            w.payout_radius_at(0.5 * l1 + 1e-9).unwrap(),
        );
        assert!((before - rho(1.0)).abs() < 1e-15 && (after - rho(0.0)).abs() < 1e-15);
        // ρ_1 − ρ_0 = d R/ρ to first order: d (1 − (d/2π)²/(2R²)) ≈ d (1 − 7.5e-5).
        let jump = before - after;
        assert!((jump - 0.004).abs() < 0.004 * 1e-4, "{jump}");
        assert!((jump - 0.004).abs() > 0.0);
        // Full drum, the outermost turn: ρ_1; empty drum: ρ_0.
        assert_eq!(w.payout_radius_at(0.0).unwrap(), w.layer_payout_radius(1));
        let c = w.layers.unwrap().cable_length;
        assert_eq!(w.payout_radius_at(c).unwrap(), w.layer_payout_radius(0));
        // The motor follows: ω_m = −(G/ρ_k) l̇, τ = (ρ_k/G) t − J_m (G/ρ_k) l̈.
        let v = w.motor_speed_at(0.1, -0.5).unwrap();
        assert!((v - 10.0 / rho(1.0) * 0.5).abs() < 1e-12, "{v}");
        let tau = w.motor_torque_at(l1, 100.0, 2.0).unwrap();
        let expected = rho(0.0) / 10.0 * 100.0 - 1e-4 * 10.0 / rho(0.0) * 2.0;
        assert!((tau - expected).abs() < 1e-12, "{tau}");
        // The old signatures keep the first layer's constant radius.
        assert_eq!(w.payout_radius(), w.layer_payout_radius(0));
        assert!((w.motor_speed(-0.5) - 10.0 / rho(0.0) * 0.5).abs() < 1e-12);
    }

    #[test]
    fn winding_angle_is_continuous_and_strictly_increasing() {
        let w = layered(3, 50.0);
        let mut boundary = 0.0;
        for k in 0..6 {
            boundary += 3.0 * TAU * rho(k as f64);
            let (a, b, c) = (
                w.winding_angle(boundary - 1e-9).unwrap(),
                w.winding_angle(boundary).unwrap(),
                w.winding_angle(boundary + 1e-9).unwrap(),
            );
            assert!(a < b && b < c, "layer {k}: {a} {b} {c}");
            // Slopes 1/ρ_k and 1/ρ_{k+1} on either side: no jump.
            assert!((b - a - 1e-9 / rho(k as f64)).abs() < 1e-12, "layer {k}");
            assert!(
                (c - b - 1e-9 / rho(k as f64 + 1.0)).abs() < 1e-12,
                "layer {k}"
            );
            assert!((b - 3.0 * TAU * (k + 1) as f64).abs() < 1e-11, "layer {k}");
        }
        let mut last = -1.0;
        for i in 0..=1000 {
            let phi = w.winding_angle(0.05 * i as f64).unwrap();
            assert!(phi > last, "W = {}", 0.05 * i as f64);
            last = phi;
            let back = w.wound_length(phi).unwrap();
            assert!(
                (back - 0.05 * i as f64).abs() < 1e-12,
                "W = {}",
                0.05 * i as f64
            );
        }
    }

    #[test]
    fn huge_layers_give_the_single_layer_drum() {
        let single = Winch::new(0.05, 10.0, 1e-4, Some(5.0), None)
            .unwrap()
            .with_cable_diameter(Some(0.004))
            .unwrap();
        let huge = single.with_layers(Some(u32::MAX), Some(20.0)).unwrap();
        for l in [0.0, 0.7, 3.2, 11.0, 20.0] {
            let (a, b) = (single.drum_angle(l), huge.drum_angle_at(l).unwrap());
            assert!((a - b).abs() < 1e-12, "L = {l}: {a} {b}");
            assert_eq!(huge.payout_radius_at(l).unwrap(), single.payout_radius());
            assert_eq!(
                huge.motor_torque_at(l, 80.0, 1.5).unwrap(),
                single.motor_torque(80.0, 1.5)
            );
            let phi = huge.winding_angle(l).unwrap();
            assert!((phi - l / single.payout_radius()).abs() < 1e-12, "W = {l}");
        }
        let mut p = profile(
            vec![Some(120.0), Some(90.0), None],
            vec![1.0, -0.3, 0.0],
            vec![-4.0, 2.0, 0.0],
        );
        p.cable_lengths = vec![2.0, 5.0, f64::NAN];
        let (a, b) = (
            drive_train(&[single], &p).unwrap(),
            drive_train(&[huge], &p).unwrap(),
        );
        assert_eq!(a.motor_torques[..2], b.motor_torques[..2]);
        assert_eq!(a.motor_speeds[..2], b.motor_speeds[..2]);
        assert_eq!(a.peak_torque, b.peak_torque);
    }

    #[test]
    fn the_drive_train_uses_the_layer_of_each_sample() {
        let (l0, l1) = (5.0 * TAU * rho(0.0), 5.0 * TAU * rho(1.0));
        let w = layered(5, l0 + l1);
        let mut p = profile(vec![Some(100.0), Some(100.0)], vec![-0.5; 2], vec![0.0; 2]);
        // Sample 0 pays out from layer 1, sample 1 (more than l1 out) from layer 0.
        p.cable_lengths = vec![0.5 * l1, l1 + 0.5 * l0];
        let d = drive_train(&[w], &p).unwrap();
        assert!((d.motor_speeds[0] - 10.0 / rho(1.0) * 0.5).abs() < 1e-12);
        assert!((d.motor_speeds[1] - 10.0 / rho(0.0) * 0.5).abs() < 1e-12);
        assert!((d.motor_torques[0] - rho(1.0) * 10.0).abs() < 1e-12);
        assert!((d.motor_torques[1] - rho(0.0) * 10.0).abs() < 1e-12);
        // More than C paid out: an error naming the cable and the time, no NaN.
        p.cable_lengths = vec![1.0, l0 + l1 + 0.25];
        let e = drive_train(&[w], &p).unwrap_err().to_string();
        assert!(
            e.starts_with("cable 1: paid-out length ")
                && e.contains(" at t = 0.5 s exceeds winch.cable_length = "),
            "{e}"
        );
        assert!(e.contains("the drum would be empty"), "{e}");
    }

    #[test]
    fn bad_layers_name_their_key() {
        let w = Winch::new(0.05, 10.0, 1e-4, None, None).unwrap();
        let e = w.with_layers(Some(10), Some(5.0)).unwrap_err().to_string();
        assert!(
            e.starts_with("winch.turns_per_layer = 10: needs winch.cable_diameter"),
            "{e}"
        );
        let w = w.with_cable_diameter(Some(0.003)).unwrap();
        let e = w.with_layers(Some(10), None).unwrap_err().to_string();
        assert!(e.contains("needs winch.cable_length too"), "{e}");
        let e = w.with_layers(None, Some(5.0)).unwrap_err().to_string();
        assert!(
            e.starts_with("winch.cable_length = 5: needs winch.turns_per_layer"),
            "{e}"
        );
        let e = w.with_layers(Some(0), Some(5.0)).unwrap_err().to_string();
        assert!(
            e.starts_with("winch.turns_per_layer = 0: must be an integer"),
            "{e}"
        );
        for c in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = w.with_layers(Some(3), Some(c)).unwrap_err().to_string();
            assert!(e.starts_with("winch.cable_length = "), "{e}");
        }
        assert_eq!(w.with_layers(None, None).unwrap(), w);
        // The layers need the diameter to stay.
        let l = w.with_layers(Some(3), Some(5.0)).unwrap();
        assert!(l.with_cable_diameter(None).is_err());
        // Paid-out lengths outside [0, C]: errors, never NaN.
        for (len, needle) in [
            (
                5.5,
                "exceeds winch.cable_length = 5 m (the drum would be empty)",
            ),
            (-0.1, "is negative"),
            (f64::NAN, "is not a finite number"),
        ] {
            let e = l.drum_angle_at(len).unwrap_err().to_string();
            assert!(e.contains(needle), "{e}");
            assert!(l.payout_radius_at(len).is_err());
        }
        assert!(l.winding_angle(-1.0).is_err() && l.wound_length(f64::NAN).is_err());
    }

    proptest::proptest! {
        /// Φ is strictly increasing, Φ⁻¹(Φ(W)) = W, and the payout Φ(C) − Φ(C − L).
        #[test]
        fn winding_angle_is_monotone_and_invertible(
            r in 0.005f64..0.3,
            d in 1e-4f64..0.02,
            n in 1u32..200,
            w1 in 0.0f64..60.0,
            step in 1e-6f64..10.0,
            frac in 0.0f64..=1.0,
        ) {
            let w = Winch::new(r, 5.0, 0.0, None, None)
                .unwrap()
                .with_cable_diameter(Some(d))
                .unwrap()
                .with_layers(Some(n), Some(w1 + step))
                .unwrap();
            let (a, b) = (w.winding_angle(w1).unwrap(), w.winding_angle(w1 + step).unwrap());
            proptest::prop_assert!(a < b, "Φ({w1}) = {a} ≥ Φ({}) = {b}", w1 + step);
            // Slopes lie between 1/ρ of the highest and of the lowest layer touched.
            let rho0 = w.layer_payout_radius(0);
            proptest::prop_assert!((b - a) * rho0 <= step * (1.0 + 1e-9) + 1e-14 * b * rho0);
            for x in [w1, w1 + step] {
                let back = w.wound_length(w.winding_angle(x).unwrap()).unwrap();
                proptest::prop_assert!((back - x).abs() <= 1e-11 * (1.0 + x), "{x} → {back}");
            }
            let c = w1 + step;
            let l = frac * c;
            let expected = b - w.winding_angle(c - l).unwrap();
            let got = w.drum_angle_at(l).unwrap();
            proptest::prop_assert!((got - expected).abs() <= 1e-10 * (1.0 + b), "{got} {expected}");
        }
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

//! # Cable state: one cable at one pose
//!
//! What inverse kinematics finds for each cable (its vector from the platform attachment to the
//! frame anchor ℓ^i = **c**^i − **T ā**^i − **u**, eq. (6.2), its length l_i = ‖ℓ^i‖, eq. (6.4),
//! its unit vector and its attachment **a**^i = **T ā**^i, eq. (6.3)), what the swivel-pulley model
//! adds to it (Pott 2018), and the state of a straight cable. Shared by the straight-cable code
//! (module `inverse_kinematics`) and the pulley model (module `pulley`), which both fill it.
//!
//! ## References
//! - Thesis eqs. (6.2)–(6.4). Picard, Caro, Plestan & Claveau 2020, §2.
//! - Pott, *Cable-Driven Parallel Robots*, Springer 2018 (pulley kinematics).

use crate::{Cable, KinematicsError};
use nalgebra::Vector3;

/// Relative length below which a cable counts as degenerate (zero length).
pub(crate) const DEGENERATE_LENGTH: f64 = 1e-12;

/// The state of one cable at one pose, all in base coordinates.
///
/// `#[repr(C)]`: 13 `f64` in the declared order (the pulley block stores them four cables at
/// a time).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C)]
pub struct CableState {
    /// ℓ^i: from the platform attachment to the frame anchor, eq. (6.2); with a pulley, to the
    /// tangent point **C** (the free segment).
    pub vector: Vector3<f64>,
    /// l_i = ‖ℓ^i‖, eq. (6.4) (m); with a pulley the total length L = ρ β + l_f from the point
    /// **a** on the swivel axis.
    pub length: f64,
    /// ℓ^i / ‖ℓ^i‖: the direction in which the cable pulls the platform.
    pub unit: Vector3<f64>,
    /// **a**^i = **T**(φ) **ā**^i: attachment relative to the platform origin, eq. (6.3).
    pub attachment: Vector3<f64>,
    /// **u** + **a**^i: the attachment point in base coordinates.
    pub attachment_point: Vector3<f64>,
}

/// What the swivel-pulley model adds to a [`CableState`] (Pott 2018; module `pulley`).
///
/// `#[repr(C)]`: 11 `f64` in the declared order (the pulley block stores them four cables at
/// a time).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct PulleyState {
    /// l_f = ‖ℓ^i‖: the free (straight) length (m).
    pub free_length: f64,
    /// (cos γ, sin γ) of the swivel angle γ; γ itself is [`PulleyState::swivel_angle`]
    /// (computed on demand: an `atan2` the hot path does not need).
    pub swivel_direction: [f64; 2],
    /// Wrap angle β of the cable on the pulley (rad), in (0, 2π).
    pub wrap_angle: f64,
    /// The tangent point **C** where the cable leaves the pulley (m).
    pub exit_point: Vector3<f64>,
    /// e_n, the unit normal of the pulley plane: the direction in which the attachment moves
    /// when the pulley swivels.
    pub plane_normal: Vector3<f64>,
    /// s_C / s, the distances of the tangent point and of the attachment from the swivel axis.
    /// With it the free-segment direction varies as δu = −(1/l_f) (I − u uᵀ − (s_C/s) e_n e_nᵀ) δB
    /// (the pulley stiffness).
    pub swivel_ratio: f64,
}

impl PulleyState {
    /// Every field zero: the placeholder a buffer slot holds before its first write.
    pub(crate) const ZERO: Self = Self {
        free_length: 0.0,
        swivel_direction: [0.0; 2],
        wrap_angle: 0.0,
        exit_point: Vector3::new(0.0, 0.0, 0.0),
        plane_normal: Vector3::new(0.0, 0.0, 0.0),
        swivel_ratio: 0.0,
    };

    /// Swivel angle γ = atan2(p_y, p_x) of the pulley (rad, in (−π, π]).
    pub fn swivel_angle(&self) -> f64 {
        self.swivel_direction[1].atan2(self.swivel_direction[0])
    }
}

/// The state of straight cable `i` (eqs. (6.2)–(6.4)) from its attachment **a**^i and attachment
/// point; a length ≤ `threshold` (or NaN) is degenerate.
#[inline(always)]
pub(crate) fn straight_cable(
    cable: &Cable,
    attachment: Vector3<f64>,
    attachment_point: Vector3<f64>,
    threshold: f64,
    i: usize,
) -> Result<CableState, KinematicsError> {
    let vector = cable.frame - attachment_point;
    let length = vector.norm();
    // Written so that a NaN length also counts as degenerate.
    if length.is_nan() || length <= threshold {
        return Err(KinematicsError::DegenerateCable { cable: i, length });
    }
    Ok(CableState {
        vector,
        length,
        unit: vector / length,
        attachment,
        attachment_point,
    })
}

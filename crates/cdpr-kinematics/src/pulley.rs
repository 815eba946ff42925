//! # Swivel-pulley kinematics
//!
//! The cable model of WireCenter `.wcrfx` files and of Pott 2018 (§ on pulley kinematics): at
//! the frame the cable runs along the swivel axis **k** (third column of the pulley frame Q)
//! through the point **a** (the cable's `frame` point), travelling in the +**k** direction; there
//! it meets a pulley of radius ρ that swivels freely about that axis, wraps it by the angle β and
//! leaves it tangentially at **C** towards the platform attachment **B** = **r** + R **b̄**.
//!
//! In the pulley frame, with **d** = **B** − **a**:
//!
//! ```text
//!   p = Qᵀ d,  s = √(p_x² + p_y²),  h = p_z,  γ = atan2(p_y, p_x)      swivel angle
//!   x = s − ρ,  BM = √(x² + h²),  l_f = √(BM² − ρ²)                     free length
//!   cos β = (l_f h − ρ x) / BM²,  sin β = (l_f x + ρ h) / BM²,  β ∈ (0, 2π)   wrap angle
//!   L = ρ β + l_f                                                        cable length from a
//!   C = a + Q R_z(γ) (ρ (1 − cos β), 0, ρ sin β)                         tangent point
//!   u = (C − B) / l_f                                                    free-segment direction
//! ```
//!
//! With QᵀQ = I, u = −Q R_z(γ) (sin β, 0, cos β), which the block update computes. A frame that
//! is orthonormal only to ~10⁻⁷ (six-digit `.wcrfx` entries such as 0.707107) makes the two
//! differ by that much: such cables take WireLib's form, C from the pulley side and
//! u = (C − B) / ‖C − B‖ (`wirelib_direction`).
//!
//! M = **a** + ρ Q R_z(γ) e_x is the pulley centre and BM the distance from it to **B**. For
//! s ≥ ρ the wrap angle is the issue's / WireLib's β = acos(l_f / BM) + acos(h / BM); that form
//! takes the *unsigned* angle between MB and **k**, which mirrors the tangent point when
//! 0 < s < ρ (the attachment between the swivel axis and the pulley centre: with **B** on the
//! axis above **a** it gives β = 2 atan(ρ / h) where the cable runs straight, β = 0). The sine
//! and cosine above are those of the signed angle and hold for every s > 0.
//!
//! **Jacobian.** The free segment is tangent to the pulley and the pulley swivels freely, so the
//! rate of the total length is the attachment velocity along the free segment:
//! L̇ = −u · (ṙ + ω × R b̄) (the arc gained is the tangent-point motion along the free segment,
//! and the swivel moves C perpendicular to u). The wrench matrix therefore keeps its form,
//! column i = [u; (R b̄) × u] with the free-segment u, and W = Jᵀ with l̇ = −J q̇ exactly as for
//! straight cables (`tests/it/pulley.rs` checks it against finite differences of L).
//!
//! **Degenerate poses** (errors for that pose): **B** inside the pulley circle (BM ≤ ρ, no
//! tangent) and **B** on the swivel axis (s = 0, γ undefined).
//!
//! **CASPR.** A `base_rotating_pulley` (`fixed_location` F, `pulley_radius` R,
//! `cable_entry_vector` v) is the same pulley: its centre is F + R · (radial direction towards
//! **B**) and the cable enters at F travelling along v. So **a** = F, ρ = R and **k** = v / ‖v‖
//! ([`Pulley::from_axis`]); CASPR does not fix the zero of the swivel angle. CASPR's arc
//! length R · acos(n₁ · n₂) is limited to wraps ≤ π; the lengths agree whenever β ≤ π.
//!
//! ## References
//! - Pott, *Cable-Driven Parallel Robots: Theory and Application*, Springer 2018 (pulley
//!   kinematics; the `.wcrfx` model of WireLib's `doInverseKinematicsPulleyEx`).
//! - CASPR (Lau et al.), `BaseRotatingPulleyAttachment`.

use crate::cable_state::{CableState, PulleyState, straight_cable};
use crate::{Cable, KinematicsError, Pulley};
use nalgebra::{Matrix3, Vector3};

/// Largest deviation |QᵀQ − I| accepted for a pulley frame.
pub(crate) const ORTHONORMAL_TOLERANCE: f64 = 1e-6;

impl Pulley {
    /// A pulley of radius ρ = `radius` swivelling about `axis` (any non-zero length; the cable
    /// arrives travelling along +axis). Q = [e₁, k × e₁, k] with k = axis / ‖axis‖ and e₁ the
    /// base x axis projected onto the plane normal to k (the base y axis instead when k is within
    /// about 25° of x), so that the swivel angle γ is measured from e₁ about k.
    ///
    /// ```
    /// use cdpr_kinematics::Pulley;
    /// use nalgebra::Vector3;
    /// let p = Pulley::from_axis(0.1, Vector3::new(0.0, 0.0, 2.0));
    /// assert_eq!(p.axis(), Vector3::z());
    /// assert_eq!(p.orientation.column(0), Vector3::x());
    /// ```
    pub fn from_axis(radius: f64, axis: Vector3<f64>) -> Self {
        let k = axis / axis.norm();
        let reference = if k.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let e1 = (reference - k * k.dot(&reference)).normalize();
        let e2 = k.cross(&e1);
        Self {
            radius,
            orientation: Matrix3::from_columns(&[e1, e2, k]),
        }
    }

    /// The swivel axis **k**: the third column of Q.
    pub fn axis(&self) -> Vector3<f64> {
        self.orientation.column(2).into_owned()
    }

    /// Why these parameters cannot describe a pulley, if they cannot: radius not finite and > 0,
    /// Q not finite or not orthonormal (|QᵀQ − I| > 1e-6), or `planar` and the axis leaves the
    /// plane z = 0.
    pub(crate) fn defect(&self, planar: bool) -> Option<(&'static str, f64)> {
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return Some(("radius must be finite and > 0", self.radius));
        }
        if let Some(&x) = self.orientation.iter().find(|x| !x.is_finite()) {
            return Some(("orientation has a non-finite entry", x));
        }
        let k = self.axis();
        if k.norm() == 0.0 {
            return Some(("swivel axis (third column of the orientation) is zero", 0.0));
        }
        let deviation =
            (self.orientation.transpose() * self.orientation - Matrix3::identity()).amax();
        if deviation > ORTHONORMAL_TOLERANCE {
            return Some((
                "orientation is not orthonormal (largest entry of |QᵀQ − I|)",
                deviation,
            ));
        }
        if planar && k.z.abs() > ORTHONORMAL_TOLERANCE {
            return Some((
                "a planar robot's pulley axis must lie in the plane (z component)",
                k.z,
            ));
        }
        None
    }
}

/// Why a pulley cable has no defined geometry at a pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum PulleyDegeneracy {
    /// The platform attachment is inside (or on) the pulley circle: no tangent exists.
    InsidePulley,
    /// The platform attachment is on the swivel axis: the swivel angle is undefined.
    OnSwivelAxis,
}

impl std::fmt::Display for PulleyDegeneracy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::InsidePulley => "the platform attachment is inside the pulley circle",
            Self::OnSwivelAxis => "the platform attachment is on the swivel axis",
        })
    }
}

/// The geometry of one pulley cable at one pose (base coordinates).
#[cfg(test)]
#[derive(Debug, Clone, Copy)]
pub(crate) struct PulleyCable {
    /// Tangent point **C** where the cable leaves the pulley.
    pub exit_point: Vector3<f64>,
    /// **C** − **B**: the free segment from the attachment to the tangent point.
    pub free_vector: Vector3<f64>,
    /// (**C** − **B**) / l_f = −(sin β **r̂** + cos β **k**), unit by construction.
    pub unit: Vector3<f64>,
    /// l_f = ‖C − B‖.
    pub free_length: f64,
    /// L = ρ β + l_f.
    pub length: f64,
    /// (cos γ, sin γ).
    pub swivel_direction: [f64; 2],
    /// β (rad), in (0, 2π).
    pub wrap_angle: f64,
    /// e_n = Q R_z(γ) e_y: unit normal of the pulley plane.
    pub plane_normal: Vector3<f64>,
    /// s_C / s: distance of the tangent point from the swivel axis over that of the attachment.
    pub swivel_ratio: f64,
}

/// The module's equations for the cable through `a` over `pulley` to the attachment point `b`.
/// `threshold` (m) is the distance below which s or l_f count as zero.
///
/// No transcendental function is called: γ enters only through (cos γ, sin γ) = (p_x, p_y) / s,
/// β through its cosine and sine (module equations) and once as an angle, by [`wrap_angle`].
/// The free-segment direction is the pulley-plane tangent at **C**: with the radial direction
/// **r̂** = Q R_z(γ) e_x, **C** − **M** = ρ (−cos β **r̂** + sin β **k**) and
/// **B** − **M** = x **r̂** + h **k**, so (**C** − **B**) / l_f = −(sin β **r̂** + cos β **k**)
/// (substitute cos β and sin β and use l_f² = BM² − ρ²).
///
/// [`update_cables`] evaluates the same three stages ([`pulley_plane`], [`wrap_angle`],
/// [`tangent`]) a block of cables at a time, with bit-identical results (the tests compare the
/// two).
#[cfg(test)]
pub(crate) fn pulley_cable(
    a: &Vector3<f64>,
    pulley: &Pulley,
    b: &Vector3<f64>,
    threshold: f64,
) -> Result<PulleyCable, (PulleyDegeneracy, f64)> {
    let p = pulley.orientation.tr_mul(&(b - a));
    let plane = pulley_plane(p.x, p.y, p.z, pulley.radius);
    plane.degeneracy(threshold).map_or(Ok(()), Err)?;
    let wrap = wrap_angle(plane.cos_beta, plane.sin_beta);
    Ok(tangent(pulley, b, &plane, wrap))
}

/// The pulley-plane quantities of one cable (module equations): everything but β itself.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct PulleyPlane {
    s: f64,
    free2: f64,
    bm2: f64,
    free_length: f64,
    cos_beta: f64,
    sin_beta: f64,
    cos_gamma: f64,
    sin_gamma: f64,
    inv_s: f64,
}

/// From p = Qᵀ(**B** − **a**) and ρ: s, l_f, cos β, sin β, cos γ, sin γ (module equations).
/// Computed whatever the geometry (NaN or ∞ when degenerate; [`PulleyPlane::degeneracy`] tells).
#[inline(always)]
fn pulley_plane(px: f64, py: f64, h: f64, rho: f64) -> PulleyPlane {
    // √ rather than `hypot`: a tenth of the cost, and s² cannot overflow for finite robots.
    let s = (px * px + py * py).sqrt();
    let x = s - rho;
    let bm2 = x * x + h * h;
    let free2 = bm2 - rho * rho;
    let free_length = free2.sqrt();
    let inv_bm2 = 1.0 / bm2;
    let inv_s = 1.0 / s;
    PulleyPlane {
        s,
        free2,
        bm2,
        free_length,
        cos_beta: (free_length * h - rho * x) * inv_bm2,
        sin_beta: (free_length * x + rho * h) * inv_bm2,
        cos_gamma: px * inv_s,
        sin_gamma: py * inv_s,
        inv_s,
    }
}

impl PulleyPlane {
    /// [`degeneracy`] of this cable.
    #[cfg(test)]
    fn degeneracy(&self, threshold: f64) -> Option<(PulleyDegeneracy, f64)> {
        degeneracy(self.s, self.free2, self.bm2, threshold)
    }
}

/// The attachment on the swivel axis (s ≤ `threshold`) or inside the pulley
/// (l_f² ≤ `threshold`²), with the distance that vanished; NaN counts as degenerate. Reads only
/// s, l_f² and BM² of a [`PulleyPlane`] (so that the block update loads nothing else).
#[inline(always)]
fn degeneracy(s: f64, free2: f64, bm2: f64, threshold: f64) -> Option<(PulleyDegeneracy, f64)> {
    if s.is_nan() || s <= threshold {
        Some((PulleyDegeneracy::OnSwivelAxis, s))
    } else if free2.is_nan() || free2 <= threshold * threshold {
        Some((PulleyDegeneracy::InsidePulley, bm2.sqrt()))
    } else {
        None
    }
}

/// The error for pulley cable `i`, which [`degeneracy`] finds degenerate.
#[cold]
#[inline(never)]
fn degenerate_pulley(i: usize, s: f64, free2: f64, bm2: f64, threshold: f64) -> KinematicsError {
    let (reason, distance) = degeneracy(s, free2, bm2, threshold)
        .expect("called only for a degenerate cable (same test as `degeneracy`)");
    KinematicsError::DegeneratePulley {
        cable: i,
        reason,
        distance,
    }
}

/// The tangent point, the free segment and the length (module equations) from the pulley-plane
/// quantities and β, for one cable: the reference that [`update_cables`]'s stage 4 evaluates
/// a block at a time (the tests compare the two bit for bit).
#[cfg(test)]
fn tangent(pulley: &Pulley, b: &Vector3<f64>, plane: &PulleyPlane, wrap: f64) -> PulleyCable {
    let q = &pulley.orientation;
    let rho = pulley.radius;
    let (cos_beta, sin_beta) = (plane.cos_beta, plane.sin_beta);
    let (cos_gamma, sin_gamma) = (plane.cos_gamma, plane.sin_gamma);
    let radial = rho * (1.0 - cos_beta);
    let (e1, e2, k) = (q.column(0), q.column(1), q.column(2));
    // r̂ = Q R_z(γ) e_x = cos γ e₁ + sin γ e₂.
    let radial_direction = e1 * cos_gamma + e2 * sin_gamma;
    let unit = -(radial_direction * sin_beta + k * cos_beta);
    let free_vector = unit * plane.free_length;
    PulleyCable {
        exit_point: b + free_vector,
        free_vector,
        unit,
        free_length: plane.free_length,
        length: rho * wrap + plane.free_length,
        swivel_direction: [cos_gamma, sin_gamma],
        wrap_angle: wrap,
        plane_normal: e2 * cos_gamma - e1 * sin_gamma,
        swivel_ratio: radial * plane.inv_s,
    }
}

/// A robot's cables in blocks of [`BLOCK`], one array per coordinate, as [`update_cables`]
/// reads them (built once, with the robot; empty for a robot without pulleys).
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct PulleyBlocks {
    blocks: Vec<PulleyBlock>,
    /// The pulley cables whose frame Q is not orthonormal to rounding (|QᵀQ − I| above
    /// [`SKEWED_FRAME`]; e.g. the EXPO 2015 files' 0.707107 entries): their free-segment
    /// direction is WireLib's ([`wirelib_direction`]).
    skewed: Vec<usize>,
}

/// The deviation |QᵀQ − I| (largest entry) from which a pulley frame takes WireLib's
/// free-segment direction: far above the rounding of a computed rotation (≈ 10⁻¹⁶), far below
/// the 6·10⁻⁷ of six-digit frames.
const SKEWED_FRAME: f64 = 1e-12;

/// [`BLOCK`] cables: frame points **a**, platform attachments **b̄**, pulley frames Q (entry k
/// of Q in column-major order is `q[k]`) and radii ρ. Straight cables hold Q = I, ρ = 0 (their
/// pulley results are not used) and the lanes past the last cable zeros with Q = I.
#[derive(Debug, Clone, PartialEq)]
#[repr(align(32))]
struct PulleyBlock {
    frame: [[f64; BLOCK]; 3],
    platform: [[f64; BLOCK]; 3],
    q: [[f64; BLOCK]; 9],
    rho: [f64; BLOCK],
    /// Every lane holds a pulley cable (a full block): the AVX2 build may store its states
    /// four cables at a time.
    all_pulleys: bool,
}

impl PulleyBlocks {
    pub(crate) fn new(cables: &[Cable]) -> Self {
        if cables.iter().all(|c| c.pulley.is_none()) {
            return Self::default();
        }
        let skewed = cables
            .iter()
            .enumerate()
            .filter(|(_, c)| {
                c.pulley.as_ref().is_some_and(|p| {
                    let q = &p.orientation;
                    (q.transpose() * q - Matrix3::identity()).amax() > SKEWED_FRAME
                })
            })
            .map(|(i, _)| i)
            .collect();
        let blocks = cables
            .chunks(BLOCK)
            .map(|cables| {
                let mut block = PulleyBlock {
                    frame: [[0.0; BLOCK]; 3],
                    platform: [[0.0; BLOCK]; 3],
                    q: [[0.0; BLOCK]; 9],
                    rho: [0.0; BLOCK],
                    all_pulleys: cables.len() == BLOCK && cables.iter().all(|c| c.pulley.is_some()),
                };
                (block.q[0], block.q[4], block.q[8]) = ([1.0; BLOCK], [1.0; BLOCK], [1.0; BLOCK]);
                for (j, cable) in cables.iter().enumerate() {
                    for c in 0..3 {
                        block.frame[c][j] = cable.frame[c];
                        block.platform[c][j] = cable.platform[c];
                    }
                    let Some(pulley) = &cable.pulley else {
                        continue;
                    };
                    for (e, q) in pulley.orientation.iter().zip(block.q.iter_mut()) {
                        q[j] = *e;
                    }
                    block.rho[j] = pulley.radius;
                }
                block
            })
            .collect();
        Self { blocks, skewed }
    }
}

/// Cables per block in [`update_cables`].
const BLOCK: usize = 8;

/// The inverse kinematics of every cable of a robot with pulleys at the pose (`rotation`,
/// `position`), into `states` and `pulleys` (one per cable); straight cables as in
/// `inverse_kinematics`. The first degenerate cable (in index order) is the error.
///
/// Same equations and operations as [`pulley_cable`], reordered for speed: each stage runs
/// over a block of [`BLOCK`] cables before the next starts, so that the cables' long dependent
/// chains (two square roots, two divisions, the wrap angle) overlap instead of following each
/// other.
///
/// On x86-64 CPUs with AVX2 the same code is compiled a second time with AVX2 enabled (chosen at
/// run time), so that the compiler can run four lanes of a stage at once. No fused multiply–add
/// is enabled, so both builds round every operation the same way: identical results.
pub(crate) fn update_cables(
    cables: &[Cable],
    geometry: &PulleyBlocks,
    rotation: &Matrix3<f64>,
    position: &Vector3<f64>,
    threshold: f64,
    states: &mut [CableState],
    pulleys: &mut [Option<PulleyState>],
) -> Result<(), KinematicsError> {
    #[cfg(target_arch = "x86_64")]
    let done = if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, the only feature the function enables.
        unsafe {
            update_cables_avx2(
                cables, geometry, rotation, position, threshold, states, pulleys,
            )
        }
    } else {
        update_cables_portable::<false>(
            cables, geometry, rotation, position, threshold, states, pulleys,
        )
    };
    #[cfg(not(target_arch = "x86_64"))]
    let done = update_cables_portable::<false>(
        cables, geometry, rotation, position, threshold, states, pulleys,
    );
    done?;
    for &i in &geometry.skewed {
        if let (Some(pulley), Some(p)) = (&cables[i].pulley, &mut pulleys[i]) {
            wirelib_direction(&cables[i].frame, pulley, &mut states[i], p);
        }
    }
    Ok(())
}

/// The free segment of a cable whose pulley frame Q is not orthonormal to rounding, as WireLib
/// computes it (Pott 2018; `CKinematics::doInverseKinematicsPulleyEx`): the tangent point from
/// the pulley side, **C** = **a** + Q R_z(γ) (ρ (1 − cos β), 0, ρ sin β), and
/// u = (**C** − **B**) / ‖**C** − **B**‖. With QᵀQ = I this is the module's u; otherwise the two
/// differ by (I − QQᵀ) **d** / l_f and by ‖Q v‖ − 1 for a unit v (docs/robot-file.md). The
/// length L = ρ β + l_f is the same in both (WireLib's too). Only such cables come here: the
/// others keep the block update's result.
#[cold]
fn wirelib_direction(
    frame: &Vector3<f64>,
    pulley: &Pulley,
    state: &mut CableState,
    p: &mut PulleyState,
) {
    let (sin_beta, cos_beta) = p.wrap_angle.sin_cos();
    let [cos_gamma, sin_gamma] = p.swivel_direction;
    let rho = pulley.radius;
    let radial = rho * (1.0 - cos_beta);
    let local = Vector3::new(radial * cos_gamma, radial * sin_gamma, rho * sin_beta);
    let exit = frame + pulley.orientation * local;
    let vector = exit - state.attachment_point;
    state.unit = vector / vector.norm();
    state.vector = vector;
    p.exit_point = exit;
}

/// [`update_cables_portable`] compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn update_cables_avx2(
    cables: &[Cable],
    geometry: &PulleyBlocks,
    rotation: &Matrix3<f64>,
    position: &Vector3<f64>,
    threshold: f64,
    states: &mut [CableState],
    pulleys: &mut [Option<PulleyState>],
) -> Result<(), KinematicsError> {
    update_cables_portable::<true>(
        cables, geometry, rotation, position, threshold, states, pulleys,
    )
}

/// [`update_cables`] for any CPU. `WIDE` (set only by [`update_cables_avx2`], on a CPU with
/// AVX2) stores the states of a block whose lanes are all pulley cables four cables at a time
/// ([`store_states_avx2`]): the same values, moved by vector shuffles instead of one by one.
#[inline(always)]
pub(crate) fn update_cables_portable<const WIDE: bool>(
    cables: &[Cable],
    geometry: &PulleyBlocks,
    rotation: &Matrix3<f64>,
    position: &Vector3<f64>,
    threshold: f64,
    states: &mut [CableState],
    pulleys: &mut [Option<PulleyState>],
) -> Result<(), KinematicsError> {
    for (block, ((cables, states), pulleys)) in cables
        .chunks(BLOCK)
        .zip(states.chunks_mut(BLOCK))
        .zip(pulleys.chunks_mut(BLOCK))
        .enumerate()
    {
        let PulleyBlock {
            frame,
            platform,
            q,
            rho,
            all_pulleys,
        } = &geometry.blocks[block];
        // Stage 1: attachments R b̄ (as nalgebra's matrix–vector product: column by column),
        // attachment points B and p = Qᵀ(B − a) (entry k of Q column-major is q[k]).
        let r = rotation;
        let (mut attachment, mut point, mut p) =
            ([[0.0; BLOCK]; 3], [[0.0; BLOCK]; 3], [[0.0; BLOCK]; 3]);
        for j in 0..BLOCK {
            let mut d = [0.0; 3];
            for c in 0..3 {
                let a = r[(c, 0)] * platform[0][j]
                    + r[(c, 1)] * platform[1][j]
                    + r[(c, 2)] * platform[2][j];
                attachment[c][j] = a;
                point[c][j] = position[c] + a;
                d[c] = point[c][j] - frame[c][j];
            }
            for k in 0..3 {
                p[k][j] = q[3 * k][j] * d[0] + q[3 * k + 1][j] * d[1] + q[3 * k + 2][j] * d[2];
            }
        }
        // Stage 2: the pulley plane; stage 3: the wrap angle.
        // One array per quantity, each its own local (one block-sized struct was cleared by a
        // `memset` call on every pose).
        let (mut s, mut free2, mut bm2, mut free_length) =
            ([0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK]);
        let (mut cos_beta, mut sin_beta) = ([0.0; BLOCK], [0.0; BLOCK]);
        let (mut cos_gamma, mut sin_gamma, mut inv_s) = ([0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK]);
        for j in 0..BLOCK {
            let plane = pulley_plane(p[0][j], p[1][j], p[2][j], rho[j]);
            (s[j], free2[j], bm2[j], free_length[j]) =
                (plane.s, plane.free2, plane.bm2, plane.free_length);
            (cos_beta[j], sin_beta[j]) = (plane.cos_beta, plane.sin_beta);
            (cos_gamma[j], sin_gamma[j], inv_s[j]) =
                (plane.cos_gamma, plane.sin_gamma, plane.inv_s);
        }
        let mut wrap = [0.0; BLOCK];
        for (wrap, (&cos_beta, &sin_beta)) in wrap.iter_mut().zip(cos_beta.iter().zip(&sin_beta)) {
            *wrap = wrap_angle(cos_beta, sin_beta);
        }
        // Stage 4: the tangent point (as `tangent`, one coordinate at a time; Q's columns are
        // e₁ = q[0..3], e₂ = q[3..6], k = q[6..9]).
        let (mut unit, mut free_vector) = ([[0.0; BLOCK]; 3], [[0.0; BLOCK]; 3]);
        let (mut exit_point, mut normal) = ([[0.0; BLOCK]; 3], [[0.0; BLOCK]; 3]);
        let (mut length, mut ratio) = ([0.0; BLOCK], [0.0; BLOCK]);
        for j in 0..BLOCK {
            let (cos_beta, sin_beta) = (cos_beta[j], sin_beta[j]);
            let (cos_gamma, sin_gamma) = (cos_gamma[j], sin_gamma[j]);
            for c in 0..3 {
                let (e1, e2, k) = (q[c][j], q[3 + c][j], q[6 + c][j]);
                let radial_direction = e1 * cos_gamma + e2 * sin_gamma;
                let u = -(radial_direction * sin_beta + k * cos_beta);
                unit[c][j] = u;
                free_vector[c][j] = u * free_length[j];
                exit_point[c][j] = point[c][j] + free_vector[c][j];
                normal[c][j] = e2 * cos_gamma - e1 * sin_gamma;
            }
            length[j] = rho[j] * wrap[j] + free_length[j];
            ratio[j] = rho[j] * (1.0 - cos_beta) * inv_s[j];
        }
        // Stage 5: the states, in cable order (the first degenerate cable is the error).
        let lane = |v: &[[f64; BLOCK]; 3], j: usize| Vector3::new(v[0][j], v[1][j], v[2][j]);
        // Index loop over equal-length slices: no bounds checks, no iterator state.
        let n = cables.len();
        let (states, pulleys) = (&mut states[..n], &mut pulleys[..n]);
        #[cfg(target_arch = "x86_64")]
        if WIDE && *all_pulleys {
            for j in 0..BLOCK {
                let (s, free2) = (s[j], free2[j]);
                if s.is_nan() || s <= threshold || free2.is_nan() || free2 <= threshold * threshold
                {
                    return Err(degenerate_pulley(
                        block * BLOCK + j,
                        s,
                        free2,
                        bm2[j],
                        threshold,
                    ));
                }
            }
            let cable_fields = [
                &free_vector[0],
                &free_vector[1],
                &free_vector[2],
                &length,
                &unit[0],
                &unit[1],
                &unit[2],
                &attachment[0],
                &attachment[1],
                &attachment[2],
                &point[0],
                &point[1],
                &point[2],
            ];
            let pulley_fields = [
                &free_length,
                &cos_gamma,
                &sin_gamma,
                &wrap,
                &exit_point[0],
                &exit_point[1],
                &exit_point[2],
                &normal[0],
                &normal[1],
                &normal[2],
                &ratio,
            ];
            // SAFETY: `WIDE` is true only in `update_cables_avx2`, which runs on CPUs with
            // AVX2; the block is full (`all_pulleys`), so `states` and `pulleys` hold
            // `BLOCK` entries.
            unsafe { store_states_avx2(&cable_fields, &pulley_fields, states, pulleys) };
            continue;
        }
        for (j, cable) in cables.iter().enumerate() {
            let i = block * BLOCK + j;
            let (attachment, attachment_point) = (lane(&attachment, j), lane(&point, j));
            if cable.pulley.is_some() {
                let (s, free2) = (s[j], free2[j]);
                // `degeneracy`'s test inline, its answer (the error) out of line.
                if s.is_nan() || s <= threshold || free2.is_nan() || free2 <= threshold * threshold
                {
                    return Err(degenerate_pulley(i, s, free2, bm2[j], threshold));
                }
                states[j] = CableState {
                    vector: lane(&free_vector, j),
                    length: length[j],
                    unit: lane(&unit, j),
                    attachment,
                    attachment_point,
                };
                pulleys[j] = Some(PulleyState {
                    free_length: free_length[j],
                    swivel_direction: [cos_gamma[j], sin_gamma[j]],
                    wrap_angle: wrap[j],
                    exit_point: lane(&exit_point, j),
                    plane_normal: lane(&normal, j),
                    swivel_ratio: ratio[j],
                });
            } else {
                states[j] = straight_cable(cable, attachment, attachment_point, threshold, i)?;
                pulleys[j] = None;
            }
        }
    }
    Ok(())
}

/// Transposes four rows of four values (row r = field r of four cables) into four columns
/// (column j = four consecutive fields of cable j).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn transpose4(rows: [std::arch::x86_64::__m256d; 4]) -> [std::arch::x86_64::__m256d; 4] {
    use std::arch::x86_64::*;
    let t0 = _mm256_unpacklo_pd(rows[0], rows[1]);
    let t1 = _mm256_unpackhi_pd(rows[0], rows[1]);
    let t2 = _mm256_unpacklo_pd(rows[2], rows[3]);
    let t3 = _mm256_unpackhi_pd(rows[2], rows[3]);
    [
        _mm256_permute2f128_pd::<0x20>(t0, t2),
        _mm256_permute2f128_pd::<0x20>(t1, t3),
        _mm256_permute2f128_pd::<0x31>(t0, t2),
        _mm256_permute2f128_pd::<0x31>(t1, t3),
    ]
}

/// Writes the [`CableState`] and [`PulleyState`] of a full block of pulley cables from their
/// fields (one array per field, in the order the `#[repr(C)]` structs declare them), four
/// cables at a time: 4 × 4 transposes and whole-vector stores instead of one store per value.
/// Only data moves, so the states equal those of the one-by-one loop bit for bit.
///
/// # Safety
/// The CPU supports AVX2; `states` and `pulleys` hold at least [`BLOCK`] entries.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn store_states_avx2(
    cable_fields: &[&[f64; BLOCK]; 13],
    pulley_fields: &[&[f64; BLOCK]; 11],
    states: &mut [CableState],
    pulleys: &mut [Option<PulleyState>],
) {
    use std::arch::x86_64::*;
    const _: () = assert!(size_of::<CableState>() == 13 * size_of::<f64>());
    const _: () = assert!(size_of::<PulleyState>() == 11 * size_of::<f64>());
    assert!(states.len() >= BLOCK && pulleys.len() >= BLOCK);
    for half in [0, 4] {
        // SAFETY (loads): each field array holds BLOCK ≥ half + 4 values.
        let load = |f: &[f64; BLOCK]| unsafe { _mm256_loadu_pd(f.as_ptr().add(half)) };
        let rows = |fields: &[&[f64; BLOCK]], first: usize| {
            let row = |k: usize| {
                fields
                    .get(first + k)
                    .map_or(_mm256_setzero_pd(), |f| load(f))
            };
            [row(0), row(1), row(2), row(3)]
        };
        // CableState: fields 0–3, 4–7, 8–11 as vectors, field 12 alone.
        let cable_groups = [
            transpose4(rows(cable_fields, 0)),
            transpose4(rows(cable_fields, 4)),
            transpose4(rows(cable_fields, 8)),
        ];
        let last = cable_fields[12];
        for j in 0..4 {
            // SAFETY: `CableState` is `#[repr(C)]` with 13 `f64` (its `Vector3`s are
            // `#[repr(C)]` arrays): 13 contiguous values, written within the struct.
            unsafe {
                let out = (&raw mut states[half + j]).cast::<f64>();
                _mm256_storeu_pd(out, cable_groups[0][j]);
                _mm256_storeu_pd(out.add(4), cable_groups[1][j]);
                _mm256_storeu_pd(out.add(8), cable_groups[2][j]);
                *out.add(12) = last[half + j];
            }
        }
        // PulleyState: fields 0–3, 4–7 as vectors, 8–10 as two values and one.
        let pulley_groups = [
            transpose4(rows(pulley_fields, 0)),
            transpose4(rows(pulley_fields, 4)),
            transpose4(rows(pulley_fields, 8)),
        ];
        for j in 0..4 {
            let slot = pulleys[half + j].get_or_insert(PulleyState::ZERO);
            // SAFETY: `PulleyState` is `#[repr(C)]` with 11 `f64`: 11 contiguous values,
            // written within the struct.
            unsafe {
                let out = (slot as *mut PulleyState).cast::<f64>();
                _mm256_storeu_pd(out, pulley_groups[0][j]);
                _mm256_storeu_pd(out.add(4), pulley_groups[1][j]);
                let tail = pulley_groups[2][j];
                _mm_storeu_pd(out.add(8), _mm256_castpd256_pd128(tail));
                _mm_store_sd(out.add(10), _mm256_extractf128_pd::<1>(tail));
            }
        }
    }
}

/// (cos α_k, sin α_k) of the halving angles α_k = π/8, π/16, π/32, π/64 of [`wrap_angle`]'s
/// range reduction, correctly rounded (computed with 300-bit arithmetic; the unit test checks
/// them against the standard library).
const HALVING_ROTATIONS: [(f64, f64); 4] = [
    (0.9238795325112867, 0.3826834323650898),
    (0.9807852804032304, 0.19509032201612828),
    (0.9951847266721969, 0.0980171403295606),
    (0.9987954562051724, 0.049067674327418015),
];

/// π/64 split for exact multiples (Cody & Waite): `PI_64_HI` keeps 33 significant bits, so
/// K · `PI_64_HI` is exact for every integer K ≤ 2²⁰, and `PI_64_HI` + `PI_64_LO` = π/64 to
/// 2⁻¹⁰⁶ relative.
const PI_64_HI: f64 = 0.049087385210441425;
const PI_64_LO: f64 = 1.899093908283185e-12;

/// The angle β ∈ [0, 2π) of the unit vector (cos β, sin β), without a libm call, a table look-up
/// or a division, as one short chain of vector-friendly operations:
///
/// 1. fold into the first octant: (c, s) = (max, min)(|cos β|, |sin β|) = (cos φ, sin φ),
///    φ ∈ [0, π/4];
/// 2. halve the range four times: for α = π/8, π/16, π/32, π/64 rotate (c, s) by −α when the
///    rotated sine is ≥ 0 (so φ ≥ α) and count k += α / (π/64); the remainder
///    φ − kπ/64 ∈ [0, π/64] (up to rounding), and exactly 0 stays exactly 0;
/// 3. the arcsine of the remaining sine t by its Taylor series to t¹¹ (truncation below
///    2·10⁻¹⁹ rad for |t| ≤ sin(π/64)), evaluated by Estrin's scheme;
/// 4. unfold: β = K π/64 ± asin t with the integer K = (octant offset) ± k, and K π/64 summed
///    in two parts ([`PI_64_HI`] exact).
///
/// Absolute error at most 0.43 units in the last place of 2π (3.8·10⁻¹⁶ rad) over 10⁶ random
/// unit vectors against 200-bit values; the unit tests compare with `f64::atan2` and with
/// correctly rounded values.
#[inline]
pub(crate) fn wrap_angle(cos_beta: f64, sin_beta: f64) -> f64 {
    let (ac, as_) = (cos_beta.abs(), sin_beta.abs());
    let steep = as_ > ac;
    // Selects only (no `f64::max`, no loop-carried branch), so that a block of cables
    // vectorises.
    let (c, s) = if steep { (as_, ac) } else { (ac, as_) };
    let [r1, r2, r3, r4] = HALVING_ROTATIONS;
    let (c, s, k) = halve(c, s, 0.0, r1, 8.0);
    let (c, s, k) = halve(c, s, k, r2, 4.0);
    let (c, s, k) = halve(c, s, k, r3, 2.0);
    let (_, s, k) = halve(c, s, k, r4, 1.0);
    let t = s;
    let t2 = t * t;
    let t4 = t2 * t2;
    let t8 = t4 * t4;
    let low = 1.0 + t2 * (1.0 / 6.0);
    let mid = 3.0 / 40.0 + t2 * (5.0 / 112.0);
    let high = 35.0 / 1152.0 + t2 * (63.0 / 2816.0);
    let series = (low + t4 * mid) + t8 * high;
    // β = offset ± φ in units of π/64: steep octants are π/2 − φ, cos β < 0 mirrors about π/2
    // (π − ·), sin β < 0 about π (2π − ·).
    let (mut offset, mut sign) = if steep { (32.0, -1.0) } else { (0.0, 1.0) };
    if cos_beta < 0.0 {
        (offset, sign) = (64.0 - offset, -sign);
    }
    if sin_beta < 0.0 {
        (offset, sign) = (128.0 - offset, -sign);
    }
    let multiple = offset + sign * k;
    multiple * PI_64_HI + (multiple * PI_64_LO + sign * t * series)
}

/// One range-halving step of [`wrap_angle`]: (c, s) rotated by −α when the rotated sine is
/// ≥ 0, with `weight` = α / (π/64) added to the count k.
#[inline(always)]
fn halve(
    c: f64,
    s: f64,
    k: f64,
    (cos_alpha, sin_alpha): (f64, f64),
    weight: f64,
) -> (f64, f64, f64) {
    let rotated_s = s * cos_alpha - c * sin_alpha;
    let rotated_c = c * cos_alpha + s * sin_alpha;
    let take = rotated_s >= 0.0;
    (
        if take { rotated_c } else { c },
        if take { rotated_s } else { s },
        k + if take { weight } else { 0.0 },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::TAU;

    fn z_pulley(rho: f64) -> Pulley {
        Pulley::from_axis(rho, Vector3::z())
    }

    #[test]
    fn attachment_straight_along_the_axis_has_no_wrap() {
        // B just off the axis above a: the cable runs (almost) straight, L → h.
        let c = pulley_cable(
            &Vector3::zeros(),
            &z_pulley(0.1),
            &Vector3::new(1e-9, 0.0, 2.0),
            1e-12,
        )
        .unwrap();
        assert!(c.wrap_angle < 1e-8, "β = {}", c.wrap_angle);
        assert_relative_eq!(c.length, 2.0, epsilon = 1e-8);
    }

    #[test]
    fn horizontal_attachment_by_hand() {
        // a = 0, k = z, ρ = 1, B = (3, 0, 0): M = (1, 0, 0), BM = 2, l_f = √3,
        // tangent point at 60° past the top of the pulley: β = π/2 + π/6 = 2π/3,
        // C = M + (−cos β, 0, sin β) = (1.5, 0, √3/2).
        let c = pulley_cable(
            &Vector3::zeros(),
            &z_pulley(1.0),
            &Vector3::new(3.0, 0.0, 0.0),
            1e-12,
        )
        .unwrap();
        assert_relative_eq!(
            c.wrap_angle,
            2.0 * std::f64::consts::FRAC_PI_3,
            epsilon = 1e-15
        );
        assert_relative_eq!(c.free_length, 3f64.sqrt(), epsilon = 1e-15);
        assert_relative_eq!(
            c.length,
            2.0 * std::f64::consts::FRAC_PI_3 + 3f64.sqrt(),
            epsilon = 1e-15
        );
        assert_relative_eq!(
            c.exit_point,
            Vector3::new(1.5, 0.0, 3f64.sqrt() / 2.0),
            epsilon = 1e-15
        );
        assert_eq!(c.swivel_direction, [1.0, 0.0]);
    }

    #[test]
    fn wrap_matches_the_issue_formula_when_s_at_least_rho() {
        let pulley = Pulley::from_axis(0.2, Vector3::new(0.3, -0.4, 1.0));
        let a = Vector3::new(1.0, 2.0, 3.0);
        for b in [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(2.5, 2.0, 3.0),
            Vector3::new(1.0, 4.0, 5.0),
            Vector3::new(-1.0, 2.0, 1.0),
        ] {
            let c = pulley_cable(&a, &pulley, &b, 1e-12).unwrap();
            let p = pulley.orientation.transpose() * (b - a);
            let (s, h) = (p.x.hypot(p.y), p.z);
            assert!(s >= pulley.radius);
            let bm = ((s - pulley.radius).powi(2) + h * h).sqrt();
            let lf = (bm * bm - pulley.radius.powi(2)).sqrt();
            let beta = (lf / bm).acos() + (h / bm).acos();
            assert_relative_eq!(c.wrap_angle, beta, epsilon = 1e-12);
            assert_relative_eq!(
                c.swivel_direction[1].atan2(c.swivel_direction[0]),
                p.y.atan2(p.x),
                epsilon = 1e-15
            );
            // C is on the pulley circle and the free segment is tangent there.
            let gamma_dir = pulley.orientation * Vector3::new(p.x / s, p.y / s, 0.0);
            let m = a + pulley.radius * gamma_dir;
            assert_relative_eq!((c.exit_point - m).norm(), pulley.radius, epsilon = 1e-12);
            assert!((c.exit_point - m).dot(&c.free_vector).abs() < 1e-12);
            assert_relative_eq!(c.free_vector.norm(), c.free_length, epsilon = 1e-12);
        }
    }

    #[test]
    fn wrap_beyond_half_turn_below_the_pulley() {
        // B far below a, between the axis and the pulley centre: the cable runs over the top and
        // down the far side, leaving just below the centre's height (β a little over π).
        let c = pulley_cable(
            &Vector3::zeros(),
            &z_pulley(1.0),
            &Vector3::new(0.5, 0.0, -5.0),
            1e-12,
        )
        .unwrap();
        assert!(c.wrap_angle > std::f64::consts::PI && c.wrap_angle < 1.5 * std::f64::consts::PI);
        assert!(
            c.exit_point.x > 1.9,
            "leaves on the far side: {}",
            c.exit_point
        );
        let m = Vector3::new(1.0, 0.0, 0.0);
        assert_relative_eq!((c.exit_point - m).norm(), 1.0, epsilon = 1e-14);
        assert!((c.exit_point - m).dot(&c.free_vector).abs() < 1e-13);
    }

    /// 11 cables (a full block and part of a second), tilted pulleys of several radii, two
    /// straight cables among them.
    fn mixed_robot() -> crate::Robot {
        robot_with(11, |i| i % 5 != 3)
    }

    /// `cables` cables on tilted pulleys of several radii, those where `has_pulley` is false
    /// straight.
    fn robot_with(cables: usize, has_pulley: impl Fn(usize) -> bool) -> crate::Robot {
        let cables = (0..cables)
            .map(|i| {
                let t = i as f64;
                let pulley = has_pulley(i).then(|| {
                    let down = if i % 4 == 0 { -1.0 } else { 1.0 };
                    Pulley::from_axis(
                        0.02 + 0.01 * t,
                        Vector3::new(0.2 * t.sin(), 0.3 * t.cos(), down),
                    )
                });
                Cable {
                    frame: Vector3::new(2.0 * (1.3 * t).cos(), 2.0 * (1.3 * t).sin(), 1.5),
                    platform: Vector3::new(0.1 * (2.1 * t).cos(), 0.1 * (2.1 * t).sin(), 0.05),
                    pulley,
                }
            })
            .collect();
        crate::Robot::new(crate::MotionPattern::Spatial, cables).unwrap()
    }

    /// The block update (AVX2 build where the CPU has it), its portable build and the per-cable
    /// equations [`pulley_cable`] give the same bits: with straight cables and a part block
    /// (stored one cable at a time), and with two full blocks of pulley cables (stored four at
    /// a time by the AVX2 build).
    #[test]
    fn block_update_equals_the_cable_equations_bit_for_bit() {
        assert_eq!(block_update_pulley_cables(&mixed_robot()), 200 * 9);
        let full = robot_with(16, |_| true);
        assert!(full.pulley_blocks().blocks.iter().all(|b| b.all_pulleys));
        assert_eq!(block_update_pulley_cables(&full), 200 * 16);
    }

    /// Compares the three paths at 200 poses; returns the pulley cables compared.
    fn block_update_pulley_cables(robot: &crate::Robot) -> usize {
        use crate::Pose;
        use nalgebra::Rotation3;
        let n = robot.cable_count();
        let mut pulley_cables = 0;
        for k in 0..200 {
            let t = k as f64;
            let pose = Pose::new(
                Vector3::new(
                    0.4 * (0.7 * t).sin(),
                    0.4 * (1.1 * t).cos(),
                    0.3 * (0.3 * t).sin(),
                ),
                Rotation3::new(Vector3::new(
                    0.3 * t.sin(),
                    0.2 * t.cos(),
                    0.5 * (0.4 * t).sin(),
                )),
            );
            let kin = robot.inverse_kinematics(&pose).unwrap();
            let threshold = crate::cable_state::DEGENERATE_LENGTH
                * robot.length_scale().max(pose.position.norm());
            let (mut states, mut pulleys) = (vec![CableState::default(); n], vec![None; n]);
            update_cables_portable::<false>(
                robot.cables(),
                robot.pulley_blocks(),
                pose.rotation.matrix(),
                &pose.position,
                threshold,
                &mut states,
                &mut pulleys,
            )
            .unwrap();
            assert_eq!(kin.cables(), &states[..]);
            for (i, (cable, state)) in robot.cables().iter().zip(&states).enumerate() {
                assert_eq!(kin.pulley(i), pulleys[i].as_ref());
                let attachment = pose.rotation * cable.platform;
                assert_eq!(state.attachment, attachment);
                assert_eq!(state.attachment_point, pose.position + attachment);
                let Some(pulley) = &cable.pulley else {
                    assert!(pulleys[i].is_none());
                    let straight = cable.frame - (pose.position + attachment);
                    assert_eq!((state.vector, state.length), (straight, straight.norm()));
                    assert_eq!(state.unit, straight / straight.norm());
                    continue;
                };
                pulley_cables += 1;
                let c =
                    pulley_cable(&cable.frame, pulley, &state.attachment_point, threshold).unwrap();
                let p = pulleys[i].unwrap();
                assert_eq!(
                    (state.length, state.unit, state.vector),
                    (c.length, c.unit, c.free_vector)
                );
                assert_eq!(
                    (
                        p.free_length,
                        p.swivel_direction,
                        p.wrap_angle,
                        p.exit_point
                    ),
                    (
                        c.free_length,
                        c.swivel_direction,
                        c.wrap_angle,
                        c.exit_point
                    )
                );
                assert_eq!(
                    (p.plane_normal, p.swivel_ratio),
                    (c.plane_normal, c.swivel_ratio)
                );
            }
        }
        pulley_cables
    }

    /// The first degenerate cable in index order is the error, in either block.
    #[test]
    fn block_update_reports_the_first_degenerate_cable() {
        use crate::{KinematicsError, Pose};
        // Mixed blocks (one cable at a time) and full pulley blocks (four at a time in the
        // AVX2 build).
        let (mixed, full) = (mixed_robot(), robot_with(16, |_| true));
        let cases = [0, 3, 9, 10].map(|i| (&mixed, i));
        for (robot, i) in cases.into_iter().chain([0, 5, 8, 15].map(|i| (&full, i))) {
            // Put the platform origin (attachment offset undone) on cable i's frame point.
            let cable = &robot.cables()[i];
            let pose = Pose::new(
                cable.frame - cable.platform,
                nalgebra::Rotation3::identity(),
            );
            match robot.inverse_kinematics(&pose).unwrap_err() {
                KinematicsError::DegeneratePulley { cable, reason, .. } => {
                    assert_eq!((cable, reason), (i, PulleyDegeneracy::OnSwivelAxis));
                }
                KinematicsError::DegenerateCable { cable, .. } => assert_eq!((cable, i), (3, 3)),
                e => panic!("{e}"),
            }
        }
    }

    #[test]
    fn halving_rotations_and_pi_split_are_correctly_rounded() {
        for (k, &(c, s)) in HALVING_ROTATIONS.iter().enumerate() {
            let alpha = std::f64::consts::PI / (8 << k) as f64;
            assert!((c - alpha.cos()).abs() <= f64::EPSILON, "cos α_{k}");
            assert!((s - alpha.sin()).abs() <= f64::EPSILON * s, "sin α_{k}");
        }
        // The high part has 33 significant bits and the two parts sum to π/64.
        assert_eq!(PI_64_HI.to_bits() & ((1 << 20) - 1), 0);
        assert_eq!(PI_64_HI + PI_64_LO, std::f64::consts::PI / 64.0);
    }

    /// `wrap_angle` against correctly rounded values of atan2 (mapped to [0, 2π)) computed with
    /// 400-bit arithmetic (mpmath), for unit vectors spread over the circle, at the halving
    /// angles and next to 0 ≡ 2π: within one unit in the last place of 2π (a sweep of 10⁶
    /// random angles against 200-bit values found at most 0.43 of one).
    #[test]
    fn wrap_angle_equals_high_precision_values() {
        use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_4};
        let cases: [(f64, f64, f64); 16] = [
            (1.0, 1e-300, 1e-300),
            (1.0, 1e-12, 1e-12),
            (0.955336489125606, 0.29552020666133955, 0.3),
            (
                0.9987954562051724,
                0.049067674327418015,
                0.04908738521234052,
            ),
            (0.9238795325112864, 0.38268343236509067, 0.39269908169872514),
            (FRAC_1_SQRT_2, 0.7071067811865475, FRAC_PI_4),
            (0.5403023058681398, 0.8414709848078965, 1.0),
            (-0.4161468365471424, 0.9092974268256817, 2.0),
            (-0.5000000000000002, 0.8660254037844385, 2.0943951023931957),
            (-1.0, 1.0000013073871702e-10, 3.141592653489793),
            (-0.9364566872907963, -0.35078322768961984, 3.5),
            (-0.6536436208636119, -0.7568024953079282, 4.0),
            (-1.8369701987210297e-16, -1.0, 4.71238898038469),
            (0.70866977429126, -0.7055403255703919, 5.5),
            (0.960170286650366, -0.27941549819892586, 6.0),
            (1.0, -1.0060909078594362e-13, 6.283185307179486),
        ];
        let ulp_tau = 4.0 * f64::EPSILON;
        for (c, s, exact) in cases {
            let beta = wrap_angle(c, s);
            assert!(
                (beta - exact).abs() <= ulp_tau,
                "({c}, {s}): {beta} vs {exact}"
            );
        }
    }

    /// `wrap_angle` against `f64::atan2` (mapped to [0, 2π)) around the whole circle, at the
    /// octant and table boundaries and at ±0: within 4 units in the last place of 2π.
    #[test]
    fn wrap_angle_equals_atan2() {
        let reference = |c: f64, s: f64| {
            let a = s.atan2(c);
            if a < 0.0 { a + TAU } else { a }
        };
        let mut worst = 0.0f64;
        let mut check = |angle: f64| {
            let (s, c) = angle.sin_cos();
            let (ours, exact) = (wrap_angle(c, s), reference(c, s));
            // Near 0 ≡ 2π either representative is the same angle.
            let error = (ours - exact).abs().min(TAU - (ours - exact).abs());
            worst = worst.max(error);
            assert!(
                error <= 4.0 * f64::EPSILON * TAU,
                "β = {angle}: {ours} vs {exact}"
            );
        };
        let n = 200_000;
        for i in 0..n {
            check(TAU * (i as f64 + 0.37) / n as f64);
        }
        for k in 0..=64 {
            let edge = k as f64 * std::f64::consts::PI / 64.0;
            for d in [-1e-9, -1e-15, 0.0, 1e-15, 1e-9] {
                check(edge + d);
            }
        }
        assert_eq!(wrap_angle(1.0, 0.0), 0.0);
        assert_eq!(wrap_angle(1.0, -0.0), 0.0);
        assert!(worst < 4.0 * f64::EPSILON * TAU);
    }

    #[test]
    fn degenerate_geometry_is_reported() {
        let p = z_pulley(0.5);
        let a = Vector3::zeros();
        assert_eq!(
            pulley_cable(&a, &p, &Vector3::new(0.0, 0.0, 1.0), 1e-12)
                .unwrap_err()
                .0,
            PulleyDegeneracy::OnSwivelAxis
        );
        // Inside the pulley: 0.1 from the centre (0.5, 0, 0).
        assert_eq!(
            pulley_cable(&a, &p, &Vector3::new(0.6, 0.0, 0.0), 1e-12)
                .unwrap_err()
                .0,
            PulleyDegeneracy::InsidePulley
        );
        assert!(pulley_cable(&a, &p, &Vector3::new(1.1, 0.0, 0.0), 1e-12).is_ok());
        assert!(pulley_cable(&a, &p, &Vector3::new(f64::NAN, 0.0, 0.0), 1e-12).is_err());
    }

    #[test]
    fn pulley_defects() {
        let planar = false;
        assert!(z_pulley(0.1).defect(planar).is_none());
        assert!(z_pulley(0.0).defect(planar).is_some());
        assert!(z_pulley(f64::INFINITY).defect(planar).is_some());
        let mut p = z_pulley(0.1);
        p.orientation[(0, 0)] = 2.0;
        assert!(p.defect(planar).is_some());
        p.orientation = Matrix3::zeros();
        assert!(p.defect(planar).is_some());
        assert!(z_pulley(0.1).defect(true).is_some());
        assert!(Pulley::from_axis(0.1, Vector3::x()).defect(true).is_none());
    }

    #[test]
    fn from_axis_is_orthonormal_with_the_axis_last() {
        for axis in [
            Vector3::x(),
            Vector3::new(1.0, 2.0, -3.0),
            -Vector3::z(),
            Vector3::y(),
        ] {
            let p = Pulley::from_axis(0.1, axis);
            assert_relative_eq!(p.axis(), axis.normalize(), epsilon = 1e-15);
            let q = p.orientation;
            assert!((q.transpose() * q - Matrix3::identity()).amax() < 1e-15);
            assert_relative_eq!(q.determinant(), 1.0, epsilon = 1e-15);
        }
    }
}

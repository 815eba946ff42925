//! # Workspace criteria
//!
//! A pose belongs to a workspace when every criterion of a list holds (a logical AND). The
//! thesis' constant-orientation workspace (6.23) is `[TensionFeasible, MinCableLength]`, plus
//! `MinJacobianDeterminant` for the 3-cable robot; CASPR's wrench-closure workspace is
//! `[WrenchClosure]`. Further criteria (stiffness floor, user closures) compose the same way.
//!
//! ## References
//! - Thesis eqs. (6.21) tension limits, (6.22) minimum cable length, (6.23) constant
//!   orientation workspace, (6.24) Jacobian determinant floor.
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4): stiffness K = Kp + Ka.
//! - Krut, Company & Pierrot 2004, eq. (19): maximum isotropic force. Guay, Cardou, Cruz-Ruiz, Caro (2014): capacity
//!   margin.
//! - Perreault, Cardou, Gosselin & Otis (2010), "Geometric determination of the
//!   interference-free constant-orientation workspace of parallel cable-driven mechanisms",
//!   ASME J. Mechanisms Robotics 2(3): cable–cable and cable–platform interference.
//! - Gouttefarde & Gosselin (2006), "Analysis of the wrench-closure workspace of planar parallel
//!   cable-driven mechanisms", IEEE T-RO 22(3): W positively spans R^DOF.

use cdpr_kinematics::{ConvexPolyhedron, Pose, PoseKinematics};
use cdpr_polytope::RequiredWrenchSet;
use cdpr_tension::Method;
use nalgebra::{DMatrix, DVector};
use std::fmt;
use std::sync::Arc;

/// One condition a pose must satisfy to belong to the workspace.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum Criterion {
    /// Eq. (6.21): some tensions t_min ≤ t ≤ t_max balance `wrench` (W t + w_ext = 0), as
    /// decided by the tension distribution `method` (`Exact` for n = DOF, `L1`, `L2`, `Pinv`,
    /// `ClosedForm`, …). Methods differ: `Pinv` (eq. (6.14), no null-space term) rejects poses
    /// where other feasible tensions exist (thesis Fig. 6.3).
    TensionFeasible {
        /// Tension distribution method.
        method: Method,
        /// External wrench w_ext on the platform, length DOF (thesis Table 6.3 loads).
        wrench: DVector<f64>,
    },
    /// Eq. (6.22): every cable length l_i ≥ l_min.
    MinCableLength(f64),
    /// Eq. (6.24), in absolute value: |det J| ≥ D_min when n = DOF (J = Wᵀ, so det J = det W);
    /// always satisfied when n ≠ DOF.
    MinJacobianDeterminant(f64),
    /// Wrench closure: the columns of W positively span R^DOF, i.e. rank W = DOF and
    /// W t = 0 for some t > 0 (componentwise). Needs n ≥ DOF + 1.
    WrenchClosure,
    /// Capacity margin (Guay et al. 2014, via `cdpr-polytope`): every external wrench of
    /// `required` (e.g. gravity plus a ball of disturbances) can be balanced with tensions in
    /// bounds, with margin at least `min_margin` (wrench units; 0 = just balanced).
    CapacityMargin {
        /// The set of external wrenches w_ext to balance.
        required: RequiredWrenchSet,
        /// Floor on the margin (≥ 0 in the usual definition of the workspace).
        min_margin: f64,
    },
    /// Maximum isotropic force (Krut, Company & Pierrot 2004, eq. (19), via `cdpr-polytope`): the platform resists a
    /// force of `min` in every direction (planar/spatial robots: at zero moment).
    IsotropicForce {
        /// Floor on the isotropic force (force units).
        min: f64,
    },
    /// Maximum isotropic force on top of a constant external wrench (Krut, Company & Pierrot 2004, eq. (19) with the
    /// facets shifted by `wrench`, via [`cdpr_polytope::isotropic_force_of_under_load`]): the
    /// platform, already loaded by `wrench` (its weight, say), resists an extra force of `min`
    /// (N) in every direction (planar/spatial robots: at zero extra moment).
    IsotropicForceUnderLoad {
        /// Floor on the extra force (N).
        min: f64,
        /// The external wrench w_ext the force is added to (N, N·m), length DOF.
        wrench: DVector<f64>,
    },
    /// Stiffness floor in separate units: for every small displacement δ = (δp, δθ),
    /// δᵀ K δ ≥ k_t ‖δp‖² + k_r ‖δθ‖², i.e. sym(K) − diag(k_t I, k_r I) is positive
    /// semidefinite (K = Kp + Ka, Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4)). The eigenvalues of that matrix mix
    /// units but their sign does not (Sylvester's law of inertia), so `translational` (N/m) and
    /// `rotational` (N·m/rad) keep their own units. Robots without orientation ignore
    /// `rotational`. Tensions as for [`Criterion::Stiffness`].
    StiffnessFloor {
        /// k_t: translational stiffness floor (N/m).
        translational: f64,
        /// k_r: rotational stiffness floor (N·m/rad).
        rotational: f64,
    },
    /// Stiffness floor: the smallest eigenvalue of the symmetric part of K = Kp + Ka
    /// (Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4)) is at least `min_eigenvalue`. For planar and spatial robots K
    /// mixes N/m, N and N·m/rad: the floor compares them as plain SI numbers (a length scale
    /// of 1 m); [`Criterion::StiffnessFloor`] keeps the units apart.
    /// K uses the tensions found by the first [`Criterion::TensionFeasible`] criterion of the
    /// list (which must exist) and the axial stiffness given with
    /// [`crate::PoseEvaluator::with_axial_stiffness`]. A pose without feasible tensions fails.
    Stiffness {
        /// Floor on λ_min((K + Kᵀ)/2).
        min_eigenvalue: f64,
    },
    /// No interference (Perreault et al. 2010; `cdpr_kinematics::interference`): every pair of
    /// cables (free segments) at least `min_distance` apart (m; with 0, the cables must not
    /// touch: distance > 10⁻¹² × the robot's size), pairs sharing an anchor or attachment left
    /// out; and, with a `platform` shape (convex polyhedron in platform coordinates), no cable
    /// passes through the platform's interior.
    Interference {
        /// Clearance D between cables (m), ≥ 0.
        min_distance: f64,
        /// The platform, if its shape is known.
        platform: Option<Arc<ConvexPolyhedron>>,
    },
    /// A user-supplied test (e.g. a collision check). It must be deterministic.
    Custom(CustomCriterion),
}

impl Criterion {
    /// A short name, for messages.
    pub fn name(&self) -> &'static str {
        match self {
            Self::TensionFeasible { .. } => "tension-feasible",
            Self::MinCableLength(_) => "min-cable-length",
            Self::MinJacobianDeterminant(_) => "min-jacobian-determinant",
            Self::WrenchClosure => "wrench-closure",
            Self::CapacityMargin { .. } => "capacity-margin",
            Self::IsotropicForce { .. } => "isotropic-force",
            Self::Stiffness { .. } => "stiffness",
            Self::Interference { .. } => "interference",
            Self::IsotropicForceUnderLoad { .. } => "isotropic-force-under-load",
            Self::StiffnessFloor { .. } => "stiffness-floor",
            Self::Custom(c) => c.name,
        }
    }

    /// Relative cost, used to evaluate cheap criteria first (the result does not depend on it).
    pub(crate) fn cost(&self) -> u8 {
        match self {
            Self::MinCableLength(_) => 0,
            Self::MinJacobianDeterminant(_) => 1,
            Self::Custom(_) | Self::Interference { .. } => 2,
            Self::WrenchClosure => 3,
            Self::TensionFeasible { .. } => 4,
            Self::CapacityMargin { .. }
            | Self::IsotropicForce { .. }
            | Self::IsotropicForceUnderLoad { .. } => 5,
            Self::Stiffness { .. } | Self::StiffnessFloor { .. } => 6,
        }
    }
}

/// What a [`CustomCriterion`] sees of a pose: the pose, its inverse kinematics and W.
#[derive(Debug, Clone, Copy)]
pub struct PoseContext<'a> {
    /// The pose being tested.
    pub pose: &'a Pose,
    /// Cable vectors, lengths and unit vectors at the pose.
    pub kinematics: &'a PoseKinematics,
    /// The DOF × n wrench matrix W at the pose.
    pub wrench_matrix: &'a DMatrix<f64>,
}

/// The test function of a [`CustomCriterion`].
pub type CustomTest = dyn Fn(&PoseContext<'_>) -> bool + Send + Sync;

/// A named user test, shared between evaluator clones.
#[derive(Clone)]
pub struct CustomCriterion {
    /// Name shown in messages.
    pub name: &'static str,
    /// The test: `true` when the pose satisfies the criterion.
    pub test: Arc<CustomTest>,
}

impl CustomCriterion {
    /// A named criterion from a closure.
    ///
    /// ```
    /// use cdpr_workspace::{Criterion, CustomCriterion};
    /// // Keep the platform above the floor y = −0.4.
    /// let above = Criterion::Custom(CustomCriterion::new("above-floor", |ctx| ctx.pose.position.y > -0.4));
    /// assert_eq!(above.name(), "above-floor");
    /// ```
    pub fn new(
        name: &'static str,
        test: impl Fn(&PoseContext<'_>) -> bool + Send + Sync + 'static,
    ) -> Self {
        Self {
            name,
            test: Arc::new(test),
        }
    }
}

impl fmt::Debug for CustomCriterion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CustomCriterion")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

/// det W for a square W (n = DOF ∈ {2, 3, 6}) without allocation; eq. (6.24) uses det J = det W.
///
/// The 2 × 2 and 3 × 3 cases read the column-major slice directly: copying into a fixed-size
/// matrix first goes through `memcpy`, whose wide stores stall the scalar loads that follow
/// (a tenth of the 3-cable grid's time).
#[inline]
pub(crate) fn square_determinant(w: &DMatrix<f64>) -> f64 {
    match (w.shape(), w.as_slice()) {
        ((1, 1), &[a]) => a,
        ((2, 2), &[a, c, b, d]) => a * d - b * c,
        // Columns (a, b, c): det = a · (b × c), expanded along the first column.
        ((3, 3), &[a0, a1, a2, b0, b1, b2, c0, c1, c2]) => {
            a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0) + a2 * (b0 * c1 - b1 * c0)
        }
        ((6, 6), s) => nalgebra::Matrix6::from_column_slice(s).determinant(),
        _ => w.clone().determinant(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn determinants_by_hand() {
        let w2 = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(square_determinant(&w2), -2.0);
        let w3 = DMatrix::from_row_slice(3, 3, &[2.0, 0.0, 1.0, 1.0, 3.0, 0.0, 0.0, 1.0, 1.0]);
        // 2(3·1 − 0·1) − 0 + 1(1·1 − 3·0) = 7
        assert!((square_determinant(&w3) - 7.0).abs() < 1e-14);
        let w6 =
            DMatrix::<f64>::from_diagonal(&DVector::from_vec(vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]));
        assert!((square_determinant(&w6) - 720.0).abs() < 1e-10);
    }

    /// The closed forms agree with nalgebra's LU determinant (independent oracle) on
    /// pseudo-random matrices of every handled size, and a size without a closed form still works.
    #[test]
    fn determinants_agree_with_lu() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for n in [1, 2, 3, 4, 6] {
            for _ in 0..50 {
                let w = DMatrix::from_fn(n, n, |_, _| rnd());
                let lu = w.clone().determinant();
                let d = square_determinant(&w);
                assert!(
                    (d - lu).abs() <= 1e-12 * lu.abs().max(1.0),
                    "n = {n}: {d} vs {lu}"
                );
            }
        }
    }
}

//! # The dynamic feasible workspace criterion
//!
//! Poses where every acceleration of a box is produced by tensions within bounds, at a given
//! twist (Gagliardini, Gouttefarde & Caro 2016): the capacity margin of the zonotope of
//! required wrenches, decided exactly by [`cdpr_dynamics::DynamicFeasibility`] and wrapped as a
//! criterion here, so grids, meshes and sections use it like any other.
//!
//! ## References
//! - Gagliardini, Gouttefarde & Caro 2016 (ARK); Barrette & Gosselin 2005.

use crate::{Criterion, CustomCriterion};
use cdpr_dynamics::DynamicFeasibility;

/// The criterion "dynamically feasible for the whole acceleration box" (margin ≥ 0).
///
/// ```
/// use cdpr_dynamics::{DynamicFeasibility, RigidBody};
/// use cdpr_kinematics::MotionPattern;
/// use cdpr_tension::TensionBounds;
/// use cdpr_wrench::Platform;
/// let body = RigidBody::point_mass(&Platform { mass: 1.0, ..Platform::default() }).unwrap();
/// let bounds = TensionBounds::uniform(3, 0.0, 100.0).unwrap();
/// let test = DynamicFeasibility::new(MotionPattern::Point2, &bounds, body, &[1.0, 1.0], &[0.0, 0.0], &[0.0, 0.0]).unwrap();
/// assert_eq!(cdpr_workspace::dynamic_criterion(test).name(), "dynamic");
/// ```
pub fn dynamic_criterion(test: DynamicFeasibility) -> Criterion {
    Criterion::Custom(CustomCriterion::new("dynamic", move |ctx| {
        // An error here is an overflow of huge wrenches: not certified feasible.
        test.is_feasible(ctx.pose, ctx.wrench_matrix)
            .unwrap_or(false)
    }))
}

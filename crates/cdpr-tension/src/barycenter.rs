//! # Barycentric (centroid) tension distribution
//!
//! For redundancy 2, the tensions at the area centroid of the feasible polygon (Picard, Caro, Plestan & Claveau 2020
//! eqs. (5)–(6)): far from all bounds, continuous along trajectories, and computed by a
//! finite number of operations (Lamaury & Gouttefarde 2013 walk the polygon's edges; so do we
//! first, module `planar_active_set`, and clip it, see [`crate::FeasiblePolygon`], for what the
//! walk hands back). The area centroid commutes with affine maps, so the
//! result does not depend on the choice of the null-space basis. A degenerate (zero-area)
//! polygon gives the mean of its vertices. Other redundancies: [`crate::TensionError::MethodNotApplicable`].
//!
//! ## References
//! - Lamaury & Gouttefarde (2013), *A tension distribution method with improved computational
//!   efficiency*, Cable-Driven Parallel Robots, Springer, pp. 71–85.
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6), Fig. 2.

use crate::Infeasibility;
use crate::feasible_polygon::Region;
use crate::linear_program::write_tensions;
use crate::null_space::NullSpace;

/// Barycentre tensions on a built, non-empty polygon (r = 2).
pub(crate) fn solve_on_region(
    ns: &NullSpace,
    region: &Region,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    if region.is_unbounded() {
        return Err(Infeasibility::Unbounded {
            method: "barycenter",
        });
    }
    write_tensions(ns, region.centroid(), t);
    Ok(())
}

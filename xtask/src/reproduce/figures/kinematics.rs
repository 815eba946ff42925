//! The kinematics figure: one cable over a swivel pulley (Pott 2018 model, issue 14), drawn from
//! the library's own inverse kinematics.

use super::Figure;
use cdpr::plot::{PulleyCablePlot, save};
use nalgebra::Vector3;
use std::path::Path;

/// Writes this area's figures into `dir`.
pub fn figures(dir: &Path) -> Result<Vec<Figure>, String> {
    // A 0.3 m pulley swivelling about a vertical axis, the attachment 1.2 m out and 0.6 m below:
    // the cable arrives going up, runs over the top and leaves past the half turn's midpoint.
    let plot = PulleyCablePlot::new(
        "One cable over a swivel pulley (Pott 2018; WireCenter model)",
        0.3,
        Vector3::z(),
        Vector3::new(0.75, 0.95, -0.6),
    )
    .map_err(|e| e.to_string())?;
    let file = "pulley_cable.png";
    save(&plot, dir.join(file)).map_err(|e| e.to_string())?;
    Ok(vec![Figure {
        file: file.into(),
        source: "Pulley kinematics (Pott 2018)".into(),
        caption: format!(
            "The swivel-pulley model of `cdpr_kinematics` (module `pulley`): the cable arrives \
             along the swivel axis k at a, wraps the pulley (radius ρ = 0.3 m) by the wrap angle \
             β = {:.4} rad and leaves it at the tangent point C towards the attachment B; the \
             pulley plane is turned about k by the swivel angle γ = {:.4} rad from the first \
             column of Q. Length L = ρβ + l_f = {:.4} m. Computed by the library's inverse \
             kinematics, not drawn by hand.",
            plot.wrap_angle, plot.swivel_angle, plot.lengths.0
        ),
    }])
}

//! `cdpr workspace --boundary grid` (the default): a [`WorkspaceRequest`] run by `cdpr-api`
//! (thesis Algorithm 6.2), its report rendered as JSON (the serialised report), text, a point
//! file or a plot.

use super::region::{
    at_orientation, draw_pose, plot_title, progress, resolution, rotation, save_grid_plot,
    save_scene_plot,
};
use super::{CliError, print_report};
use cdpr::api::{WorkspaceReport, WorkspaceRequest};
use cdpr::kinematics::Pose;
use std::path::Path;

/// How the report is shown.
pub struct View<'a> {
    /// Pose at which the robot is drawn (motion-pattern coordinates).
    pub draw_pose: Option<&'a [f64]>,
    /// The figure (.svg, .png; .html for 3-D robots).
    pub plot: Option<&'a Path>,
    /// The grid verdicts as CSV.
    pub points: Option<&'a Path>,
    /// One JSON object on stdout.
    pub json: bool,
}

/// Runs the request with a progress bar and renders its report.
pub fn run(request: &WorkspaceRequest, view: &View<'_>) -> Result<(), CliError> {
    let desc = request.robot.description();
    let motion = desc.robot.motion();
    let dim = motion.space_dim();
    let rows = resolution(request.grid, dim, 50).map_or(0, |m| (m + 1).pow(dim as u32 - 1));
    let bar = progress(rows);
    let report = request.run_with_progress(&|| bar.inc(1))?;
    bar.finish_and_clear();
    if let Some(path) = view.points {
        super::workspace_mesh::write_points(&report.workspace, path)?;
    }
    if let Some(path) = view.plot {
        let rot = rotation(motion, request.orientation.as_deref())?;
        let pose = draw_pose(
            &desc.robot,
            view.draw_pose,
            &report.workspace.grid.region,
            &rot,
        )?;
        save_workspace_plot(request, &report, &pose, path)?;
    }
    if view.json {
        return print_report(&report);
    }
    print_grid(request, &report);
    if let Some(p) = view.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// Area (2-D) or volume (3-D) and its unit.
fn measure_name(dim: usize) -> (&'static str, &'static str) {
    if dim == 2 {
        ("area", "m²")
    } else {
        ("volume", "m³")
    }
}

/// The 3-D scene (SVG/PNG views or HTML) or the planar grid.
fn save_workspace_plot(
    request: &WorkspaceRequest,
    r: &WorkspaceReport,
    pose: &Pose,
    path: &Path,
) -> Result<(), CliError> {
    let desc = request.robot.description();
    let (ws, m, convention) = (&r.workspace, r.resolution, request.volume_convention);
    let motion = desc.robot.motion();
    let labels = r.criteria.join(", ");
    if motion.space_dim() == 3 {
        return save_scene_plot(
            desc,
            pose,
            ws,
            (
                format!(
                    "{}: constant-orientation workspace{}",
                    desc.name,
                    at_orientation(&r.orientation)
                ),
                vec![
                    format!(
                        "volume {:.4} m³ ({} of {} points, m = {m}, {convention} convention)",
                        r.area, r.feasible_points, r.total_points,
                    ),
                    format!("criteria: {labels}"),
                    format!(
                        "draw pose ({:.3}, {:.3}, {:.3}) m",
                        pose.position.x, pose.position.y, pose.position.z
                    ),
                ],
            ),
            request.criteria.cable_model.as_deref(),
            path,
        );
    }
    let (title, setting) = plot_title(
        &desc.name,
        "constant-orientation workspace (grid)",
        motion,
        &r.orientation,
        &r.external_wrench,
        &r.tension_method,
    );
    let (what, unit) = measure_name(2);
    save_grid_plot(
        desc,
        pose,
        ws,
        title,
        vec![
            setting,
            format!(
                "{what} {:.4} {unit} ({} of {} points, m = {m}, {convention} convention); {labels}",
                r.area, r.feasible_points, r.total_points,
            ),
        ],
        path,
    )
}

/// The text answer.
fn print_grid(request: &WorkspaceRequest, r: &WorkspaceReport) {
    let desc = request.robot.description();
    let motion = desc.robot.motion();
    let (what, unit) = measure_name(r.dimension);
    println!(
        "robot {}: constant-orientation workspace at orientation {}, w_ext {}",
        r.robot,
        if r.orientation.is_empty() {
            "(none: a point robot)".to_string()
        } else {
            format!("{} rad", super::nums(&r.orientation))
        },
        super::wrench_text(&r.external_wrench, motion.translation_dof())
    );
    println!(
        "criteria: {} (tensions: {})",
        r.criteria.join(", "),
        r.tension_method
    );
    println!(
        "grid m = {} over {} m: {} of {} points feasible, cell {what} {:.6e} {unit}",
        r.resolution,
        super::nums(&r.area_box),
        r.feasible_points,
        r.total_points,
        r.cell_area
    );
    println!(
        "{what} {:.6} {unit} ({})",
        r.area,
        request.volume_convention.describe()
    );
}

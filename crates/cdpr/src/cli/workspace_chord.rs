//! `cdpr workspace --boundary chord` and `--section AXIS=VALUE`: a [`ChordRequest`] (the boundary
//! curves of a planar workspace) or a [`SectionRequest`] (a plane section of a 3-D workspace),
//! run by `cdpr-api` (the chord method, thesis §6.4.3), their reports rendered as JSON (the
//! serialised report), text or a plot.

use super::region::{
    box_region, draw_pose, is_html, plot_title, print_header, save_plot, workspace_plot,
};
use super::{CliError, num, print_report};
use cdpr::api::{ChordReport, ChordRequest, CurvesReport, SectionReport, SectionRequest};
use cdpr::kinematics::Pose;
use cdpr::plot::WorkspacePlot;
use cdpr::workspace::Section;
use nalgebra::Vector2;
use std::path::Path;

/// How a report is shown.
pub struct View<'a> {
    /// Pose at which the robot is drawn (motion-pattern coordinates).
    pub draw_pose: Option<&'a [f64]>,
    /// The figure (.svg or .png).
    pub plot: Option<&'a Path>,
    /// One JSON object on stdout.
    pub json: bool,
}

/// `--boundary chord`: runs the request and renders its report.
pub fn run_chord(request: &ChordRequest, view: &View<'_>) -> Result<(), CliError> {
    if let Some(p) = view.plot.filter(|p| is_html(p)) {
        return Err(format!(
            "--plot {}: the HTML viewer shows 3-D workspaces (point3, spatial) on the grid; use \
             .svg or .png",
            p.display()
        )
        .into());
    }
    let report = request.run()?;
    if let Some(path) = view.plot {
        save_chord_plot(request, &report, view.draw_pose, path)?;
    }
    if view.json {
        return print_report(&report);
    }
    print_header(
        &report.robot,
        "chord-method workspace",
        &report.orientation,
        &report.external_wrench,
        request.robot.robot.motion().translation_dof(),
        &report.criteria,
        &report.tension_method,
    );
    let (regions, holes) = report.curves.regions_and_holes();
    println!(
        "area {:.6} m²: {regions} region(s), {holes} hole(s), chord d = {} m, {} pose evaluations",
        report.curves.area, report.chord, report.curves.evaluations
    );
    print_curves(&report.curves);
    if let Some(p) = view.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// Each boundary's size, and the walks abandoned.
fn print_curves(c: &CurvesReport) {
    for (k, b) in c.boundaries.iter().enumerate() {
        println!(
            "  boundary {}: {} vertices, signed area {:+.6} m², perimeter {:.4} m, {} bifurcation \
             point(s)",
            k + 1,
            b.len(),
            c.signed_areas[k],
            c.perimeter(k),
            c.bifurcations[k].len()
        );
    }
    if c.abandoned > 0 {
        println!(
            "warning: {} boundary walk(s) abandoned (curves missing)",
            c.abandoned
        );
    }
}

/// The polygons of a report as plot points.
fn polygons(c: &CurvesReport) -> Vec<Vec<(f64, f64)>> {
    let pts = |b: &Vec<[f64; 2]>| b.iter().map(|v| (v[0], v[1])).collect();
    c.boundaries.iter().map(pts).collect()
}

/// The plot of `--boundary chord`: the robot and the boundary curves.
fn save_chord_plot(
    request: &ChordRequest,
    r: &ChordReport,
    q: Option<&[f64]>,
    path: &Path,
) -> Result<(), CliError> {
    let desc = request.robot.description();
    let robot = &desc.robot;
    let rotation = super::region::rotation(robot.motion(), request.orientation.as_deref())?;
    let pose = draw_pose(robot, q, &box_region(&r.area_box), &rotation)?;
    let (regions, holes) = r.curves.regions_and_holes();
    let (title, setting) = plot_title(
        &desc.name,
        "constant-orientation workspace (chord method)",
        robot.motion(),
        &r.orientation,
        &r.external_wrench,
        &r.tension_method,
    );
    let mut fig = workspace_plot(
        robot,
        &pose,
        None,
        polygons(&r.curves),
        title,
        vec![
            setting,
            format!(
                "area {:.4}, {regions} region(s), {holes} hole(s), chord d = {}; {}",
                r.curves.area,
                r.chord,
                r.criteria.join(", ")
            ),
        ],
    );
    fig.anchor_names = cdpr::plot::cable_names(&desc.cable_names);
    save_plot(&fig, path)
}

/// `--section AXIS=VALUE`: runs the request and renders its report.
pub fn run_section(request: &SectionRequest, view: &View<'_>) -> Result<(), CliError> {
    let report = request.run()?;
    if let Some(path) = view.plot {
        save_section_plot(request, &report, view.draw_pose, path)?;
    }
    if view.json {
        return print_report(&report);
    }
    let s = &report.section;
    print_header(
        &report.robot,
        &format!("workspace section {} = {} m", s.axis, s.value),
        &report.orientation,
        &report.external_wrench,
        3,
        &report.criteria,
        &report.tension_method,
    );
    let (regions, holes) = report.curves.regions_and_holes();
    println!(
        "area {:.6} m² in the ({}, {}) plane: {regions} region(s), {holes} hole(s), chord d = {} m, \
         {} pose evaluations",
        report.curves.area,
        s.plane_axes[0],
        s.plane_axes[1],
        report.chord,
        report.curves.evaluations
    );
    print_curves(&report.curves);
    if let Some(p) = view.plot {
        println!("plot written to {}", p.display());
    }
    Ok(())
}

/// The robot drawn at `--draw-pose`, or at the box centre moved into the plane.
fn section_pose(
    request: &SectionRequest,
    r: &SectionReport,
    q: Option<&[f64]>,
) -> Result<(Pose, Section), CliError> {
    let robot = &request.robot.robot;
    let region = box_region(&r.area_box);
    let rotation = super::region::rotation(robot.motion(), request.orientation.as_deref())?;
    let section = Section {
        axis: request.section.axis.index(),
        value: request.section.value,
    };
    let mut pose = draw_pose(robot, q, &region, &rotation)?;
    if q.is_none() {
        let [a, b] = section.in_plane_axes();
        let u = Vector2::new(pose.position[a], pose.position[b]);
        pose = Pose::new(section.embed(u), pose.rotation);
    }
    Ok((pose, section))
}

/// The plot of `--section`: the boundary polygons filled, their corners marked, the box and the
/// robot projected on the plane.
fn save_section_plot(
    request: &SectionRequest,
    r: &SectionReport,
    q: Option<&[f64]>,
    path: &Path,
) -> Result<(), CliError> {
    let desc = request.robot.description();
    let (pose, section) = section_pose(request, r, q)?;
    let [a, b] = section.in_plane_axes();
    let bx = &r.area_box;
    let (lo, hi) = (|k: usize| bx[2 * k], |k: usize| bx[2 * k + 1]);
    let (regions, holes) = r.curves.regions_and_holes();
    let s = &r.section;
    let markers: Vec<(f64, f64)> = r
        .curves
        .bifurcations
        .iter()
        .flatten()
        .map(|v| (v[0], v[1]))
        .collect();
    let fig = WorkspacePlot {
        title: format!(
            "{}: workspace section {} = {} m",
            desc.name, s.axis, s.value
        ),
        anchor_names: cdpr::plot::cable_names(&desc.cable_names),
        boundaries: polygons(&r.curves),
        fill_boundaries: true,
        frame: vec![
            (lo(a), lo(b)),
            (hi(a), lo(b)),
            (hi(a), hi(b)),
            (lo(a), hi(b)),
        ],
        marker_label: (!markers.is_empty())
            .then(|| "bifurcation points (boundary corners)".to_string()),
        markers,
        notes: vec![
            format!(
                "area {:.4} m², {regions} region(s), {holes} hole(s); chord method, d = {} m, \
                 vertices on the boundary to {} m",
                r.curves.area,
                r.chord,
                num(r.tolerance)
            ),
            format!(
                "{}{}; thin rectangle: the search box; robot projected at its draw pose",
                if r.orientation.is_empty() {
                    String::new()
                } else {
                    format!("orientation {}; ", super::pose_text(&r.orientation, 0))
                },
                r.criteria.join(", ")
            ),
        ],
        axis_names: Some((
            format!("{} (m)", s.plane_axes[0]),
            format!("{} (m)", s.plane_axes[1]),
        )),
        ..WorkspacePlot::default()
    }
    .with_robot_projected(&desc.robot, &pose, [a, b]);
    save_plot(&fig, path)
}

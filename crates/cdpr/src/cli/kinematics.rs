//! `cdpr kinematics`: inverse kinematics and the wrench matrix at one pose.

use super::{CliError, Numbers, load_robot, print_matrix, print_report};
use cdpr::api::{KinematicsModel, KinematicsReport, KinematicsRequest, Robot};
use nalgebra::DMatrix;
use std::path::PathBuf;

/// Inverse kinematics at a pose (thesis eqs. (6.2)–(6.4), (6.11); pulleys: Pott 2018).
///
/// Prints each cable's length l_i (m) and unit vector (from the platform attachment towards the
/// frame anchor, or towards the point where the cable leaves its pulley), and the DOF × n wrench
/// matrix W with W t + w_ext = 0. With pulleys (`--kinematics pulley`, the default when the robot
/// file has any) the length is the wrapped arc plus the free segment, measured from `frame`.
/// JSON fields: `kinematics` ("pulley" | "standard"), `lengths` (m), `free_lengths` (m, the straight
/// part), `swivel_angles` and `wrap_angles` (rad; 0 for cables without a pulley), `unit_vectors`
/// (one array per cable), `wrench_matrix` (one array per row of W), `attachment_points` (m),
/// `exit_points` (m, where each cable leaves the frame or its pulley), `jacobian_determinant`
/// (n = DOF only), `closest_cables`
/// (the two cables, 1-based, whose straight segments come closest; pairs sharing an anchor or
/// attachment are left out; null if none), `closest_distance` (their distance, m),
/// `closest_points` (the closest point on each, m), and with a `[platform] shape` in the robot
/// file `platform_interference` (null, or the cable, 1-based, that passes deepest through the
/// platform and its `penetration` in m). With passive springs in the robot file (CASPR's
/// `cable_passive_linear_spring`), `passive_springs`: their `lengths` (m), `forces` K (l − l0)
/// (N) and `wrench` (N, N·m), the part of w_ext they contribute; null without springs.
///
/// With `--cable-model elastic|catenary --tensions T1,…,Tn` (platform-end tensions, N): per cable
/// `unstrained_lengths` (m), `chord_lengths` (m), `frame_end_tensions` (N),
/// `platform_end_tensions` (N), `max_sag` (m, below the chord), `angle_to_chord` (rad, at the
/// platform) and the `wrench_matrix` whose columns are the unit forces the cables apply.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Robot file: .toml, CASPR NAME_cables.xml or WireCenter .wcrfx.
    robot: PathBuf,
    /// Platform pose, e.g. `--pose -0.5,0.2,0` for a planar robot (x, y, φ).
    #[arg(long, allow_hyphen_values = true)]
    pose: Numbers,
    #[command(flatten)]
    cable_model: super::cable_model::CableModelArgs,
    /// Platform-end cable tensions T1,…,Tn (N) for --cable-model elastic|catenary.
    #[arg(long)]
    tensions: Option<Numbers>,
    /// Draw the robot at the pose: .svg or .png (2-D robots seen from +z, 3-D robots an
    /// isometric view with three sections) or .html (an interactive 3-D view); anchors carry
    /// the cables' names.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Write one JSON object on stdout instead of tables.
    #[arg(long)]
    json: bool,
}

/// Runs the command: the request, its report, rendered as JSON or tables.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    if let Some(path) = &args.plot {
        super::robot_plot::check_path(path)?;
    }
    if args.cable_model.catenaries(&robot)?.is_some() {
        if args.plot.is_some() {
            return Err(
                "--plot is not drawn with --cable-model elastic|catenary (straight cables only)"
                    .into(),
            );
        }
        let t = args.tensions.as_deref();
        return super::cable_model::kinematics(robot, &args.cable_model, t, &args.pose, args.json);
    }
    let request = KinematicsRequest {
        robot: Robot::from_description(robot),
        pose: args.pose.0,
    };
    let report = request.run()?;
    if let Some(path) = &args.plot {
        plot(&request, &report, path)?;
    }
    if args.json {
        print_report(&report)
    } else {
        print_text(&report, request.robot.robot.motion().space_dim());
        Ok(())
    }
}

/// `--plot`: the robot at the pose ([`super::robot_plot`]).
fn plot(
    request: &KinematicsRequest,
    r: &KinematicsReport,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let desc = request.robot.description();
    let dim = desc.robot.motion().space_dim();
    let pose = super::pose(desc, &request.pose)?;
    super::robot_plot::RobotFigure {
        desc,
        pose: &pose,
        title: format!("{} at pose {}", r.robot, super::pose_text(&r.pose, dim)),
        notes: vec![format!("{} kinematics", r.kinematics.name())],
        tensions: None,
    }
    .save(path)
}

/// The report as tables (`dim` position coordinates in the pose).
fn print_text(r: &KinematicsReport, dim: usize) {
    println!(
        "robot {} ({}, {} kinematics), pose {}",
        r.robot,
        r.motion,
        r.kinematics.name(),
        super::pose_text(&r.pose, dim)
    );
    let pulleys = r.kinematics == KinematicsModel::Pulley;
    if pulleys {
        println!(
            "{:>6} {:>12} {:>12} {:>10} {:>10}  unit vector",
            "cable", "length (m)", "free (m)", "swivel γ", "wrap β"
        );
    } else {
        println!("{:>6} {:>12}  unit vector", "cable", "length (m)");
    }
    for (i, unit) in r.unit_vectors.iter().enumerate() {
        let u: Vec<String> = unit.iter().map(|x| format!("{x:>10.6}")).collect();
        if pulleys {
            println!(
                "{:>6} {:>12.6} {:>12.6} {:>6.4} rad {:>6.4} rad  {}",
                i + 1,
                r.lengths[i],
                r.free_lengths[i],
                r.swivel_angles[i],
                r.wrap_angles[i],
                u.join(" ")
            );
        } else {
            println!("{:>6} {:>12.6}  {}", i + 1, r.lengths[i], u.join(" "));
        }
    }
    let w = &r.wrench_matrix;
    let cols = w.first().map_or(0, Vec::len);
    let w = DMatrix::from_row_iterator(w.len(), cols, w.iter().flatten().copied());
    print_matrix("wrench matrix W (DOF × n), W t + w_ext = 0:", &w);
    if let Some(s) = &r.passive_springs {
        println!("{:>6} {:>12} {:>12}", "spring", "length (m)", "force (N)");
        for (j, (l, f)) in s.lengths.iter().zip(&s.forces).enumerate() {
            println!("{:>6} {:>12.6} {:>12.6}", j + 1, l, f);
        }
        let parts: Vec<String> = s.wrench.iter().map(|v| format!("{v:.6}")).collect();
        println!(
            "passive springs' wrench (N, N·m; part of w_ext): [{}]",
            parts.join(", ")
        );
    }
    if let Some(d) = r.jacobian_determinant {
        println!("det J = {d:.6e}");
    }
    match (r.closest_cables, r.closest_distance) {
        (Some([a, b]), Some(d)) => println!("closest cables: {a} and {b}, {d:.6} m apart"),
        _ => println!("closest cables: none (every pair shares an anchor or attachment)"),
    }
    match &r.platform_interference {
        None => {}
        Some(p) => match p.cable {
            None => println!("platform: no cable passes through it"),
            Some(c) => println!(
                "platform: cable {c} passes through it, {:.6} m deep",
                p.penetration
            ),
        },
    }
}

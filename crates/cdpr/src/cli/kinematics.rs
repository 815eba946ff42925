//! `cdpr kinematics`: inverse kinematics and the wrench matrix at one pose.

use super::{
    CliError, KinematicsModel, Numbers, kinematics_model, load_robot, matrix_rows, pose,
    print_json, print_matrix,
};
use serde_json::json;
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
    /// Write one JSON object on stdout instead of tables.
    #[arg(long)]
    json: bool,
}

/// Runs the command.
pub fn run(args: Args) -> Result<(), CliError> {
    let robot = load_robot(&args.robot)?;
    let pose = pose(&robot, &args.pose)?;
    let kin = robot.robot.inverse_kinematics(&pose)?;
    if let Some(cables) = args.cable_model.catenaries(&robot)? {
        let (t, name) = (args.tensions.as_deref(), args.cable_model.model().name());
        return super::cable_model::kinematics(
            &robot, &kin, &cables, t, name, &args.pose, args.json,
        );
    }
    let model = kinematics_model(&robot);
    let n = kin.cable_count();
    let w = kin.wrench_matrix();
    let dim = robot.robot.motion().space_dim();
    let vec_of = |v: &nalgebra::Vector3<f64>| v.iter().take(dim).copied().collect::<Vec<f64>>();
    let closest = cdpr::kinematics::closest_cables(&kin);
    let through = robot.platform_shape.as_ref().map(|shape| {
        cdpr::kinematics::platform_interference(&kin, shape, &pose.position, &pose.rotation)
    });
    let springs = match &robot.passive_springs {
        None => None,
        Some(s) => {
            let (sk, forces) = s.state(&pose)?;
            let ws = sk.wrench_matrix() * nalgebra::DVector::from_column_slice(&forces);
            Some((sk.lengths().collect::<Vec<_>>(), forces, ws))
        }
    };
    if args.json {
        print_json(&json!({
            "robot": robot.name,
            "motion": robot.robot.motion().name(),
            "pose": args.pose.0,
            "kinematics": model.name(),
            "lengths": kin.lengths().collect::<Vec<_>>(),
            "free_lengths": (0..n).map(|i| kin.free_length(i)).collect::<Vec<_>>(),
            "swivel_angles": (0..n).map(|i| kin.swivel_angle(i)).collect::<Vec<_>>(),
            "wrap_angles": (0..n).map(|i| kin.wrap_angle(i)).collect::<Vec<_>>(),
            "unit_vectors": kin.cables().iter().map(|c| vec_of(&c.unit)).collect::<Vec<_>>(),
            "attachment_points": kin.cables().iter().map(|c| vec_of(&c.attachment_point)).collect::<Vec<_>>(),
            "exit_points": (0..n).map(|i| vec_of(&kin.exit_point(i))).collect::<Vec<_>>(),
            "wrench_matrix": matrix_rows(&w),
            "jacobian_determinant": kin.jacobian_determinant(),
            "closest_cables": closest.map(|c| [c.cables.0 + 1, c.cables.1 + 1]),
            "closest_distance": closest.map(|c| c.distance),
            "closest_points": closest.map(|c| [vec_of(&c.points.0), vec_of(&c.points.1)]),
            "platform_interference": match through {
                None => json!(null),
                Some(None) => json!({ "cable": null, "penetration": 0.0 }),
                Some(Some(p)) => json!({ "cable": p.cable + 1, "penetration": p.penetration }),
            },
            "passive_springs": springs.as_ref().map(|(l, f, w)| json!({
                "lengths": l, "forces": f, "wrench": w.as_slice(),
            })),
        }))
    } else {
        println!(
            "robot {} ({}, {} kinematics), pose {}",
            robot.name,
            robot.robot.motion(),
            model.name(),
            super::pose_text(&args.pose.0, robot.robot.motion().space_dim())
        );
        let pulleys = model == KinematicsModel::Pulley;
        if pulleys {
            println!(
                "{:>6} {:>12} {:>12} {:>10} {:>10}  unit vector",
                "cable", "length (m)", "free (m)", "swivel γ", "wrap β"
            );
        } else {
            println!("{:>6} {:>12}  unit vector", "cable", "length (m)");
        }
        for (i, c) in kin.cables().iter().enumerate() {
            let u: Vec<String> = vec_of(&c.unit)
                .iter()
                .map(|x| format!("{x:>10.6}"))
                .collect();
            if pulleys {
                println!(
                    "{:>6} {:>12.6} {:>12.6} {:>6.4} rad {:>6.4} rad  {}",
                    i + 1,
                    c.length,
                    kin.free_length(i),
                    kin.swivel_angle(i),
                    kin.wrap_angle(i),
                    u.join(" ")
                );
            } else {
                println!("{:>6} {:>12.6}  {}", i + 1, c.length, u.join(" "));
            }
        }
        print_matrix("wrench matrix W (DOF × n), W t + w_ext = 0:", &w);
        if let Some((l, f, ws)) = &springs {
            println!("{:>6} {:>12} {:>12}", "spring", "length (m)", "force (N)");
            for (j, (l, f)) in l.iter().zip(f).enumerate() {
                println!("{:>6} {:>12.6} {:>12.6}", j + 1, l, f);
            }
            let parts: Vec<String> = ws.iter().map(|v| format!("{v:.6}")).collect();
            println!(
                "passive springs' wrench (N, N·m; part of w_ext): [{}]",
                parts.join(", ")
            );
        }
        if let Some(d) = kin.jacobian_determinant() {
            println!("det J = {d:.6e}");
        }
        match closest {
            Some(c) => println!(
                "closest cables: {} and {}, {:.6} m apart",
                c.cables.0 + 1,
                c.cables.1 + 1,
                c.distance
            ),
            None => println!("closest cables: none (every pair shares an anchor or attachment)"),
        }
        match through {
            None => {}
            Some(None) => println!("platform: no cable passes through it"),
            Some(Some(p)) => println!(
                "platform: cable {} passes through it, {:.6} m deep",
                p.cable + 1,
                p.penetration
            ),
        }
        Ok(())
    }
}

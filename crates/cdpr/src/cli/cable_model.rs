//! `--cable-model straight|elastic|catenary` (issue 29): the flag every command where cables
//! carry force flattens in, and the sag-aware outputs of `cdpr kinematics` and `cdpr tension`.
//!
//! `straight` (the default) leaves every result unchanged. `elastic` treats the cables as
//! massless springs (needs `axial_stiffness`: L0 = l/(1 + t/EA)); `catenary` as heavy elastic
//! cables, Irvine's elastic catenary (needs `axial_stiffness` and `linear_density`; gravity from
//! the robot file's `[platform] gravity`).

use super::{CliError, matrix_rows, print_json, print_matrix};
use cdpr::RobotDescription;
use cdpr::kinematics::catenary::write_sagging_wrench_matrix;
use cdpr::kinematics::{CableModel, PoseKinematics, RobotCatenaries, SaggingCable};
use cdpr::tension::{
    Method, SaggingOutcome, SaggingSettings, SaggingStatics, TensionBounds, TensionSolver,
};
use nalgebra::{DMatrix, DVector};
use serde_json::json;

/// The `--cable-model` option, flattened into a command's arguments.
#[derive(clap::Args, Debug, Clone)]
pub struct CableModelArgs {
    /// Cable model: straight (massless, inextensible; the default, results unchanged), elastic
    /// (massless springs; needs `axial_stiffness`), catenary (heavy elastic cables, Irvine's
    /// elastic catenary; needs `axial_stiffness` and `linear_density`).
    #[arg(long = "cable-model", value_enum, default_value = "straight")]
    pub cable_model: CableModelName,
}

/// The spellings of `--cable-model`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CableModelName {
    /// Massless inextensible straight cables.
    Straight,
    /// Massless elastic straight cables.
    Elastic,
    /// Heavy elastic cables (elastic catenary).
    Catenary,
}

impl CableModelArgs {
    /// The model chosen.
    pub fn model(&self) -> CableModel {
        match self.cable_model {
            CableModelName::Straight => CableModel::Straight,
            CableModelName::Elastic => CableModel::Elastic,
            CableModelName::Catenary => CableModel::Catenary,
        }
    }

    /// The robot's cables under the chosen model: `None` for straight cables; a usage error
    /// when the robot file lacks the keys the model needs or has pulleys.
    pub fn catenaries(
        &self,
        robot: &RobotDescription,
    ) -> Result<Option<RobotCatenaries>, CliError> {
        Ok(cdpr::api::cable_model::catenaries(robot, self.model())?)
    }
}

/// The per-cable JSON fields of sagging cables.
pub fn cables_json(cables: &[SaggingCable]) -> serde_json::Value {
    let field = |f: fn(&SaggingCable) -> f64| cables.iter().map(f).collect::<Vec<_>>();
    json!({
        "unstrained_lengths": field(|c| c.unstrained_length),
        "chord_lengths": field(|c| c.chord_length),
        "frame_end_tensions": field(|c| c.frame_end_tension),
        "platform_end_tensions": field(|c| c.platform_end_tension),
        "max_sag": field(|c| c.max_sag),
        "angle_to_chord": field(|c| c.angle_to_chord),
    })
}

fn print_cables(cables: &[SaggingCable]) {
    println!(
        "{:>6} {:>12} {:>12} {:>12} {:>14} {:>12} {:>12}",
        "cable", "L0 (m)", "chord (m)", "T_B (N)", "T_frame (N)", "sag (m)", "angle (rad)"
    );
    for (i, c) in cables.iter().enumerate() {
        println!(
            "{:>6} {:>12.6} {:>12.6} {:>12.6} {:>14.6} {:>12.6} {:>12.6}",
            i + 1,
            c.unstrained_length,
            c.chord_length,
            c.platform_end_tension,
            c.frame_end_tension,
            c.max_sag,
            c.angle_to_chord
        );
    }
}

/// `cdpr kinematics --cable-model elastic|catenary --tensions …`: each cable's catenary for its
/// platform-end tension, and the sag-aware wrench matrix.
pub fn kinematics(
    robot: &RobotDescription,
    kin: &PoseKinematics,
    model: &RobotCatenaries,
    tensions: Option<&[f64]>,
    name: &str,
    pose: &[f64],
    json_out: bool,
) -> Result<(), CliError> {
    let n = kin.cable_count();
    let t = tensions.ok_or_else(|| {
        format!("--cable-model {name} needs --tensions T1,…,T{n} (platform-end tensions, N)")
    })?;
    if t.len() != n {
        return Err(format!(
            "--tensions needs {n} numbers (one per cable), got {}",
            t.len()
        )
        .into());
    }
    if let Some(i) = t.iter().position(|&v| !(v.is_finite() && v >= 0.0)) {
        return Err(format!(
            "--tensions: cable {} has tension {} N; tensions are finite numbers ≥ 0",
            i + 1,
            t[i]
        )
        .into());
    }
    let mut cables = Vec::new();
    model.with_tensions(kin, t, &mut cables)?;
    let mut w = DMatrix::zeros(0, 0);
    write_sagging_wrench_matrix(kin, &cables, &mut w);
    if json_out {
        let mut v = json!({
            "robot": robot.name,
            "motion": robot.robot.motion().name(),
            "pose": pose,
            "cable_model": name,
            "wrench_matrix": matrix_rows(&w),
        });
        if let (Some(o), serde_json::Value::Object(c)) = (v.as_object_mut(), cables_json(&cables)) {
            o.extend(c);
        }
        print_json(&v)
    } else {
        println!(
            "robot {} ({}), pose {}, cable model {name}",
            robot.name,
            robot.robot.motion(),
            super::pose_text(pose, robot.robot.motion().space_dim())
        );
        print_cables(&cables);
        print_matrix(
            "wrench matrix W (DOF × n; columns: unit forces of the cables at the platform), W t + w_ext = 0:",
            &w,
        );
        Ok(())
    }
}

/// `cdpr tension --cable-model elastic|catenary`: the fixed point of
/// [`cdpr::tension::sagging_statics`] for `method`.
#[allow(clippy::too_many_arguments)]
pub fn tension(
    robot: &RobotDescription,
    kin: &PoseKinematics,
    model: &RobotCatenaries,
    method: Method,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    name: &str,
    pose: &[f64],
    json_out: bool,
) -> Result<(), CliError> {
    if method == Method::Sotda {
        return Err(format!("--cable-model {name} does not apply to sotda (its stiffness model is the straight cables')").into());
    }
    let outcome = SaggingStatics::new(SaggingSettings::default()).solve(
        &mut TensionSolver::new(method),
        kin,
        model,
        w_ext,
        bounds,
    )?;
    if json_out {
        let mut v = json!({
            "robot": robot.name,
            "pose": pose,
            "external_wrench": w_ext.as_slice(),
            "method": method.name(),
            "cable_model": name,
        });
        match &outcome {
            SaggingOutcome::Feasible(s) => {
                v["feasible"] = json!(true);
                v["tensions"] = json!(s.tensions.as_slice());
                v["residual"] = json!(s.residual);
                v["iterations"] = json!(s.iterations);
                v["reason"] = json!(null);
                v["wrench_matrix"] = json!(matrix_rows(&s.wrench_matrix));
                if let (Some(o), serde_json::Value::Object(c)) =
                    (v.as_object_mut(), cables_json(&s.cables))
                {
                    o.extend(c);
                }
            }
            SaggingOutcome::Infeasible(r) => {
                v["feasible"] = json!(false);
                v["tensions"] = json!(null);
                v["residual"] = json!(null);
                v["reason"] = json!(r.to_string());
            }
        }
        print_json(&v)
    } else {
        println!(
            "robot {}, pose {}, w_ext {}, method {}, cable model {name}",
            robot.name,
            super::pose_text(pose, robot.robot.motion().space_dim()),
            super::wrench_text(w_ext.as_slice(), robot.robot.motion().translation_dof()),
            method.name()
        );
        match &outcome {
            SaggingOutcome::Feasible(s) => {
                println!(
                    "feasible (residual {:.3e} with the catenary forces, {} fixed-point iterations)",
                    s.residual, s.iterations
                );
                print_cables(&s.cables);
            }
            SaggingOutcome::Infeasible(r) => println!("infeasible: {r}"),
        }
        Ok(())
    }
}

/// `--unstrained-lengths`: one finite length > 0 (m) per cable of `n`.
fn check_unstrained_lengths(l0: &[f64], n: usize) -> Result<(), CliError> {
    if l0.len() != n {
        return Err(format!(
            "--unstrained-lengths needs {n} numbers (one per cable), got {}",
            l0.len()
        )
        .into());
    }
    if let Some(i) = l0.iter().position(|&v| !(v.is_finite() && v > 0.0)) {
        return Err(format!(
            "--unstrained-lengths: cable {} has length {} m; lengths are finite numbers > 0",
            i + 1,
            l0[i]
        )
        .into());
    }
    Ok(())
}

/// `cdpr forward --unstrained-lengths … --cable-model elastic|catenary`: the elasto-geometric
/// forward kinematics ([`cdpr::kinematics::ElastoGeometricForward`]) under the platform's
/// weight (and springs) from the robot file plus `wrench`, from `guess` or else from the
/// straight cables' poses for the unstrained lengths (multi-start).
pub fn forward(
    robot: &RobotDescription,
    args: &CableModelArgs,
    l0: &[f64],
    wrench: Option<&[f64]>,
    guess: Option<cdpr::kinematics::Pose>,
    json_out: bool,
) -> Result<(), CliError> {
    use cdpr::kinematics::ElastoGeometricForward;
    let name = args.model().name();
    let Some(model) = args.catenaries(robot)? else {
        return Err(
            "--unstrained-lengths needs --cable-model elastic or catenary (straight cables have no unstrained length: use --lengths)"
                .into(),
        );
    };
    let n = robot.robot.cable_count();
    check_unstrained_lengths(l0, n)?;
    let w_e = super::wrench(robot, wrench)?;
    let mut fk = ElastoGeometricForward::new(&robot.robot, &model, Default::default())?;
    let mut load = |p: &cdpr::kinematics::Pose, out: &mut [f64]| {
        let w = robot.load_wrench(p)? + &w_e;
        out.copy_from_slice(w.as_slice());
        Ok(())
    };
    let sol = match guess {
        Some(g) => fk.solve_with_load(l0, &mut load, &g)?,
        None => fk.solve_multistart_with_load(l0, &mut load)?,
    };
    let w_ext = robot.load_wrench(&sol.pose)? + &w_e;
    let motion = robot.robot.motion();
    let slack: Vec<usize> = (0..n).filter(|&i| fk.is_slack(i)).map(|i| i + 1).collect();
    let cables = fk.cables();
    let coordinates = sol.pose.coordinates(motion);
    if json_out {
        let mut v = json!({
            "robot": robot.name,
            "motion": motion.name(),
            "cable_model": name,
            "pose": coordinates,
            "tensions": cables.iter().map(|c| c.platform_end_tension).collect::<Vec<_>>(),
            "residual": sol.residual,
            "status": sol.status.name(),
            "iterations": sol.iterations,
            "slack_cables": slack,
            "external_wrench": w_ext.as_slice(),
        });
        if let (Some(o), serde_json::Value::Object(c)) = (v.as_object_mut(), cables_json(cables)) {
            o.extend(c);
        }
        print_json(&v)
    } else {
        println!(
            "robot {} ({motion}), cable model {name}, w_ext {}",
            robot.name,
            super::wrench_text(w_ext.as_slice(), motion.translation_dof()),
        );
        println!(
            "{} after {} iterations: pose {} (m, rad), residual {:.3e} N",
            sol.status.name(),
            sol.iterations,
            super::pose_text(&coordinates, motion.space_dim()),
            sol.residual
        );
        if !slack.is_empty() {
            println!("slack cables: {slack:?}");
        }
        print_cables(cables);
        Ok(())
    }
}

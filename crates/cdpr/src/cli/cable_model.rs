//! `--cable-model straight|elastic|catenary` (issue 29): the flag every command where cables
//! carry force flattens in, and the sag-aware outputs of `cdpr kinematics` and `cdpr tension`.
//!
//! `straight` (the default) leaves every result unchanged. `elastic` treats the cables as
//! massless springs (needs `axial_stiffness`: L0 = l/(1 + t/EA)); `catenary` as heavy elastic
//! cables, Irvine's elastic catenary (needs `axial_stiffness` and `linear_density`; gravity from
//! the robot file's `[platform] gravity`).

use super::{CliError, print_matrix, print_report};
use cdpr::RobotDescription;
use cdpr::api::sagging::{
    ElastoGeometricRequest, SaggingCablesReport, SaggingKinematicsRequest, SaggingTensionRequest,
};
use cdpr::kinematics::{CableModel, RobotCatenaries};
use cdpr::tension::{Method, SaggingOutcome, SaggingSettings, SaggingStatics, TensionSolver};
use nalgebra::DMatrix;

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
    /// when the robot file lacks the keys the model needs, or for the catenary over pulleys.
    pub fn catenaries(
        &self,
        robot: &RobotDescription,
    ) -> Result<Option<RobotCatenaries>, CliError> {
        Ok(cdpr::api::cable_model::catenaries(robot, self.model())?)
    }
}

impl CableModelArgs {
    /// The request's spelling of the model.
    pub fn api_name(&self) -> cdpr::api::cable_model::CableModelName {
        use cdpr::api::cable_model::CableModelName as Api;
        match self.cable_model {
            CableModelName::Straight => Api::Straight,
            CableModelName::Elastic => Api::Elastic,
            CableModelName::Catenary => Api::Catenary,
        }
    }
}

fn print_cables(c: &SaggingCablesReport) {
    // Over pulleys the chord is the free segment's and L0 includes the wrapped arc.
    let wrapped = c.wrapped_lengths.as_deref();
    println!(
        "{:>6} {:>12} {:>12}{} {:>12} {:>14} {:>12} {:>12}",
        "cable",
        "L0 (m)",
        "chord (m)",
        if wrapped.is_some() {
            "  wrapped (m)"
        } else {
            ""
        },
        "T_B (N)",
        "T_frame (N)",
        "sag (m)",
        "angle (rad)"
    );
    for i in 0..c.unstrained_lengths.len() {
        println!(
            "{:>6} {:>12.6} {:>12.6}{} {:>12.6} {:>14.6} {:>12.6} {:>12.6}",
            i + 1,
            c.unstrained_lengths[i],
            c.chord_lengths[i],
            wrapped.map_or(String::new(), |w| format!(" {:>12.6}", w[i])),
            c.platform_end_tensions[i],
            c.frame_end_tensions[i],
            c.max_sag[i],
            c.angle_to_chord[i]
        );
    }
}

/// `cdpr kinematics --cable-model elastic|catenary --tensions …`: each cable's catenary for its
/// platform-end tension, and the sag-aware wrench matrix ([`SaggingKinematicsRequest`]).
pub fn kinematics(
    robot: RobotDescription,
    args: &CableModelArgs,
    tensions: Option<&[f64]>,
    pose: &[f64],
    json_out: bool,
) -> Result<(), CliError> {
    let (n, name) = (robot.robot.cable_count(), args.model().name());
    let t = tensions.ok_or_else(|| {
        format!("--cable-model {name} needs --tensions T1,…,T{n} (platform-end tensions, N)")
    })?;
    let request = SaggingKinematicsRequest {
        robot: cdpr::api::Robot::from_description(robot),
        pose: pose.to_vec(),
        cable_model: args.api_name(),
        tensions: t.to_vec(),
    };
    let r = request.run()?;
    if json_out {
        return print_report(&r);
    }
    let motion = request.robot.robot.motion();
    println!(
        "robot {} ({motion}), pose {}, cable model {name}",
        r.robot,
        super::pose_text(pose, motion.space_dim())
    );
    print_cables(&r.cables);
    print_matrix(
        "wrench matrix W (DOF × n; columns: unit forces of the cables at the platform), W t + w_ext = 0:",
        &DMatrix::from_row_iterator(
            r.wrench_matrix.len(),
            n,
            r.wrench_matrix.iter().flatten().copied(),
        ),
    );
    Ok(())
}

/// `cdpr tension --cable-model elastic|catenary`: the fixed point of
/// [`cdpr::tension::sagging_statics`] for `method` ([`SaggingTensionRequest`]).
pub fn tension(
    robot: RobotDescription,
    args: &CableModelArgs,
    method: Method,
    wrench: Option<&[f64]>,
    pose: &[f64],
    json_out: bool,
) -> Result<(), CliError> {
    let request = SaggingTensionRequest {
        robot: cdpr::api::Robot::from_description(robot),
        pose: pose.to_vec(),
        wrench: wrench.map(<[f64]>::to_vec),
        method,
        cable_model: args.api_name(),
    };
    let r = request.run()?;
    if json_out {
        return print_report(&r);
    }
    let motion = request.robot.robot.motion();
    println!(
        "robot {}, pose {}, w_ext {}, method {}, cable model {}",
        r.robot,
        super::pose_text(pose, motion.space_dim()),
        super::wrench_text(&r.external_wrench, motion.translation_dof()),
        r.method,
        r.cable_model
    );
    match (&r.cables, r.residual, r.iterations) {
        (Some(c), Some(res), Some(it)) => {
            println!(
                "feasible (residual {res:.3e} with the catenary forces, {it} fixed-point iterations)"
            );
            print_cables(c);
        }
        _ => println!("infeasible: {}", r.reason.as_deref().unwrap_or_default()),
    }
    Ok(())
}

/// `cdpr forward --unstrained-lengths … --cable-model elastic|catenary`: the elasto-geometric
/// forward kinematics ([`ElastoGeometricRequest`]) under the platform's weight (and springs)
/// from the robot file plus `wrench`, from `guess` or else from the straight cables' poses for
/// the unstrained lengths (multi-start).
pub fn forward(
    robot: RobotDescription,
    args: &CableModelArgs,
    l0: &[f64],
    wrench: Option<&[f64]>,
    guess: Option<&[f64]>,
    json_out: bool,
) -> Result<(), CliError> {
    let request = ElastoGeometricRequest {
        robot: cdpr::api::Robot::from_description(robot),
        unstrained_lengths: l0.to_vec(),
        cable_model: args.api_name(),
        wrench: wrench.map(<[f64]>::to_vec),
        guess: guess.map(<[f64]>::to_vec),
    };
    let r = request.run()?;
    if json_out {
        return print_report(&r);
    }
    let motion = request.robot.robot.motion();
    println!(
        "robot {} ({motion}), cable model {}, w_ext {}",
        r.robot,
        r.cable_model,
        super::wrench_text(&r.external_wrench, motion.translation_dof()),
    );
    println!(
        "{} after {} iterations: pose {} (m, rad), residual {:.3e} N",
        r.status,
        r.iterations,
        super::pose_text(&r.pose, motion.space_dim()),
        r.residual
    );
    if !r.slack_cables.is_empty() {
        println!("slack cables: {:?}", r.slack_cables);
    }
    print_cables(&r.cables);
    Ok(())
}

/// A cable drawn as points (m, base coordinates).
type Polyline = Vec<[f64; 3]>;

/// Points drawn per sagging cable.
const CURVE_POINTS: usize = 33;

/// The sagging cables of a 3-D plot's draw pose under `--cable-model catenary` (`model`, the
/// criteria's spelling; other models draw straight cables): the l2 sagging statics
/// ([`SaggingStatics`]) under the robot file's load at `pose`, each cable the polyline of its
/// catenary, and a legend line. No curves, and a legend line saying so, where the pose has no
/// sagging equilibrium.
pub fn draw_curves(
    desc: &RobotDescription,
    model: Option<&str>,
    pose: &cdpr::kinematics::Pose,
) -> Result<(Vec<Polyline>, Option<String>), CliError> {
    if model != Some("catenary") {
        return Ok((Vec::new(), None));
    }
    let Some(cats) = cdpr::api::cable_model::catenaries(desc, CableModel::Catenary)? else {
        return Ok((Vec::new(), None));
    };
    let kin = desc.robot.inverse_kinematics(pose)?;
    let w_ext = desc.load_wrench(pose)?;
    let outcome = SaggingStatics::new(SaggingSettings::default()).solve(
        &mut TensionSolver::new(Method::L2),
        &kin,
        &cats,
        &w_ext,
        &desc.bounds,
    )?;
    let SaggingOutcome::Feasible(s) = outcome else {
        return Ok((
            Vec::new(),
            Some("cables drawn straight: no sagging-cable equilibrium at the draw pose".into()),
        ));
    };
    let up = cats.up();
    let curves = s
        .cables
        .iter()
        .zip(cats.cables())
        .zip(kin.cables())
        .map(|((c, m), k)| {
            let a = k.attachment_point + k.vector;
            c.polyline(m, &a, &k.attachment_point, &up, CURVE_POINTS)
                .iter()
                .map(|p| [p.x, p.y, p.z])
                .collect()
        })
        .collect();
    let sag = s.cables.iter().map(|c| c.max_sag).fold(0.0, f64::max);
    Ok((
        curves,
        Some(format!(
            "cables drawn as catenaries (l2 statics at the draw pose; largest sag {sag:.3} m)"
        )),
    ))
}

//! # Cable models of a request
//!
//! `straight` (massless, inextensible: every result as in the classical model), `elastic`
//! (massless springs, L0 = l/(1 + t/EA), l the whole length, over pulleys too; needs
//! `axial_stiffness`) or `catenary` (heavy elastic
//! cables, Irvine's elastic catenary; needs `axial_stiffness` and `linear_density`), and the flex
//! and sag compensation along a path: per pose, the sagging-cable statics' platform-end tensions
//! and the unstrained lengths the winches pay out for the platform to be there.
//!
//! ## References
//! - Irvine 1981, *Cable Structures*, §2.3 (the elastic catenary).
//! - docs/algorithms.md, "Sagging cables".

use cdpr_dynamics::{DynamicsError, Winch};
use cdpr_io::RobotDescription;
use cdpr_kinematics::{CableModel, Pose, RobotCatenaries};
use cdpr_tension::{Method, SaggingOutcome, SaggingSettings, SaggingStatics, TensionSolver};
use nalgebra::DVector;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::ApiError;

/// The spelling of a cable model in a request (`--cable-model`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum CableModelName {
    /// Massless inextensible straight cables (the default).
    #[default]
    Straight,
    /// Massless elastic straight cables.
    Elastic,
    /// Heavy elastic cables (elastic catenary).
    Catenary,
}

impl CableModelName {
    /// The model.
    pub fn model(self) -> CableModel {
        match self {
            Self::Straight => CableModel::Straight,
            Self::Elastic => CableModel::Elastic,
            Self::Catenary => CableModel::Catenary,
        }
    }

    /// Whether the model is the default straight one.
    pub fn is_straight(&self) -> bool {
        *self == Self::Straight
    }
}

/// The robot's cables under `model`: `None` for straight cables; an error when the robot file
/// lacks the keys the model needs, or for `catenary` on a robot with pulleys (elastic cables
/// over pulleys are modelled: docs/algorithms.md, "Elastic cables over pulleys").
pub fn catenaries(
    robot: &RobotDescription,
    model: CableModel,
) -> Result<Option<RobotCatenaries>, ApiError> {
    if model == CableModel::Straight {
        return Ok(None);
    }
    let name = model.name();
    if model == CableModel::Catenary
        && let Some(i) = robot.robot.cables().iter().position(|c| c.pulley.is_some())
    {
        return Err(ApiError::invalid(format!(
            "--cable-model catenary does not model pulleys yet (cable {} has one); use --cable-model elastic, --kinematics standard or a robot without pulleys",
            i + 1
        )));
    }
    let es = robot.axial_stiffness.as_ref().ok_or_else(|| {
        ApiError::invalid(format!(
            "--cable-model {name} needs `axial_stiffness` (E·S, N) on every cable of the robot file"
        ))
    })?;
    Ok(Some(match model {
        CableModel::Elastic => RobotCatenaries::elastic(es)?,
        _ => {
            let rho = robot.linear_density.as_ref().ok_or(ApiError::invalid(
                "--cable-model catenary needs `linear_density` (kg/m) on every cable of the robot file",
            ))?;
            RobotCatenaries::new(rho, es, &robot.platform.gravity)?
        }
    }))
}

/// Flex and sag compensation along poses: per pose the unstrained lengths L0 (m), the
/// platform-end tensions (N) and, with winches, the drum angles (rad), `None` where the sagging-cable statics have no certified
/// equilibrium, and then its reason.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Compensation {
    /// L0 per cable (m) per pose.
    pub unstrained_lengths: Vec<Option<Vec<f64>>>,
    /// Platform-end tensions (N) per pose.
    pub platform_end_tensions: Vec<Option<Vec<f64>>>,
    /// Why a pose has no equilibrium.
    pub reasons: Vec<Option<String>>,
    /// With a `winch` on every cable: per pose the drum angles φ_i (rad) that pay out the
    /// unstrained lengths, L0_i/ρ_i with ρ_i the winch's payout radius (the drum radius, or
    /// with `cable_diameter` d the single-layer helix √((r + d/2)² + (d/2π)²)), or on a
    /// multi-layer drum (`turns_per_layer` N, `cable_length` C) Φ(C) − Φ(C − L0_i)
    /// ([`Winch::drum_angle_at`]); `None` without winches.
    pub drum_angles: Option<Vec<Option<Vec<f64>>>>,
}

/// Runs [`SaggingStatics`] with `method` at every pose, under the wrench `w_ext(k)`.
pub fn compensation(
    robot: &RobotDescription,
    model: &RobotCatenaries,
    method: Method,
    poses: &[Pose],
    w_ext: impl Fn(usize) -> DVector<f64>,
) -> Result<Compensation, ApiError> {
    if method == Method::Sotda {
        return Err(ApiError::invalid(
            "--cable-model elastic|catenary does not apply to sotda",
        ));
    }
    let mut statics = SaggingStatics::new(SaggingSettings::default());
    let mut solver = TensionSolver::new(method);
    let mut out = Compensation::default();
    for (k, pose) in poses.iter().enumerate() {
        let kin = robot.robot.inverse_kinematics(pose)?;
        match statics.solve(&mut solver, &kin, model, &w_ext(k), &robot.bounds)? {
            SaggingOutcome::Feasible(s) => {
                let lengths = s.cables.iter().map(|c| c.unstrained_length).collect();
                out.unstrained_lengths.push(Some(lengths));
                out.platform_end_tensions
                    .push(Some(s.tensions.as_slice().to_vec()));
                out.reasons.push(None);
            }
            SaggingOutcome::Infeasible(r) => {
                out.unstrained_lengths.push(None);
                out.platform_end_tensions.push(None);
                out.reasons.push(Some(r.to_string()));
            }
        }
    }
    if let Some(winches) = &robot.winches {
        out.drum_angles = Some(drum_angles(winches, &out.unstrained_lengths)?);
    }
    Ok(out)
}

/// Per pose the drum angles (rad) that pay out the lengths L0 ([`Winch::drum_angle_at`]: on a
/// multi-layer drum Φ(C) − Φ(C − L0)); an L0 beyond a winch's `cable_length` is an error
/// naming the cable and the pose.
fn drum_angles(
    winches: &[Winch],
    lengths: &[Option<Vec<f64>>],
) -> Result<Vec<Option<Vec<f64>>>, ApiError> {
    lengths
        .iter()
        .enumerate()
        .map(|(k, l)| {
            l.as_ref()
                .map(|l| {
                    l.iter()
                        .zip(winches)
                        .enumerate()
                        .map(|(i, (&l, w))| {
                            w.drum_angle_at(l).map_err(|e| match e {
                                DynamicsError::PaidOutLength {
                                    length,
                                    cable_length,
                                    ..
                                } => ApiError::invalid(format!(
                                    "pose {}: {}",
                                    k + 1,
                                    DynamicsError::PaidOutLength {
                                        cable: Some(i + 1),
                                        time: None,
                                        length,
                                        cable_length,
                                    }
                                )),
                                e => e.into(),
                            })
                        })
                        .collect()
                })
                .transpose()
        })
        .collect()
}

//! `--criteria dynamic --acceleration-box A1,…,Ad [--velocity V1,…,Vd]` of the workspace
//! commands (issue 28): the dynamic feasible workspace, decided by the capacity margin of the
//! zonotope of required wrenches (`cdpr_dynamics::DynamicFeasibility`).

use super::CliError;
use super::Numbers;
use cdpr::RobotDescription;
use cdpr::dynamics::{DynamicFeasibility, RigidBody};
use cdpr::workspace::Criterion;
use cdpr::workspace::CriterionSpec as Spec;

/// What the `dynamic` criterion needs from the command line and the robot file.
#[derive(Debug, Clone)]
pub struct DynamicSetup {
    body: RigidBody,
    acceleration_box: Vec<f64>,
    velocity: Vec<f64>,
}

/// Reads --acceleration-box/--velocity when `dynamic` is among the criteria (usage errors
/// otherwise: a box without the criterion, the criterion without a box, wrong sizes).
pub fn setup(
    acceleration_box: Option<&Numbers>,
    velocity: Option<&Numbers>,
    desc: &RobotDescription,
    specs: &[Spec],
) -> Result<Option<DynamicSetup>, CliError> {
    let wanted = specs.contains(&Spec::Dynamic);
    let dof = desc.robot.dof();
    match (acceleration_box, wanted) {
        (None, false) => Ok(None),
        (Some(_), false) => Err("--acceleration-box needs `dynamic` in --criteria".into()),
        (None, true) => Err(
            "--criteria dynamic needs --acceleration-box A1,…,Ad (half-widths, m/s² and rad/s²)"
                .into(),
        ),
        (Some(a), true) => {
            if a.len() != dof {
                return Err(format!(
                    "--acceleration-box needs {dof} half-widths (one per DOF), got {}",
                    a.len()
                )
                .into());
            }
            if let Some(x) = a.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
                return Err(format!("--acceleration-box: {x} must be a finite number ≥ 0").into());
            }
            let velocity = match velocity {
                Some(v) if v.len() != dof => {
                    return Err(format!(
                        "--velocity needs {dof} numbers (one per DOF), got {}",
                        v.len()
                    )
                    .into());
                }
                Some(v) => v.0.clone(),
                None => vec![0.0; dof],
            };
            if let Some(x) = velocity.iter().find(|x| !x.is_finite()) {
                return Err(format!("--velocity: {x} is not finite").into());
            }
            Ok(Some(DynamicSetup {
                body: super::time_law::rigid_body(desc)?,
                acceleration_box: a.0.clone(),
                velocity,
            }))
        }
    }
}

/// The criterion for an evaluator, with the constant w_e of the command line.
pub fn criterion(
    setup: Option<&DynamicSetup>,
    desc: &RobotDescription,
    wrench: Option<&[f64]>,
) -> Result<Criterion, CliError> {
    let s = setup.ok_or("--criteria dynamic needs --acceleration-box")?;
    let w = super::wrench(desc, wrench)?;
    let test = DynamicFeasibility::new(
        desc.robot.motion(),
        &desc.bounds,
        s.body,
        &s.acceleration_box,
        &s.velocity,
        w.as_slice(),
    )?;
    Ok(cdpr::workspace::dynamic_criterion(test))
}

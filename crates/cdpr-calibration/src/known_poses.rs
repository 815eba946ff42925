//! # Calibration from known poses
//!
//! When an external tracker measures the pose x_k of every sample, each cable's parameters
//! (anchor c_i, attachment ā_i, offset o_i, gain g_i) enter only that cable's readings:
//! the least-squares problem splits into one small problem per cable,
//!
//! ```text
//!   min Σ_k ( ‖c_i − p_k − R_k ā_i‖ − g_i ρ_ki − o_i )²
//! ```
//!
//! solved together by the adjustment ([`crate::adjustment`], whose normal matrix is then
//! block-diagonal by cable). No gauge: the known poses fix the base frame. Each cable needs at
//! least as many samples as it has unknowns (the counting rule with d = 0). Cables over swivel
//! pulleys have the pulley model's length ([`crate::model`]), the pulleys held at their nominal
//! radius and orientation.
//!
//! ## References
//! - Pott, *Cable-Driven Parallel Robots*, Springer 2018, §5 (calibration with an external
//!   measurement system).

use crate::adjustment::Problem;
use crate::gauge::{Gauge, ParameterSpace};
use crate::identifiability::counting_rule;
use crate::{Calibration, CalibrationError, Parameters, Readings, Samples, Unknowns};
use cdpr_kinematics::Robot;

/// Calibrates `unknowns` of `robot` from readings at known poses (`samples.poses` required).
pub fn calibrate_known_poses(
    robot: &Robot,
    samples: &Samples,
    unknowns: Unknowns,
    readings: &Readings,
) -> Result<Calibration, CalibrationError> {
    known_poses_from(
        robot,
        Parameters::nominal(robot),
        samples,
        unknowns,
        readings,
    )
}

/// [`calibrate_known_poses`] from `nominal` (its offsets and gains: an earlier calibration).
pub(crate) fn known_poses_from(
    robot: &Robot,
    nominal: Parameters,
    samples: &Samples,
    unknowns: Unknowns,
    readings: &Readings,
) -> Result<Calibration, CalibrationError> {
    let (n, motion) = (robot.cable_count(), robot.motion());
    let k = crate::check_inputs(robot, samples, unknowns)?;
    let pulleys = crate::pulleys(robot);
    let Some(poses) = samples.poses.clone() else {
        return Err(CalibrationError::WrongCount {
            what: "known poses (one per sample)".into(),
            expected: k,
            found: 0,
        });
    };
    let space = ParameterSpace::new(motion, &nominal, unknowns, Gauge::None)?;
    let p = space.parameters.len();
    let counting = counting_rule(k, n, motion.dof(), p, 0, true);
    if !counting.holds {
        return Ok(Calibration::not_identifiable(
            nominal,
            poses,
            false,
            counting,
            Vec::new(),
        ));
    }
    let problem = Problem {
        motion,
        space: &space,
        readings,
        rho: &samples.readings,
        n,
        estimate_poses: false,
        pulleys: pulleys.as_deref(),
    };
    let fit = problem.solve(nominal, poses, robot.length_scale())?;
    Ok(Calibration::from_fit(fit, &space, unknowns, counting, n, 0))
}

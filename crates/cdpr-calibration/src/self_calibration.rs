//! # Self-calibration (unknown poses)
//!
//! Without a tracker, the poses x_1 … x_k of the samples are unknowns too: the parameters and
//! the poses are adjusted together (Borgstrom et al. 2009; Miermeister & Pott 2012),
//!
//! ```text
//!   min over θ, x_1…x_k of Σ_k Σ_i ( l_i(x_k; θ) − g_i ρ_ki − o_i )²
//! ```
//!
//! with the gauge fixed ([`crate::gauge`]). The starting poses are the forward kinematics of
//! the nominal robot on the readings taken at face value (l = g ρ + o with the nominal gains
//! and offsets): each sample from the previous sample's pose, or by the multi-start when that
//! does not give a solution nor a least-squares pose within twice the misfit the multi-start
//! found so far ([`cdpr_kinematics::ForwardKinematics`]). Levenberg–Marquardt then
//! runs on poses and parameters at once ([`crate::adjustment`]). Identifiable only if
//! k (n − d) ≥ p − g ([`crate::identifiability`]); a robot with n = d never is.
//!
//! ## References
//! - Borgstrom, Jordan, Borgstrom, Stealey, Sukhatme, Batalin & Kaiser 2009, *NIMS-PL: A
//!   cable-driven robot with self-calibration capabilities*, IEEE T-RO 25(5).
//! - Miermeister & Pott 2012, *Auto-calibration method for overconstrained cable-driven
//!   parallel robots*, ICRA.

use crate::adjustment::Problem;
use crate::gauge::{Gauge, ParameterSpace};
use crate::identifiability::counting_rule;
use crate::model::cable;
use crate::{Calibration, CalibrationError, Parameters, Readings, Samples, Unknowns};
use cdpr_kinematics::{ForwardKinematics, ForwardSettings, ForwardStatus, Pose, Robot};

/// Self-calibrates `unknowns` of `robot` from readings at unknown poses (`samples.poses` is
/// ignored).
pub fn self_calibrate(
    robot: &Robot,
    samples: &Samples,
    unknowns: Unknowns,
    readings: &Readings,
) -> Result<Calibration, CalibrationError> {
    self_calibrate_from(
        robot,
        Parameters::nominal(robot),
        samples,
        unknowns,
        readings,
    )
}

/// [`self_calibrate`] from `nominal` (its offsets and gains: an earlier calibration).
pub(crate) fn self_calibrate_from(
    robot: &Robot,
    nominal: Parameters,
    samples: &Samples,
    unknowns: Unknowns,
    readings: &Readings,
) -> Result<Calibration, CalibrationError> {
    let (n, motion) = (robot.cable_count(), robot.motion());
    let d = motion.dof();
    let k = crate::check_inputs(robot, samples, unknowns)?;
    if robot.has_pulleys() {
        return Err(CalibrationError::Pulleys);
    }
    let pulleys = crate::pulleys(robot);
    // Relative readings without unknown offsets see translations: only rotations about the
    // reference point remain (module `gauge`).
    let gauge = match readings {
        Readings::Relative { reference } if !unknowns.offsets => {
            if unknowns.platform {
                return Err(CalibrationError::Unsupported(
                    "self-calibration of platform attachments from relative readings without \
                     unknown offsets",
                ));
            }
            Gauge::RotationsAbout(reference.position)
        }
        _ => Gauge::Rigid,
    };
    let space = ParameterSpace::new(motion, &nominal, unknowns, gauge)?;
    let p = space.parameters.len() + space.gauge;
    let counting = counting_rule(k, n, d, p, space.gauge, false);
    if !counting.holds {
        return Ok(Calibration::not_identifiable(
            nominal,
            Vec::new(),
            true,
            counting,
            space.fixed.clone(),
        ));
    }
    let poses = starting_poses(robot, &nominal, samples, readings, k)?;
    let problem = Problem {
        motion,
        space: &space,
        readings,
        rho: &samples.readings,
        n,
        estimate_poses: true,
        pulleys: pulleys.as_deref(),
    };
    let fit = problem.solve(nominal, poses, robot.length_scale())?;
    Ok(Calibration::from_fit(fit, &space, unknowns, counting, n, d))
}

/// The forward kinematics of the nominal robot on the readings taken at face value.
fn starting_poses(
    robot: &Robot,
    nominal: &Parameters,
    samples: &Samples,
    readings: &Readings,
    k: usize,
) -> Result<Vec<Pose>, CalibrationError> {
    let n = robot.cable_count();
    let mut fk = ForwardKinematics::new(robot, ForwardSettings::default())?;
    let reference: Vec<f64> = (0..n)
        .map(|i| match readings {
            Readings::Absolute => 0.0,
            Readings::Relative { reference } => {
                cable(&nominal.frame[i], &nominal.platform[i], reference).0
            }
        })
        .collect();
    let mut poses = Vec::with_capacity(k);
    let mut lengths = vec![0.0; n];
    // The largest residual_rms of the multi-start answers so far: the misfit of the nominal
    // robot on readings taken at face value (unknown offsets of centimetres make every sample
    // `inconsistent`, so "is a solution" cannot be the test of a warm start).
    let mut typical_misfit: Option<f64> = None;
    for s in 0..k {
        for i in 0..n {
            let rho = samples.readings[s * n + i];
            lengths[i] = (nominal.gains[i] * rho + nominal.offsets[i] + reference[i]).max(0.0);
        }
        // Warm start from the previous sample's pose: kept when it answers the lengths, or
        // when it converged to a least-squares pose no worse than twice the typical misfit
        // (a far-off local minimum has a much larger residual); otherwise the multi-start.
        let from_previous = match poses.last() {
            Some(prev) => fk.solve(&lengths, prev).ok().filter(|s| {
                s.status.is_solution()
                    || (s.converged
                        && s.status == ForwardStatus::Inconsistent
                        && typical_misfit.is_some_and(|t| s.residual_rms <= 2.0 * t))
            }),
            None => None,
        };
        let sol = match from_previous {
            Some(s) => s,
            None => {
                let best = fk.solve_multistart(&lengths)?[0];
                typical_misfit = Some(typical_misfit.unwrap_or(0.0).max(best.residual_rms));
                best
            }
        };
        poses.push(sol.pose);
    }
    Ok(poses)
}

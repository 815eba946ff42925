//! # The calibration report
//!
//! What a calibration found: the calibrated parameters, their standard deviations
//! σ̂ √diag((JᵀJ)⁻¹) (σ̂² = ‖r‖²/(N − P), [`crate::covariance`]), the poses, the residual, and
//! the identifiability verdict (counting rule, rank, conditioning).

use crate::adjustment::Fit;
use crate::gauge::{Parameter, ParameterSpace};
use crate::identifiability::Counting;
use crate::{Parameters, Unknowns};
use cdpr_kinematics::Pose;
use cdpr_kinematics::nalgebra::Vector3;

/// Condition number above which the report warns that the samples determine the parameters
/// poorly.
pub const CONDITION_WARNING: f64 = 1e3;

/// Standard deviations of the calibrated parameters, per group (`None`: not an unknown).
/// Coordinates held by the gauge have σ = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterSigma {
    /// Of each anchor coordinate (m).
    pub frame: Option<Vec<Vector3<f64>>>,
    /// Of each attachment coordinate (m).
    pub platform: Option<Vec<Vector3<f64>>>,
    /// Of each offset (m).
    pub offsets: Option<Vec<f64>>,
    /// Of each gain.
    pub gains: Option<Vec<f64>>,
}

/// The outcome of a calibration.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// The calibrated parameters (the nominal ones where not unknown, or when not identifiable).
    pub parameters: Parameters,
    /// Standard deviations (`None` when not identifiable or too few residuals to estimate σ).
    pub sigma: Option<ParameterSigma>,
    /// The poses of the samples: estimated (self-calibration) or the known ones.
    pub poses: Vec<Pose>,
    /// Whether the poses were estimated.
    pub poses_estimated: bool,
    /// √(Σ r² / N) over the N = k n readings (m).
    pub residual_rms: f64,
    /// max |r| (m).
    pub residual_max: f64,
    /// σ̂ = √(Σ r² / (N − P)), the length noise estimated from the residual (m); `None` when
    /// N ≤ P.
    pub length_sigma: Option<f64>,
    /// The counting rule k (n − d) ≥ p − g.
    pub counting: Counting,
    /// The counting rule holds and the Jacobian has full rank at the solution.
    pub identifiable: bool,
    /// Directions of the parameters (and poses) the readings do not determine.
    pub rank_deficiency: usize,
    /// Condition number of the column-scaled Jacobian (parameter block after eliminating the
    /// poses).
    pub condition_number: f64,
    /// What the gauge holds at its nominal values.
    pub gauge: Vec<String>,
    /// Levenberg–Marquardt iterations.
    pub iterations: usize,
    /// Whether the iteration converged.
    pub converged: bool,
    /// Warnings (ill-conditioning, rank deficiency).
    pub warnings: Vec<String>,
}

impl Calibration {
    /// A report for a problem the counting rule rejects: the nominal parameters, no fit.
    pub(crate) fn not_identifiable(
        nominal: Parameters,
        poses: Vec<Pose>,
        poses_estimated: bool,
        counting: Counting,
        gauge: Vec<String>,
    ) -> Self {
        Self {
            parameters: nominal,
            sigma: None,
            poses,
            poses_estimated,
            residual_rms: f64::NAN,
            residual_max: f64::NAN,
            length_sigma: None,
            counting,
            identifiable: false,
            rank_deficiency: 0,
            condition_number: f64::INFINITY,
            gauge,
            iterations: 0,
            converged: false,
            warnings: Vec::new(),
        }
    }

    /// The report of a fit.
    pub(crate) fn from_fit(
        fit: Fit,
        space: &ParameterSpace,
        unknowns: Unknowns,
        counting: Counting,
        n: usize,
        pose_dof: usize,
    ) -> Self {
        let k = fit.poses.len();
        let readings = k * n;
        let poses_estimated = pose_dof > 0;
        let unknowns_total = space.parameters.len() + k * pose_dof;
        let length_sigma = (readings > unknowns_total)
            .then(|| (fit.squared / (readings - unknowns_total) as f64).sqrt());
        let rank_deficiency = fit.analysis.rank_deficiency + fit.singular_poses;
        let identifiable = counting.holds && rank_deficiency == 0;
        let mut warnings = Vec::new();
        if rank_deficiency > 0 {
            warnings.push(format!(
                "the readings do not determine {rank_deficiency} combination(s) of the unknowns \
                 (rank deficiency{}): more varied poses or fewer unknowns",
                if fit.singular_poses > 0 {
                    format!(", {} sample pose(s) undetermined", fit.singular_poses)
                } else {
                    String::new()
                }
            ));
        } else if fit.analysis.condition_number > CONDITION_WARNING {
            warnings.push(format!(
                "condition number {:.3e} > {CONDITION_WARNING:e}: the samples determine the \
                 parameters poorly (spread the poses over the workspace)",
                fit.analysis.condition_number
            ));
        }
        if !fit.converged {
            warnings.push(format!(
                "Levenberg–Marquardt did not converge in {} iterations",
                fit.iterations
            ));
        }
        let sigma = match (&fit.analysis.inverse, length_sigma, identifiable) {
            (Some(inv), Some(s), true) => Some(sigma_of(space, inv, s, unknowns, n)),
            _ => None,
        };
        Self {
            parameters: fit.parameters,
            sigma,
            poses: fit.poses,
            poses_estimated,
            residual_rms: (fit.squared / readings as f64).sqrt(),
            residual_max: fit.max_residual,
            length_sigma,
            counting,
            identifiable,
            rank_deficiency,
            condition_number: fit.analysis.condition_number,
            gauge: space.fixed.clone(),
            iterations: fit.iterations,
            converged: fit.converged,
            warnings,
        }
    }
}

/// Per-coordinate σ from the covariance σ̂² S⁻¹ of the free parameters: a coordinate moved by
/// several free directions e_j has variance Σ_jl e_j[c] e_l[c] Cov_jl.
fn sigma_of(
    space: &ParameterSpace,
    inv: &cdpr_kinematics::nalgebra::DMatrix<f64>,
    s: f64,
    unknowns: Unknowns,
    n: usize,
) -> ParameterSigma {
    let mut frame = vec![Vector3::zeros(); n];
    let mut platform = vec![Vector3::zeros(); n];
    let mut offsets = vec![0.0; n];
    let mut gains = vec![0.0; n];
    let params = &space.parameters;
    for (j, pj) in params.iter().enumerate() {
        match *pj {
            Parameter::Offset { cable } => offsets[cable] = s * inv[(j, j)].sqrt(),
            Parameter::Gain { cable } => gains[cable] = s * inv[(j, j)].sqrt(),
            Parameter::Frame { .. } | Parameter::Platform { .. } => {}
        }
    }
    for (is_frame, out) in [(true, &mut frame), (false, &mut platform)] {
        for (cable, slot) in out.iter_mut().enumerate() {
            let dirs: Vec<(usize, Vector3<f64>)> = params
                .iter()
                .enumerate()
                .filter_map(|(j, p)| match *p {
                    Parameter::Frame {
                        cable: c,
                        direction,
                    } if is_frame && c == cable => Some((j, direction)),
                    Parameter::Platform {
                        cable: c,
                        direction,
                    } if !is_frame && c == cable => Some((j, direction)),
                    _ => None,
                })
                .collect();
            for axis in 0..3 {
                let var: f64 = dirs
                    .iter()
                    .flat_map(|(j, ej)| {
                        dirs.iter()
                            .map(move |(l, el)| ej[axis] * el[axis] * inv[(*j, *l)])
                    })
                    .sum();
                slot[axis] = if var > 0.0 { s * var.sqrt() } else { 0.0 };
            }
        }
    }
    ParameterSigma {
        frame: unknowns.frame.then_some(frame),
        platform: unknowns.platform.then_some(platform),
        offsets: unknowns.offsets.then_some(offsets),
        gains: unknowns.gains.then_some(gains),
    }
}

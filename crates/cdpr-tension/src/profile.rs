//! # Tension profiles along a path
//!
//! The tensions a robot needs along a motion: one certified tension distribution per path sample
//! (any [`Method`](crate::Method)), infeasible samples kept with their path parameter and reason,
//! and the continuity of the result: the largest jump per cable between consecutive samples.
//! Thesis Fig. 6.6 shows that minimum-norm tensions can jump; Picard, Caro, Plestan & Claveau 2020, §4 reports SOTDA
//! tensions staying continuous.

use crate::{
    StiffnessData, TensionBounds, TensionError, TensionOutcome, TensionProblem, TensionSolver,
};
use cdpr_kinematics::{MotionPattern, Path, PathSample, Pose, PoseKinematics, Robot};
use nalgebra::{DMatrix, DVector};

/// Tensions along a sampled path.
#[derive(Debug, Clone, PartialEq)]
pub struct TensionProfile {
    /// Path parameter s ∈ [0, 1] of each sample.
    pub s: Vec<f64>,
    /// Tensions per sample, `None` where infeasible.
    pub tensions: Vec<Option<DVector<f64>>>,
    /// Why a sample is infeasible (`None` where feasible).
    pub reasons: Vec<Option<String>>,
    /// Per cable, the largest |t_i(k+1) − t_i(k)| over consecutive feasible samples.
    pub max_jump: Vec<f64>,
}

impl TensionProfile {
    /// Number of feasible samples.
    pub fn feasible_count(&self) -> usize {
        self.tensions.iter().filter(|t| t.is_some()).count()
    }

    /// Largest change of any cable tension between samples k and k+1 (both feasible), per k.
    pub fn jumps(&self) -> Vec<Option<f64>> {
        self.tensions
            .windows(2)
            .map(|w| match (&w[0], &w[1]) {
                (Some(a), Some(b)) => Some((b - a).amax()),
                _ => None,
            })
            .collect()
    }

    /// Indices k where the step k → k+1 looks like a discontinuity: its jump exceeds `ratio`
    /// times the median jump of the profile (and 10⁻⁹ of the largest tension). With samples
    /// refined, continuous profiles have jumps that shrink with the step; a discontinuity does not.
    pub fn discontinuities(&self, ratio: f64) -> Vec<usize> {
        let jumps = self.jumps();
        let mut finite: Vec<f64> = jumps.iter().flatten().copied().collect();
        if finite.is_empty() {
            return Vec::new();
        }
        finite.sort_by(f64::total_cmp);
        let median = finite[finite.len() / 2];
        let scale = self
            .tensions
            .iter()
            .flatten()
            .map(|t| t.amax())
            .fold(0.0, f64::max);
        let threshold = (ratio * median).max(1e-9 * scale);
        jumps
            .iter()
            .enumerate()
            .filter_map(|(k, j)| j.filter(|&j| j > threshold).map(|_| k))
            .collect()
    }
}

/// External wrenches given at the waypoints of a path, interpolated linearly in the path
/// parameter s between consecutive waypoints. Waypoint k sits at s_k = (length of the path
/// through waypoints 0…k) / (total length), lengths by the pose distance of
/// [`cdpr_kinematics::Path`]; on a path of zero length every waypoint after the first sits at 1.
#[derive(Debug, Clone, PartialEq)]
pub struct WaypointWrenches {
    s: Vec<f64>,
    wrenches: Vec<DVector<f64>>,
}

impl WaypointWrenches {
    /// One wrench per waypoint (at least two waypoints).
    pub fn new(
        motion: MotionPattern,
        poses: &[Pose],
        wrenches: Vec<DVector<f64>>,
    ) -> Result<Self, TensionError> {
        if poses.len() < 2 {
            return Err(TensionError::DimensionMismatch {
                what: "waypoints of a path (at least)",
                expected: 2,
                found: poses.len(),
            });
        }
        if wrenches.len() != poses.len() {
            return Err(TensionError::DimensionMismatch {
                what: "waypoint wrenches (one per waypoint)",
                expected: poses.len(),
                found: wrenches.len(),
            });
        }
        let length = |k: usize| {
            Path::new(motion, poses[..=k].to_vec())
                .map(|p| p.length())
                .unwrap_or(0.0)
        };
        let total = length(poses.len() - 1);
        let s = (0..poses.len())
            .map(|k| match k {
                0 => 0.0,
                _ if total == 0.0 => 1.0,
                _ => length(k) / total,
            })
            .collect();
        Ok(Self { s, wrenches })
    }

    /// s_k of each waypoint.
    pub fn waypoint_s(&self) -> &[f64] {
        &self.s
    }

    /// The wrench at path parameter s: (1 − τ) w_k + τ w_{k+1} on the segment s_k ≤ s ≤ s_{k+1}
    /// (τ clamped to [0, 1]; w_{k+1} on a segment of zero length).
    pub fn at(&self, s: f64) -> DVector<f64> {
        let k = self
            .s
            .partition_point(|&c| c <= s)
            .clamp(1, self.s.len() - 1)
            - 1;
        let span = self.s[k + 1] - self.s[k];
        let tau = if span > 0.0 {
            ((s - self.s[k]) / span).clamp(0.0, 1.0)
        } else {
            1.0
        };
        &self.wrenches[k] * (1.0 - tau) + &self.wrenches[k + 1] * tau
    }
}

/// Tensions along `samples` with `solver` (its method and settings), bounds `bounds`, and the
/// external wrench `wrench_at(sample)` (e.g. constant, or with the gravity of the platform).
/// `axial_stiffness` (E·S per cable) is needed by SOTDA only.
///
/// A sample where a cable has zero length is reported infeasible with that reason.
pub fn tension_profile(
    robot: &Robot,
    samples: &[PathSample],
    bounds: &TensionBounds,
    solver: &mut TensionSolver,
    axial_stiffness: Option<&[f64]>,
    mut wrench_at: impl FnMut(&PathSample) -> DVector<f64>,
) -> Result<TensionProfile, TensionError> {
    let n = robot.cable_count();
    let mut kin = PoseKinematics::for_robot(robot);
    let mut w = DMatrix::zeros(robot.dof(), n);
    let mut profile = TensionProfile {
        s: Vec::with_capacity(samples.len()),
        tensions: Vec::with_capacity(samples.len()),
        reasons: Vec::with_capacity(samples.len()),
        max_jump: vec![0.0; n],
    };
    for sample in samples {
        profile.s.push(sample.s);
        if let Err(e) = robot.update_kinematics(&sample.pose, &mut kin) {
            profile.tensions.push(None);
            profile.reasons.push(Some(e.to_string()));
            continue;
        }
        kin.write_wrench_matrix(&mut w);
        let w_ext = wrench_at(sample);
        let mut problem = TensionProblem::new(&w, &w_ext, bounds);
        if let Some(es) = axial_stiffness {
            problem.stiffness = Some(StiffnessData {
                kinematics: &kin,
                axial_stiffness: es,
            });
        }
        match solver.solve(&problem)? {
            TensionOutcome::Feasible(s) => {
                profile.tensions.push(Some(s.tensions));
                profile.reasons.push(None);
            }
            TensionOutcome::Infeasible(r) => {
                profile.tensions.push(None);
                profile.reasons.push(Some(r.to_string()));
            }
        }
    }
    for pair in profile.tensions.windows(2) {
        if let (Some(a), Some(b)) = (&pair[0], &pair[1]) {
            for (m, (x, y)) in profile.max_jump.iter_mut().zip(a.iter().zip(b.iter())) {
                *m = m.max((y - x).abs());
            }
        }
    }
    Ok(profile)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Waypoints on a line 1 m then 3 m apart: s = 0, 0.25, 1; wrenches interpolate linearly
    /// on each segment.
    #[test]
    fn waypoint_wrenches_interpolate_in_s() {
        let poses = [
            Pose::point(0.0, 0.0, 0.0),
            Pose::point(1.0, 0.0, 0.0),
            Pose::point(4.0, 0.0, 0.0),
        ];
        let w = |v: f64| DVector::from_vec(vec![v, -v]);
        let ww = WaypointWrenches::new(MotionPattern::Point2, &poses, vec![w(0.0), w(4.0), w(8.0)])
            .unwrap();
        assert_eq!(ww.waypoint_s(), &[0.0, 0.25, 1.0]);
        assert_eq!(ww.at(0.125), w(2.0));
        assert_eq!(ww.at(0.625), w(6.0));
        assert_eq!(ww.at(1.0), w(8.0));
        let still = [poses[0], poses[0]];
        let ww =
            WaypointWrenches::new(MotionPattern::Point2, &still, vec![w(1.0), w(3.0)]).unwrap();
        assert_eq!(ww.waypoint_s(), &[0.0, 1.0]);
        assert!(WaypointWrenches::new(MotionPattern::Point2, &poses, vec![w(0.0)]).is_err());
        assert!(WaypointWrenches::new(MotionPattern::Point2, &poses[..1], vec![w(0.0)]).is_err());
    }
}

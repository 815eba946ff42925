//! # Paths
//!
//! A straight segment or a polyline through poses, sampled at a given count or step, for any
//! motion pattern. Positions are interpolated linearly; orientations along the shortest rotation
//! between waypoints (slerp; planar φ therefore varies linearly).
//!
//! The path parameter s runs from 0 to 1 in proportion to the pose distance
//! √(‖Δu‖² + θ²) along the polyline, θ being the rotation angle between waypoints in radians
//! (1 rad counts as one length unit). Every waypoint is a sample.

use crate::{KinematicsError, MotionPattern, Pose};

/// A polyline through two or more waypoints.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    motion: MotionPattern,
    waypoints: Vec<Pose>,
    /// Cumulative pose distance at each waypoint (first 0).
    cumulative: Vec<f64>,
}

/// How densely to sample a path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sampling {
    /// This many samples in all (at least 2), evenly spaced in s.
    Count(usize),
    /// Samples at most this pose distance apart (plus every waypoint).
    Step(f64),
}

/// One sample: path parameter s ∈ [0, 1] and the pose there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSample {
    /// Path parameter in [0, 1].
    pub s: f64,
    /// The pose.
    pub pose: Pose,
}

fn distance(a: &Pose, b: &Pose) -> f64 {
    let du = (b.position - a.position).norm_squared();
    let theta = a.rotation.angle_to(&b.rotation);
    (du + theta * theta).sqrt()
}

impl Path {
    /// A polyline through `waypoints` (coordinates of the motion pattern, at least two).
    ///
    /// ```
    /// use cdpr_kinematics::{MotionPattern, Path, Sampling};
    /// let path = Path::from_coordinates(MotionPattern::Planar, &[vec![0.0, 0.0, 0.0], vec![1.0, 0.0, 0.0]]).unwrap();
    /// let samples = path.sample(Sampling::Count(5)).unwrap();
    /// assert_eq!(samples.len(), 5);
    /// assert!((samples[2].pose.position.x - 0.5).abs() < 1e-15);
    /// ```
    pub fn from_coordinates(
        motion: MotionPattern,
        waypoints: &[Vec<f64>],
    ) -> Result<Self, KinematicsError> {
        let poses = waypoints
            .iter()
            .map(|q| Pose::from_coordinates(motion, q))
            .collect::<Result<Vec<_>, _>>()?;
        Self::new(motion, poses)
    }

    /// A polyline through poses (at least two).
    pub fn new(motion: MotionPattern, waypoints: Vec<Pose>) -> Result<Self, KinematicsError> {
        if waypoints.len() < 2 {
            return Err(KinematicsError::WrongDimension {
                what: "path waypoints".into(),
                motion: motion.name(),
                expected: 2,
                found: waypoints.len(),
            });
        }
        let mut cumulative = vec![0.0];
        for w in waypoints.windows(2) {
            let last = *cumulative.last().expect("non-empty");
            cumulative.push(last + distance(&w[0], &w[1]));
        }
        Ok(Self {
            motion,
            waypoints,
            cumulative,
        })
    }

    /// The motion pattern.
    pub fn motion(&self) -> MotionPattern {
        self.motion
    }

    /// Total pose distance along the polyline.
    pub fn length(&self) -> f64 {
        *self.cumulative.last().expect("at least two waypoints")
    }

    /// The pose at path parameter s ∈ [0, 1] (clamped).
    pub fn pose_at(&self, s: f64) -> Pose {
        let total = self.length();
        if total == 0.0 {
            return self.waypoints[0];
        }
        let d = s.clamp(0.0, 1.0) * total;
        let k = self
            .cumulative
            .partition_point(|&c| c <= d)
            .clamp(1, self.waypoints.len() - 1)
            - 1;
        let seg = self.cumulative[k + 1] - self.cumulative[k];
        let tau = if seg > 0.0 {
            ((d - self.cumulative[k]) / seg).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (a, b) = (&self.waypoints[k], &self.waypoints[k + 1]);
        let rotation = a
            .rotation
            .try_slerp(&b.rotation, tau, 1e-12)
            .unwrap_or(if tau < 0.5 { a.rotation } else { b.rotation });
        Pose::new(a.position.lerp(&b.position, tau), rotation)
    }

    /// Samples along the path, in order of s, including both ends.
    pub fn sample(&self, sampling: Sampling) -> Result<Vec<PathSample>, KinematicsError> {
        let total = self.length();
        let s_values: Vec<f64> = match sampling {
            Sampling::Count(n) => {
                if n < 2 {
                    return Err(KinematicsError::TooFewSamples {
                        found: n,
                        needed: 2,
                    });
                }
                (0..n).map(|i| i as f64 / (n - 1) as f64).collect()
            }
            Sampling::Step(h) => {
                if !(h.is_finite() && h > 0.0) {
                    return Err(KinematicsError::NotFinite {
                        what: "path step (must be positive)".into(),
                        value: h,
                    });
                }
                let mut s = vec![0.0];
                for w in self.cumulative.windows(2) {
                    let pieces = ((w[1] - w[0]) / h).ceil().max(1.0) as usize;
                    for p in 1..=pieces {
                        let d = w[0] + (w[1] - w[0]) * p as f64 / pieces as f64;
                        s.push(if total > 0.0 { d / total } else { 1.0 });
                    }
                }
                s
            }
        };
        Ok(s_values
            .into_iter()
            .map(|s| PathSample {
                s,
                pose: self.pose_at(s),
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// One sample is too few, and the message says so in the path's terms, not the motion
    /// pattern's (issue 25: "path samples has 1 components, the motion pattern point3 needs 2").
    #[test]
    fn one_sample_is_refused_by_name() {
        let p = Path::from_coordinates(
            MotionPattern::Point3,
            &[vec![0.0, 0.0, 0.0], vec![1.0, 0.0, 0.0]],
        )
        .unwrap();
        for n in [0, 1] {
            let e = p.sample(Sampling::Count(n)).unwrap_err();
            assert_eq!(
                e,
                KinematicsError::TooFewSamples {
                    found: n,
                    needed: 2
                }
            );
            assert_eq!(
                e.to_string(),
                format!("a path needs at least 2 samples (its two ends), got {n}")
            );
        }
        assert_eq!(p.sample(Sampling::Count(2)).unwrap().len(), 2);
    }

    #[test]
    fn polyline_passes_through_waypoints_with_proportional_s() {
        let p = Path::from_coordinates(
            MotionPattern::Point2,
            &[vec![0.0, 0.0], vec![3.0, 0.0], vec![3.0, 1.0]],
        )
        .unwrap();
        assert_relative_eq!(p.length(), 4.0);
        assert_relative_eq!(p.pose_at(0.75).position.x, 3.0);
        assert_relative_eq!(p.pose_at(0.875).position.y, 0.5);
        let samples = p.sample(Sampling::Step(0.5)).unwrap();
        assert_eq!(samples.len(), 9);
        assert!(samples.iter().any(|s| (s.pose.position.x - 3.0).abs() < 1e-15 && s.pose.position.y.abs() < 1e-15));
    }

    #[test]
    fn planar_angle_interpolates_linearly() {
        let p = Path::from_coordinates(
            MotionPattern::Planar,
            &[vec![0.0, 0.0, 0.0], vec![0.0, 0.0, 0.4]],
        )
        .unwrap();
        assert_relative_eq!(
            p.pose_at(0.5).coordinates(MotionPattern::Planar)[2],
            0.2,
            epsilon = 1e-12
        );
    }

    #[test]
    fn bad_paths_are_errors() {
        assert!(Path::from_coordinates(MotionPattern::Point2, &[vec![0.0, 0.0]]).is_err());
        let p = Path::from_coordinates(MotionPattern::Point2, &[vec![0.0, 0.0], vec![1.0, 0.0]])
            .unwrap();
        assert!(p.sample(Sampling::Count(1)).is_err());
        assert!(p.sample(Sampling::Step(0.0)).is_err());
        assert!(p.sample(Sampling::Step(f64::NAN)).is_err());
    }
}

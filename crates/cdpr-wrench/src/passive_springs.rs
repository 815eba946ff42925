//! # Passive springs
//!
//! A passive spring is attached like a cable, from a frame point **a** to a platform point
//! **b̄**, but nothing controls its force: it follows from the spring's length at the pose,
//!
//!   f_j = K_j (l_j − l₀,j)                                        (CASPR's
//!   `cable_passive_linear_spring`; Duan, Vashista & Agrawal 2015)
//!
//! with K_j its stiffness (N/m) and l₀,j its free length (m). As CASPR models it, f_j is used
//! with its sign: a spring shorter than its free length pushes (f_j < 0). It acts on the
//! platform along its unit vector **u**_j (from the platform attachment towards the frame
//! point), so its wrench is its column **w**_j of the wrench matrix a cable with the same
//! attachments has (thesis eq. (6.11)): the springs add
//!
//!   **w**_s(q) = Σ_j f_j(q) **w**_j(q)
//!
//! to the external wrench, and the actuated cables balance W t + **w**_ext + **w**_s = 0. Since
//! **w**_s depends on the position as well as the orientation, an analysis that keeps one
//! external wrench over a region of poses cannot include it.
//!
//! ## References
//! - Duan, Vashista & Agrawal, *Effect on wrench-feasible workspace of cable-driven parallel
//!   robots by adding springs*, Mechanism and Machine Theory 86, 2015.
//! - Lau, Eden, Tan & Oetomo, CASPR, IROS 2016 (`CableModelPassiveLinearSpring`).

use crate::WrenchError;
use crate::error::check_slice;
use cdpr_kinematics::{KinematicsError, Pose, PoseKinematics, Robot};
use nalgebra::DVector;

/// Passive linear springs attached between the frame and the platform.
#[derive(Debug, Clone, PartialEq)]
pub struct PassiveSprings {
    geometry: Robot,
    stiffness: Vec<f64>,
    free_length: Vec<f64>,
}

impl PassiveSprings {
    /// Springs with the attachments of `geometry`'s cables (straight, no pulleys), stiffness
    /// K_j > 0 (N/m) and free length l₀,j ≥ 0 (m), one per spring.
    pub fn new(
        geometry: Robot,
        stiffness: Vec<f64>,
        free_length: Vec<f64>,
    ) -> Result<Self, WrenchError> {
        let n = geometry.cable_count();
        check_slice("spring stiffness K", &stiffness, n)?;
        check_slice("spring free length l0", &free_length, n)?;
        if let Some(j) = stiffness.iter().position(|&k| k <= 0.0) {
            return Err(WrenchError::NonPositiveSpring {
                spring: j,
                what: "stiffness K (N/m)",
                value: stiffness[j],
            });
        }
        if let Some(j) = free_length.iter().position(|&l| l < 0.0) {
            return Err(WrenchError::NonPositiveSpring {
                spring: j,
                what: "free length l0 (m)",
                value: free_length[j],
            });
        }
        Ok(Self {
            geometry,
            stiffness,
            free_length,
        })
    }

    /// The attachments, as a robot whose cables are the springs.
    pub fn geometry(&self) -> &Robot {
        &self.geometry
    }

    /// K_j (N/m).
    pub fn stiffness(&self) -> &[f64] {
        &self.stiffness
    }

    /// l₀,j (m).
    pub fn free_length(&self) -> &[f64] {
        &self.free_length
    }

    /// Number of springs.
    pub fn count(&self) -> usize {
        self.stiffness.len()
    }

    /// The springs' kinematics (lengths l_j, unit vectors, wrench columns) at `pose`, and their
    /// forces f_j = K_j (l_j − l₀,j) (N).
    pub fn state(&self, pose: &Pose) -> Result<(PoseKinematics, Vec<f64>), KinematicsError> {
        let kin = self.geometry.inverse_kinematics(pose)?;
        let forces = kin
            .lengths()
            .zip(self.stiffness.iter().zip(&self.free_length))
            .map(|(l, (k, l0))| k * (l - l0))
            .collect();
        Ok((kin, forces))
    }

    /// **w**_s = Σ_j f_j **w**_j at `pose` (N, N·m): what the springs add to the external
    /// wrench.
    ///
    /// ```
    /// use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
    /// use cdpr_wrench::PassiveSprings;
    /// use nalgebra::Vector2;
    /// // One spring from (0, 3) to the platform origin, K = 5 N/m, l0 = 1 m: at the origin it
    /// // is 3 m long and pulls up with 5 · (3 − 1) = 10 N.
    /// let geometry = Robot::new(MotionPattern::Point2, vec![
    ///     Cable::point2(Vector2::new(0.0, 3.0)),
    /// ]).unwrap();
    /// let springs = PassiveSprings::new(geometry, vec![5.0], vec![1.0]).unwrap();
    /// let w = springs.wrench(&Pose::point(0.0, 0.0, 0.0)).unwrap();
    /// assert_eq!(w.as_slice(), &[0.0, 10.0]);
    /// ```
    pub fn wrench(&self, pose: &Pose) -> Result<DVector<f64>, KinematicsError> {
        let (kin, forces) = self.state(pose)?;
        Ok(kin.wrench_matrix() * DVector::from_vec(forces))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdpr_kinematics::{Cable, MotionPattern};
    use nalgebra::{Vector2, Vector3};

    /// The spring "spring 0" of CASPR's Passive_springs_planar model (one_spring set), in our
    /// plane (CASPR's y, z → x, y): frame (0, 5), platform (0, 0.1) from the centre of mass,
    /// K = 5 N/m, l0 = 1 m. At the pose (0.3, −0.4, θ = 0.2), by hand:
    /// b = (0.3, −0.4) + R(0.2) (0, 0.1) = (0.3 − 0.1 sin 0.2, −0.4 + 0.1 cos 0.2),
    /// ℓ = a − b, l = ‖ℓ‖, f = 5 (l − 1), w = f [ℓ/l; (R b̄) × ℓ/l].
    #[test]
    fn planar_spring_wrench_by_hand() {
        let geometry = Robot::new(
            MotionPattern::Planar,
            vec![Cable::planar(
                Vector2::new(0.0, 5.0),
                Vector2::new(0.0, 0.1),
            )],
        )
        .unwrap();
        let springs = PassiveSprings::new(geometry, vec![5.0], vec![1.0]).unwrap();
        let th: f64 = 0.2;
        let r = Vector2::new(-0.1 * th.sin(), 0.1 * th.cos());
        let b = Vector2::new(0.3, -0.4) + r;
        let ell = Vector2::new(0.0, 5.0) - b;
        let l = ell.norm();
        let f = 5.0 * (l - 1.0);
        let u = ell / l;
        let expected = [f * u.x, f * u.y, f * (r.x * u.y - r.y * u.x)];
        let w = springs.wrench(&Pose::planar(0.3, -0.4, th)).unwrap();
        for (a, e) in w.iter().zip(expected) {
            assert!((a - e).abs() < 1e-12, "{a} vs {e}");
        }
        let (kin, forces) = springs.state(&Pose::planar(0.3, -0.4, th)).unwrap();
        assert!((kin.lengths().next().unwrap() - l).abs() < 1e-12);
        assert!((forces[0] - f).abs() < 1e-12);
    }

    /// Two opposite springs of equal K and l0 through the platform origin cancel; a compressed
    /// spring pushes (f < 0), as CASPR models it.
    #[test]
    fn symmetric_springs_cancel_and_a_compressed_spring_pushes() {
        let geometry = Robot::new(
            MotionPattern::Point3,
            vec![
                Cable::point3(Vector3::new(0.0, 0.0, 2.0)),
                Cable::point3(Vector3::new(0.0, 0.0, -2.0)),
            ],
        )
        .unwrap();
        let springs = PassiveSprings::new(geometry.clone(), vec![7.0; 2], vec![0.5; 2]).unwrap();
        let w = springs.wrench(&Pose::point(0.0, 0.0, 0.0)).unwrap();
        assert!(w.norm() < 1e-12);
        // Moved up by 1: upper spring 1 m (f = 3.5 N, up), lower 3 m (f = 17.5 N, down).
        let w = springs.wrench(&Pose::point(0.0, 0.0, 1.0)).unwrap();
        assert!((w[2] - (3.5 - 17.5)).abs() < 1e-12);
        let short = PassiveSprings::new(geometry, vec![7.0; 2], vec![3.0; 2]).unwrap();
        let (_, f) = short.state(&Pose::point(0.0, 0.0, 0.0)).unwrap();
        assert_eq!(f, vec![-7.0, -7.0]);
    }

    #[test]
    fn bad_springs_are_errors() {
        let geometry = Robot::new(
            MotionPattern::Point2,
            vec![Cable::point2(Vector2::new(0.0, 3.0))],
        )
        .unwrap();
        assert!(PassiveSprings::new(geometry.clone(), vec![0.0], vec![1.0]).is_err());
        assert!(PassiveSprings::new(geometry.clone(), vec![1.0], vec![-1.0]).is_err());
        assert!(PassiveSprings::new(geometry.clone(), vec![f64::NAN], vec![1.0]).is_err());
        assert!(PassiveSprings::new(geometry, vec![1.0, 2.0], vec![1.0]).is_err());
    }
}

//! # Batch inverse kinematics: wrench matrices of many poses
//!
//! Grids, trajectories and the Python package need W (eq. (6.11)) for thousands of poses and
//! nothing else. [`Robot::wrench_matrices`] computes, for every pose, the cable vectors
//! ℓ^i = **c**^i − **T ā**^i − **u** (eq. (6.2)), their unit vectors and the columns
//! `[u_i ; a_i × u_i]` (restricted to the motion pattern, Picard, Caro, Plestan & Claveau 2020,
//! eq. (2)) straight into one flat buffer: one DOF × n column-major block per pose (the storage
//! order of `DMatrix`), without the per-cable [`crate::CableState`] records of
//! [`Robot::update_kinematics`]. The arithmetic is the same expression by expression, so every
//! block equals the single-pose `wrench_matrix()` bit for bit (tested), and a pose is rejected
//! (`valid[k] = false`) exactly when `update_kinematics` fails on it (non-finite position,
//! degenerate cable). Robots with pulleys go through `update_kinematics` pose by pose (the same
//! answers; one `PoseKinematics` allocated per call).
//!
//! ## References
//! - Thesis eqs. (6.2)–(6.4), (6.11). Picard, Caro, Plestan & Claveau 2020, eqs. (1)–(2).

use crate::inverse_kinematics::DEGENERATE_LENGTH;
use crate::{KinematicsError, MotionPattern, Pose, PoseKinematics, Robot};
use nalgebra::Vector3;

impl Robot {
    /// W of every pose in `poses` into `out` (`poses.len()` blocks of DOF · n values, each
    /// column-major like `DMatrix::as_slice`); `valid[k]` tells whether pose k has a wrench
    /// matrix (its block is then written; otherwise the block is left as it was). Returns the
    /// number of valid poses; errors only when `out` or `valid` has the wrong length. Allocates
    /// nothing for robots without pulleys.
    ///
    /// ```
    /// use cdpr_kinematics::{Pose, reference_robots::ipanema_like_8};
    /// let robot = ipanema_like_8();
    /// let poses = [Pose::spatial([0.0, 0.0, 1.0].into(), 0.0, 0.0, 0.0),
    ///              Pose::spatial([0.2, -0.1, 0.8].into(), 0.05, 0.0, -0.1)];
    /// let mut w = vec![0.0; poses.len() * 6 * 8];
    /// let mut valid = [false; 2];
    /// assert_eq!(robot.wrench_matrices(&poses, &mut w, &mut valid).unwrap(), 2);
    /// let single = robot.inverse_kinematics(&poses[1]).unwrap().wrench_matrix();
    /// assert_eq!(&w[48..], single.as_slice());
    /// ```
    pub fn wrench_matrices(
        &self,
        poses: &[Pose],
        out: &mut [f64],
        valid: &mut [bool],
    ) -> Result<usize, KinematicsError> {
        let (dof, n) = (self.motion().dof(), self.cable_count());
        let block = dof * n;
        if out.len() != poses.len() * block {
            return Err(KinematicsError::WrongDimension {
                what: "wrench matrix buffer (poses × DOF × cables)".into(),
                motion: self.motion().name(),
                expected: poses.len() * block,
                found: out.len(),
            });
        }
        if valid.len() != poses.len() {
            return Err(KinematicsError::WrongDimension {
                what: "validity flags (one per pose)".into(),
                motion: self.motion().name(),
                expected: poses.len(),
                found: valid.len(),
            });
        }
        if self.has_pulleys() {
            return Ok(self.wrench_matrices_by_pose(poses, out, valid));
        }
        Ok(match self.motion() {
            MotionPattern::Spatial => self.straight::<6>(poses, out, valid, |u, a, col| {
                let m = a.cross(u);
                col[..3].copy_from_slice(u.as_slice());
                col[3..].copy_from_slice(m.as_slice());
            }),
            MotionPattern::Planar => self.straight::<3>(poses, out, valid, |u, a, col| {
                col[0] = u.x;
                col[1] = u.y;
                col[2] = a.x * u.y - a.y * u.x;
            }),
            MotionPattern::Point3 => self.straight::<3>(poses, out, valid, |u, _, col| {
                col.copy_from_slice(u.as_slice());
            }),
            MotionPattern::Point2 => self.straight::<2>(poses, out, valid, |u, _, col| {
                col[0] = u.x;
                col[1] = u.y;
            }),
        })
    }

    /// The straight-cable loop for DOF = D, with the column formula of the motion pattern.
    #[inline(always)]
    fn straight<const D: usize>(
        &self,
        poses: &[Pose],
        out: &mut [f64],
        valid: &mut [bool],
        column: impl Fn(&Vector3<f64>, &Vector3<f64>, &mut [f64; D]),
    ) -> usize {
        let n = self.cable_count();
        let mut count = 0;
        for ((pose, block), ok) in poses.iter().zip(out.chunks_exact_mut(D * n)).zip(valid) {
            *ok = self.straight_pose::<D>(pose, block, &column);
            count += *ok as usize;
        }
        count
    }

    /// One pose: the expressions of `update_kinematics` and `write_wrench_matrix`.
    #[inline(always)]
    fn straight_pose<const D: usize>(
        &self,
        pose: &Pose,
        block: &mut [f64],
        column: &impl Fn(&Vector3<f64>, &Vector3<f64>, &mut [f64; D]),
    ) -> bool {
        if !pose.position.iter().all(|v| v.is_finite()) {
            return false;
        }
        let r = pose.rotation.matrix();
        let threshold = DEGENERATE_LENGTH * self.length_scale().max(pose.position.norm());
        for (cable, col) in self.cables().iter().zip(block.chunks_exact_mut(D)) {
            let attachment = r * cable.platform;
            let attachment_point = pose.position + attachment;
            let vector = cable.frame - attachment_point;
            let length = vector.norm();
            if length.is_nan() || length <= threshold {
                return false;
            }
            let unit = vector / length;
            let col: &mut [f64; D] = col.try_into().expect("chunks of D");
            column(&unit, &attachment, col);
        }
        true
    }

    /// Robots with pulleys: `update_kinematics` pose by pose.
    #[cold]
    fn wrench_matrices_by_pose(
        &self,
        poses: &[Pose],
        out: &mut [f64],
        valid: &mut [bool],
    ) -> usize {
        let block = self.motion().dof() * self.cable_count();
        let mut kin = PoseKinematics::for_robot(self);
        let mut w = nalgebra::DMatrix::zeros(self.motion().dof(), self.cable_count());
        let mut count = 0;
        for ((pose, dst), ok) in poses.iter().zip(out.chunks_exact_mut(block)).zip(valid) {
            *ok = self.update_kinematics(pose, &mut kin).is_ok();
            if *ok {
                kin.write_wrench_matrix(&mut w);
                dst.copy_from_slice(w.as_slice());
                count += 1;
            }
        }
        count
    }
}

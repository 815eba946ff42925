//! # Inverse kinematics
//!
//! For a platform pose (**u**, **T**), each cable's vector from platform attachment to frame anchor
//! ℓ^i = **c**^i − **T ā**^i − **u** (eq. (6.2)), its length l_i = ‖ℓ^i‖ (eq. (6.4)), its unit
//! vector ℓ^i / l_i (Picard, Caro, Plestan & Claveau 2020: ᵇu_i, pointing from B_i to A_i) and the attachment **a**^i = **T ā**^i
//! (eq. (6.3); Picard, Caro, Plestan & Claveau 2020: ᵇb_i).
//!
//! A cable with a [`crate::Pulley`] follows the swivel-pulley model of Pott 2018 (module
//! `pulley`): its length is the arc wrapped on the pulley plus the free segment, and its vector
//! and unit vector are those of the free segment, from the attachment to the tangent point.
//! Cables without a pulley run the straight-cable code unchanged (bit-identical results).
//!
//! ## References
//! - Thesis eqs. (6.2)–(6.4). Picard, Caro, Plestan & Claveau 2020, §2.
//! - Pott, *Cable-Driven Parallel Robots*, Springer 2018 (pulley kinematics).

use crate::cable_state::{CableState, DEGENERATE_LENGTH, PulleyState, straight_cable};
use crate::pulley::update_cables;
use crate::{KinematicsError, MotionPattern, Pose, Robot};
use nalgebra::Vector3;

/// The inverse kinematics of a robot at one pose: one [`CableState`] per cable.
///
/// Reuse one value across poses with [`Robot::update_kinematics`] to avoid allocation.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseKinematics {
    motion: MotionPattern,
    cables: Vec<CableState>,
    /// One entry per cable when the robot has pulleys (`None` for its straight cables); empty
    /// otherwise, so that straight robots write nothing more than before pulleys existed.
    pulleys: Vec<Option<PulleyState>>,
}

impl PoseKinematics {
    /// An empty buffer for `robot`, to be filled by [`Robot::update_kinematics`].
    pub fn for_robot(robot: &Robot) -> Self {
        Self {
            motion: robot.motion(),
            cables: vec![CableState::default(); robot.cable_count()],
            pulleys: if robot.has_pulleys() {
                vec![None; robot.cable_count()]
            } else {
                Vec::new()
            },
        }
    }

    /// The motion pattern of the robot these states belong to.
    pub fn motion(&self) -> MotionPattern {
        self.motion
    }

    /// Per-cable states.
    pub fn cables(&self) -> &[CableState] {
        &self.cables
    }

    /// Number of cables n.
    pub fn cable_count(&self) -> usize {
        self.cables.len()
    }

    /// The pulley state of cable `i`, `None` for a straight cable.
    pub fn pulley(&self, i: usize) -> Option<&PulleyState> {
        self.pulleys.get(i).and_then(Option::as_ref)
    }

    /// Free (straight) length of cable `i` (m): l_f with a pulley, l_i without.
    pub fn free_length(&self, i: usize) -> f64 {
        self.pulley(i)
            .map_or(self.cables[i].length, |p| p.free_length)
    }

    /// Swivel angle γ of cable `i`'s pulley (rad), 0 without a pulley.
    pub fn swivel_angle(&self, i: usize) -> f64 {
        self.pulley(i).map_or(0.0, PulleyState::swivel_angle)
    }

    /// Wrap angle β of cable `i` on its pulley (rad), 0 without a pulley.
    pub fn wrap_angle(&self, i: usize) -> f64 {
        self.pulley(i).map_or(0.0, |p| p.wrap_angle)
    }

    /// Where cable `i` leaves the frame towards the platform: the tangent point **C** with a
    /// pulley, the frame anchor (attachment point + ℓ^i) without.
    pub fn exit_point(&self, i: usize) -> Vector3<f64> {
        self.pulley(i).map_or_else(
            || self.cables[i].attachment_point + self.cables[i].vector,
            |p| p.exit_point,
        )
    }

    /// Cable lengths l_i.
    pub fn lengths(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.cables.iter().map(|c| c.length)
    }

    /// Shortest cable length, for the l_min criterion of eq. (6.22).
    pub fn min_length(&self) -> f64 {
        self.lengths().fold(f64::INFINITY, f64::min)
    }
}

impl Robot {
    /// Inverse kinematics at `pose`, eqs. (6.2)–(6.4), and the swivel-pulley model for cables
    /// with a pulley.
    ///
    /// Errors with [`KinematicsError::DegenerateCable`] if a cable has zero length at this pose
    /// (its direction is undefined), [`KinematicsError::DegeneratePulley`] if a platform
    /// attachment is inside its pulley or on its swivel axis, or [`KinematicsError::NotFinite`]
    /// for a non-finite pose.
    ///
    /// ```
    /// use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
    /// use nalgebra::Vector3;
    /// let robot = Robot::new(MotionPattern::Planar, vec![
    ///     Cable { frame: Vector3::new(1.0, 0.5, 0.0), platform: Vector3::new(0.1, 0.1, 0.0), pulley: None },
    /// ]).unwrap();
    /// let kin = robot.inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0)).unwrap();
    /// assert!((kin.cables()[0].length - (0.81f64 + 0.16).sqrt()).abs() < 1e-15);
    /// ```
    pub fn inverse_kinematics(&self, pose: &Pose) -> Result<PoseKinematics, KinematicsError> {
        let mut kin = PoseKinematics::for_robot(self);
        self.update_kinematics(pose, &mut kin)?;
        Ok(kin)
    }

    /// Inverse kinematics into an existing buffer (no allocation when `kin` has the right size).
    pub fn update_kinematics(
        &self,
        pose: &Pose,
        kin: &mut PoseKinematics,
    ) -> Result<(), KinematicsError> {
        if let Some(&v) = pose.position.iter().find(|v| !v.is_finite()) {
            return Err(KinematicsError::NotFinite {
                what: "pose position".into(),
                value: v,
            });
        }
        kin.motion = self.motion();
        kin.cables.resize(self.cable_count(), CableState::default());
        // The pulley path overwrites every entry: resize only (no refill) when the buffer
        // already fits.
        if self.has_pulleys() {
            kin.pulleys.resize(self.cable_count(), None);
        } else {
            kin.pulleys.clear();
        }
        let r = pose.rotation.matrix();
        // One threshold per pose: lengths are compared with the size of the robot and the pose.
        let threshold = DEGENERATE_LENGTH * self.length_scale().max(pose.position.norm());
        if self.has_pulleys() {
            return update_cables(
                self.cables(),
                self.pulley_blocks(),
                r,
                &pose.position,
                threshold,
                &mut kin.cables,
                &mut kin.pulleys,
            );
        }
        for (i, (cable, state)) in self.cables().iter().zip(kin.cables.iter_mut()).enumerate() {
            let attachment = r * cable.platform;
            let attachment_point = pose.position + attachment;
            *state = straight_cable(cable, attachment, attachment_point, threshold, i)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Cable;
    use approx::assert_relative_eq;

    #[test]
    fn zero_length_cable_is_an_error_for_that_pose() {
        let robot = Robot::new(
            MotionPattern::Point2,
            vec![Cable {
                frame: Vector3::new(0.5, 0.5, 0.0),
                platform: Vector3::zeros(),
                pulley: None,
            }],
        )
        .unwrap();
        assert!(matches!(
            robot.inverse_kinematics(&Pose::point(0.5, 0.5, 0.0)),
            Err(KinematicsError::DegenerateCable { cable: 0, .. })
        ));
        assert!(
            robot
                .inverse_kinematics(&Pose::point(0.4, 0.5, 0.0))
                .is_ok()
        );
    }

    #[test]
    fn rotated_attachment_follows_eq_6_3() {
        let robot = Robot::new(
            MotionPattern::Planar,
            vec![Cable {
                frame: Vector3::new(1.0, 1.0, 0.0),
                platform: Vector3::new(0.1, 0.0, 0.0),
                pulley: None,
            }],
        )
        .unwrap();
        let kin = robot
            .inverse_kinematics(&Pose::planar(0.2, 0.0, std::f64::consts::FRAC_PI_2))
            .unwrap();
        let c = kin.cables()[0];
        assert_relative_eq!(c.attachment, Vector3::new(0.0, 0.1, 0.0), epsilon = 1e-15);
        assert_relative_eq!(c.vector, Vector3::new(0.8, 0.9, 0.0), epsilon = 1e-15);
        assert_relative_eq!(c.unit.norm(), 1.0, epsilon = 1e-15);
    }
}

//! # Robot geometry
//!
//! A cable-driven parallel robot, as far as kinematics is concerned: a motion pattern and, per
//! cable i, the frame anchor **c**^i (base coordinates) and the platform attachment **ā**^i
//! (platform coordinates). Thesis Fig. 6.1 and Tables 6.1–6.2; Picard, Caro, Plestan & Claveau 2020, §2 calls them A_i, B_i.

use crate::pulley::PulleyBlocks;
use crate::{KinematicsError, MotionPattern};
use nalgebra::{Matrix3, Vector2, Vector3};

/// A swivel pulley at a cable's frame anchor (Pott, *Cable-Driven Parallel Robots*, Springer
/// 2018; the WireCenter `.wcrfx` model): it swivels about the axis through the frame anchor
/// **a** along the third column of Q, and the cable wraps it before leaving tangentially
/// towards the platform attachment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pulley {
    /// Radius ρ (m), > 0.
    pub radius: f64,
    /// Pulley frame Q in base coordinates: its first column is the zero of the swivel angle,
    /// its third column the swivel axis. Used as written (not re-orthonormalised).
    pub orientation: Matrix3<f64>,
}

/// One cable: where it leaves the frame and where it is attached to the platform.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cable {
    /// Frame anchor **c**^i in base coordinates (z = 0 for 2-D motion patterns); with a pulley,
    /// the point **a** on its swivel axis.
    pub frame: Vector3<f64>,
    /// Platform attachment **ā**^i in platform coordinates (zero for point motion patterns).
    pub platform: Vector3<f64>,
    /// The swivel pulley that guides the cable at the frame, if any (`None`: a straight cable
    /// from the frame anchor).
    pub pulley: Option<Pulley>,
}

impl Cable {
    /// A cable from slices whose length must match the motion pattern's space dimension
    /// (`platform` may be empty for point patterns).
    pub fn from_slices(
        motion: MotionPattern,
        index: usize,
        frame: &[f64],
        platform: &[f64],
    ) -> Result<Self, KinematicsError> {
        let frame = to_vector(motion, &format!("cable {} frame anchor", index + 1), frame)?;
        let platform = if platform.is_empty() && !motion.has_orientation() {
            Vector3::zeros()
        } else {
            to_vector(
                motion,
                &format!("cable {} platform attachment", index + 1),
                platform,
            )?
        };
        Ok(Self {
            frame,
            platform,
            pulley: None,
        })
    }
}

/// Constructors per motion pattern: a planar or point2 robot is built from 2-vectors in the
/// plane z = 0 (thesis Table 6.1 gives its anchors that way).
///
/// ```
/// use cdpr_kinematics::nalgebra::Vector2;
/// use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
/// // The thesis chapter's 4-cable planar robot: frame corners, platform attachments of Table 6.1.
/// let cables = vec![
///     Cable::planar(Vector2::new(-1.0, -1.0), Vector2::new(-0.1, -0.05)),
///     Cable::planar(Vector2::new(1.0, -1.0), Vector2::new(0.1, -0.05)),
///     Cable::planar(Vector2::new(1.0, 1.0), Vector2::new(0.1, 0.05)),
///     Cable::planar(Vector2::new(-1.0, 1.0), Vector2::new(-0.1, 0.05)),
/// ];
/// let robot = Robot::new(MotionPattern::Planar, cables).unwrap();
/// let kin = robot.inverse_kinematics(&Pose::planar(0.0, 0.0, 0.0)).unwrap();
/// let l1 = kin.lengths().next().unwrap();
/// assert!((l1 - (0.9f64.powi(2) + 0.95f64.powi(2)).sqrt()).abs() < 1e-12);
///
/// // A point-mass robot needs only the frame anchors.
/// let point = Robot::new(
///     MotionPattern::Point2,
///     vec![Cable::point2(Vector2::new(0.0, 1.0)), Cable::point2(Vector2::new(-1.0, -1.0)),
///          Cable::point2(Vector2::new(1.0, -1.0))],
/// )
/// .unwrap();
/// assert_eq!(point.cable_count(), 3);
/// ```
impl Cable {
    /// A straight cable (no pulley) from frame anchor **c** (base coordinates, m) to platform
    /// attachment **ā** (platform coordinates, m), for any motion pattern.
    pub fn new(frame: Vector3<f64>, platform: Vector3<f64>) -> Self {
        Self {
            frame,
            platform,
            pulley: None,
        }
    }

    /// A cable of a `planar` robot: anchor and attachment in the plane z = 0 (m).
    pub fn planar(frame: Vector2<f64>, platform: Vector2<f64>) -> Self {
        Self::new(frame.push(0.0), platform.push(0.0))
    }

    /// A cable of a `point2` robot (a point mass in the plane): its frame anchor (m).
    pub fn point2(frame: Vector2<f64>) -> Self {
        Self::new(frame.push(0.0), Vector3::zeros())
    }

    /// A cable of a `point3` robot (a point mass in space): its frame anchor (m).
    pub fn point3(frame: Vector3<f64>) -> Self {
        Self::new(frame, Vector3::zeros())
    }

    /// A cable of a `spatial` robot (6 DOF): anchor and attachment (m), as [`Cable::new`].
    pub fn spatial(frame: Vector3<f64>, platform: Vector3<f64>) -> Self {
        Self::new(frame, platform)
    }
}

fn to_vector(
    motion: MotionPattern,
    what: &str,
    v: &[f64],
) -> Result<Vector3<f64>, KinematicsError> {
    let d = motion.space_dim();
    if v.len() != d {
        return Err(KinematicsError::WrongDimension {
            what: what.into(),
            motion: motion.name(),
            expected: d,
            found: v.len(),
        });
    }
    if let Some(&x) = v.iter().find(|x| !x.is_finite()) {
        return Err(KinematicsError::NotFinite {
            what: what.into(),
            value: x,
        });
    }
    Ok(Vector3::new(v[0], v[1], if d == 3 { v[2] } else { 0.0 }))
}

/// The geometry of a cable robot: motion pattern and cables.
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Robot};
/// use nalgebra::Vector3;
/// let cable = |x: f64, y: f64| Cable { frame: Vector3::new(x, y, 0.0), platform: Vector3::zeros(), pulley: None };
/// let robot = Robot::new(MotionPattern::Point2, vec![cable(1.0, 0.0), cable(-0.5, 0.8), cable(-0.5, -0.8)]).unwrap();
/// assert_eq!(robot.cable_count(), 3);
/// assert_eq!(robot.redundancy(), 1);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    motion: MotionPattern,
    cables: Vec<Cable>,
    /// max(1, ‖c^i‖, ‖ā^i‖): the length scale for degeneracy tests.
    length_scale: f64,
    /// Whether any cable has a pulley.
    has_pulleys: bool,
    /// The cables' geometry as the pulley inverse kinematics reads it (empty without pulleys).
    pulley_blocks: PulleyBlocks,
}

impl Robot {
    /// A robot from its cables. Errors on no cables or non-finite coordinates; 2-D patterns
    /// must have zero z components and point patterns zero platform attachments; a pulley needs a
    /// finite radius > 0 and an orthonormal Q (|QᵀQ − I| ≤ 1e-6), whose axis lies in the plane
    /// for 2-D patterns.
    pub fn new(motion: MotionPattern, cables: Vec<Cable>) -> Result<Self, KinematicsError> {
        if cables.is_empty() {
            return Err(KinematicsError::NoCables);
        }
        for (i, c) in cables.iter().enumerate() {
            for (what, v) in [
                ("frame anchor", &c.frame),
                ("platform attachment", &c.platform),
            ] {
                if let Some(&x) = v.iter().find(|x| !x.is_finite()) {
                    return Err(KinematicsError::NotFinite {
                        what: format!("cable {} {what}", i + 1),
                        value: x,
                    });
                }
            }
            if motion.space_dim() == 2 && (c.frame.z != 0.0 || c.platform.z != 0.0) {
                return Err(KinematicsError::WrongDimension {
                    what: format!("cable {} (non-zero z)", i + 1),
                    motion: motion.name(),
                    expected: 2,
                    found: 3,
                });
            }
            if let Some((problem, value)) = c
                .pulley
                .as_ref()
                .and_then(|p| p.defect(motion.space_dim() == 2))
            {
                return Err(KinematicsError::InvalidPulley {
                    cable: i,
                    problem,
                    value,
                });
            }
            if !motion.has_orientation() && c.platform != Vector3::zeros() {
                return Err(KinematicsError::WrongDimension {
                    what: format!(
                        "cable {} platform attachment (a point platform has none)",
                        i + 1
                    ),
                    motion: motion.name(),
                    expected: 0,
                    found: motion.space_dim(),
                });
            }
        }
        let length_scale = cables
            .iter()
            .flat_map(|c| [c.frame.norm(), c.platform.norm()])
            .fold(1.0, f64::max);
        let has_pulleys = cables.iter().any(|c| c.pulley.is_some());
        Ok(Self {
            motion,
            pulley_blocks: PulleyBlocks::new(&cables),
            cables,
            length_scale,
            has_pulleys,
        })
    }

    /// max(1, ‖c^i‖, ‖ā^i‖): the robot's length scale (relative tolerances use it).
    pub fn length_scale(&self) -> f64 {
        self.length_scale
    }

    /// The motion pattern.
    pub fn motion(&self) -> MotionPattern {
        self.motion
    }

    /// Degrees of freedom (rows of W).
    pub fn dof(&self) -> usize {
        self.motion.dof()
    }

    /// The cables, in order.
    pub fn cables(&self) -> &[Cable] {
        &self.cables
    }

    /// Number of cables n (columns of W).
    pub fn cable_count(&self) -> usize {
        self.cables.len()
    }

    /// Redundancy r = n − DOF (negative for under-constrained robots).
    pub fn redundancy(&self) -> isize {
        self.cables.len() as isize - self.dof() as isize
    }

    /// Pairs of cables that are exact duplicates (same anchor and attachment): legal, but the
    /// wrench matrix then has equal columns. Shared anchors alone are normal (IPAnema 1).
    pub fn duplicate_cables(&self) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for i in 0..self.cables.len() {
            for j in i + 1..self.cables.len() {
                if self.cables[i] == self.cables[j] {
                    out.push((i, j));
                }
            }
        }
        out
    }

    /// Bounding box of the frame anchors: `(min, max)` corners (Algorithm 6.2 step 2).
    pub fn frame_bounding_box(&self) -> (Vector3<f64>, Vector3<f64>) {
        let mut lo = self.cables[0].frame;
        let mut hi = lo;
        for c in &self.cables[1..] {
            lo = lo.inf(&c.frame);
            hi = hi.sup(&c.frame);
        }
        (lo, hi)
    }

    /// The default search region of the analyses (workspace, gallery, forward-kinematics
    /// starts): the frame anchors' bounding box, except that a robot in space whose anchors
    /// span less than a quarter of the frame's width in height (all anchors near one level: a
    /// suspended robot such as a spidercam, CAROCA, CoGiRo, the NIST RoboCrane) gets a box
    /// reaching half the width below its highest anchor, where the platform hangs. The width
    /// is the larger of the box's x and y extents. `(min, max)` corners.
    ///
    /// ```
    /// use cdpr_kinematics::{Cable, MotionPattern, Robot};
    /// use nalgebra::Vector3;
    /// let c = |x: f64, y: f64| Cable { frame: Vector3::new(x, y, 30.0), platform: Vector3::zeros(), pulley: None };
    /// let robot = Robot::new(MotionPattern::Point3, vec![c(50.0, 35.0), c(-50.0, 35.0), c(-50.0, -35.0), c(50.0, -35.0)]).unwrap();
    /// let (lo, hi) = robot.default_region();
    /// assert_eq!((lo.z, hi.z), (30.0 - 50.0, 30.0));
    /// ```
    pub fn default_region(&self) -> (Vector3<f64>, Vector3<f64>) {
        let (mut lo, hi) = self.frame_bounding_box();
        if self.is_suspended() {
            let width = (hi.x - lo.x).max(hi.y - lo.y);
            lo.z = lo.z.min(hi.z - 0.5 * width);
        }
        (lo, hi)
    }

    /// Whether the robot is suspended by the rule of [`Self::default_region`]: it moves in
    /// space and its anchors span less than a quarter of the frame's width (the larger of the
    /// anchors' x and y extents) in height.
    pub fn is_suspended(&self) -> bool {
        let (lo, hi) = self.frame_bounding_box();
        let width = (hi.x - lo.x).max(hi.y - lo.y);
        self.motion().space_dim() == 3 && hi.z - lo.z < 0.25 * width
    }

    /// Whether any cable runs over a pulley (the pulley model then differs from the standard one).
    pub fn has_pulleys(&self) -> bool {
        self.has_pulleys
    }

    /// The same robot with every pulley removed: the standard model, each cable a straight
    /// segment from its `frame` point (with a pulley, the point **a** on the swivel axis).
    pub fn without_pulleys(&self) -> Self {
        let mut r = self.clone();
        for c in &mut r.cables {
            c.pulley = None;
        }
        r.has_pulleys = false;
        r.pulley_blocks = PulleyBlocks::new(&r.cables);
        r
    }

    /// The robot made of the cables `order` picks, in that order: `order[k]` is the old index of
    /// new cable k. A permutation reorders the cables; a shorter list keeps a subset (which is
    /// validated as a new robot: its pulley flag and length scale are its own).
    ///
    /// ```
    /// use cdpr_kinematics::{Cable, KinematicsError, MotionPattern, Robot};
    /// use nalgebra::Vector2;
    /// let c = |x: f64, y: f64| Cable::point2(Vector2::new(x, y));
    /// let robot = Robot::new(MotionPattern::Point2, vec![c(0.0, 0.0), c(1.0, 0.0), c(0.0, 1.0)]).unwrap();
    /// assert_eq!(robot.permuted(&[2, 0]).unwrap().cables()[0], robot.cables()[2]);
    /// assert_eq!(robot.permuted(&[3]), Err(KinematicsError::NoSuchCable { cable: 3, cables: 3 }));
    /// ```
    pub fn permuted(&self, order: &[usize]) -> Result<Self, KinematicsError> {
        let cables = self.cables.len();
        if let Some(&cable) = order.iter().find(|&&i| i >= cables) {
            return Err(KinematicsError::NoSuchCable { cable, cables });
        }
        Self::new(self.motion, order.iter().map(|&i| self.cables[i]).collect())
    }

    /// The cables' geometry in blocks for the pulley inverse kinematics.
    pub(crate) fn pulley_blocks(&self) -> &PulleyBlocks {
        &self.pulley_blocks
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_subset_of_cables_is_a_robot_of_its_own() {
        let straight = Cable::spatial(Vector3::new(2.0, 0.0, 1.0), Vector3::new(0.1, 0.0, 0.0));
        let mut guided = Cable::spatial(Vector3::new(-2.0, 0.0, 1.0), Vector3::zeros());
        guided.pulley = Some(Pulley::from_axis(0.05, Vector3::z()));
        let robot = Robot::new(MotionPattern::Spatial, vec![straight, guided]).unwrap();
        assert!(robot.has_pulleys());
        let reordered = robot.permuted(&[1, 0]).unwrap();
        assert_eq!(reordered.cables(), &[guided, straight]);
        assert!(reordered.has_pulleys());
        assert_eq!(reordered.length_scale(), robot.length_scale());
        let first = robot.permuted(&[0]).unwrap();
        assert!(!first.has_pulleys());
        assert_eq!(first.length_scale(), Vector3::new(2.0, 0.0, 1.0).norm());
        assert_eq!(robot.permuted(&[]), Err(KinematicsError::NoCables));
        assert_eq!(
            robot.permuted(&[0, 2]),
            Err(KinematicsError::NoSuchCable {
                cable: 2,
                cables: 2
            })
        );
    }

    #[test]
    fn rejects_bad_geometry() {
        assert_eq!(
            Robot::new(MotionPattern::Planar, vec![]),
            Err(KinematicsError::NoCables)
        );
        let bad = Cable {
            frame: Vector3::new(f64::NAN, 0.0, 0.0),
            platform: Vector3::zeros(),
            pulley: None,
        };
        assert!(matches!(
            Robot::new(MotionPattern::Planar, vec![bad]),
            Err(KinematicsError::NotFinite { .. })
        ));
        let z = Cable {
            frame: Vector3::new(1.0, 0.0, 1.0),
            platform: Vector3::zeros(),
            pulley: None,
        };
        assert!(matches!(
            Robot::new(MotionPattern::Planar, vec![z]),
            Err(KinematicsError::WrongDimension { .. })
        ));
        let att = Cable {
            frame: Vector3::new(1.0, 0.0, 0.0),
            platform: Vector3::new(0.1, 0.0, 0.0),
            pulley: None,
        };
        assert!(matches!(
            Robot::new(MotionPattern::Point2, vec![att]),
            Err(KinematicsError::WrongDimension { .. })
        ));
        assert!(Cable::from_slices(MotionPattern::Spatial, 0, &[1.0, 2.0], &[0.0; 3]).is_err());
    }

    #[test]
    fn duplicates_are_reported_not_rejected() {
        let c = Cable {
            frame: Vector3::new(1.0, 0.0, 0.0),
            platform: Vector3::zeros(),
            pulley: None,
        };
        let r = Robot::new(MotionPattern::Point2, vec![c, c]).unwrap();
        assert_eq!(r.duplicate_cables(), vec![(0, 1)]);
    }
}

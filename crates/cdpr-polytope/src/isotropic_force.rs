//! # Maximum isotropic force
//!
//! The largest force the platform can resist in *every* direction: the radius of the largest
//! ball centred at the origin inside the operational force polytope (Krut, Company & Pierrot 2004, §IV, Fig. 4).
//! With the facets `n_k · w ≤ d_k` of the available wrench set (unit normals, signed d_k),
//! eq. (19) reads
//!
//! ```text
//!     f_min = min_k d_k          (= min_i 1/‖v_i‖ of eq. (19) when the origin is inside)
//! ```
//!
//! and is **signed**: negative when the origin lies outside the polytope (the pose cannot even
//! balance a zero load; Krut, Company & Pierrot 2004 draws those poses white). It is then the most violated facet's
//! signed distance, whose magnitude is at most the distance from the origin to the polytope.
//! The AWS {W t} and the balanceable set −AWS give the same value: a ball centred at the origin
//! is its own mirror.
//!
//! **Which ball.** For `point2` / `point3` robots every wrench component is a force and f_min is
//! the force radius. For `planar` / `spatial` robots a wrench mixes forces (N) and moments (N·m);
//! [`isotropic_force`] then returns the **force index at zero moment**: the radius of the largest
//! force ball in the slice of the AWS by moment = 0. Writing each facet as n_k = [n_f,k; n_m,k]
//! (force and moment parts), the slice is {f : n_f,k · f ≤ d_k}, so
//!
//! ```text
//!     f_min = min_k d_k / ‖n_f,k‖
//! ```
//!
//! where a facet with ‖n_f,k‖ ≈ 0 (below 1e-12) imposes no constraint if d_k ≥ 0 and makes the
//! slice empty if d_k < 0 (result −∞). [`isotropic_wrench_radius`] gives the ball in the full
//! wrench space instead (min_k d_k with unit normals; unit-dependent, for completeness).
//!
//! **Under a load.** With a constant external wrench w_ext on the platform (its weight, say), the
//! question becomes: which extra force can be added to w_ext in every direction and still be
//! balanced? Balancing w_ext + f needs −(w_ext + f) ∈ AWS, i.e. n_k · (−w_ext − f) ≤ d_k for
//! every facet, so the facets are shifted to d_k + n_k · w_ext and
//!
//! ```text
//!     f_min(w_ext) = min_k (d_k + n_k · w_ext) / ‖n_f,k‖
//! ```
//!
//! ([`isotropic_force_under_load`], [`isotropic_force_of_under_load`],
//! [`IsotropicForce::with_load`]); w_ext = 0 gives back eq. (19). It is negative when w_ext
//! itself cannot be balanced.
//!
//! ## References
//! - S. Krut, O. Company, F. Pierrot, IROS 2004 (Krut, Company & Pierrot 2004), §IV-A eq. (19), §IV-B.
//! - S. Krut, O. Company, F. Pierrot, *Velocity performance indexes for parallel mechanisms with
//!   actuation redundancy*, Robotica 22(2), 2004 (Krut, Company & Pierrot's (2004) reference \[1\]).

use crate::PolytopeError;
use crate::available_wrench_set::AvailableWrenchSet;
use crate::hyperplane_shifting::{HyperplaneShifting, for_each_halfspace};
use crate::input::{MAX_DOF, check_vector};
use cdpr_kinematics::{MotionPattern, Pose, PoseKinematics, Robot};
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, DVector};

/// ‖n_f‖ below which a facet has no force part.
const NO_FORCE_PART: f64 = 1e-12;

/// Contribution of one facet to the zero-moment force index (see the module docs).
#[inline]
fn force_term(normal: &[f64], offset: f64, force_rows: usize) -> f64 {
    if force_rows == normal.len() {
        return offset; // a pure force space: the normal is already a unit force direction
    }
    let nf = normal[..force_rows]
        .iter()
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt();
    if nf > NO_FORCE_PART {
        offset / nf
    } else if offset >= 0.0 {
        f64::INFINITY
    } else {
        f64::NEG_INFINITY
    }
}

/// min of [`force_term`] over the pair of half-spaces ±n (same ‖n_f‖); +∞ offsets stay +∞.
#[inline(always)]
fn pair_force_term(normal: &[f64], dp: f64, dm: f64, force_rows: usize) -> f64 {
    let d = if dp < dm { dp } else { dm };
    if force_rows == normal.len() {
        return d;
    }
    force_term(normal, d, force_rows)
}

/// Maximum isotropic force of an AWS, eq. (19), signed; the zero-moment force index for planar
/// and spatial motion patterns (module docs). +∞ if no facet limits the force (infinite t_max
/// with positively spanning cables).
///
/// ```
/// use cdpr_kinematics::MotionPattern;
/// use cdpr_polytope::{hyperplane_shifting::available_wrench_set, isotropic_force};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::dmatrix;
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
/// assert!((isotropic_force(&aws, MotionPattern::Point2).unwrap() - 9.0).abs() < 1e-12);
/// ```
pub fn isotropic_force(
    aws: &AvailableWrenchSet,
    motion: MotionPattern,
) -> Result<f64, PolytopeError> {
    if aws.dof() != motion.dof() {
        return Err(PolytopeError::DimensionMismatch {
            what: "AWS dimension vs motion pattern DOF",
            expected: motion.dof(),
            found: aws.dof(),
        });
    }
    let rows = motion.translation_dof();
    Ok(aws
        .supporting_halfspaces()
        .iter()
        .map(|f| force_term(f.normal.as_slice(), f.offset, rows))
        .fold(f64::INFINITY, f64::min))
}

/// The isotropic force on top of a constant external wrench `w_ext` (N, N·m; e.g. the platform's
/// weight): the largest extra force, in every direction (at zero extra moment for planar and
/// spatial robots), that can be added to `w_ext` and still be balanced with tensions in bounds
/// (module docs, "Under a load"). Negative when `w_ext` itself cannot be balanced.
///
/// ```
/// use cdpr_kinematics::MotionPattern;
/// use cdpr_polytope::{hyperplane_shifting::available_wrench_set, isotropic_force_under_load};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::{dmatrix, dvector};
/// // AWS = [−9, 9]²; a weight of 5 N downwards leaves 4 N of force in every direction.
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
/// let f = isotropic_force_under_load(&aws, MotionPattern::Point2, &dvector![0.0, -5.0]);
/// assert!((f.unwrap() - 4.0).abs() < 1e-12);
/// ```
pub fn isotropic_force_under_load(
    aws: &AvailableWrenchSet,
    motion: MotionPattern,
    w_ext: &DVector<f64>,
) -> Result<f64, PolytopeError> {
    if aws.dof() != motion.dof() || w_ext.len() != motion.dof() {
        return Err(PolytopeError::DimensionMismatch {
            what: "AWS dimension and external wrench vs motion pattern DOF",
            expected: motion.dof(),
            found: if aws.dof() != motion.dof() {
                aws.dof()
            } else {
                w_ext.len()
            },
        });
    }
    check_vector("external wrench", w_ext.as_slice(), motion.dof())?;
    let rows = motion.translation_dof();
    Ok(aws
        .supporting_halfspaces()
        .iter()
        .map(|f| {
            let shift = f.normal.dot(w_ext);
            force_term(f.normal.as_slice(), f.offset + shift, rows)
        })
        .fold(f64::INFINITY, f64::min))
}

/// [`isotropic_force_under_load`] straight from W without building the facet list.
pub fn isotropic_force_of_under_load(
    motion: MotionPattern,
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
    w_ext: &[f64],
) -> Result<f64, PolytopeError> {
    if w.nrows() != motion.dof() {
        return Err(PolytopeError::DimensionMismatch {
            what: "rows of W vs motion pattern DOF",
            expected: motion.dof(),
            found: w.nrows(),
        });
    }
    check_vector("external wrench", w_ext, motion.dof())?;
    let rows = motion.translation_dof();
    let mut r = f64::INFINITY;
    for_each_halfspace(w, bounds, |n, d| {
        let shift: f64 = n.iter().zip(w_ext).map(|(a, b)| a * b).sum();
        r = r.min(force_term(n, d + shift, rows));
    })?;
    Ok(r)
}

/// Radius of the largest origin-centred ball in the full wrench space inside the AWS:
/// min_k d_k (unit normals), signed. Mixes N and N·m for planar/spatial robots.
pub fn isotropic_wrench_radius(aws: &AvailableWrenchSet) -> f64 {
    aws.supporting_halfspaces()
        .iter()
        .map(|f| f.offset)
        .fold(f64::INFINITY, f64::min)
}

/// Allocation-free maximum isotropic force for repeated poses of one robot with fixed tension
/// bounds, checked once at construction (hyperplane shifting on the fly, no facet list).
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
/// use cdpr_polytope::IsotropicForce;
/// use cdpr_tension::TensionBounds;
/// use nalgebra::Vector3;
/// // Krut, Company & Pierrot's (2004) robot: motors at 1000 mm, 30°, 150°, 270°; tensions in [50, 500].
/// let motor = |deg: f64| Cable {
///     frame: Vector3::new(1000.0 * deg.to_radians().cos(), 1000.0 * deg.to_radians().sin(), 0.0),
///     platform: Vector3::zeros(),
///     pulley: None,
/// };
/// let robot = Robot::new(MotionPattern::Point2, vec![motor(30.0), motor(150.0), motor(270.0)]).unwrap();
/// let bounds = TensionBounds::uniform(3, 50.0, 500.0).unwrap();
/// let mut index = IsotropicForce::new(&robot, &bounds).unwrap();
/// let f = index.force_at_pose(&Pose::point(0.0, 0.0, 0.0)).unwrap();
/// assert!((f - 225.0 * 3f64.sqrt()).abs() < 1e-9);
/// ```
#[derive(Debug, Clone)]
pub struct IsotropicForce {
    robot: Robot,
    engine: HyperplaneShifting,
    kinematics: PoseKinematics,
    w: DMatrix<f64>,
    /// The constant external wrench w_ext the force is added to (zero: eq. (19)), padded to 6.
    load: [f64; MAX_DOF],
}

impl IsotropicForce {
    /// Buffers for `robot` with `bounds` (one pair per cable).
    pub fn new(robot: &Robot, bounds: &TensionBounds) -> Result<Self, PolytopeError> {
        if bounds.len() != robot.cable_count() {
            return Err(PolytopeError::DimensionMismatch {
                what: "tension bounds vs cables of the robot",
                expected: robot.cable_count(),
                found: bounds.len(),
            });
        }
        Ok(Self {
            robot: robot.clone(),
            engine: HyperplaneShifting::new(robot.dof(), bounds)?,
            kinematics: PoseKinematics::for_robot(robot),
            w: DMatrix::zeros(robot.dof(), robot.cable_count()),
            load: [0.0; MAX_DOF],
        })
    }

    /// The same index on top of a constant external wrench `w_ext` (N, N·m; e.g. the platform's
    /// weight): see [`isotropic_force_under_load`]. Both indices shift their facets by it.
    pub fn with_load(mut self, w_ext: &[f64]) -> Result<Self, PolytopeError> {
        self.set_load(w_ext)?;
        Ok(self)
    }

    /// Changes the external wrench in place (a load that varies from pose to pose, e.g. the
    /// weight's moment at each orientation), without reallocating anything.
    pub fn set_load(&mut self, w_ext: &[f64]) -> Result<(), PolytopeError> {
        check_vector("external wrench", w_ext, self.robot.dof())?;
        self.load = [0.0; MAX_DOF];
        self.load[..w_ext.len()].copy_from_slice(w_ext);
        Ok(())
    }

    /// n · w_ext for a normal of length DOF.
    #[inline(always)]
    fn shift(&self, n: &[f64]) -> f64 {
        n.iter().zip(&self.load).map(|(a, b)| a * b).sum()
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The wrench matrix of the last pose evaluated (zeros before the first).
    pub fn wrench_matrix(&self) -> &DMatrix<f64> {
        &self.w
    }

    /// The force index (zero-moment slice for planar/spatial) of W, see [`isotropic_force`].
    #[inline]
    pub fn force(&self, w: &DMatrix<f64>) -> Result<f64, PolytopeError> {
        Ok(self.indices(w)?.0)
    }

    /// The full-wrench-space ball radius of W, see [`isotropic_wrench_radius`].
    #[inline]
    pub fn wrench_radius(&self, w: &DMatrix<f64>) -> Result<f64, PolytopeError> {
        Ok(self.indices(w)?.1)
    }

    /// Both indices of W in one enumeration: (force index, wrench radius).
    #[inline]
    pub fn indices(&self, w: &DMatrix<f64>) -> Result<(f64, f64), PolytopeError> {
        let rows = self.robot.motion().translation_dof();
        let (mut f, mut r) = (f64::INFINITY, f64::INFINITY);
        self.engine.for_each_pair(w, |n, dp, dm| {
            // Half-spaces n·w ≤ dp and −n·w ≤ dm, shifted by w_ext (+∞ stays +∞).
            let s = self.shift(n);
            let (dp, dm) = (dp + s, dm - s);
            f = f.min(pair_force_term(n, dp, dm, rows));
            r = r.min(dp).min(dm);
            2
        })?;
        Ok((f, r))
    }

    /// Inverse kinematics, W and the force index at `pose`, reusing this value's buffers.
    #[inline]
    pub fn force_at_pose(&mut self, pose: &Pose) -> Result<f64, PolytopeError> {
        self.update(pose)?;
        let rows = self.robot.motion().translation_dof();
        let mut f = f64::INFINITY;
        let load = &self.load;
        self.engine.for_each_pair(&self.w, |n, dp, dm| {
            let s: f64 = n.iter().zip(load).map(|(a, b)| a * b).sum();
            f = f.min(pair_force_term(n, dp + s, dm - s, rows));
            2
        })?;
        Ok(f)
    }

    /// Inverse kinematics, W and both indices (force index, wrench radius) at `pose`.
    pub fn indices_at_pose(&mut self, pose: &Pose) -> Result<(f64, f64), PolytopeError> {
        self.update(pose)?;
        self.indices(&self.w)
    }

    #[inline]
    fn update(&mut self, pose: &Pose) -> Result<(), PolytopeError> {
        self.robot.update_kinematics(pose, &mut self.kinematics)?;
        self.kinematics.write_wrench_matrix(&mut self.w);
        Ok(())
    }
}

/// [`isotropic_force`] straight from W without building the facet list (no allocation).
pub fn isotropic_force_of(
    motion: MotionPattern,
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
) -> Result<f64, PolytopeError> {
    if w.nrows() != motion.dof() {
        return Err(PolytopeError::DimensionMismatch {
            what: "rows of W vs motion pattern DOF",
            expected: motion.dof(),
            found: w.nrows(),
        });
    }
    let rows = motion.translation_dof();
    let mut r = f64::INFINITY;
    for_each_halfspace(w, bounds, |n, d| r = r.min(force_term(n, d, rows)))?;
    Ok(r)
}

/// [`isotropic_wrench_radius`] straight from W without building the facet list (no allocation).
pub fn isotropic_wrench_radius_of(
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
) -> Result<f64, PolytopeError> {
    let mut r = f64::INFINITY;
    for_each_halfspace(w, bounds, |_, d| r = r.min(d))?;
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hyperplane_shifting::available_wrench_set;
    use approx::assert_relative_eq;
    use nalgebra::dmatrix;

    #[test]
    fn zero_moment_slice_by_hand() {
        // Planar-like W with rows f_x, f_y, m: cables ±x (moment arm ±1 about z is carried by
        // columns 1, 2), ±y without moment. Columns: [1,0,1], [-1,0,1], [0,1,0], [0,-1,0].
        // Tensions in [0, 1]. At zero moment t1 + t2 = 0 ⇒ t1 = t2 = 0 ⇒ f_x = 0: the slice is
        // the segment f_x = 0, f_y ∈ [−1, 1], so the force index is 0.
        let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0; 1.0, 1.0, 0.0, 0.0];
        let b = TensionBounds::uniform(4, 0.0, 1.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_relative_eq!(
            isotropic_force(&aws, MotionPattern::Planar).unwrap(),
            0.0,
            epsilon = 1e-12
        );
        // Without moment coupling (third row from independent cables) the slice is the square.
        let w = dmatrix![1.0, -1.0, 0.0, 0.0, 0.0, 0.0;
                         0.0, 0.0, 1.0, -1.0, 0.0, 0.0;
                         0.0, 0.0, 0.0, 0.0, 1.0, -1.0];
        let b = TensionBounds::uniform(6, 1.0, 3.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_relative_eq!(
            isotropic_force(&aws, MotionPattern::Planar).unwrap(),
            2.0,
            epsilon = 1e-12
        );
        assert_relative_eq!(isotropic_wrench_radius(&aws), 2.0, epsilon = 1e-12);
        assert_relative_eq!(
            isotropic_force_of(MotionPattern::Planar, &w, &b).unwrap(),
            2.0,
            epsilon = 1e-12
        );
        assert_relative_eq!(
            isotropic_wrench_radius_of(&w, &b).unwrap(),
            2.0,
            epsilon = 1e-12
        );
        assert!(isotropic_force_of(MotionPattern::Point2, &w, &b).is_err());
    }

    /// Issue 13 §1: the weight is part of the isotropic force. AWS = [−9, 9]² (t ∈ [1, 10]);
    /// a weight of 5 N downwards: the cables can add 9 − 5 = 4 N downwards... and upwards
    /// 9 + 5 = 14 N, sideways 9 N: the index is 4 N. Every path (facet list, streaming,
    /// repeated-pose evaluator) agrees; a load the AWS cannot balance gives a negative index.
    #[test]
    fn the_load_shifts_the_isotropic_force() {
        use nalgebra::{Vector3, dvector};
        let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
        let b = TensionBounds::uniform(4, 1.0, 10.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        let g = dvector![0.0, -5.0];
        let m = MotionPattern::Point2;
        assert_relative_eq!(
            isotropic_force_under_load(&aws, m, &g).unwrap(),
            4.0,
            epsilon = 1e-12
        );
        assert_relative_eq!(
            isotropic_force_of_under_load(m, &w, &b, g.as_slice()).unwrap(),
            4.0,
            epsilon = 1e-12
        );
        assert_relative_eq!(
            isotropic_force_under_load(&aws, m, &dvector![0.0, 0.0]).unwrap(),
            isotropic_force(&aws, m).unwrap(),
            epsilon = 1e-12
        );
        assert_relative_eq!(
            isotropic_force_under_load(&aws, m, &dvector![12.0, 0.0]).unwrap(),
            -3.0,
            epsilon = 1e-12
        );
        // The repeated-pose evaluator: 4 cables pulling a point along ±x, ±y from far away.
        let cable =
            |x: f64, y: f64| cdpr_kinematics::Cable::new(Vector3::new(x, y, 0.0), Vector3::zeros());
        let robot = Robot::new(
            m,
            vec![
                cable(1e6, 0.0),
                cable(-1e6, 0.0),
                cable(0.0, 1e6),
                cable(0.0, -1e6),
            ],
        )
        .unwrap();
        let pose = Pose::point(0.0, 0.0, 0.0);
        let mut free = IsotropicForce::new(&robot, &b).unwrap();
        let mut loaded = IsotropicForce::new(&robot, &b)
            .unwrap()
            .with_load(&[0.0, -5.0])
            .unwrap();
        assert_relative_eq!(free.force_at_pose(&pose).unwrap(), 9.0, epsilon = 1e-6);
        assert_relative_eq!(loaded.force_at_pose(&pose).unwrap(), 4.0, epsilon = 1e-6);
        assert_relative_eq!(
            loaded.indices_at_pose(&pose).unwrap().0,
            4.0,
            epsilon = 1e-6
        );
        assert!(
            IsotropicForce::new(&robot, &b)
                .unwrap()
                .with_load(&[f64::NAN, 0.0])
                .is_err()
        );
    }

    #[test]
    fn empty_slice_is_minus_infinity() {
        // A facet with no force part and d < 0: the moment row m = t3 ∈ [1, 2] can never be 0.
        let w = dmatrix![1.0, -1.0, 0.0, 0.0, 0.0;
                         0.0, 0.0, 1.0, -1.0, 0.0;
                         0.0, 0.0, 0.0, 0.0, 1.0];
        let b = TensionBounds::uniform(5, 1.0, 2.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_eq!(
            isotropic_force(&aws, MotionPattern::Planar).unwrap(),
            f64::NEG_INFINITY
        );
        assert_relative_eq!(isotropic_wrench_radius(&aws), -1.0, epsilon = 1e-12);
        assert!(isotropic_force(&aws, MotionPattern::Point2).is_err());
    }
}

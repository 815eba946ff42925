//! # Pose evaluator
//!
//! Decides whether one pose satisfies a list of [`Criterion`]s, reusing every buffer (inverse
//! kinematics, W, tension solvers and their tensions, the wrench-closure and capacity-margin
//! scratch, K): no allocation per pose once warmed up (`tests/no_allocation.rs` counts them;
//! tension methods that allocate internally, such as the interior-point path of
//! `cdpr-tension`, are the exception). Cheap criteria are tested first and the first failure
//! ends the test. Grids clone one evaluator per rayon thread. [`PoseEvaluator::feasible_batch`]
//! evaluates a list of poses, taking W from the batch inverse kinematics (SIMD across poses,
//! `Robot::wrench_matrices`) when every criterion needs W only.
//!
//! ## References
//! - Thesis eq. (6.23): the constant-orientation workspace definition.

use crate::criteria::square_determinant;
use crate::wrench_closure::{LANES, WrenchClosureTest};
use crate::{Criterion, PoseContext, WorkspaceError};
use cdpr_kinematics::{KinematicsError, Pose, PoseKinematics, Robot, RobotCatenaries};
use cdpr_polytope::{CapacityMargin, isotropic_force_of, isotropic_force_of_under_load};
use cdpr_tension::{
    Method, MethodOptions, SaggingOutcome, SaggingSettings, SaggingStatics, StiffnessData,
    TensionBounds, TensionError, TensionProblem, TensionSolver,
};
use nalgebra::{DMatrix, DVector, Matrix2, Matrix3, Matrix6, SymmetricEigen};

/// Tests poses against composable workspace criteria (thesis eq. (6.23) and more).
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
/// use cdpr_tension::{Method, TensionBounds};
/// use cdpr_workspace::{Criterion, PoseEvaluator};
/// use nalgebra::{DVector, Vector3};
/// let c = |x: f64, y: f64| Cable { frame: Vector3::new(x, y, 0.0), platform: Vector3::zeros(), pulley: None };
/// let robot = Robot::new(MotionPattern::Point2, vec![c(1.0, 1.0), c(-1.0, 1.0), c(0.0, -1.0)]).unwrap();
/// let mut eval = PoseEvaluator::new(
///     robot,
///     TensionBounds::uniform(3, 5.0, 100.0).unwrap(),
///     vec![
///         Criterion::TensionFeasible { method: Method::L1, wrench: DVector::from_vec(vec![0.0, -10.0]) },
///         Criterion::MinCableLength(0.1),
///     ],
/// ).unwrap();
/// assert!(eval.is_feasible(&Pose::point(0.0, 0.0, 0.0)));
/// assert!(!eval.is_feasible(&Pose::point(0.0, -0.95, 0.0))); // cable 3 shorter than 0.1
/// assert!(!eval.is_feasible(&Pose::point(0.0, -1.0, 0.0)));  // zero-length cable
/// ```
#[derive(Debug, Clone)]
pub struct PoseEvaluator {
    robot: Robot,
    bounds: TensionBounds,
    criteria: Vec<Criterion>,
    axial_stiffness: Option<Vec<f64>>,
    /// Elastic or heavy cables ([`PoseEvaluator::with_cable_model`]); `None`: straight cables.
    catenaries: Option<RobotCatenaries>,
    /// Criterion indices, cheapest first.
    order: Vec<usize>,
    /// How many criteria at the head of `order` need no W (the cable-length floors): W is
    /// written only when a pose passes them.
    wrench_free: usize,
    /// Index of the TensionFeasible criterion whose tensions the stiffness criterion uses.
    tension_source: Option<usize>,
    scratch: Scratch,
}

#[derive(Debug, Clone)]
struct Scratch {
    kin: PoseKinematics,
    w: DMatrix<f64>,
    solvers: Vec<Option<TensionSolver>>,
    closure: Option<WrenchClosureTest>,
    margin: Option<CapacityMargin>,
    tensions: DVector<f64>,
    tensions_valid: bool,
    stiffness: DMatrix<f64>,
    batch: BatchBuffers,
    sagging: Sagging,
}

/// The sagging-cable statics of the tension criterion and what the capacity criterion takes
/// from its equilibrium (sized on first use).
#[derive(Debug, Clone, Default)]
struct Sagging {
    statics: SaggingStatics,
    /// The sag-aware W at the tension criterion's equilibrium.
    w: DMatrix<f64>,
    /// Platform-end bounds that keep every point of each cable within [t_min, t_max] there.
    bounds: Option<TensionBounds>,
}

/// Poses per call of the batch inverse kinematics in [`PoseEvaluator::feasible_batch`].
pub(crate) const BATCH: usize = 64;

/// W and validity flags of [`BATCH`] poses (sized on first use).
#[derive(Debug, Clone, Default)]
struct BatchBuffers {
    w: Vec<f64>,
    valid: Vec<bool>,
}

impl PoseEvaluator {
    /// An evaluator for `robot` with tension limits `bounds` (one pair per cable) and the
    /// criteria a pose must all satisfy. Errors on wrong sizes or non-finite limits, and on a
    /// tension method that does not apply to the robot (`WorkspaceError::Tension` with
    /// `TensionError::MethodNotApplicable` or `NeedsFiniteBounds`).
    pub fn new(
        robot: Robot,
        bounds: TensionBounds,
        criteria: Vec<Criterion>,
    ) -> Result<Self, WorkspaceError> {
        let (dof, n) = (robot.dof(), robot.cable_count());
        if bounds.len() != n {
            return Err(WorkspaceError::DimensionMismatch {
                what: "tension bounds (one pair per cable)",
                expected: n,
                found: bounds.len(),
            });
        }
        let mut tension_source = None;
        let mut needs_tensions = false;
        for (k, c) in criteria.iter().enumerate() {
            match c {
                Criterion::TensionFeasible { wrench, method } => {
                    // A method that does not apply is a usage error, found here once rather
                    // than as an empty workspace (issue 13).
                    method.check_redundancy(n as isize - dof as isize)?;
                    if *method == Method::ImprovedClosedForm
                        && let Some(cable) = bounds.max().iter().position(|v| !v.is_finite())
                    {
                        return Err(TensionError::NeedsFiniteBounds {
                            method: *method,
                            cable,
                        }
                        .into());
                    }
                    if wrench.len() != dof {
                        return Err(WorkspaceError::DimensionMismatch {
                            what: "external wrench (one entry per DOF)",
                            expected: dof,
                            found: wrench.len(),
                        });
                    }
                    if let Some(&v) = wrench.iter().find(|v| !v.is_finite()) {
                        return Err(WorkspaceError::NotFinite {
                            what: "external wrench",
                            value: v,
                        });
                    }
                    tension_source.get_or_insert(k);
                }
                Criterion::MinCableLength(v) | Criterion::MinJacobianDeterminant(v) => {
                    if !v.is_finite() || *v < 0.0 {
                        return Err(WorkspaceError::InvalidSetting {
                            what: "criterion floor (l_min or D_min)",
                            value: *v,
                            expected: "finite and ≥ 0",
                        });
                    }
                }
                Criterion::Stiffness { min_eigenvalue } => {
                    if !min_eigenvalue.is_finite() {
                        return Err(WorkspaceError::NotFinite {
                            what: "stiffness floor",
                            value: *min_eigenvalue,
                        });
                    }
                    needs_tensions = true;
                }
                Criterion::StiffnessFloor {
                    translational,
                    rotational,
                } => {
                    for (what, v) in [
                        ("translational stiffness floor (N/m)", translational),
                        ("rotational stiffness floor (N·m/rad)", rotational),
                    ] {
                        if !v.is_finite() {
                            return Err(WorkspaceError::NotFinite { what, value: *v });
                        }
                    }
                    needs_tensions = true;
                }
                Criterion::IsotropicForceUnderLoad { min, wrench } => {
                    if !min.is_finite() {
                        return Err(WorkspaceError::NotFinite {
                            what: "isotropic force floor",
                            value: *min,
                        });
                    }
                    if wrench.len() != dof {
                        return Err(WorkspaceError::DimensionMismatch {
                            what: "external wrench of the isotropic force (one entry per DOF)",
                            expected: dof,
                            found: wrench.len(),
                        });
                    }
                    if let Some(&v) = wrench.iter().find(|v| !v.is_finite()) {
                        return Err(WorkspaceError::NotFinite {
                            what: "external wrench",
                            value: v,
                        });
                    }
                }
                Criterion::CapacityMargin {
                    required,
                    min_margin,
                } => {
                    if required.dof() != dof {
                        return Err(WorkspaceError::DimensionMismatch {
                            what: "required wrench set (one entry per DOF)",
                            expected: dof,
                            found: required.dof(),
                        });
                    }
                    if !min_margin.is_finite() {
                        return Err(WorkspaceError::NotFinite {
                            what: "capacity margin floor",
                            value: *min_margin,
                        });
                    }
                }
                Criterion::IsotropicForce { min } => {
                    if !min.is_finite() {
                        return Err(WorkspaceError::NotFinite {
                            what: "isotropic force floor",
                            value: *min,
                        });
                    }
                }
                Criterion::Interference { min_distance, .. } => {
                    if !min_distance.is_finite() || *min_distance < 0.0 {
                        return Err(WorkspaceError::InvalidSetting {
                            what: "cable clearance D of the interference criterion (m)",
                            value: *min_distance,
                            expected: "finite and ≥ 0",
                        });
                    }
                }
                Criterion::WrenchClosure | Criterion::Custom(_) => {}
            }
        }
        if needs_tensions && tension_source.is_none() {
            return Err(WorkspaceError::StiffnessNeedsTensions);
        }
        let mut order: Vec<usize> = (0..criteria.len()).collect();
        order.sort_by_key(|&k| (criteria[k].cost(), k));
        let wrench_free = order
            .iter()
            .take_while(|&&k| matches!(criteria[k], Criterion::MinCableLength(_)))
            .count();
        let solvers = criteria
            .iter()
            .map(|c| match c {
                Criterion::TensionFeasible { method, .. } => Some(TensionSolver::new(*method)),
                _ => None,
            })
            .collect();
        let closure = criteria
            .iter()
            .any(|c| matches!(c, Criterion::WrenchClosure))
            .then(|| WrenchClosureTest::new(dof, n));
        let margin = criteria
            .iter()
            .any(|c| matches!(c, Criterion::CapacityMargin { .. }))
            .then(|| CapacityMargin::new(dof, n));
        let scratch = Scratch {
            margin,
            kin: PoseKinematics::for_robot(&robot),
            w: DMatrix::zeros(dof, n),
            solvers,
            closure,
            tensions: DVector::zeros(n),
            tensions_valid: false,
            stiffness: DMatrix::zeros(dof, dof),
            batch: BatchBuffers::default(),
            sagging: Sagging::default(),
        };
        Ok(Self {
            robot,
            bounds,
            criteria,
            axial_stiffness: None,
            catenaries: None,
            order,
            wrench_free,
            tension_source: needs_tensions.then_some(tension_source).flatten(),
            scratch,
        })
    }

    /// The options of the tension criteria's methods (puncture's interior point, dykstra's
    /// variant and cap, p-norm's p, optimally-safe's α; `cdpr_tension::MethodOptions`): every
    /// tension criterion's solver takes them, on every path (pose by pose, the batch and the
    /// four-lane 6 × 8 paths, the sagging-cable statics). Errors on invalid numbers
    /// (`WorkspaceError::Tension`).
    pub fn with_tension_options(mut self, options: MethodOptions) -> Result<Self, WorkspaceError> {
        for solver in self.scratch.solvers.iter_mut().flatten() {
            *solver = solver.clone().with_options(options)?;
        }
        Ok(self)
    }

    /// Sets the cables' axial stiffness E·S (N, one per cable; k_i = E·S / l_i), needed by the
    /// stiffness criterion and by the SOTDA tension method.
    pub fn with_axial_stiffness(mut self, es: Vec<f64>) -> Result<Self, WorkspaceError> {
        if es.len() != self.robot.cable_count() {
            return Err(WorkspaceError::DimensionMismatch {
                what: "axial stiffness (one per cable)",
                expected: self.robot.cable_count(),
                found: es.len(),
            });
        }
        if let Some(&v) = es.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            return Err(WorkspaceError::InvalidSetting {
                what: "axial stiffness E·S",
                value: v,
                expected: "finite and > 0",
            });
        }
        self.axial_stiffness = Some(es);
        Ok(self)
    }

    /// Elastic or heavy sagging cables (Irvine's elastic catenary, one model per cable): the
    /// tension criterion then solves the platform's equilibrium with the catenaries' end forces
    /// (`cdpr_tension::sagging_statics`, bounds holding along each whole cable), and the capacity
    /// criterion measures the wrench set of the sag-aware W at that equilibrium, with the
    /// platform-end bounds that keep each whole cable within [t_min, t_max] there (a
    /// linearisation about the equilibrium). Length, determinant, wrench-closure and
    /// interference criteria keep the chords; custom criteria see the chords' W. Errors on a
    /// wrong number of cable models, on criteria that have no sagging version (isotropic force,
    /// stiffness, SOTDA), and on a capacity criterion without a tension criterion to supply the
    /// equilibrium.
    pub fn with_cable_model(mut self, model: RobotCatenaries) -> Result<Self, WorkspaceError> {
        if model.cables().len() != self.robot.cable_count() {
            return Err(WorkspaceError::DimensionMismatch {
                what: "cable models (one per cable)",
                expected: self.robot.cable_count(),
                found: model.cables().len(),
            });
        }
        for c in &self.criteria {
            let unsupported = match c {
                Criterion::TensionFeasible {
                    method: Method::Sotda,
                    ..
                } => Some("the sotda method"),
                Criterion::IsotropicForce { .. } | Criterion::IsotropicForceUnderLoad { .. } => {
                    Some("the isotropic-force criterion")
                }
                Criterion::Stiffness { .. } | Criterion::StiffnessFloor { .. } => {
                    Some("the stiffness criterion")
                }
                _ => None,
            };
            if let Some(what) = unsupported {
                return Err(WorkspaceError::NoSaggingModel { what });
            }
        }
        let tension = self
            .criteria
            .iter()
            .position(|c| matches!(c, Criterion::TensionFeasible { .. }));
        if self
            .criteria
            .iter()
            .any(|c| matches!(c, Criterion::CapacityMargin { .. }))
        {
            if tension.is_none() {
                return Err(WorkspaceError::NoSaggingModel {
                    what: "the capacity criterion without the tension criterion",
                });
            }
            self.tension_source = tension;
        }
        self.scratch.sagging.statics = SaggingStatics::new(SaggingSettings::default());
        self.catenaries = Some(model);
        Ok(self)
    }

    /// The cables' models, if not straight.
    pub fn cable_model(&self) -> Option<&RobotCatenaries> {
        self.catenaries.as_ref()
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The tension limits.
    pub fn bounds(&self) -> &TensionBounds {
        &self.bounds
    }

    /// The criteria, in the order given.
    pub fn criteria(&self) -> &[Criterion] {
        &self.criteria
    }

    /// The axial stiffness E·S, if given.
    pub fn axial_stiffness(&self) -> Option<&[f64]> {
        self.axial_stiffness.as_deref()
    }

    /// Checks that everything the criteria need is present (axial stiffness for the stiffness
    /// criterion and for SOTDA). Workspace functions call it before evaluating any pose.
    pub fn validate(&self) -> Result<(), WorkspaceError> {
        if self.axial_stiffness.is_none() {
            for c in &self.criteria {
                match c {
                    Criterion::Stiffness { .. } | Criterion::StiffnessFloor { .. } => {
                        return Err(WorkspaceError::MissingAxialStiffness {
                            criterion: "stiffness",
                        });
                    }
                    Criterion::TensionFeasible {
                        method: Method::Sotda,
                        ..
                    } => {
                        return Err(WorkspaceError::MissingAxialStiffness { criterion: "sotda" });
                    }
                    _ => {}
                }
            }
        }
        Ok(())
    }

    /// Whether `pose` satisfies every criterion; `false` for a pose with a zero-length cable and
    /// for any input error (see [`PoseEvaluator::check`] to tell them apart).
    #[inline]
    pub fn is_feasible(&mut self, pose: &Pose) -> bool {
        self.check(pose).unwrap_or(false)
    }

    /// Whether `pose` satisfies every criterion. A zero-length cable gives `Ok(false)`; a
    /// non-finite pose or missing axial stiffness is an error.
    pub fn check(&mut self, pose: &Pose) -> Result<bool, WorkspaceError> {
        if let Some(&v) = pose.rotation.matrix().iter().find(|v| !v.is_finite()) {
            return Err(WorkspaceError::NotFinite {
                what: "pose rotation",
                value: v,
            });
        }
        self.evaluate(pose)
    }

    /// [`PoseEvaluator::is_feasible`] for a pose whose rotation is known to be finite (grids
    /// check their orientation once, with `checked_orientation`, not at every point).
    #[inline]
    pub(crate) fn is_feasible_finite_rotation(&mut self, pose: &Pose) -> bool {
        debug_assert!(pose.rotation.matrix().iter().all(|v| v.is_finite()));
        self.evaluate(pose).unwrap_or(false)
    }

    /// Whether every criterion needs W only (no cable lengths, no per-cable states, no pose):
    /// then [`PoseEvaluator::feasible_batch`] takes W from the batch inverse kinematics
    /// (`Robot::wrench_matrices`) instead of `update_kinematics` pose by pose.
    fn needs_only_w(&self) -> bool {
        !self.robot.has_pulleys()
            && self.axial_stiffness.is_none()
            && self.catenaries.is_none()
            && self.criteria.iter().all(|c| match c {
                Criterion::WrenchClosure
                | Criterion::MinJacobianDeterminant(_)
                | Criterion::CapacityMargin { .. }
                | Criterion::IsotropicForce { .. }
                | Criterion::IsotropicForceUnderLoad { .. } => true,
                Criterion::TensionFeasible { method, .. } => *method != Method::Sotda,
                _ => false,
            })
    }

    /// [`PoseEvaluator::is_feasible`] of every pose of `poses` into `feasible` (same length;
    /// panics otherwise). When every criterion needs W only (wrench closure, tension
    /// feasibility without stiffness, capacity margin, isotropic force, Jacobian determinant) and
    /// the robot has no pulleys, W comes from the batch inverse kinematics
    /// (`Robot::wrench_matrices`, SIMD across poses) 64 poses at a time, in buffers kept
    /// by the evaluator: no allocation once warmed up. Every verdict equals the pose-by-pose
    /// one (the batch W is the single-pose W bit for bit).
    ///
    /// ```
    /// use cdpr_kinematics::{Pose, reference_robots::ipanema_like_8};
    /// use cdpr_tension::TensionBounds;
    /// use cdpr_workspace::{Criterion, PoseEvaluator};
    /// let mut eval = PoseEvaluator::new(ipanema_like_8(), TensionBounds::uniform(8, 1.0, 1e3).unwrap(),
    ///                                   vec![Criterion::WrenchClosure]).unwrap();
    /// let poses: Vec<Pose> = (0..10).map(|k| Pose::point(0.1 * k as f64 - 0.5, 0.0, 1.0)).collect();
    /// let mut feasible = vec![false; poses.len()];
    /// eval.feasible_batch(&poses, &mut feasible);
    /// assert!(poses.iter().zip(&feasible).all(|(p, &f)| eval.is_feasible(p) == f));
    /// ```
    pub fn feasible_batch(&mut self, poses: &[Pose], feasible: &mut [bool]) {
        assert_eq!(poses.len(), feasible.len(), "one verdict per pose");
        if !self.needs_only_w() {
            for (pose, f) in poses.iter().zip(feasible) {
                *f = self.is_feasible(pose);
            }
            return;
        }
        // Wrench closure alone: decided on the batch's W in place (no copy into the matrix).
        let closure_only = matches!(self.criteria.as_slice(), [Criterion::WrenchClosure]);
        if closure_only && (self.robot.dof(), self.robot.cable_count()) == (6, 8) {
            self.wrench_closure_six_eight(poses, feasible);
            return;
        }
        if let [Criterion::TensionFeasible { .. }] = self.criteria.as_slice()
            && (self.robot.dof(), self.robot.cable_count()) == (6, 8)
        {
            self.tension_six_eight(poses, feasible);
            return;
        }
        let block = self.robot.dof() * self.robot.cable_count();
        let mut batch = std::mem::take(&mut self.scratch.batch);
        batch.w.resize(BATCH * block, 0.0);
        batch.valid.resize(BATCH, false);
        for (chunk, verdicts) in poses.chunks(BATCH).zip(feasible.chunks_mut(BATCH)) {
            let (w, valid) = (
                &mut batch.w[..chunk.len() * block],
                &mut batch.valid[..chunk.len()],
            );
            self.robot
                .wrench_matrices(chunk, w, valid)
                .expect("buffers sized for the chunk");
            // A non-finite pose is infeasible, as in `is_feasible` (the batch flags a
            // non-finite position; a non-finite rotation is checked here).
            let poses_ok =
                |k: usize| valid[k] && chunk[k].rotation.matrix().iter().all(|v| v.is_finite());
            for (k, (pose, f)) in chunk.iter().zip(verdicts).enumerate() {
                *f = poses_ok(k) && {
                    let wk = &w[k * block..(k + 1) * block];
                    let direct = match self.scratch.closure.as_mut() {
                        Some(test) if closure_only => test.is_wrench_closure_columns(wk),
                        _ => None,
                    };
                    direct.unwrap_or_else(|| {
                        self.scratch.w.as_mut_slice().copy_from_slice(wk);
                        self.run_criteria(pose, true).unwrap_or(false)
                    })
                };
            }
        }
        self.scratch.batch = batch;
    }

    /// [`PoseEvaluator::feasible_batch`] for wrench closure alone on a 6-DOF, 8-cable robot
    /// (the IPAnema-type robots): four poses at a time from W in lanes
    /// (`Robot::wrench_matrix_lanes`) to the decision (SIMD across poses throughout, no
    /// transposition in between); the last group is padded with copies of its last pose,
    /// which are not decided.
    fn wrench_closure_six_eight(&mut self, poses: &[Pose], feasible: &mut [bool]) {
        let test = self
            .scratch
            .closure
            .as_mut()
            .expect("a wrench-closure test exists for the wrench-closure criterion");
        let mut columns = [[[0.0; LANES]; 6]; 8];
        for (group, verdicts) in poses.chunks(LANES).zip(feasible.chunks_mut(LANES)) {
            // Full groups are read in place; the last one is padded (not copied otherwise).
            let padded: [Pose; LANES];
            let four = match <&[Pose; LANES]>::try_from(group) {
                Ok(four) => four,
                Err(_) => {
                    padded = std::array::from_fn(|l| group[l.min(group.len() - 1)]);
                    &padded
                }
            };
            let valid = self
                .robot
                .wrench_matrix_lanes(four, &mut columns)
                .expect("a 6-DOF (spatial) robot and one column per cable");
            // A non-finite pose is infeasible, as in `is_feasible` (the kinematics flag a
            // non-finite position; a non-finite rotation is checked here, without branches).
            let wanted = std::array::from_fn(|l| {
                let rotation = four[l].rotation.matrix();
                l < group.len() && valid[l] & rotation.iter().fold(true, |ok, v| ok & v.is_finite())
            });
            let decided = test.decide_four_6x8(&columns, wanted);
            verdicts.copy_from_slice(&decided[..group.len()]);
        }
    }

    /// [`PoseEvaluator::feasible_batch`] for tension feasibility alone on a 6-DOF, 8-cable
    /// robot: four poses at a time from W in lanes (`Robot::wrench_matrix_lanes`) to
    /// `TensionSolver::is_feasible_four_6x8` (the four null spaces in SIMD lanes, bit for bit
    /// those of `is_feasible`, which goes on pose by pose: the same verdicts). The last group is
    /// padded as in [`Self::wrench_closure_six_eight`].
    fn tension_six_eight(&mut self, poses: &[Pose], feasible: &mut [bool]) {
        let Self {
            robot,
            bounds,
            criteria,
            scratch,
            ..
        } = self;
        let Criterion::TensionFeasible { wrench, .. } = &criteria[0] else {
            unreachable!("called for one tension criterion");
        };
        let solver = scratch.solvers[0]
            .as_mut()
            .expect("a solver exists for every tension criterion");
        let mut columns = [[[0.0; LANES]; 6]; 8];
        for (group, verdicts) in poses.chunks(LANES).zip(feasible.chunks_mut(LANES)) {
            let padded: [Pose; LANES] = std::array::from_fn(|l| group[l.min(group.len() - 1)]);
            let valid = robot
                .wrench_matrix_lanes(&padded, &mut columns)
                .expect("a 6-DOF (spatial) robot and one column per cable");
            // As `feasible_batch`: a non-finite pose is infeasible.
            let wanted = std::array::from_fn(|l| {
                l < group.len()
                    && valid[l]
                    && padded[l].rotation.matrix().iter().all(|v| v.is_finite())
            });
            let decided =
                solver.is_feasible_four_6x8(&columns, wanted, wrench, bounds, &mut scratch.w);
            for (v, d) in verdicts.iter_mut().zip(decided) {
                *v = d.unwrap_or(false);
            }
        }
    }

    /// Eq. (6.23): every criterion, cheapest first; the first failure ends the test.
    fn evaluate(&mut self, pose: &Pose) -> Result<bool, WorkspaceError> {
        match self.robot.update_kinematics(pose, &mut self.scratch.kin) {
            Ok(()) => {}
            Err(KinematicsError::DegenerateCable { .. }) => return Ok(false),
            Err(e) => return Err(e.into()),
        }
        self.run_criteria(pose, false)
    }

    /// The criteria at `pose`, whose kinematics are in the scratch (or, with `w_given`, whose
    /// W is, for criteria that need W only).
    fn run_criteria(&mut self, pose: &Pose, w_given: bool) -> Result<bool, WorkspaceError> {
        let Self {
            robot,
            bounds,
            criteria,
            axial_stiffness,
            catenaries,
            order,
            wrench_free,
            tension_source,
            scratch,
        } = self;
        scratch.tensions_valid = false;
        for (position, &k) in order.iter().enumerate() {
            if position == *wrench_free && !w_given {
                scratch.kin.write_wrench_matrix(&mut scratch.w);
            }
            let ok = match &criteria[k] {
                Criterion::MinCableLength(l_min) => scratch.kin.min_length() >= *l_min,
                Criterion::MinJacobianDeterminant(d_min) => {
                    scratch.w.nrows() != scratch.w.ncols()
                        || square_determinant(&scratch.w).abs() >= *d_min
                }
                Criterion::Custom(c) => (c.test)(&PoseContext {
                    pose,
                    kinematics: &scratch.kin,
                    wrench_matrix: &scratch.w,
                }),
                Criterion::Interference {
                    min_distance,
                    platform,
                } => {
                    let touching = 1e-12 * robot.length_scale().max(pose.position.norm());
                    cdpr_kinematics::min_cable_distance(&scratch.kin) >= min_distance.max(touching)
                        && platform.as_deref().is_none_or(|shape| {
                            cdpr_kinematics::platform_interference(
                                &scratch.kin,
                                shape,
                                &pose.position,
                                &pose.rotation,
                            )
                            .is_none()
                        })
                }
                Criterion::WrenchClosure => scratch
                    .closure
                    .as_mut()
                    .is_some_and(|t| t.is_wrench_closure(&scratch.w)),
                Criterion::CapacityMargin {
                    required,
                    min_margin,
                } => {
                    let cm = scratch
                        .margin
                        .as_mut()
                        .expect("a margin evaluator exists for a margin criterion");
                    if catenaries.is_some() {
                        // The tension criterion ran before (cost order) and set the sag-aware
                        // W and bounds of this pose's equilibrium, or failed the pose.
                        let sag = &scratch.sagging;
                        match &sag.bounds {
                            Some(b) if scratch.tensions_valid => {
                                cm.margin(&sag.w, b, required)? >= *min_margin
                            }
                            _ => false,
                        }
                    } else {
                        cm.margin(&scratch.w, bounds, required)? >= *min_margin
                    }
                }
                Criterion::IsotropicForce { min } => {
                    isotropic_force_of(robot.motion(), &scratch.w, bounds)? >= *min
                }
                Criterion::IsotropicForceUnderLoad { min, wrench } => {
                    isotropic_force_of_under_load(
                        robot.motion(),
                        &scratch.w,
                        bounds,
                        wrench.as_slice(),
                    )? >= *min
                }
                Criterion::TensionFeasible { wrench, .. } if catenaries.is_some() => {
                    let model = catenaries.as_ref().expect("matched Some");
                    let solver = scratch.solvers[k]
                        .as_mut()
                        .expect("a solver exists for every tension criterion");
                    let outcome = scratch.sagging.statics.solve(
                        solver,
                        &scratch.kin,
                        model,
                        wrench,
                        bounds,
                    )?;
                    match outcome {
                        SaggingOutcome::Feasible(s) => {
                            if *tension_source == Some(k) {
                                scratch.tensions.copy_from(&s.tensions);
                                scratch.tensions_valid = true;
                                scratch.sagging.bounds = platform_end_bounds(bounds, &s.cables);
                                scratch.sagging.w = s.wrench_matrix;
                            }
                            true
                        }
                        SaggingOutcome::Infeasible(_) => false,
                    }
                }
                Criterion::TensionFeasible { method, wrench } => {
                    let stiffness = match (method, axial_stiffness.as_deref()) {
                        (Method::Sotda, None) => {
                            return Err(WorkspaceError::MissingAxialStiffness {
                                criterion: "sotda",
                            });
                        }
                        (_, Some(es)) => Some(StiffnessData {
                            kinematics: &scratch.kin,
                            axial_stiffness: es,
                        }),
                        (_, None) => None,
                    };
                    let problem = TensionProblem {
                        wrench_matrix: &scratch.w,
                        external_wrench: wrench,
                        bounds,
                        stiffness,
                    };
                    let solver = scratch.solvers[k]
                        .as_mut()
                        .expect("a solver exists for every tension criterion");
                    if *tension_source == Some(k) {
                        let found = solver.solve_into(&problem, &mut scratch.tensions)?.is_ok();
                        scratch.tensions_valid = found;
                        found
                    } else {
                        solver.is_feasible(&problem)?
                    }
                }
                stiffness @ (Criterion::Stiffness { .. } | Criterion::StiffnessFloor { .. }) => {
                    let Some(es) = axial_stiffness.as_deref() else {
                        return Err(WorkspaceError::MissingAxialStiffness {
                            criterion: "stiffness",
                        });
                    };
                    // The tension criterion ran before (cost order) and failed the pose
                    // otherwise, so the tensions are those of this pose.
                    scratch.tensions_valid && {
                        cdpr_wrench::write_stiffness_matrix(
                            &scratch.kin,
                            scratch.tensions.as_slice(),
                            es,
                            &mut scratch.stiffness,
                        )?;
                        let kk = &mut scratch.stiffness;
                        match stiffness {
                            Criterion::StiffnessFloor {
                                translational,
                                rotational,
                            } => {
                                // sym(K − D) = sym(K) − D: subtract the floors on the diagonal.
                                let rows = robot.motion().translation_dof();
                                for i in 0..kk.nrows() {
                                    kk[(i, i)] -= if i < rows {
                                        *translational
                                    } else {
                                        *rotational
                                    };
                                }
                                min_symmetric_eigenvalue(kk) >= 0.0
                            }
                            Criterion::Stiffness { min_eigenvalue } => {
                                min_symmetric_eigenvalue(kk) >= *min_eigenvalue
                            }
                            _ => unreachable!("matched a stiffness criterion"),
                        }
                    }
                }
            };
            if !ok {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// The tensions of the first tension-feasibility criterion at `pose`, if feasible (for
    /// reporting; allocates).
    pub fn tensions(&mut self, pose: &Pose) -> Result<Option<DVector<f64>>, WorkspaceError> {
        let Self {
            robot,
            bounds,
            criteria,
            axial_stiffness,
            scratch: s,
            ..
        } = self;
        let Some((k, method, wrench)) = criteria.iter().enumerate().find_map(|(k, c)| match c {
            Criterion::TensionFeasible { method, wrench } => Some((k, *method, wrench)),
            _ => None,
        }) else {
            return Ok(None);
        };
        match robot.update_kinematics(pose, &mut s.kin) {
            Ok(()) => {}
            Err(KinematicsError::DegenerateCable { .. }) => return Ok(None),
            Err(e) => return Err(e.into()),
        }
        s.kin.write_wrench_matrix(&mut s.w);
        let stiffness = axial_stiffness.as_deref().map(|es| StiffnessData {
            kinematics: &s.kin,
            axial_stiffness: es,
        });
        if method == Method::Sotda && stiffness.is_none() {
            return Err(WorkspaceError::MissingAxialStiffness { criterion: "sotda" });
        }
        let problem = TensionProblem {
            wrench_matrix: &s.w,
            external_wrench: wrench,
            bounds,
            stiffness,
        };
        let solver = s.solvers[k]
            .as_mut()
            .expect("solver of a tension criterion");
        Ok(solver.solve(&problem)?.tensions().cloned())
    }
}

/// The platform-end bounds that keep every point of each cable within `bounds` at its catenary
/// `cables` (T_B shifted by the differences to the lowest and largest tension along the cable);
/// `None` when some cable's range is wider than its bounds.
fn platform_end_bounds(
    bounds: &TensionBounds,
    cables: &[cdpr_kinematics::SaggingCable],
) -> Option<TensionBounds> {
    let (mut lo, mut hi) = (Vec::new(), Vec::new());
    for ((c, &t_min), &t_max) in cables.iter().zip(bounds.min()).zip(bounds.max()) {
        let t = c.platform_end_tension;
        let largest = c.frame_end_tension.max(t);
        lo.push(t_min + (t - c.lowest_tension));
        hi.push(t_max - (largest - t));
    }
    TensionBounds::new(lo, hi).ok()
}

/// Smallest eigenvalue of (K + Kᵀ)/2, on the stack for DOF ∈ {2, 3, 6}.
fn min_symmetric_eigenvalue(k: &DMatrix<f64>) -> f64 {
    macro_rules! fixed {
        ($m:ty) => {{
            let m = <$m>::from_column_slice(k.as_slice());
            SymmetricEigen::new((m + m.transpose()) * 0.5)
                .eigenvalues
                .min()
        }};
    }
    match k.shape() {
        (2, 2) => fixed!(Matrix2<f64>),
        (3, 3) => fixed!(Matrix3<f64>),
        (6, 6) => fixed!(Matrix6<f64>),
        _ => SymmetricEigen::new((k + k.transpose()) * 0.5)
            .eigenvalues
            .min(),
    }
}

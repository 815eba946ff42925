//! The fixtures of the speed goals of issues 27, 28 and 29, one type per goal, each with the
//! unit of work its criterion bench times (`benches/{calibration,kinematics,dynamics,tension}.rs`)
//! and `examples/goals_instructions.rs` counts under callgrind: both run exactly this code.
//!
//! | goal | fixture | unit of [`Goal::run`] | budget |
//! |---|---|---|---|
//! | 27 self-calibration | [`SelfCalibration`] | one calibration | ≤ 50 ms |
//! | 27 noisy forward kinematics | [`NoisyForward`] | one solve | ≤ 5 µs |
//! | 28 inverse dynamics | [`InverseDynamics`] | 10 000 samples | ≤ 10 ms |
//! | 28 RK4 | [`Rk4`] | 1 000 steps | ≥ 500 000 steps/s |
//! | 28 dynamic grid | [`DynamicGrid`] | 15 625 poses | ≤ 50 ms on 2 cores |
//! | 29 catenary solve | [`CatenarySolve`] | 100 solves | ≤ 1 µs per solve |
//! | 29 sagging statics | [`SaggingStatics`] | 100 poses | ≤ 20 µs per pose |
//! | 29 elastic forward kinematics | [`ElasticForward`] | 100 solves | ≤ 10 µs per solve |

use crate::{ipanema_like_8, spatial_poses};
use cdpr_calibration::{Readings, Samples, Unknowns, calibrate};
use cdpr_dynamics::{
    DynamicFeasibility, RigidBody, Simulator, State, TimeLaw, TimedSample, TimingSettings,
    Trajectory, inverse_dynamics,
};
use cdpr_kinematics::catenary::write_sagging_wrench_matrix;
use cdpr_kinematics::{
    Cable, ElasticCatenary, ElastoGeometricForward, ElastoGeometricStatus, ForwardKinematics,
    ForwardSettings, MotionPattern, Pose, PoseKinematics, Robot, RobotCatenaries,
};
use cdpr_tension::{
    Method, SaggingOutcome, TensionBounds, TensionOutcome, TensionProblem, TensionSolver,
};
use cdpr_workspace::{Grid, PoseEvaluator, constant_orientation_workspace, dynamic_criterion};
use cdpr_wrench::{Platform, STANDARD_GRAVITY};
use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Vector3, Vector6};

/// One speed goal: its fixture is built once, [`Goal::run`] is the timed unit of work.
pub trait Goal {
    /// How many of the goal's units one [`Goal::run`] does (solves, samples, steps, poses).
    const UNITS: u64;
    /// One iteration of the bench; the value is a checksum (kept alive by `black_box`).
    fn run(&mut self) -> f64;
    /// What the example prints about the work done (iterations per solve), if anything.
    fn describe(&mut self) -> String {
        String::new()
    }
}

/// A fixture's robot or model, kept for the rest of the process (the solvers borrow them).
fn leak<T>(x: T) -> &'static T {
    Box::leak(Box::new(x))
}

/// Lengths of every pose and a guess 2 cm and 0.02 rad away from it (the forward kinematics
/// problems of `benches/kinematics.rs`).
pub fn forward_problems(robot: &Robot, poses: &[Pose]) -> Vec<(Vec<f64>, Pose)> {
    let dp = Vector3::new(1.0, -1.0, 1.0).normalize() * 0.02;
    let dr = Rotation3::new(Vector3::new(-1.0, 1.0, 1.0).normalize() * 0.02);
    poses
        .iter()
        .map(|p| {
            let l = robot.inverse_kinematics(p).unwrap().lengths().collect();
            (l, Pose::new(p.position + dp, dr * p.rotation))
        })
        .collect()
}

/// Issue 27: self-calibration of an 8-cable spatial robot from 40 samples (≤ 50 ms): anchors
/// and offsets unknown (p = 32, gauge 6, 240 pose unknowns), the IPAnema-like robot as built
/// (anchors moved by up to 2 cm, offsets up to 5 cm), lengths with a deterministic error of
/// about 0.1 mm, starting from the nominal robot (forward kinematics of every sample included).
pub struct SelfCalibration {
    /// The nominal robot (the start).
    pub nominal: Robot,
    /// 40 samples of 8 readings, no poses.
    pub samples: Samples,
    /// `frame,offsets`.
    pub unknowns: Unknowns,
}

impl SelfCalibration {
    /// The fixture (its calibration is checked identifiable and converged).
    pub fn new() -> Self {
        let nominal = ipanema_like_8();
        let wave = |k: usize, f: f64| (f * k as f64).sin();
        let truth = Robot::new(
            nominal.motion(),
            nominal
                .cables()
                .iter()
                .enumerate()
                .map(|(i, c)| Cable {
                    frame: c.frame + 0.02 * Vector3::new(wave(i, 1.3), wave(i, 2.1), wave(i, 0.7)),
                    ..*c
                })
                .collect(),
        )
        .unwrap();
        let offsets: Vec<f64> = (0..8).map(|i| 0.05 * wave(i, 0.9)).collect();
        let mut readings = Vec::new();
        for k in 0..40 {
            let pose = Pose::new(
                Vector3::new(
                    0.9 * wave(k, 0.7),
                    0.7 * wave(k, 1.1),
                    1.0 + 0.35 * wave(k, 0.5),
                ),
                Rotation3::new(0.2 * Vector3::new(wave(k, 0.3), wave(k, 1.7), wave(k, 2.3))),
            );
            for (i, l) in truth
                .inverse_kinematics(&pose)
                .unwrap()
                .lengths()
                .enumerate()
            {
                readings.push(l - offsets[i] + 1e-4 * wave(8 * k + i, 3.7));
            }
        }
        let samples = Samples {
            readings,
            poses: None,
        };
        let unknowns = Unknowns::parse("frame,offsets").unwrap();
        let check = calibrate(&nominal, &samples, unknowns, &Readings::Absolute).unwrap();
        assert!(check.identifiable && check.converged, "{check:?}");
        Self {
            nominal,
            samples,
            unknowns,
        }
    }
}

impl Default for SelfCalibration {
    fn default() -> Self {
        Self::new()
    }
}

impl Goal for SelfCalibration {
    const UNITS: u64 = 1;
    fn run(&mut self) -> f64 {
        calibrate(
            &self.nominal,
            std::hint::black_box(&self.samples),
            self.unknowns,
            &Readings::Absolute,
        )
        .unwrap()
        .residual_rms
    }
}

/// Issue 27: forward kinematics on measured lengths (≤ 5 µs per solve): the 1000 problems of
/// [`forward_problems`] on `ipanema_like_8` with a deterministic length error of up to 0.1 mm,
/// each solve giving the least-squares pose, its `fitted` test, residual_rms and the pose's
/// standard deviations. One [`Goal::run`] is the next problem's solve.
pub struct NoisyForward {
    problems: Vec<(Vec<f64>, Pose)>,
    fk: ForwardKinematics<'static>,
    next: usize,
}

impl NoisyForward {
    /// The fixture.
    pub fn new() -> Self {
        let robot = ipanema_like_8();
        let mut problems = forward_problems(&robot, &spatial_poses(1000));
        for (j, (l, _)) in problems.iter_mut().enumerate() {
            for (i, v) in l.iter_mut().enumerate() {
                *v += 1e-4 * (((7 * j + 3 * i) % 11) as f64 / 5.0 - 1.0);
            }
        }
        let fk = ForwardKinematics::new(leak(robot), ForwardSettings::default()).unwrap();
        Self {
            problems,
            fk,
            next: 0,
        }
    }
}

impl Default for NoisyForward {
    fn default() -> Self {
        Self::new()
    }
}

impl Goal for NoisyForward {
    const UNITS: u64 = 1;
    fn run(&mut self) -> f64 {
        self.next = (self.next + 1) % self.problems.len();
        let (l, guess) = &self.problems[self.next];
        self.fk
            .solve(std::hint::black_box(l), guess)
            .unwrap()
            .residual_rms
    }
}

/// Issue 28's platform: a 5 kg cuboid, centre of mass (0.02, 0, −0.01) m off the origin,
/// I_G = diag(0.0208, 0.0208, 0.0333) kg·m², under standard gravity.
pub fn dynamics_body() -> RigidBody {
    let p = Platform {
        mass: 5.0,
        centre_of_mass: Vector3::new(0.02, 0.0, -0.01),
        gravity: STANDARD_GRAVITY,
    };
    RigidBody::new(
        &p,
        Matrix3::from_diagonal(&Vector3::new(0.0208, 0.0208, 0.0333)),
    )
    .unwrap()
}

/// Issue 28: inverse dynamics with ℓ2 along a 10 000-sample trajectory (≤ 10 ms, single
/// thread): `ipanema_like_8`, t ∈ [10, 1000] N, [`dynamics_body`], a quintic rest-to-rest
/// motion in 2 s from (−0.4, −0.3, 0.8) m, (0, 0, −0.05) rad to (0.4, 0.3, 1.1) m,
/// (0.05, 0, 0.05) rad; the load is the weight. Every sample is feasible.
pub struct InverseDynamics {
    /// The robot.
    pub robot: Robot,
    /// The platform.
    pub body: RigidBody,
    /// The 10 000 samples.
    pub samples: Vec<TimedSample>,
    /// t ∈ [10, 1000] N.
    pub bounds: TensionBounds,
    /// ℓ2.
    pub solver: TensionSolver,
}

impl InverseDynamics {
    /// Samples of the trajectory.
    pub const SAMPLES: usize = 10_000;

    /// The fixture (every sample checked feasible).
    pub fn new() -> Self {
        let robot = ipanema_like_8();
        let wp = [
            Pose::spatial(Vector3::new(-0.4, -0.3, 0.8), 0.0, 0.0, -0.05),
            Pose::spatial(Vector3::new(0.4, 0.3, 1.1), 0.05, 0.0, 0.05),
        ];
        let traj = Trajectory::new(
            MotionPattern::Spatial,
            &wp,
            &TimingSettings::with_duration(TimeLaw::Quintic, 2.0),
        )
        .unwrap();
        let samples = traj.sample(2.0 / (Self::SAMPLES - 1) as f64).unwrap();
        assert_eq!(samples.len(), Self::SAMPLES);
        let mut me = Self {
            robot,
            body: dynamics_body(),
            samples,
            bounds: TensionBounds::uniform(8, 10.0, 1000.0).unwrap(),
            solver: TensionSolver::new(Method::L2),
        };
        assert_eq!(me.run(), Self::SAMPLES as f64, "every sample feasible");
        me
    }

    /// The profile (tensions, inertial wrenches, cable lengths, speeds and accelerations).
    pub fn profile(&mut self) -> cdpr_dynamics::DynamicsProfile {
        let body = &self.body;
        let load = |_: usize, s: &TimedSample| {
            DVector::from_column_slice(body.gravity_wrench6(s.pose.rotation.matrix()).as_slice())
        };
        inverse_dynamics(
            &self.robot,
            Some(body),
            std::hint::black_box(&self.samples),
            &self.bounds,
            &mut self.solver,
            None,
            load,
        )
        .unwrap()
    }
}

impl Default for InverseDynamics {
    fn default() -> Self {
        Self::new()
    }
}

impl Goal for InverseDynamics {
    const UNITS: u64 = Self::SAMPLES as u64;
    fn run(&mut self) -> f64 {
        self.profile().feasible_count() as f64
    }
}

/// Issue 28: tension-driven forward dynamics by RK4 (≥ 500 000 steps/s, single thread):
/// `ipanema_like_8` and [`dynamics_body`] started at (0.1, 0.05, 1) m with twist
/// (0.1, 0, 0, 0, 0, 0.2), driven by the constant ℓ2 tensions (t ∈ [10, 1000] N) that hold the
/// body at rest there; one [`Goal::run`] is 1 000 steps of 1 ms.
pub struct Rk4 {
    robot: &'static Robot,
    sim: Simulator<'static>,
    start: State,
}

impl Rk4 {
    /// Steps per run.
    pub const STEPS: usize = 1000;

    /// The fixture (the robot is leaked once: the simulator borrows it for the process).
    pub fn new() -> Self {
        let robot = leak(ipanema_like_8());
        let b = dynamics_body();
        let pose = Pose::point(0.1, 0.05, 1.0);
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let w = kin.wrench_matrix();
        let g = DVector::from_column_slice(b.gravity_wrench6(pose.rotation.matrix()).as_slice());
        let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
        let TensionOutcome::Feasible(t) = TensionSolver::new(Method::L2)
            .solve(&TensionProblem::new(&w, &g, &bounds))
            .unwrap()
        else {
            panic!("infeasible start")
        };
        let drive = cdpr_dynamics::Drive::Tensions(t.tensions.iter().copied().collect());
        let sim = Simulator::new(robot, b, drive, &[0.0; 6]).unwrap();
        let start = State::new(&pose, Vector6::new(0.1, 0.0, 0.0, 0.0, 0.0, 0.2));
        Self { robot, sim, start }
    }

    /// The robot simulated.
    pub fn robot(&self) -> &Robot {
        self.robot
    }

    /// The state after one run (1 000 steps of 1 ms from the start).
    pub fn end_state(&mut self) -> State {
        let mut x = std::hint::black_box(self.start);
        for k in 0..Self::STEPS {
            x = self.sim.rk4_step(k as f64 * 1e-3, &x, 1e-3).unwrap();
        }
        x
    }
}

impl Default for Rk4 {
    fn default() -> Self {
        Self::new()
    }
}

impl Goal for Rk4 {
    const UNITS: u64 = Self::STEPS as u64;
    fn run(&mut self) -> f64 {
        self.end_state().position.z
    }
}

/// Issue 28: the dynamic-feasible workspace of `ipanema_like_8` on a 25³ = 15 625-pose grid
/// over its frame (≤ 50 ms on 2 cores): [`dynamics_body`], t ∈ [10, 1000] N, identity
/// orientation, at rest (ẋ = 0), acceleration box ±2 m/s² and ±5 rad/s² (decided exactly by the
/// zonotope margin of `cdpr_dynamics::DynamicFeasibility`). Runs on rayon's pool
/// (`RAYON_NUM_THREADS`).
pub struct DynamicGrid {
    eval: PoseEvaluator,
    grid: Grid,
}

impl DynamicGrid {
    /// The fixture (its grid is checked to hold both feasible and infeasible poses).
    pub fn new() -> Self {
        let robot = ipanema_like_8();
        let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
        let test = DynamicFeasibility::new(
            MotionPattern::Spatial,
            &bounds,
            dynamics_body(),
            &[2.0, 2.0, 2.0, 5.0, 5.0, 5.0],
            &[0.0; 6],
            &[0.0; 6],
        )
        .unwrap();
        let grid = Grid::over_frame(&robot, 24);
        let eval = PoseEvaluator::new(robot, bounds, vec![dynamic_criterion(test)]).unwrap();
        let mut me = Self { eval, grid };
        let feasible = me.run();
        assert!(feasible > 0.0 && feasible < 15_625.0, "{feasible} feasible");
        me
    }

    /// Feasible poses of the grid.
    pub fn feasible(&self) -> usize {
        let ws = constant_orientation_workspace(
            std::hint::black_box(&self.eval),
            &Rotation3::identity(),
            &self.grid,
        )
        .unwrap();
        ws.feasible.iter().filter(|&&f| f).count()
    }
}

impl Default for DynamicGrid {
    fn default() -> Self {
        Self::new()
    }
}

impl Goal for DynamicGrid {
    const UNITS: u64 = 15_625;
    fn run(&mut self) -> f64 {
        self.feasible() as f64
    }
}

/// Issue 29: one catenary solve, span and platform-end tension → L0 and end forces (≤ 1 µs):
/// the example cable (w = 0.5 N/m, EA = 10⁶ N) at 100 spans around its span
/// (9.730114663, −5.131623707) m, tension 111.8 N. One [`Goal::run`] is the 100 solves.
pub struct CatenarySolve {
    /// The cable.
    pub cable: ElasticCatenary,
    /// (horizontal, vertical) spans (m).
    pub spans: Vec<(f64, f64)>,
}

impl CatenarySolve {
    /// The fixture.
    pub fn new() -> Self {
        Self {
            cable: ElasticCatenary::new(0.5, 1e6).unwrap(),
            spans: (0..100)
                .map(|k| {
                    let s = k as f64 / 100.0;
                    (9.730114663 + s, -5.131623707 + 2.0 * s)
                })
                .collect(),
        }
    }

    /// The same spans solved for the unstrained length 11 m instead (the sum of F_x, N).
    pub fn run_for_length(&self) -> f64 {
        let mut f = 0.0;
        for &(x, z) in &self.spans {
            f += self
                .cable
                .solve_for_length(std::hint::black_box(x), z, 11.0)
                .unwrap()
                .horizontal_force;
        }
        f
    }
}

impl Default for CatenarySolve {
    fn default() -> Self {
        Self::new()
    }
}

impl Goal for CatenarySolve {
    const UNITS: u64 = 100;
    fn run(&mut self) -> f64 {
        let mut l = 0.0;
        for &(x, z) in &self.spans {
            l += self
                .cable
                .solve_for_tension(std::hint::black_box(x), z, 111.8)
                .unwrap()
                .unstrained_length;
        }
        l
    }
}

/// Poses with their kinematics and W, the load (N, N·m) and the tension bounds (N).
pub type FeasiblePoses = (
    Vec<(PoseKinematics, DMatrix<f64>)>,
    DVector<f64>,
    TensionBounds,
);

/// The first `count` poses of [`spatial_poses`] where `robot` holds a 10 kg platform under
/// gravity with ℓ2 tensions in [1, 1000] N: their kinematics and W (the fixture of
/// `benches/tension.rs`), with the load and bounds.
pub fn feasible_poses(robot: &Robot, count: usize) -> FeasiblePoses {
    let we = DVector::from_vec(vec![0.0, 0.0, -9.80665 * 10.0, 0.0, 0.0, 0.0]);
    let b = TensionBounds::uniform(robot.cable_count(), 1.0, 1000.0).unwrap();
    let mut l2 = TensionSolver::new(Method::L2);
    let mut out = Vec::new();
    for pose in spatial_poses(20 * count) {
        let Ok(kin) = robot.inverse_kinematics(&pose) else {
            continue;
        };
        let w = kin.wrench_matrix();
        if l2.is_feasible(&TensionProblem::new(&w, &we, &b)).unwrap() {
            out.push((kin, w));
            if out.len() == count {
                break;
            }
        }
    }
    assert_eq!(out.len(), count, "not enough feasible poses");
    (out, we, b)
}

/// Issue 29: ℓ2 statics with sagging cables (≤ 20 µs per pose): the fixed point of
/// `cdpr_tension::SaggingStatics` on the first 100 poses of [`feasible_poses`] of
/// `ipanema_like_8` (10 kg under gravity, t ∈ [1, 1000] N), cables of 0.02 kg/m and
/// E·S = 60 kN under 9.80665 m/s². One [`Goal::run`] is the 100 poses.
pub struct SaggingStatics {
    poses: Vec<PoseKinematics>,
    load: DVector<f64>,
    bounds: TensionBounds,
    model: RobotCatenaries,
    statics: cdpr_tension::SaggingStatics,
    solver: TensionSolver,
}

impl SaggingStatics {
    /// The fixture.
    pub fn new() -> Self {
        let (poses, load, bounds) = feasible_poses(&ipanema_like_8(), 100);
        let g0 = Vector3::new(0.0, 0.0, -9.80665);
        Self {
            poses: poses.into_iter().map(|(k, _)| k).collect(),
            load,
            bounds,
            model: RobotCatenaries::new(&[0.02; 8], &[60_000.0; 8], &g0).unwrap(),
            statics: cdpr_tension::SaggingStatics::default(),
            solver: TensionSolver::new(Method::L2),
        }
    }

    /// The outcomes of the 100 poses.
    pub fn outcomes(&mut self) -> Vec<SaggingOutcome> {
        self.poses
            .iter()
            .map(|kin| {
                self.statics
                    .solve(&mut self.solver, kin, &self.model, &self.load, &self.bounds)
                    .unwrap()
            })
            .collect()
    }
}

impl Default for SaggingStatics {
    fn default() -> Self {
        Self::new()
    }
}

impl Goal for SaggingStatics {
    const UNITS: u64 = 100;
    fn run(&mut self) -> f64 {
        let mut feasible = 0;
        for kin in &self.poses {
            let o = self
                .statics
                .solve(
                    &mut self.solver,
                    std::hint::black_box(kin),
                    &self.model,
                    &self.load,
                    &self.bounds,
                )
                .unwrap();
            feasible += matches!(o, SaggingOutcome::Feasible(_)) as usize;
        }
        feasible as f64
    }
    fn describe(&mut self) -> String {
        let its: Vec<usize> = self
            .outcomes()
            .iter()
            .filter_map(|o| match o {
                SaggingOutcome::Feasible(s) => Some(s.iterations),
                SaggingOutcome::Infeasible(_) => None,
            })
            .collect();
        let mean = its.iter().sum::<usize>() as f64 / its.len().max(1) as f64;
        format!(
            "{} feasible, {mean:.2} fixed-point iterations per pose",
            its.len()
        )
    }
}

/// Issue 29: elasto-geometric forward kinematics (≤ 10 µs per solve): `ipanema_like_8`, 100
/// poses of [`spatial_poses`], platform-end tensions 100 N (the wrench they balance is the
/// load), each solve started 1 mm and 1 mrad from the pose (tracking a moving platform);
/// E·S = 60 kN, weightless ([`ElasticForward::elastic`]) or 0.02 kg/m
/// ([`ElasticForward::catenary`]). One [`Goal::run`] is the 100 solves.
pub struct ElasticForward {
    cases: Vec<(Vec<f64>, Vec<f64>, Pose)>,
    fk: ElastoGeometricForward<'static>,
}

impl ElasticForward {
    /// Weightless elastic cables (the goal's case).
    pub fn elastic() -> Self {
        Self::with_density(0.0)
    }

    /// Sagging cables of 0.02 kg/m.
    pub fn catenary() -> Self {
        Self::with_density(0.02)
    }

    fn with_density(rho: f64) -> Self {
        let robot = ipanema_like_8();
        let model =
            RobotCatenaries::new(&[rho; 8], &[6e4; 8], &Vector3::new(0.0, 0.0, -9.81)).unwrap();
        let mut cases = Vec::new();
        let mut cables = Vec::new();
        let mut w = DMatrix::zeros(0, 0);
        for p in &spatial_poses(100) {
            let kin = robot.inverse_kinematics(p).unwrap();
            model.with_tensions(&kin, &[100.0; 8], &mut cables).unwrap();
            write_sagging_wrench_matrix(&kin, &cables, &mut w);
            let w_ext: Vec<f64> = (0..6).map(|r| -100.0 * w.row(r).sum()).collect();
            let l0: Vec<f64> = cables.iter().map(|c| c.unstrained_length).collect();
            let start = Pose::new(
                p.position + Vector3::new(1e-3, -1e-3, 1e-3),
                Rotation3::new(Vector3::new(1e-3, 0.0, -1e-3)) * p.rotation,
            );
            cases.push((l0, w_ext, start));
        }
        let fk = ElastoGeometricForward::new(leak(robot), leak(model), Default::default()).unwrap();
        Self { cases, fk }
    }
}

impl Goal for ElasticForward {
    const UNITS: u64 = 100;
    fn run(&mut self) -> f64 {
        let mut ok = 0;
        for (l0, w_ext, start) in &self.cases {
            let s = self
                .fk
                .solve(std::hint::black_box(l0), w_ext, start)
                .unwrap();
            ok += (s.status == ElastoGeometricStatus::Equilibrium) as usize;
        }
        assert_eq!(ok, self.cases.len());
        ok as f64
    }
}

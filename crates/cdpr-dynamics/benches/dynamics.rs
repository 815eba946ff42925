//! Dynamics hot paths on the IPAnema-1-like 8-cable robot (`ipanema_like_8`, t ∈ [10, 1000] N,
//! 5 kg cuboid platform, centre of mass 2 cm off the origin), single thread:
//! - `inverse_dynamics/l2_10000_samples`: a 10 000-sample quintic trajectory (2 s), ℓ2 tensions
//!   with the inertial wrench at every sample (target ≤ 10 ms);
//! - `inverse_dynamics/drive_train_10000_samples`: motor speeds, torques, powers, peaks and RMS
//!   values of 8 winches along that profile;
//! - `forward_dynamics/rk4_tension_driven`: RK4 steps under constant tensions (the static
//!   tensions of the start pose), 1 000 steps of 1 ms per iteration (target ≥ 500 000 steps/s).

use cdpr_dynamics::{
    Drive, RigidBody, Simulator, State, TimeLaw, TimingSettings, Trajectory, Winch, drive_train,
    inverse_dynamics,
};
use cdpr_kinematics::reference_robots::ipanema_like_8;
use cdpr_kinematics::{MotionPattern, Pose};
use cdpr_tension::{Method, TensionBounds, TensionOutcome, TensionProblem, TensionSolver};
use cdpr_wrench::{Platform, STANDARD_GRAVITY};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{DVector, Matrix3, Vector3, Vector6};
use std::hint::black_box;

fn body() -> RigidBody {
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

fn bench_inverse(c: &mut Criterion) {
    const N: usize = 10_000;
    let robot = ipanema_like_8();
    let b = body();
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
    let samples = traj.sample(2.0 / (N - 1) as f64).unwrap();
    assert_eq!(samples.len(), N);
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let mut solver = TensionSolver::new(Method::L2);
    let load = |_: usize, s: &cdpr_dynamics::TimedSample| {
        DVector::from_column_slice(b.gravity_wrench6(s.pose.rotation.matrix()).as_slice())
    };
    let p = inverse_dynamics(&robot, Some(&b), &samples, &bounds, &mut solver, None, load).unwrap();
    assert_eq!(
        p.feasible_count(),
        N,
        "{:?}",
        p.reasons.iter().flatten().next()
    );
    let mut g = c.benchmark_group("inverse_dynamics");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("l2_10000_samples", |bench| {
        bench.iter(|| {
            let p = inverse_dynamics(&robot, Some(&b), &samples, &bounds, &mut solver, None, load)
                .unwrap();
            black_box(p.feasible_count())
        })
    });
    let winches = [Winch::new(0.05, 10.0, 2e-4, Some(5.0), Some(300.0)).unwrap(); 8];
    g.bench_function("drive_train_10000_samples", |bench| {
        bench.iter(|| black_box(drive_train(&winches, &p).unwrap().within_limits))
    });
    g.finish();
}

fn bench_forward(c: &mut Criterion) {
    const STEPS: usize = 1000;
    let robot = ipanema_like_8();
    let b = body();
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
    let drive = Drive::Tensions(t.tensions.iter().copied().collect());
    let mut sim = Simulator::new(&robot, b, drive, &[0.0; 6]).unwrap();
    let start = State::new(&pose, Vector6::new(0.1, 0.0, 0.0, 0.0, 0.0, 0.2));
    let mut g = c.benchmark_group("forward_dynamics");
    g.throughput(Throughput::Elements(STEPS as u64));
    g.bench_function("rk4_tension_driven", |bench| {
        bench.iter(|| {
            let mut x = start;
            for k in 0..STEPS {
                x = sim.rk4_step(k as f64 * 1e-3, &x, 1e-3).unwrap();
            }
            black_box(x)
        })
    });
    g.finish();
}

criterion_group!(benches, bench_inverse, bench_forward);
criterion_main!(benches);

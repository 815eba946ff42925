//! Tension profiles along a path (issue 8): a 1000-sample straight path of the 8-cable spatial
//! robot (`ipanema_like_8`, t ∈ [10, 1000] N, E·S = 60 000 N, 5 kg platform under gravity plus a
//! 30 N lateral load) with SOTDA (corners, ν = 0.9), and with ℓ2 and the barycentre for
//! comparison. Each iteration computes the whole profile (inverse kinematics, W, tensions,
//! certificate, jumps): the target is ≤ 20 ms per 1000-sample SOTDA trajectory.

use cdpr_benches::ipanema_like_8;
use cdpr_kinematics::{MotionPattern, Path, Sampling};
use cdpr_tension::profile::tension_profile;
use cdpr_tension::{Method, SotdaSettings, TensionBounds, TensionSolver};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::DVector;
use std::hint::black_box;

fn bench_trajectory(c: &mut Criterion) {
    const N: usize = 1000;
    let robot = ipanema_like_8();
    let path = Path::from_coordinates(
        MotionPattern::Spatial,
        &[
            vec![-0.4, -0.3, 0.8, 0.0, 0.0, -0.05],
            vec![0.4, 0.3, 1.2, 0.05, 0.0, 0.05],
        ],
    )
    .unwrap();
    let samples = path.sample(Sampling::Count(N)).unwrap();
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let es = [60_000.0; 8];
    let wrench = DVector::from_vec(vec![0.0, 30.0, -5.0 * 9.80665, 0.0, 0.0, 0.0]);
    let mut g = c.benchmark_group("trajectory_8_cable_1000_samples");
    g.throughput(Throughput::Elements(N as u64));
    for (name, mut solver) in [
        (
            "sotda",
            TensionSolver::sotda(SotdaSettings {
                nu: 0.9,
                ..SotdaSettings::default()
            }),
        ),
        ("l2", TensionSolver::new(Method::L2)),
        ("barycenter", TensionSolver::new(Method::Barycenter)),
    ] {
        // Sanity: the whole path is feasible (otherwise we would time the infeasible branch).
        let p = tension_profile(&robot, &samples, &bounds, &mut solver, Some(&es), |_| {
            wrench.clone()
        })
        .unwrap();
        assert_eq!(p.feasible_count(), N, "{name}: {:?}", p.reasons);
        g.bench_function(name, |b| {
            b.iter(|| {
                let p = tension_profile(&robot, &samples, &bounds, &mut solver, Some(&es), |_| {
                    wrench.clone()
                })
                .unwrap();
                black_box(p.max_jump)
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench_trajectory);
criterion_main!(benches);

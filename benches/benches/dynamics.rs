//! Issue 28's speed goals on the IPAnema-1-like 8-cable robot (`ipanema_like_8`, 5 kg cuboid
//! platform with its centre of mass 2 cm off the origin), fixtures in [`cdpr_benches::goals`]:
//! - `inverse_dynamics/l2_10000_samples` ([`InverseDynamics`], single thread, ≤ 10 ms);
//! - `inverse_dynamics/drive_train_10000_samples`: motor speeds, torques, powers, peaks and RMS
//!   values of 8 winches along that profile;
//! - `forward_dynamics/rk4_tension_driven` ([`Rk4`], 1 000 steps per iteration, single thread,
//!   ≥ 500 000 steps/s);
//! - `dynamic_grid/eight_cable_15625` ([`DynamicGrid`], rayon's pool: ≤ 50 ms on 2 cores).
//!
//! Instruction counts of the same code: `examples/goals_instructions.rs`.

use cdpr_benches::goals::{DynamicGrid, Goal, InverseDynamics, Rk4};
use cdpr_dynamics::{Winch, drive_train};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

fn bench_inverse(c: &mut Criterion) {
    let mut goal = InverseDynamics::new();
    let mut g = c.benchmark_group("inverse_dynamics");
    g.throughput(Throughput::Elements(InverseDynamics::UNITS));
    g.bench_function("l2_10000_samples", |b| b.iter(|| black_box(goal.run())));
    let p = goal.profile();
    let winches = [Winch::new(0.05, 10.0, 2e-4, Some(5.0), Some(300.0)).unwrap(); 8];
    g.bench_function("drive_train_10000_samples", |b| {
        b.iter(|| black_box(drive_train(&winches, &p).unwrap().within_limits))
    });
    g.finish();
}

fn bench_forward(c: &mut Criterion) {
    let mut goal = Rk4::new();
    let mut g = c.benchmark_group("forward_dynamics");
    g.throughput(Throughput::Elements(Rk4::UNITS));
    g.bench_function("rk4_tension_driven", |b| b.iter(|| black_box(goal.run())));
    g.finish();
}

fn bench_grid(c: &mut Criterion) {
    let mut goal = DynamicGrid::new();
    let mut g = c.benchmark_group("dynamic_grid");
    g.sample_size(20);
    g.throughput(Throughput::Elements(DynamicGrid::UNITS));
    g.bench_function("eight_cable_15625", |b| b.iter(|| black_box(goal.run())));
    g.finish();
}

criterion_group!(benches, bench_inverse, bench_forward, bench_grid);
criterion_main!(benches);

//! Issue 27: self-calibration of an 8-cable spatial robot from 40 samples (goal ≤ 50 ms); the
//! fixture is [`cdpr_benches::goals::SelfCalibration`] (instruction counts of the same code:
//! `examples/goals_instructions.rs self_calibration`).

use cdpr_benches::goals::{Goal, SelfCalibration};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn self_calibration(c: &mut Criterion) {
    let mut goal = SelfCalibration::new();
    let mut g = c.benchmark_group("calibration");
    g.sample_size(20);
    g.bench_function("self_calibration_8_spatial_40_samples", |b| {
        b.iter(|| black_box(goal.run()))
    });
    g.finish();
}

criterion_group!(benches, self_calibration);
criterion_main!(benches);

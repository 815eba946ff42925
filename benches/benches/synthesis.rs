//! Dimensional synthesis (thesis §6.6): one dextrous-area evaluation and one optimisation run.

use cdpr_tension::Method as TensionMethod;
use cdpr_workspace::synthesis::{DextrousArea, Method, SynthesisSettings, synthesise};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

/// Load L1 of Table 6.3.
const L1: [f64; 3] = [0.0, -10.0, 0.0];

fn synthesis(c: &mut Criterion) {
    let mut g = c.benchmark_group("synthesis");
    g.sample_size(10);
    // Table 6.5 run 3: 3 cables, m = 100, m_sl = 3, exact tensions.
    let objective = DextrousArea::thesis(3, L1, TensionMethod::Exact).expect("thesis settings");
    let start = [0.2814, 3.978, 4.278];
    g.bench_function("dextrous_area/three_cable_m100_3_slices", |b| {
        b.iter(|| black_box(objective.area(black_box(&start)).expect("valid design")))
    });
    // One Dynamic-Q run from the same start (the thesis' optimiser).
    let settings = SynthesisSettings {
        method: Method::DynamicQ,
        ..SynthesisSettings::default()
    };
    g.bench_function("dynamic_q/table_6_5_run_3", |b| {
        b.iter(|| {
            let mut obj = objective.clone();
            black_box(
                synthesise(&mut obj, &start, &settings)
                    .expect("valid settings")
                    .area,
            )
        })
    });
    g.finish();
}

criterion_group!(benches, synthesis);
criterion_main!(benches);

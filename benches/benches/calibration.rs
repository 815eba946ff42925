//! Issue 27: self-calibration of an 8-cable spatial robot from 40 samples (goal ≤ 50 ms):
//! anchors and offsets unknown (p = 32, gauge 6, 240 pose unknowns), the IPAnema-like robot as
//! built (anchors moved by up to 2 cm, offsets up to 5 cm), lengths with a deterministic error
//! of about 0.1 mm, starting from the nominal robot (forward kinematics of every sample
//! included).

use cdpr_calibration::nalgebra::{Rotation3, Vector3};
use cdpr_calibration::{Readings, Samples, Unknowns, calibrate};
use cdpr_kinematics::reference_robots::ipanema_like_8;
use cdpr_kinematics::{Cable, Pose, Robot};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn problem() -> (Robot, Samples) {
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
    (
        nominal,
        Samples {
            readings,
            poses: None,
        },
    )
}

fn self_calibration(c: &mut Criterion) {
    let (nominal, samples) = problem();
    let unknowns = Unknowns::parse("frame,offsets").unwrap();
    let check = calibrate(&nominal, &samples, unknowns, &Readings::Absolute).unwrap();
    assert!(check.identifiable && check.converged, "{check:?}");
    let mut g = c.benchmark_group("calibration");
    g.sample_size(20);
    g.bench_function("self_calibration_8_spatial_40_samples", |b| {
        b.iter(|| {
            black_box(
                calibrate(&nominal, black_box(&samples), unknowns, &Readings::Absolute)
                    .unwrap()
                    .residual_rms,
            )
        })
    });
    g.finish();
}

criterion_group!(benches, self_calibration);
criterion_main!(benches);

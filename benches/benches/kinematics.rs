//! Inverse kinematics and wrench matrix (cdpr-kinematics).

use cdpr_benches::{ipanema_like_8, spatial_poses};
use cdpr_kinematics::PoseKinematics;
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::DMatrix;
use std::hint::black_box;

fn inverse_kinematics(c: &mut Criterion) {
    let robot = ipanema_like_8();
    let poses = spatial_poses(1000);
    let mut kin = PoseKinematics::for_robot(&robot);
    let mut w = DMatrix::zeros(6, 8);
    let mut g = c.benchmark_group("kinematics");
    // One iteration = one pose: IK of 8 cables + the 6 × 8 wrench matrix, no allocation.
    let mut k = 0;
    g.bench_function("ik_and_wrench_matrix/spatial_8", |b| {
        b.iter(|| {
            k = (k + 1) % poses.len();
            robot
                .update_kinematics(black_box(&poses[k]), &mut kin)
                .unwrap();
            kin.write_wrench_matrix(&mut w);
            black_box(w[(5, 7)])
        })
    });
    g.finish();
}

criterion_group!(benches, inverse_kinematics);
criterion_main!(benches);

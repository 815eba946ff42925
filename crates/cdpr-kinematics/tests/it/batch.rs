//! `Robot::wrench_matrices` (batch IK + W): every block equals the single-pose wrench matrix
//! bit for bit, for every motion pattern and with pulleys; rejected poses are exactly those
//! `update_kinematics` rejects; wrong buffer lengths are errors.

use cdpr_kinematics::reference_robots::{
    ipanema_like_8, ipanema_like_8_pulleys, krut_point_robot, thesis_four_cable,
};
use cdpr_kinematics::strategies::{arb_pose, arb_robot};
use cdpr_kinematics::{Cable, KinematicsError, MotionPattern, Pose, Robot};
use nalgebra::Vector3;
use proptest::prelude::*;

fn poses(motion: MotionPattern, count: usize) -> Vec<Pose> {
    (0..count)
        .map(|k| {
            let s = k as f64 / count as f64;
            let (x, y, z) = (-0.4 + 0.8 * s, 0.3 - 0.5 * s, 0.6 + 0.7 * s);
            match motion {
                MotionPattern::Spatial => {
                    Pose::spatial(Vector3::new(x, y, z), 0.1 * s, -0.05, 0.2 - 0.3 * s)
                }
                MotionPattern::Planar => Pose::planar(0.3 * x, 0.3 * y, 0.2 - 0.4 * s),
                MotionPattern::Point3 => Pose::point(x, y, z),
                MotionPattern::Point2 => Pose::point(100.0 * x, 100.0 * y, 0.0),
            }
        })
        .collect()
}

fn point3_robot() -> Robot {
    let c = |x: f64, y: f64, z: f64| Cable {
        frame: Vector3::new(x, y, z),
        platform: Vector3::zeros(),
        pulley: None,
    };
    Robot::new(
        MotionPattern::Point3,
        vec![
            c(2.0, 2.0, 2.0),
            c(-2.0, 2.0, 2.0),
            c(0.0, -2.0, 2.0),
            c(0.0, 0.0, -1.0),
        ],
    )
    .unwrap()
}

fn check_bitwise(robot: &Robot, poses: &[Pose]) {
    check_path_bitwise(robot, poses, Robot::wrench_matrices);
    check_path_bitwise(robot, poses, Robot::wrench_matrices_portable);
}

type BatchPath = fn(&Robot, &[Pose], &mut [f64], &mut [bool]) -> Result<usize, KinematicsError>;

/// One build of the batch kernel (the one the CPU selects, or the portable one) against the
/// single-pose path.
fn check_path_bitwise(robot: &Robot, poses: &[Pose], path: BatchPath) {
    let block = robot.motion().dof() * robot.cable_count();
    let mut out = vec![f64::NAN; poses.len() * block];
    let mut valid = vec![false; poses.len()];
    let count = path(robot, poses, &mut out, &mut valid).unwrap();
    assert_eq!(count, valid.iter().filter(|v| **v).count());
    for (k, pose) in poses.iter().enumerate() {
        match robot.inverse_kinematics(pose) {
            Ok(kin) => {
                assert!(valid[k], "pose {k}");
                let w = kin.wrench_matrix();
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&out[k * block..][..block]),
                    bits(w.as_slice()),
                    "pose {k}"
                );
            }
            Err(_) => assert!(!valid[k], "pose {k}"),
        }
    }
}

#[test]
fn blocks_equal_the_single_pose_wrench_matrix_bit_for_bit() {
    for robot in [
        ipanema_like_8(),
        ipanema_like_8_pulleys(),
        thesis_four_cable(),
        krut_point_robot(3, 1000.0, 30.0),
        point3_robot(),
    ] {
        check_bitwise(&robot, &poses(robot.motion(), 57));
    }
}

#[test]
fn rejected_poses_are_those_inverse_kinematics_rejects() {
    let robot = ipanema_like_8();
    let anchor = robot.cables()[0].frame - robot.cables()[0].platform;
    let mut p = poses(MotionPattern::Spatial, 5);
    // Cable 1 of zero length, a NaN position, an overflowing one.
    p[1] = Pose::spatial(anchor, 0.0, 0.0, 0.0);
    p[2] = Pose::spatial(Vector3::new(f64::NAN, 0.0, 1.0), 0.0, 0.0, 0.0);
    p[3] = Pose::spatial(Vector3::new(1e308, 1e308, 1.0), 0.0, 0.0, 0.0);
    let mut out = vec![0.0; 5 * 48];
    let mut valid = [true; 5];
    assert_eq!(robot.wrench_matrices(&p, &mut out, &mut valid).unwrap(), 2);
    assert_eq!(valid, [true, false, false, false, true]);
    check_bitwise(&robot, &p);
}

#[test]
fn wrong_buffer_lengths_are_errors() {
    let robot = ipanema_like_8();
    let p = poses(MotionPattern::Spatial, 3);
    let mut valid = [false; 3];
    let err = robot
        .wrench_matrices(&p, &mut vec![0.0; 3 * 48 - 1], &mut valid)
        .unwrap_err();
    assert!(matches!(
        err,
        KinematicsError::WrongDimension {
            expected: 144,
            found: 143,
            ..
        }
    ));
    let err = robot
        .wrench_matrices(&p, &mut vec![0.0; 3 * 48], &mut [false; 2])
        .unwrap_err();
    assert!(matches!(
        err,
        KinematicsError::WrongDimension {
            expected: 3,
            found: 2,
            ..
        }
    ));
}

proptest! {
    /// The structure-of-arrays kernel (groups of four poses, AVX2 or portable build) equals the
    /// single-pose path bit for bit on random spatial robots and pose lists of any length, with
    /// poses that put a platform attachment on its frame anchor (rejected per pose).
    #[test]
    fn lanes_equal_single_pose_bit_for_bit(
        robot in arb_robot(MotionPattern::Spatial, 7..=16),
        mut poses in prop::collection::vec(arb_pose(MotionPattern::Spatial), 0..23),
        degenerate in prop::collection::vec((0usize..64, 0usize..16), 0..3),
    ) {
        for (k, i) in degenerate {
            if !poses.is_empty() {
                let k = k % poses.len();
                let cable = &robot.cables()[i % robot.cable_count()];
                let r = poses[k].rotation;
                poses[k].position = cable.frame - r * cable.platform;
            }
        }
        check_bitwise(&robot, &poses);
    }
}

/// On this machine type the AVX2 build is the one `wrench_matrices` runs: make sure the test
/// above compared two different builds (a CPU without AVX2 compares the portable one twice).
#[test]
fn avx2_build_runs_where_available() {
    #[cfg(target_arch = "x86_64")]
    if !std::arch::is_x86_feature_detected!("avx2") {
        eprintln!("no AVX2 on this CPU: only the portable build is tested");
    }
    let robot = ipanema_like_8();
    check_bitwise(&robot, &poses(MotionPattern::Spatial, 1000));
}

type LanePath = fn(&Robot, &[Pose; 4], &mut [[[f64; 4]; 6]]) -> Result<[bool; 4], KinematicsError>;

/// `Robot::wrench_matrix_lanes` (both builds) against `Robot::wrench_matrices`: the same bits
/// lane by lane and the same validity, for each group of four of `poses` (a multiple of 4).
fn check_lanes(robot: &Robot, poses: &[Pose]) {
    let n = robot.cable_count();
    let mut blocks = vec![0.0; poses.len() * 6 * n];
    let mut valid = vec![false; poses.len()];
    robot
        .wrench_matrices(poses, &mut blocks, &mut valid)
        .unwrap();
    let paths: [LanePath; 2] = [
        Robot::wrench_matrix_lanes,
        Robot::wrench_matrix_lanes_portable,
    ];
    for path in paths {
        for (g, group) in poses.chunks_exact(4).enumerate() {
            let mut out = vec![[[f64::NAN; 4]; 6]; n];
            let ok = path(robot, group.try_into().unwrap(), &mut out).unwrap();
            for l in 0..4 {
                let k = 4 * g + l;
                assert_eq!(ok[l], valid[k], "pose {k}");
                if ok[l] {
                    for j in 0..n {
                        for i in 0..6 {
                            assert_eq!(
                                out[j][i][l].to_bits(),
                                blocks[k * 6 * n + 6 * j + i].to_bits()
                            );
                        }
                    }
                }
            }
        }
    }
}

proptest! {
    /// W in lanes (four poses, cable × row × pose) is the batch W bit for bit, hence the
    /// single-pose W, on random spatial robots (up to 20 cables: beyond the 16 of the block
    /// kernel too) with degenerate poses among them.
    #[test]
    fn wrench_matrix_lanes_equal_the_batch_bit_for_bit(
        robot in arb_robot(MotionPattern::Spatial, 7..=20),
        mut poses in prop::collection::vec(arb_pose(MotionPattern::Spatial), 8),
        degenerate in prop::collection::vec((0usize..8, 0usize..20), 0..3),
    ) {
        for (k, i) in degenerate {
            let cable = &robot.cables()[i % robot.cable_count()];
            let r = poses[k].rotation;
            poses[k].position = cable.frame - r * cable.platform;
        }
        check_lanes(&robot, &poses);
    }
}

/// Lanes with pulleys (pose by pose), with a NaN position; wrong shapes are errors.
#[test]
fn wrench_matrix_lanes_with_pulleys_and_errors() {
    let mut p = poses(MotionPattern::Spatial, 8);
    p[5].position.y = f64::NAN;
    check_lanes(&ipanema_like_8_pulleys(), &p);
    check_lanes(&ipanema_like_8(), &p);
    let four: [Pose; 4] = p[..4].try_into().unwrap();
    let err = ipanema_like_8()
        .wrench_matrix_lanes(&four, &mut [[[0.0; 4]; 6]; 7])
        .unwrap_err();
    assert!(matches!(
        err,
        KinematicsError::WrongDimension {
            expected: 8,
            found: 7,
            ..
        }
    ));
    let planar = thesis_four_cable();
    let four = [Pose::planar(0.0, 0.0, 0.0); 4];
    let err = planar
        .wrench_matrix_lanes(&four, &mut vec![[[0.0; 4]; 6]; planar.cable_count()])
        .unwrap_err();
    assert!(matches!(
        err,
        KinematicsError::WrongDimension {
            expected: 3,
            found: 6,
            ..
        }
    ));
}

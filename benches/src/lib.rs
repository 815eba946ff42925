//! Shared fixtures for the criterion benchmarks in `benches/`: every benchmark draws its robots and
//! poses from here, so that the numbers in the notes refer to the same problems.

use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
use nalgebra::Vector3;

pub use cdpr_kinematics::reference_robots::{ipanema_like_8, ipanema_like_8_pulleys};

/// `count` deterministic poses spread over the central part of the 8-cable robot's frame
/// (|x| ≤ 1, |y| ≤ 0.75, z ∈ [0.5, 1.5], angles within ±0.1 rad), from a fixed LCG.
pub fn spatial_poses(count: usize) -> Vec<Pose> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            let p = Vector3::new(2.0 * next() - 1.0, 1.5 * next() - 0.75, 0.5 + next());
            Pose::spatial(
                p,
                0.2 * next() - 0.1,
                0.2 * next() - 0.1,
                0.2 * next() - 0.1,
            )
        })
        .collect()
}

/// Krut, Company & Pierrot's (2004) 3-motor point robot (§IV-B): motors at 1000 mm, angles 30°, 150°, 270°.
pub fn krut_three_motor() -> Robot {
    let motor = |deg: f64| {
        let a = deg.to_radians();
        Cable {
            frame: Vector3::new(1000.0 * a.cos(), 1000.0 * a.sin(), 0.0),
            platform: Vector3::zeros(),
            pulley: None,
        }
    };
    Robot::new(
        MotionPattern::Point2,
        vec![motor(30.0), motor(150.0), motor(270.0)],
    )
    .expect("valid robot")
}

/// `count` deterministic point poses inside Krut, Company & Pierrot's (2004) triangle (|x|, |y| ≤ 300 mm).
pub fn krut_poses(count: usize) -> Vec<Pose> {
    (0..count)
        .map(|i| {
            let a = i as f64 * 2.399_963; // golden angle: a sunflower spiral
            let r = 300.0 * ((i as f64 + 0.5) / count as f64).sqrt();
            Pose::point(r * a.cos(), r * a.sin(), 0.0)
        })
        .collect()
}

/// A 10-cable spatial robot (6 DOF, redundancy 4): the 8-cable robot of
/// [`ipanema_like_8`] plus two cables from the middle of its long sides to the platform's
/// centre line. Hyperplane shifting gives 2·C(10, 5) = 504 supporting half-spaces.
pub fn ten_cable_spatial() -> Robot {
    let base = ipanema_like_8();
    let mut cables = base.cables().to_vec();
    cables.push(Cable {
        frame: Vector3::new(0.0, 1.5, 2.0),
        platform: Vector3::new(0.0, 0.12, 0.05),
        pulley: None,
    });
    cables.push(Cable {
        frame: Vector3::new(0.0, -1.5, 0.0),
        platform: Vector3::new(0.0, -0.12, -0.05),
        pulley: None,
    });
    Robot::new(MotionPattern::Spatial, cables).expect("valid 10-cable robot")
}

/// Issue 17's fixture: the IPAnema 1 of `examples/robots/caspr-ipanema-1.toml` (8 cables, 6 DOF),
/// bounds t ∈ [1, 1000] N, the platform's 25 kg under the file's gravity (245.25 N along −z),
/// 20 000 poses of [`spatial_poses`].
pub mod issue_17 {
    use super::spatial_poses;
    use cdpr_io::RobotDescription;
    use cdpr_kinematics::{Pose, Robot};
    use cdpr_tension::TensionBounds;
    use nalgebra::DVector;

    /// Poses per iteration.
    pub const POSES: usize = 20_000;

    /// The robot, bounds, load and poses of issue 17.
    pub struct Fixture {
        pub robot: Robot,
        pub bounds: TensionBounds,
        pub load: DVector<f64>,
        pub poses: Vec<Pose>,
    }

    pub fn fixture() -> Fixture {
        let file = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../examples/robots/caspr-ipanema-1.toml"
        );
        let desc = RobotDescription::load(file).expect("IPAnema 1 robot file");
        assert_eq!(desc.robot.cable_count(), 8);
        let p = &desc.platform;
        assert_eq!(p.centre_of_mass.norm(), 0.0, "no gravity moment");
        let weight = p.mass * p.gravity;
        assert!((weight.z + 245.25).abs() < 1e-9, "25 kg under 9.81 m/s²");
        Fixture {
            robot: desc.robot,
            bounds: TensionBounds::uniform(8, 1.0, 1000.0).unwrap(),
            load: DVector::from_vec(vec![weight.x, weight.y, weight.z, 0.0, 0.0, 0.0]),
            poses: spatial_poses(POSES),
        }
    }
}

/// A 12-cable spatial robot (6 DOF, redundancy 6): the 10-cable robot of
/// [`ten_cable_spatial`] plus two cables from the middle of its short sides to the platform's
/// ends. l2-max on it has C(12, 6)·2⁶ = 59 136 candidate bases.
pub fn twelve_cable_spatial() -> Robot {
    let base = ten_cable_spatial();
    let mut cables = base.cables().to_vec();
    cables.push(Cable {
        frame: Vector3::new(2.0, 0.0, 2.0),
        platform: Vector3::new(0.15, 0.0, 0.05),
        pulley: None,
    });
    cables.push(Cable {
        frame: Vector3::new(-2.0, 0.0, 0.0),
        platform: Vector3::new(-0.15, 0.0, -0.05),
        pulley: None,
    });
    Robot::new(MotionPattern::Spatial, cables).expect("valid 12-cable robot")
}

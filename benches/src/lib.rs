//! Shared fixtures for the criterion benchmarks in `benches/`: every benchmark draws its robots and
//! poses from here, so that the numbers in the notes refer to the same problems.

pub mod goals;

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

/// Issue 26's fixture, WireLib's own robot: `CIPAnema1Design` (Pott et al. 2013; WireLib's
/// geometry generator with its nominal parameters, frame 4 × 3 × 2 m, platform 0.12 × 0.12 m):
/// base anchors (∓2, ±1.5, 2) m for cables 1–4 and the same corners at z = 0 for cables 5–8,
/// platform anchors (∓0.06, ±0.06, 0) m in the same corner order (cable k's base and platform
/// corners on the same side, as WireLib's `setBase`/`setPlatform` order and
/// `examples/robots/caspr-ipanema-1.toml`); bounds t ∈ [1, 1000] N; external wrench
/// w = (0, 0, −245.25 N, 0, 0, 0) (25 kg under 9.81 m/s²); 20 000 poses, x, y uniform in
/// [−1, 1] m, z in [0.3, 1.7] m, XYZ Euler angles (R = R_x R_y R_z, WireLib's
/// `getMatrixFromXYZ`) uniform in [−0.1, 0.1] rad, from SplitMix64 seeded with 26.
pub mod issue_26 {
    use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};
    use cdpr_tension::TensionBounds;
    use nalgebra::{DVector, Vector3};

    /// Poses per iteration.
    pub const POSES: usize = 20_000;
    /// The seed of the pose sampler.
    pub const SEED: u64 = 26;

    /// The robot, bounds, load and poses of issue 26.
    pub struct Fixture {
        /// WireLib's `CIPAnema1Design`.
        pub robot: Robot,
        /// t ∈ [1, 1000] N.
        pub bounds: TensionBounds,
        /// w_ext = (0, 0, −245.25, 0, 0, 0) (N, N·m).
        pub load: DVector<f64>,
        /// The 20 000 poses.
        pub poses: Vec<Pose>,
    }

    /// WireLib's `CIPAnema1Design` (frame length 4 m, width 3 m, height 2 m, platform
    /// 0.12 m × 0.12 m).
    pub fn robot() -> Robot {
        let (fl, fw, fh, pl, pw) = (4.0, 3.0, 2.0, 0.12, 0.12);
        let corner = |k: usize| -> (f64, f64) {
            match k % 4 {
                0 => (-0.5, 0.5),
                1 => (0.5, 0.5),
                2 => (0.5, -0.5),
                _ => (-0.5, -0.5),
            }
        };
        let cables = (0..8)
            .map(|k| {
                let (sx, sy) = corner(k);
                Cable {
                    frame: Vector3::new(sx * fl, sy * fw, if k < 4 { fh } else { 0.0 }),
                    platform: Vector3::new(sx * pl, sy * pw, 0.0),
                    pulley: None,
                }
            })
            .collect();
        Robot::new(MotionPattern::Spatial, cables).expect("valid IPAnema 1")
    }

    /// SplitMix64 (Steele, Lea & Flood 2014): uniform f64 in [0, 1) from the top 53 bits.
    fn uniform(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// `count` poses of the issue's distribution from `seed` (x, y, z, then the three angles
    /// of each pose, in that order).
    pub fn poses(count: usize, seed: u64) -> Vec<Pose> {
        let mut next = uniform(seed);
        (0..count)
            .map(|_| {
                let x = -1.0 + 2.0 * next();
                let y = -1.0 + 2.0 * next();
                let z = 0.3 + 1.4 * next();
                let a = -0.1 + 0.2 * next();
                let b = -0.1 + 0.2 * next();
                let c = -0.1 + 0.2 * next();
                Pose::spatial(Vector3::new(x, y, z), a, b, c)
            })
            .collect()
    }

    /// The fixture.
    pub fn fixture() -> Fixture {
        Fixture {
            robot: robot(),
            bounds: TensionBounds::uniform(8, 1.0, 1000.0).unwrap(),
            load: DVector::from_vec(vec![0.0, 0.0, -245.25, 0.0, 0.0, 0.0]),
            poses: poses(POSES, SEED),
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

//! The checks of issue 27: noise-free recovery (known poses: anchors and offsets to 1e-9;
//! unknown poses: inter-anchor distances to 1e-9), the residual and the reported σ under noise,
//! the counting rule (6-cable spatial robots never self-calibrate), relative readings.

use cdpr_calibration::nalgebra::{Rotation3, Vector3};
use cdpr_calibration::{
    Calibration, CalibrationError, Parameters, Readings, Samples, Unknowns, calibrate,
};
use cdpr_kinematics::reference_robots::{ipanema_like_8, ipanema_like_8_pulleys};
use cdpr_kinematics::{Cable, MotionPattern, Pose, Robot};

/// A deterministic generator: splitmix64, uniform in [−1, 1) and standard normal (Box–Muller).
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn normal(&mut self) -> f64 {
        let u1 = ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
        let u2 = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}

/// The "as built" robot: each nominal anchor moved by up to ±2 cm, each attachment by ±5 mm.
fn as_built(nominal: &Robot, rng: &mut Rng) -> Robot {
    let cables = nominal
        .cables()
        .iter()
        .map(|c| {
            let mut frame =
                c.frame + 0.02 * Vector3::new(rng.uniform(), rng.uniform(), rng.uniform());
            let mut platform =
                c.platform + 0.005 * Vector3::new(rng.uniform(), rng.uniform(), rng.uniform());
            if nominal.motion().space_dim() == 2 {
                frame.z = 0.0;
                platform.z = 0.0;
            }
            if !nominal.motion().has_orientation() {
                platform = Vector3::zeros();
            }
            Cable {
                frame,
                platform,
                pulley: None,
            }
        })
        .collect();
    Robot::new(nominal.motion(), cables).unwrap()
}

/// k poses spread in the IPAnema-like robot's workspace (±0.2 rad).
fn spatial_poses(k: usize, rng: &mut Rng) -> Vec<Pose> {
    (0..k)
        .map(|_| {
            Pose::new(
                Vector3::new(
                    0.9 * rng.uniform(),
                    0.7 * rng.uniform(),
                    1.0 + 0.35 * rng.uniform(),
                ),
                Rotation3::new(0.2 * Vector3::new(rng.uniform(), rng.uniform(), rng.uniform())),
            )
        })
        .collect()
}

/// Readings ρ = (l − o) / g of the true robot, plus noise of σ (m) on each length.
fn readings(
    truth: &Robot,
    offsets: &[f64],
    gains: &[f64],
    poses: &[Pose],
    sigma: f64,
    rng: &mut Rng,
) -> Vec<f64> {
    poses
        .iter()
        .flat_map(|p| {
            truth
                .inverse_kinematics(p)
                .unwrap()
                .lengths()
                .collect::<Vec<_>>()
        })
        .enumerate()
        .map(|(j, l)| {
            let i = j % offsets.len();
            (l + sigma * rng.normal() - offsets[i]) / gains[i]
        })
        .collect()
}

/// `truth` with the attachments of `nominal`.
fn nominal_attachments(truth: &Robot, nominal: &Robot) -> Robot {
    Robot::new(
        truth.motion(),
        truth
            .cables()
            .iter()
            .zip(nominal.cables())
            .map(|(t, n)| Cable {
                platform: n.platform,
                ..*t
            })
            .collect(),
    )
    .unwrap()
}

fn offsets_of(n: usize, rng: &mut Rng) -> Vec<f64> {
    (0..n).map(|_| 0.05 * rng.uniform()).collect()
}

fn distances(frame: &[Vector3<f64>]) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 0..frame.len() {
        for j in i + 1..frame.len() {
            out.push((frame[i] - frame[j]).norm());
        }
    }
    out
}

#[test]
fn known_poses_recover_anchors_attachments_and_offsets_exactly() {
    let mut rng = Rng(1);
    let nominal = ipanema_like_8();
    let truth = as_built(&nominal, &mut rng);
    let offsets = offsets_of(8, &mut rng);
    let gains = vec![1.0; 8];
    let poses = spatial_poses(20, &mut rng);
    let samples = Samples {
        readings: readings(&truth, &offsets, &gains, &poses, 0.0, &mut rng),
        poses: Some(poses),
    };
    let unknowns = Unknowns::parse("frame,platform,offsets").unwrap();
    let cal = calibrate(&nominal, &samples, unknowns, &Readings::Absolute).unwrap();
    assert!(cal.identifiable && cal.converged, "{cal:?}");
    assert_eq!(cal.rank_deficiency, 0);
    for (i, c) in truth.cables().iter().enumerate() {
        assert!(
            (cal.parameters.frame[i] - c.frame).norm() < 1e-9,
            "anchor {i}"
        );
        assert!(
            (cal.parameters.platform[i] - c.platform).norm() < 1e-9,
            "attachment {i}"
        );
        assert!(
            (cal.parameters.offsets[i] - offsets[i]).abs() < 1e-9,
            "offset {i}"
        );
    }
    assert!(cal.residual_rms < 1e-12);
    assert!(cal.gauge.is_empty());
}

#[test]
fn self_calibration_recovers_inter_anchor_distances_and_offsets_exactly() {
    let mut rng = Rng(2);
    let nominal = ipanema_like_8();
    // The attachments as nominal: frame and offsets unknown.
    let truth = nominal_attachments(&as_built(&nominal, &mut rng), &nominal);
    let offsets = offsets_of(8, &mut rng);
    let poses = spatial_poses(40, &mut rng);
    let samples = Samples {
        readings: readings(&truth, &offsets, &[1.0; 8], &poses, 0.0, &mut rng),
        poses: None,
    };
    let unknowns = Unknowns::parse("frame,offsets").unwrap();
    let cal = calibrate(&nominal, &samples, unknowns, &Readings::Absolute).unwrap();
    assert!(cal.identifiable && cal.converged, "{cal:?}");
    assert_eq!(cal.counting.gauge, 6);
    assert_eq!(cal.gauge.len(), 3, "{:?}", cal.gauge);
    let true_frame: Vec<Vector3<f64>> = truth.cables().iter().map(|c| c.frame).collect();
    for (a, b) in distances(&cal.parameters.frame)
        .iter()
        .zip(distances(&true_frame))
    {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
    for (got, expected) in cal.parameters.offsets.iter().zip(&offsets) {
        assert!((got - expected).abs() < 1e-9);
    }
    assert_eq!(cal.poses.len(), 40);
    assert!(cal.poses_estimated);
    // Anchor 1 is the datum: held at its nominal value.
    assert_eq!(cal.parameters.frame[0], nominal.cables()[0].frame);
}

/// With length noise σ: residual_rms ≈ σ √(1 − P/N), and the reported σ of each parameter
/// matches the spread of the estimates over repeated draws within a factor of 2.
#[test]
fn reported_sigma_matches_the_spread_over_draws() {
    let mut rng = Rng(3);
    let nominal = ipanema_like_8();
    let truth = nominal_attachments(&as_built(&nominal, &mut rng), &nominal);
    let offsets = offsets_of(8, &mut rng);
    let poses = spatial_poses(30, &mut rng);
    let sigma = 1e-4;
    let unknowns = Unknowns::parse("frame,offsets").unwrap();
    let draws = 40;
    let mut estimates: Vec<Parameters> = Vec::new();
    let mut reported: Vec<Calibration> = Vec::new();
    for _ in 0..draws {
        let samples = Samples {
            readings: readings(&truth, &offsets, &[1.0; 8], &poses, sigma, &mut rng),
            poses: Some(poses.clone()),
        };
        let cal = calibrate(&nominal, &samples, unknowns, &Readings::Absolute).unwrap();
        assert!(cal.identifiable);
        // N = 240 readings, P = 32 parameters.
        let expected_rms = sigma * (1.0f64 - 32.0 / 240.0).sqrt();
        assert!(
            (cal.residual_rms / expected_rms - 1.0).abs() < 0.2,
            "{} vs {expected_rms}",
            cal.residual_rms
        );
        estimates.push(cal.parameters.clone());
        reported.push(cal);
    }
    let spread = |f: &dyn Fn(&Parameters) -> f64| {
        let mean = estimates.iter().map(f).sum::<f64>() / draws as f64;
        (estimates.iter().map(|p| (f(p) - mean).powi(2)).sum::<f64>() / (draws - 1) as f64).sqrt()
    };
    for i in 0..8 {
        for axis in 0..3 {
            let s = spread(&|p: &Parameters| p.frame[i][axis]);
            let r = reported
                .iter()
                .map(|c| c.sigma.as_ref().unwrap().frame.as_ref().unwrap()[i][axis])
                .sum::<f64>()
                / draws as f64;
            assert!(
                r / s < 2.0 && s / r < 2.0,
                "anchor {i} axis {axis}: reported {r}, spread {s}"
            );
        }
        let s = spread(&|p: &Parameters| p.offsets[i]);
        let r = reported
            .iter()
            .map(|c| c.sigma.as_ref().unwrap().offsets.as_ref().unwrap()[i])
            .sum::<f64>()
            / draws as f64;
        assert!(
            r / s < 2.0 && s / r < 2.0,
            "offset {i}: reported {r}, spread {s}"
        );
    }
}

/// The same check for self-calibration (unknown poses, gauge fixed): an 8-cable point robot
/// (the IPAnema-like frame, a point platform), anchors and offsets unknown (p = 32, g = 6),
/// 20 samples: N = 160 readings, P = 26 parameters + 60 pose coordinates. The mean of
/// residual_rms² over the draws is σ² (1 − P/N), and the reported σ of every coordinate not
/// held by the gauge matches the spread of the estimates (in the gauge's datum) within a
/// factor of 2.
#[test]
fn self_calibration_sigma_matches_the_spread_over_draws() {
    let mut rng = Rng(7);
    let nominal = Robot::new(
        MotionPattern::Point3,
        ipanema_like_8()
            .cables()
            .iter()
            .map(|c| Cable::point3(c.frame))
            .collect(),
    )
    .unwrap();
    let truth = as_built(&nominal, &mut rng);
    let offsets = offsets_of(8, &mut rng);
    let poses: Vec<Pose> = spatial_poses(20, &mut rng)
        .iter()
        .map(|p| Pose::point(p.position.x, p.position.y, p.position.z))
        .collect();
    let sigma = 1e-4;
    let unknowns = Unknowns::parse("frame,offsets").unwrap();
    let draws = 30;
    let (n_readings, p_unknowns) = (160.0, 26.0 + 60.0);
    let mut estimates: Vec<Parameters> = Vec::new();
    let mut reported: Vec<Calibration> = Vec::new();
    let mut mean_square = 0.0;
    for _ in 0..draws {
        let samples = Samples {
            readings: readings(&truth, &offsets, &[1.0; 8], &poses, sigma, &mut rng),
            poses: None,
        };
        let cal = calibrate(&nominal, &samples, unknowns, &Readings::Absolute).unwrap();
        assert!(
            cal.identifiable && cal.converged && cal.poses_estimated,
            "{cal:?}"
        );
        assert_eq!((cal.counting.parameters, cal.counting.gauge), (32, 6));
        mean_square += cal.residual_rms.powi(2) / draws as f64;
        estimates.push(cal.parameters.clone());
        reported.push(cal);
    }
    let expected_rms = sigma * (1.0f64 - p_unknowns / n_readings).sqrt();
    assert!(
        (mean_square.sqrt() / expected_rms - 1.0).abs() < 0.1,
        "rms {} vs σ √(1 − P/N) = {expected_rms}",
        mean_square.sqrt()
    );
    let spread = |f: &dyn Fn(&Parameters) -> f64| {
        let mean = estimates.iter().map(f).sum::<f64>() / draws as f64;
        (estimates.iter().map(|p| (f(p) - mean).powi(2)).sum::<f64>() / (draws - 1) as f64).sqrt()
    };
    let mut compared = 0;
    for i in 0..8 {
        for axis in 0..3 {
            let s = spread(&|p: &Parameters| p.frame[i][axis]);
            let r = reported
                .iter()
                .map(|c| c.sigma.as_ref().unwrap().frame.as_ref().unwrap()[i][axis])
                .sum::<f64>()
                / draws as f64;
            if r == 0.0 {
                // Held by the gauge: the estimate does not move either.
                assert!(s < 1e-12, "anchor {i} axis {axis} held but spread {s}");
                continue;
            }
            compared += 1;
            assert!(
                r / s < 2.0 && s / r < 2.0,
                "anchor {i} axis {axis}: reported {r}, spread {s}"
            );
        }
        let s = spread(&|p: &Parameters| p.offsets[i]);
        let r = reported
            .iter()
            .map(|c| c.sigma.as_ref().unwrap().offsets.as_ref().unwrap()[i])
            .sum::<f64>()
            / draws as f64;
        compared += 1;
        assert!(
            r / s < 2.0 && s / r < 2.0,
            "offset {i}: reported {r}, spread {s}"
        );
    }
    // 24 anchor coordinates less the 3 + 2 + 1 the datum holds (anchor 1; anchor 2 moves along
    // x, anchor 3 in z = 2 m: the box's edges are axis-aligned), plus the 8 offsets.
    assert_eq!(compared, 24 - 6 + 8);
}

/// Six cables on a six-DOF platform: k (n − d) = 0, never identifiable, whatever k.
#[test]
fn a_six_cable_spatial_robot_is_not_identifiable() {
    let nominal = ipanema_like_8();
    let six = Robot::new(MotionPattern::Spatial, nominal.cables()[..6].to_vec()).unwrap();
    let mut rng = Rng(4);
    let poses = spatial_poses(50, &mut rng);
    let samples = Samples {
        readings: readings(&six, &[0.0; 6], &[1.0; 6], &poses, 0.0, &mut rng),
        poses: None,
    };
    let cal = calibrate(
        &six,
        &samples,
        Unknowns::parse("frame").unwrap(),
        &Readings::Absolute,
    )
    .unwrap();
    assert!(!cal.identifiable);
    assert_eq!(cal.counting.samples_needed, None);
    assert!(
        cal.counting
            .reason
            .as_ref()
            .unwrap()
            .contains("as many cables")
    );
}

/// Too few samples: not identifiable, with the count needed: 8 cables, frame and offsets
/// (p = 32, g = 6): k ≥ 26 / 2 = 13.
#[test]
fn too_few_samples_say_how_many_are_needed() {
    let nominal = ipanema_like_8();
    let mut rng = Rng(5);
    let poses = spatial_poses(12, &mut rng);
    let samples = Samples {
        readings: readings(&nominal, &[0.0; 8], &[1.0; 8], &poses, 0.0, &mut rng),
        poses: None,
    };
    let cal = calibrate(
        &nominal,
        &samples,
        Unknowns::parse("frame,offsets").unwrap(),
        &Readings::Absolute,
    )
    .unwrap();
    assert!(!cal.identifiable);
    assert_eq!(cal.counting.samples_needed, Some(13));
}

/// The Hangprinter workflow: readings relative to the homed pose (the origin), anchors
/// unknown. Rotations about the origin are the only gauge (3); the anchors' distances to the
/// origin and to each other are recovered.
#[test]
fn relative_readings_self_calibrate_a_hangprinter() {
    let nominal = Robot::new(
        MotionPattern::Point3,
        [
            [0.0, -1.61098, -0.13153],
            [1.31422, 1.26814, -0.12128],
            [-1.41573, 0.70761, -0.12182],
            [0.0, 0.00001, 2.29983],
        ]
        .iter()
        .map(|a| Cable::point3(Vector3::from(*a)))
        .collect(),
    )
    .unwrap();
    let mut rng = Rng(6);
    let truth = as_built(&nominal, &mut rng);
    let home = Pose::point(0.0, 0.0, 0.0);
    let poses: Vec<Pose> = (0..30)
        .map(|_| {
            Pose::point(
                0.5 * rng.uniform(),
                0.5 * rng.uniform(),
                0.6 + 0.5 * rng.uniform(),
            )
        })
        .collect();
    let home_lengths: Vec<f64> = truth.inverse_kinematics(&home).unwrap().lengths().collect();
    let rho: Vec<f64> = poses
        .iter()
        .flat_map(|p| {
            truth
                .inverse_kinematics(p)
                .unwrap()
                .lengths()
                .zip(&home_lengths)
                .map(|(l, h)| l - h)
                .collect::<Vec<_>>()
        })
        .collect();
    let samples = Samples {
        readings: rho,
        poses: None,
    };
    let cal = calibrate(
        &nominal,
        &samples,
        Unknowns::parse("frame").unwrap(),
        &Readings::Relative { reference: home },
    )
    .unwrap();
    assert!(cal.identifiable && cal.converged, "{cal:?}");
    assert_eq!(cal.counting.gauge, 3);
    for (i, c) in truth.cables().iter().enumerate() {
        assert!((cal.parameters.frame[i].norm() - c.frame.norm()).abs() < 1e-9);
    }
    let true_frame: Vec<Vector3<f64>> = truth.cables().iter().map(|c| c.frame).collect();
    for (a, b) in distances(&cal.parameters.frame)
        .iter()
        .zip(distances(&true_frame))
    {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
}

/// Swivel pulleys (0.05 m, the IPAnema-like robot's): from known poses the pulley model
/// recovers the anchors (points on the swivel axes), attachments and offsets exactly, where the
/// straight model cannot fit the same readings. Self-calibration of a pulley robot is refused
/// with its reason.
#[test]
fn known_poses_calibrate_a_robot_with_pulleys() {
    let mut rng = Rng(8);
    let nominal = ipanema_like_8_pulleys();
    let moved = as_built(&nominal.without_pulleys(), &mut rng);
    // The as-built robot keeps its pulleys' radius and orientation.
    let truth = Robot::new(
        nominal.motion(),
        moved
            .cables()
            .iter()
            .zip(nominal.cables())
            .map(|(m, n)| Cable {
                pulley: n.pulley,
                ..*m
            })
            .collect(),
    )
    .unwrap();
    let offsets = offsets_of(8, &mut rng);
    let poses = spatial_poses(20, &mut rng);
    let samples = Samples {
        readings: readings(&truth, &offsets, &[1.0; 8], &poses, 0.0, &mut rng),
        poses: Some(poses),
    };
    let unknowns = Unknowns::parse("frame,platform,offsets").unwrap();
    let cal = calibrate(&nominal, &samples, unknowns, &Readings::Absolute).unwrap();
    assert!(cal.identifiable && cal.converged, "{cal:?}");
    assert!(cal.residual_rms < 1e-12, "{}", cal.residual_rms);
    for (i, c) in truth.cables().iter().enumerate() {
        assert!(
            (cal.parameters.frame[i] - c.frame).norm() < 1e-9,
            "anchor {i}"
        );
        assert!(
            (cal.parameters.platform[i] - c.platform).norm() < 1e-9,
            "attachment {i}"
        );
        assert!((cal.parameters.offsets[i] - offsets[i]).abs() < 1e-9);
    }
    // The straight model on the same readings: a millimetre-scale misfit.
    let straight = calibrate(
        &nominal.without_pulleys(),
        &samples,
        unknowns,
        &Readings::Absolute,
    )
    .unwrap();
    assert!(straight.residual_rms > 1e-4, "{}", straight.residual_rms);
    // Unknown poses: refused, saying why.
    let unknown_poses = Samples {
        poses: None,
        ..samples
    };
    let e = calibrate(
        &nominal,
        &unknown_poses,
        Unknowns::parse("frame").unwrap(),
        &Readings::Absolute,
    )
    .unwrap_err();
    assert!(matches!(e, CalibrationError::Pulleys));
    assert!(e.to_string().contains("known poses"), "{e}");
}

#[test]
fn bad_input_is_an_error() {
    let nominal = ipanema_like_8();
    let samples = Samples {
        readings: vec![1.0; 15],
        poses: None,
    };
    let u = Unknowns::parse("frame").unwrap();
    assert!(matches!(
        calibrate(&nominal, &samples, u, &Readings::Absolute),
        Err(CalibrationError::WrongCount { .. })
    ));
    let mut r = vec![1.0; 16];
    r[9] = f64::NAN;
    let e = calibrate(
        &nominal,
        &Samples {
            readings: r,
            poses: None,
        },
        u,
        &Readings::Absolute,
    )
    .unwrap_err();
    assert!(e.to_string().contains("sample 2"), "{e}");
    assert!(Unknowns::parse("").is_err());
    assert!(Unknowns::parse("frame,anchors").is_err());
    let point = Robot::new(
        MotionPattern::Point3,
        vec![Cable::point3(Vector3::new(1.0, 0.0, 1.0)); 4],
    );
    if let Ok(point) = point {
        assert!(matches!(
            calibrate(
                &point,
                &Samples {
                    readings: vec![1.0; 8],
                    poses: None
                },
                Unknowns::parse("platform").unwrap(),
                &Readings::Absolute
            ),
            Err(CalibrationError::NoPlatform(_))
        ));
    }
}

//! Inverse dynamics along timed trajectories of the IPAnema-1-like robot (8 cables), with an
//! offset centre of mass: the Newton–Euler identity at every sample, and the cable rates
//! against finite differences in time (straight cables and swivel pulleys).

use approx::assert_relative_eq;
use cdpr_dynamics::{
    RigidBody, TimeLaw, TimedSample, TimingSettings, Trajectory, inverse_dynamics,
};
use cdpr_kinematics::reference_robots::{ipanema_like_8, ipanema_like_8_pulleys};
use cdpr_kinematics::{MotionPattern, Pose, Robot};
use cdpr_tension::{Method, TensionBounds, TensionSolver};
use cdpr_wrench::{Platform, STANDARD_GRAVITY};
use nalgebra::{DVector, Matrix3, Vector3};

fn body() -> RigidBody {
    let p = Platform {
        mass: 5.0,
        centre_of_mass: Vector3::new(0.02, -0.01, -0.03),
        gravity: STANDARD_GRAVITY,
    };
    RigidBody::new(
        &p,
        Matrix3::new(0.05, 0.002, 0.0, 0.002, 0.04, -0.001, 0.0, -0.001, 0.03),
    )
    .unwrap()
}

fn trajectory(law: TimeLaw) -> Trajectory {
    let wp = [
        Pose::spatial(Vector3::new(-0.4, -0.3, 0.8), 0.0, 0.0, -0.05),
        Pose::spatial(Vector3::new(0.1, 0.2, 1.0), 0.05, -0.03, 0.0),
        Pose::spatial(Vector3::new(0.4, 0.3, 1.2), 0.05, 0.0, 0.05),
    ];
    let mut s = TimingSettings::with_duration(law, 2.0);
    if law == TimeLaw::Trapezoid {
        s.max_acceleration = Some(5.0);
    }
    Trajectory::new(MotionPattern::Spatial, &wp, &s).unwrap()
}

/// W t + w_g = M ẍ + b at every feasible sample, with M ẍ + b recomputed about the centre of
/// mass (f = m a_G, τ_P = I_G ω̇ + ω × I_G ω + c × f): residual at round-off.
#[test]
fn newton_euler_identity_at_every_sample() {
    let robot = ipanema_like_8();
    let b = body();
    for law in TimeLaw::ALL {
        let samples = trajectory(law).sample(0.01).unwrap();
        let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
        for method in [Method::L2, Method::Barycenter] {
            let mut solver = TensionSolver::new(method);
            let p = inverse_dynamics(
                &robot,
                Some(&b),
                &samples,
                &bounds,
                &mut solver,
                None,
                |_, s| {
                    let g = b.gravity_wrench6(s.pose.rotation.matrix());
                    DVector::from_column_slice(g.as_slice())
                },
            )
            .unwrap();
            assert_eq!(p.feasible_count(), samples.len(), "{law} {method:?}");
            for (k, s) in samples.iter().enumerate() {
                let r = s.pose.rotation.matrix();
                let c = r * b.centre_of_mass;
                let ig = r * b.inertia * r.transpose();
                let w = s.twist.fixed_rows::<3>(3);
                let (vd, wd) = (
                    s.twist_rate.fixed_rows::<3>(0),
                    s.twist_rate.fixed_rows::<3>(3),
                );
                let a_g = vd + wd.cross(&c) + w.cross(&w.cross(&c));
                let f = b.mass * a_g;
                let tau = ig * wd + w.cross(&(ig * w)) + c.cross(&f);
                let inertial = &p.inertial_wrench[k * 6..(k + 1) * 6];
                for i in 0..3 {
                    assert_relative_eq!(inertial[i], f[i], epsilon = 1e-12);
                    assert_relative_eq!(inertial[i + 3], tau[i], epsilon = 1e-12);
                }
                let kin = robot.inverse_kinematics(&s.pose).unwrap();
                let t = p.tensions[k].as_ref().unwrap();
                let g = b.gravity_wrench6(r);
                let lhs = kin.wrench_matrix() * t;
                for i in 0..6 {
                    let residual = lhs[i] + g[i] - inertial[i];
                    assert!(
                        residual.abs() < 1e-9 * 1000.0,
                        "{law} sample {k}: {residual}"
                    );
                }
                assert!(
                    t.iter()
                        .all(|&x| (10.0 - 1e-9..=1000.0 + 1e-9).contains(&x))
                );
            }
        }
    }
}

fn check_rates(robot: &Robot, law: TimeLaw) {
    let traj = trajectory(law);
    let b = body();
    let h = 1e-5;
    let ts: Vec<f64> = (1..40).map(|k| 0.05 * k as f64 + 0.0123).collect();
    let mut samples: Vec<TimedSample> = Vec::new();
    for &t in &ts {
        samples.extend([traj.at(t - h), traj.at(t), traj.at(t + h)]);
    }
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let mut solver = TensionSolver::new(Method::L2);
    let p = inverse_dynamics(
        robot,
        Some(&b),
        &samples,
        &bounds,
        &mut solver,
        None,
        |_, _| DVector::zeros(6),
    )
    .unwrap();
    let n = 8;
    for k in 0..ts.len() {
        let row = |q: &[f64], j: usize| q[(3 * k + j) * n..(3 * k + j + 1) * n].to_vec();
        let (l0, l2) = (row(&p.cable_lengths, 0), row(&p.cable_lengths, 2));
        let (s0, s1, s2) = (
            row(&p.cable_speeds, 0),
            row(&p.cable_speeds, 1),
            row(&p.cable_speeds, 2),
        );
        let a1 = row(&p.cable_accelerations, 1);
        for i in 0..n {
            assert_relative_eq!(s1[i], (l2[i] - l0[i]) / (2.0 * h), epsilon = 1e-7);
            assert_relative_eq!(a1[i], (s2[i] - s0[i]) / (2.0 * h), epsilon = 1e-5);
        }
    }
}

/// l̇ and l̈ are the time derivatives of l (central differences, h = 10⁻⁵ s), straight cables.
#[test]
fn cable_rates_are_time_derivatives() {
    for law in [TimeLaw::Quintic, TimeLaw::ParabolicBlend] {
        check_rates(&ipanema_like_8(), law);
    }
}

/// The same with swivel pulleys (l̈ by the directional difference of Wᵀ ẋ).
#[test]
fn cable_rates_with_pulleys() {
    check_rates(&ipanema_like_8_pulleys(), TimeLaw::Cubic);
}

/// The drive train against hand-derived values: a 2 kg point on two cables to (∓1, 1) lifted
/// straight up from (0, 0) by a trapezoid law. In the acceleration phase ÿ = a, both tensions
/// are t = m (g + a) l / (2 (1 − y)), and with u = 1 − y, l = √(1 + u²):
/// l̇ = −u ẏ / l, l̈ = ẏ² / l³ − u a / l, so ω_m = −(G/r) l̇ and τ = (r/G) t − J (G/r) l̈.
#[test]
fn drive_train_of_a_vertical_lift_matches_the_hand_derivation() {
    use cdpr_dynamics::{Winch, drive_train};
    use nalgebra::Vector2;
    let robot = Robot::new(
        MotionPattern::Point2,
        vec![
            cdpr_kinematics::Cable::point2(Vector2::new(-1.0, 1.0)),
            cdpr_kinematics::Cable::point2(Vector2::new(1.0, 1.0)),
        ],
    )
    .unwrap();
    let (m, g, a) = (2.0, 9.81, 2.0);
    let body = RigidBody::point_mass(&Platform {
        mass: m,
        gravity: Vector3::new(0.0, -g, 0.0),
        ..Platform::default()
    })
    .unwrap();
    let mut settings = TimingSettings::with_duration(TimeLaw::Trapezoid, 1.0);
    settings.max_acceleration = Some(a);
    let path = [Pose::point(0.0, 0.0, 0.0), Pose::point(0.0, 0.4, 0.0)];
    let traj = Trajectory::new(MotionPattern::Point2, &path, &settings).unwrap();
    let samples = traj.sample(0.01).unwrap();
    let bounds = TensionBounds::uniform(2, 0.0, 1000.0).unwrap();
    let mut solver = TensionSolver::new(Method::L2);
    let weight = DVector::from_vec(vec![0.0, -m * g]);
    let profile = inverse_dynamics(
        &robot,
        Some(&body),
        &samples,
        &bounds,
        &mut solver,
        None,
        |_, _| weight.clone(),
    )
    .unwrap();
    let (r, gear, j) = (0.04, 8.0, 3e-4);
    let winch = Winch::new(r, gear, j, None, None).unwrap();
    let d = drive_train(&[winch; 2], &profile).unwrap();
    let mut checked = 0;
    for (k, s) in samples.iter().enumerate() {
        let acc = s.twist_rate[1];
        if (acc - a).abs() > 1e-9 || s.t == 0.0 {
            continue; // only the constant-acceleration phase
        }
        let (y, vy) = (s.pose.position.y, s.twist[1]);
        let u = 1.0 - y;
        let l = (1.0 + u * u).sqrt();
        let t = m * (g + a) * l / (2.0 * u);
        let l_dot = -u * vy / l;
        let l_ddot = vy * vy / l.powi(3) - u * a / l;
        for i in 0..2 {
            assert_relative_eq!(d.motor_speeds[2 * k + i], -gear / r * l_dot, epsilon = 1e-9);
            let tau = r / gear * t - j * gear / r * l_ddot;
            assert_relative_eq!(d.motor_torques[2 * k + i], tau, epsilon = 1e-9);
            assert_relative_eq!(
                d.motor_powers[2 * k + i],
                tau * (-gear / r * l_dot),
                epsilon = 1e-8
            );
        }
        checked += 1;
    }
    assert!(
        checked >= 10,
        "only {checked} samples in the acceleration phase"
    );
    // Lifting: the motors wind in (ω > 0) and drive (P > 0) while accelerating.
    assert!(d.peak_power[0] > 0.0);
}

//! Statics with sagging cables (issue 29): the fixed point against straight cables as w → 0,
//! and its certificate checked independently with the catenary forces.

use cdpr_kinematics::nalgebra::{DVector, Vector3};
use cdpr_kinematics::reference_robots::{ipanema_like_8, ipanema_like_8_pulleys};
use cdpr_kinematics::{Pose, RobotCatenaries, SaggingCable};
use cdpr_tension::{
    Method, SaggingOutcome, SaggingSettings, SaggingStatics, TensionBounds, TensionProblem,
    TensionSolver,
};

const G: f64 = 9.81;

fn poses() -> Vec<Pose> {
    let mut out = Vec::new();
    for &(x, y, z, r) in &[
        (0.0, 0.0, 1.0, 0.0),
        (0.4, -0.3, 0.8, 0.05),
        (-0.6, 0.5, 1.3, -0.08),
        (0.9, 0.7, 0.6, 0.1),
    ] {
        out.push(Pose::spatial(Vector3::new(x, y, z), r, -r, 0.5 * r));
    }
    out
}

/// 5 kg platform under gravity along −z.
fn load() -> DVector<f64> {
    DVector::from_vec(vec![0.0, 0.0, -5.0 * G, 0.0, 0.0, 0.0])
}

fn straight(pose: &Pose, method: Method, bounds: &TensionBounds) -> Option<DVector<f64>> {
    let kin = ipanema_like_8().inverse_kinematics(pose).unwrap();
    let w = kin.wrench_matrix();
    let w_ext = load();
    let outcome = TensionSolver::new(method)
        .solve(&TensionProblem::new(&w, &w_ext, bounds))
        .unwrap();
    outcome.tensions().cloned()
}

fn sagging(
    pose: &Pose,
    method: Method,
    bounds: &TensionBounds,
    model: &RobotCatenaries,
) -> SaggingOutcome {
    let kin = ipanema_like_8().inverse_kinematics(pose).unwrap();
    SaggingStatics::new(SaggingSettings::default())
        .solve(
            &mut TensionSolver::new(method),
            &kin,
            model,
            &load(),
            bounds,
        )
        .unwrap()
}

#[test]
fn weightless_cables_give_the_straight_answers() {
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let elastic = RobotCatenaries::elastic(&[6e4; 8]).unwrap();
    let g = Vector3::new(0.0, 0.0, -G);
    let feather = RobotCatenaries::new(&[1e-9; 8], &[6e4; 8], &g).unwrap();
    let mut compared = 0;
    for pose in poses() {
        for method in [Method::L2, Method::L1, Method::Linf, Method::Pinv] {
            let reference = straight(&pose, method, &bounds);
            for (model, tol) in [(&elastic, 1e-9), (&feather, 1e-5)] {
                match (sagging(&pose, method, &bounds, model), &reference) {
                    (SaggingOutcome::Feasible(s), Some(t)) => {
                        let d = (&s.tensions - t).amax();
                        assert!(d <= tol * t.amax(), "{method:?}: {d}");
                        compared += 1;
                    }
                    (SaggingOutcome::Infeasible(_), None) => {}
                    (o, r) => panic!("{method:?}: sagging {o:?} vs straight {r:?}"),
                }
            }
        }
    }
    assert!(compared >= 24, "{compared}");
}

#[test]
fn elastic_unstrained_lengths_are_l_over_one_plus_t_over_ea() {
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let elastic = RobotCatenaries::elastic(&[6e4; 8]).unwrap();
    let pose = &poses()[1];
    let kin = ipanema_like_8().inverse_kinematics(pose).unwrap();
    let SaggingOutcome::Feasible(s) = sagging(pose, Method::L2, &bounds, &elastic) else {
        panic!("infeasible");
    };
    for ((c, l), t) in s.cables.iter().zip(kin.lengths()).zip(s.tensions.iter()) {
        assert!((c.unstrained_length - l / (1.0 + t / 6e4)).abs() < 1e-12 * l);
        assert_eq!(c.max_sag, 0.0);
    }
}

/// Elastic cables over pulleys (issue 29): a frictionless pulley keeps one tension along the
/// cable and the elastic stretch turns no force, so the statics are the straight pulley
/// model's (its W, columns along the free segments), for every method, and each L0 is
/// l/(1 + t/EA) with l = ρ β + l_f the whole length.
#[test]
fn elastic_cables_over_pulleys_give_the_straight_pulley_answers() {
    let robot = ipanema_like_8_pulleys();
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let ea = 6e4;
    let elastic = RobotCatenaries::elastic(&[ea; 8]).unwrap();
    let mut compared = 0;
    for pose in poses() {
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let w = kin.wrench_matrix();
        for method in [Method::L2, Method::L1, Method::Linf, Method::Pinv] {
            let reference = TensionSolver::new(method)
                .solve(&TensionProblem::new(&w, &load(), &bounds))
                .unwrap();
            let outcome = SaggingStatics::new(SaggingSettings::default())
                .solve(
                    &mut TensionSolver::new(method),
                    &kin,
                    &elastic,
                    &load(),
                    &bounds,
                )
                .unwrap();
            match (outcome, reference.tensions()) {
                (SaggingOutcome::Feasible(s), Some(t)) => {
                    let d = (&s.tensions - t).amax();
                    assert!(d <= 1e-9 * t.amax(), "{method:?}: {d}");
                    assert!((&s.wrench_matrix - &w).amax() < 1e-12);
                    for (i, (c, t)) in s.cables.iter().zip(s.tensions.iter()).enumerate() {
                        let l = kin.cables()[i].length;
                        assert!(
                            (c.unstrained_length - l / (1.0 + t / ea)).abs() < 1e-12 * l,
                            "cable {i}: {c:?}"
                        );
                        assert!(c.wrapped_length > 0.0 && c.chord_length < l);
                    }
                    compared += 1;
                }
                (SaggingOutcome::Infeasible(_), None) => {}
                (o, r) => panic!("{method:?}: elastic {o:?} vs straight {r:?}"),
            }
        }
    }
    assert!(compared >= 12, "{compared}");
}

#[test]
fn heavy_cables_are_certified_with_their_own_forces() {
    // 0.1 kg/m (a heavy rope on a 4 m frame): sag of millimetres to centimetres, tensions
    // visibly changed. (At 0.5 kg/m a lower cable at t_min = 10 N cannot hold itself up across
    // its span: the fixed point then names that cable.)
    let g = Vector3::new(0.0, 0.0, -G);
    let model = RobotCatenaries::new(&[0.1; 8], &[6e4; 8], &g).unwrap();
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let mut checked = 0;
    for pose in poses() {
        for method in [Method::L2, Method::L1, Method::Linf, Method::L2Max] {
            let s = match sagging(&pose, method, &bounds, &model) {
                SaggingOutcome::Feasible(s) => s,
                SaggingOutcome::Infeasible(r) => {
                    eprintln!("{method:?} at {pose:?}: {r}");
                    continue;
                }
            };
            let kin = ipanema_like_8().inverse_kinematics(&pose).unwrap();
            // Independent check: each cable's catenary re-solved from its tension, the forces
            // and moments summed by hand.
            let up = Vector3::z();
            let (mut force, mut moment) = (Vector3::zeros(), Vector3::zeros());
            for (i, c) in kin.cables().iter().enumerate() {
                let a = c.attachment_point + c.vector;
                let cable = SaggingCable::with_tension(
                    &model.cables()[i],
                    &a,
                    &c.attachment_point,
                    &up,
                    s.tensions[i],
                )
                .unwrap();
                let f = cable.unit * s.tensions[i];
                force += f;
                moment += c.attachment.cross(&f);
                // Both ends within the bounds; the frame end carries the cable's weight.
                assert!(cable.frame_end_tension <= 1000.0 + 1e-6);
                assert!(cable.lowest_tension >= 10.0 - 1e-6);
                assert!(cable.max_sag > 0.0);
            }
            let w = load();
            let r = (force + Vector3::new(w[0], w[1], w[2])).amax()
                + (moment + Vector3::new(w[3], w[4], w[5])).amax();
            assert!(r < 1e-8, "{method:?}: residual {r}");
            // Heavy cables need other tensions than straight ones.
            if let Some(t) = straight(&pose, method, &bounds) {
                assert!((&s.tensions - t).amax() > 1e-3);
            }
            assert!(s.iterations >= 2 && s.iterations < 100);
            checked += 1;
        }
    }
    assert!(checked >= 12, "{checked}");
    // The heavy rope: a lower cable at t_min = 10 N cannot hold itself up across its span;
    // its least tension becomes its floor and the answer is still certified.
    let heavy = RobotCatenaries::new(&[0.5; 8], &[6e4; 8], &g).unwrap();
    let pose = &poses()[0];
    let kin = ipanema_like_8().inverse_kinematics(pose).unwrap();
    match sagging(pose, Method::L2, &bounds, &heavy) {
        SaggingOutcome::Feasible(s) => {
            let c = &kin.cables()[4];
            let (a, b) = (c.attachment_point + c.vector, c.attachment_point);
            let (x, z, _) = cdpr_kinematics::catenary::plane_span(&a, &b, &Vector3::z());
            let least = heavy.cables()[4].least_tension(x, z).unwrap();
            assert!(least > 10.0, "{least}");
            assert!(s.tensions[4] >= least, "{} < {least}", s.tensions[4]);
        }
        o => panic!("{o:?}"),
    }
    // Heavier still (5 kg/m on a 1000 N cable): named, never a panic.
    let rope = RobotCatenaries::new(&[50.0; 8], &[6e4; 8], &g).unwrap();
    match sagging(pose, Method::L2, &bounds, &rope) {
        SaggingOutcome::Infeasible(r) => assert!(r.to_string().contains("cable"), "{r}"),
        o => panic!("{o:?}"),
    }
}

/// Timing (not criterion): `cargo test -p cdpr-tension --test it sagging_timing -- --ignored
/// --nocapture` prints µs per pose of the l2 fixed point, 8-cable spatial robot, 0.02 kg/m.
#[test]
#[ignore]
fn sagging_timing() {
    let g = Vector3::new(0.0, 0.0, -G);
    let model = RobotCatenaries::new(&[0.02; 8], &[6e4; 8], &g).unwrap();
    let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
    let kins: Vec<_> = poses()
        .iter()
        .map(|p| ipanema_like_8().inverse_kinematics(p).unwrap())
        .collect();
    let mut statics = SaggingStatics::default();
    let mut solver = TensionSolver::new(Method::L2);
    let (w, n) = (load(), 20_000);
    let start = std::time::Instant::now();
    let mut iterations = 0;
    for k in 0..n {
        if let SaggingOutcome::Feasible(s) = statics
            .solve(&mut solver, &kins[k % kins.len()], &model, &w, &bounds)
            .unwrap()
        {
            iterations += s.iterations;
        }
    }
    let us = start.elapsed().as_secs_f64() * 1e6 / n as f64;
    eprintln!(
        "sagging l2 statics: {us:.2} µs per pose, {:.1} iterations",
        iterations as f64 / n as f64
    );
}

mod fuzz {
    //! Newton robustness of the sagging statics over wide ranges (very light to very heavy
    //! cables, EA from soft to huge, loose and tight bounds, light and heavy platforms): never
    //! a panic or a NaN; an infeasible answer carries its reason.
    use super::*;
    use proptest::prelude::*;

    fn decades(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
        (lo..hi).prop_map(|e: f64| 10f64.powf(e))
    }

    fn config(cases: u32) -> ProptestConfig {
        let mut c = ProptestConfig::default();
        if std::env::var_os("PROPTEST_CASES").is_none() {
            c.cases = cases;
        }
        c
    }

    proptest! {
        #![proptest_config(config(100))]

        #[test]
        fn never_panics_or_returns_nan(
            rho in prop_oneof![1 => Just(0.0), 4 => decades(-6.0, 1.0)],
            ea in prop_oneof![1 => Just(f64::INFINITY), 4 => decades(1.0, 13.0)],
            (x, y, z) in (-1.2..1.2f64, -1.2..1.2f64, 0.2..1.8f64),
            (t_min, span) in (decades(-3.0, 2.0), decades(0.0, 4.0)),
            mass in decades(-2.0, 3.0),
            method in prop_oneof![Just(Method::L2), Just(Method::L1), Just(Method::Linf),
                                  Just(Method::Pinv)],
        ) {
            // A rigid weightless cable is the straight model (RobotCatenaries refuses nothing).
            let model = RobotCatenaries::new(&[rho; 8], &[ea; 8], &Vector3::new(0.0, 0.0, -G)).unwrap();
            let bounds = TensionBounds::uniform(8, t_min, t_min * (1.0 + span)).unwrap();
            let kin = ipanema_like_8()
                .inverse_kinematics(&Pose::spatial(Vector3::new(x, y, z), 0.0, 0.0, 0.0))
                .unwrap();
            let w_ext = DVector::from_vec(vec![0.0, 0.0, -mass * G, 0.0, 0.0, 0.0]);
            let outcome = SaggingStatics::new(SaggingSettings::default()).solve(
                &mut TensionSolver::new(method), &kin, &model, &w_ext, &bounds);
            match outcome {
                Ok(SaggingOutcome::Feasible(s)) => {
                    prop_assert!(s.tensions.iter().all(|t| t.is_finite()), "{:?}", s.tensions);
                    prop_assert!(s.residual.is_finite());
                    for c in &s.cables {
                        prop_assert!(c.unstrained_length.is_finite() && c.frame_end_tension.is_finite()
                            && c.max_sag.is_finite() && c.angle_to_chord.is_finite(), "{:?}", c);
                    }
                }
                Ok(SaggingOutcome::Infeasible(r)) => prop_assert!(!r.to_string().is_empty()),
                Err(e) => prop_assert!(!e.to_string().is_empty()),
            }
        }
    }
}

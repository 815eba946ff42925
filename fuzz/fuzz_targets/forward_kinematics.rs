//! Forward kinematics (`cdpr_kinematics::ForwardKinematics`) on random robots — straight or over
//! swivel pulleys with random radii and axes — random poses, and lengths that are either the
//! inverse kinematics of a pose (maybe perturbed) or arbitrary numbers (NaN, ±∞, huge, negative),
//! from a guess or by multi-start. Invariants: no panic, no hang, no NaN in an answer, and an
//! honest certificate: the reported residual is max |l_i(pose) − L_i| recomputed here, `Solved`
//! means residual ≤ tolerance, and "did not converge" is never reported as converged.
#![no_main]

use arbitrary::Unstructured;
use cdpr_fuzz::{Numbers, motion_for};
use cdpr_kinematics::{
    Cable, ForwardKinematics, ForwardSettings, ForwardSolution, ForwardStatus, Pose, Pulley, Robot,
};
use libfuzzer_sys::fuzz_target;
use nalgebra::Vector3;

fn check(robot: &Robot, lengths: &[f64], settings: &ForwardSettings, s: &ForwardSolution) {
    let p = s.pose.position;
    assert!(
        p.iter().all(|v| v.is_finite()) && s.pose.rotation.matrix().iter().all(|v| v.is_finite()),
        "non-finite pose {s:?}"
    );
    assert!(!s.residual.is_nan() && !s.min_singular_value.is_nan(), "NaN in {s:?}");
    assert!(s.min_singular_value >= 0.0);
    let kin = robot
        .inverse_kinematics(&s.pose)
        .unwrap_or_else(|e| panic!("returned pose is degenerate ({e}): {s:?}"));
    let residual = kin
        .lengths()
        .zip(lengths)
        .fold(0.0f64, |m, (l, t)| m.max((l - t).abs()));
    assert_eq!(residual.to_bits(), s.residual.to_bits(), "dishonest residual: {s:?}");
    match s.status {
        ForwardStatus::Solved => assert!(s.residual <= settings.tolerance && s.converged),
        ForwardStatus::NoPoseWithinTolerance => assert!(s.converged && s.residual > settings.tolerance),
        ForwardStatus::NotConverged => assert!(!s.converged && s.residual > settings.tolerance),
        _ => {}
    }
    assert!(s.iterations <= settings.max_iterations);
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok(head) = u.arbitrary::<[u8; 4]>() else {
        return;
    };
    let motion = motion_for([2, 3, 6][head[0] as usize % 3], head[0] & 8 != 0);
    let n = motion.dof() + (head[1] % 4) as usize;
    let pulleys = head[2] & 1 != 0;
    let mut num = Numbers::new(&mut u);
    let d = motion.space_dim();
    let mut cables = Vec::with_capacity(n);
    for _ in 0..n {
        let (mut frame, mut platform, mut axis) = (Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
        for k in 0..d {
            let Ok(v) = num.finite() else { return };
            frame[k] = v;
            if motion.has_orientation() {
                let Ok(v) = num.finite() else { return };
                platform[k] = v * 0.1;
            }
            let Ok(v) = num.finite() else { return };
            axis[k] = v;
        }
        let pulley = if pulleys {
            let Ok(r) = num.finite() else { return };
            Some(Pulley::from_axis(r.abs() * 0.01, axis))
        } else {
            None
        };
        cables.push(Cable { frame, platform, pulley });
    }
    let Ok(robot) = Robot::new(motion, cables) else {
        return;
    };
    let mut q = Vec::with_capacity(motion.dof());
    for _ in 0..motion.dof() {
        let Ok(v) = num.finite() else { return };
        q.push(v * 0.01);
    }
    let Ok(pose) = Pose::from_coordinates(motion, &q) else {
        return;
    };
    // Lengths: of the pose (perturbed by up to one value), or arbitrary.
    let lengths: Vec<f64> = if head[2] & 2 == 0 {
        let Ok(kin) = robot.inverse_kinematics(&pose) else {
            return;
        };
        let mut l: Vec<f64> = kin.lengths().collect();
        if head[2] & 4 != 0 {
            let Ok(e) = num.any() else { return };
            let i = head[3] as usize % n;
            l[i] += e;
        }
        l
    } else {
        let mut l = Vec::with_capacity(n);
        for _ in 0..n {
            let Ok(v) = num.any() else { return };
            l.push(v);
        }
        l
    };
    let settings = ForwardSettings {
        max_iterations: 1 + head[3] as usize % 60,
        ..ForwardSettings::default()
    };
    let Ok(mut fk) = ForwardKinematics::new(&robot, settings) else {
        return;
    };
    if head[2] & 8 == 0 {
        // From a guess near the pose.
        let mut g = q.clone();
        for v in &mut g {
            let Ok(e) = num.finite() else { return };
            *v += e * 1e-3;
        }
        let Ok(guess) = Pose::from_coordinates(motion, &g) else {
            return;
        };
        match fk.solve(&lengths, &guess) {
            Ok(s) => check(&robot, &lengths, &settings, &s),
            Err(e) => {
                // Only bad input (non-finite lengths) or a degenerate guess are errors.
                let _ = e.to_string();
                assert!(
                    lengths.iter().any(|l| !l.is_finite()) || robot.inverse_kinematics(&guess).is_err(),
                    "unexpected error {e}"
                );
            }
        }
    } else if let Ok(solutions) = fk.solve_multistart(&lengths) {
        for s in &solutions {
            check(&robot, &lengths, &settings, s);
        }
    }
});

//! Every `cdpr_tension::Method` on arbitrary W / w_ext / bounds (NaN, ±∞, zero and duplicate
//! columns, t_min > t_max, huge and tiny numbers). Invariants: no panic, no hang, and every
//! `Feasible` verdict passes the certificate re-checked here independently.
//!
//! SOTDA needs stiffness data: the target builds a robot with the same DOF and n from the bytes
//! and, depending on a flag, solves either the fuzzed W (stiffness of an unrelated robot: still a
//! valid input) or the robot's own W.
#![no_main]

use arbitrary::Unstructured;
use cdpr_fuzz::{Numbers, TensionCase, check_certificate, decode_robot, motion_for};
use cdpr_tension::{
    Method, SotdaSettings, SotdaVariant, StiffnessData, TensionBounds, TensionProblem,
    TensionSolver,
};
use libfuzzer_sys::fuzz_target;
use nalgebra::{DMatrix, DVector, Vector3};

fn run(
    method: Method,
    solver: &mut TensionSolver,
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    bounds: &TensionBounds,
    stiffness: Option<StiffnessData>,
) {
    let mut problem = TensionProblem::new(w, w_ext, bounds);
    problem.stiffness = stiffness;
    let outcome = solver.solve(&problem);
    // Errors (bad input) and infeasibility are fine; a feasible verdict must be certified.
    if let Ok(out) = &outcome
        && let Some(t) = out.tensions()
        && let Err(e) = check_certificate(
            w,
            w_ext,
            bounds.min().as_slice(),
            bounds.max().as_slice(),
            t.as_slice(),
        )
    {
        panic!(
            "{method}: feasible verdict fails the certificate: {e:?}\nW = {w:?}\nw_ext = {w_ext:?}\nbounds = {bounds:?}\nt = {t:?}"
        );
    }
    // The allocation-free entry points must agree with `solve`.
    let feasible = solver.is_feasible(&problem);
    match (&outcome, &feasible) {
        (Ok(o), Ok(f)) => assert_eq!(
            o.is_feasible(),
            *f,
            "{method}: solve and is_feasible disagree"
        ),
        (Err(_), Err(_)) => {}
        _ => panic!("{method}: solve and is_feasible disagree on errors"),
    }
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let Ok(case) = TensionCase::decode(&mut u, &[2, 3, 6]) else {
        return;
    };
    let n = case.w.ncols();
    // Invalid bounds (NaN, t_min > t_max, −∞) must be an error, never a panic.
    let Ok(bounds) = TensionBounds::new(case.t_min.clone(), case.t_max.clone()) else {
        assert!(
            case.t_min
                .iter()
                .zip(&case.t_max)
                .any(|(lo, hi)| !lo.is_finite()
                    || hi.is_nan()
                    || *hi == f64::NEG_INFINITY
                    || lo > hi),
            "valid bounds rejected: {:?} {:?}",
            case.t_min,
            case.t_max
        );
        return;
    };
    if std::env::var_os("CDPR_FUZZ_DEBUG").is_some() {
        // Replaying an artifact: show the decoded input.
        eprintln!(
            "W = {:?}\nw_ext = {:?}\nbounds = {bounds:?}",
            case.w, case.w_ext
        );
    }
    for method in Method::ALL {
        if method == Method::Sotda {
            continue;
        }
        let mut solver = TensionSolver::new(method);
        run(method, &mut solver, &case.w, &case.w_ext, &bounds, None);
    }

    // SOTDA: needs kinematics and axial stiffness of a robot with the same DOF and n.
    let alt: bool = u.arbitrary().unwrap_or(false);
    let motion = motion_for(case.dof, alt);
    let own_w: bool = u.arbitrary().unwrap_or(false);
    let variant: u8 = u.arbitrary().unwrap_or(0);
    let mut num = Numbers::new(&mut u);
    let Ok(Some((_robot, kin, robot_w))) = decode_robot(&mut num, motion, n) else {
        return;
    };
    let Ok(stiff) = (0..n)
        .map(|_| num.any())
        .collect::<arbitrary::Result<Vec<f64>>>()
    else {
        return;
    };
    let settings = SotdaSettings {
        direction: Vector3::new(
            num.any().unwrap_or(0.0),
            num.any().unwrap_or(1.0),
            num.any().unwrap_or(0.0),
        ),
        nu: match num.bytes().arbitrary::<u8>().unwrap_or(255) {
            b @ 0..=250 => f64::from(b) / 250.0,
            _ => num.any().unwrap_or(2.0),
        },
        variant: match variant % 3 {
            0 => SotdaVariant::Corners,
            1 => SotdaVariant::Vertices,
            _ => SotdaVariant::Full,
        },
        perturbation: None,
    };
    let data = StiffnessData {
        kinematics: &kin,
        axial_stiffness: &stiff,
    };
    let w = if own_w { &robot_w } else { &case.w };
    let mut solver = TensionSolver::sotda(settings);
    run(
        Method::Sotda,
        &mut solver,
        w,
        &case.w_ext,
        &bounds,
        Some(data),
    );
    // Without stiffness data SOTDA must return an error, not panic.
    let mut plain = TensionSolver::new(Method::Sotda);
    let _ = plain.solve(&TensionProblem::new(w, &case.w_ext, &bounds));
});

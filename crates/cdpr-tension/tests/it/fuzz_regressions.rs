//! Inputs found by the fuzz target `tension_methods` (fuzz/fuzz_targets/tension_methods.rs).
//! Each test's comment describes the wrong behaviour when the input was found; all are fixed.

use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver, certify};
use nalgebra::{DMatrix, DVector};

/// Fuzz finding (crash-a1fe827f…, session 2): tensions and wrench components of 1e300, one
/// t_max infinite (redundancy 3). In the Goldfarb–Idnani dual active set, a multiplier ratio
/// u/y overflowed to +∞, tied with the initial "no partial step" value +∞, and the
/// tie-break read the working set one past its end: index out of bounds (a panic). Every
/// method must answer (feasible and certified, infeasible, or an error) without panicking.
#[test]
fn overflowing_multiplier_ratio_does_not_panic() {
    let w = DMatrix::from_column_slice(
        3,
        6,
        &[
            -0.001, 23130.0, -0.166, -0.001, -0.001, -0.001, 13.926, -668.2, 0.001, -13.926, 668.2,
            -0.001, -0.166, -0.001, -0.166, -0.001, 668.2, -0.166,
        ],
    );
    let w_ext = DVector::from_vec(vec![1e300, 1e300, 0.020_56]);
    let mut max = vec![1e300; 6];
    max[2] = f64::INFINITY;
    let b = TensionBounds::new(vec![1e300; 6], max).unwrap();
    let problem = TensionProblem::new(&w, &w_ext, &b);
    for method in Method::ALL {
        if method == Method::Sotda {
            continue; // needs stiffness data
        }
        let mut solver = TensionSolver::new(method);
        if let Ok(out) = solver.solve(&problem)
            && let Some(t) = out.tensions()
        {
            assert!(
                certify(&w, &w_ext, &b, t.as_slice()).is_valid(),
                "{method}: uncertified {t:?}"
            );
        }
        let _ = solver.is_feasible(&problem);
    }
}

/// Fuzz finding (crash-9fb07f31…, session 2): w_ext has a component −1e300 and cable 2 has
/// t_max = ∞; closed-form answered `Feasible` with t₂ = ∞. W t + w_ext was infinite and so was
/// the certificate's scale (‖W‖∞ max|t_i|), and ∞ ≤ 10⁻⁹ · ∞ held. A certified answer now needs
/// a finite residual.
#[test]
fn infinite_tension_is_never_certified() {
    let w = DMatrix::from_column_slice(2, 3, &[-262.14, -262.14, 262.14, 0.026214, 315.28, -1e300]);
    let w_ext = DVector::from_vec(vec![-1e300, -2.1146]);
    let b = TensionBounds::new(
        vec![23.101, 1023.0, -0.001],
        vec![24.38, f64::INFINITY, 0.002],
    )
    .unwrap();
    let problem = TensionProblem::new(&w, &w_ext, &b);
    for method in Method::ALL {
        if method == Method::Sotda {
            continue; // needs stiffness data
        }
        let mut solver = TensionSolver::new(method);
        if let Ok(out) = solver.solve(&problem)
            && let Some(t) = out.tensions()
        {
            assert!(t.iter().all(|x| x.is_finite()), "{method}: {t:?}");
            assert!(
                certify(&w, &w_ext, &b, t.as_slice()).is_valid(),
                "{method}: {t:?}"
            );
        }
    }
    // The certificate itself.
    let c = certify(&w, &w_ext, &b, &[24.0, f64::INFINITY, 0.0]);
    assert!(!c.is_valid(), "{c:?}");
}

/// Every listed method must answer `Feasible` with certified tensions.
fn assert_all_feasible(
    w: &DMatrix<f64>,
    w_ext: &DVector<f64>,
    b: &TensionBounds,
    methods: &[Method],
) {
    let problem = TensionProblem::new(w, w_ext, b);
    for &method in methods {
        let out = TensionSolver::new(method).solve(&problem).unwrap();
        let t = out
            .tensions()
            .unwrap_or_else(|| panic!("{method}: {:?}", out.infeasibility()));
        assert!(
            certify(w, w_ext, b, t.as_slice()).is_valid(),
            "{method}: {t:?}"
        );
    }
}

/// Soak finding (issue 13, 77 of 50 000 such problems): n = DOF = 3 with a fixed cable
/// (t_min = t_max). l1, l1-max, l2, l2-max and linf answered "no feasible tension" although
/// exact, pinv and the improved closed form return t ≈ (0.7198, 1052.61, 2530.76): the
/// feasible-set test compared t0 = −W⁻¹ w_ext, rounded by 1.9·10⁻¹², against the fixed bound
/// with a tolerance of 10⁻¹².
#[test]
fn fixed_cable_at_redundancy_0_is_feasible() {
    let w = DMatrix::from_row_slice(
        3,
        3,
        &[
            -0.1147310923714546,
            -0.9766749182937946,
            0.3750336553503939,
            -0.9933965856812941,
            0.21472331959014035,
            -0.9270111959164906,
            0.019391463830488304,
            -0.1097767960315261,
            0.07621880030232725,
        ],
    );
    let w_ext = DVector::from_vec(vec![
        79.0148024974934,
        2120.742416207248,
        -77.35403314682765,
    ]);
    let b = TensionBounds::new(
        vec![0.7197532984792598, 14.02290868156111, 14.449224393172953],
        vec![0.7197532984792598, 2131.0771731459895, 3692.095276179377],
    )
    .unwrap();
    use Method::*;
    assert_all_feasible(
        &w,
        &w_ext,
        &b,
        &[Exact, Pinv, L1, L1Max, L2, L2Max, Linf, ImprovedClosedForm],
    );
    let t = TensionSolver::new(L1)
        .solve(&TensionProblem::new(&w, &w_ext, &b))
        .unwrap();
    let t = t.tensions().unwrap();
    assert!(
        (t[1] - 1052.606).abs() < 1e-2 && (t[2] - 2530.764).abs() < 1e-2,
        "{t:?}"
    );
}

/// Soak finding (issue 13, 78 cases): redundancy 2, planar, 5 cables, cable 1 fixed and cable 4
/// with t_max = ∞. Every polygon method answered "no feasible tension" although
/// t ≈ (12.78, 386.72, 625.60, 1373.72, 625.60) is feasible: the fixed cable's strip (width 0)
/// was clipped one side at a time from the 2.5·10⁹-wide artificial box, whose vertices carry
/// an error of ~10⁻⁶, and the second side cut everything away.
#[test]
fn fixed_cable_next_to_an_infinite_bound_is_feasible() {
    let w = DMatrix::from_row_slice(
        3,
        5,
        &[
            -0.8270493700908047,
            0.13224942003699167,
            -0.2316945924941441,
            0.7692782475693918,
            -0.9995882874887525,
            -0.562129290672887,
            -0.9912164702525272,
            -0.9727885771373822,
            -0.6389139048546099,
            0.028692429581738118,
            -0.25661990835441784,
            -0.18435041087660617,
            0.23307358227659508,
            0.2403051580981772,
            0.016445720304226436,
        ],
    );
    let w_ext = DVector::from_vec(vec![
        -327.0597899389119,
        1858.818236392134,
        -411.63881162625313,
    ]);
    let b = TensionBounds::new(
        vec![12.778596303228078; 5],
        vec![
            12.778596303228078,
            709.9690597811764,
            709.9690597811764,
            f64::INFINITY,
            709.9690597811764,
        ],
    )
    .unwrap();
    use Method::*;
    // Sotda needs stiffness data; it shares the polygon with barycenter.
    assert_all_feasible(&w, &w_ext, &b, &[L1, L2, Linf, Barycenter]);
    // With t_max,4 = ∞ the maximisers are unbounded (t4 grows along the fixed-cable line),
    // which is an answer, not "no feasible tension".
    let problem = TensionProblem::new(&w, &w_ext, &b);
    for m in [L1Max, L2Max] {
        let out = TensionSolver::new(m).solve(&problem).unwrap();
        assert!(
            out.is_feasible()
                || matches!(
                    out.infeasibility(),
                    Some(cdpr_tension::Infeasibility::Unbounded { .. })
                ),
            "{m}: {out:?}"
        );
    }
}

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

//! Bad input is an error, degenerate input never panics.

use cdpr_tension::{
    Method, TensionBounds, TensionError, TensionOutcome, TensionProblem, TensionSolver,
};
use nalgebra::{DMatrix, DVector};

/// The methods that apply to `p` (inapplicable ones are usage errors, tested below), except
/// sotda, which needs stiffness data.
fn methods(p: &TensionProblem) -> Vec<Method> {
    Method::applicable(p.redundancy())
        .into_iter()
        .filter(|m| *m != Method::Sotda)
        .collect()
}

fn all(p: &TensionProblem) -> Vec<Result<TensionOutcome, TensionError>> {
    methods(p)
        .iter()
        .map(|&m| TensionSolver::new(m).solve(p))
        .collect()
}

#[test]
fn nan_and_shapes_are_errors() {
    let b = TensionBounds::uniform(3, 0.0, 10.0).unwrap();
    let mut w = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, -1.0, 0.0, 1.0, -1.0]);
    let we = DVector::from_vec(vec![0.0, -1.0]);
    w[(1, 1)] = f64::NAN;
    for r in all(&TensionProblem::new(&w, &we, &b)) {
        assert!(matches!(r, Err(TensionError::NotFinite { .. })));
    }
    w[(1, 1)] = 1.0;
    let bad = DVector::from_vec(vec![f64::INFINITY, 0.0]);
    for r in all(&TensionProblem::new(&w, &bad, &b)) {
        assert!(matches!(r, Err(TensionError::NotFinite { .. })));
    }
    let short = DVector::from_vec(vec![0.0]);
    for r in all(&TensionProblem::new(&w, &short, &b)) {
        assert!(matches!(r, Err(TensionError::DimensionMismatch { .. })));
    }
    let b4 = TensionBounds::uniform(4, 0.0, 10.0).unwrap();
    for r in all(&TensionProblem::new(&w, &we, &b4)) {
        assert!(matches!(r, Err(TensionError::DimensionMismatch { .. })));
    }
    assert!(matches!(
        TensionBounds::new(vec![2.0], vec![1.0]),
        Err(TensionError::InvertedBounds { .. })
    ));
    // SOTDA without stiffness data (at redundancy 2, where it applies).
    let w4 = DMatrix::from_row_slice(2, 4, &[1.0, 0.0, -1.0, 1.0, 0.0, 1.0, -1.0, 1.0]);
    let b4 = TensionBounds::uniform(4, 0.0, 10.0).unwrap();
    assert_eq!(
        TensionSolver::new(Method::Sotda).solve(&TensionProblem::new(&w4, &we, &b4)),
        Err(TensionError::MissingStiffness)
    );
}

#[test]
fn zero_and_duplicate_columns_do_not_panic() {
    // Zero column: cable 3 does nothing. Duplicate columns 0 and 1.
    let w = DMatrix::from_row_slice(2, 5, &[1.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    let we = DVector::from_vec(vec![0.5, -1.0]);
    for lo in [0.0, 0.5, 3.0] {
        let b = TensionBounds::uniform(5, lo, 10.0).unwrap();
        let p = TensionProblem::new(&w, &we, &b);
        for (m, r) in methods(&p).iter().zip(all(&p)) {
            let r = r.unwrap();
            if let Some(t) = r.tensions() {
                assert!((&w * t + &we).amax() < 1e-9, "{m}");
            }
        }
    }
    // All-zero W: singular, never a panic.
    let z = DMatrix::zeros(3, 5);
    let we = DVector::from_vec(vec![0.0, -1.0, 0.0]);
    let b = TensionBounds::uniform(5, 0.0, 10.0).unwrap();
    for r in all(&TensionProblem::new(&z, &we, &b)) {
        assert!(!r.unwrap().is_feasible());
    }
    // Equal bounds t_min = t_max: a single point may be feasible.
    let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, -1.0]);
    let we = DVector::from_vec(vec![-1.0]);
    let b = TensionBounds::uniform(3, 1.0, 1.0).unwrap();
    let p = TensionProblem::new(&w, &we, &b);
    for (m, r) in methods(&p).iter().zip(all(&p)) {
        let r = r.unwrap();
        if ![
            Method::Exact,
            Method::Pinv,
            Method::ClosedForm,
            Method::Barycenter,
            // No interior point: the barrier method's documented give-up.
            Method::PNorm,
        ]
        .contains(m)
        {
            assert!(r.is_feasible(), "{m}: {r:?}");
        }
    }
    // Infinite t_max: minimisation works, maximisation is unbounded.
    let b = TensionBounds::new(vec![1.0; 3], vec![f64::INFINITY; 3]).unwrap();
    let p = TensionProblem::new(&w, &we, &b);
    let l1 = TensionSolver::new(Method::L1).solve(&p).unwrap();
    assert!((l1.tensions().unwrap().sum() - 3.0).abs() < 1e-9);
    assert!(
        !TensionSolver::new(Method::L1Max)
            .solve(&p)
            .unwrap()
            .is_feasible()
    );
}

/// Issue 13 §1: a method that does not apply is a usage error of the call carrying the method,
/// the redundancy it needs, the problem's n − DOF and the methods that apply (it used to be an
/// `Infeasible(NotApplicable)` outcome, which a workspace grid counted as an empty workspace).
#[test]
fn inapplicable_methods_are_errors() {
    // 1 DOF, redundancy 0..=3.
    for n in 1..=4usize {
        let w = DMatrix::from_fn(1, n, |_, i| if i % 2 == 0 { 1.0 } else { -1.0 });
        let we = DVector::from_vec(vec![-0.5]);
        let b = TensionBounds::uniform(n, 1.0, 10.0).unwrap();
        let p = TensionProblem::new(&w, &we, &b);
        let r = n as isize - 1;
        for method in Method::ALL {
            let out = TensionSolver::new(method).solve(&p);
            if method.applies_to(r) {
                if method != Method::Sotda {
                    assert!(out.is_ok(), "{method} at r = {r}: {out:?}");
                }
                continue;
            }
            match out {
                Err(TensionError::MethodNotApplicable {
                    method: m,
                    redundancy,
                    ref applicable,
                    ..
                }) => {
                    assert_eq!((m, redundancy), (method, r));
                    assert_eq!(applicable, &Method::applicable(r));
                    assert!(!applicable.contains(&method));
                }
                other => panic!("{method} at r = {r}: {other:?}"),
            }
            assert!(TensionSolver::new(method).is_feasible(&p).is_err());
        }
    }
    // The improved closed form starts from (t_min + t_max)/2: t_max = ∞ is a usage error.
    let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, -1.0]);
    let we = DVector::from_vec(vec![-2.0]);
    let b = TensionBounds::new(vec![1.0; 3], vec![10.0, f64::INFINITY, 10.0]).unwrap();
    let err = TensionSolver::new(Method::ImprovedClosedForm)
        .solve(&TensionProblem::new(&w, &we, &b))
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "method improved-closed-form needs a finite t_max for every cable; cable 2 has t_max = ∞"
    );
}

//! Bad input is an error, degenerate input never panics.

use cdpr_tension::{
    Method, TensionBounds, TensionError, TensionOutcome, TensionProblem, TensionSolver,
};
use nalgebra::{DMatrix, DVector};

fn all(p: &TensionProblem) -> Vec<Result<TensionOutcome, TensionError>> {
    Method::ALL
        .iter()
        .filter(|m| **m != Method::Sotda)
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
    // SOTDA without stiffness data.
    assert_eq!(
        TensionSolver::new(Method::Sotda).solve(&TensionProblem::new(&w, &we, &b)),
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
        for (m, r) in Method::ALL
            .iter()
            .filter(|m| **m != Method::Sotda)
            .zip(all(&p))
        {
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
    for (m, r) in Method::ALL
        .iter()
        .filter(|m| **m != Method::Sotda)
        .zip(all(&TensionProblem::new(&w, &we, &b)))
    {
        let r = r.unwrap();
        if ![
            Method::Exact,
            Method::Pinv,
            Method::ClosedForm,
            Method::Barycenter,
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

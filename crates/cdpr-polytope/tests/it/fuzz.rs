//! Robustness: the public entry points never panic on arbitrary wrench matrices (NaN, ±∞,
//! subnormal and huge entries, zero and duplicate columns) or bounds, and every `Ok` index is a
//! number (finite or ±∞, never NaN). The cargo-fuzz target calls the same functions.

use cdpr_kinematics::MotionPattern;
use cdpr_polytope::{
    CapacityMargin, CapacityMarginEvaluator, PolytopeError, RequiredWrenchSet, capacity_margin,
    hyperplane_shifting, isotropic_force, isotropic_force_of, isotropic_wrench_radius,
    isotropic_wrench_radius_of, krut_vertex_projection, largest_inscribed_ellipse, limiting_facet,
};
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

/// Any f64, weighted towards the troublesome ones.
fn nasty() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -1.0f64..1.0,
        1 => any::<f64>(),
        1 => prop::sample::select(vec![
            0.0, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::MAX, -f64::MAX,
            f64::MIN_POSITIVE, 5e-324, -5e-324, 1e300, -1e300, 1e-300, 1.0, -1.0,
        ]),
    ]
}

/// A W of 1..=7 rows and 0..=9 columns: either scaled regular entries (scale 1, 1e±300 or
/// subnormal) or [`nasty`] ones; sometimes with a zeroed or duplicated column.
fn arb_w() -> impl Strategy<Value = DMatrix<f64>> {
    (1usize..=7, 0usize..=9)
        .prop_flat_map(|(m, n)| {
            let entries = prop_oneof![
                2 => (
                    prop::collection::vec(-1.0f64..1.0, m * n),
                    prop::sample::select(vec![1.0, 1e-300, 1e300, 1e-320, 1e-150, 1e150]),
                )
                    .prop_map(|(v, s)| v.into_iter().map(|x| x * s).collect::<Vec<_>>()),
                1 => prop::collection::vec(nasty(), m * n),
            ];
            (
                entries,
                Just((m, n)),
                0usize..3,
                any::<prop::sample::Index>(),
            )
        })
        .prop_map(|(v, (m, n), edit, i)| {
            let mut w = DMatrix::from_vec(m, n, v);
            if n >= 2 {
                let j = i.index(n - 1) + 1;
                match edit {
                    1 => w.column_mut(j).fill(0.0),
                    2 => {
                        let c = w.column(0).into_owned();
                        w.column_mut(j).copy_from(&c);
                    }
                    _ => {}
                }
            }
            w
        })
}

/// Valid bounds (finite t_min ≤ t_max, t_max possibly +∞) of length n, or of a wrong length.
fn arb_bounds(n: usize) -> impl Strategy<Value = TensionBounds> {
    let value = prop_oneof![0.0f64..100.0, -100.0f64..0.0, Just(1e300), Just(0.0)];
    (
        prop::collection::vec(
            (value.clone(), 0.0f64..1000.0, prop::bool::weighted(0.1)),
            n,
        ),
        prop::bool::weighted(0.05),
    )
        .prop_map(|(v, wrong_len)| {
            let mut lo: Vec<f64> = v.iter().map(|x| x.0).collect();
            let mut hi: Vec<f64> = v
                .iter()
                .map(|x| if x.2 { f64::INFINITY } else { x.0 + x.1 })
                .collect();
            if wrong_len {
                lo.push(1.0);
                hi.push(2.0);
            }
            TensionBounds::new(lo, hi).expect("valid by construction")
        })
}

fn not_nan(what: &str, x: f64) -> Result<(), TestCaseError> {
    prop_assert!(!x.is_nan(), "{} is NaN", what);
    Ok(())
}

fn motion_for(dof: usize) -> MotionPattern {
    match dof {
        2 => MotionPattern::Point2,
        3 => MotionPattern::Point3,
        6 => MotionPattern::Spatial,
        _ => MotionPattern::Planar, // a mismatch for other sizes: must be an error
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn no_panic_and_no_nan(
        (w, b) in arb_w().prop_flat_map(|w| { let n = w.ncols(); (Just(w), arb_bounds(n)) }),
        centre in prop::collection::vec(nasty(), 7),
        half in prop::collection::vec(0.0f64..50.0, 7),
        ball in prop::bool::ANY,
    ) {
        let dof = w.nrows();
        let motion = motion_for(dof);
        let required = if ball {
            RequiredWrenchSet::ball(DVector::from_column_slice(&centre[..dof]), half[0])
        } else {
            RequiredWrenchSet::boxed(
                DVector::from_column_slice(&centre[..dof]),
                DVector::from_column_slice(&half[..dof]),
            )
        };
        if let Ok(x) = isotropic_force_of(motion, &w, &b) { not_nan("isotropic_force_of", x)?; }
        if let Ok(x) = isotropic_wrench_radius_of(&w, &b) { not_nan("wrench radius", x)?; }
        let aws = hyperplane_shifting::available_wrench_set(&w, &b);
        if let Ok(aws) = &aws {
            for f in aws.facets() {
                prop_assert!(f.offset.is_finite() && f.normal.iter().all(|x| x.is_finite()));
            }
            if let Ok(x) = isotropic_force(aws, motion) { not_nan("isotropic_force", x)?; }
            not_nan("isotropic_wrench_radius", isotropic_wrench_radius(aws))?;
            if dof == 2 {
                let _ = largest_inscribed_ellipse(aws);
            }
        }
        if w.ncols() <= 4 && dof <= 3
            && let Ok(k) = krut_vertex_projection::available_wrench_set(&w, &b) {
                prop_assert!(k.facets().iter().all(|f| f.offset.is_finite()));
            }
        if let Ok(r) = &required {
            if let Ok(aws) = &aws {
                if let Ok(m) = capacity_margin(aws, r) { not_nan("capacity_margin", m)?; }
                let _ = limiting_facet(aws, r);
            }
            if let Ok(m) = CapacityMargin::new(dof, w.ncols()).margin(&w, &b, r) {
                not_nan("CapacityMargin", m)?;
            }
            if let Ok(ev) = CapacityMarginEvaluator::new(&b, r)
                && let Ok(m) = ev.margin(&w) { not_nan("CapacityMarginEvaluator", m)?; }
        }
        // Whenever W has a non-finite entry, every entry point says so.
        if w.iter().any(|x| !x.is_finite()) && b.len() == w.ncols() && dof <= 6 {
            let is_not_finite = |e: &PolytopeError| matches!(e, PolytopeError::NotFinite { .. });
            prop_assert!(aws.as_ref().err().is_some_and(is_not_finite));
            prop_assert!(isotropic_wrench_radius_of(&w, &b).err().is_some_and(|e| is_not_finite(&e)));
        }
    }
}

#[test]
fn inverted_or_nan_bounds_cannot_be_built() {
    // t_min > t_max, NaN and infinite t_min are rejected by TensionBounds itself, so no
    // polytope function can ever see them.
    assert!(TensionBounds::new(vec![5.0], vec![1.0]).is_err());
    assert!(TensionBounds::new(vec![f64::NAN], vec![1.0]).is_err());
    assert!(TensionBounds::new(vec![f64::NEG_INFINITY], vec![1.0]).is_err());
    assert!(TensionBounds::new(vec![0.0], vec![f64::NAN]).is_err());
}

#[test]
fn overflowing_offsets_are_an_error_not_infinity() {
    // Facet offsets Σ |c·w_j| t_max overflow: reported, never a silent +∞.
    let w = DMatrix::from_row_slice(2, 4, &[1e300, -1e300, 0.0, 0.0, 0.0, 0.0, 1e300, -1e300]);
    let b = TensionBounds::uniform(4, 0.0, 1e10).unwrap();
    let r = isotropic_wrench_radius_of(&w, &b);
    assert!(matches!(r, Err(PolytopeError::Overflow { .. })), "{r:?}");
    // Subnormal and huge but representable: a proper answer.
    let tiny = DMatrix::from_row_slice(
        2,
        4,
        &[5e-324, -5e-324, 0.0, 0.0, 0.0, 0.0, 5e-324, -5e-324],
    );
    let r =
        isotropic_wrench_radius_of(&tiny, &TensionBounds::uniform(4, 0.0, 1.0).unwrap()).unwrap();
    assert!(r.is_finite() && r >= 0.0);
    let huge = DMatrix::from_row_slice(2, 4, &[1e300, -1e300, 0.0, 0.0, 0.0, 0.0, 1e300, -1e300]);
    let r =
        isotropic_wrench_radius_of(&huge, &TensionBounds::uniform(4, 1.0, 2.0).unwrap()).unwrap();
    assert!((r / 1e300 - 1.0).abs() < 1e-12, "{r}"); // square [−1e300, 1e300]²
}

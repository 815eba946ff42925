//! # Minimum-norm approach
//!
//! For n = DOF the unique solution t = −W⁻¹ w_ext (thesis eq. (6.12)); for n > DOF the
//! minimum-norm solution t^mn = −W⁺ w_ext = −Wᵀ(W Wᵀ)⁻¹ w_ext (eq. (6.14), Fattah & Agrawal),
//! i.e. t^nul = 0 in eq. (6.13). The bounds are only checked: the thesis' Fig. 6.3 shows how much
//! workspace this loses compared with the constrained ℓ₂ approach (see
//! `tests/it/minimum_norm_vs_l2.rs`). Both are computed from the pivoted QR of Wᵀ (see the
//! null-space docs), which also detects singular poses.
//!
//! **Small fast path.** For n = DOF ≤ 3 (the thesis' 3-cable planar robot, point robots) eq.
//! (6.12) is solved with the explicit inverse W⁻¹ = adj(W)/det W (for DOF 3 the rows of W⁻¹ are
//! the cross products of the columns of W divided by det W = c₁·(c₂ × c₃)). The singularity rule
//! is the QR path's: the Hadamard ratio ρ = √det(W Wᵀ)/Π‖row_k(W)‖ = |det W|/Π‖row_k(W)‖ must be
//! at least 10⁻¹⁰. If the answer fails the certificate's equilibrium test (possible only for
//! ill-conditioned W) the solver repeats the QR path, so the fast path never turns a certified
//! answer into a failure.
//!
//! ## References
//! - Thesis eqs. (6.12)–(6.14). Fattah & Agrawal (2005).

use crate::certificate::bound_violation;
use crate::null_space::{NullSpace, SINGULARITY_RATIO};
use crate::{Infeasibility, TensionBounds, TensionProblem};
use nalgebra::DVector;

/// Eq. (6.12) (r = 0) or eq. (6.14) (r > 0) into `t`; checks the bounds.
pub(crate) fn minimum_norm(
    ns: &mut NullSpace,
    problem: &TensionProblem,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    ns.compute(problem.wrench_matrix, problem.external_wrench)
        .map_err(|condition| Infeasibility::SingularPose { condition })?;
    t.copy_from_slice(&ns.t0);
    check_bounds(problem.bounds, t)
}

/// Eq. (6.12) for n = DOF = M ≤ 3 by the explicit inverse (see the module docs) into `t`;
/// checks the singularity rule and the bounds.
#[inline]
pub(crate) fn exact_small<const M: usize>(
    problem: &TensionProblem,
    t: &mut [f64],
) -> Result<(), Infeasibility> {
    let ws = problem.wrench_matrix.as_slice();
    let we = problem.external_wrench.as_slice();
    debug_assert!(ws.len() == M * M && we.len() == M && t.len() == M);
    let col = |i: usize| -> [f64; 3] {
        let mut c = [0.0; 3];
        c[..M].copy_from_slice(&ws[i * M..i * M + M]);
        c
    };
    let c0 = col(0);
    let c1 = if M >= 2 { col(1) } else { [0.0; 3] };
    let c2 = if M >= 3 { col(2) } else { [0.0; 3] };
    // Π ‖row_k‖² (rows of W = k-th entries of the columns).
    let mut rows2 = 1.0;
    for k in 0..M {
        let r = c0[k] * c0[k] + c1[k] * c1[k] + c2[k] * c2[k];
        if r == 0.0 {
            return Err(Infeasibility::SingularPose {
                condition: f64::INFINITY,
            });
        }
        rows2 *= r;
    }
    // Rows of adj(W) (W⁻¹ = adj / det).
    let (a0, a1, a2): ([f64; 3], [f64; 3], [f64; 3]) = match M {
        1 => ([1.0, 0.0, 0.0], [0.0; 3], [0.0; 3]),
        2 => ([c1[1], -c1[0], 0.0], [-c0[1], c0[0], 0.0], [0.0; 3]),
        _ => (cross(&c1, &c2), cross(&c2, &c0), cross(&c0, &c1)),
    };
    let det = a0[0] * c0[0] + a0[1] * c0[1] + a0[2] * c0[2];
    let ratio = (det.abs() / rows2.sqrt()).min(1.0);
    if det == 0.0 || ratio.is_nan() || ratio < SINGULARITY_RATIO {
        return Err(Infeasibility::SingularPose {
            condition: if det == 0.0 {
                f64::INFINITY
            } else {
                1.0 / ratio
            },
        });
    }
    let inv = -1.0 / det;
    let mut w = [0.0; 3];
    w[..M].copy_from_slice(we);
    let dot = |a: &[f64; 3]| a[0] * w[0] + a[1] * w[1] + a[2] * w[2];
    t[0] = dot(&a0) * inv;
    if M >= 2 {
        t[1] = dot(&a1) * inv;
    }
    if M >= 3 {
        t[2] = dot(&a2) * inv;
    }
    check_bounds(problem.bounds, t)
}

#[inline(always)]
fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `BoundsViolated` for the cable with the largest relative violation, if any exceeds the
/// certificate tolerance.
#[inline]
pub(crate) fn check_bounds(bounds: &TensionBounds, t: &[f64]) -> Result<(), Infeasibility> {
    let inside = t
        .iter()
        .zip(bounds.min().iter().zip(bounds.max().iter()))
        .fold(true, |ok, (&ti, (&lo, &hi))| ok & (ti >= lo) & (ti <= hi));
    if inside {
        return Ok(());
    }
    check_bounds_slow(bounds, t)
}

#[cold]
fn check_bounds_slow(bounds: &TensionBounds, t: &[f64]) -> Result<(), Infeasibility> {
    let mut worst = (0, f64::NEG_INFINITY);
    for (i, &ti) in t.iter().enumerate() {
        let v = bound_violation(bounds.min()[i], bounds.max()[i], ti);
        if v > worst.1 {
            worst = (i, v);
        }
    }
    if worst.1 > crate::certificate::BOUND_TOLERANCE {
        let (i, ti) = (worst.0, t[worst.0]);
        return Err(Infeasibility::BoundsViolated {
            cable: i,
            tension: ti,
            bound: if ti < bounds.min()[i] {
                bounds.min()[i]
            } else {
                bounds.max()[i]
            },
            tensions: DVector::from_vec(Vec::new()),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Method, TensionSolver};
    use nalgebra::{DMatrix, DVector};

    /// The fixed-size inverse agrees with the QR path (verdict, singularity rule, tensions) on
    /// random square problems of size 1–3, including nearly singular ones.
    #[test]
    fn small_exact_agrees_with_qr() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let (mut feasible, mut singular) = (0, 0);
        for case in 0..3000 {
            let m = 1 + case % 3;
            let mut w = DMatrix::from_fn(m, m, |_, _| rnd());
            if case % 5 == 0 && m > 1 {
                // Nearly dependent columns: Hadamard ratio around 10⁻¹⁰ (both sides of it).
                let eps = 10f64.powf(-8.0 - 4.0 * rnd().abs());
                let c0 = w.column(0).into_owned();
                for k in 0..m {
                    w[(k, 1)] = c0[k] + eps * rnd();
                }
            }
            let we = DVector::from_fn(m, |_, _| 3.0 * rnd());
            let b = TensionBounds::uniform(m, -5.0, 5.0).unwrap();
            let p = TensionProblem::new(&w, &we, &b);
            let mut t_fast = vec![0.0; m];
            let fast = match m {
                1 => exact_small::<1>(&p, &mut t_fast),
                2 => exact_small::<2>(&p, &mut t_fast),
                _ => exact_small::<3>(&p, &mut t_fast),
            };
            let mut t_qr = vec![0.0; m];
            let mut ns = NullSpace::default();
            let qr = minimum_norm(&mut ns, &p, &mut t_qr);
            match (&fast, &qr) {
                (Ok(()), Ok(())) => {
                    feasible += 1;
                    let s = t_qr.iter().fold(1.0f64, |a, v| a.max(v.abs()));
                    let cond = 1.0 / ns.ratio;
                    for (a, b) in t_fast.iter().zip(&t_qr) {
                        assert!((a - b).abs() <= 1e-13 * cond * s, "case {case}: {a} vs {b}");
                    }
                }
                (
                    Err(Infeasibility::SingularPose { condition: a }),
                    Err(Infeasibility::SingularPose { condition: b }),
                ) => {
                    singular += 1;
                    assert!(
                        (a / b - 1.0).abs() < 1e-14 * a.max(1.0) || a == b,
                        "case {case}: {a} vs {b}"
                    );
                }
                (
                    Err(Infeasibility::BoundsViolated { cable: a, .. }),
                    Err(Infeasibility::BoundsViolated { cable: b, .. }),
                ) => {
                    assert_eq!(a, b, "case {case}");
                }
                _ => panic!("case {case}: {fast:?} vs {qr:?}"),
            }
            // Through the solver (fast path with QR fallback): certified whenever QR is.
            let out = TensionSolver::new(Method::Exact).solve(&p).unwrap();
            if qr.is_ok() {
                assert!(out.is_feasible(), "case {case}: {out:?}");
            }
        }
        assert!(feasible > 500 && singular > 50, "{feasible} {singular}");
    }
}

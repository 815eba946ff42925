//! # Dykstra's alternating projections (Hassan & Khajepour 2007)
//!
//! The feasible set is the intersection of the affine equilibrium set A = {t : W t + w_ext = 0}
//! and the box B = [t_min, t_max]. Both projections are explicit:
//!
//! ```text
//!   P_A(x) = x − W⁺ (W x + w_ext) = t₀ + N Nᵀ (x − t₀),     P_B(x)_i = clamp(x_i, t_min,i, t_max,i)
//! ```
//!
//! **Dykstra's algorithm** (Boyle & Dykstra 1986) from t_m = (t_min + t_max)/2 converges to
//! the projection of t_m onto A ∩ B — the `l2-mid` tensions. Because A is affine its correction
//! term vanishes (it lies in range(Wᵀ), which P_A removes), so only the box keeps one:
//!
//! ```text
//!   x₀ = P_A(t_m),  p₀ = 0;    y_k = P_B(x_k + p_k),  p_{k+1} = x_k + p_k − y_k,  x_{k+1} = P_A(y_k)
//! ```
//!
//! `--alternating` drops the correction (p ≡ 0): von Neumann's alternating projections, as
//! WireLib's `getDistributionDykstra` and cdpyr do; they converge to *a* point of A ∩ B, not
//! to the projection.
//!
//! **Stopping.** As WireLib, the box of the projections is shrunk by δ_i = 10⁻⁶ (t_max,i −
//! t_min,i) (10⁻³ N on [1, 1000] N), so that when A ∩ B has some interior the iterates x_k ∈ A
//! enter the true box (within 10⁻¹⁰ relative) after finitely many steps; the first such x_k is
//! the answer (it passes the certificate).
//!
//! **Slow iterates, and the line through two of them.** In the coordinates x = t₀ + N λ
//! (N orthonormal), once the set I of clamped cables stops changing, one projection pair is
//! affine — the clamped cables of y_k sit on their (shrunk) bounds whatever x_k, with or
//! without Dykstra's correction — and its error obeys
//!
//! ```text
//!   λ_{k+1} − λ* = (I − N_Iᵀ N_I) (λ_k − λ*),      eigenvalues 1 − σ_j², σ_j the singular values of N_I
//! ```
//!
//! (N_I: the rows of N of the clamped cables). The rows of an orthonormal N have
//! Σ_i ‖N_i‖² = r, so a cable whose tension barely moves on A (small ‖N_i‖), or two clamped
//! cables with nearly parallel rows (a thin corner of the feasible polygon), give a rate
//! 1 − σ² close to 1: on issue 26's fixture 10 feasible poses needed more than the 5 000
//! pairs to come within δ of the limit. The error then shrinks along the eigenvector of the
//! largest eigenvalue, so the line through x_k and x_{k+1} points at the limit (the reason for
//! extrapolating alternating projections along it, Gearhart & Koshy 1989; Bauschke, Deutsch,
//! Hundal & Park 2003). After each pair whose x_{k+1} is outside the box, the steps s ≥ 0 with
//! x_{k+1} + s (x_{k+1} − x_k) in the shrunk box form one interval (a 1-D bound per cable);
//! when it is not empty, z = P_A(x_{k+1} + s_lo (x_{k+1} − x_k)) (on A already; projecting again
//! removes the rounding a long step magnifies) is the answer if it is in the box. The
//! iterates are still Dykstra's (von Neumann's with `--alternating`) unchanged; only the
//! answer may be this point of A ∩ B on the line of the last two iterates instead of an
//! iterate. Neither is the limit — the projection of t_m onto A ∩ B is `l2-mid`, computed
//! exactly. On the fixture this finds all 15 793 LP-feasible poses within the cap (10 give-ups
//! before), in 14 pairs per pose on average instead of 57.
//!
//! **Infeasibility.** Each iterate outside the box also tries a proof of infeasibility: with
//! v = x_k − P_B(x_k) projected onto range(Wᵀ) (v ⟂ N), vᵀt = vᵀx_k for every t ∈ A, while over
//! the box vᵀt ranges over [Σ min(v_i t_min,i, v_i t_max,i), Σ max(…)]; when vᵀx_k lies outside
//! that range by more than 10⁻⁹ Σ|v_i| max(1, |t_min,i|, |t_max,i|), A ∩ B is empty
//! ([`Infeasibility::NoFeasibleTension`]; when the sets are disjoint x_k − y_k tends to the
//! gap vector, which separates them). After the iteration cap (`max_iterations`, default
//! 5 000, WireLib's) without either the method gives up ([`crate::GiveUp::IterationLimit`]).
//!
//! ## References
//! - Boyle, J. P. & Dykstra, R. L. (1986), *A method for finding projections onto the
//!   intersection of convex sets in Hilbert spaces*, Lecture Notes in Statistics 37, pp. 28–47.
//! - Hassan, M. & Khajepour, A. (2007), *Minimum-norm solution for the actuator forces in
//!   cable-based parallel manipulators based on convex optimization*, ICRA 2007, pp. 1498–1503.
//! - Bauschke, H. H. & Borwein, J. M. (1994), *Dykstra's alternating projection algorithm for
//!   two sets*, J. Approx. Theory 79, pp. 418–443 (the gap vector of disjoint sets).
//! - Gearhart, W. B. & Koshy, M. (1989), *Acceleration schemes for the method of alternating
//!   projections*, J. Comput. Appl. Math. 26, pp. 235–249.
//! - Bauschke, H. H., Deutsch, F., Hundal, H. & Park, S.-H. (2003), *Accelerating the
//!   convergence of the method of alternating projections*, Trans. Amer. Math. Soc. 355,
//!   pp. 3433–3461.

use crate::certificate::SET_TOLERANCE;
use crate::null_space::NullSpace;
use crate::pott_closed_form::middle;
use crate::{GiveUp, Infeasibility, TensionBounds};

/// Relative shrinking of the box of the projections.
const SHRINK: f64 = 1e-6;

/// Buffers (no allocation once sized).
#[derive(Debug, Clone, Default)]
pub(crate) struct Dykstra {
    y: Vec<f64>,
    p: Vec<f64>,
    v: Vec<f64>,
    /// The previous iterate x_{k−1}.
    prev: Vec<f64>,
    lambda: Vec<f64>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    /// Iterations of the last solve (tests, soak).
    pub iterations: usize,
}

/// Whether t is in the box within [`SET_TOLERANCE`] (relative to max(1, |bound|)): the
/// certificate, with its 10 times wider tolerance, snaps it onto the bounds.
#[inline]
fn in_box(t: &[f64], lo: &[f64], hi: &[f64]) -> bool {
    t.iter().zip(lo.iter().zip(hi)).all(|(&ti, (&l, &h))| {
        ti >= l - SET_TOLERANCE * l.abs().max(1.0) && ti <= h + SET_TOLERANCE * h.abs().max(1.0)
    })
}

impl Dykstra {
    /// Runs the projections into `t` (module docs); `alternating`: no correction term.
    /// `converge`: go on after entering the box until the iterates move less than 10⁻¹²
    /// relative (tests of the limit).
    pub fn solve(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        alternating: bool,
        max_iterations: usize,
        converge: bool,
        t: &mut [f64],
    ) -> Result<(), Infeasibility> {
        let (n, r) = (ns.n, ns.r());
        let (lo, hi) = (bounds.min(), bounds.max());
        self.y.resize(n, 0.0);
        self.p.clear();
        self.p.resize(n, 0.0);
        self.v.resize(n, 0.0);
        self.prev.resize(n, 0.0);
        self.lambda.resize(r, 0.0);
        self.lo.resize(n, 0.0);
        self.hi.resize(n, 0.0);
        for i in 0..n {
            let delta = SHRINK * (hi[i] - lo[i]);
            self.lo[i] = lo[i] + delta;
            self.hi[i] = hi[i] - delta;
        }
        // x₀ = P_A(t_m).
        middle(bounds, &mut self.y);
        ns.coordinates(&self.y, &mut self.lambda);
        ns.tensions(&self.lambda, t);
        self.iterations = 0;
        let mut inside_since = false;
        loop {
            let inside = in_box(t, lo.as_slice(), hi.as_slice());
            if inside && !converge {
                return Ok(());
            }
            if !inside {
                if self.proves_empty(ns, bounds, t) {
                    return Err(Infeasibility::NoFeasibleTension);
                }
                // The line of the last two iterates (x_{k−1} in `self.prev`).
                if !converge && self.iterations > 0 && self.ray_enters_box(ns, bounds, t) {
                    return Ok(());
                }
            }
            if self.iterations == max_iterations {
                break;
            }
            self.iterations += 1;
            // y = P_B(x + p), p ← x + p − y, x ← P_A(y).
            for (i, &x) in t.iter().enumerate() {
                let z = x + self.p[i];
                let y = z.max(self.lo[i]).min(self.hi[i]);
                self.y[i] = y;
                if !alternating {
                    self.p[i] = z - y;
                }
            }
            ns.coordinates(&self.y, &mut self.lambda);
            self.prev.copy_from_slice(t);
            ns.tensions(&self.lambda, t);
            if converge {
                let moved = t
                    .iter()
                    .zip(&self.prev)
                    .fold(0f64, |m, (a, b)| m.max((a - b).abs() / a.abs().max(1.0)));
                if inside && inside_since && moved < 1e-12 {
                    return Ok(());
                }
            }
            inside_since = inside;
        }
        Err(Infeasibility::GaveUp {
            method: "dykstra",
            reason: GiveUp::IterationLimit {
                iterations: max_iterations,
            },
        })
    }

    /// The stopping test on the line of the last two iterates (module docs): with
    /// d = x_{k+1} − x_k (x_k in `self.prev`, x_{k+1} in `t`), the steps s ≥ 0 for which
    /// x_{k+1} + s d lies in the shrunk box form one interval [s_lo, s_hi] (one 1-D bound per
    /// cable). When it is not empty, z = P_A(x_{k+1} + s_lo d) (A contains the line; the
    /// projection removes the rounding a long step magnifies) is the answer if it lies in the
    /// box: `t` becomes z. `self.y`, `self.lambda` and `self.v` are scratch here.
    fn ray_enters_box(&mut self, ns: &NullSpace, bounds: &TensionBounds, t: &mut [f64]) -> bool {
        let (mut s_lo, mut s_hi) = (0f64, f64::INFINITY);
        for (i, &x) in t.iter().enumerate() {
            let d = x - self.prev[i];
            let (a, b) = (self.lo[i] - x, self.hi[i] - x);
            if d > 0.0 {
                s_lo = s_lo.max(a / d);
                s_hi = s_hi.min(b / d);
            } else if d < 0.0 {
                s_lo = s_lo.max(b / d);
                s_hi = s_hi.min(a / d);
            } else if a > 0.0 || b < 0.0 {
                return false;
            }
            if s_lo > s_hi {
                return false;
            }
        }
        if !s_lo.is_finite() {
            return false;
        }
        for (i, &x) in t.iter().enumerate() {
            self.y[i] = x + s_lo * (x - self.prev[i]);
        }
        ns.coordinates(&self.y, &mut self.lambda);
        ns.tensions(&self.lambda, &mut self.v);
        if !in_box(&self.v, bounds.min().as_slice(), bounds.max().as_slice()) {
            return false;
        }
        t.copy_from_slice(&self.v);
        true
    }

    /// The separation test of the module docs at x = `t` ∈ A.
    fn proves_empty(&mut self, ns: &NullSpace, bounds: &TensionBounds, t: &[f64]) -> bool {
        let (n, r) = (ns.n, ns.r());
        let (lo, hi) = (bounds.min(), bounds.max());
        for i in 0..n {
            self.v[i] = t[i] - t[i].max(lo[i]).min(hi[i]);
        }
        // v ← v − N Nᵀ v.
        for j in 0..r {
            let col = &ns.basis[j * n..(j + 1) * n];
            let c: f64 = col.iter().zip(&self.v).map(|(a, b)| a * b).sum();
            for (vi, a) in self.v.iter_mut().zip(col) {
                *vi -= c * a;
            }
        }
        let (mut at, mut low, mut high, mut size) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..n {
            let v = self.v[i];
            at += v * t[i];
            let (a, b) = (v * lo[i], v * hi[i]);
            low += a.min(b);
            high += a.max(b);
            size += v.abs() * lo[i].abs().max(hi[i].abs()).max(1.0).max(t[i].abs());
        }
        let margin = 1e-9 * size;
        size > 0.0
            && high.is_finite()
            && low.is_finite()
            && (at > high + margin || at < low - margin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::active_set::ActiveSet;
    use crate::l2_mid::L2Mid;
    use nalgebra::{DMatrix, DVector};

    /// Σ t = 20 and t1 − t2 + 2 t3 − 2 t4 = 8 with t ∈ [3, 10]: the closed form
    /// (4.8, 3.2, 5.6, 2.4, 4) breaks t4 ≥ 3, so l2-mid lies on a bound. Dykstra's iterates
    /// converge to it (within the 10⁻⁶-relative shrinking of the box); the alternating
    /// projections stop at a feasible point too.
    #[test]
    fn dykstra_converges_to_l2_mid() {
        let w =
            DMatrix::from_row_slice(2, 5, &[1.0, 1.0, 1.0, 1.0, 1.0, 1.0, -1.0, 2.0, -2.0, 0.0]);
        let we = DVector::from_vec(vec![-20.0, -8.0]);
        let b = TensionBounds::uniform(5, 3.0, 10.0).unwrap();
        let mut ns = NullSpace::default();
        ns.compute(&w, &we).unwrap();
        let (mut t, mut mid) = ([0.0; 5], [0.0; 5]);
        L2Mid::default()
            .solve(&ns, &b, &mut ActiveSet::default(), &mut mid)
            .unwrap();
        assert!((mid[3] - 3.0).abs() < 1e-9, "{mid:?}");
        let mut d = Dykstra::default();
        d.solve(&ns, &b, false, 100_000, true, &mut t).unwrap();
        for (a, e) in t.iter().zip(&mid) {
            assert!((a - e).abs() < 1e-4, "{t:?} vs {mid:?}");
        }
        d.solve(&ns, &b, true, 5_000, false, &mut t).unwrap();
        assert!(t.iter().all(|&x| (3.0..=10.0).contains(&x)), "{t:?}");
        let r = &w * DVector::from_column_slice(&t) + &we;
        assert!(r.amax() < 1e-12, "{r}");
    }

    /// A cable whose tension barely moves on A: W = [[1, −1, 0], [0.01, 0.01, −2]], the
    /// equilibrium line t = (300, 300, −3) + μ n, n = (1, 1, 0.01)/√2.0001, bounds [0, 1000]:
    /// feasible for μ ∈ [424.3, 990.0] (t₃ ≥ 0 and t₁ ≤ 1000). From P_A(t_m) (μ = 286.4,
    /// t₃ = −0.97 N) each projection pair removes only n₃² = 5·10⁻⁵ of t₃'s violation, so the
    /// iterates alone need about ln(0.97 / 10⁻³) / 5·10⁻⁵ ≈ 1.4·10⁵ pairs (both variants gave
    /// up at the 5 000 cap before). The line of the first two iterates is A itself: its entry
    /// into the shrunk box, t₃ = δ = 10⁻³ N, which is also Dykstra's limit, is found after one
    /// pair.
    #[test]
    fn a_slow_cable_is_found_on_the_line_of_the_iterates() {
        let w = DMatrix::from_row_slice(2, 3, &[1.0, -1.0, 0.0, 0.01, 0.01, -2.0]);
        let we = DVector::from_vec(vec![0.0, -12.0]);
        let b = TensionBounds::uniform(3, 0.0, 1000.0).unwrap();
        let mut ns = NullSpace::default();
        ns.compute(&w, &we).unwrap();
        for alternating in [false, true] {
            let mut d = Dykstra::default();
            let mut t = [0.0; 3];
            d.solve(&ns, &b, alternating, 5_000, false, &mut t).unwrap();
            assert!(d.iterations <= 2, "{alternating}: {} pairs", d.iterations);
            assert!((t[2] - 1e-3).abs() < 1e-9, "{t:?}");
            assert!((t[0] - t[1]).abs() < 1e-9 && t[0] < 1000.0, "{t:?}");
            let r = &w * DVector::from_column_slice(&t) + &we;
            assert!(r.amax() < 1e-12, "{r}");
        }
    }
}

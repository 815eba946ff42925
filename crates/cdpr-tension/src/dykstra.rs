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
//! the answer (it passes the certificate). Each iterate outside the box also tries a proof of infeasibility: with
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
        while self.iterations < max_iterations {
            let inside = in_box(t, lo.as_slice(), hi.as_slice());
            if inside && !converge {
                return Ok(());
            }
            if !inside && self.proves_empty(ns, bounds, t) {
                return Err(Infeasibility::NoFeasibleTension);
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
            self.v.copy_from_slice(t);
            ns.tensions(&self.lambda, t);
            let moved = t
                .iter()
                .zip(&self.v)
                .fold(0f64, |m, (a, b)| m.max((a - b).abs() / a.abs().max(1.0)));
            if converge && inside && inside_since && moved < 1e-12 {
                return Ok(());
            }
            inside_since = inside;
        }
        if in_box(t, lo.as_slice(), hi.as_slice()) {
            return Ok(());
        }
        Err(Infeasibility::GaveUp {
            method: "dykstra",
            reason: GiveUp::IterationLimit {
                iterations: max_iterations,
            },
        })
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
}

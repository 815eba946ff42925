//! # Vertex centroid of the feasible polytope (Mikelsons et al. 2008)
//!
//! The mean of the vertices of the feasible polytope {t = t0 + N λ : t_min ≤ t ≤ t_max}, for
//! any redundancy r (WireLib's `weightedSum`; the *area* centroid of the polygon at r = 2 is
//! `barycenter`, a different point unless the polygon is regular). A convex combination of
//! feasible vertices, so feasible whenever the set is non-empty.
//!
//! Every vertex makes r bound constraints active with independent null-space rows: for each
//! set S of r cables (C(n, r) sets) whose rows N_S are independent (LU with partial pivoting,
//! smallest pivot above 10⁻¹⁰; the rows of N have norm ≤ 1), and each of the 2^r choices of a
//! bound per cable, N_S λ = b_S − t0_S gives a candidate; it is a vertex when every cable is
//! within its bounds (relative tolerance 10⁻¹⁰; for a cable whose null-space row is zero, whose
//! tension is t0_i on the whole equilibrium set, e.g. every cable at r = 0, the certificate's
//! 10⁻⁹, since t0 = −W⁺ w_ext carries its own rounding, as in the l2 active set). Degenerate vertices (more than r active
//! bounds) are found from several bases and kept once (entries equal within 10⁻⁹ relative), as
//! WireLib drops its doublets. The answer is their mean. For a bounded set (finite t_max) a
//! non-empty feasible set has at least one vertex; when none is found the solver confirms the
//! verdict with the l2 dense active set before reporting it. More than 2²⁰ candidate bases is
//! a documented give-up ([`crate::GiveUp::TooManyBases`]).
//!
//! ## References
//! - Mikelsons, L., Bruckmann, T., Hiller, M. & Schramm, D. (2008), *A real-time capable force
//!   calculation algorithm for redundant tendon-based parallel manipulators*, ICRA 2008,
//!   pp. 3869–3874.
//! - WireLib (Pott, Fraunhofer IPA), `CForceDistribution::getDistributionAllVertices` and
//!   `getDistributionWeightedSum`.

use crate::active_set::ZERO_ROW;
use crate::certificate::{BOUND_TOLERANCE, SET_TOLERANCE};
use crate::null_space::NullSpace;
use crate::{GiveUp, Infeasibility, TensionBounds};

/// Candidate bases above which the enumeration gives up.
pub(crate) const MAX_BASES: u128 = 1 << 20;
/// Smallest LU pivot of an independent N_S.
const PIVOT: f64 = 1e-10;
/// Relative distance under which two vertices are one.
const SAME: f64 = 1e-9;

/// Buffers (no allocation once sized, apart from the vertex list's growth).
#[derive(Debug, Clone, Default)]
pub(crate) struct VertexCentroid {
    cables: Vec<usize>,
    lu: Vec<f64>,
    piv: Vec<usize>,
    lambda: Vec<f64>,
    cand: Vec<f64>,
    /// Lowest and highest accepted tension of each cable.
    below: Vec<f64>,
    above: Vec<f64>,
    vertices: Vec<f64>,
    /// Distinct vertices found by the last solve.
    pub count: usize,
}

/// C(n, r)·2^r, saturating.
pub(crate) fn candidate_bases(n: usize, r: usize) -> u128 {
    let mut c: u128 = 1;
    for k in 0..r as u128 {
        c = c.saturating_mul(n as u128 - k) / (k + 1);
    }
    c.saturating_mul(1u128 << r.min(100))
}

impl VertexCentroid {
    /// The vertex centroid into `t`; `Err(NoFeasibleTension)` when no vertex was found
    /// (callers confirm it).
    pub fn solve(
        &mut self,
        ns: &NullSpace,
        bounds: &TensionBounds,
        t: &mut [f64],
    ) -> Result<(), Infeasibility> {
        let (n, r) = (ns.n, ns.r());
        let bases = candidate_bases(n, r);
        if bases > MAX_BASES {
            return Err(Infeasibility::GaveUp {
                method: "vertex-centroid",
                reason: GiveUp::TooManyBases { bases },
            });
        }
        let (lo, hi) = (bounds.min(), bounds.max());
        self.cables.clear();
        self.cables.extend(0..r);
        self.lu.resize(r * r, 0.0);
        self.piv.resize(r, 0);
        self.lambda.resize(r, 0.0);
        self.cand.resize(n, 0.0);
        self.below.clear();
        self.above.clear();
        for i in 0..n {
            // A cable with a zero null-space row is at t0_i on every candidate: judged with
            // the certificate's tolerance (soak problem 203901: r = 0, a fixed cable 4.9·10⁻¹⁰
            // N off its bound of 3.29 N was "no vertex").
            let row2: f64 = (0..r).map(|j| ns.basis[j * n + i].powi(2)).sum();
            let tol = if row2 <= ZERO_ROW * ZERO_ROW {
                BOUND_TOLERANCE
            } else {
                SET_TOLERANCE
            };
            self.below.push(lo[i] - tol * lo[i].abs().max(1.0));
            self.above.push(hi[i] + tol * hi[i].abs().max(1.0));
        }
        self.vertices.clear();
        self.count = 0;
        loop {
            if self.factor(ns) {
                for pattern in 0..1usize << r {
                    for (k, &i) in self.cables.iter().enumerate() {
                        let b = if pattern >> k & 1 == 1 { hi[i] } else { lo[i] };
                        self.lambda[k] = b - ns.t0[i];
                    }
                    self.lu_solve(r);
                    ns.tensions(&self.lambda, &mut self.cand);
                    let feasible = (0..n).all(|i| {
                        let c = self.cand[i];
                        c >= self.below[i] && c <= self.above[i]
                    });
                    if feasible && !self.known(n) {
                        self.vertices.extend_from_slice(&self.cand);
                        self.count += 1;
                    }
                }
            }
            if !next_combination(&mut self.cables, n) {
                break;
            }
        }
        if self.count == 0 {
            return Err(Infeasibility::NoFeasibleTension);
        }
        t.fill(0.0);
        for v in self.vertices.chunks_exact(n) {
            for (ti, vi) in t.iter_mut().zip(v) {
                *ti += vi;
            }
        }
        let k = self.count as f64;
        for ti in t.iter_mut() {
            *ti /= k;
        }
        Ok(())
    }

    /// Whether the candidate equals a kept vertex.
    fn known(&self, n: usize) -> bool {
        self.vertices.chunks_exact(n).any(|v| {
            v.iter()
                .zip(&self.cand)
                .all(|(a, b)| (a - b).abs() <= SAME * a.abs().max(1.0))
        })
    }

    /// LU with partial pivoting of N_S (rows N_i, i ∈ S); false when dependent.
    fn factor(&mut self, ns: &NullSpace) -> bool {
        let (n, r) = (ns.n, ns.r());
        for (k, &i) in self.cables.iter().enumerate() {
            for j in 0..r {
                self.lu[k * r + j] = ns.basis[j * n + i];
            }
        }
        for col in 0..r {
            let mut p = col;
            for row in col + 1..r {
                if self.lu[row * r + col].abs() > self.lu[p * r + col].abs() {
                    p = row;
                }
            }
            if self.lu[p * r + col].abs() < PIVOT {
                return false;
            }
            self.piv[col] = p;
            if p != col {
                for j in 0..r {
                    self.lu.swap(p * r + j, col * r + j);
                }
            }
            let d = self.lu[col * r + col];
            for row in col + 1..r {
                let f = self.lu[row * r + col] / d;
                self.lu[row * r + col] = f;
                for j in col + 1..r {
                    self.lu[row * r + j] -= f * self.lu[col * r + j];
                }
            }
        }
        true
    }

    /// Solves N_S λ = `lambda` in place with the factors of [`Self::factor`].
    fn lu_solve(&mut self, r: usize) {
        let x = &mut self.lambda;
        for col in 0..r {
            x.swap(col, self.piv[col]);
        }
        for row in 0..r {
            for j in 0..row {
                x[row] -= self.lu[row * r + j] * x[j];
            }
        }
        for row in (0..r).rev() {
            for j in row + 1..r {
                x[row] -= self.lu[row * r + j] * x[j];
            }
            x[row] /= self.lu[row * r + row];
        }
    }
}

/// The next r-subset of 0..n in lexicographic order; false after the last.
fn next_combination(c: &mut [usize], n: usize) -> bool {
    let r = c.len();
    let mut k = r;
    while k > 0 {
        k -= 1;
        if c[k] < n - r + k {
            c[k] += 1;
            for j in k + 1..r {
                c[j] = c[j - 1] + 1;
            }
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combinations_and_counts() {
        let mut c = vec![0, 1];
        let mut seen = 1;
        while next_combination(&mut c, 5) {
            seen += 1;
        }
        assert_eq!(seen, 10);
        assert_eq!(candidate_bases(8, 2), 28 * 4);
        assert_eq!(candidate_bases(6, 0), 1);
        let mut none: Vec<usize> = vec![];
        assert!(!next_combination(&mut none, 3));
    }
}

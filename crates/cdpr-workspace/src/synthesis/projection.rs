//! # Dykstra's alternating projection
//!
//! Euclidean projection onto the intersection of a box and half-spaces: the exact solution of the
//! Dynamic-Q subproblem, whose objective approximation is spherical (eq. (6.29) constraints
//! linearised, move limit as a box).
//!
//! ## References
//! - J. P. Boyle and R. L. Dykstra, "A method for finding projections onto the intersection of
//!   convex sets in Hilbert spaces", *Lecture Notes in Statistics* 37 (1986) 28–47.

/// Half-space σ (s_j − s_i) ≥ rhs in step space (normal −σ e_i + σ e_j).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PairHalfSpace {
    pub i: usize,
    pub j: usize,
    pub sign: f64,
    pub rhs: f64,
}

impl PairHalfSpace {
    fn value(&self, s: &[f64]) -> f64 {
        if self.i == self.j {
            0.0
        } else {
            self.sign * (s[self.j] - s[self.i])
        }
    }

    /// Projects `s` onto the half-space in place.
    fn project(&self, s: &mut [f64]) {
        if self.i == self.j {
            return;
        }
        let gap = self.rhs - self.value(s);
        if gap > 0.0 {
            // ‖normal‖² = 2.
            let t = gap / 2.0;
            s[self.j] += self.sign * t;
            s[self.i] -= self.sign * t;
        }
    }
}

/// Scratch buffers of [`project`].
#[derive(Debug, Clone, Default)]
pub(crate) struct Projector {
    increments: Vec<f64>,
    z: Vec<f64>,
}

impl Projector {
    /// Writes into `s` the projection of `y` onto {|s_k| ≤ radius} ∩ half-spaces. When the
    /// intersection is empty the iteration stops after its sweep budget at a point between the sets.
    pub fn project(&mut self, y: &[f64], radius: f64, halfspaces: &[PairHalfSpace], s: &mut [f64]) {
        let n = y.len();
        let sets = halfspaces.len() + 1;
        self.increments.clear();
        self.increments.resize(n * sets, 0.0);
        self.z.resize(n, 0.0);
        s.copy_from_slice(y);
        for _ in 0..20_000 {
            // Stop when a whole sweep leaves every increment unchanged (Birgin and Raydan's
            // criterion; the iterate alone can pause while the increments still move).
            let mut change = 0.0f64;
            for k in 0..sets {
                let p = &mut self.increments[k * n..(k + 1) * n];
                for ((z, si), pi) in self.z.iter_mut().zip(s.iter()).zip(p.iter()) {
                    *z = si + pi;
                }
                s.copy_from_slice(&self.z);
                if k == 0 {
                    for v in s.iter_mut() {
                        *v = v.clamp(-radius, radius);
                    }
                } else {
                    halfspaces[k - 1].project(s);
                }
                for ((pi, z), si) in p.iter_mut().zip(&self.z).zip(s.iter()) {
                    let new = z - si;
                    change = change.max((new - *pi).abs());
                    *pi = new;
                }
            }
            if change < 1e-15 * (1.0 + radius) {
                break;
            }
        }
        // Dykstra converges slowly where constraints are nearly parallel (thin feasible sets);
        // finish exactly: project onto the constraints active at its iterate and keep the result
        // if it satisfies the KKT conditions (feasible, non-negative multipliers).
        polish_on_active_set(y, radius, halfspaces, s);
    }
}

/// Rows a·s ≥ b of the box |s_k| ≤ radius and the half-spaces.
fn rows(n: usize, radius: f64, halfspaces: &[PairHalfSpace]) -> Vec<(Vec<f64>, f64)> {
    let mut out = Vec::with_capacity(2 * n + halfspaces.len());
    for k in 0..n {
        for sign in [1.0, -1.0] {
            let mut a = vec![0.0; n];
            a[k] = sign;
            out.push((a, -radius));
        }
    }
    for h in halfspaces.iter().filter(|h| h.i != h.j) {
        let mut a = vec![0.0; n];
        a[h.j] += h.sign;
        a[h.i] -= h.sign;
        out.push((a, h.rhs));
    }
    out
}

/// When `s` is infeasible, replaces it by the exact projection of `y`: the KKT point
/// s* = y + Aᵀμ (A s* = b on an active set, μ ≥ 0, s* feasible). The active set is guessed from
/// the constraints nearly active at `s`, and, for up to 6 variables, found by enumeration when
/// the guess fails (a KKT point of this convex problem is its unique solution).
fn polish_on_active_set(y: &[f64], radius: f64, halfspaces: &[PairHalfSpace], s: &mut [f64]) {
    let all = rows(y.len(), radius, halfspaces);
    let dot = |a: &[f64], v: &[f64]| a.iter().zip(v).map(|(p, q)| p * q).sum::<f64>();
    if all
        .iter()
        .all(|(a, b)| dot(a, s) - b >= -1e-13 * (1.0 + radius))
    {
        return;
    }
    for tol in [1e-6, 1e-4, 1e-2] {
        let active: Vec<usize> = (0..all.len())
            .filter(|&k| dot(&all[k].0, s) - all[k].1 <= tol * (1.0 + radius))
            .collect();
        if let Some(candidate) = kkt_point(y, &all, &active, radius) {
            s.copy_from_slice(&candidate);
            return;
        }
    }
    let (n, m) = (y.len(), all.len());
    if n > 6 || m > 20 {
        return;
    }
    for mask in 1u32..(1 << m) {
        if mask.count_ones() as usize > n {
            continue;
        }
        let active: Vec<usize> = (0..m).filter(|&k| mask & (1 << k) != 0).collect();
        if let Some(candidate) = kkt_point(y, &all, &active, radius) {
            s.copy_from_slice(&candidate);
            return;
        }
    }
}

/// The KKT point with the rows `active` held as equalities, if it is one.
fn kkt_point(
    y: &[f64],
    all: &[(Vec<f64>, f64)],
    active: &[usize],
    radius: f64,
) -> Option<Vec<f64>> {
    let n = y.len();
    let dot = |a: &[f64], v: &[f64]| a.iter().zip(v).map(|(p, q)| p * q).sum::<f64>();
    if active.is_empty() {
        return None;
    }
    let m = active.len();
    let a = nalgebra::DMatrix::from_fn(m, n, |r, c| all[active[r]].0[c]);
    let rhs = nalgebra::DVector::from_fn(m, |r, _| all[active[r]].1 - dot(&all[active[r]].0, y));
    let pinv = (&a * a.transpose()).pseudo_inverse(1e-12).ok()?;
    let mu = pinv * rhs;
    if mu.iter().any(|&v| v < -1e-12) {
        return None;
    }
    let candidate = nalgebra::DVector::from_column_slice(y) + a.transpose() * mu;
    let c = candidate.as_slice();
    let scale = 1e-12 * (1.0 + radius);
    // Feasible everywhere, and the multipliers reproduce the active rows (a rank-deficient set
    // may not).
    let feasible = all.iter().all(|(r, b)| dot(r, c) - b >= -scale);
    let consistent = active
        .iter()
        .all(|&k| (dot(&all[k].0, c) - all[k].1).abs() <= scale);
    (feasible && consistent).then(|| c.to_vec())
}

/// Largest violation of the box and half-spaces at `s` (0 when feasible).
#[cfg(test)]
pub(crate) fn violation(s: &[f64], radius: f64, halfspaces: &[PairHalfSpace]) -> f64 {
    let b = s.iter().map(|v| v.abs() - radius).fold(0.0, f64::max);
    halfspaces
        .iter()
        .map(|h| h.rhs - h.value(s))
        .fold(b, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;
    use proptest::prelude::*;

    #[test]
    fn box_only_is_a_clamp() {
        let mut p = Projector::default();
        let mut s = [0.0; 3];
        p.project(&[0.5, -0.05, -3.0], 0.1, &[], &mut s);
        assert_eq!(s, [0.1, -0.05, -0.1]);
    }

    #[test]
    fn hand_solved_two_dimensional_case() {
        // min ‖s − (0, 0)‖² s.t. s_1 − s_0 ≥ 0.1, |s| ≤ 1: s = (−0.05, 0.05).
        let h = [PairHalfSpace {
            i: 0,
            j: 1,
            sign: 1.0,
            rhs: 0.1,
        }];
        let mut p = Projector::default();
        let mut s = [0.0; 2];
        p.project(&[0.0, 0.0], 1.0, &h, &mut s);
        assert_abs_diff_eq!(s[0], -0.05, epsilon = 1e-12);
        assert_abs_diff_eq!(s[1], 0.05, epsilon = 1e-12);
        // Radius 0.06 and y = (0.3, 0): the box caps s_1 at 0.06, so s_0 = −0.04.
        p.project(&[0.3, 0.0], 0.06, &h, &mut s);
        assert_abs_diff_eq!(s[1], 0.06, epsilon = 1e-9);
        assert_abs_diff_eq!(s[0], -0.04, epsilon = 1e-9);
    }

    proptest! {
        /// Optimality against brute force: no feasible grid point is closer to y than the answer.
        #[test]
        fn projection_is_feasible_and_nearest(
            y in proptest::collection::vec(-0.5..0.5f64, 3),
            rhs in proptest::collection::vec(-0.1..0.1f64, 3),
            signs in proptest::collection::vec(proptest::bool::ANY, 3),
        ) {
            let pairs = [(0, 1), (1, 2), (2, 0)];
            let h: Vec<PairHalfSpace> = pairs.iter().zip(&rhs).zip(&signs)
                .map(|((&(i, j), &r), &sg)| PairHalfSpace { i, j, sign: if sg { 1.0 } else { -1.0 }, rhs: r / 3.0 })
                .collect();
            let r = 0.2;
            let mut p = Projector::default();
            let mut s = [0.0; 3];
            p.project(&y, r, &h, &mut s);
            // The constraints admit s = 0 only when every rhs ≤ 0: require feasibility via grid.
            let dist = |v: &[f64]| v.iter().zip(&y).map(|(a, b)| (a - b).powi(2)).sum::<f64>();
            let mut best = f64::INFINITY;
            let k = 40;
            for a in 0..=k { for b in 0..=k { for c in 0..=k {
                let v = [-r + 2.0 * r * a as f64 / k as f64, -r + 2.0 * r * b as f64 / k as f64, -r + 2.0 * r * c as f64 / k as f64];
                if violation(&v, r, &h) <= 0.0 { best = best.min(dist(&v)); }
            }}}
            prop_assume!(best.is_finite());
            prop_assert!(violation(&s, r, &h) < 1e-9);
            prop_assert!(dist(&s) <= best + 1e-9);
        }
    }
}

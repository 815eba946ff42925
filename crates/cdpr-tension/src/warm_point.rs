//! # A second interior candidate for the verdicts of grids (l2, 6 × 8, redundancy 2)
//!
//! When the central point λ_c = Nᵀ t_mid − g of `TensionSolver::is_feasible` (l2, r = 2;
//! module `central_point`) misses its margin, a second candidate is proposed, in SIMD lanes for
//! the four problems of `TensionSolver::is_feasible_four_6x8`, before any lane goes to the l2
//! active set. Along a line λ = a + s u every tension is affine in s,
//! t_i(s) = t_i(a) + s N_i u, so the s that keep every t_i inside its bounds by the margin
//! form an interval, the intersection of n intervals (a chord of the feasible polygon shrunk by
//! the margin); its middle is the candidate of that line. The lines, each tried only for the
//! lanes the previous ones missed:
//!
//! 1. *warm* (grid neighbours have close tensions): the solver's last certified tensions t_w
//!    (kept per solver, i.e. per thread; see below) give λ_w = Nᵀ t_w − g, the point of the
//!    problem's affine set t = t0 + N λ nearest t_w (N orthonormal; Picard, Caro, Plestan &
//!    Claveau 2020, eq. (5)); the line from λ_c through λ_w;
//! 2. the line through λ_w across it (direction (−u₂, u₁));
//! 3. *clipped*: the line from λ_c toward the central tensions clipped into their bounds less
//!    the margin, u = Nᵀ e with e_i = min(max(t_i, t_min,i + m_i), t_max,i − m_i) − t_i (λ_c + u
//!    is the point nearest the clipped tensions: one step of alternating projections). It needs
//!    no memory.
//!
//! The candidate is then tested exactly as the central point is (`central_point`, the same
//! functions): every t_i = t0_i + N_i λ inside its bounds by
//! m_i = 10⁻⁶ (t_max,i − t_min,i) + 10⁻⁹ max(|t_min,i|, |t_max,i|), and the certificate's
//! residual within 10⁻⁹ max(1, ‖w_ext‖∞), for W and w_ext finite and a regular null space.
//! The tensions of the last lane it certifies become the next t_w; so do the tensions of the l2
//! active set when a grid problem needs it. On the bench grid of issue 17 the three lines
//! settle 3 100 of the 3 420 feasible poses whose central point fails (the clipped line alone
//! 2 782, the warm lines alone 2 640).
//!
//! **Why this candidate cannot change a verdict.** The chords only *propose* a point; the
//! verdict "feasible" rests on the same two tests as the central point's, which do not depend
//! on where the point came from: tensions that pass the certificate and lie inside every bound
//! by the margin (far above the polygon's clipping tolerance 10⁻¹⁰ max(1, |bound|) and the
//! rounding of t0 + N λ) show that the feasible polygon has interior around that λ, where the
//! l2 active set, the clipped polygon and so every method's `solve` find a feasible point too
//! (the argument of the central point: `planar_active_set::central_point`, and
//! `docs/algorithms.md`, "Feasibility verdicts at r = 2"); nor can a Farkas proof of
//! infeasibility (module `infeasibility`) succeed there, since it shows that no tension passes
//! the certificate. A lane whose candidate fails goes on exactly as without it, so every
//! "infeasible" is still the method's own verdict. Hence a grid verdict depends neither on
//! which thread evaluates which pose nor on their order: the remembered tensions change only
//! how fast "feasible" is found.
//!
//! Each lane performs the same operations in the same order in the AVX2 build (chosen at run
//! time) and the portable one, without fused multiply–adds: the same bits.
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (5)–(6).
//! - Thesis eqs. (6.11), (6.21) (the certificate).

use crate::TensionBounds;
use crate::central_point::{balanced, inside_margin, nearest, regular, tensions};
use crate::lanes::{F64x4, Portable};
use crate::null_space::{FourNullSpaces, LANES};
use crate::planar_active_set::central_margin;

/// The tensions t_w of the last certified grid verdict (see the module docs).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct WarmPoint {
    /// t_w, when there is one.
    t: Option<[f64; 8]>,
}

impl WarmPoint {
    /// Keeps `t` (certified tensions of an 8-cable problem) for the next problems; any other
    /// length is ignored.
    #[inline]
    pub(crate) fn remember(&mut self, t: &[f64]) {
        if let Ok(t) = <[f64; 8]>::try_from(t) {
            self.t = Some(t);
        }
    }

    /// The lanes of `todo` whose candidate (see the module docs) is certified (bit l for
    /// problem l; W and w_ext finite are the caller's part of `todo`), and remembers the
    /// tensions of the last one.
    /// The arguments are those of `central_point::four_6x8`. AVX2 when the CPU has it.
    pub(crate) fn four_6x8(
        &mut self,
        four: &FourNullSpaces,
        columns: &[[[f64; LANES]; 6]; 8],
        w_ext: &[f64],
        bounds: &TensionBounds,
        todo: u32,
    ) -> u32 {
        if todo == 0 {
            return 0;
        }
        let mut t = [[0.0; LANES]; 8];
        let certified = warm_6x8(four, columns, w_ext, bounds, self.t.as_ref(), todo, &mut t);
        if certified != 0 {
            let l = (31 - certified.leading_zeros()) as usize;
            let mut last = [0.0; 8];
            for (d, ti) in last.iter_mut().zip(&t) {
                *d = ti[l];
            }
            self.t = Some(last);
        }
        certified
    }
}

/// The candidates of four problems (see the module docs; `warm`: the remembered tensions, if
/// any): the lanes of `todo` certified, and their candidate tensions in `t`. AVX2 when the CPU
/// has it.
pub(crate) fn warm_6x8(
    four: &FourNullSpaces,
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
    warm: Option<&[f64; 8]>,
    todo: u32,
    t: &mut [[f64; LANES]; 8],
) -> u32 {
    #[cfg(target_arch = "x86_64")]
    if let Some(v) = crate::lanes::Avx2::detect() {
        // SAFETY: `detect` found AVX2.
        return unsafe { warm_6x8_avx2(v, four, columns, w_ext, bounds, warm, todo, t) };
    }
    warm_6x8_lanes(
        Portable([0.0; LANES]),
        four,
        columns,
        w_ext,
        bounds,
        warm,
        todo,
        t,
    )
}

/// [`warm_6x8`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2 (an [`crate::lanes::Avx2`] value is the proof).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn warm_6x8_avx2(
    v: crate::lanes::Avx2,
    four: &FourNullSpaces,
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
    warm: Option<&[f64; 8]>,
    todo: u32,
    t: &mut [[f64; LANES]; 8],
) -> u32 {
    warm_6x8_lanes(v, four, columns, w_ext, bounds, warm, todo, t)
}

/// [`warm_6x8`] on the lanes of `v` (portable or AVX2: the same bits).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn warm_6x8_lanes<V: F64x4>(
    v: V,
    four: &FourNullSpaces,
    columns: &[[[f64; LANES]; 6]; 8],
    w_ext: &[f64],
    bounds: &TensionBounds,
    warm: Option<&[f64; 8]>,
    todo: u32,
    t: &mut [[f64; LANES]; 8],
) -> u32 {
    debug_assert_eq!((w_ext.len(), bounds.len()), (6, 8));
    let (lo, hi) = (&bounds.min().as_slice()[..8], &bounds.max().as_slice()[..8]);
    let we: &[f64; 6] = w_ext[..6].try_into().expect("six components");
    let zero = v.splat(0.0);
    let mut mid = [zero; 8];
    for i in 0..8 {
        mid[i] = v.splat(0.5 * (lo[i] + hi[i]));
    }
    let lc = nearest(v, four, &mid);
    let tc = tensions(v, four, lc);
    let (mut x, mut found) = (lc, v.mask(false));
    if let Some(warm) = warm {
        // Along the line from λ_c through λ_w; where it misses, across it through λ_w.
        let mut target = [zero; 8];
        for i in 0..8 {
            target[i] = v.splat(warm[i]);
        }
        let lw = nearest(v, four, &target);
        let u = [lw[0].sub(lc[0]), lw[1].sub(lc[1])];
        (x, found) = chord_middle(v, four, bounds, lc, &tc, u);
        if V::bits(found) & todo != todo {
            let tw = tensions(v, four, lw);
            let (y, hit) = chord_middle(v, four, bounds, lw, &tw, [u[1].neg(), u[0]]);
            let new = V::and_not(hit, found);
            x = [V::select(new, y[0], x[0]), V::select(new, y[1], x[1])];
            found = V::or(found, hit);
        }
    }
    if V::bits(found) & todo != todo {
        // From λ_c toward the central tensions clipped into their bounds (less the margin):
        // u = Nᵀ e, e_i = min(max(t_i, t_min,i + m_i), t_max,i − m_i) − t_i.
        let mut u = [zero; 2];
        for i in 0..8 {
            let margin = central_margin(lo[i], hi[i]);
            let (lo_m, hi_m) = (v.splat(lo[i] + margin), v.splat(hi[i] - margin));
            let e = tc[i].max(lo_m).min(hi_m).sub(tc[i]);
            u[0] = u[0].add(v.load(four.basis[0][i]).mul(e));
            u[1] = u[1].add(v.load(four.basis[1][i]).mul(e));
        }
        let (y, hit) = chord_middle(v, four, bounds, lc, &tc, u);
        let new = V::and_not(hit, found);
        x = [V::select(new, y[0], x[0]), V::select(new, y[1], x[1])];
        found = V::or(found, hit);
    }
    let found = V::bits(found);
    // Lanes without a chord, or outside the margin, are not certified: the rest is skipped
    // when no lane is left (the same branches in both builds).
    let todo = todo & found & regular(v, four);
    if todo == 0 || !we.iter().all(|e| e.is_finite()) {
        return 0;
    }
    let tx = tensions(v, four, x);
    for (d, ti) in t.iter_mut().zip(&tx) {
        *d = ti.to_array();
    }
    let todo = todo & inside_margin(v, &tx, bounds);
    if todo == 0 {
        return 0;
    }
    todo & balanced(v, columns, we, &tx)
}

/// The middle of the chord {a + s u : every t_i inside its bounds by the margin} of each lane
/// (`ta`: the tensions at a), and the lanes where it exists (finite, s₀ < s₁). Only a
/// proposal: the caller tests it.
#[inline(always)]
fn chord_middle<V: F64x4>(
    v: V,
    four: &FourNullSpaces,
    bounds: &TensionBounds,
    a: [V; 2],
    ta: &[V; 8],
    u: [V; 2],
) -> ([V; 2], V::Mask) {
    let (lo, hi) = (&bounds.min().as_slice()[..8], &bounds.max().as_slice()[..8]);
    let (n1, n2) = (&four.basis[0], &four.basis[1]);
    let (mut s0, mut s1) = (v.splat(f64::NEG_INFINITY), v.splat(f64::INFINITY));
    for i in 0..8 {
        let margin = central_margin(lo[i], hi[i]);
        let rate = v.load(n1[i]).mul(u[0]).add(v.load(n2[i]).mul(u[1]));
        // s with lo + margin < t_a + s·rate < hi − margin: between the two quotients (their
        // order is the sign of the rate; a zero rate gives ±∞ for a satisfied bound).
        let q1 = v.splat(lo[i] + margin).sub(ta[i]).div(rate);
        let q2 = v.splat(hi[i] - margin).sub(ta[i]).div(rate);
        s0 = s0.max(q1.min(q2));
        s1 = s1.min(q1.max(q2));
    }
    let s = s0.add(s1).mul(v.splat(0.5));
    let ok = V::and(s0.lt(s1), s.abs().lt(v.splat(f64::INFINITY)));
    ([a[0].add(s.mul(u[0])), a[1].add(s.mul(u[1]))], ok)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::central_point::four_6x8 as central_points;
    use crate::certificate::EQUILIBRIUM_TOLERANCE;
    use crate::certificate::snap_and_certify;
    use crate::certificate::tests::uniform;
    use crate::null_space::four_6x8 as null_spaces;
    use crate::{Method, TensionProblem, TensionSolver};
    use cdpr_kinematics::Pose;
    use cdpr_kinematics::reference_robots::ipanema_like_8;
    use nalgebra::{DVector, Vector3};

    /// Along random straight paths of an 8-cable spatial robot, four poses at a time with the
    /// tensions of the previous certified pose as t_w (none on every third path: the clipped
    /// line alone): the portable and (where the CPU has it)
    /// the AVX2 build give the same bits (verdicts and candidate tensions); every lane the warm
    /// candidate certifies has tensions inside every bound by the margin that pass the
    /// certificate, and `solve` (l2) calls it feasible; the candidate settles many of the
    /// poses whose central point fails, and not all. W is scaled up now and then (the residual
    /// beyond its first test), a lane gets NaN, and one t_max is infinite (never certified).
    #[test]
    #[allow(clippy::needless_range_loop)]
    fn warm_lanes_are_certified_and_bit_identical() {
        let robot = ipanema_like_8();
        let mut rnd = uniform(0x9e37_79b9_7f4a_7c15);
        let mut solver = TensionSolver::new(Method::L2);
        let (mut tried, mut hits, mut cold) = (0, 0, 0);
        for case in 0..400 {
            let open = case % 41 == 0;
            let mut hi = vec![1000.0; 8];
            if open {
                hi[2] = f64::INFINITY;
            }
            let b = TensionBounds::new(vec![1.0; 8], hi).unwrap();
            let mass = 5.0 + 20.0 * rnd();
            let we = DVector::from_vec(vec![0.0, 0.0, -9.81 * mass, 0.0, 0.0, 0.0]);
            let start = Vector3::new(2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0, 2.0 * rnd());
            let step = Vector3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 0.1;
            let mut warm: Option<[f64; 8]> = None;
            for group in 0..6 {
                let mut columns = [[[0.0; LANES]; 6]; 8];
                let mut ws = Vec::new();
                for l in 0..LANES {
                    let p = start + step * (4 * group + l) as f64;
                    let pose = Pose::spatial(p, 0.0, 0.0, 0.0);
                    let mut w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
                    if (case + group + l) % 29 == 0 {
                        w *= 10f64.powf(3.0 + 4.0 * rnd());
                    }
                    if (case + group + l) % 31 == 0 {
                        w[(3, 6)] = f64::NAN;
                    }
                    for j in 0..8 {
                        for i in 0..6 {
                            columns[j][i][l] = w[(i, j)];
                        }
                    }
                    ws.push(w);
                }
                let four = null_spaces(
                    &columns,
                    we.as_slice(),
                    &mut crate::null_space::FourQr::default(),
                );
                let c = central_points(&four, &columns, we.as_slice(), &b);
                let todo = c.finite & !c.certified;
                {
                    // Without remembered tensions every third path (the clipped direction alone).
                    let tw = if case % 3 == 0 { None } else { warm };
                    let mut t = [[0.0; LANES]; 8];
                    let portable = warm_6x8_lanes(
                        Portable([0.0; LANES]),
                        &four,
                        &columns,
                        we.as_slice(),
                        &b,
                        tw.as_ref(),
                        todo,
                        &mut t,
                    );
                    #[cfg(target_arch = "x86_64")]
                    if let Some(v) = crate::lanes::Avx2::detect() {
                        let mut t2 = [[0.0; LANES]; 8];
                        // SAFETY: `detect` found AVX2.
                        let avx2 = unsafe {
                            warm_6x8_avx2(
                                v,
                                &four,
                                &columns,
                                we.as_slice(),
                                &b,
                                tw.as_ref(),
                                todo,
                                &mut t2,
                            )
                        };
                        assert_eq!(avx2, portable, "case {case}");
                        let bits = |t: &[[f64; LANES]; 8]| t.map(|r| r.map(f64::to_bits));
                        assert_eq!(bits(&t2), bits(&t), "case {case}");
                    }
                    tried += todo.count_ones();
                    hits += portable.count_ones();
                    if tw.is_none() {
                        cold += portable.count_ones();
                    }
                    assert_eq!(portable & !todo, 0, "case {case}");
                    assert!(!open || portable == 0, "case {case}");
                    for (l, w) in ws.iter().enumerate() {
                        if portable >> l & 1 == 0 {
                            continue;
                        }
                        let mut tl: Vec<f64> = t.iter().map(|r| r[l]).collect();
                        for (i, ti) in tl.iter().enumerate() {
                            let m = central_margin(b.min()[i], b.max()[i]);
                            assert!(ti - b.min()[i] > m && b.max()[i] - ti > m, "case {case}");
                        }
                        let we_max = we.amax();
                        let r = snap_and_certify(w, &we, &b, &mut tl).expect("certified");
                        assert!(r <= EQUILIBRIUM_TOLERANCE * we_max.max(1.0), "case {case}");
                        let p = TensionProblem::new(w, &we, &b);
                        assert!(solver.solve(&p).unwrap().is_feasible(), "case {case}");
                    }
                }
                // The next t_w: the l2 tensions of the last feasible pose of the group.
                for w in &ws {
                    if w.iter().all(|x| x.is_finite())
                        && let Some(t) = solver
                            .solve(&TensionProblem::new(w, &we, &b))
                            .unwrap()
                            .tensions()
                    {
                        warm = Some(std::array::from_fn(|i| t[i]));
                    }
                }
            }
        }
        assert!(
            hits > 100 && hits < tried && cold > 50,
            "{hits} of {tried}, {cold}"
        );
    }

    /// Remembered tensions are kept only for 8 cables; without any, no lane is decided.
    #[test]
    fn remembers_eight_cables() {
        let mut w = WarmPoint::default();
        w.remember(&[1.0; 7]);
        assert!(w.t.is_none());
        w.remember(&[2.0; 8]);
        assert_eq!(w.t, Some([2.0; 8]));
    }
}

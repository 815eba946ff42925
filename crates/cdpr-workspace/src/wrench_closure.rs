//! # Wrench closure (positive spanning of W)
//!
//! A pose is *wrench-closure* when the cables can balance any wrench with positive tensions,
//! i.e. the n columns of W positively span R^DOF. Equivalently (Gordan's alternative) rank W =
//! DOF and W t = 0 for some t > 0, i.e. some t in the null space of W has all components
//! positive. Writing the null space as {N λ : λ ∈ R^r}, r = n − rank W, the test is whether the
//! rows ν_i of N lie strictly on one side of a hyperplane through 0 (∃ λ: ν_i·λ > 0 ∀ i).
//!
//! - r = 0 (n = DOF, or W rank-deficient by its excess): never (W t = 0 forces t = 0, or the rank
//!   condition fails).
//! - r = 1: the null vector has components of a single strict sign.
//! - r = 2: the rows ν_i ∈ R² lie in an open half-plane iff the largest angular gap between
//!   consecutive directions exceeds π, i.e. some consecutive pair (in angle order) has a
//!   negative cross product, beyond a relative margin of 10⁻⁹. Only the pair on either side
//!   of the direction −ν_0 can be that pair, so it is found in one O(n) pass without sorting
//!   and without trigonometry (the decision of the former sorted test, kept as the oracle of
//!   the property tests).
//! - r ≥ 3: a linear programme, W t = 0 with t ≥ 1 (the scale of t is free), solved with the
//!   `L1` method of `cdpr-tension` under bounds [1, ∞).
//!
//! N comes from the reduced row echelon form of W (partial pivoting), computed in reusable
//! buffers: no allocation per pose for r ≤ 2. The common shapes run on stack arrays, the case
//! where the first DOF columns are the pivot columns unrolled, and 6 × 8 in an AVX2 build when
//! the CPU has it (run-time detection): all of them the same operations in the same order as
//! the general reduction, hence the same bits. Grids decide 6 × 8 matrices four poses at a
//! time (`WrenchClosureTest::decide_four_6x8`): reduction and half-plane test on four f64
//! lanes (`cdpr_kinematics::lanes`: AVX2 registers or a portable array), again with the
//! single-pose bits.
//!
//! ## References
//! - Gouttefarde & Gosselin (2006), IEEE T-RO 22(3), Theorem 1 (positive spanning).
//! - Pham, Yeo, Yang, Kurbanhusen, Chen, Lin (2006), "Force-closure workspace analysis of
//!   cable-driven parallel mechanisms", Mech. Mach. Theory 41: the null-space test.
//! - CASPR (Lau et al. 2016): the wrench-closure workspace condition.

#[cfg(target_arch = "x86_64")]
use cdpr_kinematics::lanes::Avx2;
use cdpr_kinematics::lanes::{F64x4, Portable};

use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector};

/// Relative size below which a pivot counts as zero (rank decision).
const RANK_TOLERANCE: f64 = 1e-9;
/// Relative margin for strict positivity.
const STRICT_TOLERANCE: f64 = 1e-9;

/// Reusable state of the wrench-closure test for one robot (DOF × n wrench matrices).
#[derive(Debug, Clone)]
pub struct WrenchClosureTest {
    dof: usize,
    n: usize,
    /// Row-major copy of W reduced in place to RREF.
    a: Vec<f64>,
    /// Pivot column of each pivot row.
    pivots: Vec<usize>,
    /// Whether a column is a pivot column.
    is_pivot: Vec<bool>,
    /// Null basis N, n × r, row-major (row i = ν_i).
    null: Vec<f64>,
    /// LP for r ≥ 3.
    lp: Option<Lp>,
    /// Whether the CPU runs the AVX2 build of the 6 × 8 reduction (run-time detection).
    avx2: bool,
}

#[derive(Debug, Clone)]
struct Lp {
    solver: TensionSolver,
    bounds: TensionBounds,
    zero: DVector<f64>,
}

impl WrenchClosureTest {
    /// Buffers for DOF × n wrench matrices.
    pub fn new(dof: usize, n: usize) -> Self {
        let lp = (n >= dof + 3).then(|| Lp {
            solver: TensionSolver::new(Method::L1),
            bounds: TensionBounds::uniform(n, 1.0, f64::INFINITY)
                .expect("finite lower bound 1 below infinite upper bound"),
            zero: DVector::zeros(dof),
        });
        Self {
            dof,
            n,
            a: vec![0.0; dof * n],
            pivots: Vec::with_capacity(dof),
            is_pivot: vec![false; n],
            null: vec![0.0; n * n.saturating_sub(dof).max(1)],
            lp,
            #[cfg(target_arch = "x86_64")]
            avx2: std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(not(target_arch = "x86_64"))]
            avx2: false,
        }
    }

    /// Whether the columns of `w` positively span R^DOF. `w` must be DOF × n as given to
    /// [`WrenchClosureTest::new`]; a matrix of another shape is not wrench-closure.
    pub fn is_wrench_closure(&mut self, w: &DMatrix<f64>) -> bool {
        w.shape() == (self.dof, self.n) && self.decide(w.as_slice(), Some(w)).unwrap_or(false)
    }

    /// [`WrenchClosureTest::is_wrench_closure`] of the DOF × n matrix whose column-major
    /// entries are `w` (W straight from the batch inverse kinematics, not copied into a
    /// matrix), or `None` when the decision needs the linear programme (r ≥ 3) or `w` has not
    /// DOF · n entries.
    pub(crate) fn is_wrench_closure_columns(&mut self, w: &[f64]) -> Option<bool> {
        if w.len() != self.dof * self.n {
            return None;
        }
        self.decide(w, None)
    }

    /// The decision for column-major entries `w` of a DOF × n matrix; `matrix` (the same
    /// entries) serves the linear programme, `None` when it is needed but not given.
    fn decide(&mut self, w: &[f64], matrix: Option<&DMatrix<f64>>) -> Option<bool> {
        let (dof, n) = (self.dof, self.n);
        // Finiteness of every entry as one branch-free pass (vectorised), not an early exit.
        if n <= dof || !w.iter().fold(true, |ok, v| ok & v.is_finite()) {
            return Some(false);
        }
        let Some(r) = self.reduce(w) else {
            return Some(false);
        };
        match r {
            1 => Some(self.one_dimensional()),
            2 => Some(self.half_plane()),
            _ => matrix.map(|m| self.linear_programme(m)),
        }
    }

    /// RREF of W; fills the null basis and returns r = n − DOF, or `None` if rank W < DOF.
    /// The common shapes run [`WrenchClosureTest::reduce_fixed`] (the same arithmetic on the
    /// stack, sizes known at compile time: the same bits).
    fn reduce(&mut self, w: &[f64]) -> Option<usize> {
        match (self.dof, self.n) {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU supports AVX2 (checked at run time in `new`).
            (6, 8) if self.avx2 => unsafe { self.reduce_fixed_avx2::<6, 8>(w) },
            (6, 8) => self.reduce_fixed::<6, 8>(w),
            (6, 7) => self.reduce_fixed::<6, 7>(w),
            (3, 5) => self.reduce_fixed::<3, 5>(w),
            (3, 4) => self.reduce_fixed::<3, 4>(w),
            (2, 4) => self.reduce_fixed::<2, 4>(w),
            _ => self.reduce_dynamic(w),
        }
    }

    /// [`WrenchClosureTest::reduce_fixed`] compiled for AVX2 (wider vectors for the row
    /// updates; no fused multiply–adds, which Rust never forms: the same bits).
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn reduce_fixed_avx2<const D: usize, const N: usize>(
        &mut self,
        w: &[f64],
    ) -> Option<usize> {
        self.reduce_fixed::<D, N>(w)
    }

    /// [`WrenchClosureTest::reduce`] for D × N matrices, in a stack array: the operations of
    /// [`WrenchClosureTest::reduce_dynamic`] in the same order.
    #[inline(always)]
    fn reduce_fixed<const D: usize, const N: usize>(&mut self, w: &[f64]) -> Option<usize> {
        let mut a = [[0.0f64; N]; D];
        // The largest |w_ij| by comparisons (the entries are finite: `f64::max` would give
        // the same value at twice the instructions).
        let mut largest = 0.0f64;
        for (j, column) in w.chunks_exact(D).enumerate() {
            for (i, &v) in column.iter().enumerate() {
                a[i][j] = v;
                largest = if v.abs() > largest { v.abs() } else { largest };
            }
        }
        let scale = largest.max(1e-300);
        if self.reduce_leading(&mut a, scale) {
            return Some(N - D);
        }
        // Rare: a leading column is not a pivot column; start again from W.
        for (j, column) in w.chunks_exact(D).enumerate() {
            for (i, &v) in column.iter().enumerate() {
                a[i][j] = v;
            }
        }
        let mut pivots = [0usize; D];
        let mut is_pivot = [false; N];
        let mut row = 0;
        for col in 0..N {
            if row == D {
                break;
            }
            let (best, best_abs) = partial_pivot(&a, row, col);
            if best_abs <= RANK_TOLERANCE * scale {
                continue;
            }
            if best != row {
                a.swap(row, best);
            }
            let inv = 1.0 / a[row][col];
            // While no column has been skipped (row = col), every column left of `col` is a
            // pivot column, whose entries are never read again: whole rows can then be updated
            // (fixed length, unrolled) with the same values in every entry that is read.
            let full = row == col;
            if full {
                a[row].iter_mut().for_each(|v| *v *= inv);
            } else {
                a[row][col..].iter_mut().for_each(|v| *v *= inv);
            }
            let pivot = a[row];
            for (i, other) in a.iter_mut().enumerate() {
                if i == row {
                    continue;
                }
                let f = other[col];
                if f != 0.0 {
                    if full {
                        for (o, p) in other.iter_mut().zip(&pivot) {
                            *o -= f * p;
                        }
                    } else {
                        for (o, p) in other[col..].iter_mut().zip(&pivot[col..]) {
                            *o -= f * p;
                        }
                    }
                }
            }
            pivots[row] = col;
            is_pivot[col] = true;
            row += 1;
        }
        if row < D {
            return None;
        }
        let r = N - D;
        let null = &mut self.null[..N * r];
        // Every entry written once: free rows hold the identity, pivot rows −a[p][f_k].
        let mut k = 0;
        for f in 0..N {
            if is_pivot[f] {
                continue;
            }
            for (g, &pivot) in is_pivot.iter().enumerate() {
                if !pivot {
                    null[g * r + k] = if g == f { 1.0 } else { 0.0 };
                }
            }
            for (p, &pc) in pivots.iter().enumerate() {
                null[pc * r + k] = -a[p][f];
            }
            k += 1;
        }
        Some(r)
    }

    /// The common case of [`WrenchClosureTest::reduce_fixed`]: the first D columns are the
    /// pivot columns. The operations of its loop in the same order (no column skipped, so
    /// pivot rows are updated whole), unrolled at compile time; writes N and returns `true`,
    /// or returns `false` (N untouched, `a` part-reduced) at the first pivot below the
    /// tolerance, where the general loop takes over from W.
    #[inline(always)]
    fn reduce_leading<const D: usize, const N: usize>(
        &mut self,
        a: &mut [[f64; N]; D],
        scale: f64,
    ) -> bool {
        for col in 0..D {
            let (best, best_abs) = partial_pivot(a, col, col);
            if best_abs <= RANK_TOLERANCE * scale {
                return false;
            }
            if best != col {
                a.swap(col, best);
            }
            let inv = 1.0 / a[col][col];
            a[col].iter_mut().for_each(|v| *v *= inv);
            let pivot = a[col];
            for (i, other) in a.iter_mut().enumerate() {
                let f = other[col];
                if i != col && f != 0.0 {
                    for (o, p) in other.iter_mut().zip(&pivot) {
                        *o -= f * p;
                    }
                }
            }
        }
        // Free columns D..N: column k of N is e_{D+k} above −a[·][D+k].
        let r = N - D;
        let null = &mut self.null[..N * r];
        for k in 0..r {
            for (p, row) in a.iter().enumerate() {
                null[p * r + k] = -row[D + k];
            }
            for g in 0..r {
                null[(D + g) * r + k] = if g == k { 1.0 } else { 0.0 };
            }
        }
        true
    }

    /// [`WrenchClosureTest::reduce`] for any shape, in the reusable buffers.
    fn reduce_dynamic(&mut self, w: &[f64]) -> Option<usize> {
        let (dof, n) = (self.dof, self.n);
        for i in 0..dof {
            for j in 0..n {
                self.a[i * n + j] = w[j * dof + i];
            }
        }
        let scale = self
            .a
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            .max(1e-300);
        self.pivots.clear();
        self.is_pivot.iter_mut().for_each(|p| *p = false);
        let a = &mut self.a[..dof * n];
        let mut row = 0;
        for col in 0..n {
            if row == dof {
                break;
            }
            let (mut best, mut best_abs) = (row, 0.0);
            for i in row..dof {
                let v = a[i * n + col].abs();
                if v > best_abs {
                    best = i;
                    best_abs = v;
                }
            }
            if best_abs <= RANK_TOLERANCE * scale {
                continue;
            }
            if best != row {
                let (lo, hi) = a.split_at_mut(best * n);
                lo[row * n..row * n + n].swap_with_slice(&mut hi[..n]);
            }
            // Normalise the pivot row (its columns before `col` are zero), then eliminate.
            let inv = 1.0 / a[row * n + col];
            a[row * n + col..row * n + n]
                .iter_mut()
                .for_each(|v| *v *= inv);
            let (before, rest) = a.split_at_mut(row * n);
            let (pivot_row, after) = rest.split_at_mut(n);
            let pivot = &pivot_row[col..];
            for other in before.chunks_exact_mut(n).chain(after.chunks_exact_mut(n)) {
                let f = other[col];
                if f != 0.0 {
                    for (o, p) in other[col..].iter_mut().zip(pivot) {
                        *o -= f * p;
                    }
                }
            }
            self.pivots.push(col);
            self.is_pivot[col] = true;
            row += 1;
        }
        if self.pivots.len() < dof {
            return None;
        }
        let r = n - dof;
        // Column k of N: the free variable f_k set to 1, pivot variables x_p = −a[p][f_k].
        self.null[..n * r].iter_mut().for_each(|v| *v = 0.0);
        let mut k = 0;
        for f in 0..n {
            if self.is_pivot[f] {
                continue;
            }
            self.null[f * r + k] = 1.0;
            for (p, &pc) in self.pivots.iter().enumerate() {
                self.null[pc * r + k] = -self.a[p * n + f];
            }
            k += 1;
        }
        Some(r)
    }

    fn one_dimensional(&self) -> bool {
        let v = &self.null[..self.n];
        let scale = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let tol = STRICT_TOLERANCE * scale;
        v.iter().all(|&x| x > tol) || v.iter().all(|&x| x < -tol)
    }

    /// r = 2: the rows ν_i lie in an open half-plane. The decision is that of sorting the rows
    /// by pseudo-angle (stable: ties in index order) and asking whether some cyclically
    /// consecutive pair (u, w) has `gap(u, w)` (a negative cross product, |sin| of the angle
    /// beyond `STRICT_TOLERANCE`), but without the sort, in O(n):
    ///
    /// - the pair tested is the one straddling t = angle(−ν_0): u the last row (in the order
    ///   above) with angle < t, w the first with angle ≥ t (cyclically: the last and first rows
    ///   overall when one side is empty). u, w are consecutive in that order, so a `true` here
    ///   is a `true` of the sorted test.
    /// - conversely, if some consecutive pair (u*, w*) passes `gap`, the rows lie in the closed
    ///   arc from w* to u* of width < π − 10⁻⁹ rad, and −ν_0 lies in the open arc from u* to w*
    ///   at least 10⁻⁹ rad from its ends. The pseudo-angle grows at least 1/2 per radian and
    ///   is computed within ~10⁻¹⁵, so t separates the angles of u* and w* and the pair
    ///   straddling t is (u*, w*).
    ///
    /// `tests::half_plane_equals_the_sorted_test` checks it against the sorted test, kept as
    /// the oracle.
    fn half_plane(&self) -> bool {
        // Eight cables (6 DOF) with the length known at compile time: no bounds checks.
        match <&[f64; 16]>::try_from(&self.null[..2 * self.n]) {
            Ok(null) => straddling_pair_gap(8, 0, |i| (null[2 * i], null[2 * i + 1])),
            Err(_) => {
                let null = &self.null[..2 * self.n];
                straddling_pair_gap(self.n, 0, |i| (null[2 * i], null[2 * i + 1]))
            }
        }
    }
}

/// Poses per group of [`WrenchClosureTest::decide_four_6x8`] (four f64 lanes: one AVX2
/// register).
pub(crate) const LANES: usize = 4;

/// One f64 per pose of a group.
pub(crate) type Lanes = [f64; LANES];

/// What [`decide_lanes`] found for each pose of a group.
struct LaneDecision {
    /// Every entry of W finite.
    finite: [bool; LANES],
    /// The first six columns were the pivot columns (the common case): the null basis is
    /// in the columns 6 and 7 of the reduced rows.
    leading: [bool; LANES],
    /// Some coordinate of the null basis is NaN (overflow in the reduction): the half-plane
    /// test is left to the single-pose [`straddling_pair_gap`], which orders NaN rows by
    /// their `f64::total_cmp` keys.
    nan: [bool; LANES],
    /// [`WrenchClosureTest::half_plane`] of the null basis (meaningful where `leading` is
    /// set and `nan` is not).
    closure: [bool; LANES],
    /// Rows 0–5 of the null basis N (its coordinates x, y per row); rows 6 and 7 are e₁, e₂.
    null: [[Lanes; 6]; 2],
}

impl WrenchClosureTest {
    /// The decisions of four 6 × 8 wrench matrices given as lanes, `columns[j][i][l]` =
    /// W(i, j) of pose l (the layout of `Robot::wrench_matrix_lanes`):
    /// [`WrenchClosureTest::is_wrench_closure_columns`] of each, with the finiteness check,
    /// the scale, the reduction of the common case (leading pivot columns,
    /// [`WrenchClosureTest::reduce_leading`]) and the half-plane test computed across the four
    /// poses at once ([`decide_lanes`]): the operations of the single-pose path on the same
    /// values, hence the same bits. A pose outside the common case goes through the
    /// single-pose path. Lanes with `wanted[l]` false are not decided (`false`).
    pub(crate) fn decide_four_6x8(
        &mut self,
        columns: &[[Lanes; 6]; 8],
        wanted: [bool; LANES],
    ) -> [bool; LANES] {
        assert!(self.dof == 6 && self.n == 8, "6 × 8 wrench matrices");
        let lanes = match self.avx2 {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU supports AVX2 (checked at run time in `new`).
            true => unsafe { decide_lanes_avx2(columns) },
            _ => decide_lanes(Portable([0.0; LANES]), columns),
        };
        let mut decided = [false; LANES];
        for (l, d) in decided.iter_mut().enumerate() {
            *d = if !(wanted[l] && lanes.finite[l]) {
                false
            } else if lanes.leading[l] && !lanes.nan[l] {
                lanes.closure[l]
            } else {
                self.decide_lane_alone(columns, &lanes, l)
            };
        }
        decided
    }

    /// The decision of lane `l` outside the common case of [`decide_lanes`] (a pivot column
    /// skipped, or a NaN in the null basis): the single-pose half-plane test on the lanes' null
    /// basis, or the single-pose path from W.
    #[cold]
    #[inline(never)]
    fn decide_lane_alone(
        &mut self,
        columns: &[[Lanes; 6]; 8],
        lanes: &LaneDecision,
        l: usize,
    ) -> bool {
        if lanes.leading[l] {
            let null = &mut self.null[..16];
            for p in 0..6 {
                null[2 * p] = lanes.null[0][p][l];
                null[2 * p + 1] = lanes.null[1][p][l];
            }
            null[12..].copy_from_slice(&[1.0, 0.0, 0.0, 1.0]);
            self.half_plane()
        } else {
            let w: [f64; 48] = std::array::from_fn(|k| columns[k / 6][k % 6][l]);
            self.decide(&w, None).unwrap_or(false)
        }
    }
}

/// [`decide_lanes`] on AVX2 registers ([`Avx2`]).
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn decide_lanes_avx2(columns: &[[Lanes; 6]; 8]) -> LaneDecision {
    // SAFETY: the CPU supports AVX2 (this function's contract).
    decide_lanes(unsafe { Avx2::new_unchecked() }, columns)
}

/// The four-pose decision on lanes of type `V`: finiteness (as `decide`), the scale and
/// [`WrenchClosureTest::reduce_leading`] (as `reduce_fixed`), then
/// [`WrenchClosureTest::half_plane`] ([`half_plane_lanes`]). Each step does, lane by lane,
/// what the single-pose path does; a branch becomes a mask and a blend. A lane whose pivot
/// falls below the rank tolerance is flagged (`leading` false) and its values are
/// meaningless. `v` witnesses that `V`'s instructions are available.
#[inline(always)]
fn decide_lanes<V: F64x4>(v: V, columns: &[[Lanes; 6]; 8]) -> LaneDecision {
    // No closures here: a closure is not compiled with the caller's target features, so the
    // AVX2 intrinsics would become calls.
    // Finiteness, and the largest |w_ij| by comparisons, column by column.
    let mut finite = v.mask(true);
    let mut largest = v.splat(0.0);
    for column in columns {
        for entry in column {
            let e = v.load(*entry).abs();
            finite = V::and(finite, e.lt(v.splat(f64::INFINITY)));
            largest = V::select(e.gt(largest), e, largest);
        }
    }
    // `largest.max(1e-300)` (largest is finite and ≥ 0 where it matters).
    let tiny = v.splat(1e-300);
    let tolerance = v
        .splat(RANK_TOLERANCE)
        .mul(V::select(largest.lt(tiny), tiny, largest));
    let mut leading = finite;
    // The reduced matrix; step 0 reads W from `columns` (no copy) and writes every entry that
    // later steps read.
    let mut a = [[v.splat(0.0); 6]; 8];
    pivot_step::<V, 0>(&mut a, columns, &mut leading, tolerance);
    pivot_step::<V, 1>(&mut a, columns, &mut leading, tolerance);
    pivot_step::<V, 2>(&mut a, columns, &mut leading, tolerance);
    pivot_step::<V, 3>(&mut a, columns, &mut leading, tolerance);
    pivot_step::<V, 4>(&mut a, columns, &mut leading, tolerance);
    pivot_step::<V, 5>(&mut a, columns, &mut leading, tolerance);
    // Row p of N is −(row p)[6..8].
    let (mut x, mut y) = ([v.splat(0.0); 8], [v.splat(0.0); 8]);
    let mut null = [[[0.0; LANES]; 6]; 2];
    for p in 0..6 {
        (x[p], y[p]) = (a[6][p].neg(), a[7][p].neg());
        (null[0][p], null[1][p]) = (x[p].to_array(), y[p].to_array());
    }
    (x[6], y[7]) = (v.splat(1.0), v.splat(1.0));
    let (nan, closure) = half_plane_lanes(&x, &y);
    LaneDecision {
        finite: V::to_bools(finite),
        leading: V::to_bools(leading),
        nan: V::to_bools(nan),
        closure: V::to_bools(closure),
        null,
    }
}

/// Step `C` of [`WrenchClosureTest::reduce_leading`], pivot column `C`, on lanes. Only the
/// columns right of C are updated (the single-pose loop updates whole rows, but its entries
/// left of the pivot column are never read again). `tolerance` is also the witness of `V`'s
/// instructions.
#[inline(always)]
fn pivot_step<V: F64x4, const C: usize>(
    a: &mut [[V; 6]; 8],
    columns: &[[Lanes; 6]; 8],
    leading: &mut V::Mask,
    tolerance: V,
) {
    let v = tolerance;
    // Partial pivoting (`partial_pivot`): the first row from C on with the largest |a_iC|.
    let mut best_abs = v.splat(0.0);
    let mut best = v.splat(C as f64);
    for i in C..6 {
        let e = entry::<V, C>(v, a, columns, C, i).abs();
        let take = e.gt(best_abs);
        best_abs = V::select(take, e, best_abs);
        best = V::select(take, v.splat(i as f64), best);
    }
    *leading = V::and_not(*leading, best_abs.le(tolerance));
    // `a.swap(C, best)`: the pivot row gathered (columns C..8); row i > C is row C where it
    // was the pivot row (applied as the row is read below, so that every store is a plain one).
    let mut chosen = [v.mask(false); 6];
    for (i, c) in chosen.iter_mut().enumerate().skip(C + 1) {
        *c = best.eq(v.splat(i as f64));
    }
    let mut pivot = [v.splat(0.0); 8];
    for (j, p) in pivot.iter_mut().enumerate().skip(C) {
        *p = entry::<V, C>(v, a, columns, j, C);
    }
    for (i, &is) in chosen.iter().enumerate().skip(C + 1) {
        for (j, p) in pivot.iter_mut().enumerate().skip(C) {
            *p = V::select(is, entry::<V, C>(v, a, columns, j, i), *p);
        }
    }
    // The pivot row scaled by 1/pivot; `o −= f · p` in every other row whose entry in column
    // C is not zero (the product kept as +0 otherwise: e − (+0) is e, −0 included).
    let inv = v.splat(1.0).div(pivot[C]);
    for p in pivot[C + 1..].iter_mut() {
        *p = p.mul(inv);
    }
    for i in 0..6 {
        if i == C {
            continue;
        }
        let f = row_after_exchange::<V, C>(v, a, columns, &chosen, i, C);
        let eliminate = f.ne(v.splat(0.0));
        for j in C + 1..8 {
            a[j][i] = row_after_exchange::<V, C>(v, a, columns, &chosen, i, j)
                .sub(f.mul(pivot[j]).keep(eliminate));
        }
    }
    for j in C + 1..8 {
        a[j][C] = pivot[j];
    }
}

/// [`straddling_pair_gap`] with row 0 as reference, on lanes: rows 0–5 of the null basis
/// (`x`, `y`), rows 6 and 7 e₁ and e₂, in the single-pose order (which fixes its ties).
/// Returns the masks (NaN in the basis, half-plane verdict). Each step with the same
/// arithmetic, branches becoming blends:
///
/// - the norm pass, the same comparisons in the same order;
/// - [`diamond_angle`] as one division per row: the branch picks numerator, denominator
///   (x ± y with the signs of the branch: −x + y, −x − y and x − y are (−x) + y, (−x) + (−y)
///   and x + (−y) exactly) and the constant c of c − q (3 + q is 3 − (−q) exactly);
/// - the keys of `f64::total_cmp`: without NaN rows every angle of a lane that passes the norm
///   test lies in {−0} ∪ [0, 4] (no row is zero, so no 0/0), where the order of the bits as
///   signed integers is that of `total_cmp` (−0 has the smallest key, the rest are
///   non-negative);
/// - the four running pairs (first, last, last below t, first at or above t) as blends of
///   keys and rows, with the single-pose comparisons (strict or not) and a "none yet" flag;
/// - [`gap`] of the chosen rows.
#[inline(always)]
fn half_plane_lanes<V: F64x4>(x: &[V; 8], y: &[V; 8]) -> (V::Mask, V::Mask) {
    // Any lane value witnesses that `V`'s instructions are available.
    let v = x[0];
    let zero = v.splat(0.0);
    // The norm pass and the NaN flag (a NaN norm is a NaN coordinate).
    let mut scale2 = zero;
    let mut smallest = v.splat(f64::INFINITY);
    let mut nan = v.mask(false);
    for i in 0..8 {
        let s = x[i].mul(x[i]).add(y[i].mul(y[i]));
        nan = V::or(nan, s.ne(s));
        scale2 = V::select(s.gt(scale2), s, scale2);
        smallest = V::select(s.lt(smallest), s, smallest);
    }
    let tol2 = v.splat(STRICT_TOLERANCE * STRICT_TOLERANCE);
    let slack = smallest.le(tol2.mul(scale2));
    let t = diamond_angle_lanes(x[0].neg(), y[0].neg());
    // (key, x, y) of the first and last rows overall, of the last row below t and of the
    // first at or above t.
    let (max, min) = (
        v.splat(f64::from_bits(i64::MAX as u64)),
        v.splat(f64::from_bits(i64::MIN as u64)),
    );
    let (mut first, mut last) = ((max, x[0], y[0]), (min, x[0], y[0]));
    let (mut below, mut above) = ((min, x[0], y[0]), (max, x[0], y[0]));
    let (mut any_below, mut any_above) = (v.mask(false), v.mask(false));
    for i in 0..8 {
        let k = diamond_angle_lanes(x[i], y[i]);
        let row = (k, x[i], y[i]);
        let is_below = k.lt_bits(t);
        take::<V>(k.lt_bits(first.0), row, &mut first);
        take::<V>(V::not(k.lt_bits(last.0)), row, &mut last);
        take::<V>(V::and_not(is_below, k.lt_bits(below.0)), row, &mut below);
        let m = V::and_not(V::or(k.lt_bits(above.0), V::not(any_above)), is_below);
        take::<V>(m, row, &mut above);
        any_below = V::or(any_below, is_below);
        any_above = V::or(any_above, m);
    }
    let (ux, uy) = (
        V::select(any_below, below.1, last.1),
        V::select(any_below, below.2, last.2),
    );
    let (wx, wy) = (
        V::select(any_above, above.1, first.1),
        V::select(any_above, above.2, first.2),
    );
    let cross = ux.mul(wy).sub(uy.mul(wx));
    let nu = ux.mul(ux).add(uy.mul(uy));
    let nw = wx.mul(wx).add(wy.mul(wy));
    let gap = V::and(cross.lt(zero), cross.mul(cross).gt(tol2.mul(nu).mul(nw)));
    (nan, V::and_not(gap, slack))
}

/// `pair` = `row` (key, x, y) in the lanes of the mask `m`.
#[inline(always)]
fn take<V: F64x4>(m: V::Mask, row: (V, V, V), pair: &mut (V, V, V)) {
    *pair = (
        V::select(m, row.0, pair.0),
        V::select(m, row.1, pair.1),
        V::select(m, row.2, pair.2),
    );
}

/// Entry (i, j) of the matrix after the exchange of rows C and `best` of step C (i ≠ C):
/// row C where row i is the pivot row (`chosen[i]`).
#[inline(always)]
fn row_after_exchange<V: F64x4, const C: usize>(
    v: V,
    a: &[[V; 6]; 8],
    columns: &[[Lanes; 6]; 8],
    chosen: &[V::Mask; 6],
    i: usize,
    j: usize,
) -> V {
    let e = entry::<V, C>(v, a, columns, j, i);
    if i > C {
        V::select(chosen[i], entry::<V, C>(v, a, columns, j, C), e)
    } else {
        e
    }
}

/// Entry (i, j) of the matrix as step C finds it: W itself for step 0, else the reduced
/// matrix `a` (`v` is the witness of `V`'s instructions).
#[inline(always)]
fn entry<V: F64x4, const C: usize>(
    v: V,
    a: &[[V; 6]; 8],
    columns: &[[Lanes; 6]; 8],
    j: usize,
    i: usize,
) -> V {
    if C == 0 {
        v.load(columns[j][i])
    } else {
        a[j][i]
    }
}

/// [`diamond_angle`] on lanes, one division per lane (see [`half_plane_lanes`]); the same
/// bits for coordinates that are not NaN.
#[inline(always)]
fn diamond_angle_lanes<V: F64x4>(x: V, y: V) -> V {
    let zero = x.splat(0.0);
    let (sx, sy) = (x.lt(zero), y.lt(zero));
    // Branches: A (y ≥ 0, x ≥ 0) y / (x + y); B (y ≥ 0, x < 0) 1 − x / (−x + y);
    // C (y < 0, x < 0) 2 − y / (−x − y); D (y < 0, x ≥ 0) 3 + x / (x − y) = 3 − (−x / (x − y)).
    let den = x.neg_where(sx).add(y.neg_where(sy));
    let q = V::select(V::xor(sx, sy), x, y).div(den);
    let c = V::select(sy, V::select(sx, x.splat(2.0), x.splat(3.0)), x.splat(1.0));
    let r = c.sub(q.neg_where(V::and_not(sy, sx)));
    V::select(V::or(sx, sy), r, q)
}

/// [`WrenchClosureTest::half_plane`] of the n rows `row(i)` = ν_i of a null basis, with
/// −ν_`reference` as the direction t that the tested pair straddles. Any row will do: when some
/// consecutive pair (u*, w*) passes `gap`, the rows, ν_`reference` among them, lie in a closed
/// arc of width < π − 10⁻⁹ rad, so −ν_`reference` lies in the open arc from u* to w*, at least
/// 10⁻⁹ rad from its ends (`tests::half_plane_equals_the_sorted_test` checks every choice).
#[inline(always)]
fn straddling_pair_gap(n: usize, reference: usize, row: impl Fn(usize) -> (f64, f64)) -> bool {
    let norm2 = |(x, y): (f64, f64)| x * x + y * y;
    // The largest and the smallest norm by comparisons in one pass: `smallest ≤ tol2 · scale2`
    // is "some row has norm2 ≤ tol2 · scale2" (NaN norms take part in neither).
    let (mut scale2, mut smallest) = (0.0f64, f64::INFINITY);
    for i in 0..n {
        let v = norm2(row(i));
        scale2 = if v > scale2 { v } else { scale2 };
        smallest = if v < smallest { v } else { smallest };
    }
    let tol2 = STRICT_TOLERANCE * STRICT_TOLERANCE;
    if smallest <= tol2 * scale2 {
        return false; // a cable slack in every self-stress
    }
    let (rx, ry) = row(reference);
    let t = total_order_key(diamond_angle(-rx, -ry));
    // (angle, row) of the last row below t, the first at or above t, and the first and last
    // overall; angles compared as `f64::total_cmp` does (the sort's comparison). `NONE` marks
    // "no row yet"; every key is ≥ i64::MIN, so the first row below t always replaces it.
    const NONE: usize = usize::MAX;
    let mut last_below = (i64::MIN, NONE);
    let mut first_above = (i64::MAX, NONE);
    let (mut first, mut last) = ((i64::MAX, usize::MAX), (i64::MIN, 0));
    for i in 0..n {
        let (x, y) = row(i);
        let a = total_order_key(diamond_angle(x, y));
        if a < first.0 {
            first = (a, i);
        }
        if a >= last.0 {
            last = (a, i);
        }
        if a < t {
            if a >= last_below.0 {
                last_below = (a, i);
            }
        } else if a < first_above.0 || first_above.1 == NONE {
            first_above = (a, i);
        }
    }
    let u = if last_below.1 == NONE {
        last.1
    } else {
        last_below.1
    };
    let w = if first_above.1 == NONE {
        first.1
    } else {
        first_above.1
    };
    gap(row(u), row(w), tol2)
}

impl WrenchClosureTest {
    fn linear_programme(&mut self, w: &DMatrix<f64>) -> bool {
        let Some(lp) = self.lp.as_mut() else {
            return false;
        };
        let problem = TensionProblem {
            wrench_matrix: w,
            external_wrench: &lp.zero,
            bounds: &lp.bounds,
            stiffness: None,
        };
        lp.solver.is_feasible(&problem).unwrap_or(false)
    }

    /// The same decision by the linear programme alone (any r ≥ 1), for cross-checks.
    pub fn is_wrench_closure_by_lp(&mut self, w: &DMatrix<f64>) -> bool {
        let (dof, n) = (self.dof, self.n);
        if w.shape() != (dof, n) || n <= dof || self.reduce(w.as_slice()).is_none() {
            return false;
        }
        let lp = self.lp.get_or_insert_with(|| Lp {
            solver: TensionSolver::new(Method::L1),
            bounds: TensionBounds::uniform(n, 1.0, f64::INFINITY)
                .expect("finite lower bound 1 below infinite upper bound"),
            zero: DVector::zeros(dof),
        });
        let problem = TensionProblem {
            wrench_matrix: w,
            external_wrench: &lp.zero,
            bounds: &lp.bounds,
            stiffness: None,
        };
        lp.solver.is_feasible(&problem).unwrap_or(false)
    }
}

/// Partial pivoting: the first row from `row` on with the largest |a[i][col]|, and that value
/// (0 and `row` if all are zero).
#[inline(always)]
fn partial_pivot<const D: usize, const N: usize>(
    a: &[[f64; N]; D],
    row: usize,
    col: usize,
) -> (usize, f64) {
    let (mut best, mut best_abs) = (row, 0.0);
    for (i, r) in a.iter().enumerate().skip(row) {
        let v = r[col].abs();
        if v > best_abs {
            best = i;
            best_abs = v;
        }
    }
    (best, best_abs)
}

/// Whether the counter-clockwise angle from row u to row w of a null basis exceeds π by more
/// than the strict tolerance: ν_u × ν_w < 0 and (ν_u × ν_w)² > tol2 |ν_u|² |ν_w|².
#[inline(always)]
fn gap(u: (f64, f64), w: (f64, f64), tol2: f64) -> bool {
    let norm2 = |(x, y): (f64, f64)| x * x + y * y;
    let cross = u.0 * w.1 - u.1 * w.0;
    cross < 0.0 && cross * cross > tol2 * norm2(u) * norm2(w)
}

/// The integer whose order is that of [`f64::total_cmp`] (its own definition).
#[inline]
fn total_order_key(x: f64) -> i64 {
    let bits = x.to_bits() as i64;
    bits ^ (((bits >> 63) as u64) >> 1) as i64
}

/// A monotone stand-in for atan2(y, x) ∈ [0, 4) (the "diamond angle"), without trigonometry.
#[inline]
fn diamond_angle(x: f64, y: f64) -> f64 {
    if y >= 0.0 {
        if x >= 0.0 {
            y / (x + y)
        } else {
            1.0 - x / (-x + y)
        }
    } else if x < 0.0 {
        2.0 - y / (-x - y)
    } else {
        3.0 + x / (x - y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    impl WrenchClosureTest {
        /// The r = 2 test as it was before the straddling pair (the oracle): sort the rows by
        /// pseudo-angle, then look for a consecutive pair passing `gap`.
        fn half_plane_sorted(&self) -> bool {
            let n = self.n;
            let null = &self.null[..2 * n];
            let norm2 = |i: usize| null[2 * i] * null[2 * i] + null[2 * i + 1] * null[2 * i + 1];
            let scale2 = (0..n).map(norm2).fold(0.0f64, f64::max);
            let tol2 = STRICT_TOLERANCE * STRICT_TOLERANCE;
            let mut angles = vec![0.0; n];
            for (i, a) in angles.iter_mut().enumerate() {
                if norm2(i) <= tol2 * scale2 {
                    return false;
                }
                *a = diamond_angle(null[2 * i], null[2 * i + 1]);
            }
            let mut order: Vec<usize> = (0..n).collect();
            order.sort_unstable_by(|&a, &b| angles[a].total_cmp(&angles[b]));
            (0..n).any(|k| {
                let (u, w) = (order[k], order[(k + 1) % n]);
                let cross = null[2 * u] * null[2 * w + 1] - null[2 * u + 1] * null[2 * w];
                cross < 0.0 && cross * cross > tol2 * norm2(u) * norm2(w)
            })
        }

        /// The whole decision as before (general reduction, sorted half-plane test).
        fn is_wrench_closure_reference(&mut self, w: &DMatrix<f64>) -> bool {
            let (dof, n) = (self.dof, self.n);
            if w.shape() != (dof, n) || n <= dof || w.as_slice().iter().any(|v| !v.is_finite()) {
                return false;
            }
            match self.reduce_dynamic(w.as_slice()) {
                None => false,
                Some(1) => self.one_dimensional(),
                Some(2) => self.half_plane_sorted(),
                Some(_) => self.linear_programme(w),
            }
        }
    }

    /// Rows of an n × 2 null basis at the angles `angles` (radians) with lengths `lengths`.
    fn rows(angles: &[f64], lengths: &[f64]) -> Vec<f64> {
        angles
            .iter()
            .zip(lengths)
            .flat_map(|(a, l)| [l * a.cos(), l * a.sin()])
            .collect()
    }

    /// How to place n rows of a null basis around a cluster of a given width: its start angle
    /// and, per row, (fraction, kind, exponent).
    #[derive(Debug, Clone)]
    struct Layout {
        start: f64,
        spec: Vec<(f64, u8, i32)>,
    }

    /// Layouts at the boundary of the rule: cluster ends on an axis or anywhere; rows at the
    /// ends (exact ties), at the axes (±0 components), tiny rows near the slack threshold,
    /// lengths that are powers of two (exact ties of the pseudo-angle), rows anywhere inside.
    fn layouts(n: usize) -> impl Strategy<Value = Layout> {
        (
            0.0f64..std::f64::consts::TAU,
            proptest::collection::vec((0.0f64..1.0, 0u8..8, -2i32..3), n),
            0u8..4,
        )
            .prop_map(|(start, spec, quarter)| Layout {
                start: match quarter {
                    0 => 0.0,
                    1 => std::f64::consts::FRAC_PI_2,
                    _ => start,
                },
                spec,
            })
    }

    /// The rows of `layout` for a cluster of width `width` (radians): the first two rows are
    /// its ends.
    fn layout_rows(layout: &Layout, width: f64) -> Vec<f64> {
        let mut angles: Vec<f64> = Vec::with_capacity(layout.spec.len());
        let mut lengths = Vec::with_capacity(layout.spec.len());
        for (k, &(f, kind, e)) in layout.spec.iter().enumerate() {
            let a = match (k, kind) {
                (0, _) => layout.start,
                (1, _) => layout.start + width,
                (_, 0) => angles[0],
                (_, 1) => angles[1],
                (_, 2) => std::f64::consts::FRAC_PI_2 * f64::from(e.rem_euclid(4)),
                _ => layout.start + f * width,
            };
            angles.push(a);
            lengths.push(match kind {
                3 => 1e-9 * (0.5 + f),
                _ => 2f64.powi(e),
            });
        }
        let mut r = rows(&angles, &lengths);
        for (k, &(_, kind, e)) in layout.spec.iter().enumerate() {
            if kind == 2 {
                for v in &mut r[2 * k..2 * k + 2] {
                    if v.abs() < 1e-12 {
                        *v = if e < 0 { -0.0 } else { 0.0 };
                    }
                }
            }
        }
        r
    }

    /// Row sets at and around the boundary: widths π (two antipodal rows), π − δ with δ
    /// around the tolerance 10⁻⁹, and any.
    fn boundary_rows(n: usize) -> impl Strategy<Value = Vec<f64>> {
        let widths = prop_oneof![
            Just(std::f64::consts::PI),
            (-3.0f64..3.0).prop_map(|e| std::f64::consts::PI - 1e-9 * (1.0 + e)),
            (1e-12f64..1e-7).prop_map(|d| std::f64::consts::PI - d),
            (0.0f64..std::f64::consts::PI),
            (std::f64::consts::PI..6.2),
        ];
        (layouts(n), widths).prop_map(|(layout, width)| layout_rows(&layout, width))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// The straddling-pair test gives the sorted test's decision (the same tolerance rule)
        /// on row sets at and around the boundary, with ties and signed zeros, for n = 3…12,
        /// rows in any order.
        #[test]
        fn half_plane_equals_the_sorted_test(
            (n, null, shift) in (3usize..13).prop_flat_map(|n| (Just(n), boundary_rows(n), 0..n))
        ) {
            let mut t = WrenchClosureTest::new(n - 2, n);
            let mut null = null;
            null.rotate_left(2 * shift);
            t.null[..2 * n].copy_from_slice(&null);
            let sorted = t.half_plane_sorted();
            prop_assert_eq!(t.half_plane(), sorted, "{:?}", null);
            // Every row serves as the reference direction (the proof in `straddling_pair_gap`).
            for reference in 0..n {
                let straddling = straddling_pair_gap(n, reference, |i| (null[2 * i], null[2 * i + 1]));
                prop_assert_eq!(straddling, sorted, "reference {}, {:?}", reference, null);
            }
        }

        /// At the exact floating-point boundary of the tolerance rule: the width where the
        /// sorted test flips, found by bisection down to adjacent doubles, and the widths
        /// next to it.
        #[test]
        fn half_plane_equals_the_sorted_test_at_the_flip(
            (n, layout) in (3usize..13).prop_flat_map(|n| (Just(n), layouts(n)))
        ) {
            let mut t = WrenchClosureTest::new(n - 2, n);
            // Row 1 (a cluster end) moved by (dx, dy) ulps.
            let mut decide_nudged = |width: f64, dx: i64, dy: i64| {
                let mut rows = layout_rows(&layout, width);
                let ulps = |v: f64, k: i64| f64::from_bits((v.to_bits() as i64 + k) as u64);
                rows[2] = ulps(rows[2], dx);
                rows[3] = ulps(rows[3], dy);
                t.null[..2 * n].copy_from_slice(&rows);
                let sorted = t.half_plane_sorted();
                // Whether the decision with every row as the reference direction is the sorted one.
                let every_reference = (0..n).all(|k| {
                    straddling_pair_gap(n, k, |i| (rows[2 * i], rows[2 * i + 1])) == sorted
                });
                (t.half_plane(), sorted, every_reference)
            };
            let mut decide = |width: f64| decide_nudged(width, 0, 0);
            let (mut lo, mut hi) = (std::f64::consts::PI - 1e-8, std::f64::consts::PI);
            let (at_lo, at_hi) = (decide(lo).1, decide(hi).1);
            if at_lo != at_hi {
                while f64::from_bits(lo.to_bits() + 1) < hi {
                    let mid = 0.5 * (lo + hi);
                    if decide(mid).1 == at_lo { lo = mid } else { hi = mid }
                }
                for k in 0..4u64 {
                    for width in [f64::from_bits(lo.to_bits() - k), f64::from_bits(hi.to_bits() + k)] {
                        for (dx, dy) in (-3..=3).flat_map(|dx| (-3..=3).map(move |dy| (dx, dy))) {
                            let (new, old, every_reference) = decide_nudged(width, dx, dy);
                            prop_assert_eq!(new, old, "width {:e}, nudge ({}, {})", width, dx, dy);
                            prop_assert!(every_reference, "width {:e}, nudge ({}, {})", width, dx, dy);
                        }
                    }
                }
            }
        }

        /// The whole decision equals the former one on 6 × 8 (and 3 × 5, 2 × 4) wrench
        /// matrices W = M Bᵀ whose null space is spanned by boundary row sets (B an orthonormal
        /// basis of its complement, M random), on random W, and on rank-deficient W.
        #[test]
        fn wrench_closure_equals_the_former_decision(
            (dof, n, null, m, kind) in prop_oneof![Just((6usize, 8usize)), Just((3, 5)), Just((2, 4))]
                .prop_flat_map(|(dof, n)| (
                    Just(dof),
                    Just(n),
                    boundary_rows(n),
                    proptest::collection::vec(-1.0f64..1.0, dof * n),
                    0u8..4,
                ))
        ) {
            let basis = DMatrix::from_row_slice(n, 2, &null);
            let random = DMatrix::from_row_slice(dof, n, &m);
            let w = match kind {
                0 | 1 => {
                    // Complement of span(N): the last n − 2 columns of Q in N = Q R.
                    let q = basis.clone().insert_columns(2, n - 2, 0.0)
                        + DMatrix::from_fn(n, n, |i, j| if j >= 2 && i == j { 1.0 } else { 0.0 });
                    let q = q.qr().q();
                    let b = q.columns(2, n - 2).into_owned();
                    let mm = random.columns(0, dof).into_owned();
                    if kind == 0 { &mm * b.transpose() } else { (&mm * b.transpose()) * 1e3 }
                }
                2 => random,
                _ => {
                    let mut w = random;
                    let r = w.row(0) * -2.0;
                    w.set_row(dof - 1, &r);
                    w
                }
            };
            let mut t = WrenchClosureTest::new(dof, n);
            let new = t.is_wrench_closure(&w);
            prop_assert_eq!(new, t.is_wrench_closure_reference(&w), "{}", w);
        }
    }

    /// [`half_plane_lanes`] on AVX2 registers, for the tests.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn half_plane_lanes_avx2(
        x: &[[f64; LANES]; 8],
        y: &[[f64; LANES]; 8],
    ) -> [[bool; LANES]; 2] {
        // SAFETY: the CPU supports AVX2 (this function's contract).
        let v = unsafe { Avx2::new_unchecked() };
        let (mut vx, mut vy) = ([v.splat(0.0); 8], [v.splat(0.0); 8]);
        for i in 0..8 {
            (vx[i], vy[i]) = (v.load(x[i]), v.load(y[i]));
        }
        let (nan, closure) = half_plane_lanes(&vx, &vy);
        [Avx2::to_bools(nan), Avx2::to_bools(closure)]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// The half-plane test in lanes gives the single-pose `straddling_pair_gap` on any
        /// eight rows, four row sets at a time, at and around the boundary, with ties (equal
        /// angles, lengths apart), signed zeros, tiny rows and NaN coordinates (flagged, not
        /// decided), in the portable and the AVX2 build.
        #[test]
        fn half_plane_in_lanes_equals_one_at_a_time(
            sets in proptest::collection::vec((boundary_rows(8), 0..8usize, 0..64usize), 4)
        ) {
            let mut x = [[0.0; LANES]; 8];
            let mut y = [[0.0; LANES]; 8];
            let mut single = [false; LANES];
            let mut nan = [false; LANES];
            for (l, (rows, shift, poison)) in sets.iter().enumerate() {
                let mut rows = rows.clone();
                rows.rotate_left(2 * shift);
                if *poison < 16 {
                    rows[*poison] = f64::NAN;
                }
                for i in 0..8 {
                    (x[i][l], y[i][l]) = (rows[2 * i], rows[2 * i + 1]);
                }
                single[l] = straddling_pair_gap(8, 0, |i| (rows[2 * i], rows[2 * i + 1]));
                nan[l] = rows.iter().any(|v| v.is_nan());
            }
            let (p_nan, p_closure) = half_plane_lanes(&x.map(Portable), &y.map(Portable));
            let mut builds = vec![[Portable::to_bools(p_nan), Portable::to_bools(p_closure)]];
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2 (just detected).
                builds.push(unsafe { half_plane_lanes_avx2(&x, &y) });
            }
            for [b_nan, b_closure] in builds {
                prop_assert_eq!(b_nan, nan);
                for l in (0..LANES).filter(|&l| !nan[l]) {
                    prop_assert_eq!(b_closure[l], single[l], "lane {}", l);
                }
            }
        }
    }

    /// A 6 × 8 wrench matrix for the four-pose tests: W = M Bᵀ with the null space spanned by
    /// a boundary row set (kinds 0, 1), random (2), rank-deficient (3), entries from a small
    /// set so that partial pivoting meets exact ties (4), or with a non-finite entry (5).
    fn six_eight() -> impl Strategy<Value = DMatrix<f64>> {
        (
            boundary_rows(8),
            proptest::collection::vec(-1.0f64..1.0, 48),
            proptest::collection::vec(0usize..5, 48),
            0u8..6,
        )
            .prop_map(|(null, m, small, kind)| {
                let random = DMatrix::from_row_slice(6, 8, &m);
                match kind {
                    0 | 1 => {
                        let basis = DMatrix::from_row_slice(8, 2, &null);
                        let q = basis.insert_columns(2, 6, 0.0)
                            + DMatrix::from_fn(
                                8,
                                8,
                                |i, j| if j >= 2 && i == j { 1.0 } else { 0.0 },
                            );
                        let b = q.qr().q().columns(2, 6).into_owned();
                        let w = random.columns(0, 6).into_owned() * b.transpose();
                        if kind == 0 { w } else { w * 1e3 }
                    }
                    2 => random,
                    3 => {
                        let mut w = random;
                        let r = w.row(0) * -2.0;
                        w.set_row(5, &r);
                        w
                    }
                    4 => DMatrix::from_iterator(
                        6,
                        8,
                        small.iter().map(|&k| [0.0, 1.0, -1.0, 0.5, -0.0][k]),
                    ),
                    _ => {
                        let mut w = random;
                        w[(small[0], small[1] + 3)] =
                            [f64::NAN, f64::INFINITY, -f64::INFINITY, f64::NAN, 1e308][small[2]];
                        w
                    }
                }
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2048))]

        /// Four poses at a time (`decide_four_6x8`, SIMD across poses) give the single-pose
        /// decisions, in the portable build and in the AVX2 build where the CPU has it, and
        /// undecided lanes are `false`.
        #[test]
        fn four_at_a_time_equals_one_at_a_time(
            ws in proptest::collection::vec(six_eight(), 4),
            wanted in proptest::array::uniform4(prop::bool::weighted(0.9)),
        ) {
            let mut t = WrenchClosureTest::new(6, 8);
            let single: Vec<bool> = ws.iter().map(|w| t.is_wrench_closure(w)).collect();
            let columns: [[Lanes; 6]; 8] =
                std::array::from_fn(|j| std::array::from_fn(|i| std::array::from_fn(|l| ws[l][(i, j)])));
            // The reduction itself, bit for bit: the lanes' flags and null bases against the
            // single-pose `reduce_leading` of each matrix.
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let portable = decide_lanes(Portable([0.0; LANES]), &columns);
            for (l, w) in ws.iter().enumerate() {
                let finite = w.iter().all(|v| v.is_finite());
                prop_assert_eq!(portable.finite[l], finite);
                if !finite {
                    continue;
                }
                let mut a = [[0.0f64; 8]; 6];
                let mut largest = 0.0f64;
                for i in 0..6 {
                    for j in 0..8 {
                        a[i][j] = w[(i, j)];
                        largest = largest.max(w[(i, j)].abs());
                    }
                }
                let leading = t.reduce_leading(&mut a, largest.max(1e-300));
                prop_assert_eq!(portable.leading[l], leading, "lane {}", l);
                if leading {
                    // The null basis bit for bit, then the half-plane test on it: NaN flagged
                    // exactly, and otherwise the single-pose verdict.
                    let mut null = [0.0; 12];
                    for p in 0..6 {
                        null[2 * p] = portable.null[0][p][l];
                        null[2 * p + 1] = portable.null[1][p][l];
                    }
                    prop_assert_eq!(bits(&null), bits(&t.null[..12]), "lane {}", l);
                    t.null[12..16].copy_from_slice(&[1.0, 0.0, 0.0, 1.0]);
                    prop_assert_eq!(portable.nan[l], t.null[..16].iter().any(|v| v.is_nan()));
                    if !portable.nan[l] {
                        prop_assert_eq!(portable.closure[l], t.half_plane(), "lane {}", l);
                    }
                }
            }
            // The AVX2 build gives the portable one's flags, and its bits and verdicts in every
            // lane in the common case (a broken AVX2 build could otherwise hide behind the
            // single-pose fallback; other lanes hold meaningless values, NaNs whose sign may
            // differ).
            let avx2_here = t.avx2;
            #[cfg(target_arch = "x86_64")]
            if avx2_here {
                // SAFETY: the CPU supports AVX2 (run-time detection in `new`).
                let avx = unsafe { decide_lanes_avx2(&columns) };
                prop_assert_eq!(avx.finite, portable.finite);
                prop_assert_eq!(avx.leading, portable.leading);
                for l in (0..LANES).filter(|&l| portable.leading[l]) {
                    let lane = |d: &LaneDecision| {
                        let v: Vec<f64> = d.null.iter().flatten().map(|x| x[l]).collect();
                        bits(&v)
                    };
                    prop_assert_eq!(lane(&avx), lane(&portable), "lane {}", l);
                    prop_assert_eq!(avx.nan[l], portable.nan[l], "lane {}", l);
                    if !portable.nan[l] {
                        prop_assert_eq!(avx.closure[l], portable.closure[l], "lane {}", l);
                    }
                }
            }
            for avx2 in [false, avx2_here] {
                t.avx2 = avx2;
                let four = t.decide_four_6x8(&columns, wanted);
                for l in 0..LANES {
                    prop_assert_eq!(four[l], wanted[l] && single[l], "lane {}, avx2 {}", l, avx2);
                }
            }
        }
    }

    fn mat(rows: usize, cols: usize, v: &[f64]) -> DMatrix<f64> {
        DMatrix::from_row_slice(rows, cols, v)
    }

    #[test]
    fn three_cables_on_a_point_by_hand() {
        // Unit vectors at 0°, 120°, 240°: positively spanning (t = (1, 1, 1) balances).
        let (c, s) = (0.5, 3f64.sqrt() / 2.0);
        let w = mat(2, 3, &[1.0, -c, -c, 0.0, s, -s]);
        let mut t = WrenchClosureTest::new(2, 3);
        assert!(t.is_wrench_closure(&w));
        // All three in the upper half-plane: not.
        let w = mat(2, 3, &[1.0, 0.0, -1.0, 0.1, 1.0, 0.1]);
        assert!(!t.is_wrench_closure(&w));
        // Two opposite cables and one along them: W t = 0 needs t_3 = 0 or rank 1.
        let w = mat(2, 3, &[1.0, -1.0, 1.0, 0.0, 0.0, 0.0]);
        assert!(!t.is_wrench_closure(&w));
    }

    #[test]
    fn four_cables_on_a_point_by_hand() {
        let mut t = WrenchClosureTest::new(2, 4);
        // ±x, ±y: positively spanning.
        let w = mat(2, 4, &[1.0, 0.0, -1.0, 0.0, 0.0, 1.0, 0.0, -1.0]);
        assert!(t.is_wrench_closure(&w));
        // All in the closed upper half-plane (two opposite on its edge): not strictly.
        let w = mat(2, 4, &[1.0, 0.0, -1.0, 0.5, 0.0, 1.0, 0.0, 1.0]);
        assert!(!t.is_wrench_closure(&w));
        // Redundancy 2 but one cable (−y) needed: drop it → upper half-plane + axis: not.
        let w = mat(2, 4, &[1.0, 0.3, -1.0, -0.3, 0.0, 1.0, 0.0, 1.0]);
        assert!(!t.is_wrench_closure(&w));
    }

    /// The fixed-size reduction gives the bits of the general one (null basis and rank
    /// decision) on random matrices of every specialised shape, rank-deficient ones included
    /// (a repeated column pair, a zero row, a row that is a multiple of another).
    #[test]
    fn fixed_size_reduction_equals_the_general_one() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut rank_deficient = 0;
        let avx2_here = WrenchClosureTest::new(6, 8).avx2;
        for (dof, n) in [(6, 8), (6, 7), (3, 5), (3, 4), (2, 4)] {
            let mut t = WrenchClosureTest::new(dof, n);
            for case in 0..400 {
                let mut w = DMatrix::from_fn(dof, n, |_, _| next());
                match case % 4 {
                    1 => w.set_column(1, &w.column(0).clone_owned()),
                    2 => w.row_mut(dof - 1).fill(0.0),
                    3 => {
                        let r = w.row(0) * 3.0;
                        w.set_row(1, &r);
                    }
                    _ => {}
                }
                let general = t.reduce_dynamic(w.as_slice());
                let general_null = t.null.clone();
                rank_deficient += usize::from(general.is_none());
                // The portable build, and the AVX2 build where the CPU has it.
                for avx2 in [false, avx2_here] {
                    t.avx2 = avx2;
                    t.null.iter_mut().for_each(|v| *v = f64::NAN);
                    let fixed = t.reduce(w.as_slice());
                    assert_eq!(fixed, general, "{dof}×{n}, case {case}, avx2 {avx2}");
                    if let Some(r) = general {
                        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                        assert_eq!(bits(&general_null[..n * r]), bits(&t.null[..n * r]));
                    }
                }
            }
        }
        // Zero rows and proportional rows are rank-deficient; repeated columns are not.
        assert!(rank_deficient >= 2 * 5 * 100, "{rank_deficient}");
    }

    #[test]
    fn total_order_key_orders_as_total_cmp() {
        let v = [
            -1.5,
            -0.0,
            0.0,
            1e-300,
            0.25,
            1.0,
            3.999,
            4.0,
            f64::INFINITY,
        ];
        for a in v {
            for b in v {
                assert_eq!(total_order_key(a).cmp(&total_order_key(b)), a.total_cmp(&b));
            }
        }
    }

    #[test]
    fn diamond_angle_is_monotone_in_the_angle() {
        let mut prev = -1.0;
        for k in 0..720 {
            let a = k as f64 * std::f64::consts::TAU / 720.0;
            let d = diamond_angle(a.cos(), a.sin());
            assert!(d > prev && (0.0..4.0).contains(&d), "{a}");
            prev = d;
        }
    }

    #[test]
    fn square_or_wrong_shape_is_never_closure() {
        let mut t = WrenchClosureTest::new(2, 2);
        assert!(!t.is_wrench_closure(&DMatrix::identity(2, 2)));
        let mut t = WrenchClosureTest::new(2, 3);
        assert!(!t.is_wrench_closure(&DMatrix::identity(2, 2)));
        let w = mat(2, 3, &[1.0, f64::NAN, 0.0, 0.0, 1.0, -1.0]);
        assert!(!t.is_wrench_closure(&w));
    }
}

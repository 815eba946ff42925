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
//! the general reduction, hence the same bits.
//!
//! ## References
//! - Gouttefarde & Gosselin (2006), IEEE T-RO 22(3), Theorem 1 (positive spanning).
//! - Pham, Yeo, Yang, Kurbanhusen, Chen, Lin (2006), "Force-closure workspace analysis of
//!   cable-driven parallel mechanisms", Mech. Mach. Theory 41: the null-space test.
//! - CASPR (Lau et al. 2016): the wrench-closure workspace condition.

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

/// `[f64; LANES]` with lane `l` set to the expression: one operation on whole lanes (a loop
/// the compiler turns into SIMD instructions; `if` becomes a blend).
macro_rules! lanes {
    ($l:ident => $e:expr) => {{
        let mut lane = [0.0f64; LANES];
        for $l in 0..LANES {
            lane[$l] = $e;
        }
        lane
    }};
}

/// What [`reduce_leading_lanes`] found for each pose of a group.
struct LaneReduction {
    /// Every entry of W finite.
    finite: [bool; LANES],
    /// The first six columns were the pivot columns (the common case): the null basis is
    /// in the columns 6 and 7 of the reduced rows.
    leading: [bool; LANES],
    /// Position (0–5) of each physical row after the row exchanges of partial pivoting, per
    /// lane (small integers as f64).
    position: [Lanes; 6],
}

impl WrenchClosureTest {
    /// The decisions of four 6 × 8 wrench matrices given as lanes, `columns[j][i][l]` =
    /// W(i, j) of pose l (the layout of `Robot::wrench_matrix_lanes`):
    /// [`WrenchClosureTest::is_wrench_closure_columns`] of each, with the finiteness check,
    /// the scale and the reduction of the common case (leading pivot columns,
    /// [`WrenchClosureTest::reduce_leading`]) computed across the four poses at once. The
    /// reduction performs the operations of the single-pose path on the same values (row
    /// exchanges tracked as positions, not moved), hence the same bits; a pose outside the
    /// common case goes through the single-pose path. Lanes with `wanted[l]` false are not
    /// decided (`false`).
    pub(crate) fn decide_four_6x8(
        &mut self,
        columns: &[[Lanes; 6]; 8],
        wanted: [bool; LANES],
    ) -> [bool; LANES] {
        assert!(self.dof == 6 && self.n == 8, "6 × 8 wrench matrices");
        let mut a = *columns;
        let reduction = match self.avx2 {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU supports AVX2 (checked at run time in `new`).
            true => unsafe { reduce_leading_lanes_avx2(&mut a) },
            _ => reduce_leading_lanes::<false>(&mut a),
        };
        std::array::from_fn(|l| {
            if !(wanted[l] && reduction.finite[l]) {
                false
            } else if reduction.leading[l] {
                // Row p of N is −(row at position p)[6..8]; rows 6, 7 are e_1, e_2. (Built
                // in a local array with rows 6, 7 as constants it ran 1.6 times slower,
                // although in fewer instructions.)
                let null = &mut self.null[..16];
                for (i, position) in reduction.position.iter().enumerate() {
                    // A position is an integer 0–5 (exact in f64).
                    let p = position[l] as u8 as usize;
                    null[2 * p] = -a[6][i][l];
                    null[2 * p + 1] = -a[7][i][l];
                }
                null[12..].copy_from_slice(&[1.0, 0.0, 0.0, 1.0]);
                self.half_plane()
            } else {
                let w: [f64; 48] = std::array::from_fn(|k| columns[k / 6][k % 6][l]);
                self.decide(&w, None).unwrap_or(false)
            }
        })
    }
}

/// [`reduce_leading_lanes`] compiled for AVX2 (no fused multiply–adds, which Rust never
/// forms: the same bits).
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn reduce_leading_lanes_avx2(a: &mut [[Lanes; 6]; 8]) -> LaneReduction {
    reduce_leading_lanes::<true>(a)
}

/// Finiteness, scale and [`WrenchClosureTest::reduce_leading`] of four 6 × 8 matrices, one
/// per lane of `a[column][row]`. Each step does, lane by lane, what the single-pose loop does:
/// partial pivoting picks the first row in position order with the largest |a_ic| (rows
/// keep their place; `position` records the exchanges), the pivot row is scaled by 1/pivot,
/// and every other row with a non-zero entry in the pivot column gets `o −= f · p`. Only the
/// columns right of the pivot are updated: the single-pose loop updates whole rows, but its
/// entries left of the pivot column are never read again. A lane whose pivot falls below the
/// rank tolerance is flagged (`leading` false) and its values are meaningless. `AVX` (only in
/// [`reduce_leading_lanes_avx2`]) makes the selects blend instructions ([`blend`]).
#[inline(always)]
fn reduce_leading_lanes<const AVX: bool>(a: &mut [[Lanes; 6]; 8]) -> LaneReduction {
    // Finiteness (as `decide`) and the largest |w_ij| by comparisons (as `reduce_fixed`).
    let mut finite: Mask = [u64::MAX; LANES];
    let mut largest = [0.0f64; LANES];
    for column in a.iter() {
        for entry in column {
            let v = lanes!(l => entry[l].abs());
            for l in 0..LANES {
                finite[l] &= mask(v[l] < f64::INFINITY);
            }
            let larger: Mask = std::array::from_fn(|l| mask(v[l] > largest[l]));
            largest = blend::<AVX>(larger, v, largest);
        }
    }
    // `largest.max(1e-300)` (largest is finite and ≥ 0 where it matters).
    let tolerance =
        lanes!(l => RANK_TOLERANCE * select(mask(largest[l] < 1e-300), 1e-300, largest[l]));
    let mut position: [Lanes; 6] = std::array::from_fn(|i| [i as f64; LANES]);
    let mut leading = finite;
    // One step per pivot column, each unrolled for its column at compile time.
    pivot_step::<0, AVX>(a, &mut position, &mut leading, &tolerance);
    pivot_step::<1, AVX>(a, &mut position, &mut leading, &tolerance);
    pivot_step::<2, AVX>(a, &mut position, &mut leading, &tolerance);
    pivot_step::<3, AVX>(a, &mut position, &mut leading, &tolerance);
    pivot_step::<4, AVX>(a, &mut position, &mut leading, &tolerance);
    pivot_step::<5, AVX>(a, &mut position, &mut leading, &tolerance);
    LaneReduction {
        finite: finite.map(|m| m != 0),
        leading: leading.map(|m| m != 0),
        position,
    }
}

/// Step `C` of [`reduce_leading_lanes`]: pivot column `C`, lane by lane.
#[inline(always)]
fn pivot_step<const C: usize, const AVX: bool>(
    a: &mut [[Lanes; 6]; 8],
    position: &mut [Lanes; 6],
    leading: &mut Mask,
    tolerance: &Lanes,
) {
    let col = C as f64;
    // Partial pivoting among the rows at positions ≥ C: the largest |a_iC|, the smallest
    // position among equals (the single-pose scan keeps the first, by `>`). Masks are
    // all-ones/all-zeros words combined with bitwise operations, selects are bitwise blends:
    // whole-lane operations without branches.
    let mut best_abs = [0.0f64; LANES];
    let mut best_position = [f64::INFINITY; LANES];
    for (entry, pos) in a[C].iter().zip(position.iter()) {
        let v = lanes!(l => entry[l].abs());
        let take: Mask = std::array::from_fn(|l| {
            mask(pos[l] >= col)
                & (mask(v[l] > best_abs[l])
                    | (mask(v[l] == best_abs[l]) & mask(pos[l] < best_position[l])))
        });
        best_abs = blend::<AVX>(take, v, best_abs);
        best_position = blend::<AVX>(take, *pos, best_position);
    }
    for l in 0..LANES {
        leading[l] &= !mask(best_abs[l] <= tolerance[l]);
    }
    let chosen: [Mask; 6] =
        std::array::from_fn(|i| std::array::from_fn(|l| mask(position[i][l] == best_position[l])));
    // The pivot row, scaled by 1/pivot (columns C..8).
    let mut pivot = [[0.0f64; LANES]; 8];
    for (i, is) in chosen.iter().enumerate() {
        for j in C..8 {
            pivot[j] = blend::<AVX>(*is, a[j][i], pivot[j]);
        }
    }
    let inv = lanes!(l => 1.0 / pivot[C][l]);
    for p in pivot[C + 1..].iter_mut() {
        *p = lanes!(l => p[l] * inv[l]);
    }
    for (i, is) in chosen.iter().enumerate() {
        let f = a[C][i];
        let eliminate: Mask = std::array::from_fn(|l| mask(f[l] != 0.0));
        for j in C + 1..8 {
            let e = a[j][i];
            let reduced = lanes!(l => e[l] - f[l] * pivot[j][l]);
            let other = blend::<AVX>(eliminate, reduced, e);
            a[j][i] = blend::<AVX>(*is, pivot[j], other);
        }
    }
    // Exchange positions C and that of the pivot row.
    for (pos, is) in position.iter_mut().zip(&chosen) {
        let at_col: Mask = std::array::from_fn(|l| mask(pos[l] == col));
        let other = blend::<AVX>(at_col, best_position, *pos);
        *pos = blend::<AVX>(*is, [col; LANES], other);
    }
}

/// One all-ones (true) or all-zeros (false) word per lane.
type Mask = [u64; LANES];

/// The all-ones word for `true`, zero for `false`.
#[inline(always)]
fn mask(b: bool) -> u64 {
    0u64.wrapping_sub(u64::from(b))
}

/// [`select`] lane by lane. With `AVX` one `vblendvpd` (the compiler turns the bitwise
/// form into three instructions): the same bits, a select is exact.
#[inline(always)]
fn blend<const AVX: bool>(m: Mask, a: Lanes, b: Lanes) -> Lanes {
    #[cfg(target_arch = "x86_64")]
    if AVX {
        use std::arch::x86_64::{__m256d, _mm256_blendv_pd};
        use std::mem::transmute;
        // SAFETY: `AVX` is true only in `reduce_leading_lanes_avx2`, which runs on CPUs with
        // AVX2 (run-time detection in `WrenchClosureTest::new`); the transmutes are between
        // 32-byte plain-data types. `blendv` takes `a` where the sign bit of `m` is set, and
        // every lane of `m` is all ones or all zeros.
        return unsafe {
            transmute::<__m256d, Lanes>(_mm256_blendv_pd(
                transmute::<Lanes, __m256d>(b),
                transmute::<Lanes, __m256d>(a),
                transmute::<Mask, __m256d>(m),
            ))
        };
    }
    lanes!(l => select(m[l], a[l], b[l]))
}

/// `a` where `m` is all ones, `b` where it is zero, by bits.
#[inline(always)]
fn select(m: u64, a: f64, b: f64) -> f64 {
    f64::from_bits((m & a.to_bits()) | (!m & b.to_bits()))
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
            let mut lanes_a = columns;
            let reduction = reduce_leading_lanes::<false>(&mut lanes_a);
            for (l, w) in ws.iter().enumerate() {
                let finite = w.iter().all(|v| v.is_finite());
                prop_assert_eq!(reduction.finite[l], finite);
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
                prop_assert_eq!(reduction.leading[l], leading, "lane {}", l);
                if leading {
                    let mut null = [0.0; 12];
                    for (i, position) in reduction.position.iter().enumerate() {
                        let p = position[l] as usize;
                        null[2 * p] = -lanes_a[6][i][l];
                        null[2 * p + 1] = -lanes_a[7][i][l];
                    }
                    prop_assert_eq!(bits(&null), bits(&t.null[..12]), "lane {}", l);
                }
            }
            // The AVX2 build of the reduction gives the portable one's flags, and its bits in
            // every lane in the common case (a broken AVX2 reduction could otherwise hide
            // behind the single-pose fallback; other lanes hold meaningless values, NaNs whose
            // sign may differ).
            let avx2_here = t.avx2;
            #[cfg(target_arch = "x86_64")]
            if avx2_here {
                let mut lanes_b = columns;
                // SAFETY: the CPU supports AVX2 (run-time detection in `new`).
                let avx = unsafe { reduce_leading_lanes_avx2(&mut lanes_b) };
                prop_assert_eq!(avx.finite, reduction.finite);
                prop_assert_eq!(avx.leading, reduction.leading);
                let lane = |m: &[[Lanes; 6]; 8], p: &[Lanes; 6], l: usize| {
                    let v: Vec<f64> = m.iter().flatten().chain(p).map(|x| x[l]).collect();
                    bits(&v)
                };
                for l in (0..LANES).filter(|&l| reduction.leading[l]) {
                    prop_assert_eq!(
                        lane(&lanes_b, &avx.position, l),
                        lane(&lanes_a, &reduction.position, l),
                        "lane {}", l
                    );
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

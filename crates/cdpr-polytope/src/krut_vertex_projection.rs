//! # Krut's vertex projection method (operational force polytope)
//!
//! Krut, Company & Pierrot 2004, §III computes the operational force polytope {W t : t_min ≤ t ≤ t_max} (W = Jₘᵀ) by
//! projecting the 2ⁿ vertices of the tension box onto the range of W and keeping, among all
//! hyperplanes through DOF projected vertices, those with every projected vertex on one side
//! (here n is the number of cables and DOF the wrench-space dimension; the paper writes m for the
//! motors and n for the DOF):
//!
//! 1. SVD W = U [S 0] Vᵀ and the 2ⁿ box vertices τ_vertex of the box (3). The paper's text breaks
//!    off before Step 1 (its eqs. (4)–(7) are missing); this step is reconstructed from Steps 2–3,
//!    which name "the SVD joint base" V and the factors U, S;
//! 2. τ_s = Vᵀ τ_vertex, eq. (8);
//! 3. τ_r = P τ_s, the first DOF components, eq. (9);
//! 4. for each of the C(2ⁿ, DOF) choices of DOF projected vertices, the hyperplane through them,
//!    eqs. (10)–(14);
//! 5. border test (15): all projected vertices on one side (type 1: τ_rᵀ u_k ≤ 1, type 2: ≥ 1);
//!    a type-2 border means the origin is outside the polytope (the pose cannot balance a null
//!    perturbation);
//! 6. mapping to the operational space, eqs. (17)–(18): f = U S τ_r, so a border a · τ_r ≤ b
//!    becomes (U S⁻¹ a) · f ≤ b. The facet's unit normal is U S⁻¹ a / ‖S⁻¹ a‖ and its signed
//!    distance from the origin the term of eq. (19) (1/‖v_k‖ for a type-1 border, v_k = S⁻¹ u_k).
//!
//! **Numerics.** Eq. (14) writes the hyperplane as τ_rᵀ u_k = 1, u_k = T_k⁻¹ [1 … 1]ᵀ, which
//! fails for a hyperplane through the origin (the paper's second situation, T_k singular: the
//! origin on the polytope's boundary) and loses every digit when the polytope is far from the
//! origin compared with its size (T_k nearly singular). We compute the same hyperplanes in a
//! translation-invariant form, and every quantity from the box's *generators*
//! g_j = P Vᵀ e_j (t_max,j − t_min,j) = S⁻¹ Uᵀ w_j (t_max,j − t_min,j) (the second form, from W's
//! columns: the small entries of a computed V carry round-off of order ε·s₁/s_DOF):
//! - the normal a of the plane through the chosen vertices τ_r,0 … τ_r,DOF−1 is orthogonal to
//!   their differences, each formed as Σ ± g_j over the bits in which the vertices differ
//!   (Gaussian elimination with complete pivoting on the normalised differences; a difference
//!   that cancels to round-off, as for antiparallel cables, means coincident vertices); b =
//!   a · τ_r,0, and when b ≠ 0, u_k = a / b is the paper's u_k. A thin facet (spanned by a
//!   generator 10⁻¹¹ times shorter than the others) keeps its precision;
//! - the border test (15) compares a · τ_r,v with a · τ_r,0 for every vertex v through the
//!   generators (Σ ± a · g_j over the differing bits), with a tolerance of 10⁻⁹ times that
//!   path's length Σ ‖g_j‖: it depends neither on the distance of the polytope from the origin
//!   nor on how the generators' lengths compare (a tolerance relative to the polytope's size
//!   accepts planes cutting through its thin directions);
//! - a border must contain DOF − 1 independent generators (a facet of the image of a box is
//!   spanned by box edges; a plane tilted about an edge by a tiny generator difference can pass
//!   the border test within round-off while touching only that edge), and its normal is then
//!   recomputed from those generators, more precisely than from the vertex differences.
//!
//! A cable with t_min = t_max or a zero column is a zero generator: it translates the polytope
//! and doubles each projected vertex, so the vertices are enumerated over the other cables only.
//!
//! The result is stored with unit normals and *signed* offsets (a type-2 border gets normal
//! −U S⁻¹ a and offset −b, normalised), exactly as [`crate::hyperplane_shifting`] produces it.
//!
//! [`candidate_hyperplanes`] lists every candidate of step 4 with its border test (15), mapped
//! to the wrench space (Krut, Company & Pierrot 2004, Fig. 8); it and [`available_wrench_set`] share one enumeration.
//!
//! The cost is C(2ⁿ, DOF) small solves each followed by a 2ⁿ-point border test: the method is
//! refused for n > 10 or more than 10⁸ candidates ([`PolytopeError::TooLarge`]; e.g. 6 DOF with
//! 6 cables has 7.5·10⁷ candidates and takes about a minute). Use hyperplane shifting beyond that.
//!
//! ## References
//! - S. Krut, O. Company, F. Pierrot, *Force performance indexes for parallel mechanisms with
//!   actuation redundancy, especially for parallel wire-driven manipulators*, IROS 2004 (Krut, Company & Pierrot 2004),
//!   §III steps 1–6, eqs. (3), (8)–(18).

use crate::PolytopeError;
use crate::available_wrench_set::{AvailableWrenchSet, Facet, binomial, next_combination};
use crate::input::{self, MAX_DOF};
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, DVector};

/// Largest cable count accepted (2ⁿ box vertices).
pub const MAX_CABLES: usize = 10;
/// Largest number C(2ⁿ, DOF) of candidate hyperplanes accepted.
pub const MAX_CANDIDATES: f64 = 1e8;

/// Relative pivot (on unit difference rows) below which DOF projected vertices count as
/// affinely dependent.
const PIVOT_TOL: f64 = 1e-10;
/// Relative length below which a difference of generator sums counts as zero (cancellation).
const COINCIDENT_TOL: f64 = 1e-10;
/// Border-test tolerance: a vertex may be off the plane by this fraction of its path length
/// from the first chosen vertex along the generators (an angle, so thin and wide generators are
/// judged alike).
const BORDER_TOL: f64 = 1e-9;

type Vec6 = [f64; MAX_DOF];

/// Available wrench set {W t : t_min ≤ t ≤ t_max} by Krut's steps 1–6 (unit normals, signed
/// offsets, duplicates merged, vertices for DOF 2 and 3).
///
/// Needs finite t_max, rank(W) = DOF, n ≤ [`MAX_CABLES`]; a polytope with an empty interior (e.g. a
/// zero-width tension box) is [`PolytopeError::LowerDimensional`].
///
/// ```
/// use cdpr_polytope::krut_vertex_projection::available_wrench_set;
/// use cdpr_tension::TensionBounds;
/// use nalgebra::dmatrix;
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
/// assert_eq!(aws.facets().len(), 4); // the square [−9, 9]²
/// assert_eq!(aws.vertices().unwrap().len(), 4);
/// ```
pub fn available_wrench_set(
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
) -> Result<AvailableWrenchSet, PolytopeError> {
    input::check(w, bounds)?;
    // Extreme scales (|W| or |t| beyond 2^±64) are brought near 1 by powers of two, which are
    // exact: AWS(k_w W, k_t t) = k_w k_t · AWS(W, t). The tolerances of steps 1–6 are relative,
    // but products of tiny or huge numbers underflow or overflow (issue 13: W = s·W₀ with
    // s = 10²⁰⁰ or 10⁻¹⁶⁰ gave no facets and an isotropic force of +∞).
    let kw = power_of_two_scale(w.amax());
    let kt = power_of_two_scale(
        bounds
            .min()
            .iter()
            .chain(bounds.max().iter())
            .fold(0.0f64, |a, &b| a.max(b.abs())),
    );
    if kw == 1.0 && kt == 1.0 {
        return available_wrench_set_unscaled(w, bounds);
    }
    let ws = w * kw;
    let bs = TensionBounds::new(
        (bounds.min() * kt).as_slice().to_vec(),
        (bounds.max() * kt).as_slice().to_vec(),
    )
    .map_err(|e| PolytopeError::SolverFailure {
        detail: format!("rescaled tension bounds: {e}"),
    })?;
    available_wrench_set_unscaled(&ws, &bs)?.rescaled(1.0 / kw, 1.0 / kt)
}

/// 2^−e with 2^e the power of two nearest to `magnitude`, when `magnitude` lies outside
/// [2⁻⁶⁴, 2⁶⁴]; 1 otherwise (and for 0).
fn power_of_two_scale(magnitude: f64) -> f64 {
    if magnitude > 0.0
        && magnitude.is_finite()
        && !(2f64.powi(-64)..=2f64.powi(64)).contains(&magnitude)
    {
        2f64.powi(-(magnitude.log2().round() as i32))
    } else {
        1.0
    }
}

/// Steps 1–6 on data of moderate scale.
fn available_wrench_set_unscaled(
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
) -> Result<AvailableWrenchSet, PolytopeError> {
    let p = ProjectedBox::new(w, bounds, MAX_CANDIDATES)?;
    let mut borders: Vec<(Vec6, usize)> = Vec::new(); // (outward a, a vertex on the border)
    p.for_each_candidate(|idx, verdict| {
        if let Verdict::Border(a) = verdict {
            borders.push((a, idx[0]));
        }
    });
    let raw: Vec<Facet> = borders
        .iter()
        .filter_map(|(a, v)| p.operational(a, *v))
        .collect();
    if raw.is_empty() {
        // A full-dimensional bounded polytope has facets: none found is a numerical failure,
        // never an AWS without facets (whose isotropic force would be +∞).
        return Err(PolytopeError::SolverFailure {
            detail: "Krut's vertex projection found no border hyperplane".into(),
        });
    }
    Ok(AvailableWrenchSet::from_halfspaces(
        p.dof(),
        raw,
        true,
        p.scale,
    ))
}

/// Largest number of candidates [`candidate_hyperplanes`] lists (each is a small allocation).
pub const MAX_LISTED_CANDIDATES: f64 = 1e6;

/// One of the C(2ⁿ, DOF) choices of DOF box vertices of step 4 (Krut, Company & Pierrot 2004, Fig. 8 draws them for
/// n = 3, DOF = 2: the 28 lines through pairs of the 8 projected vertices).
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// The chosen box vertices, increasing, each a bit pattern over the cables: bit j set means
    /// t_j = t_max,j, clear t_min,j (a cable whose tension cannot vary, or whose column of W is
    /// zero, is always clear: see [`candidate_hyperplanes`]).
    pub vertices: Vec<usize>,
    /// The hyperplane `normal · f = offset` through their images f = W τ in the wrench space
    /// (unit normal, offset the signed distance from the origin), eqs. (10)–(14) mapped by
    /// eqs. (17)–(18); `None` when the images are affinely dependent (for DOF = 2: they
    /// coincide), so that system (12) determines no hyperplane.
    pub hyperplane: Option<Facet>,
    /// Whether the hyperplane passes the border test (15), i.e. is a facet of the available
    /// wrench set, its normal then pointing outward (for a non-border the orientation is
    /// arbitrary). A hyperplane that passes (15) only within round-off while touching a
    /// lower-dimensional face (it contains fewer than DOF − 1 independent box edges) is not a
    /// border (module docs).
    pub border: bool,
}

/// Every candidate hyperplane of Krut's step 4 and its border test (15), in the order the
/// method enumerates them (lexicographic in the vertex indices), for plotting and teaching
/// (Krut, Company & Pierrot 2004, Fig. 8). The borders are exactly the supporting half-spaces
/// [`available_wrench_set`] builds (same code path), before duplicates are merged.
///
/// Unlike the paper's u_k of eq. (14), a hyperplane through the origin (T_k singular, the
/// images aligned with O) is found like any other. As in [`available_wrench_set`], a cable with
/// t_min = t_max or a zero column only translates the polytope: the enumeration runs over the
/// 2^n' vertices of the other n' cables (the paper's C(2ⁿ, DOF) choices would add choices of
/// coinciding images, which give no hyperplane). Same errors as [`available_wrench_set`], and
/// [`PolytopeError::TooLarge`] beyond [`MAX_LISTED_CANDIDATES`] candidates.
///
/// ```
/// use cdpr_polytope::krut_vertex_projection::candidate_hyperplanes;
/// use cdpr_tension::TensionBounds;
/// use nalgebra::dmatrix;
/// // The unit square {t : 0 ≤ t ≤ 1}: 4 vertices, C(4, 2) = 6 lines, 4 of them sides.
/// let w = dmatrix![1.0, 0.0; 0.0, 1.0];
/// let c = candidate_hyperplanes(&w, &TensionBounds::uniform(2, 0.0, 1.0).unwrap()).unwrap();
/// assert_eq!(c.len(), 6);
/// assert_eq!(c.iter().filter(|c| c.border).count(), 4);
/// assert_eq!(c[2].vertices, [0, 3]); // the diagonal from (0, 0) to (1, 1): not a side
/// assert!(!c[2].border);
/// ```
pub fn candidate_hyperplanes(
    w: &DMatrix<f64>,
    bounds: &TensionBounds,
) -> Result<Vec<Candidate>, PolytopeError> {
    let p = ProjectedBox::new(w, bounds, MAX_LISTED_CANDIDATES)?;
    let mut out = Vec::new();
    p.for_each_candidate(|idx, verdict| {
        let (a, border) = match verdict {
            Verdict::Dependent => (None, false),
            Verdict::Plane(a) => (Some(a), false),
            Verdict::Border(a) => (Some(a), true),
        };
        let hyperplane = a.and_then(|a| p.operational(&a, idx[0]));
        out.push(Candidate {
            vertices: idx.iter().map(|&v| p.cable_bits(v)).collect(),
            border: border && hyperplane.is_some(),
            hyperplane,
        });
    });
    Ok(out)
}

/// What steps 4–5 make of one choice of DOF projected vertices.
enum Verdict {
    /// The vertices are affinely dependent (e.g. two coincide): no hyperplane.
    Dependent,
    /// The unit normal a (in τ_r coordinates, orientation arbitrary) of a hyperplane that fails
    /// the border test (15).
    Plane(Vec6),
    /// The refined unit normal a of a border, oriented outward: every projected vertex has
    /// a · τ_r ≤ a · τ_r,v₀ (a type-2 border is flipped).
    Border(Vec6),
}

/// Steps 1–3 (eqs. (3), (8), (9)): the tension box projected on the range of W, as the
/// projected generators g_j of the cables whose tension can vary.
struct ProjectedBox<'a> {
    w: &'a DMatrix<f64>,
    bounds: &'a TensionBounds,
    /// The cables whose tension can vary and whose column is not zero.
    varying: Vec<usize>,
    /// g_j = S⁻¹ Uᵀ w_j (t_max,j − t_min,j) for the varying cables.
    g: Vec<Vec6>,
    g_norm: Vec<f64>,
    /// The SVD factors U (DOF × DOF) and S of W.
    u: DMatrix<f64>,
    s: DVector<f64>,
    /// max|W_ij|·max|t| (tolerances of the resulting set).
    scale: f64,
}

impl<'a> ProjectedBox<'a> {
    /// Checks the input and computes the generators; [`PolytopeError::TooLarge`] beyond
    /// [`MAX_CABLES`] varying cables or `max_candidates` candidates.
    fn new(
        w: &'a DMatrix<f64>,
        bounds: &'a TensionBounds,
        max_candidates: f64,
    ) -> Result<Self, PolytopeError> {
        let (scale, _) = input::check(w, bounds)?;
        let (dof, n) = w.shape();
        if let Some(j) = bounds.max().iter().position(|x| !x.is_finite()) {
            return Err(PolytopeError::UnboundedTension {
                cable: j,
                what: "Krut's vertex projection",
            });
        }
        let (tmin, tmax) = (bounds.min(), bounds.max());
        // Cables whose tension can vary and whose column is not zero: the box's generators.
        let varying: Vec<usize> = (0..n)
            .filter(|&j| tmax[j] > tmin[j] && w.column(j).iter().any(|&x| x != 0.0))
            .collect();
        let nv = varying.len();
        let candidates = if nv <= 30 {
            binomial((1u64 << nv) as f64, dof)
        } else {
            f64::INFINITY
        };
        if nv > MAX_CABLES || candidates > max_candidates {
            return Err(PolytopeError::TooLarge {
                method: "Krut's vertex projection",
                cables: n,
                dof,
                candidates,
                max_cables: MAX_CABLES,
                max_candidates,
            });
        }
        // The generators must span the wrench space, or the polytope has an empty interior
        // (e.g. a zero-width tension box): checked on their unit directions, so that a tiny
        // generator still counts.
        let directions = DMatrix::from_fn(dof, nv, |i, c| {
            let col = w.column(varying[c]);
            col[i] / col.amax()
        });
        if nv < dof || input::numerical_rank(&directions) < dof {
            return Err(PolytopeError::LowerDimensional {
                rank: input::numerical_rank(&directions).min(input::numerical_rank(w)),
                dof,
            });
        }

        // Step 1: SVD W = U Σ Vᵀ (thin: U DOF × DOF; Vᵀ is used through S⁻¹ Uᵀ W, below).
        let svd = w.clone().svd(true, false);
        let Some(u) = svd.u else {
            return Err(PolytopeError::SolverFailure {
                detail: "SVD of W did not converge".into(),
            });
        };
        let s = svd.singular_values;
        let smax = s.max();
        if smax <= 0.0 || s.iter().any(|&x| x <= 1e-10 * smax) {
            return Err(PolytopeError::LowerDimensional {
                rank: s.iter().filter(|&&x| x > 1e-10 * smax).count(),
                dof,
            });
        }
        // Steps 1–3 (eqs. (3), (8), (9)), in generator form: the box vertex with bits v is
        // τ = t_min + Σ_{j ∈ v} e_j (t_max,j − t_min,j), so τ_r = P Vᵀ t_min + Σ_{j ∈ v} g_j with
        // g_j = P Vᵀ e_j (t_max,j − t_min,j). The first DOF rows of Vᵀ equal S⁻¹ Uᵀ W; g_j is
        // formed that way, from the column w_j, because the computed V of an ill-conditioned W
        // carries round-off of order ε·s₁/s_DOF in its small entries (a fuzzed W with condition
        // 1.5·10⁷ turned facet normals by 10⁻⁴).
        let mut g: Vec<Vec6> = vec![[0.0; MAX_DOF]; nv];
        for (c, &j) in varying.iter().enumerate() {
            let uw = u.tr_mul(&w.column(j)); // Uᵀ w_j
            for i in 0..dof {
                g[c][i] = uw[i] / s[i] * (tmax[j] - tmin[j]);
            }
        }
        let g_norm = g.iter().map(norm).collect();
        Ok(Self {
            w,
            bounds,
            varying,
            g,
            g_norm,
            u,
            s,
            scale,
        })
    }

    fn dof(&self) -> usize {
        self.w.nrows()
    }

    /// The bit pattern over all cables of projected vertex `v` (bits over the varying cables).
    fn cable_bits(&self, v: usize) -> usize {
        self.varying
            .iter()
            .enumerate()
            .filter(|&(c, _)| v >> c & 1 == 1)
            .fold(0, |bits, (_, &j)| bits | 1 << j)
    }

    /// Steps 4–5: calls `visit` with each of the C(2^n', DOF) choices of DOF projected vertices
    /// (bit patterns over the varying cables, increasing) and the hyperplane through them,
    /// eqs. (10)–(14), judged by the border test (15). Allocates only its two 2^n' buffers.
    fn for_each_candidate(&self, mut visit: impl FnMut(&[usize], Verdict)) {
        let (g, g_norm, dof) = (&self.g, &self.g_norm, self.dof());
        let vertex_count = 1usize << g.len();
        // path[m] = Σ_{j ∈ m} ‖g_j‖: the length of the way from a vertex v₀ to v₀ xor m along
        // the generators, the scale of the round-off in that vertex's height.
        let mut path = vec![0.0f64; vertex_count];
        for m in 1..vertex_count {
            path[m] = path[m & (m - 1)] + g_norm[m.trailing_zeros() as usize];
        }
        let mut height = vec![0.0f64; vertex_count]; // a · (τ_r,(v₀ xor m) − τ_r,v₀)
        let mut q = [0.0f64; MAX_CABLES]; // the height gained by flipping bit j of v₀
        let q = &mut q[..g.len()];
        let mut idx = [0usize; MAX_DOF];
        let idx = &mut idx[..dof];
        for (k, i) in idx.iter_mut().enumerate() {
            *i = k;
        }
        loop {
            let verdict = match candidate_normal(g, g_norm, idx, dof) {
                None => Verdict::Dependent,
                Some(a) => {
                    let v0 = idx[0];
                    for (j, (qj, gj)) in q.iter_mut().zip(g).enumerate() {
                        let p = dot(&a, gj, dof);
                        *qj = if v0 >> j & 1 == 1 { -p } else { p };
                    }
                    // Every vertex is v₀ xor m; its height relative to v₀ is a subset sum of q,
                    // built in increasing order of m (m extends m without its lowest bit), with
                    // an early exit. A vertex counts as on the plane within BORDER_TOL times its
                    // path length from v₀.
                    let (mut type1, mut type2) = (true, true);
                    for m in 1..vertex_count {
                        let x = height[m & (m - 1)] + q[m.trailing_zeros() as usize];
                        height[m] = x;
                        let tol = BORDER_TOL * path[m];
                        type1 &= x <= tol;
                        type2 &= x >= -tol;
                        if !type1 && !type2 {
                            break;
                        }
                    }
                    // A facet of the image of the box is spanned by DOF − 1 independent
                    // generators lying in it; a plane that only touches an edge can pass the
                    // border test within round-off (vertices v₀ xor m whose generator heights
                    // cancel), so require it. The normal is then recomputed from those
                    // generators, which is more precise than from the differences of the chosen
                    // vertices.
                    match (type1 != type2)
                        .then(|| facet_normal(g, g_norm, q, &a, dof))
                        .flatten()
                    {
                        // The origin test of the paper's type 2: stored as (−a) · τ_r ≤ −b.
                        Some(n) if type2 => Verdict::Border(n.map(|x| -x)),
                        Some(n) => Verdict::Border(n),
                        None => Verdict::Plane(a),
                    }
                }
            };
            visit(idx, verdict);
            if !next_combination(idx, vertex_count) {
                break;
            }
        }
    }

    /// Step 6: f = U S τ_r (eq. (17)), so a · τ_r ≤ b ⇔ (U S⁻¹ a) · f ≤ b, eq. (18): the
    /// hyperplane with τ_r-normal `a` through projected vertex `v` in the wrench space, with unit
    /// normal U S⁻¹ a / ‖S⁻¹ a‖ and as offset the image f_v = W τ_v of its vertex on that
    /// normal. `None` if the normal is not finite.
    fn operational(&self, a: &Vec6, v: usize) -> Option<Facet> {
        let dof = self.dof();
        let sa = DVector::from_fn(dof, |i, _| a[i] / self.s[i]); // v_k = S⁻¹ u_k up to scale
        let gdir = &self.u * sa;
        let len = gdir.norm();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        let normal = gdir / len;
        let bits = self.cable_bits(v);
        let (tmin, tmax) = (self.bounds.min(), self.bounds.max());
        let tau = DVector::from_fn(self.w.ncols(), |j, _| {
            if bits >> j & 1 == 1 { tmax[j] } else { tmin[j] }
        });
        let offset = normal.dot(&(self.w * tau));
        Some(Facet { normal, offset })
    }
}

/// Eqs. (12)–(14) in translation-invariant form: the unit normal of the hyperplane through the
/// projected vertices `idx` (bit patterns over the generators), orthogonal to their differences
/// δ_i − δ_0 = Σ_j (v_i,j − v_0,j) g_j. `None` if the vertices are affinely dependent.
fn candidate_normal(g: &[Vec6], g_norm: &[f64], idx: &[usize], dof: usize) -> Option<Vec6> {
    let k = dof - 1;
    let mut rows = [[0.0f64; MAX_DOF]; MAX_DOF];
    for r in 0..k {
        let (vi, v0) = (idx[r + 1], idx[0]);
        let row = &mut rows[r];
        let mut mass = 0.0;
        // Over the bits in which the two vertices differ, in increasing order.
        let mut diff = vi ^ v0;
        while diff != 0 {
            let j = diff.trailing_zeros() as usize;
            diff &= diff - 1;
            let coef = if vi >> j & 1 == 1 { 1.0 } else { -1.0 };
            mass += g_norm[j];
            for c in 0..dof {
                row[c] += coef * g[j][c];
            }
        }
        // Two chosen vertices coincide, exactly or up to the round-off of their generators
        // (antiparallel cables: g_a + g_b ≈ 0): the difference has no direction.
        let len = norm(row);
        if !(len > COINCIDENT_TOL * mass && len.is_finite()) {
            return None;
        }
        for x in row.iter_mut() {
            *x /= len;
        }
    }
    orthogonal_complement(&mut rows[..k], dof)
}

/// The refined normal of a border: the generators lying in the candidate plane (height |q_j|
/// within [`BORDER_TOL`] of their length) must span DOF − 1 dimensions, and the unit vector
/// orthogonal to them, oriented like `a`, is returned. `None` if they span less: the plane only
/// touches a lower-dimensional face (an edge, say) within round-off.
fn facet_normal(g: &[Vec6], g_norm: &[f64], q: &[f64], a: &Vec6, dof: usize) -> Option<Vec6> {
    let mut rows = [[0.0f64; MAX_DOF]; MAX_CABLES];
    let mut count = 0;
    for ((gj, &len), &qj) in g.iter().zip(g_norm).zip(q) {
        if qj.abs() <= BORDER_TOL * len {
            for c in 0..dof {
                rows[count][c] = gj[c] / len;
            }
            count += 1;
        }
    }
    let mut n = orthogonal_complement(&mut rows[..count], dof)?;
    if dot(&n, a, dof) < 0.0 {
        for x in n.iter_mut() {
            *x = -*x;
        }
    }
    Some(n)
}

/// The unit vector orthogonal to the first dof − 1 independent directions among unit `rows`,
/// by Gaussian elimination with complete pivoting stopped after dof − 1 pivots (pivots below
/// [`PIVOT_TOL`] end it earlier); `None` if the rows span fewer than dof − 1 dimensions.
///
/// Rows beyond the dof − 1 pivots are not tested: [`facet_normal`] passes generators already
/// known to lie in one plane to 10⁻⁹, and a tiny generator's direction can be off that plane by
/// more than [`PIVOT_TOL`] from round-off alone (its component along a thin singular direction
/// of W cancels; fuzz finding `thin_facet_among_generators_of_very_different_sizes`).
fn orthogonal_complement(rows: &mut [Vec6], dof: usize) -> Option<Vec6> {
    let k = dof - 1;
    let mut piv = [0usize; MAX_DOF];
    let mut used = [false; MAX_DOF];
    let mut rank = 0;
    while rank < rows.len().min(k) {
        let (mut bi, mut bj, mut best) = (rank, 0, -1.0f64);
        for (i, row) in rows.iter().enumerate().skip(rank) {
            for (j, &x) in row.iter().enumerate().take(dof) {
                if !used[j] && x.abs() > best {
                    (bi, bj, best) = (i, j, x.abs());
                }
            }
        }
        // Written so that a NaN pivot also ends the elimination.
        if best.partial_cmp(&PIVOT_TOL) != Some(std::cmp::Ordering::Greater) {
            break;
        }
        rows.swap(rank, bi);
        used[bj] = true;
        piv[rank] = bj;
        let pivot_row = rows[rank];
        for row in rows.iter_mut().skip(rank + 1) {
            let f = row[bj] / pivot_row[bj];
            for c in 0..dof {
                row[c] -= f * pivot_row[c];
            }
            row[bj] = 0.0;
        }
        rank += 1;
    }
    if rank != k {
        return None;
    }
    // The one column never pivoted is free: set it to 1 and back-substitute.
    let mut x = [0.0f64; MAX_DOF];
    x[(0..dof).find(|&j| !used[j])?] = 1.0;
    for step in (0..k).rev() {
        let row = &rows[step];
        let sum: f64 = (0..dof).map(|c| row[c] * x[c]).sum();
        x[piv[step]] = -sum / row[piv[step]];
    }
    let len = norm(&x);
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    for v in x.iter_mut() {
        *v /= len;
    }
    Some(x)
}

fn dot(a: &Vec6, b: &Vec6, dof: usize) -> f64 {
    (0..dof).map(|i| a[i] * b[i]).sum()
}

fn norm(a: &Vec6) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::dmatrix;

    /// `normal · p = offset` for each point, within 1e-12 of the offset's scale.
    fn passes_through(f: &Facet, points: &[[f64; 2]]) -> bool {
        points
            .iter()
            .all(|p| (f.normal[0] * p[0] + f.normal[1] * p[1] - f.offset).abs() < 1e-12)
    }

    /// W = I₂, t ∈ [0, 1]²: the 4 vertices (0, 0), (1, 0), (0, 1), (1, 1) (bits 0–3) give
    /// C(4, 2) = 6 lines, the 4 sides of the unit square (borders, outward normals) and the two
    /// diagonals; three of them pass through the origin, where the paper's eq. (14) has no u_k.
    #[test]
    fn unit_square_candidates_by_hand() {
        let w = dmatrix![1.0, 0.0; 0.0, 1.0];
        let c = candidate_hyperplanes(&w, &TensionBounds::uniform(2, 0.0, 1.0).unwrap()).unwrap();
        let pairs: Vec<Vec<usize>> = c.iter().map(|c| c.vertices.clone()).collect();
        let expected = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];
        assert_eq!(pairs, expected.map(Vec::from));
        let point = |v: usize| [(v & 1) as f64, (v >> 1 & 1) as f64];
        // (border, outward normal and offset of a border, or a normal ± and |offset|).
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let hand: [(bool, [f64; 2], f64); 6] = [
            (true, [0.0, -1.0], 0.0), // y = 0
            (true, [-1.0, 0.0], 0.0), // x = 0
            (false, [s, -s], 0.0),    // the diagonal y = x, through the origin
            (false, [s, s], s),       // the diagonal x + y = 1
            (true, [1.0, 0.0], 1.0),  // x = 1
            (true, [0.0, 1.0], 1.0),  // y = 1
        ];
        for (cand, (border, n, d)) in c.iter().zip(hand) {
            let f = cand
                .hyperplane
                .as_ref()
                .expect("two distinct points give a line");
            assert_eq!(cand.border, border, "{cand:?}");
            assert!(passes_through(
                f,
                &cand.vertices.iter().map(|&v| point(v)).collect::<Vec<_>>()
            ));
            let sign = if border {
                1.0
            } else {
                f.normal[0].signum() * n[0].signum()
            };
            assert_relative_eq!(f.normal[0], sign * n[0], epsilon = 1e-12);
            assert_relative_eq!(f.normal[1], sign * n[1], epsilon = 1e-12);
            assert_relative_eq!(f.offset, sign * d, epsilon = 1e-12);
        }
    }

    /// Krut, Company & Pierrot's (2004) 3-motor robot at the centre (unit columns at 30°, 150°, 270°, t ∈ [50, 500]):
    /// Σ w_j = 0, so t = 50·1 and t = 500·1 both map to the origin and the other 6 vertices to
    /// ±450 w_j, a regular hexagon of circumradius 450. Of the 28 pairs, 1 coincides (vertices
    /// 0 and 7), 15 lie on the 3 diameters (offset 0), 6 on the short diagonals (offset
    /// 450 cos 60° = 225) and 6 are the sides (apothem 450 cos 30°): exactly the facets of
    /// `available_wrench_set`.
    #[test]
    fn krut3_centre_candidates_and_borders() {
        let w = DMatrix::from_fn(2, 3, |i, j| {
            let a = (30.0f64 + 120.0 * j as f64).to_radians();
            if i == 0 { a.cos() } else { a.sin() }
        });
        let b = TensionBounds::uniform(3, 50.0, 500.0).unwrap();
        let c = candidate_hyperplanes(&w, &b).unwrap();
        assert_eq!(c.len(), 28);
        let none: Vec<&Candidate> = c.iter().filter(|c| c.hyperplane.is_none()).collect();
        assert_eq!(none.len(), 1);
        assert_eq!(none[0].vertices, [0, 7]);
        let count = |d: f64| {
            c.iter()
                .filter(|c| {
                    c.hyperplane
                        .as_ref()
                        .is_some_and(|f| (f.offset.abs() - d).abs() < 1e-9)
                })
                .count()
        };
        let apothem = 450.0 * 30f64.to_radians().cos();
        assert_eq!((count(0.0), count(225.0), count(apothem)), (15, 6, 6));
        let borders: Vec<&Facet> = c
            .iter()
            .filter(|c| c.border)
            .map(|c| c.hyperplane.as_ref().unwrap())
            .collect();
        assert_eq!(borders.len(), 6);
        assert!(borders.iter().all(|f| (f.offset - apothem).abs() < 1e-9));
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_eq!(aws.facets().len(), 6);
        for f in aws.facets() {
            let same = |g: &&&Facet| {
                (&g.normal - &f.normal).amax() < 1e-9 && (g.offset - f.offset).abs() < 1e-9
            };
            assert_eq!(borders.iter().filter(same).count(), 1, "{f:?}");
        }
    }

    /// A cable with t_min = t_max only translates the polytope: its bit stays clear and the
    /// enumeration runs over the other cables' 4 vertices (the square [5, 6]²).
    #[test]
    fn fixed_cable_translates() {
        let w = dmatrix![1.0, 0.0, 5.0; 0.0, 1.0, 5.0];
        let b = TensionBounds::new(vec![0.0, 0.0, 1.0], vec![1.0, 1.0, 1.0]).unwrap();
        let c = candidate_hyperplanes(&w, &b).unwrap();
        assert_eq!(c.len(), 6);
        assert!(c.iter().all(|c| c.vertices.iter().all(|&v| v < 4)));
        let mut sides: Vec<(i64, i64, i64)> = c
            .iter()
            .filter(|c| c.border)
            .map(|c| {
                let f = c.hyperplane.as_ref().unwrap();
                let r = |x: f64| x.round() as i64;
                (r(f.normal[0]), r(f.normal[1]), r(f.offset))
            })
            .collect();
        sides.sort();
        assert_eq!(sides, [(-1, 0, -5), (0, -1, -5), (0, 1, 6), (1, 0, 6)]);
    }

    /// The listing stops at MAX_LISTED_CANDIDATES, below the method's own limit: a full-rank
    /// 3 × 8 W has C(256, 3) ≈ 2.8·10⁶ candidates.
    #[test]
    fn listing_is_bounded() {
        const { assert!(MAX_LISTED_CANDIDATES < MAX_CANDIDATES) };
        let w = DMatrix::from_fn(3, 8, |i, j| 1.0 / (1 + i + j) as f64);
        let b = TensionBounds::uniform(8, 1.0, 2.0).unwrap();
        match candidate_hyperplanes(&w, &b) {
            Err(PolytopeError::TooLarge {
                cables: 8,
                dof: 3,
                candidates,
                max_candidates,
                ..
            }) => {
                assert_eq!(candidates, 256.0 * 255.0 * 254.0 / 6.0);
                assert_eq!(max_candidates, MAX_LISTED_CANDIDATES);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn square_and_signed_offsets() {
        // x = t1 − t2 ∈ [−9, 9]; y = t3 ∈ [1, 10]: the facet −y ≤ −1 has the origin outside.
        let w = dmatrix![1.0, -1.0, 0.0; 0.0, 0.0, 1.0];
        let b = TensionBounds::uniform(3, 1.0, 10.0).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_eq!(aws.facets().len(), 4);
        let down = aws
            .facets()
            .iter()
            .find(|f| f.normal[1] < -0.5)
            .expect("facet −y");
        assert_relative_eq!(down.offset, -1.0, epsilon = 1e-10);
        let up = aws.facets().iter().find(|f| f.normal[1] > 0.5).unwrap();
        assert_relative_eq!(up.offset, 10.0, epsilon = 1e-10);
    }

    #[test]
    fn hyperplane_through_the_origin_is_found() {
        // y = t3 ∈ [0, 1]: the facet −y ≤ 0 passes through the origin (non-Cramer T_k).
        let w = dmatrix![1.0, -1.0, 0.0; 0.0, 0.0, 1.0];
        let b = TensionBounds::new(vec![0.0, 0.0, 0.0], vec![1.0, 1.0, 1.0]).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        assert_eq!(aws.facets().len(), 4);
        let down = aws.facets().iter().find(|f| f.normal[1] < -0.5).unwrap();
        assert!(down.offset.abs() < 1e-10);
    }

    #[test]
    fn guards() {
        let w = DMatrix::from_fn(2, 11, |i, j| if i == 0 { 1.0 } else { j as f64 });
        let b = TensionBounds::uniform(11, 1.0, 2.0).unwrap();
        assert!(matches!(
            available_wrench_set(&w, &b),
            Err(PolytopeError::TooLarge { cables: 11, .. })
        ));
        let w = dmatrix![1.0, 0.0; 0.0, 1.0];
        let b = TensionBounds::new(vec![0.0, 0.0], vec![1.0, f64::INFINITY]).unwrap();
        assert!(matches!(
            available_wrench_set(&w, &b),
            Err(PolytopeError::UnboundedTension { cable: 1, .. })
        ));
        let w = dmatrix![1.0, 2.0, -1.0; 0.0, 0.0, 0.0];
        let b = TensionBounds::uniform(3, 1.0, 2.0).unwrap();
        assert!(matches!(
            available_wrench_set(&w, &b),
            Err(PolytopeError::LowerDimensional { rank: 1, dof: 2 })
        ));
    }
}

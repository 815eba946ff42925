//! # Available wrench set (operational force polytope)
//!
//! The set of wrenches the cables can apply to the platform with admissible tensions,
//!
//! ```text
//!     AWS = { W t : t_min ≤ t ≤ t_max }            (Krut, Company & Pierrot 2004, §III: image of the box (3) by Jₘᵀ = W)
//! ```
//!
//! stored as its H-representation `n_k · w ≤ d_k` with **unit** normals n_k, so that d_k is the
//! signed distance from the origin to facet k (positive when the origin is on the inner side).
//!
//! **Sign convention.** Equilibrium is W t + w_ext = 0, so an *external* wrench w_ext can be
//! balanced iff −w_ext ∈ AWS: the set of balanceable external wrenches is the mirror −AWS.
//! [`AvailableWrenchSet::contains`] tests the AWS itself, [`AvailableWrenchSet::can_balance`]
//! the mirror.
//!
//! Build one with [`crate::hyperplane_shifting::available_wrench_set`] (any size) or
//! [`crate::krut_vertex_projection::available_wrench_set`] (Krut, Company & Pierrot's (2004) method, small n).
//!
//! ## References
//! - S. Krut, O. Company, F. Pierrot, *Force performance indexes for parallel mechanisms with
//!   actuation redundancy, especially for parallel wire-driven manipulators*, IROS 2004 (Krut, Company & Pierrot 2004),
//!   eqs. (3), (16)–(18).

use nalgebra::{DMatrix, DVector};

/// Relative tolerance used to merge duplicate facets and vertices.
const MERGE_TOL: f64 = 1e-7;

/// One facet (or supporting half-space) `normal · w ≤ offset` with ‖normal‖ = 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Facet {
    /// Unit outward normal n_k (length DOF).
    pub normal: DVector<f64>,
    /// Offset d_k: the signed distance from the origin to the facet's hyperplane (N, or N·m
    /// mixed for wrench spaces; +∞ never occurs, such half-spaces are dropped).
    pub offset: f64,
}

/// One face of a bounded available wrench set of DOF 2 or 3: the vertices on the facet
/// `facets()[facet]`, as indices into [`AvailableWrenchSet::vertices`].
///
/// DOF 3: a polygon, its vertices counter-clockwise seen from outside (along −n), so that
/// n · ((v₁ − v₀) × (v₂ − v₀)) > 0. DOF 2: an edge, its two vertices in the counter-clockwise
/// order of the polygon.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Face {
    /// Vertex indices, counter-clockwise seen from outside.
    pub vertices: Vec<usize>,
    /// Index of the face's facet `n · w ≤ d` in [`AvailableWrenchSet::facets`] (its outward
    /// unit normal and offset).
    pub facet: usize,
}

/// The available wrench set {W t : t_min ≤ t ≤ t_max} in H-representation, plus its vertices and
/// faces for DOF 2 and 3 when it is bounded.
///
/// Two lists describe the same set: [`AvailableWrenchSet::supporting_halfspaces`], every
/// half-space the method produced, and [`AvailableWrenchSet::facets`], the same with
/// near-duplicates (normals within 1e-7) merged for presentation. Membership and the indices of
/// this crate are computed from the first list, so they agree exactly with the streaming
/// evaluators ([`crate::isotropic_force_of`], [`crate::CapacityMargin`]), which never build a
/// list.
#[derive(Debug, Clone, PartialEq)]
pub struct AvailableWrenchSet {
    dof: usize,
    halfspaces: Vec<Facet>,
    /// For each supporting half-space, the index of its merged facet.
    group: Vec<usize>,
    facets: Vec<Facet>,
    vertices: Option<Vec<DVector<f64>>>,
    faces: Option<Vec<Face>>,
    scale: f64,
}

/// Whether two normals agree within [`MERGE_TOL`] in every component (‖a − b‖∞ < tol, no
/// allocation).
#[inline]
fn same_normal(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < MERGE_TOL)
}

/// An integer with the order of [`f64::total_cmp`] (IEEE 754 totalOrder).
#[inline]
fn total_order_key(x: f64) -> i64 {
    let b = x.to_bits() as i64;
    b ^ (((b >> 63) as u64) >> 1) as i64
}

/// Lexicographic order of two normals by [`f64::total_cmp`] (a plain loop: the comparison
/// dominates the sort of the 504 half-spaces of 10 cables in 6 DOF).
#[inline]
fn lexicographic(a: &[f64], b: &[f64]) -> std::cmp::Ordering {
    for (x, y) in a.iter().zip(b) {
        let o = x.total_cmp(y);
        if o.is_ne() {
            return o;
        }
    }
    a.len().cmp(&b.len())
}

/// Merges half-spaces sorted lexicographically by normal into facets: each half-space joins the
/// first facet (in order of creation) whose normal is within [`MERGE_TOL`] of its own, and a
/// facet keeps the tighter half-space whole (normal and offset of one supporting half-space, so
/// that the merged list stays sound). Returns the facets and, per half-space, its facet.
///
/// Comparing each half-space with every facet is quadratic (3.2 ms for the 504 half-spaces of
/// 10 cables in 6 DOF, issue 13). Because the input is sorted, the first components n₀ never
/// decrease, and a facet's normal changes only when it matches: once a facet's n₀ is
/// [`MERGE_TOL`] or more below the current half-space's, no later half-space can match it. So
/// only the *live* facets (n₀ within the tolerance) are compared, in order of creation — the same
/// first match, the same result, with no allocation per comparison.
fn merge_sorted(raw: &[Facet]) -> (Vec<Facet>, Vec<usize>) {
    let mut groups = Groups::default();
    groups.merge(raw.len(), |i| raw[i].normal.as_slice(), |i| raw[i].offset);
    let facets = groups.reps.iter().map(|&r| raw[r].clone()).collect();
    (facets, groups.group)
}

/// The merge of [`merge_sorted`] on indices, with its buffers (reused from call to call: no
/// allocation once they have grown): the one copy of the rule, shared by the set and by
/// [`crate::LimitingFacet`], which never builds the facet list.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Groups {
    /// Per facet, the half-space (sorted index) whose normal and offset it keeps.
    pub(crate) reps: Vec<usize>,
    /// Per half-space (sorted index), its facet.
    pub(crate) group: Vec<usize>,
    live: Vec<usize>,
}

impl Groups {
    /// Merges `count` half-spaces sorted by [`sort_halfspaces`], the i-th with `normal(i)` and
    /// `offset(i)`.
    pub(crate) fn merge<'a>(
        &mut self,
        count: usize,
        normal: impl Fn(usize) -> &'a [f64],
        offset: impl Fn(usize) -> f64,
    ) {
        let Self { reps, group, live } = self;
        reps.clear();
        group.clear();
        live.clear();
        let first = |v: &[f64]| v.first().copied().unwrap_or(0.0);
        for i in 0..count {
            let (n, f0) = (normal(i), first(normal(i)));
            live.retain(|&k| (first(normal(reps[k])) - f0).abs() < MERGE_TOL);
            if let Some(k) = live
                .iter()
                .copied()
                .find(|&k| same_normal(normal(reps[k]), n))
            {
                if offset(i) < offset(reps[k]) {
                    reps[k] = i;
                }
                group.push(k);
            } else {
                live.push(reps.len());
                group.push(reps.len());
                reps.push(i);
            }
        }
    }
}

/// Sorts the indices of `count` half-spaces (the i-th with `normal(i)`, `offset(i)`) into the
/// set's deterministic order, `order[j].1` the j-th: by an integer key of the first component
/// of the normal (the order of [`f64::total_cmp`]), then the whole normal and the offset;
/// unstable, since elements comparing equal are equal (same normal and offset).
pub(crate) fn sort_halfspaces<'a>(
    order: &mut Vec<(i64, usize)>,
    count: usize,
    normal: impl Fn(usize) -> &'a [f64],
    offset: impl Fn(usize) -> f64,
) {
    order.clear();
    order.extend((0..count).map(|i| {
        (
            total_order_key(normal(i).first().copied().unwrap_or(0.0)),
            i,
        )
    }));
    order.sort_unstable_by(|a, b| {
        a.0.cmp(&b.0).then_with(|| {
            lexicographic(normal(a.1), normal(b.1)).then(offset(a.1).total_cmp(&offset(b.1)))
        })
    });
}

impl AvailableWrenchSet {
    /// Builds the set from raw half-spaces (unit normals), merging duplicates and computing the
    /// vertices for DOF 2 and 3 when `bounded`. `scale` is a typical wrench magnitude (for
    /// tolerances).
    pub(crate) fn from_halfspaces(
        dof: usize,
        mut raw: Vec<Facet>,
        bounded: bool,
        scale: f64,
    ) -> Self {
        let scale = scale.max(f64::MIN_POSITIVE);
        // Deterministic order: lexicographic on the normal, then the offset.
        raw.retain(|f| f.offset.is_finite());
        let mut order = Vec::with_capacity(raw.len());
        sort_halfspaces(
            &mut order,
            raw.len(),
            |i| raw[i].normal.as_slice(),
            |i| raw[i].offset,
        );
        let empty = || Facet {
            normal: DVector::zeros(0),
            offset: 0.0,
        };
        let raw: Vec<Facet> = order
            .iter()
            .map(|&(_, i)| std::mem::replace(&mut raw[i], empty()))
            .collect();
        let (facets, group) = merge_sorted(&raw);
        let mut set = Self {
            dof,
            halfspaces: raw,
            group,
            facets,
            vertices: None,
            faces: None,
            scale,
        };
        if bounded && (dof == 2 || dof == 3) {
            let vertices = set.compute_vertices();
            set.faces = Some(set.compute_faces(&vertices));
            set.vertices = Some(vertices);
        }
        set
    }

    /// The AWS of (a·W, b·t): offsets, vertices and scale times a·b (normals unchanged). `a`
    /// and `b` are powers of two (exact); [`PolytopeError::Overflow`] if an offset leaves the
    /// range of f64.
    pub(crate) fn rescaled(mut self, a: f64, b: f64) -> Result<Self, crate::PolytopeError> {
        let ab = a * b;
        let mul = |x: f64| {
            if ab.is_finite() && ab > 0.0 {
                x * ab
            } else {
                x * a * b
            }
        };
        for f in self.halfspaces.iter_mut().chain(self.facets.iter_mut()) {
            f.offset = mul(f.offset);
            if !f.offset.is_finite() {
                return Err(crate::PolytopeError::Overflow { value: f.offset });
            }
        }
        if let Some(vs) = &mut self.vertices {
            for v in vs.iter_mut() {
                v.iter_mut().for_each(|x| *x = mul(*x));
            }
        }
        self.scale = mul(self.scale).clamp(f64::MIN_POSITIVE, f64::MAX);
        Ok(self)
    }

    /// Dimension of the wrench space (rows of W).
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// The facets `n_k · w ≤ d_k`, unit normals, duplicates merged, in lexicographic order of
    /// the normals.
    pub fn facets(&self) -> &[Facet] {
        &self.facets
    }

    /// The vertices of the AWS for DOF 2 (ordered counter-clockwise) and DOF 3 (unordered),
    /// `None` for other DOF or when a t_max is infinite (unbounded set).
    pub fn vertices(&self) -> Option<&[DVector<f64>]> {
        self.vertices.as_deref()
    }

    /// The faces (DOF 2: edges; DOF 3: polygons) with their vertices counter-clockwise seen from
    /// outside, one per facet that holds at least DOF vertices (facets that only touch the
    /// set at a vertex or an edge have none); `None` when [`AvailableWrenchSet::vertices`] is
    /// `None`. Every vertex v satisfies every facet, n_k · v ≤ d_k; for DOF 3, V − E + F = 2
    /// (Euler).
    ///
    /// ```
    /// use cdpr_polytope::hyperplane_shifting::available_wrench_set;
    /// use cdpr_tension::TensionBounds;
    /// use nalgebra::DMatrix;
    ///
    /// // Three orthogonal cables and one along −(1,1,1): the image of a box in 3-D.
    /// let s = -1.0 / 3f64.sqrt();
    /// let w = DMatrix::from_row_slice(3, 4, &[1.0, 0.0, 0.0, s, 0.0, 1.0, 0.0, s, 0.0, 0.0, 1.0, s]);
    /// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 10.0, 100.0)?)?;
    /// let (v, faces) = (aws.vertices().unwrap(), aws.faces().unwrap());
    /// assert_eq!(v.len() + faces.len(), faces.iter().map(|f| f.vertices.len()).sum::<usize>() / 2 + 2);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn faces(&self) -> Option<&[Face]> {
        self.faces.as_deref()
    }

    /// Every supporting half-space `n · w ≤ d` the method produced (unit normals, finite
    /// offsets), before merging, sorted. Their intersection is the AWS.
    pub fn supporting_halfspaces(&self) -> &[Facet] {
        &self.halfspaces
    }

    /// The merged facet (an index into [`AvailableWrenchSet::facets`]) of supporting
    /// half-space `k`.
    pub(crate) fn facet_of(&self, k: usize) -> usize {
        self.group[k]
    }

    /// The largest violation `max_k (n_k · w − d_k)` over the supporting half-spaces (≤ 0
    /// inside; panic-free, −∞ if there is none).
    pub fn violation(&self, w: &DVector<f64>) -> f64 {
        self.halfspaces
            .iter()
            .map(|f| f.normal.dot(w) - f.offset)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Whether the cables can *apply* the wrench `w` to the platform: w ∈ AWS (with a relative
    /// tolerance of 1e-9 of the set's scale).
    pub fn contains(&self, w: &DVector<f64>) -> bool {
        w.len() == self.dof && self.violation(w) <= 1e-9 * self.scale
    }

    /// Whether the platform can *resist* the external wrench `w_ext` (W t + w_ext = 0 with
    /// admissible t): −w_ext ∈ AWS.
    pub fn can_balance(&self, w_ext: &DVector<f64>) -> bool {
        self.contains(&-w_ext)
    }

    /// Vertices as the feasible intersections of DOF facets, merged; for DOF 2 sorted by angle
    /// around their centroid.
    fn compute_vertices(&self) -> Vec<DVector<f64>> {
        let d = self.dof;
        let m = self.facets.len();
        let tol = 1e-9 * self.scale;
        let mut out: Vec<DVector<f64>> = Vec::new();
        let mut idx: Vec<usize> = (0..d).collect();
        if m < d {
            return out;
        }
        loop {
            let a = DMatrix::from_fn(d, d, |r, c| self.facets[idx[r]].normal[c]);
            let b = DVector::from_fn(d, |r, _| self.facets[idx[r]].offset);
            let lu = a.lu();
            let det = lu.determinant();
            if det.abs() > 1e-10
                && let Some(x) = lu.solve(&b)
                && self.violation(&x) <= tol
                && !out
                    .iter()
                    .any(|v| (v - &x).amax() <= MERGE_TOL * self.scale)
            {
                out.push(x);
            }
            if !next_combination(&mut idx, m) {
                break;
            }
        }
        if d == 2 && !out.is_empty() {
            let c = out.iter().fold(DVector::zeros(2), |s, v| s + v) / out.len() as f64;
            out.sort_by(|p, q| {
                let ap = (p[1] - c[1]).atan2(p[0] - c[0]);
                let aq = (q[1] - c[1]).atan2(q[0] - c[0]);
                ap.total_cmp(&aq)
            });
        }
        out
    }
}

impl AvailableWrenchSet {
    /// The faces of [`AvailableWrenchSet::faces`]: for each facet, the vertices within
    /// 10⁻⁸·scale of its plane, sorted by angle about their centroid in a basis (u, v) of the
    /// plane with u × v = n (counter-clockwise seen from outside).
    fn compute_faces(&self, vertices: &[DVector<f64>]) -> Vec<Face> {
        let tol = 1e-8 * self.scale;
        let mut faces = Vec::new();
        for (k, f) in self.facets.iter().enumerate() {
            let mut on: Vec<usize> = (0..vertices.len())
                .filter(|&i| (f.normal.dot(&vertices[i]) - f.offset).abs() <= tol)
                .collect();
            if on.len() < self.dof {
                continue;
            }
            let n = &f.normal;
            let centroid = on
                .iter()
                .fold(DVector::zeros(self.dof), |s, &i| s + &vertices[i])
                / on.len() as f64;
            let key = |p: &DVector<f64>| -> f64 {
                if self.dof == 2 {
                    // Along u = n rotated by +90° (the counter-clockwise tangent).
                    -n[1] * (p[0] - centroid[0]) + n[0] * (p[1] - centroid[1])
                } else {
                    // The angle in a basis (u, v = n × u) of the plane, u ⟂ n from the axis
                    // least aligned with n.
                    let n3 = nalgebra::Vector3::new(n[0], n[1], n[2]);
                    let axis = if n3.x.abs() <= n3.y.abs() && n3.x.abs() <= n3.z.abs() {
                        nalgebra::Vector3::x()
                    } else if n3.y.abs() <= n3.z.abs() {
                        nalgebra::Vector3::y()
                    } else {
                        nalgebra::Vector3::z()
                    };
                    let u = n3.cross(&axis).normalize();
                    let v = n3.cross(&u);
                    let d = nalgebra::Vector3::new(
                        p[0] - centroid[0],
                        p[1] - centroid[1],
                        p[2] - centroid[2],
                    );
                    d.dot(&v).atan2(d.dot(&u))
                }
            };
            on.sort_by(|&a, &b| key(&vertices[a]).total_cmp(&key(&vertices[b])));
            faces.push(Face {
                vertices: on,
                facet: k,
            });
        }
        faces
    }
}

/// Advances `idx` (strictly increasing, values < n) to the next k-combination in lexicographic
/// order; returns false after the last one. Returns the first changed position via the caller's
/// comparison if needed.
pub(crate) fn next_combination(idx: &mut [usize], n: usize) -> bool {
    let k = idx.len();
    let mut i = k;
    while i > 0 {
        i -= 1;
        if idx[i] < n - k + i {
            idx[i] += 1;
            for j in i + 1..k {
                idx[j] = idx[j - 1] + 1;
            }
            return true;
        }
    }
    false
}

/// Binomial coefficient as f64 (exact for the sizes used here).
pub(crate) fn binomial(n: f64, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i as f64) / (i as f64 + 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_order_key_orders_as_total_cmp() {
        let xs = [
            f64::NEG_INFINITY,
            -1.0,
            -f64::MIN_POSITIVE,
            -5e-324,
            -0.0,
            0.0,
            5e-324,
            1e-300,
            0.5,
            1.0,
            f64::MAX,
            f64::INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        for a in xs {
            for b in xs {
                assert_eq!(
                    super::total_order_key(a).cmp(&super::total_order_key(b)),
                    a.total_cmp(&b),
                    "{a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn combinations_are_enumerated_in_order() {
        let mut idx = vec![0, 1];
        let mut all = vec![idx.clone()];
        while next_combination(&mut idx, 4) {
            all.push(idx.clone());
        }
        assert_eq!(
            all,
            vec![
                vec![0, 1],
                vec![0, 2],
                vec![0, 3],
                vec![1, 2],
                vec![1, 3],
                vec![2, 3]
            ]
        );
        assert_eq!(binomial(64.0, 3), 41664.0);
        let mut empty: Vec<usize> = vec![];
        assert!(!next_combination(&mut empty, 3));
    }

    #[test]
    fn unit_square_vertices_and_membership() {
        let f = |x: f64, y: f64| Facet {
            normal: DVector::from_vec(vec![x, y]),
            offset: 1.0,
        };
        let set = AvailableWrenchSet::from_halfspaces(
            2,
            vec![
                f(1.0, 0.0),
                f(0.0, 1.0),
                f(-1.0, 0.0),
                f(0.0, -1.0),
                f(1.0, 0.0),
            ],
            true,
            1.0,
        );
        assert_eq!(set.facets().len(), 4);
        let v = set.vertices().unwrap();
        assert_eq!(v.len(), 4);
        // Counter-clockwise from angle −π: (−1,−1), (1,−1), (1,1), (−1,1).
        assert_eq!(v[0].as_slice(), &[-1.0, -1.0]);
        assert_eq!(v[1].as_slice(), &[1.0, -1.0]);
        assert_eq!(v[2].as_slice(), &[1.0, 1.0]);
        assert!(set.contains(&DVector::from_vec(vec![0.5, -0.9])));
        assert!(!set.contains(&DVector::from_vec(vec![1.1, 0.0])));
        assert!(set.can_balance(&DVector::from_vec(vec![-0.5, 0.9])));
    }

    /// The merge before issue 13 (every half-space against every facet, one allocation per
    /// comparison): the reference that [`merge_sorted`] must reproduce exactly.
    fn merge_quadratic(raw: &[Facet]) -> (Vec<Facet>, Vec<usize>) {
        let mut facets: Vec<Facet> = Vec::with_capacity(raw.len());
        let mut group = Vec::with_capacity(raw.len());
        for f in raw {
            if let Some(k) = facets
                .iter()
                .position(|g| (&g.normal - &f.normal).amax() < MERGE_TOL)
            {
                if f.offset < facets[k].offset {
                    facets[k] = f.clone();
                }
                group.push(k);
            } else {
                group.push(facets.len());
                facets.push(f.clone());
            }
        }
        (facets, group)
    }

    /// Random half-spaces whose normals cluster around a few directions, with offsets of
    /// 10⁻⁸ to 10⁻⁶ (so some fall within the tolerance and some just outside, including
    /// chains a − b < tol, b − c < tol, a − c ≥ tol): the sort-and-window merge gives exactly the
    /// quadratic merge's facets and groups.
    #[test]
    fn windowed_merge_equals_the_quadratic_merge() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..300 {
            let dof = 2 + case % 5;
            let centres: Vec<Vec<f64>> = (0..1 + case % 7)
                .map(|_| {
                    (0..dof)
                        .map(|_| (next() * 4.0).round() / 4.0 - 0.5)
                        .collect()
                })
                .collect();
            let count = 5 + (case * 7) % 200;
            let mut raw: Vec<Facet> = (0..count)
                .map(|_| {
                    let c = &centres[(next() * centres.len() as f64) as usize % centres.len()];
                    let spread = [0.0, 3e-8, 6e-8, 1e-7, 3e-7][(next() * 5.0) as usize % 5];
                    Facet {
                        normal: DVector::from_fn(dof, |i, _| c[i] + spread * (next() - 0.5)),
                        offset: (next() * 8.0).round() - 2.0,
                    }
                })
                .collect();
            raw.sort_by(|a, b| {
                a.normal
                    .iter()
                    .zip(b.normal.iter())
                    .map(|(x, y)| x.total_cmp(y))
                    .find(|o| o.is_ne())
                    .unwrap_or(std::cmp::Ordering::Equal)
                    .then(a.offset.total_cmp(&b.offset))
            });
            assert_eq!(merge_sorted(&raw), merge_quadratic(&raw), "case {case}");
        }
    }

    /// A pseudo-random wrench matrix DOF × n (entries in [−1, 1]).
    fn random_w(dof: usize, n: usize, seed: u64) -> DMatrix<f64> {
        let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        DMatrix::from_fn(dof, n, |_, _| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            2.0 * ((state >> 11) as f64 / (1u64 << 53) as f64) - 1.0
        })
    }

    /// 3-D: every vertex satisfies every facet, each face's vertices lie on its facet, faces
    /// turn counter-clockwise seen from outside, V − E + F = 2, and a generic zonotope of n
    /// generators has n(n − 1) parallelogram faces.
    #[test]
    fn faces_of_3d_polytopes_are_oriented_and_satisfy_euler() {
        for seed in 0..40 {
            let n = 3 + (seed as usize % 6);
            let w = random_w(3, n, seed);
            let bounds = cdpr_tension::TensionBounds::uniform(n, 5.0, 120.0).unwrap();
            let aws = crate::hyperplane_shifting::available_wrench_set(&w, &bounds).unwrap();
            let v = aws.vertices().unwrap();
            let faces = aws.faces().unwrap();
            let scale = 120.0 * n as f64;
            for p in v {
                for f in aws.facets() {
                    assert!(f.normal.dot(p) <= f.offset + 1e-9 * scale, "seed {seed}");
                }
            }
            let mut edges = 0;
            for face in faces {
                let f = &aws.facets()[face.facet];
                for &i in &face.vertices {
                    assert!((f.normal.dot(&v[i]) - f.offset).abs() <= 1e-8 * scale);
                }
                let m = face.vertices.len();
                edges += m;
                for j in 0..m {
                    let [a, b, c] = [0, 1, 2].map(|d| &v[face.vertices[(j + d) % m]]);
                    let (e1, e2) = (b - a, c - a);
                    let cross = nalgebra::Vector3::new(e1[0], e1[1], e1[2])
                        .cross(&nalgebra::Vector3::new(e2[0], e2[1], e2[2]));
                    let turn = cross.dot(&nalgebra::Vector3::new(
                        f.normal[0],
                        f.normal[1],
                        f.normal[2],
                    ));
                    assert!(turn > 0.0, "seed {seed}: face {face:?} turns clockwise");
                }
            }
            assert_eq!(edges % 2, 0);
            let (nv, ne, nf) = (v.len() as i64, edges as i64 / 2, faces.len() as i64);
            assert_eq!(nv - ne + nf, 2, "seed {seed}: V {nv}, E {ne}, F {nf}");
            let zonotope_faces = (n * (n - 1)) as i64;
            assert_eq!(nf, zonotope_faces, "seed {seed}");
            assert_eq!(nv, zonotope_faces + 2, "seed {seed}");
        }
    }

    /// 2-D: the faces are the polygon's edges, consecutive in counter-clockwise order, with
    /// the outward normal on their right: n × (v₁ − v₀) > 0.
    #[test]
    fn faces_of_2d_polygons_are_its_edges_counter_clockwise() {
        let f = |x: f64, y: f64| Facet {
            normal: DVector::from_vec(vec![x, y]),
            offset: 1.0,
        };
        let set = AvailableWrenchSet::from_halfspaces(
            2,
            vec![f(1.0, 0.0), f(0.0, 1.0), f(-1.0, 0.0), f(0.0, -1.0)],
            true,
            1.0,
        );
        let v = set.vertices().unwrap();
        let faces = set.faces().unwrap();
        assert_eq!(faces.len(), 4);
        for face in faces {
            let [a, b] = [face.vertices[0], face.vertices[1]];
            assert_eq!(b, (a + 1) % 4, "{face:?}");
            let n = &set.facets()[face.facet].normal;
            let e = &v[b] - &v[a];
            assert!(n[0] * e[1] - n[1] * e[0] > 0.0);
        }
        for seed in 0..20 {
            let n = 3 + seed as usize % 5;
            let w = random_w(2, n, seed + 100);
            let bounds = cdpr_tension::TensionBounds::uniform(n, 1.0, 50.0).unwrap();
            let aws = crate::hyperplane_shifting::available_wrench_set(&w, &bounds).unwrap();
            let (v, faces) = (aws.vertices().unwrap(), aws.faces().unwrap());
            assert_eq!(faces.len(), v.len(), "seed {seed}");
            assert_eq!(faces.len(), 2 * n, "seed {seed}: a zonogon of n generators");
        }
    }
}

//! # Capacity margin
//!
//! How far a *required external wrench set* R is from leaving the set of wrenches the robot can
//! balance. With W t + w_ext = 0, w_ext is balanced iff −w_ext ∈ AWS; so R is balanced iff
//! −R ⊂ AWS. For each facet n_k · w ≤ d_k of the AWS (unit n_k),
//!
//! ```text
//!     s_k = d_k − max_{w ∈ R} n_k · (−w) = d_k − h_R(−n_k),      margin = min_k s_k,
//! ```
//!
//! where h_R is the support function of R: for a box with centre c and half-widths h,
//! h_R(−n) = −n·c + Σ_i |n_i| h_i; for a ball with centre c and radius ρ, h_R(−n) = −n·c + ρ.
//! The margin is positive iff every wrench of R can be balanced with tensions in bounds (zero:
//! some wrench of R is on the boundary); when positive it is the largest ρ such that R grown by
//! a ball of radius ρ is still balanced, i.e. the distance from −R to the AWS boundary. A ball of
//! radius 0 at the origin gives back the isotropic wrench radius min_k d_k.
//!
//! A ball in the wrench space mixes N and N·m for planar/spatial robots, as in Guay et al.: its
//! radius ρ bounds √(‖f‖² + ‖m‖²) with forces in N and moments in N·m taken as numbers (a
//! length scale of 1 m). To keep the units apart, [`RequiredWrenchSet::force_and_moment_balls`]
//! requires every force ‖f‖ ≤ ρ_f (N) together with every moment ‖m‖ ≤ ρ_m (N·m): the product
//! of two balls, whose support function is h_R(−n) = −n·c + ρ_f ‖n_f‖ + ρ_m ‖n_m‖ (n_f, n_m:
//! the force and moment parts of n).
//!
//! ## References
//! - F. Guay, P. Cardou, A. L. Cruz-Ruiz, S. Caro, *Measuring how well a structure supports
//!   varying external wrenches*, New Advances in Mechanisms, Transmissions and Applications
//!   (MeTrApp 2013), Springer 2014: the capacity margin.
//! - S. Bouchard, C. Gosselin, B. Moore, J. Mech. Robot. 2(1), 2010 (hyperplane shifting).

use crate::PolytopeError;
use crate::available_wrench_set::{AvailableWrenchSet, Groups, sort_halfspaces};
use crate::hyperplane_shifting::{HyperplaneShifting, for_each_halfspace};
use crate::input::{MAX_DOF, check_vector};
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, DVector};

/// A set of *external* wrenches w_ext (acting on the platform) the robot is required to
/// balance: a box or a ball around a centre wrench (e.g. gravity), of dimension 1 to 6.
#[derive(Debug, Clone, PartialEq)]
pub struct RequiredWrenchSet {
    centre: DVector<f64>,
    /// Half-widths (box) or zeros (ball), padded to 6.
    half_widths: [f64; MAX_DOF],
    /// Ball radius (0 for a box).
    radius: f64,
    /// Centre padded to 6.
    centre_fixed: [f64; MAX_DOF],
    is_box: bool,
    /// Force and moment balls: (force rows, ρ_f, ρ_m); `radius` is then 0.
    split: Option<(usize, f64, f64)>,
}

impl RequiredWrenchSet {
    /// The single external wrench `w_ext` (a ball of radius 0).
    pub fn point(w_ext: DVector<f64>) -> Result<Self, PolytopeError> {
        Self::ball(w_ext, 0.0)
    }

    /// All external wrenches within `radius` of `centre` (Euclidean, in wrench units).
    pub fn ball(centre: DVector<f64>, radius: f64) -> Result<Self, PolytopeError> {
        let centre_fixed = Self::check_centre(&centre)?;
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(PolytopeError::InvalidParameter {
                what: "required ball radius",
                must: "finite and ≥ 0",
                value: radius,
            });
        }
        Ok(Self {
            centre,
            half_widths: [0.0; MAX_DOF],
            radius,
            centre_fixed,
            is_box: false,
            split: None,
        })
    }

    /// Every external wrench w = c + (f, m) with ‖f‖ ≤ `force_radius` (N) and ‖m‖ ≤
    /// `moment_radius` (N·m): force and moment bounded separately, in their own units. The
    /// first `force_rows` components of a wrench are forces (2 planar, 3 spatial:
    /// `MotionPattern::translation_dof`), the others moments; with no moment rows it is the
    /// force ball.
    ///
    /// ```
    /// use cdpr_polytope::{capacity_margin, hyperplane_shifting::available_wrench_set, RequiredWrenchSet};
    /// use cdpr_tension::TensionBounds;
    /// use nalgebra::{dmatrix, dvector};
    /// // AWS = [−9, 9]³ (forces x, y and the moment about z independent): a force ball of 2 N
    /// // with a moment range of ±3 N·m leaves min(9 − 2, 9 − 3) = 6.
    /// let w = dmatrix![1.0, -1.0, 0.0, 0.0, 0.0, 0.0;
    ///                  0.0, 0.0, 1.0, -1.0, 0.0, 0.0;
    ///                  0.0, 0.0, 0.0, 0.0, 1.0, -1.0];
    /// let aws = available_wrench_set(&w, &TensionBounds::uniform(6, 1.0, 10.0).unwrap()).unwrap();
    /// let r = RequiredWrenchSet::force_and_moment_balls(dvector![0.0, 0.0, 0.0], 2, 2.0, 3.0).unwrap();
    /// assert!((capacity_margin(&aws, &r).unwrap() - 6.0).abs() < 1e-12);
    /// ```
    pub fn force_and_moment_balls(
        centre: DVector<f64>,
        force_rows: usize,
        force_radius: f64,
        moment_radius: f64,
    ) -> Result<Self, PolytopeError> {
        let mut set = Self::ball(centre, 0.0)?;
        for (what, r) in [
            ("required force radius", force_radius),
            ("required moment radius", moment_radius),
        ] {
            if !(r.is_finite() && r >= 0.0) {
                return Err(PolytopeError::InvalidParameter {
                    what,
                    must: "finite and ≥ 0",
                    value: r,
                });
            }
        }
        if force_rows == 0 || force_rows > set.dof() {
            return Err(PolytopeError::DimensionMismatch {
                what: "force rows of the required wrench set",
                expected: set.dof(),
                found: force_rows,
            });
        }
        set.split = Some((force_rows, force_radius, moment_radius));
        Ok(set)
    }

    /// (force radius ρ_f in N, moment radius ρ_m in N·m) of
    /// [`RequiredWrenchSet::force_and_moment_balls`], `None` otherwise.
    pub fn force_and_moment_radii(&self) -> Option<(f64, f64)> {
        self.split.map(|(_, f, m)| (f, m))
    }

    /// The box `centre_i − h_i ≤ w_ext,i ≤ centre_i + h_i` (half-widths h_i ≥ 0).
    pub fn boxed(centre: DVector<f64>, half_widths: DVector<f64>) -> Result<Self, PolytopeError> {
        let centre_fixed = Self::check_centre(&centre)?;
        check_vector(
            "required box half-widths",
            half_widths.as_slice(),
            centre.len(),
        )?;
        if let Some(&h) = half_widths.iter().find(|&&h| h < 0.0) {
            return Err(PolytopeError::InvalidParameter {
                what: "required box half-width",
                must: "≥ 0",
                value: h,
            });
        }
        let mut h = [0.0; MAX_DOF];
        h[..centre.len()].copy_from_slice(half_widths.as_slice());
        Ok(Self {
            centre,
            half_widths: h,
            radius: 0.0,
            centre_fixed,
            is_box: true,
            split: None,
        })
    }

    fn check_centre(centre: &DVector<f64>) -> Result<[f64; MAX_DOF], PolytopeError> {
        if centre.is_empty() || centre.len() > MAX_DOF {
            return Err(PolytopeError::UnsupportedDof { dof: centre.len() });
        }
        check_vector("required wrench centre", centre.as_slice(), centre.len())?;
        let mut c = [0.0; MAX_DOF];
        c[..centre.len()].copy_from_slice(centre.as_slice());
        Ok(c)
    }

    /// Moves the set to a new centre wrench (same dimension, finite), in place: the required
    /// set of a batch whose centre (the platform's weight, an external wrench) changes from
    /// pose to pose, without reallocating.
    pub fn set_centre(&mut self, centre: &[f64]) -> Result<(), PolytopeError> {
        check_vector("required wrench centre", centre, self.dof())?;
        self.centre.copy_from_slice(centre);
        self.centre_fixed[..centre.len()].copy_from_slice(centre);
        Ok(())
    }

    /// Dimension of the wrenches.
    pub fn dof(&self) -> usize {
        self.centre.len()
    }

    /// The centre wrench.
    pub fn centre(&self) -> &DVector<f64> {
        &self.centre
    }

    /// The box half-widths, `None` for a ball.
    pub fn half_widths(&self) -> Option<&[f64]> {
        self.is_box.then(|| &self.half_widths[..self.dof()])
    }

    /// The ball radius, `None` for a box or for separate force and moment balls.
    pub fn radius(&self) -> Option<f64> {
        (!self.is_box && self.split.is_none()).then_some(self.radius)
    }

    /// h_R(−n) = max_{w ∈ R} (−n · w) = −n·c + Σ_i |n_i| h_i + ρ (a box has ρ = 0, a ball
    /// h = 0). `n` has length DOF.
    #[inline]
    fn mirrored_support(&self, n: &[f64]) -> f64 {
        let (along, spread) = self.support_parts(n);
        spread - along
    }

    /// (n·c, ρ + Σ_i |n_i| h_i): h_R(−n) = spread − along and h_R(n) = spread + along.
    #[inline(always)]
    fn support_parts(&self, n: &[f64]) -> (f64, f64) {
        let (mut along, mut spread) = (0.0, self.radius);
        for ((a, c), h) in n.iter().zip(&self.centre_fixed).zip(&self.half_widths) {
            along += a * c;
            spread += a.abs() * h;
        }
        if let Some((rows, rf, rm)) = self.split {
            let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
            spread += rf * norm(&n[..rows]) + rm * norm(&n[rows..]);
        }
        (along, spread)
    }
}

/// A margin that came out NaN (only through overflow of huge wrenches) is reported as such.
fn finite_or_overflow(m: f64) -> Result<f64, PolytopeError> {
    if m.is_nan() {
        Err(PolytopeError::Overflow { value: m })
    } else {
        Ok(m)
    }
}

/// The capacity margin min_k (d_k − h_R(−n_k)) of a required external wrench set against an
/// AWS (module docs). +∞ if the AWS has no facet (unbounded in every direction).
///
/// ```
/// use cdpr_polytope::{capacity_margin, hyperplane_shifting::available_wrench_set, RequiredWrenchSet};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::{dmatrix, dvector};
/// // AWS = [−9, 9]²; gravity w_ext = (0, −5) leaves 4 below / 9 sideways / 14 above: margin 4.
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
/// let gravity = RequiredWrenchSet::point(dvector![0.0, -5.0]).unwrap();
/// assert!((capacity_margin(&aws, &gravity).unwrap() - 4.0).abs() < 1e-12);
/// ```
pub fn capacity_margin(
    aws: &AvailableWrenchSet,
    required: &RequiredWrenchSet,
) -> Result<f64, PolytopeError> {
    Ok(limiting_facet(aws, required)?.map_or(f64::INFINITY, |(_, m)| m))
}

/// The facet of the AWS that limits the capacity margin: `(k, s_k)` with s_k the margin,
/// `k` an index into [`AvailableWrenchSet::facets`]; `None` if the AWS has no facet.
///
/// ```
/// use cdpr_polytope::{capacity_margin::limiting_facet, hyperplane_shifting::available_wrench_set, RequiredWrenchSet};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::{dmatrix, dvector};
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
/// let gravity = RequiredWrenchSet::point(dvector![0.0, -5.0]).unwrap();
/// let (k, m) = limiting_facet(&aws, &gravity).unwrap().unwrap();
/// // Balancing (0, −5) needs the cables to pull up: the limiting facet is y ≤ 9.
/// assert_eq!(aws.facets()[k].normal.as_slice(), &[0.0, 1.0]);
/// assert!((m - 4.0).abs() < 1e-12);
/// ```
pub fn limiting_facet(
    aws: &AvailableWrenchSet,
    required: &RequiredWrenchSet,
) -> Result<Option<(usize, f64)>, PolytopeError> {
    if required.dof() != aws.dof() {
        return Err(PolytopeError::DimensionMismatch {
            what: "required wrench set vs AWS dimension",
            expected: aws.dof(),
            found: required.dof(),
        });
    }
    let mut best: Option<(usize, f64)> = None;
    // Scored over every supporting half-space (as the streaming evaluator does), reported as
    // the merged facet it belongs to.
    for (k, f) in aws.supporting_halfspaces().iter().enumerate() {
        let s = finite_or_overflow(f.offset - required.mirrored_support(f.normal.as_slice()))?;
        if best.is_none_or(|(_, m)| s < m) {
            best = Some((k, s));
        }
    }
    Ok(best.map(|(k, s)| (aws.facet_of(k), s)))
}

/// Allocation-free capacity margin for repeated poses: hyperplane shifting on the fly, each
/// half-space scored as it is found. Checks the bounds and the required set at each call; use
/// [`CapacityMarginEvaluator`] to check them once.
///
/// ```
/// use cdpr_polytope::{CapacityMargin, RequiredWrenchSet};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::{dmatrix, dvector};
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let bounds = TensionBounds::uniform(4, 1.0, 10.0).unwrap();
/// let mut cm = CapacityMargin::new(2, 4);
/// let r = RequiredWrenchSet::ball(dvector![0.0, -5.0], 1.0).unwrap();
/// assert!((cm.margin(&w, &bounds, &r).unwrap() - 3.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CapacityMargin {
    dof: usize,
    cables: usize,
}

impl CapacityMargin {
    /// A margin evaluator for DOF × n wrench matrices.
    pub fn new(dof: usize, cables: usize) -> Self {
        Self { dof, cables }
    }

    /// The capacity margin of `required` at the pose whose wrench matrix is `w`.
    pub fn margin(
        &mut self,
        w: &DMatrix<f64>,
        bounds: &TensionBounds,
        required: &RequiredWrenchSet,
    ) -> Result<f64, PolytopeError> {
        if w.nrows() != self.dof {
            return Err(PolytopeError::DimensionMismatch {
                what: "rows of W",
                expected: self.dof,
                found: w.nrows(),
            });
        }
        if w.ncols() != self.cables {
            return Err(PolytopeError::DimensionMismatch {
                what: "columns of W",
                expected: self.cables,
                found: w.ncols(),
            });
        }
        if required.dof() != self.dof {
            return Err(PolytopeError::DimensionMismatch {
                what: "required wrench set vs rows of W",
                expected: self.dof,
                found: required.dof(),
            });
        }
        let mut m = f64::INFINITY;
        for_each_halfspace(w, bounds, |n, d| {
            m = m.min(d - required.mirrored_support(n));
        })?;
        finite_or_overflow(m)
    }
}

/// The capacity margin of one required set with fixed tension bounds, both checked once at
/// construction: the fast path for sweeps over many poses (no allocation, no re-validation;
/// each call checks only the shape and finiteness of W).
///
/// ```
/// use cdpr_polytope::{CapacityMarginEvaluator, RequiredWrenchSet};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::{dmatrix, dvector};
/// let bounds = TensionBounds::uniform(4, 1.0, 10.0).unwrap();
/// let r = RequiredWrenchSet::ball(dvector![0.0, -5.0], 1.0).unwrap();
/// let cm = CapacityMarginEvaluator::new(&bounds, &r).unwrap();
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// assert!((cm.margin(&w).unwrap() - 3.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CapacityMarginEvaluator {
    engine: HyperplaneShifting,
    required: RequiredWrenchSet,
}

impl CapacityMarginEvaluator {
    /// An evaluator for DOF × n wrench matrices, DOF = `required.dof()`, n = `bounds.len()`.
    pub fn new(
        bounds: &TensionBounds,
        required: &RequiredWrenchSet,
    ) -> Result<Self, PolytopeError> {
        Ok(Self {
            engine: HyperplaneShifting::new(required.dof(), bounds)?,
            required: required.clone(),
        })
    }

    /// The required set.
    pub fn required(&self) -> &RequiredWrenchSet {
        &self.required
    }

    /// The capacity margin at the pose whose wrench matrix is `w` (+∞ if no facet).
    #[inline]
    pub fn margin(&self, w: &DMatrix<f64>) -> Result<f64, PolytopeError> {
        let r = &self.required;
        let mut m = f64::INFINITY;
        // Both half-spaces ±c of a subset share n·c and Σ|n_i| h_i; +∞ offsets stay +∞.
        self.engine.for_each_pair(w, |n, dp, dm| {
            let (along, spread) = r.support_parts(n);
            let (a, b) = (dp - (spread - along), dm - (spread + along));
            let s = if a < b { a } else { b };
            if s < m {
                m = s;
            }
            2
        })?;
        finite_or_overflow(m)
    }
}

/// [`limiting_facet`] of the AWS of W, for many poses: the same facet index and margin,
/// without building the set (no vertices, no faces, no facet list; the half-spaces of hyperplane
/// shifting sorted and merged in buffers kept from pose to pose, by the set's own sort and
/// merge rule). The bounds are checked once, at construction.
///
/// ```
/// use cdpr_polytope::{LimitingFacet, RequiredWrenchSet, capacity_margin::limiting_facet};
/// use cdpr_polytope::hyperplane_shifting::available_wrench_set;
/// use cdpr_tension::TensionBounds;
/// use nalgebra::{dmatrix, dvector};
/// let bounds = TensionBounds::uniform(4, 1.0, 10.0).unwrap();
/// let w = dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0];
/// let gravity = RequiredWrenchSet::point(dvector![0.0, -5.0]).unwrap();
/// let mut lf = LimitingFacet::new(2, &bounds).unwrap();
/// let aws = available_wrench_set(&w, &bounds).unwrap();
/// assert_eq!(lf.at(&w, &gravity).unwrap(), limiting_facet(&aws, &gravity).unwrap());
/// ```
#[derive(Debug, Clone)]
pub struct LimitingFacet {
    engine: HyperplaneShifting,
    /// The half-spaces of the last pose: normals (DOF each, in a row) and finite offsets.
    normals: Vec<f64>,
    offsets: Vec<f64>,
    order: Vec<(i64, usize)>,
    groups: Groups,
}

impl LimitingFacet {
    /// Buffers for DOF × n wrench matrices with `bounds` (n pairs).
    pub fn new(dof: usize, bounds: &TensionBounds) -> Result<Self, PolytopeError> {
        Ok(Self {
            engine: HyperplaneShifting::new(dof, bounds)?,
            normals: Vec::new(),
            offsets: Vec::new(),
            order: Vec::new(),
            groups: Groups::default(),
        })
    }

    /// `limiting_facet(&available_wrench_set(w, bounds)?, required)`: the merged facet (index
    /// into [`AvailableWrenchSet::facets`]) where the margin is reached, and the margin.
    pub fn at(
        &mut self,
        w: &DMatrix<f64>,
        required: &RequiredWrenchSet,
    ) -> Result<Option<(usize, f64)>, PolytopeError> {
        let dof = self.engine.dof();
        if required.dof() != dof {
            return Err(PolytopeError::DimensionMismatch {
                what: "required wrench set vs rows of W",
                expected: dof,
                found: required.dof(),
            });
        }
        let Self {
            engine,
            normals,
            offsets,
            order,
            groups,
        } = self;
        normals.clear();
        offsets.clear();
        engine.for_each_halfspace(w, |n, d| {
            if d.is_finite() {
                normals.extend_from_slice(n);
                offsets.push(d);
            }
        })?;
        let normal = |i: usize| &normals[i * dof..(i + 1) * dof];
        sort_halfspaces(order, offsets.len(), normal, |i| offsets[i]);
        let sorted = |j: usize| order[j].1;
        groups.merge(offsets.len(), |j| normal(sorted(j)), |j| offsets[sorted(j)]);
        let mut best: Option<(usize, f64)> = None;
        for j in 0..offsets.len() {
            let i = sorted(j);
            let s = finite_or_overflow(offsets[i] - required.mirrored_support(normal(i)))?;
            if best.is_none_or(|(_, m)| s < m) {
                best = Some((j, s));
            }
        }
        Ok(best.map(|(j, s)| (groups.group[j], s)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hyperplane_shifting::available_wrench_set;
    use approx::assert_relative_eq;
    use nalgebra::{dmatrix, dvector};

    fn square() -> (DMatrix<f64>, TensionBounds) {
        (
            dmatrix![1.0, -1.0, 0.0, 0.0; 0.0, 0.0, 1.0, -1.0],
            TensionBounds::uniform(4, 1.0, 10.0).unwrap(),
        )
    }

    #[test]
    fn box_margin_by_hand() {
        // AWS = [−9, 9]². External box centred (3, 0) with half-widths (2, 1): the balanced
        // set is −AWS = [−9, 9]², the box spans x ∈ [1, 5], y ∈ [−1, 1]: margin 9 − 5 = 4.
        let (w, b) = square();
        let aws = available_wrench_set(&w, &b).unwrap();
        let r = RequiredWrenchSet::boxed(dvector![3.0, 0.0], dvector![2.0, 1.0]).unwrap();
        assert_relative_eq!(capacity_margin(&aws, &r).unwrap(), 4.0, epsilon = 1e-12);
        let mut cm = CapacityMargin::new(2, 4);
        assert_relative_eq!(cm.margin(&w, &b, &r).unwrap(), 4.0, epsilon = 1e-12);
        // Half-width 12: −R spans x ∈ [−15, 9], 6 beyond the facet x ≥ −9: margin −6.
        let r = RequiredWrenchSet::boxed(dvector![3.0, 0.0], dvector![12.0, 1.0]).unwrap();
        assert_relative_eq!(cm.margin(&w, &b, &r).unwrap(), -6.0, epsilon = 1e-12);
    }

    #[test]
    fn the_sign_of_the_external_wrench_matters() {
        // Unsymmetric AWS: x ∈ [−3, 3], y ∈ [1, 4] (cables can only pull up, 1 ≤ t3 ≤ 4).
        // Gravity w_ext = (0, −2) needs the cables to pull up by 2: balanced, margin
        // min(3, 3, 4 − 2, 2 − 1) = 1. The opposite load (0, +2) cannot be balanced: margin −3.
        let w = dmatrix![1.0, -1.0, 0.0; 0.0, 0.0, 1.0];
        let b = TensionBounds::new(vec![0.0, 2.0, 1.0], vec![5.0, 3.0, 4.0]).unwrap();
        let aws = available_wrench_set(&w, &b).unwrap();
        let gravity = RequiredWrenchSet::point(dvector![0.0, -2.0]).unwrap();
        assert_relative_eq!(
            capacity_margin(&aws, &gravity).unwrap(),
            1.0,
            epsilon = 1e-12
        );
        assert!(aws.can_balance(gravity.centre()));
        let lift = RequiredWrenchSet::point(dvector![0.0, 2.0]).unwrap();
        assert_relative_eq!(capacity_margin(&aws, &lift).unwrap(), -3.0, epsilon = 1e-12);
        assert!(!aws.can_balance(lift.centre()));
    }

    #[test]
    fn bad_required_sets_are_errors() {
        assert!(RequiredWrenchSet::ball(dvector![0.0, f64::NAN], 1.0).is_err());
        assert!(RequiredWrenchSet::ball(dvector![0.0, 0.0], -1.0).is_err());
        assert!(RequiredWrenchSet::boxed(dvector![0.0, 0.0], dvector![1.0]).is_err());
        assert!(RequiredWrenchSet::boxed(dvector![0.0, 0.0], dvector![1.0, -1.0]).is_err());
        let (w, b) = square();
        let r3 = RequiredWrenchSet::point(dvector![0.0, 0.0, 0.0]).unwrap();
        assert!(CapacityMargin::new(2, 4).margin(&w, &b, &r3).is_err());
        assert!(CapacityMargin::new(3, 4).margin(&w, &b, &r3).is_err());
        let aws = available_wrench_set(&w, &b).unwrap();
        assert!(capacity_margin(&aws, &r3).is_err());
    }

    /// [`LimitingFacet`] gives `limiting_facet` of the built set on random W (DOF 2, 3 and 6;
    /// boxes, balls, points; centres moved with `set_centre`), on W with repeated and opposite
    /// columns (coinciding half-spaces that the merge joins into one facet), and with an
    /// infinite t_max (half-spaces dropped): one buffer reused over every case.
    #[test]
    fn limiting_facet_without_the_set_equals_the_sets() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut rand = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut compared = 0;
        for (dof, n) in [(2, 4), (2, 5), (3, 5), (3, 7), (6, 8)] {
            let mut t_max = vec![50.0; n];
            t_max[n - 1] = f64::INFINITY;
            let bounded = TensionBounds::uniform(n, 1.0, 50.0).unwrap();
            let open = TensionBounds::new(vec![1.0; n], t_max).unwrap();
            for bounds in [&bounded, &open] {
                let mut lf = LimitingFacet::new(dof, bounds).unwrap();
                let mut ball = RequiredWrenchSet::ball(DVector::zeros(dof), 2.0).unwrap();
                let half = DVector::from_element(dof, 1.5);
                let mut boxed = RequiredWrenchSet::boxed(DVector::zeros(dof), half).unwrap();
                for case in 0..40 {
                    let mut w = DMatrix::from_fn(dof, n, |_, _| rand());
                    if case % 3 == 0 {
                        // Column 1 repeats column 0, column 2 opposes it.
                        let c0 = w.column(0).into_owned();
                        w.set_column(1, &c0);
                        w.set_column(2, &(-c0));
                    }
                    let centre: Vec<f64> = (0..dof).map(|_| 10.0 * rand()).collect();
                    ball.set_centre(&centre).unwrap();
                    boxed.set_centre(&centre).unwrap();
                    let point = RequiredWrenchSet::point(DVector::from_column_slice(&centre));
                    let aws = available_wrench_set(&w, bounds).unwrap();
                    for required in [&ball, &boxed, &point.unwrap()] {
                        assert_eq!(required.centre().as_slice(), centre.as_slice());
                        let expected = limiting_facet(&aws, required).unwrap();
                        assert_eq!(lf.at(&w, required).unwrap(), expected, "case {case}");
                        compared += 1;
                    }
                }
            }
        }
        assert_eq!(compared, 5 * 2 * 40 * 3);
        // A wrong dimension is an error, not a panic.
        let mut lf = LimitingFacet::new(2, &TensionBounds::uniform(4, 1.0, 10.0).unwrap()).unwrap();
        let (w, _) = square();
        let r3 = RequiredWrenchSet::point(dvector![0.0, 0.0, 0.0]).unwrap();
        assert!(lf.at(&w, &r3).is_err());
        let mut r2 = RequiredWrenchSet::point(dvector![0.0, 0.0]).unwrap();
        assert!(r2.set_centre(&[1.0]).is_err() && r2.set_centre(&[f64::NAN, 0.0]).is_err());
    }
}

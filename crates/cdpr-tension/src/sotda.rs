//! # Stiffness-oriented tension distribution (SOTDA)
//!
//! Among the tensions of the feasible polygon (redundancy 2), pick those that minimise the
//! platform displacement along a direction d under a small wrench δw_e (Picard, Caro, Plestan & Claveau 2020, eq. (7)):
//!
//! ```text
//!   min_t |d · δp(t)|,   δX(t) = [δp; δφ] = K(t)⁻¹ δw_e,   K = Kp + Ka  (Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4))
//! ```
//!
//! with K from `cdpr_wrench::write_stiffness_matrix` (k_i = E S / l_i). δw_e is
//! [`SotdaSettings::perturbation`] if given, else the external wrench w_ext; if w_ext has no
//! force component along d (or is zero), a unit force along d is used instead so the objective
//! is not identically zero. d is restricted to the translation components of the motion
//! pattern and normalised.
//!
//! Variants (Picard, Caro, Plestan & Claveau 2020, Algorithm 1 and §3):
//! - [`SotdaVariant::Full`]: evaluate a 24 × 24 grid over the polygon's bounding box (points
//!   inside), its vertices, edge midpoints and centroid, then refine the best point by a
//!   projected pattern search down to 10⁻⁹ of the polygon size.
//! - [`SotdaVariant::Corners`] (default): the paper's real-time variant. §3 assumes that
//!   (i) the robot is stiffest when at least one cable tension reaches t_max and (ii) a second
//!   cable is at t_min or t_max, i.e. the optimum is a corner of the polygon with a cable at
//!   t_max ("a maximum of 16 sets for an 8-cable CDPR"). So only the vertices where some cable
//!   is at its t_max are evaluated (tolerance τ_i = 10⁻⁹ (t_max,i − t_min,i) + 10⁻¹² s, s the
//!   data scale, see `UpperBoundTest`); vertices with both active cables at t_min are skipped.
//!   If no vertex qualifies (no finite t_max is ever reached), or K is singular at all that do,
//!   every vertex is evaluated instead: the paper takes "the best of the computed ones", and an
//!   empty candidate set would compute none.
//! - [`SotdaVariant::Vertices`]: every vertex of the polygon (including t_min–t_min corners), a
//!   superset of the corner candidates, so never a larger displacement than `Corners`.
//!
//! Finally the intermediate solution (Fig. 2): t = t_bary + ν (t_opt − t_bary), ν ∈ [0, 1], which
//! stays in the polygon by convexity.
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020: Picard, Caro, Plestan & Claveau (2020), *Stiffness oriented tension distribution
//!   algorithm for cable-driven parallel robots*, ARK 2020, eqs. (3)–(7), Algorithm 1, Fig. 2.

use crate::feasible_polygon::{P2, Region};
use crate::linear_program::write_tensions;
use crate::null_space::NullSpace;
use crate::{Infeasibility, StiffnessData, TensionBounds, TensionError};
use nalgebra::{DMatrix, DVector, Vector3};

/// Which points of the feasible polygon SOTDA evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SotdaVariant {
    /// Dense search plus local refinement over the whole polygon.
    Full,
    /// Picard, Caro, Plestan & Claveau's (2020) real-time variant: the polygon's vertices at which some cable is at its
    /// t_max (§3 assumptions (i)–(ii)); all vertices if there is none.
    #[default]
    Corners,
    /// Every vertex of the polygon (also those with both active cables at t_min).
    Vertices,
}

/// Settings of [`crate::Method::Sotda`].
#[derive(Clone, Debug, PartialEq)]
pub struct SotdaSettings {
    /// Direction d along which the displacement is minimised (base frame; only the translation
    /// components of the motion pattern are used). Default +y, as in Picard, Caro, Plestan & Claveau 2020.
    pub direction: Vector3<f64>,
    /// ν ∈ [0, 1]: 0 gives the barycentre, 1 the stiffness-oriented optimum (Fig. 2).
    pub nu: f64,
    /// Full search, every vertex, or the paper's corners (default).
    pub variant: SotdaVariant,
    /// δw_e (length DOF); `None`: the external wrench (see the module docs).
    pub perturbation: Option<DVector<f64>>,
}

impl Default for SotdaSettings {
    fn default() -> Self {
        Self {
            direction: Vector3::y(),
            nu: 1.0,
            variant: SotdaVariant::Corners,
            perturbation: None,
        }
    }
}

impl SotdaSettings {
    /// Checks ν ∈ [0, 1], a finite non-zero direction and a finite perturbation.
    pub fn validate(&self) -> Result<(), TensionError> {
        if !(0.0..=1.0).contains(&self.nu) {
            return Err(TensionError::InvalidSettings("nu must lie in [0, 1]"));
        }
        if !self.direction.iter().all(|v| v.is_finite()) || self.direction.norm() == 0.0 {
            return Err(TensionError::InvalidSettings(
                "direction must be finite and non-zero",
            ));
        }
        if let Some(p) = &self.perturbation
            && !p.iter().all(|v| v.is_finite())
        {
            return Err(TensionError::InvalidSettings("perturbation must be finite"));
        }
        Ok(())
    }
}

/// Buffers of SOTDA (no allocation once sized).
#[derive(Debug, Clone, Default)]
pub(crate) struct Sotda {
    k: DMatrix<f64>,
    lu: Vec<f64>,
    x: Vec<f64>,
    dw: Vec<f64>,
    dir: Vec<f64>,
    t: Vec<f64>,
}

impl Sotda {
    /// Sets δw_e and d for this problem.
    pub fn prepare(
        &mut self,
        settings: &SotdaSettings,
        stiffness: &StiffnessData,
        w_ext: &DVector<f64>,
    ) -> Result<(), TensionError> {
        settings.validate()?;
        let motion = stiffness.kinematics.motion();
        let m = motion.dof();
        if w_ext.len() != m {
            return Err(TensionError::DimensionMismatch {
                what: "sotda: wrench length vs motion pattern DOF",
                expected: m,
                found: w_ext.len(),
            });
        }
        let td = motion.translation_dof();
        self.dir.clear();
        self.dir
            .extend_from_slice(&settings.direction.as_slice()[..td]);
        let dn = self.dir.iter().map(|v| v * v).sum::<f64>().sqrt();
        if dn == 0.0 {
            return Err(TensionError::InvalidSettings(
                "direction has no component in the platform's translations",
            ));
        }
        self.dir.iter_mut().for_each(|v| *v /= dn);
        self.dw.clear();
        match &settings.perturbation {
            Some(p) => {
                if p.len() != m {
                    return Err(TensionError::DimensionMismatch {
                        what: "sotda perturbation length vs DOF",
                        expected: m,
                        found: p.len(),
                    });
                }
                self.dw.extend_from_slice(p.as_slice());
            }
            None => {
                let along: f64 = (0..td).map(|k| w_ext[k] * self.dir[k]).sum();
                if along.abs() > 1e-12 * w_ext.amax() && w_ext.amax() > 0.0 {
                    self.dw.extend_from_slice(w_ext.as_slice());
                } else {
                    self.dw.resize(m, 0.0);
                    self.dw[..td].copy_from_slice(&self.dir);
                }
            }
        }
        self.lu.resize(m * m, 0.0);
        self.x.resize(m, 0.0);
        self.t.resize(stiffness.kinematics.cable_count(), 0.0);
        Ok(())
    }

    /// |d · δp| at tensions `t`; +∞ when K(t) is singular.
    pub fn displacement(
        &mut self,
        stiffness: &StiffnessData,
        t: &[f64],
    ) -> Result<f64, TensionError> {
        cdpr_wrench::write_stiffness_matrix(
            stiffness.kinematics,
            t,
            stiffness.axial_stiffness,
            &mut self.k,
        )?;
        let m = self.k.nrows();
        for r in 0..m {
            for c in 0..m {
                self.lu[r * m + c] = self.k[(r, c)];
            }
        }
        self.x.copy_from_slice(&self.dw);
        if !lu_solve(&mut self.lu, m, &mut self.x) {
            return Ok(f64::INFINITY);
        }
        Ok(self
            .dir
            .iter()
            .zip(&self.x)
            .map(|(d, x)| d * x)
            .sum::<f64>()
            .abs())
    }

    fn at(
        &mut self,
        ns: &NullSpace,
        stiffness: &StiffnessData,
        l: P2,
    ) -> Result<f64, TensionError> {
        let mut t = std::mem::take(&mut self.t);
        write_tensions(ns, l, &mut t);
        let f = self.displacement(stiffness, &t);
        self.t = t;
        f
    }

    /// Picard, Caro, Plestan & Claveau 2020, Algorithm 1 with the intermediate solution; writes t.
    pub fn solve_on_region(
        &mut self,
        settings: &SotdaSettings,
        stiffness: &StiffnessData,
        ns: &NullSpace,
        region: &Region,
        bounds: &TensionBounds,
        t: &mut [f64],
    ) -> Result<Result<(), Infeasibility>, TensionError> {
        if region.is_unbounded() {
            return Ok(Err(Infeasibility::Unbounded { method: "sotda" }));
        }
        let centroid = region.centroid();
        let mut best = region.verts[0];
        let mut fb = f64::INFINITY;
        // Corners: only the vertices with a cable at t_max (§3 assumptions (i)–(ii)); if that
        // leaves no candidate with a finite displacement, every vertex (see the module docs).
        let filtered = settings.variant == SotdaVariant::Corners;
        let tol = filtered.then(|| UpperBoundTest::new(ns, bounds));
        for j in 0..region.verts.len() {
            let v = region.verts[j];
            if let Some(tol) = &tol
                && !tol.some_cable_at_max(ns, bounds, v)
            {
                continue;
            }
            let f = self.at(ns, stiffness, v)?;
            if f < fb {
                (best, fb) = (v, f);
            }
        }
        if filtered && !fb.is_finite() {
            for j in 0..region.verts.len() {
                let v = region.verts[j];
                let f = self.at(ns, stiffness, v)?;
                if f < fb {
                    (best, fb) = (v, f);
                }
            }
        }
        if settings.variant == SotdaVariant::Full {
            let k = region.verts.len();
            let f = self.at(ns, stiffness, centroid)?;
            if f < fb {
                (best, fb) = (centroid, f);
            }
            for j in 0..k {
                let (p, q) = (region.verts[j], region.verts[(j + 1) % k]);
                let mid = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
                let f = self.at(ns, stiffness, mid)?;
                if f < fb {
                    (best, fb) = (mid, f);
                }
            }
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for v in &region.verts {
                for d in 0..2 {
                    lo[d] = lo[d].min(v[d]);
                    hi[d] = hi[d].max(v[d]);
                }
            }
            const G: usize = 24;
            for a in 0..=G {
                for b in 0..=G {
                    let p = [
                        lo[0] + (hi[0] - lo[0]) * a as f64 / G as f64,
                        lo[1] + (hi[1] - lo[1]) * b as f64 / G as f64,
                    ];
                    if region.contains(p) {
                        let f = self.at(ns, stiffness, p)?;
                        if f < fb {
                            (best, fb) = (p, f);
                        }
                    }
                }
            }
            // Projected pattern search.
            let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
            let mut h = extent / G as f64;
            const DIRS: [P2; 8] = [
                [1.0, 0.0],
                [-1.0, 0.0],
                [0.0, 1.0],
                [0.0, -1.0],
                [
                    std::f64::consts::FRAC_1_SQRT_2,
                    std::f64::consts::FRAC_1_SQRT_2,
                ],
                [
                    -std::f64::consts::FRAC_1_SQRT_2,
                    std::f64::consts::FRAC_1_SQRT_2,
                ],
                [
                    std::f64::consts::FRAC_1_SQRT_2,
                    -std::f64::consts::FRAC_1_SQRT_2,
                ],
                [
                    -std::f64::consts::FRAC_1_SQRT_2,
                    -std::f64::consts::FRAC_1_SQRT_2,
                ],
            ];
            let mut iters = 0;
            while h > 1e-9 * extent && iters < 2000 {
                iters += 1;
                let mut improved = false;
                for d in DIRS {
                    let p = region.project([best[0] + h * d[0], best[1] + h * d[1]]);
                    let f = self.at(ns, stiffness, p)?;
                    if f < fb {
                        (best, fb) = (p, f);
                        improved = true;
                        break;
                    }
                }
                if !improved {
                    h *= 0.5;
                }
            }
        }
        if !fb.is_finite() {
            return Ok(Err(Infeasibility::SolverFailure {
                detail: "sotda: the stiffness matrix is singular on the whole polygon".into(),
            }));
        }
        let nu = settings.nu;
        let l = [
            centroid[0] + nu * (best[0] - centroid[0]),
            centroid[1] + nu * (best[1] - centroid[1]),
        ];
        write_tensions(ns, l, t);
        Ok(Ok(()))
    }
}

/// The test "cable i is at its upper bound" of Picard, Caro, Plestan & Claveau 2020, §3 assumption (i), applied to the
/// vertices of the clipped polygon: t_i(λ) ≥ t_max,i − τ_i with
///
/// ```text
///   τ_i = 10⁻⁹ (t_max,i − t_min,i) + 10⁻¹² s,   s = max(1, |t0_j|, |t_min,j|, finite |t_max,j|)
/// ```
///
/// A vertex on the line t_i = t_max,i carries only round-off (≈ ε s, s the data scale, the
/// same as the polygon builder's) in t_i = t0_i + N_i λ; a vertex off that line is (generically)
/// a finite distance away. Cables with an infinite t_max never qualify.
struct UpperBoundTest {
    abs: f64,
}

impl UpperBoundTest {
    /// Relative part of τ_i (fraction of the tension range).
    const REL: f64 = 1e-9;
    /// Absolute part of τ_i (fraction of the data scale s).
    const ABS: f64 = 1e-12;

    fn new(ns: &NullSpace, bounds: &TensionBounds) -> Self {
        let (lo, hi) = (bounds.min(), bounds.max());
        let mut s: f64 = 1.0;
        for i in 0..ns.n {
            s = s.max(ns.t0[i].abs()).max(lo[i].abs());
            if hi[i].is_finite() {
                s = s.max(hi[i].abs());
            }
        }
        Self { abs: Self::ABS * s }
    }

    /// Whether some cable's tension at λ = `l` is at its t_max (within τ_i).
    fn some_cable_at_max(&self, ns: &NullSpace, bounds: &TensionBounds, l: P2) -> bool {
        let (lo, hi) = (bounds.min(), bounds.max());
        (0..ns.n).any(|i| {
            hi[i].is_finite()
                && ns.tension2(i, l) >= hi[i] - (Self::REL * (hi[i] - lo[i]) + self.abs)
        })
    }
}

/// Gaussian elimination with partial pivoting, in place (row-major m × m); false if singular.
fn lu_solve(a: &mut [f64], m: usize, x: &mut [f64]) -> bool {
    let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for k in 0..m {
        let mut p = k;
        for r in k + 1..m {
            if a[r * m + k].abs() > a[p * m + k].abs() {
                p = r;
            }
        }
        let piv = a[p * m + k].abs();
        if piv.is_nan() || piv <= 1e-14 * scale {
            return false;
        }
        if p != k {
            for c in 0..m {
                a.swap(k * m + c, p * m + c);
            }
            x.swap(k, p);
        }
        let piv = a[k * m + k];
        for r in k + 1..m {
            let f = a[r * m + k] / piv;
            if f != 0.0 {
                for c in k..m {
                    a[r * m + c] -= f * a[k * m + c];
                }
                x[r] -= f * x[k];
            }
        }
    }
    for k in (0..m).rev() {
        let mut s = x[k];
        for c in k + 1..m {
            s -= a[k * m + c] * x[c];
        }
        x[k] = s / a[k * m + k];
    }
    true
}

/// The SOTDA objective |d · δp(t)| of Picard, Caro, Plestan & Claveau 2020, eq. (7) at given tensions (for analysis and
/// tests); `None` when K(t) is singular.
pub fn sotda_displacement(
    stiffness: &StiffnessData,
    settings: &SotdaSettings,
    external_wrench: &DVector<f64>,
    tensions: &[f64],
) -> Result<Option<f64>, TensionError> {
    let mut s = Sotda::default();
    s.prepare(settings, stiffness, external_wrench)?;
    let f = s.displacement(stiffness, tensions)?;
    Ok(f.is_finite().then_some(f))
}

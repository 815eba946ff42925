//! # The tension solver
//!
//! [`TensionSolver`] holds a [`Method`] and every scratch buffer the methods need, so that
//! repeated calls (workspace grids, trajectories) do not allocate: [`TensionSolver::is_feasible`]
//! and [`TensionSolver::solve_into`] allocate nothing after the first call for a given problem
//! size, except for l2-max at r ≥ 3 (vertex enumeration) and a Clarabel fallback. Clone one
//! solver per thread.
//!
//! Every candidate passes [`crate::certify`] before it is returned as feasible.
//!
//! | method | r = 0 | r = 1 | r = 2 | r ≥ 3 |
//! |---|---|---|---|---|
//! | exact | QR (n ≤ 3: adjugate) | – | – | – |
//! | pinv | QR | QR | QR | QR |
//! | closed-form | – | Alg. 6.1 (DOF ≤ 3: minors, lean path) | – | – |
//! | l1, l1-max | point | interval | planar simplex from the l2 optimum, else polygon | active-set LP (Bland), from the l2 optimum |
//! | linf | point | interval | active-set LP | active-set LP (Bland), from the l2 optimum |
//! | l2 | point | interval | planar active set, else polygon | Goldfarb–Idnani dual active set |
//! | l2-max | point | interval | polygon | vertex enumeration |
//! | improved-closed-form | Pott 2014 | ← | ← | ← |
//! | barycenter | – | – | polygon by an edge walk from the l1 vertex, else clipped | – |
//! | sotda | – | – | polygon | – |
//!
//! The active-set solvers (r ≥ 3; linf from r = 2; private module `active_set`, on the null-space
//! parametrisation) fall back to Clarabel ([`crate::interior_point()`]) only on a
//! numerical failure (iteration cap, dependent working set, an answer that fails the
//! certificate, or a dual-method infeasibility that phase 1 does not confirm); such fallbacks
//! are counted by [`TensionSolver::clarabel_fallbacks`], and a Clarabel failure then names both
//! reasons in [`Infeasibility::SolverFailure`]. Measured per solve (`cargo bench -p cdpr-benches
//! --bench tension -- tension_planar_8_cable`, 8-cable planar robot, r = 5, shared machine):
//! l2 1.6–2.4 µs vs 64–80 µs with Clarabel (≈ 30×), l1 3.3–3.8 µs vs 68–77 µs (≈ 20×).

use crate::active_set::{ActiveSet, DenseEnd};
use crate::central_point;
use crate::certificate::{Certificate, snap_and_certify, snap_and_certify_fixed};
use crate::closed_form::{self, ClosedForm};
use crate::feasible_polygon::{self, Region};
use crate::improved_closed_form::ImprovedClosedForm;
use crate::infeasibility;
use crate::interior_point::{Objective, interior_point};
use crate::linear_program::{self, Linear, write_tensions};
use crate::minimum_norm::{exact_small, minimum_norm};
use crate::null_space::{self, FourQr, NullSpace};
use crate::outcome::validate;
use crate::planar_active_set::{self, Triple};
use crate::sotda::{Sotda, SotdaSettings};
use crate::vertex_enumeration::VertexSearch;
use crate::warm_point::WarmPoint;
use crate::{
    Infeasibility, Method, TensionBounds, TensionError, TensionOutcome, TensionProblem,
    TensionSolution, barycenter, quadratic_program,
};
use crate::{MethodOptions, PunctureInterior};
use crate::{dykstra::Dykstra, l2_mid::L2Mid, p_norm::PNorm, pott_closed_form::PottClosedForm};
use crate::{optimally_safe, puncture, vertex_centroid::VertexCentroid};
use nalgebra::{DMatrix, DVector};

/// Algorithm 6.1 for DOF = M ≤ 3 and n = M + 1, then the certificate (fixed sizes throughout).
/// `maximize`: the larger-Σt end (l1-max).
#[inline(always)]
fn closed_form_small<const M: usize>(
    p: &TensionProblem,
    maximize: bool,
    t: &mut [f64],
) -> Result<f64, Infeasibility> {
    closed_form::solve_small::<M>(p, maximize, t).map_err(|e| rename_unbounded(e, maximize))?;
    snap_and_certify_fixed::<M>(p.wrench_matrix, p.external_wrench, p.bounds, t)
        .map_err(certificate_failed)
}

/// `dst.copy_from_slice(src)`, element by element for up to 4 cables (a dynamic-length copy is
/// a `memcpy` call, ~1 % of the ~80 ns closed-form solve).
#[inline(always)]
fn copy_tensions(dst: &mut [f64], src: &[f64]) {
    if src.len() <= 4 {
        for (d, s) in dst.iter_mut().zip(src) {
            *d = *s;
        }
    } else {
        dst.copy_from_slice(src);
    }
}

/// Algorithm 6.1 serves l1 and l1-max at r = 1: an unbounded end is reported under l1-max.
#[cold]
fn rename_unbounded(e: Infeasibility, maximize: bool) -> Infeasibility {
    match e {
        Infeasibility::Unbounded { .. } if maximize => {
            Infeasibility::Unbounded { method: "l1-max" }
        }
        e => e,
    }
}

/// The reason for a candidate that failed the certificate.
#[cold]
fn certificate_failed(c: Certificate) -> Infeasibility {
    Infeasibility::CertificateFailed {
        residual: c.residual,
        bound_violation: c.bound_violation,
    }
}

/// A tension distribution method with reusable buffers. `Clone + Send`.
///
/// ```
/// use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
/// use nalgebra::{DMatrix, DVector};
/// let w = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, -1.0]);
/// let we = DVector::from_vec(vec![-2.0]);
/// let b = TensionBounds::uniform(3, 1.0, 10.0).unwrap();
/// let mut solver = TensionSolver::new(Method::L1);
/// let out = solver.solve(&TensionProblem::new(&w, &we, &b)).unwrap();
/// // min Σt with t1 + t2 − t3 = 2, t ≥ 1: t3 = 1, t1 + t2 = 3.
/// assert!((out.tensions().unwrap().sum() - 4.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct TensionSolver {
    method: Method,
    settings: SotdaSettings,
    ns: NullSpace,
    region: Region,
    closed: ClosedForm,
    icf: ImprovedClosedForm,
    sotda: Sotda,
    dense: ActiveSet,
    vertices: VertexSearch,
    fallbacks: u64,
    t: Vec<f64>,
    /// The null space of the current problem, already in `ns` (computed four at a time by
    /// [`TensionSolver::is_feasible_four_6x8`]); taken by `null_space`.
    prepared: Option<Result<(), f64>>,
    /// The central point of the current problem is known to fail its margin (tested four at a
    /// time by [`TensionSolver::is_feasible_four_6x8`]): `central` is not tried again.
    off_centre: bool,
    /// The last triple of bound constraints that proved a problem infeasible (l2, r = 2,
    /// `is_feasible`): grid neighbours are often infeasible for the same three cables, so it is
    /// tried before the active set. Any triple is safe to try: the proof is rigorous whatever
    /// its direction (module `infeasibility`), so this memory never changes a verdict.
    separating: Option<Triple>,
    /// The wrench-space direction of the last proof of infeasibility of a 6 × 8 problem, tried
    /// on the next four problems of [`TensionSolver::is_feasible_four_6x8`] before their null
    /// spaces (dropped after four feasible ones): as safe as `separating`.
    separating_y: Option<[f64; 6]>,
    /// The QR of the four wrench matrices of [`TensionSolver::is_feasible_four_6x8`], and the
    /// lane of the current problem: read only by a proof of infeasibility.
    four_qr: FourQr,
    lane: Option<usize>,
    /// The last certified tensions of a verdict of [`TensionSolver::is_feasible_four_6x8`] that
    /// needed more than the central point (l2, r = 2): they propose the second candidate of the
    /// next problems (module `warm_point`; it never changes a verdict).
    warm: WarmPoint,
    /// Options of the methods of issue 26 (puncture, dykstra, p-norm, optimally-safe).
    options: MethodOptions,
    pott: PottClosedForm,
    dykstra: Dykstra,
    l2_mid: L2Mid,
    centroid: VertexCentroid,
    p_norm: PNorm,
    /// The interior point of the puncture method.
    interior: Vec<f64>,
    /// Puncture's line start t0 = −W⁺ w_ext from the improved closed form's factor.
    t0: Vec<f64>,
}

impl TensionSolver {
    /// A solver for `method` (SOTDA with [`SotdaSettings::default`]).
    pub fn new(method: Method) -> Self {
        Self {
            method,
            settings: SotdaSettings::default(),
            ns: NullSpace::default(),
            region: Region::default(),
            closed: ClosedForm::default(),
            icf: ImprovedClosedForm::default(),
            sotda: Sotda::default(),
            dense: ActiveSet::default(),
            vertices: VertexSearch::default(),
            fallbacks: 0,
            t: Vec::new(),
            prepared: None,
            off_centre: false,
            separating: None,
            separating_y: None,
            four_qr: FourQr::default(),
            lane: None,
            warm: WarmPoint::default(),
            options: MethodOptions::default(),
            pott: PottClosedForm::default(),
            dykstra: Dykstra::default(),
            l2_mid: L2Mid::default(),
            centroid: VertexCentroid::default(),
            p_norm: PNorm::default(),
            interior: Vec::new(),
            t0: Vec::new(),
        }
    }

    /// This solver with `options` (puncture's interior point, dykstra's variant and cap,
    /// p-norm's exponent, optimally-safe's α; other methods ignore them), validated by
    /// [`MethodOptions::validate`].
    ///
    /// ```
    /// use cdpr_tension::{Method, MethodOptions, TensionSolver};
    /// let s = TensionSolver::new(Method::PNorm)
    ///     .with_options(MethodOptions { p: 6.0, ..Default::default() })
    ///     .unwrap();
    /// assert_eq!(s.options().p, 6.0);
    /// assert!(TensionSolver::new(Method::PNorm)
    ///     .with_options(MethodOptions { p: 1.0, ..Default::default() })
    ///     .is_err());
    /// ```
    pub fn with_options(mut self, options: MethodOptions) -> Result<Self, TensionError> {
        options.validate()?;
        self.options = options;
        Ok(self)
    }

    /// The options of the methods that take some.
    pub fn options(&self) -> &MethodOptions {
        &self.options
    }

    /// Iterations of the last dykstra solve (projection pairs) and of the last p-norm solve
    /// (Newton steps), for tests and the soak.
    pub fn iterations(&self) -> usize {
        match self.method {
            Method::Dykstra => self.dykstra.iterations,
            Method::PNorm => self.p_norm.iterations,
            _ => 0,
        }
    }

    /// A SOTDA solver with the given settings.
    pub fn sotda(settings: SotdaSettings) -> Self {
        Self {
            settings,
            ..Self::new(Method::Sotda)
        }
    }

    /// The method.
    pub fn method(&self) -> Method {
        self.method
    }

    /// The SOTDA settings (used only by [`Method::Sotda`]).
    pub fn sotda_settings(&self) -> &SotdaSettings {
        &self.settings
    }

    /// How many solves of this solver fell back from the dense active-set path (redundancy
    /// r ≥ 3, see the module docs) to Clarabel after a numerical failure.
    pub fn clarabel_fallbacks(&self) -> u64 {
        self.fallbacks
    }

    /// Solves `problem`. Errors on bad input and on a method that does not apply to the
    /// problem ([`TensionError::MethodNotApplicable`], [`TensionError::NeedsFiniteBounds`]);
    /// infeasibility is an outcome.
    pub fn solve(&mut self, problem: &TensionProblem) -> Result<TensionOutcome, TensionError> {
        Ok(match self.run(problem, false)? {
            Ok(residual) => TensionOutcome::Feasible(TensionSolution {
                tensions: DVector::from_column_slice(&self.t),
                residual,
            }),
            Err(Infeasibility::BoundsViolated {
                cable,
                tension,
                bound,
                ..
            }) => {
                // exact / pinv left t = −W⁺ w_ext in the buffer: hand it out.
                TensionOutcome::Infeasible(Infeasibility::BoundsViolated {
                    cable,
                    tension,
                    bound,
                    tensions: DVector::from_column_slice(&self.t),
                })
            }
            Err(reason) => TensionOutcome::Infeasible(reason),
        })
    }

    /// Same verdict as `solve(..).is_feasible()`, without allocating after the first call
    /// (except on the interior-point path, see the module docs).
    ///
    /// l2 at r = 2 first tries the point of the affine set t = t0 + N λ closest to the middle
    /// of the bounds: when it is well inside every bound and passes the certificate, the answer
    /// is "feasible" without the l2 optimum (issue 17; `planar_active_set::central_point`).
    /// Otherwise the method's own solve decides, so "infeasible" is always its verdict.
    #[inline]
    pub fn is_feasible(&mut self, problem: &TensionProblem) -> Result<bool, TensionError> {
        Ok(self.run(problem, true)?.is_ok())
    }

    /// [`TensionSolver::is_feasible`] of four problems whose 6 × 8 wrench matrices are given in
    /// lanes, `columns[j][i][l]` = W(i, j) of problem l (the layout of
    /// `cdpr_kinematics::Robot::wrench_matrix_lanes`), with one external wrench and one set of
    /// bounds; `w` is scratch. For the methods whose redundancy-2 path starts from the null space
    /// (l1, l1-max, l2, l2-max, barycentre) the four null spaces are computed at once in SIMD
    /// lanes, bit for bit those of the single-problem path, which then goes on problem by
    /// problem: the same verdicts. For l2 the central point of `is_feasible` and its
    /// certificate are also taken four at a time (module `central_point`): lanes it certifies
    /// are "feasible" at once, the others go on problem by problem without repeating what the
    /// lanes decided (a central point outside its margin, the finiteness of W). Problems with
    /// `wanted[l]` false are not decided (`Ok(false)`). No allocation after the first call on
    /// the fast paths.
    pub fn is_feasible_four_6x8(
        &mut self,
        columns: &[[[f64; null_space::LANES]; 6]; 8],
        wanted: [bool; null_space::LANES],
        external_wrench: &DVector<f64>,
        bounds: &TensionBounds,
        w: &mut DMatrix<f64>,
    ) -> [Result<bool, TensionError>; null_space::LANES] {
        let we = external_wrench.as_slice();
        let wanted_bits: u32 = (0..null_space::LANES)
            .map(|l| u32::from(wanted[l]) << l)
            .sum();
        // The direction of the last proof of infeasibility, on all four problems at once.
        let proved = match self.separating_y {
            Some(y) if self.method == Method::L2 && wanted_bits != 0 => {
                infeasibility::four_6x8_separated(columns, we, bounds, &y) & wanted_bits
            }
            _ => 0,
        };
        if proved != 0 && proved == wanted_bits {
            return [const { Ok(false) }; null_space::LANES];
        }
        let lanes = (matches!(
            self.method,
            Method::L1 | Method::L1Max | Method::L2 | Method::L2Max | Method::Barycenter
        ) && we.len() == 6
            && bounds.len() == 8
            && wanted.iter().any(|&x| x))
        .then(|| null_space::four_6x8(columns, we, &mut self.four_qr));
        // Bits of the lanes: certified at the central point (l2 only), central point outside
        // its margin, W finite (with w_ext finite: validated).
        let (certified, outside, valid) = match &lanes {
            Some(ns) if self.method == Method::L2 => {
                let c = central_point::four_6x8(ns, columns, we, bounds);
                let we_finite = we.iter().all(|e| e.is_finite());
                let valid = if we_finite { c.finite } else { 0 };
                // A second candidate where the central point failed (module `warm_point`).
                let todo = wanted_bits & !proved & valid & !c.certified;
                let warm = self.warm.four_6x8(ns, columns, we, bounds, todo);
                (c.certified | warm, !c.inside, valid)
            }
            _ => (0, 0, 0),
        };
        if w.shape() != (6, 8) {
            *w = DMatrix::zeros(6, 8);
        }
        let verdicts = std::array::from_fn(|l| {
            if !wanted[l] || proved >> l & 1 == 1 {
                return Ok(false);
            }
            if certified >> l & 1 == 1 {
                return Ok(true);
            }
            for (dst, column) in w.as_mut_slice().chunks_exact_mut(6).zip(columns) {
                for (d, row) in dst.iter_mut().zip(column) {
                    *d = row[l];
                }
            }
            let problem = TensionProblem::new(w, external_wrench, bounds);
            self.prepared = lanes.as_ref().map(|ns| ns.write_lane(l, &mut self.ns));
            self.lane = lanes.as_ref().map(|_| l);
            self.off_centre = outside >> l & 1 == 1;
            let verdict = if valid >> l & 1 == 1 {
                // `run` without `validate`, done in lanes (6 × 8, 8 bounds, W and w_ext
                // finite): l2 applies at r = 2 and has no lean closed-form path.
                self.run_general(&problem, 6, 8, true)
            } else {
                self.run(&problem, true)
            };
            self.prepared = None;
            self.lane = None;
            self.off_centre = false;
            verdict.map(|out| out.is_ok())
        });
        // Far from an infeasible region, trying the last direction only costs time.
        if proved == 0 && verdicts.iter().all(|v| matches!(v, Ok(true))) {
            self.separating_y = None;
        }
        verdicts
    }

    /// Like [`TensionSolver::solve`] but writes the tensions into `tensions` (resized to n) and
    /// returns the residual; no allocation after the first call on the fast paths.
    #[inline]
    pub fn solve_into(
        &mut self,
        problem: &TensionProblem,
        tensions: &mut DVector<f64>,
    ) -> Result<Result<f64, Infeasibility>, TensionError> {
        let out = self.run(problem, false)?;
        if out.is_ok() {
            if tensions.len() != self.t.len() {
                *tensions = DVector::zeros(self.t.len());
            }
            copy_tensions(tensions.as_mut_slice(), &self.t);
        }
        Ok(out)
    }

    /// The method's answer; `verdict_only`: any certified feasible point will do (see
    /// [`Self::is_feasible`]).
    #[inline]
    fn run(
        &mut self,
        p: &TensionProblem,
        verdict_only: bool,
    ) -> Result<Result<f64, Infeasibility>, TensionError> {
        validate(p)?;
        let (m, n) = p.wrench_matrix.shape();
        let r = n as isize - m as isize;
        if !self.method.applies_to(r) {
            return Err(self.method.not_applicable(r));
        }
        // Lean path of Algorithm 6.1 for DOF ≤ 3 (the thesis' planar 4-cable robot): fixed-size
        // solve and certificate, no dispatch (the same answer as the general path). At r = 1
        // Algorithm 6.1 is also the exact solver of l1 (min Σ t) and l1-max (max Σ t): Σ t is
        // linear on the feasible interval, so its optimum is the better end (issue 13 §7).
        if matches!(self.method, Method::ClosedForm | Method::L1 | Method::L1Max)
            && n == m + 1
            && m <= 3
        {
            if self.t.len() != n {
                self.t.resize(n, 0.0);
            }
            let maximize = self.method == Method::L1Max;
            return Ok(match m {
                1 => closed_form_small::<1>(p, maximize, &mut self.t),
                2 => closed_form_small::<2>(p, maximize, &mut self.t),
                _ => closed_form_small::<3>(p, maximize, &mut self.t),
            });
        }
        self.run_general(p, m, n, verdict_only)
    }

    /// Every method and size other than the lean closed-form path of [`Self::run`].
    #[inline(never)]
    fn run_general(
        &mut self,
        p: &TensionProblem,
        m: usize,
        n: usize,
        verdict_only: bool,
    ) -> Result<Result<f64, Infeasibility>, TensionError> {
        if self.method == Method::Sotda {
            self.prepare_sotda(p, m, n)?;
        }
        if self.method.needs_finite_bounds()
            && let Some(cable) = p
                .bounds
                .max()
                .as_slice()
                .iter()
                .position(|v| !v.is_finite())
        {
            return Err(TensionError::NeedsFiniteBounds {
                method: self.method,
                cable,
            });
        }
        if self.t.len() != n {
            self.t.resize(n, 0.0);
        }
        // Fixed-size exact solve (n = DOF ≤ 3); the QR path repeats it if it fails the
        // certificate (see `minimum_norm` docs).
        if self.method == Method::Exact && m == n && m <= 3 {
            let small = match m {
                1 => exact_small::<1>(p, &mut self.t),
                2 => exact_small::<2>(p, &mut self.t),
                _ => exact_small::<3>(p, &mut self.t),
            };
            match small {
                Err(reason) => return Ok(Err(reason)),
                Ok(()) => {
                    if let Ok(residual) =
                        snap_and_certify(p.wrench_matrix, p.external_wrench, p.bounds, &mut self.t)
                    {
                        return Ok(Ok(residual));
                    }
                }
            }
        }
        match self.dispatch(p, verdict_only)? {
            Err(reason) => return Ok(Err(reason)),
            Ok(Some(residual)) => return Ok(Ok(residual)),
            Ok(None) => {}
        }
        Ok(
            snap_and_certify(p.wrench_matrix, p.external_wrench, p.bounds, &mut self.t)
                .map_err(certificate_failed),
        )
    }

    /// l2, l1, l1-max and the barycentre at r = 2 by the planar active set, simplex and edge
    /// walk (module `planar_active_set`): the residual of the certified answer, or `None` when
    /// the clipped feasible polygon must decide.
    #[inline]
    fn planar(&mut self, p: &TensionProblem) -> Option<f64> {
        let l = match self.method {
            Method::L2 => planar_active_set::l2_projection(&self.ns, p.bounds)?,
            Method::L1 => planar_active_set::l1_vertex(&self.ns, p.bounds, false)?,
            Method::L1Max => planar_active_set::l1_vertex(&self.ns, p.bounds, true)?,
            Method::Barycenter => {
                let mut verts = [[0.0; 2]; planar_active_set::WALK_VERTICES];
                let k = planar_active_set::polygon_walk(&self.ns, p.bounds, &mut verts)?;
                feasible_polygon::centroid(&verts[..k])
            }
            _ => return None,
        };
        write_tensions(&self.ns, l, &mut self.t);
        snap_and_certify(p.wrench_matrix, p.external_wrench, p.bounds, &mut self.t).ok()
    }

    /// t0, N and g of `p` in `self.ns` (`Err(condition)` for a singular W): those prepared by
    /// [`Self::is_feasible_four_6x8`], else [`NullSpace::compute`].
    #[inline]
    fn null_space(&mut self, p: &TensionProblem) -> Result<(), f64> {
        match self.prepared.take() {
            Some(prepared) => prepared,
            None => self.ns.compute(p.wrench_matrix, p.external_wrench),
        }
    }

    /// Whether the three constraints of `triple` prove that no tension of `p` passes the
    /// certificate ([`infeasibility::multipliers`], then
    /// [`infeasibility::direction_proves_empty`]; `false`: not proved). A triple kept from a
    /// problem with more cables is not proved.
    fn proves_empty(&mut self, triple: Triple, p: &TensionProblem) -> bool {
        if !triple.fits(self.ns.n) {
            return false;
        }
        let planes = triple.planes(&self.ns, p.bounds);
        let Some(mu) = infeasibility::multipliers(&planes) else {
            return false;
        };
        if !self.ns.has_qr() {
            match self.lane {
                // The lane's QR, computed with its null space in `is_feasible_four_6x8`.
                Some(l) => self.four_qr.write_lane(l, &mut self.ns),
                None => {
                    if self.ns.keep_qr(p.wrench_matrix, p.external_wrench).is_err() {
                        return false;
                    }
                }
            }
        }
        match infeasibility::direction_proves_empty(
            &planes,
            &mu,
            &self.ns,
            p.wrench_matrix,
            p.external_wrench,
            p.bounds,
        ) {
            Some(y) => {
                if p.wrench_matrix.shape() == (6, 8) {
                    self.separating_y = Some(y);
                }
                true
            }
            None => false,
        }
    }

    /// The certified residual of [`planar_active_set::central_point`] (r = 2), if any.
    #[inline]
    fn central(&mut self, p: &TensionProblem) -> Option<f64> {
        let l = planar_active_set::central_point(&self.ns, p.bounds)?;
        write_tensions(&self.ns, l, &mut self.t);
        snap_and_certify(p.wrench_matrix, p.external_wrench, p.bounds, &mut self.t).ok()
    }

    /// Clarabel after a numerical failure of the dense active-set path (`why`), counted in
    /// [`Self::clarabel_fallbacks`]; a Clarabel failure reports both reasons.
    #[cold]
    fn clarabel_fallback(
        &mut self,
        p: &TensionProblem,
        objective: Objective,
        why: &'static str,
    ) -> Result<Result<(), Infeasibility>, TensionError> {
        self.fallbacks += 1;
        Ok(match interior_point(p, objective)? {
            Ok(t) => {
                self.t.copy_from_slice(t.as_slice());
                Ok(())
            }
            Err(Infeasibility::SolverFailure { detail }) => Err(Infeasibility::SolverFailure {
                detail: format!("dense active set: {why}; clarabel fallback: {detail}"),
            }),
            Err(reason) => Err(reason),
        })
    }

    #[cold]
    fn prepare_sotda(
        &mut self,
        p: &TensionProblem,
        m: usize,
        n: usize,
    ) -> Result<(), TensionError> {
        let s = p.stiffness.as_ref().ok_or(TensionError::MissingStiffness)?;
        if s.kinematics.cable_count() != n {
            return Err(TensionError::DimensionMismatch {
                what: "sotda: kinematics cables vs wrench matrix columns",
                expected: n,
                found: s.kinematics.cable_count(),
            });
        }
        if s.kinematics.motion().dof() != m {
            return Err(TensionError::DimensionMismatch {
                what: "sotda: motion pattern DOF vs wrench matrix rows",
                expected: m,
                found: s.kinematics.motion().dof(),
            });
        }
        if s.axial_stiffness.len() != n {
            return Err(TensionError::DimensionMismatch {
                what: "sotda: axial stiffness per cable",
                expected: n,
                found: s.axial_stiffness.len(),
            });
        }
        self.sotda.prepare(&self.settings, s, p.external_wrench)
    }

    /// The methods of issue 26 on the null space in `self.ns` (tensions in `self.t`, not yet
    /// certified).
    fn peer(&mut self, p: &TensionProblem) -> Result<(), Infeasibility> {
        let (ns, bounds, t) = (&self.ns, p.bounds, &mut self.t[..]);
        let o = self.options;
        match self.method {
            Method::PottClosedForm => self.pott.solve(ns, bounds, false, t),
            Method::PottClosedFormEe => self.pott.solve(ns, bounds, true, t),
            Method::Puncture => {
                // `--interior cf`, or the improved closed form found nothing
                // ([`Self::puncture_icf`]): the closed form; a bound violation does not
                // matter, only the line counts.
                self.interior.resize(ns.n, 0.0);
                let _ = self.pott.solve(ns, bounds, false, &mut self.interior);
                puncture::solve(&ns.t0, &self.interior, bounds, t)
            }
            Method::Dykstra => {
                self.dykstra
                    .solve(ns, bounds, o.alternating, o.max_iterations, false, t)
            }
            Method::L2Mid => self.l2_mid.solve(ns, bounds, &mut self.dense, t),
            Method::VertexCentroid => match self.centroid.solve(ns, bounds, t) {
                Err(Infeasibility::NoFeasibleTension) => {
                    // No vertex: confirm before answering. At r = 2 the clipped feasible
                    // polygon decides an empty set, as it does for l2 and the barycentre
                    // (about a third of the dense active set's instructions on issue 26's
                    // infeasible poses); a polygon that is not empty, and every other r, go
                    // to the dense active set (l2).
                    if ns.r() == 2 && !self.region.build(ns, bounds) {
                        return Err(Infeasibility::NoFeasibleTension);
                    }
                    match self.dense.solve(ns, bounds, Objective::L2, "l2", t) {
                        DenseEnd::Infeasible(reason) => Err(reason),
                        DenseEnd::Solved => Err(Infeasibility::SolverFailure {
                            detail: "vertex-centroid: no vertex found on a non-empty set"
                                .to_string(),
                        }),
                        DenseEnd::Failed(why) => Err(Infeasibility::SolverFailure {
                            detail: format!("vertex-centroid: no vertex found, and {why}"),
                        }),
                    }
                }
                other => other,
            },
            Method::PNorm if bounds.min().iter().zip(bounds.max()).any(|(l, h)| l == h) => {
                self.p_norm_fixed_cables(p)
            }
            Method::PNorm => {
                self.p_norm
                    .solve(ns, bounds, o.p, o.max_iterations, &mut self.dense, t)
            }
            Method::OptimallySafe => {
                optimally_safe::solve(ns, bounds, o.alpha, &mut self.dense, t).map(|_| ())
            }
            _ => unreachable!("only the methods of issue 26"),
        }
    }

    /// p-norm with cables fixed at t_min = t_max, which leave the feasible set no interior for
    /// the log barriers: each fixed cable is moved into the load (w' = w_ext + Σ_fixed w_i t_i)
    /// and p-norm runs on the other cables (their own null space). A fixed cable's term
    /// |t_i − t_m,i|^p is 0 on the whole feasible set, so the reduced optimum is the optimum.
    /// Fewer free cables than DOF, or a singular reduced W, is still the documented give-up
    /// `EmptyInterior` (allocates: a cold path).
    #[cold]
    fn p_norm_fixed_cables(&mut self, p: &TensionProblem) -> Result<(), Infeasibility> {
        let give_up = Infeasibility::GaveUp {
            method: "p-norm",
            reason: crate::GiveUp::EmptyInterior,
        };
        let (lo, hi) = (p.bounds.min(), p.bounds.max());
        let (m, n) = p.wrench_matrix.shape();
        let free: Vec<usize> = (0..n).filter(|&i| lo[i] != hi[i]).collect();
        if free.len() < m {
            return Err(give_up);
        }
        let w = p.wrench_matrix.select_columns(free.iter());
        let mut load = p.external_wrench.clone();
        for i in (0..n).filter(|&i| lo[i] == hi[i]) {
            load.axpy(lo[i], &p.wrench_matrix.column(i), 1.0);
            self.t[i] = lo[i];
        }
        let Ok(bounds) = TensionBounds::new(
            free.iter().map(|&i| lo[i]).collect(),
            free.iter().map(|&i| hi[i]).collect(),
        ) else {
            return Err(give_up);
        };
        let mut ns = NullSpace::default();
        if ns.compute(&w, &load).is_err() {
            return Err(give_up);
        }
        let mut t = vec![0.0; free.len()];
        let o = self.options;
        self.p_norm
            .solve(&ns, &bounds, o.p, o.max_iterations, &mut self.dense, &mut t)?;
        for (&i, ti) in free.iter().zip(t) {
            self.t[i] = ti;
        }
        Ok(())
    }

    /// Puncture towards the improved closed form (`--interior icf`, the default): the line
    /// start t0 = −W⁺ w_ext comes from the improved closed form's first L D Lᵀ factor of W Wᵀ
    /// (no null-space basis) where its Hadamard ratio is at least 10⁻³, else from the QR null
    /// space; where the improved closed form finds no interior point the closed form on the
    /// null space is the interior, as with `--interior cf` ([`Self::peer`]).
    fn puncture_icf(
        &mut self,
        p: &TensionProblem,
    ) -> Result<Result<Option<f64>, Infeasibility>, TensionError> {
        let n = self.t.len();
        self.interior.resize(n, 0.0);
        self.t0.resize(n, 0.0);
        let found = self
            .icf
            .solve_and_minimum_norm(p, &mut self.interior, &mut self.t0)
            .is_ok();
        let answer = if found && self.t0.iter().all(|v| v.is_finite()) {
            puncture::solve(&self.t0, &self.interior, p.bounds, &mut self.t)
        } else {
            if let Err(condition) = self.null_space(p) {
                return Ok(Err(Infeasibility::SingularPose { condition }));
            }
            let (ns, bounds, t) = (&self.ns, p.bounds, &mut self.t[..]);
            if found {
                puncture::solve(&ns.t0, &self.interior, bounds, t)
            } else {
                let _ = self.pott.solve(ns, bounds, false, &mut self.interior);
                puncture::solve(&ns.t0, &self.interior, bounds, t)
            }
        };
        Ok(answer.map(|()| None))
    }

    /// The answer of the method: `Ok(Some(residual))` when it is certified already, `Ok(None)`
    /// when the tensions in `self.t` still need their certificate.
    fn dispatch(
        &mut self,
        p: &TensionProblem,
        verdict_only: bool,
    ) -> Result<Result<Option<f64>, Infeasibility>, TensionError> {
        let r = p.redundancy();
        let method = self.method;
        let answer = match method {
            Method::Exact | Method::Pinv => minimum_norm(&mut self.ns, p, &mut self.t),
            Method::ClosedForm => self.closed.solve(p, false, &mut self.t),
            Method::L1 | Method::L1Max if r == 1 => {
                let maximize = method == Method::L1Max;
                self.closed
                    .solve(p, maximize, &mut self.t)
                    .map_err(|e| rename_unbounded(e, maximize))
            }
            Method::ImprovedClosedForm => self.icf.solve(p, &mut self.t),
            Method::PottClosedForm | Method::PottClosedFormEe => {
                let energy_efficient = method == Method::PottClosedFormEe;
                match self
                    .pott
                    .solve_fast(&mut self.icf, p, energy_efficient, &mut self.t)
                {
                    Some(answer) => answer,
                    None => {
                        if let Err(condition) = self.null_space(p) {
                            return Ok(Err(Infeasibility::SingularPose { condition }));
                        }
                        self.peer(p)
                    }
                }
            }
            Method::Puncture if self.options.interior == PunctureInterior::ImprovedClosedForm => {
                return self.puncture_icf(p);
            }
            Method::Puncture
            | Method::Dykstra
            | Method::L2Mid
            | Method::VertexCentroid
            | Method::PNorm
            | Method::OptimallySafe => {
                if let Err(condition) = self.null_space(p) {
                    return Ok(Err(Infeasibility::SingularPose { condition }));
                }
                self.peer(p)
            }
            // linf at r = 2 too: the active-set LP is exact and about 3.5 times cheaper than
            // bisection on the feasible polygon (issue 17, IPAnema 1: 22 000 against 78 000
            // instructions per solve).
            Method::L1 | Method::L1Max | Method::L2 | Method::Linf
                if r > 2 || (r == 2 && method == Method::Linf) =>
            {
                let objective = match method {
                    Method::L1 => Objective::L1,
                    Method::L1Max => Objective::L1Max,
                    Method::L2 => Objective::L2,
                    _ => Objective::Linf,
                };
                if let Err(condition) = self.null_space(p) {
                    return Ok(Err(Infeasibility::SingularPose { condition }));
                }
                let why = match self.dense.solve(
                    &self.ns,
                    p.bounds,
                    objective,
                    method.name(),
                    &mut self.t,
                ) {
                    DenseEnd::Infeasible(reason) => return Ok(Err(reason)),
                    DenseEnd::Solved => {
                        // Certified here so that a numerical failure can still fall back.
                        match snap_and_certify(
                            p.wrench_matrix,
                            p.external_wrench,
                            p.bounds,
                            &mut self.t,
                        ) {
                            Ok(residual) => return Ok(Ok(Some(residual))),
                            Err(_) => "dense answer failed the certificate",
                        }
                    }
                    DenseEnd::Failed(why) => why,
                };
                self.clarabel_fallback(p, objective, why)?
            }
            Method::L2Max if r > 2 => {
                if let Err(condition) = self.null_space(p) {
                    return Ok(Err(Infeasibility::SingularPose { condition }));
                }
                quadratic_program::l2_max_high_redundancy(
                    p,
                    &self.ns,
                    &mut self.dense,
                    &mut self.vertices,
                    &mut self.t,
                )
            }
            _ => {
                if let Err(condition) = self.null_space(p) {
                    return Ok(Err(Infeasibility::SingularPose { condition }));
                }
                if verdict_only
                    && method == Method::L2
                    && r == 2
                    && !self.off_centre
                    && let Some(residual) = self.central(p)
                {
                    return Ok(Ok(Some(residual)));
                }
                if verdict_only && method == Method::L2 && r == 2 {
                    if let Some(triple) = self.separating
                        && self.proves_empty(triple, p)
                    {
                        return Ok(Err(Infeasibility::NoFeasibleTension));
                    }
                    match planar_active_set::l2_search(&self.ns, p.bounds) {
                        Ok(l) => {
                            write_tensions(&self.ns, l, &mut self.t);
                            if let Ok(residual) = snap_and_certify(
                                p.wrench_matrix,
                                p.external_wrench,
                                p.bounds,
                                &mut self.t,
                            ) {
                                if self.lane.is_some() {
                                    // A grid's problem (`is_feasible_four_6x8`): its
                                    // neighbours' second candidate (module `warm_point`).
                                    self.warm.remember(&self.t);
                                }
                                return Ok(Ok(Some(residual)));
                            }
                        }
                        // No tension passes the certificate: the verdict of every solve.
                        Err(Some(triple)) if self.proves_empty(triple, p) => {
                            self.separating = Some(triple);
                            return Ok(Err(Infeasibility::NoFeasibleTension));
                        }
                        Err(_) => {}
                    }
                } else if matches!(
                    method,
                    Method::L2 | Method::L1 | Method::L1Max | Method::Barycenter
                ) && r == 2
                    && let Some(residual) = self.planar(p)
                {
                    return Ok(Ok(Some(residual)));
                }
                if !self.region.build(&self.ns, p.bounds) {
                    return Ok(Err(Infeasibility::NoFeasibleTension));
                }
                let (ns, region, t) = (&self.ns, &mut self.region, &mut self.t[..]);
                let name = method.name();
                match method {
                    Method::L1 => linear_program::solve_on_region(
                        Linear::MinSum,
                        ns,
                        region,
                        p.bounds,
                        name,
                        t,
                    ),
                    Method::L1Max => linear_program::solve_on_region(
                        Linear::MaxSum,
                        ns,
                        region,
                        p.bounds,
                        name,
                        t,
                    ),
                    Method::Linf => linear_program::solve_on_region(
                        Linear::MinMax,
                        ns,
                        region,
                        p.bounds,
                        name,
                        t,
                    ),
                    Method::L2 => quadratic_program::solve_on_region(false, ns, region, name, t),
                    Method::L2Max => quadratic_program::solve_on_region(true, ns, region, name, t),
                    Method::Barycenter => barycenter::solve_on_region(ns, region, t),
                    Method::Sotda => {
                        let s = p.stiffness.as_ref().ok_or(TensionError::MissingStiffness)?;
                        self.sotda
                            .solve_on_region(&self.settings, s, ns, region, p.bounds, t)?
                    }
                    _ => unreachable!("all other methods are dispatched above"),
                }
            }
        };
        Ok(answer.map(|()| None))
    }
}

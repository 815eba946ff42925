//! # The tension solver
//!
//! [`TensionSolver`] holds a [`Method`] and every scratch buffer the methods need, so that
//! repeated calls (workspace grids, trajectories) do not allocate: [`TensionSolver::is_feasible`]
//! allocates nothing after the first call for a given problem size, except on the
//! interior-point path (redundancy ≥ 3 for l1, l1-max, l2, linf; l2-max at r ≥ 3 enumerates
//! vertices with allocation). Clone one solver per thread.
//!
//! Every candidate passes [`crate::certify`] before it is returned as feasible.
//!
//! | method | r = 0 | r = 1 | r = 2 | r ≥ 3 |
//! |---|---|---|---|---|
//! | exact | QR | – | – | – |
//! | pinv | QR | QR | QR | QR |
//! | closed-form | – | Alg. 6.1 | – | – |
//! | l1, l1-max, l2, l2-max, linf | point | interval | polygon | Clarabel (l2-max: vertices) |
//! | improved-closed-form | Pott 2014 | ← | ← | ← |
//! | barycenter, sotda | – | – | polygon | – |

use crate::certificate::snap_and_certify;
use crate::closed_form::ClosedForm;
use crate::feasible_polygon::Region;
use crate::improved_closed_form::ImprovedClosedForm;
use crate::interior_point::{Objective, interior_point};
use crate::linear_program::{self, Linear};
use crate::minimum_norm::{exact_small, minimum_norm};
use crate::null_space::NullSpace;
use crate::outcome::validate;
use crate::sotda::{Sotda, SotdaSettings};
use crate::{
    Infeasibility, Method, TensionError, TensionOutcome, TensionProblem, TensionSolution,
    barycenter, quadratic_program,
};
use nalgebra::DVector;

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
    t: Vec<f64>,
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
            t: Vec::new(),
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

    /// Solves `problem`. Errors only on bad input; infeasibility is an outcome.
    pub fn solve(&mut self, problem: &TensionProblem) -> Result<TensionOutcome, TensionError> {
        Ok(match self.run(problem)? {
            Ok(residual) => TensionOutcome::Feasible(TensionSolution {
                tensions: DVector::from_column_slice(&self.t),
                residual,
            }),
            Err(reason) => TensionOutcome::Infeasible(reason),
        })
    }

    /// Same verdict as `solve(..).is_feasible()`, without allocating after the first call
    /// (except on the interior-point path, see the module docs).
    #[inline]
    pub fn is_feasible(&mut self, problem: &TensionProblem) -> Result<bool, TensionError> {
        Ok(self.run(problem)?.is_ok())
    }

    /// Like [`TensionSolver::solve`] but writes the tensions into `tensions` (resized to n) and
    /// returns the residual; no allocation after the first call on the fast paths.
    #[inline]
    pub fn solve_into(
        &mut self,
        problem: &TensionProblem,
        tensions: &mut DVector<f64>,
    ) -> Result<Result<f64, Infeasibility>, TensionError> {
        let out = self.run(problem)?;
        if out.is_ok() {
            if tensions.len() != self.t.len() {
                *tensions = DVector::zeros(self.t.len());
            }
            tensions.as_mut_slice().copy_from_slice(&self.t);
        }
        Ok(out)
    }

    #[inline]
    fn run(&mut self, p: &TensionProblem) -> Result<Result<f64, Infeasibility>, TensionError> {
        validate(p)?;
        let (m, n) = p.wrench_matrix.shape();
        if self.method == Method::Sotda {
            self.prepare_sotda(p, m, n)?;
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
        if let Err(reason) = self.dispatch(p)? {
            return Ok(Err(reason));
        }
        Ok(
            snap_and_certify(p.wrench_matrix, p.external_wrench, p.bounds, &mut self.t).map_err(
                |c| Infeasibility::CertificateFailed {
                    residual: c.residual,
                    bound_violation: c.bound_violation,
                },
            ),
        )
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

    fn dispatch(&mut self, p: &TensionProblem) -> Result<Result<(), Infeasibility>, TensionError> {
        let r = p.redundancy();
        let method = self.method;
        let na = Err(Infeasibility::NotApplicable {
            method: method.name(),
            redundancy: r,
        });
        if r < 0 {
            return Ok(na);
        }
        Ok(match method {
            Method::Exact if r != 0 => na,
            Method::Exact | Method::Pinv => minimum_norm(&mut self.ns, p, &mut self.t),
            Method::ClosedForm if r != 1 => na,
            Method::ClosedForm => self.closed.solve(p, false, &mut self.t),
            Method::ImprovedClosedForm => self.icf.solve(p, &mut self.t),
            Method::Barycenter | Method::Sotda if r != 2 => na,
            Method::L1 | Method::L1Max | Method::L2 | Method::Linf if r > 2 => {
                let objective = match method {
                    Method::L1 => Objective::L1,
                    Method::L1Max => Objective::L1Max,
                    Method::L2 => Objective::L2,
                    _ => Objective::Linf,
                };
                interior_point(p, objective)?.map(|t| self.t.copy_from_slice(t.as_slice()))
            }
            Method::L2Max if r > 2 => {
                if let Err(condition) = self.ns.compute(p.wrench_matrix, p.external_wrench) {
                    return Ok(Err(Infeasibility::SingularPose { condition }));
                }
                quadratic_program::l2_max_by_vertices(&self.ns, p.bounds, &mut self.t)
            }
            _ => {
                if let Err(condition) = self.ns.compute(p.wrench_matrix, p.external_wrench) {
                    return Ok(Err(Infeasibility::SingularPose { condition }));
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
                            .solve_on_region(&self.settings, s, ns, region, t)?
                    }
                    _ => unreachable!("all other methods are dispatched above"),
                }
            }
        })
    }
}

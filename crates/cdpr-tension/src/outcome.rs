//! # Problems and outcomes
//!
//! The input of every method ([`TensionProblem`]) and its result ([`TensionOutcome`]):
//! infeasibility is a value with a reason ([`Infeasibility`]), never an error.

use crate::{TensionBounds, TensionError};
use cdpr_kinematics::PoseKinematics;
use nalgebra::{DMatrix, DVector};
use std::fmt;

/// A tension distribution problem: find t with W t + w_ext = 0 and t_min ≤ t ≤ t_max.
#[derive(Debug, Clone, Copy)]
pub struct TensionProblem<'a> {
    /// W, DOF × n (thesis eq. (6.11): S; Picard, Caro, Plestan & Claveau 2020, eq. (2)).
    pub wrench_matrix: &'a DMatrix<f64>,
    /// w_ext, length DOF: the wrench applied to the platform (W t + w_ext = 0).
    pub external_wrench: &'a DVector<f64>,
    /// Per-cable bounds.
    pub bounds: &'a TensionBounds,
    /// Only [`crate::Method::Sotda`] needs it.
    pub stiffness: Option<StiffnessData<'a>>,
}

impl<'a> TensionProblem<'a> {
    /// A problem without stiffness data.
    pub fn new(
        wrench_matrix: &'a DMatrix<f64>,
        external_wrench: &'a DVector<f64>,
        bounds: &'a TensionBounds,
    ) -> Self {
        Self {
            wrench_matrix,
            external_wrench,
            bounds,
            stiffness: None,
        }
    }

    /// Redundancy r = n − DOF.
    pub fn redundancy(&self) -> isize {
        self.wrench_matrix.ncols() as isize - self.wrench_matrix.nrows() as isize
    }
}

/// What SOTDA needs to build the stiffness matrix K = Kp + Ka (Picard, Caro, Plestan & Claveau 2020, eq. (4)).
#[derive(Debug, Clone, Copy)]
pub struct StiffnessData<'a> {
    /// The inverse kinematics at the pose W was built from.
    pub kinematics: &'a PoseKinematics,
    /// E·S per cable (N); k_i = E·S / l_i.
    pub axial_stiffness: &'a [f64],
}

/// A certified tension distribution.
#[derive(Debug, Clone, PartialEq)]
pub struct TensionSolution {
    /// Cable tensions t (same unit as the wrench).
    pub tensions: DVector<f64>,
    /// ‖W t + w_ext‖∞ (certified ≤ 10⁻⁹ · scale, see [`crate::certify`]).
    pub residual: f64,
}

/// Why no tension distribution was returned.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Infeasibility {
    /// The feasible set {t : W t + w_ext = 0, t_min ≤ t ≤ t_max} is empty.
    NoFeasibleTension,
    /// exact / pinv: the unique (6.12) or minimum-norm (6.14) solution balances the wrench but
    /// breaks a bound of `cable`.
    BoundsViolated {
        /// Cable with the largest relative violation (0-based).
        cable: usize,
        /// Its tension.
        tension: f64,
        /// The bound it breaks: its t_min when `tension` is below it, else its t_max.
        bound: f64,
        /// The whole solution t = −W⁺ w_ext (W t + w_ext = 0, bounds not met); filled by
        /// [`crate::TensionSolver::solve`] (empty from the non-allocating calls).
        tensions: DVector<f64>,
    },
    /// W is rank-deficient or ill-conditioned (`condition` = 1/Hadamard ratio, see
    /// `null_space` docs; singular above 10¹⁰).
    SingularPose {
        /// Condition estimate (∞ for an exactly rank-deficient W).
        condition: f64,
    },
    /// A maximisation over an unbounded feasible set (some t_max = ∞).
    Unbounded {
        /// Method name.
        method: &'static str,
    },
    /// A heuristic method (improved closed form) found no feasible tension; the feasible set may
    /// still be non-empty.
    Inconclusive {
        /// Method name.
        method: &'static str,
    },
    /// The candidate tensions failed the certificate (see [`crate::certify`]); this happens
    /// only at 10⁻⁹ margins of the feasible set.
    CertificateFailed {
        /// ‖W t + w_ext‖∞ of the candidate.
        residual: f64,
        /// Its largest relative bound violation.
        bound_violation: f64,
    },
    /// The numerical solver failed.
    SolverFailure {
        /// What happened.
        detail: String,
    },
    /// An iterative or interior method stopped by its documented rule without a verdict
    /// (iteration cap, a feasible set without interior, too many vertices): the feasible set
    /// may or may not be empty. Counted apart from "infeasible" verdicts.
    GaveUp {
        /// Method name.
        method: &'static str,
        /// Which rule stopped it.
        reason: GiveUp,
    },
}

/// The documented rule by which a method of [`Infeasibility::GaveUp`] stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum GiveUp {
    /// The iteration cap was reached (dykstra, p-norm).
    IterationLimit {
        /// The cap.
        iterations: usize,
    },
    /// The method needs a strictly interior point and the feasible set has none (p-norm; or
    /// puncture from a degenerate interior point).
    EmptyInterior,
    /// More candidate vertex bases than the cap (vertex-centroid at a high redundancy).
    TooManyBases {
        /// Candidate bases C(n, r)·2^r.
        bases: u128,
    },
}

impl fmt::Display for GiveUp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::IterationLimit { iterations } => {
                write!(f, "iteration cap of {iterations} reached")
            }
            Self::EmptyInterior => f.write_str("the feasible set has no interior point"),
            Self::TooManyBases { bases } => {
                write!(f, "{bases} candidate vertex bases exceed the cap")
            }
        }
    }
}

/// A value rounded to 6 significant digits for a message (`157.000001` → `157`).
fn significant(v: f64) -> f64 {
    format!("{v:.5e}").parse().unwrap_or(v)
}

impl fmt::Display for Infeasibility {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoFeasibleTension => f.write_str(
                "no tensions within the bounds balance the external wrench (empty feasible set)",
            ),
            Self::BoundsViolated {
                cable,
                tension,
                bound,
                ..
            } => write!(
                f,
                "the solution needs cable {} at {} N, {} its {} of {} N",
                cable + 1,
                significant(*tension),
                if tension < bound { "below" } else { "above" },
                if tension < bound { "t_min" } else { "t_max" },
                significant(*bound)
            ),
            Self::SingularPose { condition } => write!(
                f,
                "the wrench matrix is singular at this pose (condition ≈ {condition:.3e})"
            ),
            Self::Unbounded { method } => write!(
                f,
                "method {method}: the feasible set is unbounded (infinite t_max)"
            ),
            Self::Inconclusive { method } => write!(
                f,
                "method {method} found no feasible tensions (heuristic: a feasible set may exist)"
            ),
            Self::CertificateFailed {
                residual,
                bound_violation,
            } => write!(
                f,
                "candidate tensions failed the certificate (residual {residual:.3e}, relative bound violation {bound_violation:.3e})"
            ),
            Self::SolverFailure { detail } => write!(f, "solver failure: {detail}"),
            Self::GaveUp { method, reason } => write!(
                f,
                "method {method} gave up ({reason}); the feasible set may still be non-empty"
            ),
        }
    }
}

/// The result of a tension distribution method.
#[derive(Debug, Clone, PartialEq)]
pub enum TensionOutcome {
    /// Certified tensions.
    Feasible(TensionSolution),
    /// No tensions, and why.
    Infeasible(Infeasibility),
}

impl TensionOutcome {
    /// Whether tensions were found.
    pub fn is_feasible(&self) -> bool {
        matches!(self, Self::Feasible(_))
    }

    /// The tensions, if feasible.
    pub fn tensions(&self) -> Option<&DVector<f64>> {
        match self {
            Self::Feasible(s) => Some(&s.tensions),
            Self::Infeasible(_) => None,
        }
    }

    /// Tensions that balance the wrench: the certified ones if feasible, else the exact / pinv
    /// solution t = −W⁺ w_ext that breaks a bound ([`Infeasibility::BoundsViolated`]).
    pub fn balancing_tensions(&self) -> Option<&DVector<f64>> {
        match self {
            Self::Feasible(s) => Some(&s.tensions),
            Self::Infeasible(Infeasibility::BoundsViolated { tensions, .. }) => Some(tensions),
            Self::Infeasible(_) => None,
        }
    }

    /// The reason, if infeasible.
    pub fn infeasibility(&self) -> Option<&Infeasibility> {
        match self {
            Self::Feasible(_) => None,
            Self::Infeasible(r) => Some(r),
        }
    }
}

/// Whether every entry is finite (branch-free, one pass).
#[inline]
fn all_finite(s: &[f64]) -> bool {
    s.iter().fold(true, |ok, v| ok & v.is_finite())
}

/// Checks shapes and finiteness of a problem (bounds are validated by [`TensionBounds`]).
/// One branch-free pass over W and w_ext; the offending entry is located only on failure.
#[inline]
pub(crate) fn validate(problem: &TensionProblem) -> Result<(), TensionError> {
    let (m, n) = problem.wrench_matrix.shape();
    if m != 0
        && problem.external_wrench.len() == m
        && problem.bounds.len() == n
        && all_finite(problem.wrench_matrix.as_slice())
        && all_finite(problem.external_wrench.as_slice())
    {
        return Ok(());
    }
    validate_slow(problem)
}

#[cold]
fn validate_slow(problem: &TensionProblem) -> Result<(), TensionError> {
    let w = problem.wrench_matrix;
    let (m, n) = w.shape();
    if m == 0 {
        return Err(TensionError::DimensionMismatch {
            what: "wrench matrix rows (DOF)",
            expected: problem.external_wrench.len().max(1),
            found: 0,
        });
    }
    if problem.external_wrench.len() != m {
        return Err(TensionError::DimensionMismatch {
            what: "external wrench length vs wrench matrix rows",
            expected: m,
            found: problem.external_wrench.len(),
        });
    }
    if problem.bounds.len() != n {
        return Err(TensionError::DimensionMismatch {
            what: "tension bounds vs wrench matrix columns",
            expected: n,
            found: problem.bounds.len(),
        });
    }
    if let Some((index, &value)) = w.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(TensionError::NotFinite {
            what: "wrench matrix entry (column-major index)",
            index,
            value,
        });
    }
    if let Some((index, &value)) = problem
        .external_wrench
        .iter()
        .enumerate()
        .find(|(_, v)| !v.is_finite())
    {
        return Err(TensionError::NotFinite {
            what: "external wrench component",
            index,
            value,
        });
    }
    Ok(())
}

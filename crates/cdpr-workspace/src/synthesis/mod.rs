//! # Dimensional synthesis (the thesis chapter on planar tendon-driven manipulators, §6.6)
//!
//! Place the frame anchors of a planar cable robot on the 2 × 2 square frame so that the dextrous
//! workspace is as large as possible (eq. (6.29)):
//!
//! max_**d** A(W^D[φ_min, φ_max]) such that the anchors are at least β_min apart,
//!
//! with design vector **d** = [β^1, …, β^n] (polar angles of the anchors, rad; see [`design`]).
//! The objective is a grid-based area ([`objective::DextrousArea`]), hence piecewise constant and
//! noisy and has several local maxima, so three optimisers are offered:
//!
//! - [`dynamic_q`]: the thesis' Dynamic-Q method (successive spherical quadratic approximations
//!   with a move limit, gradients by central differences over a wide interval Γ that smooths the
//!   grid noise);
//! - [`compass_search`]: a derivative-free compass (pattern) search with restarts, robust on
//!   plateaus; [`Method::DynamicQThenCompass`] polishes the Dynamic-Q answer with it;
//! - [`multi_start`]: the global stage of [`Method::Global`]: quasi-random designs over the whole
//!   admissible set of the start's cyclic order (a circle of rotations times a simplex of gaps
//!   ≥ β_min), the best few polished by the compass search, the best of all kept.
//!
//! ## Constraint handling for eq. (6.29)
//! The separation s_ij = min(δ, 2π − δ), δ = (β^j − β^i) mod 2π, is piecewise linear in **d**.
//! Dynamic-Q, like the original, approximates every constraint at each iterate; here the
//! approximation is the exact local linearisation, and the subproblem (spherical quadratic
//! objective, linear constraints, box move limit) is solved exactly as a Euclidean projection
//! (Dykstra's algorithm). An infeasible start (several published starting designs violate
//! β_min = 10°) is thus pulled to feasibility within the move limit. The compass search uses the
//! exact ℓ1 penalty −A + μ Σ max(0, β_min − s_ij) with a large μ ([`SynthesisSettings::penalty`]).
//!
//! **Cable order.** Both optimisers keep the start's [`cyclic_order`] of the anchors: a design
//! with another order is inadmissible. Eq. (6.29) constrains the pairs (i, i+1) and (n, 1) by
//! index, "the angle between consecutive cable attachment points", which are the neighbours
//! around the frame only while the order is kept. No continuous path satisfying eq. (6.29)
//! changes the order, so a gradient method such as Dynamic-Q never does; a compass poll or a
//! restart offset could jump an anchor past its neighbour, making cables cross and leaving the
//! new neighbours unconstrained. Such polls and offsets are rejected, and the global stage
//! samples only designs in the start's order. To explore another topology, start from a design
//! in that order.
//!
//! ```
//! use cdpr_workspace::synthesis::{synthesise, Method, SynthesisSettings};
//! // A smooth stand-in for the area: maximal at β = [0.5, 2.5, 4.5].
//! let mut area = |d: &[f64]| 1.0 - (d[0] - 0.5).powi(2) - (d[1] - 2.5).powi(2) - (d[2] - 4.5).powi(2);
//! let settings = SynthesisSettings { method: Method::DynamicQ, ..SynthesisSettings::default() };
//! let result = synthesise(&mut area, &[0.3, 2.8, 4.2], &settings).unwrap();
//! assert!((result.design[1] - 2.5).abs() < 1e-3);
//! assert!(result.evaluations.gradient > 0);
//! ```
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators, §6.6, eq. (6.29), Tables 6.5–6.10.
//! - A. H. G. Rinnooy Kan and G. T. Timmer, "Stochastic global optimization methods part I:
//!   clustering methods", *Mathematical Programming* 39 (1987) 27–56 (multi-start).
//! - J. A. Snyman and A. M. Hay, "The Dynamic-Q optimization method: an alternative to SQP?",
//!   *Computers & Mathematics with Applications* 44 (2002) 1589–1598.
//! - T. G. Kolda, R. M. Lewis and V. Torczon, "Optimization by direct search: new perspectives on
//!   some classical and modern methods", *SIAM Review* 45 (2003) 385–482.

pub mod compass_search;
pub mod design;
pub mod dynamic_q;
pub mod multi_start;
pub mod objective;
mod projection;

pub use compass_search::CompassSettings;
pub use design::{
    cables_clear_platform, cyclic_order, frame_anchor, in_first_turn, robot_from_design,
    same_cyclic_order, separation_violation, thesis_platform,
};
pub use dynamic_q::DynamicQSettings;
pub use multi_start::MultiStartSettings;
pub use objective::{DextrousArea, Objective};

use cdpr_kinematics::KinematicsError;
use thiserror::Error;

/// What can go wrong when setting up a synthesis.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SynthesisError {
    /// The design vector has no angles.
    #[error("the design vector is empty")]
    EmptyDesign,
    /// A design angle is NaN or infinite.
    #[error("design angle β^{} is not finite ({value})", index + 1)]
    NotFinite {
        /// 0-based index of the angle.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// Design and platform have different numbers of cables.
    #[error("the design has {found} angles but the platform has {expected} attachments")]
    DimensionMismatch {
        /// Number of platform attachments.
        expected: usize,
        /// Number of design angles.
        found: usize,
    },
    /// A setting is out of its domain.
    #[error("setting `{name}` = {value} is invalid: {reason}")]
    InvalidSetting {
        /// Setting name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What is required.
        reason: &'static str,
    },
    /// n anchors at least β_min apart need n · β_min ≤ 2π (the n gaps around the circle sum
    /// to 2π): no design satisfies the constraint.
    #[error(
        "a minimum separation of {min_separation} rad between {cables} anchors is impossible: \
         {cables} × {min_separation} = {:.4} rad exceeds a full turn (2π = 6.2832 rad); \
         β_min must be at most 2π/{cables} = {:.4} rad",
        *cables as f64 * min_separation,
        std::f64::consts::TAU / *cables as f64
    )]
    ImpossibleSeparation {
        /// Number of anchors n.
        cables: usize,
        /// β_min (rad).
        min_separation: f64,
    },
    /// The robot built from the design is invalid.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// The workspace evaluator, grid or orientation range is invalid.
    #[error(transparent)]
    Workspace(#[from] crate::WorkspaceError),
    /// The tension bounds are invalid.
    #[error(transparent)]
    Tension(#[from] cdpr_tension::TensionError),
}

/// Which optimiser [`synthesise`] runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Method {
    /// Dynamic-Q (the thesis' method).
    DynamicQ,
    /// Compass search with restarts (derivative free).
    CompassSearch,
    /// Dynamic-Q, then compass search from its answer.
    #[default]
    DynamicQThenCompass,
    /// [`Method::DynamicQThenCompass`] from the start, then the global stage
    /// ([`multi_start`]): quasi-random designs of the start's topology, the best polished by the
    /// compass search; the best of all is returned.
    Global,
}

/// Settings of the synthesis (eq. (6.29)) and its optimisers.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthesisSettings {
    /// Optimiser.
    pub method: Method,
    /// β_min of eq. (6.29) (rad). Default π/18 = 10°: the separation active at every published
    /// optimum of Tables 6.5–6.10 (0.174–0.175 to print precision).
    pub min_separation: f64,
    /// μ of the exact penalty used by the compass search (area units per rad of violation).
    pub penalty: f64,
    /// Dynamic-Q settings.
    pub dynamic_q: DynamicQSettings,
    /// Compass-search settings.
    pub compass: CompassSettings,
    /// Settings of the global stage ([`Method::Global`] only).
    pub multi_start: MultiStartSettings,
}

impl Default for SynthesisSettings {
    fn default() -> Self {
        Self {
            method: Method::default(),
            min_separation: std::f64::consts::PI / 18.0,
            penalty: 1e3,
            dynamic_q: DynamicQSettings::default(),
            compass: CompassSettings::default(),
            multi_start: MultiStartSettings::default(),
        }
    }
}

impl SynthesisSettings {
    /// Checks every setting's domain.
    pub fn validate(&self) -> Result<(), SynthesisError> {
        if !(self.min_separation >= 0.0 && self.min_separation < std::f64::consts::PI) {
            return Err(invalid(
                "min_separation",
                self.min_separation,
                "need 0 ≤ β_min < π",
            ));
        }
        if !(self.penalty > 0.0 && self.penalty.is_finite()) {
            return Err(invalid("penalty", self.penalty, "need a finite μ > 0"));
        }
        self.dynamic_q.validate()?;
        self.compass.validate()?;
        self.multi_start.validate()
    }
}

impl SynthesisSettings {
    /// Whether `cables` anchors can be β_min apart: n · β_min ≤ 2π (a design with every gap at
    /// β_min exists exactly then).
    pub fn check_feasible_separation(&self, cables: usize) -> Result<(), SynthesisError> {
        if cables as f64 * self.min_separation > std::f64::consts::TAU * (1.0 + 1e-12) {
            return Err(SynthesisError::ImpossibleSeparation {
                cables,
                min_separation: self.min_separation,
            });
        }
        Ok(())
    }
}

pub(crate) fn invalid(name: &'static str, value: f64, reason: &'static str) -> SynthesisError {
    SynthesisError::InvalidSetting {
        name,
        value,
        reason,
    }
}

/// Evaluation counts of an optimisation run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Evaluations {
    /// Objective evaluations in total (including those spent on finite differences).
    pub function: usize,
    /// Gradient evaluations N^g (Dynamic-Q only; each costs 2n function evaluations).
    pub gradient: usize,
}

impl std::ops::AddAssign for Evaluations {
    fn add_assign(&mut self, rhs: Self) {
        self.function += rhs.function;
        self.gradient += rhs.gradient;
    }
}

/// Why an optimiser stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Termination {
    /// The step (Dynamic-Q) or poll size (compass search) fell below its tolerance.
    Converged,
    /// The evaluation budget ran out.
    Budget,
}

/// Outcome of a synthesis run.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthesisResult {
    /// The best design found **d*** (rad).
    pub design: Vec<f64>,
    /// Objective (area) at `design`.
    pub area: f64,
    /// Violation Σ max(0, β_min − s_ij) of eq. (6.29) at `design` (rad); 0 when feasible.
    pub constraint_violation: f64,
    /// Evaluation counts.
    pub evaluations: Evaluations,
    /// Iterations (Dynamic-Q) or polls (compass search).
    pub iterations: usize,
    /// Why the (last) optimiser stopped.
    pub termination: Termination,
}

/// Solves eq. (6.29) from `start` with the chosen [`Method`]: maximises `objective` over designs
/// whose consecutive anchors are at least β_min apart.
pub fn synthesise<O: Objective + ?Sized>(
    objective: &mut O,
    start: &[f64],
    settings: &SynthesisSettings,
) -> Result<SynthesisResult, SynthesisError> {
    settings.validate()?;
    design::check_design(start)?;
    settings.check_feasible_separation(start.len())?;
    match settings.method {
        Method::DynamicQ => Ok(dynamic_q::maximise(
            objective,
            start,
            settings.min_separation,
            settings.penalty,
            &settings.dynamic_q,
        )),
        Method::CompassSearch => Ok(compass_search::maximise(
            objective,
            start,
            settings.min_separation,
            settings.penalty,
            &settings.compass,
        )),
        Method::DynamicQThenCompass | Method::Global => {
            let first = dynamic_q::maximise(
                objective,
                start,
                settings.min_separation,
                settings.penalty,
                &settings.dynamic_q,
            );
            let mut second = compass_search::maximise(
                objective,
                &first.design,
                settings.min_separation,
                settings.penalty,
                &settings.compass,
            );
            second.evaluations += first.evaluations;
            second.iterations += first.iterations;
            // The compass search never returns a worse penalised value than its start.
            if settings.method == Method::Global {
                return Ok(multi_start::maximise(
                    objective,
                    second,
                    settings.min_separation,
                    settings.penalty,
                    &settings.multi_start,
                ));
            }
            Ok(second)
        }
    }
}

/// Test functions shared by the optimisers' unit tests.
#[cfg(test)]
pub(crate) mod test_functions {
    /// β_min = 10° (the default).
    pub const BETA_MIN: f64 = std::f64::consts::PI / 18.0;

    /// Smooth concave bowl with its maximum 1 at `c`.
    pub fn bowl(c: &[f64]) -> impl FnMut(&[f64]) -> f64 + '_ {
        move |d: &[f64]| 1.0 - d.iter().zip(c).map(|(x, y)| (x - y).powi(2)).sum::<f64>()
    }

    /// The bowl evaluated at d rounded to a lattice of spacing `q`: piecewise constant in **d**
    /// like a grid-based area, with its top plateau within q/2 of `c` per coordinate.
    pub fn staircase(c: &[f64], q: f64) -> impl FnMut(&[f64]) -> f64 + '_ {
        move |d: &[f64]| {
            1.0 - d
                .iter()
                .zip(c)
                .map(|(x, y)| ((x / q).round() * q - y).powi(2))
                .sum::<f64>()
        }
    }

    /// The constrained optimum of the bowl when only pair (i, j) (short way counter-clockwise
    /// from i to j) is closer than β_min: both move apart symmetrically.
    pub fn split(c: &[f64], i: usize, j: usize) -> Vec<f64> {
        let s = (c[j] - c[i]).rem_euclid(std::f64::consts::TAU);
        let push = (BETA_MIN - s) / 2.0;
        let mut d = c.to_vec();
        d[i] -= push;
        d[j] += push;
        d
    }
}

#[cfg(test)]
mod tests {
    use super::test_functions::*;
    use super::*;

    #[test]
    fn settings_validate() {
        assert!(SynthesisSettings::default().validate().is_ok());
        let bad = |f: fn(&mut SynthesisSettings)| {
            let mut s = SynthesisSettings::default();
            f(&mut s);
            assert!(matches!(
                s.validate(),
                Err(SynthesisError::InvalidSetting { .. })
            ));
        };
        bad(|s| s.min_separation = -0.1);
        bad(|s| s.min_separation = f64::NAN);
        bad(|s| s.penalty = 0.0);
        bad(|s| s.dynamic_q.move_limit = 0.0);
        bad(|s| s.dynamic_q.fd_interval = f64::INFINITY);
        bad(|s| s.dynamic_q.max_gradient_evaluations = 0);
        bad(|s| s.compass.min_step = 1.0);
        bad(|s| s.compass.restart_radius = -1.0);
    }

    /// Issue 13 §1: 3 anchors 3 rad apart would need 9 rad > 2π; 3 anchors 2π/3 apart fit.
    #[test]
    fn synthesise_rejects_an_impossible_separation() {
        let mut f = bowl(&[0.5, 2.5, 4.5]);
        let s = SynthesisSettings {
            min_separation: 3.0,
            ..SynthesisSettings::default()
        };
        assert_eq!(
            synthesise(&mut f, &[0.5, 2.5, 4.5], &s).unwrap_err(),
            SynthesisError::ImpossibleSeparation {
                cables: 3,
                min_separation: 3.0
            }
        );
        let msg = s.check_feasible_separation(3).unwrap_err().to_string();
        assert!(
            msg.contains("9.0000 rad") && msg.contains("2.0944 rad"),
            "{msg}"
        );
        let s = SynthesisSettings {
            min_separation: std::f64::consts::TAU / 3.0,
            ..SynthesisSettings::default()
        };
        assert!(s.check_feasible_separation(3).is_ok());
        assert!(s.check_feasible_separation(4).is_err());
    }

    #[test]
    fn synthesise_rejects_bad_starts() {
        let mut f = bowl(&[0.0]);
        let s = SynthesisSettings::default();
        assert_eq!(
            synthesise(&mut f, &[], &s).unwrap_err(),
            SynthesisError::EmptyDesign
        );
        assert!(matches!(
            synthesise(&mut f, &[f64::NAN], &s),
            Err(SynthesisError::NotFinite { index: 0, .. })
        ));
    }

    #[test]
    fn every_method_finds_the_bowl_top_and_the_staircase_plateau() {
        let c = [0.5, 2.5, 4.5];
        for method in [
            Method::DynamicQ,
            Method::CompassSearch,
            Method::DynamicQThenCompass,
        ] {
            let s = SynthesisSettings {
                method,
                ..SynthesisSettings::default()
            };
            let r = synthesise(&mut bowl(&c), &[0.3, 2.8, 4.2], &s).unwrap();
            for (d, e) in r.design.iter().zip(&c) {
                assert!((d - e).abs() < 3e-3, "{method:?}: {:?}", r.design);
            }
            let q = 0.01;
            let r = synthesise(&mut staircase(&c, q), &[0.3, 2.8, 4.2], &s).unwrap();
            // The top plateau: every coordinate rounds to the lattice point nearest c.
            for (d, e) in r.design.iter().zip(&c) {
                assert!(
                    ((d / q).round() * q - e).abs() < 1e-9,
                    "{method:?}: {:?}",
                    r.design
                );
            }
            assert!((r.area - 1.0).abs() < 1e-12);
            assert_eq!(r.constraint_violation, 0.0);
        }
    }

    #[test]
    fn chained_method_adds_up_evaluations() {
        let c = [0.5, 2.5, 4.5];
        let s = SynthesisSettings::default();
        let mut calls = 0;
        let mut f = |d: &[f64]| {
            calls += 1;
            bowl(&c)(d)
        };
        let r = synthesise(&mut f, &[0.3, 2.8, 4.2], &s).unwrap();
        assert_eq!(r.evaluations.function, calls);
        assert!(r.evaluations.gradient >= 2);
        // Each gradient costs 2n = 6 evaluations.
        assert!(r.evaluations.function > 6 * r.evaluations.gradient);
    }

    #[test]
    fn constrained_optima_on_inner_and_wrap_pairs() {
        for method in [Method::DynamicQ, Method::CompassSearch] {
            let s = SynthesisSettings {
                method,
                ..SynthesisSettings::default()
            };
            // Pair (1, 2) wants to be 0.05 apart.
            let c = [1.0, 1.05, 4.0];
            let r = synthesise(&mut bowl(&c), &[0.8, 1.5, 3.8], &s).unwrap();
            let e = split(&c, 0, 1);
            for (d, e) in r.design.iter().zip(&e) {
                assert!((d - e).abs() < 5e-3, "{method:?}: {:?} vs {e:?}", r.design);
            }
            assert!(r.constraint_violation < 1e-6, "{method:?}");
            // Pair (3, 1) across β = 0 wants to be 0.05 + 2π − 6.2 = 0.133 apart.
            let c = [0.05, 2.0, 6.2];
            let r = synthesise(&mut bowl(&c), &[0.3, 2.2, 5.9], &s).unwrap();
            let e = split(&c, 2, 0);
            for (d, e) in r.design.iter().zip(&e) {
                assert!((d - e).abs() < 5e-3, "{method:?}: {:?} vs {e:?}", r.design);
            }
            assert!(r.constraint_violation < 1e-6, "{method:?}");
        }
    }

    #[test]
    fn infeasible_start_is_repaired() {
        // Like the published 4-cable starts whose last two anchors are 0.069 rad apart.
        let c = [0.8, 2.3, 4.6, 4.8];
        let start = [0.101, 2.683, 4.338, 4.407];
        for method in [Method::DynamicQ, Method::CompassSearch] {
            let s = SynthesisSettings {
                method,
                ..SynthesisSettings::default()
            };
            let r = synthesise(&mut bowl(&c), &start, &s).unwrap();
            assert!(r.constraint_violation < 1e-6, "{method:?}: {:?}", r.design);
            for (d, e) in r.design.iter().zip(&c) {
                assert!((d - e).abs() < 5e-3, "{method:?}: {:?}", r.design);
            }
        }
    }
}

//! # Statics with sagging cables (Kozak, Zhou & Wang 2006)
//!
//! With heavy elastic cables the force a cable applies to the platform is not along its chord:
//! it is −T_B times the unit tangent of its catenary at B, which itself depends on T_B
//! ([`cdpr_kinematics::catenary`]). The platform's equilibrium
//!
//! ```text
//!   Σ_i T_B,i [u_i(T_B,i); a_i × u_i(T_B,i)] + w_ext = 0
//! ```
//!
//! is solved by a fixed point (Kozak, Zhou & Wang 2006, §IV): distribute the tensions with W
//! built from the current end directions u_i (any [`crate::Method`]), solve each cable's
//! catenary for its new T_B,i (taut branch), rebuild W, repeat until the tensions and
//! directions stop changing (relative 10⁻¹² by default, at most 100 iterations). Tension
//! bounds hold along the whole cable: each iteration tightens cable i's platform-end bounds by
//! the differences between T_B,i and the largest and smallest tension along the cable (at its
//! ends, or the horizontal force where the cable's tangent is horizontal). A cable given less
//! tension than the least with which it can hang taut across its span
//! ([`cdpr_kinematics::ElasticCatenary::least_tension`]) gets that least tension as a floor of
//! its platform-end bound, and the distribution is solved again.
//!
//! The answer is certified with the catenary forces themselves: W(T_B) T_B + w_ext (W from the
//! catenaries at the returned tensions) must vanish to 10⁻⁹ · scale, and both ends (and the
//! lowest point) of every cable must be within the bounds. With weightless cables the
//! directions are the chords: one iteration reproduces the straight-cable answer.
//!
//! ## References
//! - Kozak, Zhou & Wang 2006, "Static analysis of cable-driven manipulators with
//!   non-negligible cable mass", IEEE T-RO 22(3), §IV.
//! - Irvine, *Cable Structures*, MIT Press 1981, §2.3.

use crate::certificate::{BOUND_TOLERANCE, EQUILIBRIUM_TOLERANCE, bound_violation};
use crate::{
    Infeasibility, TensionBounds, TensionError, TensionOutcome, TensionProblem, TensionSolver,
};
use cdpr_kinematics::catenary::write_sagging_wrench_matrix;
use cdpr_kinematics::{
    CatenaryError, KinematicsError, PoseKinematics, RobotCatenaries, SaggingCable,
};
use nalgebra::{DMatrix, DVector};

/// Settings of the fixed point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SaggingSettings {
    /// Stop when tensions (relative to max(1, max T_B)) and unit vectors change less.
    pub tolerance: f64,
    /// Iteration cap.
    pub max_iterations: usize,
}

impl Default for SaggingSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            max_iterations: 100,
        }
    }
}

/// A certified equilibrium with sagging cables.
#[derive(Debug, Clone, PartialEq)]
pub struct SaggingSolution {
    /// Platform-end tensions T_B (N).
    pub tensions: DVector<f64>,
    /// Each cable's catenary at those tensions (unstrained length, frame-end tension, sag).
    pub cables: Vec<SaggingCable>,
    /// The sag-aware wrench matrix at the solution (columns: unit forces on the platform).
    pub wrench_matrix: DMatrix<f64>,
    /// ‖W(T_B) T_B + w_ext‖∞ with the catenary forces.
    pub residual: f64,
    /// Fixed-point iterations.
    pub iterations: usize,
}

/// The result: certified tensions, or why none.
#[derive(Debug, Clone, PartialEq)]
pub enum SaggingOutcome {
    /// Certified tensions.
    Feasible(SaggingSolution),
    /// No tensions, and why: the reason of the last linearised tension problem, a cable whose
    /// catenary has no taut solution, or a fixed point that did not settle.
    Infeasible(Infeasibility),
}

/// The smallest and largest tension along a cable.
fn tension_range(c: &SaggingCable) -> (f64, f64) {
    (
        c.lowest_tension,
        c.frame_end_tension.max(c.platform_end_tension),
    )
}

/// Reusable buffers of the fixed point (no allocation per pose once sized, apart from the
/// tension method's own).
#[derive(Debug, Clone, Default)]
pub struct SaggingStatics {
    settings: SaggingSettings,
    w: DMatrix<f64>,
    cables: Vec<SaggingCable>,
    previous: Vec<SaggingCable>,
    t: DVector<f64>,
}

impl SaggingStatics {
    /// A solver with these settings.
    pub fn new(settings: SaggingSettings) -> Self {
        Self {
            settings,
            ..Self::default()
        }
    }

    /// The platform's equilibrium at the pose of `kin` under `w_ext` with the cables of
    /// `model`, distributed by `solver`'s method, `bounds` holding along every cable.
    pub fn solve(
        &mut self,
        solver: &mut TensionSolver,
        kin: &PoseKinematics,
        model: &RobotCatenaries,
        w_ext: &DVector<f64>,
        bounds: &TensionBounds,
    ) -> Result<SaggingOutcome, TensionError> {
        let n = kin.cable_count();
        if model.cables().len() != n || bounds.len() != n {
            return Err(TensionError::DimensionMismatch {
                what: "cable models and bounds (one per cable)",
                expected: n,
                found: if bounds.len() != n {
                    bounds.len()
                } else {
                    model.cables().len()
                },
            });
        }
        kin.write_wrench_matrix(&mut self.w);
        let mut effective = bounds.clone();
        let tol = self.settings.tolerance;
        self.previous.clear();
        // Least platform-end tensions of cables found too slack to span (N).
        let mut floor = vec![f64::NEG_INFINITY; n];
        for it in 1..=self.settings.max_iterations {
            let problem = TensionProblem::new(&self.w, w_ext, &effective);
            if solver.solve_into(&problem, &mut self.t)?.is_err() {
                // The outcome with its reason (as `solve` words it).
                match solver.solve(&problem)? {
                    TensionOutcome::Feasible(s) => self.t = s.tensions,
                    TensionOutcome::Infeasible(r) => return Ok(SaggingOutcome::Infeasible(r)),
                }
            }
            let t = &self.t;
            // Each cable's solve starts from its catenary of the previous iteration; the sag
            // (not needed by the iterations) is filled in at the end.
            match model.forces_with_tensions_from(
                kin,
                t.as_slice(),
                &self.previous,
                &mut self.cables,
            ) {
                Ok(()) => {}
                Err(KinematicsError::Catenary {
                    cable,
                    source:
                        CatenaryError::Unreachable {
                            horizontal,
                            vertical,
                            ..
                        },
                }) if floor[cable] < f64::INFINITY => {
                    // Too little tension to hold the cable up: no catenary below its least
                    // tension, which becomes a floor of its platform-end bound.
                    let least = model.cables()[cable]
                        .least_tension(horizontal, vertical)
                        .unwrap_or(f64::INFINITY);
                    let raised = least * (1.0 + 1e-9) + 1e-12;
                    if raised.is_nan() || raised <= floor[cable] || raised > effective.max()[cable]
                    {
                        return Ok(SaggingOutcome::Infeasible(Infeasibility::SolverFailure {
                            detail: format!(
                                "cable {}: it needs at least {least} N at the platform to hold itself up across its span, above the tension the other bounds allow",
                                cable + 1
                            ),
                        }));
                    }
                    floor[cable] = raised;
                    let lo: Vec<f64> = effective
                        .min()
                        .iter()
                        .zip(&floor)
                        .map(|(&a, &b)| a.max(b))
                        .collect();
                    effective = TensionBounds::new(lo, effective.max().as_slice().to_vec())?;
                    continue;
                }
                Err(e) => {
                    return Ok(SaggingOutcome::Infeasible(Infeasibility::SolverFailure {
                        detail: e.to_string(),
                    }));
                }
            }
            write_sagging_wrench_matrix(kin, &self.cables, &mut self.w);
            let scale = t.amax().max(1.0);
            let settled = self.previous.len() == n
                && self.previous.iter().zip(&self.cables).all(|(p, c)| {
                    (p.platform_end_tension - c.platform_end_tension).abs() <= tol * scale
                        && (p.unit - c.unit).amax() <= tol
                });
            if settled || (it > 1 && model.cables().iter().all(|c| c.weight() == 0.0)) {
                model.fill_sag(kin, &mut self.cables);
                return Ok(self.certified(t.clone(), w_ext, bounds, it));
            }
            // Platform-end bounds that keep the whole cable within [t_min, t_max].
            let (mut lo, mut hi) = (
                bounds.min().as_slice().to_vec(),
                bounds.max().as_slice().to_vec(),
            );
            for (i, c) in self.cables.iter().enumerate() {
                let (lowest, highest) = tension_range(c);
                lo[i] += c.platform_end_tension - lowest;
                lo[i] = lo[i].max(floor[i]);
                hi[i] -= highest - c.platform_end_tension;
                if lo[i] > hi[i] {
                    return Ok(SaggingOutcome::Infeasible(Infeasibility::NoFeasibleTension));
                }
            }
            effective = TensionBounds::new(lo, hi)?;
            std::mem::swap(&mut self.previous, &mut self.cables);
        }
        Ok(SaggingOutcome::Infeasible(Infeasibility::SolverFailure {
            detail: format!(
                "the sagging-cable fixed point did not settle in {} iterations",
                self.settings.max_iterations
            ),
        }))
    }

    /// The certificate with the catenary forces at `t` (W already built from them).
    fn certified(
        &self,
        t: DVector<f64>,
        w_ext: &DVector<f64>,
        bounds: &TensionBounds,
        iterations: usize,
    ) -> SaggingOutcome {
        let r = &self.w * &t + w_ext;
        let residual = r.amax();
        let row_sum = self.w.abs().row_sum().amax();
        let scale = 1f64.max(w_ext.amax()).max(row_sum * t.amax());
        let mut violation = f64::NEG_INFINITY;
        for (i, c) in self.cables.iter().enumerate() {
            let (lowest, highest) = tension_range(c);
            let (lo, hi) = (bounds.min()[i], bounds.max()[i]);
            violation = violation
                .max(bound_violation(lo, hi, lowest))
                .max(bound_violation(lo, hi, highest));
        }
        if !(residual.is_finite() && residual <= EQUILIBRIUM_TOLERANCE * scale)
            || violation > BOUND_TOLERANCE
        {
            return SaggingOutcome::Infeasible(Infeasibility::CertificateFailed {
                residual,
                bound_violation: violation,
            });
        }
        SaggingOutcome::Feasible(SaggingSolution {
            tensions: t,
            cables: self.cables.clone(),
            wrench_matrix: self.w.clone(),
            residual,
            iterations,
        })
    }
}

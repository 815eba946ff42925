//! # Objective of the dimensional synthesis (thesis eq. (6.29))
//!
//! What the optimisers maximise: any [`Objective`] (closures included), and the thesis' objective
//! [`DextrousArea`], the grid-based dextrous-workspace area of the robot built from a design.
//!
//! ## References
//! - Thesis §6.5 (eq. (6.28)), §6.6 (eq. (6.29)).

use super::SynthesisError;
use super::design::robot_from_design;
use crate::{
    Criterion, DextrousWorkspace, Grid, OrientationRange, PoseEvaluator, Region, dextrous_workspace,
};
use cdpr_tension::{Method, TensionBounds};
use nalgebra::DVector;
use std::collections::HashMap;

/// A function of the design **d** (rad) to maximise.
///
/// Non-finite values count as −∞ (never accepted by the optimisers).
pub trait Objective {
    /// The value at `design`.
    fn value(&mut self, design: &[f64]) -> f64;
}

impl<F: FnMut(&[f64]) -> f64> Objective for F {
    fn value(&mut self, design: &[f64]) -> f64 {
        self(design)
    }
}

/// The thesis' objective: the area A_d of the dextrous workspace W^D[φ_min, φ_max] (eq. (6.28)),
/// on a fixed grid, of the planar robot whose frame anchors sit at the design angles.
#[derive(Debug, Clone)]
pub struct DextrousArea {
    /// Platform attachments **ā**^i (one per design angle), e.g. [`super::thesis_platform`].
    pub platform: Vec<[f64; 2]>,
    /// Tension limits t_min ≤ t_i ≤ t_max.
    pub bounds: TensionBounds,
    /// Workspace criteria of eq. (6.23) (tension feasibility, l_min, D_min, …).
    pub criteria: Vec<Criterion>,
    /// [φ_min, φ_max] and m_sl.
    pub range: OrientationRange,
    /// The grid (fixed: it must not follow the anchors, or the area would not be comparable
    /// between designs).
    pub grid: Grid,
}

/// Loads L1–L3 of thesis Table 6.3, [f_x, f_y, τ] applied at the platform origin.
pub const THESIS_LOADS: [[f64; 3]; 3] = [[0.0, -10.0, 0.0], [5.0, -10.0, 0.0], [5.0, -10.0, 1.0]];

impl DextrousArea {
    /// The objective from its parts; checks the grid, the range and the sizes.
    pub fn new(
        platform: Vec<[f64; 2]>,
        bounds: TensionBounds,
        criteria: Vec<Criterion>,
        range: OrientationRange,
        grid: Grid,
    ) -> Result<Self, SynthesisError> {
        range.validate()?;
        grid.validate(2)?;
        if bounds.len() != platform.len() {
            return Err(SynthesisError::DimensionMismatch {
                expected: platform.len(),
                found: bounds.len(),
            });
        }
        Ok(Self {
            platform,
            bounds,
            criteria,
            range,
            grid,
        })
    }

    /// The setting of thesis §6.6.2 for the 3- or 4-cable manipulator under the external
    /// wrench `load` = [f_x, f_y, τ] (e.g. [`THESIS_LOADS`]) with tension method `method`
    /// (`Exact` for 3 cables; `L1` or `ClosedForm` for 4): platform of Table 6.1,
    /// t ∈ [5, 100], l_min = 0.1, D_min = 10⁻³ (3 cables only, |det J|), grid over the whole
    /// frame [−1, 1]²; 3 cables: φ ∈ [−0.1, 0.1], m = 100, m_sl = 3; 4 cables: φ ∈ [−0.2, 0.2],
    /// m = 50, m_sl = 21. Other cable counts are a dimension error.
    pub fn thesis(cables: usize, load: [f64; 3], method: Method) -> Result<Self, SynthesisError> {
        let platform = super::thesis_platform(cables).ok_or(SynthesisError::DimensionMismatch {
            expected: 3,
            found: cables,
        })?;
        let mut criteria = vec![
            Criterion::TensionFeasible {
                method,
                wrench: DVector::from_row_slice(&load),
            },
            Criterion::MinCableLength(0.1),
        ];
        let (range, resolution) = if cables == 3 {
            criteria.push(Criterion::MinJacobianDeterminant(1e-3));
            (
                OrientationRange {
                    min: -0.1,
                    max: 0.1,
                    slices: 3,
                },
                100,
            )
        } else {
            (
                OrientationRange {
                    min: -0.2,
                    max: 0.2,
                    slices: 21,
                },
                50,
            )
        };
        Self::new(
            platform,
            TensionBounds::uniform(cables, 5.0, 100.0)?,
            criteria,
            range,
            Grid::new(resolution, Region::planar(-1.0, 1.0, -1.0, 1.0)),
        )
    }

    /// The dextrous workspace of the robot with anchors at `design` (rad).
    pub fn workspace(&self, design: &[f64]) -> Result<DextrousWorkspace, SynthesisError> {
        let robot = robot_from_design(design, &self.platform)?;
        let eval = PoseEvaluator::new(robot, self.bounds.clone(), self.criteria.clone())?;
        Ok(dextrous_workspace(&eval, &self.range, &self.grid)?)
    }

    /// A_d at `design`.
    pub fn area(&self, design: &[f64]) -> Result<f64, SynthesisError> {
        Ok(self.workspace(design)?.workspace.area)
    }
}

impl Objective for DextrousArea {
    /// A_d, or −∞ for a design the workspace crate rejects (wrong length, non-finite angle).
    fn value(&mut self, design: &[f64]) -> f64 {
        self.area(design).unwrap_or(f64::NEG_INFINITY)
    }
}

/// An objective with an evaluation counter, a memo of the designs already evaluated (pattern
/// searches revisit points: after a move by +h v the poll x − h v is the previous iterate) and
/// the exact penalty of eq. (6.29): φ(**d**) = −A(**d**) + μ Σ max(0, β_min − s_ij) (minimised).
pub(crate) struct Merit<'a, O: ?Sized> {
    objective: &'a mut O,
    /// Cyclic order of the start: designs with another order are inadmissible (φ = +∞).
    order: Vec<usize>,
    min_separation: f64,
    penalty: f64,
    /// Platform attachments whose polygon no cable may enter at the reference pose (see
    /// [`super::design::cables_clear_platform`]); `None` checks nothing.
    pub platform: Option<Vec<[f64; 2]>>,
    memo: HashMap<Vec<u64>, f64>,
    /// Objective evaluations so far (memo hits excluded).
    pub evaluations: usize,
}

impl<'a, O: Objective + ?Sized> Merit<'a, O> {
    pub fn new(objective: &'a mut O, start: &[f64], min_separation: f64, penalty: f64) -> Self {
        Self {
            objective,
            order: super::design::cyclic_order(start),
            min_separation,
            penalty,
            platform: None,
            memo: HashMap::new(),
            evaluations: 0,
        }
    }

    /// The objective A(**d**), non-finite values mapped to −∞.
    pub fn area(&mut self, design: &[f64]) -> f64 {
        let key: Vec<u64> = design.iter().map(|x| x.to_bits()).collect();
        if let Some(&a) = self.memo.get(&key) {
            return a;
        }
        self.evaluations += 1;
        let a = self.objective.value(design);
        let a = if a.is_finite() { a } else { f64::NEG_INFINITY };
        self.memo.insert(key, a);
        a
    }

    /// Whether `design` keeps the start's cyclic order of anchors (see
    /// [`super::design::same_cyclic_order`]) and, if a platform is set, its cables clear it.
    pub fn admissible(&self, design: &[f64]) -> bool {
        super::design::cyclic_order(design) == self.order
            && self
                .platform
                .as_deref()
                .is_none_or(|p| super::design::cables_clear_platform(design, p))
    }

    /// φ(**d**) for an already computed area; +∞ for a design that is not [`Self::admissible`].
    pub fn merit(&self, design: &[f64], area: f64) -> f64 {
        if !self.admissible(design) {
            return f64::INFINITY;
        }
        -area + self.penalty * super::design::separation_violation(design, self.min_separation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Thesis Table 6.8 run 1: d* = [0.8205, 2.338, 4.595, 4.769] under L1 has A_d* = 1.1040
    /// (690 points of the 51 × 51 grid); both ℓ1 implementations agree.
    #[test]
    fn reproduces_table_6_8_run_1_optimum() {
        let d = [0.8205, 2.338, 4.595, 4.769];
        for method in [Method::ClosedForm, Method::L1] {
            let o = DextrousArea::thesis(4, THESIS_LOADS[0], method).unwrap();
            let ws = o.workspace(&d).unwrap();
            assert_eq!(ws.workspace.feasible_points, 690, "{method}");
            assert!((ws.workspace.area - 1.1040).abs() < 1e-12);
        }
    }

    /// Thesis Table 6.5 run 3: d* = [0.7645, 3.477, 3.651] under L1 has A_d* = 0.3172 (793
    /// points of the 101 × 101 grid) with exact tensions and |det J| ≥ 10⁻³.
    #[test]
    fn reproduces_table_6_5_run_3_optimum() {
        let mut o = DextrousArea::thesis(3, THESIS_LOADS[0], Method::Exact).unwrap();
        let a = o.value(&[0.7645, 3.477, 3.651]);
        assert!((a - 0.3172).abs() < 1e-12, "{a}");
    }

    #[test]
    fn bad_inputs() {
        assert!(matches!(
            DextrousArea::thesis(5, THESIS_LOADS[0], Method::L1),
            Err(SynthesisError::DimensionMismatch { .. })
        ));
        let mut o = DextrousArea::thesis(3, THESIS_LOADS[0], Method::Exact).unwrap();
        assert_eq!(o.value(&[0.0, 1.0]), f64::NEG_INFINITY);
        assert_eq!(o.value(&[0.0, 1.0, f64::NAN]), f64::NEG_INFINITY);
        let mut bad_grid = o.clone();
        bad_grid.grid.resolution = 0;
        assert!(
            DextrousArea::new(
                bad_grid.platform,
                bad_grid.bounds,
                bad_grid.criteria,
                bad_grid.range,
                bad_grid.grid
            )
            .is_err()
        );
    }
}

//! # Dextrous workspace (eq. (6.28))
//!
//! The set of positions u at which every orientation of a range is feasible: the intersection
//! of the constant-orientation workspaces of m_sl regularly spaced orientations φ_min, …, φ_max
//! (endpoints included), computed on one grid by testing each point for all orientations
//! (thesis §6.5: "testing for compliance in Step 4 for a range of values of φ_P").
//!
//! **The check of §6.5.** Du Plessis and Snyman's shortcut uses only the two extreme
//! orientations; it is valid when the workspace at the central orientation (φ_min + φ_max)/2
//! contains the intersection of the two extreme workspaces. [`CentralCheck`] reports whether
//! that holds on the grid, and how many grid points violate it.
//!
//! **The planar r = 1 path.** The thesis' robots (4 cables, 3 DOF) with cable-length and
//! Algorithm 6.1 criteria (`closed-form`, `l1`, `l1-max`) are tested by [`PlanarSlice`]: per
//! orientation the attachments R a_i are computed once, and per pose the cable vectors, W and
//! the closed-form tensions with their certificate run on the stack — the evaluator's arithmetic
//! expression by expression, hence its verdicts, without its generic per-pose path.
//!
//! Planar robots rotate about z; spatial robots about a chosen axis
//! ([`dextrous_workspace_about_axis`]) or over any list of orientations, e.g. a box of Euler
//! angles ([`euler_box`], [`dextrous_workspace_over`]).
//!
//! ## References
//! - Thesis §6.5, eq. (6.28).
//! - Du Plessis & Snyman (2003), dextrous workspaces of parallel manipulators (the thesis chapter ref. \[18\]).

use crate::discretisation::{checked_orientation, map_grid};
use crate::{Criterion, Grid, GridWorkspace, PoseEvaluator, WorkspaceError};
use cdpr_kinematics::{MotionPattern, Pose};
use cdpr_tension::Method;
use cdpr_tension::closed_form::PlanarClosedForm;
use nalgebra::{Rotation3, Unit, Vector3};

/// A range of orientation angles [min, max] sampled at `slices` = m_sl regularly spaced values,
/// endpoints included (radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientationRange {
    /// φ_min.
    pub min: f64,
    /// φ_max.
    pub max: f64,
    /// m_sl ≥ 2 (or 1 when min = max).
    pub slices: usize,
}

impl OrientationRange {
    /// Checks finite min ≤ max and m_sl ≥ 2 (1 allowed when min = max).
    pub fn validate(&self) -> Result<(), WorkspaceError> {
        for v in [self.min, self.max] {
            if !v.is_finite() {
                return Err(WorkspaceError::NotFinite {
                    what: "orientation range",
                    value: v,
                });
            }
        }
        if self.min > self.max {
            return Err(WorkspaceError::InvalidSetting {
                what: "orientation range min",
                value: self.min,
                expected: "min ≤ max",
            });
        }
        if self.slices == 0 || (self.slices == 1 && self.min != self.max) {
            return Err(WorkspaceError::InvalidSetting {
                what: "slices m_sl",
                value: self.slices as f64,
                expected: "m_sl ≥ 2 (endpoints included), or 1 when min = max",
            });
        }
        Ok(())
    }

    /// The m_sl angles φ_k = φ_min + k (φ_max − φ_min)/(m_sl − 1), k = 0 … m_sl − 1.
    pub fn angles(&self) -> Vec<f64> {
        if self.slices <= 1 {
            return vec![self.min];
        }
        let last = self.slices - 1;
        (0..self.slices)
            .map(|k| {
                if k == last {
                    self.max
                } else {
                    self.min + (self.max - self.min) * k as f64 / last as f64
                }
            })
            .collect()
    }

    /// The central angle (φ_min + φ_max)/2.
    pub fn central(&self) -> f64 {
        0.5 * (self.min + self.max)
    }
}

/// The §6.5 check of the two-extremes shortcut on the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentralCheck {
    /// Whether the central orientation's workspace contains the intersection of the two
    /// extreme ones at every grid point.
    pub holds: bool,
    /// Grid points feasible at both extremes but not at the central orientation.
    pub violations: usize,
    /// Grid points feasible at both extremes (the shortcut's dextrous workspace).
    pub extremes_points: usize,
}

/// A dextrous workspace on a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct DextrousWorkspace {
    /// Points feasible at every sampled orientation; `area` is the dextrous area A_d.
    pub workspace: GridWorkspace,
    /// The §6.5 check.
    pub central_check: CentralCheck,
    /// The sampled angles, endpoints included.
    pub angles: Vec<f64>,
}

/// The length above which, relative to the robot's size and the position, a cable is tested by
/// [`PlanarSlice`] itself; a shorter one (near the kinematics' degenerate-cable threshold,
/// 10⁻¹² of it) goes through [`PoseEvaluator`].
const LEAN_MIN_LENGTH: f64 = 1e-9;

/// One orientation of a planar robot with 4 cables (redundancy 1) whose criteria are only
/// cable-length floors (eq. (6.22)) and tension feasibility by Algorithm 6.1 (`closed-form`,
/// `l1`, `l1-max`): the verdict of [`PoseEvaluator::is_feasible`] at that orientation,
/// computed on the stack. The attachments R a_i are computed once; per pose the cable vectors
/// ℓ_i = c_i − (u + R a_i) (eq. (6.2)), the columns [u_i; (R a_i) × u_i] of W (eq. (6.11))
/// and the closed-form tensions with their certificate
/// ([`PlanarClosedForm`], the arithmetic of [`cdpr_tension::closed_form::is_feasible_planar`])
/// are the evaluator's expressions, so the
/// verdicts are the same bit for bit (test `planar_slice_agrees_with_the_evaluator`).
#[derive(Debug, Clone)]
pub struct PlanarSlice {
    /// c_i and R a_i in the plane (their z is 0, so the 3-vector sums of the evaluator are
    /// these sums, bit for bit).
    frame: [[f64; 2]; 4],
    attachment: [[f64; 2]; 4],
    length_scale: f64,
    /// The largest cable-length floor (−∞ without one).
    min_length: f64,
    /// Algorithm 6.1 with its certificate for every tension criterion (w_ext, end).
    tension: Vec<PlanarClosedForm>,
}

impl PlanarSlice {
    /// The lean test of `eval` at `rotation`, or `None` when it does not apply (not planar, not
    /// 4 cables, pulleys, another criterion or method, a non-finite load or rotation, a point
    /// off the plane z = 0).
    pub fn new(eval: &PoseEvaluator, rotation: &Rotation3<f64>) -> Option<Self> {
        let robot = eval.robot();
        if robot.motion() != MotionPattern::Planar
            || robot.cable_count() != 4
            || robot.cables().iter().any(|c| c.pulley.is_some())
            || eval.bounds().len() != 4
            || !rotation.matrix().iter().all(|v| v.is_finite())
        {
            return None;
        }
        let mut min_length = f64::NEG_INFINITY;
        let mut tension = Vec::new();
        for c in eval.criteria() {
            match c {
                Criterion::MinCableLength(l) if !l.is_nan() => min_length = min_length.max(*l),
                Criterion::TensionFeasible { method, wrench }
                    if wrench.len() == 3 && wrench.iter().all(|v| v.is_finite()) =>
                {
                    let maximize = match method {
                        Method::ClosedForm | Method::L1 => false,
                        Method::L1Max => true,
                        _ => return None,
                    };
                    let we = Vector3::new(wrench[0], wrench[1], wrench[2]);
                    tension.push(PlanarClosedForm::new(&we, eval.bounds(), maximize).ok()?);
                }
                _ => return None,
            }
        }
        let r = rotation.matrix();
        let cables = robot.cables();
        let attachment: Vec<Vector3<f64>> = cables.iter().map(|c| r * c.platform).collect();
        if cables.iter().any(|c| c.frame.z != 0.0) || attachment.iter().any(|a| a.z != 0.0) {
            return None;
        }
        Some(Self {
            frame: std::array::from_fn(|i| [cables[i].frame.x, cables[i].frame.y]),
            attachment: std::array::from_fn(|i| [attachment[i].x, attachment[i].y]),
            length_scale: robot.length_scale(),
            min_length,
            tension,
        })
    }

    /// The evaluator's verdict at `position` (finite, z = 0) and this orientation, or `None` when
    /// a cable is nearly degenerate or z ≠ 0 (the caller asks the evaluator).
    #[inline]
    pub fn is_feasible(&self, position: &Vector3<f64>) -> Option<bool> {
        if position.z != 0.0 {
            return None;
        }
        let (px, py) = (position.x, position.y);
        // ‖u‖ and the cable vectors as the evaluator's 3-vectors with z = 0: the same roundings.
        let floor = LEAN_MIN_LENGTH * self.length_scale.max((px * px + py * py).sqrt());
        let mut w = [[0.0; 3]; 4];
        let mut short = false;
        for (i, wi) in w.iter_mut().enumerate() {
            let [ax, ay] = self.attachment[i];
            let [cx, cy] = self.frame[i];
            // ℓ_i = c_i − (u + R a_i), eq. (6.2).
            let (vx, vy) = (cx - (px + ax), cy - (py + ay));
            let length = (vx * vx + vy * vy).sqrt();
            if length.is_nan() || length <= floor {
                return None;
            }
            short |= length < self.min_length;
            let (ux, uy) = (vx / length, vy / length);
            *wi = [ux, uy, ax * uy - ay * ux];
        }
        if short {
            return Some(false);
        }
        Some(self.tension.iter().all(|t| t.is_feasible(&w)))
    }
}

/// Eq. (6.28) for a planar robot: orientations φ ∈ [min, max] about z (point robots: the
/// constant-orientation workspace).
///
/// ```
/// use cdpr_kinematics::{Cable, MotionPattern, Robot};
/// use cdpr_workspace::{dextrous_workspace, Criterion, Grid, OrientationRange, PoseEvaluator, Region};
/// use cdpr_tension::TensionBounds;
/// use nalgebra::Vector3;
/// let s = 0.1 / 2f64.sqrt();
/// let c = |x: f64, y: f64, a: f64, b: f64| Cable { frame: Vector3::new(x, y, 0.0), platform: Vector3::new(a, b, 0.0), pulley: None };
/// let robot = Robot::new(MotionPattern::Planar, vec![
///     c(1.0, 0.5, s, s), c(-1.0, 0.5, -s, s), c(-1.0, -0.5, -0.1, -0.1), c(1.0, -0.5, 0.1, -0.1),
/// ]).unwrap();
/// let eval = PoseEvaluator::new(robot, TensionBounds::uniform(4, 1.0, 10.0).unwrap(),
///                               vec![Criterion::WrenchClosure]).unwrap();
/// let grid = Grid::new(20, Region::planar(-1.0, 1.0, -0.5, 0.5));
/// let range = OrientationRange { min: -0.1, max: 0.1, slices: 3 };
/// let dex = dextrous_workspace(&eval, &range, &grid).unwrap();
/// assert!(dex.workspace.feasible_points > 0);
/// assert_eq!(dex.angles, vec![-0.1, 0.0, 0.1]);
/// ```
pub fn dextrous_workspace(
    eval: &PoseEvaluator,
    range: &OrientationRange,
    grid: &Grid,
) -> Result<DextrousWorkspace, WorkspaceError> {
    dextrous_workspace_about_axis(
        eval,
        &Vector3::z_axis(),
        &Rotation3::identity(),
        range,
        grid,
    )
}

/// Eq. (6.28) for rotations `base · R(axis, φ)`, φ ∈ range (spatial robots; a planar robot
/// needs the z axis).
pub fn dextrous_workspace_about_axis(
    eval: &PoseEvaluator,
    axis: &Unit<Vector3<f64>>,
    base: &Rotation3<f64>,
    range: &OrientationRange,
    grid: &Grid,
) -> Result<DextrousWorkspace, WorkspaceError> {
    range.validate()?;
    let motion = eval.robot().motion();
    let dim = motion.space_dim();
    grid.validate(dim)?;
    eval.validate()?;
    if let Some(&v) = axis.iter().find(|v| !v.is_finite()) {
        return Err(WorkspaceError::NotFinite {
            what: "rotation axis",
            value: v,
        });
    }
    let rot =
        |phi: f64| checked_orientation(motion, &(base * Rotation3::from_axis_angle(axis, phi)));
    let angles = range.angles();
    let (first, last) = (rot(range.min)?, rot(range.max)?);
    let central = rot(range.central())?;
    // Interior slices (the extremes are tested first; the central one next if it is a slice).
    let interior: &[f64] = if angles.len() > 2 {
        &angles[1..angles.len() - 1]
    } else {
        &[]
    };
    let others = interior
        .iter()
        .filter(|&&a| a != range.central())
        .map(|&a| rot(a))
        .collect::<Result<Vec<_>, _>>()?;
    let central_is_slice = angles.contains(&range.central());
    // The lean planar path, when every orientation has it (the same verdicts).
    let lean = |r: &Rotation3<f64>| PlanarSlice::new(eval, r);
    let lean: Option<(PlanarSlice, PlanarSlice, PlanarSlice, Vec<PlanarSlice>)> = (|| {
        Some((
            lean(&first)?,
            lean(&last)?,
            lean(&central)?,
            others.iter().map(lean).collect::<Option<Vec<_>>>()?,
        ))
    })();
    // Per point: (dextrous, feasible at both extremes, violation of the central check).
    let verdicts = map_grid(eval, grid, dim, |ev, u| {
        let mut ok = |r: &Rotation3<f64>, s: Option<&PlanarSlice>| {
            s.and_then(|s| s.is_feasible(&u))
                .unwrap_or_else(|| ev.is_feasible_finite_rotation(&Pose::new(u, *r)))
        };
        let l = lean.as_ref();
        if !ok(&first, l.map(|l| &l.0)) || (angles.len() > 1 && !ok(&last, l.map(|l| &l.1))) {
            return (false, false, false);
        }
        let central_ok = ok(&central, l.map(|l| &l.2));
        let dextrous = (central_ok || !central_is_slice)
            && others
                .iter()
                .enumerate()
                .all(|(k, r)| ok(r, l.map(|l| &l.3[k])));
        (dextrous, true, !central_ok)
    });
    let feasible: Vec<bool> = verdicts.iter().map(|v| v.0).collect();
    let violations = verdicts.iter().filter(|v| v.2).count();
    let central_check = CentralCheck {
        holds: violations == 0,
        violations,
        extremes_points: verdicts.iter().filter(|v| v.1).count(),
    };
    Ok(DextrousWorkspace {
        workspace: GridWorkspace::from_verdicts(*grid, dim, feasible),
        central_check,
        angles,
    })
}

/// Points feasible at every orientation of `orientations` (any robot): the general form of
/// eq. (6.28).
pub fn dextrous_workspace_over(
    eval: &PoseEvaluator,
    orientations: &[Rotation3<f64>],
    grid: &Grid,
) -> Result<GridWorkspace, WorkspaceError> {
    let motion = eval.robot().motion();
    let dim = motion.space_dim();
    grid.validate(dim)?;
    eval.validate()?;
    if orientations.is_empty() {
        return Err(WorkspaceError::InvalidSetting {
            what: "number of orientations",
            value: 0.0,
            expected: "≥ 1",
        });
    }
    let rots = orientations
        .iter()
        .map(|r| checked_orientation(motion, r))
        .collect::<Result<Vec<_>, _>>()?;
    let feasible = map_grid(eval, grid, dim, |ev, u| {
        rots.iter()
            .all(|r| ev.is_feasible_finite_rotation(&Pose::new(u, *r)))
    });
    Ok(GridWorkspace::from_verdicts(*grid, dim, feasible))
}

/// The orientations of a box of XYZ Euler angles (`R = R_x R_y R_z`, as
/// [`Pose::spatial`]): `slices` values per angle, endpoints included, `slices³` rotations.
pub fn euler_box(
    min: [f64; 3],
    max: [f64; 3],
    slices: usize,
) -> Result<Vec<Rotation3<f64>>, WorkspaceError> {
    let ranges = (0..3)
        .map(|k| {
            let r = OrientationRange {
                min: min[k],
                max: max[k],
                slices: if min[k] == max[k] { 1 } else { slices },
            };
            r.validate().map(|_| r.angles())
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut out = Vec::new();
    for &a in &ranges[0] {
        for &b in &ranges[1] {
            for &c in &ranges[2] {
                out.push(Pose::spatial(Vector3::zeros(), a, b, c).rotation);
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_include_endpoints() {
        let r = OrientationRange {
            min: -0.2,
            max: 0.2,
            slices: 5,
        };
        let a = r.angles();
        assert_eq!(a.len(), 5);
        assert_eq!((a[0], a[4]), (-0.2, 0.2)); // endpoints exact
        for (x, y) in a.iter().zip([-0.2, -0.1, 0.0, 0.1, 0.2]) {
            assert!((x - y).abs() < 1e-15);
        }
        assert_eq!(r.central(), 0.0);
        assert!(
            OrientationRange {
                min: 0.1,
                max: 0.0,
                slices: 2
            }
            .validate()
            .is_err()
        );
        assert!(
            OrientationRange {
                min: 0.0,
                max: 0.1,
                slices: 1
            }
            .validate()
            .is_err()
        );
        assert_eq!(euler_box([0.0; 3], [0.1, 0.0, 0.1], 3).unwrap().len(), 9);
    }
}

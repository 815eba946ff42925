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

use crate::discretisation::{checked_orientation, map_grid, map_grid_tasks};
use crate::{Criterion, Grid, GridWorkspace, PoseEvaluator, WorkspaceError};
use cdpr_kinematics::{MotionPattern, Pose};
use cdpr_tension::Method;
use cdpr_tension::closed_form::PlanarClosedForm;
use cdpr_tension::lanes::F64x4;
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
        let (w, short) = self.wrench_columns(position.x, position.y)?;
        if short {
            return Some(false);
        }
        Some(self.tension.iter().all(|t| t.is_feasible(&w)))
    }

    /// The columns [u_i; (R a_i) × u_i] of W (eq. (6.11)) at (x, y, 0), and whether a cable is
    /// shorter than the length floor; `None` when a cable is nearly degenerate.
    #[inline(always)]
    fn wrench_columns(&self, px: f64, py: f64) -> Option<([[f64; 3]; 4], bool)> {
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
        Some((w, short))
    }

    /// [`PlanarSlice::is_feasible`] at four positions (x, y, 0), one per lane of `x` and `y`:
    /// `(verdicts, deferred)`, bit l for lane l; a deferred lane is one where
    /// [`PlanarSlice::is_feasible`] gives `None` (its verdict bit is meaningless). Each lane
    /// performs the scalar operations in the same order (`PlanarSlice::wrench_columns`, then
    /// [`PlanarClosedForm::is_feasible_lanes`]): the same verdicts bit for bit (tests
    /// `planar_slice_agrees_with_the_evaluator`, `wrench_columns_lanes_are_the_scalar_bits`).
    #[inline(always)]
    pub fn is_feasible_lanes<V: F64x4>(&self, x: V, y: V) -> (u32, u32) {
        let (w, long, short) = self.wrench_columns_lanes(x, y);
        let deferred = !V::bits(long) & 0b1111;
        let mut verdicts = V::bits(V::and_not(long, short));
        for t in &self.tension {
            if verdicts == 0 {
                break;
            }
            verdicts &= t.is_feasible_lanes(&w);
        }
        (verdicts, deferred)
    }

    /// [`PlanarSlice::wrench_columns`] lane by lane: W, the lanes where no cable is degenerate
    /// (`Some`), the lanes with a cable below the length floor.
    #[inline(always)]
    fn wrench_columns_lanes<V: F64x4>(&self, x: V, y: V) -> ([[V; 3]; 4], V::Mask, V::Mask) {
        // No closures here: they would not inherit the caller's target features.
        let floor = x.splat(LEAN_MIN_LENGTH).mul(
            x.mul(x)
                .add(y.mul(y))
                .sqrt()
                .max(x.splat(self.length_scale)),
        );
        let zero = x.splat(0.0);
        let (mut long, mut short) = (zero.eq(zero), zero.ne(zero));
        let min_length = x.splat(self.min_length);
        let mut w = [[zero; 3]; 4];
        for (i, wi) in w.iter_mut().enumerate() {
            let ([ax, ay], [cx, cy]) = (self.attachment[i], self.frame[i]);
            let (ax, ay) = (x.splat(ax), x.splat(ay));
            let (vx, vy) = (x.splat(cx).sub(x.add(ax)), x.splat(cy).sub(y.add(ay)));
            let length = vx.mul(vx).add(vy.mul(vy)).sqrt();
            long = V::and(long, length.gt(floor));
            short = V::or(short, length.lt(min_length));
            let (ux, uy) = (vx.div(length), vy.div(length));
            *wi = [ux, uy, ax.mul(uy).sub(ay.mul(ux))];
        }
        (w, long, short)
    }
}

/// Buffers of [`dextrous_verdicts_lean`], reused from call to call (no allocation once warm).
#[derive(Debug, Clone, Default)]
pub struct LeanScratch {
    alive: Vec<u32>,
    central: Vec<u32>,
}

/// The orientation at which a point is asked: `Some(k)` the k-th sampled orientation, `None`
/// the central one when it is not sampled.
pub type OrientationIndex = Option<usize>;

/// Eq. (6.28) by the lean planar path over `points`, in the order of tests of
/// [`dextrous_workspace_about_axis`] (both extremes, the central orientation, the others), one
/// orientation at a time over the points still feasible, four points at a time
/// ([`PlanarSlice::is_feasible_lanes`], AVX2 when the CPU has it). `slices` are the m_sl sampled
/// orientations in order; `central` is the index of the central one among them, or its own
/// slice. `verdicts[i]` receives (dextrous, feasible at both extremes, central check violated)
/// of `points[i]` (it must hold `(false, false, false)` on entry); `deferred(k, u)` gives the
/// verdict at a point that [`PlanarSlice::is_feasible`] defers (the evaluator's).
pub fn dextrous_verdicts_lean(
    slices: &[PlanarSlice],
    central: Result<usize, &PlanarSlice>,
    points: &[Vector3<f64>],
    verdicts: &mut [(bool, bool, bool)],
    scratch: &mut LeanScratch,
    mut deferred: impl FnMut(OrientationIndex, &Vector3<f64>) -> bool,
) {
    let n = slices.len();
    assert!(n > 0 && verdicts.len() == points.len() && points.len() < u32::MAX as usize);
    let path = LanePath::detect();
    let LeanScratch {
        alive,
        central: central_ok,
    } = scratch;
    alive.clear();
    alive.extend(0..points.len() as u32);
    let mut keep = |k: OrientationIndex, list: &mut Vec<u32>, rejected: &mut dyn FnMut(usize)| {
        let slice = k.map_or_else(|| central.unwrap_err(), |k| &slices[k]);
        path.keep_feasible(slice, points, list, &mut |u| deferred(k, u), rejected)
    };
    keep(Some(0), alive, &mut |_| {});
    if n > 1 {
        keep(Some(n - 1), alive, &mut |_| {});
    }
    for &i in alive.iter() {
        verdicts[i as usize] = (false, true, false);
    }
    central_ok.clear();
    central_ok.extend_from_slice(alive);
    let central_index = central.ok();
    keep(central_index, central_ok, &mut |i| verdicts[i].2 = true);
    if central_index.is_some() {
        std::mem::swap(alive, central_ok);
    }
    for k in (1..n.saturating_sub(1)).filter(|&k| Some(k) != central_index) {
        keep(Some(k), alive, &mut |_| {});
    }
    for &i in alive.iter() {
        verdicts[i as usize].0 = true;
    }
}

/// Which build of [`keep_feasible`] runs.
#[derive(Clone, Copy)]
enum LanePath {
    #[cfg(target_arch = "x86_64")]
    Avx2(cdpr_tension::lanes::Avx2),
    Portable,
}

impl LanePath {
    /// AVX2 if the CPU has it (`is_x86_feature_detected!` caches its answer).
    fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        if let Some(v) = cdpr_tension::lanes::Avx2::detect() {
            return LanePath::Avx2(v);
        }
        LanePath::Portable
    }

    fn keep_feasible(
        self,
        slice: &PlanarSlice,
        points: &[Vector3<f64>],
        list: &mut Vec<u32>,
        deferred: &mut dyn FnMut(&Vector3<f64>) -> bool,
        rejected: &mut dyn FnMut(usize),
    ) {
        match self {
            // SAFETY: an `Avx2` value exists only on a CPU with AVX2.
            #[cfg(target_arch = "x86_64")]
            LanePath::Avx2(v) => unsafe {
                keep_feasible_avx2(v, slice, points, list, deferred, rejected)
            },
            LanePath::Portable => {
                let v = cdpr_tension::lanes::Portable([0.0; 4]);
                keep_feasible(v, slice, points, list, deferred, rejected)
            }
        }
    }
}

/// [`keep_feasible`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2 (`v` exists).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn keep_feasible_avx2(
    v: cdpr_tension::lanes::Avx2,
    slice: &PlanarSlice,
    points: &[Vector3<f64>],
    list: &mut Vec<u32>,
    deferred: &mut dyn FnMut(&Vector3<f64>) -> bool,
    rejected: &mut dyn FnMut(usize),
) {
    keep_feasible(v, slice, points, list, deferred, rejected)
}

/// Keeps in `list` (indices into `points`, in order) the points feasible at `slice`'s
/// orientation and calls `rejected` with the others: four at a time through
/// [`PlanarSlice::is_feasible_lanes`] (the last group padded with its last point); the points
/// it defers, or off the plane z = 0, through `deferred`.
#[inline(always)]
fn keep_feasible<V: F64x4>(
    v: V,
    slice: &PlanarSlice,
    points: &[Vector3<f64>],
    list: &mut Vec<u32>,
    deferred: &mut dyn FnMut(&Vector3<f64>) -> bool,
    rejected: &mut dyn FnMut(usize),
) {
    let (len, mut kept, mut j) = (list.len(), 0, 0);
    while j < len {
        let k = (len - j).min(4);
        let last = list[j + k - 1] as usize;
        let mut index = [last; 4];
        for (l, i) in index[..k].iter_mut().enumerate() {
            *i = list[j + l] as usize;
        }
        let u = [
            points[index[0]],
            points[index[1]],
            points[index[2]],
            points[index[3]],
        ];
        let (verdicts, defer) = slice.is_feasible_lanes(
            v.load([u[0].x, u[1].x, u[2].x, u[3].x]),
            v.load([u[0].y, u[1].y, u[2].y, u[3].y]),
        );
        for l in 0..k {
            let ok = if defer >> l & 1 == 1 || u[l].z != 0.0 {
                deferred(&u[l])
            } else {
                verdicts >> l & 1 == 1
            };
            if ok {
                list[kept] = index[l] as u32;
                kept += 1;
            } else {
                rejected(index[l]);
            }
        }
        j += k;
    }
    list.truncate(kept);
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
    let all: Vec<Rotation3<f64>> = angles.iter().map(|&a| rot(a)).collect::<Result<_, _>>()?;
    let lean = all
        .iter()
        .map(|r| PlanarSlice::new(eval, r))
        .collect::<Option<Vec<_>>>()
        .zip(PlanarSlice::new(eval, &central));
    // Per point: (dextrous, feasible at both extremes, violation of the central check).
    let verdicts = if let Some((slices, central_slice)) = &lean {
        let central_index = angles.iter().position(|&a| a == range.central());
        let central_lean = central_index.ok_or(central_slice);
        let state = (eval.clone(), Vec::new(), LeanScratch::default());
        map_grid_tasks(
            &state,
            grid,
            dim,
            |(ev, points, scratch), axes, start, slots| {
                points.clear();
                axes.for_each_point(start, slots, |_, u| points.push(u));
                dextrous_verdicts_lean(slices, central_lean, points, slots, scratch, |k, u| {
                    let r = k.map_or(&central, |k| &all[k]);
                    ev.is_feasible_finite_rotation(&Pose::new(*u, *r))
                });
            },
        )
    } else {
        map_grid(eval, grid, dim, |ev, u| {
            let mut ok = |r: &Rotation3<f64>| ev.is_feasible_finite_rotation(&Pose::new(u, *r));
            if !ok(&first) || (angles.len() > 1 && !ok(&last)) {
                return (false, false, false);
            }
            let central_ok = ok(&central);
            let dextrous = (central_ok || !central_is_slice) && others.iter().all(&mut ok);
            (dextrous, true, !central_ok)
        })
    };
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

    /// [`PlanarSlice::wrench_columns_lanes`] gives [`PlanarSlice::wrench_columns`]'s W bit for
    /// bit in every lane, in the portable and (on a CPU with it) the AVX2 build, and the same
    /// degenerate and short cables: positions over and beyond the frame, on a frame anchor,
    /// tiny and huge coordinates.
    #[test]
    fn wrench_columns_lanes_are_the_scalar_bits() {
        use cdpr_kinematics::{Cable, Robot};
        use cdpr_tension::TensionBounds;
        use cdpr_tension::lanes::Portable;
        let cable = |c: [f64; 2], a: [f64; 2]| Cable {
            frame: Vector3::new(c[0], c[1], 0.0),
            platform: Vector3::new(a[0], a[1], 0.0),
            pulley: None,
        };
        let robot = Robot::new(
            MotionPattern::Planar,
            vec![
                cable([1.0, 0.9451], [0.0707, 0.0707]),
                cable([-1.0, 0.2232], [-0.0707, 0.0707]),
                cable([-1.0, 0.0446], [-0.1, -0.1]),
                cable([0.9069, -1.0], [0.1, -0.1]),
            ],
        )
        .unwrap();
        let criteria = vec![
            Criterion::TensionFeasible {
                method: Method::L1,
                wrench: nalgebra::DVector::from_row_slice(&[5.0, -10.0, 1.0]),
            },
            Criterion::MinCableLength(0.3),
        ];
        let eval = PoseEvaluator::new(
            robot,
            TensionBounds::uniform(4, 5.0, 100.0).unwrap(),
            criteria,
        )
        .unwrap();
        let r = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.17);
        let slice = PlanarSlice::new(&eval, &r).unwrap();
        // A frame anchor minus the rotated attachment: a zero-length cable.
        let a0 = r * Vector3::new(0.0707, 0.0707, 0.0);
        let mut xs: Vec<[f64; 2]> = (0..=40)
            .flat_map(|i| (0..=40).map(move |j| [-1.3 + 0.065 * i as f64, -1.3 + 0.065 * j as f64]))
            .collect();
        xs.extend([
            [1.0 - a0.x, 0.9451 - a0.y],
            [1e-300, -1e-300],
            [3e150, -2e150],
            [0.0, 0.0],
        ]);
        let bits = |w: &[[f64; 3]; 4]| w.map(|c| c.map(f64::to_bits));
        let mut degenerate = 0;
        for j in 0..xs.len() {
            let p: [[f64; 2]; 4] = std::array::from_fn(|l| xs[(j + 7 * l) % xs.len()]);
            let expected = p.map(|[x, y]| slice.wrench_columns(x, y));
            degenerate += expected.iter().filter(|e| e.is_none()).count();
            let check = |w: [[[f64; 4]; 3]; 4], long: u32, short: u32| {
                for (l, e) in expected.iter().enumerate() {
                    assert_eq!(long >> l & 1 == 1, e.is_some(), "lane {l} at {:?}", p[l]);
                    if let Some((we, se)) = e {
                        let wl = w.map(|c| c.map(|v| v[l]));
                        assert_eq!(bits(&wl), bits(we), "lane {l} at {:?}", p[l]);
                        assert_eq!(short >> l & 1 == 1, *se, "lane {l} at {:?}", p[l]);
                    }
                }
            };
            let v = Portable([0.0; 4]);
            let (w, long, short) =
                slice.wrench_columns_lanes(v.load(p.map(|p| p[0])), v.load(p.map(|p| p[1])));
            check(
                w.map(|c| c.map(|v| v.0)),
                Portable::bits(long),
                Portable::bits(short),
            );
            #[cfg(target_arch = "x86_64")]
            if let Some(v) = cdpr_tension::lanes::Avx2::detect() {
                use cdpr_tension::lanes::Avx2;
                let (w, long, short) =
                    slice.wrench_columns_lanes(v.load(p.map(|p| p[0])), v.load(p.map(|p| p[1])));
                check(
                    w.map(|c| c.map(Avx2::to_array)),
                    Avx2::bits(long),
                    Avx2::bits(short),
                );
            }
        }
        assert!(degenerate >= 4, "{degenerate}");
    }

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

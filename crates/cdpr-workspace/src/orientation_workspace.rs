//! # Orientation workspaces of spatial robots
//!
//! A set of orientations 𝓡 (sampled) turns the constant-orientation workspace into three
//! others (Merlet 2006 §6.1; Bosscher, Riechel & Ebert-Uphoff 2006 for cable robots):
//!
//! - the **total-orientation workspace** W_𝓡 = {u : (u, R) feasible for every R ∈ 𝓡}, the
//!   spatial form of the dextrous workspace of thesis eq. (6.28);
//! - the **maximal workspace** {u : (u, R) feasible for some R ∈ 𝓡};
//! - the **orientation workspace at a position** u: {R ∈ 𝓡 : (u, R) feasible}.
//!
//! So, for a sampled set, total ⊆ W_R ⊆ maximal for every R ∈ 𝓡 (each a grid- or point-wise
//! intersection or union of constant-orientation verdicts).
//!
//! **Orientation sets** ([`OrientationSet`], text syntax in degrees, see [`OrientationSet`]'s
//! `FromStr`):
//! - a box of XYZ Euler angles (R = R_x(r_x) R_y(r_y) R_z(r_z), as `Pose::spatial`),
//!   n values per angle with a range, endpoints included: n³ orientations at most;
//! - a tilt cone plus a torsion range, in the tilt-and-torsion angles of Bonev, Zlatanov &
//!   Gosselin (2002): R = R_z(φ) R_y(θ) R_z(σ − φ), where the platform z axis is tilted by θ
//!   ∈ [0, θ_max] from the base z axis towards azimuth φ, and σ is the torsion about it.
//!   Sampling: n tilt rings θ_k = k θ_max / (n − 1), ring k with max(1, round(a k / (n − 1)))
//!   azimuths φ = 2π j / count (a = 4(n − 1) by default, so neighbouring samples on the outer
//!   ring are as far apart as neighbouring rings), and n torsions σ over the range, endpoints
//!   included.
//!
//! **Sampling, not certification, in orientation.** Every verdict at a sampled orientation is
//! the evaluator's (certified where its criteria are); between samples nothing is claimed:
//! the total-orientation workspace of the continuous set can be smaller than that of the
//! samples (refine n to see it converge).
//!
//! **Limiting orientation.** At a boundary point of the total-orientation workspace some
//! orientation is the first to fail going outwards. For each feasible grid point next to an
//! infeasible one (6-neighbourhood), every orientation failing at the outside neighbour is
//! bisected along the grid edge to where it starts failing (to 10⁻⁹ of the edge); the one that
//! fails closest to the inside point is the limiting ("worst") orientation there, and that
//! crossing is the boundary point ([`LimitingOrientation`]).
//!
//! On the boundary mesh ([`orientation_boundary_mesh`]) the same test is the per-point
//! predicate of [`boundary_mesh_of`]: every vertex lies on the total (maximal) boundary to the
//! mesh tolerance, and each boundary vertex of a total-orientation workspace gets its limiting
//! orientation: of the orientations failing just beyond it, the first to fail along its edge.
//!
//! Each position test is an [`OrientationTest`]: per orientation its own evaluator (the
//! gravity moment of an offset centre of mass turns with the platform) — the per-point
//! predicate the boundary mesh and the grid both use.
//!
//! ## References
//! - J.-P. Merlet, *Parallel Robots*, 2nd ed., Springer 2006, §6.1 (workspace types).
//! - Bosscher, Riechel & Ebert-Uphoff (2006), "Wrench-feasible workspace generation for
//!   cable-driven robots", IEEE T-RO 22(5).
//! - Bonev, Zlatanov & Gosselin (2002), "Advantages of the modified Euler angles in the design
//!   and control of PKMs" (tilt-and-torsion angles).
//! - Thesis §6.5, eq. (6.28) (dextrous workspace).

use crate::boundary_mesh::{BoundaryMesh, MeshSettings, MeshVertex, boundary_mesh_of};
use crate::discretisation::{checked_orientation, map_grid};
use crate::{Grid, GridWorkspace, PoseEvaluator, WorkspaceError};
use cdpr_kinematics::{MotionPattern, Pose};
use nalgebra::{Rotation3, Vector3};
use std::fmt;
use std::str::FromStr;

/// A set of platform orientations, angles in radians (parsed from degrees).
#[derive(Debug, Clone, PartialEq)]
pub enum OrientationSet {
    /// A box of XYZ Euler angles [min_k, max_k], k = x, y, z; `samples` values per angle whose
    /// range is not a single value.
    EulerBox {
        /// Lower corners (r_x, r_y, r_z), rad.
        min: [f64; 3],
        /// Upper corners, rad.
        max: [f64; 3],
        /// n ≥ 2 values per non-degenerate range, endpoints included.
        samples: usize,
    },
    /// A tilt cone θ ≤ θ_max around the base z axis plus a torsion range.
    TiltTorsion {
        /// θ_max, rad, in [0, π).
        max_tilt: f64,
        /// σ range [min, max], rad.
        torsion: (f64, f64),
        /// n ≥ 2 tilt rings and torsion values (1 torsion value when min = max).
        samples: usize,
        /// Azimuths on the outer ring (default 4(n − 1)).
        azimuths: usize,
    },
}

/// One sampled orientation: its rotation and its coordinates in the set's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledOrientation {
    /// The rotation R.
    pub rotation: Rotation3<f64>,
    /// (r_x, r_y, r_z) for an Euler box, (θ, φ, σ) = (tilt, azimuth, torsion) for a tilt
    /// cone; rad.
    pub angles: [f64; 3],
}

/// R = R_z(φ) R_y(θ) R_z(σ − φ): tilt θ towards azimuth φ, torsion σ (Bonev et al. 2002).
pub fn tilt_torsion_rotation(tilt: f64, azimuth: f64, torsion: f64) -> Rotation3<f64> {
    let z = Vector3::z_axis();
    Rotation3::from_axis_angle(&z, azimuth)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), tilt)
        * Rotation3::from_axis_angle(&z, torsion - azimuth)
}

/// `samples` values over [a, b], endpoints included (one value when a = b).
fn linspace(a: f64, b: f64, samples: usize) -> Vec<f64> {
    if a == b || samples < 2 {
        return vec![a];
    }
    let last = samples - 1;
    (0..samples)
        .map(|k| {
            if k == last {
                b
            } else {
                a + (b - a) * k as f64 / last as f64
            }
        })
        .collect()
}

impl OrientationSet {
    /// The parameter names, for reports: `["rx", "ry", "rz"]` or `["tilt", "azimuth",
    /// "torsion"]`.
    pub fn angle_names(&self) -> [&'static str; 3] {
        match self {
            Self::EulerBox { .. } => ["rx", "ry", "rz"],
            Self::TiltTorsion { .. } => ["tilt", "azimuth", "torsion"],
        }
    }

    /// Checks finite angles, min ≤ max, n ≥ 2, θ_max ∈ [0, 180°), at most 100 000 samples.
    pub fn validate(&self) -> Result<(), WorkspaceError> {
        let (angles, samples): (Vec<f64>, usize) = match self {
            Self::EulerBox { min, max, samples } => {
                for k in 0..3 {
                    if min[k] > max[k] {
                        return Err(WorkspaceError::InvalidSetting {
                            what: "Euler angle range min",
                            value: min[k],
                            expected: "min ≤ max",
                        });
                    }
                }
                (min.iter().chain(max).copied().collect(), *samples)
            }
            Self::TiltTorsion {
                max_tilt,
                torsion,
                samples,
                azimuths,
            } => {
                if !(0.0..std::f64::consts::PI).contains(max_tilt) {
                    return Err(WorkspaceError::InvalidSetting {
                        what: "maximum tilt θ_max (rad)",
                        value: *max_tilt,
                        expected: "0 ≤ θ_max < π",
                    });
                }
                if torsion.0 > torsion.1 {
                    return Err(WorkspaceError::InvalidSetting {
                        what: "torsion range min",
                        value: torsion.0,
                        expected: "min ≤ max",
                    });
                }
                if *azimuths == 0 {
                    return Err(WorkspaceError::InvalidSetting {
                        what: "azimuths on the outer tilt ring",
                        value: 0.0,
                        expected: "≥ 1",
                    });
                }
                (vec![*max_tilt, torsion.0, torsion.1], *samples)
            }
        };
        if let Some(&v) = angles.iter().find(|v| !v.is_finite()) {
            return Err(WorkspaceError::NotFinite {
                what: "orientation set angle",
                value: v,
            });
        }
        if samples < 2 {
            return Err(WorkspaceError::InvalidSetting {
                what: "samples n per angle",
                value: samples as f64,
                expected: "n ≥ 2 (endpoints included)",
            });
        }
        let count = self.len();
        if count > 100_000 {
            return Err(WorkspaceError::InvalidSetting {
                what: "number of sampled orientations",
                value: count as f64,
                expected: "≤ 100 000 (lower n)",
            });
        }
        Ok(())
    }

    /// Number of sampled orientations.
    pub fn len(&self) -> usize {
        match self {
            Self::EulerBox { min, max, samples } => (0..3)
                .map(|k| if min[k] == max[k] { 1 } else { *samples })
                .product(),
            Self::TiltTorsion {
                torsion,
                samples,
                azimuths,
                ..
            } => {
                let torsions = if torsion.0 == torsion.1 { 1 } else { *samples };
                self.ring_counts(*samples, *azimuths).iter().sum::<usize>() * torsions
            }
        }
    }

    /// Whether the set is empty (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Azimuths per tilt ring (1 on the axis θ = 0, and on every ring when θ_max = 0).
    fn ring_counts(&self, samples: usize, azimuths: usize) -> Vec<usize> {
        let flat = matches!(self, Self::TiltTorsion { max_tilt, .. } if *max_tilt == 0.0);
        if flat {
            return vec![1];
        }
        let last = samples.saturating_sub(1).max(1);
        (0..samples)
            .map(|k| ((azimuths * k) as f64 / last as f64).round().max(1.0) as usize)
            .collect()
    }

    /// The sampled orientations, in a fixed order (Euler: r_x slowest, r_z fastest; tilt
    /// cone: ring, azimuth, torsion fastest).
    pub fn orientations(&self) -> Result<Vec<SampledOrientation>, WorkspaceError> {
        self.validate()?;
        let mut out = Vec::with_capacity(self.len());
        match self {
            Self::EulerBox { min, max, samples } => {
                let axes: Vec<Vec<f64>> =
                    (0..3).map(|k| linspace(min[k], max[k], *samples)).collect();
                for &a in &axes[0] {
                    for &b in &axes[1] {
                        for &c in &axes[2] {
                            out.push(SampledOrientation {
                                rotation: Pose::spatial(Vector3::zeros(), a, b, c).rotation,
                                angles: [a, b, c],
                            });
                        }
                    }
                }
            }
            Self::TiltTorsion {
                max_tilt,
                torsion,
                samples,
                azimuths,
            } => {
                let torsions = linspace(torsion.0, torsion.1, *samples);
                let counts = self.ring_counts(*samples, *azimuths);
                let tilts = linspace(0.0, *max_tilt, counts.len());
                for (&tilt, &count) in tilts.iter().zip(&counts) {
                    for j in 0..count {
                        let azimuth = std::f64::consts::TAU * j as f64 / count as f64;
                        for &sigma in &torsions {
                            out.push(SampledOrientation {
                                rotation: tilt_torsion_rotation(tilt, azimuth, sigma),
                                angles: [tilt, azimuth, sigma],
                            });
                        }
                    }
                }
            }
        }
        Ok(out)
    }
}

impl fmt::Display for OrientationSet {
    /// The set in the syntax [`OrientationSet`]'s `FromStr` reads (degrees).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Degrees rounded to 1e-9 (the radians of `-30` print as −29.999999999999996°).
        let deg = |x: f64| (x.to_degrees() * 1e9).round() / 1e9;
        let range = |a: f64, b: f64| {
            let (a, b) = (deg(a), deg(b));
            if a == b {
                format!("{a}")
            } else {
                format!("{a}..{b}")
            }
        };
        match self {
            Self::EulerBox { min, max, samples } => write!(
                f,
                "euler:rx={},ry={},rz={},n={samples}",
                range(min[0], max[0]),
                range(min[1], max[1]),
                range(min[2], max[2])
            ),
            Self::TiltTorsion {
                max_tilt,
                torsion,
                samples,
                azimuths,
            } => write!(
                f,
                "tilt:{},torsion={},n={samples},azimuths={azimuths}",
                deg(*max_tilt),
                range(torsion.0, torsion.1)
            ),
        }
    }
}

/// A parse error of the `--orientations` syntax.
#[derive(Debug, Clone, PartialEq)]
pub struct OrientationSyntaxError(pub String);

impl fmt::Display for OrientationSyntaxError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (expected e.g. `euler:rx=-10..10,ry=-10..10,rz=-20..20,n=5` or \
             `tilt:20,torsion=-30..30,n=5`; angles in degrees)",
            self.0
        )
    }
}

impl std::error::Error for OrientationSyntaxError {}

/// `A..B` or `A` (degrees) as radians.
fn range_deg(key: &str, v: &str) -> Result<(f64, f64), OrientationSyntaxError> {
    let num = |s: &str| {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| OrientationSyntaxError(format!("`{key}`: `{s}` is not a number")))
    };
    let (a, b) = match v.split_once("..") {
        Some((a, b)) => (num(a)?, num(b)?),
        None => {
            let a = num(v)?;
            (a, a)
        }
    };
    if a > b {
        return Err(OrientationSyntaxError(format!(
            "`{key}`: range {a}..{b} has min > max"
        )));
    }
    Ok((a.to_radians(), b.to_radians()))
}

impl FromStr for OrientationSet {
    type Err = OrientationSyntaxError;

    /// `euler:rx=A..B,ry=A..B,rz=A..B,n=N` (omitted angles are 0, a single value fixes one;
    /// default n = 3) or `tilt:T,torsion=A..B,n=N[,azimuths=K]` (cone half-angle T, default
    /// torsion 0, n = 3); degrees.
    ///
    /// ```
    /// use cdpr_workspace::OrientationSet;
    /// let s: OrientationSet = "euler:rx=-10..10,rz=5,n=3".parse().unwrap();
    /// assert_eq!(s.len(), 3); // rx takes 3 values, ry = 0 and rz = 5° are fixed
    /// let t: OrientationSet = "tilt:20,torsion=-30..30,n=3".parse().unwrap();
    /// assert_eq!(t.len(), (1 + 4 + 8) * 3); // rings of 1, 4, 8 azimuths; 3 torsions
    /// assert!("tilt:20,twist=3".parse::<OrientationSet>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (kind, rest) = s
            .split_once(':')
            .ok_or_else(|| OrientationSyntaxError(format!("`{s}`: no `euler:` or `tilt:`")))?;
        let mut samples = 3usize;
        let mut azimuths = None;
        let count = |key: &str, v: &str| {
            v.trim()
                .parse::<usize>()
                .map_err(|_| OrientationSyntaxError(format!("`{key}`: `{v}` is not a count")))
        };
        let set = match kind.trim() {
            "euler" => {
                let (mut min, mut max) = ([0.0; 3], [0.0; 3]);
                for item in rest.split(',').map(str::trim).filter(|i| !i.is_empty()) {
                    let (key, v) = item.split_once('=').ok_or_else(|| {
                        OrientationSyntaxError(format!("`{item}`: expected key=value"))
                    })?;
                    match key.trim() {
                        k @ ("rx" | "ry" | "rz") => {
                            let i = ["rx", "ry", "rz"].iter().position(|n| *n == k).unwrap_or(0);
                            (min[i], max[i]) = range_deg(k, v)?;
                        }
                        "n" => samples = count("n", v)?,
                        other => {
                            return Err(OrientationSyntaxError(format!(
                                "unknown key `{other}` for euler (rx, ry, rz, n)"
                            )));
                        }
                    }
                }
                Self::EulerBox { min, max, samples }
            }
            "tilt" => {
                let mut items = rest.split(',').map(str::trim);
                let first = items.next().unwrap_or_default();
                let tilt = first
                    .parse::<f64>()
                    .ok()
                    .filter(|t| t.is_finite() && (0.0..180.0).contains(t))
                    .ok_or_else(|| {
                        OrientationSyntaxError(format!(
                            "tilt cone half-angle `{first}` is not a number of degrees in [0, 180)"
                        ))
                    })?;
                let mut torsion = (0.0, 0.0);
                for item in items.filter(|i| !i.is_empty()) {
                    let (key, v) = item.split_once('=').ok_or_else(|| {
                        OrientationSyntaxError(format!("`{item}`: expected key=value"))
                    })?;
                    match key.trim() {
                        "torsion" => torsion = range_deg("torsion", v)?,
                        "n" => samples = count("n", v)?,
                        "azimuths" => azimuths = Some(count("azimuths", v)?),
                        other => {
                            return Err(OrientationSyntaxError(format!(
                                "unknown key `{other}` for tilt (torsion, n, azimuths)"
                            )));
                        }
                    }
                }
                Self::TiltTorsion {
                    max_tilt: tilt.to_radians(),
                    torsion,
                    samples,
                    azimuths: azimuths.unwrap_or(4 * samples.saturating_sub(1).max(1)),
                }
            }
            other => {
                return Err(OrientationSyntaxError(format!(
                    "unknown orientation set `{other}`"
                )));
            }
        };
        set.validate()
            .map_err(|e| OrientationSyntaxError(e.to_string()))?;
        Ok(set)
    }
}

/// Which workspace an [`OrientationTest`] decides.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OrientationWorkspaceKind {
    /// Every orientation of the set feasible.
    Total,
    /// Some orientation of the set feasible.
    Maximal,
}

impl OrientationWorkspaceKind {
    /// `"total"` or `"maximal"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Total => "total",
            Self::Maximal => "maximal",
        }
    }
}

/// The per-position test of an orientation workspace: one evaluator per sampled orientation.
///
/// Cloning it clones the evaluators (one per rayon thread on a grid). The test starts with the
/// orientation that decided the previous position (it is likely to decide the next one too);
/// the verdict does not depend on that order.
#[derive(Debug, Clone)]
pub struct OrientationTest {
    kind: OrientationWorkspaceKind,
    rotations: Vec<Rotation3<f64>>,
    evaluators: Vec<PoseEvaluator>,
    /// Index of the orientation that decided the last verdict.
    last: usize,
}

impl OrientationTest {
    /// A test from one evaluator per orientation (same robot; e.g. each with the gravity
    /// wrench of its orientation). Errors on an empty or mismatched list, a non-spatial robot
    /// (planar robots: `dextrous_workspace`) or a non-finite rotation.
    pub fn new(
        kind: OrientationWorkspaceKind,
        rotations: Vec<Rotation3<f64>>,
        evaluators: Vec<PoseEvaluator>,
    ) -> Result<Self, WorkspaceError> {
        if rotations.is_empty() || rotations.len() != evaluators.len() {
            return Err(WorkspaceError::DimensionMismatch {
                what: "orientations and evaluators (one per orientation, at least one)",
                expected: rotations.len().max(1),
                found: evaluators.len(),
            });
        }
        for e in &evaluators {
            let motion = e.robot().motion();
            if motion != MotionPattern::Spatial {
                return Err(WorkspaceError::NotSixDof {
                    method: "an orientation workspace",
                    motion: motion.name(),
                });
            }
            e.validate()?;
        }
        let rotations = rotations
            .iter()
            .map(|r| checked_orientation(MotionPattern::Spatial, r))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            kind,
            rotations,
            evaluators,
            last: 0,
        })
    }

    /// The same evaluator at every orientation (no orientation-dependent load).
    pub fn uniform(
        kind: OrientationWorkspaceKind,
        eval: &PoseEvaluator,
        orientations: &[SampledOrientation],
    ) -> Result<Self, WorkspaceError> {
        Self::new(
            kind,
            orientations.iter().map(|o| o.rotation).collect(),
            vec![eval.clone(); orientations.len()],
        )
    }

    /// Total or maximal.
    pub fn kind(&self) -> OrientationWorkspaceKind {
        self.kind
    }

    /// Number of orientations.
    pub fn len(&self) -> usize {
        self.rotations.len()
    }

    /// Always false (a test has at least one orientation).
    pub fn is_empty(&self) -> bool {
        self.rotations.is_empty()
    }

    /// Whether orientation k is feasible at position u.
    #[inline]
    pub fn is_feasible_at(&mut self, k: usize, u: Vector3<f64>) -> bool {
        self.evaluators[k].is_feasible_finite_rotation(&Pose::new(u, self.rotations[k]))
    }

    /// Whether u belongs to the workspace: all (total) or some (maximal) orientations feasible.
    pub fn is_feasible(&mut self, u: Vector3<f64>) -> bool {
        let n = self.len();
        // Total fails at the first infeasible orientation; maximal succeeds at the first
        // feasible one: the deciding orientation, tried first next time.
        let decisive = self.kind == OrientationWorkspaceKind::Maximal;
        for step in 0..n {
            let k = (self.last + step) % n;
            if self.is_feasible_at(k, u) == decisive {
                self.last = k;
                return decisive;
            }
        }
        !decisive
    }

    /// The verdict of every orientation at u (the orientation workspace at a position).
    pub fn feasible_orientations(&mut self, u: Vector3<f64>) -> Vec<bool> {
        (0..self.len()).map(|k| self.is_feasible_at(k, u)).collect()
    }

    /// Along the segment from `inside` (orientation k feasible) to `outside` (infeasible), the
    /// parameter t ∈ [0, 1] where orientation k starts failing, by bisection to 2⁻³⁰.
    fn crossing(&mut self, k: usize, inside: Vector3<f64>, outside: Vector3<f64>) -> f64 {
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..30 {
            let mid = 0.5 * (lo + hi);
            if self.is_feasible_at(k, inside + (outside - inside) * mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// The orientation that limits the total-orientation workspace at one boundary point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitingOrientation {
    /// Flat index of the feasible grid point.
    pub point: usize,
    /// Index of the limiting orientation in the sampled set.
    pub orientation: usize,
    /// Where that orientation starts failing along the edge to the nearest infeasible
    /// neighbour: a point of the total-orientation boundary (m).
    pub boundary_point: Vector3<f64>,
}

/// An orientation workspace on a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct OrientationGridWorkspace {
    /// Total or maximal.
    pub kind: OrientationWorkspaceKind,
    /// The verdicts (feasible = in the workspace).
    pub workspace: GridWorkspace,
    /// Total-orientation workspaces: one entry per feasible grid point with an infeasible
    /// 6-neighbour (empty for maximal workspaces).
    pub limiting: Vec<LimitingOrientation>,
}

/// The total-orientation or maximal workspace of `test` on a 3-D `grid`, with the limiting
/// orientation at every boundary grid point of a total-orientation workspace.
///
/// ```
/// use cdpr_kinematics::reference_robots::ipanema_like_8;
/// use cdpr_tension::TensionBounds;
/// use cdpr_workspace::{
///     orientation_workspace, Criterion, Grid, OrientationSet, OrientationTest,
///     OrientationWorkspaceKind, PoseEvaluator, Region,
/// };
/// use nalgebra::Vector3;
/// // An 8-cable robot with crossed cables (4 m × 3 m × 2 m frame): wrench-closed at its centre
/// // for torsions within ±5° (not at ±10°: `cdpr orientations` shows it).
/// let eval = PoseEvaluator::new(ipanema_like_8(), TensionBounds::uniform(8, 1.0, 100.0).unwrap(),
///                               vec![Criterion::WrenchClosure]).unwrap();
/// let set: OrientationSet = "euler:rz=-5..5,n=3".parse().unwrap();
/// let test = OrientationTest::uniform(OrientationWorkspaceKind::Total, &eval,
///                                     &set.orientations().unwrap()).unwrap();
/// let centre = Vector3::new(0.0, 0.0, 1.0);
/// let grid = Grid::new(4, Region::cuboid(centre.add_scalar(-0.8), centre.add_scalar(0.8)));
/// let ws = orientation_workspace(&test, &grid).unwrap();
/// assert!(ws.workspace.feasible[62]); // the centre of the 5 × 5 × 5 grid
/// ```
pub fn orientation_workspace(
    test: &OrientationTest,
    grid: &Grid,
) -> Result<OrientationGridWorkspace, WorkspaceError> {
    grid.validate(3)?;
    let feasible = map_grid(test, grid, 3, |t, u| t.is_feasible(u));
    let workspace = GridWorkspace::from_verdicts(*grid, 3, feasible);
    let limiting = match test.kind {
        OrientationWorkspaceKind::Maximal => Vec::new(),
        OrientationWorkspaceKind::Total => limiting_orientations(test, &workspace),
    };
    Ok(OrientationGridWorkspace {
        kind: test.kind,
        workspace,
        limiting,
    })
}

/// The boundary mesh of an orientation workspace, with the limiting orientation per vertex.
#[derive(Debug, Clone, PartialEq)]
pub struct OrientationMesh {
    /// The mesh (vertices on the total-orientation or maximal boundary to its tolerance).
    pub mesh: BoundaryMesh,
    /// Total-orientation workspaces: per mesh vertex on the boundary (a grid-edge crossing),
    /// the index of the limiting orientation — among those failing a tolerance ε beyond the
    /// vertex along its edge, the one that starts failing closest to the edge's feasible end;
    /// `None` for box-cap corners and for maximal workspaces.
    pub limiting: Vec<Option<usize>>,
}

/// The total-orientation or maximal workspace of `test` as a boundary mesh
/// ([`boundary_mesh_of`] with the test as the per-point predicate), with the limiting
/// orientation at every boundary vertex of a total-orientation workspace.
pub fn orientation_boundary_mesh(
    test: &OrientationTest,
    grid: &Grid,
    settings: &MeshSettings,
) -> Result<OrientationMesh, WorkspaceError> {
    let mesh = boundary_mesh_of(
        test,
        |t: &mut OrientationTest, u| t.is_feasible(u),
        grid,
        settings,
    )?;
    let limiting = match test.kind {
        OrientationWorkspaceKind::Maximal => vec![None; mesh.vertices.len()],
        OrientationWorkspaceKind::Total => {
            let eps = mesh.tolerance;
            crate::parallel::map_init(
                mesh.vertices.len(),
                || test.clone(),
                |t, i| {
                    let (v, origin) = (&mesh.vertices[i], &mesh.origins[i]);
                    let MeshVertex::Crossing {
                        feasible_end,
                        infeasible_end,
                        ..
                    } = origin
                    else {
                        return None;
                    };
                    let (a, b) = (Vector3::from(*feasible_end), Vector3::from(*infeasible_end));
                    let dir = (b - a).normalize();
                    let outside = Vector3::from(*v) + dir * eps;
                    let failing: Vec<usize> = (0..t.len())
                        .filter(|&k| !t.is_feasible_at(k, outside))
                        .collect();
                    match failing.as_slice() {
                        [] => None,
                        [k] => Some(*k),
                        _ => failing
                            .iter()
                            .map(|&k| (t.crossing(k, a, outside), k))
                            .min_by(|x, y| x.0.total_cmp(&y.0))
                            .map(|(_, k)| k),
                    }
                },
            )
        }
    };
    Ok(OrientationMesh { mesh, limiting })
}

/// The 6-neighbours of grid point `idx` (flat index, x fastest) inside the grid.
fn neighbours(idx: usize, p: usize) -> impl Iterator<Item = usize> {
    let (i, j, l) = (idx % p, (idx / p) % p, idx / (p * p));
    let steps = [1, p, p * p];
    [i, j, l]
        .into_iter()
        .zip(steps)
        .flat_map(move |(c, s)| [(c > 0).then(|| idx - s), (c + 1 < p).then_some(idx + s)])
        .flatten()
}

/// The limiting orientation at every feasible grid point next to an infeasible one.
fn limiting_orientations(test: &OrientationTest, ws: &GridWorkspace) -> Vec<LimitingOrientation> {
    let p = ws.grid.points_per_axis();
    let boundary: Vec<(usize, usize)> = (0..ws.feasible.len())
        .filter(|&i| ws.feasible[i])
        .filter_map(|i| neighbours(i, p).find(|&j| !ws.feasible[j]).map(|j| (i, j)))
        .collect();
    crate::parallel::map_init(
        boundary.len(),
        || test.clone(),
        |t, b| {
            let (i, j) = boundary[b];
            let (inside, outside) = (ws.point(i), ws.point(j));
            let mut best = (f64::INFINITY, 0);
            for k in 0..t.len() {
                if !t.is_feasible_at(k, outside) {
                    let s = t.crossing(k, inside, outside);
                    if s < best.0 {
                        best = (s, k);
                    }
                }
            }
            LimitingOrientation {
                point: i,
                orientation: best.1,
                boundary_point: inside + (outside - inside) * best.0.min(1.0),
            }
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn tilt_torsion_axis_and_torsion_by_hand() {
        // Tilt 30° towards azimuth 90°: the platform z axis is (0, sin 30°, cos 30°).
        let r = tilt_torsion_rotation(30f64.to_radians(), 90f64.to_radians(), 0.0);
        let z = r * Vector3::z();
        assert_relative_eq!(
            z,
            Vector3::new(0.0, 0.5, 3f64.sqrt() / 2.0),
            epsilon = 1e-15
        );
        // No tilt: a pure rotation by the torsion about z.
        let r = tilt_torsion_rotation(0.0, 1.0, 0.4);
        assert_relative_eq!(r.angle(), 0.4, epsilon = 1e-15);
    }

    #[test]
    fn parsing_and_counts() {
        let e: OrientationSet = "euler:rx=-10..10,ry=-10..10,rz=-20..20,n=5"
            .parse()
            .unwrap();
        assert_eq!(e.len(), 125);
        let o = e.orientations().unwrap();
        assert_eq!(o.len(), 125);
        assert_relative_eq!(o[0].angles[0], -10f64.to_radians());
        assert_relative_eq!(o[124].angles[2], 20f64.to_radians());
        let t: OrientationSet = "tilt:20,torsion=-30..30,n=5".parse().unwrap();
        // Rings of 1, 4, 8, 12, 16 azimuths, 5 torsions.
        assert_eq!(t.len(), 41 * 5);
        assert_eq!(t.orientations().unwrap().len(), 205);
        for set in [&e, &t] {
            let again: OrientationSet = set.to_string().parse().unwrap();
            assert_eq!(again.len(), set.len(), "{set}");
        }
        assert_eq!(t.to_string(), "tilt:20,torsion=-30..30,n=5,azimuths=16");
        let flat: OrientationSet = "tilt:0,n=4".parse().unwrap();
        assert_eq!(flat.len(), 1);
        for bad in [
            "euler:rx=10..-10",
            "euler:rw=1",
            "euler:n=1,rx=0..1",
            "tilt:200",
            "tilt:x",
            "cone:10",
            "euler:rx=nan",
            "euler:rx=-90..90,ry=-90..90,rz=-90..90,n=100",
        ] {
            assert!(bad.parse::<OrientationSet>().is_err(), "{bad}");
        }
    }

    #[test]
    fn neighbours_stay_in_the_grid() {
        let p = 3;
        let mut corner: Vec<usize> = neighbours(0, p).collect();
        corner.sort();
        assert_eq!(corner, vec![1, 3, 9]);
        assert_eq!(neighbours(13, p).count(), 6); // the centre
    }
}

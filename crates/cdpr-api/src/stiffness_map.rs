//! # The stiffness map over the feasible polygon
//!
//! The stiffness-oriented study of Picard, Caro, Plestan & Claveau 2020 (Fig. 4) at one pose of
//! a robot with redundancy n − DOF = 2: every equilibrium tension is t = t0 + N λ, λ in the
//! feasible polygon (eqs. 5–6). For each tension the platform moves by δX = K(t)⁻¹ δw under the
//! load δw, with K = Kp + Ka (eq. 4, k_i = E·S / l_i). The map gives |d · δp| on a grid over the
//! polygon, at the barycentre and at the SOTDA optimum (eq. 7), along t(ν) = t_bary + ν (t_opt −
//! t_bary), ν ∈ [0, 1], and the reduction 100 (δ_bary − δ_opt) / δ_bary in %. The tensions
//! balance the wrench plus the platform's gravity; the displacement is the response to the wrench
//! alone (a unit force along d if it is zero), in thousandths of the robot's length unit.
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020, eqs. (4)–(7) and Fig. 4.

use cdpr_tension::{
    FeasiblePolygon, Method, SotdaSettings, StiffnessData, TensionBounds, TensionOutcome,
    TensionProblem, TensionSolver, sotda_displacement,
};
use nalgebra::{DVector, Vector2};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::{check_method, external_wrench, pose, wrench};
use crate::tension::{SotdaSearch, sotda_settings};
use crate::{ApiError, Robot};

/// The unit of the displacements.
pub const DISPLACEMENT_UNIT: &str = "mm (1e-3 of the robot's length unit)";

fn default_grid() -> usize {
    80
}

fn default_nu_samples() -> usize {
    21
}

/// The displacement over the feasible polygon at one pose (`cdpr stiffness-map`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct StiffnessMapRequest {
    /// The robot (redundancy 2, `axial_stiffness` on every cable).
    pub robot: Robot,
    /// Platform pose (motion-pattern coordinates, m and rad).
    pub pose: Vec<f64>,
    /// External wrench w_e (N, N·m; default zero).
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// Direction d of the displacement (2 or 3 numbers; default +y).
    #[serde(default)]
    pub direction: Option<Vec<f64>>,
    /// Grid points per λ axis over the polygon's bounding box (2…2000, default 80).
    #[serde(default = "default_grid")]
    pub grid: usize,
    /// ν values in [0, 1] of the intermediate-solution curve (2…10000, default 21).
    #[serde(default = "default_nu_samples")]
    pub nu_samples: usize,
    /// SOTDA's real-time variant (the corners with a cable at t_max) instead of the full search.
    #[serde(default)]
    pub corners: bool,
}

/// |d · δp| on the grid over the polygon's bounding box.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct LambdaGridReport {
    /// λ1 of the columns (N).
    pub lambda1: Vec<f64>,
    /// λ2 of the rows (N).
    pub lambda2: Vec<f64>,
    /// `values[j][i]` at (`lambda1[i]`, `lambda2[j]`) (mm); null outside the polygon.
    pub values: Vec<Vec<Option<f64>>>,
}

/// What the map found when the polygon is not empty.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct MapReport {
    /// d.
    pub direction: Vec<f64>,
    /// w_ext = w_e + the robot file's load (N, N·m): what the tensions balance.
    pub external_wrench: Vec<f64>,
    /// δw: the load of the displacement (N, N·m); null for a unit force along d.
    pub load: Option<Vec<f64>>,
    /// `sotda (corners)` or `sotda (full search)`.
    pub method: String,
    /// The unit of the displacements.
    pub unit: String,
    /// |d·δp| at the barycentre (mm).
    pub displacement_barycenter: f64,
    /// |d·δp| at the SOTDA optimum (mm).
    pub displacement_optimum: f64,
    /// 100 (δ_bary − δ_opt) / δ_bary (%).
    pub reduction_percent: f64,
    /// grid_max − grid_min (mm).
    pub spread: f64,
    /// Smallest grid value (mm).
    pub grid_min: f64,
    /// Largest grid value (mm).
    pub grid_max: f64,
    /// The polygon's vertices λ (N).
    pub polygon: Vec<[f64; 2]>,
    /// λ of the barycentre (N).
    pub barycenter_lambda: [f64; 2],
    /// λ of the SOTDA optimum (N).
    pub optimum_lambda: [f64; 2],
    /// Tensions at the barycentre (N).
    pub tensions_barycenter: Vec<f64>,
    /// Tensions at the SOTDA optimum (N).
    pub tensions_optimum: Vec<f64>,
    /// [ν, |d·δp| (mm)] pairs.
    pub nu_curve: Vec<[f64; 2]>,
    /// The grid.
    pub grid: LambdaGridReport,
}

/// The JSON of `cdpr stiffness-map --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct StiffnessMapReport {
    /// Robot name.
    pub robot: String,
    /// The pose.
    pub pose: Vec<f64>,
    /// Whether the feasible polygon is not empty.
    pub feasible: bool,
    /// Why there is no polygon (infeasible poses only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// The map (feasible poses only).
    #[serde(flatten)]
    pub map: Option<MapReport>,
}

impl StiffnessMapRequest {
    /// A request at `pose` with the default grid, curve and search.
    pub fn new(robot: Robot, pose: Vec<f64>) -> Self {
        Self {
            robot,
            pose,
            wrench: None,
            direction: None,
            grid: default_grid(),
            nu_samples: default_nu_samples(),
            corners: false,
        }
    }

    /// Checks the request; the cables' E·S (N) and the SOTDA settings.
    fn prepare(&self) -> Result<(Vec<f64>, SotdaSettings), ApiError> {
        let robot = self.robot.description();
        robot
            .require_no_passive_springs(
                "the stiffness map (cables only; the springs' K would add to it)",
            )
            .map_err(ApiError::invalid)?;
        check_method(robot, Method::Sotda)?;
        if !(2..=2000).contains(&self.grid) {
            return Err(ApiError::invalid("--grid must lie in [2, 2000]"));
        }
        if !(2..=10_000).contains(&self.nu_samples) {
            return Err(ApiError::invalid("--nu-samples must lie in [2, 10000]"));
        }
        let es = robot.axial_stiffness.clone().ok_or_else(|| {
            ApiError::invalid(
                "stiffness-map needs `axial_stiffness` (E·S, N) on every cable of the robot file",
            )
        })?;
        let r = robot.robot.cable_count() as isize - robot.robot.dof() as isize;
        if r != 2 {
            return Err(ApiError::invalid(format!(
                "stiffness-map needs redundancy n − DOF = 2 (the feasible polygon), this robot \
                 has {r}"
            )));
        }
        let search = if self.corners {
            SotdaSearch::Corners
        } else {
            SotdaSearch::Full
        };
        let mut settings = sotda_settings(self.direction.as_deref(), 1.0, search)?;
        let w_e = wrench(robot, self.wrench.as_deref())?;
        if w_e.amax() > 0.0 {
            settings.perturbation = Some(w_e);
        }
        Ok((es, settings))
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare()?;
        pose(self.robot.description(), &self.pose).map(|_| ())
    }

    /// The map, or why the pose has no feasible polygon.
    pub fn run(&self) -> Result<StiffnessMapReport, ApiError> {
        let (es, settings) = self.prepare()?;
        let robot = self.robot.description();
        let pose = pose(robot, &self.pose)?;
        let w_ext = external_wrench(robot, &pose, self.wrench.as_deref())?;
        let kin = robot.robot.inverse_kinematics(&pose)?;
        let w = kin.wrench_matrix();
        let mut problem = TensionProblem::new(&w, &w_ext, &robot.bounds);
        problem.stiffness = Some(StiffnessData {
            kinematics: &kin,
            axial_stiffness: &es,
        });
        let report = |map: Option<MapReport>, reason: Option<String>| StiffnessMapReport {
            robot: robot.name.clone(),
            pose: self.pose.clone(),
            feasible: map.is_some(),
            reason,
            map,
        };
        let polygon = match FeasiblePolygon::compute(&problem)? {
            Ok(p) => p,
            Err(reason) => return Ok(report(None, Some(reason.to_string()))),
        };
        let optimum = match TensionSolver::sotda(settings.clone()).solve(&problem)? {
            TensionOutcome::Feasible(s) => s.tensions,
            TensionOutcome::Infeasible(reason) => {
                return Ok(report(None, Some(reason.to_string())));
            }
        };
        let stiff = problem.stiffness.expect("set above");
        let disp = |t: &DVector<f64>| -> Result<f64, ApiError> {
            let d = sotda_displacement(&stiff, &settings, &w_ext, t.as_slice())?;
            Ok(d.unwrap_or(f64::NAN) * 1e3)
        };
        let map = self.map(&robot.bounds, polygon, optimum, disp)?;
        Ok(report(
            Some(MapReport {
                direction: settings.direction.as_slice().to_vec(),
                external_wrench: w_ext.as_slice().to_vec(),
                load: settings
                    .perturbation
                    .as_ref()
                    .map(|p| p.as_slice().to_vec()),
                method: if self.corners {
                    "sotda (corners)"
                } else {
                    "sotda (full search)"
                }
                .into(),
                unit: DISPLACEMENT_UNIT.into(),
                ..map
            }),
            None,
        ))
    }

    /// The displacements at the barycentre, the optimum, along t(ν) and over the polygon.
    fn map(
        &self,
        bounds: &TensionBounds,
        polygon: FeasiblePolygon,
        optimum: DVector<f64>,
        disp: impl Fn(&DVector<f64>) -> Result<f64, ApiError>,
    ) -> Result<MapReport, ApiError> {
        let t_bary = polygon.barycenter();
        let l_bary = polygon.barycenter_lambda();
        let v = polygon.null_space.transpose() * (&optimum - &polygon.particular);
        let (d_bary, d_opt) = (disp(&t_bary)?, disp(&optimum)?);
        let nu_curve = (0..self.nu_samples)
            .map(|k| {
                let nu = k as f64 / (self.nu_samples - 1) as f64;
                Ok([nu, disp(&(&t_bary + (&optimum - &t_bary) * nu))?])
            })
            .collect::<Result<Vec<_>, ApiError>>()?;
        let grid = lambda_grid(&polygon, bounds, self.grid, &disp)?;
        let finite = grid.values.iter().flatten().flatten();
        let (gmin, gmax) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
        Ok(MapReport {
            direction: Vec::new(),
            external_wrench: Vec::new(),
            load: None,
            method: String::new(),
            unit: String::new(),
            displacement_barycenter: d_bary,
            displacement_optimum: d_opt,
            reduction_percent: 100.0 * (d_bary - d_opt) / d_bary,
            spread: gmax - gmin,
            grid_min: gmin,
            grid_max: gmax,
            polygon: polygon.vertices.iter().map(|v| [v.x, v.y]).collect(),
            barycenter_lambda: [l_bary.x, l_bary.y],
            optimum_lambda: [v[0], v[1]],
            tensions_barycenter: t_bary.as_slice().to_vec(),
            tensions_optimum: optimum.as_slice().to_vec(),
            nu_curve,
            grid,
        })
    }
}

/// `f(t(λ))` on an n × n grid over the polygon's bounding box (None outside).
fn lambda_grid(
    polygon: &FeasiblePolygon,
    bounds: &TensionBounds,
    n: usize,
    f: impl Fn(&DVector<f64>) -> Result<f64, ApiError>,
) -> Result<LambdaGridReport, ApiError> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for v in &polygon.vertices {
        for d in 0..2 {
            lo[d] = lo[d].min(v[d]);
            hi[d] = hi[d].max(v[d]);
        }
    }
    let axis = |d: usize| -> Vec<f64> {
        (0..n)
            .map(|i| lo[d] + (hi[d] - lo[d]) * i as f64 / (n - 1) as f64)
            .collect()
    };
    let (lambda1, lambda2) = (axis(0), axis(1));
    let values = lambda2
        .iter()
        .map(|&l2| {
            lambda1
                .iter()
                .map(|&l1| {
                    let l = Vector2::new(l1, l2);
                    let inside = polygon.contains(&l, bounds);
                    let v = inside.then(|| f(&polygon.tensions_at(&l))).transpose()?;
                    Ok(v.filter(|v| v.is_finite()))
                })
                .collect::<Result<Vec<_>, ApiError>>()
        })
        .collect::<Result<Vec<_>, ApiError>>()?;
    Ok(LambdaGridReport {
        lambda1,
        lambda2,
        values,
    })
}

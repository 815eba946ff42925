//! # Dimensional synthesis
//!
//! Places the frame anchors of a planar robot on the 2 × 2 square frame [−1, 1]² to maximise
//! its dextrous workspace area A_d (thesis §6.6, eq. 6.29): the design d = [β1, …, βn] puts
//! anchor i where the ray from the origin at polar angle βi meets the frame; the only
//! constraint is a minimum angular separation β_min of consecutive anchors. The objective is
//! the dextrous area (eq. 6.28, [`crate::dextrous()`]) on a fixed grid, counted as the thesis
//! does (feasible points × cell area), maximised by Dynamic-Q (Snyman & Hay 2002), a compass
//! search (Kolda, Lewis & Torczon 2003), both in turn, or those and a global stage
//! (`cdpr_workspace::synthesis`).
//!
//! ## References
//! - Thesis §6.6, eq. 6.29 and Tables 6.5–6.10 (the settings and the published optima).

use cdpr_kinematics::MotionPattern;
use cdpr_tension::Method;
use cdpr_workspace::synthesis::{
    Method as Optimizer, SynthesisResult, SynthesisSettings, Termination, frame_anchor,
    in_first_turn, robot_from_design, separation_violation, synthesise,
};
use cdpr_workspace::{Grid, GridWorkspace, OrientationRange, VolumeConvention};
use nalgebra::{Rotation3, Vector3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::criteria::{CriteriaSetup, WorkspaceCriteria};
use crate::workspace::box_numbers;
use crate::{ApiError, CentralCheckReport, Dextrous, RangeReport, Robot, dextrous, region};

/// The optimiser of a synthesis (`--optimizer`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum SynthesisOptimizer {
    /// The thesis' Dynamic-Q (spherical quadratic approximations).
    DynamicQ,
    /// Derivative-free compass search with restarts (exact penalty).
    Compass,
    /// Dynamic-Q, then the compass search polishes its answer.
    #[default]
    DynamicQCompass,
    /// Dynamic-Q-compass, then 128 quasi-random designs, the best 3 polished.
    Global,
}

impl SynthesisOptimizer {
    /// The name on the command line and in JSON (`dynamic-q`, `compass`, …).
    pub fn name(self) -> &'static str {
        match self {
            Self::DynamicQ => "dynamic-q",
            Self::Compass => "compass",
            Self::DynamicQCompass => "dynamic-q-compass",
            Self::Global => "global",
        }
    }

    /// The optimiser of a name (`None` for an unknown name).
    pub fn from_name(name: &str) -> Option<Self> {
        [
            Self::DynamicQ,
            Self::Compass,
            Self::DynamicQCompass,
            Self::Global,
        ]
        .into_iter()
        .find(|o| o.name() == name)
    }

    fn method(self) -> Optimizer {
        match self {
            Self::DynamicQ => Optimizer::DynamicQ,
            Self::Compass => Optimizer::CompassSearch,
            Self::DynamicQCompass => Optimizer::DynamicQThenCompass,
            Self::Global => Optimizer::Global,
        }
    }
}

fn default_move_limit() -> f64 {
    0.1
}

/// Dimensional synthesis of a planar robot for maximal dextrous area (`cdpr synthesize`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct SynthesisRequest {
    /// The robot (planar): platform attachments, limits and gravity are used; its frame anchors
    /// are replaced by the design.
    pub robot: Robot,
    /// The criteria and their load. Default tension method: exact for n = DOF, closed-form
    /// (Algorithm 6.1) for n = DOF + 1, l1 otherwise.
    #[serde(flatten)]
    pub criteria: WorkspaceCriteria,
    /// The orientation range of the dextrous workspace (rad).
    pub orientations: RangeReport,
    /// M: (M+1)² grid points of the objective (default 100 for 3 cables, 50 otherwise).
    #[serde(default)]
    pub grid: Option<usize>,
    /// The objective's grid box `XMIN,XMAX,YMIN,YMAX` (m; default the frame -1,1,-1,1).
    #[serde(default)]
    pub grid_box: Option<Vec<f64>>,
    /// The starting design β1,…,βn (rad), one angle per cable.
    pub start: Vec<f64>,
    /// The optimiser.
    #[serde(default)]
    pub optimizer: SynthesisOptimizer,
    /// β_min (rad): minimum separation of consecutive anchors (default π/18).
    #[serde(default)]
    pub min_separation: Option<f64>,
    /// Dynamic-Q move limit ρ (rad).
    #[serde(default = "default_move_limit")]
    pub move_limit: f64,
    /// Dynamic-Q central-difference interval Γ (rad; default 0.05 for 3 cables, 0.1 otherwise).
    #[serde(default)]
    pub fd_interval: Option<f64>,
}

/// Function and gradient evaluations of a synthesis.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, JsonSchema)]
pub struct EvaluationsReport {
    /// Objective (area) evaluations.
    pub function: usize,
    /// Gradient evaluations (central differences).
    pub gradient: usize,
}

/// The JSON of `cdpr synthesize --json`.
#[derive(Clone, Debug, Serialize, JsonSchema)]
pub struct SynthesisReport {
    /// Robot name.
    pub robot: String,
    /// `dynamic-q`, `compass`, `dynamic-q-compass` or `global`.
    pub optimizer: String,
    /// Criterion labels.
    pub criteria: Vec<String>,
    /// Tension method of the tension criterion.
    pub tension_method: String,
    /// The orientation range (rad).
    pub orientations: RangeReport,
    /// M of the objective's grid.
    pub resolution: usize,
    /// The objective's grid box `XMIN,XMAX,YMIN,YMAX` (m).
    #[serde(rename = "box")]
    pub area_box: Vec<f64>,
    /// β_min (rad).
    pub min_separation: f64,
    /// The starting design (rad).
    pub start: Vec<f64>,
    /// A_d of the start (m²).
    pub start_area: f64,
    /// The start's separation violation (rad).
    pub start_constraint_violation: f64,
    /// The optimised angles (rad), shifted by whole turns so that β1 ∈ [−π, π].
    pub design: Vec<f64>,
    /// A_d of the design (m², feasible points × cell area).
    pub area: f64,
    /// The optimised frame anchors (m).
    pub anchors: Vec<[f64; 2]>,
    /// The design's separation violation (rad).
    pub constraint_violation: f64,
    /// Objective and gradient evaluations.
    pub evaluations: EvaluationsReport,
    /// Optimiser iterations.
    pub iterations: usize,
    /// `converged` or `budget`.
    pub termination: String,
    /// Grid points of the design's dextrous workspace.
    pub feasible_points: usize,
    /// (M+1)².
    pub total_points: usize,
    /// Area of one grid cell (m²).
    pub cell_area: f64,
    /// `points` (A_d = feasible points × cell area, the thesis' convention).
    pub volume_convention: String,
    /// The §6.5 check at the design.
    pub central_check: CentralCheckReport,
    /// The design as optimised, before the shift to the first turn (rad; not in JSON).
    #[serde(skip)]
    pub design_raw: Vec<f64>,
    /// The platform attachments (m; not in JSON).
    #[serde(skip)]
    pub platform: Vec<[f64; 2]>,
    /// The design's dextrous workspace on the grid (for plots; not in JSON).
    #[serde(skip)]
    pub workspace: GridWorkspace,
}

/// The checked parts of a request.
struct Problem<'a> {
    robot: &'a Robot,
    setup: CriteriaSetup,
    platform: Vec<[f64; 2]>,
    range: OrientationRange,
    grid: Grid,
    settings: SynthesisSettings,
}

impl Problem<'_> {
    /// The dextrous workspace of a design (eq. 6.28).
    fn dextrous(&self, design: &[f64]) -> Result<Dextrous, ApiError> {
        let robot = robot_from_design(design, &self.platform)?;
        dextrous(
            &self.setup,
            self.robot.description(),
            &robot,
            &Rotation3::identity(),
            &Vector3::z_axis(),
            &self.range,
            &self.grid,
            &|| {},
        )
    }
}

/// The thesis' tension method: exact for n = DOF, Algorithm 6.1 (the closed-form constrained
/// minimum ℓ1) for n = DOF + 1, the ℓ1 linear program otherwise.
pub fn synthesis_method(n: usize, dof: usize) -> Method {
    if n == dof {
        Method::Exact
    } else if n == dof + 1 {
        Method::ClosedForm
    } else {
        Method::L1
    }
}

impl SynthesisRequest {
    /// A request from `start` over `orientations` with the default criteria and settings.
    pub fn new(robot: Robot, orientations: RangeReport, start: Vec<f64>) -> Self {
        Self {
            robot,
            criteria: WorkspaceCriteria::default(),
            orientations,
            grid: None,
            grid_box: None,
            start,
            optimizer: SynthesisOptimizer::default(),
            min_separation: None,
            move_limit: default_move_limit(),
            fd_interval: None,
        }
    }

    /// Checks the request.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.prepare().map(|_| ())
    }

    /// The grid resolution M (default 100 for n = DOF, 50 otherwise).
    pub fn resolution(&self) -> usize {
        let robot = &self.robot.robot;
        self.grid.unwrap_or(if robot.cable_count() == robot.dof() {
            100
        } else {
            50
        })
    }

    /// Checks the robot, the start and the grid, in the order the command line reports them.
    fn check_robot(&self) -> Result<(), ApiError> {
        self.robot
            .require_no_passive_springs("synthesize")
            .map_err(ApiError::Invalid)?;
        let robot = &self.robot.robot;
        if robot.motion() != MotionPattern::Planar {
            return Err(ApiError::invalid(format!(
                "synthesize places anchors on the planar square frame; this robot is `{}` (need planar)",
                robot.motion().name()
            )));
        }
        let n = robot.cable_count();
        if self.start.len() != n {
            return Err(ApiError::invalid(format!(
                "--start has {} angles but the robot file has {n} cables (one angle per cable)",
                self.start.len()
            )));
        }
        Ok(())
    }

    /// The optimiser's settings.
    fn settings(&self, platform: &[[f64; 2]]) -> Result<SynthesisSettings, ApiError> {
        let n = self.robot.robot.cable_count();
        let mut settings = SynthesisSettings {
            method: self.optimizer.method(),
            ..SynthesisSettings::default()
        };
        settings.multi_start.platform = Some(platform.to_vec());
        if let Some(b) = self.min_separation {
            settings.min_separation = b;
        }
        settings.dynamic_q.move_limit = self.move_limit;
        settings.dynamic_q.fd_interval =
            self.fd_interval.unwrap_or(if n <= 3 { 0.05 } else { 0.1 });
        settings.validate()?;
        settings
            .check_feasible_separation(n)
            .map_err(|e| ApiError::invalid(format!("--min-separation: {e}")))?;
        Ok(settings)
    }

    /// Checks the request and builds its criteria, range, grid and settings.
    fn prepare(&self) -> Result<Problem<'_>, ApiError> {
        self.check_robot()?;
        let desc = self.robot.description();
        let robot = &desc.robot;
        let method = self
            .criteria
            .method
            .unwrap_or_else(|| synthesis_method(robot.cable_count(), robot.dof()));
        let setup = CriteriaSetup::new(&self.criteria, desc, method)?;
        let platform: Vec<[f64; 2]> = robot
            .cables()
            .iter()
            .map(|c| [c.platform.x, c.platform.y])
            .collect();
        let frame_box = [-1.0, 1.0, -1.0, 1.0];
        let area = region::region(
            robot,
            Some(self.grid_box.as_deref().unwrap_or(&frame_box)),
            "--grid-box",
        )?;
        let m = self.resolution();
        if !(1..=1000).contains(&m) {
            return Err(ApiError::invalid("--grid M must lie in [1, 1000]"));
        }
        let o = self.orientations;
        let range = OrientationRange {
            min: o.min,
            max: o.max,
            slices: o.slices,
        };
        let settings = self.settings(&platform)?;
        range.validate()?;
        Ok(Problem {
            robot: &self.robot,
            setup,
            platform,
            range,
            grid: Grid::new(m, area),
            settings,
        })
    }

    /// Runs the synthesis; `evaluated(k)` after the k-th area evaluation.
    pub fn run_with_progress(
        &self,
        evaluated: &dyn Fn(usize),
    ) -> Result<SynthesisReport, ApiError> {
        let problem = self.prepare()?;
        // Bad input (a non-finite angle, an invalid criterion) is reported here, not hidden as −∞.
        let start = problem.dextrous(&self.start)?;
        let mut calls = 0usize;
        let mut objective = |d: &[f64]| -> f64 {
            calls += 1;
            evaluated(calls);
            problem
                .dextrous(d)
                .map_or(f64::NEG_INFINITY, |w| w.workspace.area)
        };
        let result = synthesise(&mut objective, &self.start, &problem.settings)?;
        let best = problem.dextrous(&result.design)?;
        Ok(self.report(&problem, &start, result, best))
    }

    /// Runs the synthesis.
    pub fn run(&self) -> Result<SynthesisReport, ApiError> {
        self.run_with_progress(&|_| {})
    }

    fn report(
        &self,
        problem: &Problem<'_>,
        start: &Dextrous,
        result: SynthesisResult,
        best: Dextrous,
    ) -> SynthesisReport {
        let min_separation = problem.settings.min_separation;
        let (ws, check) = (best.workspace, best.central_check);
        SynthesisReport {
            robot: self.robot.name.clone(),
            optimizer: self.optimizer.name().into(),
            criteria: problem.setup.labels(),
            tension_method: problem.setup.method.name().into(),
            orientations: self.orientations,
            resolution: problem.grid.resolution,
            area_box: box_numbers(&problem.grid.region, 2),
            min_separation,
            start: self.start.clone(),
            start_area: start.workspace.area,
            start_constraint_violation: separation_violation(&self.start, min_separation),
            design: in_first_turn(&result.design),
            area: result.area,
            anchors: result.design.iter().map(|&b| frame_anchor(b)).collect(),
            constraint_violation: result.constraint_violation,
            evaluations: EvaluationsReport {
                function: result.evaluations.function,
                gradient: result.evaluations.gradient,
            },
            iterations: result.iterations,
            termination: match result.termination {
                Termination::Converged => "converged",
                Termination::Budget => "budget",
            }
            .into(),
            feasible_points: ws.feasible_points,
            total_points: ws.total_points,
            cell_area: ws.cell_area,
            volume_convention: VolumeConvention::Points.name().into(),
            central_check: CentralCheckReport {
                holds: check.holds,
                violations: check.violations,
                extremes_points: check.extremes_points,
            },
            design_raw: result.design,
            platform: problem.platform.clone(),
            workspace: ws,
        }
    }
}

impl SynthesisReport {
    /// The optimised robot (its frame anchors from the design).
    pub fn optimised_robot(&self) -> Result<cdpr_kinematics::Robot, ApiError> {
        Ok(robot_from_design(&self.design_raw, &self.platform)?)
    }
}

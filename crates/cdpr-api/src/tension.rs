//! # Tension distribution at a pose
//!
//! Cable tensions t with W t + w_ext = 0 and t_min ≤ t ≤ t_max by any method of `cdpr-tension`
//! (closed form, ℓ1, ℓ2, barycentre, SOTDA, the peers' methods, …). Every "feasible" answer is
//! certified by the solver (equilibrium residual and bounds); "infeasible" comes with its reason.
//!
//! ## References
//! - Picard, Caro, Plestan & Claveau 2020 (SOTDA, the feasible polygon and the displacement).
//! - Pott 2014 (improved closed form); Gouttefarde, Lamaury, Reichert & Bruckmann 2015
//!   (barycentre).

use cdpr_tension::{
    ClosestBalance, FeasiblePolygon, Infeasibility, Method, MethodOptions, PunctureInterior,
    SotdaSettings, SotdaVariant, StiffnessData, TensionOutcome, TensionProblem, TensionSolver,
    closest_balancing_tensions,
};
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::inputs::{check_method, external_wrench, method_name, pose};
use crate::{ApiError, Robot};

/// The points of the feasible polygon SOTDA evaluates ([`SotdaVariant`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum SotdaSearch {
    /// Picard, Caro, Plestan & Claveau's (2020) real-time variant: the vertices with a cable at
    /// t_max.
    #[default]
    Corners,
    /// Every vertex of the polygon.
    Vertices,
    /// A grid over the whole polygon refined by a pattern search.
    Full,
}

impl SotdaSearch {
    /// The command-line spelling (JSON `sotda_search`).
    pub fn name(self) -> &'static str {
        match self {
            SotdaSearch::Corners => "corners",
            SotdaSearch::Vertices => "vertices",
            SotdaSearch::Full => "full",
        }
    }
}

/// SOTDA settings: direction d (2 or 3 numbers; default +y), ν and the search.
pub fn sotda_settings(
    direction: Option<&[f64]>,
    nu: f64,
    search: SotdaSearch,
) -> Result<SotdaSettings, ApiError> {
    let mut s = SotdaSettings {
        nu,
        ..SotdaSettings::default()
    };
    if let Some(d) = direction {
        s.direction = match d.len() {
            2 => Vector3::new(d[0], d[1], 0.0),
            3 => Vector3::new(d[0], d[1], d[2]),
            k => {
                return Err(ApiError::invalid(format!(
                    "--direction needs 2 or 3 numbers, got {k}"
                )));
            }
        };
    }
    s.variant = match search {
        SotdaSearch::Corners => SotdaVariant::Corners,
        SotdaSearch::Vertices => SotdaVariant::Vertices,
        SotdaSearch::Full => SotdaVariant::Full,
    };
    s.validate()?;
    Ok(s)
}

/// The options of the peers' methods (issue 26); each belongs to one method and is refused with
/// another.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PeerOptions {
    /// puncture: the interior point aimed at, `icf` (default) or `cf`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interior: Option<String>,
    /// dykstra: plain (von Neumann) alternating projections.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub alternating: bool,
    /// p-norm: the exponent p ≥ 2 (default 4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub p: Option<f64>,
    /// optimally-safe: the weight α > 0 of the upper margin (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alpha: Option<f64>,
}

impl PeerOptions {
    /// The [`MethodOptions`] for `method`; an option of another method is refused.
    pub fn for_method(&self, method: Method) -> Result<MethodOptions, ApiError> {
        let given = [
            ("interior", self.interior.is_some()),
            ("alternating", self.alternating),
            ("p", self.p.is_some()),
            ("alpha", self.alpha.is_some()),
        ];
        for (name, set) in given {
            if set && !method.takes_option(name) {
                return Err(ApiError::invalid(format!(
                    "--{name} is an option of another method, not of {method} (--interior: \
                     puncture, --alternating: dykstra, --p: p-norm, --alpha: optimally-safe)"
                )));
            }
        }
        let mut o = MethodOptions {
            alternating: self.alternating,
            ..MethodOptions::default()
        };
        if let Some(i) = &self.interior {
            o.interior = i.parse::<PunctureInterior>()?;
        }
        if let Some(p) = self.p {
            o.p = p;
        }
        if let Some(a) = self.alpha {
            o.alpha = a;
        }
        o.validate()?;
        Ok(o)
    }
}

/// The options of a tension method where a request solves many poses (a path, a timed
/// trajectory): SOTDA's direction, ν and search, and the peers' options. Each belongs to its
/// method and is refused with another.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MethodSettings {
    /// SOTDA: direction d of the displacement to minimise (2 or 3 numbers; default +y).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<Vec<f64>>,
    /// SOTDA: ν ∈ [0, 1] between the barycentre (0) and the stiffness-oriented optimum (1);
    /// default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nu: Option<f64>,
    /// SOTDA: which points of the feasible polygon are evaluated.
    #[serde(default)]
    pub sotda_search: SotdaSearch,
    /// Options of the peers' methods.
    #[serde(default, flatten)]
    pub peer: PeerOptions,
}

impl MethodSettings {
    /// SOTDA's ν (default 1) when the method is SOTDA, else `None`.
    pub fn nu_of(&self, method: Method) -> Option<f64> {
        (method == Method::Sotda).then_some(self.nu.unwrap_or(1.0))
    }

    /// The solver of `method` with these settings, for `robot`: the method applies (its
    /// redundancy), SOTDA's options are refused with another method, SOTDA needs
    /// `axial_stiffness`.
    pub fn solver(
        &self,
        robot: &cdpr_io::RobotDescription,
        method: Method,
    ) -> Result<TensionSolver, ApiError> {
        if let Some(nu) = self.nu
            && !(0.0..=1.0).contains(&nu)
        {
            return Err(ApiError::invalid(format!(
                "--nu must lie in [0, 1], got {nu}"
            )));
        }
        refuse_sotda_options(method, self.nu.is_some(), self.direction.is_some(), false)?;
        let options = self.peer.for_method(method)?;
        if method != Method::Sotda {
            return Ok(TensionSolver::new(method).with_options(options)?);
        }
        if robot.axial_stiffness.is_none() {
            return Err(ApiError::invalid(
                "sotda needs `axial_stiffness` (E·S, N) on every cable of the robot file",
            ));
        }
        let s = sotda_settings(
            self.direction.as_deref(),
            self.nu.unwrap_or(1.0),
            self.sotda_search,
        )?;
        Ok(TensionSolver::sotda(s))
    }
}

/// `nu`, `direction` (and the command line's `--full`) belong to SOTDA: with another method
/// they would be ignored, so they are refused, naming the method.
pub fn refuse_sotda_options(
    method: Method,
    nu: bool,
    direction: bool,
    full: bool,
) -> Result<(), ApiError> {
    if method == Method::Sotda {
        return Ok(());
    }
    let given: Vec<&str> = [("--nu", nu), ("--direction", direction), ("--full", full)]
        .into_iter()
        .filter_map(|(name, set)| set.then_some(name))
        .collect();
    let (verb, pronoun) = match given.len() {
        0 => return Ok(()),
        1 => ("is an option", "it"),
        _ => ("are options", "them"),
    };
    Err(ApiError::invalid(format!(
        "{} {verb} of the sotda method only, and the method is {method} (add --method \
         sotda, or leave {pronoun} out)",
        given.join(", ")
    )))
}

fn default_method() -> Method {
    Method::L2
}

fn default_nu() -> f64 {
    1.0
}

/// Cable tensions at one pose (`cdpr tension`).
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
pub struct TensionRequest {
    /// The robot.
    pub robot: Robot,
    /// Platform pose (m, rad).
    pub pose: Vec<f64>,
    /// External wrench w_e (N, N·m; DOF numbers; default zero), added to the robot file's load.
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// Tension distribution method (default `l2`).
    #[serde(default = "default_method", with = "method_name")]
    #[schemars(with = "String")]
    pub method: Method,
    /// SOTDA: direction d of the displacement to minimise (2 or 3 numbers; default +y).
    #[serde(default)]
    pub direction: Option<Vec<f64>>,
    /// SOTDA: ν ∈ [0, 1] between the barycentre (0) and the stiffness-oriented optimum (1).
    #[serde(default = "default_nu")]
    pub nu: f64,
    /// SOTDA: which points of the feasible polygon are evaluated.
    #[serde(default)]
    pub sotda_search: SotdaSearch,
    /// Options of the peers' methods.
    #[serde(default, flatten)]
    pub options: PeerOptions,
}

/// The feasible polygon of a redundancy-2 problem (barycenter, sotda), or why there is none.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum PolygonReport {
    /// The polygon.
    Polygon {
        /// Vertices in the null-space coordinates λ.
        vertices_lambda: Vec<[f64; 2]>,
        /// Vertices as tensions (N).
        vertices_tension: Vec<Vec<f64>>,
        /// The barycentre in λ.
        barycenter_lambda: [f64; 2],
        /// The barycentre as tensions (N).
        barycenter: Vec<f64>,
        /// Area in λ.
        area: f64,
    },
    /// No polygon.
    None {
        /// Why.
        none: String,
    },
}

impl PolygonReport {
    /// The feasible polygon of `problem`.
    pub fn of(problem: &TensionProblem) -> Result<Self, ApiError> {
        Ok(match FeasiblePolygon::compute(problem)? {
            Ok(p) => Self::Polygon {
                vertices_lambda: p.vertices.iter().map(|v| [v.x, v.y]).collect(),
                vertices_tension: p
                    .tension_vertices
                    .iter()
                    .map(|t| t.as_slice().to_vec())
                    .collect(),
                barycenter_lambda: [p.barycenter_lambda().x, p.barycenter_lambda().y],
                barycenter: p.barycenter().as_slice().to_vec(),
                area: p.area(),
            },
            Err(reason) => Self::None {
                none: reason.to_string(),
            },
        })
    }
}

/// SOTDA's part of a tension report.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct SotdaReport {
    /// Platform displacement along the direction (m), null when infeasible.
    pub displacement: Option<f64>,
    /// ν as requested.
    pub nu: f64,
    /// The search as requested.
    pub sotda_search: SotdaSearch,
}

/// One cable that breaks its bound in the closest balancing tensions.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct BindingCable {
    /// Cable number (from 1).
    pub cable: usize,
    /// Its tension in the closest balancing tensions (N).
    pub tension: f64,
    /// The bound it breaks (N).
    pub bound: f64,
    /// Which bound: "t_min" or "t_max".
    pub which: String,
}

/// Why the feasible set is empty: the balancing tensions closest to the bounds
/// (`cdpr_tension::binding`) and the cables that break them most there.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct BindingReport {
    /// The smallest widening of every [t_min, t_max] that balances the wrench (N).
    pub violation: f64,
    /// The cables that break a bound by that much, in cable order.
    pub cables: Vec<BindingCable>,
}

impl From<ClosestBalance> for BindingReport {
    fn from(c: ClosestBalance) -> Self {
        Self {
            violation: c.violation,
            cables: c
                .binding
                .iter()
                .map(|b| BindingCable {
                    cable: b.cable + 1,
                    tension: b.tension,
                    bound: b.bound,
                    which: if b.below() { "t_min" } else { "t_max" }.to_string(),
                })
                .collect(),
        }
    }
}

/// The JSON of `cdpr tension --json`.
#[derive(Clone, Debug, PartialEq, Serialize, JsonSchema)]
pub struct TensionReport {
    /// Robot name.
    pub robot: String,
    /// The pose (m, rad).
    pub pose: Vec<f64>,
    /// w_ext = w_e + the robot file's load (N, N·m).
    pub external_wrench: Vec<f64>,
    /// The method's name.
    pub method: String,
    /// Whether certified tensions exist.
    pub feasible: bool,
    /// The tensions (N); exact/pinv: t = −W⁺ w_ext even when it breaks a bound; else null.
    pub tensions: Option<Vec<f64>>,
    /// Equilibrium residual ‖W t + w_ext‖ of a feasible answer.
    pub residual: Option<f64>,
    /// Why it is infeasible, or null.
    pub reason: Option<String>,
    /// barycenter and sotda: the feasible polygon.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub polygon: Option<PolygonReport>,
    /// sotda: `displacement`, `nu`, `sotda_search`.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub sotda: Option<SotdaReport>,
    /// An empty feasible set: the binding cables ("cable 3 would need 157 N, below its t_min of
    /// 200 N").
    #[serde(skip_serializing_if = "Option::is_none")]
    pub binding_cables: Option<BindingReport>,
}

impl TensionRequest {
    /// A request for `method` at `pose` with every option at its default.
    pub fn new(robot: Robot, pose: Vec<f64>, method: Method) -> Self {
        Self {
            robot,
            pose,
            wrench: None,
            method,
            direction: None,
            nu: 1.0,
            sotda_search: SotdaSearch::Corners,
            options: PeerOptions::default(),
        }
    }

    /// Checks the request: the method applies to the robot, its options, the pose and wrench.
    pub fn validate(&self) -> Result<(), ApiError> {
        self.checked().map(|_| ())
    }

    fn checked(&self) -> Result<TensionSolver, ApiError> {
        if !(0.0..=1.0).contains(&self.nu) {
            return Err(ApiError::invalid(format!(
                "--nu must lie in [0, 1], got {}",
                self.nu
            )));
        }
        check_method(&self.robot, self.method)?;
        let options = self.options.for_method(self.method)?;
        let p = pose(&self.robot, &self.pose)?;
        external_wrench(&self.robot, &p, self.wrench.as_deref())?;
        if self.method == Method::Sotda {
            if self.robot.axial_stiffness.is_none() {
                return Err(ApiError::invalid(
                    "sotda needs `axial_stiffness` (E·S, N) on every cable of the robot file",
                ));
            }
            let s = sotda_settings(self.direction.as_deref(), self.nu, self.sotda_search)?;
            return Ok(TensionSolver::sotda(s));
        }
        Ok(TensionSolver::new(self.method).with_options(options)?)
    }

    /// Solves for the tensions.
    pub fn run(&self) -> Result<TensionReport, ApiError> {
        let mut solver = self.checked()?;
        let robot = &self.robot;
        let p = pose(robot, &self.pose)?;
        let w_ext = external_wrench(robot, &p, self.wrench.as_deref())?;
        let kin = robot.robot.inverse_kinematics(&p)?;
        let w = kin.wrench_matrix();
        let mut problem = TensionProblem::new(&w, &w_ext, &robot.bounds);
        if let Some(es) = &robot.axial_stiffness {
            problem.stiffness = Some(StiffnessData {
                kinematics: &kin,
                axial_stiffness: es,
            });
        }
        let outcome = solver.solve(&problem)?;
        let sotda = if self.method == Method::Sotda {
            let displacement = match (&outcome, &problem.stiffness) {
                (TensionOutcome::Feasible(s), Some(st)) => cdpr_tension::sotda_displacement(
                    st,
                    solver.sotda_settings(),
                    &w_ext,
                    s.tensions.as_slice(),
                )?,
                _ => None,
            };
            Some(SotdaReport {
                displacement,
                nu: self.nu,
                sotda_search: self.sotda_search,
            })
        } else {
            None
        };
        let polygon = match self.method {
            Method::Barycenter | Method::Sotda => Some(PolygonReport::of(&problem)?),
            _ => None,
        };
        let binding_cables = match outcome.infeasibility() {
            Some(Infeasibility::NoFeasibleTension) => {
                closest_balancing_tensions(&problem)?.map(BindingReport::from)
            }
            _ => None,
        };
        Ok(TensionReport {
            binding_cables,
            robot: robot.name.clone(),
            pose: self.pose.clone(),
            external_wrench: w_ext.as_slice().to_vec(),
            method: self.method.name().to_string(),
            feasible: outcome.is_feasible(),
            tensions: outcome.balancing_tensions().map(|t| t.as_slice().to_vec()),
            residual: match &outcome {
                TensionOutcome::Feasible(s) => Some(s.residual),
                _ => None,
            },
            reason: outcome.infeasibility().map(|r| r.to_string()),
            polygon,
            sotda,
        })
    }
}

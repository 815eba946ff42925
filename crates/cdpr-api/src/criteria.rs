//! # Workspace criteria
//!
//! The criteria a region analysis tests at every pose (thesis eqs. 6.21–6.24; wrench closure;
//! capacity margin, Guay et al. 2014; isotropic force, Krut, Company & Pierrot 2004; stiffness,
//! Picard, Caro, Plestan & Claveau 2020; cable interference; the dynamic criterion), as a request
//! names them ([`WorkspaceCriteria`]: `--criteria`, `--method`, `--wrench`, `--wrench-box`,
//! `--acceleration-box`, `--velocity`), checked once against the robot file into a
//! [`CriteriaSetup`] that builds a pose evaluator at any orientation. The one copy shared by
//! `cdpr workspace`, `orientations`, `dextrous` and `synthesize`.
//!
//! ## References
//! - Thesis eqs. 6.21–6.24 (the criteria of a constant-orientation workspace).
//! - Guay, Cardou, Cruz-Ruiz & Caro 2014 (capacity margin).
//! - Krut, Company & Pierrot 2004 (isotropic force).
//! - Picard, Caro, Plestan & Claveau 2020 (stiffness K = Kp + Ka).

use std::sync::Arc;

use cdpr_dynamics::{DynamicFeasibility, RigidBody};
use cdpr_io::RobotDescription;
use cdpr_kinematics::{CableModel, Pose, Robot, RobotCatenaries};
use cdpr_polytope::RequiredWrenchSet;
use cdpr_tension::{Method, MethodOptions};
use cdpr_workspace::{Criterion, CriterionSpec as Spec, PoseEvaluator};
use nalgebra::{DVector, Rotation3, Vector3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::ApiError;
use crate::inputs::{check_method, external_wrench, wrench};
use crate::tension::PeerOptions;

/// The criteria of a region analysis and their load, as the command line spells them.
#[derive(Clone, Debug, Default, Serialize, Deserialize, JsonSchema)]
pub struct WorkspaceCriteria {
    /// Comma list of criteria that must all hold: `tension`, `length[:L]` (m), `det[:D]`,
    /// `wrench-closure`, `capacity[:M]`, `isotropic:F` (N), `stiffness:KT,KR` or `stiffness:K`,
    /// `interference[:D]` (m), `dynamic`. Default: tension, plus length and det when the robot file
    /// gives their limits.
    #[serde(default)]
    pub criteria: Option<String>,
    /// Tension method of the `tension` criterion (default: exact when n = DOF, else l2).
    #[serde(default, with = "crate::inputs::option_method_name")]
    #[schemars(with = "Option<String>")]
    pub method: Option<Method>,
    /// External wrench w_e (N, N·m; default zero); the robot file's load is added.
    #[serde(default)]
    pub wrench: Option<Vec<f64>>,
    /// Half-widths of the required wrench box of the `capacity` criterion (N, N·m; ≥ 0).
    #[serde(default)]
    pub wrench_box: Option<Vec<f64>>,
    /// Half-widths of the acceleration box of the `dynamic` criterion (m/s², rad/s²; ≥ 0).
    #[serde(default)]
    pub acceleration_box: Option<Vec<f64>>,
    /// The twist ẋ of the `dynamic` criterion (m/s, rad/s; default 0).
    #[serde(default)]
    pub velocity: Option<Vec<f64>>,
    /// `straight` (default), `elastic` (needs `axial_stiffness`) or `catenary` (also
    /// `linear_density`): the `tension` criterion solves the equilibrium with the catenaries' end
    /// forces, bounds holding along each whole cable; `capacity` measures the sag-aware wrench set
    /// at that equilibrium.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cable_model: Option<String>,
    /// Options of the peers' methods for the `tension` criterion (`interior`, `alternating`,
    /// `p`, `alpha`), checked as `cdpr tension` checks them ([`PeerOptions::for_method`]).
    #[serde(default, flatten)]
    pub peer: PeerOptions,
}

/// Default tension method of the workspace analyses: exact when n = DOF, else constrained ℓ2.
pub fn default_method(robot: &Robot) -> Method {
    if robot.cable_count() == robot.dof() {
        Method::Exact
    } else {
        Method::L2
    }
}

/// What the `dynamic` criterion needs: the platform's body, the acceleration box, the twist.
#[derive(Debug, Clone)]
struct DynamicSetup {
    body: RigidBody,
    acceleration_box: Vec<f64>,
    velocity: Vec<f64>,
}

/// The criteria of a request, checked against its robot, ready to build an evaluator at any
/// orientation.
#[derive(Debug, Clone)]
pub struct CriteriaSetup {
    /// The criteria.
    pub specs: Vec<Spec>,
    /// Tension method of the tension criterion.
    pub method: Method,
    /// Its options (puncture's interior point, dykstra's variant, p-norm's p,
    /// optimally-safe's α).
    pub options: MethodOptions,
    /// w_e (N, N·m; the robot file's load is added per orientation).
    pub wrench: Option<Vec<f64>>,
    /// Half-widths of the capacity box.
    pub wrench_box: Option<Vec<f64>>,
    /// The cables' models, `None` for straight cables.
    pub catenaries: Option<RobotCatenaries>,
    dynamic: Option<DynamicSetup>,
}

/// The robot's cables under the cable model named `name` (`straight`, `elastic`, `catenary`):
/// `None` for straight cables; an error naming the missing robot-file key, and for the
/// catenary over pulleys ([`crate::cable_model::catenaries`]).
pub fn catenaries(
    desc: &RobotDescription,
    name: Option<&str>,
) -> Result<Option<RobotCatenaries>, ApiError> {
    let model: CableModel = name
        .unwrap_or("straight")
        .parse()
        .map_err(|e| ApiError::invalid(format!("--cable-model: {e}")))?;
    crate::cable_model::catenaries(desc, model)
}

/// The platform's rigid body from the robot file (an error if the file lacks what the motion
/// pattern needs, or if the inertia is not symmetric positive definite).
pub fn rigid_body(robot: &RobotDescription) -> Result<RigidBody, ApiError> {
    let p = &robot.platform;
    if !(p.mass.is_finite() && p.mass > 0.0) {
        return Err(ApiError::invalid(format!(
            "[platform] mass = {} kg: dynamics needs a finite positive platform mass",
            p.mass
        )));
    }
    if robot.robot.motion().has_orientation() {
        let inertia = robot.inertia.ok_or(ApiError::invalid(
            "dynamics of a planar or spatial platform needs `[platform] inertia` (kg·m², about the centre of mass)",
        ))?;
        RigidBody::new(p, inertia)
            .map_err(|e| ApiError::invalid(format!("[platform] inertia: {e}")))
    } else {
        Ok(RigidBody::point_mass(p)?)
    }
}

/// Reads the acceleration box and the twist when `dynamic` is among the criteria (errors
/// otherwise: a box without the criterion, the criterion without a box, wrong sizes).
fn dynamic_setup(
    c: &WorkspaceCriteria,
    desc: &RobotDescription,
    specs: &[Spec],
) -> Result<Option<DynamicSetup>, ApiError> {
    let dof = desc.robot.dof();
    let a = match (&c.acceleration_box, specs.contains(&Spec::Dynamic)) {
        (None, false) => return Ok(None),
        (Some(_), false) => {
            return Err(ApiError::invalid(
                "--acceleration-box needs `dynamic` in --criteria",
            ));
        }
        (None, true) => {
            return Err(ApiError::invalid(
                "--criteria dynamic needs --acceleration-box A1,…,Ad (half-widths, m/s² and rad/s²)",
            ));
        }
        (Some(a), true) => a,
    };
    if a.len() != dof {
        return Err(ApiError::invalid(format!(
            "--acceleration-box needs {dof} half-widths (one per DOF), got {}",
            a.len()
        )));
    }
    if let Some(x) = a.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
        return Err(ApiError::invalid(format!(
            "--acceleration-box: {x} must be a finite number ≥ 0"
        )));
    }
    let velocity = match &c.velocity {
        Some(v) if v.len() != dof => {
            return Err(ApiError::invalid(format!(
                "--velocity needs {dof} numbers (one per DOF), got {}",
                v.len()
            )));
        }
        Some(v) => v.clone(),
        None => vec![0.0; dof],
    };
    if let Some(x) = velocity.iter().find(|x| !x.is_finite()) {
        return Err(ApiError::invalid(format!("--velocity: {x} is not finite")));
    }
    Ok(Some(DynamicSetup {
        body: rigid_body(desc)?,
        acceleration_box: a.clone(),
        velocity,
    }))
}

impl CriteriaSetup {
    /// Checks the criteria against the robot file, with `method` for the tension criterion.
    pub fn new(
        c: &WorkspaceCriteria,
        desc: &RobotDescription,
        method: Method,
    ) -> Result<Self, ApiError> {
        check_method(desc, method)?;
        let options = c.peer.for_method(method)?;
        desc.require_no_passive_springs("the workspace")
            .map_err(ApiError::Invalid)?;
        let dof = desc.robot.dof();
        let limits = desc.limits;
        let specs = cdpr_workspace::parse_criteria(
            c.criteria.as_deref().map(|c| [c]),
            desc.robot.motion(),
            limits.min_cable_length,
            limits.min_jacobian_det,
        )
        .map_err(|e| ApiError::invalid(format!("--criteria: {e}")))?;
        let wrench_box = c.wrench_box.clone();
        if specs.iter().any(|s| matches!(s, Spec::Capacity(_))) {
            match &wrench_box {
                None => {
                    return Err(ApiError::invalid(
                        "--criteria capacity needs --wrench-box (half-widths per component)",
                    ));
                }
                Some(b) if b.len() != dof => {
                    return Err(ApiError::invalid(format!(
                        "--wrench-box needs {dof} half-widths (one per wrench component), got {}",
                        b.len()
                    )));
                }
                Some(_) => {}
            }
        }
        let stiffness_spec = |s: &Spec| matches!(s, Spec::Stiffness(_) | Spec::StiffnessFloor(..));
        let needs_stiffness = specs.iter().any(stiffness_spec)
            || (method == Method::Sotda && specs.contains(&Spec::Tension));
        if needs_stiffness && desc.axial_stiffness.is_none() {
            return Err(ApiError::invalid(
                "the stiffness criterion and the sotda method need `axial_stiffness` (E·S, N) on \
                 every cable of the robot file",
            ));
        }
        if specs.iter().any(stiffness_spec) && !specs.contains(&Spec::Tension) {
            return Err(ApiError::invalid(
                "--criteria stiffness:K needs the tension criterion too (K uses its tensions)",
            ));
        }
        let dynamic = dynamic_setup(c, desc, &specs)?;
        let catenaries = catenaries(desc, c.cable_model.as_deref())?;
        if catenaries.is_some() && dynamic.is_some() {
            return Err(ApiError::invalid(
                "the dynamic criterion has no version with elastic or sagging cables (use --cable-model straight)",
            ));
        }
        Ok(Self {
            specs,
            method,
            options,
            wrench: c.wrench.clone(),
            wrench_box,
            catenaries,
            dynamic,
        })
    }

    /// Criterion labels.
    pub fn labels(&self) -> Vec<String> {
        self.specs.iter().map(Spec::label).collect()
    }

    /// The external wrench (w_e + the robot file's load) at orientation `rotation`.
    pub fn external_wrench(
        &self,
        desc: &RobotDescription,
        rotation: &Rotation3<f64>,
    ) -> Result<DVector<f64>, ApiError> {
        external_wrench(
            desc,
            &Pose::new(Vector3::zeros(), *rotation),
            self.wrench.as_deref(),
        )
    }

    /// The `dynamic` criterion, with the constant w_e of the request.
    fn dynamic_criterion(&self, desc: &RobotDescription) -> Result<Criterion, ApiError> {
        let s = self.dynamic.as_ref().ok_or(ApiError::invalid(
            "--criteria dynamic needs --acceleration-box",
        ))?;
        let w = wrench(desc, self.wrench.as_deref())?;
        let test = DynamicFeasibility::new(
            desc.robot.motion(),
            &desc.bounds,
            s.body,
            &s.acceleration_box,
            &s.velocity,
            w.as_slice(),
        )?;
        Ok(cdpr_workspace::dynamic_criterion(test))
    }

    /// One criterion of the evaluator, with w_ext bound.
    fn criterion(
        &self,
        spec: &Spec,
        desc: &RobotDescription,
        w_ext: &DVector<f64>,
    ) -> Result<Criterion, ApiError> {
        Ok(match spec {
            Spec::Tension => Criterion::TensionFeasible {
                method: self.method,
                wrench: w_ext.clone(),
            },
            Spec::Length(l) => Criterion::MinCableLength(*l),
            Spec::Det(d) => Criterion::MinJacobianDeterminant(*d),
            Spec::WrenchClosure => Criterion::WrenchClosure,
            Spec::Capacity(m) => Criterion::CapacityMargin {
                required: RequiredWrenchSet::boxed(
                    w_ext.clone(),
                    DVector::from_column_slice(self.wrench_box.as_deref().unwrap_or_default()),
                )?,
                min_margin: *m,
            },
            Spec::Isotropic(f) => Criterion::IsotropicForceUnderLoad {
                min: *f,
                wrench: w_ext.clone(),
            },
            Spec::Stiffness(k) => Criterion::Stiffness { min_eigenvalue: *k },
            Spec::StiffnessFloor(kt, kr) => Criterion::StiffnessFloor {
                translational: *kt,
                rotational: *kr,
            },
            Spec::Interference(d) => Criterion::Interference {
                min_distance: *d,
                platform: desc.platform_shape.clone().map(Arc::new),
            },
            Spec::Dynamic => self.dynamic_criterion(desc)?,
        })
    }

    /// An evaluator for `robot` (the file's, or a synthesised one with as many cables) at the
    /// orientation `rotation` (which fixes the gravity moment of an offset centre of mass).
    pub fn evaluator(
        &self,
        desc: &RobotDescription,
        robot: Robot,
        rotation: &Rotation3<f64>,
    ) -> Result<PoseEvaluator, ApiError> {
        let w_ext = self.external_wrench(desc, rotation)?;
        let criteria = self
            .specs
            .iter()
            .map(|s| self.criterion(s, desc, &w_ext))
            .collect::<Result<Vec<_>, ApiError>>()?;
        let mut eval = PoseEvaluator::new(robot, desc.bounds.clone(), criteria)?
            .with_tension_options(self.options)?;
        if let Some(es) = &desc.axial_stiffness {
            eval = eval.with_axial_stiffness(es.clone())?;
        }
        if let Some(model) = &self.catenaries {
            eval = eval.with_cable_model(model.clone())?;
        }
        eval.validate()?;
        Ok(eval)
    }
}

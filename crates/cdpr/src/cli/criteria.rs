//! Workspace criteria from the command line (`--criteria`, `--method`, `--wrench`,
//! `--wrench-box`), shared by `workspace`, `orientations`, `dextrous` and `synthesize`: parsed once
//! against the robot file into a [`CriteriaSetup`] that builds a pose evaluator at any orientation.

use super::{CliError, Numbers, check_method, external_wrench};
use cdpr::RobotDescription;
use cdpr::kinematics::{Pose, Robot};
use cdpr::polytope::RequiredWrenchSet;
use cdpr::tension::Method;
use cdpr::workspace::{Criterion, PoseEvaluator};
use nalgebra::{DVector, Rotation3, Vector3};

/// Workspace criteria and load, shared by `workspace`, `dextrous` and `synthesize`.
#[derive(clap::Args, Clone)]
pub struct CriteriaArgs {
    /// External wrench w_e on the platform (DOF numbers; default zero), e.g. --wrench 0,-10,0 for
    /// the thesis' load L1. The platform's gravity from the robot file is added.
    #[arg(long, allow_hyphen_values = true)]
    pub wrench: Option<Numbers>,
    /// Tension distribution method of the `tension` criterion: exact (n = DOF, eq. 6.12),
    /// closed-form (Alg. 6.1, n = DOF + 1), l1 (eq. 6.19), l2 (eq. 6.17), pinv (eq. 6.14: bounds
    /// only checked, smaller workspace), linf, improved-closed-form, barycenter, sotda, …
    /// Default: exact when n = DOF, else l2 (the thesis' workspace figures); synthesize: exact,
    /// closed-form or l1 (the thesis' constrained minimum ℓ1).
    #[arg(long)]
    pub method: Option<Method>,
    /// Comma list of criteria that must all hold: tension, length[:L] (m), det[:D],
    /// wrench-closure, capacity[:M], isotropic:F (N), stiffness:KT,KR (N/m, N·m/rad) or
    /// stiffness:K, interference[:D] (m) (see `cdpr workspace --help`). Default: tension, plus
    /// length and det when the robot file gives their limits.
    #[arg(long, value_name = "LIST")]
    pub criteria: Option<String>,
    /// Half-widths of the required wrench box of the `capacity` criterion (DOF numbers ≥ 0),
    /// centred on the external wrench.
    #[arg(long, allow_hyphen_values = true)]
    pub wrench_box: Option<Numbers>,
    /// Half-widths A_i of the acceleration box of the `dynamic` criterion (DOF numbers ≥ 0,
    /// m/s² and rad/s², centred on 0): every acceleration in it must be balanced within the
    /// bounds (needs the platform's mass, and `inertia` for planar/spatial platforms).
    #[arg(long, allow_hyphen_values = true)]
    pub acceleration_box: Option<Numbers>,
    /// The twist ẋ of the `dynamic` criterion (DOF numbers, m/s and rad/s; default 0).
    #[arg(long, allow_hyphen_values = true, requires = "acceleration_box")]
    pub velocity: Option<Numbers>,
}

/// One criterion as read from the command line (the wrench is bound per orientation later).
pub use cdpr::workspace::CriterionSpec as Spec;

/// The criteria of a command, ready to build an evaluator at any orientation.
#[derive(Debug, Clone)]
pub struct CriteriaSetup {
    /// The criteria.
    pub specs: Vec<Spec>,
    /// Tension method of the tension criterion.
    pub method: Method,
    /// w_e from the command line (gravity is added per orientation).
    pub wrench: Option<Vec<f64>>,
    /// Half-widths of the capacity box.
    pub wrench_box: Option<Vec<f64>>,
    /// The `dynamic` criterion's test (bounds, body, acceleration box, twist; w_e bound per
    /// evaluator).
    pub dynamic: Option<super::dynamic_workspace::DynamicSetup>,
}

/// Default tension method of the workspace commands: exact when n = DOF, else constrained ℓ2.
pub fn default_method(robot: &Robot) -> Method {
    if robot.cable_count() == robot.dof() {
        Method::Exact
    } else {
        Method::L2
    }
}

impl CriteriaSetup {
    /// Reads the criteria options against the robot file.
    pub fn from_args(
        args: &CriteriaArgs,
        desc: &RobotDescription,
        method: Method,
    ) -> Result<Self, CliError> {
        check_method(desc, method)?;
        desc.require_no_passive_springs("the workspace")?;
        let dof = desc.robot.dof();
        let limits = desc.limits;
        let specs = cdpr::workspace::parse_criteria(
            args.criteria.as_deref().map(|c| [c]),
            desc.robot.motion(),
            limits.min_cable_length,
            limits.min_jacobian_det,
        )
        .map_err(|e| format!("--criteria: {e}"))?;
        let wrench_box = args.wrench_box.as_ref().map(|b| b.0.clone());
        if specs.iter().any(|s| matches!(s, Spec::Capacity(_))) {
            match &wrench_box {
                None => {
                    return Err(
                        "--criteria capacity needs --wrench-box (half-widths per component)".into(),
                    );
                }
                Some(b) if b.len() != dof => {
                    return Err(format!(
                        "--wrench-box needs {dof} half-widths (one per wrench component), got {}",
                        b.len()
                    )
                    .into());
                }
                Some(_) => {}
            }
        }
        let stiffness_spec = |s: &Spec| matches!(s, Spec::Stiffness(_) | Spec::StiffnessFloor(..));
        let needs_stiffness = specs.iter().any(stiffness_spec)
            || (method == Method::Sotda && specs.contains(&Spec::Tension));
        if needs_stiffness && desc.axial_stiffness.is_none() {
            return Err(
                "the stiffness criterion and the sotda method need `axial_stiffness` (E·S, N) on \
                 every cable of the robot file"
                    .into(),
            );
        }
        if specs.iter().any(stiffness_spec) && !specs.contains(&Spec::Tension) {
            return Err(
                "--criteria stiffness:K needs the tension criterion too (K uses its tensions)"
                    .into(),
            );
        }
        let dynamic = super::dynamic_workspace::setup(
            args.acceleration_box.as_ref(),
            args.velocity.as_ref(),
            desc,
            &specs,
        )?;
        Ok(Self {
            specs,
            method,
            wrench: args.wrench.as_ref().map(|w| w.0.clone()),
            wrench_box,
            dynamic,
        })
    }

    /// Criterion labels.
    pub fn labels(&self) -> Vec<String> {
        self.specs.iter().map(Spec::label).collect()
    }

    /// The external wrench (w_e + gravity) at orientation `rotation`.
    pub fn external_wrench(
        &self,
        desc: &RobotDescription,
        rotation: &Rotation3<f64>,
    ) -> Result<DVector<f64>, CliError> {
        external_wrench(
            desc,
            &Pose::new(Vector3::zeros(), *rotation),
            self.wrench.as_deref(),
        )
    }

    /// An evaluator for `robot` (the file's, or a synthesised one with as many cables) at the
    /// orientation `rotation` (which fixes the gravity moment of an offset centre of mass).
    pub fn evaluator(
        &self,
        desc: &RobotDescription,
        robot: Robot,
        rotation: &Rotation3<f64>,
    ) -> Result<PoseEvaluator, CliError> {
        let w_ext = self.external_wrench(desc, rotation)?;
        let criteria = self
            .specs
            .iter()
            .map(|s| {
                Ok(match s {
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
                            DVector::from_column_slice(
                                self.wrench_box.as_deref().unwrap_or_default(),
                            ),
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
                        platform: desc.platform_shape.clone().map(std::sync::Arc::new),
                    },
                    Spec::Dynamic => super::dynamic_workspace::criterion(
                        self.dynamic.as_ref(),
                        desc,
                        self.wrench.as_deref(),
                    )?,
                })
            })
            .collect::<Result<Vec<_>, CliError>>()?;
        let mut eval = PoseEvaluator::new(robot, desc.bounds.clone(), criteria)?;
        if let Some(es) = &desc.axial_stiffness {
            eval = eval.with_axial_stiffness(es.clone())?;
        }
        eval.validate()?;
        Ok(eval)
    }
}

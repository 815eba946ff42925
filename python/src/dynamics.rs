//! # Platform dynamics: the mass matrix and forward dynamics
//!
//! ``Robot.mass_matrix(poses)``: M(x) of the platform's equations of motion
//! M(x) ẍ + b(x, ẋ) = W t + w_e + w_g in the motion pattern's twist coordinates
//! (`cdpr_dynamics::RigidBody::mass_matrix`: M = [[m I, −m[c]×], [m[c]×, I_P]], c = R c̄,
//! I_P = R I_G Rᵀ − m[c]×[c]×, reduced to the pattern's components). ``Robot.simulate(…)``:
//! `cdpr simulate` through its request (`cdpr_api::simulate::SimulateRequest`).
//!
//! ## References
//! - Barrette & Gosselin 2005, J. Mech. Des. 127(2) (the equations of motion).

use crate::arrays::{Rows, to_numpy};
use crate::model::Robot;
use crate::requests::{api_error, api_robot, matrix};
use crate::value_error;
use cdpr_api::simulate::{IntegratorName, SimulateReport, SimulateRequest, TensionProfile};
use cdpr_kinematics::Pose;
use numpy::PyArrayDyn;
use pyo3::prelude::*;

/// Forward dynamics (``Robot.simulate``), the JSON of ``cdpr simulate --json``.
///
/// ``t`` (S,) in s; ``poses`` (S, DOF); ``velocities``, ``accelerations`` (S, DOF): the twist
/// [v (m/s); ω (rad/s)] and its rate; ``tensions`` (S, n) in N; ``steps``, ``rejected_steps``;
/// ``integrator`` (``"rk4"`` or ``"rk45"``).
#[pyclass(module = "cdpr", frozen, get_all)]
pub struct SimulationResult {
    pub t: Py<PyArrayDyn<f64>>,
    pub poses: Py<PyArrayDyn<f64>>,
    pub velocities: Py<PyArrayDyn<f64>>,
    pub accelerations: Py<PyArrayDyn<f64>>,
    pub tensions: Py<PyArrayDyn<f64>>,
    pub steps: usize,
    pub rejected_steps: usize,
    pub integrator: String,
}

#[pymethods]
impl SimulationResult {
    fn __repr__(&self) -> String {
        format!(
            "SimulationResult(integrator={:?}, steps={}, rejected_steps={})",
            self.integrator, self.steps, self.rejected_steps
        )
    }
}

/// The drive of ``simulate``: one of constant tensions, a profile, unstrained lengths.
pub struct DriveArgs {
    /// Tensions held constant (N).
    pub tensions: Option<Vec<f64>>,
    /// (times (s), tensions (N) per time).
    pub profile: Option<(Vec<f64>, Vec<Vec<f64>>)>,
    /// Commanded unstrained lengths (m) of elastic cables.
    pub unstrained_lengths: Option<Vec<f64>>,
    /// Damping (N·s/m) of elastic cables.
    pub damping: f64,
}

/// The integration and the initial state of ``simulate``.
pub struct RunArgs {
    /// Initial pose.
    pub start: Vec<f64>,
    /// Initial twist.
    pub velocity: Option<Vec<f64>>,
    /// Simulated time (s).
    pub duration: f64,
    /// Output period and RK4 step (s).
    pub dt: f64,
    /// ``rk4`` or ``rk45``.
    pub integrator: String,
    /// rk45's tolerance.
    pub tolerance: f64,
    /// External wrench.
    pub wrench: Option<Vec<f64>>,
}

/// Runs `cdpr simulate`'s request.
pub fn simulate(
    robot: &Robot,
    py: Python<'_>,
    run: RunArgs,
    drive: DriveArgs,
) -> PyResult<SimulationResult> {
    let integrator = match run.integrator.as_str() {
        "rk4" => IntegratorName::Rk4,
        "rk45" => IntegratorName::Rk45,
        other => {
            return Err(value_error(format!(
                "integrator: `{other}` is not one of rk4, rk45"
            )));
        }
    };
    let request = SimulateRequest {
        robot: api_robot(robot),
        from: run.start,
        velocity: run.velocity,
        duration: run.duration,
        dt: run.dt,
        tensions: drive.tensions,
        tension_profile: drive.profile.map(|(t, tensions)| TensionProfile {
            t,
            tensions: tensions.into_iter().map(Some).collect(),
            file: None,
        }),
        unstrained_lengths: drive.unstrained_lengths,
        damping: drive.damping,
        integrator,
        tolerance: run.tolerance,
        wrench: run.wrench,
    };
    let r = crate::parallel(py, || request.run().map_err(api_error))?;
    Ok(result(py, &r, robot.geometry().cable_count()))
}

fn result(py: Python<'_>, r: &SimulateReport, n: usize) -> SimulationResult {
    let dof = r.poses.first().map_or(0, Vec::len);
    SimulationResult {
        t: to_numpy(py, &[r.t.len()], r.t.clone()).unbind(),
        poses: matrix(py, &r.poses, dof).unbind(),
        velocities: matrix(py, &r.velocities, dof).unbind(),
        accelerations: matrix(py, &r.accelerations, dof).unbind(),
        tensions: matrix(py, &r.tensions, n).unbind(),
        steps: r.steps,
        rejected_steps: r.rejected_steps,
        integrator: r.integrator.clone(),
    }
}

/// M(x) at each pose: (DOF, DOF) for one pose, (N, DOF, DOF) for N.
pub fn mass_matrix<'py>(
    robot: &Robot,
    py: Python<'py>,
    poses: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let geo = robot.geometry();
    let (motion, dof) = (geo.motion(), geo.dof());
    let body = cdpr_api::criteria::rigid_body(&robot.desc).map_err(api_error)?;
    let rows = Rows::new(poses, dof, "poses", robot.pose_hint())?;
    let mut data = Vec::with_capacity(rows.count * dof * dof);
    for (k, q) in rows.array.data().chunks(dof).enumerate() {
        let pose = Pose::from_coordinates(motion, q)
            .map_err(|e| value_error(format!("poses[{k}]: {e}")))?;
        let m = body.mass_matrix(motion, &pose);
        data.extend((0..dof * dof).map(|i| m[(i / dof, i % dof)]));
    }
    let shape: Vec<usize> = match rows.single {
        true => vec![dof, dof],
        false => vec![rows.count, dof, dof],
    };
    Ok(to_numpy(py, &shape, data))
}

//! # Robot
//!
//! The Python `cdpr.Robot`: everything a robot file describes (geometry, tension bounds,
//! limits, platform mass, axial stiffness), loaded from a file through `cdpr-io` or built from
//! anchor arrays: its Python methods. The struct itself is in module `model` (what the analysis
//! modules read); each analysis method here calls the module named after it.

use crate::arrays::{FloatArray, shape_string, to_numpy};
use crate::model::Robot;
use crate::{count, value_error};
use cdpr_io::{Limits, RobotDescription};
use cdpr_kinematics::{Cable, MotionPattern, Robot as Geometry};
use cdpr_tension::TensionBounds;
use cdpr_wrench::{Platform, STANDARD_GRAVITY};
use nalgebra::Vector3;
use numpy::PyArrayDyn;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::sync::Arc;

/// A per-cable value: a scalar or an array of length n.
fn per_cable(obj: &Bound<'_, PyAny>, n: usize, what: &str) -> PyResult<Vec<f64>> {
    if let Ok(v) = obj.extract::<f64>() {
        return Ok(vec![v; n]);
    }
    let a = FloatArray::new(obj, what)?;
    match a.shape() {
        [m] if *m == n => Ok(a.data().into_owned()),
        s => Err(value_error(format!(
            "{what}: expected a number or an array of shape ({n},) (one per cable), got {}",
            shape_string(s)
        ))),
    }
}

/// An optional 2- or 3-vector for the robot's space.
fn space_vector(
    obj: Option<&Bound<'_, PyAny>>,
    dim: usize,
    what: &str,
) -> PyResult<Option<Vector3<f64>>> {
    let Some(obj) = obj else { return Ok(None) };
    let a = FloatArray::new(obj, what)?;
    if a.shape() != [dim] {
        return Err(value_error(format!(
            "{what}: expected shape ({dim},), got {}",
            shape_string(a.shape())
        )));
    }
    a.check_finite(what)?;
    let d = a.data();
    Ok(Some(Vector3::new(
        d[0],
        d[1],
        if dim == 3 { d[2] } else { 0.0 },
    )))
}

/// Rows of anchor coordinates, (n, dim).
fn anchors(obj: &Bound<'_, PyAny>, dim: usize, what: &str) -> PyResult<(usize, Vec<f64>)> {
    let a = FloatArray::new(obj, what)?;
    match a.shape() {
        [n, d] if *d == dim && *n > 0 => {
            a.check_finite(what)?;
            Ok((*n, a.data().into_owned()))
        }
        s => Err(value_error(format!(
            "{what}: expected shape (n, {dim}) with n ≥ 1, got {}",
            shape_string(s)
        ))),
    }
}

/// The cables of `from_anchors`: frame anchors and platform attachments (zero for point
/// robots, required otherwise), (n, dim) each.
fn geometry(
    motion: MotionPattern,
    frame: &Bound<'_, PyAny>,
    platform: Option<&Bound<'_, PyAny>>,
) -> PyResult<Geometry> {
    let dim = motion.space_dim();
    let (n, frame) = anchors(frame, dim, "frame")?;
    let platform = match platform {
        Some(p) => {
            let (m, p) = anchors(p, dim, "platform")?;
            if m != n {
                return Err(value_error(format!(
                    "platform: {m} attachments for {n} frame anchors"
                )));
            }
            p
        }
        None if motion.has_orientation() => {
            return Err(value_error(format!(
                "platform: a `{motion}` robot needs the platform attachment of every cable"
            )));
        }
        None => vec![0.0; n * dim],
    };
    let cables = (0..n)
        .map(|i| {
            let (f, p) = (
                &frame[i * dim..(i + 1) * dim],
                &platform[i * dim..(i + 1) * dim],
            );
            Cable::from_slices(motion, i, f, p)
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(value_error)?;
    Geometry::new(motion, cables).map_err(value_error)
}

/// Tension bounds of `from_anchors` (N; default 0 and infinity): a negative bound is an error,
/// as in a robot file (a cable can only pull).
fn tension_bounds(
    t_min: Option<&Bound<'_, PyAny>>,
    t_max: Option<&Bound<'_, PyAny>>,
    n: usize,
) -> PyResult<TensionBounds> {
    let t_min = t_min.map_or(Ok(vec![0.0; n]), |t| per_cable(t, n, "t_min"))?;
    let t_max = t_max.map_or(Ok(vec![f64::INFINITY; n]), |t| per_cable(t, n, "t_max"))?;
    for (what, bound) in [("t_min", &t_min), ("t_max", &t_max)] {
        if let Some((i, v)) = bound.iter().enumerate().find(|(_, v)| **v < 0.0) {
            return Err(value_error(format!(
                "{what}[{i}] = {v} N is negative: a cable can only pull ({what} ≥ 0)"
            )));
        }
    }
    TensionBounds::new(t_min, t_max).map_err(value_error)
}

/// The limits of `from_anchors`: l_min (m) and D_min, each a finite number ≥ 0.
fn limits_of(min_cable_length: Option<f64>, min_jacobian_det: Option<f64>) -> PyResult<Limits> {
    for (what, v) in [
        ("min_cable_length", min_cable_length),
        ("min_jacobian_det", min_jacobian_det),
    ] {
        if let Some(v) = v
            && !(v.is_finite() && v >= 0.0)
        {
            return Err(value_error(format!(
                "{what}: {v} must be a finite number ≥ 0"
            )));
        }
    }
    Ok(Limits {
        min_cable_length,
        min_jacobian_det,
    })
}

/// The platform of `from_anchors`: mass (kg), centre of mass (m) and gravity (m/s², default
/// −z in space, −y in the plane).
fn platform_of(
    mass: f64,
    centre_of_mass: Option<&Bound<'_, PyAny>>,
    gravity: Option<&Bound<'_, PyAny>>,
    dim: usize,
) -> PyResult<Platform> {
    if !(mass.is_finite() && mass >= 0.0) {
        return Err(value_error(format!(
            "mass: {mass} must be a finite number ≥ 0"
        )));
    }
    let mut platform = Platform {
        mass,
        ..Platform::default()
    };
    if dim == 2 {
        platform.gravity = Vector3::new(0.0, -STANDARD_GRAVITY.z.abs(), 0.0);
    }
    if let Some(c) = space_vector(centre_of_mass, dim, "centre_of_mass")? {
        platform.centre_of_mass = c;
    }
    if let Some(g) = space_vector(gravity, dim, "gravity")? {
        platform.gravity = g;
    }
    Ok(platform)
}

#[pymethods]
impl Robot {
    /// Loads a robot file in any format ``cdpr-io`` reads, told apart by the extension: cdpr
    /// TOML (``.toml``), a CASPR model (``NAME_cables.xml`` with ``NAME_bodies.xml`` beside it;
    /// ``cable_set`` picks a ``<cable_set id>``) or WireCenter (``.wcrfx``).
    ///
    /// Raises ``ValueError`` naming the file, line and key (or element) of the first problem.
    #[staticmethod]
    #[pyo3(signature = (path, cable_set=None))]
    fn load(path: std::path::PathBuf, cable_set: Option<String>) -> PyResult<Self> {
        let options = match cable_set {
            Some(id) => cdpr_io::LoadOptions::cable_set(id),
            None => cdpr_io::LoadOptions::default(),
        };
        let desc = RobotDescription::load_with(&path, &options).map_err(value_error)?;
        Ok(Self {
            desc: Arc::new(desc),
        })
    }

    /// A robot from arrays.
    ///
    /// ``motion``: ``"point2"``, ``"planar"``, ``"point3"`` or ``"spatial"``. ``frame``: anchors
    /// on the fixed frame, shape ``(n, 2)`` or ``(n, 3)`` (base coordinates, m). ``platform``:
    /// attachments in platform coordinates, same shape (omit for point robots). ``t_min``,
    /// ``t_max``: tension bounds (N), scalars or arrays of shape ``(n,)`` (default 0 and
    /// infinity). ``mass`` (kg),
    /// ``centre_of_mass`` (platform coordinates, m) and ``gravity`` (m/s², default −z in space,
    /// −y in the plane) give the gravity wrench added to every load. ``axial_stiffness``: E·S
    /// per cable (N), a scalar or ``(n,)``, for stiffness and SOTDA.
    #[staticmethod]
    #[pyo3(signature = (motion, frame, platform=None, t_min=None, t_max=None, *, mass=0.0,
        centre_of_mass=None, gravity=None, axial_stiffness=None, min_cable_length=None,
        min_jacobian_det=None, name="robot".to_string()))]
    #[allow(clippy::too_many_arguments)]
    fn from_anchors(
        motion: &str,
        frame: &Bound<'_, PyAny>,
        platform: Option<&Bound<'_, PyAny>>,
        t_min: Option<&Bound<'_, PyAny>>,
        t_max: Option<&Bound<'_, PyAny>>,
        mass: f64,
        centre_of_mass: Option<&Bound<'_, PyAny>>,
        gravity: Option<&Bound<'_, PyAny>>,
        axial_stiffness: Option<&Bound<'_, PyAny>>,
        min_cable_length: Option<f64>,
        min_jacobian_det: Option<f64>,
        name: String,
    ) -> PyResult<Self> {
        let motion: MotionPattern = motion.parse().map_err(value_error)?;
        let robot = geometry(motion, frame, platform)?;
        let n = robot.cable_count();
        let bounds = tension_bounds(t_min, t_max, n)?;
        let platform = platform_of(mass, centre_of_mass, gravity, motion.space_dim())?;
        let axial_stiffness = axial_stiffness
            .map(|es| per_cable(es, n, "axial_stiffness"))
            .transpose()?;
        if let Some(es) = &axial_stiffness
            && let Some(v) = es.iter().find(|v| !(v.is_finite() && **v > 0.0))
        {
            return Err(value_error(format!(
                "axial_stiffness: {v} must be a finite number > 0"
            )));
        }
        let warnings = robot
            .duplicate_cables()
            .into_iter()
            .map(|(i, j)| {
                format!(
                    "cables {} and {} are exact duplicates (same anchor and attachment)",
                    i + 1,
                    j + 1
                )
            })
            .collect();
        Ok(Self {
            desc: Arc::new(RobotDescription {
                name,
                robot,
                bounds,
                limits: limits_of(min_cable_length, min_jacobian_det)?,
                platform,
                axial_stiffness,
                linear_density: None,
                platform_shape: None,
                cable_names: vec![None; n],
                inertia: None,
                home_pose: None,
                winches: None,
                passive_springs: None,
                passive_spring_names: Vec::new(),
                encoders: None,
                warnings,
            }),
        })
    }

    /// Degrees of freedom (rows of the wrench matrix, length of a pose and of a wrench).
    #[getter]
    fn dof(&self) -> usize {
        self.geometry().dof()
    }

    /// Number of cables n.
    #[getter]
    fn n_cables(&self) -> usize {
        self.geometry().cable_count()
    }

    /// The motion pattern: ``"point2"``, ``"planar"``, ``"point3"`` or ``"spatial"``.
    #[getter]
    fn motion(&self) -> &'static str {
        self.motion_pattern().name()
    }

    /// The robot's name (from the file, or ``name=`` of :meth:`from_anchors`).
    #[getter]
    fn name(&self) -> &str {
        &self.desc.name
    }

    /// Frame anchors, shape (n, 2) or (n, 3) (base coordinates, m).
    #[getter]
    fn frame<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        self.cable_vectors(py, |c| c.frame)
    }

    /// Platform attachments, shape (n, 2) or (n, 3) (platform coordinates, m).
    #[getter]
    fn platform<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        self.cable_vectors(py, |c| c.platform)
    }

    /// Lower tension bounds t_min, shape (n,) (N).
    #[getter]
    fn t_min<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let v = self.desc.bounds.min().as_slice().to_vec();
        to_numpy(py, &[v.len()], v)
    }

    /// Upper tension bounds t_max, shape (n,) (N).
    #[getter]
    fn t_max<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let v = self.desc.bounds.max().as_slice().to_vec();
        to_numpy(py, &[v.len()], v)
    }

    /// Platform mass (kg).
    #[getter]
    fn mass(&self) -> f64 {
        self.desc.platform.mass
    }

    /// Gravity vector (m/s², base coordinates), shape (2,) or (3,).
    #[getter]
    fn gravity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        self.space_vector(py, self.desc.platform.gravity)
    }

    /// Centre of mass in platform coordinates (m), shape (2,) or (3,).
    #[getter]
    fn centre_of_mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        self.space_vector(py, self.desc.platform.centre_of_mass)
    }

    /// E·S per cable (N), shape (n,), or None when the robot has none.
    #[getter]
    fn axial_stiffness<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArrayDyn<f64>>> {
        self.desc
            .axial_stiffness
            .as_ref()
            .map(|v| to_numpy(py, &[v.len()], v.clone()))
    }

    /// l_min of the robot file's ``[limits]`` (m), or None.
    #[getter]
    fn min_cable_length(&self) -> Option<f64> {
        self.desc.limits.min_cable_length
    }

    /// D_min of the robot file's ``[limits]``, or None.
    #[getter]
    fn min_jacobian_det(&self) -> Option<f64> {
        self.desc.limits.min_jacobian_det
    }

    /// Non-fatal remarks about the robot (e.g. duplicate cables).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.desc.warnings.clone()
    }

    /// The gravity wrench of the platform at each pose, shape (N, DOF) or (DOF,).
    fn gravity_wrench<'py>(
        &self,
        py: Python<'py>,
        poses: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let rows =
            crate::arrays::Rows::new(poses, self.geometry().dof(), "poses", self.pose_hint())?;
        let dof = self.geometry().dof();
        let data = rows.array.data();
        let mut out = Vec::with_capacity(rows.count * dof);
        for q in data.chunks(dof) {
            let pose = cdpr_kinematics::Pose::from_coordinates(self.motion_pattern(), q)
                .map_err(value_error)?;
            out.extend_from_slice(
                self.desc
                    .platform
                    .gravity_wrench(self.motion_pattern(), &pose)
                    .as_slice(),
            );
        }
        Ok(to_numpy(
            py,
            &crate::arrays::batch_shape(rows.single, rows.count, &[dof]),
            out,
        ))
    }

    /// Inverse kinematics of one pose ``(DOF,)`` or a batch ``(N, DOF)``: cable lengths, unit
    /// vectors, attachment points and the wrench matrix W (W t + w_ext = 0).
    ///
    /// Raises ``ValueError`` for a wrong shape, a non-finite coordinate, or a pose where a
    /// cable has zero length (its direction is undefined), naming the pose.
    ///
    /// ``out``: a result of an earlier call with the same number of poses; its arrays are
    /// overwritten and it is returned (no new memory for a large batch). Its arrays must keep
    /// their shapes and must not share memory with ``poses``.
    ///
    /// ``cable_model``: ``"straight"`` (default), or ``"elastic"`` / ``"catenary"`` (needs the
    /// robot file's ``axial_stiffness`` and, for catenary, ``linear_density``) with one pose and
    /// its platform-end ``tensions`` (n,) in N: a :class:`SaggingResult` (unstrained lengths,
    /// sag, the sag-aware wrench matrix), as ``cdpr kinematics --cable-model``.
    #[pyo3(signature = (poses, *, out=None, cable_model="straight", tensions=None))]
    fn inverse_kinematics(
        &self,
        py: Python<'_>,
        poses: &Bound<'_, PyAny>,
        out: Option<Bound<'_, crate::kinematics::KinematicsResult>>,
        cable_model: &str,
        tensions: Option<Vec<f64>>,
    ) -> PyResult<Py<PyAny>> {
        if let Some(model) = crate::sagging::model_name(cable_model)? {
            let r = crate::sagging::kinematics(self, py, poses, model, tensions)?;
            return Ok(Py::new(py, r)?.into_any());
        }
        if tensions.is_some() {
            return Err(crate::value_error(
                "tensions: only with cable_model=\"elastic\" or \"catenary\"",
            ));
        }
        Ok(crate::kinematics::inverse_kinematics(self, py, poses, out)?.into_any())
    }

    /// Tension distributions at one pose or a batch.
    ///
    /// ``wrenches``: the external wrench w_e on the platform (N, N·m), shape ``(DOF,)`` for all
    /// poses or ``(N, DOF)``; default zero. The platform's gravity (robot file) is added, as the
    /// ``cdpr tension`` command does. ``method``: one of ``cdpr.METHODS`` (default ``"l2"``,
    /// the constrained minimum 2-norm, thesis eq. (6.17)). SOTDA options: ``direction``
    /// (2 or 3 numbers), ``nu`` ∈ [0, 1], ``sotda_search`` (``"corners"``, ``"vertices"``,
    /// ``"full"``). Options of single methods: ``interior`` (puncture: ``"icf"`` default or
    /// ``"cf"``), ``alternating`` (dykstra: plain alternating projections), ``p`` (p-norm,
    /// default 4), ``alpha`` (optimally-safe, default 1); given with another method they are a
    /// ``ValueError``. Infeasible poses are answers (NaN tensions and a reason), not errors.
    ///
    /// ``cable_model="elastic"`` or ``"catenary"``: the statics with sagging cables at one pose
    /// (``cdpr tension --cable-model``), a :class:`SaggingResult` (platform-end ``tensions``,
    /// unstrained lengths, frame-end tensions, sag; not with sotda).
    #[pyo3(signature = (poses, wrenches=None, method="l2", *, direction=None, nu=1.0,
        sotda_search="corners", interior=None, alternating=false, p=None, alpha=None,
        cable_model="straight"))]
    #[allow(clippy::too_many_arguments)]
    fn tensions(
        &self,
        py: Python<'_>,
        poses: &Bound<'_, PyAny>,
        wrenches: Option<&Bound<'_, PyAny>>,
        method: &str,
        direction: Option<Vec<f64>>,
        nu: f64,
        sotda_search: &str,
        interior: Option<String>,
        alternating: bool,
        p: Option<f64>,
        alpha: Option<f64>,
        cable_model: &str,
    ) -> PyResult<Py<PyAny>> {
        if let Some(model) = crate::sagging::model_name(cable_model)? {
            let m = crate::tension::parse_method(method)?;
            let r = crate::sagging::tension(self, py, poses, wrenches, m, model)?;
            return Ok(Py::new(py, r)?.into_any());
        }
        let peer = crate::tension::PeerOptions {
            interior,
            alternating,
            p,
            alpha,
        };
        let r = crate::tension::tensions(
            self,
            py,
            poses,
            wrenches,
            method,
            direction,
            nu,
            sotda_search,
            peer,
        )?;
        Ok(Py::new(py, r)?.into_any())
    }

    /// Forward kinematics: the pose whose cable lengths are ``lengths`` (m; ``(n,)`` or a batch
    /// ``(N, n)``), by Levenberg–Marquardt (Pott 2018) from ``guess`` (``(DOF,)`` for every row
    /// or ``(N, DOF)``) or, without one, from a fixed set of starts (every distinct solution in
    /// ``solutions``). A pose solves the lengths when max |l_i − L_i| ≤ ``tolerance`` (m).
    /// Unsolved lengths are answers (``status``), not errors. With more cables than DOF,
    /// ``length_sigma`` (m) is the length noise that makes a least-squares pose ``"fitted"``.
    ///
    /// ``cable_model="elastic"`` or ``"catenary"``: ``lengths`` (n,) are the *unstrained*
    /// lengths and the answer the platform's equilibrium under its weight plus ``wrench``
    /// (DOF,), the elasto-geometric forward kinematics of ``cdpr forward --unstrained-lengths``:
    /// a :class:`SaggingResult` (``pose``, ``tensions``, ``residual``, ``status``,
    /// ``slack_cables``).
    #[pyo3(signature = (lengths, guess=None, *, tolerance=1e-9, max_iterations=100, length_sigma=1e-4,
        cable_model="straight", wrench=None))]
    #[allow(clippy::too_many_arguments)]
    fn forward_kinematics(
        &self,
        py: Python<'_>,
        lengths: &Bound<'_, PyAny>,
        guess: Option<&Bound<'_, PyAny>>,
        tolerance: f64,
        max_iterations: i64,
        length_sigma: f64,
        cable_model: &str,
        wrench: Option<Vec<f64>>,
    ) -> PyResult<Py<PyAny>> {
        if let Some(model) = crate::sagging::model_name(cable_model)? {
            let r = crate::sagging::forward(self, py, lengths, guess, wrench, model)?;
            return Ok(Py::new(py, r)?.into_any());
        }
        if wrench.is_some() {
            return Err(crate::value_error(
                "wrench: only with cable_model=\"elastic\" or \"catenary\" (measured lengths are the straight cables')",
            ));
        }
        let max_iterations = count(max_iterations, "max_iterations")?;
        let r = crate::forward::forward_kinematics(
            self,
            py,
            lengths,
            guess,
            tolerance,
            max_iterations,
            length_sigma,
        )?;
        Ok(Py::new(py, r)?.into_any())
    }

    /// Capacity margin (Guay et al. 2014) of a required wrench set at one pose or a batch.
    ///
    /// The required set is centred on ``wrenches`` (``(DOF,)`` or ``(N, DOF)``, default zero)
    /// plus the platform's gravity: a point, a box (``wrench_box``: DOF half-widths) or a ball
    /// (``wrench_ball``: radius), as ``cdpr capacity`` takes them.
    #[pyo3(signature = (poses, wrenches=None, *, wrench_box=None, wrench_ball=None))]
    fn capacity_margin(
        &self,
        py: Python<'_>,
        poses: &Bound<'_, PyAny>,
        wrenches: Option<&Bound<'_, PyAny>>,
        wrench_box: Option<Vec<f64>>,
        wrench_ball: Option<f64>,
    ) -> PyResult<crate::polytope::CapacityResult> {
        crate::polytope::capacity_margin(self, py, poses, wrenches, wrench_box, wrench_ball)
    }

    /// Maximum isotropic force (Krut, Company & Pierrot 2004) at one pose or a batch: the
    /// largest force the platform resists in every direction with tensions in bounds, on top of
    /// the external wrench ``wrenches`` (default zero) plus the platform's weight, as
    /// ``cdpr isotropic`` computes it.
    #[pyo3(signature = (poses, wrenches=None))]
    fn isotropic_force(
        &self,
        py: Python<'_>,
        poses: &Bound<'_, PyAny>,
        wrenches: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<crate::polytope::IsotropicResult> {
        crate::polytope::isotropic(self, py, poses, wrenches)
    }

    /// Stiffness matrix K = Kp + Ka (Picard, Caro, Plestan & Claveau 2020, eqs. (3)–(4)) at one
    /// pose or a batch, under ``tensions`` (``(n,)`` for every pose or ``(N, n)``, N).
    /// ``axial_stiffness`` (E·S, N; scalar or ``(n,)``) overrides the robot's.
    #[pyo3(signature = (poses, tensions, axial_stiffness=None))]
    fn stiffness(
        &self,
        py: Python<'_>,
        poses: &Bound<'_, PyAny>,
        tensions: &Bound<'_, PyAny>,
        axial_stiffness: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<crate::polytope::StiffnessResult> {
        crate::polytope::stiffness(self, py, poses, tensions, axial_stiffness)
    }

    /// Constant-orientation workspace (thesis Algorithm 6.2 on a grid, or the chord method).
    ///
    /// ``resolution`` M: M intervals per side (default 50 in the plane, 20 in space);
    /// ``box``: (xmin, xmax, ymin, ymax[, zmin, zmax]), default the frame anchors' bounding
    /// box; ``orientation``: φ (planar) or (rx, ry, rz) (spatial); ``criteria``: a list (or a
    /// comma string) of ``tension``, ``length[:L]``, ``det[:D]``, ``wrench-closure``,
    /// ``capacity[:M]``, ``isotropic:F``, ``stiffness:K``, ``stiffness:KT,KR``,
    /// ``interference[:D]`` (default: tension, plus length and det
    /// when the robot has those limits); ``method``: tension method (default exact when
    /// n = DOF, else l2); ``wrench``: w_e (gravity is added); ``wrench_box``: half-widths of
    /// the capacity criterion's box; ``boundary``: ``"grid"``, ``"chord"`` (robots in the plane,
    /// chord length ``chord``) or ``"mesh"`` (robots in space: the boundary as a triangle
    /// mesh); ``volume_convention``: ``"cells"`` (default, as ``cdpr workspace``) or
    /// ``"points"`` (the thesis' feasible points × cell area). Grids run in parallel with the
    /// GIL released.
    #[pyo3(signature = (resolution=None, r#box=None, orientation=None, criteria=None, method=None,
        wrench=None, wrench_box=None, boundary="grid", chord=0.05, volume_convention="cells", *,
        interior=None, alternating=false, p=None, alpha=None))]
    #[allow(clippy::too_many_arguments)]
    fn workspace(
        &self,
        py: Python<'_>,
        resolution: Option<i64>,
        r#box: Option<Vec<f64>>,
        orientation: Option<&Bound<'_, PyAny>>,
        criteria: Option<&Bound<'_, PyAny>>,
        method: Option<&str>,
        wrench: Option<Vec<f64>>,
        wrench_box: Option<Vec<f64>>,
        boundary: &str,
        chord: f64,
        volume_convention: &str,
        interior: Option<String>,
        alternating: bool,
        p: Option<f64>,
        alpha: Option<f64>,
    ) -> PyResult<crate::workspace::WorkspaceResult> {
        let resolution = resolution.map(|m| count(m, "resolution")).transpose()?;
        let orientation = orientation
            .map(|o| match o.extract::<f64>() {
                Ok(phi) => Ok(vec![phi]),
                Err(_) => o.extract::<Vec<f64>>(),
            })
            .transpose()?;
        let criteria = criteria
            .map(|c| match c.extract::<String>() {
                Ok(s) => Ok(vec![s]),
                Err(_) => c.extract::<Vec<String>>(),
            })
            .transpose()?;
        let args = crate::workspace::WorkspaceArgs {
            resolution,
            region_box: r#box,
            orientation,
            criteria,
            method,
            wrench,
            wrench_box,
            boundary,
            chord,
            volume_convention,
            peer: crate::tension::PeerOptions {
                interior,
                alternating,
                p,
                alpha,
            },
        };
        crate::workspace::workspace(self, py, &args)
    }

    /// Tensions along a path (the ``cdpr trajectory`` command, through its request):
    /// ``waypoints`` (K ≥ 2, DOF) is a polyline sampled by ``samples`` (evenly in s; default
    /// 101) or ``step`` (largest pose distance between samples); ``wrenches``: w_e, ``(DOF,)``
    /// or one per waypoint ``(K, DOF)`` interpolated linearly (gravity is added); ``method``
    /// and the SOTDA options as in :meth:`tensions`; ``jump_ratio``: a step is a discontinuity
    /// when its jump exceeds this many median jumps.
    ///
    /// With ``time_law`` (``linear``, ``cubic``, ``quintic``, ``trapezoid``,
    /// ``parabolic-blend``) the path is timed: ``duration`` (s) or ``times`` (one per waypoint,
    /// s), sampled every ``dt`` s (default 0.01), ``max_velocity`` (m/s), ``max_acceleration``
    /// (m/s²), ``blend_time`` (s); ``dynamics=True`` balances the inertial wrench M ẍ + b too.
    /// Returns a :class:`TimedTrajectoryResult` then, else a :class:`TrajectoryResult`.
    ///
    /// ``cable_model="elastic"`` or ``"catenary"`` (untimed paths): the flex and sag
    /// compensation of ``cdpr trajectory --cable-model``, per sample the ``unstrained_lengths``
    /// (m) the winches pay out, the sagging statics' ``platform_end_tensions`` (N) and, with a
    /// winch on every cable, the ``drum_angles`` (rad) that pay them out.
    ///
    /// ``caspr_trajectory`` (a CASPR ``NAME_trajectories.xml``) instead of ``waypoints``: one of
    /// its joint-space trajectories (``trajectory_id``; default the file's only one), sampled
    /// every ``time_step`` of the file with CASPR's splines — the ``cdpr trajectory
    /// --trajectory FILE --trajectory-id ID`` command; returns a :class:`TimedTrajectoryResult`.
    #[pyo3(signature = (waypoints=None, samples=None, step=None, wrenches=None, method="l2", *,
        direction=None, nu=1.0, sotda_search="corners", jump_ratio=20.0, time_law=None,
        duration=None, dt=None, times=None, max_velocity=None, max_acceleration=None,
        blend_time=None, dynamics=false, cable_model="straight", interior=None, alternating=false,
        p=None, alpha=None, caspr_trajectory=None, trajectory_id=None))]
    #[allow(clippy::too_many_arguments)]
    fn trajectory(
        &self,
        py: Python<'_>,
        waypoints: Option<&Bound<'_, PyAny>>,
        samples: Option<i64>,
        step: Option<f64>,
        wrenches: Option<&Bound<'_, PyAny>>,
        method: &str,
        direction: Option<Vec<f64>>,
        nu: f64,
        sotda_search: &str,
        jump_ratio: f64,
        time_law: Option<&str>,
        duration: Option<f64>,
        dt: Option<f64>,
        times: Option<Vec<f64>>,
        max_velocity: Option<f64>,
        max_acceleration: Option<f64>,
        blend_time: Option<f64>,
        dynamics: bool,
        cable_model: &str,
        interior: Option<String>,
        alternating: bool,
        p: Option<f64>,
        alpha: Option<f64>,
        caspr_trajectory: Option<std::path::PathBuf>,
        trajectory_id: Option<String>,
    ) -> PyResult<Py<PyAny>> {
        use crate::trajectory::{MethodArgs, PathArgs};
        let caspr = match caspr_trajectory {
            Some(file) => Some(cdpr_api::timed::CasprTrajectorySource {
                text: std::fs::read_to_string(&file).map_err(|e| {
                    crate::value_error(format!("{}: cannot read: {e}", file.display()))
                })?,
                id: trajectory_id,
                file: Some(file.display().to_string()),
            }),
            None if trajectory_id.is_some() => {
                return Err(crate::value_error(
                    "trajectory_id needs caspr_trajectory (the CASPR trajectories file)",
                ));
            }
            None => None,
        };
        let cable_model = crate::sagging::model_name(cable_model)?.unwrap_or_default();
        let time_law = time_law
            .map(|l| l.parse().map_err(crate::value_error))
            .transpose()?;
        let timing = cdpr_api::timed::TimedSettings {
            time_law,
            duration,
            dt,
            max_velocity,
            max_acceleration,
            blend_time,
            dynamics,
        };
        let path = PathArgs {
            waypoints,
            caspr,
            wrenches,
            times,
            samples: samples.map(|k| count(k, "samples")).transpose()?,
            step,
            jump_ratio,
        };
        let method = MethodArgs {
            method: method.into(),
            direction,
            nu,
            sotda_search: sotda_search.into(),
            peer: crate::tension::PeerOptions {
                interior,
                alternating,
                p,
                alpha,
            },
        };
        crate::trajectory::trajectory(self, py, path, method, (timing, cable_model))
    }

    /// Forward dynamics (the ``cdpr simulate`` command, through its request): the motion from
    /// ``start`` (a pose) with twist ``velocity`` (default rest) over ``duration`` s, output
    /// every ``dt`` s, driven by exactly one of ``tensions`` (N, held constant),
    /// ``tension_profile`` (``(times, tensions)``: (S,) s and (S, n) N, interpolated linearly;
    /// e.g. a timed trajectory's ``t`` and ``tensions``) or ``unstrained_lengths`` (m, elastic
    /// cables with ``axial_stiffness``, ``damping`` in N·s/m); ``integrator`` ``"rk4"`` (fixed
    /// step) or ``"rk45"`` (adaptive, ``tolerance``); ``wrench``: w_e held constant.
    #[pyo3(signature = (start, duration, dt, *, velocity=None, tensions=None,
        tension_profile=None, unstrained_lengths=None, damping=0.0, integrator="rk4",
        tolerance=1e-9, wrench=None))]
    #[allow(clippy::too_many_arguments)]
    fn simulate(
        &self,
        py: Python<'_>,
        start: Vec<f64>,
        duration: f64,
        dt: f64,
        velocity: Option<Vec<f64>>,
        tensions: Option<Vec<f64>>,
        tension_profile: Option<(Vec<f64>, Vec<Vec<f64>>)>,
        unstrained_lengths: Option<Vec<f64>>,
        damping: f64,
        integrator: &str,
        tolerance: f64,
        wrench: Option<Vec<f64>>,
    ) -> PyResult<crate::dynamics::SimulationResult> {
        let run = crate::dynamics::RunArgs {
            start,
            velocity,
            duration,
            dt,
            integrator: integrator.into(),
            tolerance,
            wrench,
        };
        let drive = crate::dynamics::DriveArgs {
            tensions,
            profile: tension_profile,
            unstrained_lengths,
            damping,
        };
        crate::dynamics::simulate(self, py, run, drive)
    }

    /// The platform's mass matrix M(x) (kg, kg·m, kg·m²) in the motion pattern's twist
    /// coordinates: ``(DOF, DOF)`` for one pose, ``(N, DOF, DOF)`` for ``(N, DOF)`` poses
    /// (needs ``[platform] mass``, and ``inertia`` for planar and spatial platforms).
    fn mass_matrix<'py>(
        &self,
        py: Python<'py>,
        poses: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArrayDyn<f64>>> {
        crate::dynamics::mass_matrix(self, py, poses)
    }

    fn __repr__(&self) -> String {
        format!(
            "Robot(name={:?}, motion={:?}, n_cables={}, dof={})",
            self.desc.name,
            self.motion(),
            self.n_cables(),
            self.dof()
        )
    }

    /// The robot as cdpr TOML (the robot-file format; ``header`` becomes a comment).
    #[pyo3(signature = (header=""))]
    fn to_toml(&self, header: &str) -> String {
        self.desc.to_toml(header)
    }

    /// A robot from cdpr TOML text (``file`` names it in error messages).
    #[staticmethod]
    #[pyo3(signature = (text, file="<string>"))]
    fn from_toml(text: &str, file: &str) -> PyResult<Self> {
        let desc = RobotDescription::parse(text, file).map_err(value_error)?;
        Ok(Self {
            desc: Arc::new(desc),
        })
    }

    /// Pickling (for process pools and Dask workers): the robot travels as its TOML text.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let rebuild = py.get_type::<Robot>().getattr("from_toml")?;
        let args = (slf.get().to_toml(""), "<pickle>").into_pyobject(py)?;
        PyTuple::new(py, [rebuild.into_any(), args.into_any()])
    }
}

impl Robot {
    fn space_vector<'py>(&self, py: Python<'py>, v: Vector3<f64>) -> Bound<'py, PyArrayDyn<f64>> {
        let dim = self.motion_pattern().space_dim();
        to_numpy(py, &[dim], v.as_slice()[..dim].to_vec())
    }

    fn cable_vectors<'py>(
        &self,
        py: Python<'py>,
        f: impl Fn(&Cable) -> Vector3<f64>,
    ) -> Bound<'py, PyArrayDyn<f64>> {
        let dim = self.motion_pattern().space_dim();
        let cables = self.geometry().cables();
        let data = cables
            .iter()
            .flat_map(|c| f(c).as_slice()[..dim].to_vec())
            .collect();
        to_numpy(py, &[cables.len(), dim], data)
    }
}

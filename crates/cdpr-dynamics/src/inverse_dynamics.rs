//! # Inverse dynamics along a timed trajectory
//!
//! At every sample of a [`Trajectory`](crate::Trajectory) the tensions t that move the platform
//! as planned: W t + w_ext + w_g = M ẍ + b, i.e. the static problem W t + w = 0 of
//! `cdpr-tension` with w = w_ext + w_g − (M ẍ + b), solved by any method and certified as
//! there (equilibrium and bounds). Infeasible samples are answers with their reason.
//!
//! Along with the tensions: the inertial wrench M ẍ + b, the cable lengths l, their rates
//! l̇ = −Wᵀ ẋ and accelerations l̈ = −Wᵀ ẍ − Ẇᵀ ẋ. Without pulleys l̈ is exact:
//! l̈_i = (‖v_a‖² − (u_i · v_a)²) / l_i − u_i · a_a, with v_a = v + ω × a_i and
//! a_a = v̇ + ω̇ × a_i + ω × (ω × a_i) the velocity and acceleration of the attachment; with
//! swivel pulleys the Ẇᵀ ẋ term is the central difference of Wᵀ ẋ along ẋ (error O(h²)).
//!
//! ## References
//! - Gagliardini, Gouttefarde & Caro 2016 (ARK), eq. (4): the wrench to balance along a motion.
//! - Lau et al. 2016 (CASPR), the inverse dynamics solver: the same per-sample problem.

use crate::rigid_body::pattern_components;
use crate::{DynamicsError, RigidBody, TimedSample};
use cdpr_kinematics::{MotionPattern, Pose, PoseKinematics, Robot};
use cdpr_tension::{StiffnessData, TensionBounds, TensionProblem, TensionSolver};
use nalgebra::{DMatrix, DVector, Rotation3, Vector6};

/// What a robot needs along a timed trajectory, one entry per sample. Per-sample vectors are
/// stored flat: entry k of a per-cable quantity is `[k * n .. (k + 1) * n]`.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsProfile {
    /// Number of cables n.
    pub cables: usize,
    /// DOF.
    pub dof: usize,
    /// t (s).
    pub t: Vec<f64>,
    /// Tensions (N) per sample, `None` where infeasible.
    pub tensions: Vec<Option<DVector<f64>>>,
    /// Why a sample is infeasible (`None` where feasible).
    pub reasons: Vec<Option<String>>,
    /// M ẍ + b (N, N·m), DOF per sample.
    pub inertial_wrench: Vec<f64>,
    /// l (m), n per sample (NaN where the kinematics fail).
    pub cable_lengths: Vec<f64>,
    /// l̇ = −Wᵀ ẋ (m/s), n per sample.
    pub cable_speeds: Vec<f64>,
    /// l̈ (m/s²), n per sample.
    pub cable_accelerations: Vec<f64>,
}

impl DynamicsProfile {
    /// Number of feasible samples.
    pub fn feasible_count(&self) -> usize {
        self.tensions.iter().filter(|t| t.is_some()).count()
    }

    /// Rows of a flat per-sample quantity.
    pub fn rows<'a>(&self, flat: &'a [f64], width: usize) -> Vec<&'a [f64]> {
        flat.chunks(width.max(1)).collect()
    }
}

/// The inverse dynamics of `samples`: tensions by `solver` within `bounds` balancing
/// `load(k, sample)` (w_ext + w_g and any springs, N and N·m, DOF numbers) minus the inertial
/// wrench of `body` (with `None` the inertial wrench is zero: the quasi-static tensions along
/// the timed path). `axial_stiffness` is needed by SOTDA only.
pub fn inverse_dynamics(
    robot: &Robot,
    body: Option<&RigidBody>,
    samples: &[TimedSample],
    bounds: &TensionBounds,
    solver: &mut TensionSolver,
    axial_stiffness: Option<&[f64]>,
    mut load: impl FnMut(usize, &TimedSample) -> DVector<f64>,
) -> Result<DynamicsProfile, DynamicsError> {
    let (n, motion) = (robot.cable_count(), robot.motion());
    let dof = motion.dof();
    let count = samples.len();
    let mut out = DynamicsProfile {
        cables: n,
        dof,
        t: Vec::with_capacity(count),
        tensions: Vec::with_capacity(count),
        reasons: Vec::with_capacity(count),
        inertial_wrench: vec![0.0; count * dof],
        cable_lengths: vec![f64::NAN; count * n],
        cable_speeds: vec![f64::NAN; count * n],
        cable_accelerations: vec![f64::NAN; count * n],
    };
    let mut kin = PoseKinematics::for_robot(robot);
    let mut scratch = PoseKinematics::for_robot(robot);
    let mut w = DMatrix::zeros(dof, n);
    let mut wrench = DVector::zeros(dof);
    for (k, sample) in samples.iter().enumerate() {
        out.t.push(sample.t);
        let inertial = &mut out.inertial_wrench[k * dof..(k + 1) * dof];
        let vel = pattern_slice(motion, &sample.twist);
        let acc = pattern_slice(motion, &sample.twist_rate);
        if let Some(body) = body {
            body.inertial_wrench(motion, &sample.pose, &vel[..dof], &acc[..dof], inertial);
        }
        if let Err(e) = robot.update_kinematics(&sample.pose, &mut kin) {
            out.tensions.push(None);
            out.reasons.push(Some(e.to_string()));
            continue;
        }
        let rows = k * n..(k + 1) * n;
        cable_rates(
            robot,
            &kin,
            &mut scratch,
            sample,
            &mut out.cable_lengths[rows.clone()],
            &mut out.cable_speeds[rows.clone()],
            &mut out.cable_accelerations[rows],
        );
        kin.write_wrench_matrix(&mut w);
        let l = load(k, sample);
        if l.len() != dof {
            return Err(DynamicsError::DimensionMismatch {
                what: "load wrench",
                expected: dof,
                found: l.len(),
            });
        }
        for i in 0..dof {
            wrench[i] = l[i] - inertial[i];
        }
        let mut problem = TensionProblem::new(&w, &wrench, bounds);
        if let Some(es) = axial_stiffness {
            problem.stiffness = Some(StiffnessData {
                kinematics: &kin,
                axial_stiffness: es,
            });
        }
        match solver.solve(&problem)? {
            cdpr_tension::TensionOutcome::Feasible(s) => {
                out.tensions.push(Some(s.tensions));
                out.reasons.push(None);
            }
            cdpr_tension::TensionOutcome::Infeasible(r) => {
                out.tensions.push(None);
                out.reasons.push(Some(r.to_string()));
            }
        }
    }
    Ok(out)
}

fn pattern_slice(motion: MotionPattern, v: &Vector6<f64>) -> [f64; 6] {
    let mut o = [0.0; 6];
    for (x, &i) in o.iter_mut().zip(pattern_components(motion)) {
        *x = v[i];
    }
    o
}

/// l, l̇ = −Wᵀ ẋ and l̈ of every cable at a sample (the module's formulas).
pub fn cable_rates(
    robot: &Robot,
    kin: &PoseKinematics,
    scratch: &mut PoseKinematics,
    sample: &TimedSample,
    lengths: &mut [f64],
    speeds: &mut [f64],
    accelerations: &mut [f64],
) {
    let v = sample.twist.fixed_rows::<3>(0).into_owned();
    let w = sample.twist.fixed_rows::<3>(3).into_owned();
    let vd = sample.twist_rate.fixed_rows::<3>(0).into_owned();
    let wd = sample.twist_rate.fixed_rows::<3>(3).into_owned();
    for (i, c) in kin.cables().iter().enumerate() {
        let va = v + w.cross(&c.attachment);
        let aa = vd + wd.cross(&c.attachment) + w.cross(&w.cross(&c.attachment));
        lengths[i] = c.length;
        speeds[i] = -c.unit.dot(&va);
        let along = c.unit.dot(&va);
        accelerations[i] = (va.norm_squared() - along * along) / c.length - c.unit.dot(&aa);
    }
    if robot.has_pulleys() {
        // l̈ = −Wᵀ ẍ − d/dh [W(x + h ẋ)ᵀ ẋ]: the second term by central differences.
        let speed = v.norm() + w.norm() * robot.length_scale().max(1e-3);
        if speed == 0.0 {
            for (i, c) in kin.cables().iter().enumerate() {
                accelerations[i] = -c.unit.dot(&(vd + wd.cross(&c.attachment)));
            }
            return;
        }
        let h = 1e-5 * robot.length_scale().max(1e-3) / speed;
        let along = |s: f64, scratch: &mut PoseKinematics| -> Option<Vec<f64>> {
            let pose = Pose::new(
                sample.pose.position + s * v,
                Rotation3::new(s * w) * sample.pose.rotation,
            );
            robot.update_kinematics(&pose, scratch).ok()?;
            Some(
                scratch
                    .cables()
                    .iter()
                    .map(|c| c.unit.dot(&(v + w.cross(&c.attachment))))
                    .collect(),
            )
        };
        if let (Some(p), Some(m)) = (along(h, scratch), along(-h, scratch)) {
            for (i, c) in kin.cables().iter().enumerate() {
                let dwx = (p[i] - m[i]) / (2.0 * h);
                accelerations[i] = -c.unit.dot(&(vd + wd.cross(&c.attachment))) - dwx;
            }
        }
    }
}

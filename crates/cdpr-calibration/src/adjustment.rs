//! # Levenberg–Marquardt adjustment of parameters (and poses) to cable readings
//!
//! Minimises ½ Σ_k Σ_i r_ki² over the free parameters θ ([`crate::gauge`]) and, for
//! self-calibration, the k poses x_k. The Jacobian has one block A_k = ∂r_k/∂x_k per sample
//! (n × d) and a parameter block B_k = ∂r_k/∂θ, so JᵀJ has the arrow shape of bundle
//! adjustment:
//!
//! ```text
//!   [ U   W ]   U = diag(U_k),  U_k = A_kᵀ A_k,  W_k = A_kᵀ B_k,  V = Σ_k B_kᵀ B_k
//!   [ Wᵀ  V ]
//! ```
//!
//! Each damped step (JᵀJ + μ diag JᵀJ) δ = −Jᵀr eliminates the poses first (the Schur
//! complement S = V − Σ W_kᵀ U_k⁻¹ W_k, a P × P system), then back-substitutes each pose:
//! O(k (d³ + d² P + d P²) + P³) per iteration instead of O((k d + P)³). μ follows Nielsen's
//! rule, as in the forward kinematics. With known poses U is empty and S = V: the normal
//! matrix is block-diagonal by cable, so the joint solve is the per-cable least squares.
//!
//! ## References
//! - Levenberg 1944, Marquardt 1963; Nielsen 1999 (damping update).
//! - Triggs, McLauchlan, Hartley & Fitzgibbon 2000, *Bundle adjustment — a modern synthesis*
//!   (the Schur complement, §6.1).

use crate::covariance::{NormalAnalysis, analyse_normal_matrix};
use crate::gauge::ParameterSpace;
use crate::model::{Reading, displaced, pose_gradient, reading};
use crate::{Parameters, Readings};
use cdpr_kinematics::nalgebra::{DMatrix, DVector, Rotation3};
use cdpr_kinematics::{Cable, KinematicsError, MotionPattern, Pose, PoseKinematics, Pulley, Robot};
use std::ops::Range;

/// Largest number of Levenberg–Marquardt iterations (accepted or rejected steps). Long curved
/// valleys of ill-conditioned problems (a flat frame seen from low poses) take hundreds.
const MAX_ITERATIONS: usize = 2000;

/// The problem: readings ρ (k × n), what is free, how readings relate to lengths.
pub(crate) struct Problem<'a> {
    pub motion: MotionPattern,
    pub space: &'a ParameterSpace,
    pub readings: &'a Readings,
    pub rho: &'a [f64],
    pub n: usize,
    /// Whether the poses are unknowns.
    pub estimate_poses: bool,
    /// The swivel pulleys of the cables (held at their nominal radius and orientation), when
    /// the robot has any: the lengths are then those of the pulley model.
    pub pulleys: Option<&'a [Option<Pulley>]>,
}

/// Where the lengths of one set of parameters come from.
enum Lengths<'p> {
    /// Straight cables, eq. (6.4) in closed form ([`reading`]).
    Straight(&'p Parameters),
    /// Swivel pulleys (Pott 2018): the inverse kinematics of `cdpr-kinematics` on the robot with
    /// these anchors and attachments; the free-segment direction takes the place of the cable
    /// direction in every derivative (the arc's rate cancels: module `cdpr_kinematics::pulley`).
    Pulleys(Box<PulleyLengths<'p>>),
}

/// The pulley robot of one set of parameters and its kinematics buffers.
struct PulleyLengths<'p> {
    params: &'p Parameters,
    robot: Robot,
    kin: PoseKinematics,
    /// The lengths and directions at the reference pose (relative readings).
    reference: Option<(PoseKinematics, Rotation3<f64>)>,
}

/// The outcome of the adjustment.
pub(crate) struct Fit {
    pub parameters: Parameters,
    pub poses: Vec<Pose>,
    pub iterations: usize,
    pub converged: bool,
    /// Σ r² at the solution (m²).
    pub squared: f64,
    /// max |r| (m).
    pub max_residual: f64,
    /// Of the Schur complement at the solution.
    pub analysis: NormalAnalysis,
    /// Samples whose pose block U_k is singular at the solution.
    pub singular_poses: usize,
}

/// The normal equations at one point.
struct Normal {
    u: Vec<DMatrix<f64>>,
    w: Vec<DMatrix<f64>>,
    gx: Vec<DVector<f64>>,
    v: DMatrix<f64>,
    gt: DVector<f64>,
}

impl Problem<'_> {
    fn dof(&self) -> usize {
        if self.estimate_poses {
            self.motion.dof()
        } else {
            0
        }
    }

    /// The parameter indices of each cable (parameters are ordered by cable).
    fn ranges(&self) -> Vec<Range<usize>> {
        let mut out = vec![0..0; self.n];
        for (j, p) in self.space.parameters.iter().enumerate() {
            let c = p.cable();
            if out[c].is_empty() {
                out[c] = j..j + 1;
            } else {
                out[c].end = j + 1;
            }
        }
        out
    }

    /// The length model of `params` (for pulleys: their robot, built once per evaluation).
    fn lengths<'p>(&self, params: &'p Parameters) -> Result<Lengths<'p>, KinematicsError> {
        let Some(pulleys) = self.pulleys else {
            return Ok(Lengths::Straight(params));
        };
        let cables = params
            .frame
            .iter()
            .zip(&params.platform)
            .zip(pulleys)
            .map(|((c, a), p)| Cable {
                frame: *c,
                platform: *a,
                pulley: *p,
            })
            .collect();
        let robot = Robot::new(self.motion, cables)?;
        let reference = match self.readings {
            Readings::Absolute => None,
            Readings::Relative { reference } => {
                Some((robot.inverse_kinematics(reference)?, reference.rotation))
            }
        };
        Ok(Lengths::Pulleys(Box::new(PulleyLengths {
            params,
            kin: PoseKinematics::for_robot(&robot),
            robot,
            reference,
        })))
    }

    /// Calls `f(i, reading)` for the n readings of sample `s` at `pose`, in cable order (an
    /// error: a pulley cable degenerate at this pose). No allocation.
    #[inline(always)]
    fn sample(
        &self,
        lengths: &mut Lengths<'_>,
        pose: &Pose,
        s: usize,
        mut f: impl FnMut(usize, Reading),
    ) -> Result<(), KinematicsError> {
        let rho = &self.rho[s * self.n..(s + 1) * self.n];
        match lengths {
            Lengths::Straight(params) => {
                for (i, &r) in rho.iter().enumerate() {
                    f(i, reading(params, self.readings, i, pose, r));
                }
            }
            Lengths::Pulleys(pulleys) => {
                let PulleyLengths {
                    params,
                    robot,
                    kin,
                    reference,
                } = &mut **pulleys;
                robot.update_kinematics(pose, kin)?;
                for (i, state) in kin.cables().iter().enumerate() {
                    let mut model = params.gains[i] * rho[i] + params.offsets[i];
                    if let Some((k, _)) = reference {
                        model += k.cables()[i].length;
                    }
                    f(
                        i,
                        Reading {
                            residual: state.length - model,
                            rho: rho[i],
                            unit: state.unit,
                            attachment: state.attachment,
                            rotation: pose.rotation,
                            reference: reference.as_ref().map(|(k, r)| (k.cables()[i].unit, *r)),
                        },
                    );
                }
            }
        }
        Ok(())
    }

    /// (Σ r², max |r|); infinite when a pulley cable is degenerate at a pose.
    fn cost(&self, params: &Parameters, poses: &[Pose]) -> (f64, f64) {
        let Ok(mut lengths) = self.lengths(params) else {
            return (f64::INFINITY, f64::INFINITY);
        };
        let mut sum = 0.0;
        let mut max = 0.0f64;
        for (s, pose) in poses.iter().enumerate() {
            let evaluated = self.sample(&mut lengths, pose, s, |_, rd| {
                let r = rd.residual;
                sum += r * r;
                max = max.max(r.abs());
            });
            if evaluated.is_err() {
                return (f64::INFINITY, f64::INFINITY);
            }
        }
        (sum, max)
    }

    fn normal(
        &self,
        params: &Parameters,
        poses: &[Pose],
        ranges: &[Range<usize>],
    ) -> Result<Normal, KinematicsError> {
        let d = self.dof();
        let p = self.space.parameters.len();
        let mut v = DMatrix::zeros(p, p);
        let mut gt = DVector::zeros(p);
        let (mut u, mut w, mut gx) = (Vec::new(), Vec::new(), Vec::new());
        let mut grad = [0.0; 16];
        let mut lengths = self.lengths(params)?;
        for (s, pose) in poses.iter().enumerate() {
            let mut uk = DMatrix::zeros(d, d);
            let mut wk = DMatrix::zeros(d, p);
            let mut gk = DVector::zeros(d);
            self.sample(&mut lengths, pose, s, |i, rd| {
                let range = &ranges[i];
                let r = rd.residual;
                let a = pose_gradient(self.motion, &rd.unit, &rd.attachment);
                let m = range.len();
                for (slot, j) in grad.iter_mut().zip(range.clone()) {
                    *slot = rd.derivative(&self.space.parameters[j]);
                }
                for (x, j) in range.clone().enumerate() {
                    gt[j] += grad[x] * r;
                    for (y, l) in range.clone().enumerate() {
                        v[(j, l)] += grad[x] * grad[y];
                    }
                }
                for a_row in 0..d {
                    gk[a_row] += a[a_row] * r;
                    for b in 0..d {
                        uk[(a_row, b)] += a[a_row] * a[b];
                    }
                    for x in 0..m {
                        wk[(a_row, range.start + x)] += a[a_row] * grad[x];
                    }
                }
            })?;
            u.push(uk);
            w.push(wk);
            gx.push(gk);
        }
        Ok(Normal { u, w, gx, v, gt })
    }

    /// The damped step (δθ, δx_k), or `None` when a damped block is not positive definite.
    fn step(&self, nm: &Normal, mu: f64) -> Option<(DVector<f64>, Vec<DVector<f64>>)> {
        let damp = |m: &DMatrix<f64>| {
            let mut out = m.clone();
            let max = m.diagonal().max().max(0.0);
            for i in 0..m.nrows() {
                out[(i, i)] += mu * m[(i, i)].max(1e-12 * max);
            }
            out
        };
        let mut s = damp(&nm.v);
        let mut rhs = -&nm.gt;
        let mut inv_u = Vec::with_capacity(nm.u.len());
        for ((uk, wk), gk) in nm.u.iter().zip(&nm.w).zip(&nm.gx) {
            if uk.nrows() == 0 {
                inv_u.push(None);
                continue;
            }
            let chol = damp(uk).cholesky()?;
            let uw = chol.solve(wk); // U_k⁻¹ W_k
            let ug = chol.solve(gk); // U_k⁻¹ g_k
            s -= wk.transpose() * &uw;
            rhs += wk.transpose() * &ug;
            inv_u.push(Some(chol));
        }
        let dt = s.cholesky()?.solve(&rhs);
        let mut dx = Vec::with_capacity(nm.u.len());
        for ((chol, wk), gk) in inv_u.iter().zip(&nm.w).zip(&nm.gx) {
            dx.push(match chol {
                Some(c) => c.solve(&(-gk - wk * &dt)),
                None => DVector::zeros(0),
            });
        }
        if dt.iter().chain(dx.iter().flatten()).all(|v| v.is_finite()) {
            Some((dt, dx))
        } else {
            None
        }
    }

    /// The Schur complement at μ = 0 and the count of singular pose blocks.
    fn schur(&self, nm: &Normal) -> (DMatrix<f64>, usize) {
        let mut s = nm.v.clone();
        let mut singular = 0;
        for (uk, wk) in nm.u.iter().zip(&nm.w) {
            if uk.nrows() == 0 {
                continue;
            }
            let scaled_ok = analyse_normal_matrix(uk).rank_deficiency == 0;
            match uk.clone().cholesky() {
                Some(c) if scaled_ok => s -= wk.transpose() * c.solve(wk),
                _ => singular += 1,
            }
        }
        (s, singular)
    }

    /// Levenberg–Marquardt from (params, poses); an error when a pulley cable is degenerate at
    /// a starting pose.
    pub fn solve(
        &self,
        mut params: Parameters,
        mut poses: Vec<Pose>,
        length_scale: f64,
    ) -> Result<Fit, KinematicsError> {
        let ranges = self.ranges();
        let (mut cost, _) = self.cost(&params, &poses);
        let mut mu = 0.0;
        let mut nu = 2.0;
        let mut iterations = 0;
        let mut converged = false;
        let step_tolerance = 1e-14 * length_scale;
        while iterations < MAX_ITERATIONS {
            iterations += 1;
            // Every accepted point has a finite cost: its lengths evaluate.
            let nm = self.normal(&params, &poses, &ranges)?;
            let gradient = nm
                .gt
                .iter()
                .chain(nm.gx.iter().flatten())
                .fold(0.0f64, |m, v| m.max(v.abs()));
            if gradient == 0.0 || cost == 0.0 {
                converged = true;
                break;
            }
            let Some((dt, dx)) = self.step(&nm, mu) else {
                mu = if mu == 0.0 { 1e-6 } else { mu * nu };
                nu *= 2.0;
                if mu > 1e12 {
                    break;
                }
                continue;
            };
            let size = dt
                .iter()
                .chain(dx.iter().flatten())
                .fold(0.0f64, |m, v| m.max(v.abs()));
            let trial_params = self.space.apply(&params, dt.as_slice());
            let trial_poses: Vec<Pose> = if self.estimate_poses {
                poses
                    .iter()
                    .zip(&dx)
                    .map(|(x, d)| displaced(self.motion, x, d.as_slice()))
                    .collect()
            } else {
                poses.clone()
            };
            let (trial_cost, _) = self.cost(&trial_params, &trial_poses);
            if trial_cost.is_finite() && trial_cost < cost {
                params = trial_params;
                poses = trial_poses;
                let relative = (cost - trial_cost) / cost;
                cost = trial_cost;
                mu /= 3.0;
                nu = 2.0;
                if size <= step_tolerance || relative <= 1e-12 {
                    converged = true;
                    break;
                }
            } else {
                if size <= step_tolerance {
                    converged = true;
                    break;
                }
                mu = if mu == 0.0 { 1e-6 } else { mu * nu };
                nu *= 2.0;
                if mu > 1e12 {
                    converged = true;
                    break;
                }
            }
        }
        let nm = self.normal(&params, &poses, &ranges)?;
        let (s, singular_poses) = self.schur(&nm);
        let analysis = analyse_normal_matrix(&s);
        let (squared, max_residual) = self.cost(&params, &poses);
        Ok(Fit {
            parameters: params,
            poses,
            iterations,
            converged,
            squared,
            max_residual,
            analysis,
            singular_poses,
        })
    }
}

//! # Forward kinematics
//!
//! From measured cable lengths **L** (n ≥ DOF) to the platform pose: Levenberg–Marquardt on the
//! residual **r**(x) = **l**(x) − **L**, with the analytic Jacobian of whichever cable model the
//! robot uses (straight cables, or the swivel-pulley model: in both, l̇ = −Wᵀ q̇ for the twist
//! q̇ of the motion pattern). Each iteration solves
//!
//! ```text
//!   (W Wᵀ + μ diag(W Wᵀ)) δ = W r,     x ← x ⊕ δ
//! ```
//!
//! where x ⊕ δ moves the position by δ_p and rotates the platform by exp([δ_φ]×) (base-frame
//! rotation vector, as in the Jacobian). μ starts at 0 (a Gauss–Newton step); a step that does
//! not lower ½‖r‖² is rejected and μ raised, an accepted one lowers it (Nielsen's rule). When
//! n > DOF and the lengths are inconsistent (noise) the iteration converges to the least-squares
//! pose, the minimiser of ‖l(x) − L‖₂.
//!
//! Every answer carries its certificate: the residual max |l_i(x) − L_i| recomputed at the
//! returned pose, the iterations, whether the iteration converged, and the smallest singular
//! value σ_min of J = Wᵀ there (σ_min → 0 near a singularity, where the pose is ill-determined
//! by the lengths: pose error ≲ length error / σ_min). "Did not converge" and "no pose within
//! the tolerance" are [`ForwardStatus`] values, not errors.
//!
//! ## Measured lengths: solved, fitted or inconsistent
//!
//! Measured lengths carry noise. With n > DOF the least-squares pose x̂ leaves a residual
//! r = l(x̂) − L; for independent length errors of standard deviation σ (`length_sigma`,
//! default 0.1 mm) the sum ‖r‖² / σ² follows a χ² law with n − DOF degrees of freedom. The
//! status is `solved` when max |r_i| ≤ tolerance, `fitted` when ‖r‖² / σ² is below the 99.9 %
//! quantile of that law (Wilson & Hilferty 1931 approximation), `inconsistent` otherwise. Every
//! answer reports `residual_rms` = ‖r‖ / √n and the pose's standard deviations
//! √diag(σ² (JᵀJ)⁻¹) (first-order propagation of the length noise, J = Wᵀ; position in m,
//! rotation as the base-frame rotation vector in rad).
//!
//! ## Suspended robots and the mirror pose
//!
//! When every anchor lies at one height (a spidercam, the NIST RoboCrane), the lengths are
//! symmetric in the anchors' plane: every hanging pose has a mirror pose above the anchors,
//! and on the plane the Jacobian is singular. For such a suspended robot
//! ([`Robot::is_suspended`]: in space, anchors spanning less than a quarter of the frame's
//! width in height) a pose at which no cable rises from the platform (every unit vector
//! towards the anchors has u_z ≤ 0: the platform on or above all its anchors, where no cable
//! can carry its weight) has status `above the anchors`, never `solved`.
//!
//! Without a guess, [`ForwardKinematics::solve_multistart`] starts from the centre of the frame
//! anchors' bounding box in several orientations, from points halfway to its corners and, when
//! the anchors span little height ([`Robot::default_region`] extends the box below them), from
//! three heights on the hanging side (1/8, 1/4 and 1/2 of the frame's width below the highest
//! anchor). It returns every distinct pose found. A fixed set of starts can miss a pose: a
//! pose reached from none of them is not reported; give `--guess` (or [`ForwardKinematics::solve`])
//! near it.
//!
//! ## References
//! - Pott, *Cable-Driven Parallel Robots*, Springer 2018 (forward kinematics by nonlinear
//!   least squares).
//! - Levenberg 1944, Marquardt 1963; Nielsen 1999 (damping update); Madsen, Nielsen & Tingleff
//!   2004, *Methods for non-linear least squares problems* (stopping rules).
//! - Wilson & Hilferty 1931, *The distribution of chi-square*, PNAS 17 (χ² quantiles).

use crate::{KinematicsError, MotionPattern, Pose, PoseKinematics, Robot};
use nalgebra::{Rotation3, Vector3};

/// Settings of the forward-kinematics solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForwardSettings {
    /// A pose whose residual max |l_i(x) − L_i| is at most this (m) solves the lengths.
    pub tolerance: f64,
    /// Largest number of iterations (accepted or rejected steps) per start.
    pub max_iterations: usize,
    /// Standard deviation σ of the length measurements (m): lengths whose least-squares
    /// residual is consistent with it are `fitted`; it scales the pose's standard deviations.
    pub length_sigma: f64,
}

impl Default for ForwardSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-9,
            max_iterations: 100,
            length_sigma: 1e-4,
        }
    }
}

impl ForwardSettings {
    /// Errors on a tolerance that is not finite and > 0, or a zero iteration limit.
    pub fn validate(&self) -> Result<(), KinematicsError> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(KinematicsError::InvalidSetting {
                what: "forward-kinematics tolerance (must be finite and > 0)",
                value: self.tolerance,
            });
        }
        if !(self.length_sigma.is_finite() && self.length_sigma > 0.0) {
            return Err(KinematicsError::InvalidSetting {
                what: "length standard deviation σ (m; must be finite and > 0)",
                value: self.length_sigma,
            });
        }
        if self.max_iterations == 0 {
            return Err(KinematicsError::InvalidSetting {
                what: "forward-kinematics iteration limit (must be ≥ 1)",
                value: 0.0,
            });
        }
        Ok(())
    }
}

/// How a forward-kinematics solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ForwardStatus {
    /// The iteration converged and max |l_i(x) − L_i| ≤ tolerance.
    Solved,
    /// n = DOF: the iteration converged (the step vanished) to a pose whose residual exceeds
    /// the tolerance: unreachable lengths, or a local minimum. No pose within the tolerance was
    /// found from this start.
    NoPoseWithinTolerance,
    /// The iteration limit was reached first; the pose is the best one found.
    NotConverged,
    /// n > DOF: the least-squares pose, with a residual consistent with the length noise σ
    /// (‖r‖²/σ² below the 99.9 % quantile of χ² with n − DOF degrees of freedom).
    Fitted,
    /// n > DOF: the iteration converged to a pose whose residual is too large for the length
    /// noise σ: inconsistent lengths (or a local minimum).
    Inconsistent,
    /// The pose lies on or above the plane of the anchors (no cable rises from the platform):
    /// the mirror image of a hanging pose, never a solution (space only).
    AboveAnchors,
}

impl ForwardStatus {
    /// The name used in JSON output and messages.
    pub fn name(self) -> &'static str {
        match self {
            Self::Solved => "solved",
            Self::NoPoseWithinTolerance => "no pose within tolerance",
            Self::NotConverged => "did not converge",
            Self::Fitted => "fitted",
            Self::Inconsistent => "inconsistent",
            Self::AboveAnchors => "above the anchors",
        }
    }

    /// Whether the pose answers the lengths: `Solved` or `Fitted`.
    pub fn is_solution(self) -> bool {
        matches!(self, Self::Solved | Self::Fitted)
    }
}

/// A forward-kinematics answer with its certificate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForwardSolution {
    /// The pose found (the best one, whatever the status).
    pub pose: Pose,
    /// max |l_i(pose) − L_i| (m), recomputed at `pose`.
    pub residual: f64,
    /// Iterations taken (accepted and rejected steps).
    pub iterations: usize,
    /// Whether the iteration converged (status `Solved` or `NoPoseWithinTolerance`).
    pub converged: bool,
    /// How the solve ended.
    pub status: ForwardStatus,
    /// Smallest singular value of J = Wᵀ at `pose` (m per unit twist: m/m and m/rad).
    pub min_singular_value: f64,
    /// ‖l(pose) − L‖ / √n (m).
    pub residual_rms: f64,
    /// Standard deviations of the pose, √diag(σ² (JᵀJ)⁻¹) with σ = `length_sigma`: the first
    /// DOF entries, in twist order (position m; base-frame rotation vector rad), the rest 0;
    /// infinite where JᵀJ is singular.
    pub pose_std: [f64; MAX_DOF],
}

impl ForwardSolution {
    /// The pose's standard deviations for a motion pattern with `dof` degrees of freedom.
    pub fn pose_std(&self, dof: usize) -> &[f64] {
        &self.pose_std[..dof.min(MAX_DOF)]
    }
}

/// Largest DOF of any motion pattern.
const MAX_DOF: usize = 6;
/// A D × D matrix on the stack (row-major); the solver is compiled once per DOF (2, 3, 6).
type Square<const D: usize> = [[f64; D]; D];

/// A reusable forward-kinematics solver for one robot: no allocation per solve.
///
/// ```
/// use cdpr_kinematics::{ForwardKinematics, ForwardSettings, ForwardStatus, Pose};
/// use cdpr_kinematics::reference_robots::ipanema_like_8_pulleys;
/// use nalgebra::Vector3;
/// let robot = ipanema_like_8_pulleys();
/// let truth = Pose::spatial(Vector3::new(0.3, -0.2, 1.1), 0.05, -0.02, 0.1);
/// let lengths: Vec<f64> = robot.inverse_kinematics(&truth).unwrap().lengths().collect();
/// let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
/// let guess = Pose::spatial(Vector3::new(0.0, 0.0, 1.0), 0.0, 0.0, 0.0);
/// let sol = fk.solve(&lengths, &guess).unwrap();
/// assert_eq!(sol.status, ForwardStatus::Solved);
/// assert!((sol.pose.position - truth.position).norm() < 1e-9);
/// ```
#[derive(Debug, Clone)]
pub struct ForwardKinematics<'a> {
    robot: &'a Robot,
    settings: ForwardSettings,
    /// σ² × the 99.9 % quantile of χ²(n − DOF): the largest ‖r‖² of a `fitted` pose.
    fit_threshold: f64,
    /// A robot in space whose anchors span little height ([`Robot::is_suspended`]).
    suspended: bool,
    kin: PoseKinematics,
    trial: PoseKinematics,
}

impl<'a> ForwardKinematics<'a> {
    /// A solver for `robot` (any cable model). Errors on invalid settings or n < DOF.
    pub fn new(robot: &'a Robot, settings: ForwardSettings) -> Result<Self, KinematicsError> {
        settings.validate()?;
        if robot.cable_count() < robot.dof() {
            return Err(KinematicsError::TooFewCables {
                cables: robot.cable_count(),
                dof: robot.dof(),
            });
        }
        let redundancy = robot.cable_count() - robot.dof();
        Ok(Self {
            robot,
            settings,
            fit_threshold: settings.length_sigma.powi(2) * chi_square_quantile_999(redundancy),
            suspended: robot.is_suspended(),
            kin: PoseKinematics::for_robot(robot),
            trial: PoseKinematics::for_robot(robot),
        })
    }

    /// The settings in use.
    pub fn settings(&self) -> &ForwardSettings {
        &self.settings
    }

    fn check_lengths(&self, lengths: &[f64]) -> Result<(), KinematicsError> {
        if lengths.len() != self.robot.cable_count() {
            return Err(KinematicsError::WrongCableCount {
                what: "measured cable lengths".into(),
                cables: self.robot.cable_count(),
                found: lengths.len(),
            });
        }
        if let Some((i, &v)) = lengths.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(KinematicsError::NotFinite {
                what: format!("length of cable {}", i + 1),
                value: v,
            });
        }
        if let Some((cable, &value)) = lengths.iter().enumerate().find(|(_, v)| **v < 0.0) {
            return Err(KinematicsError::NegativeLength { cable, value });
        }
        Ok(())
    }

    /// The pose whose cable lengths are `lengths` (m), by Levenberg–Marquardt from `guess`.
    ///
    /// Errors only on bad input (wrong count, non-finite lengths or guess, a guess at which the
    /// inverse kinematics is degenerate); every numerical outcome is a [`ForwardSolution`].
    pub fn solve(
        &mut self,
        lengths: &[f64],
        guess: &Pose,
    ) -> Result<ForwardSolution, KinematicsError> {
        self.check_lengths(lengths)?;
        if let Some(&v) = guess.rotation.matrix().iter().find(|v| !v.is_finite()) {
            return Err(KinematicsError::NotFinite {
                what: "guess orientation".into(),
                value: v,
            });
        }
        self.robot.update_kinematics(guess, &mut self.kin)?;
        Ok(self.iterate(lengths, *guess))
    }

    /// Solves along a path: sample k starts from the solution of sample k − 1 (the first from
    /// `guess`). `lengths` holds the samples one after another (n values each). A sample whose
    /// start is degenerate restarts from `guess`.
    pub fn solve_path(
        &mut self,
        lengths: &[f64],
        guess: &Pose,
    ) -> Result<Vec<ForwardSolution>, KinematicsError> {
        let n = self.robot.cable_count();
        if !lengths.len().is_multiple_of(n) {
            return Err(KinematicsError::WrongDimension {
                what: "concatenated cable lengths (a multiple of the cable count)".into(),
                motion: self.robot.motion().name(),
                expected: n * lengths.len().div_ceil(n).max(1),
                found: lengths.len(),
            });
        }
        let mut out = Vec::with_capacity(lengths.len() / n);
        let mut start = *guess;
        for sample in lengths.chunks_exact(n) {
            let sol = match self.solve(sample, &start) {
                Err(KinematicsError::DegenerateCable { .. })
                | Err(KinematicsError::DegeneratePulley { .. }) => self.solve(sample, guess)?,
                other => other?,
            };
            if sol.converged {
                start = sol.pose;
            }
            out.push(sol);
        }
        Ok(out)
    }

    /// Every distinct pose found from a fixed set of starts, solutions (status `Solved`, then
    /// `Fitted`) by residual; if none answers the lengths, the best converged (or best) answer
    /// alone. A fixed set of starts can miss a pose (see the module documentation).
    ///
    /// Starts: the centre of the frame anchors' bounding box, in the reference orientation and
    /// (for oriented platforms) rotated by ±π/2 about each rotation axis and by π about z, and
    /// the points halfway from the centre to each corner of the box in the reference
    /// orientation; for a robot whose anchors span little height (suspended: the default
    /// region extends below them), also three points on the hanging side, 1/8, 1/4 and 1/2 of
    /// the frame's width below the highest anchor (the middle one in every orientation above).
    /// Two poses are the same when their positions differ by less than 1e-6 × the robot's
    /// length scale and their orientations by less than 1e-6 rad.
    pub fn solve_multistart(
        &mut self,
        lengths: &[f64],
    ) -> Result<Vec<ForwardSolution>, KinematicsError> {
        self.check_lengths(lengths)?;
        let motion = self.robot.motion();
        let mut solutions: Vec<ForwardSolution> = Vec::new();
        let mut best: Option<ForwardSolution> = None;
        let scale = self.robot.length_scale();
        for start in multistart_poses(self.robot) {
            if self.robot.update_kinematics(&start, &mut self.kin).is_err() {
                continue;
            }
            let sol = self.iterate(lengths, start);
            let better = |b: &ForwardSolution| {
                (sol.status.is_solution(), sol.converged, -sol.residual)
                    > (b.status.is_solution(), b.converged, -b.residual)
            };
            if best.as_ref().is_none_or(better) {
                best = Some(sol);
            }
            if sol.status.is_solution()
                && !solutions
                    .iter()
                    .any(|s| same_pose(motion, &s.pose, &sol.pose, scale))
            {
                solutions.push(sol);
            }
        }
        if solutions.is_empty() {
            solutions.extend(best);
        }
        let rank = |s: &ForwardSolution| (s.status != ForwardStatus::Solved) as u8;
        solutions.sort_by(|a, b| {
            rank(a)
                .cmp(&rank(b))
                .then(a.residual.total_cmp(&b.residual))
        });
        Ok(solutions)
    }

    /// The Levenberg–Marquardt loop from `x`, whose kinematics are in `self.kin`.
    fn iterate(&mut self, lengths: &[f64], x: Pose) -> ForwardSolution {
        match self.robot.motion().dof() {
            2 => self.iterate_fixed::<2>(lengths, x),
            3 => self.iterate_fixed::<3>(lengths, x),
            MAX_DOF => {
                #[cfg(target_arch = "x86_64")]
                if std::arch::is_x86_feature_detected!("avx2") {
                    // SAFETY: the CPU supports AVX2, the only feature the function enables.
                    return unsafe { self.iterate_spatial_avx2(lengths, x) };
                }
                self.iterate_fixed::<MAX_DOF>(lengths, x)
            }
            d => unreachable!("no motion pattern has {d} degrees of freedom"),
        }
    }

    /// [`Self::iterate_fixed`] for spatial robots compiled with AVX2 (chosen at run time): the
    /// normal equations, factorisations and σ_min run four lanes wide. No fused multiply–add is
    /// enabled, so every operation rounds as in the portable build: identical results.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn iterate_spatial_avx2(&mut self, lengths: &[f64], x: Pose) -> ForwardSolution {
        self.iterate_fixed::<MAX_DOF>(lengths, x)
    }

    /// [`Self::iterate`] for a motion pattern with D degrees of freedom.
    #[inline(always)]
    fn iterate_fixed<const D: usize>(&mut self, lengths: &[f64], mut x: Pose) -> ForwardSolution {
        let motion = self.robot.motion();
        let d = D;
        let scale = self.robot.length_scale();
        // Below this step (m, rad) nothing changes at the precision of the lengths.
        let step_tolerance = 1e-13 * scale;
        let mut cost = half_squared_residual(&self.kin, lengths);
        let mut mu = 0.0;
        let mut nu = 2.0;
        let mut iterations = 0;
        let mut converged = false;
        let mut a: Square<D> = [[0.0; D]; D];
        let mut rhs = [0.0; D];
        // Whether `a` holds W Wᵀ at x (then the certificate reuses it).
        let mut a_at_x = false;
        while iterations < self.settings.max_iterations {
            if max_residual(&self.kin, lengths) <= f64::EPSILON * scale {
                converged = true;
                break;
            }
            normal_equations(&self.kin, lengths, &mut a, &mut rhs);
            a_at_x = true;
            let diag_max = (0..d).map(|k| a[k][k]).fold(0.0, f64::max);
            if diag_max == 0.0 {
                break;
            }
            let mut damped = a;
            for k in 0..d {
                damped[k][k] += mu * a[k][k].max(1e-12 * diag_max);
            }
            iterations += 1;
            let Some(delta) = cholesky_solve(&damped, &rhs) else {
                mu = if mu == 0.0 { 1e-6 } else { mu * nu };
                nu *= 2.0;
                continue;
            };
            let step = delta.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            // The step rule of Madsen, Nielsen & Tingleff, tested before the trial pose is
            // evaluated: a step this short cannot move the pose at the precision of the
            // lengths (below, either outcome of the trial ends the loop as converged), so when
            // x already solves the lengths the trial's inverse kinematics is skipped.
            if step <= step_tolerance && max_residual(&self.kin, lengths) <= self.settings.tolerance
            {
                converged = true;
                break;
            }
            let trial = displaced(motion, &x, &delta);
            let accepted = match self.robot.update_kinematics(&trial, &mut self.trial) {
                Ok(()) => {
                    let trial_cost = half_squared_residual(&self.trial, lengths);
                    trial_cost < cost
                }
                Err(_) => false,
            };
            if accepted {
                cost = half_squared_residual(&self.trial, lengths);
                x = trial;
                a_at_x = false;
                std::mem::swap(&mut self.kin, &mut self.trial);
                mu /= 3.0;
                nu = 2.0;
                if step <= step_tolerance {
                    converged = true;
                    break;
                }
            } else {
                if step <= step_tolerance {
                    // Even the undamped-size step cannot lower the cost: a stationary point.
                    converged = true;
                    break;
                }
                mu = if mu == 0.0 { 1e-6 } else { mu * nu };
                nu *= 2.0;
                if mu > 1e12 {
                    // The gradient no longer points downhill at any representable step.
                    converged = true;
                    break;
                }
            }
        }
        let residual = max_residual(&self.kin, lengths);
        if !a_at_x {
            normal_equations(&self.kin, lengths, &mut a, &mut rhs);
        }
        // σ_min(J)² = λ_min(JᵀJ) = λ_min(W Wᵀ), once, at the returned pose.
        let min_singular_value = smallest_eigenvalue(&a).max(0.0).sqrt();
        let squared = 2.0 * half_squared_residual(&self.kin, lengths);
        let within = residual <= self.settings.tolerance;
        let redundant = lengths.len() > d;
        let status = if (converged || within) && self.suspended && above_anchors(&self.kin) {
            ForwardStatus::AboveAnchors
        } else if within {
            ForwardStatus::Solved
        } else if !converged {
            ForwardStatus::NotConverged
        } else if !redundant {
            ForwardStatus::NoPoseWithinTolerance
        } else if squared <= self.fit_threshold {
            ForwardStatus::Fitted
        } else {
            ForwardStatus::Inconsistent
        };
        let mut pose_std = [0.0; MAX_DOF];
        let inverse_diagonal = inverse_diagonal(&a);
        for k in 0..d {
            pose_std[k] = self.settings.length_sigma * inverse_diagonal[k].sqrt();
        }
        ForwardSolution {
            pose: x,
            residual,
            iterations,
            converged: converged || within,
            status,
            min_singular_value,
            residual_rms: (squared / lengths.len() as f64).sqrt(),
            pose_std,
        }
    }
}

impl Robot {
    /// Forward kinematics from `guess` with the given settings (see [`ForwardKinematics`]).
    pub fn forward_kinematics(
        &self,
        lengths: &[f64],
        guess: &Pose,
        settings: ForwardSettings,
    ) -> Result<ForwardSolution, KinematicsError> {
        ForwardKinematics::new(self, settings)?.solve(lengths, guess)
    }
}

/// The 99.9 % quantile of χ² with k degrees of freedom (Wilson & Hilferty 1931:
/// k (1 − 2/(9k) + z √(2/(9k)))³, z = 3.0902 the standard normal 99.9 % quantile; at most
/// 3.1 % above the exact quantile for k ≥ 1: 11.16 against 10.83 at k = 1, 29.76 against 29.59
/// at k = 10). 0 for k = 0.
pub fn chi_square_quantile_999(k: usize) -> f64 {
    if k == 0 {
        return 0.0;
    }
    let k = k as f64;
    let c = 2.0 / (9.0 * k);
    k * (1.0 - c + 3.090_232 * c.sqrt()).powi(3)
}

/// Whether no cable rises from the platform (u_z ≤ 0 for every cable): the platform on or
/// above the plane of all its anchors.
fn above_anchors(kin: &PoseKinematics) -> bool {
    kin.cables().iter().all(|c| c.unit.z <= 1e-9)
}

/// diag(A⁻¹) of a symmetric positive definite A, from its Cholesky factor:
/// (A⁻¹)_kk = Σ_i (L⁻¹)_ik². Infinite entries when A is not positive definite.
// Index loops read as the textbook algorithm on these small fixed arrays.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn inverse_diagonal<const D: usize>(a: &Square<D>) -> [f64; D] {
    let Some(l) = cholesky(a, 0.0) else {
        return [f64::INFINITY; D];
    };
    let mut out = [0.0; D];
    // Column j of X = L⁻¹ (lower triangular), by forward substitution.
    for j in 0..D {
        let mut x = [0.0; D];
        x[j] = 1.0 / l[j][j];
        out[j] += x[j] * x[j];
        for i in j + 1..D {
            let mut s = 0.0;
            for k in j..i {
                s -= l[i][k] * x[k];
            }
            x[i] = s / l[i][i];
            out[j] += x[i] * x[i];
        }
    }
    // out[j] = Σ_i X_ij² is the squared norm of column j of X: (XᵀX)_jj = (A⁻¹)_jj.
    out
}

fn max_residual(kin: &PoseKinematics, lengths: &[f64]) -> f64 {
    kin.lengths()
        .zip(lengths)
        .fold(0.0, |m, (l, t)| m.max((l - t).abs()))
}

fn half_squared_residual(kin: &PoseKinematics, lengths: &[f64]) -> f64 {
    0.5 * kin
        .lengths()
        .zip(lengths)
        .map(|(l, t)| (l - t) * (l - t))
        .sum::<f64>()
}

/// A = W Wᵀ and rhs = W r (r = l − L).
///
/// Both triangles are accumulated (col_i col_j and col_j col_i are the same product, so A is
/// exactly symmetric): whole rows of equal length, which the compiler turns into vector
/// operations.
// Index loops read as the textbook algorithm on these small fixed arrays.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn normal_equations<const D: usize>(
    kin: &PoseKinematics,
    lengths: &[f64],
    a: &mut Square<D>,
    rhs: &mut [f64; D],
) {
    let motion = kin.motion();
    *a = [[0.0; D]; D];
    *rhs = [0.0; D];
    for (c, &target) in kin.cables().iter().zip(lengths) {
        let col: [f64; D] = wrench_column(motion, &c.unit, &c.attachment);
        let r = c.length - target;
        for i in 0..D {
            rhs[i] += col[i] * r;
            for j in 0..D {
                a[i][j] += col[i] * col[j];
            }
        }
    }
}

/// Column of W for one cable (the same as `PoseKinematics::write_wrench_matrix`); D is the
/// motion pattern's DOF.
#[inline]
fn wrench_column<const D: usize>(
    motion: MotionPattern,
    u: &Vector3<f64>,
    b: &Vector3<f64>,
) -> [f64; D] {
    let full = match motion {
        MotionPattern::Point2 => [u.x, u.y, 0.0, 0.0, 0.0, 0.0],
        MotionPattern::Planar => [u.x, u.y, b.x * u.y - b.y * u.x, 0.0, 0.0, 0.0],
        MotionPattern::Point3 => [u.x, u.y, u.z, 0.0, 0.0, 0.0],
        MotionPattern::Spatial => {
            let m = b.cross(u);
            [u.x, u.y, u.z, m.x, m.y, m.z]
        }
    };
    std::array::from_fn(|i| full[i])
}

/// The Cholesky factor L (lower triangular, L Lᵀ = A − shift · I) of a symmetric matrix;
/// `None` if A − shift · I is not positive definite (a pivot ≤ 0, NaN or infinite).
// Index loops read as the textbook algorithm on these small fixed arrays.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn cholesky<const D: usize>(a: &Square<D>, shift: f64) -> Option<Square<D>> {
    let mut l: Square<D> = [[0.0; D]; D];
    // Constant loop bounds with the triangles as conditions: the compiler unrolls all of it.
    for i in 0..D {
        for j in 0..D {
            if j > i {
                continue;
            }
            let mut s = a[i][j];
            if i == j {
                s -= shift;
            }
            for k in 0..D {
                if k < j {
                    s -= l[i][k] * l[j][k];
                }
            }
            if i == j {
                if s.is_nan() || s <= 0.0 || s.is_infinite() {
                    return None;
                }
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
    Some(l)
}

/// Solves A δ = b for symmetric positive definite A; `None` if not SPD.
// Index loops read as the textbook algorithm on these small fixed arrays.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn cholesky_solve<const D: usize>(a: &Square<D>, b: &[f64; D]) -> Option<[f64; D]> {
    let l = cholesky(a, 0.0)?;
    let mut y = *b;
    for i in 0..D {
        let mut s = y[i];
        for k in 0..i {
            s -= l[i][k] * y[k];
        }
        y[i] = s / l[i][i];
    }
    for i in (0..D).rev() {
        let mut s = y[i];
        for k in i + 1..D {
            s -= l[k][i] * y[k];
        }
        y[i] = s / l[i][i];
    }
    y.iter().all(|v| v.is_finite()).then_some(y)
}

/// Smallest eigenvalue λ₁ of the symmetric positive semi-definite D × D matrix `a`, by
/// Laguerre's method on its characteristic polynomial p(λ) = det(A − λI), from λ = 0.
///
/// With M = A − λI = L Lᵀ (Cholesky) and X = L⁻¹, the roots' distances dᵢ = λᵢ − λ give
/// G = Σ 1/dᵢ = tr M⁻¹ = ‖X‖²_F and H = Σ 1/dᵢ² = tr M⁻² = ‖XᵀX‖²_F, and the step is
///
/// ```text
///   λ ← λ + D / (G + √((D − 1)(D H − G²)))
/// ```
///
/// For a polynomial with real roots Laguerre's iterates from below the smallest root increase
/// monotonically towards it and never pass it (Wilkinson 1965, §7.10): each iterate is a lower
/// bound, and the Cholesky factorisation that exists there confirms it. Convergence is cubic,
/// and exact in one step when every eigenvalue is equal. The loop stops when the step no
/// longer changes λ by more than 4 ε λ, or when the factorisation fails at the new λ, which then
/// lies at λ₁ within the factorisation's backward error (about D ε ‖A‖). Returns 0 when A
/// itself has no Cholesky factor (singular to working precision).
// Index loops read as the textbook algorithm on these small fixed arrays.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn smallest_eigenvalue<const D: usize>(a: &Square<D>) -> f64 {
    let n = D as f64;
    let mut lambda = 0.0;
    let Some(mut l) = cholesky(a, 0.0) else {
        return 0.0;
    };
    for _ in 0..64 {
        // X = L⁻¹ (lower triangular), column by column.
        let mut x: Square<D> = [[0.0; D]; D];
        for j in 0..D {
            x[j][j] = 1.0 / l[j][j];
            for i in j + 1..D {
                let mut s = 0.0;
                for k in j..i {
                    s -= l[i][k] * x[k][j];
                }
                x[i][j] = s / l[i][i];
            }
        }
        // M⁻¹ = XᵀX; G = tr M⁻¹, H = ‖M⁻¹‖²_F.
        let (mut g, mut h) = (0.0, 0.0);
        for i in 0..D {
            for j in 0..=i {
                let mut m = 0.0;
                for k in i..D {
                    m += x[k][i] * x[k][j];
                }
                if i == j {
                    g += m;
                    h += m * m;
                } else {
                    h += 2.0 * m * m;
                }
            }
        }
        let step = n / (g + ((n - 1.0) * (n * h - g * g)).max(0.0).sqrt());
        let next = lambda + step;
        if step.is_nan() {
            return lambda;
        }
        if step <= 4.0 * f64::EPSILON * next {
            return next;
        }
        match cholesky(a, next) {
            Some(factor) => {
                l = factor;
                lambda = next;
            }
            // In exact arithmetic next ≤ λ₁; a failed factorisation puts it within the
            // rounding of the factorisation of λ₁.
            None => return next,
        }
    }
    lambda
}

/// x ⊕ δ: the pose moved by the twist δ of the motion pattern (position first, then the
/// rotation vector in base coordinates, applied on the left as in the Jacobian).
pub(crate) fn displaced(motion: MotionPattern, pose: &Pose, delta: &[f64]) -> Pose {
    let (dp, dphi) = match motion {
        MotionPattern::Point2 => (Vector3::new(delta[0], delta[1], 0.0), None),
        MotionPattern::Planar => (
            Vector3::new(delta[0], delta[1], 0.0),
            Some(Vector3::new(0.0, 0.0, delta[2])),
        ),
        MotionPattern::Point3 => (Vector3::new(delta[0], delta[1], delta[2]), None),
        MotionPattern::Spatial => (
            Vector3::new(delta[0], delta[1], delta[2]),
            Some(Vector3::new(delta[3], delta[4], delta[5])),
        ),
    };
    let rotation = match dphi {
        Some(w) => Rotation3::new(w) * pose.rotation,
        None => pose.rotation,
    };
    Pose::new(pose.position + dp, rotation)
}

fn same_pose(motion: MotionPattern, a: &Pose, b: &Pose, scale: f64) -> bool {
    let position = (a.position - b.position).norm() <= 1e-6 * scale;
    // ‖R_a − R_b‖_F ≈ √2 × their angle (`angle_to`, an acos of the trace, is NaN or 1e-8 for
    // equal rotations).
    let rotation =
        !motion.has_orientation() || (a.rotation.matrix() - b.rotation.matrix()).norm() <= 1e-6;
    position && rotation
}

/// The starts of [`ForwardKinematics::solve_multistart`].
fn multistart_poses(robot: &Robot) -> Vec<Pose> {
    let motion = robot.motion();
    let (lo, hi) = robot.frame_bounding_box();
    let centre = (lo + hi) / 2.0;
    let half = (hi - lo) / 4.0;
    let mut rotations = vec![Rotation3::identity()];
    match motion {
        MotionPattern::Planar => {
            for angle in [
                std::f64::consts::FRAC_PI_2,
                -std::f64::consts::FRAC_PI_2,
                std::f64::consts::PI,
            ] {
                rotations.push(Rotation3::from_axis_angle(&Vector3::z_axis(), angle));
            }
        }
        MotionPattern::Spatial => {
            for axis in [Vector3::x_axis(), Vector3::y_axis(), Vector3::z_axis()] {
                for angle in [std::f64::consts::FRAC_PI_2, -std::f64::consts::FRAC_PI_2] {
                    rotations.push(Rotation3::from_axis_angle(&axis, angle));
                }
            }
            rotations.push(Rotation3::from_axis_angle(
                &Vector3::z_axis(),
                std::f64::consts::PI,
            ));
        }
        MotionPattern::Point2 | MotionPattern::Point3 => {}
    }
    let mut starts: Vec<Pose> = rotations.iter().map(|r| Pose::new(centre, *r)).collect();
    let dims = motion.space_dim();
    for corner in 0..(1 << dims) {
        let mut p = centre;
        for k in 0..dims {
            p[k] += if corner & (1 << k) == 0 {
                -half[k]
            } else {
                half[k]
            };
        }
        starts.push(Pose::new(p, Rotation3::identity()));
    }
    if robot.is_suspended() {
        // Suspended: the hanging side, below the highest anchor.
        let width = (hi.x - lo.x).max(hi.y - lo.y);
        for (k, depth) in [0.125, 0.25, 0.5].into_iter().enumerate() {
            let p = Vector3::new(centre.x, centre.y, hi.z - depth * width);
            if k == 1 {
                starts.extend(rotations.iter().map(|r| Pose::new(p, *r)));
            } else {
                starts.push(Pose::new(p, Rotation3::identity()));
            }
        }
    }
    starts
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spatial solver as dispatched (AVX2 build where the CPU has it) and its portable
    /// build give the same bits, with pulleys and without, on exact and noisy lengths.
    #[test]
    fn dispatched_and_portable_solvers_agree_bit_for_bit() {
        use crate::reference_robots::{ipanema_like_8, ipanema_like_8_pulleys};
        for robot in [ipanema_like_8(), ipanema_like_8_pulleys()] {
            let mut fk = ForwardKinematics::new(&robot, ForwardSettings::default()).unwrap();
            for k in 0..40 {
                let t = k as f64;
                let pose = Pose::new(
                    Vector3::new(0.3 * (0.7 * t).sin(), 0.3 * (1.3 * t).cos(), 0.2 * t.sin()),
                    Rotation3::new(Vector3::new(0.2 * t.cos(), 0.1 * t.sin(), 0.3 * t.cos())),
                );
                let mut lengths: Vec<f64> =
                    robot.inverse_kinematics(&pose).unwrap().lengths().collect();
                if k % 2 == 1 {
                    lengths[k % 8] += 1e-4;
                }
                let guess = Pose::new(
                    pose.position + Vector3::new(0.02, -0.01, 0.01),
                    Rotation3::new(Vector3::new(0.0, 0.02, -0.01)) * pose.rotation,
                );
                let dispatched = fk.solve(&lengths, &guess).unwrap();
                robot.update_kinematics(&guess, &mut fk.kin).unwrap();
                let portable = fk.iterate_fixed::<MAX_DOF>(&lengths, guess);
                assert_eq!(dispatched, portable);
                assert!(dispatched.converged, "{dispatched:?}");
            }
        }
    }

    #[test]
    fn cholesky_and_jacobi_by_hand() {
        let mut a: Square<3> = [[4.0, 2.0, 0.0], [2.0, 3.0, 0.0], [0.0, 0.0, 9.0]];
        let b = [2.0, 1.0, 3.0];
        let x = cholesky_solve(&a, &b).unwrap();
        // [[4, 2], [2, 3]] x = [2, 1] → x = (0.5, 0); 9 x₂ = 3.
        assert!((x[0] - 0.5).abs() < 1e-15 && x[1].abs() < 1e-15);
        assert!((x[2] - 1.0 / 3.0).abs() < 1e-15);
        // Eigenvalues of [[4, 2], [2, 3]]: (7 ± √17) / 2; and 9.
        let expected = (7.0 - 17f64.sqrt()) / 2.0;
        assert!((smallest_eigenvalue(&a) - expected).abs() < 1e-14);
        a[0][0] = -1.0;
        assert!(cholesky_solve(&a, &b).is_none());
    }

    /// λ_min by Laguerre's method against nalgebra's symmetric eigenvalues (QL) for
    /// A = V diag(λ) Vᵀ with random rotations V and spectra that are well separated, clustered
    /// (equal, paired), spread over 12 decades, and rank deficient.
    #[test]
    fn smallest_eigenvalue_matches_a_full_eigen_solve() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let spectra: [[f64; 6]; 7] = [
            [0.3, 1.0, 2.0, 3.0, 5.0, 8.0],
            [2.0; 6],
            [1e-3, 1e-3, 1.0, 1.0, 4.0, 4.0],
            [1e-6, 1e-4, 1e-2, 1.0, 1e2, 1e4],
            [0.7, 0.7 + 1e-9, 3.0, 3.0, 3.0, 9.0],
            [1e-12, 1.0, 1.0, 2.0, 3.0, 4.0],
            [0.0, 1.0, 2.0, 3.0, 4.0, 5.0],
        ];
        for spectrum in spectra {
            for _ in 0..50 {
                let q = nalgebra::Matrix6::from_fn(|_, _| next()).qr().q();
                let m = q * nalgebra::Matrix6::from_diagonal(&spectrum.into()) * q.transpose();
                let m = (m + m.transpose()) / 2.0;
                let a: Square<6> = std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]));
                let ours = smallest_eigenvalue(&a);
                let reference = m.symmetric_eigenvalues().min();
                let scale = spectrum[5];
                assert!(
                    (ours - reference).abs() <= 1e-13 * scale,
                    "{spectrum:?}: {ours} vs {reference}"
                );
                assert!(ours >= 0.0 && ours <= spectrum[0] + 1e-13 * scale);
            }
        }
    }

    #[test]
    fn settings_are_validated() {
        assert!(ForwardSettings::default().validate().is_ok());
        for bad in [
            ForwardSettings {
                tolerance: 0.0,
                ..Default::default()
            },
            ForwardSettings {
                tolerance: f64::NAN,
                ..Default::default()
            },
            ForwardSettings {
                max_iterations: 0,
                ..Default::default()
            },
        ] {
            assert!(bad.validate().is_err());
        }
    }
}

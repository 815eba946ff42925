//! # A downstream user of cdpr-kinematics and cdpr-tension
//!
//! What a winch controller does at every control period: the platform pose of the trajectory at
//! this instant, the cables' wrench matrix W there (cdpr-kinematics), and tensions t_min ≤ t ≤
//! t_max with W t + w_ext = 0 for the platform's weight (cdpr-tension, minimum ‖t‖₂). Every answer
//! is checked here independently of the library: the equilibrium residual recomputed from W, the
//! bounds, and every pose of the trajectory must be feasible. Any failure ends the program with a
//! non-zero status, so CI fails.
//!
//! The buffers (kinematics, W, tensions, solver) are allocated once, before the loop.

use std::process::ExitCode;
use std::time::Instant;

use cdpr_kinematics::nalgebra::{DMatrix, DVector, Vector3};
use cdpr_kinematics::{Cable, MotionPattern, Path, PoseKinematics, Robot, Sampling};
use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};

/// Control rate of the loop (Hz) and trajectory duration (s): 2 001 poses.
const RATE_HZ: f64 = 1000.0;
const DURATION_S: f64 = 2.0;
/// Platform mass (kg) and standard gravity (m/s²).
const MASS_KG: f64 = 5.0;
const G: f64 = 9.80665;
/// Tension bounds (N).
const T_MIN: f64 = 10.0;
const T_MAX: f64 = 1000.0;

/// An 8-cable spatial robot in a 4 m × 3 m × 2 m frame, a 0.2 m × 0.2 m × 0.1 m platform, the
/// upper cables holding the lower platform corners and vice versa (IPAnema-like crossing).
fn robot() -> Robot {
    let mut cables = Vec::new();
    for (z, pz) in [(2.0, -0.05), (0.0, 0.05)] {
        for (x, y) in [(2.0f64, 1.5f64), (-2.0, 1.5), (-2.0, -1.5), (2.0, -1.5)] {
            cables.push(Cable {
                frame: Vector3::new(x, y, z),
                platform: Vector3::new(0.1f64.copysign(x), 0.1f64.copysign(y), pz),
                pulley: None,
            });
        }
    }
    Robot::new(MotionPattern::Spatial, cables).expect("a valid robot")
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("downstream: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let robot = robot();
    let n = robot.cable_count();
    // A pick-and-place move at constant orientation: up, across and down (x, y, z in m; rx, ry,
    // rz in rad).
    let path = Path::from_coordinates(
        MotionPattern::Spatial,
        &[
            vec![-0.6, -0.4, 0.8, 0.0, 0.0, 0.0],
            vec![-0.6, -0.4, 1.0, 0.0, 0.0, 0.0],
            vec![0.6, 0.4, 1.0, 0.0, 0.0, 0.0],
            vec![0.6, 0.4, 0.8, 0.0, 0.0, 0.0],
        ],
    )?;
    let samples = path.sample(Sampling::Count((RATE_HZ * DURATION_S) as usize + 1))?;

    let bounds = TensionBounds::uniform(n, T_MIN, T_MAX)?;
    // The platform's weight at its centre (force in N, moment in N·m about the reference point).
    let w_ext = DVector::from_vec(vec![0.0, 0.0, -MASS_KG * G, 0.0, 0.0, 0.0]);
    let mut solver = TensionSolver::new(Method::L2);
    let mut kin = PoseKinematics::for_robot(&robot);
    let mut w = DMatrix::zeros(6, n);
    let mut t = DVector::zeros(n);

    let (mut worst_residual, mut lowest, mut highest) = (0.0f64, f64::INFINITY, 0.0f64);
    let start = Instant::now();
    for (k, sample) in samples.iter().enumerate() {
        robot.update_kinematics(&sample.pose, &mut kin)?;
        kin.write_wrench_matrix(&mut w);
        let problem = TensionProblem::new(&w, &w_ext, &bounds);
        if let Err(why) = solver.solve_into(&problem, &mut t)? {
            return Err(format!("pose {k} (s = {:.4}): infeasible: {why:?}", sample.s).into());
        }
        // Independent checks of the answer: equilibrium W t + w_ext = 0 and the bounds.
        let residual = (&w * &t + &w_ext).amax();
        if residual > 1e-9 * T_MAX {
            return Err(format!("pose {k}: equilibrium residual {residual:e} N").into());
        }
        if let Some(i) = (0..n).find(|&i| !(T_MIN - 1e-9..=T_MAX + 1e-9).contains(&t[i])) {
            return Err(
                format!("pose {k}: cable {} tension {} N out of bounds", i + 1, t[i]).into(),
            );
        }
        worst_residual = worst_residual.max(residual);
        lowest = lowest.min(t.min());
        highest = highest.max(t.max());
    }
    let elapsed = start.elapsed();
    println!(
        "{} poses ({DURATION_S} s at {RATE_HZ} Hz), all feasible: tensions in [{lowest:.3} N, {highest:.3} N] \
         (bounds [{T_MIN} N, {T_MAX} N]), worst equilibrium residual {worst_residual:.3e} N, \
         {:.2} µs per pose",
        samples.len(),
        elapsed.as_secs_f64() * 1e6 / samples.len() as f64
    );
    Ok(())
}

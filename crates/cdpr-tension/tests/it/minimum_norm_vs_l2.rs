//! Thesis Fig. 6.3: the minimum-norm approach (eq. (6.14), t^nul = 0) underestimates the
//! workspace of the 4-cable robot with c = [±1, ±0.15] (Table 6.1 platform, t ∈ [5, 100],
//! load L1, φ = 0) compared with the constrained ℓ₂ approach (eq. (6.17)).

use crate::common;

use cdpr_kinematics::Pose;
use cdpr_tension::{Method, TensionBounds, TensionProblem, TensionSolver};
use common::{four_cable, load};

/// Counts grid points (m = 50, i.e. 51 × 51 points as Algorithm 6.2 step 3) over `[x0, x1] ×
/// [y0, y1]` where each method finds valid tensions. Poses where a cable has zero length are
/// outside the workspace.
fn count(x: (f64, f64), y: (f64, f64), phi: f64) -> (usize, usize, usize) {
    let robot = four_cable(0.15);
    let b = TensionBounds::uniform(4, 5.0, 100.0).unwrap();
    let we = load(1);
    let (mut pinv, mut l2, mut l1) = (0, 0, 0);
    let mut sp = TensionSolver::new(Method::Pinv);
    let mut s2 = TensionSolver::new(Method::L2);
    let mut s1 = TensionSolver::new(Method::ClosedForm);
    let m = 50;
    for i in 0..=m {
        for j in 0..=m {
            let px = x.0 + (x.1 - x.0) * i as f64 / m as f64;
            let py = y.0 + (y.1 - y.0) * j as f64 / m as f64;
            let Ok(kin) = robot.inverse_kinematics(&Pose::planar(px, py, phi)) else {
                continue;
            };
            let w = kin.wrench_matrix();
            let p = TensionProblem::new(&w, &we, &b);
            let (a, c, d) = (
                sp.is_feasible(&p).unwrap(),
                s2.is_feasible(&p).unwrap(),
                s1.is_feasible(&p).unwrap(),
            );
            assert!(!a || c, "pinv feasible but l2 not at ({px}, {py})");
            assert_eq!(c, d, "l2 and closed form disagree at ({px}, {py})");
            pinv += a as usize;
            l2 += c as usize;
            l1 += d as usize;
        }
    }
    (pinv, l2, l1)
}

/// The grid is Algorithm 6.2's: the bounding box of the frame anchors, [−1, 1] × [−0.15, 0.15],
/// m = 50. Measured (51² points): φ = 0: pinv 265, l2 1310; φ = 0.2: pinv 0, l2 1126;
/// φ = 0.4: pinv 0, l2 808 — the thesis' "extreme underestimation". (On the square [−1, 1]²
/// most points lie outside the frame: φ = 0 gives pinv 152 vs l2 347.)
#[test]
fn minimum_norm_workspace_is_much_smaller_than_l2() {
    for phi in [0.0, 0.2, 0.4] {
        let (pinv, l2, _) = count((-1.0, 1.0), (-0.15, 0.15), phi);
        eprintln!("Fig. 6.3, φ = {phi}: pinv {pinv} points, l2 {l2} points of 51²");
        assert!(l2 > 500, "φ = {phi}: l2 {l2}");
        assert!(pinv * 4 < l2, "φ = {phi}: pinv {pinv} vs l2 {l2}");
    }
    let (pinv, l2, _) = count((-1.0, 1.0), (-1.0, 1.0), 0.0);
    assert!(pinv * 2 < l2, "square grid: pinv {pinv} vs l2 {l2}");
}

//! Fixtures shared by the integration tests: the thesis robots (thesis Tables 6.1–6.3).
#![allow(dead_code)]

use cdpr_kinematics::{Cable, MotionPattern, Robot};
use nalgebra::{DVector, Vector3};

/// Table 6.1 platform attachments of the 4-cable robot.
pub fn thesis_platform() -> [[f64; 2]; 4] {
    let s = 0.1 / 2f64.sqrt();
    [[s, s], [-s, s], [-0.1, -0.1], [0.1, -0.1]]
}

/// A planar 4-cable robot with frame anchors [±1, ±h] (Table 6.2: h = 0.5; Fig. 6.3: 0.15;
/// Fig. 6.6: 0.1), in the thesis' order c¹ = [1, h], c² = [−1, h], c³ = [−1, −h], c⁴ = [1, −h].
pub fn four_cable(h: f64) -> Robot {
    let c = [[1.0, h], [-1.0, h], [-1.0, -h], [1.0, -h]];
    let a = thesis_platform();
    Robot::new(
        MotionPattern::Planar,
        (0..4)
            .map(|i| Cable {
                frame: Vector3::new(c[i][0], c[i][1], 0.0),
                platform: Vector3::new(a[i][0], a[i][1], 0.0),
                pulley: None,
            })
            .collect(),
    )
    .unwrap()
}

/// Table 6.3 loads L1–L3 (f_x, f_y, τ).
pub fn load(k: usize) -> DVector<f64> {
    match k {
        1 => DVector::from_vec(vec![0.0, -10.0, 0.0]),
        2 => DVector::from_vec(vec![5.0, -10.0, 0.0]),
        _ => DVector::from_vec(vec![5.0, -10.0, 1.0]),
    }
}

//! # Reference robots of the papers
//!
//! The robots the reference papers study, built in code so tests, benchmarks and examples share one
//! definition (the same robots ship as files in `examples/robots/`).
//!
//! ## References
//! - Thesis Tables 6.1–6.2 (planar 3- and 4-cable manipulators) and Figs. 6.3, 6.6.
//! - Krut, Company & Pierrot 2004, §IV-B (3 motors at 1000 mm, 30°/150°/270°) and Fig. 10 (n motors on a circle).

use crate::{Cable, MotionPattern, Pulley, Robot};
use nalgebra::{Matrix3, Vector3};

/// Platform attachments ā^i of Table 6.1 for the 3- or 4-cable manipulator.
pub fn thesis_platform(cables: usize) -> Vec<Vector3<f64>> {
    let s = 0.1 / 2f64.sqrt();
    let mut a = vec![Vector3::new(s, s, 0.0), Vector3::new(-s, s, 0.0)];
    if cables == 3 {
        a.push(Vector3::new(0.0, -0.1, 0.0));
    } else {
        a.push(Vector3::new(-0.1, -0.1, 0.0));
        a.push(Vector3::new(0.1, -0.1, 0.0));
    }
    a
}

/// A planar manipulator with the Table 6.1 platform and the given frame anchors (3 or 4).
///
/// ```
/// use cdpr_kinematics::reference_robots::thesis_manipulator;
/// // Thesis Fig. 6.3's robot: c = [±1, ±0.15].
/// let r = thesis_manipulator(&[[1.0, 0.15], [-1.0, 0.15], [-1.0, -0.15], [1.0, -0.15]]);
/// assert_eq!(r.cable_count(), 4);
/// ```
///
/// # Panics
/// If `anchors` does not have 3 or 4 entries, or holds non-finite numbers.
pub fn thesis_manipulator(anchors: &[[f64; 2]]) -> Robot {
    assert!(
        matches!(anchors.len(), 3 | 4),
        "the thesis manipulators have 3 or 4 cables"
    );
    let cables = anchors
        .iter()
        .zip(thesis_platform(anchors.len()))
        .map(|(c, a)| Cable {
            frame: Vector3::new(c[0], c[1], 0.0),
            platform: a,
            pulley: None,
        })
        .collect();
    Robot::new(MotionPattern::Planar, cables).expect("finite anchors")
}

/// The thesis 3-cable manipulator (Tables 6.1, 6.2): c = [1, 1], [−1, 1], [0, −1].
pub fn thesis_three_cable() -> Robot {
    thesis_manipulator(&[[1.0, 1.0], [-1.0, 1.0], [0.0, -1.0]])
}

/// The thesis 4-cable manipulator (Tables 6.1, 6.2): c = [±1, ±0.5].
pub fn thesis_four_cable() -> Robot {
    thesis_manipulator(&[[1.0, 0.5], [-1.0, 0.5], [-1.0, -0.5], [1.0, -0.5]])
}

/// Krut, Company & Pierrot's (2004) point robot with `n` motors at radius `radius`, the first at `first_deg` degrees
/// and the others evenly spaced (3 motors at 30°: the §IV-B robot; Fig. 10: n = 4, 5, 6).
pub fn krut_point_robot(n: usize, radius: f64, first_deg: f64) -> Robot {
    let cables = (0..n)
        .map(|k| {
            let a = (first_deg + 360.0 * k as f64 / n as f64).to_radians();
            Cable {
                frame: Vector3::new(radius * a.cos(), radius * a.sin(), 0.0),
                platform: Vector3::zeros(),
                pulley: None,
            }
        })
        .collect();
    Robot::new(MotionPattern::Point2, cables).expect("finite anchors")
}

/// The 8-cable spatial robot of `examples/robots/ipanema-like-8.toml`: frame anchors at the corners
/// of a 4 m × 3 m × 2 m box, attachments at the corners of a 0.2 × 0.2 × 0.1 m platform, crossed
/// (the upper cables hold the lower platform corners and vice versa).
pub fn ipanema_like_8() -> Robot {
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
    Robot::new(MotionPattern::Spatial, cables).expect("valid robot")
}

/// [`ipanema_like_8`] with a swivel pulley of radius 0.05 m at every frame anchor, its axis
/// pointing up (+z, Q = I, as in the IPAnema `.wcrfx` file of WireCenter): the robot of
/// `examples/robots/ipanema-like-8-pulleys.toml`.
pub fn ipanema_like_8_pulleys() -> Robot {
    let cables = ipanema_like_8()
        .cables()
        .iter()
        .map(|c| Cable {
            pulley: Some(Pulley {
                radius: 0.05,
                orientation: Matrix3::identity(),
            }),
            ..*c
        })
        .collect();
    Robot::new(MotionPattern::Spatial, cables).expect("valid robot")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn krut_three_motor_anchors() {
        let r = krut_point_robot(3, 1000.0, 30.0);
        let c = r.cables()[2].frame;
        assert!((c.x).abs() < 1e-9 && (c.y + 1000.0).abs() < 1e-9);
    }

    #[test]
    fn thesis_platforms() {
        assert_eq!(
            thesis_three_cable().cables()[2].platform,
            Vector3::new(0.0, -0.1, 0.0)
        );
        assert_eq!(
            thesis_four_cable().cables()[3].frame,
            Vector3::new(1.0, -0.5, 0.0)
        );
    }
}

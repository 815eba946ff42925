//! Proptest strategies shared by every crate of the stack (feature `proptest`), in the manner of
//! nalgebra's `proptest-support`: robots with frame anchors on a shell of radius 1.5–3 around the
//! origin, platform attachments within 0.25, and poses within 0.5 of the origin and 0.3 rad of
//! the reference orientation, so that no cable is degenerate.

use crate::{Cable, MotionPattern, Pose, Robot};
use nalgebra::Vector3;
use proptest::prelude::*;
use std::ops::RangeInclusive;

/// Any motion pattern.
pub fn arb_motion() -> impl Strategy<Value = MotionPattern> {
    prop::sample::select(MotionPattern::ALL.to_vec())
}

fn arb_direction(dim: usize) -> impl Strategy<Value = Vector3<f64>> {
    (0.0..std::f64::consts::TAU, -1.0f64..1.0).prop_map(move |(theta, z)| {
        if dim == 2 {
            Vector3::new(theta.cos(), theta.sin(), 0.0)
        } else {
            let r = (1.0 - z * z).sqrt();
            Vector3::new(r * theta.cos(), r * theta.sin(), z)
        }
    })
}

fn arb_cable(motion: MotionPattern) -> impl Strategy<Value = Cable> {
    let dim = motion.space_dim();
    (
        arb_direction(dim),
        1.5f64..3.0,
        arb_direction(dim),
        0.0f64..0.25,
    )
        .prop_map(move |(d, r, e, s)| Cable {
            frame: d * r,
            platform: if motion.has_orientation() {
                e * s
            } else {
                Vector3::zeros()
            },
            pulley: None,
        })
}

/// A robot of the given motion pattern with a cable count in `cables`.
pub fn arb_robot(
    motion: MotionPattern,
    cables: RangeInclusive<usize>,
) -> impl Strategy<Value = Robot> {
    prop::collection::vec(arb_cable(motion), cables)
        .prop_map(move |c| Robot::new(motion, c).expect("strategy builds valid robots"))
}

/// A pose of the given motion pattern near the origin.
pub fn arb_pose(motion: MotionPattern) -> impl Strategy<Value = Pose> {
    prop::collection::vec(-0.5f64..0.5, 3)
        .prop_flat_map(move |p| (Just(p), prop::collection::vec(-0.3f64..0.3, 3)))
        .prop_map(move |(p, a)| {
            let q: Vec<f64> = match motion {
                MotionPattern::Point2 => vec![p[0], p[1]],
                MotionPattern::Planar => vec![p[0], p[1], a[0]],
                MotionPattern::Point3 => p.clone(),
                MotionPattern::Spatial => vec![p[0], p[1], p[2], a[0], a[1], a[2]],
            };
            Pose::from_coordinates(motion, &q).expect("finite coordinates")
        })
}

/// A robot together with a pose of the same motion pattern, any pattern.
pub fn arb_robot_and_pose(
    cables_above_dof: RangeInclusive<usize>,
) -> impl Strategy<Value = (Robot, Pose)> {
    arb_motion().prop_flat_map(move |m| {
        let (lo, hi) = (
            m.dof() + cables_above_dof.start(),
            m.dof() + cables_above_dof.end(),
        );
        (arb_robot(m, lo..=hi), arb_pose(m))
    })
}

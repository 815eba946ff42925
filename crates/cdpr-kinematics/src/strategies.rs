//! Proptest strategies shared by every crate of the stack (feature `proptest`), in the manner of
//! nalgebra's `proptest-support`: robots with frame anchors on a shell of radius 1.5–3 around the
//! origin, platform attachments within 0.25, and poses within 0.5 of the origin and 0.3 rad of
//! the reference orientation, so that no cable is degenerate. Pulley robots add a swivel pulley of
//! radius 0.02–0.2 with a random axis (in the plane for 2-D patterns; at least 0.7 rad from the
//! line towards the origin) and a random zero of the swivel angle to every cable: attachments
//! stay well outside every pulley and off every swivel axis.

use crate::{Cable, MotionPattern, Pose, Pulley, Robot};
use nalgebra::{Rotation3, Vector3};
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

/// A pulley for a cable whose frame anchor is `frame`: its axis makes an angle of 0.7 to π − 0.7
/// rad with the direction from the anchor to the origin, so that no attachment near the origin
/// comes close to the swivel axis.
fn arb_pulley(dim: usize, frame: Vector3<f64>) -> impl Strategy<Value = Pulley> {
    (
        arb_direction(dim),
        0.7f64..std::f64::consts::PI - 0.7,
        0.02f64..0.2,
        0.0..std::f64::consts::TAU,
    )
        .prop_map(move |(e, angle, radius, zero)| {
            let inward = -frame.normalize();
            let side = if dim == 2 {
                Vector3::new(-inward.y, inward.x, 0.0) * e.x.signum()
            } else {
                let side = e - inward * inward.dot(&e);
                if side.norm() > 1e-3 {
                    side.normalize()
                } else {
                    inward.cross(&Vector3::x()).normalize()
                }
            };
            let axis = inward * angle.cos() + side * angle.sin();
            let mut p = Pulley::from_axis(radius, axis);
            p.orientation *= Rotation3::from_axis_angle(&Vector3::z_axis(), zero).matrix();
            p
        })
}

/// A robot of the given motion pattern with a cable count in `cables`, every cable over a swivel
/// pulley.
pub fn arb_pulley_robot(
    motion: MotionPattern,
    cables: RangeInclusive<usize>,
) -> impl Strategy<Value = Robot> {
    let dim = motion.space_dim();
    let cable = arb_cable(motion).prop_flat_map(move |c| (Just(c), arb_pulley(dim, c.frame)));
    prop::collection::vec(cable, cables).prop_map(move |c| {
        let cables = c
            .into_iter()
            .map(|(cable, pulley)| Cable {
                pulley: Some(pulley),
                ..cable
            })
            .collect();
        Robot::new(motion, cables).expect("strategy builds valid robots")
    })
}

/// A pulley robot together with a pose of the same motion pattern, any pattern.
pub fn arb_pulley_robot_and_pose(
    cables_above_dof: RangeInclusive<usize>,
) -> impl Strategy<Value = (Robot, Pose)> {
    arb_motion().prop_flat_map(move |m| {
        let (lo, hi) = (
            m.dof() + cables_above_dof.start(),
            m.dof() + cables_above_dof.end(),
        );
        (arb_pulley_robot(m, lo..=hi), arb_pose(m))
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

//! # Design parametrisation of the planar frame (thesis §6.6.1)
//!
//! The frame anchors **c**^i of the planar manipulator lie on the 2 × 2 square frame centred at the
//! origin. Anchor i sits where the ray from the origin at polar angle β^i meets the frame, so the
//! design vector is **d** = [β^1, …, β^n] (rad). The only design constraint is a lower limit
//! β_min on the angular separation of consecutive anchors, measured the short way round the
//! frame, including the pair (n, 1) (eq. (6.29)).
//!
//! ## References
//! - The thesis chapter on planar tendon-driven manipulators (chapter 6, "The planar tendon-driven parallel manipulator"), §6.2 and
//!   §6.6.1, eq. (6.29); Tables 6.1, 6.2.

use super::SynthesisError;
use cdpr_kinematics::{Cable, MotionPattern, Robot};
use nalgebra::Vector3;
use std::f64::consts::{PI, TAU};

/// Half the side of the square frame (the frame is [−1, 1]², thesis §6.2).
pub const FRAME_HALF_SIDE: f64 = 1.0;

/// Frame anchor **c** = ρ(β) [cos β, sin β] with ρ(β) = 1 / max(|cos β|, |sin β|): the point where
/// the ray at polar angle β (rad) meets the boundary of the square frame [−1, 1]².
pub fn frame_anchor(beta: f64) -> [f64; 2] {
    let (s, c) = beta.sin_cos();
    let rho = FRAME_HALF_SIDE / c.abs().max(s.abs());
    [rho * c, rho * s]
}

/// The same design shifted by a whole number of turns, 2π·round(β₁ / 2π), so that β₁ ∈ [−π, π]
/// and the other angles keep their offsets from it (the cyclic order reads as written). Every
/// anchor depends on its angle modulo 2π only; the optimisers, whose steps may carry the angles
/// past 2π (the global stage reached [5.9570, 8.6478, 12.0656] rad), are left untouched, and
/// reports print this form (thesis Table 6.10 writes d* = [−0.3146, 2.379, 5.794]).
pub fn in_first_turn(betas: &[f64]) -> Vec<f64> {
    let turns = betas.first().map_or(0.0, |b| (b / TAU).round());
    betas.iter().map(|b| b - turns * TAU).collect()
}

/// Platform attachments **ā**^i of Table 6.1 (platform coordinates, z = 0) for the 3- or 4-cable
/// manipulator of the thesis chapter on planar tendon-driven manipulators; `None` for other cable counts.
pub fn thesis_platform(cables: usize) -> Option<Vec<[f64; 2]>> {
    let s = 0.1 / 2f64.sqrt();
    match cables {
        3 => Some(vec![[s, s], [-s, s], [0.0, -0.1]]),
        4 => Some(vec![[s, s], [-s, s], [-0.1, -0.1], [0.1, -0.1]]),
        _ => None,
    }
}

/// The planar robot with frame anchors at the angles `betas` (rad) and the given platform
/// attachments (one per angle, in the same order).
///
/// Errors: empty or non-finite design, or a platform of a different length.
pub fn robot_from_design(betas: &[f64], platform: &[[f64; 2]]) -> Result<Robot, SynthesisError> {
    check_design(betas)?;
    if platform.len() != betas.len() {
        return Err(SynthesisError::DimensionMismatch {
            expected: platform.len(),
            found: betas.len(),
        });
    }
    let cables = betas
        .iter()
        .zip(platform)
        .map(|(&b, a)| {
            let c = frame_anchor(b);
            Cable {
                frame: Vector3::new(c[0], c[1], 0.0),
                platform: Vector3::new(a[0], a[1], 0.0),
                pulley: None,
            }
        })
        .collect();
    Ok(Robot::new(MotionPattern::Planar, cables)?)
}

/// Errors on an empty design or a non-finite angle.
pub fn check_design(betas: &[f64]) -> Result<(), SynthesisError> {
    if betas.is_empty() {
        return Err(SynthesisError::EmptyDesign);
    }
    if let Some((index, &value)) = betas.iter().enumerate().find(|(_, b)| !b.is_finite()) {
        return Err(SynthesisError::NotFinite { index, value });
    }
    Ok(())
}

/// Angular separation of two anchors measured the short way round: in [0, π].
pub fn separation(beta_a: f64, beta_b: f64) -> f64 {
    let d = (beta_b - beta_a).rem_euclid(TAU);
    d.min(TAU - d)
}

/// Index pairs constrained by eq. (6.29): (i, i+1) for i = 1 … n−1 and (n, 1); for n = 2 the single
/// pair (1, 2); none for n = 1.
pub fn constrained_pairs(n: usize) -> impl Iterator<Item = (usize, usize)> {
    let wrap = if n > 2 { Some((n - 1, 0)) } else { None };
    (0..n.saturating_sub(1)).map(|i| (i, i + 1)).chain(wrap)
}

/// The separations of all pairs of eq. (6.29), in [`constrained_pairs`] order.
pub fn separations(betas: &[f64]) -> Vec<f64> {
    constrained_pairs(betas.len())
        .map(|(i, j)| separation(betas[i], betas[j]))
        .collect()
}

/// Total violation Σ max(0, β_min − s_ij) of eq. (6.29) (rad); zero for a feasible design.
pub fn separation_violation(betas: &[f64], min_separation: f64) -> f64 {
    constrained_pairs(betas.len())
        .map(|(i, j)| (min_separation - separation(betas[i], betas[j])).max(0.0))
        .sum()
}

/// The cyclic order of the anchors around the frame: the cable indices sorted by β mod 2π
/// (ties by index), rotated so that cable 0 comes first. Two designs with the same cyclic order
/// have the same cable topology: cable i runs to ā^i from between the same two neighbours.
pub fn cyclic_order(betas: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..betas.len()).collect();
    order.sort_by(|&a, &b| {
        let (x, y) = (betas[a].rem_euclid(TAU), betas[b].rem_euclid(TAU));
        x.total_cmp(&y).then(a.cmp(&b))
    });
    if let Some(first) = order.iter().position(|&i| i == 0) {
        order.rotate_left(first);
    }
    order
}

/// Whether every cable leaves its platform attachment away from the platform at the reference
/// pose (platform origin at the frame centre, φ = 0): the direction c^i − ā^i must not point into
/// the convex polygon of the attachments `platform` (one per angle of `betas`), i.e. not strictly
/// inside the angle that the polygon makes at ā^i. A cable that does passes through the platform
/// body, which the line model of the thesis chapter does not see: the published optima all
/// satisfy this, and so do the designs of the global stage ([`super::multi_start`]).
/// Attachments inside the polygon (not vertices) and degenerate platforms are not checked.
pub fn cables_clear_platform(betas: &[f64], platform: &[[f64; 2]]) -> bool {
    let n = platform.len();
    if n < 3 || betas.len() != n {
        return true;
    }
    // The attachments counter-clockwise around their centroid.
    let cx = platform.iter().map(|p| p[0]).sum::<f64>() / n as f64;
    let cy = platform.iter().map(|p| p[1]).sum::<f64>() / n as f64;
    let mut ring: Vec<usize> = (0..n).collect();
    ring.sort_by(|&a, &b| {
        let t = |p: [f64; 2]| (p[1] - cy).atan2(p[0] - cx);
        t(platform[a]).total_cmp(&t(platform[b]))
    });
    let cross = |u: [f64; 2], v: [f64; 2]| u[0] * v[1] - u[1] * v[0];
    let sub = |u: [f64; 2], v: [f64; 2]| [u[0] - v[0], u[1] - v[1]];
    (0..n).all(|k| {
        let i = ring[k];
        let v = platform[i];
        let next = sub(platform[ring[(k + 1) % n]], v);
        let prev = sub(platform[ring[(k + n - 1) % n]], v);
        if cross(next, prev) <= 0.0 {
            return true; // a reflex or flat corner: not a vertex of the convex polygon
        }
        let d = sub(frame_anchor(betas[i]), v);
        !(cross(next, d) > 0.0 && cross(d, prev) > 0.0)
    })
}

/// Whether two designs place the anchors in the same [`cyclic_order`].
///
/// No continuous path that keeps eq. (6.29) satisfied changes the cyclic order (an anchor would
/// have to pass one of its two constrained neighbours), so the published optima all keep the
/// order of their starts. A jump that changes it makes cables cross, and eq. (6.29) then
/// constrains pairs that are no longer neighbours while the new neighbours may coincide: the
/// optimisers reject such designs.
pub fn same_cyclic_order(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && cyclic_order(a) == cyclic_order(b)
}

/// One constraint of eq. (6.29) linearised at a design: s_ij(d + δ) ≈ value + δ_j σ − δ_i σ,
/// exact while the short way round does not switch sides (σ = +1 if the short way from β^i to
/// β^j is counter-clockwise, −1 otherwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LinearSeparation {
    pub i: usize,
    pub j: usize,
    pub value: f64,
    pub sign: f64,
}

/// The constraints of eq. (6.29) linearised at `betas` (the separation is piecewise linear in β, so
/// the linearisation is exact in a neighbourhood of any design without coincident or opposite
/// anchors).
pub(crate) fn linear_separations(betas: &[f64]) -> Vec<LinearSeparation> {
    constrained_pairs(betas.len())
        .map(|(i, j)| {
            let d = (betas[j] - betas[i]).rem_euclid(TAU);
            let (value, sign) = if d <= PI { (d, 1.0) } else { (TAU - d, -1.0) };
            LinearSeparation { i, j, value, sign }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;
    use proptest::prelude::*;

    #[test]
    fn designs_are_reported_in_the_first_turn() {
        let d = in_first_turn(&[5.9570, 8.6478, 12.0656]);
        let e = [5.9570 - TAU, 8.6478 - TAU, 12.0656 - TAU];
        for (a, b) in d.iter().zip(e) {
            assert_abs_diff_eq!(*a, b, epsilon = 1e-15);
        }
        assert_eq!(
            in_first_turn(&[-0.3146, 2.379, 5.794]),
            [-0.3146, 2.379, 5.794]
        );
        assert_eq!(in_first_turn(&[-7.0])[0], -7.0 + TAU);
        assert!(in_first_turn(&[]).is_empty());
        // The same anchors.
        for (a, b) in d.iter().zip([5.9570, 8.6478, 12.0656]) {
            let (p, q) = (frame_anchor(*a), frame_anchor(b));
            assert_abs_diff_eq!(p[0], q[0], epsilon = 1e-12);
            assert_abs_diff_eq!(p[1], q[1], epsilon = 1e-12);
        }
    }

    #[test]
    fn anchors_of_hand_picked_angles() {
        let close = |b: f64, e: [f64; 2]| {
            let c = frame_anchor(b);
            assert_abs_diff_eq!(c[0], e[0], epsilon = 1e-12);
            assert_abs_diff_eq!(c[1], e[1], epsilon = 1e-12);
        };
        close(0.0, [1.0, 0.0]);
        close(PI / 4.0, [1.0, 1.0]);
        close(3.0 * PI / 2.0, [0.0, -1.0]);
        close(PI, [-1.0, 0.0]);
        close(-PI / 4.0, [1.0, -1.0]);
        // tan(π/6) = 1/√3 on the right edge.
        close(PI / 6.0, [1.0, 1.0 / 3f64.sqrt()]);
        // Table 6.2's 3-cable frame: c¹ = [1, 1], c² = [−1, 1], c³ = [0, −1].
        close(3.0 * PI / 4.0, [-1.0, 1.0]);
    }

    #[test]
    fn separation_short_way_round() {
        assert_abs_diff_eq!(separation(0.1, 0.3), 0.2, epsilon = 1e-12);
        assert_abs_diff_eq!(separation(0.3, 0.1), 0.2, epsilon = 1e-12);
        assert_abs_diff_eq!(separation(0.1, TAU - 0.1), 0.2, epsilon = 1e-12);
        assert_abs_diff_eq!(separation(-0.3146, 5.794), 0.1740, epsilon = 1e-3);
        assert_abs_diff_eq!(separation(0.0, PI), PI, epsilon = 1e-12);
        // Table 6.5 run 1 optimum: 3.605 − 3.430 = 0.175 ≥ β_min = π/18 (to print precision).
        let d = [0.7676, 3.430, 3.605];
        let s = separations(&d);
        assert_eq!(s.len(), 3);
        assert_abs_diff_eq!(s[1], 0.175, epsilon = 1e-9);
        // Pair (3, 1): 3.605 − 0.7676 = 2.8374 < π, so the short way is the direct one.
        assert_abs_diff_eq!(s[2], 2.8374, epsilon = 1e-9);
        assert_eq!(separation_violation(&d, 0.17), 0.0);
        assert_abs_diff_eq!(separation_violation(&d, 0.2), 0.025, epsilon = 1e-9);
    }

    #[test]
    fn constrained_pairs_match_eq_6_29() {
        assert_eq!(
            constrained_pairs(4).collect::<Vec<_>>(),
            vec![(0, 1), (1, 2), (2, 3), (3, 0)]
        );
        assert_eq!(constrained_pairs(2).collect::<Vec<_>>(), vec![(0, 1)]);
        assert_eq!(constrained_pairs(1).count(), 0);
    }

    #[test]
    fn cyclic_order_of_hand_picked_designs() {
        // Table 6.5 run 1 optimum: increasing angles, order 0, 1, 2.
        assert_eq!(cyclic_order(&[0.7676, 3.430, 3.605]), vec![0, 1, 2]);
        // Anchors 2 and 3 swapped: cable 3 now lies between cables 1 and 2.
        assert_eq!(cyclic_order(&[0.1598, 3.698, 2.3573]), vec![0, 2, 1]);
        // Angles are taken mod 2π: −0.3 is 5.98, after 3.0.
        assert_eq!(cyclic_order(&[1.0, 3.0, -0.3]), vec![0, 1, 2]);
        assert_eq!(cyclic_order(&[-0.3, 1.0, 3.0]), vec![0, 1, 2]);
        // A rigid rotation past 2π keeps the order.
        assert!(same_cyclic_order(&[0.1, 2.0, 4.0], &[2.5, 4.4, 6.4]));
        assert!(!same_cyclic_order(&[0.1, 2.0, 4.0], &[0.1, 4.0, 2.0]));
        // Table 6.8 run 1 start vs an optimum with β⁴ < β³.
        assert!(!same_cyclic_order(
            &[0.8205, 2.338, 4.595, 4.769],
            &[0.8205, 2.338, 4.769, 4.595]
        ));
        assert!(!same_cyclic_order(&[0.1, 2.0], &[0.1, 2.0, 3.0]));
        assert!(cyclic_order(&[]).is_empty());
    }

    #[test]
    fn cables_clear_the_platform_at_the_published_optimum_but_not_when_rotated() {
        let p = thesis_platform(3).unwrap();
        // Table 6.5 run 3 optimum: cable 1 runs up-right from the upper-right attachment.
        assert!(cables_clear_platform(&[0.7645, 3.477, 3.651], &p));
        // The same anchors turned by π: cable 1 runs down-left from ā¹ across the platform.
        assert!(!cables_clear_platform(&[3.9065, 6.8958, 7.0704], &p));
        // Table 6.10 run 1 optimum (4 cables).
        let p4 = thesis_platform(4).unwrap();
        assert!(cables_clear_platform(&[0.7572, 2.922, 3.097, 5.449], &p4));
        // Fewer than 3 attachments: nothing to enter.
        assert!(cables_clear_platform(
            &[0.0, 1.0],
            &[[0.1, 0.0], [-0.1, 0.0]]
        ));
    }

    #[test]
    fn robot_from_design_validates() {
        let p = thesis_platform(3).unwrap();
        assert!(matches!(
            robot_from_design(&[], &p),
            Err(SynthesisError::EmptyDesign)
        ));
        assert!(matches!(
            robot_from_design(&[0.0, f64::NAN, 1.0], &p),
            Err(SynthesisError::NotFinite { index: 1, .. })
        ));
        assert!(matches!(
            robot_from_design(&[0.0, 1.0], &p),
            Err(SynthesisError::DimensionMismatch { .. })
        ));
        let r = robot_from_design(&[PI / 4.0, 3.0 * PI / 4.0, 1.5 * PI], &p).unwrap();
        assert_abs_diff_eq!(r.cables()[2].frame.y, -1.0, epsilon = 1e-12);
        assert_abs_diff_eq!(
            r.cables()[1].platform.x,
            -0.1 / 2f64.sqrt(),
            epsilon = 1e-15
        );
        assert!(thesis_platform(5).is_none());
    }

    proptest! {
        #[test]
        fn anchors_lie_on_the_frame_at_the_right_angle(beta in -10.0..10.0f64) {
            let c = frame_anchor(beta);
            prop_assert!((c[0].abs().max(c[1].abs()) - 1.0).abs() < 1e-12);
            // Same direction as [cos β, sin β].
            let (s, co) = beta.sin_cos();
            prop_assert!((c[0] * s - c[1] * co).abs() < 1e-12);
            prop_assert!(c[0] * co + c[1] * s > 0.0);
        }

        #[test]
        fn small_feasible_steps_keep_the_cyclic_order(
            first in -7.0..7.0f64,
            gaps in proptest::collection::vec(0.2..2.0f64, 1..5),
            step in proptest::collection::vec(-0.09..0.09f64, 6),
        ) {
            // Anchors ≥ 0.2 apart (the wrap gap too) moved by < 0.1 each cannot pass each other.
            let mut d = vec![first];
            for g in &gaps { d.push(d.last().unwrap() + g); }
            prop_assume!(TAU - (d[d.len() - 1] - d[0]) >= 0.2);
            let moved: Vec<f64> = d.iter().zip(&step).map(|(b, s)| b + s).collect();
            prop_assert!(same_cyclic_order(&d, &moved));
            // Order is invariant under a rigid rotation by any angle.
            let rotated: Vec<f64> = d.iter().map(|b| b + 10.0 * step[0]).collect();
            prop_assert!(same_cyclic_order(&d, &rotated));
        }

        #[test]
        fn linearisation_is_exact_nearby(
            betas in proptest::collection::vec(-7.0..7.0f64, 2..6),
            step in proptest::collection::vec(-1e-4..1e-4f64, 6),
        ) {
            let lin = linear_separations(&betas);
            let moved: Vec<f64> = betas.iter().zip(&step).map(|(b, s)| b + s).collect();
            let exact = separations(&moved);
            for (l, e) in lin.iter().zip(&exact) {
                // Skip pairs near 0 or π where the short way switches sides.
                prop_assume!(l.value > 1e-3 && l.value < PI - 1e-3);
                let approx = l.value + l.sign * (step[l.j] - step[l.i]);
                prop_assert!((approx - e).abs() < 1e-9);
            }
        }
    }
}

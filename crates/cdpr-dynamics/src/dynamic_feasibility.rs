//! # Dynamic feasibility (the dynamic feasible workspace criterion)
//!
//! A pose x moving with twist ẋ is dynamically feasible for the accelerations of a box
//! A = {ẍ : |ẍ_i| ≤ A_i} when every ẍ ∈ A is produced by tensions within bounds:
//! W t + w_ext + w_g = M ẍ + b. In the convention of the capacity margin (W t + w = 0 for every
//! w of a required set R) this is R = {w_ext + w_g − b − M ẍ : ẍ ∈ A}: the image of a box by a
//! linear map, a zonotope with centre c = w_ext + w_g − b and generators −A_i M e_i. Its
//! support function in the direction −n is h_R(−n) = −n·c + Σ_i A_i |(M n)_i| (M symmetric), so
//! the margin min_k (d_k − h_R(−n_k)) over the half-spaces n_k·w ≤ d_k of the available wrench
//! set (hyperplane shifting, `cdpr-polytope`) decides the whole box at once: feasible iff the
//! margin is ≥ 0. No linear program per vertex of the box (CASPR's approach) is needed.
//!
//! ## References
//! - Gagliardini, Gouttefarde & Caro 2016 (ARK), *Determination of a dynamic feasible workspace
//!   for cable-driven parallel robots*: the required wrench set as a zonotope.
//! - Barrette & Gosselin 2005: the dynamic workspace of planar cable robots.
//! - Guay, Cardou, Cruz-Ruiz & Caro 2014: the capacity margin; Bouchard, Gosselin & Moore 2010:
//!   hyperplane shifting.

use crate::error::bad;
use crate::rigid_body::{embed, pattern_components};
use crate::{DynamicsError, RigidBody};
use cdpr_kinematics::{MotionPattern, Pose};
use cdpr_polytope::hyperplane_shifting::HyperplaneShifting;
use cdpr_tension::TensionBounds;
use nalgebra::{DMatrix, Vector6};

/// The dynamic-feasibility test of one robot: bounds, body, acceleration box, twist and load.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicFeasibility {
    motion: MotionPattern,
    engine: HyperplaneShifting,
    body: RigidBody,
    half_widths: [f64; 6],
    twist: Vector6<f64>,
    external: Vector6<f64>,
}

impl DynamicFeasibility {
    /// A test for `motion` robots with `bounds`: `acceleration_box` the half-widths A_i
    /// (DOF numbers, m/s² and rad/s², ≥ 0, centred on 0), `velocity` the twist ẋ (DOF numbers,
    /// m/s and rad/s) and `external` a constant w_ext (DOF numbers, N and N·m), on top of the
    /// body's weight.
    pub fn new(
        motion: MotionPattern,
        bounds: &TensionBounds,
        body: RigidBody,
        acceleration_box: &[f64],
        velocity: &[f64],
        external: &[f64],
    ) -> Result<Self, DynamicsError> {
        let dof = motion.dof();
        for (what, v) in [
            ("acceleration box", acceleration_box),
            ("velocity", velocity),
            ("external wrench", external),
        ] {
            if v.len() != dof {
                return Err(DynamicsError::DimensionMismatch {
                    what,
                    expected: dof,
                    found: v.len(),
                });
            }
            if let Some((i, &x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(bad(format!("{what}[{i}]"), x, "must be finite"));
            }
        }
        if let Some((i, &a)) = acceleration_box.iter().enumerate().find(|(_, a)| **a < 0.0) {
            return Err(bad(
                format!("acceleration-box[{i}]"),
                a,
                "half-widths must be ≥ 0",
            ));
        }
        let engine = HyperplaneShifting::new(dof, bounds).map_err(|e| {
            bad(
                "tension bounds",
                f64::NAN,
                format!("hyperplane shifting refuses them: {e}"),
            )
        })?;
        let mut half_widths = [0.0; 6];
        half_widths[..dof].copy_from_slice(acceleration_box);
        Ok(Self {
            motion,
            engine,
            body,
            half_widths,
            twist: embed(motion, velocity),
            external: embed(motion, external),
        })
    }

    /// The margin min_k (d_k − h_R(−n_k)) at `pose` whose wrench matrix is `w` (N or N·m; +∞ if
    /// the available wrench set has no facet): ≥ 0 iff every acceleration of the box is
    /// feasible there.
    pub fn margin(&self, pose: &Pose, w: &DMatrix<f64>) -> Result<f64, DynamicsError> {
        let keep = pattern_components(self.motion);
        let dof = keep.len();
        let r = pose.rotation.matrix();
        let (m6, b6) = self.body.pattern_terms(self.motion, r, &self.twist);
        let c6 = self.external + self.body.gravity_wrench6(r) - b6;
        let mut c = [0.0; 6];
        let mut m = [[0.0; 6]; 6];
        for (i, &ki) in keep.iter().enumerate() {
            c[i] = c6[ki];
            for (j, &kj) in keep.iter().enumerate() {
                m[i][j] = m6[(ki, kj)];
            }
        }
        let a = &self.half_widths;
        let mut best = f64::INFINITY;
        self.engine
            .for_each_halfspace(w, |n, d| {
                let mut support = 0.0;
                for i in 0..dof {
                    support -= n[i] * c[i];
                    let mn: f64 = (0..dof).map(|j| m[i][j] * n[j]).sum();
                    support += a[i] * mn.abs();
                }
                best = best.min(d - support);
            })
            .map_err(|e| bad("wrench matrix", f64::NAN, e.to_string()))?;
        if best.is_nan() {
            return Err(bad("margin", best, "overflow"));
        }
        Ok(best)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdpr_kinematics::{Cable, Robot};
    use cdpr_wrench::Platform;
    use nalgebra::{Vector2, Vector3};

    /// The closed form: a point mass on two cables to (0, h) and (d, h) under gravity
    /// g (−y), tensions t ≥ 0 unbounded above, is dynamically feasible for an acceleration a
    /// iff 0 ≤ x + (h − y) a_x / (g + a_y) ≤ d (the line through the platform along the
    /// required force m (a − g) meets the ceiling between the anchors). A box is feasible iff
    /// its four corners are (the feasible accelerations form a convex cone). Every grid pose
    /// and box agrees with it, poses within 10⁻⁹ of the boundary left out.
    #[test]
    fn point_mass_on_two_cables_follows_the_closed_form() {
        let (d, h, g) = (2.0, 1.5, 9.81);
        let robot = Robot::new(
            MotionPattern::Point2,
            vec![
                Cable::point2(Vector2::new(0.0, h)),
                Cable::point2(Vector2::new(d, h)),
            ],
        )
        .unwrap();
        let body = RigidBody::point_mass(&Platform {
            mass: 3.0,
            centre_of_mass: Vector3::zeros(),
            gravity: Vector3::new(0.0, -g, 0.0),
        })
        .unwrap();
        let bounds = TensionBounds::uniform(2, 0.0, f64::INFINITY).unwrap();
        let (mut feasible, mut infeasible) = (0, 0);
        for (ax, ay) in [(0.0, 0.0), (2.0, 1.0), (4.0, 3.0), (1.0, 5.0), (6.0, 2.0)] {
            let test = DynamicFeasibility::new(
                MotionPattern::Point2,
                &bounds,
                body,
                &[ax, ay],
                &[0.0, 0.0],
                &[0.0, 0.0],
            )
            .unwrap();
            for i in 0..=40 {
                for j in 0..=40 {
                    let (x, y) = (-0.5 + 3.0 * i as f64 / 40.0, -1.0 + 2.4 * j as f64 / 40.0);
                    let pose = Pose::point(x, y, 0.0);
                    let w = robot.inverse_kinematics(&pose).unwrap().wrench_matrix();
                    let margin = test.margin(&pose, &w).unwrap();
                    let mut slack = f64::INFINITY;
                    for (sx, sy) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
                        let (cx, cy) = (sx * ax, sy * ay);
                        let xi = x + (h - y) * cx / (g + cy);
                        slack = slack.min(xi).min(d - xi);
                    }
                    if slack.abs() < 1e-9 {
                        continue;
                    }
                    assert_eq!(
                        margin >= 0.0,
                        slack > 0.0,
                        "({x}, {y}), box ({ax}, {ay}): margin {margin}, closed-form slack {slack}"
                    );
                    if slack > 0.0 {
                        feasible += 1;
                    } else {
                        infeasible += 1;
                    }
                }
            }
        }
        assert!(
            feasible > 500 && infeasible > 500,
            "{feasible} / {infeasible}"
        );
    }

    #[test]
    fn bad_input_names_its_key() {
        let body = RigidBody::point_mass(&Platform {
            mass: 1.0,
            ..Platform::default()
        })
        .unwrap();
        let bounds = TensionBounds::uniform(2, 0.0, 10.0).unwrap();
        let e = DynamicFeasibility::new(
            MotionPattern::Point2,
            &bounds,
            body,
            &[-1.0, 0.0],
            &[0.0, 0.0],
            &[0.0, 0.0],
        );
        assert!(
            matches!(e, Err(DynamicsError::BadSetting { key, .. }) if key == "acceleration-box[0]")
        );
        assert!(
            DynamicFeasibility::new(
                MotionPattern::Point2,
                &bounds,
                body,
                &[1.0],
                &[0.0, 0.0],
                &[0.0, 0.0]
            )
            .is_err()
        );
    }
}

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
    tmin: Vec<f64>,
    tmax: Vec<f64>,
}

/// The pose-dependent terms of the test in pattern components: the centre c of the required
/// set, the mass matrix M and their dimension.
struct Terms {
    dof: usize,
    c: [f64; 6],
    m: [[f64; 6]; 6],
}

/// Cables handled by the quick feasibility test (beyond, the margin decides).
const MAX_CABLES: usize = 16;

/// Alternating projections of the quick feasibility test.
const PROJECTIONS: usize = 8;

/// Binding normals kept per thread for the quick infeasibility test.
const NORMALS: usize = 4;

/// Recent binding normals with their dimension, most recent first.
type Normals = [Option<(usize, [f64; 6])>; NORMALS];

thread_local! {
    /// The normals of the binding half-spaces of the last infeasible poses tested on this
    /// thread, most recent first (any unit normal proves infeasibility when its margin is
    /// negative: hints, not results), with their dimension.
    static LAST_NORMALS: std::cell::Cell<Normals> = const { std::cell::Cell::new([None; NORMALS]) };
}

/// Margins and tension slacks closer to zero than this, relative to the problem's scale, are
/// left to the full enumeration (the quick tests decide only clear cases).
const QUICK_TOLERANCE: f64 = 1e-9;

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
            tmin: bounds.min().as_slice().to_vec(),
            tmax: bounds.max().as_slice().to_vec(),
        })
    }

    /// c = w_ext + w_g − b and M at `pose`, in pattern components.
    fn terms(&self, pose: &Pose) -> Terms {
        let keep = pattern_components(self.motion);
        let r = pose.rotation.matrix();
        let (m6, b6) = self.body.pattern_terms(self.motion, r, &self.twist);
        let c6 = self.external + self.body.gravity_wrench6(r) - b6;
        let mut t = Terms {
            dof: keep.len(),
            c: [0.0; 6],
            m: [[0.0; 6]; 6],
        };
        for (i, &ki) in keep.iter().enumerate() {
            t.c[i] = c6[ki];
            for (j, &kj) in keep.iter().enumerate() {
                t.m[i][j] = m6[(ki, kj)];
            }
        }
        t
    }

    /// h_R(−n) = −n·c + Σ_i A_i |(M n)_i|.
    #[inline]
    fn support(&self, t: &Terms, n: &[f64]) -> f64 {
        let mut support = 0.0;
        for i in 0..t.dof {
            support -= n[i] * t.c[i];
            let mn: f64 = (0..t.dof).map(|j| t.m[i][j] * n[j]).sum();
            support += self.half_widths[i] * mn.abs();
        }
        support
    }

    /// min_k (d_k − h_R(−n_k)) and the normal n_k where it is reached.
    fn margin_and_normal(
        &self,
        t: &Terms,
        w: &DMatrix<f64>,
    ) -> Result<(f64, [f64; 6]), DynamicsError> {
        let mut best = f64::INFINITY;
        let mut normal = [0.0; 6];
        self.engine
            .for_each_halfspace(w, |n, d| {
                let m = d - self.support(t, n);
                if m < best {
                    best = m;
                    normal[..n.len()].copy_from_slice(n);
                }
            })
            .map_err(|e| bad("wrench matrix", f64::NAN, e.to_string()))?;
        if best.is_nan() {
            return Err(bad("margin", best, "overflow"));
        }
        Ok((best, normal))
    }

    /// The margin min_k (d_k − h_R(−n_k)) at `pose` whose wrench matrix is `w` (N or N·m; +∞ if
    /// the available wrench set has no facet): ≥ 0 iff every acceleration of the box is
    /// feasible there.
    pub fn margin(&self, pose: &Pose, w: &DMatrix<f64>) -> Result<f64, DynamicsError> {
        let t = self.terms(pose);
        Ok(self.margin_and_normal(&t, w)?.0)
    }

    /// Whether every acceleration of the box is feasible at `pose` (wrench matrix `w`):
    /// the verdict of [`DynamicFeasibility::margin`] ≥ 0, reached faster on clear cases.
    /// Two sufficient tests run before the enumeration of the available wrench set:
    /// - *infeasible* if the half-space n·w ≤ d(n) = Σ_j max(n·w_j t_min,j, n·w_j t_max,j) of
    ///   the last binding normal n found on this thread (any n bounds the available set) has a
    ///   clearly negative margin d(n) − h_R(−n);
    /// - *feasible* if the affine tensions t(ẍ) = t₀ + W⁺ M ẍ, with W t₀ = −c the point nearest
    ///   the middle of the bounds and W⁺ = Wᵀ(W Wᵀ)⁻¹, stay clearly within the bounds over the
    ///   whole box: t₀,j ∓ Σ_i A_i |(W⁺ M)_ji| (then W t(ẍ) + c − M ẍ = 0 for every ẍ).
    ///
    /// "Clearly" is beyond 10⁻⁹ of the problem's scale; everything else is decided by the
    /// margin, so the verdict is the margin's.
    pub fn is_feasible(&self, pose: &Pose, w: &DMatrix<f64>) -> Result<bool, DynamicsError> {
        let t = self.terms(pose);
        if w.nrows() == t.dof && w.ncols() == self.tmin.len() && w.iter().all(|x| x.is_finite()) {
            let mut normals = LAST_NORMALS.get();
            for k in 0..NORMALS {
                if let Some((dof, n)) = normals[k]
                    && dof == t.dof
                    && self.separates(&t, w, &n)
                {
                    normals[..=k].rotate_right(1);
                    LAST_NORMALS.set(normals);
                    return Ok(false);
                }
            }
            if self.affine_tensions_fit(&t, w) {
                return Ok(true);
            }
        }
        let (margin, normal) = self.margin_and_normal(&t, w)?;
        if margin < 0.0 {
            let mut normals = LAST_NORMALS.get();
            normals.rotate_right(1);
            normals[0] = Some((t.dof, normal));
            LAST_NORMALS.set(normals);
        }
        Ok(margin >= 0.0)
    }

    /// The half-space of normal `n` proves the box infeasible (margin clearly < 0).
    fn separates(&self, t: &Terms, w: &DMatrix<f64>, n: &[f64; 6]) -> bool {
        let mut d = 0.0;
        let mut scale = 0.0f64;
        for (j, col) in w.column_iter().enumerate() {
            let nw: f64 = (0..t.dof).map(|i| n[i] * col[i]).sum();
            let (lo, hi) = (nw * self.tmin[j], nw * self.tmax[j]);
            d += lo.max(hi);
            scale = scale.max(lo.abs()).max(hi.abs());
        }
        let support = self.support(t, n);
        let scale = scale.max(support.abs()).max(1.0);
        d - support < -QUICK_TOLERANCE * scale
    }

    /// The affine tensions of [`DynamicFeasibility::is_feasible`] fit the bounds with a clear
    /// slack (false when W Wᵀ is not safely positive definite or a bound is infinite).
    fn affine_tensions_fit(&self, t: &Terms, w: &DMatrix<f64>) -> bool {
        let (dof, n) = (t.dof, w.ncols());
        if n > MAX_CABLES || self.tmax.iter().any(|x| !x.is_finite()) {
            return false;
        }
        // G = W Wᵀ and its Cholesky factor L (lower).
        let mut l = [[0.0f64; 6]; 6];
        for i in 0..dof {
            for k in 0..=i {
                let mut s = 0.0;
                for j in 0..n {
                    s += w[(i, j)] * w[(k, j)];
                }
                l[i][k] = s;
            }
        }
        let trace: f64 = (0..dof).map(|i| l[i][i]).sum();
        for i in 0..dof {
            for k in 0..=i {
                let dot: f64 = l[i][..k].iter().zip(&l[k][..k]).map(|(a, b)| a * b).sum();
                let s = l[i][k] - dot;
                if i == k {
                    if s.is_nan() || s <= 1e-8 * trace {
                        return false;
                    }
                    l[i][i] = s.sqrt();
                } else {
                    l[i][k] = s / l[k][k];
                }
            }
        }
        let solve = |b: &mut [f64; 6]| {
            for i in 0..dof {
                let mut s = b[i];
                for p in 0..i {
                    s -= l[i][p] * b[p];
                }
                b[i] = s / l[i][i];
            }
            for i in (0..dof).rev() {
                let mut s = b[i];
                for p in i + 1..dof {
                    s -= l[p][i] * b[p];
                }
                b[i] = s / l[i][i];
            }
        };
        // y = G⁻¹ (−c − W t_mid), X = G⁻¹ M (column by column).
        let mut y = [0.0f64; 6];
        for (i, yi) in y.iter_mut().enumerate().take(dof) {
            let wt: f64 = (0..n)
                .map(|j| w[(i, j)] * 0.5 * (self.tmin[j] + self.tmax[j]))
                .sum();
            *yi = -t.c[i] - wt;
        }
        solve(&mut y);
        let mut x = [[0.0f64; 6]; 6]; // x[col] = G⁻¹ M e_col
        for (col, xc) in x.iter_mut().enumerate().take(dof) {
            for (i, xi) in xc.iter_mut().enumerate().take(dof) {
                *xi = t.m[i][col];
            }
            solve(xc);
        }
        // Per cable the spread s_j = Σ_i A_i |(W⁺ M)_ji| and the box t₀ must lie in.
        let mut lo = [0.0f64; MAX_CABLES];
        let mut hi = [0.0f64; MAX_CABLES];
        let mut t0 = [0.0f64; MAX_CABLES];
        for j in 0..n {
            let wj = w.column(j);
            let mut spread = 0.0;
            for (col, xc) in x.iter().enumerate().take(dof) {
                let pm: f64 = (0..dof).map(|i| wj[i] * xc[i]).sum();
                spread += self.half_widths[col] * pm.abs();
            }
            let slack = QUICK_TOLERANCE * self.tmax[j].abs().max(self.tmin[j].abs()).max(1.0);
            (lo[j], hi[j]) = (self.tmin[j] + spread + slack, self.tmax[j] - spread - slack);
            if lo[j].is_nan() || hi[j].is_nan() || lo[j] > hi[j] {
                return false;
            }
            t0[j] =
                0.5 * (self.tmin[j] + self.tmax[j]) + (0..dof).map(|i| wj[i] * y[i]).sum::<f64>();
        }
        // t₀ starts at the point of W t = −c nearest the middle of the bounds; alternating
        // projections on the box [lo, hi] and back on the affine set (von Neumann) look for a
        // point of both. Every iterate is on the affine set when tested.
        for _ in 0..PROJECTIONS {
            if (0..n).all(|j| t0[j] >= lo[j] && t0[j] <= hi[j]) {
                return true;
            }
            for j in 0..n {
                t0[j] = t0[j].clamp(lo[j], hi[j]);
            }
            // t₀ −= Wᵀ G⁻¹ (W t₀ + c).
            let mut r = [0.0f64; 6];
            for (i, ri) in r.iter_mut().enumerate().take(dof) {
                *ri = t.c[i] + (0..n).map(|j| w[(i, j)] * t0[j]).sum::<f64>();
            }
            solve(&mut r);
            for (j, tj) in t0.iter_mut().enumerate().take(n) {
                *tj -= (0..dof).map(|i| w[(i, j)] * r[i]).sum::<f64>();
            }
        }
        (0..n).all(|j| t0[j] >= lo[j] && t0[j] <= hi[j])
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
                    assert_eq!(test.is_feasible(&pose, &w).unwrap(), margin >= 0.0);
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

    /// The quick tests of `is_feasible` (a cached separating normal, affine tensions) give the
    /// margin's verdict: the IPAnema-like robot on a 9³ grid over its frame, four boxes, two
    /// orientations and a twist; each quick test decides some poses, the margin the rest.
    #[test]
    fn is_feasible_is_the_margin_verdict() {
        use cdpr_kinematics::reference_robots::ipanema_like_8;
        let robot = ipanema_like_8();
        let body = RigidBody::new(
            &Platform {
                mass: 5.0,
                centre_of_mass: Vector3::new(0.02, 0.0, -0.01),
                gravity: cdpr_wrench::STANDARD_GRAVITY,
            },
            nalgebra::Matrix3::from_diagonal(&Vector3::new(0.0208, 0.0208, 0.0333)),
        )
        .unwrap();
        let bounds = TensionBounds::uniform(8, 10.0, 1000.0).unwrap();
        let (mut agree, mut feasible, mut infeasible) = (0, 0, 0);
        let mut quick = [0usize; 2];
        for (a, v) in [
            ([2.0, 2.0, 2.0, 5.0, 5.0, 5.0], [0.0; 6]),
            ([0.5, 0.5, 0.5, 1.0, 1.0, 1.0], [0.0; 6]),
            ([10.0, 10.0, 20.0, 30.0, 30.0, 30.0], [0.0; 6]),
            (
                [1.0, 3.0, 2.0, 2.0, 0.0, 4.0],
                [0.5, -0.3, 0.2, 1.0, 2.0, -1.5],
            ),
        ] {
            let test =
                DynamicFeasibility::new(MotionPattern::Spatial, &bounds, body, &a, &v, &[0.0; 6])
                    .unwrap();
            for tilt in [0.0, 0.15] {
                for k in 0..729 {
                    let (i, j, l) = (k % 9, (k / 9) % 9, k / 81);
                    let p = Vector3::new(
                        -1.9 + 3.8 * i as f64 / 8.0,
                        -1.4 + 2.8 * j as f64 / 8.0,
                        0.05 + 1.9 * l as f64 / 8.0,
                    );
                    let pose = Pose::spatial(p, tilt, -tilt, 0.5 * tilt);
                    let Ok(kin) = robot.inverse_kinematics(&pose) else {
                        continue;
                    };
                    let w = kin.wrench_matrix();
                    let t = test.terms(&pose);
                    let margin = test.margin(&pose, &w);
                    let separated = LAST_NORMALS
                        .get()
                        .iter()
                        .flatten()
                        .any(|(_, n)| test.separates(&t, &w, n));
                    let verdict = test.is_feasible(&pose, &w).unwrap_or(false);
                    assert_eq!(
                        verdict,
                        margin.as_ref().is_ok_and(|m| *m >= 0.0),
                        "{pose:?}: {margin:?}"
                    );
                    agree += 1;
                    if verdict {
                        feasible += 1;
                        quick[1] += test.affine_tensions_fit(&t, &w) as usize;
                    } else {
                        infeasible += 1;
                        quick[0] += separated as usize;
                    }
                }
            }
        }
        assert!(
            feasible > 500 && infeasible > 500,
            "{feasible} / {infeasible}"
        );
        assert!(quick[0] > 100 && quick[1] > 100, "{quick:?} of {agree}");
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

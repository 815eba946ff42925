//! # Rigid-body dynamics of the platform (Newton–Euler in twist coordinates)
//!
//! Twist coordinates ẋ = [v_P; ω]: v_P the velocity of the platform origin P, ω the angular
//! velocity, both in base axes. With c = R c̄ the centre of mass seen from P and
//! I_P = R I_G Rᵀ − m \[c\]×\[c\]× the inertia about P, the equations of motion read
//!
//! M(x) ẍ + b(x, ẋ) = W t + w_ext + w_g,
//!
//! ```text
//! M = [[m 1, −m [c]×], [m [c]×, I_P]],   b = [m ω × (ω × c); ω × (I_P ω)].
//! ```
//!
//! The planar pattern (x, y, φ) keeps the rows and columns (v_x, v_y, ω_z) of these; the point
//! patterns have M = m 1 and b = 0 (the mass sits on the point).
//!
//! CASPR's `SPATIAL_EULER_XYZ` joints use Euler rates φ̇ instead of ω: with R = R_x R_y R_z,
//! ω = H(φ) φ̇ ([`euler_rate_matrix`]) and ω̇ = H φ̈ + Ḣ φ̇ ([`twist_from_euler_rates`]).
//!
//! ## References
//! - Barrette & Gosselin 2005, J. Mech. Des. 127(2), §2: the Newton–Euler equations of the
//!   platform of a cable-driven robot.
//! - Gagliardini, Gouttefarde & Caro 2016 (ARK), eqs. (1)–(4): M, the bias term and the
//!   dynamic feasibility condition in twist coordinates.
//! - Featherstone 2008, *Rigid Body Dynamics Algorithms*, §2.12: the spatial inertia about a
//!   point other than the centre of mass.

use crate::DynamicsError;
use cdpr_kinematics::{MotionPattern, Pose};
use cdpr_wrench::Platform;
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// Mass properties of the platform: mass, centre of mass, inertia and gravity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// m (kg).
    pub mass: f64,
    /// c̄: the centre of mass in platform coordinates (m).
    pub centre_of_mass: Vector3<f64>,
    /// I_G: the inertia tensor about the centre of mass in platform axes (kg·m²).
    pub inertia: Matrix3<f64>,
    /// g in base coordinates (m/s²).
    pub gravity: Vector3<f64>,
}

/// Components of the 6-vector [v; ω] (or [f; m]) that a motion pattern keeps, in its order.
pub fn pattern_components(motion: MotionPattern) -> &'static [usize] {
    match motion {
        MotionPattern::Point2 => &[0, 1],
        MotionPattern::Planar => &[0, 1, 5],
        MotionPattern::Point3 => &[0, 1, 2],
        MotionPattern::Spatial => &[0, 1, 2, 3, 4, 5],
    }
}

/// [a]×, the cross-product matrix: [a]× b = a × b.
fn skew(a: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

impl RigidBody {
    /// A body from a [`Platform`] (mass, centre of mass, gravity) and I_G, checked: m finite
    /// and positive, I_G symmetric (to 10⁻⁹ of its largest entry) and positive definite.
    ///
    /// ```
    /// use cdpr_dynamics::RigidBody;
    /// use cdpr_wrench::Platform;
    /// use nalgebra::Matrix3;
    /// let p = Platform { mass: 2.0, ..Platform::default() };
    /// assert!(RigidBody::new(&p, Matrix3::from_diagonal_element(0.1)).is_ok());
    /// assert!(RigidBody::new(&p, Matrix3::from_diagonal_element(-0.1)).is_err());
    /// ```
    pub fn new(platform: &Platform, inertia: Matrix3<f64>) -> Result<Self, DynamicsError> {
        let body = Self::unchecked(platform, inertia);
        body.check_mass()?;
        let rows = [
            [inertia[(0, 0)], inertia[(0, 1)], inertia[(0, 2)]],
            [inertia[(1, 0)], inertia[(1, 1)], inertia[(1, 2)]],
            [inertia[(2, 0)], inertia[(2, 1)], inertia[(2, 2)]],
        ];
        let fail = |why| DynamicsError::InertiaNotPositiveDefinite { inertia: rows, why };
        if inertia.iter().any(|v| !v.is_finite()) {
            return Err(fail("an entry is not finite"));
        }
        let scale = inertia.amax();
        if (inertia - inertia.transpose()).amax() > 1e-9 * scale {
            return Err(fail("it is not symmetric"));
        }
        if scale == 0.0 || inertia.cholesky().is_none() {
            return Err(fail("an eigenvalue is not positive"));
        }
        Ok(body)
    }

    /// A point mass (no inertia): enough for the point patterns, whose M = m 1.
    pub fn point_mass(platform: &Platform) -> Result<Self, DynamicsError> {
        let body = Self::unchecked(platform, Matrix3::zeros());
        body.check_mass()?;
        Ok(body)
    }

    fn unchecked(platform: &Platform, inertia: Matrix3<f64>) -> Self {
        Self {
            mass: platform.mass,
            centre_of_mass: platform.centre_of_mass,
            inertia,
            gravity: platform.gravity,
        }
    }

    fn check_mass(&self) -> Result<(), DynamicsError> {
        if !(self.mass.is_finite() && self.mass > 0.0) {
            return Err(DynamicsError::BadMass { mass: self.mass });
        }
        Ok(())
    }

    /// The spatial M (6 × 6) and b (6) at orientation `rotation` and angular velocity ω (base
    /// axes), the module's equations (Gagliardini, Gouttefarde & Caro 2016, eq. (2)).
    pub fn spatial_terms(
        &self,
        rotation: &Matrix3<f64>,
        omega: &Vector3<f64>,
    ) -> (Matrix6<f64>, Vector6<f64>) {
        let m = self.mass;
        let c = rotation * self.centre_of_mass;
        let cx = skew(&c);
        let ip = rotation * self.inertia * rotation.transpose() - m * cx * cx;
        let mut mm = Matrix6::zeros();
        mm.fixed_view_mut::<3, 3>(0, 0).fill_diagonal(m);
        mm.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-m * cx));
        mm.fixed_view_mut::<3, 3>(3, 0).copy_from(&(m * cx));
        mm.fixed_view_mut::<3, 3>(3, 3).copy_from(&ip);
        let f = m * omega.cross(&omega.cross(&c));
        let t = omega.cross(&(ip * omega));
        (mm, Vector6::new(f.x, f.y, f.z, t.x, t.y, t.z))
    }

    /// M and b of a motion pattern, embedded in 6 × 6 / 6: the pattern's rows and columns
    /// ([`pattern_components`]) hold its M and b, the others are zero. The point patterns have
    /// M = m 1, b = 0.
    pub fn pattern_terms(
        &self,
        motion: MotionPattern,
        rotation: &Matrix3<f64>,
        twist6: &Vector6<f64>,
    ) -> (Matrix6<f64>, Vector6<f64>) {
        match motion {
            MotionPattern::Point2 | MotionPattern::Point3 => {
                let mut mm = Matrix6::zeros();
                for &i in pattern_components(motion) {
                    mm[(i, i)] = self.mass;
                }
                (mm, Vector6::zeros())
            }
            MotionPattern::Spatial => {
                self.spatial_terms(rotation, &twist6.fixed_rows::<3>(3).into_owned())
            }
            MotionPattern::Planar => {
                let omega = Vector3::new(0.0, 0.0, twist6[5]);
                let (m6, b6) = self.spatial_terms(rotation, &omega);
                let keep = pattern_components(motion);
                let mut mm = Matrix6::zeros();
                let mut b = Vector6::zeros();
                for &i in keep {
                    b[i] = b6[i];
                    for &j in keep {
                        mm[(i, j)] = m6[(i, j)];
                    }
                }
                (mm, b)
            }
        }
    }

    /// M(x) of a motion pattern (DOF × DOF, its coordinates' order), kg and kg·m.
    ///
    /// ```
    /// use cdpr_dynamics::RigidBody;
    /// use cdpr_kinematics::{MotionPattern, Pose};
    /// use cdpr_wrench::Platform;
    /// use nalgebra::{Matrix3, Vector3};
    /// let p = Platform { mass: 2.0, centre_of_mass: Vector3::new(0.1, 0.0, 0.0), ..Platform::default() };
    /// let body = RigidBody::new(&p, Matrix3::from_diagonal_element(0.01)).unwrap();
    /// let m = body.mass_matrix(MotionPattern::Planar, &Pose::planar(0.0, 0.0, 0.0));
    /// // I_P,zz = I_G,zz + m |c|² = 0.01 + 2 · 0.01; coupling m c_x = 0.2.
    /// assert!((m[(2, 2)] - 0.03).abs() < 1e-15 && (m[(1, 2)] - 0.2).abs() < 1e-15);
    /// ```
    pub fn mass_matrix(&self, motion: MotionPattern, pose: &Pose) -> nalgebra::DMatrix<f64> {
        let (m6, _) = self.pattern_terms(motion, pose.rotation.matrix(), &Vector6::zeros());
        let keep = pattern_components(motion);
        nalgebra::DMatrix::from_fn(keep.len(), keep.len(), |i, j| m6[(keep[i], keep[j])])
    }

    /// The inertial wrench M ẍ + b (N, N·m) of a motion pattern, at `pose` with twist ẋ
    /// (`velocity`) and its derivative ẍ (`acceleration`), DOF numbers each in the pattern's
    /// order. Written into `out` (length DOF).
    pub fn inertial_wrench(
        &self,
        motion: MotionPattern,
        pose: &Pose,
        velocity: &[f64],
        acceleration: &[f64],
        out: &mut [f64],
    ) {
        let v6 = embed(motion, velocity);
        let a6 = embed(motion, acceleration);
        let (m6, b6) = self.pattern_terms(motion, pose.rotation.matrix(), &v6);
        let w = m6 * a6 + b6;
        for (o, &i) in out.iter_mut().zip(pattern_components(motion)) {
            *o = w[i];
        }
    }

    /// The gravity wrench w_g = [m g; c × m g] about P in the pattern's components.
    pub fn gravity_wrench6(&self, rotation: &Matrix3<f64>) -> Vector6<f64> {
        let f = self.mass * self.gravity;
        let m = (rotation * self.centre_of_mass).cross(&f);
        Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z)
    }

    /// ½ ẋᵀ M ẋ: the kinetic energy (J) of a 6-D twist.
    pub fn kinetic_energy(&self, rotation: &Matrix3<f64>, twist6: &Vector6<f64>) -> f64 {
        let (m6, _) = self.spatial_terms(rotation, &twist6.fixed_rows::<3>(3).into_owned());
        0.5 * twist6.dot(&(m6 * twist6))
    }
}

/// The pattern's DOF numbers placed in a 6-vector (others zero).
pub fn embed(motion: MotionPattern, x: &[f64]) -> Vector6<f64> {
    let mut v = Vector6::zeros();
    for (&i, &xi) in pattern_components(motion).iter().zip(x) {
        v[i] = xi;
    }
    v
}

/// H(φ) of XYZ Euler angles φ = (r_x, r_y, r_z), R = R_x R_y R_z: ω = H φ̇ (base axes).
///
/// Columns: e_x, R_x e_y, R_x R_y e_z.
pub fn euler_rate_matrix(angles: &[f64; 3]) -> Matrix3<f64> {
    let (sa, ca) = angles[0].sin_cos();
    let (sb, cb) = angles[1].sin_cos();
    Matrix3::new(1.0, 0.0, sb, 0.0, ca, -sa * cb, 0.0, sa, ca * cb)
}

/// Ḣ(φ, φ̇), the time derivative of [`euler_rate_matrix`].
pub fn euler_rate_matrix_derivative(angles: &[f64; 3], rates: &[f64; 3]) -> Matrix3<f64> {
    let (sa, ca) = angles[0].sin_cos();
    let (sb, cb) = angles[1].sin_cos();
    let (da, db) = (rates[0], rates[1]);
    Matrix3::new(
        0.0,
        0.0,
        db * cb,
        0.0,
        -da * sa,
        -da * ca * cb + db * sa * sb,
        0.0,
        da * ca,
        -da * sa * cb - db * ca * sb,
    )
}

/// Spatial coordinates' rates (ẋ, ẏ, ż, φ̇) and accelerations → twist [v; ω] and its
/// derivative [v̇; ω̇], with ω = H φ̇ and ω̇ = H φ̈ + Ḣ φ̇ (CASPR's `SPATIAL_EULER_XYZ`).
pub fn twist_from_euler_rates(
    q: &[f64; 6],
    q_dot: &[f64; 6],
    q_ddot: &[f64; 6],
) -> (Vector6<f64>, Vector6<f64>) {
    let ang = [q[3], q[4], q[5]];
    let rate = [q_dot[3], q_dot[4], q_dot[5]];
    let h = euler_rate_matrix(&ang);
    let hd = euler_rate_matrix_derivative(&ang, &rate);
    let rv = Vector3::from(rate);
    let ra = Vector3::new(q_ddot[3], q_ddot[4], q_ddot[5]);
    let w = h * rv;
    let wd = h * ra + hd * rv;
    (
        Vector6::new(q_dot[0], q_dot[1], q_dot[2], w.x, w.y, w.z),
        Vector6::new(q_ddot[0], q_ddot[1], q_ddot[2], wd.x, wd.y, wd.z),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::Rotation3;

    fn body() -> RigidBody {
        let p = Platform {
            mass: 3.0,
            centre_of_mass: Vector3::new(0.05, -0.1, 0.2),
            ..Platform::default()
        };
        let i = Matrix3::new(0.3, 0.01, -0.02, 0.01, 0.2, 0.03, -0.02, 0.03, 0.1);
        RigidBody::new(&p, i).unwrap()
    }

    /// M ẍ + b equals the Newton–Euler equations written about the centre of mass G:
    /// f = m a_G with a_G = v̇_P + ω̇ × c + ω × (ω × c), and τ_P = I_G' ω̇ + ω × I_G' ω + c × f
    /// with I_G' = R I_G Rᵀ (independent derivation).
    #[test]
    fn newton_euler_identity_with_offset_centre_of_mass() {
        let b = body();
        let r = Rotation3::from_euler_angles(0.3, -0.5, 1.1);
        let rm = *r.matrix();
        let w = Vector3::new(0.7, -1.3, 0.4);
        let vdot = Vector3::new(0.2, 0.5, -1.0);
        let wdot = Vector3::new(-2.0, 0.3, 1.5);
        let c = rm * b.centre_of_mass;
        let ig = rm * b.inertia * rm.transpose();
        let a_g = vdot + wdot.cross(&c) + w.cross(&w.cross(&c));
        let f = b.mass * a_g;
        let tau = ig * wdot + w.cross(&(ig * w)) + c.cross(&f);
        let twist = Vector6::new(0.1, 0.2, 0.3, w.x, w.y, w.z);
        let acc = Vector6::new(vdot.x, vdot.y, vdot.z, wdot.x, wdot.y, wdot.z);
        let (m6, b6) = b.spatial_terms(&rm, &w);
        let got = m6 * acc + b6;
        for k in 0..3 {
            assert_relative_eq!(got[k], f[k], epsilon = 1e-13);
            assert_relative_eq!(got[k + 3], tau[k], epsilon = 1e-13);
        }
        // The same through the public slice API.
        let mut out = [0.0; 6];
        let pose = Pose::new(Vector3::zeros(), r);
        b.inertial_wrench(
            MotionPattern::Spatial,
            &pose,
            twist.as_slice(),
            acc.as_slice(),
            &mut out,
        );
        assert_relative_eq!(Vector6::from(out), got, epsilon = 1e-15);
        // M is symmetric positive definite.
        assert_relative_eq!(m6, m6.transpose(), epsilon = 1e-15);
        assert!(m6.cholesky().is_some());
    }

    /// Hand values: a 2 kg point, a planar body with its mass 0.1 m along x.
    #[test]
    fn hand_values() {
        let p = Platform {
            mass: 2.0,
            ..Platform::default()
        };
        let point = RigidBody::point_mass(&p).unwrap();
        let mut out = [0.0; 3];
        point.inertial_wrench(
            MotionPattern::Point3,
            &Pose::point(0.0, 0.0, 0.0),
            &[5.0, 5.0, 5.0],
            &[1.0, -2.0, 3.0],
            &mut out,
        );
        assert_eq!(out, [2.0, -4.0, 6.0]);
        let p = Platform {
            mass: 2.0,
            centre_of_mass: Vector3::new(0.1, 0.0, 0.0),
            ..Platform::default()
        };
        let planar = RigidBody::new(&p, Matrix3::from_diagonal_element(0.01)).unwrap();
        // Spinning at ω = 3 rad/s, no acceleration: the centripetal force −m ω² c = (−1.8, 0).
        planar.inertial_wrench(
            MotionPattern::Planar,
            &Pose::planar(0.0, 0.0, 0.0),
            &[0.0, 0.0, 3.0],
            &[0.0, 0.0, 0.0],
            &mut out,
        );
        assert_relative_eq!(out[0], -1.8, epsilon = 1e-14);
        assert_relative_eq!(out[1], 0.0, epsilon = 1e-14);
        assert_relative_eq!(out[2], 0.0, epsilon = 1e-14);
        // φ̈ = 1 rad/s² at φ = π/2 (c = (0, 0.1)): f = m ω̇ × c = (−0.2, 0), τ = 0.03.
        planar.inertial_wrench(
            MotionPattern::Planar,
            &Pose::planar(0.0, 0.0, std::f64::consts::FRAC_PI_2),
            &[0.0, 0.0, 0.0],
            &[0.0, 0.0, 1.0],
            &mut out,
        );
        assert_relative_eq!(out[0], -0.2, epsilon = 1e-14);
        assert_relative_eq!(out[1], 0.0, epsilon = 1e-14);
        assert_relative_eq!(out[2], 0.03, epsilon = 1e-14);
    }

    #[test]
    fn inertia_that_is_not_spd_is_an_error() {
        let p = Platform {
            mass: 1.0,
            ..Platform::default()
        };
        let asym = Matrix3::new(1.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
        assert!(matches!(
            RigidBody::new(&p, asym),
            Err(DynamicsError::InertiaNotPositiveDefinite {
                why: "it is not symmetric",
                ..
            })
        ));
        let indefinite = Matrix3::new(1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0);
        assert!(RigidBody::new(&p, indefinite).is_err());
        assert!(RigidBody::new(&p, Matrix3::zeros()).is_err());
        let nan = Matrix3::from_diagonal_element(f64::NAN);
        assert!(RigidBody::new(&p, nan).is_err());
        let massless = Platform::default();
        assert!(matches!(
            RigidBody::new(&massless, Matrix3::identity()),
            Err(DynamicsError::BadMass { .. })
        ));
    }

    /// ω = H φ̇ against the finite-difference derivative of R = R_x R_y R_z, and Ḣ against
    /// finite differences of H.
    #[test]
    fn euler_rates_to_angular_velocity() {
        let q = [0.3, -0.4, 0.9];
        let qd = [0.5, -1.2, 0.7];
        let rot = |q: &[f64; 3]| {
            *Pose::spatial(Vector3::zeros(), q[0], q[1], q[2])
                .rotation
                .matrix()
        };
        let h = 1e-6;
        let step = |s: f64| [q[0] + s * qd[0], q[1] + s * qd[1], q[2] + s * qd[2]];
        let rdot = (rot(&step(h)) - rot(&step(-h))) / (2.0 * h);
        let wx = rdot * rot(&q).transpose(); // [ω]×
        let w = euler_rate_matrix(&q) * Vector3::from(qd);
        assert_relative_eq!(wx[(2, 1)], w.x, epsilon = 1e-8);
        assert_relative_eq!(wx[(0, 2)], w.y, epsilon = 1e-8);
        assert_relative_eq!(wx[(1, 0)], w.z, epsilon = 1e-8);
        let hd = (euler_rate_matrix(&step(h)) - euler_rate_matrix(&step(-h))) / (2.0 * h);
        assert_relative_eq!(hd, euler_rate_matrix_derivative(&q, &qd), epsilon = 1e-8);
    }
}

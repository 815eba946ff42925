//! # The state at a pose
//!
//! What the page shows live while the pose changes, each number from the request/report layer
//! (`cdpr-api`), the same requests `cdpr kinematics`, `cdpr tension`, `cdpr capacity` and
//! `cdpr isotropic` run: cable lengths l_i (inverse kinematics, thesis eqs. (6.2)–(6.4)), the
//! tension distribution W t + w_ext = 0, t_min ≤ t ≤ t_max by the chosen method (certified before
//! "feasible" is returned), the capacity margin of the load (Guay et al. 2014) and the isotropic
//! force (Krut, Company & Pierrot 2004, eq. (19)) from the available wrench set (hyperplane
//! shifting, Gouttefarde & Krut 2010).
//!
//! ## References
//! - Gouttefarde & Krut 2010; Guay, Cardou, Cruz-Ruiz & Caro 2014; Krut, Company & Pierrot 2004.

use crate::{Studio, StudioError};
use cdpr_api::{CapacityRequest, IsotropicRequest, KinematicsRequest, Robot, TensionRequest};
use cdpr_tension::Method;
use serde::Serialize;

/// The page's state at one pose (the JSON of `<output id="cdpr-state">`, without the page's
/// own timing fields).
#[derive(Debug, Clone, Serialize)]
pub struct State {
    /// Robot name.
    pub robot: String,
    /// Motion pattern (`point2`, `planar`, `point3`, `spatial`).
    pub motion: String,
    /// Pose in motion-pattern coordinates (m, rad; spatial: x, y, z, XYZ Euler angles).
    pub pose: Vec<f64>,
    /// Tension method (command-line name).
    pub method: String,
    /// What the method computes and its reference.
    pub method_reference: &'static str,
    /// External wrench w_ext (N, N·m): the wrench asked for plus gravity and passive springs.
    pub external_wrench: Vec<f64>,
    /// Cable lengths l_i (m).
    pub lengths: Vec<f64>,
    /// Tensions t_i (N); null without a solution. For `exact`/`pinv`, t = −W⁺ w_ext even when
    /// it breaks a bound (then `feasible` is false).
    pub tensions: Option<Vec<f64>>,
    /// Tensions within bounds and in equilibrium (certified).
    pub feasible: bool,
    /// Why not feasible; null when feasible.
    pub reason: Option<String>,
    /// Equilibrium residual ‖W t + w_ext‖ (N) of a feasible answer.
    pub residual: Option<f64>,
    /// Lower tension bounds t_min (N).
    pub t_min: Vec<f64>,
    /// Upper tension bounds t_max (N; null for ∞).
    pub t_max: Vec<f64>,
    /// Capacity margin of the load w_ext (N, N·m; null when the wrench set is unbounded or was
    /// not computed, see `polytope_note`).
    pub capacity_margin: Option<f64>,
    /// Largest force the platform can resist in every direction under the load (N).
    pub isotropic_force: Option<f64>,
    /// Why the capacity margin or isotropic force is missing.
    pub polytope_note: Option<String>,
}

impl Studio {
    /// The state at pose `q` (motion-pattern coordinates) for the tension `method` and the
    /// external wrench `wrench` (DOF numbers, N and N·m; gravity of the platform is added).
    pub fn state(
        &self,
        q: &[f64],
        method: &str,
        wrench: Option<&[f64]>,
    ) -> Result<State, StudioError> {
        let method = parse_method(method)?;
        let robot = Robot::from_description(self.desc.clone());
        let pose = q.to_vec();
        let wrench = wrench.map(<[f64]>::to_vec);
        let mut tension = TensionRequest::new(robot.clone(), pose.clone(), method);
        tension.wrench = wrench.clone();
        let tension = tension.run()?;
        let kinematics = KinematicsRequest {
            robot: robot.clone(),
            pose: pose.clone(),
        }
        .run()?;
        // The wrench-set indices need finite bounds (and wrench closure for the isotropic
        // force): where they do not apply the page says why instead of failing.
        let capacity = CapacityRequest {
            robot: robot.clone(),
            pose: pose.clone(),
            wrench: wrench.clone(),
            wrench_box: None,
            wrench_ball: None,
            force_radius: None,
            moment_radius: None,
        }
        .run();
        let isotropic = IsotropicRequest {
            robot,
            pose,
            wrench,
            ellipse: false,
        }
        .run();
        let note = match (&capacity, &isotropic) {
            (Err(e), _) | (_, Err(e)) => Some(e.to_string()),
            _ => None,
        };
        let d = &self.desc;
        Ok(State {
            robot: tension.robot,
            motion: kinematics.motion,
            pose: tension.pose,
            method: tension.method,
            method_reference: method.summary(),
            external_wrench: tension.external_wrench,
            lengths: kinematics.lengths,
            tensions: tension.tensions,
            feasible: tension.feasible,
            reason: tension.reason,
            residual: tension.residual,
            t_min: d.bounds.min().as_slice().to_vec(),
            t_max: d.bounds.max().as_slice().to_vec(),
            capacity_margin: capacity.ok().and_then(|c| c.capacity_margin),
            isotropic_force: isotropic.ok().map(|i| i.isotropic_force),
            polytope_note: note,
        })
    }
}

/// A method by its command-line name.
pub(crate) fn parse_method(name: &str) -> Result<Method, StudioError> {
    name.parse::<Method>()
        .map_err(|_| StudioError::UnknownMethod {
            name: name.into(),
            known: Method::ALL.map(Method::name).join(", "),
        })
}

#[cfg(test)]
mod tests {
    use crate::test_support::open;

    /// The 4-cable planar robot of the thesis at the centre: lengths by hand, equilibrium.
    #[test]
    fn lengths_and_certified_tensions_at_a_pose() {
        let s = open("tdpm-4.toml");
        let st = s
            .state(&[0.0, 0.0, 0.0], "l2", Some(&[0.0, -10.0, 0.0]))
            .unwrap();
        let d = s.description();
        for (i, c) in d.robot.cables().iter().enumerate() {
            assert!((st.lengths[i] - (c.frame - c.platform).norm()).abs() < 1e-12);
        }
        let t = st.tensions.unwrap();
        assert!(st.feasible && st.residual.unwrap() < 1e-8);
        // Equilibrium: the sum of t_i u_i balances the 10 N load in y.
        let fy: f64 = d
            .robot
            .cables()
            .iter()
            .zip(&t)
            .map(|(c, t)| t * (c.frame - c.platform).normalize().y)
            .sum();
        assert!((fy - 10.0).abs() < 1e-6, "{fy}");
        assert!(st.capacity_margin.unwrap() > 0.0);
    }

    #[test]
    fn bad_inputs_are_errors_with_a_message() {
        let s = open("tdpm-4.toml");
        let e = s.state(&[0.0, 0.0], "l2", None).unwrap_err().to_string();
        assert!(e.contains("3"), "{e}");
        let e = s
            .state(&[0.0, 0.0, 0.0], "magic", None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("unknown tension method `magic`") && e.contains("l2"),
            "{e}"
        );
        let e = s.state(&[f64::NAN, 0.0, 0.0], "l2", None).unwrap_err();
        assert!(e.to_string().contains("finite"), "{e}");
        // closed-form needs redundancy 1; tdpm-4 (n = 4, DOF 3) has it, krut-5 (r = 3) not.
        assert!(
            open("krut-5.toml")
                .state(&[0.0, 0.0], "closed-form", None)
                .is_err()
        );
    }
}

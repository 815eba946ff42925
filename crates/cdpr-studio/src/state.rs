//! # The state at a pose
//!
//! What the page shows live while the pose changes: inverse kinematics (cable lengths l_i,
//! thesis eqs. (6.2)–(6.4)), the tension distribution W t + w_ext = 0, t_min ≤ t ≤ t_max by the
//! chosen method (certified before "feasible" is returned), the capacity margin of the load
//! (Guay et al. 2014) and the isotropic force (Krut, Company & Pierrot 2004, eq. (19)) from the
//! available wrench set (hyperplane shifting, Gouttefarde & Krut 2010). The numbers are those of
//! `cdpr kinematics`, `cdpr tension`, `cdpr capacity` and `cdpr isotropic` with `--json`: the same
//! library calls in the same order.
//!
//! ## References
//! - Gouttefarde & Krut 2010; Guay, Cardou, Cruz-Ruiz & Caro 2014; Krut, Company & Pierrot 2004.

use crate::{Studio, StudioError};
use cdpr_polytope::{
    RequiredWrenchSet, hyperplane_shifting, isotropic_force_under_load, limiting_facet,
};
use cdpr_tension::{
    Method, SotdaSettings, StiffnessData, TensionOutcome, TensionProblem, TensionSolver,
};
use nalgebra::DVector;
use serde::Serialize;

/// The page's state at one pose (the JSON of `<output id="cdpr-state">`, without the page's
/// own timing fields).
#[derive(Debug, Clone, Serialize)]
pub struct State {
    /// Robot name.
    pub robot: String,
    /// Motion pattern (`point2`, `planar`, `point3`, `spatial`).
    pub motion: &'static str,
    /// Pose in motion-pattern coordinates (m, rad; spatial: x, y, z, XYZ Euler angles).
    pub pose: Vec<f64>,
    /// Tension method (command-line name).
    pub method: &'static str,
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
        let d = &self.desc;
        let method = parse_method(method)?;
        cdpr_wrench::require_enough_cables(&d.robot, "tension distribution")?;
        let r = d.robot.cable_count() as isize - d.robot.dof() as isize;
        method.check_redundancy(r)?;
        if method == Method::ImprovedClosedForm
            && let Some(cable) = d.bounds.max().iter().position(|v| !v.is_finite())
        {
            return Err(TensionError::NeedsFiniteBounds { method, cable }.into());
        }
        let motion = d.robot.motion();
        let pose = cdpr_kinematics::Pose::from_coordinates(motion, q)?;
        let given = match wrench {
            Some(w) => cdpr_wrench::wrench_from_slice(motion, w)?,
            None => DVector::zeros(motion.dof()),
        };
        let w_ext = given + d.load_wrench(&pose)?;
        let kin = d.robot.inverse_kinematics(&pose)?;
        let w = kin.wrench_matrix();
        let mut problem = TensionProblem::new(&w, &w_ext, &d.bounds);
        if let Some(es) = &d.axial_stiffness {
            problem.stiffness = Some(StiffnessData {
                kinematics: &kin,
                axial_stiffness: es,
            });
        }
        let mut solver = if method == Method::Sotda {
            if d.axial_stiffness.is_none() {
                return Err(StudioError::Files(
                    "sotda needs `axial_stiffness` (E·S, N) on every cable of the robot file"
                        .into(),
                ));
            }
            TensionSolver::sotda(SotdaSettings::default())
        } else {
            TensionSolver::new(method)
        };
        let outcome = solver.solve(&problem)?;
        let (capacity_margin, isotropic_force, polytope_note) =
            match hyperplane_shifting::available_wrench_set(&w, &d.bounds) {
                Ok(aws) => {
                    let load = RequiredWrenchSet::point(w_ext.clone())?;
                    let margin = limiting_facet(&aws, &load)?.map(|(_, m)| m);
                    let iso = isotropic_force_under_load(&aws, motion, &w_ext);
                    let note = iso.as_ref().err().map(ToString::to_string);
                    (margin, iso.ok(), note)
                }
                Err(e) => (None, None, Some(e.to_string())),
            };
        Ok(State {
            robot: d.name.clone(),
            motion: motion.name(),
            pose: q.to_vec(),
            method: method.name(),
            method_reference: method.summary(),
            external_wrench: w_ext.as_slice().to_vec(),
            lengths: kin.lengths().collect(),
            tensions: outcome.balancing_tensions().map(|t| t.as_slice().to_vec()),
            feasible: outcome.is_feasible(),
            reason: outcome.infeasibility().map(|r| r.to_string()),
            residual: match &outcome {
                TensionOutcome::Feasible(s) => Some(s.residual),
                TensionOutcome::Infeasible(_) => None,
            },
            t_min: d.bounds.min().as_slice().to_vec(),
            t_max: d.bounds.max().as_slice().to_vec(),
            capacity_margin,
            isotropic_force,
            polytope_note,
        })
    }
}

use cdpr_tension::TensionError;

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
    use crate::{RobotFileText, Studio};

    fn open(name: &str) -> Studio {
        let path = format!(
            "{}/../../examples/robots/{name}",
            env!("CARGO_MANIFEST_DIR")
        );
        let text = std::fs::read_to_string(path).unwrap();
        Studio::open(&[RobotFileText {
            name: name.into(),
            text,
        }])
        .unwrap()
    }

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

//! Newton robustness of the elasto-geometric forward kinematics (issue 29): over wide cable
//! ranges (very light to very heavy, EA from soft to huge) and unstrained lengths from tight to
//! very slack, a solve never panics and never returns a NaN; an error names its cause.

use cdpr_kinematics::nalgebra::Vector3;
use cdpr_kinematics::reference_robots::ipanema_like_8;
use cdpr_kinematics::{ElastoGeometricForward, ElastoGeometricStatus, Pose, RobotCatenaries};
use proptest::prelude::*;

fn decades(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi).prop_map(|e: f64| 10f64.powf(e))
}

fn config(cases: u32) -> ProptestConfig {
    let mut c = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = cases;
    }
    c
}

proptest! {
    #![proptest_config(config(150))]

    #[test]
    fn never_panics_or_returns_nan(
        rho in prop_oneof![1 => Just(0.0), 4 => decades(-6.0, 1.0)],
        ea in decades(1.0, 13.0),
        (x, y, z) in (-1.2..1.2f64, -1.2..1.2f64, 0.2..1.8f64),
        tension in decades(-2.0, 4.0),
        scale in prop::collection::vec(0.8..1.3f64, 8),
        mass in decades(-2.0, 3.0),
        off in (-0.3..0.3f64, -0.3..0.3f64, -0.3..0.3f64, -0.3..0.3f64),
    ) {
        let robot = ipanema_like_8();
        let model = RobotCatenaries::new(&[rho; 8], &[ea; 8], &Vector3::new(0.0, 0.0, -9.81)).unwrap();
        let pose = Pose::spatial(Vector3::new(x, y, z), 0.0, 0.0, 0.0);
        let kin = robot.inverse_kinematics(&pose).unwrap();
        let mut cables = Vec::new();
        // Lengths around those of a uniform tension, some much longer (slack) or shorter.
        let l0: Vec<f64> = match model.with_tensions(&kin, &[tension; 8], &mut cables) {
            Ok(()) => cables.iter().zip(&scale).map(|(c, s)| c.unstrained_length * s).collect(),
            Err(e) => {
                prop_assert!(!e.to_string().is_empty());
                kin.lengths().zip(&scale).map(|(l, s)| l * s).collect()
            }
        };
        let mut fk = ElastoGeometricForward::new(&robot, &model, Default::default()).unwrap();
        let w = [0.0, 0.0, -mass * 9.81, 0.0, 0.0, 0.0];
        // From a start up to 0.3 m and 0.3 rad off.
        let guess = Pose::spatial(pose.position + Vector3::new(off.0, off.1, off.2), off.3, 0.0, 0.0);
        match fk.solve(&l0, &w, &guess) {
            Ok(sol) => {
                prop_assert!(sol.residual.is_finite(), "{:?}", sol);
                prop_assert!(sol.pose.position.iter().all(|v| v.is_finite()), "{:?}", sol);
                prop_assert!(sol.pose.rotation.matrix().iter().all(|v| v.is_finite()));
                for c in fk.cables() {
                    prop_assert!(c.platform_end_tension.is_finite() && c.frame_end_tension.is_finite()
                        && c.unstrained_length.is_finite(), "{:?}", c);
                }
                if sol.status == ElastoGeometricStatus::Equilibrium {
                    prop_assert!(fk.cables().iter().all(|c| c.platform_end_tension >= 0.0));
                }
            }
            Err(e) => prop_assert!(!e.to_string().is_empty()),
        }
    }
}

//! The robot-file parsers on arbitrary text: cdpr TOML (`RobotDescription::parse`), and for
//! text that starts with `<` the XML readers — WireCenter `.wcrfx` when it contains `<models`,
//! otherwise a CASPR model whose bodies file starts at `<bodies_system` (`parse_caspr`).
//! Invariants: no panic and no hang; errors display (with the file name first); an accepted file
//! is consistent (one bound per cable, finite geometry, t_min ≤ t_max), writes as TOML that reads
//! back as the same robot, and its robot goes through inverse kinematics, the gravity wrench and
//! a tension distribution whose feasible verdict passes the certificate.
#![no_main]

use cdpr::RobotDescription;
use cdpr::kinematics::Pose;
use cdpr::tension::{Method, TensionProblem, TensionSolver};
use cdpr_fuzz::check_certificate;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let parsed = if !text.trim_start().starts_with('<') {
        RobotDescription::parse(text, "fuzz.toml")
    } else if text.contains("<models") {
        RobotDescription::parse_wcrfx(text, "fuzz.wcrfx")
    } else {
        let (cables, bodies) = text.split_at(text.find("<bodies_system").unwrap_or(text.len()));
        RobotDescription::parse_caspr(cables, "fuzz_cables.xml", bodies, "fuzz_bodies.xml", None)
    };
    let desc = match parsed {
        Ok(d) => d,
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.starts_with("fuzz"), "error without file name: {msg}");
            return;
        }
    };
    let again = RobotDescription::parse(&desc.to_toml("fuzz"), "again.toml")
        .unwrap_or_else(|e| panic!("written TOML does not read back: {e}"));
    assert_eq!(again.robot, desc.robot, "TOML round trip changed the robot");
    assert_eq!(again.bounds, desc.bounds, "TOML round trip changed the bounds");
    assert_eq!(
        again.passive_springs, desc.passive_springs,
        "TOML round trip changed the passive springs"
    );
    // Fewer cables than DOF is a robot (kinematics only); at least one cable.
    let robot = &desc.robot;
    let n = robot.cable_count();
    assert!(n >= 1, "accepted a robot without cables");
    assert_eq!(desc.bounds.len(), n, "one bound pair per cable");
    for i in 0..n {
        let (lo, hi) = (desc.bounds.min()[i], desc.bounds.max()[i]);
        assert!(
            lo.is_finite() && hi.is_finite() && lo <= hi,
            "bad bounds accepted"
        );
    }
    if let Some(es) = &desc.axial_stiffness {
        assert_eq!(es.len(), n);
        assert!(es.iter().all(|&k| k.is_finite() && k > 0.0));
    }
    let motion = robot.motion();
    let pose = Pose::from_coordinates(motion, &vec![0.0; motion.dof()]).expect("zero pose");
    let Ok(kin) = robot.inverse_kinematics(&pose) else {
        return; // a cable of zero length at the origin: an error, fine
    };
    let w = kin.wrench_matrix();
    let w_ext = desc.platform.gravity_wrench(motion, &pose);
    let problem = TensionProblem::new(&w, &w_ext, &desc.bounds);
    if let Ok(out) = TensionSolver::new(Method::L2).solve(&problem)
        && let Some(t) = out.tensions()
        && let Err(e) = check_certificate(
            &w,
            &w_ext,
            desc.bounds.min().as_slice(),
            desc.bounds.max().as_slice(),
            t.as_slice(),
        )
    {
        panic!("l2 on a parsed robot fails the certificate: {e:?}");
    }
});

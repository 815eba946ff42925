//! CASPR's `NAME_trajectories.xml`: every vendored file parses, each trajectory's profile starts
//! and ends at the file's points, CASPR's orientation interpolation is reproduced, and bad files
//! are errors naming the file, line and element.

use cdpr_dynamics::SplineKind;
use cdpr_io::{
    RobotDescription, RobotFileError, caspr_trajectory_ids, load_caspr_trajectory,
    parse_caspr_trajectory,
};
use cdpr_kinematics::MotionPattern;
use nalgebra::{Matrix3, Vector3};
use std::path::{Path, PathBuf};

fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/caspr")
        .join(rel)
}

/// Every vendored `*_trajectories.xml`, with its robot's cables file.
fn trajectory_files() -> Vec<(PathBuf, PathBuf)> {
    let mut out = Vec::new();
    for group in [
        "planar_manipulators",
        "spatial_manipulators",
        "spherical_manipulators",
    ] {
        for robot in std::fs::read_dir(data(group)).unwrap() {
            let dir = robot.unwrap().path();
            for f in std::fs::read_dir(&dir).unwrap() {
                let f = f.unwrap().path();
                let name = f.file_name().unwrap().to_string_lossy().into_owned();
                if let Some(prefix) = name.strip_suffix("_trajectories.xml") {
                    out.push((f.clone(), dir.join(format!("{prefix}_cables.xml"))));
                }
            }
        }
    }
    out.sort();
    out
}

/// Every vendored trajectory of every robot cdpr reads gives a profile whose first and last
/// poses are the file's first and last points, sampled every `time_step`.
#[test]
fn every_vendored_trajectory_parses_and_ends_at_its_points() {
    let files = trajectory_files();
    assert_eq!(files.len(), 14);
    let mut profiles = 0;
    for (file, cables) in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let ids = caspr_trajectory_ids(&text, file).unwrap_or_else(|e| panic!("{e}"));
        let robot = match RobotDescription::load(cables) {
            Ok(r) => r,
            // Myorob_shoulder: a spherical joint, which cdpr does not model.
            Err(RobotFileError::Unsupported { .. }) => continue,
            Err(e) => panic!("{e}"),
        };
        let motion = robot.robot.motion();
        for (id, element) in ids {
            assert_eq!(element, "quintic_spline_trajectory");
            let t = load_caspr_trajectory(file, &id, motion).unwrap_or_else(|e| panic!("{e}"));
            let samples = t.spline.samples();
            let (first, last) = (&t.points[0], t.points.last().unwrap());
            let q0 = samples[0].pose.coordinates(motion);
            let q1 = samples.last().unwrap().pose.coordinates(motion);
            for i in 0..motion.dof() {
                assert!(
                    (q0[i] - first.q[i]).abs() < 1e-12,
                    "{id}: {q0:?} vs {:?}",
                    first.q
                );
                assert!(
                    (q1[i] - last.q[i]).abs() < 1e-12,
                    "{id}: {q1:?} vs {:?}",
                    last.q
                );
            }
            // CASPR's time vector: 0, dt, …, the last point's time.
            let dt = t.spline.time_step();
            assert_eq!(samples[0].t, 0.0);
            assert!((samples.last().unwrap().t - last.time).abs() < 1e-12);
            assert_eq!(samples.len(), (last.time / dt).round() as usize + 1, "{id}");
            for w in samples.windows(2) {
                assert!((w[1].t - w[0].t - dt).abs() < 1e-9);
            }
            // Rest at the ends (the files' q_dot and q_ddot are zero).
            assert!(samples[0].twist.norm() < 1e-12);
            assert!(samples.last().unwrap().twist.norm() < 1e-12);
            profiles += 1;
        }
    }
    // CAROCA 1, CoGiRo 4, IPAnema_1 2, IPAnema_2 3, The_Cable_Robot_Simulator 1.
    assert_eq!(profiles, 11);
}

/// The IPAnema_1 robot's `traj_1` reproduces CASPR's profile: positions by the quintic law
/// component by component, orientations along CASPR's quaternion axis–angle path
/// (`Quaternion.FromRotationMatrix`, `AxisAngle.FromQuaternion`, `rotation_matrix_to_angles`),
/// written here from CASPR's formulas independently of cdpr's rotations.
#[test]
fn ipanema_1_traj_1_reproduces_caspr() {
    let file = data("spatial_manipulators/IPAnema_1/IPAnema_1_trajectories.xml");
    let t = load_caspr_trajectory(&file, "traj_1", MotionPattern::Spatial).unwrap();
    assert_eq!(t.spline.kind(), SplineKind::Quintic);
    let (qs, qe) = (&t.points[0].q, &t.points[1].q);
    let rot = |a: f64, b: f64, g: f64| -> Matrix3<f64> {
        let (sa, ca) = a.sin_cos();
        let (sb, cb) = b.sin_cos();
        let (sg, cg) = g.sin_cos();
        let rx = Matrix3::new(1.0, 0.0, 0.0, 0.0, ca, -sa, 0.0, sa, ca);
        let ry = Matrix3::new(cb, 0.0, sb, 0.0, 1.0, 0.0, -sb, 0.0, cb);
        let rz = Matrix3::new(cg, -sg, 0.0, sg, cg, 0.0, 0.0, 0.0, 1.0);
        rx * ry * rz
    };
    let r_s = rot(qs[3], qs[4], qs[5]);
    let r_se = r_s.transpose() * rot(qe[3], qe[4], qe[5]);
    // Quaternion of R_se, then its axis and angle.
    let q0 = 0.5 * (1.0 + r_se.trace()).sqrt();
    let qv = Vector3::new(
        r_se[(2, 1)] - r_se[(1, 2)],
        r_se[(0, 2)] - r_se[(2, 0)],
        r_se[(1, 0)] - r_se[(0, 1)],
    ) / (4.0 * q0);
    let th_e = 2.0 * q0.acos();
    let k = qv / (th_e / 2.0).sin();
    let samples = t.spline.samples();
    for &j in &[13usize, 37, 50, 81] {
        let time = j as f64 * 0.01;
        let tau = time / 1.0;
        let sigma = tau.powi(3) * (10.0 - 15.0 * tau + 6.0 * tau * tau);
        // Positions: the quintic rest-to-rest law.
        for i in 0..3 {
            let want = qs[i] + (qe[i] - qs[i]) * sigma;
            assert!((samples[j].pose.position[i] - want).abs() < 1e-13);
        }
        // Orientation: R_s · R(quaternion of (k, σ θ_e)), Euler angles as CASPR extracts them.
        let th = sigma * th_e;
        let (c, s) = ((th / 2.0).cos(), (th / 2.0).sin());
        let (w, x, y, z) = (c, k.x * s, k.y * s, k.z * s);
        let r_sp = Matrix3::new(
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        );
        let r = r_s * r_sp;
        let b = r[(0, 2)].asin();
        let g = -r[(0, 1)].atan2(r[(0, 0)]);
        let a = -r[(1, 2)].atan2(r[(2, 2)]);
        let got = samples[j].pose.coordinates(MotionPattern::Spatial);
        for (i, want) in [a, b, g].into_iter().enumerate() {
            assert!((got[3 + i] - want).abs() < 1e-12, "t = {time}: {got:?}");
        }
        // ω = R_s k θ̇ with θ̇ = θ_e σ̇.
        let dsigma = 30.0 * tau * tau * (1.0 - tau).powi(2);
        let omega = r_s * k * (th_e * dsigma);
        for i in 0..3 {
            assert!((samples[j].twist[3 + i] - omega[i]).abs() < 1e-12);
        }
    }
    // Not the Euler angles splined one by one: at mid-time they differ.
    let mid = samples[50].pose.coordinates(MotionPattern::Spatial);
    let naive = 0.5 * (qs[4] + qe[4]);
    assert!((mid[4] - naive).abs() > 1e-3, "{} vs {naive}", mid[4]);
}

/// CASPR's planar example file exercises the other four kinds (and a `file_trajectory`,
/// which cdpr does not read).
#[test]
fn caspr_example_planar_xy_all_kinds() {
    let file = data("examples/Example_planar_XY/Example_planar_XY_trajectories.xml");
    let text = std::fs::read_to_string(&file).unwrap();
    let ids = caspr_trajectory_ids(&text, &file).unwrap();
    assert_eq!(ids.len(), 13);
    let mut kinds = Vec::new();
    for (id, element) in &ids {
        let r = parse_caspr_trajectory(&text, &file, id, MotionPattern::Planar);
        if element == "file_trajectory" {
            let e = r.unwrap_err();
            assert!(matches!(e, RobotFileError::Unsupported { .. }), "{e}");
            assert!(e.to_string().contains("<file_trajectory>"), "{e}");
            continue;
        }
        let t = r.unwrap_or_else(|e| panic!("{id}: {e}"));
        kinds.push(t.spline.kind());
        let samples = t.spline.samples();
        let (first, last) = (&t.points[0], t.points.last().unwrap());
        let q0 = samples[0].pose.coordinates(MotionPattern::Planar);
        let q1 = samples
            .last()
            .unwrap()
            .pose
            .coordinates(MotionPattern::Planar);
        for i in 0..3 {
            assert!((q0[i] - first.q[i]).abs() < 1e-12, "{id}");
            assert!((q1[i] - last.q[i]).abs() < 1e-12, "{id}");
        }
    }
    for k in SplineKind::ALL {
        assert!(kinds.contains(&k), "{k:?}");
    }
    // The parabolic blend: absolute times 0, 5, 10 s; blend 0.5 s on the first segment
    // (blend_time_default), 1.5 s on the second (the third point's blend_time).
    let t = parse_caspr_trajectory(
        &text,
        &file,
        "example_parabolic_blend",
        MotionPattern::Planar,
    )
    .unwrap();
    // First segment x: 0.3 → 0.7 in 5 s: a = 0.4 / (0.5 · 4.5), cruise a · 0.5 = 0.4 / 4.5.
    let mid = t.spline.at(2.5);
    assert!((mid.twist[0] - 0.4 / 4.5).abs() < 1e-14);
    // Second segment x: 0.7 → 0.4 in 5 s, t_b = 1.5: cruise −0.3 / 3.5.
    assert!((t.spline.at(7.5).twist[0] + 0.3 / 3.5).abs() < 1e-14);
    // At rest at the middle point (CASPR's blends stop at every point).
    assert!(t.spline.at(5.0).twist.norm() < 1e-14);
    assert_eq!(t.spline.samples().len(), 1001);
    // Cubic average velocity: the interior point's velocity is the mean of the two slopes.
    let t = parse_caspr_trajectory(
        &text,
        &file,
        "example_cubic_average_velocity",
        MotionPattern::Planar,
    )
    .unwrap();
    let v = t.spline.at(2.0).twist;
    assert!((v[0] - 0.5 * (0.1 / 2.0 + 0.3 / 3.0)).abs() < 1e-14);
    assert!((v[1] - 0.5 * (-0.2 / 2.0 + 0.2 / 3.0)).abs() < 1e-14);
}

fn bad(xml: &str, id: &str) -> String {
    let text = format!(
        "<trajectories>\n<joint_trajectories>\n{xml}\n</joint_trajectories>\n</trajectories>"
    );
    parse_caspr_trajectory(
        &text,
        Path::new("bad_trajectories.xml"),
        id,
        MotionPattern::Point2,
    )
    .unwrap_err()
    .to_string()
}

/// Bad files: the message names the file, the line and the element (and attribute).
#[test]
fn bad_trajectory_files_name_the_element() {
    let two = |kind: &str, attrs: &str, p0: &str, p1: &str| {
        format!(
            "<{kind} id=\"t\" {attrs}>\n<points>\n<point>{p0}</point>\n<point time=\"1\">{p1}</point>\n</points>\n</{kind}>"
        )
    };
    let ok_attrs = "time_definition=\"relative\" time_step=\"0.1\"";
    let lin = two(
        "linear_spline_trajectory",
        ok_attrs,
        "<q>0 0</q>",
        "<q>1 0</q>",
    );
    let e = bad(&lin, "nope");
    assert!(
        e.starts_with("bad_trajectories.xml:2: <joint_trajectories>"),
        "{e}"
    );
    assert!(
        e.contains("no joint trajectory with id `nope` (the file has: t)"),
        "{e}"
    );
    let e = bad(
        &two(
            "linear_spline_trajectory",
            "time_definition=\"later\" time_step=\"0.1\"",
            "<q>0 0</q>",
            "<q>1 0</q>",
        ),
        "t",
    );
    assert!(
        e.contains(":3: <linear_spline_trajectory> attribute `time_definition`: `later`"),
        "{e}"
    );
    // The template's time_step="dt".
    let e = bad(
        &two(
            "quintic_spline_trajectory",
            "time_definition=\"relative\" time_step=\"dt\"",
            "<q>0 0</q>",
            "<q>1 0</q>",
        ),
        "t",
    );
    assert!(
        e.contains("attribute `time_step`: `dt` is not a number"),
        "{e}"
    );
    let e = bad(
        &two(
            "linear_spline_trajectory",
            "time_definition=\"relative\" time_step=\"-0.1\"",
            "<q>0 0</q>",
            "<q>1 0</q>",
        ),
        "t",
    );
    assert!(
        e.contains("attribute `time_step`: -0.1: must be a finite number > 0"),
        "{e}"
    );
    // A cubic point without q_dot: the point's line.
    let e = bad(
        &two(
            "cubic_spline_trajectory",
            ok_attrs,
            "<q>0 0</q><q_dot>0 0</q_dot>",
            "<q>1 0</q>",
        ),
        "t",
    );
    assert!(e.contains(":6: <point>: missing <q_dot>"), "{e}");
    // Three numbers for a two-coordinate robot.
    let e = bad(
        &two(
            "linear_spline_trajectory",
            ok_attrs,
            "<q>0 0 0</q>",
            "<q>1 0</q>",
        ),
        "t",
    );
    assert!(
        e.contains(":5: <q>: expected 2 numbers (the robot's point2 coordinates x y), found 3"),
        "{e}"
    );
    // A segment shorter than the time step.
    let e = bad(
        &two(
            "linear_spline_trajectory",
            "time_definition=\"relative\" time_step=\"2\"",
            "<q>0 0</q>",
            "<q>1 0</q>",
        ),
        "t",
    );
    assert!(
        e.contains(
            ":6: <point> attribute `time`: 1: the segment from 0 s is shorter than time_step"
        ),
        "{e}"
    );
    // Absolute times going back.
    let back = "<linear_spline_trajectory id=\"t\" time_definition=\"absolute\" time_step=\"0.1\">\n<points>\n<point><q>0 0</q></point>\n<point time=\"2\"><q>1 0</q></point>\n<point time=\"1\"><q>2 0</q></point>\n</points>\n</linear_spline_trajectory>";
    let e = bad(back, "t");
    assert!(
        e.contains(":7: <point> attribute `time`: 1: point times must increase strictly"),
        "{e}"
    );
    // A blend longer than half its segment.
    let e = bad(
        &two(
            "parabolic_blend_trajectory",
            "time_definition=\"relative\" time_step=\"0.1\" blend_time_default=\"0.6\"",
            "<q>0 0</q>",
            "<q>1 0</q>",
        ),
        "t",
    );
    assert!(e.contains("<parabolic_blend_trajectory> attribute `blend_time_default`: 0.6: must be > 0 and less than half"), "{e}");
    // A missing time on a later point, an unknown element in a point.
    let e = bad(
        "<linear_spline_trajectory id=\"t\" time_definition=\"relative\" time_step=\"0.1\">\n<points>\n<point><q>0 0</q></point>\n<point><q>1 0</q></point>\n</points>\n</linear_spline_trajectory>",
        "t",
    );
    assert!(e.contains(":6: <point> attribute `time`: missing"), "{e}");
    let e = bad(
        &two(
            "linear_spline_trajectory",
            ok_attrs,
            "<q>0 0</q><qdot>0 0</qdot>",
            "<q>1 0</q>",
        ),
        "t",
    );
    assert!(e.contains(":5: <qdot>: unknown element"), "{e}");
    // Not a trajectories file.
    let e = parse_caspr_trajectory("<bodies/>", Path::new("x.xml"), "t", MotionPattern::Point2)
        .unwrap_err()
        .to_string();
    assert!(e.contains("x.xml:1: <bodies>"), "{e}");
}

//! The CASPR and WireCenter readers against values derived by hand from the files' numbers,
//! the details the published files exercise, and bad files (file, line, element in every error).

use cdpr_io::{LoadOptions, RobotDescription, RobotFileError, pulley_frame};
use cdpr_kinematics::{MotionPattern, Pose};
use nalgebra::{Matrix3, Vector3};
use std::path::{Path, PathBuf};

fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(rel)
}

fn caspr(robot: &str, set: Option<&str>) -> RobotDescription {
    let dir = if robot.contains("planar") || robot == "2_DoF_VSD" {
        "planar_manipulators"
    } else {
        "spatial_manipulators"
    };
    let file = if robot == "NIST_ROBOCRANE" {
        "NIST_RoboCrane".to_string()
    } else {
        robot.to_string()
    };
    let mut options = LoadOptions::default();
    options.cable_set = set.map(str::to_string);
    RobotDescription::load_with(
        data(&format!("caspr/{dir}/{robot}/{file}_cables.xml")),
        &options,
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

fn lengths(d: &RobotDescription, q: &[f64]) -> Vec<f64> {
    let pose = Pose::from_coordinates(d.robot.motion(), q).unwrap();
    d.robot
        .inverse_kinematics(&pose)
        .unwrap()
        .lengths()
        .collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn caroca_lengths_by_hand() {
    // CAROCA_cables.xml, set "original", cable 1: frame (1.659, -2.850, 3.221), platform
    // (0.16, 0.14, 0.105) in the joint frame. At q_initial = (0, 0, 1, 0, 0, 0) the attachment
    // is at (0.16, 0.14, 1.105): l = ‖(1.499, -2.99, 2.116)‖.
    let d = caspr("CAROCA", None);
    assert_eq!(d.robot.motion(), MotionPattern::Spatial);
    assert_eq!(
        d.home_pose.as_deref(),
        Some(&[0.0, 0.0, 1.0, 0.0, 0.0, 0.0][..])
    );
    let l = lengths(&d, &[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    let by_hand = (1.499f64.powi(2) + 2.99f64.powi(2) + 2.116f64.powi(2)).sqrt();
    assert!(close(l[0], by_hand), "{} vs {by_hand}", l[0]);
    // Rotation by γ = π/2 about z (CASPR's R = R_x R_y R_z): (0.16, 0.14, 0.105) → (-0.14, 0.16,
    // 0.105); cable 2 (frame (1.350, -3.159, 3.221), platform (-0.13, -0.21, -0.105)) → (0.21,
    // -0.13, -0.105), at z = 1: (0.21, -0.13, 0.895).
    let q = [0.0, 0.0, 1.0, 0.0, 0.0, std::f64::consts::FRAC_PI_2];
    let l = lengths(&d, &q);
    let c1 = (1.799f64.powi(2) + 3.01f64.powi(2) + 2.116f64.powi(2)).sqrt();
    let c2 = (1.14f64.powi(2) + 3.029f64.powi(2) + 2.326f64.powi(2)).sqrt();
    assert!(close(l[0], c1) && close(l[1], c2), "{l:?} vs {c1}, {c2}");
    // The commented-out "Small Platform" link (30 kg) is not read: the large one is (150 kg).
    assert_eq!(d.platform.mass, 150.0);
    assert_eq!(
        d.inertia,
        Some(Matrix3::from_diagonal(&Vector3::new(6.5, 20.0, 22.5)))
    );
    assert_eq!(d.platform.gravity, Vector3::new(0.0, 0.0, -9.81));
}

#[test]
fn caspr_euler_convention_is_x_then_y_then_z() {
    // A cable with frame anchor at the origin and attachment (1, 0, 0): after R_x(a) R_y(b) R_z(c)
    // the attachment is R e_x = (cos b cos c, cos a sin c + sin a sin b cos c, sin a sin c -
    // cos a sin b cos c). Compare ‖u + R e_x − 0‖ at u = (0, 0, 2) for CAROCA's cable 1 shape.
    let d = caspr("CAROCA", None);
    let (a, b, c) = (0.3f64, -0.4f64, 0.5f64);
    let rex = Vector3::new(
        b.cos() * c.cos(),
        a.cos() * c.sin() + a.sin() * b.sin() * c.cos(),
        a.sin() * c.sin() - a.cos() * b.sin() * c.cos(),
    );
    let pose = Pose::from_coordinates(MotionPattern::Spatial, &[0.0, 0.0, 2.0, a, b, c]).unwrap();
    assert!((pose.rotation * Vector3::x() - rex).norm() < 1e-15);
    let _ = d;
}

#[test]
fn joint_referenced_attachments_do_not_add_the_centre_of_mass() {
    // IPAnema_2: com_location (0, 0, 0.5), attachment_reference="joint": cable 1 platform
    // location (-0.65, 0.125, 0.25) is used as written.
    let d = caspr("IPAnema_2", None);
    assert_eq!(d.platform.centre_of_mass, Vector3::new(0.0, 0.0, 0.5));
    assert_eq!(
        d.robot.cables()[0].platform,
        Vector3::new(-0.65, 0.125, 0.25)
    );
    // ACROBOT: com (0.1645, 0.177, 0.149), joint-referenced too.
    let a = caspr("ACROBOT", None);
    assert_eq!(
        a.platform.centre_of_mass,
        Vector3::new(0.1645, 0.177, 0.149)
    );
    let text = std::fs::read_to_string(data(
        "caspr/spatial_manipulators/ACROBOT/ACROBOT_cables.xml",
    ))
    .unwrap();
    assert!(text.contains("attachment_reference=\"joint\""));
}

const BODIES: &str = r#"<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE bodies_system SYSTEM "bodies.dtd">
<bodies_system>
  <links>
    <!-- <link_rigid num="9"> a commented link with <mass>1</mass> -->
    <link_rigid num="1" name="Platform">
      <joint type="SPATIAL_EULER_XYZ" q_initial="0 0 1 0 0 0"/>
      <physical>
        <mass>2</mass>
        <com_location>0.1	0.0
            0.2</com_location>
        <end_location>0 0 0</end_location>
        <inertia ref="com">
          <Ixx>1</Ixx><Iyy>2</Iyy><Izz>3</Izz><Ixy>0</Ixy><Ixz>0</Ixz><Iyz>0</Iyz>
        </inertia>
      </physical>
      <parent><num>0</num><location>0 0 0</location></parent>
    </link_rigid>
  </links>
</bodies_system>
"#;

fn cable(name: &str, reference: &str, frame: &str, platform: &str) -> String {
    format!(
        r#"    <cable_ideal name="{name}" attachment_reference="{reference}">
      <properties><force_min>1</force_min><force_max>100</force_max></properties>
      <attachments>
        <attachment><link>0</link><location>{frame}</location></attachment>
        <attachment><link>1</link><location>{platform}</location></attachment>
      </attachments>
    </cable_ideal>
"#
    )
}

fn cables_file(cables: &[String]) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<cables default_cable_set=\"a\">\n  <cable_set id=\"a\">\n{}  </cable_set>\n</cables>\n",
        cables.concat()
    )
}

fn six(reference: &str) -> Vec<String> {
    (0..6)
        .map(|i| {
            let a = i as f64 * std::f64::consts::PI / 3.0;
            cable(
                "same name",
                reference,
                &format!("{} {} 3", 2.0 * a.cos(), 2.0 * a.sin()),
                &format!("{}\t{}\n 0", 0.1 * a.cos(), 0.1 * a.sin()),
            )
        })
        .collect()
}

#[test]
fn com_referenced_attachments_add_the_centre_of_mass_and_vectors_take_any_whitespace() {
    let com = RobotDescription::parse_caspr(
        &cables_file(&six("com")),
        "m_cables.xml",
        BODIES,
        "m_bodies.xml",
        None,
    )
    .unwrap();
    let joint = RobotDescription::parse_caspr(
        &cables_file(&six("joint")),
        "m_cables.xml",
        BODIES,
        "m_bodies.xml",
        None,
    )
    .unwrap();
    assert_eq!(com.platform.centre_of_mass, Vector3::new(0.1, 0.0, 0.2));
    for (c, j) in com.robot.cables().iter().zip(joint.robot.cables()) {
        assert_eq!(c.platform, j.platform + Vector3::new(0.1, 0.0, 0.2));
    }
    // Names repeat (as in CASPR's MACARM): kept, never used as keys.
    assert_eq!(com.cable_names, vec![Some("same name".to_string()); 6]);
    assert_eq!(com.name, "m");
}

#[test]
fn macarm_duplicate_names_and_nist_per_cable_limits() {
    let m = caspr("MACARM", None);
    assert_eq!(m.robot.cable_count(), 8);
    assert_eq!(m.cable_names[0], m.cable_names[7]);
    assert_ne!(m.robot.cables()[0], m.robot.cables()[7]);
    let n = caspr("NIST_ROBOCRANE", None);
    assert_eq!(
        n.bounds.max().as_slice(),
        &[1000.0, 5000.0, 1000.0, 5000.0, 5000.0, 5000.0]
    );
    let toml = n.to_toml("");
    let again = RobotDescription::parse(&toml, "nist.toml").unwrap();
    assert_eq!(again.bounds, n.bounds);
}

#[test]
fn caroca_rotating_pulleys() {
    let d = caspr("CAROCA", Some("with_rotating_pulleys"));
    let p = d.robot.cables()[0].pulley.expect("pulley");
    assert_eq!(p.radius, 0.045);
    // cable_entry_vector (0, 0, 1): swivel axis +z, Q = I.
    assert_eq!(p.orientation, Matrix3::identity());
    assert_eq!(
        d.robot.cables()[0].frame,
        Vector3::new(1.659, -2.850, 3.221)
    );
    // The default set has none.
    assert!(
        caspr("CAROCA", None)
            .robot
            .cables()
            .iter()
            .all(|c| c.pulley.is_none())
    );
    // A converted file keeps the pulleys and states its gravity.
    let toml = d.to_toml("CAROCA");
    assert!(toml.contains("pulley = { radius = 0.045"), "{toml}");
    assert!(toml.contains("gravity = [0.0, 0.0, -9.81]"), "{toml}");
}

#[test]
fn pulley_frame_from_an_entry_vector() {
    for v in [
        Vector3::new(0.0, 0.0, 2.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(0.3, -0.4, 0.5),
    ] {
        let q = pulley_frame(&v);
        assert!((q.column(2) - v.normalize()).norm() < 1e-15);
        assert!((q.transpose() * q - Matrix3::identity()).norm() < 1e-14);
        assert!((q.determinant() - 1.0).abs() < 1e-14);
    }
}

#[test]
fn planar_and_translational_caspr_models() {
    // KNTU_planar: PLANAR_XY, com-referenced, gravity normal to the plane (none in it).
    let k = caspr("KNTU_planar", None);
    assert_eq!(k.robot.motion(), MotionPattern::Planar);
    assert_eq!(k.platform.gravity, Vector3::zeros());
    // Cable 1: frame (-1.12, -1.05), platform (-0.15, 0): at (0, 0, 0) l = ‖(-0.97, -1.05)‖.
    let l = lengths(&k, &[0.0, 0.0, 0.0]);
    assert!(close(l[0], (0.97f64.powi(2) + 1.05f64.powi(2)).sqrt()));
    assert_eq!(k.bounds.min()[0], 0.001);
    // 2_DoF_VSD: P_XY joint (point2); its linear-spring set gives K → E·S = K·l(q_initial).
    let v = caspr("2_DoF_VSD", Some("basic_linear"));
    assert_eq!(v.robot.motion(), MotionPattern::Point2);
    let es = v.axial_stiffness.as_ref().expect("stiffness");
    let l = lengths(&v, v.home_pose.as_ref().unwrap());
    for (k, l) in es.iter().zip(&l) {
        assert!(close(*k, 13000.0 * l), "{k} vs {}", 13000.0 * l);
    }
    let ideal = caspr("2_DoF_VSD", Some("stiff"));
    assert!(ideal.axial_stiffness.is_none());
}

fn err(cables: &str, bodies: &str) -> RobotFileError {
    RobotDescription::parse_caspr(cables, "x_cables.xml", bodies, "x_bodies.xml", None).unwrap_err()
}

#[test]
fn caspr_errors_name_file_line_and_element() {
    // Multi-body: a second link_rigid.
    let two = BODIES.replace(
        "  </links>",
        "    <link_rigid num=\"2\"><joint type=\"R_X\"/></link_rigid>\n  </links>",
    );
    let e = err(&cables_file(&six("joint")), &two);
    let msg = e.to_string();
    assert!(
        msg.starts_with("x_bodies.xml:19: <link_rigid>: not modelled"),
        "{msg}"
    );
    assert!(msg.contains("multi-body"), "{msg}");
    // A VSD cable in the set.
    let mut cs = six("joint");
    cs[2] = cs[2].replace("cable_ideal", "cable_vsd_torsion_spring");
    let msg = err(&cables_file(&cs), BODIES).to_string();
    assert!(
        msg.starts_with("x_cables.xml:20: <cable_vsd_torsion_spring>"),
        "{msg}"
    );
    // A passive spring without its stiffness K.
    let mut cs = six("joint");
    cs[0] = cs[0].replace("cable_ideal", "cable_passive_linear_spring");
    let msg = err(&cables_file(&cs), BODIES).to_string();
    assert!(
        msg.starts_with("x_cables.xml:5: <properties>: missing child element <K>"),
        "{msg}"
    );
    // A bad number, with its line.
    let cs = cables_file(&six("joint")).replacen("<force_max>100<", "<force_max>lots<", 1);
    let msg = err(&cs, BODIES).to_string();
    assert!(
        msg.starts_with("x_cables.xml:5: <force_max>: `lots` is not a number"),
        "{msg}"
    );
    // A missing force limit.
    let cs = cables_file(&six("joint")).replacen("<force_min>1</force_min>", "", 1);
    let msg = err(&cs, BODIES).to_string();
    assert!(
        msg.contains("<properties>") && msg.contains("force_min"),
        "{msg}"
    );
    // A bad attachment reference (attribute named).
    let cs = cables_file(&six("joint")).replacen("\"joint\"", "\"tip\"", 1);
    let msg = err(&cs, BODIES).to_string();
    assert!(
        msg.starts_with("x_cables.xml:4: <cable_ideal> attribute `attachment_reference`"),
        "{msg}"
    );
    // Two numbers for a 3-vector.
    let cs = cables_file(&six("joint")).replacen("3</location>", "</location>", 1);
    let msg = err(&cs, BODIES).to_string();
    assert!(msg.contains("<location>: expected 3 numbers"), "{msg}");
    // Not XML.
    let msg = err("<cables><cable_set>", BODIES).to_string();
    assert!(
        msg.starts_with("x_cables.xml:1: not well-formed XML"),
        "{msg}"
    );
    // An unknown cable set.
    let e = RobotDescription::parse_caspr(
        &cables_file(&six("joint")),
        "x_cables.xml",
        BODIES,
        "x_bodies.xml",
        Some("b"),
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("no <cable_set id=\"b\"> (the file has: a)"),
        "{e}"
    );
    // A missing bodies file.
    let dir = // Cargo's scratch directory for integration tests (target/tmp), reused by every run, so
    // that no run leaves a directory behind in the system's temporary directory.
    std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("readers");
    std::fs::create_dir_all(&dir).unwrap();
    let lonely = dir.join("lonely_cables.xml");
    std::fs::write(&lonely, cables_file(&six("joint"))).unwrap();
    let msg = RobotDescription::load(&lonely).unwrap_err().to_string();
    assert!(msg.contains("lonely_bodies.xml: cannot read"), "{msg}");
    // An .xml that is not a CASPR cables or bodies file name.
    let msg = RobotDescription::load(dir.join("robot.xml"))
        .unwrap_err()
        .to_string();
    assert!(msg.contains("NAME_cables.xml"), "{msg}");
}

#[test]
fn wirecenter_ipanema_by_hand() {
    let d = RobotDescription::load(data("wirecenter/IPAnema.wcrfx")).unwrap();
    assert_eq!(d.robot.motion(), MotionPattern::Spatial);
    // Chain 1: base (-2, 1.5, 2), platform (-0.06, 0.06, 0); at (0, 0, 1): ‖(-1.94, 1.44, 1)‖.
    let straight = RobotDescription {
        robot: d.robot.without_pulleys(),
        ..d.clone()
    };
    let l = lengths(&straight, &[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    assert!(close(
        l[0],
        (1.94f64.powi(2) + 1.44f64.powi(2) + 1.0).sqrt()
    ));
    // Pulley radius 0.1 with the identity orientation.
    let p = d.robot.cables()[0].pulley.unwrap();
    assert_eq!((p.radius, p.orientation), (0.1, Matrix3::identity()));
    // Platform: mass 25 kg, centre of gravity (0, 1, 0.2), inertia Ixx = 14 (the rest absent).
    assert_eq!(d.platform.mass, 25.0);
    assert_eq!(d.platform.centre_of_mass, Vector3::new(0.0, 1.0, 0.2));
    assert_eq!(
        d.inertia,
        Some(Matrix3::from_diagonal(&Vector3::new(14.0, 0.0, 0.0)))
    );
    assert_eq!(d.platform.gravity, Vector3::new(0.0, 0.0, -9.81));
    // E·S = E π r² = 1.1e11 · π · 0.006².
    let es = 110000000000.0 * std::f64::consts::PI * 0.006 * 0.006;
    assert!(close(d.axial_stiffness.as_ref().unwrap()[0], es));
    // No <application>: the winch's f_max = 720 N and the cable's minimum_load = 0.
    assert_eq!((d.bounds.min()[0], d.bounds.max()[0]), (0.0, 720.0));
    assert!(d.warnings.iter().any(|w| w.contains("f_max")));
    // With an <application>: its loads.
    let c = RobotDescription::load(data("wirecenter/CableMasterRobot.wcrfx")).unwrap();
    assert_eq!((c.bounds.min()[0], c.bounds.max()[0]), (40.0, 1000.0));
    assert_eq!(c.robot.cable_count(), 7);
}

#[test]
#[allow(
    clippy::approx_constant,
    reason = "0.707107 is the file's number, deliberately not 1/√2"
)]
fn wirecenter_orientations_are_used_as_written() {
    let d = RobotDescription::load(data("wirecenter/EXPO2015_Lucia.wcrfx")).unwrap();
    let q = d.robot.cables()[0].pulley.unwrap().orientation;
    // a11 = 0.707107, a12 = -0.707107, a21 = -0.707107, a22 = -0.707107, a33 = -1 (row i, column j).
    assert_eq!(
        q,
        Matrix3::new(
            0.707107, -0.707107, 0.0, -0.707107, -0.707107, 0.0, 0.0, -0.0, -1.0
        )
    );
    assert_eq!(d.robot.cables()[0].pulley.unwrap().radius, 0.01);
}

const WCRFX: &str = r#"<models version="0.31">
    <robot name="t" motionpattern="1R2T">
        <geometry>
            <chain id="a"><base x="1" y="1" z="0" radius="0.05" /><platform x="0.1" y="0.1" z="0" /></chain>
            <chain id="a"><base x="-1" y="1" z="0" radius="0.05" /><platform x="-0.1" y="0.1" z="0" /></chain>
            <chain id="b"><base x="-1" y="-1" z="0" radius="0.05" /><platform x="-0.1" y="-0.1" z="0" /></chain>
            <chain id="c"><base x="1" y="-1" z="0" radius="0.05" /><platform x="0.1" y="-0.1" z="0" /></chain>
        </geometry>
        <platform mass="2"><centerofgravity x="0" y="0.01" z="0" /></platform>
        <application min_cable_load="5" max_cable_load="50" />
    </robot>
</models>
"#;

#[test]
fn wirecenter_planar_and_errors() {
    let d = RobotDescription::parse_wcrfx(WCRFX, "t.wcrfx").unwrap();
    assert_eq!(d.robot.motion(), MotionPattern::Planar);
    assert!(d.robot.cables().iter().all(|c| c.pulley.is_none()));
    assert_eq!(d.cable_names[0], d.cable_names[1]);
    assert_eq!((d.bounds.min()[0], d.bounds.max()[0]), (5.0, 50.0));
    let msg = |t: &str| {
        RobotDescription::parse_wcrfx(t, "t.wcrfx")
            .unwrap_err()
            .to_string()
    };
    let m = msg(&WCRFX.replace("1R2T", "2R3T"));
    assert!(
        m.starts_with("t.wcrfx:2: <robot>: not modelled by cdpr: motionpattern 2R3T"),
        "{m}"
    );
    let m = msg(&WCRFX.replacen("y=\"1\" z=\"0\"", "y=\"1\" z=\"0.5\"", 1));
    assert!(m.starts_with("t.wcrfx:4: <base> attribute `z`"), "{m}");
    let m = msg(&WCRFX.replacen("x=\"1\"", "x=\"one\"", 1));
    assert!(
        m.starts_with("t.wcrfx:4: <base> attribute `x`: `one` is not a number"),
        "{m}"
    );
    let m = msg(&WCRFX.replacen("radius=\"0.05\"", "radius=\"0.05\" a11=\"1\"", 1));
    assert!(m.contains("attribute `a12`: missing"), "{m}");
    let m = msg(&WCRFX.replace("min_cable_load=\"5\"", "min_cable_load=\"500\""));
    assert!(
        m.starts_with("t.wcrfx:10: <application> attribute `min_cable_load`"),
        "{m}"
    );
    let m = msg("<models><robot>");
    assert!(m.starts_with("t.wcrfx:1: not well-formed XML"), "{m}");
}

#[test]
fn wcrfx_writer_refuses_what_it_cannot_hold() {
    let n = caspr("NIST_ROBOCRANE", None);
    let e = n.to_wcrfx("nist.wcrfx").unwrap_err();
    assert!(matches!(e, RobotFileError::Unrepresentable { .. }));
    assert!(
        e.to_string().contains("per-cable tension bounds differ"),
        "{e}"
    );
    // CASPR gravity is WireLib's; a TOML default gravity (9.80665) is reported as not written.
    let caroca = caspr("CAROCA", None);
    assert!(!caroca.wcrfx_losses().iter().any(|l| l.contains("gravity")));
    let tdpm = RobotDescription::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/robots/ipanema-like-8.toml"
    ))
    .unwrap();
    let _ = tdpm.wcrfx_losses();
}

/// 2DIPAnema2 declares `3R3T` for a planar layout of 4 cables: it is read as declared (spatial,
/// 6 DOF) with its 4 cables; kinematics works at a pose (the lengths are the anchor distances),
/// and analyses that balance a wrench refuse it by name (n = 4 < DOF = 6).
#[test]
fn fewer_cables_than_dof_is_read_and_kinematics_works() {
    let m = RobotDescription::load(data("wirecenter/2DIPAnema2.wcrfx")).unwrap();
    assert_eq!(m.robot.motion(), MotionPattern::Spatial);
    assert_eq!(m.robot.cable_count(), 4);
    assert_eq!(m.robot.redundancy(), -2);
    let robot = m.robot.without_pulleys();
    let pose = Pose::spatial(Vector3::new(0.01, -0.02, 0.0), 0.0, 0.0, 0.1);
    let kin = robot.inverse_kinematics(&pose).unwrap();
    for (c, l) in robot.cables().iter().zip(kin.lengths()) {
        let b = pose.position + pose.rotation * c.platform;
        assert!((l - (c.frame - b).norm()).abs() < 1e-12);
    }
    assert_eq!(kin.wrench_matrix().shape(), (6, 4));
    let e = cdpr_wrench::require_enough_cables(&m.robot, "tension distribution").unwrap_err();
    assert_eq!(
        e.to_string(),
        "tension distribution needs at least as many cables as degrees of freedom (n ≥ DOF); this spatial robot has n = 4 cables for DOF = 6 (its cable lengths and W are still computed by `kinematics`)"
    );
}

/// CASPR's Passive_springs_planar (Duan, Vashista & Agrawal 2015): a `PLANAR_YZ` joint (y, z, θ
/// about x) with 4 actuated cables and 4 `cable_passive_linear_spring`s (K = 5 N/m, l0 = 1 m),
/// 3 kg under CASPR's gravity 9.81 m/s² along −z, which lies in this vertical plane. Lengths
/// and the load wrench (weight + springs) at a pose, by hand in the file's own coordinates.
#[test]
fn passive_springs_planar_yz_by_hand() {
    let d = caspr("Passive_springs_planar", None);
    assert_eq!(d.robot.motion(), MotionPattern::Planar);
    assert_eq!(d.robot.cable_count(), 4);
    let springs = d.passive_springs.as_ref().expect("four passive springs");
    assert_eq!(springs.count(), 4);
    assert_eq!(springs.stiffness(), &[5.0; 4]);
    assert_eq!(springs.free_length(), &[1.0; 4]);
    assert_eq!(d.passive_spring_names[0].as_deref(), Some("spring 1"));
    // Gravity −z of the file is −y of cdpr's plane (file y, z → cdpr x, y).
    assert_eq!(d.platform.gravity, Vector3::new(0.0, -9.81, 0.0));
    assert_eq!(d.platform.mass, 3.0);
    // Ixx about the joint's x axis (normal to the plane) becomes Izz.
    assert_eq!(d.inertia.unwrap()[(2, 2)], 0.0925);
    assert_eq!(d.bounds.max().as_slice(), &[60.0; 4]);

    // At (y, z, θ) = (0.2, −0.1, 0.3), CASPR's frame: platform point b = (0, y, z) + R_x(θ) r.
    let (y, z, th) = (0.2, -0.1, 0.3f64);
    let point = |r: [f64; 3]| {
        [
            0.0,
            y + th.cos() * r[1] - th.sin() * r[2],
            z + th.sin() * r[1] + th.cos() * r[2],
        ]
    };
    let dist = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    let l = lengths(&d, &[y, z, th]);
    // cable 1: frame (0, −2, 3), platform (0, −0.3, 0.05); cable 3: (0, 1.5, −3), (0, 0.3, −0.05).
    assert!(close(
        l[0],
        dist([0.0, -2.0, 3.0], point([0.0, -0.3, 0.05]))
    ));
    assert!(close(
        l[2],
        dist([0.0, 1.5, -3.0], point([0.0, 0.3, -0.05]))
    ));
    // The load wrench (f_y, f_z, τ_x in the file's axes = f_x, f_y, τ_z in cdpr's):
    // weight (0, −3·9.81, 0) at the centre of mass (the joint) plus, per spring,
    // f = 5 (l − 1) along u = (a − b)/l with moment (b − p) × f u.
    let spring_file = [
        ([0.0, 4.0, 3.0], [0.0, 0.15, 0.1]),
        ([0.0, -4.0, 3.0], [0.0, -0.15, 0.1]),
        ([0.0, 1.0, 5.0], [0.0, 0.15, -0.1]),
        ([0.0, -1.0, 5.0], [0.0, -0.15, -0.1]),
    ];
    let mut expected = [0.0, -3.0 * 9.81, 0.0];
    for (a, r) in spring_file {
        let b = point(r);
        let l = dist(a, b);
        let f = 5.0 * (l - 1.0);
        let (uy, uz) = ((a[1] - b[1]) / l, (a[2] - b[2]) / l);
        let (ry, rz) = (b[1] - y, b[2] - z);
        expected[0] += f * uy;
        expected[1] += f * uz;
        expected[2] += f * (ry * uz - rz * uy);
    }
    let pose = Pose::from_coordinates(MotionPattern::Planar, &[y, z, th]).unwrap();
    let w = d.load_wrench(&pose).unwrap();
    for (a, e) in w.iter().zip(expected) {
        assert!((a - e).abs() < 1e-12, "{a} vs {e}");
    }
    // The springs carry a real part of the weight here: more than 10 N upwards.
    assert!(expected[1] - (-3.0 * 9.81) > 10.0, "{expected:?}");
}

//! `cdpr trajectory --time-law … --dynamics`, `cdpr simulate` and `--criteria dynamic`
//! (issue 28 contract: flag and JSON names).

use crate::common;

use common::{cdpr, json, robot};

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The timed JSON fields, the quintic peak speed 1.875 Δ/T, rest at both ends, and the
/// inertial wrench M ẍ (a point of the 8-cable robot moving along x: m ẍ).
#[test]
fn timed_trajectory_json() {
    let r = robot("ipanema-like-8.toml");
    let v = json(&[
        "trajectory",
        &r,
        "--from",
        "-0.2,0,1,0,0,0",
        "--to",
        "0.2,0,1,0,0,0",
        "--time-law",
        "quintic",
        "--duration",
        "2",
        "--dt",
        "0.5",
        "--dynamics",
        "--json",
    ]);
    assert_eq!(floats(&v["t"]), [0.0, 0.5, 1.0, 1.5, 2.0]);
    for key in [
        "velocity",
        "acceleration",
        "cable_lengths",
        "cable_speeds",
        "cable_accelerations",
        "inertial_wrench",
        "tensions",
    ] {
        assert_eq!(v[key].as_array().unwrap().len(), 5, "{key}");
    }
    let vel = floats(&v["velocity"][2]);
    assert!((vel[0] - 1.875 * 0.4 / 2.0).abs() < 1e-12);
    assert_eq!(floats(&v["velocity"][0]), [0.0; 6]);
    // m = 5 kg: inertial force m ẍ at t = 0.5 s (τ = 0.25: s̈ = 60τ(1 − 3τ + 2τ²) Δ/T²).
    let tau: f64 = 0.25;
    let sdd = 60.0 * tau * (1.0 - 3.0 * tau + 2.0 * tau * tau) * 0.4 / 4.0;
    assert!((floats(&v["inertial_wrench"][1])[0] - 5.0 * sdd).abs() < 1e-9);
    // l̇ = −Wᵀẋ: at rest, zero.
    assert!(
        floats(&v["cable_speeds"][0])
            .iter()
            .all(|x| x.abs() < 1e-15)
    );
    assert_eq!(v["feasible_count"], 5);
    // Without --dynamics: no inertial wrench.
    let q = json(&[
        "trajectory",
        &r,
        "--from",
        "-0.2,0,1,0,0,0",
        "--to",
        "0.2,0,1,0,0,0",
        "--time-law",
        "cubic",
        "--duration",
        "2",
        "--json",
    ]);
    assert!(q.get("inertial_wrench").is_none());
    assert_eq!(q["t"].as_array().unwrap().len(), 201);
}

/// Bad input exits 2 naming the key and the value.
#[test]
fn timed_trajectory_bad_input() {
    let r = robot("ipanema-like-8.toml");
    let base = [
        "trajectory",
        &r,
        "--from",
        "0,0,1,0,0,0",
        "--to",
        "0.2,0,1,0,0,0",
    ];
    for (extra, needle) in [
        (
            vec!["--time-law", "cubic", "--duration", "-1"],
            "--duration",
        ),
        (
            vec!["--time-law", "cubic", "--duration", "1", "--dt", "0"],
            "--dt",
        ),
        (
            vec![
                "--time-law",
                "trapezoid",
                "--duration",
                "1",
                "--max-acceleration",
                "0.1",
            ],
            "max-acceleration = 0.1",
        ),
        (
            vec![
                "--time-law",
                "quintic",
                "--duration",
                "1",
                "--max-velocity",
                "0.1",
            ],
            "max-velocity = 0.1",
        ),
    ] {
        let out = cdpr().args(base).args(&extra).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{extra:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{extra:?}: {err}");
    }
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("w.toml");
    std::fs::write(
        &file,
        "[[waypoints]]\npose = [0, 0, 1, 0, 0, 0]\ntime = 0.0\n[[waypoints]]\npose = [0.2, 0, 1, 0, 0, 0]\ntime = 1.0\n[[waypoints]]\npose = [0.2, 0.2, 1, 0, 0, 0]\ntime = 0.5\n",
    )
    .unwrap();
    let out = cdpr()
        .args([
            "trajectory",
            &r,
            "--waypoints",
            file.to_str().unwrap(),
            "--time-law",
            "cubic",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("waypoints[2].time = 0.5"));
}

/// Free fall with zero tensions: z = z₀ − g t²/2 (RK4 exact on quadratics).
#[test]
fn simulate_free_fall() {
    let r = robot("ipanema-like-8.toml");
    let v = json(&[
        "simulate",
        &r,
        "--from",
        "0,0,1,0,0,0",
        "--duration",
        "0.3",
        "--dt",
        "0.01",
        "--tensions",
        "0,0,0,0,0,0,0,0",
        "--json",
    ]);
    let t = floats(&v["t"]);
    assert_eq!(t.len(), 31);
    for (k, &tk) in t.iter().enumerate() {
        let z = floats(&v["poses"][k])[2];
        assert!(
            (z - (1.0 - 0.5 * 9.80665 * tk * tk)).abs() < 1e-12,
            "{tk}: {z}"
        );
    }
    for key in ["velocities", "accelerations", "tensions"] {
        assert_eq!(v[key].as_array().unwrap().len(), 31, "{key}");
    }
    let out = cdpr()
        .args([
            "simulate",
            &r,
            "--from",
            "0,0,1,0,0,0",
            "--duration",
            "1",
            "--dt",
            "0.1",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "no drive is a usage error");
}

/// `--criteria dynamic`: the two-cable point mass's closed form at grid points.
#[test]
fn dynamic_workspace_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("two.toml");
    std::fs::write(
        &file,
        "name = \"two\"\nmotion = \"point2\"\n[tension]\nmin = 0.0\nmax = 1e6\n[platform]\nmass = 3.0\ngravity = [0.0, -9.81]\n[[cables]]\nframe = [0.0, 1.5]\n[[cables]]\nframe = [2.0, 1.5]\n",
    )
    .unwrap();
    let points = dir.path().join("p.csv");
    let out = cdpr()
        .args([
            "workspace",
            file.to_str().unwrap(),
            "--criteria",
            "dynamic",
            "--acceleration-box",
            "2,1",
            "--box",
            "-0.5,2.5,-1,1.4",
            "--grid",
            "20",
            "--points",
            points.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&points).unwrap();
    let mut checked = 0;
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (x, y): (f64, f64) = (f[0].parse().unwrap(), f[1].parse().unwrap());
        let feasible = f[2].trim() == "true" || f[2].trim() == "1";
        let mut slack = f64::INFINITY;
        for (ax, ay) in [(-2.0, -1.0), (-2.0, 1.0), (2.0, -1.0), (2.0, 1.0)] {
            let xi = x + (1.5 - y) * ax / (9.81 + ay);
            slack = slack.min(xi).min(2.0 - xi);
        }
        if slack.abs() > 1e-9 && (1.5 - y).abs() > 1e-9 {
            assert_eq!(feasible, slack > 0.0, "({x}, {y})");
            checked += 1;
        }
    }
    assert!(checked > 300);
}

/// The 8-cable robot with a winch on every cable (r = 0.05 m, G = 10, J_m = 2e-4 kg·m²).
fn robot_with_winches(dir: &std::path::Path, max_torque: f64) -> String {
    let text = std::fs::read_to_string(robot("ipanema-like-8.toml")).unwrap();
    let winch = format!(
        "axial_stiffness = 60000.0\nwinch = {{ drum_radius = 0.05, gear_ratio = 10.0, motor_inertia = 2e-4, max_torque = {max_torque}, max_speed = 300.0 }}"
    );
    let text = text.replace("axial_stiffness = 60000.0", &winch);
    assert_eq!(text.matches("winch = ").count(), 8);
    let file = dir.join(format!("winches-{max_torque}.toml"));
    std::fs::write(&file, text).unwrap();
    file.display().to_string()
}

/// The drive-train fields: τ = (r/G) t − J_m (G/r) l̈ and ω = −(G/r) l̇ against the JSON's own
/// tensions and cable rates, the peak, and the verdict against max_torque.
#[test]
fn timed_trajectory_motor_torques_and_speeds() {
    let dir = tempfile::tempdir().unwrap();
    let args = |file: &str| -> Vec<String> {
        [
            "trajectory",
            file,
            "--from",
            "-0.3,0,0.8,0,0,0",
            "--to",
            "0.3,0.2,1.2,0,0,0.1",
            "--time-law",
            "quintic",
            "--duration",
            "1",
            "--dt",
            "0.05",
            "--dynamics",
            "--json",
        ]
        .map(String::from)
        .to_vec()
    };
    let file = robot_with_winches(dir.path(), 100.0);
    let a = args(&file);
    let v = json(&a.iter().map(String::as_str).collect::<Vec<_>>());
    let (r, g, j) = (0.05, 10.0, 2e-4);
    let samples = v["t"].as_array().unwrap().len();
    assert_eq!(samples, 21);
    let mut peak = [0.0f64; 8];
    for k in 0..samples {
        let t = floats(&v["tensions"][k]);
        let l_dot = floats(&v["cable_speeds"][k]);
        let l_dd = floats(&v["cable_accelerations"][k]);
        let tau = floats(&v["motor_torques"][k]);
        let omega = floats(&v["motor_speeds"][k]);
        for i in 0..8 {
            let expected = r / g * t[i] - j * g / r * l_dd[i];
            assert!((tau[i] - expected).abs() < 1e-9, "k {k} cable {i}");
            assert!((omega[i] + g / r * l_dot[i]).abs() < 1e-9);
            peak[i] = peak[i].max(tau[i].abs());
        }
    }
    let reported = floats(&v["motor_peak_torque"]);
    for i in 0..8 {
        assert!((reported[i] - peak[i]).abs() < 1e-12);
    }
    assert_eq!(v["motors_within_limits"], true);
    assert_eq!(floats(&v["motor_max_torque"]), [100.0; 8]);
    // A torque limit below the peak: the verdict is no, naming the motor.
    let lowest = peak.iter().cloned().fold(f64::INFINITY, f64::min);
    let tight = robot_with_winches(dir.path(), 0.5 * lowest);
    let a = args(&tight);
    let v = json(&a.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(v["motors_within_limits"], false);
    let violations = v["motor_limit_violations"].as_array().unwrap();
    assert_eq!(violations.len(), 8, "{violations:?}");
    assert!(
        violations[0]
            .as_str()
            .unwrap()
            .starts_with("motor 1: |τ| = ")
    );
    // The plots are written; without winches the torque plot is a usage error.
    let torque = dir.path().join("torques.png");
    let speed = dir.path().join("speeds.png");
    let mut a = args(&file);
    a.pop();
    a.extend([
        "--motor-torque-plot".into(),
        torque.display().to_string(),
        "--cable-speed-plot".into(),
        speed.display().to_string(),
    ]);
    let out = cdpr().args(&a).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("the motors can do it"), "{text}");
    assert!(std::fs::metadata(&torque).unwrap().len() > 1000);
    assert!(std::fs::metadata(&speed).unwrap().len() > 1000);
    let plain = robot("ipanema-like-8.toml");
    let mut a = args(&plain);
    a.extend(["--motor-torque-plot".into(), torque.display().to_string()]);
    let out = cdpr().args(&a).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("winch"));
}

/// `--replay FILE.html`: a self-contained page with every sample's pose and tensions, which
/// draws without a script error in a headless browser (where one is installed).
#[test]
fn timed_trajectory_replay_page() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("replay.html");
    let r = robot("ipanema-like-8.toml");
    let out = cdpr()
        .args([
            "trajectory",
            &r,
            "--from",
            "-0.3,0,0.8,0,0,0",
            "--to",
            "0.3,0.2,1.2,0,0,0.1",
            "--time-law",
            "quintic",
            "--duration",
            "1",
            "--dt",
            "0.1",
            "--dynamics",
            "--replay",
            page.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(&page).unwrap();
    for network in ["src=\"http", "href=\"http", "<link", "fetch("] {
        assert!(!html.contains(network), "{network}");
    }
    assert!(html.contains("\"t\":[0.0,0.1,"), "times");
    // The colour scale ends at the largest tension along the trajectory (t_max = 1000 N).
    let t_max: f64 = html
        .split("\"tMax\":")
        .nth(1)
        .unwrap()
        .split([',', '}'])
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(t_max > 10.0 && t_max < 1000.0, "{t_max}");
    let Some(b) = crate::viewer::browser() else {
        println!("note: no Chromium found (set CDPR_CHROMIUM): the replay page was not loaded");
        return;
    };
    let dom = crate::viewer::dump_dom(&b, &page);
    assert!(
        dom.contains("data-state=\"ok\">replayed 11 frames of 8 cables"),
        "{}",
        dom.lines()
            .filter(|l| l.contains("cdpr-status"))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// Issue 25: `cdpr trajectory --json` (untimed, timed with dynamics and a drive train) and
/// `cdpr simulate --json` are the serialised reports of their `cdpr-api` requests.
#[test]
fn trajectory_and_simulate_print_their_reports() {
    use cdpr::api::simulate::SimulateRequest;
    use cdpr::api::timed::TimedSettings;
    use cdpr::api::trajectory::TrajectoryRequest;
    use cdpr::api::{Robot, RobotSource};
    let dir = tempfile::tempdir().unwrap();
    let file = robot_with_winches(dir.path(), 100.0);
    let api_robot =
        || Robot::from_source(RobotSource::toml(std::fs::read_to_string(&file).unwrap())).unwrap();
    let (from, to) = (
        vec![-0.3, 0.0, 0.8, 0.0, 0.0, 0.0],
        vec![0.3, 0.2, 1.2, 0.0, 0.0, 0.1],
    );
    let mut r = TrajectoryRequest::segment(api_robot(), from.clone(), to.clone());
    r.samples = Some(7);
    let cli = json(&[
        "trajectory",
        &file,
        "--from",
        "-0.3,0,0.8,0,0,0",
        "--to",
        "0.3,0.2,1.2,0,0,0.1",
        "--samples",
        "7",
        "--json",
    ]);
    assert_eq!(serde_json::to_value(r.run().unwrap()).unwrap(), cli);
    let mut r = TrajectoryRequest::segment(api_robot(), from.clone(), to);
    r.timing = TimedSettings {
        time_law: Some("quintic".parse().unwrap()),
        duration: Some(1.0),
        dt: Some(0.05),
        dynamics: true,
        ..TimedSettings::default()
    };
    let timed = serde_json::to_value(r.run().unwrap()).unwrap();
    let cli = json(&[
        "trajectory",
        &file,
        "--from",
        "-0.3,0,0.8,0,0,0",
        "--to",
        "0.3,0.2,1.2,0,0,0.1",
        "--time-law",
        "quintic",
        "--duration",
        "1",
        "--dt",
        "0.05",
        "--dynamics",
        "--json",
    ]);
    assert_eq!(timed, cli);
    assert!(cli.get("motor_torques").is_some() && cli.get("inertial_wrench").is_some());
    let s = SimulateRequest::with_tensions(api_robot(), from, vec![20.0; 8], 0.1, 0.02);
    let cli = json(&[
        "simulate",
        &file,
        "--from",
        "-0.3,0,0.8,0,0,0",
        "--tensions",
        "20,20,20,20,20,20,20,20",
        "--duration",
        "0.1",
        "--dt",
        "0.02",
        "--json",
    ]);
    assert_eq!(serde_json::to_value(s.run().unwrap()).unwrap(), cli);
}

fn caspr_data(rel: &str) -> String {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cdpr-io/tests/data/caspr")
        .join(rel)
        .to_string_lossy()
        .into_owned()
}

/// `cdpr trajectory ROBOT --trajectory NAME_trajectories.xml --trajectory-id ID`: CASPR's
/// IPAnema 2 `traj_z_up` (a quintic lift from z = 0.5 to 2 m in 1 s, time_step 0.01 s) with
/// its inverse dynamics: the JSON's times, ends, peak speed 1.875 Δ/T and m z̈ in the inertial
/// wrench.
#[test]
fn caspr_trajectory_json() {
    let dir = "spatial_manipulators/IPAnema_2";
    let v = json(&[
        "trajectory",
        &caspr_data(&format!("{dir}/IPAnema_2_cables.xml")),
        "--trajectory",
        &caspr_data(&format!("{dir}/IPAnema_2_trajectories.xml")),
        "--trajectory-id",
        "traj_z_up",
        "--dynamics",
        "--json",
    ]);
    assert_eq!(v["time_law"], "quintic_spline_trajectory");
    assert_eq!(v["trajectory_id"], "traj_z_up");
    let t = floats(&v["t"]);
    assert_eq!(t.len(), 101);
    assert!((t[37] - 0.37).abs() < 1e-12 && t[100] == 1.0);
    assert_eq!(floats(&v["poses"][0]), [0.0, 0.0, 0.5, 0.0, 0.0, 0.0]);
    assert_eq!(floats(&v["poses"][100]), [0.0, 0.0, 2.0, 0.0, 0.0, 0.0]);
    assert!((floats(&v["velocity"][50])[2] - 1.875 * 1.5).abs() < 1e-12);
    // z̈ at τ = 0.25: 60τ(1 − 3τ + 2τ²) Δ/T²; the force is m z̈ (the orientation does not move).
    let tau: f64 = 0.25;
    let zdd = 60.0 * tau * (1.0 - 3.0 * tau + 2.0 * tau * tau) * 1.5;
    assert!((floats(&v["acceleration"][25])[2] - zdd).abs() < 1e-9);
    let w = floats(&v["inertial_wrench"][25]);
    let mass = w[2] / zdd;
    assert!(
        mass > 0.0 && w[0].abs() < 1e-9 && w[1].abs() < 1e-9,
        "{w:?}"
    );
    assert_eq!(v["tensions"].as_array().unwrap().len(), 101);
}

/// Bad CASPR trajectory input: exit 2 naming the element, the id, or the flag.
#[test]
fn caspr_trajectory_bad_input() {
    let dir = "spatial_manipulators/IPAnema_1";
    let robot = caspr_data(&format!("{dir}/IPAnema_1_cables.xml"));
    let file = caspr_data(&format!("{dir}/IPAnema_1_trajectories.xml"));
    let run = |extra: &[&str]| {
        let out = cdpr()
            .args(["trajectory", &robot, "--trajectory", &file])
            .args(extra)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{extra:?}");
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let e = run(&["--trajectory-id", "traj_9"]);
    assert!(
        e.contains("IPAnema_1_trajectories.xml:4: <joint_trajectories>: no joint trajectory with id `traj_9` (the file has: traj_1, traj_z_up)"),
        "{e}"
    );
    let e = run(&[]);
    assert!(
        e.contains("give --trajectory-id (the file has 2 joint trajectories: traj_1, traj_z_up)"),
        "{e}"
    );
    let e = run(&["--trajectory-id", "traj_1", "--duration", "2"]);
    assert!(
        e.contains("--duration does not apply to --trajectory"),
        "{e}"
    );
    let e = run(&["--trajectory-id", "traj_1", "--time-law", "cubic"]);
    assert!(
        e.contains("--time-law") && e.contains("--trajectory"),
        "{e}"
    );
    // A bad file: a cubic point without q_dot.
    let tmp = tempfile::tempdir().unwrap();
    let bad = tmp.path().join("bad_trajectories.xml");
    std::fs::write(
        &bad,
        "<trajectories>\n<joint_trajectories>\n<cubic_spline_trajectory id=\"a\" time_definition=\"relative\" time_step=\"0.1\">\n<points>\n<point><q>0 0 1 0 0 0</q></point>\n<point time=\"1\"><q>0 0 1.2 0 0 0</q><q_dot>0 0 0 0 0 0</q_dot></point>\n</points>\n</cubic_spline_trajectory>\n</joint_trajectories>\n</trajectories>\n",
    )
    .unwrap();
    let out = cdpr()
        .args(["trajectory", &robot, "--trajectory", bad.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(
        e.contains("bad_trajectories.xml:5: <point>: missing <q_dot>"),
        "{e}"
    );
}

/// An inertia that is not symmetric positive definite (issue 28, bad input): exit 2 naming the
/// key and the value, for the dynamics and the simulation alike.
#[test]
fn an_inertia_that_is_not_positive_definite_exits_2_naming_key_and_value() {
    let text = std::fs::read_to_string(robot("ipanema-like-8.toml")).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("inertia = "))
        .expect("the fixture gives an inertia");
    let dir = tempfile::tempdir().unwrap();
    for (inertia, why) in [
        (
            "[[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]",
            "positive definite",
        ),
        (
            "[[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]",
            "symmetric",
        ),
    ] {
        let file = dir.path().join("bad.toml");
        std::fs::write(&file, text.replace(line, &format!("inertia = {inertia}"))).unwrap();
        let file = file.to_str().unwrap();
        for args in [
            vec![
                "trajectory",
                file,
                "--from",
                "0,0,1,0,0,0",
                "--to",
                "0.1,0,1,0,0,0",
                "--time-law",
                "quintic",
                "--duration",
                "1",
                "--dt",
                "0.1",
                "--dynamics",
            ],
            vec![
                "simulate",
                file,
                "--from",
                "0,0,1,0,0,0",
                "--duration",
                "0.1",
                "--dt",
                "0.01",
            ],
        ] {
            let out = cdpr().args(&args).output().unwrap();
            assert_eq!(out.status.code(), Some(2), "{args:?}");
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(err.contains("inertia") && err.contains(inertia), "{err}");
            assert!(err.contains(why), "{why}: {err}");
        }
    }
}

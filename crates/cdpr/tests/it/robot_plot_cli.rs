//! `cdpr kinematics --plot` and `cdpr tension --plot` (issue 25): the robot drawn at the pose,
//! anchors under the cables' names, and for `tension` every cable's tension on its anchor's
//! label (SVG/PNG) or its cable coloured by it (HTML, the tensions of the JSON in the page).

use crate::common::{cdpr, json, robot};

/// The numbers `v` of the labels `NAME: v N` in an SVG (the first of each name).
fn tension_labels(svg: &str, names: &[&str]) -> Vec<f64> {
    names
        .iter()
        .map(|name| {
            let key = format!("{name}: ");
            let start = svg
                .find(&key)
                .unwrap_or_else(|| panic!("no label {key} in the SVG"));
            let rest = &svg[start + key.len()..];
            let end = rest.find(" N").expect("a tension in N");
            rest[..end].parse().expect("a number")
        })
        .collect()
}

#[test]
fn tension_plot_labels_each_anchor_with_its_cables_tension() {
    let dir = tempfile::tempdir().unwrap();
    let path = robot("spidercam-like-4.toml");
    let path = path.as_str();
    let svg_path = dir.path().join("tensions.svg");
    let svg_file = svg_path.to_str().unwrap();
    let args = [
        "tension", path, "--pose", "10,-5,12", "--json", "--plot", svg_file,
    ];
    let report = json(&args);
    assert_eq!(report["feasible"], true);
    let expected: Vec<f64> = report["tensions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect();
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let drawn = tension_labels(&svg, &["NE", "NW", "SW", "SE"]);
    for (d, e) in drawn.iter().zip(&expected) {
        assert!(
            (d - e).abs() <= 5e-4 * e.abs(),
            "label {d} N, JSON {e} N (4 digits)"
        );
    }
    assert!(
        svg.contains("method l2, feasible"),
        "the verdict under the title"
    );
    // A figure of the robot alone speaks of no workspace and draws no search box.
    for word in ["misses the workspace", "search box", "blue: workspace"] {
        assert!(!svg.contains(word), "robot-only figure says {word:?}");
    }
    assert!(
        svg.contains("grey: cables at the pose"),
        "the robot's colour key"
    );
    // The HTML page: the replay view of one frame, cables coloured by the same tensions.
    let html_path = dir.path().join("tensions.html");
    let html_args = [
        "tension",
        path,
        "--pose",
        "10,-5,12",
        "--plot",
        html_path.to_str().unwrap(),
    ];
    cdpr().args(html_args).assert().success();
    let html = std::fs::read_to_string(&html_path).unwrap();
    let data = html
        .split("\"tensions\":")
        .nth(1)
        .expect("tensions in the page");
    let list = &data[..data.find("]]").expect("one frame") + 2];
    let page: Vec<Vec<f64>> = serde_json::from_str(list).unwrap();
    assert_eq!(page, vec![expected]);
}

#[test]
fn kinematics_plot_draws_2d_and_3d_robots_with_their_anchor_names() {
    let dir = tempfile::tempdir().unwrap();
    // A planar robot seen from +z: every anchor labelled A1–A4 (the file names no cable).
    let planar = dir.path().join("tdpm.svg");
    let tdpm = robot("tdpm-4.toml");
    let tdpm = tdpm.as_str();
    cdpr()
        .args(["kinematics", tdpm, "--pose", "0.1,0.2,0.1", "--plot"])
        .arg(&planar)
        .assert()
        .success();
    let svg = std::fs::read_to_string(&planar).unwrap();
    for label in ["A1", "A2", "A3", "A4"] {
        assert!(
            svg.contains(&format!("\n{label}\n")),
            "{label} in the planar view"
        );
    }
    assert!(svg.contains("tdpm-4 at pose (0.1 m, 0.2 m, 0.1 rad)"));
    // A 3-D robot: the isometric view (PNG, SVG) and the HTML viewer, named anchors.
    let spidercam = robot("spidercam-like-4.toml");
    let spidercam = spidercam.as_str();
    for ext in ["png", "svg", "html"] {
        let out = dir.path().join(format!("spidercam.{ext}"));
        cdpr()
            .args(["kinematics", spidercam, "--pose", "10,-5,12", "--plot"])
            .arg(&out)
            .assert()
            .success();
        let bytes = std::fs::read(&out).unwrap();
        assert!(bytes.len() > 1000, "{ext}: {} bytes", bytes.len());
        if ext != "png" {
            let text = String::from_utf8(bytes).unwrap();
            assert!(
                text.contains("NE") && text.contains("SW"),
                "{ext}: anchor names"
            );
        }
    }
}

#[test]
fn plot_with_an_unknown_extension_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("robot.txt");
    for command in ["kinematics", "tension"] {
        let o = cdpr()
            .args([
                command,
                robot("tdpm-4.toml").as_str(),
                "--pose",
                "0,0,0",
                "--plot",
            ])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{command}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("--plot") && err.contains(".svg, .png or .html"),
            "{err}"
        );
        assert!(!out.exists());
    }
}

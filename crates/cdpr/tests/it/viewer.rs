//! The 3-D views: the self-contained HTML viewer (loaded in headless Chromium where one is
//! installed: the page must draw without a script error) and the isometric PNG/SVG figure with
//! three sections, on meshes built here (an octahedron, the grid surface of a ball) and through
//! the CLI on the 8-cable example.

use crate::common;

use cdpr::kinematics::Pose;
use cdpr::plot::{Scene, grid_surface};
use cdpr::workspace::{Grid, GridWorkspace, Region};
use common::{cdpr, robot};
use nalgebra::Vector3;
use std::path::Path;
use std::process::Command;

/// The regular octahedron |x| + |y| + |z| ≤ 1 around (0, 0, 1): 6 vertices, 8 outward triangles.
fn octahedron() -> Scene {
    let v = vec![
        [1.0, 0.0, 1.0],
        [-1.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
        [0.0, -1.0, 1.0],
        [0.0, 0.0, 2.0],
        [0.0, 0.0, 0.0],
    ];
    let t = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    let desc = cdpr::RobotDescription::load(robot("ipanema-like-8.toml")).unwrap();
    Scene {
        title: "octahedron test <mesh> & \"quotes\" </script>".into(),
        vertices: v,
        triangles: t,
        region: ([-2.0, -1.5, 0.0], [2.0, 1.5, 2.0]),
        legend: vec!["volume 4/3 m³ (exact)".into(), "test scene".into()],
        mesh_label: "octahedron".into(),
        ..Scene::default()
    }
    .with_robot(
        &desc.robot,
        &Pose::spatial(Vector3::new(0.3, 0.2, 1.0), 0.1, 0.0, 0.2),
        None,
    )
}

/// A browser to test with: $CDPR_CHROMIUM, or chromium / chromium-browser / google-chrome on
/// the PATH.
pub(crate) fn browser() -> Option<String> {
    if let Ok(b) = std::env::var("CDPR_CHROMIUM") {
        return Some(b);
    }
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|b| {
            Command::new(b)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
        .map(String::from)
}

/// Loads `page` headless and returns the DOM after the scripts ran.
pub(crate) fn dump_dom(browser: &str, page: &Path) -> String {
    let profile = tempfile::tempdir().unwrap();
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-first-run",
            "--window-size=1200,800",
            "--virtual-time-budget=3000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn html_page_is_self_contained_and_escapes_its_data() {
    let html = cdpr::plot::viewer::html(&octahedron());
    for network in ["src=\"http", "href=\"http", "<link", "import ", "fetch("] {
        assert!(!html.contains(network), "{network}");
    }
    // The data cannot close its script element, the title is escaped.
    assert_eq!(html.matches("</script>").count(), 2);
    assert!(
        html.contains(
            "<title>octahedron test &lt;mesh&gt; &amp; \"quotes\" &lt;/script&gt;</title>"
        )
    );
    assert!(html.contains("\"triangles\":[[0,2,4]"));
}

#[test]
fn html_page_draws_in_a_headless_browser() {
    let Some(b) = browser() else {
        println!("note: no Chromium found (set CDPR_CHROMIUM): the HTML viewer was not loaded");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("octahedron.html");
    cdpr::plot::viewer::save_html(&octahedron(), &page).unwrap();
    let dom = dump_dom(&b, &page);
    assert!(
        dom.contains("id=\"cdpr-status\" data-state=\"ok\">rendered 8 triangles"),
        "{}",
        dom.lines()
            .filter(|l| l.contains("cdpr-status"))
            .collect::<Vec<_>>()
            .join("\n")
    );
    // A page whose script fails reports it (the check can fail).
    let broken = std::fs::read_to_string(&page)
        .unwrap()
        .replace("\"vertices\":", "\"vertices_gone\":");
    std::fs::write(&page, broken).unwrap();
    let dom = dump_dom(&b, &page);
    assert!(
        dom.contains("data-state=\"error\""),
        "broken page not reported"
    );
}

/// The grid surface of the ball ‖u − c‖ ≤ 0.8 drawn as PNG and SVG: right size, sections and
/// axis labels with units present.
#[test]
fn iso_figure_of_a_ball() {
    let grid = Grid::new(
        12,
        Region::cuboid(Vector3::new(-2.0, -1.5, 0.0), Vector3::new(2.0, 1.5, 2.0)),
    );
    let c = Vector3::new(0.0, 0.0, 1.0);
    let feasible = (0..grid.point_count(3))
        .map(|i| (grid.point(3, i) - c).norm() <= 0.8)
        .collect();
    let ws = GridWorkspace::from_verdicts(grid, 3, feasible);
    let (vertices, triangles) = grid_surface(&ws);
    let scene = Scene {
        title: "ball".into(),
        vertices,
        triangles,
        region: ([-2.0, -1.5, 0.0], [2.0, 1.5, 2.0]),
        ..octahedron()
    };
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("ball.png");
    cdpr::plot::save_scene(&scene, &png).unwrap();
    let bytes = std::fs::read(&png).unwrap();
    assert!(bytes.starts_with(b"\x89PNG"));
    let (w, h) = (
        u32::from_be_bytes(bytes[16..20].try_into().unwrap()),
        u32::from_be_bytes(bytes[20..24].try_into().unwrap()),
    );
    assert_eq!((w, h), (1300, 1100));
    let svg = dir.path().join("ball.svg");
    cdpr::plot::save_scene(&scene, &svg).unwrap();
    let text = std::fs::read_to_string(&svg).unwrap();
    for label in [
        "isometric view",
        "section z = 1 m",
        "section y = 0.2 m",
        "section x = 0.3 m",
        "x (m)",
        "z (m)",
        "A1",
        "A8",
    ] {
        assert!(text.contains(label), "{label}");
    }
    assert!(!text.contains("misses the workspace"));
}

#[test]
fn cli_writes_the_viewer_and_the_iso_figure_for_spatial_robots() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("ws.html");
    let png = dir.path().join("ws.png");
    for p in [&page, &png] {
        cdpr()
            .args([
                "workspace",
                &robot("ipanema-like-8.toml"),
                "--grid",
                "6",
                "--plot",
            ])
            .arg(p)
            .assert()
            .success();
    }
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("volume 20.") || html.contains("volume "));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    if let Some(b) = browser() {
        assert!(dump_dom(&b, &page).contains("data-state=\"ok\""));
    }
    // A planar robot has no 3-D page.
    let out = cdpr()
        .args(["workspace", &robot("tdpm-4.toml"), "--plot"])
        .arg(dir.path().join("planar.html"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("3-D"));
}

/// The force polytope view (a cube of forces with its inscribed ball, no robot) draws in a
/// headless browser without a script error.
#[test]
fn force_polytope_page_draws_in_a_headless_browser() {
    let aws = cdpr::polytope::hyperplane_shifting::available_wrench_set(
        &nalgebra::DMatrix::identity(3, 3),
        &cdpr::tension::TensionBounds::uniform(3, 0.0, 2.0).unwrap(),
    )
    .unwrap();
    let scene = cdpr::plot::force_polytope_scene(&aws, [1.0; 3], 1.0).unwrap();
    let html = cdpr::plot::viewer::html(&scene);
    assert!(html.contains("\"ball\":{\"centre\":[1.0,1.0,1.0],\"radius\":1.0}"));
    let Some(b) = browser() else {
        println!("note: no Chromium found (set CDPR_CHROMIUM): the HTML viewer was not loaded");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("polytope.html");
    std::fs::write(&page, html).unwrap();
    let dom = dump_dom(&b, &page);
    assert!(
        dom.contains("data-state=\"ok\">rendered 12 triangles"),
        "{}",
        dom.lines()
            .filter(|l| l.contains("cdpr-status"))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// Anchors carry the cables' `name` keys (NE, NW, …) in the HTML viewer and in the isometric
/// figure alike; robots without names get A1, A2, ….
#[test]
fn anchors_are_labelled_by_cable_name_in_every_3d_view() {
    let dir = tempfile::tempdir().unwrap();
    let (page, svg) = (dir.path().join("s.html"), dir.path().join("s.svg"));
    for p in [&page, &svg] {
        let out = cdpr()
            .args([
                "workspace",
                &robot("spidercam-like-4.toml"),
                "--grid",
                "3",
                "--plot",
            ])
            .arg(p)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.contains("\"anchorNames\":[\"NE\",\"NW\",\"SW\",\"SE\"]"),
        "names in the viewer"
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    let labels: Vec<&str> = text.lines().map(str::trim).collect();
    for name in ["NE", "NW", "SW", "SE"] {
        assert!(
            labels.iter().any(|l| l.split('/').any(|n| n == name)),
            "{name} in the figure"
        );
    }
    assert!(!labels.contains(&"A1"));
    let html = cdpr::plot::viewer::html(&octahedron());
    assert!(html.contains("\"anchorNames\":[\"A1\",\"A2\""));
}

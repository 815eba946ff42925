//! Plots render with the bundled font to SVG and PNG, and refuse unknown extensions.

use cdpr::plot::{ForcePolygonPlot, HeatMap, LinePlot, PlotError, Series, save};
use cdpr::polytope::{hyperplane_shifting::available_wrench_set, largest_inscribed_ellipse};
use cdpr::tension::TensionBounds;
use nalgebra::DMatrix;

fn heat_map() -> HeatMap {
    let n = 41;
    let values = (0..n * n)
        .map(|k| {
            let (x, y) = ((k % n) as f64 / 20.0 - 1.0, (k / n) as f64 / 20.0 - 1.0);
            1.0 - x * x - y * y
        })
        .collect();
    HeatMap {
        title: "test field 1 − x² − y²".into(),
        labels: ("x".into(), "y".into()),
        value_label: "value".into(),
        x_range: (-1.0, 1.0),
        y_range: (-1.0, 1.0),
        shape: (n, n),
        values,
        blank_below: 0.0,
        markers: vec![(1.1, 1.1), (-1.1, -1.1)],
        outlines: vec![vec![(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]],
        highlight: vec![((0.0, 0.0), "max".into())],
    }
}

#[test]
fn heat_map_and_line_plot_render() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["svg", "png"] {
        let path = dir.path().join(format!("map.{ext}"));
        save(&heat_map(), &path).unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 1000);
    }
    let svg = std::fs::read_to_string(dir.path().join("map.svg")).unwrap();
    assert!(
        svg.contains("test field"),
        "title text missing from the SVG"
    );
    let lines = LinePlot {
        title: "profile".into(),
        labels: ("s".into(), "t (N)".into()),
        series: vec![Series {
            label: "t1".into(),
            points: vec![(0.0, 1.0), (0.5, f64::NAN), (1.0, 2.0), (2.0, 3.0)],
        }],
        reference_lines: vec![(0.5, "t_min".into()), (3.5, "t_max".into())],
        gap_label: Some("infeasible".into()),
    };
    save(&lines, dir.path().join("lines.png")).unwrap();
}

#[test]
fn unknown_extension_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    assert!(matches!(
        save(&heat_map(), dir.path().join("map.pdf")),
        Err(PlotError::UnknownFormat(_))
    ));
}

/// W = [2 −2 0 0; 0 0 1 −1], t ∈ [0, 1]: the force polygon is the box [−2, 2] × [−1, 1], so the
/// centred circle has radius 1 and touches exactly the two facets y = ±1, and the largest
/// centred ellipse has semi-axes 2 and 1 (derived by hand).
#[test]
fn force_polygon_of_a_box_by_hand() {
    let w = DMatrix::from_row_slice(2, 4, &[2.0, -2.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0]);
    let bounds = TensionBounds::uniform(4, 0.0, 1.0).unwrap();
    let aws = available_wrench_set(&w, &bounds).unwrap();
    let ellipse = largest_inscribed_ellipse(&aws).unwrap().unwrap();
    let fig = ForcePolygonPlot::operational(&aws, Some(&ellipse)).unwrap();
    assert_eq!(fig.polygon.len(), 4);
    for &(x, y) in &fig.polygon {
        assert!((x.abs() - 2.0).abs() < 1e-9 && (y.abs() - 1.0).abs() < 1e-9);
    }
    let (r, _) = fig.circle.clone().unwrap();
    assert!((r - 1.0).abs() < 1e-12);
    let edges = &fig.highlighted_edges.0;
    assert_eq!(edges.len(), 2);
    for (a, b) in edges {
        assert!((a.1.abs() - 1.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9);
        assert!((a.0 - b.0).abs() > 3.9);
    }
    let (b, _) = fig.ellipse.clone().unwrap();
    assert!((b[0][0] - 2.0).abs() < 1e-5 && (b[1][1] - 1.0).abs() < 1e-5);
    assert!(b[0][1].abs() < 1e-5);
    let dir = tempfile::tempdir().unwrap();
    save(&fig, dir.path().join("box.png")).unwrap();
    assert!(std::fs::metadata(dir.path().join("box.png")).unwrap().len() > 5000);
    // Cables pulling along (1, 0), (0, 1), (1, 1) only, t ∈ [0.1, 1]: every force has
    // f_x, f_y ≥ 0.2 > 0, the origin is outside, so no circle and no touching facet.
    let w = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, 1.0, 0.0, 1.0, 1.0]);
    let aws = available_wrench_set(&w, &TensionBounds::uniform(3, 0.1, 1.0).unwrap()).unwrap();
    let fig = ForcePolygonPlot::operational(&aws, None).unwrap();
    assert!(fig.circle.is_none() && fig.highlighted_edges.0.is_empty());
    // A 3-D wrench set has no force polygon.
    let w = DMatrix::from_row_slice(
        3,
        4,
        &[1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0, 1.0, 1.0, 1.0, 1.0],
    );
    let aws = available_wrench_set(&w, &TensionBounds::uniform(4, 0.0, 1.0).unwrap()).unwrap();
    assert!(ForcePolygonPlot::operational(&aws, None).is_none());
}

#[test]
fn pulley_cable_figure_renders_the_library_geometry() {
    use cdpr::plot::PulleyCablePlot;
    use nalgebra::Vector3;
    let plot =
        PulleyCablePlot::new("pulley", 0.3, Vector3::z(), Vector3::new(0.75, 0.95, -0.6)).unwrap();
    // B below the pulley plane's centre height: more than a quarter turn of wrap.
    assert!(
        plot.wrap_angle > std::f64::consts::FRAC_PI_2 && plot.wrap_angle < std::f64::consts::PI
    );
    assert!((plot.swivel_angle - 0.95f64.atan2(0.75)).abs() < 1e-15);
    // The tangent point lies on the circle of radius ρ about M = ρ (cos γ, sin γ, 0).
    let m = Vector3::new(plot.swivel_angle.cos(), plot.swivel_angle.sin(), 0.0) * 0.3;
    assert!(((plot.exit_point - m).norm() - 0.3).abs() < 1e-12);
    let dir = tempfile::tempdir().unwrap();
    let path = std::env::var_os("CDPR_KEEP_PLOT")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| dir.path().join("pulley.png"));
    save(&plot, &path).unwrap();
    assert!(std::fs::metadata(&path).unwrap().len() > 5000);
}

/// A tension profile of 50–153 N under a 5 000 N limit (issue 25): the chart keeps the curves'
/// scale (no tick of 1 000 N or more; the limit is a legend note), the equal curves t1 and t3
/// are named as coinciding, and t_min and t_max are drawn in different dash patterns.
#[test]
fn trajectory_plot_fits_its_curves_and_shows_equal_curves_and_both_limits() {
    let curve = |f: fn(f64) -> f64| {
        (0..=10)
            .map(|k| k as f64 / 10.0)
            .map(|s| (s, f(s)))
            .collect()
    };
    let lines = LinePlot {
        title: "profile".into(),
        labels: ("s".into(), "t (N)".into()),
        series: vec![
            Series {
                label: "t1".into(),
                points: curve(|s| 50.0 + 103.0 * s),
            },
            Series {
                label: "t2".into(),
                points: curve(|s| 153.0 - 103.0 * s),
            },
            Series {
                label: "t3".into(),
                points: curve(|s| 50.0 + 103.0 * s),
            },
        ],
        reference_lines: vec![
            (10.0, "t_min = 10 N".into()),
            (5000.0, "t_max = 5000 N".into()),
        ],
        gap_label: None,
    };
    assert_eq!(lines.coincident(), vec![None, None, Some(0)]);
    let dir = tempfile::tempdir().unwrap();
    save(&lines, dir.path().join("lines.svg")).unwrap();
    save(&lines, dir.path().join("lines.png")).unwrap();
    let svg = std::fs::read_to_string(dir.path().join("lines.svg")).unwrap();
    for big in [">1000<", ">2000<", ">4000<", ">5000<"] {
        assert!(!svg.contains(big), "tick {big} on a 50–153 N chart");
    }
    assert!(svg.contains("t_max = 5000 N (above the chart)"));
    assert!(svg.contains("t3 (coincides with t1)"));
    assert_eq!(
        lines.placements(),
        vec![cdpr::plot::Placement::OnChart, cdpr::plot::Placement::Above]
    );
    assert!(svg.contains("stroke-dasharray") || svg.matches("<polyline").count() > 20);
}

//! Plots render with the bundled font to SVG and PNG, and refuse unknown extensions.

use cdpr::plot::{HeatMap, LinePlot, PlotError, Series, save};

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

//! Line plots: tension profiles along a path, convergence curves.

use super::{DrawResult, Figure};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One curve. NaN y values split the curve (e.g. infeasible samples).
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// (x, y) samples.
    pub points: Vec<(f64, f64)>,
}

/// Curves against a common x axis, with optional horizontal reference lines (t_min, t_max).
#[derive(Debug, Clone, Default)]
pub struct LinePlot {
    /// Title.
    pub title: String,
    /// Axis labels (x, y).
    pub labels: (String, String),
    /// The curves.
    pub series: Vec<Series>,
    /// Horizontal dashed reference lines with labels.
    pub reference_lines: Vec<(f64, String)>,
}

const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

impl Figure for LinePlot {
    fn size(&self) -> (u32, u32) {
        (1000, 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let finite = self
            .series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| p.0.is_finite() && p.1.is_finite());
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &(x, y) in finite {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        for (y, _) in &self.reference_lines {
            y0 = y0.min(*y);
            y1 = y1.max(*y);
        }
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        if x1 - x0 < 1e-12 {
            x1 = x0 + 1.0;
        }
        let pad = 0.06 * (y1 - y0).max(1e-9);
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 22))
            .margin(14)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(x0..x1, y0 - pad..y1 + pad)?;
        chart
            .configure_mesh()
            .x_desc(self.labels.0.as_str())
            .y_desc(self.labels.1.as_str())
            .x_label_formatter(&|v| super::tick(*v))
            .y_label_formatter(&|v| super::tick(*v))
            .label_style(("sans-serif", 15))
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        for (y, label) in &self.reference_lines {
            let style = BLACK.mix(0.6).stroke_width(1);
            chart.draw_series(DashedLineSeries::new(vec![(x0, *y), (x1, *y)], 8, 5, style))?;
            chart.draw_series(std::iter::once(Text::new(
                label.clone(),
                (x0, *y + pad * 0.2),
                ("sans-serif", 14),
            )))?;
        }
        for (k, s) in self.series.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for &p in &s.points {
                if p.1.is_finite() {
                    segments.last_mut().expect("non-empty").push(p);
                } else if !segments.last().expect("non-empty").is_empty() {
                    segments.push(Vec::new());
                }
            }
            let mut first = true;
            for seg in segments.into_iter().filter(|s| !s.is_empty()) {
                let drawn = chart.draw_series(LineSeries::new(seg, colour.stroke_width(2)))?;
                if first {
                    drawn.label(s.label.clone()).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3))
                    });
                    first = false;
                }
            }
        }
        if !self.series.is_empty() {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .label_font(("sans-serif", 15))
                .draw()?;
        }
        Ok(())
    }
}

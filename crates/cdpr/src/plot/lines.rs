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
///
/// The x axis spans every sample, NaN ones included, so a path that ends infeasible is drawn to
/// its end; the legend (curves, reference lines, gaps) sits in a column right of the chart, where
/// it covers nothing.
#[derive(Debug, Clone, Default)]
pub struct LinePlot {
    /// Title.
    pub title: String,
    /// Axis labels (x, y), with units.
    pub labels: (String, String),
    /// The curves.
    pub series: Vec<Series>,
    /// Horizontal dashed reference lines with their legend labels (with value and unit, e.g.
    /// "t_max = 100 N").
    pub reference_lines: Vec<(f64, String)>,
    /// When set, the x intervals where every curve is NaN (e.g. infeasible poses) are shaded and
    /// listed in the legend under this label.
    pub gap_label: Option<String>,
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

const GAP: RGBColor = RGBColor(250, 215, 215);

/// Width of the legend column (pixels).
const LEGEND_WIDTH: u32 = 230;

impl LinePlot {
    /// The x intervals [a, b] where every curve is NaN: runs of consecutive all-NaN samples,
    /// widened to the neighbouring finite samples (the gap as drawn).
    pub fn gaps(&self) -> Vec<(f64, f64)> {
        let Some(first) = self.series.first() else {
            return Vec::new();
        };
        let xs: Vec<f64> = first.points.iter().map(|p| p.0).collect();
        let missing = |k: usize| {
            self.series
                .iter()
                .all(|s| s.points.get(k).is_none_or(|p| !p.1.is_finite()))
        };
        let mut out = Vec::new();
        let mut k = 0;
        while k < xs.len() {
            if missing(k) {
                let start = k;
                while k < xs.len() && missing(k) {
                    k += 1;
                }
                let a = xs[start.saturating_sub(1)];
                let b = xs[k.min(xs.len() - 1)];
                out.push((a, b));
            } else {
                k += 1;
            }
        }
        out
    }
}

impl Figure for LinePlot {
    fn size(&self) -> (u32, u32) {
        (1100, 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &(x, y) in self.series.iter().flat_map(|s| s.points.iter()) {
            if x.is_finite() {
                x0 = x0.min(x);
                x1 = x1.max(x);
            }
            if x.is_finite() && y.is_finite() {
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
        for (y, _) in &self.reference_lines {
            if y.is_finite() {
                y0 = y0.min(*y);
                y1 = y1.max(*y);
            }
        }
        if !x0.is_finite() {
            (x0, x1) = (0.0, 1.0);
        }
        if !y0.is_finite() {
            (y0, y1) = (0.0, 1.0);
        }
        if x1 - x0 < 1e-12 {
            x1 = x0 + 1.0;
        }
        let pad = 0.06 * (y1 - y0).max(1e-9);
        let titled = root.titled(&self.title, ("sans-serif", 22))?;
        let (w, _) = titled.dim_in_pixel();
        let (body, legend) = titled.split_horizontally(w.saturating_sub(LEGEND_WIDTH));
        let mut chart = ChartBuilder::on(&body)
            .margin(14)
            .x_label_area_size(45)
            .y_label_area_size(75)
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
        let gaps = if self.gap_label.is_some() {
            self.gaps()
        } else {
            Vec::new()
        };
        chart.draw_series(
            gaps.iter()
                .map(|&(a, b)| Rectangle::new([(a, y0 - pad), (b, y1 + pad)], GAP.filled())),
        )?;
        for (y, _) in &self.reference_lines {
            let style = BLACK.mix(0.6).stroke_width(1);
            chart.draw_series(DashedLineSeries::new(vec![(x0, *y), (x1, *y)], 8, 5, style))?;
        }
        for (k, s) in self.series.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for &p in &s.points {
                if p.0.is_finite() && p.1.is_finite() {
                    segments.last_mut().expect("non-empty").push(p);
                } else if !segments.last().expect("non-empty").is_empty() {
                    segments.push(Vec::new());
                }
            }
            for seg in segments.into_iter().filter(|s| !s.is_empty()) {
                chart.draw_series(LineSeries::new(seg, colour.stroke_width(2)))?;
            }
        }
        // The legend column: one row per curve, reference line and the gaps.
        let font = ("sans-serif", 15).into_font();
        let mut row = 30;
        let mut entry = |label: String, swatch: &dyn Fn(i32) -> DrawResult| -> DrawResult {
            swatch(row)?;
            legend.draw(&Text::new(label, (46, row - 8), font.clone()))?;
            row += 24;
            Ok(())
        };
        for (k, s) in self.series.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            entry(s.label.clone(), &|y| {
                legend.draw(&PathElement::new(
                    vec![(10, y), (38, y)],
                    colour.stroke_width(3),
                ))?;
                Ok(())
            })?;
        }
        for (_, label) in &self.reference_lines {
            entry(label.clone(), &|y| {
                legend.draw(&PathElement::new(
                    vec![(10, y), (18, y)],
                    BLACK.mix(0.6).stroke_width(1),
                ))?;
                legend.draw(&PathElement::new(
                    vec![(26, y), (38, y)],
                    BLACK.mix(0.6).stroke_width(1),
                ))?;
                Ok(())
            })?;
        }
        if let (Some(label), false) = (&self.gap_label, gaps.is_empty()) {
            entry(label.clone(), &|y| {
                legend.draw(&Rectangle::new([(10, y - 7), (38, y + 7)], GAP.filled()))?;
                Ok(())
            })?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaps_are_the_runs_where_every_curve_is_missing() {
        let nan = f64::NAN;
        let plot = LinePlot {
            series: vec![
                Series {
                    label: "t1".into(),
                    points: vec![(0.0, 1.0), (1.0, nan), (2.0, nan), (3.0, 1.0), (4.0, nan)],
                },
                Series {
                    label: "t2".into(),
                    points: vec![(0.0, 1.0), (1.0, nan), (2.0, 2.0), (3.0, 1.0), (4.0, nan)],
                },
            ],
            ..LinePlot::default()
        };
        // Sample 2 has t2: only sample 1 and the last one are gaps.
        assert_eq!(plot.gaps(), vec![(0.0, 2.0), (3.0, 4.0)]);
        assert!(LinePlot::default().gaps().is_empty());
    }
}

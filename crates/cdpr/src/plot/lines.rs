//! Line plots: tension profiles along a path, convergence curves.

use super::{DrawResult, Figure};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
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

/// The dash patterns (dash, gap in pixels) of reference lines 1, 2, 3, …: t_min dashed, t_max
/// dotted, so the two never share a style.
const REFERENCE_DASHES: [(u32, u32); 3] = [(8, 5), (2, 4), (14, 4)];

/// The dash pattern of a curve that coincides with an earlier one: drawn dashed over it, so both
/// colours show.
const COINCIDENT_DASH: (u32, u32) = (9, 9);

/// The style of reference line `k` (0-based): its dash pattern.
fn reference_dash(k: usize) -> (u32, u32) {
    REFERENCE_DASHES[k % REFERENCE_DASHES.len()]
}

/// The colour of curve `k` (0-based).
fn colour(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// Where a reference line sits relative to the chart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Placement {
    /// Drawn across the chart.
    OnChart,
    /// Far above every curve: not drawn, noted in the legend.
    Above,
    /// Far below every curve: not drawn, noted in the legend.
    Below,
}

/// The smallest and largest finite values of `values`, `None` if there is none.
fn finite_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values.filter(|v| v.is_finite()).fold(None, |r, v| match r {
        None => Some((v, v)),
        Some((a, b)) => Some((a.min(v), b.max(v))),
    })
}

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

    /// The finite y range of the curves' samples (those with a finite x).
    fn data_y_range(&self) -> Option<(f64, f64)> {
        finite_range(
            self.series
                .iter()
                .flat_map(|s| s.points.iter())
                .filter(|p| p.0.is_finite())
                .map(|p| p.1),
        )
    }

    /// Where each reference line goes. A line is on the chart when it lies within one data span
    /// of the curves (so 0 N under curves of 50–153 N is drawn, a 5 000 N limit is not: the chart
    /// keeps the curves' own scale and the legend notes the limit); every line is on the chart
    /// when there is no finite sample.
    pub fn placements(&self) -> Vec<Placement> {
        let data = self.data_y_range();
        self.reference_lines
            .iter()
            .map(|&(y, _)| {
                let Some((lo, hi)) = data else {
                    return Placement::OnChart;
                };
                let span = (hi - lo).max(0.1 * hi.abs().max(lo.abs())).max(1e-9);
                if !y.is_finite() || y > hi + span {
                    Placement::Above
                } else if y < lo - span {
                    Placement::Below
                } else {
                    Placement::OnChart
                }
            })
            .collect()
    }

    /// For each curve, the earlier curve it coincides with (the same samples to 10⁻⁹ of the
    /// values' scale, NaN where it is NaN), if any: it is drawn dashed over that one and named so
    /// in the legend, since a solid line would hide the other.
    pub fn coincident(&self) -> Vec<Option<usize>> {
        let scale = self
            .data_y_range()
            .map_or(1.0, |(a, b)| a.abs().max(b.abs()).max(1e-300));
        let same = |a: &Series, b: &Series| {
            a.points.len() == b.points.len()
                && a.points.iter().zip(&b.points).all(|(p, q)| {
                    p.0 == q.0
                        && match (p.1.is_finite(), q.1.is_finite()) {
                            (true, true) => (p.1 - q.1).abs() <= 1e-9 * scale,
                            (a, b) => a == b,
                        }
                })
        };
        (0..self.series.len())
            .map(|j| (0..j).find(|&i| same(&self.series[i], &self.series[j])))
            .collect()
    }

    /// The chart's x range and y range (before padding): every finite sample and the reference
    /// lines drawn on the chart.
    fn ranges(&self, placements: &[Placement]) -> ((f64, f64), (f64, f64)) {
        let xs = self
            .series
            .iter()
            .flat_map(|s| s.points.iter())
            .map(|p| p.0);
        let (x0, mut x1) = finite_range(xs).unwrap_or((0.0, 1.0));
        if x1 - x0 < 1e-12 {
            x1 = x0 + 1.0;
        }
        let on_chart = self
            .reference_lines
            .iter()
            .zip(placements)
            .filter(|(_, p)| **p == Placement::OnChart)
            .map(|((y, _), _)| *y);
        let ys = self.data_y_range().into_iter().flat_map(|(a, b)| [a, b]);
        let y = finite_range(ys.chain(on_chart)).unwrap_or((0.0, 1.0));
        ((x0, x1), y)
    }

    /// The legend label of reference line `k`, with a note when it is off the chart.
    fn reference_label(&self, k: usize, placement: Placement) -> String {
        let label = &self.reference_lines[k].1;
        match placement {
            Placement::OnChart => label.clone(),
            Placement::Above => format!("{label} (above the chart)"),
            Placement::Below => format!("{label} (below the chart)"),
        }
    }

    /// The legend label of curve `k`, naming the curve it coincides with.
    fn series_label(&self, k: usize, coincident: &[Option<usize>]) -> String {
        match coincident[k] {
            Some(i) => format!(
                "{} (coincides with {})",
                self.series[k].label, self.series[i].label
            ),
            None => self.series[k].label.clone(),
        }
    }
}

/// The finite runs of a curve's samples (NaN samples split it).
fn segments(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for &p in points {
        if p.0.is_finite() && p.1.is_finite() {
            segments.last_mut().expect("non-empty").push(p);
        } else if !segments.last().expect("non-empty").is_empty() {
            segments.push(Vec::new());
        }
    }
    segments.retain(|s| !s.is_empty());
    segments
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

impl Figure for LinePlot {
    fn size(&self) -> (u32, u32) {
        (1100, 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let placements = self.placements();
        let coincident = self.coincident();
        let ((x0, x1), (y0, y1)) = self.ranges(&placements);
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
        self.draw_reference_lines(&mut chart, (x0, x1), &placements)?;
        self.draw_curves(&mut chart, &coincident)?;
        self.draw_legend(&legend, &placements, &coincident, !gaps.is_empty())
    }
}

impl LinePlot {
    /// The reference lines on the chart, each in its own dash pattern.
    fn draw_reference_lines<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        (x0, x1): (f64, f64),
        placements: &[Placement],
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        for (k, ((y, _), p)) in self.reference_lines.iter().zip(placements).enumerate() {
            if *p != Placement::OnChart {
                continue;
            }
            let (dash, gap) = reference_dash(k);
            let style = BLACK.mix(0.6).stroke_width(1);
            chart.draw_series(DashedLineSeries::new(
                vec![(x0, *y), (x1, *y)],
                dash,
                gap,
                style,
            ))?;
        }
        Ok(())
    }

    /// The curves: solid, or dashed over the curve they coincide with.
    fn draw_curves<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        coincident: &[Option<usize>],
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        for (k, s) in self.series.iter().enumerate() {
            let style = colour(k).stroke_width(2);
            for seg in segments(&s.points) {
                if coincident[k].is_some() {
                    let (dash, gap) = COINCIDENT_DASH;
                    chart.draw_series(DashedLineSeries::new(seg, dash, gap, style))?;
                } else {
                    chart.draw_series(LineSeries::new(seg, style))?;
                }
            }
        }
        Ok(())
    }

    /// The legend column: one row per curve, reference line and the gaps, each swatch drawn in
    /// the style of its line.
    fn draw_legend<DB: DrawingBackend>(
        &self,
        legend: &DrawingArea<DB, Shift>,
        placements: &[Placement],
        coincident: &[Option<usize>],
        has_gaps: bool,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let font = ("sans-serif", 15).into_font();
        let mut row = 30;
        let mut entry = |label: String, swatch: &dyn Fn(i32) -> DrawResult| -> DrawResult {
            swatch(row)?;
            legend.draw(&Text::new(label, (46, row - 8), font.clone()))?;
            row += 24;
            Ok(())
        };
        for k in 0..self.series.len() {
            let (dash, gap) = match coincident[k] {
                Some(_) => (COINCIDENT_DASH.0 as i32 / 2, COINCIDENT_DASH.1 as i32 / 2),
                None => (28, 0),
            };
            let style = colour(k).stroke_width(3);
            entry(self.series_label(k, coincident), &|y| {
                dashes(legend, y, (dash, gap), style)
            })?;
        }
        for (k, p) in placements.iter().enumerate() {
            let (dash, gap) = reference_dash(k);
            let style = BLACK.mix(0.6).stroke_width(1);
            entry(self.reference_label(k, *p), &|y| {
                dashes(legend, y, (dash as i32, gap as i32), style)
            })?;
        }
        if let (Some(label), true) = (&self.gap_label, has_gaps) {
            entry(label.clone(), &|y| {
                legend.draw(&Rectangle::new([(10, y - 7), (38, y + 7)], GAP.filled()))?;
                Ok(())
            })?;
        }
        Ok(())
    }
}

/// A legend swatch from x = 10 to 38 px at height `y`: dashes of `dash` px with `gap` px between
/// (a solid line when `gap` is 0).
fn dashes<DB: DrawingBackend>(
    legend: &DrawingArea<DB, Shift>,
    y: i32,
    (dash, gap): (i32, i32),
    style: ShapeStyle,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let mut x = 10;
    while x < 38 {
        let end = (x + dash.max(1)).min(38);
        legend.draw(&PathElement::new(vec![(x, y), (end, y)], style))?;
        x = end + gap;
    }
    Ok(())
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

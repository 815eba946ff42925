//! A scalar field on a regular grid, coloured, with a colour bar (Krut, Company & Pierrot 2004, Figs. 9–10 style).

use super::{DrawResult, Figure, colour_map};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Values on a regular (nx × ny) grid over `x_range × y_range`; cells whose value is NaN or
/// below `blank_below` are left white (Krut, Company & Pierrot 2004: white where the index is negative).
#[derive(Debug, Clone)]
pub struct HeatMap {
    /// Title above the plot.
    pub title: String,
    /// Axis labels (x, y).
    pub labels: (String, String),
    /// Colour-bar label (quantity and unit).
    pub value_label: String,
    /// x extent of the grid (first and last sample).
    pub x_range: (f64, f64),
    /// y extent of the grid.
    pub y_range: (f64, f64),
    /// Number of samples along x and y.
    pub shape: (usize, usize),
    /// Row-major values, x fastest: `values[j * nx + i]`.
    pub values: Vec<f64>,
    /// Values below this are drawn white.
    pub blank_below: f64,
    /// Points to mark (e.g. frame anchors), drawn as black squares.
    pub markers: Vec<(f64, f64)>,
    /// Closed outlines to draw (e.g. a feasible polygon).
    pub outlines: Vec<Vec<(f64, f64)>>,
    /// One highlighted point with its label (e.g. the optimum).
    pub highlight: Vec<((f64, f64), String)>,
}

impl HeatMap {
    fn value_range(&self) -> (f64, f64) {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for &v in &self.values {
            if v.is_finite() && v >= self.blank_below {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        if !lo.is_finite() {
            return (0.0, 1.0);
        }
        if hi - lo < 1e-12 * hi.abs().max(1.0) {
            (lo - 0.5, hi + 0.5)
        } else {
            (lo, hi)
        }
    }
}

/// Pixel offset of a highlight label from its point: left of it (by the text's width, about
/// 8.5 px per character at 15 px) in the right half of the chart, right of it otherwise; below
/// it in the upper half, above it otherwise.
fn highlight_offset(label: &str, right_half: bool, upper_half: bool) -> (i32, i32) {
    let width = (8.5 * label.chars().count() as f64).ceil() as i32;
    let dx = if right_half { -10 - width } else { 10 };
    let dy = if upper_half { 8 } else { -24 };
    (dx, dy)
}

/// The chart of a heat map (m, or the quantities of `labels`, on both axes).
type Chart<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

impl HeatMap {
    /// The grid spacing (Δx, Δy); 1 along an axis with one sample.
    fn cell(&self) -> (f64, f64) {
        let (nx, ny) = self.shape;
        let dx = if nx > 1 {
            (self.x_range.1 - self.x_range.0) / (nx - 1) as f64
        } else {
            1.0
        };
        let dy = if ny > 1 {
            (self.y_range.1 - self.y_range.0) / (ny - 1) as f64
        } else {
            1.0
        };
        (dx, dy)
    }

    /// The x and y extents of the cells, markers and outlines.
    fn extent(&self, (dx, dy): (f64, f64)) -> ((f64, f64), (f64, f64)) {
        let mut xs = (self.x_range.0 - dx / 2.0, self.x_range.1 + dx / 2.0);
        let mut ys = (self.y_range.0 - dy / 2.0, self.y_range.1 + dy / 2.0);
        for &(x, y) in self.markers.iter().chain(self.outlines.iter().flatten()) {
            xs = (xs.0.min(x), xs.1.max(x));
            ys = (ys.0.min(y), ys.1.max(y));
        }
        (xs, ys)
    }

    /// The coloured cells over `lo..hi`.
    fn draw_cells<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        (dx, dy): (f64, f64),
        (lo, hi): (f64, f64),
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let nx = self.shape.0;
        chart.draw_series(self.values.iter().enumerate().filter_map(|(k, &v)| {
            if !(v.is_finite() && v >= self.blank_below) {
                return None;
            }
            let (i, j) = (k % nx, k / nx);
            let (x, y) = (
                self.x_range.0 + i as f64 * dx,
                self.y_range.0 + j as f64 * dy,
            );
            let c = colour_map((v - lo) / (hi - lo));
            Some(Rectangle::new(
                [(x - dx / 2.0, y - dy / 2.0), (x + dx / 2.0, y + dy / 2.0)],
                c.filled(),
            ))
        }))?;
        Ok(())
    }

    /// The outlines, the markers and the highlighted points with their labels.
    fn draw_overlays<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        (xs, ys): ((f64, f64), (f64, f64)),
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        for outline in &self.outlines {
            let mut pts = outline.clone();
            if let Some(&first) = outline.first() {
                pts.push(first);
            }
            chart.draw_series(std::iter::once(PathElement::new(
                pts,
                BLACK.stroke_width(2),
            )))?;
        }
        chart.draw_series(self.markers.iter().map(|&(x, y)| {
            EmptyElement::at((x, y)) + Rectangle::new([(-5, -5), (5, 5)], BLACK.filled())
        }))?;
        // Labels go on the side of the point with more room, so that none is clipped.
        let (xmid, ymid) = (0.5 * (xs.0 + xs.1), 0.5 * (ys.0 + ys.1));
        for ((x, y), label) in &self.highlight {
            let (dx, dy) = highlight_offset(label, *x > xmid, *y > ymid);
            chart.draw_series(std::iter::once(
                EmptyElement::at((*x, *y))
                    + Circle::new((0, 0), 6, RED.filled())
                    + Text::new(label.clone(), (dx, dy), ("sans-serif", 15).into_font()),
            ))?;
        }
        Ok(())
    }

    /// The colour bar over `lo..hi`.
    fn draw_colour_bar<DB: DrawingBackend>(
        &self,
        bar: &DrawingArea<DB, Shift>,
        (lo, hi): (f64, f64),
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let mut bar_chart = ChartBuilder::on(bar)
            .margin_top(50)
            .margin_bottom(57)
            .margin_right(10)
            .y_label_area_size(0)
            .right_y_label_area_size(90)
            .build_cartesian_2d(0.0..1.0, lo..hi)?;
        bar_chart
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(self.value_label.as_str())
            .y_label_formatter(&|v| super::tick(*v))
            .label_style(("sans-serif", 14))
            .draw()?;
        let steps = 100;
        bar_chart.draw_series((0..steps).map(|s| {
            let a = lo + (hi - lo) * s as f64 / steps as f64;
            let b = lo + (hi - lo) * (s + 1) as f64 / steps as f64;
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                colour_map(s as f64 / (steps - 1) as f64).filled(),
            )
        }))?;
        Ok(())
    }
}

impl Figure for HeatMap {
    fn size(&self) -> (u32, u32) {
        (1000, 820)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (main, bar) = root.split_horizontally(840);
        let cell = self.cell();
        let (xs, ys) = self.extent(cell);
        let pad = 0.04 * (xs.1 - xs.0).max(ys.1 - ys.0);
        let mut chart = ChartBuilder::on(&main)
            .caption(&self.title, ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(xs.0 - pad..xs.1 + pad, ys.0 - pad..ys.1 + pad)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.labels.0.as_str())
            .y_desc(self.labels.1.as_str())
            .x_label_formatter(&|v| super::tick(*v))
            .y_label_formatter(&|v| super::tick(*v))
            .label_style(("sans-serif", 15))
            .draw()?;
        let range = self.value_range();
        self.draw_cells(&mut chart, cell, range)?;
        self.draw_overlays(&mut chart, (xs, ys))?;
        self.draw_colour_bar(&bar, range)
    }
}

#[cfg(test)]
mod tests {
    use super::highlight_offset;

    /// A label at a point in the right half is drawn to its left, ending before the point.
    #[test]
    fn highlight_labels_point_inwards() {
        let label = "SOTDA optimum 18.730 mm";
        let (dx, _) = highlight_offset(label, true, false);
        assert!(
            dx + (8.5 * label.chars().count() as f64) as i32 <= -8,
            "{dx}"
        );
        assert_eq!(highlight_offset(label, false, false), (10, -24));
        assert_eq!(highlight_offset(label, false, true).1, 8);
    }
}

//! Page layout shared by the chart figures with a legend column (force polygons, candidate
//! lines, the tension box): title, note lines under it, chart body and legend side by side; and
//! the bounding box of the points to show.

use plotters::coord::Shift;
use plotters::prelude::*;

/// Height of one note line under the title (pixels).
const NOTE_HEIGHT: u32 = 20;

/// Bounding box (x range, y range) of finite points; the unit square if there is none.
pub(super) fn bounds(points: impl IntoIterator<Item = (f64, f64)>) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in points
        .into_iter()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
    {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0.is_finite() {
        ((x0, x1), (y0, y1))
    } else {
        ((0.0, 1.0), (0.0, 1.0))
    }
}

/// Title, notes under it, and the remaining area split into a body and a legend column.
pub(super) type Layout<DB> = (DrawingArea<DB, Shift>, DrawingArea<DB, Shift>);

pub(super) fn layout<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    notes: &[String],
    legend_width: u32,
) -> Result<Layout<DB>, Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let titled = root.titled(title, ("sans-serif", 20))?;
    let (top, rest) = titled.split_vertically(6 + NOTE_HEIGHT * notes.len() as u32);
    for (k, note) in notes.iter().enumerate() {
        top.draw(&Text::new(
            note.clone(),
            (14, 2 + NOTE_HEIGHT as i32 * k as i32),
            ("sans-serif", 15).into_font(),
        ))?;
    }
    let (w, _) = rest.dim_in_pixel();
    Ok(rest.split_horizontally(w.saturating_sub(legend_width)))
}

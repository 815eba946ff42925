//! Krut, Company & Pierrot's (2004) pictures of Krut's vertex projection: the admissible joint force space, the box
//! t_min ≤ t ≤ t_max of eq. (3) for three cables in an oblique view (Fig. 3), and the possible
//! frontiers of step 4, the lines through pairs of projected box vertices with the borders of
//! test (15) highlighted (Fig. 8).
//!
//! Both keep equal scales on their two screen axes, so angles and lengths are not distorted by
//! the image's aspect ratio; labels sit on white boxes so that lines do not cross them.

use super::layout::{bounds, layout};
use super::{DrawResult, Figure, Segment, tick};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const FILL: RGBColor = RGBColor(198, 219, 239);
const EDGE: RGBColor = RGBColor(8, 69, 148);
const CANDIDATE: RGBColor = RGBColor(150, 150, 150);
const BORDER: RGBColor = RGBColor(255, 127, 14);
const AXIS: RGBColor = RGBColor(60, 60, 60);
const FACES: [RGBColor; 3] = [
    RGBColor(190, 212, 236),
    RGBColor(214, 228, 243),
    RGBColor(235, 242, 250),
];
const LEGEND_WIDTH: u32 = 330;
const MARGIN: u32 = 14;
const X_LABELS: u32 = 42;
const Y_LABELS: u32 = 62;

/// The part of the line `normal · p = offset` inside the rectangle `xs × ys`, or `None` (also for
/// a zero or non-finite normal).
pub fn clip_line(
    normal: (f64, f64),
    offset: f64,
    xs: (f64, f64),
    ys: (f64, f64),
) -> Option<Segment> {
    let len = normal.0.hypot(normal.1);
    if !(len > 0.0 && len.is_finite() && offset.is_finite()) {
        return None;
    }
    let (ux, uy) = (normal.0 / len, normal.1 / len);
    // p(s) = (offset / len) u + s (−u_y, u_x): the foot of the perpendicular plus the direction.
    let (px, py, dx, dy) = (ux * offset / len, uy * offset / len, -uy, ux);
    let (mut s0, mut s1) = (f64::NEG_INFINITY, f64::INFINITY);
    for (p, d, (lo, hi)) in [(px, dx, xs), (py, dy, ys)] {
        if d.abs() < 1e-15 {
            if p < lo || p > hi {
                return None;
            }
        } else {
            let (a, b) = ((lo - p) / d, (hi - p) / d);
            s0 = s0.max(a.min(b));
            s1 = s1.min(a.max(b));
        }
    }
    (s0 <= s1).then_some(((px + s0 * dx, py + s0 * dy), (px + s1 * dx, py + s1 * dy)))
}

/// Ranges around `(x0, x1) × (y0, y1)`, padded by `pad` of the larger side and widened along
/// one axis so that a plot of `pixels` has equal scales.
fn equal_scale_ranges(
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    pad: f64,
    pixels: (u32, u32),
) -> ((f64, f64), (f64, f64)) {
    let size = (x1 - x0).max(y1 - y0).max(1e-9);
    let (mut hx, mut hy) = (0.5 * (x1 - x0) + pad * size, 0.5 * (y1 - y0) + pad * size);
    let (w, h) = (f64::from(pixels.0.max(1)), f64::from(pixels.1.max(1)));
    if hx / w > hy / h {
        hy = hx * h / w;
    } else {
        hx = hy * w / h;
    }
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    ((cx - hx, cx + hx), (cy - hy, cy + hy))
}

/// Draws `label` next to the point `at` (data coordinates of `area`) on a white box, offset by
/// `gap` pixels in the screen direction `dir` (x right, y up) and aligned away from the point.
fn label<DB, CT>(
    area: &DrawingArea<DB, CT>,
    at: CT::From,
    text: &str,
    dir: (f64, f64),
    gap: f64,
) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    CT: plotters::coord::CoordTranslate,
{
    let len = dir.0.hypot(dir.1);
    let (dx, dy) = if len > 0.0 {
        (dir.0 / len, dir.1 / len)
    } else {
        (1.0, -1.0)
    };
    let h = if dx > 0.35 {
        HPos::Left
    } else if dx < -0.35 {
        HPos::Right
    } else {
        HPos::Center
    };
    let v = if dy > 0.35 {
        VPos::Bottom
    } else if dy < -0.35 {
        VPos::Top
    } else {
        VPos::Center
    };
    let style = TextStyle::from(("sans-serif", 15).into_font()).pos(Pos::new(h, v));
    let (w, ht) = area.estimate_text_size(text, &style)?;
    let (w, ht) = (w as i32, ht as i32);
    let (ox, oy) = ((gap * dx).round() as i32, (-gap * dy).round() as i32);
    let x0 = match h {
        HPos::Left => ox,
        HPos::Right => ox - w,
        HPos::Center => ox - w / 2,
    };
    let y0 = match v {
        VPos::Top => oy,
        VPos::Bottom => oy - ht,
        VPos::Center => oy - ht / 2,
    };
    area.draw(
        &(EmptyElement::at(at)
            + Rectangle::new(
                [(x0 - 3, y0 - 2), (x0 + w + 3, y0 + ht + 2)],
                WHITE.mix(0.9).filled(),
            )
            + Text::new(text.to_string(), (ox, oy), style)),
    )?;
    Ok(())
}

/// How a legend entry is drawn.
enum Swatch {
    /// A filled rectangle, outlined if `true`.
    Fill(bool),
    Line(RGBColor, u32),
    Dashed(RGBColor, u32),
    Dot,
    Origin,
}

/// Draws the legend column: a swatch and a label (lines split at '\n') per entry.
fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(Swatch, String)],
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let mut y = 30;
    let (sx0, sx1) = (10, 46);
    for (swatch, text) in entries {
        match swatch {
            Swatch::Fill(outline) => {
                area.draw(&Rectangle::new([(sx0, y - 8), (sx1, y + 8)], FILL.filled()))?;
                if *outline {
                    area.draw(&Rectangle::new(
                        [(sx0, y - 8), (sx1, y + 8)],
                        EDGE.stroke_width(2),
                    ))?;
                }
            }
            Swatch::Line(c, width) => {
                area.draw(&PathElement::new(
                    vec![(sx0, y), (sx1, y)],
                    c.stroke_width(*width),
                ))?;
            }
            Swatch::Dashed(c, width) => {
                for x in [sx0, sx0 + 14, sx0 + 28] {
                    area.draw(&PathElement::new(
                        vec![(x, y), (x + 8, y)],
                        c.stroke_width(*width),
                    ))?;
                }
            }
            Swatch::Dot => area.draw(&Circle::new((28, y), 5, BLACK.filled()))?,
            Swatch::Origin => area.draw(
                &(EmptyElement::at((28, y)) + Cross::new((0, 0), 8, BLACK.stroke_width(2))),
            )?,
        }
        for line in text.lines() {
            area.draw(&Text::new(
                line.to_string(),
                (sx1 + 10, y - 8),
                ("sans-serif", 15).into_font(),
            ))?;
            y += 19;
        }
        y += 12;
    }
    Ok(())
}

/// Krut, Company & Pierrot 2004, Fig. 8: candidate frontiers `normal · p = offset` through pairs of projected box
/// vertices, clipped to the plot, thin and grey, the borders of test (15) thick; the labelled
/// points (the projected vertices) and the polygon they bound.
#[derive(Debug, Clone, Default)]
pub struct CandidateLinesPlot {
    /// Title.
    pub title: String,
    /// Axis labels (x, y).
    pub labels: (String, String),
    /// Lines printed under the title (counts, settings).
    pub notes: Vec<String>,
    /// The polygon's vertices in order (closed automatically), filled under the lines.
    pub polygon: Vec<(f64, f64)>,
    /// Legend entry of the polygon.
    pub polygon_label: String,
    /// The lines `normal · p = offset`; `true` marks a border (drawn thick, on top).
    pub lines: Vec<((f64, f64), f64, bool)>,
    /// Legend entries of the non-border lines and of the borders.
    pub line_labels: (String, String),
    /// Labelled points; points within 10⁻⁹ of the extent of each other share one marker and
    /// their labels are joined with " = ".
    pub points: Vec<((f64, f64), String)>,
    /// Legend entry of the points.
    pub points_label: String,
    /// Mark the origin with a cross (legend "origin").
    pub origin: bool,
}

impl CandidateLinesPlot {
    /// The points with coincident ones merged (labels joined with " = ").
    fn merged_points(&self) -> Vec<((f64, f64), String)> {
        let ((x0, x1), (y0, y1)) = bounds(self.points.iter().map(|p| p.0));
        let tol = 1e-9 * (x1 - x0).max(y1 - y0).max(f64::MIN_POSITIVE);
        let mut out: Vec<((f64, f64), String)> = Vec::new();
        for (p, text) in &self.points {
            match out
                .iter_mut()
                .find(|(q, _)| (q.0 - p.0).abs() <= tol && (q.1 - p.1).abs() <= tol)
            {
                Some((_, t)) => {
                    t.push_str(" = ");
                    t.push_str(text);
                }
                None => out.push((*p, text.clone())),
            }
        }
        out
    }
}

/// A chart in data coordinates (N or the quantities of the labels on both axes).
type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A plotting area in data coordinates.
type DataArea<DB> = DrawingArea<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

impl CandidateLinesPlot {
    /// The chart's x and y ranges: the points, the polygon and the origin, equal scales on a
    /// w × h px body.
    fn ranges(&self, (w, h): (u32, u32)) -> ((f64, f64), (f64, f64)) {
        let mut extent: Vec<(f64, f64)> = self.points.iter().map(|p| p.0).collect();
        extent.extend(&self.polygon);
        if self.origin {
            extent.push((0.0, 0.0));
        }
        let plot_px = (
            w.saturating_sub(2 * MARGIN + Y_LABELS),
            h.saturating_sub(2 * MARGIN + X_LABELS),
        );
        let (xs, ys) = bounds(extent);
        equal_scale_ranges(xs, ys, 0.2, plot_px)
    }

    /// The polygon, the candidate lines and borders clipped to `xs` × `ys`, and the origin.
    fn draw_lines<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        xs: (f64, f64),
        ys: (f64, f64),
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        if self.polygon.len() > 2 {
            let mut p = self.polygon.clone();
            p.push(self.polygon[0]);
            chart.draw_series(std::iter::once(Polygon::new(p, FILL.filled())))?;
        }
        for border in [false, true] {
            let style = if border {
                BORDER.stroke_width(4)
            } else {
                CANDIDATE.stroke_width(1)
            };
            let segments = self
                .lines
                .iter()
                .filter(|l| l.2 == border)
                .filter_map(|&(n, d, _)| clip_line(n, d, xs, ys));
            chart.draw_series(segments.map(|(a, b)| PathElement::new(vec![a, b], style)))?;
        }
        if self.origin {
            chart.draw_series(std::iter::once(
                EmptyElement::at((0.0, 0.0)) + Cross::new((0, 0), 8, BLACK.stroke_width(2)),
            ))?;
        }
        Ok(())
    }

    /// The (merged) points and their labels, away from their centroid.
    fn draw_points<DB: DrawingBackend>(
        &self,
        area: &DataArea<DB>,
        points: &[((f64, f64), String)],
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let n = points.len().max(1) as f64;
        let c = points
            .iter()
            .fold((0.0, 0.0), |s, p| (s.0 + p.0.0 / n, s.1 + p.0.1 / n));
        for (p, _) in points {
            area.draw(&Circle::new(*p, 5, BLACK.filled()))?;
        }
        for (p, text) in points {
            // Away from the points' centroid; a point at the centroid gets its label below right.
            label(area, *p, text, (p.0 - c.0, p.1 - c.1), 12.0)?;
        }
        Ok(())
    }

    /// The legend entries of what is drawn.
    fn legend_entries(&self, has_points: bool) -> Vec<(Swatch, String)> {
        let mut entries = Vec::new();
        if self.polygon.len() > 2 {
            entries.push((Swatch::Fill(false), self.polygon_label.clone()));
        }
        if self.lines.iter().any(|l| !l.2) {
            entries.push((Swatch::Line(CANDIDATE, 1), self.line_labels.0.clone()));
        }
        if self.lines.iter().any(|l| l.2) {
            entries.push((Swatch::Line(BORDER, 4), self.line_labels.1.clone()));
        }
        if has_points {
            entries.push((Swatch::Dot, self.points_label.clone()));
        }
        if self.origin {
            entries.push((Swatch::Origin, "origin".into()));
        }
        entries
    }
}

impl Figure for CandidateLinesPlot {
    fn size(&self) -> (u32, u32) {
        (1200, 900)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let (body, legend_area) = layout(root, &self.title, &self.notes, LEGEND_WIDTH)?;
        let (xs, ys) = self.ranges(body.dim_in_pixel());
        let mut chart = ChartBuilder::on(&body)
            .margin(MARGIN)
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS)
            .build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)?;
        chart
            .configure_mesh()
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.08))
            .x_desc(self.labels.0.as_str())
            .y_desc(self.labels.1.as_str())
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .label_style(("sans-serif", 14))
            .draw()?;
        self.draw_lines(&mut chart, xs, ys)?;
        let points = self.merged_points();
        self.draw_points(chart.plotting_area(), &points)?;
        legend(&legend_area, &self.legend_entries(!points.is_empty()))
    }
}

/// Krut, Company & Pierrot 2004, Fig. 3: the box t_min ≤ t ≤ t_max of three tensions in an oblique (orthographic,
/// axonometric) view: the three visible faces shaded, hidden edges dashed, the eight vertices
/// labelled with their tensions and the axes t₁, t₂, t₃ drawn from the origin.
#[derive(Debug, Clone)]
pub struct TensionBoxPlot {
    /// Title.
    pub title: String,
    /// Lines printed under the title.
    pub notes: Vec<String>,
    /// t_min (N).
    pub min: [f64; 3],
    /// t_max (N).
    pub max: [f64; 3],
    /// Axis names, e.g. "t₁ (N)".
    pub axes: [String; 3],
    /// Viewing direction: azimuth from the t₁ axis towards t₂ and elevation above the t₁t₂
    /// plane (degrees). The isometric view (45°, 35.26°) would hide the vertex t_min behind
    /// t_max for a cube; the default (30°, 25°) keeps all eight apart.
    pub view: (f64, f64),
}

impl TensionBoxPlot {
    /// The box `min ≤ t ≤ max` with axes "t₁ (N)", "t₂ (N)", "t₃ (N)" and the default view.
    pub fn new(min: [f64; 3], max: [f64; 3]) -> Self {
        Self {
            title: String::new(),
            notes: Vec::new(),
            min,
            max,
            axes: ["t₁ (N)".into(), "t₂ (N)".into(), "t₃ (N)".into()],
            view: (30.0, 25.0),
        }
    }

    /// The screen directions (right, up) of the three axes, and the viewing direction.
    fn frame(&self) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let (az, el) = (self.view.0.to_radians(), self.view.1.to_radians());
        let right = [-az.sin(), az.cos(), 0.0];
        let up = [-el.sin() * az.cos(), -el.sin() * az.sin(), el.cos()];
        let toward = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
        (right, up, toward)
    }

    /// Screen coordinates of the point `t`.
    fn project(&self, t: [f64; 3]) -> (f64, f64) {
        let (r, u, _) = self.frame();
        let dot = |a: [f64; 3]| a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
        (dot(r), dot(u))
    }

    /// The vertex with bit j of `bits` set at t_max,j, else at t_min,j.
    fn corner(&self, bits: usize) -> [f64; 3] {
        std::array::from_fn(|j| {
            if bits >> j & 1 == 1 {
                self.max[j]
            } else {
                self.min[j]
            }
        })
    }

    /// Whether face (j, at max?) faces the viewer.
    fn visible(&self, j: usize, at_max: bool) -> bool {
        let d = self.frame().2[j];
        if at_max { d > 0.0 } else { d < 0.0 }
    }

    /// Axis length from the origin: beyond the box and the origin.
    fn axis_end(&self, j: usize) -> f64 {
        let span = self.max[j] - self.min[j];
        self.max[j].max(0.0) + 0.3 * span.max(self.max[j].abs())
    }
}

/// An axis tip and the unit direction of its axis on screen.
type AxisTip = ((f64, f64), (f64, f64));

impl TensionBoxPlot {
    /// The tip of axis j (N).
    fn axis_tip(&self, j: usize) -> [f64; 3] {
        let mut t = [0.0; 3];
        t[j] = self.axis_end(j);
        t
    }

    /// The chart's x and y ranges: the vertices, the origin and the axis tips, equal scales on
    /// a w × h px body.
    fn ranges(&self, (w, h): (u32, u32)) -> ((f64, f64), (f64, f64)) {
        let mut extent: Vec<(f64, f64)> = (0..8).map(|b| self.project(self.corner(b))).collect();
        extent.push(self.project([0.0; 3]));
        extent.extend((0..3).map(|j| self.project(self.axis_tip(j))));
        let (xs, ys) = bounds(extent);
        equal_scale_ranges(
            xs,
            ys,
            0.12,
            (w.saturating_sub(2 * MARGIN), h.saturating_sub(2 * MARGIN)),
        )
    }

    /// The axes with their arrow heads and the origin; returns each tip and its direction.
    fn draw_axes<DB: DrawingBackend>(
        &self,
        area: &DataArea<DB>,
        px_per_unit: f64,
    ) -> Result<Vec<AxisTip>, Box<dyn std::error::Error>>
    where
        DB::ErrorType: 'static,
    {
        let origin = self.project([0.0; 3]);
        let mut axis_labels = Vec::new();
        for j in 0..3 {
            let tip = self.project(self.axis_tip(j));
            area.draw(&PathElement::new(vec![origin, tip], AXIS.stroke_width(2)))?;
            let (dx, dy) = (tip.0 - origin.0, tip.1 - origin.1);
            let len = dx.hypot(dy).max(f64::MIN_POSITIVE);
            let (ux, uy) = (dx / len, dy / len);
            let (a, b) = (14.0 / px_per_unit, 5.0 / px_per_unit);
            area.draw(&Polygon::new(
                vec![
                    tip,
                    (tip.0 - a * ux - b * uy, tip.1 - a * uy + b * ux),
                    (tip.0 - a * ux + b * uy, tip.1 - a * uy - b * ux),
                ],
                AXIS.filled(),
            ))?;
            axis_labels.push((tip, (ux, uy)));
        }
        area.draw(&Circle::new(origin, 4, AXIS.filled()))?;
        Ok(axis_labels)
    }

    /// The visible faces, translucent, a shade per axis.
    fn draw_faces<DB: DrawingBackend>(&self, area: &DataArea<DB>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        for (j, shade) in FACES.iter().enumerate() {
            for at_max in [false, true] {
                if !self.visible(j, at_max) {
                    continue;
                }
                let (a, b) = ((j + 1) % 3, (j + 2) % 3);
                let fixed = if at_max { 1 << j } else { 0 };
                let face: Vec<(f64, f64)> = [0, 1 << a, (1 << a) | (1 << b), 1 << b]
                    .iter()
                    .map(|&bits| self.project(self.corner(fixed | bits)))
                    .collect();
                area.draw(&Polygon::new(face, shade.mix(0.75).filled()))?;
            }
        }
        Ok(())
    }

    /// The edges: along axis k, with the other two bounds fixed; hidden (dashed) unless on a
    /// visible face.
    fn draw_edges<DB: DrawingBackend>(&self, area: &DataArea<DB>, px_per_unit: f64) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        for k in 0..3 {
            for other in 0..8usize {
                if other >> k & 1 == 1 {
                    continue;
                }
                let on_visible = (0..3)
                    .filter(|&j| j != k)
                    .any(|j| self.visible(j, other >> j & 1 == 1));
                let (p, q) = (
                    self.project(self.corner(other)),
                    self.project(self.corner(other | 1 << k)),
                );
                if on_visible {
                    area.draw(&PathElement::new(vec![p, q], EDGE.stroke_width(3)))?;
                } else {
                    // Dashes of 10 px every 16 px.
                    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
                    let len = dx.hypot(dy) * px_per_unit;
                    let mut s = 0.0;
                    while s < len {
                        let (a, b) = (s / len, ((s + 10.0) / len).min(1.0));
                        area.draw(&PathElement::new(
                            vec![(p.0 + a * dx, p.1 + a * dy), (p.0 + b * dx, p.1 + b * dy)],
                            EDGE.mix(0.7).stroke_width(2),
                        ))?;
                        s += 16.0;
                    }
                }
            }
        }
        Ok(())
    }

    /// The axis names, the vertices with their tensions and the origin's "0".
    fn draw_labels<DB: DrawingBackend>(
        &self,
        area: &DataArea<DB>,
        axis_labels: Vec<AxisTip>,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let centre = self.project(std::array::from_fn(|j| 0.5 * (self.min[j] + self.max[j])));
        let origin = self.project([0.0; 3]);
        for (j, (tip, dir)) in axis_labels.into_iter().enumerate() {
            label(area, tip, &self.axes[j], dir, 10.0)?;
        }
        for bits in 0..8 {
            let t = self.corner(bits);
            let p = self.project(t);
            area.draw(&Circle::new(p, 5, BLACK.filled()))?;
            let text = format!("({}, {}, {})", tick(t[0]), tick(t[1]), tick(t[2]));
            // Away from the box's centre, except the vertex t_min: away from the origin, which
            // projects next to it and is labelled away from the centre.
            let from = if bits == 0 { origin } else { centre };
            label(area, p, &text, (p.0 - from.0, p.1 - from.1), 10.0)?;
        }
        label(
            area,
            origin,
            "0",
            (origin.0 - centre.0, origin.1 - centre.1),
            8.0,
        )
    }
}

impl Figure for TensionBoxPlot {
    fn size(&self) -> (u32, u32) {
        (1100, 820)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let (body, legend_area) = layout(root, &self.title, &self.notes, LEGEND_WIDTH)?;
        let (xs, ys) = self.ranges(body.dim_in_pixel());
        let chart = ChartBuilder::on(&body)
            .margin(MARGIN)
            .build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)?;
        let area = chart.plotting_area();
        let px_per_unit = f64::from(area.dim_in_pixel().0.max(1)) / (xs.1 - xs.0);
        // Axes first, under the translucent faces: their parts behind the box show through.
        // No ticks: the points (t_min, 0, 0) … sit next to the labelled vertices.
        let axis_labels = self.draw_axes(area, px_per_unit)?;
        self.draw_faces(area)?;
        self.draw_edges(area, px_per_unit)?;
        self.draw_labels(area, axis_labels)?;
        legend(
            &legend_area,
            &[
                (
                    Swatch::Fill(true),
                    "admissible tensions\nt_min ≤ t ≤ t_max, eq. (3)".into(),
                ),
                (Swatch::Line(EDGE, 3), "visible edges".into()),
                (Swatch::Dashed(EDGE, 2), "hidden edges".into()),
                (Swatch::Dot, "vertices (t₁, t₂, t₃) in N".into()),
            ],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_line_by_hand() {
        let sq = ((-1.0, 1.0), (-1.0, 1.0));
        // x = 0.5 crosses the square from bottom to top; x + y = 1 cuts a corner; x = 2 misses.
        assert_eq!(
            clip_line((2.0, 0.0), 1.0, sq.0, sq.1),
            Some(((0.5, -1.0), (0.5, 1.0)))
        );
        let ((a, b), (c, d)) = clip_line((1.0, 1.0), 1.0, sq.0, sq.1).unwrap();
        let mut ends = [(a, b), (c, d)];
        ends.sort_by(|p, q| p.0.total_cmp(&q.0));
        for (got, want) in ends.iter().zip([(0.0, 1.0), (1.0, 0.0)]) {
            assert!((got.0 - want.0).abs() < 1e-12 && (got.1 - want.1).abs() < 1e-12);
        }
        assert_eq!(clip_line((1.0, 0.0), 2.0, sq.0, sq.1), None);
        assert_eq!(clip_line((0.0, 0.0), 0.0, sq.0, sq.1), None);
    }

    #[test]
    fn equal_scales() {
        let (xs, ys) = equal_scale_ranges((0.0, 2.0), (0.0, 1.0), 0.0, (400, 400));
        assert_eq!((xs, ys), ((0.0, 2.0), (-0.5, 1.5)));
        let (xs, ys) = equal_scale_ranges((0.0, 1.0), (0.0, 1.0), 0.5, (200, 100));
        assert_eq!(ys, (-0.5, 1.5));
        assert_eq!(xs, (-1.5, 2.5));
    }

    /// In the default view every vertex of a cube projects to its own point and exactly the
    /// three faces t_j = t_max face the viewer.
    #[test]
    fn box_view_separates_the_vertices() {
        let b = TensionBoxPlot::new([50.0; 3], [500.0; 3]);
        let p: Vec<(f64, f64)> = (0..8).map(|k| b.project(b.corner(k))).collect();
        for i in 0..8 {
            for j in 0..i {
                assert!((p[i].0 - p[j].0).hypot(p[i].1 - p[j].1) > 50.0, "{i} {j}");
            }
        }
        for j in 0..3 {
            assert!(b.visible(j, true) && !b.visible(j, false));
        }
    }

    #[test]
    fn coincident_points_share_a_label() {
        let fig = CandidateLinesPlot {
            points: vec![
                ((0.0, 0.0), "a".into()),
                ((1.0, 0.0), "b".into()),
                ((0.0, 1e-12), "c".into()),
            ],
            ..CandidateLinesPlot::default()
        };
        assert_eq!(
            fig.merged_points(),
            [
                ((0.0, 0.0), "a = c".to_string()),
                ((1.0, 0.0), "b".to_string())
            ]
        );
    }

    #[test]
    fn both_figures_are_written() {
        let dir = tempfile::tempdir().unwrap();
        let mut fig8 = CandidateLinesPlot {
            title: "unit square".into(),
            polygon: vec![(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)],
            lines: vec![((0.0, 1.0), 0.0, true), ((1.0, -1.0), 0.0, false)],
            origin: true,
            ..CandidateLinesPlot::default()
        };
        fig8.points = fig8
            .polygon
            .iter()
            .map(|&p| (p, format!("{p:?}")))
            .collect();
        let mut fig3 = TensionBoxPlot::new([50.0; 3], [500.0; 3]);
        fig3.notes.push("a note".into());
        for (name, result) in [
            (
                "fig8.png",
                super::super::save(&fig8, dir.path().join("fig8.png")),
            ),
            (
                "fig3.svg",
                super::super::save(&fig3, dir.path().join("fig3.svg")),
            ),
        ] {
            result.unwrap();
            assert!(std::fs::metadata(dir.path().join(name)).unwrap().len() > 5_000);
        }
    }
}

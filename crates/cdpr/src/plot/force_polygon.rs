//! A convex polygon in a plane with origin-centred inscribed shapes and marked points: the
//! operational force polygon of Krut, Company & Pierrot 2004, Fig. 4 (available force polygon {W t}, the largest
//! centred circle, whose radius is the maximum isotropic force of eq. (19), the largest-area
//! centred ellipse of §IV-C, and the facet the circle touches), or the feasible polygon of
//! Picard, Caro, Plestan & Claveau 2020, Fig. 2 in λ coordinates with its barycentre, the stiffness-oriented solution and the
//! intermediate solutions.
//!
//! The axes have equal scales, so circles look round. The legend sits in a column to the right
//! of the chart and the notes under the title, so neither covers the data.

use super::{DrawResult, Figure, layout};
use cdpr_polytope::{AvailableWrenchSet, InscribedEllipse, isotropic_wrench_radius};
use plotters::coord::Shift;
use plotters::prelude::*;

/// A segment (from, to).
pub type Segment = ((f64, f64), (f64, f64));

/// A polygon with an optional centred circle and ellipse, highlighted edges, points and dashed
/// segments, each labelled in the legend.
#[derive(Debug, Clone, Default)]
pub struct ForcePolygonPlot {
    /// Title.
    pub title: String,
    /// Axis labels (x, y).
    pub labels: (String, String),
    /// Lines printed under the title (values, settings).
    pub notes: Vec<String>,
    /// The polygon's vertices in order (closed automatically), filled.
    pub polygon: Vec<(f64, f64)>,
    /// Legend entry of the polygon.
    pub polygon_label: String,
    /// Circle centred at the origin: (radius, legend entry); not drawn unless radius > 0.
    pub circle: Option<(f64, String)>,
    /// Ellipse {B u : ‖u‖ ≤ 1} centred at the origin: (B = [[b11, b12], [b21, b22]], legend).
    pub ellipse: Option<([[f64; 2]; 2], String)>,
    /// Edges drawn thick (e.g. the facets the circle touches), with one legend entry.
    pub highlighted_edges: (Vec<Segment>, String),
    /// Mark the origin with a cross (legend "origin").
    pub origin: bool,
    /// Marked points with their legend entries (a different marker for each).
    pub points: Vec<((f64, f64), String)>,
    /// Dashed segments with their legend entries.
    pub segments: Vec<(Segment, String)>,
}

const FILL: RGBColor = RGBColor(198, 219, 239);
const EDGE: RGBColor = RGBColor(8, 69, 148);
const CIRCLE: RGBColor = RGBColor(214, 39, 40);
const ELLIPSE: RGBColor = RGBColor(44, 160, 44);
const HIGHLIGHT: RGBColor = RGBColor(255, 127, 14);
const SEGMENT: RGBColor = RGBColor(90, 90, 90);
const POINTS: [RGBColor; 5] = [
    RGBColor(148, 103, 189),
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
];
const LEGEND_WIDTH: u32 = 300;

/// How a legend entry is drawn.
enum Swatch {
    Fill,
    Line(RGBColor, u32),
    Dashed(RGBColor, u32),
    Origin,
    Point(usize),
}

/// Draws the marker of point `k` at `at` on `area` (data or pixel coordinates).
fn marker<DB, CT>(area: &DrawingArea<DB, CT>, k: usize, at: CT::From) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    CT: plotters::coord::CoordTranslate,
{
    let c = POINTS[k % POINTS.len()];
    let e = EmptyElement::at(at);
    match k % 4 {
        0 => area.draw(&(e + Circle::new((0, 0), 7, c.filled())))?,
        1 => area.draw(&(e + Rectangle::new([(-7, -7), (7, 7)], c.filled())))?,
        2 => area.draw(&(e + TriangleMarker::new((0, 0), 9, c.filled())))?,
        _ => area.draw(&(e + Cross::new((0, 0), 7, c.stroke_width(3))))?,
    }
    Ok(())
}

/// Points of the origin-centred ellipse {B u : ‖u‖ = 1}.
fn ellipse_points(b: &[[f64; 2]; 2]) -> Vec<(f64, f64)> {
    (0..=240)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 240.0;
            let (c, s) = (a.cos(), a.sin());
            (b[0][0] * c + b[0][1] * s, b[1][0] * c + b[1][1] * s)
        })
        .collect()
}

/// The facets n_k · f ≤ d_k with d_k ≤ r + tol (those the circle of radius r touches) as edges
/// between their two vertices, and their outward normals' angles (degrees in [0, 360), rounded
/// to 0.1°); none when r ≤ 0.
type TouchingFacets = (Vec<((f64, f64), (f64, f64))>, Vec<f64>);

fn touching_facets(
    aws: &AvailableWrenchSet,
    vertices: &[(f64, f64)],
    r: f64,
    tol: f64,
) -> TouchingFacets {
    let mut edges = Vec::new();
    let mut touching = Vec::new();
    if r > 0.0 {
        for f in aws.facets().iter().filter(|f| f.offset <= r + tol) {
            let on: Vec<(f64, f64)> = vertices
                .iter()
                .copied()
                .filter(|&(x, y)| (f.normal[0] * x + f.normal[1] * y - f.offset).abs() <= tol)
                .collect();
            if let [a, b] = on[..] {
                edges.push((a, b));
                // In [0°, 360°), rounded to 0.1° (so that −0 and 360 do not appear).
                let deg = f.normal[1]
                    .atan2(f.normal[0])
                    .to_degrees()
                    .rem_euclid(360.0);
                touching.push((deg * 10.0).round() % 3600.0 / 10.0);
            }
        }
    }
    (edges, touching)
}

/// The note lines of [`ForcePolygonPlot::operational`]: the vertex count and circle radius (N),
/// the touching facets' normals, the ellipse's semi-axes (N), angle and area (N²).
fn operational_notes(
    vertex_count: usize,
    r: f64,
    mut touching: Vec<f64>,
    ellipse: Option<&InscribedEllipse>,
) -> Vec<String> {
    let mut notes = vec![format!(
        "{} vertices; largest centred circle: radius {:.1} N (maximum isotropic force, eq. 19){}",
        vertex_count,
        r,
        if r > 0.0 {
            ""
        } else {
            ": the origin is outside, no circle"
        }
    )];
    touching.sort_by(f64::total_cmp);
    if !touching.is_empty() {
        notes.push(format!(
            "circle touches {} facet(s), outward normals at {}",
            touching.len(),
            touching
                .iter()
                .map(|a| format!("{a:.1}°"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if let Some(e) = ellipse {
        let [a, b] = e.semi_axes;
        notes.push(if a - b <= 1e-6 * a {
            format!("largest centred ellipse: the circle (semi-axes {a:.1} N, {b:.1} N)")
        } else {
            format!(
                "largest centred ellipse: semi-axes {a:.1} N, {b:.1} N, major axis at {:.1}°, \
                 area {:.0} N²",
                e.angle.to_degrees(),
                e.area()
            )
        });
    }
    notes
}

impl ForcePolygonPlot {
    /// Krut, Company & Pierrot 2004, Fig. 4 for a 2-D available wrench set (point2 robots): the polygon from its
    /// vertices, the largest origin-centred circle (radius min_k d_k over the supporting
    /// half-spaces n_k · f ≤ d_k, the maximum isotropic force of eq. (19); drawn only when the
    /// origin is strictly inside), the facets whose offset equals that radius (to 10⁻⁷ of the
    /// polygon's size) highlighted, the origin, and `ellipse` (Krut, Company & Pierrot 2004, §IV-C) if given. Notes
    /// give the values. `None` unless the set is 2-D and bounded.
    pub fn operational(
        aws: &AvailableWrenchSet,
        ellipse: Option<&InscribedEllipse>,
    ) -> Option<Self> {
        if aws.dof() != 2 {
            return None;
        }
        let vertices: Vec<(f64, f64)> = aws.vertices()?.iter().map(|v| (v[0], v[1])).collect();
        if vertices.len() < 3 {
            return None;
        }
        let r = isotropic_wrench_radius(aws);
        let size = vertices
            .iter()
            .map(|&(x, y)| x.hypot(y))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let (edges, touching) = touching_facets(aws, &vertices, r, 1e-7 * size);
        let notes = operational_notes(vertices.len(), r, touching, ellipse);
        Some(Self {
            labels: ("f_x (N)".into(), "f_y (N)".into()),
            notes,
            polygon: vertices,
            polygon_label: "available force polygon {W t}".into(),
            circle: (r > 0.0).then(|| (r, format!("largest centred circle, r = {r:.1} N"))),
            ellipse: ellipse.map(|e| {
                let m = e.matrix;
                (
                    [[m[(0, 0)], m[(0, 1)]], [m[(1, 0)], m[(1, 1)]]],
                    "largest centred ellipse".to_string(),
                )
            }),
            highlighted_edges: (edges, "facet(s) touching the circle".into()),
            origin: true,
            ..Self::default()
        })
    }

    /// The legend entries in drawing order.
    fn legend(&self) -> Vec<(Swatch, String)> {
        let mut out = Vec::new();
        if !self.polygon.is_empty() {
            out.push((Swatch::Fill, self.polygon_label.clone()));
        }
        if let Some((r, label)) = &self.circle
            && *r > 0.0
        {
            out.push((Swatch::Line(CIRCLE, 3), label.clone()));
        }
        if let Some((_, label)) = &self.ellipse {
            out.push((Swatch::Dashed(ELLIPSE, 3), label.clone()));
        }
        if !self.highlighted_edges.0.is_empty() {
            out.push((Swatch::Line(HIGHLIGHT, 5), self.highlighted_edges.1.clone()));
        }
        for (_, label) in &self.segments {
            out.push((Swatch::Dashed(SEGMENT, 2), label.clone()));
        }
        if self.origin {
            out.push((Swatch::Origin, "origin".into()));
        }
        for (k, (_, label)) in self.points.iter().enumerate() {
            out.push((Swatch::Point(k), label.clone()));
        }
        out
    }
}

/// The chart of a force polygon (N on both axes).
type Chart<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

impl ForcePolygonPlot {
    /// The square view: its centre and half-width (N) around the polygon, shapes, points,
    /// segments and the origin (equal scales).
    fn view(&self) -> ((f64, f64), f64) {
        let mut pts: Vec<(f64, f64)> = self.polygon.clone();
        if let Some((r, _)) = &self.circle
            && *r > 0.0
        {
            pts.extend([(-r, -r), (*r, *r)]);
        }
        if let Some((b, _)) = &self.ellipse {
            pts.extend(ellipse_points(b));
        }
        pts.extend(self.points.iter().map(|p| p.0));
        pts.extend(self.segments.iter().flat_map(|(s, _)| [s.0, s.1]));
        if self.origin || pts.is_empty() {
            pts.push((0.0, 0.0));
        }
        let ((x0, x1), (y0, y1)) = layout::bounds(pts);
        let half = (0.5 * (x1 - x0).max(y1 - y0) * 1.08).max(1e-9);
        ((0.5 * (x0 + x1), 0.5 * (y0 + y1)), half)
    }

    /// The polygon, the highlighted edges, the circle and the ellipse.
    fn draw_shapes<DB: DrawingBackend>(&self, chart: &mut Chart<'_, DB>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        if self.polygon.len() > 1 {
            let mut p = self.polygon.clone();
            p.push(self.polygon[0]);
            chart.draw_series(std::iter::once(Polygon::new(p.clone(), FILL.filled())))?;
            chart.draw_series(std::iter::once(PathElement::new(p, EDGE.stroke_width(2))))?;
        }
        for (a, b) in &self.highlighted_edges.0 {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![*a, *b],
                HIGHLIGHT.stroke_width(5),
            )))?;
        }
        if let Some((r, _)) = &self.circle
            && *r > 0.0
        {
            let r = *r;
            let circle = ellipse_points(&[[r, 0.0], [0.0, r]]);
            chart.draw_series(std::iter::once(PathElement::new(
                circle,
                CIRCLE.stroke_width(3),
            )))?;
        }
        if let Some((b, _)) = &self.ellipse {
            // Dashed, so that a circle under it (an isotropic polygon) stays visible.
            chart.draw_series(DashedLineSeries::new(
                ellipse_points(b),
                12,
                8,
                ELLIPSE.stroke_width(3),
            ))?;
        }
        Ok(())
    }

    /// The segments, the origin and the points.
    fn draw_marks<DB: DrawingBackend>(&self, chart: &mut Chart<'_, DB>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        for ((a, b), _) in &self.segments {
            chart.draw_series(DashedLineSeries::new(
                vec![*a, *b],
                10,
                6,
                SEGMENT.stroke_width(2),
            ))?;
        }
        if self.origin {
            chart.draw_series(std::iter::once(
                EmptyElement::at((0.0, 0.0)) + Cross::new((0, 0), 8, BLACK.stroke_width(2)),
            ))?;
        }
        for (k, (p, _)) in self.points.iter().enumerate() {
            marker(chart.plotting_area(), k, *p)?;
        }
        Ok(())
    }

    /// The legend column; a label may span several lines ('\n').
    fn draw_legend<DB: DrawingBackend>(&self, legend: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let mut y = 30;
        for (swatch, label) in self.legend() {
            draw_swatch(legend, swatch, y)?;
            for line in label.lines() {
                legend.draw(&Text::new(
                    line.to_string(),
                    (SWATCH_X.1 + 10, y - 8),
                    ("sans-serif", 15).into_font(),
                ))?;
                y += 19;
            }
            y += 12;
        }
        Ok(())
    }
}

/// The legend swatches' left and right ends (px).
const SWATCH_X: (i32, i32) = (10, 46);

/// One legend swatch centred at height `y` (px).
fn draw_swatch<DB: DrawingBackend>(
    legend: &DrawingArea<DB, Shift>,
    swatch: Swatch,
    y: i32,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let (sx0, sx1) = SWATCH_X;
    match swatch {
        Swatch::Fill => {
            legend.draw(&Rectangle::new([(sx0, y - 8), (sx1, y + 8)], FILL.filled()))?;
            legend.draw(&Rectangle::new(
                [(sx0, y - 8), (sx1, y + 8)],
                EDGE.stroke_width(2),
            ))?;
        }
        Swatch::Line(c, width) => {
            legend.draw(&PathElement::new(
                vec![(sx0, y), (sx1, y)],
                c.stroke_width(width),
            ))?;
        }
        Swatch::Dashed(c, width) => {
            for x in [sx0, sx0 + 14, sx0 + 28] {
                legend.draw(&PathElement::new(
                    vec![(x, y), (x + 8, y)],
                    c.stroke_width(width),
                ))?;
            }
        }
        Swatch::Origin => {
            legend.draw(
                &(EmptyElement::at((28, y)) + Cross::new((0, 0), 8, BLACK.stroke_width(2))),
            )?;
        }
        Swatch::Point(i) => marker(legend, i, (28, y))?,
    }
    Ok(())
}

impl Figure for ForcePolygonPlot {
    fn size(&self) -> (u32, u32) {
        (1050, 820)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let ((cx, cy), half) = self.view();
        let (body, legend) = layout::layout(root, &self.title, &self.notes, LEGEND_WIDTH)?;
        let mut chart = ChartBuilder::on(&body)
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(62)
            .build_cartesian_2d(cx - half..cx + half, cy - half..cy + half)?;
        chart
            .configure_mesh()
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.08))
            .x_desc(self.labels.0.as_str())
            .y_desc(self.labels.1.as_str())
            .x_label_formatter(&|v| super::tick(*v))
            .y_label_formatter(&|v| super::tick(*v))
            .label_style(("sans-serif", 14))
            .draw()?;
        self.draw_shapes(&mut chart)?;
        self.draw_marks(&mut chart)?;
        self.draw_legend(&legend)
    }
}

//! Workspace figures in the style of the thesis (thesis Figs. 6.4, 6.5, 6.8, 6.9): frame anchors,
//! the cables drawn to the platform at one pose, the feasible region filled, boundaries outlined.

use super::{DrawResult, Figure};
use plotters::coord::Shift;
use plotters::prelude::*;

/// A planar workspace drawing.
#[derive(Debug, Clone, Default)]
pub struct WorkspacePlot {
    /// Title.
    pub title: String,
    /// Frame anchors c^i.
    pub anchors: Vec<(f64, f64)>,
    /// Cables drawn at one pose: (frame anchor, platform attachment point).
    pub cables: Vec<((f64, f64), (f64, f64))>,
    /// Platform outline at that pose (closed polygon through the attachment points).
    pub platform: Vec<(f64, f64)>,
    /// Feasible grid points, each drawn as a filled cell of size `cell`.
    pub feasible_points: Vec<(f64, f64)>,
    /// Grid spacing (Δx, Δy).
    pub cell: (f64, f64),
    /// Boundary polygons (chord method), outlined.
    pub boundaries: Vec<Vec<(f64, f64)>>,
    /// Fill the inside of `boundaries`: counter-clockwise polygons (regions) in the workspace
    /// colour, clockwise ones (holes) white, largest first so that nested curves show.
    pub fill_boundaries: bool,
    /// Extra annotation lines printed under the title (area, settings).
    pub notes: Vec<String>,
    /// The frame outline (e.g. the 2 × 2 square), drawn thin.
    pub frame: Vec<(f64, f64)>,
    /// Extra open polylines drawn as chained (dash-dot) lines, e.g. the section line of
    /// thesis Fig. 6.6(a); they count in the view's extent.
    pub chained_lines: Vec<Vec<(f64, f64)>>,
    /// Points marked with a red ring, e.g. the bifurcation points of a chord boundary.
    pub markers: Vec<(f64, f64)>,
    /// What the red rings mark, shown in a legend (none: no legend).
    pub marker_label: Option<String>,
    /// Axis captions (default "x" and "y"), e.g. "y (m)" and "z (m)" for a section x = c.
    pub axis_names: Option<(String, String)>,
    /// Drawn in a box near the top of the chart, e.g. "no feasible pose in the box": an empty
    /// result says so instead of looking like a missing drawing.
    pub empty_message: Option<String>,
    /// Anchor labels: the cables' `name` keys (empty: `A1`, `A2`, …; see [`super::anchor_label`]).
    pub anchor_names: Vec<String>,
}

const FILL: RGBColor = RGBColor(158, 202, 225);
const BOUNDARY: RGBColor = RGBColor(8, 69, 148);
const CABLE: RGBColor = RGBColor(120, 120, 120);
const MARKER: RGBColor = RGBColor(200, 30, 30);

/// The chart of a workspace figure (m on both axes).
type Chart<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

impl WorkspacePlot {
    /// The square view around the content: its centre and half-width (m).
    fn view(&self) -> ((f64, f64), f64) {
        let pts = self
            .anchors
            .iter()
            .chain(self.frame.iter())
            .chain(self.boundaries.iter().flatten())
            .chain(self.feasible_points.iter())
            .chain(self.chained_lines.iter().flatten());
        let (mut x0, mut x1, mut y0, mut y1) = (-1.0f64, 1.0f64, -1.0f64, 1.0f64);
        for &(x, y) in pts {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        // Equal scales on both axes: a square view around the content, with room outside the
        // outermost anchors for their labels.
        let room = if self.anchors.is_empty() { 1.08 } else { 1.22 };
        let half = 0.5 * (x1 - x0).max(y1 - y0) * room;
        ((0.5 * (x0 + x1), 0.5 * (y0 + y1)), half)
    }

    /// The title and the note lines; returns the area under them.
    fn header<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<DrawingArea<DB, Shift>, Box<dyn std::error::Error>>
    where
        DB::ErrorType: 'static,
    {
        let titled = root.titled(&self.title, ("sans-serif", 20))?;
        let (notes, body) = titled.split_vertically(4 + 18 * self.notes.len() as u32);
        for (k, note) in self.notes.iter().enumerate() {
            notes.draw(&Text::new(
                note.clone(),
                (70, 2 + 18 * k as i32),
                ("sans-serif", 14).into_font(),
            ))?;
        }
        Ok(body)
    }

    /// The chart with its axes.
    fn chart<'a, DB: DrawingBackend>(
        &self,
        body: &'a DrawingArea<DB, Shift>,
        (cx, cy): (f64, f64),
        half: f64,
    ) -> Result<Chart<'a, DB>, Box<dyn std::error::Error>>
    where
        DB::ErrorType: 'static,
    {
        let mut chart = ChartBuilder::on(body)
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(cx - half..cx + half, cy - half..cy + half)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.axis_names.as_ref().map_or("x", |a| a.0.as_str()))
            .y_desc(self.axis_names.as_ref().map_or("y", |a| a.1.as_str()))
            .x_label_formatter(&|v| super::tick(*v))
            .y_label_formatter(&|v| super::tick(*v))
            .label_style(("sans-serif", 14))
            .draw()?;
        Ok(chart)
    }

    /// The frame outline, the feasible cells, the filled regions and the boundaries.
    fn draw_regions<DB: DrawingBackend>(&self, chart: &mut Chart<'_, DB>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        if self.frame.len() > 1 {
            let mut f = self.frame.clone();
            f.push(self.frame[0]);
            chart.draw_series(std::iter::once(PathElement::new(
                f,
                BLACK.mix(0.4).stroke_width(1),
            )))?;
        }
        let (dx, dy) = (self.cell.0 / 2.0, self.cell.1 / 2.0);
        chart.draw_series(
            self.feasible_points
                .iter()
                .map(|&(x, y)| Rectangle::new([(x - dx, y - dy), (x + dx, y + dy)], FILL.filled())),
        )?;
        if self.fill_boundaries {
            let mut order: Vec<(f64, &Vec<(f64, f64)>)> = self
                .boundaries
                .iter()
                .map(|b| (signed_area(b), b))
                .collect();
            order.sort_by(|a, b| b.0.abs().total_cmp(&a.0.abs()));
            for (area, b) in order {
                let colour = if area > 0.0 { FILL } else { WHITE };
                chart.draw_series(std::iter::once(Polygon::new(b.clone(), colour.filled())))?;
            }
        }
        for b in &self.boundaries {
            let mut p = b.clone();
            if let Some(&first) = b.first() {
                p.push(first);
            }
            chart.draw_series(std::iter::once(PathElement::new(
                p,
                BOUNDARY.stroke_width(2),
            )))?;
        }
        Ok(())
    }

    /// The chained lines, the cables and the platform.
    fn draw_robot<DB: DrawingBackend>(&self, chart: &mut Chart<'_, DB>, half: f64) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        // Chained lines: dash (4 % of the view), gap, dot, gap, in data units (equal scales).
        let period = 0.08 * half;
        for line in &self.chained_lines {
            let pieces = chain_pattern(line, [0.5 * period, 0.2 * period, 0.1 * period]);
            chart.draw_series(
                pieces
                    .into_iter()
                    .map(|p| PathElement::new(p, RGBColor(200, 30, 30).stroke_width(2))),
            )?;
        }
        for &(a, b) in &self.cables {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![a, b],
                CABLE.stroke_width(1),
            )))?;
        }
        if self.platform.len() > 1 {
            let mut p = self.platform.clone();
            p.push(self.platform[0]);
            chart.draw_series(std::iter::once(Polygon::new(
                p.clone(),
                RGBColor(250, 160, 60).mix(0.55).filled(),
            )))?;
            chart.draw_series(std::iter::once(PathElement::new(p, BLACK.stroke_width(1))))?;
        }
        Ok(())
    }

    /// The red rings and their legend entry.
    fn draw_markers<'a, DB: DrawingBackend + 'a>(&self, chart: &mut Chart<'a, DB>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let ring = |p: (f64, f64)| Circle::new(p, 6, MARKER.stroke_width(2));
        let rings = chart.draw_series(self.markers.iter().map(|&p| ring(p)))?;
        if let Some(label) = self
            .marker_label
            .as_ref()
            .filter(|_| !self.markers.is_empty())
        {
            rings
                .label(label.as_str())
                .legend(move |(x, y)| Circle::new((x, y), 6, MARKER.stroke_width(2)));
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .label_font(("sans-serif", 14))
                .draw()?;
        }
        Ok(())
    }

    /// The anchors and their labels, and the message of an empty result.
    fn draw_anchors<DB: DrawingBackend>(&self, chart: &mut Chart<'_, DB>, half: f64) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        // Anchors that coincide in the drawing (e.g. the upper and lower anchors of a spatial
        // frame seen from above) share one label; labels sit outside, away from the centroid.
        let labels = anchor_labels(&self.anchors, &self.anchor_names, 0.01 * half);
        chart.draw_series(labels.into_iter().map(|((x, y), text, (ox, oy))| {
            let dx = (ox * 16.0) as i32 - if ox < -0.3 { 7 * text.len() as i32 } else { 0 };
            let dy = (-oy * 16.0) as i32 - 8;
            EmptyElement::at((x, y))
                + Rectangle::new([(-5, -5), (5, 5)], BLACK.filled())
                + Text::new(text, (dx, dy), ("sans-serif", 14).into_font())
        }))?;
        if let Some(message) = &self.empty_message {
            let area = chart.plotting_area().strip_coord_spec();
            let (w, h) = area.dim_in_pixel();
            let font = ("sans-serif", 18).into_font();
            let width = 9 * message.chars().count() as i32 + 24;
            // Near the top, clear of the platform drawn at the centre.
            let (x, y) = (w as i32 / 2 - width / 2, h as i32 / 8);
            area.draw(&Rectangle::new(
                [(x, y), (x + width, y + 36)],
                WHITE.filled(),
            ))?;
            area.draw(&Rectangle::new(
                [(x, y), (x + width, y + 36)],
                RGBColor(200, 30, 30).stroke_width(2),
            ))?;
            area.draw(&Text::new(message.clone(), (x + 12, y + 8), font))?;
        }
        Ok(())
    }
}

impl Figure for WorkspacePlot {
    fn size(&self) -> (u32, u32) {
        (800, 820)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (centre, half) = self.view();
        // Title, then the note lines, then the chart.
        let body = self.header(root)?;
        let mut chart = self.chart(&body, centre, half)?;
        self.draw_regions(&mut chart)?;
        self.draw_robot(&mut chart, half)?;
        self.draw_markers(&mut chart)?;
        self.draw_anchors(&mut chart, half)
    }
}

/// A drawn anchor position, its label, and the unit direction in which the label goes.
type AnchorLabel = ((f64, f64), String, (f64, f64));

/// One label per drawn anchor position: anchors closer than `tolerance` share a label
/// ("A1, A5", or the cables' names); each label comes with the unit direction from the anchors' centroid to the anchor
/// (where to put the text so that it points away from the frame's inside).
fn anchor_labels(anchors: &[(f64, f64)], names: &[String], tolerance: f64) -> Vec<AnchorLabel> {
    let mut groups: Vec<((f64, f64), Vec<usize>)> = Vec::new();
    for (i, &p) in anchors.iter().enumerate() {
        match groups
            .iter_mut()
            .find(|(q, _)| (q.0 - p.0).hypot(q.1 - p.1) <= tolerance)
        {
            Some((_, members)) => members.push(i),
            None => groups.push((p, vec![i])),
        }
    }
    let n = groups.len().max(1) as f64;
    let cx = groups.iter().map(|g| g.0.0).sum::<f64>() / n;
    let cy = groups.iter().map(|g| g.0.1).sum::<f64>() / n;
    groups
        .into_iter()
        .map(|(p, members)| {
            let text = members
                .iter()
                .map(|&i| super::anchor_label(names, i))
                .collect::<Vec<_>>()
                .join(", ");
            let (dx, dy) = (p.0 - cx, p.1 - cy);
            let r = dx.hypot(dy);
            let dir = if r > 0.0 {
                (dx / r, dy / r)
            } else {
                (0.7, 0.7)
            };
            (p, text, dir)
        })
        .collect()
}

/// Splits a polyline into the drawn pieces of a dash–gap–dot–gap pattern with lengths
/// [dash, gap, dot].
fn chain_pattern(line: &[(f64, f64)], [dash, gap, dot]: [f64; 3]) -> Vec<Vec<(f64, f64)>> {
    let pattern = [(dash, true), (gap, false), (dot, true), (gap, false)];
    let mut out = Vec::new();
    if !(dash > 0.0 && gap > 0.0 && dot > 0.0) {
        return out;
    }
    let (mut k, mut left) = (0, pattern[0].0);
    let mut current: Vec<(f64, f64)> = line.first().copied().into_iter().collect();
    for w in line.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let mut s = 0.0;
        while len - s > left {
            s += left;
            let p = (a.0 + (b.0 - a.0) * s / len, a.1 + (b.1 - a.1) * s / len);
            if pattern[k].1 {
                current.push(p);
                out.push(std::mem::take(&mut current));
            } else {
                current = vec![p];
            }
            k = (k + 1) % pattern.len();
            left = pattern[k].0;
        }
        left -= len - s;
        if pattern[k].1 {
            current.push(b);
        }
    }
    if pattern[k].1 && current.len() > 1 {
        out.push(current);
    }
    out
}

/// Shoelace signed area (positive counter-clockwise).
fn signed_area(p: &[(f64, f64)]) -> f64 {
    let n = p.len();
    0.5 * (0..n)
        .map(|k| {
            let (a, b) = (p[k], p[(k + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
}

impl WorkspacePlot {
    /// Frame anchors, and the cables and platform drawn at `pose` (if no cable is degenerate there).
    pub fn with_robot(self, robot: &cdpr_kinematics::Robot, pose: &cdpr_kinematics::Pose) -> Self {
        self.with_robot_projected(robot, pose, [0, 1])
    }

    /// The robot at `pose` projected on the coordinate plane of `axes` (e.g. [1, 2]: the y–z
    /// plane, for a section x = c).
    pub fn with_robot_projected(
        mut self,
        robot: &cdpr_kinematics::Robot,
        pose: &cdpr_kinematics::Pose,
        axes: [usize; 2],
    ) -> Self {
        let [a, b] = axes;
        let pr = |v: &nalgebra::Vector3<f64>| (v[a], v[b]);
        self.anchors = robot.cables().iter().map(|c| pr(&c.frame)).collect();
        if let Ok(kin) = robot.inverse_kinematics(pose) {
            self.cables = robot
                .cables()
                .iter()
                .zip(kin.cables())
                .map(|(c, s)| (pr(&c.frame), pr(&s.attachment_point)))
                .collect();
            // Platform outline: attachment points ordered by angle around the platform origin.
            let mut pts: Vec<(f64, f64)> = kin
                .cables()
                .iter()
                .map(|s| pr(&s.attachment_point))
                .collect();
            let (px, py) = pr(&pose.position);
            pts.sort_by(|a, b| {
                (a.1 - py)
                    .atan2(a.0 - px)
                    .total_cmp(&(b.1 - py).atan2(b.0 - px))
            });
            pts.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12);
            self.platform = pts;
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::{anchor_labels, chain_pattern};

    /// The 8 anchors of a spatial frame seen from above: 4 drawn positions, each labelled once
    /// with both cables, the labels pointing away from the centre.
    #[test]
    fn coinciding_anchors_share_one_label() {
        let corners = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];
        let anchors: Vec<(f64, f64)> = corners.iter().chain(&corners).copied().collect();
        let labels = anchor_labels(&anchors, &[], 1e-3);
        assert_eq!(labels.len(), 4);
        assert_eq!(labels[0].1, "A1, A5");
        let names: Vec<String> = ["NE", "", "", "", "NE low"].map(String::from).to_vec();
        assert_eq!(anchor_labels(&anchors, &names, 1e-3)[0].1, "NE, NE low");
        assert_eq!(labels[3].1, "A4, A8");
        let s = 0.5f64.sqrt();
        assert!((labels[1].2.0 + s).abs() < 1e-12 && (labels[1].2.1 - s).abs() < 1e-12);
        // Distinct anchors keep their own labels.
        assert_eq!(anchor_labels(&corners, &[], 1e-3).len(), 4);
    }

    /// Dash 0.5, gap 0.2, dot 0.1 along a 1.25-long polyline with a corner at x = 0.6: drawn
    /// pieces [0, 0.5], [0.7, 0.8] and [1.0, 1.25] of arc length (the corner falls in a gap).
    #[test]
    fn chained_line_pieces_by_hand() {
        let line = [(0.0, 0.0), (0.6, 0.0), (0.6, 0.65)];
        let pieces = chain_pattern(&line, [0.5, 0.2, 0.1]);
        let close = |p: (f64, f64), q: (f64, f64)| (p.0 - q.0).abs() + (p.1 - q.1).abs() < 1e-12;
        assert_eq!(pieces.len(), 3, "{pieces:?}");
        assert!(close(pieces[0][0], (0.0, 0.0)) && close(pieces[0][1], (0.5, 0.0)));
        assert_eq!(pieces[1].len(), 2);
        assert!(close(pieces[1][0], (0.6, 0.1)) && close(pieces[1][1], (0.6, 0.2)));
        assert!(close(pieces[2][0], (0.6, 0.4)) && close(pieces[2][1], (0.6, 0.65)));
        // A dash across the corner keeps the corner point.
        let pieces = chain_pattern(&line, [1.0, 0.1, 0.1]);
        assert_eq!(pieces[0], vec![(0.0, 0.0), (0.6, 0.0), (0.6, 0.4)]);
        assert!(chain_pattern(&line, [0.0, 0.1, 0.1]).is_empty());
    }
}

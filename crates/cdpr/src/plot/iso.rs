//! The 3-D workspace figure for `--plot FILE.png|svg` of spatial and point3 robots: an
//! isometric view of the workspace mesh (painter's order, flat shading, semi-transparent) with
//! the frame anchors, the robot at its draw pose and the search box; and three orthogonal
//! sections through the draw pose (z, y and x = const), each with axes in metres. Anchor labels
//! are placed so that they do not overlap ([`super::scene::place_labels`]).

use super::scene::{Scene, place_labels};
use super::{DrawResult, Figure, tick};
use plotters::coord::Shift;
use plotters::prelude::*;

/// The figure of a [`Scene`].
#[derive(Debug, Clone)]
pub struct IsoFigure {
    /// The scene.
    pub scene: Scene,
}

const MESH: RGBColor = RGBColor(70, 130, 180);
const SECTION: RGBColor = RGBColor(214, 39, 40);
const BOX: RGBColor = RGBColor(31, 95, 160);
const CABLE: RGBColor = RGBColor(90, 90, 90);
const PLATFORM: RGBColor = RGBColor(232, 163, 61);
const AXES: [&str; 3] = ["x", "y", "z"];

/// Isometric view: yaw 45°, elevation atan(1/√2) ≈ 35.26° (the true isometric angles).
struct Camera {
    centre: [f64; 3],
    scale: f64,
    origin: (f64, f64),
}

impl Camera {
    fn view(&self, p: &[f64; 3]) -> [f64; 3] {
        let (sy, cy) = (-std::f64::consts::FRAC_PI_4).sin_cos();
        let e = (1.0f64 / 2f64.sqrt()).atan();
        let (se, ce) = e.sin_cos();
        let (x, y, z) = (
            p[0] - self.centre[0],
            p[1] - self.centre[1],
            p[2] - self.centre[2],
        );
        let (x1, y1) = (x * cy - y * sy, x * sy + y * cy);
        [x1, y1 * se + z * ce, -y1 * ce + z * se]
    }
    fn screen(&self, v: &[f64; 3]) -> (i32, i32) {
        (
            (self.origin.0 + v[0] * self.scale).round() as i32,
            (self.origin.1 - v[1] * self.scale).round() as i32,
        )
    }
    fn project(&self, p: &[f64; 3]) -> (i32, i32) {
        self.screen(&self.view(p))
    }
}

fn dashed<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: (i32, i32),
    b: (i32, i32),
    style: ShapeStyle,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    let (dx, dy) = ((b.0 - a.0) as f64, (b.1 - a.1) as f64);
    let len = dx.hypot(dy);
    let steps = (len / 6.0).ceil().max(1.0) as usize;
    for k in (0..steps).step_by(2) {
        let s0 = k as f64 / steps as f64;
        let s1 = ((k + 1) as f64 / steps as f64).min(1.0);
        let p = |s: f64| (a.0 + (dx * s).round() as i32, a.1 + (dy * s).round() as i32);
        area.draw(&PathElement::new(vec![p(s0), p(s1)], style))?;
    }
    Ok(())
}

fn box_corners(lo: [f64; 3], hi: [f64; 3]) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { lo[0] } else { hi[0] },
                if i & 2 == 0 { lo[1] } else { hi[1] },
                if i & 4 == 0 { lo[2] } else { hi[2] },
            ]
        })
        .collect()
}

const BOX_EDGES: [(usize, usize); 12] = [
    (0, 1),
    (2, 3),
    (4, 5),
    (6, 7),
    (0, 2),
    (1, 3),
    (4, 6),
    (5, 7),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];

impl IsoFigure {
    /// The camera that fits the scene's bounding box into `area` (w × h px).
    fn camera(&self, (w, h): (u32, u32)) -> Camera {
        let (lo, hi) = self.scene.bounds();
        let centre = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
        let mut cam = Camera {
            centre,
            scale: 1.0,
            origin: (w as f64 / 2.0, h as f64 / 2.0 + 8.0),
        };
        // Fit the bounding box's corners.
        let views: Vec<[f64; 3]> = box_corners(lo, hi).iter().map(|c| cam.view(c)).collect();
        let span = |k: usize| {
            let (a, b) = views
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |m, v| {
                    (m.0.min(v[k]), m.1.max(v[k]))
                });
            (b - a).max(1e-12)
        };
        cam.scale = ((w as f64 - 60.0) / span(0)).min((h as f64 - 70.0) / span(1));
        cam
    }

    /// The frame (the anchors' bounding box, grey) and the search box (dashed).
    fn draw_boxes<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        cam: &Camera,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let s = &self.scene;
        if let Some(first) = s.anchors.first() {
            let (mut alo, mut ahi) = (*first, *first);
            for a in &s.anchors {
                for k in 0..3 {
                    alo[k] = alo[k].min(a[k]);
                    ahi[k] = ahi[k].max(a[k]);
                }
            }
            let c = box_corners(alo, ahi);
            for (i, j) in BOX_EDGES {
                area.draw(&PathElement::new(
                    vec![cam.project(&c[i]), cam.project(&c[j])],
                    RGBColor(200, 200, 200).stroke_width(1),
                ))?;
            }
        }
        if s.hide_box {
            return Ok(());
        }
        let c = box_corners(s.region.0, s.region.1);
        for (i, j) in BOX_EDGES {
            dashed(
                area,
                cam.project(&c[i]),
                cam.project(&c[j]),
                BOX.stroke_width(1),
            )?;
        }
        Ok(())
    }

    /// The boundary mesh, shaded, back to front.
    fn draw_mesh<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        cam: &Camera,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let s = &self.scene;
        let light = [0.35, 0.45, 0.82];
        // (depth, screen corners, shade) per triangle.
        type Shaded = (f64, [(i32, i32); 3], f64);
        let mut tris: Vec<Shaded> = s
            .triangles
            .iter()
            .map(|t| {
                let v = t.map(|i| cam.view(&s.vertices[i as usize]));
                let u = [0, 1, 2].map(|k| v[1][k] - v[0][k]);
                let q = [0, 1, 2].map(|k| v[2][k] - v[0][k]);
                let n = [
                    u[1] * q[2] - u[2] * q[1],
                    u[2] * q[0] - u[0] * q[2],
                    u[0] * q[1] - u[1] * q[0],
                ];
                let nn = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-300);
                let shade = (n[0] * light[0] + n[1] * light[1] + n[2] * light[2]).abs() / nn;
                let depth = (v[0][2] + v[1][2] + v[2][2]) / 3.0;
                (depth, v.map(|p| cam.screen(&p)), shade)
            })
            .collect();
        tris.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, p, shade) in &tris {
            let k = 0.45 + 0.55 * shade;
            let c = RGBColor(
                (MESH.0 as f64 * k) as u8,
                (MESH.1 as f64 * k) as u8,
                (MESH.2 as f64 * k + 40.0 * (1.0 - k)) as u8,
            );
            area.draw(&Polygon::new(p.to_vec(), c.mix(0.45).filled()))?;
        }
        Ok(())
    }

    /// The robot at the draw pose: cables (sagging ones as their catenaries), platform faces
    /// back to front, anchors.
    fn draw_robot<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        cam: &Camera,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let s = &self.scene;
        for (a, b) in (0..s.cables.len()).flat_map(|i| s.cable_segments(i)) {
            area.draw(&PathElement::new(
                vec![cam.project(&a), cam.project(&b)],
                CABLE.stroke_width(1),
            ))?;
        }
        let mut faces: Vec<(f64, Vec<(i32, i32)>)> = s
            .platform
            .iter()
            .map(|f| {
                let v: Vec<[f64; 3]> = f.iter().map(|p| cam.view(p)).collect();
                let d = v.iter().map(|p| p[2]).sum::<f64>() / v.len() as f64;
                (d, v.iter().map(|p| cam.screen(p)).collect())
            })
            .collect();
        faces.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, f) in &faces {
            area.draw(&Polygon::new(f.clone(), PLATFORM.mix(0.9).filled()))?;
        }
        if s.platform.is_empty() {
            area.draw(&Circle::new(
                cam.project(&s.platform_position),
                4,
                PLATFORM.filled(),
            ))?;
        }
        self.anchor_labels(area, |p| cam.project(p))
    }

    /// The axes triad at the box's lower corner, and that corner's coordinates.
    fn draw_triad<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        cam: &Camera,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let s = &self.scene;
        let (lo, hi) = s.bounds();
        let o = s.region.0;
        let len = 0.15 * (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        for k in 0..3 {
            let mut e = o;
            e[k] += len;
            let colour = [
                RGBColor(192, 57, 43),
                RGBColor(39, 174, 96),
                RGBColor(46, 98, 201),
            ][k];
            area.draw(&PathElement::new(
                vec![cam.project(&o), cam.project(&e)],
                colour.stroke_width(2),
            ))?;
            let p = cam.project(&e);
            area.draw(&Text::new(
                format!("{} (m)", AXES[k]),
                (p.0 + 3, p.1 - 14),
                ("sans-serif", 13).into_font(),
            ))?;
        }
        let corner = |c: [f64; 3]| format!("({}, {}, {}) m", tick(c[0]), tick(c[1]), tick(c[2]));
        let p = cam.project(&s.region.0);
        area.draw(&Text::new(
            corner(s.region.0),
            (p.0 - 40, p.1 + 10),
            ("sans-serif", 12).into_font().color(&BOX),
        ))?;
        Ok(())
    }

    /// The isometric view: boxes, mesh, robot and axes.
    fn draw_iso<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        area.draw(&Text::new(
            "isometric view",
            (10, 6),
            ("sans-serif", 16).into_font(),
        ))?;
        let cam = self.camera(area.dim_in_pixel());
        self.draw_boxes(area, &cam)?;
        self.draw_mesh(area, &cam)?;
        self.draw_robot(area, &cam)?;
        self.draw_triad(area, &cam)
    }

    /// Anchors as black squares with non-overlapping labels A1, A2, …
    fn anchor_labels<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        project: impl Fn(&[f64; 3]) -> (i32, i32),
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let pts: Vec<(f64, f64)> = self
            .scene
            .anchors
            .iter()
            .map(|a| {
                let p = project(a);
                (p.0 as f64, p.1 as f64)
            })
            .collect();
        let names: Vec<String> = (0..pts.len())
            .map(|i| super::anchor_label(&self.scene.anchor_names, i))
            .collect();
        let (w, h) = area.dim_in_pixel();
        for (p, corner, text) in place_labels(&pts, &names, 7.5, 14.0, (w as f64, h as f64)) {
            let p = (p.0 as i32, p.1 as i32);
            area.draw(&Rectangle::new(
                [(p.0 - 3, p.1 - 3), (p.0 + 3, p.1 + 3)],
                BLACK.filled(),
            ))?;
            area.draw(&Text::new(
                text,
                (corner.0 as i32, corner.1 as i32),
                ("sans-serif", 13).into_font(),
            ))?;
        }
        Ok(())
    }

    /// The section's chart range: the scene's bounds on axes `u`, `v`, padded and widened to
    /// equal scales in a w × h px area (x0, x1, y0, y1, m).
    fn section_range(&self, (u, v): (usize, usize), (w, h): (u32, u32)) -> (f64, f64, f64, f64) {
        let (lo, hi) = self.scene.bounds();
        // Equal scales: widen the shorter range to the plot's aspect ratio.
        let (pw, ph) = (w as f64 - 75.0, h as f64 - 75.0);
        let (mut x0, mut x1, mut y0, mut y1) = (lo[u], hi[u], lo[v], hi[v]);
        let pad = 0.05 * (x1 - x0).max(y1 - y0);
        (x0, x1, y0, y1) = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
        let per_px = ((x1 - x0) / pw).max((y1 - y0) / ph);
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        (x0, x1) = (cx - 0.5 * pw * per_px, cx + 0.5 * pw * per_px);
        (y0, y1) = (cy - 0.5 * ph * per_px, cy + 0.5 * ph * per_px);
        (x0, x1, y0, y1)
    }

    /// The section by the plane `axis` = the draw pose's coordinate.
    fn draw_section<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        axis: usize,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let s = &self.scene;
        let value = s.platform_position[axis];
        let (u, v) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let (x0, x1, y0, y1) = self.section_range((u, v), area.dim_in_pixel());
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("section {} = {} m", AXES[axis], tick(value)),
                ("sans-serif", 16),
            )
            .margin(8)
            .x_label_area_size(38)
            .y_label_area_size(50)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("{} (m)", AXES[u]))
            .y_desc(format!("{} (m)", AXES[v]))
            .x_label_formatter(&|x| tick(*x))
            .y_label_formatter(&|y| tick(*y))
            .label_style(("sans-serif", 13))
            .draw()?;
        let (b0, b1) = s.region;
        chart.draw_series((!s.hide_box).then(|| {
            PathElement::new(
                vec![
                    (b0[u], b0[v]),
                    (b1[u], b0[v]),
                    (b1[u], b1[v]),
                    (b0[u], b1[v]),
                    (b0[u], b0[v]),
                ],
                BOX.stroke_width(1),
            )
        }))?;
        for (a, b) in (0..s.cables.len()).flat_map(|i| s.cable_segments(i)) {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(a[u], a[v]), (b[u], b[v])],
                CABLE.mix(0.5).stroke_width(1),
            )))?;
        }
        let section = s.section(axis, value);
        chart.draw_series(section.iter().map(|(a, b)| {
            PathElement::new(vec![(a[u], a[v]), (b[u], b[v])], SECTION.stroke_width(2))
        }))?;
        if section.is_empty() && !s.hide_box {
            chart.draw_series(std::iter::once(Text::new(
                "(the plane misses the workspace)",
                (x0 + 0.05 * (x1 - x0), y1 - 0.06 * (y1 - y0)),
                ("sans-serif", 13).into_font(),
            )))?;
        }
        chart.draw_series(std::iter::once(Circle::new(
            (s.platform_position[u], s.platform_position[v]),
            4,
            PLATFORM.filled(),
        )))?;
        let to_px = |p: &[f64; 3]| chart.backend_coord(&(p[u], p[v]));
        let pts: Vec<(i32, i32)> = s.anchors.iter().map(to_px).collect();
        let (ox, oy) = area.get_base_pixel();
        self.anchor_labels(area, |p| {
            let k = s.anchors.iter().position(|a| a == p).unwrap_or(0);
            (pts[k].0 - ox, pts[k].1 - oy)
        })?;
        Ok(())
    }
}

impl IsoFigure {
    /// The colour key under the notes: the robot alone (no mesh, no search box) or with its
    /// workspace.
    fn key(&self) -> String {
        let s = &self.scene;
        if s.triangles.is_empty() && s.hide_box {
            return "grey: cables at the pose; orange: platform; light grey: the frame anchors' \
                    bounding box"
                .to_string();
        }
        format!(
            "blue: {}; red: its sections; grey: cables at the draw pose; orange: platform; \
             dashed: search box",
            if s.mesh_label.is_empty() {
                "workspace"
            } else {
                &s.mesh_label
            }
        )
    }
}

impl Figure for IsoFigure {
    fn size(&self) -> (u32, u32) {
        (1300, 1100)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let titled = root.titled(&self.scene.title, ("sans-serif", 20))?;
        let notes = &self.scene.legend;
        let (top, body) = titled.split_vertically(6 + 18 * notes.len() as u32 + 20);
        for (k, note) in notes.iter().enumerate() {
            top.draw(&Text::new(
                note.clone(),
                (14, 2 + 18 * k as i32),
                ("sans-serif", 14).into_font(),
            ))?;
        }
        top.draw(&Text::new(
            self.key(),
            (14, 2 + 18 * notes.len() as i32),
            ("sans-serif", 13).into_font().color(&RGBColor(90, 90, 90)),
        ))?;
        let panels = body.split_evenly((2, 2));
        self.draw_iso(&panels[0])?;
        self.draw_section(&panels[1], 2)?;
        self.draw_section(&panels[2], 1)?;
        self.draw_section(&panels[3], 0)?;
        Ok(())
    }
}

//! One cable over a swivel pulley (Pott 2018 model): a side view in the pulley plane (wrap angle
//! β, tangent point C, free segment) and a view along the swivel axis (swivel angle γ).

use super::{DrawResult, Figure};
use cdpr_kinematics::{Cable, KinematicsError, MotionPattern, Pose, Pulley, Robot};
use nalgebra::Vector3;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The geometry of one pulley cable, in pulley coordinates, computed by `cdpr-kinematics`.
#[derive(Debug, Clone)]
pub struct PulleyCablePlot {
    /// Title.
    pub title: String,
    /// Radius ρ (m).
    pub radius: f64,
    /// Attachment in the pulley frame: p = Qᵀ (B − a) (m).
    pub attachment: Vector3<f64>,
    /// Tangent point in the pulley frame: Qᵀ (C − a) (m).
    pub exit_point: Vector3<f64>,
    /// Swivel angle γ (rad).
    pub swivel_angle: f64,
    /// Wrap angle β (rad).
    pub wrap_angle: f64,
    /// Total length L = ρ β + l_f (m) and free length l_f (m).
    pub lengths: (f64, f64),
}

impl PulleyCablePlot {
    /// The figure for a pulley of radius `radius` about `axis` through the origin and a point
    /// platform at `attachment` (base coordinates), through the library's inverse kinematics.
    pub fn new(
        title: &str,
        radius: f64,
        axis: Vector3<f64>,
        attachment: Vector3<f64>,
    ) -> Result<Self, KinematicsError> {
        let pulley = Pulley::from_axis(radius, axis);
        let robot = Robot::new(
            MotionPattern::Point3,
            vec![Cable {
                frame: Vector3::zeros(),
                platform: Vector3::zeros(),
                pulley: Some(pulley),
            }],
        )?;
        let kin =
            robot.inverse_kinematics(&Pose::point(attachment.x, attachment.y, attachment.z))?;
        let state = kin.pulley(0).expect("the only cable has a pulley");
        let q = pulley.orientation;
        Ok(Self {
            title: title.to_string(),
            radius,
            attachment: q.transpose() * attachment,
            exit_point: q.transpose() * state.exit_point,
            swivel_angle: state.swivel_angle(),
            wrap_angle: state.wrap_angle,
            lengths: (kin.cables()[0].length, state.free_length),
        })
    }
}

const CABLE: RGBColor = RGBColor(214, 39, 40);
const PULLEY: RGBColor = RGBColor(31, 119, 180);
const ANGLE: RGBColor = RGBColor(44, 160, 44);

fn label<DB: DrawingBackend>(
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    text: &str,
    at: (f64, f64),
    colour: RGBColor,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    chart.draw_series(std::iter::once(Text::new(
        text.to_string(),
        at,
        ("sans-serif", 17).into_font().color(&colour),
    )))?;
    Ok(())
}

/// A chart of the figure, in metres on both axes.
type Chart<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// `n + 1` points `f(k / n)`, k = 0 … n.
fn sampled(n: usize, f: impl Fn(f64) -> (f64, f64)) -> Vec<(f64, f64)> {
    (0..=n).map(|k| f(k as f64 / n as f64)).collect()
}

/// The dashed line style of axes.
fn axis_style() -> ShapeStyle {
    BLACK.mix(0.5).stroke_width(1)
}

/// A chart with its mesh (no light lines) over `x` × `y` (m).
fn chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): (std::ops::Range<f64>, std::ops::Range<f64>),
    (x_desc, y_desc): (&str, &str),
) -> Result<Chart<'a, DB>, Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(x, y)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", 14))
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    Ok(chart)
}

impl PulleyCablePlot {
    /// B's radial distance s from the swivel axis and its height h along it (m).
    fn attachment_sh(&self) -> (f64, f64) {
        (
            self.attachment.x.hypot(self.attachment.y),
            self.attachment.z,
        )
    }

    /// The tangent point C in the side view: radial x' (towards B) and axial z' (m).
    fn exit_side(&self) -> (f64, f64) {
        let (gc, gs) = (self.swivel_angle.cos(), self.swivel_angle.sin());
        (
            self.exit_point.x * gc + self.exit_point.y * gs,
            self.exit_point.z,
        )
    }

    /// Side view: the swivel axis, the pulley, the wrapped arc, β and the free segment.
    fn draw_side<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let rho = self.radius;
        let (s, h) = self.attachment_sh();
        let span = s.max(h.abs()).max(3.0 * rho) * 1.15;
        let mut chart = chart(
            area,
            "in the pulley plane (side view)",
            (-0.35 * span..1.05 * span, -0.7 * span..0.7 * span),
            ("radial x' (m)", "along the swivel axis z' (m)"),
        )?;
        // Swivel axis and the incoming cable along +k.
        chart.draw_series(DashedLineSeries::new(
            vec![(0.0, -0.7 * span), (0.0, 0.7 * span)],
            8,
            5,
            axis_style(),
        ))?;
        label(
            &mut chart,
            "swivel axis k",
            (0.01 * span, 0.62 * span),
            BLACK,
        )?;
        chart.draw_series(LineSeries::new(
            vec![(0.0, -0.7 * span), (0.0, 0.0)],
            CABLE.stroke_width(3),
        ))?;
        label(
            &mut chart,
            "cable from the winch (+k)",
            (0.01 * span, -0.6 * span),
            CABLE,
        )?;
        self.draw_pulley_and_wrap(&mut chart, span)?;
        self.draw_side_points(&mut chart, span)
    }

    /// The pulley circle (centre M = (ρ, 0)), the wrapped arc from a to C and the wrap angle β.
    fn draw_pulley_and_wrap<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        span: f64,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let rho = self.radius;
        let (cx, cz) = self.exit_side();
        let circle = sampled(200, |u| {
            let t = u * std::f64::consts::TAU;
            (rho + rho * t.cos(), rho * t.sin())
        });
        chart.draw_series(LineSeries::new(circle, PULLEY.stroke_width(2)))?;
        chart.draw_series(std::iter::once(Circle::new((rho, 0.0), 3, PULLEY.filled())))?;
        label(chart, "M", (rho + 0.03 * span, -0.04 * span), PULLEY)?;
        // Wrapped arc from a (β = 0) to C (β): (ρ (1 − cos t), ρ sin t).
        let arc = sampled(200, |u| {
            let t = u * self.wrap_angle;
            (rho * (1.0 - t.cos()), rho * t.sin())
        });
        chart.draw_series(LineSeries::new(arc, CABLE.stroke_width(3)))?;
        // Wrap angle β at M, from Ma to MC.
        let wedge = sampled(100, |u| {
            let t = u * self.wrap_angle;
            (rho - 0.45 * rho * t.cos(), 0.45 * rho * t.sin())
        });
        chart.draw_series(LineSeries::new(wedge, ANGLE.stroke_width(2)))?;
        chart.draw_series(LineSeries::new(
            vec![(0.0, 0.0), (rho, 0.0), (cx, cz)],
            ANGLE.mix(0.7).stroke_width(1),
        ))?;
        let mid = 0.5 * self.wrap_angle;
        label(
            chart,
            &format!("β = {:.3} rad", self.wrap_angle),
            (
                rho - 0.9 * rho * mid.cos() + 0.02 * span,
                0.9 * rho * mid.sin() + 0.06 * span,
            ),
            ANGLE,
        )
    }

    /// The free segment C → B, the points a, C, B and the lengths.
    fn draw_side_points<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        span: f64,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let rho = self.radius;
        let (s, h) = self.attachment_sh();
        let (cx, cz) = self.exit_side();
        chart.draw_series(LineSeries::new(
            vec![(cx, cz), (s, h)],
            CABLE.stroke_width(3),
        ))?;
        for (p, name) in [
            ((0.0, 0.0), "a"),
            ((cx, cz), "C (tangent point)"),
            ((s, h), "B (attachment)"),
        ] {
            chart.draw_series(std::iter::once(Circle::new(p, 5, BLACK.filled())))?;
            label(chart, name, (p.0 + 0.03 * span, p.1 + 0.03 * span), BLACK)?;
        }
        let (l, lf) = self.lengths;
        label(
            chart,
            &format!("L = ρβ + l_f = {l:.3} m (l_f = {lf:.3} m, ρ = {rho} m)"),
            (-0.3 * span, -0.66 * span),
            BLACK,
        )
    }

    /// View along the swivel axis: e₁ (γ = 0), the pulley plane at γ, and B's projection.
    fn draw_top<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let rho = self.radius;
        let (s, _) = self.attachment_sh();
        let (cx, _) = self.exit_side();
        let (gc, gs) = (self.swivel_angle.cos(), self.swivel_angle.sin());
        let r = s.max(2.0 * rho) * 1.3;
        let mut top = chart(
            area,
            "along the swivel axis (top view)",
            (-r..r, -r..r),
            ("e₁ (m)", "e₂ = k × e₁ (m)"),
        )?;
        top.draw_series(DashedLineSeries::new(
            vec![(0.0, 0.0), (0.95 * r, 0.0)],
            8,
            5,
            axis_style(),
        ))?;
        label(
            &mut top,
            "γ = 0 (first column of Q)",
            (0.3 * r, -0.12 * r),
            BLACK,
        )?;
        // The pulley seen edge-on: a segment of length 2ρ along the radial direction.
        top.draw_series(LineSeries::new(
            vec![(0.0, 0.0), (2.0 * rho * gc, 2.0 * rho * gs)],
            PULLEY.stroke_width(6),
        ))?;
        top.draw_series(LineSeries::new(
            vec![(0.0, 0.0), (cx * gc, cx * gs), (s * gc, s * gs)],
            CABLE.stroke_width(3),
        ))?;
        self.draw_swivel(&mut top, r)
    }

    /// The swivel angle γ and the points a and B in the top view.
    fn draw_swivel<DB: DrawingBackend>(&self, top: &mut Chart<'_, DB>, r: f64) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let (s, _) = self.attachment_sh();
        let (gc, gs) = (self.swivel_angle.cos(), self.swivel_angle.sin());
        let sweep = sampled(100, |u| {
            let t = u * self.swivel_angle;
            (0.3 * r * t.cos(), 0.3 * r * t.sin())
        });
        top.draw_series(LineSeries::new(sweep, ANGLE.stroke_width(2)))?;
        let mid = 0.5 * self.swivel_angle;
        label(
            top,
            &format!("γ = {:.3} rad", self.swivel_angle),
            (0.36 * r * mid.cos(), 0.36 * r * mid.sin()),
            ANGLE,
        )?;
        for (p, name, at) in [
            (
                (0.0, 0.0),
                "a (axis k out of the page)",
                (-0.95 * r, -0.12 * r),
            ),
            (
                (s * gc, s * gs),
                "B",
                (s * gc + 0.04 * r, s * gs + 0.04 * r),
            ),
        ] {
            top.draw_series(std::iter::once(Circle::new(p, 5, BLACK.filled())))?;
            label(top, name, at, BLACK)?;
        }
        Ok(())
    }
}

impl Figure for PulleyCablePlot {
    fn size(&self) -> (u32, u32) {
        (1300, 650)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let root = root.titled(&self.title, ("sans-serif", 22))?;
        let (left, right) = root.split_horizontally(650);
        self.draw_side(&left)?;
        self.draw_top(&right)
    }
}

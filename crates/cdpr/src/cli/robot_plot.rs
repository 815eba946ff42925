//! `--plot FILE` of `cdpr kinematics` and `cdpr tension`: the robot drawn at the pose.
//!
//! 2-D robots (point2, planar) are drawn seen from +z (`.svg`/`.png`), as the workspace
//! figures draw the robot; 3-D robots (point3, spatial) as the isometric view with its three
//! sections (`.svg`/`.png`), and every robot as the interactive viewer (`.html`). Frame anchors
//! carry the cables' `name` keys (else A1, A2, …). `cdpr tension` adds each cable's tension
//! (N, four significant digits) to its anchor's label, and its `.html` page colours the cables by tension (the
//! trajectory replay's blue → red scale, from t_min to the largest tension).

use super::CliError;
use cdpr::RobotDescription;
use cdpr::kinematics::Pose;
use cdpr::plot::replay::Replay;
use cdpr::plot::{Scene, WorkspacePlot, anchor_label, cable_names};
use std::path::Path;

/// The robot at one pose, as `--plot` draws it.
pub struct RobotFigure<'a> {
    /// The robot file.
    pub desc: &'a RobotDescription,
    /// The pose drawn.
    pub pose: &'a Pose,
    /// Title (robot, pose).
    pub title: String,
    /// Lines under the title (method, external wrench, verdict).
    pub notes: Vec<String>,
    /// Cable tensions (N), one per cable: `cdpr tension`'s feasible answer.
    pub tensions: Option<&'a [f64]>,
}

/// `--plot`'s file must end in `.svg`, `.png` or `.html`: checked before any work (exit 2,
/// naming the flag).
pub fn check_path(path: &Path) -> Result<(), CliError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg" | "png" | "html") => Ok(()),
        _ => Err(format!(
            "--plot {}: the robot is drawn as .svg, .png or .html",
            path.display()
        )
        .into()),
    }
}

impl RobotFigure<'_> {
    /// The anchor labels: each cable's name (A1, … without one), with its tension when given.
    fn labels(&self) -> Vec<String> {
        let names = cable_names(&self.desc.cable_names);
        (0..self.desc.robot.cable_count())
            .map(|i| {
                let name = anchor_label(&names, i);
                match self.tensions.and_then(|t| t.get(i)) {
                    // Four significant digits (a label, not a table).
                    Some(t) => {
                        let shown: f64 = format!("{t:.3e}").parse().unwrap_or(*t);
                        format!("{name}: {} N", super::num(shown))
                    }
                    None => name,
                }
            })
            .collect()
    }

    /// Writes the figure to `path` (format by extension, see [`check_path`]).
    pub fn save(&self, path: &Path) -> Result<(), CliError> {
        check_path(path)?;
        let html = super::region::is_html(path);
        if html && self.tensions.is_some() {
            cdpr::plot::replay::save_html(&self.replay(), path)?;
        } else if html || self.desc.robot.motion().space_dim() == 3 {
            cdpr::plot::save_scene(&self.scene(), path)?;
        } else {
            cdpr::plot::save(&self.top_view(), path)?;
        }
        Ok(())
    }

    /// A 2-D robot seen from +z.
    fn top_view(&self) -> WorkspacePlot {
        let axis = super::region::length_axis;
        WorkspacePlot {
            title: self.title.clone(),
            notes: self.notes.clone(),
            axis_names: Some((axis("x"), axis("y"))),
            anchor_names: self.labels(),
            ..WorkspacePlot::default()
        }
        .with_robot(&self.desc.robot, self.pose)
    }

    /// The 3-D scene: anchors, cables and platform, framed by the anchors and the pose.
    fn scene(&self) -> Scene {
        let (lo, hi) = self.desc.robot.frame_bounding_box();
        let p = self.pose.position;
        let region = (
            [lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z)],
            [hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z)],
        );
        Scene {
            title: self.title.clone(),
            legend: self.notes.clone(),
            region,
            hide_box: true,
            anchor_names: self.labels(),
            ..Scene::default()
        }
        .with_robot(
            &self.desc.robot,
            self.pose,
            self.desc.platform_shape.as_ref(),
        )
    }

    /// The HTML page of one frame with the cables coloured by tension.
    fn replay(&self) -> Replay {
        let robot = &self.desc.robot;
        let arr = |v: &nalgebra::Vector3<f64>| [v.x, v.y, v.z];
        let r = self.pose.rotation.matrix();
        let tensions = self.tensions.map(<[f64]>::to_vec);
        let largest = tensions
            .iter()
            .flatten()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let t_min = self
            .desc
            .bounds
            .min()
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        Replay {
            title: self.title.clone(),
            anchors: robot.cables().iter().map(|c| arr(&c.frame)).collect(),
            attachments: robot.cables().iter().map(|c| arr(&c.platform)).collect(),
            t: vec![0.0],
            positions: vec![arr(&self.pose.position)],
            rotations: vec![[0, 1, 2].map(|i| [r[(i, 0)], r[(i, 1)], r[(i, 2)]])],
            tensions: vec![tensions],
            reasons: vec![None],
            t_min,
            t_max: largest.max(t_min),
            planar: robot.motion().space_dim() == 2,
        }
    }
}

//! # Plots
//!
//! SVG or PNG figures (chosen by the file extension) drawn with `plotters` and a bundled font
//! (DejaVu Sans), so no system library is needed. Each figure type implements [`Figure`].

mod force_polygon;
mod heat_map;
pub mod iso;
mod layout;
mod lines;
mod panels;
mod polytope_view;
mod pulley;
pub mod replay;
pub mod scene;
mod vertex_projection;
pub mod viewer;
mod workspace;

pub use force_polygon::{ForcePolygonPlot, Segment};
pub use heat_map::HeatMap;
pub use iso::IsoFigure;
pub use lines::{LinePlot, Placement, Series};
pub use panels::Panels;
pub use polytope_view::force_polytope_scene;
pub use pulley::PulleyCablePlot;
pub use replay::Replay;
pub use scene::{Scene, grid_surface};
pub use vertex_projection::{CandidateLinesPlot, TensionBoxPlot, clip_line};
pub use workspace::WorkspacePlot;

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;
use thiserror::Error;

/// A plot that could not be written.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum PlotError {
    /// The extension is neither `.svg` nor `.png` (nor `.html` for 3-D scenes).
    #[error("{0}: plot files must end in .svg or .png (.html for 3-D workspaces)")]
    UnknownFormat(String),
    /// The folder the file should go to does not exist.
    #[error("cannot write {file}: no such directory ({dir})")]
    NoDirectory {
        /// The file.
        file: String,
        /// Its folder.
        dir: String,
    },
    /// Drawing or writing failed.
    #[error("cannot draw {file}: {message}")]
    Draw {
        /// The file.
        file: String,
        /// What went wrong.
        message: String,
    },
}

/// Result of drawing onto a backend; errors are rendered to text by [`save`].
pub type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// Something that can be drawn on any plotters backend.
pub trait Figure {
    /// Size in pixels.
    fn size(&self) -> (u32, u32) {
        (900, 800)
    }
    /// Draws the figure.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static;
}

static FONT: Once = Once::new();

/// Registers the bundled font as `sans-serif` (idempotent).
pub fn register_font() {
    FONT.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../assets/DejaVuSans.ttf");
        for style in [
            FontStyle::Normal,
            FontStyle::Bold,
            FontStyle::Italic,
            FontStyle::Oblique,
        ] {
            // Registration only fails on a corrupt font file, which is bundled and tested.
            let _ = plotters::style::register_font("sans-serif", style, bytes);
        }
    });
}

/// Writes `figure` to `path` as SVG or PNG according to its extension.
pub fn save(figure: &impl Figure, path: impl AsRef<Path>) -> Result<(), PlotError> {
    register_font();
    let path = path.as_ref();
    let name = path.display().to_string();
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        return Err(PlotError::NoDirectory {
            file: name,
            dir: dir.display().to_string(),
        });
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let err = |e: Box<dyn std::error::Error>| PlotError::Draw {
        file: name.clone(),
        message: e.to_string(),
    };
    match ext.as_deref() {
        Some("svg") => {
            let root = SVGBackend::new(path, figure.size()).into_drawing_area();
            figure.draw(&root).map_err(err)?;
            root.present().map_err(|e| err(Box::new(e)))
        }
        Some("png") => {
            let root = BitMapBackend::new(path, figure.size()).into_drawing_area();
            figure.draw(&root).map_err(err)?;
            root.present().map_err(|e| err(Box::new(e)))
        }
        _ => Err(PlotError::UnknownFormat(name)),
    }
}

/// Writes a 3-D scene: `.html` the interactive viewer ([`viewer`]), `.svg`/`.png` the
/// isometric view with three sections ([`IsoFigure`]).
pub fn save_scene(scene: &Scene, path: impl AsRef<Path>) -> Result<(), PlotError> {
    let path = path.as_ref();
    let html = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("html"));
    if html {
        viewer::save_html(scene, path).map_err(|e| PlotError::Draw {
            file: path.display().to_string(),
            message: e.to_string(),
        })
    } else {
        save(
            &IsoFigure {
                scene: scene.clone(),
            },
            path,
        )
    }
}

/// The label of frame anchor `i` (0-based) in every view (3-D, sections, plots): the cable's
/// `name` from the robot file when `names` gives one, else `A` and its 1-based index.
pub fn anchor_label(names: &[String], i: usize) -> String {
    match names.get(i).filter(|n| !n.is_empty()) {
        Some(n) => n.clone(),
        None => format!("A{}", i + 1),
    }
}

/// The anchor names of a robot file's cables (`name` keys; empty where none) for
/// [`anchor_label`].
pub fn cable_names(names: &[Option<String>]) -> Vec<String> {
    names
        .iter()
        .map(|n| n.clone().unwrap_or_default())
        .collect()
}

/// A colour map from 0 to 1 (viridis-like, perceptually ordered).
pub fn colour_map(v: f64) -> RGBColor {
    const STOPS: [(f64, [u8; 3]); 5] = [
        (0.0, [68, 1, 84]),
        (0.25, [59, 82, 139]),
        (0.5, [33, 145, 140]),
        (0.75, [94, 201, 98]),
        (1.0, [253, 231, 37]),
    ];
    let v = if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        0.0
    };
    for w in STOPS.windows(2) {
        let ((a, ca), (b, cb)) = (w[0], w[1]);
        if v <= b {
            let s = (v - a) / (b - a);
            let mix = |i: usize| (ca[i] as f64 + s * (cb[i] as f64 - ca[i] as f64)).round() as u8;
            return RGBColor(mix(0), mix(1), mix(2));
        }
    }
    RGBColor(253, 231, 37)
}

/// An axis tick label: up to 4 significant decimals, no "-0".
pub fn tick(v: f64) -> String {
    let v = if v.abs() < 1e-12 { 0.0 } else { v };
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

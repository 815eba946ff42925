//! # The HTML replay of a timed trajectory
//!
//! `cdpr trajectory … --time-law LAW --replay FILE.html` writes one self-contained page (no
//! library, no network; `replay.js`, licensed with this crate): the platform (the convex hull of
//! its attachments) and its cables moving along the trajectory, cables coloured by tension on
//! a blue → red scale from t_min to the largest tension along the trajectory (`t_max` of
//! [`Replay`]) and dashed grey at infeasible samples, the path of the
//! platform origin, a play button (real time) and a time slider; drag to orbit, wheel to zoom.
//!
//! When the page has drawn, it writes `replayed N frames of n cables` into `#cdpr-status`
//! (`error: …` if a script error happened): the marker the browser test reads.

use serde_json::json;
use std::path::Path;

const TEMPLATE: &str = include_str!("replay.html");
const SCRIPT: &str = include_str!("replay.js");

/// What the replay shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Replay {
    /// Title (robot, law, method).
    pub title: String,
    /// Frame anchors (m, base frame), one per cable.
    pub anchors: Vec<[f64; 3]>,
    /// Platform attachments (m, platform frame), one per cable.
    pub attachments: Vec<[f64; 3]>,
    /// Sample times (s).
    pub t: Vec<f64>,
    /// Platform origin at each sample (m).
    pub positions: Vec<[f64; 3]>,
    /// Platform orientation at each sample, rows of the rotation matrix.
    pub rotations: Vec<[[f64; 3]; 3]>,
    /// Tensions (N) at each sample, `None` where infeasible.
    pub tensions: Vec<Option<Vec<f64>>>,
    /// Why a sample is infeasible.
    pub reasons: Vec<Option<String>>,
    /// Lower end of the colour scale (N): t_min.
    pub t_min: f64,
    /// Upper end of the colour scale (N): the largest tension along the trajectory.
    pub t_max: f64,
    /// A 2-D robot (seen from +z).
    pub planar: bool,
}

/// The page of a replay.
pub fn html(replay: &Replay) -> String {
    let data = json!({
        "title": replay.title,
        "anchors": replay.anchors,
        "attachments": replay.attachments,
        "t": replay.t,
        "positions": replay.positions,
        "rotations": replay.rotations,
        "tensions": replay.tensions,
        "reasons": replay.reasons,
        "tMin": replay.t_min,
        "tMax": replay.t_max,
        "planar": replay.planar,
    });
    // `</` inside a script element would end it: JSON allows `<\/`.
    let data = data.to_string().replace("</", "<\\/");
    TEMPLATE
        .replace(
            "{{TITLE}}",
            &replay
                .title
                .replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('>', "&gt;"),
        )
        .replace("{{DATA}}", &data)
        .replace("{{SCRIPT}}", SCRIPT)
}

/// Writes the page.
pub fn save_html(replay: &Replay, path: &Path) -> std::io::Result<()> {
    std::fs::write(path, html(replay))
}

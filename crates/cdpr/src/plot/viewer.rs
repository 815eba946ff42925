//! # The HTML viewer
//!
//! `--plot FILE.html` writes one self-contained page: the [`Scene`] as JSON and a small
//! hand-written canvas renderer (no library, no network; about 250 lines of JavaScript in
//! `viewer.js`, licensed with this crate). Orthographic projection, flat shading, painter's
//! order (triangles sorted back to front, drawn semi-transparent); drag to orbit, wheel to
//! zoom, a slider that cuts the workspace by a plane x, y or z = s (the part beyond is hidden,
//! the section drawn in red), and a legend with the volume and the settings.
//!
//! When the page has drawn, it writes `rendered N triangles` into the element
//! `#cdpr-status` (`error: …` if a script error happened): the marker the browser test reads.

use super::scene::Scene;
use serde_json::json;
use std::path::Path;

const TEMPLATE: &str = include_str!("viewer.html");
const SCRIPT: &str = include_str!("viewer.js");

/// The page of a scene.
pub fn html(scene: &Scene) -> String {
    let data = json!({
        "title": scene.title,
        "anchors": scene.anchors,
        "cables": scene.cables.iter().map(|(a, b)| [a, b]).collect::<Vec<_>>(),
        "platform": scene.platform,
        "platformPosition": scene.platform_position,
        "vertices": scene.vertices,
        "triangles": scene.triangles,
        "box": [scene.region.0, scene.region.1],
        "legend": scene.legend,
        "meshLabel": scene.mesh_label,
    });
    // `</` inside a script element would end it: JSON allows `<\/`.
    let data = data.to_string().replace("</", "<\\/");
    TEMPLATE
        .replace("{{TITLE}}", &escape(&scene.title))
        .replace("{{SCENE}}", &data)
        .replace("{{SCRIPT}}", SCRIPT)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Writes the page.
pub fn save_html(scene: &Scene, path: &Path) -> std::io::Result<()> {
    std::fs::write(path, html(scene))
}

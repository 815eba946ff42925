//! # The HTML viewer
//!
//! `--plot FILE.html` writes one self-contained page: the [`Scene`] as JSON and a small
//! hand-written canvas renderer (no library, no network; about 250 lines of JavaScript in
//! `viewer.js`, licensed with this crate). Orthographic projection, flat shading, painter's
//! order (triangles sorted back to front, drawn semi-transparent); drag to orbit, wheel to
//! zoom, a slider that cuts the workspace by a plane x, y or z = s (the part beyond is hidden,
//! the section drawn in red), and a legend with the volume and the settings.
//!
//! The same page shows a force polytope (`cdpr isotropic --pose … --plot FILE.html`, point3
//! robots): the mesh is then the polytope's faces in N, with the largest ball centred at −w_ext
//! drawn inside ([`Scene::ball`]), and no robot.
//!
//! Sagging cables ([`Scene::cable_curves`], `--cable-model catenary`) are drawn as the
//! polylines of their catenaries instead of their chords.
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
        "anchorNames": (0..scene.anchors.len())
            .map(|i| super::anchor_label(&scene.anchor_names, i))
            .collect::<Vec<_>>(),
        "cables": scene.cables.iter().map(|(a, b)| [a, b]).collect::<Vec<_>>(),
        "cableCurves": scene.cable_curves,
        "platform": scene.platform,
        "platformPosition": scene.platform_position,
        "vertices": scene.vertices,
        "triangles": scene.triangles,
        "box": [scene.region.0, scene.region.1],
        "legend": scene.legend,
        "meshLabel": scene.mesh_label,
        "units": if scene.units.is_empty() { "m" } else { scene.units.as_str() },
        "ball": scene.ball.map(|(c, r)| json!({ "centre": c, "radius": r })),
        "ballLabel": scene.ball_label,
        "hideBox": scene.hide_box,
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

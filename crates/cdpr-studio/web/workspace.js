// cdpr studio: the workspace on demand (MIT OR Apache-2.0), drawn in the scene: the boundary
// mesh with its volume (STL and JSON downloads), the feasible grid points (`cdpr workspace
// --grid M`) and plane sections by the chord method (`cdpr workspace --section AXIS=VALUE`), all
// at the orientation shown, with the method and load chosen. Each is one cdpr-api request in
// the wasm session; the page only draws the answer.
import { $, page, fmt, message, writeState, later, download } from "./core.js";
import { update } from "./pose.js";

const AXES = ["x", "y", "z"];

// What is drawn (page.overlay keeps the same arrays until the next computation, so the
// renderer keeps them in its cached layer).
export function clearWorkspace() {
  page.overlay = null;
  page.mesh = null;
  ["workspace", "grid", "section"].forEach((k) => delete page.extra[k]);
  $("stl").disabled = $("mesh-json").disabled = true;
  Object.keys(lines).forEach((k) => delete lines[k]);
  $("mesh-result").textContent = "";
}

// One line per kind of result (mesh, grid, section) under the buttons.
const lines = {};
function say(kind, text) {
  lines[kind] = text;
  $("mesh-result").textContent = ["mesh", "grid", "section"].filter((k) => lines[k]).map((k) => lines[k]).join("\n");
}

function overlay() {
  if (!page.overlay) page.overlay = { vertices: [], triangles: [], points: [], sections: [], box: null };
  return page.overlay;
}

// Runs one workspace request `f` (returns the report, or throws the library's message).
function run(label, f) {
  $("mesh-result").textContent = `computing the ${label}…`;
  return later(() => {
    const t0 = performance.now();
    let r;
    try {
      r = f();
    } catch (e) {
      $("mesh-result").textContent = "";
      message(`${label}: ${e.message}`);
      page.extra.workspace_error = `${label}: ${e.message}`;
      writeState();
      return null;
    }
    message("");
    delete page.extra.workspace_error;
    return { report: r, ms: performance.now() - t0 };
  });
}

function args() {
  return [page.pose.join(","), Number($("grid").value)];
}

export async function computeMesh() {
  const [pose, grid] = args();
  const out = await run("boundary mesh", () => JSON.parse(page.session.workspace_mesh(pose, grid, page.method, page.wrench)));
  if (!out) return false;
  const m = out.report;
  page.mesh = m;
  page.timing.mesh = out.ms;
  Object.assign(overlay(), { vertices: m.vertices, triangles: m.triangles, box: m.box });
  page.extra.workspace = { grid, volume_m3: m.volume, grid_volume_m3: m.grid_volume, triangles: m.triangles.length, method: m.method, criteria: m.criteria };
  say("mesh", `volume ${fmt(m.volume, 4)} m³ (grid count ${fmt(m.grid_volume, 4)} m³), ${m.triangles.length} triangles, grid ${grid}, ${m.evaluations} pose evaluations, ${fmt(out.ms / 1000, 2)} s; criteria ${m.criteria.join(", ")}, method ${m.method}`);
  $("stl").disabled = $("mesh-json").disabled = false;
  update(true);
  return true;
}

export async function computeGrid() {
  const [pose, grid] = args();
  const out = await run("workspace grid", () => JSON.parse(page.session.workspace_grid(pose, grid, page.method, page.wrench)));
  if (!out) return false;
  const g = out.report;
  page.timing.grid = out.ms;
  Object.assign(overlay(), { points: g.points });
  const unit = g.dimension === 2 ? "m²" : "m³";
  page.extra.grid = {
    resolution: g.resolution, dimension: g.dimension, feasible_points: g.feasible_points, total_points: g.total_points,
    area: g.area, area_points: g.area_points, volume: g.volume, criteria: g.criteria, method: g.method, orientation: g.orientation,
  };
  say("grid", `${g.feasible_points} of ${g.total_points} grid points feasible (grid ${g.resolution}); measure ${fmt(g.area, 4)} ${unit} (cells), ${fmt(g.area_points, 4)} ${unit} (points); criteria ${g.criteria.join(", ")}, ${fmt(out.ms / 1000, 2)} s`);
  update(false);
  return true;
}

// The section axis = value (m), chord d (m), seeded by the grid.
export async function computeSection() {
  const [pose, grid] = args();
  const axis = Number($("section-axis").value), value = Number($("section-value").value), chord = Number($("chord").value);
  if (!isFinite(value) || $("section-value").value.trim() === "") {
    message(`section: "${$("section-value").value}" is not a coordinate (m)`);
    return false;
  }
  const out = await run("plane section", () => JSON.parse(page.session.workspace_section(pose, axis, value, grid, chord, page.method, page.wrench)));
  if (!out) return false;
  const s = out.report;
  page.timing.section = out.ms;
  const sections = overlay().sections.filter((x) => !(x.axis === axis)).concat([{ axis, loops: s.loops }]);
  overlay().sections = sections;
  page.extra.section = { axis, value, area: s.area, chord: s.chord, loops: s.loops.length, signed_areas: s.signed_areas, evaluations: s.evaluations };
  const holes = s.signed_areas.filter((a) => a < 0).length;
  say("section", `section ${AXES[axis]} = ${fmt(value, 4)} m: area ${fmt(s.area, 4)} m², ${s.loops.length - holes} region(s), ${holes} hole(s); chord d = ${fmt(chord)} m, ${s.evaluations} pose evaluations, ${fmt(out.ms / 1000, 2)} s`);
  update(false);
  return true;
}

export function wireWorkspace() {
  $("mesh").addEventListener("click", computeMesh);
  $("grid-points").addEventListener("click", computeGrid);
  $("section").addEventListener("click", computeSection);
  $("clear-workspace").addEventListener("click", () => { clearWorkspace(); update(false); });
  $("stl").addEventListener("click", () => download(`${page.table.name}-workspace.stl`, page.session.mesh_stl(), "model/stl"));
  $("mesh-json").addEventListener("click", () => download(`${page.table.name}-workspace.json`, JSON.stringify(page.mesh), "application/json"));
  $("section-axis").addEventListener("change", sectionDefault);
}

// The section value's default: the platform's coordinate along the axis.
export function sectionDefault() {
  const k = Number($("section-axis").value);
  if (page.pose.length > k) $("section-value").value = fmt(page.pose[k], 4);
}

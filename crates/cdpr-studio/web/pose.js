// cdpr studio: the pose (MIT OR Apache-2.0). The sliders, dragging the platform in the 3-D view,
// the state at the pose (cdpr-api's requests through the wasm session) and the scene drawn with
// the shared renderer (viewer.js, window.CdprViewer).
import { $, page, fmt, colour, message, writeState, planar, wrenchUnit } from "./core.js";

const NONE = [];

// Draws `scene` (the session's scene at a pose) with cable colours `colours` and the workspace
// shown (page.overlay: mesh, grid points, sections; the same arrays every time, so the renderer
// keeps them in its cached layer).
export function drawScene(scene, colours, refit) {
  const o = page.overlay || {};
  scene.cableColours = colours;
  scene.vertices = o.vertices || NONE;
  scene.triangles = o.triangles || NONE;
  scene.points = o.points || NONE;
  scene.sections = o.sections || NONE;
  scene.box = o.box || page.table.region;
  scene.planar = planar(page.table.motion);
  scene.anchorNames = page.table.anchorNames;
  if (!page.renderer) page.renderer = CdprViewer.create($("view"), scene, { onPlatformDrag });
  page.renderer.setScene(scene, refit);
  page.scene = scene;
}

// The state at page.pose: tensions, lengths, indices (the library), then the scene.
export function update(refit) {
  if (!page.session) return;
  const t0 = performance.now();
  let state, scene;
  try {
    state = JSON.parse(page.session.state(page.pose.join(","), page.method, page.wrench));
    scene = JSON.parse(page.session.scene(page.pose.join(",")));
  } catch (e) {
    message(e.message);
    page.state = { robot: page.table.name, pose: page.pose.slice(), method: page.method, error: e.message };
    writeState();
    return;
  }
  message("");
  const t1 = performance.now();
  const tens = state.tensions;
  drawScene(scene, scene.cables.map((_, i) => colour(tens ? tens[i] : null, state.t_min[i], state.t_max[i])), refit);
  const t2 = performance.now();
  showState(state);
  poseNote();
  page.state = state;
  page.timing.compute = t1 - t0;
  page.timing.pose_update = performance.now() - t0;
  page.timing.draw = t2 - t1;
  $("timing").textContent = `${fmt(page.timing.pose_update, 2)} ms (library ${fmt(page.timing.compute, 2)} ms)`;
  writeState();
}

function showState(s) {
  const v = $("verdict");
  v.className = "verdict " + (s.feasible ? "ok" : "no");
  v.innerHTML = s.feasible ? `Feasible <span class="why">tensions in bounds, residual ${fmt(s.residual)} N (certified)</span>` : "Infeasible <span class='why'></span>";
  if (!s.feasible) v.querySelector(".why").textContent = s.reason || "";
  const body = $("cables").querySelector("tbody");
  body.innerHTML = "";
  const top = Math.max(...s.t_max.map((t, i) => t === null ? (s.tensions ? Math.abs(s.tensions[i]) : 1) : t), 1e-12);
  s.lengths.forEach((l, i) => {
    const t = s.tensions ? s.tensions[i] : null;
    const lo = s.t_min[i], hi = s.t_max[i] === null ? top : s.t_max[i];
    const tr = document.createElement("tr");
    const left = 100 * lo / top, width = 100 * (hi - lo) / top;
    const at = t === null ? null : Math.max(0, Math.min(100, 100 * t / top));
    tr.innerHTML = `<td>${page.table.anchorNames[i]}</td><td>${fmt(l)}</td><td>${fmt(t, 2)}</td><td class="bar" title="t = ${fmt(t, 3)} N against t_min ${fmt(lo)} N, t_max ${s.t_max[i] === null ? "∞" : fmt(hi)} N"><div class="barbox">` +
      `<span style="left:${left}%;width:${width}%;background:#d5dde6"></span>` +
      (at === null ? "" : `<span style="left:0;width:${at}%;background:${colour(t, lo, s.t_max[i])};opacity:0.9"></span>`) + `</div></td>`;
    body.appendChild(tr);
  });
  const unit = wrenchUnit(s.motion);
  $("margin").textContent = s.capacity_margin === null ? (s.polytope_note || "unbounded") : `${fmt(s.capacity_margin, 3)} ${unit}`;
  $("isotropic").textContent = s.isotropic_force === null ? (s.polytope_note || "—") : `${fmt(s.isotropic_force, 3)} N`;
  $("wext").textContent = `(${s.external_wrench.map((x) => fmt(x, 3)).join(", ")}) ${unit}`;
}

// A position outside the frame's box is computed (the model holds anywhere) but said.
function poseNote() {
  const t = page.table, out = [];
  t.coordinates.forEach(([name, unit], k) => {
    const x = page.pose[k];
    if (unit === "m" && (x < t.region[0][k] - 1e-12 || x > t.region[1][k] + 1e-12)) {
      out.push(`${name} = ${fmt(x, 4)} m is outside the frame's box [${fmt(t.region[0][k], 4)}, ${fmt(t.region[1][k], 4)}] m`);
    }
  });
  $("pose-note").textContent = out.length ? out.join("; ") + ": the numbers are the model's at that pose, with the platform outside the frame." : "";
}

// The user moves the platform: a path replay stops.
function pause() {
  if (page.pauseReplay) page.pauseReplay();
}

// ---- the sliders -------------------------------------------------------------------------------

// One slider and number field per pose coordinate: positions over the frame's box, angles over
// ±π/2 (the number field takes any value).
export function buildSliders() {
  const t = page.table, box = $("pose");
  box.innerHTML = "";
  t.coordinates.forEach(([name, unit], k) => {
    const row = document.createElement("div");
    row.className = "slider";
    const lo = unit === "m" ? t.region[0][k] : -Math.PI / 2, hi = unit === "m" ? t.region[1][k] : Math.PI / 2;
    const pad = unit === "m" && hi - lo < 1e-9 ? 1 : 0;
    row.innerHTML = `<span title="${name} (${unit})">${name} <span class="unit">${unit}</span></span><input type="range" min="${lo - pad}" max="${hi + pad}" step="${(hi - lo + 2 * pad) / 1000}" title="${name} (${unit})"><input type="number" step="any" title="${name} (${unit})">`;
    const [range, num] = row.querySelectorAll("input");
    range.addEventListener("input", () => { pause(); page.pose[k] = +range.value; num.value = fmt(+range.value, 5); update(false); });
    num.addEventListener("change", () => {
      const x = num.value.trim() === "" ? NaN : Number(num.value);
      if (!isFinite(x)) {
        message(`${name}: "${num.value}" is not a number (${unit})`);
        num.value = fmt(page.pose[k], 5);
        return;
      }
      pause(); page.pose[k] = x; range.value = x; update(false);
    });
    box.appendChild(row);
  });
  syncSliders();
}

export function syncSliders() {
  $("pose").querySelectorAll(".slider").forEach((row, k) => {
    const [range, num] = row.querySelectorAll("input");
    range.value = page.pose[k];
    num.value = fmt(page.pose[k], 5);
  });
}

// ---- dragging the platform ---------------------------------------------------------------------

// The renderer turns a drag on the platform into a displacement (m) from the drag's start: the
// position coordinates follow it (x, y in a plane; x, y, z in space), the sliders follow.
function onPlatformDrag(e) {
  if (e.phase === "start") {
    pause();
    page.dragFrom = page.pose.slice();
    return;
  }
  if (e.phase === "end") {
    if (page.dragFrom) page.extra.drag = { from: page.dragFrom, to: page.pose.slice(), axis: e.axis, view: page.renderer.view() };
    page.dragFrom = null;
    writeState();
    return;
  }
  const d = planar(page.table.motion) ? 2 : 3;
  page.pose = page.dragFrom.map((v, k) => (k < d ? v + e.displacement[k] : v));
  syncSliders();
  update(false);
}

// Drags the platform with mouse events on the canvas: from the platform's centre by (dx, dy) px
// in `steps` moves; `mode` "shift" (the best axis) or "x", "y", "z" (a held key), else the view
// plane. Returns the time of each move (ms: the event, the library and the drawing).
export function simulateDrag(dx, dy, mode, steps) {
  const canvas = $("view"), r = canvas.getBoundingClientRect();
  const p = page.renderer.screenOf(page.scene.platformPosition);
  const x0 = r.left + p[0], y0 = r.top + p[1];
  const key = /^[xyz]$/.test(mode || "") ? mode : null;
  const mouse = (type, x, y, target) =>
    target.dispatchEvent(new MouseEvent(type, { clientX: x, clientY: y, shiftKey: mode === "shift", bubbles: true }));
  if (key) window.dispatchEvent(new KeyboardEvent("keydown", { key }));
  mouse("mousedown", x0, y0, canvas);
  const times = [];
  for (let i = 1; i <= steps; i++) {
    const t0 = performance.now();
    mouse("mousemove", x0 + (dx * i) / steps, y0 + (dy * i) / steps, window);
    times.push(performance.now() - t0);
  }
  mouse("mouseup", x0 + dx, y0 + dy, window);
  if (key) window.dispatchEvent(new KeyboardEvent("keyup", { key }));
  if (page.extra.drag) page.extra.drag.pixels = [dx, dy];
  writeState();
  return times;
}

// ---- timing ------------------------------------------------------------------------------------

function median(times) {
  const s = times.slice().sort((a, b) => a - b);
  return { median: s[Math.floor(s.length / 2)], max: s[s.length - 1] };
}

// Real-time cost of `n` pose changes (library + drawing) around the current pose, by the
// sliders' path and by dragging the platform: the median and the largest, in ms.
export function timePoseChanges(n) {
  const base = page.pose.slice(), times = [];
  for (let i = 0; i < n; i++) {
    const t0 = performance.now();
    page.pose = base.map((v, k) => v + (k < 3 ? 0.05 : 0.02) * Math.sin(0.1 * i + k));
    update(false);
    times.push(performance.now() - t0);
  }
  page.pose = base;
  update(false);
  const m = median(times);
  Object.assign(page.timing, { pose_changes: n, pose_change_median: m.median, pose_change_max: m.max });
  const drag = median(simulateDrag(40, -25, null, n));
  page.pose = base;
  syncSliders();
  update(false);
  delete page.extra.drag;
  Object.assign(page.timing, { drag_moves: n, drag_move_median: drag.median, drag_move_max: drag.max });
}

// cdpr studio: the page's glue (MIT OR Apache-2.0). Everything it shows is computed by the cdpr
// crates (cdpr_studio.wasm); this file reads files, builds the controls and draws with the HTML
// viewer's renderer (viewer.js, window.CdprViewer).
//
// Test hook: <output id="cdpr-state"> holds the current state as JSON (robot, pose, lengths,
// tensions, feasible, method, ... and the page's timings in ms); <output id="cdpr-errors">
// collects script errors (it stays empty on a healthy page). Query: ?robot=URL&pose=…&method=…
// &wrench=…&mesh=GRID (numbers comma-separated; a CASPR model by its NAME_cables.xml URL).
// With &timing=N the page loads synchronously and times N pose changes in real time (headless
// Chromium's --virtual-time-budget freezes performance.now(); --dump-dom without it dumps at the
// load event, which a synchronous page has reached only when everything is computed).
import init, { initSync, StudioSession } from "./cdpr_studio.js";

const $ = (id) => document.getElementById(id);
const errors = $("cdpr-errors");
function scriptError(msg) {
  errors.textContent += (errors.textContent ? "\n" : "") + msg;
}
window.addEventListener("error", (e) => scriptError(e.message));
window.addEventListener("unhandledrejection", (e) => scriptError(String(e.reason && e.reason.message || e.reason)));
const consoleError = console.error.bind(console);
console.error = (...a) => { scriptError(a.map(String).join(" ")); consoleError(...a); };

const page = { session: null, table: null, pose: [], method: "l2", wrench: "", state: null, mesh: null, timing: {}, renderer: null };

// An honest message for a bad input (shown over the scene, kept in the state as `error`).
function message(text) {
  const m = $("message");
  m.hidden = !text;
  m.textContent = text || "";
}

function fmt(v, digits = 4) {
  if (v === null || v === undefined) return "—";
  if (!isFinite(v)) return v > 0 ? "∞" : "−∞";
  const a = Math.abs(v);
  if (a !== 0 && (a < 1e-3 || a >= 1e6)) return v.toExponential(3);
  return Number(v.toFixed(digits)).toString();
}

function download(name, text, type) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type: type || "text/plain" }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

// Tension colour: a blue–red ramp over [t_min, t_max]; magenta outside the bounds.
function colour(t, lo, hi) {
  if (t === null || t === undefined) return "#999";
  const top = hi === null ? lo + 1 : hi;
  const eps = 1e-9 * Math.max(1, Math.abs(top));
  if (t < lo - eps || (hi !== null && t > hi + eps)) return "#c51b7d";
  const s = hi === null ? 0.5 : Math.max(0, Math.min(1, (t - lo) / Math.max(hi - lo, 1e-12)));
  const stops = [[33, 102, 172], [27, 158, 119], [230, 97, 1], [178, 24, 43]];
  const x = s * (stops.length - 1), i = Math.min(stops.length - 2, Math.floor(x)), f = x - i;
  const c = stops[i].map((a, k) => Math.round(a + f * (stops[i + 1][k] - a)));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}

function writeState(extra) {
  const s = Object.assign({}, page.state || {}, extra || {});
  s.timing_ms = page.timing;
  s.ready = !!page.ready;
  if (page.mesh) s.workspace = { grid: page.mesh.grid, volume_m3: page.mesh.volume, triangles: page.mesh.triangles.length, method: page.mesh.method, criteria: page.mesh.criteria };
  $("cdpr-state").textContent = JSON.stringify(s);
}

// ---- opening robots ---------------------------------------------------------------------------

async function openFiles(files, pose) {
  const t0 = performance.now();
  let session;
  try {
    session = new StudioSession(JSON.stringify(files));
  } catch (e) {
    message(`Could not open ${files.map((f) => f.name).join(" + ")}:\n${e.message}`);
    page.state = { error: e.message };
    writeState();
    return false;
  }
  if (page.session) page.session.free();
  page.session = session;
  page.mesh = null;
  $("stl").disabled = $("mesh-json").disabled = true;
  $("mesh-result").textContent = "";
  loadTable(pose);
  page.timing.open = performance.now() - t0;
  update(true);
  return true;
}

const SYNC = new URLSearchParams(location.search).has("timing");

// Synchronous requests (the timing mode only).
function syncRequest(url, binary) {
  const x = new XMLHttpRequest();
  x.open("GET", url, false);
  if (binary) x.overrideMimeType("text/plain; charset=x-user-defined");
  x.send();
  if (x.status !== 200) throw new Error(`${url}: HTTP ${x.status}`);
  return x.responseText;
}

async function fetchText(url) {
  if (SYNC) return syncRequest(url, false);
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return r.text();
}

async function openUrl(url, pose) {
  const name = decodeURIComponent(url.split("/").pop().split("?")[0]);
  try {
    const files = [{ name, text: await fetchText(url) }];
    if (/_cables\.xml$/i.test(name)) {
      const bodies = url.replace(/_cables\.xml$/i, "_bodies.xml");
      files.push({ name: name.replace(/_cables\.xml$/i, "_bodies.xml"), text: await fetchText(bodies) });
    }
    return openFiles(files, pose);
  } catch (e) {
    message(`Could not load the robot ${url}: ${e.message}`);
    page.state = { error: e.message };
    writeState();
    return false;
  }
}

async function openLocal(fileList) {
  const files = await Promise.all(Array.from(fileList).map(async (f) => ({ name: f.name, text: await f.text() })));
  // A CASPR pair opens by its cables file.
  files.sort((a, b) => (/_cables\.xml$/i.test(b.name) ? 1 : 0) - (/_cables\.xml$/i.test(a.name) ? 1 : 0));
  openFiles(files);
}

// ---- controls ----------------------------------------------------------------------------------

function loadTable(pose) {
  const t = JSON.parse(page.session.table());
  page.table = t;
  $("robot-name").textContent = `${t.name} — ${t.motion}, ${t.cables.length} cables`;
  // A pose given in the query is kept as given: a wrong one gets the library's message.
  page.pose = pose ? pose.slice() : t.start_pose.slice();
  // Methods that apply, with their reference on hover.
  const sel = $("method");
  sel.innerHTML = "";
  t.methods.forEach((m) => {
    const o = document.createElement("option");
    o.value = m.name; o.textContent = m.name; o.title = m.reference;
    sel.appendChild(o);
  });
  if (!t.methods.some((m) => m.name === page.method)) page.method = t.methods.length ? t.methods[0].name : "l2";
  sel.value = page.method;
  showReference();
  const forces = t.motion === "point2" || t.motion === "planar" ? 2 : 3;
  const moments = t.motion === "planar" ? 1 : t.motion === "spatial" ? 3 : 0;
  $("wrench-unit").textContent = `(${t.coordinates.length} numbers: ${forces} forces in N${moments ? `, ${moments} moment${moments > 1 ? "s" : ""} in N·m` : ""})`;
  // Pose sliders: positions over the anchors' box, angles over ±π/2.
  const box = $("pose");
  box.innerHTML = "";
  t.coordinates.forEach(([name, unit], k) => {
    const row = document.createElement("div");
    row.className = "slider";
    const lo = unit === "m" ? t.region[0][k] : -Math.PI / 2, hi = unit === "m" ? t.region[1][k] : Math.PI / 2;
    const pad = unit === "m" && hi - lo < 1e-9 ? 1 : 0;
    row.innerHTML = `<span title="${unit}">${name}</span><input type="range" min="${lo - pad}" max="${hi + pad}" step="${(hi - lo + 2 * pad) / 1000}"><input type="number" step="any" title="${name} (${unit})">`;
    const [range, num] = row.querySelectorAll("input");
    range.value = num.value = page.pose[k];
    range.addEventListener("input", () => { page.pose[k] = +range.value; num.value = fmt(+range.value, 5); update(false); });
    num.addEventListener("change", () => { page.pose[k] = +num.value; range.value = num.value; update(false); });
    box.appendChild(row);
  });
  // The robot table.
  $("mass").value = t.mass;
  const body = $("table").querySelector("tbody");
  body.innerHTML = "";
  const dim = t.motion === "point2" || t.motion === "planar" ? 2 : 3;
  const vec = (v) => v.slice(0, dim).map((x) => fmt(x, 6)).join(", ");
  t.cables.forEach((c, i) => {
    const tr = document.createElement("tr");
    tr.innerHTML = `<td>${i + 1}</td><td><input data-k="frame" value="${vec(c.frame)}" ${c.pulley ? "disabled title='runs over a pulley'" : ""}></td>` +
      `<td><input data-k="platform" value="${vec(c.platform)}"></td><td><input data-k="t_min" value="${c.t_min}"></td>` +
      `<td><input data-k="t_max" value="${c.t_max === null ? "inf" : c.t_max}"></td>`;
    body.appendChild(tr);
  });
  $("warnings").textContent = t.warnings.length ? "Warnings: " + t.warnings.join("; ") : "";
}

function showReference() {
  const m = page.table && page.table.methods.find((x) => x.name === page.method);
  $("method-reference").textContent = m ? m.reference : "";
  $("method").title = m ? m.reference : "";
}

function readTable() {
  const t = JSON.parse(JSON.stringify(page.table));
  t.mass = Number($("mass").value);
  const dim = t.motion === "point2" || t.motion === "planar" ? 2 : 3;
  const rows = $("table").querySelectorAll("tbody tr");
  rows.forEach((tr, i) => {
    tr.querySelectorAll("input").forEach((inp) => {
      const k = inp.dataset.k, text = inp.value.trim();
      if (k === "frame" || k === "platform") {
        const v = text.split(",").map((x) => Number(x));
        if (v.length !== dim || v.some((x) => !isFinite(x))) throw new Error(`cable ${i + 1}: ${k === "frame" ? "anchor" : "attachment"} needs ${dim} numbers (m), got "${text}"`);
        t.cables[i][k] = dim === 2 ? [v[0], v[1], 0] : v;
      } else if (k === "t_max" && /^(inf|∞)$/i.test(text)) {
        t.cables[i].t_max = null;
      } else {
        const x = Number(text);
        if (text === "" || !isFinite(x)) throw new Error(`cable ${i + 1}: ${k} (N) must be a number, got "${text}"`);
        t.cables[i][k] = x;
      }
    });
  });
  return t;
}

// ---- the state at the pose ---------------------------------------------------------------------

function update(refit) {
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
  scene.cableColours = scene.cables.map((_, i) => colour(tens ? tens[i] : null, state.t_min[i], state.t_max[i]));
  scene.vertices = page.mesh ? page.mesh.vertices : [];
  scene.triangles = page.mesh ? page.mesh.triangles : [];
  scene.box = page.mesh ? page.mesh.box : page.table.region;
  if (!page.renderer) page.renderer = CdprViewer.create($("view"), scene, {});
  page.renderer.setScene(scene, refit);
  const t2 = performance.now();
  showState(state);
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
    tr.innerHTML = `<td>${i + 1}</td><td>${fmt(l)}</td><td>${fmt(t, 2)}</td><td class="bar" title="t_min ${fmt(lo)} N, t_max ${s.t_max[i] === null ? "∞" : fmt(hi)} N"><div class="barbox">` +
      `<span style="left:${left}%;width:${width}%;background:#d5dde6"></span>` +
      (at === null ? "" : `<span style="left:0;width:${at}%;background:${colour(t, lo, s.t_max[i])};opacity:0.9"></span>`) + `</div></td>`;
    body.appendChild(tr);
  });
  const forceUnit = s.motion === "point2" || s.motion === "point3" ? "N" : "N, N·m";
  $("margin").textContent = s.capacity_margin === null ? (s.polytope_note || "unbounded") : `${fmt(s.capacity_margin, 3)} ${forceUnit}`;
  $("isotropic").textContent = s.isotropic_force === null ? (s.polytope_note || "—") : `${fmt(s.isotropic_force, 3)} N`;
  $("wext").textContent = `(${s.external_wrench.map((x) => fmt(x, 3)).join(", ")}) ${forceUnit}`;
}

// ---- the workspace -----------------------------------------------------------------------------

function computeMesh() {
  const grid = Number($("grid").value);
  $("mesh-result").textContent = "computing…";
  // Let the page paint the message before the (single-threaded) computation.
  return new Promise((done) => (SYNC ? (f) => f() : (f) => setTimeout(f, 0))(() => {
    const t0 = performance.now();
    try {
      page.mesh = JSON.parse(page.session.workspace_mesh(page.pose.join(","), grid, page.method, page.wrench));
    } catch (e) {
      $("mesh-result").textContent = "";
      message(e.message);
      page.mesh = null;
      done(false);
      return;
    }
    page.timing.mesh = performance.now() - t0;
    $("mesh-result").textContent = `volume ${fmt(page.mesh.volume, 4)} m³ (grid count ${fmt(page.mesh.grid_volume, 4)} m³), ${page.mesh.triangles.length} triangles, grid ${grid}, ${page.mesh.evaluations} pose evaluations, ${fmt(page.timing.mesh / 1000, 2)} s; criteria ${page.mesh.criteria.join(", ")}, method ${page.mesh.method}`;
    $("stl").disabled = $("mesh-json").disabled = false;
    update(true);
    done(true);
  }));
}

// Real-time cost of `n` pose changes (library + drawing) around the current pose: the median
// and the largest, in ms.
function timePoseChanges(n) {
  const base = page.pose.slice(), times = [];
  for (let i = 0; i < n; i++) {
    const t0 = performance.now();
    page.pose = base.map((v, k) => v + (k < 3 ? 0.05 : 0.02) * Math.sin(0.1 * i + k));
    update(false);
    times.push(performance.now() - t0);
  }
  page.pose = base;
  update(false);
  times.sort((a, b) => a - b);
  page.timing.pose_changes = n;
  page.timing.pose_change_median = times[Math.floor(n / 2)];
  page.timing.pose_change_max = times[n - 1];
}

// ---- start -------------------------------------------------------------------------------------

function numbers(text) {
  return text ? text.split(",").map(Number) : null;
}

async function main() {
  const t0 = performance.now();
  if (SYNC) {
    const text = syncRequest("cdpr_studio_bg.wasm", true);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i) & 0xff;
    initSync({ module: bytes });
  } else {
    await init();
  }
  page.timing.wasm_load = performance.now() - t0;
  const q = new URLSearchParams(location.search);
  page.method = q.get("method") || "l2";
  page.wrench = q.get("wrench") || "";
  $("wrench").value = page.wrench;

  $("method").addEventListener("change", () => { page.method = $("method").value; showReference(); update(false); });
  $("wrench").addEventListener("change", () => { page.wrench = $("wrench").value.trim(); update(false); });
  $("picker").addEventListener("change", (e) => openLocal(e.target.files));
  const drop = $("drop");
  ["dragenter", "dragover"].forEach((ev) => drop.addEventListener(ev, (e) => { e.preventDefault(); drop.classList.add("over"); }));
  ["dragleave", "drop"].forEach((ev) => drop.addEventListener(ev, () => drop.classList.remove("over")));
  drop.addEventListener("drop", (e) => { e.preventDefault(); openLocal(e.dataTransfer.files); });
  $("examples").addEventListener("change", (e) => { if (e.target.value) openUrl(e.target.value); });
  $("mesh").addEventListener("click", computeMesh);
  $("stl").addEventListener("click", () => download(`${page.table.name}-workspace.stl`, page.session.mesh_stl(), "model/stl"));
  $("mesh-json").addEventListener("click", () => {
    download(`${page.table.name}-workspace.json`, JSON.stringify(page.mesh), "application/json");
  });
  $("toml").addEventListener("click", () => download(`${page.table.name}.toml`, page.session.to_toml()));
  $("wcrfx").addEventListener("click", () => {
    try { download(`${page.table.name}.wcrfx`, page.session.to_wcrfx(), "application/xml"); } catch (e) { message(e.message); }
  });
  $("apply").addEventListener("click", () => {
    try {
      page.session.edit(JSON.stringify(readTable()));
      page.mesh = null;
      loadTable(page.pose);
      update(true);
    } catch (e) { message(`Robot table: ${e.message}`); }
  });

  try {
    const list = JSON.parse(await fetchText("robots/index.json"));
    list.forEach((name) => {
      const o = document.createElement("option");
      o.value = "robots/" + name; o.textContent = name.replace(/\.toml$/, "");
      $("examples").appendChild(o);
    });
  } catch (e) {
    message(`The example list could not be read (${e.message}); open a robot file instead.`);
  }
  const robot = q.get("robot") || "robots/ipanema-like-8.toml";
  $("examples").value = robot;
  if (await openUrl(robot, numbers(q.get("pose"))) && q.get("mesh")) {
    $("grid").value = q.get("mesh");
    await computeMesh();
  }
  page.timing.first_state = performance.now() - t0;
  if (SYNC && page.session) timePoseChanges(Math.max(1, Number(q.get("timing")) || 100));
  page.ready = true;
  writeState();
}

main().catch((e) => scriptError(e && e.message ? e.message : String(e)));

// cdpr studio: the page's entry (MIT OR Apache-2.0). Everything it shows is computed by the cdpr
// crates (cdpr_studio.wasm, cdpr-api's requests); the modules read files, build the controls
// and draw with the HTML viewer's renderer (viewer.js, window.CdprViewer):
// core.js (state, test hook, formatting), robot.js (files, methods, robot table), pose.js
// (sliders, dragging the platform, the state at the pose), workspace.js (mesh, grid points,
// sections), path.js (a path replayed with its tension plot).
//
// Test hook: <output id="cdpr-state"> holds the current state as JSON (robot, pose, lengths,
// tensions, feasible, method, ..., workspace, grid, section, path, drag, and the page's timings
// in ms); <output id="cdpr-errors"> collects script errors (it stays empty on a healthy page).
// Query: ?robot=URL&pose=…&method=…&wrench=… (numbers comma-separated; a CASPR model by its
// NAME_cables.xml URL), and on demand &mesh=GRID, &grid=M (grid points), &section=AXIS=VALUE
// (with &chord=D, seeded by &grid or 20), &path=POSE&steps=N (a path to POSE; timed with
// &law=NAME&duration=T&dt=DT[&dynamics=0]), &drag=DX,DY[,MODE]
// (a mouse drag of the platform by DX, DY px; MODE shift, x, y or z).
// With &timing=N the page loads synchronously and times N pose changes in real time (headless
// Chromium's --virtual-time-budget freezes performance.now(); --dump-dom without it dumps at the
// load event, which a synchronous page has reached only when everything is computed).
import init, { initSync } from "./cdpr_studio.js";
import { $, page, SYNC, syncRequest, fetchText, message, writeState, scriptError, download } from "./core.js";
import { openUrl, openLocal, loadTable, readTable, showReference } from "./robot.js";
import { update, simulateDrag, timePoseChanges } from "./pose.js";
import { wireWorkspace, computeMesh, computeGrid, computeSection, clearWorkspace, sectionDefault } from "./workspace.js";
import { wirePath, computePath, clearPath } from "./path.js";

async function loadWasm() {
  if (SYNC) {
    const text = syncRequest("cdpr_studio_bg.wasm", true);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i) & 0xff;
    initSync({ module: bytes });
  } else {
    await init();
  }
}

function wireControls() {
  $("method").addEventListener("change", () => { page.method = $("method").value; showReference(); update(false); });
  $("wrench").addEventListener("change", () => { page.wrench = $("wrench").value.trim(); update(false); });
  $("picker").addEventListener("change", (e) => openLocal(e.target.files));
  const drop = $("drop");
  ["dragenter", "dragover"].forEach((ev) => drop.addEventListener(ev, (e) => { e.preventDefault(); drop.classList.add("over"); }));
  ["dragleave", "drop"].forEach((ev) => drop.addEventListener(ev, () => drop.classList.remove("over")));
  drop.addEventListener("drop", (e) => { e.preventDefault(); openLocal(e.dataTransfer.files); });
  $("examples").addEventListener("change", (e) => { if (e.target.value) openUrl(e.target.value).then(sectionDefault); });
  $("toml").addEventListener("click", () => download(`${page.table.name}.toml`, page.session.to_toml()));
  $("wcrfx").addEventListener("click", () => {
    try { download(`${page.table.name}.wcrfx`, page.session.to_wcrfx(), "application/xml"); } catch (e) { message(e.message); }
  });
  $("apply").addEventListener("click", () => {
    try {
      page.session.edit(JSON.stringify(readTable()));
      clearWorkspace();
      clearPath();
      loadTable(page.pose);
      update(true);
    } catch (e) { message(`Robot table: ${e.message}`); }
  });
  wireWorkspace();
  wirePath();
}

async function exampleList() {
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
}

function numbers(text) {
  return text ? text.split(",").map(Number) : null;
}

// What the query asks for beyond the pose: the workspace, a path, a drag.
async function onDemand(q) {
  if (q.get("grid")) $("grid").value = q.get("grid");
  if (q.get("mesh")) {
    $("grid").value = q.get("mesh");
    await computeMesh();
    if (q.get("grid")) $("grid").value = q.get("grid");
  }
  if (q.get("grid") && !q.get("section")) await computeGrid();
  const sec = /^([xyz])=(.+)$/.exec(q.get("section") || "");
  if (sec) {
    $("section-axis").value = "xyz".indexOf(sec[1]);
    $("section-value").value = sec[2];
    if (!q.get("grid")) $("grid").value = 20;
    if (q.get("chord")) $("chord").value = q.get("chord");
    await computeSection();
  }
  if (q.get("path")) {
    $("time-law").value = q.get("law") || "";
    ["duration", "dt"].forEach((k) => { if (q.get(k)) $(k).value = q.get(k); });
    $("dynamics").checked = q.get("dynamics") !== "0";
    await computePath(q.get("path"), Number(q.get("steps")) || 40);
  }
  const drag = (q.get("drag") || "").split(",");
  if (drag.length >= 2) simulateDrag(Number(drag[0]), Number(drag[1]), drag[2] || null, 10);
}

async function main() {
  const t0 = performance.now();
  await loadWasm();
  page.timing.wasm_load = performance.now() - t0;
  const q = new URLSearchParams(location.search);
  page.method = q.get("method") || "l2";
  page.wrench = q.get("wrench") || "";
  $("wrench").value = page.wrench;
  wireControls();
  await exampleList();
  const robot = q.get("robot") || "robots/ipanema-like-8.toml";
  $("examples").value = robot;
  const opened = await openUrl(robot, numbers(q.get("pose")));
  if (opened) {
    sectionDefault();
    $("path-to").value = page.pose.map((x, k) => Number((x + (k < 2 ? 0.3 : 0)).toFixed(4))).join(", ");
    await onDemand(q);
  }
  page.timing.first_state = performance.now() - t0;
  if (SYNC && page.session) timePoseChanges(Math.max(1, Number(q.get("timing")) || 100));
  page.ready = true;
  writeState();
}

main().catch((e) => scriptError(e && e.message ? e.message : String(e)));

// cdpr studio: the robot (MIT OR Apache-2.0). Opening robot files (the wasm session parses them
// with cdpr-io), the method list with each method's reference, and the editable robot table.
import { StudioSession } from "./cdpr_studio.js";
import { $, page, fmt, message, writeState, fetchText, planar } from "./core.js";
import { update, buildSliders } from "./pose.js";
import { clearWorkspace } from "./workspace.js";
import { clearPath } from "./path.js";

// Opens [{ name, text }, …] (one file or a CASPR pair) at `pose` (else the robot's start pose).
export function openFiles(files, pose) {
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
  clearWorkspace();
  clearPath();
  loadTable(pose);
  page.timing.open = performance.now() - t0;
  update(true);
  return true;
}

// A robot by URL; a CASPR model by its NAME_cables.xml (NAME_bodies.xml beside it).
export async function openUrl(url, pose) {
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

export async function openLocal(fileList) {
  const files = await Promise.all(Array.from(fileList).map(async (f) => ({ name: f.name, text: await f.text() })));
  // A CASPR pair opens by its cables file.
  files.sort((a, b) => (/_cables\.xml$/i.test(b.name) ? 1 : 0) - (/_cables\.xml$/i.test(a.name) ? 1 : 0));
  openFiles(files);
}

// The session's robot table into the page: name, pose, methods, sliders, the edit table.
export function loadTable(pose) {
  const t = JSON.parse(page.session.table());
  page.table = t;
  $("robot-name").textContent = `${t.name} — ${t.motion}, ${t.cables.length} cables`;
  // A pose given in the query is kept as given: a wrong one gets the library's message.
  page.pose = pose ? pose.slice() : t.start_pose.slice();
  t.anchorNames = t.cables.map((c, i) => c.name || `A${i + 1}`);
  buildMethods(t);
  const forces = planar(t.motion) ? 2 : 3;
  const moments = t.motion === "planar" ? 1 : t.motion === "spatial" ? 3 : 0;
  $("wrench-unit").textContent = `(${t.coordinates.length} numbers: ${forces} forces in N${moments ? `, ${moments} moment${moments > 1 ? "s" : ""} in N·m` : ""})`;
  buildSliders();
  buildEditTable(t);
  $("warnings").textContent = t.warnings.length ? "Warnings: " + t.warnings.join("; ") : "";
}

// The methods that apply, each with its reference on hover (the library's text).
function buildMethods(t) {
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
}

export function showReference() {
  const m = page.table && page.table.methods.find((x) => x.name === page.method);
  $("method-reference").textContent = m ? m.reference : "";
  $("method").title = m ? m.reference : "";
  page.extra.method_reference = m ? m.reference : null;
}

function buildEditTable(t) {
  $("mass").value = t.mass;
  const body = $("table").querySelector("tbody");
  body.innerHTML = "";
  const dim = planar(t.motion) ? 2 : 3;
  const vec = (v) => v.slice(0, dim).map((x) => fmt(x, 6)).join(", ");
  t.cables.forEach((c, i) => {
    const tr = document.createElement("tr");
    tr.innerHTML = `<td>${t.anchorNames[i]}</td><td><input data-k="frame" value="${vec(c.frame)}" ${c.pulley ? "disabled title='runs over a pulley'" : ""}></td>` +
      `<td><input data-k="platform" value="${vec(c.platform)}"></td><td><input data-k="t_min" value="${c.t_min}"></td>` +
      `<td><input data-k="t_max" value="${c.t_max === null ? "inf" : c.t_max}"></td>`;
    body.appendChild(tr);
  });
}

// The edited table, checked cell by cell (a bad cell is a message naming cable, key and text).
export function readTable() {
  const t = JSON.parse(JSON.stringify(page.table));
  delete t.anchorNames;
  t.mass = Number($("mass").value);
  const dim = planar(t.motion) ? 2 : 3;
  $("table").querySelectorAll("tbody tr").forEach((tr, i) => {
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

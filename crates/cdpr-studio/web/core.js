// cdpr studio: what every part of the page shares (MIT OR Apache-2.0): the page's state, the
// test hook's outputs, messages, number formatting, the tension colours, downloads and reading
// files over HTTP.
//
// Test hook: <output id="cdpr-state"> holds the current state as JSON (robot, pose, lengths,
// tensions, feasible, method, ... and the page's timings in ms); <output id="cdpr-errors">
// collects script errors (it stays empty on a healthy page).

export const $ = (id) => document.getElementById(id);

const errors = $("cdpr-errors");
export function scriptError(msg) {
  errors.textContent += (errors.textContent ? "\n" : "") + msg;
}
window.addEventListener("error", (e) => scriptError(e.message));
window.addEventListener("unhandledrejection", (e) => scriptError(String(e.reason && e.reason.message || e.reason)));
const consoleError = console.error.bind(console);
console.error = (...a) => { scriptError(a.map(String).join(" ")); consoleError(...a); };

// The session (the wasm StudioSession), the robot table, the pose and load, the last state and
// the workspace and trajectory shown. `extra` collects what the test hook reports beside the
// state (workspace, section, trajectory, drag).
export const page = {
  session: null, table: null, pose: [], method: "l2", wrench: "", state: null,
  overlay: null, trajectory: null, replay: null, timing: {}, renderer: null, extra: {}, ready: false,
};

// With `&timing=N` the page loads synchronously (see studio.js).
export const SYNC = new URLSearchParams(location.search).has("timing");

// An honest message for a bad input, shown over the scene (empty text: hide it).
export function message(text) {
  const m = $("message");
  m.hidden = !text;
  m.textContent = text || "";
}

export function fmt(v, digits = 4) {
  if (v === null || v === undefined) return "—";
  if (!isFinite(v)) return v > 0 ? "∞" : "−∞";
  const a = Math.abs(v);
  if (a !== 0 && (a < 1e-3 || a >= 1e6)) return v.toExponential(3);
  return Number(v.toFixed(digits)).toString();
}

export function download(name, data, type) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([data], { type: type || "text/plain" }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

// Tension colour: a blue–red ramp over [t_min, t_max]; magenta outside the bounds.
export function colour(t, lo, hi) {
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

// Robots moving in a plane (drawn in z = 0) or in space.
export function planar(motion) {
  return motion === "point2" || motion === "planar";
}

// The force and moment units of a wrench of this motion pattern.
export function wrenchUnit(motion) {
  return motion === "point2" || motion === "point3" ? "N" : "N, N·m";
}

export function writeState() {
  const s = Object.assign({}, page.state || {}, page.extra);
  s.timing_ms = page.timing;
  s.ready = page.ready;
  $("cdpr-state").textContent = JSON.stringify(s);
}

// Synchronous requests (the timing mode only).
export function syncRequest(url, binary) {
  const x = new XMLHttpRequest();
  x.open("GET", url, false);
  if (binary) x.overrideMimeType("text/plain; charset=x-user-defined");
  x.send();
  if (x.status !== 200) throw new Error(`${url}: HTTP ${x.status}`);
  return x.responseText;
}

export async function fetchText(url) {
  if (SYNC) return syncRequest(url, false);
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return r.text();
}

// Runs `f` after the page painted (a "computing…" note first); at once in the timing mode.
export function later(f) {
  return new Promise((done) => (SYNC ? done(f()) : setTimeout(() => done(f()), 0)));
}

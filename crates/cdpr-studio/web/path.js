// cdpr studio: a path or timed trajectory replayed (MIT OR Apache-2.0). The segment from the
// pose shown to a target pose through cdpr-api's trajectory request (`cdpr trajectory --from
// --to --json`): untimed, N + 1 samples of the path parameter s; with a time law, samples every
// dt s (the inertial wrench balanced with "dynamics"), and the motor torques when every cable
// has a winch. The plots under the scene show each cable's tension (N) with the bounds and the
// motor torques (N·m); Play moves the platform along it.
import { $, page, fmt, message, writeState, later } from "./core.js";
import { update, syncSliders } from "./pose.js";

const PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];

export function clearPath() {
  stop();
  page.trajectory = null;
  delete page.extra.path;
  $("path-box").hidden = true;
  $("path-result").textContent = "";
  $("play").disabled = true;
}

// The request's settings from the page: the segment, the samples, the method, the load and
// the time law (none: the untimed path along s).
function settings(to, n) {
  const law = $("time-law").value;
  const s = { from: page.pose.slice(), to, method: page.method };
  if (page.wrench) s.wrench = page.wrench.split(",").map(Number);
  if (!law) return Object.assign(s, { samples: n + 1 });
  return Object.assign(s, { time_law: law, duration: Number($("duration").value), dt: Number($("dt").value), dynamics: $("dynamics").checked });
}

// The report of `cdpr trajectory --json` as series against s or t.
function series(r, from, to) {
  const timed = Array.isArray(r.t), dt = r.drive_train;
  return {
    from, to, at: 0, timed, x: timed ? r.t : r.s, poses: r.poses, tensions: r.tensions,
    feasible: r.tensions.map((t) => t !== null), t_min: r.t_min, t_max: r.t_max,
    torques: dt ? dt.motor_torques : null, report: r,
  };
}

// Computes the path or trajectory to the target pose of the "path-to" field.
export async function computePath(target, steps) {
  if (target !== undefined) $("path-to").value = target;
  if (steps) $("path-steps").value = steps;
  const text = $("path-to").value;
  const to = text.split(",").map((x) => (x.trim() === "" ? NaN : Number(x)));
  const n = Number($("path-steps").value);
  if (to.length !== page.pose.length || to.some((x) => !isFinite(x))) {
    message(`path: the target pose needs ${page.pose.length} numbers (${page.table.coordinates.map(([c, u]) => `${c} ${u}`).join(", ")}), got "${text}"`);
    return false;
  }
  if (!(Number.isInteger(n) && n >= 1 && n <= 2000)) {
    message(`path: the number of steps must be an integer in 1…2000, got "${$("path-steps").value}"`);
    return false;
  }
  const t0 = performance.now(), req = settings(to, n);
  let r;
  try {
    r = await later(() => JSON.parse(page.session.trajectory(JSON.stringify(req))));
  } catch (e) {
    message(`path: ${e.message}`);
    return false;
  }
  message("");
  page.timing.path = performance.now() - t0;
  const tr = (page.trajectory = series(r, req.from, to));
  page.extra.path = {
    from: req.from, to, steps: n, method: page.method, time_law: req.time_law || null, x: tr.x, poses: tr.poses,
    tensions: tr.tensions, feasible: tr.feasible, motor_torques: tr.torques,
  };
  const bad = tr.feasible.filter((f) => !f).length;
  $("path-result").textContent = `${tr.x.length} ${tr.timed ? `samples over ${fmt(r.duration, 3)} s (${r.time_law}${r.dynamics ? ", inertia balanced" : ""})` : "poses"}, ${bad ? `${bad} infeasible (magenta band)` : "all feasible"}; method ${r.method}${tr.torques ? "; motor torques below" : ""}; ${fmt(page.timing.path, 1)} ms`;
  $("path-box").hidden = false;
  $("torque-plot").hidden = !tr.torques;
  if (page.renderer) page.renderer.draw();
  plotPath();
  writeState();
  return true;
}

// The plots: tensions (N) and, with winches, motor torques (N·m) against s or t (s).
export function plotPath() {
  const tr = page.trajectory;
  if (!tr) return;
  const xLabel = tr.timed ? "time t (s)" : "path parameter s (start 0 → target 1)";
  plotSeries($("path-plot"), tr, tr.tensions, { xLabel, yLabel: "tension (N)", bounds: true });
  if (tr.torques) plotSeries($("torque-plot"), tr, tr.torques, { xLabel, yLabel: "torque (N·m)", bounds: false });
  legend();
}

function plotSeries(cv, tr, values, o) {
  const dpr = window.devicePixelRatio || 1, W = cv.clientWidth || 360, H = cv.clientHeight || 220;
  cv.width = W * dpr; cv.height = H * dpr;
  const ctx = cv.getContext("2d");
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, W, H);
  const L = 56, R = 10, T = 10, B = 34, x0 = tr.x[0], x1 = tr.x[tr.x.length - 1];
  // The y range: the values (and t_min); t_max too unless it would flatten the curves (> 3×
  // the largest value: then it is written above the plot).
  const data = values.flatMap((v) => v || []).concat(o.bounds ? tr.t_min : []);
  const top = Math.max(...data, 0), maxes = o.bounds ? tr.t_max.filter((t) => t !== null) : [];
  const shown = maxes.filter((t) => t <= 3 * Math.max(top, 1e-12)), hidden = maxes.filter((t) => !shown.includes(t));
  let lo = Math.min(0, ...data), hi = Math.max(top, ...shown) * 1.05;
  if (!(hi > lo)) hi = lo + 1;
  const X = (x) => L + ((W - L - R) * (x - x0)) / Math.max(x1 - x0, 1e-12), Y = (t) => H - B - ((H - T - B) * (t - lo)) / (hi - lo);
  const half = (x1 - x0) / Math.max(2 * (tr.x.length - 1), 1);
  tr.feasible.forEach((f, k) => {
    if (f) return;
    ctx.fillStyle = "rgba(197,27,125,0.15)";
    ctx.fillRect(X(Math.max(x0, tr.x[k] - half)), T, X(Math.min(x1, tr.x[k] + half)) - X(Math.max(x0, tr.x[k] - half)), H - T - B);
  });
  plotAxes(ctx, { L, R, T, B, W, H, lo, hi, Y, x0, x1, xLabel: o.xLabel, yLabel: o.yLabel });
  ctx.setLineDash([5, 4]); ctx.strokeStyle = "#888"; ctx.lineWidth = 1;
  if (o.bounds) new Set(tr.t_min.concat(shown)).forEach((t) => { ctx.beginPath(); ctx.moveTo(L, Y(t)); ctx.lineTo(W - R, Y(t)); ctx.stroke(); });
  ctx.setLineDash([]);
  if (hidden.length) { ctx.fillStyle = "#555"; ctx.textAlign = "right"; ctx.fillText(`t_max = ${[...new Set(hidden)].map((t) => fmt(t)).join(", ")} N (above)`, W - R - 4, T + 4); }
  ctx.lineWidth = 1.6;
  page.table.anchorNames.forEach((name, i) => {
    ctx.strokeStyle = PALETTE[i % PALETTE.length];
    ctx.beginPath();
    let pen = false;
    values.forEach((v, k) => {
      if (!v) { pen = false; return; }
      if (pen) ctx.lineTo(X(tr.x[k]), Y(v[i])); else ctx.moveTo(X(tr.x[k]), Y(v[i]));
      pen = true;
    });
    ctx.stroke();
  });
  ctx.strokeStyle = "#000"; ctx.beginPath(); ctx.moveTo(X(tr.x[tr.at]), T); ctx.lineTo(X(tr.x[tr.at]), H - B); ctx.stroke();
}

function plotAxes(ctx, a) {
  ctx.strokeStyle = "#333"; ctx.fillStyle = "#333"; ctx.lineWidth = 1; ctx.font = "11px sans-serif";
  ctx.strokeRect(a.L, a.T, a.W - a.L - a.R, a.H - a.T - a.B);
  ctx.textAlign = "right"; ctx.textBaseline = "middle";
  for (let j = 0; j <= 4; j++) {
    const t = a.lo + ((a.hi - a.lo) * j) / 4;
    ctx.fillText(fmt(t, 1), a.L - 4, a.Y(t));
  }
  ctx.textAlign = "center"; ctx.textBaseline = "top";
  for (let j = 0; j <= 4; j++) ctx.fillText(fmt(a.x0 + ((a.x1 - a.x0) * j) / 4, 2), a.L + ((a.W - a.L - a.R) * j) / 4, a.H - a.B + 3);
  ctx.fillText(a.xLabel, (a.L + a.W - a.R) / 2, a.H - 14);
  ctx.save(); ctx.translate(11, (a.T + a.H - a.B) / 2); ctx.rotate(-Math.PI / 2);
  ctx.fillText(a.yLabel, 0, -6); ctx.restore();
}

function legend() {
  const box = $("path-legend");
  box.innerHTML = page.table.anchorNames.map((name, i) => `<span><i style="background:${PALETTE[i % PALETTE.length]}"></i>${name}</span>`).join(" ");
}

// ---- replay ------------------------------------------------------------------------------------

let timer = null;

function stop() {
  if (timer !== null) cancelAnimationFrame(timer);
  timer = null;
  $("play").textContent = "Play";
}

// Shows sample k of the path: the platform there, the state recomputed (the same request).
export function showSample(k) {
  const tr = page.trajectory;
  tr.at = k;
  page.pose = tr.poses[k].slice();
  syncSliders();
  update(false);
  plotPath();
}

function play() {
  const tr = page.trajectory;
  if (!tr) return;
  if (timer !== null) { stop(); return; }
  if (tr.at >= tr.poses.length - 1) tr.at = 0;
  $("play").textContent = "Pause";
  let last = 0;
  const frame = (time) => {
    if (time - last >= 1000 / 30) {
      last = time;
      showSample(tr.at);
      if (tr.at >= tr.poses.length - 1) { stop(); return; }
      tr.at += 1;
    }
    timer = requestAnimationFrame(frame);
  };
  timer = requestAnimationFrame(frame);
}

export function wirePath() {
  $("compute-path").addEventListener("click", () => computePath());
  $("play").addEventListener("click", play);
  page.pauseReplay = stop;
  $("path-plot").addEventListener("click", (e) => {
    const tr = page.trajectory, r = e.target.getBoundingClientRect();
    if (!tr) return;
    const n = tr.poses.length - 1, s = (e.clientX - r.left - 56) / (r.width - 66);
    stop();
    showSample(Math.max(0, Math.min(n, Math.round(s * n))));
  });
}

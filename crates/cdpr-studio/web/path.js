// cdpr studio: a path replayed (MIT OR Apache-2.0). A straight path in pose coordinates from
// the pose shown to a target pose, sampled at N + 1 poses; the state at each sample is the
// session's state request (the same as `cdpr tension --pose … --json` at that pose). The plot
// beside the scene shows each cable's tension (N) along the path with the bounds; Play moves
// the platform along it.
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

// The poses of the path: from + (to − from) k / n, k = 0…n.
function samples(from, to, n) {
  return Array.from({ length: n + 1 }, (_, k) => from.map((a, i) => a + ((to[i] - a) * k) / n));
}

// Computes the states along the path to the target pose of the "path-to" field.
export async function computePath(target, steps) {
  if (target !== undefined) $("path-to").value = target;
  if (steps) $("path-steps").value = steps;
  const text = $("path-to").value;
  const to = text.split(",").map((x) => (x.trim() === "" ? NaN : Number(x)));
  const n = steps || Number($("path-steps").value);
  if (to.length !== page.pose.length || to.some((x) => !isFinite(x))) {
    message(`path: the target pose needs ${page.pose.length} numbers (${page.table.coordinates.map(([c, u]) => `${c} ${u}`).join(", ")}), got "${text}"`);
    return false;
  }
  if (!(Number.isInteger(n) && n >= 1 && n <= 2000)) {
    message(`path: the number of steps must be an integer in 1…2000, got "${$("path-steps").value}"`);
    return false;
  }
  const from = page.pose.slice();
  const t0 = performance.now();
  let states;
  try {
    states = await later(() => samples(from, to, n).map((q) => JSON.parse(page.session.state(q.join(","), page.method, page.wrench))));
  } catch (e) {
    message(`path: ${e.message}`);
    return false;
  }
  page.timing.path = performance.now() - t0;
  page.trajectory = { from, to, states, at: 0 };
  page.extra.path = {
    from, to, steps: n, method: page.method, poses: states.map((s) => s.pose),
    tensions: states.map((s) => s.tensions), feasible: states.map((s) => s.feasible),
  };
  const bad = states.filter((s) => !s.feasible).length;
  $("path-result").textContent = `${n + 1} poses, ${bad ? `${bad} infeasible (magenta band)` : "all feasible"}; method ${page.method}; ${fmt(page.timing.path, 1)} ms`;
  $("path-box").hidden = false;
  if (page.renderer) page.renderer.draw();
  $("play").disabled = false;
  plotPath();
  writeState();
  return true;
}

// The tension plot: t_i (N) against the path parameter s (0 at the start, 1 at the target).
export function plotPath() {
  const tr = page.trajectory, cv = $("path-plot");
  if (!tr) return;
  const dpr = window.devicePixelRatio || 1, W = cv.clientWidth || 360, H = cv.clientHeight || 220;
  cv.width = W * dpr; cv.height = H * dpr;
  const ctx = cv.getContext("2d");
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, W, H);
  const L = 52, R = 10, T = 10, B = 34, n = tr.states.length - 1;
  // The y range: the tensions and t_min; t_max too unless it would flatten the curves (> 3× the
  // largest tension: then it is written above the plot).
  const data = tr.states.flatMap((s) => s.tensions || []).concat(tr.states[0].t_min);
  const top = Math.max(...data), maxes = tr.states[0].t_max.filter((t) => t !== null);
  const shown = maxes.filter((t) => t <= 3 * Math.max(top, 1e-12));
  let lo = Math.min(0, ...data), hi = Math.max(top, ...shown) * 1.05;
  if (!(hi > lo)) hi = lo + 1;
  const hidden = maxes.filter((t) => !shown.includes(t));
  const X = (k) => L + ((W - L - R) * k) / Math.max(n, 1), Y = (t) => H - B - ((H - T - B) * (t - lo)) / (hi - lo);
  tr.states.forEach((s, k) => {
    if (s.feasible) return;
    ctx.fillStyle = "rgba(197,27,125,0.15)";
    ctx.fillRect(X(Math.max(0, k - 0.5)), T, X(Math.min(n, k + 0.5)) - X(Math.max(0, k - 0.5)), H - T - B);
  });
  plotAxes(ctx, { L, R, T, B, W, H, lo, hi, Y });
  const bounds = new Set(tr.states[0].t_min.concat(shown));
  if (hidden.length) { ctx.fillStyle = "#555"; ctx.textAlign = "right"; ctx.fillText(`t_max = ${[...new Set(hidden)].map((t) => fmt(t)).join(", ")} N (above)`, W - R - 4, T + 8); }
  ctx.setLineDash([5, 4]); ctx.strokeStyle = "#888"; ctx.lineWidth = 1;
  bounds.forEach((t) => { ctx.beginPath(); ctx.moveTo(L, Y(t)); ctx.lineTo(W - R, Y(t)); ctx.stroke(); });
  ctx.setLineDash([]); ctx.lineWidth = 1.6;
  page.table.anchorNames.forEach((name, i) => {
    ctx.strokeStyle = PALETTE[i % PALETTE.length];
    ctx.beginPath();
    let pen = false;
    tr.states.forEach((s, k) => {
      const t = s.tensions ? s.tensions[i] : null;
      if (t === null) { pen = false; return; }
      if (pen) ctx.lineTo(X(k), Y(t)); else ctx.moveTo(X(k), Y(t));
      pen = true;
    });
    ctx.stroke();
  });
  ctx.strokeStyle = "#000"; ctx.beginPath(); ctx.moveTo(X(tr.at), T); ctx.lineTo(X(tr.at), H - B); ctx.stroke();
  legend();
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
  for (let j = 0; j <= 4; j++) ctx.fillText(fmt(j / 4, 2), a.L + ((a.W - a.L - a.R) * j) / 4, a.H - a.B + 3);
  ctx.fillText("path parameter s (start 0 → target 1)", (a.L + a.W - a.R) / 2, a.H - 14);
  ctx.save(); ctx.translate(11, (a.T + a.H - a.B) / 2); ctx.rotate(-Math.PI / 2);
  ctx.fillText("tension t (N); dashed: t_min, t_max", 0, -6); ctx.restore();
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
  page.pose = tr.states[k].pose.slice();
  syncSliders();
  update(false);
  plotPath();
}

function play() {
  const tr = page.trajectory;
  if (!tr) return;
  if (timer !== null) { stop(); return; }
  if (tr.at >= tr.states.length - 1) tr.at = 0;
  $("play").textContent = "Pause";
  let last = 0;
  const frame = (time) => {
    if (time - last >= 1000 / 30) {
      last = time;
      showSample(tr.at);
      if (tr.at >= tr.states.length - 1) { stop(); return; }
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
    const n = tr.states.length - 1, s = (e.clientX - r.left - 52) / (r.width - 62);
    stop();
    showSample(Math.max(0, Math.min(n, Math.round(s * n))));
  });
}

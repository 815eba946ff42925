// cdpr trajectory replay: the platform and its cables moving along a timed trajectory, cables
// coloured by tension. Part of the cdpr crate (MIT OR Apache-2.0); no external library.
(function () {
  "use strict";
  var status = document.getElementById("cdpr-status");
  function fail(msg) {
    status.textContent = "error: " + msg;
    status.setAttribute("data-state", "error");
  }
  window.addEventListener("error", function (e) { fail(e.message); });
  try {
    var R = JSON.parse(document.getElementById("replay").textContent);
    var n = R.anchors.length, frames = R.t.length;
    var canvas = document.getElementById("view"), ctx = canvas.getContext("2d");
    document.getElementById("title").textContent = R.title;
    document.getElementById("tmin").textContent = R.tMin.toPrecision(4);
    document.getElementById("tmax").textContent = R.tMax.toPrecision(4);
    var slider = document.getElementById("frame");
    slider.max = String(frames - 1);

    // World attachment of cable i at frame k: p + R b (rotation rows in R.rotations[k]).
    function attachment(k, i) {
      var p = R.positions[k], m = R.rotations[k], b = R.attachments[i];
      return [0, 1, 2].map(function (r) {
        return p[r] + m[r][0] * b[0] + m[r][1] * b[1] + m[r][2] * b[2];
      });
    }
    var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    function grow(p) {
      for (var c = 0; c < 3; c++) { lo[c] = Math.min(lo[c], p[c]); hi[c] = Math.max(hi[c], p[c]); }
    }
    R.anchors.forEach(grow);
    for (var k0 = 0; k0 < frames; k0++) for (var i0 = 0; i0 < n; i0++) grow(attachment(k0, i0));
    var centre = [0, 1, 2].map(function (c) { return 0.5 * (lo[c] + hi[c]); });
    var radius = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    var view = R.planar ? { yaw: 0, pitch: Math.PI / 2, zoom: 1 } : { yaw: -0.65, pitch: 0.45, zoom: 1 };

    function toView(p) {
      var x = p[0] - centre[0], y = p[1] - centre[1], z = p[2] - centre[2];
      var cy = Math.cos(view.yaw), sy = Math.sin(view.yaw);
      var x1 = x * cy - y * sy, y1 = x * sy + y * cy;
      var ce = Math.cos(view.pitch), se = Math.sin(view.pitch);
      return [x1, y1 * se + z * ce, -y1 * ce + z * se];
    }
    var W = 0, H = 0, scale = 1;
    function project(p) { var v = toView(p); return [W / 2 + v[0] * scale, H / 2 - v[1] * scale]; }

    // Diverging blue → red colour map on [t_min, t_max].
    var stops = [[49, 54, 149], [116, 173, 209], [254, 224, 144], [244, 109, 67], [165, 0, 38]];
    function colour(t) {
      var span = R.tMax - R.tMin;
      var s = span > 0 ? Math.min(1, Math.max(0, (t - R.tMin) / span)) : 0.5;
      var x = s * (stops.length - 1), j = Math.min(stops.length - 2, Math.floor(x)), f = x - j;
      var c = [0, 1, 2].map(function (q) { return Math.round(stops[j][q] + f * (stops[j + 1][q] - stops[j][q])); });
      return "rgb(" + c.join(",") + ")";
    }

    // Convex hull of 2-D points (monotone chain), for the platform's outline.
    function hull(pts) {
      pts = pts.slice().sort(function (a, b) { return a[0] - b[0] || a[1] - b[1]; });
      if (pts.length < 3) return pts;
      function cross(o, a, b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }
      var lower = [], upper = [];
      pts.forEach(function (p) {
        while (lower.length >= 2 && cross(lower[lower.length - 2], lower[lower.length - 1], p) <= 0) lower.pop();
        lower.push(p);
      });
      for (var q = pts.length - 1; q >= 0; q--) {
        var p = pts[q];
        while (upper.length >= 2 && cross(upper[upper.length - 2], upper[upper.length - 1], p) <= 0) upper.pop();
        upper.push(p);
      }
      return lower.slice(0, -1).concat(upper.slice(0, -1));
    }

    var current = 0;
    function draw() {
      var k = current;
      W = canvas.clientWidth; H = canvas.clientHeight;
      canvas.width = W; canvas.height = H;
      scale = 0.45 * Math.min(W, H) / radius * view.zoom;
      ctx.clearRect(0, 0, W, H);
      // Path of the platform origin.
      ctx.strokeStyle = "#1f5fa0"; ctx.lineWidth = 1; ctx.setLineDash([]);
      ctx.beginPath();
      R.positions.forEach(function (p, j) { var s = project(p); if (j) ctx.lineTo(s[0], s[1]); else ctx.moveTo(s[0], s[1]); });
      ctx.stroke();
      // Platform.
      var pts = [];
      for (var i = 0; i < n; i++) pts.push(project(attachment(k, i)));
      var h = hull(pts);
      if (h.length >= 3) {
        ctx.fillStyle = "rgba(232,163,61,0.6)"; ctx.strokeStyle = "#b57514";
        ctx.beginPath();
        h.forEach(function (s, j) { if (j) ctx.lineTo(s[0], s[1]); else ctx.moveTo(s[0], s[1]); });
        ctx.closePath(); ctx.fill(); ctx.stroke();
      } else {
        var o = project(R.positions[k]);
        ctx.fillStyle = "#e8a33d"; ctx.beginPath(); ctx.arc(o[0], o[1], 5, 0, 2 * Math.PI); ctx.fill();
      }
      // Cables, coloured by tension.
      var ts = R.tensions[k];
      for (i = 0; i < n; i++) {
        var a = project(R.anchors[i]), b = pts[i];
        ctx.lineWidth = 2.5;
        if (ts) { ctx.strokeStyle = colour(ts[i]); ctx.setLineDash([]); }
        else { ctx.strokeStyle = "#999"; ctx.setLineDash([6, 4]); }
        ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(b[0], b[1]); ctx.stroke();
        ctx.setLineDash([]);
        ctx.fillStyle = "#000"; ctx.fillRect(a[0] - 3, a[1] - 3, 6, 6);
      }
      document.getElementById("time").textContent = R.t[k].toFixed(3);
      document.getElementById("tensions").textContent = ts
        ? "tensions (N): " + ts.map(function (v) { return v.toFixed(1); }).join(", ")
        : "infeasible sample: " + (R.reasons[k] || "");
    }

    slider.addEventListener("input", function () { current = +slider.value; draw(); });
    var timer = null, button = document.getElementById("play");
    button.addEventListener("click", function () {
      if (timer) { clearInterval(timer); timer = null; button.textContent = "play"; return; }
      if (current >= frames - 1) current = 0;
      var start = performance.now(), t0 = R.t[current];
      button.textContent = "pause";
      timer = setInterval(function () {
        var t = t0 + (performance.now() - start) / 1000;
        while (current < frames - 1 && R.t[current + 1] <= t) current++;
        slider.value = String(current); draw();
        if (current >= frames - 1) { clearInterval(timer); timer = null; button.textContent = "play"; }
      }, 30);
    });
    var drag = null;
    canvas.addEventListener("mousedown", function (e) { drag = [e.clientX, e.clientY, view.yaw, view.pitch]; });
    window.addEventListener("mouseup", function () { drag = null; });
    window.addEventListener("mousemove", function (e) {
      if (!drag) return;
      view.yaw = drag[2] + (e.clientX - drag[0]) * 0.01;
      view.pitch = Math.max(-1.5, Math.min(1.5707, drag[3] + (e.clientY - drag[1]) * 0.01));
      draw();
    });
    canvas.addEventListener("wheel", function (e) {
      e.preventDefault(); view.zoom *= e.deltaY < 0 ? 1.1 : 1 / 1.1; draw();
    }, { passive: false });
    window.addEventListener("resize", draw);
    draw();
    status.textContent = "replayed " + frames + " frames of " + n + " cables";
    status.setAttribute("data-state", "ok");
  } catch (e) {
    fail(e.message);
  }
})();

// cdpr 3-D renderer: a small orthographic canvas renderer (painter's algorithm), shared by the
// self-contained HTML viewer (`--plot FILE.html`, inlined by viewer.rs) and the studio (copied
// to target/studio/viewer.js by `cargo xtask studio`).
// Part of the cdpr crate (MIT OR Apache-2.0); no external library.
var CdprViewer = (function () {
  "use strict";

  // A renderer on `canvas` for scene S: { anchors, cables, platform, platformPosition, vertices,
  // triangles, box, cableColours?, points?, sections?, planar? } (m). `controls` (all optional):
  // the cut-plane `axis` select, `cut` slider and `cutValue` label, `onDraw(triangles)` called
  // after each drawing, and `onPlatformDrag(event)`: when given, a mouse drag that starts on the
  // platform moves it instead of orbiting (see platformDrag below).
  // Returns { draw(), setScene(S, refit), screenOf(p), view(), dragDisplacement(dx, dy, axis) }.
  function create(canvas, S, controls) {
    controls = controls || {};
    var ctx = canvas.getContext("2d");
    var centre = [0, 0, 0], radius = 1;
    // The view frames the box, the anchors and the mesh.
    function fit() {
      var lo = S.box[0].slice(), hi = S.box[1].slice();
      S.anchors.concat(S.vertices).forEach(function (p) {
        for (var k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], p[k]); hi[k] = Math.max(hi[k], p[k]); }
      });
      centre = [0, 1, 2].map(function (k) { return 0.5 * (lo[k] + hi[k]); });
      radius = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    }
    var view = { yaw: -0.65, pitch: 0.45, zoom: 1 };
    var axisSel = controls.axis, cutSlider = controls.cut, cutLabel = controls.cutValue;

    function cutValue() {
      if (!axisSel) return Infinity;
      var a = +axisSel.value;
      return S.box[0][a] + (S.box[1][a] - S.box[0][a]) * (+cutSlider.value) / 1000;
    }

    // World (z up) to view: yaw about z, then pitch (elevation of the eye).
    function toView(p) {
      var x = p[0] - centre[0], y = p[1] - centre[1], z = p[2] - centre[2];
      var cy = Math.cos(view.yaw), sy = Math.sin(view.yaw);
      var x1 = x * cy - y * sy, y1 = x * sy + y * cy;
      var ce = Math.cos(view.pitch), se = Math.sin(view.pitch);
      return [x1, y1 * se + z * ce, -y1 * ce + z * se]; // screen x, screen y (up), depth (towards eye)
    }
    var W = 0, H = 0, scale = 1, layer = null;
    function toScreen(v) { return [W / 2 + v[0] * scale, H / 2 - v[1] * scale]; }
    function project(p) { return toScreen(toView(p)); }

    // Keep the part of a polygon with p[axis] <= value (Sutherland-Hodgman, one plane).
    function clip(poly, axis, value) {
      var out = [];
      for (var i = 0; i < poly.length; i++) {
        var a = poly[i], b = poly[(i + 1) % poly.length];
        var ina = a[axis] <= value, inb = b[axis] <= value;
        if (ina) out.push(a);
        if (ina !== inb) {
          var s = (value - a[axis]) / (b[axis] - a[axis]);
          out.push([a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])]);
        }
      }
      return out;
    }

    function line(a, b, colour, width, dash) {
      var p = project(a), q = project(b);
      ctx.strokeStyle = colour; ctx.lineWidth = width; ctx.setLineDash(dash || []);
      ctx.beginPath(); ctx.moveTo(p[0], p[1]); ctx.lineTo(q[0], q[1]); ctx.stroke();
      ctx.setLineDash([]);
    }

    function boxEdges(a, b, colour, width, dash) {
      var c = function (i) { return [i & 1 ? b[0] : a[0], i & 2 ? b[1] : a[1], i & 4 ? b[2] : a[2]]; };
      [[0, 1], [2, 3], [4, 5], [6, 7], [0, 2], [1, 3], [4, 6], [5, 7], [0, 4], [1, 5], [2, 6], [3, 7]]
        .forEach(function (e) { line(c(e[0]), c(e[1]), colour, width, dash); });
    }

    function labelPlacer() {
      var placed = [];
      return function (x, y, text) {
        var w = ctx.measureText(text).width, h = 13, g = 5;
        var cands = [[x + g, y - h - g], [x + g, y + g], [x - w - g, y - h - g], [x - w - g, y + g],
                     [x - w / 2, y - h - 2 * g], [x - w / 2, y + 2 * g]];
        for (var r = 1; r < 6; r++) { cands.push([x + g, y - h - g - r * (h + 2)]); cands.push([x + g, y + g + r * (h + 2)]); }
        var pick = cands[0];
        for (var i = 0; i < cands.length; i++) {
          var c = cands[i], ok = placed.every(function (q) {
            return c[0] + w <= q[0] || q[0] + q[2] <= c[0] || c[1] + h <= q[1] || q[1] + q[3] <= c[1];
          });
          if (ok) { pick = c; break; }
        }
        placed.push([pick[0], pick[1], w, h]);
        ctx.fillText(text, pick[0], pick[1] + h - 2);
      };
    }

    function draw() {
      var dpr = window.devicePixelRatio || 1;
      W = canvas.clientWidth; H = canvas.clientHeight;
      canvas.width = W * dpr; canvas.height = H * dpr;
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      scale = view.zoom * Math.min(W, H) / (2.15 * radius);
      var axis = axisSel ? +axisSel.value : 2, cut = cutValue();
      if (cutLabel) cutLabel.textContent = cut.toFixed(3);

      // The frame, the search box and the mesh change with the view only, not with the pose:
      // drawn once into a layer and reused while the platform moves (thousands of triangles).
      var key = [W, H, dpr, view.yaw, view.pitch, view.zoom, axis, cut, JSON.stringify(S.anchors), JSON.stringify(S.box)].join(";");
      if (!layer || layer.key !== key || layer.vertices !== S.vertices || layer.triangles !== S.triangles ||
          layer.points !== S.points || layer.sections !== S.sections) {
        var main = ctx, off = layer ? layer.canvas : document.createElement("canvas");
        off.width = canvas.width; off.height = canvas.height;
        ctx = off.getContext("2d");
        ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
        ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, W, H);
        // Frame: the anchors' bounding box (grey) and the search box (dashed blue).
        if (S.anchors.length) {
          var alo = S.anchors[0].slice(), ahi = S.anchors[0].slice();
          S.anchors.forEach(function (p) { for (var k = 0; k < 3; k++) { alo[k] = Math.min(alo[k], p[k]); ahi[k] = Math.max(ahi[k], p[k]); } });
          boxEdges(alo, ahi, "#c8c8c8", 1);
        }
        if (!S.hideBox) boxEdges(S.box[0], S.box[1], "#1f5fa0", 1, [5, 4]);

        // Workspace mesh, clipped by the cut plane, back to front.
        var light = [0.35, 0.45, 0.82];
        var polys = [];
        var section = [];
        for (var t = 0; t < S.triangles.length; t++) {
          var tri = S.triangles[t];
          var pts = [S.vertices[tri[0]], S.vertices[tri[1]], S.vertices[tri[2]]];
          var v = pts.map(toView);
          var ux = v[1][0] - v[0][0], uy = v[1][1] - v[0][1], uz = v[1][2] - v[0][2];
          var wx = v[2][0] - v[0][0], wy = v[2][1] - v[0][1], wz = v[2][2] - v[0][2];
          var n = [uy * wz - uz * wy, uz * wx - ux * wz, ux * wy - uy * wx];
          var nn = Math.hypot(n[0], n[1], n[2]) || 1;
          var shade = Math.abs(n[0] * light[0] + n[1] * light[1] + n[2] * light[2]) / nn;
          var poly = clip(pts, axis, cut);
          if (poly.length < 3) continue;
          var cutPts = [];
          for (var i = 0; i < 3; i++) {
            var a = pts[i], b = pts[(i + 1) % 3];
            if ((a[axis] - cut) * (b[axis] - cut) < 0) {
              var s = (cut - a[axis]) / (b[axis] - a[axis]);
              cutPts.push([a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])]);
            }
          }
          if (cutPts.length === 2) section.push(cutPts);
          var pv = poly.map(toView);
          var depth = pv.reduce(function (d, q) { return d + q[2]; }, 0) / pv.length;
          polys.push({ p: pv, depth: depth, shade: shade });
        }
        // The ball: an orthographic sphere is a disc, drawn between the faces behind its centre
        // and those in front.
        if (S.ball && S.ball.centre[axis] <= cut) {
          var bc = toView(S.ball.centre);
          polys.push({ ball: true, p: [bc], depth: bc[2], shade: 1 });
        }
        polys.sort(function (a, b) { return a.depth - b.depth; });
        polys.forEach(function (q) {
          if (q.ball) {
            var c = toScreen(q.p[0]), r = S.ball.radius * scale;
            var g = ctx.createRadialGradient(c[0] - 0.35 * r, c[1] - 0.35 * r, 0.1 * r, c[0], c[1], r);
            g.addColorStop(0, "rgba(250,200,140,0.95)"); g.addColorStop(1, "rgba(200,110,30,0.95)");
            ctx.fillStyle = g; ctx.beginPath(); ctx.arc(c[0], c[1], Math.max(r, 0), 0, 2 * Math.PI); ctx.fill();
            ctx.fillStyle = "#000"; ctx.fillRect(c[0] - 2, c[1] - 2, 4, 4);
            return;
          }
          var k = 0.45 + 0.55 * q.shade;
          ctx.fillStyle = "rgba(" + Math.round(70 * k) + "," + Math.round(130 * k) + "," + Math.round(180 * k + 40 * (1 - k)) + ",0.45)";
          ctx.beginPath();
          q.p.forEach(function (v, i) { var s = toScreen(v); if (i) ctx.lineTo(s[0], s[1]); else ctx.moveTo(s[0], s[1]); });
          ctx.closePath(); ctx.fill();
        });
        section.forEach(function (s) { line(s[0], s[1], "#d62728", 2); });
        drawPointsAndSections();

        ctx = main;
        layer = { canvas: off, key: key, vertices: S.vertices, triangles: S.triangles, points: S.points, sections: S.sections };
      }
      ctx.save(); ctx.setTransform(1, 0, 0, 1, 0, 0); ctx.drawImage(layer.canvas, 0, 0); ctx.restore();

      // Robot at the draw pose: cables, platform, anchors with labels.
      S.cables.forEach(function (c, i) {
        var colour = S.cableColours ? S.cableColours[i] : "#555";
        var curve = S.cableCurves && S.cableCurves[i];
        if (curve && curve.length > 1) {
          // A sagging cable: the polyline of its catenary (--cable-model catenary).
          for (var k = 1; k < curve.length; k++) line(curve[k - 1], curve[k], colour, 1.2);
        } else {
          line(c[0], c[1], colour, S.cableColours ? 2.5 : 1.2);
        }
      });
      var faces = S.platform.map(function (f) {
        var v = f.map(toView);
        return { v: v, depth: v.reduce(function (d, q) { return d + q[2]; }, 0) / v.length };
      }).sort(function (a, b) { return a.depth - b.depth; });
      faces.forEach(function (f) {
        ctx.fillStyle = "rgba(232,163,61,0.85)"; ctx.strokeStyle = "#8a5a12"; ctx.lineWidth = 1;
        ctx.beginPath();
        f.v.forEach(function (v, i) { var s = toScreen(v); if (i) ctx.lineTo(s[0], s[1]); else ctx.moveTo(s[0], s[1]); });
        ctx.closePath(); ctx.fill(); ctx.stroke();
      });
      if (!S.platform.length && S.anchors.length) {
        var pp = project(S.platformPosition);
        ctx.fillStyle = "#e8a33d"; ctx.beginPath(); ctx.arc(pp[0], pp[1], 4, 0, 2 * Math.PI); ctx.fill();
      }
      ctx.font = "12px 'DejaVu Sans', Arial, sans-serif";
      var place = labelPlacer();
      var groups = [];
      S.anchors.forEach(function (a, i) {
        var p = project(a);
        var g = groups.find(function (q) { return Math.abs(q.x - p[0]) <= 2 && Math.abs(q.y - p[1]) <= 2; });
        var name = (S.anchorNames && S.anchorNames[i]) || "A" + (i + 1);
        if (g) g.names.push(name); else groups.push({ x: p[0], y: p[1], names: [name] });
      });
      groups.forEach(function (g) {
        ctx.fillStyle = "#000"; ctx.fillRect(g.x - 3, g.y - 3, 6, 6);
        place(g.x, g.y, g.names.join("/"));
      });
      // Axes triad at the box's lower corner, labelled with units.
      var o = S.box[0], len = 0.12 * radius;
      ["x", "y", "z"].forEach(function (name, k) {
        var e = o.slice(); e[k] += len;
        line(o, e, ["#c0392b", "#27ae60", "#2e62c9"][k], 2);
        var s = project(e); ctx.fillStyle = "#333"; ctx.fillText(name + " (" + (S.units || "m") + ")", s[0] + 3, s[1] - 3);
      });
      drawDragGuide();
      if (controls.onDraw) controls.onDraw(S.triangles.length);
    }

    // Grid points (S.points: [[x, y, z], …], one colour, S.pointColour) and plane sections
    // (S.sections: [{ loops: [[[x, y, z], …], …], colour }]: closed boundary loops, filled by
    // the even-odd rule so holes stay open), drawn into the cached layer.
    function drawPointsAndSections() {
      if (S.points && S.points.length) {
        ctx.fillStyle = S.pointColour || "rgba(31,95,160,0.55)";
        var r = S.points.length > 4000 ? 1.2 : 1.8;
        S.points.forEach(function (p) { var q = project(p); ctx.fillRect(q[0] - r, q[1] - r, 2 * r, 2 * r); });
      }
      (S.sections || []).forEach(function (sec) {
        ctx.beginPath();
        sec.loops.forEach(function (loop) {
          loop.forEach(function (p, i) { var q = project(p); if (i) ctx.lineTo(q[0], q[1]); else ctx.moveTo(q[0], q[1]); });
          ctx.closePath();
        });
        ctx.fillStyle = sec.fill || "rgba(214,39,40,0.22)"; ctx.fill("evenodd");
        ctx.strokeStyle = sec.colour || "#d62728"; ctx.lineWidth = 2; ctx.stroke();
      });
    }

    // ---- dragging the platform (the studio) --------------------------------------------------
    // A drag that starts on the platform moves it: in the view plane (planar robots, S.planar:
    // in their plane z = const), or along one world axis: Shift picks the axis whose screen
    // image follows the mouse best, a held X, Y or Z key names it. controls.onPlatformDrag gets
    // { phase: "start" | "move" | "end", displacement: [dx, dy, dz] (m, from the drag's start),
    // axis: null | 0 | 1 | 2 }.
    function viewBasis() {
      // The rows of the view rotation of toView: world directions of screen right, screen up
      // and the line of sight (towards the eye).
      var cy = Math.cos(view.yaw), sy = Math.sin(view.yaw), ce = Math.cos(view.pitch), se = Math.sin(view.pitch);
      return { right: [cy, -sy, 0], up: [sy * se, cy * se, ce], depth: [-sy * ce, -cy * ce, se] };
    }
    // The world displacement (m) under a mouse motion of (dx, dy) px (screen y down).
    function dragDisplacement(dx, dy, axis) {
      var b = viewBasis(), sx = dx / scale, sy = -dy / scale;
      if (axis !== null && axis !== undefined) {
        // Along the axis: the displacement whose screen image is nearest the mouse motion. An
        // axis within ~8° of the line of sight does not move (its screen image is a point).
        var ax = b.right[axis], ay = b.up[axis], n2 = ax * ax + ay * ay, d = [0, 0, 0];
        if (n2 > 0.02) d[axis] = (sx * ax + sy * ay) / n2;
        return d;
      }
      var v = [0, 1, 2].map(function (k) { return sx * b.right[k] + sy * b.up[k]; });
      if (S.planar) {
        // Slide along the line of sight onto the plane z = const (orthographic projection);
        // seen edge-on, keep the in-plane part.
        var nd = b.depth[2];
        if (Math.abs(nd) > 0.15) {
          var lam = -v[2] / nd;
          v = v.map(function (x, k) { return x + lam * b.depth[k]; });
        }
        v[2] = 0;
      }
      return v;
    }
    function bestAxis(dx, dy) {
      var b = viewBasis(), best = null, score = -1, n = Math.hypot(dx, dy) || 1;
      for (var k = 0; k < (S.planar ? 2 : 3); k++) {
        var ax = b.right[k], ay = b.up[k], m = Math.hypot(ax, ay);
        if (m < 0.15) continue;
        var c = Math.abs(ax * dx - ay * dy) / (m * n);
        if (c > score) { score = c; best = k; }
      }
      return best;
    }
    function overPlatform(x, y) {
      if (!S.platformPosition) return false;
      var p = project(S.platformPosition);
      if (Math.hypot(x - p[0], y - p[1]) <= 12) return true;
      return S.platform.some(function (face) {
        var q = face.map(project), inside = false;
        for (var i = 0, j = q.length - 1; i < q.length; j = i++) {
          if ((q[i][1] > y) !== (q[j][1] > y) && x < q[j][0] + (y - q[j][1]) * (q[i][0] - q[j][0]) / (q[i][1] - q[j][1])) inside = !inside;
        }
        return inside;
      });
    }
    var heldAxis = null, platformDrag = null;
    window.addEventListener("keydown", function (e) {
      var k = { x: 0, y: 1, z: 2 }[String(e.key).toLowerCase()];
      if (k !== undefined && !(S.planar && k === 2)) heldAxis = k;
    });
    window.addEventListener("keyup", function (e) {
      if ({ x: 1, y: 1, z: 1 }[String(e.key).toLowerCase()]) heldAxis = null;
    });
    window.addEventListener("blur", function () { heldAxis = null; });
    function local(e) {
      var r = canvas.getBoundingClientRect();
      return [e.clientX - r.left, e.clientY - r.top];
    }
    function startPlatformDrag(e) {
      if (!controls.onPlatformDrag) return false;
      var at = local(e);
      if (!overPlatform(at[0], at[1])) return false;
      platformDrag = { x0: e.clientX, y0: e.clientY, axis: heldAxis, shift: e.shiftKey, origin: S.platformPosition.slice() };
      canvas.style.cursor = "move";
      controls.onPlatformDrag({ phase: "start", displacement: [0, 0, 0], axis: platformDrag.axis });
      return true;
    }
    function movePlatform(e) {
      var d = platformDrag, dx = e.clientX - d.x0, dy = e.clientY - d.y0;
      if (d.shift && d.axis === null && Math.hypot(dx, dy) >= 3) d.axis = bestAxis(dx, dy);
      if (d.shift && d.axis === null) return;
      controls.onPlatformDrag({ phase: "move", displacement: dragDisplacement(dx, dy, d.axis), axis: d.axis });
    }
    function endPlatformDrag() {
      var d = platformDrag;
      platformDrag = null;
      canvas.style.cursor = "grab";
      controls.onPlatformDrag({ phase: "end", displacement: null, axis: d.axis });
      draw();
    }
    // While dragging along an axis: a dashed line through the drag's start along it.
    function drawDragGuide() {
      if (!platformDrag || platformDrag.axis === null) return;
      var k = platformDrag.axis, a = platformDrag.origin.slice(), b = platformDrag.origin.slice();
      a[k] -= 2 * radius; b[k] += 2 * radius;
      line(a, b, ["#c0392b", "#27ae60", "#2e62c9"][k], 1.5, [6, 4]);
    }

    var drag = null;
    canvas.addEventListener("mousedown", function (e) {
      if (startPlatformDrag(e)) { e.preventDefault(); return; }
      drag = [e.clientX, e.clientY]; canvas.style.cursor = "grabbing";
    });
    window.addEventListener("mouseup", function () {
      if (platformDrag) { endPlatformDrag(); return; }
      drag = null; canvas.style.cursor = "grab";
    });
    canvas.addEventListener("mousemove", function (e) {
      if (drag || platformDrag || !controls.onPlatformDrag) return;
      var at = local(e);
      canvas.style.cursor = overPlatform(at[0], at[1]) ? "move" : "grab";
    });
    window.addEventListener("mousemove", function (e) {
      if (platformDrag) { movePlatform(e); return; }
      if (!drag) return;
      view.yaw += (e.clientX - drag[0]) * 0.01;
      view.pitch = Math.max(-1.55, Math.min(1.55, view.pitch + (e.clientY - drag[1]) * 0.01));
      drag = [e.clientX, e.clientY];
      draw();
    });
    canvas.addEventListener("wheel", function (e) {
      e.preventDefault();
      view.zoom = Math.max(0.1, Math.min(20, view.zoom * Math.exp(-e.deltaY * 0.001)));
      draw();
    }, { passive: false });
    canvas.addEventListener("dblclick", function () { view.yaw = -0.65; view.pitch = 0.45; view.zoom = 1; draw(); });
    if (cutSlider) cutSlider.addEventListener("input", draw);
    if (axisSel) axisSel.addEventListener("change", draw);
    window.addEventListener("resize", draw);
    function setScene(next, refit) {
      S = next;
      if (refit) fit();
      draw();
    }
    fit();
    return {
      draw: draw,
      setScene: setScene,
      // Where a world point (m) is drawn, in CSS px from the canvas' top left corner.
      screenOf: function (p) { return project(p); },
      // The view: yaw and pitch (rad) and the drawing scale (px per m).
      view: function () { return { yaw: view.yaw, pitch: view.pitch, scale: scale }; },
      dragDisplacement: dragDisplacement
    };
  }

  // The self-contained page of `--plot FILE.html`: the scene from #scene, its title and legend,
  // the status marker #cdpr-status that the browser test reads.
  function standalone() {
    var status = document.getElementById("cdpr-status");
    function fail(msg) {
      status.textContent = "error: " + msg;
      status.setAttribute("data-state", "error");
    }
    window.addEventListener("error", function (e) { fail(e.message); });
    try {
      var S = JSON.parse(document.getElementById("scene").textContent);
      document.getElementById("title").textContent = S.title;
      document.getElementById("mesh-label").textContent = S.meshLabel || "workspace";
      var legend = document.getElementById("legend");
      S.legend.forEach(function (line) {
        var p = document.createElement("p");
        p.textContent = line;
        legend.appendChild(p);
      });
      document.getElementById("cut-unit").textContent = S.units || "m";
      if (!S.anchors.length) {
        Array.prototype.forEach.call(document.querySelectorAll(".robot-key"), function (e) { e.style.display = "none"; });
      }
      if (S.hideBox) document.getElementById("key-box").style.display = "none";
      if (S.ball) {
        document.getElementById("key-ball").style.display = "";
        document.getElementById("ball-label").textContent = S.ballLabel || "ball";
      }
      create(document.getElementById("view"), S, {
        axis: document.getElementById("axis"),
        cut: document.getElementById("cut"),
        cutValue: document.getElementById("cut-value"),
        onDraw: function (n) {
          status.textContent = "rendered " + n + " triangles";
          status.setAttribute("data-state", "ok");
        }
      }).draw();
    } catch (e) {
      fail(e && e.message ? e.message : String(e));
    }
  }

  return { create: create, standalone: standalone };
})();

// planarkin web, a scene: loaded, solved and edited through the module (dragged points,
// a chosen assembly), and drawn: links, tracer paths, dead points, slots and sleeves.
"use strict";

(function (P) {
  const {
    $, call, num, S, linear, setMessage, fmtIn, sym, ctx, sx, sy, frame2, along, across, at, pathAt,
    finiteXY, slotTravel, COLORS, PATH_COLOR, polyline, groundMark, joint, label, bar, band, block,
  } = P;

  // --- scenes ------------------------------------------------------------------------------
  function loadScene(data, raw, name) {
    S.sceneData = data;
    S.sceneRaw = raw;
    S.name = name;
    S.overlay = null;
    $("list").textContent = "";
    const req = raw === null ? { op: "scene", scene: data } : '{"op":"scene","scene":' + raw + "}";
    const [info] = call(req);
    if (info.error) {
      S.info = null;
      S.path = null;
      S.pose = null;
      setMessage(info.error);
      return false;
    }
    setMessage("");
    S.info = info;
    if (data && data.lengths) {
      // a sketch: the core assembled the exact pose, which is drawn, edited and saved
      S.sceneData = { ...data, points: Object.fromEntries(info.names.map((n, i) => [n, info.drawn[i]])) };
      S.sceneRaw = null;
    }
    const [path, nums] = call({ op: "path" });
    const np = info.names.length;
    S.path = { ...path, pts: nums.subarray(path.offset, path.offset + path.n * np * 2) };
    // forces.js loads after this script: looked up when a scene loads
    P.loadForces();
    return true;
  }

  function solveScene() {
    if (!S.info) return;
    const [pose] = call({ op: "pose", theta: S.theta });
    S.pose = pose.error ? null : pose;
    if (pose.error) setMessage(pose.error);
  }

  // the points as shown now: the solved pose where it is solved, else as drawn
  function shownPoints() {
    const names = Object.keys(S.sceneData.points);
    const ok = S.pose && S.pose.status === "CONVERGED";
    return names.map((n, i) => (ok ? S.pose.points[i].map(num) : S.sceneData.points[n].map(Number)));
  }

  // edit: the scene drawn as shown, with point i moved to (x, y)
  function movePoint(i, x, y) {
    const names = Object.keys(S.sceneData.points);
    const shown = shownPoints();
    const data = { ...S.sceneData, points: {} };
    // a dragged point redraws the linkage: its lengths now come from the drawing
    delete data.lengths;
    names.forEach((n, k) => (data.points[n] = k === i ? [x, y] : shown[k].slice()));
    if (loadScene(data, null, S.name)) {
      S.theta = S.info.input_angle;
      solveScene();
    }
  }

  // --- drawing a scene ------------------------------------------------------------------------
  // a slot: a rail along its line (through the slot point's track, parallel to the guide's
  // line as it is now) covering the point's travel in the guide over the path, and a block
  // centred on the point. Returns what was drawn (scene units).
  function drawSlot(slot, pts, np, color) {
    const a = pts[slot.line[0]], b = pts[slot.line[1]], p = pts[slot.point];
    if (![a, b, p].every(finiteXY)) return null;
    const f = frame2(a, b);
    if (!f) return null;
    const tr = slotTravel(slot, np), now = along(p, a, f);
    const lo = tr ? Math.min(tr[0], now) : now, hi = tr ? Math.max(tr[1], now) : now;
    const pad = 22 / S.view.s, off = across(p, a, f);
    const r0 = at(a, f, lo - pad, off), r1 = at(a, f, hi + pad, off);
    band(r0, r1, 8, color, "rgba(0,0,0,0.05)", slot.guide === S.info.ground);
    return { name: slot.name, rail: [r0, r1], block: p, direction: f.u };
  }

  // a prismatic pair: an open sleeve fixed on the guide, on the axis of the sliding link's
  // point nearest the guide's line, where the link passes at every input of the path (else
  // at the guide's end that faces the link). Returns what was drawn (scene units).
  function drawSleeve(pr, pts, np, color) {
    const [ia, ib] = pr.line, a = pts[ia], b = pts[ib];
    const mine = S.info.links[pr.link].points, guide = S.info.links[pr.guide].points;
    if (![a, b, ...mine.map((j) => pts[j])].every(finiteXY)) return null;
    const f = frame2(a, b);
    if (!f) return null;
    let q = mine[0];
    for (const j of mine) if (Math.abs(across(pts[j], a, f)) < Math.abs(across(pts[q], a, f))) q = j;
    const span = (get) => {
      const t = mine.map((j) => get(j)).filter(isFinite);
      return t.length ? [Math.min(...t), Math.max(...t)] : null;
    };
    const now = span((j) => along(pts[j], a, f));
    let [lo, hi] = now;
    if (S.path) {
      for (let i = 0; i < S.path.n; i++) {
        const ai = pathAt(i, ia, np), bi = pathAt(i, ib, np), fi = finiteXY(ai) && finiteXY(bi) ? frame2(ai, bi) : null;
        if (!fi) continue;
        const sp = span((j) => along(pathAt(i, j, np), ai, fi));
        if (!sp) continue;
        lo = Math.max(lo, sp[0]); hi = Math.min(hi, sp[1]);
      }
    }
    const px = 1 / S.view.s;
    let c, h;
    if (lo <= hi) {
      c = (lo + hi) / 2; h = Math.max(8 * px, Math.min((hi - lo) / 2, 22 * px));
    } else {
      const g = guide.map((j) => along(pts[j], a, f)).filter(isFinite);
      const [g0, g1] = [Math.min(...g), Math.max(...g)], m = (now[0] + now[1]) / 2;
      h = 16 * px;
      c = m > g1 ? g1 + h : m < g0 ? g0 - h : m;
    }
    const off = across(pts[q], a, f);
    const s0 = at(a, f, c - h, off), s1 = at(a, f, c + h, off);
    band(s0, s1, 9, color, color + "30", pr.guide === S.info.ground);
    return { name: pr.name, sleeve: [s0, s1], direction: f.u };
  }

  function drawScene() {
    const data = S.sceneData;
    const names = Object.keys(data.points);
    const idx = Object.fromEntries(names.map((n, i) => [n, i]));
    const pts = shownPoints();
    const np = names.length;
    const info = S.info;
    const ground = info ? info.links[info.ground].name : data.ground;
    const links = Object.entries(data.links || {}).filter(([, pl]) => Array.isArray(pl));
    const groundPts = (links.find(([ln]) => ln === ground) || [null, []])[1];
    const perPoint = new Array(np).fill(0);
    for (const [, pl] of links) for (const n of pl) if (n in idx) perPoint[idx[n]]++;
    // not tracers: a slot's point (a joint, with its block), the points that carry a slot's
    // or prismatic pair's line, and a sliding link's points (unless they are outputs)
    if (info) {
      for (const sl of info.slots) for (const j of [sl.point, ...sl.line]) perPoint[j]++;
      for (const pr of info.prismatic) for (const j of [...pr.line, ...info.links[pr.link].points]) perPoint[j]++;
    }
    const tracer = (j) => perPoint[j] === 1 && !groundPts.includes(names[j]);
    // a ground pivot carries a moving link (or a slot's pin); a ground point that only
    // gives a line its direction is no pivot
    const moving = new Set(links.filter(([ln]) => ln !== ground).flatMap(([, pl]) => pl));
    if (info) for (const sl of info.slots) moving.add(names[sl.point]);
    const pivot = (n) => moving.has(n);
    const colorOf = {};
    let c = 0;
    for (const [ln] of links) colorOf[ln] = ln === ground ? "#555555" : COLORS[c++ % COLORS.length];
    const linkColor = (k) => colorOf[info.links[k].name] || "#555555";
    // the point that shows a linear input: the slot's point, or the sliding link's first
    let tip = -1;
    if (info && info.input) tip = info.input.tip;
    else if (info && info.linear_input) {
      const li = info.linear_input;
      tip = li.kind === "slot" ? info.slots[li.index].point : info.links[info.prismatic[li.index].link].points[0];
    }
    if (S.overlay) for (const o of S.overlay) for (let j = 0; j < np; j++) if (tracer(j)) polyline(o.pts, 2 * np, 2 * j, o.m, o.color, 1.5);
    if (S.path && $("paths").checked) {
      // tracers (points on one link) and the scene's requested outputs
      const outs = Array.isArray(data.outputs) ? data.outputs : [];
      const tracers = names.map((n, j) => j).filter((j) => !groundPts.includes(names[j]) &&
        (tracer(j) || outs.includes(names[j])));
      for (const j of tracers) polyline(S.path.pts, 2 * np, 2 * j, S.path.n, PATH_COLOR, 2);
      // the input's reach: the path of the input link's tip (where it stops, marked below)
      if (tip >= 0) polyline(S.path.pts, 2 * np, 2 * tip, S.path.n, "#bbb", 3, S.path.status);
      const marked = tip >= 0 ? [...tracers, tip] : tracers;
      // where the motion stops: the last input reached before a LIMIT (a dead point)
      // (a linear input's path spans its stroke: both ends are dead points)
      const st = S.path.status, n = S.path.n, ends = linear();
      for (let i = 0; i < n; i++) {
        const edge = st[i] === 0 && ((i + 1 < n && st[i + 1] !== 0) || (i > 0 && st[i - 1] !== 0) ||
          (ends && (i === 0 || i === n - 1)));
        if (!edge) continue;
        for (const j of marked) {
          const x = S.path.pts[(i * np + j) * 2], y = S.path.pts[(i * np + j) * 2 + 1];
          ctx.fillStyle = "#e74c3c"; ctx.beginPath(); ctx.arc(sx(x), sy(y), 4, 0, 2 * Math.PI); ctx.fill();
          if ($("labels").checked) label("dead point", x, y, 6, 14, "#e74c3c");
        }
      }
    }
    // slots' rails under the links
    const drawn = { slots: [], prismatic: [], pivots: [] };
    if (info && S.view) for (const sl of info.slots) {
      const d = drawSlot(sl, pts, np, linkColor(sl.guide));
      if (d) drawn.slots.push(d);
    }
    for (const [ln, pl] of links) {
      const xy = pl.filter((n) => n in idx).map((n) => pts[idx[n]]).filter(([x, y]) => isFinite(x) && isFinite(y));
      if (ln === ground) {
        for (const n of pl) {
          if (!(n in idx) || !pivot(n) || !finiteXY(pts[idx[n]])) continue;
          groundMark(...pts[idx[n]]);
          drawn.pivots.push(n);
        }
        continue;
      }
      const color = colorOf[ln];
      if (xy.length < 2) continue;
      if (xy.length > 2) {
        // a polygon with its points (nearly) in line is drawn as a bar
        let area = 0, extent = 0;
        xy.forEach(([x, y], k) => {
          const [x1, y1] = xy[(k + 1) % xy.length];
          area += (sx(x) * sy(y1) - sx(x1) * sy(y)) / 2;
          extent = Math.max(extent, Math.hypot(sx(x1) - sx(x), sy(y1) - sy(y)));
        });
        const flat = Math.abs(area) < 3 * extent;
        ctx.fillStyle = color + "40"; ctx.strokeStyle = color; ctx.lineWidth = flat ? 6 : 2; ctx.lineJoin = "round";
        ctx.beginPath(); xy.forEach(([x, y], k) => (k ? ctx.lineTo(sx(x), sy(y)) : ctx.moveTo(sx(x), sy(y))));
        ctx.closePath(); ctx.fill(); ctx.stroke();
      } else {
        bar(xy[0], xy[1], color);
      }
    }
    // prismatic pairs' sleeves over the sliding links, slots' blocks under the pins
    if (info && S.view) {
      for (const pr of info.prismatic) {
        const d = drawSleeve(pr, pts, np, linkColor(pr.guide));
        if (d) drawn.prismatic.push(d);
      }
      for (const d of drawn.slots) block(d.block, d.direction, "#ffd27f");
    }
    S.joints = drawn;
    const named = [];
    names.forEach((n, j) => {
      const [x, y] = pts[j];
      if (!isFinite(x)) return;
      if (groundPts.includes(n) && !pivot(n) && j !== S.drag) {
        // a point of the ground only (say, a slot's direction): a small dot
        ctx.fillStyle = "#555"; ctx.beginPath(); ctx.arc(sx(x), sy(y), 2.5, 0, 2 * Math.PI); ctx.fill();
      } else {
        joint(x, y, tracer(j) ? PATH_COLOR : j === S.drag ? "#ffd54f" : "#fff");
      }
      // one name where points coincide on the screen
      if (!$("labels").checked || named.some(([X, Y]) => Math.hypot(X - sx(x), Y - sy(y)) < 8)) return;
      named.push([sx(x), sy(y)]);
      label(n, x, y);
    });
    P.drawArrows(pts);
    P.drawEffort();
    if (info && $("labels").checked) {
      const where = info.input ? info.input.pivot : tip;
      if (where >= 0 && finiteXY(pts[where])) label(sym() + " = " + fmtIn(S.theta), ...pts[where], 10, 22);
    }
  }

  Object.assign(P, { loadScene, solveScene, shownPoints, movePoint, drawScene });
})(window.PK_PAGE);

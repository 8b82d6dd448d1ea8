// planarkin web: the page draws and handles input; planarkin's Rust core, compiled to
// WebAssembly (planarkin.wasm, here as wasm.js), computes everything it shows.
//
// URL parameters: scene=NAME (a built-in scene) or fourbar=r1,r2,r3,r4 (the four-bar by
// its lengths, the default); theta=DEGREES (the input angle; for a scene driven by a slot
// or prismatic pair, the displacement from the drawn pose in scene units); mode=open|crossed,
// p, delta=DEGREES (four-bar); auto=1 (auto-rotate, or for a linear input auto-advance
// between the stroke's ends). What the page computed is in the text of #state as JSON:
// {"scene", "theta" (radians, or the displacement), "input_kind", "points" {name: [x, y]},
// "status", "slots" and "prismatic" (what was drawn for them), ...}.
"use strict";

(function () {
  const DEG = Math.PI / 180;
  const enc = new TextEncoder();
  const dec = new TextDecoder();
  const $ = (id) => document.getElementById(id);

  // --- the module --------------------------------------------------------------------
  let ex = null; // the module's exports
  function call(req) {
    const bytes = enc.encode(typeof req === "string" ? req : JSON.stringify(req));
    const p = ex.pk_alloc(bytes.length);
    new Uint8Array(ex.memory.buffer, p, bytes.length).set(bytes);
    const n = ex.pk_call(p, bytes.length);
    ex.pk_free(p, bytes.length);
    const reply = JSON.parse(dec.decode(new Uint8Array(ex.memory.buffer, ex.pk_out(), n)));
    const k = ex.pk_nums_len();
    const nums = k ? new Float64Array(ex.memory.buffer, ex.pk_nums(), k).slice() : new Float64Array(0);
    return [reply, nums];
  }
  const num = (v) => (v === null || v === undefined ? NaN : v);

  // --- page state --------------------------------------------------------------------
  const S = {
    kind: "fourbar", // "fourbar" | "scene"
    name: "four-bar", // the built-in's name, the file's name, or "four-bar"
    r: [6, 2, 5, 5],
    mode: "open",
    p: 3,
    delta: 30 * DEG,
    theta: 0, // theta2 (four-bar), the scene's input angle (radians) or displacement (units)
    dir: 1, // auto-rotate direction (reverses where the motion stops)
    sceneData: null, // the scene as data (the file format), as drawn now
    sceneRaw: null, // its text when it came unedited from a file or a built-in
    info: null, // the module's description of the valid scene (null: invalid)
    path: null, // {theta, status, limit, pts (Float64Array N x P x 2)}
    pose: null,
    fb: null, // the four-bar reply
    fbPath: null,
    overlay: null, // circuits' traces to draw: [{pts, m, color}]
    view: null, // {s, ox, oy}: screen = (ox + s x, oy - s y)
    drag: -1,
    lastGood: 0,
    joints: { slots: [], prismatic: [] }, // what was drawn for slots and prismatic pairs
  };
  // the scene is driven by a slot or prismatic pair: its input is a displacement
  const linear = () => S.kind === "scene" && !!S.info && S.info.input_kind === "displacement";

  // --- four-bar --------------------------------------------------------------------------
  function solveFourbar() {
    const [fb, nums] = call({ op: "fourbar", r: S.r, theta2: S.theta, mode: S.mode, p: S.p, delta: S.delta });
    if (fb.error) {
      setMessage(fb.error);
      S.fb = null;
      return;
    }
    setMessage("");
    S.fb = fb;
    S.fbPath = nums.subarray(fb.path.offset, fb.path.offset + 2 * fb.path.n);
  }

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

  // --- view ---------------------------------------------------------------------------------
  const canvas = $("canvas");
  const ctx = canvas.getContext("2d");
  function fit(points) {
    let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
    for (const [x, y] of points) {
      if (!isFinite(x) || !isFinite(y)) continue;
      x0 = Math.min(x0, x); x1 = Math.max(x1, x);
      y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
    if (!isFinite(x0)) [x0, y0, x1, y1] = [-1, -1, 1, 1];
    const w = canvas.clientWidth, h = canvas.clientHeight, m = 40;
    const s = Math.min((w - 2 * m) / Math.max(x1 - x0, 1e-9), (h - 2 * m) / Math.max(y1 - y0, 1e-9));
    S.view = { s, ox: w / 2 - s * (x0 + x1) / 2, oy: h / 2 + s * (y0 + y1) / 2 };
  }
  const sx = (x) => S.view.ox + S.view.s * x;
  const sy = (y) => S.view.oy - S.view.s * y;
  const wx = (px) => (px - S.view.ox) / S.view.s;
  const wy = (py) => (S.view.oy - py) / S.view.s;

  // unit direction and normal (scene units) of the line a -> b; null if degenerate
  function frame2(a, b) {
    const dx = b[0] - a[0], dy = b[1] - a[1], l = Math.hypot(dx, dy);
    return l > 0 && isFinite(l) ? { u: [dx / l, dy / l], n: [-dy / l, dx / l] } : null;
  }
  const along = (p, a, f) => (p[0] - a[0]) * f.u[0] + (p[1] - a[1]) * f.u[1];
  const across = (p, a, f) => (p[0] - a[0]) * f.n[0] + (p[1] - a[1]) * f.n[1];
  const at = (a, f, t, o) => [a[0] + t * f.u[0] + o * f.n[0], a[1] + t * f.u[1] + o * f.n[1]];
  // the path's value of point j at input i (NaN when not solved)
  const pathAt = (i, j, np) => [S.path.pts[(i * np + j) * 2], S.path.pts[(i * np + j) * 2 + 1]];
  const finiteXY = (p) => isFinite(p[0]) && isFinite(p[1]);

  // a slot's travel along its line over the path: [lo, hi], distances from line[0] in the
  // guide (it moves with the guide); null when nothing is solved
  function slotTravel(slot, np) {
    const [ia, ib] = slot.line;
    let lo = Infinity, hi = -Infinity;
    for (let i = 0; S.path && i < S.path.n; i++) {
      const ai = pathAt(i, ia, np), bi = pathAt(i, ib, np), pi = pathAt(i, slot.point, np);
      const fi = [ai, bi, pi].every(finiteXY) ? frame2(ai, bi) : null;
      if (!fi) continue;
      const t = along(pi, ai, fi);
      lo = Math.min(lo, t); hi = Math.max(hi, t);
    }
    return lo <= hi ? [lo, hi] : null;
  }

  function fitNow() {
    const pts = [];
    if (S.kind === "fourbar") {
      if (!S.fb) return;
      const [r1, r2] = S.r;
      pts.push([-r2, -r2], [r2, r2], [r1, 0]);
      for (const q of Object.values(S.fb.points)) pts.push(q.map(num));
      for (let i = 0; i < S.fbPath.length; i += 2) pts.push([S.fbPath[i], S.fbPath[i + 1]]);
      const reach = Math.max(...S.r);
      pts.push([r1 + S.r[3], reach * 0.2], [r1 - S.r[3], -reach * 0.2]);
    } else {
      for (const v of Object.values(S.sceneData.points)) pts.push(v.map(Number));
      if (S.path) for (let i = 0; i < S.path.pts.length; i += 2) pts.push([S.path.pts[i], S.path.pts[i + 1]]);
      if (S.overlay) for (const o of S.overlay) for (let i = 0; i < o.pts.length; i += 2) pts.push([o.pts[i], o.pts[i + 1]]);
      // slots' rails wherever their guides take them
      const np = S.info ? S.info.names.length : 0;
      if (S.path && S.info) for (const sl of S.info.slots) {
        const tr = slotTravel(sl, np);
        for (let i = 0; tr && i < S.path.n; i++) {
          const ai = pathAt(i, sl.line[0], np), bi = pathAt(i, sl.line[1], np), pi = pathAt(i, sl.point, np);
          const fi = [ai, bi, pi].every(finiteXY) ? frame2(ai, bi) : null;
          if (fi) for (const t of tr) pts.push(at(ai, fi, t, across(pi, ai, fi)));
        }
      }
    }
    fit(pts);
  }

  function resize() {
    const dpr = window.devicePixelRatio || 1;
    canvas.width = Math.round(canvas.clientWidth * dpr);
    canvas.height = Math.round(canvas.clientHeight * dpr);
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    fitNow();
  }

  // --- drawing --------------------------------------------------------------------------------
  const COLORS = ["#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"];
  const PATH_COLOR = "#ff7f0e";
  const LIMIT = -8; // planarkin.Status.LIMIT

  function grid() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    const raw = 60 / S.view.s, e = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map((k) => k * e).find((v) => v >= raw);
    ctx.strokeStyle = "#e6e6e6";
    ctx.lineWidth = 1;
    ctx.fillStyle = "#999";
    ctx.font = "10px system-ui";
    for (let x = Math.ceil(wx(0) / step) * step; sx(x) < w; x += step) {
      ctx.beginPath(); ctx.moveTo(sx(x), 0); ctx.lineTo(sx(x), h); ctx.stroke();
      ctx.fillText(+x.toFixed(6) + "", sx(x) + 2, h - 4);
    }
    for (let y = Math.ceil(wy(h) / step) * step; sy(y) > 0; y += step) {
      ctx.beginPath(); ctx.moveTo(0, sy(y)); ctx.lineTo(w, sy(y)); ctx.stroke();
      ctx.fillText(+y.toFixed(6) + "", 2, sy(y) - 2);
    }
  }

  // a path of n points (x, y at i * stride + offset), broken at NaN and where mask[i] != 0
  function polyline(xy, stride, offset, n, color, width, mask = null) {
    ctx.strokeStyle = color;
    ctx.lineWidth = width;
    ctx.beginPath();
    let pen = false;
    for (let i = 0; i < n; i++) {
      const x = xy[i * stride + offset], y = xy[i * stride + offset + 1];
      if (!isFinite(x) || !isFinite(y) || (mask && mask[i] !== 0)) { pen = false; continue; }
      if (pen) ctx.lineTo(sx(x), sy(y)); else ctx.moveTo(sx(x), sy(y));
      pen = true;
    }
    ctx.stroke();
  }

  function groundMark(x, y) {
    const X = sx(x), Y = sy(y);
    ctx.fillStyle = "#555";
    ctx.beginPath(); ctx.moveTo(X, Y); ctx.lineTo(X - 9, Y + 14); ctx.lineTo(X + 9, Y + 14); ctx.closePath(); ctx.fill();
    ctx.strokeStyle = "#555"; ctx.lineWidth = 1;
    for (let k = -9; k <= 9; k += 4) { ctx.beginPath(); ctx.moveTo(X + k, Y + 14); ctx.lineTo(X + k - 4, Y + 19); ctx.stroke(); }
  }

  function joint(x, y, fill) {
    ctx.beginPath(); ctx.arc(sx(x), sy(y), 5, 0, 2 * Math.PI);
    ctx.fillStyle = fill; ctx.fill();
    ctx.strokeStyle = "#222"; ctx.lineWidth = 1.5; ctx.stroke();
  }

  function label(text, x, y, dx = 8, dy = -8, color = "#222") {
    ctx.fillStyle = color;
    ctx.font = "12px system-ui";
    ctx.fillText(text, sx(x) + dx, sy(y) + dy);
  }

  function bar(a, b, color, width = 6) {
    ctx.strokeStyle = color; ctx.lineWidth = width; ctx.lineCap = "round";
    ctx.beginPath(); ctx.moveTo(sx(a[0]), sy(a[1])); ctx.lineTo(sx(b[0]), sy(b[1])); ctx.stroke();
  }

  const fmtDeg = (t) => (t / DEG).toFixed(2) + "\u00b0";
  const units = () => (S.sceneData && typeof S.sceneData.units === "string" ? " " + S.sceneData.units : "");
  const fmtLen = (v) => v.toFixed(2) + units();
  // the scene's input value as shown, and its symbol
  const fmtIn = (t) => (linear() ? fmtLen(t) : fmtDeg(t));
  const sym = () => (linear() ? "s" : "\u03b8");

  // a straight band of half-width w pixels from a to b (scene points): the long sides stroked
  function band(a, b, w, color, fill, hatch = false) {
    const X0 = sx(a[0]), Y0 = sy(a[1]), X1 = sx(b[0]), Y1 = sy(b[1]);
    const l = Math.hypot(X1 - X0, Y1 - Y0);
    if (!(l > 0)) return;
    const nx = (-(Y1 - Y0) / l) * w, ny = ((X1 - X0) / l) * w;
    ctx.fillStyle = fill;
    ctx.beginPath(); ctx.moveTo(X0 + nx, Y0 + ny); ctx.lineTo(X1 + nx, Y1 + ny);
    ctx.lineTo(X1 - nx, Y1 - ny); ctx.lineTo(X0 - nx, Y0 - ny); ctx.closePath(); ctx.fill();
    ctx.strokeStyle = color; ctx.lineWidth = 2; ctx.lineCap = "butt";
    ctx.beginPath(); ctx.moveTo(X0 + nx, Y0 + ny); ctx.lineTo(X1 + nx, Y1 + ny);
    ctx.moveTo(X0 - nx, Y0 - ny); ctx.lineTo(X1 - nx, Y1 - ny); ctx.stroke();
    if (!hatch) return;
    // fixed to the ground: ticks outside both sides
    const ux = (X1 - X0) / l, uy = (Y1 - Y0) / l, ox = nx / w, oy = ny / w;
    ctx.lineWidth = 1;
    ctx.beginPath();
    for (let d = 4; d < l; d += 7) {
      for (const k of [1, -1]) {
        const x = X0 + ux * d + k * nx, y = Y0 + uy * d + k * ny;
        ctx.moveTo(x, y); ctx.lineTo(x + k * ox * 5 - ux * 4, y + k * oy * 5 - uy * 4);
      }
    }
    ctx.stroke();
  }
  // a slider block: a rectangle centred on p (scene), aligned with the unit direction u
  function block(p, u, color) {
    ctx.save();
    ctx.translate(sx(p[0]), sy(p[1]));
    ctx.rotate(Math.atan2(-u[1], u[0]));
    ctx.fillStyle = color; ctx.strokeStyle = "#222"; ctx.lineWidth = 1.5;
    ctx.fillRect(-13, -6, 26, 12); ctx.strokeRect(-13, -6, 26, 12);
    ctx.restore();
  }


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

  function drawFourbar() {
    const fb = S.fb;
    if (!fb) return;
    const P = Object.fromEntries(Object.entries(fb.points).map(([k, v]) => [k, v.map(num)]));
    const r2 = S.r[1];
    // crank circle: reachable arcs (the assemblable intervals) solid, unreachable red dashed
    ctx.lineWidth = 1;
    ctx.setLineDash([5, 4]); ctx.strokeStyle = "#e74c3c";
    ctx.beginPath(); ctx.arc(sx(0), sy(0), r2 * S.view.s, 0, 2 * Math.PI); ctx.stroke();
    ctx.setLineDash([]); ctx.strokeStyle = "#bbb"; ctx.lineWidth = 3;
    for (const [a, b] of fb.limits.intervals) {
      ctx.beginPath(); ctx.arc(sx(0), sy(0), r2 * S.view.s, -b, -a); ctx.stroke();
    }
    for (const t of fb.limits.dead_points) {
      const x = r2 * Math.cos(t), y = r2 * Math.sin(t); // where to draw the mark
      ctx.fillStyle = "#e74c3c"; ctx.beginPath(); ctx.arc(sx(x), sy(y), 4, 0, 2 * Math.PI); ctx.fill();
      if ($("labels").checked) label("dead " + fmtDeg(t), x, y, 6, 14, "#e74c3c");
    }
    if ($("paths").checked) polyline(S.fbPath, 2, 0, fb.path.n, PATH_COLOR, 2);
    groundMark(0, 0); groundMark(S.r[0], 0);
    bar([0, 0], [S.r[0], 0], "#999", 3);
    const solved = fb.status === "CONVERGED" || fb.status === "SINGULAR";
    bar(P.O2, P.A, COLORS[0]);
    if (solved && isFinite(P.B[0])) {
      ctx.fillStyle = "rgba(44,160,44,0.25)";
      ctx.beginPath(); ctx.moveTo(sx(P.A[0]), sy(P.A[1])); ctx.lineTo(sx(P.B[0]), sy(P.B[1]));
      ctx.lineTo(sx(P.P[0]), sy(P.P[1])); ctx.closePath(); ctx.fill();
      bar(P.A, P.B, COLORS[1]);
      bar(P.O4, P.B, COLORS[2]);
      joint(...P.B, "#fff");
      joint(...P.P, PATH_COLOR);
    }
    joint(...P.O2, "#fff"); joint(...P.O4, "#fff"); joint(...P.A, "#fff");
    if ($("labels").checked) {
      for (const k of ["O2", "O4", "A", "B", "P"]) if (isFinite(P[k][0])) label(k, ...P[k]);
      label("\u03b82 = " + fmtDeg(S.theta), 0, 0, 10, 22);
      if (solved) {
        label("\u03b83 = " + fmtDeg(fb.theta3), (P.A[0] + P.B[0]) / 2, (P.A[1] + P.B[1]) / 2, 8, 14);
        label("\u03b84 = " + fmtDeg(fb.theta4), S.r[0], 0, 10, 22);
      }
    }
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
    const drawn = { slots: [], prismatic: [] };
    if (info && S.view) for (const sl of info.slots) {
      const d = drawSlot(sl, pts, np, linkColor(sl.guide));
      if (d) drawn.slots.push(d);
    }
    for (const [ln, pl] of links) {
      const xy = pl.filter((n) => n in idx).map((n) => pts[idx[n]]).filter(([x, y]) => isFinite(x) && isFinite(y));
      if (ln === ground) {
        for (const q of xy) groundMark(...q);
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
      if (perPoint[j] === 1 && groundPts.includes(n) && j !== S.drag) {
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
    if (info && $("labels").checked) {
      const where = info.input ? info.input.pivot : tip;
      if (where >= 0 && finiteXY(pts[where])) label(sym() + " = " + fmtIn(S.theta), ...pts[where], 10, 22);
    }
  }

  function draw() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    ctx.clearRect(0, 0, w, h);
    if (!S.view) return;
    if ($("grid").checked) grid();
    if (S.kind === "fourbar") drawFourbar(); else if (S.sceneData) drawScene();
  }

  // --- status and the exposed state ----------------------------------------------------------------
  function setMessage(m) { $("message").textContent = m; }

  function badge(status) {
    const cls = status === "CONVERGED" ? "good" : "bad";
    return `<span class="badge ${cls}">${status}</span>`;
  }

  function infoText() {
    if (S.kind === "fourbar") {
      const fb = S.fb;
      if (!fb) return "";
      const l = fb.limits, g = fb.grashof;
      const spans = l.full_rotation ? "the crank turns fully" :
        "crank reaches " + l.intervals.map(([a, b]) => `[${fmtDeg(a)}, ${fmtDeg(b)}]`).join(", ") + " only";
      return `${badge(fb.status)} at \u03b82 = ${fmtDeg(S.theta)} (${fb.mode})\n` +
        `Grashof: <b>${g.condition}</b>, Barker <b>${g.barker}</b> (${g.kind})\n${g.description}\n` +
        `${spans}\n` +
        `dead points: ${l.dead_points.length ? l.dead_points.map(fmtDeg).join(", ") : "none"}\n` +
        (fb.status === "CONVERGED" ? `\u03b83 = ${fmtDeg(fb.theta3)}, \u03b84 = ${fmtDeg(fb.theta4)}, \u03bc = ${fmtDeg(fb.transmission_angle)}` : "");
    }
    if (!S.info) return "invalid scene (see the message above)";
    const p = S.pose;
    const lim = [...new Set(S.path.limit.filter((v) => v !== null).map((v) => v.toFixed(9)))].map(Number);
    const fails = S.path.status.filter((s) => s !== 0).length;
    let t = `${badge(p ? p.status : "?")} at ${sym()} = ${fmtIn(S.theta)}\n`;
    if (p && p.status === "LIMIT") t += `past the dead point at ${fmtIn(p.limit)}: the motion stops there\n`;
    // the declared output along a slot or prismatic pair: the core's coordinate, as Python's sw.output
    const lout = S.info.linear_output;
    if (lout && p && typeof p.output === "number") t += `output: ${fmtLen(p.output)} along ${lout.kind} '${lout.name}'\n`;
    t += `steps: ${S.info.steps.join(", ")}\n`;
    if (linear()) {
      const li = S.info.linear_input, [lo, hi] = S.info.stroke;
      t += `input: displacement along ${li.kind} '${li.name}' from the drawn pose\n`;
      t += `stroke (dead point to dead point): ${fmtLen(lo)} to ${fmtLen(hi)}\n`;
      const st = S.path.status, n = S.path.n;
      const atEnds = st.every((c, i) => c === 0 || i === 0 || i === n - 1);
      if (fails) t += `over the stroke: ${fails} of ${n} inputs not converged` + (atEnds ? " (at its ends, the dead points)\n" : "\n");
      return t;
    }
    t += fails ? `over one turn from the drawn pose: ${fails} of ${S.path.n} inputs not reached\n` : "the input turns fully on the drawn circuit\n";
    if (lim.length) t += `dead points (LIMIT past them): ${lim.map(fmtDeg).join(", ")}\n`;
    const st = S.path.status, ends = [];
    for (let i = 0; i < S.path.n; i++) {
      if (st[i] === 0 && ((i + 1 < S.path.n && st[i + 1] !== 0) || (i > 0 && st[i - 1] !== 0))) ends.push(S.path.theta[i]);
    }
    if (ends.length) t += `motion stops near: ${ends.map(fmtDeg).join(", ")} (last inputs reached, 1\u00b0 apart)\n`;
    return t;
  }

  function exposeState() {
    let st;
    if (S.kind === "fourbar") {
      const fb = S.fb;
      st = {
        scene: "four-bar",
        r: S.r, mode: S.mode, p: S.p, delta: S.delta,
        theta: S.theta,
        points: fb ? Object.fromEntries(Object.entries(fb.points).map(([k, v]) => [k, v])) : {},
        status: fb ? fb.status : null,
        error: $("message").textContent || null,
        grashof: fb ? fb.grashof.condition : null,
        barker: fb ? fb.grashof.barker : null,
      };
    } else {
      const names = Object.keys(S.sceneData.points);
      const p = S.pose;
      st = {
        scene: S.name,
        theta: S.theta,
        points: p ? Object.fromEntries(names.map((n, i) => [n, p.points[i]])) : {},
        status: p ? p.status : null,
        error: $("message").textContent || null,
        drawn: S.sceneData.points,
        input_kind: S.info ? S.info.input_kind : null,
        stroke: S.info ? S.info.stroke : null,
        slots: S.joints.slots,
        prismatic: S.joints.prismatic,
      };
    }
    // where each point is on the canvas (CSS pixels from its top left), for tests
    const shown = S.kind === "fourbar" ? Object.entries(st.points) :
      Object.keys(S.sceneData.points).map((n, i) => [n, shownPoints()[i]]);
    st.screen = Object.fromEntries(shown.filter(([, v]) => v && isFinite(num(v[0]))).map(([n, v]) => [n, [sx(v[0]), sy(v[1])]]));
    st.fps = fps;
    $("state").textContent = JSON.stringify(st);
  }

  function refreshText() {
    $("info").innerHTML = infoText();
    const th = $("theta");
    if (linear()) {
      // the slider spans the stroke, in scene units
      const [lo, hi] = S.info.stroke;
      const range = [String(lo), String(hi), String(hi > lo ? (hi - lo) / 1000 : 1e-3)];
      if ([th.min, th.max, th.step].join() !== range.join()) [th.min, th.max, th.step] = range;
      th.value = String(S.theta);
      $("theta-v").textContent = S.theta.toFixed(2);
      $("input-title").textContent = "Input displacement" + (units() ? ` (${units().trim()})` : "");
      $("auto-label").textContent = "auto-advance";
      $("speed-v").textContent = fmtLen((Number($("speed").value) * (hi - lo)) / 360);
    } else {
      if (th.min !== "-180") [th.min, th.max, th.step] = ["-180", "180", "0.1"];
      th.value = String(((S.theta / DEG + 540) % 360) - 180);
      $("theta-v").textContent = (S.theta / DEG).toFixed(1) + "\u00b0";
      $("input-title").textContent = "Input angle";
      $("auto-label").textContent = "auto-rotate";
      $("speed-v").textContent = $("speed").value + "\u00b0";
    }
    for (const [k, v] of [["r1", S.r[0]], ["r2", S.r[1]], ["r3", S.r[2]], ["r4", S.r[3]], ["p", S.p]]) {
      $(k).value = String(v); $(k + "-v").textContent = v.toFixed(2);
    }
    $("delta").value = String(S.delta / DEG); $("delta-v").textContent = (S.delta / DEG).toFixed(1) + "\u00b0";
    $("fourbar-panel").classList.toggle("hidden", S.kind !== "fourbar");
    $("scene-panel").classList.toggle("hidden", S.kind !== "scene");
    $("mode-" + S.mode).checked = true;
  }

  function update({ refit = false } = {}) {
    if (S.kind === "fourbar") solveFourbar(); else solveScene();
    if (refit || !S.view) fitNow();
    refreshText();
    draw();
    exposeState();
  }

  // --- input -------------------------------------------------------------------------------------------
  function step() {
    const before = S.theta;
    if (linear()) {
      // auto-advance: speed/360 of the stroke a frame, bouncing between its ends
      const [lo, hi] = S.info.stroke;
      let next = before + (S.dir * Number($("speed").value) * (hi - lo)) / 360, dir = S.dir;
      if (next >= hi) { next = hi; dir = -1; } else if (next <= lo) { next = lo; dir = 1; }
      S.theta = next;
      solveScene();
      if (S.pose && S.pose.status === "CONVERGED") S.dir = dir;
      else { S.dir = -S.dir; S.theta = before; solveScene(); }
      return;
    }
    const d = S.dir * Number($("speed").value) * DEG;
    S.theta = before + d;
    if (S.kind === "fourbar") {
      solveFourbar();
      const ok = S.fb && S.fb.status !== "NOT_ASSEMBLABLE";
      if (!ok) { S.dir = -S.dir; S.theta = before; solveFourbar(); }
    } else {
      solveScene();
      const ok = S.pose && S.pose.status === "CONVERGED";
      if (!ok) { S.dir = -S.dir; S.theta = before; solveScene(); }
    }
    if (S.theta > Math.PI) S.theta -= 2 * Math.PI;
    if (S.theta <= -Math.PI) S.theta += 2 * Math.PI;
  }

  let fps = 0, frames = 0, since = performance.now();
  function frame(now) {
    frames++;
    if (now - since >= 1000) { fps = (frames * 1000) / (now - since); frames = 0; since = now; $("hud").textContent = fps.toFixed(0) + " fps"; }
    if ($("auto").checked && S.drag < 0) {
      step();
      refreshText();
      draw();
      exposeState();
    }
    requestAnimationFrame(frame);
  }

  function choose(which) {
    S.overlay = null;
    $("list").textContent = "";
    if (which === "four-bar") {
      S.kind = "fourbar";
      S.name = "four-bar";
      setMessage("");
    } else {
      S.kind = "scene";
      const raw = window.PK_SCENES[which];
      if (loadScene(JSON.parse(raw), raw, which)) S.theta = S.info.input_angle;
    }
    update({ refit: true });
  }

  function bind() {
    const sel = $("which");
    const opt = (v, t) => { const o = document.createElement("option"); o.value = v; o.textContent = t; sel.appendChild(o); };
    opt("four-bar", "four-bar (lengths r1..r4)");
    for (const n of Object.keys(window.PK_SCENES)) opt(n, "scene: " + n);
    sel.addEventListener("change", () => choose(sel.value));

    for (const [k, i] of [["r1", 0], ["r2", 1], ["r3", 2], ["r4", 3]]) {
      $(k).addEventListener("input", () => { S.r[i] = Number($(k).value); update({ refit: true }); });
    }
    $("p").addEventListener("input", () => { S.p = Number($("p").value); update(); });
    $("delta").addEventListener("input", () => { S.delta = Number($("delta").value) * DEG; update(); });
    for (const m of ["open", "crossed"]) $("mode-" + m).addEventListener("change", () => { S.mode = m; update(); });
    $("theta").addEventListener("input", () => { S.theta = Number($("theta").value) * (linear() ? 1 : DEG); update(); });
    $("speed").addEventListener("input", () => refreshText());
    for (const k of ["grid", "labels", "paths"]) $(k).addEventListener("change", () => draw());

    $("file").addEventListener("change", async () => {
      const f = $("file").files[0];
      if (f) openText(await f.text(), f.name);
    });

    $("save").addEventListener("click", () => {
      let data;
      if (S.kind === "fourbar") {
        if (!S.fb) return;
        const P = S.fb.points;
        data = {
          name: `four-bar (${S.r.join(", ")})`,
          points: Object.fromEntries(Object.entries(P).map(([k, v]) => [k, v])),
          links: { ground: ["O2", "O4"], crank: ["O2", "A"], coupler: ["A", "B", "P"], rocker: ["O4", "B"] },
          ground: "ground",
          input: { link: "crank", pivot: "O2" },
          output: { link: "rocker", pivot: "O4" },
        };
      } else {
        // as drawn when shown at the drawn input angle (bit for bit), else the pose shown
        const names = Object.keys(S.sceneData.points);
        const asDrawn = !S.info || S.theta === S.info.input_angle;
        const shown = asDrawn ? names.map((n) => S.sceneData.points[n]) : shownPoints();
        data = { ...S.sceneData, points: Object.fromEntries(names.map((n, i) => [n, shown[i]])) };
      }
      const blob = new Blob([JSON.stringify(data, null, 1) + "\n"], { type: "application/json" });
      const a = document.createElement("a");
      a.href = URL.createObjectURL(blob);
      a.download = (S.kind === "fourbar" ? "fourbar" : String(S.name).replace(/\.json$/, "")) + "-edited.json";
      document.body.appendChild(a); a.click(); a.remove();
      setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    });

    $("assemblies-btn").addEventListener("click", () => {
      if (!S.info) return;
      const [a] = call({ op: "assemblies", theta: S.theta });
      const list = $("list");
      list.textContent = "";
      if (a.error) { setMessage(a.error); return; }
      const head = document.createElement("div");
      head.textContent = `${a.assemblies.length} assemblies at ${sym()} = ${fmtIn(S.theta)}:`;
      list.appendChild(head);
      a.assemblies.forEach((x, k) => {
        const b = document.createElement("button");
        b.textContent = `#${k + 1}  ${x.label}  det ${num(x.det).toExponential(2)}`;
        b.addEventListener("click", () => switchTo(x.points));
        list.appendChild(b);
      });
    });

    $("circuits-btn").addEventListener("click", () => {
      if (!S.info) return;
      const [c, nums] = call({ op: "circuits", theta: S.theta });
      const list = $("list");
      list.textContent = "";
      if (c.error) { setMessage(c.error); return; }
      const np = S.info.names.length;
      S.overlay = c.circuits.map((ci, k) => ({
        pts: nums.subarray(ci.trace.offset, ci.trace.offset + ci.trace.m * np * 2), m: ci.trace.m,
        color: COLORS[(k + 3) % COLORS.length] + "b0",
      }));
      const head = document.createElement("div");
      head.textContent = `${c.circuits.length} circuits at ${sym()} = ${fmtIn(S.theta)}:`;
      list.appendChild(head);
      c.circuits.forEach((ci, k) => {
        const b = document.createElement("button");
        b.style.color = COLORS[(k + 3) % COLORS.length];
        const tp = ci.turning_points.length ? `turning at ${ci.turning_points.map(fmtIn).join(", ")}` : "no turning point";
        b.textContent = `circuit ${k + 1}: ${ci.full_turn ? "full turn" : "rocks"}; ${tp}; assemblies ${ci.assemblies.map((i) => "#" + (i + 1)).join(" ")}`;
        b.addEventListener("click", () => switchTo(c.assemblies[ci.assemblies[0]].points));
        list.appendChild(b);
      });
      fitNow();
      draw();
      exposeState();
    });

    // dragging the drawn points
    const hit = (ev) => {
      if (S.kind !== "scene" || !S.sceneData) return -1;
      const r = canvas.getBoundingClientRect();
      const [mx, my] = [ev.clientX - r.left, ev.clientY - r.top];
      const pts = shownPoints();
      let best = -1, bd = 10;
      pts.forEach(([x, y], i) => { const d = Math.hypot(sx(x) - mx, sy(y) - my); if (d < bd) { bd = d; best = i; } });
      return best;
    };
    canvas.addEventListener("pointerdown", (ev) => {
      S.drag = hit(ev);
      if (S.drag >= 0) { canvas.setPointerCapture(ev.pointerId); draw(); }
    });
    canvas.addEventListener("pointermove", (ev) => {
      if (S.drag < 0) { canvas.style.cursor = hit(ev) >= 0 ? "grab" : "default"; return; }
      const r = canvas.getBoundingClientRect();
      movePoint(S.drag, wx(ev.clientX - r.left), wy(ev.clientY - r.top));
      refreshText(); draw(); exposeState();
    });
    const release = () => {
      if (S.drag < 0) return;
      S.drag = -1;
      update();
    };
    canvas.addEventListener("pointerup", release);
    canvas.addEventListener("pointercancel", release);
    window.addEventListener("resize", () => { resize(); draw(); exposeState(); });
  }

  // a scene file's text (opened from disk, or ?file=URL when served)
  function openText(text, fname) {
    const sel = $("which");
    if (![...sel.options].some((o) => o.value === "file")) {
      const o = document.createElement("option"); o.value = "file"; o.textContent = "file"; sel.appendChild(o);
    }
    sel.value = "file";
    $("list").textContent = "";
    S.kind = "scene";
    S.overlay = null;
    let data;
    try {
      data = JSON.parse(text);
    } catch (e) {
      S.sceneData = { points: {}, links: {} }; S.info = null; S.pose = null; S.path = null; S.name = fname;
      setMessage(`${fname} is not JSON: ${e.message}`);
      refreshText(); draw(); exposeState();
      return;
    }
    const drawable = data && typeof data === "object" && !Array.isArray(data) &&
      data.points && typeof data.points === "object" && !Array.isArray(data.points) &&
      Object.values(data.points).every((v) => Array.isArray(v) && v.length === 2) &&
      data.links && typeof data.links === "object" && !Array.isArray(data.links);
    // the module checks everything (and names what is wrong); the page only draws
    const ok = loadScene(data, text, fname);
    if (!drawable) S.sceneData = { points: {}, links: {} };
    if (ok) S.theta = S.info.input_angle;
    const msg = $("message").textContent;
    update({ refit: true });
    if (!ok) setMessage(msg);
    exposeState();
  }

  // a new drawing: the scene in the given assembly, at the current input angle
  function switchTo(points) {
    const names = Object.keys(S.sceneData.points);
    const data = { ...S.sceneData, points: Object.fromEntries(names.map((n, i) => [n, points[i].map(num)])) };
    const overlay = S.overlay;
    if (loadScene(data, null, S.name)) S.theta = S.info.input_angle;
    S.overlay = overlay;
    update();
  }

  // --- start -------------------------------------------------------------------------------------------
  async function start() {
    const bin = atob(window.PK_WASM_BASE64);
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    const { instance } = await WebAssembly.instantiate(bytes, {});
    ex = instance.exports;
    bind();
    const q = new URLSearchParams(location.search);
    if (q.has("fourbar")) {
      const r = q.get("fourbar").split(",").map(Number);
      if (r.length === 4) S.r = r;
    }
    if (q.has("mode")) S.mode = q.get("mode") === "crossed" ? "crossed" : "open";
    if (q.has("p")) S.p = Number(q.get("p"));
    if (q.has("delta")) S.delta = Number(q.get("delta")) * DEG;
    if (q.get("auto") === "1") $("auto").checked = true;
    if (q.has("speed")) $("speed").value = q.get("speed");
    const scene = q.get("scene");
    if (scene && !(scene in window.PK_SCENES)) setMessage(`unknown built-in scene '${scene}'; known: ${Object.keys(window.PK_SCENES).join(", ")}`);
    const which = scene && scene in window.PK_SCENES ? scene : "four-bar";
    $("which").value = which;
    resize();
    const keep = $("message").textContent;
    choose(which);
    if (keep) setMessage(keep);
    if (q.has("file")) {
      const url = q.get("file");
      const text = await (await fetch(url)).text();
      openText(text, url.split("/").pop());
    }
    if (q.has("theta")) {
      S.theta = Number(q.get("theta")) * (linear() ? 1 : DEG);
      update();
    }
    requestAnimationFrame(frame);
    document.body.dataset.ready = "1";
  }

  // hooks for benchmarks and tests: the module's own answers, timed in the page
  window.pk = {
    call: (req) => call(req)[0],
    // seconds per call of `req`, timed over blocks of n calls (the clock's resolution is
    // coarse in a browser): the median and the best of `reps` blocks, in milliseconds
    bench(req, n = 200, reps = 7) {
      const text = JSON.stringify(req);
      const per = [];
      for (let r = 0; r < reps; r++) {
        const t0 = performance.now();
        for (let i = 0; i < n; i++) call(text);
        per.push((performance.now() - t0) / n);
      }
      per.sort((a, b) => a - b);
      return { median_ms: per[reps >> 1], min_ms: per[0], n, reps };
    },
    fps: () => fps,
  };

  start().catch((e) => { setMessage("could not start: " + e); throw e; });
})();

// planarkin web, "draw a path": the user draws a curve on the canvas (mouse, pen or
// touch), and the path atlas (js/atlas-worker.js, the core's atlas in its own module
// instance) returns the best few four-bars placed onto it; each is shown moving along the
// drawn path and opens as the current scene. Placed from the atlas, not refined.
"use strict";

(function (P) {
  const { $, S, canvas, ctx, wx, wy, sx, sy, setMessage, COLORS, PATH_COLOR } = P;

  const ATLAS_SIZE = 100000;
  const ATLAS_SEED = 0;
  const SHOWN = 4; // linkages returned
  const CANDIDATES = 200; // nearest descriptors placed onto the path

  const D = {
    stroke: [], // the drawn path, scene units
    drawing: false,
    closed: true,
    worker: null, // {post(msg)}
    where: null, // "worker" | "page" (where the atlas runs)
    atlas: null, // {size, full_turn, ms} once built
    progress: null, // {done, total}
    busy: false,
    results: null, // the last query's linkages
    timings: null,
    selected: 0,
    tick: 0, // animation frame counter
    pending: new Map(), // query id -> resolve/reject
    nextId: 1,
    size: ATLAS_SIZE,
    note: "",
  };

  // --- the worker ---------------------------------------------------------------------
  function wasmBytes() {
    const bin = atob(window.PK_WASM_BASE64);
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    return bytes;
  }

  function onMessage(msg) {
    if (msg.type === "progress") {
      D.progress = { done: msg.done, total: msg.total };
    } else if (msg.type === "ready") {
      D.atlas = { size: msg.size, full_turn: msg.full_turn, ms: msg.ms };
    } else if (msg.type === "result" || msg.type === "error") {
      const p = D.pending.get(msg.id);
      if (p) {
        D.pending.delete(msg.id);
        if (msg.type === "result") p.resolve(msg); else p.reject(new Error(msg.message));
      } else if (msg.type === "error") {
        setMessage("path atlas: " + msg.message);
      }
    }
    refreshPanel();
  }

  // the worker from a Blob of its function's text (file:// refuses a worker script); where
  // no worker starts, the same function on this thread (it yields between chunks)
  function startWorker() {
    if (D.worker) return;
    const init = { type: "init", wasm: wasmBytes(), size: D.size, seed: ATLAS_SEED };
    try {
      const src = `"use strict";\n${window.pkAtlasWorker.toString()}\npkAtlasWorker(self);\n`;
      const url = URL.createObjectURL(new Blob([src], { type: "text/javascript" }));
      const w = new Worker(url);
      w.onmessage = (ev) => onMessage(ev.data);
      w.onerror = (ev) => {
        ev.preventDefault();
        if (D.where === "worker" && !D.atlas) inPage(init, "the Web Worker failed (" + (ev.message || "no reason given") + ")");
      };
      D.worker = { post: (m) => w.postMessage(m) };
      D.where = "worker";
      D.worker.post(init);
    } catch (e) {
      inPage(init, "no Web Worker here (" + e.message + ")");
    }
    refreshPanel();
  }

  function inPage(init, why) {
    const scope = { postMessage: (m) => setTimeout(() => onMessage(m), 0), onmessage: null };
    window.pkAtlasWorker(scope);
    D.worker = { post: (m) => scope.onmessage({ data: m }) };
    D.where = "page";
    D.note = why + ": the atlas is built on the page's own thread, in chunks";
    D.worker.post(init);
  }

  function ask(points, closed) {
    const id = D.nextId++;
    return new Promise((resolve, reject) => {
      D.pending.set(id, { resolve, reject });
      D.worker.post({ type: "query", id, points, closed, keep: SHOWN, candidates: CANDIDATES });
    });
  }

  // --- the mode ---------------------------------------------------------------------------
  function enter(on) {
    S.drawMode = on;
    $("drawpath-panel").classList.toggle("hidden", !on);
    $("drawpath-btn").textContent = on ? "Leave path drawing" : "Draw a path";
    for (const id of ["fourbar-panel", "scene-panel", "forces-panel"]) if (on) $(id).classList.add("hidden");
    if (on) { startWorker(); $("auto").checked = false; }
    // leaving: the linkage's own view again
    P.update({ refit: !on });
    refreshPanel();
  }

  // the drawing's entry point (pointer events and tests): points in scene units
  function setPath(points, closed) {
    D.stroke = points.map(([x, y]) => [Number(x), Number(y)]);
    if (closed !== undefined) { D.closed = !!closed; $("path-" + (D.closed ? "closed" : "open")).checked = true; }
    D.results = null; D.timings = null;
    P.draw(); P.exposeState(); refreshPanel();
  }

  async function find() {
    const pts = D.stroke;
    if (pts.length < 3) { setMessage("draw a path first (press and drag on the canvas)"); return null; }
    if (!D.worker) startWorker();
    setMessage("");
    D.busy = true; refreshPanel();
    try {
      const r = await ask(pts, D.closed);
      D.results = r.results; D.timings = { ...r.timings, candidates: r.candidates, placed: r.placed };
      D.selected = 0; D.tick = 0;
      if (!r.results.length) setMessage("no linkage of the atlas fits this path: draw it again, or try open");
      fitView();
    } catch (e) {
      setMessage(e.message);
    } finally {
      D.busy = false;
    }
    P.draw(); P.exposeState(); refreshPanel();
    return D.results;
  }

  // the view: the drawing and the selected linkage's motion
  function fitView() {
    const pts = D.stroke.slice();
    const r = D.results && D.results[D.selected];
    if (r) for (let i = 0; i < r.pts.length; i += 2) if (isFinite(r.pts[i])) pts.push([r.pts[i], r.pts[i + 1]]);
    if (!pts.length) return false;
    P.fit(pts);
    return true;
  }

  // --- a design drawn in a 2D context with its own scale (the canvas or a thumbnail) ------
  function drawDesign(g, view, r, f, stroke) {
    const X = (x) => view.ox + view.s * x, Y = (y) => view.oy - view.s * y;
    const np = r.names.length, at = (name) => {
      const j = r.names.indexOf(name);
      return [r.pts[(f * np + j) * 2], r.pts[(f * np + j) * 2 + 1]];
    };
    g.lineCap = "round"; g.lineJoin = "round";
    // the drawn path, then the coupler curve
    g.strokeStyle = "#999"; g.lineWidth = 5; g.beginPath();
    stroke.forEach(([x, y], k) => (k ? g.lineTo(X(x), Y(y)) : g.moveTo(X(x), Y(y))));
    if (r.closed) g.closePath();
    g.stroke();
    const iP = r.names.indexOf("P");
    g.strokeStyle = PATH_COLOR; g.lineWidth = 1.5; g.beginPath();
    let pen = false;
    for (let i = 0; i < r.n; i++) {
      const x = r.pts[(i * np + iP) * 2], y = r.pts[(i * np + iP) * 2 + 1];
      if (r.status[i] !== 0 || !isFinite(x)) { pen = false; continue; }
      if (pen) g.lineTo(X(x), Y(y)); else g.moveTo(X(x), Y(y));
      pen = true;
    }
    g.stroke();
    const [o2, o4, a, b, p] = ["O2", "O4", "A", "B", "P"].map(at);
    const bar = (u, v, color) => { g.strokeStyle = color; g.lineWidth = 4; g.beginPath(); g.moveTo(X(u[0]), Y(u[1])); g.lineTo(X(v[0]), Y(v[1])); g.stroke(); };
    bar(o2, a, COLORS[0]);
    bar(o4, b, COLORS[2]);
    g.fillStyle = COLORS[1] + "40"; g.strokeStyle = COLORS[1]; g.lineWidth = 2;
    g.beginPath(); g.moveTo(X(a[0]), Y(a[1])); g.lineTo(X(b[0]), Y(b[1])); g.lineTo(X(p[0]), Y(p[1])); g.closePath(); g.fill(); g.stroke();
    for (const q of [o2, o4]) {
      g.fillStyle = "#555"; g.beginPath(); g.moveTo(X(q[0]), Y(q[1])); g.lineTo(X(q[0]) - 6, Y(q[1]) + 10); g.lineTo(X(q[0]) + 6, Y(q[1]) + 10); g.closePath(); g.fill();
    }
    for (const [q, fill] of [[o2, "#fff"], [o4, "#fff"], [a, "#fff"], [b, "#fff"], [p, PATH_COLOR]]) {
      g.beginPath(); g.arc(X(q[0]), Y(q[1]), 3.5, 0, 2 * Math.PI); g.fillStyle = fill; g.fill();
      g.strokeStyle = "#222"; g.lineWidth = 1; g.stroke();
    }
  }

  // the frame shown at animation tick t: along the path and back for an open one
  function frameAt(r, t) {
    const k = r.frames.length;
    if (!k) return 0;
    if (r.closed) return r.frames[t % k];
    const m = Math.max(1, 2 * (k - 1));
    const j = t % m;
    return r.frames[j < k ? j : m - j];
  }

  // the main canvas in this mode: the drawing, and the selected linkage moving along it
  function drawMode() {
    const r = D.results && D.results[D.selected];
    if (r) drawDesign(ctx, S.view, r, frameAt(r, D.tick), D.stroke);
    else if (D.stroke.length) {
      ctx.strokeStyle = "#555"; ctx.lineWidth = 3; ctx.lineCap = "round"; ctx.lineJoin = "round";
      ctx.beginPath();
      D.stroke.forEach(([x, y], k) => (k ? ctx.lineTo(sx(x), sy(y)) : ctx.moveTo(sx(x), sy(y))));
      if (D.closed && !D.drawing) ctx.closePath();
      ctx.stroke();
    } else {
      ctx.fillStyle = "#888"; ctx.font = "14px system-ui";
      ctx.fillText("press and drag to draw the path the coupler point must follow", 20, 30);
    }
  }

  // each animation frame: the linkages move on (the speed slider: frames per tick)
  function animate() {
    if (!D.results || !D.results.length) return;
    D.tick += Math.max(1, Math.round(Number($("speed").value) / 2));
    P.draw();
    D.results.forEach((r, k) => {
      const c = $("thumb-" + k);
      if (!c) return;
      const g = c.getContext("2d");
      g.clearRect(0, 0, c.width, c.height);
      drawDesign(g, thumbView(r, c), r, frameAt(r, D.tick), D.stroke);
    });
  }

  function thumbView(r, c) {
    if (r.view) return r.view;
    let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
    const add = (x, y) => { if (isFinite(x) && isFinite(y)) { x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y); } };
    for (const [x, y] of D.stroke) add(x, y);
    for (let i = 0; i < r.pts.length; i += 2) add(r.pts[i], r.pts[i + 1]);
    const m = 8, s = Math.min((c.width - 2 * m) / Math.max(x1 - x0, 1e-9), (c.height - 2 * m) / Math.max(y1 - y0, 1e-9));
    r.view = { s, ox: c.width / 2 - (s * (x0 + x1)) / 2, oy: c.height / 2 + (s * (y0 + y1)) / 2 };
    return r.view;
  }

  // --- the panel ----------------------------------------------------------------------------
  const pct = (v) => (100 * v).toFixed(v < 0.01 ? 2 : 1) + "%";

  function refreshPanel() {
    const st = $("atlas-status");
    if (!st) return;
    let t = "";
    if (D.atlas) t = `atlas: ${D.atlas.size.toLocaleString("en")} four-bars (${D.atlas.full_turn.toLocaleString("en")} with a full-turn crank), built in ${(D.atlas.ms / 1000).toFixed(1)} s ${D.where === "worker" ? "in a Web Worker" : "on the page's thread"}`;
    else if (D.progress) t = `building the atlas: ${D.progress.done.toLocaleString("en")} of ${D.progress.total.toLocaleString("en")} four-bars`;
    else if (D.worker) t = "starting the atlas";
    if (D.note) t += `\n(${D.note})`;
    if (D.busy) t += "\nfinding linkages";
    if (D.timings) t += `\nlast search: ${D.timings.total_ms.toFixed(0)} ms (${D.timings.candidates} nearest curves placed, the best ${D.results.length} shown)`;
    st.textContent = t;
    $("find-btn").disabled = D.busy;
    const list = $("path-results");
    const rs = D.results || [];
    if (list.dataset.shown === String(D.timings && D.timings.total_ms)) {
      [...list.querySelectorAll(".result")].forEach((el, k) => el.classList.toggle("chosen", k === D.selected));
      return;
    }
    list.dataset.shown = String(D.timings && D.timings.total_ms);
    list.textContent = "";
    rs.forEach((r, k) => {
      const row = document.createElement("div");
      row.className = "result" + (k === D.selected ? " chosen" : "");
      const c = document.createElement("canvas");
      c.id = "thumb-" + k; c.width = 120; c.height = 90;
      c.title = "show this linkage on the canvas";
      c.addEventListener("click", () => select(k));
      const txt = document.createElement("div");
      txt.innerHTML = `<b>#${k + 1}</b> max error ${pct(r.error.max)}, rms ${pct(r.error.rms)} of the path's size` +
        `<br><small>atlas entry ${r.row}${r.reversed ? ", crank turning back" : ""}</small><br>`;
      const open = document.createElement("button");
      open.textContent = "Open as scene"; open.id = "open-design-" + k;
      open.addEventListener("click", () => openDesign(k));
      const dl = document.createElement("button");
      dl.textContent = "JSON"; dl.title = "download the scene (pk.Scene.load reads it)"; dl.id = "save-design-" + k;
      dl.addEventListener("click", () => download(k));
      txt.append(open, dl);
      row.append(c, txt);
      list.appendChild(row);
    });
  }

  function select(k) {
    D.selected = k; D.tick = 0;
    fitView(); P.draw(); P.exposeState(); refreshPanel();
  }

  function designText(r) { return JSON.stringify(r.scene, null, 1) + "\n"; }

  function download(k) {
    const r = D.results[k];
    const a = document.createElement("a");
    a.href = URL.createObjectURL(new Blob([designText(r)], { type: "application/json" }));
    a.download = `path-design-${k + 1}.json`;
    document.body.appendChild(a); a.click(); a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }

  // the design as the current scene (the page's own scene machinery), moving
  function openDesign(k) {
    const r = D.results[k];
    enter(false);
    P.openText(designText(r), `path-design-${k + 1}.json`);
    $("auto").checked = true;
  }

  // --- drawing with the pointer ---------------------------------------------------------------
  function bindDraw() {
    $("drawpath-btn").addEventListener("click", () => enter(!S.drawMode));
    $("find-btn").addEventListener("click", () => find());
    $("clear-btn").addEventListener("click", () => { setPath([]); setMessage(""); });
    for (const k of ["closed", "open"]) {
      $("path-" + k).addEventListener("change", () => { D.closed = k === "closed"; D.results = null; D.timings = null; P.draw(); P.exposeState(); refreshPanel(); });
    }
    const here = (ev) => {
      const r = canvas.getBoundingClientRect();
      return [wx(ev.clientX - r.left), wy(ev.clientY - r.top)];
    };
    canvas.addEventListener("pointerdown", (ev) => {
      if (!S.drawMode) return;
      canvas.setPointerCapture(ev.pointerId);
      D.drawing = true;
      D.results = null; D.timings = null;
      D.stroke = [here(ev)];
      refreshPanel(); P.draw();
    });
    canvas.addEventListener("pointermove", (ev) => {
      if (!S.drawMode || !D.drawing) return;
      const p = here(ev), q = D.stroke[D.stroke.length - 1];
      // a point where the pen has moved at least a pixel
      if (Math.hypot(p[0] - q[0], p[1] - q[1]) * S.view.s >= 1) { D.stroke.push(p); P.draw(); }
    });
    const up = () => {
      if (!D.drawing) return;
      D.drawing = false;
      P.draw(); P.exposeState();
    };
    canvas.addEventListener("pointerup", up);
    canvas.addEventListener("pointercancel", up);
  }

  // what tests read in #state
  function drawState() {
    if (!S.drawMode && !D.results) return null;
    return {
      mode: !!S.drawMode,
      points: D.stroke.length, closed: D.closed, where: D.where,
      atlas: D.atlas, progress: D.progress, busy: D.busy, timings: D.timings, selected: D.selected,
      results: (D.results || []).map((r) => ({
        row: r.row, params: r.params, signs: r.signs, cost: r.cost, a: r.a, b: r.b,
        input_angle: r.input_angle, error: r.error, scene: r.scene, reversed: r.reversed,
      })),
    };
  }

  function configure(q) {
    if (q.has("atlas")) {
      const n = Math.round(Number(q.get("atlas")));
      if (n >= 100 && n <= 2000000) D.size = n;
      else setMessage(`atlas must be a number of linkages from 100 to 2000000, got '${q.get("atlas")}'`);
    }
    if (q.get("draw") === "1") enter(true);
  }

  Object.assign(P, {
    bindDraw, drawMode, animate, fitDrawing: fitView, drawState, configure, setPath, findPaths: find, enterDraw: enter,
  });
})(window.PK_PAGE);

// planarkin web, the path atlas's worker: its own instance of the module builds a small
// four-bar atlas (the core's atlas shards, kept for the page's life), then answers a drawn
// path with the best few linkages placed onto it, each as a scene with its motion.
//
// The page starts it from a Blob of this function's text (a browser refuses a worker
// script from file://), or, where no worker starts, runs the same function on the page's
// own thread, yielding between chunks. Messages in: {type: "init", wasm (bytes), size,
// seed}, {type: "query", id, points, closed, keep, candidates}; out: {type: "progress",
// done, total}, {type: "ready", size, full_turn, ms}, {type: "result", id, results,
// timings}, {type: "error", id, message}.
"use strict";

function pkAtlasWorker(scope) {
  const enc = new TextEncoder();
  const dec = new TextDecoder();
  const TOPOLOGY = "four-bar";
  const NP = 5; // four-bar parameters: r2, r3, r4, u, v
  const D = 32; // descriptor length (the core's DESCRIPTOR)
  const CHUNK = 5000; // entries a call builds, between progress reports
  const TARGET_POINTS = 100; // the drawn path resampled by arc length
  const OFFSETS = 24; // starts tried along an arc for an open path (the core's match)
  const LINKS = { ground: ["O2", "O4"], crank: ["O2", "A"], coupler: ["A", "B", "P"], rocker: ["O4", "B"] };

  let ex = null;
  function call(req) {
    const bytes = enc.encode(JSON.stringify(req));
    const p = ex.pk_alloc(bytes.length);
    new Uint8Array(ex.memory.buffer, p, bytes.length).set(bytes);
    const n = ex.pk_call(p, bytes.length);
    ex.pk_free(p, bytes.length);
    const reply = JSON.parse(dec.decode(new Uint8Array(ex.memory.buffer, ex.pk_out(), n)));
    if (reply.error) throw new Error(reply.error);
    const k = ex.pk_nums_len();
    const nums = k ? new Float64Array(ex.memory.buffer, ex.pk_nums(), k).slice() : new Float64Array(0);
    return [reply, nums];
  }
  const pause = () => new Promise((r) => setTimeout(r, 0));

  // --- the atlas: built once, kept ------------------------------------------------------
  let atlas = null; // {n, params, signs, full, desc}
  let building = null; // the promise of the build
  async function build(size, seed) {
    const t0 = performance.now();
    const a = {
      n: size, seed,
      params: new Float64Array(size * NP), signs: new Float64Array(size),
      full: new Uint8Array(size), desc: new Float32Array(size * D),
    };
    for (let start = 0; start < size; start += CHUNK) {
      const count = Math.min(CHUNK, size - start);
      const [r, nums] = call({ op: "atlas_shard", topology: TOPOLOGY, seed, start, count });
      a.params.set(nums.subarray(r.params.offset, r.params.offset + count * NP), start * NP);
      a.signs.set(nums.subarray(r.signs.offset, r.signs.offset + count), start);
      for (let i = 0; i < count; i++) a.full[start + i] = nums[r.full_turn.offset + i];
      a.desc.set(nums.subarray(r.descriptor.offset, r.descriptor.offset + count * D), start * D);
      scope.postMessage({ type: "progress", done: start + count, total: size });
      await pause();
    }
    atlas = a;
    let full = 0;
    for (let i = 0; i < size; i++) full += a.full[i];
    scope.postMessage({ type: "ready", size, full_turn: full, ms: performance.now() - t0 });
  }

  // --- a query ----------------------------------------------------------------------------
  // n points equally spaced by arc length along pts (closed: around the loop)
  function resample(pts, closed, n) {
    const m = pts.length, segs = closed ? m : m - 1, cum = [0];
    for (let i = 0; i < segs; i++) {
      const a = pts[i], b = pts[(i + 1) % m];
      cum.push(cum[i] + Math.hypot(b[0] - a[0], b[1] - a[1]));
    }
    const total = cum[segs], div = closed ? n : n - 1, out = [];
    let i = 0;
    for (let j = 0; j < n; j++) {
      const s = (total * j) / div;
      while (i + 1 < segs && cum[i + 1] < s) i++;
      const len = cum[i + 1] - cum[i], w = len > 0 ? Math.min(Math.max((s - cum[i]) / len, 0), 1) : 0;
      const a = pts[i], b = pts[(i + 1) % m];
      out.push([a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])]);
    }
    return out;
  }

  // the descriptors a query asks with (as planarkin.atlas's descriptor_variants): the path
  // and the path reversed, each with the even harmonics' sign as computed and flipped
  function variants(pts, closed) {
    const out = [];
    for (const p of [pts, pts.slice().reverse()]) {
      const [r] = call({ op: "atlas_describe", points: p, closed });
      if (!r.descriptor) throw new Error("the path has no extent (all its points at one place)");
      const d = Float64Array.from(r.descriptor);
      const flipped = d.map((v, i) => ((Math.floor(i / 4) + 1) % 2 === 0 ? -v : v));
      out.push(d, flipped);
    }
    return out;
  }

  // the k rows nearest the variants (closed: full-turn entries only), nearest first
  function nearest(qs, closed, k) {
    const { n, full, desc } = atlas;
    const rows = [], dist = [];
    for (let i = 0; i < n; i++) {
      if (closed && !full[i]) continue;
      let best = Infinity;
      for (const q of qs) {
        let s = 0;
        for (let j = 0, o = i * D; j < D; j++) { const t = desc[o + j] - q[j]; s += t * t; }
        if (s < best) best = s;
      }
      rows.push(i); dist.push(best);
    }
    const order = rows.map((_, j) => j).sort((x, y) => dist[x] - dist[y]).slice(0, k);
    return order.map((j) => rows[j]);
  }

  // the scene of an entry drawn at its input theta and carried by z -> a z + b, as
  // planarkin.synthesis.path.templates.scene_dict builds it for "four-bar"
  function sceneOf(params, signs, a, b, theta, name, description) {
    const [r] = call({ op: "atlas_pose", topology: TOPOLOGY, params, signs, theta });
    if (!r.points) return null;
    const points = {};
    r.names.forEach((nm, i) => {
      const [x, y] = r.points[i];
      points[nm] = [a[0] * x - a[1] * y + b[0], a[1] * x + a[0] * y + b[1]];
    });
    return {
      name, description, units: "target units", points, links: LINKS, ground: "ground",
      input: { link: "crank", pivot: "O2" }, output: { link: "rocker", pivot: "O4" }, outputs: ["P"],
    };
  }

  // the distance from each target point to the polyline of P over the converged frames,
  // over the target's size: {max, rms}
  function pathError(target, pts, status, np, iP, closed, size) {
    const xs = [], ys = [];
    for (let i = 0; i < status.length; i++) {
      if (status[i] !== 0) { xs.push(NaN); ys.push(NaN); continue; }
      xs.push(pts[(i * np + iP) * 2]); ys.push(pts[(i * np + iP) * 2 + 1]);
    }
    let max = 0, sum = 0;
    for (const [px, py] of target) {
      let best = Infinity;
      for (let i = 0; i + 1 < xs.length; i++) {
        const ax = xs[i], ay = ys[i], bx = xs[i + 1], by = ys[i + 1];
        if (!(isFinite(ax) && isFinite(bx))) continue;
        const dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
        const t = l2 > 0 ? Math.min(Math.max(((px - ax) * dx + (py - ay) * dy) / l2, 0), 1) : 0;
        best = Math.min(best, Math.hypot(ax + t * dx - px, ay + t * dy - py));
      }
      max = Math.max(max, best); sum += best * best;
    }
    return { max: max / size, rms: Math.sqrt(sum / target.length) / size };
  }

  async function query(msg) {
    const t0 = performance.now();
    if (building) await building;
    const t1 = performance.now();
    const closed = !!msg.closed;
    const target = resample(msg.points, closed, TARGET_POINTS);
    let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
    for (const [x, y] of msg.points) { x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y); }
    const size = Math.hypot(x1 - x0, y1 - y0);
    if (!(size > 0) || !isFinite(size)) throw new Error("the path has no extent (all its points at one place)");
    const rows = nearest(variants(target, closed), closed, msg.candidates || 200);
    const t2 = performance.now();
    const params = [], signs = [];
    for (const i of rows) { params.push(...atlas.params.subarray(i * NP, (i + 1) * NP)); signs.push(atlas.signs[i]); }
    const [m] = call({ op: "atlas_match", topology: TOPOLOGY, params, signs, target, closed, offsets: OFFSETS });
    const placed = m.placements.map((p, j) => (p ? { ...p, row: rows[j] } : null)).filter(Boolean);
    placed.sort((p, q) => p.cost - q.cost);
    const t3 = performance.now();
    // the best by placement, shown as scenes: their motion (the module's path) and true error
    const keep = msg.keep || 4, results = [];
    for (const p of placed.slice(0, 2 * keep)) {
      const i = p.row, prm = Array.from(atlas.params.subarray(i * NP, (i + 1) * NP)), sg = [atlas.signs[i]];
      const turn = Math.atan2(p.a[1], p.a[0]);
      const scene = sceneOf(prm, sg, p.a, p.b, p.theta[0], `drawn path: atlas entry ${i}`,
        `four-bar atlas entry ${i} (seed ${atlas.seed}) placed onto a drawn ${closed ? "closed" : "open"} path ` +
        "from the atlas, not refined; use `planarkin synthesize path` for refined, verified designs");
      if (!scene) continue;
      let info, path, nums;
      try {
        [info] = call({ op: "scene", scene });
        [path, nums] = call({ op: "path" });
      } catch (e) {
        continue;
      }
      const np = info.names.length, iP = info.names.indexOf("P");
      // measured on the points as drawn (the query used them resampled)
      const error = pathError(msg.points, nums, path.status, np, iP, closed, size);
      // the frames that move along the path: a closed one all the turn, an open one its arc
      const n = path.n, span = p.theta[p.theta.length - 1] - p.theta[0];
      let frames;
      if (closed) {
        frames = [...Array(n - 1).keys()];
        if (p.reversed) frames.reverse();
      } else {
        const k = Math.min(n - 1, Math.round((Math.abs(span) / (2 * Math.PI)) * (n - 1)));
        frames = [...Array(k + 1).keys()].map((j) => (p.reversed && j ? n - 1 - j : j));
      }
      frames = frames.filter((f) => path.status[f] === 0);
      results.push({
        row: i, params: prm, signs: sg, cost: p.cost, a: p.a, b: p.b, theta: p.theta, turn,
        input_angle: p.theta[0] + turn, reversed: p.reversed, fraction: p.fraction, error, scene,
        names: info.names, n, pts: nums.slice(path.offset, path.offset + n * np * 2), status: path.status,
        frames, closed,
      });
    }
    results.sort((p, q) => p.error.max - q.error.max);
    const t4 = performance.now();
    return {
      results: results.slice(0, keep), target, size,
      timings: { wait_ms: t1 - t0, retrieval_ms: t2 - t1, placement_ms: t3 - t2, scenes_ms: t4 - t3, total_ms: t4 - t1 },
      candidates: rows.length, placed: placed.length,
    };
  }

  scope.onmessage = async (ev) => {
    const msg = ev.data;
    try {
      if (msg.type === "init") {
        if (!ex) ex = (await WebAssembly.instantiate(msg.wasm, {})).instance.exports;
        if (!building) building = build(msg.size, msg.seed);
        await building;
      } else if (msg.type === "query") {
        const r = await query(msg);
        scope.postMessage({ type: "result", id: msg.id, ...r });
      }
    } catch (e) {
      scope.postMessage({ type: "error", id: msg.id, message: String(e && e.message ? e.message : e) });
    }
  };
}

// in a worker started from this file itself (a served page), start at once
if (typeof window === "undefined" && typeof self !== "undefined") pkAtlasWorker(self);

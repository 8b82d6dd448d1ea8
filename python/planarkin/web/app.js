// planarkin web: the page draws and handles input; planarkin's Rust core, compiled to
// WebAssembly (planarkin.wasm, here as wasm.js), computes everything it shows.
//
// URL parameters (docs/site/web.rst): scene=NAME (a built-in scene) or fourbar=r1,r2,r3,r4
// (the four-bar by its lengths, the default); draw=1 (the "draw a path" mode), atlas=N
// (that mode's atlas size, default 100000); file=URL (a JSON or TOML scene file, served
// pages only); theta=DEGREES (the input angle; for a scene driven by a slot
// or prismatic pair, the displacement from the drawn pose in scene units); mode=open|crossed,
// p, delta=DEGREES (four-bar); auto=1 (auto-rotate, or for a linear input auto-advance
// between the stroke's ends). What the page computed is in the text of #state as JSON:
// {"scene", "theta" (radians, or the displacement), "input_kind", "points" {name: [x, y]},
// "status", "slots" and "prismatic" (what was drawn for them), ...}.
//
// The page's scripts (index.html loads them in order, classic scripts so that file:// works)
// share window.PK_PAGE: js/core.js (the module, the state), js/view.js, js/draw.js,
// js/fourbar.js, js/scene.js, js/ui.js (a frame, the readout, #state), js/toml.js (TOML
// scene files), js/input.js (the controls), js/atlas-worker.js and js/drawpath.js ("draw
// a path": the path atlas in a Web Worker); this one starts the page and sets the hooks
// of window.pk.
"use strict";

(function (P) {
  const {
    DEG, $, call, S, linear, setMessage, loadModule, resize, update, frame, choose, bind, openText,
  } = P;

  // --- start -------------------------------------------------------------------------------------------
  async function start() {
    await loadModule();
    bind();
    P.bindDraw();
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
    P.configure(q);
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
    fps: P.fps,
    // "draw a path": set the drawing (points in scene units, closed or open), then find
    // the linkages (resolves with #state's "draw" once they are shown)
    drawPath: (points, closed) => P.setPath(points, closed),
    findPaths: () => P.findPaths().then(() => JSON.parse(document.getElementById("state").textContent).draw),
  };

  start().catch((e) => { setMessage("could not start: " + e); throw e; });
})(window.PK_PAGE);

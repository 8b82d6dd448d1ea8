// planarkin web, the controls: the linkage list, the sliders and boxes, opening and saving
// scene files, assemblies and circuits, dragging points on the canvas.
"use strict";

(function (P) {
  const {
    DEG, $, call, num, S, linear, setMessage, fmtIn, sym, canvas, sx, sy, wx, wy, fitNow, resize,
    COLORS, loadScene, shownPoints, movePoint, draw, exposeState, refreshText, update,
  } = P;

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
    // (drawing a path, the pointer draws: js/drawpath.js)
    canvas.addEventListener("pointerdown", (ev) => {
      if (S.drawMode) return;
      S.drag = hit(ev);
      if (S.drag >= 0) { canvas.setPointerCapture(ev.pointerId); draw(); }
    });
    canvas.addEventListener("pointermove", (ev) => {
      if (S.drawMode) return;
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

  const isJson = (text) => { try { JSON.parse(text); return true; } catch (e) { return false; } };

  // a scene file's text, JSON or TOML (opened from disk, or ?file=URL when served)
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
    let raw = text;
    try {
      data = P.parseSceneText(text, fname);
      // TOML goes to the module as the JSON of what it holds, JSON as its own text
      if (/\.toml$/i.test(fname) || !isJson(text)) raw = null;
    } catch (e) {
      S.sceneData = { points: {}, links: {} }; S.info = null; S.pose = null; S.path = null; S.name = fname;
      setMessage(e.message);
      refreshText(); draw(); exposeState();
      return;
    }
    const drawable = data && typeof data === "object" && !Array.isArray(data) &&
      data.points && typeof data.points === "object" && !Array.isArray(data.points) &&
      Object.values(data.points).every((v) => Array.isArray(v) && v.length === 2) &&
      data.links && typeof data.links === "object" && !Array.isArray(data.links);
    // the module checks everything (and names what is wrong); the page only draws
    const ok = loadScene(data, raw, fname);
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

  Object.assign(P, { choose, bind, openText });
})(window.PK_PAGE);

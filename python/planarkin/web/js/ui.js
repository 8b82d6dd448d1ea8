// planarkin web, a frame: solve, draw, the readout (#info, the input's slider) and the
// state exposed in #state; auto-rotate (or auto-advance) steps the input each frame.
"use strict";

(function (P) {
  const {
    DEG, $, num, S, linear, fmtDeg, units, fmtLen, fmtIn, sym, canvas, ctx, sx, sy, fitNow, grid,
    solveFourbar, drawFourbar, solveScene, shownPoints, drawScene,
  } = P;

  // --- drawing: the grid, then the four-bar or the scene ---------------------------------------
  function draw() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    ctx.clearRect(0, 0, w, h);
    if (!S.view) return;
    if ($("grid").checked) grid();
    if (S.drawMode) P.drawMode();
    else if (S.kind === "fourbar") drawFourbar(); else if (S.sceneData) drawScene();
  }

  // --- the readout and the exposed state ---------------------------------------------------------
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
        pivots: S.joints.pivots || [],
        // the effort curve drawn (a scene with loads): input values, effort (null where
        // not solved), its unit
        effort: S.forces ? { theta: S.forces.theta, input: S.forces.effort.map((v) => (isFinite(v) ? v : null)), unit: S.forces.unit } : null,
      };
    }
    // where each point is on the canvas (CSS pixels from its top left), for tests
    const shown = S.kind === "fourbar" ? Object.entries(st.points) :
      Object.keys(S.sceneData.points).map((n, i) => [n, shownPoints()[i]]);
    st.screen = Object.fromEntries(shown.filter(([, v]) => v && isFinite(num(v[0]))).map(([n, v]) => [n, [sx(v[0]), sy(v[1])]]));
    st.fps = fps;
    // drawing a path: the drawing, the atlas and the linkages found (js/drawpath.js)
    st.draw = P.drawState ? P.drawState() : null;
    $("state").textContent = JSON.stringify(st);
  }

  function refreshText() {
    $("info").innerHTML = S.drawMode ? "" : infoText();
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
    $("fourbar-panel").classList.toggle("hidden", S.kind !== "fourbar" || !!S.drawMode);
    $("scene-panel").classList.toggle("hidden", S.kind !== "scene" || !!S.drawMode);
    $("mode-" + S.mode).checked = true;
  }

  function update({ refit = false } = {}) {
    if (S.kind === "fourbar") solveFourbar(); else solveScene();
    if (refit || !S.view) fitNow();
    refreshText();
    draw();
    exposeState();
  }

  // --- auto-rotate (auto-advance): a step each frame --------------------------------------------------
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
    if (S.drawMode) P.animate();
    else if ($("auto").checked && S.drag < 0) {
      step();
      refreshText();
      draw();
      exposeState();
    }
    requestAnimationFrame(frame);
  }

  Object.assign(P, { draw, exposeState, refreshText, update, frame, fps: () => fps });
})(window.PK_PAGE);

// planarkin web, the view: the canvas, the scale from scene units to its pixels (fitted to
// what is shown), and the plane geometry the drawing shares (lines, slots' travel).
"use strict";

(function (P) {
  const { S, $, num } = P;

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
    // drawing a path: the drawing and the linkage shown on it (js/drawpath.js)
    if (S.drawMode && P.fitDrawing && P.fitDrawing()) return;
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

  Object.assign(P, {
    canvas, ctx, fit, sx, sy, wx, wy, frame2, along, across, at, pathAt, finiteXY, slotTravel, fitNow,
    resize,
  });
})(window.PK_PAGE);

// planarkin web, forces: for a scene with loads, the statics input effort over the default
// path (the module's "forces": the core's forces kernel, as Scene.statics() gives it),
// drawn live as a curve with the current input marked, and each pin's reaction drawn as
// an arrow on the linkage at the current input.
"use strict";

(function (P) {
  const { $, call, S, ctx, sx, sy, num, linear, fmtIn } = P;

  // after a scene loads: its forces, or none (no loads, or the core refused them)
  function loadForces() {
    S.forces = null;
    $("forces-panel").classList.toggle("hidden", !(S.info && S.info.loads));
    if (!S.info || !S.info.loads) return;
    const [f, nums] = call({ op: "forces" });
    if (f.error) {
      $("forces-info").textContent = f.error;
      return;
    }
    const n = f.n;
    const effort = Array.from(nums.subarray(f.effort, f.effort + n));
    const pins = f.pins.map((p) => ({ ...p, xy: nums.slice(p.offset, p.offset + 2 * n) }));
    let big = 0;
    for (const p of pins) for (let i = 0; i < n; i++) {
      const m = Math.hypot(p.xy[2 * i], p.xy[2 * i + 1]);
      if (isFinite(m) && m > big) big = m;
    }
    S.forces = { ...f, effort, pins, big };
  }

  // the path's index nearest the current input (a turn wraps)
  function nearest() {
    const th = S.forces.theta, turn = 2 * Math.PI;
    let best = 0, bd = Infinity;
    for (let i = 0; i < th.length; i++) {
      let d = Math.abs(th[i] - S.theta);
      if (!linear()) d = Math.min(d % turn, turn - (d % turn));
      if (d < bd) { bd = d; best = i; }
    }
    return best;
  }

  // the effort curve on its own canvas, the current input marked
  function drawEffort() {
    const F = S.forces;
    if (!F) return;
    const c = $("effort"), g = c.getContext("2d");
    const w = c.width, h = c.height, pad = 4;
    g.clearRect(0, 0, w, h);
    const v = F.effort.filter(isFinite);
    if (!v.length) return;
    const lo = Math.min(0, ...v), hi = Math.max(0, ...v), span = hi - lo || 1;
    const X = (i) => pad + (i * (w - 2 * pad)) / (F.n - 1);
    const Y = (y) => h - pad - ((y - lo) * (h - 2 * pad)) / span;
    g.strokeStyle = "#ccc";
    g.beginPath(); g.moveTo(pad, Y(0)); g.lineTo(w - pad, Y(0)); g.stroke();
    g.strokeStyle = "#c0392b";
    g.lineWidth = 1.5;
    g.beginPath();
    let pen = false;
    F.effort.forEach((y, i) => {
      if (!isFinite(y)) { pen = false; return; }
      if (pen) g.lineTo(X(i), Y(y)); else g.moveTo(X(i), Y(y));
      pen = true;
    });
    g.stroke();
    const i = nearest();
    g.fillStyle = "#222";
    g.fillRect(X(i) - 1, pad, 2, h - 2 * pad);
    const now = F.effort[i];
    $("forces-info").textContent =
      `input effort at ${fmtIn(F.theta[i])}: ${isFinite(now) ? now.toPrecision(5) : F.status[i]} ${F.unit}` +
      `\npeak ${Math.max(...v.map(Math.abs)).toPrecision(5)} ${F.unit}; virtual work check ${F.check.toExponential(1)}`;
  }

  // each pin's reaction at the current input, as an arrow at its joint (the longest a
  // quarter of the drawing)
  function drawArrows(pts) {
    const F = S.forces;
    if (!F || !$("arrows").checked || !(F.big > 0)) return;
    const i = nearest();
    const scale = (0.25 * S.info.size) / F.big;
    ctx.strokeStyle = "#c0392b";
    ctx.fillStyle = "#c0392b";
    ctx.lineWidth = 2;
    for (const p of F.pins) {
      const [x, y] = pts[p.point].map(num);
      const fx = p.xy[2 * i], fy = p.xy[2 * i + 1];
      if (!isFinite(x) || !isFinite(fx)) continue;
      const x0 = sx(x), y0 = sy(y), x1 = sx(x + fx * scale), y1 = sy(y + fy * scale);
      const len = Math.hypot(x1 - x0, y1 - y0);
      if (len < 1) continue;
      ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke();
      const ux = (x1 - x0) / len, uy = (y1 - y0) / len, head = Math.min(8, len / 2);
      ctx.beginPath();
      ctx.moveTo(x1, y1);
      ctx.lineTo(x1 - head * ux - 0.5 * head * uy, y1 - head * uy + 0.5 * head * ux);
      ctx.lineTo(x1 - head * ux + 0.5 * head * uy, y1 - head * uy - 0.5 * head * ux);
      ctx.closePath();
      ctx.fill();
    }
  }

  Object.assign(P, { loadForces, drawEffort, drawArrows });
})(window.PK_PAGE);

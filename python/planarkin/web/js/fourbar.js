// planarkin web, the four-bar by its lengths: solved by the module, drawn with its crank
// circle (the reachable arcs and dead points), its path and its angles.
"use strict";

(function (P) {
  const {
    $, call, num, S, setMessage, fmtDeg, ctx, sx, sy, COLORS, PATH_COLOR, polyline, groundMark,
    joint, label, bar,
  } = P;

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

  Object.assign(P, { solveFourbar, drawFourbar });
})(window.PK_PAGE);

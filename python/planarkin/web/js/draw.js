// planarkin web, the drawing's pieces: the colours, the grid, paths, bars, joints, ground
// marks, labels, and the bands and blocks of slots and prismatic pairs.
"use strict";

(function (P) {
  const { S, canvas, ctx, sx, sy, wx, wy } = P;

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

  Object.assign(P, {
    COLORS, PATH_COLOR, grid, polyline, groundMark, joint, label, bar, band, block,
  });
})(window.PK_PAGE);

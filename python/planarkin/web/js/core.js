// planarkin web, the core: the WebAssembly module (its loading and `call`), the page's
// state `S` and the helpers every other script shares. The page's scripts share one
// namespace, window.PK_PAGE, each adding its names in the order index.html loads them.
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

  // the module from its bytes in wasm.js (base64: a browser refuses to fetch from file://)
  async function loadModule() {
    const bin = atob(window.PK_WASM_BASE64);
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    const { instance } = await WebAssembly.instantiate(bytes, {});
    ex = instance.exports;
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

  // --- the message, and values as the page shows them ------------------------------
  function setMessage(m) { $("message").textContent = m; }

  const fmtDeg = (t) => (t / DEG).toFixed(2) + "\u00b0";
  const units = () => (S.sceneData && typeof S.sceneData.units === "string" ? " " + S.sceneData.units : "");
  const fmtLen = (v) => v.toFixed(2) + units();
  // the scene's input value as shown, and its symbol
  const fmtIn = (t) => (linear() ? fmtLen(t) : fmtDeg(t));
  const sym = () => (linear() ? "s" : "\u03b8");

  window.PK_PAGE = {
    DEG, $, call, loadModule, num, S, linear, setMessage, fmtDeg, units, fmtLen, fmtIn, sym,
  };
})();

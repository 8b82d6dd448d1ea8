// planarkin web, TOML scene files: a reader of the TOML a scene file uses (tables and
// dotted keys, inline tables, arrays over several lines, strings, numbers, booleans,
// comments), so the page opens a .toml file as the command line does. What it does not
// read (dates, arrays of tables) is an error naming the line, never a silent refusal.
"use strict";

(function (P) {
  class TomlError extends Error {}

  function parseToml(text) {
    let i = 0;
    const n = text.length;
    const line = () => text.slice(0, i).split("\n").length;
    const fail = (what) => { throw new TomlError(`${what} (line ${line()})`); };
    const root = {};
    const defined = new Set(); // tables opened by a [header], or closed by being a value
    let table = root;

    const ws = () => { while (i < n && (text[i] === " " || text[i] === "\t")) i++; };
    const comment = () => { if (text[i] === "#") while (i < n && text[i] !== "\n") i++; };
    // whitespace, newlines and comments (inside arrays, between statements)
    const blank = () => {
      for (;;) {
        ws(); comment();
        if (text[i] === "\n" || text[i] === "\r") i++;
        else return;
      }
    };
    const endOfLine = () => {
      ws(); comment();
      if (i < n && text[i] !== "\n" && !(text[i] === "\r" && text[i + 1] === "\n")) fail(`unexpected '${text[i]}' after a value`);
    };

    function basicString() {
      const multi = text.startsWith('"""', i);
      i += multi ? 3 : 1;
      if (multi && text[i] === "\n") i++;
      let out = "";
      for (;;) {
        if (i >= n) fail("a string is not closed");
        const c = text[i];
        if (multi ? text.startsWith('"""', i) : c === '"') { i += multi ? 3 : 1; return out; }
        if (c === "\n" && !multi) fail("a string is not closed");
        if (c === "\\") {
          const e = text[i + 1];
          const simple = { b: "\b", t: "\t", n: "\n", f: "\f", r: "\r", '"': '"', "\\": "\\" };
          if (e in simple) { out += simple[e]; i += 2; continue; }
          if (e === "u" || e === "U") {
            const k = e === "u" ? 4 : 8;
            const hex = text.slice(i + 2, i + 2 + k);
            if (!/^[0-9a-fA-F]+$/.test(hex) || hex.length !== k) fail("a bad \\u escape");
            out += String.fromCodePoint(parseInt(hex, 16)); i += 2 + k; continue;
          }
          if (multi && (e === "\n" || e === " " || e === "\t" || e === "\r")) {
            i++; while (i < n && /\s/.test(text[i])) i++; continue; // a line-ending backslash
          }
          fail(`a bad escape '\\${e}'`);
        }
        out += c; i++;
      }
    }

    function literalString() {
      const multi = text.startsWith("'''", i);
      i += multi ? 3 : 1;
      if (multi && text[i] === "\n") i++;
      const close = multi ? "'''" : "'";
      const j = text.indexOf(close, i);
      if (j < 0 || (!multi && text.slice(i, j).includes("\n"))) fail("a string is not closed");
      const out = text.slice(i, j);
      i = j + close.length;
      return out;
    }

    function key() {
      const parts = [];
      for (;;) {
        ws();
        if (text[i] === '"') parts.push(basicString());
        else if (text[i] === "'") parts.push(literalString());
        else {
          const m = /^[A-Za-z0-9_-]+/.exec(text.slice(i));
          if (!m) fail("a key is missing");
          parts.push(m[0]); i += m[0].length;
        }
        ws();
        if (text[i] !== ".") return parts;
        i++;
      }
    }

    function number() {
      const m = /^[+-]?(inf|nan|0x[0-9a-fA-F_]+|0o[0-7_]+|0b[01_]+|[0-9_]+(\.[0-9_]+)?([eE][+-]?[0-9_]+)?)/.exec(text.slice(i));
      if (!m) return undefined;
      const raw = m[0];
      if (/^\d{4}-/.test(text.slice(i, i + 5)) || /^\d{2}:/.test(text.slice(i, i + 3))) fail("dates are not part of a scene file");
      i += raw.length;
      const s = raw.replace(/_/g, "");
      const sign = s.startsWith("-") ? -1 : 1;
      const body = s.replace(/^[+-]/, "");
      if (body === "inf") return sign * Infinity;
      if (body === "nan") return NaN;
      if (/^0[xob]/.test(body)) return sign * parseInt(body.slice(2), { x: 16, o: 8, b: 2 }[body[1]]);
      return Number(s);
    }

    function value() {
      ws();
      const c = text[i];
      if (c === '"') return basicString();
      if (c === "'") return literalString();
      if (text.startsWith("true", i)) { i += 4; return true; }
      if (text.startsWith("false", i)) { i += 5; return false; }
      if (c === "[") {
        i++;
        const arr = [];
        for (;;) {
          blank();
          if (text[i] === "]") { i++; return arr; }
          arr.push(value());
          blank();
          if (text[i] === ",") { i++; continue; }
          if (text[i] === "]") { i++; return arr; }
          fail("an array needs ',' or ']'");
        }
      }
      if (c === "{") {
        i++;
        const obj = {};
        ws();
        if (text[i] === "}") { i++; return obj; }
        for (;;) {
          const k = key();
          if (text[i] !== "=") fail("'=' is missing after a key");
          i++;
          put(obj, k, value(), true);
          ws();
          if (text[i] === ",") { i++; continue; }
          if (text[i] === "}") { i++; return obj; }
          fail("an inline table needs ',' or '}'");
        }
      }
      const v = number();
      if (v === undefined) fail(`a value is missing or not one TOML reads ('${(c || "").trim()}')`);
      return v;
    }

    function put(obj, parts, v, inline) {
      let t = obj;
      for (const p of parts.slice(0, -1)) {
        if (!(p in t)) t[p] = {};
        else if (typeof t[p] !== "object" || Array.isArray(t[p]) || (inline && defined.has(t[p]))) fail(`the key '${p}' is given twice`);
        t = t[p];
      }
      const last = parts[parts.length - 1];
      if (Object.prototype.hasOwnProperty.call(t, last)) fail(`the key '${parts.join(".")}' is given twice`);
      t[last] = v;
      if (v && typeof v === "object" && !Array.isArray(v)) defined.add(v);
    }

    for (;;) {
      blank();
      if (i >= n) return root;
      if (text[i] === "[") {
        if (text[i + 1] === "[") fail("arrays of tables are not part of a scene file");
        i++;
        const parts = key();
        if (text[i] !== "]") fail("a table header needs ']'");
        i++;
        endOfLine();
        let t = root;
        parts.forEach((p, k) => {
          if (!(p in t)) t[p] = {};
          else if (typeof t[p] !== "object" || Array.isArray(t[p])) fail(`the key '${p}' is given twice`);
          else if (k === parts.length - 1 && defined.has(t[p])) fail(`the table '${parts.join(".")}' is given twice`);
          t = t[p];
        });
        defined.add(t);
        table = t;
        continue;
      }
      const parts = key();
      if (text[i] !== "=") fail("'=' is missing after a key");
      i++;
      put(table, parts, value(), false);
      endOfLine();
    }
  }

  // a scene file's text as data: JSON, or TOML by its name (a name with neither suffix is
  // tried as JSON, then as TOML); throws an Error whose message is one line
  function parseSceneText(text, fname) {
    const toml = /\.toml$/i.test(fname || "");
    const json = /\.json$/i.test(fname || "");
    if (!toml) {
      try {
        return JSON.parse(text);
      } catch (e) {
        if (json) throw new Error(`${fname} is not JSON: ${e.message}`);
      }
    }
    try {
      return parseToml(text.replace(/^\uFEFF/, ""));
    } catch (e) {
      if (e instanceof TomlError) throw new Error(`${fname} is not ${toml ? "TOML" : "JSON or TOML"}: ${e.message}`);
      throw e;
    }
  }

  Object.assign(P, { parseToml, parseSceneText });
})(window.PK_PAGE);

"""The interactive web page, as package data: ``index.html``, ``app.js`` and ``js/*.js``
(drawing and input only, classic scripts by subject), ``planarkin.wasm`` (planarkin's Rust
core compiled to WebAssembly, which computes everything the page shows; ``wasm.js`` holds
the same bytes for ``file://``) and ``scenes.js`` (the built-in scenes). ``planarkin web``
serves this folder; ``tools/build_web.sh`` rebuilds the generated files."""

from __future__ import annotations

from pathlib import Path

__all__ = ["FOLDER", "FILES"]

#: The folder holding the page (what ``planarkin web --path`` prints).
FOLDER = Path(__file__).resolve().parent
#: The files the page needs, as paths relative to ``FOLDER``.
FILES = (
    "index.html",
    "js/core.js",
    "js/view.js",
    "js/draw.js",
    "js/fourbar.js",
    "js/scene.js",
    "js/forces.js",
    "js/ui.js",
    "js/toml.js",
    "js/input.js",
    "js/atlas-worker.js",
    "js/drawpath.js",
    "app.js",
    "wasm.js",
    "scenes.js",
    "planarkin.wasm",
)

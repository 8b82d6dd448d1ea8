"""``planarkin web [SCENE]``: the interactive page (planarkin's core compiled to
WebAssembly) served from the installed package on 127.0.0.1, opened in a browser.
``--path`` prints the page's folder, which also works as a static site or from file://."""

from __future__ import annotations

import argparse
import functools
import json
import webbrowser
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from typing import Any
from urllib.parse import urlencode

from ...scene import builtin
from ...web import FILES, FOLDER
from ._common import finite, load_scene

#: Where the page finds a scene file given on the command line (served from memory).
SCENE_URL = "/_scene.json"


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``web``."""
    p = sub.add_parser(
        "web",
        help="the interactive simulator in the browser (four-bar and any scene)",
        description="Serves the interactive page (planarkin's Rust core compiled to "
        "WebAssembly: sliders, auto-rotate, tracer paths, dragging points, assemblies and "
        "circuits) on 127.0.0.1 and opens it in a browser; Ctrl-C stops. The page's folder "
        "(--path) also works as a static site or straight from file://.",
    )
    p.add_argument(
        "scene",
        nargs="?",
        metavar="SCENE",
        help="a scene file (.json/.toml) or built-in scene name to open (default: the "
        "four-bar by its lengths; see 'planarkin scenes')",
    )
    p.add_argument("--path", action="store_true", help="print the page's folder and exit")
    p.add_argument(
        "--port", type=int, default=0, help="port on 127.0.0.1 (default 0: any free port)"
    )
    p.add_argument(
        "--theta",
        type=float,
        metavar="DEG",
        help="input angle to open at (deg); for a scene driven by a slot or prismatic pair, "
        "the displacement from the drawn pose (scene units)",
    )
    p.add_argument("--no-browser", action="store_true", help="serve without opening a browser")
    p.set_defaults(func=run)
    return p


class _Handler(SimpleHTTPRequestHandler):
    """Serves the page's folder, and the command line's scene at ``SCENE_URL``; quiet."""

    def __init__(self, *args: Any, scene_json: bytes | None, **kwargs: Any) -> None:
        self.scene_json = scene_json
        super().__init__(*args, **kwargs)

    def do_GET(self) -> None:
        if self.path.split("?")[0] == SCENE_URL and self.scene_json is not None:
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(self.scene_json)))
            self.end_headers()
            self.wfile.write(self.scene_json)
            return
        super().do_GET()

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002 (the base's name)
        pass


def run(args: argparse.Namespace) -> int:
    """Prints the folder, or serves the page until Ctrl-C; returns the exit code."""
    missing = [f for f in FILES if not (FOLDER / f).is_file()]
    if missing:
        raise OSError(f"the web page is incomplete in {FOLDER}: missing {', '.join(missing)}")
    if args.path:
        print(FOLDER)
        return 0
    if not 0 <= args.port <= 65535:
        raise ValueError(f"--port must be in 0..65535, got {args.port}")
    query: dict[str, str] = {}
    scene_json = None
    if args.scene is not None:
        if args.scene in builtin.names():
            query["scene"] = args.scene
        else:
            sc = load_scene(args.scene)  # the same checks and messages as the other commands
            scene_json = json.dumps(sc.to_dict(), indent=1).encode("utf-8")
            query["file"] = SCENE_URL.lstrip("/")
    if args.theta is not None:
        query["theta"] = repr(finite("--theta", args.theta))
    handler = functools.partial(_Handler, directory=str(FOLDER), scene_json=scene_json)
    with ThreadingHTTPServer(("127.0.0.1", args.port), handler) as server:
        port = server.server_address[1]
        url = f"http://127.0.0.1:{port}/index.html" + (f"?{urlencode(query)}" if query else "")
        print(f"planarkin web: serving {FOLDER} at {url} (Ctrl-C stops)", flush=True)
        if not args.no_browser:
            webbrowser.open(url)
        server.serve_forever()
    return 0

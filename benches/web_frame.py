"""The web page's speed and size, measured in headless Chromium (what BENCHMARKS.md's
"Web page" section reports):

- one frame of Jansen's leg solved by the WebAssembly module, as the page calls it (a
  JSON request in, the pose and the full tracer path of 361 inputs out), and its parts;
- one frame of the four-bar (pose, coupler path of 361 crank angles, class, limits);
- a scene driven by a prismatic pair (the hydraulic-cylinder boom): loading it (checks,
  plan and its stroke: the 801-input probe) and one frame (pose and the 361-input path);
- the frame rate the page holds while auto-rotating (requestAnimationFrame count);
- planarkin.wasm's size, raw and gzip -9.

Usage: python benches/web_frame.py [--page DIR] [--out JSON] [--screenshots DIR]
(needs selenium, chromium and chromedriver: see tests/web/conftest.py). --screenshots
also writes web_fourbar.png, web_jansen.png and web_slider_crank.png (the README's
pictures) into DIR."""

from __future__ import annotations

import argparse
import gzip
import json
import platform
import shutil
import time
from pathlib import Path

from selenium import webdriver
from selenium.webdriver.chrome.service import Service


def _driver(width: int, height: int) -> webdriver.Chrome:
    opts = webdriver.ChromeOptions()
    opts.binary_location = shutil.which("chromium") or shutil.which("google-chrome") or ""
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
              f"--window-size={width},{height}"):  # fmt: skip
        opts.add_argument(a)
    d = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=opts)
    # the page's own size, whatever the window's decorations take
    d.execute_cdp_cmd(
        "Emulation.setDeviceMetricsOverride",
        {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False},
    )
    return d


def _open(d: webdriver.Chrome, page: Path, query: str) -> None:
    d.get(page.joinpath("index.html").as_uri() + query)
    for _ in range(200):
        if d.execute_script("return document.body.dataset.ready === '1'"):
            return
        time.sleep(0.05)
    raise RuntimeError("the page did not start")


def main() -> None:
    from planarkin.web import FOLDER

    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--page", type=Path, default=FOLDER, help="the page's folder")
    ap.add_argument("--out", type=Path, default=Path("benches/results/web.json"))
    ap.add_argument("--screenshots", type=Path, help="write the README's pictures here")
    args = ap.parse_args()
    page = args.page.resolve()

    wasm = (page / "planarkin.wasm").read_bytes()
    res: dict = {
        "wasm_bytes": len(wasm),
        "wasm_gzip_bytes": len(gzip.compress(wasm, compresslevel=9)),
        "machine": platform.processor() or platform.machine(),
        "load_before": Path("/proc/loadavg").read_text().split()[:3],
    }
    d = _driver(1280, 800)
    try:
        res["browser"] = d.capabilities.get("browserVersion")
        _open(d, page, "?scene=jansen&theta=30")
        bench = "return window.pk.bench(arguments[0], arguments[1], arguments[2]);"
        for key, req, n in (
            ("jansen_frame", {"op": "frame", "theta": 0.5}, 200),
            ("jansen_pose", {"op": "pose", "theta": 0.5}, 2000),
            ("jansen_path", {"op": "path"}, 200),
        ):
            d.execute_script(bench, req, n, 3)  # warm up
            res[key] = d.execute_script(bench, req, n, 9)
        _open(d, page, "?fourbar=6,2,5,5&theta=30")
        req = {"op": "fourbar", "r": [6, 2, 5, 5], "theta2": 0.5, "mode": "open"}
        req.update(p=3, delta=0.5)
        d.execute_script(bench, req, 200, 3)
        res["fourbar_frame"] = d.execute_script(bench, req, 200, 9)
        # a linear input: loading the scene finds its stroke; a frame spans it
        boom = json.loads(d.execute_script("return window.PK_SCENES['hydraulic-boom'];"))
        _open(d, page, "?scene=hydraulic-boom")
        for key, req, n in (
            ("boom_scene", {"op": "scene", "scene": boom}, 20),
            ("boom_frame", {"op": "frame", "theta": 100.0}, 200),
        ):
            d.execute_script(bench, req, n, 3)
            res[key] = d.execute_script(bench, req, n, 9)
        # the frame rate while auto-rotating (the page's own requestAnimationFrame count)
        for key, query in (("fps_jansen", "?scene=jansen&auto=1&speed=2"),
                           ("fps_fourbar", "?auto=1&speed=2")):  # fmt: skip
            _open(d, page, query)
            time.sleep(1.5)
            samples = []
            for _ in range(5):
                time.sleep(1.0)
                samples.append(d.execute_script("return window.pk.fps();"))
            res[key] = {"samples": samples, "min": min(samples)}
        if args.screenshots:
            args.screenshots.mkdir(parents=True, exist_ok=True)
            shots = (("web_fourbar.png", "?fourbar=6,2,5,5&theta=60&grid=1"),
                     ("web_jansen.png", "?scene=jansen&theta=30"),
                     ("web_slider_crank.png", "?scene=slider-crank&theta=30"))  # fmt: skip
            for name, query in shots:
                _open(d, page, query)
                if "grid=1" in query:
                    d.find_element("id", "grid").click()
                if "jansen" in query:  # its circuits at this input angle, drawn and listed
                    d.find_element("id", "circuits-btn").click()
                d.save_screenshot(str(args.screenshots / name))
    finally:
        d.quit()
    res["load_after"] = Path("/proc/loadavg").read_text().split()[:3]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(res, indent=1) + "\n", encoding="utf-8")
    print(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()

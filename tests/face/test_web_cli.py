"""``planarkin web``: the page's folder (--path), serving it on 127.0.0.1 (the page, the
module and a scene file given on the command line), Ctrl-C, bad arguments. The page
itself is tested in a browser in tests/web."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import urllib.request
from urllib.parse import parse_qs, urlparse

import planarkin as pk
import pytest
from planarkin.face import cli
from planarkin.web import FILES, FOLDER


def test_path_prints_the_installed_pages_folder(capsys):
    assert cli.main(["web", "--path"]) == 0
    out = capsys.readouterr().out
    assert out == f"{FOLDER}\n"
    for f in FILES:
        assert (FOLDER / f).is_file(), f
    assert (FOLDER / "planarkin.wasm").read_bytes()[:4] == b"\0asm"


def _serve(*args: str) -> tuple[subprocess.Popen, str]:
    p = subprocess.Popen(
        [sys.executable, "-m", "planarkin", "web", "--no-browser", "--port", "0", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    line = p.stdout.readline()
    assert line.startswith("planarkin web: serving "), (line, p.stderr.read() if p.poll() else "")
    return p, line.split(" at ")[1].split()[0]


def _stop(p: subprocess.Popen) -> tuple[int, str]:
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=20)
    return p.returncode, err


def test_serves_the_page_on_localhost_and_stops_on_ctrl_c():
    p, url = _serve("jansen", "--theta", "30")
    try:
        u = urlparse(url)
        assert u.hostname == "127.0.0.1" and u.path == "/index.html"
        assert parse_qs(u.query) == {"scene": ["jansen"], "theta": ["30.0"]}
        base = f"http://127.0.0.1:{u.port}/"
        with urllib.request.urlopen(url, timeout=10) as r:
            assert b"planarkin web" in r.read()
        with urllib.request.urlopen(base + "planarkin.wasm", timeout=10) as r:
            assert r.read() == (FOLDER / "planarkin.wasm").read_bytes()
    finally:
        rc, err = _stop(p)
    assert rc == 130 and err == "planarkin: interrupted\n"


@pytest.mark.slow  # a second server process (about 1 s); the one above stays in the inner loop
def test_a_scene_file_is_served_to_the_page(tmp_path):
    path = tmp_path / "leg.toml"
    pk.scenes.load("klann").save(path)
    p, url = _serve(str(path))
    try:
        u = urlparse(url)
        assert parse_qs(u.query) == {"file": ["_scene.json"]}
        with urllib.request.urlopen(f"http://127.0.0.1:{u.port}/_scene.json", timeout=10) as r:
            data = json.loads(r.read())
    finally:
        _stop(p)
    assert pk.Scene.from_dict(data) == pk.scenes.load("klann")


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["web", "nope.json", "--no-browser"], "scene file 'nope.json' does not exist"),
        (["web", "nope", "--no-browser"], "SCENE must be a .json/.toml file or a built-in name"),
        (["web", "--port", "70000", "--no-browser"], "--port must be in 0..65535, got 70000"),
        (["web", "jansen", "--theta", "nan", "--no-browser"], "--theta must be finite, got nan"),
    ],
)
def test_bad_arguments_are_one_line_and_exit_2(capsys, argv, message):
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("planarkin: error: ") and message in err and err.count("\n") == 1

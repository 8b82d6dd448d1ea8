"""``planarkin synthesize path`` and ``planarkin atlas build|info``, with the pipeline
(``planarkin.synthesis.path.path``, ``planarkin.atlas``) replaced by fakes: the target
reaches the pipeline as the file says, the options map onto its keywords, the designs are
written as scene files that ``analyze`` and ``web`` open, report.json holds what the
design says, the error figure's distances are the geometric ones (the coupler point
worked out by hand), Ctrl-C and errors leave nothing half-written."""

from __future__ import annotations

import json
import math
import shlex
import sys
import types

import numpy as np
import planarkin as pk
import planarkin.synthesis.path as path_api
import pytest
from _support import dyad_point, run_cli
from planarkin.synthesis.path.results import Defects, Design, PathError, PathResult
from planarkin.synthesis.path.targets import CurveTarget

#: the built-in four-bar (6, 2, 5, 5), coupler point 3 from A at 30 deg from A -> B
O2, O4 = np.array([0.0, 0.0]), np.array([6.0, 0.0])


def coupler_point(theta: np.ndarray) -> np.ndarray:
    """P of the built-in four-bar at crank angles ``theta``, by hand: A on the crank, B
    where the coupler and rocker circles meet (on the drawn side, left of A -> O4), P
    at 3 from A, 30 deg counter-clockwise from A -> B."""
    a = np.column_stack([2 * np.cos(theta), 2 * np.sin(theta)])
    b = dyad_point(a, 5.0, np.broadcast_to(O4, a.shape), 5.0, +1)
    u = (b - a) / 5.0
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    return a + 3 * np.column_stack([c * u[:, 0] - s * u[:, 1], s * u[:, 0] + c * u[:, 1]])


THETA = np.linspace(0.0, math.tau, 24, endpoint=False)


def _design(inputs: np.ndarray, **kw) -> Design:  # noqa: ANN003
    args = dict(
        scene=pk.scenes.load("fourbar"), tracer="P", error=PathError(2e-7, 1e-7),
        defects=Defects(False, False, False), inputs=inputs, topology="four-bar",
        min_transmission=41.5, full_turn=True, verified=True, source={"atlas_entry": 17},
    )  # fmt: skip
    args.update(kw)
    return Design(**args)


class FakePath:
    """Stands for planarkin.synthesis.path.path: records its call, reports progress and
    returns two designs (the built-in four-bar, tracer P)."""

    def __init__(self, *, designs: int = 2, stopped: str = "done", raises=None) -> None:  # noqa: ANN001
        self.calls: list = []
        self.n, self.stopped, self.raises = designs, stopped, raises

    def __call__(self, target, **kw):  # noqa: ANN001, ANN003, ANN204
        self.calls.append((target, kw))
        if kw["progress"] is not None:
            for stage in ("retrieval", "refine", "verify"):
                for k in range(4):
                    kw["progress"](stage, k + 1, 4)
        if self.raises is not None:
            raise self.raises
        worse = _design(THETA, error=PathError(3e-2, 1e-2), verified=False,
                        defects=Defects(False, True, False), source={"atlas_entry": 3})  # fmt: skip
        designs = [_design(THETA), worse][: self.n]
        return PathResult(designs, target, {"topology": kw["topology"]},
                          {"retrieval": 0.01, "refine": 0.5}, kw["seed"], self.stopped,
                          {"topology": "four-bar", "size": 1000, "seed": 0})  # fmt: skip


@pytest.fixture
def target_csv(tmp_path):
    p = tmp_path / "target.csv"
    rows = "\n".join(f"{x!r},{y!r}" for x, y in coupler_point(THETA).tolist())
    p.write_text(f"# the built-in four-bar's coupler curve\nx,y\n{rows}\n", encoding="utf-8")
    return p


@pytest.fixture
def fake(monkeypatch):
    f = FakePath()
    monkeypatch.setattr(path_api, "path", f)
    return f


def test_synthesize_path_writes_designs_report_and_figures(tmp_path, target_csv, fake):
    out = tmp_path / "out"
    code, stdout, err = run_cli("synthesize", "path", str(target_csv), "--out", str(out),
                                "--kind", "closed", "--designs", "2", "--min-transmission",
                                "30", "--seed", "7", "--time-limit", "9.5")  # fmt: skip
    assert code == 0, err
    # the target reached the pipeline as the file holds it, the options as keywords
    ((target, kw),) = fake.calls
    np.testing.assert_allclose(target.points, coupler_point(THETA), rtol=0, atol=1e-15)
    assert target.kind == "closed" and target.inputs is None
    assert kw["topology"] == "four-bar" and kw["designs"] == 2 and kw["seed"] == 7
    assert kw["min_transmission"] == 30.0 and kw["time_limit"] == 9.5
    assert kw["atlas"] is None and kw["scheduler"] is None and callable(kw["progress"])
    names = sorted(p.name for p in out.iterdir())
    assert names == ["design_1.json", "design_2.json", "error.png", "path_design_1.png",
                     "path_design_2.png", "report.json"]  # fmt: skip
    for n in names:
        if n.endswith(".png"):
            assert (out / n).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rep = json.loads((out / "report.json").read_text())
    d1, d2 = rep["designs"]
    assert d1["file"] == "design_1.json" and d1["tracer"] == "P"
    assert d1["error"] == {"max": 2e-7, "rms": 1e-7}
    assert d1["defects"] == {"circuit": False, "branch": False, "order": False}
    assert d1["inputs"] == THETA.tolist() and d1["topology"] == "four-bar"
    assert d1["min_transmission_deg"] == 41.5 and d1["full_turn"] and d1["verified"]
    assert d1["source"] == {"atlas_entry": 17}
    assert d2["defects"]["branch"] and not d2["verified"]
    assert rep["seed"] == 7 and rep["stopped"] == "done" and rep["atlas"]["size"] == 1000
    assert rep["timings"] == {"retrieval": 0.01, "refine": 0.5}
    assert rep["options"]["min_transmission"] == 30.0 and rep["options"]["kind"] == "closed"
    assert set(rep["versions"]) >= {"planarkin", "numpy", "scipy", "python"}
    assert rep["target"]["kind"] == "closed" and len(rep["target"]["points"]) == 24
    np.testing.assert_allclose(rep["target"]["points"], coupler_point(THETA), atol=1e-15)
    assert rep["command"].startswith(f"planarkin synthesize path {target_csv} --out {out} ")
    # the design files are the scene, its tracer's path followed
    sc = pk.Scene.load(out / "design_1.json")
    assert sc.points == pk.scenes.load("fourbar").points and "P" in sc.outputs
    assert "Design 1 of a path synthesis" in sc.description
    assert "design 1: four-bar, error max 2e-07" in stdout and "NOT verified" in stdout


def test_the_design_files_open_in_analyze_and_web(tmp_path, target_csv, fake, monkeypatch):
    out = tmp_path / "out"
    assert run_cli("synthesize", "path", str(target_csv), "--out", str(out), "--designs",
                   "1", "--no-figures")[0] == 0  # fmt: skip
    design = out / "design_1.json"
    code, stdout, err = run_cli("analyze", str(design), "--out", str(tmp_path / "a"),
                                "--no-figures", "--step", "15")  # fmt: skip
    assert code == 0, err
    summary = json.loads((tmp_path / "a" / "summary.json").read_text())
    assert summary  # analyze read and swept the design
    # web: the scene the page is served is the design's (the server stubbed)
    from planarkin.face.cli import web

    served = {}

    class Server:
        def __init__(self, address, handler):  # noqa: ANN001
            served["json"] = handler.keywords["scene_json"]
            self.server_address = ("127.0.0.1", 1)

        def __enter__(self):  # noqa: ANN204
            return self

        def __exit__(self, *a):  # noqa: ANN002, ANN204
            return False

        def serve_forever(self) -> None:
            pass

    monkeypatch.setattr(web, "ThreadingHTTPServer", Server)
    code, stdout, err = run_cli("web", str(design), "--no-browser")
    assert code == 0, err
    assert pk.Scene.from_dict(json.loads(served["json"])) == pk.Scene.load(design)


def test_the_command_line_reproduces_the_options():
    from planarkin.face.cli import build_parser
    from planarkin.face.cli.synthesize_path import command_line

    parse = build_parser().parse_args
    args = parse(["synthesize", "path", "my target.svg", "--kind", "partial", "--timing",
                  "--topology", "watt2", "--designs", "3", "--min-transmission", "35",
                  "--atlas", "at las", "--scheduler", "tcp://x:8786", "--seed", "4",
                  "--time-limit", "12", "--svg-samples", "80", "--format", "svg"])  # fmt: skip
    again = parse(shlex.split(command_line(args))[1:])
    for k, v in vars(args).items():
        if k not in ("func", "scheduler", "quiet", "json"):  # they do not change the files
            assert getattr(again, k) == v, k
    cmd = command_line(parse(["synthesize", "path", "t.csv"]))
    assert cmd == ("planarkin synthesize path t.csv --out path --topology four-bar --designs 5 "
                   "--seed 0 --svg-samples 64")  # fmt: skip


def test_timing_and_svg_targets_reach_the_pipeline(tmp_path, fake):
    p = tmp_path / "t.json"
    p.write_text(json.dumps({"points": [[0, 0], [1, 0], [1, 1]], "inputs_deg": [0, 45, 90]}))
    assert run_cli("synthesize", "path", str(p), "--timing", "--out", str(tmp_path / "o"),
                   "--no-figures")[0] == 0  # fmt: skip
    target, _ = fake.calls[-1]
    np.testing.assert_allclose(target.inputs, [0, math.pi / 4, math.pi / 2], atol=1e-15)
    assert target.kind == "open"
    s = tmp_path / "t.svg"
    s.write_text('<svg><path d="M 0 0 L 4 0 L 4 4 Z"/></svg>', encoding="utf-8")
    assert run_cli("synthesize", "path", str(s), "--svg-samples", "12", "--out",
                   str(tmp_path / "s"), "--no-figures", "--topology", "auto")[0] == 0  # fmt: skip
    target, kw = fake.calls[-1]
    assert target.kind == "closed" and len(target) == 12 and kw["topology"] == "auto"


def test_progress_is_drawn_per_stage_when_asked(tmp_path, target_csv, fake, monkeypatch):
    monkeypatch.setenv("PLANARKIN_PROGRESS", "1")
    code, _, err = run_cli("synthesize", "path", str(target_csv), "--out", str(tmp_path / "o"),
                           "--no-figures")  # fmt: skip
    assert code == 0
    for stage in ("retrieval", "refine", "verify"):
        assert f"planarkin synthesize path: {stage}" in err
    monkeypatch.setenv("PLANARKIN_PROGRESS", "0")
    assert run_cli("synthesize", "path", str(target_csv), "--out", str(tmp_path / "q"),
                   "--no-figures")[2] == ""  # fmt: skip


def _no_partials(folder) -> bool:  # noqa: ANN001
    return not any(p.name.endswith(".partial") for p in folder.iterdir())


def test_ctrl_c_in_the_pipeline_writes_nothing(tmp_path, target_csv, monkeypatch):
    monkeypatch.setattr(path_api, "path", FakePath(raises=KeyboardInterrupt()))
    out = tmp_path / "out"
    code, stdout, err = run_cli("synthesize", "path", str(target_csv), "--out", str(out))
    assert code == 130 and stdout == ""
    assert err == "planarkin: interrupted; nothing written\n"
    assert not out.exists()


def test_ctrl_c_while_writing_leaves_the_folder_as_it_was(tmp_path, target_csv, fake,
                                                          monkeypatch):  # fmt: skip
    from planarkin.face.figures import path as figures

    out = tmp_path / "out"
    out.mkdir()
    (out / "design_1.json").write_text("earlier", encoding="utf-8")

    def ctrl_c(*a):  # noqa: ANN002, ANN202
        raise KeyboardInterrupt

    monkeypatch.setattr(figures, "error", ctrl_c)  # the last file drawn
    code, _, err = run_cli("synthesize", "path", str(target_csv), "--out", str(out))
    assert code == 130 and err == "planarkin: interrupted; nothing written\n"
    assert [p.name for p in out.iterdir()] == ["design_1.json"]
    assert (out / "design_1.json").read_text() == "earlier"
    assert _no_partials(tmp_path)


def test_an_interrupted_run_writes_the_designs_it_has(tmp_path, target_csv, monkeypatch):
    monkeypatch.setattr(path_api, "path", FakePath(designs=1, stopped="interrupted"))
    out = tmp_path / "out"
    code, _, err = run_cli("synthesize", "path", str(target_csv), "--out", str(out),
                           "--no-figures")  # fmt: skip
    assert code == 130
    assert err == f"planarkin: interrupted: wrote the 1 designs found so far to {out}\n"
    assert json.loads((out / "report.json").read_text())["stopped"] == "interrupted"


def test_no_design_writes_nothing(tmp_path, target_csv, monkeypatch):
    monkeypatch.setattr(path_api, "path", FakePath(designs=0, stopped="time limit"))
    out = tmp_path / "out"
    code, _, err = run_cli("synthesize", "path", str(target_csv), "--out", str(out))
    assert code == 1 and err == "planarkin: no design found (time limit); nothing written\n"
    assert not out.exists()


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--designs", "0"], "--designs must be >= 1, got 0"),
        (["--min-transmission", "95"], "--min-transmission must be in [0, 90) deg, got 95.0"),
        (["--min-transmission", "nan"], "--min-transmission must be in [0, 90) deg, got nan"),
        (["--time-limit", "0"], "--time-limit must be finite and > 0 seconds, got 0.0"),
        (["--svg-samples", "2"], "--svg-samples must be >= 3, got 2"),
        (["--atlas", "no/such/dir"], "--atlas 'no/such/dir' is not a folder"),
        (["--timing"], "timing asked for, but"),
        (["--kind", "round"], "invalid choice: 'round'"),
    ],
)
def test_bad_options_are_one_line_errors(target_csv, fake, args, words):
    code, stdout, err = run_cli("synthesize", "path", str(target_csv), *args)
    assert code == 2 and stdout == ""
    assert words in err and err.count("\n") == 1 and err.startswith("planarkin: error: ")
    assert not fake.calls


def test_ackermann_is_still_a_synthesis_problem():
    from planarkin.face.cli import build_parser

    args = build_parser().parse_args(["synthesize", "ackermann", "--starts", "3"])
    assert args.problem == "ackermann" and args.starts == 3
    assert args.func.__module__ == "planarkin.face.cli.synthesize"


# --- atlas build / info ------------------------------------------------------------------


class FakeAtlas:
    def __init__(self, manifest: dict) -> None:
        self.manifest = manifest


@pytest.fixture
def atlas_api(monkeypatch):
    calls: list = []
    mod = types.ModuleType("planarkin.atlas")

    def build(topology, size, out, *, seed=0, scheduler=None, shard_size=None, progress=None):  # noqa: ANN001, ANN202
        calls.append((topology, size, out, seed, scheduler, shard_size))
        for k in range(3):
            if progress is not None:
                progress(k + 1, 3)
        if size == 13:
            raise KeyboardInterrupt
        return FakeAtlas({"topology": topology, "size": size, "seed": seed, "shards": 3,
                          "version": 1})  # fmt: skip

    def open_(folder):  # noqa: ANN001, ANN202
        calls.append(("open", folder))
        return FakeAtlas({"topology": "four-bar", "size": 5000, "seed": 2, "version": 1,
                          "shards": list(range(10))})  # fmt: skip

    mod.build, mod.open = build, open_
    monkeypatch.setitem(sys.modules, "planarkin.atlas", mod)
    return calls


def test_atlas_build_maps_its_options(tmp_path, atlas_api, monkeypatch):
    monkeypatch.setenv("PLANARKIN_PROGRESS", "1")
    out = tmp_path / "at"
    code, stdout, err = run_cli("atlas", "build", "--topology", "watt2", "--size", "5000",
                                "--out", str(out), "--seed", "3", "--shard-size", "500",
                                "--scheduler", "tcp://127.0.0.1:8786")  # fmt: skip
    assert code == 0, err
    assert atlas_api == [("watt2", 5000, str(out), 3, "tcp://127.0.0.1:8786", 500)]
    assert stdout.startswith(f"planarkin atlas build: 5000 watt2 linkages in {out} (")
    assert "planarkin atlas build" in err  # the bar over the shards


def test_atlas_build_ctrl_c_says_how_to_resume(tmp_path, atlas_api):
    out = tmp_path / "at"
    code, _, err = run_cli("atlas", "build", "--topology", "four-bar", "--size", "13",
                           "--out", str(out))  # fmt: skip
    assert code == 130
    assert err == (f"planarkin: interrupted; the atlas in {out} is incomplete (3 finished "
                   "shards kept): run the same command again to resume\n")  # fmt: skip


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--size", "0"], "--size must be >= 1, got 0"),
        (["--size", "9", "--shard-size", "0"], "--shard-size must be >= 1, got 0"),
        (["--size", "9", "--topology", "auto"], "invalid choice: 'auto'"),
    ],
)
def test_atlas_build_bad_options(tmp_path, atlas_api, args, words):
    argv = ["atlas", "build", "--topology", "four-bar", "--out", str(tmp_path), *args]
    code, _, err = run_cli(*argv)
    assert code == 2 and words in err and err.count("\n") == 1 and not atlas_api


def test_atlas_info_prints_the_manifest(tmp_path, atlas_api):
    code, stdout, _ = run_cli("atlas", "info", str(tmp_path))
    assert code == 0 and atlas_api == [("open", str(tmp_path))]
    assert "topology  four-bar" in stdout and "shards    (10 items)" in stdout
    code, stdout, _ = run_cli("atlas", "info", str(tmp_path), "--json")
    assert json.loads(stdout)["size"] == 5000
    code, _, err = run_cli("atlas", "info", str(tmp_path / "none"))
    assert code == 2 and "does not exist" in err


# --- figures -----------------------------------------------------------------------------


def test_the_error_along_the_target_is_the_distance_to_the_tracer():
    from planarkin.face.figures import path as figures

    exact = CurveTarget(coupler_point(THETA), "closed")
    d = _design(THETA)
    # the tracer at the design's inputs is the coupler point worked out by hand
    np.testing.assert_allclose(figures.distances(exact, d), 0.0, atol=1e-12)
    shift = np.array([0.03, -0.04])  # 0.05 off every point
    moved = CurveTarget(coupler_point(THETA) + shift, "closed")
    np.testing.assert_allclose(figures.distances(moved, d), 0.05 / moved.size, rtol=1e-9)
    fig = figures.error(moved, [d])
    (line,) = fig.axes[0].get_lines()
    loop = np.vstack([moved.points, moved.points[:1]])
    chords = np.hypot(*np.diff(loop, axis=0).T)
    want = np.concatenate([[0.0], np.cumsum(chords)[:-1]]) / chords.sum()
    np.testing.assert_allclose(line.get_xdata(), want, rtol=1e-12)
    np.testing.assert_allclose(line.get_ydata(), 0.05 / moved.size, rtol=1e-9)
    # the design figure: the whole coupler curve is the hand-worked one
    curve = figures.coupler_curve(d, 73)
    np.testing.assert_allclose(curve, coupler_point(np.linspace(0, math.tau, 73)), atol=1e-9)


@pytest.mark.slow  # a child process (about 1 s)
def test_a_real_ctrl_c_exits_130_with_one_line(tmp_path, target_csv):
    import signal
    import subprocess
    import textwrap

    out = tmp_path / "out"
    code = textwrap.dedent(f"""
        import sys, time
        import planarkin.synthesis.path as api
        from planarkin.face.cli import main

        def slow(target, **kw):
            sys.stderr.write("ready\\n"); sys.stderr.flush()
            time.sleep(60)

        api.path = slow
        sys.exit(main(["synthesize", "path", {str(target_csv)!r}, "--out", {str(out)!r}]))
    """)
    p = subprocess.Popen([sys.executable, "-c", code], stderr=subprocess.PIPE, text=True)
    assert p.stderr.readline() == "ready\n"
    p.send_signal(signal.SIGINT)
    err = p.communicate(timeout=30)[1]
    assert p.returncode == 130 and err == "planarkin: interrupted; nothing written\n"
    assert not out.exists()

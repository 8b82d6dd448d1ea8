"""Progress bars and messages (issue 20, items 8, 10-13): bars quiet in a pipe and with
--quiet, drawn when forced; circuits explained and reachable inputs named; scene results
state their speed and units; one step is "1 step"; a built-in scene exported to start
from."""

from __future__ import annotations

import json

import numpy as np
import planarkin as pk
import pytest
from planarkin.face import cli, progress
from planarkin.face.cli import circuits
from planarkin.scene import report

ANIMATE = ["animate", "fourbar", "--frames", "3", "--dpi", "20"]


def test_progress_is_quiet_in_a_pipe(tmp_path, capsys, monkeypatch):
    monkeypatch.delenv(progress.ENV, raising=False)
    assert not progress.shown()  # pytest's stderr is not a terminal
    assert cli.main([*ANIMATE, "--out", str(tmp_path)]) == 0
    assert capsys.readouterr().err == ""


@pytest.mark.slow  # two animations drawn: about 1 s on 2 cores
def test_progress_is_drawn_when_forced_and_never_with_quiet(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv(progress.ENV, "1")
    assert cli.main([*ANIMATE, "--out", str(tmp_path)]) == 0
    err = capsys.readouterr().err
    assert "planarkin animate" in err and "frame" in err  # what it shows is timing-bound
    assert cli.main([*ANIMATE, "--out", str(tmp_path), "--quiet"]) == 0
    assert capsys.readouterr().err == ""
    monkeypatch.setenv(progress.ENV, "0")
    assert not progress.shown()


@pytest.mark.parametrize(
    "argv",
    [
        ["analyze", "jansen", "--no-figures", "--step", "30"],
        ["circuits", "fourbar", "--no-figures"],
        ["tradeoff", "--tols", "1e-6", "--methods", "closed-form", "--random", "2",
         "--truth-links", "1", "--points", "13", "--repeat", "1", "--no-plot"],
    ],
)  # fmt: skip
def test_every_long_command_has_a_bar(argv, tmp_path, capsys, monkeypatch):
    monkeypatch.setenv(progress.ENV, "1")
    monkeypatch.chdir(tmp_path)
    assert cli.main([*argv, "--out", str(tmp_path)] if argv[0] != "tradeoff" else argv) == 0
    assert f"planarkin {argv[0]}" in capsys.readouterr().err


def test_circuits_at_an_input_out_of_reach_names_the_reachable_inputs(tmp_path, capsys):
    sc = pk.scenes.load("double-butterfly-1")
    assert len(sc.assemblies(np.pi)) == 0
    out = tmp_path / "c"
    assert cli.main(["circuits", "double-butterfly-1", "--theta", "180", "--out", str(out),
                     "--dpi", "30", "-q"]) == 0  # fmt: skip
    text = capsys.readouterr().out
    assert "no assembly at theta = 180.000 deg" in text
    s = json.loads((out / "circuits.json").read_text())
    assert s["circuits"] == [] and s["reachable_deg"]
    for lo, hi in s["reachable_deg"]:
        for d in (lo, 0.5 * (lo + hi), hi):  # assemblable inside each range named
            assert len(sc.assemblies(np.radians(d))) > 0
        for d in (lo - circuits.REACH_STEP_DEG, hi + circuits.REACH_STEP_DEG):
            assert len(sc.assemblies(np.radians(d))) == 0  # and not beyond its ends
    fig_text = (out / "circuits.png").stat().st_size
    assert fig_text > 1000


def test_circuits_explain_their_words(tmp_path, capsys):
    assert cli.main(["circuits", "jansen", "--out", str(tmp_path), "--no-figures", "-q"]) == 0
    text = capsys.readouterr().out
    assert "6 circuits" in text
    for word in ("A circuit", "turning point", "label", "--theta"):
        assert word in text
    s = json.loads((tmp_path / "circuits.json").read_text())
    assert s["glossary"] == circuits.GLOSSARY
    for c in s["circuits"]:
        assert all(-180 < v <= 180 for v in c["turning_points_deg"])


def test_scene_sweep_carries_omega_and_accelerations_into_the_csv():
    sc = pk.scenes.load("fourbar")
    sw = sc.sweep(outputs="all", omega=2.0)
    assert sw.omega == 2.0 and sw.accelerations is not None
    cols = report.columns(sw, "mm")
    assert "B_ax [mm/s^2]" in cols and "B_vx [mm/s]" in cols and "B_x [mm]" in cols
    assert "rocker_alpha [rad/s^2]" in cols and "rocker_omega [rad/s]" in cols
    still = sc.sweep(outputs="all")
    assert still.omega is None and still.accelerations is None
    assert "B_ax [mm/s^2]" not in report.columns(still, "mm")


def test_one_step_is_singular():
    sw = pk.scenes.load("fourbar").sweep(outputs=["B"])
    assert len(sw.plan) == 1
    assert "1 step," in repr(sw) and "1 steps" not in repr(sw)


def test_export_a_built_in_scene_to_start_from(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["scenes", "--export", "klann"]) == 0
    assert pk.Scene.load(tmp_path / "klann.json") == pk.scenes.load("klann")
    assert cli.main(["scenes", "--export", "jansen", "--to", "j.toml"]) == 0
    assert pk.Scene.load(tmp_path / "j.toml") == pk.scenes.load("jansen")
    capsys.readouterr()
    assert cli.main(["scenes", "--export", "jansen", "--to", "j.toml"]) == 2
    assert "exists" in capsys.readouterr().err
    assert cli.main(["scenes", "--export", "jansen", "--to", "j.toml", "--force"]) == 0
    assert cli.main(["scenes", "--export", "nosuch"]) == 2
    assert "unknown built-in scene 'nosuch'" in capsys.readouterr().err


def test_progress_under_a_zero_column_terminal_keeps_a_fixed_width(monkeypatch):
    """A pseudo-terminal that says it has 0 columns: the bar falls back to a fixed width
    (tqdm draws nothing at 0) (issue 32, item 10)."""
    import fcntl
    import os
    import pty
    import select
    import struct
    import sys
    import termios

    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 0, 0, 0))
    assert os.get_terminal_size(slave).columns == 0
    tty = os.fdopen(slave, "w")
    try:
        monkeypatch.setattr(sys, "stderr", tty)
        monkeypatch.setenv(progress.ENV, "1")
        with progress.bar(10, "zero", unit="step") as b:
            b.update(4)
            b.refresh()
            tty.flush()
            got = b""
            while select.select([master], [], [], 0.5)[0]:
                got += os.read(master, 65536)
                if b"4/10" in got:
                    break
        text = got.decode("utf-8", "replace")
        assert "planarkin zero" in text and "4/10" in text, text
        # the fixed width: the bar's line fills it (tqdm pads to ncols)
        line = text.replace("\r", "\n").strip("\n").split("\n")[-1]
        assert len(line) == progress.FALLBACK_COLUMNS, repr(line)
    finally:
        tty.close()
        os.close(master)

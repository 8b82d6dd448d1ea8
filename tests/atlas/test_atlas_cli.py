"""`planarkin atlas build` and `atlas info` for real: the files the kernel's columns make,
and a real Ctrl-C that leaves an incomplete atlas the same command then finishes, keeping
the shards already written."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time

import numpy as np
import planarkin as pk
import pytest
from planarkin import _kernel as k
from planarkin.face.cli import main

pytest.importorskip("pyarrow")


def test_build_then_info(tmp_path, capsys):
    out = tmp_path / "atlas"
    args = ["atlas", "build", "--topology", "slider-crank", "--size", "1500", "--out", str(out)]
    assert main([*args, "--shard-size", "500", "--seed", "3", "--scheduler", "synchronous"]) == 0
    capsys.readouterr()
    assert main(["atlas", "info", str(out), "--json"]) == 0
    manifest = json.loads(capsys.readouterr().out)
    assert manifest["complete"] and manifest["size"] == 1500 and manifest["seed"] == 3
    a = pk.atlas.open(out)
    p, s, full, cond, d = k.atlas_shard("slider-crank", 3, 0, 1500)
    np.testing.assert_array_equal(a.params, p)
    np.testing.assert_array_equal(a.descriptor, d)


@pytest.mark.slow  # a child process building for about a second, then the rest
def test_ctrl_c_leaves_an_atlas_the_same_command_finishes(tmp_path):
    out = tmp_path / "atlas"
    cmd = [sys.executable, "-m", "planarkin", "atlas", "build", "--topology", "four-bar",
           "--size", "400000", "--shard-size", "20000", "--out", str(out),
           "--scheduler", "synchronous", "-q"]  # fmt: skip
    p = subprocess.Popen(cmd, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not list(out.glob("shard-*.parquet")) and time.monotonic() < deadline:
        time.sleep(0.05)
    p.send_signal(signal.SIGINT)
    err = p.communicate(timeout=60)[1]
    assert p.returncode == 130, err
    assert "again" in err and err.count("\n") == 1
    manifest = json.loads((out / "manifest.json").read_text())
    assert not manifest["complete"]
    kept = {f.name: f.stat().st_mtime_ns for f in out.glob("shard-*.parquet")}
    assert 0 < len(kept) < 20
    assert not list(out.glob("*.tmp"))
    assert subprocess.run(cmd, check=False).returncode == 0
    assert {f: (out / f).stat().st_mtime_ns for f in kept} == kept
    a = pk.atlas.open(out)
    np.testing.assert_array_equal(a.descriptor[-5:], k.atlas_shard("four-bar", 0, 399995, 5)[4])

"""``planarkin forces``: the table, forces.csv read back with the csv module against the
Python API, units in its header, the figures, and one-line refusals."""

from __future__ import annotations

import csv
import json

import numpy as np
import planarkin as pk
import pytest
from planarkin.face import cli


def _csv(path):
    with path.open(newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array(rows[1:], dtype=float)


def test_forces_csv_matches_the_api(tmp_path, capsys):
    assert cli.main(["forces", "engine", "--out", str(tmp_path), "-q", "--no-figures"]) == 0
    out = capsys.readouterr().out
    assert "peak input" in out and "check: virtual work" in out and "pin A on rod" in out
    head, data = _csv(tmp_path / "forces.csv")
    assert head[:3] == ["theta [deg]", "status", "input [N*mm]"]
    assert "F_A_rod_x [N]" in head and "N_piston [N]" in head
    r = pk.scenes.load("engine").statics()
    np.testing.assert_allclose(data[:, 0], np.degrees(r.theta), rtol=1e-15)
    np.testing.assert_allclose(data[:, 2], r.input, rtol=1e-15)
    np.testing.assert_allclose(
        data[:, head.index("F_A_rod_y [N]")], r.reactions[("A", "rod")][:, 1]
    )
    summary = json.loads((tmp_path / "forces.json").read_text())
    assert summary["kind"] == "statics" and summary["checks"]["virtual_work"] < 1e-12


def test_forces_dynamics_and_a_linear_input(tmp_path, capsys):
    assert cli.main(["forces", "engine", "--rpm", "3000", "--out", str(tmp_path), "-q",
                     "--no-figures", "--json"]) == 0  # fmt: skip
    summary = json.loads(capsys.readouterr().out)
    assert summary["kind"] == "dynamics" and summary["checks"]["energy"] < 1e-12
    assert cli.main(["forces", "hydraulic-boom-loaded", "--speed", "50", "--out",
                     str(tmp_path), "-q", "--no-figures"]) == 0  # fmt: skip
    head, _ = _csv(tmp_path / "forces.csv")
    assert head[0] == "s [mm]" and head[2] == "input [N]"


@pytest.mark.slow
def test_forces_figures(tmp_path):
    assert cli.main(["forces", "jansen-loaded", "--out", str(tmp_path), "-q",
                     "--pin", "C:lower", "--at", "90"]) == 0  # fmt: skip
    for name in ("input_effort.png", "reactions.png", "pin_polar.png", "forces_drawn.png"):
        assert (tmp_path / name).stat().st_size > 1000


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["forces", "jansen"], "has no 'loads'"),
        (["forces", "hydraulic-boom-loaded", "--rpm", "10"], "--rpm needs an angle input"),
        (["forces", "engine", "--speed", "10"], "--speed needs a linear input"),
        (["forces", "engine", "--pin", "Q:rod"], "--pin must be one of"),
    ],
)
def test_forces_refusals_are_one_line(tmp_path, capsys, argv, message):
    assert cli.main([*argv, "--out", str(tmp_path), "-q"]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1

"""Path results written as files: scene files read back by Scene.load, report.json read
back by json (strict: no NaN), everything or nothing in the folder (an error while
writing leaves it as it was; design files of an earlier run are removed)."""

from __future__ import annotations

import json
import math

import numpy as np
import planarkin as pk
import pytest
from planarkin.synthesis.path import results
from planarkin.synthesis.path.results import Defects, Design, PathError, PathResult
from planarkin.synthesis.path.targets import CurveTarget

TARGET = CurveTarget([[0.0, 0.0], [3.0, 0.0], [3.0, 4.0]], "open")


def _design(**kw) -> Design:  # noqa: ANN003
    args = dict(scene=pk.scenes.load("fourbar"), tracer="P", error=PathError(0.01, 0.005),
                defects=Defects(False, False, True), inputs=[0.0, 0.5, 1.0])  # fmt: skip
    args.update(kw)
    return Design(**args)


def test_a_design_is_plain_data_with_a_checked_tracer():
    d = _design()
    assert d.inputs.dtype == np.float64 and not d.inputs.flags.writeable
    assert d.defects.any and not d.verified and math.isnan(d.min_transmission)
    with pytest.raises(ValueError, match="tracer 'Q' is not a point of the scene"):
        _design(tracer="Q")


def test_write_gives_scene_files_and_a_strict_report(tmp_path):
    res = PathResult([_design(), _design(topology="slider-crank")], TARGET, {"designs": 2},
                     {"refine": 1.25}, 3, "time limit", {"size": 10})  # fmt: skip
    paths = res.write(tmp_path / "out", command="planarkin synthesize path t.csv")
    assert [p.name for p in paths] == ["design_1.json", "design_2.json", "report.json"]
    for p in paths[:2]:
        assert pk.Scene.load(p).points == pk.scenes.load("fourbar").points
    text = (tmp_path / "out" / "report.json").read_text()
    rep = json.loads(text, parse_constant=lambda c: pytest.fail(f"{c} in report.json"))
    assert [d["file"] for d in rep["designs"]] == ["design_1.json", "design_2.json"]
    assert rep["designs"][0]["min_transmission_deg"] is None  # NaN: not measured
    assert rep["designs"][0]["defects"] == {"circuit": False, "branch": False, "order": True}
    assert rep["designs"][1]["topology"] == "slider-crank"
    assert rep["target"] == {"points": [[0, 0], [3, 0], [3, 4]], "kind": "open",
                             "inputs": None, "size": 5.0, "length": 7.0}  # fmt: skip
    assert (rep["seed"], rep["stopped"], rep["timings"], rep["atlas"]) == (
        3,
        "time limit",
        {"refine": 1.25},
        {"size": 10},
    )
    assert rep["command"] == "planarkin synthesize path t.csv"
    assert rep["versions"]["planarkin"] == pk.__version__
    assert res.best is res.designs[0] and res.verified == []


def test_an_error_while_writing_leaves_the_folder_as_it_was(tmp_path, monkeypatch):
    out = tmp_path / "out"
    PathResult([_design(), _design(), _design()], TARGET).write(out)
    before = {p.name: p.read_bytes() for p in out.iterdir()}

    def broken(self, **kw):  # noqa: ANN001, ANN003, ANN202
        raise KeyboardInterrupt

    monkeypatch.setattr(PathResult, "report", broken)  # report.json is written last
    with pytest.raises(KeyboardInterrupt):
        PathResult([_design()], TARGET).write(out)
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]  # no staging folder left
    monkeypatch.undo()
    # a run with fewer designs removes the earlier run's extra design files
    PathResult([_design()], TARGET).write(out)
    assert sorted(p.name for p in out.iterdir()) == ["design_1.json", "report.json"]


def test_staged_moves_the_report_last(tmp_path, monkeypatch):
    moved = []
    real = results.os.replace

    def record(a, b):  # noqa: ANN001, ANN202
        moved.append(b.name)
        real(a, b)

    monkeypatch.setattr(results.os, "replace", record)
    PathResult([_design(), _design()], TARGET).write(tmp_path / "o")
    assert moved == ["design_1.json", "design_2.json", "report.json"]

"""``planarkin tradeoff`` and its figure (planarkin.face.cli.tradeoff,
planarkin.face.figures.tradeoff): the printed table, the plot and JSON it saves, bad
options, and labels that do not overprint. The study itself is tested in
fourbar/test_tradeoff.py. No timing assertions.
"""

from __future__ import annotations

import argparse
import json

import pytest
from _support import tradeoff_rows
from planarkin.face.cli import tradeoff as tr_cli
from planarkin.face.figures import tradeoff as tr_fig
from planarkin.fourbar import tradeoff as tr


def _parse(*argv: str) -> argparse.Namespace:
    p = argparse.ArgumentParser()
    tr_cli.add_arguments(p)
    return p.parse_args(argv)


def test_cli_prints_the_table_and_saves_plot_and_json(tmp_path, capsys):
    png, js = tmp_path / "t.png", tmp_path / "t.json"
    args = _parse(
        "--tols",
        "1e-4,1e-10",
        "--methods",
        "tangent,closed-form",
        "--random",
        "1",
        "--truth-links",
        "1",
        "--repeat",
        "1",
        "--points",
        "91",
        "--plot",
        str(png),
        "--json",
        str(js),
    )
    assert tr_cli.run(args) == 0
    out = capsys.readouterr().out
    assert "Newton + tangent" in out and "closed form" in out and "ns/pt" in out
    assert png.stat().st_size > 1000 and png.read_bytes()[:4] == b"\x89PNG"
    data = json.loads(js.read_text())
    assert [r["method"] for r in data["rows"]] == ["tangent", "tangent", "closed-form"]
    assert data["n_points"] == 91 and data["n_links"] == 2


def test_cli_markdown_no_plot_and_bad_options(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    args = _parse(
        "--tols",
        "1e-6",
        "--methods",
        "quadratic",
        "--random",
        "0",
        "--truth-links",
        "1",
        "--repeat",
        "1",
        "--points",
        "37",
        "--no-plot",
        "--markdown",
    )
    assert tr_cli.run(args) == 0
    assert "| Newton + quadratic | 1e-06 |" in capsys.readouterr().out
    assert not list(tmp_path.iterdir())
    for bad in (("--tols", "0"), ("--tols", "x"), ("--methods", "nope"), ("--repeat", "0")):
        with pytest.raises(SystemExit):
            _parse(*bad)


# --- the plot ------------------------------------------------------------------------------


def _result(rows):
    return tr.TradeoffResult(tr._mark_pareto(rows), "open", 3, 361, 2, 100, 1, 0.1)


def test_plot_labels_do_not_overprint_and_ticks_are_plain_numbers():
    """Tolerance labels near the 1e-15 rad floor do not overprint (no two drawn labels'
    extents overlap; nearby tolerances share one label 'a..b'), and a time axis spanning
    less than a decade has plain-number ticks ('40', not '4x10^1')."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Annotation

    tols = [10.0**-k for k in range(3, 16)]
    rows = []
    for m, scale in (("previous", 1.0), ("tangent", 0.8), ("quadratic", 0.7)):
        times = [scale * (30 + 2 * k) for k in range(13)]
        errs = [max(10.0**-k, 4.4e-13) * (1 + 0.01 * k) for k in range(3, 16)]  # a floor
        rows += tradeoff_rows(times, errs, tols, m)
    rows += tradeoff_rows([20.0], [2.2e-16], [None], "closed-form")
    fig = tr_fig.figure(_result(rows))
    FigureCanvasAgg(fig).draw()
    ax = fig.axes[0]
    shown = [t for t in ax.texts if isinstance(t, Annotation) and t.get_visible()]
    assert shown
    boxes = [t.get_window_extent() for t in shown]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            assert not a.overlaps(b)
    # every tolerance is named, alone or in a range "1e-12..1e-15"
    assert any(".." in t.get_text() for t in shown)
    ticks = [t.get_text() for t in ax.get_xticklabels() + ax.get_yticklabels() if t.get_text()]
    assert ticks
    assert not [t for t in ticks if "times" in t or "^" in t or "×" in t], ticks
    assert any(t == "40" for t in (x.get_text() for x in ax.get_xticklabels(minor=True)))

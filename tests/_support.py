"""Helpers that more than one test folder needs and that use planarkin (the independent
truth, which must not, is in truth.py): reading a scene's output rotation from the scene
solver, hand-made rows of the speed/accuracy table, and Ctrl-C sent to a child process
in the middle of a kernel call."""

from __future__ import annotations

import contextlib
import io
import math
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import planarkin as pk
from planarkin.fourbar import tradeoff as tr


def circles(p, rp, q, rq):  # noqa: ANN001, ANN201
    """Both intersections of circle (p, rp) and circle (q, rq), arrays of points (N, 2):
    (left of p -> q, right of p -> q); NaN where the circles do not meet."""
    u = q - p
    d = np.hypot(u[..., 0], u[..., 1])
    a = (rp * rp - rq * rq + d * d) / (2 * d)
    with np.errstate(invalid="ignore"):
        h = np.sqrt(rp * rp - a * a)
    m = p + (a / d)[..., None] * u
    n = np.stack([-u[..., 1], u[..., 0]], -1) / d[..., None]
    return m + h[..., None] * n, m - h[..., None] * n


def dyad_point(p, rp, q, rq, side):  # noqa: ANN001, ANN201
    """The intersection of circles (p, rp) and (q, rq) on ``side`` of p -> q (+1 left)."""
    left, right = circles(p, rp, q, rq)
    return left if side > 0 else right


def out_rotation(sc: pk.Scene, phi: np.ndarray) -> np.ndarray:
    """The output link's rotation from the drawn pose, read from swept points."""
    link, pivot = sc.output
    first = next(p for p in sc.links[link] if p != pivot)
    sw = sc.sweep(sc.input_angle + phi, outputs=[first], tol=1e-12)
    assert np.all(sw.status == 0)
    p0, q0 = np.array(sc.points[pivot]), np.array(sc.points[first])
    v = sw.points[first] - p0
    a = np.arctan2(v[:, 1], v[:, 0]) - math.atan2(*(q0 - p0)[::-1])
    return np.angle(np.exp(1j * a))


def drawn_texts(fig, dpi: float) -> list[tuple[str, object]]:
    """Every non-empty, visible Text that matplotlib draws in ``fig`` at ``dpi`` (recorded
    as it draws them: tick labels beyond the view are not drawn), with its window extent."""
    from unittest import mock

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    fig.set_dpi(dpi)
    canvas = FigureCanvasAgg(fig)
    drawn: list = []
    draw = Text.draw

    def record(self, renderer):
        drawn.append(self)
        return draw(self, renderer)

    with mock.patch.object(Text, "draw", record):
        canvas.draw()
    r = canvas.get_renderer()
    return [
        (t.get_text(), t.get_window_extent(r))
        for t in drawn
        if t.get_visible() and t.get_text().strip()
    ]


def texts_outside(fig, dpi: float) -> list[str]:
    """Every text drawn (:func:`drawn_texts`) whose window extent leaves the figure after a
    draw at ``dpi`` (1 px of slack for antialiasing)."""
    return _outside(fig, drawn_texts(fig, dpi))


def texts_overlapping(fig, dpi: float) -> list[tuple[str, str]]:
    """Pairs of drawn texts (:func:`drawn_texts`) whose extents overlap by more than a
    pixel each way: text written over text."""
    return _overlapping(drawn_texts(fig, dpi))


def text_faults(fig, dpi: float) -> tuple[list[str], list[tuple[str, str]]]:
    """:func:`texts_outside` and :func:`texts_overlapping` from one draw at ``dpi`` (a
    draw costs a constrained layout: the scene figure tests would pay it twice)."""
    texts = drawn_texts(fig, dpi)
    return _outside(fig, texts), _overlapping(texts)


def _outside(fig, texts) -> list[str]:
    box = fig.bbox
    return [
        text
        for text, e in texts
        if e.x0 < box.x0 - 1 or e.y0 < box.y0 - 1 or e.x1 > box.x1 + 1 or e.y1 > box.y1 + 1
    ]


def _overlapping(texts) -> list[tuple[str, str]]:
    out = []
    for i, (a, ea) in enumerate(texts):
        for b, eb in texts[i + 1 :]:
            w = min(ea.x1, eb.x1) - max(ea.x0, eb.x0)
            h = min(ea.y1, eb.y1) - max(ea.y0, eb.y0)
            if w > 1 and h > 1:
                out.append((a, b))
    return out


def examples(n: int) -> int:
    """A property test's ``max_examples``: ``n``, or a quarter of it in the inner loop
    (``pytest -m "not slow"``, as conftest.py records it); the full run keeps all ``n``."""
    return max(1, n // 4) if os.environ.get("PLANARKIN_TESTS_INNER_LOOP") == "1" else n


def tradeoff_rows(times, errs, tols, method="quadratic"):
    """Rows of the speed/accuracy table with the given times, errors and tolerances."""
    from planarkin.fourbar.tradeoff import Row

    label = tr.METHODS[method][0]
    return [
        Row(method, label, tol, 1.0, 1.0, t, e, e, e, 0)
        for t, e, tol in zip(times, errs, tols, strict=True)
    ]


def interrupted_child(setup: str, call: str, *, wait: float = 0.0) -> tuple[int, str, str]:
    """Runs ``setup`` then ``call`` in a fresh Python process, sends it SIGINT ``wait``
    seconds after ``setup`` is done, and returns (exit code, stdout, stderr). The child
    prints "finished" if ``call`` returns. The 60 s guard only stops a hang: the calls
    given take far longer than that when not interrupted."""
    ready, finished = "print('ready', flush=True)", "print('finished', flush=True)"
    code = "\n".join([textwrap.dedent(setup), ready, call, finished])
    p = subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        assert p.stdout is not None
        assert p.stdout.readline().strip() == "ready"
        time.sleep(wait)
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
            p.communicate()
    return p.returncode, out, err


def run_cli(*argv: str) -> tuple[int, str, str]:
    """Runs ``planarkin argv`` in-process: (exit code, stdout, stderr)."""
    from planarkin.face import cli

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = cli.main(list(argv))
        except SystemExit as e:  # argparse
            code = e.code if isinstance(e.code, int) else 1
    return code, out.getvalue(), err.getvalue()

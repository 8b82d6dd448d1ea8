"""Helpers that more than one test folder needs and that use planarkin (the independent
truth, which must not, is in truth.py): reading a scene's output rotation from the scene
solver, hand-made rows of the speed/accuracy table, and Ctrl-C sent to a child process
in the middle of a kernel call."""

from __future__ import annotations

import contextlib
import io
import math
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import planarkin as pk
from planarkin.fourbar import tradeoff as tr


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

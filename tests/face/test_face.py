"""The one face: ``analyze`` and ``animate`` take the four-bar's options or a SCENE, and a
four-bar option given with a SCENE is an error (never silently dropped); Ctrl-C ends any
command with one line and exit code 130, and stops synthesis workers at once."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest
from _support import run_cli as run

NOT_FOR_A_SCENE = [
    (("analyze", "jansen", "--links", "6", "2", "5", "5"), "--links does not apply to a scene"),
    (("analyze", "jansen", "--mode", "crossed"), "--mode does not apply to a scene"),
    (("analyze", "jansen", "--predictor", "tangent"), "--predictor does not apply to a scene"),
    (("analyze", "jansen", "--coupler", "1", "0"), "--coupler does not apply to a scene"),
    (("analyze", "jansen", "--newton-at", "30"), "--newton-at does not apply to a scene"),
    (
        ("analyze", "fourbar", "--mode", "open", "--links", "6", "2", "5", "5"),
        "--links, --mode do not apply to a scene",
    ),  # fmt: skip
    (("animate", "klann", "--links", "6", "2", "5", "5"), "--links does not apply to a scene"),
    (("animate", "klann", "--coupler", "3", "30"), "--coupler does not apply to a scene"),
    (("animate", "klann", "--predictor", "previous"), "--predictor does not apply to a scene"),
]


@pytest.mark.parametrize(("argv", "message"), NOT_FOR_A_SCENE, ids=" ".join)
def test_a_fourbar_option_with_a_scene_is_an_error(argv, message, tmp_path):
    """A four-bar option with a SCENE ('analyze jansen --links 6 2 5 5') is a one-line error
    that names the options, exit code 2, nothing written: never dropped in silence."""
    out_dir = tmp_path / "out"
    code, out, err = run(*argv, "--out", str(out_dir))
    assert code == 2 and out == ""
    assert err.startswith(f"planarkin: error: {message} ") and err.count("\n") == 1, err
    assert not out_dir.exists()  # nothing written


def test_the_same_options_are_fine_for_the_fourbar(tmp_path):
    code, _, err = run("analyze", "--links", "6", "2", "5", "5", "--mode", "crossed",
                       "--predictor", "tangent", "--coupler", "1", "0", "--newton-at", "30",
                       "--no-figures", "--out", str(tmp_path))  # fmt: skip
    assert code == 0, err


def test_animate_takes_no_crank_speed(tmp_path):
    """An animation has no crank speed: --rpm is an unrecognised argument (one line, exit
    code 2), not an option accepted and ignored."""
    code, out, err = run("animate", "--rpm", "50", "--out", str(tmp_path))
    assert code == 2 and out == ""
    assert err.startswith("planarkin: error: unrecognized arguments: --rpm")
    assert err.count("\n") == 1


# --- Ctrl-C ------------------------------------------------------------------------------


def _start(argv: list[str]) -> subprocess.Popen:
    """``planarkin argv`` in a child process, returned once its command is running."""
    code = textwrap.dedent(
        f"""
        import sys
        from planarkin.face.cli import main
        print("ready", flush=True)
        sys.exit(main({argv!r}))
        """
    )
    p = subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert p.stdout is not None and p.stdout.readline().strip() == "ready"
    return p


def _interrupt(p: subprocess.Popen, within: float) -> tuple[str, str, float]:
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=60)  # a hang guard, not the timing assertion
    finally:
        if p.poll() is None:
            p.kill()
            p.communicate()
    took = time.monotonic() - t0
    assert took < within, f"took {took:.1f} s to stop"
    return out, err, took


def _children(pid: int) -> list[int]:
    out = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == pid and fields[0] != "Z":
                out.append(int(entry))
    return out


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.slow  # a fresh process, a second of work, then the interrupt: 2 s
@pytest.mark.skipif(os.name != "posix", reason="sends SIGINT")
def test_ctrl_c_is_one_line_and_exit_130(tmp_path):
    # the mpmath truth of 400 linkages takes about a minute: interrupted after a second
    p = _start(["tradeoff", "--random", "500", "--truth-links", "400", "--repeat", "1",
                "--no-plot", "--json", str(tmp_path / "t.json")])  # fmt: skip
    time.sleep(1.0)
    out, err, _ = _interrupt(p, within=5.0)
    assert p.returncode == 130
    assert err == "planarkin: interrupted\n" and out == ""


@pytest.mark.slow  # two worker processes started and run 1.5 s before the interrupt: 2-3 s
@pytest.mark.skipif(not os.path.isdir("/proc"), reason="finds the worker processes in /proc")
def test_ctrl_c_stops_synthesis_workers_at_once(tmp_path):
    """Ctrl-C while two worker processes run synthesis starts: within 5 s one line and exit
    code 130, nothing written, and no worker left alive (read from /proc), rather than the
    pool finishing its running and queued starts (some 20 s here) first."""
    # (24 starts: with starts that stop once they stall, 6 ran to the end in about 4 s)
    p = _start(["synthesize", "ackermann", "--starts", "24", "--samples", "300",
                "--maxiter", "200", "--workers", "2", "--no-tolerance", "--no-figures",
                "--out", str(tmp_path / "syn")])  # fmt: skip
    workers: list[int] = []
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and len(workers) < 2:
            time.sleep(0.1)
            workers = _children(p.pid)
        assert len(workers) >= 2, "the worker processes never started"
        time.sleep(1.5)  # the starts are running
        assert p.poll() is None
        out, err, _ = _interrupt(p, within=5.0)
        assert p.returncode == 130
        # one line: that it was interrupted, and what (if anything) was written: nothing,
        # or where starts had finished (they stop once they stall: under a second each on
        # an idle machine), the best feasible design so far, complete
        assert err.startswith("planarkin: interrupted") and err.count("\n") == 1, err
        if "wrote the best feasible design so far" in err:
            assert (tmp_path / "syn" / "design.json").is_file()
        else:
            assert not (tmp_path / "syn").exists()
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline and any(_alive(w) for w in workers):
            time.sleep(0.05)
        assert not [w for w in workers if _alive(w)], "a worker outlived the command"
    finally:  # whatever failed, leave no process of ours behind
        if p.poll() is None:
            p.kill()
            p.communicate()
        for w in workers:
            if _alive(w):
                os.kill(w, signal.SIGKILL)

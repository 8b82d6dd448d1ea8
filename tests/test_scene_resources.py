"""Scene calls that can run long answer Ctrl-C (SIGINT) with KeyboardInterrupt, in a
fresh process too (NumPy's C API is loaded at import, so a signal pending at the first
array is an ordinary KeyboardInterrupt), and a trace that outgrows memory is a
MemoryError, not an aborted process."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap

import pytest

#: Calls that run for minutes on double-butterfly-2 (measured: the traces and the group
#: sweep take tens of minutes at these steps; 1000 assemblies about 30 s).
SLOW = {
    "assemblies": "[sc.assemblies() for _ in range(10**4)]",
    "trace": "sc.trace(step=1e-7, max_points=10**9)",
    "circuits": "sc.circuits(step=1e-7, max_points=10**9)",
    "group sweep": "sc.sweep(max_step=1e-9)",
}


@pytest.mark.skipif(os.name != "posix", reason="sends SIGINT")
@pytest.mark.parametrize("call", list(SLOW))
def test_ctrl_c_interrupts_a_long_scene_call(call):
    """The first kernel call of a fresh process, interrupted: KeyboardInterrupt, never a
    PanicException (the hang guard of 60 s is not a timing assertion: the call itself
    takes far longer)."""
    code = textwrap.dedent(
        f"""
        import planarkin as pk
        sc = pk.scenes.load("double-butterfly-2")
        print("ready", flush=True)
        {SLOW[call]}
        print("finished", flush=True)
        """
    )
    p = subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        assert p.stdout is not None
        assert p.stdout.readline().strip() == "ready"
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
            p.communicate()
    assert "finished" not in out
    assert p.returncode != 0
    assert err.rstrip().splitlines()[-1] == "KeyboardInterrupt", err
    assert "PanicException" not in err


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS")
def test_a_trace_that_outgrows_memory_is_a_memory_error():
    """A trace asked for 10^12 points at a step that never lets it close, under a 1 GiB
    address-space limit: the kernel grows the trace fallibly and says MemoryError with
    the sizes (the process ends normally)."""
    code = textwrap.dedent(
        """
        import resource
        import planarkin as pk
        sc = pk.scenes.load("fourbar")
        resource.setrlimit(resource.RLIMIT_AS, (2**30, 2**30))
        try:
            sc.trace(step=1e-9, max_points=10**12)
        except MemoryError as e:
            print("MemoryError:", e)
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=240)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("MemoryError: trace: "), out.stdout
    assert "points of 5 scene points each" in out.stdout

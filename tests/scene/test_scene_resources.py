"""Scene calls that can run long answer Ctrl-C (SIGINT) with KeyboardInterrupt, in a
fresh process too (NumPy's C API is loaded at import, so a signal pending at the first
array is an ordinary KeyboardInterrupt), and a trace that outgrows memory is a
MemoryError, not an aborted process."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import pytest
from _support import interrupted_child

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
    """The first kernel call of a fresh process, interrupted as soon as it starts:
    KeyboardInterrupt, never a PanicException."""
    setup = "import planarkin as pk\nsc = pk.scenes.load('double-butterfly-2')"
    code, out, err = interrupted_child(setup, SLOW[call])
    assert "finished" not in out
    assert code != 0
    assert err.rstrip().splitlines()[-1] == "KeyboardInterrupt", err
    assert "PanicException" not in err


@pytest.mark.slow
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

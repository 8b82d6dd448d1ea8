"""Resources of the four-bar kernels: outputs too large for memory raise MemoryError
naming the sizes instead of aborting the process, and long kernel calls answer Ctrl-C
(SIGINT) with KeyboardInterrupt. (The command's limit on --step: face/test_cli.py.)"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import numpy as np
import planarkin as pk
import pytest
from _support import interrupted_child
from truth import SEED_LINKAGE

# --- memory ------------------------------------------------------------------------------------


def test_batch_too_large_for_memory_raises_memory_error():
    """1000 linkages x 10^8 crank angles: 2.9 TB of outputs. A MemoryError that names the
    sizes, which a caller can catch, not a failed allocation that aborts the process
    ('memory allocation of 800000000000 bytes failed', exit 134)."""
    links = np.full((1000, 4), SEED_LINKAGE)
    theta2 = np.zeros(10**8)
    with pytest.raises(MemoryError, match=r"1000 x 100000000"):
        pk.sweep_batch(links, theta2=theta2)
    with pytest.raises(MemoryError, match=r"1000 x 100000000"):
        pk.closed_form_batch(links, theta2)


def test_batch_too_large_does_not_abort_the_process():
    """The same in a child process: it ends normally (exit 0), not with SIGABRT."""
    code = textwrap.dedent(
        """
        import numpy as np, planarkin as pk
        try:
            pk.sweep_batch(np.full((1000, 4), [6, 2, 5, 5.0]), theta2=np.zeros(10**8))
        except MemoryError as e:
            print("MemoryError:", e)
        """
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("MemoryError: sweep_batch: 5 output arrays of 1000 x 100000000")


# --- Ctrl-C ------------------------------------------------------------------------------------

#: Kernel calls that run for minutes: tol 1e-300 is never met (the residual does not reach
#: exactly 0) from the guess (1, 2), nor at theta2 = 3.6 (from the previous point, then
#: from the closed form), so each attempt takes all 4294967295 iterations: tens of seconds
#: for the solve, far longer for the others.
SLOW = {
    "solve": "fb.solve(0.5, tol=1e-300, max_iter=4294967295, guess=(1, 2))",
    "sweep": "fb.sweep([0.5, 3.6], tol=1e-300, max_iter=4294967295)",
    "sweep_batch": "pk.sweep_batch(np.full((4, 4), [6, 2, 5, 5.0]), [0.5, 3.6], "
    "tol=1e-300, max_iter=4294967295, threads=2)",
    "sweep_batch_global_pool": "pk.sweep_batch(np.full((4, 4), [6, 2, 5, 5.0]), [0.5, 3.6], "
    "tol=1e-300, max_iter=4294967295)",
}


#: A fresh process each, interrupted half a second into its call (about 1 s on 2 cores): a
#: single call and a batch on its own threads in the inner loop, the other two left out of it
INNER_LOOP = ("solve", "sweep_batch")


@pytest.mark.skipif(os.name != "posix", reason="sends SIGINT")
@pytest.mark.parametrize(
    "call", [c if c in INNER_LOOP else pytest.param(c, marks=pytest.mark.slow) for c in SLOW]
)
def test_ctrl_c_interrupts_a_long_kernel_call(call):
    """A child process starts a kernel call that would run for minutes; SIGINT must end
    it with KeyboardInterrupt."""
    setup = "import numpy as np, planarkin as pk\nfb = pk.FourBar(6, 2, 5, 5)"
    code, out, err = interrupted_child(setup, SLOW[call], wait=0.5)  # let the call start
    assert "finished" not in out
    assert code != 0
    assert err.rstrip().splitlines()[-1] == "KeyboardInterrupt", err

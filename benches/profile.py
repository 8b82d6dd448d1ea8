"""Where the time goes: runs one workload under ``valgrind --tool=callgrind`` and prints
the instructions per solved point of the functions that matter (instruction counts do
not depend on what else the machine is doing, unlike timings on a shared 2-core box).

    python benches/profile.py seed          # fb.sweep() of the seed linkage, 361 angles
    python benches/profile.py seed_cf       # fb.sweep(predictor="closed-form"), 361 angles
    python benches/profile.py batch         # sweep_batch, 200 random linkages, 1 thread
    python benches/profile.py closed_form   # closed_form_batch, 200 linkages, 1 thread
    python benches/profile.py numpy_cf      # the NumPy vectorized closed form, same batch
    python benches/profile.py group         # double-butterfly-1's sweep (a 6x6 group), 361 angles
    python benches/profile.py group_near    # the same, 361 angles within 20 deg (all converge)
    python benches/profile.py jansen        # Jansen's leg, the foot requested, 361 angles
    python benches/profile.py slider30      # the slider-crank's piston, a turn from 30 deg away

For cycles rather than instructions: ``perf record -g python benches/profile.py batch --run 20``
then ``perf report --no-children``.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPS = 5
M = 200
#: kind -> (points one call solves, repetitions per REPS: short calls repeat more)
KINDS = {
    "seed": (361, 100),
    "seed_cf": (361, 100),
    "batch": (M * 361, 1),
    "closed_form": (M * 361, 1),
    "numpy_cf": (M * 361, 1),
    "group": (361, 10),
    "group_near": (361, 10),
    "jansen": (361, 100),
    "slider30": (361, 100),
}


def workload(kind: str, reps: int) -> None:
    """Runs the workload ``reps`` times after one warm-up."""
    import numpy as np
    import planarkin as pk
    from planarkin.fourbar.tradeoff import random_crank_rockers
    from planarkin.reference import closed_form_vectorized

    links = np.vstack([[6.0, 2.0, 5.0, 5.0], random_crank_rockers(M - 1, seed=2024)])
    fb = pk.FourBar(6.0, 2.0, 5.0, 5.0)
    cols = [links[:, k : k + 1] for k in range(4)]
    db = pk.scenes.load("double-butterfly-1")
    db_theta = db.input_angle + np.radians(np.arange(361.0))
    db_near = db.input_angle + np.radians(np.linspace(-20.0, 20.0, 361))
    jansen = pk.scenes.load("jansen")
    j_theta = jansen.input_angle + np.radians(np.arange(361.0))
    slider = pk.scenes.load("slider-crank")
    s_theta = slider.input_angle + np.radians(np.arange(361.0) + 30.0)
    calls = {
        "seed": lambda: fb.sweep(),
        "seed_cf": lambda: fb.sweep(predictor="closed-form"),
        "batch": lambda: pk.sweep_batch(links, threads=1),
        "closed_form": lambda: pk.closed_form_batch(links, threads=1),
        "numpy_cf": lambda: closed_form_vectorized(*cols, pk.DEFAULT_THETA2),
        "group": lambda: db.sweep(db_theta),
        "group_near": lambda: db.sweep(db_near, outputs="all"),
        "jansen": lambda: jansen.sweep(j_theta, outputs=["foot"]),
        "slider30": lambda: slider.sweep(s_theta, outputs=["B"]),
    }
    fn = calls[kind]
    fn()
    for _ in range(reps):
        fn()


def _profile(kind: str, reps: int, tmp: str) -> dict[str, int]:
    """Instructions per function (exclusive) of a whole run of ``reps`` repetitions."""
    out = os.path.join(tmp, f"cg.{reps}.out")
    cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
           sys.executable, __file__, kind, "--run", str(reps)]  # fmt: skip
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}  # idle BLAS threads spin otherwise
    subprocess.run(cmd, capture_output=True, text=True, check=True, env=env)
    ann = subprocess.run(["callgrind_annotate", "--inclusive=no", "--threshold=100", out],
                         capture_output=True, text=True, check=True).stdout  # fmt: skip
    fns: dict[str, int] = {}
    for line in ann.splitlines():
        m = re.match(r"\s*([\d,]+) \(\s*[\d.]+%\)\s+(.*)", line)
        if m:
            name = m.group(2).split(" [")[0]
            name = name.split(":", 1)[1] if re.match(r"^[./?]", name) and ":" in name else name
            fns[name] = fns.get(name, 0) + int(m.group(1).replace(",", ""))
    return fns


def callgrind(kind: str) -> None:
    """Profiles 1 and 1 + REPS repetitions and prints the difference per point, so the
    interpreter start-up, imports and warm-up cancel out."""
    per, factor = KINDS[kind]
    reps = REPS * factor
    with tempfile.TemporaryDirectory() as tmp:
        base = _profile(kind, 1, tmp)
        full = _profile(kind, 1 + reps, tmp)
    points = per * reps
    diff = {k: v - base.get(k, 0) for k, v in full.items()}
    total = diff.pop("PROGRAM TOTALS", sum(diff.values()))
    print(
        f"{kind}: {total / points:.0f} instructions per point ({reps} repetitions of {per} points)"
    )
    print(f"{'Ir/point':>9}  {'share':>6}  function (exclusive)")
    for name, ir in sorted(diff.items(), key=lambda kv: -kv[1]):
        if ir / points < 1:
            break
        print(f"{ir / points:9.0f}  {100 * ir / total:5.1f}%  {name[:110]}")


if __name__ == "__main__":
    args = sys.argv[1:]
    if not args or args[0] not in KINDS:
        print(__doc__)
        sys.exit(2)
    if "--run" in args:
        workload(args[0], int(args[args.index("--run") + 1]) if len(args) > 2 else REPS)
    else:
        callgrind(args[0])

"""Writes the built-in scenes' JSON files (python/planarkin/scene/builtin/*.json), a
maintainer's script kept out of the wheel: ``python tools/make_scenes.py``.

Published linkages are assembled from their link lengths by circle intersections; the
six- and eight-bars whose geometry is ours come from seeded random searches near a
starting design, judged by the NumPy scene reference. Every scene is checked (consistent,
mobility 1, its range swept by the reference) and the checks are printed. The scenes
themselves are made in tools/scenemakers/, by family; this script checks and writes them.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from planarkin import Status
from planarkin._kernel import SCENE_KEYS
from planarkin.reference import scene as ref
from scenemakers.geometry import DEG, motion
from scenemakers.linkages import chebyshev_lambda, fourbar, jansen, klann, peaucellier, watt2
from scenemakers.loaded import LOADED
from scenemakers.searched import double_butterfly_scene, stephenson3
from scenemakers.sliders import SLIDERS

#: Where the built-in scenes live (package data of planarkin.scene.builtin).
HERE = Path(__file__).resolve().parents[1] / "python" / "planarkin" / "scene" / "builtin"


def check_slider(name, scene):
    """Prints and asserts: the kernel loads it (mobility 1, regular as drawn) and sweeps its
    default range; the NumPy reference has no sliders, so the tests hold the closed forms."""
    import planarkin as pk

    points = {k: [float(v[0]), float(v[1])] for k, v in scene["points"].items()}
    sc = pk.Scene.from_dict({**scene, "points": points})
    sw = sc.sweep()
    # a linear input's default range ends at its dead points: SINGULAR there if met exactly
    ends_ok = all(st in (Status.CONVERGED, Status.SINGULAR) for st in sw.status[[0, -1]])
    ok = bool(sw.success[1:-1].all()) and ends_ok
    rng = f"{sw.theta[0]:+.4f} to {sw.theta[-1]:+.4f} {'rad' if sw.input == 'angle' else 'mm'}"
    print(
        f"{name:24s} mobility {sc.mobility}  plan {[s.kind for s in sc.plan('all')]}  {rng}  "
        f"sweep converged {ok}"
    )
    assert sc.mobility == 1 and ok, name


def check(name, scene, lo=None, hi=None):
    """Prints and asserts: consistent, mobility 1, the range swept by the reference."""
    err = ref.scene_assemble_check(scene)
    mob = ref.scene_mobility(scene)
    if lo is None:
        lo, hi, full, w = motion(scene)
    else:
        full = hi - lo >= 2 * math.pi
        w = float("nan")
    t0 = ref._System(scene).theta0
    if full:
        th = t0 + np.arange(361) * DEG
    else:  # inside the range, 0.5 deg clear of its ends
        th = t0 + np.linspace(lo + 0.5 * DEG, hi - 0.5 * DEG, 361)
    sw = ref.scene_sweep(scene, th)
    ok = bool(np.all(sw.status == Status.CONVERGED))
    print(
        f"{name:20s} assemble {err:.1e}  mobility {mob}  drawn {t0 / DEG:9.4f} deg  "
        f"range [{lo / DEG:+9.4f}, {hi / DEG:+9.4f}] deg from drawn "
        f"({'full turn' if full else f'{(hi - lo) / DEG:.4f} deg'})  sweep converged {ok} "
        f"max nit {sw.nit.max()}  min rcond {w:.2e}"
    )
    assert err < 1e-12 and mob == 1 and ok, name
    return lo, hi, full


def write(name, scene):
    order = SCENE_KEYS  # the scene format's keys (the core's), in the order the files list them
    out = {k: scene[k] for k in order if k in scene}
    out["points"] = {k: [float(v[0]), float(v[1])] for k, v in scene["points"].items()}
    rows = []
    for key, value in out.items():
        if key in ("points", "links"):  # one entry a line
            inner = ",\n".join(f"    {json.dumps(k)}: {json.dumps(v)}" for k, v in value.items())
            rows.append(f"  {json.dumps(key)}: {{\n{inner}\n  }}")
        else:
            rows.append(f"  {json.dumps(key)}: {json.dumps(value)}")
    text = "{\n" + ",\n".join(rows) + "\n}\n"
    assert json.loads(text) == out
    (HERE / f"{name}.json").write_text(text)


def check_loaded(name, scene):
    """Prints and asserts: the kernel loads it, its sweep converges where its base's does,
    and its statics and dynamics (at 1 turn or stroke per second) close their checks."""
    import planarkin as pk

    sc = pk.Scene.from_dict(scene)
    sw = sc.sweep(outputs="all", rate=1.0)
    st = sc.statics(sw)
    dy = sc.dynamics(sw, omega=2 * math.pi if sc.input_kind == "angle" else 1.0)
    print(f"{name:24s} statics check {st.check:.1e}  dynamics check {dy.check:.1e}  "
          f"peak input {st.peak_input:.4g} / {dy.peak_input:.4g}")  # fmt: skip
    assert st.check < 1e-10 and dy.check < 1e-10, name


def main(only=()):
    """Writes every built-in scene, or only those named (``python tools/make_scenes.py
    whitworth scotch-yoke``; ``sliders`` names the slider scenes, ``loaded`` those with
    loads)."""
    if only == ("loaded",):
        for name, make in LOADED.items():
            sc = make()
            check_loaded(name, sc)
            write(name, sc)
        return
    if only:
        names = set(SLIDERS) if "sliders" in only else set(only)
        for name in sorted(names):
            if name not in SLIDERS:
                raise SystemExit(f"only the slider scenes can be made alone: {', '.join(SLIDERS)}")
            sc = SLIDERS[name]()
            check_slider(name, sc)
            write(name, sc)
        return
    made = {
        "fourbar": fourbar(),
        "watt2": watt2(),
        "jansen": jansen(),
        "klann": klann(),
        "peaucellier": peaucellier(),
        "chebyshev-lambda": chebyshev_lambda(),
    }
    made["stephenson3"], *_ = stephenson3()
    for kind in (1, 2):
        made[f"double-butterfly-{kind}"] = double_butterfly_scene(kind)
    print()
    for name, sc in sorted(made.items()):
        check(name, sc)
        write(name, sc)
    for name, make in SLIDERS.items():
        sc = make()
        check_slider(name, sc)
        write(name, sc)
        made[name] = sc
    for name, make in LOADED.items():
        sc = make()
        check_loaded(name, sc)
        write(name, sc)
        made[name] = sc
    print(f"wrote {len(made)} scenes to {HERE}")


if __name__ == "__main__":
    import sys

    main(tuple(sys.argv[1:]))

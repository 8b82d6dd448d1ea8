"""What the commands write of a force analysis: the CSV's columns (units in brackets) and
the table's figures (peak and RMS effort, each pin's peak, the checks). Plain data from a
:class:`Forces`; the commands that print or write them import this leaf."""

from __future__ import annotations

import numpy as np

from ._results import Forces

__all__ = ["columns", "totals"]


def columns(r: Forces) -> tuple[list[str], list[np.ndarray]]:
    """The CSV's header (units in brackets) and its columns."""
    f, L = r.units["force"] or "force", r.units["length"] or "length"
    e = r.effort_unit
    head = ["theta [deg]" if r.input_kind == "angle" else f"s [{L}]", "status",
            f"input [{e}]", f"input_virtual_work [{e}]"]  # fmt: skip
    x = np.degrees(r.theta) if r.input_kind == "angle" else r.theta
    cols = [x, r.status.astype(int), r.input, r.input_virtual_work]
    for (joint, link), v in r.reactions.items():
        head += [f"F_{joint}_{link}_x [{f}]", f"F_{joint}_{link}_y [{f}]"]
        cols += [v[:, 0], v[:, 1]]
    for name, v in r.normal.items():
        head.append(f"N_{name} [{f}]")
        cols.append(v)
    for name, v in r.moment.items():
        head.append(f"M_{name} [{f}*{L}]")
        cols.append(v)
    head += [f"shaking_x [{f}]", f"shaking_y [{f}]", f"shaking_moment [{f}*{L}]",
             f"kinetic_energy [{f}*{L}]", f"potential_energy [{f}*{L}]"]  # fmt: skip
    cols += [r.shaking_force[:, 0], r.shaking_force[:, 1], r.shaking_moment, r.kinetic_energy,
             r.potential_energy]  # fmt: skip
    return head, cols


def totals(r: Forces) -> dict:
    """The figures a summary reports: peak (with the input where it peaks) and RMS input
    effort, each pin's peak reaction, the checks."""
    ok = np.isfinite(r.input)
    i = int(np.nanargmax(np.abs(r.input))) if ok.any() else None
    return {
        "kind": r.kind,
        "units": r.units,
        "effort_unit": r.effort_unit,
        "points": len(r.theta),
        "solved": int(r.success.sum()),
        "peak_input": r.peak_input,
        "peak_input_at": None if i is None else float(r.theta[i]),
        "rms_input": r.rms_input,
        "peak_reactions": [
            {"joint": j, "link": k, "force": m, "at": t} for (j, k), (m, t) in r.peaks().items()
        ],
        "checks": r.checks,
    }

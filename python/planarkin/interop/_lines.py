"""What a scene's slot and prismatic lines add to it: the helper points that only hold a
line (no joint, no tracer of interest), which other formats draw or write differently."""

from __future__ import annotations

from ..scene import Scene


def helpers(sc: Scene) -> set[str]:
    """Points that only hold a slot's or prismatic pair's line: on their guide alone, used
    by nothing else (not the input's pivot or direction point, not a slot's pin)."""
    count: dict[str, int] = dict.fromkeys(sc.points, 0)
    for pts in sc.links.values():
        for p in pts:
            count[p] += 1
    used: set[str] = set()
    if sc.input_kind == "angle":
        link, pivot = sc.input
        used = {pivot, next(p for p in sc.links[link] if p != pivot)}
    used |= {pt for pt, _g, _l in sc.slots.values()}
    lines = {q for _a, _g, line in (*sc.slots.values(), *sc.prismatic.values()) for q in line}
    return {p for p in lines if count[p] == 1 and p not in used}

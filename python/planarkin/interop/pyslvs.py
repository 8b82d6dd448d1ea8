"""Pyslvs's mechanism expressions in and out: ``from_pyslvs`` builds a Scene from
``M[J[...], ...]`` and an input pair, ``to_pyslvs`` writes a scene back, ``load``/``dumps``
read and write Pyslvs project files (``.pyslvs``: the ``mechanism`` and ``input`` keys).

Joint k is point ``J<k>``; an RP joint is a slot and a P joint a prismatic pair, each
named ``J<k>``, whose line runs through the joint at its angle ``A`` on the first listed
link, held by two helper points ``S<k>a``, ``S<k>b`` of that link (``S<k>a`` at the joint).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..scene import Scene
from . import _lines
from ._pyslvs_grammar import NAME, Joint, parse, text

__all__ = ["dumps", "from_pyslvs", "load", "to_pyslvs"]

#: The frame's name in Pyslvs.
GROUND = "ground"
_JNAME = re.compile(r"J(\d+)\Z")


def _size(xy: Sequence[tuple[float, float]]) -> float:
    """How far the helper point of a slot line sits from the joint: the drawing's extent."""
    xs, ys = [p[0] for p in xy], [p[1] for p in xy]
    s = max(max(xs) - min(xs), max(ys) - min(ys)) if xy else 0.0
    return s if s > 0 else 1.0


def _helper(x: float, y: float, deg: float, h: float) -> list[float]:
    t = math.radians(deg)
    return [x + h * math.cos(t), y + h * math.sin(t)]


def _order(joints: list[Joint]) -> list[str]:
    """The links in an order that lists each joint's links as written (a topological order
    of "comes before in some L[...]", earliest seen first), so that writing the scene back
    gives the same text; first seen first where the expression's orders disagree."""
    seen: list[str] = []
    after: dict[str, set[str]] = {}
    for j in joints:
        on = j.links if j.type == "R" else j.links[1:]
        for ln in j.links:
            if ln not in seen:
                seen.append(ln)
                after[ln] = set()
        for a, b in zip(on, on[1:], strict=False):
            after[b].add(a)
    out: list[str] = []
    while len(out) < len(seen):
        ready = [ln for ln in seen if ln not in out and after[ln] <= set(out)]
        if not ready:
            return seen
        out.append(ready[0])
    return out


def _pair(inputs: object) -> tuple[int, int]:
    ok = isinstance(inputs, (list, tuple))
    seq: Any = inputs
    if not ok or len(seq) == 0:
        raise ValueError(f"inputs must be a list of one (base, driver) pair, got {inputs!r}")
    if len(seq) > 1:
        raise ValueError(f"inputs: {len(seq)} input pairs given; a scene has one input "
                         "(Pyslvs's multi-input mechanisms cannot be held)")  # fmt: skip
    p = seq[0]
    if not (isinstance(p, (list, tuple)) and len(p) == 2 and all(type(i) is int for i in p)):
        raise ValueError(f"inputs[0] must be a pair of joint numbers (base, driver), got {p!r}")
    return p[0], p[1]


def from_pyslvs(
    expr: str, inputs: Sequence[tuple[int, int]] | None = None, *, name: str | None = None
) -> Scene:
    """A scene from a Pyslvs expression and its one input pair ``[(base, driver)]``: the
    crank is the moving link through ``J<base>`` (on ground) and ``J<driver>``, its angle
    the absolute direction J<base> -> J<driver>, as in Pyslvs."""
    joints = parse(expr)
    if inputs is None:
        raise ValueError("inputs: give the input pair [(base, driver)] (joint numbers)")
    b, d = _pair(inputs)
    n = len(joints)
    for what, i in (("base", b), ("driver", d)):
        if not 0 <= i < n:
            raise ValueError(f"inputs: the {what} J{i} is not a joint (J0 .. J{n - 1})")
    h = _size([(j.x, j.y) for j in joints])
    points: dict[str, list[float]] = {}
    links: dict[str, list[str]] = {}
    slots: dict[str, dict[str, Any]] = {}
    prism: dict[str, dict[str, Any]] = {}
    for k, j in enumerate(joints):
        p = f"J{k}"
        points[p] = [j.x, j.y]
        if not j.links:
            raise ValueError(f"{p}: on no link (L[] is empty)")
        on = j.links if j.type == "R" else j.links[1:]
        if j.type != "R":
            if not on:
                raise ValueError(f"{p}: a {j.type} joint needs a link after its slot's link")
            if j.type == "P" and len(on) > 1:
                raise ValueError(f"{p}: a P joint on more than two links is not supported")
            assert j.angle is not None
            line = [f"S{k}a", f"S{k}b"]
            points[line[0]] = [j.x, j.y]
            points[line[1]] = _helper(j.x, j.y, j.angle, h)
            links.setdefault(j.links[0], []).extend(line)
            if j.type == "RP":
                slots[p] = {"point": p, "guide": j.links[0], "line": line}
            else:
                prism[p] = {"link": on[0], "guide": j.links[0], "line": line}
        for ln in on:
            links.setdefault(ln, []).append(p)
    if GROUND not in links:
        raise ValueError("L: no joint is on 'ground' (Pyslvs's frame)")
    links = {ln: links[ln] for ln in _order(joints) if ln in links}
    jb, jd = f"J{b}", f"J{d}"
    if joints[b].type != "R" or GROUND not in joints[b].links:
        raise ValueError(f"inputs: the base {jb} must be a pin (R) on ground")
    crank = [ln for ln in links if ln != GROUND and jb in links[ln] and jd in links[ln]]
    if not crank:
        raise ValueError(f"inputs: {jb} and {jd} share no moving link")
    pts = links[crank[0]]
    links[crank[0]] = [jb, jd] + [q for q in pts if q not in (jb, jd)]
    data: dict[str, Any] = {"name": name if name is not None else "Pyslvs mechanism"}
    data |= {"points": points, "links": links, "ground": GROUND}
    data["input"] = {"link": crank[0], "pivot": jb}
    if slots:
        data["slots"] = slots
    if prism:
        data["prismatic"] = prism
    return Scene.from_dict(data)


def _deg(sc: Scene, at: str, line: tuple[str, str], h: float) -> float:
    """The line's direction in degrees, written as short as gives back the same helper
    point (so an imported scene's angle comes back as typed)."""
    (x0, y0), (x1, y1) = (sc.points[q] for q in line)
    deg = math.degrees(math.atan2(y1 - y0, x1 - x0))
    for digits in range(13):
        r = round(deg, digits)
        if _helper(*sc.points[at], r, h) == [x1, y1] and sc.points[line[0]] == sc.points[at]:
            return r
    return deg


def _plan(sc: Scene) -> tuple[list[str], list[Joint], tuple[int, int]]:
    if sc.input_kind != "angle":
        raise ValueError(f"input: a linear input ({' '.join(sc.input)}) has no Pyslvs form")
    if sc.lengths is not None:
        raise ValueError("lengths: a sketch's lengths have no Pyslvs form (save its pose)")
    for ln in sc.links:
        if not NAME.match(ln) or (ln == GROUND) != (ln == sc.ground):
            raise ValueError(f"links.{ln}: not a name Pyslvs can hold as a link")
    helpers = _lines.helpers(sc)
    names = [p for p in sc.points if p not in helpers]
    nums = [_JNAME.match(p) for p in names]
    if all(nums) and sorted(int(m.group(1)) for m in nums if m) == list(range(len(names))):
        names.sort(key=lambda p: int(p[1:]))  # an imported scene keeps its numbering
    slot_of: dict[str, tuple[str, tuple[str, str]]] = {}
    for s, (pt, g, line) in sc.slots.items():
        if pt in slot_of:
            raise ValueError(f"slots.{s}: a second slot on {pt!r} has no Pyslvs form")
        slot_of[pt] = (g, line)
    # a P joint sits at a point of the sliding link on that link alone (drawn at its first
    # point, as an extra joint, where it has none free)
    at_of: dict[str, str] = {}
    prism_at: dict[str, tuple[str, str, tuple[str, str]]] = {}
    for s, (ln, g, line) in sc.prismatic.items():
        on_l = [p for p in names if [q for q, v in sc.links.items() if p in v] == [ln]]
        free = [p for p in on_l if p not in slot_of and p not in prism_at]
        at = s if s in free else (free[0] if free else f"{s} (P joint)")
        if at not in sc.points:
            names.append(at)
        at_of[at] = at if at in sc.points else sc.links[ln][0]
        prism_at[at] = (ln, g, line)
    h = _size([sc.points[at_of.get(p, p)] for p in names])
    joints: list[Joint] = []
    for p in names:
        x, y = sc.points[at_of.get(p, p)]
        on = [ln if ln != sc.ground else GROUND for ln, v in sc.links.items() if p in v]
        if p in slot_of:
            g, line = slot_of[p]
            j = Joint("RP", x, y, _deg(sc, p, line, h), (g, *on))
        elif p in prism_at:
            ln, g, line = prism_at[p]
            j = Joint("P", x, y, _deg(sc, at_of[p], line, h), (g, ln))
        else:
            j = Joint("R", x, y, None, tuple(on))
        joints.append(j)
    link, pivot = sc.input
    driver = next(p for p in sc.links[link] if p != pivot)
    return names, joints, (names.index(pivot), names.index(driver))


def to_pyslvs(sc: Scene) -> str:
    """The scene as a Pyslvs expression (its input pair: ``pyslvs_input``). What Pyslvs
    cannot hold is a one-line ValueError naming it: a linear input, a sketch's lengths."""
    return text(_plan(sc)[1])


def pyslvs_input(sc: Scene) -> tuple[int, int]:
    """The scene's input as Pyslvs's pair (base, driver) of joint numbers."""
    return _plan(sc)[2]


def dumps(sc: Scene) -> str:
    """A Pyslvs project file (YAML: ``mechanism`` and ``input``) for the scene."""
    _names, joints, (b, d) = _plan(sc)
    return f"mechanism: '{text(joints, one_line=True)}'\ninput:\n- [{b}, {d}]\n"


def loads(source: str, where: str = "pyslvs file", name: str | None = None) -> Scene:
    """A scene from a Pyslvs project's text (its ``mechanism`` and ``input`` keys; the other
    keys are Pyslvs's own and skipped), or from a bare ``M[...]`` with an ``input:`` line."""
    m = re.search(r"^mechanism:\s*", source, re.M)
    start = m.end() if m else source.find("M[")
    if start < 0:
        raise ValueError(f"{where}: no 'mechanism: M[...]' in it")
    depth, end = 0, -1
    for i in range(source.find("[", start), len(source)):
        depth += {"[": 1, "]": -1}.get(source[i], 0)
        if depth == 0:
            end = i + 1
            break
    if end < 0:
        raise ValueError(f"{where}: the mechanism's brackets do not close")
    expr = source[start:end].strip().lstrip("'\"")
    m = re.search(r"^input:(.*?)(?=^[A-Za-z_]\w*:|\Z)", source, re.M | re.S)
    nums = [int(v) for v in re.findall(r"-?\d+", m.group(1))] if m else []
    if not nums or len(nums) % 2:
        raise ValueError(f"{where}: no input pair (write 'input: [[base, driver]]')")
    pairs = [(nums[i], nums[i + 1]) for i in range(0, len(nums), 2)]
    try:
        return from_pyslvs(expr, pairs, name=name)
    except ValueError as e:
        raise ValueError(f"{where}: {e}") from None


def load(path: str | Path) -> Scene:
    """Reads a Pyslvs project file (``.pyslvs``); every error names the file."""
    p = Path(path)
    return loads(p.read_text(encoding="utf-8"), str(p), name=p.stem)

"""A scene seen as a four-bar (``Scene.as_fourbar``): recognised from its links alone
(four, the input and output pinned at the two ground pivots, a coupler joining them), and
the frames that relate the two."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, NamedTuple, NoReturn

from .._angles import wrap
from ..fourbar import LINKS, POINTS, FourBar


class FourBarView(NamedTuple):
    """A four-bar scene seen as a :class:`planarkin.FourBar` (``Scene.as_fourbar()``).

    A four-bar measures its angles from the ground line O2 -> O4 with O2 at the origin; a
    scene's are absolute. So for the same motion, scene input angle = ``theta2`` +
    ``ground_angle``; a scene link angle = the four-bar's + ``ground_angle``; a scene
    point = ``origin`` + the four-bar's point rotated by ``ground_angle``.
    """

    #: The equivalent linkage: r1 = |O2 O4|, r2 = |O2 A|, r3 = |A B|, r4 = |O4 B|.
    fourbar: FourBar
    #: The assembly mode it is drawn in: "open" (sin(theta4 - theta3) > 0) or "crossed".
    mode: str
    #: Direction of the ground line O2 -> O4 (radians, absolute).
    ground_angle: float
    #: Where the crank's ground pivot O2 is drawn.
    origin: tuple[float, float]
    #: The drawn crank angle, measured from the ground line (radians, in (-pi, pi]).
    theta2: float
    #: Four-bar name -> the scene's: points O2, O4, A, B; links ground, crank, coupler,
    #: rocker (the names ``Sweep.points``, ``Sweep.angles`` and ``FourBar.to_scene`` use).
    names: dict[str, str]
    #: Tracer points on the coupler -> (p, delta): distance from A and angle (radians)
    #: from the line A -> B, as ``FourBar.coupler_point`` takes them.
    coupler: dict[str, tuple[float, float]]


def _pair(drive: Mapping[str, str]) -> tuple[str, str]:
    """An input or output as ``Scene.input`` gives it: (link, pivot), or (kind, name)."""
    if "link" in drive:
        return drive["link"], drive["pivot"]
    return next(iter(drive.items()))


def fourbar_view(data: Mapping[str, Any], name: str | None) -> FourBarView:
    """The four-bar of a scene's data (``Scene._data``: points, links, ground, input,
    output); ValueError naming why where it is not one (``name``: the scene's)."""
    links, pts = data["links"], data["points"]

    def refuse(why: str) -> NoReturn:
        raise ValueError(f"scene {name or '(unnamed)'!r} is not a four-bar: {why}")

    if len(links) != 4:
        refuse(f"it has {len(links)} links (a four-bar has 4: ground, crank, coupler, rocker)")
    ground = data["ground"]
    crank, o2 = _pair(data["input"])
    on_ground = list(dict.fromkeys(links[ground]))
    if len(on_ground) != 2:
        refuse(f"its ground {ground!r} carries {len(on_ground)} points, not its 2 pivots")
    o4 = on_ground[1] if on_ground[0] == o2 else on_ground[0]
    carriers = {p: [k for k, v in links.items() if p in v] for p in pts}
    if data["output"] is not None and "link" in data["output"]:
        rocker, pivot = data["output"]["link"], data["output"]["pivot"]
        if pivot != o4:
            refuse(f"its output {rocker!r} is not pinned at the other ground pivot {o4!r}")
    else:
        pinned = [k for k in carriers[o4] if k != ground]
        if len(pinned) != 1:
            refuse(f"{len(pinned)} links are pinned to ground at {o4!r}, not one rocker")
        rocker = pinned[0]
    if rocker in (ground, crank):
        refuse(f"its output {rocker!r} is its {'ground' if rocker == ground else 'input'}")
    (coupler,) = (k for k in links if k not in (ground, crank, rocker))
    ends = {}
    for link, pivot in ((crank, o2), (rocker, o4)):
        others = [p for p in dict.fromkeys(links[link]) if p != pivot]
        if len(others) != 1 or others[0] not in links[coupler]:
            refuse(f"{link!r} must carry its ground pivot {pivot!r} and one joint with "
                   f"the coupler {coupler!r}, got {list(links[link])}")  # fmt: skip
        ends[link] = others[0]
    a, b = ends[crank], ends[rocker]
    tracers = [p for p in dict.fromkeys(links[coupler]) if p not in (a, b)]
    shared = [p for p in tracers if carriers[p] != [coupler]]
    if a == b or shared:
        refuse(f"the coupler {coupler!r} must join {a!r} and {b!r} and carry only tracers "
               "besides")  # fmt: skip
    xy = pts
    (x2, y2), (x4, y4), (xa, ya), (xb, yb) = xy[o2], xy[o4], xy[a], xy[b]
    fb = FourBar(
        math.dist(xy[o2], xy[o4]), math.dist(xy[o2], xy[a]),
        math.dist(xy[a], xy[b]), math.dist(xy[o4], xy[b]),
    )  # fmt: skip
    # the mode is the sign of sin(theta4 - theta3): of the cross product A->B x O4->B
    cross = (xb - xa) * (yb - y4) - (yb - ya) * (xb - x4)
    if cross == 0:
        refuse("it is drawn at a dead point (coupler and rocker in line)")
    ground_angle = math.atan2(y4 - y2, x4 - x2)
    t3 = math.atan2(yb - ya, xb - xa)
    coupler_points = {
        p: (math.dist(xy[a], xy[p]), wrap(math.atan2(xy[p][1] - ya, xy[p][0] - xa) - t3))
        for p in tracers
    }
    names = dict(zip(POINTS, (o2, o4, a, b), strict=True))
    names.update(zip(LINKS, (ground, crank, coupler, rocker), strict=True))
    return FourBarView(
        fourbar=fb,
        mode="open" if cross > 0 else "crossed",
        ground_angle=ground_angle,
        origin=(x2, y2),
        theta2=wrap(math.atan2(ya - y2, xa - x2) - ground_angle),
        names=names,
        coupler=coupler_points,
    )

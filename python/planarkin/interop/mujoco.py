"""MuJoCo models (MJCF) of scenes, loops closed: a kinematic tree over the links from the
ground (hinges at pins, slides along prismatic pairs, slide + hinge for a pin in a slot),
each joint the tree leaves out an equality constraint (``connect`` at a pin, a sliding
block ``connect``-ed to a slot's pin or ``weld``-ed to a prismatic link), the input a
position-actuated joint. Writing needs no MuJoCo; loading it is the ``mujoco`` extra.

At qpos = 0 every body is as drawn; a body's frame is the world's, moved to the point
where the tree enters it. Sites ``<link>:<point>`` mark every point a link carries."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from xml.sax.saxutils import quoteattr

from ..scene import Scene

Point = tuple[float, float]


@dataclass
class _Body:
    name: str
    origin: Point
    joints: list[str] = field(default_factory=list)  # MJCF <joint .../> lines
    children: list[_Body] = field(default_factory=list)
    sites: dict[str, Point] = field(default_factory=dict)
    geoms: list[tuple[Point, Point]] = field(default_factory=list)


@dataclass(frozen=True)
class Model:
    """The MJCF text and what a replay needs: ``input_joint`` (the actuated joint; its
    qpos is the input's change from the drawn value: radians or scene units) and
    ``sites``: site name -> (link, point)."""

    xml: str
    input_joint: str
    sites: dict[str, tuple[str, str]]


def _f(v: float) -> str:
    return repr(float(v) + 0.0)


def _xyz(p: Point) -> str:
    return f"{_f(p[0])} {_f(p[1])} 0"


def _unit(sc: Scene, line: tuple[str, str]) -> Point:
    (ax, ay), (bx, by) = (sc.points[q] for q in line)
    d = math.hypot(bx - ax, by - ay)
    return ((bx - ax) / d, (by - ay) / d)


def _rel(p: Point, o: Point) -> Point:
    return (p[0] - o[0], p[1] - o[1])


def build(sc: Scene, *, kp: float | None = None) -> Model:
    """The scene as an MJCF model (see the module doc); ``kp``: the position actuator's
    gain per unit of the bodies' total moment of inertia (default 1e5 /s^2; critically
    damped)."""
    pts, links = sc.points, sc.links
    if "world" in links:
        raise ValueError("links.world: MuJoCo's name for the ground; rename the link")
    xs, ys = [p[0] for p in pts.values()], [p[1] for p in pts.values()]
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    # edges: (kind, name, link a, link b); a pin joins every pair of the links it is on
    edges: list[tuple[str, str, str, str]] = []
    kind, name = sc.input
    if sc.input_kind == "angle":
        edges.append(("pin", name, sc.ground, kind))  # the crank first: its hinge is in the tree
    elif kind == "prismatic":
        ln, g, _ = sc.prismatic[name]
        edges.append(("prismatic", name, g, ln))
    for p in pts:
        on = [ln for ln, v in links.items() if p in v]
        edges += [("pin", p, a, b) for i, a in enumerate(on) for b in on[i + 1 :]]
    for s, (ln, g, _line) in sc.prismatic.items():
        edges.append(("prismatic", s, g, ln))
    for s, (_p, g, _line) in sc.slots.items():
        edges.append(("slot", s, g, _pin_link(sc, s)))
    edges = list(dict.fromkeys(edges))  # the input's pair is listed twice
    bodies: dict[str, _Body] = {sc.ground: _Body(sc.ground, (0.0, 0.0))}
    tree: set[tuple[str, str, str, str]] = set()
    joined: dict[str, list[set[str]]] = {}  # pin -> groups of its links joined so far
    grew = True
    while grew:  # pins first (a slot or prismatic pair only where no pin reaches the link)
        grew = False
        for k in ("pin", "prismatic", "slot"):
            for e in edges:
                ek, en, a, b = e
                if ek != k or (a in bodies) == (b in bodies):
                    continue
                parent, child = (a, b) if a in bodies else (b, a)
                if ek != "pin" and parent != a:
                    continue  # a slide hangs from its guide
                bodies[child] = _attach(sc, bodies[parent], child, e)
                tree.add(e)
                if ek == "pin":
                    joined.setdefault(en, []).append({a, b})
                grew = True
                break
            if grew:
                break
    missing = [ln for ln in links if ln not in bodies]
    if missing:
        raise ValueError(f"links.{missing[0]}: not joined to the ground by any joint")
    for ln, v in links.items():
        body = bodies[ln]
        for p in v:
            body.sites[f"{ln}:{p}"] = _rel(pts[p], body.origin)
        body.geoms += [(body.sites[f"{ln}:{v[0]}"], body.sites[f"{ln}:{q}"]) for q in v[1:]]
    equality: list[str] = []
    for p in pts:
        on = [ln for ln, v in links.items() if p in v]
        groups = _merge(joined.get(p, []))
        for ln in on[1:]:
            if not any(on[0] in g and ln in g for g in groups):
                anchor = _xyz(_rel(pts[p], bodies[on[0]].origin))
                equality.append(
                    f"<connect name={quoteattr(f'pin:{p}:{ln}')} body1={_body(sc, on[0])} "
                    f'body2={_body(sc, ln)} anchor="{anchor}"/>'
                )
                groups = _merge([*groups, {on[0], ln}])
    for e in edges:
        ek, en, g, ln = e
        if ek == "pin" or e in tree:
            continue
        at = sc.slots[en][0] if ek == "slot" else links[ln][0]
        block = _Body(f"block:{en}", pts[at])
        u = _unit(sc, (sc.slots if ek == "slot" else sc.prismatic)[en][2])
        block.joints.append(f'<joint name={quoteattr(f"slide:{en}")} type="slide" '
                            f'axis="{_xyz(u)}"/>')  # fmt: skip
        block.sites[f"block:{en}"] = (0.0, 0.0)
        bodies[g].children.append(block)
        bodies[block.name] = block
        # a pin turns freely in its block (connect); a prismatic link turns with it (weld)
        eq = 'connect anchor="0 0 0"' if ek == "slot" else "weld"
        equality.append(f"<{eq} name={quoteattr(f'{ek}:{en}')} body1={quoteattr(block.name)} "
                        f"body2={_body(sc, ln)}/>")  # fmt: skip
    if sc.input_kind == "angle":
        input_joint = f"hinge:{sc.input[1]}:{sc.input[0]}"
    else:
        input_joint = f"slide:{name}"
    gain = 1e5 if kp is None else kp
    xml = _text(sc, bodies[sc.ground], equality, input_joint, gain, size)
    sites = {f"{ln}:{p}": (ln, p) for ln, v in links.items() for p in v}
    return Model(xml, input_joint, sites)


def _pin_link(sc: Scene, slot: str) -> str:
    """The link a slot's pin rides on: the first that carries it (the others meet it at
    the pin)."""
    p = sc.slots[slot][0]
    return next(ln for ln, v in sc.links.items() if p in v)


def _body(sc: Scene, link: str) -> str:
    """A link's body name, quoted for MJCF: the ground is MuJoCo's world body."""
    return quoteattr("world" if link == sc.ground else link)


def _merge(groups: list[set[str]]) -> list[set[str]]:
    out: list[set[str]] = []
    for g in groups:
        g = set(g)
        for h in [h for h in out if h & g]:
            g |= h
            out.remove(h)
        out.append(g)
    return out


def _attach(sc: Scene, parent: _Body, child: str, e: tuple[str, str, str, str]) -> _Body:
    ek, en = e[0], e[1]
    if ek == "pin":
        b = _Body(child, sc.points[en])
        b.joints.append(f'<joint name={quoteattr(f"hinge:{en}:{child}")} type="hinge" '
                        'axis="0 0 1"/>')  # fmt: skip
    elif ek == "prismatic":
        b = _Body(child, sc.points[sc.links[child][0]])
        u = _unit(sc, sc.prismatic[en][2])
        b.joints.append(f'<joint name={quoteattr(f"slide:{en}")} type="slide" '
                        f'axis="{_xyz(u)}"/>')  # fmt: skip
    else:  # the pin's link slides along the slot, then turns about the pin
        pin = sc.slots[en][0]
        b = _Body(child, sc.points[pin])
        u = _unit(sc, sc.slots[en][2])
        b.joints.append(f'<joint name={quoteattr(f"slide:{en}")} type="slide" '
                        f'axis="{_xyz(u)}"/>')  # fmt: skip
        b.joints.append(f'<joint name={quoteattr(f"hinge:{pin}:{child}")} type="hinge" '
                        'axis="0 0 1"/>')  # fmt: skip
    parent.children.append(b)
    return b


def _inertia(b: _Body, r: float) -> float:
    """A unit mass's moment of inertia about the body's origin, about as its bar's."""
    extent = max([math.hypot(*s) for s in b.sites.values()] + [r])
    return extent * extent / 3 + r * r


def _all(b: _Body) -> list[_Body]:
    return [b] + [d for c in b.children for d in _all(c)]


def _masses(sc: Scene) -> dict[str, tuple[float, Point, float]]:
    """Link -> (mass, centre in the drawing, moment of inertia about it) from the scene's
    loads (none without them)."""
    masses = (sc.loads or {}).get("masses") or {}
    out = {}
    for link, m in masses.items():
        c = m["center"]
        centre = sc.points[c] if isinstance(c, str) else (float(c[0]), float(c[1]))
        out[link] = (float(m["mass"]), centre, float(m.get("inertia", 0.0)))
    return out


def _body_text(
    b: _Body, parent: Point, r: float, depth: int, masses: dict[str, tuple[float, Point, float]]
) -> list[str]:
    pad = "  " * depth
    out = [f'{pad}<body name={quoteattr(b.name)} pos="{_xyz(_rel(b.origin, parent))}">']
    if b.name in masses:
        # the scene's mass, centre and inertia about it (a plane body: the two in-plane
        # axes take the same value, which keeps MuJoCo's triangle inequality)
        m, centre, i_zz = masses[b.name]
        i = _f(max(i_zz, 1e-12 * m * r * r))
        out.append(f'{pad}  <inertial pos="{_xyz(_rel(centre, b.origin))}" mass="{_f(m)}" '
                   f'diaginertia="{i} {i} {i}"/>')  # fmt: skip
    else:
        extent = max([math.hypot(*s) for s in b.sites.values()] + [r])
        inertia = _f(extent * extent / 3 + r * r)
        out.append(f'{pad}  <inertial pos="0 0 0" mass="1" diaginertia="{inertia} {inertia} '
                   f'{inertia}"/>')  # fmt: skip
    out += [f"{pad}  {j}" for j in b.joints]
    for p, q in b.geoms:
        if p != q:
            out.append(f'{pad}  <geom type="capsule" size="{_f(r)}" '
                       f'fromto="{_xyz(p)} {_xyz(q)}"/>')  # fmt: skip
    for s, p in b.sites.items():
        out.append(f'{pad}  <site name={quoteattr(s)} pos="{_xyz(p)}" size="{_f(r * 0.6)}"/>')
    for c in b.children:
        out += _body_text(c, b.origin, r, depth + 1, masses)
    out.append(f"{pad}</body>")
    return out


def _text(sc: Scene, ground: _Body, equality: list[str], inp: str, kp: float, size: float) -> str:
    r = 0.02 * size
    g = (sc.loads or {}).get("gravity") or [0.0, 0.0]
    gravity = (float(g[0]), float(g[1]))
    lines = [
        f"<mujoco model={quoteattr(sc.name or 'scene')}>",
        f"  <!-- planarkin export; lengths in the scene's unit ({sc.units or 'unitless'}),"
        " angles in radians; qpos = 0 is the drawn pose -->",
        '  <compiler angle="radian" autolimits="true"/>',
        f'  <option timestep="0.0005" gravity="{_xyz(gravity)}" integrator="implicitfast">',
        '    <flag contact="disable"/>',
        "  </option>",
        "  <default>",
        '    <equality solref="0.002 1"/>',
        '    <joint damping="5"/>',
        "  </default>",
        "  <worldbody>",
    ]
    for s, p in ground.sites.items():
        lines.append(f'    <site name={quoteattr(s)} pos="{_xyz(p)}" size="{_f(r * 0.6)}"/>')
    for p, q in ground.geoms:
        if p != q:
            lines.append(f'    <geom type="capsule" size="{_f(r)}" '
                         f'fromto="{_xyz(p)} {_xyz(q)}"/>')  # fmt: skip
    masses = _masses(sc)
    for c in ground.children:
        lines += _body_text(c, ground.origin, r, 2, masses)
    # the input's servo: stiff against every body's inertia, critically damped
    inertia = sum(
        masses[b.name][2] + masses[b.name][0] * math.dist(masses[b.name][1], b.origin) ** 2
        if b.name in masses
        else _inertia(b, r)
        for c in ground.children
        for b in _all(c)
    )
    kv = 2 * math.sqrt(kp) * inertia
    kp *= inertia
    lines += ["  </worldbody>", "  <equality>"]
    lines += [f"    {e}" for e in equality]
    lines += [
        "  </equality>",
        "  <actuator>",
        f'    <position name="input" joint={quoteattr(inp)} kp="{_f(kp)}" kv="{_f(kv)}"/>',
        "  </actuator>",
        "</mujoco>",
    ]
    return "\n".join(lines) + "\n"


def write(sc: Scene, path: str | Path) -> Path:
    """Writes the scene's MJCF model; returns the path."""
    p = Path(path)
    p.write_text(build(sc).xml, encoding="utf-8")
    return p

"""The Scene: parsing, validation (in the Rust core), file round trips, plans, sweeps,
assemblies, circuits and traces; a four-bar scene is recognised in ``_fourbar_view``, a
pose given as data checked in ``_poses``."""

from __future__ import annotations

import copy
import json
import math
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from .. import _kernel
from .._args import as_angles, as_float, as_i64, as_str, as_u64
from .._svg import picture, png
from ..fourbar import FourBar
from ._fourbar_view import FourBarView, fourbar_view
from ._parse import parse
from ._poses import pose_array, redrawn
from ._results import (
    Assemblies,
    Assembly,
    Circuit,
    Plan,
    SceneGradient,
    SceneSweep,
    Step,
    Trace,
)
from ._toml import dumps as toml_dumps
from .output import needs

#: Defaults, written once in the core (``planarkin_core::scene::format``): the largest
#: continuation step of a group (3 degrees), the homotopy's seed (results are reproducible)
#: and runs, and a trace's largest arclength step (radians of rotation, all links together)
#: and length.
MAX_STEP = _kernel.MAX_STEP
SEED = _kernel.SEED
RUNS = _kernel.RUNS
TRACE_STEP = _kernel.TRACE_STEP
TRACE_MAX_POINTS = _kernel.TRACE_MAX_POINTS
TOL = _kernel.TOL
MAX_ITER = _kernel.MAX_ITER


def _entry(cond: bool, entry: str, message: str) -> None:
    if not cond:
        raise ValueError(f"{entry}: {message}")


class Scene:
    """A one-degree-of-freedom planar linkage of revolute joints, drawn in one assembled pose.

    ``points`` name -> (x, y) as drawn (any length unit); ``links`` name -> the points it
    carries (a rigid body: a ternary lists 3); a point on two or more links is a revolute
    joint, a point on one link only is a tracer. ``ground`` is the fixed link; ``input``
    the driven link, pinned to ground at its pivot; its angle is the direction (radians)
    from the pivot to the link's first other listed point. The drawn pose chooses the
    assembly that sweeps follow. Invalid scenes raise ValueError naming the entry.

    >>> import planarkin as pk
    >>> sc = pk.scenes.load("fourbar")
    >>> sw = sc.sweep(outputs=["P"])
    >>> sw.points["P"].shape
    (361, 2)
    """

    __slots__ = ("_core", "_data", "_forces", "_kind", "_max_step", "_moved", "_plans", "_svg",
                 "_theta")  # fmt: skip

    #: Other tools' formats, set by ``planarkin.interop`` (the scene subject imports none):
    #: format name -> (reader, writer) behind ``from_pyslvs`` and ``to_pyslvs``.
    formats: ClassVar[dict[str, tuple[Any, Any]]] = {}

    def __init__(self, data: Mapping[str, Any]) -> None:
        # the core reads the data (every check and message is the file format's, there)
        self._take(_kernel.load_scene(data))

    def _take(self, loaded: Any) -> None:
        """Holds what the core's ``load_scene`` (or ``load_scene_json``) returned."""
        core, text, points, links, ground, inp, out, outputs, slots, prism, lengths, extra = loaded
        moved, unit_table, loads, limits = extra
        self._core = core
        self._max_step = core.max_step  # the default, read once (every sweep takes it)
        self._moved: list[float] | None = moved  # a dict when asked for (`moved`)
        # the links a sweep's notebook picture draws, and the ground (once, not per sweep)
        self._svg = (tuple(v for k, v in links.items() if k != ground), links[ground])
        name, description, units = text
        self._data: dict[str, Any] = {
            "name": name,
            "description": description,
            "units": units,
            "points": points,
            "links": links,
            "ground": ground,
            "input": dict(inp),
            "output": None if out is None else dict(out),
            "outputs": None if outputs is None else tuple(outputs),
            "slots": dict(slots),
            "prismatic": dict(prism),
            "lengths": None if lengths is None else tuple(lengths),
            "unit_table": unit_table,
            "loads": loads,
            "limits": limits,
        }
        # (read by every sweep: found once)
        self._kind = "angle" if "link" in self._data["input"] else "displacement"
        self._plans: dict[tuple[str, ...] | None, tuple[Plan, Any]] = {}
        self._theta: np.ndarray | None = None
        self._forces: Any = None
        if outputs is not None:
            self.plan(outputs)  # names checked now, not at the first sweep

    # --- construction and files ------------------------------------------------------

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Scene:
        """A scene from a mapping with the file format's keys."""
        return cls(data)

    @classmethod
    def from_pyslvs(
        cls, expr: str, inputs: Iterable[tuple[int, int]] | None = None, *, name: str | None = None
    ) -> Scene:
        """A scene from a Pyslvs expression ``M[J[...], ...]`` and its one input pair
        ``[(base, driver)]``: joint k is point ``J<k>`` (``planarkin.interop.pyslvs``)."""
        return cls.formats["pyslvs"][0](expr, inputs, name=name)

    def to_pyslvs(self) -> str:
        """The scene as a Pyslvs expression ``M[...]`` (``planarkin.interop.pyslvs``)."""
        return self.formats["pyslvs"][1](self)

    @classmethod
    def load(cls, path: str | Path) -> Scene:
        """Reads a ``.json`` or ``.toml`` scene file; every error names the file. Plain JSON
        is read and checked in the core in one pass; other text goes through Python's
        ``json`` (or ``tomllib``), whose messages the errors quote."""
        p = Path(path)
        if p.suffix not in (".json", ".toml"):
            raise ValueError(f"path must end in .json or .toml, got {str(path)!r}")
        raw = p.read_bytes()
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError as e:
            bom = raw[:2] in (b"\xff\xfe", b"\xfe\xff")
            what = (
                "UTF-16 text" if bom else f"not UTF-8 text (byte {e.start} is {raw[e.start]:#04x})"
            )
            raise ValueError(
                f"{p}: {what}; a scene file is UTF-8 JSON or TOML (save it as UTF-8)"
            ) from None
        try:
            # plain JSON is read and checked in the core in one pass; what its reader does not
            # take (not JSON, a key twice, too deep) Python's reader words, naming the entry
            loaded = _kernel.load_scene_json(text, p.stem) if p.suffix == ".json" else None
            if loaded is not None:
                sc = cls.__new__(cls)
                sc._take(loaded)
                return sc
        except ValueError as e:
            raise ValueError(f"{p}: {e}") from None
        data = parse(text, p.suffix, str(p))
        if isinstance(data, dict) and data.get("name") is None:
            data["name"] = p.stem
        try:
            return cls(data)
        except ValueError as e:
            raise ValueError(f"{p}: {e}") from None

    def to_dict(self) -> dict[str, Any]:
        """The scene in the file format (plain lists and dicts; absent keys left out)."""
        d = self._data
        out: dict[str, Any] = {}
        for k in ("name", "description", "units"):
            if d[k] is not None:
                out[k] = d[k]
        if d["unit_table"] is not None:
            out["units"] = dict(d["unit_table"])
        out["points"] = {n: [x, y] for n, (x, y) in d["points"].items()}
        out["links"] = {n: list(v) for n, v in d["links"].items()}
        out["ground"] = d["ground"]
        out["input"] = dict(d["input"])
        if d["output"] is not None:
            out["output"] = dict(d["output"])
        if d["outputs"] is not None:
            out["outputs"] = list(d["outputs"])
        for key, first in (("slots", "point"), ("prismatic", "link")):
            if d[key]:
                out[key] = {
                    n: {first: a, "guide": g, "line": list(line)}
                    for n, (a, g, line) in d[key].items()
                }
        if d["lengths"] is not None:
            out["lengths"] = [[a, b, v] for a, b, v in d["lengths"]]
        if d["limits"] is not None:
            out["limits"] = copy.deepcopy(d["limits"])
        if d["loads"] is not None:
            # the normalised loads, less what is empty
            out["loads"] = {
                k: copy.deepcopy(v) for k, v in d["loads"].items() if v not in (None, [], {})
            }
        return out

    def save(self, path: str | Path) -> Path:
        """Writes the scene as ``.json`` or ``.toml`` (by the suffix); returns the path."""
        p = Path(path)
        if p.suffix == ".json":
            p.write_text(json.dumps(self.to_dict(), indent=2) + "\n", encoding="utf-8")
        elif p.suffix == ".toml":
            p.write_text(toml_dumps(self.to_dict()), encoding="utf-8")
        else:
            raise ValueError(f"path must end in .json or .toml, got {str(path)!r}")
        return p

    # --- what it is ------------------------------------------------------------------

    @property
    def name(self) -> str | None:
        return self._data["name"]

    @property
    def description(self) -> str | None:
        return self._data["description"]

    @property
    def units(self) -> str | None:
        return self._data["units"]

    @property
    def unit_system(self) -> dict[str, str | None]:
        """The scene's units: length (None where not named), force (default N), mass
        (default kg); ``units`` as a string names the length unit."""
        from ..forces import unit_names

        return unit_names(self._data["units"], self._data["unit_table"])

    @property
    def limits(self) -> dict[str, Any] | None:
        """The scene's travel limits as the file gives them (name -> [lo, hi], or
        {"links": [a, b], "range": [lo, hi]}), or None."""
        return copy.deepcopy(self._data["limits"])

    @property
    def loads(self) -> dict[str, Any] | None:
        """The scene's loads, normalised (every key present), or None."""
        return copy.deepcopy(self._data["loads"])

    @property
    def points(self) -> dict[str, tuple[float, float]]:
        """Point name -> (x, y) as drawn."""
        return dict(self._data["points"])

    @property
    def links(self) -> dict[str, tuple[str, ...]]:
        """Link name -> the names of the points it carries."""
        return dict(self._data["links"])

    @property
    def ground(self) -> str:
        return self._data["ground"]

    @property
    def input(self) -> tuple[str, str]:
        """(input link, its ground pivot) for an angle input; ("slot" | "prismatic", its
        name) for a linear one."""
        d = self._data["input"]
        return (d["link"], d["pivot"]) if "link" in d else next(iter(d.items()))

    @property
    def input_kind(self) -> str:
        """ "angle" (a crank's absolute direction, radians) or "displacement" (along a slot
        or prismatic pair from the drawn pose, scene units)."""
        return self._kind

    @property
    def output(self) -> tuple[str, str] | None:
        """(output link, its ground pivot), ("slot" | "prismatic", name), or None."""
        d = self._data["output"]
        if d is None:
            return None
        return (d["link"], d["pivot"]) if "link" in d else next(iter(d.items()))

    @property
    def slots(self) -> dict[str, tuple[str, str, tuple[str, str]]]:
        """Slot name -> (point, guide link, (line point, line point))."""
        return dict(self._data["slots"])

    @property
    def prismatic(self) -> dict[str, tuple[str, str, tuple[str, str]]]:
        """Prismatic pair name -> (sliding link, guide link, (line point, line point))."""
        return dict(self._data["prismatic"])

    @property
    def lengths(self) -> tuple[tuple[str, str, float], ...] | None:
        """The sketch's lengths as given, (name, name, distance); None for a scene typed as
        an exact pose."""
        return self._data["lengths"]

    @property
    def moved(self) -> dict[str, float]:
        """Point name -> how far it moved from the sketch to the exact pose (scene units;
        0 for ground points and for a scene without ``lengths``)."""
        if self._moved is None:
            return dict.fromkeys(self._data["points"], 0.0)
        return dict(zip(self._data["points"], self._moved, strict=True))

    @property
    def outputs(self) -> tuple[str, ...] | None:
        """The names requested by default (None: every point and link)."""
        return self._data["outputs"]

    @property
    def input_angle(self) -> float:
        """The input angle as drawn (radians)."""
        return self._core.input_angle

    @property
    def mobility(self) -> int:
        """Gruebler's count 3 (links - 1) - 2 joints (1 for every valid scene)."""
        return self._core.gruebler

    @property
    def joints(self) -> dict[str, tuple[str, ...]]:
        """Revolute joints: point name -> the links it joins (points on >= 2 links)."""
        on: dict[str, list[str]] = {p: [] for p in self._data["points"]}
        for n, pts in self._data["links"].items():
            for p in pts:
                on[p].append(n)
        return {p: tuple(ls) for p, ls in on.items() if len(ls) >= 2}

    def __repr__(self) -> str:
        d = self._data
        a, b = self.input
        drive = f"{a!r} at {b!r}" if self.input_kind == "angle" else f"{a} {b!r}"
        return (
            f"Scene({d['name']!r}: {len(d['points'])} points, {len(d['links'])} links, "
            f"input {drive})"
        )

    def _repr_svg_(self) -> str:
        """A notebook's picture (a few KB of SVG): the drawn pose, every point named."""
        d = self._data
        links = [v for k, v in d["links"].items() if k != d["ground"]]
        title = d["name"] or "scene"
        return picture(pose=d["points"], links=links, ground=d["links"][d["ground"]], title=title)

    def _repr_png_(self) -> bytes:
        """The same picture as PNG."""
        d = self._data
        links = [v for k, v in d["links"].items() if k != d["ground"]]
        title = d["name"] or "scene"
        return png(pose=d["points"], links=links, ground=d["links"][d["ground"]], title=title)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scene) and self.to_dict() == other.to_dict()

    __hash__ = None  # type: ignore[assignment]

    # --- solving ---------------------------------------------------------------------

    def _compiled(self, outputs: Iterable[str] | str | None) -> tuple[Plan, Any]:
        if outputs is None:
            outputs = self.outputs
        if isinstance(outputs, str):
            if outputs != "all":
                raise ValueError(f"outputs must be a list of names or 'all', got {outputs!r}")
            outputs = None
        key = None if outputs is None else tuple(outputs)
        try:
            hit = self._plans.get(key)  # only names pass the check below and get in
        except TypeError:  # an unhashable entry
            hit = None
        if hit is None:
            if key is not None and not all(isinstance(o, str) for o in key):
                raise ValueError(f"outputs must be a list of point or link names, got {outputs!r}")
            # the declared output is always reported (its link's angle, a slot's point,
            # line and rod): the plan of what was asked and of what it needs
            asked = None if key is None else list(dict.fromkeys([*key, *needs(self)]))
            core = self._core.plan(asked)
            names = list(self._data["points"])
            lnames = list(self._data["links"])
            steps = tuple(
                Step(kind, tuple(names[i] for i in pts), tuple(lnames[i] for i in unk))
                for kind, pts, unk in core.steps
            )
            plan = Plan(
                steps=steps,
                outputs=key,
                points=tuple(names[i] for i in core.points),
                links=tuple(lnames[i] for i in core.links),
            )
            hit = self._plans[key] = (plan, core)
        return hit

    def _default_theta(self) -> np.ndarray:
        """361 input angles from the drawn one through one full turn; for a linear input,
        361 displacements across the stroke reachable from the drawn pose (read-only,
        cached)."""
        if self._theta is None:
            stroke = None if self.input_kind == "angle" else self.stroke()
            t = self._core.default_inputs(stroke)
            t.setflags(write=False)
            self._theta = t
        return self._theta

    def _size(self) -> float:
        """The drawing's extent (its bounding box's larger side), scene units (the core's)."""
        return self._core.size

    def stroke(self) -> tuple[float, float]:
        """A linear input's reachable interval (lo <= 0 <= hi) from the drawn pose: its ends
        are the dead points where the motion stops (the kernel follows the motion out from
        the drawn pose both ways over 4 sizes of the drawing, and its step halving refines
        each end)."""
        _entry(self.input_kind == "displacement", "input", "stroke() is for a linear input")
        _, core = self._compiled(None)
        return core.stroke(self._core.size, TOL, MAX_ITER, self._max_step)

    def plan(self, outputs: Iterable[str] | str | None = None) -> Plan:
        """The steps that solve ``outputs`` (point or link names; None: the scene's
        ``outputs``, else everything; ``"all"``: everything). Each step has ``.kind``
        ("dyad" or "group"), ``.points`` (solved) and ``.unknowns`` (link angles)."""
        return self._compiled(outputs)[0]

    def sweep(
        self,
        theta: object = None,
        *,
        outputs: Iterable[str] | str | None = None,
        tol: float = TOL,
        max_iter: int = MAX_ITER,
        rate: float | None = None,
        max_step: float | None = None,
        predictor: str = "continuation",
        omega: float | None = None,
    ) -> SceneSweep:
        """Solves the plan of ``outputs`` at every input value ``theta``, following the
        drawn assembly: from the drawn value to ``theta[0]``, then along ``theta`` in order.
        For an angle input ``theta`` holds input angles (radians; default 361 angles from
        the drawn angle through one full turn); for a linear input (a slot or prismatic
        pair) it holds displacements s from the drawn pose (scene units; default 361
        values in increasing order across the interval reachable from the drawn pose, see
        :meth:`stroke`). ``sw.input_kind`` says which. A scalar ``theta`` gives a sweep of
        one row.

        Every value gets a status; a point that cannot be solved is NaN with its status,
        and points that do not depend on it are still solved. Dyads are closed forms on
        their drawn side. Groups follow by continuation in steps of at most ``max_step``
        (default 3 degrees; for a linear input, the drawing's size times 3 degrees in
        radians),
        each given at most ``min(max_iter, 5)`` Newton steps to reach ``tol`` before it is
        split (down to ``max_step / 2**16``: halved, or just short of where the group's
        conditioning extrapolates to zero). A value past a group's dead point is LIMIT,
        with the dead point's input value (within ``max_step / 2**16``) in ``sw.limit``;
        the part of the drawn circuit that lies the other way is then solved backwards from
        the drawn pose. ``rate``, the input's constant rate (an angular velocity in rad/s
        for an angle input, a linear speed in scene units per second for a linear one),
        adds point velocities and accelerations and link angular velocities and
        accelerations; ``omega`` is its former name, still accepted.

        ``predictor="closed-form"`` follows nothing: every value is solved on its own, each
        dyad and slider on its drawn side by its closed form, across values at once (plans
        with no group only: a ``ValueError`` naming ``predictor`` otherwise). A value where
        the drawn sides do not close is LIMIT where the linkage has some other assembly
        there and NOT_ASSEMBLABLE where it has none; ``limit`` is NaN. The default
        (``"continuation"``) already solves a plan with no group this way wherever that is
        certified to be the drawn circuit's motion (no step near a dead point, values at
        most ``max_step`` apart); the two differ only where the drawn circuit does not
        reach a value that the drawn sides close at.
        """
        plan, core = self._compiled(outputs)
        kind = self._kind
        if max_step is None:
            max_step = self._max_step
        if theta is None:
            t = self._default_theta()
        else:
            t = as_angles("theta", theta)
            if t.ndim == 0:  # a scalar broadcasts: a sweep of one row
                t = t.reshape(1)
            if t.ndim != 1:
                raise ValueError(f"theta must be a 1-D array of input angles, got shape {t.shape}")
        # (a float or str as given, without the call: a small sweep's arguments cost
        # about a tenth of it)
        tol = tol if type(tol) is float else as_float("tol", tol)
        max_iter = as_i64("max_iter", max_iter)
        ms = max_step if type(max_step) is float else as_float("max_step", max_step)
        if omega is not None:
            if rate is not None:
                raise TypeError("sweep() takes rate or its former name omega, not both")
            w: float | None = as_float("omega", omega)
        else:
            w = None if rate is None else as_float("rate", rate)
            if w is not None and not math.isfinite(w):  # the core would name it omega
                raise ValueError(f"rate must be finite, got {w}")
        p = predictor if type(predictor) is str else as_str("predictor", predictor)
        pts, ang, status, nit, det, limit, sst, sdet, pst, kin = core.sweep(
            t, tol, max_iter, ms, w, p
        )
        vel, acc = (None, None) if kin is None else (kin[:2], kin[2:])
        # the output coordinate is computed when it is first read
        output = None if self._data["output"] is None else self._output_of
        sw = SceneSweep.build(
            plan, t, pts, ang, status, nit, det, limit, sst, sdet, pst, vel, acc,
            w, kind, output, self._data["units"],
        )  # fmt: skip
        # the notebook picture draws the links whose points are reported (not a field:
        # the picture's, not the result's)
        sw.__dict__["_svg_links"], sw.__dict__["_svg_ground"] = self._svg
        return sw

    def _output_of(self, names: tuple[str, ...], coords: np.ndarray) -> np.ndarray | None:
        """The output coordinate along a sweep from its reported points (``names``, and
        their ``coords``); None: no output, or its points are not among those reported. A
        displacement is the core's (as the web page's)."""
        o = self.output
        if o is None:
            return None
        if "link" not in self._data["output"]:
            index = {n: i for i, n in enumerate(self._data["points"])}
            return self._core.linear_output([index[n] for n in names], np.ascontiguousarray(coords))
        link, pivot = o
        tip = next(q for q in self._data["links"][link] if q != pivot)
        if pivot not in names or tip not in names:
            return None
        v = coords[:, names.index(tip)] - coords[:, names.index(pivot)]
        return np.arctan2(v[:, 1], v[:, 0])

    # --- forces -----------------------------------------------------------------------

    def _force_args(self, sweep: SceneSweep | None, loads: Mapping[str, Any] | None,
                    rate: float | None) -> tuple[Any, SceneSweep, Any]:  # fmt: skip
        """The forces subject's structure of this scene (made once), a sweep reporting
        every point with velocities at a nonzero rate (and accelerations), and the loads."""
        from ..forces import Structure

        if self._forces is None:
            self._forces = Structure.of(self._data)
        if loads is None:
            chosen = self._data["loads"]
        else:
            # checked by the file format, as a scene's own
            chosen = Scene.from_dict({**self.to_dict(), "loads": loads})._data["loads"]
        if sweep is None:
            sweep = self.sweep(outputs="all", rate=rate or 1.0)
        complete = set(sweep.point_names) >= set(self._data["points"]) and set(
            sweep.link_names
        ) >= set(self._data["links"]) - {self._data["ground"]}
        # any nonzero rate serves: velocities are scaled to the rate asked for
        if not complete or sweep.rate in (None, 0.0) or sweep.acceleration_array is None:
            sweep = self.sweep(sweep.theta, outputs="all", rate=rate or sweep.rate or 1.0)
        return self._forces, sweep, chosen

    def statics(
        self,
        sweep: SceneSweep | None = None,
        loads: Mapping[str, Any] | None = None,
        *,
        engine: str = "rust",
    ) -> Any:
        """The input effort that holds the scene in equilibrium under its loads (or
        ``loads``, in the file format's ``loads`` form) at every input value of ``sweep``
        (default: the default sweep), with every joint reaction, by Newton-Euler, checked
        by virtual work. A sweep that lacks points or velocities is solved again at its
        input values. ``engine="numpy"`` solves with the NumPy reference instead of the
        core's kernel. Returns :class:`planarkin.forces.Forces`."""
        from ..forces import analyse

        st, sw, chosen = self._force_args(sweep, loads, None)
        return analyse(st, self._data, sw, chosen, engine=engine)

    def dynamics(
        self,
        sweep: SceneSweep | None = None,
        *,
        omega: object = None,
        alpha: object = None,
        loads: Mapping[str, Any] | None = None,
        engine: str = "rust",
    ) -> Any:
        """Inverse dynamics: :meth:`statics` with the links' inertia (d'Alembert forces
        from the sweep's accelerations) at input rate ``omega`` (rad/s, or length units per
        second for a linear input; a number or one per point; default the sweep's rate)
        and its rate of change ``alpha`` (default 0), with the shaking force and moment
        and the kinetic and potential energy, checked by the energy balance. ``engine`` as
        for :meth:`statics`."""
        from ..forces import analyse

        if omega is None:
            if sweep is None or sweep.rate is None:
                raise ValueError("omega is required (the input's rate) unless the sweep has a rate")
            omega = sweep.rate
        w = np.asarray(omega, dtype=np.float64)
        st, sw, chosen = self._force_args(sweep, loads, float(w) if w.ndim == 0 else None)
        return analyse(st, self._data, sw, chosen, omega=omega, alpha=alpha, engine=engine)

    def effort_gradient(
        self,
        free: Iterable[str],
        theta: object = None,
        *,
        measure: str = "peak",
        loads: Mapping[str, Any] | None = None,
    ) -> Any:
        """The peak (or with ``measure="rms"`` the RMS) statics input effort over the
        sweep at ``theta`` (default as :meth:`sweep`) under the scene's loads (or ``loads``),
        and its exact derivatives by the drawn coordinates named in ``free`` ("A.x", "A.y",
        "A"), input values held absolute: the poses' derivatives (:meth:`gradient`, pin-
        jointed scenes) carried through the loads and the Newton-Euler solve. Returns
        :class:`planarkin.forces.EffortGradient`."""
        from ..forces import effort_gradient, unit_names

        _entry(measure in ("peak", "rms"), "measure", f"must be 'peak' or 'rms', got {measure!r}")
        st, sw, chosen = self._force_args(None if theta is None else self.sweep(
            theta, outputs="all", rate=1.0), loads, None)  # fmt: skip
        g = self.gradient(free, sw.theta)
        names = list(self.points)
        cols = [(names.index(f.split(".")[0]), "xy".index(f.split(".")[1])) for f in g.free]
        # the gradient's sweep solved the same input values: its poses are this sweep's
        order = [g.sweep.point_names.index(p) for p in sw.point_names]
        units = unit_names(self._data["units"], self._data["unit_table"])
        return effort_gradient(
            st, self._data, sw, chosen, units, g.point_array[:, order], cols, g.free, measure
        )

    # --- every assembly, circuits, tracing ------------------------------------------------

    def _assembly(self, pts: np.ndarray, label: str, det: float, step_det: list[float]) -> Assembly:
        names = self._data["points"]
        return Assembly(
            {n: (float(x), float(y)) for n, (x, y) in zip(names, pts, strict=True)},
            det,
            tuple(step_det),
            label,
        )

    def _assemblies(self, theta: float, raw: tuple) -> Assemblies:
        items, counts, paths, failed, continua = raw
        found = [self._assembly(*a) for a in items]
        return Assemblies(found, theta, counts, failed, continua, paths=paths)

    def assemblies(
        self, theta: float | None = None, *, seed: int = SEED, runs: int = RUNS
    ) -> Assemblies:
        """Every real assembly at input angle ``theta`` (radians; default the drawn angle).

        Dyad steps contribute both sides; a group's solutions come from a homotopy on its
        loop equations (linear in the links' (cos, sin), with the unit circles; a slider's
        displacement is one more unknown), tracked ``runs`` times with independent random
        gammas (``seed``) and merged, then polished by Newton. Revolute groups start from
        the linear-product start system of the loop equations in isotropic coordinates
        (C(N, N/2) paths for N links: 20 for the double butterfly's six, where total degree
        would track 64); groups with sliders from total degree. ``complex_counts`` on the
        result is the number of finite complex solutions of each group (a self-check: 6
        for a Stephenson triad, 16 or 18 for the double butterfly's group), and ``paths``
        the paths tracked for it."""
        t = self.input_angle if theta is None else as_float("theta", theta)
        raw = self._core.assemblies(t, as_u64("seed", seed), as_i64("runs", runs))
        return self._assemblies(t, raw)

    def _trace(self, raw: tuple) -> Trace:
        theta, coords, det, turning, closed, limits = raw
        names = list(self._data["points"])
        return Trace(
            theta=theta,
            points={n: coords[:, j] for j, n in enumerate(names)},
            det=det,
            turning_points=np.asarray(turning, dtype=np.float64),
            closed=bool(closed),
            coords=coords,
            limits=np.asarray(limits, dtype=np.float64),
            input_kind=self.input_kind,
            units=self._data["units"],
        )

    def gradient(
        self, free: Iterable[str], theta: object = None, *, relative: bool = False
    ) -> SceneGradient:
        """Exact derivatives of the sweep at ``theta`` (default as :meth:`sweep`) by the
        drawn coordinates named in ``free`` ("A.x", "A.y", or "A" for both): every point's
        position and the output angle, by implicit differentiation of the whole linkage
        (one factorisation per input angle, reused for every coordinate). A drawn
        coordinate moves the shapes of the links through its point (the drawing is its own
        assembly), a ground pivot drawn there, and the drawn input angle. For synthesis:
        the design variables are drawn coordinates. Slots and prismatic pairs hold at their
        drawn offsets from their lines; scenes with a linear input are refused for now.

        ``relative=True`` holds the input at its rotation from the drawn pose rather than at
        its absolute angle, as synthesis measures its inputs: the change of the drawn input
        angle with the design is then not counted (``theta`` is still absolute, at this
        drawing)."""
        names = list(self.points)
        cols: list[tuple[int, int]] = []
        labels: list[str] = []
        for item in [free] if isinstance(free, str) else list(free):
            _entry(isinstance(item, str), "free", f"must name coordinates like 'A.x', got {item!r}")
            point, _, axis = item.partition(".")
            _entry(point in self.points, "free", f"{item!r}: no point {point!r}")
            _entry(axis in ("", "x", "y"), "free", f"{item!r}: the coordinate must be x or y")
            for a in ("x", "y") if axis == "" else (axis,):
                cols.append((names.index(point), "xy".index(a)))
                labels.append(f"{point}.{a}")
        _entry(len(set(cols)) == len(cols), "free", "names a coordinate twice")
        sw = self.sweep(theta, outputs="all")
        n, p = len(sw.theta), len(names)
        pts = np.ascontiguousarray(sw.coords.reshape(n * p, 2))
        raw = self._core.pose_gradient(pts, cols, bool(relative))
        g = raw.reshape(n, p, 2, len(cols))
        out = None
        o = self.output
        if o is not None and "link" in self._data["output"]:
            link, pivot = o
            tip = next(q for q in self._data["links"][link] if q != pivot)
            i, j = names.index(pivot), names.index(tip)
            d = sw.coords[:, j] - sw.coords[:, i]
            dd = g[:, j] - g[:, i]  # (N, 2, F)
            out = (d[:, 0, None] * dd[:, 1] - d[:, 1, None] * dd[:, 0]) / (d**2).sum(1)[:, None]
        return SceneGradient(free=tuple(labels), sweep=sw, point_array=g, output=out)

    def trace(
        self,
        start: Mapping[str, Any] | None = None,
        *,
        step: float = TRACE_STEP,
        max_points: int = TRACE_MAX_POINTS,
    ) -> Trace:
        """Traces the circuit through ``start`` (an assembly: dict point -> (x, y); default
        the drawn pose) by pseudo-arclength continuation, through dead points, until it
        comes back to its start or ``max_points`` points are made. The input angle starts
        increasing. ``step`` is the largest arclength step (radians of rotation)."""
        st = None if start is None else self._pose(start, "start")
        ms = as_i64("max_points", max_points)
        return self._trace(self._core.trace(st, as_float("step", step), ms))

    def circuits(
        self,
        theta: float | None = None,
        *,
        seed: int = SEED,
        runs: int = RUNS,
        step: float = TRACE_STEP,
        max_points: int = TRACE_MAX_POINTS,
    ) -> list[Circuit]:
        """The assemblies at ``theta`` (default the drawn angle) grouped by circuit: each
        unassigned assembly is traced once round its circuit; the assemblies the trace
        meets at ``theta`` (modulo 2 pi) are on it. Each circuit has its turning points
        and whether the input turns fully round on it."""
        t = self.input_angle if theta is None else as_float("theta", theta)
        raw_a, raw_c = self._core.circuits(
            t,
            as_u64("seed", seed),
            as_i64("runs", runs),
            as_float("step", step),
            as_i64("max_points", max_points),
        )
        found = self._assemblies(t, raw_a)
        out = []
        for idx, turning, net, rng, tr in raw_c:
            out.append(
                Circuit(
                    assemblies=[found[i] for i in idx],
                    turning_points=np.asarray(turning, dtype=np.float64),
                    full_turn=bool(math.isfinite(net) and abs(net) > math.pi),
                    net_turn=float(net),
                    range=(float(rng[0]), float(rng[1])),
                    trace=self._trace(tr),
                )
            )
        return out

    def _pose(self, pose: Mapping[str, Any], what: str) -> np.ndarray:
        return pose_array(self._data, pose, what)

    def at(self, assembly: Mapping[str, Any]) -> Scene:
        """A new scene drawn in ``assembly`` (e.g. one of :meth:`assemblies`): its sweeps
        follow that assembly's circuit."""
        return Scene(redrawn(self._data, self.to_dict(), self._pose(assembly, "assembly")))

    def as_fourbar(self) -> FourBarView:
        """This scene as a four-bar, when it is one: four links, the input and the output
        pinned to ground at its two points, the coupler joining them (it may carry tracer
        points). Returns the equivalent :class:`planarkin.FourBar` with its drawn mode and
        what relates the two frames (see :class:`FourBarView`). ValueError naming why for
        a scene that is not a four-bar, or one drawn at a dead point.
        :meth:`planarkin.FourBar.to_scene` goes the other way."""
        return fourbar_view(self._data, self.name)


# the bridge back from the four-bar (FourBar.to_scene) goes through this hook: the four-bar
# subject writes no import of this one
FourBar.scene_from_dict = Scene.from_dict

"""The Newton-Euler system of a scene, once per scene: which unknowns (each revolute pin's
force per (joint, link) pair, each slot's normal force, each prismatic pair's normal force
and moment, the input effort), which links they act on, with which sign, at which point and
along which direction. A kernel of the forces subject: it reads the scene's plain data."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

__all__ = ["Structure"]

#: Direction kinds of a force entry: the x or y axis, a line's unit normal, along a line.
EX, EY, NORMAL, ALONG = 0, 1, 2, 3


@dataclass(frozen=True)
class Structure:
    """The unknowns and where they act. Links are indexed with the moving links first (scene
    order), then ground (index ``nm``); points in the scene's order."""

    point_names: tuple[str, ...]
    #: Moving links (scene order), then ground last.
    link_names: tuple[str, ...]
    #: Number of moving links (3 equations each).
    nm: int
    #: Reference point index of each link (its first point): moments are taken about it.
    ref: np.ndarray
    #: Each unknown column: (kind, name, link) -- kind "pin" (name = joint point, link =
    #: the link it acts on; two columns, x then y), "normal" (slot or prismatic pair),
    #: "moment" (prismatic pair), "input".
    columns: tuple[tuple[str, str, str], ...]
    #: Force entries: link index, column, sign, point index, direction kind, line index.
    f_link: np.ndarray
    f_col: np.ndarray
    f_sign: np.ndarray
    f_pt: np.ndarray
    f_kind: np.ndarray
    f_line: np.ndarray
    #: Couple entries: link index, column, sign.
    c_link: np.ndarray
    c_col: np.ndarray
    c_sign: np.ndarray
    #: Lines of slots and prismatic pairs: (guide link index, point a, point b).
    lines: tuple[tuple[int, int, int], ...]
    #: Slot name -> (line index, point index, carrier link index); prismatic name ->
    #: (line index, reference point index, link index).
    slot_of: Mapping[str, tuple[int, int, int]]
    prismatic_of: Mapping[str, tuple[int, int, int]]
    #: The input column (the last) and the input's kind: "angle", "slot", "prismatic".
    input_kind: str
    input_name: str
    #: For a linear input: its (line, point, carrier link); for an angle: (-1, pivot, link).
    input_at: tuple[int, int, int]
    #: The drawing's size (moment rows are divided by it, for conditioning).
    size: float = 1.0
    #: The matrix's constant entries (flat, rows x columns): unit forces and couples.
    template: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: Moment entries of the axis-aligned (pin) forces: flat index, point, reference
    #: point, which coordinate of the arm (0: x, 1: y) and its sign.
    pin_idx: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.intp))
    pin_pt: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.intp))
    pin_ref: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.intp))
    pin_comp: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.intp))
    pin_sign: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: The moving links' equations in block-triangular order: (rows, columns, earlier
    #: columns those rows read), solved one block after another (a dyad's two links are
    #: one block of 6, the input link's one of 3).
    blocks: tuple[tuple[np.ndarray, np.ndarray, np.ndarray], ...] = ()
    #: What the Rust kernel was given for this structure (``_native``), made on first use.
    cache: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)

    @classmethod
    def of(cls, data: Mapping[str, Any]) -> Structure:
        """From a scene's data (``Scene._data``: points, links, ground, input, slots,
        prismatic); ValueError when the scene is statically indeterminate."""
        pnames = tuple(data["points"])
        pidx = {p: i for i, p in enumerate(pnames)}
        links: dict[str, tuple[str, ...]] = data["links"]
        ground = data["ground"]
        moving = [n for n in links if n != ground]
        lnames = (*moving, ground)
        lidx = {n: i for i, n in enumerate(lnames)}
        ref = np.array([pidx[links[n][0]] for n in lnames], dtype=np.intp)
        cols: list[tuple[str, str, str]] = []
        fe: list[tuple[int, int, float, int, int, int]] = []
        ce: list[tuple[int, int, float]] = []
        for p in pnames:
            on = [n for n in links if p in links[n]]
            for other in on[1:]:
                for k in (EX, EY):
                    c = len(cols)
                    cols.append(("pin", p, other))
                    fe.append((lidx[other], c, 1.0, pidx[p], k, -1))
                    fe.append((lidx[on[0]], c, -1.0, pidx[p], k, -1))
        lines: list[tuple[int, int, int]] = []
        slot_of: dict[str, tuple[int, int, int]] = {}
        for name, (q, guide, (a, b)) in data["slots"].items():
            holder = next(n for n in links if q in links[n] and n != guide)
            j = len(lines)
            lines.append((lidx[guide], pidx[a], pidx[b]))
            slot_of[name] = (j, pidx[q], lidx[holder])
            c = len(cols)
            cols.append(("normal", name, holder))
            fe.append((lidx[holder], c, 1.0, pidx[q], NORMAL, j))
            fe.append((lidx[guide], c, -1.0, pidx[q], NORMAL, j))
        prism_of: dict[str, tuple[int, int, int]] = {}
        for name, (link, guide, (a, b)) in data["prismatic"].items():
            j = len(lines)
            lines.append((lidx[guide], pidx[a], pidx[b]))
            r = pidx[links[link][0]]
            prism_of[name] = (j, r, lidx[link])
            c = len(cols)
            cols.append(("normal", name, link))
            fe.append((lidx[link], c, 1.0, r, NORMAL, j))
            fe.append((lidx[guide], c, -1.0, r, NORMAL, j))
            cols.append(("moment", name, link))
            ce.append((lidx[link], c + 1, 1.0))
            ce.append((lidx[guide], c + 1, -1.0))
        inp = data["input"]
        c = len(cols)
        if "link" in inp:
            kind, iname = "angle", str(inp["link"])
            cols.append(("input", iname, iname))
            ce.append((lidx[iname], c, 1.0))
            ce.append((lidx[ground], c, -1.0))
            at: tuple[int, int, int] = (-1, pidx[inp["pivot"]], lidx[iname])
        else:
            kind = "slot" if "slot" in inp else "prismatic"
            iname = inp[kind]
            j, pt, carrier = (slot_of if kind == "slot" else prism_of)[iname]
            guide = lines[j][0]
            cols.append(("input", iname, lnames[carrier]))
            fe.append((carrier, c, 1.0, pt, ALONG, j))
            fe.append((guide, c, -1.0, pt, ALONG, j))
            at = (j, pt, carrier)
        f = np.array(fe, dtype=np.float64).reshape(-1, 6)
        cpl = np.array(ce, dtype=np.float64).reshape(-1, 3)
        st = cls(
            point_names=pnames,
            link_names=lnames,
            nm=len(moving),
            ref=ref,
            columns=tuple(cols),
            f_link=f[:, 0].astype(np.intp),
            f_col=f[:, 1].astype(np.intp),
            f_sign=f[:, 2],
            f_pt=f[:, 3].astype(np.intp),
            f_kind=f[:, 4].astype(np.intp),
            f_line=f[:, 5].astype(np.intp),
            c_link=cpl[:, 0].astype(np.intp),
            c_col=cpl[:, 1].astype(np.intp),
            c_sign=cpl[:, 2],
            lines=tuple(lines),
            slot_of=slot_of,
            prismatic_of=prism_of,
            input_kind=kind,
            input_name=iname,
            input_at=at,
        )
        drawn = np.array([data["points"][p] for p in pnames], dtype=np.float64)[None]
        st = st._prepared(float(np.ptp(drawn[0], axis=0).max()) or 1.0)
        st._refuse_redundant(drawn)
        return st

    def _prepared(self, size: float) -> Structure:
        """With the constant part of :meth:`matrix` worked out once."""
        k = len(self.columns)
        rows = 3 * (self.nm + 1)
        tpl = np.zeros(rows * k)
        axis = self.f_kind <= EY
        r3 = 3 * self.f_link[axis]
        c = self.f_col[axis]
        kind = self.f_kind[axis]
        sign = self.f_sign[axis]
        tpl[(r3 + kind) * k + c] = sign
        tpl[(3 * self.c_link + 2) * k + self.c_col] = self.c_sign / size
        # moment of a unit x force at arm r: -r_y; of a unit y force: +r_x
        return replace(
            self,
            blocks=self._blocks(),
            size=size,
            template=tpl,
            pin_idx=(r3 + 2) * k + c,
            pin_pt=self.f_pt[axis],
            pin_ref=self.ref[self.f_link[axis]],
            pin_comp=np.where(kind == EX, 1, 0).astype(np.intp),
            pin_sign=np.where(kind == EX, -sign, sign) / size,
        )

    def directions(self, P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(n, lines, 2) unit directions u of the lines (from their first point to their
        second) and their unit normals n (u turned +90 degrees), at poses ``P``."""
        if not self.lines:
            z = np.zeros((P.shape[0], 0, 2))
            return z, z
        ab = np.array([(a, b) for _, a, b in self.lines], dtype=np.intp)
        d = P[:, ab[:, 1]] - P[:, ab[:, 0]]
        u = d / np.sqrt(d[..., 0] ** 2 + d[..., 1] ** 2)[..., None]
        return u, np.stack((-u[..., 1], u[..., 0]), axis=-1)

    def matrix(self, P: np.ndarray) -> np.ndarray:
        """(n, 3 (nm + 1), columns): each link's force (x, y) and moment about its reference
        point (divided by ``size``, for conditioning) from unit unknowns, ground's three
        rows last. ``P`` (n, points, 2) the poses."""
        n, k = P.shape[0], len(self.columns)
        rows = 3 * (self.nm + 1)
        A = np.empty((n, rows * k), dtype=P.dtype)
        A[:] = self.template
        # the arm's y (x forces) or x (y forces) coordinate: the flat (point, coordinate)
        flat = P.reshape(n, -1)
        A[:, self.pin_idx] = self.pin_sign * (
            flat[:, 2 * self.pin_pt + self.pin_comp] - flat[:, 2 * self.pin_ref + self.pin_comp]
        )
        line = self.f_kind > EY
        if line.any():
            u, nrm = self.directions(P)
            kind, j = self.f_kind[line], self.f_line[line]
            D = np.where((kind == NORMAL)[None, :, None], nrm[:, j], u[:, j])
            L, c, s = self.f_link[line], self.f_col[line], self.f_sign[line]
            Rl = P[:, self.f_pt[line]] - P[:, self.ref[L]]
            mom = (Rl[..., 0] * D[..., 1] - Rl[..., 1] * D[..., 0]) / self.size
            A[:, (3 * L) * k + c] = s * D[..., 0]
            A[:, (3 * L + 1) * k + c] = s * D[..., 1]
            A[:, (3 * L + 2) * k + c] = s * mom
        return A.reshape(n, rows, k)

    def _pattern(self) -> np.ndarray:
        """(3 nm, columns) bool: where the moving links' equations can read an unknown."""
        k = len(self.columns)
        S = np.zeros((3 * (self.nm + 1), k), dtype=bool)
        for L, c, kind in zip(self.f_link, self.f_col, self.f_kind, strict=True):
            S[3 * L + 2, c] = True
            if kind != EY:
                S[3 * L, c] = True
            if kind != EX:
                S[3 * L + 1, c] = True
        S[3 * self.c_link + 2, self.c_col] = True
        return S[: 3 * self.nm]

    def _blocks(self) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], ...]:
        """The block-triangular order of the equations (Dulmage-Mendelsohn: a matching of
        unknowns to equations, then the strongly connected components of what each
        unknown's equation reads, those read first); () when the structure has no perfect
        matching (the redundancy check then names the culprit)."""
        S = self._pattern()
        rows, k = S.shape
        if rows != k:
            return ()
        match_row = [-1] * rows  # row -> column

        def augment(col: int, seen: list[bool]) -> bool:
            for r in np.flatnonzero(S[:, col]):
                if not seen[r]:
                    seen[r] = True
                    if match_row[r] < 0 or augment(match_row[r], seen):
                        match_row[r] = col
                        return True
            return False

        for c in range(k):
            if not augment(c, [False] * rows):
                return ()
        row_of = [0] * k
        for r, c in enumerate(match_row):
            row_of[c] = r
        reads = [[int(x) for x in np.flatnonzero(S[row_of[c]]) if x != c] for c in range(k)]
        order: list[list[int]] = []
        index: dict[int, int] = {}
        low: dict[int, int] = {}
        stack: list[int] = []
        on: set[int] = set()

        def visit(v: int) -> None:  # Tarjan: a component is emitted after what it reads
            index[v] = low[v] = len(index)
            stack.append(v)
            on.add(v)
            for u in reads[v]:
                if u not in index:
                    visit(u)
                    low[v] = min(low[v], low[u])
                elif u in on:
                    low[v] = min(low[v], index[u])
            if low[v] == index[v]:
                comp = []
                while True:
                    u = stack.pop()
                    on.discard(u)
                    comp.append(u)
                    if u == v:
                        break
                order.append(sorted(comp))

        for v in range(k):
            if v not in index:
                visit(v)
        out: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        for comp in order:
            rs = np.array([row_of[c] for c in comp], dtype=np.intp)
            prior = sorted(set(np.flatnonzero(S[rs].any(axis=0)).tolist()) - set(comp))
            out.append((rs, np.array(comp, dtype=np.intp), np.array(prior, dtype=np.intp)))
        return tuple(out)

    def solve(self, A: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """x with A x = rhs for each of n systems (A (n, 3 nm, columns), the moving links'
        rows), block by block; NaN where a block is singular."""
        n = A.shape[0]
        if not self.blocks:
            return _solve(A, rhs)
        x = np.empty((n, A.shape[2]), dtype=A.dtype)
        for r, c, prior in self.blocks:
            b = rhs[:, r]
            if len(prior):
                b = b - np.einsum("nij,nj->ni", A[:, r[:, None], prior[None, :]], x[:, prior])
            if len(c) == 1:
                with np.errstate(divide="ignore", invalid="ignore"):
                    x[:, c] = b / A[:, r[0], c[0]][:, None]
            else:
                x[:, c] = _solve(A[:, r[:, None], c[None, :]], b)
        return x

    def _name(self, j: int) -> str:
        kind, name, link = self.columns[j]
        if kind == "pin":
            return f"the pin at joint {name!r} (link {link!r})"
        if kind == "normal":
            return f"the guide of {name!r}"
        return f"the rotation of prismatic pair {name!r}"

    def _refuse_redundant(self, P: np.ndarray) -> None:
        """ValueError naming the first constraint whose reaction the equations of motion
        cannot find (its column depends on earlier ones at the drawn pose)."""
        A = self.matrix(P)[0, : 3 * self.nm, :-1]
        k = A.shape[1]
        if k + 1 < 3 * self.nm:
            raise ValueError(
                f"scene: {3 * self.nm - k - 1} more degrees of freedom than one: forces need a "
                "one-degree-of-freedom scene"
            )
        rank = 0
        for j in range(k):
            r = np.linalg.matrix_rank(A[:, : j + 1], tol=1e-9 * max(1.0, np.abs(A).max()))
            if r == rank:
                raise ValueError(
                    f"scene: statically indeterminate: {self._name(j)} is redundant (its "
                    "reaction is not fixed by the equations of motion); remove it or free a "
                    "joint"
                )
            rank = r


def _solve(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Batched dense solve; a singular system's row is NaN (LAPACK refuses the batch)."""
    try:
        return np.linalg.solve(A, b[..., None])[..., 0]
    except np.linalg.LinAlgError:
        out = np.full(b.shape, np.nan, dtype=np.result_type(A, b))
        for i in range(len(A)):
            try:
                out[i] = np.linalg.solve(A[i], b[i])
            except np.linalg.LinAlgError:
                pass
        return out

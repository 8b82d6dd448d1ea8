"""Pyslvs's mechanism expression ``M[J[R, color[Green], P[x, y], L[ground, link_1]], ...]``
as plain data: ``parse`` reads it into one ``Joint`` per ``J[...]`` (or raises a one-line
ValueError naming the joint or the character), ``joint_text`` writes one back."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

#: Pyslvs's joint types: a pin (R), a prismatic pair (P), a pin in a slot (RP).
TYPES = ("R", "P", "RP")
#: A link name Pyslvs can read back (no spaces, brackets or commas).
NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_.\-]*\Z")

_TOKEN = re.compile(
    r"\s*(?:(?P<num>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)|(?P<name>[A-Za-z_][\w.\-]*)"
    r"|(?P<punct>[\[\](),]))"
)


@dataclass(frozen=True)
class Joint:
    """One ``J[...]``: its type, drawn position, slot angle (degrees; P and RP only) and
    links in the written order (for P and RP the first is the slot's link)."""

    type: str
    x: float
    y: float
    angle: float | None
    links: tuple[str, ...]


def _tokens(text: str) -> list[tuple[str, str, int]]:
    text = re.sub(r"#[^\n]*", "", text)  # Pyslvs allows comments to the end of a line
    out: list[tuple[str, str, int]] = []
    pos = 0
    while pos < len(text):
        if text[pos:].strip() == "":
            break
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            at = pos + len(text[pos:]) - len(text[pos:].lstrip())
            raise ValueError(f"pyslvs expression: unexpected {text[at]!r} at character {at}")
        kind = m.lastgroup or ""
        out.append((kind, m.group(kind), m.start(kind)))
        pos = m.end()
    return out


class _Reader:
    """Reads ``item := NAME ['[' items ']'] | NUMBER | '(' items ')'`` into nested tuples:
    (name, [items] | None), a float, or a list for a parenthesised tuple."""

    def __init__(self, text: str) -> None:
        self.toks = _tokens(text)
        self.i = 0

    def _peek(self) -> tuple[str, str, int]:
        return self.toks[self.i] if self.i < len(self.toks) else ("end", "", -1)

    def _expect(self, value: str) -> None:
        kind, v, at = self._peek()
        if v != value or kind != "punct":
            where = "the end" if kind == "end" else f"{v!r} at character {at}"
            raise ValueError(f"pyslvs expression: expected {value!r}, found {where}")
        self.i += 1

    def items(self, close: str) -> list[object]:
        out: list[object] = []
        while self._peek()[1] != close or self._peek()[0] != "punct":
            out.append(self.item())
            if self._peek()[1] == "," and self._peek()[0] == "punct":
                self.i += 1
            elif self._peek()[1] != close:
                self._expect(close)
        self._expect(close)
        return out

    def item(self) -> object:
        kind, v, at = self._peek()
        self.i += 1
        if kind == "num":
            return float(v)
        if kind == "name":
            if self._peek()[1] == "[" and self._peek()[0] == "punct":
                self.i += 1
                return (v, self.items("]"))
            return (v, None)
        if v == "(":
            return self.items(")")
        where = "the end" if kind == "end" else f"{v!r} at character {at}"
        raise ValueError(f"pyslvs expression: expected a name or a number, found {where}")


def _number(what: str, v: object) -> float:
    if not isinstance(v, float) or not math.isfinite(v):
        raise ValueError(f"{what} must be a finite number, got {_show(v)}")
    return v


def _show(v: object) -> str:
    if isinstance(v, tuple):
        return v[0] if v[1] is None else f"{v[0]}[...]"
    return repr(v)


def _joint(k: int, item: object) -> Joint:
    what = f"J{k}"
    if not (isinstance(item, tuple) and item[0] == "J" and item[1] is not None):
        raise ValueError(f"pyslvs expression: item {k} must be J[...], got {_show(item)}")
    args: list[object] = item[1]
    head = args[0] if args else None
    if not (isinstance(head, tuple) and head[1] is None and head[0] in TYPES):
        raise ValueError(f"{what}: the joint type must come first, one of R, P, RP; got "
                         f"{_show(head) if args else 'nothing'}")  # fmt: skip
    fields: dict[str, list[object]] = {}
    for a in args[1:]:
        if not (isinstance(a, tuple) and a[1] is not None):
            raise ValueError(f"{what}: expected a field like P[x, y], got {_show(a)}")
        if a[0] not in ("A", "color", "P", "L"):
            raise ValueError(f"{what}: unknown field {a[0]!r} (A, color, P, L)")
        if a[0] in fields:
            raise ValueError(f"{what}: field {a[0]} given twice")
        fields[a[0]] = a[1]
    if "P" not in fields or len(fields["P"]) != 2:
        raise ValueError(f"{what}: needs its position P[x, y]")
    x, y = (_number(f"{what}: P[...]", v) for v in fields["P"])
    links: list[str] = []
    for v in fields.get("L", []):
        if not (isinstance(v, tuple) and v[1] is None):
            raise ValueError(f"{what}: L[...] must list link names, got {_show(v)}")
        if v[0] in links:
            raise ValueError(f"{what}: link {v[0]!r} listed twice in L[...]")
        links.append(v[0])
    typ = head[0]
    angle = None
    if typ != "R":
        a = fields.get("A")
        if a is None or len(a) != 1:
            raise ValueError(f"{what}: a {typ} joint needs its slot angle A[degrees]")
        angle = _number(f"{what}: A[...]", a[0])
    return Joint(typ, x, y, angle, tuple(links))


def parse(text: str) -> list[Joint]:
    """The joints of a Pyslvs expression ``M[...]``, in order (joint k is ``J<k>``)."""
    if not isinstance(text, str):
        raise ValueError(f"pyslvs expression must be a string, got {type(text).__name__}")
    r = _Reader(text)
    top = r.item()
    if r.i != len(r.toks):
        _kind, v, at = r.toks[r.i]
        raise ValueError(f"pyslvs expression: unexpected {v!r} at character {at} after M[...]")
    if not (isinstance(top, tuple) and top[0] == "M" and top[1] is not None):
        raise ValueError(f"pyslvs expression must be M[...], got {_show(top)}")
    return [_joint(k, j) for k, j in enumerate(top[1])]


def _num(v: float) -> str:
    return repr(float(v) + 0.0)  # + 0.0: no "-0.0"


def joint_text(j: Joint) -> str:
    """``J[...]`` as Pyslvs writes it (its angle first for P and RP, color[Green])."""
    angle = "" if j.angle is None else f"A[{_num(j.angle)}], "
    return f"J[{j.type}, {angle}color[Green], P[{_num(j.x)}, {_num(j.y)}], L[{', '.join(j.links)}]]"


def text(joints: list[Joint], one_line: bool = False) -> str:
    """The expression ``M[...]``, one joint a line (or all on one)."""
    if one_line:
        return "M[" + ", ".join(joint_text(j) for j in joints) + "]"
    return "M[\n" + ",\n".join(f"  {joint_text(j)}" for j in joints) + "\n]"

"""The double butterfly as a graph: its loops, the seed's rules for choosing three
independent loops (seed 003), and design templates of both inversions as scenes."""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

#: Seed 003's type I, reconstructed in DESIGN.md (link: joints): 1 ground bar A K;
#: 2 input ternary A B C; 3 ternary B D E; 4 bar E H; 5 output ternary H I K; 6 bar D G;
#: 7 ternary F G I; 8 bar C F.
TYPE_I_LINKS: dict[str, tuple[str, ...]] = {
    "1": ("A", "K"),
    "2": ("A", "B", "C"),
    "3": ("B", "D", "E"),
    "4": ("E", "H"),
    "5": ("H", "I", "K"),
    "6": ("D", "G"),
    "7": ("F", "G", "I"),
    "8": ("C", "F"),
}


def loops(links: Mapping[str, Sequence[str]]) -> list[tuple[frozenset[str], tuple[str, ...]]]:
    """Every simple loop of a linkage whose joints each join two links: (the links it
    passes, the joints it passes in order), each loop once."""
    joint_links: dict[str, list[str]] = {}
    for name, pts in links.items():
        for p in pts:
            joint_links.setdefault(p, []).append(name)
    joints = {j: tuple(ls) for j, ls in joint_links.items() if len(ls) == 2}
    found: dict[frozenset[str], tuple[str, ...]] = {}
    names = sorted(links)

    def walk(start: str, link: str, used_links: list[str], path: list[str]) -> None:
        for j in links[link]:
            if j not in joints or (path and j == path[-1]):
                continue
            other = joints[j][0] if joints[j][1] == link else joints[j][1]
            if j in path:
                continue
            if other == start and len(used_links) >= 3 and path:
                key = frozenset(used_links)
                found.setdefault(key, tuple([*path, j]))
                continue
            if other in used_links or names.index(other) < names.index(start):
                continue
            walk(start, other, [*used_links, other], [*path, j])

    for s in names:
        walk(s, s, [s], [])
    # a loop through a link must enter and leave it by different joints: the walk's path
    # alternates joints, so each found cycle is simple by construction
    return sorted(found.items(), key=lambda kv: (len(kv[0]), sorted(kv[0])))


@dataclass(frozen=True)
class LoopChoice:
    """Three independent loops chosen by the seed's rules, with the unknown links each
    solves (loop 3's one unknown is eliminated with the generated output)."""

    loop1: frozenset[str]
    loop2: frozenset[str]
    loop3: frozenset[str]
    unknowns1: frozenset[str]
    unknowns2: frozenset[str]
    unknown3: str


def admissible_loop_choices(
    links: Mapping[str, Sequence[str]], ground: str, input: str, output: str
) -> list[LoopChoice]:
    """Ordered triples of loops by the seed's rules: loop 1 holds ground, input and
    output and has exactly two other (unknown) links; loop 2 (another loop) has exactly
    two unknown links once loop 1 is solved; loop 3 (a third loop) holds the output and
    has exactly one unknown link left."""
    for name, what in ((ground, "ground"), (input, "input"), (output, "output")):
        if name not in links:
            raise ValueError(f"{what} must be a link name, got {name!r}")
    known = {ground, input, output}
    all_loops = [ls for ls, _ in loops(links)]
    out = []
    for l1, l2, l3 in itertools.permutations(all_loops, 3):
        if not known <= l1:
            continue
        u1 = l1 - known
        if len(u1) != 2:
            continue
        u2 = l2 - known - u1
        if len(u2) != 2:
            continue
        if output not in l3:
            continue
        u3 = l3 - known - u1 - u2
        if len(u3) != 1:
            continue
        out.append(LoopChoice(l1, l2, l3, frozenset(u1), frozenset(u2), next(iter(u3))))
    return out


@dataclass(frozen=True)
class Template:
    """A double butterfly drawn as a scene skeleton: link lists, ground, input and output,
    and the seed's loop plan for the generated output (``dyads``: (point, from, from) in
    order, loop 1's then loop 2's; ``final``: (output joint, the loop-3 unknown link's
    joint on the output's side, its other joint))."""

    name: str
    links: dict[str, tuple[str, ...]]
    ground: str
    input: tuple[str, str]
    output: tuple[str, str]
    dyads: tuple[tuple[str, str, str], ...]
    final: tuple[str, str, str]
    description: str

    def scene_dict(self, points: Mapping[str, Sequence[float]], name: str | None = None) -> dict:
        """The scene (file format) of this template drawn at ``points``."""
        return {
            "name": name or self.name,
            "description": self.description,
            "points": {p: [float(points[p][0]), float(points[p][1])] for p in self.point_names},
            "links": {k: list(v) for k, v in self.links.items()},
            "ground": self.ground,
            "input": {"link": self.input[0], "pivot": self.input[1]},
            "output": {"link": self.output[0], "pivot": self.output[1]},
        }

    @property
    def point_names(self) -> tuple[str, ...]:
        seen: dict[str, None] = {}
        for pts in self.links.values():
            for p in pts:
                seen.setdefault(p, None)
        return tuple(seen)


#: Type II (ground a ternary) for steering: the ground ternary carries both kingpins KL, KR
#: and a lever pivot O; the knuckles are the binaries KL-P (input) and KR-Q (output); the
#: ternaries TL (P, H, U) and TR (Q, H, V) are hinged at H (the second butterfly); the
#: lever (O, R, S) is the ground's butterfly partner, tied to TL and TR by rods R-U, S-V.
#: Seed loops: loop 1 ground-knuckles-TL-TR (dyad at H), loop 2 ground-left knuckle-TL-
#: left rod-lever (dyad at R), loop 3 ground-right knuckle-TR-right rod-lever (the right
#: rod is the one unknown; the right knuckle splits into prescribed and generated).
STEERING_LEVER = Template(
    name="double butterfly steering linkage (type II, lever)",
    links={
        "ground": ("KL", "KR", "O"),
        "left_knuckle": ("KL", "P"),
        "right_knuckle": ("KR", "Q"),
        "TL": ("P", "H", "U"),
        "TR": ("Q", "H", "V"),
        "lever": ("O", "R", "S"),
        "left_rod": ("R", "U"),
        "right_rod": ("S", "V"),
    },
    ground="ground",
    input=("left_knuckle", "KL"),
    output=("right_knuckle", "KR"),
    dyads=(("H", "P", "Q"), ("R", "U", "O")),
    final=("Q", "V", "S"),
    description="Double butterfly of the seed's type II (ground ternary KL-KR-O): input the "
    "left knuckle KL-P, output the right knuckle KR-Q, both pivoted on the ground; ternaries "
    "TL (P, H, U) and TR (Q, H, V) hinged at H; lever O-R-S tied to them by rods R-U and S-V.",
)

#: Type II with the input the ground's butterfly partner (the seed's numbering: input link 2
#: a ternary, output link 8 a bar): the left knuckle is the ternary KL-A-C.
STEERING_KNUCKLE = Template(
    name="double butterfly steering linkage (type II, ternary knuckle)",
    links={
        "ground": ("KL", "KR", "O"),
        "left_knuckle": ("KL", "A", "C"),
        "right_knuckle": ("KR", "Q"),
        "rod_a": ("A", "K"),
        "TR": ("Q", "I", "K"),
        "rod_o": ("O", "G"),
        "TM": ("F", "G", "I"),
        "rod_c": ("C", "F"),
    },
    ground="ground",
    input=("left_knuckle", "KL"),
    output=("right_knuckle", "KR"),
    dyads=(("K", "A", "Q"), ("F", "C", "I")),
    final=("Q", "G", "O"),
    description="Double butterfly of the seed's type II (ground ternary KL-KR-O): input the "
    "left knuckle, the ternary KL-A-C hinged to the ground at KL; output the right knuckle "
    "KR-Q; ternaries TR (Q, I, K) and TM (F, G, I) hinged at I; rods A-K, C-F, O-G.",
)

#: The seed's type I (ground the bar A-K, input ternary 2 at A, output ternary 5 at K) with
#: its chosen loops: A-C-F-I-K (dyad at F), A-B-D-G-I-K (dyad at D), A-B-E-H-K (bar E-H
#: the one unknown, the output ternary split at H).
TYPE_I = Template(
    name="double butterfly type I",
    links={
        "ground": ("A", "K"),
        "input": ("A", "B", "C"),
        "T3": ("B", "D", "E"),
        "bar4": ("E", "H"),
        "output": ("K", "H", "I"),
        "bar6": ("D", "G"),
        "T7": ("F", "G", "I"),
        "bar8": ("C", "F"),
    },
    ground="ground",
    input=("input", "A"),
    output=("output", "K"),
    dyads=(("F", "C", "I"), ("D", "B", "G")),
    final=("H", "H", "E"),
    description="Seed 003's type I double butterfly: ground bar A-K, input ternary A-B-C, "
    "output ternary K-H-I; loops A-C-F-I-K, A-B-D-G-I-K, A-B-E-H-K.",
)

TEMPLATES = {"lever": STEERING_LEVER, "knuckle": STEERING_KNUCKLE, "type1": TYPE_I}

"""CI gate: no import circles between the files of planarkin, in Python or in Rust.

A circle is a set of files that import each other in a loop (a strongly connected
component of the file-level import graph with more than one file). Counted as imports:
- Python (python/planarkin): `import` and `from ... import` anywhere in a module (lazy
  imports inside functions too), relative or absolute, between modules of the package.
  Package faces (`__init__.py`) and the compiled `_core` are not nodes: a face re-exports
  its subject, and importing through it is how the subjects meet.
- Rust (each crate's src/): `use crate::...`, `use super::...`, `use self::...` and
  `crate::`/`super::` paths between the crate's files. A file's use of its own ancestors'
  `mod.rs`/`lib.rs` is not an edge (that is how a Rust module reaches the items its
  folder shares); inline `#[cfg(test)] mod tests { ... }` blocks are not read.

    python tools/import_circles.py [ROOT]    # prints each circle; exit 1 if any
"""

from __future__ import annotations

import ast
import re
import sys
from collections import defaultdict
from pathlib import Path

RUST_CRATES = ("rust/core", "rust/python", "rust/wasm")


def python_edges(root: Path) -> dict[str, set[str]]:
    pkg = root / "python"
    modules: dict[str, Path] = {}
    for path in sorted((pkg / "planarkin").rglob("*.py")):
        name = ".".join(path.relative_to(pkg).with_suffix("").parts)
        modules[name.removesuffix(".__init__")] = path
    faces = {m for m, p in modules.items() if p.name == "__init__.py"}
    edges: dict[str, set[str]] = defaultdict(set)
    for mod, path in modules.items():
        if mod in faces:
            continue
        package = mod.split(".")[:-1]
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                base = package[: len(package) - node.level + 1] if node.level else []
                target = ".".join(base + ([node.module] if node.module else []))
                names = [target] + [f"{target}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            else:
                continue
            for t in names:
                if t in modules and t != mod and t not in faces and not t.endswith("._core"):
                    edges[str(path.relative_to(root))].add(str(modules[t].relative_to(root)))
    return edges


USE = re.compile(r"\buse\s+((?:crate|super|self)(?:::\w+)*)(?:::\{([^;]*)\})?")
PATH = re.compile(r"\b((?:crate|super)(?:::\w+)+)")
INLINE_TESTS = re.compile(r"#\[cfg\(test\)\]\s*mod tests\s*\{.*", re.S)


def _owner(files: dict[tuple[str, ...], Path], parts: list[str]) -> tuple[str, ...] | None:
    """The file a module path comes from: the longest module prefix that names a file."""
    for k in range(len(parts), -1, -1):
        if tuple(parts[:k]) in files:
            return tuple(parts[:k])
    return None


def rust_edges(root: Path) -> dict[str, set[str]]:
    edges: dict[str, set[str]] = defaultdict(set)
    for crate in RUST_CRATES:
        src = root / crate / "src"
        if not src.is_dir():
            continue
        files: dict[tuple[str, ...], Path] = {}
        for path in src.rglob("*.rs"):
            parts = path.relative_to(src).with_suffix("").parts
            files[parts[:-1] if parts[-1] in ("mod", "lib") else parts] = path

        for key, path in files.items():
            text = INLINE_TESTS.sub("", path.read_text(encoding="utf-8"))
            text = re.sub(r"//[^\n]*", "", text)
            paths = []
            for m in USE.finditer(text):
                head = m.group(1).split("::")
                tails = [t.strip().split("::") for t in (m.group(2) or "").split(",") if t.strip()]
                for tail in tails or [[]]:
                    paths.append(head + [x for x in tail if re.fullmatch(r"\w+", x)])
            paths += [m.group(1).split("::") for m in PATH.finditer(text)]
            for p in paths:
                here = [] if p[0] == "crate" else list(key)
                p = p[1:] if p[0] == "crate" else p
                while p and p[0] in ("super", "self"):
                    here = here[:-1] if p[0] == "super" else here
                    p = p[1:]
                target = _owner(files, here + p)
                if target is None or target == key or key[: len(target)] == target:
                    continue
                edges[str(path.relative_to(root))].add(str(files[target].relative_to(root)))
    return edges


def circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one file (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for start in sorted(edges):
        if start in index:
            continue
        work = [(start, iter(sorted(edges.get(start, ()))))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, it = work[-1]
            nxt = next(it, None)
            if nxt is not None:
                if nxt not in index:
                    index[nxt] = low[nxt] = len(index)
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(sorted(edges.get(nxt, ())))))
                elif nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == node:
                        break
                if len(comp) > 1:
                    found.append(sorted(comp))
    return found


def main(root: Path) -> int:
    total = 0
    for language, edges in (("python", python_edges(root)), ("rust", rust_edges(root))):
        for comp in circles(edges):
            total += 1
            print(f"{language} circle of {len(comp)}: {', '.join(comp)}")
    print(f"import circles: {total}")
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()))

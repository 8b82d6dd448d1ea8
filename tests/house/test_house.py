"""The house rules of the Python layer: the extension has one door, the NumPy reference
reaches no kernel, the API loads no face, every module says what it is for, and the import
contracts in pyproject.toml hold (run with import-linter when it is installed)."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import planarkin
import pytest
from planarkin import reference as ref

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = Path(planarkin.__file__).resolve().parent


def _modules() -> list[Path]:
    return sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


def test_only_the_door_imports_the_extension():
    """Import graphs cannot see into planarkin._core; the contracts name planarkin._kernel
    instead, so no other module may reach the extension around it."""
    users = []
    for path in _modules():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names: list[str] = []
            if isinstance(node, ast.ImportFrom):
                names = [node.module or "", *(a.name for a in node.names)]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            if any(n == "_core" or n.endswith("._core") for n in names):
                users.append(path.relative_to(PACKAGE).as_posix())
    assert users == ["_kernel.py"]


def test_reference_imports_nothing_from_extension():
    """DESIGN.md: the reference must not import the extension, or parity is vacuous."""
    import ast
    import inspect

    # the API modules that wrap the kernel (the reference may use their plain results)
    wrappers = {"planarkin.fourbar", "planarkin.fourbar._model", "planarkin.fourbar._batch",
                "planarkin.scene", "planarkin.scene._model", "planarkin.simd"}  # fmt: skip
    import importlib

    modules = [ref] + [
        importlib.import_module(f"planarkin.reference.{p.stem}")
        for p in sorted((PACKAGE / "reference").glob("*.py"))
        if p.stem != "__init__"
    ]
    assert {m.__name__ for m in modules} >= {
        "planarkin.reference.fourbar",
        "planarkin.reference.scene",
    }
    for module in modules:
        src = inspect.getsource(module)
        package = module.__name__ if hasattr(module, "__path__") else module.__package__
        for node in ast.walk(ast.parse(src)):
            if isinstance(node, ast.ImportFrom):
                for door in ("_core", "_kernel"):  # the extension, and its one door
                    assert door not in (node.module or ""), node.module
                    assert all(a.name != door for a in node.names)
                parts = package.split(".")[: len(package.split(".")) - node.level + 1]
                absolute = node.module if not node.level else ".".join(
                    parts + ([node.module] if node.module else []))  # fmt: skip
                named = {absolute, *(f"{absolute}.{a.name}" for a in node.names)}
                assert not named & wrappers, (module.__name__, absolute)
            if isinstance(node, ast.Import):
                assert all("_core" not in a.name for a in node.names)


def test_the_tests_truth_imports_nothing_from_planarkin():
    """tests/truth.py is what the kernel and the reference are checked against: it must not
    compute anything with planarkin (mpmath and math only)."""
    tree = ast.parse((ROOT / "tests" / "truth.py").read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            assert not (node.module or "").startswith("planarkin"), node.module
        elif isinstance(node, ast.Import):
            assert all(not a.name.startswith("planarkin") for a in node.names)


def test_every_module_says_what_it_is_for():
    for path in _modules():
        doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8")))
        assert doc and len(doc.split()) >= 8, path.relative_to(PACKAGE)


def test_the_api_loads_no_face_and_no_matplotlib():
    code = (
        "import sys, planarkin as pk; pk.FourBar(6, 2, 5, 5).sweep().points; "
        "pk.scenes.load('jansen').sweep(); pk.reference.sweep(pk.FourBar(6, 2, 5, 5)); "
        "print(sorted(m for m in sys.modules if m.startswith(('matplotlib', 'planarkin.face'))))"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["[]"]


def test_import_contracts_hold():
    pytest.importorskip("importlinter")
    code = (
        "import sys; from importlinter.cli import lint_imports; "
        f"sys.exit(lint_imports(config_filename={str(ROOT / 'pyproject.toml')!r}, no_cache=True))"
    )
    r = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=ROOT
    )
    assert r.returncode == 0, r.stdout + r.stderr
    assert "0 broken" in r.stdout


def test_no_import_circles_in_either_language():
    """tools/import_circles.py: no files of python/planarkin, nor of the Rust crates,
    import each other in a loop."""
    r = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "import_circles.py"), str(ROOT)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.strip().splitlines()[-1] == "import circles: 0"

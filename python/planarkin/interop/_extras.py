"""The optional extras a format needs, imported when used: a missing one is a one-line
ImportError naming the ``pip install "planarkin[extra]"`` that adds it."""

from __future__ import annotations

import importlib
from types import ModuleType


def need(module: str, extra: str, what: str) -> ModuleType:
    """``module`` imported, or ImportError: ``what needs module: pip install ...``."""
    try:
        return importlib.import_module(module)
    except ImportError:
        raise ImportError(
            f'{what} needs {module.split(".")[0]}: pip install "planarkin[{extra}]"'
        ) from None

"""Progress bars of the commands (tqdm, on stderr): shown on a terminal, quiet in a pipe or
a file and with ``--quiet``; ``PLANARKIN_PROGRESS=1`` shows them anyway (``=0`` never)."""

from __future__ import annotations

import os
import sys
from typing import Any

from tqdm import tqdm

__all__ = ["ENV", "bar", "shown"]

#: The environment variable that forces the bars on (1) or off (0) whatever stderr is.
ENV = "PLANARKIN_PROGRESS"


def shown(quiet: bool = False) -> bool:
    """Whether a bar is drawn: never with ``quiet``, else as :data:`ENV` says, else when
    stderr is a terminal."""
    if quiet:
        return False
    force = os.environ.get(ENV, "").strip()
    if force:
        return force != "0"
    return sys.stderr.isatty()


def bar(total: int, what: str, *, quiet: bool = False, unit: str = "step") -> tqdm[Any]:
    """A bar of ``total`` units labelled "planarkin ``what``"; it disappears when done, so
    the command's own output stays as it is."""
    return tqdm(
        total=total,
        desc=f"planarkin {what}",
        unit=unit,
        disable=not shown(quiet),
        file=sys.stderr,
        leave=False,
        dynamic_ncols=True,
    )

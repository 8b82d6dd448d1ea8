"""Progress bars of the commands (tqdm, on stderr): shown on a terminal, quiet in a pipe or
a file and with ``--quiet``; ``PLANARKIN_PROGRESS=1`` shows them anyway (``=0`` never)."""

from __future__ import annotations

import os
import sys
from typing import Any

from tqdm import tqdm

__all__ = ["ENV", "FALLBACK_COLUMNS", "Stages", "bar", "shown"]

#: The environment variable that forces the bars on (1) or off (0) whatever stderr is.
ENV = "PLANARKIN_PROGRESS"
#: A bar's width where the terminal does not say its own (a pseudo-terminal of 0 columns,
#: stderr not a terminal): tqdm would draw nothing at 0.
FALLBACK_COLUMNS = 80


def shown(quiet: bool = False) -> bool:
    """Whether a bar is drawn: never with ``quiet``, else as :data:`ENV` says, else when
    stderr is a terminal."""
    if quiet:
        return False
    force = os.environ.get(ENV, "").strip()
    if force:
        return force != "0"
    return sys.stderr.isatty()


def _columns() -> int:
    """stderr's width in columns; 0 where it has none (not a terminal, or one that says 0)."""
    try:
        return os.get_terminal_size(sys.stderr.fileno()).columns
    except (OSError, ValueError, AttributeError):
        return 0


def bar(total: int, what: str, *, quiet: bool = False, unit: str = "step") -> tqdm[Any]:
    """A bar of ``total`` units labelled "planarkin ``what``"; it disappears when done, so
    the command's own output stays as it is. It follows the terminal's width, or is
    :data:`FALLBACK_COLUMNS` wide where the terminal has none."""
    sized = _columns() > 0
    return tqdm(
        total=total,
        desc=f"planarkin {what}",
        unit=unit,
        disable=not shown(quiet),
        file=sys.stderr,
        leave=False,
        dynamic_ncols=sized,
        ncols=None if sized else FALLBACK_COLUMNS,
    )


class Stages:
    """A long command's progress reports ``(stage, done, total)`` as one bar per stage
    labelled "planarkin ``what``: stage" (``what`` alone for the stage ""), each replaced by
    the next, a stage's total taken as it is reported; none in a pipe or with --quiet.
    ``done`` is the most reported in the stage so far; ``close`` also clears the line a bar
    cut short by Ctrl-C leaves."""

    def __init__(self, what: str, quiet: bool, unit: str = "step") -> None:
        self.what, self.quiet, self.unit = what, quiet, unit
        self.stage: str | None = None
        self.bar: Any = None
        self.done = 0

    def __call__(self, stage: str, done: int, total: int) -> None:
        if stage != self.stage or self.bar is None:
            if self.bar is not None:
                self.bar.close()
            self.stage, self.done = stage, 0
            label = f"{self.what}: {stage}" if stage else self.what
            self.bar = bar(max(int(total), 0), label, quiet=self.quiet, unit=self.unit)
        if total != self.bar.total:
            self.bar.total = total
        self.bar.update(max(0, int(done) - self.done))
        self.done = max(self.done, int(done))

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        if shown(self.quiet):
            sys.stderr.write("\r\x1b[K")
            sys.stderr.flush()

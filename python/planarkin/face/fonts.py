"""Names a user chose (a scene's, its points' and links') drawn without boxes: the
figures' font, then any CJK or emoji font installed (matplotlib falls back glyph by glyph
along the family list), and a character that no installed font has is left out of the
drawing (with a readable stand-in where nothing is left) instead of a box and a warning."""

from __future__ import annotations

import unicodedata
from functools import cache

from matplotlib import font_manager, rcParams
from matplotlib.ft2font import FT2Font

__all__ = ["FALLBACKS", "clean", "families", "use"]

#: Fonts tried, in order, after the default one for glyphs it lacks (any that is installed).
FALLBACKS = (
    "Noto Sans CJK JP",
    "Noto Sans CJK SC",
    "Source Han Sans",
    "WenQuanYi Zen Hei",
    "WenQuanYi Micro Hei",
    "Droid Sans Fallback",
    "AR PL UMing CN",
    "IPAGothic",
    "Noto Sans",
    "Noto Color Emoji",
    "Noto Emoji",
    "Symbola",
    "Segoe UI Emoji",
    "Apple Color Emoji",
)


@cache
def families() -> tuple[str, ...]:
    """The default sans-serif family, then every installed :data:`FALLBACKS` family."""
    installed = {f.name for f in font_manager.fontManager.ttflist}
    default = list(rcParams["font.family"])
    return (*default, *(f for f in FALLBACKS if f in installed))


@cache
def _codepoints() -> frozenset[int]:
    """Every character some font of :func:`families` can draw."""
    have: set[int] = set()
    for fam in families():
        try:
            path = font_manager.findfont(
                font_manager.FontProperties(family=[fam]), fallback_to_default=False
            )
            have.update(FT2Font(path).get_charmap())
        except (ValueError, OSError, RuntimeError):
            continue
    return frozenset(have)


def clean(text: str | None, default: str = "") -> str:
    """``text`` with every character no installed font draws left out (and runs of spaces
    that leaves behind collapsed); ``default`` when nothing drawable is left."""
    if not text:
        return default
    have = _codepoints()
    out = "".join(
        c for c in text if c in "\n\t" or ord(c) in have or unicodedata.category(c) in ("Zs", "Cc")
    )
    if out != text:
        out = " ".join(out.split(" "))
        out = "\n".join(" ".join(line.split()) for line in out.split("\n")).strip()
    return out or default


def use() -> None:
    """Makes the figures fall back, glyph by glyph, on every installed :data:`FALLBACKS`
    font (the command calls it once; a notebook's own settings are its own), and keeps an
    SVG figure's text as text (editable and searchable in a paper), not paths."""
    rcParams["font.family"] = list(families())
    rcParams["svg.fonttype"] = "none"

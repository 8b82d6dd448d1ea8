"""Animations as video files (MP4: H.264, WebM: VP9) through the ffmpeg that imageio-ffmpeg
ships (the optional extra ``video``): the animator's matplotlib animation, written frame
by frame; a missing extra is a one-line ImportError naming its pip install."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import matplotlib
from matplotlib.animation import FFMpegWriter, FuncAnimation

#: Video formats -> (codec, its extra ffmpeg arguments). yuv420p: what players expect;
#: the pad keeps both sides even, which H.264 and VP9 in yuv420p require.
CODECS = {
    "mp4": ("libx264", ["-pix_fmt", "yuv420p", "-crf", "20"]),
    "webm": ("libvpx-vp9", ["-pix_fmt", "yuv420p", "-b:v", "0", "-crf", "32"]),
}
_EVEN = ["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"]


def ffmpeg() -> str:
    """The ffmpeg executable of imageio-ffmpeg, or ImportError naming the extra."""
    try:
        mod: Any = importlib.import_module("imageio_ffmpeg")
    except ImportError:
        raise ImportError(
            'video (mp4, webm) needs imageio-ffmpeg: pip install "planarkin[video]"'
        ) from None
    return str(mod.get_ffmpeg_exe())


def save(
    anim: FuncAnimation,
    path: Path,
    *,
    fps: float,
    progress: Callable[[int, int], object] | None = None,
) -> Path:
    """Writes the animation as ``path`` (.mp4 or .webm); returns the path."""
    fmt = path.suffix.lstrip(".")
    if fmt not in CODECS:
        raise ValueError(f"video format must be {' or '.join(CODECS)}, got {path.suffix!r}")
    exe = ffmpeg()
    codec, args = CODECS[fmt]
    with matplotlib.rc_context({"animation.ffmpeg_path": exe}):
        # matplotlib's stub types fps as int; ffmpeg takes any positive rate
        writer = FFMpegWriter(fps=fps, codec=codec, extra_args=[*args, *_EVEN])  # type: ignore[arg-type]
        anim.save(str(path), writer=writer, progress_callback=progress)
    return path

"""``planarkin animate --format``: each format written alone; MP4 and WebM read back by
ffmpeg itself (imageio-ffmpeg: frame count, size, codec), the GIF by Pillow."""

from __future__ import annotations

import sys

import pytest
from planarkin.face.cli import main


@pytest.mark.parametrize(
    ("fmt", "codec"), [("mp4", "h264"), pytest.param("webm", "vp9", marks=pytest.mark.slow)]
)
def test_video_reads_back(fmt: str, codec: str, tmp_path) -> None:  # noqa: ANN001
    ffmpeg = pytest.importorskip("imageio_ffmpeg", reason="the video extra is not installed")
    args = ["animate", "--frames", "8", "--fps", "8", "--dpi", "41", "--out", str(tmp_path)]
    assert main([*args, "--format", fmt, "-q"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"linkage.{fmt}"]
    reader = ffmpeg.read_frames(str(tmp_path / f"linkage.{fmt}"))
    meta = next(reader)
    frames = list(reader)
    assert codec in meta["codec"]
    w, h = meta["size"]
    assert w % 2 == 0 and h % 2 == 0  # padded even for yuv420p
    assert all(len(f) == w * h * 3 for f in frames)
    assert len(frames) == 8
    assert meta["fps"] == pytest.approx(8.0)


def test_gif_alone(tmp_path) -> None:  # noqa: ANN001
    from PIL import Image

    args = ["animate", "jansen", "--frames", "5", "--dpi", "30", "--out", str(tmp_path), "-q"]
    assert main([*args, "--format", "gif"]) == 0
    assert [p.name for p in tmp_path.iterdir()] == ["linkage.gif"]
    with Image.open(tmp_path / "linkage.gif") as im:
        assert im.n_frames == 5


def test_html_alone(tmp_path) -> None:  # noqa: ANN001
    args = ["animate", "--frames", "4", "--dpi", "30", "--out", str(tmp_path), "-q"]
    assert main([*args, "--format", "html"]) == 0
    page = (tmp_path / "linkage.html").read_text()
    assert page.lstrip().lower().startswith("<!doctype html")
    assert [p.name for p in tmp_path.iterdir()] == ["linkage.html"]


def test_missing_video_extra(tmp_path, capsys, monkeypatch) -> None:  # noqa: ANN001
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)
    assert main(["animate", "--format", "mp4", "--out", str(tmp_path), "-q"]) == 1
    assert capsys.readouterr().err == (
        'planarkin: error: video (mp4, webm) needs imageio-ffmpeg: pip install "planarkin[video]"\n'
    )
    assert not (tmp_path / "linkage.mp4").exists()

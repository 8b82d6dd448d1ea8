"""The HTML animation: its nine buttons draw their icons as inline SVG
(no web font, no Unicode media symbols that Debian's default fonts lack) and it starts
playing on load. The browser checks run in headless Chromium and are skipped when no
``chromium`` is installed."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from html.parser import HTMLParser

import numpy as np
import planarkin as pk
import pytest
from planarkin.face import animate

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture(scope="module")
def page():
    sw = pk.FourBar(6, 2, 5, 5).sweep(np.radians(np.arange(0.0, 360.0, 30.0)))
    return animate.html_page(animate.fourbar(sw, 3.0, 0.5, frames=12, dpi=30), fps=10)


class Buttons(HTMLParser):
    """The text and the tags inside each <button>."""

    def __init__(self):
        super().__init__()
        self.buttons: list[dict] = []
        self.inside = False

    def handle_starttag(self, tag, attrs):
        if tag == "button":
            self.inside = True
            self.buttons.append({"title": dict(attrs).get("title"), "tags": [], "text": ""})
        elif self.inside:
            self.buttons[-1]["tags"].append(tag)

    def handle_endtag(self, tag):
        if tag == "button":
            self.inside = False

    def handle_data(self, data):
        if self.inside:
            self.buttons[-1]["text"] += data


def test_buttons_are_inline_svg_without_glyphs(page):
    """Each of the nine buttons draws its icon as inline SVG and holds no text: no Unicode
    media symbol (U+23EE..), which Debian's default fonts show as an empty box, and no web
    font."""
    p = Buttons()
    p.feed(page)
    assert len(p.buttons) == 9
    for b in p.buttons:
        assert "svg" in b["tags"] and ("polygon" in b["tags"] or "rect" in b["tags"]), b
        assert b["text"].strip() == "", b  # no character to find a font for
    assert "font-awesome" not in page and "http" not in page


def test_page_starts_playing_by_itself(page):
    (name,) = set(re.findall(r"\b(anim[0-9a-f]{32})\s*=\s*new Animation", page))
    assert f'window["{name}"]' in page and "play_animation()" in page.split("</script>")[-2]


def _chromium(*args: str, timeout: float = 120) -> str:
    out = subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout


@pytest.mark.slow  # a browser started, and three seconds of its virtual time
@pytest.mark.skipif(CHROMIUM is None, reason="no chromium installed")
def test_in_headless_chromium_it_plays_and_every_button_shows_its_icon(page, tmp_path):
    from PIL import Image

    # the button rectangles and the frame shown, written into the DOM after 1.5 s
    probe = (
        "<script>setTimeout(function () {"
        "var r = Array.prototype.map.call(document.querySelectorAll('.anim-buttons button'),"
        " function (b) { var q = b.getBoundingClientRect();"
        " return [q.left, q.top, q.width, q.height]; });"
        "document.body.setAttribute('data-rects', JSON.stringify(r));"
        "document.body.setAttribute('data-frame',"
        " document.querySelector('.anim-slider').value);"
        "}, 1500);</script></body>"
    )
    html = tmp_path / "page.html"
    html.write_text(page.replace("</body>", probe), encoding="utf-8")
    url = html.as_uri()
    dom = _chromium("--window-size=800,900", "--virtual-time-budget=3000", "--dump-dom", url)
    rects = json.loads(re.search(r'data-rects="([^"]*)"', dom).group(1).replace("&quot;", '"'))
    frame = int(re.search(r'data-frame="(\d+)"', dom).group(1))
    assert frame > 0  # it played without a click (the page opens on frame 0)
    shot = tmp_path / "shot.png"
    _chromium("--window-size=800,900", f"--screenshot={shot}", url)
    img = np.asarray(Image.open(shot).convert("L"), dtype=float)
    assert len(rects) == 9
    for x, y, w, h in rects:
        inner = img[int(y) + 4 : int(y + h) - 4, int(x) + 4 : int(x + w) - 4]
        assert inner.size and (inner < 110).sum() >= 12, (x, y, w, h)  # an icon is drawn

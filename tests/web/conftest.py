"""A headless Chromium driven by Selenium, opening the web page from ``file://``.

The page is the installed package's (``planarkin.web.FOLDER``), or the folder in
``PLANARKIN_WEB_DIR`` (CI points it at a fresh build). The tests skip, saying why, only
when Selenium, Chromium or chromedriver is missing here (``.ci/run`` installs them).
Browsers: ``PLANARKIN_CHROMIUM`` / ``PLANARKIN_CHROMEDRIVER``, else found on PATH."""

from __future__ import annotations

import json
import os
import shutil
import time
from pathlib import Path
from typing import Any

import pytest


def _find(env: str, names: tuple[str, ...]) -> str | None:
    if os.environ.get(env):
        return os.environ[env]
    return next((p for n in names if (p := shutil.which(n))), None)


@pytest.fixture(scope="session")
def page_dir() -> Path:
    from planarkin.web import FOLDER

    return Path(os.environ.get("PLANARKIN_WEB_DIR") or FOLDER).resolve()


@pytest.fixture(scope="session")
def downloads(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("downloads")


@pytest.fixture(scope="session")
def driver(downloads: Path):
    webdriver = pytest.importorskip(
        "selenium.webdriver", reason="selenium is not installed (pip install '.[web-test]')"
    )
    from selenium.webdriver.chrome.service import Service

    chromium = _find("PLANARKIN_CHROMIUM", ("chromium", "chromium-browser", "google-chrome"))
    chromedriver = _find("PLANARKIN_CHROMEDRIVER", ("chromedriver",))
    if chromium is None or chromedriver is None:
        pytest.skip(
            "no chromium or chromedriver here (Debian: apt-get install chromium chromium-driver)"
        )
    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1280,860",
              "--disable-dev-shm-usage", "--allow-file-access-from-files"):  # fmt: skip
        opts.add_argument(a)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    opts.add_experimental_option(
        "prefs",
        {"download.default_directory": str(downloads), "download.prompt_for_download": False},
    )
    d = webdriver.Chrome(service=Service(chromedriver), options=opts)
    yield d
    d.quit()


class Page:
    """The page in the browser: open a URL's query, read the exposed state and logs."""

    def __init__(self, driver: Any, folder: Path) -> None:
        self.d = driver
        self.folder = folder

    def open(self, query: str = "") -> dict:
        self.d.get_log("browser")  # drop what an earlier page logged
        self.d.get((self.folder / "index.html").as_uri() + query)
        for _ in range(200):
            if self.d.execute_script("return document.body.dataset.ready === '1'"):
                break
            time.sleep(0.05)
        else:
            raise AssertionError(f"the page did not start: {self.message()!r} {self.logs()}")
        return self.state()

    def state(self) -> dict:
        return json.loads(self.d.find_element("id", "state").get_attribute("textContent"))

    def message(self) -> str:
        return self.d.find_element("id", "message").get_attribute("textContent")

    def logs(self) -> list[dict]:
        return self.d.get_log("browser")

    def el(self, id_: str) -> Any:
        return self.d.find_element("id", id_)


@pytest.fixture
def page(driver: Any, page_dir: Path) -> Page:
    return Page(driver, page_dir)

"""The atlas tests build their default atlases into a cache of their own (never the
user's), once per session."""

import os

import pytest


@pytest.fixture(autouse=True, scope="session")
def _private_cache(tmp_path_factory):
    old = os.environ.get("PLANARKIN_CACHE")
    os.environ["PLANARKIN_CACHE"] = str(tmp_path_factory.mktemp("planarkin-cache"))
    yield
    if old is None:
        os.environ.pop("PLANARKIN_CACHE", None)
    else:
        os.environ["PLANARKIN_CACHE"] = old

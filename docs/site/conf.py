"""Sphinx configuration of the planarkin documentation site: the pages in this folder,
the API reference from the docstrings (autodoc, autosummary, napoleon) and a gallery whose
examples (examples/gallery/) run at build time (sphinx-gallery).

Build: ``pip install ".[docs]" && sphinx-build -W --keep-going -b html docs/site build/site``
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import planarkin

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
os.environ.setdefault("MPLBACKEND", "Agg")
sys.path.insert(0, str(HERE))

project = "planarkin"
author = "the planarkin authors"
copyright = "planarkin authors"  # noqa: A001 (Sphinx's name)
release = planarkin.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "sphinx_gallery.gen_gallery",
]

html_theme = "furo"
html_title = f"planarkin {release}"
exclude_patterns = ["_build", "**.ipynb_checkpoints", "gallery/*.ipynb", "gallery/*.zip"]
default_role = "code"

# the docstrings are prose (with their own field lists where they have them)
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_typehints = "description"
autodoc_member_order = "bysource"
autosummary_generate = False
napoleon_numpy_docstring = True
napoleon_google_docstring = False
# the extension's types have no module documentation of their own
nitpicky = False
# a name re-exported by a package face (pk.Scene is planarkin.scene.Scene) is one object:
# a cross-reference that finds it under both names is not ambiguous
suppress_warnings = ["autodoc.import_object", "ref.python"]

intersphinx_mapping = {
    "python": ("https://docs.python.org/3", None),
    "numpy": ("https://numpy.org/doc/stable/", None),
}
# no network at build time: intersphinx is off unless PLANARKIN_DOCS_ONLINE=1
if os.environ.get("PLANARKIN_DOCS_ONLINE") != "1":
    intersphinx_mapping = {}


sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples" / "gallery"),
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("_scraper.figure_scraper",),
    "reset_modules": ("matplotlib",),
}


def _escape_bars(app, what, name, obj, options, lines):  # noqa: ANN001, ANN202
    """The docstrings write absolute values as |x| (plain prose): escape the bars, which
    reStructuredText would read as substitution references."""
    for i, line in enumerate(lines):
        lines[i] = line.replace("|", "\\|")


def setup(app):  # noqa: ANN001, ANN201
    app.connect("autodoc-process-docstring", _escape_bars)

"""The gallery's image scraper: planarkin's figures are plain matplotlib ``Figure`` objects
(no pyplot), which sphinx-gallery's own matplotlib scraper cannot see."""

from __future__ import annotations


def figure_scraper(block, block_vars, gallery_conf):  # noqa: ANN001, ANN201
    """Saves every Figure a code block left in the example's namespace (each once)."""
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    seen = block_vars.setdefault("_planarkin_seen", set())
    paths = []
    images = block_vars["image_path_iterator"]
    for value in list(block_vars["example_globals"].values()):
        if isinstance(value, Figure) and id(value) not in seen:
            seen.add(id(value))
            path = next(images)
            value.savefig(path, dpi=80)
            paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])

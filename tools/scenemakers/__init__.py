"""The built-in scenes' generators, by family, for ``tools/make_scenes.py`` (which checks
and writes them): ``linkages`` (assembled by circle intersections), ``searched`` (seeded
searches), ``sliders`` (slots and prismatic pairs); ``geometry`` is what they share."""

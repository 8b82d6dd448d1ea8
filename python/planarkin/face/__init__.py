"""The face: everything a user looks at and nothing the API needs. ``cli`` (the
``planarkin`` command, one module per subcommand), ``draw`` (the one linkage drawer),
``animate`` (the one animator: GIF and a self-contained HTML page) and ``figures`` (the
figures of each subject). The API never imports it."""

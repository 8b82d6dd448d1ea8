"""The figures of each subject, as matplotlib Figures (object API, never pyplot):
``fourbar`` (positions, rates, transmission, convergence, coupler curve, linkage),
``scene`` (linkage, conditioning, tracers), ``circuits``, ``synthesis`` (the report's
figures) and ``tradeoff`` (the Pareto plot)."""

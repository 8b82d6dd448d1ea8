"""Path synthesis: from a curve (points, a CSV/JSON file, an SVG path) to linkages whose
tracer point follows it. Candidates come from an atlas of normalised coupler curves
(:mod:`planarkin.atlas`), are placed onto the target, refined by SLSQP with the scenes'
exact gradients under branch, order and transmission constraints, and re-verified on a
dense sweep of the real linkage."""

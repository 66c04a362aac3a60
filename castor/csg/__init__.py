"""Stage 2, the evaluated CSG tree: the scene graph at one frame's parameter values.

evaluate walks the DAG once per frame and gives a tree of plain, immutable,
picklable data (tree); transforms builds the matrices and paths names where
each piece comes from. Facetizer, ray tracer and drawings consume the tree.
"""

"""Stage 3, meshes: an evaluated CSG tree to closed, coloured polygon meshes.

facetize (the entry point) ─► primitives (triangle meshes of the unit solids)
─► instances (templates in the engine, placed copies) ─► booleans (broadphase,
adapter: manifold3d, checks, regularize) ─► provenance (triangles with their
origins and faces) ─► regularize (flat, sheets, seams) ─► merge (convex
polygons) ─► frame. caches holds what a process remembers; arrays the kit.
"""

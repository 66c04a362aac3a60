"""Stage 3, meshes: an evaluated CSG tree to closed, coloured polygon meshes.

primitives (triangle meshes of the unit solids) ─► engine (manifold3d, the
booleans) ─► polygons (triangles merged into convex polygons) ─► frame.
"""

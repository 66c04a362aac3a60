"""A third opinion for the oracle: the frame's volume from exact booleans.

When castor and the oracle (manifold3d called directly) disagree on a frame's
volume, both used manifold3d's floating-point booleans. This module asks a
third engine: libigl's mesh booleans through pymeshlab, which build the
meshes' arrangement in exact rational arithmetic (CGAL's kernel) and round
only the result's vertices to doubles. The scene comes from the oracle's
structure (its matrices and primitives' vertices), so it shares nothing with
castor either. (OpenSCAD's CGAL booleans are exact too, but its exports keep
six digits: too few to decide a disagreement of a few parts per million.)

Used by ``python -m tests.oracle --exact``; needs pymeshlab.
"""

from __future__ import annotations


import numpy as np

from .evaluate import frame_commands
from .solids import _value, primitive_solid, step_matrix

EMPTY = (np.zeros((0, 3)), np.zeros((0, 3), np.int64))


def available() -> bool:
    try:
        import pymeshlab  # noqa: F401
    except ImportError:
        return False
    return True


def _primitive(prim):
    gl = primitive_solid(prim).to_mesh64()
    return (np.array(np.asarray(gl.vert_properties)[:, :3], dtype=np.float64),
            np.asarray(gl.tri_verts, dtype=np.int64))


def _boolean(op: str, a, b):
    """a op b with libigl's exact booleans; a mesh is (vertices, triangles)."""
    import pymeshlab

    if len(a[1]) == 0 or len(b[1]) == 0:
        if op == "U":
            return b if len(a[1]) == 0 else a
        return a if op == "D" else EMPTY
    meshes = pymeshlab.MeshSet()
    for v, t in (a, b):
        meshes.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_matrix=t.astype(np.int32)))
    run = {"U": meshes.generate_boolean_union, "I": meshes.generate_boolean_intersection,
           "D": meshes.generate_boolean_difference}[op]
    try:
        run(first_mesh=0, second_mesh=1)
    except pymeshlab.PyMeshLabException as exc:
        if "empty" in str(exc):  # libigl's result had no triangle
            return EMPTY
        raise
    result = meshes.current_mesh()
    if result.face_number() == 0:
        return EMPTY
    return result.vertex_matrix().astype(np.float64), result.face_matrix().astype(np.int64)


class Evaluator:
    """The scene's frames, node by node, as the oracle evaluates them."""

    def __init__(self, scene):
        self.scene = scene

    def frames(self):
        """For each '>' command, the (vertices, triangles) of each object it writes."""
        for nodes, env, self.objects in frame_commands(self.scene):
            yield [self.node(n, dict(env)) for n in nodes]

    def node(self, node, env):
        kind = type(node).__name__
        if kind == "Ref":
            return self.node(self.objects[node.name], env)
        if kind == "Prim":
            return _primitive(node)
        if kind == "Tf":
            m = np.eye(4)
            for kind, args in node.steps:
                m = m @ step_matrix(kind, [_value(a, env) for a in args])
            v, t = self.node(node.child, env)
            v = v @ m[:3, :3].T + m[:3, 3]
            return (v, t[:, ::-1].copy()) if np.linalg.det(m[:3, :3]) < 0 else (v, t)
        if kind == "Rep":
            children = []
            saved = env.get(node.param)
            for k in range(node.count):
                env[node.param] = float(k)
                children.append(self.node(node.child, env))
            if saved is None:
                env.pop(node.param, None)
            else:
                env[node.param] = saved
        else:
            children = [self.node(c, env) for c in node.children]
        result = children[0]
        for other in children[1:]:
            result = _boolean(node.op, result, other)
        return result


def volume(mesh) -> float:
    v, t = mesh
    if len(t) == 0:
        return 0.0
    p = v[t]
    return float(np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6)


def area(mesh) -> float:
    v, t = mesh
    if len(t) == 0:
        return 0.0
    p = v[t]
    return float(np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1).sum() / 2)


def frame_figures(scene) -> list[tuple[float, float]]:
    """Each frame's exact (volume, area): sums over its objects. (The area is
    of libigl's result, whose coplanar faces are resolved exactly.)"""
    return [(sum(volume(m) for m in meshes), sum(area(m) for m in meshes))
            for meshes in Evaluator(scene).frames()]


def frame_volumes(scene) -> list[float]:
    """Each frame's exact volume: the sum over its objects."""
    return [v for v, _ in frame_figures(scene)]

"""The oracle's own evaluation of a scene: each frame's solids from
manifold3d called directly (booleans in another order than castor's), the
uses of the primitives in it, and smooth solids made with the reference
subdivision."""

from __future__ import annotations

import manifold3d
import numpy as np

from .scene import Prim, Ref, Rep, Scene, Smooth, Tf
from .solids import Use, _distinct, _use, _value, primitive_faces, primitive_solid, step_matrix, without_thin_shells


def frame_commands(scene: Scene):
    """For each '>' command: its nodes, the parameters' values then, and the
    objects defined so far (late binding: an object is evaluated there)."""
    env: dict[str, float] = {}
    objects: dict[str, object] = {}
    for s in scene.statements:
        if s[0] == "param":
            env[s[1]] = s[2]
        elif s[0] == "object":
            objects[s[1]] = s[2]
        else:
            yield s[1], dict(env), objects


class Oracle:
    """Evaluates a scene structure with manifold3d directly."""

    def __init__(self, scene: Scene):
        self.scene = scene
        self.smooth = False  # the frame holds a smooth solid the oracle made
        self.loose = False  # ... or one it could not: its surface alone is judged

    def frames(self):
        """For each '>' command: (manifolds of its objects, uses of primitives)."""
        for nodes, env, self.objects in frame_commands(self.scene):
            self.smooth = self.loose = False
            uses: list[Use] = []
            results, self.smooth_objects = [], []  # which objects hold a smooth solid it made
            for node in nodes:
                before = self.smooth
                self.smooth = False
                results.append(self.evaluate(node, dict(env), np.eye(4), "", uses))
                self.smooth_objects.append(self.smooth)
                self.smooth = self.smooth or before
            yield results, uses

    def evaluate(self, node, env, matrix, path, uses) -> manifold3d.Manifold:
        """The solid of ``node`` in its own coordinates; ``matrix`` places it in
        the world, for the faces of its primitives. (Booleans are done where
        their operands are defined, then moved, as a user reading the scene
        would: faces that meet there meet exactly.)"""
        if isinstance(node, Ref):
            return self.evaluate(self.objects[node.name], env, matrix, f"{path}({node.name})", uses)
        if isinstance(node, Prim):
            uses.append(_use(f"{path}!{node.kind}", node, matrix))
            return primitive_solid(node)
        if isinstance(node, Smooth):
            return self.smoothed(node, env, matrix, path, uses)
        if isinstance(node, Tf):
            m = np.eye(4)
            for kind, args in node.steps:
                values = [_value(a, env) for a in args]
                m = m @ step_matrix(kind, values)
            return self.evaluate(node.child, env, matrix @ m, path, uses).transform(m[:3, :])
        dot = "." if path else ""
        if isinstance(node, Rep):
            solids = []
            saved = env.get(node.param)
            for k in range(node.count):
                env[node.param] = float(k)
                solids.append(self.evaluate(node.child, env, matrix, f"{path}{dot}{node.op}{k + 1}",
                                            uses))
            if saved is None:
                env.pop(node.param, None)
            else:
                env[node.param] = saved
            op = node.op
        else:
            solids = [self.evaluate(c, env, matrix, f"{path}{dot}{node.op}{k}", uses)
                      for k, c in enumerate(node.children, 1)]
            op = node.op
        # A with A is A: the engine is not asked to unite or intersect a solid
        # with an exact copy of itself (its coincident faces are the hardest case)
        if op in "UI":
            solids = _distinct(solids)
        result = solids[0]
        for other in solids[1:]:  # one by one, left to right: not castor's order
            if op == "U":
                result = result + other
            elif op == "I":
                result = result ^ other
            else:
                result = result - other
            result = without_thin_shells(result)
        return result


    def smoothed(self, node: Smooth, env, matrix, path, uses) -> manifold3d.Manifold:
        """The oracle's own smooth solid of one primitive: its faces (placed by
        the steps below ``@s``) as the control mesh, four levels of the
        reference Catmull–Clark, the points at their limit."""
        child, below = node.child, np.eye(4)
        if isinstance(child, Tf) and isinstance(child.child, Prim):
            for kind, args in child.steps:
                below = below @ step_matrix(kind, [_value(a, env) for a in args])
            child = child.child
        solid = None
        # an extrusion of a non-convex outline: castor's control mesh has its
        # caps cut into convex polygons, the oracle's whole caps (another,
        # equally good, limit surface): judged as one it cannot make
        if isinstance(child, Prim) and node.angle != 0 and convex_caps(child):
            solid = smooth_solid(child, below, node.angle)
            if solid is None:  # every edge a crease: the primitive itself
                return self.evaluate(node.child, env, matrix, path, uses)
        if not solid:  # the oracle cannot make it: castor's surface alone is judged
            self.loose = self.loose or node.angle != 0
            before = len(uses)
            result = self.evaluate(node.child, env, matrix, path, uses)
            if node.angle != 0:  # its faces are curved: on no face of a primitive
                uses[before:] = [Use(u.path, u.colour, None) for u in uses[before:]]
            return result
        self.smooth = True
        uses.append(Use(f"{path}!{child.kind}", tuple(child.colour), None))
        return solid


def convex_caps(prim: Prim) -> bool:
    """Whether every face of the primitive is convex (an extrusion's outline
    may not be)."""
    if prim.kind != "ex":
        return True
    outline = np.array(prim.args, dtype=float).reshape(-1, 2)
    edge = np.roll(outline, -1, axis=0) - outline
    turn = edge[:, 0] * np.roll(edge, -1, axis=0)[:, 1] - edge[:, 1] * np.roll(edge, -1, axis=0)[:, 0]
    return bool((turn > 0).all() or (turn < 0).all())


def smooth_solid(prim: Prim, matrix: np.ndarray, angle: float):
    """``@s(angle)`` of a convex primitive placed by ``matrix``, as a manifold
    (None if every edge is a crease), with reference_subdivision."""
    from . import reference_subdivision as reference
    points, faces, number = [], [], {}
    own = primitive_faces(prim)  # welded in the primitive's own coordinates
    centre = np.concatenate(own).mean(axis=0)
    mirrored = np.linalg.det(matrix[:3, :3]) < 0
    for loop in own:
        normal = np.cross(loop[1] - loop[0], loop[2] - loop[0])
        if (normal @ (loop.mean(axis=0) - centre) < 0) != mirrored:
            loop = loop[::-1]  # counter-clockwise from outside, once placed
        face = []
        for p in loop.tolist():
            key = tuple(round(c, 9) for c in p)
            if key not in number:
                number[key] = len(points)
                points.append(key)
            face.append(number[key])
        faces.append(tuple(face))
    placed = np.array(points) @ matrix[:3, :3].T + matrix[:3, 3]
    points = [tuple(p) for p in placed.tolist()]
    sharp = reference.sharp_edges(points, faces, angle)
    if len(sharp) == len({frozenset((f[i], f[(i + 1) % len(f)])) for f in faces
                          for i in range(len(f))}):
        return None
    limit, quads = reference.smooth(points, faces, angle, 4)
    quads = np.array(quads, dtype=np.int64)
    triangles = np.vstack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(limit, dtype=np.float64),
                             tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64))
    solid = manifold3d.Manifold(mesh)
    if solid.status() != manifold3d.Error.NoError:
        NOT_MADE.append(solid.status())
        return False  # the oracle's own mesh refused: judged as one it cannot make
    return solid


NOT_MADE: list = []  # smooth solids whose mesh manifold3d refused

"""Random valid scenes: ``Generator`` (parameters, a DAG of named objects,
nested transformations with mirrors and ``@m``, nested booleans,
repetitions, several frames with late binding) and ``WideGenerator``
(coincident twins and turned rows mixed in)."""

from __future__ import annotations

import random

import numpy as np

from .scene import Bool, Param, Prim, Ref, Rep, Scene, Smooth, Tf
from .solids import _rotation


# --- random scenes ----------------------------------------------------------

class Generator:
    def __init__(self, rng: random.Random, prefix: str, smooth: bool = False):
        self.smooth = smooth  # put @s in the scenes (--smooth)
        self.rng = rng
        self.prefix = prefix
        self.params = [f"{prefix.upper()}P{k}" for k in range(3)]
        self.names: list[str] = []

    def colour(self):
        r = self.rng
        return (r.choice([0.0, 0.25, 0.5, 1.0]), r.choice([0.0, 0.5, 1.0]), r.choice([0.0, 0.5, 1.0]))

    def coordinate(self, scale=1.0):
        r = self.rng
        if r.random() < 0.6:  # on a grid: faces that touch and coincide
            return r.choice([-1.0, -0.5, 0.0, 0.5, 1.0, 1.5]) * scale
        return round(r.uniform(-1.5, 1.5), 3) * scale

    def maybe_param(self, value):
        r = self.rng
        if r.random() < 0.25:
            return Param(r.choice(self.params), r.choice([0.5, 1.0, -0.5, 0.25]), value)
        return value

    def primitive(self):
        r = self.rng
        kind = r.choice(["cu", "cu", "pr", "py", "we", "ex"])
        if kind in ("pr", "py"):
            return Prim(kind, self.colour(), (float(r.choice([3, 4, 5, 6, 8])),))
        if kind == "ex":
            shape = r.choice([
                [0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2],  # L
                [0, 0, 0, 2, 1, 2, 1, 1, 2, 1, 2, 0],  # L, clockwise
                [0, 0, 1, 0, 0.5, 0.8],
                [0, 0, 2, 0, 2, 2, 1.5, 2, 1.5, 0.5, 0.5, 0.5, 0.5, 2, 0, 2],  # U
            ])
            return Prim(kind, self.colour(), tuple(float(x) for x in shape))
        return Prim(kind, self.colour(), ())

    def steps(self):
        r = self.rng
        steps = []
        for _ in range(r.choice([1, 1, 1, 2, 3])):
            kind = r.choice(["t", "t", "t", "rx", "ry", "rz", "h", "h", "m", "r"])
            if kind == "t":
                steps.append(("t", tuple(self.maybe_param(self.coordinate()) for _ in range(3))))
            elif kind in ("rx", "ry", "rz"):
                angle = r.choice([90.0, 180.0, -90.0, 45.0, 30.0]) if r.random() < 0.7 else round(r.uniform(-180, 180), 2)
                steps.append((kind, (self.maybe_param(angle),)))
            elif kind == "r":
                steps.append(("r", (r.choice([1.0, 0.0]), 1.0, r.choice([0.0, 1.0, -1.0]),
                                    r.choice([90.0, 60.0, round(r.uniform(-90, 90), 1)]))))
            elif kind == "h":
                factors = [-1.0, 2.0, 0.5, 1.5, -2.0, 1.0]
                if r.random() < 0.4:
                    steps.append(("h", (r.choice(factors),)))
                else:
                    steps.append(("h", tuple(r.choice(factors) for _ in range(3))))
            else:
                a = _rotation((r.uniform(-1, 1), r.uniform(-1, 1), 1.0), r.uniform(-180, 180))[:3, :3]
                a = a @ np.diag([r.choice([1.0, -1.0, 1.5]), r.choice([1.0, 0.5]), 1.0])
                a[0, 1] += r.choice([0.0, 0.0, 0.3])  # a shear now and then
                rows = np.column_stack([np.round(a, 4), [self.coordinate() for _ in range(3)]])
                steps.append(("m", tuple(float(x) for x in rows.ravel())))
        return tuple(steps)

    def node(self, depth: int, rep_param: str | None = None):
        r = self.rng
        if self.smooth and r.random() < 0.3:
            # angles apart from the primitives' turns (90, 120, 72, 60, 45, a
            # wedge's 135, a pyramid's 101.5 to 132.7...): no edge is a crease
            # by a rounding (135 was one: castor and the oracle each rounded a
            # wedge's slope their own way); over one primitive mostly
            angle = r.choice([0.0, 30.0, 100.0, 140.0, 170.0, 180.0])
            if r.random() < 0.7:
                prim = self.primitive()
                while prim.kind == "ex":  # non-convex faces: castor cuts them up
                    prim = self.primitive()
                inner = prim if r.random() < 0.4 else Tf(self.steps(), prim)
                return Smooth(angle, inner) if rep_param is None else Tf(
                    (("t", (Param(rep_param, 1.0, 0.0), 0.0, 0.0)),), Smooth(angle, inner))
            return Smooth(angle, self.node(depth - 1, rep_param))
        choice = r.random()
        if depth <= 0 or choice < 0.25:
            leaf = Ref(r.choice(self.names)) if self.names and r.random() < 0.4 else self.primitive()
            if rep_param is not None:
                return Tf((("t", (Param(rep_param, r.choice([1.0, 0.5, 0.25]), 0.0), 0.0,
                                  Param(rep_param, r.choice([0.0, 0.5]), 0.0))),), leaf)
            return leaf if r.random() < 0.3 else Tf(self.steps(), leaf)
        if choice < 0.45:
            return Tf(self.steps(), self.node(depth - 1, rep_param))
        if choice < 0.55 and rep_param is None:
            param = f"{self.prefix.upper()}R{depth}"
            return Rep(r.choice(["U", "U", "I"]), param, r.choice([2, 3]),
                       self.node(depth - 1, param) if r.random() < 0.5
                       else Tf((("t", (Param(param, r.choice([1.0, 0.5]), 0.0), 0.0, 0.0)),),
                               self.node(depth - 1)))
        op = r.choice(["U", "U", "I", "D", "D"])
        count = 2 if op == "D" else r.choice([2, 2, 3, 4])
        children = tuple(self.node(depth - 1, rep_param if k == 0 else None) for k in range(count))
        if op == "I":  # mostly meeting operands: move them near the first
            children = children[:1] + tuple(c if r.random() < 0.5 else Tf((("t", (0.25, 0.25, 0.0)),), c)
                                            for c in children[1:])
        return Bool(op, children)

    def scene(self) -> Scene:
        r = self.rng
        scene = Scene()
        for name in self.params:
            scene.statements.append(("param", name, self.coordinate()))
        for k in range(r.choice([1, 2, 3])):
            name = f"{self.prefix}o{k}"
            scene.statements.append(("object", name, self.node(r.choice([1, 2, 3]))))
            self.names.append(name)
        for _ in range(r.choice([1, 2, 3])):
            if r.random() < 0.5:  # late binding: the objects see the new value
                scene.statements.append(("param", r.choice(self.params), self.coordinate()))
            objects = [Ref(r.choice(self.names)) if r.random() < 0.6 else self.node(2)
                       for _ in range(r.choice([1, 1, 2]))]
            scene.statements.append(("frame", objects))
        return scene


# --- wider scenes (issue 18): what the generator above almost never made ----
#
# Coincident twins: one primitive at one place in two operands of a boolean,
# each inside a boolean of its own (so both reach the engine inside results
# whose IDs castor cannot change), in colours of their own. Rows of touching
# or overlapping solids turned by angles that are not multiples of 90° about
# slanted axes, mirrored, with a pyramid or an extrusion beside a cube. The
# generator above picks each primitive, colour and placement at random, so
# two operands almost never hold the same primitive at one place; its
# repetitions are rows of 2 or 3; its turns are mostly by 90°, 45°, 30°.


class WideGenerator(Generator):
    """The generator above, with twins and turned rows mixed in."""

    def node(self, depth: int, rep_param: str | None = None):
        r = self.rng
        if depth >= 1 and rep_param is None:
            choice = r.random()
            if choice < 0.12:
                return self.coincident_twins(depth)
            if choice < 0.22:
                return self.turned_row()
        return super().node(depth, rep_param)

    def coincident_twins(self, depth: int):
        """$op($U(P, A), $op2(P', B)): P and P' the same primitive at the same
        place (colours apart), each beside something else."""
        r = self.rng
        twin = self.primitive()
        steps = self.slanted_steps() if r.random() < 0.5 else self.steps()
        again = Prim(twin.kind, self.colour(), twin.args)
        first = Bool("U", (Tf(steps, twin), self.node(depth - 1)))
        inner = r.choice(["U", "D", "U", "I"])
        others = self.node(depth - 1)
        if inner == "I":
            second = Bool("I", (Tf(steps, again), Tf(steps, Prim("cu", self.colour(), ()))))
        else:
            second = Bool(inner, (Tf(steps, again), others))
        return Bool(r.choice(["U", "D", "D", "I"]), (first, second) if r.random() < 0.7
                    else (second, first))

    def slanted_steps(self) -> tuple:
        """A turn about a slanted axis by an angle that is not a multiple of
        90°, after a mirror or a scale now and then."""
        r = self.rng
        steps = []
        if r.random() < 0.5:
            steps.append(("h", (r.choice([-1.0, 1.0]), 1.0, r.choice([1.0, 0.5, 0.4 + 0.25 * 0.5625]))))
        if r.random() < 0.5:
            steps.append(("t", (self.coordinate(), round(r.uniform(0, 0.6), 3), self.coordinate())))
        axis = (r.choice([1.0, 0.5, -1.0]), 1.0, r.choice([1.0, 0.3, -1.0]))
        angle = r.choice([round(r.uniform(-180, 180), 3), 356.731, 13.0, 75.0 + 0.289 * 45])
        steps.append(("r", axis + (angle,)))
        return tuple(steps)

    def turned_row(self):
        """A row of cubes, touching or overlapping, turned about a slanted
        axis; now and then a pyramid or an extrusion beside it."""
        r = self.rng
        param = f"{self.prefix.upper()}W{r.randrange(1000)}"
        step = r.choice([1.0, 1.0, 0.5, 0.1, 0.25])
        count = r.choice([3, 4, 6, 11])
        cube = Prim("cu", self.colour(), ())
        if r.random() < 0.3:  # each turned about z a little more, then about x
            member = Tf((("rz", (Param(param, 30.0, 0.0),)), ("rx", (30.0,)),
                         ("rx", (round(r.uniform(0, 1) * 45 + 45, 3),))), cube)
        else:
            member = Tf((("t", (Param(param, step, 0.0), 0.0, 0.0)),), cube)
        row = Rep("U", param, count, member)
        if r.random() < 0.4:
            beside = Prim(r.choice(["py", "ex"]), self.colour(), ())
            beside = self.primitive() if beside.kind == "ex" else Prim(
                "py", beside.colour, (float(r.choice([3, 4, 6, 10])),))
            row = Bool("U", (row, Tf((("t", (r.choice([-1.0, step * count, 0.5]), 0.0, 0.0)),),
                                     beside)))
        return Tf(self.slanted_steps(), row)


def scenes(count: int, seed: int, wide: bool = False, smooth: bool = False) -> list[Scene]:
    rng = random.Random(seed)
    kind = WideGenerator if wide else Generator
    return [kind(rng, f"s{k}", smooth).scene() for k in range(count)]

"""The smallest scene that still fails the same way."""

from __future__ import annotations

from .check import check_scenes
from .judge import kind_of
from .scene import Bool, Rep, Scene, Smooth, Tf


def shrink(scene: Scene, kind: str, sheets: bool = True, exact: bool = False) -> Scene:
    """A smaller scene that still fails the same way: drop statements, frames'
    extra objects, operands and transformation steps while it does."""
    def fails(candidate: Scene) -> bool:
        try:
            found = check_scenes([candidate], sheets, exact)
        except (RuntimeError, KeyError, ValueError, IndexError, ZeroDivisionError):
            return False
        return any(kind_of(p) == kind for _, _, ps in found for p in ps)

    def smaller_nodes(node):
        if isinstance(node, Tf):
            yield node.child
            for k in range(len(node.steps)):
                if len(node.steps) > 1:
                    yield Tf(node.steps[:k] + node.steps[k + 1:], node.child)
            for c in smaller_nodes(node.child):
                yield Tf(node.steps, c)
        elif isinstance(node, Bool):
            for c in node.children:
                yield c
            if node.op != "D" and len(node.children) > 2:
                for k in range(len(node.children)):
                    yield Bool(node.op, node.children[:k] + node.children[k + 1:])
            for k, child in enumerate(node.children):
                for c in smaller_nodes(child):
                    yield Bool(node.op, node.children[:k] + (c,) + node.children[k + 1:])
        elif isinstance(node, Smooth):
            yield node.child
            for c in smaller_nodes(node.child):
                yield Smooth(node.angle, c)
        elif isinstance(node, Rep):
            if node.count > 2:
                yield Rep(node.op, node.param, node.count - 1, node.child)
            for c in smaller_nodes(node.child):
                yield Rep(node.op, node.param, node.count, c)

    def candidates(s: Scene):
        st = s.statements
        for k in range(len(st)):
            if st[k][0] != "param":
                yield Scene(st[:k] + st[k + 1:])
        for k, item in enumerate(st):
            if item[0] == "frame":
                if len(item[1]) > 1:
                    for j in range(len(item[1])):
                        yield Scene(st[:k] + [("frame", item[1][:j] + item[1][j + 1:])] + st[k + 1:])
                for j, node in enumerate(item[1]):
                    for c in smaller_nodes(node):
                        yield Scene(st[:k] + [("frame", item[1][:j] + [c] + item[1][j + 1:])] + st[k + 1:])
            elif item[0] == "object":
                for c in smaller_nodes(item[2]):
                    yield Scene(st[:k] + [("object", item[1], c)] + st[k + 1:])

    improved = True
    tries = 0
    while improved and tries < 400:
        improved = False
        for candidate in candidates(scene):
            tries += 1
            if candidate.frames() and fails(candidate):
                scene = candidate
                improved = True
                break
            if tries >= 400:
                break
    return scene

"""Facets sized to the screen (``--pixel-error E``, CLI.md): the tolerances of
an evaluated tree set from a camera.

The evaluator gives every curved leaf the frame's tolerance. Seen from a
camera, a chord error of t scene units at depth z before a perspective camera
covers at most t·c·scale/z pixels (``scale`` the camera's pixels per unit on
the picture plane at distance 1, c = √(1 + a² + b²) at the picture point
(a, b) = (x/z, y/z) it is seen at, at most that of the picture's corners). So
a leaf whose box lies at depth z or more, seen within (a, b), may be faceted
within E·z/(c·scale) scene units, and an orthographic camera allows E/scale
everywhere. ``sized_to_screen`` gives
each curved primitive and each smooth solid (``@s``) that tolerance at the
nearest point of its box, in its own units, rounded down to a power of
2^(1/4) (castor.primitives.facets.quantize) so that alike leaves share one
facetization; never finer than the tolerance the evaluation gave it, and never
coarser than its own size (by then every circle has its 8 segments). A leaf
wholly outside the picture gets that coarsest tolerance; one whose box reaches
the eye's plane keeps its own. Flat primitives are left as they are, and so is
everything the camera changes nothing of: the same objects, the same keys.

A shared subtree placed in several places may need several tolerances: each
use gets the subtree its place needs, keyed by its content
(castor.csg.tree.content_key), so uses that need the same share one subtree,
made once.
"""

from __future__ import annotations

import math

from castor.csg import tree
from castor.primitives import PRIMITIVES
from castor.primitives.facets import largest_stretch, linear_part, product, quantize


def sized_to_screen(frame_tree: tree.FrameTree, picture, pixel_error: float,
                    camera=None) -> tree.FrameTree:
    """``frame_tree`` with the tolerances the camera of the picture settings
    ``picture`` (castor.settings.PictureSettings: size, view, eye, look) needs
    for a chord error of at most ``pixel_error`` pixels; or those of
    ``camera`` (castor.pictures.camera.Camera) where given: the live
    preview's, as its page looks."""
    screen = Screen(camera if camera is not None else frame_camera(frame_tree, picture),
                    pixel_error)
    objects = tuple(_sized(obj, screen) for obj in frame_tree.objects)
    if all(new is old for new, old in zip(objects, frame_tree.objects)):
        return frame_tree
    return frame_tree.replace(objects=objects)


def _sized(obj: tree.Object, screen: "Screen") -> tree.Object:
    root = obj.root if obj.root is None else screen.node(obj.root, tree.IDENTITY)
    return obj if root is obj.root else obj.replace(root=root)


def frame_camera(frame_tree: tree.FrameTree, picture):
    """The camera of the picture options (castor.pictures.camera.make_camera),
    framing the box of the frame's solids where it frames anything."""
    from castor.pictures.camera import make_camera

    if picture.eye is not None and picture.look is not None:
        low = high = (0.0, 0.0, 0.0)
    else:
        low, high = frame_box(frame_tree)
    return make_camera(low, high, picture.size, picture.view, picture.eye, picture.look)


def frame_box(frame_tree: tree.FrameTree) -> tuple[tuple, tuple]:
    """The box of the frame's solids, as the ray tracer bounds them: a union's
    operands' boxes, an intersection's common part, a difference's first operand."""
    known: dict[str, object] = {}
    boxes = [_box(obj.root, tree.IDENTITY, known) for obj in frame_tree.objects
             if obj.root is not None]
    return _union([b for b in boxes if b is not None]) or ((0.0,) * 3, (0.0,) * 3)


def _box(node, matrix, known: dict):
    kind = type(node)
    if kind is tree.Primitive:
        low, high = PRIMITIVES[node.kind].box(node.shape)
        return tree.placed_box(tree.compose(matrix, node.matrix), low, high)
    if kind is tree.Boolean:
        boxes = [_box(o, matrix, known) for o in node.operands]
        if node.op == "D":
            return boxes[0] if boxes else None
        if node.op == "I":
            return _intersection(boxes)
        return _union([b for b in boxes if b is not None])
    if kind is tree.Smooth:  # a smooth solid lies within its control mesh's box
        return _box(node.operand, tree.compose(matrix, node.matrix), known)
    shared = node.shared
    if shared.key not in known:
        known[shared.key] = (None if shared.child is None
                             else _box(shared.child, tree.IDENTITY, known))
    own = known[shared.key]
    return None if own is None else tree.placed_box(tree.compose(matrix, node.matrix), *own)


def _union(boxes):
    if not boxes:
        return None
    return (tuple(min(b[0][i] for b in boxes) for i in range(3)),
            tuple(max(b[1][i] for b in boxes) for i in range(3)))


def _intersection(boxes):
    if not boxes or any(b is None for b in boxes):
        return None
    low = tuple(max(b[0][i] for b in boxes) for i in range(3))
    high = tuple(min(b[1][i] for b in boxes) for i in range(3))
    return None if any(lo > hi for lo, hi in zip(low, high)) else (low, high)


class Screen:
    """The tolerances one camera needs: ``node`` gives a subtree with them."""

    def __init__(self, camera, pixel_error: float):
        self.error = pixel_error
        self.eye = tuple(float(x) for x in camera.eye)
        self.forward = tuple(float(x) for x in camera.forward)
        self.right = tuple(float(x) for x in camera.right)
        self.up = tuple(float(x) for x in camera.up)
        self.scale = camera.scale
        self.orthographic = camera.orthographic
        half_w, half_h = camera.width / 2 / self.scale, camera.height / 2 / self.scale
        self.half = (half_w, half_h)  # tangents (perspective) or scene units (orthographic)
        # scene point -> the camera's frame (right, up, forward from the eye)
        rows = (self.right, self.up, self.forward)
        self.view = tuple(v for axis in rows for v in
                          (*axis, -sum(a * e for a, e in zip(axis, self.eye))))
        self.shared: dict[str, tree.Shared] = {}  # the subtrees made, by key
        self.leaf_memo: dict[int, tuple] = {}  # id(leaf) -> (leaf, its unit box, stretch, ...)
        self.stretches: dict[tuple, float] = {}  # a linear map's largest stretch
        self.curved: dict[str, bool] = {}  # whether a shared subtree holds anything curved

    # --- what one box needs, in scene units
    def world_tolerance(self, matrix, low, high) -> float | None:
        """The chord error that covers at most E pixels anywhere in the box
        (low, high) moved by ``matrix``: 0 where it reaches the eye's plane,
        None where the camera does not see it at all."""
        # the box's corners in the camera's frame: across, up, along the line of sight
        m = tree.compose(self.view, matrix)
        corners = [(m[0] * x + m[1] * y + m[2] * z + m[3], m[4] * x + m[5] * y + m[6] * z + m[7],
                    m[8] * x + m[9] * y + m[10] * z + m[11])
                   for x in (low[0], high[0]) for y in (low[1], high[1])
                   for z in (low[2], high[2])]
        half_w, half_h = self.half
        if self.orthographic:
            if (all(c[0] > half_w for c in corners) or all(c[0] < -half_w for c in corners)
                    or all(c[1] > half_h for c in corners)
                    or all(c[1] < -half_h for c in corners)):
                return None
            return self.error / self.scale
        if (all(c[0] > half_w * c[2] for c in corners)
                or all(c[0] < -half_w * c[2] for c in corners)
                or all(c[1] > half_h * c[2] for c in corners)
                or all(c[1] < -half_h * c[2] for c in corners)):
            return None  # wholly beyond one side of the picture (or behind the eye)
        if all(c[2] <= 0 for c in corners):
            return None  # behind the eye
        near = min(c[2] for c in corners)
        if near <= 0:
            return 0.0
        # how much more than at the picture's centre a length across the line of
        # sight covers on the picture, at most, where the box shows: √(1 + a² + b²)
        # at the picture coordinates (a, b) = (x/z, y/z), which lie between those
        # of its corners (all before the eye) and within the picture
        a = min(max(abs(c[0]) / c[2] for c in corners), half_w)
        b = min(max(abs(c[1]) / c[2] for c in corners), half_h)
        return self.error * near / (math.sqrt(1 + a * a + b * b) * self.scale)

    # --- the tree
    def node(self, node, matrix, above: float = 1.0):
        """``node`` (placed in the scene by ``matrix``; its tolerances in units
        that are ``above`` scene units at most) with the camera's tolerances:
        the same object where nothing changes."""
        kind = type(node)
        if kind is tree.Primitive:
            return self._primitive(node, matrix, above)
        if kind is tree.Boolean:
            operands = tuple(self.node(o, matrix, above) for o in node.operands)
            if all(new is old for new, old in zip(operands, node.operands)):
                return node
            return tree.Boolean(node.op, operands, node.location)
        if kind is tree.Smooth:
            return self._smooth(node, matrix)
        return self._use(node, matrix)

    def _primitive(self, leaf: tree.Primitive, matrix, above: float) -> tree.Primitive:
        known = self.leaf_memo.get(id(leaf))
        if known is None or known[0] is not leaf:
            known = self.leaf_memo[id(leaf)] = self._leaf_figures(leaf)
        _, curved, low, high, linear, stretch, extent, counts = known
        if not curved:
            return leaf
        world = self.world_tolerance(tree.compose(matrix, leaf.matrix), low, high)
        tolerance = _bounded(world, above, leaf.tolerance, stretch * extent, stretch)
        if tolerance == leaf.tolerance:
            return leaf
        same = counts.get(tolerance)
        if same is None:
            same = counts[tolerance] = (PRIMITIVES[leaf.kind].facet_counts(leaf.shape, linear, tolerance)
                                  == counts[None])
        return leaf if same else leaf.replace(tolerance=tolerance)

    def _leaf_figures(self, leaf: tree.Primitive) -> tuple:
        """What does not change from one use of a leaf to the next: whether it is
        curved, its unit box, its linear map, that map's largest stretch, its
        extent, and its facet counts (None: with its own tolerance)."""
        declared = PRIMITIVES[leaf.kind]
        if not declared.curved:
            return (leaf, False) + (None,) * 6
        low, high = declared.box(leaf.shape)
        linear = linear_part(leaf.matrix)
        if leaf.metric is not None:
            linear = product(leaf.metric, linear)
        counts = {None: declared.facet_counts(leaf.shape, linear, leaf.tolerance)}
        return (leaf, True, low, high, linear, self._largest(linear), declared.extent(leaf.shape),
                counts)

    def _largest(self, linear) -> float:
        found = self.stretches.get(linear)
        if found is None:
            found = self.stretches[linear] = largest_stretch(linear)
        return found

    def _smooth(self, node: tree.Smooth, matrix) -> tree.Smooth:
        placed = tree.compose(matrix, node.matrix)
        boxes = [tree.placed_box(m, *PRIMITIVES[leaf.kind].box(leaf.shape))
                 for leaf, m, _ in tree.leaves(node.operand)]
        own = _union(boxes)
        if own is None:
            return node
        world = self.world_tolerance(placed, *own)
        size = math.dist(*own)  # in its own units
        tolerance = _bounded(world, self._largest(linear_part(placed)), node.tolerance, size)
        if tolerance == node.tolerance:
            return node
        return tree.Smooth(node.angle, node.matrix, node.operand, tolerance,
                           tree.smooth_key(node.angle, tolerance, node.operand), node.location)

    def _use(self, use: tree.Use, matrix) -> tree.Use:
        shared = use.shared
        if shared.child is None or not self._holds_curved(shared):
            return use
        placed = tree.compose(matrix, use.matrix)
        child = self.node(shared.child, placed, self._largest(linear_part(placed)))
        if child is shared.child:
            return use
        key = tree.content_key(shared.name, child)
        made = self.shared.get(key)
        if made is None:
            made = self.shared[key] = tree.Shared(shared.name, child, key, shared.location)
        return tree.Use(use.matrix, use.path, made)

    def _holds_curved(self, shared: tree.Shared) -> bool:
        """Whether a curved primitive or a smooth solid lies below."""
        found = self.curved.get(shared.key)
        if found is None:
            found = self.curved[shared.key] = self._curved_below(shared.child)
        return found

    def _curved_below(self, node) -> bool:
        kind = type(node)
        if kind is tree.Primitive:
            return PRIMITIVES[node.kind].curved
        if kind is tree.Boolean:
            return any(self._curved_below(o) for o in node.operands)
        if kind is tree.Smooth:
            return True
        return node.shared.child is not None and self._holds_curved(node.shared)


def _bounded(world: float | None, above: float, finest: float, size: float,
             unit: float = 1.0) -> float:
    """A tolerance in units of which one is ``above`` scene units at most: the
    scene's ``world`` (None: the coarsest) rounded down, no finer than
    ``finest`` and no coarser than the first power of 2^(1/4) beyond four times
    ``size`` (any coarser makes no fewer facets). It is rounded as a multiple
    of ``unit``, the primitive's own stretch, which its facet counts divide it
    by and round again (castor.primitives.facets): so that a uniform scale is
    rounded once."""
    coarsest = 2.0 ** (math.ceil(math.log2(max(4 * size, 1e-300)) * 4 - 1e-9) / 4)
    if world is None:
        tolerance = coarsest
    elif world <= 0 or above <= 0:
        return finest
    else:
        tolerance = min(quantize(world / above / unit) * unit, coarsest)
    return max(tolerance, finest)


def kept_where_close(previous: tree.FrameTree | None, needed: tree.FrameTree,
                     factor: float = 2.0) -> tree.FrameTree:
    """The live preview's rule once its camera stops (CLI.md, "Live preview"):
    ``needed`` (the frame sized to the new view) with each curved leaf and
    smooth solid as ``previous`` had it (the frame as last faceted: sized to
    the view before, or evaluated before an edit) wherever the tolerance it
    needs is within ``factor`` of the one it has, so that only those whose
    facets would change much are faceted again: the others keep their
    tolerance, hence their facetization in the facetizer's caches (a boolean
    above a changed leaf is made again). A leaf is kept only if all but its
    tolerance is the same; an object wholly kept is ``previous``'s own."""
    if previous is None or len(previous.objects) != len(needed.objects):
        return needed
    memo: dict = {}
    objects = tuple(_kept_object(old, new, factor, memo)
                    for old, new in zip(previous.objects, needed.objects))
    if all(new is kept for new, kept in zip(needed.objects, objects)):
        return needed
    return needed.replace(objects=objects)


def _kept_object(old: tree.Object, new: tree.Object, factor: float, memo: dict) -> tree.Object:
    if old is new or old.name != new.name or old.root is None or new.root is None:
        return new
    root = _kept(old.root, new.root, factor, memo)
    if root is old.root:
        return old if old.where == new.where else new.replace(root=root)
    return new if root is new.root else new.replace(root=root)


def _within(old: float, new: float, factor: float) -> bool:
    return new / factor <= old <= new * factor


def _kept(old, new, factor: float, memo: dict):
    """``new`` with what ``old`` had wherever only a tolerance differs, by no
    more than ``factor``: ``old`` itself where all of it is kept, ``new``
    where none of it is."""
    if old is new:
        return old
    kind = type(new)
    if kind is not type(old):
        return new
    if kind is tree.Primitive:
        if (old.kind != new.kind or old.shape != new.shape or old.colour != new.colour
                or old.matrix != new.matrix or old.metric != new.metric
                or old.path != new.path or not _within(old.tolerance, new.tolerance, factor)):
            return new
        return old if old.location == new.location else new.replace(tolerance=old.tolerance)
    if kind is tree.Boolean:
        if old.op != new.op or len(old.operands) != len(new.operands):
            return new
        operands = tuple(_kept(a, b, factor, memo) for a, b in zip(old.operands, new.operands))
        if all(k is a for k, a in zip(operands, old.operands)):
            return old
        if all(k is b for k, b in zip(operands, new.operands)):
            return new
        return tree.Boolean(new.op, operands, new.location)
    if kind is tree.Smooth:  # one smoothing: kept whole or made again
        same = (old.angle == new.angle and old.matrix == new.matrix
                and _within(old.tolerance, new.tolerance, factor)
                and _kept(old.operand, new.operand, factor, memo) is old.operand)
        return old if same else new
    if old.matrix != new.matrix or old.path != new.path or old.shared.name != new.shared.name:
        return new
    return _kept_use(old, new, factor, memo)


def _kept_use(old: tree.Use, new: tree.Use, factor: float, memo: dict) -> tree.Use:
    pair = (old.shared.key, new.shared.key)
    shared = memo.get(pair)
    if shared is None:
        a, b = old.shared.child, new.shared.child
        if a is None or b is None:
            shared = new.shared
        else:
            child = _kept(a, b, factor, memo)
            shared = (old.shared if child is a else new.shared if child is b
                      else tree.Shared(new.shared.name, child,
                                       tree.content_key(new.shared.name, child),
                                       new.shared.location))
        memo[pair] = shared
    if shared is old.shared:
        return old
    return new if shared is new.shared else tree.Use(new.matrix, new.path, shared)

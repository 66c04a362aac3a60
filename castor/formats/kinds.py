"""The kinds of output: each makes its product from a frame's evaluated tree.

A kind is one object that knows how to make what its formats write from a
frame's evaluated CSG tree (castor.csg.tree.FrameTree) and the frame's settings
(castor.settings.FrameSettings): a mesh frame for the polygon stream and the
mesh files, a picture, a drawing laid on its sheet, a building model. Every
format of a kind has one writer over that product (castor.formats). The kind
also says which options act on it (castor.options.OUTPUT_OPTIONS declares
them) and what it adds to --stats and --summary.

This module is read at start-up with the table of formats: it imports the
stages (facetizer, ray tracer, drawings) only where a product is made.
"""

from __future__ import annotations

import time
from typing import Callable, NamedTuple


class Framing(NamedTuple):
    """A frame of an animation before it is drawn: its tree, to be drawn with one
    camera for every frame, and its box (None: nothing to draw)."""

    tree: object  # castor.csg.tree.FrameTree
    box: tuple | None


class BuildingModel(NamedTuple):
    """What a building model's formats write: the frame's storeys, elements,
    openings and spaces (castor.bim.Building), made from its tree and polygons
    with the title and each object's class (--ifc-class)."""

    building: object  # castor.bim.Building


class Kind:
    """One kind of output. ``make`` gives its product for one frame (or None:
    nothing to write), adding to ``made`` (castor.jobs.Result) the frame's warnings,
    its --stats line and --summary record, and its mesh where the settings keep it."""

    name = ""
    plural = ""  # what messages call its outputs ("pictures")
    options: tuple[str, ...] = ()  # the output options that act on it (castor.options)
    streamed = False  # frames follow one another in one file
    polygons = False  # its product is polygons (castor-view reads its files)

    def make(self, tree, settings, chosen, made):
        raise NotImplementedError

    def weight(self, product) -> int:
        """Polygons in ``product``: a large one made by a worker process is spooled."""
        return 0

    def gather(self, parts: list, settings, each: Callable) -> object:
        """The product of a format made from every frame at once, from each frame's
        part (what ``make`` gave); ``each(function, *lists)``, as ``map``, may
        run the calls in other processes."""
        raise NotImplementedError(f"{self.name} outputs are made frame by frame")

    def after_run(self, settings, objects: set[str]) -> list[str]:
        """Warnings once the whole scene is evaluated (``objects``: its object names)."""
        return []

    def __repr__(self):
        return f"<kind {self.name}>"

    def __reduce__(self):  # pickled by name: the same object in every process
        return (_kind_named, (self.name,))


_facetizers: dict[tuple, object] = {}


def facetizer_for(mesh, merge: bool):
    """This process's facetizer for these mesh settings: its caches of shared
    subtrees and primitive shapes serve every frame it makes."""
    from castor.mesh.facetize import Facetizer

    key = (mesh.max_polygons, merge)
    facetizer = _facetizers.get(key)
    if facetizer is None:
        facetizer = _facetizers[key] = Facetizer(mesh.max_polygons, merge)
    return facetizer


def _empty(tree) -> str:
    from castor.csg.emptiness import empty_message  # as --check says it

    return empty_message(tree.number)


def _polygons(tree, settings, made, merge: bool = True):
    """The frame's polygons (a warning when there are none), and its facetizer."""
    facetizer = facetizer_for(settings.mesh, merge)
    frame = facetizer.frame(tree)
    if frame.polygon_count == 0 and not tree.spaces:  # rooms only: not an empty frame
        made.warnings.append((_empty(tree), tree.location))
    return frame, facetizer


def _warner(made, tree) -> Callable[[str], None]:
    """``warn(message)`` for the frame's take-off and model: each warning once
    (the IFC and its --summary both judge the openings)."""
    def warn(message: str) -> None:
        if (message, tree.location) not in made.warnings:
            made.warnings.append((message, tree.location))
    return warn


def _figures(settings, made, frame, facetizer, tree=None) -> None:
    """The mesh frame kept where asked, its --stats line and --summary record
    (with the frame's tree, its take-off by class too: LANGUAGE.md §11)."""
    output = settings.output
    if output.keep_mesh:
        made.mesh = frame
    if output.stats or output.summary:
        from castor.quantities import stats_line, summary_record

        stats = facetizer.stats
        if output.stats:
            made.stats = stats_line(frame, stats.primitives, stats.booleans, stats.seconds)
        if output.summary:
            made.summary = summary_record(frame, tree, facetizer, _warner(made, tree))


class Polygons(Kind):
    """The frame's polygons: the polygon stream and the mesh files."""

    polygons = True

    def __init__(self, name: str, plural: str, streamed: bool = False):
        self.name, self.plural, self.streamed = name, plural, streamed

    options = ("--pixel-error",)

    def make(self, tree, settings, chosen, made):
        # a file of triangles skips merging them into polygons, unless the take-off
        # counts the frame's polygons
        merge = chosen is None or not chosen.triangles_only or settings.output.summary
        if settings.mesh.pixel_error is not None:  # facets sized to the screen
            from castor.mesh.screen import sized_to_screen

            tree = sized_to_screen(tree, settings.picture, settings.mesh.pixel_error)
        frame, facetizer = _polygons(tree, settings, made, merge)
        _figures(settings, made, frame, facetizer, tree)
        return frame

    def weight(self, product) -> int:
        return product.polygon_count


class Pictures(Kind):
    """A picture ray traced from the exact solids (castor.pictures), never facetized."""

    name, plural = "picture", "pictures"
    options = ("--size", "--view", "--eye", "--look", "--sun", "--samples", "--edges")

    def make(self, tree, settings, chosen, made):
        from castor import pictures
        from castor.pictures.trace import compile_frame

        started = time.perf_counter()
        compiled = compile_frame(tree)
        empty = pictures.probe(compiled)
        if empty is None:  # no ray met anything: only the polygons can tell
            empty = facetizer_for(settings.mesh, True).frame(tree).polygon_count == 0
        if empty and not tree.spaces:
            made.warnings.append((_empty(tree), tree.location))
        if chosen.gathers:  # an animation is drawn at the end, one camera for all its frames
            product = Framing(tree, compiled.box if compiled.root is not None else None)
        else:
            product = pictures.draw(compiled, settings.picture)
        spec = settings.picture
        if settings.output.stats:
            made.stats = (f"castor: frame {tree.number} {tree.where}: picture "
                          f"{spec.size[0]}x{spec.size[1]}, {spec.samples} samples per pixel, "
                          f"{time.perf_counter() - started:.3f} s")
        if settings.output.summary:  # the take-off is written whatever the output (OUTPUT.md)
            from castor.quantities import summary_record

            facetizer = facetizer_for(settings.mesh, True)
            made.summary = summary_record(facetizer.frame(tree), tree, facetizer,
                                          _warner(made, tree))
        return product

    def gather(self, parts: list, settings, each: Callable) -> list:
        """Every frame's picture, from one camera that frames them all (it does not jump)."""
        from castor.pictures import draw_tree, framing

        camera, ground = framing([part.box for part in parts if part.box is not None],
                                 settings.picture)
        n = len(parts)
        return list(each(draw_tree, [part.tree for part in parts], [camera] * n,
                         [settings.picture] * n, [ground] * n))


class Drawings(Kind):
    """A plan, section or elevation laid on its sheet (castor.drawings)."""

    name, plural = "drawing", "drawings"
    options = ("--view", "--section", "--scale", "--sheet", "--title", "--project", "--number",
               "--revision", "--drawn", "--checked", "--sheets")

    def make(self, tree, settings, chosen, made):
        from castor.drawings import sheet_of

        frame, facetizer = _polygons(tree, settings, made)
        warn = lambda message: made.warnings.append((message, tree.location))  # noqa: E731
        if settings.drawing.register is not None:
            from castor.drawings import set_of

            sheet = set_of(tree, frame, settings.drawing, settings.output.title, warn,
                           facetizer, settings.output.target)
        else:
            sheet = sheet_of(tree, frame, settings.drawing, settings.output.title, warn,
                             facetizer)
        if settings.output.format == "pdf":  # its fonts may lack some of the texts' characters
            from castor.formats._pdf_fonts import missing_glyphs_warning

            missing_glyphs_warning(sheet, warn)
        _figures(settings, made, frame, facetizer, tree)
        return sheet


class BuildingModels(Kind):
    """A building model (castor.bim): storeys, the elements of the classes the
    annotations (or --ifc-class) give, openings filled by doors and windows, spaces."""

    name, plural = "bim", "building models"
    options = ("--title", "--ifc-class")

    def make(self, tree, settings, chosen, made):
        from castor.bim import build

        frame, facetizer = _polygons(tree, settings, made)
        building = build(tree, frame, facetizer, settings.output.title,
                         dict(settings.bim.classes), _warner(made, tree))
        _figures(settings, made, frame, facetizer, tree)
        return BuildingModel(building)

    def after_run(self, settings, objects: set[str]) -> list[str]:
        """An --ifc-class NAME=CLASS whose NAME is no object of the scene gives no
        element its class: most likely a typo; a CLASS the Reference View leaves
        out is written as the class it has instead."""
        from castor.language.classes import OUTSIDE_REFERENCE_VIEW, reference_view_note
        from castor.language.parse import suggestion

        said = [f"--ifc-class {name}: the scene has no object '{name}', so nothing is made "
                f"an {cls}{suggestion(name, objects)}"
                for name, cls in settings.bim.classes if name not in objects]
        return said + [f"--ifc-class {name}={cls}: {reference_view_note(cls)}; '{name}' is "
                       f"written as an {OUTSIDE_REFERENCE_VIEW[cls]}"
                       for name, cls in settings.bim.classes if cls in OUTSIDE_REFERENCE_VIEW]


STREAM = Polygons("stream", "the polygon stream", streamed=True)
MESH = Polygons("mesh", "mesh files")
PICTURE = Pictures()
DRAWING = Drawings()
BIM = BuildingModels()
KINDS = (STREAM, MESH, PICTURE, DRAWING, BIM)  # in the order messages list them


def _kind_named(name: str) -> Kind:
    return next(kind for kind in KINDS if kind.name == name)

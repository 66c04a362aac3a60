"""A frame as a building model: storeys, elements, openings, spaces (plain data).

Made once per frame by the BIM output kind (castor.formats.kinds) from the
evaluated tree, its polygons and the facetizer that made them: the elements
and openings of LANGUAGE.md §11 (castor.csg.elements) measured by the
take-off (castor.quantities.Takeoff), each element's own solid as polygons.
Where the scene leaves the model a choice (a door cut from two walls, an
opening in an unclassed object, a room below every storey, a class the
Reference View leaves out), the model makes the sensible one and says so
through ``warn``; two storeys at one level are made one by the take-off, for
every output alike.
"""

from __future__ import annotations

from typing import Callable, NamedTuple

from castor.bim import measures
from castor.language.classes import OUTSIDE_REFERENCE_VIEW, PROXY
from castor.mesh.frame import FrameObject

class Storey(NamedTuple):
    name: str
    level: float


class Part(NamedTuple):
    """An element or a space of the model."""

    key: str  # what its GlobalId is made from: its name, and a number if used again
    ifc_class: str
    predefined: str | None  # the predefined type, as annotated ("floor"), or None
    name: str
    long_name: str | None  # the annotation's quoted name
    description: str  # the annotation's description and FILE:LINE
    storey: int  # index into Building.storeys
    solid: FrameObject  # in scene coordinates
    quantities: tuple  # measures.QuantitySet, …
    settings: tuple[tuple[str, str], ...] = ()  # hinge, swing
    size: tuple[float, float] | None = None  # a door's or window's overall width, height
    properties: tuple = ()  # measures.Property, … of its common set (a stair's risers)


class Void(NamedTuple):
    """An opening: the block a door or window cut, voiding its host element."""

    key: str
    name: str
    host: int  # index into Building.elements
    solid: FrameObject
    filler: int | None  # the door or window (index into Building.elements) that fills it
    size: tuple[float, float]  # width, height


class Building(NamedTuple):
    title: str
    # what the GlobalIds are made from besides each part's key: the title castor
    # would give, whatever --title says (default_title), so that a model issued
    # again under another title keeps its elements' identities
    identity: str
    number: int  # the frame's
    where: str  # its '>' command's FILE:LINE
    parameters: tuple[tuple[str, float], ...]
    storeys: tuple[Storey, ...]
    elements: tuple[Part, ...]
    openings: tuple[Void, ...]
    spaces: tuple[Part, ...]
    # each colour of the frame with the name OBJ and glTF give its material
    # (the first, where two '>' objects name it alike): the IFC's style names
    colour_names: tuple[tuple[tuple[float, float, float], str], ...] = ()


def default_title(frame) -> str:
    """The title when --title gives none: the '>' object's name (the first
    named one), else the scene file's name without its extension."""
    import os
    import re

    for obj in frame.objects:
        if obj.name and not re.fullmatch(r"object\d+", obj.name):
            return obj.name
    file = frame.where.rpartition(":")[0] or frame.where
    stem = os.path.splitext(os.path.basename(file))[0]
    return stem if stem and stem != "<stdin>" else "castor"


def build(tree, frame, facetizer, title: str | None = None, classes: dict | None = None,
          warn: Callable[[str], None] = lambda message: None) -> Building:
    """The frame's building model: ``scene`` its evaluated tree, ``frame`` its
    polygons, made by ``facetizer`` (whose caches serve the elements' solids);
    ``classes`` the --ifc-class choices, {object name: IFC class}."""
    from castor.quantities import Takeoff

    takeoff = Takeoff(tree, facetizer, polygons=True, warn=warn)
    maker = _Maker(tree, frame, takeoff, classes or {}, warn)
    storeys = maker.storeys()
    elements, placed = maker.elements()
    openings = maker.openings(elements, placed)
    spaces = maker.spaces()
    return Building(title or default_title(frame), default_title(frame), frame.number,
                    frame.where, tree.parameters, storeys, tuple(elements), tuple(openings),
                    tuple(spaces), colour_names(frame))


def colour_names(frame) -> tuple[tuple[tuple[float, float, float], str], ...]:
    """Each colour of the frame and the name of its material in the mesh
    formats (castor.formats._mesh.materials), the first where it has two."""
    from castor.formats._mesh import materials

    found: dict = {}
    for material in materials(frame)[0]:
        found.setdefault(tuple(material.colour), material.name)
    return tuple(found.items())


def _description(classification, where: str) -> str:
    text = classification.description if classification is not None else ""
    return f"{text} ({where})" if text else where


def _in_own_colour(solid: FrameObject, name: str) -> FrameObject:
    """A door's or window's block in the colour of the door or window: the block
    is the wall's solid where the cutter was, its faces in the wall's plane of
    the wall's colour, its reveals of the cutter's."""
    mark = f"({name})"
    own = [o.colour for o in solid.origins if mark in o.path]
    if not own:
        return solid
    from dataclasses import replace

    return replace(solid, origins=[o._replace(colour=own[0]) for o in solid.origins])


class _Maker:
    def __init__(self, scene, frame, takeoff, classes: dict, warn):
        from castor.formats._mesh import object_names

        self.scene, self.frame, self.takeoff = scene, frame, takeoff
        self.classes, self.warn = classes, warn
        self.object_names = object_names(frame)
        self.keys: dict[str, int] = {}
        self.storey_of: dict[str, int] = {}  # the take-off's storey name -> index

    def key(self, kind: str, name: str) -> str:
        """A key for a GlobalId: the name, numbered from its second use."""
        base = f"{kind}\0{name}"
        self.keys[base] = self.keys.get(base, 0) + 1
        n = self.keys[base]
        return base if n == 1 else f"{base}\0{n}"

    def storeys(self) -> tuple[Storey, ...]:
        """The take-off's storeys (those at one level made one already, and said)."""
        found = self.takeoff.storeys()
        self.storey_of = {name: k for k, (name, _) in enumerate(found)}
        self.levels = tuple(Storey(name, level) for name, level in found)
        return self.levels

    def ifc_class(self, element, name: str) -> tuple[str, str | None]:
        """The element's class (--ifc-class over the annotation) and predefined type."""
        chosen = self.classes.get(element.name) or self.classes.get(name)
        classification = element.classification
        if chosen is not None:
            chosen = OUTSIDE_REFERENCE_VIEW.get(chosen, chosen)
            same = classification is not None and classification.ifc_class == chosen
            return chosen, classification.predefined if same else None
        if classification is None:
            return PROXY, None
        return classification.ifc_class, classification.predefined

    def elements(self):
        """Every element with a solid (the openings' doors and windows come later),
        on its storey: (parts, the take-off's Placed of each)."""
        takeoff = self.takeoff
        for element in takeoff.elements:
            if element.address == () and not element.parts:  # the whole '>' object
                takeoff.known(element, self.frame.objects[element.object])
        parts, placed = [], []
        for p in takeoff.placed():
            element = p.element
            whole = element.classification is None and element.address == ()
            name = self.object_names[element.object] if whole else element.name
            cls, predefined = self.ifc_class(element, name)
            classification = element.classification
            parts.append(Part(self.key("element", name), cls, predefined, name,
                              classification.long_name if classification else None,
                              _description(classification, element.where or self.frame.where),
                              self.storey_of[p.storey], takeoff.solid(element), (),
                              classification.settings if classification else ()))
            placed.append(p)
        return parts, placed

    def openings(self, parts: list, placed: list) -> list[Void]:
        """The openings: each block a door or window cut, voiding the element it
        was cut from, filled by a door or window of its size; then each element's
        quantities, its openings' volume added to its gross volume."""
        from castor.csg.elements import cuts_nothing

        voids: list[Void] = []
        taken = [0.0] * len(parts)  # volume cut out of each element by its openings
        index = {id(p.element): k for k, p in enumerate(placed)}
        of_object: dict[int, list] = {}
        for p in placed:
            of_object.setdefault(p.element.object, []).append(p)
        blocks = self.takeoff.blocks()
        for opening in self.takeoff.idle(blocks):
            self.warn(cuts_nothing(opening))
        for opening in {o.name: o for o in self.takeoff.openings}.values():
            chosen, own = self.classes.get(opening.name), opening.classification.ifc_class
            if chosen not in (None, own):
                self.warn(f"--ifc-class {opening.name}={chosen}: '{opening.name}' is a "
                          f"{opening.classification.short} filling an opening (LANGUAGE.md "
                          f"§11), so it stays an {own}; the option is ignored")
        for block in blocks:
            opening, classification = block.opening, block.opening.classification
            hosts = self.hosts(block, of_object.get(opening.object, []))
            size = (block.width, block.height)
            storey = self.storey_of[block.storey] if not hosts else parts[
                index[id(hosts[0].element)]].storey
            filler = len(parts)
            solid = _in_own_colour(block.solid, opening.name)
            parts.append(Part(self.key("element", opening.name), classification.ifc_class,
                              classification.predefined, opening.name, classification.long_name,
                              _description(classification, opening.where), storey, solid,
                              measures.element_sets(classification.ifc_class, block.solid,
                                                    block.figures, size=size),
                              classification.settings, size))
            if not hosts:
                self.warn(f"{classification.short} '{opening.name}' cuts no element: it is "
                          f"written without an opening")
                continue
            for k, host in enumerate(hosts):
                h = index[id(host.element)]
                taken[h] += block.figures.volume
                voids.append(Void(self.key("opening", opening.name), opening.name, h,
                                  block.solid, filler if k == 0 else None, size))
            self._said(opening, hosts, parts)
        for k, p in enumerate(placed):
            part = parts[k]
            parts[k] = part._replace(quantities=measures.element_sets(
                part.ifc_class, part.solid, p.figures, taken[k]),
                properties=measures.common_properties(part.ifc_class, part.solid))
        return voids

    def hosts(self, block, placed: list) -> list:
        """The elements a block was cut from (``placed``: those of its '>' object):
        those inside the first operand of the '$D' that cut it (or holding it)
        whose boxes meet the block's, the one the take-off chose first."""
        cut = block.opening.cut
        low, high = block.figures.bbox
        found = []
        for p in placed:
            e = p.element
            if p.figures.bbox is None:
                continue
            inside = e.address[:len(cut) + 1] == cut + (0,) or cut[:len(e.address)] == e.address
            a, b = p.figures.bbox
            overlap = all(min(high[i], b[i]) - max(low[i], a[i]) > 1e-9 for i in range(3))
            if inside and overlap:
                found.append(p)
        # an element that holds the '$D' and also holds others found is only their
        # owner: keep the innermost
        found = [p for p in found if not any(
            q is not p and q.element.address[:len(p.element.address)] == p.element.address
            and len(q.element.address) > len(p.element.address) for q in found)]
        found.sort(key=lambda p: p.element is not block.host)
        return found

    def _said(self, opening, hosts: list, parts: list) -> None:
        short = opening.classification.short
        names = [h.element.name or self.object_names[h.element.object] for h in hosts]
        if len(hosts) > 1:
            self.warn(f"{short} '{opening.name}' is cut from {len(hosts)} elements "
                      f"({', '.join(names)}): each has an opening, and the {short} fills the "
                      f"one in '{names[0]}'")
        if hosts[0].element.classification is None:
            self.warn(f"{short} '{opening.name}' is cut from '{names[0]}', which has no "
                      f"class: its opening voids an {PROXY}; annotate it // [wall]")

    def spaces(self) -> list[Part]:
        """The rooms, each on its storey (the lowest when below them all: said)."""
        from castor.quantities import LEVEL_SLACK

        found = []
        said: set[str] = set()  # the spaces an --ifc-class was said of
        lowest = self.levels[0]
        for room in self.takeoff.rooms():
            space = room.space
            (_, _, bottom), (_, _, top) = room.solid.vertices.min(0), room.solid.vertices.max(0)
            if bottom < lowest.level - LEVEL_SLACK:
                self.warn(f"space '{space.name}' is below every storey (its floor at "
                          f"{bottom:g}, the lowest storey at {lowest.level:g}): it is on "
                          f"'{lowest.name}'")
            chosen = self.classes.get(space.name)
            if chosen not in (None, "IfcSpace") and space.name not in said:
                said.add(space.name)
                self.warn(f"--ifc-class {space.name}={chosen}: '{space.name}' is a space (a "
                          f"room, left out of the solids: LANGUAGE.md §11), so it stays an "
                          f"IfcSpace; the option is ignored")
            c = space.classification
            found.append(Part(self.key("space", space.name), "IfcSpace", c.predefined,
                              space.name, c.long_name, _description(c, space.where),
                              self.storey_of[room.storey], room.solid,
                              (measures.QuantitySet(measures.BASE_SETS["IfcSpace"],
                                                    measures.space(room.floor_area, room.volume,
                                                                   float(top - bottom))),)))
        return found

"""IFC4 for BIM programs: the frame as the building model a coordinator accepts.

The model (castor.bim: storeys, elements, openings, spaces, quantities) is
written with ifcopenshell's entity API as buildingSMART's IFC4 Reference View
has it: ``IfcProject`` (lengths in metres: one scene unit is one metre) →
``IfcSite`` → ``IfcBuilding`` → one ``IfcBuildingStorey`` per storey, placed at
its level; every element contained in its storey, every space aggregated into
it. An element is of its class (the annotation's, or --ifc-class's) and
predefined type, named after its object, its ``Tag`` the annotation's quoted
name, its description the annotation's followed by its ``FILE:LINE``. An
opening is an ``IfcOpeningElement`` voiding its element and filled by its door
or window; the element's body keeps the hole, as the Reference View wants (no
boolean for a reader to do). Each body is one closed face set
(castor.formats._ifc_body). Quantities are buildingSMART's base quantity sets,
properties each class's common set with its ``Reference``; the frame's
parameters are ``Castor_Parameters`` on the project.

Global ids are derived (UUID 5) from the scene's identity (the title castor
would give it: its first named '>' object, else its file's name; never
--title) and each part's kind and name, numbered from a name's second use;
not drawn at random, and the header's time stamp is fixed: the same scene
gives the same file, and a model exported again — under another title, with
other parameters, an element moved — keeps its elements' identities, so that
a coordinator's comparison of two versions sees what changed.

ifcopenshell (about 200 MB) is imported here only, when an IFC file is made:
``pip install '.[ifc]'`` in castor's directory (INSTALL).
"""

from __future__ import annotations

import uuid
from typing import Iterator

from castor.formats import WriteInfo
from castor.formats import _ifc_body as ifc_body
from castor.formats._ifc_body import Styles, face_set, true_corner_first  # noqa: F401
from castor.formats.kinds import BuildingModel
from castor.language.classes import BY_NAME, CLASSES, OUTSIDE_REFERENCE_VIEW

# from castor's directory ('castor[ifc]' would fetch PyPI's unrelated package named castor)
INSTALL = "pip install '.[ifc]' in castor's directory, or pip install 'ifcopenshell>=0.8'"

# the IFC4 classes an object may take: castor.language.classes' table, less
# IfcSpace (a room is no element: tests/formats/test_ifc.py checks this list
# against ifcopenshell's schema)
ELEMENT_CLASSES = tuple(info.ifc for info in CLASSES if info.role != "space")
# what a usage error lists: the classes of a building's parts
COMMON_CLASSES = ("IfcWall", "IfcSlab", "IfcRoof", "IfcWindow", "IfcDoor", "IfcColumn",
                  "IfcBeam", "IfcStair", "IfcRailing", "IfcCovering", "IfcFurniture",
                  "IfcBuildingElementProxy")
# every way of writing one: IfcWall, ifcwall, wall (as an annotation takes them),
# and the classes the model writes as another (with a warning, as an annotation)
_BY_KEY = {**{name: info.ifc for name, info in BY_NAME.items() if info.role != "space"},
           **{name.lower(): name for name in OUTSIDE_REFERENCE_VIEW}}

# the header's fixed time stamp: the same frame gives the same bytes (as 3MF's dates)
TIME_STAMP = "1980-01-01T00:00:00"
_GUID_SPACE = uuid.UUID("6f1c1f3e-3c1e-4d7a-9a51-0c4a5f0c2a17")  # castor's, for uuid5


def installed() -> bool:
    """Whether ifcopenshell can be imported (without importing it: castor
    starts without it). This module itself imports without it, so the format
    stays in the registry, and ``-o x.ifc`` says what to install."""
    import importlib.util

    try:
        return importlib.util.find_spec("ifcopenshell") is not None
    except (ImportError, ValueError):  # a hidden or half-imported package
        return False


def unavailable() -> str | None:
    """Why IFC cannot be written here (ifcopenshell missing), as a usage error
    says it; None when it can."""
    if installed():
        return None
    return f"writing IFC needs ifcopenshell, which is not installed; {INSTALL}"


def parse_classes_option(items: list[str]) -> tuple[tuple[str, str], ...]:
    """``--ifc-class`` options as (object name, IFC class) pairs (BimSettings.classes)."""
    return tuple(parse_ifc_classes(items).items())


def element_class(text: str) -> str:
    """The IFC class ``text`` names (``IfcWall``, ``ifcwall`` or ``wall``, as an
    annotation names it); ``ValueError`` with the message a usage error shows
    when it names none."""
    key = text.strip().lower()
    found = _BY_KEY.get(key) or _BY_KEY.get("ifc" + key)
    if found is None:
        raise ValueError(f"--ifc-class: '{text}' is not an IFC4 element class; use one of "
                         f"{', '.join(COMMON_CLASSES)} (or another subtype of IfcElement)")
    return found


def parse_ifc_classes(items: list[str]) -> dict[str, str]:
    """``--ifc-class NAME=CLASS`` options as {object name: IFC class}."""
    import re

    classes: dict[str, str] = {}
    for item in items:
        name, sep, cls = item.partition("=")
        name = name.strip()
        if not sep or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name) or not cls.strip():
            raise ValueError(f"--ifc-class takes NAME=CLASS with an object NAME, such as "
                             f"maison=IfcWall, not '{item}'")
        classes[name] = element_class(cls)
    return classes



# each class's common property set (IFC4's templates: tests/formats/test_ifc_coordinator.py)
COMMON_PSETS = ("IfcWall", "IfcSlab", "IfcDoor", "IfcWindow", "IfcRoof", "IfcStair",
                "IfcStairFlight", "IfcRamp", "IfcRampFlight", "IfcColumn", "IfcBeam",
                "IfcMember", "IfcPlate", "IfcRailing", "IfcCovering", "IfcCurtainWall",
                "IfcChimney", "IfcFooting", "IfcPile", "IfcShadingDevice",
                "IfcBuildingElementProxy", "IfcElementAssembly", "IfcTransportElement",
                "IfcCivilElement", "IfcSpace")
_QUANTITY = {"length": "IfcQuantityLength", "area": "IfcQuantityArea",
             "volume": "IfcQuantityVolume"}


def measure(value: float) -> float:
    """A quantity or a size as written: to 12 significant digits, what the
    solids' arithmetic holds exactly (a door's width 0.9, not
    0.8999999999999999); coordinates are written whole, to read back the same."""
    return float(f"{float(value):.12g}") + 0.0  # + 0.0: no -0.0


def export(tree, frame, title: str | None = None, classes: dict[str, str] | None = None,
           facetizer=None, warn=lambda message: None) -> bytes:
    """The frame as an IFC4 file (STEP physical file text): ``frame_tree`` is its
    evaluated CSG tree, ``frame`` its polygons (made by ``facetizer``, or a new
    one). ``classes`` maps an object's name to its IFC class (--ifc-class)."""
    from castor.bim import build

    if facetizer is None:
        from castor.mesh.facetize import Facetizer

        facetizer = Facetizer()
    building = build(tree, frame, facetizer, title, classes, warn)
    return model(building).to_string().encode("utf-8")


def model(building, file_name: str | None = None):
    """The building model (castor.bim.Building) as an ``ifcopenshell.file``: the
    header, the project and its spatial structure, the parameters, the elements
    and their openings, the spaces (in this order: the entities' numbers follow
    it). ``file_name``: the header's, the file's name (else the title's)."""
    import ifcopenshell

    f = ifcopenshell.file(schema="IFC4")
    _header(f, file_name or f"{building.title}.ifc")
    writer = _Writer(f, building)
    project = writer.structure()
    writer.parameters(project)
    elements = [writer.element(part) for part in building.elements]
    writer.openings(elements)
    spaces = [writer.element(part) for part in building.spaces]
    writer.relate(elements, spaces)
    return f


def _header(f, file_name: str) -> None:
    from castor import __version__

    header = f.header
    header.file_description.description = ("ViewDefinition [ReferenceView_V1.2]",)
    header.file_name.name = file_name
    header.file_name.time_stamp = TIME_STAMP
    header.file_name.preprocessor_version = f"castor {__version__}"
    header.file_name.originating_system = f"castor {__version__}"


# standard base 64's digits to IFC's (buildingSMART's GUID text)
_TO_IFC = bytes.maketrans(
    b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/",
    b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_$")


def guid(name: str) -> str:
    """The GlobalId of ``name``: ``ifcopenshell.guid.compress(uuid.uuid5(castor's
    namespace, name).hex)``, made without their Python (a file of 1,024 houses
    has 160,000 of them; tests/formats/test_ifc_reissue.py checks it is the same)."""
    import base64
    import hashlib

    digest = bytearray(hashlib.sha1(_GUID_SPACE.bytes + name.encode()).digest()[:16])
    digest[6] = digest[6] & 0x0F | 0x50  # UUID version 5
    digest[8] = digest[8] & 0x3F | 0x80  # its variant
    return base64.b64encode(b"\0\0" + digest)[2:].translate(_TO_IFC).decode()


class _Writer:
    """The file being made: its entities' global ids (from the scene's identity
    and a key), the placements of the storeys, the styles of the elements' colours."""

    def __init__(self, f, building):
        from castor.formats._mesh import materials
        from castor.mesh.frame import Frame

        self.f, self.building, self.create = f, building, ifc_body.entity_maker(f)
        origin = self.create("IfcCartesianPoint", (0.0, 0.0, 0.0))
        self.axes = self.create("IfcAxis2Placement3D", origin, None, None)
        table, self.material_of = materials(Frame(building.number, building.where,
                                                  [p.solid for p in building.elements]))
        self.styles = Styles(f, table, self.create, dict(building.colour_names))
        self.attributes: dict[str, set[str]] = {}
        self.placed: dict[int, tuple] = {}  # id of an element's entity -> (placement, level)

    def guid(self, *key: str) -> str:
        return guid("\0".join((self.building.identity,) + key))

    def placement(self, relative_to=None, level: float = 0.0):
        axes = self.axes if level == 0 else self.create(
            "IfcAxis2Placement3D", self.create("IfcCartesianPoint", (0.0, 0.0, float(level))),
            None, None)
        return self.create("IfcLocalPlacement", relative_to, axes)

    def has(self, cls: str, attribute: str) -> bool:
        if cls not in self.attributes:
            import ifcopenshell.ifcopenshell_wrapper as wrapper

            declaration = wrapper.schema_by_name("IFC4").declaration_by_name(cls)
            self.attributes[cls] = {a.name() for a in declaration.all_attributes()}
        return attribute in self.attributes[cls]

    def structure(self):
        """The project (its units and context), its site, building and storeys."""
        create, guid, building = self.create, self.guid, self.building
        context = create("IfcGeometricRepresentationContext", None, "Model", 3, 1e-5, self.axes,
                         create("IfcDirection", (0.0, 1.0)))  # north is +y
        self.body = create("IfcGeometricRepresentationSubContext", "Body", "Model", None, None,
                           None, None, context, None, "MODEL_VIEW", None)
        units = create("IfcUnitAssignment", [
            create("IfcSIUnit", None, "LENGTHUNIT", None, "METRE"),
            create("IfcSIUnit", None, "AREAUNIT", None, "SQUARE_METRE"),
            create("IfcSIUnit", None, "VOLUMEUNIT", None, "CUBIC_METRE"),
            create("IfcSIUnit", None, "PLANEANGLEUNIT", None, "RADIAN")])
        project = create("IfcProject", guid("project"), None, building.title,
                         f"castor frame {building.number}, {building.where}", None, None, None,
                         [context], units)
        site_place = self.placement()
        building_place = self.placement(site_place)
        site = create("IfcSite", guid("site"), None, "Site", None, None, site_place, None, None,
                      "ELEMENT")
        whole = create("IfcBuilding", guid("building"), None, "Building", None, None,
                       building_place, None, None, "ELEMENT")
        self.storeys = []
        for storey in building.storeys:
            place = self.placement(building_place, storey.level)
            self.storeys.append((create(
                "IfcBuildingStorey", guid("storey", storey.name), None, storey.name, None, None,
                place, None, storey.name, "ELEMENT", float(storey.level)), place, storey.level))
        # keyed by the parent's role, not its name: the project's name is the title
        # (which must not change ids) and may be "Site" or "Building" (unique ids)
        for role, parent, parts in (("project", project, [site]), ("site", site, [whole]),
                                    ("building", whole, [s for s, _, _ in self.storeys])):
            create("IfcRelAggregates", guid("aggregates", role), None, None, None,
                   parent, parts)
        return project

    def parameters(self, project) -> None:
        """The frame's parameters: the project's property set Castor_Parameters."""
        create = self.create
        parameters = [create("IfcPropertySingleValue", name, None,
                             create("IfcReal", float(value)), None)
                      for name, value in self.building.parameters]
        if parameters:
            pset = create("IfcPropertySet", self.guid("Castor_Parameters"), None,
                          "Castor_Parameters",
                          "the parameter values in force at the frame's '>' command", parameters)
            create("IfcRelDefinesByProperties", self.guid("defines", "Castor_Parameters"), None,
                   None, None, [project], pset)

    def shape(self, solid, shift: float, material=None):
        item = face_set(self.f, solid, shift, material, self.styles)
        return self.create("IfcProductDefinitionShape", None, None, [
            self.create("IfcShapeRepresentation", self.body, "Body", "Tessellation", [item])])

    def element(self, part):
        """An element or a space: its entity, body, quantities and common properties."""
        _, storey_place, level = self.storeys[part.storey]
        cls = part.ifc_class
        number = len(self.placed)
        material = self.material_of[number] if number < len(self.material_of) else None
        place = self.placement(storey_place)
        values = dict(GlobalId=self.guid(*part.key.split("\0")), Name=part.name,
                      Description=part.description, ObjectPlacement=place,
                      Representation=self.shape(part.solid, level, material))
        values.update(self.typed(cls, part))
        entity = self.create(cls, **values)
        self.placed[entity.id()] = (place, level)
        for qto in part.quantities:
            self.quantities(entity, part.key, qto)
        if cls in COMMON_PSETS:
            values = {"Reference": ("IfcIdentifier", part.name)}
            values.update((p.name, (p.type, p.value)) for p in part.properties)
            self.properties(entity, part.key, f"Pset_{cls[3:]}Common", values)
        return entity

    def typed(self, cls: str, part) -> dict:
        """The attributes of the element's class: predefined type, long name,
        a door's or window's size and a door's hinge."""
        values = {}
        if self.has(cls, "PredefinedType"):
            values["PredefinedType"] = (part.predefined or "notdefined").upper()
            if part.predefined == "userdefined":
                values["ObjectType"] = part.long_name or part.name
        if part.long_name:
            values["LongName" if self.has(cls, "LongName") else "Tag"] = part.long_name
        if cls == "IfcSpace":
            values["CompositionType"] = "ELEMENT"
        if part.size is not None and self.has(cls, "OverallWidth"):
            values["OverallWidth"], values["OverallHeight"] = map(measure, part.size)
        for p in part.properties:  # an IfcStairFlight's NumberOfRisers …
            attribute = "NumberOfRisers" if p.name == "NumberOfRiser" else p.name
            if self.has(cls, attribute):
                values[attribute] = p.value
        if cls == "IfcDoor":
            hinge = dict(part.settings).get("hinge", "left")
            values["OperationType"] = f"SINGLE_SWING_{hinge.upper()}"
        return values

    def quantities(self, entity, key: str, qto) -> None:
        create = self.create
        listed = []
        for q in qto.quantities:
            kind = _QUANTITY[q.kind]
            listed.append(create(kind, q.name, None, None, measure(q.value), None))
        method = None if qto.name.startswith("Castor") else "BaseQuantities"
        quantities = create("IfcElementQuantity", self.guid(qto.name, key), None, qto.name,
                            "exact, from castor's solids", method, listed)
        create("IfcRelDefinesByProperties", self.guid("defines", qto.name, key), None, None,
               None, [entity], quantities)

    def properties(self, entity, key: str, name: str, values: dict) -> None:
        """A property set: ``values`` {name: (IFC type, value)}."""
        create = self.create
        pset = create("IfcPropertySet", self.guid(name, key), None, name, None, [
            create("IfcPropertySingleValue", k, None,
                   create(kind, measure(v) if isinstance(v, float) else v), None)
            for k, (kind, v) in values.items()])
        create("IfcRelDefinesByProperties", self.guid("defines", name, key), None, None, None,
               [entity], pset)

    def openings(self, elements: list) -> None:
        """Each opening voiding its host (placed relative to it), filled by its
        door or window."""
        create, guid = self.create, self.guid
        for void in self.building.openings:
            host = elements[void.host]
            host_place, level = self.placed[host.id()]
            key = void.key.split("\0")
            opening = create("IfcOpeningElement", guid(*key), None, f"{void.name} opening",
                             None, None, self.placement(host_place),
                             self.shape(void.solid, level), None, "OPENING")
            create("IfcRelVoidsElement", guid("voids", *key), None, None, None, host, opening)
            self.properties(opening, void.key, "Pset_OpeningElementCommon",
                            {"Reference": ("IfcIdentifier", void.name)})
            if void.filler is not None:
                create("IfcRelFillsElement", guid("fills", *key), None, None, None, opening,
                       elements[void.filler])

    def relate(self, elements: list, spaces: list) -> None:
        """Each storey contains its elements and aggregates its spaces."""
        create, guid = self.create, self.guid
        for k, (storey, _, _) in enumerate(self.storeys):
            mine = [e for e, p in zip(elements, self.building.elements) if p.storey == k]
            if mine:
                create("IfcRelContainedInSpatialStructure", guid("contains", storey.Name),
                       None, None, None, mine, storey)
            rooms = [s for s, p in zip(spaces, self.building.spaces) if p.storey == k]
            if rooms:
                create("IfcRelAggregates", guid("aggregates", "spaces", storey.Name), None,
                       None, None, storey, rooms)


def write(building: BuildingModel, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the building model as an IFC4 file,
    its header naming the file written (its base name; the title's on standard
    output)."""
    import os

    name = os.path.basename(info.path) if info.path else None
    return iter([model(building.building, name).to_string().encode("utf-8")])

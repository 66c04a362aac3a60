"""IFC4 for BIM programs: the frame as a building model a coordinator opens.

The spatial structure is the one every BIM program expects, and no more: an
``IfcProject`` (the title; lengths in metres, so one scene unit is one metre)
aggregates an ``IfcSite``, which aggregates an ``IfcBuilding``, which aggregates
one ``IfcBuildingStorey`` at elevation 0; every object of the frame is one
element contained in that storey, named after the object, of the class
``--ifc-class NAME=CLASS`` gives (``IfcBuildingElementProxy`` otherwise), with
the object's source ``FILE:LINE`` as its description.

An element's body is castor's own convex polygons as ``IfcPolygonalFaceSet``s
(no triangle added), counter-clockwise seen from outside as IFC wants. IFC
colours a representation item through a styled item, never a single face, so
an object of several colours is one face set per colour, all indexing one
coordinate list: together they are the object's closed surface, and a face set
is flagged ``Closed`` when it is that whole surface alone. There is one
``IfcSurfaceStyle`` per colour of the file, named as the other formats name
their materials. The frame's parameters are the property set
``Castor_Parameters`` of the project; each element's volume and area (those of
``--summary``) its quantity set ``Castor_Quantities``.

Global ids are derived from the title and the names (not drawn at random), and
the header's time stamp is fixed: the same scene gives the same file, and a
model exported again keeps its elements' identities, so that a coordinator's
comparison of two versions sees what changed.

ifcopenshell (about 200 MB) is imported here only, when an IFC file is made:
``pip install 'castor[ifc]'``.
"""

from __future__ import annotations

import os
import uuid
from typing import Iterator

import numpy as np

from castor.csg import tree
from castor.formats import WriteInfo
from castor.formats.kinds import BuildingModel
from castor.mesh.frame import Frame

INSTALL = "pip install 'castor[ifc]'"
DEFAULT_CLASS = "IfcBuildingElementProxy"

# the IFC4 classes an object may take: the concrete subtypes of IfcElement that
# are physical things (no feature or virtual element) and need nothing but a
# body (the 'StandardCase' and 'ElementedCase' classes require material layers
# or parts; tests/formats/test_ifc.py checks this list against ifcopenshell's schema)
ELEMENT_CLASSES = (
    "IfcActuator", "IfcAirTerminal", "IfcAirTerminalBox", "IfcAirToAirHeatRecovery",
    "IfcAlarm", "IfcAudioVisualAppliance", "IfcBeam", "IfcBoiler", "IfcBuildingElementPart",
    "IfcBuildingElementProxy", "IfcBurner", "IfcCableCarrierFitting",
    "IfcCableCarrierSegment", "IfcCableFitting", "IfcCableSegment", "IfcChiller",
    "IfcChimney", "IfcCivilElement", "IfcCoil", "IfcColumn", "IfcCommunicationsAppliance",
    "IfcCompressor", "IfcCondenser", "IfcController", "IfcCooledBeam", "IfcCoolingTower",
    "IfcCovering", "IfcCurtainWall", "IfcDamper", "IfcDiscreteAccessory",
    "IfcDistributionChamberElement", "IfcDistributionControlElement",
    "IfcDistributionElement", "IfcDistributionFlowElement", "IfcDoor", "IfcDuctFitting",
    "IfcDuctSegment", "IfcDuctSilencer", "IfcElectricAppliance",
    "IfcElectricDistributionBoard", "IfcElectricFlowStorageDevice", "IfcElectricGenerator",
    "IfcElectricMotor", "IfcElectricTimeControl", "IfcElementAssembly",
    "IfcEnergyConversionDevice", "IfcEngine", "IfcEvaporativeCooler", "IfcEvaporator",
    "IfcFan", "IfcFastener", "IfcFilter", "IfcFireSuppressionTerminal", "IfcFlowController",
    "IfcFlowFitting", "IfcFlowInstrument", "IfcFlowMeter", "IfcFlowMovingDevice",
    "IfcFlowSegment", "IfcFlowStorageDevice", "IfcFlowTerminal", "IfcFlowTreatmentDevice",
    "IfcFooting", "IfcFurnishingElement", "IfcFurniture", "IfcGeographicElement",
    "IfcHeatExchanger", "IfcHumidifier", "IfcInterceptor", "IfcJunctionBox", "IfcLamp",
    "IfcLightFixture", "IfcMechanicalFastener", "IfcMedicalDevice", "IfcMember",
    "IfcMotorConnection", "IfcOutlet", "IfcPile", "IfcPipeFitting", "IfcPipeSegment",
    "IfcPlate", "IfcProtectiveDevice", "IfcProtectiveDeviceTrippingUnit", "IfcPump",
    "IfcRailing", "IfcRamp", "IfcRampFlight", "IfcReinforcingBar", "IfcReinforcingMesh",
    "IfcRoof", "IfcSanitaryTerminal", "IfcSensor", "IfcShadingDevice", "IfcSlab",
    "IfcSolarDevice", "IfcSpaceHeater", "IfcStackTerminal", "IfcStair", "IfcStairFlight",
    "IfcSwitchingDevice", "IfcSystemFurnitureElement", "IfcTank", "IfcTendon",
    "IfcTendonAnchor", "IfcTransformer", "IfcTransportElement", "IfcTubeBundle",
    "IfcUnitaryControlElement", "IfcUnitaryEquipment", "IfcValve", "IfcVibrationIsolator",
    "IfcWall", "IfcWasteTerminal", "IfcWindow",
)
# what a usage error lists: the classes of a building's parts
COMMON_CLASSES = ("IfcWall", "IfcSlab", "IfcRoof", "IfcWindow", "IfcDoor", "IfcColumn",
                  "IfcBeam", "IfcStair", "IfcRailing", "IfcCovering", "IfcFurniture",
                  "IfcBuildingElementProxy")
_BY_KEY = {name.lower(): name for name in ELEMENT_CLASSES}

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
    """The IFC class ``text`` names (``IfcWall``, ``ifcwall`` or ``wall``);
    ``ValueError`` with the message a usage error shows when it names none."""
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


def default_title(frame: Frame) -> str:
    """The title when --title gives none: the '>' object's name (the first
    named one), else the scene file's name without its extension."""
    import re

    for obj in frame.objects:
        if obj.name and not re.fullmatch(r"object\d+", obj.name):
            return obj.name
    file = frame.where.rpartition(":")[0] or frame.where
    stem = os.path.splitext(os.path.basename(file))[0]
    return stem if stem and stem != "<stdin>" else "castor"


def export(scene: tree.FrameTree, frame: Frame, title: str | None = None,
           classes: dict[str, str] | None = None) -> bytes:
    """The frame as an IFC4 file (STEP physical file text): ``scene`` is its
    evaluated CSG tree (the parameters, each object's source), ``frame`` its
    polygons. ``classes`` maps an object's name to its IFC class
    (``element_class``'s spelling)."""
    return model(scene, frame, title, classes).to_string().encode("utf-8")


def model(scene: tree.FrameTree, frame: Frame, title: str | None = None,
          classes: dict[str, str] | None = None):
    """The frame as an ``ifcopenshell.file``: the header, the project and its
    spatial structure, the parameters, then one element per object (in this
    order: the entities' numbers follow it)."""
    import ifcopenshell

    title = title or default_title(frame)  # an empty --title is no title
    f = ifcopenshell.file(schema="IFC4")
    _header(f, title)
    built = _Builder(f, title)
    project, storey, storey_place, body = _structure(built, frame)
    _parameters(built, scene, project)
    elements = _elements(built, scene, frame, classes or {}, body, storey_place)
    if elements:
        built.create("IfcRelContainedInSpatialStructure", built.guid("contains", "storey"), None,
                     None, None, elements, storey)
    return f


def _header(f, title: str) -> None:
    from castor import __version__

    header = f.header
    header.file_description.description = ("ViewDefinition [ReferenceView_V1.2]",)
    header.file_name.name = f"{title}.ifc"
    header.file_name.time_stamp = TIME_STAMP
    header.file_name.preprocessor_version = f"castor {__version__}"
    header.file_name.originating_system = f"castor {__version__}"


class _Builder:
    """The file being made, its entities' global ids (from the title and a key)
    and the placement every entity shares."""

    def __init__(self, f, title: str):
        self.f, self.title, self.create = f, title, f.create_entity
        origin = self.create("IfcCartesianPoint", (0.0, 0.0, 0.0))
        self.axes = self.create("IfcAxis2Placement3D", origin, None, None)

    def guid(self, *key: str) -> str:
        import ifcopenshell.guid

        return ifcopenshell.guid.compress(
            uuid.uuid5(_GUID_SPACE, "\0".join((self.title,) + key)).hex)

    def placement(self, relative_to=None):
        return self.create("IfcLocalPlacement", relative_to, self.axes)


def _structure(built: _Builder, frame: Frame):
    """The project (its units and context), its site, building and one storey:
    (project, storey, the storey's placement, the body's representation context)."""
    create, guid = built.create, built.guid
    context = create("IfcGeometricRepresentationContext", None, "Model", 3, 1e-5, built.axes,
                     create("IfcDirection", (0.0, 1.0)))  # north is +y
    body = create("IfcGeometricRepresentationSubContext", "Body", "Model", None, None, None,
                  None, context, None, "MODEL_VIEW", None)
    units = create("IfcUnitAssignment", [
        create("IfcSIUnit", None, "LENGTHUNIT", None, "METRE"),
        create("IfcSIUnit", None, "AREAUNIT", None, "SQUARE_METRE"),
        create("IfcSIUnit", None, "VOLUMEUNIT", None, "CUBIC_METRE"),
        create("IfcSIUnit", None, "PLANEANGLEUNIT", None, "RADIAN")])
    project = create("IfcProject", guid("project"), None, built.title,
                     f"castor frame {frame.number}, {frame.where}", None, None, None,
                     [context], units)
    site_place = built.placement()
    building_place = built.placement(site_place)
    storey_place = built.placement(building_place)
    site = create("IfcSite", guid("site"), None, "Site", None, None, site_place, None, None,
                  "ELEMENT")
    building = create("IfcBuilding", guid("building"), None, "Building", None, None,
                      building_place, None, None, "ELEMENT")
    storey = create("IfcBuildingStorey", guid("storey"), None, "Level 0", None, None,
                    storey_place, None, None, "ELEMENT", 0.0)
    for whole, part in ((project, site), (site, building), (building, storey)):
        create("IfcRelAggregates", guid("aggregates", whole.Name or "", part.Name),
               None, None, None, whole, [part])
    return project, storey, storey_place, body


def _parameters(built: _Builder, scene: tree.FrameTree, project) -> None:
    """The frame's parameters: the project's property set Castor_Parameters."""
    create = built.create
    parameters = [create("IfcPropertySingleValue", name, None,
                         create("IfcReal", float(value)), None)
                  for name, value in scene.parameters]
    if parameters:
        pset = create("IfcPropertySet", built.guid("Castor_Parameters"), None,
                      "Castor_Parameters",
                      "the parameter values in force at the frame's '>' command", parameters)
        create("IfcRelDefinesByProperties", built.guid("defines", "Castor_Parameters"), None,
               None, None, [project], pset)


def _elements(built: _Builder, scene: tree.FrameTree, frame: Frame, classes: dict[str, str],
              body, storey_place) -> list:
    """One element per object with polygons: its body in its colours, its class,
    its quantities (those of --summary)."""
    from castor.formats._mesh import materials, object_names
    from castor.quantities import object_figures

    create, guid = built.create, built.guid
    table, material_of = materials(frame)
    styles: dict[int, object] = {}  # frame material -> IfcSurfaceStyle

    def style(m: int):
        if m not in styles:
            r, g, b = table[m].colour
            shading = create("IfcSurfaceStyleShading",
                             create("IfcColourRgb", None, float(r), float(g), float(b)), 0.0)
            # both sides: a section box shows the inside faces in the same colour
            styles[m] = create("IfcSurfaceStyle", table[m].name, "BOTH", [shading])
        return styles[m]

    elements = []
    for obj, source, name, material in zip(frame.objects, scene.objects, object_names(frame),
                                           material_of):
        if obj.polygon_count == 0:
            continue  # nothing to show: an element without a body helps no one
        items = _face_sets(built.f, obj, material, style)
        shape = create("IfcProductDefinitionShape", None, None, [
            create("IfcShapeRepresentation", body, "Body", "Tessellation", items)])
        cls = classes.get(obj.name) or classes.get(name) or _annotated(scene, source) \
            or DEFAULT_CLASS
        element = create(cls, guid("element", name), None, name, source.where or frame.where,
                         None, built.placement(storey_place), shape, None)
        elements.append(element)
        figures = object_figures(obj, name)
        quantities = create("IfcElementQuantity", guid("quantities", name), None,
                            "Castor_Quantities", "of castor's polygons, as --summary gives",
                            "castor", [
                                create("IfcQuantityVolume", "Volume", None, None,
                                       max(figures.volume, 0.0), None),
                                create("IfcQuantityArea", "SurfaceArea", None, None,
                                       figures.area, None)])
        create("IfcRelDefinesByProperties", guid("defines", "Castor_Quantities", name), None,
               None, None, [element], quantities)
    return elements


def _annotated(scene: tree.FrameTree, source: tree.Object) -> str | None:
    """The class an annotation gives the '>' object itself (LANGUAGE.md §11);
    --ifc-class overrides it. (The elements inside it are the BIM handover's.)"""
    root = source.root
    if scene.classes is None or not isinstance(root, tree.Use):
        return None
    mark = scene.classes.of(root.shared.location)
    return None if mark is None or mark.ifc_class not in ELEMENT_CLASSES else mark.ifc_class


def _face_sets(f, obj, material: np.ndarray, style) -> list:
    """The object's polygons as one IfcPolygonalFaceSet per colour, styled,
    sharing one coordinate list; each polygon keeps its vertices (1-based)."""
    create = f.create_entity
    coordinates = create("IfcCartesianPointList3D", obj.vertices.tolist())
    sizes = np.diff(obj.offsets)
    ones = true_corner_first(obj.vertices, obj.offsets, obj.indices) + 1  # IFC counts from 1
    colours = np.unique(material)
    items = []
    for m in colours.tolist():
        chosen = np.flatnonzero(material == m)
        faces = _faces(f, ones, obj.offsets, sizes, chosen)
        face_set = create("IfcPolygonalFaceSet", coordinates, len(colours) == 1, faces, None)
        create("IfcStyledItem", face_set, [style(m)], None)
        items.append(face_set)
    return items


def true_corner_first(vertices: np.ndarray, offsets: np.ndarray,
                      indices: np.ndarray) -> np.ndarray:
    """The polygons' vertex numbers, each polygon turned (same vertices, same
    order) so that its first three vertices make a true corner.

    A castor polygon may have a straight corner, a vertex in the middle of an
    edge that a neighbour ends at. A reader that takes a face's plane from its
    first three vertices (a common shortcut) finds one this way."""
    if len(indices) == 0:
        return indices
    from castor.formats._mesh import corner_turns

    sizes = np.diff(offsets)
    starts = offsets[:-1]
    following, turn, lengths = corner_turns(vertices, offsets, indices)
    true = turn > 1e-9 * lengths
    position = np.arange(len(indices))
    ready = true[following[starts]]  # the second vertex is a true corner already
    if ready.all():
        return indices
    # the first true corner of each polygon (its second vertex if none is)
    first = np.minimum.reduceat(np.where(true, position, len(indices)), starts)
    first = np.where((first < offsets[1:]) & ~ready, first, starts + 1)
    shift = np.repeat((first - starts - 1) % sizes, sizes)
    local = position - np.repeat(starts, sizes)
    return indices[np.repeat(starts, sizes) + (local + shift) % np.repeat(sizes, sizes)]


def _faces(f, ones: np.ndarray, offsets: np.ndarray, sizes: np.ndarray,
           chosen: np.ndarray) -> list:
    """An IfcIndexedPolygonalFace for each chosen polygon: the vertex tuples are cut
    from one list, a size at a time, so that Python makes no slice per polygon."""
    faces = [None] * len(chosen)
    chosen_sizes = sizes[chosen]
    make = _face_maker(f)
    for size in np.unique(chosen_sizes).tolist():
        which = np.flatnonzero(chosen_sizes == size)
        starts = offsets[chosen[which]]
        rows = ones[starts[:, None] + np.arange(size)].tolist()
        for place, row in zip(which.tolist(), rows):
            faces[place] = make(row)
    return faces


def _face_maker(f):
    """A function from a polygon's vertex numbers to a new IfcIndexedPolygonalFace.

    ``create_entity`` spends three quarters of its time in Python (argument
    checks, the undo journal); a face has one attribute, set here through the
    two calls ``create_entity`` ends in (the same entity, the same file), which
    is about three times as fast. Where an ifcopenshell lacks them, the public
    call is used."""
    import ifcopenshell

    create = getattr(f, "create", None)
    if (create is None or getattr(f, "transaction", None) is not None
            or not hasattr(ifcopenshell.entity_instance, "set_attribute_value_py")):
        return lambda row: f.create_entity("IfcIndexedPolygonalFace", row)

    def make(row):
        face = create("IfcIndexedPolygonalFace", -1)
        face.set_attribute_value_py(0, row)
        return face
    return make


def write(building: BuildingModel, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the building model as an IFC4 file,
    titled by --title, of the classes --ifc-class gives."""
    return iter([export(building.tree, building.frame, building.title, building.classes)])

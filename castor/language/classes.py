"""What an object is (LANGUAGE.md §11): the table of classes and the reading of
``// [wall]``, ``// [door hinge=left swing=in]``, ``// [space "Séjour"]`` and
``// [storey "Étage"]``.

``CLASSES`` is the one declaration of the classes: every IFC4 class of a
physical element castor can make, plus ``space``, each with its short name,
its predefined types and its own settings (allowed values, default). The
reader, the take-off, the IFC writer, the drawings and the language server
read it; none keeps a list of its own. An annotation is a comment: it never
changes the geometry, and what castor cannot understand in it is a warning
with the closest known word, the object then unclassed.
"""

from __future__ import annotations

import re
from typing import NamedTuple

from castor.diagnostics import Location
from castor.records import Record


class Setting(NamedTuple):
    """A class's own setting: ``hinge=left``."""

    name: str
    values: tuple[str, ...]
    default: str


class ClassInfo(NamedTuple):
    """One class: its IFC4 entity, its short name, its predefined types (in
    lower case, as written after the class) and its settings."""

    ifc: str
    short: str
    types: tuple[str, ...] = ()
    settings: tuple[Setting, ...] = ()
    role: str = "element"  # "element", "opening" (fills an opening when subtracted), "space"


_OPENING = (Setting("hinge", ("left", "right"), "left"), Setting("swing", ("in", "out"), "in"))
_WINDOW = (Setting("hinge", ("none", "left", "right", "top", "bottom"), "none"),
           Setting("swing", ("in", "out"), "in"))


def _types(*names: str) -> tuple[str, ...]:
    return tuple(names) + ("userdefined", "notdefined")


CLASSES: tuple[ClassInfo, ...] = (
    ClassInfo("IfcWall", "wall", _types("movable", "parapet", "partitioning", "plumbingwall",
                                        "shear", "solidwall", "standard", "polygonal",
                                        "elementedwall")),
    ClassInfo("IfcSlab", "slab", _types("floor", "roof", "landing", "baseslab")),
    ClassInfo("IfcRoof", "roof", _types("flat_roof", "shed_roof", "gable_roof", "hip_roof",
                                        "hipped_gable_roof", "gambrel_roof", "mansard_roof",
                                        "barrel_roof", "rainbow_roof", "butterfly_roof",
                                        "pavilion_roof", "dome_roof", "freeform")),
    ClassInfo("IfcDoor", "door", _types("door", "gate", "trapdoor"), _OPENING, "opening"),
    ClassInfo("IfcWindow", "window", _types("window", "skylight", "lightdome"), _WINDOW,
              "opening"),
    ClassInfo("IfcStair", "stair", _types(
        "straight_run_stair", "two_straight_run_stair", "quarter_winding_stair",
        "quarter_turn_stair", "half_winding_stair", "half_turn_stair",
        "two_quarter_winding_stair", "two_quarter_turn_stair", "three_quarter_winding_stair",
        "three_quarter_turn_stair", "spiral_stair", "double_return_stair", "curved_run_stair",
        "two_curved_run_stair")),
    ClassInfo("IfcStairFlight", "stairflight", _types("straight", "winder", "spiral", "curved",
                                                      "freeform")),
    ClassInfo("IfcRamp", "ramp", _types("straight_run_ramp", "two_straight_run_ramp",
                                        "quarter_turn_ramp", "two_quarter_turn_ramp",
                                        "half_turn_ramp", "spiral_ramp")),
    ClassInfo("IfcRampFlight", "rampflight", _types("straight", "spiral")),
    ClassInfo("IfcColumn", "column", _types("column", "pilaster")),
    ClassInfo("IfcBeam", "beam", _types("beam", "joist", "hollowcore", "lintel", "spandrel",
                                        "t_beam")),
    ClassInfo("IfcMember", "member", _types("brace", "chord", "collar", "member", "mullion",
                                            "plate", "post", "purlin", "rafter", "stringer",
                                            "strut", "stud")),
    ClassInfo("IfcPlate", "plate", _types("curtain_panel", "sheet")),
    ClassInfo("IfcRailing", "railing", _types("handrail", "guardrail", "balustrade")),
    ClassInfo("IfcCovering", "covering", _types("ceiling", "flooring", "cladding", "roofing",
                                                "molding", "skirtingboard", "insulation",
                                                "membrane", "sleeving", "wrapping")),
    ClassInfo("IfcCurtainWall", "curtainwall", _types()),
    ClassInfo("IfcChimney", "chimney", _types()),
    ClassInfo("IfcFooting", "footing", _types("caisson_foundation", "footing_beam", "pad_footing",
                                              "pile_cap", "strip_footing")),
    ClassInfo("IfcPile", "pile", _types("bored", "driven", "jetgrouting", "cohesion", "friction",
                                        "support")),
    ClassInfo("IfcShadingDevice", "shading", _types("jalousie", "shutter", "awning")),
    ClassInfo("IfcBuildingElementPart", "part", _types("insulation", "precastpanel")),
    ClassInfo("IfcBuildingElementProxy", "proxy", _types("complex", "element", "partial",
                                                         "provisionforvoid",
                                                         "provisionforspace")),
    ClassInfo("IfcFurniture", "furniture", _types("chair", "table", "desk", "bed", "filecabinet",
                                                  "shelf", "sofa")),
    ClassInfo("IfcSystemFurnitureElement", "systemfurniture", _types("panel", "worksurface")),
    ClassInfo("IfcElementAssembly", "assembly", _types(
        "accessory_assembly", "arch", "beam_grid", "braced_frame", "girder",
        "reinforcement_unit", "rigid_frame", "slab_field", "truss")),
    ClassInfo("IfcTransportElement", "transport", _types("elevator", "escalator",
                                                         "movingwalkway", "craneway",
                                                         "liftinggear")),
    ClassInfo("IfcDiscreteAccessory", "accessory", _types("anchorplate", "bracket", "shoe")),
    ClassInfo("IfcGeographicElement", "geographic", _types("terrain")),
    ClassInfo("IfcCivilElement", "civil"),
    ClassInfo("IfcSpace", "space", _types("space", "parking", "gfa", "internal", "external"),
              (), "space"),
) + tuple(ClassInfo(f"Ifc{name}", name.lower(), _types()) for name in (
    # every other IFC4 physical element: the concrete subtypes of IfcElement that
    # are no feature or virtual element and need nothing but a body (the
    # 'StandardCase' and 'ElementedCase' classes need material layers or parts:
    # OUTSIDE_REFERENCE_VIEW); their short name is their IFC name's, their types
    # only userdefined and notdefined (tests/formats/test_ifc.py checks the
    # whole table against ifcopenshell's schema)
    "Actuator AirTerminal AirTerminalBox AirToAirHeatRecovery Alarm AudioVisualAppliance "
    "Boiler Burner CableCarrierFitting CableCarrierSegment CableFitting CableSegment Chiller "
    "Coil CommunicationsAppliance Compressor Condenser Controller CooledBeam CoolingTower "
    "Damper DistributionChamberElement DistributionControlElement DistributionElement "
    "DistributionFlowElement DuctFitting DuctSegment DuctSilencer ElectricAppliance "
    "ElectricDistributionBoard ElectricFlowStorageDevice ElectricGenerator ElectricMotor "
    "ElectricTimeControl EnergyConversionDevice Engine EvaporativeCooler Evaporator Fan "
    "Fastener Filter FireSuppressionTerminal FlowController FlowFitting FlowInstrument "
    "FlowMeter FlowMovingDevice FlowSegment FlowStorageDevice FlowTerminal "
    "FlowTreatmentDevice FurnishingElement HeatExchanger Humidifier Interceptor JunctionBox "
    "Lamp LightFixture MechanicalFastener MedicalDevice MotorConnection Outlet PipeFitting "
    "PipeSegment ProtectiveDevice ProtectiveDeviceTrippingUnit Pump ReinforcingBar "
    "ReinforcingMesh SanitaryTerminal Sensor SolarDevice SpaceHeater StackTerminal "
    "SwitchingDevice Tank Tendon TendonAnchor Transformer TubeBundle UnitaryControlElement "
    "UnitaryEquipment Valve VibrationIsolator WasteTerminal").split())

PROXY = "IfcBuildingElementProxy"

# classes IFC4 has that buildingSMART's Reference View leaves out (they imply
# material layers, parts or parametric shapes: IfcWallStandardCase's rule wants a
# material layer set usage, and IFC4.3 deprecates it), and the class each is
# written as: an annotation or --ifc-class naming one is taken, with a warning
# (reference_view_note)
OUTSIDE_REFERENCE_VIEW = {
    "IfcBeamStandardCase": "IfcBeam", "IfcColumnStandardCase": "IfcColumn",
    "IfcDoorStandardCase": "IfcDoor", "IfcMemberStandardCase": "IfcMember",
    "IfcPlateStandardCase": "IfcPlate", "IfcSlabElementedCase": "IfcSlab",
    "IfcSlabStandardCase": "IfcSlab", "IfcWallElementedCase": "IfcWall",
    "IfcWallStandardCase": "IfcWall", "IfcWindowStandardCase": "IfcWindow",
}


def reference_view_note(cls: str) -> str:
    """Why a class of OUTSIDE_REFERENCE_VIEW is written as another: the words
    the annotation's warning and --ifc-class's share."""
    return (f"buildingSMART's IFC4 Reference View has no {cls} (it implies material layers "
            f"or a parametric shape)")
STOREY = "storey"

# every way of writing a class, in lower case: short names and IFC names
BY_NAME: dict[str, ClassInfo] = {}
for _info in CLASSES:
    BY_NAME[_info.short] = _info
    BY_NAME[_info.ifc.lower()] = _info
BY_IFC: dict[str, ClassInfo] = {info.ifc: info for info in CLASSES}


class Classification(Record):
    """What the annotation on an object's line says it is."""

    __slots__ = ("ifc_class", "predefined", "settings", "long_name", "description", "location")

    def __init__(self, ifc_class: str, predefined: str | None, settings: tuple[tuple[str, str], ...],
                 long_name: str | None, description: str, location: Location):
        self.ifc_class = ifc_class  # "IfcWall"
        self.predefined = predefined  # "floor", or None
        self.settings = settings  # every setting of the class, (name, value): defaults filled
        self.long_name = long_name  # the quoted name, or None
        self.description = description  # the text after ']'
        self.location = location  # where the annotation's '[' is

    @property
    def info(self) -> ClassInfo:
        return BY_IFC[self.ifc_class]

    @property
    def short(self) -> str:
        return self.info.short

    @property
    def role(self) -> str:
        return self.info.role

    def setting(self, name: str) -> str | None:
        return dict(self.settings).get(name)

    def text(self) -> str:
        """The class in words, for a hover or an outline: ``door (hinge=left, swing=in)``."""
        words = [self.short] + ([self.predefined] if self.predefined else [])
        extra = [f"{k}={v}" for k, v in self.settings]
        if self.long_name:
            extra.insert(0, f'"{self.long_name}"')
        return " ".join(words) + (f" ({', '.join(extra)})" if extra else "")


class StoreyMark(Record):
    """``// [storey "Étage"]`` on a parameter: its value is a storey's floor level."""

    __slots__ = ("parameter", "name", "location")

    def __init__(self, parameter: str, name: str, location: Location):
        self.parameter = parameter
        self.name = name
        self.location = location


class Declared(Record):
    """The classes and storeys a scene declares, as they travel with each frame's
    tree (castor.csg.tree.FrameTree.classes): objects by the place of their
    definition (FILE, LINE, COLUMN of the name), storeys in the order declared."""

    __slots__ = ("objects", "storeys", "table")
    _compared = ("objects", "storeys")

    def __init__(self, objects: tuple[tuple[tuple[str, int, int], Classification], ...] = (),
                 storeys: tuple[StoreyMark, ...] = (), table=None):
        self.objects = objects
        self.storeys = storeys
        self.table = dict(objects)

    def of(self, location: Location | None) -> Classification | None:
        if location is None:
            return None
        return self.table.get((location.file, location.line, location.column))

    @property
    def has_spaces(self) -> bool:
        return any(c.role == "space" for _, c in self.objects)


class Problem(NamedTuple):
    """A warning about an annotation: never an error."""

    message: str
    location: Location


_TOKEN = re.compile(r'"[^"]*"|"[^"]*$|[^\s"=\]]+=[^\s"\]]*|[^\s"\]]+')


def is_class_annotation(text: str) -> bool:
    """Whether a comment's text is a bracket that starts with a class's name
    or ``storey`` (``[wall]``, ``[storey "Étage"]``), rather than §10's slider
    or choices."""
    word = re.match(r"\[\s*([A-Za-z_]\w*)(?=[\s\]\"]|$)", text.lstrip())
    return word is not None and (word[1].lower() in BY_NAME or word[1].lower() == STOREY)


def _closest(word: str, known) -> str:
    import difflib  # here: only a misspelt annotation needs it

    close = difflib.get_close_matches(word.lower(), list(known), n=1, cutoff=0.6)
    return f" (did you mean {close[0]}?)" if close else ""


def _split(text: str, location: Location):
    """The bracket's words, the description after it, and where the '[' is;
    or a Problem (a quote never closed, no ']')."""
    lead = len(text) - len(text.lstrip())
    at = Location(location.file, location.line, location.column + lead)
    body = text.lstrip()[1:]
    index, quoted = 0, False
    while index < len(body):
        ch = body[index]
        if ch == '"':
            quoted = not quoted
        elif ch == "]" and not quoted:
            break
        index += 1
    if quoted:
        start = body.find('"')
        where = Location(at.file, at.line, at.column + 1 + start)
        return Problem('annotation: the quoted name is never closed; write it between two '
                       '\'"\', as in [space "Séjour"]', where)
    if index >= len(body):
        return Problem("annotation: '[' without its ']'; write [CLASS ...] then the "
                       "description", at)
    return _TOKEN.findall(body[:index]), body[index + 1:].strip(), at


def read_object_annotation(text: str, location: Location) -> tuple[Classification | None,
                                                                   Problem | None]:
    """The class an object's comment gives it (``text``: the comment after
    '//', ``location``: where the text starts), or None with a Problem when
    it cannot be understood. A comment that is not a bracket is no class."""
    if not text.lstrip().startswith("["):
        return None, None
    split = _split(text, location)
    if isinstance(split, Problem):
        return None, split
    words, description, at = split
    if not words:
        return None, Problem("annotation: '[]' names no class; write [wall], [slab floor], "
                             "[door hinge=left] ...", at)
    head = words[0]
    if head.lower() == STOREY:
        return None, Problem("annotation: [storey] is for a parameter that holds a floor "
                             "level (R1 = 3.0; // [storey \"Étage\"]), not an object; the "
                             "object is unclassed", at)
    info = BY_NAME.get(head.lower())
    replaced = next((c for c in OUTSIDE_REFERENCE_VIEW if c.lower() == head.lower()), None)
    if replaced is not None:
        info = BY_IFC[OUTSIDE_REFERENCE_VIEW[replaced]]
    if info is None:
        import difflib

        names = {n: (BY_NAME[n].ifc if n.startswith("ifc") else n) for n in BY_NAME}
        close = difflib.get_close_matches(head.lower(), list(names) + [STOREY], n=1, cutoff=0.6)
        hint = f" (did you mean {names.get(close[0], STOREY)}?)" if close else ""
        return None, Problem(f"annotation: unknown class '{head}'{hint}"
                             f"; the object is unclassed", at)
    predefined, long_name = None, None
    settings = {s.name: s.default for s in info.settings}
    for word in words[1:]:
        if word.startswith('"'):
            long_name = word[1:-1]
        elif "=" in word:
            key, _, value = word.partition("=")
            setting = next((s for s in info.settings if s.name == key.lower()), None)
            if setting is None:
                names = [s.name for s in info.settings]
                known = f"; {info.short} has {', '.join(names)}" if names else \
                    f"; {info.short} has no settings"
                return None, Problem(f"annotation: unknown setting '{key}' of {info.short}"
                                     f"{_closest(key, names)}{known}; the object is "
                                     f"unclassed", at)
            if value.lower() not in setting.values:
                return None, Problem(f"annotation: {info.short}'s {setting.name} is "
                                     f"{'|'.join(setting.values)}, not '{value}'"
                                     f"{_closest(value, setting.values)}; the object is "
                                     f"unclassed", at)
            settings[setting.name] = value.lower()
        elif predefined is None and word.lower() in info.types:
            predefined = word.lower()
        else:
            listed = ", ".join(t for t in info.types if t not in ("userdefined", "notdefined"))
            kinds = f"; the types of {info.short}: {listed}" if listed else \
                f"; {info.short} has no types"
            return None, Problem(f"annotation: '{word}' is not a type of {info.short}"
                                 f"{_closest(word, info.types)}{kinds}; the object is "
                                 f"unclassed", at)
    classification = Classification(info.ifc, predefined, tuple(settings.items()), long_name,
                                    description, at)
    if replaced is not None:
        return classification, Problem(f"annotation: {reference_view_note(replaced)}; the "
                                       f"object is written as an {info.ifc} ({info.short})", at)
    return classification, None


def read_parameter_annotation(name: str, text: str, location: Location) -> tuple[
        StoreyMark | None, Problem | None]:
    """A parameter's class-like annotation: ``[storey "Name"]`` makes a storey
    (named after the parameter when no name is given); a class is a Problem."""
    split = _split(text, location)
    if isinstance(split, Problem):
        return None, split
    words, _, at = split
    head = words[0] if words else ""
    if head.lower() == STOREY:
        quoted = [w[1:-1] for w in words[1:] if w.startswith('"')]
        others = [w for w in words[1:] if not w.startswith('"')]
        if others:
            return None, Problem(f"annotation: a storey takes only its name in quotes, not "
                                 f"'{others[0]}': [storey \"Étage\"]", at)
        return StoreyMark(name, quoted[0] if quoted else name, at), None
    if head.lower() in BY_NAME:
        return None, Problem(f"annotation: a class ([{head}]) is for an object's definition (a "
                             f"lowercase name); a parameter can only be a storey's level: "
                             f"[storey \"Name\"]", at)
    return None, Problem(f"annotation: unknown word '{head}' in a parameter's annotation"
                         f"{_closest(head, [STOREY])}; write [MIN:MAX], [A, B, C] or "
                         f"[storey \"Name\"]", at)

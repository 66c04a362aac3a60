"""What a drawing is made of, and the six directions it can be seen from."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from castor.options import ORTHOGRAPHIC


class ViewBasis(NamedTuple):
    """An orthographic direction: the page's right and up, and the direction
    towards the viewer (right x up = towards), all unit vectors of the scene."""

    name: str
    right: tuple[float, float, float]
    up: tuple[float, float, float]
    towards: tuple[float, float, float]

    def basis(self) -> np.ndarray:
        """(3, 3): rows right, up, towards; a point p is seen at basis @ p."""
        return np.array([self.right, self.up, self.towards], dtype=np.float64)

    def plane_depth(self, section) -> float | None:
        """The depth (along ``towards``) of the section plane, or None."""
        if section is None:
            return None
        axis = "xyz".index(section.axis)
        return float(self.towards[axis]) * section.value


# the named views of castor.options, each with its name
VIEWS = {name: ViewBasis(name, *axes) for name, axes in ORTHOGRAPHIC.items()}

# a section is seen from above (z, a plan) or looking towards +x or +y
SECTION_VIEWS = {"z": "top", "x": "left", "y": "front"}


def view_for(section, view) -> ViewBasis:
    """The direction a drawing is seen from: the section's own, else the
    orthographic --view, else the front (a perspective --view, the default
    included, gives the front elevation: a drawing is never in perspective)."""
    if section is not None:
        return VIEWS[SECTION_VIEWS[section.axis]]
    name = getattr(view, "name", None)
    return VIEWS[name] if name in VIEWS else VIEWS["front"]


@dataclass
class Layer:
    """One object of the frame as drawn: its cut regions (closed loops of
    page points, outer boundaries counter-clockwise, holes clockwise) and the
    segments of its edges that are seen, all in metres on the page; ``profile``
    says which seen segments are its outline against what lies behind."""

    name: str
    cuts: list[np.ndarray] = field(default_factory=list)  # each (n, 2)
    lines: np.ndarray = field(default_factory=lambda: np.zeros((0, 2, 2)))  # (L, 2, 2)
    profile: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))  # (L,)
    source: int = -1  # the index of its object in the frame
    # with classes (castor.drawings.classes): its cut regions element by element,
    # each hatched by its class; None: the cuts are solid grey
    regions: list | None = None


@dataclass
class Drawing:
    layers: list[Layer]
    view: ViewBasis
    scale: float  # the N of 1:N
    section: object = None  # castor.options.Section, None for an elevation
    symbols: object = None  # castor.drawings.classes.Symbols, with classes only
    fields: dict = field(default_factory=dict)  # the title block's fields (settings.fields)

    @property
    def is_plan(self) -> bool:
        return self.view.name == "top"

    def description(self) -> str:
        """What the drawing is, as a title block says it: 'Plan z = 1.20'."""
        if self.section is None:
            return f"Elevation {self.view.name}"
        kind = "Plan" if self.section.axis == "z" else "Section"
        text = f"{kind} {self.section.axis} = {self.section.value:.2f}"
        storey = getattr(self.symbols, "storey", None)
        if storey is not None:
            from castor.drawings.annotate import level_text

            text += f", {storey[0]} {level_text(storey[1])}"
        return text

    def box(self) -> np.ndarray:
        """(2, 2): the lower-left and upper-right corners of what is drawn, in metres."""
        points = [l.lines.reshape(-1, 2) for l in self.layers]
        points += [c for l in self.layers for c in l.cuts]
        points = [p for p in points if len(p)]
        if not points:
            return np.zeros((2, 2))
        allp = np.concatenate(points)
        return np.array([allp.min(axis=0), allp.max(axis=0)])

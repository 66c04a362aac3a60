"""What a drawing is made of, and which named view (castor.settings.ORTHOGRAPHIC)
it is seen from."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from castor.settings import ORTHOGRAPHIC, Orthographic

# a section is seen from above (z, a plan) or looking towards +x or +y
SECTION_VIEWS = {"z": "top", "x": "left", "y": "front"}


def view_for(section, view) -> Orthographic:
    """The direction a drawing is seen from: the section's own, else the
    orthographic --view, else the front (a perspective --view, the default
    included, gives the front elevation: a drawing is never in perspective)."""
    if section is not None:
        return ORTHOGRAPHIC[SECTION_VIEWS[section.axis]]
    name = getattr(view, "name", None)
    return ORTHOGRAPHIC[name] if name in ORTHOGRAPHIC else ORTHOGRAPHIC["front"]


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
    view: Orthographic
    scale: float  # the N of 1:N
    section: object = None  # castor.settings.Section, None for an elevation
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

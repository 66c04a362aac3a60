"""The building model of a frame (OUTPUT.md, "A model a BIM coordinator accepts"):
its storeys, its elements with their own solids, openings filled by doors and
windows, spaces, base quantities; plain data made from the evaluated tree and
the take-off of LANGUAGE.md §11 (castor.quantities.Takeoff), with the choices
the model had to make said as warnings. castor.formats.ifc writes it.

``model.py`` parts the frame out (storeys, elements, openings, spaces),
``measures.py`` gives each the base quantities buildingSMART names. Neither
imports ifcopenshell.
"""

from castor.bim.model import Building, Part, Storey, Void, build

__all__ = ["Building", "Part", "Storey", "Void", "build"]

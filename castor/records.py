"""Plain records: what the scene graph (castor.language.scene), the evaluated
tree (castor.csg.tree) and the settings (castor.settings) are made of, without
dataclasses.

Those two modules and the settings (castor.settings) declared 32 dataclasses,
and making a dataclass runs Python's code generator for each of its methods:
about 0.6 ms a class, some 20 ms of every start-up of castor (issue 18), for
classes whose ``__init__`` is a few lines. Their classes now write their
``__slots__`` and ``__init__`` by hand and take equality, hashing, ``replace``
and their text from ``Record``, from the fields named in ``__slots__``.
"""

from __future__ import annotations


class Record:
    """A record whose fields are its ``__slots__``: equal to a record of the same
    class whose fields it names in ``_compared`` are equal (all of them unless
    the class says otherwise), hashed alike, and written ``Name(field=value, ...)``.
    Records are never changed once made (they are not made frozen: setting each
    field through ``object.__setattr__`` would slow their making, and a scene
    makes many)."""

    __slots__ = ()
    _compared: tuple[str, ...] | None = None  # None: every field

    def _fields(self) -> tuple[str, ...]:
        return type(self).__slots__

    def _values(self) -> tuple:
        names = self._compared if self._compared is not None else self._fields()
        return tuple(getattr(self, name) for name in names)

    def __eq__(self, other) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return self._values() == other._values()

    def __hash__(self) -> int:
        return hash(self._values())

    def replace(self, **changes):
        """A copy with ``changes`` made to its fields (as ``dataclasses.replace``)."""
        values = {name: getattr(self, name) for name in self._fields()}
        values.update(changes)
        return type(self)(**values)

    def __repr__(self) -> str:
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name in self._fields())
        return f"{type(self).__name__}({fields})"


class Identified(Record):
    """A record equal only to itself (as a dataclass with ``eq=False``): the nodes
    of a scene graph, shared by reference."""

    __slots__ = ()
    __eq__ = object.__eq__
    __hash__ = object.__hash__

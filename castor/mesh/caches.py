"""Every cache of the facetizer, in one place, under one eviction policy.

A process holds one ``Caches`` (``PROCESS``): what it remembers between
booleans, parts and frames, and so how much memory it may keep. Each
cache but one is a ``Bounded`` dictionary, whose policy is the same for all:

    before an entry goes in, a cache that holds more than its number of
    entries, or whose weight with the new entry would pass its bound, is
    emptied at once.

Emptying whole is enough: what is cached is found again by content (a shared
subtree's key, a primitive's kind, shape and facets, triangles' bytes), so a
cache emptied costs time, never a different result. The exception is the
table of templates by engine ID, which holds none of them: an entry lives as
long as its template does (a weak reference).
"""

from __future__ import annotations

import weakref


class Bounded:
    """A dictionary emptied whole when it would pass its bounds (see above)."""

    __slots__ = ("weight", "max_entries", "max_weight", "_data", "hits")

    def __init__(self, max_entries: int | None = None, max_weight: int | None = None):
        self.max_entries = max_entries
        self.max_weight = max_weight
        self.weight = 0
        self._data: dict = {}
        self.hits = 0  # lookups that found their entry (what was reused, counted)

    def get(self, key):
        found = self._data.get(key)
        if found is not None:
            self.hits += 1
        return found

    def __contains__(self, key) -> bool:
        return key in self._data

    def __len__(self) -> int:
        return len(self._data)

    def put(self, key, value, weight: int = 0) -> None:
        if (self.max_entries is not None and len(self._data) > self.max_entries) or (
                self.max_weight is not None and self.weight + weight > self.max_weight):
            self.clear()
        self._data[key] = value
        self.weight += weight

    def clear(self) -> None:
        self._data.clear()
        self.weight = 0


class Caches:
    """The caches of one process, each named for what it holds."""

    def __init__(self):
        # shared subtree's key -> (the engine's solid as computed, its primitives);
        # weighed in triangles
        self.solids = Bounded(max_weight=4_000_000)
        # (kind, shape, facet tolerance) -> (the primitive's template, its triangles)
        self.templates = Bounded(max_entries=4096)
        # engine ID -> template, for every ID a template's runs carry (checks.off_faces)
        self.engine_ids: "weakref.WeakValueDictionary[int, object]" = weakref.WeakValueDictionary()
        # content key of a boolean (castor.mesh.keys) -> the engine's result,
        # regularized: the same operands met again (the next frame, a slider's
        # next value) go to the engine no more; weighed in triangles
        self.booleans = Bounded(max_entries=10_000, max_weight=1_000_000)
        # id() of a union's result no two of whose primitives' planes meet -> that
        # result (held, so that its id is not reused): no sheet can be in it
        self.plain = Bounded(max_entries=1000)
        # hash of a part's triangles and faces -> True: found free of flat
        # triangles and sheets (a copy moved by an affine map is too)
        self.clean = Bounded(max_entries=10_000)
        # digest of a batch's vertices, triangles and faces as the engine gave
        # them -> their regularization (castor.mesh.regularize): a boolean
        # whose operands did not change since the last frame is not
        # regularized again (the live preview, the language server); weighed
        # in triangles
        self.regular = Bounded(max_entries=10_000, max_weight=4_000_000)
        # digest of one plane's triangles where a sheet is cut out -> what
        # cutting it did (castor.mesh.sheets): the planes a change did not
        # touch, inside a part that did change; weighed in triangles
        self.planes = Bounded(max_entries=20_000, max_weight=500_000)
        # a part's triangles and faces -> (its polygons, its vertices): copies of
        # one object merged once (merge.Merger); weighed in triangles, emptied
        # at each frame
        self.patterns = Bounded(max_entries=10_000, max_weight=2_000_000)
        # digest of a part's vertices, triangles and faces -> its polygons
        # (merge.Merger): a part that did not change since the last frame is
        # not merged again; weighed in triangles
        self.merged = Bounded(max_entries=10_000, max_weight=1_000_000)
        # digest of one face's group of triangles, on its own vertices -> its
        # polygons (merge._groups_polygons): the faces a change did not touch,
        # inside a part that did change; weighed in triangles
        self.groups = Bounded(max_entries=100_000, max_weight=500_000)

    def new_facetizer(self) -> None:
        """A new facetizer starts from nothing built (what benchmarks measure)."""
        self.solids.clear()
        self.templates.clear()
        self.regular.clear()
        self.booleans.clear()
        self.planes.clear()
        self.merged.clear()
        self.groups.clear()


PROCESS = Caches()

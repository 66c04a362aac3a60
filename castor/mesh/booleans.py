"""The booleans: regularized union, intersection and difference of solids.

Only operands whose boxes meet go to the engine (castor.mesh.broadphase);
each result is checked and, if need be, computed again another way
(castor.mesh.checks), then regularized (castor.mesh.regularize). Uses of one
template at one place in two operands are first told apart (``_distinguished``),
so that provenance can still name each; where renaming the runs of a twin
inside a result of the engine leads the engine astray (a result off its
faces), the boolean is computed again without it, and provenance tells the
twins apart by the way their triangles face (provenance.facing_twins).
"""

from __future__ import annotations

import numpy as np

from castor.mesh import adapter, keys
from castor.mesh.arrays import row_hash, shared_across
from castor.mesh.broadphase import apart, overlap_groups
from castor.mesh.caches import PROCESS
from castor.mesh.checks import checked, off_faces
from castor.mesh.instances import Placed, fill_boxes, in_engine
from castor.mesh.provenance import Origins, merged_origins, place_key
from castor.mesh.regularize import mark_plain, planes_meet, regular
from castor.mesh.solid import EMPTY, Solid, of_parts


def _distinguished(solids: list, rename: bool = True) -> list:
    """The operands of one boolean, with every use of a primitive that stands
    where a use in an earlier operand stands given an ID of its own (its
    triangles would otherwise be told apart by neither ID nor placement: a
    cube cut away and the same cube added back have different paths and
    colours). A use not yet in the engine takes a copy of its template under
    a new ID; a use inside a result of the engine, its runs renamed
    (``_renamed_runs``) when no use of the clash is still outside it, and
    ``rename`` is true."""
    if len(solids) < 2 or not _may_clash(solids):
        return solids
    keys = [s.origins.keys() for s in solids]
    placed = [{(p.id, place_key(p.matrix)) for p in s.parts if type(p) is Placed} for s in solids]
    owners: dict = {}
    for k, operand_keys in enumerate(keys):
        for key in operand_keys:
            owners.setdefault(key, []).append(k)
    renew: list[set] = [set() for _ in solids]
    inside: list[set] = [set() for _ in solids]
    for key, where in owners.items():
        if len(where) < 2:
            continue
        # the use inside a result of the engine keeps the ID; uses not yet in
        # the engine take new ones, and other uses inside results are renamed
        fixed = [k for k in where if key not in placed[k]]
        keep = fixed[0] if fixed else where[0]
        for k in where:
            if k != keep:
                (renew if key in placed[k] else inside)[k].add(key)
    out = []
    for solid, wanted, renamed in zip(solids, renew, inside):
        if wanted:
            parts, changes = [], {}
            for part in solid.parts:
                if type(part) is Placed and (key := (part.id, place_key(part.matrix))) in wanted:
                    part = part.distinguished()
                    changes[key] = part.id
                parts.append(part)
            solid = Solid(tuple(parts), solid.origins.renamed(changes))
        if renamed and rename:
            solid = _renamed_runs(solid, renamed)
        out.append(solid)
    return out


def _renamed_runs(solid: Solid, wanted: set) -> Solid:
    """The solid whose uses ``wanted`` (keys: ID and rounded placement),
    inside results of the engine, are under new IDs: the runs of those uses
    in its engine parts and their entries in its origins."""
    new_ids = {}
    for key in sorted(wanted, key=lambda k: (k[0], k[1])):
        new_ids[key] = adapter.reserve_ids(1)
        template = PROCESS.engine_ids.get(key[0])
        if template is not None:
            PROCESS.engine_ids[new_ids[key]] = template
    parts = []
    for part in solid.parts:
        if type(part) is not Placed:
            mesh = adapter.to_arrays(part)
            if len(mesh.run_ids):
                entries = solid.origins.find(mesh.run_ids, mesh.placements)
                ids = mesh.run_ids.copy()
                for r, entry in enumerate(entries.tolist()):
                    key = (int(solid.origins.ids[entry]), place_key(solid.origins.matrices[entry]))
                    if key in new_ids:
                        ids[r] = new_ids[key]
                if np.any(ids != mesh.run_ids):
                    renamed = adapter.with_run_ids(part, ids)
                    if renamed is None:
                        # the engine would change the part: it keeps its IDs
                        # (and either twin's name may be given to both)
                        return solid
                    part = renamed
        parts.append(part)
    return Solid(tuple(parts), solid.origins.renamed(new_ids))


def _twins_renamed(solids: list, distinguished: list) -> bool:
    """Whether telling the operands' twins apart renamed runs inside results
    of the engine (a round trip of their meshes, which the engine was seen to
    treat otherwise in the boolean that follows)."""
    return any(d.parts is not s.parts and any(
        type(a) is not Placed and a is not b for a, b in zip(s.parts, d.parts))
        for s, d in zip(solids, distinguished))


def _better(first, again, made=lambda result: result):
    """The result of a boolean whose operands' twins were renamed
    (``first``: a function giving the engine's result), or, if that is off
    its faces (checks.off_faces), the same boolean of the operands as they
    were (``again``) when it has fewer triangles off; each gives (result,
    solids), and ``made`` picks from a result what the engine made."""
    result, solids = first()
    wrong = _off(made(result))
    if not wrong:
        return result, solids
    other, other_solids = again()
    return (other, other_solids) if _off(made(other)) < wrong else (result, solids)


def _off(result) -> int:
    """Triangles off their faces in a result of the engine, or in a list of
    parts (placed primitives are whole)."""
    parts = result if isinstance(result, (list, tuple)) else [result]
    return sum(off_faces(p) for p in parts if type(p) is not Placed)


def _may_clash(solids: list) -> bool:
    """Whether two operands may have a use of one template at one place: one
    number per entry (its ID and rounded placement, hashed), sorted."""
    every = Origins.merged([s.origins for s in solids])
    key = row_hash(np.column_stack([every.ids, np.round(every.matrices.reshape(-1, 12) * 1e9)]))
    owner = np.repeat(np.arange(len(solids)), [len(s.origins) for s in solids])
    return shared_across(key, owner)


class Counter:
    """Counts the calls made to the engine, for --stats."""

    def __init__(self):
        self.booleans = 0


def union(solids: list[Solid], counter: Counter) -> Solid:
    """Regularized union; parts whose boxes do not meet stay separate parts."""
    solids = [s for s in solids if not s.empty]
    if not solids:
        return EMPTY
    if len(solids) == 1:
        return solids[0]
    distinguished = _distinguished(solids)
    if not _twins_renamed(solids, distinguished):
        return _union(distinguished, counter)
    # a union of every group, or none, with renamed twins: one table of origins
    counted = counter.booleans
    result = _union(distinguished, counter)
    wrong = _off(result.parts)
    if not wrong:
        return result
    counter.booleans = counted
    again = _union(_distinguished(solids, rename=False), counter)
    return again if _off(again.parts) < wrong else result


def _union(solids: list[Solid], counter: Counter) -> Solid:
    """The union of operands whose twins are told apart."""
    parts = [part for s in solids for part in s.parts]
    known = [s.key(i) for s in solids for i in range(len(s.parts))]
    fill_boxes(parts)
    boxes = np.array([part.bounding_box() for part in parts], dtype=np.float64).reshape(-1, 2, 3)
    origins = merged_origins(solids)
    result, result_boxes, result_keys = [], [], []
    for group in overlap_groups(boxes):
        if len(group) == 1:
            result.append(parts[group[0]])
            result_boxes.append(boxes[group[0]])
            result_keys.append(known[group[0]])
            continue
        key = keys.derived(b"U", [known[i] for i in group])
        united = _reused(key, lambda: regular(_united(_distinct(
            [in_engine(parts[i]) for i in group]))), counter)
        if all(type(parts[i]) is Placed for i in group) and not planes_meet(
                [parts[i] for i in group]):
            mark_plain(united)
        result.append(united)
        result_boxes.append(np.array([boxes[group, 0].min(axis=0), boxes[group, 1].max(axis=0)]))
        result_keys.append(key)
    fewer = _fewer_parts(result, np.array(result_boxes))
    return of_parts(fewer, origins, result_keys if fewer is result else None)


def _reused(key, make, counter: Counter) -> adapter.Manifold:
    """``make()``, the engine's regularized result of a boolean whose content
    key is ``key`` (castor.mesh.keys), or the result made before for that key
    (caches.PROCESS.booleans: operands that did not change since the last
    frame); the engine's calls counted."""
    found = None if key is None else PROCESS.booleans.get(key)
    if found is not None:
        return found
    counter.booleans += 1
    made = make()
    if key is not None:
        PROCESS.booleans.put(key, made, made.num_tri())
    return made


def _distinct(manifolds: list) -> list:
    """The manifolds without exact copies: A with A is A, and the engine,
    asked to unite a solid with a copy of itself (every face coincident), was
    seen to lose volume. Copies are found by their counts, box, volume and
    area, then confirmed vertex for vertex."""
    kept, seen = [], {}
    for m in manifolds:
        key = (m.num_tri(), m.num_vert(), m.bounding_box(), m.volume(), m.surface_area())
        twins = seen.setdefault(key, [])
        if any(_same_mesh(m, other) for other in twins):
            continue
        twins.append(m)
        kept.append(m)
    return kept


def _same_mesh(a: adapter.Manifold, b: adapter.Manifold) -> bool:
    ga, gb = adapter.to_arrays(a), adapter.to_arrays(b)
    ta = np.sort(np.sort(ga.vertices[ga.triangles].reshape(-1, 9).view(
        [("", np.float64)] * 9), axis=0), axis=0)
    tb = np.sort(np.sort(gb.vertices[gb.triangles].reshape(-1, 9).view(
        [("", np.float64)] * 9), axis=0), axis=0)
    return ta.shape == tb.shape and bool(np.all(ta == tb))


def _united(operands: list) -> adapter.Manifold:
    """The union of manifolds, two at a time in a balanced tree. (manifold3d's
    batch_boolean unites them all at once; on operands whose faces coincide,
    copies of one object side by side, it was seen to lose volume where
    unions two at a time do not: tests/geometry/test_regular_booleans.py.)"""
    united = _balanced(operands)
    if not off_faces(united):
        return united
    # some union went wrong (off_faces): again, two at a time, each checked and
    # computed the other way round if need be
    while len(operands) > 1:
        operands = [_checked_union(operands[k], operands[k + 1]) if k + 1 < len(operands)
                    else operands[k] for k in range(0, len(operands), 2)]
    return operands[0]


def _checked_union(a: adapter.Manifold, b: adapter.Manifold) -> adapter.Manifold:
    """a + b, or the same union computed another way if the engine's is off
    its faces: b + a, then (a - b) + b and (b - a) + a."""
    add, subtract = adapter.add, adapter.subtract
    return checked(add(a, b), lambda: add(b, a), lambda: add(checked(subtract(a, b)), b),
                   lambda: add(checked(subtract(b, a)), a))


def _balanced(operands: list) -> adapter.Manifold:
    while len(operands) > 1:
        operands = [adapter.add(operands[k], operands[k + 1]) if k + 1 < len(operands)
                    else operands[k]
                    for k in range(0, len(operands), 2)]
    return operands[0]


# More parts than this are composed into fewer: each part costs the engine a
# few kilobytes and castor a Python call, whatever its size.
MAX_PARTS = 1024


def _fewer_parts(parts: list, boxes: np.ndarray) -> list:
    """Many parts of the engine composed into at most MAX_PARTS, neighbours
    together (by x). Placed primitives stay as they are: they cost little."""
    engine_parts = [i for i, p in enumerate(parts) if type(p) is not Placed]
    if len(engine_parts) <= MAX_PARTS:
        return parts
    placed = [p for p in parts if type(p) is Placed]
    parts = [parts[i] for i in engine_parts]
    boxes = boxes[engine_parts]
    order = np.argsort(boxes[:, 0, 0], kind="stable")
    size = -(-len(parts) // MAX_PARTS)
    # held as their parts, composed by the engine when read (adapter.Composed)
    return placed + [adapter.Composed([parts[i] for i in order[k:k + size]])
                     for k in range(0, len(parts), size)]


def intersection(solids: list[Solid], counter: Counter) -> Solid:
    """Regularized intersection; empty at once if the boxes have no common interior."""
    if not solids or any(s.empty for s in solids):
        return EMPTY
    if len(solids) == 1:
        return solids[0]
    boxes = np.stack([s.box() for s in solids])
    lo, hi = boxes[:, 0, :].max(axis=0), boxes[:, 1, :].min(axis=0)
    if np.any(lo >= hi):
        return EMPTY

    def made(operands):
        operands = [s.in_engine() for s in operands]
        wholes = [s.whole() for s in operands]
        return checked(adapter.intersect_all(wholes),
                       lambda: adapter.intersect_all(wholes[::-1])), operands

    distinguished = _distinguished(solids)
    if not _twins_renamed(solids, distinguished):
        key = keys.derived(b"I", [s.whole_key() for s in distinguished])
        result = _reused(key, lambda: regular(made(distinguished)[0]), counter)
        return of_parts([result], merged_origins(distinguished), [key])
    counter.booleans += 1
    manifold, solids = _better(lambda: made(distinguished),
                               lambda: made(_distinguished(solids, rename=False)))
    return of_parts([regular(manifold)], merged_origins(solids))


def difference(a: Solid, b: Solid, counter: Counter) -> Solid:
    """Regularized a - b, part by part; a part whose box does not meet b's stays."""
    if a.empty or b.empty:
        return a
    box_b = b.box()
    boxes = a.part_boxes()
    touched = [i for i in range(len(a.parts)) if not apart(boxes[i], box_b)]
    if not touched:
        return a

    def made(operands):
        a, b = operands
        a = a.in_engine(touched)
        b = b.in_engine()
        cutter = b.whole()
        parts = list(a.parts)
        for i in touched:
            part = parts[i]
            # (A + B) - B is A - B, computed otherwise
            parts[i] = checked(adapter.subtract(part, cutter), lambda part=part:
                               adapter.subtract(adapter.add(part, cutter), cutter))
        return parts, (a, b)

    distinguished = _distinguished([a, b])
    if not _twins_renamed([a, b], distinguished):
        return _reused_difference(distinguished, touched, counter)
    counter.booleans += 1
    parts, operands = _better(lambda: made(distinguished),
                              lambda: made(_distinguished([a, b], rename=False)),
                              lambda parts: [parts[i] for i in touched])
    for i in touched:
        parts[i] = regular(parts[i])
    return of_parts(parts, merged_origins(operands))


def _reused_difference(operands: list, touched: list, counter: Counter) -> Solid:
    """a - b part by part (the parts of a numbered in ``touched``), each part's
    result the one made before for the same part and cutter if there is one
    (``_reused``); one engine call counted for the difference."""
    a, b = operands
    known = [a.key(i) for i in range(len(a.parts))]
    cutter_key = b.whole_key()
    a, b = a.in_engine(touched), b.in_engine()
    cutter = b.whole()
    parts = list(a.parts)
    calls = Counter()
    for i in touched:
        part = parts[i]
        known[i] = keys.derived(b"D", [known[i], cutter_key])
        # (A + B) - B is A - B, computed otherwise
        parts[i] = _reused(known[i], lambda part=part: regular(checked(
            adapter.subtract(part, cutter),
            lambda: adapter.subtract(adapter.add(part, cutter), cutter))), calls)
    counter.booleans += min(calls.booleans, 1)
    return of_parts(parts, merged_origins((a, b)), known)

"""What a process remembers while it facetizes (castor.mesh.caches): one
owner, one eviction policy, and nothing remembered changes a result."""

from castor.mesh.caches import PROCESS, Bounded

FOREST = """arbre = $U(@h(0.15, 0.15, 1.2) !cy(0.45, 0.3, 0.15), @t(0, 0, 1.8) @h(0.8) !sp(0.2, 0.55, 0.2));
> $U[I = 0, 3](@t(2.5 * I, 0, 0) arbre);
"""


def test_a_cache_is_emptied_whole_past_its_number_of_entries():
    cache = Bounded(max_entries=2)
    for k in range(3):
        cache.put(k, str(k))
    assert len(cache) == 3 and cache.get(0) == "0"  # more than 2 only before the 4th
    cache.put(3, "3")
    assert len(cache) == 1 and cache.get(0) is None and cache.get(3) == "3"


def test_a_cache_is_emptied_whole_before_its_weight_would_pass():
    cache = Bounded(max_weight=10)
    cache.put("a", 1, weight=6)
    cache.put("b", 2, weight=4)
    assert cache.weight == 10 and "a" in cache
    cache.put("c", 3, weight=1)
    assert "a" not in cache and "b" not in cache and cache.get("c") == 3 and cache.weight == 1


def _frames(text):
    from castor.run import evaluated_frames

    frames, _ = evaluated_frames(text, "caches")
    return frames


def test_a_shared_solid_is_built_once_per_facetizer_and_the_same_from_the_cache():
    from castor.mesh.facetize import Facetizer

    [scene] = _frames(FOREST)
    facetizer = Facetizer()
    first = facetizer.frame(scene)
    assert facetizer.counter.booleans == 1  # the tree's union, once for 4 uses
    again = facetizer.frame(scene)
    assert facetizer.counter.booleans == 0  # from PROCESS.solids
    assert (again.objects[0].vertices == first.objects[0].vertices).all()
    assert (again.objects[0].indices == first.objects[0].indices).all()
    assert len(PROCESS.solids) >= 1 and len(PROCESS.templates) == 2
    Facetizer().frame(scene)  # a new facetizer starts from nothing built
    assert len(PROCESS.templates) == 2


def test_the_polygon_limit_holds_for_a_template_another_facetizer_cached():
    """Two facetizers of one process (jobs keeps one per setting) share the
    templates: each checks a cached primitive against its own limit."""
    import pytest

    from castor.diagnostics import LimitError
    from castor.mesh.facetize import Facetizer

    [scene] = _frames("> !sp(1, 1, 1);\n")  # about 1,100 triangles
    small = Facetizer(max_polygons=300)  # the estimate passes: under 4 x 300
    Facetizer().frame(scene)
    assert len(PROCESS.templates) == 1
    with pytest.raises(LimitError, match="more than 300 polygons") as refused:
        small.frame(scene)
    assert refused.value.location.column == 3  # at the primitive, before any merging

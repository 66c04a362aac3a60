"""A union of more parts than booleans.MAX_PARTS is composed into fewer; the
compositions are held as their parts and made by the engine when read
(adapter.Composed), not all made at once and held beside the parts they were
made of (1.1 GB of the 1.4 GB of 4,096 houses). The frame is the one the
compositions made at once give, triangle for triangle and in the same order."""

from castor.mesh import adapter, booleans
from castor.settings import EvaluationSettings

# 5 rows of 8 cubes each with a sphere on it, apart from each other: with at
# most 4 parts, each row is composed into 4 and the 20 compositions of the
# block into 4 compositions of compositions
SCENE = ("> $U[I = 0, 4]($U[J = 0, 7](@t(3 * I, 3 * J, 0) "
         "$U(!cu(1, 0, 0), @t(0.5, 0.5, 1) @h(0.5, 0.5, 0.5) !sp(0, 1, 0))));\n")


def _frame_tree():
    from castor.run import evaluated_frames

    [tree], said = evaluated_frames(SCENE, "block.cas", EvaluationSettings())
    assert not said, said
    return tree


def _made_at_once(parts):
    """The compositions as they were made before: at once, and kept."""
    made = adapter.compose(parts)
    made.num_tri()
    return made


def test_a_union_of_many_parts_holds_compositions_made_when_read(monkeypatch):
    from castor.mesh.facetize import Facetizer

    monkeypatch.setattr(booleans, "MAX_PARTS", 4)
    facetizer = Facetizer()
    tree = _frame_tree()
    solid = facetizer.solid(tree.objects[0].root)
    assert len(solid.parts) == 4
    for part in solid.parts:
        assert type(part) is adapter.Composed
        assert all(type(inner) is adapter.Composed for inner in part.parts)
        made = part.manifold()  # the engine's: the counts and box are its own
        assert (part.num_tri(), part.num_vert()) == (made.num_tri(), made.num_vert())
        assert part.bounding_box() == tuple(made.bounding_box())
    assert sum(part.num_tri() for part in solid.parts) == 40 * solid.parts[0].parts[0].parts[0].num_tri()


def test_the_frame_is_the_one_of_compositions_made_at_once(monkeypatch):
    from castor.mesh.facetize import Facetizer

    monkeypatch.setattr(booleans, "MAX_PARTS", 4)
    read = Facetizer().frame(_frame_tree())
    monkeypatch.setattr(adapter, "Composed", _made_at_once)
    at_once = Facetizer().frame(_frame_tree())
    [a], [b] = read.objects, at_once.objects
    assert a.vertices.shape == b.vertices.shape and (a.vertices == b.vertices).all()
    assert (a.indices == b.indices).all() and (a.offsets == b.offsets).all()
    assert (a.origin_of == b.origin_of).all()
    assert [o.path for o in a.origins] == [o.path for o in b.origins]

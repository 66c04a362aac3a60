"""A statement that names an undefined object is reported and dropped: the
parser stands an UndefinedReference in for the name, never a primitive."""

from castor.diagnostics import CastorError
from castor.language.parse import Parser, SkippedDefinition
from castor.language.reader import Chunk
from castor.language.scene import FrameCommand, PrimitiveNode, Tables, UndefinedReference


def _parsed(text: str, tables: Tables):
    chunk = Chunk(text, (("s.cas", 1), ("s.cas", 1)), 0)
    return list(Parser(tables).parse(chunk))


def test_an_undefined_object_is_reported_and_its_statement_dropped():
    tables = Tables()
    items = _parsed("> $U(porte, !cu(1, 0, 0));", tables)
    assert not any(isinstance(i, FrameCommand) for i in items)
    assert [i.message for i in items if isinstance(i, CastorError)] == \
        ["object 'porte' is not defined"]


def test_a_definition_naming_an_undefined_object_leaves_its_name_broken():
    tables = Tables()
    items = _parsed("mur = @t(1, 0, 0) porte;", tables)
    assert [i.message for i in items if isinstance(i, CastorError)] == \
        ["object 'porte' is not defined"]
    assert [i.name for i in items if isinstance(i, SkippedDefinition)] == ["mur"]
    assert "mur" in tables.broken and "mur" not in tables.objects


def test_the_stand_in_is_no_primitive():
    from castor.language.parse import Builder

    builder = Builder(Tables())
    builder.chunk = Chunk("porte", (("s.cas", 1), ("s.cas", 1)), 0)

    class Token(str):
        line, column, start_pos = 1, 1, 0  # (the builder reads start_pos)

    node = builder.reference([Token("porte")])
    assert isinstance(node, UndefinedReference) and not isinstance(node, PrimitiveNode)
    assert node.name == "porte" and node.params == frozenset() and node.depth == 1
    assert builder.faults[0].message == "object 'porte' is not defined"

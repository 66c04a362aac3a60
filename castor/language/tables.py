"""The LALR tables of castor.lark, made when the package is built and shipped in it.

Building lark's parser from the grammar is the slow part of start-up (about
0.2 s; loading saved tables about 0.01 s). ``pip install .`` runs ``save`` (from
setup.py's build step) into the built package, as ``castor.tables`` beside the
grammar; at run time ``load`` reads it and never writes: a file that does not
match this grammar and this lark (a grammar edited in a checkout, another lark
installed) is ignored, and the parser is built as before (lark then keeps its own
cache in the temporary directory, never in the package).

This module imports nothing from castor, so that the build can run it from the
source tree by its path.
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
GRAMMAR = HERE / "castor.lark"
TABLES = HERE / "castor.tables"

# the parser's options: the same for the tables saved and a parser built
OPTIONS = {"parser": "lalr", "lexer": "contextual", "start": ["statement", "program"],
           "maybe_placeholders": True}
_MAGIC = b"castor-lark-tables "


def _key(grammar: str) -> bytes:
    """What the tables depend on: the grammar, the options and lark's version."""
    import lark

    text = f"{grammar}\0{sorted(OPTIONS.items())!r}\0{lark.__version__}"
    return hashlib.sha256(text.encode("utf-8")).hexdigest().encode("ascii")


def save(target: str | os.PathLike, grammar: str | None = None) -> None:
    """Build the parser and write its tables to ``target`` (beside, then renamed)."""
    from lark import Lark

    grammar = GRAMMAR.read_text(encoding="utf-8") if grammar is None else grammar
    parser = Lark(grammar, **OPTIONS)
    temporary = f"{target}.{os.getpid()}.tmp"
    with open(temporary, "wb") as handle:
        handle.write(_MAGIC + _key(grammar) + b"\n")
        parser.save(handle)
    os.replace(temporary, target)


def load(grammar: str, transformer, source: str | os.PathLike = TABLES):
    """A lark parser from the saved tables, calling ``transformer`` as it reduces;
    None when there are none or they were made from another grammar or lark."""
    try:
        with open(source, "rb") as handle:
            if handle.readline().rstrip(b"\n") != _MAGIC + _key(grammar):
                return None
            from lark import Lark

            # lark's own cache loads its tables this way, with the transformer
            return Lark.__new__(Lark)._load(handle, transformer=transformer)
    except (OSError, EOFError, ValueError, KeyError, AttributeError, TypeError, ImportError):
        return None  # no tables, or unreadable ones: the parser is built instead


if __name__ == "__main__":  # python castor/language/tables.py DIRECTORY
    save(Path(sys.argv[1]) / TABLES.name)

"""The LALR tables of the grammar, made when the package is built and shipped in it.

The grammar's one source is grammar/castor.lark at the repository's top.
setup.py's build step (what ``pip install .`` runs) copies it into the built
package beside this module, as castor.lark, and makes its tables there: an
installed castor reads only its package. A checkout has no copy, and reads
grammar/castor.lark (``grammar_path``).

Building lark's parser from the grammar is the slow part of start-up (about
0.2 s; loading saved tables about 0.01 s), and importing lark costs about as
much again. The build step runs ``save`` into the built package, beside the
grammar:

- ``castor.lalr``: the tables as plain data (``export``) for castor's own driver
  (castor.language.lalr), which reads every correct statement without lark;
- ``castor.tables``: lark's own, for lark, which castor runs only on a statement
  the driver refuses, to word the syntax error.

At run time ``load_plain`` and ``load`` read them and never write into the
package: a file that does not match this grammar (and, for lark's, this lark) is
ignored. Without the plain tables (a checkout), the first run builds lark's
parser and keeps them in the temporary directory, as lark keeps its own cache
there, for the runs after it.

This module imports nothing from castor at its top (the driver, only to load
tables at run time), so that the build can run it from the source tree by its
path; and it names files with os.path, not pathlib, which would import urllib
and ipaddress for nothing at every start (issue 18).
"""

from __future__ import annotations

import marshal
import os
import sys
import zlib

HERE = os.path.dirname(os.path.realpath(__file__))
# the grammar as an installed package ships it (setup.py's build step puts it
# there), and as a checkout keeps it: grammar/ at the repository's top
SHIPPED_GRAMMAR = os.path.join(HERE, "castor.lark")
CHECKOUT_GRAMMAR = os.path.join(os.path.dirname(os.path.dirname(HERE)), "grammar", "castor.lark")
TABLES = os.path.join(HERE, "castor.tables")
PLAIN = os.path.join(HERE, "castor.lalr")

# the parser's options: the same for the tables saved and a parser built
OPTIONS = {"parser": "lalr", "lexer": "contextual", "start": ["statement", "program"],
           "maybe_placeholders": True}
_MAGIC = b"castor-lark-tables "
# the plain tables' layout, as castor.language.lalr reads it: bumped when it changes,
# so that tables of another layout are not read (2: the root lexer, and each
# lexer's terminals; 3: the terminals some rule hands its callback)
PLAIN_LAYOUT = 3


def grammar_path() -> str:
    """The grammar castor reads: the package's own copy when it has one (an
    installed castor never looks outside its package), else the checkout's."""
    return SHIPPED_GRAMMAR if os.path.exists(SHIPPED_GRAMMAR) else CHECKOUT_GRAMMAR


def _key(grammar: str) -> bytes:
    """What the tables depend on: the grammar, the options and lark's version."""
    import hashlib

    import lark

    text = f"{grammar}\0{sorted(OPTIONS.items())!r}\0{lark.__version__}"
    return hashlib.sha256(text.encode("utf-8")).hexdigest().encode("ascii")


def save(target: str | os.PathLike, grammar: str | None = None) -> None:
    """Build the parser and write its tables to ``target`` (beside, then renamed)."""
    from lark import Lark

    if grammar is None:
        with open(grammar_path(), encoding="utf-8") as handle:
            grammar = handle.read()
    parser = Lark(grammar, **OPTIONS)
    temporary = f"{target}.{os.getpid()}.tmp"
    with open(temporary, "wb") as handle:
        handle.write(_MAGIC + _key(grammar) + b"\n")
        parser.save(handle)
    os.replace(temporary, target)
    save_plain(os.path.join(os.path.dirname(os.fspath(target)), os.path.basename(PLAIN)),
               parser, grammar)


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


_PLAIN_MAGIC = b"castor-lalr-tables "


def _plain_key(grammar: str) -> bytes:
    """What the plain tables depend on: the grammar, the options and their layout
    (not lark's version: castor.language.lalr runs them without lark). A CRC-32
    and the length, not a SHA-256: it tells tables of another grammar apart (no one
    forges them: a file in the temporary directory must be the user's own), and
    hashlib (OpenSSL) took a few milliseconds of every start."""
    text = f"{grammar}\0{sorted(OPTIONS.items())!r}\0{PLAIN_LAYOUT}".encode("utf-8")
    return f"{zlib.crc32(text):08x}-{len(text)}".encode("ascii")


def export(parser) -> dict:
    """lark's parser for the grammar as plain data for castor.language.lalr: its
    parse table, each state's lexer, and each rule's callback as lark's
    parse-tree builder makes it. Raises ValueError where the parser uses a part of
    lark the driver does not (then castor runs lark itself)."""
    from lark.parse_tree_builder import (ChildFilterLALR, ChildFilterLALR_NoPlaceholders,
                                         maybe_create_child_filter)
    from lark.parsers.lalr_analysis import Shift

    options = parser.options
    if (options.parser != "lalr" or options.lexer != "contextual" or options.postlex
            or options.propagate_positions or options.lexer_callbacks or options.regex
            or options.use_bytes or options.g_regex_flags):
        raise ValueError("parser options the driver does not run")
    frontend = parser.parser
    table = frontend.parser._parse_table
    rules: dict = {}
    states = {}
    for state, actions in table.states.items():
        row = {}
        for symbol, (action, argument) in actions.items():
            if action is Shift:
                row[str(symbol)] = int(argument)
            else:
                row[str(symbol)] = -1 - rules.setdefault(argument, len(rules))
        states[int(state)] = row
    exported_rules = []
    kept = set()  # the terminals some rule hands its callback (not punctuation)
    for rule in rules:
        made = maybe_create_child_filter(rule.expansion, rule.options.keep_all_tokens, False,
                                         rule.options.empty_indices if options.maybe_placeholders
                                         else None)
        if made is None:
            include, append_none = None, 0
        elif made.func is ChildFilterLALR:
            include, append_none = tuple(made.args[0]), made.args[1]
        elif made.func is ChildFilterLALR_NoPlaceholders:
            include, append_none = tuple((i, splice, 0) for i, splice in made.args[0]), 0
        else:
            raise ValueError(f"a child filter the driver does not run: {made.func}")
        for index in (range(len(rule.expansion)) if include is None else
                      (i for i, splice, _ in include if not splice)):
            if rule.expansion[index].is_term:
                kept.add(str(rule.expansion[index].name))
        name = str(rule.alias or rule.options.template_source or rule.origin.name)
        expand_single = bool(rule.options.expand1 and not rule.alias)
        if name.startswith("_") and expand_single:
            raise ValueError(f"an inlined rule that passes a single child up: {name}")
        exported_rules.append((str(rule.origin.name), len(rule.expansion), name, expand_single,
                               None if include is None else
                               tuple((int(i), bool(s), int(n)) for i, s, n in include),
                               int(append_none)))
    lexers: dict = {}
    lexer_of = {}
    terminals = set()

    def lexer_data(lexer) -> tuple:
        """Its patterns (lark's alternation of its terminals, in lark's order of
        them, the same in every lexer), the types it skips, those that may hold
        newlines, and its terminals."""
        scanner = lexer.scanner
        if lexer.callback or lexer.user_callbacks:
            raise ValueError("a lexer with callbacks (keywords the driver cannot tell apart)")
        return (tuple((m.pattern, int(m.flags)) for m in scanner._mres),
                tuple(sorted(lexer.ignore_types)), tuple(sorted(lexer.newline_types)),
                tuple(sorted(t.name for t in lexer.terminals)))

    for state, lexer in frontend.lexer.lexers.items():
        if id(lexer) not in lexers:
            terminals.update(t.name for t in lexer.terminals)
            lexers[id(lexer)] = (len(lexers), lexer_data(lexer))
        lexer_of[int(state)] = lexers[id(lexer)][0]
    count = len(states)
    if sorted(states) != list(range(count)) or sorted(lexer_of) != list(range(count)):
        raise ValueError("parser states not numbered 0 ... n - 1")
    return {"layout": PLAIN_LAYOUT,
            "states": [states[i] for i in range(count)],
            "starts": {str(k): int(v) for k, v in table.start_states.items()},
            "ends": {str(k): int(v) for k, v in table.end_states.items()},
            "rules": exported_rules,
            "lexer_of": [lexer_of[i] for i in range(count)],
            "lexers": [entry for _, entry in sorted(lexers.values())],
            "root": lexer_data(frontend.lexer.root_lexer),
            "terminals": sorted(str(t) for t in terminals),
            "kept": sorted(kept)}


def save_plain(target: str | os.PathLike, parser, grammar: str) -> bool:
    """Write ``export(parser)`` to ``target`` (beside, then renamed); False where
    the parser cannot be exported or the file cannot be written."""
    try:
        data = marshal.dumps(export(parser))
    except (ValueError, AttributeError, TypeError, ImportError):
        return False  # another lark, or a grammar the driver does not run: lark runs it
    temporary = f"{target}.{os.getpid()}.tmp"
    try:
        with open(temporary, "wb") as handle:
            handle.write(_PLAIN_MAGIC + _plain_key(grammar) + b"\n" + data)
        os.replace(temporary, target)
    except OSError:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        return False
    return True


def cached_plain() -> str:
    """Where a checkout keeps the plain tables between runs: the temporary
    directory (as tempfile finds it from TMPDIR, TEMP or TMP, without importing
    it: this is read at every start), one file a user, as lark's own cache."""
    directory = next((os.environ[name] for name in ("TMPDIR", "TEMP", "TMP")
                      if os.environ.get(name)), None)
    if directory is None and os.name == "posix":
        directory = "/tmp"
    if directory is None:
        import tempfile

        directory = tempfile.gettempdir()
    user = os.getuid() if hasattr(os, "getuid") else 0
    # the layout in the name: castors of another layout (another checkout) keep theirs
    return os.path.join(directory, f"castor-lalr-{user}-{PLAIN_LAYOUT}.tables")


def load_plain(grammar: str, transformer, sources=None):
    """castor.language.lalr's parser from the plain tables shipped in the package,
    else from those the temporary directory keeps (written by this user); None
    when neither was made from this grammar."""
    key = _PLAIN_MAGIC + _plain_key(grammar) + b"\n"
    for source in sources or (PLAIN, None):
        source = cached_plain() if source is None else source
        try:
            with open(source, "rb") as handle:
                if source != PLAIN and hasattr(os, "getuid") and \
                        os.fstat(handle.fileno()).st_uid != os.getuid():
                    continue  # another user's file in a shared directory: not ours to trust
                if handle.readline() != key:
                    continue
                data = marshal.loads(handle.read())
                if data.get("layout") != PLAIN_LAYOUT:
                    continue
                from castor.language.lalr import Parser

                return Parser(data, transformer)
        except (OSError, EOFError, ValueError, KeyError, TypeError, IndexError, AttributeError):
            continue
    return None


if __name__ == "__main__":  # python castor/language/tables.py DIRECTORY
    save(os.path.join(sys.argv[1], os.path.basename(TABLES)))

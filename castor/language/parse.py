"""Parse statements with the grammar of grammar/castor.lark and build the DAG.

The LALR parser calls ``Builder`` as it reduces, so no parse tree is kept: each
rule directly makes a scene-graph node. Object references are looked up in the
object table at once, so a reference shares the named node. Faults a statement
can have without being a syntax error (unknown primitive, wrong number of
arguments, undefined object) are collected while building and reported
together; lark's exceptions are translated into messages in the user's words.
"""

from __future__ import annotations

import math
import threading
from bisect import bisect_right
from functools import lru_cache
from typing import Iterator

from castor.booleans import BOOLEANS
from castor.diagnostics import (ArgumentCountError, CastorError, EvaluationError, LimitError,
                                Location, SceneError, UndefinedObject)
from castor.language.expressions import FUNCTIONS, arity_message, evaluate
from castor.language.lalr import Failed, Token
from castor.language.reader import Chunk
from castor.language.scene import (EMPTY, Binary, BooleanNode, Call, FrameCommand, NamedNode,
                                   Number, ObjectDef, Param, ParamDef, PrimitiveNode, Repeat,
                                   Step, Tables, TransformedNode, Unary, UndefinedReference)
from castor.primitives import PRIMITIVES
from castor.transformations import TRANSFORMS

# how many arguments each primitive takes (without coordinate pairs)
_COUNTS = {name: declared.count for name, declared in PRIMITIVES.items()}
_new_tuple = tuple.__new__  # a Location made without the Python call of its __new__
_INFINITY = math.inf

# Deeper nesting than this (parentheses, booleans) is refused with an error.
MAX_DEPTH = 100_000


@lru_cache(maxsize=1)
def grammar_text() -> str:
    """The grammar: shipped beside this module in an installed package, else the
    checkout's grammar/castor.lark (castor.language.tables.grammar_path)."""
    from castor.language.tables import grammar_path

    with open(grammar_path(), encoding="utf-8") as handle:
        return handle.read()


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def _suggest(name: str, choices, prefix: str = "") -> str:
    """'; did you mean ...?' for the closest of ``choices``, or nothing."""
    import difflib

    close = difflib.get_close_matches(name, list(choices), n=1, cutoff=0.5)
    return f"; did you mean '{prefix}{close[0]}'?" if close else ""


suggestion = _suggest


def _known(prefix: str, name: str, choices) -> str:
    """The suggestion and the list of the known names, for an unknown primitive or
    transformation."""
    known = ", ".join(prefix + c for c in choices)
    return f"{_suggest(name, choices, prefix)} (known: {known})"


def _given(n: int) -> str:
    return f"{n} {'was' if n == 1 else 'were'} given"


class Builder:
    """Makes scene-graph nodes as the parser reduces rules.

    Lark calls each method with the list of a rule's children (no v_args
    wrapper: parsing speed is start-up speed, and a wrapper is a call more).
    """

    def __init__(self, tables: Tables):
        self.tables = tables
        self.chunk = None
        self.faults: list[CastorError] = []
        self._param_sets: dict[str, frozenset[str]] = {}
        self.on_statement = None

    @property
    def chunk(self) -> Chunk | None:
        """The statement being read."""
        return self._chunk

    @chunk.setter
    def chunk(self, chunk: Chunk | None) -> None:
        self._chunk = chunk
        # where its first line is: (file, line, columns before it, plus one), and
        # where that line ends in the text, for _at
        if chunk is not None and chunk.origins:
            file, line = chunk.origins[0]
            self._first = (file, line, chunk.first_column + 1)
            end = chunk.text.find("\n")
            self._first_end = len(chunk.text) if end < 0 else end
        else:
            self._first, self._first_end = None, -1
        self._line_starts = None  # where each line begins in the text, once asked

    def _at(self, token: Token):
        """Where a token is in the original file, from where it begins in the
        statement's text (``start_pos``, as both castor's driver and lark give
        it): Chunk.location, the first line's case inline (a long statement asks
        it of every number and name)."""
        pos = token.start_pos
        if pos < self._first_end:
            file, line, before = self._first
            return _new_tuple(Location, (file, line, pos + before))
        return self._located(pos)

    def _located(self, pos: int):
        """Chunk.location of the character at ``pos`` in the statement's text."""
        starts = self._line_starts
        if starts is None:
            import re

            starts = self._line_starts = [0] + [m.end() for m in re.finditer("\n", self._chunk.text)]
        line = bisect_right(starts, pos)
        return self._chunk.location(line, pos - starts[line - 1] + 1)

    def _depth(self, depth: int, location) -> int:
        if depth > MAX_DEPTH:
            raise LimitError(f"nesting deeper than {MAX_DEPTH} levels", location)
        return depth

    # --- statements
    def _statement(self, statement):
        """In a batch (on_statement set), hand each statement over as soon as it is
        reduced, so that it runs before the next one is read."""
        if self.on_statement is None:
            return statement
        faults, self.faults = self.faults, []
        self.on_statement(statement, faults)
        return None

    def param_def(self, children):
        name, expr = children
        if name not in self._param_sets:  # a name the scene assigns (for --set's warning)
            self._param_sets[str(name)] = frozenset((str(name),))
        return self._statement(ParamDef(str(name), expr, self._at(name)))

    def object_def(self, children):
        name, node = children
        location = self._at(name)
        return self._statement(ObjectDef(str(name), NamedNode(
            str(name), node, location, node.params, self._depth(node.depth + 1, location)),
            location))

    def facetize(self, children):
        mark, rest = children[0], children[1:]
        repeat = rest[0] if rest and isinstance(rest[0], Repeat) else None
        objects = rest[1:] if repeat else rest
        return self._statement(FrameCommand(tuple(objects), repeat, self._at(mark)))

    def program(self, children):
        return None

    # --- objects
    def object(self, items):
        atom = items[-1]
        if len(items) == 1:
            return atom
        steps = items[:-1]
        params = atom.params
        # the names the steps read that the atom does not: gathered, then one union
        # (a union per step would copy the set each time: quadratic in a long run)
        more = [a.params for s in steps for a in s.args if a.params and not a.params <= params]
        if more:
            params = params.union(*more)
        return TransformedNode(tuple(steps), atom, steps[0].location, params, atom.depth + 1)

    def transform(self, children):
        token, args = children
        args = args or ()
        location = self._at(token)
        kind = token[1:]
        if kind not in TRANSFORMS:
            self.faults.append(SceneError(
                f"unknown transformation '{token}'{_known('@', kind, TRANSFORMS)}",
                location))
        else:
            counts, form = TRANSFORMS[kind].counts, TRANSFORMS[kind].form
            if len(args) not in counts:
                wanted = " or ".join(str(c) for c in counts)
                self.faults.append(ArgumentCountError(
                    f"'{token}' takes {wanted} argument{'s' if counts[-1] > 1 else ''} ({form}), "
                    f"but {_given(len(args))}", location, _names(args)))
        return Step(kind, args, location)

    def primitive(self, children):
        token, args = children
        args = args or ()
        location = self._at(token)
        kind = token[1:]
        declared = PRIMITIVES.get(kind)
        n = len(args)
        if declared is None:
            self.faults.append(SceneError(
                f"unknown primitive '{token}'{_known('!', kind, PRIMITIVES)}", location))
        elif declared.pair_names is None:
            if n != _COUNTS[kind]:
                self.faults.append(ArgumentCountError(
                    f"'{token}' takes {declared.count} arguments ({declared.form}), "
                    f"but {_given(n)}", location, _names(args)))
        elif n < declared.count + 6:  # at least three coordinate pairs
            self.faults.append(ArgumentCountError(
                f"'{token}' takes at least {declared.count + 6} arguments ({declared.form}), "
                f"but {_given(n)}", location, _names(args)))
        elif (n - 3) % 2:
            self.faults.append(ArgumentCountError(
                f"'{token}' takes the colour then pairs of coordinates ({declared.form}), "
                f"but {n - 3} coordinates were given, an odd number", location, _names(args)))
        depth = max([a.depth for a in args], default=0)
        params = _names(args)
        return PrimitiveNode(kind, args, location, params, depth + 1)

    def boolean(self, children):
        token, rest = children[0], children[1:]
        location = self._at(token)
        repeat = rest[0] if rest and isinstance(rest[0], Repeat) else None
        operands = rest[1:] if repeat else rest
        op = token[1:]
        if op not in BOOLEANS:
            known = ", ".join(f"${name} {meaning}" for name, meaning in BOOLEANS.items())
            self.faults.append(SceneError(f"unknown boolean operator '{token}' (known: {known})",
                                          location))
        elif op == "D" and repeat is not None:
            self.faults.append(SceneError(
                "'$D' cannot repeat; subtract a repeated union instead: $D(a, $U[I = ...](b))", location))
        elif op == "D" and len(operands) != 2:
            self.faults.append(SceneError(
                f"'$D' takes exactly two operands (a - b), but {_given(len(operands))}; "
                "to subtract several, write $D(a, $U(b, c))", location))
        elif repeat is not None and len(operands) != 1:
            self.faults.append(SceneError(
                f"a repeated '{token}' takes one body, but {len(operands)} were given; "
                f"write {token}[...]($U(a, b))", location))
        params = EMPTY.union(*(o.params for o in operands))
        if repeat is not None:
            params = (params - {repeat.param}) | repeat.params
        depth = self._depth(max(o.depth for o in operands) + 1, location)
        return BooleanNode(op, tuple(operands), repeat, location, params, depth)

    def reference(self, children):
        token = children[0]
        name = str(token)
        location = self._at(token)
        node = self.tables.objects.get(name)
        if node is None:
            if name in self.tables.broken:
                self.faults.append(UndefinedObject(
                    f"object '{name}' is not defined (its definition had errors)", location, name))
            else:
                hint = _suggest(name, self.tables.objects)
                self.faults.append(UndefinedObject(f"object '{name}' is not defined{hint}",
                                                   location, name))
            return UndefinedReference(name, location)  # the statement is dropped
        return node

    def repeat(self, children):
        param, start, stop = children[:3]
        if param not in self._param_sets:
            self._param_sets[str(param)] = frozenset((str(param),))
        step = children[3] if len(children) > 3 else None
        params = start.params | stop.params | (step.params if step is not None else EMPTY)
        return Repeat(str(param), start, stop, step, self._at(param), params)

    def args(self, exprs):
        return tuple(exprs)

    # --- expressions
    def number(self, children):
        token = children[0]
        pos = token.start_pos
        if pos < self._first_end:  # _at, inline: the most made node
            file, line, before = self._first
            location = _new_tuple(Location, (file, line, pos + before))
        else:
            location = self._located(pos)
        value = float(token)
        if value == _INFINITY:
            self.faults.append(EvaluationError(f"number '{token}' is too large", location))
            value = 0.0
        return Number(value, location)

    def parameter(self, children):
        token = children[0]
        name = str(token)
        params = self._param_sets.get(name)
        if params is None:
            params = self._param_sets[name] = frozenset((name,))
        return Param(name, self._at(token), params)

    def binary(self, children):
        left, op, right = children
        location = self._at(op)
        node = Binary(str(op), left, right, location, left.params | right.params,
                      self._depth(max(left.depth, right.depth) + 1, location))
        return self._fold(node)

    def unary(self, children):
        op, operand = children
        location = self._at(op)
        node = Unary(str(op), operand, location, operand.params,
                     self._depth(operand.depth + 1, location))
        return self._fold(node)

    def call(self, children):
        name, args = children
        args = args or ()
        location = self._at(name)
        function = str(name)
        if function not in FUNCTIONS:
            if function in self.tables.objects:
                message = (f"'{function}' is an object, not a number; parameters start with "
                           "an uppercase letter")
            else:
                message = f"unknown function '{function}'{_suggest(function, FUNCTIONS)}"
            self.faults.append(SceneError(message, location))
            return Number(0.0, location)
        problem = arity_message(function, len(args))
        if problem:
            self.faults.append(SceneError(problem, location))
            return Number(0.0, location)
        params = EMPTY.union(*(a.params for a in args))
        depth = self._depth(max((a.depth for a in args), default=0) + 1, location)
        return self._fold(Call(function, tuple(args), location, params, depth))

    def _fold(self, node):
        """Evaluate an expression without parameters now (errors show at once)."""
        if node.params:
            return node
        try:
            return Number(evaluate(node, {}), node.location)
        except EvaluationError as exc:
            self.faults.append(exc)
            return Number(0.0, node.location)


_local = threading.local()


def _parser_and_builder(tables: Tables):
    """One parser for each thread, and its builder: castor's own driver
    (castor.language.lalr) on the plain tables shipped in the package or kept in
    the temporary directory, which reads a scene without importing lark; lark's
    parser where there are none yet (the first run of a checkout, which keeps
    them for the next). The builder is handed each Parser's tables before each
    parse, so that parsers made one after another, or in other threads, never mix
    up scenes."""
    shared = getattr(_local, "shared", None)
    if shared is None:
        from castor.language import tables as saved

        builder = Builder(tables)
        parser = saved.load_plain(grammar_text(), builder)
        if parser is None:
            parser = _lark(builder)
            saved.save_plain(saved.cached_plain(), parser, grammar_text())
        shared = _local.shared = (parser, builder)
    return shared


def _lark(builder: Builder):
    """This thread's lark parser, calling ``builder`` as it reduces: from the tables
    shipped in the package (castor.language.tables), else built (lark then caches
    its tables in the temporary directory between runs). castor runs it on what
    its own driver refuses: lark's exception words the syntax error."""
    lark = getattr(_local, "lark", None)
    if lark is None:
        from lark import Lark

        from castor.language import tables as saved

        grammar = grammar_text()
        lark = saved.load(grammar, builder)  # the tables made when the package was built
        if lark is None:
            try:
                lark = Lark(grammar, transformer=builder, cache=True, **saved.OPTIONS)
            except OSError:  # an unwritable temporary directory: build without the cache
                lark = Lark(grammar, transformer=builder, **saved.OPTIONS)
        _local.lark = lark
    return lark


class Parser:
    """Parses statement chunks; yields statements and the errors found."""

    def __init__(self, tables: Tables):
        self.tables = tables
        self.param_sets: dict[str, frozenset[str]] = {}

    def _ready(self):
        """This thread's parser, its builder working on this Parser's tables."""
        parser, builder = _parser_and_builder(self.tables)
        builder.tables = self.tables
        builder._param_sets = self.param_sets
        self.builder = builder
        return parser

    def parameter_names(self) -> set[str]:
        """Every parameter name the statements parsed so far assign or use."""
        return set(self.param_sets)

    def parse(self, chunk: Chunk) -> Iterator["ParamDef | ObjectDef | FrameCommand | CastorError"]:
        """Parse one chunk. A missing ';' is reported, the statement is read as if it
        were there (for its other errors) and skipped (LANGUAGE.md §9), and parsing
        resumes with the next line."""
        parser = self._ready()
        pending = [chunk]
        patched: set[int] = set()  # chunks given their missing ';': never patched twice
        while pending:
            chunk = pending.pop(0)
            self.builder.chunk = chunk
            self.builder.faults = []
            try:
                try:
                    statement = parser.parse(chunk.text, start="statement")
                except Failed:  # not a statement: lark says why, in its exception
                    self.builder.faults = []
                    statement = _lark(self.builder).parse(chunk.text, start="statement")
            except LimitError as exc:
                yield exc
                continue
            except RecursionError:
                yield LimitError("statement nested too deeply", chunk.location(1, 1))
                continue
            except _lark_errors() as exc:  # a syntax error, as lark saw it
                from castor.language.syntax_errors import DEFINED, syntax_error

                error, head, rest = syntax_error(exc, chunk, self.builder.tables)
                yield error
                defined = DEFINED.match(chunk.text)
                if head is None:
                    name = defined.group(1) if defined is not None else None
                    if name is not None and name[0].islower():
                        # its uses say why it is missing, as after any faulty definition
                        self.builder.tables.broken.add(name)
                    yield SkippedDefinition(name)
                if head is not None and id(chunk) not in patched:
                    patched.add(id(head))
                    rest = [head] + rest
                pending[:0] = rest
                continue
            if id(chunk) in patched:  # read with its missing ';' for its other errors, then skipped
                yield from self.builder.faults
                if isinstance(statement, ObjectDef):
                    self.builder.tables.broken.add(statement.name)
                yield SkippedDefinition(getattr(statement, "name", None))
                continue
            yield from self._deliver(statement, self.builder.faults)

    def _deliver(self, statement, faults):
        """The statement, or its faults (a faulty definition leaves its name broken)."""
        if faults:
            yield from faults
            if isinstance(statement, ObjectDef):
                self.builder.tables.broken.add(statement.name)
            yield SkippedDefinition(getattr(statement, "name", None))
        else:
            yield statement

    def run_batch(self, chunks: list[Chunk], execute) -> None:
        """Parse many statements with one call to lark, running each as it is
        reduced; a chunk with an error goes through ``parse`` on its own, which
        reports it, and the batch goes on after it. (One call per statement
        costs a third more: lark sets up a lexer and a parser state each time.)"""
        first = 0
        while first < len(chunks):
            batch = chunks[first:]
            done = 0

            def on_statement(statement, faults):
                nonlocal done
                done += 1
                for item in self._deliver(statement, faults):
                    execute(item)

            parser = self._ready()
            self.builder.chunk = _combined(batch)
            self.builder.faults = []
            self.builder.on_statement = on_statement
            try:
                parser.parse(self.builder.chunk.text, start="program")
                return
            except (Failed, LimitError, RecursionError) + _lark_errors():
                pass  # the chunk where it failed is parsed again below, alone
            finally:
                self.builder.on_statement = None
            failed = first + done
            for item in self.parse(chunks[failed]):
                execute(item)
            first = failed + 1


def _lark_errors() -> tuple:
    """lark's syntax error, where lark runs (it is imported): a parse by lark fails with it."""
    import sys

    exceptions = sys.modules.get("lark.exceptions")
    return (exceptions.UnexpectedInput,) if exceptions is not None else ()


def assignment_value(name: str, expr: str, parameters: dict[str, float]) -> float:
    """The value of ``NAME = EXPR`` given on the command line (--set), parsed and
    evaluated as the same statement in a scene would be; raises CastorError."""
    from castor.language.scene import ParamDef

    tables = Tables(parameters=dict(parameters))
    # the ';' on a line of its own: a '//' comment in EXPR cannot swallow it
    chunk = Chunk(f"{name} = {expr}\n;", (("<command line>", 1), ("<command line>", 1)), 0)
    results = list(Parser(tables).parse(chunk))
    problems = [r for r in results if isinstance(r, CastorError)]
    if problems:
        raise problems[0]
    if not results or not isinstance(results[0], ParamDef):
        raise CastorError("expected NAME=EXPR")
    try:
        return evaluate(results[0].expr, tables.parameters)
    except RecursionError:
        raise LimitError("the expression is nested too deeply") from None


def _combined(chunks: list[Chunk]) -> Chunk:
    """Consecutive chunks as one: their texts join back into the original text,
    and each chunk's first line is the previous one's last."""
    if len(chunks) == 1:
        return chunks[0]
    origins = list(chunks[0].origins)
    for chunk in chunks[1:]:
        origins.extend(chunk.origins[1:])
    return Chunk("".join(c.text for c in chunks), tuple(origins), chunks[0].first_column)


def _names(args) -> frozenset:
    """The parameter names some argument reads (most read none: then no union)."""
    names = [a.params for a in args if a.params]
    if not names:
        return EMPTY
    return names[0] if len(names) == 1 else EMPTY.union(*names)


class SkippedDefinition:
    """Tells the interpreter, after the errors of a statement, that it was
    dropped: the definition of ``name`` (an object's or a parameter's), or
    (None) a '>' command or a statement too broken to name."""

    def __init__(self, name: str):
        self.name = name

"""Execute statements in order: define parameters and objects, hand each frame on.

Parameter definitions are evaluated at once; objects keep their expressions
and are evaluated at each '>' command with the values then in force (late
binding): each frame becomes an evaluated CSG tree (castor.csg.evaluate)
handed to ``submit``, which facetizes and writes it here or elsewhere. An
error skips its statement and castor goes on, so that every frame without an
error is still made.
"""

from __future__ import annotations

import itertools
import math
from typing import Callable, Iterable

from castor.diagnostics import (ArgumentCountError, CastorError, LimitError, Reporter,
                                TooManyErrors, UndefinedObject, counted)
from castor.language.expressions import UndefinedParameter, evaluate
from castor.language.parse import Parser, SkippedDefinition
from castor.language.reader import Chunk
from castor.language.scene import FrameCommand, ObjectDef, ParamDef, Tables
from castor.settings import DEFAULT_TOLERANCE
from castor.settings import EvaluationSettings


# statements parsed by one call to the parser when the input is not streamed
BATCH = 500


class Interpreter:
    """Holds the symbol tables and runs statements against them."""

    def __init__(self, settings: EvaluationSettings, reporter: Reporter,
                 submit: Callable | None):
        from castor.csg.evaluate import Evaluator

        self.settings = settings
        self.reporter = reporter
        self.submit = submit  # takes each frame's tree; None for --check
        self.tables = Tables()
        self.tables.parameters.update({"PI": math.pi, "TOLERANCE": DEFAULT_TOLERANCE})
        if settings.tolerance is not None:
            self.tables.parameters["TOLERANCE"] = settings.tolerance
        self.tables.parameters.update(settings.overrides)
        self.parser = Parser(self.tables)
        self.evaluator = Evaluator()
        self.frames_attempted = 0
        self.annotated: set[str] = set()  # parameters whose annotation was looked at
        # LANGUAGE.md §11: the classes of objects by the place of their definition,
        # the storeys' parameters; handed to the evaluator with each frame
        self.classified: dict[tuple[str, int, int], object] = {}
        self.storeys: list = []
        self.declared_changed = False
        self.failed: set[str] = set()  # parameters whose last definition had errors
        # objects whose definition had only errors that others explain (and were not said)
        self.unsaid: set[str] = set()
        self.said = False  # whether an error of the statement being run was said

    def run(self, chunks: Iterable[Chunk], streaming: bool = True) -> None:
        """Execute every statement; stops early only after too many errors.

        Streaming, each statement runs as soon as its chunk arrives; otherwise
        chunks are parsed in batches, which is faster."""
        try:
            if streaming:
                for chunk in chunks:
                    for item in self.parser.parse(chunk):
                        self.execute(item)
                return
            iterator = iter(chunks)
            while True:
                batch, unread = [], None
                try:
                    for chunk in itertools.islice(iterator, BATCH):
                        batch.append(chunk)
                except CastorError as exc:  # the statements read before it run first,
                    unread = exc            # as they do streaming
                if batch:
                    self.parser.run_batch(batch, self.execute)
                if unread is not None:
                    raise unread
                if not batch:
                    break
        except CastorError as exc:  # from the reader: an unterminated comment
            self.reporter.error(exc)

    def execute(self, item) -> None:
        try:
            if isinstance(item, CastorError):
                if not self._explained(item):
                    self.reporter.error(item)
                    self.said = True
                return
            if isinstance(item, SkippedDefinition):
                if item.name is None:
                    pass
                elif item.name[0].isupper():
                    self.failed.add(item.name)
                elif not self.said:  # every fault of its definition was explained
                    self.unsaid.add(item.name)
            elif isinstance(item, ParamDef):
                self._define_parameter(item)
            elif isinstance(item, ObjectDef):
                self._define_object(item)
            elif isinstance(item, FrameCommand):
                self._run_frame_command(item)
        except CastorError as exc:
            if not self._explained(exc):
                self.reporter.error(exc)
        self.said = False

    def _define_parameter(self, statement: ParamDef) -> None:
        name = statement.name
        if name not in self.annotated:
            self.annotated.add(name)
            self._read_storey(statement)
            try:
                self._assign(statement)
            finally:  # after the value is known: a slider's range is checked against it
                self.check_annotation(statement)
            return
        self._assign(statement)

    def _assign(self, statement: ParamDef) -> None:
        name = statement.name
        if name in self.settings.overrides:
            return  # --set wins over the scene's assignments, as openscad -D does
        if name == "TOLERANCE" and self.settings.tolerance is not None:
            return
        try:
            self.tables.parameters[name] = evaluate(statement.expr, self.tables.parameters)
        except UndefinedParameter as exc:
            self.failed.add(name)
            if not self._explained(exc):
                exc.message += (f"; parameter definitions are evaluated at once, where they "
                                f"stand, so a repetition's variable such as '>[{exc.name} = "
                                f"...]' has no value here: write the expression inside the "
                                f"object that uses it, or as a macro (#define {name} (...))")
            raise
        except CastorError:
            self.failed.add(name)
            raise
        self.failed.discard(name)

    def _explained(self, error: CastorError) -> bool:
        """Whether an error already reported explains this one: one message per
        cause. A use of a parameter whose definition had errors says nothing
        more (an object's says so in a message of its own); nor does an argument
        count where an argument names a parameter that has no value after an
        #include that could not be read (it may be one of that file's macros,
        such as a colour's three components)."""
        if self.reporter.explains(error):  # a macro use left unexpanded, said by the preprocessor
            return True
        if isinstance(error, UndefinedParameter):
            return error.name in self.failed and error.name not in self.tables.parameters
        if isinstance(error, ArgumentCountError) and self.reporter.unread_includes:
            return any(name not in self.tables.parameters for name in error.names)
        return isinstance(error, UndefinedObject) and error.name in self.unsaid

    def check_annotation(self, statement: ParamDef) -> None:
        """A malformed annotation (the comment after a parameter's first definition,
        LANGUAGE.md §10) is a warning, never an error."""
        where = statement.location
        text = self.reporter.source_lines.get((where.file, where.line))
        if text is None or "//" not in text:
            return
        from castor.language.annotations import malformed

        value = None if statement.name in self.settings.overrides else \
            self.tables.parameters.get(statement.name)
        warning = malformed(text, where, value)
        if warning is not None:
            self.reporter.warning(warning.message, warning.location)

    def _read_storey(self, statement: ParamDef) -> None:
        """``R1 = 3.0; // [storey "Étage"]``: R1's value is a storey's floor level."""
        where = statement.location
        text = self.reporter.source_lines.get((where.file, where.line))
        if text is None or "storey" not in text:
            return
        from castor.language.annotations import storey_of
        from castor.language.classes import StoreyMark

        name = storey_of(text, where)
        if name is not None:
            self.storeys.append(StoreyMark(statement.name, name or statement.name, where))
            self.declared_changed = True

    def _may_be_annotated(self, location) -> bool:
        """Whether the statement starting at ``location`` may have a comment after
        its ';': its line has one, or the statement goes on below."""
        text = self.reporter.source_lines.get((location.file, location.line))
        return text is not None and ("//" in text or ";" not in text[location.column - 1:])

    def _comment(self, location):
        """The comment after the statement starting at ``location`` (castor.language.
        annotations.definition_comment), or None."""
        if not self._may_be_annotated(location):
            return None
        from castor.language.annotations import definition_comment

        lines = self.reporter.source_lines
        return definition_comment(lambda file, number: lines.get((file, number)), location)

    def _classify(self, statement: ObjectDef) -> None:
        """The class the comment on an object's definition gives it (LANGUAGE.md §11);
        what cannot be understood is a warning, and the object is unclassed."""
        where = statement.location
        if not self._may_be_annotated(where):
            return
        from castor.language.annotations import object_classes

        lines = self.reporter.source_lines
        for _, _, classification, problem in object_classes(
                [(statement.name, where)], lambda file, number: lines.get((file, number))):
            if problem is not None:
                self.reporter.warning(problem.message, problem.location)
            if classification is not None:
                self.classified[(where.file, where.line, where.column)] = classification
                self.declared_changed = True

    def _stray_annotation(self, statement: FrameCommand) -> None:
        """An annotation on a '>' command says nothing of anything: a warning."""
        found = self._comment(statement.location)
        if found is None or not found[0].lstrip().startswith("["):
            return
        text, at, _ = found
        lead = len(text) - len(text.lstrip())
        self.reporter.warning("annotation: a '>' command is not a definition; an annotation "
                              "says what an object or a parameter is: put it on the line of "
                              "its definition", at._replace(column=at.column + lead))

    def _declared(self):
        if self.declared_changed:
            from castor.language.classes import Declared

            self.declared_changed = False
            self.evaluator.declared = Declared(tuple(self.classified.items()),
                                               tuple(self.storeys))

    def _define_object(self, statement: ObjectDef) -> None:
        name = statement.name
        if name in self.tables.objects:
            self.reporter.warning(
                f"object '{name}' redefined; objects defined before keep the old definition",
                statement.location)
        self.tables.objects[name] = statement.node
        self.tables.broken.discard(name)
        self._classify(statement)
        self.unsaid.discard(name)

    def _run_frame_command(self, statement: FrameCommand) -> None:
        """One frame, or one for each value of ``>[T = ...]``; an error found in
        several of its frames is reported once, with the frames it concerns."""
        from castor.csg.evaluate import FrameErrors, repeat_values

        where = f"{statement.location.file}:{statement.location.line}"
        self._stray_annotation(statement)
        self._declared()
        if statement.repeat is None:
            values = [None]
        else:
            values = repeat_values(statement.repeat, dict(self.tables.parameters))
        failures: dict[tuple, tuple[CastorError, list[int]]] = {}
        for value in values:
            env = dict(self.tables.parameters)
            if statement.repeat is not None:
                env[statement.repeat.param] = value
            self.frames_attempted += 1
            number = self.frames_attempted
            try:
                tree = self.evaluator.frame(statement.objects, env, number, where,
                                             statement.location)
            except FrameErrors as group:
                errors = group.errors
            except CastorError as error:
                errors = [error]
            except RecursionError:  # deeper than the evaluator's stack, below the parser's limit
                errors = [LimitError("the frame's objects are nested too deeply to evaluate",
                                     statement.location)]
            else:
                errors = []
            finally:
                self._say_slow()  # before the frame is made, or its errors said
            if errors:
                for error in errors:
                    failures.setdefault((error.message, error.location), (error, []))[1].append(number)
                continue
            if self.submit is not None:
                self.submit(tree)
            else:  # evaluated only (--check, an editor): its emptiness as the tree shows it
                self._warn_if_empty(tree)
        for error, numbers in failures.values():
            if self._explained(error):
                self._unwritten(error, numbers, statement.location)
                continue
            if len(values) > 1:
                error.message += f" (in {counted('frame', numbers)})"
            self.reporter.error(error)

    def _say_slow(self) -> None:
        """The evaluator's warnings of primitives faceted so finely that their
        booleans will be slow (castor.csg.fineness)."""
        for message, location in self.evaluator.warnings:
            self.reporter.warning(message, location)
        self.evaluator.warnings.clear()

    def _unwritten(self, error: CastorError, numbers: list[int], location) -> None:
        """Frames left unmade by a parameter whose definition had errors: said in
        a note at the '>' (its error was said at the definition; the frames are not
        written, and the user is told which)."""
        if isinstance(error, UndefinedParameter) and error.name in self.failed:
            self.reporter.note(f"{location}: note: {counted('frame', numbers)} not made: "
                               f"parameter '{error.name}' has no value (its definition "
                               "had errors)")

    def _warn_if_empty(self, tree) -> None:
        """The warning a run gives a frame without polygons, where the tree shows
        it without facetizing (castor.csg.emptiness)."""
        from castor.csg.elements import cuts_nothing
        from castor.csg.emptiness import certainly_empty, empty_message, idle_openings

        if certainly_empty(tree):
            self.reporter.warning(empty_message(tree.number), tree.location)
        for opening in idle_openings(tree):  # as the take-off says it
            self.reporter.warning(cuts_nothing(opening), tree.location)

    def warn_if_no_frame(self) -> None:
        """After a run that wrote nothing, evaluating only (--check, an editor): a
        scene without a '>' command (CLI.md: a lint gives a run's warnings)."""
        if self.frames_attempted == 0 and not self.reporter.errors:
            self.reporter.warning(NO_FRAME.format("would be"))


# a scene without a '>' command: what castor says (written, or "would be")
NO_FRAME = "the scene has no '>' command, so nothing {} written; '> OBJECT;' writes an object's polygons"


__all__ = ["Interpreter", "TooManyErrors"]

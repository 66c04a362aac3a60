"""One pass of the built-in C preprocessor (pcpp): macros, #include, #if,
comments, with castor's messages for what goes wrong, and what the pass
depended on (the files it opened or looked for), so that castor.language.preprocess
can tell when a remembered pass still holds.

The output keeps ``#line`` markers, which the reader follows so that every
position castor reports names the original file and line, inside included
files too. An editor's unsaved buffers (``unsaved``) are read in place of
their files.
"""

from __future__ import annotations

import io
import os
import re
import threading
from contextlib import contextmanager
from dataclasses import dataclass

from castor.diagnostics import Location, PreprocessError, Reporter
from castor.language import macro_calls
from castor.language.cpp_messages import Blocks, castor_words, printable

MAX_INCLUDE_DEPTH = 200

# directives that mean nothing without an argument, and what they need
_NEEDS = {"define": "a macro name", "undef": "a macro name", "ifdef": "a macro name",
          "ifndef": "a macro name", "if": "a condition", "elif": "a condition",
          "include": "a file name, as in #include \"walls.cas\""}


def _false_condition(directive, toks: list) -> bool:
    """An #if or #elif whose condition cannot be read (said already) read as
    false, in place: its #else and #endif still match it."""
    import copy

    zero = copy.copy(directive)
    zero.type, zero.value = "CPP_INTEGER", "0"
    toks[:] = [zero]
    return True


def shown(name: str) -> str:
    """A file name as pcpp shows it: relative to the current directory when inside it."""
    here = os.path.abspath("") + os.sep
    return name[len(here):] if name.startswith(here) else name


def escape(name: str) -> str:
    return name.replace("\\", "\\\\").replace('"', '\\"')


class IncludeTooDeep(Exception):
    pass


class SourceLines:
    """The original text of each line of the input files, for carets and for
    mapping positions out of macro expansions."""

    def __init__(self, sources: list[tuple[str, str]]):
        # by its name and as locations name it (shown): an editor's buffer is not its file
        self.files = {k: text.split("\n") for name, text in sources for k in {name, shown(name)}}

    def line(self, file: str, number: int) -> str | None:
        lines = self.files.get(file)
        if lines is None:
            text = unsaved_text(file)
            if text is None:
                try:
                    with open(file, encoding="utf-8", errors="replace") as handle:
                        text = handle.read()
                except (OSError, ValueError):
                    text = ""
            text = text.removeprefix("\ufeff")  # a byte-order mark: no column of line 1
            lines = self.files[file] = text.split("\n") if text else []
        return lines[number - 1] if 0 < number <= len(lines) else None


def _spaced(text: str) -> str:
    return " ".join(text.split())


_PARAMETER = re.compile(r"[A-Za-z_]\w*(\s*\.\.\.)?|\.\.\.")
_ARGUMENT_COUNT = re.compile(r"Macro (\w+) requires (\d+) arguments but was passed (\d+)")


def _where(token, default: str = "<stdin>") -> Location:
    """The start of the line of a directive's token."""
    return Location(getattr(token, "source", None) or default,
                    int(getattr(token, "lineno", 0) or 0), 1)


class Hooks:
    """castor's side of pcpp's preprocessor: its messages, where each macro is
    defined, the files it opened or looked for. Mixed into pcpp.Preprocessor
    by ``_make_preprocessor`` (pcpp is imported only when a pass runs)."""

    def __init__(self, reporter: Reporter, originals: SourceLines, defines: dict[str, str],
                 included: list[str] | None):
        super().__init__()
        self.reporter = reporter
        self.originals = originals
        self.given = defines  # the -D macros
        self.included = included  # for the live preview, which watches them
        self.line_directive = "#line"
        self.compress = 0
        self.definitions: dict[str, Location] = {}  # macro -> where it was #defined
        self.redefinitions: list[tuple[str, Location]] = []  # of -D macros
        self.unreadable: list[str] = []
        self.opened: list[tuple[str, str]] = []  # (path, text) of each file #included
        self.missing: list[str] = []  # paths looked for, not there (for the cache)
        self.quiet = False  # while a use is expanded again to map a position
        self.defining = False  # while pcpp reads a #define
        self.blocks = Blocks()  # each file's open #if blocks

    def on_error(self, file, line, msg):
        self.return_code += 1
        if self.quiet:
            return  # a use expanded again to map a position: said at its pass already
        if file == "unknown":  # pcpp's name for a place it lost: the directive's
            file, line = (getattr(self.lastdirective, "source", None),
                          getattr(self.lastdirective, "lineno", 0))
        location = Location(file, int(line or 0), 1) if file else None  # None: from -D
        self.blocks.ended(file, msg)
        msg = castor_words(msg, self.defining)
        counted = _ARGUMENT_COUNT.fullmatch(msg)
        if counted and location is not None:
            location, msg = macro_calls.argument_count(self, location, *counted.groups())
            # the use stays unexpanded, and the statement cannot parse: one message
            self.reporter.explained.add(location)
        self.reporter.error(PreprocessError(msg, location))

    def collect_args(self, tokenlist, ignore_errors=False):
        """pcpp's, and a macro call whose '(' never closes said at the call: pcpp
        leaves it unexpanded without a word (as ``ignore_errors`` asks), and the
        statement then failed in words about parameters and objects."""
        found = super().collect_args(tokenlist, ignore_errors)
        if found[0] == 0 and ignore_errors and not self.quiet and tokenlist:
            macro_calls.unclosed(self, tokenlist[0])
        return found

    def on_include_not_found(self, is_malformed, is_system_include, curdir, includepath):
        """Report the #include at its place and drop the directive: the run goes on,
        so that the errors after it are seen too, as an external cpp shows them."""
        import pcpp

        location = self._include_location(includepath)
        name = printable(includepath)
        if not is_malformed and not includepath.strip():
            message = "#include names no file; write #include \"file.cas\""
        elif "\0" in includepath:
            message = (f"include file name '{name}' holds a NUL byte, which no file name "
                       f"can hold")
        elif self.unreadable:
            message = f"cannot read include file '{name}': {self.unreadable[0]}"
        elif is_malformed:
            message = f"malformed #include {name}; write #include \"file.cas\""
        else:
            message = (f"cannot find include file '{name}' (searched: "
                       f"{self._searched(is_system_include)}); give the directory that holds "
                       f"it with -I DIR")
        self.reporter.unread_includes.append(includepath)
        self.reporter.error(PreprocessError(message, location))
        raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)

    def _include_location(self, includepath: str) -> Location:
        """Where the #include being read names its file (its line's '#' when the
        name is not on the line as written)."""
        token = self.lastdirective
        file = getattr(token, "source", None) or "<stdin>"
        line = getattr(token, "lineno", 0) or 0
        text = self.originals.line(file, line)
        column = 1
        if text is not None:
            self.reporter.source_lines[(file, line)] = text
            found = text.find(includepath) if includepath else -1
            column = found if found > 0 else text.find("#") + 1
        return Location(file, line, column)

    def _searched(self, is_system_include: bool) -> str:
        """The directories an #include looked in, as a message names them."""
        searched = []
        for directory in ([] if is_system_include else self.temp_path) + self.path:
            name = shown(os.path.abspath(directory)) or "."
            if name == os.path.abspath("").rstrip(os.sep):
                name = "."
            if name not in searched:
                searched.append(name)
        return ", ".join(searched or ["."])

    def on_file_open(self, is_system_include, includepath):
        """Open and read an include file whole, as UTF-8 text. Any failure is an
        OSError for pcpp, which then tries the next directory and at the end
        calls on_include_not_found; why a file that is there could not be read
        (a directory, no permission, not UTF-8) is kept for its message."""
        if len(self.temp_path) > MAX_INCLUDE_DEPTH:
            raise IncludeTooDeep(includepath)
        try:
            text = unsaved_text(includepath)
            if text is None:
                with open(includepath, encoding="utf-8") as handle:
                    text = handle.read()
        except FileNotFoundError:
            self.missing.append(includepath)
            raise
        except IsADirectoryError:
            self.unreadable.append("it is a directory")
            raise
        except OSError as exc:
            self.unreadable.append(exc.strerror or str(exc))
            raise
        except ValueError as exc:  # a NUL byte in the name, or not UTF-8 text
            if isinstance(exc, UnicodeDecodeError):
                line = exc.object[:exc.start].count(b"\n") + 1
                self.unreadable.append(
                    f"it is not UTF-8 text (byte 0x{exc.object[exc.start]:02x} on line {line})")
            raise OSError(str(exc)) from None
        if self.included is not None:
            self.included.append(includepath)
        self.opened.append((includepath, text))
        return io.StringIO(text[1:] if text.startswith("\ufeff") else text)

    def on_directive_handle(self, directive, toks, ifpassthru, precedingtoks):
        import pcpp

        self.lastdirective = directive
        self.unreadable = []  # why the files this directive names could not be read
        self.blocks.follow(directive, _where(directive), self.reporter)
        if directive.value == "define" and toks:
            self._defining(directive, toks)
        if directive.value == "pragma" and not any(tok.value.strip() for tok in toks):
            raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)  # as cpp: nothing to do
        what = _NEEDS.get(directive.value)
        words = [tok.value for tok in toks if tok.value.strip()]
        if what and not words:
            # pcpp itself would fail on these with an IndexError
            self.reporter.error(PreprocessError(f"#{directive.value} needs {what}",
                                                _where(directive)))
            if directive.value in ("if", "elif", "ifdef", "ifndef"):  # left out, as cpp's
                return _false_condition(directive, toks)  # its #endif still matches it
            raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)
        if directive.value == "if" and words[:1] == ["!"] and \
                (len(words) == 1 or words[1] == "defined" and len(words) <= 2 + (words[2:3] == ["("])):
            # a '!' with nothing after it (pcpp reads the first #if of a file
            # for an include guard, and fails on it with an IndexError)
            self.reporter.error(PreprocessError(
                f"#if or #elif cannot evaluate '{''.join(t.value for t in toks).strip()}'; "
                f"write a condition of "
                f"numbers, macros, defined(NAME) and C's operators", _where(directive)))
            return _false_condition(directive, toks)
        return True

    def on_directive_unknown(self, directive, toks, ifpassthru, precedingtoks):
        if directive.value == "line" or directive.value.isdigit():
            return None  # a line marker from an earlier cpp: the reader follows it
        text = "".join(tok.value for tok in toks).strip()
        location = _where(directive)
        if directive.value == "error":
            self.return_code += 1
            self.reporter.error(PreprocessError(f"#error {text}", location))
        elif directive.value == "warning":
            self.reporter.warning(f"#warning {text}", location)
        elif directive.value != "pragma":  # unknown pragmas are ignored, as cpp does
            self.reporter.error(PreprocessError(
                f"unknown preprocessor directive '#{printable(directive.value)}'", location))
        return True

    def _defining(self, directive, toks):
        """Note where each macro is defined; warn when a -D macro is redefined
        differently (cpp does too), since the file's value then wins."""
        words = [t.value for t in toks if t.value.strip()]
        if not words:
            return
        name = words[0]
        location = _where(directive)
        if name in self.given and name not in self.definitions:
            text = "".join(t.value for t in toks).strip()
            value = text[len(name):].strip()
            if _spaced(value) != _spaced(self.given[name]):
                # said once the pass is over, if the #define was not in a
                # skipped #ifndef block (pcpp calls this hook there too)
                self.redefinitions.append((name, location))
        self.definitions[name] = location

    def define(self, tokens):
        """pcpp's #define, after castor's check of the parameters: an empty one
        (``#define MUR(LX, LY,)``, an IndexError inside pcpp) is an error at its
        place, and the macro is defined without it, so that its uses read as
        written; a parameter that is not a name is an error, the macro left out."""
        if not isinstance(tokens, str):
            tokens = self._checked_parameters(tokens)
            if tokens is None:
                return
        self.defining = True
        try:
            super().define(tokens)
        except LookupError:  # a definition pcpp did not expect: said, never a crash
            token = tokens[0] if tokens and not isinstance(tokens, str) else None
            self.reporter.error(PreprocessError("malformed #define", _where(token)))
        finally:
            self.defining = False

    def _checked_parameters(self, tokens: list):
        """The #define's tokens with its empty parameters left out, or None when
        a parameter is not a name (each fault reported at its place)."""
        if len(tokens) < 2 or tokens[1].value != "(":
            return tokens
        kept, group, faults = [tokens[1]], [], []
        for k in range(2, len(tokens)):
            token = tokens[k]
            if token.value not in (",", ")"):
                group.append((k, token))
                continue
            text = "".join(t.value for _, t in group).strip()
            if not text and (token.value == "," or kept[-1].value == ","):
                faults.append((k, f"a parameter is missing before '{token.value}'"))
                if token.value == ")":
                    if kept[-1].value == ",":
                        kept.pop()  # the ',' before an empty last parameter
                    kept.append(token)
            elif text and not _PARAMETER.fullmatch(text):
                first = next(j for j, t in group if t.value.strip())
                faults.append((first, f"'{text}' is not a parameter name"))
                self._parameter_faults(tokens, faults)
                return None
            else:
                kept.extend(t for _, t in group)
                kept.append(token)
            group = []
            if token.value == ")":
                self._parameter_faults(tokens, faults)
                return [tokens[0]] + kept + tokens[k + 1:]
        return tokens  # no ')': pcpp says so

    def _parameter_faults(self, tokens: list, faults: list) -> None:
        """Report each fault of a #define's parameters at its column."""
        name = tokens[0]
        original = self.originals.line(name.source or "<stdin>", int(name.lineno or 0))
        start = original.find(name.value + "(") if original is not None else -1
        for k, message in faults:
            location = _where(name)
            if start >= 0:
                column = start + sum(len(t.value) for t in tokens[:k]) + 1
                location = Location(location.file, location.line, column)
                self.reporter.source_lines[(location.file, location.line)] = original
            self.reporter.error(PreprocessError(
                f"#define {name.value}: {message}; write the parameters as names between "
                f"commas, as in #define {name.value}(X, Y)", location))

    def warn_redefinitions(self):
        for name, location in self.redefinitions:
            macro = self.macros.get(name)
            if macro is None or _spaced("".join(t.value for t in macro.value)) == \
                    _spaced(self.given[name]):
                continue
            original = self.originals.line(location.file, location.line)
            if original is not None:
                self.reporter.source_lines[(location.file, location.line)] = original
            self.reporter.warning(
                f"'{name}' redefined: this #define replaces -D {name}="
                f"{self.given[name]} of the command line; to let -D choose, write "
                f"#ifndef {name} ... #endif around it", location)

    def on_comment(self, tok):
        return True  # keep comments: the grammar skips them, and columns stay right


_classes: list = []


def _make_preprocessor(reporter: Reporter, originals: SourceLines, defines: dict[str, str],
                       included: list[str] | None = None):
    if not _classes:
        import pcpp

        _classes.append(type("Preprocessor", (Hooks, pcpp.Preprocessor), {}))
    return _classes[0](reporter, originals, defines, included)


@dataclass
class Pass:
    """What one pass gave and what it depended on."""

    text: str  # the output
    opened: tuple[tuple[str, str], ...]  # (path, text) of each #included file, in order
    missing: tuple[str, ...]  # paths looked for and not found
    p: object  # the preprocessor at the end (its macros, where they were defined)
    finder: object  # the reporter's expansions (expansion_finder)
    given: dict  # the -D macros
    sources: tuple = ()
    _names: frozenset | None = None
    _lines: dict | None = None

    def macro_names(self) -> frozenset:
        """Every name that is, or was at some point, a macro."""
        if self._names is None:
            self._names = frozenset(self.p.macros) | frozenset(self.p.definitions) | frozenset(
                self.given) | {"defined"}
        return self._names

    def fresh(self) -> bool:
        """Whether every file it #included reads the same (an editor's unsaved
        buffer first) and no file it looked for has appeared."""
        for path, text in self.opened:
            now = unsaved_text(path)
            if now is None:
                try:
                    with open(path, encoding="utf-8") as handle:
                        now = handle.read()
                except (OSError, ValueError):
                    return False
            if now != text:
                return False
        return not any(os.path.exists(path) for path in self.missing)

# --- an editor's unsaved buffers ---------------------------------------------

_overlay = threading.local()


@contextmanager
def unsaved(texts: dict[str, str]):
    """While in the block, in this thread, ``#include`` of one of these files (by
    path) reads the text given here instead of the file: the unsaved buffers of an
    editor, as a C language server reads them."""
    previous = getattr(_overlay, "texts", None)
    _overlay.texts = {os.path.realpath(path): text for path, text in texts.items()}
    try:
        yield
    finally:
        _overlay.texts = previous


def unsaved_text(path: str) -> str | None:
    texts = getattr(_overlay, "texts", None)
    if not texts:
        return None
    return texts.get(os.path.realpath(path))


def run_pass(sources: list[tuple[str, str]], defines: list[str], undefines: list[str],
         include_dirs: list[str], reporter: Reporter,
         included: list[str] | None = None) -> tuple[str, "Pass | None"]:
    """The pass itself: its output, and what the cache keeps of it (None: the
    pass was cut short)."""
    originals = SourceLines(sources)
    given = {}
    for definition in defines:
        name, _, value = definition.partition("=")
        given[name.strip()] = value if value else "1"
    p = _make_preprocessor(reporter, originals, given, included)
    for directory in include_dirs:
        p.add_path(directory)
    for name, value in given.items():
        p.define(f"{name} {value}")
    for name in undefines:
        p.undef(name)
    out = io.StringIO()
    for name, text in sources:
        # "file.cas" is looked for beside the file that includes it first, as cpp does
        p.temp_path = [] if name == "<stdin>" else [os.path.dirname(os.path.abspath(name))]
        if text and not text.endswith("\n"):
            text += "\n"
        p.parse(text, name)
        try:
            p.write(out)
        except IncludeTooDeep as exc:
            token = p.lastdirective
            reporter.error(PreprocessError(
                f"#include nested more than {MAX_INCLUDE_DEPTH} deep (does '{exc}' include itself?)",
                Location(getattr(token, "source", name) or name, getattr(token, "lineno", 0) or 0, 1)))
            return "", None
        except RecursionError:
            reporter.error(PreprocessError("macros or includes nested too deeply", Location(name, 1, 1)))
            return "", None
        out.write("\n")
    p.warn_redefinitions()
    finder = expansion_finder(p, originals)
    reporter.expansions = finder
    text = out.getvalue()
    return text, Pass(text, tuple(p.opened), tuple(p.missing), p, finder, given)


_ORIGINAL_TOKEN = re.compile(r'//.*|/\*.*?\*/|"(?:[^"\\]|\\.)*"|[A-Za-z_]\w*|.')


def expansion_finder(p, originals: SourceLines):
    """What the reporter calls, only for a line it reports on: the macro uses of
    that line (``LineExpansions``), or None where no macro changed it. Worked
    out on demand: a scene of many lines pays nothing for its macros."""
    from castor.diagnostics import LineExpansions

    found: dict[tuple, object] = {}  # kept with the pass: a slider asks the same again
    lock = threading.Lock()  # pcpp's expansion is not made for two threads at once

    def find(file: str, number: int, expanded: str | None):
        key = (file, number, expanded)
        if key in found:
            return found[key]
        original = originals.line(file, number)
        if original is None or expanded is None or original == expanded:
            result = None
        else:
            with lock:
                p.quiet = True
                try:
                    mapped = _expansions_of(expanded, original, p) or _difference(
                        expanded, original, p)
                finally:
                    p.quiet = False
            result = LineExpansions(original, tuple(mapped)) if mapped else None
        if len(found) < 100_000:
            found[key] = result
        return result

    return find


def _difference(line: str, original: str, p) -> list:
    """Where the macro uses of a line could not be lined up one by one: the part
    that differs between the line as written and as expanded, as one expansion
    of the first macro named in it (the same start and end on both lines)."""
    from castor.diagnostics import Expansion

    prefix = 0
    while prefix < min(len(line), len(original)) and line[prefix] == original[prefix]:
        prefix += 1
    suffix = 0
    while (suffix < min(len(line), len(original)) - prefix
           and line[-1 - suffix] == original[-1 - suffix]):
        suffix += 1
    names = [m.group() for m in _ORIGINAL_TOKEN.finditer(original, prefix)
             if m.start() < len(original) - suffix and m.group() in p.macros]
    if not names:
        return []
    defined = p.definitions.get(names[0])
    return [Expansion(prefix, len(line) - suffix, prefix, len(original) - suffix, names[0],
                      f"{defined.file}:{defined.line}" if defined else "the command line")]


def _expansions_of(line: str, original: str, p) -> list | None:
    """The ``Expansion`` of each macro use of ``original`` in its expanded ``line``,
    or None when the two cannot be lined up (arguments over several lines, a
    macro redefined since): the reporter then keeps the expanded positions."""
    from castor.diagnostics import Expansion

    uses = []  # (start, end, macro) of each use in the original line
    tokens = list(_ORIGINAL_TOKEN.finditer(original))
    k = 0
    while k < len(tokens):
        token = tokens[k]
        name = token.group()
        macro = p.macros.get(name)
        if macro is None or not (name[0].isalpha() or name[0] == "_"):
            k += 1
            continue
        end = token.end()
        if macro.arglist is not None:
            rest = original[end:]
            if not rest.lstrip().startswith("("):
                k += 1
                continue
            depth, i = 0, end + len(rest) - len(rest.lstrip())
            while i < len(original):
                if original[i] == "(":
                    depth += 1
                elif original[i] == ")":
                    depth -= 1
                    if depth == 0:
                        break
                i += 1
            else:
                return None  # the arguments go on beyond this line
            end = i + 1
        uses.append((token.start(), end, name))
        while k < len(tokens) and tokens[k].start() < end:
            k += 1
    out, at, previous = [], 0, 0
    for start, end, name in uses:
        literal = original[previous:start]
        if not line.startswith(literal, at):
            return None
        at += len(literal)
        try:
            expansion = "".join(t.value for t in p.expand_macros(p.tokenize(original[start:end])))
        except Exception:  # pcpp on text it did not expect: no mapping, plain positions
            return None
        if not line.startswith(expansion, at):
            return None
        defined = p.definitions.get(name)
        out.append(Expansion(at, at + len(expansion), start, end, name,
                             f"{defined.file}:{defined.line}" if defined else "the command line"))
        at += len(expansion)
        previous = end
    if line[at:] != original[previous:]:
        return None
    return out

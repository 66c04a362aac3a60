"""The built-in C preprocessor pass (pcpp): macros, #include, #if, comments.

The output keeps ``#line`` markers, which the reader follows so that every
position castor reports names the original file and line, inside included
files too.
"""

from __future__ import annotations

import io
import os
import re

from castor.diagnostics import Location, PreprocessError, Reporter

MAX_INCLUDE_DEPTH = 200

# directives that mean nothing without an argument, and what they need
_NEEDS = {"define": "a macro name", "undef": "a macro name", "ifdef": "a macro name",
          "ifndef": "a macro name", "if": "a condition", "elif": "a condition",
          "include": "a file name, as in #include \"walls.cas\""}


def _shown(name: str) -> str:
    """A file name as pcpp shows it: relative to the current directory when inside it."""
    here = os.path.abspath("") + os.sep
    return name[len(here):] if name.startswith(here) else name


def _printable(name: str) -> str:
    """A file name as a message shows it: control characters (a NUL byte) escaped."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in name)


def _escape(name: str) -> str:
    return name.replace("\\", "\\\\").replace('"', '\\"')


class IncludeTooDeep(Exception):
    pass


class SourceLines:
    """The original text of each line of the input files, for carets and for
    mapping positions out of macro expansions."""

    def __init__(self, sources: list[tuple[str, str]]):
        self.files = {name: text.split("\n") for name, text in sources}

    def line(self, file: str, number: int) -> str | None:
        lines = self.files.get(file)
        if lines is None:
            try:
                with open(file, encoding="utf-8", errors="replace") as handle:
                    lines = handle.read().split("\n")
            except OSError:
                lines = []
            self.files[file] = lines
        return lines[number - 1] if 0 < number <= len(lines) else None


def _spaced(text: str) -> str:
    return " ".join(text.split())


def _make_preprocessor(reporter: Reporter, originals: SourceLines, defines: dict[str, str],
                       included: list[str] | None = None):
    import pcpp

    class Preprocessor(pcpp.Preprocessor):
        def __init__(self):
            super().__init__()
            self.line_directive = "#line"
            self.compress = 0
            self.definitions: dict[str, Location] = {}  # macro -> where it was #defined
            self.redefinitions: list[tuple[str, Location]] = []  # of -D macros
            self.unreadable: list[str] = []

        def on_error(self, file, line, msg):
            self.return_code += 1
            reporter.error(PreprocessError(msg, Location(file or "<stdin>", int(line or 0), 1)))

        def on_include_not_found(self, is_malformed, is_system_include, curdir, includepath):
            """Report the #include at its place and drop the directive: the run goes on,
            so that the errors after it are seen too, as an external cpp shows them."""
            token = self.lastdirective
            file = getattr(token, "source", None) or "<stdin>"
            line = getattr(token, "lineno", 0) or 0
            text = originals.line(file, line)
            column = 1
            if text is not None:
                reporter.source_lines[(file, line)] = text
                found = text.find(includepath) if includepath else -1
                column = found if found > 0 else text.find("#") + 1
            location = Location(file, line, column)
            if not is_malformed and not includepath.strip():
                reporter.error(PreprocessError(
                    "#include names no file; write #include \"file.cas\"", location))
                raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)
            if "\0" in includepath:
                reporter.error(PreprocessError(
                    f"include file name '{_printable(includepath)}' holds a NUL byte, which no "
                    f"file name can hold", location))
                raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)
            if self.unreadable:
                reporter.error(PreprocessError(
                    f"cannot read include file '{_printable(includepath)}': {self.unreadable[0]}",
                    location))
                raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)
            if is_malformed:
                message = (f"malformed #include {_printable(includepath)}; write "
                           f"#include \"file.cas\"")
                reporter.error(PreprocessError(message, location))
                raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)
            shown = []
            for directory in ([] if is_system_include else self.temp_path) + self.path:
                name = _shown(os.path.abspath(directory)) or "."
                if name == os.path.abspath("").rstrip(os.sep):
                    name = "."
                if name not in shown:
                    shown.append(name)
            shown = ", ".join(shown or ["."])
            reporter.error(PreprocessError(
                f"cannot find include file '{_printable(includepath)}' (searched: {shown}); "
                f"give the directory that holds it with -I DIR", location))
            raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)

        def on_file_open(self, is_system_include, includepath):
            """Open and read an include file whole, as UTF-8 text. Any failure is an
            OSError for pcpp, which then tries the next directory and at the end
            calls on_include_not_found; why a file that is there could not be read
            (a directory, no permission, not UTF-8) is kept for its message."""
            if len(self.temp_path) > MAX_INCLUDE_DEPTH:
                raise IncludeTooDeep(includepath)
            try:
                with open(includepath, encoding="utf-8") as handle:
                    text = handle.read()
            except FileNotFoundError:
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
            if included is not None:  # for the live preview, which watches them
                included.append(includepath)
            return io.StringIO(text[1:] if text.startswith("\ufeff") else text)

        def on_directive_handle(self, directive, toks, ifpassthru, precedingtoks):
            self.lastdirective = directive
            self.unreadable = []  # why the files this directive names could not be read
            if directive.value == "define" and toks:
                self._defining(directive, toks)
            if directive.value == "pragma" and not any(tok.value.strip() for tok in toks):
                raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)  # as cpp: nothing to do
            what = _NEEDS.get(directive.value)
            if what and not any(tok.value.strip() for tok in toks):
                # pcpp itself would fail on these with an IndexError
                reporter.error(PreprocessError(
                    f"#{directive.value} needs {what}",
                    Location(directive.source or "<stdin>", int(directive.lineno or 0), 1)))
                raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)
            return True

        def on_directive_unknown(self, directive, toks, ifpassthru, precedingtoks):
            if directive.value == "line" or directive.value.isdigit():
                return None  # a line marker from an earlier cpp: the reader follows it
            text = "".join(tok.value for tok in toks).strip()
            location = Location(directive.source or "<stdin>", int(directive.lineno or 0), 1)
            if directive.value == "error":
                self.return_code += 1
                reporter.error(PreprocessError(f"#error {text}", location))
            elif directive.value == "warning":
                reporter.warning(f"#warning {text}", location)
            elif directive.value != "pragma":  # unknown pragmas are ignored, as cpp does
                reporter.error(PreprocessError(
                    f"unknown preprocessor directive '#{directive.value}'", location))
            return True

        def _defining(self, directive, toks):
            """Note where each macro is defined; warn when a -D macro is redefined
            differently (cpp does too), since the file's value then wins."""
            words = [t.value for t in toks if t.value.strip()]
            if not words:
                return
            name = words[0]
            location = Location(directive.source or "<stdin>", int(directive.lineno or 0), 1)
            if name in defines and name not in self.definitions:
                text = "".join(t.value for t in toks).strip()
                value = text[len(name):].strip()
                if _spaced(value) != _spaced(defines[name]):
                    # said once the pass is over, if the #define was not in a
                    # skipped #ifndef block (pcpp calls this hook there too)
                    self.redefinitions.append((name, location))
            self.definitions[name] = location

        def warn_redefinitions(self):
            for name, location in self.redefinitions:
                macro = self.macros.get(name)
                if macro is None or _spaced("".join(t.value for t in macro.value)) == \
                        _spaced(defines[name]):
                    continue
                original = originals.line(location.file, location.line)
                if original is not None:
                    reporter.source_lines[(location.file, location.line)] = original
                reporter.warning(
                    f"'{name}' redefined: this #define replaces -D {name}="
                    f"{defines[name]} of the command line; to let -D choose, write "
                    f"#ifndef {name} ... #endif around it", location)

        def on_comment(self, tok):
            return True  # keep comments: the grammar skips them, and columns stay right

    return Preprocessor()


_DIRECTIVE = re.compile(r"^[ \t]*#", re.M)


def preprocess(sources: list[tuple[str, str]], defines: list[str], undefines: list[str],
               include_dirs: list[str], reporter: Reporter,
               included: list[str] | None = None) -> str:
    """Run the sources, in order, through one preprocessor; return its output.

    ``included``, when given, receives the path of every file that #include opened."""
    if not defines and not any(_DIRECTIVE.search(text) or "\\\n" in text for _, text in sources):
        # No directive and no -D: cpp would change nothing (castor keeps the
        # comments), so skip the pure-Python pass and mark each file's start.
        return "".join(f'#line 1 "{_escape(_shown(name))}"\n{text}\n' for name, text in sources)
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
            return ""
        except RecursionError:
            reporter.error(PreprocessError("macros or includes nested too deeply", Location(name, 1, 1)))
            return ""
        out.write("\n")
    p.warn_redefinitions()
    reporter.expansions = _expansion_finder(p, originals)
    return out.getvalue()


_ORIGINAL_TOKEN = re.compile(r'//.*|/\*.*?\*/|"(?:[^"\\]|\\.)*"|[A-Za-z_]\w*|.')


def _expansion_finder(p, originals: SourceLines):
    """What the reporter calls, only for a line it reports on: the macro uses of
    that line (``LineExpansions``), or None where no macro changed it. Worked
    out on demand: a scene of many lines pays nothing for its macros."""
    from castor.diagnostics import LineExpansions

    def find(file: str, number: int, expanded: str | None):
        original = originals.line(file, number)
        if original is None or expanded is None or original == expanded:
            return None
        mapped = _expansions_of(expanded, original, p) or _difference(expanded, original, p)
        return LineExpansions(original, tuple(mapped)) if mapped else None

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

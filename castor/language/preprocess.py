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


def _escape(name: str) -> str:
    return name.replace("\\", "\\\\").replace('"', '\\"')


class IncludeTooDeep(Exception):
    pass


def _make_preprocessor(reporter: Reporter, included: list[str] | None = None):
    import pcpp

    class Preprocessor(pcpp.Preprocessor):
        def __init__(self):
            super().__init__()
            self.line_directive = "#line"
            self.compress = 0

        def on_error(self, file, line, msg):
            self.return_code += 1
            reporter.error(PreprocessError(msg, Location(file or "<stdin>", int(line or 0), 1)))

        def on_include_not_found(self, is_malformed, is_system_include, curdir, includepath):
            token = self.lastdirective
            file = getattr(token, "source", None) or "<stdin>"
            line = getattr(token, "lineno", 0) or 0
            if is_malformed:
                message = f"malformed #include {includepath}; write #include \"file.cas\""
            else:
                message = f"cannot find include file '{includepath}'"
            reporter.error(PreprocessError(message, Location(file, line, 1)))
            raise pcpp.OutputDirective(pcpp.Action.IgnoreAndRemove)

        def on_file_open(self, is_system_include, includepath):
            if len(self.temp_path) > MAX_INCLUDE_DEPTH:
                raise IncludeTooDeep(includepath)
            opened = super().on_file_open(is_system_include, includepath)
            if included is not None:  # for the live preview, which watches them
                included.append(includepath)
            return opened

        def on_directive_handle(self, directive, toks, ifpassthru, precedingtoks):
            self.lastdirective = directive
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
    p = _make_preprocessor(reporter, included)
    for directory in include_dirs:
        p.add_path(directory)
    for definition in defines:
        name, _, value = definition.partition("=")
        p.define(f"{name} {value if value else '1'}")
    for name in undefines:
        p.undef(name)
    out = io.StringIO()
    for name, text in sources:
        p.temp_path = []
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
    return out.getvalue()

"""The scene's parameters for a customizer: ``castor --params`` and ``-p FILE -P NAME``.

``--params`` prints every parameter with its annotation (LANGUAGE.md §10) as
JSON. ``-p``/``-P`` read a named set of values from the JSON file the live
preview saves (OpenSCAD's customizer format)::

    {"parameterSets": {"tall": {"H": "3.2", "N": "4"}}, "fileFormatVersion": "1"}

and give each as ``--set`` would. The values are numbers (or numbers written
as text, as OpenSCAD writes them), never expressions.
"""

from __future__ import annotations

import json
import math
import sys

from castor.diagnostics import CastorError, Diagnostic, TooManyErrors


class SetError(Exception):
    """A parameter file or set that cannot be used (a usage error)."""


def readable(source):
    """The source with standard input read once into memory, so that -p/-P and the
    run that follows both see it (castor.settings.Source)."""
    if source.text is None and tuple(source.files) in ((), ("-",)):
        return source.replace(files=(), text=sys.stdin.read(), name="<stdin>")
    return source


def scene_analysis(source, reading, evaluation, quiet: bool = False):
    """The check of the scene files of the command line (castor.analysis.scene);
    SetError when a file cannot be read."""
    from castor.diagnostics import UsageError
    from castor.analysis.scene import analyse

    try:
        return analyse(source, reading, evaluation, quiet=quiet)
    except UsageError as exc:
        raise SetError(str(exc).removeprefix("error: ")) from None


def params_command(source, reading, evaluation, quiet: bool = False, stdout=None,
                   stderr=None) -> int:
    """``castor --params``: the parameters as JSON on standard output; warnings and
    errors on standard error as castor prints them. Exit status as castor's."""
    from castor.diagnostics import Reporter
    from castor.analysis.scene import parameters

    stdout = stdout or sys.stdout
    reporter = Reporter(stream=stderr or sys.stderr, quiet=quiet)
    try:
        analysis = scene_analysis(readable(source), reading, evaluation, quiet)
    except SetError as exc:
        (stderr or sys.stderr).write(f"castor: error: {exc}\n")
        return 2
    found, warnings = parameters(analysis)
    for where, text in _source_lines(analysis):
        reporter.source_lines[where] = text
    diagnostics = list(analysis.diagnostics) + [
        Diagnostic("warning", w.message, w.location) for w in warnings]
    try:
        for d in sorted(diagnostics, key=_order):
            if d.kind == "error":
                reporter.error(CastorError(d.message, d.location))
            elif d.kind == "warning":
                reporter.warning(d.message, d.location)
    except TooManyErrors:  # stop saying them
        pass
    document = {"file": analysis.file,
                "parameters": [p.as_json() for p in found]}
    stdout.write(json.dumps(document, indent=2) + "\n")
    stdout.flush()
    return 1 if any(d.kind == "error" for d in analysis.diagnostics) else 0


def _order(d):
    return (d.location is None, d.location or ("", 0, 0))


def _source_lines(analysis):
    for file in list(analysis.texts):
        text = analysis.texts[file]
        for number, line in enumerate(text.split("\n"), 1):
            yield (file, number), line


def load_set(path: str, name: str | None) -> dict[str, float]:
    """The values of the set ``name`` in the parameter file ``path``; SetError
    with what there is when the file, the set or a value is not right."""
    try:
        with open(path, encoding="utf-8") as handle:
            document = json.load(handle)
    except OSError as exc:
        raise SetError(f"cannot read the parameter file '{path}': {exc.strerror}") from None
    except (ValueError, UnicodeDecodeError) as exc:
        raise SetError(f"the parameter file '{path}' is not JSON ({exc}); it holds "
                       f'{{"parameterSets": {{"NAME": {{"H": "3.2"}}}}, '
                       f'"fileFormatVersion": "1"}}') from None
    sets = document.get("parameterSets") if isinstance(document, dict) else None
    if not isinstance(sets, dict):
        raise SetError(f"the parameter file '{path}' has no \"parameterSets\" object, as "
                       f"OpenSCAD's customizer writes it")
    there = ", ".join(sorted(sets)) or "none"
    if name is None:
        raise SetError(f"-p {path} needs -P NAME, the set to use (sets in the file: {there})")
    values = sets.get(name)
    if not isinstance(values, dict):
        raise SetError(f"no parameter set '{name}' in '{path}' (sets in the file: {there})")
    out: dict[str, float] = {}
    for key, value in values.items():
        number = _number(value)
        if number is None:
            raise SetError(f"the set '{name}' in '{path}' gives {key} the value {value!r}, "
                           f"which is not a number")
        out[key] = number
    return out


def _number(value) -> float | None:
    if isinstance(value, bool):
        return float(value)  # OpenSCAD's checkboxes: true is 1, false 0
    if isinstance(value, (int, float)):
        number = float(value)
    elif isinstance(value, str):
        text = value.strip()
        if text in ("true", "false"):
            return 1.0 if text == "true" else 0.0
        try:
            number = float(text)
        except ValueError:
            return None
    else:
        return None
    return number if math.isfinite(number) else None


def set_overrides(path: str, name: str | None, source, reading, evaluation) -> dict[str, float]:
    """The values of the set ``name`` of the parameter file ``path`` as overrides,
    each checked against the scene's parameters; raises SetError. ``source`` has
    standard input read already (``readable``)."""
    values = load_set(path, name)
    analysis = scene_analysis(source, reading, evaluation, quiet=True)
    known = {d.name for d in analysis.definitions if d.kind == "parameter"}
    unknown = sorted(set(values) - known)
    if unknown:
        raise SetError(f"the set '{name}' in '{path}' names "
                       f"{', '.join(unknown)}, which the scene does not define (its parameters: "
                       f"{', '.join(sorted(known)) or 'none'})")
    return values


def _shortest(value: float) -> str:
    """The shortest text that reads back as the same double ('3.2', '4')."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def save_set(path: str, name: str, values: dict[str, float]) -> None:
    """Add or replace the set ``name`` in the parameter file ``path`` (written
    beside, then renamed), keeping the other sets."""
    import os
    import tempfile

    document = {"parameterSets": {}, "fileFormatVersion": "1"}
    try:
        with open(path, encoding="utf-8") as handle:
            loaded = json.load(handle)
        if isinstance(loaded, dict) and isinstance(loaded.get("parameterSets"), dict):
            document = loaded
    except (OSError, ValueError, UnicodeDecodeError):
        pass
    document["parameterSets"][name] = {key: _shortest(value)
                                       for key, value in values.items()}
    document.setdefault("fileFormatVersion", "1")
    directory = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(dir=directory, prefix=".castor-", suffix=".json")
    with os.fdopen(handle, "w", encoding="utf-8") as out:
        json.dump(document, out, indent=2)
        out.write("\n")
    os.replace(temporary, path)

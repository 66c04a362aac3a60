"""The live preview's parameters panel: the scene's parameters, values from the page.

The page shows the parameters ``castor --params`` lists (a slider for a range,
a list for choices, a number input otherwise, in their groups). A change sends
numbers; they are checked here (known names, finite numbers, never text that
castor evaluates) and become the overrides of the next evaluation, exactly as
``--set`` gives them: the scene file is never written. The panel's values stay
in force when the scene is saved in the editor. Named sets are saved beside
the scene (``house.json``, OpenSCAD's customizer format, read by ``-p``/``-P``).
"""

from __future__ import annotations

import math
import os
import re
import shlex
import threading

MAX_VALUE = 1e12  # as castor's coordinates
DRAFT_TOLERANCE = 0.05  # while a slider is dragged: coarser facets, the right ones on release
_SET_NAME = re.compile(r"[\w .-]{1,64}")


class PanelError(Exception):
    """A request from the page that cannot be applied (answered with 400)."""


class Panel:
    """The parameters on offer and the values the page has changed."""

    def __init__(self, files: tuple[str, ...], evaluation, reading):
        """``evaluation``, ``reading``: the command line's (castor.settings)."""
        self.files = files
        self.base = dict(evaluation.overrides)  # the command line's --set
        self.tolerance = evaluation.tolerance
        self.reading = reading
        self.defines, self.include_dirs = reading.defines, reading.include_dirs
        self.values: dict[str, float] = {}  # changed by the page
        self.lock = threading.Lock()
        self._listed: tuple | None = None  # (stamp, parameters)
        self._included: tuple[str, ...] = ()  # the files #include opened, watched too

    # --- what is on offer
    def _stamp(self) -> tuple:
        stamp = []
        for name in self.files + self._included:
            try:
                info = os.stat(name)
                stamp.append((name, info.st_mtime_ns, info.st_size))
            except OSError:
                stamp.append((name, None, None))
        return tuple(stamp)

    def parameters(self):
        """The scene's parameters (castor.analysis.scene), listed again when a file changes."""
        from castor.analysis.scene import analyse, parameters
        from castor.settings import Source

        stamp = self._stamp()
        with self.lock:
            if self._listed is not None and self._listed[0] == stamp:
                return self._listed[1]
        # the scene's own values (not the command line's --set), a file that
        # cannot be read left out (the preview says so)
        analysis = analyse(Source(tuple(self.files)), self.reading, quiet=True,
                           unreadable=lambda name, reason: None)
        found = parameters(analysis)[0]
        self._included = tuple(analysis.included)
        with self.lock:
            self._listed = (self._stamp(), found)
        return found

    def offered(self) -> list:
        """The parameters the panel offers: as OpenSCAD's customizer, neither a
        hidden one nor a value worked out from others (``HT = H + 1``)."""
        return [p for p in self.parameters() if not p.hidden and not (
            p.annotation.control == "number" and not _literal(p.expression))]

    def as_json(self) -> dict:
        offered = []
        for parameter in self.offered():
            entry = parameter.as_json()
            entry["default"] = entry["value"]
            if parameter.name in self.base:
                entry["value"] = _plain(self.base[parameter.name])
            if parameter.name in self.values:
                entry["value"] = _plain(self.values[parameter.name])
            entry["changed"] = parameter.name in self.values
            offered.append(entry)
        return {"parameters": offered, "command": self.command(), "sets": self.set_names(),
                "sets_file": os.path.basename(self.sets_path())}

    # --- changes from the page
    def change(self, request: dict) -> tuple[dict[str, float], float | None]:
        """Apply a request ``{"values": {"H": 3.2}, "draft": false}`` or
        ``{"reset": true}`` or ``{"set": "NAME"}`` or ``{"save": "NAME"}``; the
        overrides and the tolerance of the next evaluation."""
        if not isinstance(request, dict):
            raise PanelError("the request is a JSON object")
        known = {p.name for p in self.parameters()}
        draft = request.get("draft") is True
        if request.get("reset") is True:
            with self.lock:
                self.values = {}
        elif "set" in request:
            from castor.analysis.customizer import SetError, load_set

            name = request["set"]
            if not isinstance(name, str) or not _SET_NAME.fullmatch(name):
                raise PanelError("a set's name is 1 to 64 letters, digits, spaces, '.', '-'")
            try:
                values = load_set(self.sets_path(), name)
            except SetError as exc:
                raise PanelError(str(exc)) from None
            unknown = sorted(set(values) - known)
            if unknown:
                raise PanelError(f"the set '{name}' names {', '.join(unknown)}, which the scene "
                                 f"does not define")
            with self.lock:
                self.values = dict(values)
        elif "save" in request:
            from castor.analysis.customizer import save_set

            name = request["save"]
            if not isinstance(name, str) or not _SET_NAME.fullmatch(name):
                raise PanelError("a set's name is 1 to 64 letters, digits, spaces, '.', '-'")
            # what the panel offers and the user (or --set) changed: a value worked
            # out from others is not saved, so that it follows them when the set is used
            changed = {**self.base, **self.values}
            current = {p.name: changed[p.name] for p in self.offered() if p.name in changed}
            try:
                save_set(self.sets_path(), name, current)
            except OSError as exc:
                raise PanelError(f"cannot write {self.sets_path()}: {exc.strerror}") from None
        else:
            values = request.get("values")
            if not isinstance(values, dict) or not values:
                raise PanelError('send {"values": {"NAME": NUMBER}}')
            checked = {}
            for name, value in values.items():
                if name not in known:
                    raise PanelError(f"the scene has no parameter '{name}'")
                if isinstance(value, bool) or not isinstance(value, (int, float)) \
                        or not math.isfinite(value) or abs(value) > MAX_VALUE:
                    raise PanelError(f"the value of {name} must be a number, not {value!r}")
                checked[name] = float(value)
            with self.lock:
                self.values.update(checked)
        return self.overrides(), (self._draft_tolerance() if draft else self.tolerance)

    def _draft_tolerance(self) -> float:
        return max(self.tolerance or 0.0, DRAFT_TOLERANCE)

    def overrides(self) -> dict[str, float]:
        with self.lock:
            return {**self.base, **self.values}

    # --- what the page shows with it
    def command(self) -> str:
        """The command line that gives the same frames."""
        words = ["castor"]
        for name, value in self.overrides().items():
            words += ["--set", f"{name}={_plain(value)}"]
        if self.tolerance is not None:
            words += ["-t", f"{self.tolerance:g}"]
        words += [f"-D{d}" for d in self.defines] + [f"-I{i}" for i in self.include_dirs]
        words += list(self.files)
        return " ".join(shlex.quote(w) for w in words)

    def sets_path(self) -> str:
        first = self.files[0] if self.files else "scene.cas"
        return os.path.splitext(first)[0] + ".json"

    def set_names(self) -> list[str]:
        import json

        try:
            with open(self.sets_path(), encoding="utf-8") as handle:
                sets = json.load(handle).get("parameterSets", {})
            return sorted(sets) if isinstance(sets, dict) else []
        except (OSError, ValueError, AttributeError, UnicodeDecodeError):
            return []


def _plain(value: float):
    return int(value) if value == int(value) and abs(value) < 2 ** 53 else value


_LITERAL = re.compile(r"-?\s*(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _literal(expression: str) -> bool:
    return bool(_LITERAL.fullmatch(expression.strip()))

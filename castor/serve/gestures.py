"""The page's gestures (CLI.md, "Editing on screen"): ``POST /gesture`` on the
live preview's server runs castor.snap, castor.place, castor.move,
castor.measure or Undo, and hands each edit to an ``editor``: the files
themselves for ``castor --serve`` (``FileEditor``: written atomically, the
scene's own files only), or an editor's buffers for ``castor --lsp --serve``
(castor.lsp.editing sends it with ``workspace/applyEdit``).

A request is ``{"command": "castor.place", "arguments": {...}}`` (or
``{"command": "undo"}``); the answer is ``{"result": ..., "version": ...,
"written": [...]}``: the command's result, the version of the scene's text
the gesture was made on (an edit names it, and one made on an older text is
refused, nothing lost), and for an edit the lines as it wrote them. The page
never chooses the file: ``uri`` is always the scene's own. Its values are
numbers and names checked by castor.editing.commands; none is evaluated as text.
"""

from __future__ import annotations

import json
import threading

from castor.editing.commands import (COMMANDS, Cache, CommandError, apply_workspace_edit,
                                     execute, inverse_workspace_edit, text_version,
                                     write_workspace_edit)
from castor.editing.document import path_to_uri, uri_to_path

EDITS = {"castor.place": "place", "castor.move": "move"}  # command -> the label of its edit
MAX_BODY = 65536
MAX_UNDO = 100


class FileEditor:
    """``castor --serve``: an edit is written into the files, atomically."""

    def __init__(self, cache: Cache, uri: str):
        self.cache, self.uri = cache, uri

    def apply(self, edit: dict, label: str) -> None:
        write_workspace_edit(edit, self.cache, self.uri)


# how long a gesture waits for the editor to open a scene (castor --lsp --serve)
FIRST_SCENE_WAIT = 10.0


class Gestures:
    """The gestures made on the page on one scene, and their Undo."""

    def __init__(self, uri: str, cache: Cache, editor=None, buffers=None, settings=None):
        """``editor.apply(edit, label)`` makes an edit (CommandError if it cannot);
        ``buffers()``, an editor's unsaved texts by path (read by #include);
        ``settings()``, the castor.settings.EvaluationSettings of the frames the
        page shows (the panel's ``--set`` values): gestures snap on those frames."""
        self.followed = threading.Event()  # set once a scene is followed (uri)
        self.uri = uri
        self.cache = cache
        self.settings = settings
        self.editor = editor if editor is not None else FileEditor(cache, uri)
        self.buffers = buffers
        self.lock = threading.Lock()  # one gesture at a time
        self.undoes: list[tuple[dict, dict[str, str]]] = []  # (undo edit, the texts it expects)

    @property
    def uri(self) -> str:
        """The scene the gestures edit ('' until the editor opens one)."""
        return self._uri

    @uri.setter
    def uri(self, uri: str) -> None:
        self._uri = uri
        if uri:
            self.followed.set()

    def answer(self, request) -> dict:
        if not isinstance(request, dict):
            raise CommandError("send one JSON object: {\"command\": ..., \"arguments\": {...}}")
        command = request.get("command")
        if command == "undo":
            return self.undo()
        if command not in COMMANDS:
            raise CommandError(f"unknown command {command!r} (known: "
                               f"{', '.join([*COMMANDS, 'undo'])})")
        arguments = request.get("arguments", {})
        if not isinstance(arguments, dict):
            raise CommandError("the arguments are one JSON object")
        # a gesture sent as soon as the page is up may come before the editor's
        # buffer: it waits for it, within reason (as a hover waits for the first analysis)
        if not self.followed.wait(FIRST_SCENE_WAIT):
            raise CommandError("no scene yet: open one in the editor")
        arguments = dict(arguments, uri=self.uri)  # the page never names a file
        if command in EDITS and arguments.get("version") is None:
            raise CommandError("an edit names the version of the text it was made on "
                               "('version', as a snap's answer gives it)")
        with self.lock, self._unsaved():
            cache = self.cache if self.settings is None else self.cache.using(self.settings())
            text = cache.read(self.uri)
            if text is None:
                raise CommandError(f"cannot read '{uri_to_path(self.uri)}'")
            document = cache.document(self.uri)
            answer = {"result": execute(command, arguments, cache),
                      "version": text_version(text)}
            if command in EDITS:
                answer["written"] = self._make(answer["result"], document, EDITS[command])
                answer["undo"] = len(self.undoes)
        return answer

    def _unsaved(self):
        """While a command runs, ``#include`` reads the editor's unsaved buffers."""
        from contextlib import nullcontext

        if self.buffers is None:
            return nullcontext()
        from castor.language.preprocess import unsaved

        return unsaved(self.buffers())

    def _make(self, edit: dict, document, label: str) -> list[dict]:
        """Hand the edit to the editor, keeping its Undo; the lines it wrote."""
        allowed = {path_to_uri(path) for path in document.files}
        before = {}
        for uri in edit.get("changes", {}):
            if uri not in allowed:
                raise CommandError(f"'{uri_to_path(uri)}' is not one of the scene's files: "
                                   f"nothing was changed")
            before[uri] = self.cache.read(uri)
            if before[uri] is None or before[uri] != document.file_text(uri_to_path(uri)):
                raise CommandError(f"'{uri_to_path(uri)}' changed while the edit was made: "
                                   f"nothing was changed; try again")
        undo = inverse_workspace_edit(edit, before.get)
        after = apply_workspace_edit(edit, before.get)
        self.editor.apply(edit, f"castor: {label}")
        self.undoes.append((undo, after))
        del self.undoes[:-MAX_UNDO]
        return written(edit, after)

    def undo(self) -> dict:
        """The last edit made from the page, undone; refused if a text it
        changed has changed since (the editor's own undo is for that)."""
        with self.lock:
            if not self.undoes:
                raise CommandError("nothing to undo: no edit was made from this page")
            undo, expected = self.undoes[-1]
            for uri, text in expected.items():
                if self.cache.read(uri) != text:
                    raise CommandError(f"'{uri_to_path(uri)}' changed after the last edit made "
                                       f"from the page: nothing was undone")
            restored = apply_workspace_edit(undo, expected.get)
            self.editor.apply(undo, "castor: undo")
            self.undoes.pop()
            text = self.cache.read(self.uri)
            return {"result": undo, "version": text_version(text) if text is not None else None,
                    "written": written(undo, restored), "undo": len(self.undoes)}

    def description(self) -> dict:
        """What the page's toolbar offers (``/editing.json``)."""
        return {"enabled": True, "primitives": palette(), "undo": len(self.undoes)}


def written(edit: dict, texts: dict[str, str]) -> list[dict]:
    """The lines an edit wrote, as they are after it: ``{"file", "line", "text"}``."""
    out = []
    for uri, edits in edit.get("changes", {}).items():
        lines = texts[uri].split("\n")
        shift, seen = 0, set()
        for e in sorted(edits, key=lambda e: (e["range"]["start"]["line"],
                                              e["range"]["start"]["character"])):
            start, end = e["range"]["start"]["line"], e["range"]["end"]["line"]
            first = start + shift
            shift += e["newText"].count("\n") - (end - start)
            for number in range(first, start + shift + 1):
                if number not in seen and 0 <= number < len(lines):
                    seen.add(number)
                    out.append({"file": uri_to_path(uri), "line": number + 1,
                                "text": lines[number]})
    return out


def palette() -> list[str]:
    """The primitives Place offers, as castor.place takes them: each without
    coordinate pairs, with the first of a few plain values its check accepts
    for an argument (``!pr(4)``, ``!to(0.25)``)."""
    from castor.diagnostics import CastorError, Location
    from castor.primitives import PRIMITIVES

    out = []
    for name, declared in sorted(PRIMITIVES.items(), key=lambda item: item[1].place):
        if declared.pairs:
            continue
        for value in (0.25, 6):
            shape = (value,) * len(declared.arguments)
            try:
                if declared.check is not None:
                    declared.check(shape, Location("<palette>", 1, 1), f"!{name}")
            except CastorError:
                continue
            arguments = ", ".join(f"{v:g}" for v in shape)
            out.append(f"!{name}({arguments})" if arguments else f"!{name}")
            break
    return out


def file_gestures(job, preview=None) -> Gestures | None:
    """The gestures of ``castor --serve`` on its scene file (None for a scene
    read from several files or standard input: which file to write is unclear),
    made on the frames as ``preview`` (castor.serve.server.Preview) shows them,
    with its panel's values."""
    source = job.source
    if source.text is not None or len(source.files) != 1 or source.streamed:
        return None
    uri = path_to_uri(source.files[0])
    return Gestures(uri, Cache(reading=job.reading),
                    settings=shown_settings(preview) if preview is not None else None)


def shown_settings(preview):
    """The EvaluationSettings of the frames ``preview`` shows, as they change."""
    return lambda: preview.job.evaluation


def answer_post(gestures: Gestures | None, body: bytes) -> tuple[int, bytes]:
    """``POST /gesture``: the HTTP status and the JSON answer."""
    if gestures is None:
        return 404, json.dumps({"error": "editing on screen needs one scene file"}).encode()
    try:
        request = json.loads(body or b"null")
    except ValueError:
        return 400, json.dumps({"error": "the request is not JSON"}).encode()
    try:
        answer = gestures.answer(request)
    except CommandError as error:
        return 400, json.dumps({"error": error.message}).encode()
    except RecursionError:
        return 400, json.dumps({"error": "the scene is nested too deeply to edit"}).encode()
    except Exception as exc:  # castor's bug: said on the page, nothing written
        message = f"internal error: {type(exc).__name__}: {exc} (please report it)"
        return 500, json.dumps({"error": message}).encode()
    return 200, json.dumps(answer).encode()


def description(gestures: Gestures | None) -> bytes:
    if gestures is None:
        return json.dumps({"enabled": False, "primitives": [],
                           "reason": "editing on screen needs one scene file"}).encode()
    return json.dumps(gestures.description()).encode()

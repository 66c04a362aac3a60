"""Editing on screen through the language server (CLI.md, "Editing on screen").

``EditingFeatures`` is a part of castor.lsp.protocol's ``CastorServer``:

- ``workspace/executeCommand`` of ``castor.snap``, ``castor.place``,
  ``castor.move`` and ``castor.measure`` (castor.editing.commands), on the
  editor's buffers (unsaved, the files it includes read from the open
  buffers too); Place and Move send their edit back with
  ``workspace/applyEdit``, so that it lands in the buffer, unsaved, and is
  undone with ``u``; a bad argument is a JSON-RPC error, nothing changed;
- with ``castor --lsp --serve``, the live preview of the buffers
  (castor.serve.buffers) on a local address told to the editor with
  ``window/showMessage``: it follows the scene being edited, and the page's
  gestures reach the editor as ``workspace/applyEdit`` too.
"""

from __future__ import annotations

import asyncio
import os

from lsprotocol import types

from castor.editing.commands import COMMANDS, Cache, CommandError, execute
from castor.editing.document import path_to_uri, read_file, uri_to_path

APPLY_SECONDS = 20.0  # how long a gesture of the page waits for the editor to apply it
INVALID_PARAMS = -32602
REQUEST_FAILED = -32803


def _failed(message: str, code: int = REQUEST_FAILED):
    from pygls.exceptions import JsonRpcException

    return JsonRpcException(code=code, message=message)


def lsp_edit(edit: dict) -> types.WorkspaceEdit:
    """A WorkspaceEdit as castor.editing.commands gives it, as lsprotocol's."""
    changes = {}
    for uri, edits in edit.get("changes", {}).items():
        changes[uri] = [types.TextEdit(
            range=types.Range(start=types.Position(**e["range"]["start"]),
                              end=types.Position(**e["range"]["end"])),
            new_text=e["newText"]) for e in edits]
    return types.WorkspaceEdit(changes=changes)


class EditingFeatures:
    """The commands and the preview of ``castor --lsp`` (mixed into CastorServer)."""

    def _register_editing(self) -> None:
        self.editing_cache = Cache(read=self.buffer_text)
        self.preview_server = None
        self.gestures = None
        for name in COMMANDS:
            self.command(name)(self._command_handler(name))
        self.feature(types.INITIALIZED)(_initialized(self))

    # --- the buffers as the commands read them
    def buffer_text(self, uri: str) -> str | None:
        """An open buffer's text, else the file's."""
        document = self._open_buffer(uri)
        return document.text if document is not None else read_file(uri)

    def _open_buffer(self, uri: str):
        if not isinstance(uri, str):
            return None
        path = os.path.realpath(uri_to_path(uri))
        for document in list(self.documents.documents.values()):
            if document.open and document.path is not None and \
                    os.path.realpath(document.path) == path:
                return document
        return None

    def unsaved_buffers(self) -> dict[str, str]:
        return {d.path: d.text for d in list(self.documents.documents.values())
                if d.open and d.path is not None}

    # --- workspace/executeCommand
    def _command_handler(self, name: str):
        async def handler(*arguments):
            return await self.run_command(name, list(arguments))
        handler.__name__ = name.replace(".", "_")
        return handler

    async def run_command(self, name: str, arguments: list):
        loop = asyncio.get_event_loop()
        result = await loop.run_in_executor(None, self._command, name, arguments)
        if name in ("castor.place", "castor.move"):
            await self.send_edit(result, f"castor: {name.partition('.')[2]}")
        return result

    def _command(self, name: str, arguments: list):
        from castor.language.preprocess import unsaved

        try:
            with unsaved(self.unsaved_buffers()):
                return execute(name, arguments, self.editing_cache)
        except CommandError as error:
            raise _failed(error.message, INVALID_PARAMS) from None
        except RecursionError:
            raise _failed("the scene is nested too deeply to edit") from None

    async def send_edit(self, edit: dict, label: str) -> None:
        """``workspace/applyEdit``: the edit goes into the editor's buffers."""
        answer = await self.workspace_apply_edit_async(
            types.ApplyWorkspaceEditParams(edit=lsp_edit(edit), label=label))
        if not answer.applied:
            reason = f": {answer.failure_reason}" if answer.failure_reason else ""
            raise _failed(f"the editor did not apply the edit{reason}")

    # --- castor --lsp --serve
    def serve_preview(self, reading, bind: str, port: int, path: str | None = None) -> str:
        """Start the live preview of the buffers; its address. OSError if it
        cannot listen there."""
        from castor.serve.buffers import BufferPreview
        from castor.serve.gestures import Gestures, shown_settings
        from castor.serve.server import PreviewServer

        path = os.path.abspath(path) if path else None
        preview = BufferPreview(reading, path)
        self.editing_cache.reading = reading
        self.gestures = Gestures(path_to_uri(path) if path else "", self.editing_cache,
                                 editor=_BufferEditor(self), buffers=self.unsaved_buffers,
                                 settings=shown_settings(preview))
        self.preview_server = PreviewServer(preview.job, bind, port, preview=preview,
                                            gestures=self.gestures)
        from castor.pipeline import STACK_BYTES
        from castor.serve.buffers import warm

        warm()  # before the preview's thread starts: see BufferPreview._stop_stale
        self.preview_server.start(STACK_BYTES)
        return self.preview_server.url

    def preview_follows(self, document) -> None:
        """A buffer opened or changed: the preview shows the scene it is part of."""
        if self.preview_server is None or document.path is None:
            return
        scene = self.documents.owner(document)
        if scene.path is None:
            return
        text = scene.text if scene.open else read_file(path_to_uri(scene.path))
        if text is None:
            return
        self.preview_server.preview.follow(os.path.abspath(scene.path), text,
                                           self.unsaved_buffers())
        self.gestures.uri = path_to_uri(scene.path)

    def stop_preview(self) -> None:
        if self.preview_server is not None:
            self.preview_server.close()
            self.preview_server = None


class _BufferEditor:
    """Where the page's edits go under ``castor --lsp --serve``: the editor,
    with ``workspace/applyEdit`` (from the preview's thread to the protocol's)."""

    def __init__(self, server: EditingFeatures):
        self.server = server

    def apply(self, edit: dict, label: str) -> None:
        from pygls.exceptions import JsonRpcException

        loop = self.server.event_loop
        if loop is None or loop.is_closed():
            raise CommandError("no editor is connected to the language server")
        future = asyncio.run_coroutine_threadsafe(self.server.send_edit(edit, label), loop)
        try:
            future.result(APPLY_SECONDS)
        except JsonRpcException as error:
            raise CommandError(error.message) from None
        except TimeoutError:
            future.cancel()
            raise CommandError("the editor did not answer the edit in time: it may have "
                               "applied it or not; look at the buffer") from None


def _initialized(server: EditingFeatures):
    def initialized(params) -> None:
        if server.preview_server is None:
            return
        message = f"castor: the live preview of the buffers is at {server.preview_server.url}"
        server.window_log_message(types.LogMessageParams(type=types.MessageType.Info,
                                                         message=message))
        server.window_show_message(types.ShowMessageParams(type=types.MessageType.Info,
                                                           message=message))
    return initialized

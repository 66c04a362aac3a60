"""The Language Server Protocol's requests, one method each (pygls).

Each method turns the protocol's 0-based positions and URIs into castor's
(a file name as locations give it, 1-based line and column) and castor's
answers back; what the answers say comes from castor.analysis.knowledge,
over the analyses castor.analysis.documents keeps. A request about a document
whose first analysis has not come yet waits for it (at most
``FIRST_ANALYSIS_SECONDS``).
"""

from __future__ import annotations

import asyncio
import os
import threading
import time

from lsprotocol import types
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from castor.analysis import knowledge
from castor.analysis.classes import ANNOTATION_TRIGGERS
from castor.analysis.documents import Document, Documents
from castor.analysis.scene import object_figures, shown_name
from castor.diagnostics import Location
from castor.lsp.editing import EditingFeatures

FIRST_ANALYSIS_SECONDS = 15.0

_SEVERITY = {"error": types.DiagnosticSeverity.Error, "warning": types.DiagnosticSeverity.Warning}
_COMPLETION_KINDS = {"primitive": types.CompletionItemKind.Function,
                     "transform": types.CompletionItemKind.Function,
                     "boolean": types.CompletionItemKind.Operator,
                     "parameter": types.CompletionItemKind.Variable,
                     "object": types.CompletionItemKind.Class,
                     "macro": types.CompletionItemKind.Constant,
                     "class": types.CompletionItemKind.Class,
                     "type": types.CompletionItemKind.EnumMember,
                     "setting": types.CompletionItemKind.Property,
                     "value": types.CompletionItemKind.Value}
_SYMBOL_KINDS = {"parameter": types.SymbolKind.Constant, "object": types.SymbolKind.Object,
                 "frame": types.SymbolKind.Event}


def _protocol_class():
    """pygls's protocol, answering a request whose parameters it cannot read with
    the protocol's error (-32602) instead of leaving the client waiting."""
    from types import SimpleNamespace

    from pygls.exceptions import JsonRpcException
    from pygls.protocol import LanguageServerProtocol

    class Protocol(LanguageServerProtocol):
        def structure_message(self, data):
            try:
                return super().structure_message(data)
            except JsonRpcException as exc:
                if isinstance(data.get("id"), (int, str)) and "method" in data:
                    self._send_response(data["id"], error=types.ResponseError(
                        code=exc.code, message=f"{exc.message}: {data.get('method')}"))
                return SimpleNamespace(jsonrpc="dropped")  # not handled further

    return Protocol


def uri_of(file: str) -> str:
    return from_fs_path(os.path.abspath(file))


def path_of(uri: str) -> str | None:
    """The file of a URI; None when not a file, or not a name a file can have
    (a NUL byte: ``%00``)."""
    path = to_fs_path(uri) if uri.startswith("file:") else None
    return path if path and "\x00" not in path else None


def position(location: Location) -> types.Position:
    return types.Position(line=max(location.line - 1, 0), character=max(location.column - 1, 0))


def lsp_range(location: Location, end: int) -> types.Range:
    """From ``location`` to the 1-based column ``end`` of its line."""
    return types.Range(start=position(location),
                       end=types.Position(line=max(location.line - 1, 0),
                                          character=max(end - 1, location.column)))


def _function(method):
    """A bound method as the plain function pygls registers (it marks what it
    registers with attributes, which a bound method cannot take)."""
    if asyncio.iscoroutinefunction(method):
        async def handler(params):
            return await method(params)
    else:
        def handler(params):
            return method(params)
    handler.__name__ = method.__name__
    return handler


def _nowhere() -> types.Range:
    return types.Range(start=types.Position(line=0, character=0),
                       end=types.Position(line=0, character=1))


class CastorServer(EditingFeatures, LanguageServer):
    """castor's language server (its editing on screen: castor.lsp.editing)."""

    def __init__(self):
        from castor import __version__

        super().__init__("castor", __version__, protocol_cls=_protocol_class(),
                         text_document_sync_kind=types.TextDocumentSyncKind.Full)
        self.documents = Documents(self._finished, uri_of)
        self.event_loop = None
        self.figures_lock = threading.Lock()
        for method, handler, options in [
                (types.INITIALIZE, self.initialize, None),
                (types.TEXT_DOCUMENT_DID_OPEN, self.did_open, None),
                (types.TEXT_DOCUMENT_DID_CHANGE, self.did_change, None),
                (types.TEXT_DOCUMENT_DID_SAVE, self.did_save, None),
                (types.TEXT_DOCUMENT_DID_CLOSE, self.did_close, None),
                (types.TEXT_DOCUMENT_HOVER, self.hover, None),
                (types.TEXT_DOCUMENT_DEFINITION, self.definition, None),
                (types.TEXT_DOCUMENT_REFERENCES, self.references, None),
                (types.TEXT_DOCUMENT_PREPARE_RENAME, self.prepare_rename, None),
                (types.TEXT_DOCUMENT_RENAME, self.rename,
                 types.RenameOptions(prepare_provider=True)),
                (types.TEXT_DOCUMENT_COMPLETION, self.completion,
                 types.CompletionOptions(trigger_characters=["!", "@", "$",
                                                             *ANNOTATION_TRIGGERS])),
                (types.TEXT_DOCUMENT_DOCUMENT_SYMBOL, self.document_symbol, None),
                (types.SHUTDOWN, self.on_shutdown, None)]:
            self.feature(method, options)(_function(handler))
        self._register_editing()

    # --- the session
    def initialize(self, params: types.InitializeParams) -> None:
        roots = [path_of(folder.uri) for folder in params.workspace_folders or []]
        if not any(roots) and params.root_uri:
            roots = [path_of(params.root_uri)]
        self.documents.roots = [os.path.realpath(root) for root in roots if root]
        self.event_loop = asyncio.get_event_loop()

    def on_shutdown(self, params) -> None:
        self.documents.stop()
        self.stop_preview()

    # --- the buffers
    def did_open(self, params: types.DidOpenTextDocumentParams) -> None:
        doc = params.text_document
        self._opened(doc.uri, doc.version, doc.text, opening=True)

    def did_change(self, params: types.DidChangeTextDocumentParams) -> None:
        doc = self.workspace.get_text_document(params.text_document.uri)
        self._opened(params.text_document.uri, params.text_document.version, doc.source)

    def did_save(self, params: types.DidSaveTextDocumentParams) -> None:
        self.documents.saved(params.text_document.uri)

    def did_close(self, params: types.DidCloseTextDocumentParams) -> None:
        for uri in self.documents.closed(params.text_document.uri):
            self.text_document_publish_diagnostics(
                types.PublishDiagnosticsParams(uri=uri, diagnostics=[]))

    def _opened(self, uri: str, version: int, text: str, opening: bool = False) -> None:
        if self.event_loop is None:
            self.event_loop = asyncio.get_event_loop()
        document, problem = self.documents.opened(uri, path_of(uri), version, text, opening)
        self.preview_follows(document)
        if problem is None:
            return
        document.analysed = True
        if document.path is None:
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=uri, diagnostics=[types.Diagnostic(
                    range=_nowhere(), message=problem, source="castor",
                    severity=types.DiagnosticSeverity.Information)]))
        else:
            self._publish(document, None, problem, version)

    # --- diagnostics
    def _finished(self, document: Document, analysis, problem: str | None, version: int):
        """From the worker's thread: hand the result to the protocol's thread."""
        loop = self.event_loop
        if loop is None or loop.is_closed():
            return
        try:
            loop.call_soon_threadsafe(self._publish, document, analysis, problem, version)
        except RuntimeError:  # the loop has closed: the server is ending
            pass

    def _publish(self, document: Document, analysis, problem: str | None, version: int):
        if self.documents.get(document.key) is not document:
            return  # closed meanwhile: nothing more is said of it
        document.analysed = True
        by_uri: dict[str, list] = {document.key: []}
        if analysis is None:
            by_uri[document.key].append(self._diagnostic("error", problem, None, None))
        else:
            document.analysis = analysis
            found = [(d.kind, d.message, d.location) for d in analysis.diagnostics]
            found += [("warning", w.message, w.location)
                      for w in knowledge.parameters(analysis)[1]]
            for kind, message, location in found:
                by_uri.setdefault(self._file_uri(location, analysis), []).append(
                    self._diagnostic(kind, message, location, analysis))
        versions = {document.key: version}
        for part in self.documents.parts_of(document):  # said, even when nothing is wrong
            by_uri.setdefault(part.key, [])
            versions[part.key] = part.version
        for uri in document.published - set(by_uri):
            by_uri[uri] = []  # cleared: no diagnostic there any more
        document.published = {uri for uri, found in by_uri.items() if found}
        for uri, found in by_uri.items():
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=uri, diagnostics=found, version=versions.get(uri)))

    def _file_uri(self, location: Location | None, analysis=None) -> str:
        """The URI of a file as locations name it; with ``analysis``, its main
        file (or no file) is the document analysed."""
        documents = self.documents.documents.values()
        if analysis is not None and (location is None or location.file.startswith("<")
                                     or location.file == analysis.file):
            for document in documents:
                if document.analysis is analysis:
                    return document.key
            return uri_of(analysis.file)
        for document in documents:
            if document.analysis is not None and document.analysis.file == location.file:
                return document.key
        return uri_of(location.file)

    def _diagnostic(self, kind: str, message: str, location: Location | None, analysis):
        where = _nowhere()
        if location is not None:
            text = analysis.source_text(location.file) if analysis is not None else None
            where = lsp_range(location, knowledge.token_end(text, location))
        return types.Diagnostic(range=where, message=message, source="castor",
                                severity=_SEVERITY.get(kind, types.DiagnosticSeverity.Information))

    # --- what the requests read
    async def _at(self, uri: str, pos: types.Position):
        """The analysis for a request (waiting for the first one of a document
        just opened), and the cursor as castor's (file, line, column)."""
        path = path_of(uri)
        document = self.documents.get(uri)
        if document is None or path is None:
            return None, None
        deadline = time.monotonic() + FIRST_ANALYSIS_SECONDS
        while time.monotonic() < deadline and self.documents.get(uri) is document:
            owner = self.documents.owner(document)
            if owner.analysis is not None or owner.analysed:
                break
            await asyncio.sleep(0.02)
        owner = self.documents.owner(document)
        if owner.analysis is None:
            return None, None
        file = owner.analysis.file if owner is document else shown_name(path)
        return owner.analysis, (file, pos.line + 1, pos.character + 1)

    def _location(self, location: Location, end: int | None = None) -> types.Location:
        return types.Location(uri=self._file_uri(location),
                              range=lsp_range(location, end or location.column + 1))

    def _figures(self, analysis, name: str):
        """An object's box and volume, made once per analysis (one at a time: the
        facetizer's caches are shared)."""
        with self.figures_lock:
            cache = analysis.__dict__.setdefault("figures", {})
            if name not in cache:
                cache[name] = object_figures(analysis, name)
            return cache[name]

    # --- the requests
    async def hover(self, params: types.HoverParams):
        analysis, cursor = await self._at(params.text_document.uri, params.position)
        if analysis is None:
            return None
        found = await asyncio.get_event_loop().run_in_executor(  # figures take a while
            None, lambda: knowledge.hover(analysis, *cursor, figures=self._figures))
        if found is None or found[0] is None:
            return None
        text, word = found
        return types.Hover(
            contents=types.MarkupContent(kind=types.MarkupKind.PlainText, value=text),
            range=types.Range(start=types.Position(line=word.line - 1, character=word.start - 1),
                              end=types.Position(line=word.line - 1, character=word.end - 1)))

    async def definition(self, params: types.DefinitionParams):
        analysis, cursor = await self._at(params.text_document.uri, params.position)
        if analysis is None:
            return None
        return [self._location(place, knowledge.token_end(analysis.source_text(place.file), place))
                for place in knowledge.definition(analysis, *cursor)] or None

    async def references(self, params: types.ReferenceParams):
        analysis, cursor = await self._at(params.text_document.uri, params.position)
        if analysis is None:
            return None
        found = knowledge.references(analysis, *cursor,
                                     declaration=params.context.include_declaration)
        return [self._location(place, end) for place, end in found] or None

    async def prepare_rename(self, params: types.PrepareRenameParams):
        analysis, cursor = await self._at(params.text_document.uri, params.position)
        if analysis is None:
            return None
        try:
            word = knowledge.renamable(analysis, *cursor)
        except knowledge.RenameError as exc:
            raise _request_failed(exc) from None
        return types.PrepareRenamePlaceholder(
            range=types.Range(start=types.Position(line=word.line - 1, character=word.start - 1),
                              end=types.Position(line=word.line - 1, character=word.end - 1)),
            placeholder=word.name)

    async def rename(self, params: types.RenameParams):
        analysis, cursor = await self._at(params.text_document.uri, params.position)
        if analysis is None:
            return None
        try:
            edits = knowledge.rename(analysis, *cursor, params.new_name)
        except knowledge.RenameError as exc:
            raise _request_failed(exc) from None
        changes: dict[str, list] = {}
        for place, end in edits:
            changes.setdefault(self._file_uri(place), []).append(
                types.TextEdit(range=lsp_range(place, end), new_text=params.new_name))
        return types.WorkspaceEdit(changes=changes)

    def completion(self, params: types.CompletionParams):
        document = self.documents.get(params.text_document.uri)
        text = document.text if document is not None else ""
        owner = self.documents.owner(document) if document is not None else None
        analysis = owner.analysis if owner is not None else None
        file = ("" if analysis is None else analysis.file if owner is document
                else shown_name(document.path))
        context = params.context
        items = knowledge.completions(analysis, text, file, params.position.line + 1,
                                      params.position.character + 1,
                                      context.trigger_character if context else None)
        snippets = self._snippets()
        return types.CompletionList(is_incomplete=False, items=[
            types.CompletionItem(
                label=c.label, kind=_COMPLETION_KINDS[c.kind], detail=c.detail,
                documentation=c.documentation or None,
                insert_text=c.snippet if snippets and c.snippet else c.insert,
                insert_text_format=types.InsertTextFormat.Snippet if snippets and c.snippet
                else types.InsertTextFormat.PlainText)
            for c in items])

    def _snippets(self) -> bool:
        """Whether the client fills in snippets (the arguments as placeholders)."""
        try:
            return bool(self.client_capabilities.text_document.completion.completion_item
                        .snippet_support)
        except AttributeError:
            return False

    async def document_symbol(self, params: types.DocumentSymbolParams):
        analysis, cursor = await self._at(params.text_document.uri,
                                          types.Position(line=0, character=0))
        if analysis is None:
            return []
        out = []
        for s in knowledge.symbols(analysis, cursor[0]):
            whole = lsp_range(s.location, s.end)
            out.append(types.DocumentSymbol(name=s.name, kind=_SYMBOL_KINDS[s.kind], range=whole,
                                            selection_range=whole, detail=s.detail))
        return out


def _request_failed(exc: Exception):
    from pygls.exceptions import JsonRpcException

    return JsonRpcException(code=-32803, message=str(exc))  # RequestFailed (LSP 3.17)

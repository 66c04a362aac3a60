"""``castor --lsp``: the Language Server Protocol on standard input and output (pygls).

Every change of a buffer is analysed in the background, by one worker thread,
as ``castor --check`` would (castor.lsp.evaluate): the protocol's thread keeps
answering hovers and completions meanwhile. An analysis that a newer edit has
overtaken stops at its next statement and its result is dropped. The
diagnostics are published for the buffer and for each file it ``#include``s;
hovers, definitions, references, completions and the outline read the last
finished analysis (castor.lsp.knowledge).
"""

from __future__ import annotations

import asyncio
import os
import sys
import threading
from dataclasses import dataclass, field

from castor.diagnostics import Location

# a buffer larger than this is not analysed while typing (castor --check reads it)
MAX_BUFFER = 4_000_000


@dataclass
class _Document:
    uri: str
    path: str | None  # None: not a file in the workspace, not analysed
    version: int = 0
    text: str = ""
    analysis: object = None  # the last finished Analysis
    published: set[str] = field(default_factory=set)  # URIs given diagnostics


class Worker:
    """One thread that analyses the newest text of each document, newest first."""

    def __init__(self, publish):
        self.publish = publish  # publish(document, analysis or None, problem)
        self.lock = threading.Condition()
        self.pending: dict[str, tuple] = {}
        self.latest: dict[str, int] = {}  # uri -> the number of its newest submission
        self.submitted = 0
        self.stopped = False
        from castor.pipeline import STACK_BYTES

        size = threading.stack_size()
        threading.stack_size(STACK_BYTES)  # deep scenes recurse deeply, as in castor
        try:
            self.thread = threading.Thread(target=self._run, name="castor-analysis", daemon=True)
        finally:
            threading.stack_size(size)
        self.thread.start()

    def submit(self, document: _Document, unsaved: dict[str, str] | None = None) -> None:
        """Analyse the document's text as it is now, with ``unsaved``, the buffers
        of the other open files (path -> text), read instead of those files by
        its #include (castor.language.preprocess.unsaved)."""
        with self.lock:
            self.submitted += 1
            self.latest[document.uri] = self.submitted
            self.pending[document.uri] = (document, document.version, document.text,
                                          dict(unsaved or {}), self.submitted)
            self.lock.notify()

    def stop(self) -> None:
        with self.lock:
            self.stopped = True
            self.lock.notify()

    def _overtaken(self, uri: str, number: int) -> bool:
        return self.stopped or self.latest.get(uri) != number

    def _run(self) -> None:
        from castor.language.preprocess import unsaved
        from castor.lsp.evaluate import Overtaken, _shown, analyse
        from castor.settings import Source

        while True:
            with self.lock:
                while not self.pending and not self.stopped:
                    self.lock.wait()
                if self.stopped:
                    return
                uri, (document, version, text, buffers, number) = self.pending.popitem()
            try:
                with unsaved(buffers):
                    analysis = analyse(Source(text=text, name=document.path),
                                       cancelled=lambda: self._overtaken(uri, number))
                by_path = {os.path.realpath(path): text for path, text in buffers.items()}
                for path in analysis.included:  # ranges and hovers read the buffers too
                    if os.path.realpath(path) in by_path:
                        analysis.texts[path] = analysis.texts[_shown(path)] = \
                            by_path[os.path.realpath(path)]
            except Overtaken:
                continue
            except MemoryError:
                self.publish(document, None, "out of memory analysing the scene", version)
                continue
            except Exception as exc:  # a fault of castor's: said, and the server goes on
                self.publish(document, None, f"castor: internal error: {type(exc).__name__}: "
                             f"{exc} (please report it with the scene)", version)
                continue
            if not self._overtaken(uri, number):
                self.publish(document, analysis, None, version)


def _protocol_class():
    """pygls's protocol, answering a request whose parameters it cannot read with
    the protocol's error (-32602) instead of leaving the client waiting."""
    from types import SimpleNamespace

    from lsprotocol import types
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


def _server():
    from lsprotocol import types
    from pygls.lsp.server import LanguageServer
    from pygls.uris import from_fs_path, to_fs_path

    from castor import __version__
    from castor.lsp import knowledge
    from castor.lsp.evaluate import _shown

    server = LanguageServer("castor", __version__, protocol_cls=_protocol_class(),
                            text_document_sync_kind=types.TextDocumentSyncKind.Full)
    documents: dict[str, _Document] = {}
    state = {"loop": None, "roots": []}

    def uri_of(file: str) -> str:
        return from_fs_path(os.path.abspath(file))

    def position(location: Location) -> types.Position:
        return types.Position(line=max(location.line - 1, 0),
                              character=max(location.column - 1, 0))

    def lsp_range(location: Location, end: int) -> types.Range:
        return types.Range(start=position(location),
                           end=types.Position(line=max(location.line - 1, 0),
                                              character=max(end - 1, location.column)))

    def publish(document: _Document, analysis, problem: str | None, version: int) -> None:
        """From the worker: hand the diagnostics to the protocol's thread."""
        loop = state["loop"]
        if loop is None or loop.is_closed():
            return
        try:
            loop.call_soon_threadsafe(_publish, document, analysis, problem, version)
        except RuntimeError:  # the loop has closed: the server is ending
            pass

    def _publish(document: _Document, analysis, problem: str | None, version: int) -> None:
        if documents.get(document.uri) is not document:
            return  # closed meanwhile: nothing more is said of it
        by_uri: dict[str, list] = {document.uri: []}
        if analysis is not None:
            document.analysis = analysis
            for d in analysis.diagnostics:
                by_uri.setdefault(_diagnostic_uri(d.location, analysis), []).append(
                    _lsp_diagnostic(d.kind, d.message, d.location, analysis))
            for w in knowledge.parameters(analysis)[1]:
                by_uri.setdefault(_diagnostic_uri(w.location, analysis), []).append(
                    _lsp_diagnostic("warning", w.message, w.location, analysis))
        else:
            by_uri[document.uri].append(_lsp_diagnostic("error", problem, None, None))
        for uri in document.published - set(by_uri):
            by_uri[uri] = []  # cleared: no diagnostic there any more
        document.published = {uri for uri, found in by_uri.items() if found}
        for uri, found in by_uri.items():
            server.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=uri, diagnostics=found, version=version if uri == document.uri else None))

    def _diagnostic_uri(location: Location | None, analysis) -> str:
        if location is None or location.file == analysis.file:
            return documents_uri(analysis)
        if location.file.startswith("<"):
            return documents_uri(analysis)
        return uri_of(location.file)

    def documents_uri(analysis) -> str:
        for document in documents.values():
            if document.analysis is analysis or (
                    document.path and os.path.abspath(document.path) ==
                    os.path.abspath(analysis.file)):
                return document.uri
        return uri_of(analysis.file)

    def _lsp_diagnostic(kind: str, message: str, location: Location | None, analysis):
        severity = {"error": types.DiagnosticSeverity.Error,
                    "warning": types.DiagnosticSeverity.Warning}.get(
                        kind, types.DiagnosticSeverity.Information)
        if location is None:
            where = types.Range(start=types.Position(line=0, character=0),
                                end=types.Position(line=0, character=1))
        else:
            text = analysis.source_text(location.file) if analysis is not None else None
            where = lsp_range(location, knowledge.token_end(text, location))
        return types.Diagnostic(range=where, message=message, severity=severity, source="castor")

    worker = Worker(publish)

    def inside_workspace(path: str) -> bool:
        roots = state["roots"]
        if not roots:
            return True
        real = os.path.realpath(path)
        return any(real == root or real.startswith(root.rstrip(os.sep) + os.sep)
                   for root in roots)

    def open_document(uri: str, version: int, text: str, opening: bool = False) -> None:
        document = documents.get(uri)
        if document is None:
            path = to_fs_path(uri) if uri.startswith("file:") else None
            if path is not None and not inside_workspace(path):
                path = None
            document = documents[uri] = _Document(uri, path)
        document.version, document.text = version, text
        if state["loop"] is None:
            state["loop"] = asyncio.get_event_loop()
        if document.path is None:
            server.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=uri, diagnostics=[types.Diagnostic(
                    range=types.Range(start=types.Position(line=0, character=0),
                                      end=types.Position(line=0, character=0)),
                    message="castor analyses files of the workspace only; this document is "
                            "not one (open it from the folder of the scene)",
                    severity=types.DiagnosticSeverity.Information, source="castor")]))
            return
        if len(text) > MAX_BUFFER:
            _publish(document, None,
                     f"the buffer is {len(text) / 1e6:.1f} MB: too large to analyse while "
                     f"typing (at most {MAX_BUFFER / 1e6:g} MB); castor --check reads it",
                     version)
            return
        scenes = including_scenes(document)
        if not scenes:
            analyse_later(document)
            return
        # an included file is analysed as part of each scene that includes it,
        # with its unsaved text (as a C language server reads an unsaved header)
        for other in scenes:
            if not opening or other.analysis.source_text(_shown(document.path)) != text:
                analyse_later(other)

    def analyse_later(document: _Document) -> None:
        worker.submit(document, {other.path: other.text for other in documents.values()
                                 if other.path is not None and other is not document
                                 and len(other.text) <= MAX_BUFFER})

    def including_scenes(document: _Document) -> list[_Document]:
        """The open scenes whose last analysis #included this document's file: the
        file is analysed as part of them, with their macros and parameters, not alone."""
        if document.path is None:
            return []
        mine = os.path.realpath(document.path)
        return [other for other in documents.values()
                if other is not document and other.analysis is not None and any(
                    os.path.realpath(f) == mine for f in other.analysis.included)]

    def including_scene(document: _Document) -> _Document | None:
        scenes = including_scenes(document)
        return scenes[0] if scenes else None

    @server.feature(types.INITIALIZE)
    def initialize(ls, params: types.InitializeParams):
        roots = []
        for folder in params.workspace_folders or []:
            path = to_fs_path(folder.uri)
            if path:
                roots.append(os.path.realpath(path))
        if not roots and params.root_uri:
            path = to_fs_path(params.root_uri)
            if path:
                roots.append(os.path.realpath(path))
        state["roots"] = roots
        state["loop"] = asyncio.get_event_loop()

    @server.feature(types.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls, params: types.DidOpenTextDocumentParams):
        doc = params.text_document
        open_document(doc.uri, doc.version, doc.text, opening=True)

    @server.feature(types.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls, params: types.DidChangeTextDocumentParams):
        doc = ls.workspace.get_text_document(params.text_document.uri)
        open_document(params.text_document.uri, params.text_document.version, doc.source)

    @server.feature(types.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls, params: types.DidSaveTextDocumentParams):
        document = documents.get(params.text_document.uri)
        if document is None or document.path is None:
            return
        for other in list(documents.values()):  # the scenes that include it see the save
            if other is not document and other.analysis is not None and any(
                    os.path.realpath(f) == os.path.realpath(document.path)
                    for f in other.analysis.included):
                analyse_later(other)
        if including_scene(document) is None:
            analyse_later(document)  # the files it includes may have changed

    @server.feature(types.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls, params: types.DidCloseTextDocumentParams):
        document = documents.get(params.text_document.uri)
        if document is None:
            return
        scenes = including_scenes(document)
        documents.pop(params.text_document.uri)
        if scenes:  # its unsaved text is gone: the file on disk is the one included again
            for other in scenes:
                analyse_later(other)
            return
        for uri in document.published | {document.uri}:
            server.text_document_publish_diagnostics(
                types.PublishDiagnosticsParams(uri=uri, diagnostics=[]))

    def at(uri: str, pos: types.Position):
        """The analysis for a request, and the cursor as castor's (file, line, column)."""
        path = to_fs_path(uri) if uri.startswith("file:") else None
        document = documents.get(uri)
        analysis = None
        if document is not None:
            analysis = document.analysis
        if analysis is None:
            for other in documents.values():  # an included file: the scene that includes it
                if other.analysis is not None and path is not None and any(
                        os.path.abspath(f) == os.path.abspath(path)
                        for f in other.analysis.included):
                    analysis = other.analysis
        if analysis is None or path is None:
            return None, None
        file = analysis.file if document is not None and document.analysis is analysis \
            else _shown(path)
        return analysis, (file, pos.line + 1, pos.character + 1)

    def location_of(location: Location, end: int | None = None) -> types.Location:
        return types.Location(uri=_location_uri(location),
                              range=lsp_range(location, end or location.column + 1))

    def _location_uri(location: Location) -> str:
        for document in documents.values():
            if document.analysis is not None and document.analysis.file == location.file:
                return document.uri
        return uri_of(location.file)

    figures_lock = threading.Lock()

    def figures(analysis, name: str):
        """An object's box and volume, made once per analysis (one at a time: the
        facetizer's caches are shared)."""
        from castor.lsp.evaluate import object_figures

        with figures_lock:
            cache = analysis.__dict__.setdefault("figures", {})
            if name not in cache:
                cache[name] = object_figures(analysis, name)
            return cache[name]

    @server.feature(types.TEXT_DOCUMENT_HOVER)
    @server.thread()  # an object's figures may take a while: the protocol goes on
    def hover(ls, params: types.HoverParams):
        analysis, cursor = at(params.text_document.uri, params.position)
        if analysis is None:
            return None
        found = knowledge.hover(analysis, *cursor, figures=figures)
        if found is None or found[0] is None:
            return None
        text, word = found
        return types.Hover(
            contents=types.MarkupContent(kind=types.MarkupKind.PlainText, value=text),
            range=types.Range(start=types.Position(line=word.line - 1, character=word.start - 1),
                              end=types.Position(line=word.line - 1, character=word.end - 1)))

    @server.feature(types.TEXT_DOCUMENT_DEFINITION)
    def definition(ls, params: types.DefinitionParams):
        analysis, cursor = at(params.text_document.uri, params.position)
        if analysis is None:
            return None
        source = None
        places = knowledge.definition(analysis, *cursor)
        out = []
        for place in places:
            source = analysis.source_text(place.file)
            out.append(location_of(place, knowledge.token_end(source, place)))
        return out or None

    @server.feature(types.TEXT_DOCUMENT_REFERENCES)
    def references(ls, params: types.ReferenceParams):
        analysis, cursor = at(params.text_document.uri, params.position)
        if analysis is None:
            return None
        found = knowledge.references(analysis, *cursor,
                                     declaration=params.context.include_declaration)
        return [location_of(place, end) for place, end in found] or None

    kinds = {"primitive": types.CompletionItemKind.Function,
             "transform": types.CompletionItemKind.Function,
             "boolean": types.CompletionItemKind.Operator,
             "parameter": types.CompletionItemKind.Variable,
             "object": types.CompletionItemKind.Class,
             "macro": types.CompletionItemKind.Constant}

    @server.feature(types.TEXT_DOCUMENT_COMPLETION,
                    types.CompletionOptions(trigger_characters=["!", "@", "$"]))
    def completion(ls, params: types.CompletionParams):
        uri = params.text_document.uri
        document = documents.get(uri)
        text = document.text if document is not None else ""
        analysis = document.analysis if document is not None else None
        file = analysis.file if analysis is not None else ""
        items = knowledge.completions(analysis, text, file, params.position.line + 1,
                                      params.position.character + 1)
        snippets = _snippets(ls)
        return types.CompletionList(is_incomplete=False, items=[
            types.CompletionItem(
                label=c.label, kind=kinds[c.kind], detail=c.detail,
                documentation=c.documentation or None,
                insert_text=c.snippet if snippets and c.snippet else c.insert,
                insert_text_format=types.InsertTextFormat.Snippet if snippets and c.snippet
                else types.InsertTextFormat.PlainText)
            for c in items])

    symbol_kinds = {"parameter": types.SymbolKind.Constant, "object": types.SymbolKind.Object,
                    "frame": types.SymbolKind.Event}

    @server.feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def document_symbol(ls, params: types.DocumentSymbolParams):
        analysis, cursor = at(params.text_document.uri, types.Position(line=0, character=0))
        if analysis is None:
            return []
        out = []
        for s in knowledge.symbols(analysis, cursor[0]):
            whole = lsp_range(s.location, s.end)
            out.append(types.DocumentSymbol(name=s.name, kind=symbol_kinds[s.kind], range=whole,
                                            selection_range=whole, detail=s.detail))
        return out

    @server.feature(types.SHUTDOWN)
    def shutdown(ls, params):
        worker.stop()

    return server


def _snippets(ls) -> bool:
    """Whether the client fills in snippets (the vocabulary's arguments as placeholders)."""
    try:
        return bool(ls.client_capabilities.text_document.completion.completion_item
                    .snippet_support)
    except AttributeError:
        return False


def main(args=None) -> int:
    """Serve one client on standard input and output until it says exit."""
    import logging

    logging.basicConfig(level=logging.CRITICAL, stream=sys.stderr)  # nothing on the pipe
    from castor.pipeline import RECURSION_LIMIT

    sys.setrecursionlimit(RECURSION_LIMIT)
    try:
        server = _server()
    except ImportError as exc:
        sys.stderr.write(f"castor: error: --lsp needs pygls and lsprotocol ({exc.name} is "
                         f"missing): pip install 'castor[lsp]'\n")
        return 2
    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # a stray print must never corrupt the protocol's stream
    try:
        server.start_io(stdin, stdout)
    except KeyboardInterrupt:
        pass
    return 0

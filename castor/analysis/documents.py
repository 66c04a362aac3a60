"""An editor's open buffers, the scenes they are part of, and their analyses.

Each buffer of a ``*.cas`` file of the workspace is analysed as ``castor --check``
would analyse it, with the other open buffers read instead of their files. A
part that a scene ``#include``s is never analysed alone: it is analysed as part
of that scene (an open one whose last analysis included it, else the scene at
the top of the workspace's ``#include`` chains, castor.analysis.workspace,
analysed from its file as a hidden document). Documents are named by an
opaque ``key`` (the client's URI) and carry their file's path.

Threads: the worker (castor.analysis.worker) analyses; every other method runs
on the caller's one thread (the protocol's), ``finished`` included.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Callable

from castor.analysis.worker import Submission, Worker

# a buffer larger than this is not analysed while typing (castor --check reads it)
MAX_BUFFER = 4_000_000


@dataclass(eq=False)
class Document:
    key: str
    path: str | None  # None: not a file of the workspace, not analysed
    version: int = 0
    text: str = ""
    analysis: object = None  # the last finished castor.analysis.scene.Analysis
    published: set[str] = field(default_factory=set)  # keys given diagnostics
    open: bool = True  # False: a scene analysed for a part of it that is open
    scene: Document | None = None  # the scene this part is analysed with
    analysed: bool = False  # an analysis (or a problem) has come for it

    def includes(self, path: str) -> bool:
        mine = os.path.realpath(path)
        return self.analysis is not None and any(
            os.path.realpath(f) == mine for f in self.analysis.included)


def _real(path: str) -> str:
    return os.path.realpath(path)


class Documents:
    """The open documents; ``finished(document, analysis, problem, version)``
    is called from the worker's thread with each analysis that is not stale."""

    def __init__(self, finished: Callable, key_of: Callable[[str], str]):
        from castor.analysis.scene import analyse_buffers
        from castor.pipeline import STACK_BYTES

        self.key_of = key_of  # the key of a file's path (its URI)
        self.documents: dict[str, Document] = {}
        self.roots: list[str] = []
        self.worker = Worker(lambda submission, cancelled: analyse_buffers(
            submission.text, submission.name, submission.unsaved, cancelled),
            lambda submission, analysis, problem: finished(submission.payload, analysis, problem,
                                                           submission.version),
            STACK_BYTES)

    # --- which documents
    def get(self, key: str) -> Document | None:
        return self.documents.get(key)

    def inside_workspace(self, path: str) -> bool:
        if not self.roots:
            return True
        real = _real(path)
        return any(real == root or real.startswith(root.rstrip(os.sep) + os.sep)
                   for root in self.roots)

    def scenes_of(self, document: Document) -> list[Document]:
        """The scenes this document is analysed as part of (none: it is a scene)."""
        if document.path is None:
            return []
        found = [other for other in self.documents.values()
                 if other is not document and other.includes(document.path)]
        if not found and document.scene is not None and \
                self.documents.get(document.scene.key) is document.scene:
            found = [document.scene]
        return found

    def parts_of(self, scene: Document) -> list[Document]:
        """The open documents analysed as part of ``scene``."""
        return [other for other in self.documents.values()
                if other.open and other is not scene and self.owner(other) is scene]

    def owner(self, document: Document) -> Document:
        """The document whose analysis answers for this one."""
        scenes = self.scenes_of(document)
        return scenes[0] if scenes else document

    # --- changes from the editor
    def opened(self, key: str, path: str | None, version: int, text: str,
               opening: bool = False) -> tuple[Document, str | None]:
        """A buffer's new text; the document and why it is not analysed, if so."""
        document = self.documents.get(key)
        if document is None or not document.open:
            if path is not None and not self.inside_workspace(path):
                path = None
            hidden = document
            document = self.documents[key] = Document(key, path)
            if hidden is not None:  # the editor opens a scene analysed for its part
                document.published, document.analysis = hidden.published, hidden.analysis
                for other in self.documents.values():
                    if other.scene is hidden:
                        other.scene = document
        document.version, document.text = version, text
        if document.path is None:
            return document, ("castor analyses files of the workspace only; this document is "
                              "not one (open it from the folder of the scene)")
        if len(text) > MAX_BUFFER:
            return document, (f"the buffer is {len(text) / 1e6:.1f} MB: too large to analyse "
                              f"while typing (at most {MAX_BUFFER / 1e6:g} MB); castor --check "
                              f"reads it")
        self._analyse_with_scenes(document, opening)
        return document, None

    def _analyse_with_scenes(self, document: Document, opening: bool) -> None:
        scenes = self.scenes_of(document)
        if not scenes and opening:
            scenes = self._workspace_scene(document)
        if not scenes:
            self.analyse_later(document)
            return
        # a part is analysed as part of each scene that includes it, with its
        # unsaved text (as a C language server reads an unsaved header)
        for scene in scenes:
            if not opening or scene.analysis is None or \
                    scene.analysis.source_text(_shown(document.path)) != document.text:
                self.analyse_later(scene)

    def _workspace_scene(self, document: Document) -> list[Document]:
        """The scene of the workspace that includes this part, as a hidden document."""
        from castor.analysis.workspace import scenes_including

        roots = self.roots or [os.path.dirname(os.path.dirname(_real(document.path)))]
        found = scenes_including(document.path, roots)
        if not found:
            return []
        key = self.key_of(found[0])
        scene = self.documents.get(key)
        if scene is None:
            scene = self.documents[key] = Document(key, found[0], open=False)
        document.scene = scene
        return [scene]

    def saved(self, key: str) -> None:
        document = self.documents.get(key)
        if document is None or document.path is None:
            return
        scenes = self.scenes_of(document)
        for scene in scenes:  # the scenes that include it see the save
            self.analyse_later(scene)
        if not scenes:
            self.analyse_later(document)  # the files it includes may have changed

    def closed(self, key: str) -> set[str]:
        """The keys whose diagnostics are to be cleared."""
        document = self.documents.get(key)
        if document is None:
            return set()
        if self._has_open_part(document):  # still the scene of an open part
            document.open, document.text = False, ""
            self.analyse_later(document)
            return set()
        scenes = self.scenes_of(document)
        del self.documents[key]
        if not scenes:
            return document.published | {document.key}
        cleared: set[str] = set()
        for scene in scenes:  # its unsaved text is gone: the file is included again
            if scene.open or self._has_open_part(scene):
                self.analyse_later(scene)
            else:
                del self.documents[scene.key]
                cleared |= scene.published | {scene.key}
        return cleared

    def _has_open_part(self, scene: Document) -> bool:
        return any(other.open and other is not scene and (
            other.scene is scene or (other.path and scene.includes(other.path)))
            for other in self.documents.values())

    def analyse_later(self, document: Document) -> None:
        text = document.text
        if not document.open:  # a hidden scene: its file as it is now
            try:
                with open(document.path, encoding="utf-8", errors="replace") as handle:
                    text = handle.read()
            except OSError:
                text = ""
        unsaved = {other.path: other.text for other in self.documents.values()
                   if other.path is not None and other is not document and other.open
                   and len(other.text) <= MAX_BUFFER}
        self.worker.submit(Submission(document.key, text, document.path, document.version, unsaved,
                               payload=document))

    def stop(self) -> None:
        self.worker.stop()


def _shown(path: str) -> str:
    from castor.analysis.scene import shown_name

    return shown_name(path)

"""The live preview of an editor's buffers (``castor --lsp --serve``): the
same page and server as ``castor --serve``, but the scene's text is the
buffer the editor sends the language server, unsaved, and the files it
includes are read from the other open buffers (castor.language.preprocess.
unsaved), so that the preview follows the buffer, not the file.
"""

from __future__ import annotations

from dataclasses import replace

from castor.serve.evaluation import Evaluation, Watched, evaluate
from castor.serve.server import Preview
from castor.settings import ReadSettings, Source


class BufferPreview(Preview):
    """A Preview whose scene is a text given by ``follow``."""

    def __init__(self, reading: ReadSettings = ReadSettings(), path: str | None = None):
        text = ""
        if path is not None:
            try:
                with open(path, encoding="utf-8", errors="replace", newline="") as handle:
                    text = handle.read()
            except OSError:
                text = ""
        super().__init__(Watched(Source(text=text, name=path or "<scene>"), reading,
                                 quiet=True))
        self.path = path
        self.buffers: dict[str, str] = {}  # path -> an open buffer's text

    def follow(self, path: str, text: str, buffers: dict[str, str]) -> None:
        """The scene is now ``text`` (the file ``path``), with these buffers
        read in place of their files: evaluate it again."""
        with self.state:
            if path == self.path and text == self.job.source.text and buffers == self.buffers:
                return
            self.path = path
            self.job = replace(self.job, source=Source(text=text, name=path))
            self.buffers = dict(buffers)
            self._wanted += 1
            self.state.notify_all()

    def _stop_stale(self) -> None:
        """A newer text stops the evaluation under way between statements only,
        never mid-statement: the language server's worker evaluates on another
        thread at the same time, and a stop raised inside an import (a module
        imported on first use) leaves importlib's lock of that module held, so
        that the other thread waits for it forever."""

    def evaluation(self, job: Watched, stale, facets=None) -> Evaluation:
        from castor.language.preprocess import unsaved

        with unsaved(self.buffers):
            return evaluate(job, stale, facets)


def warm() -> None:
    """Import what an evaluation imports on first use, here, before the
    preview's thread and the language server's worker both do at once."""
    evaluate(Watched(Source(text="> @t(1, 0, 0) $U(!cu(1, 1, 1), !cy(1, 1, 1));\n",
                            name="<warm>"), quiet=True))

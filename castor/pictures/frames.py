"""The evaluated frames of a scene text, for tests, benchmarks and scripts
that draw pictures without the command line."""

from __future__ import annotations


def scene_frames(text: str, name: str = "<scene>", defines: tuple[str, ...] = ()) -> list:
    """Every frame (castor.csg.tree.Frame) of the scene ``text``, preprocessed."""
    import io

    from castor.diagnostics import Reporter
    from castor.interpreter import Interpreter, Settings
    from castor.language.preprocess import preprocess
    from castor.language.reader import Reader

    reporter = Reporter(io.StringIO())
    frames: list = []
    interpreter = Interpreter(Settings(), reporter, frames.append)
    text = preprocess([(name, text)], list(defines), [], [], reporter)
    interpreter.run(Reader(reporter, directives_allowed=True).chunks(text.splitlines()),
                    streaming=False)
    if reporter.errors:
        raise ValueError(reporter.stream.getvalue())
    return frames

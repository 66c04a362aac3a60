"""Frames that could not be made, said once (CLI.md: "The same error reported
for several frames of one '>[T = …]' command … is printed once, with the
frames or the count it concerns"): frames whose process failed alike
(``FrameFailure``), frames that met the same error while they were made
(``SameError``, as over --max-polygons). castor.run holds each such failure
while the frames after it fail alike, and says it once."""

from __future__ import annotations

import os

from castor.diagnostics import CastorError, LimitError, counted


class FrameFailure(LimitError):
    """Frames that could not be made (their process failed), alike: one message
    names them all (CLI.md)."""

    def __init__(self, numbers: tuple[int, ...], reason: str, location):
        self.numbers, self.reason = numbers, reason
        super().__init__(f"{counted('frame', numbers)} could not be made: {reason}", location)

    def alike(self, other) -> bool:
        return isinstance(other, FrameFailure) and \
            (self.reason, self.location) == (other.reason, other.location)

    def joined(self, other: "FrameFailure") -> "FrameFailure":
        return FrameFailure(self.numbers + other.numbers, self.reason, self.location)

    def said(self) -> CastorError:
        return self


class SameError:
    """One error that frames one after another met alike (the same words at the
    same place): said once, with the frames it concerns, as the interpreter says
    an error found in several frames of one '>' command."""

    def __init__(self, error: CastorError, numbers: tuple[int, ...]):
        self.error, self.numbers = error, numbers

    def alike(self, other) -> bool:
        return isinstance(other, SameError) and type(other.error) is type(self.error) and \
            (other.error.message, other.error.location) == (self.error.message, self.error.location)

    def joined(self, other: "SameError") -> "SameError":
        return SameError(self.error, self.numbers + other.numbers)

    def said(self) -> CastorError:
        if len(self.numbers) == 1:
            return self.error
        import copy

        error = copy.copy(self.error)
        error.message = f"{error.message} (in {counted('frame', list(self.numbers))})"
        return error


def failure_reason(exc: BaseException) -> str:
    """Why a frame's process failed, in the user's words: never Python's (its
    name and text with CASTOR_DEBUG=1)."""
    name = type(exc).__name__
    if name == "BrokenProcessPool":
        reason = "its process ended before it was done (stopped, or out of memory)"
    elif isinstance(exc, (OSError, TimeoutError)) or name in ("CancelledError", "CommClosedError"):
        reason = "the process or cluster that was making it stopped answering"
    else:
        reason = ("an internal error in the process that made it (please report it with "
                  "the scene; CASTOR_DEBUG=1 shows it)")
    if os.environ.get("CASTOR_DEBUG"):
        reason += f" [{name}: {exc}]"
    return reason

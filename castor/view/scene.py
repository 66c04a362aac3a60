"""What castor-view draws: frames of coloured convex polygons, read from a
polygon stream as it arrives (castor.formats.cps.load), or from a file through
the reader its format declares in the registry (castor.formats)."""

from __future__ import annotations

from typing import Iterator

from castor.formats.cps import StreamError, StreamFrame, load

# the stream's reader lives beside its writer
ViewError = StreamError
Picture = StreamFrame
read_stream = load


def readable_suffixes(streams: bool = True) -> list[str]:
    """The endings of the files of polygons castor-view reads (the stream's too,
    with ``streams``)."""
    from castor.formats import registry

    suffixes: list[str] = []
    for f in registry().values():
        if f.read is not None and f.kind.polygons and (streams or not f.kind.streamed):
            suffixes.extend(s for s in f.suffixes + f.reads_also if s not in suffixes)
    return suffixes


def read_file(path: str) -> Iterator[Picture]:
    """The frames of a file, read by its format's reader (z up, scene units)."""
    from castor.formats import reader_for

    chosen = reader_for(path)
    if chosen is None:
        raise ViewError(f"'{path}': castor-view reads {' '.join(readable_suffixes())} files")
    yield from chosen.read(path)


def read_mesh_file(path: str) -> Picture:
    """A mesh file as one frame."""
    return next(iter(read_file(path)))

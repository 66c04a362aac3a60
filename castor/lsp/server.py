"""``castor --lsp``: the language server on standard input and output.

The protocol is castor.lsp.protocol's ``CastorServer`` (pygls), one method per
request; what it answers comes from castor.analysis. pygls and lsprotocol are
imported here, when ``--lsp`` asks for them, never at castor's start-up.
"""

from __future__ import annotations

import sys


def main(args=None) -> int:
    """Serve one client on standard input and output until it says exit."""
    import logging

    logging.basicConfig(level=logging.CRITICAL, stream=sys.stderr)  # nothing on the pipe
    from castor.pipeline import RECURSION_LIMIT

    sys.setrecursionlimit(RECURSION_LIMIT)
    try:
        from castor.lsp.protocol import CastorServer

        server = CastorServer()
    except ImportError as exc:
        sys.stderr.write(f"castor: error: --lsp needs pygls and lsprotocol ({exc.name} is "
                         f"missing): pip install pygls lsprotocol\n")
        return 2
    if args is not None and getattr(args, "serve", False):
        status = _serve_preview(server, args)
        if status:
            return status
    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # a stray print must never corrupt the protocol's stream
    try:
        server.start_io(stdin, stdout)
    except KeyboardInterrupt:
        pass
    finally:
        server.documents.stop()
        server.stop_preview()
    return 0


def _serve_preview(server, args) -> int:
    """``castor --lsp --serve``: the live preview of the buffers (castor.lsp.editing);
    0, or the usage error's status when it cannot listen."""
    from castor.settings import ReadSettings

    files = [f for f in getattr(args, "files", []) or [] if f != "-"]
    if len(files) > 1:
        sys.stderr.write("castor: error: --lsp --serve previews one scene (or the one being "
                         "edited): give at most one file\n")
        return 2
    reading = ReadSettings(tuple(args.defines or ()), tuple(args.undefines or ()),
                           tuple(args.include_dirs or ()), bool(args.no_cpp))
    try:
        server.serve_preview(reading, args.bind, args.port, files[0] if files else None)
    except OSError as exc:
        sys.stderr.write(f"castor: error: cannot listen on {args.bind} port {args.port}: "
                         f"{exc.strerror or exc}\n")
        return 2
    return 0

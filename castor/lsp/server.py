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
    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # a stray print must never corrupt the protocol's stream
    try:
        server.start_io(stdin, stdout)
    except KeyboardInterrupt:
        pass
    finally:
        server.documents.stop()
    return 0

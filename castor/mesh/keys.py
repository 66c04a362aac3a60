"""Content keys of the engine's solids: what a boolean of the same operands,
met again (the next frame, a slider's next value), gives without the engine.

A part of a solid (castor.mesh.solid) has a key when what it is follows
from content alone: a placed primitive's key is its engine ID and matrix; a
part moved by a matrix, the part's key and the matrix; a boolean's result,
the operation and its operands' keys, in order. The engine is deterministic:
the same operands, in the same order, under the same IDs, give the same
result, which the boolean caches keep (caches.PROCESS.booleans) and give
again as it was computed. A part whose key is not known (renamed runs,
composed parts, smooth solids) is None, and its booleans go to the engine.
"""

from __future__ import annotations

import numpy as np


def digest(*pieces) -> bytes:
    """16 bytes that stand for ``pieces`` (bytes, or arrays)."""
    try:  # hashlib's own BLAKE2, without hashlib's 16 ms of OpenSSL set-up at start
        from _blake2 import blake2b
    except ImportError:
        from hashlib import blake2b

    made = blake2b(digest_size=16)
    for piece in pieces:
        made.update(piece if isinstance(piece, bytes) else np.ascontiguousarray(piece).data)
    return made.digest()


def placed(id: int, matrix: np.ndarray) -> bytes:
    """A placed primitive's key: its engine ID (the template's, or its own) and matrix."""
    return digest(b"P", int(id).to_bytes(8, "little", signed=True),
                  np.asarray(matrix, dtype=np.float64))


def derived(operation: bytes, keys, extra: bytes = b"") -> bytes | None:
    """The key of what ``operation`` makes of parts whose keys are ``keys``
    (None if one is not known)."""
    if any(key is None for key in keys):
        return None
    return digest(operation, *keys, extra)

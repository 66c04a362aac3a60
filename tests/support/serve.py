"""The live preview's server asked over HTTP: its answers, the frames' triangles
and their volume, and waiting for a condition (never for a time)."""

from __future__ import annotations

import http.client
import json
import socket
import time

import numpy as np


def wait_for(condition, seconds: float = 10.0):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.02)
    raise AssertionError("timed out")


def newer(port: int, version: int) -> dict:
    """The preview's scene once its version is past ``version`` (an evaluation
    after a save, or a value changed)."""
    return wait_for(lambda: (a := get(port, "/scene.json")[2])["version"] > version and a)


def get(port: int, path: str, headers: dict | None = None):
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    connection.request("GET", path, headers=headers or {})
    answer = connection.getresponse()
    body = answer.read()
    connection.close()
    content = json.loads(body) if answer.getheader("Content-Type") == "application/json" else body
    return answer.status, answer.getheader("Content-Type"), content


def raw(port: int, target: str, host: str = "127.0.0.1") -> tuple[int, bytes]:
    """Send a request line exactly as written (no client tidies the path)."""
    with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
        s.sendall(f"GET {target} HTTP/1.0\r\nHost: {host}\r\n\r\n".encode())
        data = b""
        while chunk := s.recv(65536):
            data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    return int(head.split()[1]), body


def triangles(data: bytes, count: int) -> np.ndarray:
    return np.frombuffer(data[:count * 36], dtype="<f4").reshape(count, 3, 3).astype(float)


def volume(tris: np.ndarray) -> float:
    return float(np.einsum("ij,ij->i", tris[:, 0], np.cross(tris[:, 1], tris[:, 2])).sum() / 6)

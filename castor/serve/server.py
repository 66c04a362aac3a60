"""The live preview's web server: the page, the current frames, and events.

Routes (anything else is 404; no path of the disk is ever looked up):

- ``/``, ``/viewer.js``, ``/style.css``: the page, read from the package once;
- ``/scene.json``: the frames' descriptions, the diagnostics, the state;
- ``/frames/ID/N.bin``: frame N of the frames numbered ID, as triangles;
- ``/events``: server-sent events, one each time the state changes;
- ``/editing.js``, ``/editing.json``, ``POST /gesture``: editing on screen
  (castor.serve.gestures);
- ``POST /camera``: the page's camera, once it stops (castor.serve.camera):
  the frames are faceted again for it, without evaluating.

Threads: one evaluates or facets again for a new camera (cancelled when a
newer save overtakes it), one polls
the files, one accepts connections, and at most MAX_REQUESTS serve them (of
which at most MAX_STREAMS hold an event stream open).
"""

from __future__ import annotations

import errno
import json
import re
import secrets
import signal
import socket
import socketserver
import sys
import threading
import time
from dataclasses import dataclass, replace
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources

from castor.diagnostics import UsageError
from castor.serve.evaluation import (Diagnostic, DrawnFrame, Evaluation, Facets, Overtaken,
                                     Watched, evaluate, refaceted)
from castor.serve.watch import Watcher

POLL_SECONDS = 0.05  # how often the files are looked at
SETTLE_SECONDS = 0.02  # after a change, for the editor to finish writing
SETTLE_PATIENCE = 0.5  # at most, while the files change or one is empty
HEARTBEAT_SECONDS = 5.0  # a comment on each event stream, to find browsers gone
REQUEST_TIMEOUT = 10.0  # seconds a connection may stay silent
MAX_REQUESTS = 48
MAX_STREAMS = 16
PORTS_TRIED = 50

_STATIC = {"/": ("index.html", "text/html; charset=utf-8"),
           "/viewer.js": ("viewer.js", "text/javascript; charset=utf-8"),
           "/style.css": ("style.css", "text/css; charset=utf-8"),
           "/editing.js": ("editing.js", "text/javascript; charset=utf-8")}
_FRAME = re.compile(r"/frames/(\d{1,9})/(\d{1,9})\.bin")
_LOOPBACK_HOSTS = {"localhost", "127.0.0.1", "[::1]"}
_HEADERS = {
    "Cache-Control": "no-store",
    "X-Content-Type-Options": "nosniff",
    "Referrer-Policy": "no-referrer",
    "Content-Security-Policy": "default-src 'none'; script-src 'self'; style-src 'self'; "
                               "connect-src 'self'; img-src 'self' data:; "
                               "frame-ancestors 'none'; base-uri 'none'; form-action 'none'",
}


@dataclass(frozen=True)
class Snapshot:
    """What the page is shown: frames (perhaps the last good ones) and diagnostics."""

    version: int = 0
    frames_id: int = 0
    frames: tuple[DrawnFrame, ...] = ()
    diagnostics: tuple[Diagnostic, ...] = ()
    stale: bool = False  # the frames are the last good ones, not this evaluation's
    evaluated: bool = False  # an evaluation has finished
    seconds: float = 0.0
    finished: float = 0.0  # time.time() at the end of the evaluation
    files: tuple[str, ...] = ()
    refaceted: float | None = None  # seconds of the refacet for the page's camera, if the last

    def as_json(self, server: str, evaluating: bool, faceting: bool = False) -> bytes:
        return json.dumps({
            "server": server, "version": self.version, "evaluating": evaluating,
            "faceting": faceting, "evaluated": self.evaluated,
            "stale": self.stale, "seconds": round(self.seconds, 4),
            "refaceted": None if self.refaceted is None else round(self.refaceted, 4),
            "finished": time.strftime("%H:%M:%S", time.localtime(self.finished))
                        if self.finished else None,
            "files": list(self.files), "diagnostics": [d.as_json() for d in self.diagnostics],
            "frames": [dict(f.as_json(), url=f"/frames/{self.frames_id}/{i}.bin")
                       for i, f in enumerate(self.frames)],
        }).encode()


class Preview:
    """The scene's current state, kept up to date with the files on disk."""

    def __init__(self, job: Watched, report=None):
        self.job = job
        self.report = report  # called with each Evaluation (to print on stderr)
        # versions count from 1 again when castor is started again: a page that
        # outlived a server knows by this name that the versions are new ones
        self.name = secrets.token_hex(6)
        self.snapshot = Snapshot(files=job.files)
        self.evaluating, self.faceting = True, False  # faceting: a refacet, nothing evaluated
        self.state = threading.Condition()
        self.stop = threading.Event()
        self._wanted = 1  # evaluations asked for (the first, then one per save)
        self._looked = 0  # cameras the page has sent (each asks to facet again)
        self._looked_done = 0  # of which the frames shown are faceted for the latest
        self._camera = None  # the page's latest (castor.pictures.camera.Camera)
        self._good: Evaluation | None = None  # the evaluation whose frames are shown
        self._last_good: tuple[int, tuple[DrawnFrame, ...]] | None = None
        self._frames_ids = 0
        self._watcher = Watcher(job.files)
        self._watcher_lock = threading.Lock()
        from castor.analysis.worker import Stopper

        self._stopper = Stopper()  # stops a stale evaluation at once, mid-statement too
        from castor.serve.parameters import Panel

        self.panel = Panel(job.files, job.evaluation, job.reading)

    def apply(self, overrides: dict[str, float], tolerance: float | None) -> None:
        """Evaluate again with the panel's values, as --set gives them."""
        from dataclasses import replace

        from castor.settings import EvaluationSettings

        with self.state:
            self.job = replace(self.job, evaluation=EvaluationSettings(overrides=overrides,
                                                                       tolerance=tolerance))
            self._wanted += 1
            self.state.notify_all()
        self._stop_stale()

    def look(self, camera, seconds: float = 0.0) -> int:
        """The page's camera has stopped at ``camera``: facet the frames for it
        (every later evaluation too). Waits at most ``seconds`` for the frames
        faceted for it to be shown; the version then shown."""
        with self.state:
            self._camera = camera
            self._looked += 1
            number = self._looked
            self.state.notify_all()
            self.state.wait_for(lambda: self._looked_done >= number or self.stop.is_set(),
                                seconds)
            return self.snapshot.version

    def _facets(self) -> Facets:
        """How this evaluation or refacet facets the frames: for the latest
        camera, keeping what the shown frames were faceted from where close."""
        good = self._good
        return Facets(self._camera, good.faceted if good is not None else None)

    def _stop_stale(self) -> None:
        """Stop the evaluation under way if a newer one is wanted."""
        self._stopper.stop(lambda generation: generation != self._wanted or self.stop.is_set())

    def state_key(self) -> tuple[int, bool, bool]:
        return self.snapshot.version, self.evaluating, self.faceting

    def watch_files(self) -> None:
        """Poll the files until stopped; a change asks for a new evaluation."""
        while not self.stop.wait(POLL_SECONDS):
            with self._watcher_lock:
                changed = self._watcher.changed()
            if not changed:
                continue
            if self._watcher.settle(self.stop.wait, self._watcher_lock, SETTLE_SECONDS,
                                    SETTLE_PATIENCE):
                return
            with self.state:
                self._wanted += 1
                self.state.notify_all()
            self._stop_stale()

    def evaluate_scene(self) -> None:
        """Evaluate whenever asked, until stopped; an evaluation overtaken by a newer
        save or value stops at once (castor.analysis.worker.Stopper), mid-statement
        too, and is thrown away. A new camera alone facets the shown frames again."""
        done = looked = 0
        while True:
            with self.state:
                while (self._wanted == done and self._looked == looked
                       and not self.stop.is_set()):
                    self.state.wait(0.5)
                if self.stop.is_set():
                    return
                generation, looked = self._wanted, self._looked
                facets = self._facets()
                if generation == done and self._good is None:
                    self._looked_done = looked  # nothing shown to facet again yet
                    self.state.notify_all()
                    continue
                if (self.evaluating, self.faceting) != (True, generation == done):
                    self.evaluating, self.faceting = True, generation == done
                    self.state.notify_all()
            started_ns = time.time_ns()
            stale = lambda: self._wanted != generation or self.stop.is_set()  # noqa: E731
            try:
                self._stopper.begin(generation)
                try:
                    if stale():  # asked for again before begin(): not stopped
                        raise Overtaken()
                    if generation == done:
                        self._publish_refaceted(refaceted(self._good, facets, stale), looked)
                        continue
                    result = self.evaluation(self.job, stale, facets)
                finally:
                    self._stopper.end()
            except Overtaken:
                continue
            except Exception as exc:  # castor's bug: said on the page, the server lives on
                message = f"internal error: {type(exc).__name__}: {exc} (please report it)"
                result = Evaluation((), (Diagnostic("error", message),), (), 0.0,
                                    f"castor: {message}\n")
            done = generation
            with self._watcher_lock:
                self._watcher.watch(self.job.files + result.included, since_ns=started_ns)
            self._publish(result, self._wanted != generation, looked)
            if self.report is not None:
                self.report(result)

    def evaluation(self, job: Watched, stale, facets: Facets | None = None) -> Evaluation:
        """One evaluation of the scene (castor.serve.buffers reads an editor's buffers)."""
        return evaluate(job, stale, facets)

    def _publish_refaceted(self, result: Evaluation, looked: int) -> None:
        """The shown frames faceted again: a new version where any changed."""
        with self.state:
            old = self.snapshot
            if self._good is not None and any(a is not b for a, b in zip(result.frames,
                                                                          self._good.frames)):
                self._frames_ids += 1
                self._last_good = (self._frames_ids, result.frames)
                self.snapshot = replace(old, version=old.version + 1,
                                        frames_id=self._frames_ids, frames=result.frames,
                                        refaceted=result.seconds)
            self._good = result
            self._looked_done = looked
            self.evaluating = self.faceting = False
            self.state.notify_all()

    def _publish(self, result: Evaluation, overtaken: bool, looked: int = 0) -> None:
        with self.state:
            old = self.snapshot
            if result.errors == 0 or self._last_good is None:
                self._frames_ids += 1
                frames_id, frames, stale = self._frames_ids, result.frames, False
                if result.errors == 0:
                    self._last_good = (frames_id, frames)
                    self._good = result
            else:
                (frames_id, frames), stale = self._last_good, True
            shown = tuple(dict.fromkeys(self.job.files + result.included))
            self.snapshot = Snapshot(old.version + 1, frames_id, frames, result.diagnostics,
                                     stale, True, result.seconds, time.time(), shown)
            self.evaluating, self.faceting = overtaken, False
            self._looked_done = max(self._looked_done, looked)
            self.state.notify_all()

    def close(self) -> None:
        self.stop.set()
        with self.state:
            self.state.notify_all()
        self._stop_stale()


class _Handler(BaseHTTPRequestHandler):
    server_version = "castor"
    protocol_version = "HTTP/1.0"
    timeout = REQUEST_TIMEOUT
    server: "_Server"

    def log_message(self, format, *args):  # noqa: A002 - the base class's name
        pass  # a request log on the terminal would bury the scene's errors

    def do_HEAD(self):
        self._answer(head=True)

    def do_GET(self):
        self._answer(head=False)

    def _answer(self, head: bool) -> None:
        if not self._host_allowed():
            self._send(403, b"unknown host\n", "text/plain; charset=utf-8", head)
            return
        path = self.path.partition("?")[0]  # never unquoted: only exact names match
        preview = self.server.preview
        if path in _STATIC:
            name, kind = _STATIC[path]
            self._send(200, self.server.pages[name], kind, head)
        elif path == "/scene.json":
            with preview.state:
                snapshot, busy = preview.snapshot, preview.state_key()[1:]
            self._send(200, snapshot.as_json(preview.name, *busy), "application/json", head)
        elif path == "/parameters.json":
            self._send(200, json.dumps(preview.panel.as_json()).encode(), "application/json",
                       head)
        elif path == "/editing.json":
            from castor.serve.gestures import description

            self._send(200, description(self.server.gestures), "application/json", head)
        elif path == "/events" and not head:
            self._events()
        elif match := _FRAME.fullmatch(path):
            snapshot = preview.snapshot
            number = int(match[2])
            if int(match[1]) == snapshot.frames_id and number < len(snapshot.frames):
                self._send(200, snapshot.frames[number].data, "application/octet-stream", head)
            else:
                self._send(404, b"no such frame (the scene has changed)\n",
                           "text/plain; charset=utf-8", head)
        else:
            self._send(404, b"not found\n", "text/plain; charset=utf-8", head)

    def do_POST(self):
        """``/parameters``: a change from the parameters panel (castor.serve.parameters)."""
        from castor.serve.parameters import PanelError

        if not self._host_allowed() or not self._same_origin():
            self._send(403, b"unknown host\n", "text/plain; charset=utf-8", False)
            return
        kind = self.headers.get("Content-Type", "").partition(";")[0].strip().lower()
        length = self.headers.get("Content-Length", "")
        if self.path == "/gesture":
            self._gesture(kind, length)
            return
        if self.path == "/camera":
            self._camera(kind, length)
            return
        if self.path != "/parameters":
            self._send(404, b"not found\n", "text/plain; charset=utf-8", False)
            return
        if kind != "application/json" or not length.isdigit() or int(length) > 65536:
            self._send(400, b"send JSON (application/json), at most 64 kB\n",
                       "text/plain; charset=utf-8", False)
            return
        preview = self.server.preview
        try:
            request = json.loads(self.rfile.read(int(length)) or b"null")
            overrides, tolerance = preview.panel.change(request)
        except (ValueError, PanelError) as exc:
            body = json.dumps({"error": str(exc)}).encode()
            self._send(400, body, "application/json", False)
            return
        if not (isinstance(request, dict) and "save" in request):
            preview.apply(overrides, tolerance)
        self._send(200, json.dumps(preview.panel.as_json()).encode(), "application/json", False)

    def _gesture(self, kind: str, length: str) -> None:
        """``/gesture``: a gesture of the page (castor.serve.gestures)."""
        from castor.serve.gestures import MAX_BODY, answer_post

        if kind != "application/json" or not length.isdigit() or int(length) > MAX_BODY:
            self._send(400, b"send JSON (application/json), at most 64 kB\n",
                       "text/plain; charset=utf-8", False)
            return
        status, body = answer_post(self.server.gestures, self.rfile.read(int(length)))
        self._send(status, body, "application/json", False)

    def _camera(self, kind: str, length: str) -> None:
        """``/camera``: the page's camera has stopped (castor.serve.camera)."""
        from castor.serve.camera import MAX_BODY, answer_post

        if kind != "application/json" or not length.isdigit() or int(length) > MAX_BODY:
            self._send(400, b"send JSON (application/json), at most 4 kB\n",
                       "text/plain; charset=utf-8", False)
            return
        status, body = answer_post(self.server.preview, self.rfile.read(int(length)))
        self._send(status, body, "application/json", False)

    def _same_origin(self) -> bool:
        """A POST from another site's page is refused (its Origin is not ours)."""
        origin = self.headers.get("Origin")
        if origin is None:
            return True
        host = self.headers.get("Host", "")
        return origin in (f"http://{host}", f"https://{host}")

    def _host_allowed(self) -> bool:
        """On the loopback address, only pages of this machine may talk to us (a
        web site whose name is made to point at 127.0.0.1 sends its own name)."""
        if not self.server.loopback:
            return True
        host = self.headers.get("Host")
        if host is None:
            return True
        host = host.strip().lower()
        name = host.rpartition(":")[0] if re.search(r":\d+$", host) else host
        return name in _LOOPBACK_HOSTS

    def _send(self, status: int, body: bytes, kind: str, head: bool) -> None:
        self.send_response(status)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(body)))
        for name, value in _HEADERS.items():
            self.send_header(name, value)
        self.end_headers()
        if not head:
            self.wfile.write(body)

    def _events(self) -> None:
        if not self.server.streams.acquire(blocking=False):
            self._send(503, b"too many event streams\n", "text/plain; charset=utf-8", False)
            return
        try:
            self.send_response(200)
            self.send_header("Content-Type", "text/event-stream")
            for name, value in _HEADERS.items():
                self.send_header(name, value)
            self.end_headers()
            self._stream(self.server.preview)
        except OSError:
            pass  # the browser went away: this thread ends
        finally:
            self.server.streams.release()

    def _stream(self, preview: Preview) -> None:
        self.wfile.write(b"retry: 1000\n\n")
        sent = None
        while not preview.stop.is_set():
            with preview.state:
                preview.state.wait_for(lambda: preview.state_key() != sent
                                       or preview.stop.is_set(), HEARTBEAT_SECONDS)
                key = preview.state_key()
            if key != sent:
                data = json.dumps({"server": preview.name, "version": key[0],
                                   "evaluating": key[1], "faceting": key[2]})
                self.wfile.write(f"event: scene\ndata: {data}\n\n".encode())
                sent = key
            else:
                self.wfile.write(b": still here\n\n")
            self.wfile.flush()


class _Server(ThreadingHTTPServer):
    daemon_threads = True
    request_queue_size = 64

    def __init__(self, address, preview: Preview, pages: dict[str, bytes]):
        self.preview = preview
        self.pages = pages
        self.slots = threading.BoundedSemaphore(MAX_REQUESTS)
        self.streams = threading.BoundedSemaphore(MAX_STREAMS)
        self.loopback = _is_loopback(address[0])
        self.gestures = None  # castor.serve.gestures.Gestures: editing on screen
        super().__init__(address, _Handler)

    def server_bind(self):
        # HTTPServer.server_bind asks the DNS for our name; there may be none
        socketserver.TCPServer.server_bind(self)
        self.server_name, self.server_port = str(self.server_address[0]), self.server_address[1]

    def process_request(self, request, client_address):
        if not self.slots.acquire(blocking=False):
            try:  # too many at once: refuse at once rather than queue a thread
                request.settimeout(0.5)
                request.sendall(b"HTTP/1.0 503 Service Unavailable\r\nContent-Length: 0\r\n"
                                b"Retry-After: 1\r\n\r\n")
            except OSError:
                pass
            self.shutdown_request(request)
            return
        try:
            super().process_request(request, client_address)
        except BaseException:
            self.slots.release()
            raise

    def process_request_thread(self, request, client_address):
        try:
            super().process_request_thread(request, client_address)
        finally:
            self.slots.release()

    def handle_error(self, request, client_address):
        pass  # a connection reset mid-request is the browser's business


class _Server6(_Server):
    address_family = socket.AF_INET6


def _is_loopback(address: str) -> bool:
    return address in ("localhost", "::1") or address.startswith("127.")


def _pages() -> dict[str, bytes]:
    folder = resources.files("castor.serve") / "static"
    return {name: (folder / name).read_bytes() for name, _ in _STATIC.values()}


class PreviewServer:
    """The preview and its server, started and stopped together."""

    def __init__(self, job: Watched, bind: str = "127.0.0.1", port: int = 0, report=None,
                 preview: Preview | None = None, gestures=None):
        """``preview``: another kind of Preview (an editor's buffers); ``gestures``:
        where the page's edits go (castor.serve.gestures; by default the file's)."""
        from castor.serve.gestures import file_gestures

        self.preview = preview if preview is not None else Preview(job, report)
        kind = _Server6 if ":" in bind else _Server
        pages = _pages()
        candidates = [port] if port == 0 else range(port, min(port + PORTS_TRIED, 65536))
        for candidate in candidates:
            try:
                self.httpd = kind((bind, candidate), self.preview, pages)
                break
            except OSError as exc:
                if exc.errno != errno.EADDRINUSE or candidate == candidates[-1]:
                    raise
        self.httpd.gestures = gestures if gestures is not None else \
            file_gestures(job, self.preview)
        self.threads: list[threading.Thread] = []

    @property
    def url(self) -> str:
        host, port = self.httpd.server_address[:2]
        return f"http://[{host}]:{port}/" if ":" in host else f"http://{host}:{port}/"

    def start(self, stack_bytes: int = 0) -> "PreviewServer":
        from castor.settings import started_thread

        # deeply nested scenes recurse deeply
        evaluator = started_thread(self.preview.evaluate_scene, "castor-evaluate", stack_bytes)
        self.threads = [evaluator,
                        threading.Thread(target=self.preview.watch_files, name="castor-watch",
                                         daemon=True),
                        threading.Thread(target=self.httpd.serve_forever, args=(0.1,),
                                         name="castor-serve", daemon=True)]
        for thread in self.threads[1:]:
            thread.start()
        return self

    def close(self) -> None:
        """Stop every thread that can be stopped and free the port. (An evaluation
        in the middle of a long frame ends with the process: it is a daemon.)"""
        self.preview.close()
        self.httpd.shutdown()
        self.httpd.server_close()
        for thread in self.threads:
            thread.join(timeout=1.0)


def serve(watched: Watched, bind: str = "127.0.0.1", port: int = 0) -> int:
    """``castor --serve``: serve until Ctrl-C; the exit status. A scene file that
    cannot be read, or an address that cannot be listened on, raises UsageError."""
    from castor.pipeline import STACK_BYTES

    for name in watched.files:
        try:
            with open(name, "rb"):
                pass
        except OSError as exc:
            raise UsageError(f"cannot read '{name}': {exc.strerror}") from None
    try:
        server = PreviewServer(watched, bind, port, report=_print_evaluation)
    except OSError as exc:
        raise UsageError(f"cannot listen on {bind} port {port}: {exc.strerror or exc}") from None
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, _interrupt)
    server.start(STACK_BYTES)
    sys.stderr.write(f"castor: serving {' '.join(watched.files)} at {server.url} "
                     "(Ctrl-C stops)\n")
    sys.stderr.flush()
    try:
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        pass
    finally:
        server.close()
    sys.stderr.write("castor: stopped\n")
    return 0


def _interrupt(signum, frame):
    raise KeyboardInterrupt


def _print_evaluation(result: Evaluation) -> None:
    """On the terminal, as castor prints them: the diagnostics, then one line."""
    frames = len(result.frames)
    polygons = sum(f.polygons for f in result.frames)
    errors = f", {result.errors} error{'s' if result.errors != 1 else ''}" if result.errors else ""
    try:
        sys.stderr.write(f"{result.printed}castor: evaluated in {result.seconds:.2f} s: "
                         f"{frames} frame{'s' if frames != 1 else ''}, {polygons} polygons"
                         f"{errors}\n")
        sys.stderr.flush()
    except (OSError, ValueError):
        pass

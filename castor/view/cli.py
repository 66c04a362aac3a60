"""The castor-view command: polygon stream or mesh file in, pictures out (CLI.md)."""

from __future__ import annotations

import argparse
import os
import re
import sys

from castor.diagnostics import USAGE_ERROR

class _Parser(argparse.ArgumentParser):
    """A usage error is its one line and a hint, never the usage text (CLI.md)."""

    def error(self, message):
        if message.startswith("unrecognized arguments:"):  # only the unknown options
            words = message.split(":", 1)[1].split()
            message = "unrecognized arguments: " + " ".join(
                [w for w in words if w.startswith("-") and w != "-"] or words)
        sys.stderr.write(f"castor-view: error: {message}\ntry 'castor-view --help'\n")
        sys.exit(USAGE_ERROR)


def _triple(text: str, parser, option: str):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3:
        parser.error(f"{option} takes X,Y,Z, not '{text}'")
    return values


def readable_suffixes(streams: bool = True) -> list[str]:
    """The endings of the files of polygons castor-view reads, as the registry
    of formats declares their readers (the stream's too, with ``streams``)."""
    from castor.formats import registry

    suffixes: list[str] = []
    for f in registry().values():
        if f.read is not None and f.kind.polygons and (streams or not f.kind.streamed):
            suffixes.extend(s for s in f.suffixes + f.reads_also if s not in suffixes)
    return suffixes


def _arguments(argv):
    from castor import __version__
    from castor.options import parse_view
    from castor.settings import VIEW_NAMES

    mesh_suffixes = " ".join(readable_suffixes(streams=False))
    p = _Parser(prog="castor-view", description="Draw castor's polygon stream or a mesh file.",
                epilog="Example: castor house.cas | castor-view --view 30,20 -o house.png")
    p.add_argument("file", nargs="?", default="-", metavar="FILE",
                   help=f"polygon stream or mesh file ({mesh_suffixes}); default stdin")
    p.add_argument("-o", "--output", metavar="PATH",
                   help=".png for one frame; .gif, or .png with a %%d pattern, for every frame")
    p.add_argument("--size", default="800x600", metavar="WxH", help="image size (800x600)")
    p.add_argument("--view", default="-60,25", metavar="AZ,EL|NAME",
                   help="camera direction in degrees: azimuth around z, elevation (-60,25); "
                        f"or {', '.join(VIEW_NAMES)} (orthographic)")
    p.add_argument("--eye", metavar="X,Y,Z", help="camera position (with --look)")
    p.add_argument("--look", metavar="X,Y,Z", help="point the camera looks at (with --eye)")
    p.add_argument("--wire", action="store_true", help="wireframe (fil de fer)")
    p.add_argument("--edges", action="store_true", help="shaded faces with their edges")
    p.add_argument("--frame", type=int, metavar="N", help="only frame N")
    p.add_argument("--delay", type=int, default=100, metavar="MS", help="GIF frame time (100 ms)")
    p.add_argument("--version", action="version", version=f"castor-view {__version__}")
    # "--view -30,20": a negative azimuth is a value, not an option
    argv = list(argv)
    for i in range(len(argv) - 1):
        if argv[i] in ("--view", "--eye", "--look") and re.match(r"-[\d.]", argv[i + 1]):
            argv[i:i + 2] = [f"{argv[i]}={argv[i + 1]}", ""]
    args = p.parse_args([a for a in argv if a != ""])
    size = re.fullmatch(r"(\d+)x(\d+)", args.size)
    if not size or not (1 <= int(size[1]) <= 16384 and 1 <= int(size[2]) <= 16384):
        p.error(f"--size takes WxH such as 800x600, not '{args.size}'")
    args.width, args.height = int(size[1]), int(size[2])
    try:
        args.view = parse_view(args.view)
    except ValueError as exc:
        p.error(str(exc))
    if (args.eye is None) != (args.look is None):
        p.error("--eye and --look go together")
    if args.eye is not None:
        args.eye = _triple(args.eye, p, "--eye")
        args.look = _triple(args.look, p, "--look")
        if args.eye == args.look:
            p.error("--eye and --look must be different points")
    if args.wire and args.edges:
        p.error("choose one of --wire and --edges")
    if args.output is None:
        p.error("no output: castor-view writes images and opens no window; give -o FILE.png "
                "(one frame) or -o FILE.gif (an animation), e.g. castor s.cas | castor-view -o s.png")
    lowered = args.output.lower()
    if not (lowered.endswith(".png") or lowered.endswith(".gif")):
        p.error(f"-o takes a .png or .gif file, not '{args.output}'")
    from castor.formats.output import destination_problem

    problem = destination_problem(args.output)
    if problem is not None:
        p.error(problem)
    return args


def _pictures(args):
    """The frames of the input: the stream as it arrives (standard input, or a
    file of no other format), else the file through its format's reader."""
    from castor.formats import format_for_suffix, reader_for
    from castor.formats.cps import load

    if args.file == "-":
        yield from load(iter(sys.stdin.readline, ""), "<stdin>")
        return
    if not os.path.exists(args.file) or os.path.isdir(args.file) \
            or not os.access(args.file, os.R_OK):  # a usage error, as castor's (exit 2)
        reason = "no such file" if not os.path.exists(args.file) else \
            "it is a directory" if os.path.isdir(args.file) else "permission denied"
        sys.stderr.write(f"castor-view: error: cannot read '{args.file}': {reason}\n")
        sys.exit(USAGE_ERROR)
    chosen = reader_for(args.file)
    if chosen is not None and not chosen.kind.streamed:
        yield from chosen.read(args.file)
        return
    if chosen is None and format_for_suffix(args.file) is not None:
        # castor writes it (a picture, a drawing), but it is no polygons to draw
        sys.stderr.write(f"castor-view: error: '{args.file}': castor-view reads a polygon "
                         f"stream or a mesh file ({' '.join(readable_suffixes(streams=False))}), not "
                         f"{args.file.rsplit('.', 1)[-1]} files\n")
        sys.exit(USAGE_ERROR)
    try:
        handle = open(args.file, encoding="utf-8", errors="surrogateescape")
    except OSError as exc:
        sys.stderr.write(f"castor-view: error: cannot read '{args.file}': "
                         f"{(exc.strerror or str(exc)).lower()}\n")
        sys.exit(USAGE_ERROR)
    with handle:
        yield from load(handle, args.file)


def _camera(args, points):
    """The camera of castor's pictures (castor.pictures.camera), framing the points."""
    import numpy as np

    from castor.pictures.camera import make_camera

    if len(points) == 0:
        points = np.zeros((1, 3))
    return make_camera(points.min(axis=0), points.max(axis=0), (args.width, args.height),
                       args.view, args.eye, args.look)


def _image(args, picture, camera):
    from PIL import Image

    from castor.view.render import render

    mode = "wire" if args.wire else "edges" if args.edges else "shaded"
    return Image.fromarray(render(picture, camera, args.width, args.height, mode), "RGB")


def _save(image, path, **options):
    """The image written beside ``path`` and renamed into place."""
    import io

    from castor.formats.output import write_atomically

    buffer = io.BytesIO()
    image.save(buffer, format="GIF" if path.lower().endswith(".gif") else "PNG", **options)
    write_atomically(path, buffer.getvalue())


def run(args) -> int:
    from castor.formats.output import frame_path, has_pattern
    from castor.formats.cps import StreamError

    pattern = has_pattern(args.output)
    gif = args.output.lower().endswith(".gif")
    pictures = []
    seen = 0
    try:
        for picture in _pictures(args):
            seen += 1
            if args.frame is not None and picture.number != args.frame:
                continue
            if pattern and not gif:
                # one image per frame, written as soon as the frame arrives
                image = _image(args, picture, _camera(args, picture.points))
                _save(image, frame_path(args.output, picture.number))
                continue
            pictures.append(picture)
            if not gif:
                break  # one .png: the first frame (or --frame N)
    except StreamError as exc:
        sys.stderr.write(f"castor-view: error: {exc}\n")
        if not pictures:
            return 1
    if pattern and not gif:
        if seen == 0:
            sys.stderr.write("castor-view: error: no frame in the input\n")
            return 1
        return 0
    if not pictures:
        which = f"frame {args.frame}" if args.frame is not None else "frame"
        sys.stderr.write(f"castor-view: error: no {which} in the input\n")
        return 1
    import numpy as np

    # one camera for the whole animation, so that it does not jump
    camera = _camera(args, np.concatenate([p.points for p in pictures]))
    images = [_image(args, p, camera) for p in pictures]
    # one file: its name with '%%' a '%', as castor's -o (a .gif named with a pattern, as is)
    name = args.output if pattern else frame_path(args.output, 1)
    if gif and len(images) > 1:
        _save(images[0], name, save_all=True, append_images=images[1:],
              duration=args.delay, loop=0)
    else:
        _save(images[0], name)
    return 0


def main(argv=None) -> int:
    from castor.formats.output import Unwritable

    args = _arguments(sys.argv[1:] if argv is None else argv)
    try:
        return run(args)
    except Unwritable as exc:  # a full disk, a directory gone since the start
        sys.stderr.write(f"castor-view: error: {exc}\n")
        return USAGE_ERROR
    except BrokenPipeError:
        return 1
    except KeyboardInterrupt:
        sys.stderr.write("castor-view: interrupted\n")
        return 130


if __name__ == "__main__":
    sys.exit(main())

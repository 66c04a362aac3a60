"""The ``castor`` command: a UNIX filter from scene text to polygons (CLI.md).

Exit status: 0 success (warnings allowed), 1 the input had errors (frames
without errors were still written), 2 a usage error.
"""

from __future__ import annotations

import argparse
import gc
import os
import re
import sys
import threading

from castor import __version__
from castor.diagnostics import (USAGE_ERROR, CastorError, ClosedStdout, Reporter, UsageError,
                                stdout_failed)
from castor.options import (OUTPUT_OPTIONS, TITLE_FIELDS, negative_values, not_utf8, option_value,
                            parse_count, warn_without_effect)
from castor.settings import DEFAULT_FORMAT, DEFAULT_MAX_POLYGONS, DEFAULT_PORT, DEFAULT_TOLERANCE


class _NotGiven(list):
    """The value of an option before the command line gives it: a list, so that an
    appending option (--ifc-class) can add to it, and an object of its own, so
    that any value the command line gives is told from it."""


def _columns() -> int:
    """The terminal's width as shutil.get_terminal_size finds it (COLUMNS, else
    standard output's terminal, else 80), without importing shutil (and bz2 and
    lzma with it): argparse asks it for every option it is given, at every start."""
    try:
        columns = int(os.environ.get("COLUMNS", 0))
    except ValueError:
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns if columns > 0 else 80


class _Help(argparse.HelpFormatter):
    """argparse's help, as wide as the terminal (argparse's own less 2)."""

    def __init__(self, prog, indent_increment=2, max_help_position=24, width=None):
        super().__init__(prog, indent_increment, max_help_position,
                         _columns() - 2 if width is None else width)


class _Parser(argparse.ArgumentParser):
    """argparse, whose usage errors are the one line that says what is wrong and
    a hint, never the usage text before it (CLI.md)."""

    def __init__(self, **options):
        super().__init__(formatter_class=_Help, **options)

    def error(self, message):
        if message.startswith("unrecognized arguments:"):
            message += self._closest(message.split(":", 1)[1].split())
        # a byte that is not UTF-8 (kept by Python as a surrogate, repr'd by argparse
        # as \udce9) shown as the byte
        message = re.sub(r"[\udc80-\udcff]|\\udc([89a-f][0-9a-f])", lambda m: "<0x%s>" % (
            m.group(1) or f"{ord(m.group()) - 0xdc00:02x}"), message)
        sys.stderr.write(f"castor: error: {message}\ntry 'castor --help'\n")
        sys.exit(USAGE_ERROR)

    def _closest(self, words: list[str]) -> str:
        """' (did you mean --summary?)' for a misspelt option among ``words``."""
        import difflib

        known = [option for action in self._actions for option in action.option_strings
                 if option.startswith("--")]
        for word in words:
            if word.startswith("--"):
                close = difflib.get_close_matches(word.partition("=")[0], known, n=1)
                if close:
                    return f" (did you mean {close[0]}?)"
        return ""


def _arguments(argv):
    """The parser and the parsed options, checked: a usage error exits (status 2)."""
    p = _parser()
    args = _parse(p, argv)
    _check_texts(p, args)
    _check_values(p, args)
    _standard_output(p, args)
    _check_macros(p, args)
    _choose_format(p, args)
    _check_destinations(p, args)
    return p, args


def _parser() -> _Parser:
    """castor's options: the general ones, then the output options as declared
    (castor.options.OUTPUT_OPTIONS), each in its --help section."""
    p = _Parser(prog="castor", description="Interpret Castor CSG scenes and write their polygons.",
                epilog="Exit status: 0 success, 1 errors in the input, 2 usage error.")
    _general_options(p)
    groups: dict[str, argparse._ArgumentGroup] = {}
    for option in OUTPUT_OPTIONS:
        group = groups.get(option.group) or groups.setdefault(
            option.group, p.add_argument_group(option.group))
        if option.metavar is None:
            group.add_argument(option.flag, action="store_true", help=option.help)
        else:
            group.add_argument(option.flag, dest=option.dest, metavar=option.metavar,
                               default=[] if option.repeat else option.default,
                               action="append" if option.repeat else "store", help=option.help)
    p.add_argument("-q", "--quiet", action="store_true", help="no warnings")
    p.add_argument("--version", action="version", version=f"castor {__version__}")
    return p


def _general_options(p: _Parser) -> None:
    from castor.formats import FORMATS

    p.add_argument("files", nargs="*", metavar="FILE", help="scene files, read in order as one "
                   "input (none or - for standard input)")
    p.add_argument("-o", "--output", metavar="PATH", help="write to PATH (format from its "
                   "extension; a %%d pattern gives one file per frame; '-': standard output, "
                   "as without -o)")
    p.add_argument("-f", "--format", choices=list(FORMATS), help="output format (default cps, "
                   "or from the extension of -o)")
    p.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME[=VALUE]",
                   help="define a preprocessor macro")
    p.add_argument("-U", dest="undefines", action="append", default=[], metavar="NAME",
                   help="undefine a preprocessor macro")
    p.add_argument("-I", dest="include_dirs", action="append", default=[], metavar="DIR",
                   help="add a directory to the #include search path")
    p.add_argument("--no-cpp", action="store_true", help="skip the built-in preprocessor and "
                   "execute statements as they arrive")
    p.add_argument("-s", "--set", dest="sets", action="append", default=[], metavar="NAME=EXPR",
                   help="give parameter NAME this value; the scene's assignments to it are ignored")
    p.add_argument("-p", dest="parameter_file", metavar="FILE",
                   help="take parameter values from FILE (the live preview's JSON), with -P")
    p.add_argument("-P", dest="parameter_set", metavar="NAME",
                   help="the parameter set NAME of the -p FILE, as if each were a --set")
    p.add_argument("--params", action="store_true",
                   help="write the scene's parameters and annotations as JSON, nothing else")
    p.add_argument("-t", "--tolerance", type=float, metavar="T",
                   help=f"facet tolerance in scene units (default {DEFAULT_TOLERANCE})")
    p.add_argument("--check", action="store_true", help="read and evaluate everything, write nothing")
    p.add_argument("--stats", action="store_true", help="one line of figures per frame on stderr")
    p.add_argument("--summary", metavar="PATH", help="write a quantity take-off (JSON) to PATH "
                   "('-': standard output)")
    p.add_argument("--max-polygons", type=int, default=DEFAULT_MAX_POLYGONS, metavar="N",
                   help=f"refuse a frame of more than N polygons (default {DEFAULT_MAX_POLYGONS})")
    p.add_argument("-j", "--jobs", default="1", metavar="N",
                   help="make up to N frames at once in separate processes (0: one per core)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="send frames to a Dask cluster (tcp://host:8786)")
    p.add_argument("--serve", action="store_true",
                   help="live preview in a web browser, evaluated again at each save")
    p.add_argument("--lsp", action="store_true",
                   help="run as a language server for editors on standard input and output")
    p.add_argument("--port", default=str(DEFAULT_PORT), metavar="N",
                   help=f"--serve: the port (default {DEFAULT_PORT}, or the next free one)")
    p.add_argument("--bind", default="127.0.0.1", metavar="ADDRESS",
                   help="--serve: the address to listen on (default loopback only)")


def _parse(p: _Parser, argv) -> argparse.Namespace:
    """The options parsed; ``args.given``: the output options the command line gave."""
    unset = {option.dest: _NotGiven() for option in OUTPUT_OPTIONS}  # told apart from any value
    argv = list(argv)
    after = argv.index("--") if "--" in argv else len(argv)  # files only, after '--'
    args, extra = p.parse_known_args(
        negative_values(argv[:after], tuple(o.flag for o in OUTPUT_OPTIONS if o.signed)),
        namespace=argparse.Namespace(**unset))
    unknown = [word for word in extra if word.startswith("-") and word != "-"]
    if unknown:  # only the unknown options: the scene files around them are no fault
        p.error(f"unrecognized arguments: {' '.join(unknown)}")
    # files between and after the options too, as cpp takes them
    args.files += extra + argv[after + 1:]
    args.given = [option.flag for option in OUTPUT_OPTIONS
                  if getattr(args, option.dest) is not unset[option.dest] or unset[option.dest]]
    for option in OUTPUT_OPTIONS:
        value = getattr(args, option.dest)
        if value is unset[option.dest]:  # an appending option adds to it: a plain list then
            default = p._option_string_actions[option.flag].default
            setattr(args, option.dest, list(value) if value else default)
    return args


# the options whose values are paths: a file's name may hold any bytes
_PATHS = frozenset({"files", "output", "summary", "include_dirs", "parameter_file", "sheets"})


def _check_texts(p: _Parser, args) -> None:
    """Every other option's value is text: a byte that is not UTF-8 (a Latin-1
    terminal's 'é', $'\\xe9') is a usage error that shows it as 0xe9, never an
    internal error of the IFC writer or a letter dropped from a drawing."""
    for action in p._actions:
        if not action.option_strings or action.dest in _PATHS:
            continue
        value = getattr(args, action.dest, None)
        for text in value if isinstance(value, list) else (value,):
            problem = not_utf8(text) if isinstance(text, str) else None
            if problem is not None:
                p.error(f"{max(action.option_strings, key=len)}: {problem}")


def _check_values(p: _Parser, args) -> None:
    """Each option's value parsed and checked (a usage error names it)."""
    if args.tolerance is not None and not (args.tolerance > 0 and args.tolerance < float("inf")):
        p.error(f"--tolerance must be a positive number, not {args.tolerance}")
    if args.max_polygons < 1:
        p.error("--max-polygons must be at least 1")
    try:
        args.jobs = parse_count(args.jobs, "--jobs", 0, 256)
        args.port = parse_count(args.port, "--port", 0, 65535)
        for option in OUTPUT_OPTIONS:
            setattr(args, option.dest, option_value(option, getattr(args, option.dest)))
    except ValueError as exc:
        p.error(str(exc))
    if (args.eye is None) != (args.look is None):
        p.error("--eye and --look go together")
    if args.eye is not None and args.eye == args.look:
        p.error("--eye and --look must be different points")
    if args.pixel_error is not None and not {"--view", "--eye"} & set(args.given):
        p.error("--pixel-error needs a camera: --view, or --eye and --look")
    if args.summary is not None and args.check:
        p.error("--summary needs the frames made; leave out --check")


def _check_macros(p: _Parser, args) -> None:
    for definition in args.defines:
        name, _, value = definition.partition("=")
        if not re.fullmatch(r"[A-Za-z_]\w*(\([\w\s,]*\))?", name.strip()):
            p.error(f"-D takes NAME or NAME=VALUE with a macro NAME (letters, digits and _, "
                    f"not starting with a digit), not {definition!r}")
        if "\n" in value or "\r" in value:
            p.error(f"-D {name}: the value of a macro is one line, not {value!r}")
    for name in args.undefines:
        if not re.fullmatch(r"[A-Za-z_]\w*", name.strip()):
            p.error(f"-U takes a macro NAME (letters, digits and _), not {name!r}")


def _choose_format(p: _Parser, args) -> None:
    """-f, else the format -o's ending names (the stream by default): one that
    can be written here."""
    from castor.formats import FORMATS, format_for_suffix
    from castor.formats.output import is_device, suffix_message

    args.format_named = args.format is not None or args.output is not None  # (--check's warnings)
    if args.format is None:
        args.format = format_for_suffix(args.output) if args.output else DEFAULT_FORMAT
        if args.format is None and is_device(args.output):
            args.format = DEFAULT_FORMAT  # -o /dev/null, a pipe: the stream, as standard output's
        if args.format is None:
            p.error(suffix_message(args.output))
    unavailable = FORMATS[args.format].unavailable  # its library is not installed
    problem = unavailable() if unavailable is not None else None
    if problem is not None:
        p.error(problem)
    if args.sheets is not None and args.format == "svg" and not (
            args.output and "%" in args.output):
        p.error("an SVG holds one sheet: give --sheets a pattern such as -o sheet-%d.svg, or "
                "write one .pdf or .dxf")


def _standard_output(p: _Parser, args) -> None:
    """'-' names standard output, as it does for cat, cpp and curl: '-o -' is as
    no -o (the frames go there); '--summary -' puts the take-off there, where the
    frames do not go (written once, after the run)."""
    if args.output == "-":
        args.output = None
    if args.summary == "-" and _on_standard_output(args.output) and not (
            args.serve or args.lsp or args.params or args.check):
        p.error("--summary -: standard output carries the frames; write them to a file "
                "(castor --summary - -o house.glb house.cas) or the figures to one "
                "(--summary figures.json)")


def _on_standard_output(output: str | None) -> bool:
    """Whether the frames go to standard output (no -o, or -o /dev/stdout)."""
    try:
        return output is None or os.path.samestat(os.stat(output), os.fstat(1))
    except (OSError, ValueError):
        return False


def _check_destinations(p: _Parser, args) -> None:
    from castor.formats.output import destination_problem, same_file

    for path, option in ((args.output, "-o"), (args.summary, "--summary")):
        if path == "-":  # standard output (_standard_output)
            continue
        problem = destination_problem(path, option) if path is not None else None
        if problem is not None:
            p.error(problem)
        if path is not None and any(same_file(path, scene) for scene in args.files):
            p.error(f"{option} {path}: is a scene castor reads; give the output another name")
        if option == "--summary" and path is not None and path.lower().endswith(".cas") \
                and os.path.isfile(path):
            # 'castor --summary house.cas' read standard input and wrote the figures over the scene
            p.error(f"--summary {path}: is a scene file; --summary takes the file the figures go "
                    f"to (castor --summary figures.json {path})")


def _overrides(parser, sets: list[str]) -> dict[str, float]:
    """Evaluate each --set NAME=EXPR with the grammar's expressions."""
    import math

    from castor.language.parse import assignment_value

    values: dict[str, float] = {}
    for item in sets:
        name, sep, expr = item.partition("=")
        name = name.strip()
        if not sep or not re.fullmatch(r"[A-Z][A-Za-z0-9_]*", name):
            hint = ""
            if sep and re.fullmatch(r"[a-z][A-Za-z0-9_]*", name):
                hint = f" ('{name}' names an object; parameters start with an uppercase letter)"
            parser.error(f"--set takes NAME=EXPR with a parameter NAME (an uppercase first "
                         f"letter), not {item!r}{hint}")
        if ";" in expr:
            parser.error(f"--set {item!r}: one parameter for each --set; write "
                         + " ".join(f"--set '{part.strip()}'" for part in item.split(";")
                                    if part.strip()))
        try:
            values[name] = assignment_value(name, expr, {"PI": math.pi,
                                                         "TOLERANCE": DEFAULT_TOLERANCE, **values})
        except CastorError as exc:
            parser.error(f"--set {item}: {exc.message}")
        except RecursionError:
            parser.error(f"--set {name}=...: the expression is nested too deeply")
    return values


# Exit status of a process ended by SIGPIPE, as the shell reports it for cat.
PIPE_CLOSED = 128 + 13


def settings_of(args, overrides: dict[str, float]):
    """The settings of each stage, from the parsed options (castor.settings)."""
    from castor.formats import FORMATS
    from castor.settings import (BimSettings, DrawingSettings, EvaluationSettings, FrameSettings,
                                 MeshSettings, OutputSettings, PictureSettings, ReadSettings,
                                 RunSettings, Source)

    source = Source(tuple(args.files))
    reading = ReadSettings(tuple(args.defines), tuple(args.undefines), tuple(args.include_dirs),
                           args.no_cpp)
    evaluation = EvaluationSettings(overrides=overrides, tolerance=args.tolerance)
    own = FORMATS[args.format].options  # the format's own options, for its writer
    options = tuple((option.dest, getattr(args, option.dest)) for option in OUTPUT_OPTIONS
                    if option.flag in own and option.flag in args.given)
    frame = FrameSettings(
        output=OutputSettings(format=args.format, target=args.output, stats=args.stats,
                              summary=args.summary is not None, title=args.title,
                              options=options),
        mesh=MeshSettings(max_polygons=args.max_polygons, pixel_error=args.pixel_error),
        picture=PictureSettings(size=args.size, view=args.view, eye=args.eye, look=args.look,
                                sun=args.sun, samples=args.samples, edges=args.edges),
        drawing=DrawingSettings(section=args.section, view=args.view, scale=args.scale,
                                sheet=args.sheet, fields=tuple(
                                    (name, getattr(args, name)) for name in TITLE_FIELDS
                                    if getattr(args, name) is not None),
                                register=args.sheets),
        bim=BimSettings(classes=args.ifc_class))
    how = RunSettings(check=args.check, jobs=args.jobs, scheduler=args.scheduler,
                      summary=args.summary)
    return source, reading, evaluation, frame, how


def main(argv=None, *, own_process: bool = False) -> int:
    """castor's command line; ``own_process``: castor's console script, whose
    process is its own (a run that makes its frames here is made in a child
    that it waits for, castor.supervisor), not a caller's."""
    # numpy's OpenBLAS starts a thread per core when numpy is imported, and they
    # spin-wait: a run of 64 houses spent a sixth of its CPU time there. castor's
    # products of matrices are (N, 3) by (3, 3), too small to gain from threads,
    # and a thread per product computes each element as one thread does (the
    # same bytes). Set by the command, before numpy is first imported (a program
    # that imports castor's modules keeps its environment); a user's setting wins.
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    parser, args = _arguments(sys.argv[1:] if argv is None else argv)
    reporter = Reporter(quiet=args.quiet)
    from castor.pipeline import RECURSION_LIMIT, STACK_BYTES
    from castor.run import frames_here, run

    source, reading, evaluation, frame, how = settings_of(args, _overrides(parser, args.sets))
    # A scene graph is many long-lived objects and few cycles: collect rarely (the
    # language server too: 1.2 s of a 40,000-cube statement's 5 s went to collections).
    gc.set_threshold(100_000, 50, 100)
    if args.lsp:
        from castor.lsp.server import main as language_server

        return language_server(args)
    if args.parameter_file is not None or args.parameter_set is not None:
        from castor.analysis.customizer import SetError, readable, set_overrides

        if args.parameter_file is None:
            parser.error(f"-P {args.parameter_set} names a set of a parameter file; give the "
                         f"file with -p FILE")
        source = readable(source)
        try:  # an explicit --set wins over the set's value
            evaluation.overrides = {**set_overrides(args.parameter_file, args.parameter_set,
                                                    source, reading, evaluation),
                                    **evaluation.overrides}
        except SetError as exc:
            sys.stderr.write(f"castor: error: {exc}\n")
            return USAGE_ERROR
    if args.params:
        from castor.analysis.customizer import params_command

        return params_command(source, reading, evaluation, quiet=args.quiet)
    if not args.serve:
        warn_without_effect(args, reporter)

    def work():
        return run(source, reporter, reading=reading, evaluation=evaluation, settings=frame,
                   how=how)

    # Deeply nested scenes recurse deeply: run on a thread with a large stack.
    sys.setrecursionlimit(RECURSION_LIMIT)
    if args.serve:
        return _serve(args, source, reading, evaluation)
    threading.stack_size(STACK_BYTES)
    if own_process and frames_here(how):
        from castor.supervisor import supervise

        if supervise():  # in the child: its parent hears Ctrl-C and SIGTERM
            return _status(_on_thread(work, signals=False))
    return _status(_on_thread(work))


def _on_thread(work, signals: bool = True) -> object:
    """What ``work`` (the run) gives, run on a thread of its own while this one
    waits for Ctrl-C or SIGTERM, which end every process at once (``signals``:
    heard here)."""
    result: list = []

    def target():
        try:
            result.append(work())
        except UsageError as exc:
            sys.stderr.write(f"castor: {exc}\n")
            result.append(USAGE_ERROR)
        except BaseException as exc:  # handed to the main thread below
            result.append(exc)

    thread = threading.Thread(target=target, name="castor", daemon=True)
    stopped_by = _stop_on_signals() if signals else [0]
    thread.start()
    try:
        while thread.is_alive():
            thread.join(0.2)
    except KeyboardInterrupt:
        _interrupted(128 + stopped_by[0])
    return result[0] if result else 1


def _status(outcome) -> int:
    """The exit status of a run that gave ``outcome`` (its status, or what it
    raised), and a one-line message for what it raised."""
    if isinstance(outcome, BrokenPipeError):
        _quiet_stdout()
        return PIPE_CLOSED
    if isinstance(outcome, SystemExit):
        return outcome.code if isinstance(outcome.code, int) else 1
    from castor.formats.output import Unwritable

    if isinstance(outcome, Unwritable):
        sys.stderr.write(f"castor: error: {outcome}\n")
        return USAGE_ERROR
    if stdout_failed(outcome):
        # standard output itself failed (a full disk behind a redirection)
        sys.stderr.write(f"castor: error: cannot write to standard output: "
                         f"{(outcome.strerror or str(outcome)).lower()}\n")
        _quiet_stdout()
        return USAGE_ERROR
    if isinstance(outcome, MemoryError):
        sys.stderr.write("castor: error: out of memory; simplify the scene, raise the tolerance "
                         "or lower --max-polygons\n")
        return 1
    if isinstance(outcome, BaseException):
        # A bug of castor's, not of the input: say so in one line (the whole
        # traceback with CASTOR_DEBUG=1), and keep the frames already written.
        if os.environ.get("CASTOR_DEBUG"):
            raise outcome
        sys.stderr.write(f"castor: internal error: {type(outcome).__name__}: {outcome} "
                         "(please report it with the scene; CASTOR_DEBUG=1 shows where)\n")
        return 1
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _quiet_stdout()
        return PIPE_CLOSED
    except OSError as exc:
        sys.stderr.write(f"castor: error: cannot write to standard output: "
                         f"{(exc.strerror or str(exc)).lower()}\n")
        _quiet_stdout()
        return USAGE_ERROR
    return outcome


def _stop_on_signals() -> list[int]:
    """SIGTERM stops castor as Ctrl-C does; the list says which signal came."""
    import signal

    stopped_by = [signal.SIGINT]

    def terminate(signum, frame):
        stopped_by[0] = signum
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, terminate)
    return stopped_by


def _interrupted(status: int) -> None:
    """Ctrl-C or SIGTERM: every process castor started ends now, no half file stays."""
    from castor.formats.output import remove_temporaries
    from castor.run import end_processes

    try:  # the run's thread goes on until the exit: whatever it says now, nobody reads
        stderr = os.dup(2)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 2)
    except OSError:
        stderr = None
    end_processes()  # the workers first: they write the spooled frames
    remove_temporaries()  # a file being written, spooled frames: no half file left
    if stderr is not None:
        try:
            os.write(stderr, b"castor: interrupted\n")
        except OSError:
            pass
    os._exit(status)


def _serve(args, source, reading, evaluation) -> int:
    """``castor --serve``: its usage errors, then the preview server until Ctrl-C."""
    def usage(message: str) -> int:
        sys.stderr.write(f"castor: error: {message}\n")
        return USAGE_ERROR

    if not args.files or "-" in args.files:
        return usage("--serve needs a scene file to watch (not standard input)")
    if args.output or args.check:
        return usage("--serve shows the frames in a web browser; it writes nothing "
                     f"({'-o' if args.output else '--check'} goes without --serve)")
    from castor.serve.evaluation import Watched
    from castor.serve.server import serve

    try:
        return serve(Watched(source, reading, evaluation, quiet=args.quiet), args.bind, args.port)
    except UsageError as exc:
        return usage(str(exc))


def entry() -> None:
    """The console script: main(), then exit at once.

    Freeing a large scene graph object by object at interpreter exit costs
    as much as a quarter of a --check run; the operating system frees it all
    at once. Output is flushed first.
    """
    if sys.stdout is None:  # started with standard output closed ('>&-')
        sys.stdout = ClosedStdout()
    status = main(own_process=True)
    from castor.run import release_processes

    release_processes()  # else the resource tracker may warn of leaked semaphores
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (BrokenPipeError, ValueError, OSError):
            pass
    if status == PIPE_CLOSED:
        # the reader of our pipe has gone: end as cat does, by SIGPIPE
        import signal

        signal.signal(signal.SIGPIPE, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGPIPE)
    os._exit(status)


def _quiet_stdout() -> None:
    """After the reader of our pipe has gone: no more writes, no message at exit."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except OSError:
        pass


if __name__ == "__main__":
    entry()

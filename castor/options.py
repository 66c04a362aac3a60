"""The command line's options shared by ``castor`` and ``castor-view``: their
parsers, and the declarations of the options that act on some outputs only.

Each parser takes the option's text and returns its value or raises
``ValueError`` with the message a usage error shows; the commands turn that
into ``PROG: error: MESSAGE`` and exit status 2. The values they make (View,
Section, Paper) and every default are castor.settings': the library's stages
read those and never import this module.
"""

from __future__ import annotations

import math
import re
from typing import NamedTuple

from castor.settings import (DEFAULT_SAMPLES, DEFAULT_SCALE, DEFAULT_SIZE, DEFAULT_SUN,
                             DEFAULT_VIEW, PAPER_SIZES, VIEW_NAMES, Paper, Section, View)

MAX_PIXELS = 16384  # the largest --size, each way

def _number(text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{what}: '{text}' is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{what}: '{text}' is not a finite number")
    return value


def _numbers(text: str, count: int, option: str, form: str) -> tuple[float, ...]:
    parts = text.split(",")
    if len(parts) != count:
        raise ValueError(f"{option} takes {form}, not '{text}'")
    return tuple(_number(p.strip(), option) for p in parts)


def parse_size(text: str) -> tuple[int, int]:
    match = re.fullmatch(r"\s*(\d{1,6})\s*[xX]\s*(\d{1,6})\s*", text)
    if not match or not (1 <= int(match[1]) <= MAX_PIXELS and 1 <= int(match[2]) <= MAX_PIXELS):
        raise ValueError(f"--size takes WxH in pixels (each 1 to {MAX_PIXELS}) such as 800x600, "
                         f"not '{text}'")
    return int(match[1]), int(match[2])


def parse_view(text: str) -> View:
    name = text.strip().lower()
    if name in VIEW_NAMES:
        return View(name, 0.0, 0.0)
    try:
        azimuth, elevation = _numbers(text, 2, "--view", "AZ,EL in degrees")
    except ValueError:
        raise ValueError(f"--view takes AZ,EL in degrees (such as -60,25) or one of "
                         f"{', '.join(VIEW_NAMES)}, not '{text}'") from None
    if not -90 <= elevation <= 90:
        raise ValueError(f"--view: the elevation must lie between -90 and 90 degrees, not "
                         f"{elevation:g}")
    return View(None, azimuth, elevation)


def parse_point(text: str, option: str) -> tuple[float, float, float]:
    return _numbers(text, 3, option, "X,Y,Z")


def parse_sun(text: str) -> tuple[float, float] | None:
    if text.strip().lower() == "none":
        return None
    try:
        azimuth, elevation = _numbers(text, 2, "--sun", "AZ,EL")
    except ValueError:
        raise ValueError(f"--sun takes AZ,EL in degrees (such as 135,50) or none, not "
                         f"'{text}'") from None
    if not 0 < elevation <= 90:
        raise ValueError(f"--sun: the elevation must lie above the horizon (0 < EL <= 90), "
                         f"not {elevation:g}")
    return azimuth, elevation


def parse_section(text: str) -> Section:
    match = re.fullmatch(r"\s*([xyzXYZ])\s*=\s*(\S+)\s*", text)
    if not match:
        raise ValueError(f"--section takes AXIS=VALUE such as z=1.2 (a plan) or x=3, not '{text}'")
    return Section(match[1].lower(), _number(match[2], "--section"))


def parse_scale(text: str) -> float:
    match = re.fullmatch(r"\s*1\s*:\s*(\S+)\s*", text)
    denominator = None
    if match:
        try:
            denominator = float(match[1])
        except ValueError:
            denominator = None
    if denominator is None or not (math.isfinite(denominator) and denominator > 0):
        raise ValueError(f"--scale takes 1:N such as 1:100 or 1:50, not '{text}'")
    return denominator


def parse_sheet(text: str) -> Paper:
    match = re.fullmatch(r"\s*(A[0-4])(-portrait)?\s*", text, re.IGNORECASE)
    if not match:
        raise ValueError(f"--sheet takes A4, A3, A2, A1 or A0 (landscape), or A4-portrait ... "
                         f"A0-portrait (upright), not '{text}'")
    size = match[1].upper()
    width, height = PAPER_SIZES[size]
    if match[2]:
        return Paper(f"{size}-portrait", height, width)
    return Paper(size, width, height)


def parse_count(text: str, option: str, low: int, high: int) -> int:
    try:
        value = int(text)
    except ValueError:
        raise ValueError(f"{option} takes a whole number, not '{text}'") from None
    if not low <= value <= high:
        raise ValueError(f"{option} takes a whole number from {low} to {high}, not {value}")
    return value


def not_utf8(text: str) -> str | None:
    """What is wrong with a command line's text that is not UTF-8 (Python keeps
    each such byte as a lone surrogate, U+DC80..U+DCFF), shown as the byte
    (0xe9) with the text before it and the text read as Latin-1; None if it is
    UTF-8."""
    bad = re.search("[\udc80-\udcff]", text)
    if bad is None:
        return None
    byte = ord(bad.group()) - 0xdc00
    latin1 = text.encode("utf-8", "surrogateescape").decode("latin-1")
    where = f"after '{text[:bad.start()]}'" if bad.start() else "at the start"
    return (f"byte 0x{byte:02x} {where} is not UTF-8; castor takes UTF-8 text, such as "
            f"'{latin1}' if it was Latin-1")


def negative_values(argv: list[str], options: tuple[str, ...]) -> list[str]:
    """``--view -30,20``: a value that starts with '-' joined to its option, so
    that argparse does not take it for an option."""
    out = list(argv)
    i = 0
    while i < len(out) - 1:
        if out[i] in options and re.match(r"-[\d.]", out[i + 1]):
            out[i:i + 2] = [f"{out[i]}={out[i + 1]}"]
        i += 1
    return out


def set_value_message(exc, parameter: str, known: dict) -> str:
    """The parser's message for a --set value, in the words of a value on the
    command line: the ';' that ends the statement it is read as is castor's, and
    only PI, TOLERANCE and the parameters of the --set options before it (``known``)
    have a value there."""
    from castor.language.expressions import UndefinedParameter

    message = exc.message.replace("found ';'", "found the end of the value").replace(
        "expected ';'", "expected an operator or the end of the value")
    where = "a --set value knows PI, TOLERANCE and the earlier --set parameters, not the scene's"
    if isinstance(exc, UndefinedParameter):
        return f"{message}; {where}"
    lower = re.match(r"'([a-z]\w*)' is not a parameter: ", message)
    if lower:
        word = lower[1]
        for meant in (word[0].upper() + word[1:], word.upper()):
            if meant in known:
                return (f"'{word}' is not a parameter: parameter names start with an "
                        f"uppercase letter ({meant})")
        return (f"'{word}' is neither a number nor a parameter: --set takes a number, such as "
                f"--set {parameter}=3.2, or an expression; {where}")
    return message


def output_clash(args, path: str, option: str) -> str | None:
    """The usage error of an output (``path``, given as ``option``) that is a file
    the run reads, or the other output, or None: written, it would destroy that
    file (the same file through another path or a symbolic link, or among an -o
    pattern's files, too)."""
    import os

    from castor.formats.output import same_file

    if any(same_file(path, scene) for scene in args.files if scene != "-"):
        return f"{option} {path}: is a scene castor reads; give the output another name"
    register = getattr(args.sheets, "path", args.sheets)  # (read by now: its path)
    for read, what in ((args.parameter_file, "the parameter file castor reads (-p)"),
                       (register, "the drawing register castor reads (--sheets)")):
        if read is not None and same_file(path, read):
            return f"{option} {path}: is {what}; give the output another name"
    if option == "--summary" and args.output not in (None, "-") and (
            same_file(args.output, path)):
        stem = os.path.splitext(path)[0]
        other = f"{stem}.json" if not path.lower().endswith(".json") else f"{stem}-summary.json"
        return (f"--summary {path}: is where -o {args.output} writes the frames; give the "
                f"figures a file of their own (--summary {other})")
    return None


def parse_samples(text: str) -> int:
    return parse_count(text, "--samples", 1, 256)


def parse_pixel_error(text: str) -> float:
    value = _number(text, "--pixel-error")
    if value <= 0:
        raise ValueError(f"--pixel-error takes a number of pixels above 0, such as 0.5, not "
                         f"'{text}'")
    return value


def parse_eye(text: str) -> tuple[float, float, float]:
    return parse_point(text, "--eye")


def parse_look(text: str) -> tuple[float, float, float]:
    return parse_point(text, "--look")


class OutputOption(NamedTuple):
    """An option that acts on some outputs only: its declaration for the command
    line. Which outputs it acts on, the kinds and formats say (castor.formats:
    a kind's ``options``, a format's own ``options``); one given for another
    output is warned about (CLI.md)."""

    flag: str  # "--size"
    metavar: str | None  # None: a switch, given or not
    help: str  # for --help (argparse's %(default)s for the default)
    group: str  # the --help section it is listed in
    default: str | None = None  # the text taken when it is not given (then parsed)
    parse: object = None  # text -> value (ValueError: a usage error); "module:function": imported when given
    absent: object = None  # the value when it is neither given nor has a default text
    repeat: bool = False  # given several times, its values a list
    signed: bool = False  # its value may start with '-' (--view -30,20)
    # given, it makes these options act on its outputs too (--pixel-error: the camera's)
    brings: tuple[str, ...] = ()

    @property
    def dest(self) -> str:
        """Its name without dashes: the attribute of the parsed options, and the
        key of a format's own option in castor.formats.WriteInfo.options."""
        return self.flag[2:].replace("-", "_")


PICTURES_AND_DRAWINGS = "pictures and drawings"
BUILDING_MODELS = "building models (IFC)"

# Every option that acts on some outputs only, in --help's order: declared here only.
OUTPUT_OPTIONS = (
    OutputOption("--size", "WxH", "picture size in pixels (default %(default)s)",
                 PICTURES_AND_DRAWINGS, "%dx%d" % DEFAULT_SIZE, parse_size),
    OutputOption("--view", "AZ,EL|NAME", "camera direction in degrees, or "
                 f"{', '.join(VIEW_NAMES)} (orthographic)", PICTURES_AND_DRAWINGS,
                 "%g,%g" % DEFAULT_VIEW, parse_view, signed=True),
    OutputOption("--eye", "X,Y,Z", "camera position (with --look)", PICTURES_AND_DRAWINGS,
                 parse=parse_eye, signed=True),
    OutputOption("--look", "X,Y,Z", "the point the camera looks at", PICTURES_AND_DRAWINGS,
                 parse=parse_look, signed=True),
    OutputOption("--sun", "AZ,EL|none", "direction of the sun (default: the camera's azimuth + "
                 "%g, %g high), or none" % DEFAULT_SUN, PICTURES_AND_DRAWINGS, parse=parse_sun,
                 absent=DEFAULT_SUN, signed=True),
    OutputOption("--samples", "N", "rays per pixel for anti-aliasing (default %(default)s)",
                 PICTURES_AND_DRAWINGS, str(DEFAULT_SAMPLES), parse_samples),
    OutputOption("--edges", None, "outline silhouettes and creases", PICTURES_AND_DRAWINGS),
    OutputOption("--section", "AXIS=VALUE", "a drawing cut by the plane z=H (a plan), x=V or y=V",
                 PICTURES_AND_DRAWINGS, parse=parse_section, signed=True),
    OutputOption("--scale", "1:N", "printed scale of a drawing (default %(default)s), or the "
                 "scale of a 3MF model (default 1:1)", PICTURES_AND_DRAWINGS,
                 f"1:{DEFAULT_SCALE}", parse_scale),
    OutputOption("--sheet", "SIZE", "lay a drawing on A4 ... A0 paper (landscape; A3-portrait "
                 "for upright), with border and title block", PICTURES_AND_DRAWINGS,
                 parse=parse_sheet),
    # one title for every document that has one: a drawing's, an IFC project's
    OutputOption("--title", "TEXT", "the title of a drawing or an IFC project (default: the "
                 "'>' object's name, or the file's)", PICTURES_AND_DRAWINGS),
    # the title block's project fields (CLI.md; also a register's [project])
    OutputOption("--project", "TEXT", "a drawing's project title, in its title block",
                 PICTURES_AND_DRAWINGS),
    OutputOption("--number", "TEXT", "the project's number, in a drawing's title block",
                 PICTURES_AND_DRAWINGS),
    OutputOption("--revision", "TEXT", "the revision, in a drawing's title block",
                 PICTURES_AND_DRAWINGS),
    OutputOption("--drawn", "TEXT", "who drew it, in a drawing's title block",
                 PICTURES_AND_DRAWINGS),
    OutputOption("--checked", "TEXT", "who checked it, in a drawing's title block",
                 PICTURES_AND_DRAWINGS),
    OutputOption("--sheets", "FILE", "a drawing set: FILE is the drawing register (TOML); "
                 "every sheet in one .pdf (an index, then a page each), one .dxf (a layout "
                 "each) or a file each for a %%d pattern", PICTURES_AND_DRAWINGS,
                 parse="castor.drawings.register:parse_register"),
    OutputOption("--pixel-error", "E", "facets sized to the screen: each curved surface "
                 "within E pixels of its facets seen from the camera (--view or --eye/--look, "
                 "--size)", PICTURES_AND_DRAWINGS, parse=parse_pixel_error,
                 brings=("--size", "--view", "--eye", "--look")),
    OutputOption("--ifc-class", "NAME=CLASS", "IFC class of the object NAME, such as "
                 "maison=IfcWall (repeatable; default IfcBuildingElementProxy)", BUILDING_MODELS,
                 parse="castor.formats.ifc:parse_classes_option", absent=(), repeat=True),
)


# the title block's fields the command line gives (their options' names)
TITLE_FIELDS = ("project", "number", "revision", "drawn", "checked")


def option_value(option: OutputOption, value):
    """An output option's value from its text (its list of texts, for a repeated
    one): parsed, or its ``absent`` value where it was not given."""
    if value is None or (option.repeat and not value):
        return option.absent
    if option.parse is None:
        return value
    parse = option.parse
    if isinstance(parse, str):  # a format's own parser: its module imported now
        import importlib

        module, _, name = parse.partition(":")
        parse = getattr(importlib.import_module(module), name)
    return parse(value)


def warn_without_effect(args, reporter) -> None:
    """Each option given that has no effect on the chosen output, once (CLI.md):
    ``args``, castor's parsed command line (castor.cli)."""
    from castor.formats import FORMATS, acts_on, without_effect

    if args.check and not args.format_named:  # no output at all (it said "no effect on cps
        # output"); with -o or -f, --check checks the options as that output takes them
        for option in args.given:
            reporter.warning(f"{option} has no effect with --check (it writes nothing); "
                             "it is ignored")
        return
    brings = {option.flag: option.brings for option in OUTPUT_OPTIONS}
    for message in without_effect(args.given, FORMATS[args.format], brings):
        reporter.warning(message)
    if "--sheets" in args.given and acts_on("--sheets", FORMATS[args.format]):
        for option in ("--section", "--view", "--scale", "--sheet"):  # the register says them
            if option in args.given:
                reporter.warning(f"{option} has no effect with --sheets (each sheet's drawing, "
                                 "scale and paper are the register's); it is ignored")
        for name in args.sheets.overridden([(n, getattr(args, n)) for n in TITLE_FIELDS
                                            if getattr(args, n)]):
            reporter.warning(f"--{name} has no effect where the register gives its own "
                             f"({args.sheets.path}); the register's is printed there")
        if "--title" in args.given and any(entry.title for entry in args.sheets.sheets):
            reporter.warning(f"--title has no effect on the sheets the register gives a title "
                             f"({args.sheets.path}); the register's is printed there")

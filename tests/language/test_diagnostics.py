"""Messages: FILE:LINE:COL, words a user knows, recovery, exit status, positions through cpp."""

import shutil
import subprocess

import pytest

from tests.support.cli import run, write
from tests.support.stream import parse_stream
from tests.support.vocabulary import primitive_names
from castor.transformations import TRANSFORMS

CUBE = "!cu(0.5, 0.5, 0.5)"


def test_error_between_two_good_frames(tmp_path):
    scene = write(tmp_path, "file.cas", f"a = {CUBE};\n> a;\n> @h(2) b;\n> @t(2, 0, 0) a;\n")
    status, out, err = run(str(scene), cwd=tmp_path)
    assert status == 1
    frames = parse_stream(out)
    assert len(frames) == 2
    assert frames[1].box()[0][0] == 2
    assert err.splitlines()[0] == "file.cas:3:9: error: object 'b' is not defined"
    # the source line and a caret follow
    assert err.splitlines()[1] == " > @h(2) b;"
    assert err.splitlines()[2] == "         ^"


@pytest.mark.parametrize("text, expected", [
    ("> !cu(1, 1 1);", "<stdin>:1:12: error: expected ',' or ')' after an argument, found the number 1"),
    ("> !cu(1, 1, 1)", "<stdin>:1:15: error: expected ';' at the end of the statement, found the end of the input"),
    ("a = !cu(1,1,1)\n> a;", "<stdin>:1:15: error: expected ';' at the end of the statement, found '>'"),
    ("> !cu(1, 1, 1;", "<stdin>:1:14: error: expected ',' or ')' after an argument, found ';'"),
    ("X = ;", "<stdin>:1:5: error: expected an expression, found ';'"),
    ("> ;", "<stdin>:1:3: error: expected an object (a primitive such as !cu(...), a transformation, $U/$I/$D or an object name) or '[', found ';'"),
    ("a = !cu(1, 1, 1) !cu(1, 1, 1);", "<stdin>:1:18: error: expected ';', found '!cu'"),
    ("> ! cu(1,1,1);", "<stdin>:1:3: error: '!' must be followed directly by a primitive name, such as !cu"),
    ("X = 3 ? 4;", "<stdin>:1:7: error: unexpected character '?'"),
    ("> !cube(1, 1, 1);", "<stdin>:1:3: error: unknown primitive '!cube'; did you mean '!cu'? (known: " + ", ".join("!" + p for p in primitive_names()) + ")"),
    ("> @tr(1, 0, 0) !cu(1, 1, 1);", "<stdin>:1:3: error: unknown transformation '@tr'; did you mean '@t'? (known: " + ", ".join("@" + t for t in TRANSFORMS) + ")"),
    ("> !cu(1, 1);", "<stdin>:1:3: error: '!cu' takes 3 arguments (R, G, B), but 2 were given"),
    ("> @t(1, 1) !cu(1, 1, 1);", "<stdin>:1:3: error: '@t' takes 3 arguments (X, Y, Z), but 2 were given"),
    ("> $D(!cu(1,1,1), !cu(1,1,1), !cu(1,1,1));", "<stdin>:1:3: error: '$D' takes exactly two operands (a - b), but 3 were given; to subtract several, write $D(a, $U(b, c))"),
    ("> $X(!cu(1,1,1));", "<stdin>:1:3: error: unknown boolean operator '$X' (known: $U union, $I intersection, $D difference)"),
    ("> !cu(255, 0, 0);", "<stdin>:1:7: error: colour component red = 255 of !cu is outside 0..1; if it is a 0..255 value, write 255/255"),
    ("> @h(1, 0, 1) !cu(1, 1, 1);", "<stdin>:1:3: error: zero scale factor for y in '@h' (flattens the object to nothing); use a small positive factor, or leave the object out"),
    ("> $U[I = 0, 1, 0](!cu(1, 1, 1));", "<stdin>:1:16: error: the step of a repetition is zero; it would never end"),
    (">[T = 0, 1, 0] !cu(1, 1, 1);", "<stdin>:1:13: error: the step of a repetition is zero; it would never end"),
    ("> nothing;", "<stdin>:1:3: error: object 'nothing' is not defined"),
    ("/* open comment\n> !cu(1,1,1);", "<stdin>:1:1: error: unterminated comment: '/*' has no matching '*/'"),
    ("> !to(1, 1, 1, 1.5);", "<stdin>:1:3: error: the tube radius K of !to must lie strictly between 0 and 1, not 1.5"),
    ("> !pr(1, 1, 1, 2.5);", "<stdin>:1:3: error: the number of sides N of !pr must be a whole number >= 3, not 2.5"),
    ("> !ex(1, 1, 1, 0, 0, 1, 1, 1, 0, 0, 1);", "<stdin>:1:3: error: the polygon of !ex intersects itself (edge 1 crosses edge 3)"),
    ("> !rv(1, 1, 1, 0, 0, -1, 0, 1, 1);", "<stdin>:1:3: error: the profile of !rv has r < 0 at vertex 2 (r = -1); a profile lies in the half-plane r >= 0"),
])
def test_messages(text, expected):
    status, out, err = run("--no-cpp", stdin=text + "\n")
    assert status == 1
    assert err.splitlines()[0] == expected


def test_missing_semicolon_skips_the_statement():
    # LANGUAGE.md §9: the statement in error is skipped (it was once taken as if
    # the ';' were there); its use then says why the object is missing
    status, out, err = run("--no-cpp", stdin=f"a = {CUBE}\n> a;\n")
    assert status == 1
    assert out == ""  # no frame: its object was skipped
    assert err.count("error:") == 2
    assert "expected ';' at the end of the statement" in err
    assert "(its definition had errors)" in err


def test_error_limit_stops_at_fifty():
    status, out, err = run("--no-cpp", stdin="> nothing;\n" * 80)
    assert status == 1
    assert err.count(": error: ") == 50
    assert "too many errors" in err


def test_missing_include(tmp_path):
    # reported at its place, and the run goes on (issue 18): the errors after it
    # are seen too, as an external cpp reports them
    scene = write(tmp_path, "s.cas", f"a = {CUBE};\n#include \"nowhere.cas\"\n> a;\n")
    status, out, err = run(str(scene), cwd=tmp_path)
    assert status == 1
    assert err.splitlines()[0] == ("s.cas:2:10: error: cannot find include file 'nowhere.cas' "
                                   "(searched: .); give the directory that holds it with -I DIR")
    assert len(parse_stream(out)) == 1


def test_error_in_included_file_names_it(tmp_path):
    write(tmp_path, "parts/wall.cas", "#define C 0.9, 0.9, 0.9\n\nmur = @h(4, 0.2, 3) !cu(C);\nbad = @h(1) zz;\n")
    scene = write(tmp_path, "house.cas", "#include \"parts/wall.cas\"\n> mur;\n")
    status, out, err = run(str(scene), cwd=tmp_path)
    assert status == 1
    assert err.splitlines()[0] == "parts/wall.cas:4:13: error: object 'zz' is not defined"
    assert len(parse_stream(out)) == 1


def test_includes_itself(tmp_path):
    scene = write(tmp_path, "loop.cas", "#include \"loop.cas\"\n> !cu(1,1,1);\n")
    status, out, err = run(str(scene), cwd=tmp_path)
    assert status == 1
    assert "include" in err.splitlines()[0] and err.splitlines()[0].startswith("loop.cas:")


@pytest.mark.parametrize("directive, message, frames", [
    ("#define", "#define needs a macro name", 1),
    # as cpp, an #ifdef without a name still opens its block, left out (so that
    # its #else and #endif match): here the block never ends, which is said too
    ("#ifdef", "#ifdef needs a macro name", 0),
    ("#include", "#include needs a file name, as in #include \"walls.cas\"", 1),
])
def test_directive_without_its_argument(directive, message, frames):
    status, out, err = run(stdin=f"{directive}\n> !cu(1,1,1);\n")
    assert status == 1
    assert err.splitlines()[0] == f"<stdin>:1:1: error: {message}"
    assert (len(parse_stream(out)) if out else 0) == frames


def test_directive_with_no_cpp_is_explained():
    status, out, err = run("--no-cpp", stdin="#define A 1\n> !cu(1,1,1);\n")
    assert status == 1
    assert err.splitlines()[0].startswith("<stdin>:1:1: error: preprocessor directive '#define' with --no-cpp")
    assert len(parse_stream(out)) == 1


@pytest.mark.skipif(shutil.which("cpp") is None, reason="GNU cpp not installed")
def test_gnu_cpp_pipeline_matches_and_maps_positions(tmp_path):
    write(tmp_path, "parts/roue.cas", "/* a wheel */\nroue = @h(0.3, 0.3, 0.1) !cy(0.1, 0.1, 0.1);\n")
    scene = write(tmp_path, "car.cas",
                  "#include \"parts/roue.cas\"\n#define ROUGE 0.8, 0.1, 0.1\n"
                  "v = $U(@h(4, 1.6, 1) !cu(ROUGE), @t(1, 0, 0.3) @rx(90) roue);\n> v;\n"
                  "\n> @h(2) oops;\n")
    pre = subprocess.run(["cpp", str(scene.name)], capture_output=True, text=True, cwd=tmp_path)
    s1, piped, err1 = run(stdin=pre.stdout, cwd=tmp_path)
    s2, direct, err2 = run(str(scene.name), cwd=tmp_path)
    assert s1 == s2 == 1
    assert piped == direct
    assert err1.splitlines()[0] == "car.cas:6:9: error: object 'oops' is not defined"
    assert err2.splitlines()[0] == err1.splitlines()[0]
    s3, streamed, _ = run("--no-cpp", stdin=pre.stdout, cwd=tmp_path)
    assert streamed == direct


def test_line_directive_is_followed():
    status, out, err = run("--no-cpp", stdin="#line 40 \"elsewhere.cas\"\n> zz;\n")
    assert err.splitlines()[0] == "elsewhere.cas:40:3: error: object 'zz' is not defined"

"""What a new user meets (issue 9): output errors, pipes, and messages that name
the real cause. Golden text where the text is the contract (diagnostics)."""

import json
import os
import re
import struct
import subprocess
import sys
import tempfile

import pytest
from hypothesis import HealthCheck, event, given, settings, strategies as st

from tests.support.cli import OUTSIDE, run, run_here, write
from tests.support.stream import parse_stream

CUBE = "!cu(0.5, 0.5, 0.5)"
SCENE = f"> {CUBE};\n"


def last_line(err):
    """The last message, less the one-line hint that may follow a usage error."""
    lines = err.strip().splitlines()
    if len(lines) > 1 and lines[-1].startswith("try '"):
        lines.pop()
    return lines[-1]


def run_briefly(*args, stdin=None, cwd=None, seconds=30):
    """Run castor with a time limit: a hang is a failure, not a stuck suite."""
    result = subprocess.run([sys.executable, "-m", "castor", *args], input=stdin,
                            cwd=cwd or OUTSIDE, capture_output=True, text=True,
                            timeout=seconds)
    assert "Traceback" not in result.stderr, result.stderr
    return result.returncode, result.stdout, result.stderr


def run_view(*args, stdin=None, cwd=None):
    result = subprocess.run([sys.executable, "-m", "castor.view.cli", *args], input=stdin,
                            capture_output=True, text=True, cwd=cwd or OUTSIDE,
                            timeout=120)
    assert "Traceback" not in result.stderr, result.stderr
    return result.returncode, result.stdout, result.stderr


# --- 6, 7, 8: outputs that cannot be written are usage errors (exit 2)

def _written_suffixes() -> str:
    """Every ending castor writes, once each, in the registry's order."""
    from castor.formats import FORMATS

    return " ".join(dict.fromkeys(f.suffix for f in FORMATS.values()))


@pytest.mark.parametrize("name, message", [
    ("x.dwg", "castor: error: cannot tell the format of 'x.dwg' from its extension; use one "
              f"of {_written_suffixes()}, or give the format with -f NAME"),
    ("x.gltf", "castor: error: cannot tell the format of 'x.gltf' from its extension (castor "
               f"writes glTF as one binary file, .glb); use one of {_written_suffixes()}, or "
               "give the format with -f NAME"),
    ("nodir/x.stl", "castor: error: cannot write 'nodir/x.stl': the directory 'nodir' does "
                    "not exist"),
    ("f-%03d-%03d.stl", "castor: error: -o f-%03d-%03d.stl: 2 frame-number patterns; a path "
                        "takes one, such as house-%03d.stl"),
    ("50%-%d.stl", "castor: error: -o 50%-%d.stl: a '%' that is not the frame-number pattern; "
                   "write '%%' for a '%' in the name"),
])
def test_unwritable_outputs_are_usage_errors(tmp_path, name, message):
    status, out, err = run("--no-cpp", "-o", name, stdin=SCENE, cwd=tmp_path)
    assert status == 2
    assert last_line(err) == message
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("args, message", [
    (["-U", ""], "castor: error: -U takes a macro NAME (letters, digits and _), not ''"),
    (["-D", "2X=1"], "castor: error: -D takes NAME or NAME=VALUE with a macro NAME (letters, "
                     "digits and _, not starting with a digit), not '2X=1'"),
    (["--summary", "q.json", "--check"], "castor: error: --summary needs the frames made; "
                                         "leave out --check"),
])
def test_option_usage_errors(tmp_path, args, message):
    status, out, err = run(*args, stdin=SCENE, cwd=tmp_path)
    assert status == 2
    assert last_line(err) == message


def test_png_is_refused_until_pictures_exist(tmp_path):
    status, out, err = run("--no-cpp", "-o", "x.png", stdin=SCENE, cwd=tmp_path)
    if status == 0:
        pytest.skip("pictures are part of this castor")
    assert status == 2 and "png" in last_line(err)
    assert os.listdir(tmp_path) == []


def test_literal_percent_and_pattern(tmp_path):
    status, out, err = run("--no-cpp", "-o", "50%%-%d.off", stdin=SCENE + SCENE, cwd=tmp_path)
    assert status == 0, err
    assert sorted(os.listdir(tmp_path)) == ["50%-1.off", "50%-2.off"]


def test_one_stream_per_frame(tmp_path):
    status, out, err = run("--no-cpp", "-o", "f-%d.cps", stdin=SCENE + SCENE, cwd=tmp_path)
    assert status == 0, err
    for n in (1, 2):
        (frame,) = parse_stream((tmp_path / f"f-{n}.cps").read_text())
        assert frame.number == n


def test_full_disk_on_standard_output():
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full on this system")
    with open("/dev/full", "w") as full:
        result = subprocess.run([sys.executable, "-m", "castor", "--no-cpp"], input=SCENE,
                                stdout=full, stderr=subprocess.PIPE, text=True, timeout=60,
                                cwd=OUTSIDE)
    assert result.returncode == 2
    assert result.stderr == "castor: error: cannot write to standard output: no space left on device\n"


def test_castor_view_output_in_a_missing_directory(tmp_path):
    status, out, err = run_view("-o", "nodir/x.png", stdin="castor-polygons 1\n", cwd=tmp_path)
    assert status == 2
    assert last_line(err) == ("castor-view: error: cannot write 'nodir/x.png': the directory "
                              "'nodir' does not exist")


def test_write_failure_after_the_check_is_said_clearly(tmp_path):
    from castor.formats.output import Unwritable, write_atomically

    with pytest.raises(Unwritable, match=r"cannot write '.*gone/x.stl': no such file"):
        write_atomically(str(tmp_path / "gone" / "x.stl"), b"data")


# --- 9: a pipe whose reader has gone

def test_closed_pipe_ends_as_cat_does(tmp_path):
    write(tmp_path, "big.cas", ">[T = 1, 40] @h(T, 1, 1) !sp(0.5, 0.5, 0.5);\n")
    command = f"'{sys.executable}' -m castor big.cas 2>err.txt | head -1 >/dev/null"
    result = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=tmp_path,
                            timeout=120)
    assert result.returncode == 128 + 13  # killed by SIGPIPE, as cat is: not 1 (errors)
    assert (tmp_path / "err.txt").read_text() == ""


# --- 10: a file name with a space keeps the record's fields

def test_file_name_with_space_is_encoded(tmp_path):
    write(tmp_path, "ma maison%.cas", SCENE)
    status, out, err = run("ma maison%.cas", cwd=tmp_path, check_status=0)
    assert out.splitlines()[1] == "frame 1 ma%20maison%25.cas:1"
    assert parse_stream(out)[0].where == "ma%20maison%25.cas:1"


# --- 11: a missing ';' before a comment, --set texts

def test_missing_semicolon_before_a_comment_at_the_end(tmp_path):
    write(tmp_path, "s.cas", "a = !cu(1,1,1);\n> a // the house\n")
    for args in (["s.cas"], ["--no-cpp", "s.cas"]):
        status, out, err = run_briefly(*args, cwd=tmp_path)
        assert status == 1
        assert err.splitlines() == [
            "s.cas:2:4: error: expected ';' at the end of the statement, found the end of the input",
            " > a // the house",
            "    ^"]
        assert out == ""  # the statement in error is skipped (LANGUAGE.md §9)


def test_set_with_a_comment_does_not_hang():
    status, out, err = run_briefly("--no-cpp", "--set", "X=2 //",
                                   stdin="> @h(X, 1, 1) !cu(1,1,1);\n", seconds=20)
    assert status == 0, err
    assert parse_stream(out)[0].box()[1][0] == 2


def test_set_with_two_assignments():
    status, out, err = run("--no-cpp", "--set", "X=2; Y=3", stdin=SCENE)
    assert status == 2
    assert last_line(err) == ("castor: error: --set 'X=2; Y=3': one parameter for each --set; "
                              "write --set 'X=2' --set 'Y=3'")


# --- 15, 16: macros and includes

def test_error_in_a_macro_expansion_points_at_its_use(tmp_path):
    write(tmp_path, "e8.cas",
          "#define FEN(X, Y) @t(X, -0.1, Y) @h(1.2, 0.5) !cu(0.2, 0.4, 0.8)\n"
          "trous = $U(FEN(1, 1), @t(5, 0, 0) !cu(1, 1, 1), FEN(3, 1));\n> trous;\n")
    status, out, err = run("e8.cas", cwd=tmp_path)
    assert status == 1
    assert err.splitlines()[:8] == [
        "e8.cas:2:12: error: '@h' takes 1 or 3 arguments (K or KX, KY, KZ), but 2 were given",
        " trous = $U(FEN(1, 1), @t(5, 0, 0) !cu(1, 1, 1), FEN(3, 1));",
        "            ^",
        "e8.cas:2:12: note: in expansion of macro FEN, defined at e8.cas:1",
        "e8.cas:2:49: error: '@h' takes 1 or 3 arguments (K or KX, KY, KZ), but 2 were given",
        " trous = $U(FEN(1, 1), @t(5, 0, 0) !cu(1, 1, 1), FEN(3, 1));",
        "                                                 ^",
        "e8.cas:2:49: note: in expansion of macro FEN, defined at e8.cas:1"]


def test_error_after_a_macro_on_its_line_keeps_its_column(tmp_path):
    write(tmp_path, "s.cas", "#define ROUGE 0.8, 0.1, 0.1\n> $U(!cu(ROUGE), nothing);\n")
    status, out, err = run("s.cas", cwd=tmp_path)
    assert err.splitlines()[:3] == ["s.cas:2:18: error: object 'nothing' is not defined",
                                    " > $U(!cu(ROUGE), nothing);",
                                    "                  ^"]


def test_missing_include_is_reported_once_with_the_search_path(tmp_path):
    write(tmp_path, "lib/x.cas", "")
    write(tmp_path, "projet/maison.cas",
          '#include "couleurs.cas"\nmur = @h(4, 0.2, 3) !cu(ENDUIT);\n> mur;\n')
    status, out, err = run("-I", "lib", "projet/maison.cas", cwd=tmp_path)
    assert status == 1
    assert err.splitlines()[:3] == [
        "projet/maison.cas:1:10: error: cannot find include file 'couleurs.cas' "
        "(searched: projet, lib); give the directory that holds it with -I DIR",
        ' #include "couleurs.cas"',
        "          ^"]
    # and nothing more: '!cu(ENDUIT)' has one argument only because ENDUIT, a
    # macro of the missing file, is not defined (issue 29, item 4: one message
    # per cause; tests/language/test_one_message_per_cause.py)
    assert len(err.splitlines()) == 3, err


def test_include_is_found_beside_the_including_file(tmp_path):
    write(tmp_path, "projet/couleurs.cas", "#define ENDUIT 0.9, 0.9, 0.8\n")
    write(tmp_path, "projet/maison.cas",
          '#include "couleurs.cas"\nmur = @h(4, 0.2, 3) !cu(ENDUIT);\n> mur;\n')
    status, out, err = run("projet/maison.cas", cwd=tmp_path, check_status=0)
    assert parse_stream(out)[0].colours() == {(0.9, 0.9, 0.8)}


# --- 17, 19: habits, numbers as written

@pytest.mark.parametrize("text, expected", [
    ("l = 8;", "<stdin>:1:5: error: 'l' starts with a lowercase letter, so it names an object, "
               "and the number 8 is not an object; a parameter name starts with an uppercase "
               "letter: L = ..."),
    ("> @h(l, 2, 3) !cu(1, 1, 1);", "<stdin>:1:6: error: 'l' is not a parameter: parameter "
                                    "names start with an uppercase letter (L)"),
    ("X = 2 * larg + 1;", "<stdin>:1:9: error: 'larg' is not a parameter: parameter names "
                          "start with an uppercase letter (Larg)"),
    ("E = 0,3;", "<stdin>:1:6: error: a decimal comma? write 0.3 with a point; a comma "
                 "separates arguments"),
    ("> @h(sin 30, 1, 1) !cu(1, 1, 1);", "<stdin>:1:6: error: the function 'sin' takes its "
                                         "argument in parentheses: sin(...)"),
    ("> !cu(0.4 * 3, 0, 0);", "<stdin>:1:11: error: colour component red = 1.2 of !cu is "
                              "outside 0..1"),  # no /255 hint: 1.2 is no byte
])
def test_habits(text, expected):
    status, out, err = run("--no-cpp", stdin=text + "\n")
    assert status == 1
    assert err.splitlines()[0] == expected


# --- 18: options the scene ignores are warned about

def test_set_of_a_name_the_scene_never_uses(tmp_path):
    scene = "PENTE = 35;\n> @ry(PENTE) !cu(1, 1, 1);\n"
    status, out, err = run("--no-cpp", "--set", "PENTES=45", stdin=scene)
    assert status == 0
    assert err == ("castor: warning: --set PENTES: the scene neither assigns nor uses a "
                   "parameter 'PENTES'; did you mean 'PENTE'?\n")
    status, out, err = run("--no-cpp", "--set", "PENTE=45", stdin=scene, check_status=0)
    assert err == ""


def test_define_overridden_by_the_file_is_warned(tmp_path):
    write(tmp_path, "s.cas", "#define ENDUIT 0.9, 0.9, 0.8\n> !cu(ENDUIT);\n")
    status, out, err = run("-D", "ENDUIT=1,0,0", "s.cas", cwd=tmp_path, check_status=0)
    assert err.splitlines() == [
        "s.cas:1:1: warning: 'ENDUIT' redefined: this #define replaces -D ENDUIT=1,0,0 of the "
        "command line; to let -D choose, write #ifndef ENDUIT ... #endif around it",
        " #define ENDUIT 0.9, 0.9, 0.8",
        " ^"]
    status, out, err = run("-D", "ENDUIT=0.9, 0.9, 0.8", "s.cas", cwd=tmp_path, check_status=0)
    assert err == ""  # the same value: nothing to say
    write(tmp_path, "g.cas", "#ifndef ENDUIT\n#define ENDUIT 0.9, 0.9, 0.8\n#endif\n"
                             "> !cu(ENDUIT);\n")
    status, out, err = run("-D", "ENDUIT=1,0,0", "g.cas", cwd=tmp_path, check_status=0)
    assert err == ""  # the way to let -D choose
    assert parse_stream(out)[0].colours() == {(1, 0, 0)}


# --- 1, 3: glTF +Y up and named; OBJ named, +Y up, materials a person recognises

def glb_document(path):
    data = path.read_bytes()
    length, kind = struct.unpack_from("<II", data, 12)
    return json.loads(data[20:20 + length])


HOUSE = ("murs = @h(4, 3, 2.5) !cu(0.9, 0.9, 0.8);\n"
         "toit = @t(0, 0, 2.5) @h(4, 3, 0.2) !cu(0.7, 0.3, 0.2);\n"
         "> murs, toit, @t(6, 0, 0) !cu(0.2, 0.6, 0.2);\n")


def test_glb_is_y_up_with_named_nodes(tmp_path):
    run("--no-cpp", "-o", str(tmp_path / "h.glb"), stdin=HOUSE, check_status=0)
    document = glb_document(tmp_path / "h.glb")
    assert [n["name"] for n in document["nodes"]] == ["murs", "toit", "object3"]
    positions = document["accessors"][0]
    # scene x 0..4, y 0..3, z 0..2.5 becomes glTF x 0..4, y (up) 0..2.5, z -3..0
    assert positions["min"] == pytest.approx([0, 0, -3])
    assert positions["max"] == pytest.approx([4, 2.5, 0])
    assert [m["name"] for m in document["materials"]] == ["murs", "toit", "rgb-0.2-0.6-0.2"]


def test_obj_is_y_up_with_named_objects_and_materials(tmp_path):
    run("--no-cpp", "-o", str(tmp_path / "h.obj"), stdin=HOUSE, check_status=0)
    lines = (tmp_path / "h.obj").read_text().splitlines()
    assert [l for l in lines if l.startswith("o ")] == ["o murs", "o toit", "o object3"]
    assert [l for l in lines if l.startswith("usemtl ")] == [
        "usemtl murs", "usemtl toit", "usemtl rgb-0.2-0.6-0.2"]
    points = [list(map(float, l.split()[1:])) for l in lines if l.startswith("v ")]
    heights = [p[1] for p in points]
    assert min(heights) == 0 and max(heights) == pytest.approx(2.7)
    mtl = (tmp_path / "h.mtl").read_text()
    assert "newmtl toit\nKa 0.7 0.3 0.2\nKd 0.7 0.3 0.2\n" in mtl


# --- 20: a quantity take-off

def test_stats_line():
    status, out, err = run("--no-cpp", "--stats", stdin=HOUSE, check_status=0)
    head, seconds = err.strip().rsplit(", ", 1)
    assert head == ("castor: frame 1 <stdin>:3: 3 primitives, 0 boolean operations, "
                    "18 polygons, 24 vertices, volume 33.4, area 91.8, box 0 0 0 to 7 3 2.7")
    assert seconds.endswith(" s")


def test_summary(tmp_path):
    scene = HOUSE + "> $U(!cu(1, 0, 0), @t(3, 0, 0) !cu(1, 0, 0));\n"
    status, out, err = run("--no-cpp", "--summary", str(tmp_path / "q.json"), stdin=scene,
                           check_status=0)
    document = json.loads((tmp_path / "q.json").read_text())
    first, second = document["frames"]
    assert (first["number"], first["where"]) == (1, "<stdin>:3")
    murs, toit, other = first["objects"]
    assert murs == {"name": "murs", "volume": 30, "area": 59, "bbox": [[0, 0, 0], [4, 3, 2.5]],
                    "shells": 1, "polygons": 6,
                    "colours": [{"rgb": [0.9, 0.9, 0.8], "area": 59}]}
    assert toit["volume"] == pytest.approx(2.4) and toit["bbox"] == [[0, 0, 2.5], [4, 3, 2.7]]
    assert other["name"] == "object3" and other["volume"] == 1
    (two_cubes,) = second["objects"]
    assert two_cubes["shells"] == 2 and two_cubes["volume"] == 2 and two_cubes["area"] == 12


def test_castor_view_draws_a_glb_and_an_obj_upright(tmp_path):
    """castor-view reads +Y-up files back into the scene's z up: the same outline as
    the polygon stream from the same camera."""
    import numpy as np
    from PIL import Image

    scene = tmp_path / "h.cas"
    scene.write_text(HOUSE)
    status, stream, err = run("--no-cpp", str(scene), check_status=0)
    (tmp_path / "h.cps").write_text(stream)
    outlines = {}
    for suffix in ("cps", "glb", "obj"):
        if suffix != "cps":
            run("--no-cpp", "-o", str(tmp_path / f"h.{suffix}"), str(scene), check_status=0)
        status, out, err = run_view(str(tmp_path / f"h.{suffix}"), "-o",
                                    str(tmp_path / f"{suffix}.png"), "--size", "160x120")
        assert status == 0, err
        pixels = np.asarray(Image.open(tmp_path / f"{suffix}.png").convert("RGB")).astype(int)
        outlines[suffix] = np.abs(pixels - pixels[0, 0]).sum(axis=2) > 30
    for suffix in ("glb", "obj"):
        both = np.count_nonzero(outlines[suffix] & outlines["cps"])
        either = np.count_nonzero(outlines[suffix] | outlines["cps"])
        assert both / either > 0.95, suffix


# --- positions through macros: random macro scenes, every message on the line as written

def _macro_scene(data):
    body = data.draw(st.lists(st.sampled_from(
        ["@t(X, 0, 1)", "@h(1.2, 0.5)", "!cu(C)", "!cu(1, 1)", "nothing", "@rz(X)", "X", "C",
         ",", "(", ")", "$U(", "!sp(C)", "1"]), min_size=1, max_size=6).map(" ".join))
    use = data.draw(st.lists(st.sampled_from(
        ["F(1)", "F(2, 3)", "F()", "C", "G", "!cu(C)", " ", "$U(", ")", ",", "@t(1, 2, 3)",
         "F(F(1))", "nothing", "/* F(1) */", "// F(1)"]), min_size=1, max_size=6).map(" ".join))
    return (f"#define C 0.5, 0.5, 0.5\n#define G F(4)\n#define F(X) {body}\n"
            f"a = {use};\n> {use};\n")


LOCATION = re.compile(r"^<stdin>:(\d+):(\d+): (?:error|warning|note): ", re.M)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_macro_positions_stay_on_the_line_as_written(data):
    scene = _macro_scene(data)
    lines = scene.split("\n")
    status, _, text = run_here("--max-polygons", "20000", stdin=scene)
    assert status in (0, 1) and "internal error" not in text, (scene, text)
    if "note: in expansion of macro" in text:
        event("an error inside an expansion")
    for line, column in LOCATION.findall(text):
        assert 1 <= int(column) <= len(lines[int(line) - 1]) + 1, (scene, text)

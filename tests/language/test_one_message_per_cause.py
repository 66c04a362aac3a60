"""One message per cause (issue 29, items 2, 4 and 5).

A failed parameter, a zero scale repeated over a stair's treads, a missing
#include whose macro is then used, a macro given the wrong number of arguments:
each said once, at the place written in the file (never ``<stdin>`` for a file),
and a #define with an empty parameter is a message, not an internal error.
"""

import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
MESSAGE = re.compile(r"^(\S+?):(\d+):(\d+): (error|warning|note): ", re.M)


def castor(tmp_path, name: str, text: str, *args: str):
    (tmp_path / name).write_text(text)
    done = subprocess.run([sys.executable, "-m", "castor", "--check", *args, name],
                          cwd=tmp_path, capture_output=True, text=True, timeout=120,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})
    return done.returncode, done.stderr


def errors(text: str) -> list[str]:
    return [line for line in text.splitlines() if ": error: " in line]


def test_a_failed_parameter_is_said_once(tmp_path):
    status, err = castor(tmp_path, "h.cas",
                         "H = 3 / 0;\na = @h(H) !cu(1,1,1);\nG = H + 1;\n> a;\n"
                         "> @h(H, G, 1) !cu(1,1,1);\n>[T = 0, 1] @h(H) !cu(1,1,1);\n"
                         "H = 2;\n> a;\n> @h(Q) !cu(1,1,1);\n")
    assert status == 1
    assert errors(err) == ["h.cas:1:7: error: division by zero",
                           "h.cas:9:6: error: parameter 'Q' is not defined"], err


def test_the_frames_a_failed_parameter_leaves_unmade_are_named_in_notes(tmp_path):
    # once per cause, but never silently short of frames: each '>' that the
    # parameter left unmade says so in a note (read by vi's :make), then the
    # frames it did make are written
    status, err = castor(tmp_path, "h.cas",
                         "H = 3 / 0;\na = @h(H) !cu(1,1,1);\n> a;\n>[T = 0, 2] @h(H + T) a;\n"
                         "> !cu(1,1,1);\nH = 2;\n> a;\n")
    assert status == 1
    notes = [line for line in err.splitlines() if ": note: " in line]
    assert notes == [
        "h.cas:3:1: note: frame 1 not made: parameter 'H' has no value (its definition had "
        "errors)",
        "h.cas:4:1: note: frames 2 to 4 not made: parameter 'H' has no value (its definition "
        "had errors)"], err


def test_a_parameter_with_a_syntax_error_is_said_once(tmp_path):
    status, err = castor(tmp_path, "k.cas", "K = 3 +;\n> @h(K) !cu(1,1,1);\n")
    assert status == 1
    assert len(errors(err)) == 1 and err.startswith("k.cas:1:8: error: "), err


def test_the_same_error_in_every_tread_is_said_once(tmp_path):
    status, err = castor(tmp_path, "stair.cas",
                         "H = 0.17;\nmarche = @t(0, I * 0.28, 0) @h(1, 0.28, (I + 1) * H)"
                         " !cu(0.7, 0.7, 0.7);\n> $U[I = 0, 14](marche);\n", "--set", "H=0")
    assert status == 1
    lines = errors(err)
    assert len(lines) == 1, err
    assert lines[0].startswith("stair.cas:2:29: error: zero scale factor for z in '@h' "
                               "(flattens U1(marche) to nothing)")
    assert lines[0].endswith("(the same in operands 1 to 15 of the repetition)")


def test_errors_that_differ_between_operands_are_each_said(tmp_path):
    status, err = castor(tmp_path, "r.cas",
                         "> $U[I = 0, 3](@t(I, 0, 0) @h(1, I - 1, I - 2) !cu(1,1,1));\n")
    assert status == 1
    # I = 1 flattens y, I = 2 flattens z: two causes, each once, without a count
    assert errors(err) == [
        "r.cas:1:28: error: zero scale factor for y in '@h' (flattens U2 to nothing); use a "
        "small positive factor, or leave the object out",
        "r.cas:1:28: error: zero scale factor for z in '@h' (flattens U3 to nothing); use a "
        "small positive factor, or leave the object out"], err


def test_a_missing_include_says_nothing_of_the_arguments_its_macros_would_give(tmp_path):
    status, err = castor(tmp_path, "m.cas",
                         '#include "couleurs.cas"\nmur = @h(4, 0.2, 3) !cu(ENDUIT);\n> mur;\n'
                         "> !cu(ENDUIT);\n> !cu(1, 1);\n")
    assert status == 1
    lines = errors(err)
    assert lines[0].startswith("m.cas:1:10: error: cannot find include file 'couleurs.cas'")
    # an argument count without any unknown name is still said
    assert lines[1:] == ["m.cas:5:3: error: '!cu' takes 3 arguments (R, G, B), but 2 were given"]


def test_a_macro_given_too_many_arguments_is_said_once_at_its_use(tmp_path):
    status, err = castor(tmp_path, "macro4.cas",
                         "#define M(X) @t(X,0,0) !cu(1,1,1)\na = $U(M(1), M(1, 2));\n> a;\n")
    assert status == 1
    assert "<stdin>" not in err
    assert err.splitlines()[:3] == ["macro4.cas:2:14: error: macro M takes 1 argument, but 2 "
                                    "were given",
                                    " a = $U(M(1), M(1, 2));",
                                    "              ^"]
    assert [line for line in err.splitlines() if "macro4.cas:2:" in line] == [
        "macro4.cas:2:14: error: macro M takes 1 argument, but 2 were given"]


def test_an_error_inside_an_expansion_names_the_macro_in_a_note(tmp_path):
    status, err = castor(tmp_path, "n.cas", "#define M(X) @h(X, 1) !cu(1,1,1)\n> $U(M(1));\n")
    assert status == 1
    assert err.splitlines() == [
        "n.cas:2:6: error: '@h' takes 1 or 3 arguments (K or KX, KY, KZ), but 2 were given",
        " > $U(M(1));",
        "      ^",
        "n.cas:2:6: note: in expansion of macro M, defined at n.cas:1"]
    # every message, the note too, is FILE:LINE:COL: as vi's :make reads it
    assert [m[0] for m in MESSAGE.findall(err)] == ["n.cas", "n.cas"]


def test_a_define_with_an_empty_parameter_is_a_message(tmp_path):
    status, err = castor(tmp_path, "mur.cas",
                         "#define MUR(LX, LY,) @t(LX, LY, 0) !cu(1,1,1)\n> MUR(1, 2);\n"
                         "#define P(A,,B) @t(A, B, 0) !cu(1,1,1)\n> P(1, 2);\n")
    assert status == 1
    assert "internal error" not in err
    assert errors(err) == [
        "mur.cas:1:20: error: #define MUR: a parameter is missing before ')'; write the "
        "parameters as names between commas, as in #define MUR(X, Y)",
        "mur.cas:3:13: error: #define P: a parameter is missing before ','; write the "
        "parameters as names between commas, as in #define P(X, Y)"], err


def test_a_define_with_a_parameter_that_is_not_a_name(tmp_path):
    status, err = castor(tmp_path, "p.cas", "#define M(A, 1) !cu(1,1,1)\n")
    assert status == 1
    assert errors(err) == ["p.cas:1:14: error: #define M: '1' is not a parameter name; write "
                           "the parameters as names between commas, as in #define M(X, Y)"], err


def test_a_repetition_bracket_inside_an_expression_is_a_syntax_error(tmp_path):
    status, err = castor(tmp_path, "e.cas",
                         "E = round(sqrt(16) + cos(60) * 1e-308 [I = 0, 3] 1);\n> !cu(1,1,1);\n")
    assert status == 1
    assert errors(err) == ["e.cas:1:39: error: expected ',' or ')' after an argument, "
                           "found '['"], err


def test_a_condition_that_cannot_be_evaluated_is_said_in_castor_s_words(tmp_path):
    status, err = castor(tmp_path, "c.cas", "#if 1 +\n#endif\n> !cu(1,1,1);\n")
    assert status == 1
    assert errors(err) == ["c.cas:1:1: error: #if or #elif cannot evaluate '1 +'; write a "
                           "condition of numbers, macros, defined(NAME) and C's operators"], err

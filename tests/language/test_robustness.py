"""No input, however broken, gives a traceback, a hang or a status other than 0 or 1.

Runs castor in-process (fast enough for hundreds of cases) on generated
garbage and on mutations of real scenes; a failing case found here is kept
below as a regression test.
"""

import os
import re
import sys
import time
from pathlib import Path

import pytest

from hypothesis import HealthCheck, example, given, settings, strategies as st

from castor.pipeline import RECURSION_LIMIT
from tests.support.cli import OUTSIDE, run_here

# castor raises the recursion limit for deep scenes; raise it before hypothesis
# looks, so that running castor in-process does not change it under its feet.
sys.setrecursionlimit(RECURSION_LIMIT)

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def fuzzed(cases: int) -> int:
    """How many cases a fuzz test runs: a few hundred in the suite (it must
    stay within its eight minutes); CASTOR_FUZZ_EXAMPLES=100000 runs every one long."""
    return int(os.environ.get("CASTOR_FUZZ_EXAMPLES", cases))

SEED_SCENES = [
    "a = !cu(1, 0, 0);\nX = 2 * PI;\n> @t(X, 0, 0) @rz(45) a;\n",
    "roue = @h(0.3, 0.3, 0.1) !cy(0.1, 0.1, 0.1);\nv = $U(@h(4,1.6,1) !cu(1,0,0), @t(1,0,0) roue);\n> v;\n",
    "T = 0;\n>[T = 0, 1, 0.5] $D(@h(2) !cu(1,1,1), @t(T, 0.5, -1) @h(0.5, 0.5, 4) !cy(0,0,1));\n",
    "m = @t(0, I * 0.28, I * 0.17) @h(1.2, 0.3, 0.17) !cu(0.7,0.7,0.7);\n> $U[I = 0, 3](m);\n",
    "> $I(!sp(1,1,1), @t(0.5,0,0) !sp(1,1,1)), !ex(1,1,1, 0,0, 2,0, 2,1, 0,1);\n",
    "#define C 1, 1, 1\n/* comment */\n> !rv(C, 0,0, 1,0, 1,1, 0,2); // end\n",
]
ALPHABET = "abcxyzXYZTI!@$UDI()[],;=>+-*/%^ .0123456789e\n#\"'/_?cuspytrhmf"
MESSAGE = re.compile(r"^(<stdin>|[^:\s]+):\d+:\d+: (error|warning): ", re.M)


def run_inprocess(text: str, *args: str):
    """castor in this process (tests.support.cli.run_here), and how long it took."""
    started = time.perf_counter()
    status, out, err = run_here("--max-polygons", "20000", *args, stdin=text)
    return status, out, err, time.perf_counter() - started


def check(text: str, *args: str) -> None:
    status, out, err, elapsed = run_inprocess(text, *args)
    assert "Traceback" not in err and "internal error" not in err, (text, err)
    assert status in (0, 1), (text, status, err)
    if status == 1:
        assert MESSAGE.search(err), (text, err)
    assert elapsed < 20, (text, elapsed)
    if out:
        assert out.startswith("castor-polygons 1\n")
        # frames are whole: every 'frame' has its 'endframe'
        assert out.count("\nframe ") == out.count("\nendframe ")


@st.composite
def mutated(draw):
    text = draw(st.sampled_from(SEED_SCENES))
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["delete", "insert", "swap", "truncate", "duplicate"]))
        if not text:
            break
        i = draw(st.integers(0, len(text) - 1))
        if kind == "delete":
            j = draw(st.integers(i, min(len(text), i + 5)))
            text = text[:i] + text[j:]
        elif kind == "insert":
            text = text[:i] + draw(st.text(ALPHABET, min_size=1, max_size=4)) + text[i:]
        elif kind == "swap" and i + 1 < len(text):
            text = text[:i] + text[i + 1] + text[i] + text[i + 2:]
        elif kind == "truncate":
            text = text[:i]
        elif kind == "duplicate":
            j = draw(st.integers(i, min(len(text), i + 20)))
            text = text[:j] + text[i:j] + text[j:]
    return text


TOKENS = ["a", "b", "X", "T", "=", ";", ",", "(", ")", "[", "]", ">", "+", "-", "*", "/", "%",
          "^", "!cu", "!sp", "!cy", "!ex", "!rv", "!to", "@t", "@h", "@rz", "@m", "@f", "$U",
          "$I", "$D", "1", "0", "2.5", "1e308", "1e-308", "PI", "sin", "\n", "/*", "*/", "//"]


@settings(max_examples=fuzzed(200), deadline=None, suppress_health_check=list(HealthCheck))
@given(st.text(ALPHABET, max_size=80))
@example("> !cu(1,1,1")
@example("/*")
@example("#include")
@example("#define")
@example("#ifdef\n#endif")
@example("#undef\n#if\n")
@example('#include "')
@example("#if\n")
@example("#define A(x) A(x)\nA(1)")
@example(">[T=0,1e300,1e-300] !cu(1,1,1);")
@example("> @h(1e300) !sp(1,1,1);")
@example("> @h(1e-300) !sp(1,1,1);")
@example("> @m(1,0,0,0, 0,1,0,0, 0,0,0,0) !cu(1,1,1);")
@example("> !ex(1,1,1, 0,0, 1,0, 0,0, 1,1);")
@example("> !pr(1,1,1, 1e9);")
@example("X = 1e308 * 10;")
def test_random_text_never_crashes(text):
    check(text, "--no-cpp")


@settings(max_examples=fuzzed(200), deadline=None, suppress_health_check=list(HealthCheck))
@given(mutated())
def test_mutated_scenes_never_crash(text):
    check(text)


@settings(max_examples=fuzzed(200), deadline=None, suppress_health_check=list(HealthCheck))
@given(st.lists(st.sampled_from(TOKENS), max_size=40))
def test_token_soup_never_crashes(tokens):
    check(" ".join(tokens), "--no-cpp")


DIRECTIVES = ["#include", "#define", "#undef", "#ifdef", "#ifndef", "#if", "#elif", "#else",
              "#endif", "#error", "#warning", "#pragma", "#line", "#", "#bogus"]
NAME_CHARS = st.sampled_from(["\0", "\x01", "\x7f", "\udcff", "\u00e9", "/", "\\", '"', "<",
                              ">", "..", ".", " ", "\t", "a", "b.cas", "%", "*", "?", "\r"])


@st.composite
def directive_lines(draw):
    """A directive with a name made of odd characters (NUL bytes, quotes, slashes,
    control characters), quoted, bracketed or bare, before a statement that works."""
    lines = []
    for _ in range(draw(st.integers(1, 3))):
        name = "".join(draw(st.lists(NAME_CHARS, max_size=6)))
        opening, closing = draw(st.sampled_from([('"', '"'), ("<", ">"), ("", ""), ('"', "")]))
        lines.append(f"{draw(st.sampled_from(DIRECTIVES))} {opening}{name}{closing}")
    return "\n".join(lines) + "\n> !cu(1, 0, 0);\n"


@settings(max_examples=fuzzed(150), deadline=None, suppress_health_check=list(HealthCheck))
@given(directive_lines())
@example('#include "a\0b.cas"\n> !cu(1, 0, 0);\n')
@example('#include <a\0b>\n> !cu(1, 0, 0);\n')
@example('#include "/"\n> !cu(1, 0, 0);\n')
@example('#include ""\n> !cu(1, 0, 0);\n')
@example('#define A "a\0b"\n#include A\n> !cu(1, 0, 0);\n')
@example('#line 1 "a\0b"\n> !cu(1, 0, 0);\n')
def test_odd_names_in_directives_never_crash(text):
    check(text)


def test_deep_expression_nesting():
    check("X = " + "(" * 10000 + "1" + ")" * 10000 + ";\n> @h(X) !cu(1,1,1);\n", "--no-cpp")
    check("X = " + "-" * 10000 + "1;\n", "--no-cpp")
    check("X = " + "(" * 30000 + "1" + ")" * 30000 + ";\n", "--no-cpp")


def test_huge_repetition_is_refused():
    status, out, err, _ = run_inprocess("> $U[I = 0, 1e7](@t(I, 0, 0) !cu(1,1,1));\n", "--no-cpp")
    assert status == 1
    assert "gives 10000001 values; at most 1000000 are allowed" in err


# --- the UNIX-filter contract, with real processes ---------------------------

import subprocess  # noqa: E402
import tempfile  # noqa: E402


def _castor(*args):
    return [sys.executable, "-m", "castor", *args]


def test_reader_closing_the_pipe_is_quiet():
    scene = "> $U[I = 0, 2000](@t(2 * I, 0, 0) !cu(1, 1, 1));\n" * 3
    castor = subprocess.Popen(_castor("--no-cpp"), stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, cwd=OUTSIDE)
    castor.stdin.write(scene.encode())
    castor.stdin.close()
    head = castor.stdout.read(100)
    castor.stdout.close()  # like `| head -c 100`
    err = castor.stderr.read().decode()
    castor.wait(timeout=120)
    assert head.startswith(b"castor-polygons 1\nframe 1")
    assert err == ""
    # ended by SIGPIPE, as cat is (CLI.md): not 1, "the input had errors"
    assert castor.returncode == -13


def test_statements_run_as_they_arrive_with_no_cpp():
    castor = subprocess.Popen(_castor("--no-cpp"), stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, cwd=OUTSIDE)
    castor.stdin.write(b"a = !cu(1, 0, 0);\n> a;\n")
    castor.stdin.flush()
    # the first frame comes out while the pipe is still open
    lines = [castor.stdout.readline() for _ in range(3)]
    assert lines[0] == b"castor-polygons 1\n"
    assert lines[1].startswith(b"frame 1 <stdin>:2")
    castor.stdin.write(b"> @t(1, 0, 0) a;\n")
    castor.stdin.close()
    rest = castor.stdout.read()
    castor.wait(timeout=60)
    assert b"frame 2 <stdin>:3" in rest
    assert castor.returncode == 0


def test_deep_object_chain_stays_small():
    lines = ["a0 = !cu(1, 1, 1);"]
    lines += [f"a{i} = $U(@t(0.001, 0, 0) a{i - 1});" for i in range(1, 5000)]
    lines.append("> a4999;")
    status, out, err, _ = run_inprocess("\n".join(lines) + "\n", "--no-cpp")
    assert status == 0, err
    assert out.count("\npoly ") == 6
    assert "(a4999).U1(a4998).U1" in out


def test_union_of_a_hundred_thousand_operands():
    status, out, err, elapsed = run_inprocess(
        "> $U[I = 0, 99999](@t(2 * I, 0, 0) !cu(1, 1, 1));\n", "--no-cpp", "--max-polygons",
        "10000000")
    assert status == 0, err
    assert out.endswith("endframe 1 600000\n")


def _run_file(text: str, *args: str):
    """castor on a file: statements are parsed in batches, not one by one."""
    with tempfile.NamedTemporaryFile("w", suffix=".cas", delete=False, dir=tempfile.gettempdir()) as f:
        f.write(text)
        name = f.name
    try:
        status, out, err, _ = run_inprocess("", *args, name)
        return status, out.replace(name, "<stdin>"), err.replace(name, "<stdin>")
    finally:
        os.unlink(name)


@settings(max_examples=fuzzed(120), deadline=None, suppress_health_check=list(HealthCheck))
@given(mutated())
@example("a = !cu(1,1,1)\n> a;\n> b;\n> @t(1,0,0) a;\n")
@example("> !cu(1,1,1); ? > !cu(1,1,1);\n> !cu(1,1,1);")
@example("X = 1;\nX = ;\na = @h(X) !cu(1,1,1);\n> a\n")
@example("m = @t(0, I * 0.28, I ;/* 0.17) @h(1.2, 0.3, 0.17) !cu(0.7,0.7,0.7);\n"
         "> $U[I = 0, 3](m);\n")
def test_batches_and_streaming_agree(text):
    """Parsing many statements at once must say and write exactly what parsing
    them one by one does."""
    if "#" in text:
        return  # directives need the preprocessor; --no-cpp refuses them either way
    streamed = run_inprocess(text, "--no-cpp")[:3]
    batched = _run_file(text, "--no-cpp")
    assert batched == streamed


@pytest.mark.parametrize("args", [["--no-cpp"], []], ids=["no-cpp", "cpp"])
def test_a_frame_before_an_unterminated_comment_is_written(args):
    """A file's statements are parsed in batches; an unterminated comment ended
    the batch being read and dropped the statements read before it (the cube
    was never written, where reading the same scene statement by statement
    wrote it): every good frame is still written."""
    status, out, err = _run_file("> !cu(1, 0, 0);\n/* never closed\n", *args)
    assert status == 1
    assert out.count("\npoly ") == 6 and out.endswith("endframe 1 6\n"), out
    assert err.startswith("<stdin>:2:1: error: unterminated comment: '/*' has no matching '*/'")


# --- the preprocessor's syntax and the language's brackets together ---------
#
# Issue 29, item 2: a macro with a trailing comma in its parameters and a
# repetition bracket inside an expression were internal errors, found by a
# fuzzer whose alphabet had the preprocessor's own syntax.
CPP_WORDS = ["#define", "#undef", "#if", "#ifdef", "#ifndef", "#elif", "#else", "#endif",
             "#include", "#line", "#error", "#warning", "#pragma", "#", "##", "defined",
             "__VA_ARGS__", "...", "\\\n", "M", "M(", "N(", "X", "Y", "LX", "LY,", '"a.cas"',
             "<a>", "__LINE__", "__FILE__", "1", "0", "(", ")", ",", "&&", "||", "!", "?", ":",
             "==", "<", "'", '"']
SCENE_WORDS = ["[", "]", "(", ")", ",", ";", "=", ">", "[I = 0, 3]", "[T = 0, 1, 0.5]",
               "$U", "$I", "$D", "$U[I = 0, 3](", ">[T = 0, 1]", "!cu(1,1,1)", "!sp(", "@t(",
               "@rz(", "a", "b", "E", "I", "T", "X", "round(", "sqrt(16)", "cos(60)", "*",
               "+", "-", "/", "^", "%", "1e-308", "1e308", "2", "0", "/*", "*/", "//", "\n"]


@st.composite
def cpp_scenes(draw):
    """Lines of directives and statements drawn from both vocabularies, the
    macros they define used in the statements."""
    lines = []
    for _ in range(draw(st.integers(1, 8))):
        if draw(st.booleans()):
            head = draw(st.sampled_from(["#define M(", "#define N(X, Y) ", "#define MUR(LX, LY,) ",
                                         "#define M ", "#if ", "#ifdef ", "#endif", "#else",
                                         "#include ", "#undef ", "#line ", "#"]))
            words = draw(st.lists(st.sampled_from(CPP_WORDS + SCENE_WORDS), max_size=8))
        else:
            head = ""
            words = draw(st.lists(st.sampled_from(SCENE_WORDS + ["M", "M(1)", "N(1, 2)",
                                                                 "MUR(1, 2,)", "M(1, 2)"]),
                                  max_size=14))
        lines.append(head + " ".join(words))
    return "\n".join(lines) + "\n"


@settings(max_examples=fuzzed(150), deadline=None, suppress_health_check=list(HealthCheck))
@given(cpp_scenes())
@example("#define MUR(LX, LY,) @t(LX, LY, 0) !cu(1,1,1)\n> MUR(1, 2,);\n")
@example("E = round(sqrt(16) + cos(60) * 1e-308 [I = 0, 3] 1);\n> !cu(1,1,1);\n")
@example("#define M(X) @t(X,0,0) !cu(1,1,1)\na = $U(M(1), M(1, 2));\n> a;\n")
@example("#if !\n")  # found by this fuzzer: pcpp's IndexError on a file's first #if
def test_preprocessor_and_brackets_never_crash(text):
    check(text)
    # from a file: parsed in batches, and every message names the file, never <stdin>
    with tempfile.NamedTemporaryFile("w", suffix=".cas", delete=False,
                                     dir=tempfile.gettempdir()) as f:
        f.write(text)
    try:
        status, _, err, _ = run_inprocess("", f.name)
    finally:
        os.unlink(f.name)
    assert status in (0, 1) and "internal error" not in err, (text, err)
    assert "<stdin>" not in err or "<stdin>" in text or "#line" in text, (text, err)


def test_a_scale_whose_square_underflows_is_no_internal_error():
    """@h(1e-300): the squares of the stretch underflowed to 0 and every curved
    primitive's facet count divided by it (found by the random texts above once
    the failed frame's message named an internal error)."""
    from castor.primitives import PRIMITIVES

    sizes = {"to": "0.3", "pr": "6", "py": "5"}
    for name, declared in PRIMITIVES.items():
        if not declared.curved:
            continue
        args = [sizes.get(name, "1")] * len(declared.arguments)
        if declared.pair_names:
            args += ["0", "0", "1", "0", "1", "1", "0", "1"]
        for scale in ("1e-300", "1e-300, 1, 1", "1, 1, 1e-300"):
            text = f"> @h({scale}) !{name}({', '.join(['1', '1', '1', *args])});\n"
            status, out, err, _ = run_inprocess(text, "--no-cpp")
            assert "internal error" not in err and "Traceback" not in err, (text, err)
            assert status in (0, 1), (text, err)

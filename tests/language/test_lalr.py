"""castor's LALR driver (castor.language.lalr) reads what lark reads, as lark reads
it: the same transformer calls with the same children, tokens and places,
and it refuses what lark refuses (issue 18, item 18: reading a scene imports no
lark). Compared on the examples and on thousands of random edits of them."""

import random
import subprocess
import sys
from pathlib import Path

import pytest
from lark import Lark
from lark.exceptions import UnexpectedInput

from castor.language import tables
from castor.language.lalr import Failed, Parser
from castor.language.parse import grammar_text

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").rglob("*.cas"))


class Recorder:
    """A transformer that writes down every call: the rule and its children, tokens
    with their type and where they begin in the text."""

    def __getattr__(self, name):
        if not name.islower() or name.startswith("_"):
            raise AttributeError(name)  # no terminal callbacks, no method for _rules

        def record(children):
            return (name, tuple(_plain(c) for c in children))

        return record


def _plain(child):
    if isinstance(child, str):  # (lines and columns follow from start_pos: Builder counts them)
        return (child.type, str(child), child.start_pos)
    return child


@pytest.fixture(scope="module", params=["token by token", "plain arguments at once"])
def parsers(request):
    """lark and the driver; the driver reading every text either token by token
    (as it reads a short statement) or with each call's plain arguments read at
    once (as it reads a long one: Parser.LONG)."""
    lark = Lark(grammar_text(), transformer=Recorder(), **tables.OPTIONS)
    driver = Parser(tables.export(Lark(grammar_text(), **tables.OPTIONS)), Recorder())
    if request.param == "plain arguments at once":
        driver.LONG = 0
    else:
        driver.LONG = 10**12
    return lark, driver


def _outcome(parser, refused, text, start):
    try:
        return parser.parse(text, start=start)
    except refused:
        return "refused"


def _same(parsers, text, start="program"):
    lark, driver = parsers
    expected = _outcome(lark, UnexpectedInput, text, start)
    got = _outcome(driver, Failed, text, start)
    assert got == expected, text


def _scene_text(path: Path) -> str:
    """The example as the parser reads it: after the preprocessor, in statements."""
    from castor.diagnostics import CollectingReporter
    from castor.pipeline import statements
    from castor.settings import ReadSettings, Source

    chunks = statements(Source(files=(str(path),)), ReadSettings(), CollectingReporter())
    return "".join(chunk.text for chunk in chunks)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_the_driver_reads_each_example_as_lark_does(parsers, path):
    text = _scene_text(path)
    lark, driver = parsers
    assert driver.parse(text, start="program") == lark.parse(text, start="program")
    for statement in text.split(";")[:300]:
        _same(parsers, statement + ";", "statement")


PIECES = ["(", ")", ",", ";", "=", "[", "]", "!cu", "@t", "$U", "$D", "> ", "-", "^", "*", "1.5e3",
          ".5", "X", "x", " ", "\n", "/* c */", "// c\n", "/*", "\t", "$", "!", "@", "#", "é", "3."]


def test_the_driver_refuses_what_lark_refuses_and_reads_the_rest_alike(parsers):
    rng = random.Random(18)
    texts = [_scene_text(p) for p in EXAMPLES]
    statements = [s + ";" for t in texts for s in t.split(";") if s.strip()]
    for _ in range(4000):
        text = rng.choice(statements)
        for _ in range(rng.randint(1, 3)):
            at = rng.randrange(len(text) + 1)
            if rng.random() < 0.5 and text:
                text = text[:at] + text[at + rng.randint(1, 3):]
            else:
                text = text[:at] + rng.choice(PIECES) + text[at:]
        _same(parsers, text, rng.choice(["statement", "statement", "program"]))


def test_comments_and_newlines_place_tokens_as_lark_does(parsers):
    for text in ["/* a\nb */ X = 1;", "x =\n\n  @t(1,\n 2, 3) // c\n !cu(1, 1, 1);",
                 "> [T = 0, 1, 0.5]\r\n x;", "X = -2 ^ 2 ^ 3 * (4 - 1) % 5;", "", "  \n ",
                 "x = !ex(1, 1, 1, 0, 0, 1, 0, 1, 1);", "x = f();", "X = f(;"]:
        _same(parsers, text, "program")
        _same(parsers, text, "statement")


ARGUMENTS = ["1, 2, 3", " 1 ,2 ,3 ", "\n-1,\t+ 2,-X", "H", "-H, 0", "1.5e3, .5, 3., 1e-3, 1E+3",
             "", "1,", ",1", "1 2", "--1", "- - 1", "1e", "1.5.3", "X1, x1", "٣, 4", "1 /* c */, 2",
             "1, // c\n 2", "2 * H, 1", "f(1), 2", "(1), 2", "1 ^ 2, 3", "X(1)", "-(1)", "1, X Y"]


def test_a_call_s_plain_arguments_read_at_once_are_read_as_lark_reads_them(parsers):
    _, driver = parsers
    _same(parsers, "x = !cu(1, 1, 1);", "statement")
    if driver.LONG == 0:
        assert driver._before_open  # the calls of a transformation, a primitive, a function
    for arguments in ARGUMENTS:
        for statement in (f"x = @t({arguments}) !cu({arguments});",
                          f"X = sin({arguments}) + 1;",
                          f"x = $U(@t ({arguments})\n!cu( {arguments} ), @r({arguments}) y);"):
            _same(parsers, statement, "statement")
            _same(parsers, statement, "program")


def test_tables_exported_from_lark_s_saved_tables_are_those_of_the_grammar(tmp_path):
    """A checkout's first run exports the tables from lark's parser as loaded from
    lark's cache or the shipped tables: they read as those of a parser built anew
    (lark numbers its states in no fixed order, so the tables are compared by what
    they read)."""
    tables.save(tmp_path / "castor.tables")
    assert (tmp_path / "castor.lalr").stat().st_size > 1000  # save writes both
    loaded = tables.load(grammar_text(), None, tmp_path / "castor.tables")
    from_loaded = Parser(tables.export(loaded), Recorder())
    from_built = Parser(tables.export(Lark(grammar_text(), **tables.OPTIONS)), Recorder())
    for path in EXAMPLES:
        text = _scene_text(path)
        assert from_loaded.parse(text, "program") == from_built.parse(text, "program")


def test_plain_tables_of_another_grammar_or_another_user_are_not_read(tmp_path):
    built = Lark(grammar_text(), **tables.OPTIONS)
    target = tmp_path / "castor.lalr"
    assert tables.save_plain(target, built, grammar_text())
    assert tables.load_plain(grammar_text(), Recorder(), [target]) is not None
    assert tables.load_plain(grammar_text() + "\n// edited\n", Recorder(), [target]) is None
    target.write_bytes(target.read_bytes()[:-40])  # cut short
    assert tables.load_plain(grammar_text(), Recorder(), [target]) is None
    assert tables.load_plain(grammar_text(), Recorder(), [tmp_path / "absent"]) is None


def test_a_scene_is_read_without_importing_lark_and_its_syntax_error_still_says_why(tmp_path):
    """With the plain tables (kept in the temporary directory by the first run of a
    checkout), a correct scene never imports lark; a syntax error is worded from
    lark's exception as before."""
    code = ("import sys; sys.argv[0] = 'castor'; from castor import cli\n"
            "try:\n    cli.main(sys.argv[1:])\nexcept SystemExit:\n    pass\n"
            "print('LARK', 'lark' in sys.modules, file=sys.stderr)\n")
    env = {"PYTHONPATH": str(ROOT), "TMPDIR": str(tmp_path), "PATH": "/usr/bin:/bin"}
    runs = [subprocess.run([sys.executable, "-c", code, "--no-cpp", "-"], input=scene,
                           capture_output=True, text=True, env=env, timeout=120)
            for scene in ("> !cu(1, 0, 0);\n", "> !cu(1, 0, 0);\n",
                          "x = @t(1, 2 !cu(1, 0, 0);\n> x;\n")]
    first, second, wrong = runs
    assert "endframe 1 6" in first.stdout and "endframe 1 6" in second.stdout
    if not (ROOT / "castor" / "language" / "castor.lalr").exists():  # a checkout's tables not built
        assert "LARK True" in first.stderr  # the first run builds the tables with lark, once
    assert "LARK False" in second.stderr, second.stderr
    assert "<stdin>:1:13: error: expected ',' or ')' after an argument, found '!cu'" in wrong.stderr
    assert "object 'x' is not defined (its definition had errors)" in wrong.stderr


def test_an_installed_castor_reads_a_scene_without_lark_from_its_first_run(tmp_path):
    """setup.py's build step (what `pip install .` runs) ships the driver's tables:
    with an empty temporary directory, a correct scene imports no lark."""
    build = tmp_path / "build"
    done = subprocess.run([sys.executable, "setup.py", "-q", "build_py", "--build-lib", str(build)],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert (build / "castor" / "language" / "castor.lalr").stat().st_size > 1000
    (tmp_path / "tmp").mkdir()
    code = ("import sys; sys.argv[0] = 'castor'; from castor import cli\n"
            "try:\n    cli.main(sys.argv[1:])\nexcept SystemExit:\n    pass\n"
            "print('LARK', 'lark' in sys.modules, cli.__file__, file=sys.stderr)\n")
    env = {"PYTHONPATH": str(build), "TMPDIR": str(tmp_path / "tmp"), "PATH": "/usr/bin:/bin"}
    cube = subprocess.run([sys.executable, "-c", code, "--no-cpp", "-"], input="> !cu(1, 0, 0);\n",
                          capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
    assert "endframe 1 6" in cube.stdout, cube.stderr
    assert f"LARK False {build}" in cube.stderr, cube.stderr
    assert list((tmp_path / "tmp").iterdir()) == []  # nothing kept: the package has them


def test_plain_arguments_are_read_token_by_token_where_the_grammar_reduces_more():
    # 'power: primary' a rule of its own (not '?power'): a callback more between a
    # number and the list, which the arguments read at once would miss
    grammar = grammar_text().replace("?power: primary\n", "power: primary\n")
    assert grammar != grammar_text()
    lark = Lark(grammar, transformer=Recorder(), **tables.OPTIONS)
    driver = Parser(tables.export(Lark(grammar, **tables.OPTIONS)), Recorder())
    driver.LONG = 0
    text = "x = @t(1, -X, 2) !cu(1, 0, 0);"
    assert driver.parse(text, start="statement") == lark.parse(text, start="statement")
    assert driver._before_open == {}

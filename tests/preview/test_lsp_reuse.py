"""What the editing loop remembers between two evaluations, and that it never
gives another result than a fresh run: the preprocessor's pass
(castor.language.preprocess: remembered, or patched for an edit of plain
lines) and the parsed statements (castor.analysis.reuse)."""

from __future__ import annotations

import random
import re
import shutil
from pathlib import Path

import pytest

from castor.diagnostics import CollectingReporter
from castor.language import preprocess as pp
from castor.analysis import reuse
from castor.analysis.scene import analyse
from castor.settings import EvaluationSettings, Source

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture
def scene(tmp_path: Path, monkeypatch) -> Path:
    shutil.copy(EXAMPLES / "house.cas", tmp_path / "house.cas")
    shutil.copy(EXAMPLES / "bus_shelter.cas", tmp_path / "bus_shelter.cas")
    shutil.copytree(EXAMPLES / "bus_shelter", tmp_path / "bus_shelter")
    monkeypatch.chdir(tmp_path)
    pp._cache.clear()
    pp._latest.clear()
    reuse.forget()
    return tmp_path


def _pass(name: str, text: str, defines=()):
    reporter = CollectingReporter(False)
    included: list[str] = []
    out = pp.preprocess([(name, text)], list(defines), [], [], reporter, included)
    return out, included, [d.message for d in reporter.diagnostics]


def _as_read(result):
    """What the reader takes from an output: each line that is not blank, with the
    file and line it comes from (by the #line markers); the messages and files."""
    out, included, messages = result
    seen, file, number = [], None, 0
    for line in out.split("\n"):
        marker = re.match(r'#line (\d+) "(.*)"$', line)
        if marker:
            file, number = marker[2], int(marker[1])
            continue
        if line.strip():
            seen.append((file, number, line))
        number += 1
    return seen, included, messages


def _fresh(name: str, text: str, defines=()):
    pp._cache.clear()
    pp._latest.clear()
    return _pass(name, text, defines)


def _counting(monkeypatch) -> dict:
    counts = {"runs": 0, "patched": 0}
    run, patched = pp.run_pass, pp._patched

    def counted_run(*args):
        counts["runs"] += 1
        return run(*args)

    def counted_patched(*args):
        found = patched(*args)
        counts["patched"] += found is not None
        return found

    monkeypatch.setattr(pp, "run_pass", counted_run)
    monkeypatch.setattr(pp, "_patched", counted_patched)
    return counts


def test_the_same_sources_are_not_preprocessed_again(scene: Path, monkeypatch):
    counts = _counting(monkeypatch)
    text = (scene / "bus_shelter.cas").read_text()
    first = _pass("bus_shelter.cas", text)
    assert _pass("bus_shelter.cas", text) == first
    assert counts == {"runs": 1, "patched": 0}
    assert len(first[1]) == 7  # the seven files it includes, given again


def test_an_included_file_changed_on_disk_is_read_again(scene: Path, monkeypatch):
    counts = _counting(monkeypatch)
    text = (scene / "bus_shelter.cas").read_text()
    _pass("bus_shelter.cas", text)
    colours = scene / "bus_shelter" / "colours.cas"
    colours.write_text(colours.read_text() + "\n#define NEW_COLOUR 1, 0, 0\n")
    out, _, _ = _pass("bus_shelter.cas", text.replace("PHASE = 0;", "PHASE = 0;\nc = !cu(NEW_COLOUR);"))
    assert counts["runs"] == 2
    assert "c = !cu(1, 0, 0);" in out


def test_a_file_that_appears_where_one_was_looked_for_first(scene: Path, monkeypatch):
    (scene / "lib").mkdir()
    (scene / "lib" / "part.cas").write_text("#define SIZE 1\n")
    main = '#include "part.cas"\nx = !cu(SIZE, SIZE, SIZE);\n'
    reporter = CollectingReporter(True)
    out = pp.preprocess([("main.cas", main)], [], [], ["lib"], reporter, [])
    assert "!cu(1, 1, 1)" in out
    (scene / "part.cas").write_text("#define SIZE 2\n")  # beside the scene: found first
    out = pp.preprocess([("main.cas", main)], [], [], ["lib"], reporter, [])
    assert "!cu(2, 2, 2)" in out


def test_a_pass_with_a_warning_says_it_each_time(scene: Path):
    text = "#warning look here\nx = !cu(1, 1, 1);\n"
    assert _pass("w.cas", text)[2] == ["#warning look here"]
    assert _pass("w.cas", text)[2] == ["#warning look here"]


def test_an_edit_of_plain_lines_is_patched_as_a_full_pass_gives_it(scene: Path, monkeypatch):
    counts = _counting(monkeypatch)
    text = (scene / "bus_shelter.cas").read_text()
    house = (scene / "house.cas").read_text()
    edits = [
        ("bus_shelter.cas", text, text.replace("PHASE = 0;", "PHASE = 0;\nX1 = 1;")),  # moves lines
        ("bus_shelter.cas", text, text.replace("PHASE = 0;", "PHASE = 1;")),
        ("bus_shelter.cas", text, text.replace("arret = $U(decor, feu);\n", "")),
        ("bus_shelter.cas", text, text.replace("PHASE = 0;", "PHASE = 0;\n\n\nY = 2;\n")),
        ("house.cas", house, house + "\nz = !cu(1, 1, 1);\n"),  # at the end
        ("house.cas", house, house.replace("H = 2.9;", "H = 3.2;")),
    ]
    for name, old, edited in edits:
        _fresh(name, old)
        counts["patched"] = 0
        patched = _pass(name, edited)
        assert counts["patched"] == 1, edited
        assert _as_read(patched) == _as_read(_fresh(name, edited))


def test_what_cannot_be_patched_is_preprocessed_again(scene: Path, monkeypatch):
    counts = _counting(monkeypatch)
    text = (scene / "bus_shelter.cas").read_text()
    edits = [
        text.replace("PHASE = 0;", "PHASE = 0;\n#define W 2"),  # a directive
        text.replace("PHASE = 0;", "PHASE = TEINTE;"),  # a macro's name
        text.replace("PHASE = 0;", "PHASE = 0; /* a comment opened"),
        text.replace("> arret;", "> decor;"),  # in a block #ifdef leaves out
        "\n" + text,  # the empty lines at a file's start, which pcpp drops
    ]
    for edited in edits:
        _fresh("bus_shelter.cas", text)
        counts["patched"] = 0
        assert _as_read(_pass("bus_shelter.cas", edited)) == \
            _as_read(_fresh("bus_shelter.cas", edited))
        assert counts["patched"] == 0, edited


@pytest.mark.parametrize("seed", [1, 2])
def test_random_edits_give_what_a_full_pass_gives(scene: Path, seed: int):
    rng = random.Random(seed)
    pieces = ["", "\t", "X = 1;", "a = !cu(1, 1, 1);", "// note", "#define Q 2", "Q", "H",
              "/* c */", "/* open", "close */", "b = @t(1, 2, 3) a;", '"s"', "__LINE__",
              "/* M */ c = a;", "x = 2; // M", "  "]
    for name in ("bus_shelter.cas", "house.cas"):
        base = (scene / name).read_text()
        for _ in range(25):
            lines = base.split("\n")
            for _ in range(rng.randint(1, 3)):
                k = rng.randrange(len(lines) + 1)
                what = rng.random()
                if what < 0.4:
                    lines.insert(k, rng.choice(pieces))
                elif what < 0.7 and k < len(lines):
                    del lines[k]
                elif k < len(lines):
                    lines[k] += rng.choice(pieces)
            edited = "\n".join(lines)
            _fresh(name, base)
            assert _as_read(_pass(name, edited)) == _as_read(_fresh(name, edited)), edited


def test_a_slider_change_parses_nothing_again(scene: Path):
    source = Source(("house.cas",))
    first = analyse(source)
    again = analyse(source, evaluation=EvaluationSettings(overrides={"H": 3.5}))
    assert again.parameters["H"] == 3.5 and first.parameters["H"] == 2.9
    assert [d.message for d in again.diagnostics] == [d.message for d in first.diagnostics]
    assert again.objects["murs"] is first.objects["murs"]  # the same node: not parsed again


def test_a_changed_definition_is_parsed_again_with_what_uses_it(scene: Path):
    text = "a = !cu(1, 1, 1);\nb = @t(1, 0, 0) a;\nc = !cu(0, 0, 1);\n> $U(b, c);\n"
    first = analyse(Source(text=text, name="s.cas"))
    second = analyse(Source(text=text.replace("a = !cu(1, 1, 1)", "a = @h(2, 2, 2) !cu(1, 1, 1)"),
                            name="s.cas"))
    assert second.objects["a"] is not first.objects["a"]
    assert second.objects["b"] is not first.objects["b"]  # it names the new 'a'
    assert second.objects["b"].child.child is second.objects["a"]
    assert second.objects["c"] is first.objects["c"]  # unchanged, reused
    # the figures follow the new definition
    from castor.analysis.scene import object_figures

    assert object_figures(second, "b")["objects"][0]["volume"] == pytest.approx(8.0)
    assert object_figures(first, "b")["objects"][0]["volume"] == pytest.approx(1.0)


def test_errors_are_said_again_each_time(scene: Path):
    text = "a = !cu(1, 1);\nb = @t(1, 0, 0) z;\n> b;\n"
    for _ in range(2):
        messages = [d.message for d in analyse(Source(text=text, name="e.cas")).diagnostics]
        assert any("'!cu' takes 3 arguments" in m for m in messages)
        assert any("object 'z' is not defined" in m for m in messages)

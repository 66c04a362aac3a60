"""One long statement is read in work that grows as the statement (issue 29, item
11: one statement of 40,000 cubes took 5 to 6.6 s to analyse, and the language
server answered the last of five quick edits 13 s after it).

The work is counted, not timed: the calls each function of the analysis makes
(cProfile's counts) for a statement and for the same statement twice as long,
and the elements copied where the names a statement reads are gathered.
benchmarks/long_statement.py and benchmarks/lsp_long_statement.py give the times.
"""

import cProfile
import gc
import pstats
import sys
import threading

import pytest

from castor.analysis import knowledge
from castor.analysis.reuse import forget
from castor.analysis.scene import analyse
from castor.diagnostics import Location
from castor.language.parse import Parser
from castor.language.reader import Chunk
from castor.language.scene import ObjectDef, Tables
from castor.settings import Source


def _cubes(count: int) -> str:
    """One definition of the union of ``count`` moved cubes, as the user wrote
    it (and benchmarks/long_statement.py), with a parameter and an expression in
    some, then its frame."""
    operands = ", ".join(f"@t({k % 200}, {k // 200} * H, 0) !cu(0.{k % 10}, 0, 0)"
                         for k in range(count))
    return f"H = 1.5;\nbig = $U({operands});\n> big;\n"


def _on_a_large_stack(work):
    """What ``work()`` gives, run on a thread with room for deep recursion (as
    castor runs an analysis)."""
    result = []
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(max(limit, 20_000))
    previous = threading.stack_size(256 * 1024 * 1024)
    try:
        thread = threading.Thread(target=lambda: result.append(work()))
        thread.start()
        thread.join()
    finally:
        threading.stack_size(previous)
        sys.setrecursionlimit(limit)
    return result[0]


def _calls(text: str) -> dict:
    """How many times each function was called while ``text`` was analysed."""
    forget()  # no statement remembered from an earlier analysis

    def profiled():
        # no collection inside: its weak-reference callbacks (_weakrefset._remove,
        # set.discard) run wherever it happens to start, and are not the analysis's calls
        gc.collect()
        gc.disable()
        try:
            profile = cProfile.Profile()
            profile.enable()
            analysis = analyse(Source(text=text, name="long.cas"))
            profile.disable()
        finally:
            gc.enable()
        assert analysis.diagnostics == []
        assert [d.name for d in analysis.definitions] == ["H", "big", ">"]
        return {key: entry[1] for key, entry in pstats.Stats(profile).stats.items()}

    return _on_a_large_stack(profiled)


def test_the_analysis_of_a_long_statement_does_twice_the_work_for_twice_the_statement():
    analyse(Source(text=_cubes(10), name="long.cas"))  # the parser's tables loaded, once
    once, twice = _calls(_cubes(1_500)), _calls(_cubes(3_000))
    assert sum(twice.values()) <= 2.05 * sum(once.values())
    grown = {f"{key[0].rsplit('/', 1)[-1]}:{key[2]}": (once.get(key, 0), count)
             for key, count in twice.items() if count > 2 * once.get(key, 0) + 20}
    assert grown == {}, grown  # no function called more than twice as often
    # and each cube costs a few hundred calls (its 17 tokens read, the 23 rules they
    # make reduced, its node checked by the evaluator), not one per cube before it
    assert sum(once.values()) < 1_500 * 500


class _Counted(frozenset):
    """A parameter's names, counting the elements the sets made from it copy."""

    copied = 0

    def _union(self, other):
        _Counted.copied += len(self) + len(other)
        return frozenset.union(self, other)

    __or__ = __ror__ = union = _union


def _transformed(count: int) -> Chunk:
    """An object moved by ``count`` steps, each by a parameter of its own."""
    steps = " ".join(f"@t(X{k}, 0, 0)" for k in range(count))
    return Chunk(f"x = {steps} !cu(1, 0, 0);", (("steps.cas", 1),), 0)


@pytest.mark.parametrize("count", [500, 2_000])
def test_the_names_a_long_run_of_steps_reads_are_gathered_once(count):
    """Each step's names were added to the names gathered so far, a new set each
    time: quadratic (20,000 steps, 5.7 s of parsing)."""
    parser = Parser(Tables())
    parser.param_sets.update((f"X{k}", _Counted((f"X{k}",))) for k in range(count))
    _Counted.copied = 0
    made = _on_a_large_stack(lambda: list(parser.parse(_transformed(count))))
    assert [type(m) for m in made] == [ObjectDef]
    assert made[0].node.params == {f"X{k}" for k in range(count)}
    assert _Counted.copied <= 4 * count


def test_a_diagnostic_s_range_splits_the_text_once_not_once_per_diagnostic():
    """Each diagnostic's range split the whole text into lines again: a thousand
    ranges in a 1 MB scene, 3.3 s."""
    text = "\n".join(f"X{k} = {k}; // a line of a scene" for k in range(30_000))
    profile = cProfile.Profile()
    profile.enable()
    ends = [knowledge.token_end(text, Location("a.cas", k + 1, 1)) for k in range(1_000)]
    profile.disable()
    splits = sum(entry[1] for key, entry in pstats.Stats(profile).stats.items()
                 if key[2] == "<method 'split' of 'str' objects>")
    assert ends[:2] == [3, 3] and ends[10] == 4  # X0, X1 ... X10: the name's end
    assert splits <= 1


def test_a_long_statement_s_plain_argument_lists_are_read_at_once_and_no_key_is_made(
        monkeypatch):
    """The driver reads a long statement's plain argument lists (numbers and
    parameters, signed or not) with one match each, not token by token; and the
    analysis never works out a shared subtree's content key (a digest of its
    40,000 primitives, which only the facetizer asks)."""
    from castor.csg import tree
    from castor.language import lalr

    read = []
    original = lalr.Parser._arguments

    def counted(self, text, pos):
        found = original(self, text, pos)
        read.append(found is not None)
        return found

    monkeypatch.setattr(lalr.Parser, "_arguments", counted)
    keys = []
    monkeypatch.setattr(tree, "content_key", lambda *args: keys.append(args) or "key")
    forget()
    analysis = _on_a_large_stack(lambda: analyse(Source(text=_cubes(1_500), name="long.cas")))
    assert analysis.diagnostics == []
    # each cube's '@t(k, k * H, 0)' read token by token, its '!cu(0.k, 0, 0)' at once
    assert (read.count(True), read.count(False)) == (1_500, 1_500)
    assert keys == []

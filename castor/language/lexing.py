"""The root lexer's expression reordered for speed, with a proof that it reads
every text as before (issue 29, item 11).

The root lexer (castor.language.lalr) is one expression: the terminals' own as
alternatives, in lark's order; at each position the first alternative that
matches wins. A long statement is mostly punctuation and blanks (``, `` after
each number), which lark's order tries after eleven other terminals. Here:

* a terminal is tried before one that lark tries before it only where the two
  can never match from the same position (proven by the first characters of
  one of them: a known, finite set that the other cannot start with; neither
  may match nothing). Then at any position the terminal that won still wins;
  the punctuation comes first;
* an ignored terminal that no other terminal may start where it does, and
  that has no group of its own (the blanks, WS) is also read, at most once,
  before the alternatives, as part of the next token's match (``(?:WS)?(?:...)``), which spares a match and a turn of the
  parser's loop per run of blanks. The token then begins at its group, not at
  the match (``Match.start(kind)``).

The analysis reads the expressions as Python's ``re`` parses them and answers
"can this terminal start with this character?" conservatively: yes wherever it
is not sure. tests/language/test_lexing.py checks that it proves the order for
grammar/castor.lark, so that a change of the grammar that breaks the proof
(and so would lose the speed, never the meaning) fails a test.
"""

from __future__ import annotations

import re
from re import _constants as c  # type: ignore[attr-defined]
from re import _parser as sre  # type: ignore[attr-defined]

_NAMED = re.compile(r"\(\?P<(\w+)>")
_CATEGORIES = {c.CATEGORY_DIGIT: r"\d", c.CATEGORY_NOT_DIGIT: r"\D", c.CATEGORY_SPACE: r"\s",
               c.CATEGORY_NOT_SPACE: r"\S", c.CATEGORY_WORD: r"\w", c.CATEGORY_NOT_WORD: r"\W"}
_REPEATS = {c.MAX_REPEAT, c.MIN_REPEAT, getattr(c, "POSSESSIVE_REPEAT", c.MAX_REPEAT)}
_ZERO_WIDTH = {c.AT, c.ASSERT, c.ASSERT_NOT}
_LARGEST_SET = 64  # a first set larger than this is taken as unknown


def alternatives(pattern: str, flags: int):
    """The named alternatives of the root expression, [(name, text)], or None
    where it is not ``(?P<A>...)|(?P<B>...)|...`` as lark writes it."""
    pieces = pattern.split("|(?P<")
    pieces = pieces[:1] + ["(?P<" + p for p in pieces[1:]]
    found = []
    for piece in pieces:
        named = _NAMED.match(piece)
        if named is None or not piece.endswith(")"):
            return None
        try:
            parsed = sre.parse(piece, flags)
        except re.error:
            return None
        if list(parsed.state.groupdict) != [named.group(1)]:
            return None
        found.append((named.group(1), piece))
    return found


def _nullable(seq) -> bool:
    return all(_item_nullable(op, av) for op, av in seq)


def _item_nullable(op, av) -> bool:
    if op in (c.LITERAL, c.NOT_LITERAL, c.ANY, c.IN):
        return False
    if op is c.SUBPATTERN:
        return _nullable(av[-1])
    if op is c.BRANCH:
        return any(_nullable(s) for s in av[1])
    if op in _REPEATS:
        return av[0] == 0 or _nullable(av[2])
    return True  # zero width, or unknown: may match nothing


def _in_set(items, char: str) -> bool:
    negate, hit = False, False
    for op, av in items:
        if op is c.NEGATE:
            negate = True
        elif op is c.LITERAL:
            hit = hit or chr(av) == char
        elif op is c.RANGE:
            hit = hit or av[0] <= ord(char) <= av[1]
        elif op is c.CATEGORY and av in _CATEGORIES:
            hit = hit or re.match(_CATEGORIES[av], char) is not None
        else:
            return True  # unknown: may
    return hit != negate


def can_start(seq, char: str) -> bool:
    """Whether the parsed expression may match a text beginning with ``char``, or
    match nothing (then it may win anywhere): True where unsure."""
    for op, av in seq:
        if _item_starts(op, av, char):
            return True
        if not _item_nullable(op, av):
            return False
    return True  # it may match nothing


def _item_starts(op, av, char: str) -> bool:
    if op is c.LITERAL:
        return chr(av) == char
    if op is c.NOT_LITERAL:
        return chr(av) != char
    if op is c.IN:
        return _in_set(av, char)
    if op is c.SUBPATTERN:
        add_flags = av[1]
        return bool(add_flags & re.IGNORECASE) or _starts_all(av[-1], char)
    if op is c.BRANCH:
        return any(_starts_all(s, char) for s in av[1])
    if op in _REPEATS:
        return av[1] != 0 and _starts_all(av[2], char)
    if op in _ZERO_WIDTH:
        return False  # it reads nothing: what follows it decides
    return True  # ANY, back-references, ...: may


def _starts_all(seq, char: str) -> bool:
    """can_start, but without the 'matches nothing' answer (the caller asks
    whether what follows may start instead)."""
    for op, av in seq:
        if _item_starts(op, av, char):
            return True
        if not _item_nullable(op, av):
            return False
    return False


def first_set(seq):
    """The characters a match of the parsed expression may begin with, where
    that is a small known set and it never matches nothing; else None."""
    chars: set[str] = set()
    for op, av in seq:
        if op is c.LITERAL:
            chars.add(chr(av))
        elif op is c.IN:
            if any(o not in (c.LITERAL, c.RANGE) for o, _ in av):
                return None
            for o, a in av:
                if o is c.LITERAL:
                    chars.add(chr(a))
                elif a[1] - a[0] >= _LARGEST_SET:
                    return None
                else:
                    chars.update(chr(x) for x in range(a[0], a[1] + 1))
        elif op is c.SUBPATTERN and not av[1] & re.IGNORECASE:
            inner = first_set(av[-1])
            if inner is None:
                return None
            chars |= inner
        elif op is c.BRANCH:
            for s in av[1]:
                inner = first_set(s)
                if inner is None:
                    return None
                chars |= inner
        elif op in _REPEATS and av[0] >= 1:
            inner = first_set(av[2])
            if inner is None:
                return None
            chars |= inner
        else:
            return None
        if len(chars) > _LARGEST_SET:
            return None
        return frozenset(chars)  # the first item reads a character: it decides
    return None  # empty: matches nothing


def _disjoint(a, b) -> bool:
    """Whether no text may be matched by both parsed expressions from one
    position (proven through the first characters of one of them)."""
    for one, other in ((a, b), (b, a)):
        firsts = first_set(one)
        if firsts is not None and not any(can_start(other, ch) for ch in firsts):
            return True
    return False


def faster_order(pieces, flags: int) -> list[str]:
    """The names of the terminals in the order to try them (module docstring):
    those of a known set of first characters first, the shortest expressions
    (punctuation) first among them, where no terminal passes one before it
    in lark's order that may match from the same position."""
    if flags & re.IGNORECASE:
        return [name for name, _ in pieces]
    parsed = [sre.parse(text, flags).data for _, text in pieces]
    sizes = []
    for seq in parsed:
        firsts = first_set(seq)
        sizes.append(_LARGEST_SET + 1 if firsts is None else len(firsts))
    disjoint: dict = {}

    def apart(a: int, b: int) -> bool:
        if (a, b) not in disjoint:
            disjoint[a, b] = disjoint[b, a] = _disjoint(parsed[a], parsed[b])
        return disjoint[a, b]

    left, chosen = list(range(len(pieces))), []
    while left:  # the earliest one left may always come next: some one is taken
        index = min((i for i in left if all(apart(i, j) for j in left if j < i)),
                    key=lambda i: (sizes[i] > _LARGEST_SET, len(pieces[i][1]), i))
        left.remove(index)
        chosen.append(pieces[index][0])
    return chosen


def order(pattern: str, flags: int, ignored) -> tuple[str, str]:
    """The root expression's alternatives reordered (faster_order) and the prefix
    read before them (the ignored terminals that no other may start like and
    without groups of their own, '' if none): the same tokens, the same types,
    from any position; lark's order where it cannot be proven."""
    pieces = alternatives(pattern, flags)
    if pieces is None:
        return pattern, ""
    names = faster_order(pieces, flags)
    texts = dict(pieces)
    skipped = []
    parsed = {name: sre.parse(text, flags).data for name, text in pieces}
    for name, text in pieces:
        if name not in ignored:
            continue
        inner = text[len(f"(?P<{name}>"):-1]
        firsts = first_set(parsed[name])
        others = [seq for other, seq in parsed.items() if other != name]
        # no other terminal may start where it does, so that it wins there in
        # any order; and it has no group of its own
        if (firsts is not None and not any(can_start(s, ch) for s in others for ch in firsts)
                and sre.parse(inner, flags).state.groups == 1):
            skipped.append(inner)
    prefix = f"(?:{'|'.join(skipped)})?" if skipped else ""
    return "|".join(texts[name] for name in names), prefix




class Arguments:
    """What castor.language.lalr needs to read a call's plain arguments at once:
    ``whole``, an expression that matches blanks, the "(", the arguments and the
    ")" of such a list, or nothing; then, to take the list apart with string
    operations, the ``opening`` parenthesis and the ``separator`` (the comma:
    one character each), the ``blanks`` (the characters of the blanks, any run of
    which is one blank token), the ``signs`` (each a sign token of its own) and
    the characters that start the second kind of value (``names``: a parameter;
    any other starts the first kind, a number)."""

    __slots__ = ("whole", "opening", "separator", "blanks", "signs", "names")

    def __init__(self, whole: str, opening: str, separator: str, blanks: str,
                 signs: frozenset, names: frozenset):
        self.whole, self.opening, self.separator = whole, opening, separator
        self.blanks, self.signs, self.names = blanks, signs, names


def arguments(pattern: str, flags: int, ignored, opening: str, punctuation: tuple[str, str],
              signs: str, values: tuple[str, str]) -> Arguments | None:
    """How to read a call's plain arguments as the root lexer reads their tokens
    (``Arguments``): in parentheses (``opening``, then ``punctuation[1]``),
    separated by ``punctuation[0]`` (the comma), each an optional sign (``signs``)
    and one of ``values`` (a number, a parameter), blanks anywhere between
    tokens. castor.language.lalr reads such a list at once (its loop then turns
    once for the parenthesized list instead of twice per argument and once per
    parenthesis).

    Proven, else None (the parser then reads arguments token by token): each of
    these terminals never matches from a position where another may
    (``_disjoint``: so that the root lexer, in any order, reads it there, as far
    as its own expression reaches: a shorter match of a number or a name is
    followed by a character of it, never by a blank or the punctuation); the
    blanks are the ignored terminal ``order`` reads before a token, one or more
    of a known set of characters; the signs and punctuation are one character
    each, none of them a blank; no sign or value may hold a blank, the comma or
    the ")" (where the list is cut); the parameter's first characters are known.
    castor.language.lalr checks, on its tables, that the rules between a value
    and the list call only the callbacks it calls."""
    pieces = alternatives(pattern, flags)
    if pieces is None or flags & re.IGNORECASE:
        return None
    texts = dict(pieces)
    wanted = (opening, *punctuation, signs, *values)
    if any(name not in texts for name in wanted):
        return None
    parsed = {name: sre.parse(text, flags).data for name, text in pieces}
    if not all(_disjoint(parsed[name], parsed[other])
               for name in wanted for other in parsed if other != name):
        return None
    _, prefix = order(pattern, flags, ignored)
    folded = [name for name in ignored
              if name in texts and prefix == f"(?:{_inner(texts[name])})?"]
    blanks = _repeated_character(parsed[folded[0]]) if len(folded) == 1 else None
    marks = [_single_character(parsed[name]) for name in (opening, *punctuation, signs)]
    names = first_set(parsed[values[1]])
    if blanks is None or names is None or any(m is None or m & blanks for m in marks):
        return None
    # nor may a value hold a blank or the punctuation: the list is cut there
    cuts = blanks | marks[1] | marks[2]
    if any(_may_hold(parsed[name], ch) for name in (signs, *values) for ch in cuts):
        return None
    blank = "[" + "".join(re.escape(ch) for ch in sorted(blanks)) + "]*"

    def bare(name: str) -> str:  # without its group (the values come twice), nor any inside
        return "(?:" + _uncaptured(_inner(texts[name])) + ")"

    value = f"(?:{bare(signs)}{blank})?(?:{'|'.join(bare(v) for v in values)})"
    whole = (f"{blank}{bare(opening)}(?:{blank}{value}{blank}{bare(punctuation[0])})*"
             f"{blank}{value}{blank}{bare(punctuation[1])}")
    (opening_mark,), (separator,) = marks[0], marks[1]
    return Arguments(whole, opening_mark, separator, "".join(sorted(blanks)), marks[-1], names)


def _inner(text: str) -> str:
    """An alternative's expression without its named group: ``(?P<A>x)`` -> ``x``."""
    return text[text.index(">") + 1:-1]


def _uncaptured(text: str) -> str:
    """An expression with its groups made non-capturing (``(a)`` -> ``(?:a)``),
    which matches the same and, inside a repetition, about twice as fast (``re``
    keeps no marks); proven by the two reading alike as ``re`` parses them but
    for the groups' numbers, else as it is."""
    out, index, size = [], 0, len(text)
    while index < size:
        char = text[index]
        if char == "\\":
            out.append(text[index:index + 2])
            index += 2
            continue
        if char == "[":  # a class, to its closing ']' (one just after '[' or '[^' is in it)
            end = index + 1 + (text[index + 1:index + 2] == "^")
            end += text[end:end + 1] == "]"
            while end < size and text[end] != "]":
                end += 2 if text[end] == "\\" else 1
            out.append(text[index:end + 1])
            index = end + 1
            continue
        out.append("(?:" if char == "(" and text[index + 1:index + 2] != "?" else char)
        index += 1
    uncaptured = "".join(out)
    try:
        same = _groupless(sre.parse(uncaptured).data) == _groupless(sre.parse(text).data)
    except (re.error, ValueError):
        same = False
    return uncaptured if same else text


def _groupless(seq):
    """A parsed expression with its groups' numbers left out, a group without
    flags spliced into what holds it as ``re`` reads ``(?:...)`` (a reference to
    a group keeps its number, and so tells the two apart)."""
    out = []
    for op, av in seq:
        if op is c.SUBPATTERN and not av[1] and not av[2]:
            out.extend(_groupless(av[3]))
            continue
        if op is c.SUBPATTERN:
            av = (None, av[1], av[2], _groupless(av[3]))
        elif op is c.BRANCH:
            av = (None, tuple(_groupless(branch) for branch in av[1]))
        elif op in _REPEATS:
            av = (av[0], av[1], _groupless(av[2]))
        elif op in (c.ASSERT, c.ASSERT_NOT):
            av = (av[0], _groupless(av[1]))
        elif op is c.IN:
            av = tuple(av)
        elif op is c.GROUPREF_EXISTS:
            raise ValueError("a reference to a group")
        out.append((op, av))
    return tuple(out)


def _may_hold(seq, char: str) -> bool:
    """Whether a match of the parsed expression may hold ``char`` anywhere in it
    (True where unsure)."""
    for op, av in seq:
        if op in (c.LITERAL, c.NOT_LITERAL, c.IN, c.ANY):
            if _item_starts(op, av, char):
                return True
        elif op is c.SUBPATTERN:
            if _may_hold(av[-1], char):
                return True
        elif op is c.BRANCH:
            if any(_may_hold(branch, char) for branch in av[1]):
                return True
        elif op in _REPEATS:
            if _may_hold(av[2], char):
                return True
        elif op not in (c.AT,):  # assertions and references: unsure
            return True
    return False


def _single_character(seq) -> frozenset | None:
    """The characters of an expression that matches exactly one of a known set."""
    if sre.SubPattern(sre.State(), seq).getwidth() != (1, 1):
        return None
    return first_set(seq)


def _repeated_character(seq) -> frozenset | None:
    """The characters of an expression that matches any run (one or more) of a
    known set of characters, ``(?:[ \\t])+`` (inside groups without flags)."""
    while len(seq) == 1 and seq[0][0] is c.SUBPATTERN and not seq[0][1][1] and \
            not seq[0][1][2]:
        seq = seq[0][1][-1]
    if len(seq) != 1 or seq[0][0] not in (c.MAX_REPEAT, c.MIN_REPEAT):
        return None
    low, high, body = seq[0][1]
    if low != 1 or high != c.MAXREPEAT:
        return None
    return _single_character(body)

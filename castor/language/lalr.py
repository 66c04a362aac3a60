"""A small LALR(1) driver for the tables of the grammar (grammar/castor.lark), so
that reading a scene need not import lark.

lark makes the tables (castor.language.tables exports them as plain data: the
parse table, each state's terminals as one regular expression, and for each
rule which children its callback is given); this module runs them as lark's
LALR parser and contextual lexer do, calling the same transformer methods with
the same children and tokens. Importing lark costs a scene about a tenth of its
start-up; this module, a millisecond.

It does only what a correct statement needs. Where the input is not one, it
raises ``Failed`` without a word, and castor.language.parse runs lark itself on
the same text for the error and its message (castor's syntax errors are worded
from lark's exceptions). tests/language/test_lalr.py checks that both read
every example, and random edits of them, alike.
"""

from __future__ import annotations

import re
from itertools import chain
from operator import itemgetter


class Failed(Exception):
    """The text is not a statement (or a program) of the grammar."""


class Token(str):
    """A terminal as lark gives it to a transformer: its text, its type (the
    terminal's name), and where it begins in the text (``start_pos``, from 0: lark's
    tokens have it too; their lines and columns follow from it, and the driver
    spares counting them as it reads: castor.language.parse.Builder counts them
    where it makes a location)."""

    type: str
    start_pos: int

    def __repr__(self):
        return f"Token({self.type!r}, {str.__repr__(self)})"


def _callback(method, expand_single: bool, include, append_none: int):
    """The transformer's ``method`` given a rule's children as lark gives them:
    tokens of punctuation left out, children of inlined rules (``_name``) spliced
    in, None for each missing ``[optional]``, a single child passed up as is where
    the rule is ``?rule``. The shapes every statement meets (some children kept;
    a list, an inlined ``(...)*``'s, a child appended to) have a function of
    their own; the others, lark's child filter as it is."""
    if include is None:
        if expand_single:
            return lambda children: children[0] if len(children) == 1 else method(children)
        return method
    indices = tuple(index for index, _, _ in include)
    splices = tuple(splice for _, splice, _ in include)
    if not expand_single and not any(nones for _, _, nones in include):
        tail = [None] * append_none
        inlined = method is _inlined  # its value is the list it is given: not called
        if not any(splices):
            if len(indices) == 1:
                only = indices[0]
                if tail:
                    return lambda children: method([children[only]] + tail)
                if inlined:
                    return lambda children: [children[only]]
                return lambda children: method([children[only]])
            picked = itemgetter(*indices)
            if tail:
                return lambda children: method([*picked(children), *tail])
            return lambda children: method([*picked(children)])
        if splices == (False, True) and not tail:  # a child, then an inlined list
            first, rest = indices
            return lambda children: method([children[first], *children[rest]])
        if splices == (True, False) and not tail:  # a list, one more child appended
            first, then = indices
            if inlined:
                def extended(children):
                    kept = children[first]  # the inlined rule's list, given up to this one
                    kept.append(children[then])
                    return kept

                return extended

            def appended(children):
                kept = children[first]  # the inlined rule's list, given up to this one
                kept.append(children[then])
                return method(kept)

            return appended

    def filtered(children):
        kept = []
        for index, splice, nones in include:
            if nones:
                kept += [None] * nones
            if splice:
                if kept:
                    kept += children[index]
                else:
                    kept = children[index]
            else:
                kept.append(children[index])
        if append_none:
            kept += [None] * append_none
        if expand_single and len(kept) == 1:
            return kept[0]
        return method(kept)

    return filtered


def _inlined(children):
    """An inlined rule's value: its children, which its parent splices in."""
    return children


def _tree(name: str):
    """A rule the transformer has no method for: lark makes a tree of it (its
    ``?rule`` passes a single child up, and then never calls this); the driver
    leaves such a text to lark."""
    def refused(children):
        raise Failed(f"no method for {name}")

    return refused


# the root lexer's groups that are no terminal (lark's terminals are upper case)
_STRAY, _END = "stray", "end_of_text"

# How the driver reduces a rule (the second field of its entry in Parser._rules),
# written as these numbers in Parser.parse:
_KEEP = 0  # a ``?rule`` of one child passes it up: the value stays, only the state changes
_ONE = 1  # the callback, given the one child the rule pops (number, parameter)
_PICK = 2  # a ``?rule`` that keeps one of its children, always: that child, no call
_CALL = 3  # the callback (the transformer's method through lark's child filter)


def _action(expand_single: bool, size: int, include, append_none: int) -> tuple:
    """How the driver reduces a rule: (_KEEP, None), (_PICK, the child's index from
    the top of the stack, negative) or (_ONE or _CALL, None)."""
    if expand_single and not append_none:
        if include is None:
            if size == 1:
                return _KEEP, None
        elif len(include) == 1:
            index, splice, nones = include[0]
            if not splice and not nones:
                return (_KEEP, None) if size == 1 else (_PICK, index - size)
    return (_ONE if size == 1 else _CALL), None


class Parser:
    """Parses text with the exported tables (castor.language.tables.export, which
    checks their layout), calling ``transformer`` as it reduces."""

    def __init__(self, tables: dict, transformer):
        if any(hasattr(transformer, name) for name in tables["terminals"]):
            raise ValueError("the transformer handles terminals")  # lark would call it on tokens
        # per state: symbol -> shift target (>= 0) or -1 - rule (~rule); lark never
        # shifts the end, which ends where a reduction reaches the start's end state
        self._states = tables["states"]
        if any(row.get("$END", -1) >= 0 for row in self._states):
            raise ValueError("the tables shift the end")
        self._starts = tables["starts"]
        self._ends = tables["ends"]
        self._lexer_of = tables["lexer_of"]  # per state: its lexer's number
        # per lexer: its ((pattern, flags), ...), the types it skips, those that may
        # hold newlines, its terminals; and the root lexer's, of every terminal
        self._lexers = tables["lexers"]
        self._compiled: list = [None] * len(self._lexers)
        self._root = tables["root"]
        self._root_compiled = None
        self._root_lexer()  # (ValueError where the driver cannot run it: lark does)
        # the terminals some rule hands its callback: the others (punctuation) are
        # shifted without a Token made for them
        self._kept = frozenset(tables["kept"])
        # per rule: (its symbol, _KEEP/_ONE/_PICK/_CALL, how many children it pops,
        # the picked child's index or the callback)
        self._rules = []
        named = {}  # (the rule's name, its size) -> (how it is reduced, its callback)
        for origin, size, name, expand_single, include, append_none in tables["rules"]:
            how, pick = _action(expand_single, size, include, append_none)
            named[name, size] = (how, pick)
            if how in (_KEEP, _PICK):
                self._rules.append((origin, how, size, pick))
                continue
            method = getattr(transformer, name, None)
            if name.startswith("_"):
                if method is not None:
                    raise ValueError(f"the transformer has a method for the inlined rule {name}")
                method = _inlined
            elif method is None:
                method = _tree(name)
            callback = _callback(method, expand_single, include, append_none)
            named[name, size] = (how, callback)
            self._rules.append((origin, how, size, callback))
        self._chains: dict = {}  # per start: (below, state, kind) -> where _chain ends
        self._named = named
        self._before_open: dict | None = None  # (_plain_arguments, for a long text)

    # the first text this long makes the parser ready to read calls' plain arguments
    # at once (_arguments), and it reads every text so from then on (the same
    # calls as token by token): making ready (proving it, compiling the
    # expression) costs about 20 ms, which a short scene's run would pay for nothing
    LONG = 20_000

    def _plain_arguments(self) -> None:
        """Where a call's arguments are read at once (``_arguments``): after the
        name of a call, a transformation or a primitive, each state from which
        "(" leads to one with a goto on ``args`` that shifts a number, a parameter
        and a sign, and from there to one that shifts ")" (the states the parser
        goes through, by state after the name); the expressions that read the
        "(" and each argument (castor.language.lexing.arguments); and the
        callbacks the parser would call on them. None of it where the grammar is
        not as this expects (the parser then reads every argument token by token)."""
        self._before_open = {}
        named = self._named
        wanted = {("number", 1): _ONE, ("parameter", 1): _ONE, ("unary", 2): _CALL,
                  ("args", 1): _ONE}
        if any(named.get(key, (None,))[0] != how for key, how in wanted.items()):
            return
        patterns, ignored, _, _ = self._root
        from castor.language.lexing import arguments

        found = arguments("|".join(pattern for pattern, _ in patterns), patterns[0][1],
                          frozenset(ignored), "LPAR", ("COMMA", "RPAR"), "ADDOP",
                          ("NUMBER", "PARAM"))
        if found is None:
            return
        self._whole_list = re.compile(found.whole, patterns[0][1]).match
        self._list_marks = (found.opening, found.separator, found.blanks, found.signs,
                            found.names)
        self._number, self._parameter, self._signed, self._args = (
            named[key][1] for key in wanted)
        states = self._states
        for state, row in enumerate(states):
            open_state = row.get("LPAR", -1)
            if open_state < 0:
                continue
            after = states[open_state]
            list_state = after.get("args", -1)
            if list_state < 0 or not all(after.get(kind, -1) >= 0
                                         for kind in ("NUMBER", "PARAM", "ADDOP")):
                continue
            close_state = states[list_state].get("RPAR", -1)
            if close_state >= 0 and self._reduced_as_read(open_state, list_state):
                self._before_open[state] = (open_state, list_state, close_state)

    def _reduced_as_read(self, open_state: int, list_state: int) -> bool:
        """Whether the parser, after the "(" (``open_state``), reduces a lone number
        or parameter before a ")" to the list (``list_state``) calling only its own
        callback and ``args``'s, before a "," to where the comma shifts calling
        only its own, and a signed number to the sign's rule then ``args``: what
        ``_arguments`` calls (a rule of one child between them, ``power:
        primary`` made a rule of its own, would be a callback more)."""
        states, rules = self._states, self._rules
        for kind, callback in (("NUMBER", self._number), ("PARAM", self._parameter)):
            shifted = states[open_state][kind]
            if self._chain(open_state, shifted, "RPAR", -1) != (list_state,
                                                                 (callback, self._args)):
                return False
            state, callbacks = self._chain(open_state, shifted, "COMMA", -1)
            if callbacks != (callback,) or states[state].get("COMMA", -1) < 0:
                return False
        sign = states[open_state]["ADDOP"]
        state, callbacks = self._chain(sign, states[sign].get("NUMBER", 0), "RPAR", -1)
        action = states[state].get("RPAR", 0)
        if callbacks != (self._number,) or action >= 0:
            return False
        origin, how, size, callback = rules[~action]
        return (how, size, callback) == (_CALL, 2, self._signed) and \
            self._chain(open_state, states[open_state].get(origin, 0), "RPAR", -1) == \
            (list_state, (self._args,))

    def _arguments(self, text: str, pos: int):
        """A call's "(" and arguments from ``pos`` (just after its name) where each
        is a number or a parameter, signed or not, with blanks around: the value
        the parser would make of them (the same callbacks on the same tokens, in
        the same order) and where the text after the closing ")" begins; None
        where they are not all such (nothing called then: the parser reads them
        token by token). One match tells such a list (castor.language.lexing.
        arguments); string operations take it apart at its commas (none inside
        an argument) and blanks."""
        whole = self._whole_list(text, pos)
        if whole is None:
            return None
        end = whole.end()
        opening, separator, blanks, signs, names = self._list_marks
        number, parameter, signed = self._number, self._parameter, self._signed
        at = text.index(opening, pos) + 1  # (only blanks before it)
        values = []
        for piece in text[at:end - 1].split(separator):
            word = piece.lstrip(blanks)
            start = at + len(piece) - len(word)
            at += len(piece) + 1
            word = word.rstrip(blanks)
            sign = None
            if word[0] in signs:
                sign = Token(word[0])
                sign.type, sign.start_pos = "ADDOP", start
                rest = word[1:].lstrip(blanks)
                start += len(word) - len(rest)
                word = rest
            token = Token(word)
            token.start_pos = start
            if word[0] in names:
                token.type = "PARAM"
                value = parameter([token])
            else:
                token.type = "NUMBER"
                value = number([token])
            if sign is not None:
                value = signed([sign, value])
            values.append(value)
        return self._args(values), end

    @staticmethod
    def _compile(lexer) -> tuple:
        patterns, ignored, newlines, _ = lexer
        return ([re.compile(pattern, flags).match for pattern, flags in patterns],
                frozenset(ignored), frozenset(newlines))

    def _lexer(self, state: int):
        number = self._lexer_of[state]
        lexer = self._compiled[number]
        if lexer is None:
            lexer = self._compiled[number] = self._compile(self._lexers[number])
        return lexer

    @staticmethod
    def _match(matchers, text: str, pos: int):
        for match in matchers:
            found = match(text, pos)
            if found is not None:
                return found
        return None

    def _read(self, text: str, pos: int, state: int):
        """The token at ``pos`` as the lexer of ``state`` reads it (lark's contextual
        lexer): where the root lexer's token is not one the state accepts."""
        found = self._match(self._lexer(state)[0], text, pos)
        if found is None:
            raise Failed(pos)
        return found

    def _root_lexer(self):
        """The root lexer's scan (an iterator of its matches from a position on:
        one expression of every terminal, in lark's order of them, then any
        character, then the end of the text), the types it skips and those that
        may hold newlines.

        Each token is first read by it: where the terminal it finds is one the
        parser's state accepts, the state's own lexer would find the same (its
        terminals are a part of the root's, in the same order, and none before
        that one matched), and compiling each state's expression (some 30 of
        them, about 0.7 ms each) is spared. Where it is not (or is no terminal:
        ``_STRAY``), the state's lexer reads the token (``_read``). The matches
        follow one another with nothing between them, each where the one before
        ends (any character matches), as the lexer reads tokens one after the
        other; the last is the empty one at the end (``_END``)."""
        if self._root_compiled is None:
            patterns, ignored, newlines, _ = self._root
            if len({flags for _, flags in patterns}) != 1:
                raise ValueError("root lexer's expressions of several flags")
            from castor.language.lexing import order

            flags = patterns[0][1]
            # the same tokens, tried in a faster order, blanks read with the next
            # token (castor.language.lexing, which proves it)
            alternatives, blanks = order("|".join(pattern for pattern, _ in patterns), flags,
                                         frozenset(ignored))
            scan = re.compile(f"{blanks}(?:{alternatives}"
                              f"|(?P<{_STRAY}>(?s:.))|(?P<{_END}>\\Z))", flags).finditer
            self._root_compiled = scan, frozenset(ignored), frozenset(newlines)
        return self._root_compiled

    def _chain(self, below: int, state: int, kind: str, end_state: int) -> tuple:
        """Where a run of rules of one child ends (``primary: NUMBER -> number``,
        then ``expr: term``, ``term: unary``, ...: five of them after each number),
        reduced one after the other from ``state`` above ``below`` with ``kind``
        next, and the callbacks they call in turn on the value on top (none for a
        ``?rule`` that passes its child up): each changes the top of the stack
        only, so that the run depends on these three alone, and ``parse`` keeps
        it (``_chains``)."""
        states, rules = self._states, self._rules
        callbacks = []
        while True:
            action = states[state].get(kind)
            if action is None or action >= 0:
                break
            origin, how, _, callback = rules[~action]
            if how == _ONE:
                callbacks.append(callback)
            elif how != _KEEP:
                break
            state = states[below][origin]
            if kind == "$END" and state == end_state:
                break
        return state, tuple(callbacks)

    def parse(self, text: str, start: str):
        """The value the transformer gives the start rule; raises Failed. One loop
        reads each token (by the lexer of the state the parser is in), reduces as
        far as it allows and shifts it; only the tokens a callback is handed are
        made (``Token``). Its time is linear in the text's length."""
        scan, ignored, _ = self._root_lexer()
        states, rules, kept = self._states, self._rules, self._kept
        if self._before_open is None and len(text) >= self.LONG:
            self._plain_arguments()
        before_open = self._before_open or {}
        chains = self._chains.setdefault(start, {})
        state, end_state = self._starts[start], self._ends[start]
        state_stack, value_stack = [state], []
        push_state, push_value = state_stack.append, value_stack.append
        next_found = scan(text).__next__
        relexed = -1  # where _read last read a token
        while True:
            found = next_found()
            kind = found.lastgroup
            if kind in ignored:
                continue
            action = states[state].get(kind)
            if action is None:
                if kind != _END:  # not a token this state accepts: the state's own lexer reads it
                    pos = found.start(kind)
                    if pos == relexed:
                        raise Failed(kind)
                    relexed = pos
                    found = self._read(text, pos, state)
                    next_found = chain((found,), scan(text, found.end())).__next__
                    continue
                kind = "$END"
                action = states[state].get(kind)
                if action is None:
                    raise Failed(kind)
            if kind in kept:
                token = Token(found.group(kind))
                token.type, token.start_pos = kind, found.start(kind)
            else:
                token = None
            while action < 0:  # reduce as far as the token allows, then shift it
                origin, how, size, callback = rules[~action]
                if how <= 1:  # _KEEP, _ONE: a run of rules of one child, the top replaced
                    below = state_stack[-2]  # the same all along the run
                    key = (below, state, kind)
                    run = chains.get(key)
                    if run is None:
                        run = chains[key] = self._chain(below, state, kind, end_state)
                    state, callbacks = run
                    state_stack[-1] = state
                    for callback in callbacks:
                        value_stack[-1] = callback(value_stack[-1:])
                else:
                    if how == 2:  # _PICK
                        value = value_stack[callback]
                    else:
                        value = callback(value_stack[-size:] if size else [])
                    if size:
                        del state_stack[-size:]
                        del value_stack[-size:]
                    push_value(value)
                    state = states[state_stack[-1]][origin]
                    push_state(state)
                if state == end_state and kind == "$END":
                    return value_stack[-1]
                action = states[state].get(kind)
                if action is None:
                    raise Failed(kind)
            # (never a shift of "$END": the tables have none)
            push_state(action)
            push_value(token)
            state = action
            if action in before_open:  # a call's name: its "(", plain arguments and ")" at once
                read = self._arguments(text, found.end())
                if read is not None:
                    value, after = read
                    open_state, list_state, state = before_open[action]
                    push_state(open_state)
                    push_value(None)
                    push_state(list_state)
                    push_value(value)
                    push_state(state)
                    push_value(None)
                    next_found = scan(text, after).__next__

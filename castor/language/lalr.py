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


class Failed(Exception):
    """The text is not a statement (or a program) of the grammar."""


class Token(str):
    """A terminal as lark gives it to a transformer: its text, its type (the
    terminal's name), and the line and column where it begins (from 1)."""

    type: str
    line: int
    column: int

    def __repr__(self):
        return f"Token({self.type!r}, {str.__repr__(self)})"


def _callback(method, expand_single: bool, include, append_none: int):
    """The transformer's ``method`` given a rule's children as lark gives them:
    tokens of punctuation left out, children of inlined rules (``_name``) spliced
    in, None for each missing ``[optional]``, a single child passed up as is where
    the rule is ``?rule``."""
    if include is None:
        if expand_single:
            return lambda children: children[0] if len(children) == 1 else method(children)
        return method

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


class Parser:
    """Parses text with the exported tables (castor.language.tables.export, which
    checks their layout), calling ``transformer`` as it reduces."""

    def __init__(self, tables: dict, transformer):
        if any(hasattr(transformer, name) for name in tables["terminals"]):
            raise ValueError("the transformer handles terminals")  # lark would call it on tokens
        self._states = tables["states"]  # per state: symbol -> shift target (>= 0) or -1 - rule
        self._starts = tables["starts"]
        self._ends = tables["ends"]
        self._lexer_of = tables["lexer_of"]  # per state: its lexer's number
        # per lexer: its ((pattern, flags), ...), the types it skips, those that may
        # hold newlines, its terminals; and the root lexer's, of every terminal
        self._lexers = tables["lexers"]
        self._compiled: list = [None] * len(self._lexers)
        self._terminals = [frozenset(lexer[3]) for lexer in self._lexers]
        self._root = tables["root"]
        self._root_compiled = None
        self._rules = []  # per rule: (its symbol, how many children it pops, its callback)
        for origin, size, name, expand_single, include, append_none in tables["rules"]:
            method = getattr(transformer, name, None)
            if name.startswith("_"):
                if method is not None:
                    raise ValueError(f"the transformer has a method for the inlined rule {name}")
                method = _inlined
            elif method is None:
                method = _tree(name)
            self._rules.append((origin, size, _callback(method, expand_single, include,
                                                        append_none)))

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

    def _tokens(self, text: str, state_stack: list):
        """The text's tokens, each read by the lexer of the state the parser is in
        when it asks (lark's contextual lexer), then the end ("$END", None).

        Each token is first read by the root lexer, whose one expression (every
        terminal, in lark's order of them) is compiled once: where the terminal it
        finds is one of the state's, the state's own lexer would find the same (its
        terminals are a part of the root's, in the same order, and none before
        that one matched), and compiling each state's expression (some 30 of
        them, about 0.7 ms each) is spared. Where it is not, the state's lexer
        reads the token."""
        if self._root_compiled is None:
            self._root_compiled = self._compile(self._root)
        root, ignored, newlines = self._root_compiled
        lexer_of, terminals = self._lexer_of, self._terminals
        end = len(text)
        pos, line, line_start = 0, 1, 0  # where the next token begins; its line's start
        while pos < end:
            state = state_stack[-1]
            found = self._match(root, text, pos)
            if found is None or found.lastgroup not in terminals[lexer_of[state]]:
                found = self._match(self._lexer(state)[0], text, pos)
                if found is None:
                    raise Failed(pos)
            value, kind = found.group(0), found.lastgroup
            token = None
            if kind not in ignored:
                token = Token(value)
                token.type, token.line, token.column = kind, line, pos - line_start + 1
            if kind in newlines:
                count = value.count("\n")
                if count:
                    line += count
                    line_start = pos + value.rindex("\n") + 1
            pos += len(value)
            if token is not None:
                yield kind, token
        yield "$END", None

    def parse(self, text: str, start: str):
        """The value the transformer gives the start rule; raises Failed."""
        states, rules = self._states, self._rules
        state_stack = [self._starts[start]]
        value_stack: list = []
        end_state = self._ends[start]
        for kind, token in self._tokens(text, state_stack):
            while True:  # reduce as far as the token allows, then shift it
                action = states[state_stack[-1]].get(kind)
                if action is None or (action >= 0 and token is None):
                    raise Failed(kind)
                if action >= 0:
                    state_stack.append(action)
                    value_stack.append(token)
                    break
                origin, size, callback = rules[-1 - action]
                if size:
                    children = value_stack[-size:]
                    del state_stack[-size:]
                    del value_stack[-size:]
                else:
                    children = []
                value_stack.append(callback(children))
                state_stack.append(states[state_stack[-1]][origin])
                if token is None and state_stack[-1] == end_state:
                    return value_stack[-1]
        raise Failed("the end")  # not reached: "$END" either reduces to the start or fails

"""Parse and evaluate: `castor --check` on 20,000 statements, against lark
parsing the same text with the same grammar and no tree kept (a parser whose
callbacks do nothing), in the same run.

Targets: at least 5,000 statements/s, and within 1.3x of bare lark.
"""

import os
import sys
import tempfile

from _common import castor_command, runs_from_env, timed

RUNS = runs_from_env(5)
COUNT = 20_000


def scene(count: int) -> str:
    lines = ["L = 2.5;", "a0 = @h(L, 1, 1) !cu(0.5, 0.5, 0.5);"]
    i = 1
    while len(lines) < count - 1:
        lines.append(f"X{i} = {i} * 0.5 + sin({i % 90}) * L;")
        lines.append(f"a{i} = $U(@t(X{i}, 0, 0) @rz({i % 360}) a{(i - 1) % 50}, @h(1, 2, 0.5) !cy(0.2, 0.3, 0.4));")
        i += 1
    lines.append(f"> @t(0, 0, 1) a{min(i - 1, 50)};")
    return "\n".join(lines[:count]) + "\n"


BARE_LARK = r'''
import sys
from lark import Lark, Transformer
from castor.language.parse import grammar_text
text = open(sys.argv[1]).read()
RULES = ["program", "param_def", "object_def", "facetize", "object", "transform", "primitive",
         "boolean", "reference", "repeat", "args", "binary", "unary", "number", "parameter", "call"]
# a callback for every rule that keeps nothing: no tree is built
Nothing = type("Nothing", (Transformer,), {name: (lambda self, children: None) for name in RULES})
parser = Lark(grammar_text(), parser="lalr", lexer="contextual", start="program",
              transformer=Nothing(), maybe_placeholders=True, cache=True)
parser.parse(text)
'''


def main() -> None:
    work = tempfile.mkdtemp()
    path = os.path.join(work, "big.cas")
    with open(path, "w") as handle:
        handle.write(scene(COUNT))
    bare_script = os.path.join(work, "bare.py")
    with open(bare_script, "w") as handle:
        handle.write(BARE_LARK)
    castor = timed(castor_command() + ["--check", "--no-cpp", path], runs=RUNS)
    castor_cpp = timed(castor_command() + ["--check", path], runs=RUNS)
    bare = timed([sys.executable, bare_script, path], runs=RUNS)
    print(f"{COUNT} statements")
    print(f"castor --check --no-cpp   {castor:.3f} s   {COUNT / castor:8.0f} statements/s (target >= 5000)")
    print(f"castor --check (with cpp) {castor_cpp:.3f} s   {COUNT / castor_cpp:8.0f} statements/s")
    print(f"lark alone, no tree       {bare:.3f} s   {COUNT / bare:8.0f} statements/s")
    print(f"castor / lark             {castor / bare:.2f}  (target <= 1.3)")


if __name__ == "__main__":
    main()

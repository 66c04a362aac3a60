"""Write the primitives and transformations of castor's vocabulary into the
vim syntax file (vim/syntax/castor.vim), so that it names exactly those
castor knows: the lines that start with ``syn match castorPrimitive`` and
``syn match castorTransform`` are replaced. Usage: python scripts/vim_syntax.py"""

from pathlib import Path

from castor.language.vocabulary import vim_syntax

SYNTAX = Path(__file__).resolve().parent.parent / "vim" / "syntax" / "castor.vim"


def main() -> None:
    lines = SYNTAX.read_text().splitlines()
    for new in vim_syntax():
        start = new.split('"')[0]
        lines = [new if line.startswith(start) else line for line in lines]
    SYNTAX.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()

"""Write the primitives and transformations of castor's vocabulary into the
vim syntax file (vim/syntax/castor.vim), so that it names exactly those
castor knows: the lines that start with ``syn match castorPrimitive`` and
``syn match castorTransform`` are replaced. Usage: python scripts/vim_syntax.py"""

from pathlib import Path

from castor.primitives import PRIMITIVES
from castor.transformations import TRANSFORMS

SYNTAX = Path(__file__).resolve().parent.parent / "vim" / "syntax" / "castor.vim"


def syntax_lines() -> list[str]:
    """The lines of the syntax file that name the primitives and the transformations."""
    return ['syn match castorPrimitive "!\\(' + "\\|".join(PRIMITIVES) + '\\)\\>"',
            'syn match castorTransform "@\\(' + "\\|".join(TRANSFORMS) + '\\)\\>"']


def main() -> None:
    lines = SYNTAX.read_text().splitlines()
    for new in syntax_lines():
        start = new.split('"')[0]
        lines = [new if line.startswith(start) else line for line in lines]
    SYNTAX.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()

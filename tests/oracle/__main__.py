"""``python -m tests.oracle ...`` from the checkout, or ``python tests/oracle ...``."""

import os
import sys

if __package__:
    from .cli import main
else:  # run as a folder: the checkout on the path, so that ``tests`` is a package
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    from tests.oracle.cli import main

main()

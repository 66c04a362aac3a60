"""Every test folder and tests/ itself on sys.path: the shared helpers
(meshcheck, oracle, exact) and helpers of one test file used by another
(``from test_drawings import Drawn``) import by their module name."""

import os
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
for _folder in sorted(os.listdir(_HERE)):
    _path = os.path.join(_HERE, _folder)
    if os.path.isdir(_path) and not _folder.startswith((".", "_")) and _path not in sys.path:
        sys.path.insert(0, _path)
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)

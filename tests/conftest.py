"""The suite's shared helpers are the packages ``tests.support`` and
``tests.oracle`` (see tests/README.md); test modules import them by those
names and never import one another. ``tests/__init__.py`` makes pytest put
the checkout on ``sys.path``, so that ``tests`` is importable however pytest
is started."""

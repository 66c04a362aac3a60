"""The build step that ships the grammar and the parser's tables.

Everything else is in pyproject.toml. The grammar's one source is
grammar/castor.lark at the repository's top; after the package is copied into
the build directory, it is copied beside castor/language/parse.py as
castor.lark, and its LALR tables are made there (castor/language/tables.py:
castor.tables for lark, castor.lalr for castor's own driver), so that
``pip install .`` installs them and castor never reads the repository, nor
builds or writes tables, at run time.
"""

import importlib.util
import os
import shutil

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = os.path.dirname(os.path.abspath(__file__))
GRAMMAR = os.path.join(ROOT, "grammar", "castor.lark")


class BuildWithTables(build_py):
    def run(self):
        super().run()
        if self.dry_run:
            return
        source = os.path.join(ROOT, "castor", "language", "tables.py")
        spec = importlib.util.spec_from_file_location("_castor_tables", source)
        tables = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(tables)  # by its path: the package need not import
        target = os.path.join(self.build_lib, "castor", "language")
        os.makedirs(target, exist_ok=True)
        shipped = os.path.join(target, os.path.basename(tables.SHIPPED_GRAMMAR))
        shutil.copyfile(GRAMMAR, shipped)
        with open(shipped, encoding="utf-8") as handle:
            grammar = handle.read()
        tables.save(os.path.join(target, os.path.basename(tables.TABLES)), grammar)


setup(cmdclass={"build_py": BuildWithTables})

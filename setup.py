"""The build step that ships the parser's tables (castor/language/tables.py).

Everything else is in pyproject.toml. After the package is copied into the build
directory, the LALR tables of castor.lark are made there as castor.tables, so
that ``pip install .`` installs them and castor never builds or writes them at
run time.
"""

import importlib.util
import os

from setuptools import setup
from setuptools.command.build_py import build_py


class BuildWithTables(build_py):
    def run(self):
        super().run()
        if self.dry_run:
            return
        source = os.path.join(os.path.dirname(os.path.abspath(__file__)), "castor", "language",
                              "tables.py")
        spec = importlib.util.spec_from_file_location("_castor_tables", source)
        tables = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(tables)  # by its path: the package need not import
        target = os.path.join(self.build_lib, "castor", "language")
        os.makedirs(target, exist_ok=True)
        tables.save(os.path.join(target, os.path.basename(tables.TABLES)))


setup(cmdclass={"build_py": BuildWithTables})

"""Start-up: `echo '> !cu(1,1,1);' | castor --no-cpp`, whole process, median of runs.

Target: at most 0.25 s. Prints bare Python and the imports for comparison.
"""

import sys

from _common import castor_command, runs_from_env, timed

RUNS = runs_from_env(15)

bare = timed([sys.executable, "-c", "pass"], runs=RUNS)
imports = timed([sys.executable, "-c", "import numpy, manifold3d"], runs=RUNS)
lark = timed([sys.executable, "-c", "import lark"], runs=RUNS)
castor = timed(castor_command() + ["--no-cpp"], stdin=b"> !cu(1,1,1);\n", runs=RUNS)
check = timed(castor_command() + ["--no-cpp", "--check"], stdin=b"> !cu(1,1,1);\n", runs=RUNS)
print(f"bare python                      {bare:.3f} s")
print(f"import numpy, manifold3d         {imports:.3f} s")
print(f"import lark                      {lark:.3f} s")
print(f"castor --no-cpp, one cube        {castor:.3f} s   (target <= 0.25 s)")
print(f"castor --no-cpp --check          {check:.3f} s")

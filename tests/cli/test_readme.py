"""The README's commands run as written (issue 18, item 13), and CI runs its test command.

Every line of the "Using it" block runs from the repository's directory, as a
reader types it: a temporary directory holds the outputs and sees the
repository's `examples/` beside them (a link), so `examples/house.cas` is
found and nothing is written into the checkout. Two lines are skipped, and
say why: `--scheduler` needs a Dask cluster at HOST, and `--serve` is a server
that runs until Ctrl-C (tests/preview/test_serve.py drives it). The pictures' table
must say what scripts/pictures.sh runs.
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SKIPPED = {"--scheduler": "needs a Dask cluster at tcp://HOST:8786",
           "--serve": "a server that runs until Ctrl-C (tests/preview/test_serve.py drives it)"}


def _blocks():
    text = (ROOT / "README.md").read_text()
    parts = text.split("```")
    return [parts[i].strip() for i in range(1, len(parts), 2)]


def using_it() -> list[str]:
    """The command lines of the README's "Using it" block, without their comments."""
    text = (ROOT / "README.md").read_text()
    block = text.split("## Using it", 1)[1].split("```")[1]
    commands = []
    for line in block.strip().splitlines():
        command = re.sub(r"\s+#\s.*$", "", line).strip()
        if command and not command.startswith("#"):
            commands.append(command)
    return commands


def test_ci_runs_the_readme_test_command_exactly():
    first, second = _blocks()[:2]
    assert "pip install ." in first and "castor examples/" in first
    assert "pytest" in second
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert ci[-1] == second


def test_using_it_has_its_commands():
    commands = using_it()
    assert len(commands) >= 15
    assert commands[0].startswith("cpp -C examples/house.cas | castor")


def _outputs(command: str) -> list[str]:
    """The files a command line names for writing: after -o and --summary."""
    words = shlex.split(command.replace("|", " | ").replace("&&", " && "))
    return [words[i + 1] for i, w in enumerate(words[:-1]) if w in ("-o", "--summary")]


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    here = tmp_path_factory.mktemp("readme")
    (here / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    return here


@pytest.mark.parametrize("command", using_it())
def test_using_it_runs_as_written(command, workdir):
    for option, why in SKIPPED.items():
        if option in command:
            pytest.skip(f"{option}: {why}")
    if command.startswith("cpp ") and shutil.which("cpp") is None:
        pytest.skip("no cpp installed")
    # the castor and castor-view of this Python, as an installed package gives them
    env = {**os.environ, "PATH": os.path.dirname(sys.executable) + os.pathsep + os.environ["PATH"]}
    started = time.perf_counter()
    done = subprocess.run(["sh", "-c", command], cwd=workdir, env=env, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, (command, done.stderr)
    assert "error" not in done.stderr and "Traceback" not in done.stderr, done.stderr
    for name in _outputs(command):
        if "%" in name:
            pattern = re.sub(r"%0?\d*d", "*", name)
            found = sorted(workdir.glob(pattern))
            assert len(found) == 9, (command, found)  # door.cas has nine frames
        else:
            assert (workdir / name).stat().st_size > 0, (command, name)
    if command.startswith("echo "):
        assert "endframe 1 6" in done.stdout
    print(f"{time.perf_counter() - started:.1f} s: {command}")


def test_the_pictures_table_says_what_the_script_runs():
    """Each picture's command in the README is the line of scripts/pictures.sh that
    draws it, its output named without the script's folder."""
    text = (ROOT / "README.md").read_text()
    using = text[text.index("## Using it"):]
    using = using[:using.index("\n## ", 1)]  # the table of the section "Using it"
    table = re.findall(r"^\| !\[[^]]*\]\(docs/pictures/([^)]+)\) \| `([^`]+)`", using, re.M)
    script = (ROOT / "scripts" / "pictures.sh").read_text().replace("\\\n", "")
    lines = [" ".join(line.split()).replace('"$out/', "").replace('"', "")
             for line in script.splitlines() if line.startswith("castor")]
    assert len(table) == len(lines) >= 6
    for picture, command in table:
        command = command.replace("\\|", "|")
        words = command.split()
        # the README puts the options first and the size where the script has it
        assert any(sorted(line.split()) == sorted(words) for line in lines), (picture, command)
        assert picture in command

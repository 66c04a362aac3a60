"""The castor command: options, exit statuses, files, the preprocessor's flags."""

import pytest

from tests.support.cli import run
from tests.support.stream import parse_stream

CUBE = "!cu(0.5, 0.5, 0.5)"


def test_version_and_help():
    status, out, err = run("--version")
    assert status == 0 and out.strip() == "castor 0.1.0"
    status, out, err = run("--help")
    assert status == 0
    for option in ("--output", "--format", "--no-cpp", "--set", "--tolerance", "--check",
                   "--stats", "--quiet", "--max-polygons"):
        assert option in out


@pytest.mark.parametrize("args, message", [
    (["--bogus"], "unrecognized arguments: --bogus"),
    (["-f", "dwg"], "invalid choice: 'dwg'"),
    (["--tolerance", "0"], "--tolerance must be a positive number"),
    (["--set", "x=1"], "--set takes NAME=EXPR with a parameter NAME"),
    (["--set", "X=1/0"], "--set X=1/0: division by zero"),
    (["no-such-file.cas"], "castor: error: cannot read 'no-such-file.cas': no such file"),
])
def test_usage_errors_exit_2(args, message):
    status, out, err = run(*args, stdin="")
    assert status == 2
    assert message in err


def test_check_writes_nothing_and_finds_errors():
    status, out, err = run("--check", "--no-cpp", stdin=f"> {CUBE};\n> @h(1, 0, 1) {CUBE};\n")
    assert status == 1 and out == ""
    assert err.startswith("<stdin>:2:3: error: zero scale factor for y")


def test_several_files_are_read_as_one_input(tmp_path):
    (tmp_path / "a.cas").write_text(f"L = 3;\nc = {CUBE};\n")
    (tmp_path / "b.cas").write_text("> @h(L, 1, 1) c;\n> zz;\n")
    status, out, err = run("a.cas", "b.cas", cwd=tmp_path)
    assert status == 1
    assert parse_stream(out)[0].volume() == pytest.approx(3)
    assert err.splitlines()[0] == "b.cas:2:3: error: object 'zz' is not defined"


def test_define_undefine_and_include_dirs(tmp_path):
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "cube.cas").write_text(f"#define SIZE 2\nc = @h(SIZE) {CUBE};\n")
    (tmp_path / "s.cas").write_text(
        "#include \"cube.cas\"\n#ifdef BIG\n> @h(5) c;\n#else\n> c;\n#endif\n")
    status, out, err = run("-I", "lib", "-D", "BIG", "s.cas", cwd=tmp_path)
    assert status == 0, err
    assert parse_stream(out)[0].volume() == pytest.approx(1000)
    status, out, err = run("-I", "lib", "-D", "BIG", "-U", "BIG", "s.cas", cwd=tmp_path)
    assert parse_stream(out)[0].volume() == pytest.approx(8)
    status, out, err = run("-D", "W=4", "--no-cpp", stdin="> !cu(1,1,1);\n")
    assert status == 0  # -D is ignored without the preprocessor


def test_output_to_a_cps_file(tmp_path):
    target = tmp_path / "out.cps"
    status, out, err = run("--no-cpp", "-o", str(target), stdin=f"> {CUBE};\n> {CUBE};\n")
    assert status == 0 and out == ""
    assert len(parse_stream(target.read_text())) == 2


def test_tolerance_option_wins_over_the_scene():
    scene = "TOLERANCE = 0.5;\n> !sp(1, 1, 1);\n"
    status, out, err = run("--no-cpp", "--tolerance", "0.01", stdin=scene)
    fine = len(parse_stream(out)[0].polygons)
    status, out, err = run("--no-cpp", stdin=scene)
    coarse = len(parse_stream(out)[0].polygons)
    assert fine > coarse


def test_output_to_a_named_pipe_is_written_into_not_renamed_over(tmp_path):
    """-o /dev/null or a pipe: castor writes into it (as root, renaming a file
    over /dev/null would replace the device)."""
    import os
    import stat
    import threading

    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    received = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()))
    reader.start()
    status, out, err = run("--no-cpp", "-o", str(fifo), stdin="> !cu(1, 0, 0);\n")
    reader.join(timeout=60)
    assert status == 0, err
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert received[0].startswith(b"castor-polygons 1\nframe 1 <stdin>:1\n")

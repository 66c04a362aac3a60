"""Input that is not text is refused at once, said once (issue 29, item 1).

Five megabytes of random bytes took castor 158 s (453 s and 1 GB without any
'#'), printing raw bytes and one "unexpected byte" per bad byte, because the
preprocessor and the grammar took them apart one by one. The input is now read
as bytes and refused at its first byte that is not UTF-8 (or when control
characters make it no text), in one message; how long that takes is measured
by benchmarks/not_text.py, not here.
"""

import os
import random
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
MESSAGE = re.compile(r"^\S+:\d+:\d+: (error|warning|note): ", re.M)


def castor(cwd, *args, stdin: bytes | None = None):
    done = subprocess.run([sys.executable, "-m", "castor", *args], cwd=cwd, input=stdin,
                          capture_output=True, timeout=120,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})
    return done.returncode, done.stdout, done.stderr.decode()


def random_bytes(size: int, seed: int = 29, without: bytes = b"") -> bytes:
    data = random.Random(seed).randbytes(size)
    for byte in without:
        data = data.replace(bytes([byte]), b"")
    return data


@pytest.fixture(scope="module")
def garbage(tmp_path_factory):
    folder = tmp_path_factory.mktemp("garbage")
    (folder / "rand.bin").write_bytes(random_bytes(3_000_000))
    (folder / "nohash.bin").write_bytes(random_bytes(3_000_000, without=b"#"))
    # UTF-8 all through, but a quarter of it control characters
    (folder / "ascii.bin").write_bytes(bytes(b & 0x7f for b in random_bytes(1_000_000)))
    return folder


@pytest.mark.parametrize("name", ["rand.bin", "nohash.bin", "ascii.bin"])
@pytest.mark.parametrize("args", [[], ["--no-cpp"]], ids=["cpp", "no-cpp"])
def test_garbage_is_refused_in_one_message(garbage, name, args):
    status, out, err = castor(garbage, *args, name)
    assert status == 1
    assert out == b""
    assert len(err.splitlines()) == 1, err[:2000]
    assert re.match(rf"{re.escape(name)}:1:\d+: error: the input is not text \(", err), err
    assert err.isprintable() or err.endswith("\n") and err[:-1].isprintable()


def test_garbage_on_standard_input(garbage):
    data = (garbage / "rand.bin").read_bytes()
    for args in ([], ["--no-cpp"]):
        status, out, err = castor(garbage, *args, stdin=data)
        assert status == 1
        assert len(err.splitlines()) == 1, err[:2000]
        assert err.startswith("<stdin>:1:") and "the input is not text (byte 0x" in err


def test_the_message_points_at_the_first_byte_that_is_not_utf8(tmp_path):
    (tmp_path / "latin1.cas").write_bytes(b"a = !cu(1, 1, 1);\n> a;\n/* fen\xeatre */\n")
    status, out, err = castor(tmp_path, "latin1.cas")
    assert status == 1
    assert err == ("latin1.cas:3:7: error: the input is not text (byte 0xea is not UTF-8); "
                   "castor reads UTF-8 text: a scene written in Latin-1 converts with "
                   "iconv -f latin1 -t utf-8\n")
    assert out == b""  # nothing of a file that is not text is run
    # read as it arrives, the statements before that line have run
    status, out, err = castor(tmp_path, "--no-cpp", "latin1.cas")
    assert status == 1 and err.startswith("latin1.cas:3:7: error: the input is not text")
    assert out.endswith(b"endframe 1 6\n")


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-be"])
def test_a_utf16_scene_is_told_how_to_convert(tmp_path, encoding):
    # its byte-order mark is not Latin-1: iconv -f latin1 would make garbage of it
    text = "> !cu(1, 1, 1);\n".encode(encoding)
    (tmp_path / "u16.cas").write_bytes(text if text[:2] in (b"\xff\xfe", b"\xfe\xff")
                                       else b"\xfe\xff" + text)
    for args in ([], ["--no-cpp"]):
        status, out, err = castor(tmp_path, *args, "u16.cas")
        assert status == 1 and out == b""
        assert err.endswith("castor reads UTF-8 text: this one starts as UTF-16 does, and "
                            "converts with iconv -f utf-16 -t utf-8\n"), err
        assert err.startswith("u16.cas:1:1: error: the input is not text (byte 0xf")


def test_a_file_that_is_not_text_is_skipped_and_the_others_read(tmp_path):
    (tmp_path / "a.cas").write_text("a = !cu(1, 1, 1);\n")
    (tmp_path / "b.bin").write_bytes(b"\xff\xfe\x00\x01" * 100)
    (tmp_path / "c.cas").write_text("> @h(2) a;\n")
    for args in ([], ["--no-cpp"]):
        status, out, err = castor(tmp_path, *args, "a.cas", "b.bin", "c.cas")
        assert status == 1
        assert err.startswith("b.bin:1:1: error: the input is not text (byte 0xff")
        assert len(err.splitlines()) == 1, err
        assert out.endswith(b"endframe 1 6\n")


def test_text_with_a_few_control_characters_is_still_read_as_text(tmp_path):
    """A stray NUL is said at its place (issue 18), not taken for a binary file."""
    (tmp_path / "s.cas").write_bytes(b'#include "a\0b.cas"\n> !cu(1, 0, 0);\n')
    status, out, err = castor(tmp_path, "s.cas")
    assert status == 1 and err.startswith("s.cas:1:10: error: ") and "NUL" in err
    assert out.endswith(b"endframe 1 6\n")


def test_line_ends_of_every_kind_read_as_before(tmp_path):
    for ending in (b"\n", b"\r\n", b"\r"):
        scene = ending.join([b"a = !cu(1, 1, 1);", b"/* two", b"lines */ > @h(2) a;",
                             b"> a"]) + b";"
        (tmp_path / "e.cas").write_bytes(scene)
        for args in ([], ["--no-cpp"]):
            status, out, err = castor(tmp_path, *args, "e.cas")
            assert status == 0, (ending, args, err)
            frames = re.findall(rb"frame (\d+) e\.cas:(\d+)", out)
            assert frames == [(b"1", b"3"), (b"2", b"4")], (ending, args, out[:300])


@pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="needs /proc")
def test_memory_stays_bounded(garbage):
    """The whole file is never decoded when its first block is refused: a run
    on 3 MB of garbage peaks well under what reading it into str would cost."""
    # VmHWM: this process's own peak (ru_maxrss would count the fork of pytest)
    code = ("from castor.cli import main\n"
            "status = main(['--check', 'nohash.bin'])\n"
            "print(open('/proc/self/status').read().split('VmHWM:')[1].split()[0])\n")
    done = subprocess.run([sys.executable, "-c", code], cwd=garbage, capture_output=True,
                          text=True, timeout=120, env={"PYTHONPATH": str(REPO)})
    assert "the input is not text" in done.stderr
    assert int(done.stdout.split()[-1]) < 80_000  # kB: castor itself takes about 20 MB

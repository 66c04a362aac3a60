"""The mesh writers write a frame a piece at a time, in bounded memory: the
bytes are those of the whole frame at once, whatever the size of the pieces,
and they go to their file as they are made."""

import os
from pathlib import Path

import pytest

import importlib

from castor.formats import FORMATS, WriteInfo, of_kind
from castor.settings import FrameSettings, OutputSettings
from castor.formats.output import Output, Spooled, encode, encode_pieces, write_atomically

# several objects, colours, polygons of more than four vertices (a box less a
# cylinder), polygons with a straight corner (where the bar ends on a face),
# slanted quads (spheres), an object named by the '>' command
SCENE = """TOLERANCE = 0.02;
boite = $D(@t(-1, -1, -1) @h(2, 2, 2) !cu(0.2, 0.8, 0.2),
           $U(@h(0.5, 0.5, 3) @t(0, 0, -0.5) !cy(0.2, 0.2, 0.9),
              @t(0.5, -0.2, -0.2) @h(1, 0.4, 0.4) !cu(0.9, 0.2, 0.2)));
> boite, @t(4, 0, 0) $U(!sp(0.8, 0.2, 0.2), @t(0.5, 0, 0) !sp(0.9, 0.9, 0.1)),
  @t(0, 4, 0) @rx(30) @h(1, 2, 1) !sp(0.5, 0.5, 0.5), @t(0, -4, 0) !pr(1, 1, 1, 6);
"""

# the formats written a piece at a time (GLB is made per object: few, large pieces)
CHUNKED = [f.name for f in of_kind("stream", "mesh") if f.name not in ("glb", "3mf")]


@pytest.fixture(scope="module")
def frame():
    from castor.mesh.facetize import Facetizer
    from castor.run import evaluated_frames

    (scene,), said = evaluated_frames(SCENE)
    assert said == ""
    made = Facetizer().frame(scene)
    assert len(made.objects) == 4 and made.polygon_count > 1000
    return made


def _sizes(frame):
    return sorted({int(n) for obj in frame.objects for n in (obj.offsets[1:] - obj.offsets[:-1])})


def test_the_scene_has_what_the_writers_must_cut(frame):
    sizes = _sizes(frame)
    assert sizes[0] == 3 and sizes[-1] > 4


@pytest.mark.parametrize("name", CHUNKED)
@pytest.mark.parametrize("size", [1, 7, 1000])
def test_pieces_join_to_the_whole_frame(frame, name, size):
    whole = b"".join(FORMATS[name].write(frame, WriteInfo("scene.obj")))
    module = importlib.import_module(FORMATS[name].write.module)
    chunks = module.export_ascii_chunks if name == "stl-ascii" else module.export_chunks
    pieces = list(chunks(frame, "scene.obj", size=size))
    assert b"".join(pieces) == whole
    if size == 7:  # many pieces, each small
        assert len(pieces) > 50
        assert max(map(len, pieces)) < len(whole) / 10


def test_writers_made_whole_are_handed_on_in_pieces_or_one(frame):
    # GLB's buffer views are all made before its first byte (the JSON gives
    # their lengths and bounds); 3MF's package is compressed whole
    glb = list(encode_pieces(frame, "glb")[0])
    import json

    views = json.loads(glb[0][20:20 + int.from_bytes(glb[0][12:16], "little")])["bufferViews"]
    assert len(glb) == 2 + len(views)  # the header and JSON, the binary's header, each view
    assert b"".join(glb) == encode(frame, "glb")[0]
    assert glb[0][:4] == b"glTF" and int.from_bytes(glb[0][8:12], "little") == len(b"".join(glb))
    (package,) = encode_pieces(frame, "3mf")[0]
    assert package == encode(frame, "3mf")[0]


def test_a_stream_file_is_written_as_its_frames_come(tmp_path, frame):
    target = tmp_path / "scene.cps"
    target.write_bytes(b"old")
    output = Output(str(target), "cps")
    output.start()
    first, _ = encode_pieces(frame, "cps")
    output.put(1, first, {}, None)
    (temporary,) = [p for p in tmp_path.iterdir() if p.name.startswith(".castor-")]
    written = temporary.read_bytes()  # all but what the file's buffer holds
    assert written.startswith(b"castor-polygons 1\nframe 1 ") and len(written) > 100_000
    assert target.read_bytes() == b"old"  # in place only when complete
    output.put(2, b"frame 2 x:1\nendframe 2 0\n", {}, None)
    assert output.finish(False)
    assert target.read_bytes() == (b"castor-polygons 1\n" + encode(frame, "cps")[0]
                                   + b"frame 2 x:1\nendframe 2 0\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.cps"]


def test_an_abandoned_stream_file_leaves_the_old_one(tmp_path, frame):
    target = tmp_path / "scene.cps"
    target.write_bytes(b"old")
    output = Output(str(target), "cps")
    output.put(1, encode_pieces(frame, "cps")[0], {}, None)
    output.abandon()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.cps"]
    assert target.read_bytes() == b"old"


def test_a_failing_writer_leaves_the_old_file(tmp_path):
    target = tmp_path / "x.stl"
    target.write_bytes(b"old")

    def pieces():
        yield b"half"
        raise MemoryError

    with pytest.raises(MemoryError):
        write_atomically(str(target), pieces())
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.stl"]
    assert target.read_bytes() == b"old"


def _spooled_job(monkeypatch, directory, name, target):
    """A frame made as a worker makes a large one: its bytes in a spooled file."""
    import castor.jobs as jobs
    from castor.run import evaluated_frames

    monkeypatch.setattr(jobs, "SPOOL_POLYGONS", 0)
    (scene,), _ = evaluated_frames(SCENE)
    result = jobs.make(jobs.Job(scene, FrameSettings(OutputSettings(
        format=name, target=target, spool=str(directory)))))
    assert isinstance(result.data, Spooled)
    assert os.path.dirname(result.data.path) == str(directory)
    return result


@pytest.mark.parametrize("name", ["stl", "obj", "cps"])
def test_a_spooled_frame_is_written_as_the_bytes_are(tmp_path, monkeypatch, name):
    import castor.jobs as jobs
    from castor.run import evaluated_frames

    suffix = FORMATS[name].suffix
    (scene,), _ = evaluated_frames(SCENE)
    expected = jobs.make(jobs.Job(scene, FrameSettings(OutputSettings(
        format=name, target=str(tmp_path / f"a{suffix}")))))
    assert isinstance(expected.data, bytes)
    # beside the output: renamed into place (a stream file's frames are copied)
    result = _spooled_job(monkeypatch, tmp_path, name, str(tmp_path / f"b{suffix}"))
    output = Output(str(tmp_path / f"b{suffix}"), name)
    output.put(result.number, result.data, result.companions, result.location)
    output.finish(False)
    written = (tmp_path / f"b{suffix}").read_bytes()
    if name == "cps":
        written = written[len(b"castor-polygons 1\n"):]
    if name == "obj":
        written = written.replace(b"mtllib b.mtl", b"mtllib a.mtl")
    assert written == expected.data
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".castor-")]
    assert oct((tmp_path / f"b{suffix}").stat().st_mode & 0o777) != "0o600"


def test_a_spooled_frame_to_standard_output(tmp_path, monkeypatch, capfdbinary):
    result = _spooled_job(monkeypatch, tmp_path, "stl", None)
    expected = Path(result.data.path).read_bytes()
    Output(None, "stl").put(result.number, result.data, {}, result.location)
    assert capfdbinary.readouterr().out == expected
    assert list(tmp_path.iterdir()) == []


def test_a_worker_whose_driver_has_gone_leaves_no_spooled_file(tmp_path, monkeypatch):
    import subprocess
    import sys

    from castor import jobs
    from castor.run import evaluated_frames

    gone = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True)
    monkeypatch.setattr(jobs, "SPOOL_POLYGONS", 0)
    (scene,), _ = evaluated_frames(SCENE)
    result = jobs.make(jobs.Job(scene, FrameSettings(OutputSettings(
        format="stl", spool=str(tmp_path), spool_owner=int(gone.stdout)))))
    assert result.data == b""
    assert list(tmp_path.iterdir()) == []

"""Mesh formats: each opens in trimesh, closed, with the stream's volume and colours."""

from pathlib import Path

import pytest
import trimesh

from castor.formats import FORMATS as REGISTRY, of_kind
from tests.support.cli import run
from tests.support.stream import parse_stream

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# every mesh format castor writes, but 3MF, which trimesh reads only with networkx
# (castor-view reads it with castor's own reader: see below)
FORMATS = [f.name for f in of_kind("mesh") if f.name != "3mf"]
# the mesh formats castor-view reads, each through its format's reader
VIEWED = [f.name for f in of_kind("mesh") if f.read is not None and f.name != "stl-ascii"]


@pytest.fixture(scope="module", params=["car.cas", "house.cas"])
def scene(request, tmp_path_factory):
    directory = tmp_path_factory.mktemp(request.param.split(".")[0])
    status, out, err = run(str(EXAMPLES / request.param), cwd=directory)
    assert status == 0, err
    (frame,) = parse_stream(out)[:1]
    return EXAMPLES / request.param, directory, frame


@pytest.mark.parametrize("name", FORMATS)
def test_format_loads_closed_with_same_volume(scene, name):
    source, directory, frame = scene
    suffix = "stl" if name == "stl-ascii" else name
    target = directory / f"out-{name}.{suffix}"
    status, out, err = run("-f", name, "-o", str(target), str(source), "-D", "ONE_FRAME",
                           cwd=directory)
    assert status == 0, err
    mesh = trimesh.load_mesh(str(target))
    # OBJ materials and glTF primitives share their vertices in the file; trimesh
    # copies them per material on loading, so identify them again by position.
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    assert mesh.is_watertight
    expected = frame.volume()
    tolerance = 1e-6 if name not in ("stl", "glb") else 1e-5  # single precision
    assert mesh.volume == pytest.approx(expected, rel=tolerance)


@pytest.mark.parametrize("name", ["off", "ply", "obj", "glb"])
def test_format_keeps_colours(scene, name):
    source, directory, frame = scene
    target = directory / f"colours.{name}"
    status, out, err = run("-o", str(target), str(source), "-D", "ONE_FRAME", cwd=directory)
    assert status == 0, err
    if name == "off":
        lines = target.read_text().splitlines()
        nv, nf, _ = map(int, lines[1].split())
        colours = {tuple(l.split()[-3:]) for l in lines[2 + nv:2 + nv + nf]}
    elif name == "ply":
        # vertex colours (what Blender reads), one colour per written vertex
        mesh = trimesh.load_mesh(str(target), process=False)
        colours = {tuple(c) for c in mesh.visual.vertex_colors.tolist()}
    else:
        loaded = trimesh.load(str(target))
        materials = [g.visual.material for g in loaded.geometry.values()]
        if name == "obj":
            colours = {tuple(m.main_color.tolist()) for m in materials}
        else:
            colours = {tuple(m.baseColorFactor.tolist()) for m in materials}
    assert len(colours) >= 2
    assert len(colours) == len(frame.colours())


def test_second_frame_without_pattern_is_an_error(tmp_path):
    scene = "> !cu(1,1,1);\n> @t(2,0,0) !cu(1,1,1);\n"
    status, out, err = run("--no-cpp", "-o", str(tmp_path / "x.stl"), stdin=scene)
    assert status == 1
    assert ("<stdin>:2:1: error: stl output holds one frame, and this is frame 2 for "
            f"{tmp_path / 'x.stl'}; give a pattern such as -o {tmp_path / 'x'}-%03d.stl "
            "for one file per frame") in err
    assert trimesh.load_mesh(str(tmp_path / "x.stl")).volume == pytest.approx(1)


def test_pattern_writes_one_file_per_frame(tmp_path):
    scene = ">[T = 1, 3] @h(T, 1, 1) !cu(1,1,1);\n"
    status, out, err = run("--no-cpp", "-o", str(tmp_path / "f-%02d.ply"), stdin=scene)
    assert status == 0, err
    volumes = [trimesh.load_mesh(str(tmp_path / f"f-{i:02d}.ply")).volume for i in (1, 2, 3)]
    assert volumes == pytest.approx([1, 2, 3])


def test_failed_run_keeps_the_old_file(tmp_path):
    target = tmp_path / "keep.cps"
    target.write_text("old\n")
    status, out, err = run("--no-cpp", "-o", str(target), stdin="> nothing;\n")
    assert status == 1
    assert target.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.cps"]


def test_output_file_has_ordinary_permissions(tmp_path):
    target = tmp_path / "p.off"
    run("--no-cpp", "-o", str(target), stdin="> !cu(1,1,1);\n", check_status=0)
    assert target.stat().st_mode & 0o777 == 0o644 or target.stat().st_mode & 0o044


@pytest.mark.skipif(__import__("shutil").which("openscad") is None,
                    reason="OpenSCAD not installed (apt-get install openscad)")
@pytest.mark.parametrize("name", ["off", "stl", "stl-ascii"])
def test_openscad_imports(tmp_path, name):
    """OpenSCAD 2021's import() takes OFF and STL (it has no PLY reader)."""
    import subprocess

    suffix = "stl" if name.startswith("stl") else name
    source = tmp_path / f"house.{suffix}"
    run("-f", name, "-o", str(source), str(EXAMPLES / "house.cas"), check_status=0)
    (tmp_path / "imp.scad").write_text(f'import("{source.name}");\n')
    result = subprocess.run(["openscad", "-o", "back.stl", "imp.scad"], cwd=tmp_path,
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    assert "WARNING" not in result.stderr and "ERROR" not in result.stderr
    back = trimesh.load_mesh(str(tmp_path / "back.stl"))
    original = trimesh.load_mesh(str(source))
    assert back.is_watertight
    assert back.volume == pytest.approx(original.volume, rel=1e-5)


@pytest.mark.parametrize("name", [n for n in VIEWED if n != "stl"])  # STL: no colours
def test_castor_view_draws_a_mesh_file_in_its_colours(tmp_path, name):
    import subprocess
    import sys

    import numpy as np
    from PIL import Image

    path = tmp_path / f"car{REGISTRY[name].suffix}"
    run("-o", str(path), str(Path(__file__).resolve().parents[2] / "examples" / "car.cas"),
        check_status=0)
    picture = tmp_path / "car.png"
    subprocess.run([sys.executable, "-m", "castor.view.cli", "-o", str(picture), str(path)],
                   check=True, capture_output=True, timeout=120)
    image = np.asarray(Image.open(picture)).astype(int)
    red = (image[..., 0] > image[..., 1] + 80) & (image[..., 0] > image[..., 2] + 80)
    assert red.sum() > 1000  # the car's red body, not grey
    (tmp_path / "x.svg").write_text("<svg/>")  # a drawing, which castor-view does not read
    sys_error = subprocess.run([sys.executable, "-m", "castor.view.cli", "-o",
                                str(tmp_path / "x.png"), str(tmp_path / "x.svg")],
                               capture_output=True, text=True, timeout=60)
    assert sys_error.returncode == 2 and "not svg files" in sys_error.stderr


def _view(tmp_path, path, name):
    import subprocess
    import sys

    import numpy as np
    from PIL import Image

    picture = tmp_path / name
    result = subprocess.run([sys.executable, "-m", "castor.view.cli", "--size", "320x240", "-o",
                             str(picture), str(path)], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 0, result.stderr
    return np.asarray(Image.open(picture).convert("RGB")).astype(int)


def test_castor_view_draws_the_house_from_its_3mf_as_from_its_glb(tmp_path):
    import numpy as np

    source = str(Path(__file__).resolve().parents[2] / "examples" / "house.cas")
    for suffix in (".3mf", ".glb"):
        run("-D", "ONE_FRAME", "-o", str(tmp_path / f"house{suffix}"), source, check_status=0)
    from_3mf = _view(tmp_path, tmp_path / "house.3mf", "from-3mf.png")
    from_glb = _view(tmp_path, tmp_path / "house.glb", "from-glb.png")
    background = from_3mf[0, 0]
    drawn = np.any(np.abs(from_3mf - background) > 30, axis=2)
    assert drawn.sum() > 0.1 * drawn.size  # the house, not an empty picture
    # the same house, in the same place and colours: 3MF is in millimetres and z up,
    # glTF in metres and y up, and each reader brings its file back to the scene
    differ = np.any(np.abs(from_3mf - from_glb) > 24, axis=2)
    assert differ.sum() < 0.01 * differ.size
    hues = {tuple(c) for c in (from_3mf[drawn] // 32).tolist()}
    assert len(hues) >= 3  # walls, roof, windows in their colours


def test_the_registry_declares_each_format_once_with_a_known_kind():
    from castor.formats import KINDS

    assert len(REGISTRY) >= 12
    for name, record in REGISTRY.items():
        assert record.name == name and record.kind in KINDS and callable(record.write)
        assert record.suffixes and all(s.startswith(".") for s in record.suffixes)
    # every polygon format castor writes, castor reads back (castor-view draws it)
    assert [f.name for f in of_kind("stream", "mesh") if f.read is None] == []


@pytest.mark.parametrize("name", VIEWED)
def test_each_reader_gives_back_the_frame_castor_wrote(scene, name):
    """Read through the registry: the same box and area as the stream, in scene
    units and z up, whatever the file's units (3MF: mm) and up axis (glTF: y)."""
    import numpy as np

    source, directory, frame = scene
    target = directory / f"back-{name}{REGISTRY[name].suffix}"
    run("-f", name, "-o", str(target), str(source), "-D", "ONE_FRAME", cwd=directory,
        check_status=0)
    [back] = list(REGISTRY[name].read(str(target)))
    np.testing.assert_allclose([back.points.min(axis=0), back.points.max(axis=0)], frame.box(),
                               atol=1e-4)
    tris, _ = back.triangles()
    corners = back.points[tris]
    area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0],
                                         corners[:, 2] - corners[:, 0]), axis=1).sum()
    assert area == pytest.approx(frame.area(), rel=1e-4)

"""Meshes closed as written, and closed as opened after the clicks docs/formats.md gives.

Issue 18, item 16. glTF: every primitive of an object indexes one accessor of
positions, so the object's triangles pair every edge as written; importers still
make a piece per primitive, closed again by merging vertices (Blender's "Merge
Vertices", MeshLab's "Merge Close Vertices", trimesh's merge_vertices). PLY:
a vertex per colour where colours meet (Blender reads only vertex colours), closed
by the same merge. Each tool's figures before and after are asserted here, where
the tool is installed.
"""

import json
import os
import shutil
import struct
import subprocess
from pathlib import Path

import numpy as np
import pytest

from tests.support.cli import run

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def house(tmp_path_factory):
    here = tmp_path_factory.mktemp("closed")
    for suffix in ("glb", "ply"):
        run("-o", str(here / f"house.{suffix}"), str(EXAMPLES / "house.cas"), check_status=0)
    return here


def _glb(path):
    data = path.read_bytes()
    length, _ = struct.unpack_from("<II", data, 12)
    document = json.loads(data[20:20 + length])
    binary = data[20 + length + 8:]
    return document, binary


def _edges_pair(triangles: np.ndarray) -> bool:
    """Every directed edge used once, and its reverse once: a closed, oriented surface."""
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    forward = {tuple(e) for e in edges.tolist()}
    return len(forward) == len(edges) and all((b, a) in forward for a, b in forward)


def test_glb_objects_share_one_accessor_of_positions_and_close(house):
    document, binary = _glb(house / "house.glb")
    for mesh in document["meshes"]:
        positions = {p["attributes"]["POSITION"] for p in mesh["primitives"]}
        assert len(positions) == 1 and len(mesh["primitives"]) > 1
        triangles = []
        for primitive in mesh["primitives"]:
            accessor = document["accessors"][primitive["indices"]]
            view = document["bufferViews"][accessor["bufferView"]]
            start = view["byteOffset"] + accessor.get("byteOffset", 0)
            triangles.append(np.frombuffer(binary, "<u4", accessor["count"], start).reshape(-1, 3))
        assert _edges_pair(np.concatenate(triangles)), mesh["name"]


def test_trimesh_closes_each_object_after_merging(house):
    trimesh = pytest.importorskip("trimesh")
    scene = trimesh.load(house / "house.glb")
    pieces = list(scene.geometry.values())
    assert len(pieces) == 6 and not any(p.is_watertight for p in pieces)  # one per colour
    merged = trimesh.load(house / "house.glb", force="mesh")
    merged.merge_vertices()
    assert not merged.is_watertight  # vertices of each material kept apart by default
    merged.merge_vertices(merge_tex=True, merge_norm=True)
    assert merged.is_watertight and merged.is_winding_consistent
    ply = trimesh.load(house / "house.ply", process=False)
    assert not ply.is_watertight  # a vertex per colour
    ply = trimesh.load(house / "house.ply")  # trimesh merges them as it loads
    assert ply.is_watertight


def test_meshlab_closes_them_after_merge_close_vertices(house):
    pymeshlab = pytest.importorskip("pymeshlab")
    for suffix in ("glb", "ply"):
        meshes = pymeshlab.MeshSet()
        meshes.load_new_mesh(str(house / f"house.{suffix}"))
        before = meshes.get_topological_measures()["boundary_edges"]
        meshes.meshing_merge_close_vertices()
        after = meshes.get_topological_measures()["boundary_edges"]
        assert before > 0 and after == 0, (suffix, before, after)


BLENDER_SCRIPT = """
import sys
import numpy
numpy.bool = bool  # Debian's numpy 1.24+ against Blender 3.4's glTF importer
import bmesh, bpy
path, merge = sys.argv[-2], sys.argv[-1] == "merge"
bpy.ops.wm.read_factory_settings(use_empty=True)
if path.endswith(".glb"):
    bpy.ops.import_scene.gltf(filepath=path, merge_vertices=merge)
else:
    bpy.ops.import_mesh.ply(filepath=path)
for o in bpy.data.objects:
    if o.type == "MESH":
        bm = bmesh.new()
        bm.from_mesh(o.data)
        if merge and path.endswith(".ply"):  # Mesh > Clean Up > Merge by Distance
            bmesh.ops.remove_doubles(bm, verts=bm.verts, dist=1e-6)
        print("NONMANIFOLD", sum(1 for e in bm.edges if not e.is_manifold))
"""


@pytest.mark.skipif(shutil.which("blender") is None,
                    reason="Blender not installed (apt-get install blender)")
@pytest.mark.parametrize("suffix", ["glb", "ply"])
def test_blender_closes_them_after_merging(house, suffix):
    (house / "count.py").write_text(BLENDER_SCRIPT)
    # Blender's own Python may lack numpy (its glTF importer needs it): lend it ours
    env = {**os.environ, "PYTHONPATH": os.path.dirname(os.path.dirname(np.__file__))}
    counts = {}
    for merge in ("plain", "merge"):
        result = subprocess.run(["blender", "-b", "--factory-startup", "--python",
                                 str(house / "count.py"), "--", str(house / f"house.{suffix}"),
                                 merge], capture_output=True, text=True, timeout=300, env=env)
        if "No module named 'numpy'" in result.stdout + result.stderr:
            pytest.skip("Blender's Python has no numpy")
        found = [int(line.split()[1]) for line in result.stdout.splitlines()
                 if line.startswith("NONMANIFOLD")]
        assert len(found) == 1, result.stdout + result.stderr
        counts[merge] = found[0]
    assert counts["plain"] > 0 and counts["merge"] == 0, counts

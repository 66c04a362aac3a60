"""What castor-view draws: frames of coloured convex polygons, read from a
polygon stream as it arrives, or from a mesh file through trimesh."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator

import numpy as np


class ViewError(Exception):
    """Input castor-view cannot read; the message says where and why."""


@dataclass
class Picture:
    """One frame: polygons as a flat vertex list with offsets, and a colour each."""

    number: int
    where: str
    points: np.ndarray  # (N, 3) float64, polygon after polygon
    offsets: np.ndarray  # (P + 1,)
    colours: np.ndarray  # (P, 3) in 0..1

    @property
    def polygon_count(self) -> int:
        return len(self.offsets) - 1

    def triangles(self) -> tuple[np.ndarray, np.ndarray]:
        """Fan triangles as point numbers, and the polygon of each."""
        from castor.mesh.polygons import fan_triangles

        return fan_triangles(self.offsets, np.arange(len(self.points)))


def read_stream(lines: Iterator[str], name: str = "<stdin>") -> Iterator[Picture]:
    """Frames of a castor polygon stream, each as soon as its 'endframe' is read."""
    header_seen = False
    current = None
    for number, line in enumerate(lines, 1):
        line = line.rstrip("\n")
        if not line:
            continue
        if not header_seen:
            if not line.startswith("castor-polygons "):
                raise ViewError(f"{name}:{number}: not a castor polygon stream (first line is "
                                f"'{line[:40]}'); give a mesh file, or pipe castor's output")
            header_seen = True
            continue
        fields = line.split(" ")
        kind = fields[0]
        try:
            if kind == "frame":
                current = (int(fields[1]), fields[2] if len(fields) > 2 else "", [], [], [0])
            elif kind == "poly":
                _, _, points, colours, offsets = current
                n = int(fields[5])
                values = np.array(fields[6:6 + 3 * n], dtype=np.float64)
                if len(values) != 3 * n:
                    raise ValueError("vertex count")
                colours.append([float(x) for x in fields[2:5]])
                points.append(values.reshape(n, 3))
                offsets.append(offsets[-1] + n)
            elif kind == "endframe":
                frame_number, where, points, colours, offsets = current
                yield Picture(frame_number, where,
                              np.concatenate(points) if points else np.zeros((0, 3)),
                              np.array(offsets, np.int64),
                              np.array(colours, dtype=np.float64).reshape(-1, 3))
                current = None
        except (ValueError, IndexError, TypeError):
            raise ViewError(f"{name}:{number}: malformed '{kind}' record") from None


def read_mesh_file(path: str) -> Picture:
    """A mesh file (.off .obj .stl .ply .glb) as one frame."""
    try:
        import trimesh
    except ImportError:  # pragma: no cover - trimesh is a dependency
        raise ViewError("reading mesh files needs trimesh") from None
    try:
        loaded = trimesh.load(path, process=False)
    except Exception as exc:  # trimesh raises many kinds; all mean "cannot read"
        raise ViewError(f"{path}: cannot read this mesh file ({exc})") from None
    meshes = list(loaded.geometry.values()) if hasattr(loaded, "geometry") else [loaded]
    if hasattr(loaded, "graph"):
        meshes = []
        for node in loaded.graph.nodes_geometry:
            transform, name = loaded.graph[node]
            mesh = loaded.geometry[name].copy()
            mesh.apply_transform(transform)
            meshes.append(mesh)
    points, colours = [], []
    for mesh in meshes:
        if not hasattr(mesh, "faces") or len(mesh.faces) == 0:
            continue
        points.append(np.asarray(mesh.vertices, dtype=np.float64)[mesh.faces].reshape(-1, 3))
        colours.append(_face_colours(mesh))
    if not points:
        raise ViewError(f"{path}: the file holds no faces")
    count = sum(len(c) for c in colours)
    points = np.concatenate(points)
    if path.lower().endswith((".glb", ".gltf", ".obj")):
        # +Y up in the file (as castor writes them): back to the scene's z up
        points = np.column_stack([points[:, 0], -points[:, 2], points[:, 1]]) + 0.0
    return Picture(1, path, points, np.arange(count + 1) * 3, np.concatenate(colours))


def _face_colours(mesh) -> np.ndarray:
    default = np.full((len(mesh.faces), 3), 0.8)
    visual = getattr(mesh, "visual", None)
    try:
        material = getattr(visual, "material", None)
        if material is not None:
            colour = getattr(material, "baseColorFactor", None)
            if colour is None:
                colour = getattr(material, "main_color", None)
            if colour is not None:
                rgb = np.asarray(colour, dtype=np.float64)[:3]
                rgb = rgb / 255.0 if rgb.max() > 1 else rgb
                if getattr(material, "baseColorFactor", None) is not None:
                    rgb = np.where(rgb <= 0.0031308, rgb * 12.92, 1.055 * rgb ** (1 / 2.4) - 0.055)
                return np.tile(rgb, (len(mesh.faces), 1))
        if visual is not None and visual.kind == "face":
            return np.asarray(visual.face_colors, dtype=np.float64)[:, :3] / 255.0
    except Exception:  # colours are a nicety: fall back to grey
        return default
    return default

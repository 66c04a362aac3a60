"""Reading a mesh file back (castor-view) through trimesh: OBJ, STL, PLY, glTF."""

from __future__ import annotations

import numpy as np

from castor.formats.cps import StreamError, StreamFrame


def read_with_trimesh(path: str, up: str = "z"):
    """A mesh file as one frame of coloured triangles (castor.formats.cps.StreamFrame),
    z up: a file written +Y up (``up="y"``: glTF, OBJ) is turned back to the
    scene's axes. Raises castor.formats.cps.StreamError when it cannot be read."""
    try:
        import trimesh
    except ImportError:  # pragma: no cover - trimesh is a dependency
        raise StreamError("reading mesh files needs trimesh") from None
    try:
        loaded = trimesh.load(path, process=False)
    except Exception as exc:  # trimesh raises many kinds; all mean "cannot read"
        raise StreamError(f"{path}: cannot read this mesh file ({exc})") from None
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
        raise StreamError(f"{path}: the file holds no faces")
    count = sum(len(c) for c in colours)
    points = np.concatenate(points)
    if up == "y":  # back to the scene's z up: the inverse of ``y_up``
        points = np.column_stack([points[:, 0], -points[:, 2], points[:, 1]]) + 0.0
    yield StreamFrame(1, path, points, np.arange(count + 1) * 3, np.concatenate(colours))


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
        if visual is not None and visual.kind == "vertex":  # a PLY's vertex colours
            corners = np.asarray(visual.vertex_colors, dtype=np.float64)[mesh.faces, :3]
            return corners.mean(axis=1) / 255.0
    except Exception:  # colours are a nicety: fall back to grey
        return default
    return default

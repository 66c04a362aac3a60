"""What castor-view draws: frames of coloured convex polygons, read from a
polygon stream as it arrives (castor.formats.cps.load), or from a mesh file
through trimesh."""

from __future__ import annotations

import numpy as np

from castor.formats.cps import StreamError, StreamFrame, load


# the stream's reader lives beside its writer
ViewError = StreamError
Picture = StreamFrame
read_stream = load


def read_mesh_file(path: str) -> Picture:
    """A mesh file (.off .obj .stl .ply .glb) as one frame."""
    if path.lower().endswith(".off"):  # read beside its writer: trimesh drops OFF colours
        from castor.formats.off import load

        try:
            with open(path, encoding="utf-8", errors="replace") as handle:
                points, offsets, colours = load(handle.read())
        except (OSError, ValueError, IndexError) as exc:
            raise ViewError(f"{path}: cannot read this OFF file ({exc})") from None
        return Picture(1, path, points, offsets, colours)
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
        if visual is not None and visual.kind == "vertex":  # a PLY's vertex colours
            corners = np.asarray(visual.vertex_colors, dtype=np.float64)[mesh.faces, :3]
            return corners.mean(axis=1) / 255.0
    except Exception:  # colours are a nicety: fall back to grey
        return default
    return default

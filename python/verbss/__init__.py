"""verbss: Vertex-Ball Spring Smoothing mesh motion for unstructured 2D/3D
hybrid meshes (triangles, quads, tetrahedra, hexahedra, prisms, pyramids),
from numpy.

    import numpy as np
    import verbss

    mesh = verbss.read("mesh_NACA0012_inv.su2")
    d = verbss.Deformer(mesh, tolerance=1e-6)
    for n in range(1, 11):
        points = d.step({"airfoil": np.array([0.0, 0.01 * n])})  # (N, 2) array
        print(d.info["iterations"], d.info["min_quality"])
    d.mesh.write("moved.vtu")

Errors raise :class:`VerbssError` (a ``ValueError``) with the message the
``verbss`` command prints.
"""

import json
from typing import Any, Dict, List, Tuple

import numpy as np

from ._verbss import Deformer, GilProbe, Mesh, VerbssError, quality_json, read, settings_table

__all__ = [
    "Deformer",
    "GilProbe",
    "Mesh",
    "VerbssError",
    "from_meshio",
    "quality",
    "read",
    "settings_table",
    "to_meshio",
]

#: Topological dimension of each cell kind verbss knows (meshio names).
_KIND_DIM = {
    "vertex": 0,
    "line": 1,
    "triangle": 2,
    "quad": 2,
    "tetra": 3,
    "hexahedron": 3,
    "wedge": 3,
    "pyramid": 3,
}


def quality(mesh: Mesh) -> Dict[str, Any]:
    """The ``verbss quality --json`` summary of ``mesh``: dimension, nodes,
    elements, element counts per kind, distinct nodes per group, quality
    (``min``, ``mean`` and the paper's five ``bins`` with ``lo``, ``hi``,
    ``count``) and the number of inverted (tangled or degenerate) elements."""
    return json.loads(quality_json(mesh))


def from_meshio(m: Any) -> Mesh:
    """A :class:`Mesh` from a ``meshio.Mesh``.

    The volume cells are the blocks of the highest dimension (3 if there is a
    tetra, hexahedron, wedge or pyramid block, else 2); a 2D mesh keeps the
    first two coordinate columns. Groups come from ``m.cell_sets`` (their
    lower-dimensional cells become the group's facets); without cell sets,
    from the ``gmsh:physical`` or ``su2:tag`` cell data (named from
    ``m.field_data`` where it names the tag, else by the tag number); and
    from ``m.point_sets`` (node ids). Node order is passed through unchanged.
    """
    kinds = [block.type for block in m.cells]
    unknown = sorted(set(kinds) - set(_KIND_DIM))
    if unknown:
        raise VerbssError(
            "invalid mesh: meshio cell kind(s) %s are not linear kinds verbss knows"
            % ", ".join(unknown)
        )
    dim = max((_KIND_DIM[k] for k in kinds), default=0)
    if dim not in (2, 3):
        raise VerbssError("invalid mesh: the meshio mesh has no 2D or 3D cells")
    points = np.asarray(m.points, dtype=np.float64)[:, :dim]
    cells = [(b.type, b.data) for b in m.cells if _KIND_DIM[b.type] == dim]
    groups: Dict[str, Dict[str, np.ndarray]] = {}

    def add(name: str, kind: str, facets: np.ndarray) -> None:
        if len(facets) == 0:
            return
        kinds_of = groups.setdefault(name, {})
        if kind in kinds_of:
            kinds_of[kind] = np.concatenate([kinds_of[kind], facets])
        else:
            kinds_of[kind] = facets

    for name, per_block in (m.cell_sets or {}).items():
        for block, index in zip(m.cells, per_block):
            if index is not None and _KIND_DIM[block.type] < dim:
                add(name, block.type, block.data[np.asarray(index, dtype=np.int64)])
    if not groups:
        tag_key = next((k for k in ("gmsh:physical", "su2:tag") if k in m.cell_data), None)
        if tag_key is not None:
            names = {
                (int(v[0]), int(v[1])): name
                for name, v in (m.field_data or {}).items()
                if len(v) >= 2
            }
            for block, tags in zip(m.cells, m.cell_data[tag_key]):
                kind_dim = _KIND_DIM[block.type]
                if kind_dim >= dim:
                    continue
                for tag in np.unique(tags):
                    name = names.get((int(tag), kind_dim), str(int(tag)))
                    add(name, block.type, block.data[tags == tag])
    for name, ids in (m.point_sets or {}).items():
        if name not in groups:
            add(name, "vertex", np.asarray(ids, dtype=np.int64).reshape(-1, 1))
    return Mesh(points, cells, groups)


def to_meshio(mesh: Mesh) -> Any:
    """``mesh`` as a ``meshio.Mesh``: the volume cells by kind, each group's
    facets as blocks of their own named in ``cell_sets`` (so that
    :func:`from_meshio` gives the groups back), groups of single nodes as
    ``point_sets``."""
    import meshio  # type: ignore[import-untyped]

    blocks: List[Tuple[str, np.ndarray]] = list(mesh.cells.items())
    members: Dict[str, List[int]] = {}
    point_sets: Dict[str, np.ndarray] = {}
    for name in mesh.groups:
        for kind, facets in mesh.group_facets(name).items():
            if kind == "vertex":
                point_sets[name] = facets[:, 0]
            else:
                members.setdefault(name, []).append(len(blocks))
                blocks.append((kind, facets))
    cell_sets = {
        name: [
            np.arange(len(data)) if b in own else np.zeros(0, dtype=np.int64)
            for b, (_, data) in enumerate(blocks)
        ]
        for name, own in members.items()
    }
    return meshio.Mesh(mesh.points, blocks, cell_sets=cell_sets, point_sets=point_sets)

#!/usr/bin/env python3
"""Writes the meshio-made .vtu fixtures under assets/meshes/vtu/.

The Rust tests in crates/verbss/src/io/vtu.rs read these files and compare
them with the meshes built here, so keep the two in step. Run from the
repository root:  python3 scripts/make_vtu_fixtures.py  (needs meshio, numpy).
"""

import pathlib

import meshio
import numpy as np

OUT = pathlib.Path(__file__).resolve().parent.parent / "assets" / "meshes" / "vtu"

# 2D: two triangles and a quad on [0,2]x[0,1]; boundary lines at the bottom
# and at the top.
POINTS_2D = np.array(
    [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0]]
)
CELLS_2D = [
    ("triangle", np.array([[1, 2, 5], [1, 5, 4]])),
    ("quad", np.array([[0, 1, 4, 3]])),
    ("line", np.array([[0, 1], [1, 2], [5, 4], [4, 3]])),
]

# 3D: a unit hexahedron, a wedge beside it, a pyramid on top of it and a
# tetrahedron beside the pyramid; two boundary facets.
POINTS_3D = np.array(
    [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
        [2.0, 0.0, 0.0],
        [2.0, 0.0, 1.0],
        [0.5, 0.5, 1.5],
        [1.5, 0.25, 1.5],
    ]
)
CELLS_3D = [
    ("hexahedron", np.array([[0, 1, 2, 3, 4, 5, 6, 7]])),
    ("wedge", np.array([[1, 8, 2, 5, 9, 6]])),
    ("pyramid", np.array([[4, 5, 6, 7, 10]])),
    ("tetra", np.array([[5, 9, 6, 11]])),
    ("quad", np.array([[0, 3, 2, 1]])),
    ("triangle", np.array([[1, 2, 8]])),
]


def main():
    OUT.mkdir(parents=True, exist_ok=True)

    # zlib-compressed inline binary, UInt32 headers (meshio's default), with
    # point and cell data. (meshio writes no <FieldData>, so no group names.)
    mesh = meshio.Mesh(
        POINTS_2D,
        CELLS_2D,
        point_data={"u": POINTS_2D * 0.5},
        cell_data={
            "pressure": [
                np.array([1.5, 2.5]),
                np.array([3.5]),
                np.array([0.0, 0.0, 0.0, 0.0]),
            ],
        },
    )
    meshio.write(OUT / "meshio_2d_zlib.vtu", mesh)

    # ascii, no group array: the facets form the group "boundary".
    mesh = meshio.Mesh(POINTS_3D, CELLS_3D)
    meshio.write(OUT / "meshio_3d_ascii.vtu", mesh, binary=False)

    # uncompressed inline binary, UInt64 headers, Float32 points, Int32 cells.
    mesh = meshio.Mesh(
        POINTS_3D.astype(np.float32),
        [(kind, nodes.astype(np.int32)) for kind, nodes in CELLS_3D],
    )
    meshio.write(
        OUT / "meshio_3d_raw64.vtu", mesh, compression=None, header_type="UInt64"
    )


if __name__ == "__main__":
    main()

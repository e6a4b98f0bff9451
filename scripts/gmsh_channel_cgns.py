#!/usr/bin/env python3
"""Writes, with Gmsh's own CGNS writer, a 2D channel around a square
cylinder (triangles) and a 3D box around a cube (tetrahedra) as
DIR/channel2.cgns and DIR/channel3.cgns, each with physical groups
`cylinder`, `inlet`, `outlet`, `walls` and `fluid`.

The CGNS tests of verbss-cli and verbss-mpi run it:
python3 scripts/gmsh_channel_cgns.py DIR  (needs PyPI gmsh).
"""
import sys, gmsh
gmsh.initialize(); gmsh.option.setNumber("General.Terminal", 0)
for dim in (2, 3):
    gmsh.model.add(f"channel{dim}")
    occ = gmsh.model.occ
    if dim == 2:
        outer, inner = occ.addRectangle(0, 0, 0, 4, 1), occ.addRectangle(1, 0.4, 0, 0.2, 0.2)
    else:
        outer, inner = occ.addBox(0, 0, 0, 4, 1, 1), occ.addBox(1, 0.4, 0.4, 0.2, 0.2, 0.2)
    fluid, _ = occ.cut([(dim, outer)], [(dim, inner)])
    occ.synchronize()
    faces = {"cylinder": [], "inlet": [], "outlet": [], "walls": []}
    for _, tag in gmsh.model.getBoundary(fluid, oriented=False):
        x, y, z = occ.getCenterOfMass(dim - 1, tag)
        name = ("inlet" if x < 1e-9 else "outlet" if x > 4 - 1e-9 else
                "cylinder" if 0.9 < x < 1.3 and 0.3 < y < 0.7 and (dim == 2 or 0.3 < z < 0.7)
                else "walls")
        faces[name].append(tag)
    for name, tags in faces.items():
        gmsh.model.addPhysicalGroup(dim - 1, tags, name=name)
    gmsh.model.addPhysicalGroup(dim, [t for _, t in fluid], name="fluid")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.25 if dim == 3 else 0.1)
    gmsh.model.mesh.generate(dim)
    gmsh.write(f"{sys.argv[1]}/channel{dim}.cgns")
    gmsh.model.remove()
gmsh.finalize()

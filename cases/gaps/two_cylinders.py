"""Two cylinders of radius 0.5 at (-1.5, 0) and (1.5, 0) in the box [-5, 5] x [-3, 3]
(groups `left`, `right`, `box`), Gmsh triangles of size H/4 at the cylinders growing
to H at distance 2 (docs/robustness.md, "Squeezed gaps": the left cylinder moved 1.8,
90% of the gap, in 40 steps).

    python3 cases/gaps/two_cylinders.py H OUT.msh
    verbss deform OUT.msh -o moved.msh --moving left --translate 1.8,0 --steps 40
"""

import sys

import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("two")
occ = gmsh.model.occ
box = occ.addRectangle(-5, -3, 0, 10, 6)
a = occ.addDisk(-1.5, 0, 0, 0.5, 0.5); b = occ.addDisk(1.5, 0, 0, 0.5, 0.5)
out, _ = occ.cut([(2, box)], [(2, a), (2, b)]); occ.synchronize()
curves = gmsh.model.getBoundary(out, oriented=False)
ca, cb, outer = [], [], []
for _, c in curves:
    x, y, _ = occ.getCenterOfMass(1, c)
    (ca if abs(x + 1.5) < 0.6 and abs(y) < 0.6 else cb if abs(x - 1.5) < 0.6 and abs(y) < 0.6 else outer).append(c)
gmsh.model.addPhysicalGroup(1, ca, name="left")
gmsh.model.addPhysicalGroup(1, cb, name="right")
gmsh.model.addPhysicalGroup(1, outer, name="box")
gmsh.model.addPhysicalGroup(2, [out[0][1]], name="fluid")
gmsh.option.setNumber("Mesh.MeshSizeMax", float(sys.argv[1]))
gmsh.option.setNumber("Mesh.MeshSizeMin", float(sys.argv[1]) / 4)
f = gmsh.model.mesh.field
d = f.add("Distance"); f.setNumbers(d, "CurvesList", ca + cb)
t = f.add("Threshold"); f.setNumber(t, "InField", d); f.setNumber(t, "SizeMin", float(sys.argv[1]) / 4)
f.setNumber(t, "SizeMax", float(sys.argv[1])); f.setNumber(t, "DistMin", 0.2); f.setNumber(t, "DistMax", 2)
f.setAsBackgroundMesh(t)
gmsh.model.mesh.generate(2)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.write(sys.argv[2]); gmsh.finalize()

"""A boundary-layer airfoil in a box, meshed by Gmsh (physical groups
`airfoil`, `farfield`, `fluid`), written whole and split in 3 by Gmsh's
partitioner, as MSH 4.1: DIR/whole.msh and DIR/split.msh.

In the split file, the partition curves between partitions also carry the
physical tag of their parent surface and line elements, as some Gmsh
versions and scripts write them (issue 43, 17: verbss read them as
numbered groups of interior nodes, held fixed by `deform`).

Usage: python3 scripts/gmsh_partitioned_airfoil.py DIR
"""

import sys

import gmsh

out = sys.argv[1]
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
occ = gmsh.model.occ
box = occ.addRectangle(-2, -2, 0, 5, 4)
wing = occ.addPlaneSurface([occ.addCurveLoop([occ.addEllipse(0.5, 0, 0, 0.5, 0.06)])])
occ.rotate([(2, wing)], 0.5, 0, 0, 0, 0, 1, -0.1)
fluid = occ.cut([(2, box)], [(2, wing)])[0]
occ.synchronize()
curves = [t for _, t in gmsh.model.getBoundary(fluid, oriented=False)]
inner = [c for c in curves if gmsh.model.getBoundingBox(1, c)[0] > -1]
gmsh.model.addPhysicalGroup(1, inner, name="airfoil")
gmsh.model.addPhysicalGroup(1, [c for c in curves if c not in inner], name="farfield")
surface = gmsh.model.addPhysicalGroup(2, [t for _, t in fluid], name="fluid")
fields = gmsh.model.mesh.field
layer = fields.add("BoundaryLayer")
fields.setNumbers(layer, "CurvesList", inner)
fields.setNumber(layer, "Size", 0.004)
fields.setNumber(layer, "Ratio", 1.3)
fields.setNumber(layer, "Thickness", 0.04)
fields.setNumber(layer, "Quads", 1)
fields.setAsBoundaryLayer(layer)
gmsh.option.setNumber("Mesh.MeshSizeMax", 0.25)
gmsh.option.setNumber("Mesh.MeshSizeMin", 0.01)
gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 30)
gmsh.model.mesh.generate(2)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.write(f"{out}/whole.msh")

gmsh.model.mesh.partition(3)
# The edges between two partitions, on the partition curve of that pair.
pieces = {}
for dim, tag in gmsh.model.getEntities(2):
    parts = gmsh.model.getPartitions(dim, tag)
    if len(parts) != 1:
        continue
    for kind, nodes in zip(*gmsh.model.mesh.getElements(dim, tag)[::2]):
        k = gmsh.model.mesh.getElementProperties(kind)[3]
        corners = {3: 3, 6: 3, 4: 4, 9: 4}.get(k, k)
        for e in range(len(nodes) // k):
            element = nodes[e * k : e * k + corners]
            for i in range(corners):
                edge = tuple(sorted((element[i], element[(i + 1) % corners])))
                pieces.setdefault(edge, set()).add(parts[0])
between = {}
for edge, parts in pieces.items():
    if len(parts) == 2:
        between.setdefault(tuple(sorted(parts)), []).extend(edge)
boundaries = []
for dim, tag in gmsh.model.getEntities(1):
    parent = gmsh.model.getParent(dim, tag)
    parts = tuple(sorted(gmsh.model.getPartitions(dim, tag)))
    if parent[0] == 2 and parts in between:
        gmsh.model.mesh.addElementsByType(tag, 1, [], between[parts])
        boundaries.append(tag)
gmsh.model.addPhysicalGroup(1, boundaries, surface)
gmsh.write(f"{out}/split.msh")
gmsh.finalize()

"""Generate the small Gmsh fixtures in assets/meshes/gmsh/ with Gmsh itself.

Run from the repository root:

    python3 scripts/make_gmsh_fixtures.py

It writes

* channel_hole_v22_ascii.msh, channel_hole_v22_binary.msh,
  channel_hole_v41_ascii.msh, channel_hole_v41_binary.msh: one 2D hybrid mesh
  (triangles around a circular hole in [0,1]x[0,1], a transfinite quad block in
  [1,2]x[0,1]) with physical curves "wall", "inlet", "outlet", "sides", a
  physical point "corner" and a physical surface "fluid";
* box_v41_ascii.msh, box_v22_ascii.msh: a 3D tetrahedral box [0,1]^3 with
  physical surfaces "inlet" (x=0), "outlet" (x=1), "sides" (the four others)
  and "boundary" (all six, so every boundary triangle is in two groups) and a
  physical volume "fluid";
* counts.json: Gmsh's own numbers for each file (the mesh dimension, the number
  of cells of that dimension per Gmsh element type, the number of elements in
  each physical group, all taken from the model in memory, and the number of
  nodes Gmsh finds when it reopens the file), the reference the reader's tests
  compare against.
"""

import json
import os
import sys

import gmsh

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "meshes", "gmsh")


def on_line(tag, dim, coord, value, tol=1e-6):
    """Whether entity (dim, tag) lies entirely on the plane coord = value."""
    box = gmsh.model.getBoundingBox(dim, tag)
    return abs(box[coord] - value) < tol and abs(box[coord + 3] - value) < tol


def channel_with_hole():
    gmsh.model.add("channel_hole")
    occ = gmsh.model.occ
    left = occ.addRectangle(0, 0, 0, 1, 1)
    hole = occ.addDisk(0.5, 0.5, 0, 0.2, 0.2)
    cut, _ = occ.cut([(2, left)], [(2, hole)])
    right = occ.addRectangle(1, 0, 0, 1, 1)
    occ.fragment(cut, [(2, right)])
    occ.synchronize()
    surfaces = [t for _, t in gmsh.model.getEntities(2)]
    quad_block = [s for s in surfaces if gmsh.model.getBoundingBox(2, s)[0] > 0.5][0]
    for _, c in gmsh.model.getBoundary([(2, quad_block)], oriented=False):
        gmsh.model.mesh.setTransfiniteCurve(c, 7)
    gmsh.model.mesh.setTransfiniteSurface(quad_block)
    gmsh.model.mesh.setRecombine(2, quad_block)
    curves = [t for _, t in gmsh.model.getEntities(1)]
    wall = [c for c in curves if gmsh.model.getType(1, c) != "Line"]
    inlet = [c for c in curves if on_line(c, 1, 0, 0.0)]
    outlet = [c for c in curves if on_line(c, 1, 0, 2.0)]
    sides = [c for c in curves if on_line(c, 1, 1, 0.0) or on_line(c, 1, 1, 1.0)]
    corner = [p for _, p in gmsh.model.getEntities(0)
              if on_line(p, 0, 0, 0.0) and on_line(p, 0, 1, 0.0)]
    gmsh.model.addPhysicalGroup(1, wall, name="wall")
    gmsh.model.addPhysicalGroup(1, inlet, name="inlet")
    gmsh.model.addPhysicalGroup(1, outlet, name="outlet")
    gmsh.model.addPhysicalGroup(1, sides, name="sides")
    gmsh.model.addPhysicalGroup(0, corner, name="corner")
    gmsh.model.addPhysicalGroup(2, surfaces, name="fluid")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.15)
    gmsh.model.mesh.generate(2)


def box():
    gmsh.model.add("box")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    faces = [t for _, t in gmsh.model.getEntities(2)]
    inlet = [f for f in faces if on_line(f, 2, 0, 0.0)]
    outlet = [f for f in faces if on_line(f, 2, 0, 1.0)]
    sides = [f for f in faces if f not in inlet + outlet]
    gmsh.model.addPhysicalGroup(2, inlet, name="inlet")
    gmsh.model.addPhysicalGroup(2, outlet, name="outlet")
    gmsh.model.addPhysicalGroup(2, sides, name="sides")
    gmsh.model.addPhysicalGroup(2, faces, name="boundary")
    gmsh.model.addPhysicalGroup(3, [1], name="fluid")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.4)
    gmsh.model.mesh.generate(3)


def save(name, version, binary):
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", 1 if binary else 0)
    gmsh.write(os.path.join(OUT, name))


def model_reference():
    """What the model in memory holds: its cells and its physical groups."""
    top = gmsh.model.getDimension()
    types, elems, _ = gmsh.model.mesh.getElements(top)
    per_type = {str(t): len(e) for t, e in zip(types, elems)}
    groups = {}
    for dim, tag in gmsh.model.getPhysicalGroups():
        n = 0
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            _, ents, _ = gmsh.model.mesh.getElements(dim, ent)
            n += sum(len(e) for e in ents)
        groups[gmsh.model.getPhysicalName(dim, tag)] = {"dim": dim, "tag": tag, "elements": n}
    return {"dim": top, "cells": sum(len(e) for e in elems), "cells_per_type": per_type,
            "groups": groups}


def node_count(name):
    """Reopen a written file and count the nodes Gmsh finds in it."""
    gmsh.clear()
    gmsh.open(os.path.join(OUT, name))
    tags, _, _ = gmsh.model.mesh.getNodes()
    return len(tags)


def main():
    os.makedirs(OUT, exist_ok=True)
    gmsh.initialize(sys.argv[:1])
    gmsh.option.setNumber("General.Terminal", 0)
    files = {}
    channel_with_hole()
    reference = model_reference()
    for name, version, binary in [
        ("channel_hole_v22_ascii.msh", 2.2, False),
        ("channel_hole_v22_binary.msh", 2.2, True),
        ("channel_hole_v41_ascii.msh", 4.1, False),
        ("channel_hole_v41_binary.msh", 4.1, True),
    ]:
        save(name, version, binary)
        files[name] = reference
    box()
    reference = model_reference()
    for name, version, binary in [
        ("box_v41_ascii.msh", 4.1, False),
        ("box_v22_ascii.msh", 2.2, False),
    ]:
        save(name, version, binary)
        files[name] = reference
    counts = {name: dict(ref, nodes=node_count(name)) for name, ref in files.items()}
    gmsh.finalize()
    with open(os.path.join(OUT, "counts.json"), "w") as f:
        json.dump(counts, f, indent=2, sort_keys=True)
        f.write("\n")


if __name__ == "__main__":
    main()

"""What the mesh scripts in this folder share: the graded size field, the
Gmsh options, writing Gmsh MSH 4.1 binary, and the command line."""

import sys

import gmsh


def graded(key, tags, h_min, h_max, d_min, d_max, sampling=None):
    """A Threshold field on the distance to `tags` (`key`: "PointsList",
    "CurvesList" or "SurfacesList", sampled at `sampling` points per curve
    when given): size `h_min` up to distance `d_min`, growing linearly to
    `h_max` at `d_max`. Returns the field's tag."""
    f = gmsh.model.mesh.field
    dist = f.add("Distance")
    f.setNumbers(dist, key, tags)
    if sampling is not None:
        f.setNumber(dist, "Sampling", sampling)
    thr = f.add("Threshold")
    f.setNumber(thr, "InField", dist)
    f.setNumber(thr, "SizeMin", h_min)
    f.setNumber(thr, "SizeMax", h_max)
    f.setNumber(thr, "DistMin", d_min)
    f.setNumber(thr, "DistMax", d_max)
    return thr


def finish(out, dim, fluid, h):
    """Sizes from the background field only, meshes in `dim` dimensions,
    writes `out` (MSH 4.1 binary) and reports the node count of physical
    group `fluid`."""
    for key in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber("Mesh." + key, 0)
    gmsh.model.mesh.generate(dim)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1)
    nodes = len(gmsh.model.mesh.getNodesForPhysicalGroup(dim, fluid)[0])
    gmsh.write(out)
    gmsh.finalize()
    print(f"{out}: {nodes} nodes (h = {h})")


def command_line(build, name, size):
    """`name OUT.msh` (element size `size`) or `name --size H OUT.msh`."""
    if len(sys.argv) == 4 and sys.argv[1] == "--size":
        build(float(sys.argv[2]), sys.argv[3])
    elif len(sys.argv) == 2:
        build(size, sys.argv[1])
    else:
        sys.exit(f"usage: {name} OUT.msh | --size H OUT.msh")

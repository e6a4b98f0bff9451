#!/usr/bin/env python3
"""Meshes written by Gmsh itself, and the check that a file verbss wrote
back differs from them only in the node coordinates.

    python3 scripts/gmsh_round_trip.py make DIR
        writes into DIR, each in MSH 4.1 and 2.2, ASCII and binary
        (NAME_4.1_ascii.msh, NAME_2.2_binary.msh, ...):
        channel: 2D, a disk cut from a rectangle, physical curves cylinder,
                 inlet, outlet, walls and the physical surface fluid;
        partitioned: 3D, a sphere cut from a box, physical surfaces body,
                 inlet, outlet, walls and the volume fluid, in 2 partitions
                 (one file);
        periodic: the same box, its outlet periodic with its inlet.

    python3 scripts/gmsh_round_trip.py compare IN OUT
        fails (exit 1) unless OUT holds IN's bytes outside $Nodes, and in
        $Nodes, read with the Gmsh API, the same node tags and parametric
        coordinates on each entity; prints {"nodes": N, "moved": M} with M
        the nodes whose coordinates changed.
"""

import json
import sys

import gmsh

ENCODINGS = [(4.1, 0, "4.1_ascii"), (4.1, 1, "4.1_binary"),
             (2.2, 0, "2.2_ascii"), (2.2, 1, "2.2_binary")]


def physical(dim, groups):
    for name, tags in groups.items():
        gmsh.model.addPhysicalGroup(dim, tags, name=name)


def channel():
    occ = gmsh.model.occ
    cut, _ = occ.cut([(2, occ.addRectangle(-2, -1, 0, 6, 2))],
                     [(2, occ.addDisk(0, 0, 0, 0.3, 0.3))])
    occ.synchronize()
    groups = {"cylinder": [], "inlet": [], "outlet": [], "walls": []}
    for _, tag in gmsh.model.getBoundary(cut, oriented=False):
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, tag)
        if x1 - x0 < 1 and y1 - y0 < 1:
            groups["cylinder"].append(tag)
        elif x1 < -1.9:
            groups["inlet"].append(tag)
        elif x0 > 3.9:
            groups["outlet"].append(tag)
        else:
            groups["walls"].append(tag)
    physical(1, groups)
    physical(2, {"fluid": [t for _, t in cut]})
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.4)
    gmsh.model.mesh.generate(2)


def box(periodic):
    occ = gmsh.model.occ
    cut, _ = occ.cut([(3, occ.addBox(0, 0, 0, 2, 1, 1))],
                     [(3, occ.addSphere(1, 0.5, 0.5, 0.2))])
    occ.synchronize()
    groups = {"body": [], "inlet": [], "outlet": [], "walls": []}
    for _, tag in gmsh.model.getBoundary(cut, oriented=False):
        x0, _, _, x1, _, _ = gmsh.model.getBoundingBox(2, tag)
        if x1 < 0.01:
            groups["inlet"].append(tag)
        elif x0 > 1.99:
            groups["outlet"].append(tag)
        elif x1 - x0 < 1.5:
            groups["body"].append(tag)
        else:
            groups["walls"].append(tag)
    physical(2, groups)
    physical(3, {"fluid": [t for _, t in cut]})
    if periodic:
        shift = [1, 0, 0, 2, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
        gmsh.model.mesh.setPeriodic(2, groups["outlet"], groups["inlet"], shift)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.3)
    gmsh.model.mesh.generate(3)


def make(folder):
    builders = {
        "channel": channel,
        "partitioned": lambda: box(False),
        "periodic": lambda: box(True),
    }
    for name, build in builders.items():
        gmsh.clear()
        build()
        if name == "partitioned":
            gmsh.option.setNumber("Mesh.PartitionSplitMeshFiles", 0)
            gmsh.model.mesh.partition(2)
        for version, binary, suffix in ENCODINGS:
            gmsh.option.setNumber("Mesh.MshFileVersion", version)
            gmsh.option.setNumber("Mesh.Binary", binary)
            gmsh.write(f"{folder}/{name}_{suffix}.msh")


def outside_nodes(path):
    data = open(path, "rb").read()
    start = data.index(b"\n$Nodes\n")
    end = data.index(b"\n$EndNodes\n")
    return data[:start], data[end:]


def nodes(path):
    """Per entity: node tags and parametric coordinates; all coordinates by tag."""
    gmsh.clear()
    gmsh.open(path)
    per_entity = {}
    coords = {}
    for dim, tag in gmsh.model.getEntities():
        tags, xyz, param = gmsh.model.mesh.getNodes(dim, tag, returnParametricCoord=True)
        per_entity[(dim, tag)] = (list(tags), list(param))
        for i, t in enumerate(tags):
            coords[int(t)] = tuple(xyz[3 * i:3 * i + 3])
    return per_entity, coords


def compare(original, written):
    before, after = outside_nodes(original), outside_nodes(written)
    for part, a, b in zip(("before", "after"), before, after):
        if a != b:
            sys.exit(f"{written}: the bytes {part} $Nodes differ from {original}")
    entities_in, coords_in = nodes(original)
    entities_out, coords_out = nodes(written)
    if entities_in != entities_out:
        sys.exit(f"{written}: node tags or parametric coordinates differ from {original}")
    moved = sum(1 for t, p in coords_in.items() if coords_out[t] != p)
    print(json.dumps({"nodes": len(coords_in), "moved": moved}))


def main():
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    if sys.argv[1:2] == ["make"] and len(sys.argv) == 3:
        make(sys.argv[2])
    elif sys.argv[1:2] == ["compare"] and len(sys.argv) == 4:
        compare(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
    gmsh.finalize()


if __name__ == "__main__":
    main()

"""Generate the partitioned Gmsh fixtures in assets/meshes/gmsh/ with Gmsh itself.

Run from the repository root (after scripts/make_gmsh_fixtures.py, whose
models it reuses):

    python3 scripts/make_partitioned_fixtures.py

It partitions each model as `gmsh -part N -format msh41` does
(METIS, with Gmsh's partition boundary entities) and writes

* channel_hole_part3_v41_ascii.msh: the 2D hybrid channel, ASCII;
* box_part3_v41_binary.msh: the 3D tetrahedral box, binary, with the
  ghost cells of `-part_ghosts` (a $GhostElements section);
* box_part6_v41_ascii.msh: the box of box_v41_ascii.msh in 6 parts, ASCII,
  where Gmsh puts
  nodes that elements of one partition use on partition boundary entities
  that do not list that partition (four such references);
* channel_hole_split3_v41_ascii_1.msh to _3.msh: the channel of
  channel_hole_part3_v41_ascii.msh, the same 3 partitions, one file a
  partition, as `gmsh -part 3 -part_split` writes them;
* box_split6_v41_ascii_1.msh to _6.msh: the box of box_part6_v41_ascii.msh,
  the same 6 partitions, one file a partition;
* partitions.json: per file and partition, Gmsh's own numbers: the cells
  of the mesh dimension and the nodes on the partition's entities.
"""

import json
import os
import sys

import gmsh

from make_gmsh_fixtures import OUT, box, channel_with_hole


def partition_counts():
    """Per partition: its cells of the mesh dimension and its entities' nodes."""
    top = gmsh.model.getDimension()
    counts = {}
    for dim, tag in gmsh.model.getEntities():
        # Ghost entities (-part_ghosts) copy other partitions' cells.
        if not gmsh.model.getType(dim, tag).startswith("Partition"):
            continue
        parts = gmsh.model.getPartitions(dim, tag)
        nodes, _, _ = gmsh.model.mesh.getNodes(dim, tag)
        _, elems, _ = gmsh.model.mesh.getElements(dim, tag)
        cells = sum(len(e) for e in elems) if dim == top else 0
        for p in parts:
            entry = counts.setdefault(str(p), {"cells": 0, "nodes": 0})
            entry["nodes"] += len(nodes)
            if len(parts) == 1:
                entry["cells"] += cells
    return counts


def box_as_written():
    """The box as make_gmsh_fixtures.py wrote it (box_v41_ascii.msh)."""
    gmsh.open(os.path.join(OUT, "box_v41_ascii.msh"))


def main():
    gmsh.initialize(sys.argv[:1])
    gmsh.option.setNumber("General.Terminal", 0)
    files = {}
    for make, name, parts, binary, ghosts, split in [
        (channel_with_hole, "channel_hole_part3_v41_ascii.msh", 3, False, False, False),
        (box, "box_part3_v41_binary.msh", 3, True, True, False),
        (box_as_written, "box_part6_v41_ascii.msh", 6, False, False, False),
        (channel_with_hole, "channel_hole_split3_v41_ascii.msh", 3, False, False, True),
        (box_as_written, "box_split6_v41_ascii.msh", 6, False, False, True),
    ]:
        make()
        gmsh.option.setNumber("Mesh.PartitionCreateGhostCells", 1 if ghosts else 0)
        gmsh.model.mesh.partition(parts)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 1 if binary else 0)
        # -part_split: NAME_1.msh to NAME_K.msh, one file a partition.
        gmsh.option.setNumber("Mesh.PartitionSplitMeshFiles", 1 if split else 0)
        gmsh.write(os.path.join(OUT, name))
        if not split:
            files[name] = partition_counts()
        gmsh.clear()
    gmsh.finalize()
    with open(os.path.join(OUT, "partitions.json"), "w") as f:
        json.dump(files, f, indent=2, sort_keys=True)
        f.write("\n")


if __name__ == "__main__":
    main()

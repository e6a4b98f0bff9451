#!/usr/bin/env python3
"""Opens mesh files with meshio (and .msh files also with Gmsh) and prints
what they found, as one JSON object per line:

    {"file": ..., "meshio": {"points": N, "cells": N, "blocks": {"triangle": N, ...},
                             "field_data": [names]},
     "gmsh": {"nodes": N, "elements": N}}          (the "gmsh" part for .msh only)

Exits 1 if any file fails to open (the error is printed on stderr and as
"error" in that file's line), 2 if meshio or gmsh cannot be imported.

Usage: python3 scripts/check_external_readers.py FILE...
"""

import json
import sys


def meshio_counts(path):
    import meshio

    mesh = meshio.read(path)
    blocks = {}
    for block in mesh.cells:
        blocks[block.type] = blocks.get(block.type, 0) + len(block.data)
    return {
        "points": int(len(mesh.points)),
        "cells": int(sum(blocks.values())),
        "blocks": blocks,
        "field_data": sorted(mesh.field_data),
    }


def gmsh_counts(path):
    import gmsh

    gmsh.clear()
    gmsh.open(path)
    node_tags, _, _ = gmsh.model.mesh.getNodes()
    _, element_tags, _ = gmsh.model.mesh.getElements()
    return {
        "nodes": int(len(node_tags)),
        "elements": int(sum(len(t) for t in element_tags)),
    }


def main(paths):
    if not paths:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        import meshio  # noqa: F401

        if any(p.endswith(".msh") for p in paths):
            import gmsh
    except ImportError as e:
        print(f"cannot import {e.name}: {e}", file=sys.stderr)
        return 2
    use_gmsh = "gmsh" in sys.modules
    if use_gmsh:
        gmsh.initialize(interruptible=False)
        gmsh.option.setNumber("General.Terminal", 0)
    failed = False
    for path in paths:
        result = {"file": path}
        try:
            result["meshio"] = meshio_counts(path)
            if path.endswith(".msh"):
                result["gmsh"] = gmsh_counts(path)
        except Exception as e:  # any reader failure is a finding, not a crash
            result["error"] = f"{type(e).__name__}: {e}"
            print(f"{path}: {result['error']}", file=sys.stderr)
            failed = True
        print(json.dumps(result, sort_keys=True))
    if use_gmsh:
        gmsh.finalize()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

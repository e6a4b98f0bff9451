"""Check that Gmsh itself opens .msh files (e.g. files written by verbss).

    python3 scripts/check_gmsh_opens.py FILE.msh [FILE.msh ...]

For each file it prints what Gmsh finds (nodes, elements per dimension,
physical groups with their element counts) and fails, with exit status 1, when
Gmsh reports an error or a warning while reading, or finds no node or no
element. Needs the `gmsh` Python package (pip install gmsh).
"""

import sys

import gmsh


def check(path):
    """Open `path` in a fresh model; return a list of problems (empty if fine)."""
    gmsh.clear()
    gmsh.logger.start()
    problems = []
    try:
        gmsh.open(path)
    except Exception as e:  # Gmsh raises on read errors
        problems.append(f"gmsh.open failed: {e}")
    log = gmsh.logger.get()
    gmsh.logger.stop()
    problems += [line for line in log if line.startswith(("Error", "Warning"))]
    if problems:
        return problems
    tags, _, _ = gmsh.model.mesh.getNodes()
    per_dim = {}
    for dim in range(4):
        _, elems, _ = gmsh.model.mesh.getElements(dim)
        n = sum(len(e) for e in elems)
        if n:
            per_dim[dim] = n
    groups = []
    for dim, tag in gmsh.model.getPhysicalGroups():
        n = 0
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
            _, elems, _ = gmsh.model.mesh.getElements(dim, ent)
            n += sum(len(e) for e in elems)
        groups.append(f"{gmsh.model.getPhysicalName(dim, tag)!r} (dim {dim}, tag {tag}): {n}")
    print(f"{path}: {len(tags)} nodes, elements per dimension {per_dim}")
    for g in groups:
        print(f"    {g}")
    if len(tags) == 0:
        problems.append("no nodes")
    if not per_dim:
        problems.append("no elements")
    return problems


def main(paths):
    if not paths:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    gmsh.initialize(sys.argv[:1])
    gmsh.option.setNumber("General.Terminal", 0)
    failed = 0
    for path in paths:
        problems = check(path)
        for p in problems:
            print(f"{path}: {p}", file=sys.stderr)
        failed += bool(problems)
    gmsh.finalize()
    if failed:
        print(f"{failed} of {len(paths)} files failed", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

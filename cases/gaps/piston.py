"""A piston compressing a 3D channel to 30% of its length (docs/robustness.md,
"Squeezed gaps"), by verbss and by OpenFOAM's displacementLaplacian, on two
meshes of the channel [0, 1] x [0, 0.2] x [0, 0.2]:

* hexahedra: an OpenFOAM case made with blockMesh (30 x 6 x 6 cells);
* prisms: Gmsh triangles of size 0.04 in the x-y plane extruded 6 layers in z.

The piston (patch `piston`, x = 0) moves 0.7 along the channel in 20 steps;
the far end (`outlet`) stays; the four walls (`bottom`, `top`, `sideA`,
`sideB`) slip, as a user sets the walls a piston slides along (fixed walls
would hold the piston's edge). verbss: `--moving piston --slide
bottom,top,sideA,sideB --translate 0.7,0,0 --steps 20`; OpenFOAM: the same
patches `slip`, `outlet` fixedValue 0, the piston solidBodyMotionDisplacement.

    python3 cases/gaps/piston.py [--json OUT] [--verbss PATH] [--work DIR]

Needs OpenFOAM v1912 (blockMesh, gmshToFoam, moveDynamicMesh) and gmsh.
"""

import shutil
import tempfile
from pathlib import Path

import gmsh

import gaps_common as common

LENGTH, WIDTH, STEPS, STROKE = 1.0, 0.2, 20, 0.7
WALLS = ["bottom", "top", "sideA", "sideB"]
MOTION = ["--moving", "piston", "--slide", ",".join(WALLS), "--translate", f"{STROKE},0,0"]
BODY = dict(body="piston", steps=STEPS, translate=(STROKE, 0.0, 0.0))
BLOCK = """
convertToMeters 1;
vertices ((0 0 0) (L 0 0) (L W 0) (0 W 0) (0 0 W) (L 0 W) (L W W) (0 W W));
blocks (hex (0 1 2 3 4 5 6 7) (30 6 6) simpleGrading (1 1 1));
boundary (
    piston { type patch; faces ((0 4 7 3)); }
    outlet { type patch; faces ((1 2 6 5)); }
    bottom { type wall; faces ((0 1 5 4)); }
    top { type wall; faces ((3 7 6 2)); }
    sideA { type wall; faces ((0 3 2 1)); }
    sideB { type wall; faces ((4 5 6 7)); }
);
""".replace("L", f"{LENGTH:g}").replace("W", f"{WIDTH:g}")


def foam_case(folder):
    """A bare OpenFOAM case folder (system/ with ASCII output)."""
    for d in ("system", "constant", "0"):
        (folder / d).mkdir(parents=True, exist_ok=True)
    for name, (cls, text) in common.peer.foam_dicts(BODY, "laplacian", [], 1e-20).items():
        if name.startswith("system"):
            (folder / name).write_text(common.peer.FOAM_HEADER % (cls, Path(name).name) + text)
    return folder


def hex_case(folder):
    foam_case(folder)
    (folder / "system/blockMeshDict").write_text(
        common.peer.FOAM_HEADER % ("dictionary", "blockMeshDict") + BLOCK)
    common.peer.run(["blockMesh"], cwd=folder, env=common.peer.foam_env(folder))
    return folder


def prism_mesh(path):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    occ = gmsh.model.occ
    occ.addRectangle(0, 0, 0, LENGTH, WIDTH)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.04)
    out = occ.extrude([(2, 1)], 0, 0, WIDTH, numElements=[6], recombine=True)
    occ.synchronize()
    volume = [t for d, t in out if d == 3][0]
    named = {}
    for _, s in gmsh.model.getEntities(2):
        x, y, z = occ.getCenterOfMass(2, s)
        name = ("piston" if x < 1e-9 else "outlet" if x > LENGTH - 1e-9 else
                "bottom" if y < 1e-9 else "top" if y > WIDTH - 1e-9 else
                "sideA" if z < 1e-9 else "sideB")
        named.setdefault(name, []).append(s)
    for name, surfaces in named.items():
        gmsh.model.addPhysicalGroup(2, surfaces, name=name)
    gmsh.model.addPhysicalGroup(3, [volume], name="fluid")
    gmsh.model.mesh.generate(3)
    gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
    gmsh.write(str(path))
    nodes = len(gmsh.model.mesh.getNodes()[0])
    gmsh.finalize()
    return nodes


def main():
    args = common.options(__doc__).parse_args()
    verbss = str(Path(args.verbss).resolve())
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(args.work or tmp).resolve()
        work.mkdir(parents=True, exist_ok=True)
        rows = []
        # hexahedra: verbss writes time folders into a fresh copy of the case
        base = hex_case(work / "hex")
        nodes = len(common.peer.read_foam_points(base / "constant/polyMesh/points"))

        def copy(slug):
            run = work / f"hex-{slug}"
            shutil.rmtree(run, ignore_errors=True)
            shutil.copytree(base, run)
            return run, run

        name = "blockMesh hexahedra 30x6x6"
        rows += common.verbss_rows(verbss, "piston", name, nodes, copy, STEPS, MOTION + [
            "--every", str(STEPS), "--overwrite"], work)
        rows += common.openfoam_rows(verbss, "piston", name, nodes, base, BODY, WALLS, ["outlet"], work)
        common.print_rows(rows)
        # prisms: verbss reads the Gmsh file, OpenFOAM its gmshToFoam conversion
        msh = work / "prisms.msh"
        nodes = prism_mesh(msh)
        name = "Gmsh prisms (triangles 0.04, 6 layers)"
        prism_rows = common.verbss_rows(verbss, "piston", name, nodes,
                                        lambda slug: (msh, work / f"prisms-{slug}.vtu"),
                                        STEPS, MOTION, work)
        case = foam_case(work / "prisms")
        common.peer.run(["gmshToFoam", str(msh)], cwd=case, env=common.peer.foam_env(case))
        prism_rows += common.openfoam_rows(verbss, "piston", name, nodes, case, BODY, WALLS, ["outlet"], work)
        common.print_rows(prism_rows)
        common.write_json(args.json, rows + prism_rows)


if __name__ == "__main__":
    main()

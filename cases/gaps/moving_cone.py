"""OpenFOAM's movingCone pushed 3 mm by verbss and by OpenFOAM (docs/robustness.md,
"Squeezed gaps"), in 600 and in 30 steps, two readings of its boundaries:

* the tutorial's: the cone (`movingWall`) moves, `farField` and `farFieldMoving`
  slip, `left` and `fixedWall` stay (verbss `--slide axis,farField,farFieldMoving`);
* the far field fixed: `farField` and `farFieldMoving` stay too (verbss
  `--slide axis`), the cone sliding under a wall 0.5 mm above its tip.

OpenFOAM moves it with the tutorial's own solver, velocityComponentLaplacian
with `directional (1 200 0)` (the far field's pointMotionUx `uniformFixedValue
constant 0` in the second reading), and in 30 steps also with
displacementLaplacian (cases/gaps/gaps_common.py: inverseDistance of the
cone, quadratic inverseDistance, inverseVolume; the sliding patches `slip`). Prints the rows of cases/gaps/gaps_common.py
and the minimum quality (verbss's measure) at 20, 40, 60, 80 and 100% of the
motion; OpenFOAM's meshes are measured at every step of the 30-step runs and
every 20th of the 600-step runs.

    cargo build --release -p verbss-cli
    python3 cases/gaps/moving_cone.py [--json OUT] [--verbss PATH] [--work DIR]

Needs OpenFOAM v1912 (blockMesh, moveDynamicMesh, foamDictionary; its bashrc
sourced) and the tutorial under /usr/share/doc/openfoam-examples.
"""

import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import gaps_common as common

TUTORIAL = Path(
    "/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam/laminar/movingCone"
)
STROKE = 0.003  # 3 mm: 600 of the tutorial's deltaT 5e-6 at 1 m/s
FRACTIONS = (1, 2, 3, 4, 5)
CONSTRAINTS = {"front": "wedge", "back": "wedge", "axis": "empty"}
DISPLACEMENT_STEPS = 30  # displacementLaplacian writes and is measured every step: 30 only
READINGS = [("tutorial's conditions", "axis,farField,farFieldMoving", ["left", "fixedWall"]),
            ("far field fixed", "axis", ["left", "fixedWall", "farField", "farFieldMoving"])]


def run(cmd, cwd=None):
    return subprocess.run(cmd, cwd=cwd, check=True, capture_output=True, text=True).stdout


def fresh(root, name, steps):
    """The tutorial's case, ASCII, `steps` steps of the 3 ms, blockMesh run."""
    case = root / name
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(TUTORIAL, case)
    for gz in case.rglob("*.gz"):
        run(["gunzip", str(gz)])
    for key, value in [("deltaT", f"{STROKE / steps:g}"), ("writeFormat", "ascii"),
                       ("writeInterval", str(max(1, steps // 30)))]:
        run(["foamDictionary", "-entry", key, "-set", value, "system/controlDict"], cwd=case)
    run(["blockMesh"], cwd=case)
    return case


def openfoam(verbss, root, steps, reading, fixed, mesh_name):
    case = fresh(root, f"openfoam-{steps}-{len(fixed)}", steps)
    if reading != READINGS[0][0]:
        motion = case / "0/pointMotionUx"
        motion.write_text(re.sub(r"(farField\w*\s*\{\s*type\s+)slip;",
                                 r"\1uniformFixedValue; uniformValue constant 0;",
                                 motion.read_text()))
    log = subprocess.run(["moveDynamicMesh"], cwd=case, capture_output=True, text=True).stdout
    (case / "log.moveDynamicMesh").write_text(log)
    moved, free = common.held_and_free(case, ["movingWall"], fixed)
    nodes = len(common.peer.read_foam_points(case / "constant/polyMesh/points"))
    return common.foam_row(verbss, "moving-cone", mesh_name, nodes,
                           "OpenFOAM velocityComponentLaplacian directional (1 200 0)", case, case,
                           log, steps, moved, free, root, unit=STROKE / steps)


def main():
    args = common.options(__doc__).parse_args()
    verbss = str(Path(args.verbss).resolve())
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(args.work or tmp).resolve()
        root.mkdir(parents=True, exist_ok=True)
        for reading, slide, fixed in READINGS:
            mesh_name = f"movingCone wedge (blockMesh), {reading}"
            for steps in (600, 30):
                rows.append(openfoam(verbss, root, steps, reading, fixed, mesh_name))
                nodes = rows[-1]["nodes"]

                def copy(slug):
                    case = fresh(root, f"verbss-{slug}-{steps}", steps)
                    return case, case

                motion = ["--moving", "movingWall", "--slide", slide, "--translate", f"{STROKE},0",
                          "--every", str(10 * steps)]
                reports = root / f"reports-{slide.count(',')}-{steps}"
                reports.mkdir(exist_ok=True)
                rows += common.verbss_rows(verbss, "moving-cone", mesh_name, nodes, copy, steps,
                                           motion, reports)
                if steps <= DISPLACEMENT_STEPS:
                    body = dict(body="movingWall", steps=steps, translate=(STROKE, 0.0, 0.0))
                    slip = [p for p in slide.split(",") if p != "axis"]
                    rows += common.openfoam_rows(verbss, "moving-cone", mesh_name, nodes,
                                                 fresh(root, f"foam-{steps}", steps), body, slip,
                                                 fixed, root, constraints=CONSTRAINTS)
    common.print_rows(rows)
    print("\n| reading | run | steps | 20% | 40% | 60% | 80% | 100% |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        at = [r["min_quality_per_step"][k * r["steps"] // 5 - 1]
              if k * r["steps"] // 5 <= r["steps_done"] else None for k in FRACTIONS]
        cells = " | ".join(common.fmt(q, ".4f") for q in at)
        print(f"| {r['mesh'].split(', ')[1]} | {r['run']} | {r['steps_done']}/{r['steps']} "
              f"| {cells} |")
    common.write_json(args.json, rows)


if __name__ == "__main__":
    main()

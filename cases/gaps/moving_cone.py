"""OpenFOAM's movingCone pushed 3 mm by verbss and by OpenFOAM (docs/robustness.md,
"Squeezed gaps"): one Markdown table on standard output, the minimum quality
(verbss's measure) at 20, 40, 60, 80 and 100% of the motion, in 600 and in 30 steps.

    cargo build --release -p verbss-cli
    python3 cases/gaps/moving_cone.py [--verbss target/release/verbss]

Needs OpenFOAM v1912 (blockMesh, moveDynamicMesh, foamDictionary; its bashrc
sourced) and the tutorial under /usr/share/doc/openfoam-examples. The tutorial's
own boundary conditions: the cone moves, `farField` and `farFieldMoving` slip,
`left` and `fixedWall` stay; OpenFOAM moves it with velocityComponentLaplacian.
"""

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

TUTORIAL = Path(
    "/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam/laminar/movingCone"
)
DELTA_T = 5e-6  # the tutorial's deltaT; 600 steps make its 3 ms
FRACTIONS = (1, 2, 3, 4, 5)


def run(cmd, cwd=None):
    return subprocess.run(cmd, cwd=cwd, check=True, capture_output=True, text=True).stdout


def fresh(root, name):
    case = root / name
    shutil.copytree(TUTORIAL, case)
    for gz in case.rglob("*.gz"):
        run(["gunzip", str(gz)])
    run(["blockMesh"], cwd=case)
    return case


def min_quality(verbss, case, time, root):
    """verbss's minimum quality of the mesh OpenFOAM wrote at `time`."""
    q = root / "quality"
    shutil.rmtree(q, ignore_errors=True)
    (q / "constant").mkdir(parents=True)
    shutil.copytree(case / "constant" / "polyMesh", q / "constant" / "polyMesh")
    shutil.copytree(case / "system", q / "system")
    shutil.copy(case / time / "polyMesh" / "points", q / "constant" / "polyMesh" / "points")
    return json.loads(run([verbss, "quality", "--json", str(q)]))["quality"]["min"]


def openfoam(verbss, root, steps):
    case = fresh(root, f"openfoam-{steps}")
    dt = 0.003 / steps
    for key, value in [("deltaT", f"{dt:g}"), ("writeInterval", str(steps // 5)),
                       ("writeFormat", "ascii")]:
        run(["foamDictionary", "-entry", key, "-set", value, "system/controlDict"], cwd=case)
    log = run(["moveDynamicMesh"], cwd=case)
    ok = log.count("Mesh OK.")
    qualities = [min_quality(verbss, case, f"{k * dt * steps / 5:g}", root) for k in FRACTIONS]
    return f"{ok}/{steps} Mesh OK", qualities


def verbss_run(verbss, root, steps, extra):
    case = fresh(root, f"verbss-{steps}-{'-'.join(extra)}")
    report = root / "report.json"
    done = subprocess.run(
        [verbss, "deform", str(case), "-o", str(case), "--moving", "movingWall",
         "--slide", "axis,farField,farFieldMoving", "--translate", "0.003,0",
         "--steps", str(steps), "--every", str(10 * steps), "--report", str(report),
         "--quiet", *extra], capture_output=True, text=True)
    records = json.loads(report.read_text())["steps"] if report.exists() else []
    reached = max((r["step"] for r in records if r["inverted"] == 0), default=0)
    by_step = {r["step"]: r["min_quality"] for r in records}
    qualities = [by_step.get(k * steps // 5) for k in FRACTIONS]
    status = f"{reached}/{steps}" + ("" if done.returncode == 0 else " (stopped)")
    return status, qualities


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--verbss", default="target/release/verbss")
    verbss = str(Path(parser.parse_args().verbss).resolve())
    print("| run | steps | 20% | 40% | 60% | 80% | 100% |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        for steps in (600, 30):
            rows = [(f"OpenFOAM velocityComponentLaplacian, {steps} steps",
                     openfoam(verbss, root, steps))]
            for name, extra in [("default", []), ("--method verbss", ["--method", "verbss"]),
                                ("--method laplacian", ["--method", "laplacian"])]:
                rows.append((f"verbss {name}, {steps} steps",
                             verbss_run(verbss, root, steps, extra)))
            for name, (status, qualities) in rows:
                cells = " | ".join("–" if q is None else f"{q:.4f}" for q in qualities)
                print(f"| {name} | {status} | {cells} |")
                sys.stdout.flush()


if __name__ == "__main__":
    main()

"""A NACA0012 airfoil pitching about its quarter chord, moved by verbss from
Python once per time step, and the element quality histogram (the VerBSS
paper's five bins) of the input mesh and of the step of worst quality,
plotted with matplotlib to quality_histogram.png.

    pip install ./python matplotlib      # from the repository root
    python3 examples/python/pitching_airfoil.py --steps 40 --out out/
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import verbss  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
CENTER = np.array([0.25, 0.0])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mesh", default=ROOT / "assets/meshes/su2/mesh_NACA0012_inv.su2")
    parser.add_argument("--group", default="airfoil", help="the moving group")
    parser.add_argument("--steps", type=int, default=40, help="time steps of one period")
    parser.add_argument("--amplitude", type=float, default=10.0, help="pitch amplitude, degrees")
    parser.add_argument("--out", type=Path, default=Path("."), help="folder of the picture")
    args = parser.parse_args()

    mesh = verbss.read(args.mesh)
    deformer = verbss.Deformer(mesh, tolerance=1e-5)

    def pitch(step):
        """The pitch angle (radians) at a step: one sine period over the run."""
        return np.radians(args.amplitude) * np.sin(2 * np.pi * step / args.steps)

    def displacement(x0, step):
        """The airfoil's displacement from the input mesh at `step`: a
        rotation of its input coordinates `x0` about the quarter chord."""
        c, s = np.cos(pitch(step)), np.sin(pitch(step))
        r = x0 - CENTER
        return CENTER + np.column_stack([c * r[:, 0] - s * r[:, 1], s * r[:, 0] + c * r[:, 1]]) - x0

    worst = (np.inf, 0, None)
    min_quality = []
    for n in range(1, args.steps + 1):
        deformer.step({args.group: displacement})
        info = deformer.info
        min_quality.append(info["min_quality"])
        print(
            "step %d: pitch %+6.2f deg, %4d sweeps, min quality %.4f, %.3f s"
            % (n, np.degrees(pitch(n)), info["iterations"], info["min_quality"], info["seconds"])
        )
        if info["min_quality"] < worst[0]:
            worst = (info["min_quality"], n, verbss.quality(deformer.mesh))

    initial = verbss.quality(mesh)
    labels = ["%.2f-%.2f" % (b["lo"], b["hi"]) for b in initial["quality"]["bins"]]
    x = np.arange(len(labels))
    fig, (bars, line) = plt.subplots(1, 2, figsize=(11, 4))
    for offset, (name, summary) in zip(
        (-0.2, 0.2), (("input mesh", initial), ("step %d (worst)" % worst[1], worst[2]))
    ):
        counts = [b["count"] for b in summary["quality"]["bins"]]
        bars.bar(x + offset, counts, width=0.4, label=name)
    bars.set_xticks(x, labels)
    bars.set_yscale("log")
    bars.set_xlabel("element quality")
    bars.set_ylabel("elements")
    bars.set_title("Quality histogram")
    bars.legend()
    line.plot(range(1, args.steps + 1), min_quality, marker=".")
    line.set_xlabel("step")
    line.set_ylabel("min quality")
    line.set_title("Smallest element quality per step")
    fig.tight_layout()
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / "quality_histogram.png"
    fig.savefig(path, dpi=100)
    print("wrote %s" % path)


if __name__ == "__main__":
    main()

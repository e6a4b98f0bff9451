"""The Python bindings give what the ``verbss`` command gives: the same
coordinates after ``verbss deform`` on the repository's meshes, the same
``verbss quality --json`` and the same error messages.

The command is ``$VERBSS_CLI`` (set by crates/verbss-cli/tests/python_bindings.rs,
which runs these tests under ``cargo test``), else ``target/release/verbss`` or
``target/debug/verbss``; tests that need it are skipped without it.
"""

import json
import os
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

import verbss

ROOT = Path(__file__).resolve().parents[2]
MESHES = ROOT / "assets" / "meshes" / "su2"
NACA = MESHES / "mesh_NACA0012_inv.su2"

# (mesh, moving group, total translation): the four shared meshes.
CASES = [
    ("mesh_NACA0012_inv.su2", "airfoil", [0.05, 0.1]),
    ("mesh_RAE2822_turb_ffd.su2", "AIRFOIL", [0.02, -0.03]),
    ("mesh_brick_tets_ffd.su2", "x_p", [0.2, 0.0, 0.05]),
    ("mesh_brick_hex_ffd.su2", "x_p", [0.2, 0.0, 0.05]),
]
STEPS = 2
SETTINGS = dict(method="verbss", omega=1.6, tolerance=1e-5, max_iterations=3000)


@pytest.fixture(scope="session")
def cli():
    """The path of the ``verbss`` command."""
    candidates = [os.environ.get("VERBSS_CLI")] + [
        str(ROOT / "target" / profile / "verbss") for profile in ("release", "debug")
    ]
    for path in candidates:
        if path and Path(path).is_file():
            return path
    pytest.skip("no verbss command: set VERBSS_CLI or build it with cargo build")


def run_cli(cli, *args):
    return subprocess.run([cli, *map(str, args)], capture_output=True, text=True)


def cli_deform(cli, tmp_path, mesh, group, shift, steps=STEPS, extra=(), method="verbss"):
    """The coordinates ``verbss deform --translate --method METHOD`` writes."""
    out = tmp_path / "cli.su2"
    done = run_cli(
        cli, "deform", MESHES / mesh, "-o", out, "--moving", group,
        "--translate", ",".join(map(repr, shift)), "--steps", steps,
        "--omega", SETTINGS["omega"], "--tolerance", SETTINGS["tolerance"],
        "--max-iterations", SETTINGS["max_iterations"], "--method", method, "--quiet", *extra,
    )
    assert done.returncode == 0, done.stderr
    return verbss.read(out).points


@pytest.mark.parametrize("mesh,group,shift", CASES)
def test_deform_matches_the_command_bit_for_bit(cli, tmp_path, mesh, group, shift):
    expected = cli_deform(cli, tmp_path, mesh, group, shift)
    d = verbss.Deformer(verbss.read(MESHES / mesh), threads=0, **SETTINGS)
    total = np.array(shift)
    for n in range(1, STEPS + 1):
        points = d.step({group: n / STEPS * total})
        assert d.info["step"] == n and d.info["inverted"] == 0
    assert points.shape == expected.shape
    assert not np.array_equal(points, verbss.read(MESHES / mesh).points)
    assert np.array_equal(points, expected)
    assert np.array_equal(d.points, expected)


def test_callable_and_per_node_arrays_give_the_same_steps(cli, tmp_path):
    mesh, group, shift = CASES[0]
    expected = cli_deform(cli, tmp_path, mesh, group, shift)
    seen = []

    def translation(x0, step):
        seen.append((x0.shape, step))
        return np.tile(step / STEPS * np.array(shift), (len(x0), 1))

    d = verbss.Deformer(verbss.read(MESHES / mesh), **SETTINGS)
    for _ in range(STEPS):
        d.step({group: translation})
    assert seen == [((200, 2), 1), ((200, 2), 2)]
    assert np.array_equal(d.points, expected)


def test_arrays_built_mesh_matches_the_read_mesh():
    read = verbss.read(NACA)
    built = verbss.Mesh(read.points, read.cells, read.groups)
    assert built.dim == 2
    assert {k: v.shape for k, v in built.cells.items()} == {"triangle": (10216, 3)}
    assert {k: len(v) for k, v in built.groups.items()} == {"airfoil": 200, "farfield": 50}
    assert list(built.group_facets("airfoil")) == ["vertex"]
    assert list(read.group_facets("airfoil")) == ["line"]
    results = []
    for mesh in (read, built):
        d = verbss.Deformer(mesh, **SETTINGS)
        for n in (1, 2):
            d.step({"airfoil": [0.0, 0.02 * n]})
        results.append(d.points)
    assert np.array_equal(results[0], results[1])


def test_rotation_matches_the_command_to_rounding(cli, tmp_path):
    # The command rotates X itself; the binding receives u = R(X) - X and puts
    # the node at X + u, which can differ from R(X) in the last bit.
    out = tmp_path / "rotated.su2"
    done = run_cli(
        cli, "deform", NACA, "-o", out, "--moving", "airfoil", "--rotate", 6,
        "--center", "0.25,0", "--steps", STEPS, "--omega", SETTINGS["omega"],
        "--tolerance", SETTINGS["tolerance"], "--max-iterations",
        SETTINGS["max_iterations"], "--method", "verbss", "--quiet",
    )
    assert done.returncode == 0, done.stderr
    expected = verbss.read(out).points

    def pitch(x0, step):
        a = np.radians(6.0) * step / STEPS
        c, s = np.cos(a), np.sin(a)
        x, y = x0[:, 0] - 0.25, x0[:, 1]
        return np.column_stack([0.25 + c * x - s * y, s * x + c * y]) - x0

    d = verbss.Deformer(verbss.read(NACA), **SETTINGS)
    for _ in range(STEPS):
        d.step({"airfoil": pitch})
    assert np.abs(d.points - expected).max() < 1e-12


def test_quality_is_the_command_json(cli):
    for mesh in ("mesh_RAE2822_turb_ffd.su2", "mesh_brick_hex_ffd.su2"):
        done = run_cli(cli, "quality", MESHES / mesh, "--json")
        assert done.returncode == 0, done.stderr
        assert verbss.quality(verbss.read(MESHES / mesh)) == json.loads(done.stdout)


def test_a_zone_of_a_multi_zone_file_is_the_command_zone(cli):
    fsi = ROOT / "cases" / "meshes" / "fsi_airfoil.su2"
    assert len(verbss.read(fsi).points) == 12
    solid = verbss.read(fsi, zone=2)
    assert (len(solid.points), list(solid.groups)) == (5, ["interface"])
    done = run_cli(cli, "quality", fsi, "--json", "--zone", "2")
    assert done.returncode == 0, done.stderr
    assert verbss.quality(solid) == json.loads(done.stdout)
    with pytest.raises(verbss.VerbssError) as e:
        verbss.read(fsi, zone=3)
    assert str(e.value) == f"{fsi}:1: zone 3 asked for, but NZONE= 2 (zones 1 to 2)"


def test_errors_carry_the_command_message(cli, tmp_path):
    missing = tmp_path / "missing.su2"
    done = run_cli(cli, "quality", missing)
    with pytest.raises(verbss.VerbssError) as e:
        verbss.read(missing)
    assert done.stderr == "error: %s\n" % e.value
    assert str(e.value) == "%s: No such file or directory (os error 2)" % missing

    done = run_cli(
        cli, "deform", NACA, "-o", tmp_path / "o.su2", "--moving", "wing", "--translate", "0,1"
    )
    with pytest.raises(verbss.VerbssError) as e:
        verbss.Deformer(verbss.read(NACA)).step({"wing": [0.0, 1.0]})
    assert done.stderr == "error: %s\n" % e.value
    assert str(e.value) == "unknown group 'wing' (the mesh has: airfoil, farfield)"

    # Pushing the airfoil through the farfield inverts elements: exit code 3.
    done = run_cli(
        cli, "deform", NACA, "-o", tmp_path / "o.su2", "--moving", "airfoil",
        "--translate", "30,0", "--omega", SETTINGS["omega"], "--tolerance",
        SETTINGS["tolerance"], "--max-iterations", SETTINGS["max_iterations"],
        "--method", "verbss", "--quiet",
    )
    assert done.returncode == 3
    with pytest.raises(verbss.VerbssError) as e:
        verbss.Deformer(verbss.read(NACA), **SETTINGS).step({"airfoil": [30.0, 0.0]})
    assert done.stderr.splitlines()[0] == "error: %s" % e.value
    assert str(e.value).startswith("step 1: element ")
    assert issubclass(verbss.VerbssError, ValueError)


def test_accel_amg_matches_the_command(cli, tmp_path):
    mesh, group, shift = CASES[1]
    expected = cli_deform(cli, tmp_path, mesh, group, shift, extra=("--accel", "amg"))
    d = verbss.Deformer(verbss.read(MESHES / mesh), accel="amg", **SETTINGS)
    for n in range(1, STEPS + 1):
        got = d.step({group: np.array(shift) * n / STEPS})
    assert np.allclose(got, expected, rtol=0, atol=1e-12)


def test_robust_method_matches_the_command_default(cli, tmp_path):
    # The reference of the robust preset is chosen by the motions, as on the
    # command line: given positions are a one-way motion (updated), as the
    # command's translation.
    mesh, group, shift = CASES[1]
    expected = cli_deform(cli, tmp_path, mesh, group, shift, method="robust")
    plain = cli_deform(cli, tmp_path, mesh, group, shift)
    d = verbss.Deformer(verbss.read(MESHES / mesh), **dict(SETTINGS, method="robust"))
    for n in range(1, STEPS + 1):
        got = d.step({group: np.array(shift) * n / STEPS})
    # The binding's wall positions are X + u, which the rigid layer carries as
    # (X + u) - X: equal to the command's translation up to rounding.
    assert np.allclose(got, expected, rtol=0, atol=1e-12)
    assert not np.allclose(got, plain, rtol=0, atol=1e-6)


def test_the_keywords_are_the_settings_table():
    # The stub's keywords of Deformer are the library's settings, and each
    # is taken by the constructor with the table's default.
    import ast

    stub = ast.parse((Path(verbss.__file__).parent / "_verbss.pyi").read_text())
    deformer = next(n for n in stub.body if isinstance(n, ast.ClassDef) and n.name == "Deformer")
    new = next(f for f in deformer.body if isinstance(f, ast.FunctionDef) and f.name == "__new__")
    keywords = [a.arg for a in new.args.args[2:] + new.args.kwonlyargs]
    names = [row["name"] for row in verbss.settings_table()]
    assert sorted(k for k in keywords if k != "slide") == sorted(names)
    mesh = verbss.read(NACA)
    for row in verbss.settings_table():
        verbss.Deformer(mesh, **{row["name"]: row["default"]})
    with pytest.raises(verbss.VerbssError) as e:
        verbss.Deformer(mesh, omegga=1.5)
    assert str(e.value).startswith("invalid setting: unknown setting 'omegga' (expected method,")


def test_near_wall_settings_and_slides_match_the_command(cli, tmp_path):
    mesh, group, shift = CASES[3]
    extra = [
        # No stiffening: a body moved by given positions (the binding's)
        # is not stiffened, one moved by --translate is.
        "--slide", "y_m,y_p", "--rigid-layer", "0.1", "--stiffening", "0",
        "--substeps", "3", "--blend", "off", "--predictor", "linear", "--reference", "updated",
    ]
    expected = cli_deform(cli, tmp_path, mesh, group, shift, extra=extra, method="robust")
    d = verbss.Deformer(
        verbss.read(MESHES / mesh), **dict(SETTINGS, method="robust"), slide=["y_m", "y_p"],
        rigid_layer=0.1, stiffening=0.0, substeps=3, blend=False, predictor="linear",
        reference="updated",
    )
    for n in range(1, STEPS + 1):
        got = d.step({group: np.array(shift) * n / STEPS})
    assert np.allclose(got, expected, rtol=0, atol=1e-12)
    # The sliding walls' nodes stayed on their planes.
    start = verbss.read(MESHES / mesh)
    for name in ("y_m", "y_p"):
        nodes = start.groups[name]
        assert np.array_equal(got[nodes, 1], start.points[nodes, 1])


def test_reference_predictor_and_absolute_tolerance_match_the_command(cli, tmp_path):
    mesh, group, shift = CASES[0]
    extra = ("--reference", "fixed", "--predictor", "linear", "--absolute-tolerance", "on")
    expected = cli_deform(cli, tmp_path, mesh, group, shift, extra=extra)
    plain = cli_deform(cli, tmp_path, mesh, group, shift)
    d = verbss.Deformer(
        verbss.read(MESHES / mesh), **SETTINGS, reference="fixed", predictor="linear",
        absolute_tolerance=True,
    )
    for n in range(1, STEPS + 1):
        got = d.step({group: np.array(shift) * n / STEPS})
    assert np.array_equal(got, expected)
    assert not np.array_equal(got, plain)


def test_slide_normals_match_a_case_file(cli, tmp_path):
    # `verbss run` with `kind = "slide"` tables: y_m in the plane of a given
    # normal (0.29° off its own: within the half degree allowed), y_p in its
    # own plane.
    mesh, group, shift = CASES[3]
    case = tmp_path / "normals.toml"
    case.write_text(
        "mesh = %s\nsteps = %d\n\n[solver]\nmethod = \"verbss\"\nomega = %r\n"
        "tolerance = %r\nmax_iterations = %d\n\n"
        "[[motion]]\nkind = \"translation\"\ngroups = [\"%s\"]\ndisplacement = %r\n\n"
        "[[motion]]\nkind = \"slide\"\ngroups = [\"y_m\"]\nnormal = [0.0, 1.0, 0.005]\n\n"
        "[[motion]]\nkind = \"slide\"\ngroups = [\"y_p\"]\n\n"
        "[output]\nseries = false\nreport = false\n"
        % (json.dumps(str(MESHES / mesh)), STEPS, SETTINGS["omega"], SETTINGS["tolerance"],
           SETTINGS["max_iterations"], group, shift)
    )
    done = run_cli(cli, "run", case, "--out", tmp_path / "run", "--quiet")
    assert done.returncode == 0, done.stderr
    expected = verbss.read(tmp_path / "run" / mesh).points
    start = verbss.read(MESHES / mesh)
    d = verbss.Deformer(start, **SETTINGS, slide={"y_m": [0.0, 1.0, 0.005], "y_p": None})
    for n in range(1, STEPS + 1):
        got = d.step({group: np.array(shift) * n / STEPS})
    assert np.array_equal(got, expected)
    # The nodes of y_m that only slide moved within the plane of the normal.
    others = np.concatenate([start.groups[g] for g in start.groups if g != "y_m"])
    slid = np.setdiff1d(start.groups["y_m"], others)
    u = got[slid] - start.points[slid]
    assert np.abs(u @ np.array([0.0, 1.0, 0.005])).max() < 1e-12
    assert np.abs(u[:, 1]).max() > 1e-6


def test_rejected_step_keeps_the_last_one_and_can_be_retried():
    mesh = verbss.read(NACA)
    d = verbss.Deformer(mesh, **SETTINGS)
    assert d.info is None
    first = d.step({"airfoil": [0.0, 0.01]}).copy()
    with pytest.raises(verbss.VerbssError, match=r"^step 2: element \d+ inverted at "):
        d.step({"airfoil": [30.0, 0.0]})
    assert d.info["step"] == 1
    assert np.array_equal(d.points, first)
    d.step({"airfoil": [0.0, 0.02]})
    assert d.info["step"] == 2 and d.info["inverted"] == 0


def test_bad_displacements_are_named():
    d = verbss.Deformer(verbss.read(NACA))
    node = int(d.mesh.groups["airfoil"][0])
    named = ("invalid displacement: Python Deformer.step displacement of node %d (row 0 of "
             "group 'airfoil') is %s (expected finite numbers within ±1e100)")
    cases = [
        ({"airfoil": np.zeros((3, 2))},
         "invalid displacement: the displacement of group 'airfoil' has shape (3, 2), "
         "expected (200, 2) or (2,)"),
        ({"airfoil": [0.0, np.nan]}, named % (node, "NaN")),
        # Issue 43, 11 and 15: a huge displacement is named, printed short,
        # before it makes a NaN position.
        ({"airfoil": [1e308, 0.0]}, named % (node, "1e308")),
        ({}, "invalid setting: the first step names no group to move"),
    ]
    for given, message in cases:
        with pytest.raises(verbss.VerbssError) as e:
            d.step(given)
        assert str(e.value) == message
    d.step({"airfoil": [0.0, 0.01]})
    with pytest.raises(verbss.VerbssError) as e:
        d.step({"airfoil": [0.0, 0.01], "farfield": [0.0, 0.0]})
    assert str(e.value) == (
        "invalid setting: the step moves airfoil, farfield but the deformer moves "
        "airfoil (the groups of its first step)"
    )
    # A misspelt group on a later step is unknown, not another group.
    with pytest.raises(verbss.VerbssError) as e:
        d.step({"Airfoil": [0.0, 0.01]})
    assert str(e.value) == "unknown group 'Airfoil' (the mesh has: airfoil, farfield)"


def test_whole_float_ids_are_taken():
    whole = verbss.Mesh([[0, 0], [1, 0], [0, 1]], {"triangle": np.array([[0.0, 1.0, 2.0]])})
    assert whole.cells["triangle"].tolist() == [[0, 1, 2]]


def test_bad_settings_and_arrays_are_named():
    mesh = verbss.read(NACA)
    cases = [
        (lambda: verbss.Deformer(mesh, method="fast"),
         "invalid setting: unknown method 'fast' (expected robust, verbss, ball-vertex, spring or laplacian)"),
        (lambda: verbss.Deformer(mesh, reference="moving"),
         "invalid setting: unknown reference 'moving' (expected auto, updated, fixed or anchored)"),
        (lambda: verbss.Deformer(mesh, omega=2.5),
         "invalid setting: omega must be a number in (0, 2) (got 2.5)"),
        (lambda: verbss.Deformer(mesh, threads=-1),
         "invalid setting: threads must be a whole number from 0 to 4096 (got -1)"),
        (lambda: verbss.Deformer(mesh, rigid_layer="thick"),
         "invalid setting: rigid_layer must be off, auto or a positive wall distance (got 'thick')"),
        (lambda: verbss.Deformer(mesh, substeps=40),
         "invalid setting: substeps must be a whole number from 0 to 30 (got 40)"),
        (lambda: verbss.Deformer(mesh, accel="fast"),
         "invalid setting: unknown accel 'fast' (expected none, amg or auto)"),
        (lambda: verbss.Deformer(mesh, tolerance=-1.0, absolute_tolerance=True),
         "invalid setting: tolerance must be a finite number ≥ 0 (got -1)"),
        (lambda: verbss.Deformer(mesh, slide=["wing"]),
         "unknown group 'wing' (the mesh has: airfoil, farfield)"),
        (lambda: verbss.Deformer(mesh, slide={"farfield": [0.0, 0.0, 1.0]}),
         "invalid setting: the slide normal of group 'farfield' has z = 1 on a 2D mesh: "
         "give NX,NY (or NX,NY,0)"),
        (lambda: verbss.Deformer(mesh, slide={"farfield": [[0.0, 1.0]]}),
         "invalid setting: the slide normal of group 'farfield' has shape (1, 2), expected (2,)"),
        (lambda: verbss.Deformer(mesh, slide="farfield"),
         "invalid setting: slide must be a list of group names or a mapping of a group name "
         "to its plane's normal (got the string 'farfield')"),
        (lambda: verbss.Mesh([[0, 0], [1, 0], [0, 1]], {"tri": [[0, 1, 2]]}),
         "invalid mesh: unknown cell kind 'tri' (expected triangle, quad, tetra, hexahedron, wedge or pyramid)"),
        (lambda: verbss.Mesh([[0, 0], [1, 0], [0, 1]], {"triangle": [[0, 1, 3]]}),
         "invalid mesh: cells 'triangle' uses node 3, not a node id of the mesh (0 to 2)"),
        (lambda: verbss.Mesh([[0, 0], [1, 0], [0, 1]], {"triangle": [[0, 1]]}),
         "invalid mesh: cells 'triangle' must be an (M, 3) array"),
        (lambda: verbss.Mesh([[0, 0], [1, 0], [0, np.inf]], {"triangle": [[0, 1, 2]]}),
         "invalid mesh: node 2 has a non-finite coordinate"),
        (lambda: verbss.Mesh([0.0, 1.0], {}),
         "invalid mesh: points is a 1-dimensional array (expected an (N, D) array)"),
        # Float ids were cut (0.9 became 0, 1.9 became 1): refused, unless whole.
        (lambda: verbss.Mesh([[0, 0], [1, 0], [0, 1]], {"triangle": np.array([[0, 1, 2]]) + 0.9}),
         "invalid mesh: cells 'triangle' holds 0.9 at flat index 0: node ids must be whole numbers"),
        (lambda: verbss.Mesh([[0, 0], [1, 0], [0, 1]], {"triangle": [[0, 1, 2]]},
                             {"wall": [0.7, 1.9]}),
         "invalid mesh: group 'wall' holds 0.7 at flat index 0: node ids must be whole numbers"),
        (lambda: verbss.Mesh([[0, 0], [1, 0], [0, 1]], {"triangle": [["0", "1", "2"]]}),
         "invalid mesh: cells 'triangle' is an array of <U1 (expected integer node ids)"),
    ]
    for make, message in cases:
        with pytest.raises(verbss.VerbssError) as e:
            make()
        assert str(e.value) == message


def test_write_and_read_back(tmp_path):
    mesh = verbss.read(MESHES / "mesh_RAE2822_turb_ffd.su2")
    d = verbss.Deformer(mesh, **SETTINGS)
    d.step({"AIRFOIL": [0.0, 0.005]})
    for name in ("moved.su2", "moved.vtu", "moved.msh"):
        d.mesh.write(tmp_path / name)
        back = verbss.read(tmp_path / name)
        assert np.array_equal(back.points, d.points)
        assert back.cells.keys() == mesh.cells.keys()
        assert all(np.array_equal(back.groups[g], mesh.groups[g]) for g in mesh.groups)


def test_meshio_round_trip(tmp_path):
    meshio = pytest.importorskip("meshio")
    mesh = verbss.read(MESHES / "mesh_RAE2822_turb_ffd.su2")
    m = verbss.to_meshio(mesh)
    assert isinstance(m, meshio.Mesh)
    back = verbss.from_meshio(m)
    assert np.array_equal(back.points, mesh.points)
    assert all(np.array_equal(back.cells[k], mesh.cells[k]) for k in mesh.cells)
    assert all(np.array_equal(back.groups[g], mesh.groups[g]) for g in mesh.groups)
    assert back.group_facets("AIRFOIL")["line"].shape == (192, 2)
    # A file meshio read: SU2 markers come back by their tag numbers.
    m = meshio.read(NACA)
    back = verbss.from_meshio(m)
    assert {k: len(v) for k, v in back.groups.items()} == {"1": 200, "2": 50}
    assert np.array_equal(back.points, verbss.read(NACA).points)


def test_solve_releases_the_gil():
    # The step signals the probe once it has released the GIL and waits there
    # for the answer: this thread can only answer (Python code) if the step
    # holds no GIL. Holding it, the step would fail after 30 s.
    d = verbss.Deformer(verbss.read(NACA), threads=1)
    probe = verbss.GilProbe()
    result = []
    worker = threading.Thread(
        target=lambda: result.append(d.step({"airfoil": [0.0, 0.01]}, probe=probe))
    )
    worker.start()
    assert probe.wait(30.0)
    probe.answer()
    worker.join()
    assert len(result) == 1 and d.info["step"] == 1, d.info


def test_example_plots_the_histogram(tmp_path):
    pytest.importorskip("matplotlib")
    script = ROOT / "examples" / "python" / "pitching_airfoil.py"
    done = subprocess.run(
        [sys.executable, str(script), "--steps", "4", "--out", str(tmp_path)],
        capture_output=True, text=True,
    )
    assert done.returncode == 0, done.stderr
    png = tmp_path / "quality_histogram.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "step 4" in done.stdout

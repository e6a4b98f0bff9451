"""Type stubs of the native part of verbss (``verbss._verbss``)."""

import os
from typing import (
    Callable,
    Dict,
    List,
    Mapping,
    Optional,
    Sequence,
    Tuple,
    TypedDict,
    Union,
    final,
    type_check_only,
)

import numpy as np
import numpy.typing as npt

__all__ = ["Deformer", "Mesh", "VerbssError", "quality_json", "read"]

_Ids = npt.ArrayLike
_Displacement = Union[npt.ArrayLike, Callable[[np.ndarray, int], npt.ArrayLike]]

class VerbssError(ValueError):
    """A verbss error: a file that cannot be read, an invalid mesh or
    setting, an unknown group, or a step that inverted an element. The
    message is the one the ``verbss`` command prints after ``error: ``."""

@type_check_only
class StepInfo(TypedDict):
    """What one step did (``Deformer.info``)."""

    step: int
    iterations: int
    residual: float
    converged: bool
    seconds: float
    form_seconds: float
    solve_seconds: float
    min_quality: float
    mean_quality: float
    inverted: int
    bins: List[int]

@final
class Mesh:
    """An unstructured 2D or 3D hybrid mesh: node coordinates, volume cells
    and named boundary groups.

    - ``points``: (N, D) floats, D = 2 or 3.
    - ``cells``: a mapping from a meshio cell kind name (``"triangle"``,
      ``"quad"``, ``"tetra"``, ``"hexahedron"``, ``"wedge"``, ``"pyramid"``)
      to an (M, k) array of 0-based node ids, or a sequence of (kind, array)
      pairs; nodes in Gmsh's order (VTK's, except for the wedge).
    - ``groups``: a mapping from a group name to its node ids (1-D), or to its
      boundary facets (an (M, k) array: k = 2 lines, 3 triangles, 4 quads; or
      a mapping kind → array for mixed facets).

    Raises VerbssError when the arrays do not make a valid mesh.
    """

    def __new__(
        cls,
        points: npt.ArrayLike,
        cells: Union[Mapping[str, _Ids], Sequence[Tuple[str, _Ids]]],
        groups: Optional[Mapping[str, Union[_Ids, Mapping[str, _Ids]]]] = None,
    ) -> "Mesh": ...
    @property
    def points(self) -> np.ndarray:
        """The node coordinates, an (N, D) float64 array (a copy)."""
    @property
    def cells(self) -> Dict[str, np.ndarray]:
        """The volume cells: {kind name: (M, k) int64 array of node ids},
        kinds in order of first appearance (copies)."""
    @property
    def groups(self) -> Dict[str, np.ndarray]:
        """The groups: {name: sorted int64 array of its distinct node ids}."""
    @property
    def dim(self) -> int:
        """The spatial dimension, 2 or 3."""
    def group_facets(self, name: str) -> Dict[str, np.ndarray]:
        """The boundary facets of group ``name``: {kind name: (M, k) int64
        array} (``"vertex"`` for groups given as node ids)."""
    def write(self, path: Union[str, os.PathLike]) -> None:
        """Writes the mesh to ``path`` in the format of its extension (.msh
        Gmsh 4.1, .su2, .vtu), with the mesh's numbering."""

@final
class Deformer:
    """A mesh in motion, stepped by a flow solver (see :meth:`step`).

    Every keyword but ``slide`` is a setting of the library's one table
    (:func:`settings_table`, docs/case-file.md): the same name as a case
    file's ``[solver]`` key and ``verbss deform``'s option (``-`` for
    ``_``), the same values — a string, a number, or True/False for on/off;
    None or left out: what ``method`` implies. ``method`` is ``"robust"``
    (the default: VerBSS with the near-wall treatments), ``"verbss"`` (the
    paper's method), ``"ball-vertex"``, ``"spring"`` or ``"laplacian"``.
    ``threads`` defaults to one per core; the results do not depend on it.

    ``slide``: group names, each sliding in its own plane, or a mapping of a
    group name to its plane's normal (D numbers, or None for its own plane).

    Invalid settings, unknown slide groups and slide normals of the wrong
    length raise :class:`VerbssError` here, not at the first step.
    """

    def __new__(
        cls,
        mesh: Mesh,
        method: str = "robust",
        *,
        slide: Union[Sequence[str], Mapping[str, Optional[npt.ArrayLike]], None] = None,
        reference: Optional[str] = None,
        predictor: Optional[str] = None,
        rigid_layer: Union[str, float, None] = None,
        stiffening: Optional[float] = None,
        substeps: Optional[int] = None,
        blend: Optional[bool] = None,
        relocate: Optional[bool] = None,
        solver: Optional[str] = None,
        accel: Optional[str] = None,
        escalate: Optional[bool] = None,
        omega: Optional[float] = None,
        tolerance: Optional[float] = None,
        absolute_tolerance: Optional[bool] = None,
        max_iterations: Optional[int] = None,
        threads: Optional[int] = None,
    ) -> "Deformer": ...
    def step(
        self, displacements: Mapping[str, _Displacement], *, probe: Optional[GilProbe] = None
    ) -> np.ndarray:
        """Takes the next time step and returns the new node coordinates, an
        (N, D) float64 array.

        ``displacements`` maps each moving group's name to its displacement
        from the input mesh at this step: an (n, D) array (rows in the order
        of ``mesh.groups[name]``), a (D,) array (the same for every node), or
        a callable ``f(points, step)`` given the group's input coordinates (an
        (n, D) array, same order) and the step number (1 for the first step),
        returning either. Each node of a group goes exactly to its input
        position plus its displacement; a node in several moving groups
        follows the first one named. Every other boundary node stays where it
        is, the interior nodes follow by the springs. The first step fixes
        which groups move: every later step names the same groups.

        The solve runs with the GIL released (``probe`` shows it). Raises VerbssError when a group
        is unknown, a displacement has the wrong shape or is not finite, or
        the step inverted an element: the step is then rejected and the
        deformer keeps the last accepted step (so the same step can be
        retried)."""
    @property
    def points(self) -> np.ndarray:
        """The current node coordinates, an (N, D) float64 array (a copy)."""
    @property
    def mesh(self) -> Mesh:
        """The input mesh with the current coordinates."""
    @property
    def info(self) -> Optional[StepInfo]:
        """What the last accepted step did, or None before the first step."""

def settings_table() -> List[Dict[str, Any]]:
    """The library's table of settings, the keywords of :class:`Deformer`:
    one dict per setting with its ``name``, ``values``, ``default``,
    ``presets`` (the presets whose value differs, and that value) and
    ``help``."""

def read(path: Union[str, os.PathLike], zone: int = 1) -> Mesh:
    """Reads a mesh file (.msh Gmsh 2.2/4.1, .su2, .vtu), chosen by
    extension; of a multi-zone SU2 file, zone ``zone`` (its IZONE= K).
    Raises VerbssError naming the file, the line and what was expected."""

def quality_json(mesh: Mesh) -> str:
    """The ``verbss quality --json`` summary of a mesh, as JSON text."""

class GilProbe:
    """A handshake across a step's GIL release: ``step(..., probe=p)``
    signals ``p`` once the GIL is released and waits there (at most 30 s) for
    ``p.answer()`` before it solves, so a caller that answers ran while the
    step held no GIL."""

    def __init__(self) -> None: ...
    def wait(self, timeout: float) -> bool:
        """Waits (GIL released, at most ``timeout`` seconds) for a step's
        signal; whether it came."""
    def answer(self) -> None:
        """Lets the signalled step go on to its solve."""

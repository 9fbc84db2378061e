"""grainpack: packs ellipsoidal grains into a box without overlaps.

The Python face of the Rust library (one native module, no second implementation):

- the narrow phase on numpy arrays: :func:`contact_function`, :func:`overlaps`,
  :func:`contact_geometry`, with pw85's argument layout;
- scenes and packing: :class:`Scene` (``from_toml``, ``from_dict``), :func:`pack`
  returning a :class:`Packing` (numpy grain table, ``summary``, ``write``,
  ``voxelise``, ``to_pyvista``);
- :class:`SceneError`, raised with the CLI's message for a scene it would refuse.

Quadratic forms are given as the 6 entries of their upper triangle, row-major
(``q[0] q[1] q[2] / q[3] q[4] / q[5]``), as in pw85: ``Q = R diag(a1², a2², a3²) Rᵀ``
for an ellipsoid of semi-axes ``a`` along the columns of ``R``.
"""

from __future__ import annotations

import json
import os
import sys
from typing import Any, Callable, NamedTuple

import numpy as np

from . import _grainpack
from ._grainpack import Scene, SceneError, __version__

__all__ = [
    "ContactGeometry",
    "Packing",
    "Scene",
    "SceneError",
    "contact_function",
    "contact_geometry",
    "overlaps",
    "pack",
    "quadratic_form",
    "__version__",
]


# --- contact functions -------------------------------------------------------------


def _rows(r12: Any, q1: Any, q2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """The three arguments as C-contiguous float64 arrays of shapes (n, 3), (n, 6), (n, 6),
    and whether a single pair (1-D arguments) was given."""
    arrays = [np.ascontiguousarray(a, dtype=np.float64) for a in (r12, q1, q2)]
    single = all(a.ndim == 1 for a in arrays)
    if single:
        arrays = [a.reshape(1, -1) for a in arrays]
    n = arrays[0].shape[0] if arrays[0].ndim == 2 else -1
    for name, a, cols in zip(("r12", "q1", "q2"), arrays, (3, 6, 6)):
        if a.ndim != 2 or a.shape[1] != cols or a.shape[0] != n:
            want = f"({cols},)" if single else f"(n, {cols}) with n = {n}"
            raise ValueError(
                f"{name} has shape {a.shape if not single else a.shape[1:]}, expected {want}"
                " (r12: (n, 3), q1 and q2: (n, 6), or (3,), (6,), (6,) for one pair)"
            )
    return arrays[0], arrays[1], arrays[2], single


class ContactResult(NamedTuple):
    """μ² and its maximiser λ, per pair (floats for one pair, arrays for n)."""

    mu2: Any
    lam: Any


def contact_function(r12: Any, q1: Any, q2: Any, out: np.ndarray | None = None) -> Any:
    """The Perram–Wertheim contact function μ² of pairs of ellipsoids, and its maximiser λ.

    ``μ² = max_{λ∈[0,1]} λ(1−λ) r12ᵀ [(1−λ)Q1 + λQ2]⁻¹ r12``: μ is the common factor by
    which both ellipsoids must be scaled about their centres to touch, so μ² < 1 means
    overlap. Accurate to a few ulps (the library's ``contact_function``), computed eight
    pairs at a time where the build targets AVX-512 or AVX2, with the GIL released.

    Parameters
    ----------
    r12 : array_like, shape (n, 3) or (3,)
        ``c2 − c1``, the centre of the second ellipsoid relative to the first.
    q1, q2 : array_like, shape (n, 6) or (6,)
        The quadratic forms, upper triangle row-major, as in pw85.
    out : ndarray, optional
        pw85's full output: shape (2,) for one pair, (n, 2) for n; ``out[..., 0]``
        receives μ² and ``out[..., 1]`` λ, and μ² alone is returned, as pw85 does.

    Returns
    -------
    ContactResult
        ``(mu2, lam)``: arrays of shape (n,), or floats for a single pair.

    Raises
    ------
    ValueError
        For arrays of the wrong shape, and for the first row without an answer, named
        with the library's reason (``row 17: q1 is not positive definite: ...``, a
        non-finite value, two forms singular along a common direction).
    ArithmeticError
        For a row whose μ² overflows, or where the solver ran out of iterations (never
        reported as an answer).

    Invalid rows raise rather than give NaN: a NaN μ² compares false with 1 and would
    read as "apart", the silent failure this library is built to avoid. Rows are
    checked in full before anything is returned; to skip bad rows, filter them first.
    """
    r, a, b, single = _rows(r12, q1, q2)
    mu2, lam = _grainpack.contact_function_rows(r, a, b)
    if out is not None:
        target = np.asarray(out)
        want = (2,) if single else (mu2.shape[0], 2)
        if target.shape != want:
            raise ValueError(f"out has shape {target.shape}, expected {want}")
        target[..., 0] = mu2[0] if single else mu2
        target[..., 1] = lam[0] if single else lam
        return float(mu2[0]) if single else mu2
    if single:
        return ContactResult(float(mu2[0]), float(lam[0]))
    return ContactResult(mu2, lam)


def overlaps(r12: Any, q1: Any, q2: Any) -> Any:
    """Whether each pair of ellipsoids overlaps (μ² < 1), decided with a certified test.

    Same arguments and errors as :func:`contact_function`. Returns a bool array of shape
    (n,), or a bool for a single pair. Touching ellipsoids (μ² = 1) do not overlap.
    One pair at a time (the library has no eight-lane version of this test), with the
    GIL released.
    """
    r, a, b, single = _rows(r12, q1, q2)
    answers = _grainpack.overlaps_rows(r, a, b)
    return bool(answers[0]) if single else answers


class ContactGeometry(NamedTuple):
    """Where two ellipsoids touch once both are scaled by μ about their centres.

    ``point`` is relative to the first centre; ``normal`` is the unit normal there,
    from the first ellipsoid to the second; ``gap`` is ``|r12| (1 − 1/μ)`` projected on
    the normal (positive apart, negative a penetration depth).
    """

    mu2: Any
    lam: Any
    point: Any
    normal: Any
    gap: Any


def contact_geometry(r12: Any, q1: Any, q2: Any) -> ContactGeometry:
    """The contact point, normal and gap of each pair (see :class:`ContactGeometry`).

    Same arguments and errors as :func:`contact_function`; the coincident centres of a
    pair make the normal undefined, and raise ``ValueError`` naming the row. Arrays of
    shapes (n,), (n,), (n, 3), (n, 3), (n,); for a single pair, floats and (3,) arrays.
    """
    r, a, b, single = _rows(r12, q1, q2)
    mu2, lam, point, normal, gap = _grainpack.contact_geometry_rows(r, a, b)
    if single:
        return ContactGeometry(float(mu2[0]), float(lam[0]), point[0], normal[0], float(gap[0]))
    return ContactGeometry(mu2, lam, point, normal, gap)


def rotation_matrices(quaternions: Any) -> np.ndarray:
    """Rotation matrices (n, 3, 3) of unit quaternions ``[w, x, y, z]`` (Hamilton), as the
    grain table stores them: semi-axis ``k`` lies along column ``k``."""
    q = np.asarray(quaternions, dtype=np.float64)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
        ],
        -2,
    )


def quadratic_form(semi_axes: Any, quaternions: Any) -> np.ndarray:
    """``Q = R diag(a²) Rᵀ`` of ellipsoids as the 6 upper-triangle entries (n, 6), the
    layout :func:`contact_function` takes, from semi-axes (n, 3) and quaternions (n, 4)."""
    a = np.asarray(semi_axes, dtype=np.float64)
    r = rotation_matrices(quaternions)
    q = np.einsum("...ik,...k,...jk->...ij", r, a * a, r)
    rows, cols = np.triu_indices(3)
    return np.ascontiguousarray(q[..., rows, cols])


# --- scenes and packing ------------------------------------------------------------


def _from_toml(path_or_text: str | os.PathLike[str]) -> Scene:
    """A scene from a TOML file or TOML text, validated as ``pack SCENE.toml`` does.

    A ``pathlib.Path`` (any ``os.PathLike``) is a file; a ``str`` is TOML text if it
    holds a newline or an ``=`` (every scene has a key), and a file name otherwise.
    Raises :class:`SceneError` with the CLI's message (``file:line:column: key = value:
    reason``; text is named ``<string>``).
    """
    if isinstance(path_or_text, os.PathLike):
        return Scene._from_path(os.fspath(path_or_text))
    if not isinstance(path_or_text, str):
        raise TypeError(f"expected a path or TOML text, got {type(path_or_text).__name__}")
    if "\n" in path_or_text or "=" in path_or_text:
        return Scene._from_text(path_or_text)
    return Scene._from_path(path_or_text)


def _from_dict(scene: dict[str, Any]) -> Scene:
    """A scene from a dict shaped like the TOML file (``{"seed": 1, "box": {...},
    "phase": [{...}, ...]}``), validated as ``pack SCENE.toml`` does.

    Raises :class:`SceneError` naming the key (``<dict>:line:column: phase[0].size.sigma
    = -0.8: must be positive``; the line is that of the dict written as TOML), and
    ``ValueError`` for values TOML cannot hold (None, NaN).
    """
    if not isinstance(scene, dict):
        raise TypeError(f"expected a dict, got {type(scene).__name__}")
    try:
        text = json.dumps(scene, allow_nan=False, default=_plain)
    except ValueError as e:
        raise ValueError(f"the scene holds a value TOML cannot: {e}") from None
    if "null" in text:
        _reject_none(scene, "")
    return Scene._from_json(text)


def _plain(value: Any) -> Any:
    """numpy scalars and arrays, tuples and paths as JSON values."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    raise TypeError(f"{type(value).__name__} is not a scene value")


def _reject_none(value: Any, key: str) -> None:
    if value is None:
        raise ValueError(f"{key or 'scene'} = None: TOML has no null; leave the key out")
    if isinstance(value, dict):
        for k, v in value.items():
            _reject_none(v, f"{key}.{k}" if key else str(k))
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            _reject_none(v, f"{key}[{i}]")


Scene.from_toml = staticmethod(_from_toml)  # type: ignore[attr-defined]
Scene.from_dict = staticmethod(_from_dict)  # type: ignore[attr-defined]


class Packing:
    """A packed scene: the grains as numpy arrays, the run's summary, and its files.

    Attributes
    ----------
    grains : dict[str, numpy.ndarray]
        The grain table, column by column, exactly as ``grains.csv`` holds it (same
        column names and order, same doubles; int64 for integer columns): ``id``,
        ``phase``, ``x y z``, ``a1 a2 a3``, ``qw qx qy qz``, and any column the library
        adds to the file.
    centres, semi_axes, quaternions, phase, ids : numpy.ndarray
        Views of the table: (n, 3), (n, 3), (n, 4) ``[w, x, y, z]``, (n,), (n,).
    summary : dict
        ``summary.json``'s content: the same keys and values the CLI writes (the
        timings are this run's). Before :meth:`write`, without the ``rve`` entry and
        with ``timings.outputs = 0``; after it, exactly the file written.
    """

    def __init__(self, native: Any) -> None:
        self._native = native
        self.grains: dict[str, np.ndarray] = native._grain_table()

    def _columns(self, *names: str) -> np.ndarray:
        return np.column_stack([self.grains[n] for n in names])

    @property
    def centres(self) -> np.ndarray:
        """Centres (n, 3); inside ``[0, L)`` in a periodic box."""
        return self._columns("x", "y", "z")

    @property
    def semi_axes(self) -> np.ndarray:
        """Semi-axes (n, 3) as packed."""
        return self._columns("a1", "a2", "a3")

    @property
    def quaternions(self) -> np.ndarray:
        """Orientations (n, 4), ``[w, x, y, z]`` (Hamilton); semi-axis k along column k
        of the rotation matrix."""
        return self._columns("qw", "qx", "qy", "qz")

    @property
    def phase(self) -> np.ndarray:
        """Phase index of each grain (into :attr:`phase_names`)."""
        return self.grains["phase"]

    @property
    def ids(self) -> np.ndarray:
        """Grain ids (0..n−1, the voxel grid's material numbers)."""
        return self.grains["id"]

    @property
    def quadratic_forms(self) -> np.ndarray:
        """``Q = R diag(a²) Rᵀ`` of each grain, (n, 6), as :func:`contact_function`
        takes them."""
        return quadratic_form(self.semi_axes, self.quaternions)

    @property
    def summary(self) -> dict[str, Any]:
        return json.loads(self._native._summary_json())

    @property
    def box_size(self) -> tuple[float, float, float]:
        """Box edges ``(Lx, Ly, Lz)``."""
        return self._native.box_size

    @property
    def seed(self) -> int:
        """The seed used."""
        return self._native.seed

    @property
    def stop_reason(self) -> str:
        """``target_reached``, ``jammed`` or ``step_limit``."""
        return self._native.stop_reason

    @property
    def phase_names(self) -> list[str]:
        """The scene's phase names."""
        return self._native.phase_names

    def __len__(self) -> int:
        return len(self._native)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"Packing({len(self)} grains, packing_fraction={s['packing_fraction']:.4f}, "
            f"stop_reason={s['stop_reason']!r}, seed={s['seed']})"
        )

    def write(self, dir: str | os.PathLike[str]) -> list[str]:
        """Writes into ``dir`` (created if missing) exactly the files ``pack SCENE.toml
        --seed SEED --out DIR`` writes for this run, as the scene's ``[output]`` asks,
        each to a temporary name renamed when complete, ``summary.json`` last. Returns
        the paths written. Raises ``OSError`` with the CLI's message if it cannot."""
        return [os.fspath(p) for p in self._native._write(os.fspath(dir))]

    def voxelise(
        self, resolution: int | tuple[int, int, int] = 64, fill: str = "grains", *, field: str = "material"
    ) -> np.ndarray:
        """The grains sampled on a regular grid over the box, as the RVE (``rve.vti``).

        Parameters
        ----------
        resolution : int or (nx, ny, nz)
            An int puts that many cells along the longest edge and proportionally many
            along the others (as the scene's ``rve_resolution = N``); three ints give
            each count.
        fill : "grains" or "matrix"
            ``"grains"``: every voxel goes to the grain it is nearest to in the grains'
            own metrics; ``"matrix"``: voxels outside every grain are the matrix,
            material ``n`` (phase ``len(phase_names)``).
        field : "material" or "phase"
            Grain id of each voxel, or its phase.

        Returns
        -------
        numpy.ndarray of uint32, shape (nx, ny, nz)
            Indexed ``[i, j, k]`` with voxel centres at ``((i + ½) Lx/nx, ...)`` (x
            fastest in memory, as DAMASK's ``GeomGrid.material``).
        """
        if field not in ("material", "phase"):
            raise ValueError(f'field = {field!r}: must be "material" or "phase"')
        cells = [int(resolution)] if np.isscalar(resolution) else [int(n) for n in resolution]
        if any(n < 1 for n in cells):
            raise ValueError(f"resolution = {resolution!r}: cell counts must be at least 1")
        material, phase, (nx, ny, nz) = self._native._voxelise(cells, fill)
        values = material if field == "material" else phase
        return values.reshape(nz, ny, nx).transpose()

    def to_pyvista(self, resolution: int = 16) -> Any:
        """The grains' surfaces as one ``pyvista.PolyData`` (needs pyvista), with cell
        data ``grain`` (id) and ``phase``; ``.plot()`` shows them. Each grain is a unit
        sphere of ``resolution`` × ``resolution`` points mapped onto its ellipsoid,
        drawn about its centre (grains crossing a periodic face are not wrapped)."""
        try:
            import pyvista as pv
        except ImportError as e:
            raise ImportError("to_pyvista needs pyvista: pip install pyvista") from e
        sphere = pv.Sphere(radius=1.0, theta_resolution=resolution, phi_resolution=resolution)
        unit = np.asarray(sphere.points)
        faces = np.asarray(sphere.faces).reshape(-1, 4)  # triangles: [3, i, j, k]
        n, m = len(self), unit.shape[0]
        r = rotation_matrices(self.quaternions)
        points = self.centres[:, None, :] + np.einsum(
            "gij,gmj->gmi", r, self.semi_axes[:, None, :] * unit[None, :, :]
        )
        offsets = (np.arange(n) * m)[:, None, None]
        cells = np.broadcast_to(faces, (n, *faces.shape)).copy()
        cells[:, :, 1:] += offsets
        mesh = pv.PolyData(points.reshape(-1, 3), cells.reshape(-1))
        per_grain = faces.shape[0]
        mesh.cell_data["grain"] = np.repeat(self.ids, per_grain)
        mesh.cell_data["phase"] = np.repeat(self.phase, per_grain)
        return mesh


def _progress_printer(total_grains: float) -> Callable[[int, float, float, int], None] | None:
    """The default progress display: a tqdm bar (a widget in a notebook) when tqdm is
    installed, else one line redrawn on stderr in a terminal or a notebook; nothing
    otherwise."""
    try:
        from tqdm.auto import tqdm
    except ImportError:
        # A notebook's output cell redraws a line ending in "\r" as a terminal does.
        if not (sys.stderr.isatty() or "ipykernel" in sys.modules):
            return None

        def line(step: int, scale: float, fraction: float, overlaps: int) -> None:
            done = int(20 * min(max(scale, 0.0), 1.0))
            sys.stderr.write(
                f"\r[{'=' * done}{' ' * (20 - done)}] step {step}  scale {scale:.4f}  "
                f"fraction {fraction:.4f}  overlaps {overlaps}   "
            )
            sys.stderr.flush()

        line.close = lambda: sys.stderr.write("\n")  # type: ignore[attr-defined]
        return line
    bar = tqdm(total=1000, desc=f"{total_grains:.0f} grains", unit="‰", leave=False)

    def update(step: int, scale: float, fraction: float, overlaps: int) -> None:
        bar.n = int(1000 * min(max(scale, 0.0), 1.0))
        bar.set_postfix(step=step, fraction=f"{fraction:.4f}", overlaps=overlaps, refresh=False)
        bar.refresh()

    update.close = bar.close  # type: ignore[attr-defined]
    return update


def pack(
    scene: Scene,
    seed: int | None = None,
    threads: int | None = None,
    progress: bool | Callable[[dict[str, Any]], Any] | None = None,
) -> Packing:
    """Packs ``scene``: draws its grains, packs them, checks every pair exactly, and
    measures the result against the scene's laws (as ``pack SCENE.toml`` does, without
    writing: see :meth:`Packing.write`).

    Parameters
    ----------
    scene : Scene
    seed : int, optional
        Seed of the random generator (default: the scene's). The same seed gives the
        same packing, whatever the number of threads.
    threads : int, optional
        Threads of the packing loop (default: one per core).
    progress : bool or callable, optional
        ``None`` (default): a progress bar (tqdm's, a widget in a notebook, when tqdm is
        installed; else a line redrawn on stderr in a terminal or a notebook). ``False``:
        none.
        A callable: called with a dict ``{"step", "scale", "fraction", "overlaps"}`` at
        most every 0.1 s, from the calling thread; an exception it raises stops the
        packing and is raised here.

    The GIL is released while packing. Ctrl-C (SIGINT) stops the loop within about
    0.1 s and raises ``KeyboardInterrupt``; the process stays usable.

    Returns a :class:`Packing`. A target not reached (jammed, step limit) is not an
    error: see ``Packing.stop_reason``. Raises ``RuntimeError`` with the CLI's message
    for a run that fails (an internal error on a validated scene).
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a grainpack.Scene, got {type(scene).__name__}")
    if seed is not None and (not isinstance(seed, (int, np.integer)) or seed < 0):
        raise ValueError(f"seed = {seed!r}: must be a non-negative integer")
    if threads is not None and (not isinstance(threads, (int, np.integer)) or threads < 1):
        raise ValueError(f"threads = {threads!r}: must be a positive integer (or None)")
    display = None
    callback: Callable[[int, float, float, int], Any] | None
    if progress is None or progress is True:
        display = _progress_printer(scene.expected_count)
        callback = display
    elif progress is False:
        callback = None
    elif callable(progress):
        user = progress

        def callback(step: int, scale: float, fraction: float, overlaps: int) -> Any:
            return user({"step": step, "scale": scale, "fraction": fraction, "overlaps": overlaps})

    else:
        raise TypeError("progress must be None, a bool or a callable")
    try:
        native = _grainpack.pack_scene(scene, seed, threads, callback)
    finally:
        if display is not None:
            display.close()  # type: ignore[attr-defined]
    return Packing(native)

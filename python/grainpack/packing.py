"""pack and Packing: the run, its progress display, and its result as numpy arrays."""

from __future__ import annotations

import json
import os
import sys
from typing import Any, Callable

import numpy as np

from . import _grainpack
from ._grainpack import Scene
from .contact import quadratic_form, rotation_matrices


class Packing:
    """A packed scene: the grains as numpy arrays, the run's summary, and its files.

    Attributes
    ----------
    grains : dict[str, numpy.ndarray]
        The grain table, column by column, exactly as ``grains.csv`` holds it (same
        column names and order, same doubles; int64 for integer columns): ``id``,
        ``phase``, ``x y z``, ``a1 a2 a3``, ``qw qx qy qz`` (a 2D scene: ``x y``,
        ``a1 a2``, ``angle`` in degrees), and any column the library adds to the file.
    centres, semi_axes, quaternions, phase, ids : numpy.ndarray
        Views of the table: (n, 3), (n, 3), (n, 4) ``[w, x, y, z]``, (n,), (n,); in a
        2D scene centres and semi-axes are (n, 2), and :attr:`angles` (n,) gives the
        orientations.
    summary : dict
        ``summary.json``'s content: the same keys and values the CLI writes (the
        timings are this run's). Before :meth:`write`, without the ``rve`` entry and
        with ``timings.outputs = 0``; after it, exactly the file written.

    A Packing lives in the process that packed it (it does not pickle): from Dask or
    multiprocessing tasks, return its ``summary``, its arrays, or write it.
    """

    def __init__(self, native: Any) -> None:
        self._native = native
        self.grains: dict[str, np.ndarray] = native._grain_table()

    def _columns(self, *names: str) -> np.ndarray:
        return np.column_stack([self.grains[n] for n in names])

    @property
    def dimension(self) -> int:
        """2 for ellipses in a rectangle (a box with two lengths), 3 for ellipsoids."""
        return 3 if "z" in self.grains else 2

    @property
    def centres(self) -> np.ndarray:
        """Centres (n, 3), or (n, 2) in 2D; inside ``[0, L)`` in a periodic box."""
        return self._columns(*"xyz"[: self.dimension])

    @property
    def semi_axes(self) -> np.ndarray:
        """Semi-axes (n, 3) as packed, or (n, 2) in 2D: ``a1`` along the angle."""
        return self._columns(*["a1", "a2", "a3"][: self.dimension])

    @property
    def angles(self) -> np.ndarray:
        """2D only: the angle (n,) in radians, in (−π/2, π/2], of each ellipse's first
        semi-axis from x, counter-clockwise (the table's ``angle`` is in degrees)."""
        if self.dimension != 2:
            raise AttributeError("angles: a 3D packing has quaternions, not angles")
        return np.deg2rad(self.grains["angle"])

    @property
    def quaternions(self) -> np.ndarray:
        """Orientations (n, 4), ``[w, x, y, z]`` (Hamilton); semi-axis k along column k
        of the rotation matrix. In 2D, the turn by :attr:`angles` about z."""
        if self.dimension == 2:
            half = 0.5 * self.angles
            zero = np.zeros_like(half)
            return np.column_stack([np.cos(half), zero, zero, np.sin(half)])
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
        takes them; in 2D the ellipses' 2×2 forms ``[q00, q01, q11]``, (n, 3)."""
        if self.dimension == 2:
            a1, a2 = self.semi_axes.T
            c, s = np.cos(self.angles), np.sin(self.angles)
            return np.column_stack(
                [a1**2 * c**2 + a2**2 * s**2, (a1**2 - a2**2) * c * s, a1**2 * s**2 + a2**2 * c**2]
            )
        return quadratic_form(self.semi_axes, self.quaternions)

    @property
    def summary(self) -> dict[str, Any]:
        return json.loads(self._native._summary_json())

    @property
    def box_size(self) -> tuple[float, ...]:
        """Box edges ``(Lx, Ly, Lz)``, or the rectangle's ``(Lx, Ly)`` in 2D (as
        ``Scene.box_size``)."""
        return tuple(self._native.box_size[: self.dimension])

    @property
    def seed(self) -> int:
        """The seed used."""
        return self._native.seed

    @property
    def stop_reason(self) -> str:
        """``target_reached``, ``jammed``, ``step_limit``, ``interrupted`` or
        ``time_limit`` (the scene's ``packing.time_limit`` ran out)."""
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

    def mesh(
        self, dir: str | os.PathLike[str], size: float = 0.3, order: int = 1, fill: str = "matrix"
    ) -> dict[str, Any]:
        """Meshes the packing with gmsh as ``[output] mesh = true`` does (needs gmsh in
        this interpreter: ``pip install gmsh==4.15.2``, and a packing with
        ``packing.gap`` >= 0.02).

        Writes ``mesh.msh``, ``mesh.inp`` and ``mesh.vtu`` into ``dir`` (created if
        missing), all or none. ``size`` is the largest element edge over the smallest
        grain's equivalent diameter, ``order`` 1 (C3D4) or 2 (C3D10); a 2D packing is
        meshed as plane-strain triangles, CPE3 or CPE6. ``fill`` is ``"matrix"`` (the
        elements between the grains are the matrix) or ``"grains"`` (shared out among
        the grains, as ``voxelise(fill="grains")`` shares voxels). Returns a dict:
        ``files`` (the paths), ``summary`` (what ``summary.json``'s ``mesh`` holds) and
        ``grid`` (``mesh.vtu`` as a ``pyvista.UnstructuredGrid`` when pyvista is
        installed, else None). Raises ``ValueError`` for bad arguments or a packing
        without the gap, ``RuntimeError`` with gmsh's message if it cannot mesh."""
        if isinstance(order, bool) or not isinstance(order, int):
            raise ValueError(f"order = {order!r}: must be 1 or 2")
        if not isinstance(fill, str) or fill not in ("matrix", "grains"):
            raise ValueError(f'fill = {fill!r}: must be "matrix" or "grains"')
        # gmsh runs in this interpreter (the one the caller installed gmsh into).
        files, stats = self._native._mesh(os.fspath(dir), float(size), order, fill, sys.executable)
        files = [os.fspath(p) for p in files]
        try:
            import pyvista
        except ImportError:
            grid = None
        else:
            grid = pyvista.read(files[2])
        return {"files": files, "summary": json.loads(stats), "grid": grid}

    def voxelise(
        self, resolution: int | tuple[int, int, int] = 64, fill: str = "grains", *, field: str = "material"
    ) -> np.ndarray:
        """The grains sampled on a regular grid over the box, as the RVE (``rve.vti``).

        Parameters
        ----------
        resolution : int, (nx, ny, nz), or (nx, ny) in 2D
            An int puts that many cells along the longest edge and proportionally many
            along the others (as the scene's ``rve_resolution = N``); three ints give
            each count. A 2D scene's grid is one cell thick (``nz = 1``): an int, or
            two ints ``(nx, ny)``.
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
        if not isinstance(fill, str) or fill not in ("grains", "matrix"):
            raise ValueError(f'fill = {fill!r}: must be "grains" or "matrix"')
        if field not in ("material", "phase"):
            raise ValueError(f'field = {field!r}: must be "material" or "phase"')
        try:
            cells = [int(resolution)] if np.isscalar(resolution) else [int(n) for n in resolution]
        except (TypeError, ValueError, OverflowError):
            raise ValueError(f"resolution = {resolution!r}: must be an int or a list of ints") from None
        if any(not 1 <= n < 2**32 for n in cells):
            raise ValueError(f"resolution = {resolution!r}: cell counts must be in [1, 2**32)")
        material, phase, (nx, ny, nz) = self._native._voxelise(cells, fill)
        values = material if field == "material" else phase
        return values.reshape(nz, ny, nx).transpose()

    def to_pyvista(self, resolution: int = 16) -> Any:
        """The grains' surfaces as one ``pyvista.PolyData`` (needs pyvista), with cell
        data ``grain`` (id) and ``phase``; ``.plot()`` shows them. Each grain is a unit
        sphere of ``resolution`` × ``resolution`` points mapped onto its ellipsoid,
        drawn about its centre (grains crossing a periodic face are not wrapped). In 2D,
        each ellipse is a polygon of ``4 * resolution`` points at z = 0."""
        try:
            import pyvista as pv
        except ImportError as e:
            raise ImportError("to_pyvista needs pyvista: pip install pyvista") from e
        if self.dimension == 2:
            return self._polygons(pv, 4 * resolution)
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

    def _polygons(self, pv: Any, m: int) -> Any:
        """The ellipses as one polygon each, of ``m`` points on the ellipse."""
        t = 2 * np.pi * np.arange(m) / m
        a1, a2 = self.semi_axes.T
        c, s = np.cos(self.angles)[:, None], np.sin(self.angles)[:, None]
        u, v = a1[:, None] * np.cos(t), a2[:, None] * np.sin(t)
        x = self.centres[:, :1] + c * u - s * v
        y = self.centres[:, 1:] + s * u + c * v
        points = np.stack([x, y, np.zeros_like(x)], axis=-1).reshape(-1, 3)
        n = len(self)
        ids = np.arange(n * m).reshape(n, m)
        faces = np.column_stack([np.full(n, m), ids]).reshape(-1)
        mesh = pv.PolyData(points, faces)
        mesh.cell_data["grain"] = self.ids
        mesh.cell_data["phase"] = self.phase
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
    if seed is not None and (not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**64):
        raise ValueError(f"seed = {seed!r}: must be a non-negative integer below 2**64")
    if threads is not None and (not isinstance(threads, (int, np.integer)) or not 1 <= threads < 2**64):
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

"""The narrow phase on numpy arrays: pw85's argument layout, the library's functions."""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from . import _grainpack


def _rows(r12: Any, q1: Any, q2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """The three arguments as C-contiguous float64 arrays of shapes (n, 3), (n, 6), (n, 6)
    (ellipsoids) or (n, 2), (n, 3), (n, 3) (ellipses: forms with 3 columns), and whether
    a single pair (1-D arguments) was given."""
    arrays = [np.ascontiguousarray(a, dtype=np.float64) for a in (r12, q1, q2)]
    single = all(a.ndim == 1 for a in arrays)
    if single:
        arrays = [a.reshape(1, -1) for a in arrays]
    n = next((a.shape[0] for a in arrays if a.ndim == 2), 0)
    plane = arrays[1].ndim == 2 and arrays[1].shape[1] == 3
    for name, a, cols in zip(("r12", "q1", "q2"), arrays, (2, 3, 3) if plane else (3, 6, 6)):
        if a.ndim != 2 or a.shape[1] != cols or a.shape[0] != n:
            want = f"({cols},)" if single else f"(n, {cols}) with n = {n}"
            raise ValueError(
                f"{name} has shape {a.shape if not single else a.shape[1:]}, expected {want}"
                " (r12: (n, 3), q1 and q2: (n, 6), or (3,), (6,), (6,) for one pair;"
                " ellipses: (n, 2), (n, 3), (n, 3), or (2,), (3,), (3,))"
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
    r12 : array_like, shape (n, 3) or (3,); (n, 2) or (2,) for ellipses
        ``c2 − c1``, the centre of the second ellipsoid relative to the first.
    q1, q2 : array_like, shape (n, 6) or (6,); (n, 3) or (3,) for ellipses
        The quadratic forms, upper triangle row-major, as in pw85: ``[q00, q01, q11]``
        for ellipses, which are answered as the ellipsoids they are the cross-sections
        of (the library's ``contact_function_2d``, exactly the ellipses' function).
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
    shapes (n,), (n,), (n, 3), (n, 3), (n,); for a single pair, floats and (3,) arrays
    ((n, 2) and (2,) for ellipses).
    """
    r, a, b, single = _rows(r12, q1, q2)
    mu2, lam, point, normal, gap = _grainpack.contact_geometry_rows(r, a, b)
    # Ellipses: the embedded point and normal lie in the plane z = 0.
    point, normal = point[:, : r.shape[1]], normal[:, : r.shape[1]]
    if single:
        return ContactGeometry(float(mu2[0]), float(lam[0]), point[0], normal[0], float(gap[0]))
    return ContactGeometry(mu2, lam, point, normal, gap)


def ellipse_form(semi_axes: Any, angles: Any) -> np.ndarray:
    """``Q = R diag(a1², a2²) Rᵀ`` of ellipses as ``[q00, q01, q11]`` (n, 3), the layout
    :func:`contact_function` takes for ellipses, from semi-axes (n, 2) and the angles
    (n,) of the first semi-axis from x, in radians."""
    a = np.asarray(semi_axes, dtype=np.float64)
    c, s = np.cos(angles), np.sin(angles)
    p, q = a[..., 0] ** 2, a[..., 1] ** 2
    return np.ascontiguousarray(np.stack([p * c * c + q * s * s, (p - q) * c * s, p * s * s + q * c * c], -1))


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

"""An overlap check of packed grains independent of grainpack's contact code and octree:
numpy only, every pair by brute force, μ² by golden-section search (as
tests/support/packed.rs does in Rust)."""

from __future__ import annotations

import numpy as np

# A pair overlaps when μ² < 1 − MU2_TOL. f is computed in double precision by solves
# with Q(λ) of condition at most (a_max/a_min)² ≈ 20 for the shipped scenes, so its
# relative error is below 1e-13; 1e-10 is a wide margin no real overlap hides in (the
# loop's exact check reports any overlap deeper than rounding).
MU2_TOL = 1e-10

# Golden-section iterations: 0.618⁹⁰ ≈ 1e-19 of the initial bracket [0, 1].
ITERATIONS = 90


def rotation(quaternions: np.ndarray) -> np.ndarray:
    w, x, y, z = quaternions.T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
        ],
        -2,
    )


def forms(semi_axes: np.ndarray, quaternions: np.ndarray) -> np.ndarray:
    """Full 3×3 quadratic forms R diag(a²) Rᵀ."""
    r = rotation(quaternions)
    return np.einsum("nik,nk,njk->nij", r, semi_axes**2, r)


def contact_mu2(r: np.ndarray, q1: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """max over λ ∈ [0, 1] of λ(1−λ) rᵀ[(1−λ)Q1 + λQ2]⁻¹ r, per row, by golden section
    (f is concave on [0, 1], so the bracket keeps its maximum)."""

    def f(lam: np.ndarray) -> np.ndarray:
        m = q1 * (1 - lam)[:, None, None] + q2 * lam[:, None, None]
        x = np.linalg.solve(m, r[..., None])[..., 0]
        return lam * (1 - lam) * np.sum(r * x, axis=1)

    g = (np.sqrt(5) - 1) / 2
    a, b = np.zeros(len(r)), np.ones(len(r))
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(ITERATIONS):
        left = fc > fd
        b = np.where(left, d, b)
        a = np.where(left, a, c)
        c_new = np.where(left, b - g * (b - a), d)
        d_new = np.where(left, c, a + g * (b - a))
        fc_new = np.where(left, np.nan, fd)
        fd_new = np.where(left, fc, np.nan)
        c, d = c_new, d_new
        fc = np.where(left, f(c), fc_new)
        fd = np.where(left, fd_new, f(d))
    return np.maximum(fc, fd)


def check(centres, semi_axes, quaternions, size, periodic):
    """(candidate pairs, overlapping pairs, smallest μ²) over all pairs at their minimum
    image whose bounding spheres meet. Needs a box wider than four largest radii in a
    periodic box (else second images could meet; asserted)."""
    size = np.asarray(size, dtype=float)
    radius = semi_axes.max(axis=1)
    assert not periodic or np.all(size > 4 * radius.max()), "box too small for minimum images"
    i, j = np.triu_indices(len(centres), k=1)
    r = centres[j] - centres[i]
    if periodic:
        r -= size * np.round(r / size)
    near = np.linalg.norm(r, axis=1) <= radius[i] + radius[j]
    i, j, r = i[near], j[near], r[near]
    q = forms(semi_axes, quaternions)
    mu2 = contact_mu2(r, q[i], q[j])
    return len(r), int(np.sum(mu2 < 1 - MU2_TOL)), float(mu2.min()) if len(r) else np.inf

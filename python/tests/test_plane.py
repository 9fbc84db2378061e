"""pack in 2D: a box with two lengths packs ellipses, returned as 2D arrays ((n, 2)
centres and semi-axes, (n,) angles, (n, 3) forms), checked without overlap by an
independent search, with the plane statistics in the summary and the plane files
written."""

from __future__ import annotations

import csv

import numpy as np
import pytest

import grainpack as gp

BOX = (40.0, 30.0)

PLANE_SCENE = {
    "seed": 5,
    "target_fraction": 0.6,
    "box": {"size": list(BOX), "boundary": "periodic"},
    "phase": [
        {
            "name": "ellipses",
            "size": {"distribution": "uniform", "min": 3.0, "max": 4.0},
            "aspect_ratio": {"distribution": "constant", "value": 1.5},
            "orientation": {"kind": "random"},
        }
    ],
}


@pytest.fixture(scope="module")
def plane():
    return gp.pack(gp.Scene.from_dict(PLANE_SCENE), progress=False)


def contact_mu2(r, a, b):
    """max over λ of λ(1−λ) rᵀ[(1−λ)A + λB]⁻¹ r for 2×2 forms, by golden-section search
    (the function is concave in λ); 80 steps shrink the bracket to 0.618⁸⁰ ≈ 1e-17."""
    lo, hi = np.zeros(len(r)), np.ones(len(r))
    g = (np.sqrt(5) - 1) / 2

    def f(lam):
        m = (1 - lam)[:, None, None] * a + lam[:, None, None] * b
        x = np.linalg.solve(m, r[:, :, None])[:, :, 0]
        return lam * (1 - lam) * np.einsum("ni,ni->n", r, x)

    for _ in range(80):
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        left = f(x1) > f(x2)
        hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
    return f(0.5 * (lo + hi))


def test_a_2d_scene_packs_ellipses_as_2d_arrays(plane):
    p = plane
    n = len(p)
    assert p.dimension == 2 and p.box_size == BOX
    assert p.centres.shape == (n, 2) and p.semi_axes.shape == (n, 2) and p.angles.shape == (n,)
    assert np.all((p.centres >= 0) & (p.centres < np.array(BOX)))
    np.testing.assert_allclose(p.semi_axes[:, 0] / p.semi_axes[:, 1], 1.5, rtol=1e-14)
    assert np.all((p.angles > -np.pi / 2) & (p.angles <= np.pi / 2))
    s = p.summary
    area = np.sum(np.pi * np.prod(p.semi_axes, axis=1)) / (BOX[0] * BOX[1])
    assert abs(area - s["packing_fraction"]) <= 1e-12
    # The forms: the end of each first semi-axis lies on its ellipse, xᵀ Q⁻¹ x = 1.
    q = p.quadratic_forms
    assert q.shape == (n, 3)
    forms = np.stack([np.stack([q[:, 0], q[:, 1]], -1), np.stack([q[:, 1], q[:, 2]], -1)], 1)
    tip = p.semi_axes[:, :1] * np.column_stack([np.cos(p.angles), np.sin(p.angles)])
    on = np.einsum("ni,ni->n", tip, np.linalg.solve(forms, tip[:, :, None])[:, :, 0])
    np.testing.assert_allclose(on, 1, rtol=1e-12)
    # No two ellipses overlap, over every pair and the nearest periodic image.
    i, j = np.triu_indices(n, 1)
    r = p.centres[j] - p.centres[i]
    r -= np.array(BOX) * np.round(r / np.array(BOX))
    mu2 = contact_mu2(r, forms[i], forms[j])
    assert mu2.min() >= 1 - 1e-9, mu2.min()


def test_the_summary_has_the_plane_statistics(plane):
    s = plane.summary
    stats = s["plane"]
    assert 0 <= stats["psi6_global"] <= 1 and 0 <= stats["psi6_local"] <= 1
    assert stats["nearest_centre_distance"]["min"] > 0
    assert stats["nearest_gap"]["min"] >= 0
    angles = s["phases"][0]["angle_deg"]
    assert 0 <= angles["order"] <= 1


def test_write_gives_the_plane_files(plane, tmp_path):
    names = {p.rsplit("/", 1)[-1] for p in plane.write(tmp_path)}
    assert {"grains.csv", "grains.vtu", "centers.vtp", "packing.png", "summary.json"} <= names
    with open(tmp_path / "grains.csv", newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0][:7] == ["id", "phase", "x", "y", "a1", "a2", "angle"]
    np.testing.assert_array_equal([float(r[6]) for r in rows[1:]], plane.grains["angle"])
    mesh = plane.to_pyvista() if _has_pyvista() else None
    if mesh is not None:
        assert mesh.n_cells == len(plane)


def _has_pyvista():
    try:
        import pyvista  # noqa: F401
    except ImportError:
        return False
    return True

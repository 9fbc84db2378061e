"""The contact functions on ellipses ((n, 2) offsets, (n, 3) forms) against the committed
2D mpmath references (the thresholds of tests/contact_plane.rs), and their handling of
bad rows and shapes."""

from __future__ import annotations

import csv
from collections import defaultdict

import numpy as np
import pytest

import grainpack as gp
from conftest import DATA

# tests/contact_plane.rs: the accurate method's error on every row, a few ulps.
ACCURATE_TOL = 1e-15
# The yes/no test must match the sign of μ² − 1 wherever |μ² − 1| exceeds this.
TANGENCY = 1e-12
# Identities exact in real arithmetic, reproduced to a few ulps (as test_contact.py).
IDENTITY_TOL = 16 * np.finfo(float).eps
SETS = ["contact_plane_typical.csv", "contact_plane_extreme.csv"]


def load(name: str):
    with open(DATA / name, newline="") as f:
        rows = list(csv.DictReader(f))
    r12 = np.array([[float(row[f"r{k}"]) for k in range(2)] for row in rows])
    q1 = np.array([[float(row[f"q1_{k}"]) for k in range(3)] for row in rows])
    q2 = np.array([[float(row[f"q2_{k}"]) for k in range(3)] for row in rows])
    mu2 = np.array([float(row["mu2"]) for row in rows])
    category = np.array([row.get("category", "typical") for row in rows])
    return r12, q1, q2, mu2, category


@pytest.mark.parametrize("name", SETS)
def test_contact_function_of_ellipses_is_within_a_few_ulps(name):
    r12, q1, q2, reference, category = load(name)
    mu2, lam = gp.contact_function(r12, q1, q2)
    assert mu2.shape == lam.shape == reference.shape
    assert np.all((lam >= 0) & (lam <= 1))
    err = np.abs((mu2 - reference) / reference)
    worst = defaultdict(float)
    for c, e in zip(category, err):
        worst[c] = max(worst[c], e)
    assert all(e <= ACCURATE_TOL for e in worst.values()), dict(worst)


@pytest.mark.parametrize("name", SETS)
def test_overlaps_of_ellipses_agrees_with_the_reference_sign(name):
    r12, q1, q2, reference, _ = load(name)
    keep = np.abs(reference - 1) > TANGENCY
    np.testing.assert_array_equal(gp.overlaps(r12[keep], q1[keep], q2[keep]), reference[keep] < 1)


def test_circles_and_one_pair():
    rng = np.random.default_rng(3)
    radii = rng.uniform(0.1, 10, size=(200, 2))
    angles = rng.uniform(-np.pi, np.pi, size=(200, 2))
    q1 = gp.ellipse_form(np.repeat(radii[:, :1], 2, axis=1), angles[:, 0])
    q2 = gp.ellipse_form(np.repeat(radii[:, 1:], 2, axis=1), angles[:, 1])
    r12 = rng.normal(size=(200, 2)) * 10
    mu2, lam = gp.contact_function(r12, q1, q2)
    want = np.sum(r12 * r12, axis=1) / radii.sum(axis=1) ** 2
    assert np.all(np.abs(mu2 - want) <= IDENTITY_TOL * want)
    one = gp.contact_function(r12[7], q1[7], q2[7])
    assert isinstance(one.mu2, float) and one.mu2 == mu2[7] and one.lam == lam[7]
    assert gp.overlaps(r12[7], q1[7], q2[7]) == bool(mu2[7] < 1)


def test_contact_geometry_of_ellipses_is_in_the_plane():
    q = gp.ellipse_form([[2.0, 1.0]], [0.3])[0]
    g = gp.contact_geometry([[3.0, 1.0]], [q], [q])
    assert g.point.shape == (1, 2) and g.normal.shape == (1, 2)
    # Equal ellipses: they touch half-way, the point at r12 / 2 scaled by μ.
    np.testing.assert_allclose(g.point[0], [1.5, 0.5], rtol=IDENTITY_TOL)
    assert abs(np.linalg.norm(g.normal[0]) - 1) <= IDENTITY_TOL
    single = gp.contact_geometry([3.0, 1.0], q, q)
    assert single.point.shape == (2,)


def test_a_bad_2d_row_names_the_2d_entry():
    r12 = np.ones((20, 2)) * 3
    q = np.tile([1.0, 0.0, 1.0], (20, 1))
    bad = q.copy()
    bad[11] = [1.0, 0.0, -1.0]
    with pytest.raises(ValueError, match=r"^row 11: q2 is not positive definite: pivot 1"):
        gp.contact_function(r12, q, bad)
    with pytest.raises(ValueError, match=r"^row 11: q2 is not positive definite: pivot 1"):
        gp.overlaps(r12, q, bad)
    bad[11] = [1.0, 0.0, np.inf]
    with pytest.raises(ValueError, match=r"^row 11: q2\[2\] is not finite: inf"):
        gp.contact_function(r12, q, bad)
    segment = np.array([1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="^row 0: q1 and q2 are both singular"):
        gp.contact_function([0.0, 1.0], segment, segment)


@pytest.mark.parametrize(
    "args, message",
    [
        ((np.zeros((4, 3)), np.zeros((4, 3)), np.zeros((4, 3))), r"r12 has shape \(4, 3\), expected \(n, 2\)"),
        ((np.zeros((4, 2)), np.zeros((4, 3)), np.zeros((4, 6))), r"q2 has shape \(4, 6\), expected \(n, 3\)"),
        ((np.zeros((4, 2)), np.zeros((4, 3)), np.zeros((3, 3))), r"q2 has shape \(3, 3\)"),
        ((np.zeros(2), np.zeros(3), np.zeros(2)), r"q2 has shape \(2,\), expected \(3,\)"),
    ],
)
def test_2d_arrays_of_the_wrong_shape_raise_value_error(args, message):
    with pytest.raises(ValueError, match=message):
        gp.contact_function(*args)

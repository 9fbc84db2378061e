"""The contact functions against the committed mpmath references (the thresholds of
tests/contact_reference.rs), their properties, and their handling of bad rows."""

from __future__ import annotations

import csv
from collections import defaultdict

import numpy as np
import pytest

import grainpack as gp
from conftest import DATA

# tests/contact_reference.rs: the accurate method's error on every row of every set, a
# few ulps (measured at most 3.6e-16); and its looser per-set requirements.
ACCURATE_TOL = 1e-15
TYPICAL_TOL = 1e-14
EXTREME_TOL = 1e-12
# tests/contact_reference.rs: the yes/no test must match the sign of μ² − 1 wherever
# |μ² − 1| exceeds this (tangent pairs are decided either way by rounding).
TANGENCY = 1e-12
# tests/contact_properties.rs: identities exact in real arithmetic, reproduced to a few
# ulps; 16 ε leaves room for the rounding of the transformed inputs.
IDENTITY_TOL = 16 * np.finfo(float).eps
# tests/contact_properties.rs: the contact point lies on both scaled ellipsoids; the
# check inverts Q in double precision (condition up to 1e4 for these pairs).
SURFACE_TOL = 1e-9


def load(name: str):
    with open(DATA / name, newline="") as f:
        rows = list(csv.DictReader(f))
    r12 = np.array([[float(row[f"r{k}"]) for k in range(3)] for row in rows])
    q1 = np.array([[float(row[f"q1_{k}"]) for k in range(6)] for row in rows])
    q2 = np.array([[float(row[f"q2_{k}"]) for k in range(6)] for row in rows])
    mu2 = np.array([float(row["mu2"]) for row in rows])
    category = np.array([row.get("category", "typical") for row in rows])
    return r12, q1, q2, mu2, category


def worst_by_category(mu2, reference, category):
    err = np.abs((mu2 - reference) / reference)
    worst = defaultdict(float)
    for c, e in zip(category, err):
        worst[c] = max(worst[c], e)
    return dict(worst)


@pytest.mark.parametrize("name", ["contact_typical.csv", "contact_extreme.csv", "contact_degenerate.csv"])
def test_contact_function_is_within_a_few_ulps_on_every_set(name):
    r12, q1, q2, reference, category = load(name)
    mu2, lam = gp.contact_function(r12, q1, q2)
    assert mu2.shape == lam.shape == reference.shape
    assert np.all((lam >= 0) & (lam <= 1))
    for cat, err in worst_by_category(mu2, reference, category).items():
        assert err <= ACCURATE_TOL, f"{name}, {cat}: {err:e}"


def test_typical_and_extreme_sets_meet_their_own_bounds():
    r12, q1, q2, reference, category = load("contact_typical.csv")
    assert len(reference) == 1000
    assert worst_by_category(gp.contact_function(r12, q1, q2).mu2, reference, category)["typical"] <= TYPICAL_TOL
    r12, q1, q2, reference, category = load("contact_extreme.csv")
    worst = worst_by_category(gp.contact_function(r12, q1, q2).mu2, reference, category)
    assert len(worst) == 8, worst
    assert all(err <= EXTREME_TOL for err in worst.values()), worst


@pytest.mark.parametrize("name", ["contact_typical.csv", "contact_extreme.csv"])
def test_overlaps_agrees_with_the_reference_sign_away_from_tangency(name):
    r12, q1, q2, reference, _ = load(name)
    keep = np.abs(reference - 1) > TANGENCY
    answers = gp.overlaps(r12[keep], q1[keep], q2[keep])
    assert answers.dtype == bool
    np.testing.assert_array_equal(answers, reference[keep] < 1)


def test_batch_rows_equal_single_calls_bitwise():
    r12, q1, q2, _, _ = load("contact_extreme.csv")
    mu2, lam = gp.contact_function(r12, q1, q2)
    for i in range(0, len(mu2), 37):
        one = gp.contact_function(r12[i], q1[i], q2[i])
        assert isinstance(one.mu2, float)
        assert (one.mu2, one.lam) == (mu2[i], lam[i])


def test_the_pw85_manual_example_and_pw85s_out_argument():
    # pw85's spheroid() rounds Q_zz to 0.010000000000005116; with it the manual prints
    # μ² = 3.362706040638343 and λ = 0.1668589553405904.
    q1 = np.array([100.0, 0.0, 0.0, 100.0, 0.0, 0.010000000000005116])
    q2 = np.array([25.0, 0.0, 0.0, 0.25, 0.0, 0.25])
    r12 = np.array([0.2 - -0.5, -0.3 - 0.4, 0.4 - -0.7])
    out = np.empty(2)
    mu2 = gp.contact_function(r12, q1, q2, out)
    assert mu2 == out[0]
    assert abs(mu2 - 3.362706040638343) <= IDENTITY_TOL * mu2
    assert abs(out[1] - 0.1668589553405904) <= 1e-14
    many = np.empty((3, 2))
    values = gp.contact_function(np.tile(r12, (3, 1)), np.tile(q1, (3, 1)), np.tile(q2, (3, 1)), many)
    np.testing.assert_array_equal(values, many[:, 0])
    np.testing.assert_array_equal(many, np.tile(out, (3, 1)))


def random_pairs(rng, n):
    axes = 10.0 ** rng.uniform(-1, 1, size=(n, 2, 3))
    quats = rng.uniform(-1, 1, size=(n, 2, 4))
    quats /= np.linalg.norm(quats, axis=-1, keepdims=True)
    q1 = gp.quadratic_form(axes[:, 0], quats[:, 0])
    q2 = gp.quadratic_form(axes[:, 1], quats[:, 1])
    return rng.uniform(-5, 5, size=(n, 3)), q1, q2


def close(a, b, tol):
    return np.abs(a - b) <= tol * np.maximum(np.abs(a), np.abs(b))


def test_swapping_the_ellipsoids_keeps_mu2_and_mirrors_lambda():
    r12, q1, q2 = random_pairs(np.random.default_rng(1), 2000)
    a = gp.contact_function(r12, q1, q2)
    b = gp.contact_function(-r12, q2, q1)
    assert np.all(close(a.mu2, b.mu2, IDENTITY_TOL))
    # λ is located to the solver's tolerance, not to ulps: f is flat at its maximum.
    assert np.all(np.abs(a.lam - (1 - b.lam)) <= 1e-7)


def test_scaling_by_s_scales_mu2_by_one_over_s_squared_for_the_forms():
    r12, q1, q2 = random_pairs(np.random.default_rng(2), 2000)
    base = gp.contact_function(r12, q1, q2).mu2
    # Powers of two, so that the scaled inputs are exact and the identity is exact in
    # floating point too: with s = 3 the rounding of q·s² alone moves μ² by up to
    # cond · ε (measured 227 ε for axes ratios up to 100).
    for s in (4.0, 0.125):
        # Both ellipsoids scaled by s (forms by s²), centres fixed: μ² divided by s².
        scaled = gp.contact_function(r12, q1 * s * s, q2 * s * s).mu2
        assert np.all(close(scaled * s * s, base, IDENTITY_TOL))
        # The whole pair scaled by s: unchanged.
        whole = gp.contact_function(r12 * s, q1 * s * s, q2 * s * s).mu2
        assert np.all(close(whole, base, IDENTITY_TOL))


def test_two_spheres_give_the_squared_distance_ratio():
    rng = np.random.default_rng(3)
    a, b = rng.uniform(0.5, 2, size=(2, 500))
    r12 = rng.uniform(-5, 5, size=(500, 3))
    ball = lambda r: np.outer(r * r, [1, 0, 0, 1, 0, 1])
    mu2, _ = gp.contact_function(r12, ball(a), ball(b))
    exact = np.sum(r12 * r12, axis=1) / (a + b) ** 2
    assert np.all(close(mu2, exact, IDENTITY_TOL))


def test_contact_point_lies_on_both_scaled_ellipsoids_with_a_common_normal():
    r12, q1, q2 = random_pairs(np.random.default_rng(8), 500)
    g = gp.contact_geometry(r12, q1, q2)
    full = lambda q: q[:, [0, 1, 2, 1, 3, 4, 2, 4, 5]].reshape(-1, 3, 3)
    inv1, inv2 = np.linalg.inv(full(q1)), np.linalg.inv(full(q2))
    x1, x2 = g.point, g.point - r12
    h1 = np.einsum("ni,nij,nj->n", x1, inv1, x1)
    h2 = np.einsum("ni,nij,nj->n", x2, inv2, x2)
    assert np.all(close(h1, g.mu2, SURFACE_TOL)) and np.all(close(h2, g.mu2, SURFACE_TOL))
    for v in (np.einsum("nij,nj->ni", inv1, x1), -np.einsum("nij,nj->ni", inv2, x2)):
        v = v / np.linalg.norm(v, axis=1, keepdims=True)
        assert np.all(np.sum(v * g.normal, axis=1) > 1 - SURFACE_TOL)
    np.testing.assert_array_equal(g.gap > 0, g.mu2 > 1)
    np.testing.assert_array_equal(g.mu2, gp.contact_function(r12, q1, q2).mu2)


def test_a_bad_row_raises_naming_it_and_nothing_crashes():
    r12, q1, q2 = random_pairs(np.random.default_rng(4), 50)
    bad = q2.copy()
    bad[17] = [1, 0, 0, -1, 0, 1]
    with pytest.raises(ValueError, match=r"^row 17: q2 is not positive definite"):
        gp.contact_function(r12, q1, bad)
    with pytest.raises(ValueError, match=r"^row 17: q2 is not positive definite"):
        gp.overlaps(r12, q1, bad)
    nan = r12.copy()
    nan[3, 1] = np.nan
    with pytest.raises(ValueError, match=r"^row 3: r12\[1\] is not finite: NaN"):
        gp.contact_function(nan, q1, q2)
    with pytest.raises(ValueError, match="^row 0: the centres coincide"):
        gp.contact_geometry(np.zeros(3), q1[0], q2[0])
    disc = np.array([1.0, 0, 0, 1, 0, 0])
    with pytest.raises(ValueError, match="^row 0: q1 and q2 are both singular"):
        gp.contact_function([0.0, 0.0, 1.0], disc, disc)


@pytest.mark.parametrize(
    "args, message",
    [
        ((np.zeros((4, 3)), np.zeros((4, 6)), np.zeros((3, 6))), r"q2 has shape \(3, 6\)"),
        ((np.zeros((4, 2)), np.zeros((4, 6)), np.zeros((4, 6))), r"r12 has shape \(4, 2\)"),
        ((np.zeros(3), np.zeros(5), np.zeros(6)), r"q1 has shape \(5,\)"),
        ((np.zeros((2, 2, 3)), np.zeros((2, 6)), np.zeros((2, 6))), "r12 has shape"),
        ((np.zeros(3), np.zeros((2, 6)), np.zeros((2, 6))), r"r12 has shape \(3,\), expected \(n, 3\) with n = 2"),
    ],
)
def test_arrays_of_the_wrong_shape_raise_value_error(args, message):
    with pytest.raises(ValueError, match=message):
        gp.contact_function(*args)


def test_any_layout_and_dtype_is_accepted():
    r12, q1, q2 = random_pairs(np.random.default_rng(5), 64)
    want = gp.contact_function(r12, q1, q2).mu2
    got = gp.contact_function(np.asfortranarray(r12), q1.astype(np.float32).astype(np.float64)[:, :], q2.tolist()).mu2
    np.testing.assert_array_equal(got[:1], gp.contact_function(r12[:1], q1[:1].astype(np.float32).astype(np.float64), q2[:1]).mu2)
    strided = np.repeat(r12, 2, axis=0)[::2]
    np.testing.assert_array_equal(gp.contact_function(strided, q1, q2).mu2, want)
    assert gp.contact_function(np.zeros((0, 3)), np.zeros((0, 6)), np.zeros((0, 6))).mu2.shape == (0,)
    assert got.shape == want.shape

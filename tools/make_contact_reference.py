#!/usr/bin/env python3
"""Reference data for the Perram–Wertheim contact function of two ellipsoids.

An ellipsoid is {m : (m - c)ᵀ Q⁻¹ (m - c) <= 1}.  For a pair with r = c2 - c1 the
contact function is

    μ² = max over λ in [0, 1] of f(λ) = λ(1-λ) rᵀ [(1-λ) Q1 + λ Q2]⁻¹ r,

and λ* is the maximiser.  Q is stored as its upper triangle, row-major:
[Q00, Q01, Q02, Q11, Q12, Q22].

Every input (r, q1, q2) is a double, generated in double precision and written with
repr() (shortest round-trip form).  The reference μ² and λ* are computed with mpmath
at DPS decimal digits from exactly those doubles, by a safeguarded Newton/bisection
on g(λ) = -f'(λ), and written with 30 significant digits.  A sample of rows is
re-solved at CHECK_DPS digits by an independent method (the root of the degree-6
numerator of f'(λ), built from the polynomial adjugate and determinant of Q(λ)) and
must agree to at least 30 digits in μ² and in λ* (relative to min(λ*, 1 - λ*));
--check-all re-solves every row.  The degenerate rows are checked by a golden-section
search of f itself (tools/contact_exact.py): 30 digits in μ², MIN_GOLDEN_LAMBDA_DIGITS
in λ* where it is not an end.

Output (header r0,r1,r2,q1_0..q1_5,q2_0..q2_5,mu2,lambda):

tests/data/contact_typical.csv   N_TYPICAL rows.  Triaxial ellipsoids with semi-axes
    log-uniform in [0.1, 10], uniformly random rotations, random direction of r,
    and |r| scaled so that μ² is log-uniform in [1e-2, 1e2].

tests/data/contact_extreme.csv   N_PER_CATEGORY rows per category (8 categories; the last
    has len(NEAR_ASPECTS) × len(NEAR_PERTURBATIONS) × ROWS_PER_NEAR = 240 rows),
    with an extra final column `category`:
    aspect_ratio     needles (a, a/A, a/A), platelets (a, a, a/A) and triaxial
                     (a, a/A^t, a/A) ellipsoids, A log-uniform in [10, 1e4] (a quarter
                     exactly 1e4), a log-uniform in [0.1, 10]; μ² in [1e-2, 1e2].
    size_ratio       a typical ellipsoid and one scaled up by ρ, log-uniform in
                     [1e3, 1e6], alternately first and second, so λ* lies within
                     about 1/ρ of 1 or of 0; μ² in [1e-2, 1e2].
    near_tangent     typical pairs with r scaled so that μ² = 1 (half the rows) or
                     1 ± 1e-14, 1 ± 1e-12, 1 ± 1e-10 in exact arithmetic before r is
                     rounded to doubles.
    identical        Q2 == Q1 exactly (half the rows, λ* = 1/2), or Q2 = Q1 with every
                     entry perturbed by a relative amount up to ε, ε log-uniform in
                     [1e-15, 1e-8]; μ² in [1e-2, 1e2].
    tiny_scale       typical pairs with all lengths scaled by 1e-6 (Q by 1e-12).
    huge_scale       typical pairs with all lengths scaled by 1e6 (Q by 1e12).
    near_coincident  typical pairs with |r| tiny: μ² log-uniform in [1e-24, 1e-4].
    nearly_identical Q2 a tiny change of Q1 with nearly parallel axes, for every aspect
                     ratio A in NEAR_ASPECTS (needles, platelets, triaxial, as in
                     aspect_ratio; A = 1 is a ball) and perturbation δ in
                     NEAR_PERTURBATIONS (1e-16 to 1e-2), ROWS_PER_NEAR rows each: the
                     semi-axes multiplied by 1 + δξ (ξ uniform in [-1, 1]), or the
                     orientation turned by an angle δ about a random axis, alternately;
                     μ² in [1e-2, 1e2].  The coefficients of f cancel here.

tests/data/contact_degenerate.csv   N_PER_CATEGORY rows per category, with `category`,
    solved by tools/contact_exact.py (exact rational coefficients; see its docstring):
    semi_definite    a singular form against a definite one (typical or elongated), in
                     either order: a flat disc (rank 2), a zero-radius needle (rank 1)
                     or a point (Q = 0); and, one row in five, a disc against a disc or
                     a needle crossing it (both singular, in no common direction).  The
                     singular forms are B Bᵀ with B (3 × rank) a rotation's columns times
                     semi-axes in [0.1, 10], rounded to 20 bits: every product and sum is
                     then exact in doubles, so they are exactly singular.  μ² in
                     [1e-2, 1e2]; λ* may be 0 or 1 (the limit at the singular end).
    huge_ratio       a typical ellipsoid and one scaled up by ρ, log-uniform in
                     HUGE_RATIO_RANGE (up to 1e150, Q ratio 1e300), alternately first and
                     second; μ² in [1e-2, 1e2].

The script also checks the worked example of the pw85 manual.  It is deterministic:
random numbers come only from random.Random(SEED).random(), whose sequence Python
guarantees, transcendental functions are evaluated by mpmath and rounded to doubles,
and Q is computed with plain Python float arithmetic in a fixed order.

Run from the repository root:  python3 tools/make_contact_reference.py [--check-all]
"""

import argparse
import math
import random
import sys
import time
from collections import namedtuple
from pathlib import Path

import mpmath
from mpmath import mp, mpf

from contact_exact import contact_exact, contact_golden, agreeing

SEED = 20240611
DPS = 60
CHECK_DPS = 120
N_TYPICAL = 1000
N_PER_CATEGORY = 215
N_CHECK_PER_GROUP = 8
MIN_AGREEING_DIGITS = 30
MAX_ITERATIONS = 400
SIZE_RATIO_RANGE = (1e3, 1e6)
NEAR_ASPECTS = [1.0, 3.0, 10.0, 100.0, 1e3, 1e4]
NEAR_PERTURBATIONS = [1e-16, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2]
ROWS_PER_NEAR = 5
HUGE_RATIO_RANGE = (1e6, 1e150)
SINGULAR_BITS = 20
MIN_GOLDEN_LAMBDA_DIGITS = 15
OUT_DIR = Path(__file__).resolve().parent.parent / "tests" / "data"

HEADER = (
    ["r0", "r1", "r2"]
    + [f"q1_{k}" for k in range(6)]
    + [f"q2_{k}" for k in range(6)]
    + ["mu2", "lambda"]
)
NEAR_TANGENT_OFFSETS = [0.0] * 6 + [1e-14, -1e-14, 1e-12, -1e-12, 1e-10, -1e-10]


# ----------------------------------------------------------------------------------
# Random inputs (doubles)
# ----------------------------------------------------------------------------------

def log_uniform(rng, lo, hi):
    """A double log-uniformly distributed in [lo, hi]."""
    a, b = mp.log10(lo), mp.log10(hi)
    return float(mpf(10) ** (a + (b - a) * rng.random()))


def typical_semi_axes(rng):
    """Three semi-axes, each log-uniform in [0.1, 10]."""
    return [log_uniform(rng, 0.1, 10.0) for _ in range(3)]


def random_quaternion(rng):
    """A uniformly random unit quaternion (w, x, y, z) as doubles (Shoemake)."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = mp.sqrt(1 - u1), mp.sqrt(u1)
    t2, t3 = 2 * mp.pi * u2, 2 * mp.pi * u3
    return tuple(float(v) for v in (a * mp.sin(t2), a * mp.cos(t2), b * mp.sin(t3), b * mp.cos(t3)))


def random_direction(rng):
    """A uniformly random unit vector, in high precision (mpf)."""
    z = 2 * mpf(rng.random()) - 1
    phi = 2 * mp.pi * rng.random()
    rho = mp.sqrt(1 - z * z)
    return (rho * mp.cos(phi), rho * mp.sin(phi), z)


def rotation_matrix(quat):
    """Rotation matrix of a unit quaternion (w, x, y, z), Hamilton convention."""
    w, x, y, z = quat
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]


def quadratic_form(semi_axes, quat):
    """Upper triangle of Q = R diag(a²) Rᵀ, in doubles; semi-axis k along column k of R."""
    rot = rotation_matrix(quat)
    sq = [a * a for a in semi_axes]
    return tuple(
        sum(rot[i][k] * sq[k] * rot[j][k] for k in range(3))
        for i, j in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
    )


def random_form(rng, semi_axes):
    """Q of an ellipsoid with the given semi-axes and a uniformly random orientation."""
    return quadratic_form(semi_axes, random_quaternion(rng))


def scaled_separation(rng, q1, q2, mu2_target, solve=None):
    """A random r, rounded to doubles, with μ²(exact r before rounding) = mu2_target.

    μ² is computed for a unit r in high precision (by `solve`, default `contact`); μ² ∝
    |r|², so r is scaled by sqrt(mu2_target / μ²(unit r)) and each component rounded to
    the nearest double.
    """
    direction = random_direction(rng)
    unit_mu2 = contact(direction, q1, q2).mu2 if solve is None else solve(direction, q1, q2).mu2
    scale = mp.sqrt(mpf(mu2_target) / unit_mu2)
    return tuple(float(scale * d) for d in direction)


# ----------------------------------------------------------------------------------
# High-precision contact function (primary method)
# ----------------------------------------------------------------------------------

Contact = namedtuple("Contact", "mu2 lam iterations")
Contact.__doc__ = "μ², the maximiser λ* and the number of Newton/bisection iterations."


def to_mp(values):
    """Exact conversion of doubles (or mpf) to mpf."""
    return [mpf(v) for v in values]


def adjugate(q):
    """Adjugate (upper triangle) and determinant of a symmetric 3×3 matrix."""
    a, b, c, d, e, f = q
    adj = (d * f - e * e, c * e - b * f, b * e - c * d, a * f - c * c, b * c - a * e, a * d - b * b)
    return adj, a * adj[0] + b * adj[1] + c * adj[2]


def sym_mul(q, x):
    """Product of a symmetric 3×3 matrix (upper triangle) and a vector."""
    return (
        q[0] * x[0] + q[1] * x[1] + q[2] * x[2],
        q[1] * x[0] + q[3] * x[1] + q[4] * x[2],
        q[2] * x[0] + q[4] * x[1] + q[5] * x[2],
    )


def dot(x, y):
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]


def pencil(q1, dq, lam):
    """Q(λ) = (1-λ) Q1 + λ Q2 = Q1 + λ (Q2 - Q1)."""
    return [a + lam * b for a, b in zip(q1, dq)]


def f_value(r, q1, dq, lam):
    """f(λ) = λ(1-λ) rᵀ Q(λ)⁻¹ r."""
    adj, det = adjugate(pencil(q1, dq, lam))
    return lam * (1 - lam) * dot(r, sym_mul(adj, r)) / det


def g_and_slope(r, q1, dq, lam):
    """g(λ) = -f'(λ) and g'(λ)."""
    adj, det = adjugate(pencil(q1, dq, lam))
    s = [x / det for x in sym_mul(adj, r)]
    u = sym_mul(dq, s)
    v = [x / det for x in sym_mul(adj, u)]
    rs, su, uv = dot(r, s), dot(s, u), dot(u, v)
    g = (2 * lam - 1) * rs + lam * (1 - lam) * su
    slope = 2 * rs + 2 * (1 - 2 * lam) * su - 2 * lam * (1 - lam) * uv
    return g, slope


def contact(r, q1, q2):
    """μ² and λ* at the current mp precision by safeguarded Newton on g.

    g is increasing with g(0) < 0 < g(1); the bracket [lo, hi] around the root is
    kept, and a bisection replaces the Newton step when that step leaves the bracket
    or would not be at most half the previous step (as in rtsafe).  Stops when the
    Newton correction |Δλ| = |g/g'| <= 10^-(dps-15) · max(λ, 1e-30), after applying it.
    """
    r, q1, q2 = to_mp(r), to_mp(q1), to_mp(q2)
    assert any(r), "r = 0: λ* is undefined"
    dq = [b - a for a, b in zip(q1, q2)]
    tol = mpf(10) ** (15 - mp.dps)
    lo, hi = mpf(0), mpf(1)
    lam = last_step = mpf(1) / 2
    for iteration in range(1, MAX_ITERATIONS + 1):
        g, slope = g_and_slope(r, q1, dq, lam)
        if g == 0:
            return Contact(f_value(r, q1, dq, lam), lam, iteration)
        if g < 0:
            lo = lam
        else:
            hi = lam
        step = -g / slope if slope > 0 else None
        if step is not None and abs(step) <= tol * max(lam, mpf("1e-30")):
            lam += step
            return Contact(f_value(r, q1, dq, lam), lam, iteration)
        if step is None or not lo < lam + step < hi or abs(2 * g) > abs(last_step * slope):
            step = (lo + hi) / 2 - lam
        lam += step
        last_step = step
    raise AssertionError(f"no convergence after {MAX_ITERATIONS} iterations: r={r} q1={q1} q2={q2}")


def assert_positive_definite(q):
    """Sylvester's criterion on the doubles of q (products of three doubles are exact at DPS)."""
    a, b, c, d, e, f = to_mp(q)
    minors = (a, a * d - b * b, adjugate((a, b, c, d, e, f))[1])
    assert all(m > 0 for m in minors), f"not positive definite: {q}"


# ----------------------------------------------------------------------------------
# Independent cross-check: root of the numerator polynomial of f'(λ)
# ----------------------------------------------------------------------------------

def poly_add(p, q):
    n = max(len(p), len(q))
    return [(p[k] if k < len(p) else 0) + (q[k] if k < len(q) else 0) for k in range(n)]


def poly_mul(p, q):
    out = [mpf(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def poly_scale(p, c):
    return [c * a for a in p]


def poly_deriv(p):
    return [k * p[k] for k in range(1, len(p))]


def poly_eval(p, x):
    acc = mpf(0)
    for a in reversed(p):
        acc = acc * x + a
    return acc


def contact_by_polynomial(r, q1, q2):
    """μ² and λ* from f = h/D with h = λ(1-λ) rᵀ adj(Q(λ)) r and D = det Q(λ).

    The entries of Q(λ) are degree-1 polynomials; the adjugate and the determinant are
    expanded as polynomials, and λ* is the only root in (0, 1) of h'D - hD' (degree 6
    at most), found among all its complex roots by mpmath.polyroots.
    """
    r, q1, q2 = to_mp(r), to_mp(q1), to_mp(q2)
    a, b, c, d, e, f = ([x, y - x] for x, y in zip(q1, q2))

    def minor(x, y, z, w):
        return poly_add(poly_mul(x, y), poly_scale(poly_mul(z, w), -1))

    adj = (minor(d, f, e, e), minor(c, e, b, f), minor(b, e, c, d),
           minor(a, f, c, c), minor(b, c, a, e), minor(a, d, b, b))
    det = poly_add(poly_add(poly_mul(a, adj[0]), poly_mul(b, adj[1])), poly_mul(c, adj[2]))
    weights = (r[0] * r[0], 2 * r[0] * r[1], 2 * r[0] * r[2], r[1] * r[1], 2 * r[1] * r[2], r[2] * r[2])
    quad = [mpf(0)]
    for w, p in zip(weights, adj):
        quad = poly_add(quad, poly_scale(p, w))
    h = poly_mul([mpf(0), mpf(1), mpf(-1)], quad)
    numerator = poly_add(poly_mul(poly_deriv(h), det), poly_scale(poly_mul(h, poly_deriv(det)), -1))
    while numerator[-1] == 0:
        numerator.pop()
    roots = mpmath.polyroots(numerator[::-1], maxsteps=500, extraprec=2 * mp.prec)
    tiny = mpf(10) ** (20 - mp.dps)
    inside = [z.real for z in map(mpmath.mpc, roots) if abs(z.imag) <= tiny and 0 < z.real < 1]
    assert len(inside) == 1, f"expected one root of the numerator in (0, 1), got {inside}"
    lam = inside[0]
    return Contact(poly_eval(h, lam) / poly_eval(det, lam), lam, None)


def agreeing_digits(x, y):
    """-log10 of the relative difference (inf if equal)."""
    if x == y:
        return math.inf
    return float(-mp.log10(abs(x - y) / max(abs(x), abs(y))))


# ----------------------------------------------------------------------------------
# Categories
# ----------------------------------------------------------------------------------

def typical_pair(rng, length_scale=1.0):
    """Two typical triaxial ellipsoids, all semi-axes multiplied by length_scale."""
    return tuple(random_form(rng, [length_scale * a for a in typical_semi_axes(rng)]) for _ in range(2))


def typical_rows(rng, n, length_scale=1.0, mu2_range=(1e-2, 1e2)):
    rows = []
    for _ in range(n):
        q1, q2 = typical_pair(rng, length_scale)
        rows.append((q1, q2, log_uniform(rng, *mu2_range)))
    return rows


def elongated_semi_axes(rng):
    """A needle, platelet or triaxial ellipsoid with aspect ratio up to 1e4."""
    kind = int(3 * rng.random())
    aspect = 1e4 if rng.random() < 0.25 else log_uniform(rng, 10.0, 1e4)
    size = log_uniform(rng, 0.1, 10.0)
    if kind == 0:
        return [size, size / aspect, size / aspect]
    if kind == 1:
        return [size, size, size / aspect]
    return [size, size / float(mpf(aspect) ** rng.random()), size / aspect]


def aspect_ratio_rows(rng, n):
    rows = []
    for _ in range(n):
        q1 = random_form(rng, elongated_semi_axes(rng))
        q2 = random_form(rng, elongated_semi_axes(rng))
        rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


def size_ratio_rows(rng, n):
    rows = []
    for i in range(n):
        ratio = log_uniform(rng, *SIZE_RATIO_RANGE)
        small = random_form(rng, typical_semi_axes(rng))
        big = random_form(rng, [ratio * a for a in typical_semi_axes(rng)])
        q1, q2 = (big, small) if i % 2 == 0 else (small, big)
        rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


def near_tangent_rows(rng, n):
    rows = []
    for i in range(n):
        q1, q2 = typical_pair(rng)
        rows.append((q1, q2, 1 + mpf(NEAR_TANGENT_OFFSETS[i % len(NEAR_TANGENT_OFFSETS)])))
    return rows


def perturbed(rng, q, eps):
    """q with every entry multiplied by 1 + eps·ξ, ξ uniform in [-1, 1], rounded to doubles."""
    return tuple(x * (1 + eps * (2 * rng.random() - 1)) for x in q)


def identical_rows(rng, n):
    rows = []
    for i in range(n):
        q1 = random_form(rng, typical_semi_axes(rng))
        q2 = q1 if i % 2 == 0 else perturbed(rng, q1, log_uniform(rng, 1e-15, 1e-8))
        rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


def shaped_semi_axes(rng, aspect):
    """A needle, platelet or triaxial ellipsoid of the given aspect ratio (as
    elongated_semi_axes), size log-uniform in [0.1, 10]."""
    kind = int(3 * rng.random())
    size = log_uniform(rng, 0.1, 10.0)
    if kind == 0:
        return [size, size / aspect, size / aspect]
    if kind == 1:
        return [size, size, size / aspect]
    return [size, size / float(mpf(aspect) ** rng.random()), size / aspect]


def turned(quat, axis, angle):
    """The unit quaternion quat ⊗ (cos(angle/2), sin(angle/2) axis), in doubles."""
    w1, x1, y1, z1 = (mpf(v) for v in quat)
    half = mpf(angle) / 2
    w2, (x2, y2, z2) = mp.cos(half), (mp.sin(half) * a for a in axis)
    return tuple(float(v) for v in (
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    ))


def nearly_identical_rows(rng, _n):
    rows = []
    for aspect in NEAR_ASPECTS:
        for delta in NEAR_PERTURBATIONS:
            for i in range(ROWS_PER_NEAR):
                axes, quat = shaped_semi_axes(rng, aspect), random_quaternion(rng)
                q1 = quadratic_form(axes, quat)
                if i % 2 == 0:
                    q2 = quadratic_form([a * (1 + delta * (2 * rng.random() - 1)) for a in axes], quat)
                else:
                    q2 = quadratic_form(axes, turned(quat, random_direction(rng), delta))
                rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


CATEGORIES = {
    "aspect_ratio": aspect_ratio_rows,
    "size_ratio": size_ratio_rows,
    "near_tangent": near_tangent_rows,
    "identical": identical_rows,
    "tiny_scale": lambda rng, n: typical_rows(rng, n, length_scale=1e-6),
    "huge_scale": lambda rng, n: typical_rows(rng, n, length_scale=1e6),
    "near_coincident": lambda rng, n: typical_rows(rng, n, mu2_range=(1e-24, 1e-4)),
    "nearly_identical": nearly_identical_rows,
}


def exactly_singular_form(rng, semi_axes, rank):
    """B Bᵀ with B the first `rank` columns of a random rotation times the semi-axes,
    rounded to SINGULAR_BITS bits at a common scale: integers times 2^(2e), sums of at
    most three products below 2^(2 SINGULAR_BITS + 2), so exact in doubles and exactly
    of rank `rank` (0: Q = 0)."""
    rot = rotation_matrix(random_quaternion(rng))
    cols = [[rot[i][k] * semi_axes[k] for i in range(3)] for k in range(rank)]
    if rank == 0:
        return (0.0,) * 6
    largest = max(abs(x) for col in cols for x in col)
    unit = 2.0 ** (math.frexp(largest)[1] - SINGULAR_BITS)
    cols = [[round(x / unit) * unit for x in col] for col in cols]
    return tuple(
        sum(col[i] * col[j] for col in cols)
        for i, j in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
    )


def semi_definite_rows(rng, n):
    rows = []
    for i in range(n):
        kind = i % 5
        singular = exactly_singular_form(rng, typical_semi_axes(rng), [2, 1, 0, 2, 1][kind])
        if kind < 3:
            axes = typical_semi_axes(rng) if (i // 5) % 2 == 0 else elongated_semi_axes(rng)
            other = random_form(rng, axes)
        else:
            other = exactly_singular_form(rng, typical_semi_axes(rng), 2)
        q1, q2 = (singular, other) if (i // 10) % 2 == 0 else (other, singular)
        rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


def huge_ratio_rows(rng, n):
    rows = []
    for i in range(n):
        ratio = log_uniform(rng, *HUGE_RATIO_RANGE)
        small = random_form(rng, typical_semi_axes(rng))
        big = random_form(rng, [ratio * a for a in typical_semi_axes(rng)])
        q1, q2 = (big, small) if i % 2 == 0 else (small, big)
        rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


DEGENERATE = {
    "semi_definite": semi_definite_rows,
    "huge_ratio": huge_ratio_rows,
}


# ----------------------------------------------------------------------------------
# Driver
# ----------------------------------------------------------------------------------

def reference_row(rng, q1, q2, mu2_target):
    """Choose r for the target μ², then compute the reference from the doubles written."""
    assert_positive_definite(q1)
    assert_positive_definite(q2)
    r = scaled_separation(rng, q1, q2, mu2_target)
    return r, q1, q2, contact(r, q1, q2)


def exact_contact(r, q1, q2):
    """tools/contact_exact.py's primary method, as a Contact."""
    return Contact(*contact_exact(r, q1, q2))


def degenerate_row(rng, q1, q2, mu2_target):
    """reference_row for the degenerate categories: forms that may be singular (the
    generators make them exactly so), solved by contact_exact."""
    r = scaled_separation(rng, q1, q2, mu2_target, exact_contact)
    return r, q1, q2, exact_contact(r, q1, q2)


def format_row(r, q1, q2, result, category=None):
    fields = [repr(x) for x in (*r, *q1, *q2)]
    fields += [mpmath.nstr(result.mu2, 30), mpmath.nstr(result.lam, 30)]
    if category is not None:
        fields.append(category)
    return ",".join(fields)


def write_csv(path, header, lines):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(",".join(header) + "\n" + "\n".join(lines) + "\n")


def pw85_spheroid(a, c, n):
    """Q of a spheroid (equatorial radius a, polar radius c, unit axis n), in doubles,
    with the same operations as pw85_spheroid: n nᵀ (c² - a²) + a² I."""
    a2 = a * a
    c2_minus_a2 = c * c - a2
    return (n[0] * n[0] * c2_minus_a2 + a2, n[0] * n[1] * c2_minus_a2, n[0] * n[2] * c2_minus_a2,
            n[1] * n[1] * c2_minus_a2 + a2, n[1] * n[2] * c2_minus_a2, n[2] * n[2] * c2_minus_a2 + a2)


def check_worked_example():
    """The pw85 manual example: μ² = 3.362706040638343, λ = 0.1668589553405904.

    Those values hold for Q built by pw85_spheroid, whose q1[5] is the double
    (0.1² - 100) + 100 = 0.010000000000005116, not 0.01.  Q1 has condition number
    1e4, and that relative change of 5e-13 in q1[5] moves μ² by 8.5e-14 relative:
    with q1[5] = 0.01 exactly, μ² = 3.36270604063862932 (13 agreeing digits).
    """
    c1, c2 = (-0.5, 0.4, -0.7), (0.2, -0.3, 0.4)
    r = tuple(b - a for a, b in zip(c1, c2))
    q1 = pw85_spheroid(10.0, 0.1, (0.0, 0.0, 1.0))
    q2 = pw85_spheroid(0.5, 5.0, (1.0, 0.0, 0.0))
    result = contact(r, q1, q2)
    print(f"worked example (pw85_spheroid, q1[5] = {q1[5]!r}): "
          f"mu2 = {mpmath.nstr(result.mu2, 20)}, lambda = {mpmath.nstr(result.lam, 20)}")
    for got, want in ((result.mu2, "3.362706040638343"), (result.lam, "0.1668589553405904")):
        assert agreeing_digits(got, mpf(want)) >= 15, f"worked example: {got} != {want}"
    literal = contact(r, (100.0, 0.0, 0.0, 100.0, 0.0, 0.01), q2)
    print(f"worked example (q1[5] = 0.01): mu2 = {mpmath.nstr(literal.mu2, 20)}, "
          f"lambda = {mpmath.nstr(literal.lam, 20)}")


def cross_check(rows):
    """Re-solve rows by the polynomial method at CHECK_DPS; μ² and λ* must agree.

    λ* is compared relative to min(λ*, 1 - λ*), its distance to the nearer end.
    """
    worst_mu2, worst_lam = math.inf, math.inf
    for r, q1, q2, result in rows:
        with mp.workdps(CHECK_DPS):
            other = contact_by_polynomial(r, q1, q2)
            mu2_digits = agreeing_digits(result.mu2, other.mu2)
            edge = min(other.lam, 1 - other.lam)
            lam_digits = agreeing_digits(result.lam / edge, other.lam / edge)
        assert min(mu2_digits, lam_digits) >= MIN_AGREEING_DIGITS, (
            f"cross-check: mu2 {result.mu2} vs {other.mu2}, lambda {result.lam} vs {other.lam}")
        worst_mu2, worst_lam = min(worst_mu2, mu2_digits), min(worst_lam, lam_digits)
    print(f"cross-check of {len(rows)} rows at dps {CHECK_DPS}: mu2 agrees to >= {worst_mu2:.1f} digits, "
          f"lambda to >= {worst_lam:.1f} digits relative to min(lambda, 1 - lambda)")


def golden_check(rows):
    """Re-solve degenerate rows by contact_golden; μ² must agree to MIN_AGREEING_DIGITS,
    λ* (relative to its distance to the nearer end) to MIN_GOLDEN_LAMBDA_DIGITS unless
    it is an end."""
    worst_mu2, worst_lam = math.inf, math.inf
    for r, q1, q2, result in rows:
        mu2, lam = contact_golden(r, q1, q2)
        mu2_digits = agreeing(result.mu2, mu2)
        assert mu2_digits >= MIN_AGREEING_DIGITS, f"golden check: mu2 {result.mu2} vs {mu2}"
        worst_mu2 = min(worst_mu2, mu2_digits)
        if 0 < result.lam < 1:
            with mp.workdps(CHECK_DPS):
                edge = min(result.lam, 1 - result.lam)
                lam_digits = agreeing(result.lam / edge, lam / edge)
            assert lam_digits >= MIN_GOLDEN_LAMBDA_DIGITS, f"golden check: lambda {result.lam} vs {lam}"
            worst_lam = min(worst_lam, lam_digits)
    print(f"golden-section check of {len(rows)} degenerate rows: mu2 agrees to >= {worst_mu2:.1f} digits, "
          f"lambda to >= {worst_lam:.1f} digits where it is not an end")


def spread_sample(rows):
    """N_CHECK_PER_GROUP rows evenly spread over rows."""
    return rows[:: len(rows) // N_CHECK_PER_GROUP][:N_CHECK_PER_GROUP]


def summarise(name, rows):
    """One line per category: count, μ² range, closest λ* to 0 or 1, worst iteration count."""
    mu2 = [row[3].mu2 for row in rows]
    edge = min(min(row[3].lam, 1 - row[3].lam) for row in rows)
    iterations = max(row[3].iterations for row in rows)
    line = (f"  {name:16s} {len(rows):5d} rows  mu2 in [{mpmath.nstr(min(mu2), 3)}, {mpmath.nstr(max(mu2), 3)}]"
            f"  min(lambda, 1-lambda) = {mpmath.nstr(edge, 3)}  max iterations = {iterations}")
    if name == "near_tangent":
        gaps = [abs(x - 1) for x in mu2]
        line += f"  |mu2-1| in [{mpmath.nstr(min(gaps), 3)}, {mpmath.nstr(max(gaps), 3)}]"
    print(line)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check-all", action="store_true",
                        help="cross-check every row, not a sample (about 1.5 minutes more)")
    parser.add_argument("--out", type=Path, default=OUT_DIR,
                        help="directory to write the CSV files to (default: tests/data); "
                             "CI writes elsewhere and compares with the committed files")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    mp.dps = DPS
    rng = random.Random(SEED)
    check_worked_example()

    typical = [reference_row(rng, *spec) for spec in typical_rows(rng, N_TYPICAL)]
    extreme = {name: [reference_row(rng, *spec) for spec in make(rng, N_PER_CATEGORY)]
               for name, make in CATEGORIES.items()}

    degenerate = {name: [degenerate_row(rng, *spec) for spec in make(rng, N_PER_CATEGORY)]
                  for name, make in DEGENERATE.items()}

    exact_identical = [row for row in extreme["identical"] if row[1] == row[2]]
    assert all(abs(row[3].lam - mpf(1) / 2) < mpf(10) ** (10 - DPS) for row in exact_identical)

    write_csv(args.out / "contact_typical.csv", HEADER, [format_row(*row) for row in typical])
    write_csv(args.out / "contact_extreme.csv", HEADER + ["category"],
              [format_row(*row, name) for name, rows in extreme.items() for row in rows])
    write_csv(args.out / "contact_degenerate.csv", HEADER + ["category"],
              [format_row(*row, name) for name, rows in degenerate.items() for row in rows])

    groups = [typical] + list(extreme.values())
    cross_check([row for rows in groups for row in (rows if args.check_all else spread_sample(rows))])
    golden_check([row for rows in degenerate.values()
                  for row in (rows if args.check_all else spread_sample(rows))])

    print("rows written:")
    summarise("typical", typical)
    for name, rows in [*extreme.items(), *degenerate.items()]:
        summarise(name, rows)
    print(f"done in {time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())

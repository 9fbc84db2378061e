#!/usr/bin/env python3
"""Reference data for the Perram–Wertheim contact function of two ellipses (2D).

An ellipse is {m in R² : (m - c)ᵀ Q⁻¹ (m - c) <= 1}, Q a symmetric 2×2 form stored as
[Q00, Q01, Q11].  For a pair with r = c2 - c1,

    μ² = max over λ in [0, 1] of f(λ) = λ(1-λ) rᵀ [(1-λ) Q1 + λ Q2]⁻¹ r.

Computed directly in 2D (no embedding), from exactly the doubles written, by two
methods that must agree on every row:

  primary    exact rational arithmetic (fractions.Fraction of the doubles) for
             h(λ) = λ(1-λ) rᵀ adj(Q(λ)) r (degree 3) and D(λ) = det Q(λ) (degree 2),
             common factors λ and 1-λ divided out exactly (semi-definite forms); f = h/D
             is concave, and λ* is where h'D - hD' changes sign, found by bisection of
             ln(λ/(1-λ)) on its exact sign to DPS digits (the pair mirrored so that
             λ* ≤ 1/2), or the end where f is largest when it does not change sign;
  check      a safeguarded Newton iteration on g = -f' with the 2×2 inverse at CHECK_DPS
             digits plus the decimal span of the inputs (make_contact_reference.py's
             method), where λ* is inside (0, 1) at DPS digits.

μ² must agree to MIN_AGREEING_DIGITS digits, λ* to as many relative to min(λ*, 1-λ*).

Output (header r0,r1,q1_0,q1_1,q1_2,q2_0,q2_1,q2_2,mu2,lambda; the CSV `pack contact`
reads in 2D):

tests/data/contact_plane_typical.csv   N_TYPICAL rows: semi-axes log-uniform in
    [0.1, 10], angles uniform, random direction of r, μ² log-uniform in [1e-2, 1e2].

tests/data/contact_plane_extreme.csv   with a final column `category`:
    aspect_ratio     aspect ratios A log-uniform in [10, 1e4] (a quarter exactly 1e4).
    size_ratio       a typical ellipse and one scaled by ρ log-uniform in [1e3, 1e6].
    huge_ratio       the same with ρ log-uniform in [1e6, 1e150].
    near_tangent     typical pairs with μ² = 1, 1 ± 1e-14, 1 ± 1e-12, 1 ± 1e-10 before
                     r is rounded to doubles.
    identical        Q2 == Q1 (half the rows) or every entry perturbed by up to ε,
                     ε log-uniform in [1e-15, 1e-8].
    nearly_identical for each aspect ratio in NEAR_ASPECTS and perturbation δ in
                     NEAR_PERTURBATIONS, ROWS_PER_NEAR rows: semi-axes times 1 + δξ, or
                     the angle turned by δ, alternately.
    tiny_scale       typical pairs with all lengths times 1e-6.
    huge_scale       typical pairs with all lengths times 1e6.
    near_coincident  typical pairs with μ² log-uniform in [1e-24, 1e-4].
    semi_definite    a segment (rank 1: b bᵀ with b rounded to SINGULAR_BITS bits, so
                     exactly singular in doubles) or a point (Q = 0) against a typical or
                     elongated ellipse, in either order, and one row in four two crossing
                     segments.

Deterministic: random numbers come only from random.Random(SEED).random().
Run from the repository root:  python3 tools/make_contact_reference_2d.py [--out DIR]
"""

import argparse
import math
import random
import sys
import time
from fractions import Fraction
from pathlib import Path

import mpmath
from mpmath import mp, mpf

from make_contact_reference import agreeing_digits, log_uniform, NEAR_TANGENT_OFFSETS

SEED = 20261126
DPS = 60
CHECK_DPS = 80
N_TYPICAL = 1000
N_PER_CATEGORY = 200
MIN_AGREEING_DIGITS = 30
MAX_ITERATIONS = 2000  # bisection alone reaches λ* ~ 1e-150 in ~500 steps
SINGULAR_BITS = 20
NEAR_ASPECTS = [1.0, 3.0, 10.0, 100.0, 1e3, 1e4]
NEAR_PERTURBATIONS = [1e-16, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2]
ROWS_PER_NEAR = 4
OUT_DIR = Path(__file__).resolve().parent.parent / "tests" / "data"
HEADER = ["r0", "r1", "q1_0", "q1_1", "q1_2", "q2_0", "q2_1", "q2_2", "mu2", "lambda"]


# ----------------------------------------------------------------------------------
# Random inputs (doubles)
# ----------------------------------------------------------------------------------

def random_angle(rng):
    return float(mp.pi * (2 * mpf(rng.random()) - 1))


def ellipse_form(a1, a2, theta):
    """[Q00, Q01, Q11] of R diag(a1², a2²) Rᵀ, R the rotation by theta, in doubles."""
    c, s = float(mp.cos(theta)), float(mp.sin(theta))
    p, q = a1 * a1, a2 * a2
    return (p * c * c + q * s * s, (p - q) * c * s, p * s * s + q * c * c)


def typical_form(rng, scale=1.0):
    a1, a2 = (scale * log_uniform(rng, 0.1, 10.0) for _ in range(2))
    return ellipse_form(a1, a2, random_angle(rng))


def elongated_form(rng, aspect=None):
    aspect = aspect or (1e4 if rng.random() < 0.25 else log_uniform(rng, 10.0, 1e4))
    size = log_uniform(rng, 0.1, 10.0)
    return ellipse_form(size, size / aspect, random_angle(rng))


def segment_form(rng):
    """b bᵀ, b of length in [0.1, 10] rounded to SINGULAR_BITS bits: exact, rank 1."""
    length, theta = log_uniform(rng, 0.1, 10.0), random_angle(rng)
    b = [length * float(mp.cos(theta)), length * float(mp.sin(theta))]
    unit = 2.0 ** (math.frexp(max(map(abs, b)))[1] - SINGULAR_BITS)
    b = [round(x / unit) * unit for x in b]
    return (b[0] * b[0], b[0] * b[1], b[1] * b[1])


# ----------------------------------------------------------------------------------
# Exact polynomials (primary method)
# ----------------------------------------------------------------------------------

def pmul(p, q):
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def padd(p, q, c=1):
    n = max(len(p), len(q))
    return [(p[k] if k < len(p) else 0) + c * (q[k] if k < len(q) else 0) for k in range(n)]


def peval(p, x):
    acc = 0
    for a in reversed(p):
        acc = acc * x + a
    return acc


def divide_by_lambda(p):
    assert p[0] == 0
    return p[1:]


def divide_by_one_minus_lambda(p):
    """p / (1 - λ) for p(1) = 0, by synthetic division."""
    assert sum(p) == 0
    # p = (1 - λ) s  <=>  p_k = s_k - s_{k-1}
    s, acc = [], Fraction(0)
    for c in p[:-1]:
        acc += c
        s.append(acc)
    return s


def pair_polynomials(r, q1, q2):
    """h and D with the common factors λ and 1-λ divided out, exact."""
    r = [Fraction(x) for x in r]
    a, b = [Fraction(x) for x in q1], [Fraction(x) for x in q2]
    p, o, s = ([a[k], b[k] - a[k]] for k in range(3))
    det = padd(pmul(p, s), pmul(o, o), -1)
    quad = padd(padd([r[0] * r[0] * c for c in s], [2 * r[0] * r[1] * c for c in o], -1),
                [r[1] * r[1] * c for c in p])
    h = pmul([Fraction(0), Fraction(1), Fraction(-1)], quad)
    assert any(det), "Q(λ) singular for every λ (common null direction)"
    while h and det and h[0] == 0 and det[0] == 0:
        h, det = divide_by_lambda(h), divide_by_lambda(det)
    while h and det and sum(h) == 0 and sum(det) == 0:
        h, det = divide_by_one_minus_lambda(h), divide_by_one_minus_lambda(det)
    return h, det


U_MAX = 2000
BISECTION_DIGITS = DPS + 5
COARSE_STEPS = 64
NEWTON_STEPS = 4


def bits(c):
    """About log2 of a positive Fraction."""
    return c.numerator.bit_length() - c.denominator.bit_length()


def to_mpf(c):
    return mpf(c.numerator) / c.denominator


def to_fraction(x):
    """The exact value of an mpf."""
    man, exp = int(x.man), int(x.exp)
    return Fraction(man * 2 ** exp) if exp >= 0 else Fraction(man, 2 ** -exp)


def slope_numerator(h, det):
    """h'D - hD', whose sign is that of f' inside (0, 1)."""
    dh = [k * c for k, c in enumerate(h)][1:]
    dd = [k * c for k, c in enumerate(det)][1:]
    return padd(pmul(dh, det), pmul(h, dd), -1)


def lower_root(h, det):
    """(μ², λ*) for a pair whose f' ≤ 0 at 1/2: λ* in [0, 1/2]; λ* = 0 if f' < 0
    throughout (down to λ = e^-U_MAX).

    λ* is bracketed by COARSE_STEPS bisections of u = ln(λ/(1-λ)) in [-U_MAX, 0] (λ keeps
    its relative precision however close to 0 it is) and polished by Newton's method on
    h'D - hD', both in mp at DPS digits plus the decimal span of its coefficients; the
    root is then proved to DPS - 2 digits by the exact signs of h'D - hD' on either side
    (else the exact bisection of `exact_root` decides).
    """
    n = slope_numerator(h, det)
    if not peval(n, to_fraction(lam_of(mpf(-U_MAX)))) > 0:
        assert peval(det, Fraction(0)) != 0, "f unbounded at an end"
        return to_mpf(peval(h, Fraction(0)) / peval(det, Fraction(0))), mpf(0)
    sizes = [abs(c) for c in n if c != 0]
    span = int(0.302 * (max(map(bits, sizes)) - min(map(bits, sizes))))
    with mp.workdps(DPS + span + 20):
        c = [to_mpf(x) for x in n]
        dc = [k * x for k, x in enumerate(c)][1:]
        lo, hi = mpf(-U_MAX), mpf(0)
        for _ in range(COARSE_STEPS):
            mid = (lo + hi) / 2
            if peval(c, lam_of(mid)) > 0:
                lo = mid
            else:
                hi = mid
        lam = lam_of((lo + hi) / 2)
        for _ in range(NEWTON_STEPS):
            lam -= peval(c, lam) / peval(dc, lam)
        delta = lam * mpf(10) ** (2 - DPS)
        below, above = to_fraction(lam - delta), to_fraction(lam + delta)
    if not (peval(n, below) > 0 and peval(n, above) <= 0):
        return exact_root(h, det, n)
    exact = to_fraction(lam)
    return to_mpf(peval(h, exact) / peval(det, exact)), to_mpf(exact)


def lam_of(u):
    return mp.exp(u) / (1 + mp.exp(u))


def exact_root(h, det, n):
    """λ* by bisection of u on the exact sign of h'D - hD' alone (slow, and sure)."""
    sign = lambda u: peval(n, to_fraction(lam_of(u))) > 0
    with mp.workdps(BISECTION_DIGITS + 10):
        lo, hi = mpf(-U_MAX), mpf(0)
        while hi - lo > mpf(10) ** (-BISECTION_DIGITS) * max(1, abs(lo)):
            mid = (lo + hi) / 2
            if sign(mid):
                lo = mid
            else:
                hi = mid
        lam = to_fraction(lam_of((lo + hi) / 2))
        return to_mpf(peval(h, lam) / peval(det, lam)), to_mpf(lam)


def contact_exact(r, q1, q2):
    """(μ², λ*) at mp precision from the exact polynomials of the pair: the pair is
    mirrored (λ -> 1-λ, the forms swapped) when f' > 0 at 1/2, so that λ* ≤ 1/2."""
    h, det = pair_polynomials(r, q1, q2)
    if peval(slope_numerator(h, det), Fraction(1, 2)) > 0:
        mu2, lam = lower_root(*pair_polynomials(r, q2, q1))
        return mu2, 1 - lam
    return lower_root(h, det)


# ----------------------------------------------------------------------------------
# Newton on g with the 2×2 inverse (independent check)
# ----------------------------------------------------------------------------------

def contact_newton(r, q1, q2):
    r, q1, q2 = ([mpf(x) for x in v] for v in (r, q1, q2))
    dq = [b - a for a, b in zip(q1, q2)]

    def solve(q, x):
        det = q[0] * q[2] - q[1] * q[1]
        return [(q[2] * x[0] - q[1] * x[1]) / det, (q[0] * x[1] - q[1] * x[0]) / det]

    def mul(q, x):
        return [q[0] * x[0] + q[1] * x[1], q[1] * x[0] + q[2] * x[1]]

    def dot(x, y):
        return x[0] * y[0] + x[1] * y[1]

    def at(lam):
        q = [a + lam * d for a, d in zip(q1, dq)]
        s = solve(q, r)
        u = mul(dq, s)
        v = solve(q, u)
        rs, su, uv = dot(r, s), dot(s, u), dot(u, v)
        g = (2 * lam - 1) * rs + lam * (1 - lam) * su
        slope = 2 * rs + 2 * (1 - 2 * lam) * su - 2 * lam * (1 - lam) * uv
        return g, slope, lam * (1 - lam) * rs

    # Relative to CHECK_DPS, not mp.dps: the extra digits only carry Q1 beside λ(Q2 - Q1).
    tol = mpf(10) ** (15 - CHECK_DPS)
    lo, hi = mpf(0), mpf(1)
    lam = last_step = mpf(1) / 2
    for _ in range(MAX_ITERATIONS):
        g, slope, _ = at(lam)
        if g < 0:
            lo = lam
        else:
            hi = lam
        step = -g / slope if slope > 0 else None
        if g == 0 or (step is not None and abs(step) <= tol * min(lam, 1 - lam)):
            lam += step or 0
            return at(lam)[2], lam
        if step is None or not lo < lam + step < hi or abs(2 * g) > abs(last_step * slope):
            step = (lo + hi) / 2 - lam
        lam += step
        last_step = step
    raise AssertionError(f"Newton: no convergence for r={r} q1={q1} q2={q2}")


# ----------------------------------------------------------------------------------
# Rows
# ----------------------------------------------------------------------------------

def random_direction(rng):
    phi = 2 * mp.pi * rng.random()
    return (mp.cos(phi), mp.sin(phi))


def reference_row(rng, q1, q2, mu2_target):
    """r for the target μ², rounded to doubles, and the reference from those doubles."""
    direction = random_direction(rng)
    unit = contact_exact([float(x) for x in direction], q1, q2)[0]
    # μ² of the rounded unit direction; the scale error is far below the target's spread.
    scale = mp.sqrt(mpf(mu2_target) / unit)
    r = tuple(float(scale * d) for d in direction)
    return r, q1, q2, contact_exact(r, q1, q2)


def typical_rows(rng, n, scale=1.0, mu2_range=(1e-2, 1e2)):
    return [(typical_form(rng, scale), typical_form(rng, scale), log_uniform(rng, *mu2_range))
            for _ in range(n)]


def ratio_rows(rng, n, lo, hi):
    rows = []
    for i in range(n):
        small, big = typical_form(rng), typical_form(rng, log_uniform(rng, lo, hi))
        q1, q2 = (big, small) if i % 2 == 0 else (small, big)
        rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


def near_tangent_rows(rng, n):
    return [(typical_form(rng), typical_form(rng), 1 + mpf(NEAR_TANGENT_OFFSETS[i % len(NEAR_TANGENT_OFFSETS)]))
            for i in range(n)]


def identical_rows(rng, n):
    rows = []
    for i in range(n):
        q1 = typical_form(rng)
        eps = log_uniform(rng, 1e-15, 1e-8)
        q2 = q1 if i % 2 == 0 else tuple(x * (1 + eps * (2 * rng.random() - 1)) for x in q1)
        rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


def nearly_identical_rows(rng, _n):
    rows = []
    for aspect in NEAR_ASPECTS:
        for delta in NEAR_PERTURBATIONS:
            for i in range(ROWS_PER_NEAR):
                size, theta = log_uniform(rng, 0.1, 10.0), random_angle(rng)
                a1, a2 = size, size / aspect
                q1 = ellipse_form(a1, a2, theta)
                if i % 2 == 0:
                    q2 = ellipse_form(a1 * (1 + delta * (2 * rng.random() - 1)),
                                      a2 * (1 + delta * (2 * rng.random() - 1)), theta)
                else:
                    q2 = ellipse_form(a1, a2, float(mpf(theta) + delta))
                rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


def semi_definite_rows(rng, n):
    rows = []
    for i in range(n):
        kind = i % 4
        if kind == 3:
            q1, q2 = segment_form(rng), segment_form(rng)
        else:
            singular = segment_form(rng) if kind < 2 else (0.0, 0.0, 0.0)
            other = typical_form(rng) if (i // 4) % 2 == 0 else elongated_form(rng)
            q1, q2 = (singular, other) if (i // 8) % 2 == 0 else (other, singular)
        rows.append((q1, q2, log_uniform(rng, 1e-2, 1e2)))
    return rows


CATEGORIES = {
    "aspect_ratio": lambda rng, n: [(elongated_form(rng), elongated_form(rng), log_uniform(rng, 1e-2, 1e2))
                                    for _ in range(n)],
    "size_ratio": lambda rng, n: ratio_rows(rng, n, 1e3, 1e6),
    "huge_ratio": lambda rng, n: ratio_rows(rng, n, 1e6, 1e150),
    "near_tangent": near_tangent_rows,
    "identical": identical_rows,
    "nearly_identical": nearly_identical_rows,
    "tiny_scale": lambda rng, n: typical_rows(rng, n, scale=1e-6),
    "huge_scale": lambda rng, n: typical_rows(rng, n, scale=1e6),
    "near_coincident": lambda rng, n: typical_rows(rng, n, mu2_range=(1e-24, 1e-4)),
    "semi_definite": semi_definite_rows,
}


def check(rows):
    """Every row re-solved by Newton at CHECK_DPS where λ* is inside (0, 1)."""
    worst_mu2, worst_lam, checked = math.inf, math.inf, 0
    for r, q1, q2, (mu2, lam) in rows:
        if not 0 < lam < 1:
            continue
        # Q(λ) = Q1 + λ(Q2 - Q1) must keep Q1's digits beside λ(Q2 - Q1): the span of
        # the inputs' magnitudes is added to the working precision.
        sizes = [abs(x) for x in (*r, *q1, *q2) if x != 0]
        span = int(math.log10(max(sizes) / min(sizes)))
        with mp.workdps(CHECK_DPS + span):
            mu2_n, lam_n = contact_newton(r, q1, q2)
            edge = min(lam_n, 1 - lam_n)
            mu2_digits = agreeing_digits(mu2, mu2_n)
            lam_digits = agreeing_digits(lam / edge, lam_n / edge)
        assert min(mu2_digits, lam_digits) >= MIN_AGREEING_DIGITS, (
            f"check: mu2 {mu2} vs {mu2_n}, lambda {lam} vs {lam_n} (r={r} q1={q1} q2={q2})")
        worst_mu2, worst_lam = min(worst_mu2, mu2_digits), min(worst_lam, lam_digits)
        checked += 1
    print(f"  Newton check of {checked} of {len(rows)} rows: mu2 >= {worst_mu2:.1f} digits, "
          f"lambda >= {worst_lam:.1f} digits relative to min(lambda, 1 - lambda)")


def format_row(r, q1, q2, result, category=None):
    fields = [repr(x) for x in (*r, *q1, *q2)]
    fields += [mpmath.nstr(result[0], 30), mpmath.nstr(result[1], 30)]
    if category is not None:
        fields.append(category)
    return ",".join(fields)


def write_csv(path, header, lines):
    path.write_text(",".join(header) + "\n" + "\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=OUT_DIR,
                        help="directory to write the CSV files to (default: tests/data)")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    mp.dps = DPS
    rng = random.Random(SEED)
    typical = [reference_row(rng, *spec) for spec in typical_rows(rng, N_TYPICAL)]
    extreme = {name: [reference_row(rng, *spec) for spec in make(rng, N_PER_CATEGORY)]
               for name, make in CATEGORIES.items()}
    assert all(abs(row[3][1] - mpf(1) / 2) < mpf(10) ** (10 - DPS)
               for row in extreme["identical"] if row[1] == row[2])
    write_csv(args.out / "contact_plane_typical.csv", HEADER, [format_row(*row) for row in typical])
    write_csv(args.out / "contact_plane_extreme.csv", HEADER + ["category"],
              [format_row(*row, name) for name, rows in extreme.items() for row in rows])
    print("typical:")
    check(typical)
    for name, rows in extreme.items():
        mu2 = [row[3][0] for row in rows]
        ends = sum(1 for row in rows if not 0 < row[3][1] < 1)
        print(f"{name}: {len(rows)} rows, mu2 in [{mpmath.nstr(min(mu2), 3)}, {mpmath.nstr(max(mu2), 3)}], "
              f"{ends} with lambda at an end")
        check(rows)
    print(f"done in {time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The contact function of two forms that may be singular or of sizes far apart, for
the degenerate reference rows of make_contact_reference.py.

Primary method (contact_exact): with Q(λ) = (1-λ) Q1 + λ Q2, the polynomials
h(λ) = λ(1-λ) rᵀ adj(Q(λ)) r and D(λ) = det Q(λ) are expanded with exact rational
coefficients (fractions.Fraction, from the exact doubles), so f = h / D exactly.  If
f'(1/2) > 0 the maximiser lies above 1/2 and the pencil is mirrored (λ = 1 - u), so
that the variable u = distance to the nearer end keeps its relative precision however
close λ* is to 1.  The common factor u^m of h and D (m > 0 when the form at that end
is singular) is divided out exactly; f then has a finite limit at u = 0, and if f
does not rise from there (the first non-zero coefficient of P = h'D - hD' is negative)
the maximum is that limit.  Otherwise λ* is the root of P in (0, 1/2], bracketed in
log u, then found by Newton's method with bisection at PRIMARY_DPS digits.

Check (contact_golden): f(λ) = λ(1-λ) rᵀ adj(Q) r / det Q evaluated directly at
CHECK_DPS digits, maximised by golden-section search in log u on each half (u = λ and
u = 1 - λ down to SMALLEST_U), the larger of the two kept.  det Q(u) cancels to
u^(3 - rank) of its terms at a singular end, 320 digits at u = SMALLEST_U = 1e-160 for
a needle, which leaves 80; the size ratios (up to 1e150) put λ* within about 1e-150 of
an end, above SMALLEST_U.  It shares no code with the
primary method beyond the adjugate formula.
"""

from fractions import Fraction
import math

from mpmath import mp, mpf

PRIMARY_DPS = 80
CHECK_DPS = 400
SMALLEST_U = mpf("1e-160")
GOLDEN_STEPS = 120
MAX_NEWTON = 400


def to_fraction(x):
    """A double or an mpf, exactly."""
    if isinstance(x, float):
        return Fraction(x)
    x = mpf(x)
    man, exp = x.man_exp  # the magnitude's
    value = Fraction(int(man)) * Fraction(2) ** int(exp)
    return -value if x < 0 else value


def p_add(p, q):
    n = max(len(p), len(q))
    return [(p[k] if k < len(p) else 0) + (q[k] if k < len(q) else 0) for k in range(n)]


def p_mul(p, q):
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def p_scale(p, c):
    return [c * a for a in p]


def p_deriv(p):
    return [k * p[k] for k in range(1, len(p))] or [Fraction(0)]


def p_eval(p, x):
    acc = 0
    for a in reversed(p):
        acc = acc * x + a
    return acc


def p_mirror(p):
    """Coefficients of p(1 - u) from those of p(λ)."""
    out = [Fraction(0)]
    for a in reversed(p):
        out = p_add(p_mul(out, [Fraction(1), Fraction(-1)]), [a])
    return out


def lowest(p):
    """Index of the first non-zero coefficient (len(p) if none)."""
    return next((k for k, a in enumerate(p) if a != 0), len(p))


def pencil_polynomials(r, q1, q2):
    """h(λ) and D(λ) with exact rational coefficients (lowest degree first)."""
    r = [to_fraction(x) for x in r]
    a, b, c, d, e, f = ([to_fraction(x), to_fraction(y) - to_fraction(x)] for x, y in zip(q1, q2))

    def minor(x, y, z, w):
        return p_add(p_mul(x, y), p_scale(p_mul(z, w), -1))

    adj = (minor(d, f, e, e), minor(c, e, b, f), minor(b, e, c, d),
           minor(a, f, c, c), minor(b, c, a, e), minor(a, d, b, b))
    det = p_add(p_add(p_mul(a, adj[0]), p_mul(b, adj[1])), p_mul(c, adj[2]))
    weights = (r[0] * r[0], 2 * r[0] * r[1], 2 * r[0] * r[2], r[1] * r[1], 2 * r[1] * r[2], r[2] * r[2])
    quad = [Fraction(0)]
    for w, p in zip(weights, adj):
        quad = p_add(quad, p_scale(p, w))
    h = p_mul([Fraction(0), Fraction(1), Fraction(-1)], quad)
    return h, det


def to_mp(p):
    return [mpf(a.numerator) / a.denominator for a in p]


def root_of(poly):
    """The root in (0, 1/2] of a polynomial (mpf coefficients) positive just above 0 and
    not positive at 1/2: bracketed in log u, then Newton with bisection."""
    dpoly = [k * poly[k] for k in range(1, len(poly))]
    hi = mpf(1) / 2
    if p_eval(poly, hi) == 0:
        return hi, 0
    lo = hi
    while p_eval(poly, lo) <= 0:
        hi, lo = lo, lo * mpf(2) ** -64
    iterations = 0
    while hi > 2 * lo:
        iterations += 1
        mid = mp.sqrt(lo * hi)
        if p_eval(poly, mid) > 0:
            lo = mid
        else:
            hi = mid
    tol = mpf(10) ** (15 - mp.dps)
    x = (lo + hi) / 2
    for _ in range(MAX_NEWTON):
        iterations += 1
        value = p_eval(poly, x)
        if value == 0:
            return x, iterations
        if value > 0:
            lo = x
        else:
            hi = x
        slope = p_eval(dpoly, x)
        nx = x - value / slope if slope != 0 else None
        if nx is None or not lo < nx < hi:
            nx = (lo + hi) / 2
        if abs(nx - x) <= tol * x:
            return nx, iterations
        x = nx
    raise AssertionError("no convergence of the root of P")


def contact_exact(r, q1, q2):
    """(μ², λ*, iterations) by the primary method (module docstring)."""
    h, det = pencil_polynomials(r, q1, q2)
    slope_at_half = p_eval(p_add(p_mul(p_deriv(h), det), p_scale(p_mul(h, p_deriv(det)), -1)),
                           Fraction(1, 2))
    mirrored = slope_at_half > 0
    if mirrored:
        h, det = p_mirror(h), p_mirror(det)
    m = lowest(det)
    assert m < len(det), "det Q(λ) vanishes identically: a common null direction"
    assert lowest(h) >= m, "f is unbounded at an end"
    h, det = h[m:] or [Fraction(0)], det[m:]
    poly = p_add(p_mul(p_deriv(h), det), p_scale(p_mul(h, p_deriv(det)), -1))
    first = lowest(poly)
    with mp.workdps(PRIMARY_DPS):
        if lowest(h) == 0 and (first == len(poly) or poly[first] < 0):
            u, mu2, iterations = mpf(0), mpf(h[0].numerator) / h[0].denominator, 0
            mu2 /= mpf(det[0].numerator) / det[0].denominator
        else:
            u, iterations = root_of(to_mp(poly))
            mu2 = p_eval(to_mp(h), u) / p_eval(to_mp(det), u)
        lam = 1 - u if mirrored else u
        return +mu2, +lam, iterations


def contact_golden(r, q1, q2):
    """(μ², λ*) by the check method (module docstring), at CHECK_DPS digits."""
    with mp.workdps(CHECK_DPS):
        r = [mpf(x) for x in r]
        q1, q2 = [mpf(x) for x in q1], [mpf(x) for x in q2]

        def f(lam, one_minus):
            q = [one_minus * x + lam * y for x, y in zip(q1, q2)]
            a, b, c, d, e, g = q
            adj = (d * g - e * e, c * e - b * g, b * e - c * d, a * g - c * c, b * c - a * e, a * d - b * b)
            det = a * adj[0] + b * adj[1] + c * adj[2]
            x = (adj[0] * r[0] + adj[1] * r[1] + adj[2] * r[2],
                 adj[1] * r[0] + adj[3] * r[1] + adj[4] * r[2],
                 adj[2] * r[0] + adj[4] * r[1] + adj[5] * r[2])
            return lam * one_minus * (r[0] * x[0] + r[1] * x[1] + r[2] * x[2]) / det

        best = None
        for upper in (False, True):
            def value(v):
                u = mp.exp(v)
                return f(1 - u, u) if upper else f(u, 1 - u)
            lo, hi = mp.log(SMALLEST_U), mp.log(mpf(1) / 2)
            g = (mp.sqrt(5) - 1) / 2
            x, y = hi - g * (hi - lo), lo + g * (hi - lo)
            fx, fy = value(x), value(y)
            for _ in range(GOLDEN_STEPS):
                if fx < fy:
                    lo, x, fx = x, y, fy
                    y = lo + g * (hi - lo)
                    fy = value(y)
                else:
                    hi, y, fy = y, x, fx
                    x = hi - g * (hi - lo)
                    fx = value(x)
            v = (lo + hi) / 2
            candidate = (value(v), 1 - mp.exp(v) if upper else mp.exp(v))
            if best is None or candidate[0] > best[0]:
                best = candidate
        return best


def agreeing(x, y):
    """-log10 of the relative difference (inf if equal)."""
    if x == y:
        return math.inf
    return float(-mp.log10(abs(x - y) / max(abs(x), abs(y))))

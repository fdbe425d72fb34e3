"""Small relative-error minimax polynomial fitter used for pf_erfc / pf_erf.

fit(f, a, b, deg) returns coefficients c[0..deg] of p(v) = sum c[k] v^k that
minimise max |p(v)/f(v) - 1| on [a, b]. Method: Lawson's iteratively reweighted
least squares on a Chebyshev-clustered grid (linear convergence to the minimax
solution), solved in mpmath at 40 digits so the normal equations stay exact
enough. Then coefficients are rounded one at a time to the target precision,
refitting the remaining ones after each rounding, so the rounding of the
leading coefficients is compensated by the others.
"""
import mpmath as mp
import struct

mp.mp.dps = 40


def to_float32(x):
    return mp.mpf(struct.unpack('f', struct.pack('f', float(x)))[0])


def to_float64(x):
    return mp.mpf(float(x))


def grid(a, b, n):
    # Chebyshev extrema mapped to [a, b]: dense near the ends where minimax errors peak
    return [a + (b - a) * (1 - mp.cos(mp.pi * i / (n - 1))) / 2 for i in range(n)]


def _solve_ls(rows, rhs, w):
    n = len(rows[0])
    A = mp.matrix(n, n)
    y = mp.matrix(n, 1)
    for r, t, wi in zip(rows, rhs, w):
        for i in range(n):
            y[i] += wi * r[i] * t
            for j in range(i, n):
                A[i, j] += wi * r[i] * r[j]
    for i in range(n):
        for j in range(i):
            A[i, j] = A[j, i]
    return mp.lu_solve(A, y)


def fit(f, a, b, deg, fixed=None, npts=300, iters=60, powers=None):
    """fixed: dict k -> value of coefficients already chosen (not refitted).
    powers: list of monomial exponents (default 0..deg)."""
    if powers is None:
        powers = list(range(deg + 1))
    fixed = fixed or {}
    free = [k for k in powers if k not in fixed]
    vs = grid(mp.mpf(a), mp.mpf(b), npts)
    fv = [f(v) for v in vs]
    # relative error: minimise (p - f)/f, i.e. rows scaled by 1/f
    rows = [[v ** k / fi for k in free] for v, fi in zip(vs, fv)]
    rhs = [1 - sum(c * v ** k for k, c in fixed.items()) / fi for v, fi in zip(vs, fv)]
    w = [mp.mpf(1)] * npts
    best = None
    for _ in range(iters):
        sol = _solve_ls(rows, rhs, w)
        err = [sum(sol[i] * r[i] for i in range(len(free))) - t for r, t in zip(rows, rhs)]
        m = max(abs(e) for e in err)
        if best is None or m < best[0]:
            best = (m, sol)
        s = sum(wi * abs(e) for wi, e in zip(w, err))
        w = [wi * abs(e) / s for wi, e in zip(w, err)]
    c = dict(fixed)
    for i, k in enumerate(free):
        c[k] = best[1][i]
    return c, best[0]


def fit_rounded(f, a, b, deg, rnd=to_float32, npts=300, iters=60, powers=None):
    """Round coefficients to the working precision from the highest power down?
    No: from c[0] up, since the low-order terms dominate the value on small |v|;
    each remaining coefficient is refitted after every rounding."""
    if powers is None:
        powers = list(range(deg + 1))
    fixed = {}
    for k in powers:
        c, e = fit(f, a, b, deg, fixed=fixed, npts=npts, iters=iters, powers=powers)
        fixed[k] = rnd(c[k])
    return fixed, max_rel_err(f, fixed, a, b)


def max_rel_err(f, c, a, b, n=2000):
    m = mp.mpf(0)
    at = a
    for v in grid(mp.mpf(a), mp.mpf(b), n):
        p = sum(ck * v ** k for k, ck in c.items())
        e = abs(p / f(v) - 1)
        if e > m:
            m, at = e, v
    return m, at

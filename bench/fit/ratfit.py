"""ratfit.py - near-minimax rational fits with relative error, for prefilter's fitted kernels.

Fits r(x) = P(x)/Q(x), deg P = m, deg Q = n, Q(0) = 1, to a target f on [a, b] minimizing
max |r/f - 1|. Method: Lawson's iteratively reweighted linearized least squares (the Loeb
linearization P - f Q, weighted by 1/(f Q_prev)), on Chebyshev-distributed points, in mpmath
so the fit itself is not limited by double precision. Reproducible: no randomness.

Used by fit_smith.py; run with python3 (needs only mpmath)."""
from mpmath import mp, mpf, matrix, lu_solve, cos, pi

def cheb_points(a, b, count):
    return [(a + b) / 2 + (b - a) / 2 * cos(pi * (k + mpf(0.5)) / count) for k in range(count)]

def horner(c, x):
    r = mpf(0)
    for v in reversed(c):
        r = r * x + v
    return r

def fit(f, a, b, m, n, count=400, iters=60, xs=None, extra=()):
    """extra: additional (x, target) pairs fitted with the same relative weight, e.g. a
    second target at an end point that the fit must also approach."""
    a, b = mpf(a), mpf(b)
    if xs is None:
        xs = cheb_points(a, b, count) + [a, b]
    fs = [f(x) for x in xs]
    xs = xs + [mpf(x) for x, _ in extra]
    fs = fs + [mpf(t) for _, t in extra]
    w = [mpf(1)] * len(xs)
    qprev = [mpf(1)] * len(xs)
    best = None
    for it in range(iters):
        # unknowns: p0..pm, q1..qn ; residual_i = (P(x_i) - f_i Q(x_i)) / (f_i Qprev_i)
        nu = m + 1 + n
        A = matrix(nu, nu)
        rhs = matrix(nu, 1)
        for x, fx, wi, qp in zip(xs, fs, w, qprev):
            scale = 1 / (fx * qp)
            row = [x ** j * scale for j in range(m + 1)] + [-fx * x ** j * scale for j in range(1, n + 1)]
            t = fx * scale  # target: P - f(Q-1) = f
            for i in range(nu):
                ri = wi * row[i]
                rhs[i] += ri * t
                for j in range(nu):
                    A[i, j] += ri * row[j]
        sol = lu_solve(A, rhs)
        p = [sol[i] for i in range(m + 1)]
        q = [mpf(1)] + [sol[m + 1 + i] for i in range(n)]
        errs = [horner(p, x) / horner(q, x) / fx - 1 for x, fx in zip(xs, fs)]
        emax = max(abs(e) for e in errs)
        if best is None or emax < best[0]:
            best = (emax, p, q)
        qprev = [horner(q, x) for x in xs]
        s = sum(wi * abs(e) for wi, e in zip(w, errs))
        w = [wi * abs(e) / s * len(xs) for wi, e in zip(w, errs)]
    return best

def max_rel_dense(f, p, q, a, b, count=4000):
    a, b = mpf(a), mpf(b)
    worst = (mpf(0), a)
    for k in range(count + 1):
        x = a + (b - a) * k / count
        fx = f(x)
        if fx == 0:
            continue
        e = abs(horner(p, x) / horner(q, x) / fx - 1)
        if e > worst[0]:
            worst = (e, x)
    return worst

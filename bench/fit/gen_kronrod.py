#!/usr/bin/env python3
"""gen_kronrod.py - compute Gauss-Legendre / Kronrod-extension nodes and weights for
tests/reference/pf_oracle.h from first principles (no published table is used).

usage: python3 bench/fit/gen_kronrod.py [n]      (n = Gauss points, default 15 -> G15-K31)

Method (all in mpmath at 80 significant digits):
  1. Gauss nodes: zeros of the Legendre polynomial P_n, found by Newton from the
     Chebyshev-like guess cos(pi (i - 1/4) / (n + 1/2)); weights 2 / ((1 - x^2) P_n'(x)^2).
  2. Kronrod nodes: zeros of the Stieltjes polynomial E_{n+1}, the polynomial of degree n+1
     (coefficient of P_{n+1} equal to 1) with  integral_{-1}^{1} P_n(x) E_{n+1}(x) P_k(x) dx = 0  for k = 0..n.  E_{n+1} is
     written in the Legendre basis and the n+1 conditions are solved as a linear system whose
     entries are integrals of products of three Legendre polynomials, computed exactly by a
     Gauss-Legendre rule with enough points.  Its zeros interlace the Gauss nodes, so each is
     bracketed by two neighbouring Gauss nodes (or a node and +-1) and found by bisection.
  3. Kronrod weights: the 2n+1 weights that make the rule exact on P_0..P_{2n}
     (sum_i w_i P_k(x_i) = 2 delta_k0), a small dense solve.
  4. Checks printed to stderr: the K rule integrates x^d exactly up to d = 3n+1 (3n+2 for odd
     n), the G rule up to 2n-1, all weights are positive and Kronrod nodes interlace.
Output: C arrays (non-negative abscissae, descending, centre last) to stdout.
"""
import sys
import mpmath as mp

mp.mp.dps = 80


def legendre(n, x):
    """P_n(x) and P_n'(x) by the three-term recurrence (P_n' only for |x| < 1)."""
    p0, p1 = mp.mpf(1), x
    if n == 0:
        return p0, mp.mpf(0)
    for k in range(2, n + 1):
        p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
    dp = n * (x * p1 - p0) / (x * x - 1) if abs(x) < 1 else None
    return p1, dp


def bracketed_root(f, lo, hi):
    """Zero of f in (lo, hi) where f changes sign, by plain bisection to ~75 digits."""
    flo = f(lo)
    assert flo * f(hi) < 0, "no sign change in bracket"
    for _ in range(260):
        mid = (lo + hi) / 2
        fm = f(mid)
        if fm == 0:
            return mid
        if (fm < 0) == (flo < 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return (lo + hi) / 2


def gauss(n):
    nodes, weights = [], []
    for i in range(1, n + 1):
        x = mp.cos(mp.pi * (i - mp.mpf(1) / 4) / (n + mp.mpf(1) / 2))
        for _ in range(100):
            p, dp = legendre(n, x)
            dx = p / dp
            x -= dx
            if abs(dx) < mp.mpf(10) ** (-75):
                break
        p, dp = legendre(n, x)
        nodes.append(x)
        weights.append(2 / ((1 - x * x) * dp * dp))
    return nodes, weights  # descending


def stieltjes_coeffs(n):
    """Legendre-basis coefficients c_0..c_{n+1} of E_{n+1} with c_{n+1} = 1."""
    qx, qw = gauss(2 * n + 4)  # exact for degree <= 4n+7 >= n + (n+1) + n
    P = [[legendre(k, x)[0] for x in qx] for k in range(n + 2)]
    Pn = [legendre(n, x)[0] for x in qx]

    def tri(j, k):
        return mp.fsum(qw[i] * Pn[i] * P[j][i] * P[k][i] for i in range(len(qx)))

    A = mp.matrix(n + 1, n + 1)
    rhs = mp.matrix(n + 1, 1)
    for k in range(n + 1):
        for j in range(n + 1):
            A[k, j] = tri(j, k)
        rhs[k] = -tri(n + 1, k)
    # E_{n+1} has the parity of n+1, so only P_j with n+1-j even appear; the conditions for
    # k of the other parity hold trivially (odd integrand). What remains is square.
    cols = [j for j in range(n + 1) if (n + 1 - j) % 2 == 0]
    rows = [k for k in range(n + 1) if any(abs(A[k, j]) > mp.mpf(10) ** -60 for j in cols)]
    assert len(rows) == len(cols), "Stieltjes system is not square"
    M = mp.matrix(len(rows), len(cols))
    r = mp.matrix(len(rows), 1)
    for a, k in enumerate(rows):
        for b, j in enumerate(cols):
            M[a, b] = A[k, j]
        r[a] = rhs[k]
    sol = mp.lu_solve(M, r)
    c = [mp.mpf(0)] * (n + 2)
    for b, j in enumerate(cols):
        c[j] = sol[b]
    c[n + 1] = mp.mpf(1)
    return c


def eval_legendre_series(c, x):
    s = mp.mpf(0)
    for k, ck in enumerate(c):
        if ck != 0:
            s += ck * legendre(k, x)[0]
    return s


def kronrod(n):
    gx, gw = gauss(n)
    c = stieltjes_coeffs(n)
    E = lambda x: eval_legendre_series(c, x)
    # Brackets: (1, g1), (g1, g2), ..., (gn, -1): one Stieltjes zero in each.
    edges = [mp.mpf(1)] + gx + [mp.mpf(-1)]
    ext = []
    for i in range(n + 1):
        hi, lo = edges[i], edges[i + 1]
        x = bracketed_root(E, lo, hi)
        assert lo < x < hi, "Kronrod node outside its Gauss bracket"
        ext.append(x)
    allx = sorted(gx + ext, reverse=True)
    m = len(allx)
    A = mp.matrix(m, m)
    b = mp.matrix(m, 1)
    for k in range(m):
        for i, x in enumerate(allx):
            A[k, i] = legendre(k, x)[0]
        b[k] = 2 if k == 0 else 0
    w = mp.lu_solve(A, b)
    return allx, [w[i] for i in range(m)], gx, gw


def check(n, kx, kw, gx, gw):
    degk = 3 * n + 1 + (n % 2)
    worst = mp.mpf(0)
    for d in range(degk + 1):
        exact = mp.mpf(2) / (d + 1) if d % 2 == 0 else mp.mpf(0)
        worst = max(worst, abs(mp.fsum(w * x ** d for x, w in zip(kx, kw)) - exact))
    nxt = mp.fsum(w * x ** (degk + 1) for x, w in zip(kx, kw)) - mp.mpf(2) / (degk + 2)
    gworst = mp.mpf(0)
    for d in range(2 * n):
        exact = mp.mpf(2) / (d + 1) if d % 2 == 0 else mp.mpf(0)
        gworst = max(gworst, abs(mp.fsum(w * x ** d for x, w in zip(gx, gw)) - exact))
    sys.stderr.write("K%d exact to degree %d: max error %s (degree %d error %s)\n"
                     % (2 * n + 1, degk, mp.nstr(worst, 3), degk + 1, mp.nstr(nxt, 3)))
    sys.stderr.write("G%d exact to degree %d: max error %s\n" % (n, 2 * n - 1, mp.nstr(gworst, 3)))
    sys.stderr.write("min Kronrod weight %s, min Gauss weight %s\n"
                     % (mp.nstr(min(kw), 5), mp.nstr(min(gw), 5)))


def emit(n):
    kx, kw, gx, gw = kronrod(n)
    check(n, kx, kw, gx, gw)
    m = 2 * n + 1
    half = n + 1  # non-negative Kronrod abscissae: indices 0..n (n is the centre)
    fmt = lambda v: mp.nstr(v, 30, strip_zeros=False, min_fixed=-1, max_fixed=1) + "L"
    print("/* Generated by bench/fit/gen_kronrod.py %d (G%d-K%d). Abscissae in [0, 1), descending;"
          % (n, n, m))
    print("   the rule uses +-x. Odd entries (1, 3, ...) of the Kronrod list are the Gauss nodes. */")
    print("static const long double pf_oracle__xk[%d] = {" % half)
    for i in range(half):
        x = kx[i] if i < n else mp.mpf(0)
        print("    %s," % fmt(abs(x)))
    print("};")
    print("static const long double pf_oracle__wk[%d] = {" % half)
    for i in range(half):
        print("    %s," % fmt(kw[i]))
    print("};")
    ng = (n + 1) // 2
    print("/* Gauss weights for the Gauss nodes pf_oracle__xk[1], [3], ...%s */"
          % (" (the last one is the centre)" if n % 2 else ""))
    print("static const long double pf_oracle__wg[%d] = {" % ng)
    for j in range(ng):
        print("    %s," % fmt(gw[j]))
    print("};")


if __name__ == "__main__":
    emit(int(sys.argv[1]) if len(sys.argv) > 1 else 15)

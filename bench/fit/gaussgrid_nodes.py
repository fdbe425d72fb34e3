#!/usr/bin/env python3
"""gaussgrid_nodes.py - node tables of include/pf_gaussgrid.h, computed from scratch.

usage: python3 bench/fit/gaussgrid_nodes.py [--check] [nmax]     (nmax defaults to 9)

Three quadratures of a 1D standard normal Z ~ N(0, 1), each for N = 1 .. nmax points, all
symmetric about 0 so that only the ceil(N/2) non-negative nodes are stored (half index k = 0 is
the smallest non-negative node: 0 for odd N, the smallest positive one for even N).

  uniform   LEADR's grid (Dupuy et al. 2013 sec. 5.1): N equally spaced nodes on
            [-lambda, lambda], weights proportional to exp(-p^2/2), normalized to sum 1.
            LEADR only gives lambda = 1.8 for N = 5; for other N we use
            lambda(N) = 0.9 sqrt(N - 1), which reproduces that point and lets both the range
            (truncation error) and the spacing (discretization error) improve as N grows.
            N = 1 is the single node 0.
  matched   the uniform grid with the same weights and its nodes multiplied by
            s = 1 / sqrt(sum_j W_j p_j^2), so that the grid reproduces the unit variance.
  hermite   Gauss-Hermite, probabilists' weight exp(-x^2/2), normalized to sum 1: nodes are the
            zeros of He_N (eigenvalues of the Jacobi matrix with off-diagonal sqrt(k), found with
            mpmath's symmetric eigensolver, then polished by Newton on the three-term recurrence
            He_{k+1} = x He_k - k He_{k-1}); weights (N-1)! / (N He_{N-1}(x_i)^2).

Everything in mpmath at 50 digits; printed with 17 significant digits (exact to double's
rounding). Output: the C switch functions pasted into pf_gaussgrid.h between its
GAUSSGRID TABLES markers. --check prints, to stderr, the captured variance sum W p^2 of each set
and the highest even moment each reproduces exactly.
"""
import sys
import mpmath as mp

mp.mp.dps = 50


def uniform_lambda(n):
    return mp.mpf("0.9") * mp.sqrt(n - 1)


def uniform(n):
    if n == 1:
        return [mp.mpf(0)], [mp.mpf(1)]
    lam = uniform_lambda(n)
    p = [lam * (2 * mp.mpf(j) / (n - 1) - 1) for j in range(n)]
    e = [mp.exp(-x * x / 2) for x in p]
    s = mp.fsum(e)
    return p, [x / s for x in e]


def matched(n):
    p, w = uniform(n)
    if n == 1:
        return p, w
    var = mp.fsum(wi * pi * pi for pi, wi in zip(p, w))
    s = 1 / mp.sqrt(var)
    return [s * x for x in p], w


def hermite_he(n, x):
    """He_n(x) and He_{n-1}(x) by the recurrence."""
    h0, h1 = mp.mpf(1), x
    if n == 0:
        return h0, mp.mpf(0)
    for k in range(1, n):
        h0, h1 = h1, x * h1 - k * h0
    return h1, h0


def hermite(n):
    if n == 1:
        return [mp.mpf(0)], [mp.mpf(1)]
    jac = mp.matrix(n, n)
    for k in range(1, n):
        jac[k - 1, k] = jac[k, k - 1] = mp.sqrt(k)
    ev, _ = mp.eigsy(jac)
    nodes = sorted(ev[i] for i in range(n))
    out_p, out_w = [], []
    for x in nodes:
        for _ in range(60):
            h, hm1 = hermite_he(n, x)
            dx = h / (n * hm1)  # He_n' = n He_{n-1}
            x -= dx
            if abs(dx) < mp.mpf(10) ** (-45):
                break
        h, hm1 = hermite_he(n, x)
        out_p.append(x)
        out_w.append(mp.factorial(n - 1) / (n * hm1 * hm1))
    # exact symmetry
    for i in range(n // 2):
        a = (out_p[n - 1 - i] - out_p[i]) / 2
        out_p[i], out_p[n - 1 - i] = -a, a
        w = (out_w[i] + out_w[n - 1 - i]) / 2
        out_w[i] = out_w[n - 1 - i] = w
    if n % 2:
        out_p[n // 2] = mp.mpf(0)
    s = mp.fsum(out_w)
    return out_p, [w / s for w in out_w]


def half(values, n):
    """non-negative half, k = 0 nearest the centre"""
    return values[n // 2:] if n % 2 == 0 else values[(n - 1) // 2:]


def fmt(x):
    s = mp.nstr(x, 17, min_fixed=-4, max_fixed=4)
    if "." not in s and "e" not in s:
        s += ".0"
    return s


def emit(name, what, table, nmax, comment):
    print("/* %s */" % comment)
    print("PF_DEF pf_real %s(int n, int k)" % name)
    print("{")
    print("    switch (n * 8 + k) {")
    for n in range(1, nmax + 1):
        vals = half(table[n][what], n)
        for k, v in enumerate(vals):
            print("    case %d: return PF_R(%s);" % (n * 8 + k, fmt(v)))
    print("    default: return PF_R(0.0);")
    print("    }")
    print("}")
    print()


def exact_even_moment(p, w, tol=mp.mpf(10) ** (-40)):
    """highest even d such that sum w p^d equals E[Z^d] = (d-1)!! for all even d' <= d"""
    d = 0
    while d < 60:
        m = mp.fsum(wi * pi ** (d + 2) for pi, wi in zip(p, w))
        ex = mp.fac2(d + 1)
        if abs(m - ex) > tol * ex:
            return d
        d += 2
    return d


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    nmax = int(args[0]) if args else 9
    assert nmax <= 9, "the switch key n * 8 + k assumes k < 8, i.e. n <= 15; tables stop at 9"
    sets = {"uniform": uniform, "matched": matched, "hermite": hermite}
    tabs = {name: {n: f(n) for n in range(1, nmax + 1)} for name, f in sets.items()}
    if "--check" in sys.argv:
        for name in sets:
            for n in range(1, nmax + 1):
                p, w = tabs[name][n]
                var = mp.fsum(wi * pi * pi for pi, wi in zip(p, w))
                sys.stderr.write("%-8s N=%d  sum W p^2 = %s  exact even moments up to %d\n"
                                 % (name, n, mp.nstr(var, 8), exact_even_moment(p, w)))
    print("/* GAUSSGRID TABLES BEGIN: generated by bench/fit/gaussgrid_nodes.py %d, do not edit. */" % nmax)
    emit("pfi_gg_uniform_node", 0, tabs["uniform"], nmax,
         "LEADR uniform grid: node k of the non-negative half, lambda(N) = 0.9 sqrt(N - 1)")
    emit("pfi_gg_uniform_weight", 1, tabs["uniform"], nmax,
         "LEADR uniform grid: normalized weight exp(-p^2/2) / sum (also the matched grid's)")
    emit("pfi_gg_matched_node", 0, tabs["matched"], nmax,
         "moment-matched uniform grid: uniform nodes times 1/sqrt(sum W p^2)")
    emit("pfi_gg_hermite_node", 0, tabs["hermite"], nmax,
         "Gauss-Hermite (probabilists'): non-negative zeros of He_N")
    emit("pfi_gg_hermite_weight", 1, tabs["hermite"], nmax,
         "Gauss-Hermite: normalized weights (N-1)! / (N He_{N-1}(x)^2)")
    print("/* GAUSSGRID TABLES END */")


if __name__ == "__main__":
    main()

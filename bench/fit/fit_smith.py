"""fit_smith.py - reproduces every fitted coefficient in include/pf_smith.h.

    python3 bench/fit/fit_smith.py        (needs mpmath only; ~3 minutes)

Truth: Lambda(nu) = exp(-nu^2)/(2 nu sqrt(pi)) - erfc(nu)/2 (Smith 1967 for a Gaussian slope
distribution, as written in Dupuy et al. 2013 sec. 4.3) evaluated in 50-digit arithmetic.

Kernels (all fitted as near-minimax rationals with relative error, see ratfit.py):
  K(nu) = 1 - nu sqrt(pi) exp(nu^2) erfc(nu)        on [0, 2]       Lambda = exp(-nu^2) K / (2 sqrt(pi) nu)
  F(s)  = 2 K(1/sqrt(s)) / s,  s = 1/nu^2            on [0, 1/4]     Lambda = exp(-nu^2) F / (4 sqrt(pi) nu^3)
  H(nu) = G1(nu)/nu = 1/(nu (1 + Lambda))            on [0, c]       G1 = nu H, and G1 = 1 past c
K and F have no cancellation (K in (0, 1], F -> 1), unlike the two-term closed form whose terms
nearly cancel for large nu. H is the float G1 path (5,5) and the 'fast' tier (3,2)."""
import sys, os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ratfit import fit, max_rel_dense
from mpmath import mp, mpf, exp, erfc, sqrt, pi, nstr

mp.dps = 50

def lam(n):
    return exp(-n * n) / (2 * n * sqrt(pi)) - erfc(n) / 2

def K(n):
    return 1 - n * sqrt(pi) * exp(n * n) * erfc(n)

def F(s):
    if s == 0:
        return mpf(1)
    return 2 * K(1 / sqrt(s)) / s

def H(n):
    if n == 0:
        return 2 * sqrt(pi)
    return 1 / (1 + lam(n)) / n

def show(name, p, q, err, digits):
    print("/* %s: max relative fit error %s */" % (name, nstr(err, 3)))
    print("  P:", ", ".join(nstr(v, digits) for v in p))
    print("  Q:", ", ".join(nstr(v, digits) for v in q))
    sys.stdout.flush()

def best_cutoff(m, n, cuts):
    best = None
    for c in cuts:
        e, p, q = fit(H, 0, c, m, n, count=200, iters=40)
        tail = 1 - 1 / (1 + lam(mpf(c)))
        tot = max(e, tail)
        print("   H(%d,%d) cutoff %.3f: fit %s, tail 1-G1(c) %s" % (m, n, c, nstr(e, 3), nstr(tail, 3)))
        if best is None or tot < best[0]:
            best = (tot, c, p, q)
    return best

if __name__ == "__main__":
    what = sys.argv[1:] or ["fast", "g1f", "kf", "kd", "lambda_fast"]
    if "fast" in what:
        # Branch-free tier: nu is clamped to [0, c] and the fit at c serves every nu beyond,
        # so it is also fitted toward G1 = 1 at c (an extra target point H = 1/c).
        for c in [mpf("2.2"), mpf("2.3")]:
            e, p, q = fit(H, 0, c, 3, 2, count=200, iters=50, extra=[(c, 1 / c)])
            show("G1 fast tier H(3,2) on [0, %s], clamped beyond (divide P, Q by Q's last coefficient "
                 "for the header's monic form)" % nstr(c, 3), p, q, e, 10)
    if "g1f" in what:
        # issue 17: H(4,5) on [0, 3.1], pulled toward G1 = 1 at the clamp (the header divides
        # P and Q by Q's last coefficient for its monic form); fit 4.66e-7, tail 2.78e-7
        c = mpf("3.1")
        e, p, q = fit(H, 0, c, 4, 5, count=160, iters=40, extra=[(c, 1 / c)])
        show("G1 float path H(4,5) on [0, 3.1], clamped beyond", p, q, e, 12)
    if "lambda_fast" in what:
        # issue 17: Lambda = exp(-nu^2) z^2 L(z) / nu, z = 1/(nu + 2.5), L = K (nu + 2.5)^2 /
        # (2 sqrt(pi)) a degree-7 polynomial, relative minimax on 0 <= nu <= 10.5, float
        # coefficients rounded one at a time (remez.fit_rounded); the header writes z^2 L in
        # w = a z, a = c7^(1/9), where it is monic (prints a and the d_k = c_k / a^(k+2))
        import remez
        A, XM = mpf("2.5"), mpf("10.5")
        def Lz(z):
            nu = 1 / z - A
            return K(nu) * (nu + A) ** 2 / (2 * sqrt(pi))
        remez.mp.dps = 30
        cs, (e, at) = remez.fit_rounded(Lz, 1 / (XM + A), 1 / A, 7, rnd=remez.to_float32, npts=100, iters=40)
        a = remez.to_float32(cs[7] ** (mpf(1) / 9))
        print("/* Lambda fast tier L(z), degree 7: max relative fit error %s */" % nstr(e, 3))
        print("  a = %.9g; d_k:" % float(a), ", ".join("%.9g" % float(remez.to_float32(cs[k] / a ** (k + 2))) for k in range(8)))
    if "kf" in what:
        e, p, q = fit(K, 0, 2, 4, 4, count=150, iters=40)
        show("float K(4,4) on [0,2]", p, q, e, 10)
        e, p, q = fit(F, 0, mpf(1) / 4, 3, 3, count=150, iters=40)
        show("float F(3,3) on s in [0,1/4]", p, q, e, 10)
    if "kd" in what:
        e, p, q = fit(K, 0, 2, 8, 8, count=220, iters=50)
        show("double K(8,8) on [0,2]", p, q, e, 21)
        e, p, q = fit(F, 0, mpf(1) / 4, 8, 8, count=220, iters=50)
        show("double F(8,8) on s in [0,1/4]", p, q, e, 21)

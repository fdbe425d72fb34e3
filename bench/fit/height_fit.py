"""height_fit.py - reproduces the fitted constants of include/pf_height.h (our visible-height tier).

    python3 bench/fit/height_fit.py            (needs mpmath only; about a minute)
    python3 bench/fit/height_fit.py check      (also compares the truth with mpmath quadrature)

Truth. The visible height distribution of Heitz et al. 2014 eq. 15, heights in units of sigma_h:
    D(z) = (L + 1) phi(z) Phi(z)^L,   L = Lambda_o + Lambda_i,
a probability density (integral of phi Phi^L is 1/(L+1)); for integer L it is the density of the
maximum of L + 1 standard normals. mu_d = E[z], sigma_d = sqrt(E[(z - mu_d)^2]) (the central
deviation). Both are computed here in double precision by a sinh-mapped trapezoidal rule with 600
nodes, centred on the distribution in two passes (the same rule as pf_visible_height_exact, with
10x the nodes). `check` compares it with 30-digit mpmath adaptive quadrature: agreement ~1e-15.

Fits (near-minimax in relative error, Lawson's method, ratfit.py), in the variable
    s = sqrt(log(1 + L)),  s in [0, S],  S = sqrt(log(1 + 1e30)) = 8.31 (L up to PF_LAMBDA_MAX):
    mu_d    = s^2 * P_mu(s) / Q_mu(s),     deg Q = deg P + 1, so mu_d ~ const * s for large s
                                            (the true growth, sqrt(2 log L)), and
                                            mu_d ~ 0.9026 L near L = 0 (relative fit => absolute
                                            error vanishes there)
    sigma_d = P_sg(s) / Q_sg(s),           deg Q = deg P + 1, sigma_d ~ const / s (Gumbel limit)
The fit is done over the whole range so that every Lambda, up to PF_LAMBDA_MAX, gets a finite,
smooth, monotone answer; the accuracy goal (1% over L in [0, 1000]) is met with a wide margin.
Output: the coefficients, and the max relative error on a dense grid in L."""
import sys, os, math
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ratfit import fit, horner
from mpmath import mp, mpf, nstr

mp.dps = 30
S_MAX = math.sqrt(math.log1p(1e30))

def log_phi(z):
    """log Phi(z) in double, accurate in both tails."""
    if z > 0:
        return math.log1p(-0.5 * math.erfc(z / math.sqrt(2)))
    if z < -30:
        s = 1 / (z * z)
        return (-z * z / 2 - math.log(-z * math.sqrt(2 * math.pi))
                + math.log1p(-s + 3 * s * s - 15 * s ** 3 + 105 * s ** 4 - 945 * s ** 5))
    return math.log(0.5 * math.erfc(-z / math.sqrt(2)))

def moments(L, n=600):
    """(mass, mu_d, sigma_d) of D for L >= 0 (double precision)."""
    c = math.sqrt(2 * math.log1p(L)) if L > 1 else 0.5 * L
    s = 1.0 / (1 + 0.3 * math.log1p(L))
    m0 = 1.0
    for _ in range(2):
        x0, x1 = -6.0, 7.0
        h = (x1 - x0) / (n - 1)
        a = 0.5 * s
        m0 = m1 = m2 = 0.0
        for i in range(n):
            x = x0 + i * h
            z = c + a * math.sinh(x)
            v = math.exp(math.log1p(L) - z * z / 2 + L * log_phi(z)) / math.sqrt(2 * math.pi) \
                * a * math.cosh(x) * h
            d = z - c
            m0 += v; m1 += v * d; m2 += v * d * d
        e1 = m1 / m0
        c, s = c + e1, math.sqrt(m2 / m0 - e1 * e1)
    return m0, c, s

_cache = {}
def truth_s(s):
    key = float(s)
    if key not in _cache:
        _cache[key] = moments(math.expm1(key * key))
    return _cache[key]

def mu_over_s2(s):
    s = float(s)
    if s < 1e-6:   # limit: mu ~ mu'(0) L, L ~ s^2
        return mpf(truth_s(1e-3)[1] / math.expm1(1e-6)) if False else mpf(truth_s(1e-4)[1] / 1e-8)
    return mpf(truth_s(s)[1] / (s * s))

def sigma_of_s(s):
    return mpf(truth_s(float(s))[2])

def check_grid():
    """Dense grid in L: 0, then log-spaced 1e-6 .. 1e30 (truth recomputed)."""
    Ls = [0.0] + [10 ** (k / 20.0) for k in range(-120, 601)]
    return Ls

def eval_fit(p, q, s):
    return float(horner(p, mpf(s)) / horner(q, mpf(s)))

def report(name, p, q, kind):
    worst_rel = (0, 0); worst_abs = (0, 0); worst_rel1000 = (0, 0)
    for L in check_grid():
        m0, mu, sd = moments(L)
        s = math.sqrt(math.log1p(L))
        if kind == "mu":
            got = s * s * eval_fit(p, q, s); ref = mu
        else:
            got = eval_fit(p, q, s); ref = sd
        ea = abs(got - ref); er = ea / ref if ref > 0 else ea
        if ea > worst_abs[0]: worst_abs = (ea, L)
        if er > worst_rel[0]: worst_rel = (er, L)
        if L <= 1000 and er > worst_rel1000[0]: worst_rel1000 = (er, L)
    print("/* %s: max rel %s at L=%s (L <= 1000: %s), max abs %s sigma_h at L=%s */" % (
        name, nstr(worst_rel[0], 3), "%.3g" % worst_rel[1], nstr(worst_rel1000[0], 3),
        nstr(worst_abs[0], 3), "%.3g" % worst_abs[1]))
    print("  P:", ", ".join(nstr(v, 10) for v in p))
    print("  Q:", ", ".join(nstr(v, 10) for v in q))
    sys.stdout.flush()

if __name__ == "__main__":
    if "check" in sys.argv[1:]:
        from mpmath import quad, exp, log, sqrt, pi, ncdf, inf, log1p
        for L in [0.001, 0.5, 1, 10, 1000, 1e6, 1e12]:
            Lm = mpf(L); nn = Lm + 1
            c = sqrt(2 * log(nn)) if nn > 2 else mpf(0)
            lphi = lambda z: log1p(-ncdf(-z)) if z > 0 else log(ncdf(z))
            f0 = lambda z: exp(log(nn) - z * z / 2 - log(sqrt(2 * pi)) + Lm * lphi(z))
            pts = [-inf, c - 8, c - 3, c - 1, c, c + 1, c + 3, c + 8, inf]
            m0 = quad(f0, pts); mu = quad(lambda z: z * f0(z), pts) / m0
            sd = sqrt(quad(lambda z: (z - mu) ** 2 * f0(z), pts) / m0)
            t = moments(L)
            print("L=%g  mu rel diff %.2e  sigma rel diff %.2e" % (L, abs(t[1] - mu) / mu, abs(t[2] - sd) / sd))
    degs = [(int(a), int(b)) for a, b in (x.split(",") for x in os.environ.get("DEGS", "3,4").split())]
    for m, n in degs:
        e, p, q = fit(mu_over_s2, 0, S_MAX, m, n, count=120, iters=40)
        report("mu_d = s^2 P%d/Q%d (fit err %s)" % (m, n, nstr(e, 3)), p, q, "mu")
        e, p, q = fit(sigma_of_s, 0, S_MAX, m, n, count=120, iters=40)
        report("sigma_d = P%d/Q%d (fit err %s)" % (m, n, nstr(e, 3)), p, q, "sigma")

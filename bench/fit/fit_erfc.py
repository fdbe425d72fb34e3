"""Fit the coefficients of pf_erfc / pf_erf (include/pf_core.h).

usage: python3 bench/fit/fit_erfc.py float|double|fast (needs mpmath only)

fast: the shader tier pf_erfc_fast (issue 17): N = exp(x^2) erfc(x) (x + 2) as a degree-6
polynomial in z = 1/(x + 2), relative minimax on 0 <= x <= 10.1, float coefficients rounded
one at a time; printed also in w = a z, a = c6^(1/7), where z N is monic (the header's form).

Two approximations are fitted, both minimising the maximum RELATIVE error:

1. erf(x) / x = P(s), s = x^2, on 0 <= x <= 1. P(0) = 2/sqrt(pi) is kept
   exact in the fit; the code evaluates erf = x + x * (P(s) - 1) so that the
   leading coefficient's rounding costs nothing.

2. N = exp(x^2) * erfc(x) * (x + A), A = 0.625, as a polynomial in
   z = 1/(x + A) - 1/2 (minus a centre): float one piece of degree 12 on
   0.5 <= x <= 10.5; double three pieces on [0.5, 2], [2, 5], [5, 27.5] of
   degree 18/17/17. N is flat (0.57..0.70), because exp(x^2) erfc(x) behaves
   like 1/(sqrt(pi) x) for large x. The code writes N = 0.625 + y with the
   exact short constant 0.625, so its rounding errors only touch the small y;
   the constant term printed is therefore N(centre) - 0.625.

Float coefficients are rounded one at a time (lowest degree first) and the
remaining ones refitted after each rounding; double ones are rounded at once.
Runtime: about 1 minute (float), 10 minutes (double).
"""
import sys
import os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import remez
from remez import mp, fit, max_rel_err, to_float32, to_float64

prec = sys.argv[1] if len(sys.argv) > 1 else 'float'
if prec == 'fast':
    mp.mp.dps = 30
    A2, XM = mp.mpf(2), mp.mpf('10.1')
    def Nfast(z):
        x = 1 / z - A2
        return mp.exp(x * x) * mp.erfc(x) * (x + A2)
    c, (e, at) = remez.fit_rounded(Nfast, 1 / (XM + A2), 1 / A2, 6, rnd=to_float32, npts=120, iters=50)
    a = to_float32(c[6] ** (mp.mpf(1) / 7))
    print('/* pf_erfc_fast N(z), degree 6: max relative fit error %s */' % mp.nstr(e, 3))
    print('  c_k:', ', '.join('%.9g' % float(c[k]) for k in range(7)))
    print('  a = %.9g; d_k = c_k / a^(k+1):' % float(a), ', '.join('%.9g' % float(to_float32(c[k] / a ** (k + 1))) for k in range(7)))
    sys.exit(0)
if prec == 'float':
    mp.mp.dps = 40
    rnd, fmt = to_float32, '%.9g'
    PDEG, NDEG, XMAX, NPTS, ITERS = 6, 12, 10.5, 200, 50
else:
    mp.mp.dps = 80
    rnd, fmt = to_float64, '%.17g'
    PDEG, NDEG, XMAX, NPTS, ITERS = 11, 17, 27.5, 200, 60

A = mp.mpf('0.625')
W0 = mp.mpf('0.5')


def Pf(s):
    if s == 0:
        return 2 / mp.sqrt(mp.pi)
    r = mp.sqrt(s)
    return mp.erf(r) / r


def Nf(z):
    w = z + W0
    x = 1 / w - A
    return mp.erfc(x) * mp.exp(x * x) / w


def progressive(f, a, b, deg, fixed):
    fixed = dict(fixed)
    if prec == 'double':
        # 53-bit rounding of the coefficients costs far less than the fit error
        # budget, so fit once and round everything (refitting 27 times at
        # 80 digits would take an hour).
        c, e = fit(f, a, b, deg, fixed=fixed, npts=NPTS, iters=ITERS)
        return {k: (v if k in fixed else rnd(v)) for k, v in c.items()}
    for k in range(deg + 1):
        if k in fixed:
            continue
        c, e = fit(f, a, b, deg, fixed=fixed, npts=NPTS, iters=ITERS)
        fixed[k] = rnd(c[k])
    return fixed


def emit(name, c, err, extra=''):
    print('/* %s: max rel err of the fit %s at %s%s */' % (name, mp.nstr(err[0], 3), mp.nstr(err[1], 6), extra))
    for k in sorted(c):
        print('  c%d = ' % k + fmt % float(c[k]))


# 1. erf(x)/x in s = x^2, c0 exact
p = progressive(Pf, 0, 1, PDEG, {0: 2 / mp.sqrt(mp.pi)})
p1 = dict(p)
p1[0] = rnd(p[0] - 1)
emit('P(s) = erf(x)/x, s in [0,1]; c0 below is P(0)-1', p1, max_rel_err(Pf, p, 0, 1))

# 2. N in z = 1/(x+A) - W0; the code uses y = N - 0.625 (constant printed below)
def piece(xa, xb, deg, center=None):
    zlo = 1 / (mp.mpf(xb) + A) - W0
    zhi = 1 / (mp.mpf(xa) + A) - W0
    if center is None:
        center = rnd((zlo + zhi) / 2)
    f = lambda v: Nf(v + center)
    n0 = f(mp.mpf(0))
    n = progressive(f, zlo - center, zhi - center, deg, {0: n0})
    emit('N(z), x in [%s, %s], polynomial in v = z - (%s)' % (xa, xb, fmt % float(center)), n,
         max_rel_err(f, n, zlo - center, zhi - center),
         '; constant term minus 0.625: ' + fmt % float(rnd(n0 - mp.mpf('0.625'))))


if prec == 'float':
    piece('0.5', '10.5', NDEG, center=mp.mpf(0))
else:
    # one piece of degree ~26 does not reach 1e-17 on [0.5, 27.5]; three pieces do
    piece('0.5', '2', 18)
    piece('2', '5', 17)
    piece('5', '27.5', 17)

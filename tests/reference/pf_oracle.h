/* pf_oracle.h - the numerical oracle that prefilter's formula tests are checked against.

   PURPOSE
   Test-only code. Adaptive Gauss-Kronrod quadrature in long double (1D on finite, semi-infinite
   and infinite intervals, nested 2D), plus the standard normal pdf/cdf/sf. A formula in
   include/ (a Smith Lambda, a moment, a filtered lobe) is tested by integrating its definition
   here and comparing. The oracle is independent of the library: it never includes or calls
   anything from include/, it only uses <math.h> long double functions (expl, erfcl, fabsl).
   It is CPU code: pointers, function pointers and a fixed-size interval heap on the stack, no
   malloc, no static mutable state, so every function is re-entrant (an integrand may itself
   call the integrator; that is how the 2D integral works). C99 and C++11.

   CONFIGURATION (define before including; both optional)
     PF_ORACLE_MAX_INTERVALS  capacity of the interval heap of one 1D call (default 2000; each
                              entry is 112 bytes of stack on x86-64, so 220 KB per active call).
     PF_ORACLE_DEF            linkage of every function (default: static, marked unused for
                              GCC/Clang so a test that uses only part of the API stays -Werror
                              clean; plain static inline elsewhere).

   USAGE
     static long double gauss(long double x, void *ctx) { (void)ctx; return expl(-x * x); }
     pf_oracle_result r = pf_oracle_integrate(gauss, NULL, -HUGE_VALL, HUGE_VALL,
                                              0.0L, 1e-17L, PF_ORACLE_MAX_INTERVALS);
     if (r.converged) ... r.value is sqrt(pi) to ~1e-19, r.error bounds it (conservatively)

     breakpoints (kinks, peak centres), here for max(0, x - k) on [0, 2]:
     pf_oracle_result r = pf_oracle_integrate_points(ramp, &k, 0.0L, 2.0L, &k, 1,
                                                     0.0L, 1e-17L, PF_ORACLE_MAX_INTERVALS);
     2D, the unit disc:
     pf_oracle_2d pb = pf_oracle_2d_make(one, NULL, -1.0L, 1.0L, 0.0L, 0.0L);
     pb.ylo = disc_lo;  pb.yhi = disc_hi;  (functions of x returning -+sqrt(1 - x^2))
     pf_oracle_result area = pf_oracle_integrate_2d(&pb);

   FUNCTIONS
     pf_oracle_integrate(f, ctx, a, b, epsabs, epsrel, max_intervals)
         integral of f over [a, b]; a, b may be -HUGE_VALL / +HUGE_VALL; a > b gives minus the
         integral over [b, a].
     pf_oracle_integrate_points(f, ctx, a, b, points, npoints, epsabs, epsrel, max_intervals)
         the same, with the interval split first at the given points (kinks, steps, peaks).
     pf_oracle_2d_make(f, ctx, ax, bx, ay, by)      a 2D problem with default settings
     pf_oracle_integrate_2d(&problem)
         integral over x in [ax, bx] of the integral over y in [ylo(x), yhi(x)] of f(x, y).
     pf_oracle_normal_pdf(z)  pf_oracle_normal_cdf(z)  pf_oracle_normal_sf(z)
         standard normal density, lower tail P(Z <= z), upper tail P(Z > z).
     pf_oracle_status_name(status)                  "ok", "max-intervals", ...
     pf_oracle_normal2_pdf(dx, dy, vx, vy, c)       bivariate normal density (slope PDF P22)
     pf_oracle_lambda_beckmann(nu)                  Smith Lambda of Gaussian slopes, closed form
     pf_oracle_lambda_1d(c, mu, sigma)              the same Lambda by quadrature of its definition
   The integrators return a pf_oracle_result {value, error, converged, status, intervals,
   evals}; converged is 1 exactly when status is PF_ORACLE_OK.

   THE RULE
   Gauss-Kronrod G15-K31, globally adaptive: the interval with the largest error estimate is
   bisected until the total estimate is <= max(epsabs, epsrel * |value|). Why G15-K31 rather
   than G7-K15 or G10-K21: the oracle aims at ~1e-18 relative in long double, and the
   integrands here are smooth nearly everywhere (Gaussians, rational slopes) with breakpoints
   passed at the kinks; there a degree-47 rule needs far fewer bisections than the degree-23
   and degree-31 ones. Measured on tests/test_oracle.c (same tests, table swapped): G7-K15
   6.8 M integrand evaluations, G10-K21 3.2 M, G15-K31 1.8 M (the nested 2D tests dominate).
   The nodes and weights were computed from scratch by bench/fit/gen_kronrod.py (mpmath, 80
   digits: Legendre zeros, the zeros of the Stieltjes polynomial E_16, weights from exactness
   on P_0..P_30) and checked there: K31 exact to degree 47, all weights positive.

   ERROR ESTIMATE AND STATUS
   Per interval: |K31 - G15| * h + LDBL_EPSILON * (integral of |f|). The first term is the
   Gauss rule's error, so it overstates the error of the K31 value that is returned, often by
   orders of magnitude: treat r.error as a bound (the tests check it is one), not a measurement.
   It covers the quadrature only, not the integrand's own evaluation error (see below).
   An interval is frozen (never bisected again, its error still counted) when
     - K and G already agree to rounding level (|K - G| <= 32 eps integral |f|), or
     - bisecting it did not help: the two halves' errors add up to >= 1/4 of the parent's
       while the parent's is <= 1e-9 of its integral of |f|. A smooth integrand gains orders
       of magnitude per bisection and an end singularity keeps a large relative difference,
       so this is noise in the integrand (e.g. expl of a large, rounded exponent), or
     - it is too narrow to bisect without its outermost nodes rounding onto its ends.
   The call stops with PF_ORACLE_ROUNDOFF (converged = 0, value and error still the best
   available) when frozen intervals alone exceed the tolerance and the refinable ones no
   longer dominate the error: the tolerance is below what long double, or the integrand's own
   rounding, allows. Ask for epsrel around 1e-17; 1e-18 is reachable for clean integrands.

   INFINITE INTERVALS
   Each piece with an infinite end is mapped onto a finite t-interval:
     [a, +inf)    x = a + t / (1 - t),      t in [0, 1),  dx = dt / (1 - t)^2
     (-inf, b]    x = b - t / (1 - t),      t in [0, 1),  dx = dt / (1 - t)^2
     (-inf, +inf) x = t / ((1 - t)(1 + t)), t in (-1, 1), dx = (1 + t^2) / (1 - t^2)^2 dt
   (with breakpoints, the two outer pieces of an infinite interval use the first two maps).
   Gauss-Kronrod nodes are interior, and an interval is never bisected so finely that its
   outermost node could round onto an end, so the singular t = 1 (t = -1) is never evaluated;
   a t that still rounds to it contributes 0. The map has unit scale: put a breakpoint at the
   centre of a far or narrow peak (a Gaussian's mean) so the first rule sees it.

   WHAT AN INTEGRAND MUST TOLERATE
     - any x strictly inside the interval, in any order, many times (a pure function of x and
       ctx; it may itself call the integrator: everything is re-entrant);
     - on infinite intervals, huge finite x: |x| up to about |a| + 1 / LDBL_EPSILON ~ 1e19.
       It must return a finite number there (0 is fine), never inf or NaN: x * expl(-x * x)
       is fine (it is 0), expl(x * x) / expl(2 * x * x) is not (inf / inf);
     - on finite intervals, x very close to an end (never the end itself), so an integrable
       end singularity such as 1 / sqrt(x) on [0, 1] works (slowly: ~90 intervals for 1e-15).
   A non-finite value stops the integration with PF_ORACLE_NONFINITE and a NaN result.
   The oracle is only as accurate as the integrand. Far-tail integrands should be written
   relative to the tail point: for (x - c) N(x; mu, s) on [c, inf) with z = (c - mu) / s = 30,
   evaluating N at a rounded large x puts ~z |c| eps / s of noise in the exponent (3e-17
   measured); in u = x - c with N(c + u) = pdf(z) exp(-w (z + w / 2)) / s, w = u / s, the
   same integral comes out to 2e-19. Infinite limits, the exact splitting in the normal
   functions and the NaN checks need IEEE semantics: no -ffast-math (under it the normal
   tails lose accuracy to ~3e-17 and non-finite integrands go undetected).

   NESTED 2D
   pf_oracle_integrate_2d integrates, for each outer node x, the inner integral over y with
   the 1D integrator (an inner-context struct on the caller's stack carries x; no statics).
   Inner integrals ask for epsabs/8, epsrel/8. An inner PF_ORACLE_ROUNDOFF is accepted (it
   happens where the inner integral is negligible or cancels, e.g. a Gaussian's far tails with
   exponents ~ 1e4); other inner failures make the 2D status PF_ORACLE_INNER_FAILED. Inner
   breakpoints may depend on x (ypoints), e.g. the conditional mean, or a kink line.

   ACCURACY MEASURED (tests/test_oracle.c, x86-64 80-bit long double, epsrel 1e-17)
     x^d on one K31 rule, d <= 47 ................................. <= 3.9e-19 relative
     exp on [0,1], [-3,40], (-inf,2] .............................. <= 6.6e-20
     1/(1+x^2) on R (pi), [1,inf), (-inf,0] ....................... <= 6.9e-20
     exp(-x^2) on R (sqrt pi) ..................................... 6.1e-20
     N(50, 1/64) on R with a breakpoint at 50 ...................... 3.3e-19
     x exp(-x^2) on [a,inf), a = 0..5 ............................. <= 1e-18; a = 20: 1.5e-17
                                         (x * x rounding in the integrand, ~a^2 eps)
     (x-c) N(x; mu, s) on [c,inf), z = -8..30, u form ............. <= 2.3e-19
                                   x form (integrand-limited) ..... <= 3.3e-17 at z = 30
     |x - 0.3| on [0,1]: with the breakpoint 9.3e-20 (62 evaluations), without 1.2e-18 (1519)
     sqrt(x) on [0,1] 4.9e-19; 1/sqrt(x) on [0,1] 6.3e-16 (epsrel 1e-15)
     2D: bivariate normal (rho 0.6) mass, E[x], E[y], cov, var ...... <= 2e-19
         half-plane x + 2y > c ........................................ 3e-19
         unit disc area (pi) and x^2 moment (pi/4), y limits +-sqrt(1-x^2) <= 4.8e-19
     normal pdf/sf/cdf at |z| <= 37.5 (mpmath references) ........... <= 1e-19
   Runtime of the whole test: about 0.2 s at -O2, 0.25 s under clang ASan+UBSan.

   LICENCE: MIT (see README.md). */
#ifndef PF_ORACLE_H
#define PF_ORACLE_H

#include <float.h>
#include <math.h>
#include <stddef.h>

#ifndef PF_ORACLE_DEF
#  if defined(__GNUC__) || defined(__clang__)
#    define PF_ORACLE_DEF static __attribute__((unused))
#  else
#    define PF_ORACLE_DEF static inline
#  endif
#endif

#ifndef PF_ORACLE_MAX_INTERVALS
#  define PF_ORACLE_MAX_INTERVALS 2000
#endif
#define PF_ORACLE_MAX_POINTS 64 /* breakpoints accepted by one call */

/* Status codes (pf_oracle_result.status). */
#define PF_ORACLE_OK            0 /* converged: error <= max(epsabs, epsrel |value|) */
#define PF_ORACLE_MAX_INTERVALS_HIT 1 /* interval budget used up before converging */
#define PF_ORACLE_ROUNDOFF      2 /* tolerance below the rounding level; value is best effort */
#define PF_ORACLE_NONFINITE     3 /* the integrand returned inf or NaN; value is NaN */
#define PF_ORACLE_BAD_INPUT     4 /* NaN limit, too many points, budget < pieces */
#define PF_ORACLE_INNER_FAILED  5 /* 2D: outer converged, but some inner integral did not */

/* The integrand: f(x, ctx). ctx is passed through untouched. */
typedef long double (*pf_oracle_fn)(long double x, void *ctx);
/* 2D integrand f(x, y, ctx) and an inner limit or breakpoint generator as a function of x. */
typedef long double (*pf_oracle_fn2)(long double x, long double y, void *ctx);
typedef long double (*pf_oracle_limit_fn)(long double x, void *ctx);
/* Writes up to max_points inner breakpoints for this x into points; returns how many. */
typedef int (*pf_oracle_points_fn)(long double x, long double *points, int max_points, void *ctx);

typedef struct pf_oracle_result {
    long double value; /* the integral (K31 sums over the final partition) */
    long double error; /* estimated absolute error (conservative, see ERROR ESTIMATE) */
    int converged;     /* 1 when status is PF_ORACLE_OK */
    int status;        /* PF_ORACLE_OK, ... */
    int intervals;     /* intervals in the final partition (outer one for 2D) */
    long evals;        /* integrand evaluations, inner ones included for 2D */
} pf_oracle_result;

/* A 2D problem: integral over x in [ax, bx] of integral over y in [ylo(x), yhi(x)] of f.
   Make it with pf_oracle_2d_make, then set the optional fields. */
typedef struct pf_oracle_2d {
    pf_oracle_fn2 f;
    void *ctx;                  /* passed to f, ylo, yhi, ypoints */
    long double ax, bx;         /* outer limits, may be infinite */
    const long double *xpoints; /* optional outer breakpoints (NULL, 0 by default) */
    int nxpoints;
    long double ay, by;         /* inner limits where ylo / yhi is NULL; may be infinite */
    pf_oracle_limit_fn ylo;     /* optional inner lower limit as a function of x */
    pf_oracle_limit_fn yhi;     /* optional inner upper limit as a function of x */
    pf_oracle_points_fn ypoints; /* optional inner breakpoints as a function of x */
    long double epsabs;         /* default 0 */
    long double epsrel;         /* default 1e-16; each inner integral gets epsabs/8, epsrel/8 */
    int max_intervals;          /* for the outer and for each inner integral; default 400 */
} pf_oracle_2d;

/* ================================================================ normal distribution */

/* Exact product: a * b = *hi + *lo with *hi = fl(a * b) (Dekker's splitting, no FMA needed). */
PF_ORACLE_DEF void pf_oracle__two_prod(long double a, long double b, long double *hi,
                                       long double *lo)
{
    const long double split = ldexpl(1.0L, (LDBL_MANT_DIG + 1) / 2) + 1.0L;
    long double ta = split * a, tb = split * b;
    long double ah = ta - (ta - a), al = a - ah;
    long double bh = tb - (tb - b), bl = b - bh;
    *hi = a * b;
    *lo = ((ah * bh - *hi) + ah * bl + al * bh) + al * bl;
}

/* pf_oracle_normal_pdf(z) = exp(-z^2 / 2) / sqrt(2 pi), every z (0 beyond |z| ~ 150).
   z^2 is formed exactly as hi + lo, so the only errors are expl's and one product:
   relative error ~ 2 ulp of long double at any z. */
PF_ORACLE_DEF long double pf_oracle_normal_pdf(long double z)
{
    long double hi, lo;
    pf_oracle__two_prod(z, z, &hi, &lo);
    if (!(hi < 4.0L * (long double)LDBL_MAX_EXP)) return z != z ? z : 0.0L; /* NaN stays NaN */
    return 0.398942280401432677939946059934381868L * expl(-0.5L * hi) * (1.0L - 0.5L * lo);
}

/* 0.5 * erfc(z / sqrt 2) with z / sqrt 2 carried exactly to first order: erfcl is evaluated at
   y = fl(z c), c = 1/sqrt 2 as hi + lo, and corrected by -d * 2/sqrt(pi) exp(-y^2) for the
   remainder d = z c - y. The naive form loses about 2 y^2 eps relative in the tail. */
PF_ORACLE_DEF long double pf_oracle__half_erfc_scaled(long double z)
{
    const long double c_hi = 0.707106781186547524400844362104849039L; /* rounded 1/sqrt 2 */
    long double sq, sq_lo, c_lo, y, e, d;
    if (!(fabsl(z) < 1e30L)) return 0.5L * erfcl(z * c_hi); /* 0 or 1 exactly; inf, NaN */
    /* c_lo = 1/sqrt 2 - c_hi from one Newton step on c^2 = 1/2 with c_hi^2 formed exactly
       (0.5 - sq is exact by Sterbenz): portable to any long double format */
    pf_oracle__two_prod(c_hi, c_hi, &sq, &sq_lo);
    c_lo = ((0.5L - sq) - sq_lo) / (2.0L * c_hi);
    pf_oracle__two_prod(z, c_hi, &y, &e);
    d = e + z * c_lo;
    return 0.5L * (erfcl(y) - d * 1.12837916709551257389615890312154517L * expl(-y * y));
}

/* pf_oracle_normal_sf(z) = P(Z > z) = erfc(z / sqrt 2) / 2, accurate in relative terms far
   into the upper tail (until underflow near z = 150). */
PF_ORACLE_DEF long double pf_oracle_normal_sf(long double z)
{
    return pf_oracle__half_erfc_scaled(z);
}

/* pf_oracle_normal_cdf(z) = P(Z <= z) = erfc(-z / sqrt 2) / 2, accurate in the lower tail. */
PF_ORACLE_DEF long double pf_oracle_normal_cdf(long double z)
{
    return pf_oracle__half_erfc_scaled(-z);
}

/* ================================================================ Gauss-Kronrod G15-K31 */

#define PF_ORACLE__NG 15 /* Gauss points; the Kronrod rule has 2 NG + 1 */

/* Generated by bench/fit/gen_kronrod.py 15 (G15-K31). Abscissae in [0, 1), descending;
   the rule uses +-x. Odd entries (1, 3, ...) of the Kronrod list are the Gauss nodes. */
static const long double pf_oracle__xk[16] = {
    9.98002298693397060285172840152e-1L,
    9.87992518020485428489565718587e-1L,
    9.67739075679139134257347978784e-1L,
    9.37273392400705904307758947710e-1L,
    8.97264532344081900882509656454e-1L,
    8.48206583410427216200648320774e-1L,
    7.90418501442465932967649294818e-1L,
    7.24417731360170047416186054614e-1L,
    6.50996741297416970533735895313e-1L,
    5.70972172608538847537226737254e-1L,
    4.85081863640239680693655740232e-1L,
    3.94151347077563369897207370981e-1L,
    2.99180007153168812166780024266e-1L,
    2.01194093997434522300628303395e-1L,
    1.01142066918717499027074231447e-1L,
    0.0L,
};
static const long double pf_oracle__wk[16] = {
    5.37747987292334898779205143013e-3L,
    1.50079473293161225383747630758e-2L,
    2.54608473267153201868740010197e-2L,
    3.53463607913758462220379484784e-2L,
    4.45897513247648766082272993733e-2L,
    5.34815246909280872653431472394e-2L,
    6.20095678006706402851392309608e-2L,
    6.98541213187282587095200770991e-2L,
    7.68496807577203788944327774827e-2L,
    8.30805028231330210382892472861e-2L,
    8.85644430562117706472754436938e-2L,
    9.31265981708253212254868727473e-2L,
    9.66427269836236785051799076276e-2L,
    9.91735987217919593323931734846e-2L,
    1.00769845523875595044946662618e-1L,
    1.01330007014791549017374792767e-1L,
};
/* Gauss weights for the Gauss nodes pf_oracle__xk[1], [3], ... (the last one is the centre) */
static const long double pf_oracle__wg[8] = {
    3.07532419961172683546283935772e-2L,
    7.03660474881081247092674164507e-2L,
    1.07159220467171935011869546686e-1L,
    1.39570677926154314447804794511e-1L,
    1.66269205816993933553200860481e-1L,
    1.86161000015562211026800561866e-1L,
    1.98431485327111576456118326444e-1L,
    2.02578241925561272880620199968e-1L,
};

/* Map kinds of a piece: the integrand in t is f(x(t)) x'(t). */
#define PF_ORACLE__MAP_FINITE 0 /* x = t */
#define PF_ORACLE__MAP_UPPER  1 /* [base, inf):  x = base + t/(1-t), t in [0, 1) */
#define PF_ORACLE__MAP_LOWER  2 /* (-inf, base]: x = base - t/(1-t), t in [0, 1) */
#define PF_ORACLE__MAP_BOTH   3 /* (-inf, inf):  x = t/(1-t^2),      t in (-1, 1) */

typedef struct pf_oracle__piece {
    int map;
    long double base;
} pf_oracle__piece;

/* One interval of the partition, in t. prio is err, or -1 once the interval is frozen. */
typedef struct pf_oracle__interval {
    long double t0, t1, value, err, resabs, prio;
    int piece;
} pf_oracle__interval;

/* Everything one integration needs besides the heap (lives on the caller's stack). */
typedef struct pf_oracle__job {
    pf_oracle_fn f;
    void *ctx;
    const pf_oracle__piece *pieces;
    long evals;
    int nonfinite;
} pf_oracle__job;

/* The transformed integrand at t in piece p. */
PF_ORACLE_DEF long double pf_oracle__eval(pf_oracle__job *job, int p, long double t)
{
    const pf_oracle__piece *pc = &job->pieces[p];
    long double x, jac, v, u;
    switch (pc->map) {
    case PF_ORACLE__MAP_UPPER:
    case PF_ORACLE__MAP_LOWER:
        u = 1.0L - t;
        if (!(u > 0.0L)) return 0.0L; /* the singular end: contributes nothing */
        jac = 1.0L / (u * u);
        x = pc->map == PF_ORACLE__MAP_UPPER ? pc->base + t / u : pc->base - t / u;
        break;
    case PF_ORACLE__MAP_BOTH:
        u = (1.0L - t) * (1.0L + t);
        if (!(u > 0.0L)) return 0.0L;
        x = t / u;
        jac = (1.0L + t * t) / (u * u);
        break;
    default:
        x = t;
        jac = 1.0L;
        break;
    }
    job->evals++;
    v = job->f(x, job->ctx);
    if (jac != 1.0L) v *= jac;
    if (v != v || v - v != 0.0L) { /* NaN or inf */
        job->nonfinite = 1;
        return 0.0L;
    }
    return v;
}

/* Apply the K31 / G15 pair to [t0, t1] of piece p; fills value, err, resabs, prio. */
PF_ORACLE_DEF void pf_oracle__rule(pf_oracle__job *job, pf_oracle__interval *iv)
{
    const long double c = 0.5L * (iv->t0 + iv->t1), h = 0.5L * (iv->t1 - iv->t0);
    const long double fc = pf_oracle__eval(job, iv->piece, c);
    long double resk = pf_oracle__wk[PF_ORACLE__NG] * fc;
    long double resg = (PF_ORACLE__NG & 1) ? pf_oracle__wg[PF_ORACLE__NG / 2] * fc : 0.0L;
    long double resabs = pf_oracle__wk[PF_ORACLE__NG] * fabsl(fc);
    long double diff, noise;
    int j;
    for (j = 0; j < PF_ORACLE__NG; j++) {
        const long double d = h * pf_oracle__xk[j];
        const long double f1 = pf_oracle__eval(job, iv->piece, c - d);
        const long double f2 = pf_oracle__eval(job, iv->piece, c + d);
        resk += pf_oracle__wk[j] * (f1 + f2);
        resabs += pf_oracle__wk[j] * (fabsl(f1) + fabsl(f2));
        if (j & 1) resg += pf_oracle__wg[j / 2] * (f1 + f2);
    }
    iv->value = resk * h;
    iv->resabs = resabs * fabsl(h);
    diff = fabsl(resk - resg) * fabsl(h);
    noise = LDBL_EPSILON * iv->resabs;
    iv->err = diff + noise;
    /* frozen: the rules already agree to rounding level, bisecting cannot help */
    iv->prio = diff <= 32.0L * noise ? -1.0L : iv->err;
}

/* Can [t0, t1] be bisected so that the children's outermost nodes stay strictly inside? */
PF_ORACLE_DEF int pf_oracle__splittable(long double t0, long double t1)
{
    const long double m = 0.5L * (t0 + t1), hq = 0.25L * (t1 - t0);
    const long double off = hq * pf_oracle__xk[0];
    return t0 < m && m < t1 && t0 < (0.5L * (t0 + m)) - off && (0.5L * (t0 + m)) + off < m &&
           m < (0.5L * (m + t1)) - off && (0.5L * (m + t1)) + off < t1;
}

/* Binary max-heap on prio. */
PF_ORACLE_DEF void pf_oracle__heap_push(pf_oracle__interval *heap, int *n,
                                        const pf_oracle__interval *iv)
{
    int i = (*n)++;
    while (i > 0) {
        int parent = (i - 1) / 2;
        if (!(heap[parent].prio < iv->prio)) break;
        heap[i] = heap[parent];
        i = parent;
    }
    heap[i] = *iv;
}

PF_ORACLE_DEF pf_oracle__interval pf_oracle__heap_pop(pf_oracle__interval *heap, int *n)
{
    pf_oracle__interval top = heap[0], last = heap[--(*n)];
    int i = 0;
    for (;;) {
        int child = 2 * i + 1;
        if (child >= *n) break;
        if (child + 1 < *n && heap[child].prio < heap[child + 1].prio) child++;
        if (!(last.prio < heap[child].prio)) break;
        heap[i] = heap[child];
        i = child;
    }
    if (*n > 0) heap[i] = last;
    return top;
}

/* Exact sums over the partition: value, error, and the error of frozen intervals. */
PF_ORACLE_DEF void pf_oracle__sums(const pf_oracle__interval *heap, int n, long double *value,
                                   long double *err, long double *ferr)
{
    int i;
    *value = 0.0L;
    *err = 0.0L;
    *ferr = 0.0L;
    for (i = 0; i < n; i++) {
        *value += heap[i].value;
        *err += heap[i].err;
        if (heap[i].prio < 0.0L) *ferr += heap[i].err;
    }
}

/* The globally adaptive driver over npieces pieces, each starting as one interval in t. */
/* The result of a call that did no work: value 0, status PF_ORACLE_BAD_INPUT. */
PF_ORACLE_DEF pf_oracle_result pf_oracle__result_bad_input(void)
{
    pf_oracle_result r;
    r.value = 0.0L;
    r.error = 0.0L;
    r.converged = 0;
    r.status = PF_ORACLE_BAD_INPUT;
    r.intervals = 0;
    r.evals = 0;
    return r;
}

PF_ORACLE_DEF pf_oracle_result pf_oracle__adapt(pf_oracle__job *job, const long double *t0s,
                                                const long double *t1s, int npieces,
                                                long double epsabs, long double epsrel,
                                                int max_intervals)
{
    pf_oracle__interval heap[PF_ORACLE_MAX_INTERVALS];
    pf_oracle_result r;
    long double value = 0.0L, err = 0.0L, ferr = 0.0L; /* ferr: error of frozen intervals */
    int n = 0, i, iter = 0;
    r = pf_oracle__result_bad_input();
    if (max_intervals > PF_ORACLE_MAX_INTERVALS) max_intervals = PF_ORACLE_MAX_INTERVALS;
    if (npieces > max_intervals || !(epsabs >= 0.0L) || !(epsrel >= 0.0L)) return r;
    for (i = 0; i < npieces; i++) {
        pf_oracle__interval iv;
        iv.t0 = t0s[i];
        iv.t1 = t1s[i];
        iv.piece = i;
        pf_oracle__rule(job, &iv);
        if (!pf_oracle__splittable(iv.t0, iv.t1)) iv.prio = -1.0L;
        pf_oracle__heap_push(heap, &n, &iv);
    }
    pf_oracle__sums(heap, n, &value, &err, &ferr);
    for (;;) {
        pf_oracle__interval top, left, right;
        long double tol;
        int c;
        if (job->nonfinite) {
            r.status = PF_ORACLE_NONFINITE;
            break;
        }
        tol = epsabs > epsrel * fabsl(value) ? epsabs : epsrel * fabsl(value);
        /* Stop when converged; when out of intervals; or when the frozen intervals alone
           exceed the tolerance and the live ones no longer dominate (refining cannot help).
           Running sums drift (large errors were added and later removed), so every decision
           to stop is taken on exact sums, which are also refreshed every 16 steps. */
        if (err <= tol || n >= max_intervals || heap[0].prio < 0.0L ||
            (ferr > tol && err <= 2.0L * ferr) || (iter & 15) == 0) {
            pf_oracle__sums(heap, n, &value, &err, &ferr);
            tol = epsabs > epsrel * fabsl(value) ? epsabs : epsrel * fabsl(value);
            if (err <= tol) {
                r.status = PF_ORACLE_OK;
                break;
            }
            if (n >= max_intervals) {
                r.status = PF_ORACLE_MAX_INTERVALS_HIT;
                break;
            }
            /* every interval is at rounding level or unsplittable, or they decide the total */
            if (heap[0].prio < 0.0L || (ferr > tol && err <= 2.0L * ferr)) {
                r.status = PF_ORACLE_ROUNDOFF;
                break;
            }
        }
        iter++;
        top = pf_oracle__heap_pop(heap, &n);
        if (!pf_oracle__splittable(top.t0, top.t1)) {
            top.prio = -1.0L;
            ferr += top.err;
            pf_oracle__heap_push(heap, &n, &top);
            continue;
        }
        left = top;
        right = top;
        left.t1 = right.t0 = 0.5L * (top.t0 + top.t1);
        pf_oracle__rule(job, &left);
        pf_oracle__rule(job, &right);
        /* Noise: the halves together disagree at least a quarter as much as the whole did,
           at a level far below the integral of |f|. A smooth integrand gains orders of
           magnitude per bisection and a singular one keeps a large relative difference, so
           this is the integrand's own rounding (e.g. expl of a large, rounded exponent).
           Stop refining these two; their errors still count, so the call ends with
           PF_ORACLE_ROUNDOFF if they matter, never with a false "ok". */
        if (left.err + right.err >= 0.25L * top.err && top.err <= 1e-9L * top.resabs) {
            left.prio = -1.0L;
            right.prio = -1.0L;
        }
        for (c = 0; c < 2; c++) {
            const pf_oracle__interval *iv = c ? &right : &left;
            pf_oracle__heap_push(heap, &n, iv);
            value += iv->value;
            err += iv->err;
            if (iv->prio < 0.0L) ferr += iv->err;
        }
        value -= top.value;
        err -= top.err;
    }
    pf_oracle__sums(heap, n, &value, &err, &ferr);
    r.value = job->nonfinite ? (long double)NAN : value;
    r.error = job->nonfinite ? (long double)NAN : err;
    r.converged = r.status == PF_ORACLE_OK;
    r.intervals = n;
    r.evals = job->evals;
    return r;
}

PF_ORACLE_DEF int pf_oracle__is_inf(long double x) { return x > LDBL_MAX || x < -LDBL_MAX; }

/* integral of f over [a, b], split at the points strictly inside (a, b); see the top. */
PF_ORACLE_DEF pf_oracle_result pf_oracle_integrate_points(pf_oracle_fn f, void *ctx,
                                                          long double a, long double b,
                                                          const long double *points, int npoints,
                                                          long double epsabs, long double epsrel,
                                                          int max_intervals)
{
    pf_oracle__piece pieces[PF_ORACLE_MAX_POINTS + 1];
    long double cuts[PF_ORACLE_MAX_POINTS + 2];
    long double t0s[PF_ORACLE_MAX_POINTS + 1], t1s[PF_ORACLE_MAX_POINTS + 1];
    pf_oracle__job job;
    pf_oracle_result r;
    long double sign = 1.0L;
    int ncut = 0, i, j;
    r = pf_oracle__result_bad_input();
    if (a != a || b != b || npoints < 0 || npoints > PF_ORACLE_MAX_POINTS ||
        (npoints > 0 && points == NULL) || f == NULL)
        return r;
    if (a == b) {
        r.converged = 1;
        r.status = PF_ORACLE_OK;
        return r;
    }
    if (a > b) {
        long double tmp = a;
        a = b;
        b = tmp;
        sign = -1.0L;
    }
    /* sorted, distinct, finite cut points strictly inside (a, b), by insertion */
    cuts[ncut++] = a;
    for (i = 0; i < npoints; i++) {
        long double p = points[i];
        if (!(p > a && p < b) || pf_oracle__is_inf(p)) continue;
        for (j = ncut; j > 1 && cuts[j - 1] > p; j--) cuts[j] = cuts[j - 1];
        if (cuts[j - 1] == p) { /* duplicate: undo the shift */
            for (; j < ncut; j++) cuts[j] = cuts[j + 1];
            continue;
        }
        cuts[j] = p;
        ncut++;
    }
    cuts[ncut++] = b;
    for (i = 0; i + 1 < ncut; i++) {
        long double lo = cuts[i], hi = cuts[i + 1];
        int lo_inf = pf_oracle__is_inf(lo), hi_inf = pf_oracle__is_inf(hi);
        if (lo_inf && hi_inf) {
            pieces[i].map = PF_ORACLE__MAP_BOTH;
            pieces[i].base = 0.0L;
            t0s[i] = -1.0L;
            t1s[i] = 1.0L;
        } else if (hi_inf) {
            pieces[i].map = PF_ORACLE__MAP_UPPER;
            pieces[i].base = lo;
            t0s[i] = 0.0L;
            t1s[i] = 1.0L;
        } else if (lo_inf) {
            pieces[i].map = PF_ORACLE__MAP_LOWER;
            pieces[i].base = hi;
            t0s[i] = 0.0L;
            t1s[i] = 1.0L;
        } else {
            pieces[i].map = PF_ORACLE__MAP_FINITE;
            pieces[i].base = 0.0L;
            t0s[i] = lo;
            t1s[i] = hi;
        }
    }
    job.f = f;
    job.ctx = ctx;
    job.pieces = pieces;
    job.evals = 0;
    job.nonfinite = 0;
    r = pf_oracle__adapt(&job, t0s, t1s, ncut - 1, epsabs, epsrel, max_intervals);
    r.value *= sign;
    return r;
}

/* integral of f over [a, b] (either may be infinite) to max(epsabs, epsrel |I|), bisecting at
   most until max_intervals intervals (capped at PF_ORACLE_MAX_INTERVALS). */
PF_ORACLE_DEF pf_oracle_result pf_oracle_integrate(pf_oracle_fn f, void *ctx, long double a,
                                                   long double b, long double epsabs,
                                                   long double epsrel, int max_intervals)
{
    return pf_oracle_integrate_points(f, ctx, a, b, NULL, 0, epsabs, epsrel, max_intervals);
}

/* ================================================================ nested 2D */

/* State shared by the outer integrand and the inner one; on the caller's stack. */
typedef struct pf_oracle__inner {
    const pf_oracle_2d *pb;
    long double x;
    long evals;
    int failures;
} pf_oracle__inner;

PF_ORACLE_DEF long double pf_oracle__inner_fn(long double y, void *ctx)
{
    pf_oracle__inner *in = (pf_oracle__inner *)ctx;
    return in->pb->f(in->x, y, in->pb->ctx);
}

PF_ORACLE_DEF long double pf_oracle__outer_fn(long double x, void *ctx)
{
    pf_oracle__inner *in = (pf_oracle__inner *)ctx;
    const pf_oracle_2d *pb = in->pb;
    long double pts[PF_ORACLE_MAX_POINTS];
    long double lo = pb->ylo ? pb->ylo(x, pb->ctx) : pb->ay;
    long double hi = pb->yhi ? pb->yhi(x, pb->ctx) : pb->by;
    int np = 0;
    pf_oracle_result r;
    in->x = x;
    if (pb->ypoints) {
        np = pb->ypoints(x, pts, PF_ORACLE_MAX_POINTS, pb->ctx);
        if (np < 0) np = 0;
        if (np > PF_ORACLE_MAX_POINTS) np = PF_ORACLE_MAX_POINTS;
    }
    if (!(hi > lo)) return 0.0L; /* empty (or reversed: treated as empty) inner range */
    r = pf_oracle_integrate_points(pf_oracle__inner_fn, in, lo, hi, pts, np, 0.125L * pb->epsabs,
                                   0.125L * pb->epsrel, pb->max_intervals);
    in->evals += r.evals;
    /* ROUNDOFF is accepted: the inner value is then as good as long double allows (it happens
       where the inner integral nearly cancels, e.g. a conditional mean crossing 0) */
    if (r.status != PF_ORACLE_OK && r.status != PF_ORACLE_ROUNDOFF) in->failures++;
    return r.value;
}

/* A 2D problem with constant limits (any may be infinite), no breakpoints, epsabs 0,
   epsrel 1e-16, max_intervals 400 (outer and each inner). */
PF_ORACLE_DEF pf_oracle_2d pf_oracle_2d_make(pf_oracle_fn2 f, void *ctx, long double ax,
                                             long double bx, long double ay, long double by)
{
    pf_oracle_2d pb;
    pb.f = f;
    pb.ctx = ctx;
    pb.ax = ax;
    pb.bx = bx;
    pb.xpoints = NULL;
    pb.nxpoints = 0;
    pb.ay = ay;
    pb.by = by;
    pb.ylo = NULL;
    pb.yhi = NULL;
    pb.ypoints = NULL;
    pb.epsabs = 0.0L;
    pb.epsrel = 1e-16L;
    pb.max_intervals = 400;
    return pb;
}

/* integral over x in [ax, bx] of integral over y in [ylo(x), yhi(x)] of f(x, y). The inner
   integrals ask for epsabs/8 and epsrel/8 so their errors stay a small part of the outer
   tolerance; the outer Kronrod-Gauss estimate also sees any inner noise. Where yhi(x) <= ylo(x)
   the inner integral is 0; ax > bx gives minus the integral over [bx, ax].
   status: PF_ORACLE_INNER_FAILED when the outer converged but an inner integral ran out of
   intervals or saw a non-finite value; evals counts every f call. */
PF_ORACLE_DEF pf_oracle_result pf_oracle_integrate_2d(const pf_oracle_2d *pb)
{
    pf_oracle__inner in;
    pf_oracle_result r;
    in.pb = pb;
    in.x = 0.0L;
    in.evals = 0;
    in.failures = 0;
    r = pf_oracle_integrate_points(pf_oracle__outer_fn, &in, pb->ax, pb->bx, pb->xpoints,
                                   pb->nxpoints, pb->epsabs, pb->epsrel, pb->max_intervals);
    r.evals = in.evals;
    if (r.status == PF_ORACLE_OK && in.failures > 0) {
        r.status = PF_ORACLE_INNER_FAILED;
        r.converged = 0;
    }
    return r;
}

/* A short name for a status code, for test notes. */
PF_ORACLE_DEF const char *pf_oracle_status_name(int status)
{
    switch (status) {
    case PF_ORACLE_OK: return "ok";
    case PF_ORACLE_MAX_INTERVALS_HIT: return "max-intervals";
    case PF_ORACLE_ROUNDOFF: return "roundoff";
    case PF_ORACLE_NONFINITE: return "nonfinite";
    case PF_ORACLE_BAD_INPUT: return "bad-input";
    case PF_ORACLE_INNER_FAILED: return "inner-failed";
    default: return "unknown";
    }
}

/* ================================================================ reference formulas
   Long double references that several tests and benches need, written once here from the
   papers (still nothing from include/). */

/* Bivariate normal density at offset (dx, dy) from the mean, covariance [[vx, c], [c, vy]]
   (the slope PDF P22 of Dupuy et al. 2013 eq. 8), by the explicit inverse. */
PF_ORACLE_DEF long double pf_oracle_normal2_pdf(long double dx, long double dy, long double vx,
                                                long double vy, long double c)
{
    long double det = vx * vy - c * c;
    return expl(-0.5L * (vy * dx * dx - 2.0L * c * dx * dy + vx * dy * dy) / det) /
           (6.28318530717958647692528676655900577L * sqrtl(det));
}

/* Smith's Lambda of Gaussian slopes as a function of nu (Dupuy et al. 2013 sec. 4.3):
       Lambda(nu) = exp(-nu^2) / (2 nu sqrt(pi)) - erfc(nu) / 2,
   as written for nu <= 2 (the two terms cancel by at most ~10x there); for nu > 2 through
   the Laplace continued fraction sqrt(pi) exp(nu^2) erfc(nu) = 1 / (nu + T),
   T = (1/2) / (nu + 1 / (nu + (3/2) / (nu + ...))), evaluated backwards from
   40 + 240/nu^2 terms, so Lambda = exp(-nu^2) / (2 sqrt(pi)) T / (nu (nu + T)) carries no
   cancellation. Checked against __float128 at nu = 1e-3 ... 10: <= 2e-18 relative.
   nu <= 0 (on or below the mean plane) gives HUGE_VALL. */
PF_ORACLE_DEF long double pf_oracle_lambda_beckmann(long double nu)
{
    const long double sqrt_pi = 1.772453850905516027298167483341145182798L;
    long double t = 0.0L;
    int k, kmax;
    if (!(nu > 0.0L)) return HUGE_VALL;
    if (nu <= 2.0L) return expl(-nu * nu) / (2.0L * sqrt_pi * nu) - 0.5L * erfcl(nu);
    kmax = 40 + (int)(240.0L / (nu * nu));
    for (k = kmax; k >= 1; --k) t = (0.5L * (long double)k) / (nu + t);
    return expl(-nu * nu) / (2.0L * sqrt_pi) * t / (nu * (nu + t));
}

typedef struct pf_oracle__tail {
    long double c, mu, sigma;
} pf_oracle__tail;

PF_ORACLE_DEF long double pf_oracle__tail_fn(long double u, void *ctx)
{
    const pf_oracle__tail *g = (const pf_oracle__tail *)ctx;
    return u * pf_oracle_normal_pdf((g->c + u - g->mu) / g->sigma) / g->sigma;
}

/* Smith's Lambda from its definition, by quadrature (Dupuy et al. 2013 eq. 13 text, with the
   mesosurface normalization of pf_smith.h (1)): for slopes along the view azimuth of mean mu
   and deviation sigma, seen at cot theta = c > mu,
       Lambda = integral_c^inf (x - c) N(x; mu, sigma^2) dx / (c - mu),
   integrated in u = x - c so the tail keeps its relative accuracy. */
PF_ORACLE_DEF long double pf_oracle_lambda_1d(long double c, long double mu, long double sigma)
{
    pf_oracle__tail g;
    pf_oracle_result r;
    g.c = c;
    g.mu = mu;
    g.sigma = sigma;
    r = pf_oracle_integrate(pf_oracle__tail_fn, &g, 0.0L, HUGE_VALL, 0.0L, 1e-18L, PF_ORACLE_MAX_INTERVALS);
    return r.value / (c - mu);
}

#endif /* PF_ORACLE_H */

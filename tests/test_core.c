/* test_core.c - tests of pf_core.h: pf_erfc / pf_erf against long double erfcl / erfl,
   their edge cases, pf_atan2 against atan2l, the scalar helpers and the small vectors (cross-checked against GLM
   when compiled as C++).

   Built as C99 float, C99 double (-DPF_DOUBLE), C++11, clang sanitizers and -ffast-math
   (edge_* tests only). The accuracy tests assert the bounds stated in pf_core.h and
   docs/core.md and record the measured maxima with pf_test_note. */
#include <string.h>
#include "pf_core.h"
#include "pf_test.h"

#ifdef __cplusplus
#  include <glm/glm.hpp>
#endif

#ifdef PF_DOUBLE
#  define T_NEXT(x, to) nextafter(x, to)
#else
#  define T_NEXT(x, to) nextafterf(x, to)
#endif

/* ------------------------------------------------------------------ bounds (see docs/core.md) */
#ifdef PF_DOUBLE
#  define ERFC_MAX_ULP 2.5L      /* normal results */
#  define ERF_MAX_ULP 2.5L
#  define ERFC_SUB_UNITS 2.0L    /* subnormal results: absolute error in 2^-1074 */
#  define ERFC_ZERO_AT 27.25     /* erfc(x) < 2^-1075 from here on: rounds to 0 */
#  define ERFC_TAIL_END 27.5
#else
#  define ERFC_MAX_ULP 2.0L
#  define ERF_MAX_ULP 2.0L
#  define ERFC_SUB_UNITS 2.0L    /* in units of 2^-149 */
#  define ERFC_ZERO_AT 10.07
#  define ERFC_TAIL_END 10.5
#endif

/* Accumulates the error of one function over many points: ulps where the reference is a
   normal number, units of the smallest subnormal where it is not. */
typedef struct acc_err {
    pf_test_max normal;
    pf_test_max sub;
    long n;
} acc_err;

static acc_err acc_init(void)
{
    acc_err a;
    a.normal = pf_test_max_init();
    a.sub = pf_test_max_init();
    a.n = 0;
    return a;
}

static void acc_erfc(acc_err *a, pf_real x)
{
    long double ref = erfcl((long double)x);
    long double e = pf_test_ulp_error(pf_erfc(x), ref);
    if (fabsl(ref) >= (long double)PF_REAL_MIN) pf_test_max_update(&a->normal, e, (long double)x);
    else pf_test_max_update(&a->sub, e, (long double)x);
    a->n++;
}

static void acc_erf(acc_err *a, pf_real x)
{
    long double ref = erfl((long double)x);
    long double e = pf_test_ulp_error(pf_erf(x), ref);
    if (fabsl(ref) >= (long double)PF_REAL_MIN || ref == 0.0L) pf_test_max_update(&a->normal, e, (long double)x);
    else pf_test_max_update(&a->sub, e, (long double)x);
    a->n++;
}

/* Points where the method changes: the small/large split of erfc and erf, the exp tail
   switch, the subnormal and underflow boundaries, the clamp. */
static const double erfc_breaks[] = {0.0, 0.5, 1.0, 9.19, 9.274, 9.345, 10.05, 10.125, 26.46, 26.55, 27.23, 27.25};

static void test_erfc_grid(void)
{
    acc_err a = acc_init();
    int i, k;
    /* uniform grid over the whole interesting line, both signs */
    for (i = 0; i <= 200000; ++i) {
        double x = -6.0 + (ERFC_TAIL_END + 6.0) * i / 200000.0;
        acc_erfc(&a, (pf_real)x);
    }
    /* dense neighbourhoods of every break point (a few thousand ulps either side) */
    for (k = 0; k < (int)(sizeof erfc_breaks / sizeof erfc_breaks[0]); ++k) {
        pf_real c = (pf_real)erfc_breaks[k];
        pf_real x = c, y = c;
        for (i = 0; i < 4000; ++i) {
            acc_erfc(&a, x);
            acc_erfc(&a, -y);
            acc_erfc(&a, y);
            x = T_NEXT(x, (pf_real)100);
            y = T_NEXT(y, (pf_real)-100);
        }
    }
    pf_test_note("%ld points: max %.3Lf ulp at x=%.9Lg (normal), %.3Lf x min-subnormal at x=%.9Lg", a.n,
                 a.normal.err, a.normal.at, a.sub.err, a.sub.at);
    PF_CHECK(a.normal.err <= ERFC_MAX_ULP, "erfc max %.3Lf ulp at x=%.9Lg", a.normal.err, a.normal.at);
    PF_CHECK(a.sub.err <= ERFC_SUB_UNITS, "erfc subnormal max %.3Lf units at x=%.9Lg", a.sub.err, a.sub.at);
}

static void test_erfc_random(void)
{
    acc_err a = acc_init();
    pf_test_rng r = pf_test_rng_seed(0xE4FC0001ULL);
    int i;
    for (i = 0; i < 150000; ++i) {
        acc_erfc(&a, (pf_real)pf_test_uniform(&r, -7.0, ERFC_TAIL_END + 0.5));
        acc_erfc(&a, (pf_real)(pf_test_log_uniform(&r, 1e-30, 1.0) * (i & 1 ? -1.0 : 1.0)));
    }
    pf_test_note("%ld points: max %.3Lf ulp at x=%.9Lg (normal), %.3Lf x min-subnormal at x=%.9Lg", a.n,
                 a.normal.err, a.normal.at, a.sub.err, a.sub.at);
    PF_CHECK(a.normal.err <= ERFC_MAX_ULP, "erfc max %.3Lf ulp at x=%.9Lg", a.normal.err, a.normal.at);
    PF_CHECK(a.sub.err <= ERFC_SUB_UNITS, "erfc subnormal max %.3Lf units at x=%.9Lg", a.sub.err, a.sub.at);
}

static void test_erf_grid_random(void)
{
    acc_err a = acc_init();
    pf_test_rng r = pf_test_rng_seed(0xE4F00002ULL);
    int i;
    for (i = 0; i <= 100000; ++i) acc_erf(&a, (pf_real)(-7.0 + 14.0 * i / 100000.0));
    for (i = 0; i < 100000; ++i) {
        acc_erf(&a, (pf_real)pf_test_uniform(&r, -6.0, 6.0));
        /* tiny |x| down to subnormals: erf must stay relatively accurate */
        acc_erf(&a, (pf_real)(pf_test_log_uniform(&r, 1e-40, 1.0) * (i & 1 ? -1.0 : 1.0)));
    }
    pf_test_note("%ld points: max %.3Lf ulp at x=%.9Lg; subnormal results max %.3Lf units at x=%.9Lg", a.n,
                 a.normal.err, a.normal.at, a.sub.err, a.sub.at);
    PF_CHECK(a.normal.err <= ERF_MAX_ULP, "erf max %.3Lf ulp at x=%.9Lg", a.normal.err, a.normal.at);
    PF_CHECK(a.sub.err <= 1.0L, "erf subnormal max %.3Lf units at x=%.9Lg", a.sub.err, a.sub.at);
}

/* pf_erfc_fast, the shader tier: relative error against erfcl where erfc is a normal number,
   asserted against the bound its comment states (float: 2e-6 + 6e-8 x^2, the second term the
   rounding of x*x inside exp; double: 1.5e-6, the fit), on a dense grid of both signs and on
   log-uniform small |x|. Abramowitz & Stegun 7.1.26, the formula it replaces at the same cost,
   is measured alongside to record what "relative" buys in the tail. */
static pf_real as_7_1_26(pf_real x)
{
    pf_real ax = PF_FABS(x);
    pf_real t = PF_R(1.0) / (PF_R(1.0) + PF_R(0.3275911) * ax);
    pf_real y = t * (PF_R(0.254829592) + t * (PF_R(-0.284496736) + t * (PF_R(1.421413741) +
                t * (PF_R(-1.453152027) + t * PF_R(1.061405429))))) * PF_EXP(-ax * ax);
    return x < PF_R(0.0) ? PF_R(2.0) - y : y;
}

static void test_erfc_fast(void)
{
    pf_test_rng r = pf_test_rng_seed(0xE4FC0017ULL);
    long double worst = 0, worst_excess = 0, worst_as = 0, at = 0, at_excess = 0;
    int i, n = 0;
    for (i = 0; i <= 400000; ++i) {
        pf_real x = i < 300000 ? (pf_real)(-6.0 + 16.0 * i / 300000.0)
                               : (pf_real)(pf_test_log_uniform(&r, 1e-30, 1.0) * (i & 1 ? -1.0 : 1.0));
        long double ref = erfcl((long double)x), e, bound;
        if (!(ref >= (long double)PF_REAL_MIN)) continue;
        e = fabsl(((long double)pf_erfc_fast(x) - ref) / ref);
#ifdef PF_DOUBLE
        bound = 1.5e-6L;
#else
        bound = 2e-6L + 6e-8L * (long double)x * (long double)x;
#endif
        if (e > worst) { worst = e; at = (long double)x; }
        if (e - bound > worst_excess || n == 0) { worst_excess = e - bound; at_excess = (long double)x; }
        if ((long double)x < 9.2L) {
            long double ea = fabsl(((long double)as_7_1_26(x) - ref) / ref);
            if (ea > worst_as) worst_as = ea;
        }
        n++;
    }
    pf_test_note("%d points: max rel %.3Lg at x=%.6Lg (A&S 7.1.26 on the same points: %.3Lg)", n, worst, at, worst_as);
    PF_CHECK(worst_excess <= 0.0L, "pf_erfc_fast exceeds its bound by %.3Lg at x=%.9Lg", worst_excess, at_excess);
}

/* pfi_split_hi must give the same halves when a compiler contracts it into FMAs (GPUs, and
   gcc's default -ffp-contract=fast with -mfma): (a + s) - s with s = 2^12 a (2^27 a) computed
   as fma(a, 2^12, a) and fma(-a, 2^12, t) is the same arithmetic, since a * 2^12 is exact.
   Checked with explicit fma on every binade, and the halves' widths checked: 12 (26)
   significant bits each, so their products are exact. (Veltkamp's c - (c - a) contracted
   returned a itself: pf_erfc reached 2.09 ulp with -ffp-contract=fast -mfma.) */
static void test_split_contraction_invariant(void)
{
#if !defined(__FAST_MATH__)
    pf_test_rng r = pf_test_rng_seed(0x5917ULL);
#  ifdef PF_DOUBLE
    const pf_real s = PF_R(134217728.0);
    const int half_bits = 26;
#  else
    const pf_real s = PF_R(4096.0);
    const int half_bits = 12;
#  endif
    int i, bad = 0, wide = 0;
    for (i = 0; i < 200000; ++i) {
        pf_real a = (pf_real)(pf_test_log_uniform(&r, 1e-30, 1e30));
        pf_real h = pfi_split_hi(a), l = a - h;
#  ifdef PF_DOUBLE
        pf_real hf = fma(-a, s, fma(a, s, a));
#  else
        pf_real hf = fmaf(-a, s, fmaf(a, s, a));
#  endif
        int e;
        long double mh = frexpl((long double)h, &e), ml;
        if (hf != h || (long double)h + (long double)l != (long double)a) bad++;
        /* significant bits: the scaled mantissas must be integers */
        ml = l == PF_R(0.0) ? 0.0L : frexpl((long double)l, &e);
        if (ldexpl(mh, half_bits + 1) != floorl(ldexpl(mh, half_bits + 1)) ||
            ldexpl(ml, half_bits + 1) != floorl(ldexpl(ml, half_bits + 1)))
            wide++;
    }
    pf_test_note("200000 values 1e-30..1e30: %d differ under explicit fma, %d halves wider than %d bits", bad, wide,
                 half_bits + 1);
    PF_CHECK(bad == 0 && wide == 0, "%d contraction mismatches, %d wide halves", bad, wide);
#endif
}

/* The tier's edge behaviour (also under -ffast-math): range [0, 2], the limits, symmetry
   erfc(-x) = 2 - erfc(x), non-increasing within its accuracy. */
static void edge_erfc_fast(void)
{
    static const double xs[] = {-1e30, -30.0, -10.0, -1.0, -1e-20, 0.0, 1e-30, 0.5, 3.0, 9.0, 10.05, 10.2, 30.0, 1e30};
    int i, bad = 0;
    pf_real prev = PF_R(2.0);
    for (i = 0; i < (int)(sizeof xs / sizeof xs[0]); ++i) {
        pf_real v = pf_erfc_fast((pf_real)xs[i]);
        if (!pf_test_finite(v) || v < PF_R(0.0) || v > PF_R(2.0)) bad++;
    }
    PF_CHECK(bad == 0, "%d values outside [0, 2]", bad);
    PF_CHECK(pf_erfc_fast(PF_R(1e30)) == PF_R(0.0) && pf_erfc_fast(PF_R(-1e30)) == PF_R(2.0), "limits");
    PF_CHECK(fabsl((long double)pf_erfc_fast(PF_R(0.0)) - 1.0L) < 2e-6L, "erfc_fast(0) = %.9g", (double)pf_erfc_fast(PF_R(0.0)));
    for (i = 0; i <= 20000; ++i) {
        pf_real x = (pf_real)(-6.0 + 16.0 * i / 20000.0), v = pf_erfc_fast(x);
        /* + PF_REAL_MIN: near x = 10 the float values are subnormal (erfc(10) = 2e-45), and
           -ffast-math flushes subnormals to zero in some operations and not in others (clang
           -O3 vectorizes this loop), so prev * (1 + 4e-6) can read 0 where v does not */
        if ((long double)v > (long double)prev * (1.0L + 4e-6L) + (long double)PF_REAL_MIN) bad++;
        /* exact reflection except at x = 0, where erfc_fast(+-0) = 1 - 1.4e-6 (the fit) */
        if (fabsl((long double)pf_erfc_fast(-x) - (2.0L - (long double)v)) > 4.0L * PF_TEST_EPS + 3e-6L) bad++;
        prev = v;
    }
    PF_CHECK(bad == 0, "%d steps not monotone or not symmetric", bad);
}

/* ------------------------------------------------------------------ erfc / erf edge cases
   These run in the -ffast-math builds too, so they check values that survive it (exact
   simple cases, range, symmetry, monotonicity with a small slack); the checks that need
   IEEE semantics (inf, NaN, signed zero, subnormals) are skipped under __FAST_MATH__. */
static void edge_erfc_special_values(void)
{
    PF_CHECK(pf_erfc(PF_R(0.0)) == PF_R(1.0), "erfc(0) = %.9g", (double)pf_erfc(PF_R(0.0)));
    PF_CHECK(pf_erfc(-PF_R(0.0)) == PF_R(1.0), "erfc(-0) = %.9g", (double)pf_erfc(-PF_R(0.0)));
    PF_CHECK(pf_erf(PF_R(0.0)) == PF_R(0.0), "erf(0) = %.9g", (double)pf_erf(PF_R(0.0)));
    PF_CHECK(pf_erfc(PF_R(1e30)) == PF_R(0.0), "erfc(1e30) = %.9g", (double)pf_erfc(PF_R(1e30)));
    PF_CHECK(pf_erfc(-PF_R(1e30)) == PF_R(2.0), "erfc(-1e30) = %.9g", (double)pf_erfc(-PF_R(1e30)));
    PF_CHECK(pf_erfc(PF_REAL_MAX) == PF_R(0.0), "erfc(max) = %.9g", (double)pf_erfc(PF_REAL_MAX));
    PF_CHECK(pf_erfc(-PF_REAL_MAX) == PF_R(2.0), "erfc(-max) = %.9g", (double)pf_erfc(-PF_REAL_MAX));
    PF_CHECK(pf_erf(PF_REAL_MAX) == PF_R(1.0), "erf(max) = %.9g", (double)pf_erf(PF_REAL_MAX));
    PF_CHECK(pf_erf(-PF_REAL_MAX) == PF_R(-1.0), "erf(-max) = %.9g", (double)pf_erf(-PF_REAL_MAX));
#ifndef __FAST_MATH__
    PF_CHECK(pf_erfc(PF_R(ERFC_ZERO_AT)) == PF_R(0.0), "erfc(%g) = %.9g", ERFC_ZERO_AT,
             (double)pf_erfc(PF_R(ERFC_ZERO_AT)));
#else
    /* -ffast-math gives up exact rounding: the true value rounds to 0, and clang -O3
       -ffast-math returns the smallest subnormal (measured); in range is what fast-math keeps */
    PF_CHECK(pf_erfc(PF_R(ERFC_ZERO_AT)) >= PF_R(0.0) &&
             pf_erfc(PF_R(ERFC_ZERO_AT)) <= PF_REAL_MIN * PF_REAL_EPSILON, "erfc(%g) = %.9g", ERFC_ZERO_AT,
             (double)pf_erfc(PF_R(ERFC_ZERO_AT)));
#endif
#ifndef __FAST_MATH__
    {
        pf_real inf = PF_REAL_MAX * PF_R(2.0);
        pf_real nan = inf - inf;
        PF_CHECK(pf_erfc(inf) == PF_R(0.0) && pf_erfc(-inf) == PF_R(2.0), "erfc(+-inf) = %g, %g",
                 (double)pf_erfc(inf), (double)pf_erfc(-inf));
        PF_CHECK(pf_erf(inf) == PF_R(1.0) && pf_erf(-inf) == PF_R(-1.0), "erf(+-inf) = %g, %g",
                 (double)pf_erf(inf), (double)pf_erf(-inf));
        PF_CHECK(isnan((double)pf_erfc(nan)) && isnan((double)pf_erf(nan)), "NaN in gives %g, %g",
                 (double)pf_erfc(nan), (double)pf_erf(nan));
        PF_CHECK(signbit((double)pf_erf(-PF_R(0.0))), "erf(-0) = %g, want -0", (double)pf_erf(-PF_R(0.0)));
    }
#endif
}

static void edge_erf_tiny(void)
{
    /* erf(x) ~ 2x/sqrt(pi) down to the smallest subnormal: never 1 - erfc */
    pf_real x = PF_R(1e-3);
    int i;
    for (i = 0; i < 400 && x > PF_R(0.0); ++i, x = x * PF_R(0.7)) {
        pf_real e = pf_erf(x), m = pf_erf(-x);
        PF_CHECK(pf_test_finite(e) && e == -m, "erf(%g) = %g, erf(-x) = %g", (double)x, (double)e, (double)m);
        PF_CHECK(pf_erfc(x) <= PF_R(1.0) && pf_erfc(-x) >= PF_R(1.0), "erfc(+-%g) = %.9g %.9g", (double)x,
                 (double)pf_erfc(x), (double)pf_erfc(-x));
#ifndef __FAST_MATH__
        /* relative error (one ulp of slack) where x is normal, absolute below */
        long double want = erfl((long double)x);
        if (x >= PF_REAL_MIN) {
            PF_CHECK(pf_test_rel_error((long double)e, want) <= 2.0L * (long double)PF_REAL_EPSILON,
                     "erf(%g) = %.9g, want %.9Lg", (double)x, (double)e, want);
        } else {
            PF_CHECK(pf_test_ulp_error(e, want) <= 1.0L, "erf(%g) = %g, want %Lg", (double)x, (double)e, want);
        }
#else
        PF_CHECK(e >= PF_R(0.0) && e <= PF_R(1.2) * x + PF_REAL_MIN, "erf(%g) = %g", (double)x, (double)e);
#endif
    }
}

static void edge_erfc_range_symmetry(void)
{
    pf_test_rng r = pf_test_rng_seed(0xED6E0003ULL);
    int i, bad_range = 0, bad_sym = 0, bad_fin = 0;
    for (i = 0; i < 60000; ++i) {
        /* log-uniform magnitudes from 1e-30 to 1e30, both signs */
        pf_real x = (pf_real)(pf_test_log_uniform(&r, 1e-30, 1e30) * (i & 1 ? -1.0 : 1.0));
        pf_real c = pf_erfc(x), e = pf_erf(x), en = pf_erf(-x);
        if (!pf_test_finite(c) || !pf_test_finite(e)) bad_fin++;
        if (!(c >= PF_R(0.0) && c <= PF_R(2.0) && e >= PF_R(-1.0) && e <= PF_R(1.0))) bad_range++;
        if (en != -e) bad_sym++;
    }
    PF_CHECK(bad_fin == 0, "%d non-finite results for finite inputs", bad_fin);
    PF_CHECK(bad_range == 0, "%d results outside [0, 2] / [-1, 1]", bad_range);
    PF_CHECK(bad_sym == 0, "%d inputs with erf(-x) != -erf(x)", bad_sym);
}

/* erfc must not increase, also across the internal boundaries and into the underflow. */
static void edge_erfc_monotonic(void)
{
    /* slack: none in IEEE builds (a correctly rounded monotone function stays monotone to
       within the error bound; check with 4 ulp), a relative 1e-4 under fast-math */
#ifdef __FAST_MATH__
    const long double slack = 1e-4L;
#else
    const long double slack = 4.0L * (long double)PF_REAL_EPSILON;
#endif
    pf_real prev = pf_erfc(PF_R(-7.0));
    int i, bad = 0;
    double worst_at = 0.0;
    for (i = 1; i <= 100000; ++i) {
        pf_real x = (pf_real)(-7.0 + (ERFC_TAIL_END + 7.5) * i / 100000.0);
        pf_real c = pf_erfc(x);
        if ((long double)c > (long double)prev * (1.0L + slack)) {
            if (!bad) worst_at = (double)x;
            bad++;
        }
        prev = c;
    }
    PF_CHECK(bad == 0, "%d increases, first at x=%.9g", bad, worst_at);
    /* ulp by ulp across each break point */
    {
        int k;
        for (k = 0; k < (int)(sizeof erfc_breaks / sizeof erfc_breaks[0]); ++k) {
            pf_real x = T_NEXT((pf_real)erfc_breaks[k], (pf_real)-100);
            pf_real p = pf_erfc(x);
            int j;
            x = (pf_real)erfc_breaks[k];
            for (j = 0; j < 2000; ++j) {
                pf_real sx = x;
                pf_real c;
                x = T_NEXT(x, (pf_real)100);
                c = pf_erfc(sx);
                PF_CHECK((long double)c <= (long double)p * (1.0L + slack),
                         "erfc increases at x=%.9g: %.9g after %.9g", (double)sx, (double)c, (double)p);
                p = c;
            }
        }
    }
}

static void edge_erfc_underflow(void)
{
    /* tail: non-negative, tiny, exactly 0 past the underflow point */
    pf_real x;
    int bad = 0;
    for (x = PF_R(ERFC_ZERO_AT) - PF_R(1.0); x < PF_R(ERFC_ZERO_AT) + PF_R(2.0); x += PF_R(0.001)) {
        pf_real c = pf_erfc(x);
        if (!(c >= PF_R(0.0)) || !(c < PF_R(1e-30)) || (x >= PF_R(ERFC_ZERO_AT) && c != PF_R(0.0))) bad++;
        if (pf_erfc(-x) != PF_R(2.0) || pf_erf(x) != PF_R(1.0)) bad++;
    }
    PF_CHECK(bad == 0, "%d bad values in the tail", bad);
}

/* ------------------------------------------------------------------ scalar helpers */
/* pf_exp_neg_sq(x) = exp(-x*x) against expl of the exactly formed long double square, over
   every region where the result is normal (|x| < 9.3 float, 26.6 double), dense grid plus
   seeded random points; the plain PF_EXP(-x*x) is measured alongside to show what the split
   buys. Bound: 1.5 ulp (pf_core.h). */
static void test_exp_neg_sq(void)
{
#ifdef PF_DOUBLE
    const double top = 26.6;
#else
    const double top = 9.3;
#endif
    pf_test_max m = pf_test_max_init(), naive = pf_test_max_init();
    pf_test_rng rng = pf_test_rng_seed(0xe4e5ULL);
    int i;
    for (i = 0; i < 400000; i++) {
        pf_real x = (pf_real)(i < 200000 ? top * (double)i / 200000.0 : pf_test_uniform(&rng, -top, top));
        long double lx = (long double)x;
        long double ref = expl(-lx * lx); /* lx*lx is exact in long double for float and double x */
        if (ref < (long double)PF_REAL_MIN) continue;
        pf_test_max_update(&m, pf_test_ulp_error(pf_exp_neg_sq(x), ref), lx);
        pf_test_max_update(&naive, pf_test_ulp_error(PF_EXP(-x * x), ref), lx);
    }
    pf_test_note("max %.2f ulp at x=%.6g (PF_EXP(-x*x): %.1f ulp at x=%.4g)", (double)m.err, (double)m.at,
                 (double)naive.err, (double)naive.at);
    PF_CHECK(m.err <= 1.5L, "pf_exp_neg_sq max %.3g ulp at x=%.9g", (double)m.err, (double)m.at);
    PF_CHECK(pf_exp_neg_sq(PF_R(0.0)) == PF_R(1.0), "exp(-0) = %g", (double)pf_exp_neg_sq(PF_R(0.0)));
}

/* Finite, in [0, 1], even, 0 far out, for every finite input (also under -ffast-math). */
static void edge_exp_neg_sq(void)
{
    static const double xs[] = {0.0, 1e-30, 1e-10, 0.5, 1.0, 9.0, 9.5, 10.0, 26.0, 27.0, 30.0, 64.0, 100.0, 1e10,
                                1e30};
    int i;
    for (i = 0; i < (int)(sizeof xs / sizeof xs[0]); i++) {
        pf_real x = (pf_real)xs[i];
        pf_real e = pf_exp_neg_sq(x), en = pf_exp_neg_sq(-x);
        PF_CHECK(pf_test_finite(e) && e >= PF_R(0.0) && e <= PF_R(1.0), "exp_neg_sq(%g) = %g", xs[i], (double)e);
        PF_CHECK(e == en, "exp_neg_sq(-%g) = %g differs from %g", xs[i], (double)en, (double)e);
        if (xs[i] >= 30.0) PF_CHECK(e == PF_R(0.0), "exp_neg_sq(%g) = %g, expected 0", xs[i], (double)e);
    }
}

static void edge_scalar_helpers(void)
{
    PF_CHECK(pf_min(PF_R(1.0), PF_R(2.0)) == PF_R(1.0) && pf_min(PF_R(2.0), PF_R(-3.0)) == PF_R(-3.0), "pf_min");
    PF_CHECK(pf_max(PF_R(1.0), PF_R(2.0)) == PF_R(2.0) && pf_max(PF_R(2.0), PF_R(-3.0)) == PF_R(2.0), "pf_max");
    PF_CHECK(pf_clamp(PF_R(5.0), PF_R(-1.0), PF_R(1.0)) == PF_R(1.0), "clamp high");
    PF_CHECK(pf_clamp(PF_R(-5.0), PF_R(-1.0), PF_R(1.0)) == PF_R(-1.0), "clamp low");
    PF_CHECK(pf_clamp(PF_R(0.25), PF_R(-1.0), PF_R(1.0)) == PF_R(0.25), "clamp inside");
    PF_CHECK(pf_saturate(PF_R(1.5)) == PF_R(1.0) && pf_saturate(PF_R(-0.5)) == PF_R(0.0)
             && pf_saturate(PF_R(0.75)) == PF_R(0.75), "pf_saturate");
    PF_CHECK(pf_sq(PF_R(-3.0)) == PF_R(9.0), "pf_sq");
#ifndef __FAST_MATH__
    {
        pf_real nan = (PF_REAL_MAX * PF_R(2.0)) - (PF_REAL_MAX * PF_R(2.0));
        /* documented: pf_max(NaN, 0) is 0, a sanitizer */
        PF_CHECK(pf_max(nan, PF_R(0.0)) == PF_R(0.0), "pf_max(NaN, 0) = %g", (double)pf_max(nan, PF_R(0.0)));
    }
#endif
}

/* ------------------------------------------------------------------ pf_atan2 */
#ifdef PF_DOUBLE
#  define ATAN2_MAX_ULP 1.0L /* libm's atan2 */
#else
#  define ATAN2_MAX_ULP 2.5L /* pf_core.h's bound; measured 2.09 here */
#endif
static long double ulp_of(long double ref)
{
    int e;
    frexpl(ref, &e);
    return ldexpl(1.0L, e - 1 - (PF_REAL_EPSILON == PF_R(2.220446049250313e-16) ? 52 : 23));
}

/* against atan2l: pairs in [-1, 1]^2, and with one side scaled by 10^-30 .. 10^30 (the
   scaling to 2^+-100 and the reductions), in ulps of the result */
static void test_atan2_accuracy(void)
{
    pf_test_rng r = pf_test_rng_seed(29);
    pf_test_max m = pf_test_max_init();
    long i;
    for (i = 0; i < 400000; ++i) {
        pf_real y = (pf_real)pf_test_uniform(&r, -1.0, 1.0), x = (pf_real)pf_test_uniform(&r, -1.0, 1.0), a;
        long double ref, e;
        if (i % 4 == 1) y *= (pf_real)pf_test_log_uniform(&r, 1e-30, 1e30);
        if (i % 4 == 2) x *= (pf_real)pf_test_log_uniform(&r, 1e-30, 1e30);
        if (i % 4 == 3) { y *= PF_R(1e-3); x *= PF_R(1e-36); }
        if (x == PF_R(0.0) && y == PF_R(0.0)) continue;
        a = pf_atan2(y, x);
        ref = atan2l((long double)y, (long double)x);
        e = fabsl((long double)a - ref) / ulp_of(ref);
        pf_test_max_update(&m, e, (long double)i);
    }
    pf_test_note("pf_atan2 max %.2Lf ulp", m.err);
    PF_CHECK(m.err <= ATAN2_MAX_ULP, "pf_atan2 max %.3Lf ulp (bound %.1Lf) at sample %.0Lf", m.err, ATAN2_MAX_ULP, m.at);
}

/* documented values: 0 at (0, 0) for every sign of zero; subnormal pairs (C keeps them; a GPU
   that flushes reads them as (0, 0)); overflow-free near PF_REAL_MAX; infinities as in C;
   NaN in, NaN out; the range [-pi, pi] */
static void edge_atan2(void)
{
    const pf_real z = PF_R(0.0), mz = -PF_R(0.0), inf = PF_REAL_MAX * PF_R(2.0);
    const pf_real pi4 = PF_PI * PF_R(0.25), pi2 = PF_PI * PF_R(0.5);
    pf_real sub = PF_REAL_MIN * PF_R(0.25);
    PF_CHECK(pf_atan2(z, z) == z && pf_atan2(mz, z) == z && pf_atan2(z, mz) == z && pf_atan2(mz, mz) == z,
             "atan2 of zeros: %g %g %g %g", (double)pf_atan2(z, z), (double)pf_atan2(mz, z), (double)pf_atan2(z, mz),
             (double)pf_atan2(mz, mz));
    PF_CHECK(fabsl((long double)pf_atan2(PF_REAL_MAX, PF_REAL_MAX) - (long double)pi4) <= 2.0L * ulp_of((long double)pi4),
             "atan2(max, max) = %.9g", (double)pf_atan2(PF_REAL_MAX, PF_REAL_MAX));
    PF_CHECK(fabsl((long double)pf_atan2(PF_REAL_MAX, PF_REAL_MIN) - (long double)pi2) <= 1.0L * ulp_of((long double)pi2),
             "atan2(max, min) = %.9g", (double)pf_atan2(PF_REAL_MAX, PF_REAL_MIN));
    PF_CHECK(fabsl((long double)pf_atan2(PF_R(1.0), z) - (long double)pi2) <= 1.0L * ulp_of((long double)pi2) &&
             fabsl((long double)pf_atan2(-PF_R(1.0), z) + (long double)pi2) <= 1.0L * ulp_of((long double)pi2),
             "atan2(+-1, 0) = %.9g %.9g", (double)pf_atan2(PF_R(1.0), z), (double)pf_atan2(-PF_R(1.0), z));
    PF_CHECK(fabsl((long double)pf_atan2(z, -PF_R(1.0)) - (long double)PF_PI) <= 1.0L * ulp_of((long double)PF_PI),
             "atan2(0, -1) = %.9g", (double)pf_atan2(z, -PF_R(1.0)));
#ifndef __FAST_MATH__ /* -ffast-math flushes subnormals (as a GPU may: then 0, the zero pair's value) */
    PF_CHECK(fabsl((long double)pf_atan2(sub, sub) - (long double)pi4) <= 2.0L * ulp_of((long double)pi4), "atan2(sub, sub) = %.9g",
             (double)pf_atan2(sub, sub));
    PF_CHECK(fabsl((long double)pf_atan2(-sub, -sub) + 3.0L * (long double)pi4) <= 4.0L * ulp_of((long double)pi4), "atan2(-sub, -sub) = %.9g",
             (double)pf_atan2(-sub, -sub));
    PF_CHECK(fabsl((long double)pf_atan2(inf, inf) - (long double)pi4) <= 2.0L * ulp_of((long double)pi4) &&
             fabsl((long double)pf_atan2(inf, PF_R(1.0)) - (long double)pi2) <= 1.0L * ulp_of((long double)pi2) &&
             fabsl((long double)pf_atan2(PF_R(1.0), -inf) - (long double)PF_PI) <= 1.0L * ulp_of((long double)PF_PI) &&
             pf_atan2(-PF_R(1.0), inf) == z,
             "atan2 with infinities: %.9g %.9g %.9g %.9g", (double)pf_atan2(inf, inf), (double)pf_atan2(inf, PF_R(1.0)),
             (double)pf_atan2(PF_R(1.0), -inf), (double)pf_atan2(-PF_R(1.0), inf));
    {
        pf_real nan = inf - inf, a = pf_atan2(nan, PF_R(1.0)), b = pf_atan2(PF_R(1.0), nan);
        PF_CHECK(a != a && b != b, "atan2 with NaN: %g %g", (double)a, (double)b);
    }
#else
    (void)inf;
    (void)sub;
#endif
    {   /* the range, on a grid of the unit square's boundary scaled over 60 decades */
        int i, j, bad = 0;
        for (i = -30; i <= 30; i += 3)
            for (j = 0; j < 64; ++j) {
                pf_real t = PF_R(6.283185307179586) * PF_R(j) / PF_R(64.0), s = (pf_real)pow(10.0, (double)i);
                pf_real a = pf_atan2(PF_SIN(t) * s, PF_COS(t) * s);
                if (!(a >= -PF_PI && a <= PF_PI)) bad++;
            }
        PF_CHECK(bad == 0, "%d results outside [-pi, pi]", bad);
    }
}

/* ------------------------------------------------------------------ vectors */
static long double ld_len3(pf_vec3 v)
{
    long double x = (long double)v.x, y = (long double)v.y, z = (long double)v.z;
    return sqrtl(x * x + y * y + z * z);
}

static pf_vec3 rand_vec3(pf_test_rng *r, double lo, double hi)
{
    return pf_vec3_make((pf_real)pf_test_uniform(r, lo, hi), (pf_real)pf_test_uniform(r, lo, hi),
                        (pf_real)pf_test_uniform(r, lo, hi));
}

static void test_vec_ops(void)
{
    pf_test_rng r = pf_test_rng_seed(0x7EC30004ULL);
    pf_test_max dot_err = pf_test_max_init(), cross_err = pf_test_max_init(), len_err = pf_test_max_init();
    int i;
    pf_vec2 u = pf_vec2_make(PF_R(3.0), PF_R(-4.0));
    PF_CHECK(u.x == PF_R(3.0) && u.y == PF_R(-4.0), "pf_vec2_make");
    PF_CHECK(pf_vec2_dot(u, pf_vec2_make(PF_R(2.0), PF_R(0.5))) == PF_R(4.0), "pf_vec2_dot");
    {
        pf_vec3 a = pf_vec3_make(PF_R(1.0), PF_R(2.0), PF_R(3.0)), b = pf_vec3_make(PF_R(-2.0), PF_R(0.5), PF_R(4.0));
        pf_vec3 s = pf_vec3_add(a, b), d = pf_vec3_sub(a, b), k = pf_vec3_scale(a, PF_R(-2.0));
        pf_vec3 c = pf_vec3_cross(pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(0.0)), pf_vec3_make(PF_R(0.0), PF_R(1.0), PF_R(0.0)));
        PF_CHECK(s.x == PF_R(-1.0) && s.y == PF_R(2.5) && s.z == PF_R(7.0), "pf_vec3_add");
        PF_CHECK(d.x == PF_R(3.0) && d.y == PF_R(1.5) && d.z == PF_R(-1.0), "pf_vec3_sub");
        PF_CHECK(k.x == PF_R(-2.0) && k.y == PF_R(-4.0) && k.z == PF_R(-6.0), "pf_vec3_scale");
        PF_CHECK(pf_vec3_dot(a, b) == PF_R(11.0), "pf_vec3_dot = %g", (double)pf_vec3_dot(a, b));
        PF_CHECK(c.x == PF_R(0.0) && c.y == PF_R(0.0) && c.z == PF_R(1.0), "x cross y = z");
        PF_CHECK(pf_vec3_length(pf_vec3_make(PF_R(2.0), PF_R(3.0), PF_R(6.0))) == PF_R(7.0), "length 7");
    }
    for (i = 0; i < 20000; ++i) {
        pf_vec3 a = rand_vec3(&r, -10.0, 10.0), b = rand_vec3(&r, -10.0, 10.0);
        long double ax = (long double)a.x, ay = (long double)a.y, az = (long double)a.z;
        long double bx = (long double)b.x, by = (long double)b.y, bz = (long double)b.z;
        long double dref = ax * bx + ay * by + az * bz;
        long double scale = ld_len3(a) * ld_len3(b);
        pf_vec3 c = pf_vec3_cross(a, b);
        long double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
        long double cerr = sqrtl(((long double)c.x - cx) * ((long double)c.x - cx) + ((long double)c.y - cy) * ((long double)c.y - cy)
                                 + ((long double)c.z - cz) * ((long double)c.z - cz));
        /* errors relative to |a||b|, the natural scale of both products */
        pf_test_max_update(&dot_err, fabsl((long double)pf_vec3_dot(a, b) - dref) / scale, (long double)i);
        pf_test_max_update(&cross_err, cerr / scale, (long double)i);
        pf_test_max_update(&len_err, pf_test_rel_error((long double)pf_vec3_length(a), ld_len3(a)), (long double)i);
    }
    pf_test_note("dot %.2Lf eps, cross %.2Lf eps, length %.2Lf eps (relative to |a||b|, |a|)",
                 dot_err.err / (long double)PF_REAL_EPSILON, cross_err.err / (long double)PF_REAL_EPSILON,
                 len_err.err / (long double)PF_REAL_EPSILON);
    PF_CHECK(dot_err.err <= 4.0L * (long double)PF_REAL_EPSILON, "dot error %Lg", dot_err.err);
    PF_CHECK(cross_err.err <= 4.0L * (long double)PF_REAL_EPSILON, "cross error %Lg", cross_err.err);
    PF_CHECK(len_err.err <= 3.0L * (long double)PF_REAL_EPSILON, "length error %Lg", len_err.err);
}

static void edge_vec3_normalize(void)
{
    pf_test_rng r = pf_test_rng_seed(0x7EC30005ULL);
    int i;
    long double worst = 0.0L;
    pf_vec3 n = pf_vec3_normalize(pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0)));
    PF_CHECK(n.x == PF_R(0.0) && n.y == PF_R(0.0) && n.z == PF_R(1.0), "normalize(0) = (%g %g %g)", (double)n.x,
             (double)n.y, (double)n.z);
    n = pf_vec3_normalize(pf_vec3_make(PF_R(0.0), PF_R(-5.0), PF_R(0.0)));
    PF_CHECK(n.x == PF_R(0.0) && n.y == PF_R(-1.0) && n.z == PF_R(0.0), "normalize(0,-5,0)");
    /* tiny and huge vectors: squaring them would underflow / overflow */
    for (i = 0; i < 3000; ++i) {
        double mag = (i % 3 == 0) ? 1e-30 : (i % 3 == 1 ? 1e30 : 1.0);
#ifdef PF_DOUBLE
        if (i % 3 == 0) mag = 1e-300;
        if (i % 3 == 1) mag = 1e300;
#endif
        pf_vec3 a = rand_vec3(&r, -mag, mag);
        pf_vec3 u = pf_vec3_normalize(a);
        long double l = ld_len3(u);
        PF_CHECK(pf_test_finite(u.x) && pf_test_finite(u.y) && pf_test_finite(u.z), "non-finite normalize");
        if (fabsl(l - 1.0L) > worst) worst = fabsl(l - 1.0L);
        /* same direction: u * |a| ~ a */
        PF_CHECK(pf_vec3_dot(u, pf_vec3_scale(a, PF_R(1.0) / pf_max(pf_max(PF_FABS(a.x), PF_FABS(a.y)), PF_FABS(a.z))))
                     > PF_R(0.0), "normalize flips direction");
    }
    pf_test_note("| |normalize(v)| - 1 | <= %.2Lf eps", worst / (long double)PF_REAL_EPSILON);
#ifdef __FAST_MATH__
    PF_CHECK(worst <= 1e-3L, "| |n| - 1 | = %Lg", worst);
#else
    PF_CHECK(worst <= 4.0L * (long double)PF_REAL_EPSILON, "| |n| - 1 | = %Lg", worst);
#endif
}

/* The stability sweep's failing inputs (docs/stability.md, first sweep): a subnormal largest
   component made 1/m overflow (NaN); under -ffast-math a component near PF_REAL_MAX made 1/m
   subnormal, flushed to 0 (NaN). Then every binade of the type, components of mixed scale. */
static void edge_vec3_normalize_extreme(void)
{
    pf_test_rng r = pf_test_rng_seed(0x7EC30006ULL);
#ifdef PF_DOUBLE
    pf_vec3 sub = pf_vec3_make((pf_real)ldexp(-5.0, -1072), PF_R(0.0), PF_R(0.0)); /* -0x0.0000000000014p-1022 */
    pf_vec3 big = pf_vec3_make((pf_real)ldexp(-312.0, 40), (pf_real)ldexp(-7.0, 454), (pf_real)ldexp(1.0, 1023));
    const int emin = -1074, emax = 1023;
#else
    pf_vec3 sub = pf_vec3_make((pf_real)ldexp(-313.0, -139), PF_R(0.0), PF_R(0.0)); /* -0x1.39p-131 */
    pf_vec3 big = pf_vec3_make((pf_real)ldexp(-312.0, -22), (pf_real)ldexp(-7.0, 43), (pf_real)ldexp(1.0, 127));
    const int emin = -149, emax = 127;
#endif
    long double worst = 0.0L;
    int e, k, bad = 0;
    pf_vec3 u = pf_vec3_normalize(sub);
#ifndef __FAST_MATH__
    PF_CHECK(u.x == PF_R(-1.0) && u.y == PF_R(0.0) && u.z == PF_R(0.0), "normalize(subnormal, 0, 0) = (%g %g %g)",
             (double)u.x, (double)u.y, (double)u.z);
#else
    /* subnormal inputs may read as 0 (DAZ): then the zero vector's (0, 0, 1) */
    PF_CHECK(pf_test_bits_finite(u.x) && pf_test_bits_finite(u.y) && pf_test_bits_finite(u.z), "normalize(subnormal, 0, 0) not finite");
#endif
    u = pf_vec3_normalize(big);
    /* z within 4 eps of 1 (clang -ffast-math uses an approximate reciprocal square root) */
    PF_CHECK(pf_test_bits_finite(u.x) && pf_test_bits_finite(u.y) && pf_test_bits_finite(u.z) && u.z >= PF_R(1.0) - PF_R(4.0) * PF_REAL_EPSILON &&
                 u.z <= PF_R(1.0) && u.x <= PF_R(0.0) && u.y < PF_R(0.0),
             "normalize(huge) = (%g %g %.9g)", (double)u.x, (double)u.y, (double)u.z);
    for (e = emin; e <= emax; ++e) {
        for (k = 0; k < 24; ++k) {
            /* the largest component 2^e times [1/2, 1), the others up to 2^-30 smaller */
            pf_real c[3];
            int i, lead = k % 3;
            pf_vec3 a;
            long double l;
            for (i = 0; i < 3; ++i) {
                int drop = i == lead ? 0 : (int)(pf_test_rng_next(&r) % 31u);
                double sign = (pf_test_rng_next(&r) & 1u) ? -1.0 : 1.0;
                c[i] = (pf_real)(sign * ldexp(pf_test_uniform(&r, 0.5, 1.0), e - drop));
            }
            a = pf_vec3_make(c[0], c[1], c[2]);
            u = pf_vec3_normalize(a);
            if (!(pf_test_bits_finite(u.x) && pf_test_bits_finite(u.y) && pf_test_bits_finite(u.z))) { bad++; continue; }
            l = ld_len3(u);
            if (fabsl(l - 1.0L) > worst) worst = fabsl(l - 1.0L);
#ifndef __FAST_MATH__
            /* same direction: the leading component keeps its sign and dominates */
            if (!((c[lead] > PF_R(0.0)) == ((lead == 0 ? u.x : (lead == 1 ? u.y : u.z)) > PF_R(0.0)))) bad++;
#endif
        }
    }
    pf_test_note("every binade 2^%d .. 2^%d: | |n| - 1 | <= %.2Lf eps, %d bad", emin, emax,
                 worst / (long double)PF_REAL_EPSILON, bad);
    PF_CHECK(bad == 0, "%d non-finite or flipped results", bad);
    PF_CHECK(worst <= 4.0L * (long double)PF_REAL_EPSILON, "| |n| - 1 | = %Lg", worst);
}

#ifdef __cplusplus
/* GLM as an independent implementation of the same vector operations. */
#  ifdef PF_DOUBLE
typedef glm::dvec3 glm_v3;
#  else
typedef glm::vec3 glm_v3;
#  endif
static glm_v3 to_glm(pf_vec3 a) { return glm_v3(a.x, a.y, a.z); }

static long double v3_rel(pf_vec3 a, glm_v3 g)
{
    long double dx = (long double)a.x - g.x, dy = (long double)a.y - g.y, dz = (long double)a.z - g.z;
    long double gl = sqrtl((long double)g.x * g.x + (long double)g.y * g.y + (long double)g.z * g.z);
    return sqrtl(dx * dx + dy * dy + dz * dz) / (gl > 0.0L ? gl : 1.0L);
}

static void test_vec_vs_glm(void)
{
    pf_test_rng r = pf_test_rng_seed(0x61A0006ULL);
    long double worst = 0.0L, e;
    int i;
    for (i = 0; i < 20000; ++i) {
        pf_vec3 a = rand_vec3(&r, -100.0, 100.0), b = rand_vec3(&r, -100.0, 100.0);
        pf_real s = (pf_real)pf_test_uniform(&r, -4.0, 4.0);
        glm_v3 ga = to_glm(a), gb = to_glm(b);
        long double scale = (long double)glm::length(ga) * (long double)glm::length(gb);
        e = v3_rel(pf_vec3_add(a, b), ga + gb);
        if (e > worst) worst = e;
        e = v3_rel(pf_vec3_sub(a, b), ga - gb);
        if (e > worst) worst = e;
        e = v3_rel(pf_vec3_scale(a, s), ga * s);
        if (e > worst) worst = e;
        e = v3_rel(pf_vec3_normalize(a), glm::normalize(ga));
        if (e > worst) worst = e;
        e = fabsl((long double)pf_vec3_length(a) - (long double)glm::length(ga)) / (long double)glm::length(ga);
        if (e > worst) worst = e;
        /* products: compare relative to |a||b| (cancellation makes them small) */
        e = fabsl((long double)pf_vec3_dot(a, b) - (long double)glm::dot(ga, gb)) / scale;
        if (e > worst) worst = e;
        {
            glm_v3 gc = glm::cross(ga, gb);
            pf_vec3 c = pf_vec3_cross(a, b);
            long double dx = (long double)c.x - gc.x, dy = (long double)c.y - gc.y, dz = (long double)c.z - gc.z;
            e = sqrtl(dx * dx + dy * dy + dz * dz) / scale;
            if (e > worst) worst = e;
        }
    }
    pf_test_note("max relative difference to GLM %.2Lf eps", worst / (long double)PF_REAL_EPSILON);
    PF_CHECK(worst <= 8.0L * (long double)PF_REAL_EPSILON, "difference to GLM %Lg", worst);
}
#endif


/* The CPU-only size helpers (pf_core.h, "sizes and errors") against exact arithmetic: products
   formed in long double (64-bit mantissa on x86; exact for the magnitudes compared here, which
   are checked against a 2^40-ish limit) and an unsigned 128-bit-free reference for the wrap. */
static void edge_size_helpers(void)
{
    static const long long v[] = {-1, 0, 1, 2, 3, 5, 65537, (1LL << 20), (1LL << 24), (1LL << 30),
                                  2147483647LL, (1LL << 40), (1LL << 40) + 1, 9223372036854775807LL};
    const int nv = (int)(sizeof v / sizeof v[0]);
    int i, j, k, bad = 0;
    for (i = 0; i < nv; ++i)
        for (j = 0; j < nv; ++j) {
            long long a = v[i], b = v[j], got = pf_size_mul(a, b);
            long double exact = (long double)a * (long double)b;
            long long want = (a < 0 || b < 0 || exact > (long double)PF_MAX_REALS) ? -1 : a * b;
            if (got != want) {
                if (bad++ < 4) printf("    pf_size_mul(%lld, %lld) = %lld, want %lld\n", a, b, got, want);
            }
            for (k = 0; k < nv; ++k) {
                long long c = v[k], g3 = pf_size_mul3(a, b, c);
                long double e3 = exact * (long double)c;
                long long w3 = (a < 0 || b < 0 || c < 0 || exact > (long double)PF_MAX_REALS ||
                                e3 > (long double)PF_MAX_REALS) ? -1 : a * b * c;
                if (g3 != w3 && bad++ < 4)
                    printf("    pf_size_mul3(%lld, %lld, %lld) = %lld, want %lld\n", a, b, c, g3, w3);
            }
        }
    PF_CHECK(bad == 0, "%d wrong checked products", bad);
    /* the issue 19 table size: 65537^2 fits 64 bits and the limit, 2 x 2 x 2^30 too */
    PF_CHECK(pf_size_mul3(65537, 65537, 1) == (PF_MAX_REALS >= 4295098369LL ? 4295098369LL : -1),
             "65537^2 -> %lld (PF_MAX_REALS %lld)", pf_size_mul3(65537, 65537, 1), (long long)PF_MAX_REALS);
    PF_CHECK(pf_size_mul3(1LL << 24, 1LL << 24, 5) == -1, "2^24 x 2^24 x 5 must exceed PF_MAX_REALS");
    PF_CHECK(pf_size_side_ok(1) && pf_size_side_ok(PF_MAX_SIDE) && !pf_size_side_ok(0) &&
                 !pf_size_side_ok(PF_MAX_SIDE + 1) && !pf_size_side_ok(-5),
             "side limits");
    /* floor to a clamped index: huge values never reach the conversion; NaN and infinities
       neither (not under -ffast-math, which lets the compiler assume they never occur) */
    PF_CHECK(pf_floor_index(PF_REAL_MAX, 0, 2147483647LL) == 2147483647LL &&
                 pf_floor_index(-PF_REAL_MAX, -3, 9) == -3 && pf_floor_index(PF_R(2.5), 0, 9) == 2 &&
                 pf_floor_index(PF_R(-0.5), -3, 9) == -1 && pf_floor_index(PF_R(8.99), 0, 9) == 8 &&
                 pf_floor_index(PF_R(1.0e6), 0, 1LL << 24) == 1000000,
             "pf_floor_index finite values");
#ifndef __FAST_MATH__
    {
        volatile pf_real zero = PF_R(0.0);
        pf_real nan = zero / zero, inf = PF_R(1.0) / zero;
        PF_CHECK(pf_floor_index(nan, 0, 9) == 0 && pf_floor_index(inf, 0, 9) == 9 &&
                     pf_floor_index(-inf, 0, 9) == 0,
                 "pf_floor_index NaN and infinities");
    }
#endif
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_erfc_grid);
    PF_TEST_RUN(test_erfc_random);
    PF_TEST_RUN(test_erf_grid_random);
    PF_TEST_RUN(edge_erfc_special_values);
    PF_TEST_RUN(edge_erf_tiny);
    PF_TEST_RUN(edge_erfc_range_symmetry);
    PF_TEST_RUN(edge_erfc_monotonic);
    PF_TEST_RUN(edge_erfc_underflow);
    PF_TEST_RUN(test_erfc_fast);
    PF_TEST_RUN(test_split_contraction_invariant);
    PF_TEST_RUN(edge_erfc_fast);
    PF_TEST_RUN(test_exp_neg_sq);
    PF_TEST_RUN(edge_exp_neg_sq);
    PF_TEST_RUN(edge_scalar_helpers);
    PF_TEST_RUN(test_atan2_accuracy);
    PF_TEST_RUN(edge_atan2);
    PF_TEST_RUN(test_vec_ops);
    PF_TEST_RUN(edge_vec3_normalize);
    PF_TEST_RUN(edge_vec3_normalize_extreme);
    PF_TEST_RUN(edge_size_helpers);
#ifdef __cplusplus
    PF_TEST_RUN(test_vec_vs_glm);
#endif
    return PF_TEST_END();
}

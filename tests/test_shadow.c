/* test_shadow.c - tests of include/pf_shadow.h against brute force.

   Truth is never a method's own formula: it is the average of binary depth tests (the
   fraction of depths z >= d) over an explicit discrete depth distribution - seeded random
   distributions, two-depth planar occluders, constant footprints, and footprints of the
   synthetic shadow maps of tests/shadow_scenes.h. The moments each method consumes are built
   from the same depths in long double with the pf_moments.h per-texel constructors and
   rounded to pf_real, as fp32 storage would hold them. The same bodies run in float, double,
   C++ and under sanitizers; edge_* tests also run under -ffast-math. */
#include "pf_shadow.h"
#include "pf_test.h"
#include "shadow_scenes.h"

#define MINVAR PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT
#define ALPHA PF_SHADOW_MSM_MOMENT_BIAS_DEFAULT
#define CPOS PF_SHADOW_EVSM_POS_DEFAULT
#define CNEG PF_SHADOW_EVSM_NEG_DEFAULT
#define CESM PF_SHADOW_ESM_EXPONENT_DEFAULT

/* ------------------------------------------------------------------ discrete distributions */
#define MAX_ATOMS 16
typedef struct dist {
    int n;
    long double z[MAX_ATOMS], w[MAX_ATOMS]; /* depths (already pf_real values) and weights */
} dist;

/* Every moment a method consumes, in long double, rounded to pf_real at the end. */
typedef struct dist_moments {
    pf_depth_moments2 vsm, evsm2;
    pf_evsm_moments evsm4;
    pf_depth_moments4 msm;
    pf_real esm_log;
    long double mean;
} dist_moments;

static dist_moments moments_of(const dist *p)
{
    long double v[4] = { 0, 0, 0, 0 }, e[2] = { 0, 0 }, q[4] = { 0, 0, 0, 0 }, lmax = -HUGE_VALL, s = 0;
    dist_moments r;
    int i;
    for (i = 0; i < p->n; ++i) {
        long double z = p->z[i], w = p->w[i], zs = 2.0L * z - 1.0L;
        long double pp = expl((long double)CPOS * zs), nn = -expl(-(long double)CNEG * zs);
        v[0] += w * z; v[1] += w * z * z; v[2] += w * z * z * z; v[3] += w * z * z * z * z;
        e[0] += w * pp; e[1] += w * pp * pp;
        q[0] += w * pp; q[1] += w * pp * pp; q[2] += w * nn; q[3] += w * nn * nn;
        if ((long double)CESM * z > lmax && w > 0) lmax = (long double)CESM * z;
    }
    for (i = 0; i < p->n; ++i) s += p->w[i] * expl((long double)CESM * p->z[i] - lmax);
    r.vsm = pf_depth_moments2_make((pf_real)v[0], (pf_real)v[1]);
    r.evsm2 = pf_depth_moments2_make((pf_real)e[0], (pf_real)e[1]);
    r.evsm4 = pf_evsm_moments_make((pf_real)q[0], (pf_real)q[1], (pf_real)q[2], (pf_real)q[3]);
    r.msm = pf_depth_moments4_make((pf_real)v[0], (pf_real)v[1], (pf_real)v[2], (pf_real)v[3]);
    r.esm_log = (pf_real)(lmax + logl(s));
    r.mean = v[0];
    return r;
}

/* P(z >= d) and P(z > d) */
static long double lit_of(const dist *p, long double d)
{
    long double s = 0;
    int i;
    for (i = 0; i < p->n; ++i)
        if (p->z[i] >= d) s += p->w[i];
    return s;
}

static long double lit_strict_of(const dist *p, long double d)
{
    long double s = 0;
    int i;
    for (i = 0; i < p->n; ++i)
        if (p->z[i] > d) s += p->w[i];
    return s;
}

static dist random_dist(pf_test_rng *r)
{
    dist p;
    int i, clustered = pf_test_uniform(r, 0.0, 1.0) < 0.3;
    long double sum = 0, c = (long double)pf_test_uniform(r, 0.1, 0.9);
    p.n = 1 + (int)(pf_test_rng_next(r) % 12u);
    for (i = 0; i < p.n; ++i) {
        double z = clustered ? (double)c + pf_test_uniform(r, -0.05, 0.05) : pf_test_uniform(r, 0.0, 1.0);
        if (z < 0.0) z = 0.0;
        if (z > 1.0) z = 1.0;
        p.z[i] = (long double)(pf_real)z;
        p.w[i] = (long double)pf_test_uniform(r, 0.05, 1.0);
        sum += p.w[i];
    }
    for (i = 0; i < p.n; ++i) p.w[i] /= sum;
    return p;
}

static dist two_point(long double z0, long double f, long double z1)
{
    dist p;
    p.n = 2;
    p.z[0] = (long double)(pf_real)z0;
    p.w[0] = f;
    p.z[1] = (long double)(pf_real)z1;
    p.w[1] = 1.0L - f;
    return p;
}

/* ------------------------------------------------------------------ exact cases */

/* A planar occluder at z0 covering a fraction f of the footprint, in front of a planar
   receiver at z1 = d: Chebyshev is attained by this two-point distribution (the receiver is
   its upper atom), so VSM, EVSM-2, EVSM-4 return the true 1 - f; MSM returns it up to its
   moment bias; ESM returns (1 - f) + f exp(-c (z1 - z0)) (its leak), computed here by brute
   force from the two depths. Minimum variance 0 (the bound is exact only without it). */
static void test_planar_occluder_exact(void)
{
    long double worst_vsm = 0, worst_evsm2 = 0, worst_evsm4 = 0, worst_msm = 0, worst_msm0 = 0, worst_esm = 0;
    long double worst_cond = 0;
    int i, j, k, n = 0;
    for (i = 0; i < 9; ++i)
        for (j = 0; j < 9; ++j)
            for (k = 0; k < 6; ++k) {
                long double z0 = 0.05L + 0.1L * i, f = 0.05L + 0.1125L * j, gap = 0.02L + 0.06L * k;
                long double z1 = z0 + gap, truth, esm_ref, cond, e;
                dist p;
                dist_moments m;
                pf_real d;
                if (z1 > 1.0L) continue;
                p = two_point(z0, f, z1);
                m = moments_of(&p);
                d = (pf_real)p.z[1];
                truth = lit_of(&p, (long double)d);
                esm_ref = (1.0L - f) + f * expl(-(long double)CESM * (p.z[1] - p.z[0]));
                /* condition of Chebyshev: E[z^2] / Var(z) amplifies the moments' rounding */
                cond = (f * p.z[0] * p.z[0] + (1 - f) * p.z[1] * p.z[1]) / (f * (1 - f) * gap * gap);
                if (cond > worst_cond) worst_cond = cond;
                e = fabsl((long double)pf_shadow_vsm(m.vsm, d, PF_R(0.0), PF_R(0.0)) - truth) / cond;
                if (e > worst_vsm) worst_vsm = e;
                e = fabsl((long double)pf_shadow_evsm2(m.evsm2, d, CPOS, PF_R(0.0), PF_R(0.0)) - truth);
                if (e > worst_evsm2) worst_evsm2 = e;
                e = fabsl((long double)pf_shadow_evsm4(m.evsm4, d, CPOS, CNEG, PF_R(0.0), PF_R(0.0)) - truth);
                if (e > worst_evsm4) worst_evsm4 = e;
                e = fabsl((long double)pf_shadow_msm(m.msm, d, ALPHA, PF_R(0.0)) - truth);
                if (e > worst_msm) worst_msm = e;
                e = fabsl((long double)pf_shadow_msm(m.msm, d, PF_R(0.0), PF_R(0.0)) - truth);
                if (e > worst_msm0) worst_msm0 = e;
                e = fabsl((long double)pf_shadow_esm(m.esm_log, d, CESM) - esm_ref);
                if (e > worst_esm) worst_esm = e;
                n++;
            }
    pf_test_note("%d cases; VSM %.2g eps x cond (cond <= %.3g); EVSM-2 %.2g; EVSM-4 %.2g; MSM %.2g "
                 "(bias %.0e), %.2g (no bias); ESM vs its brute-force leak %.2g", n, (double)(worst_vsm / PF_TEST_EPS),
                 (double)worst_cond, (double)worst_evsm2, (double)worst_evsm4, (double)worst_msm, (double)ALPHA,
                 (double)worst_msm0, (double)worst_esm);
    PF_CHECK(worst_vsm <= 16.0L * PF_TEST_EPS, "VSM error %.3g eps x cond", (double)(worst_vsm / PF_TEST_EPS));
#ifdef PF_DOUBLE
    PF_CHECK(worst_evsm2 <= 1e-9L && worst_evsm4 <= 1e-9L, "EVSM %.3g %.3g", (double)worst_evsm2, (double)worst_evsm4);
    PF_CHECK(worst_esm <= 1e-12L, "ESM %.3g", (double)worst_esm);
#else
    PF_CHECK(worst_evsm2 <= 2e-3L && worst_evsm4 <= 2e-3L, "EVSM %.3g %.3g", (double)worst_evsm2, (double)worst_evsm4);
    PF_CHECK(worst_esm <= 1e-4L, "ESM %.3g", (double)worst_esm);
#endif
    /* MSM: exact without bias (the pivot floors stand in for the singular Hankel matrix); the
       bias pulls the two-point distribution toward a fair coin on {0, 1}, and where the
       occluder is close in front of the receiver the reconstruction moves the most */
#ifdef PF_DOUBLE
    PF_CHECK(worst_msm0 <= 1e-10L, "MSM without bias %.3g", (double)worst_msm0);
#endif /* in float the unbiased value of a singular Hankel matrix is rounding noise: why the bias exists */
    PF_CHECK(worst_msm <= 0.025L, "MSM %.3g", (double)worst_msm);
}

/* Constant footprints (every texel at z0): a receiver at or in front of z0 is fully lit, one
   behind by a gap g fully shadowed. What each method returns behind is its own floor: VSM
   v / (v + g^2) (minimum variance v), ESM exp(-c g), EVSM the warped minimum variance, MSM the
   moment bias; the test checks lit >= 1 - tol in front and the floors behind. */
static void test_fully_lit_and_shadowed(void)
{
    static const double zs[] = { 0.0, 1e-4, 0.1, 0.25, 0.5, 0.75, 0.9, 0.999, 1.0 };
    static const double gaps[] = { 0.01, 0.05, 0.2 };
    long double lit_min[SHS_N_METHODS], dark_max[SHS_N_METHODS][3];
    int i, j, m, g;
    for (m = 0; m < SHS_N_METHODS; ++m) {
        lit_min[m] = 1;
        for (g = 0; g < 3; ++g) dark_max[m][g] = 0;
    }
    for (i = 0; i < (int)(sizeof zs / sizeof zs[0]); ++i) {
        dist p;
        dist_moments mo;
        shs_lookup L;
        p.n = 1;
        p.z[0] = (long double)(pf_real)zs[i];
        p.w[0] = 1;
        mo = moments_of(&p);
        memset(&L, 0, sizeof L);
        L.vsm = mo.vsm;
        L.evsm2 = mo.evsm2;
        L.evsm4 = mo.evsm4;
        L.msm = mo.msm;
        L.esm_log = mo.esm_log;
        L.z_centre = (pf_real)p.z[0];
        for (j = 0; j < 3; ++j) { /* receivers at z0, z0 - 0.1, 0 */
            L.d = j == 0 ? (pf_real)p.z[0] : (j == 1 ? (pf_real)fmax(0.0, zs[i] - 0.1) : PF_R(0.0));
            for (m = 0; m < SHS_N_METHODS; ++m) {
                long double v = (long double)shs_eval(m, &L);
                if (v < lit_min[m]) lit_min[m] = v;
            }
        }
        for (g = 0; g < 3; ++g) {
            if (zs[i] + gaps[g] > 1.0) continue;
            L.d = (pf_real)(zs[i] + gaps[g]);
            for (m = 0; m < SHS_N_METHODS; ++m) {
                long double v = (long double)shs_eval(m, &L);
                if (!(v <= dark_max[m][g])) dark_max[m][g] = v;
            }
        }
    }
    for (m = 0; m < SHS_N_METHODS; ++m) {
        pf_test_note("%s lit>=%.6f dark<=%.2g/%.2g/%.2g", shs_method_names[m], (double)lit_min[m],
                     (double)dark_max[m][0], (double)dark_max[m][1], (double)dark_max[m][2]);
        PF_CHECK(lit_min[m] >= 1.0L - (long double)ALPHA - 1e3L * PF_TEST_EPS, "%s lit footprint reads %.9g",
                 shs_method_names[m], (double)lit_min[m]);
    }
    for (g = 0; g < 3; ++g) {
        long double gg = (long double)gaps[g], v = (long double)MINVAR;
        long double vsm_floor = v / (v + gg * gg) * 1.01L + 1e3L * PF_TEST_EPS;
        long double esm_floor = expl(-(long double)CESM * (gg - 1e-6L)) + 1e3L * PF_TEST_EPS;
        PF_CHECK(dark_max[SHS_M_VSM][g] <= vsm_floor, "VSM dark %.3g > %.3g", (double)dark_max[SHS_M_VSM][g],
                 (double)vsm_floor);
        PF_CHECK(dark_max[SHS_M_ESM][g] <= esm_floor, "ESM dark %.3g > %.3g", (double)dark_max[SHS_M_ESM][g],
                 (double)esm_floor);
        PF_CHECK(dark_max[SHS_M_EVSM2][g] <= vsm_floor && dark_max[SHS_M_EVSM4][g] <= vsm_floor,
                 "EVSM dark %.3g %.3g > %.3g", (double)dark_max[SHS_M_EVSM2][g], (double)dark_max[SHS_M_EVSM4][g],
                 (double)vsm_floor);
        PF_CHECK(dark_max[SHS_M_VSM_BLEED][g] == 0.0L, "bleeding reduction leaves %.3g",
                 (double)dark_max[SHS_M_VSM_BLEED][g]);
        PF_CHECK(dark_max[SHS_M_PCF1][g] == 0.0L, "1-tap test leaks %.3g", (double)dark_max[SHS_M_PCF1][g]);
    }
    /* MSM: the bias leaks most just behind the occluder (measured 0.07 at g = 0.01) */
    PF_CHECK(dark_max[SHS_M_MSM][0] <= 0.1L && dark_max[SHS_M_MSM][1] <= 0.01L && dark_max[SHS_M_MSM][2] <= 1e-3L,
             "MSM dark %.3g %.3g %.3g", (double)dark_max[SHS_M_MSM][0], (double)dark_max[SHS_M_MSM][1],
             (double)dark_max[SHS_M_MSM][2]);
}

/* ------------------------------------------------------------------ bounds */

/* For seeded random discrete distributions (1-12 atoms, 30% clustered within 0.1) and
   receivers behind the mean, the Chebyshev values (VSM, EVSM-2, EVSM-4, no bleeding
   reduction) are upper bounds of the true lit fraction (the tolerance covers the rounding
   of the moments to pf_real). */
static void test_chebyshev_upper_bound_random(void)
{
    pf_test_rng r = pf_test_rng_seed(0x5a11u);
    long double worst[3] = { 1, 1, 1 }, slack = 0;
    int i, n = 0, k;
    for (i = 0; i < 6000; ++i) {
        dist p = random_dist(&r);
        dist_moments m = moments_of(&p);
        pf_real d = (pf_real)pf_test_uniform(&r, (double)m.mean, 1.0);
        long double truth = lit_of(&p, (long double)d), v[3];
        if (!((long double)d > m.mean)) continue;
        v[0] = (long double)pf_shadow_vsm(m.vsm, d, MINVAR, PF_R(0.0));
        v[1] = (long double)pf_shadow_evsm2(m.evsm2, d, CPOS, MINVAR, PF_R(0.0));
        v[2] = (long double)pf_shadow_evsm4(m.evsm4, d, CPOS, CNEG, MINVAR, PF_R(0.0));
        for (k = 0; k < 3; ++k)
            if (v[k] - truth < worst[k]) worst[k] = v[k] - truth;
        slack += v[0] - truth;
        n++;
    }
    pf_test_note("%d distributions; min (bound - truth): VSM %.2g, EVSM-2 %.2g, EVSM-4 %.2g; mean VSM slack %.3f",
                 n, (double)worst[0], (double)worst[1], (double)worst[2], (double)(slack / n));
    PF_CHECK(n > 4000, "only %d cases", n);
    PF_CHECK(worst[0] >= -64.0L * PF_TEST_EPS, "VSM below the truth by %.3g", (double)-worst[0]);
#ifdef PF_DOUBLE
    PF_CHECK(worst[1] >= -1e-9L && worst[2] >= -1e-9L, "EVSM below the truth by %.3g %.3g", (double)-worst[1],
             (double)-worst[2]);
#else
    PF_CHECK(worst[1] >= -2e-3L && worst[2] >= -2e-3L, "EVSM below the truth by %.3g %.3g", (double)-worst[1],
             (double)-worst[2]);
#endif
}

/* MSM bounds: for the same random distributions and any receiver, the true lit fraction of
   the biased distribution (1 - a) p + a (fair coin on {0, 1}), whose moments MSM actually
   sees, lies in [lower, upper] of pf_shadow_msm_bounds, and pf_shadow_msm returns upper. */
static void test_msm_bounds_random(void)
{
    pf_test_rng r = pf_test_rng_seed(0x4d53u);
    long double worst_lo = 0, worst_hi = 0, a = (long double)ALPHA, width = 0;
    int i, n = 0, same = 1;
    for (i = 0; i < 6000; ++i) {
        dist p = random_dist(&r);
        dist_moments m = moments_of(&p);
        pf_real d = (pf_real)pf_test_uniform(&r, 0.0, 1.0);
        pf_vec2 b = pf_shadow_msm_bounds(m.msm, d, ALPHA, PF_R(0.0));
        long double coin_ge = 0.5L * ((long double)d <= 0.0L ? 1.0L : 0.0L) + 0.5L;
        long double coin_gt = 0.5L * ((long double)d < 0.0L ? 1.0L : 0.0L) + 0.5L * ((long double)d < 1.0L ? 1.0L : 0.0L);
        long double t_ge = (1 - a) * lit_of(&p, (long double)d) + a * coin_ge;
        long double t_gt = (1 - a) * lit_strict_of(&p, (long double)d) + a * coin_gt;
        if ((long double)b.x - t_gt > worst_lo) worst_lo = (long double)b.x - t_gt;
        if (t_ge - (long double)b.y > worst_hi) worst_hi = t_ge - (long double)b.y;
        if (pf_shadow_msm(m.msm, d, ALPHA, PF_R(0.0)) != b.y) same = 0;
        width += (long double)(b.y - b.x);
        n++;
    }
    pf_test_note("%d distributions; lower exceeds truth by <= %.2g, truth exceeds upper by <= %.2g; mean width %.3f",
                 n, (double)worst_lo, (double)worst_hi, (double)(width / n));
    PF_CHECK(same, "pf_shadow_msm differs from the upper bound");
#ifdef PF_DOUBLE
    PF_CHECK(worst_lo <= 1e-6L && worst_hi <= 1e-6L, "bounds violated by %.3g / %.3g", (double)worst_lo, (double)worst_hi);
#else
    PF_CHECK(worst_lo <= 2e-3L && worst_hi <= 2e-3L, "bounds violated by %.3g / %.3g", (double)worst_lo, (double)worst_hi);
#endif
}

/* Sharpness: a three-atom distribution with an atom at the receiver depth is the extremal
   one (it has the fewest atoms with these moments and an atom at d), so with no bias the
   bounds are attained: upper = P(z >= d), lower = P(z > d). */
static void test_msm_bounds_sharp(void)
{
    pf_test_rng r = pf_test_rng_seed(0x3a70u);
    long double worst = 0;
    int i;
    for (i = 0; i < 3000; ++i) {
        dist p;
        dist_moments m;
        pf_vec2 b;
        long double s;
        int k;
        p.n = 3;
        do {
            for (k = 0; k < 3; ++k) p.z[k] = (long double)(pf_real)pf_test_uniform(&r, 0.0, 1.0);
        } while (fabsl(p.z[0] - p.z[1]) < 0.1L || fabsl(p.z[1] - p.z[2]) < 0.1L || fabsl(p.z[0] - p.z[2]) < 0.1L);
        s = 0;
        for (k = 0; k < 3; ++k) s += (p.w[k] = (long double)pf_test_uniform(&r, 0.1, 1.0));
        for (k = 0; k < 3; ++k) p.w[k] /= s;
        m = moments_of(&p);
        b = pf_shadow_msm_bounds(m.msm, (pf_real)p.z[i % 3], PF_R(0.0), PF_R(0.0));
        s = fabsl((long double)b.y - lit_of(&p, p.z[i % 3]));
        if (s > worst) worst = s;
        s = fabsl((long double)b.x - lit_strict_of(&p, p.z[i % 3]));
        if (s > worst) worst = s;
    }
    pf_test_note("3000 three-atom distributions (atoms >= 0.1 apart): max |bound - attained| %.2g", (double)worst);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-9L, "MSM bound not attained: %.3g", (double)worst);
#else
    PF_CHECK(worst <= 2e-3L, "MSM bound not attained: %.3g", (double)worst);
#endif
}

/* pf_shadow_chebyshev_upper is scale-free: (m1, m2, x, v) and (s m1, s^2 m2, s x, s^2 v) give
   the same value for s from 1e-15 to 1e18 (EVSM at c = 44 has m2 ~ 1e38 in float). */
static void test_chebyshev_scale_free(void)
{
    pf_test_rng r = pf_test_rng_seed(0xc4e1u);
    long double worst = 0;
    int i, j;
    for (i = 0; i < 500; ++i) {
        dist p = random_dist(&r);
        dist_moments m = moments_of(&p);
        pf_real x = (pf_real)pf_test_uniform(&r, 0.0, 1.0);
        pf_real ref = pf_shadow_vsm(m.vsm, x, MINVAR, PF_R(0.0));
        pf_real ref2 = pf_shadow_chebyshev_upper(m.vsm.m1, m.vsm.m2, x, MINVAR);
        long double e = fabsl((long double)ref - (long double)ref2);
        if (e > worst) worst = e;
        for (j = -15; j <= 18; j += 3) {
            pf_real s = (pf_real)pow(10.0, j);
            pf_real v = pf_shadow_chebyshev_upper(s * m.vsm.m1, (s * m.vsm.m2) * s, s * x, (s * MINVAR) * s);
            e = fabsl((long double)v - (long double)ref);
            if (e > worst) worst = e;
        }
    }
    pf_test_note("max difference over scales 1e-15..1e18: %.2g", (double)worst);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-9L, "Chebyshev depends on scale: %.3g", (double)worst);
#else
    PF_CHECK(worst <= 2e-3L, "Chebyshev depends on scale: %.3g", (double)worst);
#endif
}

/* Light-bleeding reduction: linstep(t, 1, lit), against the definition. */
static void test_reduce_bleeding(void)
{
    long double worst = 0;
    int i, j;
    for (i = 0; i <= 40; ++i)
        for (j = 0; j < 5; ++j) {
            long double lit = i / 40.0L, t = 0.2L * j, ref = (lit - t) / (1 - t);
            long double v = (long double)pf_shadow_reduce_bleeding((pf_real)lit, (pf_real)t);
            if (ref < 0) ref = 0;
            if (fabsl(v - ref) > worst) worst = fabsl(v - ref);
        }
    PF_CHECK(worst <= 8.0L * PF_TEST_EPS, "bleeding reduction off by %.3g", (double)worst);
}

/* ------------------------------------------------------------------ synthetic shadow maps */

/* Published figures per scene and method: bounds on the mean absolute error (all receivers),
   the mean leak (lit reported where the truth is 0). Measured figures are the notes; the
   bounds are the larger of the float and double figures + 15% + 5e-4, rounded up. Columns:
   pcf_1tap, vsm, vsm_bleed0.3, esm, evsm2, evsm4, msm. */
static const double bound_mean[SHS_N_SCENES][SHS_N_METHODS] = {
    { 0.05, 0.062, 0.059, 0.081, 0.034, 0.015, 0.013 },  /* boxes */
    { 0.13, 0.14, 0.13, 0.17, 0.12, 0.083, 0.087 },     /* spheres */
    { 0.057, 0.065, 0.065, 0.087, 0.046, 0.018, 0.011 }, /* layers 0.01 */
    { 0.064, 0.065, 0.066, 0.091, 0.05, 0.017, 0.011 },  /* layers 0.05 */
    { 0.063, 0.071, 0.068, 0.09, 0.049, 0.021, 0.014 },  /* layers 0.2 */
};
static const double bound_leak[SHS_N_SCENES][SHS_N_METHODS] = {
    { 0, 0.13, 0.081, 0.17, 0.0062, 0.0062, 0.028 },
    { 0, 0.13, 0.075, 0.12, 0.0063, 0.0063, 0.036 },
    { 0, 0.1, 0.059, 0.13, 0.0055, 0.0055, 0.013 },
    { 0, 0.11, 0.06, 0.14, 0.0063, 0.0063, 0.021 },
    { 0, 0.12, 0.065, 0.13, 0.0062, 0.0062, 0.027 },
};

static void scene_test(int scene)
{
    shs_lookup *L = (shs_lookup *)malloc(sizeof(shs_lookup) * SHS_LOOKUPS_PER_SCENE);
    shs_stats st[SHS_N_METHODS];
    long double vsm_under = 0;
    int i, m;
    if (!L) abort();
    memset(st, 0, sizeof st);
    shs_scene_lookups(scene, L);
    for (i = 0; i < SHS_LOOKUPS_PER_SCENE; ++i) {
        for (m = 0; m < SHS_N_METHODS; ++m) {
            pf_real v = shs_eval(m, &L[i]);
            shs_stats_add(&st[m], (long double)v, L[i].truth);
            PF_CHECK(v >= PF_R(0.0) && v <= PF_R(1.0), "%s returned %g", shs_method_names[m], (double)v);
            /* the Chebyshev bound holds on real footprints too */
            if (m == SHS_M_VSM && (long double)L[i].d > (long double)L[i].vsm.m1) {
                /* in units of the rounding of the bound: eps E[z^2] / max(Var, v) */
                long double m1 = (long double)L[i].vsm.m1, m2 = (long double)L[i].vsm.m2, var = m2 - m1 * m1;
                long double u = (L[i].truth - (long double)v) / (PF_TEST_EPS * m2 / (var > (long double)MINVAR ? var : (long double)MINVAR));
                if (u > vsm_under) vsm_under = u;
            }
        }
    }
    pf_test_note("%d lookups, %ld fully shadowed", SHS_LOOKUPS_PER_SCENE, st[0].n_dark);
    for (m = 0; m < SHS_N_METHODS; ++m) {
        pf_test_note("%s %.4f/%.2f leak %.4f/%.2f", shs_method_names[m], (double)shs_mean_err(&st[m]),
                     (double)st[m].max_err, (double)shs_mean_leak(&st[m]), (double)st[m].max_leak);
        PF_CHECK(shs_mean_err(&st[m]) <= (long double)bound_mean[scene][m], "%s mean error %.4f > %.4f",
                 shs_method_names[m], (double)shs_mean_err(&st[m]), bound_mean[scene][m]);
        PF_CHECK(shs_mean_leak(&st[m]) <= (long double)bound_leak[scene][m], "%s mean leak %.4f > %.4f",
                 shs_method_names[m], (double)shs_mean_leak(&st[m]), bound_leak[scene][m]);
    }
    PF_CHECK(st[0].n_dark > 100, "only %ld fully shadowed lookups", st[0].n_dark);
    PF_CHECK(vsm_under <= 16.0L, "VSM below the truth by %.3g eps x cond on a scene footprint", (double)vsm_under);
    /* the orderings the docs state */
    PF_CHECK(shs_mean_err(&st[SHS_M_MSM]) < shs_mean_err(&st[SHS_M_VSM]), "MSM not better than VSM");
    PF_CHECK(shs_mean_err(&st[SHS_M_EVSM4]) < shs_mean_err(&st[SHS_M_EVSM2]), "EVSM-4 not better than EVSM-2");
    PF_CHECK(shs_mean_leak(&st[SHS_M_EVSM4]) < shs_mean_leak(&st[SHS_M_VSM]), "EVSM-4 leaks more than VSM");
    free(L);
}

static void test_scene_boxes(void) { scene_test(SHS_BOXES); }
static void test_scene_spheres(void) { scene_test(SHS_SPHERES); }
static void test_scene_layers_001(void) { scene_test(SHS_LAYERS_001); }
static void test_scene_layers_005(void) { scene_test(SHS_LAYERS_005); }
static void test_scene_layers_02(void) { scene_test(SHS_LAYERS_02); }

/* ------------------------------------------------------------------ float safety (edge_) */

static int in_unit(pf_real v) { return pf_test_finite(v) && v >= PF_R(0.0) && v <= PF_R(1.0); }

/* Every method on degenerate and extreme inputs: finite and in [0, 1], also under -ffast-math.
   Inputs: receivers at 0, 1 and near them; constant footprints at 0, 1 and in between; empty
   (all-zero) moments; variances made slightly negative; Hankel matrices made singular (two
   depths exactly 0 and 1, one depth, moments perturbed by a few ulps); the largest exponents
   (EVSM c = PF_EVSM_EXP_MAX_F32 with depth 1: moments ~ exp(88)); ESM log values from -1e30
   to 1e30. */
static void edge_shadow_finite(void)
{
    static const double ds[] = { 0.0, 1e-7, 1e-3, 0.3, 0.5, 0.7, 0.999, 0.9999999, 1.0 };
    static const double perturb[] = { 0.0, 1.0, -1.0, 4.0, -4.0, 64.0, -64.0 };
    pf_test_rng r = pf_test_rng_seed(0xed9eu);
    int i, j, k, bad = 0, n = 0;
    pf_real cmax = PF_EVSM_EXP_MAX_F32;
    for (i = 0; i < 400; ++i) {
        dist p;
        dist_moments m;
        if (i < 60) { /* constant footprints, including 0 and 1 */
            p.n = 1;
            p.z[0] = (long double)(pf_real)(i < 20 ? (i % 2 ? 1.0 : 0.0) : (i - 20) / 40.0);
            p.w[0] = 1;
        } else if (i < 120) { /* two depths, including exactly 0 and 1 */
            long double z0 = i < 80 ? 0.0L : (long double)pf_test_uniform(&r, 0, 1);
            long double f = (long double)pf_test_uniform(&r, 0, 1);
            long double z1 = i < 100 ? 1.0L : (long double)pf_test_uniform(&r, 0, 1);
            p = two_point(z0, f, z1);
        } else {
            p = random_dist(&r);
        }
        m = moments_of(&p);
        if (i % 50 == 7) { /* empty footprint: all moments 0 */
            memset(&m, 0, sizeof m);
            m.esm_log = PF_R(-1.0e30);
        }
        for (k = 0; k < (int)(sizeof perturb / sizeof perturb[0]); ++k) {
            /* perturb the higher moments by a few ulps: negative variance, singular Hankel */
            pf_real s = PF_R(1.0) + (pf_real)(perturb[k] * (double)PF_TEST_EPS);
            pf_depth_moments2 v = pf_depth_moments2_make(m.vsm.m1, m.vsm.m2 * s);
            pf_depth_moments2 e2 = pf_depth_moments2_make(m.evsm2.m1, m.evsm2.m2 * s);
            pf_evsm_moments e4 = pf_evsm_moments_make(m.evsm4.pos1, m.evsm4.pos2 * s, m.evsm4.neg1, m.evsm4.neg2 * s);
            pf_depth_moments4 q = pf_depth_moments4_make(m.msm.m1, m.msm.m2 * s, m.msm.m3 / s, m.msm.m4 * s);
            for (j = 0; j < (int)(sizeof ds / sizeof ds[0]); ++j) {
                pf_real d = (pf_real)ds[j];
                pf_vec2 b = pf_shadow_msm_bounds(q, d, ALPHA, PF_R(0.0));
                pf_vec2 b0 = pf_shadow_msm_bounds(q, d, PF_R(0.0), PF_R(0.0));
                pf_real vals[12];
                int t;
                vals[0] = pf_shadow_vsm(v, d, MINVAR, PF_R(0.0));
                vals[1] = pf_shadow_vsm(v, d, PF_R(0.0), PF_R(0.3));
                vals[2] = pf_shadow_evsm2(e2, d, CPOS, MINVAR, PF_R(0.0));
                vals[3] = pf_shadow_evsm4(e4, d, CPOS, CNEG, PF_R(0.0), PF_R(0.0));
                vals[4] = pf_shadow_esm(m.esm_log, d, CESM);
                vals[5] = b.x;
                vals[6] = b.y;
                vals[7] = b0.x;
                vals[8] = b0.y;
                vals[9] = pf_shadow_msm(q, d, PF_R(1.0), PF_R(0.0));
                vals[10] = pf_shadow_chebyshev_upper(v.m1, v.m2, d, PF_R(0.0));
                vals[11] = pf_shadow_msm(q, d, ALPHA, PF_R(0.01));
                for (t = 0; t < 12; ++t) {
                    n++;
                    if (!in_unit(vals[t])) {
                        bad++;
                        PF_CHECK(0, "value %d = %g at case %d, d = %g", t, (double)vals[t], i, ds[j]);
                    }
                }
                PF_CHECK(b.x <= b.y, "MSM lower %g > upper %g", (double)b.x, (double)b.y);
            }
        }
    }
    /* the largest exponents: EVSM with c = 44 and depths 0 and 1 (moments up to exp(88)) */
    for (i = 0; i <= 20; ++i) {
        pf_real z = (pf_real)(i / 20.0);
        pf_evsm_moments e4 = pf_evsm_moments_from_depth(z, cmax, cmax);
        pf_depth_moments2 e2 = pf_evsm2_from_depth(z, cmax);
        for (j = 0; j < (int)(sizeof ds / sizeof ds[0]); ++j) {
            pf_real d = (pf_real)ds[j];
            pf_real a = pf_shadow_evsm4(e4, d, cmax, cmax, MINVAR, PF_R(0.0));
            pf_real b = pf_shadow_evsm2(e2, d, cmax, MINVAR, PF_R(0.0));
            pf_real c = pf_shadow_esm(pf_esm_log_from_depth(z, PF_R(1.0e4)), d, PF_R(1.0e4));
            n += 3;
            if (!in_unit(a) || !in_unit(b) || !in_unit(c)) {
                bad++;
                PF_CHECK(0, "exponent limit: z %g d %g: %g %g %g", (double)z, (double)d, (double)a, (double)b, (double)c);
            }
            if ((long double)d <= (long double)z) /* lit where it must be */
                PF_CHECK(a >= PF_R(0.99) && b >= PF_R(0.99) && c >= PF_R(0.99), "c = 44 lit case reads %g %g %g",
                         (double)a, (double)b, (double)c);
        }
    }
    /* ESM log values across the whole float range */
    for (i = -30; i <= 30; i += 3) {
        pf_real l = (pf_real)(i < 0 ? -pow(10.0, -i) : pow(10.0, i));
        pf_real v = pf_shadow_esm(l, PF_R(0.5), CESM);
        n++;
        if (!in_unit(v)) {
            bad++;
            PF_CHECK(0, "ESM log %g -> %g", (double)l, (double)v);
        }
    }
    pf_test_note("%d values, %d outside [0, 1] or not finite", n, bad);
}

/* Monotone in the receiver depth where it must be: a receiver further behind is never more
   lit (Chebyshev, ESM, EVSM exactly; MSM's bound too, up to rounding). */
static void edge_shadow_monotone(void)
{
    pf_test_rng r = pf_test_rng_seed(0x303au);
    long double worst[SHS_N_METHODS];
    int i, j, m;
    for (m = 0; m < SHS_N_METHODS; ++m) worst[m] = 0;
    for (i = 0; i < 300; ++i) {
        dist p = random_dist(&r);
        dist_moments mo = moments_of(&p);
        shs_lookup L;
        pf_real prev[SHS_N_METHODS];
        memset(&L, 0, sizeof L);
        L.vsm = mo.vsm;
        L.evsm2 = mo.evsm2;
        L.evsm4 = mo.evsm4;
        L.msm = mo.msm;
        L.esm_log = mo.esm_log;
        for (j = 0; j <= 200; ++j) {
            L.d = (pf_real)(j / 200.0);
            for (m = 1; m < SHS_N_METHODS; ++m) {
                pf_real v = shs_eval(m, &L);
                if (j > 0 && (long double)v - (long double)prev[m] > worst[m]) worst[m] = (long double)v - (long double)prev[m];
                prev[m] = v;
            }
        }
    }
    pf_test_note("largest increase with d: vsm %.2g esm %.2g evsm2 %.2g evsm4 %.2g msm %.2g", (double)worst[SHS_M_VSM],
                 (double)worst[SHS_M_ESM], (double)worst[SHS_M_EVSM2], (double)worst[SHS_M_EVSM4], (double)worst[SHS_M_MSM]);
    for (m = 1; m < SHS_M_MSM; ++m)
        PF_CHECK(worst[m] <= 1e-5L, "%s increases by %.3g with d", shs_method_names[m], (double)worst[m]);
    PF_CHECK(worst[SHS_M_MSM] <= 1e-2L, "MSM increases by %.3g with d", (double)worst[SHS_M_MSM]);
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_planar_occluder_exact);
    PF_TEST_RUN(test_fully_lit_and_shadowed);
    PF_TEST_RUN(test_chebyshev_upper_bound_random);
    PF_TEST_RUN(test_msm_bounds_random);
    PF_TEST_RUN(test_msm_bounds_sharp);
    PF_TEST_RUN(test_chebyshev_scale_free);
    PF_TEST_RUN(test_reduce_bleeding);
    PF_TEST_RUN(test_scene_boxes);
    PF_TEST_RUN(test_scene_spheres);
    PF_TEST_RUN(test_scene_layers_001);
    PF_TEST_RUN(test_scene_layers_005);
    PF_TEST_RUN(test_scene_layers_02);
    PF_TEST_RUN(edge_shadow_finite);
    PF_TEST_RUN(edge_shadow_monotone);
    return PF_TEST_END();
}

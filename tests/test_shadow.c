/* test_shadow.c - tests of include/pf_shadow.h against brute force.

   Truth is never a method's own formula: it is the average of binary depth tests (the
   fraction of depths z >= d) over an explicit discrete depth distribution - seeded random
   distributions, two-depth planar occluders, constant footprints, and footprints of the
   synthetic shadow maps of tests/reference/shadow_scenes.h. The moments each method consumes are built
   from the same depths in long double with the pf_moments.h per-texel constructors and
   rounded to pf_real, as fp32 storage would hold them. The same bodies run in float, double,
   C++ and under sanitizers; edge_* tests also run under -ffast-math. */
#include "pf_shadow.h"
#include "pf_map.h"
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
    long double v[4] = { 0, 0, 0, 0 }, mu[4] = { 0, 0, 0, 0 }, e[2] = { 0, 0 }, q[4] = { 0, 0, 0, 0 }, lmax = -HUGE_VALL, s = 0;
    dist_moments r;
    int i;
    for (i = 0; i < p->n; ++i) {
        long double z = p->z[i], w = p->w[i], zs = 2.0L * z - 1.0L, u = 1.0L - z; /* MSM stores u */
        long double pp = expl((long double)CPOS * zs), nn = -expl(-(long double)CNEG * zs);
        v[0] += w * z; v[1] += w * z * z; v[2] += w * z * z * z; v[3] += w * z * z * z * z;
        mu[0] += w * u; mu[1] += w * u * u; mu[2] += w * u * u * u; mu[3] += w * u * u * u * u;
        e[0] += w * pp; e[1] += w * pp * pp;
        q[0] += w * pp; q[1] += w * pp * pp; q[2] += w * nn; q[3] += w * nn * nn;
        if ((long double)CESM * z > lmax && w > 0) lmax = (long double)CESM * z;
    }
    for (i = 0; i < p->n; ++i) s += p->w[i] * expl((long double)CESM * p->z[i] - lmax);
    r.vsm = pf_depth_moments2_make((pf_real)v[0], (pf_real)v[1]);
    r.evsm2 = pf_depth_moments2_make((pf_real)e[0], (pf_real)e[1]);
    r.evsm4 = pf_evsm_moments_make((pf_real)q[0], (pf_real)q[1], (pf_real)q[2], (pf_real)q[3]);
    r.msm = pf_depth_moments4_make((pf_real)mu[0], (pf_real)mu[1], (pf_real)mu[2], (pf_real)mu[3]);
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

/* Issue 17: two depths near the far plane, 1 (weight 0.45) and z1 (0.55), receiver at 1, the
   default bias; the truth is 0.45 (brute force: the fraction of depths >= 1). With z-power
   moments in fp32 the float upper bound read 0.4347, 0.4410, 0.9514, 0.0414 for these z1:
   the moments' rounding swamped the depth difference. The reversed storage (u = 1 - z) keeps
   it; both the stored moments and the reconstruction run through the library's own
   constructor and weighted sum in pf_real, as a shader would. */
static void test_msm_two_depth_far_plane(void)
{
    static const double z1s[4] = { 0.997, 0.999, 0.9999, 0.99999 };
    long double worst = 0;
    int i;
    char buf[160] = "";
    for (i = 0; i < 4; ++i) {
        dist p = two_point(1.0L, 0.45L, (long double)z1s[i]);
        pf_depth_moments4 m = pf_depth_moments4_add(
            pf_depth_moments4_scale(pf_depth_moments4_from_depth((pf_real)p.z[0]), PF_R(0.45)),
            pf_depth_moments4_scale(pf_depth_moments4_from_depth((pf_real)p.z[1]), PF_R(0.55)));
        pf_real up = pf_shadow_msm(m, PF_R(1.0), ALPHA, PF_SHADOW_MSM_DEPTH_BIAS_DEFAULT);
        long double err = fabsl((long double)up - lit_of(&p, 1.0L));
        size_t len = strlen(buf);
        snprintf(buf + len, sizeof buf - len, "%s%.5f: %.4f", i ? ", " : "", z1s[i], (double)up);
        if (err > worst) worst = err;
    }
    pf_test_note("lit (truth 0.45) %s", buf);
#ifdef PF_DOUBLE
    /* the bias moves the sharp bound by a (coin_ge - truth) = 3e-5 x 0.05 */
    PF_CHECK(worst <= 1e-6L + 0.05L * (long double)ALPHA, "two-depth footprint off by %.3g", (double)worst);
#else
    PF_CHECK(worst <= 0.05L, "two-depth footprint off by %.3g", (double)worst);
#endif
}

/* Issue 17: footprints clustered at any depth, with spreads 1e-5 .. 0.1 (so that the fp32
   moments lose the cluster's shape at some depths), receivers at a footprint depth or inside
   the cluster. Where the moments cannot resolve the cluster the bound must err toward lit
   (the conditioning-aware pivot floors), not fall below the truth: counted as falls of more
   than 0.1 below brute force (the z-power storage with fixed floors had 958 in 200k here). */
static void test_msm_clustered_falls(void)
{
    pf_test_rng r = pf_test_rng_seed(0x17c1u);
    int i, k, falls = 0, falls_h = 0, n = 40000;
    long double worst = 0, worst_h = 0;
    for (i = 0; i < n; ++i) {
        dist p;
        long double sum = 0, c = (long double)pf_test_uniform(&r, 0.0, 1.0);
        long double s = powl(10.0L, (long double)pf_test_uniform(&r, -5.0, -1.0)), dd;
        dist_moments m;
        pf_real d, up;
        p.n = 2 + (int)(pf_test_rng_next(&r) % 5u);
        for (k = 0; k < p.n; ++k) {
            long double z = c + s * (long double)pf_test_uniform(&r, -1.0, 1.0);
            p.z[k] = (long double)(pf_real)(z < 0 ? 0 : (z > 1 ? 1 : z));
            p.w[k] = (long double)pf_test_uniform(&r, 0.05, 1.05);
            sum += p.w[k];
        }
        for (k = 0; k < p.n; ++k) p.w[k] /= sum;
        dd = pf_test_uniform(&r, 0.0, 1.0) < 0.5 ? p.z[pf_test_rng_next(&r) % (unsigned)p.n]
                                                 : c + s * (long double)pf_test_uniform(&r, -1.0, 1.0);
        d = (pf_real)(dd < 0 ? 0 : (dd > 1 ? 1 : dd));
        m = moments_of(&p);
        up = pf_shadow_msm(m.msm, d, ALPHA, PF_R(0.0));
        if (lit_of(&p, (long double)d) - (long double)up > worst) worst = lit_of(&p, (long double)d) - (long double)up;
        falls += lit_of(&p, (long double)d) - (long double)up > 0.1L;
        up = pf_shadow_msm_hausdorff(m.msm, d, ALPHA, PF_R(0.0));
        if (lit_of(&p, (long double)d) - (long double)up > worst_h) worst_h = lit_of(&p, (long double)d) - (long double)up;
        falls_h += lit_of(&p, (long double)d) - (long double)up > 0.1L;
    }
    pf_test_note("%d clustered footprints: %d fall > 0.1 below the truth, largest fall %.2g; Hausdorff %d, largest %.2g", n, falls,
                 (double)worst, falls_h, (double)worst_h);
    /* Hausdorff is the tighter bound, so rounding reaches below the truth more easily: measured 1
       fall (0.11) in float, 0 in double */
    PF_CHECK(falls == 0 && falls_h <= 2 && worst_h <= 0.15L, "%d / %d falls of more than 0.1 below the truth (largest %.2f)",
             falls, falls_h, (double)worst_h);
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

/* ------------------------------------------------------------------ lean paths (issue 17) */

/* EVSM's lean evaluation (no scaling, the minimum variance's slope taken at E[p] for the
   positive warp and at w(d) for the negative one, the receiver-in-front test folded into
   t = max(w - m1, 0)) against the documented semantics evaluated in long double on the same
   stored moments: Chebyshev with the minimum variance mapped at whichever of w(d) and E[w] is
   nearer 0, and read as at least PF_REAL_MIN. Tolerance: the rounding of m2 - m1^2 and of t (w carries the exp argument's
   rounding, about c ulps) relative to var + t^2. Taking the slope at the wrong point moves
   the bound by 4 c^2 v / (1 + 4 c^2 v) ~ 6e-3 at c = 40, far above it. */
static long double evsm_oracle(long double m1, long double m2, long double w, long double c, long double v,
                               long double *scale)
{
    long double a = fabsl(w) < fabsl(m1) ? fabsl(w) : fabsl(m1), k = 2.0L * c * a;
    long double var = m2 - m1 * m1, mv = v * k * k, t = w - m1;
    if (var < mv) var = mv;
    /* the documented floor: a warped variance below the smallest normal is read as it (it
       matters for the negative warp with c_neg > 30 near d = 1, warped values < 1e-17) */
    if (var < (long double)PF_REAL_MIN) var = (long double)PF_REAL_MIN;
    *scale = (fabsl(m2) + m1 * m1 + (c + 4.0L) * w * w + mv) / (var + t * t);
    return t <= 0 ? 1.0L : var / (var + t * t);
}

static void test_evsm_lean_matches_chebyshev(void)
{
    static const double cs[] = { 1.0, 5.0, 20.0, 40.0, 44.0 };
    pf_test_rng r = pf_test_rng_seed(0x1e4au);
    long double worst = 0;
    int i, j, n = 0;
    for (i = 0; i < 3000; ++i) {
        dist p = random_dist(&r);
        long double cp = (long double)cs[i % 5], cn = (long double)cs[(i / 5) % 5];
        long double v = i % 7 == 0 ? 0.0L : (long double)pf_test_log_uniform(&r, 1e-8, 1e-3);
        long double q[4] = { 0, 0, 0, 0 };
        pf_evsm_moments m;
        for (j = 0; j < p.n; ++j) {
            long double zs = 2.0L * p.z[j] - 1.0L, pp = expl(cp * zs), nn = -expl(-cn * zs);
            q[0] += p.w[j] * pp; q[1] += p.w[j] * pp * pp; q[2] += p.w[j] * nn; q[3] += p.w[j] * nn * nn;
        }
        m = pf_evsm_moments_make((pf_real)q[0], (pf_real)q[1], (pf_real)q[2], (pf_real)q[3]);
        for (j = 0; j <= 40; ++j) {
            pf_real d = (pf_real)(j / 40.0);
            long double zs = 2.0L * (long double)d - 1.0L, sp, sn, e;
            long double lp = evsm_oracle((long double)m.pos1, (long double)m.pos2, expl(cp * zs), cp, v, &sp);
            long double ln = evsm_oracle((long double)m.neg1, (long double)m.neg2, -expl(-cn * zs), cn, v, &sn);
            long double got2 = (long double)pf_shadow_evsm2(pf_depth_moments2_make(m.pos1, m.pos2), d, (pf_real)cp, (pf_real)v, PF_R(0.0));
            long double got4 = (long double)pf_shadow_evsm4(m, d, (pf_real)cp, (pf_real)cn, (pf_real)v, PF_R(0.0));
            e = fabsl(got2 - lp) / (2.0L * PF_TEST_EPS * (sp + 1.0L));
            if (e > worst) worst = e;
            e = fabsl(got4 - (lp < ln ? lp : ln)) / (2.0L * PF_TEST_EPS * ((lp < ln ? sp : sn) + 1.0L));
            if (e > worst) worst = e;
            n += 2;
        }
    }
    pf_test_note("%d values; worst error %.3g of the rounding bound 2 eps (1 + (m2 + m1^2 + (c + 4) w^2 + mv) / (var + t^2))",
                 n, (double)worst);
    PF_CHECK(worst <= 1.0L, "EVSM lean path off its long double Chebyshev by %.3g bounds", (double)worst);
}

/* Degenerate moments and parameters at the edges of their domains: point masses (E[z^2] =
   E[z]^2, or a few ulps below), minimum variance 0, receivers a subnormal step behind the
   occluder, huge minimum variances with EVSM's largest exponent, bleeding thresholds 0, 0.999,
   1 and beyond: every value finite and in [0, 1], a receiver at or in front of a point mass
   exactly 1 (t = 0 gives var / var), one clearly behind it 0 (to 1e-6) when min_variance = 0. */
static void edge_shadow_degenerate(void)
{
    static const double zs[] = { 0.0, 1e-30, 0.25, 0.5, 0.999, 1.0 };
    static const double steps[] = { -0.1, 0.0, 1e-40, 1e-30, 1e-20, 1e-7, 0.1 };
    static const double bleeds[] = { 0.0, 0.3, 0.999, 1.0, 2.0, -1.0 };
    static const double mvs[] = { 0.0, 1e-6, 1.0, 4294967296.0, 1e30 };
    int i, j, k, b, n = 0, bad = 0;
    for (i = 0; i < (int)(sizeof zs / sizeof zs[0]); ++i)
        for (k = -2; k <= 0; ++k) {
            pf_real z = (pf_real)zs[i];
            pf_real z2 = z * z * (PF_R(1.0) + (pf_real)k * (pf_real)PF_TEST_EPS);
            pf_depth_moments2 m = pf_depth_moments2_make(z, z2);
            for (j = 0; j < (int)(sizeof steps / sizeof steps[0]); ++j) {
                /* volatile: under -ffast-math the compiler would otherwise fold (z + step) - z
                   inside the inlined test to step, while d itself rounds to z */
                volatile pf_real dv = z + (pf_real)steps[j];
                pf_real d = dv;
                pf_real v0 = pf_shadow_vsm(m, d, PF_R(0.0), PF_R(0.0));
                n++;
                if (!in_unit(v0)) { bad++; PF_CHECK(0, "VSM point mass z %g d %g: %g", (double)z, (double)d, (double)v0); }
                if (d <= z) PF_CHECK(v0 == PF_R(1.0), "VSM point mass, receiver in front: %g", (double)v0);
                if ((long double)d - (long double)z >= 1e-7L && k == 0)
                    PF_CHECK(v0 <= PF_R(1.0e-6), "VSM point mass z %g, receiver behind by %g: %g", (double)z,
                             (double)((long double)d - (long double)z), (double)v0);
                for (b = 0; b < (int)(sizeof bleeds / sizeof bleeds[0]); ++b) {
                    int t;
                    for (t = 0; t < (int)(sizeof mvs / sizeof mvs[0]); ++t) {
                        pf_real mv = (pf_real)mvs[t], bl = (pf_real)bleeds[b];
                        pf_real cmax = PF_EVSM_EXP_MAX_F32;
                        pf_evsm_moments e = pf_evsm_moments_from_depth(z, cmax, cmax);
                        pf_real vals[4];
                        int u;
                        vals[0] = pf_shadow_vsm(m, d, mv, bl);
                        vals[1] = pf_shadow_evsm2(pf_depth_moments2_make(e.pos1, e.pos2), d, cmax, mv, bl);
                        vals[2] = pf_shadow_evsm4(e, d, cmax, cmax, mv, bl);
                        vals[3] = pf_shadow_chebyshev_upper(m.m1, m.m2, d, mv);
                        for (u = 0; u < 4; ++u) {
                            n++;
                            if (!in_unit(vals[u])) {
                                bad++;
                                PF_CHECK(0, "test %d z %g d %g mv %g bleed %g: %g", u, (double)z, (double)d, (double)mv,
                                         (double)bl, (double)vals[u]);
                            }
                        }
                    }
                }
            }
        }
    pf_test_note("%d values, %d outside [0, 1] or not finite", n, bad);
}

/* A NaN mean reads as an unknown footprint: lit; a NaN E[z^2] alone as the minimum variance (C semantics of the comparison-based min/max;
   not an edge test, -ffast-math may drop it). A NaN bleeding threshold reads as 0. */
static void test_shadow_nan_inputs(void)
{
    pf_real nan = (pf_real)NAN;
    pf_depth_moments2 a = pf_depth_moments2_make(nan, PF_R(0.25)), b = pf_depth_moments2_make(PF_R(0.5), nan);
    pf_evsm_moments e = pf_evsm_moments_make(nan, nan, nan, nan);
    pf_real v[5];
    v[0] = pf_shadow_vsm(a, PF_R(0.7), MINVAR, PF_R(0.0));
    v[1] = pf_shadow_vsm(b, PF_R(0.7), MINVAR, PF_R(0.0));
    v[2] = pf_shadow_evsm2(a, PF_R(0.7), CPOS, MINVAR, PF_R(0.0));
    v[3] = pf_shadow_evsm4(e, PF_R(0.7), CPOS, CNEG, MINVAR, PF_R(0.0));
    v[4] = pf_shadow_chebyshev_upper(nan, PF_R(0.25), PF_R(0.7), MINVAR);
    PF_CHECK(v[0] == PF_R(1.0) && v[2] == PF_R(1.0) && v[3] == PF_R(1.0) && v[4] == PF_R(1.0) && in_unit(v[1]),
             "NaN moments: %g %g %g %g %g (want 1, and [0, 1] for a NaN E[z^2] alone: the minimum variance)",
             (double)v[0], (double)v[1], (double)v[2], (double)v[3], (double)v[4]);
    PF_CHECK(in_unit(pf_shadow_vsm(pf_depth_moments2_make(PF_R(0.3), PF_R(0.1)), PF_R(0.7), MINVAR, nan)),
             "NaN bleeding threshold");
}

/* ------------------------------------------------------------------ CSM (helper L, issue 16)
   Oracles: the Fourier coefficients of the period-2 step by quadrature, brute-force lit
   fractions, and cosl/sinl of the depths (never the library's constructor). */
#define CSM_PI 3.14159265358979323846264338327950288L

/* The filtered basis of a discrete distribution, harmonics 1..2 npairs, from cosl/sinl in
   long double, rounded to pf_real (fp32 storage in the float build). */
static void csm_values_of(const dist *p, int npairs, pf_real *v)
{
    int i, k;
    for (k = 0; k < 4 * npairs; ++k) v[k] = 0;
    for (k = 0; k < 2 * npairs; ++k) {
        long double c = 0, s = 0, f = (2.0L * (k + 1) - 1.0L) * CSM_PI;
        for (i = 0; i < p->n; ++i) {
            c += p->w[i] * cosl(f * p->z[i]);
            s += p->w[i] * sinl(f * p->z[i]);
        }
        v[2 * k] = (pf_real)c;
        v[2 * k + 1] = (pf_real)s;
    }
}
static pf_csm_pair csm_pair_at(const pf_real *v, int j) { return pf_csm_pair_make(v[4 * j], v[4 * j + 1], v[4 * j + 2], v[4 * j + 3]); }
static pf_csm_moments csm_moments_of(const pf_real *v)
{
    pf_csm_moments m;
    m.p0 = csm_pair_at(v, 0); m.p1 = csm_pair_at(v, 1); m.p2 = csm_pair_at(v, 2); m.p3 = csm_pair_at(v, 3);
    m.p4 = csm_pair_at(v, 4); m.p5 = csm_pair_at(v, 5); m.p6 = csm_pair_at(v, 6); m.p7 = csm_pair_at(v, 7);
    return m;
}
/* The raw series (no sharpening, no clamp) of `terms` harmonics through the streaming API. */
static long double csm_raw(const pf_real *v, int terms, pf_real d, pf_real offset)
{
    pf_csm_sum a = pf_csm_sum_begin(d, offset);
    int k;
    for (k = 0; k < terms; ++k) a = pf_csm_sum_add_harmonic(a, v[2 * k], v[2 * k + 1]);
    return (long double)a.value;
}

/* Eq. 36 for one depth: the library's series against the truncated Fourier series of the
   step whose coefficients come from quadrature over one period (composite Simpson on (0, 1),
   where the period-2 step is 1; it is 0 on (-1, 0)): a0/2 + sum_{n=1..2M} a_n cos(n pi x) +
   b_n sin(n pi x), even n included (quadrature finds them 0: the library omits them). */
static void test_csm_fourier_coefficients(void)
{
    enum { NQ = 4096, NH = 32 };
    long double a[NH + 1], b[NH + 1], worst = 0, worst_even = 0, worst_coef = 0;
    int n, q, i, j, t;
    static const int terms[3] = { 4, 8, 16 };
    for (n = 0; n <= NH; ++n) {
        long double sa = 0, sb = 0, h = 1.0L / (long double)NQ;
        for (q = 0; q <= NQ; ++q) {
            long double x = q * h, wq = (q == 0 || q == NQ) ? 1.0L : ((q & 1) ? 4.0L : 2.0L);
            sa += wq * cosl(n * CSM_PI * x);
            sb += wq * sinl(n * CSM_PI * x);
        }
        a[n] = sa * h / 3.0L; /* (1/L) integral over the period, L = 1 */
        b[n] = sb * h / 3.0L;
    }
    for (n = 1; n <= NH; ++n) {
        long double e = (n & 1) ? fabsl(b[n] - 2.0L / (n * CSM_PI)) : fabsl(b[n]);
        if (!(n & 1) && fabsl(b[n]) > worst_even) worst_even = fabsl(b[n]);
        if (fabsl(a[n]) > worst_even) worst_even = fabsl(a[n]);
        if ((n & 1) && e > worst_coef) worst_coef = e;
    }
    for (i = 0; i <= 20; ++i)
        for (j = 0; j <= 20; ++j)
            for (t = 0; t < 3; ++t) {
                dist p;
                pf_real v[64], d = (pf_real)(j / 20.0), off = (pf_real)(0.003 * (i % 4));
                long double x, ref = a[0] / 2.0L, got;
                p.n = 1;
                p.z[0] = (long double)(pf_real)(i / 20.0);
                p.w[0] = 1;
                csm_values_of(&p, terms[t] / 2, v);
                x = p.z[0] - (long double)d + (long double)off;
                if (!(x > -1.0L && x < 1.0L)) continue; /* the documented domain */
                for (n = 1; n <= 2 * terms[t]; ++n) ref += a[n] * cosl(n * CSM_PI * x) + b[n] * sinl(n * CSM_PI * x);
                got = csm_raw(v, terms[t], d, off);
                if (fabsl(got - ref) > worst) worst = fabsl(got - ref);
            }
    pf_test_note("quadrature: odd b_n - 2/(n pi) <= %.2g, even and cosine coefficients <= %.2g; single depth, "
                 "M = 4, 8, 16: |series - quadrature series| <= %.2g", (double)worst_coef, (double)worst_even, (double)worst);
    PF_CHECK(worst_coef <= 1e-9L && worst_even <= 1e-9L, /* Simpson, h = 1/4096, n <= 32 */ "quadrature coefficients %.3g %.3g", (double)worst_coef,
             (double)worst_even);
    /* float: phases up to 31 pi rounded to 2^-24 relative (1e-5 rad), summed over 16 terms;
       double: the quadrature coefficients' own error (3.6e-11) summed over 32 of them */
    PF_CHECK(worst <= (sizeof(pf_real) == sizeof(float) ? 2e-5L : 2e-9L), "series off the quadrature series by %.3g",
             (double)worst);
}

/* Convergence with M on two-depth footprints (z0 with weight f, z1): for a receiver at
   distance >= delta from both depths (and x = z - d inside (-1 + delta, 1 - delta)), Abel
   summation bounds the tail of the series by 2 / (pi (2M + 1) sin(pi delta)) per depth, so
   the plain series (scale 1, offset 0) is within that of the brute-force lit fraction. */
static void test_csm_convergence(void)
{
    static const int Ms[6] = { 2, 4, 8, 16, 32, 64 };
    long double worst[6] = { 0, 0, 0, 0, 0, 0 }, delta = 0.05L;
    pf_test_rng r = pf_test_rng_seed(0xc5a1u);
    int i, j, k, ok = 1;
    char buf[200] = "";
    for (i = 0; i < 400; ++i) {
        /* one draw per statement: argument evaluation order is unspecified in C */
        long double z0 = (long double)pf_test_uniform(&r, 0.05, 0.5), f = (long double)pf_test_uniform(&r, 0.1, 0.9);
        long double z1 = (long double)pf_test_uniform(&r, 0.5, 0.95);
        dist p = two_point(z0, f, z1);
        pf_real v[256];
        csm_values_of(&p, 32, v);
        for (j = 0; j <= 100; ++j) {
            pf_real d = (pf_real)(j / 100.0);
            long double truth = lit_of(&p, (long double)d);
            if (fabsl((long double)d - p.z[0]) < delta || fabsl((long double)d - p.z[1]) < delta) continue;
            if (fabsl(p.z[0] - (long double)d) > 1 - delta || fabsl(p.z[1] - (long double)d) > 1 - delta) continue;
            for (k = 0; k < 6; ++k) {
                long double e = fabsl(csm_raw(v, Ms[k], d, PF_R(0.0)) - truth);
                if (e > worst[k]) worst[k] = e;
            }
        }
    }
    for (k = 0; k < 6; ++k) {
        long double bound = 2.0L / (CSM_PI * (2 * Ms[k] + 1) * sinl(CSM_PI * delta)) + 64.0L * Ms[k] * PF_TEST_EPS;
        size_t len = strlen(buf);
        snprintf(buf + len, sizeof buf - len, "%sM=%d %.2g (bound %.2g)", k ? ", " : "", Ms[k], (double)worst[k],
                 (double)bound);
        if (!(worst[k] <= bound)) ok = 0;
        if (k > 0 && !(worst[k] < worst[k - 1])) ok = 0;
    }
    pf_test_note("two depths, receivers >= 0.05 from both: max |series - truth| %s", buf);
    PF_CHECK(ok, "CSM series does not converge within the Abel bound: %s", buf);
}

/* The pyramid (pf_depth_pyramid_from_depths, PF_DEPTH_CSM4/8/16, even and odd sizes): the
   1 x 1 top holds the mean over the map of cos/sin((2k - 1) pi z) computed with cosl/sinl
   (the polyphase box gives every texel the same weight), and an even level's texel the mean
   of its 2 x 2 block; the stamped reduce2x2 agrees with it. */
static void test_csm_pyramid_average(void)
{
    static const int kinds[3] = { PF_DEPTH_CSM4, PF_DEPTH_CSM8, PF_DEPTH_CSM16 };
    static const int ws[2] = { 8, 7 }, hs[2] = { 6, 5 };
    pf_test_rng r = pf_test_rng_seed(0xc5a2u);
    long double worst_top = 0, worst_box = 0, worst_stamp = 0;
    int t, s, i, k, x, y;
    for (t = 0; t < 3; ++t)
        for (s = 0; s < 2; ++s) {
            int w = ws[s], h = hs[s], nc = pf_depth_moment_channels(kinds[t]);
            long long total = pf_mip_texel_count(w, h), top = pf_mip_level_offset(w, h, pf_mip_level_count(w, h) - 1);
            pf_real z[56], *pyr = (pf_real *)malloc(sizeof(pf_real) * (size_t)(total * nc));
            if (!pyr) abort();
            PF_CHECK(nc == 8 << t, "kind %d has %d channels", kinds[t], nc);
            for (i = 0; i < w * h; ++i) z[i] = (pf_real)pf_test_uniform(&r, 0.0, 1.0);
            PF_CHECK(pf_depth_pyramid_from_depths(z, w, h, kinds[t], PF_R(0.0), PF_R(0.0), pyr) == PF_OK, "build");
            for (k = 0; k < nc; ++k) {
                long double f = (2.0L * (k / 2 + 1) - 1.0L) * CSM_PI, m = 0;
                for (i = 0; i < w * h; ++i) m += (k & 1) ? sinl(f * (long double)z[i]) : cosl(f * (long double)z[i]);
                m /= (long double)(w * h);
                if (fabsl((long double)pyr[top * nc + k] - m) > worst_top) worst_top = fabsl((long double)pyr[top * nc + k] - m);
            }
            if (s == 0) /* level 1 of 8 x 6 is 4 x 3: each texel the mean of a 2 x 2 block of level 0 */
                for (y = 0; y < 3; ++y)
                    for (x = 0; x < 4; ++x) {
                        const pf_real *l1 = pyr + (w * h + y * 4 + x) * nc;
                        for (k = 0; k < nc; ++k) {
                            long double m = 0;
                            int a, b;
                            for (b = 0; b < 2; ++b)
                                for (a = 0; a < 2; ++a) m += (long double)pyr[((2 * y + b) * w + 2 * x + a) * nc + k];
                            if (fabsl((long double)l1[k] - m / 4) > worst_box) worst_box = fabsl((long double)l1[k] - m / 4);
                        }
                        for (k = 0; 4 * k < nc; ++k) {
                            const pf_real *t00 = pyr + ((2 * y) * w + 2 * x) * nc + 4 * k;
                            pf_csm_pair q = pf_csm_pair_reduce2x2(
                                pf_csm_pair_make(t00[0], t00[1], t00[2], t00[3]),
                                pf_csm_pair_make(t00[nc], t00[nc + 1], t00[nc + 2], t00[nc + 3]),
                                pf_csm_pair_make(t00[w * nc], t00[w * nc + 1], t00[w * nc + 2], t00[w * nc + 3]),
                                pf_csm_pair_make(t00[(w + 1) * nc], t00[(w + 1) * nc + 1], t00[(w + 1) * nc + 2], t00[(w + 1) * nc + 3]));
                            long double e = fabsl((long double)q.cos_a - (long double)l1[4 * k]) + fabsl((long double)q.sin_a - (long double)l1[4 * k + 1])
                                          + fabsl((long double)q.cos_b - (long double)l1[4 * k + 2]) + fabsl((long double)q.sin_b - (long double)l1[4 * k + 3]);
                            if (e > worst_stamp) worst_stamp = e;
                        }
                    }
            free(pyr);
        }
    pf_test_note("top texel vs cosl/sinl mean %.2g; level-1 texel vs 2x2 mean %.2g; stamp reduce2x2 vs pyramid %.2g",
                 (double)worst_top, (double)worst_box, (double)worst_stamp);
    /* the basis of phases up to 31 pi: the argument's rounding, 31 pi x 2^-24 ~ 6e-6 in float */
    PF_CHECK(worst_top <= (sizeof(pf_real) == sizeof(float) ? 1.5e-5L : 1e-13L), "top texel off by %.3g", (double)worst_top);
    PF_CHECK(worst_box <= 8.0L * PF_TEST_EPS, "2x2 box off by %.3g", (double)worst_box);
    PF_CHECK(worst_stamp <= 16.0L * PF_TEST_EPS, "stamp differs by %.3g", (double)worst_stamp);
}

/* Degenerate and out-of-range inputs: all-zero moments (no weight: the series reads 1/2),
   moments far outside [-1, 1], receivers outside [0, 1], scales 0 .. 1e30 and negative,
   offsets, terms from -5 to 100: every value finite and in [0, 1]. */
static void edge_csm_degenerate(void)
{
    static const double ds[] = { -1.0, 0.0, 1e-30, 0.3, 0.5, 0.999, 1.0, 2.0 };
    static const double scales[] = { 0.0, 1.0, 4.0, 1e30, -1.0 };
    static const double vals[] = { 0.0, 1.0, -1.0, 1e30, -1e30, 3.0e38 };
    static const int terms[] = { -5, 0, 1, 4, 7, 16, 100 };
    int a, b, c, t, n = 0, bad = 0, zero_half = 1;
    for (a = 0; a < (int)(sizeof vals / sizeof vals[0]); ++a) {
        pf_real v[64];
        pf_csm_moments m;
        int k;
        for (k = 0; k < 64; ++k) v[k] = (pf_real)((k & 1) ? -vals[a] : vals[a]);
        m = csm_moments_of(v);
        for (b = 0; b < (int)(sizeof ds / sizeof ds[0]); ++b)
            for (c = 0; c < (int)(sizeof scales / sizeof scales[0]); ++c)
                for (t = 0; t < (int)(sizeof terms / sizeof terms[0]); ++t) {
                    pf_real lit = pf_shadow_csm(m, (pf_real)ds[b], terms[t], (pf_real)scales[c],
                                                PF_SHADOW_CSM_OFFSET_DEFAULT(16));
                    n++;
                    if (!in_unit(lit)) {
                        bad++;
                        PF_CHECK(0, "CSM value %g at moments %g d %g scale %g terms %d", (double)lit, vals[a], ds[b],
                                 scales[c], terms[t]);
                    }
                    if (a == 0 && scales[c] >= 0 && scales[c] < 1e29 && lit != PF_R(0.5)) zero_half = 0;
                }
    }
    pf_test_note("%d values, %d outside [0, 1] or not finite; all-zero moments read 1/2: %s", n, bad, zero_half ? "yes" : "no");
    PF_CHECK(zero_half, "all-zero CSM moments do not read 1/2");
}

/* NaN moments (C semantics: clamped to -1 by the comparison-based clamp; not an edge test). */
static void test_csm_nan_inputs(void)
{
    pf_real v[64], lit;
    int k;
    for (k = 0; k < 64; ++k) v[k] = (pf_real)NAN;
    lit = pf_shadow_csm(csm_moments_of(v), PF_R(0.5), 16, PF_SHADOW_CSM_SCALE_DEFAULT, PF_SHADOW_CSM_OFFSET_DEFAULT(16));
    PF_CHECK(in_unit(lit), "NaN CSM moments give %g", (double)lit);
}

/* The shadow lookup family's scenes (tests/reference/shadow_scenes.h) at M = 4, 8, 16 with the default
   scale and offset, the moments built from cosl/sinl of the stored depths: mean abs error and
   mean leak bounds (measured + 15% + 5e-4), and the documented finding that CSM up to 16
   terms stays above EVSM-4's mean error on every scene. */
static void test_csm_scenes(void)
{
    static const double bound_csm[3] = { 0.13, 0.089, 0.069 };
    shs_lookup *L = (shs_lookup *)malloc(sizeof(shs_lookup) * SHS_LOOKUPS_PER_SCENE);
    double *zd = (double *)malloc(sizeof(double) * SHS_N * SHS_N);
    long double *basis = (long double *)malloc(sizeof(long double) * SHS_N * SHS_N * 32);
    shs_stats all[3], ev;
    int s, i, t, x, y;
    char buf[400] = "";
    if (!L || !zd || !basis) abort();
    memset(all, 0, sizeof all);
    memset(&ev, 0, sizeof ev);
    for (s = 0; s < SHS_N_SCENES; ++s) {
        shs_stats sc[3], sev;
        memset(sc, 0, sizeof sc);
        memset(&sev, 0, sizeof sev);
        shs_scene_lookups(s, L);
        shs_make_scene(s, zd);
        for (i = 0; i < SHS_N * SHS_N; ++i) /* each texel's basis, of its depth as stored */
            for (t = 0; t < 16; ++t) {
                long double z = (long double)(pf_real)zd[i], f = (2.0L * t + 1.0L) * CSM_PI;
                basis[32 * i + 2 * t] = cosl(f * z);
                basis[32 * i + 2 * t + 1] = sinl(f * z);
            }
        for (i = 0; i < SHS_LOOKUPS_PER_SCENE; ++i) {
            pf_real v[64];
            pf_csm_moments m;
            int k = L[i].size, h;
            for (h = 0; h < 16; ++h) { /* E[cos], E[sin] of harmonic h + 1 over the texels */
                long double c = 0, sn = 0;
                for (y = L[i].y0; y < L[i].y0 + k; ++y)
                    for (x = L[i].x0; x < L[i].x0 + k; ++x) {
                        c += basis[32 * (y * SHS_N + x) + 2 * h];
                        sn += basis[32 * (y * SHS_N + x) + 2 * h + 1];
                    }
                v[2 * h] = (pf_real)(c / (long double)(k * k));
                v[2 * h + 1] = (pf_real)(sn / (long double)(k * k));
            }
            m = csm_moments_of(v);
            for (t = 0; t < 3; ++t) {
                int M = 4 << t;
                long double got = (long double)pf_shadow_csm(m, L[i].d, M, PF_SHADOW_CSM_SCALE_DEFAULT,
                                                             PF_SHADOW_CSM_OFFSET_DEFAULT(M));
                shs_stats_add(&sc[t], got, L[i].truth);
                shs_stats_add(&all[t], got, L[i].truth);
            }
            shs_stats_add(&sev, (long double)shs_eval(SHS_M_EVSM4, &L[i]), L[i].truth);
            shs_stats_add(&ev, (long double)shs_eval(SHS_M_EVSM4, &L[i]), L[i].truth);
        }
        {
            size_t len = strlen(buf);
            snprintf(buf + len, sizeof buf - len, "%s%s (%ld): csm4 %.4f csm8 %.4f csm16 %.4f evsm4 %.4f", s ? "; " : "",
                     shs_scene_names[s], sc[0].n, (double)shs_mean_err(&sc[0]), (double)shs_mean_err(&sc[1]),
                     (double)shs_mean_err(&sc[2]), (double)shs_mean_err(&sev));
        }
        PF_CHECK(sc[0].n > 0 && shs_mean_err(&sc[2]) > shs_mean_err(&sev), "%s: CSM-16 %.4f not above EVSM-4 %.4f",
                 shs_scene_names[s], (double)shs_mean_err(&sc[2]), (double)shs_mean_err(&sev));
    }
    pf_test_note("mean abs error: %s; all: csm4 %.4f csm8 %.4f csm16 %.4f (leak %.4f %.4f %.4f) evsm4 %.4f", buf, (double)shs_mean_err(&all[0]), (double)shs_mean_err(&all[1]), (double)shs_mean_err(&all[2]),
                 (double)shs_mean_leak(&all[0]), (double)shs_mean_leak(&all[1]), (double)shs_mean_leak(&all[2]),
                 (double)shs_mean_err(&ev));
    for (t = 0; t < 3; ++t)
        PF_CHECK(shs_mean_err(&all[t]) <= (long double)bound_csm[t], "CSM-%d mean error %.4f > %.3f", 4 << t,
                 (double)shs_mean_err(&all[t]), bound_csm[t]);
    PF_CHECK(shs_mean_err(&all[2]) < shs_mean_err(&all[1]) && shs_mean_err(&all[1]) < shs_mean_err(&all[0]),
             "CSM error does not fall with M");
    free(L);
    free(zd);
    free(basis);
}
/* pf_shadow_csm (unrolled, 8 pairs) equals the streamed series of the same `terms` harmonics,
   bit for bit, for terms 1..16; terms <= 0 reads as 1 and terms > 16 as 16 (documented). */
static void test_csm_terms_match_stream(void)
{
    pf_test_rng r = pf_test_rng_seed(0xc5a3u);
    int i, t, k, bad = 0;
    for (i = 0; i < 200; ++i) {
        dist p = random_dist(&r);
        pf_real v[64], d = (pf_real)pf_test_uniform(&r, 0.0, 1.0), sc = (pf_real)pf_test_uniform(&r, 1.0, 4.0);
        pf_real off = (pf_real)pf_test_uniform(&r, 0.0, 0.02);
        pf_csm_moments m;
        csm_values_of(&p, 8, v);
        m = csm_moments_of(v);
        for (t = -2; t <= 20; ++t) {
            int n = t < 1 ? 1 : (t > 16 ? 16 : t);
            pf_csm_sum a = pf_csm_sum_begin(d, off);
            for (k = 0; k < n; ++k) a = pf_csm_sum_add_harmonic(a, v[2 * k], v[2 * k + 1]);
            if (pf_shadow_csm(m, d, t, sc, off) != pf_csm_sum_lit(a, sc)) bad++;
        }
        { /* pairs: pf_csm_sum_add is two add_harmonic calls */
            pf_csm_sum a = pf_csm_sum_begin(d, off), b = a;
            for (k = 0; k < 8; ++k) {
                a = pf_csm_sum_add(a, csm_pair_at(v, k));
                b = pf_csm_sum_add_harmonic(pf_csm_sum_add_harmonic(b, v[4 * k], v[4 * k + 1]), v[4 * k + 2], v[4 * k + 3]);
            }
            if (a.value != b.value) bad++;
        }
    }
    PF_CHECK(bad == 0, "%d mismatches between pf_shadow_csm and the streamed series", bad);
}
/* ------------------------------------------------------------------ end of CSM */

/* ------------------------------------------------------------------ Hausdorff 4MSM, stored formats */

/* The Hausdorff bound is a bound: for random distributions of depths in [0, 1] (the same
   generator as test_msm_bounds_random, receivers uniform in [0, 1]) the upper bound is at least
   the biased truth, and never above the Hamburger bound (it only adds the support constraint). */
static void test_msm_hausdorff_bound_random(void)
{
    pf_test_rng r = pf_test_rng_seed(0x4a75u);
    long double worst_hi = 0, worst_above = 0, a = (long double)ALPHA, gain = 0;
    int i, n = 0, tighter = 0;
    for (i = 0; i < 6000; ++i) {
        dist p = random_dist(&r);
        dist_moments m = moments_of(&p);
        pf_real d = (pf_real)pf_test_uniform(&r, 0.0, 1.0);
        pf_real h = pf_shadow_msm_hausdorff(m.msm, d, ALPHA, PF_R(0.0));
        pf_real hb = pf_shadow_msm(m.msm, d, ALPHA, PF_R(0.0));
        long double coin_ge = 0.5L * ((long double)d <= 0.0L ? 1.0L : 0.0L) + 0.5L;
        long double t_ge = (1 - a) * lit_of(&p, (long double)d) + a * coin_ge;
        if (t_ge - (long double)h > worst_hi) worst_hi = t_ge - (long double)h;
        if ((long double)h - (long double)hb > worst_above) worst_above = (long double)h - (long double)hb;
        if (h < hb - PF_R(1e-4)) tighter++;
        gain += (long double)(hb - h);
        n++;
    }
    pf_test_note("%d distributions on [0, 1]: truth exceeds the Hausdorff bound by <= %.2g; above Hamburger by <= %.2g; "
                 "tighter than Hamburger (by > 1e-4) in %d, mean gain %.4f",
                 n, (double)worst_hi, (double)worst_above, tighter, (double)(gain / n));
    PF_CHECK(worst_above == 0, "Hausdorff above Hamburger by %.3g", (double)worst_above);
    PF_CHECK(tighter > n / 20, "Hausdorff tighter in only %d of %d", tighter, n);
#ifdef PF_DOUBLE
    PF_CHECK(worst_hi <= 1e-6L, "Hausdorff bound violated by %.3g", (double)worst_hi);
#else
    PF_CHECK(worst_hi <= 2e-3L, "Hausdorff bound violated by %.3g", (double)worst_hi);
#endif
}

/* Sharp: the bound is attained by the extremal distributions. Four atoms {0, uf, x, 1} (depths
   {1, d, z_x, 0}) with weights >= 0.05: the bound at the receiver d is P(z >= d) of that
   distribution (the oracle, by brute force over its atoms), whatever side of d the free atom
   lies; and for three interior atoms whose Hamburger extremal stays in [0, 1] it is the
   Hamburger value. No bias. Together with the bound property above this makes the value the
   supremum over all distributions on [0, 1] with those moments. */
static void test_msm_hausdorff_sharp(void)
{
    pf_test_rng r = pf_test_rng_seed(0x5ba2u);
    long double worst4 = 0, worst3 = 0;
    int i, k;
    for (i = 0; i < 3000; ++i) {
        dist p;
        dist_moments m;
        long double s = 0, e;
        pf_real h;
        p.n = 4;
        p.z[0] = 0.0L;
        p.z[1] = 1.0L;
        do {
            p.z[2] = (long double)(pf_real)pf_test_uniform(&r, 0.1, 0.9);
            p.z[3] = (long double)(pf_real)pf_test_uniform(&r, 0.1, 0.9);
        } while (fabsl(p.z[2] - p.z[3]) < 0.1L);
        for (k = 0; k < 4; ++k) s += (p.w[k] = (long double)pf_test_uniform(&r, 0.05, 1.0));
        for (k = 0; k < 4; ++k) p.w[k] /= s;
        m = moments_of(&p);
        h = pf_shadow_msm_hausdorff(m.msm, (pf_real)p.z[2], PF_R(0.0), PF_R(0.0));
        e = fabsl((long double)h - lit_of(&p, p.z[2]));
        if (e > worst4) worst4 = e;
        /* three interior atoms: the Hamburger extremal itself */
        p.n = 3;
        p.z[0] = (long double)(pf_real)pf_test_uniform(&r, 0.05, 0.3);
        p.z[1] = (long double)(pf_real)pf_test_uniform(&r, 0.4, 0.6);
        p.z[2] = (long double)(pf_real)pf_test_uniform(&r, 0.7, 0.95);
        s = 0;
        for (k = 0; k < 3; ++k) s += (p.w[k] = (long double)pf_test_uniform(&r, 0.1, 1.0));
        for (k = 0; k < 3; ++k) p.w[k] /= s;
        m = moments_of(&p);
        h = pf_shadow_msm_hausdorff(m.msm, (pf_real)p.z[i % 3], PF_R(0.0), PF_R(0.0));
        e = fabsl((long double)h - lit_of(&p, p.z[i % 3]));
        if (e > worst3) worst3 = e;
    }
    pf_test_note("3000 four-atom {0, d, x, 1} distributions: max |bound - attained| %.2g; 3000 interior three-atom: %.2g",
                 (double)worst4, (double)worst3);
#ifdef PF_DOUBLE
    PF_CHECK(worst4 <= 1e-8L && worst3 <= 1e-8L, "Hausdorff bound not attained: %.3g / %.3g", (double)worst4, (double)worst3);
#else
    PF_CHECK(worst4 <= 5e-3L && worst3 <= 5e-3L, "Hausdorff bound not attained: %.3g / %.3g", (double)worst4, (double)worst3);
#endif
}

/* Degenerate and arbitrary finite moments (point masses at 0, 1/2, 1, two-point footprints,
   all-zero, huge and negative values, biases 0 .. 1, receivers outside [0, 1]): Hausdorff and the
   64-bit decoders return a finite value in [0, 1]. Also under -ffast-math. */
static void edge_msm_hausdorff_finite(void)
{
    static const double vals[] = { 0.0, 1e-30, 1e-7, 0.25, 0.5, 1.0 - 1e-7, 1.0, 2.0, -1e-7, -1.0, 1e30, -1e30 };
    static const double ds[] = { -1.0, 0.0, 1e-7, 0.3, 0.5, 0.999999, 1.0, 2.0 };
    static const double biases[] = { 0.0, 3e-5, 1e-4, 1.0 };
    pf_test_rng r = pf_test_rng_seed(0xed9eu);
    const int nv = (int)(sizeof vals / sizeof vals[0]);
    long bad = 0, total = 0;
    int a, b, c, e, k, j;
    for (a = 0; a < nv; ++a)
        for (b = 0; b < nv; ++b)
            for (c = 0; c < nv; ++c)
                for (e = 0; e < nv; e += 3)
                    for (k = 0; k < 8; ++k) {
                        pf_depth_moments4 m = pf_depth_moments4_make((pf_real)vals[a], (pf_real)vals[b], (pf_real)vals[c], (pf_real)vals[e]);
                        pf_real bias = (pf_real)biases[k & 3], d = (pf_real)ds[k];
                        pf_real v1 = pf_shadow_msm_hausdorff(m, d, bias, PF_R(0.0));
                        pf_real v2 = pf_shadow_msm16(m, d, bias, PF_R(0.0));
                        pf_real v3 = pf_shadow_msm16_hausdorff(m, d, bias, PF_R(0.0));
                        bad += !(v1 >= PF_R(0.0) && v1 <= PF_R(1.0)) + !(v2 >= PF_R(0.0) && v2 <= PF_R(1.0))
                             + !(v3 >= PF_R(0.0) && v3 <= PF_R(1.0));
                        total += 3;
                    }
    /* moments of point masses and two-point footprints, as fp32 stores them */
    for (j = 0; j < 20000; ++j) {
        pf_real z0 = (pf_real)(j % 3 == 0 ? 0.0 : (j % 3 == 1 ? 1.0 : pf_test_uniform(&r, 0.0, 1.0)));
        pf_real z1 = (pf_real)pf_test_uniform(&r, 0.0, 1.0), f = (pf_real)pf_test_uniform(&r, 0.0, 1.0);
        pf_depth_moments4 m0 = pf_depth_moments4_from_depth(z0), m1 = pf_depth_moments4_from_depth(z1);
        pf_depth_moments4 m = pf_depth_moments4_make(f * m0.m1 + (1 - f) * m1.m1, f * m0.m2 + (1 - f) * m1.m2,
                                                     f * m0.m3 + (1 - f) * m1.m3, f * m0.m4 + (1 - f) * m1.m4);
        pf_real d = (pf_real)pf_test_uniform(&r, -0.1, 1.1);
        pf_real v1 = pf_shadow_msm_hausdorff(m, d, j & 1 ? ALPHA : PF_R(0.0), PF_R(0.0));
        pf_real v2 = pf_shadow_msm16_hausdorff(pf_msm_quantize_moments(m), d, PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT, PF_R(0.0));
        bad += !(v1 >= PF_R(0.0) && v1 <= PF_R(1.0)) + !(v2 >= PF_R(0.0) && v2 <= PF_R(1.0));
        total += 2;
    }
    pf_test_note("%ld values, %ld outside [0, 1] or not finite", total, bad);
    PF_CHECK(bad == 0, "%ld of %ld Hausdorff/MSM16 values outside [0, 1] or not finite", bad, total);
}

/* Linear: decode(lerp(encode a, encode b, t)) = lerp(moments a, moments b, t). Unquantized (the
   affine map in pf_real), up to its rounding; stored as UNORM16 per texel, up to the storage
   rounding (<= 1.414 x 2^-17 = 1.08e-5 per moment, see pf_shadow.h). */
static void test_msm16_linear(void)
{
    pf_test_rng r = pf_test_rng_seed(0x11e4u);
    long double worst = 0, worst_q = 0;
    int i;
    for (i = 0; i < 20000; ++i) {
        pf_real za = (pf_real)pf_test_uniform(&r, 0.0, 1.0), zb = (pf_real)pf_test_uniform(&r, 0.0, 1.0);
        pf_real t = (pf_real)pf_test_uniform(&r, 0.0, 1.0);
        pf_depth_moments4 a = pf_depth_moments4_from_depth(za), b = pf_depth_moments4_from_depth(zb);
        pf_depth_moments4 qa = pf_msm_quantize_moments(a), qb = pf_msm_quantize_moments(b);
        pf_depth_moments4 mix = pf_depth_moments4_make(qa.m1 + t * (qb.m1 - qa.m1), qa.m2 + t * (qb.m2 - qa.m2),
                                                       qa.m3 + t * (qb.m3 - qa.m3), qa.m4 + t * (qb.m4 - qa.m4));
        pf_depth_moments4 dm = pf_msm_dequantize_moments(mix);
        unsigned short sa[4], sb[4];
        pf_real zz[2];
        pf_depth_moments4 da, db;
        long double want[4], got[4], gotq[4];
        int k;
        zz[0] = za, zz[1] = zb;
        want[0] = (long double)a.m1 + (long double)t * ((long double)b.m1 - (long double)a.m1);
        want[1] = (long double)a.m2 + (long double)t * ((long double)b.m2 - (long double)a.m2);
        want[2] = (long double)a.m3 + (long double)t * ((long double)b.m3 - (long double)a.m3);
        want[3] = (long double)a.m4 + (long double)t * ((long double)b.m4 - (long double)a.m4);
        got[0] = (long double)dm.m1, got[1] = (long double)dm.m2, got[2] = (long double)dm.m3, got[3] = (long double)dm.m4;
        if (pf_shadow_encode_msm16(zz, 1, sa) != PF_OK || pf_shadow_encode_msm16(zz + 1, 1, sb) != PF_OK) { worst_q = 1; break; }
        da = pf_shadow_decode_msm16(sa), db = pf_shadow_decode_msm16(sb);
        gotq[0] = (long double)da.m1 + (long double)t * ((long double)db.m1 - (long double)da.m1);
        gotq[1] = (long double)da.m2 + (long double)t * ((long double)db.m2 - (long double)da.m2);
        gotq[2] = (long double)da.m3 + (long double)t * ((long double)db.m3 - (long double)da.m3);
        gotq[3] = (long double)da.m4 + (long double)t * ((long double)db.m4 - (long double)da.m4);
        for (k = 0; k < 4; ++k) {
            if (fabsl(got[k] - want[k]) > worst) worst = fabsl(got[k] - want[k]);
            if (fabsl(gotq[k] - want[k]) > worst_q) worst_q = fabsl(gotq[k] - want[k]);
        }
    }
    pf_test_note("20000 lerps: |decode(lerp(q)) - lerp(b)| <= %.2g unquantized, %.2g through UNORM16 (bound 1.08e-5)",
                 (double)worst, (double)worst_q);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-12L, "MSM quantization not linear: %.3g", (double)worst);
    PF_CHECK(worst_q <= 1.09e-5L, "UNORM16 error above its bound: %.3g", (double)worst_q);
#else
    PF_CHECK(worst <= 1e-5L, "MSM quantization not linear: %.3g", (double)worst);
    PF_CHECK(worst_q <= 1.2e-5L, "UNORM16 error above its bound: %.3g", (double)worst_q);
#endif
}

/* The clustered footprints of test_msm_clustered_falls stored at 64 bits per texel (each depth
   encoded by pf_shadow_encode_msm16, the decoded UNORM values averaged with the footprint's
   weights: a sampler's filter): counts of lit fractions more than 0.1 below the truth (a lit
   receiver read as shadowed: acne), Hamburger and Hausdorff, for several moment biases; the
   check is on PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT. */
static void test_msm16_clustered_falls(void)
{
    static const double biases[5] = { 0.0, 1e-5, 2e-5, 3e-5, 1e-4 };
    int falls[5][2], i, k, j, n = 40000, dflt = -1;
    long double worst[5][2];
    char line[640];
    size_t used = 0;
    for (j = 0; j < 5; ++j) {
        pf_test_rng r = pf_test_rng_seed(0x17c1u);
        falls[j][0] = falls[j][1] = 0;
        worst[j][0] = worst[j][1] = 0;
        if ((pf_real)biases[j] == PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT) dflt = j;
        for (i = 0; i < n; ++i) {
            dist p;
            long double sum = 0, c = (long double)pf_test_uniform(&r, 0.0, 1.0), acc[4] = { 0, 0, 0, 0 }, truth;
            long double s = powl(10.0L, (long double)pf_test_uniform(&r, -5.0, -1.0)), dd;
            pf_depth_moments4 b;
            pf_real d, up[2];
            int t;
            p.n = 2 + (int)(pf_test_rng_next(&r) % 5u);
            for (k = 0; k < p.n; ++k) {
                long double z = c + s * (long double)pf_test_uniform(&r, -1.0, 1.0);
                p.z[k] = (long double)(pf_real)(z < 0 ? 0 : (z > 1 ? 1 : z));
                p.w[k] = (long double)pf_test_uniform(&r, 0.05, 1.05);
                sum += p.w[k];
            }
            for (k = 0; k < p.n; ++k) {
                unsigned short q[4];
                pf_real zk = (pf_real)p.z[k];
                p.w[k] /= sum;
                if (pf_shadow_encode_msm16(&zk, 1, q) != PF_OK) q[0] = q[1] = q[2] = q[3] = 0;
                for (t = 0; t < 4; ++t) acc[t] += p.w[k] * (long double)q[t] / 65535.0L;
            }
            dd = pf_test_uniform(&r, 0.0, 1.0) < 0.5 ? p.z[pf_test_rng_next(&r) % (unsigned)p.n]
                                                     : c + s * (long double)pf_test_uniform(&r, -1.0, 1.0);
            d = (pf_real)(dd < 0 ? 0 : (dd > 1 ? 1 : dd));
            b = pf_depth_moments4_make((pf_real)acc[0], (pf_real)acc[1], (pf_real)acc[2], (pf_real)acc[3]);
            up[0] = pf_shadow_msm16(b, d, (pf_real)biases[j], PF_R(0.0));
            up[1] = pf_shadow_msm16_hausdorff(b, d, (pf_real)biases[j], PF_R(0.0));
            truth = lit_of(&p, (long double)d);
            for (t = 0; t < 2; ++t) {
                if (truth - (long double)up[t] > worst[j][t]) worst[j][t] = truth - (long double)up[t];
                falls[j][t] += truth - (long double)up[t] > 0.1L;
            }
        }
        used += (size_t)snprintf(line + used, sizeof line - used, "%sbias %.0e: %d / %d falls > 0.1 (largest %.2f / %.2f)",
                                 j ? ", " : "", biases[j], falls[j][0], falls[j][1], (double)worst[j][0], (double)worst[j][1]);
    }
    pf_test_note("%d clustered footprints at 64 bits, Hamburger / Hausdorff: %s", n, line);
    PF_CHECK(dflt >= 0, "default bias not among those tested");
    /* measured at the default: Hamburger 0 (float) / 1 (double) falls, largest 0.08 / 0.13;
       Hausdorff (the tighter bound) 3 / 5, largest 0.20 */
    if (dflt >= 0)
        PF_CHECK(falls[dflt][0] <= 2 && worst[dflt][0] <= 0.15L && falls[dflt][1] <= 8 && worst[dflt][1] <= 0.25L,
                 "%d / %d falls at the default bias (largest %.2f / %.2f)", falls[dflt][0], falls[dflt][1],
                 (double)worst[dflt][0], (double)worst[dflt][1]);
}

/* fp16 conversion: every finite fp16 value round-trips; values between two fp16 numbers round
   to the nearer (ties to even); infinities and NaN decode to finite values. */
static void test_half_conversion(void)
{
    long bad = 0;
    unsigned h;
    for (h = 0; h < 65536u; ++h) {
        pf_real v = pf_real_from_half((unsigned short)h);
        int ex = (int)((h >> 10) & 31u);
        if (!(v - v == PF_R(0.0))) bad++;
        if (ex != 31 && pf_half_from_real(v) != (unsigned short)h && !(v == PF_R(0.0) && (h & 0x7fffu) == 0)) bad++;
        if (ex < 30 && (h & 0x7fffu) != 0x7bffu) {
            pf_real next = pf_real_from_half((unsigned short)(h + 1u));
            pf_real mid = (v + next) * PF_R(0.5);
            unsigned short want = (unsigned short)((h & 1u) ? h + 1u : h); /* ties to even */
            if ((h & 0x8000u) == 0 && pf_half_from_real(mid) != want) bad++;
        }
    }
    bad += pf_half_from_real(PF_R(65519.0)) != 0x7bffu;
    bad += pf_half_from_real(PF_R(65520.0)) != 0x7c00u;
    pf_test_note("65536 fp16 patterns: %ld round-trip, midpoint or finiteness failures", bad);
    PF_CHECK(bad == 0, "%ld fp16 conversion failures", bad);
}

/* fp16 EVSM at the exponent ceiling does not overflow: the largest stored value exp(2c) at
   c = PF_EVSM_EXP_MAX_F16 is finite in fp16 (and so is every filtered mean of finite values);
   an exponent above the ceiling is refused, fp32 likewise at PF_EVSM_EXP_MAX_F32. */
static void test_f16_no_overflow(void)
{
    pf_real z[5] = { PF_R(0.0), PF_R(0.25), PF_R(0.5), PF_R(0.75), PF_R(1.0) };
    unsigned short h[20];
    float f[20];
    pf_real c = PF_EVSM_EXP_MAX_F16, largest = 0;
    int i, rc, rc_above, rc32, rc32_above, inf = 0;
    rc = pf_shadow_encode_f16(PF_SHADOW_STORE_EVSM4, z, 5, c, c, h);
    for (i = 0; i < 20; ++i) {
        pf_real v = pf_real_from_half(h[i]);
        inf += ((h[i] >> 10) & 31u) == 31u;
        if (PF_FABS(v) > largest) largest = PF_FABS(v);
    }
    rc_above = pf_shadow_encode_f16(PF_SHADOW_STORE_EVSM2, z, 5, c + PF_R(0.01), c, h);
    rc32 = pf_shadow_encode_f32(PF_SHADOW_STORE_EVSM4, z, 5, PF_EVSM_EXP_MAX_F32, PF_EVSM_EXP_MAX_F32, f);
    for (i = 0; i < 20; ++i) inf += !(f[i] - f[i] == 0.0f);
    rc32_above = pf_shadow_encode_f32(PF_SHADOW_STORE_EVSM4, z, 5, PF_EVSM_EXP_MAX_F32, PF_EVSM_EXP_MAX_F32 + PF_R(0.5), f);
    pf_test_note("fp16 at c = %.2f: largest stored %.0f (fp16 max 65504), %d non-finite; above the ceiling: %s; fp32 at 44: %s",
                 (double)c, (double)largest, inf, rc_above == PF_ERR_ARG ? "refused" : "ACCEPTED",
                 rc32_above == PF_ERR_ARG ? "refused above" : "ACCEPTED above");
    PF_CHECK(rc == PF_OK && rc32 == PF_OK, "encoders failed at the ceiling: %d %d", rc, rc32);
    PF_CHECK(inf == 0 && largest < PF_R(65504.0) && largest > PF_R(60000.0), "fp16 overflow: %d non-finite, largest %g", inf,
             (double)largest);
    PF_CHECK(rc_above == PF_ERR_ARG && rc32_above == PF_ERR_ARG, "exponent above the ceiling accepted");
}

/* Bad input: every encoder refuses NaN/inf/out-of-range depths, non-finite moments, bad exponents,
   NULL, negative and huge counts, unknown kinds - and writes nothing (the sentinel survives). */
static void test_shadow_encode_bad_input(void)
{
    pf_real z[3] = { PF_R(0.5), PF_R(0.25), PF_R(0.75) };
    pf_real bad_z[5];
    pf_depth_moments4 mb[2];
    unsigned short h[12];
    float f[12];
    int i, k, fails = 0, untouched = 1;
    bad_z[0] = (pf_real)NAN; bad_z[1] = (pf_real)INFINITY; bad_z[2] = -(pf_real)INFINITY; bad_z[3] = PF_R(-0.001);
    bad_z[4] = PF_R(1.001);
    for (i = 0; i < 12; ++i) h[i] = 0xabcdu, f[i] = 12345.0f;
    for (i = 0; i < 5; ++i) {
        z[1] = bad_z[i];
        for (k = 0; k < 4; ++k) {
            fails += pf_shadow_encode_f16(k, z, 3, PF_R(5.0), PF_R(5.0), h) != PF_ERR_ARG;
            fails += pf_shadow_encode_f32(k, z, 3, PF_R(5.0), PF_R(5.0), f) != PF_ERR_ARG;
        }
        fails += pf_shadow_encode_msm16(z, 3, h) != PF_ERR_ARG;
    }
    z[1] = PF_R(0.25);
    for (i = 0; i < 4; ++i) { /* exponents: NaN, 0, negative, inf */
        pf_real c = i == 0 ? (pf_real)NAN : (i == 1 ? PF_R(0.0) : (i == 2 ? PF_R(-1.0) : (pf_real)INFINITY));
        fails += pf_shadow_encode_f16(PF_SHADOW_STORE_EVSM2, z, 3, c, PF_R(1.0), h) != PF_ERR_ARG;
        fails += pf_shadow_encode_f16(PF_SHADOW_STORE_EVSM4, z, 3, PF_R(1.0), c, h) != PF_ERR_ARG;
        fails += pf_shadow_encode_f32(PF_SHADOW_STORE_EVSM4, z, 3, c, PF_R(1.0), f) != PF_ERR_ARG;
    }
    fails += pf_shadow_encode_f16(7, z, 3, PF_R(1.0), PF_R(1.0), h) != PF_ERR_ARG;
    fails += pf_shadow_encode_f16(-1, z, 3, PF_R(1.0), PF_R(1.0), h) != PF_ERR_ARG;
    fails += pf_shadow_encode_f16(PF_SHADOW_STORE_VSM, NULL, 3, PF_R(1.0), PF_R(1.0), h) != PF_ERR_ARG;
    fails += pf_shadow_encode_f32(PF_SHADOW_STORE_VSM, z, 3, PF_R(1.0), PF_R(1.0), NULL) != PF_ERR_ARG;
    fails += pf_shadow_encode_f16(PF_SHADOW_STORE_VSM, z, -1, PF_R(1.0), PF_R(1.0), h) != PF_ERR_ARG;
    fails += pf_shadow_encode_msm16(z, -5, h) != PF_ERR_ARG;
    fails += pf_shadow_encode_f16(PF_SHADOW_STORE_EVSM4, z, PF_MAX_REALS, PF_R(1.0), PF_R(1.0), h) != PF_ERR_SIZE;
    fails += pf_shadow_encode_msm16(z, PF_MAX_REALS / 2, h) != PF_ERR_SIZE;
    fails += pf_shadow_encode_msm16_moments(mb, PF_MAX_REALS / 2, h) != PF_ERR_SIZE;
    mb[0] = pf_depth_moments4_from_depth(PF_R(0.5));
    for (i = 0; i < 6; ++i) {
        mb[1] = pf_depth_moments4_from_depth(PF_R(0.5));
        if (i == 0) mb[1].m1 = (pf_real)NAN;
        if (i == 1) mb[1].m2 = (pf_real)INFINITY;
        if (i == 2) mb[1].m3 = -(pf_real)INFINITY;
        if (i == 3) mb[1].m4 = (pf_real)NAN;
        if (i == 4) mb[1].m1 = PF_R(1e30), mb[1].m2 = PF_R(-1e30); /* huge: no inf - inf inside */
        if (i == 5) mb[1].m4 = PF_R(2.001);
        fails += pf_shadow_encode_msm16_moments(mb, 2, h) != PF_ERR_ARG;
    }
    fails += pf_shadow_encode_msm16_moments(NULL, 2, h) != PF_ERR_ARG;
    for (i = 0; i < 12; ++i) untouched &= h[i] == 0xabcdu && f[i] == 12345.0f;
    /* n = 0 writes nothing and succeeds */
    fails += pf_shadow_encode_msm16(z, 0, h) != PF_OK;
    pf_test_note("%d wrong return codes, output %s", fails, untouched ? "untouched" : "WRITTEN");
    PF_CHECK(fails == 0 && untouched, "%d wrong codes, untouched %d", fails, untouched);
}

/* Any stored bit pattern decodes to finite values and a lit fraction in [0, 1]: the 64-bit MSM
   texel over every combination of {0, 1, 32767, 32768, 65534, 65535} per channel and 50000
   random patterns; fp16 VSM/EVSM texels over random patterns (infinities and NaN included,
   through pf_real_from_half). Also under -ffast-math. */
static void edge_shadow_decode_any_bits(void)
{
    static const unsigned short sp[6] = { 0, 1, 32767, 32768, 65534, 65535 };
    pf_test_rng r = pf_test_rng_seed(0xdec0u);
    long bad = 0, total = 0;
    int i, k;
    for (i = 0; i < 6 * 6 * 6 * 6 + 50000; ++i) {
        unsigned short t[4];
        pf_depth_moments4 b, q;
        pf_real d = (pf_real)pf_test_uniform(&r, 0.0, 1.0), v1, v2, v3, v4, v5;
        pf_evsm_moments e;
        if (i < 1296) {
            t[0] = sp[i % 6], t[1] = sp[(i / 6) % 6], t[2] = sp[(i / 36) % 6], t[3] = sp[(i / 216) % 6];
        } else {
            for (k = 0; k < 4; ++k) t[k] = (unsigned short)(pf_test_rng_next(&r) & 0xffffu);
        }
        b = pf_shadow_decode_msm16(t);
        q = pf_msm_quantize_moments(b);
        v1 = pf_shadow_msm(b, d, PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT, PF_R(0.0));
        v2 = pf_shadow_msm_hausdorff(b, d, PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT, PF_R(0.0));
        v3 = pf_shadow_msm16(q, d, PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT, PF_R(0.0));
        e = pf_evsm_moments_make(pf_real_from_half(t[0]), pf_real_from_half(t[1]), pf_real_from_half(t[2]),
                                 pf_real_from_half(t[3]));
        v4 = pf_shadow_evsm4(e, d, PF_SHADOW_EVSM16_POS_DEFAULT, PF_SHADOW_EVSM16_NEG_DEFAULT,
                             PF_SHADOW_VSM16_MIN_VARIANCE_DEFAULT, PF_R(0.0));
        v5 = pf_shadow_vsm(pf_depth_moments2_make(e.pos1, e.pos2), d, PF_SHADOW_VSM16_MIN_VARIANCE_DEFAULT, PF_R(0.0));
        bad += !(b.m1 - b.m1 == PF_R(0.0) && b.m2 - b.m2 == PF_R(0.0) && b.m3 - b.m3 == PF_R(0.0) && b.m4 - b.m4 == PF_R(0.0));
        bad += !(v1 >= PF_R(0.0) && v1 <= PF_R(1.0)) + !(v2 >= PF_R(0.0) && v2 <= PF_R(1.0))
             + !(v3 >= PF_R(0.0) && v3 <= PF_R(1.0)) + !(v4 >= PF_R(0.0) && v4 <= PF_R(1.0))
             + !(v5 >= PF_R(0.0) && v5 <= PF_R(1.0));
        total += 6;
    }
    pf_test_note("%ld decoded values, %ld outside [0, 1] or not finite", total, bad);
    PF_CHECK(bad == 0, "%ld of %ld decoded values bad", bad, total);
}

/* The stored formats on the shadow scenes: each footprint's texels encoded as stored (64-bit MSM,
   fp16 VSM/EVSM at the fp16 defaults, fp16 MSM u-moments), decoded and box-filtered (the
   sampler's work), against the same footprint in fp32 moments. Targets: 64-bit MSM within 0.01
   mean absolute lit fraction of fp32 MSM on every scene, no more mean leak than fp32 (+0.002), no
   NaN; the fp16 forms finite. */
static void test_stored_formats_scenes(void)
{
    double *zd = (double *)malloc(sizeof(double) * SHS_N * SHS_N);
    pf_real *z = (pf_real *)malloc(sizeof(pf_real) * SHS_N * SHS_N);
    unsigned short *m16 = (unsigned short *)malloc(sizeof(unsigned short) * 4 * SHS_N * SHS_N);
    unsigned short *e16 = (unsigned short *)malloc(sizeof(unsigned short) * 4 * SHS_N * SHS_N);
    const pf_real c16 = PF_SHADOW_EVSM16_POS_DEFAULT;
    shs_lookup *L = (shs_lookup *)malloc(sizeof(shs_lookup) * SHS_LOOKUPS_PER_SCENE);
    int s, i, worst_scene = 0, nonfinite = 0;
    long double worst_diff = 0, worst_leak_gap = -1, worst_e16 = 0;
    char line[320];
    if (!zd || !z || !m16 || !e16 || !L) { PF_CHECK(0, "out of memory"); free(zd); free(z); free(m16); free(e16); free(L); return; }
    for (s = 0; s < SHS_N_SCENES; ++s) {
        shs_stats st32, st16, sth32, sth16;
        long double diff = 0, de16 = 0;
        memset(&st32, 0, sizeof st32); memset(&st16, 0, sizeof st16);
        memset(&sth32, 0, sizeof sth32); memset(&sth16, 0, sizeof sth16);
        shs_make_scene(s, zd);
        for (i = 0; i < SHS_N * SHS_N; ++i) z[i] = (pf_real)zd[i];
        if (pf_shadow_encode_msm16(z, SHS_N * SHS_N, m16) != PF_OK
            || pf_shadow_encode_f16(PF_SHADOW_STORE_EVSM4, z, SHS_N * SHS_N, c16, c16, e16) != PF_OK) {
            PF_CHECK(0, "encode failed");
            break;
        }
        shs_scene_lookups(s, L);
        for (i = 0; i < SHS_LOOKUPS_PER_SCENE; ++i) {
            long double acc[4] = { 0, 0, 0, 0 };
            int x, y, k, n = L[i].size * L[i].size;
            pf_depth_moments4 b;
            pf_real v16, v32, h16, h32;
            long double ae[4] = { 0, 0, 0, 0 }, a32[4] = { 0, 0, 0, 0 };
            pf_real e16v, e32v;
            for (y = L[i].y0; y < L[i].y0 + L[i].size; ++y)
                for (x = L[i].x0; x < L[i].x0 + L[i].size; ++x) {
                    pf_evsm_moments e = pf_evsm_moments_from_depth(z[y * SHS_N + x], c16, c16);
                    for (k = 0; k < 4; ++k) {
                        acc[k] += (long double)m16[4 * (y * SHS_N + x) + k] / 65535.0L;
                        ae[k] += (long double)pf_real_from_half(e16[4 * (y * SHS_N + x) + k]);
                    }
                    a32[0] += (long double)e.pos1, a32[1] += (long double)e.pos2, a32[2] += (long double)e.neg1, a32[3] += (long double)e.neg2;
                }
            e16v = pf_shadow_evsm4(pf_evsm_moments_make((pf_real)(ae[0] / n), (pf_real)(ae[1] / n), (pf_real)(ae[2] / n), (pf_real)(ae[3] / n)),
                                   L[i].d, c16, c16, PF_SHADOW_VSM16_MIN_VARIANCE_DEFAULT, PF_R(0.0));
            e32v = pf_shadow_evsm4(pf_evsm_moments_make((pf_real)(a32[0] / n), (pf_real)(a32[1] / n), (pf_real)(a32[2] / n), (pf_real)(a32[3] / n)),
                                   L[i].d, c16, c16, PF_SHADOW_VSM16_MIN_VARIANCE_DEFAULT, PF_R(0.0));
            nonfinite += !(e16v - e16v == PF_R(0.0));
            de16 += fabsl((long double)e16v - (long double)e32v);
            b = pf_depth_moments4_make((pf_real)(acc[0] / n), (pf_real)(acc[1] / n), (pf_real)(acc[2] / n), (pf_real)(acc[3] / n));
            v16 = pf_shadow_msm16(b, L[i].d, PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT, PF_R(0.0));
            h16 = pf_shadow_msm16_hausdorff(b, L[i].d, PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT, PF_R(0.0));
            v32 = pf_shadow_msm(L[i].msm, L[i].d, ALPHA, PF_R(0.0));
            h32 = pf_shadow_msm_hausdorff(L[i].msm, L[i].d, ALPHA, PF_R(0.0));
            nonfinite += !(v16 - v16 == PF_R(0.0)) + !(h16 - h16 == PF_R(0.0));
            shs_stats_add(&st16, (long double)v16, L[i].truth);
            shs_stats_add(&st32, (long double)v32, L[i].truth);
            shs_stats_add(&sth16, (long double)h16, L[i].truth);
            shs_stats_add(&sth32, (long double)h32, L[i].truth);
            diff += fabsl((long double)v16 - (long double)v32);
        }
        diff /= SHS_LOOKUPS_PER_SCENE;
        de16 /= SHS_LOOKUPS_PER_SCENE;
        if (de16 > worst_e16) worst_e16 = de16;
        if (diff > worst_diff) worst_diff = diff, worst_scene = s;
        if (shs_mean_leak(&st16) - shs_mean_leak(&st32) > worst_leak_gap) worst_leak_gap = shs_mean_leak(&st16) - shs_mean_leak(&st32);
        snprintf(line, sizeof line, "%s: MSM64 vs fp32 %.4f, err %.4f/%.4f leak %.4f/%.4f, Hausdorff err %.4f/%.4f, "
                 "EVSM-4 fp16 vs fp32 (c = 5.54) %.4f",
                 shs_scene_names[s], (double)diff, (double)shs_mean_err(&st16), (double)shs_mean_err(&st32),
                 (double)shs_mean_leak(&st16), (double)shs_mean_leak(&st32), (double)shs_mean_err(&sth16),
                 (double)shs_mean_err(&sth32), (double)de16);
        pf_test_note("%s", line);
    }
    PF_CHECK(nonfinite == 0, "%d non-finite", nonfinite);
    PF_CHECK(worst_e16 <= 0.005L, "fp16 EVSM-4 off fp32 storage at the same exponent by %.4f", (double)worst_e16);
    PF_CHECK(worst_diff <= 0.01L, "64-bit MSM off fp32 MSM by %.4f on %s", (double)worst_diff, shs_scene_names[worst_scene]);
    PF_CHECK(worst_leak_gap <= 0.002L, "64-bit MSM leaks %.4f more than fp32", (double)worst_leak_gap);
    free(zd); free(z); free(m16); free(e16); free(L);
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_planar_occluder_exact);
    PF_TEST_RUN(test_fully_lit_and_shadowed);
    PF_TEST_RUN(test_chebyshev_upper_bound_random);
    PF_TEST_RUN(test_msm_bounds_random);
    PF_TEST_RUN(test_msm_bounds_sharp);
    PF_TEST_RUN(test_msm_two_depth_far_plane);
    PF_TEST_RUN(test_msm_clustered_falls);
    PF_TEST_RUN(test_chebyshev_scale_free);
    PF_TEST_RUN(test_reduce_bleeding);
    PF_TEST_RUN(test_scene_boxes);
    PF_TEST_RUN(test_scene_spheres);
    PF_TEST_RUN(test_scene_layers_001);
    PF_TEST_RUN(test_scene_layers_005);
    PF_TEST_RUN(test_scene_layers_02);
    PF_TEST_RUN(edge_shadow_finite);
    PF_TEST_RUN(edge_shadow_monotone);
    PF_TEST_RUN(test_evsm_lean_matches_chebyshev);
    PF_TEST_RUN(edge_shadow_degenerate);
    PF_TEST_RUN(test_shadow_nan_inputs);
    PF_TEST_RUN(test_csm_fourier_coefficients);
    PF_TEST_RUN(test_csm_convergence);
    PF_TEST_RUN(test_csm_pyramid_average);
    PF_TEST_RUN(edge_csm_degenerate);
    PF_TEST_RUN(test_csm_nan_inputs);
    PF_TEST_RUN(test_csm_scenes);
    PF_TEST_RUN(test_csm_terms_match_stream);
    PF_TEST_RUN(test_msm_hausdorff_bound_random);
    PF_TEST_RUN(test_msm_hausdorff_sharp);
    PF_TEST_RUN(edge_msm_hausdorff_finite);
    PF_TEST_RUN(test_msm16_linear);
    PF_TEST_RUN(test_msm16_clustered_falls);
    PF_TEST_RUN(test_half_conversion);
    PF_TEST_RUN(test_f16_no_overflow);
    PF_TEST_RUN(test_shadow_encode_bad_input);
    PF_TEST_RUN(edge_shadow_decode_any_bits);
    PF_TEST_RUN(test_stored_formats_scenes);
    return PF_TEST_END();
}

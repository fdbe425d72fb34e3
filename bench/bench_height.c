/* bench_height.c - cost and accuracy of pf_height.h: the visible height distribution's mean and
   deviation (three tiers), Smith height visibility, and colour-map filtering (closed form
   versus the pre-convolved table).

   Families
     visible_height_mean  mu_d(Lambda), Lambda = Lambda_o + Lambda_i: pf_visible_height_published
                          (Heitz et al. 2014 eq. 16, the BASELINE), pf_visible_height (ours),
                          pf_visible_height_exact (64-node quadrature).
     visible_height_dev   sigma_d(Lambda), published (BASELINE) and ours (eq. 17); the exact
                          tier is timed once, in visible_height_mean (same call).
     height_visibility    P_h(z)^Lambda: pf_height_visibility, and the BASELINE people write,
                          pow(0.5 erfc(-z/sqrt 2), Lambda) with the libm erfc and pow.
     colormap             E[C(X)], X ~ N(mean, sigma^2), for a fixed 8-knot piecewise-linear
                          colour map (1 channel): the 256 x 256 pre-convolved table with bilinear
                          lookup (Heitz et al. 2014 sec. 4.2, the BASELINE; its GPU form is one
                          texture fetch), pf_colormap_filter (closed form over the knots),
                          the shader loop of pf_gauss_segment_weights over the pieces, and the
                          unfiltered map at the mean (what naive code does; cost anchor and error).

   REFERENCES (long double, written here, independent of pf_height.h)
     mu_d, sigma_d: the density (L+1) phi(z) Phi(z)^L integrated by a 1200-node sinh-mapped
       trapezoidal rule centred in two passes (bench/fit/height_fit.py's truth, in long double;
       it agrees with 30-digit mpmath quadrature to ~1e-15, and tests/test_height.c checks the
       library against the adaptive oracle independently).
     visibility: expl(L * log Phi(z)), log Phi from erfcl / log1pl.
     colour map: per piece, the closed form in long double with erfcl and expl (M0 = Phi(b) -
       Phi(a) from the small tails, U1 = ((mean - x0) M0 + sigma (phi(a) - phi(b))) / w), which
       tests/test_height.c checks against quadrature.

   See pf_bench.h for what every column means; bench/run.sh (make bench) runs this. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_height.h"

/* ---------------------------------------------------------------- the colour map and its table */
#define CM_N 8
static const pf_real cm_x[CM_N] = { PF_R(-1.5), PF_R(-0.9), PF_R(-0.4), PF_R(-0.1), PF_R(0.2),
                                    PF_R(0.6), PF_R(1.1), PF_R(1.6) };
static const pf_real cm_c[CM_N] = { PF_R(0.05), PF_R(0.9), PF_R(0.3), PF_R(0.7), PF_R(0.1),
                                    PF_R(1.0), PF_R(0.4), PF_R(0.6) };
#define TAB_N 256
#define TAB_MEAN_MIN PF_R(-6.0)
#define TAB_MEAN_MAX PF_R(6.0)
#define TAB_SIGMA_MAX PF_R(1.5)
static pf_real tab_buf[TAB_N * TAB_N];
static pf_colormap_table tab;

static pf_real cm_closed(pf_real mean, pf_real sigma)
{
    pf_real out[1];
    pf_colormap_filter(cm_x, cm_c, CM_N, 1, mean, sigma, out);
    return out[0];
}

static pf_real cm_segments(pf_real mean, pf_real sigma)
{
    pf_real acc = cm_c[0] * pf_gauss_cdf(cm_x[0], mean, sigma) + cm_c[CM_N - 1] * pf_gauss_step(cm_x[CM_N - 1], mean, sigma);
    int k;
    for (k = 0; k + 1 < CM_N; k++) {
        pf_vec2 w = pf_gauss_segment_weights(cm_x[k], cm_x[k + 1], mean, sigma);
        acc += w.x * cm_c[k] + w.y * cm_c[k + 1];
    }
    return acc;
}

static pf_real cm_table(pf_real mean, pf_real sigma)
{
    pf_real out[1];
    pf_colormap_table_lookup(&tab, mean, sigma, out);
    return out[0];
}

static pf_real cm_unfiltered(pf_real mean)
{
    int k;
    if (mean < cm_x[0]) return cm_c[0];
    for (k = 0; k + 1 < CM_N; k++)
        if (mean < cm_x[k + 1]) return cm_c[k] + (cm_c[k + 1] - cm_c[k]) * (mean - cm_x[k]) / (cm_x[k + 1] - cm_x[k]);
    return cm_c[CM_N - 1];
}

/* ---------------------------------------------------------------- methods */
PFB_METHOD(mu_published, pf_visible_height_published(x).mean)
PFB_METHOD(mu_ours, pf_visible_height(x).mean)
PFB_METHOD(mu_exact, pf_visible_height_exact(x).mean)
PFB_METHOD(sd_published, pf_visible_height_published(x).dev)
PFB_METHOD(sd_ours, pf_visible_height(x).dev)

#define NAIVE_VIS(z, l) PF_POW(PF_R(0.5) * PFB_LIBM_ERFC(-(z) * PF_INV_SQRT2), (l))
PFB_METHOD(vis_ours, pf_height_visibility(x, y))
PFB_METHOD(vis_naive, NAIVE_VIS(x, y))

PFB_METHOD(cm_tab, cm_table(x, y))
PFB_METHOD(cm_cf, cm_closed(x, y))
PFB_METHOD(cm_seg, cm_segments(x, y))
PFB_METHOD(cm_naive, cm_unfiltered(x))

/* ---------------------------------------------------------------- references */
static long double ref_log_cdf(long double z)
{
    if (z >= 0.0L) return log1pl(-0.5L * erfcl(z / sqrtl(2.0L)));
    if (z > -100.0L) return logl(0.5L * erfcl(-z / sqrtl(2.0L)));
    {
        long double s = 1.0L / (z * z);
        return -0.5L * z * z - logl(-z) - 0.918938533204672741780329736405617640L +
               log1pl(s * (-1.0L + s * (3.0L + s * (-15.0L + s * 105.0L))));
    }
}

/* mass-normalized (mean, central deviation) of (L+1) phi Phi^L, 1200-node sinh trapezoid */
static void ref_moments(long double l, long double *mean, long double *dev)
{
    long double c = l > 1.0L ? sqrtl(2.0L * log1pl(l)) : 0.5L * l;
    long double s = 1.0L / (1.0L + 0.3L * log1pl(l));
    int pass, i;
    const int n = 1200;
    for (pass = 0; pass < 2; pass++) {
        long double x0 = -6.0L, h = 13.0L / (long double)(n - 1), a = 0.5L * s;
        long double m0 = 0.0L, m1 = 0.0L, m2 = 0.0L, e1;
        for (i = 0; i < n; i++) {
            long double x = x0 + (long double)i * h;
            long double d = a * sinhl(x), z = c + d;
            long double lp = l > 0.0L ? l * ref_log_cdf(z) : 0.0L;
            long double v = expl(log1pl(l) - 0.5L * z * z + lp) * a * coshl(x);
            m0 += v;
            m1 += v * d;
            m2 += v * d * d;
        }
        e1 = m1 / m0;
        c += e1;
        s = sqrtl(m2 / m0 - e1 * e1);
    }
    *mean = c;
    *dev = s;
}

static long double ref_mu(long double x, long double y, long double z)
{
    long double m, d;
    (void)y; (void)z;
    ref_moments(x, &m, &d);
    return m;
}

static long double ref_sd(long double x, long double y, long double z)
{
    long double m, d;
    (void)y; (void)z;
    ref_moments(x, &m, &d);
    return d;
}

static long double ref_vis(long double x, long double y, long double z)
{
    (void)z;
    return expl(y * ref_log_cdf(x));
}

static long double ref_cm(long double mean, long double sigma, long double z)
{
    long double acc = 0.0L, r2 = sqrtl(2.0L);
    int k;
    (void)z;
    if (sigma <= 0.0L) return (long double)cm_unfiltered((pf_real)mean);
    acc = (long double)cm_c[0] * 0.5L * erfcl(-((long double)cm_x[0] - mean) / sigma / r2) +
          (long double)cm_c[CM_N - 1] * 0.5L * erfcl(((long double)cm_x[CM_N - 1] - mean) / sigma / r2);
    for (k = 0; k + 1 < CM_N; k++) {
        long double x0 = (long double)cm_x[k], x1 = (long double)cm_x[k + 1];
        long double a = (x0 - mean) / sigma, b = (x1 - mean) / sigma, m0, u1;
        if (a >= 0.0L) m0 = 0.5L * (erfcl(a / r2) - erfcl(b / r2));
        else if (b <= 0.0L) m0 = 0.5L * (erfcl(-b / r2) - erfcl(-a / r2));
        else m0 = 1.0L - 0.5L * erfcl(-a / r2) - 0.5L * erfcl(b / r2);
        u1 = ((mean - x0) * m0 + sigma * (expl(-0.5L * a * a) - expl(-0.5L * b * b)) * 0.398942280401432677939946059934381868L) / (x1 - x0);
        acc += (long double)cm_c[k] * (m0 - u1) + (long double)cm_c[k + 1] * u1;
    }
    return acc;
}

/* ---------------------------------------------------------------- inputs */
/* Lambda: log-uniform in [1e-3, 1e3] (a shading mix of near-normal and grazing views). */
static void gen_lambda(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) a[i] = (pf_real)pfb_logunif(r, 1e-3, 1e3);
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
}

/* accuracy: 200 log-spaced in [1e-4, 1], 200 uniform in (1, 1000] (the range; L = 0,
   where mu_d = 0 exactly, is in tests/test_height.c) */
static size_t grid_lambda(pf_real *a, pf_real *b, pf_real *c)
{
    size_t i, n = 400;
    if (!a) return n;
    for (i = 0; i < 200; ++i) a[i] = (pf_real)(1e-4 * pow(1e4, (double)i / 199.0));
    for (i = 0; i < 200; ++i) a[200 + i] = (pf_real)(1.0 + 999.0 * (double)(i + 1) / 200.0);
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
    return n;
}

/* visibility: z uniform in [-4, 4], Lambda log-uniform in [1e-2, 1e2] */
static void gen_vis(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_unif_in(r, -4.0, 4.0);
        b[i] = (pf_real)pfb_logunif(r, 1e-2, 1e2);
    }
    memset(c, 0, n * sizeof *c);
}

/* 301 z uniform in [-12, 12] x 41 Lambda log-spaced in [1e-3, 1e9] */
static size_t grid_vis(pf_real *a, pf_real *b, pf_real *c)
{
    size_t i, j, n = 301 * 41;
    if (!a) return n;
    for (i = 0; i < 301; ++i)
        for (j = 0; j < 41; ++j) {
            a[i * 41 + j] = (pf_real)(-12.0 + 24.0 * (double)i / 300.0);
            b[i * 41 + j] = (pf_real)(1e-3 * pow(1e12, (double)j / 40.0));
        }
    memset(c, 0, n * sizeof *c);
    return n;
}

/* colour map: mean uniform in [-2.5, 2.5], sigma uniform in [0, 1.5] */
static void gen_cm(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_unif_in(r, -2.5, 2.5);
        b[i] = (pf_real)pfb_unif_in(r, 0.0, 1.5);
    }
    memset(c, 0, n * sizeof *c);
}

/* 601 means uniform in [-2.5, 2.5] x 61 sigmas uniform in [0.0025, 1.5] (off the table's grid) */
static size_t grid_cm(pf_real *a, pf_real *b, pf_real *c)
{
    size_t i, j, n = 601 * 61;
    if (!a) return n;
    for (i = 0; i < 601; ++i)
        for (j = 0; j < 61; ++j) {
            a[i * 61 + j] = (pf_real)(-2.5 + 5.0 * (double)i / 600.0);
            b[i * 61 + j] = (pf_real)(0.0025 + 1.4975 * (double)j / 60.0);
        }
    memset(c, 0, n * sizeof *c);
    return n;
}

/* ---------------------------------------------------------------- families */
#define VH_NOTES                                                                              \
    "timing inputs: Lambda = Lambda_o + Lambda_i log-uniform in [1e-3, 1e3] (seeded)\n"       \
    "grid: 200 Lambda log-spaced in [1e-4, 1], 200 uniform in (1, 1000]\n"               \
    "reference: long double 1200-node sinh-mapped trapezoid of (L+1) phi Phi^L, two centring " \
    "passes (see bench_height.c)"

static const pfb_family families[] = {
    { "visible_height_mean", 1, { "Lambda", NULL }, 0, VH_NOTES, gen_lambda, grid_lambda, 3,
      { PFB_ENTRY("pf_visible_height_published", mu_published, ref_mu, 0),
        PFB_ENTRY("pf_visible_height", mu_ours, ref_mu, 0),
        PFB_ENTRY("pf_visible_height_exact", mu_exact, ref_mu, 0) } },
    { "visible_height_dev", 1, { "Lambda", NULL }, 0,
      VH_NOTES "\nthe exact tier is timed in visible_height_mean only (the same call; ~1000x the "
      "baseline, it would dominate the bench's run time); its sigma_d error is in docs/height.md's test table",
      gen_lambda, grid_lambda, 2,
      { PFB_ENTRY("pf_visible_height_published", sd_published, ref_sd, 0),
        PFB_ENTRY("pf_visible_height", sd_ours, ref_sd, 0) } },
    { "height_visibility", 2, { "z", "Lambda" }, 1,
      "timing inputs: z uniform in [-4, 4], Lambda log-uniform in [1e-2, 1e2] (seeded)\n"
      "grid: 301 z uniform in [-12, 12] x 41 Lambda log-spaced in [1e-3, 1e9] (the conditioning of V grows with |log V| and Lambda z^2)\n"
      "reference: expl(Lambda log Phi(z)), log Phi from erfcl/log1pl\n"
      "baseline naive_pow_erfc: pow(0.5 erfc(-z/sqrt 2), Lambda) with libm erfc and pow",
      gen_vis, grid_vis, 2,
      { PFB_ENTRY("pf_height_visibility", vis_ours, ref_vis, 0),
        PFB_ENTRY("naive_pow_erfc" PFB_LIBM_SUFFIX, vis_naive, ref_vis, 0) } },
    { "colormap", 2, { "mean", "sigma" }, 0,
      "timing inputs: mean uniform in [-2.5, 2.5], sigma uniform in [0, 1.5] (seeded); an 8-knot "
      "piecewise-linear map on [-1.5, 1.6], 1 channel\n"
      "grid: 601 means uniform in [-2.5, 2.5] x 61 sigmas uniform in [0.0025, 1.5] (between the table's samples)\n"
      "reference: long double closed form per piece (erfcl, expl); the table is 256 x 256 over mean "
      "[-6, 6], sigma [0, 1.5] (the paper's size), bilinear\n"
      "unfiltered_map_at_mean: C(mean), what code without pre-filtering does (its error is the aliasing)",
      gen_cm, grid_cm, 4,
      { PFB_ENTRY("pf_colormap_table_lookup", cm_tab, ref_cm, 0),
        PFB_ENTRY("pf_colormap_filter", cm_cf, ref_cm, 0),
        PFB_ENTRY("pf_gauss_segment_weights_loop", cm_seg, ref_cm, 0),
        PFB_ENTRY("unfiltered_map_at_mean", cm_naive, ref_cm, 0) } },
};

int main(int argc, char **argv)
{
    if (pf_colormap_table_build(&tab, tab_buf, TAB_N, TAB_N, TAB_MEAN_MIN, TAB_MEAN_MAX, TAB_SIGMA_MAX, cm_x, cm_c,
                                CM_N, 1) != 0) {
        fprintf(stderr, "bench_height: table build failed\n");
        return 2;
    }
    return pfb_main(argc, argv, "height", families, (int)(sizeof families / sizeof families[0]));
}

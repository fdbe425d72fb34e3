/* test_vmf_fit.c - tests of include/pf_vmf_fit.h (the EM fit, the lobe pyramid; the scaling
   function's tests are tests/test_vmf_scale.c).

   The truth is never the module's own formula:
   - EM: normals sampled (seeded) from known vMF mixtures must give back the lobes;
   - degenerate input: equal normals, zero and NaN weights, NaN normals, bad sizes, and
     canaries after every buffer;
   Same bodies in float and double; edge_* tests also run under -ffast-math. */
/* MAP_ANONYMOUS and MAP_NORESERVE for pf_test_guarded_alloc under -std=c99 (before any include) */
#if defined(__unix__) && !defined(_DEFAULT_SOURCE)
#  define _DEFAULT_SOURCE 1
#endif
#include "pf_vmf_fit.h"
#include "pf_oracle.h"
#include "pf_test.h"
#include "pf_microsurface.h"

/* ------------------------------------------------------------------ seeded sampling */
typedef struct trng { unsigned long long s; } trng;
static double trng_u(trng *r)
{
    unsigned long long z = (r->s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/* one normal from a vMF of axis mu, kappa: cos t = 1 + log(u + (1 - u) e^(-2 kappa)) / kappa */
static void sample_vmf(trng *r, const double mu[3], double kappa, double out[3])
{
    double u = trng_u(r), ph = 2.0 * PFM_PI * trng_u(r);
    double c = 1.0 + log(u + (1.0 - u) * exp(-2.0 * kappa)) / kappa, s = sqrt(fmax(0.0, 1.0 - c * c));
    double t1[3], t2[3], a[3] = { 1, 0, 0 }, l;
    int k;
    if (fabs(mu[0]) > 0.9) {
        a[0] = 0;
        a[1] = 1;
    }
    t1[0] = a[1] * mu[2] - a[2] * mu[1];
    t1[1] = a[2] * mu[0] - a[0] * mu[2];
    t1[2] = a[0] * mu[1] - a[1] * mu[0];
    l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (k = 0; k < 3; ++k) t1[k] /= l;
    t2[0] = mu[1] * t1[2] - mu[2] * t1[1];
    t2[1] = mu[2] * t1[0] - mu[0] * t1[2];
    t2[2] = mu[0] * t1[1] - mu[1] * t1[0];
    for (k = 0; k < 3; ++k) out[k] = c * mu[k] + s * (cos(ph) * t1[k] + sin(ph) * t2[k]);
}

static void dir_deg(double theta, double phi, double w[3])
{
    theta *= PFM_PI / 180.0;
    phi *= PFM_PI / 180.0;
    w[0] = sin(theta) * cos(phi);
    w[1] = sin(theta) * sin(phi);
    w[2] = cos(theta);
}

/* ------------------------------------------------------------------ EM */
static void test_em_recovers_mixture(void)
{
    static const double amp[3] = { 0.5, 0.3, 0.2 }, kap[3] = { 400.0, 150.0, 800.0 };
    static const double th[3] = { 0.0, 25.0, 30.0 }, ph[3] = { 0.0, 40.0, 200.0 };
    enum { N = 20000 };
    pf_real *nr = (pf_real *)malloc(N * 3 * sizeof(pf_real));
    trng r;
    pf_vmf_mixture m;
    long double worst_ang = 0, worst_amp = 0, worst_k = 0;
    int i, k, j;
    r.s = 77;
    for (i = 0; i < N; ++i) {
        double u = trng_u(&r), mu[3], x[3];
        k = u < amp[0] ? 0 : (u < amp[0] + amp[1] ? 1 : 2);
        dir_deg(th[k], ph[k], mu);
        sample_vmf(&r, mu, kap[k], x);
        for (j = 0; j < 3; ++j) nr[3 * i + j] = (pf_real)x[j];
    }
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, N, 3, 50, &m) == PF_OK, "fit failed");
    PF_CHECK(m.count == 3, "%d lobes", m.count);
    for (k = 0; k < 3 && m.count == 3; ++k) {
        double mu[3];
        long double best = 10, ea, ek;
        int bj = 0;
        dir_deg(th[k], ph[k], mu);
        for (j = 0; j < 3; ++j) {
            long double d = acosl(fminl(1.0L, (long double)(mu[0] * (double)m.lobe[j].mu.x + mu[1] * (double)m.lobe[j].mu.y +
                                                            mu[2] * (double)m.lobe[j].mu.z)));
            if (d < best) {
                best = d;
                bj = j;
            }
        }
        ea = fabsl((long double)m.lobe[bj].amp - (long double)amp[k]);
        ek = fabsl((long double)m.lobe[bj].kappa - (long double)kap[k]) / (long double)kap[k];
        if (best > worst_ang) worst_ang = best;
        if (ea > worst_amp) worst_amp = ea;
        if (ek > worst_k) worst_k = ek;
    }
    pf_test_note("3 lobes from 20000 normals: axis %.2Lg deg, amplitude %.4Lf, kappa %.3Lf (rel)",
                 worst_ang * 180.0L / PF_TEST_PI, worst_amp, worst_k);
    PF_CHECK(worst_ang <= 0.01L && worst_amp <= 0.01L && worst_k <= 0.1L, "axis %.3Lg rad, amp %.4Lf, kappa %.3Lf",
             worst_ang, worst_amp, worst_k);
    free(nr);
}

static void test_em_deterministic_and_weighted(void)
{
    /* the same input twice gives the same bits; weight 2 on a point = the point twice */
    enum { N = 600 };
    pf_real nr[2 * N * 3], w[2 * N];
    pf_vmf_mixture a, b, c;
    trng r;
    int i, j, same = 1, close = 1;
    r.s = 5;
    for (i = 0; i < N; ++i) {
        double mu[3], x[3];
        dir_deg(i % 2 ? 20.0 : 0.0, i % 3 ? 0.0 : 120.0, mu);
        sample_vmf(&r, mu, 200.0, x);
        for (j = 0; j < 3; ++j) nr[3 * i + j] = nr[3 * (N + i) + j] = (pf_real)x[j];
        w[i] = PF_R(2.0);
        w[N + i] = PF_R(1.0);
    }
    pf_vmf_fit_normals(nr, NULL, N, 4, 30, &a);
    pf_vmf_fit_normals(nr, NULL, N, 4, 30, &b);
    pf_vmf_fit_normals(nr, w, N, 4, 30, &c); /* weights 2 on the first N */
    same = a.count == b.count;
    for (i = 0; i < a.count && same; ++i) /* field by field: the struct may have padding */
        same = a.lobe[i].amp == b.lobe[i].amp && a.lobe[i].kappa == b.lobe[i].kappa && a.lobe[i].mu.x == b.lobe[i].mu.x && a.lobe[i].mu.y == b.lobe[i].mu.y &&
               a.lobe[i].mu.z == b.lobe[i].mu.z;
    for (i = 0; i < a.count; ++i)
        if (fabs((double)(a.lobe[i].amp - c.lobe[i].amp)) > 1e-5 || fabs((double)(a.lobe[i].kappa - c.lobe[i].kappa)) > 1e-3 * (double)a.lobe[i].kappa)
            close = 0;
    PF_CHECK(same, "two fits differ");
    PF_CHECK(close && a.count == c.count, "uniform weights 2 changed the fit");
}

/* ------------------------------------------------------------------ degenerate input, buffers */
/* NaN inputs: not an edge_ test (-ffast-math compiles NaN tests away; its results on NaN
   input are undefined) */
static void test_fit_degenerate(void)
{
    pf_real nr[3 * 16], wz[16], pyr[400];
    pf_vmf_mixture m;
    int i, rc;
    for (i = 0; i < 16; ++i) {
        nr[3 * i] = PF_R(0.3);
        nr[3 * i + 1] = PF_R(0.0);
        nr[3 * i + 2] = PF_R(0.9);
        wz[i] = PF_R(0.0);
    }
    rc = pf_vmf_fit_normals(nr, NULL, 16, 8, 20, &m);
    PF_CHECK(rc == PF_OK && m.count == 1 && m.lobe[0].kappa == PF_VMF_KAPPA_MAX, "equal normals: rc %d, %d lobes", rc, m.count);
    m.count = 99;
    rc = pf_vmf_fit_normals(nr, wz, 16, 4, 20, &m);
    PF_CHECK(rc == PF_ERR_ARG && m.count == 99, "zero weights: rc %d, *out written on the error", rc);
    nr[0] = (pf_real)NAN;
    nr[4] = (pf_real)INFINITY;
    wz[5] = (pf_real)NAN;
    for (i = 6; i < 16; ++i) wz[i] = PF_R(1.0);
    nr[3 * 7 + 1] = PF_R(0.2);
    rc = pf_vmf_fit_normals(nr, wz, 16, 4, 20, &m);
    PF_CHECK(rc == PF_OK && m.count >= 1, "NaN normals skipped: rc %d", rc);
    for (i = 0; i < m.count; ++i)
        PF_CHECK(isfinite((double)m.lobe[i].amp) && isfinite((double)m.lobe[i].kappa) && isfinite((double)m.lobe[i].mu.z), "lobe %d not finite", i);
    for (i = 0; i < 16 * 3; ++i) nr[i] = (pf_real)NAN;
    m.count = 99;
    rc = pf_vmf_fit_normals(nr, NULL, 16, 4, 20, &m);
    PF_CHECK(rc == PF_ERR_ARG && m.count == 99, "all NaN: rc %d, *out written on the error", rc);
    PF_CHECK(pf_vmf_fit_normals(NULL, NULL, 16, 4, 20, &m) == PF_ERR_ARG, "NULL normals");
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, 16, 0, 20, &m) == PF_ERR_ARG, "0 lobes");
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, 16, PF_VMF_MAX_LOBES + 1, 20, &m) == PF_ERR_ARG, "17 lobes");
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, 0, 4, 20, &m) == PF_ERR_ARG, "0 normals");
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, 16, 4, 20, NULL) == PF_ERR_ARG, "NULL out");
    /* pyramid of a NaN map: flat lobes, PF_OK, nothing past the buffer */
    for (i = 0; i < 400; ++i) pyr[i] = PF_R(-7.0);
    PF_CHECK(pf_vmf_pyramid_texel_count(4, 4) == 21, "texel count %lld", pf_vmf_pyramid_texel_count(4, 4));
    rc = pf_vmf_pyramid_from_normals(nr, NULL, 4, 4, 2, 10, pyr);
    PF_CHECK(rc == PF_OK, "NaN map rc %d", rc);
    for (i = 0; i < 21 * 8; ++i) PF_CHECK(isfinite((double)pyr[i]) && pyr[i] != PF_R(-7.0), "texel value %d unwritten", i);
    for (i = 21 * 8; i < 400; ++i) PF_CHECK(pyr[i] == PF_R(-7.0), "canary %d overwritten", i);
    PF_CHECK(pf_vmf_pyramid_from_normals(nr, NULL, 3, 4, 2, 10, pyr) == PF_ERR_ARG, "non power of two");
    PF_CHECK(pf_vmf_pyramid_from_normals(nr, NULL, 4, 4, PF_VMF_MAX_LOBES + 1, 10, pyr) == PF_ERR_ARG, "17 lobes");
    PF_CHECK(pf_vmf_pyramid_from_normals(NULL, NULL, 4, 4, 2, 10, pyr) == PF_ERR_ARG, "NULL");
    PF_CHECK(pf_vmf_pyramid_texel_count(0, 4) == 0 && pf_vmf_pyramid_level_offset(5, 4, 1) == -1, "bad sizes");
}

static void test_pyramid_levels(void)
{
    /* 8 x 4 map: levels 8x4, 4x2, 2x1, 1x1; the top texel equals the fit of the whole map,
       every level-0 texel its own normal (one sharp lobe) */
    enum { W = 8, H = 4 };
    pf_real nr[W * H * 3], pyr[43 * 4 * 2 + 8];
    trng r;
    pf_vmf_mixture whole, top, t0;
    long long off;
    int i, j, ok = 1;
    r.s = 3;
    for (i = 0; i < W * H; ++i) {
        double mu[3] = { 0, 0, 1 }, x[3];
        sample_vmf(&r, mu, 20.0, x);
        for (j = 0; j < 3; ++j) nr[3 * i + j] = (pf_real)x[j];
    }
    for (i = 0; i < (int)(sizeof pyr / sizeof pyr[0]); ++i) pyr[i] = PF_R(-7.0);
    PF_CHECK(pf_vmf_pyramid_level_count(W, H) == 4, "levels %d", pf_vmf_pyramid_level_count(W, H));
    PF_CHECK(pf_vmf_pyramid_texel_count(W, H) == 32 + 8 + 2 + 1, "texels %lld", pf_vmf_pyramid_texel_count(W, H));
    PF_CHECK(pf_vmf_pyramid_from_normals(nr, NULL, W, H, 2, 30, pyr) == PF_OK, "rc");
    off = pf_vmf_pyramid_level_offset(W, H, 3);
    top = pf_vmf_mixture_from_texel(pyr + off * 8, 2);
    pf_vmf_fit_normals(nr, NULL, W * H, 2, 30, &whole);
    PF_CHECK(top.count == whole.count, "top %d lobes, whole %d", top.count, whole.count);
    for (i = 0; i < top.count && i < whole.count; ++i)
        if (top.lobe[i].amp != whole.lobe[i].amp || top.lobe[i].kappa != whole.lobe[i].kappa || top.lobe[i].mu.x != whole.lobe[i].mu.x) ok = 0;
    PF_CHECK(ok, "top texel differs from the fit of the whole map");
    t0 = pf_vmf_mixture_from_texel(pyr + 5 * 8, 2);
    PF_CHECK(t0.count == 1 && t0.lobe[0].kappa == PF_VMF_KAPPA_MAX &&
                 fabs((double)(t0.lobe[0].mu.x - nr[15] / pf_vec3_length(pf_vec3_make(nr[15], nr[16], nr[17])))) < 1e-5,
             "level-0 texel 5: %d lobes, kappa %g", t0.count, (double)t0.lobe[0].kappa);
    for (i = 43 * 8; i < (int)(sizeof pyr / sizeof pyr[0]); ++i) PF_CHECK(pyr[i] == PF_R(-7.0), "canary %d", i);
}

/* ================================================================== SAFETY: scaling of the inputs, contracts
   Reproducers of the defects found by probing the CPU functions as a new user would (guard
   pages, the whole int range, tiny and huge data): each test names the call that failed and
   checks the contract instead. edge_ ones also run under -ffast-math. */
/* pf_vmf_fit_normals on weights 1e-40 (float) / 1e-310 (double), PF_REAL_MAX, and normals
   scaled by 1e19 / 1e-16 (double 1e100 / 1e-100): before, PF_ERR_ARG and the flat lobe (the
   pyramid: flat lobes and PF_OK). Every scaling now gives the unscaled fit. (Not under
   -ffast-math: it flushes subnormal weights to 0.) */
static void test_safety_fit_scaled_inputs(void)
{
    pf_real nr[3 * 16], n2[3 * 16], wt[16], pyr_ref[21 * 8], pyr[21 * 8];
    pf_vmf_mixture ref, m;
#ifdef PF_DOUBLE
    const pf_real tiny_w = (pf_real)1e-310, big_n = PF_R(1e100), small_n = PF_R(1e-100);
#else
    const pf_real tiny_w = (pf_real)1e-40, big_n = PF_R(1e19), small_n = PF_R(1e-16);
#endif
    const pf_real ws[3] = { tiny_w, PF_REAL_MAX, PF_R(1.0) }, ns[3] = { PF_R(1.0), big_n, small_n };
    int i, k, q, rc;
    long double worst = 0;
    for (i = 0; i < 16; ++i) {
        nr[3 * i] = PF_R(0.3) * (pf_real)(i % 4) / PF_R(3.0);
        nr[3 * i + 1] = PF_R(0.2) * (pf_real)(i / 4) / PF_R(3.0) - PF_R(0.1);
        nr[3 * i + 2] = PF_R(0.9);
    }
    rc = pf_vmf_fit_normals(nr, NULL, 16, 2, 20, &ref);
    PF_CHECK(rc == PF_OK && ref.count == 2, "reference fit rc %d, %d lobes", rc, ref.count);
    for (k = 0; k < 3; ++k)
        for (q = 0; q < 3; ++q) {
            for (i = 0; i < 16; ++i) wt[i] = ws[k];
            for (i = 0; i < 48; ++i) n2[i] = nr[i] * ns[q];
            rc = pf_vmf_fit_normals(n2, wt, 16, 2, 20, &m);
            PF_CHECK(rc == PF_OK && m.count == ref.count, "weights %g, normals x %g: rc %d, %d lobes", (double)ws[k], (double)ns[q], rc,
                     m.count);
            if (rc != PF_OK || m.count != ref.count) continue;
            for (i = 0; i < m.count; ++i) {
                worst = fmaxl(worst, fabsl((long double)m.lobe[i].kappa / (long double)ref.lobe[i].kappa - 1.0L));
                worst = fmaxl(worst, fabsl((long double)m.lobe[i].amp - (long double)ref.lobe[i].amp));
                worst = fmaxl(worst, fabsl((long double)m.lobe[i].mu.x - (long double)ref.lobe[i].mu.x));
                worst = fmaxl(worst, fabsl((long double)m.lobe[i].mu.y - (long double)ref.lobe[i].mu.y));
            }
        }
    /* the scaled inputs round differently (a few eps per normal), which the EM's stopping
       rule (log-likelihood change below 1e-6) can carry into the lobes: 1e-5, against the
       flat lobe (kappa 1e5 for 197) the fit returned before */
    pf_test_note("tiny/huge weights and normals: worst lobe difference %.2Le", worst);
    PF_CHECK(worst <= 1e-5L, "worst %.3Le", worst);
    /* the pyramid: a 4 x 4 map of those normals with tiny weights equals the unweighted one */
    for (i = 0; i < 16; ++i) wt[i] = tiny_w;
    PF_CHECK(pf_vmf_pyramid_from_normals(nr, NULL, 4, 4, 2, 20, pyr_ref) == PF_OK, "pyramid ref");
    for (i = 0; i < 48; ++i) n2[i] = nr[i] * big_n;
    PF_CHECK(pf_vmf_pyramid_from_normals(n2, wt, 4, 4, 2, 20, pyr) == PF_OK, "pyramid");
    worst = 0;
    for (i = 0; i < 21 * 8; ++i)
        worst = fmaxl(worst, fabsl((long double)pyr[i] - (long double)pyr_ref[i]) / (1.0L + fabsl((long double)pyr_ref[i])));
    pf_test_note("pyramid %.2Le", worst);
    PF_CHECK(worst <= 1e-5L, "pyramid of scaled input differs by %.3Le", worst);
}

/* contracts: pf_vmf_pyramid_texel_count(2^24, 2^24) was 375299968947541 (> PF_MAX_REALS), now
   0 and the pyramid refuses the size; pf_vmf_fit_normals wrote the flat lobe to *out on every
   error, now nothing (the heights at their documented limit: tests/test_vmf_scale.c) */
static void edge_safety_contracts(void)
{
    pf_real nr[12] = { 0 };
    pf_vmf_mixture m;
    int rc;
    PF_CHECK(pf_vmf_pyramid_texel_count(1 << 24, 1 << 24) == 0, "texel count %lld", pf_vmf_pyramid_texel_count(1 << 24, 1 << 24));
    PF_CHECK(pf_vmf_pyramid_from_normals(nr, NULL, 1 << 24, 1 << 24, 1, 1, nr) == PF_ERR_SIZE, "2^24 pyramid accepted");
    m.count = 77;
    m.lobe[0].kappa = PF_R(-3.0);
    rc = pf_vmf_fit_normals(NULL, NULL, 4, 2, 3, &m);
    PF_CHECK(rc == PF_ERR_ARG && m.count == 77 && m.lobe[0].kappa == PF_R(-3.0), "NULL normals: rc %d, *out written", rc);
    rc = pf_vmf_fit_normals(nr, NULL, 4, 2, 3, &m); /* zero normals: none usable */
    PF_CHECK(rc == PF_ERR_ARG && m.count == 77 && m.lobe[0].kappa == PF_R(-3.0), "zero normals: rc %d, *out written", rc);
    rc = pf_vmf_fit_normals(nr, NULL, 4, 0, 3, &m);
    PF_CHECK(rc == PF_ERR_ARG && m.count == 77, "0 lobes: rc %d, *out written", rc);
}

/* ================================================================== end of SAFETY */

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_em_recovers_mixture);
    PF_TEST_RUN(test_em_deterministic_and_weighted);
    PF_TEST_RUN(test_pyramid_levels);
    PF_TEST_RUN(test_fit_degenerate);

    PF_TEST_RUN(test_safety_fit_scaled_inputs);
    PF_TEST_RUN(edge_safety_contracts);
    return PF_TEST_END();
}

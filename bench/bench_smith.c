/* bench_smith.c - cost and accuracy of pf_smith.h: Beckmann G1 and Lambda tiers, GGX.

   Families
     beckmann_g1      pf_g1_beckmann (exact), pf_g1_beckmann_walter (Walter et al. 2007
                      rational, the BASELINE), pf_g1_beckmann_fast, and naive_libm_erfc: the
                      G1 = 1 / (1 + Lambda) people usually write, with Lambda from exp and the
                      libm erfcf (float build) / erfc (double build).
     beckmann_lambda  pf_lambda_beckmann, pf_lambda_beckmann_walter (BASELINE),
                      pf_lambda_beckmann_fast, naive_libm_erfc (Lambda from exp and libm erfc).
     ggx              pf_g1_ggx_iso, pf_g1_ggx, pf_lambda_ggx_iso, pf_lambda_ggx; the vec3
                      variants get w = (sin, 0, cos) and alpha_x = alpha_y = alpha. The baseline
                      is a cost anchor with no accuracy columns: Beckmann G1 by Walter for the
                      same (cos, alpha) inputs, nu = cos / (alpha sin), so a GGX row's ratio
                      reads "cost relative to the Beckmann baseline for the same shading input".
                      beckmann_fast_g1_cos is the same anchor for pf_g1_beckmann_fast.

   REFERENCE (long double, pf_oracle_lambda_beckmann of tests/reference/pf_oracle.h, independent of
   pf_smith.h)
     Lambda(nu) = exp(-nu^2) / (2 nu sqrt(pi)) - erfc(nu) / 2,   G1 = 1 / (1 + Lambda).
     nu <= 2: the formula as written with expl and erfcl. The two terms cancel by at most a
              factor ~10 (at nu = 2), i.e. ~3.5 of the 64 bits.
     nu >  2: the Laplace continued fraction sqrt(pi) exp(nu^2) erfc(nu) = 1 / (nu + T),
              T = (1/2) / (nu + 1 / (nu + (3/2) / (nu + 2 / (nu + ...)))), i.e. partial
              numerators k/2, evaluated backwards from K = 40 + 240 / nu^2 terms. Then
              1/nu - 1/(nu + T) = T / (nu (nu + T)) has no cancellation, and
              Lambda = exp(-nu^2) / (2 sqrt(pi)) * T / (nu (nu + T)).
     Checked once against __float128 (libquadmath erfcq/expq) at nu = 1e-3 ... 10: relative
     difference <= 2e-18 on both branches, i.e. ~1e-11 of a float ulp and ~1e-2 of a double
     ulp, so the reference error is negligible in both builds.
     GGX: Lambda = t2 / (2 (1 + sqrt(1 + t2))), t2 = alpha^2 sin^2 / cos^2 (no cancellation),
     with sin^2 = 1 - cos^2 in long double for the _iso variants and sin as given to the vec3
     variants.

   See pf_bench.h for what every column means; bench/run.sh (make bench) runs this. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_smith.h"
#include "pf_oracle.h" /* the long double Lambda reference, shared with the tests */

/* ---------------------------------------------------------------- methods */
/* the G1 / Lambda most code bases carry: closed form with the libm erfc */
#define NAIVE_LAMBDA(nu) \
    (PF_EXP(-(nu) * (nu)) / (PF_R(2.0) * PF_SQRT_PI * (nu)) - PF_R(0.5) * PFB_LIBM_ERFC(nu))

PFB_METHOD(g1_exact, pf_g1_beckmann(x))
PFB_METHOD(g1_walter, pf_g1_beckmann_walter(x))
PFB_METHOD(g1_fast, pf_g1_beckmann_fast(x))
PFB_METHOD(g1_naive, PF_R(1.0) / (PF_R(1.0) + NAIVE_LAMBDA(x)))

PFB_METHOD(lambda_exact, pf_lambda_beckmann(x))
PFB_METHOD(lambda_walter, pf_lambda_beckmann_walter(x))
PFB_METHOD(lambda_fast, pf_lambda_beckmann_fast(x))
PFB_METHOD(lambda_naive, NAIVE_LAMBDA(x))

/* ggx inputs: x = cos_theta, y = alpha, z = sin_theta */
PFB_METHOD(ggx_g1_iso, pf_g1_ggx_iso(x, y))
PFB_METHOD(ggx_g1, pf_g1_ggx(pf_vec3_make(z, PF_R(0.0), x), y, y))
PFB_METHOD(ggx_lambda_iso, pf_lambda_ggx_iso(x, y))
PFB_METHOD(ggx_lambda, pf_lambda_ggx(pf_vec3_make(z, PF_R(0.0), x), y, y))
PFB_METHOD(ggx_anchor_walter, pf_g1_beckmann_walter(x / (y * z)))
PFB_METHOD(ggx_anchor_fast, pf_g1_beckmann_fast(x / (y * z)))

/* ---------------------------------------------------------------- references */
static long double ref_lambda_beckmann(long double nu) { return pf_oracle_lambda_beckmann(nu); }

static long double ref_lambda(long double x, long double y, long double z)
{
    (void)y; (void)z;
    return ref_lambda_beckmann(x);
}

static long double ref_g1(long double x, long double y, long double z)
{
    (void)y; (void)z;
    return 1.0L / (1.0L + ref_lambda_beckmann(x));
}

static long double ref_ggx_lambda_sc(long double s, long double c, long double alpha)
{
    long double t2 = alpha * alpha * s * s / (c * c);
    return t2 / (2.0L * (1.0L + sqrtl(1.0L + t2)));
}

static long double ref_ggx_lambda_iso(long double c, long double alpha, long double s)
{
    (void)s;
    return ref_ggx_lambda_sc(sqrtl(1.0L - c * c), c, alpha);
}

static long double ref_ggx_g1_iso(long double c, long double alpha, long double s)
{
    return 1.0L / (1.0L + ref_ggx_lambda_iso(c, alpha, s));
}

static long double ref_ggx_lambda_vec(long double c, long double alpha, long double s)
{
    return ref_ggx_lambda_sc(s, c, alpha);
}

static long double ref_ggx_g1_vec(long double c, long double alpha, long double s)
{
    return 1.0L / (1.0L + ref_ggx_lambda_sc(s, c, alpha));
}

/* ---------------------------------------------------------------- inputs */
/* Timing: nu uniform in (0, 4] (the targets are stated over nu > 0; G1 is 1 to float
   precision past nu ~ 4, where every tier is cheap and alike). */
static void gen_nu(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) a[i] = (pf_real)(4.0 * (1.0 - pfb_unif(r)));
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
}

/* Accuracy: 2^19 uniform points nu = 10 i / 2^19 (i = 1 .. 2^19) + 2^15 log-spaced points on
   [1e-8, 1]. */
#define NU_U (1u << 19)
#define NU_L (1u << 15)
static size_t grid_nu(pf_real *a, pf_real *b, pf_real *c)
{
    size_t i, n = NU_U + NU_L;
    if (!a) return n;
    for (i = 0; i < NU_U; ++i) a[i] = (pf_real)(10.0 * (double)(i + 1) / (double)NU_U);
    for (i = 0; i < NU_L; ++i) a[NU_U + i] = (pf_real)(1e-8 * pow(1e8, (double)i / (double)(NU_L - 1)));
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
    return n;
}

/* GGX timing: cos uniform in (0, 1], alpha uniform in [0.05, 1], sin = sqrt(1 - cos^2). */
static void gen_ggx(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        pf_real co = (pf_real)(1.0 - pfb_unif(r));
        a[i] = co;
        b[i] = (pf_real)pfb_unif_in(r, 0.05, 1.0);
        c[i] = PF_SQRT(pf_max(PF_R(1.0) - co * co, PF_R(0.0)));
    }
}

/* GGX accuracy: 1024 cos values (512 log-spaced on [1e-4, 1), 512 uniform on (0, 1]) times
   256 alpha values uniform on [0.01, 1]. */
#define GGX_C 1024u
#define GGX_A 256u
static size_t grid_ggx(pf_real *a, pf_real *b, pf_real *c)
{
    size_t i, j, n = (size_t)GGX_C * GGX_A;
    if (!a) return n;
    for (i = 0; i < GGX_C; ++i) {
        double co = i < GGX_C / 2 ? 1e-4 * pow(1e4, (double)i / (double)(GGX_C / 2))
                                  : (double)(i - GGX_C / 2 + 1) / (double)(GGX_C / 2);
        pf_real cr = (pf_real)co;
        pf_real sr = PF_SQRT(pf_max(PF_R(1.0) - cr * cr, PF_R(0.0)));
        for (j = 0; j < GGX_A; ++j) {
            size_t k = i * GGX_A + j;
            a[k] = cr;
            b[k] = (pf_real)(0.01 + 0.99 * (double)j / (double)(GGX_A - 1));
            c[k] = sr;
        }
    }
    return n;
}

/* ---------------------------------------------------------------- families */
#define NU_NOTES                                                                              \
    "timing inputs: nu uniform in (0, 4] (seeded)\n"                                     \
    "grid: 2^19 uniform nu in (0, 10] + 2^15 log-spaced nu in [1e-8, 1]\n"                    \
    "reference: long double closed form (expl, erfcl) for nu <= 2, cancellation-free "        \
    "continued fraction for nu > 2 (see bench_smith.c); relative error only where the "       \
    "reference is a normal pf_real"

static const pfb_family families[] = {
    { "beckmann_g1", 1, { "nu", NULL }, 1, NU_NOTES, gen_nu, grid_nu, 4,
      { PFB_ENTRY("pf_g1_beckmann", g1_exact, ref_g1, 0),
        PFB_ENTRY("pf_g1_beckmann_walter", g1_walter, ref_g1, 0),
        PFB_ENTRY("pf_g1_beckmann_fast", g1_fast, ref_g1, 0),
        PFB_ENTRY("naive_libm_erfc" PFB_LIBM_SUFFIX, g1_naive, ref_g1, 0) } },
    { "beckmann_lambda", 1, { "nu", NULL }, 1, NU_NOTES, gen_nu, grid_nu, 4,
      { PFB_ENTRY("pf_lambda_beckmann", lambda_exact, ref_lambda, 0),
        PFB_ENTRY("pf_lambda_beckmann_walter", lambda_walter, ref_lambda, 0),
        PFB_ENTRY("pf_lambda_beckmann_fast", lambda_fast, ref_lambda, 0),
        PFB_ENTRY("naive_libm_erfc" PFB_LIBM_SUFFIX, lambda_naive, ref_lambda, 0) } },
    { "ggx", 2, { "cos", "alpha" }, 4,
      "timing inputs: (cos, alpha), cos uniform in (0, 1], alpha uniform in [0.05, 1] (seeded); "
      "vec3 variants get w = (sqrt(1 - cos^2), 0, cos), alpha_x = alpha_y = alpha\n"
      "grid: 1024 cos (512 log-spaced on [1e-4, 1), 512 uniform on (0, 1]) x 256 alpha uniform on [0.01, 1]\n"
      "reference: long double t2 / (2 (1 + sqrt(1 + t2))), t2 = alpha^2 tan^2\n"
      "baseline beckmann_walter_g1_cos: pf_g1_beckmann_walter(cos / (alpha sin)), a cost anchor "
      "(Beckmann for the same input); its accuracy is in beckmann_g1",
      gen_ggx, grid_ggx, 6,
      { PFB_ENTRY("pf_g1_ggx_iso", ggx_g1_iso, ref_ggx_g1_iso, 0),
        PFB_ENTRY("pf_g1_ggx", ggx_g1, ref_ggx_g1_vec, 0),
        PFB_ENTRY("pf_lambda_ggx_iso", ggx_lambda_iso, ref_ggx_lambda_iso, 0),
        PFB_ENTRY("pf_lambda_ggx", ggx_lambda, ref_ggx_lambda_vec, 0),
        PFB_ENTRY("beckmann_walter_g1_cos", ggx_anchor_walter, NULL, 0),
        PFB_ENTRY("beckmann_fast_g1_cos", ggx_anchor_fast, NULL, 0) } },
};

int main(int argc, char **argv)
{
    return pfb_main(argc, argv, "smith", families, (int)(sizeof families / sizeof families[0]));
}

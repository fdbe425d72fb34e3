/* bench_core.c - cost and accuracy of pf_core.h: pf_erfc and pf_erf against libm.

   Families
     erfc   pf_erfc and its shader tier pf_erfc_fast vs libm erfcf (float build) / erfc
            (double build), the baseline; Abramowitz & Stegun 7.1.26 (the shader formula the
            fast tier replaces; bench/gpu/textbook.h) alongside.
     erf    pf_erf  vs libm erff / erf, the baseline.
   Reference: glibc erfcl / erfl in long double (64-bit significand). Errors in ulps of pf_real.
   See pf_bench.h for what every column means; bench/run.sh (make bench) runs this. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */

#include "gpu/textbook.h" /* Abramowitz & Stegun 7.1.26, the shader baseline (issue 17) */

PFB_METHOD(pf_erfc, pf_erfc(x))
PFB_METHOD(pf_erfc_fast, pf_erfc_fast(x))
PFB_METHOD(as_7_1_26, pf_textbook_erfc_as(x))
PFB_METHOD(libm_erfc, PFB_LIBM_ERFC(x))
PFB_METHOD(pf_erf, pf_erf(x))
PFB_METHOD(libm_erf, PFB_LIBM_ERF(x))

static long double ref_erfc(long double x, long double y, long double z)
{
    (void)y; (void)z;
    return erfcl(x);
}

static long double ref_erf(long double x, long double y, long double z)
{
    (void)y; (void)z;
    return erfl(x);
}

/* Timing inputs: 3/4 uniform in [lo, hi], 1/4 log-uniform |x| in [1e-6, 1] with a random
   sign, mixed at random (so branchy code pays its mispredictions as in real use). */
static void gen_mix(pfb_rng *r, pf_real *a, size_t n, double lo, double hi)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        double x;
        if (pfb_unif(r) < 0.75) {
            x = pfb_unif_in(r, lo, hi);
        } else {
            x = pfb_logunif(r, 1e-6, 1.0);
            if (pfb_unif(r) < 0.5) x = -x;
        }
        a[i] = (pf_real)x;
    }
}

static void gen_erfc(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    gen_mix(r, a, n, -3.0, 10.0);
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
}

static void gen_erf(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    gen_mix(r, a, n, -4.0, 4.0);
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
}

/* Accuracy grid: GRID_U uniformly spaced points over [lo, hi] plus 2 * GRID_L log-spaced
   points with |x| in [1e-12, 1] of both signs. Each point is rounded to pf_real. */
#define GRID_U (1u << 21)
#define GRID_L (1u << 14)

static size_t grid_fill(pf_real *a, pf_real *b, pf_real *c, double lo, double hi)
{
    size_t i, n = GRID_U + 2 * GRID_L;
    if (!a) return n;
    for (i = 0; i < GRID_U; ++i) a[i] = (pf_real)(lo + (hi - lo) * (double)i / (double)(GRID_U - 1));
    for (i = 0; i < GRID_L; ++i) {
        double x = 1e-12 * pow(1e12, (double)i / (double)(GRID_L - 1));
        a[GRID_U + 2 * i] = (pf_real)x;
        a[GRID_U + 2 * i + 1] = (pf_real)-x;
    }
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
    return n;
}

#ifdef PF_DOUBLE
#  define ERFC_LO (-6.0)
#  define ERFC_HI 27.0
#  define ERFC_GRID_NOTE "grid (double): 2^21 uniform points on [-6, 27] + 2^15 log-spaced |x| in [1e-12, 1], both signs"
#else
#  define ERFC_LO (-10.0)
#  define ERFC_HI 10.1
#  define ERFC_GRID_NOTE "grid (float): 2^21 uniform points on [-10, 10.1] + 2^15 log-spaced |x| in [1e-12, 1], both signs"
#endif

static size_t grid_erfc(pf_real *a, pf_real *b, pf_real *c) { return grid_fill(a, b, c, ERFC_LO, ERFC_HI); }
static size_t grid_erf(pf_real *a, pf_real *b, pf_real *c) { return grid_fill(a, b, c, -6.0, 6.0); }

static const pfb_family families[] = {
    { "erfc", 1, { "x", NULL }, 3,
      "timing inputs: x, 3/4 uniform on [-3, 10], 1/4 log-uniform |x| in [1e-6, 1] with random sign (seeded)\n"
      ERFC_GRID_NOTE "\n"
      "reference: glibc erfcl (long double); ulps of pf_real; relative error only where erfc(x) is a normal pf_real",
      gen_erfc, grid_erfc, 4,
      { PFB_ENTRY("pf_erfc", pf_erfc, ref_erfc, 1),
        PFB_ENTRY("pf_erfc_fast", pf_erfc_fast, ref_erfc, 1),
        PFB_ENTRY("as_7_1_26", as_7_1_26, ref_erfc, 1),
        PFB_ENTRY("libm_erfc" PFB_LIBM_SUFFIX, libm_erfc, ref_erfc, 1) } },
    { "erf", 1, { "x", NULL }, 1,
      "timing inputs: x, 3/4 uniform on [-4, 4], 1/4 log-uniform |x| in [1e-6, 1] with random sign (seeded)\n"
      "grid: 2^21 uniform points on [-6, 6] + 2^15 log-spaced |x| in [1e-12, 1], both signs\n"
      "reference: glibc erfl (long double); ulps of pf_real",
      gen_erf, grid_erf, 2,
      { PFB_ENTRY("pf_erf", pf_erf, ref_erf, 1),
        PFB_ENTRY("libm_erf" PFB_LIBM_SUFFIX, libm_erf, ref_erf, 1) } },
};

int main(int argc, char **argv)
{
    return pfb_main(argc, argv, "core", families, (int)(sizeof families / sizeof families[0]));
}

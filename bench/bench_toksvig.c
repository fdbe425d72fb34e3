/* bench_toksvig.c - cost and accuracy of pf_toksvig.h against the convolution it approximates.

   Family
     toksvig_lobe   inputs alpha (Blinn-Phong exponent), sigma (deviation of the normal angle,
                    per axis), beta (angle between h and the mean normal). Output: the filtered
                    lobe for the unfiltered lobe (n.h)^alpha of peak 1.
                    pf_toksvig_lobe              (1 + a')/(1 + a) cos^a' beta, a' = a/(1 + a s^2)
                    beckmann_widened             a -> m = sqrt(2/(a + 2)) (Walter et al. 2007),
                                                 m'^2 = m^2 + 2 s^2 (pf_toksvig_beckmann_m),
                                                 back to a' = 2/m'^2 - 2, same normalization
                    unfiltered_pow (BASELINE)    cos^a beta: what shading does without Toksvig
                    The reference is the lobe convolved with the Gaussian of the normal angle,
                    integrated over the sphere in long double (bench/fit/toksvig_convolution.h).
                    Accuracy grid: alpha = 10^(k/2), k = 0..8; sigma in {0, 0.02, 0.05, 0.1,
                    0.2, 0.3, 0.5}; beta = (j/4) * 1.5/sqrt(a'), j = 0..4, at most 1.4 (the core,
                    where the exact lobe is >= ~30% of its peak, so relative errors are
                    meaningful; tests/test_toksvig.c measures the error over the whole lobe
                    relative to the peak).

   See pf_bench.h for what every column means; bench/run.sh (make bench) runs this. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_toksvig.h"
#include "fit/toksvig_convolution.h"

/* x = alpha, y = sigma, z = beta */
PFB_METHOD(toksvig, pf_toksvig_lobe(PF_COS(z), x, y * y))
PFB_METHOD(unfiltered, PF_POW(PF_COS(z), x))
PFB_METHOD(beckmann_widened,
           pf_toksvig_normalization(x, pf_beckmann_to_blinn_phong(pf_toksvig_beckmann_m(pf_blinn_phong_to_beckmann(x), y * y)))
           * PF_POW(PF_COS(z), pf_beckmann_to_blinn_phong(pf_toksvig_beckmann_m(pf_blinn_phong_to_beckmann(x), y * y))))

static long double ref_lobe(long double x, long double y, long double z)
{
    return tkc_filtered(TKC_BLINN_PHONG, x, y, z, NULL);
}

static void gen_lobe(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_logunif(r, 1.0, 1e4);
        b[i] = (pf_real)pfb_unif_in(r, 0.0, 0.5);
        c[i] = (pf_real)pfb_unif_in(r, 0.0, 1.0);
    }
}

static size_t grid_lobe(pf_real *a, pf_real *b, pf_real *c)
{
    static const double sig[] = {0.0, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5};
    size_t n = 0;
    int k, s, j;
    for (k = 0; k <= 8; ++k)
        for (s = 0; s < 7; ++s)
            for (j = 0; j <= 4; ++j) {
                if (a) {
                    double al = pow(10.0, k / 2.0), ap = al / (1.0 + al * sig[s] * sig[s]);
                    a[n] = (pf_real)al;
                    b[n] = (pf_real)sig[s];
                    double beta = j / 4.0 * 1.5 / sqrt(ap);
                    c[n] = (pf_real)(beta < 1.4 ? beta : 1.4); /* wide lobes: stay above the horizon */
                }
                ++n;
            }
    return n;
}

static const pfb_family families[] = {
    { "toksvig_lobe", 2, { "alpha", "sigma" }, 1,
      "inputs alpha log-uniform in [1, 1e4], sigma uniform in [0, 0.5], beta uniform in [0, 1]\n"
      "accuracy grid: alpha = 10^(k/2), k = 0..8; sigma in {0, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5}; beta = (j/4) 1.5/sqrt(alpha'), j = 0..4, at most 1.4 (the lobe's core)\n"
      "reference: Blinn-Phong lobe convolved with a Gaussian of the normal angle (per-axis deviation sigma), 2D quadrature over the sphere in long double",
      gen_lobe, grid_lobe, 3,
      { PFB_ENTRY("pf_toksvig_lobe", toksvig, ref_lobe, 0),
        PFB_ENTRY("unfiltered_pow", unfiltered, ref_lobe, 0),
        PFB_ENTRY("beckmann_widened", beckmann_widened, ref_lobe, 0) } },
};

int main(int argc, char **argv)
{
    return pfb_main(argc, argv, "toksvig", families, (int)(sizeof families / sizeof families[0]));
}

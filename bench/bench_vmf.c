/* bench_vmf.c - cost and accuracy of pf_vmf.h against long double references.

   Families
     vmf_normalization  input kappa. C(kappa) = kappa / (2 pi (1 - exp(-2 kappa))):
                        pf_vmf_normalization (Kahan's expm1 form below kappa = 0.25) against
                        naive_direct (BASELINE: 1 - exp(-2 kappa) as written, which cancels
                        for small kappa). Reference: the same in long double with expm1l.
     vmf_convolution    inputs kappa (log-uniform 1-1e4), psi (angle from the axis, in units
                        of 1/sqrt(kappa')). The value of a vMF lobe of kappa convolved with a
                        vMF base lobe of kappa_b = 100: one_lobe_rule = pf_vmf_lobe_eval with
                        pf_vmf_convolve_kappa (1/kappa' = 1/kappa + 1/kappa_b) against
                        unconvolved (BASELINE: the lobe without its base). Reference: the
                        exact spherical convolution of two vMF lobes in closed form,
                        C1 C2 e^(-k1-k2) 4 pi sinh|k1 mu + k2 w| / |k1 mu + k2 w|.
     vmf_specular       inputs theta_o, theta_i, phi (relative azimuth). A fixed 4-lobe
                        mixture (the corpus's typical tilts and kappas) shaded by
                        vmf_m4 = pf_vmf_sum_add x 4 + pf_vmf_sum_specular (one-Gaussian Smith),
                        vmf_m4_mix_smith (pf_vmf_sum_add_masking too, exact mixture Smith),
                        vmf_m1 (one lobe), vmf_m4_texel and vmf_m4_texel_mix_smith (the shader
                        path: pf_vmf_pixel_make, pf_vmf_sum_add_texel(_mixture) x 4, the same
                        specular), against pf_leadr_specular (BASELINE, the footprint's
                        one Gaussian, no lobes). Reference for vmf_m4: its formula (slope form,
                        one-Gaussian Smith) re-evaluated in long double with the oracle's
                        Lambda (tests/reference/pf_oracle.h): the row's error is the rounding of the
                        float/double evaluation; the others are timed against it and their
                        error says how far the other models are from vmf_m4.

   See pf_bench.h for what every column means; bench/run.sh (make bench) runs this. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_vmf_fit.h"
#include "pf_vmf_scale.h"
#include "pf_map_downsample.h"
#include "pf_oracle.h"

/* ------------------------------------------------------------------ normalization */
PFB_METHOD(norm, pf_vmf_normalization(x))
PFB_METHOD(norm_naive, x * (PF_R(0.5) * PF_INV_PI) / (PF_R(1.0) - PF_EXP(PF_R(-2.0) * x)))

static long double ref_norm(long double x, long double y, long double z)
{
    (void)y;
    (void)z;
    return x / (2.0L * 3.14159265358979323846264338327950288L * -expm1l(-2.0L * x));
}
static void gen_norm(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_logunif(r, 1e-4, 1e5);
        b[i] = c[i] = PF_R(0.0);
    }
}
static size_t grid_norm(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int k;
    for (k = 0; k <= 180; ++k) {
        if (a) {
            a[n] = (pf_real)pow(10.0, -4.0 + k / 20.0);
            b[n] = c[n] = PF_R(0.0);
        }
        ++n;
    }
    return n;
}

/* ------------------------------------------------------------------ convolution */
#define KB 100.0
static pf_vec3 dir_psi(pf_real psi) { return pf_vec3_make(PF_SIN(psi), PF_R(0.0), PF_COS(psi)); }
static pf_real psi_of(pf_real kappa, pf_real t) { return t / PF_SQRT(pf_vmf_convolve_kappa(kappa, PF_R(KB))); }
PFB_METHOD(conv_rule, pf_vmf_lobe_eval(pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)),
                                       pf_vmf_convolve_kappa(x, PF_R(KB)), dir_psi(psi_of(x, y))))
PFB_METHOD(conv_none, pf_vmf_lobe_eval(pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)), x, dir_psi(psi_of(x, y))))

static long double ref_conv(long double x, long double y, long double z)
{
    long double k1 = x, k2 = KB, psi = (long double)psi_of((pf_real)x, (pf_real)y);
    long double c1 = k1 / (2.0L * 3.14159265358979323846264338327950288L * -expm1l(-2.0L * k1));
    long double c2 = k2 / (2.0L * 3.14159265358979323846264338327950288L * -expm1l(-2.0L * k2));
    long double r = sqrtl(k1 * k1 + k2 * k2 + 2.0L * k1 * k2 * cosl(psi));
    (void)z;
    return c1 * c2 * 2.0L * 3.14159265358979323846264338327950288L * (-expm1l(-2.0L * r)) / r * expl(r - k1 - k2);
}
static void gen_conv(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_logunif(r, 1.0, 1e4);
        b[i] = (pf_real)pfb_unif_in(r, 0.0, 2.0);
        c[i] = PF_R(0.0);
    }
}
static size_t grid_conv(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int k, j;
    for (k = 0; k <= 16; ++k)
        for (j = 0; j <= 8; ++j) {
            if (a) {
                a[n] = (pf_real)pow(10.0, k / 4.0);
                b[n] = (pf_real)(j * 0.2); /* the core: at least ~45% of the peak */
                c[n] = PF_R(0.0);
            }
            ++n;
        }
    return n;
}

/* ------------------------------------------------------------------ specular */
#define BVAR 0.01
static const double lobe_x[4] = { 0.05, -0.35, 0.3, 0.1 }, lobe_y[4] = { -0.02, 0.1, 0.25, -0.4 };
static const double lobe_k[4] = { 80.0, 40.0, 150.0, 25.0 }, lobe_a[4] = { 0.4, 0.25, 0.2, 0.15 };

static pf_vec3 dir_of(pf_real theta, pf_real phi)
{
    return pf_vec3_make(PF_SIN(theta) * PF_COS(phi), PF_SIN(theta) * PF_SIN(phi), PF_COS(theta));
}
static pf_real spec_m(int m, int mix, pf_real to, pf_real ti, pf_real ph)
{
    pf_vec3 wo = dir_of(to, PF_R(0.0)), wi = dir_of(ti, ph);
    pf_vmf_sum s = pf_vmf_sum_zero();
    int k;
    for (k = 0; k < m; ++k) {
        pf_vmf_lobe l = pf_vmf_lobe_make(m == 1 ? PF_R(1.0) : (pf_real)lobe_a[k], (pf_real)lobe_x[k], (pf_real)lobe_y[k],
                                         (pf_real)lobe_k[k]);
        s = pf_vmf_sum_add(s, l, wo, wi, PF_R(BVAR));
        if (mix) s = pf_vmf_sum_add_masking(s, l, wo, wi, PF_R(BVAR));
    }
    return mix ? pf_vmf_sum_specular_mixture(s, wo, wi, PF_R(1.0)) : pf_vmf_sum_specular(s, wo, wi, PF_R(1.0));
}
/* the footprint's one Gaussian: mixture moments of the 4 lobes (long double, computed once) */
static pf_slope_stats leadr_stats;
static pf_real spec_leadr(pf_real to, pf_real ti, pf_real ph)
{
    return pf_leadr_specular(dir_of(to, PF_R(0.0)), dir_of(ti, ph), leadr_stats, PF_R(1.0));
}
/* the shader path: pf_vmf_pixel_make once, pf_vmf_sum_add_texel (_mixture) per lobe */
static pf_real spec_texel(int m, int mix, pf_real to, pf_real ti, pf_real ph)
{
    pf_vec3 wo = dir_of(to, PF_R(0.0)), wi = dir_of(ti, ph);
    pf_vmf_pixel px = pf_vmf_pixel_make(wo, wi, PF_R(BVAR));
    pf_vmf_sum s = pf_vmf_sum_zero();
    int k;
    for (k = 0; k < m; ++k) {
        pf_real a = m == 1 ? PF_R(1.0) : (pf_real)lobe_a[k];
        s = mix ? pf_vmf_sum_add_texel_mixture(s, px, wo, wi, a, (pf_real)lobe_x[k], (pf_real)lobe_y[k], (pf_real)lobe_k[k])
                : pf_vmf_sum_add_texel(s, px, a, (pf_real)lobe_x[k], (pf_real)lobe_y[k], (pf_real)lobe_k[k]);
    }
    return mix ? pf_vmf_sum_specular_mixture(s, wo, wi, PF_R(1.0)) : pf_vmf_sum_specular(s, wo, wi, PF_R(1.0));
}
PFB_METHOD(spec_m4_texel, spec_texel(4, 0, x, y, z))
PFB_METHOD(spec_m4_texel_mix, spec_texel(4, 1, x, y, z))
PFB_METHOD(spec_m4, spec_m(4, 0, x, y, z))
PFB_METHOD(spec_m4_mix, spec_m(4, 1, x, y, z))
PFB_METHOD(spec_m1, spec_m(1, 0, x, y, z))
PFB_METHOD(spec_leadr, spec_leadr(x, y, z))

/* long double slope statistics of a lobe (the header's definitions) */
static void ref_lobe_stats(int k, long double st[5])
{
    long double x = (long double)(pf_real)lobe_x[k], y = (long double)(pf_real)lobe_y[k], kap = (long double)(pf_real)lobe_k[k];
    long double z = sqrtl(1.0L - x * x - y * y), a3 = 1.0L / tanhl(kap) - 1.0L / kap, v = a3 / kap;
    long double r2 = x * x + y * y, c2 = x * x / r2, s2 = y * y / r2, cs = x * y / r2;
    long double va = v / (z * z * z * z), vc = v / (z * z), b = (long double)PF_R(BVAR);
    st[0] = -x / z;
    st[1] = -y / z;
    st[2] = c2 * va + s2 * vc + b;
    st[3] = s2 * va + c2 * vc + b;
    st[4] = cs * (va - vc);
}
static long double ref_lambda(const long double w[3], const long double m[5])
{
    long double num = w[2] - w[0] * m[0] - w[1] * m[1];
    long double var = w[0] * w[0] * m[2] + w[1] * w[1] * m[3] + 2.0L * w[0] * w[1] * m[4];
    if (!(num > 0)) return 1e30L;
    if (!(var > 0)) return 0.0L;
    return pf_oracle_lambda_beckmann(num / sqrtl(2.0L * var));
}
static long double ref_spec(long double to, long double ti, long double ph)
{
    long double wo[3], wi[3], h[3], hl, d = 0, mom[5] = { 0, 0, 0, 0, 0 }, m[5], ao, ai, g;
    int k;
    wo[0] = sinl(to);
    wo[1] = 0.0L;
    wo[2] = cosl(to);
    wi[0] = sinl(ti) * cosl(ph);
    wi[1] = sinl(ti) * sinl(ph);
    wi[2] = cosl(ti);
    for (k = 0; k < 3; ++k) h[k] = wo[k] + wi[k];
    hl = sqrtl(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (k = 0; k < 3; ++k) h[k] /= hl;
    for (k = 0; k < 4; ++k) {
        long double st[5], a = (long double)(pf_real)lobe_a[k], sx, sy;
        ref_lobe_stats(k, st);
        sx = -h[0] / h[2];
        sy = -h[1] / h[2];
        d += a * pf_oracle_normal2_pdf(sx - st[0], sy - st[1], st[2], st[3], st[4]) / powl(h[2], 4.0L);
        mom[0] += a * st[0];
        mom[1] += a * st[1];
        mom[2] += a * (st[2] + st[0] * st[0]);
        mom[3] += a * (st[3] + st[1] * st[1]);
        mom[4] += a * (st[4] + st[0] * st[1]);
    }
    m[0] = mom[0];
    m[1] = mom[1];
    m[2] = mom[2] - m[0] * m[0];
    m[3] = mom[3] - m[1] * m[1];
    m[4] = mom[4] - m[0] * m[1];
    ao = wo[2] - wo[0] * m[0] - wo[1] * m[1];
    ai = wi[2] - wi[0] * m[0] - wi[1] * m[1];
    if (!(ao > 0) || !(ai > 0)) return 0.0L;
    g = 1.0L / (1.0L + ref_lambda(wo, m) + ref_lambda(wi, m));
    return d * g / (4.0L * ao);
}
static void gen_spec(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_unif_in(r, 0.0, 1.3);
        b[i] = (pf_real)pfb_unif_in(r, 0.0, 1.3);
        c[i] = (pf_real)pfb_unif_in(r, 0.0, 6.283);
    }
}
static size_t grid_spec(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int i, j, k;
    for (i = 0; i < 8; ++i)
        for (j = 0; j < 8; ++j)
            for (k = 0; k < 8; ++k) {
                if (a) {
                    a[n] = (pf_real)(0.17 * i);
                    b[n] = (pf_real)(0.17 * j);
                    c[n] = (pf_real)(0.785 * k);
                }
                ++n;
            }
    return n;
}

static const pfb_family families[] = {
    { "vmf_normalization", 1, { "kappa", "" }, 1,
      "input kappa log-uniform in [1e-4, 1e5]\n"
      "accuracy grid: kappa = 10^(-4 + k/20), k = 0..180\n"
      "reference: kappa / (2 pi (1 - exp(-2 kappa))) in long double (expm1l)",
      gen_norm, grid_norm, 2,
      { PFB_ENTRY("pf_vmf_normalization", norm, ref_norm, 1), PFB_ENTRY("naive_direct", norm_naive, ref_norm, 1) } },
    { "vmf_convolution", 2, { "kappa", "psi_sqrt_kappa" }, 1,
      "inputs kappa log-uniform in [1, 1e4], psi = t / sqrt(kappa'), t uniform in [0, 2]; base lobe kappa_b = 100\n"
      "accuracy grid: kappa = 10^(k/4), k = 0..16; t = 0, 0.2, ..., 1.6 (the core)\n"
      "reference: the exact spherical convolution of two vMF lobes (closed form, long double)",
      gen_conv, grid_conv, 2,
      { PFB_ENTRY("one_lobe_rule", conv_rule, ref_conv, 0), PFB_ENTRY("unconvolved", conv_none, ref_conv, 0) } },
    { "vmf_specular", 2, { "theta_o", "theta_i" }, 3,
      "inputs theta_o, theta_i uniform in [0, 1.3], relative azimuth uniform in [0, 2 pi); a fixed 4-lobe mixture, base slope variance 0.01, f0 = 1\n"
      "accuracy grid: theta_o, theta_i = 0.17 i, i = 0..7; azimuth 0.785 k, k = 0..7\n"
      "reference: vmf_m4's formula (slope form, one-Gaussian Smith) in long double with the oracle's Lambda; the other rows measure their distance from it",
      gen_spec, grid_spec, 6,
      { PFB_ENTRY("vmf_m4", spec_m4, ref_spec, 0), PFB_ENTRY("vmf_m4_mix_smith", spec_m4_mix, ref_spec, 0),
        PFB_ENTRY("vmf_m1", spec_m1, ref_spec, 0), PFB_ENTRY("pf_leadr_specular", spec_leadr, ref_spec, 0),
        PFB_ENTRY("vmf_m4_texel", spec_m4_texel, ref_spec, 0), PFB_ENTRY("vmf_m4_texel_mix_smith", spec_m4_texel_mix, ref_spec, 0) } },
};

/* ------------------------------------------------------------------ scaling function (helper J)
   `bench_vmf-float --scaling [size] [lobes] [masking] [nt] [np] [kind]` (defaults 256 4 1 6 5,
   every kind): on
   tests/reference/pf_microsurface.h maps of `size`^2 texels cut into 64 x 64 patches (4096-texel
   footprints), builds the scaling function of Wu et al. 2019 (pfi_vmf_scale_patch on every
   patch, pfi_vmf_scale_factor: T per patch, S over nt x nt x np cells, theta_max 75 deg,
   masking PF_VMF_SCALE_*: 1 G_GAUSSIAN, 2 G_MIXTURE, 3 UNMASKED) and prints per kind: the factorization's error on its own samples
   (T S f_lobes against f_eff, and T S against R), then on 400 held-out direction pairs per
   patch (uniform in theta_o, theta_i <= 75 deg and both azimuths, seeded) the specular error
   against the brute-force effective BRDF (the in-footprint reference: pf_vmf_effective_brdf,
   tested equal to pfm_reference_shade with pfm_visibility_map_box) of f_lobes alone, S f_lobes
   (T = 1) and T S f_lobes (S read by pf_vmf_scale_lookup), relative L2 pooled. Base lobe:
   slope deviation 0.1, f0 = 0.04 (the bench's microsurface base BRDF). */
#include "pf_microsurface.h"
#include <stdio.h>
#include <time.h>

static int scaling_main(int argc, char **argv)
{
    static const int kinds[] = { PFM_GAUSSIAN_FINE, PFM_GAUSSIAN, PFM_GAUSSIAN_ANISO, PFM_RIDGES, PFM_CRATERS, PFM_TILES };
    const int size = argc > 2 ? atoi(argv[2]) : 256, lobes = argc > 3 ? atoi(argv[3]) : 4;
    const int masking = argc > 4 ? atoi(argv[4]) : PF_VMF_SCALE_G_GAUSSIAN, nt = argc > 5 ? atoi(argv[5]) : 6;
    const int np = argc > 6 ? atoi(argv[6]) : 5, n = 64, held = 400;
    const pf_real tm = PF_R(75.0) * PF_PI / PF_R(180.0), sigma = PF_R(0.1), f0 = PF_R(0.04);
    int per = size / n, patches = per * per, ki;
    long long cnt = pf_vmf_scale_sample_count(nt, np), cells = pf_vmf_scale_cell_count(nt, np);
    long long vb = pf_vmf_scale_vis_bytes(nt, np, n);
    pf_real *hm = (pf_real *)malloc((size_t)size * size * sizeof(pf_real));
    pf_real *nr = (pf_real *)malloc((size_t)3 * n * n * sizeof(pf_real));
    pf_real *fe = (pf_real *)malloc((size_t)(cnt * patches) * sizeof(pf_real));
    pf_real *fl = (pf_real *)malloc((size_t)(cnt * patches) * sizeof(pf_real));
    pf_real *T = (pf_real *)malloc((size_t)patches * sizeof(pf_real)), *S = (pf_real *)malloc((size_t)cells * sizeof(pf_real));
    pf_real *scr = (pf_real *)malloc((size_t)(2 * cells * patches) * sizeof(pf_real));
    unsigned char *vis = (unsigned char *)malloc((size_t)vb);
    pf_vmf_scale_desc ed; /* the effective BRDF's description: the map, the base BRDF */
    memset(&ed, 0, sizeof ed);
    ed.heights = hm, ed.w = size, ed.h = size, ed.texel = PF_R(1.0), ed.base_sigma = sigma, ed.f0 = f0;
    if (per < 1 || cnt == 0 || !hm || !nr || !fe || !fl || !T || !S || !scr || !vis) {
        fprintf(stderr, "bench_vmf --scaling: bad arguments or no memory\n");
        return 1;
    }
    printf("scaling function (Wu et al. 2019 eqs. 6-8, 12-14, 21-24): %s, %d^2 maps, %d patches of %d^2 texels, m = %d, "
           "masking %d, S %d x %d x %d cells (%lld bytes float32), T %d values (%d bytes float32), %lld samples per patch\n",
           sizeof(pf_real) == 4 ? "float" : "double", size, patches, n, lobes, masking, nt, nt, np, cells * 4, patches,
           patches * 4, cnt);
    printf("| kind | fact. err (BRDF) | fact. err (R) | unscaled (own samples) | held-out: f_lobes | S f_lobes | T S f_lobes | build s |\n");
    printf("|---|--:|--:|--:|--:|--:|--:|--:|\n");
    for (ki = 0; ki < (int)(sizeof kinds / sizeof kinds[0]); ++ki) {
        pfm_surface s;
        pf_real err[3];
        long double e_l = 0, e_s = 0, e_ts = 0, ref = 0;
        unsigned long long rs = 0x9E3779B97F4A7C15ULL * (unsigned long long)(ki + 1);
        clock_t c0 = clock();
        int p, i, rc = PF_OK;
        if (argc > 7 && strcmp(argv[7], pfm_kind_name(kinds[ki])) != 0) continue;
        if (pfm_surface_make(&s, size, size, 1.0, pfm_params_default(kinds[ki])) != 0) return 1;
        for (i = 0; i < size * size; ++i) hm[i] = (pf_real)s.height[i];
        for (p = 0; p < patches && rc == PF_OK; ++p)
            /* the per-patch samples and the factorization the library's level calls build on
               (pf_vmf_scale.h, private: this experiment fits each patch's own lobes) */
            rc = pfi_vmf_scale_patch(hm, size, size, PF_R(1.0), (p % per) * n, (p / per) * n, n, lobes, 24, sigma, f0, masking,
                                     nt, np, tm, nr, vis, fe + p * cnt, fl + p * cnt);
        if (rc == PF_OK) rc = pfi_vmf_scale_factor(fe, fl, patches, nt, np, 30, PF_R(0.0), T, S, scr, NULL, err);
        if (rc != PF_OK) {
            fprintf(stderr, "%s: error %d\n", pfm_kind_name(kinds[ki]), rc);
            return 1;
        }
        for (p = 0; p < patches; ++p) {
            pf_vmf_mixture mix;
            int j, k, x0 = (p % per) * n, y0 = (p / per) * n, q;
            for (j = 0; j < n; ++j)
                for (i = 0; i < n; ++i) {
                    double m3[3];
                    pfm_normal(&s, x0 + i, y0 + j, m3);
                    for (q = 0; q < 3; ++q) nr[3 * (j * n + i) + q] = (pf_real)m3[q];
                }
            pf_vmf_fit_normals(nr, 0, (long long)n * n, lobes, 24, &mix);
            for (j = 0; j < held; ++j) {
                pf_real u[4], fe1 = 0, fl1, sv;
                pf_vec3 wo, wi;
                pf_vmf_sum sum = pf_vmf_sum_zero();
                for (q = 0; q < 4; ++q) {
                    rs += 0x9E3779B97F4A7C15ULL;
                    u[q] = (pf_real)((double)((rs ^ (rs >> 29)) * 0xBF58476D1CE4E5B9ULL >> 11) * (1.0 / 9007199254740992.0));
                }
                wo = pf_vec3_make(PF_SIN(u[0] * tm) * PF_COS(u[1] * PF_R(2.0) * PF_PI),
                                  PF_SIN(u[0] * tm) * PF_SIN(u[1] * PF_R(2.0) * PF_PI), PF_COS(u[0] * tm));
                wi = pf_vec3_make(PF_SIN(u[2] * tm) * PF_COS(u[3] * PF_R(2.0) * PF_PI),
                                  PF_SIN(u[2] * tm) * PF_SIN(u[3] * PF_R(2.0) * PF_PI), PF_COS(u[2] * tm));
                pf_vmf_effective_brdf(&ed, x0, y0, n, wo, wi, &fe1);
                for (k = 0; k < mix.count; ++k) {
                    sum = pf_vmf_sum_add(sum, mix.lobe[k], wo, wi, sigma * sigma);
                    if (masking == PF_VMF_SCALE_G_MIXTURE) sum = pf_vmf_sum_add_masking(sum, mix.lobe[k], wo, wi, sigma * sigma);
                }
                fl1 = masking == PF_VMF_SCALE_UNMASKED    ? pf_vmf_sum_specular_unmasked(sum, wo, wi, f0)
                      : masking == PF_VMF_SCALE_G_GAUSSIAN ? pf_vmf_sum_specular(sum, wo, wi, f0)
                                                           : pf_vmf_sum_specular_mixture(sum, wo, wi, f0);
                sv = pf_vmf_scale_lookup(S, nt, np, tm, wo, wi);
                ref += (long double)fe1 * (long double)fe1;
                e_l += ((long double)fl1 - (long double)fe1) * ((long double)fl1 - (long double)fe1);
                e_s += ((long double)(sv * fl1) - (long double)fe1) * ((long double)(sv * fl1) - (long double)fe1);
                e_ts += ((long double)pf_vmf_scale_apply(T[p], sv, fl1) - (long double)fe1) *
                        ((long double)pf_vmf_scale_apply(T[p], sv, fl1) - (long double)fe1);
            }
        }
        printf("| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.1f |\n", pfm_kind_name(kinds[ki]), (double)err[0],
               (double)err[2], (double)err[1], (double)sqrtl(e_l / ref), (double)sqrtl(e_s / ref), (double)sqrtl(e_ts / ref),
               (double)(clock() - c0) / CLOCKS_PER_SEC);
        fflush(stdout);
        pfm_surface_free(&s);
    }
    free(hm);
    free(nr);
    free(fe);
    free(fl);
    free(T);
    free(S);
    free(scr);
    free(vis);
    return 0;
}
/* ------------------------------------------------------------------ end of scaling function */

/* ------------------------------------------------------------------ downsampling (helper I)
   `bench_vmf-float --downsample` (not part of the method tables): the slope-preserving
   downsampling of pf_map_downsample_slopes (Wu et al. 2019 eqs. 9-10) on the corpus's
   512 x 512 height maps (tests/reference/pf_microsurface.h, wrapped), factors 2 (to 256 x 256) and 8:
   wall time of one solve (best of 3), CG iterations, and the RMS error of the coarse map's
   slopes against the fine footprints' mean slopes (long double, computed here from the
   definitions) for the solve and for the plain box average of the heights. */
/* the library's wrapped height-slope stencil, in long double */
static long double ds_cd(const long double *v, long long stride, int i, int n)
{
    return 0.5L * (v[(long long)((i + 1) % n) * stride] - v[(long long)((i + n - 1) % n) * stride]);
}
/* RMS over coarse texels of |slope - footprint mean slope|, per fine texel (world slope at texel 1) */
static long double ds_err(const pf_real *coarse, const long double *sx, const long double *sy, int W, int f)
{
    long double *v = (long double *)malloc((size_t)W * W * sizeof(long double)), e = 0.0L;
    int i, j;
    if (!v) return -1.0L;
    for (i = 0; i < W * W; ++i) v[i] = (long double)coarse[i];
    for (j = 0; j < W; ++j)
        for (i = 0; i < W; ++i) {
            long double dx = ds_cd(v + (long long)j * W, 1, i, W) / f - sx[j * W + i];
            long double dy = ds_cd(v + i, W, j, W) / f - sy[j * W + i];
            e += dx * dx + dy * dy;
        }
    free(v);
    return sqrtl(e / ((long double)W * W));
}
static int downsample_main(void)
{
    static const int kinds[] = { PFM_GAUSSIAN, PFM_GAUSSIAN_FINE, PFM_RIDGES, PFM_CRATERS, PFM_TILES };
    static const int factors[] = { 2, 8 };
    const int N = 512;
    const pf_real tol = sizeof(pf_real) == 4 ? PF_R(1e-5) : PF_R(1e-8);
    int ki, fi;
    printf("\n== vmf_downsample (%s): pf_map_downsample_slopes, 512 x 512 corpus maps, wrap, reg_weight 0.01, tol %g, max_iter 2000\n",
           PFB_BUILD, (double)tol);
    printf("  %-14s %6s %8s %6s %12s %12s %12s %9s\n", "kind", "factor", "ms", "iters", "rms_slope", "err_box", "err_solve",
           "solve/box");
    for (ki = 0; ki < (int)(sizeof kinds / sizeof kinds[0]); ++ki) {
        pfm_surface surf;
        pf_real *fine = (pf_real *)malloc((size_t)N * N * sizeof(pf_real));
        long double *v = (long double *)malloc((size_t)N * N * sizeof(long double));
        int i, j;
        if (!fine || !v || pfm_surface_make(&surf, N, N, 1.0, pfm_params_default(kinds[ki])) != 0) {
            fprintf(stderr, "downsample: setup failed\n");
            return 1;
        }
        for (i = 0; i < N * N; ++i) {
            fine[i] = (pf_real)surf.height[i];
            v[i] = (long double)fine[i];
        }
        for (fi = 0; fi < 2; ++fi) {
            int f = factors[fi], W = N / f, n = W * W, it = 0, rep;
            long long need = pf_map_downsample_scratch_size(N, N, f);
            pf_real *coarse = (pf_real *)malloc((size_t)n * sizeof(pf_real)), *box = (pf_real *)calloc((size_t)n, sizeof(pf_real));
            pf_real *scratch = (pf_real *)malloc((size_t)need * sizeof(pf_real));
            long double *sx = (long double *)calloc((size_t)n, sizeof(long double));
            long double *sy = (long double *)calloc((size_t)n, sizeof(long double));
            long double s2 = 0.0L, eb, es;
            double best = 1e300;
            if (!coarse || !box || !scratch || !sx || !sy) {
                fprintf(stderr, "downsample: out of memory\n");
                return 1;
            }
            for (j = 0; j < N; ++j)
                for (i = 0; i < N; ++i) {
                    int t = (j / f) * W + i / f;
                    sx[t] += ds_cd(v + (long long)j * N, 1, i, N) / ((long double)f * f);
                    sy[t] += ds_cd(v + i, N, j, N) / ((long double)f * f);
                    box[t] += fine[j * N + i] / (pf_real)(f * f);
                }
            for (i = 0; i < n; ++i) s2 += sx[i] * sx[i] + sy[i] * sy[i];
            for (rep = 0; rep < 3; ++rep) {
                pf_map_downsample_desc dd;
                double t0;
                memset(&dd, 0, sizeof dd);
                dd.fine = fine, dd.w = N, dd.h = N, dd.factor = f, dd.border = PF_BORDER_WRAP, dd.reg_weight = PF_R(0.01);
                dd.max_iter = 2000, dd.tol = tol;
                t0 = pfb_now_ns();
                if (pf_map_downsample_slopes(&dd, coarse, scratch, need, &it, NULL) != PF_OK) {
                    fprintf(stderr, "downsample: solve failed\n");
                    return 1;
                }
                t0 = pfb_now_ns() - t0;
                if (t0 < best) best = t0;
            }
            eb = ds_err(box, sx, sy, W, f);
            es = ds_err(coarse, sx, sy, W, f);
            printf("  %-14s %6d %8.1f %6d %12.4g %12.4g %12.4g %9.3f\n", pfm_kind_name(kinds[ki]), f, best * 1e-6, it,
                   (double)sqrtl(s2 / n), (double)eb, (double)es, (double)(es / eb));
            free(coarse);
            free(box);
            free(scratch);
            free(sx);
            free(sy);
        }
        pfm_surface_free(&surf);
        free(fine);
        free(v);
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--scaling") == 0) return scaling_main(argc, argv);
    if (argc > 1 && strcmp(argv[1], "--downsample") == 0) return downsample_main();
    long double mom[5] = { 0, 0, 0, 0, 0 };
    int k;
    for (k = 0; k < 4; ++k) {
        long double st[5], a = (long double)(pf_real)lobe_a[k];
        ref_lobe_stats(k, st);
        mom[0] += a * st[0];
        mom[1] += a * st[1];
        mom[2] += a * (st[2] + st[0] * st[0]);
        mom[3] += a * (st[3] + st[1] * st[1]);
        mom[4] += a * (st[4] + st[0] * st[1]);
    }
    leadr_stats = pf_slope_stats_from_moments((pf_real)mom[0], (pf_real)mom[1], (pf_real)mom[2], (pf_real)mom[3],
                                              (pf_real)mom[4]);
    return pfb_main(argc, argv, "vmf", families, (int)(sizeof families / sizeof families[0]));
}

/* bench_horizon.c - cost and accuracy of pf_horizon.h, and (with --masking) horizon-map masking
   against the brute-force microsurface reference.

   DEFAULT RUN (bench/run.sh, make bench): the pf_bench.h families of the shader evaluators.
     hdf_visibility  inputs mu (mean horizon elevation), sigma (its deviation), e (view
                     elevation). pf_horizon_visibility_gauss (Tan et al. 2008) against the
                     Gaussian CDF in long double (erfcl); pf_horizon_visibility_ramp (Fournier
                     1992) against the same CDF (its model error, not a rounding error);
                     BASELINE: the step H(e - mu) of the unfiltered mean horizon.
     hdf_masking     inputs zenith angle t, rho (correlation of slope and horizon), sigma_T.
                     pf_horizon_visible_area against the bivariate-Gaussian expectation by
                     quadrature in long double (E[S] = 0.1, sigma_S = 0.4, E[T] = 0.3);
                     BASELINE: pf_beckmann_g1 (what it multiplies: the cost it adds).
   --masking [--quick] [--kinds K,K..] [--steps S] [--n N]: the masking error on the synthetic surfaces
     of tests/reference/pf_microsurface.h (512^2, periodic; quick: 256^2), 16-, 256- and 4096-texel
     footprints (4 x 4, 16 x 16, 64 x 64), every position on the mip grid (one texel of level
     2, 4 resp. 6 of the pyramids), march bounded to S texels (default 128), the rows marked
     n=16 with N azimuths instead (default 16, at most 64), views
     0-75 deg at azimuths 10 and 100 deg (bench/microsurface.c's protocol; views whose mean
     projected area is below 1/4 of a flat footprint's are skipped there and here), masking
     reference sum V a+ / sum a+ with the full march (and the in-footprint one at 4096), error
     relative L2 pooled over the views. Also the mean over footprints and views of the area
     ratio sum V a / sum a, estimated by pf_horizon_visible_area (the rows' n) and true (the
     marched visibility): the argument of pf_horizon_masking_lod's fade (docs/horizon.md). Also
     the CPU cost of pf_horizon_map for n = 4, 8, 16 and the evaluators' cost per footprint.
     Prints markdown tables. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_horizon.h"
#include <time.h>
#include "pf_microsurface.h"

/* ---------------------------------------------------------------- default families */
/* x = mu, y = sigma, z = e */
PFB_METHOD(gauss, pf_horizon_visibility_gauss(pf_hdf_moments_make(x, x * x + y * y, PF_R(0.0)), z))
PFB_METHOD(ramp, pf_horizon_visibility_ramp(pf_hdf_moments_make(x, x * x + y * y, PF_R(0.0)), z))
PFB_METHOD(step, z >= x ? PF_R(1.0) : PF_R(0.0))

static long double ref_gauss(long double mu, long double sd, long double e)
{
    return 0.5L * erfcl((mu - e) / (sd * sqrtl(2.0L)));
}

static void gen_vis(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_unif_in(r, -0.5, 1.0);
        b[i] = (pf_real)pfb_unif_in(r, 0.01, 0.5);
        c[i] = (pf_real)pfb_unif_in(r, 0.0, 1.5);
    }
}

static size_t grid_vis(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int i, j, k;
    for (i = 0; i <= 6; ++i)
        for (j = 0; j <= 5; ++j)
            for (k = -8; k <= 8; ++k) {
                if (a) {
                    double mu = -0.3 + 0.2 * i, sd = 0.02 + 0.08 * j;
                    a[n] = (pf_real)mu;
                    b[n] = (pf_real)sd;
                    c[n] = (pf_real)(mu + 0.5 * k * sd); /* +-4 sigma */
                }
                ++n;
            }
    return n;
}

/* masking family: x = zenith t, y = rho, z = sigma_T; fixed E[T] = 0.3, E[S] = 0.1 along the
   view azimuth (x axis), sigma_S = 0.4 */
#define HM_MT 0.3
#define HM_MS 0.1
#define HM_SS 0.4
static pf_real hm_eval(pf_real t, pf_real rho, pf_real sdt)
{
    pf_vec3 w = pf_vec3_make(PF_SIN(t), PF_R(0.0), PF_COS(t));
    pf_real cov = rho * PF_R(HM_SS) * sdt;
    pf_hdf_moments m = pf_hdf_moments_make(PF_R(HM_MT), PF_R(HM_MT * HM_MT) + sdt * sdt,
                                           cov + PF_R(HM_MT * HM_MS));
    return pf_horizon_visible_area(w, m, PF_R(HM_MS), PF_R(0.0));
}
PFB_METHOD(visible_area, hm_eval(x, y, z))
PFB_METHOD(smith_g1, pf_beckmann_g1(pf_vec3_make(PF_SIN(x), PF_R(0.0), PF_COS(x)),
                                    pf_slope_stats_make(PF_R(HM_MS), PF_R(0.0), PF_R(HM_SS * HM_SS) * (PF_R(1.0) + y * z),
                                                        PF_R(0.16), PF_R(0.0))))

/* E[1{T < e} (cos t - sin t S)] / (cos t - sin t E[S]) by quadrature over T (S given T is
   Gaussian, so E[S | T] = E[S] + rho sigma_S (T - E[T])/sigma_T) */
static long double ref_visible_area(long double t, long double rho, long double sdt)
{
    long double e = atan2l(cosl(t), sinl(t)), sum = 0.0L, h;
    long double lo = 0.3L - 12.0L * sdt, hi = e < 0.3L + 12.0L * sdt ? e : 0.3L + 12.0L * sdt;
    int i, n = 20000;
    if (!(hi > lo)) return 0.0L;
    h = (hi - lo) / n;
    for (i = 0; i <= n; ++i) {
        long double T = lo + h * i, z = (T - 0.3L) / sdt;
        long double pdf = expl(-0.5L * z * z) / (sdt * sqrtl(2.0L * PFM_PIL));
        long double es = 0.1L + rho * 0.4L * z;
        long double wgt = (i == 0 || i == n) ? 1.0L : ((i & 1) ? 4.0L : 2.0L);
        sum += wgt * pdf * (cosl(t) - sinl(t) * es);
    }
    sum *= h / 3.0L;
    sum /= cosl(t) - sinl(t) * 0.1L;
    /* the documented clamp (a negative correlation can make the Gaussian model's E[V a] < 0) */
    return sum < 0.0L ? 0.0L : (sum > 2.0L ? 2.0L : sum);
}

static void gen_mask(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_unif_in(r, 0.0, 1.3);
        b[i] = (pf_real)pfb_unif_in(r, -0.5, 0.9);
        c[i] = (pf_real)pfb_unif_in(r, 0.05, 0.4);
    }
}

static size_t grid_mask(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int i, j, k;
    for (i = 0; i <= 13; ++i)
        for (j = 0; j <= 7; ++j)
            for (k = 0; k <= 3; ++k) {
                if (a) {
                    a[n] = (pf_real)(0.1 * i);
                    b[n] = (pf_real)(-0.5 + 0.2 * j);
                    c[n] = (pf_real)(0.05 + 0.1 * k);
                }
                ++n;
            }
    return n;
}

static const pfb_family families[] = {
    { "hdf_visibility", 2, { "mu", "sigma" }, 2,
      "inputs mu uniform in [-0.5, 1], sigma in [0.01, 0.5], e in [0, 1.5] (radians)\n"
      "accuracy grid: mu = -0.3 .. 0.9 step 0.2, sigma = 0.02 .. 0.42 step 0.08, e = mu + k sigma/2, k = -8..8\n"
      "reference: Gaussian HDF CDF 0.5 erfc((mu - e)/(sigma sqrt 2)) in long double (Tan et al. 2008); ramp and step are measured against it (model error)",
      gen_vis, grid_vis, 3,
      { PFB_ENTRY_ABS("pf_horizon_visibility_gauss", gauss, ref_gauss),
        PFB_ENTRY_ABS("pf_horizon_visibility_ramp", ramp, ref_gauss),
        PFB_ENTRY_ABS("step_mean_horizon", step, ref_gauss) } },
    { "hdf_masking", 2, { "zenith", "rho" }, 1,
      "inputs zenith uniform in [0, 1.3], rho in [-0.5, 0.9], sigma_T in [0.05, 0.4]; E[T] = 0.3, E[S] = 0.1, sigma_S = 0.4\n"
      "accuracy grid: zenith 0 .. 1.3 step 0.1, rho -0.5 .. 0.9 step 0.2, sigma_T 0.05 .. 0.35 step 0.1\n"
      "reference: E[1{T < e}(cos t - sin t S)]/(cos t - sin t E[S]) for jointly Gaussian (T, S), Simpson over T with 20001 nodes in long double",
      gen_mask, grid_mask, 2,
      { PFB_ENTRY("pf_horizon_visible_area", visible_area, ref_visible_area, 0),
        PFB_ENTRY("pf_beckmann_g1", smith_g1, NULL, 0) } },
};

/* ---------------------------------------------------------------- --masking */
#define NV 7
static const double view_deg[NV] = { 0, 15, 30, 45, 60, 70, 75 };
#define DEG (3.14159265358979323846 / 180.0)
#define NMETH 12
static const char *meth_name[NMETH] = {
    "smith_g1 (pf_beckmann_g1)", "replace: V_A gauss n=16", "replace: V_A ramp n=16",
    "replace: V_A legendre n=8 k=8", "multiply: V_A gauss n=16 x smith", "pf_horizon_masking n=4",
    "pf_horizon_masking n=8", "pf_horizon_masking n=16", "pf_horizon_masking n=16, V lerp",
    "oracle: counted horizon n=16 x area", "oracle: counted horizon n=16 x smith", "no_masking" };

typedef struct acc { double d2[NMETH], r2; long n; double r_est, r_true; } acc;

static double now_s(void) { return pfb_now_ns() * 1e-9; }

static void fetch(const pf_real *pyr, int W, int C, int lod, int x0, int y0, int n, pf_real *out)
{
    int g = W / n;
    pf_real u = (PF_R(x0 / n) + PF_R(0.5)) / PF_R(g), v = (PF_R(y0 / n) + PF_R(0.5)) / PF_R(g);
    pf_mip_sample_bilinear(pyr, W, W, C, lod, u, v, PF_BORDER_WRAP, out);
}

static pf_hdf_moments hdf_at(const pf_real *t, pf_horizon_azimuth az)
{
    return pf_hdf_moments_lerp(pf_hdf_moments_make(t[3 * az.i0], t[3 * az.i0 + 1], t[3 * az.i0 + 2]),
                               pf_hdf_moments_make(t[3 * az.i1], t[3 * az.i1 + 1], t[3 * az.i1 + 2]), az.f);
}

static int ilog2i(int n) { int l = 0; while ((1 << l) < n) ++l; return l; }

/* the rest of a markdown table's header: one column per kind run (have[kind]), then the rule */
static void kind_columns(const int *kinds, int nk, const int *have)
{
    int ki;
    for (ki = 0; ki < nk; ++ki)
        if (have[kinds[ki]]) printf(" %s |", pfm_kind_name(kinds[ki]));
    printf("\n|---|");
    for (ki = 0; ki < nk; ++ki)
        if (have[kinds[ki]]) printf("--:|");
    printf("\n");
}

static int run_masking(int quick, const char *kinds, int steps, int nbig)
{
    static const int kind_list[] = { PFM_GAUSSIAN, PFM_GAUSSIAN_FINE, PFM_GAUSSIAN_ANISO, PFM_PEAKED,
                                     PFM_RIDGES, PFM_CRATERS, PFM_TILES };
    const int W = quick ? 256 : 512;
    const int nsz = 3, sizes[3] = { 4, 16, 64 };
    int ki, r;
    size_t npix = (size_t)W * W;
    long long nt = pf_mip_texel_count(W, W);
    int C4 = pf_horizon_channels(PF_HORIZON_MOMENTS, 4, 0), C8 = pf_horizon_channels(PF_HORIZON_MOMENTS, 8, 0);
    int C16 = pf_horizon_channels(PF_HORIZON_MOMENTS, nbig, 0), CL = pf_horizon_channels(PF_HORIZON_LEGENDRE, 8, 8);
    pf_real *hts = (pf_real *)malloc(npix * sizeof(pf_real));
    pf_real *slope = (pf_real *)malloc((size_t)nt * 5 * sizeof(pf_real));
    pf_real *p4 = (pf_real *)malloc((size_t)nt * C4 * sizeof(pf_real));
    pf_real *p8 = (pf_real *)malloc((size_t)nt * C8 * sizeof(pf_real));
    pf_real *p16 = (pf_real *)malloc((size_t)nt * C16 * sizeof(pf_real));
    pf_real *pl = (pf_real *)malloc((size_t)nt * CL * sizeof(pf_real));
    pf_real *ang = (pf_real *)malloc(npix * (size_t)nbig * sizeof(pf_real));
    unsigned char *vis = (unsigned char *)malloc(npix), *box = (unsigned char *)malloc(npix);
    static double res[PFM_KIND_COUNT][3][2][NMETH]; /* kind, size, ref, method */
    static int have[PFM_KIND_COUNT];
    static double rmean[PFM_KIND_COUNT][3][2]; /* kind, size: mean estimated and true area ratio */
    double eval_ns = 0.0, smith_ns = 0.0;
    if (!hts || !slope || !p4 || !p8 || !p16 || !pl || !ang || !vis || !box) {
        fprintf(stderr, "bench_horizon: out of memory\n");
        return 1;
    }
    printf("# horizon-map masking against the microsurface reference (%d x %d, march %d texels; rows marked n=16 use n = %d)\n\n", W, W, steps, nbig);
    for (ki = 0; ki < (int)(sizeof kind_list / sizeof kind_list[0]); ++ki) {
        int kind = kind_list[ki], si, vi, ai;
        pfm_surface s;
        acc A[3][2];
        double t0;
        size_t i;
        if (kinds && !strstr(kinds, pfm_kind_name(kind))) continue;
        memset(A, 0, sizeof A);
        if (pfm_surface_make(&s, W, W, 1.0, pfm_params_default(kind)) != 0) return 1;
        for (i = 0; i < npix; ++i) hts[i] = (pf_real)s.height[i];
        pf_slope_pyramid_from_heights(hts, W, W, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP, slope);
        t0 = now_s();
        if (pf_horizon_pyramid(hts, W, W, PF_R(1.0), 4, steps, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, p4) != PF_OK ||
            pf_horizon_pyramid(hts, W, W, PF_R(1.0), 8, steps, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, p8) != PF_OK ||
            pf_horizon_pyramid(hts, W, W, PF_R(1.0), nbig, steps, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, p16) != PF_OK ||
            pf_horizon_pyramid(hts, W, W, PF_R(1.0), 8, steps, PF_BORDER_WRAP, PF_HORIZON_LEGENDRE, 8, pl) != PF_OK ||
            pf_horizon_map(hts, W, W, PF_R(1.0), nbig, steps, PF_BORDER_WRAP, PF_HORIZON_ANGLES, 0, ang) != PF_OK) {
            fprintf(stderr, "bench_horizon: build failed\n");
            return 1;
        }
        fprintf(stderr, "bench_horizon: %s: maps built in %.1f s\n", pfm_kind_name(kind), now_s() - t0);
        for (vi = 0; vi < NV; ++vi) {
            int naz = view_deg[vi] == 0.0 ? 1 : 2;
            for (ai = 0; ai < naz; ++ai) {
                double wd[3], th = view_deg[vi] * DEG, ph = (10.0 + 90.0 * ai) * DEG;
                pf_vec3 wo;
                pf_real e;
                pf_horizon_azimuth a4, a8, a16;
                wd[0] = sin(th) * cos(ph);
                wd[1] = sin(th) * sin(ph);
                wd[2] = cos(th);
                wo = pf_vec3_make((pf_real)wd[0], (pf_real)wd[1], (pf_real)wd[2]);
                e = pf_horizon_elevation(wo);
                a4 = pf_horizon_azimuth_of(wo, 4);
                a8 = pf_horizon_azimuth_of(wo, 8);
                a16 = pf_horizon_azimuth_of(wo, nbig);
                pfm_visibility_map(&s, wd, vis);
                for (si = 0; si < nsz; ++si) {
                    int n = sizes[si], g = W / n, lod = ilog2i(n), p;
                    for (p = 0; p < g * g; ++p) {
                        int x0 = (p % g) * n, y0 = (p / g) * n, x, y;
                        pf_real t4[12], t8[24], t16[3 * 64], tl[64], sm[5];
                        pf_slope_stats s0;
                        pf_hdf_legendre L0, L1;
                        pf_hdf_moments m16;
                        double f[NMETH], refs[2], cnt_num = 0.0, cnt_den = 0.0, g1, vis_num = 0.0;
                        pfm_shade sh;
                        int q;
                        sh = pfm_reference_shade(&s, vis, NULL, x0, y0, n, wd, wd, 0.0, 1.0);
                        if (!(sh.area > 0.25 * wd[2])) continue;
                        refs[0] = sh.masking;
                        refs[1] = -1.0;
                        if (n == 64) {
                            pfm_visibility_map_box(&s, wd, x0, y0, n, vis, box);
                            refs[1] = pfm_reference_shade(&s, box, NULL, x0, y0, n, wd, wd, 0.0, 1.0).masking;
                        }
                        fetch(slope, W, 5, lod, x0, y0, n, sm);
                        fetch(p4, W, C4, lod, x0, y0, n, t4);
                        fetch(p8, W, C8, lod, x0, y0, n, t8);
                        fetch(p16, W, C16, lod, x0, y0, n, t16);
                        fetch(pl, W, CL, lod, x0, y0, n, tl);
                        s0 = pf_slope_moments_stats(pf_slope_moments_make(sm[0], sm[1], sm[2], sm[3], sm[4]), PF_R(0.0));
                        g1 = (double)pf_beckmann_g1(wo, s0);
                        m16 = hdf_at(t16, a16);
                        {
                            const pf_real *c0 = tl + 8 * a8.i0, *c1 = tl + 8 * a8.i1;
                            L0 = pf_hdf_legendre_make(c0[0], c0[1], c0[2], c0[3], c0[4], c0[5], c0[6], c0[7]);
                            L1 = pf_hdf_legendre_make(c1[0], c1[1], c1[2], c1[3], c1[4], c1[5], c1[6], c1[7]);
                        }
                        f[0] = g1;
                        f[1] = (double)pf_horizon_visibility_gauss(m16, e);
                        f[2] = (double)pf_horizon_visibility_ramp(m16, e);
                        f[3] = (double)pf_horizon_visibility_legendre(pf_hdf_legendre_lerp(L0, L1, a8.f), 8, wo.z);
                        f[4] = f[1] * g1;
                        f[5] = (double)pf_horizon_masking(wo, hdf_at(t4, a4), s0);
                        f[6] = (double)pf_horizon_masking(wo, hdf_at(t8, a8), s0);
                        f[7] = (double)pf_horizon_masking(wo, m16, s0);
                        {
                            pf_hdf_moments b0 = pf_hdf_moments_make(t16[3 * a16.i0], t16[3 * a16.i0 + 1], t16[3 * a16.i0 + 2]);
                            pf_hdf_moments b1 = pf_hdf_moments_make(t16[3 * a16.i1], t16[3 * a16.i1 + 1], t16[3 * a16.i1 + 2]);
                            f[8] = (1.0 - (double)a16.f) * (double)pf_horizon_masking(wo, b0, s0) +
                                   (double)a16.f * (double)pf_horizon_masking(wo, b1, s0);
                        }
                        /* oracles: the level-0 horizon angles counted (eq. 26 exactly), V_t
                           interpolated between the two azimuths, weighted by a_t */
                        for (y = 0; y < n; ++y)
                            for (x = 0; x < n; ++x) {
                                size_t id = (size_t)(y0 + y) * W + (size_t)(x0 + x);
                                double sx, sy, at, vt;
                                pfm_slope(&s, x0 + x, y0 + y, &sx, &sy);
                                at = wd[2] - sx * wd[0] - sy * wd[1];
                                vt = (1.0 - (double)a16.f) * ((double)ang[id * nbig + a16.i0] < (double)e) +
                                     (double)a16.f * ((double)ang[id * nbig + a16.i1] < (double)e);
                                cnt_num += vt * at;
                                cnt_den += at;
                                vis_num += vis[id] ? at : 0.0; /* the marched visibility: the true ratio */
                            }
                        /* the area ratio's mean, estimated (pf_horizon_visible_area) and true */
                        A[si][0].r_est += (double)pf_horizon_visible_area(wo, m16, s0.mean_x, s0.mean_y);
                        A[si][0].r_true += cnt_den > 0.0 ? vis_num / cnt_den : 0.0;
                        {
                            double front = sh.front_area * n * n;
                            f[9] = front > 0.0 ? cnt_num / front : 0.0;
                            if (f[9] > 1.0) f[9] = 1.0;
                            if (f[9] < 0.0) f[9] = 0.0;
                            f[10] = cnt_den > 0.0 ? cnt_num / cnt_den * g1 : 0.0;
                            if (f[10] > 1.0) f[10] = 1.0;
                            if (f[10] < 0.0) f[10] = 0.0;
                        }
                        f[11] = 1.0;
                        for (r = 0; r < 2; ++r) {
                            if (refs[r] < 0.0) continue;
                            for (q = 0; q < NMETH; ++q) A[si][r].d2[q] += (f[q] - refs[r]) * (f[q] - refs[r]);
                            A[si][r].r2 += refs[r] * refs[r];
                            A[si][r].n++;
                        }
                    }
                }
            }
        }
        for (si = 0; si < nsz; ++si)
            for (r = 0; r < 2; ++r) {
                int q;
                for (q = 0; q < NMETH; ++q)
                    res[kind][si][r][q] = A[si][r].r2 > 0.0 ? sqrt(A[si][r].d2[q] / A[si][r].r2) : -1.0;
            }
        for (si = 0; si < nsz; ++si) {
            rmean[kind][si][0] = A[si][0].n ? A[si][0].r_est / (double)A[si][0].n : -1.0;
            rmean[kind][si][1] = A[si][0].n ? A[si][0].r_true / (double)A[si][0].n : -1.0;
        }
        have[kind] = 1;
        fprintf(stderr, "bench_horizon: %s done (%.1f s), %ld samples at 16 texels\n", pfm_kind_name(kind),
                now_s() - t0, A[0][0].n);
        pfm_surface_free(&s);
    }
    {
        static const char *rn[2] = { "full", "in_footprint" };
        int si;
        for (si = 0; si < nsz; ++si)
            for (r = 0; r < 2; ++r) {
                int q;
                if (sizes[si] != 64 && r == 1) continue;
                printf("\n## masking, %d-texel footprints, %s reference, views 0-75 pooled, relative L2\n\n| method |",
                       sizes[si] * sizes[si], rn[r]);
                kind_columns(kind_list, (int)(sizeof kind_list / sizeof kind_list[0]), have);
                for (q = 0; q < NMETH; ++q) {
                    printf("| %s |", meth_name[q]);
                    for (ki = 0; ki < (int)(sizeof kind_list / sizeof kind_list[0]); ++ki)
                        if (have[kind_list[ki]]) printf(" %.3f |", res[kind_list[ki]][si][r][q]);
                    printf("\n");
                }
            }
    }
    /* the area ratio R = sum V a / sum a: its mean over footprints and views, estimated by
       pf_horizon_visible_area (rows n=16 of this run) and counted with the marched visibility
       (full reference). Docs/horizon.md's lod-fade argument: the two agree at small footprints
       and part at large ones, where the truth tends to 1. */
    printf("\n## mean area ratio sum V a / sum a over footprints and views 0-75: estimate (pf_horizon_visible_area, n = %d) / true (marched)\n\n| footprint |", nbig);
    kind_columns(kind_list, (int)(sizeof kind_list / sizeof kind_list[0]), have);
    {
        int si;
        for (si = 0; si < nsz; ++si) {
            printf("| %d texels |", sizes[si] * sizes[si]);
            for (ki = 0; ki < (int)(sizeof kind_list / sizeof kind_list[0]); ++ki)
                if (have[kind_list[ki]])
                    printf(" %.3f / %.3f |", rmean[kind_list[ki]][si][0], rmean[kind_list[ki]][si][1]);
            printf("\n");
        }
    }
    /* CPU cost of the maps, gaussian kind */
    {
        pfm_surface s;
        int nz[3] = { 4, 8, 16 }, i2, kind2;
        size_t i;
        pfm_surface_make(&s, W, W, 1.0, pfm_params_default(PFM_GAUSSIAN));
        for (i = 0; i < npix; ++i) hts[i] = (pf_real)s.height[i];
        printf("\n## CPU cost of pf_horizon_map (%d x %d gaussian, march %d texels, one core, CPU time, best of %d)\n\n"
               "| n | kind | seconds | ns per texel and azimuth |\n|--:|---|--:|--:|\n", W, W, steps, quick ? 3 : 1);
        for (i2 = 0; i2 < 3; ++i2)
            for (kind2 = 0; kind2 < 2; ++kind2) {
                double best = 1e30;
                int rep;
                for (rep = 0; rep < (quick ? 3 : 1); ++rep) {
                    /* process CPU time: the machine may be shared */
                    double t0 = (double)clock() / CLOCKS_PER_SEC, dt;
                    pf_horizon_map(hts, W, W, PF_R(1.0), nz[i2], steps, PF_BORDER_WRAP,
                                   kind2 ? PF_HORIZON_MOMENTS : PF_HORIZON_ANGLES, 0, p16);
                    dt = (double)clock() / CLOCKS_PER_SEC - t0;
                    if (dt < best) best = dt;
                }
                printf("| %d | %s | %.3f | %.1f |\n", nz[i2], kind2 ? "MOMENTS" : "ANGLES", best,
                       best * 1e9 / ((double)npix * nz[i2]));
            }
        /* the evaluators' cost per footprint (fetched values in registers) */
        {
            volatile pf_real sink = 0;
            int reps = 2000000, k2;
            double t0;
            pf_slope_stats s0 = pf_slope_stats_make(PF_R(0.05), PF_R(-0.02), PF_R(0.15), PF_R(0.16), PF_R(0.01));
            pf_hdf_moments m = pf_hdf_moments_make(PF_R(0.2), PF_R(0.09), PF_R(0.01));
            t0 = now_s();
            for (k2 = 0; k2 < reps; ++k2) {
                pf_real t = PF_R(0.01) + PF_R(1.3) * PF_R(k2 % 1000) / PF_R(1000.0);
                pf_vec3 wo = pf_vec3_make(PF_SIN(t), PF_R(0.1), PF_COS(t));
                pf_horizon_azimuth az = pf_horizon_azimuth_of(wo, 16);
                sink += pf_horizon_masking(wo, pf_hdf_moments_lerp(m, m, az.f), s0);
            }
            eval_ns = (now_s() - t0) * 1e9 / reps;
            t0 = now_s();
            for (k2 = 0; k2 < reps; ++k2) {
                pf_real t = PF_R(0.01) + PF_R(1.3) * PF_R(k2 % 1000) / PF_R(1000.0);
                pf_vec3 wo = pf_vec3_make(PF_SIN(t), PF_R(0.1), PF_COS(t));
                sink += pf_beckmann_g1(wo, s0);
            }
            smith_ns = (now_s() - t0) * 1e9 / reps;
            (void)sink;
            printf("\n## evaluation cost (one core, -O2, values in registers)\n\n"
                   "| method | ns per evaluation |\n|---|--:|\n"
                   "| pf_horizon_azimuth_of + pf_hdf_moments_lerp + pf_horizon_masking | %.1f |\n"
                   "| pf_beckmann_g1 alone | %.1f |\n", eval_ns, smith_ns);
        }
        pfm_surface_free(&s);
    }
    free(hts); free(slope); free(p4); free(p8); free(p16); free(pl); free(ang); free(vis); free(box);
    return 0;
}

int main(int argc, char **argv)
{
    int i, masking = 0, quick = 0, steps = 128, nbig = 16;
    const char *kinds = NULL;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--masking")) masking = 1;
        else if (!strcmp(argv[i], "--quick")) quick = 1;
        else if (!strcmp(argv[i], "--kinds") && i + 1 < argc) kinds = argv[++i];
        else if (!strcmp(argv[i], "--steps") && i + 1 < argc) steps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--n") && i + 1 < argc) nbig = atoi(argv[++i]);
    }
    if (nbig < 1 || nbig > 64) nbig = 16;
    if (masking) return run_masking(quick, kinds, steps > 0 ? steps : 128, nbig);
    return pfb_main(argc, argv, "horizon", families, (int)(sizeof families / sizeof families[0]));
}

/* map_proxies.c - seven periodic 256 x 256 height maps that stand in for maps a user brings to
   `make bench MAP=...` (docs/horizon.md, "User maps"): none is a kind of the corpus
   (tests/reference/pf_microsurface.h). Written as raw little-endian float32 heights (texel
   units, any scale: the MAP path rescales to its RMS slope), one file per map in OUT_DIR:
     fbm_b24         fBm terrain, power spectrum 1/f^2.4, frequencies 1 .. 128 cycles per map
     fbm_b30         the same with 1/f^3 (smoother, longer correlation)
     fbm_b20_detail  1/f^2 from 4 cycles per map up (a detail texture)
     fbm_clipped     1/f^2.4 from 2 cycles, the heights above the 70th percentile flattened to
                     plateaus (slope times 0.1): an eroded / clipped terrain
     fbm_creased     -|fBm| (1/f^2.2 from 2 cycles): sharp valleys
     photo_peaky     exp(fBm 1/f^2 from 6 cycles, unit deviation) plus a little 1/f^0.5 grain: a
                     photographed-texture proxy with heavy-tailed slopes (kurtosis ~30)
     photo_stone     Worley F2 - F1 of 90 cells capped at 3 texels (flat stones, steep grout)
                     plus 1/f grain
   Spectral synthesis: Gaussian amplitudes of deviation f^(-beta/2) per frequency, the real
   part of the inverse DFT (naive, separable: a few seconds). CPU-only bench tool, not part of
   the library. Build and run:  make build/bench/map_proxies && build/bench/map_proxies /tmp/maps
   then e.g.  build/bench/microsurface --map /tmp/maps/fbm_b24.raw --map-raw-size 256x256 --no-cost

   MASKING PARTS (docs/horizon.md, "User maps"): build/bench/map_proxies --masking-parts MAP
   takes one map (a 256 x 256 raw file as written here, rescaled to RMS slope 0.3 as the MAP
   path does, or kind:NAME, a corpus kind of tests/reference/pf_microsurface.h at 512^2) and
   splits the error of pf_horizon_masking (n = 32 azimuths, march 64 texels, the two stored
   azimuths around the view mixed, as bench/microsurface.c's horizon_masking_n32) at EVERY
   4 x 4-texel footprint (the bench samples 256 of them), full reference, views 0-75 deg at
   azimuths 10 and 100 deg (footprint-views with a mean projected area under 1/4 of a flat
   one's skipped, the bench's cull). The reference is G1 = sum V a+ / sum a+ = Rt St with
   Rt = sum V a / sum a (the visible projected area over the mean: the horizon's part) and
   St = sum a / sum a+ (Smith's part), V marched by pfm_visibility_map, a = w.z - s.w_xy. The
   method is pf_horizon_masking = Rk Se: Rk its area ratio with the skewed (Gram-Charlier) HDF,
   Se = pf_beckmann_g1. Rows: the method; Rt Se (only Smith's part estimated); Re St (only the
   horizon's part, Re = pf_horizon_visible_area: the bivariate-Gaussian HDF); Rh St with Rh
   counted on the stored level-0 horizons of the footprint's 16 texels (eq. 26 by counting, the
   two azimuths mixed: what the horizon data can give); then shapes of the HDF computed here in
   double, the Gram-Charlier CDF with skewness g, Phi(z) - g/6 (z^2 - 1) phi(z), whose partial
   mean keeps the Gaussian's closed form (E[(T - mu)/sigma; T < e] = -phi(z) (1 + g z^3/6)): g
   the footprint's own skewness counted on its level-0 horizons (what a stored E[T^3] would
   give; clamped to [0, 1.2]); g = sigma_T/E[T] (1 - rho^2) from the stored moments (rho the
   slope-horizon correlation along the view's azimuth; capped at 1, and 1 where E[T] <= 0: the
   library's choice, so this row checks the method's); the same capped at 0.7 and at 0.5;
   g = sigma_T/E[T] without rho (capped at 1); last the Gaussian HDF, Re Se (pf_horizon_masking
   before the skew). Relative L2 and the relative bias (sum of method -
   reference over sum of reference) per view and azimuth, then pooled; last, the footprints'
   mean skewness of T. One thread, a few seconds per 256^2 map. */
#include "pf_bench_base.h" /* first: _POSIX_C_SOURCE */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pf_beckmann.h"
#include "pf_moments.h"
#include "pf_horizon.h"
#include "pf_microsurface.h"
#include "pf_maps.h"
#define N 256
static const double mp_pi = 3.14159265358979323846;
static unsigned long long rng = 1;
static double rnd(void)
{
    rng = rng * 6364136223846793005ULL + 1442695040888963407ULL;
    return ((double)(rng >> 11) + 0.5) / 9007199254740992.0;
}
static double gauss(void)
{
    double u = rnd(), v = rnd();
    return sqrt(-2.0 * log(u)) * cos(2.0 * mp_pi * v);
}
/* in place: the inverse DFT of (re, im), separable, naive */
static void idft2(double *re, double *im)
{
    static double tr[N], ti[N], c[N], sn[N];
    int i, j, k, pass;
    for (k = 0; k < N; ++k) {
        c[k] = cos(2.0 * mp_pi * k / N);
        sn[k] = sin(2.0 * mp_pi * k / N);
    }
    for (pass = 0; pass < 2; ++pass)
        for (i = 0; i < N; ++i) {
            for (j = 0; j < N; ++j) {
                double a = 0.0, b = 0.0;
                for (k = 0; k < N; ++k) {
                    int idx = pass ? k * N + i : i * N + k, ph = (j * k) % N;
                    a += re[idx] * c[ph] - im[idx] * sn[ph];
                    b += re[idx] * sn[ph] + im[idx] * c[ph];
                }
                tr[j] = a;
                ti[j] = b;
            }
            for (j = 0; j < N; ++j) {
                int idx = pass ? j * N + i : i * N + j;
                re[idx] = tr[j];
                im[idx] = ti[j];
            }
        }
}
/* fBm: power spectrum 1/f^beta for fmin <= f <= fmax cycles per map; seed: the generator's */
static void fbm(double *h, double beta, double fmin, double fmax, unsigned long long seed)
{
    double *re = (double *)calloc(N * N, sizeof *re), *im = (double *)calloc(N * N, sizeof *im);
    int x, y, i;
    if (!re || !im) exit(1);
    rng = seed;
    for (y = 0; y < N; ++y)
        for (x = 0; x < N; ++x) {
            int fx = x <= N / 2 ? x : x - N, fy = y <= N / 2 ? y : y - N;
            double f = sqrt((double)fx * fx + (double)fy * fy), a, g1, g2;
            if (f < fmin || f > fmax) continue;
            a = pow(f, -0.5 * beta);
            g1 = gauss();
            g2 = gauss();
            re[y * N + x] = a * g1;
            im[y * N + x] = a * g2;
        }
    idft2(re, im);
    for (i = 0; i < N * N; ++i) h[i] = re[i];
    free(re);
    free(im);
}
static double rms(const double *h)
{
    double s = 0.0;
    int i;
    for (i = 0; i < N * N; ++i) s += h[i] * h[i];
    return sqrt(s / (N * N));
}
static int save(const char *dir, const char *name, const double *h)
{
    char p[1024];
    float f[N];
    FILE *o;
    int x, y;
    snprintf(p, sizeof p, "%s/%s.raw", dir, name);
    o = fopen(p, "wb");
    if (!o) return 1;
    for (y = 0; y < N; ++y) {
        for (x = 0; x < N; ++x) f[x] = (float)h[y * N + x];
        if (fwrite(f, 4, N, o) != N) break;
    }
    if (fclose(o) != 0 || y < N) return 1;
    printf("%s\n", p);
    return 0;
}
static int cmpd(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
static double percentile(const double *h, double q)
{
    double *c = (double *)malloc(sizeof *c * N * N), r;
    if (!c) exit(1);
    memcpy(c, h, sizeof *c * N * N);
    qsort(c, N * N, sizeof *c, cmpd);
    r = c[(int)(q * (N * N - 1))];
    free(c);
    return r;
}
/* ---------------------------------------------------------------- --masking-parts (see the header) */
#define MP_NAZ 32
#define MP_NV 7
#define MP_NROW 10
static const char *mp_row[MP_NROW] = { "method Rk Se (pf_horizon_masking)", "Rt Se (Smith's part alone)",
                                        "Re St (horizon's part alone, Gaussian HDF)", "Rh St (counted level-0 horizons)",
                                        "GC, counted skew", "GC, g = cv (1 - rho^2), cap 1", "GC, cap 0.7", "GC, cap 0.5", "GC, g = cv, no rho", "Gaussian HDF (pf_horizon_visible_area x g1)" };
/* E[V a]/E[a] with the Gram-Charlier HDF of skewness g (g = 0: pf_horizon_visible_area's formula) */
static double mp_area_gc(const double w[3], pf_hdf_moments m, pf_slope_stats s, double g)
{
    double r = sqrt(w[0] * w[0] + w[1] * w[1]), rs = w[0] * (double)s.mean_x + w[1] * (double)s.mean_y;
    double ea = w[2] - rs, e = atan2(w[2], r), var = (double)m.m2 - (double)m.m1 * (double)m.m1;
    double sd = sqrt(var > 0.0 ? var : 0.0), z, cdf, pdf, cov, eva, pm;
    if (!(ea > 0.0)) return 0.0;
    if (!(sd > 1e-6)) return e >= (double)m.m1 ? 1.0 : 0.0;
    z = (e - (double)m.m1) / sd;
    z = z < -12.0 ? -12.0 : (z > 12.0 ? 12.0 : z);
    pdf = exp(-0.5 * z * z) / sqrt(2.0 * 3.14159265358979323846);
    cdf = 0.5 * erfc(-z / sqrt(2.0)) - g / 6.0 * (z * z - 1.0) * pdf;
    cdf = cdf < 0.0 ? 0.0 : (cdf > 1.0 ? 1.0 : cdf);
    cov = (r * (double)m.ms - rs * (double)m.m1) / sd;
    pm = -pdf * (1.0 + g / 6.0 * z * z * z);
    pm = pm < z * cdf ? pm : z * cdf; /* the clamped CDF's partial mean, as pf_horizon_masking's */
    eva = w[2] * cdf - (rs * cdf + cov * pm);
    eva /= ea;
    return eva < 0.0 ? 0.0 : (eva > 2.0 ? 2.0 : eva);
}
static double mp_sat(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }
static int masking_parts(const char *what)
{
    static const double vdeg[MP_NV] = { 0, 15, 30, 45, 60, 70, 75 };
    double E[MP_NROW][MP_NV][2], B[MP_NROW][MP_NV][2], R2[MP_NV][2], R1[MP_NV][2], sk_sum = 0.0;
    long sk_n = 0;
    pfm_surface s;
    pf_real *hr, *slope, *hor;
    unsigned char *vis;
    long long n, t, tc;
    int w, h, v, a, k, x0, y0, C = pf_horizon_channels(PF_HORIZON_MOMENTS, MP_NAZ, 0);
    double mean = 0.0;
    memset(&s, 0, sizeof s);
    if (!strncmp(what, "kind:", 5)) {
        for (k = 0; k < PFM_KIND_COUNT; ++k)
            if (!strcmp(pfm_kind_name(k), what + 5)) break;
        if (k == PFM_KIND_COUNT || pfm_surface_make(&s, 512, 512, 1.0, pfm_params_default(k)) != 0) {
            fprintf(stderr, "map_proxies: no corpus kind %s\n", what + 5);
            return 1;
        }
    } else {
        pfmap_options o = pfmap_options_default();
        pfmap_info info;
        char err[512];
        o.raw_w = o.raw_h = N;
        if (pfmap_load(what, &o, &s, &info, err, sizeof err) != 0) {
            fprintf(stderr, "map_proxies: %s\n", err);
            return 1;
        }
    }
    w = s.w;
    h = s.h;
    n = (long long)w * h;
    tc = pf_mip_texel_count(w, h);
    hr = (pf_real *)malloc(sizeof *hr * (size_t)n);
    slope = (pf_real *)malloc(sizeof *slope * 5 * (size_t)tc);
    hor = (pf_real *)malloc(sizeof *hor * (size_t)C * (size_t)tc);
    vis = (unsigned char *)malloc((size_t)n);
    if (!hr || !slope || !hor || !vis) exit(1);
    for (t = 0; t < n; ++t) mean += s.height[t];
    mean /= (double)n;
    for (t = 0; t < n; ++t) hr[t] = (pf_real)(s.height[t] - mean);
    pf_slope_pyramid_from_heights(hr, w, h, (pf_real)s.texel, (pf_real)s.texel, PF_R(1.0), PF_BORDER_WRAP, slope);
    if (pf_horizon_pyramid(hr, w, h, (pf_real)s.texel, MP_NAZ, 64, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, hor) != PF_OK)
        exit(1);
    memset(E, 0, sizeof E);
    memset(B, 0, sizeof B);
    memset(R2, 0, sizeof R2);
    memset(R1, 0, sizeof R1);
    for (v = 0; v < MP_NV; ++v)
        for (a = 0; a < (v ? 2 : 1); ++a) {
            double th = vdeg[v] * 3.14159265358979323846 / 180.0, ph = (10.0 + 90.0 * a) * 3.14159265358979323846 / 180.0;
            double wd[3], e, cp = cos(ph), sp = sin(ph);
            pf_vec3 wo;
            pf_horizon_azimuth az;
            wd[0] = sin(th) * cp;
            wd[1] = sin(th) * sp;
            wd[2] = cos(th);
            wo = pf_vec3_make((pf_real)wd[0], (pf_real)wd[1], (pf_real)wd[2]);
            az = pf_horizon_azimuth_of(wo, MP_NAZ);
            e = atan2(wd[2], sin(th));
            pfm_visibility_map(&s, wd, vis);
            for (y0 = 0; y0 < h; y0 += 4)
                for (x0 = 0; x0 < w; x0 += 4) {
                    const long long tex = pf_mip_level_offset(w, h, 2) + (long long)(y0 / 4) * (w / 4) + x0 / 4;
                    const pf_real *st = slope + tex * 5, *tx = hor + tex * C;
                    double sva = 0, sa = 0, sap = 0, svh = 0, t1 = 0, t2 = 0, t3 = 0, m[MP_NROW], ref, Rt, St, Re, Se, Rh;
                    double var, vs, rho2, mu, va, m3, sk, cv;
                    pf_slope_stats ss = pf_slope_moments_stats(pf_slope_moments_make(st[0], st[1], st[2], st[3], st[4]),
                                                               PF_R(0.0));
                    pf_hdf_moments hm = pf_hdf_moments_lerp(pf_hdf_moments_make(tx[3 * az.i0], tx[3 * az.i0 + 1], tx[3 * az.i0 + 2]),
                                                            pf_hdf_moments_make(tx[3 * az.i1], tx[3 * az.i1 + 1], tx[3 * az.i1 + 2]),
                                                            az.f);
                    int i, j;
                    for (j = 0; j < 4; ++j)
                        for (i = 0; i < 4; ++i) {
                            long long q = (long long)(y0 + j) * w + x0 + i;
                            double sx, sy, at, th0 = (double)hor[q * C + 3 * az.i0], th1 = (double)hor[q * C + 3 * az.i1];
                            double f = (double)az.f, tm = (1.0 - f) * th0 + f * th1;
                            pfm_slope(&s, x0 + i, y0 + j, &sx, &sy);
                            at = wd[2] - sx * wd[0] - sy * wd[1];
                            sa += at;
                            sap += at > 0.0 ? at : 0.0;
                            sva += vis[q] ? at : 0.0;
                            svh += ((1.0 - f) * (e >= th0) + f * (e >= th1)) * at;
                            t1 += tm;
                            t2 += tm * tm;
                            t3 += tm * tm * tm;
                        }
                    if (!(sa / 16.0 >= 0.25 * wd[2]) || !(sap > 0.0)) continue; /* the bench's cull */
                    ref = sva / sap;
                    Rt = sva / sa;
                    St = sa / sap;
                    Rh = svh / sa;
                    Re = (double)pf_horizon_visible_area(wo, hm, ss.mean_x, ss.mean_y);
                    Se = (double)pf_beckmann_g1(wo, ss);
                    mu = t1 / 16.0;
                    va = t2 / 16.0 - mu * mu;
                    m3 = t3 / 16.0 - 3.0 * mu * va - mu * mu * mu;
                    sk = va > 1e-12 ? m3 / pow(va, 1.5) : 0.0;
                    var = (double)hm.m2 - (double)hm.m1 * (double)hm.m1;
                    vs = cp * cp * (double)ss.var_x + sp * sp * (double)ss.var_y + 2.0 * cp * sp * (double)ss.cov_xy;
                    rho2 = var > 1e-12 && vs > 1e-12
                               ? pow((double)hm.ms - (cp * (double)ss.mean_x + sp * (double)ss.mean_y) * (double)hm.m1, 2.0) / (var * vs)
                               : 0.0;
                    cv = (double)hm.m1 > 0.0 ? sqrt(var > 0.0 ? var : 0.0) / (double)hm.m1 * (1.0 - (rho2 < 1.0 ? rho2 : 1.0)) : 1.0;
                    if (v == MP_NV - 1 && va > 1e-12) { /* once per footprint and azimuth */
                        sk_sum += sk;
                        ++sk_n;
                    }
                    m[0] = (double)pf_horizon_masking(wo, hm, ss);
                    m[1] = mp_sat(Rt * Se);
                    m[2] = mp_sat(Re * St);
                    m[3] = mp_sat(Rh * St);
                    m[4] = mp_sat(mp_area_gc(wd, hm, ss, sk < 0.0 ? 0.0 : (sk > 1.2 ? 1.2 : sk)) * Se);
                    m[5] = mp_sat(mp_area_gc(wd, hm, ss, cv < 1.0 ? cv : 1.0) * Se);
                    m[6] = mp_sat(mp_area_gc(wd, hm, ss, cv < 0.7 ? cv : 0.7) * Se);
                    m[7] = mp_sat(mp_area_gc(wd, hm, ss, cv < 0.5 ? cv : 0.5) * Se);
                    { double c0 = (double)hm.m1 > 0.0 ? sqrt(var > 0.0 ? var : 0.0) / (double)hm.m1 : 1.0;
                      m[8] = mp_sat(mp_area_gc(wd, hm, ss, c0 < 1.0 ? c0 : 1.0) * Se); }
                    m[9] = mp_sat(Re * Se);
                    for (k = 0; k < MP_NROW; ++k) {
                        E[k][v][a] += (m[k] - ref) * (m[k] - ref);
                        B[k][v][a] += m[k] - ref;
                    }
                    R2[v][a] += ref * ref;
                    R1[v][a] += ref;
                }
        }
    printf("%s: masking at 16 texels, full reference, every footprint; relative L2 / relative bias per view (deg) / "
           "azimuth (deg), then pooled over views 0-75\n%-44s", what, "");
    for (v = 0; v < MP_NV; ++v)
        for (a = 0; a < (v ? 2 : 1); ++a) printf(" %6.0f/%-3.0f", vdeg[v], 10.0 + 90.0 * a);
    printf("     pooled\n");
    for (k = 0; k < MP_NROW; ++k) {
        double se = 0.0, sr = 0.0;
        printf("%-44s", mp_row[k]);
        for (v = 0; v < MP_NV; ++v)
            for (a = 0; a < (v ? 2 : 1); ++a) {
                printf(" %10.4f", sqrt(E[k][v][a] / R2[v][a]));
                se += E[k][v][a];
                sr += R2[v][a];
            }
        printf("   %.4f\n%-44s", sqrt(se / sr), "   bias");
        for (v = 0; v < MP_NV; ++v)
            for (a = 0; a < (v ? 2 : 1); ++a) printf(" %+10.4f", B[k][v][a] / R1[v][a]);
        printf("\n");
    }
    printf("footprints' mean skewness of T (level-0 horizons, the view's two azimuths mixed) %.3f (%ld footprint-azimuths)\n",
           sk_sum / (double)sk_n, sk_n);
    free(hr);
    free(slope);
    free(hor);
    free(vis);
    pfm_surface_free(&s);
    return 0;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    double *h, *g, sd, sg, hi;
    int i, x, y, k, bad = 0;
    if (argc > 2 && !strcmp(argv[1], "--masking-parts")) return masking_parts(argv[2]);
    h = (double *)malloc(sizeof *h * N * N);
    g = (double *)malloc(sizeof *g * N * N);
    if (!h || !g) return 1;
    fbm(h, 2.4, 1, N / 2, 11);
    bad |= save(dir, "fbm_b24", h);
    fbm(h, 3.0, 1, N / 2, 12);
    bad |= save(dir, "fbm_b30", h);
    fbm(h, 2.0, 4, N / 2, 13);
    bad |= save(dir, "fbm_b20_detail", h);
    fbm(h, 2.4, 2, N / 2, 14);
    hi = percentile(h, 0.7);
    for (i = 0; i < N * N; ++i) g[i] = h[i] > hi ? hi + 0.1 * (h[i] - hi) : h[i];
    bad |= save(dir, "fbm_clipped", g);
    fbm(h, 2.2, 2, N / 2, 15);
    for (i = 0; i < N * N; ++i) g[i] = -fabs(h[i]);
    bad |= save(dir, "fbm_creased", g);
    fbm(h, 2.0, 6, N / 2, 16);
    sd = rms(h);
    fbm(g, 0.5, 32, N / 2, 17);
    sg = rms(g);
    for (i = 0; i < N * N; ++i) h[i] = exp(h[i] / sd) + 0.03 * g[i] / sg;
    bad |= save(dir, "photo_peaky", h);
    {
        double px[90], py[90];
        rng = 99;
        for (k = 0; k < 90; ++k) {
            px[k] = rnd() * N;
            py[k] = rnd() * N;
        }
        fbm(g, 1.0, 16, N / 2, 18);
        sg = rms(g);
        for (y = 0; y < N; ++y)
            for (x = 0; x < N; ++x) {
                double d1 = 1e30, d2 = 1e30, e;
                for (k = 0; k < 90; ++k) {
                    double dx = fabs(x - px[k]), dy = fabs(y - py[k]), d;
                    if (dx > N / 2) dx = N - dx;
                    if (dy > N / 2) dy = N - dy;
                    d = sqrt(dx * dx + dy * dy);
                    if (d < d1) {
                        d2 = d1;
                        d1 = d;
                    } else if (d < d2) d2 = d;
                }
                e = d2 - d1;
                h[y * N + x] = (e > 3.0 ? 3.0 : e) + 0.08 * g[y * N + x] / sg;
            }
        bad |= save(dir, "photo_stone", h);
    }
    free(h);
    free(g);
    if (bad) fprintf(stderr, "map_proxies: cannot write to %s\n", dir);
    return bad;
}

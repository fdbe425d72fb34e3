/* bench/microsurface.c - ground truth on synthetic microsurfaces (issue 9, items 2 and 3).

   The library's filtered answers, computed from mip pyramids of moments exactly as a renderer
   would fetch them, against a brute-force reference that shades the same pixel footprint
   texel by texel on an actual height field (tests/pf_microsurface.h: micro-normals from the
   heights, masking and shadowing by marching the height field, a narrow Beckmann base lobe
   or a Lambertian one, the projected-area normalization of LEADR eqs. 1-3).

   CORPUS. The five kinds of pfm_params_default (Gaussian isotropic and anisotropic, ridges,
   craters, tiles), 512 x 512 texels of size 1, periodic.
   FOOTPRINTS. n x n texels, n = 1, 2, 4, ..., 64 (1 to 4096 texels), aligned on the n-grid so
   that the footprint is exactly one texel of pyramid level log2(n) (a box filter: what a
   mip level holds). All positions where there are at most maxpos of them, otherwise a seeded
   subset of maxpos (maxpos = 256 up to 16 x 16 texels, 64 above; quick mode 64 and 16).
   DIRECTIONS. Views theta_o in {0, 15, 30, 45, 60, 70, 75, 80, 85} degrees at a few azimuths;
   lights: a seeded set over the upper hemisphere (theta_i <= 85 degrees) plus, per footprint,
   the mirror direction of the view about the footprint's mesonormal (the specular peak).
   Visibility maps (one per direction) are cached and shared by every footprint; the mirror
   light differs per footprint, so its visibility is marched for the footprint's texels only.

   TASKS AND METHODS (each method from the pyramids only: what a shader can fetch)
     masking   reference: visible projected area / mesosurface projected area (G1 of the
               footprint). smith_g1_exact = pf_beckmann_g1 on the footprint's slope stats,
               smith_g1_fast = pf_g1_beckmann_fast(pf_smith_nu), smith_g1_walter =
               pf_g1_beckmann_walter(pf_smith_nu), no_masking = 1.
     specular  reference: narrow Beckmann base lobe (deviation BASE_SIGMA) per texel, Smith
               G2 of that lobe, V_o V_i by marching, f0 = 1. leadr_joint = pf_leadr_specular,
               leadr_masking = pf_leadr_specular_masking (base variance BASE_SIGMA^2 added by
               pf_slope_moments_stats), lean = P22 at the half vector's slope (no masking, no
               Jacobian, no projected area: bench_beckmann.c's lean_lobe), toksvig = Beckmann
               Cook-Torrance lobe (height-correlated Smith G2) around the normalized average
               normal with roughness pf_toksvig_beckmann_m(sqrt(2) BASE_SIGMA, Toksvig
               variance), times max(0, n.wi) (the engine form), naive_mip_normal = the same
               lobe with the base roughness only.
     diffuse   reference: Lambertian micro-BRDF, albedo 1, V_o V_i. leadr_gg_* =
               pf_gg_diffuse_directional on the footprint's slope stats (LEADR eq. 21, node
               set and N in the name), lambert_mesonormal = max(0, nbar.wi)/pi,
               lambert_macro = max(0, wi.z)/pi.
     oracles   (specular and diffuse; they read every texel, so they are not shader methods)
               oracle_histogram_no_vis = the reference with every texel visible (the exact
               slope histogram, no masking/shadowing), oracle_histogram_smith = that times the
               footprint's Smith 1/(1 + Lambda_o + Lambda_i): they split the library's error
               into visibility model (Smith) and Gaussian fit of the histogram.
     colour_*  height-correlated colour (Heitz et al. 2014): a_t = C(h_t) with C a
               piecewise-linear colour map of the height ('ramp': one linear ramp over +-2
               height deviations; 'bands': three plateaus joined by steep ramps). Reference:
               the V_o V_i projected-area weighted mean of a_t over the footprint
               (pfm_reference_visible_mean). height_visible = C filtered over the library's
               Gaussian fit of the visible-height distribution for Lambda_o + Lambda_i of the
               footprint (pf_height_colour_dist + pf_colormap_filter, heights from the
               (E[h], E[h^2]) pyramid; the reference is a normalized mean, so without the
               mean-visibility factor of eq. 13), gauss_unmasked = the same filter with Lambda
               = 0 (Gaussian heights, no visibility), naive_mip = the mip-mapped a_t,
               mean_height = C(E[h]).
   ERROR. Per cell (kind, task, method, footprint size, view angle) over its lights, azimuths
   and positions: rel_l2 = sqrt(sum (f - ref)^2 / sum ref^2) and max_rel = max |f - ref|/ref
   over the samples with ref >= 10% of the cell's largest ref. Samples whose view is at or
   below the footprint's mesosurface (projected area <= 0: culled by a renderer) are skipped;
   colour samples with nothing visible and lit are skipped.
   COST (item 3). Gaussian kind, view 60 deg, seeded footprints and lights: ns per footprint of
   the brute force (march the footprint's visibility toward view and light, then shade; and
   the shading sum alone with cached visibility maps) and of the filtered evaluations (pyramid
   fetch + evaluation), medians over repetitions.

   OUTPUT (directory --out, default bench/out): microsurface_errors.csv, microsurface_cost.csv,
   microsurface.md (report fragment), microsurface_*.svg (gnuplot, bench/microsurface.gp; the
   .dat files it reads are deleted afterwards).
   Usage: microsurface [--quick] [--out DIR] [--gp FILE] [--no-charts]; BENCH_QUICK=1 in the
   environment also selects the quick mode (smaller map, fewer views, lights, positions). */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>

#include "pf_beckmann.h"
#include "pf_moments.h"
#include "pf_toksvig.h"
#include "pf_gaussgrid.h"
#include "pf_height.h"
#include "pf_microsurface.h"

#define BASE_SIGMA 0.1 /* deviation of the base lobe's slopes (reference and library) */
#define F0 1.0         /* Fresnel off: the reference's F is 1 */
#define NSIZE 7        /* n = 1 .. 64 */
#define NVIEW 9
#define NTASK 5
#define NMETH 7
#define NKIND PFM_KIND_COUNT
#define DEG (3.14159265358979323846 / 180.0)
#define POOL_VIEW_HI 6 /* pooled view range of tables and size charts: 0 .. 75 degrees */

enum { T_MASK, T_SPEC, T_DIFF, T_RAMP, T_BANDS };

static const double view_deg[NVIEW] = { 0, 15, 30, 45, 60, 70, 75, 80, 85 };
static const char *task_name[NTASK] = { "masking", "specular", "diffuse", "colour_ramp", "colour_bands" };
static const char *task_title[NTASK] = { "Masking G1", "Specular (narrow Beckmann base lobe)",
                                         "Diffuse (Lambertian base)",
                                         "Height-correlated colour, ramp map",
                                         "Height-correlated colour, banded map" };
static const int task_nmeth[NTASK] = { 4, 7, 7, 4, 4 };
static const char *meth_name[NTASK][NMETH] = {
    { "smith_g1_exact", "smith_g1_fast", "smith_g1_walter", "no_masking", NULL, NULL, NULL },
    { "leadr_joint", "leadr_masking", "lean", "toksvig", "naive_mip_normal", "oracle_histogram_smith",
      "oracle_histogram_no_vis" },
    { "leadr_gg_matched3", "leadr_gg_matched5", "leadr_gg_hermite3", "lambert_mesonormal", "lambert_macro",
      "oracle_histogram_smith", "oracle_histogram_no_vis" },
    { "height_visible", "gauss_unmasked", "naive_mip", "mean_height", NULL, NULL, NULL },
    { "height_visible", "gauss_unmasked", "naive_mip", "mean_height", NULL, NULL, NULL },
};

/* ---------------------------------------------------------------- settings */
typedef struct settings {
    int quick;
    int map;        /* map side, texels */
    int maxpos;     /* footprint positions per size at most */
    int naz;        /* view azimuths */
    int nlights;    /* hemisphere lights */
    int cost_reps;  /* timing repetitions */
    const char *out, *gp;
    int charts;
} settings;

/* ---------------------------------------------------------------- rng (splitmix64) */
typedef struct rng { unsigned long long s; } rng;
static unsigned long long rng_next(rng *r)
{
    unsigned long long z = (r->s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}
static double rng_unif(rng *r) { return (double)(rng_next(r) >> 11) * (1.0 / 9007199254740992.0); }
static int rng_int(rng *r, int n) { return (int)(rng_unif(r) * n) % n; }

/* ---------------------------------------------------------------- small helpers */
static pf_vec3 v3(const double w[3]) { return pf_vec3_make((pf_real)w[0], (pf_real)w[1], (pf_real)w[2]); }
static void dir_from_angles(double theta, double phi, double w[3])
{
    w[0] = sin(theta) * cos(phi);
    w[1] = sin(theta) * sin(phi);
    w[2] = cos(theta);
}
static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}
static void *xmalloc(size_t n)
{
    void *p = calloc(n ? n : 1, 1); /* zeroed: also keeps gcc's maybe-uninitialized quiet */
    if (!p) {
        fprintf(stderr, "microsurface: out of memory\n");
        exit(1);
    }
    return p;
}
static int ilog2(int n)
{
    int l = 0;
    while ((1 << l) < n) ++l;
    return l;
}

/* ---------------------------------------------------------------- colour maps
   Knots in units of the map's global height deviation about its global mean (the pyramid
   stores heights minus the global mean, as a shader would after a bias). */
#define NK_MAX 6
typedef struct cmap {
    int n;
    double z[NK_MAX], c[NK_MAX];
    pf_real x[NK_MAX], cr[NK_MAX]; /* knots in (centered) heights, for the library */
} cmap;

static const double ramp_z[2] = { -2.0, 2.0 }, ramp_c[2] = { 0.2, 1.0 };
static const double bands_z[6] = { -0.6, -0.4, 0.4, 0.6, 1.3, 1.5 };
static const double bands_c[6] = { 0.25, 0.9, 0.9, 0.4, 0.4, 1.0 };

static cmap cmap_make(const double *z, const double *c, int n, double sd)
{
    cmap m;
    int k;
    m.n = n;
    for (k = 0; k < n; ++k) {
        m.z[k] = z[k] * sd;
        m.c[k] = c[k];
        m.x[k] = (pf_real)(z[k] * sd);
        m.cr[k] = (pf_real)c[k];
    }
    return m;
}

/* C(h), h centered, in double (the reference's attribute) */
static double cmap_eval(const cmap *m, double h)
{
    int k;
    if (h <= m->z[0]) return m->c[0];
    for (k = 0; k + 1 < m->n; ++k)
        if (h < m->z[k + 1]) {
            double t = (h - m->z[k]) / (m->z[k + 1] - m->z[k]);
            return m->c[k] + t * (m->c[k + 1] - m->c[k]);
        }
    return m->c[m->n - 1];
}

static pf_real cmap_filter(const cmap *m, pf_real mean, pf_real dev)
{
    pf_real out = PF_R(0.0);
    pf_colormap_filter(m->x, m->cr, m->n, 1, mean, dev, &out);
    return out;
}

/* ---------------------------------------------------------------- the library's view of a map */
typedef struct lib_maps {
    int w, h;
    pf_real *slope;  /* 5-moment pyramid */
    pf_real *normal; /* average-normal pyramid */
    pf_real *height; /* (E[h], E[h^2]) pyramid, h centered */
    pf_real *attr[2];/* (E[a], E[a^2]) pyramids of the two colour attributes */
    double *attr_d[2]; /* per-texel attributes in double (the reference's) */
    cmap cm[2];
    double mean_h, sd_h;
} lib_maps;

static void lib_maps_build(lib_maps *L, const pfm_surface *s)
{
    int w = s->w, h = s->h, k;
    long long n = (long long)w * h, t, tc = pf_mip_texel_count(w, h);
    pf_real *hr = (pf_real *)xmalloc((size_t)n * sizeof *hr);
    pf_real *nr = (pf_real *)xmalloc((size_t)n * 3 * sizeof *nr);
    pf_real *ar = (pf_real *)xmalloc((size_t)n * sizeof *ar);
    double sum = 0, sum2 = 0;
    L->w = w;
    L->h = h;
    for (t = 0; t < n; ++t) sum += s->height[t];
    L->mean_h = sum / (double)n;
    for (t = 0; t < n; ++t) sum2 += (s->height[t] - L->mean_h) * (s->height[t] - L->mean_h);
    L->sd_h = sqrt(sum2 / (double)n);
    for (t = 0; t < n; ++t) hr[t] = (pf_real)(s->height[t] - L->mean_h);
    L->slope = (pf_real *)xmalloc((size_t)tc * 5 * sizeof(pf_real));
    pf_slope_pyramid_from_heights(hr, w, h, PF_R(s->texel), PF_R(s->texel), PF_R(1.0), PF_BORDER_WRAP,
                                  L->slope);
    /* unit micro-normals from the level-0 slopes (the same central differences) */
    for (t = 0; t < n; ++t) {
        pf_vec3 m = pf_normal_avg_from_slope(L->slope[5 * t], L->slope[5 * t + 1]);
        nr[3 * t] = m.x;
        nr[3 * t + 1] = m.y;
        nr[3 * t + 2] = m.z;
    }
    L->normal = (pf_real *)xmalloc((size_t)tc * 3 * sizeof(pf_real));
    pf_normal_pyramid_from_normals(nr, w, h, L->normal);
    L->height = (pf_real *)xmalloc((size_t)tc * 2 * sizeof(pf_real));
    pf_scalar_pyramid_from_values(hr, w, h, L->height);
    L->cm[0] = cmap_make(ramp_z, ramp_c, 2, L->sd_h);
    L->cm[1] = cmap_make(bands_z, bands_c, 6, L->sd_h);
    for (k = 0; k < 2; ++k) {
        L->attr_d[k] = (double *)xmalloc((size_t)n * sizeof(double));
        for (t = 0; t < n; ++t) {
            L->attr_d[k][t] = cmap_eval(&L->cm[k], s->height[t] - L->mean_h);
            ar[t] = (pf_real)L->attr_d[k][t];
        }
        L->attr[k] = (pf_real *)xmalloc((size_t)tc * 2 * sizeof(pf_real));
        pf_scalar_pyramid_from_values(ar, w, h, L->attr[k]);
    }
    free(hr);
    free(nr);
    free(ar);
}

static void lib_maps_free(lib_maps *L)
{
    free(L->slope);
    free(L->normal);
    free(L->height);
    free(L->attr[0]);
    free(L->attr[1]);
    free(L->attr_d[0]);
    free(L->attr_d[1]);
}

/* What a shader fetches for a footprint: one texel of level log2(n) (a bilinear sample at its
   centre reads exactly that texel). */
typedef struct fetch {
    pf_slope_moments m;
    pf_vec3 navg;
    pf_scalar_moments hm, am[2];
} fetch;

static fetch fetch_footprint(const lib_maps *L, int x0, int y0, int n)
{
    fetch f;
    int g = L->w / n;
    pf_real lod = PF_R(ilog2(n));
    pf_real u = (PF_R(x0 / n) + PF_R(0.5)) / PF_R(g), v = (PF_R(y0 / n) + PF_R(0.5)) / PF_R(L->h / n);
    f.m = pf_slope_moments_sample(L->slope, L->w, L->h, lod, u, v, PF_BORDER_WRAP);
    f.navg = pf_normal_avg_sample(L->normal, L->w, L->h, lod, u, v, PF_BORDER_WRAP);
    f.hm = pf_scalar_moments_sample(L->height, L->w, L->h, lod, u, v, PF_BORDER_WRAP);
    f.am[0] = pf_scalar_moments_sample(L->attr[0], L->w, L->h, lod, u, v, PF_BORDER_WRAP);
    f.am[1] = pf_scalar_moments_sample(L->attr[1], L->w, L->h, lod, u, v, PF_BORDER_WRAP);
    return f;
}

/* ---------------------------------------------------------------- the compared methods */
static pf_real lean_lobe(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s)
{
    pf_vec3 h = pf_vec3_add(wo, wi);
    pf_real iz;
    if (!(h.z > PF_R(0.0))) return PF_R(0.0);
    iz = PF_R(1.0) / h.z;
    return pf_beckmann_p22(-h.x * iz, -h.y * iz, s);
}

/* Cook-Torrance with an isotropic Beckmann NDF of roughness m (m = sqrt(2) slope deviation)
   around the unit normal n, height-correlated Smith G2, Schlick F, times max(0, n.wi):
   F D G / (4 n.wo). The engine form fed by a (Toksvig-filtered) normal map. */
static pf_real ct_beckmann(pf_vec3 n, pf_vec3 wo, pf_vec3 wi, pf_real m)
{
    pf_real no = pf_vec3_dot(n, wo), ni = pf_vec3_dot(n, wi), nh, c2, t2, m2, d, g, f;
    pf_vec3 h;
    if (!(no > PF_R(0.0)) || !(ni > PF_R(0.0))) return PF_R(0.0);
    h = pf_vec3_normalize(pf_vec3_add(wo, wi));
    nh = pf_vec3_dot(n, h);
    if (!(nh > PF_R(0.0))) return PF_R(0.0);
    c2 = nh * nh;
    t2 = (PF_R(1.0) - c2) / c2;
    m2 = m * m;
    d = PF_EXP(-t2 / m2) / (PF_PI * m2 * c2 * c2);
    g = pf_g2_beckmann(pf_smith_nu_iso(no, m * PF_INV_SQRT2), pf_smith_nu_iso(ni, m * PF_INV_SQRT2));
    f = pf_fresnel_schlick(PF_R(F0), pf_vec3_dot(h, wi));
    return f * d * g / (PF_R(4.0) * no);
}

static pf_real toksvig_spec(pf_vec3 navg, pf_vec3 wo, pf_vec3 wi, int widen)
{
    pf_real m = PF_SQRT2 * PF_R(BASE_SIGMA);
    if (widen) m = pf_toksvig_beckmann_m(m, pf_toksvig_variance_from_normal(navg));
    return ct_beckmann(pf_vec3_normalize(navg), wo, wi, m);
}

/* The library's height-correlated colour for a footprint (normalized: no mean-visibility
   factor, see the header). */
static pf_real colour_visible(const cmap *cm, pf_scalar_moments hm, pf_real lo, pf_real li)
{
    pf_height_dist d = pf_height_colour_dist(lo, li, pf_scalar_moments_mean(hm),
                                             pf_scalar_moments_deviation(hm), PF_R(0.0), PF_R(0.0));
    return cmap_filter(cm, d.mean, d.dev);
}

/* The reference with every texel visible (the oracle of the exact slope histogram): the
   reference sh plus the terms of the texels that the marched V_o V_i removed, so only those
   pay the long double base lobe a second time (the same sums as pfm_reference_shade). */
static pfm_shade oracle_no_vis(const pfm_surface *s, const unsigned char *vis_o, const unsigned char *vis_i,
                               int x0, int y0, int n, const double wo[3], const double wi[3], pfm_shade sh)
{
    double A = sh.area * (double)n * (double)n;
    long double spec = 0.0L, diff = 0.0L;
    int i, j;
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            int x = (x0 + i) % s->w, y = (y0 + j) % s->h;
            size_t id = (size_t)y * s->w + x;
            double sx, sy, ao, ai;
            if (vis_o[id] && vis_i[id]) continue;
            pfm_slope(s, x, y, &sx, &sy);
            ao = wo[2] - sx * wo[0] - sy * wo[1];
            ai = wi[2] - sx * wi[0] - sy * wi[1];
            if (!(ao > 0.0) || !(ai > 0.0)) continue;
            diff += (long double)(ao * ai / sqrt(1.0 + sx * sx + sy * sy) / 3.14159265358979323846);
            spec += (long double)pfm_base_specular(wo, wi, sx, sy, BASE_SIGMA, F0);
        }
    sh.spec += (double)(spec / (long double)A);
    sh.diffuse += (double)(diff / (long double)A);
    return sh;
}

/* ---------------------------------------------------------------- sample store per cell */
typedef struct cell {
    double *v;   /* rows of 1 + NMETH: ref, then the methods */
    int n, cap;
} cell;

typedef struct stat {
    double rel_l2, max_rel, sum_d2, sum_r2;
    long samples;
    int valid;
} stat;

static cell cells[NTASK][NSIZE][NVIEW];
static stat stats[NKIND][NTASK][NMETH][NSIZE][NVIEW];

static void cell_add(cell *c, double ref, const double *f, int nm)
{
    int k;
    if (c->n == c->cap) {
        c->cap = c->cap ? 2 * c->cap : 256;
        c->v = (double *)realloc(c->v, (size_t)c->cap * (1 + NMETH) * sizeof(double));
        if (!c->v) {
            fprintf(stderr, "microsurface: out of memory\n");
            exit(1);
        }
    }
    c->v[(size_t)c->n * (1 + NMETH)] = ref;
    for (k = 0; k < NMETH; ++k) c->v[(size_t)c->n * (1 + NMETH) + 1 + k] = k < nm ? f[k] : 0.0;
    c->n++;
}

static void cells_reduce(int kind)
{
    int t, s, v, k, i;
    for (t = 0; t < NTASK; ++t)
        for (s = 0; s < NSIZE; ++s)
            for (v = 0; v < NVIEW; ++v) {
                cell *c = &cells[t][s][v];
                double rmax = 0, r2 = 0;
                for (i = 0; i < c->n; ++i) {
                    double r = c->v[(size_t)i * (1 + NMETH)];
                    r2 += r * r;
                    if (fabs(r) > rmax) rmax = fabs(r);
                }
                for (k = 0; k < task_nmeth[t]; ++k) {
                    stat *st = &stats[kind][t][k][s][v];
                    double d2 = 0, mr = 0;
                    for (i = 0; i < c->n; ++i) {
                        double r = c->v[(size_t)i * (1 + NMETH)], f = c->v[(size_t)i * (1 + NMETH) + 1 + k];
                        d2 += (f - r) * (f - r);
                        if (fabs(r) >= 0.1 * rmax && r != 0.0 && fabs(f - r) / fabs(r) > mr) mr = fabs(f - r) / fabs(r);
                    }
                    st->samples = c->n;
                    st->sum_d2 = d2;
                    st->sum_r2 = r2;
                    st->valid = c->n > 0 && r2 > 1e-300;
                    st->rel_l2 = st->valid ? sqrt(d2 / r2) : 0.0;
                    st->max_rel = mr;
                }
                c->n = 0;
            }
}

/* ---------------------------------------------------------------- one kind */
typedef struct corpus_info {
    double rms_x, rms_y, kurt_x, skew_x, mean_masking_60;
    double seconds;
} corpus_info;
static corpus_info info[NKIND];

static void slope_moments_info(const pfm_surface *s, corpus_info *ci)
{
    long long n = (long long)s->w * s->h;
    double m1 = 0, m2 = 0, m3 = 0, m4 = 0, my2 = 0;
    int x, y;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            double sx, sy;
            pfm_slope(s, x, y, &sx, &sy);
            m1 += sx;
            my2 += sy * sy;
        }
    m1 /= (double)n;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            double sx, sy, d;
            pfm_slope(s, x, y, &sx, &sy);
            d = sx - m1;
            m2 += d * d;
            m3 += d * d * d;
            m4 += d * d * d * d;
        }
    m2 /= (double)n;
    m3 /= (double)n;
    m4 /= (double)n;
    ci->rms_x = sqrt(m2);
    ci->rms_y = sqrt(my2 / (double)n);
    ci->skew_x = m3 / pow(m2, 1.5);
    ci->kurt_x = m4 / (m2 * m2);
}

static void run_kind(int kind, const settings *S, pfm_surface *keep, lib_maps *keep_maps)
{
    pfm_surface surf;
    lib_maps L;
    int W = S->map, si, vi, ai, li, k;
    size_t npix = (size_t)W * W;
    unsigned char *vis_o = (unsigned char *)xmalloc(npix), *vis_m = (unsigned char *)xmalloc(npix);
    unsigned char **vis_l = (unsigned char **)xmalloc((size_t)S->nlights * sizeof *vis_l);
    double (*lights)[3] = (double (*)[3])xmalloc((size_t)S->nlights * sizeof *lights);
    rng r;
    double t0 = now_ns();
    double mask_sum = 0;
    long mask_n = 0;
    r.s = 0x6d6963726f000000ULL + (unsigned long long)kind;
    if (pfm_surface_make(&surf, W, W, 1.0, pfm_params_default(kind)) != 0) {
        fprintf(stderr, "microsurface: pfm_surface_make failed for %s\n", pfm_kind_name(kind));
        exit(1);
    }
    lib_maps_build(&L, &surf);
    slope_moments_info(&surf, &info[kind]);
    /* hemisphere lights: uniform in solid angle, theta_i <= 85 degrees */
    for (li = 0; li < S->nlights; ++li) {
        double cz = cos(85.0 * DEG) + (1.0 - cos(85.0 * DEG)) * rng_unif(&r);
        double ph = 2.0 * 3.14159265358979323846 * rng_unif(&r);
        dir_from_angles(acos(cz), ph, lights[li]);
        vis_l[li] = (unsigned char *)xmalloc(npix);
        pfm_visibility_map(&surf, lights[li], vis_l[li]);
    }
    for (vi = 0; vi < NVIEW; ++vi) {
        int naz = view_deg[vi] == 0.0 ? 1 : S->naz;
        for (ai = 0; ai < naz; ++ai) {
            double wo_d[3];
            pf_vec3 wo;
            dir_from_angles(view_deg[vi] * DEG, (10.0 + 90.0 * ai) * DEG, wo_d);
            wo = v3(wo_d);
            pfm_visibility_map(&surf, wo_d, vis_o);
            for (si = 0; si < NSIZE; ++si) {
                int n = 1 << si, g = W / n, npos = g * g, p, maxpos = n <= 16 ? 4 * S->maxpos : S->maxpos;
                int count = npos < maxpos ? npos : maxpos;
                for (p = 0; p < count; ++p) {
                    int cellid = npos <= maxpos ? p : rng_int(&r, npos);
                    int x0 = (cellid % g) * n, y0 = (cellid / g) * n;
                    fetch f = fetch_footprint(&L, x0, y0, n);
                    pf_slope_stats s0 = pf_slope_moments_stats(f.m, PF_R(0.0));
                    pf_slope_stats sb = pf_slope_moments_stats(f.m, PF_R(BASE_SIGMA * BASE_SIGMA));
                    pf_vec3 nbar = pf_beckmann_mesonormal(s0);
                    pf_real lo = pf_beckmann_lambda(wo, s0), nu_o = pf_smith_nu(wo, s0);
                    pf_gg_grid gm3 = pf_gg_grid_make(wo, s0, PF_GG_MATCHED, 3);
                    pf_gg_grid gm5 = pf_gg_grid_make(wo, s0, PF_GG_MATCHED, 5);
                    pf_gg_grid gh3 = pf_gg_grid_make(wo, s0, PF_GG_HERMITE, 3);
                    int first = 1;
                    for (li = 0; li <= S->nlights; ++li) {
                        double wi_d[3];
                        const unsigned char *vi_map;
                        pf_vec3 wi;
                        pfm_shade sh, nv;
                        double fm[NMETH], g2;
                        if (li < S->nlights) {
                            memcpy(wi_d, lights[li], sizeof wi_d);
                            vi_map = vis_l[li];
                        } else {
                            /* mirror of the view about the mesonormal (the specular peak) */
                            double nb[3], d, len;
                            int x, y;
                            nb[0] = (double)nbar.x;
                            nb[1] = (double)nbar.y;
                            nb[2] = (double)nbar.z;
                            len = sqrt(nb[0] * nb[0] + nb[1] * nb[1] + nb[2] * nb[2]);
                            for (k = 0; k < 3; ++k) nb[k] /= len;
                            d = nb[0] * wo_d[0] + nb[1] * wo_d[1] + nb[2] * wo_d[2];
                            for (k = 0; k < 3; ++k) wi_d[k] = 2.0 * d * nb[k] - wo_d[k];
                            if (!(wi_d[2] > 0.02)) continue;
                            for (y = 0; y < n; ++y)
                                for (x = 0; x < n; ++x) {
                                    int xx = (x0 + x) % W, yy = (y0 + y) % W;
                                    vis_m[(size_t)yy * W + xx] = (unsigned char)pfm_visible(&surf, xx, yy, wi_d);
                                }
                            vi_map = vis_m;
                        }
                        wi = v3(wi_d);
                        sh = pfm_reference_shade(&surf, vis_o, vi_map, x0, y0, n, wo_d, wi_d, BASE_SIGMA, F0);
                        if (!(sh.area > 1e-12)) break; /* view at or below the mesosurface: culled */
                        /* oracles: the footprint's exact slope histogram without visibility, and
                           the same times the library's joint Smith term of the footprint */
                        nv = oracle_no_vis(&surf, vis_o, vi_map, x0, y0, n, wo_d, wi_d, sh);
                        g2 = (double)pf_beckmann_masking_shadowing(wo, wi, s0);
                        if (first) {
                            fm[0] = (double)pf_g1_beckmann(nu_o);
                            fm[1] = (double)pf_g1_beckmann_fast(nu_o);
                            fm[2] = (double)pf_g1_beckmann_walter(nu_o);
                            fm[3] = 1.0;
                            cell_add(&cells[T_MASK][si][vi], sh.masking, fm, 4);
                            if (vi == 4) {
                                mask_sum += sh.masking;
                                mask_n++;
                            }
                            first = 0;
                        }
                        fm[0] = (double)pf_leadr_specular(wo, wi, sb, PF_R(F0));
                        fm[1] = (double)pf_leadr_specular_masking(wo, wi, sb, PF_R(F0));
                        fm[2] = (double)lean_lobe(wo, wi, sb);
                        fm[3] = (double)toksvig_spec(f.navg, wo, wi, 1);
                        fm[4] = (double)toksvig_spec(f.navg, wo, wi, 0);
                        fm[5] = nv.spec * g2;
                        fm[6] = nv.spec;
                        cell_add(&cells[T_SPEC][si][vi], sh.spec, fm, 7);
                        fm[0] = (double)pf_gg_diffuse_directional(gm3, wi);
                        fm[1] = (double)pf_gg_diffuse_directional(gm5, wi);
                        fm[2] = (double)pf_gg_diffuse_directional(gh3, wi);
                        fm[3] = (double)(pf_max(pf_vec3_dot(nbar, wi), PF_R(0.0)) * PF_INV_PI);
                        fm[4] = (double)(pf_max(wi.z, PF_R(0.0)) * PF_INV_PI);
                        fm[5] = nv.diffuse * g2;
                        fm[6] = nv.diffuse;
                        cell_add(&cells[T_DIFF][si][vi], sh.diffuse, fm, 7);
                        if (sh.joint > 1e-9) {
                            pf_real li_l = pf_beckmann_lambda(wi, s0);
                            for (k = 0; k < 2; ++k) {
                                double ref = pfm_reference_visible_mean(&surf, vis_o, vi_map, x0, y0, n, wo_d,
                                                                        L.attr_d[k]);
                                fm[0] = (double)colour_visible(&L.cm[k], f.hm, lo, li_l);
                                fm[1] = (double)colour_visible(&L.cm[k], f.hm, PF_R(0.0), PF_R(0.0));
                                fm[2] = (double)pf_scalar_moments_mean(f.am[k]);
                                fm[3] = (double)cmap_filter(&L.cm[k], pf_scalar_moments_mean(f.hm), PF_R(0.0));
                                cell_add(&cells[T_RAMP + k][si][vi], ref, fm, 4);
                            }
                        }
                    }
                }
            }
        }
    }
    cells_reduce(kind);
    info[kind].mean_masking_60 = mask_n ? mask_sum / (double)mask_n : 0.0;
    info[kind].seconds = (now_ns() - t0) * 1e-9;
    for (li = 0; li < S->nlights; ++li) free(vis_l[li]);
    free(vis_l);
    free(lights);
    free(vis_o);
    free(vis_m);
    if (keep) {
        *keep = surf;
        *keep_maps = L;
    } else {
        lib_maps_free(&L);
        pfm_surface_free(&surf);
    }
}

/* ---------------------------------------------------------------- cost against footprint size */
#define NCOST 7
enum { C_MARCH, C_REF, C_FLOAT, C_LEADR, C_DIFF, C_TOKS, C_COL };
static const char *cost_name[NCOST] = { "brute_force_march_and_shade", "brute_force_shade_only",
                                        "brute_force_float_shade",
                                        "leadr_specular", "leadr_diffuse_gg_matched3",
                                        "toksvig_specular", "leadr_colour_bands" };
typedef struct cost_row {
    double med, q1, q3;
    int batch;
} cost_row;
static cost_row cost[NCOST][NSIZE];
static volatile double sink;

#define COST_LIGHTS 4
#define COST_FP 256 /* footprints per size (seeded), cycled through */

static void run_cost(const settings *S, const pfm_surface *surf, const lib_maps *L)
{
    int W = surf->w, si, mi, rep, b, li, k;
    size_t npix = (size_t)W * W;
    double wo_d[3], lights[COST_LIGHTS][3];
    unsigned char *vis_o = (unsigned char *)xmalloc(npix), *vis_l[COST_LIGHTS];
    unsigned char *sv_o = (unsigned char *)xmalloc(npix), *sv_i = (unsigned char *)xmalloc(npix);
    int fx[COST_FP], fy[COST_FP], fl[COST_FP];
    double *times = (double *)xmalloc((size_t)S->cost_reps * sizeof(double));
    pf_vec3 wo;
    rng r;
    r.s = 0xc057c057ULL;
    dir_from_angles(60.0 * DEG, 10.0 * DEG, wo_d);
    wo = v3(wo_d);
    pfm_visibility_map(surf, wo_d, vis_o);
    memset(sv_o, 0, npix);
    memset(sv_i, 0, npix);
    for (li = 0; li < COST_LIGHTS; ++li) {
        double cz = cos(80.0 * DEG) + (1.0 - cos(80.0 * DEG)) * rng_unif(&r);
        dir_from_angles(acos(cz), 2.0 * 3.14159265358979323846 * rng_unif(&r), lights[li]);
        vis_l[li] = (unsigned char *)xmalloc(npix);
        pfm_visibility_map(surf, lights[li], vis_l[li]);
    }
    for (si = 0; si < NSIZE; ++si) {
        int n = 1 << si, g = W / n;
        for (k = 0; k < COST_FP; ++k) {
            int c = rng_int(&r, g * g);
            fx[k] = (c % g) * n;
            fy[k] = (c / g) * n;
            fl[k] = rng_int(&r, COST_LIGHTS);
        }
        for (mi = 0; mi < NCOST; ++mi) {
            /* batch: about 1-4 ms of work per repetition */
            int batch = mi == C_MARCH ? (n * n >= 4096 ? 2 : (n * n >= 256 ? 16 : 128))
                      : mi == C_REF ? (n * n >= 1024 ? 32 : 1024)
                      : mi == C_FLOAT ? (n * n >= 1024 ? 128 : 2048) : 4096;
            if (S->quick && batch > 8) batch /= 2;
            for (rep = 0; rep < S->cost_reps; ++rep) {
                double t0 = now_ns(), acc = 0;
                for (b = 0; b < batch; ++b) {
                    int q = (b + rep * 7) % COST_FP, x0 = fx[q], y0 = fy[q];
                    const double *wi_d = lights[fl[q]];
                    pf_vec3 wi = v3(wi_d);
                    if (mi == C_MARCH) {
                        int x, y;
                        pfm_shade sh;
                        for (y = 0; y < n; ++y)
                            for (x = 0; x < n; ++x) {
                                int xx = (x0 + x) % W, yy = (y0 + y) % W;
                                sv_o[(size_t)yy * W + xx] = (unsigned char)pfm_visible(surf, xx, yy, wo_d);
                                sv_i[(size_t)yy * W + xx] = (unsigned char)pfm_visible(surf, xx, yy, wi_d);
                            }
                        sh = pfm_reference_shade(surf, sv_o, sv_i, x0, y0, n, wo_d, wi_d, BASE_SIGMA, F0);
                        acc += sh.spec + sh.diffuse;
                    } else if (mi == C_FLOAT) {
                        /* the brute force in the library's own arithmetic: every texel's base lobe
                           (pf_leadr_specular of a one-slope footprint) from level 0 of the slope
                           pyramid, cached visibility, projected-area weights (eqs. 1-3) */
                        const unsigned char *vl = vis_l[fl[q]];
                        pf_real sum = PF_R(0.0), area = PF_R(0.0);
                        int x, y;
                        for (y = 0; y < n; ++y)
                            for (x = 0; x < n; ++x) {
                                size_t id = (size_t)((y0 + y) % W) * W + (size_t)((x0 + x) % W);
                                pf_real sx = L->slope[5 * id], sy = L->slope[5 * id + 1];
                                pf_real a = wo.z - sx * wo.x - sy * wo.y;
                                area += a;
                                if (vis_o[id] && vl[id] && a > PF_R(0.0))
                                    sum += a * pf_leadr_specular(wo, wi, pf_slope_stats_make(sx, sy,
                                               PF_R(BASE_SIGMA * BASE_SIGMA), PF_R(BASE_SIGMA * BASE_SIGMA),
                                               PF_R(0.0)), PF_R(F0));
                            }
                        acc += area > PF_R(0.0) ? (double)(sum / area) : 0.0;
                    } else if (mi == C_REF) {
                        pfm_shade sh = pfm_reference_shade(surf, vis_o, vis_l[fl[q]], x0, y0, n, wo_d, wi_d,
                                                           BASE_SIGMA, F0);
                        acc += sh.spec + sh.diffuse;
                    } else {
                        pf_real lod = PF_R(si);
                        pf_real u = (PF_R(x0 / n) + PF_R(0.5)) / PF_R(g), v = (PF_R(y0 / n) + PF_R(0.5)) / PF_R(g);
                        pf_real res;
                        if (mi == C_LEADR) {
                            pf_slope_moments m = pf_slope_moments_sample(L->slope, W, W, lod, u, v, PF_BORDER_WRAP);
                            res = pf_leadr_specular(wo, wi, pf_slope_moments_stats(m, PF_R(BASE_SIGMA * BASE_SIGMA)),
                                                    PF_R(F0));
                        } else if (mi == C_DIFF) {
                            pf_slope_moments m = pf_slope_moments_sample(L->slope, W, W, lod, u, v, PF_BORDER_WRAP);
                            res = pf_gg_diffuse_directional(
                                pf_gg_grid_make(wo, pf_slope_moments_stats(m, PF_R(0.0)), PF_GG_MATCHED, 3), wi);
                        } else if (mi == C_TOKS) {
                            pf_vec3 na = pf_normal_avg_sample(L->normal, W, W, lod, u, v, PF_BORDER_WRAP);
                            res = toksvig_spec(na, wo, wi, 1);
                        } else {
                            pf_slope_moments m = pf_slope_moments_sample(L->slope, W, W, lod, u, v, PF_BORDER_WRAP);
                            pf_scalar_moments hm = pf_scalar_moments_sample(L->height, W, W, lod, u, v, PF_BORDER_WRAP);
                            pf_slope_stats s0 = pf_slope_moments_stats(m, PF_R(0.0));
                            res = colour_visible(&L->cm[1], hm, pf_beckmann_lambda(wo, s0),
                                                 pf_beckmann_lambda(wi, s0));
                        }
                        acc += (double)res;
                    }
                }
                times[rep] = (now_ns() - t0) / (double)batch;
                sink += acc;
            }
            qsort(times, (size_t)S->cost_reps, sizeof(double), cmp_double);
            cost[mi][si].med = times[S->cost_reps / 2];
            cost[mi][si].q1 = times[S->cost_reps / 4];
            cost[mi][si].q3 = times[(3 * S->cost_reps) / 4];
            cost[mi][si].batch = batch;
        }
    }
    for (li = 0; li < COST_LIGHTS; ++li) free(vis_l[li]);
    free(vis_o);
    free(sv_o);
    free(sv_i);
    free(times);
}

/* ---------------------------------------------------------------- output */
static FILE *open_out(const settings *S, const char *name)
{
    char path[1024];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", S->out, name);
    f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "microsurface: cannot write %s\n", path);
        exit(1);
    }
    return f;
}

/* pooled rel L2 over a set of cells: sqrt(sum d2 / sum r2) */
static double pooled(int kind, int t, int k, int s_lo, int s_hi, int v_lo, int v_hi)
{
    double d2 = 0, r2 = 0;
    int s, v;
    for (s = s_lo; s <= s_hi; ++s)
        for (v = v_lo; v <= v_hi; ++v)
            if (stats[kind][t][k][s][v].valid) {
                d2 += stats[kind][t][k][s][v].sum_d2;
                r2 += stats[kind][t][k][s][v].sum_r2;
            }
    return r2 > 0 ? sqrt(d2 / r2) : -1.0;
}

static void fmt_err(char *buf, size_t n, double e)
{
    if (e < 0) snprintf(buf, n, "-");
    else if (e >= 0.995) snprintf(buf, n, "%.3g", e);
    else snprintf(buf, n, "%.3f", e);
}

static void write_errors_csv(const settings *S)
{
    FILE *f = open_out(S, "microsurface_errors.csv");
    int kind, t, k, s, v;
    fprintf(f, "task,method,kind,footprint_texels,view_deg,rel_l2,max_rel,samples\n");
    for (t = 0; t < NTASK; ++t)
        for (k = 0; k < task_nmeth[t]; ++k)
            for (kind = 0; kind < NKIND; ++kind)
                for (s = 0; s < NSIZE; ++s)
                    for (v = 0; v < NVIEW; ++v) {
                        stat *st = &stats[kind][t][k][s][v];
                        if (!st->valid) continue;
                        fprintf(f, "%s,%s,%s,%d,%g,%.6g,%.6g,%ld\n", task_name[t], meth_name[t][k],
                                pfm_kind_name(kind), 1 << (2 * s), view_deg[v], st->rel_l2, st->max_rel,
                                st->samples);
                    }
    fclose(f);
}

static void write_cost_csv(const settings *S)
{
    FILE *f = open_out(S, "microsurface_cost.csv");
    int m, s;
    fprintf(f, "method,footprint_texels,ns_per_footprint,ns_q1,ns_q3,reps,batch,x_leadr_specular\n");
    for (m = 0; m < NCOST; ++m)
        for (s = 0; s < NSIZE; ++s)
            fprintf(f, "%s,%d,%.6g,%.6g,%.6g,%d,%d,%.6g\n", cost_name[m], 1 << (2 * s), cost[m][s].med,
                    cost[m][s].q1, cost[m][s].q3, S->cost_reps, cost[m][s].batch,
                    cost[m][s].med / cost[C_LEADR][s].med);
    fclose(f);
}

/* chart data: wide tables, '?' = missing */
static void write_dat(const settings *S, const char *name, int ncol, const char **colname,
                      int nrow, const double *x, const double *y /* nrow x ncol */)
{
    FILE *f = open_out(S, name);
    int i, j;
    fprintf(f, "x");
    for (j = 0; j < ncol; ++j) fprintf(f, "\t%s", colname[j]);
    fprintf(f, "\n");
    for (i = 0; i < nrow; ++i) {
        fprintf(f, "%g", x[i]);
        for (j = 0; j < ncol; ++j) {
            double e = y[i * ncol + j];
            if (e < 0) fprintf(f, "\t?");
            else fprintf(f, "\t%.6g", e < 1e-6 ? 1e-6 : e);
        }
        fprintf(f, "\n");
    }
    fclose(f);
}

static int charts_made = 0;
static void chart(const settings *S, const char *name, const char *title, const char *xlabel,
                  const char *ylabel, int logx, int ncol)
{
    char cmd[4096], dat[1024], svg[1024];
    snprintf(dat, sizeof dat, "%s/%s.dat", S->out, name);
    snprintf(svg, sizeof svg, "%s/%s.svg", S->out, name);
    if (S->charts) {
        snprintf(cmd, sizeof cmd,
                 "gnuplot -e \"datf='%s'; outf='%s'; ttl='%s'; xl='%s'; yl='%s'; logx=%d; ncol=%d\" %s",
                 dat, svg, title, xlabel, ylabel, logx, ncol, S->gp);
        if (system(cmd) == 0) charts_made++;
        else fprintf(stderr, "microsurface: gnuplot failed for %s\n", name);
    }
    remove(dat);
}

static void make_charts(const settings *S)
{
    double x[16], y[16 * 8];
    const char *cols[8];
    char name[256], title[512];
    int t, k, s, v, kind;
    for (t = 0; t < NTASK; ++t) {
        /* error vs footprint size, Gaussian kind, pooled over views */
        for (s = 0; s < NSIZE; ++s) {
            x[s] = (double)(1 << (2 * s));
            for (k = 0; k < task_nmeth[t]; ++k) y[s * task_nmeth[t] + k] = pooled(PFM_GAUSSIAN, t, k, s, s, 0, POOL_VIEW_HI);
        }
        for (k = 0; k < task_nmeth[t]; ++k) cols[k] = meth_name[t][k];
        snprintf(name, sizeof name, "microsurface_size_%s", task_name[t]);
        write_dat(S, strcat(strcpy(title, name), ".dat"), task_nmeth[t], cols, NSIZE, x, y);
        snprintf(title, sizeof title, "%s, gaussian kind: error vs footprint (views 0-75 deg pooled)", task_title[t]);
        chart(S, name, title, "footprint (texels, log)", "relative L2 error (log)", 1, task_nmeth[t]);
        /* error vs view angle, Gaussian kind, pooled over sizes */
        for (v = 0; v < NVIEW; ++v) {
            x[v] = view_deg[v];
            for (k = 0; k < task_nmeth[t]; ++k) y[v * task_nmeth[t] + k] = pooled(PFM_GAUSSIAN, t, k, 4, NSIZE - 1, v, v);
        }
        snprintf(name, sizeof name, "microsurface_view_%s", task_name[t]);
        write_dat(S, strcat(strcpy(title, name), ".dat"), task_nmeth[t], cols, NVIEW, x, y);
        snprintf(title, sizeof title, "%s, gaussian kind: error vs view angle (footprints of 256-4096 texels pooled)", task_title[t]);
        chart(S, name, title, "view angle theta_o (degrees)", "relative L2 error (log)", 0, task_nmeth[t]);
        /* the library's method on every kind */
        for (s = 0; s < NSIZE; ++s) {
            x[s] = (double)(1 << (2 * s));
            for (kind = 0; kind < NKIND; ++kind) y[s * NKIND + kind] = pooled(kind, t, 0, s, s, 0, POOL_VIEW_HI);
        }
        for (kind = 0; kind < NKIND; ++kind) cols[kind] = pfm_kind_name(kind);
        snprintf(name, sizeof name, "microsurface_kinds_%s", task_name[t]);
        write_dat(S, strcat(strcpy(title, name), ".dat"), NKIND, cols, NSIZE, x, y);
        snprintf(title, sizeof title, "%s: %s on every kind (views 0-75 deg pooled)", task_title[t], meth_name[t][0]);
        chart(S, name, title, "footprint (texels, log)", "relative L2 error (log)", 1, NKIND);
    }
    for (s = 0; s < NSIZE; ++s) {
        x[s] = (double)(1 << (2 * s));
        for (k = 0; k < NCOST; ++k) y[s * NCOST + k] = cost[k][s].med;
    }
    for (k = 0; k < NCOST; ++k) cols[k] = cost_name[k];
    write_dat(S, "microsurface_cost.dat", NCOST, cols, NSIZE, x, y);
    chart(S, "microsurface_cost", "Cost per footprint: brute force vs filtered (gaussian kind, view 60 deg)",
          "footprint (texels, log)", "median ns per footprint (log)", 3, NCOST);
}

static void write_md(const settings *S, double total_s)
{
    FILE *f = open_out(S, "microsurface.md");
    static const int tab_sizes[4] = { 0, 2, 4, 6 };      /* 1, 16, 256, 4096 texels */
    static const int tab_views[6] = { 0, 2, 4, 6, 7, 8 }; /* 0, 30, 60, 75, 80, 85 deg */
    int t, k, s, v, kind, i;
    char b[64];
    fprintf(f, "## Ground truth on synthetic microsurfaces\n\n");
    fprintf(f, "Generated by `bench/microsurface.c` (%s mode, %.0f s); every number below is computed "
               "in that run. Raw cells: `microsurface_errors.csv`, timings: `microsurface_cost.csv`.\n\n",
            S->quick ? "QUICK (smoke run: do not publish)" : "full", total_s);
    fprintf(f, "**Reference.** A brute-force shading of the pixel footprint texel by texel on an actual "
               "height field (`tests/pf_microsurface.h`): micro-normals from central differences of the "
               "heights, masking toward the view and shadowing toward the light by marching the "
               "(bilinear, periodic) height field, a narrow Beckmann base lobe of slope deviation %.2g "
               "with its own Smith G2 (specular, f0 = 1: no Fresnel) or a Lambertian one of albedo 1 "
               "(diffuse), normalized by the projected area of the mesosurface (LEADR 2013 eqs. 1-3). "
               "The filtered answers read only what a shader can fetch: one texel of the mip pyramids "
               "of the slope moments, average normals, (E[h], E[h^2]) and the colour attribute, built "
               "by `pf_moments.h` from the same heights.\n\n", BASE_SIGMA);
    fprintf(f, "**Corpus.** %d x %d periodic maps (texel 1), the five kinds of `pfm_params_default`; "
               "footprints of n x n texels (n = 1, 2, ..., 64) aligned so that each is exactly one texel of "
               "pyramid level log2(n), at most %d positions per size up to 256 texels and %d above (all of "
               "them where there are fewer; a seeded subset otherwise); "
               "views theta_o = 0..85 degrees at %d azimuth(s); %d seeded lights over the hemisphere "
               "(theta_i <= 85 degrees) plus the mirror direction of the view about each footprint's "
               "mesonormal (the specular peak).\n\n", S->map, S->map, 4 * S->maxpos, S->maxpos, S->naz, S->nlights);
    fprintf(f, "**Error.** Per cell (kind, task, method, footprint size, view angle) over its lights, "
               "azimuths and positions: relative L2 error sqrt(sum (f - ref)^2 / sum ref^2); the CSV also "
               "has the max relative error over the samples with ref >= 10%% of the cell's largest. "
               "Pooled values (charts, tables) are the same ratio over the union of cells (views 0-75 "
               "degrees unless stated: the grazing views have their own columns). Samples "
               "whose view is at or below the footprint's mesosurface are skipped (a renderer culls "
               "them).\n\n");
    fprintf(f, "| kind | slope RMS x | slope RMS y | slope skewness x | slope kurtosis x | mean G1 at 60 deg (reference) |\n");
    fprintf(f, "|---|--:|--:|--:|--:|--:|\n");
    for (kind = 0; kind < NKIND; ++kind)
        fprintf(f, "| %s | %.3f | %.3f | %.2f | %.2f | %.3f |\n", pfm_kind_name(kind), info[kind].rms_x,
                info[kind].rms_y, info[kind].skew_x, info[kind].kurt_x, info[kind].mean_masking_60);
    fprintf(f, "\nMethods: masking: `pf_beckmann_g1` (exact), `pf_g1_beckmann_fast`, `pf_g1_beckmann_walter` "
               "on the footprint's slope statistics, and no masking (G1 = 1). Specular: `pf_leadr_specular` "
               "(joint masking-shadowing), `pf_leadr_specular_masking`, LEAN (P22 at the half vector's slope, "
               "no masking, Jacobian or projected area), Toksvig (Cook-Torrance Beckmann lobe around the "
               "normalized average normal, roughness widened by `pf_toksvig_beckmann_m`), the naive "
               "mip-mapped normal (same lobe, base roughness only). Diffuse: `pf_gg_diffuse_directional` "
               "(LEADR eq. 21) with the matched grid N = 3, 5 and Gauss-Hermite N = 3; Lambert on the "
               "mesonormal; Lambert on the macro normal. Two oracles (not shader methods: they read every "
               "texel) split the specular and diffuse errors into their causes: `oracle_histogram_no_vis` "
               "is the reference with every texel visible (the footprint's exact slope histogram, no "
               "masking or shadowing: its error is the visibility alone), `oracle_histogram_smith` is that "
               "times the footprint's Smith term 1/(1 + Lambda_o + Lambda_i) (the library's visibility "
               "model on the exact histogram: its error is Smith's, the gap between it and leadr_joint "
               "is the Gaussian fit of the histogram). Colour: the colour map filtered over the "
               "library's visible-height distribution (`pf_height_colour_dist` for Lambda_o + Lambda_i, "
               "`pf_colormap_filter`; normalized, i.e. without the mean-visibility factor of Heitz et al. "
               "2014 eq. 13, because the reference is a normalized mean), the same filter without "
               "visibility (Gaussian heights, Lambda = 0), the mip-mapped colour, and the colour at the "
               "mean height.\n");
    fprintf(f, "\n**Key numbers** (Gaussian kind, footprint 4096 texels, relative L2 error pooled over "
               "views 0-75 degrees; the tables below have the rest):\n\n");
    fprintf(f, "- masking: `pf_beckmann_g1` %.3f, no masking %.3f; at 85 degrees alone %.3f and %.3f.\n",
            pooled(0, T_MASK, 0, 6, 6, 0, POOL_VIEW_HI), pooled(0, T_MASK, 3, 6, 6, 0, POOL_VIEW_HI),
            pooled(0, T_MASK, 0, 6, 6, 8, 8), pooled(0, T_MASK, 3, 6, 6, 8, 8));
    fprintf(f, "- specular: `pf_leadr_specular` %.3f, Toksvig %.3f, LEAN %.3f, naive mip-mapped normal %.3f; "
               "the exact slope histogram with the same Smith term (oracle) %.3f%s.\n",
            pooled(0, T_SPEC, 0, 6, 6, 0, POOL_VIEW_HI), pooled(0, T_SPEC, 3, 6, 6, 0, POOL_VIEW_HI),
            pooled(0, T_SPEC, 2, 6, 6, 0, POOL_VIEW_HI), pooled(0, T_SPEC, 4, 6, 6, 0, POOL_VIEW_HI),
            pooled(0, T_SPEC, 5, 6, 6, 0, POOL_VIEW_HI),
            pooled(0, T_SPEC, 5, 6, 6, 0, POOL_VIEW_HI) < 0.5 * pooled(0, T_SPEC, 0, 6, 6, 0, POOL_VIEW_HI)
                ? ": most of LEADR's error at this size is the Gaussian fit of the footprint's slope "
                  "histogram, not the masking model"
                : "");
    fprintf(f, "- diffuse: LEADR grid (matched, N = 3) %.3f, Lambert on the mesonormal %.3f, on the macro "
               "normal %.3f.\n",
            pooled(0, T_DIFF, 0, 6, 6, 0, POOL_VIEW_HI), pooled(0, T_DIFF, 3, 6, 6, 0, POOL_VIEW_HI),
            pooled(0, T_DIFF, 4, 6, 6, 0, POOL_VIEW_HI));
    fprintf(f, "- colour (banded map): visible-height filtering %.3f, mip-mapped colour %.3f, colour at the "
               "mean height %.3f.\n",
            pooled(0, T_BANDS, 0, 6, 6, 0, POOL_VIEW_HI), pooled(0, T_BANDS, 2, 6, 6, 0, POOL_VIEW_HI),
            pooled(0, T_BANDS, 3, 6, 6, 0, POOL_VIEW_HI));
    fprintf(f, "- cost at 4096 texels: brute force %.3g ns per footprint (march + shade), `pf_leadr_specular` "
               "with its fetch %.3g ns: %.3g times cheaper (at 1 texel: %.3g times); against a brute "
               "force in the library's own float arithmetic with cached visibility, %.3g times.\n",
            cost[C_MARCH][NSIZE - 1].med, cost[C_LEADR][NSIZE - 1].med,
            cost[C_MARCH][NSIZE - 1].med / cost[C_LEADR][NSIZE - 1].med,
            cost[C_MARCH][0].med / cost[C_LEADR][0].med, cost[C_FLOAT][NSIZE - 1].med / cost[C_LEADR][NSIZE - 1].med);
    for (t = 0; t < NTASK; ++t) {
        fprintf(f, "\n### %s\n\n", task_title[t]);
        fprintf(f, "Gaussian kind, relative L2 error by footprint (texels) and view angle.\n\n");
        fprintf(f, "| method | texels |");
        for (i = 0; i < 6; ++i) fprintf(f, " %g deg |", view_deg[tab_views[i]]);
        fprintf(f, " 0-75 deg pooled |\n|---|--:|");
        for (i = 0; i < 7; ++i) fprintf(f, "--:|");
        fprintf(f, "\n");
        for (k = 0; k < task_nmeth[t]; ++k)
            for (s = 0; s < 4; ++s) {
                int si = tab_sizes[s];
                fprintf(f, "| %s | %d |", s == 0 ? meth_name[t][k] : "", 1 << (2 * si));
                for (i = 0; i < 6; ++i) {
                    stat *st = &stats[PFM_GAUSSIAN][t][k][si][tab_views[i]];
                    fmt_err(b, sizeof b, st->valid ? st->rel_l2 : -1.0);
                    fprintf(f, " %s |", b);
                }
                fmt_err(b, sizeof b, pooled(PFM_GAUSSIAN, t, k, si, si, 0, POOL_VIEW_HI));
                fprintf(f, " %s |\n", b);
            }
        fprintf(f, "\n![%s: error vs footprint](microsurface_size_%s.svg)\n", task_name[t], task_name[t]);
        fprintf(f, "![%s: error vs view](microsurface_view_%s.svg)\n", task_name[t], task_name[t]);
    }
    (void)v;
    fprintf(f, "\n### Every kind: where the Gaussian assumption breaks\n\n");
    fprintf(f, "Relative L2 error pooled over views 0-75 degrees, at footprints of 16 / 4096 texels. The Gaussian "
               "kinds satisfy the assumptions of the filtered models (Gaussian slopes and heights); "
               "ridges, craters and tiles do not.\n\n| task | method |");
    for (kind = 0; kind < NKIND; ++kind) fprintf(f, " %s |", pfm_kind_name(kind));
    fprintf(f, "\n|---|---|");
    for (kind = 0; kind < NKIND; ++kind) fprintf(f, "--:|");
    fprintf(f, "\n");
    for (t = 0; t < NTASK; ++t)
        for (k = 0; k < task_nmeth[t]; ++k) {
            fprintf(f, "| %s | %s |", k == 0 ? task_name[t] : "", meth_name[t][k]);
            for (kind = 0; kind < NKIND; ++kind) {
                char b2[64];
                fmt_err(b, sizeof b, pooled(kind, t, k, 2, 2, 0, POOL_VIEW_HI));
                fmt_err(b2, sizeof b2, pooled(kind, t, k, 6, 6, 0, POOL_VIEW_HI));
                fprintf(f, " %s / %s |", b, b2);
            }
            fprintf(f, "\n");
        }
    for (t = 0; t < NTASK; ++t)
        fprintf(f, "\n![%s on every kind](microsurface_kinds_%s.svg)", task_name[t], task_name[t]);
    fprintf(f, "\n\n### Cost against footprint size\n\n");
    fprintf(f, "Gaussian kind, view 60 degrees, %d seeded footprints per size and %d seeded lights; "
               "median ns per footprint over %d repetitions (quartiles in `microsurface_cost.csv`). "
               "Brute force (march + shade): marches the visibility of the footprint's texels toward "
               "the view and the light (2 n^2 rays), then sums the reference shading (specular, "
               "diffuse, masking together). Brute force (shade only): the same sum with the "
               "visibility maps already computed (cached maps, as in the error runs); both are the "
               "long double reference of `tests/pf_microsurface.h`. Brute force (float shade): the "
               "same sum in the library's own arithmetic (pf_real), every texel's base lobe by "
               "`pf_leadr_specular` of a one-slope footprint, slopes read from level 0 of the pyramid, "
               "cached visibility: what a supersampling shader would pay, without the march. Filtered: one "
               "pyramid fetch (bilinear sample at the texel centre) plus the evaluation.\n\n",
            COST_FP, COST_LIGHTS, S->cost_reps);
    fprintf(f, "| texels |");
    for (k = 0; k < NCOST; ++k) fprintf(f, " %s (ns) |", cost_name[k]);
    fprintf(f, " march+shade / leadr_specular | float shade / leadr_specular |\n|--:|");
    for (k = 0; k <= NCOST + 1; ++k) fprintf(f, "--:|");
    fprintf(f, "\n");
    for (s = 0; s < NSIZE; ++s) {
        fprintf(f, "| %d |", 1 << (2 * s));
        for (k = 0; k < NCOST; ++k) fprintf(f, " %.4g |", cost[k][s].med);
        fprintf(f, " %.3g | %.3g |\n", cost[C_MARCH][s].med / cost[C_LEADR][s].med,
                cost[C_FLOAT][s].med / cost[C_LEADR][s].med);
    }
    fprintf(f, "\n![cost per footprint](microsurface_cost.svg)\n");
    if (!charts_made) fprintf(f, "\n(no charts were made in this run: gnuplot missing or --no-charts.)\n");
    fclose(f);
}

int main(int argc, char **argv)
{
    settings S;
    int i, kind;
    const char *q = getenv("BENCH_QUICK");
    pfm_surface gauss_surf;
    lib_maps gauss_maps;
    double t0 = now_ns();
    memset(&S, 0, sizeof S);
    S.quick = q && *q && strcmp(q, "0") != 0 && strcmp(q, "no") != 0;
    S.out = "bench/out";
    S.gp = "bench/microsurface.gp";
    S.charts = 1;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--quick")) S.quick = 1;
        else if (!strcmp(argv[i], "--no-charts")) S.charts = 0;
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) S.out = argv[++i];
        else if (!strcmp(argv[i], "--gp") && i + 1 < argc) S.gp = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--quick] [--out DIR] [--gp FILE] [--no-charts]\n", argv[0]);
            return 2;
        }
    }
    if (S.quick) {
        S.map = 256;
        S.maxpos = 16;
        S.naz = 1;
        S.nlights = 3;
        S.cost_reps = 7;
    } else {
        S.map = 512;
        S.maxpos = 64;
        S.naz = 2;
        S.nlights = 8;
        S.cost_reps = 21;
    }
    if (S.charts && system("gnuplot --version > /dev/null 2>&1") != 0) {
        fprintf(stderr, "microsurface: gnuplot not found, charts skipped\n");
        S.charts = 0;
    }
    for (kind = 0; kind < NKIND; ++kind) {
        run_kind(kind, &S, kind == PFM_GAUSSIAN ? &gauss_surf : NULL, &gauss_maps);
        fprintf(stderr, "microsurface: %s done (%.1f s)\n", pfm_kind_name(kind), info[kind].seconds);
    }
    run_cost(&S, &gauss_surf, &gauss_maps);
    fprintf(stderr, "microsurface: cost done (%.1f s total)\n", (now_ns() - t0) * 1e-9);
    write_errors_csv(&S);
    write_cost_csv(&S);
    make_charts(&S);
    write_md(&S, (now_ns() - t0) * 1e-9);
    lib_maps_free(&gauss_maps);
    pfm_surface_free(&gauss_surf);
    printf("microsurface: wrote %s/microsurface.md, microsurface_errors.csv, microsurface_cost.csv, %d charts (%.1f s)\n",
           S.out, charts_made, (now_ns() - t0) * 1e-9);
    return 0;
}

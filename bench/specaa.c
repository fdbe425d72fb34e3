/* bench/specaa.c - roughness mips baked from normal maps (pf_specaa.h's baker) against the
   engines' formulas, measured on the microsurface corpus against the exact NDF of each mip
   texel's footprint; and curved, normal-mapped scenes (bench/specaa_scenes.h) for the
   geometry kernel.

   THE ORACLE. A mip texel of level L covers a box of 2^L x 2^L texels of the normal map. Each
   texel t carries the base lobe of roughness alpha0 (GGX or Beckmann) around its own slope
   s_t (the slope-space model of LEADR and of every roughness-widening formula), so the exact
   NDF of the footprint, as a density of slopes, is the mixture
       P_ref(s) = (1/N) sum_t P_alpha0(s - s_t).
   A baker gives one isotropic roughness alpha' for the texel; a renderer centres that lobe on
   the footprint's averaged normal (the normal map's own mip), slope c:
       P_bake(s) = P_alpha'(s - c).
   The error of a baker on a texel is the relative L2 distance ||P_bake - P_ref|| / ||P_ref||
   over the slope plane (a G x G midpoint grid around c, half-width 4 sqrt(alpha0^2 + 2 var) +
   |mean - c|, var the footprint's per-axis slope variance; P_ref summed texel by texel, no
   histogram). "oracle" is the best isotropic alpha at that centre (golden-section search on
   log alpha): what no roughness formula can beat, so a reader sees the room left.

   BAKERS (r = |mean of the footprint's unit normals|, kappa = (3r - r^3)/(1 - r^2), Banerjee
   et al. 2005; every one gets the same alpha0 and the same centre). The engines' as their
   source reads (docs/specaa.md cites file and function); where an engine stores PERCEPTUAL
   roughness p (alpha = p^2) and adds to p^2, the increment lands on alpha, not alpha^2:
     naive     alpha' = alpha0 (the roughness map's mip, no normal variance)
     toksvig   alpha'^2 = alpha0^2 + 2 (1 - r)/r                   (Toksvig 2005; pf_toksvig_ggx_alpha)
     filament  alpha' = alpha0 + min(2 x 0.25/kappa, 0.2^2)        (tools/roughness-prefilter: on the
                                                                    perceptual roughness it writes)
     hdrp      alpha'^2 = alpha0^2 + min(2 min(0.25/kappa, 0.03125), 0.2^2)
                                                                   (NormalMapFilteringTexturePostprocessor's
                                                                    variance in the B channel, NormalFiltering
                                                                    at run time on alpha^2, threshold 0.2)
     godot     alpha' = alpha0 + min(3 x 0.25/kappa, 0.4^2)        (Image::generate_mipmap_roughness, on
                                                                    the perceptual roughness channel)
     library   pf_specaa_bake: alpha'^2 = E[alpha^2] + 2 g var rho, the footprint's slope variance
               corrected by its peakedness rho = 8 var^2 / E|s - E s|^4 (clamped to [0, 2]) from
               its slope moments up to the fourth (pf_map.h pyramid), g = PF_SPECAA_GAIN_GGX /
               _BECKMANN
   GAIN. The same error for g on a grid (the table "gain"): the default g is the grid's best
   mean over the whole corpus (both alpha0), measured here. The table "spread estimators"
   gives other spreads v in alpha'^2 = alpha0^2 + 2 g v, each at its own best g.

   CORPUS. The seven kinds of tests/reference/pf_microsurface.h (512 x 512, quick 256), the
   normals from its central-difference slopes; levels 1-6 (2 to 64 texels on a side); alpha0
   in {0.05, 0.2}; 8 mip texels per level up to 16 x 16, 4 above (seeded; quick: 4 and 2).

   OUTPUT (--out DIR, default bench/out): specaa_bakers.csv (kind, ndf, alpha0, level, baker,
   mean and max error, texels), specaa_scenes.csv (the curved scenes, bench/specaa_scenes.h),
   specaa.md (the tables; docs/specaa.md's generated block). BENCH_QUICK=1 or --quick: the smoke
   run (256 x 256, a 32 x 32 slope grid, fewer texels; scenes 8 x 8 rays, 6 frames, 16 and
   24 px). --scenes-only: the curved scenes alone.
   THE USER'S MAP (--map PATH and pf_maps.h's --map-NAME VALUE options, what `make bench MAP=`
   runs through bench/map.sh): the corpus is replaced by that map (its slopes as
   tests/reference/pf_maps.h makes them), the same tables for the one kind "map", no scenes.
   Usage: specaa [--quick] [--out DIR] [--scenes-only] [--map PATH [--map-NAME VALUE ...]].
   PFB_THREADS as every bench program. */
#include "pf_bench_base.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include "pf_parallel.h"

#include "pf_specaa.h"
#include "pf_toksvig.h"
#include "pf_microsurface.h"
#include "pf_maps.h"

#define NKIND PFM_KIND_COUNT
#define NLEVEL 6
#define NALPHA 2
#define NNDF 2
static const double alpha0s[NALPHA] = { 0.05, 0.2 };
static const char *ndf_name[NNDF] = { "ggx", "beckmann" };

enum { B_NAIVE, B_TOKSVIG, B_FILAMENT, B_HDRP, B_GODOT, B_LIB, B_ORACLE, NBAKER };
static const char *baker_name[NBAKER] = { "naive", "toksvig", "filament", "hdrp", "godot", "library", "oracle" };
static const double gains[] = { 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.6, 2.0 };
#define NGAIN ((int)(sizeof gains / sizeof gains[0]))

static int N = 512, G = 64, npos_small = 8, npos_large = 4;
/* the user's map (--map): one kind, "map", in slot 0 */
static int nkinds = NKIND;
static const char *map_path;
static const char *kname(int k) { return map_path ? "map" : pfm_kind_name(k); }

typedef struct kind_data {
    double *slope;    /* N*N*2 */
    pf_real *normals; /* N*N*3 (library input) */
    pf_real *alpha[NNDF][NALPHA]; /* the library's baked pyramid */
    double *navg;     /* normal pyramid, N*N*4/3 *3 (double, own box means) */
} kind_data;
static kind_data K[NKIND];

typedef struct item {
    int kind, ndf, ai, level, px, py;
} item;
static item *items;
static long long nitems;
/* results per item: error per baker, and per gain */
static double *err_b;  /* nitems * NBAKER */
static double *err_g;  /* nitems * NGAIN */
#define NVAR 7
static double *err_v;  /* nitems * NVAR * NGAIN: variance estimators (experiment) */

static double p22(int ndf, double sx, double sy, double a)
{
    double q = (sx * sx + sy * sy) / (a * a);
    if (ndf == 0) return 1.0 / (3.14159265358979323846 * a * a * (1.0 + q) * (1.0 + q));
    return exp(-q) / (3.14159265358979323846 * a * a);
}

static double kappa_of(double r)
{
    if (!(r < 1.0)) return INFINITY;
    return r * (3.0 - r * r) / ((1.0 - r) * (1.0 + r));
}

typedef struct grid_ctx {
    const double *pref;
    double cx, cy, x0, h, ref_norm;
    int ndf;
} grid_ctx;

static double lobe_err(const grid_ctx *g, double a)
{
    double s = 0.0;
    int i, j;
    if (!(a > 1e-6)) a = 1e-6;
    for (j = 0; j < G; ++j)
        for (i = 0; i < G; ++i) {
            double x = g->x0 + (i + 0.5) * g->h, y = g->x0 + (j + 0.5) * g->h;
            double d = p22(g->ndf, x, y, a) - g->pref[j * G + i];
            s += d * d;
        }
    return sqrt(s) / g->ref_norm;
}

static void run_item(void *ctx, long long it)
{
    const item *I = &items[it];
    const kind_data *D = &K[I->kind];
    int n = 1 << I->level, x, y, i, j, b;
    double a0 = alpha0s[I->ai];
    double mx = 0, my = 0, mxx = 0, myy = 0, nx = 0, ny = 0, nz = 0, pxx = 0, rho = 1, var, r, cx, cy, W, kap;
    double *pref = (double *)malloc(sizeof(double) * (size_t)G * (size_t)G);
    double *ts = (double *)malloc(sizeof(double) * 2 * (size_t)n * (size_t)n);
    grid_ctx g;
    double alpha[NBAKER];
    (void)ctx;
    if (!pref || !ts) { fprintf(stderr, "specaa: out of memory\n"); exit(1); }
    for (y = 0; y < n; ++y)
        for (x = 0; x < n; ++x) {
            long long t = (long long)(I->py * n + y) * N + (I->px * n + x);
            double sx = D->slope[2 * t], sy = D->slope[2 * t + 1], l = 1.0 / sqrt(1.0 + sx * sx + sy * sy);
            ts[2 * (y * n + x)] = sx;
            ts[2 * (y * n + x) + 1] = sy;
            mx += sx; my += sy; mxx += sx * sx; myy += sy * sy;
            nx += -sx * l; ny += -sy * l; nz += l;
            pxx += sx * sx * l * l + sy * sy * l * l;
        }
    mx /= n * n; my /= n * n; mxx /= n * n; myy /= n * n;
    nx /= n * n; ny /= n * n; nz /= n * n;
    var = 0.5 * ((mxx - mx * mx) + (myy - my * my));
    if (var < 0) var = 0;
    {   /* the library's peakedness-corrected spread, in double (the bench's own computation) */
        double m4c = 0;
        int t;
        for (t = 0; t < n * n; ++t) {
            double dx = ts[2 * t] - mx, dy = ts[2 * t + 1] - my, q = dx * dx + dy * dy;
            m4c += q * q;
        }
        m4c /= n * n;
        rho = m4c > 0 ? fmin(8.0 * var * var / m4c, 2.0) : 1.0;
    }
    r = sqrt(nx * nx + ny * ny + nz * nz);
    cx = -nx / nz;
    cy = -ny / nz;
    W = 4.0 * sqrt(a0 * a0 + 2.0 * var) + sqrt((mx - cx) * (mx - cx) + (my - cy) * (my - cy));
    g.h = 2.0 * W / G;
    g.x0 = -W;
    g.ndf = I->ndf;
    g.pref = pref;
    g.ref_norm = 0.0;
    for (j = 0; j < G; ++j)
        for (i = 0; i < G; ++i) {
            double px = cx + g.x0 + (i + 0.5) * g.h, py = cy + g.x0 + (j + 0.5) * g.h, s = 0.0;
            int t;
            for (t = 0; t < n * n; ++t) s += p22(I->ndf, px - ts[2 * t], py - ts[2 * t + 1], a0);
            pref[j * G + i] = s / (n * n);
            g.ref_norm += pref[j * G + i] * pref[j * G + i];
        }
    g.ref_norm = sqrt(g.ref_norm);
    kap = kappa_of(r);
    alpha[B_NAIVE] = a0;
    alpha[B_TOKSVIG] = (double)pf_toksvig_ggx_alpha((pf_real)a0, pf_toksvig_variance((pf_real)r));
    /* Filament's roughness-prefilter tool: sqrt(r^2 + min(2 x 0.25/kappa, 0.2^2)) on the roughness it
       stores, which Filament reads as perceptual roughness (alpha = r^2): alpha' = alpha + min(0.5/kappa, 0.04) */
    alpha[B_FILAMENT] = a0 + (isinf(kap) ? 0.0 : fmin(0.5 / kap, 0.04));
    /* HDRP: min(2 min(0.25/kappa, 0.03125), 0.2^2) on alpha^2; the encoder's cap 0.03125 never binds under 0.2^2 */
    alpha[B_HDRP] = sqrt(a0 * a0 + (isinf(kap) ? 0.0 : fmin(0.5 / kap, 0.04)));
    /* Godot adds to the PERCEPTUAL roughness squared, which is alpha (alpha_ggx = roughness^2) */
    alpha[B_GODOT] = a0 + (isinf(kap) ? 0.0 : fmin(0.75 / kap, 0.16));
    {
        long long off = pf_mip_level_offset(N, N, I->level);
        int lw = pf_mip_level_size(N, I->level);
        alpha[B_LIB] = (double)D->alpha[I->ndf][I->ai][off + (long long)I->py * lw + I->px];
    }
    {   /* oracle: golden section on log alpha */
        double lo = log(a0 * 0.5), hi = log(3.0), gr = 0.6180339887498949;
        double c1 = hi - gr * (hi - lo), c2 = lo + gr * (hi - lo);
        double f1 = lobe_err(&g, exp(c1)), f2 = lobe_err(&g, exp(c2));
        int k;
        for (k = 0; k < 48; ++k) {
            if (f1 < f2) { hi = c2; c2 = c1; f2 = f1; c1 = hi - gr * (hi - lo); f1 = lobe_err(&g, exp(c1)); }
            else { lo = c1; c1 = c2; f1 = f2; c2 = lo + gr * (hi - lo); f2 = lobe_err(&g, exp(c2)); }
        }
        alpha[B_ORACLE] = exp(0.5 * (lo + hi));
    }
    for (b = 0; b < NBAKER; ++b) err_b[it * NBAKER + b] = lobe_err(&g, alpha[b]);
    for (b = 0; b < NGAIN; ++b) {
        double e2 = a0 * a0 + 2.0 * gains[b] * var * rho;
        err_g[it * NGAIN + b] = lobe_err(&g, sqrt(e2));
    }
    {

        double vp = 0.5 * (pxx / (n * n) - nx * nx - ny * ny), vs;
        if (vp < 0) vp = 0;
        if (vp > 0.2499) vp = 0.2499;
        vs = vp / (1.0 - 4.0 * vp);
        for (b = 0; b < NGAIN; ++b) {
            double tv = r < 1.0 ? (1.0 - r) / r : 0.0, kv = isinf(kap) ? 0.0 : 1.0 / kap;
            err_v[(it * NVAR + 0) * NGAIN + b] = lobe_err(&g, sqrt(a0 * a0 + 2.0 * gains[b] * var * rho));
            err_v[(it * NVAR + 5) * NGAIN + b] = lobe_err(&g, sqrt(a0 * a0 + 2.0 * gains[b] * var));
            err_v[(it * NVAR + 6) * NGAIN + b] = lobe_err(&g, sqrt(a0 * a0 + 2.0 * gains[b] * var * sqrt(rho)));
            err_v[(it * NVAR + 1) * NGAIN + b] = lobe_err(&g, sqrt(a0 * a0 + 2.0 * gains[b] * tv));
            err_v[(it * NVAR + 2) * NGAIN + b] = lobe_err(&g, sqrt(a0 * a0 + 2.0 * gains[b] * kv));
            err_v[(it * NVAR + 3) * NGAIN + b] = lobe_err(&g, sqrt(a0 * a0 + 2.0 * gains[b] * sqrt(var * tv)));
            err_v[(it * NVAR + 4) * NGAIN + b] = lobe_err(&g, sqrt(a0 * a0 + 2.0 * gains[b] * vs));
        }
    }
    free(pref);
    free(ts);
}

#include "specaa_scenes.h"

int main(int argc, char **argv)
{
    const char *outdir = "bench/out";
    int quick = 0, scenes_only = 0, k, a, d, l, i;
    pfmap_options map_opt = pfmap_options_default();
    pfm_surface map_surf;
    pfmap_info map_info;
    char err[512];
    char path[1024];
    FILE *f;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--quick")) quick = 1;
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) outdir = argv[++i];
        else if (!strcmp(argv[i], "--scenes-only") || !strcmp(argv[i], "--sphere-only")) scenes_only = 1;
        else if (!strcmp(argv[i], "--map") && i + 1 < argc) map_path = argv[++i];
        else if (!strncmp(argv[i], "--map-", 6) && i + 1 < argc) {
            const char *o = argv[i] + 6, *v = argv[++i];
            if (pfmap_parse_option(o, v, &map_opt, err, sizeof err) != 0) { fprintf(stderr, "specaa: %s\n", err); return 2; }
        } else {
            fprintf(stderr, "usage: specaa [--quick] [--out DIR] [--scenes-only] [--map PATH [--map-NAME VALUE ...]]\n");
            return 2;
        }
    }
    if (!quick) { const char *q = getenv("BENCH_QUICK"); quick = q && *q && strcmp(q, "0"); }
    if (quick) { N = 256; G = 32; npos_small = 4; npos_large = 2; }
    if (map_path) {   /* the user's map replaces the corpus; loaded and checked before anything is written */
        if (pfmap_load(map_path, &map_opt, &map_surf, &map_info, err, sizeof err) != 0) { fprintf(stderr, "specaa: %s\n", err); return 1; }
        if (map_surf.w < 64) {
            fprintf(stderr, "specaa: %s: the kept square is %d x %d texels; footprints up to 64 x 64 need at least 64 x 64\n",
                    map_path, map_surf.w, map_surf.h);
            return 1;
        }
        nkinds = 1;
        N = map_surf.w;
    }
    if (scenes_only) goto scenes;
    /* the corpus: normals and the library's baked pyramids */
    for (k = 0; k < nkinds; ++k) {
        pfm_surface s;
        long long t, nt = pf_mip_texel_count(N, N);
        pf_real *scratch = (pf_real *)malloc(sizeof(pf_real) * (size_t)pf_specaa_bake_scratch_reals(N, N));
        if (map_path) s = map_surf;
        else if (pfm_surface_make(&s, N, N, 1.0, pfm_params_default(k)) != 0) { fprintf(stderr, "specaa: surface\n"); return 1; }
        if (!scratch) { fprintf(stderr, "specaa: out of memory\n"); return 1; }
        K[k].slope = (double *)malloc(sizeof(double) * 2 * (size_t)N * N);
        K[k].normals = (pf_real *)malloc(sizeof(pf_real) * 3 * (size_t)N * N);
        if (!K[k].slope || !K[k].normals) return 1;
        for (t = 0; t < (long long)N * N; ++t) {
            double sx, sy, m[3];
            pfm_slope(&s, (int)(t % N), (int)(t / N), &sx, &sy);
            pfm_normal(&s, (int)(t % N), (int)(t / N), m);
            K[k].slope[2 * t] = sx; K[k].slope[2 * t + 1] = sy;
            K[k].normals[3 * t] = (pf_real)m[0]; K[k].normals[3 * t + 1] = (pf_real)m[1]; K[k].normals[3 * t + 2] = (pf_real)m[2];
        }
        for (d = 0; d < NNDF; ++d)
            for (a = 0; a < NALPHA; ++a) {
                pf_specaa_bake_desc desc;
                memset(&desc, 0, sizeof desc);
                desc.normals = K[k].normals;
                desc.width = N; desc.height = N;
                desc.alpha = (pf_real)alpha0s[a];
                desc.ndf = d == 0 ? PF_SPECAA_NDF_GGX : PF_SPECAA_NDF_BECKMANN;
                K[k].alpha[d][a] = (pf_real *)malloc(sizeof(pf_real) * (size_t)nt);
                if (!K[k].alpha[d][a] || pf_specaa_bake(&desc, scratch, K[k].alpha[d][a], NULL) != PF_OK) {
                    fprintf(stderr, "specaa: bake failed\n");
                    return 1;
                }
            }
        free(scratch);
        pfm_surface_free(&s);
    }
    /* the work items */
    nitems = 0;
    for (l = 1; l <= NLEVEL; ++l) nitems += (long long)nkinds * NNDF * NALPHA * (l <= 4 ? npos_small : npos_large);
    items = (item *)malloc(sizeof(item) * (size_t)nitems);
    err_b = (double *)malloc(sizeof(double) * (size_t)nitems * NBAKER);
    err_g = (double *)malloc(sizeof(double) * (size_t)nitems * NGAIN);
    err_v = (double *)malloc(sizeof(double) * (size_t)nitems * NVAR * NGAIN);
    if (!items || !err_b || !err_g) return 1;
    {
        long long n = 0;
        pfm_rng rng;
        rng.state = 0x5eca5eca5ecaULL;
        for (l = NLEVEL; l >= 1; --l) /* largest first: the parallel loop ends evenly */
            for (k = 0; k < nkinds; ++k)
                for (d = 0; d < NNDF; ++d)
                    for (a = 0; a < NALPHA; ++a) {
                        int p, np = l <= 4 ? npos_small : npos_large, lw = N >> l;
                        for (p = 0; p < np; ++p) {
                            item *I = &items[n++];
                            I->kind = k; I->ndf = d; I->ai = a; I->level = l;
                            I->px = (int)(pfm_rng_uniform(&rng) * lw);
                            I->py = (int)(pfm_rng_uniform(&rng) * lw);
                        }
                    }
    }
    pfb_parallel_for(nitems, run_item, NULL, "specaa: footprint NDFs");

    /* CSV: per kind, ndf, alpha0, level, baker */
    snprintf(path, sizeof path, "%s/specaa_bakers.csv", outdir);
    f = fopen(path, "w");
    if (!f) { fprintf(stderr, "specaa: cannot write %s\n", path); return 1; }
    fprintf(f, "kind,ndf,alpha0,level,texels,baker,mean_err,max_err,footprints\n");
    for (k = 0; k < nkinds; ++k)
        for (d = 0; d < NNDF; ++d)
            for (a = 0; a < NALPHA; ++a)
                for (l = 1; l <= NLEVEL; ++l) {
                    int b;
                    for (b = 0; b < NBAKER + NGAIN; ++b) {
                        double s = 0, mx = 0;
                        int c = 0;
                        long long it;
                        for (it = 0; it < nitems; ++it) {
                            const item *I = &items[it];
                            double e;
                            if (I->kind != k || I->ndf != d || I->ai != a || I->level != l) continue;
                            e = b < NBAKER ? err_b[it * NBAKER + b] : err_g[it * NGAIN + b - NBAKER];
                            s += e; if (e > mx) mx = e; ++c;
                        }
                        if (b < NBAKER)
                            fprintf(f, "%s,%s,%g,%d,%d,%s,%.5g,%.5g,%d\n", kname(k), ndf_name[d], alpha0s[a], l, 1 << (2 * l),
                                    baker_name[b], s / c, mx, c);
                        else
                            fprintf(f, "%s,%s,%g,%d,%d,gain_%g,%.5g,%.5g,%d\n", kname(k), ndf_name[d], alpha0s[a], l,
                                    1 << (2 * l), gains[b - NBAKER], s / c, mx, c);
                    }
                }
    fclose(f);

    /* the fragment */
    snprintf(path, sizeof path, "%s/specaa.md", outdir);
    f = fopen(path, "w");
    if (!f) { fprintf(stderr, "specaa: cannot write %s\n", path); return 1; }
    fprintf(f, "## Specular antialiasing: roughness bakers%s\n\n", map_path ? " on this map" : " and the curved scenes (pf_specaa.h)");
    if (map_path) fprintf(f, "The user's map `%s` (%s, the kept %dx%d square): its mip texels baked by every baker below. ", map_path,
                          pfmap_kind_name(map_opt.kind), N, N);
    fprintf(f, "Measured by `bench/specaa.c`%s: %dx%d texels of %s, mip levels 1-%d (footprints of 4 to %d texels), "
               "alpha0 in {0.05, 0.2}, %d + %d mip texels per level (small, large), slope grid %dx%d. Error: relative L2 distance "
               "between the baked lobe (centred on the averaged normal) and the exact NDF of the footprint's texels, mean over "
               "levels, alpha0 and texels. **bold**: the best formula of the row (the oracle excepted).\n\n",
            quick ? " (BENCH_QUICK: smoke run, not for publication)" : "", N, N, map_path ? "the user's map" : "the microsurface corpus", NLEVEL, 1 << (2 * NLEVEL), npos_small,
            npos_large, G, G);
    for (d = 0; d < NNDF; ++d) {
        int b, wins = 0;
        fprintf(f, "#### %s\n\n| kind |", d == 0 ? "GGX" : "Beckmann");
        for (b = 0; b < NBAKER; ++b) fprintf(f, " %s |", baker_name[b]);
        fprintf(f, " library best? |\n| --- |");
        for (b = 0; b < NBAKER; ++b) fprintf(f, " ---: |");
        fprintf(f, " --- |\n");
        for (k = 0; k < nkinds; ++k) {
            double m[NBAKER], best = 1e300;
            int bb = 0;
            for (b = 0; b < NBAKER; ++b) {
                double s = 0;
                int c = 0;
                long long it;
                for (it = 0; it < nitems; ++it)
                    if (items[it].kind == k && items[it].ndf == d) { s += err_b[it * NBAKER + b]; ++c; }
                m[b] = s / c;
                if (b != B_ORACLE && m[b] < best) { best = m[b]; bb = b; }
            }
            fprintf(f, "| %s |", kname(k));
            for (b = 0; b < NBAKER; ++b) fprintf(f, b == bb ? " **%.4f** |" : " %.4f |", m[b]);
            fprintf(f, " %s |\n", bb == B_LIB ? "yes" : "no");
            wins += bb == B_LIB;
        }
        fprintf(f, "\nThe library's baker is the most accurate formula on %d of %d kinds (%s).\n\n", wins, nkinds, ndf_name[d]);
    }
    fprintf(f, "#### Gain g of the library's baker (mean error over the corpus)\n\n| g |");
    for (i = 0; i < NGAIN; ++i) fprintf(f, " %g |", gains[i]);
    fprintf(f, "\n| --- |");
    for (i = 0; i < NGAIN; ++i) fprintf(f, " ---: |");
    fprintf(f, "\n");
    for (d = 0; d < NNDF; ++d) {
        double best = 1e300;
        int bi = 0;
        double m[NGAIN];
        for (i = 0; i < NGAIN; ++i) {
            double s = 0;
            int c = 0;
            long long it;
            for (it = 0; it < nitems; ++it)
                if (items[it].ndf == d) { s += err_g[it * NGAIN + i]; ++c; }
            m[i] = s / c;
            if (m[i] < best) { best = m[i]; bi = i; }
        }
        fprintf(f, "| %s |", ndf_name[d]);
        for (i = 0; i < NGAIN; ++i) fprintf(f, i == bi ? " **%.4f** |" : " %.4f |", m[i]);
        fprintf(f, "\n");
        fprintf(stderr, "specaa: %s best gain %g (mean err %.4f); default %g\n", ndf_name[d], gains[bi], best,
                d == 0 ? (double)PF_SPECAA_GAIN_GGX : (double)PF_SPECAA_GAIN_BECKMANN);
    }
    fprintf(f, "\nDefaults: PF_SPECAA_GAIN_GGX = %g, PF_SPECAA_GAIN_BECKMANN = %g. Per level, alpha0 and kind: "
               "`bench/out/specaa_bakers.csv`.\n", (double)PF_SPECAA_GAIN_GGX, (double)PF_SPECAA_GAIN_BECKMANN);
    fclose(f);
    {   /* the spread estimators tried, each at its best gain */
        static const char *vname[NVAR] = { "var rho (the library)", "Toksvig (1 - r)/r", "vMF 1/kappa",
                                           "sqrt(var x Toksvig)", "projected variance through (3)",
                                           "var (rho = 1)", "var sqrt(rho)" };
        int v;
        f = fopen(path, "a");
        if (!f) return 1;
        fprintf(f, "\n#### Spread estimators tried (alpha'^2 = alpha0^2 + 2 g v, each at its best g on the grid)\n\n");
        for (d = 0; d < NNDF; ++d) {
            fprintf(f, "%s\n\n| estimator v | best g | mean |", d == 0 ? "GGX" : "Beckmann");
            for (k = 0; k < nkinds; ++k) fprintf(f, " %s |", kname(k));
            fprintf(f, "\n| --- | ---: | ---: |");
            for (k = 0; k < nkinds; ++k) fprintf(f, " ---: |");
            fprintf(f, "\n");
            for (v = 0; v < NVAR; ++v) {
                double best = 1e300;
                int bi = 0;
                for (i = 0; i < NGAIN; ++i) {
                    double sm = 0;
                    int c = 0;
                    long long it;
                    for (it = 0; it < nitems; ++it)
                        if (items[it].ndf == d) { sm += err_v[(it * NVAR + v) * NGAIN + i]; ++c; }
                    if (sm / c < best) { best = sm / c; bi = i; }
                }
                fprintf(f, "| %s | %g | %.4f |", vname[v], gains[bi], best);
                for (k = 0; k < nkinds; ++k) {
                    double sm = 0;
                    int c = 0;
                    long long it;
                    for (it = 0; it < nitems; ++it)
                        if (items[it].ndf == d && items[it].kind == k) { sm += err_v[(it * NVAR + v) * NGAIN + bi]; ++c; }
                    fprintf(f, " %.4f |", sm / c);
                }
                fprintf(f, "\n");
            }
            fprintf(f, "\n");
        }
        fclose(f);
    }
    if (map_path) goto done; /* the curved scenes have their own map */
    /* ---- the curved scenes (specaa_scenes.h) */
scenes:
    if (scenes_only) { snprintf(path, sizeof path, "%s/specaa.md", outdir); f = fopen(path, "w"); if (f) fclose(f); }
    {   /* the curved, normal-mapped scenes (specaa_scenes.h) */
        FILE *md, *c;
        snprintf(path, sizeof path, "%s/specaa.md", outdir);
        md = fopen(path, "a");
        snprintf(path, sizeof path, "%s/specaa_scenes.csv", outdir);
        c = fopen(path, "w");
        if (!c || !md) { fprintf(stderr, "specaa: cannot write the scene tables\n"); return 1; }
        sc_bench(quick, md, c);
        fclose(c);
        fclose(md);
    }
done:
    fprintf(stderr, "specaa: wrote %s/specaa.md and specaa_bakers.csv\n", outdir);
    return 0;
}

/* bench/microsurface.c - ground truth on synthetic microsurfaces (issue 9, items 2 and 3).

   The library's filtered answers, computed from mip pyramids of moments exactly as a renderer
   would fetch them, against a brute-force reference that shades the same pixel footprint
   texel by texel on an actual height field (tests/reference/pf_microsurface.h: micro-normals from the
   heights, masking and shadowing by marching the height field, a narrow Beckmann base lobe
   or a Lambertian one, the projected-area normalization of LEADR eqs. 1-3).

   TWO REFERENCES. "full": the march sees every occluder of the (periodic) height field.
   "in_footprint": only the occluders inside the footprint's box count (pfm_visibility_map_box:
   a ray that leaves the n x n box is visible). At footprints smaller than the features most
   shadows and masking are cast by bumps OUTSIDE the footprint, which no filtered model of the
   footprint's own statistics can know (LEADR takes them from the displaced geometry and shadow
   maps); the in-footprint reference is what a filtered model can represent (its error is the
   model's), the full one what a renderer without resolved geometry would show.

   CORPUS. The seven kinds of pfm_params_default: Gaussian isotropic (12-texel correlation
   length), fine Gaussian (3 texels: footprints of 256-4096 texels hold ~9-145 correlation
   areas pi L^2, the papers' regime), anisotropic Gaussian, peaked (log-normal bumps: slope
   kurtosis ~5, the photographed-texture regime), ridges, craters, tiles; 512 x 512 texels of
   size 1, periodic.
   THE USER'S MAP (--map PATH, what `make bench MAP=...` runs): the corpus is replaced by one
   height or normal map loaded by tests/reference/pf_maps.h (its header has the formats, the crop, the
   borders, the scale and the integration of normal maps), the kind "map" in the CSV; the same
   footprints, views, lights, tasks, methods and error measures; the cost section on that map;
   the fragment (microsurface.md) describes the map and its slope statistics (RMS, skewness,
   kurtosis, anisotropy, correlation length). The map is loaded and checked before anything is
   written: a bad map stops the program with one message and exit status 1, no output.
   FOOTPRINTS. n x n texels, n = 1, 2, 4, ..., 64 (1 to 4096 texels), aligned on the n-grid so
   that the footprint is exactly one texel of pyramid level log2(n) (a box filter: what a
   mip level holds). All positions where there are at most maxpos of them, otherwise a seeded
   subset of maxpos (maxpos = 256 up to 16 x 16 texels, 64 above; quick mode 64 and 16).
   DIRECTIONS. Views theta_o in {0, 15, 30, 45, 60, 70, 75, 80, 85} degrees at a few azimuths;
   lights: a seeded set over the upper hemisphere (theta_i <= 85 degrees) plus, per footprint,
   the mirror direction of the view about the footprint's mesonormal (the specular peak).
   Full visibility maps (one per direction) are cached and shared by every footprint; the
   mirror light differs per footprint, so its visibility is marched for the footprint's texels
   only; the in-footprint maps are per footprint (only the texels the full map occludes are
   re-marched: the box only removes occluders), those toward the lights marched once per
   footprint and shared by every view that shades it.

   TASKS AND METHODS (each method from the pyramids only: what a shader can fetch)
     masking   reference: the visible fraction of the footprint's front-facing projected
               micro-area, sum V_o a_t(wo)+ / sum a_t(wo)+ (pfm_shade.masking; comparable with
               Smith's G1 = 1/(1 + Lambda_o)). smith_g1_exact = pf_beckmann_g1 on the
               footprint's slope stats, smith_g1_fast = pf_g1_beckmann_fast(pf_smith_nu),
               smith_g1_walter = pf_g1_beckmann_walter(pf_smith_nu), no_masking = 1.
               horizon_masking_n16, horizon_masking_n32 = pf_horizon_masking (pf_horizon.h:
               Smith's G1 times the visible projected area of the footprint's horizon
               distribution) from an HDF-moment pyramid of n = 16 resp. 32 azimuths built per
               kind by pf_horizon_pyramid (march HOR_STEPS texels, periodic; build time per kind
               on stderr), the two stored azimuths around wo's fetched (6 channels) and mixed
               by pf_hdf_moments_lerp; they see occluders outside the footprint, so the full
               reference is theirs (docs/horizon.md: n = 32 meets 0.05 at 16 texels).
               horizon_masking_lod_n32 = pf_horizon_masking_lod from the n = 32 pyramid: the
               horizon term faded to Smith by mip level, whole up to level HOR_LOD_FULL (16
               texels), none from HOR_LOD_SMITH (4096 texels) on.
     specular  reference: narrow Beckmann base lobe (deviation BASE_SIGMA) per texel, Smith
               G2 of that lobe, V_o V_i by marching, f0 = 1. leadr_joint = pf_leadr_specular,
               leadr_masking = pf_leadr_specular_masking (base variance BASE_SIGMA^2 added by
               pf_slope_moments_stats), lean = P22 at the half vector's slope (no masking, no
               Jacobian, no projected area: bench_beckmann.c's lean_lobe), toksvig = Beckmann
               Cook-Torrance lobe (height-correlated Smith G2) around the normalized average
               normal with roughness pf_toksvig_beckmann_m(sqrt(2) BASE_SIGMA, Toksvig
               variance), times max(0, n.wi) (the engine form), naive_mip_normal = the same
               lobe with the base roughness only. vmf_m1, vmf_m2, vmf_m4, vmf_m8 = the multi-lobe
               BRDF of pf_vmf.h (Wu et al. 2019 eqs. 4-5): m vMF lobes per texel of a lobe
               pyramid fitted by EM from the finest normals of each texel's footprint
               (pf_vmf_pyramid_from_normals, VMF_ITER iterations at most; the fit time per kind
               is printed on stderr), fetched as m RGBA texels, each lobe's Beckmann lobe in
               slope space with BASE_SIGMA^2 added, Smith G of the mixture's slope mean and
               covariance (pf_vmf_sum_specular); vmf_m4_mix_smith, vmf_m8_mix_smith = the same
               with the mixture's exact Smith Lambda (pf_vmf_sum_specular_mixture); vmf_m16 =
               16 lobes (issue 15's gaussian target). vmf_m4_scaled, vmf_m8_scaled = vmf_m4,
               vmf_m8 times the scaling function T(x) S(wi, wo) of Wu et al. 2019 (eqs. 12-14,
               sec. 6) at 4096-texel footprints (the unscaled lobes below), S per kind fitted
               to the IN-FOOTPRINT effective BRDF (pf_vmf_scale_fit_level, a prior toward 1),
               T per pyramid texel (pf_vmf_scale_texel_t; see "scaling function"
               below); vmf_m8_scaled_s = S alone (T = 1). Each of these shades through
               pf_vmf_lobe_make + pf_vmf_sum_add (the exact tangent variance); its twin
               <name>_texel shades the same texels through the shader path bench/gpu/ prices
               (pf_vmf_pixel_make, pf_vmf_sum_add_texel or _texel_mixture: the rational
               tangent variance), the scaled twins with the same T and S.
               Grazing views (issue 28, item 2): leadr_base = pf_leadr_specular_base (LEADR
               times pf_beckmann_base_masking: the base lobe's own masking-shadowing averaged
               over the reflecting texels' slopes, which eq. 17's one Smith G of the summed
               Gaussian misses; bench/grazing_diag.c has the factor-by-factor diagnosis);
               vmf_m16_base = vmf_m16 with each lobe's NDF term times that factor for the
               lobe's own slope statistics (pf_vmf_lobe_slope_stats), vmf_m16_base_fp = vmf_m16
               times one factor of the footprint's slope moments (fetched), vmf_m16_base_sum =
               vmf_m16 times one factor of the mixture's own moments (pf_vmf_sum_stats;
               pf_vmf_sum_specular_base); in all three Smith's G of the mixture reads its
               moments without base_var (pf_vmf_sum_without_base), as pf_leadr_specular_base's
               G, so the base lobe's masking is counted once.
     diffuse   reference: Lambertian micro-BRDF, albedo 1, V_o V_i. leadr_gg_* =
               pf_gg_diffuse_directional on the footprint's slope stats (LEADR eq. 21, node
               set and N in the name), lambert_mesonormal = max(0, nbar.wi)/pi,
               lambert_macro = max(0, wi.z)/pi. leadr_gg_matched3_horizon_n32 = leadr_gg_matched3
               times pf_horizon_visible_area toward wo (as pf_horizon_masking multiplies Smith)
               and toward wi (capped at 1), n = 32: our combination, not a formula of the
               module or the papers. horizon_diffuse_n32 = pf_horizon_diffuse_directional
               (pf_horizon.h): the same matched 3 x 3 grid with Smith's factor replaced by each
               facet's horizon visibility toward wo and wi (the HDF conditioned on the facet's
               slope, n = 32, two azimuths fetched per direction) joined by Tan et al.'s eq. 28;
               horizon_diffuse_lod_n32 = pf_horizon_diffuse_lod, that faded to
               leadr_gg_matched3 by mip level (HOR_LOD_FULL .. HOR_LOD_SMITH).
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
   Each method is one row of the registry (`methods`, below: its tasks, name, evaluator, what a
   shader fetches for it, oracle or not) and one evaluator function (fetch + evaluation), the
   same code the cost section times; adding a method is a row and a function.
   ERROR. Per cell (kind, reference, task, method, footprint size, view angle) over its lights,
   azimuths and positions: rel_l2 = sqrt(sum_sq_err / sum_sq_ref), sum_sq_err = sum (f - ref)^2,
   sum_sq_ref = sum ref^2 (both in the CSV, so cells pool: sqrt(sum sum_sq_err / sum
   sum_sq_ref)), and max_rel = max |f - ref|/ref over the samples with ref >= 10% of the cell's
   largest ref. Footprint-views whose mesosurface projected area A = (nbar.wo)/(nbar.z) is
   below CULL_AREA = 1/4 of a flat footprint's (wo.z) are skipped: at or below the mesosurface
   a renderer culls them, and near edge-on the normalization by A of LEADR eqs. 2-3 breaks for
   an n x n footprint (its visible projected micro-area reaches ~30 A, so the reference
   radiance ~1/A is meaningless; a renderer gives such a footprint a share ~A of a pixel);
   the fragment reports how many. Colour samples with nothing visible and lit (full
   reference) are skipped for both references.
   COST (item 3). Gaussian kind, view 60 deg, seeded footprints and lights: ns per footprint of
   every method of the error CSV (oracles excepted; pyramid fetches included, the ones each
   method needs; colour methods with the 6-knot banded map) and of the brute force (march the
   footprint's visibility toward view and light, full or in-footprint, then shade; the shading
   sum alone with cached visibility maps; the same in the library's float arithmetic), medians
   over repetitions.
   EVERY CORE (bench/pf_parallel.h; PFB_THREADS=N threads, default every core): per kind, the
   lobe fits (one item per lobe count) with the horizon pyramid, the scaling function's patches,
   the full visibility maps, the in-footprint maps toward the lights and the footprints (runs of
   about FP_ITEM_TEXELS texels) are parallel work items; random numbers are drawn before, in the
   serial order, each item writes only its own outputs, and the reductions run in item order (the
   serial loop's), so every CSV is the same for any thread count, bit for bit. The cost section's
   timing loop runs alone on one thread, after every parallel step. Steps that run longer than
   2 s print progress with an estimate of the time left on stderr. MICROSURFACE_CHECK=1 compares
   the shortcuts (patches sampled in parallel, the n = 16 horizon pyramid read from the n = 32
   one, in float32 and in the storage formats, and every method's value with what its sample's
   methods share (mmemo) against the method alone) with the serial calls they replace, bit for
   bit.

   OUTPUT (directory --out, default bench/out): microsurface_errors.csv, microsurface_cost.csv,
   microsurface.md (report fragment), microsurface_*.svg (gnuplot, bench/microsurface.gp; the
   .dat files it reads are deleted afterwards).
   Usage: microsurface [--quick] [--out DIR] [--gp FILE] [--no-charts] [--kinds K1,K2,..]
   [--no-cost]; BENCH_QUICK=1 in the environment also selects the quick mode (smaller map, fewer
   views, lights, positions). --kinds runs a subset of the corpus (names as in the CSV, e.g.
   --kinds gaussian,tiles) and writes only microsurface_errors.csv (plus microsurface_cost.csv
   when gaussian is among them and --no-cost is not given) and a summary of the specular task
   at 4096 texels on stdout: a cheap way to measure a change on the kinds it concerns. */
#include "pf_bench_base.h" /* first: _POSIX_C_SOURCE; the rng, the clock, checked allocation */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include "pf_parallel.h"

#include "pf_beckmann.h"
#include "pf_moments.h"
#include "pf_toksvig.h"
#include "pf_gaussgrid.h"
#include "pf_height.h"
#include "pf_vmf.h"
#include "pf_horizon.h"
#include "pf_microsurface.h"
#include "pf_hist_oracle.h" /* the exact-histogram oracle, shared with bench/frame/frame.c */
#include "pf_maps.h"
#include "vmf_scaling.h"

#define BASE_SIGMA 0.1 /* deviation of the base lobe's slopes (reference and library) */
#define F0 1.0         /* Fresnel off: the reference's F is 1 */
#define NSIZE 7        /* n = 1 .. 64 */
#define NVIEW 9
#define NTASK 5
#define MAX_TASK_METHODS 40 /* methods of one task at most (the registry is checked against it) */
#define NKIND PFM_KIND_COUNT
#define KIND_MAP NKIND /* the user's map (--map): one more slot in the per-kind arrays */
#define NREF 2         /* the full and the in-footprint reference */
#define CULL_AREA 0.25 /* samples with a mesosurface projected area below this share of a flat
                          footprint's (wo.z) are skipped (near edge-on; see run_kind) */
#define DEG (3.14159265358979323846 / 180.0)
#define POOL_VIEW_HI 6 /* pooled view range of tables and size charts: 0 .. 75 degrees */
#define FP_ITEM_TEXELS 4096 /* footprint texels per parallel work item (at least one footprint) */

enum { T_MASK, T_SPEC, T_DIFF, T_RAMP, T_BANDS };
enum { R_FULL, R_BOX };
static const char *ref_name[NREF] = { "full", "in_footprint" };
/* display order of the kinds: the two isotropic Gaussian kinds first */
static const int kind_order[NKIND] = { PFM_GAUSSIAN, PFM_GAUSSIAN_FINE, PFM_GAUSSIAN_ANISO, PFM_PEAKED,
                                       PFM_RIDGES, PFM_CRATERS, PFM_TILES };
/* the user's map (--map), loaded before anything is written */
static pfm_surface map_surf;
static pfmap_info map_info;
static pfmap_options map_opt;
static pfmap_stats map_stats;
static const char *map_path = NULL;
static const char *kname(int kind) { return kind == KIND_MAP ? "map" : pfm_kind_name(kind); }

static const double view_deg[NVIEW] = { 0, 15, 30, 45, 60, 70, 75, 80, 85 };
static const char *task_name[NTASK] = { "masking", "specular", "diffuse", "colour_ramp", "colour_bands" };
static const char *task_title[NTASK] = { "Masking G1", "Specular (narrow Beckmann base lobe)",
                                         "Diffuse (Lambertian base)",
                                         "Height-correlated colour, ramp map",
                                         "Height-correlated colour, banded map" };

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

/* ---------------------------------------------------------------- small helpers */
static pf_vec3 v3(const double w[3]) { return pf_vec3_make((pf_real)w[0], (pf_real)w[1], (pf_real)w[2]); }
static void dir_from_angles(double theta, double phi, double w[3])
{
    w[0] = sin(theta) * cos(phi);
    w[1] = sin(theta) * sin(phi);
    w[2] = cos(theta);
}
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
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
/* the multi-lobe specular methods (pf_vmf.h): m lobes per texel, fitted by EM from the finest
   normals of each texel's footprint, VMF_ITER iterations at most; one pyramid per lobe count */
#define NVMF 5
#define VMF_ITER 24
/* the EM iterations of the lobe fits: VMF_ITER, fewer in the quick run (main: its outputs are
   read only by the determinism check and CI's success, so it runs every code path with less
   work) */
static int vmf_iter = VMF_ITER;
enum { V1, V2, V4, V8, V16 }; /* the lobe pyramids, by index into vmf_lobes */
static const int vmf_lobes[NVMF] = { 1, 2, 4, 8, 16 };
/* The scaling function of Wu et al. 2019 (eqs. 12-14, sec. 6; pf_vmf.h "SCALING FUNCTION",
   docs/vmf.md) as methods vmf_m4_scaled, vmf_m8_scaled (T(x) S(wi, wo) times vmf_m4, vmf_m8)
   and vmf_m8_scaled_s (S alone, T = 1), built per kind at the footprint levels from
   sc_min_level to sc_max_level (4096 texels; see there why not below) as the paper builds them
   per map and level; at other levels these methods return the unscaled lobes:
     S per level and m (a 6 x 6 x 5 node table fitted over 16 patches of the level, with a
       prior toward 1) and T per pyramid texel (the patch's own samples given S), as
       bench/vmf_scaling.h's settings say (pf_vmf_scale_fit_level per level, its training
       patches on every core (scale_build), then pf_vmf_scale_texel_t per texel on every
       core); the training patches' T when S is built, every other texel's before the
       footprints that read it are shaded (scale_T_fill: the error run's footprints, then
       the cost section's, before the cost is timed).
   The shader fetches T (one texel of level log2 n) and S (pf_vmf_scale_lookup: 8 nodes,
   trilinear) and multiplies (pf_vmf_scale_apply). */
#define NSCALE 2
static const int scale_pyr[NSCALE] = { V4, V8 };
enum { SC4, SC8 }; /* the scaling functions, by index into scale_pyr */
/* the levels the scaling function is built and applied at: 4096-texel footprints (level 6)
   only; at other levels the scaled methods return the unscaled lobes. Why: with the node
   direction set of pf_vmf_scale_patch, T and S are fitted from samples that often miss a
   patch's highlight; measured on every kind (quick maps, prior 1, in-footprint reference,
   docs/vmf.md), T S helped or was neutral at 4096 texels on all seven kinds, but below it
   made several worse (1024 texels: gaussian_aniso 0.10 -> 0.44, gaussian 0.15 -> 0.21;
   16-256 texels up to 1.4), where the lobes alone are already within 0.002-0.24. */
static int sc_min_level = NSIZE - 1, sc_max_level = NSIZE - 1;
/* the horizon-map masking methods (pf_horizon.h): HDF moment pyramids (E[T], E[T^2], E[S T]
   per azimuth) with hor_n[i] stored azimuths, march bounded to HOR_STEPS texels (docs/horizon.md:
   64 and 128 give the same errors to +-0.001 at n = 16) */
#define NHOR 2
#define HOR_STEPS 64
enum { H16, H32 }; /* the horizon pyramids, by index into hor_n */
/* the lod fade of pf_horizon_masking_lod: the horizon term whole up to level HOR_LOD_FULL
   (16 texels), Smith alone from HOR_LOD_SMITH (4096 texels) on (docs/horizon.md) */
#define HOR_LOD_FULL 2.0
#define HOR_LOD_SMITH 6.0
static const int hor_n[NHOR] = { 16, 32 };
typedef struct lib_maps {
    int w, h;
    pf_real *slope;  /* 5-moment pyramid */
    pf_real *normal; /* average-normal pyramid */
    pf_real *height; /* (E[h], E[h^2]) pyramid, h centered */
    pf_real *attr[2];/* (E[a], E[a^2]) pyramids of the two colour attributes */
    pf_real *vmf[NVMF]; /* vMF lobe pyramids (pf_vmf.h), vmf_lobes[i] lobes per texel */
    double vmf_fit_seconds[NVMF];
    pf_real *hor[NHOR]; /* horizon HDF-moment pyramids (pf_horizon.h), hor_n[i] azimuths */
    pf_real *heights;   /* the centred heights (pf_vmf_scale_patch reads them) */
    pf_real sc_S[NSIZE][NSCALE][VS_CELLS]; /* scaling function: S per level and lobe count */
    pf_real sc_prior[NSIZE][NSCALE];       /* and the prior of T's fit (pf_vmf_scale_t) */
    pf_real *sc_T[NSCALE]; /* T per pyramid texel (NaN: not computed yet) */
    double sc_seconds;     /* S fits and T computations so far */
    long sc_patches;       /* patches whose samples were computed */
    double hor_seconds[NHOR];
    double *attr_d[2]; /* per-texel attributes in double (the reference's) */
    cmap cm[2];
    double mean_h, sd_h;
} lib_maps;

static void fatal(const char *what)
{
    fprintf(stderr, "microsurface: %s\n", what);
    exit(1);
}
/* MICROSURFACE_CHECK=1: the shortcut of this file (the n = 16 horizon pyramid taken from the
   n = 32 one) is compared bit for bit with the serial call it replaces (pf_horizon_pyramid),
   which costs its time again; a difference stops the run */
static int check_on(void)
{
    const char *e = getenv("MICROSURFACE_CHECK");
    return e && *e && strcmp(e, "0") != 0;
}
static int check_mode; /* check_on(), read once by main (the footprints' items read it) */

/* ---- CPU and wall seconds per pass (over every kind), printed on stderr at the end: where the
   run's time goes (process CPU time: the passes run one after the other, each on every core) */
enum { PS_MAPS, PS_SCALE_FIT, PS_STORE, PS_VIS, PS_T, PS_BOX, PS_FP, PS_COST_VIS, PS_COST, NPASS };
static const char *pass_name[NPASS] = { "lobe fits + horizon pyramid", "scaling function fit (patches)",
                                        "storage pass: pyramids", "full visibility maps", "scaling function T (texels)",
                                        "in-footprint maps toward the lights", "footprints (references, methods, storage)",
                                        "cost: visibility maps", "cost: timings (one thread)" };
static double pass_cpu[NPASS], pass_wall[NPASS];
static double cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
static void pass_add(int pass, double cpu0, double wall0)
{
    pass_cpu[pass] += cpu_s() - cpu0;
    pass_wall[pass] += pfb_wall_s() - wall0;
}
/* pfb_parallel_for, timed into pass `pass` */
static void ms_parallel_for(int pass, long long n, pfb_item_fn fn, void *ctx, const char *label)
{
    const double c0 = cpu_s(), w0 = pfb_wall_s();
    pfb_parallel_for(n, fn, ctx, label);
    pass_add(pass, c0, w0);
}
static void pass_report(double cpu0, double wall0)
{
    double c = cpu_s() - cpu0, w = pfb_wall_s() - wall0, rc = c, rw = w;
    int k;
    fprintf(stderr, "microsurface: CPU and wall seconds per pass (%d threads):\n", pfb_thread_count());
    for (k = 0; k < NPASS; ++k) {
        fprintf(stderr, "microsurface:   %-44s CPU %8.1f s  wall %7.1f s\n", pass_name[k], pass_cpu[k], pass_wall[k]);
        rc -= pass_cpu[k];
        rw -= pass_wall[k];
    }
    fprintf(stderr, "microsurface:   %-44s CPU %8.1f s  wall %7.1f s\n", "the rest (serial)", rc, rw);
    fprintf(stderr, "microsurface:   %-44s CPU %8.1f s  wall %7.1f s\n", "total", c, w);
}
static void check_same(const void *a, const void *b, size_t bytes, const char *what)
{
    if (memcmp(a, b, bytes) != 0) {
        fprintf(stderr, "microsurface: MICROSURFACE_CHECK: %s differs from the serial computation\n", what);
        exit(1);
    }
    fprintf(stderr, "microsurface: MICROSURFACE_CHECK: %s is the serial computation's, bit for bit\n", what);
}

/* ---- the scaling function (see above; bench/vmf_scaling.h) */
/* the library's description of the kind's scaling function (bench/vmf_scaling.h's settings):
   the centred heights and the NSCALE lobe pyramids of scale_pyr */
static pf_vmf_scale_desc scale_desc(const lib_maps *L)
{
    const pf_real *pyrs[NSCALE];
    int ms[NSCALE], j;
    for (j = 0; j < NSCALE; ++j) {
        pyrs[j] = L->vmf[scale_pyr[j]];
        ms[j] = vmf_lobes[scale_pyr[j]];
    }
    return vs_desc(L->heights, L->w, L->h, PF_R(BASE_SIGMA), PF_R(F0), NSCALE, pyrs, ms);
}

/* T of texels of `level` (given the level's S and prior) on every core: one
   pf_vmf_scale_texel_t per texel, each work item with its own scratch */
typedef struct scale_job {
    const lib_maps *L;
    pf_vmf_scale_desc d, r; /* the description, resolved (pfi_vmf_scale_resolve) */
    int level;
    long long scratch_len;
    const long long *texels; /* item i: texel texels[i] of the level (row-major) */
    pf_real *t_out;          /* T per item and lobe count: t_out[i NSCALE + j] */
} scale_job;

static void scale_texel_item(void *ctx, long long i)
{
    const scale_job *J = (const scale_job *)ctx;
    const lib_maps *L = J->L;
    const long long gw = L->w >> J->level, tx = J->texels[i] % gw, ty = J->texels[i] / gw;
    const long long cnt = pf_vmf_scale_sample_count(J->r.nt, J->r.np);
    const pf_real *s_tab[NSCALE];
    /* pf_vmf_scale_texel_t's work with the hoisted sampler (vs_texel_samples): the texel's
       samples, then T per lobe count from them (pfi_vmf_scale_t) */
    pf_real *smp = (pf_real *)pfb_xcalloc((size_t)((1 + NSCALE) * cnt + vs_samples_work(&J->r, J->level)), sizeof(pf_real));
    int j;
    for (j = 0; j < NSCALE; ++j) s_tab[j] = L->sc_S[J->level][j];
    if (tx >= gw || ty >= (L->h >> J->level) ||
        vs_texel_samples(&J->r, J->level, tx, ty, smp, smp + cnt, cnt, smp + (1 + NSCALE) * cnt) != PF_OK)
        fatal("the scaling function's T failed");
    for (j = 0; j < NSCALE; ++j)
        J->t_out[i * NSCALE + j] = pfi_vmf_scale_t(smp, smp + (1 + j) * cnt, J->r.nt, J->r.np, s_tab[j], L->sc_prior[J->level][j]);
    free(smp);
    if (check_mode) { /* MICROSURFACE_CHECK=1: against the library's pf_vmf_scale_texel_t */
        pf_real *scratch = (pf_real *)pfb_xcalloc((size_t)J->scratch_len, sizeof(pf_real)), t[NSCALE];
        if (pf_vmf_scale_texel_t(&J->d, J->level, tx, ty, s_tab, L->sc_prior[J->level], t, scratch, J->scratch_len) != PF_OK)
            fatal("the scaling function's T failed");
        if (memcmp(t, J->t_out + i * NSCALE, sizeof t) != 0) check_same(t, J->t_out + i * NSCALE, sizeof t, "a texel's T");
        free(scratch);
    }
}

/* ---- the scaling function's fit on every core (bench-side driver of pf_vmf_scale_fit_level)
   S and the prior per lobe count at the scaled levels, and the training patches' T; every other
   texel's T NaN (scale_T_fill computes them). pf_vmf_scale_fit_level does, per level: the
   samples of VS_TRAIN evenly spaced training patches (pfi_vmf_scale_texel_samples: the marches
   and the effective BRDF, nearly all its time), then per lobe count the factorization
   (pfi_vmf_scale_factor) and the training patches' T (pfi_vmf_scale_t). This driver makes the
   same calls in the same order on the same inputs, with the patches' samples as the parallel
   work items (one per training patch of every scaled level, each writing only its own slot,
   with its own scratch; the samples by vs_texel_samples, bench/vmf_scaling.h: the library's
   values with the per-facet work hoisted out of the direction pairs) and the factorizations
   after the loop in level and lobe-count order: S, prior and T are those of
   pf_vmf_scale_fit_level bit for bit, for any thread count (MICROSURFACE_CHECK=1 compares them
   with the serial call). One work item per level would leave all but one core idle. The other
   texels' T (scale_T_fill) are pf_vmf_scale_texel_t's the same way (checked too). */
typedef struct {
    pf_vmf_scale_desc r; /* the resolved description (pfi_vmf_scale_resolve) */
    int level[NSIZE];    /* per scaled level (index si - sc_min_level): */
    long long P[NSIZE];  /*   training patches, */
    long long first[NSIZE]; /*   its first work item, */
    pf_real *f_eff[NSIZE];  /*   f_eff of its patches (P cnt) and f_lobes per pyramid (NSCALE P cnt), */
    pf_real *f_l[NSIZE];
    int status[NSIZE];      /*   and the first failed patch's error (PF_OK: none) */
    int patch_rc[NSIZE * VS_TRAIN]; /* per work item */
    int nlevels;
    long long cnt, work_len;
} scale_fit_job;

/* work item i: one training patch's samples (pf_vmf_scale_fit_level's loop body) */
static void scale_patch_item(void *ctx, long long i)
{
    scale_fit_job *J = (scale_fit_job *)ctx;
    const pf_vmf_scale_desc *r = &J->r;
    int li = 0;
    long long p, c, gw, gh;
    pf_real *work;
    while (li + 1 < J->nlevels && i >= J->first[li + 1]) ++li;
    p = i - J->first[li];
    gw = r->w >> J->level[li];
    gh = r->h >> J->level[li];
    c = (p * gw * gh) / J->P[li];
    work = (pf_real *)pfb_xcalloc((size_t)J->work_len, sizeof(pf_real));
    J->patch_rc[i] = vs_texel_samples(r, J->level[li], c % gw, c / gw, J->f_eff[li] + p * J->cnt, J->f_l[li] + p * J->cnt,
                                      J->P[li] * J->cnt, work);
    free(work);
}

/* one level's factorization per lobe count from its patches' samples (the rest of
   pf_vmf_scale_fit_level, same calls, same order) */
static int scale_factor_level(lib_maps *L, const scale_fit_job *J, int li)
{
    const pf_vmf_scale_desc *r = &J->r;
    const int si = J->level[li];
    const long long P = J->P[li], cnt = J->cnt, cells = pf_vmf_scale_cell_count(r->nt, r->np);
    const long long gw = r->w >> si, gh = r->h >> si, off = pf_vmf_pyramid_level_offset(L->w, L->h, si);
    pf_real *fac = (pf_real *)pfb_xcalloc((size_t)(2 * P * cells + P), sizeof(pf_real)), *t = fac + 2 * P * cells;
    long long p;
    int k, rc = PF_OK;
    for (k = 0; k < NSCALE && rc == PF_OK; ++k) {
        const pf_real *fk = J->f_l[li] + k * P * cnt;
        rc = pfi_vmf_scale_factor(J->f_eff[li], fk, (int)P, r->nt, r->np, r->rounds, r->shrink, t, L->sc_S[si][k], fac,
                                  &L->sc_prior[si][k], 0);
        if (rc == PF_OK)
            for (p = 0; p < P; ++p)
                L->sc_T[k][off + (p * gw * gh) / P] =
                    pfi_vmf_scale_t(J->f_eff[li] + p * cnt, fk + p * cnt, r->nt, r->np, L->sc_S[si][k],
                                    L->sc_prior[si][k]);
    }
    free(fac);
    return rc;
}

/* MICROSURFACE_CHECK=1: the serial pf_vmf_scale_fit_level of level si, compared bit for bit */
static void scale_check_level(const lib_maps *L, const pf_vmf_scale_desc *d, int si)
{
    const long long len = pf_vmf_scale_scratch_size(d, si), lt = (long long)(L->w >> si) * (L->h >> si);
    const long long off = pf_vmf_pyramid_level_offset(L->w, L->h, si);
    pf_real *scratch = (pf_real *)pfb_xcalloc((size_t)len, sizeof(pf_real));
    pf_real S[NSCALE][VS_CELLS], prior[NSCALE], *s_out[NSCALE], *t_level[NSCALE];
    long long i;
    int j;
    for (j = 0; j < NSCALE; ++j) {
        s_out[j] = S[j];
        t_level[j] = (pf_real *)pfb_xcalloc((size_t)lt, sizeof(pf_real));
        for (i = 0; i < lt; ++i) t_level[j][i] = (pf_real)NAN; /* untouched texels: the same NaNs as sc_T's */
    }
    if (pf_vmf_scale_fit_level(d, si, s_out, prior, t_level, scratch, len) != PF_OK)
        fatal("the scaling function's fit failed");
    check_same(S, L->sc_S[si], sizeof S, "the scaling function's S (parallel patches)");
    check_same(prior, L->sc_prior[si], sizeof prior, "the scaling function's prior (parallel patches)");
    for (j = 0; j < NSCALE; ++j) {
        check_same(t_level[j], L->sc_T[j] + off, (size_t)lt * sizeof(pf_real),
                   "the training patches' T (parallel patches)");
        free(t_level[j]);
    }
    free(scratch);
}

static void scale_build(lib_maps *L, const char *kind_name)
{
    scale_fit_job J;
    pf_vmf_scale_desc d = scale_desc(L);
    long long tc = pf_vmf_pyramid_texel_count(L->w, L->h), i, items = 0;
    int si, j, li;
    double t0 = pfb_now_ns();
    struct timespec c0, c1;
    char label[96];
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
    memset(&J, 0, sizeof J);
    for (j = 0; j < NSCALE; ++j) {
        L->sc_T[j] = (pf_real *)pfb_xcalloc((size_t)tc, sizeof(pf_real));
        for (i = 0; i < tc; ++i) L->sc_T[j][i] = (pf_real)NAN;
    }
    if (!pfi_vmf_scale_resolve(&d, &J.r)) fatal("the scaling function's fit failed");
    J.cnt = pf_vmf_scale_sample_count(J.r.nt, J.r.np);
    J.nlevels = sc_max_level - sc_min_level + 1;
    J.work_len = 0;
    for (li = 0; li < J.nlevels; ++li) {
        const int s = sc_max_level - li; /* the largest patches first */
        const long long gp = (long long)(L->w >> s) * (L->h >> s);
        const long long wl = vs_samples_work(&J.r, s); /* vs_texel_samples' work */
        if (pfi_vmf_scale_check(&J.r, s) != PF_OK || pf_vmf_scale_scratch_size(&J.r, s) <= 0)
            fatal("the scaling function's fit failed");
        J.level[li] = s;
        J.P[li] = gp < J.r.train_patches ? gp : J.r.train_patches;
        if (J.P[li] > VS_TRAIN) fatal("the scaling function's fit: more training patches than VS_TRAIN");
        J.first[li] = items;
        items += J.P[li];
        J.f_eff[li] = (pf_real *)pfb_xcalloc((size_t)((1 + NSCALE) * J.P[li] * J.cnt), sizeof(pf_real));
        J.f_l[li] = J.f_eff[li] + J.P[li] * J.cnt;
        J.work_len = wl > J.work_len ? wl : J.work_len;
    }
    snprintf(label, sizeof label, "%s: scaling function fit (training patches)", kind_name);
    ms_parallel_for(PS_SCALE_FIT, items, scale_patch_item, &J, label);
    /* in level order after the loop: the first failed patch, else the factorizations */
    for (li = 0; li < J.nlevels; ++li) {
        J.status[li] = PF_OK;
        for (i = J.first[li]; i < J.first[li] + J.P[li] && J.status[li] == PF_OK; ++i) J.status[li] = J.patch_rc[i];
        if (J.status[li] == PF_OK) J.status[li] = scale_factor_level(L, &J, li);
        if (J.status[li] != PF_OK) fatal("the scaling function's fit failed");
        free(J.f_eff[li]);
    }
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
    L->sc_seconds = (pfb_now_ns() - t0) * 1e-9;
    L->sc_patches = 0;
    for (si = sc_min_level; si <= sc_max_level; ++si) {
        const long long gp = (long long)(L->w >> si) * (L->h >> si);
        L->sc_patches += gp < VS_TRAIN ? (int)gp : VS_TRAIN;
    }
    fprintf(stderr, "microsurface: scaling function S (%d x %d x %d nodes, %d patches per level, m = 4, 8): %.2f s"
                    " (CPU %.2f s, %d threads)\n",
            VS_NT, VS_NT, VS_NP, VS_TRAIN, L->sc_seconds,
            (double)(c1.tv_sec - c0.tv_sec) + 1e-9 * (double)(c1.tv_nsec - c0.tv_nsec), pfb_thread_count());
    if (check_on())
        for (si = sc_min_level; si <= sc_max_level; ++si) scale_check_level(L, &d, si);
}

/* the id of footprint (x0, y0, n)'s texel in the level-log2(n) T table */
static long long scale_texel(const lib_maps *L, int x0, int y0, int n)
{
    return pf_vmf_pyramid_level_offset(L->w, L->h, ilog2(n)) + (long long)(y0 / n) * (L->w / n) + x0 / n;
}

/* T of every footprint of the list (size n; x0[i], y0[i]) whose T is not computed yet, in
   parallel; a no-op outside the scaled levels */
static void scale_T_fill(lib_maps *L, int n, const int *x0, const int *y0, long long count, const char *label)
{
    const int si = ilog2(n), gw = L->w / n;
    long long i, m = 0, k;
    long long *texels;
    pf_real *t;
    char *seen;
    int j;
    double t0 = pfb_now_ns();
    if (si < sc_min_level || si > sc_max_level || count <= 0) return;
    texels = (long long *)pfb_xcalloc((size_t)count, sizeof *texels);
    seen = (char *)pfb_xcalloc((size_t)gw * (size_t)(L->h / n), 1);
    for (i = 0; i < count; ++i) {
        long long c = (long long)(y0[i] / n) * gw + x0[i] / n;
        if (seen[c] || L->sc_T[0][scale_texel(L, x0[i], y0[i], n)] == L->sc_T[0][scale_texel(L, x0[i], y0[i], n)])
            continue; /* listed already, or computed (not NaN) */
        seen[c] = 1;
        texels[m++] = c;
    }
    if (m > 0) {
        scale_job J;
        J.L = L;
        J.d = scale_desc(L);
        J.level = si;
        J.scratch_len = pf_vmf_scale_scratch_size(&J.d, si);
        if (J.scratch_len <= 0 || !pfi_vmf_scale_resolve(&J.d, &J.r) || pfi_vmf_scale_check(&J.r, si) != PF_OK)
            fatal("the scaling function's T failed");
        J.texels = texels;
        t = (pf_real *)pfb_xcalloc((size_t)m * NSCALE, sizeof(pf_real));
        J.t_out = t;
        ms_parallel_for(PS_T, m, scale_texel_item, &J, label);
        for (k = 0; k < m; ++k)
            for (j = 0; j < NSCALE; ++j)
                L->sc_T[j][pf_vmf_pyramid_level_offset(L->w, L->h, si) + texels[k]] = t[k * NSCALE + j];
        free(t);
        L->sc_patches += m;
        L->sc_seconds += (pfb_now_ns() - t0) * 1e-9;
    }
    free(texels);
    free(seen);
}

/* T of the footprint's pyramid texel (level log2 n) for scaled lobe count j: computed before
   (scale_build, scale_T_fill), so that the evaluation only reads */
static pf_real scale_T(const lib_maps *L, int j, int x0, int y0, int n)
{
    pf_real t = L->sc_T[j][scale_texel(L, x0, y0, n)];
    if (t != t) fatal("internal: the scaling function's T of a shaded footprint was not computed first");
    return t;
}

/* ---- the pyramids: the lobe fits (one per lobe count) and the horizon pyramid are the
   costly ones, built in parallel (one work item each, the costliest first) */
typedef struct maps_job {
    lib_maps *L;
    const pf_real *nr, *hr;
    double texel;
} maps_job;
#define MAPS_ITEMS (NVMF + 1)
static void maps_item(void *ctx, long long item)
{
    maps_job *J = (maps_job *)ctx;
    lib_maps *L = J->L;
    const int w = L->w, h = L->h;
    const long long tc = pf_mip_texel_count(w, h);
    double t0 = pfb_now_ns();
    if (item == 1) { /* the n = 32 horizon pyramid (the n = 16 one is its even azimuths: lib_maps_build) */
        int C = pf_horizon_channels(PF_HORIZON_MOMENTS, hor_n[H32], 0);
        L->hor[H32] = (pf_real *)pfb_xcalloc((size_t)tc * (size_t)C, sizeof(pf_real));
        if (pf_horizon_pyramid(J->hr, w, h, PF_R(J->texel), hor_n[H32], HOR_STEPS, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0,
                               L->hor[H32]) != PF_OK)
            fatal("pf_horizon_pyramid failed");
        L->hor_seconds[H32] = (pfb_now_ns() - t0) * 1e-9;
    } else { /* items 0, 2, 3, ...: lobe counts 16, 8, 4, 2, 1 */
        int k = NVMF - 1 - (item == 0 ? 0 : (int)item - 1);
        L->vmf[k] = (pf_real *)pfb_xcalloc((size_t)tc * 4 * (size_t)vmf_lobes[k], sizeof(pf_real));
        if (pf_vmf_pyramid_from_normals(J->nr, NULL, w, h, vmf_lobes[k], vmf_iter, L->vmf[k]) != PF_OK)
            fatal("pf_vmf_pyramid_from_normals failed");
        L->vmf_fit_seconds[k] = (pfb_now_ns() - t0) * 1e-9;
    }
}

/* The n = 16 horizon pyramid from the n = 32 one: azimuth a of 16 is azimuth 2a of 32 (phi =
   2 pi a / n is the same float for both: the factor 2 is exact), marched by the same code, and
   pf_mip_build filters each channel alone, so its channels are those of pf_horizon_pyramid at
   n = 16 bit for bit (MICROSURFACE_CHECK=1 builds both and compares) without marching
   the same rays twice. */
/* the n = 16 channels of tc texels of n = 32 HDF moments: its even azimuths (allocated) */
static pf_real *hdf_even_azimuths(const pf_real *h32, long long tc)
{
    const int C16 = pf_horizon_channels(PF_HORIZON_MOMENTS, hor_n[H16], 0);
    const int C32 = pf_horizon_channels(PF_HORIZON_MOMENTS, hor_n[H32], 0);
    pf_real *h16 = (pf_real *)pfb_xcalloc((size_t)tc * (size_t)C16, sizeof(pf_real));
    long long t;
    int a, q;
    for (t = 0; t < tc; ++t)
        for (a = 0; a < hor_n[H16]; ++a)
            for (q = 0; q < 3; ++q) h16[t * C16 + 3 * a + q] = h32[t * C32 + 3 * (2 * a) + q];
    return h16;
}
static void horizon_even_azimuths(lib_maps *L, const pf_real *hr, double texel)
{
    const long long tc = pf_mip_texel_count(L->w, L->h);
    const int C16 = pf_horizon_channels(PF_HORIZON_MOMENTS, hor_n[H16], 0);
    double t0 = pfb_now_ns();
    L->hor[H16] = hdf_even_azimuths(L->hor[H32], tc);
    L->hor_seconds[H16] = (pfb_now_ns() - t0) * 1e-9;
    if (check_on()) {
        pf_real *ref = (pf_real *)pfb_xcalloc((size_t)tc * (size_t)C16, sizeof(pf_real));
        if (pf_horizon_pyramid(hr, L->w, L->h, PF_R(texel), hor_n[H16], HOR_STEPS, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0,
                               ref) != PF_OK)
            fatal("pf_horizon_pyramid failed");
        check_same(ref, L->hor[H16], (size_t)tc * (size_t)C16 * sizeof(pf_real), "the n = 16 horizon pyramid");
        free(ref);
    }
}

static void lib_maps_build(lib_maps *L, const pfm_surface *s, const char *kind_name)
{
    int w = s->w, h = s->h, k;
    long long n = (long long)w * h, t, tc = pf_mip_texel_count(w, h);
    pf_real *hr = (pf_real *)pfb_xcalloc((size_t)n, sizeof *hr);
    pf_real *nr = (pf_real *)pfb_xcalloc((size_t)n * 3, sizeof *nr);
    pf_real *ar = (pf_real *)pfb_xcalloc((size_t)n, sizeof *ar);
    double sum = 0, sum2 = 0;
    maps_job J;
    char label[160];
    L->w = w;
    L->h = h;
    for (t = 0; t < n; ++t) sum += s->height[t];
    L->mean_h = sum / (double)n;
    for (t = 0; t < n; ++t) sum2 += (s->height[t] - L->mean_h) * (s->height[t] - L->mean_h);
    L->sd_h = sqrt(sum2 / (double)n);
    for (t = 0; t < n; ++t) hr[t] = (pf_real)(s->height[t] - L->mean_h);
    L->slope = (pf_real *)pfb_xcalloc((size_t)tc * 5, sizeof(pf_real));
    pf_slope_pyramid_from_heights(hr, w, h, PF_R(s->texel), PF_R(s->texel), PF_R(1.0), PF_BORDER_WRAP,
                                  L->slope);
    /* unit micro-normals from the level-0 slopes (the same central differences) */
    for (t = 0; t < n; ++t) {
        pf_vec3 m = pf_normal_avg_from_slope(L->slope[5 * t], L->slope[5 * t + 1]);
        nr[3 * t] = m.x;
        nr[3 * t + 1] = m.y;
        nr[3 * t + 2] = m.z;
    }
    J.L = L;
    J.nr = nr;
    J.hr = hr;
    J.texel = s->texel;
    snprintf(label, sizeof label, "microsurface: %s: vMF lobe fits and horizon pyramid", kind_name);
    ms_parallel_for(PS_MAPS, MAPS_ITEMS, maps_item, &J, label);
    horizon_even_azimuths(L, hr, s->texel);
    fprintf(stderr, "microsurface: vMF lobe pyramids %d x %d, m = 1, 2, 4, 8, 16: %.2f %.2f %.2f %.2f %.2f s\n", w, h,
            L->vmf_fit_seconds[0], L->vmf_fit_seconds[1], L->vmf_fit_seconds[2], L->vmf_fit_seconds[3],
            L->vmf_fit_seconds[4]);
    fprintf(stderr, "microsurface: horizon pyramids %d x %d, n = %d (its even azimuths), %d (march %d texels): %.2f %.2f s\n",
            w, h, hor_n[H16], hor_n[H32], HOR_STEPS, L->hor_seconds[H16], L->hor_seconds[H32]);
    L->normal = (pf_real *)pfb_xcalloc((size_t)tc * 3, sizeof(pf_real));
    pf_normal_pyramid_from_normals(nr, w, h, L->normal);
    L->height = (pf_real *)pfb_xcalloc((size_t)tc * 2, sizeof(pf_real));
    pf_scalar_pyramid_from_values(hr, w, h, L->height);
    L->cm[0] = cmap_make(ramp_z, ramp_c, 2, L->sd_h);
    L->cm[1] = cmap_make(bands_z, bands_c, 6, L->sd_h);
    for (k = 0; k < 2; ++k) {
        L->attr_d[k] = (double *)pfb_xcalloc((size_t)n, sizeof(double));
        for (t = 0; t < n; ++t) {
            L->attr_d[k][t] = cmap_eval(&L->cm[k], s->height[t] - L->mean_h);
            ar[t] = (pf_real)L->attr_d[k][t];
        }
        L->attr[k] = (pf_real *)pfb_xcalloc((size_t)tc * 2, sizeof(pf_real));
        pf_scalar_pyramid_from_values(ar, w, h, L->attr[k]);
    }
    L->heights = hr;
    scale_build(L, kind_name);
    free(nr);
    free(ar);
}

static void lib_maps_free(lib_maps *L)
{
    int k;
    free(L->slope);
    free(L->normal);
    free(L->height);
    free(L->attr[0]);
    free(L->attr[1]);
    free(L->attr_d[0]);
    free(L->attr_d[1]);
    for (k = 0; k < NVMF; ++k) free(L->vmf[k]);
    for (k = 0; k < NHOR; ++k) free(L->hor[k]);
    for (k = 0; k < NSCALE; ++k) free(L->sc_T[k]);
    free(L->heights);
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
/* The HDF moments toward w from horizon pyramid i at texel (x0/n, y0/n) of level log2(n): the
   two stored azimuths around w's (6 channels fetched), mixed by pf_hdf_moments_lerp */
static pf_hdf_moments horizon_hdf(const lib_maps *L, int i, int x0, int y0, int n, pf_vec3 w)
{
    const int W = L->w, H = L->h, nh = hor_n[i], C = 3 * nh;
    const pf_real *tx = L->hor[i] + (pf_mip_level_offset(W, H, ilog2(n)) + (long long)(y0 / n) * (W / n) + x0 / n) * C;
    pf_horizon_azimuth az = pf_horizon_azimuth_of(w, nh);
    pf_hdf_moments h0 = pf_hdf_moments_make(tx[3 * az.i0], tx[3 * az.i0 + 1], tx[3 * az.i0 + 2]);
    pf_hdf_moments h1 = pf_hdf_moments_make(tx[3 * az.i1], tx[3 * az.i1 + 1], tx[3 * az.i1 + 2]);
    return pf_hdf_moments_lerp(h0, h1, az.f);
}
static pf_real horizon_area(const lib_maps *L, int i, int x0, int y0, int n, pf_vec3 w, pf_slope_stats s0)
{
    return pf_horizon_visible_area(w, horizon_hdf(L, i, x0, y0, n, w), s0.mean_x, s0.mean_y);
}

/* ---------------------------------------------------------------- one method = fetch + evaluation
   What a shader does for a footprint: fetch one texel of level log2(n) of the pyramids the
   method needs (a bilinear sample at its centre reads exactly that texel), then evaluate.
   The error runs and the cost section both call a method's evaluator, so the timed code is the
   measured one. */
/* what a method sees: the maps, the task (the colour tasks: T_RAMP shades with the ramp map,
   T_BANDS with the banded one), the footprint (texel (x0/n, y0/n) of level log2 n), the view and
   the light; oracles also the reference shading with every texel visible (NULL in the cost
   section, which times shader methods only) */
/* what the methods of one sample (one footprint, view, light and set of pyramids) share,
   computed once by the first method that needs it and read by the others: the fetched slope
   statistics (without and with the base variance), the value of each vMF pyramid per path (mix,
   texel), the exact-path lobe sum of each pyramid (the horizon and grazing rows sum the same 16
   lobes as vmf_m16; the scaled rows shade the same lobes as their unscaled twins). The same
   calls on the same inputs: every value is the one the method computes alone. NULL (the cost
   section): each method does all its own work, as a shader would. */
typedef struct mmemo {
    unsigned char have_slope[2], have_f[NVMF][2][2], have_sum[NVMF];
    pf_slope_stats slope[2];
    pf_real f[NVMF][2][2];
    pf_vmf_sum sum[NVMF];
} mmemo;
typedef struct mctx {
    const lib_maps *L;
    int task, x0, y0, n;
    pf_vec3 wo, wi;
    const pfm_shade *novis;
    mmemo *memo; /* NULL: nothing shared */
} mctx;
static pf_real ctx_lod(const mctx *c) { return PF_R(ilog2(c->n)); }
static pf_real ctx_u(const mctx *c) { return (PF_R(c->x0 / c->n) + PF_R(0.5)) / PF_R(c->L->w / c->n); }
static pf_real ctx_v(const mctx *c) { return (PF_R(c->y0 / c->n) + PF_R(0.5)) / PF_R(c->L->h / c->n); }
/* the footprint's slope statistics (one texel of the 5-moment pyramid) with base_var added */
static pf_slope_stats fetch_slope(const mctx *c, pf_real base_var)
{
    const lib_maps *L = c->L;
    const int b = base_var != PF_R(0.0); /* the two variances the methods ask for: 0, BASE_SIGMA^2 */
    mmemo *memo = base_var == PF_R(0.0) || base_var == PF_R(BASE_SIGMA * BASE_SIGMA) ? c->memo : NULL;
    pf_slope_stats s;
    if (memo && memo->have_slope[b]) return memo->slope[b];
    s = pf_slope_moments_stats(pf_slope_moments_sample(L->slope, L->w, L->h, ctx_lod(c), ctx_u(c), ctx_v(c), PF_BORDER_WRAP),
                               base_var);
    if (memo) {
        memo->slope[b] = s;
        memo->have_slope[b] = 1;
    }
    return s;
}
static pf_slope_stats fetch_slope_spec(const mctx *c) { return fetch_slope(c, PF_R(BASE_SIGMA * BASE_SIGMA)); }
/* the footprint's (E[h], E[h^2]) texel and the task's colour map */
static pf_scalar_moments fetch_height(const mctx *c)
{
    return pf_scalar_moments_sample(c->L->height, c->L->w, c->L->h, ctx_lod(c), ctx_u(c), ctx_v(c), PF_BORDER_WRAP);
}
static const cmap *task_cmap(const mctx *c) { return &c->L->cm[c->task == T_BANDS]; }

/* the lobes of texel (x0/n, y0/n) of level log2(n) of vMF pyramid p: m RGBA fetches, shaded
   with Smith G of the mixture's moments (mix = 0) or the mixture's exact Smith (mix = 1);
   texel = 0: through pf_vmf_lobe_make + pf_vmf_sum_add (+ pf_vmf_sum_add_masking), the exact
   tangent variance; texel = 1: the shader path bench/gpu/ prices (pf_vmf_pixel_make once,
   pf_vmf_sum_add_texel or _texel_mixture per fetched texel as stored, its rational tangent
   variance) */
/* the exact path's sum of texel (x0/n, y0/n) of vMF pyramid p's lobes (pf_vmf_lobe_make +
   pf_vmf_sum_add, base variance added: vs_texel_spec's loop), shared through the memo */
static pf_vmf_sum vmf_sum_exact(const mctx *c, int p)
{
    const lib_maps *L = c->L;
    const int m = vmf_lobes[p], W = L->w, H = L->h;
    long long id = pf_vmf_pyramid_level_offset(W, H, ilog2(c->n)) + (long long)(c->y0 / c->n) * (W / c->n) + c->x0 / c->n;
    const pf_real *tx = L->vmf[p] + id * 4 * m;
    pf_vmf_sum sum = pf_vmf_sum_zero();
    int j;
    if (c->memo && c->memo->have_sum[p]) return c->memo->sum[p];
    for (j = 0; j < m; ++j) /* padding lobes (amp 0) add nothing */
        sum = pf_vmf_sum_add(sum, pf_vmf_lobe_make(tx[4 * j + 3], tx[4 * j], tx[4 * j + 1], tx[4 * j + 2]), c->wo, c->wi,
                             PF_R(BASE_SIGMA * BASE_SIGMA));
    if (c->memo) {
        c->memo->sum[p] = sum;
        c->memo->have_sum[p] = 1;
    }
    return sum;
}

static pf_real vmf_texel_spec(const lib_maps *L, int p, int x0, int y0, int n, pf_vec3 wo, pf_vec3 wi, int mix, int texel)
{
    const int m = vmf_lobes[p], W = L->w, H = L->h;
    long long id = pf_vmf_pyramid_level_offset(W, H, ilog2(n)) + (long long)(y0 / n) * (W / n) + x0 / n;
    const pf_real *tx = L->vmf[p] + id * 4 * m;
    pf_vmf_sum sum = pf_vmf_sum_zero();
    int j;
    if (texel) {
        pf_vmf_pixel px = pf_vmf_pixel_make(wo, wi, PF_R(BASE_SIGMA * BASE_SIGMA));
        for (j = 0; j < m; ++j) /* padding lobes (amp 0) add nothing */
            sum = mix ? pf_vmf_sum_add_texel_mixture(sum, px, wo, wi, tx[4 * j + 3], tx[4 * j], tx[4 * j + 1], tx[4 * j + 2])
                      : pf_vmf_sum_add_texel(sum, px, tx[4 * j + 3], tx[4 * j], tx[4 * j + 1], tx[4 * j + 2]);
        return mix ? pf_vmf_sum_specular_mixture(sum, wo, wi, PF_R(F0)) : pf_vmf_sum_specular(sum, wo, wi, PF_R(F0));
    }
    if (!mix) /* the texel's lobes, Smith G of their moments (what the scaling function is fitted to) */
        return vs_texel_spec(L->vmf[p], W, H, m, ilog2(n), x0 / n, y0 / n, wo, wi, PF_R(BASE_SIGMA * BASE_SIGMA), PF_R(F0));
    for (j = 0; j < m; ++j) { /* padding lobes (amp 0) add nothing */
        pf_vmf_lobe lobe = pf_vmf_lobe_make(tx[4 * j + 3], tx[4 * j], tx[4 * j + 1], tx[4 * j + 2]);
        sum = pf_vmf_sum_add(sum, lobe, wo, wi, PF_R(BASE_SIGMA * BASE_SIGMA));
        sum = pf_vmf_sum_add_masking(sum, lobe, wo, wi, PF_R(BASE_SIGMA * BASE_SIGMA));
    }
    return pf_vmf_sum_specular_mixture(sum, wo, wi, PF_R(F0));
}


/* vMF lobe pyramid p (mix: the mixture's exact Smith), times the scaling function sc (-1: none;
   use_t: T S, else S alone) at the scaled levels; the unscaled lobes elsewhere (sc_min_level);
   texel: the shader path (vmf_texel_spec), the scaling function the same (fitted to the exact
   path's lobes, applied to the shader path's value, as a shader would) */
static double vmf_method(const mctx *c, int p, int mix, int sc, int use_t, int texel)
{
    const lib_maps *L = c->L;
    const int lev = ilog2(c->n);
    pf_real f;
    if (c->memo && c->memo->have_f[p][mix][texel]) f = c->memo->f[p][mix][texel];
    else {
        f = c->memo && !mix && !texel ? pf_vmf_sum_specular(vmf_sum_exact(c, p), c->wo, c->wi, PF_R(F0)) /* vs_texel_spec */
                                      : vmf_texel_spec(L, p, c->x0, c->y0, c->n, c->wo, c->wi, mix, texel);
        if (c->memo) {
            c->memo->f[p][mix][texel] = f;
            c->memo->have_f[p][mix][texel] = 1;
        }
    }
    if (sc < 0 || lev < sc_min_level || lev > sc_max_level) return (double)f;
    /* T: one texel of level log2(n); S: 8 nodes of the level's table, trilinear */
    return (double)pf_vmf_scale_apply(use_t ? scale_T(L, sc, c->x0, c->y0, c->n) : PF_R(1.0),
                                      pf_vmf_scale_lookup(L->sc_S[lev][sc], VS_NT, VS_NP, (pf_real)VS_THETA_MAX, c->wo, c->wi),
                                      f);
}
/* the HDF moments of horizon pyramid i toward w at the footprint's texel */
static pf_hdf_moments ctx_hdf(const mctx *c, int i, pf_vec3 w) { return horizon_hdf(c->L, i, c->x0, c->y0, c->n, w); }

/* ---- the evaluators, one per method (the registry below says what each one is) */
/* masking */
static double m_smith_g1_exact(const mctx *c) { return (double)pf_beckmann_g1(c->wo, fetch_slope(c, PF_R(0.0))); }
static double m_smith_g1_fast(const mctx *c)
{
    return (double)pf_g1_beckmann_fast(pf_smith_nu(c->wo, fetch_slope(c, PF_R(0.0))));
}
static double m_smith_g1_walter(const mctx *c)
{
    return (double)pf_g1_beckmann_walter(pf_smith_nu(c->wo, fetch_slope(c, PF_R(0.0))));
}
static double m_no_masking(const mctx *c)
{
    (void)c;
    return 1.0;
}
static double m_horizon_masking_n16(const mctx *c)
{
    return (double)pf_horizon_masking(c->wo, ctx_hdf(c, H16, c->wo), fetch_slope(c, PF_R(0.0)));
}
static double m_horizon_masking_n32(const mctx *c)
{
    return (double)pf_horizon_masking(c->wo, ctx_hdf(c, H32, c->wo), fetch_slope(c, PF_R(0.0)));
}
static double m_horizon_masking_lod_n32(const mctx *c)
{
    return (double)pf_horizon_masking_lod(c->wo, ctx_hdf(c, H32, c->wo), fetch_slope(c, PF_R(0.0)), ctx_lod(c),
                                          PF_R(HOR_LOD_FULL), PF_R(HOR_LOD_SMITH));
}
/* specular */
static double m_leadr_joint(const mctx *c) { return (double)pf_leadr_specular(c->wo, c->wi, fetch_slope_spec(c), PF_R(F0)); }
static double m_leadr_masking(const mctx *c)
{
    return (double)pf_leadr_specular_masking(c->wo, c->wi, fetch_slope_spec(c), PF_R(F0));
}
static double m_lean(const mctx *c) { return (double)lean_lobe(c->wo, c->wi, fetch_slope_spec(c)); }
static pf_vec3 fetch_normal(const mctx *c)
{
    return pf_normal_avg_sample(c->L->normal, c->L->w, c->L->h, ctx_lod(c), ctx_u(c), ctx_v(c), PF_BORDER_WRAP);
}
static double m_toksvig(const mctx *c) { return (double)toksvig_spec(fetch_normal(c), c->wo, c->wi, 1); }
static double m_naive_mip_normal(const mctx *c) { return (double)toksvig_spec(fetch_normal(c), c->wo, c->wi, 0); }
static double m_vmf_m1(const mctx *c) { return vmf_method(c, V1, 0, -1, 0, 0); }
static double m_vmf_m2(const mctx *c) { return vmf_method(c, V2, 0, -1, 0, 0); }
static double m_vmf_m4(const mctx *c) { return vmf_method(c, V4, 0, -1, 0, 0); }
static double m_vmf_m8(const mctx *c) { return vmf_method(c, V8, 0, -1, 0, 0); }
static double m_vmf_m4_mix_smith(const mctx *c) { return vmf_method(c, V4, 1, -1, 0, 0); }
static double m_vmf_m8_mix_smith(const mctx *c) { return vmf_method(c, V8, 1, -1, 0, 0); }
static double m_vmf_m16(const mctx *c) { return vmf_method(c, V16, 0, -1, 0, 0); }
static double m_vmf_m4_scaled(const mctx *c) { return vmf_method(c, V4, 0, SC4, 1, 0); }
static double m_vmf_m8_scaled(const mctx *c) { return vmf_method(c, V8, 0, SC8, 1, 0); }
static double m_vmf_m8_scaled_s(const mctx *c) { return vmf_method(c, V8, 0, SC8, 0, 0); }
/* the same rows through the shader path (pf_vmf_sum_add_texel: what bench/gpu/ counts) */
static double m_vmf_m1_texel(const mctx *c) { return vmf_method(c, V1, 0, -1, 0, 1); }
static double m_vmf_m2_texel(const mctx *c) { return vmf_method(c, V2, 0, -1, 0, 1); }
static double m_vmf_m4_texel(const mctx *c) { return vmf_method(c, V4, 0, -1, 0, 1); }
static double m_vmf_m8_texel(const mctx *c) { return vmf_method(c, V8, 0, -1, 0, 1); }
static double m_vmf_m4_mix_smith_texel(const mctx *c) { return vmf_method(c, V4, 1, -1, 0, 1); }
static double m_vmf_m8_mix_smith_texel(const mctx *c) { return vmf_method(c, V8, 1, -1, 0, 1); }
static double m_vmf_m16_texel(const mctx *c) { return vmf_method(c, V16, 0, -1, 0, 1); }
static double m_vmf_m4_scaled_texel(const mctx *c) { return vmf_method(c, V4, 0, SC4, 1, 1); }
static double m_vmf_m8_scaled_texel(const mctx *c) { return vmf_method(c, V8, 0, SC8, 1, 1); }
static double m_vmf_m8_scaled_s_texel(const mctx *c) { return vmf_method(c, V8, 0, SC8, 0, 1); }
/* pf_horizon.h: the specular with the reflecting facets' horizon visibility instead of Smith's
   G (n = 32, two azimuths fetched toward wo and toward wi), alone or faded to the unshadowed
   method by mip level (HOR_LOD_FULL .. HOR_LOD_SMITH) */
static double m_leadr_horizon_n32(const mctx *c)
{
    return (double)pf_horizon_leadr_specular(c->wo, c->wi, fetch_slope_spec(c), PF_R(BASE_SIGMA * BASE_SIGMA),
                                             ctx_hdf(c, H32, c->wo), ctx_hdf(c, H32, c->wi), PF_R(F0));
}
static double m_leadr_horizon_lod_n32(const mctx *c)
{
    return (double)pf_horizon_leadr_specular_lod(c->wo, c->wi, fetch_slope_spec(c), PF_R(BASE_SIGMA * BASE_SIGMA),
                                                 ctx_hdf(c, H32, c->wo), ctx_hdf(c, H32, c->wi), PF_R(F0), ctx_lod(c),
                                                 PF_R(HOR_LOD_FULL), PF_R(HOR_LOD_SMITH));
}
/* the texel's lobes of vMF pyramid p summed (slope form), then the horizon specular conditioned
   on the slope-moment texel's statistics (lod: faded) */
static double vmf_horizon_method(const mctx *c, int p, int lod)
{
    const pf_vmf_sum sum = vmf_sum_exact(c, p);
    const pf_real bv = PF_R(BASE_SIGMA * BASE_SIGMA);
    pf_slope_stats st = fetch_slope_spec(c);
    if (!lod)
        return (double)pf_horizon_vmf_specular(sum, c->wo, c->wi, st, bv, ctx_hdf(c, H32, c->wo), ctx_hdf(c, H32, c->wi), PF_R(F0));
    return (double)pf_horizon_vmf_specular_lod(sum, c->wo, c->wi, st, bv, ctx_hdf(c, H32, c->wo), ctx_hdf(c, H32, c->wi),
                                               PF_R(F0), ctx_lod(c), PF_R(HOR_LOD_FULL), PF_R(HOR_LOD_SMITH));
}
static double m_vmf_m16_horizon_n32(const mctx *c) { return vmf_horizon_method(c, V16, 0); }
static double m_vmf_m16_horizon_lod_n32(const mctx *c) { return vmf_horizon_method(c, V16, 1); }
/* ---- grazing views (issue 28, item 2): the base lobe's own masking-shadowing at the
   reflecting facets (pf_beckmann_base_masking). leadr_base = pf_leadr_specular_base;
   vmf_m16_base = vmf_m16 with each lobe's NDF term times the factor of that lobe's slope
   statistics (the caller-applied per-lobe form); vmf_m16_base_fp = vmf_m16 times one factor of
   the footprint's slope moments (one evaluation per pixel) */
static double m_leadr_base(const mctx *c)
{
    return (double)pf_leadr_specular_base(c->wo, c->wi, fetch_slope_spec(c), PF_R(BASE_SIGMA * BASE_SIGMA), PF_R(F0));
}
static double vmf_base_method(const mctx *c, int p, int per_lobe)
{
    const lib_maps *L = c->L;
    const int m = vmf_lobes[p], W = L->w, H = L->h;
    long long id = pf_vmf_pyramid_level_offset(W, H, ilog2(c->n)) + (long long)(c->y0 / c->n) * (W / c->n) + c->x0 / c->n;
    const pf_real *tx = L->vmf[p] + id * 4 * m;
    const pf_real bv = PF_R(BASE_SIGMA * BASE_SIGMA);
    pf_vmf_sum sum = pf_vmf_sum_zero();
    int j;
    /* every form: Smith's G of the mixture's own slopes (pf_vmf_sum_without_base), the base
       lobe's masking left to the factor (as pf_leadr_specular_base) */
    if (per_lobe != 1) {
        pf_real f;
        sum = vmf_sum_exact(c, p);
        if (per_lobe == 2) /* the factor of the mixture's own moments: no fetch beyond the lobes */
            return (double)pf_vmf_sum_specular_base(sum, c->wo, c->wi, bv, PF_R(F0));
        f = pf_vmf_sum_specular(pf_vmf_sum_without_base(sum, bv), c->wo, c->wi, PF_R(F0));
        return (double)f * (double)pf_beckmann_base_masking(c->wo, c->wi, fetch_slope_spec(c), bv);
    }
    for (j = 0; j < m; ++j) {
        pf_vmf_lobe lobe = pf_vmf_lobe_make(tx[4 * j + 3], tx[4 * j], tx[4 * j + 1], tx[4 * j + 2]);
        pf_real before = sum.ndf;
        if (!(lobe.amp > PF_R(0.0))) continue; /* padding */
        sum = pf_vmf_sum_add(sum, lobe, c->wo, c->wi, bv);
        sum.ndf = before + (sum.ndf - before) *
                               pf_beckmann_base_masking(c->wo, c->wi, pf_vmf_lobe_slope_stats(lobe.mu, lobe.kappa, bv), bv);
    }
    return (double)pf_vmf_sum_specular(pf_vmf_sum_without_base(sum, bv), c->wo, c->wi, PF_R(F0));
}
static double m_vmf_m16_base(const mctx *c) { return vmf_base_method(c, V16, 1); }
static double m_vmf_m16_base_fp(const mctx *c) { return vmf_base_method(c, V16, 0); }
static double m_vmf_m16_base_sum(const mctx *c) { return vmf_base_method(c, V16, 2); }
/* ---- end of the grazing-view block */
/* diffuse */
static double gg_diffuse(const mctx *c, int nodes, int n)
{
    return (double)pf_gg_diffuse_directional(pf_gg_grid_make(c->wo, fetch_slope(c, PF_R(0.0)), nodes, n), c->wi);
}
static double m_leadr_gg_matched3(const mctx *c) { return gg_diffuse(c, PF_GG_MATCHED, 3); }
static double m_leadr_gg_matched5(const mctx *c) { return gg_diffuse(c, PF_GG_MATCHED, 5); }
static double m_leadr_gg_hermite3(const mctx *c) { return gg_diffuse(c, PF_GG_HERMITE, 3); }
static double m_lambert_mesonormal(const mctx *c)
{
    return (double)(pf_max(pf_vec3_dot(pf_beckmann_mesonormal(fetch_slope(c, PF_R(0.0))), c->wi), PF_R(0.0)) * PF_INV_PI);
}
static double m_lambert_macro(const mctx *c) { return (double)(pf_max(c->wi.z, PF_R(0.0)) * PF_INV_PI); }
/* ours, not from the module: LEADR's grid times the horizon's visible-area ratios toward the
   view (as in pf_horizon_masking) and the light (capped at 1) */
static double m_leadr_gg_matched3_horizon_n32(const mctx *c)
{
    pf_slope_stats s0 = fetch_slope(c, PF_R(0.0));
    return (double)(pf_gg_diffuse_directional(pf_gg_grid_make(c->wo, s0, PF_GG_MATCHED, 3), c->wi) *
                    horizon_area(c->L, H32, c->x0, c->y0, c->n, c->wo, s0) *
                    pf_saturate(horizon_area(c->L, H32, c->x0, c->y0, c->n, c->wi, s0)));
}
/* pf_horizon.h: the matched grid with the HDF's visibility per facet */
static double m_horizon_diffuse_n32(const mctx *c)
{
    pf_gg_grid g = pf_gg_grid_make(c->wo, fetch_slope(c, PF_R(0.0)), PF_GG_MATCHED, 3);
    return (double)pf_horizon_diffuse_directional(g, c->wi, ctx_hdf(c, H32, c->wo), ctx_hdf(c, H32, c->wi));
}
static double m_horizon_diffuse_lod_n32(const mctx *c)
{
    pf_gg_grid g = pf_gg_grid_make(c->wo, fetch_slope(c, PF_R(0.0)), PF_GG_MATCHED, 3);
    return (double)pf_horizon_diffuse_lod(g, c->wi, ctx_hdf(c, H32, c->wo), ctx_hdf(c, H32, c->wi), ctx_lod(c),
                                          PF_R(HOR_LOD_FULL), PF_R(HOR_LOD_SMITH));
}
/* oracles (specular and diffuse): the reference with every texel visible, alone or times the
   footprint's Smith 1/(1 + Lambda_o + Lambda_i) */
static double novis_value(const mctx *c) { return c->task == T_SPEC ? c->novis->spec : c->novis->diffuse; }
static double m_oracle_histogram_no_vis(const mctx *c) { return novis_value(c); }
static double m_oracle_histogram_smith(const mctx *c)
{
    return pfb_oracle_smith(novis_value(c), c->wo, c->wi, fetch_slope(c, PF_R(0.0)));
}
/* colour (either map: task_cmap) */
static double m_height_visible(const mctx *c)
{
    pf_slope_stats s0 = fetch_slope(c, PF_R(0.0));
    return (double)colour_visible(task_cmap(c), fetch_height(c), pf_beckmann_lambda(c->wo, s0), pf_beckmann_lambda(c->wi, s0));
}
static double m_gauss_unmasked(const mctx *c) { return (double)colour_visible(task_cmap(c), fetch_height(c), PF_R(0.0), PF_R(0.0)); }
static double m_naive_mip(const mctx *c)
{
    const lib_maps *L = c->L;
    return (double)pf_scalar_moments_mean(
        pf_scalar_moments_sample(L->attr[c->task == T_BANDS], L->w, L->h, ctx_lod(c), ctx_u(c), ctx_v(c), PF_BORDER_WRAP));
}
static double m_mean_height(const mctx *c)
{
    return (double)cmap_filter(task_cmap(c), pf_scalar_moments_mean(fetch_height(c)), PF_R(0.0));
}

/* ---------------------------------------------------------------- the method registry
   One row per method: the tasks it answers (a bit per task; the colour methods answer both
   colour maps), its name (CSV, tables, charts), its evaluator, what a shader fetches for it (one
   texel of level log2 n of each pyramid named; "" nothing), and whether it is an oracle (it reads
   every texel of the footprint: not a shader method, so no cost row and never a candidate for
   "most accurate"). A task's methods are its rows in table order; its first is the library's
   default (the headline of the charts and tables). Everything downstream (samples, the CSVs,
   cost rows, charts, tables) follows this table: adding a method is a row here and its
   evaluator above. */
#define TB(t) (1u << (t))
#define TB_COLOUR (TB(T_RAMP) | TB(T_BANDS))
typedef double (*method_fn)(const mctx *c);
typedef struct method {
    unsigned tasks;
    const char *name;
    method_fn eval;
    const char *fetch;
    int oracle;
} method;
static const method methods[] = {
    { TB(T_MASK), "smith_g1_exact", m_smith_g1_exact, "slope moments", 0 },
    { TB(T_MASK), "smith_g1_fast", m_smith_g1_fast, "slope moments", 0 },
    { TB(T_MASK), "smith_g1_walter", m_smith_g1_walter, "slope moments", 0 },
    { TB(T_MASK), "no_masking", m_no_masking, "", 0 },
    { TB(T_MASK), "horizon_masking_n16", m_horizon_masking_n16, "slope moments, 2 azimuths of the n = 16 HDF moments", 0 },
    { TB(T_MASK), "horizon_masking_n32", m_horizon_masking_n32, "slope moments, 2 azimuths of the n = 32 HDF moments", 0 },
    { TB(T_MASK), "horizon_masking_lod_n32", m_horizon_masking_lod_n32, "slope moments, 2 azimuths of the n = 32 HDF moments", 0 },
    { TB(T_SPEC), "leadr_joint", m_leadr_joint, "slope moments", 0 },
    { TB(T_SPEC), "leadr_masking", m_leadr_masking, "slope moments", 0 },
    { TB(T_SPEC), "lean", m_lean, "slope moments", 0 },
    { TB(T_SPEC), "toksvig", m_toksvig, "average normal", 0 },
    { TB(T_SPEC), "naive_mip_normal", m_naive_mip_normal, "average normal", 0 },
    { TB(T_SPEC), "oracle_histogram_smith", m_oracle_histogram_smith, "every texel", 1 },
    { TB(T_SPEC), "oracle_histogram_no_vis", m_oracle_histogram_no_vis, "every texel", 1 },
    { TB(T_SPEC), "vmf_m1", m_vmf_m1, "1 vMF lobe texel", 0 },
    { TB(T_SPEC), "vmf_m2", m_vmf_m2, "2 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m4", m_vmf_m4, "4 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m8", m_vmf_m8, "8 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m4_mix_smith", m_vmf_m4_mix_smith, "4 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m8_mix_smith", m_vmf_m8_mix_smith, "8 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m16", m_vmf_m16, "16 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m4_scaled", m_vmf_m4_scaled, "4 vMF lobe texels, T, 8 nodes of S", 0 },
    { TB(T_SPEC), "vmf_m8_scaled", m_vmf_m8_scaled, "8 vMF lobe texels, T, 8 nodes of S", 0 },
    { TB(T_SPEC), "vmf_m8_scaled_s", m_vmf_m8_scaled_s, "8 vMF lobe texels, 8 nodes of S", 0 },
    { TB(T_SPEC), "vmf_m1_texel", m_vmf_m1_texel, "1 vMF lobe texel", 0 },
    { TB(T_SPEC), "vmf_m2_texel", m_vmf_m2_texel, "2 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m4_texel", m_vmf_m4_texel, "4 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m8_texel", m_vmf_m8_texel, "8 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m4_mix_smith_texel", m_vmf_m4_mix_smith_texel, "4 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m8_mix_smith_texel", m_vmf_m8_mix_smith_texel, "8 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m16_texel", m_vmf_m16_texel, "16 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m4_scaled_texel", m_vmf_m4_scaled_texel, "4 vMF lobe texels, T, 8 nodes of S", 0 },
    { TB(T_SPEC), "vmf_m8_scaled_texel", m_vmf_m8_scaled_texel, "8 vMF lobe texels, T, 8 nodes of S", 0 },
    { TB(T_SPEC), "vmf_m8_scaled_s_texel", m_vmf_m8_scaled_s_texel, "8 vMF lobe texels, 8 nodes of S", 0 },
    { TB(T_SPEC), "leadr_horizon_n32", m_leadr_horizon_n32, "slope moments, 2 x 2 azimuths of the n = 32 HDF moments", 0 },
    { TB(T_SPEC), "leadr_horizon_lod_n32", m_leadr_horizon_lod_n32,
      "slope moments, 2 x 2 azimuths of the n = 32 HDF moments", 0 },
    { TB(T_SPEC), "vmf_m16_horizon_n32", m_vmf_m16_horizon_n32, "16 vMF lobe texels, slope moments, 2 x 2 azimuths of the n = 32 HDF moments", 0 },
    { TB(T_SPEC), "vmf_m16_horizon_lod_n32", m_vmf_m16_horizon_lod_n32,
      "16 vMF lobe texels, slope moments, 2 x 2 azimuths of the n = 32 HDF moments", 0 },
    /* grazing views (issue 28, item 2) */
    { TB(T_SPEC), "leadr_base", m_leadr_base, "slope moments", 0 },
    { TB(T_SPEC), "vmf_m16_base", m_vmf_m16_base, "16 vMF lobe texels", 0 },
    { TB(T_SPEC), "vmf_m16_base_fp", m_vmf_m16_base_fp, "16 vMF lobe texels, slope moments", 0 },
    { TB(T_SPEC), "vmf_m16_base_sum", m_vmf_m16_base_sum, "16 vMF lobe texels", 0 },
    { TB(T_DIFF), "leadr_gg_matched3", m_leadr_gg_matched3, "slope moments", 0 },
    { TB(T_DIFF), "leadr_gg_matched5", m_leadr_gg_matched5, "slope moments", 0 },
    { TB(T_DIFF), "leadr_gg_hermite3", m_leadr_gg_hermite3, "slope moments", 0 },
    { TB(T_DIFF), "lambert_mesonormal", m_lambert_mesonormal, "slope moments", 0 },
    { TB(T_DIFF), "lambert_macro", m_lambert_macro, "", 0 },
    { TB(T_DIFF), "oracle_histogram_smith", m_oracle_histogram_smith, "every texel", 1 },
    { TB(T_DIFF), "oracle_histogram_no_vis", m_oracle_histogram_no_vis, "every texel", 1 },
    { TB(T_DIFF), "leadr_gg_matched3_horizon_n32", m_leadr_gg_matched3_horizon_n32,
      "slope moments, 2 x 2 azimuths of the n = 32 HDF moments", 0 },
    { TB(T_DIFF), "horizon_diffuse_n32", m_horizon_diffuse_n32, "slope moments, 2 x 2 azimuths of the n = 32 HDF moments", 0 },
    { TB(T_DIFF), "horizon_diffuse_lod_n32", m_horizon_diffuse_lod_n32,
      "slope moments, 2 x 2 azimuths of the n = 32 HDF moments", 0 },
    { TB_COLOUR, "height_visible", m_height_visible, "(E[h], E[h^2]), slope moments", 0 },
    { TB_COLOUR, "gauss_unmasked", m_gauss_unmasked, "(E[h], E[h^2])", 0 },
    { TB_COLOUR, "naive_mip", m_naive_mip, "the mip-mapped colour", 0 },
    { TB_COLOUR, "mean_height", m_mean_height, "(E[h], E[h^2])", 0 },
};
#define NMETHODS ((int)(sizeof methods / sizeof methods[0]))

/* a task's methods: task_meth[t][k] = the row of its k-th method (registry_init) */
static int task_meth[NTASK][MAX_TASK_METHODS], task_n[NTASK];
static void registry_init(void)
{
    int t, i;
    for (t = 0; t < NTASK; ++t) {
        task_n[t] = 0;
        for (i = 0; i < NMETHODS; ++i)
            if (methods[i].tasks & TB(t)) {
                if (task_n[t] == MAX_TASK_METHODS) fatal("more methods in a task than MAX_TASK_METHODS");
                task_meth[t][task_n[t]++] = i;
            }
    }
}
static const method *meth(int t, int k) { return &methods[task_meth[t][k]]; }
static const char *mname(int t, int k) { return meth(t, k)->name; }
/* MICROSURFACE_CHECK=1: the values of task t's methods in vals (computed through the memo of
   c) against each method alone (no memo), bit for bit */
static void check_memo(const mctx *c, int t, const double *vals)
{
    mctx a = *c;
    int k;
    a.memo = NULL;
    a.task = t;
    for (k = 0; k < task_n[t]; ++k) {
        double v = meth(t, k)->eval(&a);
        if (memcmp(&v, &vals[k], sizeof v) != 0) {
            fprintf(stderr, "microsurface: MICROSURFACE_CHECK: %s through the shared values (mmemo) differs from the "
                            "method alone\n", mname(t, k));
            exit(1);
        }
    }
}
/* the index of method `name` in task t (the report's named columns); a missing name is a bug */
static int mk(int t, const char *name)
{
    int k;
    for (k = 0; k < task_n[t]; ++k)
        if (!strcmp(mname(t, k), name)) return k;
    fprintf(stderr, "microsurface: internal: no method %s in task %s\n", name, task_name[t]);
    exit(1);
}
/* the task the cost section times a method in: its last (the colour methods: the banded map,
   6 knots, the costlier of the two) */
static int cost_task(const method *m)
{
    int t = NTASK - 1;
    while (t > 0 && !(m->tasks & TB(t))) --t;
    return t;
}

/* the storage pass: every method with its pyramids in 16- and 8-bit formats (bench/storage.h) */
#include "storage.h"

/* ---------------------------------------------------------------- sample store per cell */
/* a sample of task t: the references (full, in-footprint), then the task's methods */
#define ROWW(t) (NREF + task_n[t])
typedef struct cell {
    double *v;
    long n, cap;
} cell;

typedef struct stat {
    double rel_l2, max_rel, sum_d2, sum_r2;
    long samples;
    int valid;
} stat;

static cell cells[NTASK][NSIZE][NVIEW];
static stat stats[NKIND + 1][NREF][NTASK][MAX_TASK_METHODS][NSIZE][NVIEW];

/* append nrow samples of task t (ROWW(t) doubles each) */
static void cell_add_rows(cell *c, int t, const double *rows, long nrow)
{
    const int w = ROWW(t);
    if (c->n + nrow > c->cap) {
        while (c->n + nrow > c->cap) c->cap = c->cap ? 2 * c->cap : 256;
        c->v = (double *)realloc(c->v, (size_t)c->cap * (size_t)w * sizeof(double));
        if (!c->v) fatal("out of memory");
    }
    memcpy(c->v + (size_t)c->n * w, rows, (size_t)nrow * (size_t)w * sizeof(double));
    c->n += nrow;
}

static void cells_reduce(int kind)
{
    int t, s, v, k, r;
    long i;
    for (t = 0; t < NTASK; ++t)
        for (s = 0; s < NSIZE; ++s)
            for (v = 0; v < NVIEW; ++v) {
                cell *c = &cells[t][s][v];
                const int w = ROWW(t);
                for (r = 0; r < NREF; ++r) {
                    double rmax = 0, r2 = 0;
                    for (i = 0; i < c->n; ++i) {
                        double x = c->v[(size_t)i * w + r];
                        r2 += x * x;
                        if (fabs(x) > rmax) rmax = fabs(x);
                    }
                    for (k = 0; k < task_n[t]; ++k) {
                        stat *st = &stats[kind][r][t][k][s][v];
                        double d2 = 0, mr = 0;
                        for (i = 0; i < c->n; ++i) {
                            double x = c->v[(size_t)i * w + r], f = c->v[(size_t)i * w + NREF + k];
                            d2 += (f - x) * (f - x);
                            if (fabs(x) >= 0.1 * rmax && x != 0.0 && fabs(f - x) / fabs(x) > mr) mr = fabs(f - x) / fabs(x);
                        }
                        st->samples = c->n;
                        st->sum_d2 = d2;
                        st->sum_r2 = r2;
                        st->valid = c->n > 0 && r2 > 1e-300;
                        st->rel_l2 = st->valid ? sqrt(d2 / r2) : 0.0;
                        st->max_rel = mr;
                    }
                }
                c->n = 0;
            }
}

/* ---------------------------------------------------------------- one kind */
typedef struct corpus_info {
    double rms_x, rms_y, kurt_x, skew_x, corr, var_in_4096, mean_masking_60[NREF];
    double vis_num, vis_den; /* full reference: sum visible_area * area, sum area (4096 texels, 75 deg) */
    double mask_sum[NREF];
    long mask_n, samples_all, samples_culled, samples_backfacing;
    double seconds;
} corpus_info;
static corpus_info info[NKIND + 1];

/* features per footprint: texels / (pi L^2), L the kind's correlation length */
static double features(int kind, int si) { return (double)(1 << (2 * si)) / (3.14159265358979323846 * info[kind].corr * info[kind].corr); }

static void slope_moments_info(const pfm_surface *s, corpus_info *ci)
{
    long long n = (long long)s->w * s->h;
    double m1 = 0, m2 = 0, m3 = 0, m4 = 0, my2 = 0, m[5], tot, acc = 0;
    int x, y, cnt = 0;
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
    /* the fraction of the slope variance inside 64 x 64 footprints (the rest is the spread of
       their mean slopes: resolved geometry at that scale) */
    pfm_footprint_moments(s, 0, 0, s->w, m);
    tot = m[2] - m[0] * m[0] + m[3] - m[1] * m[1];
    for (y = 0; y + 64 <= s->h; y += 64)
        for (x = 0; x + 64 <= s->w; x += 64) {
            pfm_footprint_moments(s, x, y, 64, m);
            acc += m[2] - m[0] * m[0] + m[3] - m[1] * m[1];
            ++cnt;
        }
    ci->var_in_4096 = cnt ? acc / cnt / tot : 0.0;
}

/* ---- one kind's samples, in parallel (pf_parallel.h). Every work item writes only its own
   outputs (sample rows, per-footprint records); the reduction then appends them in item order,
   which is the order of the serial loop (view, azimuth, size, position, light), so every sum and
   every number of the CSVs is the same for any thread count. Random numbers (lights, footprint
   positions) are drawn before, serially, in the serial loop's order. */
typedef struct view_dir {
    int vi, ai;
    double wo[3];
} view_dir;
/* per footprint-view: what the corpus table needs (culling counts, mean masking, visible area) */
typedef struct fp_rec {
    int state; /* 0 shaded, 1 culled near edge-on, 2 back-facing */
    double mask[NREF], vis_num, vis_den;
} fp_rec;
typedef struct fp_item {
    int v, si, p0, p1; /* view v (views[]), size si, positions [p0, p1) of that list */
    double *rows[NTASK];
    long nrows[NTASK], cap[NTASK];
    fp_rec *rec;
    int nrec;
    store_acc *store; /* the storage pass's sums (bench/storage.h) */
} fp_item;
typedef struct kind_job {
    const pfm_surface *surf;
    const lib_maps *L;
    int nlights, nviews;
    const double (*lights)[3];
    const view_dir *views;
    unsigned char **vis_l, **vis_v; /* full visibility maps: per light, per view */
    unsigned char **box_l;          /* per size and light (si nlights + li): every footprint's in-footprint map */
    const int *pos;                 /* footprint cells per (view, size): pos + pos_off[v NSIZE + si] */
    const long long *pos_off;
    int *used_x0, *used_y0;         /* distinct footprints per size (the light box maps' items) */
    const long long *used_off;
    fp_item *items;
    long long nitems;
    long long *box_item_off; /* box items: [box_item_off[i], box_item_off[i + 1]) of the used list */
    store_set *store;        /* the pyramids in the storage formats (bench/storage.h) */
} kind_job;

/* a full visibility map per direction: the lights', then the views' */
static void vis_item(void *ctx, long long i)
{
    kind_job *J = (kind_job *)ctx;
    if (i < J->nlights) pfm_visibility_map(J->surf, J->lights[i], J->vis_l[i]);
    else pfm_visibility_map(J->surf, J->views[i - J->nlights].wo, J->vis_v[i - J->nlights]);
}

/* the in-footprint visibility toward every light of some footprints of one size, written into
   that size's box maps (footprints of one size do not overlap): marched once per footprint and
   light, read by every view */
static void box_item(void *ctx, long long i)
{
    kind_job *J = (kind_job *)ctx;
    long long q;
    int si = 0, li;
    while (J->used_off[si + 1] <= J->box_item_off[i]) ++si;
    for (q = J->box_item_off[i]; q < J->box_item_off[i + 1]; ++q)
        for (li = 0; li < J->nlights; ++li)
            pfm_visibility_map_box(J->surf, J->lights[li], J->used_x0[q], J->used_y0[q], 1 << si, J->vis_l[li],
                                   J->box_l[si * J->nlights + li]);
}

/* pfm_reference_visible_mean (tests/reference/pf_microsurface.h) of both colour attributes for
   the NREF visibility pairs, in one pass over the footprint instead of four: per texel the
   slope and the projected area ao once, then for each pair that sees the texel the same long
   double sums (num += ao a, den += ao) in the same texel order, so each mean is the
   function's, bit for bit (MICROSURFACE_CHECK=1 compares them). out[a][r]: attribute a, pair r. */
static void colour_reference(const pfm_surface *s, const unsigned char *const *vo, const unsigned char *const *vi, int x0,
                             int y0, int n, const double wo[3], double *const *attr, double out[2][NREF])
{
    long double num[2][NREF], den[NREF];
    int i, j, r, a;
    for (r = 0; r < NREF; ++r) num[0][r] = num[1][r] = den[r] = 0.0L;
    for (j = 0; j < n; ++j) {
        int y = pfmi_wrap(y0 + j, s->h);
        for (i = 0; i < n; ++i) {
            int x = pfmi_wrap(x0 + i, s->w), seen = 0;
            size_t id = (size_t)y * s->w + x;
            double sx, sy;
            long double ao;
            for (r = 0; r < NREF; ++r) seen |= (vo[r][id] && vi[r][id]) << r;
            if (!seen) continue;
            pfm_slope(s, x, y, &sx, &sy);
            ao = (long double)wo[2] - (long double)sx * (long double)wo[0] - (long double)sy * (long double)wo[1];
            if (!(ao > 0.0L)) continue;
            for (r = 0; r < NREF; ++r)
                if (seen >> r & 1) {
                    for (a = 0; a < 2; ++a) num[a][r] += ao * (long double)attr[a][id];
                    den[r] += ao;
                }
        }
    }
    for (a = 0; a < 2; ++a)
        for (r = 0; r < NREF; ++r) out[a][r] = den[r] > 0.0L ? (double)(num[a][r] / den[r]) : 0.0;
}

static double *item_row(fp_item *I, int t)
{
    const int w = ROWW(t);
    if (I->nrows[t] == I->cap[t]) {
        I->cap[t] = I->cap[t] ? 2 * I->cap[t] : 64;
        I->rows[t] = (double *)realloc(I->rows[t], (size_t)I->cap[t] * (size_t)w * sizeof(double));
        if (!I->rows[t]) fatal("out of memory");
    }
    return I->rows[t] + (size_t)I->nrows[t]++ * w;
}

/* the footprints of one item: references (full, in-footprint, no visibility) and every method,
   for every light and the mirror direction */
static void fp_item_run(void *ctx, long long it)
{
    kind_job *J = (kind_job *)ctx;
    fp_item *I = &J->items[it];
    const pfm_surface *surf = J->surf;
    const lib_maps *L = J->L;
    const view_dir *V = &J->views[I->v];
    const int W = surf->w, n = 1 << I->si, g = W / n, si = I->si;
    const size_t npix = (size_t)W * W;
    const double *wo_d = V->wo;
    const pf_vec3 wo = v3(wo_d);
    unsigned char *box_o = (unsigned char *)pfb_xcalloc(npix, 1), *vis_m = (unsigned char *)pfb_xcalloc(npix, 1);
    unsigned char *box_m = (unsigned char *)pfb_xcalloc(npix, 1);
    int p, li, k, r, t;
    I->rec = (fp_rec *)pfb_xcalloc((size_t)(I->p1 - I->p0), sizeof(fp_rec));
    for (p = I->p0; p < I->p1; ++p) {
        int cellid = J->pos[J->pos_off[I->v * NSIZE + si] + p];
        int x0 = (cellid % g) * n, y0 = (cellid / g) * n, lod = ilog2(n), first = 1;
        pf_real u = (PF_R(x0 / n) + PF_R(0.5)) / PF_R(g), v = (PF_R(y0 / n) + PF_R(0.5)) / PF_R(g);
        pf_slope_stats s0 = pf_slope_moments_stats(
            pf_slope_moments_sample(L->slope, W, W, PF_R(lod), u, v, PF_BORDER_WRAP), PF_R(0.0));
        pf_vec3 nbar = pf_beckmann_mesonormal(s0);
        fp_rec *rec = &I->rec[I->nrec++];
        pfm_visibility_map_box(surf, wo_d, x0, y0, n, J->vis_v[I->v], box_o);
        for (li = 0; li <= J->nlights; ++li) {
            double wi_d[3], *row;
            const unsigned char *vo_set[3], *vi_set[3];
            pfm_shade sh[3];
            mctx c;
            mmemo memo;
            if (li < J->nlights) {
                memcpy(wi_d, J->lights[li], sizeof wi_d);
                vi_set[0] = J->vis_l[li];
                vi_set[1] = J->box_l[si * J->nlights + li]; /* box_item */
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
                        vis_m[(size_t)yy * W + xx] = (unsigned char)pfm_visible(surf, xx, yy, wi_d);
                    }
                pfm_visibility_map_box(surf, wi_d, x0, y0, n, vis_m, box_m);
                vi_set[0] = vis_m;
                vi_set[1] = box_m;
            }
            /* the full reference, the in-footprint one and the exact histogram without
               visibility (oracle), in one pass */
            vo_set[0] = J->vis_v[I->v];
            vo_set[1] = box_o;
            vo_set[2] = NULL;
            vi_set[2] = NULL;
            pfm_reference_shade_set(surf, 3, vo_set, vi_set, x0, y0, n, wo_d, wi_d, BASE_SIGMA, F0, sh);
            /* the view at or below the footprint's mesosurface (culled by a renderer), or within
               CULL_AREA of edge-on: LEADR's normalization by the mesosurface's projected area A
               (eqs. 2-3) assumes the visible projected micro-area is A, and an n x n footprint
               seen nearly edge-on breaks that (visible area up to ~30 A measured), so its
               reference radiance ~1/A is meaningless (and a renderer gives it a share ~A of a
               pixel) */
            if (!(sh[0].area > CULL_AREA * wo_d[2])) {
                rec->state = sh[0].area > 0.0 ? 1 : 2;
                break; /* A does not depend on the light: the first one decides */
            }
            c.L = L;
            c.x0 = x0;
            c.y0 = y0;
            c.n = n;
            c.wo = wo;
            c.wi = v3(wi_d);
            c.novis = &sh[2];
            memset(&memo, 0, sizeof memo);
            c.memo = &memo;
            if (first) { /* masking depends on the view only */
                c.task = T_MASK;
                row = item_row(I, T_MASK);
                for (r = 0; r < NREF; ++r) row[r] = sh[r].masking;
                for (k = 0; k < task_n[T_MASK]; ++k) row[NREF + k] = meth(T_MASK, k)->eval(&c);
                if (check_mode) check_memo(&c, T_MASK, row + NREF);
                store_rows(J->store, &I->store, T_MASK, &c, row);
                for (r = 0; r < NREF; ++r) rec->mask[r] = sh[r].masking;
                rec->vis_num = sh[0].visible_area * sh[0].area;
                rec->vis_den = sh[0].area;
                first = 0;
            }
            for (t = T_SPEC; t <= T_DIFF; ++t) {
                c.task = t;
                row = item_row(I, t);
                for (r = 0; r < NREF; ++r) row[r] = t == T_SPEC ? sh[r].spec : sh[r].diffuse;
                for (k = 0; k < task_n[t]; ++k) row[NREF + k] = meth(t, k)->eval(&c);
                if (check_mode) check_memo(&c, t, row + NREF);
                store_rows(J->store, &I->store, t, &c, row);
            }
            if (sh[0].joint > 1e-9) {
                double cref[2][NREF];
                colour_reference(surf, vo_set, vi_set, x0, y0, n, wo_d, L->attr_d, cref);
                for (t = T_RAMP; t <= T_BANDS; ++t) {
                    c.task = t;
                    row = item_row(I, t);
                    for (r = 0; r < NREF; ++r) {
                        row[r] = cref[t - T_RAMP][r];
                        if (check_mode) {
                            double v = pfm_reference_visible_mean(surf, vo_set[r], vi_set[r], x0, y0, n, wo_d, L->attr_d[t - T_RAMP]);
                            if (memcmp(&v, &row[r], sizeof v) != 0) {
                                fprintf(stderr, "microsurface: MICROSURFACE_CHECK: the colour reference differs from "
                                                "pfm_reference_visible_mean\n");
                                exit(1);
                            }
                        }
                    }
                    for (k = 0; k < task_n[t]; ++k) row[NREF + k] = meth(t, k)->eval(&c);
                    if (check_mode) check_memo(&c, t, row + NREF);
                    store_rows(J->store, &I->store, t, &c, row);
                }
            }
        }
    }
    free(box_o);
    free(vis_m);
    free(box_m);
}

/* the full visibility maps of the kept kind's views (the cost section's kind), kept for the
   cost section: its view is one of them (60 degrees, azimuth 10), not marched again */
#define NVIEWDIR (NVIEW * 8)
static unsigned char *kept_view_map[NVIEWDIR];
static double kept_view_dir[NVIEWDIR][3];
static void kept_views_free(void)
{
    int v;
    for (v = 0; v < NVIEWDIR; ++v) {
        free(kept_view_map[v]);
        kept_view_map[v] = NULL;
    }
}

static void run_kind(int kind, const settings *S, pfm_surface *keep, lib_maps *keep_maps)
{
    pfm_surface surf;
    lib_maps L;
    pfm_params P = pfm_params_default(kind == KIND_MAP ? PFM_GAUSSIAN : kind);
    const int W = kind == KIND_MAP ? map_surf.w : S->map;
    const size_t npix = (size_t)W * W;
    int si, vi, ai, li, p, v, t, r, nviews = 0;
    long long i, q, npos_all = 0;
    double (*lights)[3] = (double (*)[3])pfb_xcalloc((size_t)S->nlights, sizeof *lights);
    view_dir views[NVIEWDIR];
    corpus_info *ci = &info[kind];
    pfb_rng rg = pfb_rng_make(0x6d6963726f000000ULL + (unsigned long long)kind);
    double t0 = pfb_now_ns();
    kind_job J;
    long long pos_off[NVIEWDIR * NSIZE + 1], used_off[NSIZE + 1];
    int *pos;
    char label[200];
    const char *kn = kname(kind);
    if (S->naz > 8) fatal("at most 8 view azimuths");
    if (kind == KIND_MAP) { /* a copy: the loaded map stays for the cost section */
        if (pfm_surface_alloc(&surf, W, W, 1.0) != 0) fatal("out of memory");
        memcpy(surf.height, map_surf.height, npix * sizeof(double));
        pfm_surface_bounds(&surf);
    } else if (pfm_surface_make(&surf, W, W, 1.0, P) != 0) {
        fprintf(stderr, "microsurface: pfm_surface_make failed for %s\n", pfm_kind_name(kind));
        exit(1);
    }
    lib_maps_build(&L, &surf, kn);
    slope_moments_info(&surf, ci);
    ci->corr = kind == KIND_MAP ? map_stats.corr : P.corr_texels;
    /* hemisphere lights: uniform in solid angle, theta_i <= 85 degrees */
    for (li = 0; li < S->nlights; ++li) {
        double cz = cos(85.0 * DEG) + (1.0 - cos(85.0 * DEG)) * pfb_unif(&rg);
        double ph = 2.0 * 3.14159265358979323846 * pfb_unif(&rg);
        dir_from_angles(acos(cz), ph, lights[li]);
    }
    /* the views, and the footprints of each view and size: every position where there are at
       most maxpos, else a seeded subset (drawn here, in the order of the serial loop) */
    for (vi = 0; vi < NVIEW; ++vi) {
        int naz = view_deg[vi] == 0.0 ? 1 : S->naz;
        for (ai = 0; ai < naz; ++ai, ++nviews) {
            views[nviews].vi = vi;
            views[nviews].ai = ai;
            dir_from_angles(view_deg[vi] * DEG, (10.0 + 90.0 * ai) * DEG, views[nviews].wo);
            for (si = 0; si < NSIZE; ++si) {
                int n = 1 << si, g = W / n, npos = g * g, maxpos = n <= 16 ? 4 * S->maxpos : S->maxpos;
                npos_all += npos < maxpos ? npos : maxpos;
            }
        }
    }
    pos = (int *)pfb_xcalloc((size_t)npos_all, sizeof *pos);
    q = 0;
    for (v = 0; v < nviews; ++v)
        for (si = 0; si < NSIZE; ++si) {
            int n = 1 << si, g = W / n, npos = g * g, maxpos = n <= 16 ? 4 * S->maxpos : S->maxpos;
            int count = npos < maxpos ? npos : maxpos;
            pos_off[v * NSIZE + si] = q;
            for (p = 0; p < count; ++p) pos[q++] = npos <= maxpos ? p : pfb_int(&rg, npos);
        }
    pos_off[nviews * NSIZE] = q;
    memset(&J, 0, sizeof J);
    J.surf = &surf;
    J.L = &L;
    J.nlights = S->nlights;
    J.nviews = nviews;
    J.lights = (const double (*)[3])lights;
    J.views = views;
    J.pos = pos;
    J.pos_off = pos_off;
    J.store = store_build(&L);
    /* full visibility maps, one per light and per view, shared by every footprint */
    J.vis_l = (unsigned char **)pfb_xcalloc((size_t)S->nlights, sizeof *J.vis_l);
    J.vis_v = (unsigned char **)pfb_xcalloc((size_t)nviews, sizeof *J.vis_v);
    for (li = 0; li < S->nlights; ++li) J.vis_l[li] = (unsigned char *)pfb_xcalloc(npix, 1);
    for (v = 0; v < nviews; ++v) J.vis_v[v] = (unsigned char *)pfb_xcalloc(npix, 1);
    snprintf(label, sizeof label, "microsurface: %s: full visibility maps", kn);
    ms_parallel_for(PS_VIS, S->nlights + nviews, vis_item, &J, label);
    /* the distinct footprints per size over every view: their in-footprint visibility toward
       each light (box_item), and the scaling function's T at the scaled levels */
    J.used_x0 = (int *)pfb_xcalloc((size_t)npos_all, sizeof(int));
    J.used_y0 = (int *)pfb_xcalloc((size_t)npos_all, sizeof(int));
    q = 0;
    for (si = 0; si < NSIZE; ++si) {
        int n = 1 << si, g = W / n;
        char *seen = (char *)pfb_xcalloc((size_t)g * g, 1);
        used_off[si] = q;
        for (v = 0; v < nviews; ++v)
            for (i = pos_off[v * NSIZE + si]; i < pos_off[v * NSIZE + si + 1]; ++i)
                if (!seen[pos[i]]) {
                    seen[pos[i]] = 1;
                    J.used_x0[q] = (pos[i] % g) * n;
                    J.used_y0[q] = (pos[i] / g) * n;
                    ++q;
                }
        free(seen);
        snprintf(label, sizeof label, "microsurface: %s: scaling function T of the shaded texels", kn);
        scale_T_fill(&L, n, J.used_x0 + used_off[si], J.used_y0 + used_off[si], q - used_off[si], label);
    }
    used_off[NSIZE] = q;
    J.used_off = used_off;
    J.box_l = (unsigned char **)pfb_xcalloc((size_t)NSIZE * S->nlights, sizeof *J.box_l);
    for (i = 0; i < (long long)NSIZE * S->nlights; ++i) J.box_l[i] = (unsigned char *)pfb_xcalloc(npix, 1);
    /* box items: runs of footprints of one size, about FP_ITEM_TEXELS texels each */
    {
        long long nb = 0;
        J.box_item_off = (long long *)pfb_xcalloc((size_t)q + 1, sizeof(long long));
        for (si = 0; si < NSIZE; ++si) {
            long long per = FP_ITEM_TEXELS >> (2 * si) > 0 ? FP_ITEM_TEXELS >> (2 * si) : 1;
            for (i = used_off[si]; i < used_off[si + 1]; i += per) J.box_item_off[nb++] = i;
        }
        J.box_item_off[nb] = q;
        snprintf(label, sizeof label, "microsurface: %s: in-footprint visibility toward the lights", kn);
        ms_parallel_for(PS_BOX, nb, box_item, &J, label);
    }
    /* footprint items, in the serial loop's order: view (and azimuth), size, runs of positions */
    for (i = 0; i < 2; ++i) { /* pass 0 counts, pass 1 fills */
        long long m = 0;
        for (v = 0; v < nviews; ++v)
            for (si = 0; si < NSIZE; ++si) {
                int count = (int)(pos_off[v * NSIZE + si + 1] - pos_off[v * NSIZE + si]);
                int per = FP_ITEM_TEXELS >> (2 * si) > 0 ? FP_ITEM_TEXELS >> (2 * si) : 1;
                for (p = 0; p < count; p += per, ++m)
                    if (i) {
                        J.items[m].v = v;
                        J.items[m].si = si;
                        J.items[m].p0 = p;
                        J.items[m].p1 = p + per < count ? p + per : count;
                    }
            }
        if (!i) {
            J.nitems = m;
            J.items = (fp_item *)pfb_xcalloc((size_t)m, sizeof(fp_item));
        }
    }
    snprintf(label, sizeof label, "microsurface: %s: footprints (references and methods)", kn);
    ms_parallel_for(PS_FP, J.nitems, fp_item_run, &J, label);
    /* the reduction, in item order (the serial loop's) */
    for (i = 0; i < J.nitems; ++i) {
        fp_item *I = &J.items[i];
        vi = views[I->v].vi;
        for (t = 0; t < NTASK; ++t) {
            cell_add_rows(&cells[t][I->si][vi], t, I->rows[t], I->nrows[t]);
            free(I->rows[t]);
        }
        for (p = 0; p < I->nrec; ++p) {
            const fp_rec *rec = &I->rec[p];
            ci->samples_all++; /* footprint-views */
            if (rec->state) {
                ci->samples_culled += rec->state == 1;
                ci->samples_backfacing += rec->state == 2;
                continue;
            }
            if (vi == 4) {
                for (r = 0; r < NREF; ++r) ci->mask_sum[r] += rec->mask[r];
                ci->mask_n++;
            }
            if (vi == 6 && I->si == NSIZE - 1) {
                ci->vis_num += rec->vis_num;
                ci->vis_den += rec->vis_den;
            }
        }
        free(I->rec);
        store_reduce(kind, I->store, I->si, vi);
    }
    cells_reduce(kind);
    store_free(J.store);
    fprintf(stderr, "microsurface: %s: scaling function S and T: %.1f s, %ld patches' samples\n", kn, L.sc_seconds,
            L.sc_patches);
    for (r = 0; r < NREF; ++r) ci->mean_masking_60[r] = ci->mask_n ? ci->mask_sum[r] / (double)ci->mask_n : 0.0;
    ci->seconds = (pfb_now_ns() - t0) * 1e-9;
    for (li = 0; li < S->nlights; ++li) free(J.vis_l[li]);
    for (v = 0; v < nviews; ++v)
        if (keep) {
            kept_view_map[v] = J.vis_v[v];
            memcpy(kept_view_dir[v], views[v].wo, sizeof kept_view_dir[v]);
        } else
            free(J.vis_v[v]);
    for (i = 0; i < (long long)NSIZE * S->nlights; ++i) free(J.box_l[i]);
    free(J.vis_l);
    free(J.vis_v);
    free(J.box_l);
    free(J.box_item_off);
    free(J.used_x0);
    free(J.used_y0);
    free(J.items);
    free(pos);
    free(lights);
    if (keep) {
        *keep = surf;
        *keep_maps = L;
    } else {
        lib_maps_free(&L);
        pfm_surface_free(&surf);
    }
}

/* ---------------------------------------------------------------- cost against footprint size
   Rows: the brute force (NBRUTE rows), then every shader method of the error CSV under the
   same name (colour methods with the banded map: 6 knots, the costlier of the two maps). */
#define NBRUTE 4
enum { C_MARCH, C_BOX_MARCH, C_REF, C_FLOAT };
static const char *brute_name[NBRUTE] = { "brute_force_march_and_shade", "brute_force_box_march_and_shade",
                                          "brute_force_shade_only", "brute_force_float_shade" };
#define NCOST_MAX (NBRUTE + NMETHODS)
typedef struct cost_row {
    const char *name;
    const method *m; /* NULL for the brute force */
    int task;        /* the task it is timed in (cost_task) */
    double med[NSIZE], q1[NSIZE], q3[NSIZE];
    int batch[NSIZE];
} cost_row;
static cost_row cost[NCOST_MAX];
static int ncost = 0, c_leadr = -1;
static volatile double sink;

#define COST_LIGHTS 4
#define COST_FP 256 /* footprints per size (seeded), cycled through */

static int cost_find(const char *name)
{
    int i;
    for (i = 0; i < ncost; ++i)
        if (!strcmp(cost[i].name, name)) return i;
    return -1;
}

/* the cost section's full visibility maps (the view's, the lights'), in parallel */
typedef struct cost_vis_job {
    const pfm_surface *surf;
    int n;
    const double *dirs[1 + COST_LIGHTS];
    unsigned char *maps[1 + COST_LIGHTS];
} cost_vis_job;
static void cost_vis_item(void *ctx, long long i)
{
    cost_vis_job *J = (cost_vis_job *)ctx;
    pfm_visibility_map(J->surf, J->dirs[i], J->maps[i]);
}

/* Everything the timings need (visibility maps, the scaling function's T of the timed
   footprints) is computed first, in parallel; the timing loop itself runs alone on one thread,
   after every parallel step of the run. */
static void run_cost(const settings *S, const pfm_surface *surf, lib_maps *L)
{
    int W = surf->w, si, mi, rep, b, li, k;
    size_t npix = (size_t)W * W;
    double wo_d[3], lights[COST_LIGHTS][3];
    unsigned char *vis_o = (unsigned char *)pfb_xcalloc(1, npix), *vis_l[COST_LIGHTS];
    unsigned char *sv_o = (unsigned char *)pfb_xcalloc(1, npix), *sv_i = (unsigned char *)pfb_xcalloc(1, npix);
    int fx[NSIZE][COST_FP], fy[NSIZE][COST_FP], fl[NSIZE][COST_FP];
    double *times = (double *)pfb_xcalloc((size_t)S->cost_reps, sizeof(double));
    pf_vec3 wo, wil[COST_LIGHTS];
    pfb_rng r = pfb_rng_make(0xc057c057ULL);
    double cost_c0, cost_w0;
    cost_vis_job VJ;
    pfb_progress prog;
    /* the rows */
    ncost = 0;
    for (k = 0; k < NBRUTE; ++k) {
        cost[ncost].name = brute_name[k];
        cost[ncost].m = NULL;
        cost[ncost].task = -1;
        ++ncost;
    }
    for (k = 0; k < NMETHODS; ++k) { /* every shader method once, in registry order */
        if (methods[k].oracle) continue;
        cost[ncost].name = methods[k].name;
        cost[ncost].m = &methods[k];
        cost[ncost].task = cost_task(&methods[k]);
        ++ncost;
    }
    c_leadr = cost_find("leadr_joint");
    dir_from_angles(60.0 * DEG, 10.0 * DEG, wo_d);
    wo = v3(wo_d);
    memset(sv_o, 0, npix);
    memset(sv_i, 0, npix);
    VJ.surf = surf;
    VJ.n = 0;
    for (k = 0; k < NVIEWDIR; ++k) /* the view's map from the error run, when it marched it */
        if (kept_view_map[k] && !memcmp(kept_view_dir[k], wo_d, sizeof wo_d)) break;
    if (k < NVIEWDIR) {
        memcpy(vis_o, kept_view_map[k], npix);
    } else {
        VJ.dirs[VJ.n] = wo_d;
        VJ.maps[VJ.n++] = vis_o;
    }
    for (li = 0; li < COST_LIGHTS; ++li) {
        double cz = cos(80.0 * DEG) + (1.0 - cos(80.0 * DEG)) * pfb_unif(&r);
        dir_from_angles(acos(cz), 2.0 * 3.14159265358979323846 * pfb_unif(&r), lights[li]);
        wil[li] = v3(lights[li]);
        vis_l[li] = (unsigned char *)pfb_xcalloc(npix, 1);
        VJ.dirs[VJ.n] = lights[li];
        VJ.maps[VJ.n++] = vis_l[li];
    }
    ms_parallel_for(PS_COST_VIS, VJ.n, cost_vis_item, &VJ, "microsurface: cost: visibility maps");
    /* the seeded footprints and lights of every size (drawn in the order of the timing loop) */
    for (si = 0; si < NSIZE; ++si) {
        int n = 1 << si, g = W / n;
        for (k = 0; k < COST_FP; ++k) {
            int c = pfb_int(&r, g * g);
            fx[si][k] = (c % g) * n;
            fy[si][k] = (c / g) * n;
            fl[si][k] = pfb_int(&r, COST_LIGHTS);
        }
        /* the scaling function's T of these footprints, computed (and cached) before timing */
        scale_T_fill(L, n, fx[si], fy[si], COST_FP, "microsurface: cost: scaling function T of the timed texels");
    }
    cost_c0 = cpu_s();
    cost_w0 = pfb_wall_s();
    prog = pfb_progress_start("microsurface: cost (timed alone, one thread)", (long long)NSIZE * ncost);
    for (si = 0; si < NSIZE; ++si) {
        int n = 1 << si;
        for (mi = 0; mi < ncost; ++mi) {
            cost_row *cr = &cost[mi];
            /* batch: about 1-4 ms of work per repetition */
            int batch = mi == C_MARCH ? (n * n >= 4096 ? 2 : (n * n >= 256 ? 16 : 128))
                      : mi == C_BOX_MARCH ? (n * n >= 1024 ? 8 : 128)
                      : mi == C_REF ? (n * n >= 1024 ? 32 : 1024)
                      : mi == C_FLOAT ? (n * n >= 1024 ? 128 : 2048) : 4096;
            if (S->quick && batch > 8) batch /= 2;
            for (rep = 0; rep < S->cost_reps; ++rep) {
                double t0 = pfb_now_ns(), acc = 0;
                for (b = 0; b < batch; ++b) {
                    int q = (b + rep * 7) % COST_FP, x0 = fx[si][q], y0 = fy[si][q], lq = fl[si][q];
                    const double *wi_d = lights[lq];
                    if (mi == C_MARCH || mi == C_BOX_MARCH) {
                        /* march the footprint's texels toward the view and the light (every
                           occluder, or the box's only), then shade */
                        int x, y;
                        pfm_shade sh;
                        for (y = 0; y < n; ++y)
                            for (x = 0; x < n; ++x) {
                                int xx = (x0 + x) % W, yy = (y0 + y) % W;
                                size_t id = (size_t)yy * W + xx;
                                if (mi == C_MARCH) {
                                    sv_o[id] = (unsigned char)pfm_visible(surf, xx, yy, wo_d);
                                    sv_i[id] = (unsigned char)pfm_visible(surf, xx, yy, wi_d);
                                } else {
                                    sv_o[id] = (unsigned char)pfm_visible_box(surf, xx, yy, wo_d, x0, y0, n);
                                    sv_i[id] = (unsigned char)pfm_visible_box(surf, xx, yy, wi_d, x0, y0, n);
                                }
                            }
                        sh = pfm_reference_shade(surf, sv_o, sv_i, x0, y0, n, wo_d, wi_d, BASE_SIGMA, F0);
                        acc += sh.spec + sh.diffuse;
                    } else if (mi == C_FLOAT) {
                        /* the brute force in the library's own arithmetic: every texel's base lobe
                           (pf_leadr_specular of a one-slope footprint) from level 0 of the slope
                           pyramid, cached visibility, projected-area weights (eqs. 1-3) */
                        const unsigned char *vl = vis_l[lq];
                        pf_vec3 wi = wil[lq];
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
                        pfm_shade sh = pfm_reference_shade(surf, vis_o, vis_l[lq], x0, y0, n, wo_d, wi_d,
                                                           BASE_SIGMA, F0);
                        acc += sh.spec + sh.diffuse;
                    } else {
                        mctx c;
                        c.L = L;
                        c.task = cr->task;
                        c.x0 = x0;
                        c.y0 = y0;
                        c.n = n;
                        c.wo = wo;
                        c.wi = wil[lq];
                        c.novis = NULL;
                        c.memo = NULL; /* each method timed with all its own work */
                        acc += cr->m->eval(&c);
                    }
                }
                times[rep] = (pfb_now_ns() - t0) / (double)batch;
                sink += acc;
            }
            qsort(times, (size_t)S->cost_reps, sizeof(double), cmp_double);
            cr->med[si] = times[S->cost_reps / 2];
            cr->q1[si] = times[S->cost_reps / 4];
            cr->q3[si] = times[(3 * S->cost_reps) / 4];
            cr->batch[si] = batch;
            pfb_progress_update(&prog, (long long)si * ncost + mi + 1);
        }
    }
    pfb_progress_end(&prog);
    pass_add(PS_COST, cost_c0, cost_w0);
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

/* pooled rel L2 over a set of cells: sqrt(sum d2 / sum r2); -1 if none */
static double pooled(int kind, int r, int t, int k, int s_lo, int s_hi, int v_lo, int v_hi)
{
    double d2 = 0, r2 = 0;
    int s, v;
    for (s = s_lo; s <= s_hi; ++s)
        for (v = v_lo; v <= v_hi; ++v)
            if (stats[kind][r][t][k][s][v].valid) {
                d2 += stats[kind][r][t][k][s][v].sum_d2;
                r2 += stats[kind][r][t][k][s][v].sum_r2;
            }
    return r2 > 0 ? sqrt(d2 / r2) : -1.0;
}

/* the same over every kind of the run */
static int run_kinds[NKIND + 1], n_run_kinds = 0;
static double pooled_all(int r, int t, int k, int s_lo, int s_hi, int v_lo, int v_hi)
{
    double d2 = 0, r2 = 0;
    int s, v, ko;
    for (ko = 0; ko < n_run_kinds; ++ko)
        for (s = s_lo; s <= s_hi; ++s)
            for (v = v_lo; v <= v_hi; ++v) {
                const stat *st = &stats[run_kinds[ko]][r][t][k][s][v];
                if (!st->valid) continue;
                d2 += st->sum_d2;
                r2 += st->sum_r2;
            }
    return r2 > 0 ? sqrt(d2 / r2) : -1.0;
}

/* error-against-cost regimes: (footprint sizes, reference, footprint size of the cost) */
#define NEC 2
static const int ec_lo[NEC] = { 0, 4 }, ec_hi[NEC] = { 2, NSIZE - 1 }, ec_ref[NEC] = { R_FULL, R_BOX };
static const char *ec_name[NEC] = { "small", "large" };
static const char *ec_title[NEC] = { "footprints of 1-16 texels, full reference, cost at 16 texels",
                                     "footprints of 256-4096 texels, in-footprint reference, cost at 4096 texels" };

static void fmt_err(char *buf, size_t n, double e) /* buf: at least 16 bytes */
{
    if (e < 0) snprintf(buf, n, "-");
    else if (e >= 0.995) snprintf(buf, n, "%.3g", e);
    else snprintf(buf, n, "%.3f", e);
}

/* "in / full" pair of pooled errors */
static const char *fmt_pair(char *buf, size_t n, int kind, int t, int k, int s_lo, int s_hi, int v_lo, int v_hi)
{
    char a[16], b[16];
    fmt_err(a, sizeof a, pooled(kind, R_BOX, t, k, s_lo, s_hi, v_lo, v_hi));
    fmt_err(b, sizeof b, pooled(kind, R_FULL, t, k, s_lo, s_hi, v_lo, v_hi));
    snprintf(buf, n, "%s / %s", a, b);
    return buf;
}

/* the kinds of this run, in display order (run_kinds, n_run_kinds above): the corpus, or the
   user's map alone */

static void write_errors_csv(const settings *S)
{
    FILE *f = open_out(S, "microsurface_errors.csv");
    int ko, kind, t, k, s, v, r;
    fprintf(f, "task,method,kind,reference,footprint_texels,view_deg,rel_l2,max_rel,samples,sum_sq_err,sum_sq_ref\n");
    for (t = 0; t < NTASK; ++t)
        for (k = 0; k < task_n[t]; ++k)
            for (ko = 0; ko < n_run_kinds; ++ko)
                for (r = 0; r < NREF; ++r)
                    for (s = 0; s < NSIZE; ++s)
                        for (v = 0; v < NVIEW; ++v) {
                            stat *st;
                            kind = run_kinds[ko];
                            st = &stats[kind][r][t][k][s][v];
                            if (!st->valid) continue;
                            fprintf(f, "%s,%s,%s,%s,%d,%g,%.6g,%.6g,%ld,%.9g,%.9g\n", task_name[t], mname(t, k),
                                    kname(kind), ref_name[r], 1 << (2 * s), view_deg[v], st->rel_l2,
                                    st->max_rel, st->samples, st->sum_d2, st->sum_r2);
                        }
    fclose(f);
}

static void write_cost_csv(const settings *S)
{
    FILE *f = open_out(S, "microsurface_cost.csv");
    int m, s;
    fprintf(f, "method,footprint_texels,ns_per_footprint,ns_q1,ns_q3,reps,batch,x_leadr_specular\n");
    for (m = 0; m < ncost; ++m)
        for (s = 0; s < NSIZE; ++s)
            fprintf(f, "%s,%d,%.6g,%.6g,%.6g,%d,%d,%.6g\n", cost[m].name, 1 << (2 * s), cost[m].med[s], cost[m].q1[s],
                    cost[m].q3[s], S->cost_reps, cost[m].batch[s], cost[m].med[s] / cost[c_leadr].med[s]);
    fclose(f);
}

/* chart data: wide tables, '?' = missing (negative values) */
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
static pfb_progress chart_progress; /* gnuplot runs, counted by make_charts */
static long long charts_tried = 0;
static void chart(const settings *S, const char *name, const char *title, const char *xlabel,
                  const char *ylabel, int logx, int ncol, double ymin)
{
    char cmd[4096], dat[1024], svg[1024];
    snprintf(dat, sizeof dat, "%s/%s.dat", S->out, name);
    snprintf(svg, sizeof svg, "%s/%s.svg", S->out, name);
    if (S->charts) {
        snprintf(cmd, sizeof cmd,
                 "gnuplot -e \"datf='%s'; outf='%s'; ttl='%s'; xl='%s'; yl='%s'; logx=%d; ncol=%d; ymin=%g\" %s",
                 dat, svg, title, xlabel, ylabel, logx, ncol, ymin, S->gp);
        if (system(cmd) != 0) { /* a missing chart is a failed run, never a silent gap */
            fprintf(stderr, "microsurface: gnuplot failed for %s\n", name);
            exit(1);
        }
        charts_made++;
    }
    remove(dat);
    pfb_progress_update(&chart_progress, ++charts_tried);
}

#define YMIN 1e-4 /* lower end of the error charts' y axes */
/* the per-task charts and tables: gaussian_fine (the papers' regime), or the user's map */
static int chart_kind = PFM_GAUSSIAN_FINE;
#define CHART_KIND chart_kind
static void make_charts(const settings *S)
{
    static char colbuf[MAX_TASK_METHODS + 2][96];
    double x[32], y[32 * (MAX_TASK_METHODS + 2)];
    const char *cols[MAX_TASK_METHODS + 2];
    char name[256], title[512], dat[300];
    int t, k, s, v, ko, nc;
    /* per task: size, view (and on the corpus: kinds, features); cost; error against cost */
    chart_progress = pfb_progress_start(S->charts ? "microsurface: charts (gnuplot)" : NULL,
                                        NTASK * (map_path ? 2 : 4) + 1 + (NTASK - 1) * NEC);
    for (t = 0; t < NTASK; ++t) {
        int nm = task_n[t];
        /* error vs footprint size: every method against the in-footprint reference, the
           library's method also against the full one */
        nc = nm + 1;
        for (k = 0; k < nm; ++k) cols[k] = mname(t, k);
        snprintf(colbuf[0], sizeof colbuf[0], "%s vs full reference", mname(t, 0));
        cols[nm] = colbuf[0];
        for (s = 0; s < NSIZE; ++s) {
            x[s] = (double)(1 << (2 * s));
            for (k = 0; k < nm; ++k) y[s * nc + k] = pooled(CHART_KIND, R_BOX, t, k, s, s, 0, POOL_VIEW_HI);
            y[s * nc + nm] = pooled(CHART_KIND, R_FULL, t, 0, s, s, 0, POOL_VIEW_HI);
        }
        snprintf(name, sizeof name, "microsurface_size_%s", task_name[t]);
        snprintf(dat, sizeof dat, "%s.dat", name);
        write_dat(S, dat, nc, cols, NSIZE, x, y);
        snprintf(title, sizeof title, "%s on %s, in-footprint reference: error vs footprint (views 0-75 deg)",
                 task_name[t], kname(CHART_KIND));
        chart(S, name, title, "footprint (texels, log)", "relative L2 error (log)", 1, nc, YMIN);
        /* error vs view angle, footprints of 256-4096 texels pooled */
        for (v = 0; v < NVIEW; ++v) {
            x[v] = view_deg[v];
            for (k = 0; k < nm; ++k) y[v * nc + k] = pooled(CHART_KIND, R_BOX, t, k, 4, NSIZE - 1, v, v);
            y[v * nc + nm] = pooled(CHART_KIND, R_FULL, t, 0, 4, NSIZE - 1, v, v);
        }
        snprintf(name, sizeof name, "microsurface_view_%s", task_name[t]);
        snprintf(dat, sizeof dat, "%s.dat", name);
        write_dat(S, dat, nc, cols, NVIEW, x, y);
        snprintf(title, sizeof title, "%s on %s, in-footprint reference: error vs view (256-4096 texels)",
                 task_name[t], kname(CHART_KIND));
        chart(S, name, title, "view angle theta_o (degrees)", "relative L2 error (log)", 0, nc, YMIN);
        if (map_path) continue; /* one kind: no comparison between kinds */
        /* the library's method on every kind (in-footprint reference) */
        for (s = 0; s < NSIZE; ++s) {
            x[s] = (double)(1 << (2 * s));
            for (ko = 0; ko < NKIND; ++ko) y[s * NKIND + ko] = pooled(kind_order[ko], R_BOX, t, 0, s, s, 0, POOL_VIEW_HI);
        }
        for (ko = 0; ko < NKIND; ++ko) cols[ko] = pfm_kind_name(kind_order[ko]);
        snprintf(name, sizeof name, "microsurface_kinds_%s", task_name[t]);
        snprintf(dat, sizeof dat, "%s.dat", name);
        write_dat(S, dat, NKIND, cols, NSIZE, x, y);
        snprintf(title, sizeof title, "%s: %s on every kind, in-footprint reference (views 0-75 deg)", task_name[t],
                 mname(t, 0));
        chart(S, name, title, "footprint (texels, log)", "relative L2 error (log)", 1, NKIND, YMIN);
        /* error vs features per footprint: the two isotropic Gaussian kinds, both references;
           rows of the two kinds interleaved by x, '?' where a column has no point */
        {
            const int kk[2] = { PFM_GAUSSIAN, PFM_GAUSSIAN_FINE };
            int i = 0, a = 0, bb = 0, j;
            for (j = 0; j < 2; ++j) {
                snprintf(colbuf[2 * j], sizeof colbuf[0], "%s (L = %g), in-footprint", pfm_kind_name(kk[j]), info[kk[j]].corr);
                snprintf(colbuf[2 * j + 1], sizeof colbuf[0], "%s (L = %g), full", pfm_kind_name(kk[j]), info[kk[j]].corr);
                cols[2 * j] = colbuf[2 * j];
                cols[2 * j + 1] = colbuf[2 * j + 1];
            }
            while (a < NSIZE || bb < NSIZE) {
                int use0 = bb >= NSIZE || (a < NSIZE && features(kk[0], a) <= features(kk[1], bb));
                int s2 = use0 ? a++ : bb++, kind = kk[use0 ? 0 : 1];
                x[i] = features(kind, s2);
                for (j = 0; j < 4; ++j) y[i * 4 + j] = -1.0;
                y[i * 4 + (use0 ? 0 : 2)] = pooled(kind, R_BOX, t, 0, s2, s2, 0, POOL_VIEW_HI);
                y[i * 4 + (use0 ? 1 : 3)] = pooled(kind, R_FULL, t, 0, s2, s2, 0, POOL_VIEW_HI);
                ++i;
            }
            snprintf(name, sizeof name, "microsurface_features_%s", task_name[t]);
            snprintf(dat, sizeof dat, "%s.dat", name);
            write_dat(S, dat, 4, cols, i, x, y);
            snprintf(title, sizeof title, "%s: %s vs features per footprint (views 0-75 deg)", task_name[t],
                     mname(t, 0));
            chart(S, name, title, "footprint texels / (pi L^2), L = correlation length (log)",
                  "relative L2 error (log)", 1, 4, YMIN);
        }
    }
    /* cost: the brute force and the library's method of each task */
    {
        static const char *shown[] = { "brute_force_march_and_shade", "brute_force_box_march_and_shade",
                                       "brute_force_shade_only", "brute_force_float_shade", "leadr_joint", "toksvig",
                                       "leadr_gg_matched3", "smith_g1_exact", "height_visible", "horizon_masking_n32",
                                       "vmf_m4", "vmf_m8" };
        int ns = (int)(sizeof shown / sizeof shown[0]), i;
        for (s = 0; s < NSIZE; ++s) {
            x[s] = (double)(1 << (2 * s));
            for (i = 0; i < ns; ++i) {
                int c = cost_find(shown[i]);
                y[s * ns + i] = c >= 0 ? cost[c].med[s] : -1.0;
            }
        }
        for (i = 0; i < ns; ++i) cols[i] = shown[i];
        write_dat(S, "microsurface_cost.dat", ns, cols, NSIZE, x, y);
        chart(S, "microsurface_cost", map_path ? "Cost per footprint: brute force vs filtered (your map, view 60 deg)"
                                               : "Cost per footprint: brute force vs filtered (gaussian kind, view 60 deg)",
              "footprint (texels, log)", "median ns per footprint (log)", 1, ns, 0.0);
    }
    /* error against cost: one point per shader method (a column each, one row each), error
       pooled over every kind of the run and views 0-75 deg, cost from the cost section */
    for (t = 0; t < NTASK; ++t) {
        int e, j;
        if (t == T_RAMP) continue; /* the colour methods are timed with the banded map */
        for (e = 0; e < NEC; ++e) {
            int n = 0, cs = e == 0 ? 2 : NSIZE - 1;
            for (k = 0; k < task_n[t] && n < MAX_TASK_METHODS + 2; ++k) {
                int c = cost_find(mname(t, k));
                if (meth(t, k)->oracle || c < 0) continue;
                cols[n] = mname(t, k);
                x[n] = cost[c].med[cs] > 0.0 ? cost[c].med[cs] : 1e-3;
                ++n;
            }
            for (k = 0, j = 0; k < task_n[t] && j < n; ++k) {
                int i;
                if (meth(t, k)->oracle || cost_find(mname(t, k)) < 0) continue;
                for (i = 0; i < n; ++i) y[j * n + i] = -1.0;
                y[j * n + j] = pooled_all(ec_ref[e], t, k, ec_lo[e], ec_hi[e], 0, POOL_VIEW_HI);
                ++j;
            }
            snprintf(name, sizeof name, "microsurface_errcost_%s_%s", task_name[t], ec_name[e]);
            snprintf(dat, sizeof dat, "%s.dat", name);
            write_dat(S, dat, n, cols, n, x, y);
            snprintf(title, sizeof title, "%s: error against cost, %s (every kind, views 0-75 deg)", task_name[t],
                     ec_title[e]);
            chart(S, name, title, "median ns per footprint, fetch included (log)", "relative L2 error (log)", 1, n,
                  YMIN);
        }
    }
    pfb_progress_end(&chart_progress);
}

/* "in / full" pooled pair in a ring of static buffers (several in one printf) */
static const char *PR(int kind, int t, int k, int s_lo, int s_hi, int v_lo, int v_hi)
{
    static char ring[48][80];
    static int next = 0;
    char *b = ring[next];
    next = (next + 1) % 48;
    return fmt_pair(b, sizeof ring[0], kind, t, k, s_lo, s_hi, v_lo, v_hi);
}

static void kinds_table(FILE *f, int si)
{
    int t, k, ko;
    fprintf(f, "| task | method |");
    for (ko = 0; ko < NKIND; ++ko) fprintf(f, " %s |", pfm_kind_name(kind_order[ko]));
    fprintf(f, "\n|---|---|");
    for (ko = 0; ko < NKIND; ++ko) fprintf(f, "--:|");
    fprintf(f, "\n");
    for (t = 0; t < NTASK; ++t)
        for (k = 0; k < task_n[t]; ++k) {
            fprintf(f, "| %s | %s |", k == 0 ? task_name[t] : "", mname(t, k));
            for (ko = 0; ko < NKIND; ++ko) fprintf(f, " %s |", PR(kind_order[ko], t, k, si, si, 0, POOL_VIEW_HI));
            fprintf(f, "\n");
        }
}

/* per-task tables of CHART_KIND: error by footprint and view, with the size and view charts */
static void write_task_tables(FILE *f)
{
    static const int tab_sizes[4] = { 0, 2, 4, 6 };      /* 1, 16, 256, 4096 texels */
    static const int tab_views[6] = { 0, 2, 4, 6, 7, 8 }; /* 0, 30, 60, 75, 80, 85 deg */
    const int VH = POOL_VIEW_HI;
    int t, k, s, i;
    /* ---- per-task tables */
    for (t = 0; t < NTASK; ++t) {
        fprintf(f, "\n### %s\n\n", task_title[t]);
        fprintf(f, "`%s` kind, relative L2 error (*in-footprint / full* reference) by footprint (texels) and "
                   "view angle.\n\n", kname(CHART_KIND));
        fprintf(f, "| method | texels |");
        for (i = 0; i < 6; ++i) fprintf(f, " %g deg |", view_deg[tab_views[i]]);
        fprintf(f, " 0-75 deg pooled |\n|---|--:|");
        for (i = 0; i < 7; ++i) fprintf(f, "--:|");
        fprintf(f, "\n");
        for (k = 0; k < task_n[t]; ++k)
            for (s = 0; s < 4; ++s) {
                int si = tab_sizes[s];
                fprintf(f, "| %s | %d |", s == 0 ? mname(t, k) : "", 1 << (2 * si));
                for (i = 0; i < 6; ++i)
                    fprintf(f, " %s |", PR(CHART_KIND, t, k, si, si, tab_views[i], tab_views[i]));
                fprintf(f, " %s |\n", PR(CHART_KIND, t, k, si, si, 0, VH));
            }
        fprintf(f, "\n![%s: error vs footprint](microsurface_size_%s.svg)\n", task_name[t], task_name[t]);
        fprintf(f, "![%s: error vs view](microsurface_view_%s.svg)\n", task_name[t], task_name[t]);
    }
}

/* the cost section: brute force and every shader method by footprint size */
static void write_cost_section(FILE *f, const settings *S)
{
    const int TOP = NSIZE - 1;
    int s, c;
    /* ---- cost */
    fprintf(f, "\n### Cost against footprint size\n\n");
    fprintf(f, "%s, view 60 degrees, %d seeded footprints per size and %d seeded lights; "
               "median ns per footprint over %d repetitions (quartiles in `microsurface_cost.csv`). "
               "Every shader method of the error tables is timed under the same name, with the pyramid "
               "fetches it needs (bilinear samples at the texel centre; `no_masking` and `lambert_macro` "
               "need none); the colour methods with the banded map (6 knots; the ramp has 2); `no_masking` and "
               "`lambert_macro` (%.2g ns) are the timing loop's own floor. "
               "Brute force (march + shade): marches the visibility of the footprint's texels toward "
               "the view and the light (2 n^2 rays; every occluder, or in the box variant only those "
               "inside the footprint), then sums the reference shading (specular, diffuse, masking "
               "together). Brute force (shade only): the same sum with the visibility maps already "
               "computed (cached maps, as in the error runs); these are the long double reference of "
               "`tests/reference/pf_microsurface.h`. Brute force (float shade): the same sum in the library's own "
               "arithmetic (pf_real), every texel's base lobe by `pf_leadr_specular` of a one-slope "
               "footprint, slopes read from level 0 of the pyramid, cached visibility: what a "
               "supersampling shader would pay, without the march.\n\n",
            map_path ? "Your map" : "Gaussian kind", COST_FP, COST_LIGHTS, S->cost_reps,
            cost[cost_find("no_masking")].med[TOP]);
    fprintf(f, "| method |");
    for (s = 0; s < NSIZE; s += 2) fprintf(f, " %d texels (ns) |", 1 << (2 * s));
    fprintf(f, " x `pf_leadr_specular` at 4096 |\n|---|");
    for (s = 0; s < NSIZE; s += 2) fprintf(f, "--:|");
    fprintf(f, "--:|\n");
    for (c = 0; c < ncost; ++c) {
        fprintf(f, "| %s |", cost[c].name);
        for (s = 0; s < NSIZE; s += 2) fprintf(f, " %.4g |", cost[c].med[s]);
        fprintf(f, " %.3g |\n", cost[c].med[TOP] / cost[c_leadr].med[TOP]);
    }
    fprintf(f, "\n![cost per footprint](microsurface_cost.svg)\n");
    fprintf(f, "\nError against cost, every shader method of each task (one point each; relative L2 error "
               "pooled over %s and views 0-75 degrees): small footprints (1-16 texels) against the full "
               "reference, where occlusion from outside the footprint dominates (the horizon-map masking "
               "methods' regime), and large ones (256-4096 texels) against the in-footprint reference.\n\n",
            map_path ? "your map" : "every kind");
    for (c = 0; c < NTASK; ++c) {
        if (c == T_RAMP) continue;
        for (s = 0; s < NEC; ++s)
            fprintf(f, "![%s: error against cost, %s](microsurface_errcost_%s_%s.svg)\n", task_name[c], ec_title[s],
                    task_name[c], ec_name[s]);
    }
}

static void write_md(const settings *S, double total_s)
{
    FILE *f = open_out(S, "microsurface.md");
    const int G = PFM_GAUSSIAN, FN = PFM_GAUSSIAN_FINE, TOP = NSIZE - 1, VH = POOL_VIEW_HI;
    const int k_hor16 = mk(T_MASK, "horizon_masking_n16"), k_hor32 = mk(T_MASK, "horizon_masking_n32");
    const int k_oracle = mk(T_SPEC, "oracle_histogram_smith"), k_toksvig = mk(T_SPEC, "toksvig");
    int t, ko, kind;
    fprintf(f, "## Ground truth on synthetic microsurfaces\n\n");
    fprintf(f, "Generated by `bench/microsurface.c` (%s mode, %.0f s); every number below is computed "
               "in that run. Raw cells: `microsurface_errors.csv` (with `sum_sq_err` and `sum_sq_ref`, so "
               "any set of cells pools as sqrt(sum sum_sq_err / sum sum_sq_ref)), timings: "
               "`microsurface_cost.csv`.\n\n",
            S->quick ? "QUICK (smoke run: do not publish)" : "full", total_s);
    fprintf(f, "**Reference.** A brute-force shading of the pixel footprint texel by texel on an actual "
               "height field (`tests/reference/pf_microsurface.h`): micro-normals from central differences of the "
               "heights, masking toward the view and shadowing toward the light by marching the "
               "(bilinear, periodic) height field, a narrow Beckmann base lobe of slope deviation %.2g "
               "with its own Smith G2 (specular, f0 = 1: no Fresnel) or a Lambertian one of albedo 1 "
               "(diffuse), normalized by the projected area of the mesosurface (LEADR 2013 eqs. 1-3). "
               "The masking reference is the visible fraction of the footprint's front-facing projected "
               "micro-area (the quantity Smith's G1 = 1/(1 + Lambda) estimates). "
               "The filtered answers read only what a shader can fetch: one texel of the mip pyramids "
               "of the slope moments, average normals, (E[h], E[h^2]) and the colour attribute, built "
               "by `pf_moments.h` from the same heights.\n\n", BASE_SIGMA);
    fprintf(f, "**Two references.** *in-footprint*: only occluders inside the footprint's box cast "
               "masking and shadows (a ray that leaves the n x n box counts as visible): what a filtered "
               "model of the footprint's own statistics can represent, so its error is the **model's "
               "error**. *full*: every occluder of the height field, bumps outside the footprint "
               "included: what a renderer **without resolved geometry** would show. At footprints "
               "smaller than the features most shadows come from outside the footprint; in LEADR's "
               "pipeline those come from the displaced geometry and shadow maps, not from the filtered "
               "BRDF. Neither is exactly what Smith's statistics describe (an endless surface with the "
               "footprint's slopes): the box also frees the rays of texels near its edges, so at "
               "footprints only a few features wide the in-footprint reference has fewer shadows than "
               "such a surface, and it can sit further from the model than the full one. Tables give "
               "both as *in-footprint / full*; charts use the in-footprint reference, plus the library's "
               "method against the full one.\n\n");
    fprintf(f, "**Corpus.** %d x %d periodic maps (texel 1), the seven kinds of `pfm_params_default` "
               "(below; `gaussian_fine` is the isotropic Gaussian generator with a %g-texel correlation "
               "length, so that footprints of 256-4096 texels hold tens to hundreds of features: the "
               "regime the filtering papers claim); footprints of n x n texels (n = 1, 2, ..., 64) "
               "aligned so that each is exactly one texel of pyramid level log2(n), at most %d positions "
               "per size up to 256 texels and %d above (all of them where there are fewer; a seeded "
               "subset otherwise); views theta_o = 0..85 degrees at %d azimuth(s); %d seeded lights over "
               "the hemisphere (theta_i <= 85 degrees) plus the mirror direction of the view about each "
               "footprint's mesonormal (the specular peak).\n\n",
            S->map, S->map, info[FN].corr, 4 * S->maxpos, S->maxpos, S->naz, S->nlights);
    fprintf(f, "**Error.** Per cell (kind, reference, task, method, footprint size, view angle) over its "
               "lights, azimuths and positions: relative L2 error sqrt(sum (f - ref)^2 / sum ref^2); the "
               "CSV also has the max relative error over the samples with ref >= 10%% of the cell's "
               "largest. Pooled values (charts, tables) are the same ratio over the union of cells "
               "(views 0-75 degrees unless stated: the grazing views have their own columns). "
               "Footprint-views whose mesosurface projected area A = (nbar.wo)/(nbar.z) is below %g of a "
               "flat footprint's (cos theta_o) are skipped: at or below the mesosurface a renderer culls "
               "them, and near edge-on the normalization by A (LEADR eqs. 2-3) breaks down for an n x n "
               "footprint (its visible projected micro-area, which must equal A, was measured up to ~30 "
               "A), so its reference radiance ~1/A means nothing, and a renderer would give it a share "
               "~A of a pixel. The table below gives the share skipped per kind (nearly all at 70-85 "
               "degrees and footprints of 1-256 texels).\n\n", CULL_AREA);
    fprintf(f, "| kind | correlation length L (texels) | correlation areas pi L^2 in 4096 texels | slope RMS x | "
               "slope RMS y | slope skewness x | slope kurtosis x | share of the slope variance inside "
               "4096-texel footprints | mean G1 at 60 deg (in-footprint / full) | visible projected area at "
               "75 deg, 4096 texels (reference consistency, ideal 1) | footprint-views skipped: back-facing "
               "/ near edge-on |\n");
    fprintf(f, "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    for (ko = 0; ko < NKIND; ++ko) {
        const corpus_info *ci;
        kind = kind_order[ko];
        ci = &info[kind];
        fprintf(f, "| %s | %g | %.0f | %.3f | %.3f | %.2f | %.2f | %.2f | %.3f / %.3f | %.3f | %.1f%% / %.1f%% |\n",
                pfm_kind_name(kind), ci->corr, features(kind, TOP), ci->rms_x, ci->rms_y, ci->skew_x, ci->kurt_x,
                ci->var_in_4096, ci->mean_masking_60[R_BOX], ci->mean_masking_60[R_FULL],
                ci->vis_den > 0 ? ci->vis_num / ci->vis_den : 0.0,
                100.0 * (double)ci->samples_backfacing / (double)(ci->samples_all > 0 ? ci->samples_all : 1),
                100.0 * (double)ci->samples_culled / (double)(ci->samples_all > 0 ? ci->samples_all : 1));
    }
    fprintf(f, "\nThe last column checks the reference itself: every viewing ray meets exactly one visible "
               "point, so the visible projected micro-area must equal the mesosurface's. The march sees "
               "the bilinear surface, which at a 3-texel correlation length is rougher than its "
               "central-difference slopes say: on `gaussian_fine` the full reference loses that share "
               "of the visible area at grazing views, and errors of that order there are the "
               "reference's, not the method's.\n");
    fprintf(f, "\nMethods: masking: `pf_beckmann_g1` (exact), `pf_g1_beckmann_fast`, `pf_g1_beckmann_walter` "
               "on the footprint's slope statistics, no masking (G1 = 1), and the horizon-map masking of "
               "`pf_horizon.h` (`horizon_masking_n16`, `horizon_masking_n32`: `pf_horizon_masking`, Smith's G1 "
               "times the footprint's visible projected area estimated from the filtered horizon "
               "distribution of the two stored azimuths around the view's, n = 16 or 32 azimuths, HDF moment "
               "pyramids built per kind by `pf_horizon_pyramid` with a %d-texel march; docs/horizon.md): they "
               "see the bumps outside the footprint, so their reference is the full one; "
               "`horizon_masking_lod_n32` (`pf_horizon_masking_lod`) fades that horizon term to Smith by mip "
               "level, whole up to 16 texels and none from 4096 texels on. Specular: `pf_leadr_specular` "
               "(joint masking-shadowing), `pf_leadr_specular_masking`, LEAN (P22 at the half vector's slope, "
               "no masking, Jacobian or projected area), Toksvig (Cook-Torrance Beckmann lobe around the "
               "normalized average normal, roughness widened by `pf_toksvig_beckmann_m`), the naive "
               "mip-mapped normal (same lobe, base roughness only), and the multi-lobe BRDF of `pf_vmf.h` "
               "(Wu et al. 2019 eqs. 4-5; docs/vmf.md): `vmf_m1` .. `vmf_m8` fetch m vMF lobes per texel "
               "of a lobe pyramid fitted by EM, each lobe a Beckmann lobe in slope space with the base "
               "roughness added, Smith G of the mixture's slope mean and covariance; "
               "`vmf_m4_mix_smith`, `vmf_m8_mix_smith` use the mixture's exact Smith Lambda instead; `vmf_m16` "
               "has 16 lobes; `vmf_m4_scaled`, `vmf_m8_scaled` multiply `vmf_m4`, `vmf_m8` by the scaling function "
               "T(x) S(wi, wo) of Wu et al. 2019 (eqs. 12-14) at 4096-texel footprints (unscaled below: "
               "docs/vmf.md), S (6 x 6 x 5 nodes) per kind fitted to the in-footprint effective BRDF of 16 "
               "patches with a prior toward 1, T per pyramid texel (`vmf_m8_scaled_s`: S alone). "
               "Diffuse: `pf_gg_diffuse_directional` "
               "(LEADR eq. 21) with the matched grid N = 3, 5 and Gauss-Hermite N = 3; Lambert on the "
               "mesonormal; Lambert on the macro normal; `leadr_gg_matched3_horizon_n32`, the matched grid times "
               "the horizon map's visible-area ratios (`pf_horizon_visible_area`, n = 32) toward the view and "
               "toward the light (capped at 1): an ad-hoc combination of ours, measured here, not a formula "
               "of the module; `horizon_diffuse_n32` (`pf_horizon_diffuse_directional`), the matched grid "
               "with Smith's factor replaced by each grid facet's horizon visibility toward the view and the "
               "light (the HDF conditioned on the facet's slope) joined by Tan et al.'s eq. 28, and "
               "`horizon_diffuse_lod_n32` (`pf_horizon_diffuse_lod`), that faded to `leadr_gg_matched3` by "
               "mip level like the masking. Two oracles (not shader methods: they read every "
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
               "mean height.\n", HOR_STEPS);
    /* ---- key numbers */
    fprintf(f, "\n**Key numbers** (relative L2 error pooled over views 0-75 degrees, *in-footprint / full* "
               "reference; the tables below have the rest):\n\n");
    {
        char a[16], b[16], c[16];
        fprintf(f, "- masking at 16 texels against the **full** reference (occlusion by bumps outside the "
                   "footprint), `horizon_masking_n32` / `horizon_masking_n16` / `pf_beckmann_g1`:");
        for (ko = 0; ko < NKIND; ++ko) {
            kind = kind_order[ko];
            fmt_err(a, sizeof a, pooled(kind, R_FULL, T_MASK, k_hor32, 2, 2, 0, VH));
            fmt_err(b, sizeof b, pooled(kind, R_FULL, T_MASK, k_hor16, 2, 2, 0, VH));
            fmt_err(c, sizeof c, pooled(kind, R_FULL, T_MASK, 0, 2, 2, 0, VH));
            fprintf(f, "%s %s %s / %s / %s", ko ? ";" : "", pfm_kind_name(kind), a, b, c);
        }
        fmt_err(a, sizeof a, pooled_all(R_BOX, T_MASK, k_hor32, TOP, TOP, 0, VH));
        fmt_err(b, sizeof b, pooled_all(R_BOX, T_MASK, 0, TOP, TOP, 0, VH));
        fmt_err(c, sizeof c, pooled_all(R_BOX, T_MASK, mk(T_MASK, "horizon_masking_lod_n32"), TOP, TOP, 0, VH));
        fprintf(f, ". At 4096 texels against the in-footprint reference, every kind pooled: `horizon_masking_n32` "
                   "%s, `horizon_masking_lod_n32` %s, `pf_beckmann_g1` %s.\n", a, c, b);
        fprintf(f, "- diffuse at 16 texels against the **full** reference, `horizon_diffuse_n32` / "
                   "`leadr_gg_matched3_horizon_n32` / `leadr_gg_matched3`:");
        for (ko = 0; ko < NKIND; ++ko) {
            kind = kind_order[ko];
            fmt_err(a, sizeof a, pooled(kind, R_FULL, T_DIFF, mk(T_DIFF, "leadr_gg_matched3_horizon_n32"), 2, 2, 0, VH));
            fmt_err(b, sizeof b, pooled(kind, R_FULL, T_DIFF, 0, 2, 2, 0, VH));
            fmt_err(c, sizeof c, pooled(kind, R_FULL, T_DIFF, mk(T_DIFF, "horizon_diffuse_n32"), 2, 2, 0, VH));
            fprintf(f, "%s %s %s / %s / %s", ko ? ";" : "", pfm_kind_name(kind), c, a, b);
        }
        fprintf(f, ".\n");
    }
    fprintf(f, "- `gaussian_fine` (L = %g texels, ~%.0f correlation areas per 4096-texel footprint), 4096 "
               "texels: masking `pf_beckmann_g1` %s (no masking %s); specular `pf_leadr_specular` %s, "
               "Toksvig %s, LEAN %s, naive mip-mapped normal %s, the exact slope histogram with the same "
               "Smith term (oracle) %s; diffuse LEADR grid (matched, N = 3) %s, Lambert on the mesonormal "
               "%s; colour (banded map) visible-height filtering %s, mip-mapped colour %s.\n",
            info[FN].corr, features(FN, TOP), PR(FN, T_MASK, 0, TOP, TOP, 0, VH),
            PR(FN, T_MASK, mk(T_MASK, "no_masking"), TOP, TOP, 0, VH), PR(FN, T_SPEC, 0, TOP, TOP, 0, VH),
            PR(FN, T_SPEC, k_toksvig, TOP, TOP, 0, VH), PR(FN, T_SPEC, mk(T_SPEC, "lean"), TOP, TOP, 0, VH),
            PR(FN, T_SPEC, mk(T_SPEC, "naive_mip_normal"), TOP, TOP, 0, VH), PR(FN, T_SPEC, k_oracle, TOP, TOP, 0, VH),
            PR(FN, T_DIFF, 0, TOP, TOP, 0, VH), PR(FN, T_DIFF, mk(T_DIFF, "lambert_mesonormal"), TOP, TOP, 0, VH),
            PR(FN, T_BANDS, 0, TOP, TOP, 0, VH), PR(FN, T_BANDS, mk(T_BANDS, "naive_mip"), TOP, TOP, 0, VH));
    fprintf(f, "- the same at 256 texels (~%.0f correlation areas): masking %s, specular `pf_leadr_specular` %s "
               "(oracle %s), diffuse %s.\n",
            features(FN, 4), PR(FN, T_MASK, 0, 4, 4, 0, VH), PR(FN, T_SPEC, 0, 4, 4, 0, VH),
            PR(FN, T_SPEC, k_oracle, 4, 4, 0, VH), PR(FN, T_DIFF, 0, 4, 4, 0, VH));
    fprintf(f, "- `gaussian` (L = %g texels, ~%.0f correlation areas per 4096 texels): at 4096 texels masking "
               "%s, specular `pf_leadr_specular` %s (oracle %s%s), diffuse %s; at 16 texels, where the "
               "features are larger than the footprint, specular %s and diffuse %s, masking %s: the gap "
               "between the two references is the occlusion cast from outside the footprint.\n",
            info[G].corr, features(G, TOP), PR(G, T_MASK, 0, TOP, TOP, 0, VH), PR(G, T_SPEC, 0, TOP, TOP, 0, VH),
            PR(G, T_SPEC, k_oracle, TOP, TOP, 0, VH),
            pooled(G, R_BOX, T_SPEC, k_oracle, TOP, TOP, 0, VH) < 0.5 * pooled(G, R_BOX, T_SPEC, 0, TOP, TOP, 0, VH)
                ? ": most of LEADR's error there is the Gaussian fit of a slope histogram made of few features, "
                  "not the masking model"
                : "",
            PR(G, T_DIFF, 0, TOP, TOP, 0, VH), PR(G, T_SPEC, 0, 2, 2, 0, VH),
            PR(G, T_DIFF, 0, 2, 2, 0, VH), PR(G, T_MASK, 0, 2, 2, 0, VH));
    fprintf(f, "- non-Gaussian kinds, 4096 texels: specular `pf_leadr_specular` on ridges %s, craters %s, "
               "tiles %s; diffuse LEADR grid on ridges %s, craters %s, tiles %s (anisotropic Gaussian: "
               "specular %s, diffuse %s).\n",
            PR(PFM_RIDGES, T_SPEC, 0, TOP, TOP, 0, VH), PR(PFM_CRATERS, T_SPEC, 0, TOP, TOP, 0, VH),
            PR(PFM_TILES, T_SPEC, 0, TOP, TOP, 0, VH), PR(PFM_RIDGES, T_DIFF, 0, TOP, TOP, 0, VH),
            PR(PFM_CRATERS, T_DIFF, 0, TOP, TOP, 0, VH), PR(PFM_TILES, T_DIFF, 0, TOP, TOP, 0, VH),
            PR(PFM_GAUSSIAN_ANISO, T_SPEC, 0, TOP, TOP, 0, VH), PR(PFM_GAUSSIAN_ANISO, T_DIFF, 0, TOP, TOP, 0, VH));
    fprintf(f, "- `peaked` (log-normal bumps, slope kurtosis %.1f: peaked and heavy-tailed like photographed "
               "textures, unimodal), 4096 texels: masking `pf_beckmann_g1` %s; specular `pf_leadr_specular` %s "
               "(oracle %s), Toksvig %s; diffuse LEADR grid %s; at 256 texels specular %s, diffuse %s.\n",
            info[PFM_PEAKED].kurt_x, PR(PFM_PEAKED, T_MASK, 0, TOP, TOP, 0, VH), PR(PFM_PEAKED, T_SPEC, 0, TOP, TOP, 0, VH),
            PR(PFM_PEAKED, T_SPEC, k_oracle, TOP, TOP, 0, VH), PR(PFM_PEAKED, T_SPEC, k_toksvig, TOP, TOP, 0, VH),
            PR(PFM_PEAKED, T_DIFF, 0, TOP, TOP, 0, VH), PR(PFM_PEAKED, T_SPEC, 0, 4, 4, 0, VH),
            PR(PFM_PEAKED, T_DIFF, 0, 4, 4, 0, VH));
    {
        int cm = cost_find("brute_force_march_and_shade"), cb = cost_find("brute_force_box_march_and_shade");
        int cf = cost_find("brute_force_float_shade");
        fprintf(f, "- cost at 4096 texels: brute force %.3g ns per footprint (march + shade; %.3g with the march "
                   "limited to the footprint), `pf_leadr_specular` with its fetch %.3g ns: %.3g times cheaper "
                   "(at 1 texel: %.3g times); against a brute force in the library's own float arithmetic "
                   "with cached visibility, %.3g times.\n",
                cost[cm].med[TOP], cost[cb].med[TOP], cost[c_leadr].med[TOP], cost[cm].med[TOP] / cost[c_leadr].med[TOP],
                cost[cm].med[0] / cost[c_leadr].med[0], cost[cf].med[TOP] / cost[c_leadr].med[TOP]);
    }
    /* ---- error against features per footprint */
    fprintf(f, "\n### Error against features per footprint\n\n");
    fprintf(f, "The library's method of each task on the two isotropic Gaussian kinds (same slope RMS, "
               "correlation lengths %g and %g texels), by the number of correlation areas pi L^2 in the "
               "footprint; *in-footprint / full*, views 0-75 degrees pooled. If the error is a function "
               "of the features per footprint, the two kinds' rows interleave smoothly.\n\n",
            info[G].corr, info[FN].corr);
    fprintf(f, "| kind | texels | features | masking `pf_beckmann_g1` | specular `pf_leadr_specular` | "
               "specular oracle (exact histogram + Smith) | diffuse LEADR grid | colour (bands) |\n");
    fprintf(f, "|---|--:|--:|--:|--:|--:|--:|--:|\n");
    {
        const int kk[2] = { PFM_GAUSSIAN, PFM_GAUSSIAN_FINE };
        int a = 2, bb = 2;
        while (a < NSIZE || bb < NSIZE) {
            int use0 = bb >= NSIZE || (a < NSIZE && features(kk[0], a) <= features(kk[1], bb));
            int s2 = use0 ? a++ : bb++;
            kind = kk[use0 ? 0 : 1];
            fprintf(f, "| %s | %d | %.2g | %s | %s | %s | %s | %s |\n", pfm_kind_name(kind), 1 << (2 * s2),
                    features(kind, s2), PR(kind, T_MASK, 0, s2, s2, 0, VH), PR(kind, T_SPEC, 0, s2, s2, 0, VH),
                    PR(kind, T_SPEC, k_oracle, s2, s2, 0, VH), PR(kind, T_DIFF, 0, s2, s2, 0, VH),
                    PR(kind, T_BANDS, 0, s2, s2, 0, VH));
        }
    }
    fprintf(f, "\n");
    for (t = 0; t < NTASK; ++t)
        fprintf(f, "![%s against features per footprint](microsurface_features_%s.svg)\n", task_name[t], task_name[t]);
    write_task_tables(f);
    /* ---- every kind */
    fprintf(f, "\n### Every kind: where the Gaussian assumption breaks\n\n");
    fprintf(f, "Relative L2 error (*in-footprint / full*) pooled over views 0-75 degrees. The Gaussian "
               "kinds satisfy the assumptions of the filtered models (Gaussian slopes and heights); "
               "peaked, ridges, craters and tiles do not.\n\nFootprints of 4096 texels:\n\n");
    kinds_table(f, TOP);
    fprintf(f, "\nFootprints of 256 texels:\n\n");
    kinds_table(f, 4);
    fprintf(f, "\n");
    for (t = 0; t < NTASK; ++t) fprintf(f, "![%s on every kind](microsurface_kinds_%s.svg)\n", task_name[t], task_name[t]);
    write_cost_section(f, S);
    if (!charts_made) fprintf(f, "\n(no charts were made in this run: gnuplot missing or --no-charts.)\n");
    fclose(f);
}

/* the most accurate shader method of task t on kind over sizes s_lo..s_hi, views 0..VH
   (in-footprint reference); -1 if none */
/* the reference that applies at footprint size index si (1 << 2 si texels): the full one up to
   16 texels, where most occlusion is cast from outside the footprint and a renderer without the
   resolved geometry shows it, the in-footprint one above (what a filtered model represents) */
static int ref_at_size(int si) { return si <= 2 ? R_FULL : R_BOX; }
/* the most accurate shader method of task t on a kind at sizes s_lo..s_hi, views 0-75, against
   reference r */
static int best_method(int kind, int r, int t, int s_lo, int s_hi)
{
    int k, best = -1;
    double be = 1e300;
    for (k = 0; k < task_n[t]; ++k) {
        double e;
        if (meth(t, k)->oracle) continue;
        e = pooled(kind, r, t, k, s_lo, s_hi, 0, POOL_VIEW_HI);
        if (e >= 0.0 && e < be) {
            be = e;
            best = k;
        }
    }
    return best;
}

/* The fragment of a --map run: the map, its slope statistics, the key numbers, the per-task
   tables and charts, the cost. */
static void write_md_map(const settings *S, double total_s)
{
    FILE *f = open_out(S, "microsurface.md");
    const int M = KIND_MAP, TOP = NSIZE - 1, VH = POOL_VIEW_HI;
    const corpus_info *ci = &info[M];
    const char *base = strrchr(map_path, '/');
    int t, is_normal = map_opt.kind != PFMAP_HEIGHT;
    base = base ? base + 1 : map_path;
    fprintf(f, "## Ground truth on your map\n\n");
    fprintf(f, "Generated by `bench/microsurface.c --map` (%s mode, %.0f s) from `%s`; every number below is "
               "computed in that run. Raw cells: `microsurface_errors.csv` (kind `map`, with `sum_sq_err` and "
               "`sum_sq_ref`, so any set of cells pools as sqrt(sum sum_sq_err / sum sum_sq_ref)); timings: "
               "`microsurface_cost.csv`. Which method to use on this map for each error target: "
               "[the method guide](#choosing-a-method-on-this-map).\n\n",
            S->quick ? "QUICK (smoke run)" : "full", total_s, base);
    /* ---- the map */
    fprintf(f, "**The map.** A %s, %s, %d x %d texels in the file", pfmap_kind_name(map_opt.kind), map_info.format,
            map_info.file_w, map_info.file_h);
    if (map_info.crop_n != map_info.file_w || map_info.crop_n != map_info.file_h)
        fprintf(f, ", cropped to its centred %d x %d square (columns %d-%d, rows %d-%d from the top; the "
                   "march, the mip pyramids and the FFT need a power-of-two square)",
                map_info.crop_n, map_info.crop_n, map_info.crop_x, map_info.crop_x + map_info.crop_n - 1,
                map_info.crop_y, map_info.crop_y + map_info.crop_n - 1);
    if (map_opt.border == PFMAP_MIRROR)
        fprintf(f, "; clamped borders (`MAP_BORDER=clamped`): the map does not tile, so it was mirrored to "
                   "%d x %d (reflected about its far edges: heights continuous across the seams, slopes "
                   "change sign there, a crease along them)", map_surf.w, map_surf.h);
    else
        fprintf(f, "; periodic borders (the default, `MAP_BORDER=periodic`): the map tiles, and the march and "
                   "the slopes wrap across its edges (a map that does not tile has a step there: give "
                   "`MAP_BORDER=clamped`)");
    fprintf(f, ". Texel = 1 world unit; row 0 of the surface is the image's bottom row (x to the right, y "
               "up the image, z out of it). ");
    if (map_opt.rms_slope > 0.0)
        fprintf(f, "%s rescaled to an RMS slope of %g (`MAP_RMS_SLOPE`; factor %.4g on the %s).", is_normal ? "Slopes" : "Heights",
                map_opt.rms_slope, map_info.factor, is_normal ? "encoded slopes" : "file's values");
    else if (map_opt.scale > 0.0)
        fprintf(f, "%s times %g (`MAP_SCALE`%s): RMS slope %.3g.", is_normal ? "Slopes" : "Heights", map_opt.scale,
                is_normal ? "" : map_info.format[0] == 'P' ? ": full white is that many texels high" : ": a factor on the stored heights",
                map_info.rms_slope);
    else if (is_normal)
        fprintf(f, "Slopes as encoded (no `MAP_SCALE` or `MAP_RMS_SLOPE`): RMS slope %.3g.", map_info.rms_slope);
    else
        fprintf(f, "No `MAP_SCALE` or `MAP_RMS_SLOPE` given: a height map's slopes in texel units depend on a "
                   "scale the file does not hold, so the heights were rescaled to the default RMS slope %g "
                   "(factor %.4g on the file's values; give the real one for a real answer).",
                PFMAP_DEFAULT_RMS_SLOPE, map_info.factor);
    fprintf(f, "\n\n");
    if (is_normal) {
        fprintf(f, "**Normal map to heights.** The brute force marches heights for masking and shadowing, so the "
                   "normal map was integrated: least squares over the whole (periodic%s) map with the "
                   "reference's own central differences (Frankot and Chellappa 1988), solved by FFT: "
                   "H(k) = -i (sin kx P(k) + sin ky Q(k)) / (sin^2 kx + sin^2 ky), P, Q the transforms of the map's "
                   "slopes -n.x/n.z and -n.y/n.z (`tests/reference/pf_maps.h`). **Residual %.3g**: the RMS of |D h - (p, q)| "
                   "over the RMS slope (largest %.3g slope units): that share of the map is not the gradient of "
                   "any height field (its curl), and the reference shades the nearest height field instead. ",
                map_opt.border == PFMAP_MIRROR ? ", mirrored" : "", map_info.residual, map_info.residual_max);
        if (map_info.residual > PFMAP_RESIDUAL_WARN)
            fprintf(f, "**Warning: the residual is above %.2g.** The normal map is far from any height field "
                       "(painted or blended details, a detail map, or the other green convention: try "
                       "`MAP_KIND=%s`); the masking and shadowing the reference computes are those of the "
                       "integrated heights, and the errors below describe that surface, not the map. ",
                    PFMAP_RESIDUAL_WARN, map_opt.kind == PFMAP_NORMAL_GL ? "normal-dx" : "normal-gl");
        else
            fprintf(f, "Below %.2g: the map is close to a height field, and the integrated surface can be trusted. ",
                    PFMAP_RESIDUAL_WARN);
        if (map_info.clamped)
            fprintf(f, "%ld texels had n.z below %.2g (raised to it: slope at most %.0f).", map_info.clamped,
                    PFMAP_MIN_NZ, 1.0 / PFMAP_MIN_NZ);
        fprintf(f, "\n\n");
    }
    /* ---- slope statistics */
    fprintf(f, "**Slope statistics** of the surface the reference shades (central differences, every texel):\n\n");
    fprintf(f, "| RMS slope x / y | mean slope x / y | skewness x / y | kurtosis x / y | kurtosis, 2D | anisotropy "
               "(RMS ratio; direction of the larger) | correlation length L (texels) | correlation areas pi L^2 per "
               "4096 texels | share of the slope variance inside 4096-texel footprints |\n");
    fprintf(f, "|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    fprintf(f, "| %.3f / %.3f | %.3f / %.3f | %.2f / %.2f | %.2f / %.2f | %.2f | %.2f; %.0f deg | %.1f | %.0f | %.2f |\n\n",
            map_stats.rms_x, map_stats.rms_y, map_stats.mean_x, map_stats.mean_y, map_stats.skew_x, map_stats.skew_y,
            map_stats.kurt_x, map_stats.kurt_y, map_stats.kurt_r, map_stats.aniso, map_stats.aniso_angle_deg,
            map_stats.corr, features(M, TOP), ci->var_in_4096);
    fprintf(f, "Kurtosis: E[(s - mean)^4] / E[(s - mean)^2]^2 per axis; the 2D one is 1.5 E|d|^4 / E[|d|^2]^2, so "
               "that both are 3 for a Gaussian. A Gaussian has skewness 0 and kurtosis 3; above 3 the slope "
               "histogram is peaked and heavy-tailed, which a Gaussian fit of a footprint's slopes (LEADR, "
               "Toksvig) does not represent (the main report's `peaked`, `ridges`, `craters` and `tiles` "
               "kinds measure what that costs). Anisotropy: sqrt of the ratio of the slope covariance's "
               "eigenvalues (1: isotropic). Correlation length: the radius where the heights' periodic "
               "autocorrelation, averaged over directions, falls to 1/e (L of exp(-r^2 / L^2)); a filtered "
               "model needs many correlation areas per footprint. Share inside 4096-texel footprints: the "
               "rest of the slope variance is the spread of their mean slopes, i.e. resolved geometry at that "
               "scale.\n\n");
    fprintf(f, "Reference checks on this map: mean G1 at 60 degrees %.3f / %.3f (*in-footprint / full*); visible "
               "projected area at 75 degrees, 4096 texels %.3f (ideal 1: every viewing ray meets one visible "
               "point; a deficit is the bilinear surface being rougher than its central-difference slopes, "
               "and errors of that order at grazing views are the reference's); footprint-views skipped as "
               "back-facing %.1f%%, near edge-on %.1f%%.\n\n",
            ci->mean_masking_60[R_BOX], ci->mean_masking_60[R_FULL], ci->vis_den > 0 ? ci->vis_num / ci->vis_den : 0.0,
            100.0 * (double)ci->samples_backfacing / (double)(ci->samples_all > 0 ? ci->samples_all : 1),
            100.0 * (double)ci->samples_culled / (double)(ci->samples_all > 0 ? ci->samples_all : 1));
    /* ---- reference, in short */
    fprintf(f, "**Reference and error.** As in the main report's ground truth: every texel of an n x n footprint "
               "(n = 1 .. 64, aligned so that it is one texel of mip level log2 n) shaded with its own "
               "micro-normal, a narrow Beckmann base lobe (slope deviation %.2g) or a Lambertian one, masking and "
               "shadowing marched through the height field; the filtered methods read only what a shader can "
               "fetch (one texel of the moment pyramids). Two references: *in-footprint* (occluders inside "
               "the footprint only: what a filtered model can represent, so its error is the model's) and "
               "*full* (every occluder). Error: relative L2, sqrt(sum (f - ref)^2 / sum ref^2) over views at "
               "%d azimuth(s), %d seeded lights plus the mirror direction, and up to %d positions per size "
               "(%d above 256 texels).\n\n",
            BASE_SIGMA, S->naz, S->nlights, 4 * S->maxpos, S->maxpos);
    /* ---- key numbers */
    fprintf(f, "**Key numbers** (relative L2 error pooled over views 0-75 degrees, *in-footprint / full* "
               "reference; the most accurate shader method of each task, and the library's default). Methods "
               "are ranked by the reference that applies at each size, named in the *ranked by* column: the "
               "**full** one at 1-16 texels (most shadows and masking there are cast by bumps outside the "
               "footprint, and a renderer without the resolved geometry shows them), the **in-footprint** one "
               "at 256 and 4096 texels (what a filtered model represents; the resolved geometry's occlusion "
               "is the renderer's job).\n\n");
    fprintf(f, "| task | texels | ranked by | most accurate method | its error | library default | its error |\n");
    fprintf(f, "|---|--:|---|---|--:|---|--:|\n");
    for (t = 0; t < NTASK; ++t) {
        static const int sz[3] = { 6, 4, 2 };
        int j;
        for (j = 0; j < 3; ++j) {
            int b = best_method(M, ref_at_size(sz[j]), t, sz[j], sz[j]);
            if (b < 0) continue;
            fprintf(f, "| %s | %d | %s | `%s` | %s | `%s` | %s |\n", j == 0 ? task_name[t] : "", 1 << (2 * sz[j]),
                    ref_at_size(sz[j]) == R_FULL ? "full" : "in-footprint", mname(t, b), PR(M, t, b, sz[j], sz[j], 0, VH),
                    mname(t, 0), PR(M, t, 0, sz[j], sz[j], 0, VH));
        }
    }
    fprintf(f, "\nThe oracles (`oracle_histogram_smith`: the exact slope histogram of the footprint with Smith's "
               "visibility; `oracle_histogram_no_vis`: without visibility) read every texel, so they are not "
               "shader methods; in the tables below they split a method's error into the Gaussian fit of the "
               "histogram and the visibility model.\n");
    write_task_tables(f);
    write_cost_section(f, S);
    if (!charts_made) fprintf(f, "\n(no charts were made in this run: --no-charts.)\n");
    fclose(f);
}

/* --kinds: the specular task's pooled errors (views 0-75) at 4096 texels, both references, per
   kind and method, and the cost at 4096 texels when the cost section ran */
static void print_subset_summary(int with_cost)
{
    int ko, k, r;
    for (r = R_BOX; r >= R_FULL; --r) {
        printf("specular, %s reference, 4096 texels, views 0-75 pooled\n%-26s", ref_name[r], "method");
        for (ko = 0; ko < n_run_kinds; ++ko) printf(" %14s", kname(run_kinds[ko]));
        printf("\n");
        for (k = 0; k < task_n[T_SPEC]; ++k) {
            printf("%-26s", mname(T_SPEC, k));
            for (ko = 0; ko < n_run_kinds; ++ko)
                printf(" %14.3f", pooled(run_kinds[ko], r, T_SPEC, k, NSIZE - 1, NSIZE - 1, 0, POOL_VIEW_HI));
            printf("\n");
        }
    }
    if (with_cost) {
        printf("cost, gaussian, view 60, ns per footprint (x leadr_joint) at 1 / 16 / 256 / 4096 texels\n");
        for (k = 0; k < ncost; ++k) {
            int s;
            if (cost[k].task != T_SPEC) continue;
            printf("%-26s", cost[k].name);
            for (s = 0; s < NSIZE; s += 2) printf(" %8.1f (%.2fx)", cost[k].med[s], cost[k].med[s] / cost[c_leadr].med[s]);
            printf("\n");
        }
    }
}

int main(int argc, char **argv)
{
    settings S;
    int i, kind, check_only = 0, no_cost = 0;
    const char *kinds_arg = NULL;
    const char *q = getenv("BENCH_QUICK");
    pfm_surface gauss_surf;
    lib_maps gauss_maps;
    int have_gauss = 0;
    double t0 = pfb_now_ns(), cpu0 = cpu_s(), wall0 = pfb_wall_s();
    char err[1024];
    registry_init();
    check_mode = check_on();
    map_opt = pfmap_options_default();
    memset(&S, 0, sizeof S);
    S.quick = q && *q && strcmp(q, "0") != 0 && strcmp(q, "no") != 0;
    S.out = "bench/out";
    S.gp = "bench/microsurface.gp";
    S.charts = 1;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--quick")) S.quick = 1;
        else if (!strcmp(argv[i], "--check")) check_only = 1; /* load and check the map, write nothing */
        else if (!strcmp(argv[i], "--no-charts")) S.charts = 0;
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) S.out = argv[++i];
        else if (!strcmp(argv[i], "--gp") && i + 1 < argc) S.gp = argv[++i];
        else if (!strcmp(argv[i], "--map") && i + 1 < argc) map_path = argv[++i];
        else if (!strcmp(argv[i], "--kinds") && i + 1 < argc) kinds_arg = argv[++i];
        else if (!strcmp(argv[i], "--no-cost")) no_cost = 1;
        else if (!strncmp(argv[i], "--map-", 6) && i + 1 < argc) {
            /* the map's options; each value checked here, before anything is written */
            const char *o = argv[i] + 6, *v = argv[++i];
            if (pfmap_parse_option(o, v, &map_opt, err, sizeof err) != 0) {
                fprintf(stderr, "microsurface: %s\n", err);
                return 2;
            }
        } else {
            fprintf(stderr, "usage: %s [--quick] [--out DIR] [--gp FILE] [--no-charts] [--kinds K1,K2,..] [--no-cost] [--check] [--map PATH [--map-kind "
                            "height|normal-gl|normal-dx] [--map-scale S | --map-rms-slope R] [--map-border "
                            "periodic|clamped] [--map-raw-size WxH]]\n", argv[0]);
            return 2;
        }
    }
    /* the user's map: loaded and checked before anything is written */
    if (map_path) {
        if (pfmap_load(map_path, &map_opt, &map_surf, &map_info, err, sizeof err) != 0) {
            fprintf(stderr, "microsurface: %s\n", err);
            return 1;
        }
        if (map_surf.w < 64) {
            fprintf(stderr, "microsurface: %s: the kept square is %d x %d texels; the ground truth needs at least "
                            "64 x 64 (footprints up to 64 x 64)\n", map_path, map_surf.w, map_surf.h);
            pfm_surface_free(&map_surf);
            return 1;
        }
        pfmap_slope_stats(&map_surf, &map_stats);
    }
    if (check_only) {
        if (!map_path) {
            fprintf(stderr, "microsurface: --check needs --map PATH\n");
            return 2;
        }
        printf("microsurface: %s: %s, %s, %d x %d texels in the file, %d x %d kept%s; RMS slope %.3f, slope "
               "kurtosis %.2f / %.2f, correlation length %.1f texels",
               map_path, pfmap_kind_name(map_opt.kind), map_info.format, map_info.file_w, map_info.file_h, map_surf.w,
               map_surf.h, map_opt.border == PFMAP_MIRROR ? " (mirrored)" : "", map_info.rms_slope, map_stats.kurt_x,
               map_stats.kurt_y, map_stats.corr);
        if (map_opt.kind != PFMAP_HEIGHT)
            printf("; integration residual %.3g%s", map_info.residual,
                   map_info.residual > PFMAP_RESIDUAL_WARN ? " (WARNING: far from a height field)" : "");
        printf("\n");
        pfm_surface_free(&map_surf);
        return 0;
    }
    if (S.quick) {
        S.map = 256;
        S.maxpos = 16;
        S.naz = 1;
        S.nlights = 3;
        S.cost_reps = 3; /* the smoke run's timings are not read: 3, the fewest with quartiles */
        /* the lobe fits' EM, a third of a quick kind's time, with 8 iterations: every code
           path still runs. (Fewer training patches for the scaling function do not help: the
           texels left out need their T computed before they are shaded, which costs more.) */
        vmf_iter = 8;
        store_max_kinds = 1; /* the storage pass on the first kind only (bench/storage.h) */
    } else {
        S.map = 512;
        S.maxpos = 64;
        S.naz = 2;
        S.nlights = 8;
        S.cost_reps = 21;
    }
    {
        char cmd[1200];
        snprintf(cmd, sizeof cmd, "mkdir -p '%s'", S.out);
        if (system(cmd) != 0) fprintf(stderr, "microsurface: cannot create %s\n", S.out);
    }
    if (S.charts && system("gnuplot --version > /dev/null 2>&1") != 0) {
        fprintf(stderr, "microsurface: gnuplot not found (make bench installs it; --no-charts to run "
                        "without charts)\n");
        return 1;
    }
    if (map_path) {
        /* one kind, the map; the cost section on it too */
        n_run_kinds = 1;
        run_kinds[0] = KIND_MAP;
        chart_kind = KIND_MAP;
        S.map = map_surf.w;
        fprintf(stderr, "microsurface: %s: %s, %s, %d x %d texels, RMS slope %.3f, slope kurtosis %.2f%s\n", map_path,
                pfmap_kind_name(map_opt.kind), map_info.format, map_surf.w, map_surf.h, map_info.rms_slope,
                map_stats.kurt_x, map_opt.kind != PFMAP_HEIGHT ? "" : "");
        if (map_opt.kind != PFMAP_HEIGHT)
            fprintf(stderr, "microsurface: normal map integrated, residual %.3g%s\n", map_info.residual,
                    map_info.residual > PFMAP_RESIDUAL_WARN ? " (WARNING: far from a height field; see the report)" : "");
        run_kind(KIND_MAP, &S, &gauss_surf, &gauss_maps);
        fprintf(stderr, "microsurface: map done (%.1f s)\n", info[KIND_MAP].seconds);
    } else if (kinds_arg) {
        /* a subset of the corpus (--kinds): the errors CSV and a summary on stdout only; the
           cost section when the gaussian kind is in the subset and --no-cost is not given */
        for (i = 0; i < NKIND; ++i) {
            const char *name = pfm_kind_name(kind_order[i]), *p = kinds_arg;
            size_t len = strlen(name);
            while (p && *p) {
                if (!strncmp(p, name, len) && (p[len] == ',' || p[len] == '\0')) {
                    run_kinds[n_run_kinds++] = kind_order[i];
                    break;
                }
                p = strchr(p, ',');
                if (p) ++p;
            }
        }
        if (n_run_kinds == 0) {
            fprintf(stderr, "microsurface: --kinds %s: no kind of the corpus named\n", kinds_arg);
            return 2;
        }
        for (i = 0; i < n_run_kinds; ++i) {
            kind = run_kinds[i];
            run_kind(kind, &S, kind == PFM_GAUSSIAN ? &gauss_surf : NULL, &gauss_maps);
            fprintf(stderr, "microsurface: %s done (%.1f s)\n", pfm_kind_name(kind), info[kind].seconds);
            if (kind == PFM_GAUSSIAN) have_gauss = 1;
        }
    } else {
        for (i = 0; i < NKIND; ++i) run_kinds[i] = kind_order[i];
        n_run_kinds = NKIND;
        pfb_progress kinds = pfb_progress_start("microsurface: the corpus (kinds)", NKIND);
        for (kind = 0; kind < NKIND; ++kind) {
            run_kind(kind, &S, kind == PFM_GAUSSIAN ? &gauss_surf : NULL, &gauss_maps);
            fprintf(stderr, "microsurface: %s done (%.1f s)\n", pfm_kind_name(kind), info[kind].seconds);
            pfb_progress_update(&kinds, kind + 1);
        }
        pfb_progress_end(&kinds);
        have_gauss = 1;
    }
    if (map_path) have_gauss = 1;
    if (have_gauss && !no_cost) {
        run_cost(&S, &gauss_surf, &gauss_maps);
        fprintf(stderr, "microsurface: cost done (%.1f s total)\n", (pfb_now_ns() - t0) * 1e-9);
    }
    write_errors_csv(&S);
    store_write(&S); /* microsurface_storage.csv, storage.md (bench/storage.h) */
    if (kinds_arg && !map_path) {
        print_subset_summary(have_gauss && !no_cost);
        if (have_gauss && !no_cost) write_cost_csv(&S);
        if (have_gauss) {
            lib_maps_free(&gauss_maps);
            kept_views_free();
            pfm_surface_free(&gauss_surf);
        }
        pass_report(cpu0, wall0);
        printf("microsurface: wrote %s/microsurface_errors.csv%s (%.1f s)\n", S.out,
               have_gauss && !no_cost ? ", microsurface_cost.csv" : "", (pfb_now_ns() - t0) * 1e-9);
        return 0;
    }
    write_cost_csv(&S);
    make_charts(&S);
    if (map_path) write_md_map(&S, (pfb_now_ns() - t0) * 1e-9);
    else write_md(&S, (pfb_now_ns() - t0) * 1e-9);
    lib_maps_free(&gauss_maps);
    kept_views_free();
    pfm_surface_free(&gauss_surf);
    pfm_surface_free(&map_surf);
    pass_report(cpu0, wall0);
    printf("microsurface: wrote %s/microsurface.md, microsurface_errors.csv, microsurface_cost.csv, %d charts (%.1f s)\n",
           S.out, charts_made, (pfb_now_ns() - t0) * 1e-9);
    return 0;
}

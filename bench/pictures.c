/* pictures.c - images of the brute-force reference next to the library's filtered shading
   (issue 9, item 6). CPU-only bench program, not part of the library.

   WHAT IT DRAWS. Two scenes, each rendered four ways from the same per-pixel geometry:
     reference   the brute force of tests/reference/pf_microsurface.h: every texel of the pixel's
                 footprint shaded on its own (its micro-normal from the height field, a narrow
                 Beckmann base lobe of deviation BASE_SIGMA with its Smith G2, masking toward the
                 viewer and shadowing toward the light found by marching the height field with
                 pfm_visible), summed with the projected-area normalization of LEADR (Dupuy et
                 al. 2013 eqs. 1-3; pfm_reference_shade).
     LEADR       the library: the five slope moments sampled trilinearly from the moment pyramid
                 (pf_slope_pyramid_from_heights, pf_slope_moments_sample) at the footprint's
                 level of detail, turned into a noncentered Beckmann lobe plus the base roughness
                 (pf_slope_moments_stats) and shaded with pf_leadr_specular (eq. 17).
     naive       the mip-mapped normal: unit micro-normals averaged by the mip pyramid
                 (pf_normal_pyramid_from_normals), renormalized, and shaded with the base lobe
                 alone (no filtered roughness): what plain normal-map mipmapping does.
     vMF m = 8   the multi-lobe BRDF of pf_vmf.h (Wu et al. 2019 eqs. 4-5, slope form, Smith G
                 of the mixture's moments; bench/microsurface.c's vmf_m8): 8 vMF lobes per
                 texel of a lobe pyramid fitted by EM (pf_vmf_pyramid_from_normals), sampled
                 trilinearly like LEADR's moments: the lobes of the 8 texels around the
                 footprint's lod, amplitudes times the trilinear weights (shade_vmf). In the
                 tables also vMF m = 4 (not drawn).
     vMF m = 8 + horizon  the same lobes with the mixture's Smith G replaced by the horizon
                 visibility of the reflecting facets (pf_horizon_vmf_specular_lod: the HDF moments of
                 the whole height field toward wo and wi, HOR_N azimuths, conditioned on the slope
                 moments' statistics, faded to the lobes' own Smith G from lod HOR_LOD_FULL to
                 HOR_LOD_SMITH; built once per map by pf_horizon_pyramid, docs/horizon.md), drawn
                 as a shader would switch its fetch (shade_vmf_m8_horizon_switch): under
                 SWITCH_SIDE-texel footprint sides the lobes, moments and HDF moments through the
                 "box taps" (box_taps: 4 bilinear taps at the level where the footprint is 1-2
                 texels, weighted to the square's covered area), from SWITCH_SIDE on trilinear at
                 the footprint's lod like LEADR's moments (where the two fetches are within 2
                 points: docs/horizon.md). In the tables also the trilinear and box-taps rows of
                 vMF m = 8 + horizon, LEADR + horizon (pf_horizon_leadr_specular_lod) and its
                 exact-box oracle (not drawn): the horizon sees the bumps outside the footprint,
                 which the full reference marches.
   Also measured but not drawn: the other "box taps" rows (LEADR, LEADR + horizon, vMF m = 8)
   with the footprint-following fetch in place of the trilinear one;
   "LEADR, exact box", the same formula fed with the exact mean of
   the level-0 moments over the reference's own box footprint (a summed-area table in double).
   Its error is the model's alone; the difference to the trilinear LEADR error is what the mip
   filter's footprint adds. The model's error is split further (ERRORS below).

   Scene 1 "plane": a tiled Gaussian surface (pfm corpus defaults) on the plane z = 0, seen by
   a pinhole camera above it, looking toward the horizon; a directional light low in the sky
   in front of the camera (grazing view and light: masking, shadowing and the forward highlight).
   Footprints from under a texel (resolved bumps) to the whole map (the horizon).
   Scene 2 "sphere": the same surface wrapped around a sphere with a longitude-latitude map,
   tiled SPHERE_TILES times around the equator (texels square at the equator), finely enough
   that every pixel covers a few to many bumps (footprint sides of about 30 to 256 texels
   against the 12-texel correlation length): LEADR's domain, where it claims to match a
   supersampled reference (Dupuy et al. 2013 sec. 7, fig. 8). The view and the
   light are rotated into each pixel's tangent frame (x along increasing longitude = texture u,
   y toward the north pole = texture v, z the sphere's normal). As for tangent-space normal maps,
   the micro-slopes are those of the texture in texel units: the map's stretch toward the poles
   widens the footprint (in texels), it does not shear the micro-surface.

   FOOTPRINT. Ray differentials: the rays through the neighbouring pixels (+1 in x, +1 in y) are
   intersected with the tangent plane at the hit point; the two offsets, converted to texels, give
   the isotropic footprint side f = max(|dP/dx|, |dP/dy|) in texels (the GPU's level-of-detail
   rule), capped at the map size. LEADR and naive sample the pyramid at lod = log2(f)
   (trilinear). The reference integrates the footprint's square, side f centred on the hit point,
   over the texels it touches, each weighted by the area it covers (sq_reference: a 0.74-texel
   footprint is the covered parts of up to four texels, as bench/frame/frame.c's pixel reference
   integrates its parallelogram), for squares touching fewer than REF_MAX_SAMPLES texels a side;
   wider footprints shade the n x n texel box centred on the hit point, n = round(f), and beyond
   ref_max texels on a side (REF_MAX_SAMPLES, SPHERE_REF_MAX) an evenly spaced ref_max x ref_max
   subset of the box (stride n / ref_max texels; shade_reference, bench/pic_scenes.h). Before,
   every footprint took the round(f)^2 box (a 0.74-texel footprint was one whole texel): the
   numbers of docs/horizon.md "Specular in the pictures" give both. Texels whose
   base lobe at the half vector is below exp(-LOBE_CUTOFF) of its peak are not marched (their
   term would be below 1e-13 of the peak whatever their visibility).

   ERRORS. Per pixel e = |filtered - reference| / max(reference, floor) with floor = LIT_FRACTION
   times the 99th percentile of the reference over the surface pixels; "lit" pixels are the
   surface pixels whose reference is at least the floor. The fragment reports the mean and the
   95th percentile of e over lit pixels, and the same by footprint size with the bias
   sum(method)/sum(reference). The heat maps show e on a log scale from 3.2% (black) to 316%
   (pale yellow), clamped, each with its numbered colour bar; background pixels are grey.
   What the error is made of, per footprint-size row:
     out-of-footprint occlusion: a second reference, "in-box", marches the same texels with
       only the footprint box's own height field as occluder (pfm_visible_box); the rows
       report how far it is from the full reference, and the errors against it;
     the Gaussian-slope assumption: with no visibility at all, the NDF at the half vector of
       the shaded texels (the mean of their base lobes) against the Gaussian with the same
       texels' moments plus the base variance (LEADR eqs. 8-10): the footprint's slope
       histogram is lumpy at the scale of the narrow base lobe when it holds few bumps;
     the reference's own sampling deviation on subsampled footprints: half the difference of
       the two interleaved (checkerboard) halves of the samples, relative, rms.

   SELF-CHECKS. Before the pictures, both scenes are rendered small with the map flattened (RMS
   slope FLAT_RMS_SLOPE): the three methods and the in-box reference must then match the
   reference to rounding (bound in main), the vMF methods to VMF_CHECK_BOUND, the horizon methods
   to HOR_CHECK_BOUND (and the sum for vMF + horizon); the program
   fails otherwise. It checks the plumbing
   that the comparison relies on (frames, footprints, the recombination of the reference,
   conventions of the two shaders).

   METHODS. Each method is one row of pic_methods (name, shading function, what it fetches,
   oracle or not, its picture panel, its self-check bound) and one shading function; everything
   else loops over the rows (see "the method registry" below).

   EVERY CORE (bench/pf_parallel.h, PFB_THREADS threads, default all). The maps are built once
   per height map and shared by both scenes (the two lobe pyramids fitted in parallel); the
   brute force of both scenes runs as one parallel step over image rows, with the scaling
   function as one more item beside them (its code keeps static scratch: one item, serial);
   with one thread the scaling function runs alone first, each step with its own progress;
   the filtered methods' values are one parallel step over rows per scene. Every pixel's value
   depends on that pixel alone, so every output is the same for any thread count. Steps longer
   than 2 s print their progress and the time left on stderr.

   TIMES. Measured apart, after the parallel steps, on one thread: the brute force (and its
   in-box variant, apart) on about PIC_TIME_REF_PIXELS surface pixels evenly spread over the
   image, the filtered methods on about PIC_TIME_METHOD_PIXELS (best of 5 passes), each scaled
   to all the surface pixels; the pyramids once (a one-off per map: not counted in the
   methods' times), the lobe pyramids and the scaling function by the CPU time of the thread
   that built them.

   OUTPUT. Usage: pictures [OUT_DIR] [--gp SCRIPT] [--map PATH --map-kind K --map-scale S
   --map-rms-slope R --map-border B --map-raw-size WxH] (defaults bench/out, bench/pictures.gp;
   run from the repository root). With --map (`make bench MAP=...`, bench/map.sh) both scenes
   tile the user's height or normal map, loaded by tests/reference/pf_maps.h before anything is written
   (a bad map: one message, exit 1, no output); the flat self-check keeps the Gaussian map. pic_plane.png, pic_sphere.png: 5 x 2 panels, reference | LEADR |
   vMF m = 8 | vMF m = 8 + horizon | naive (radiance), footprint side | LEADR error | vMF m = 8 error | vMF m = 8 +
   horizon error | naive error, every panel titled (with its
   time per pixel or its mean and 95th-percentile error from this run) and with its own
   numbered colour bar; pictures.md, the markdown fragment of the report (every number computed
   in this run). BENCH_QUICK=1 renders smaller images.

   PICTURES. Drawn by gnuplot, the bench's chart tool already, rather than libpng or
   stb_image_write: it titles the panels and numbers the colour bars, which a pixel writer
   cannot, and adds no library to link. This program writes the values (radiance, footprint,
   error) as float32 planes and the titles; bench/pictures.gp maps them through the display
   curve and the colour maps (write_picture). Without gnuplot the program stops at once. */
#include "pf_bench_base.h" /* first: _POSIX_C_SOURCE; the clock and checked allocation */
#include "pf_parallel.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pf_moments.h"
#include "pf_beckmann.h"
#include "pf_vmf.h"
#include "pf_horizon.h"
#include "pf_microsurface.h"
#include "pf_maps.h"
#include "pic_scenes.h" /* the scenes, their settings and the brute-force reference (shared with bench/frame/) */
#include "vmf_scaling.h"

/* ---------------------------------------------------------------- settings */
#define REF_MAX_SAMPLES 64      /* reference texels per footprint side, at most */
#define SPHERE_REF_MAX  128     /* sphere: the same (BENCH_QUICK: REF_MAX_SAMPLES) */
#define REF_SCRATCH     (REF_MAX_SAMPLES > SPHERE_REF_MAX ? REF_MAX_SAMPLES : SPHERE_REF_MAX)
#define ERR_LOG_MIN     (-1.5)  /* error maps: log10 of the error at the bottom of the colour
                                   scale (3.2%; smaller errors are drawn at 3.2%) */
#define ERR_LOG_MAX     0.5     /* ... and at its top (316%; larger ones drawn at 316%) */
#define FP_SHOWN_MIN    0.25    /* footprint map: colour scale from 1/4 texel to the map size */
#define WHITE_EXPOSURE  5.0     /* shaded panels: the colour bar ends at L = this / exposure,
                                   where the display curve 1 - exp(-exposure L) reaches 0.993 */
#define FLAT_RMS_SLOPE  1e-9    /* self-check: the map flattened to this RMS slope */
#define SC_LEVEL        6       /* the scaling function's level: 64 x 64-texel footprints, the only
                                   level bench/microsurface.c scales (docs/vmf.md) */
#define VMF_CHECK_BOUND 2e-2    /* self-check bound of the vMF methods on the flat map: its fitted
                                   lobe is the sharpest the fit stores (kappa 1e5), whose own slope
                                   variance (~1e-5) widens the base lobe's 0.01 (docs/vmf.md: 4.4e-3
                                   against one-slope LEADR; tests/test_vmf.c's bound 2e-2) */
#define HOR_CHECK_BOUND 2e-3    /* self-check bound of the horizon methods on the flat map: they drop
                                   the base lobe's own Smith G2 (the horizon replaces G), which the
                                   reference keeps; 1 - G2 of the 0.1-deviation lobe at the check's
                                   most grazing lit pixels: 4.5e-4 measured */
#define NVMF_PIC        2       /* lobe pyramids: m = vmf_pic_lobes[i] */
/* the horizon methods (pf_horizon.h): one HDF-moment pyramid (E[T], E[T^2], E[S T] per azimuth)
   of HOR_N azimuths, marched HOR_STEPS texels (periodic), faded to the unshadowed method from mip
   level HOR_LOD_FULL (4-texel footprint sides) to HOR_LOD_SMITH (64): bench/microsurface.c's
   n = 32 pyramid and fade, docs/horizon.md */
#define HOR_N           32
#define HOR_STEPS       64
#define HOR_LOD_FULL    2.0
#define HOR_LOD_SMITH   6.0
static const int vmf_pic_lobes[NVMF_PIC] = {4, 8};


/* The user's map (--map PATH, `make bench MAP=...`; tests/reference/pf_maps.h): when set, both scenes
   tile it instead of the Gaussian corpus map (the flat self-check still uses the Gaussian
   map: it checks the plumbing, not the surface). map_label names it in titles and text. */
static pfm_surface *user_map = NULL;
static char map_label[256] = "";
static char map_title[256] = ""; /* for gnuplot titles: no backquote, quote or backslash */
static double map_rms = 0.0, map_corr = 0.0;
/* the side of the map the scenes use (footprints are capped at it) */
static int map_side(void) { return user_map ? user_map->w : MAP_SIZE; }

/* CPU seconds of the calling thread: the one-off builds that run inside a parallel step are
   timed by their own thread's CPU time (not the wall clock, which other threads share). */
static double thread_cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}



/* The maps of one height map, built once and shared by both scenes (and the self-check's flat
   map by both of its scenes): pyramids, lobe pyramids, the scaling function, a summed-area table. */
typedef struct {
    pfm_surface surf;
    pf_real *heights;     /* the heights in pf_real (the scaling function's input) */
    pf_real *slope_pyr;   /* 5-moment pyramid */
    pf_real *normal_pyr;  /* average-normal pyramid */
    double *sat;          /* (W + 1) (H + 1) 5 summed-area table of the level-0 moments */
    double t_pyramid;     /* seconds to build both pyramids */
    pf_real *vmf_pyr[NVMF_PIC]; /* vMF lobe pyramids (pf_vmf.h), vmf_pic_lobes[i] lobes per texel */
    double t_vmf[NVMF_PIC];     /* CPU seconds of the thread that fitted each */
    pf_real *hor;         /* HDF-moment pyramid (pf_horizon_pyramid: HOR_N azimuths x 3 channels) */
    double t_hor;         /* CPU seconds of the thread that marched it */
    const pf_real *vmf_normals; /* the unit normals the lobe pyramids are fitted to (maps_make only) */
    /* the scaling function (bench/vmf_scaling.h) of both lobe pyramids at level SC_LEVEL:
       S, the prior, T per texel of the level; sc_ok = 0 when the map has no such level.
       Built by maps_scale (run as one item of the brute force's parallel step) */
    int sc_ok, sc_failed;
    pf_real sc_S[NVMF_PIC][VS_CELLS], sc_prior[NVMF_PIC], *sc_T[NVMF_PIC];
    double t_scale;       /* CPU seconds of the thread that built it */
} pic_maps;

/* parallel item k: the horizon pyramid (k = 0, the first: the dearest on large maps), then lobe
   pyramid k - 1 (m = vmf_pic_lobes[k - 1]), each timed by its thread's CPU time */
static void maps_vmf_item(void *ctx, long long k)
{
    pic_maps *m = (pic_maps *)ctx;
    double t0 = thread_cpu_seconds();
    if (k == 0) {
        if (pf_horizon_pyramid(m->heights, m->surf.w, m->surf.h, PF_R(1.0), HOR_N, HOR_STEPS, PF_BORDER_WRAP,
                               PF_HORIZON_MOMENTS, 0, m->hor) != PF_OK) {
            fprintf(stderr, "pictures: pf_horizon_pyramid failed\n");
            exit(1);
        }
        m->t_hor = thread_cpu_seconds() - t0;
        return;
    }
    --k;
    if (pf_vmf_pyramid_from_normals(m->vmf_normals, NULL, m->surf.w, m->surf.h, vmf_pic_lobes[k], VMF_ITER,
                                    m->vmf_pyr[k]) != PF_OK) {
        fprintf(stderr, "pictures: pf_vmf_pyramid_from_normals failed (m = %d)\n", vmf_pic_lobes[k]);
        exit(1);
    }
    m->t_vmf[k] = thread_cpu_seconds() - t0;
}

/* flat = 1: the same map scaled to an RMS slope of FLAT_RMS_SLOPE (the pipeline self-check).
   Everything but the scaling function (maps_scale). */
static int maps_make(pic_maps *m, int flat)
{
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    int W = (user_map && !flat) ? user_map->w : MAP_SIZE, H = (user_map && !flat) ? user_map->h : MAP_SIZE, x, y, k;
    long long nt = pf_mip_texel_count(W, H);
    pf_real *normals;
    double t0;
    if (flat) p.rms_slope = FLAT_RMS_SLOPE;
    memset(m, 0, sizeof *m);
    if (user_map && !flat) {
        if (pfm_surface_alloc(&m->surf, W, H, 1.0) != 0) return 1;
        memcpy(m->surf.height, user_map->height, sizeof(double) * (size_t)W * (size_t)H);
        pfm_surface_bounds(&m->surf);
    } else if (pfm_surface_make(&m->surf, W, H, 1.0, p) != 0)
        return 1;
    m->heights = (pf_real *)pfb_xmalloc(sizeof(pf_real) * (size_t)W * (size_t)H);
    normals = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 3 * (size_t)W * (size_t)H);
    m->slope_pyr = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 5 * (size_t)nt);
    m->normal_pyr = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 3 * (size_t)nt);
    m->sat = (double *)pfb_xcalloc((size_t)(W + 1) * (size_t)(H + 1) * 5, sizeof(double));
    for (k = 0; k < W * H; ++k) m->heights[k] = (pf_real)m->surf.height[k];
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            double n[3];
            pfm_normal(&m->surf, x, y, n);
            for (k = 0; k < 3; ++k) normals[3 * (y * W + x) + k] = (pf_real)n[k];
        }
    t0 = pfb_now_s();
    pf_slope_pyramid_from_heights(m->heights, W, H, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP,
                                  m->slope_pyr);
    pf_normal_pyramid_from_normals(normals, W, H, m->normal_pyr);
    m->t_pyramid = pfb_now_s() - t0;
    /* the lobe pyramids: independent fits, one parallel item each */
    for (k = 0; k < NVMF_PIC; ++k)
        m->vmf_pyr[k] = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 4 * (size_t)vmf_pic_lobes[k] *
                                               (size_t)pf_vmf_pyramid_texel_count(W, H));
    m->hor = (pf_real *)pfb_xmalloc(sizeof(pf_real) * (size_t)pf_horizon_channels(PF_HORIZON_MOMENTS, HOR_N, 0) *
                                    (size_t)nt);
    m->vmf_normals = normals;
    pfb_parallel_for(NVMF_PIC + 1, maps_vmf_item, m, flat ? NULL : "pictures: horizon and vMF lobe pyramids");
    m->vmf_normals = NULL;
    /* the scaling function at SC_LEVEL (not for the flat self-check map): maps_scale */
    m->sc_ok = !flat && (W >> SC_LEVEL) >= 1 && (H >> SC_LEVEL) >= 1 &&
               (long long)(W >> SC_LEVEL) * (H >> SC_LEVEL) <= 256; /* a 1024^2 map at most: ~0.4 s per T */
    for (k = 0; k < NVMF_PIC && m->sc_ok; ++k)
        m->sc_T[k] = (pf_real *)pfb_xmalloc(sizeof(pf_real) * (size_t)((W >> SC_LEVEL) * (H >> SC_LEVEL)));
    /* summed-area table of the level-0 moments, in double, from pfm's own slopes */
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            double sx, sy, t[5];
            double *o = m->sat + 5 * ((size_t)(y + 1) * (W + 1) + (x + 1));
            const double *l = m->sat + 5 * ((size_t)(y + 1) * (W + 1) + x);
            const double *u = m->sat + 5 * ((size_t)y * (W + 1) + (x + 1));
            const double *ul = m->sat + 5 * ((size_t)y * (W + 1) + x);
            pfm_slope(&m->surf, x, y, &sx, &sy);
            t[0] = sx;
            t[1] = sy;
            t[2] = sx * sx;
            t[3] = sy * sy;
            t[4] = sx * sy;
            for (k = 0; k < 5; ++k) o[k] = t[k] + l[k] + u[k] - ul[k];
        }
    free(normals);
    return 0;
}

/* The scaling function of both lobe pyramids at SC_LEVEL (when m->sc_ok): S and the prior from
   the training patches (vs_fit_level), T of every other texel of the level (vs_texel_t). Serial:
   bench/vmf_scaling.h keeps static scratch, so at most one thread may be in it; the brute force
   runs it as one item of its parallel step, beside the pixels (label NULL: no progress), or
   alone before it on one thread (with its progress under label). Sets sc_failed on failure. */
static void maps_scale(pic_maps *m, const char *label)
{
    const int W = m->surf.w, H = m->surf.h;
    const pf_real *pyrs[NVMF_PIC];
    long long gw = W >> SC_LEVEL, gh = H >> SC_LEVEL, t;
    double t0 = thread_cpu_seconds();
    int k, done;
    pfb_progress pr;
    if (!m->sc_ok) return;
    pr = pfb_progress_start(label, gw * gh);
    for (k = 0; k < NVMF_PIC; ++k) {
        pyrs[k] = m->vmf_pyr[k];
        for (t = 0; t < gw * gh; ++t) m->sc_T[k][t] = (pf_real)NAN;
    }
    done = vs_fit_level(m->heights, W, H, SC_LEVEL, (pf_real)BASE_SIGMA, (pf_real)F0, NVMF_PIC, pyrs, vmf_pic_lobes,
                        m->sc_S, m->sc_prior, m->sc_T);
    if (done < 0) {
        m->sc_failed = 1;
        return;
    }
    pfb_progress_update(&pr, done);
    for (t = 0; t < gw * gh; ++t)
        if (m->sc_T[0][t] != m->sc_T[0][t]) { /* not a training patch */
            pf_real tv[NVMF_PIC];
            if (vs_texel_t(m->heights, W, H, SC_LEVEL, t % gw, t / gw, (pf_real)BASE_SIGMA, (pf_real)F0, NVMF_PIC, pyrs,
                           vmf_pic_lobes, m->sc_S, m->sc_prior, tv) != 0) {
                m->sc_failed = 1;
                return;
            }
            for (k = 0; k < NVMF_PIC; ++k) m->sc_T[k][t] = tv[k];
            pfb_progress_update(&pr, ++done);
        }
    pfb_progress_end(&pr);
    m->t_scale = thread_cpu_seconds() - t0;
}

static void maps_free(pic_maps *m)
{
    int k;
    pfm_surface_free(&m->surf);
    free(m->heights);
    free(m->slope_pyr);
    free(m->normal_pyr);
    free(m->sat);
    free(m->hor);
    for (k = 0; k < NVMF_PIC; ++k) {
        free(m->vmf_pyr[k]);
        free(m->sc_T[k]);
    }
}

/* Sum of the level-0 moments over [0, x) x [0, y) of the periodic extension of the map. */
static void sat_periodic(const pic_maps *m, long x, long y, double out[5])
{
    int W = m->surf.w, H = m->surf.h, k;
    long qx = x >= 0 ? x / W : -((-x + W - 1) / W), qy = y >= 0 ? y / H : -((-y + H - 1) / H);
    int rx = (int)(x - qx * W), ry = (int)(y - qy * H);
    const double *tot = m->sat + 5 * ((size_t)H * (W + 1) + W);
    const double *row = m->sat + 5 * ((size_t)ry * (W + 1) + W);  /* S(W, ry) */
    const double *col = m->sat + 5 * ((size_t)H * (W + 1) + rx);  /* S(rx, H) */
    const double *in = m->sat + 5 * ((size_t)ry * (W + 1) + rx);  /* S(rx, ry) */
    for (k = 0; k < 5; ++k)
        out[k] = (double)qx * (double)qy * tot[k] + (double)qx * row[k] + (double)qy * col[k] +
                 in[k];
}

/* ---------------------------------------------------------------- the three shaders */

static pf_vec3 to_pf(const double a[3])
{
    return pf_vec3_make((pf_real)a[0], (pf_real)a[1], (pf_real)a[2]);
}

static pf_real pic_lod(double fp) { return (pf_real)(fp > 1.0 ? log2(fp) : 0.0); }

/* The footprint's slope statistics: the five moments sampled trilinearly at its level of detail,
   plus the base lobe's variance */
static pf_slope_stats leadr_stats(const pic_maps *m, const pic_sample *p)
{
    pf_slope_moments mo = pf_slope_moments_sample(m->slope_pyr, m->surf.w, m->surf.h, pic_lod(p->fp),
                                                  (pf_real)(p->tx / m->surf.w), (pf_real)(p->ty / m->surf.h),
                                                  PF_BORDER_WRAP);
    return pf_slope_moments_stats(mo, (pf_real)(BASE_SIGMA * BASE_SIGMA));
}

/* LEADR from the trilinear moment sample at the footprint's level of detail. */
static double shade_leadr(const pic_maps *m, const pic_sample *p)
{
    return (double)pf_leadr_specular(to_pf(p->wo), to_pf(p->wi), leadr_stats(m, p), (pf_real)F0);
}

/* The mip-mapped normal: the base lobe alone around the renormalized average normal. */
static double shade_naive(const pic_maps *m, const pic_sample *p)
{
    pf_vec3 n = pf_normal_avg_sample(m->normal_pyr, m->surf.w, m->surf.h, pic_lod(p->fp),
                                     (pf_real)(p->tx / m->surf.w), (pf_real)(p->ty / m->surf.h),
                                     PF_BORDER_WRAP);
    pf_slope_moments mo = pf_slope_moments_from_normal(n);
    pf_slope_stats st = pf_slope_moments_stats(mo, (pf_real)(BASE_SIGMA * BASE_SIGMA));
    return (double)pf_leadr_specular(to_pf(p->wo), to_pf(p->wi), st, (pf_real)F0);
}

/* 1 when the reference integrates the pixel's footprint square, [t - fp/2, t + fp/2] on each
   axis (texel i spans [i, i + 1)), over the texels it touches by covered area (sq_reference):
   squares touching fewer than REF_MAX_SAMPLES texels per side, in both scenes; 0 for wider
   footprints, whose reference is shade_reference's round(fp)^2 box (subsampled beyond ref_max). */
static int sq_covered(const pic_sample *p)
{
    return (int)floor(p->tx + 0.5 * p->fp) - (int)floor(p->tx - 0.5 * p->fp) < REF_MAX_SAMPLES &&
           (int)floor(p->ty + 0.5 * p->fp) - (int)floor(p->ty - 0.5 * p->fp) < REF_MAX_SAMPLES;
}

/* Overlap of texel i, [i, i + 1), with [a, b]. */
static double cover_1d(int i, double a, double b)
{
    double lo = a > (double)i ? a : (double)i, hi = b < (double)(i + 1) ? b : (double)(i + 1);
    return hi > lo ? hi - lo : 0.0;
}

/* The brute force of shade_reference over the footprint square (sq_covered) instead of the
   round(fp)^2 box: every texel the square touches weighted by the area it covers (a 0.74-texel
   footprint is up to four texels' parts, not one whole texel; a 2.6-texel one 2.6^2 texels, not
   3^2), the value sum_t c_t V_o V_i spec_t a_t / sum_t c_t a_t, as bench/frame/frame.c's pixel
   reference (shade_reference_cover) integrates its parallelogram, here for the isotropic square
   that a trilinear lookup at lod log2(fp) stands for. The in-box variant marches the texels
   occluded in the full march again with only the integer box of the touched texels as occluder
   (pfm_visible_box; its side the larger of the two extents). Every texel is shaded (no
   subsampling: r.noise 0); the NDF terms weighted by c_t. Marching order and lobe cutoff as in
   shade_reference. */
static ref_result sq_reference(const pfm_surface *s, const unsigned char *vis_light, const pic_sample *p)
{
    double h = 0.5 * p->fp, X0 = p->tx - h, X1 = p->tx + h, Y0 = p->ty - h, Y1 = p->ty + h;
    int x0 = (int)floor(X0), x1 = (int)floor(X1), y0 = (int)floor(Y0), y1 = (int)floor(Y1);
    int nb = (x1 - x0 > y1 - y0 ? x1 - x0 : y1 - y0) + 1, bx0 = wrap_index(x0, s->w), by0 = wrap_index(y0, s->h), xu, yu;
    double num = 0.0, area = 0.0, num_box = 0.0, t0 = pfb_now_s(), ndf = 0.0, cw = 0.0, mom[5] = {0, 0, 0, 0, 0};
    double shx, shy;
    int lit = pic_half_slope(p, &shx, &shy), light_first = pic_light_first(p, vis_light);
    ref_result r;
    memset(&r, 0, sizeof r);
    for (yu = y0; yu <= y1; ++yu) {
        double cy = cover_1d(yu, Y0, Y1);
        int y = wrap_index(yu, s->h);
        if (!(cy > 0.0)) continue;
        for (xu = x0; xu <= x1; ++xu) {
            double c = cy * cover_1d(xu, X0, X1), sx, sy, at, qq, term;
            int x = wrap_index(xu, s->w), vo, vi;
            if (!(c > 0.0)) continue;
            pfm_slope(s, x, y, &sx, &sy);
            at = p->wo[2] - sx * p->wo[0] - sy * p->wo[1];
            area += c * at;
            cw += c;
            mom[0] += c * sx;
            mom[1] += c * sy;
            mom[2] += c * sx * sx;
            mom[3] += c * sy * sy;
            mom[4] += c * sx * sy;
            qq = ((sx - shx) * (sx - shx) + (sy - shy) * (sy - shy)) / (2.0 * BASE_SIGMA * BASE_SIGMA);
            if (lit) ndf += c * exp(-qq);
            if (!lit || !(at > 0.0) || qq > LOBE_CUTOFF) continue;
            term = c * at * pfm_reference_shade(s, NULL, NULL, x, y, 1, p->wo, p->wi, BASE_SIGMA, F0).spec;
            /* the full march (the second direction only when the first sees), then the box's
               for the directions the full march found hidden */
            if (light_first) {
                vi = vis_light ? vis_light[(size_t)y * s->w + x] : pfm_visible(s, x, y, p->wi);
                vo = vi ? pfm_visible(s, x, y, p->wo) : -1;
                if (vi && vo) {
                    num += term;
                    num_box += term;
                    continue;
                }
                if (!vi && !pfm_visible_box(s, x, y, p->wi, bx0, by0, nb)) continue;
                if (vo != 1 && !pfm_visible_box(s, x, y, p->wo, bx0, by0, nb)) continue;
            } else {
                vo = pfm_visible(s, x, y, p->wo);
                vi = vo ? pfm_visible(s, x, y, p->wi) : -1;
                if (vo && vi) {
                    num += term;
                    num_box += term;
                    continue;
                }
                if (!vo && !pfm_visible_box(s, x, y, p->wo, bx0, by0, nb)) continue;
                if (vi != 1 && !pfm_visible_box(s, x, y, p->wi, bx0, by0, nb)) continue;
            }
            num_box += term;
        }
    }
    r.full = area > 0.0 ? num / area : 0.0;
    r.inbox = area > 0.0 ? num_box / area : 0.0;
    r.t_full = pfb_now_s() - t0;
    if (lit && cw > 0.0) pic_ndf_pair(&r, ndf, mom, cw, shx, shy); /* P22 at s_h: texels' lobes, Gaussian of their moments */
    return r;
}

/* The picture's reference of pixel p: sq_reference for footprints sq_covered takes, else
   shade_reference's (subsampled) box. */
static ref_result pic_reference(const pfm_surface *s, const unsigned char *vis_light, const pic_sample *p, int ref_max,
                                ref_texel *scratch)
{
    return sq_covered(p) ? sq_reference(s, vis_light, p) : shade_reference(s, vis_light, p, ref_max, 0, scratch);
}

/* sat_periodic at a fractional corner: the texels are constant, so the integral over
   [0, x) x [0, y) is bilinear between the integer corners */
static void sat_frac(const pic_maps *m, double x, double y, double out[5])
{
    long ix = (long)floor(x), iy = (long)floor(y);
    double fx = x - (double)ix, fy = y - (double)iy, a[5], b[5], c[5], d[5];
    int k;
    sat_periodic(m, ix, iy, a);
    sat_periodic(m, ix + 1, iy, b);
    sat_periodic(m, ix, iy + 1, c);
    sat_periodic(m, ix + 1, iy + 1, d);
    for (k = 0; k < 5; ++k)
        out[k] = (1.0 - fy) * ((1.0 - fx) * a[k] + fx * b[k]) + fy * ((1.0 - fx) * c[k] + fx * d[k]);
}

/* The exact slope statistics of the reference's footprint (summed-area table), base lobe added:
   the covered square weighted by area (sq_covered), else the round(fp)^2 box. */
static pf_slope_stats box_stats(const pic_maps *m, const pic_sample *p)
{
    int k;
    double a[5], b[5], c[5], d[5], inv;
    pf_real mo[5];
    pf_slope_stats st;
    if (sq_covered(p)) {
        double h = 0.5 * p->fp;
        sat_frac(m, p->tx + h, p->ty + h, a);
        sat_frac(m, p->tx - h, p->ty + h, b);
        sat_frac(m, p->tx + h, p->ty - h, c);
        sat_frac(m, p->tx - h, p->ty - h, d);
        inv = 1.0 / (p->fp * p->fp);
    } else {
        int n = footprint_side(p->fp);
        long x0 = footprint_start(p->tx, n), y0 = footprint_start(p->ty, n);
        sat_periodic(m, x0 + n, y0 + n, a);
        sat_periodic(m, x0, y0 + n, b);
        sat_periodic(m, x0 + n, y0, c);
        sat_periodic(m, x0, y0, d);
        inv = 1.0 / ((double)n * (double)n);
    }
    for (k = 0; k < 5; ++k) mo[k] = (pf_real)((a[k] - b[k] - c[k] + d[k]) * inv);
    st = pf_slope_moments_stats(pf_slope_moments_make(mo[0], mo[1], mo[2], mo[3], mo[4]),
                                (pf_real)(BASE_SIGMA * BASE_SIGMA));
    return st;
}

/* LEADR fed with the exact moments of the reference's box (the model's own error). */
static double shade_leadr_box(const pic_maps *m, const pic_sample *p)
{
    return (double)pf_leadr_specular(to_pf(p->wo), to_pf(p->wi), box_stats(m, p), (pf_real)F0);
}

/* The multi-lobe BRDF of pf_vmf.h (Wu et al. 2019 eqs. 4-5, slope form, Smith G of the
   mixture's slope mean and covariance: bench/microsurface.c's vmf_m4, vmf_m8) from the lobe
   pyramid sampled trilinearly at the footprint's level of detail, as LEADR's moments are: the
   lobes of the (up to) 8 texels of the two levels around lod, each texel's amplitudes scaled
   by its trilinear weight. A mixture of mixtures is a mixture, so this is the NDF the
   trilinear filter's footprint holds (what filtering the lobe textures linearly cannot give);
   it costs 8 m lobe evaluations. Texel centres, wrap and level clamp as pf_moments.h's sampler. */
static pf_vmf_sum vmf_sum_sample(const pic_maps *m, const pic_sample *p, int which)
{
    const int W = m->surf.w, H = m->surf.h, nm = vmf_pic_lobes[which];
    const pf_real base_var = (pf_real)(BASE_SIGMA * BASE_SIGMA);
    pf_vec3 wo = to_pf(p->wo), wi = to_pf(p->wi);
    pf_vmf_sum sum = pf_vmf_sum_zero();
    pic_taps tp;
    int n = pic_trilinear_taps(m->vmf_pyr[which], W, H, 4 * nm, p->tx / W, p->ty / H, p->fp > 1.0 ? log2(p->fp) : 0.0, &tp), t, j;
    for (t = 0; t < n; ++t)
        for (j = 0; j < nm; ++j) { /* one RGBA texel per lobe: (mu.x, mu.y, kappa, amp) */
            const pf_real *tex = tp.tex[t];
            pf_vmf_lobe lobe = pf_vmf_lobe_make((pf_real)tp.w[t] * tex[4 * j + 3], tex[4 * j], tex[4 * j + 1], tex[4 * j + 2]);
            sum = pf_vmf_sum_add(sum, lobe, wo, wi, base_var);
        }
    return sum;
}

static double shade_vmf(const pic_maps *m, const pic_sample *p, int which)
{
    return (double)pf_vmf_sum_specular(vmf_sum_sample(m, p, which), to_pf(p->wo), to_pf(p->wi), (pf_real)F0);
}

/* shade_vmf times the scaling function (Wu et al. 2019 eqs. 13-14) where the footprint reaches
   level SC_LEVEL: T sampled bilinearly from its level (wrap, texel centres) and S at (wo, wi)
   (pf_vmf_scale_lookup), the factor T S faded in by the level's share of the trilinear fetch,
   w = clamp(lod - (SC_LEVEL - 1), 0, 1), and kept at w = 1 above (T and S of level SC_LEVEL
   stand for coarser footprints too). Our rule for continuous footprints, not the paper's:
   bench/microsurface.c scales 64 x 64 footprints only, and below that level the fit made
   several kinds worse (docs/vmf.md). */
static double shade_vmf_scaled(const pic_maps *m, const pic_sample *p, int which)
{
    const int W = m->surf.w, H = m->surf.h, gw = W >> SC_LEVEL, gh = H >> SC_LEVEL;
    double f = shade_vmf(m, p, which), lod = p->fp > 1.0 ? log2(p->fp) : 0.0, w = lod - (SC_LEVEL - 1), x, y, fx, fy, t = 0.0;
    long ix, iy;
    int k;
    if (!m->sc_ok || !(w > 0.0) || !(f > 0.0)) return f;
    if (w > 1.0) w = 1.0;
    x = (p->tx / W - floor(p->tx / W)) * gw - 0.5;
    y = (p->ty / H - floor(p->ty / H)) * gh - 0.5;
    ix = (long)floor(x);
    iy = (long)floor(y);
    fx = x - (double)ix;
    fy = y - (double)iy;
    for (k = 0; k < 4; ++k) {
        long tx = wrap_index((int)(ix + (k & 1)), gw), ty = wrap_index((int)(iy + (k >> 1)), gh);
        t += ((k & 1) ? fx : 1.0 - fx) * ((k & 2) ? fy : 1.0 - fy) * (double)m->sc_T[which][ty * gw + tx];
    }
    t *= (double)pf_vmf_scale_lookup(m->sc_S[which], VS_NT, VS_NP, (pf_real)VS_THETA_MAX, to_pf(p->wo), to_pf(p->wi));
    return f * (1.0 + w * (t - 1.0));
}

static double shade_vmf_m4(const pic_maps *m, const pic_sample *p) { return shade_vmf(m, p, 0); }
static double shade_vmf_m8(const pic_maps *m, const pic_sample *p) { return shade_vmf(m, p, 1); }
static double shade_vmf_m4_scaled(const pic_maps *m, const pic_sample *p) { return shade_vmf_scaled(m, p, 0); }
static double shade_vmf_m8_scaled(const pic_maps *m, const pic_sample *p) { return shade_vmf_scaled(m, p, 1); }

/* The HDF moments toward w at the footprint: the two stored azimuths around w's
   (pf_horizon_azimuth_of), each sampled trilinearly from the horizon pyramid at the footprint's
   level of detail as LEADR's moments are (the moments are linear in the texels' HDFs, so the
   trilinear mean is the HDF of the trilinear filter's footprint), mixed by pf_hdf_moments_lerp:
   6 channels of the 8 texels. Texel centres, wrap and level clamp as shade_vmf. */
static pf_hdf_moments hdf_sample(const pic_maps *m, const pic_sample *p, const double w[3])
{
    const int W = m->surf.w, H = m->surf.h;
    pf_horizon_azimuth az = pf_horizon_azimuth_of(to_pf(w), HOR_N);
    double acc[2][3] = {{0, 0, 0}, {0, 0, 0}};
    pic_taps tp;
    int n = pic_trilinear_taps(m->hor, W, H, 3 * HOR_N, p->tx / W, p->ty / H, p->fp > 1.0 ? log2(p->fp) : 0.0, &tp), t, q, a;
    for (t = 0; t < n; ++t)
        for (a = 0; a < 2; ++a)
            for (q = 0; q < 3; ++q) acc[a][q] += tp.w[t] * (double)tp.tex[t][3 * (a ? az.i1 : az.i0) + q];
    return pf_hdf_moments_lerp(pf_hdf_moments_make((pf_real)acc[0][0], (pf_real)acc[0][1], (pf_real)acc[0][2]),
                               pf_hdf_moments_make((pf_real)acc[1][0], (pf_real)acc[1][1], (pf_real)acc[1][2]), az.f);
}

/* pf_horizon_leadr_specular_lod: LEADR (trilinear moments) with the reflecting facets' horizon
   visibility toward wo and wi instead of Smith's G, faded to shade_leadr by level of detail
   (HOR_LOD_FULL .. HOR_LOD_SMITH). It sees the bumps outside the footprint, as the reference. */
static double shade_leadr_horizon(const pic_maps *m, const pic_sample *p)
{
    return (double)pf_horizon_leadr_specular_lod(to_pf(p->wo), to_pf(p->wi), leadr_stats(m, p),
                                                 (pf_real)(BASE_SIGMA * BASE_SIGMA), hdf_sample(m, p, p->wo),
                                                 hdf_sample(m, p, p->wi), (pf_real)F0, pic_lod(p->fp),
                                                 (pf_real)HOR_LOD_FULL, (pf_real)HOR_LOD_SMITH);
}

/* pf_horizon_vmf_specular_lod: shade_vmf's trilinear lobes with the same visibility
   (conditioned on the slope-moment texel's statistics, as pf_horizon_vmf_specular asks) */
static double shade_vmf_horizon(const pic_maps *m, const pic_sample *p, int which)
{
    return (double)pf_horizon_vmf_specular_lod(vmf_sum_sample(m, p, which), to_pf(p->wo), to_pf(p->wi),
                                               leadr_stats(m, p), (pf_real)(BASE_SIGMA * BASE_SIGMA),
                                               hdf_sample(m, p, p->wo), hdf_sample(m, p, p->wi), (pf_real)F0,
                                               pic_lod(p->fp), (pf_real)HOR_LOD_FULL, (pf_real)HOR_LOD_SMITH);
}
static double shade_vmf_m8_horizon(const pic_maps *m, const pic_sample *p) { return shade_vmf_horizon(m, p, 1); }
/* LEADR + horizon fed with the exact moments of the reference's box (an oracle, as leadr_box):
   the horizon's effect apart from the mip filter's footprint (the HDF is still trilinear) */
static double shade_leadr_box_horizon(const pic_maps *m, const pic_sample *p)
{
    return (double)pf_horizon_leadr_specular_lod(to_pf(p->wo), to_pf(p->wi), box_stats(m, p),
                                                 (pf_real)(BASE_SIGMA * BASE_SIGMA), hdf_sample(m, p, p->wo),
                                                 hdf_sample(m, p, p->wi), (pf_real)F0, pic_lod(p->fp),
                                                 (pf_real)HOR_LOD_FULL, (pf_real)HOR_LOD_SMITH);
}

/* ---------------------------------------------------------------- box taps
   A footprint-following fetch a shader can do, in place of the trilinear one: at level l =
   max(0, ceil(log2 side) - 1) the footprint's square is at most 2 texels of that level a side,
   so it touches at most 3 of them per axis, and its covered-area weights over them are 2 x 2
   bilinear taps at level l: per axis, the weights w0, w1, w2 of texels j0, j0 + 1, j0 + 2 are
   tap A between j0 and j0 + 1 (weight w0 + w1/2, fraction (w1/2)/(w0 + w1/2)) and tap B between
   j0 + 1 and j0 + 2 (weight w2 + w1/2, fraction w2/(w2 + w1/2)): 4 textureLod(..., l) fetches
   instead of one trilinear lookup (two levels' bilinear mixes, a footprint up to twice as wide).
   At level 0 (sides up to 2 texels) the taps are exactly the reference's square (sq_reference);
   above, the square is rounded to the level's texels within its 3 x 3. The moments, the HDF
   moments and the lobes' amplitudes are linear in the texels, so the weighted taps are that
   mean. Each tap is a pic_sample at the tap's coordinate with a footprint of 2^l texels (lod l),
   read through the same helpers as the trilinear rows (hdf_sample, vmf_sum_sample). */

/* the 4 taps of pixel p, their weights (sum 1), and the level */
static int box_taps(const pic_sample *p, pic_sample tap[4], double wt[4])
{
    double c[2][2], w[2][2], sc;
    int a, t, l = 0;
    while (l < 30 && p->fp > (double)(2 << l)) ++l; /* p->fp / 2^l in (1, 2], or <= 1 at level 0 */
    sc = (double)(1 << l);
    for (a = 0; a < 2; ++a) {
        double f = p->fp / sc, x = (a ? p->ty : p->tx) / sc, lo = x - 0.5 * f, hi = x + 0.5 * f;
        int j0 = (int)floor(lo);
        double w0 = cover_1d(j0, lo, hi) / f, w1 = cover_1d(j0 + 1, lo, hi) / f, w2 = cover_1d(j0 + 2, lo, hi) / f;
        double wa = w0 + 0.5 * w1, wb = w2 + 0.5 * w1;
        w[a][0] = wa;
        w[a][1] = wb;
        c[a][0] = sc * ((double)j0 + 0.5 + (wa > 0.0 ? 0.5 * w1 / wa : 0.0));
        c[a][1] = sc * ((double)j0 + 1.5 + (wb > 0.0 ? w2 / wb : 0.0));
    }
    for (t = 0; t < 4; ++t) {
        tap[t] = *p;
        tap[t].tx = c[0][t & 1];
        tap[t].ty = c[1][t >> 1];
        tap[t].fp = sc;
        wt[t] = w[0][t & 1] * w[1][t >> 1];
    }
    return l;
}

/* LEADR's slope statistics from the box taps */
static pf_slope_stats tap_stats(const pic_maps *m, const pic_sample *p)
{
    pic_sample tap[4];
    double wt[4], mo[5] = {0, 0, 0, 0, 0};
    int t;
    int l = box_taps(p, tap, wt);
    for (t = 0; t < 4; ++t) {
        pf_slope_moments s = pf_slope_moments_sample(m->slope_pyr, m->surf.w, m->surf.h, (pf_real)l,
                                                     (pf_real)(tap[t].tx / m->surf.w), (pf_real)(tap[t].ty / m->surf.h),
                                                     PF_BORDER_WRAP);
        mo[0] += wt[t] * (double)s.ex;
        mo[1] += wt[t] * (double)s.ey;
        mo[2] += wt[t] * (double)s.exx;
        mo[3] += wt[t] * (double)s.eyy;
        mo[4] += wt[t] * (double)s.exy;
    }
    return pf_slope_moments_stats(pf_slope_moments_make((pf_real)mo[0], (pf_real)mo[1], (pf_real)mo[2], (pf_real)mo[3],
                                                        (pf_real)mo[4]),
                                  (pf_real)(BASE_SIGMA * BASE_SIGMA));
}

/* the HDF moments toward w from the box taps */
static pf_hdf_moments tap_hdf(const pic_maps *m, const pic_sample *p, const double w[3])
{
    pic_sample tap[4];
    double wt[4], a[3] = {0, 0, 0};
    int t;
    box_taps(p, tap, wt);
    for (t = 0; t < 4; ++t) {
        pf_hdf_moments h = hdf_sample(m, &tap[t], w);
        a[0] += wt[t] * (double)h.m1;
        a[1] += wt[t] * (double)h.m2;
        a[2] += wt[t] * (double)h.ms;
    }
    return pf_hdf_moments_make((pf_real)a[0], (pf_real)a[1], (pf_real)a[2]);
}

/* the lobes of the box taps: every field of a pf_vmf_sum is a
   sum over lobes linear in their amplitudes, so the taps' sums weighted by the tap weights are
   the sum of the taps' lobes with their amplitudes so weighted */
static pf_vmf_sum tap_vmf_sum(const pic_maps *m, const pic_sample *p, int which)
{
    pic_sample tap[4];
    double wt[4];
    pf_vmf_sum s = pf_vmf_sum_zero();
    int t;
    box_taps(p, tap, wt);
    for (t = 0; t < 4; ++t) {
        pf_vmf_sum q = vmf_sum_sample(m, &tap[t], which);
        pf_real k = (pf_real)wt[t];
        s.amp += k * q.amp;
        s.ndf += k * q.ndf;
        s.ex += k * q.ex;
        s.ey += k * q.ey;
        s.exx += k * q.exx;
        s.eyy += k * q.eyy;
        s.exy += k * q.exy;
        s.excess_o += k * q.excess_o;
        s.excess_i += k * q.excess_i;
    }
    return s;
}

static double shade_leadr_tap(const pic_maps *m, const pic_sample *p)
{
    return (double)pf_leadr_specular(to_pf(p->wo), to_pf(p->wi), tap_stats(m, p), (pf_real)F0);
}
static double shade_leadr_horizon_tap(const pic_maps *m, const pic_sample *p)
{
    return (double)pf_horizon_leadr_specular_lod(to_pf(p->wo), to_pf(p->wi), tap_stats(m, p),
                                                 (pf_real)(BASE_SIGMA * BASE_SIGMA), tap_hdf(m, p, p->wo),
                                                 tap_hdf(m, p, p->wi), (pf_real)F0, pic_lod(p->fp),
                                                 (pf_real)HOR_LOD_FULL, (pf_real)HOR_LOD_SMITH);
}
static double shade_vmf_m8_tap(const pic_maps *m, const pic_sample *p)
{
    return (double)pf_vmf_sum_specular(tap_vmf_sum(m, p, 1), to_pf(p->wo), to_pf(p->wi), (pf_real)F0);
}
static double shade_vmf_m8_horizon_tap(const pic_maps *m, const pic_sample *p)
{
    return (double)pf_horizon_vmf_specular_lod(tap_vmf_sum(m, p, 1), to_pf(p->wo), to_pf(p->wi), tap_stats(m, p),
                                               (pf_real)(BASE_SIGMA * BASE_SIGMA), tap_hdf(m, p, p->wo),
                                               tap_hdf(m, p, p->wi), (pf_real)F0, pic_lod(p->fp),
                                               (pf_real)HOR_LOD_FULL, (pf_real)HOR_LOD_SMITH);
}
/* The drawn vMF m = 8 + horizon: the box taps under SWITCH_SIDE-texel footprint sides (where
   they halve the trilinear fetch's error: 18% against 27% under 16 texels, docs/horizon.md),
   the trilinear fetch from there on (within 2 points of the taps, one lookup instead of four),
   as a shader would switch on the footprint side it computes for the lod anyway. */
#define SWITCH_SIDE 16.0
static double shade_vmf_m8_horizon_switch(const pic_maps *m, const pic_sample *p)
{
    return p->fp < SWITCH_SIDE ? shade_vmf_m8_horizon_tap(m, p) : shade_vmf_m8_horizon(m, p);
}

/* ---------------------------------------------------------------- the method registry */
/* Every method of the pictures is one row here and one shading function above; everything
   else (the value and timing passes, the error statistics, the tables, the self-check, the
   panels) loops over the rows. Row 0 is the brute-force reference (no shading function: it
   is shade_reference, run by the brute-force step). To add a method: write
   double shade_x(const pic_maps *, const pic_sample *) and add its row. */
typedef struct {
    const char *key;    /* short name (method_index) */
    const char *label;  /* its row in the tables */
    const char *column; /* its column in the by-footprint table */
    double (*shade)(const pic_maps *m, const pic_sample *p); /* per pixel; NULL: the reference */
    const char *fetches; /* what it reads per pixel (on a GPU: its texture fetches) */
    int oracle;         /* 1: reads what a renderer does not have (the reference's own box) */
    int panel;          /* drawn as picture column 1..NPANEL_COLS - 1 (0: not drawn) */
    const char *panel_title, *panel_short;
    double check_bound; /* flat-map self-check bound; 0: the library's rounding (main) */
} pic_method;

static const pic_method pic_methods[] = {
    {"ref", "reference (brute force)", "reference", NULL,
     "every texel of the footprint (at most ref_max^2), marched toward wo and wi", 1, 0,
     "reference (brute force)", "reference", 0.0},
    {"leadr", "LEADR (trilinear)", "LEADR (trilinear)", shade_leadr,
     "5 slope moments, trilinear (8 texels x 5 values)", 0, 1, "LEADR (trilinear moments)", "LEADR", 0.0},
    {"leadr_box", "LEADR, exact box moments", "LEADR, exact box", shade_leadr_box,
     "the exact mean of the 5 moments over the reference's box (summed-area table, 4 x 5 doubles)", 1, 0,
     NULL, NULL, 0.0},
    {"leadr_hor", "LEADR + horizon (trilinear)", "LEADR + horizon", shade_leadr_horizon,
     "LEADR's, and 2 x 2 azimuths of the n = 32 HDF moments, trilinear (2 x 8 texels x 6 values)", 0, 0, NULL, NULL,
     HOR_CHECK_BOUND},
    {"leadr_box_hor", "LEADR + horizon, exact box moments", "LEADR + horizon, exact box", shade_leadr_box_horizon,
     "the exact box moments (as LEADR, exact box) and LEADR + horizon's HDF moments", 1, 0, NULL, NULL,
     HOR_CHECK_BOUND},
    {"naive", "naive mip-mapped normal", "naive", shade_naive,
     "average normal, trilinear (8 texels x 3 values)", 0, 4, "naive mip-mapped normal", "naive", 0.0},
    {"vmf4", "vMF m = 4 (trilinear lobes)", "vMF m = 4", shade_vmf_m4,
     "4 lobes of the 8 trilinear texels (8 x 4 x 4 values)", 0, 0, NULL, NULL, VMF_CHECK_BOUND},
    {"vmf8", "vMF m = 8 (trilinear lobes)", "vMF m = 8", shade_vmf_m8,
     "8 lobes of the 8 trilinear texels (8 x 8 x 4 values)", 0, 2, "vMF m = 8 (trilinear lobes)", "vMF m = 8",
     VMF_CHECK_BOUND},
    {"vmf8_hor", "vMF m = 8 + horizon (trilinear)", "vMF m = 8 + horizon", shade_vmf_m8_horizon,
     "vMF m = 8's, LEADR's moments, and 2 x 2 azimuths of the HDF moments (2 x 8 texels x 6 values)", 0, 0,
     NULL, NULL, VMF_CHECK_BOUND + HOR_CHECK_BOUND},
    {"leadr_tap", "LEADR (box taps)", "LEADR, taps", shade_leadr_tap,
     "5 slope moments, 4 bilinear taps at one level (16 texels x 5 values)", 0, 0, NULL,
     NULL, 0.0},
    {"leadr_hor_tap", "LEADR + horizon (box taps)", "LEADR + horizon, taps", shade_leadr_horizon_tap,
     "LEADR + horizon's values, 4 bilinear taps at one level (16 texels)", 0, 0, NULL,
     NULL, HOR_CHECK_BOUND},
    {"vmf8_tap", "vMF m = 8 (box taps)", "vMF m = 8, taps", shade_vmf_m8_tap,
     "8 lobes of the 16 texels of 4 bilinear taps at one level (16 x 8 x 4 values)", 0, 0, NULL, NULL,
     VMF_CHECK_BOUND},
    {"vmf8_hor_tap", "vMF m = 8 + horizon (box taps)", "vMF m = 8 + horizon, taps",
     shade_vmf_m8_horizon_tap,
     "vMF m = 8 + horizon's values, 4 bilinear taps at one level (16 texels)", 0, 0,
     NULL, NULL, VMF_CHECK_BOUND + HOR_CHECK_BOUND},
    {"vmf8_hor_sw", "vMF m = 8 + horizon (box taps under 16 texels, trilinear above)", "vMF m = 8 + horizon, drawn",
     shade_vmf_m8_horizon_switch,
     "vMF m = 8 + horizon (box taps)'s values under 16-texel footprint sides, vMF m = 8 + horizon (trilinear)'s "
     "from 16 on", 0, 3, "vMF m = 8 + horizon (pf_horizon.h; box taps < 16 texels)", "vMF m = 8 + horizon",
     VMF_CHECK_BOUND + HOR_CHECK_BOUND},
    {"vmf4s", "vMF m = 4, scaling function", "vMF m = 4, scaled", shade_vmf_m4_scaled,
     "vMF m = 4's, and T bilinear (4 values) and S (a 6 x 6 x 5 table, 8 values)", 0, 0, NULL, NULL, VMF_CHECK_BOUND},
    {"vmf8s", "vMF m = 8, scaling function", "vMF m = 8, scaled", shade_vmf_m8_scaled,
     "vMF m = 8's, and T bilinear (4 values) and S (a 6 x 6 x 5 table, 8 values)", 0, 0, NULL, NULL, VMF_CHECK_BOUND},
};
#define M_COUNT ((int)(sizeof pic_methods / sizeof pic_methods[0]))
#define M_REF   0

/* The row of the method named key (the analyses name the methods they compare); exits if none. */
static int method_index(const char *key)
{
    int k;
    for (k = 0; k < M_COUNT; ++k)
        if (!strcmp(pic_methods[k].key, key)) return k;
    fprintf(stderr, "pictures: no method \"%s\" in pic_methods\n", key);
    exit(1);
}

/* ---------------------------------------------------------------- scenes: per-pixel geometry */
typedef struct {
    const char *name;
    int w, h;
    double exposure;
    double bg[3];          /* background colour (linear) */
    int ref_max;           /* reference texels per footprint side, at most */
    pic_sample *px;
    unsigned char *vis_light; /* visibility toward the light when it is one direction in every
                                 pixel's frame (the plane: a map of the whole surface), or NULL */
} pic_scene;


#define PLANE_EXPOSURE   0.35   /* fixed; puts the reference's 99th percentile near 0.9 */

#define SPHERE_EXPOSURE  2.0

/* The pixels of scene which (bench/pic_scenes.h: cameras, lights, rays, footprints). */
static void scene_pixels(pic_scene *sc, const pic_maps *m, int which, int w, int h)
{
    pic_camera cam;
    double light[3];
    int i, j;
    pic_scene_view(which, w, h, 0.0, &cam, light);
    sc->w = w;
    sc->h = h;
    sc->px = (pic_sample *)pfb_xcalloc((size_t)w * (size_t)h, sizeof(pic_sample));
    sc->vis_light = NULL;
    if (which == PIC_PLANE) { /* the light is the same direction in every pixel's (world) frame: one visibility map */
        sc->vis_light = (unsigned char *)pfb_xmalloc((size_t)m->surf.w * (size_t)m->surf.h);
        pfm_visibility_map(&m->surf, light, sc->vis_light);
    }
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i)
            pic_scene_pixel(which, &cam, light, (double)m->surf.w, (double)m->surf.h, 0.0, i, j, &sc->px[(size_t)j * w + i]);
}

static void scene_plane(pic_scene *sc, const pic_maps *m, int w, int h)
{
    sc->name = "plane";
    sc->exposure = PLANE_EXPOSURE;
    sc->ref_max = REF_MAX_SAMPLES;
    v3_set(sc->bg, 0.30, 0.42, 0.60);
    scene_pixels(sc, m, PIC_PLANE, w, h);
}

static void scene_sphere(pic_scene *sc, const pic_maps *m, int w, int h)
{
    sc->name = "sphere";
    sc->exposure = SPHERE_EXPOSURE;
    sc->ref_max = SPHERE_REF_MAX;
    v3_set(sc->bg, 0.08, 0.09, 0.11);
    scene_pixels(sc, m, PIC_SPHERE, w, h);
}

/* ---------------------------------------------------------------- statistics */

typedef struct { double mean, p95; } pic_err;

#define PIC_BINS 9

static int footprint_bin(double fp)
{
    int b = 0;
    while (b < PIC_BINS - 1 && fp >= (double)(2 << b)) ++b;
    return b;
}

typedef struct {
    double *val[M_COUNT];
    double *inbox;           /* the reference with occluders inside the footprint box only */
    double *noise;           /* the reference's sampling deviation estimate (0: shaded fully) */
    double *ndf_t, *ndf_g;   /* NDF at h: the shaded texels' lobes, their Gaussian fit */
    double floor_ndf;        /* LIT_FRACTION of the 99th percentile of ndf_t */
    double seconds[M_COUNT]; /* shading time over all surface pixels */
    double seconds_inbox;    /* the in-box variant's extra marching and shading */
    int n_surface, n_lit, n_subsampled;
    int n_lit_u;             /* surface pixels lit in either reference (full or in-box) */
    int n_zero[M_COUNT];     /* lit pixels where the method returns exactly 0 (culled) */
    double floor;
    pic_err err[M_COUNT];    /* against the reference */
    pic_err err_in[M_COUNT]; /* against the in-box reference over the pixels lit in either
                                reference (M_REF: the full reference against the in-box one) */
    double fp_min, fp_med, fp_p95, fp_max;
    double samples_per_pixel; /* reference texels shaded per surface pixel (mean) */
    /* by footprint side: bin b holds sides in [2^b, 2^(b+1)) (bin 0 also below 1) */
    int bin_lit[PIC_BINS], bin_surface[PIC_BINS], bin_noisy[PIC_BINS], bin_lit_u[PIC_BINS];
    double bin_err[PIC_BINS][M_COUNT];    /* mean relative error over the bin's lit pixels */
    double bin_ratio[PIC_BINS][M_COUNT];  /* sum method / sum reference over all its pixels */
    /* over the pixels lit in either reference: mean relative error against the in-box
       reference, and against the full one (the two compared on the same pixels) */
    double bin_err_in[PIC_BINS][M_COUNT], bin_err_u[PIC_BINS][M_COUNT];
    double bin_noise[PIC_BINS];           /* rms relative sampling deviation of the reference */
    double bin_ndf[PIC_BINS];             /* mean NDF error over the bin's pixels lit in either */
} pic_result;

/* Relative error of v against the reference value ref: |v - ref| / max(ref, floor). */
static double rel_err(double v, double ref, double floor_)
{
    return fabs(v - ref) / (ref > floor_ ? ref : floor_);
}

/* Comparisons between the two references (pixels lit in either): every error of pixel i is
   divided by the larger of the two references and the floor, so that errors against the full
   and against the in-box reference differ only in their numerators. */
static double pair_floor(const pic_result *r, int i)
{
    double a = r->val[M_REF][i], b = r->inbox[i];
    double m = a > b ? a : b;
    return m > r->floor ? m : r->floor;
}

/* ---------------------------------------------------------------- rendering on every core */
#define PIC_TIME_REF_PIXELS 400      /* the reference is timed on this many pixels (about) */
#define PIC_TIME_METHOD_PIXELS 16384 /* the filtered methods on this many (about), best of 5 */

static void result_alloc(pic_result *r, int n)
{
    int mth;
    memset(r, 0, sizeof *r);
    for (mth = 0; mth < M_COUNT; ++mth) r->val[mth] = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
    r->inbox = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
    r->noise = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
    r->ndf_t = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
    r->ndf_g = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
}

/* The brute force of a few scenes tiling the same maps as one parallel step whose items are
   image rows (every pixel's reference depends on that pixel alone: the results do not depend
   on the thread count), and, as its item 0 when `scale` is set, the scaling function of those
   maps (maps_scale: serial code, so one item; the longest, so first; it runs beside the rows). */
#define PIC_MAX_SCENES 2
typedef struct {
    const pic_maps *m;
    pic_maps *scale;
    int nscene;
    const pic_scene *sc[PIC_MAX_SCENES];
    pic_result *r[PIC_MAX_SCENES];
} pic_bf_step;

static void bf_row(const pic_maps *m, const pic_scene *sc, pic_result *r, int j)
{
    ref_texel *scratch = (ref_texel *)pfb_xmalloc(sizeof(ref_texel) * REF_SCRATCH * REF_SCRATCH);
    int i;
    for (i = j * sc->w; i < (j + 1) * sc->w; ++i) {
        ref_result q;
        r->val[M_REF][i] = r->inbox[i] = r->noise[i] = r->ndf_t[i] = r->ndf_g[i] = 0.0;
        if (!sc->px[i].hit) continue;
        q = pic_reference(&m->surf, sc->vis_light, &sc->px[i], sc->ref_max, scratch);
        r->val[M_REF][i] = q.full;
        r->inbox[i] = q.inbox;
        r->noise[i] = q.noise;
        r->ndf_t[i] = q.ndf_texels;
        r->ndf_g[i] = q.ndf_gauss;
    }
    free(scratch);
}

static void bf_item(void *ctx, long long it)
{
    pic_bf_step *st = (pic_bf_step *)ctx;
    int k;
    if (st->scale) {
        if (it == 0) {
            maps_scale(st->scale, NULL);
            return;
        }
        --it;
    }
    for (k = 0; k < st->nscene; ++k) {
        if (it < st->sc[k]->h) {
            bf_row(st->m, st->sc[k], st->r[k], (int)it);
            return;
        }
        it -= st->sc[k]->h;
    }
}

static void brute_force(const pic_maps *m, pic_maps *scale, int nscene, const pic_scene *const *sc, pic_result *const *r,
                        const char *label)
{
    pic_bf_step st;
    long long items = scale ? 1 : 0;
    int k;
    if (nscene > PIC_MAX_SCENES) {
        fprintf(stderr, "pictures: brute_force takes %d scenes at most\n", PIC_MAX_SCENES);
        exit(1);
    }
    st.m = m;
    st.scale = scale;
    st.nscene = nscene;
    for (k = 0; k < nscene; ++k) {
        st.sc[k] = sc[k];
        st.r[k] = r[k];
        items += sc[k]->h;
    }
    pfb_parallel_for(items, bf_item, &st, label);
}

/* The filtered methods' values, one parallel item per image row. */
typedef struct {
    const pic_maps *m;
    const pic_scene *sc;
    pic_result *r;
} pic_method_step;

static void methods_item(void *ctx, long long j)
{
    const pic_method_step *st = (const pic_method_step *)ctx;
    int i, mth;
    for (i = (int)j * st->sc->w; i < ((int)j + 1) * st->sc->w; ++i) {
        const pic_sample *p = &st->sc->px[i];
        for (mth = 1; mth < M_COUNT; ++mth) st->r->val[mth][i] = p->hit ? pic_methods[mth].shade(st->m, p) : 0.0;
    }
}

/* Times, single-threaded and apart from the parallel steps: the reference (full and in-box
   variant) over about PIC_TIME_REF_PIXELS surface pixels evenly spread over the image, each
   filtered method over about PIC_TIME_METHOD_PIXELS (best of 5 passes); scaled to all the
   surface pixels (seconds[], seconds_inbox). The values computed here are discarded: they are
   those of the parallel steps. */
static void time_scene(const pic_maps *m, const pic_scene *sc, pic_result *r)
{
    int n = sc->w * sc->h, i, k, mth, nt = 0, ns = 0;
    int stride_ref = r->n_surface / PIC_TIME_REF_PIXELS, stride = r->n_surface / PIC_TIME_METHOD_PIXELS;
    int *timed = (int *)pfb_xmalloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    ref_texel *scratch = (ref_texel *)pfb_xmalloc(sizeof(ref_texel) * REF_SCRATCH * REF_SCRATCH);
    double t_full = 0.0, t_inbox = 0.0, sink = 0.0;
    if (stride_ref < 1) stride_ref = 1;
    if (stride < 1) stride = 1;
    for (i = 0, k = 0; i < n; ++i)
        if (sc->px[i].hit && k++ % stride_ref == 0) {
            ref_result q = pic_reference(&m->surf, sc->vis_light, &sc->px[i], sc->ref_max, scratch);
            t_full += q.t_full;
            t_inbox += q.t_inbox;
            ++nt;
        }
    r->seconds[M_REF] = nt ? t_full * r->n_surface / nt : 0.0;
    r->seconds_inbox = nt ? t_inbox * r->n_surface / nt : 0.0;
    for (i = 0, k = 0; i < n; ++i)
        if (sc->px[i].hit && k++ % stride == 0) timed[ns++] = i;
    for (mth = 1; mth < M_COUNT; ++mth) {
        double best = 1e30;
        for (k = 0; k < 5; ++k) {
            double t0 = pfb_now_s(), t;
            for (i = 0; i < ns; ++i) sink += pic_methods[mth].shade(m, &sc->px[timed[i]]);
            t = pfb_now_s() - t0;
            if (t < best) best = t;
        }
        r->seconds[mth] = ns ? best * r->n_surface / ns : 0.0;
    }
    if (sink != sink) fprintf(stderr, "pictures: a timed method returned NaN\n"); /* keeps the calls */
    free(timed);
    free(scratch);
}

/* The filtered methods on every core, and (timed = 1) the times, then the statistics of the
   scene, given its brute force (brute_force). */
static void render_scene(const pic_maps *m, const pic_scene *sc, pic_result *r, int timed, const char *label)
{
    int n = sc->w * sc->h, i, k, mth, b;
    double *tmp = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
    double *tmp_in = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
    double *fps = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
    double samples = 0.0, sref[PIC_BINS];
    pic_method_step ms;
    ms.m = m;
    ms.sc = sc;
    ms.r = r;
    pfb_parallel_for(sc->h, methods_item, &ms, label);
    for (i = 0; i < n; ++i)
        if (sc->px[i].hit) {
            const pic_sample *p = &sc->px[i];
            int side = footprint_side(p->fp);
            int ns = side < sc->ref_max ? side : sc->ref_max;
            fps[r->n_surface] = p->fp;
            tmp[r->n_surface++] = r->val[M_REF][i];
            if (sq_covered(p)) /* the texels the square touches (sq_reference) */
                samples += (double)((int)floor(p->tx + 0.5 * p->fp) - (int)floor(p->tx - 0.5 * p->fp) + 1) *
                           (double)((int)floor(p->ty + 0.5 * p->fp) - (int)floor(p->ty - 0.5 * p->fp) + 1);
            else
                samples += (double)ns * ns;
            if (side > sc->ref_max) r->n_subsampled++;
        }
    r->samples_per_pixel = r->n_surface ? samples / r->n_surface : 0.0;
    if (timed) time_scene(m, sc, r);
    r->floor = LIT_FRACTION * quantile(tmp, r->n_surface, 0.99);
    for (i = 0, k = 0; i < n; ++i)
        if (sc->px[i].hit) tmp_in[k++] = r->ndf_t[i];
    r->floor_ndf = LIT_FRACTION * quantile(tmp_in, k, 0.99);
    printf("  reference quantiles: 50%% %.3g, 90%% %.3g, 99%% %.3g\n",
           quantile(tmp, r->n_surface, 0.5), quantile(tmp, r->n_surface, 0.9),
           quantile(tmp, r->n_surface, 0.99));
    r->fp_min = quantile(fps, r->n_surface, 0.0);
    r->fp_med = quantile(fps, r->n_surface, 0.5);
    r->fp_p95 = quantile(fps, r->n_surface, 0.95);
    r->fp_max = quantile(fps, r->n_surface, 1.0);
    /* lit pixels: the reference at least the floor; errors against the reference and against
       the in-box reference (M_REF's "error" against the in-box one: how much the occluders
       outside the footprint change the answer) */
    for (mth = 0; mth < M_COUNT; ++mth) {
        int nl = 0, nu = 0;
        double sum = 0.0, sum_in = 0.0;
        for (i = 0; i < n; ++i) {
            double ref = r->val[M_REF][i];
            if (!sc->px[i].hit) continue;
            if (ref >= r->floor) {
                tmp[nl] = rel_err(r->val[mth][i], ref, r->floor);
                if (r->val[mth][i] == 0.0) r->n_zero[mth]++;
                sum += tmp[nl++];
            }
            if (ref >= r->floor || r->inbox[i] >= r->floor) {
                tmp_in[nu] = rel_err(r->val[mth][i], r->inbox[i], pair_floor(r, i));
                sum_in += tmp_in[nu++];
            }
        }
        r->n_lit = nl;
        r->n_lit_u = nu;
        r->err[mth].mean = nl ? sum / nl : 0.0;
        r->err[mth].p95 = quantile(tmp, nl, 0.95);
        r->err_in[mth].mean = nu ? sum_in / nu : 0.0;
        r->err_in[mth].p95 = quantile(tmp_in, nu, 0.95);
    }
    memset(sref, 0, sizeof sref);
    for (i = 0; i < n; ++i) {
        double ref = r->val[M_REF][i];
        if (!sc->px[i].hit) continue;
        b = footprint_bin(sc->px[i].fp);
        r->bin_surface[b]++;
        sref[b] += ref;
        for (mth = 1; mth < M_COUNT; ++mth) r->bin_ratio[b][mth] += r->val[mth][i];
        r->bin_ratio[b][M_REF] += r->inbox[i];
        if (ref >= r->floor || r->inbox[i] >= r->floor) { /* lit in either reference */
            r->bin_lit_u[b]++;
            r->bin_ndf[b] += rel_err(r->ndf_g[i], r->ndf_t[i], r->floor_ndf);
            for (mth = 0; mth < M_COUNT; ++mth) {
                r->bin_err_u[b][mth] += rel_err(r->val[mth][i], ref, pair_floor(r, i));
                r->bin_err_in[b][mth] += rel_err(r->val[mth][i], r->inbox[i], pair_floor(r, i));
            }
        }
        if (!(ref >= r->floor)) continue;
        r->bin_lit[b]++;
        for (mth = 0; mth < M_COUNT; ++mth)
            r->bin_err[b][mth] += rel_err(r->val[mth][i], ref, r->floor);
        if (footprint_side(sc->px[i].fp) > sc->ref_max) {
            double e = r->noise[i] / (ref > r->floor ? ref : r->floor);
            r->bin_noisy[b]++;
            r->bin_noise[b] += e * e;
        }
    }
    for (b = 0; b < PIC_BINS; ++b) {
        for (mth = 0; mth < M_COUNT; ++mth) {
            if (r->bin_lit[b]) r->bin_err[b][mth] /= r->bin_lit[b];
            if (r->bin_lit_u[b]) {
                r->bin_err_u[b][mth] /= r->bin_lit_u[b];
                r->bin_err_in[b][mth] /= r->bin_lit_u[b];
            }
            if (sref[b] > 0.0) r->bin_ratio[b][mth] /= sref[b];
        }
        if (r->bin_noisy[b]) r->bin_noise[b] = sqrt(r->bin_noise[b] / r->bin_noisy[b]);
        if (r->bin_lit_u[b]) r->bin_ndf[b] /= r->bin_lit_u[b];
    }
    free(tmp);
    free(tmp_in);
    free(fps);
}

static void result_free(pic_result *r)
{
    int k;
    for (k = 0; k < M_COUNT; ++k) free(r->val[k]);
    free(r->inbox);
    free(r->noise);
    free(r->ndf_t);
    free(r->ndf_g);
}

/* ---------------------------------------------------------------- the picture (gnuplot) */
/* gnuplot draws the picture from the values themselves, not from colours made here:
   DIR/pic_NAME.bin holds 2 NPANEL_COLS float32 planes of w x h pixels (native byte order, bottom row
   first as gnuplot's binary arrays go): the radiance of the reference, LEADR, vMF m = 8 and
   naive; the footprint side in texels; the relative error of the three methods in percent, clamped to
   the colour scale; NaN where the pixel misses the surface. DIR/pic_NAME.gpv sets the
   script's variables (sizes, exposure, colour ranges, and titles carrying this run's numbers);
   bench/pictures.gp (gp) lays out the NPANEL_COLS x 2 panels with a title and a numbered colour bar on
   each. Both files are removed once gnuplot has written the PNG. Returns 0 on success. */
#define NPANEL_COLS 5 /* the reference and the methods with a panel (pic_methods: LEADR, vMF m = 8,
                         vMF m = 8 + horizon, naive); below: the footprint and their errors */
static int write_picture(const pic_scene *sc, const pic_result *r, const char *outdir,
                         const char *png, const char *gp)
{
    int w = sc->w, h = sc->h, n = w * h, x, y, k, rc;
    int methods[NPANEL_COLS]; /* the method of each panel column (pic_methods[].panel) */
    double e_lo = pow(10.0, ERR_LOG_MIN), e_hi = pow(10.0, ERR_LOG_MAX);
    double us_ref = 1e6 * r->seconds[M_REF] / r->n_surface;
    char bin[1024], gpv[1024], cmd[4096];
    float *plane = (float *)malloc(sizeof(float) * (size_t)n);
    FILE *f;
    methods[0] = M_REF;
    for (k = 1; k < NPANEL_COLS; ++k) methods[k] = -1;
    for (k = 1; k < M_COUNT; ++k)
        if (pic_methods[k].panel > 0 && pic_methods[k].panel < NPANEL_COLS) methods[pic_methods[k].panel] = k;
    for (k = 1; k < NPANEL_COLS; ++k)
        if (methods[k] < 0) {
            fprintf(stderr, "pictures: no method in pic_methods has panel %d\n", k);
            free(plane);
            return 1;
        }
    snprintf(bin, sizeof bin, "%s/pic_%s.bin", outdir, sc->name);
    snprintf(gpv, sizeof gpv, "%s/pic_%s.gpv", outdir, sc->name);
    f = fopen(bin, "wb");
    if (!f || !plane) {
        if (f) fclose(f);
        free(plane);
        return 1;
    }
    for (k = 0; k < 2 * NPANEL_COLS; ++k) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                int i_img = y * w + x; /* image row y from the top; the file's row h - 1 - y */
                double v = 0.0;
                if (!sc->px[i_img].hit) v = (double)NAN;
                else if (k < NPANEL_COLS) v = r->val[methods[k]][i_img];
                else if (k == NPANEL_COLS) v = sc->px[i_img].fp;
                else {
                    double ref = r->val[M_REF][i_img];
                    v = fabs(r->val[methods[k - NPANEL_COLS]][i_img] - ref) / (ref > r->floor ? ref : r->floor);
                    v = 100.0 * (v < e_lo ? e_lo : (v > e_hi ? e_hi : v));
                }
                if (k == NPANEL_COLS && v < FP_SHOWN_MIN) v = FP_SHOWN_MIN;
                plane[(size_t)(h - 1 - y) * w + x] = (float)v;
            }
        if (fwrite(plane, sizeof(float), (size_t)n, f) != (size_t)n) break;
    }
    free(plane);
    if (fclose(f) != 0 || k < 2 * NPANEL_COLS) return 1;
    f = fopen(gpv, "w");
    if (!f) return 1;
    /* gnuplot strings in double quotes: \n is a line break */
    fprintf(f, "# written by bench/pictures.c for %s\n", gp);
    fprintf(f, "datf = \"%s\"\noutf = \"%s/%s\"\nw = %d\nh = %d\n", bin, outdir, png, w, h);
    fprintf(f, "expo = %.6g\nlmax = %.6g\n", sc->exposure, WHITE_EXPOSURE / sc->exposure);
    fprintf(f, "bg = \"#%02x%02x%02x\"\n", (unsigned)floor(255.0 * pow(sc->bg[0], 1.0 / 2.2) + 0.5),
            (unsigned)floor(255.0 * pow(sc->bg[1], 1.0 / 2.2) + 0.5),
            (unsigned)floor(255.0 * pow(sc->bg[2], 1.0 / 2.2) + 0.5));
    fprintf(f, "errlo = %.6g\nerrhi = %.6g\nfplo = %.6g\nfphi = %.6g\n", 100.0 * e_lo,
            100.0 * e_hi, FP_SHOWN_MIN, (double)map_side());
    if (strcmp(sc->name, "plane") == 0)
        fprintf(f, "ttl = \"Rough specular plane toward the horizon, brute force against the "
                   "filtered formulas\\n%dx%d %s tiled, light %.0f degrees "
                   "above the horizon, %dx%d pixels\"\n",
                map_side(), map_side(), user_map ? map_title : "Gaussian height map", PLANE_LIGHT_ELEV, w, h);
    else
        fprintf(f, "ttl = \"Sphere in LEADR's domain, brute force against the filtered "
                   "formulas\\n%dx%d %s tiled %d times around the equator, "
                   "%dx%d pixels\"\n",
                map_side(), map_side(), user_map ? map_title : "Gaussian height map", SPHERE_TILES, w, h);
    fprintf(f, "t0 = \"reference (brute force)\\n%.0f us per pixel\"\n", us_ref);
    for (k = 1; k < NPANEL_COLS; ++k)
        fprintf(f, "t%d = \"%s\\n%.0f ns per pixel (%.0fx faster)\"\n", k, pic_methods[methods[k]].panel_title,
                1e9 * r->seconds[methods[k]] / r->n_surface,
                r->seconds[M_REF] / r->seconds[methods[k]]);
    fprintf(f, "t%d = \"footprint side (texels)\\nmedian %.1f, max %.0f\"\n", NPANEL_COLS, r->fp_med, r->fp_max);
    for (k = 1; k < NPANEL_COLS; ++k)
        fprintf(f, "t%d = \"%s: relative error\\nmean %.0f%%, 95th percentile %.0f%%\"\n",
                k + NPANEL_COLS, pic_methods[methods[k]].panel_short, 100.0 * r->err[methods[k]].mean,
                100.0 * r->err[methods[k]].p95);
    fprintf(f, "ncols = %d\n", NPANEL_COLS);
    fprintf(f, "note = \"Top: reflected radiance L per unit light radiance, one exposure for "
               "all (display 1 - exp(-%.2f L), gamma 2.2).\\nBottom: the footprint side "
               "of each pixel in texels; the relative error |method - reference| / "
               "max(reference, %.0f%% of its 99th percentile),\\nlog scale, clamped at %.1f%% and "
               "%.0f%%. Grey: no surface. Titles: time per pixel on one core; mean and 95th "
               "percentile of the error over the lit pixels.\"\n",
            sc->exposure, 100.0 * LIT_FRACTION, 100.0 * e_lo, 100.0 * e_hi);
    if (fclose(f) != 0) return 1;
    snprintf(cmd, sizeof cmd, "gnuplot '%s' '%s'", gpv, gp);
    rc = system(cmd);
    if (rc != 0) {
        fprintf(stderr, "pictures: `%s` failed (exit %d); its inputs are kept\n", cmd, rc);
        return 1;
    }
    remove(bin);
    remove(gpv);
    return 0;
}

/* ---------------------------------------------------------------- main */
static const char *const err_scale_text =
    "relative error, log scale from 3.2% (black) to 316% (pale yellow), clamped at both ends";

/* Mean of a per-bin quantity over bins b0 .. b1 - 1, weighted by the counts of pixels lit in
   either reference (noise = 1: rms, weighted by the counts of subsampled lit pixels). */
static double bins_mean(const pic_result *r, const double *per_bin, int stride, int b0, int b1,
                        int noise)
{
    double s = 0.0, w = 0.0;
    int b;
    for (b = b0; b < b1; ++b) {
        double wb = noise ? (double)r->bin_noisy[b] : (double)r->bin_lit_u[b];
        double v = per_bin[b * stride];
        s += wb * (noise ? v * v : v);
        w += wb;
    }
    if (!(w > 0.0)) return 0.0;
    return noise ? sqrt(s / w) : s / w;
}

#define SMALL_BINS 4 /* bins 0-3: footprint sides under 16 texels */

/* x as a percentage for "%.0f%%", without a "-0" for tiny negatives */
/* First cell of a footprint-bin row: bin k holds sides in [2^k, 2^(k+1)) texels, the first
   everything below 2 and the last everything from 2^k up. */
static void print_bin_label(FILE *md, int k)
{
    if (k == 0) fprintf(md, "| < 2 |");
    else if (k == PIC_BINS - 1) fprintf(md, "| >= %d |", 1 << k);
    else fprintf(md, "| %d - %d |", 1 << k, 2 << k);
}

static double pct(double x)
{
    double v = 100.0 * x;
    return fabs(v) < 0.5 ? 0.0 : v;
}

/* Mean error of method k over footprint sides under 16 texels: over the pixels lit in either
   reference (bins_mean of bin_err_u) or (lit_only) over the lit pixels (bin_err by bin_lit). */
static double small_err(const pic_result *r, int k, int lit_only)
{
    double sum = 0.0;
    int b, n = 0;
    if (!lit_only) return bins_mean(r, &r->bin_err_u[0][k], M_COUNT, 0, SMALL_BINS, 0);
    for (b = 0; b < SMALL_BINS; ++b) {
        sum += r->bin_err[b][k] * r->bin_lit[b];
        n += r->bin_lit[b];
    }
    return n ? sum / n : 0.0;
}

/* The horizon methods against their unshadowed methods under 16 texels, and which method to
   draw: the non-oracle method with the smallest error there over the pixels lit in either
   reference (the set where a shadow cast from outside the footprint counts). */
static void describe_horizon(FILE *md, const pic_scene *sc, const pic_result *r, const pic_maps *m)
{
    const int pairs[3][2] = {{method_index("leadr"), method_index("leadr_hor")},
                             {method_index("vmf8"), method_index("vmf8_hor")},
                             {method_index("leadr_box"), method_index("leadr_box_hor")}};
    int k, best = -1, lit_s = 0;
    for (k = 0; k < SMALL_BINS; ++k) lit_s += r->bin_lit_u[k];
    if (lit_s == 0) return;
    for (k = 1; k < M_COUNT; ++k)
        if (!pic_methods[k].oracle && (best < 0 || small_err(r, k, 0) < small_err(r, best, 0))) best = k;
    fprintf(md, "**Horizon visibility (%s).** The horizon methods (`pf_horizon_leadr_specular_lod`, "
                "`pf_horizon_vmf_specular_lod`: the reflecting facets' visibility toward the view and the light "
                "from the HDF moments of the whole height field, %d azimuths, %d-texel march, sampled "
                "trilinearly like the moments; faded to the unshadowed method from %.0f- to %.0f-texel "
                "footprint sides) see the bumps outside the footprint, as the full reference does. "
                "Footprint sides under 16 texels, mean error against the full reference over the %d pixels "
                "lit in either reference, without and with the horizon:",
            sc->name, HOR_N, HOR_STEPS, pow(2.0, HOR_LOD_FULL), pow(2.0, HOR_LOD_SMITH), lit_s);
    for (k = 0; k < 3; ++k)
        fprintf(md, "%s %s %.1f%% -> %.1f%%", k ? ";" : "", pic_methods[pairs[k][0]].column,
                100.0 * small_err(r, pairs[k][0], 0), 100.0 * small_err(r, pairs[k][1], 0));
    fprintf(md, ". Over the lit pixels alone (the reference above the floor: a pixel the full reference "
                "leaves in shadow does not count, however bright a method draws it):");
    for (k = 0; k < 3; ++k)
        fprintf(md, "%s %s %.0f%% -> %.0f%%", k ? ";" : "", pic_methods[pairs[k][0]].column,
                100.0 * small_err(r, pairs[k][0], 1), 100.0 * small_err(r, pairs[k][1], 1));
    fprintf(md, ". The method to draw under 16 texels, by the first measure: **%s** (%.0f%%; %.0f ns per "
                "pixel on one core). The exact-box rows are oracles (they read the reference's own box): their "
                "gap to the trilinear rows is the mip filter's footprint, which no visibility term "
                "repairs.\n\n",
            pic_methods[best].label, 100.0 * small_err(r, best, 0), 1e9 * r->seconds[best] / r->n_surface);
    { /* the drawn panel: the taps under 16 texels, so its error there is the taps row's */
        const int sw = method_index("vmf8_hor_sw"), tri = method_index("vmf8_hor");
        fprintf(md, "The picture draws %s: under 16 texels %.1f%% (the trilinear fetch: %.1f%%; half of the "
                    "unshadowed vMF m = 8 (trilinear) in this run, %.1f%%, is %.1f%%), over all lit pixels %.1f%% (trilinear: "
                    "%.1f%%).\n\n",
                pic_methods[sw].label, 100.0 * small_err(r, sw, 0), 100.0 * small_err(r, tri, 0),
                100.0 * small_err(r, method_index("vmf8"), 0), 50.0 * small_err(r, method_index("vmf8"), 0),
                100.0 * r->err[sw].mean, 100.0 * r->err[tri].mean);
    }
    { /* the bias of the 4-16-texel rows: pixels whose footprint faces away from the view on average */
        const int lh = method_index("leadr_hor"), ll = method_index("leadr"), vh = method_index("vmf8_hor");
        int b, i, n_away[2] = {0, 0}, n_all[2] = {0, 0};
        double s_ref[2] = {0, 0}, s_away[2][3] = {{0, 0, 0}, {0, 0, 0}}, s_face[2][3] = {{0, 0, 0}, {0, 0, 0}};
        for (i = 0; i < sc->w * sc->h; ++i) {
            const pic_sample *p = &sc->px[i];
            pf_slope_stats st;
            int away;
            if (!p->hit || p->fp < 4.0 || p->fp >= 16.0) continue;
            b = p->fp < 8.0 ? 0 : 1;
            st = box_stats(m, p);
            away = !(p->wo[2] - (double)st.mean_x * p->wo[0] - (double)st.mean_y * p->wo[1] > 0.0);
            n_all[b]++;
            n_away[b] += away;
            s_ref[b] += r->val[M_REF][i];
            s_away[b][0] += away ? r->val[lh][i] : 0.0, s_face[b][0] += away ? 0.0 : r->val[lh][i];
            s_away[b][1] += away ? r->val[ll][i] : 0.0, s_face[b][1] += away ? 0.0 : r->val[ll][i];
            s_away[b][2] += away ? r->val[vh][i] : 0.0, s_face[b][2] += away ? 0.0 : r->val[vh][i];
        }
        if (n_all[0] > 0 && n_all[1] > 0 && s_ref[0] > 0.0 && s_ref[1] > 0.0)
            fprintf(md, "**Bias at 4-16 texels (%s).** Of the surface pixels with footprint sides of 4-8 and 8-16 "
                        "texels, %d of %d and %d of %d have a footprint whose mean plane faces away from the view "
                        "(its texels' projected areas sum to 0 or less, from the exact moments): the reference is 0 "
                        "there by its normalization (sum V a spec / sum a, LEADR eqs. 1-3), while a method whose "
                        "trilinear moments have another mean slope still shades them. Their sums, over the row's "
                        "reference sum (4-8, 8-16): LEADR + horizon %.2f, %.2f; LEADR %.2f, %.2f; vMF m = 8 + "
                        "horizon %.2f, %.2f. The bias over the other pixels: LEADR + horizon %.2f, %.2f; LEADR "
                        "%.2f, %.2f; vMF m = 8 + horizon %.2f, %.2f (the sums of the two parts are the table's bias "
                        "column).\n\n",
                    sc->name, n_away[0], n_all[0], n_away[1], n_all[1], s_away[0][0] / s_ref[0], s_away[1][0] / s_ref[1],
                    s_away[0][1] / s_ref[0], s_away[1][1] / s_ref[1], s_away[0][2] / s_ref[0], s_away[1][2] / s_ref[1],
                    s_face[0][0] / s_ref[0], s_face[1][0] / s_ref[1], s_face[0][1] / s_ref[0], s_face[1][1] / s_ref[1],
                    s_face[0][2] / s_ref[0], s_face[1][2] / s_ref[1]);
    }
}

static void describe_scene(FILE *md, const pic_scene *sc, const pic_result *r, const char *png,
                           const pic_maps *m)
{
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    double us_ref = 1e6 * r->seconds[M_REF] / r->n_surface;
    double box_s, box_l, in_s, in_l, oof_s, oof_l, tri_s, tri_l, trin_s, trin_l, noise_l;
    double ndf_s, ndf_l;
    const int leadr = method_index("leadr"), box = method_index("leadr_box"), naive = method_index("naive");
    int k, lit_s = 0, lit_l = 0, n_noisy = 0;
    if (user_map) {
        p.rms_slope = map_rms;
        p.corr_texels = map_corr;
    }
    fprintf(md, "![%s: reference, LEADR, vMF m = 8, vMF m = 8 + horizon, naive; footprint size, LEADR error, vMF error, "
                "vMF + horizon error, naive error](%s)\n\n",
            sc->name, png);
    if (strcmp(sc->name, "plane") == 0)
        fprintf(md,
                "**Rough specular plane.** A %dx%d %s: "
                "RMS slope %.2f per axis, correlation length %.0f texels), tiled on the plane "
                "z = 0, seen by a pinhole camera %.0f texels above it, pitched %.0f degrees down "
                "(vertical field of view %.0f degrees) toward the horizon; a directional light "
                "%.0f degrees above the horizon, in front of the camera (%.0f degrees to the "
                "right). The footprints run from resolved bumps near the camera to thousands of "
                "bumps at the horizon. ",
                m->surf.w, m->surf.h, user_map ? map_label : "Gaussian height map (`pfm` corpus defaults",
                p.rms_slope, p.corr_texels, PLANE_CAM_HEIGHT,
                PLANE_PITCH_DEG, PLANE_FOV_DEG, PLANE_LIGHT_ELEV, PLANE_LIGHT_AZIM);
    else
        fprintf(md,
                "**Sphere, in LEADR's domain.** The same %dx%d height map wrapped around a "
                "sphere (longitude-latitude map, %d tiles around the equator, texels square at "
                "the equator), seen from %.1f radii; a directional light from the upper right, on "
                "the camera's side; view and light rotated into each pixel's tangent frame. The "
                "map is tiled finely enough that every pixel covers several to many bumps "
                "(footprint sides of %.0f texels and more against the %.0f-texel correlation "
                "length): the regime where LEADR claims to match a supersampled reference "
                "(Dupuy et al. 2013 sec. 7). ",
                m->surf.w, m->surf.h, SPHERE_TILES, SPHERE_CAM_DIST / SPHERE_RADIUS,
                floor(r->fp_min), p.corr_texels);
    fprintf(md,
            "Image %dx%d pixels: %d on the surface, %d lit (reference >= %.0f%% of its 99th "
            "percentile). Footprint side in texels: min %.2f, median %.1f, 95th percentile %.0f, "
            "max %.0f; the reference shades the footprint's square (side the footprint, centred on the hit) "
            "with every texel it touches weighted by the area it covers, up to %d texels a side, and beyond "
            "that the round(side)^2 texel box (%d pixels subsampled to %dx%d evenly spaced texels; %.0f texels "
            "shaded per pixel on average). Base lobe deviation %.2f, no Fresnel. Top: reference, LEADR, the 8-lobe "
            "vMF mixture of `pf_vmf.h`, the same with the horizon visibility of `pf_horizon.h` (fetched by 4 box taps under 16-texel footprint sides, trilinearly above), naive mip-mapped normal (same fixed exposure %.2f, display 1 - exp(-exposure L), gamma "
            "2.2; the colour bar gives the radiance). Bottom: the footprint side in texels (log scale), "
            "the error of LEADR, vMF m = 8, vMF m = 8 + horizon and naive (%s). Every panel carries its title and colour "
            "bar.\n\n",
            sc->w, sc->h, r->n_surface, r->n_lit, 100.0 * LIT_FRACTION, r->fp_min, r->fp_med,
            r->fp_p95, r->fp_max, REF_MAX_SAMPLES, r->n_subsampled, sc->ref_max, sc->ref_max,
            r->samples_per_pixel, BASE_SIGMA, sc->exposure, err_scale_text);
    fprintf(
        md,
        "| %s: method | mean rel. error (lit pixels) | 95th percentile | against the in-box "
        "reference (pixels lit in either): mean, 95th | lit pixels returned 0 | time per pixel | "
        "brute force / this |\n|---|---|---|---|---|---|---|\n",
        sc->name);
    fprintf(md, "| %s | - | - | %.1f%%, %.1f%% | - | %.1f us | 1 |\n", pic_methods[M_REF].label,
            100.0 * r->err_in[M_REF].mean, 100.0 * r->err_in[M_REF].p95, us_ref);
    for (k = 1; k < M_COUNT; ++k)
        fprintf(md, "| %s | %.1f%% | %.1f%% | %.1f%%, %.1f%% | %d | %.0f ns | %.0f |\n",
                pic_methods[k].label, 100.0 * r->err[k].mean, 100.0 * r->err[k].p95,
                100.0 * r->err_in[k].mean, 100.0 * r->err_in[k].p95, r->n_zero[k],
                1e9 * r->seconds[k] / r->n_surface, r->seconds[M_REF] / r->seconds[k]);
    fprintf(md, "\n\"Lit pixels returned 0\": lit pixels (reference at least the floor) where the "
                "method's value is exactly 0, drawn black; the target is 0 for every filtered "
                "method (issue 15).\n");
    fprintf(md, "\nBy footprint side: mean relative error over the lit pixels, and the bias "
                "sum(method) / sum(reference) over all surface pixels of the row (a bias above 1 "
                "in rows with few lit pixels comes from the Gaussian lobe's tails lighting pixels "
                "that the reference leaves dark).\n\n"
                "| %s: footprint side (texels) | surface pixels | lit |",
            sc->name);
    for (k = 1; k < M_COUNT; ++k) fprintf(md, " %s%s |", pic_methods[k].column, k == 1 ? ": error, bias" : "");
    fprintf(md, "\n|---|---|---|");
    for (k = 1; k < M_COUNT; ++k) fprintf(md, "---|");
    fprintf(md, "\n");
    for (k = 0; k < PIC_BINS; ++k) {
        int mth;
        if (!r->bin_surface[k]) continue;
        print_bin_label(md, k);
        fprintf(md, " %d | %d |", r->bin_surface[k], r->bin_lit[k]);
        for (mth = 1; mth < M_COUNT; ++mth) /* nothing lit: no error, and the bias is 0/0 */
            if (r->bin_lit[k] == 0) fprintf(md, " - |");
            else fprintf(md, " %.0f%%, %.2f |", 100.0 * r->bin_err[k][mth], r->bin_ratio[k][mth]);
        fprintf(md, "\n");
    }
    fprintf(md, "\nBy footprint side, over the pixels lit in either reference (full or in-box: the pixels that "
                "a shadow cast from outside the footprint darkens count too), the mean relative error against "
                "the full reference, each difference divided by the larger reference (or the floor):\n\n"
                "| %s: footprint side (texels) | lit in either |", sc->name);
    for (k = 1; k < M_COUNT; ++k) fprintf(md, " %s |", pic_methods[k].column);
    fprintf(md, "\n|---|---|");
    for (k = 1; k < M_COUNT; ++k) fprintf(md, "---|");
    fprintf(md, "\n");
    for (k = 0; k < PIC_BINS; ++k) {
        int mth;
        if (!r->bin_lit_u[k]) continue;
        print_bin_label(md, k);
        fprintf(md, " %d |", r->bin_lit_u[k]);
        for (mth = 1; mth < M_COUNT; ++mth) fprintf(md, " %.0f%% |", 100.0 * r->bin_err_u[k][mth]);
        fprintf(md, "\n");
    }
    fprintf(md, "\n");
    describe_horizon(md, sc, r, m);
    /* what the error is made of */
    for (k = 0; k < PIC_BINS; ++k) {
        if (k < SMALL_BINS) lit_s += r->bin_lit_u[k];
        else lit_l += r->bin_lit_u[k];
        n_noisy += r->bin_noisy[k];
    }
    box_s = bins_mean(r, &r->bin_err_u[0][box], M_COUNT, 0, SMALL_BINS, 0);
    box_l = bins_mean(r, &r->bin_err_u[0][box], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    in_s = bins_mean(r, &r->bin_err_in[0][box], M_COUNT, 0, SMALL_BINS, 0);
    in_l = bins_mean(r, &r->bin_err_in[0][box], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    tri_s = bins_mean(r, &r->bin_err_u[0][leadr], M_COUNT, 0, SMALL_BINS, 0);
    tri_l = bins_mean(r, &r->bin_err_u[0][leadr], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    trin_s = bins_mean(r, &r->bin_err_in[0][leadr], M_COUNT, 0, SMALL_BINS, 0);
    trin_l = bins_mean(r, &r->bin_err_in[0][leadr], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    oof_s = bins_mean(r, &r->bin_err_in[0][M_REF], M_COUNT, 0, SMALL_BINS, 0);
    oof_l = bins_mean(r, &r->bin_err_in[0][M_REF], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    ndf_s = bins_mean(r, r->bin_ndf, 1, 0, SMALL_BINS, 0);
    ndf_l = bins_mean(r, r->bin_ndf, 1, SMALL_BINS, PIC_BINS, 0);
    noise_l = bins_mean(r, r->bin_noise, 1, 0, PIC_BINS, 1);
    if (strcmp(sc->name, "plane") != 0)
        fprintf(md, "**Where the error comes from (%s).** The same three effects as for the "
                    "plane. ",
                sc->name);
    else
        fprintf(md,
            "**Where the error comes from (%s).** Three effects, measured per pixel in the same "
            "run. (1) *Occlusion from outside the footprint.* A footprint narrower than the "
            "bumps (correlation length %.0f texels) is shadowed and masked mostly by bumps "
            "outside it: the brute force finds them by marching the whole height field; LEADR "
            "cannot, since all it knows is the footprint's own slope distribution. In LEADR's "
            "pipeline those resolved-scale shadows come from the displaced geometry itself and "
            "a shadow map (Dupuy et al. 2013, overview in sec. 1 and \"Shadowing\" in sec. 6); "
            "here the macrosurface is flat and nothing supplies them. An *in-box reference* "
            "marches the same texels with only the footprint box's own height field as "
            "occluder. (2) *Gaussian slopes.* Without any visibility, the NDF at the half "
            "vector of the shaded texels (the mean of their base lobes) differs from the "
            "Gaussian of the same texels' moments that LEADR uses (eqs. 8-10): a footprint "
            "holding few bumps has a lumpy slope histogram at the scale of the narrow base lobe "
            "(deviation %.2f against an RMS slope of %.2f), which no Gaussian follows; this "
            "falls as the footprint grows, down to the lumpiness of the %dx%d map itself. (3) "
            "The rest is masking and shadowing within the footprint (Smith's Lambda of the "
            "footprint's Gaussian, with V_o and V_i taken as uncorrelated, eq. 13) and, for the "
            "trilinear column, the mip filter's power-of-two boxes, which are not the pixel's "
            "box.\n\n",
            sc->name, p.corr_texels, BASE_SIGMA, p.rms_slope, m->surf.w, m->surf.h);
    if (lit_s > 0)
        fprintf(md,
                "Footprint sides under 16 texels (%d pixels lit in either reference): the two "
                "references differ by %.0f%% (mean relative difference); LEADR with the exact box "
                "moments is off by "
                "%.0f%% against the full reference and %.0f%% against the in-box one, so "
                "occlusion from outside the footprint makes %.0f%% of its error there (trilinear "
                "LEADR: %.0f%% and %.0f%%); the texels' NDF differs from its Gaussian by "
                "%.0f%%. ",
                lit_s, 100.0 * oof_s, 100.0 * box_s, 100.0 * in_s,
                box_s > 0.0 ? 100.0 * (box_s - in_s) / box_s : 0.0, 100.0 * tri_s, 100.0 * trin_s,
                100.0 * ndf_s);
    if (lit_l > 0)
        fprintf(md,
                "Sides of 16 texels and more (%d pixels lit in either): the references differ by "
                "%.0f%%; "
                "exact-box LEADR is off by %.0f%% (full) and %.0f%% (in-box), trilinear LEADR by "
                "%.0f%% and %.0f%%; NDF against its Gaussian: %.0f%%. ",
                lit_l, 100.0 * oof_l, 100.0 * box_l, 100.0 * in_l, 100.0 * tri_l,
                100.0 * trin_l, 100.0 * ndf_l);
    if (strcmp(sc->name, "plane") == 0)
        fprintf(md,
                "At large footprints the in-box reference stops being a target: near the "
                "horizon a ray 5 degrees above the plane crosses up to %.0f texels before it "
                "clears the highest bump (height range %.1f texels), so a box of any size cuts "
                "real masking by the surrounding surface, which is statistically the footprint's "
                "own and which Smith's Lambda does model; there the full reference is the one to "
                "match. ",
                (m->surf.hmax - m->surf.hmin) / m->surf.texel / tan(5.0 * pic_pi / 180.0),
                (m->surf.hmax - m->surf.hmin) / m->surf.texel);
    if (strcmp(sc->name, "plane") != 0 && lit_l > 0) {
        double lo = 1e30, hi = -1e30;
        int first = -1, last = -1;
        for (k = 0; k < PIC_BINS; ++k) {
            if (!r->bin_lit[k]) continue;
            if (r->bin_ratio[k][box] < lo) lo = r->bin_ratio[k][box];
            if (r->bin_ratio[k][box] > hi) hi = r->bin_ratio[k][box];
            if (first < 0) first = k;
            last = k;
        }
        fprintf(md,
                "So in its domain LEADR is much closer on average than pixel by pixel: per row, "
                "the exact-box LEADR's sum over the pixels is %.2f to %.2f times the "
                "reference's, while single pixels are off by about as much as the footprint's "
                "slope histogram is off its Gaussian. That part, (2), shrinks as a footprint "
                "covers more bumps (NDF error %.0f%% in the first row, %.0f%% in the last); in "
                "the last row, at the limb where the view is grazing, the exact-box error is "
                "still %.0f%%: there (3) dominates. ",
                lo, hi, pct(r->bin_ndf[first]), pct(r->bin_ndf[last]),
                pct(r->bin_err[last][box]));
    }
    fprintf(md,
            "The reference's own sampling deviation on subsampled footprints (half the "
            "difference of two interleaved halves of the samples, relative, rms) is %.1f%% over "
            "its %d lit subsampled pixels.\n\n",
            100.0 * noise_l, n_noisy);
    fprintf(md, "Per row, over the pixels lit in either reference; every difference is divided "
                "by the larger of the two references (or the floor), so the errors against the "
                "full and the in-box reference differ only in what they subtract. The share is 1 "
                "- (exact-box error against the in-box reference) / (against the full one), "
                "meaningful where the footprint is smaller than a ray's path out of the bumps "
                "(see above):\n\n"
                "| %s: footprint side (texels) | lit in either | full reference vs in-box: "
                "mean difference; sum(in-box) / sum(full), all pixels | LEADR exact box vs "
                "in-box | LEADR "
                "(trilinear) vs in-box | share of the exact-box error due to out-of-footprint "
                "occlusion | texels' NDF at h vs its Gaussian | reference sampling deviation "
                "(rms, subsampled lit pixels) |\n"
                "|---|---|---|---|---|---|---|---|\n",
            sc->name);
    for (k = 0; k < PIC_BINS; ++k) {
        if (!r->bin_lit_u[k]) continue;
        print_bin_label(md, k);
        fprintf(
            md, " %d | %.0f%%, %.2f | %.0f%% | %.0f%% | %.0f%% | %.0f%% |", r->bin_lit_u[k],
            pct(r->bin_err_in[k][M_REF]), r->bin_ratio[k][M_REF], pct(r->bin_err_in[k][box]),
            pct(r->bin_err_in[k][leadr]),
            r->bin_err_u[k][box] > 0.0
                ? pct((r->bin_err_u[k][box] - r->bin_err_in[k][box]) / r->bin_err_u[k][box])
                : 0.0,
            pct(r->bin_ndf[k]));
        if (r->bin_noisy[k])
            fprintf(md, " %.1f%% (%d px) |\n", 100.0 * r->bin_noise[k], r->bin_noisy[k]);
        else fprintf(md, " 0 (shaded fully) |\n");
    }
    fprintf(md, "\n");
    printf("%s: %dx%d, surface %d, lit %d, footprint %.2f..%.0f (median %.1f), subsampled %d\n",
           sc->name, sc->w, sc->h, r->n_surface, r->n_lit, r->fp_min, r->fp_max, r->fp_med,
           r->n_subsampled);
    printf("  reference %.2f s (%.1f us/pixel), in-box variant +%.2f s\n", r->seconds[M_REF],
           us_ref, r->seconds_inbox);
    printf("  in-box reference vs reference: mean %.1f%%\n", 100.0 * r->err_in[M_REF].mean);
    for (k = 1; k < M_COUNT; ++k)
        printf("  %-26s mean %6.1f%%  p95 %7.1f%%  vs in-box %6.1f%%  zero %5d  %4.0f ns/pixel  "
               "speed-up %.0f\n",
               pic_methods[k].label, 100.0 * r->err[k].mean, 100.0 * r->err[k].p95,
               100.0 * r->err_in[k].mean, r->n_zero[k], 1e9 * r->seconds[k] / r->n_surface,
               r->seconds[M_REF] / r->seconds[k]);
    for (k = 0; k < PIC_BINS; ++k)
        if (r->bin_surface[k])
            printf("  footprint >= %3d: %5d px, lit %5d: leadr %5.1f%% (%.2f) box %5.1f%% (%.2f) "
                   "naive %6.1f%% (%.2f) | in-box: ref %5.1f%% (%.2f) box %5.1f%% leadr %5.1f%% "
                   "noise %4.1f%% (%d) ndf %5.1f%%\n",
                   k ? 1 << k : 0, r->bin_surface[k], r->bin_lit[k],
                   100.0 * r->bin_err[k][leadr], r->bin_ratio[k][leadr],
                   100.0 * r->bin_err[k][box], r->bin_ratio[k][box],
                   100.0 * r->bin_err[k][naive], r->bin_ratio[k][naive],
                   100.0 * r->bin_err_in[k][M_REF], r->bin_ratio[k][M_REF],
                   100.0 * r->bin_err_in[k][box], 100.0 * r->bin_err_in[k][leadr],
                   100.0 * r->bin_noise[k], r->bin_noisy[k], 100.0 * r->bin_ndf[k]);
}

static void scene_make(int which, pic_scene *sc, const pic_maps *m, int w, int h)
{
    if (which == 0) scene_plane(sc, m, w, h);
    else scene_sphere(sc, m, w, h);
}

/* Image sizes: full and BENCH_QUICK (half), per scene. */
static const int scene_size[2][2] = {{400, 250}, {300, 300}};

/* Pipeline self-check (a check that can fail): on the same scenes with the map flattened to an
   RMS slope of FLAT_RMS_SLOPE, every texel is the same narrow lobe and nothing is masked, so the
   reference, LEADR and naive must agree to the library's rounding. Small images; returns the
   largest relative error over the lit pixels of both scenes and the methods checked to rounding
   (pic_methods[].check_bound 0) and of the in-box reference, in *worst_loose that of the others
   (the vMF methods), and in *over the number of those above their own check_bound. */
static double check_worst[M_COUNT]; /* self_check: each method's largest relative error (M_REF: the in-box reference) */
static double self_check(double *worst_loose, int *over)
{
    double worst = 0.0;
    int s, k, i;
    pic_maps m;
    pic_scene sc[2];
    pic_result r[2];
    const pic_scene *scp[2];
    pic_result *rp[2];
    if (maps_make(&m, 1) != 0) return 1e30;
    for (s = 0; s < 2; ++s) {
        scene_make(s, &sc[s], &m, scene_size[s][0] / 8, scene_size[s][1] / 8);
        result_alloc(&r[s], sc[s].w * sc[s].h);
        scp[s] = &sc[s];
        rp[s] = &r[s];
    }
    brute_force(&m, NULL, 2, scp, rp, NULL);
    *over = 0;
    for (s = 0; s < 2; ++s) {
        render_scene(&m, &sc[s], &r[s], 0, NULL);
        for (k = 0; k < M_COUNT; ++k) /* k = M_REF: the in-box reference */
            for (i = 0; i < sc[s].w * sc[s].h; ++i) {
                double ref = r[s].val[M_REF][i], e;
                if (!sc[s].px[i].hit || !(ref >= r[s].floor)) continue;
                e = fabs((k == M_REF ? r[s].inbox[i] : r[s].val[k][i]) - ref) / ref;
                if (!(e <= check_worst[k])) check_worst[k] = e;
                if (pic_methods[k].check_bound > 0.0) {
                    if (!(e <= *worst_loose)) *worst_loose = e;
                    if (!(e <= pic_methods[k].check_bound)) ++*over;
                } else if (!(e <= worst)) worst = e; /* NaN counts as the worst */
            }
        result_free(&r[s]);
        free(sc[s].px);
        free(sc[s].vis_light);
    }
    maps_free(&m);
    return worst;
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n = -1;
    if (f && fseek(f, 0, SEEK_END) == 0) n = ftell(f);
    if (f) fclose(f);
    return n;
}

int main(int argc, char **argv)
{
    const char *outdir = "bench/out", *gp = "bench/pictures.gp";
    const char *q = getenv("BENCH_QUICK");
    int quick = q && *q && strcmp(q, "0") != 0 && strcmp(q, "no") != 0 && strcmp(q, "NO") != 0;
    int div = quick ? 2 : 1, s;
    /* float library: the flat lobe's peak D ~ 1/(2 pi 0.01) and the Smith terms in float.
       Double: the map keeps slopes of ~FLAT_RMS_SLOPE, and where two methods' footprints
       differ (trilinear against box) the lobe's centre moves by that much, a relative change
       of up to |s_h - s| FLAT_RMS_SLOPE / BASE_SIGMA^2 ~ 3e-7 */
    double check_bound = sizeof(pf_real) == sizeof(float) ? 1e-4 : 1e-6, check, check_vmf = 0.0;
    int check_over = 0;
    pic_maps m;
    pic_scene scn[2];
    pic_result res[2];
    const pic_scene *scp[2];
    pic_result *resp[2];
    char path[1024];
    FILE *md;
    double t_start = pfb_now_s(), t_png = 0.0;
    long png_bytes[2] = {0, 0};
    FILE *gpf;
    const char *map_path = NULL;
    pfmap_options map_opt = pfmap_options_default();
    pfm_surface map_surf;
    char err[1024];
    memset(&map_surf, 0, sizeof map_surf);
    for (s = 1; s < argc; ++s) {
        if (!strcmp(argv[s], "--gp") && s + 1 < argc) gp = argv[++s];
        else if (!strcmp(argv[s], "--map") && s + 1 < argc) map_path = argv[++s];
        else if (!strncmp(argv[s], "--map-", 6) && s + 1 < argc) {
            const char *name = argv[s] + 6, *v = argv[s + 1];
            ++s;
            if (pfmap_parse_option(name, v, &map_opt, err, sizeof err) != 0) {
                fprintf(stderr, "pictures: %s\n", err);
                return 2;
            }
        } else if (argv[s][0] != '-') outdir = argv[s];
        else {
            fprintf(stderr, "usage: %s [OUT_DIR] [--gp bench/pictures.gp] [--map PATH [--map-kind K] "
                            "[--map-scale S | --map-rms-slope R] [--map-border periodic|clamped] "
                            "[--map-raw-size WxH]]\n", argv[0]);
            return 2;
        }
    }
    /* the user's map: loaded and checked before anything is written */
    if (map_path) {
        pfmap_info mi;
        pfmap_stats st;
        const char *base = strrchr(map_path, '/');
        if (pfmap_load(map_path, &map_opt, &map_surf, &mi, err, sizeof err) != 0) {
            fprintf(stderr, "pictures: %s\n", err);
            return 1;
        }
        pfmap_slope_stats(&map_surf, &st);
        user_map = &map_surf;
        map_rms = sqrt(0.5 * (st.rms_x * st.rms_x + st.rms_y * st.rms_y));
        map_corr = st.corr;
        snprintf(map_label, sizeof map_label, "user map (`%s`, %s%s", base ? base + 1 : map_path,
                 map_opt.kind == PFMAP_HEIGHT ? "height map" : "normal map integrated to heights",
                 map_opt.border == PFMAP_MIRROR ? ", mirrored" : "");
        {
            size_t j;
            snprintf(map_title, sizeof map_title, "map %s", base ? base + 1 : map_path);
            for (j = 0; map_title[j]; ++j)
                if (map_title[j] == '`' || map_title[j] == '"' || map_title[j] == '\\' || map_title[j] == '\'')
                    map_title[j] = '_';
        }
    }
    /* gnuplot draws the pictures: without it there is nothing to show, so stop before the
       minutes of rendering (tests/deps.sh installs it) */
    gpf = fopen(gp, "r");
    if (!gpf || system("gnuplot --version > /dev/null 2>&1") != 0) {
        fprintf(stderr, "pictures: %s; gnuplot draws the pictures (Debian: apt-get install "
                        "gnuplot-nox)\n", gpf ? "gnuplot not found" : "cannot read the script");
        if (gpf) fclose(gpf);
        return 1;
    }
    fclose(gpf);
    check = self_check(&check_vmf, &check_over);
    for (s = 0; s < M_COUNT; ++s)
        printf("pictures: method %-28s %-6s reads %s\n", pic_methods[s].label, pic_methods[s].oracle ? "oracle" : "",
               pic_methods[s].fetches);
    printf("pictures: self-check on a flat map, max relative error %.2e (bound %.0e), vMF %.2e "
           "(bound %.0e)\n", check, check_bound, check_vmf, VMF_CHECK_BOUND);
    for (s = 1; s < M_COUNT; ++s)
        if (pic_methods[s].check_bound > 0.0)
            printf("pictures: self-check: %-30s %.2e (bound %.0e)\n", pic_methods[s].label, check_worst[s],
                   pic_methods[s].check_bound);
    if (!(check <= check_bound) || check_over > 0) {
        fprintf(stderr, "pictures: FAILED self-check: flat map error %.3e > %.0e or vMF %.3e > %.0e\n",
                check, check_bound, check_vmf, VMF_CHECK_BOUND);
        return 1;
    }
    snprintf(path, sizeof path, "%s/pictures.md", outdir);
    md = fopen(path, "w");
    if (!md) {
        fprintf(stderr, "pictures: cannot write %s (does the directory exist?)\n", path);
        return 1;
    }
    fprintf(md, "## Pictures: brute force against the filtered formulas\n\n"
                "Each picture: the brute-force reference (every texel of the pixel's footprint "
                "shaded with its own micro-normal, a narrow Beckmann base lobe, and masking and "
                "shadowing marched through the height field: `tests/reference/pf_microsurface.h`), LEADR "
                "from the trilinearly sampled moment pyramid (`pf_slope_moments_sample`, "
                "`pf_leadr_specular`), the vMF lobes of `pf_vmf.h` alone and with the horizon visibility of "
                "`pf_horizon.h` (`pf_horizon_vmf_specular_lod`), and the naive mip-mapped normal (average normals, "
                "renormalized, base lobe only), with their relative-error maps. "
                "\"LEADR, exact box moments\" (not drawn) feeds the same formula with the exact "
                "moments of the reference's own box: its error is the model's, which the last "
                "table of each scene splits into occlusion from outside the footprint, the "
                "Gaussian-slope assumption and the rest; the difference to the trilinear error is "
                "the mip filter's footprint. Relative error per pixel: "
                "|method - reference| / max(reference, %.0f%% of the reference's 99th "
                "percentile), averaged over the lit pixels (reference above that floor). The "
                "footprint is isotropic (the larger of the two ray-differential axes, as a GPU "
                "picks its mip level) and capped at the map size.\n\n",
            100.0 * LIT_FRACTION);
    /* the maps, built once for both scenes; the scenes' geometry; then one parallel step for the
       brute force of both and the scaling function (the sphere's rows first: the dearest) */
    if (maps_make(&m, 0) != 0) {
        fprintf(stderr, "pictures: out of memory\n");
        return 1;
    }
    for (s = 0; s < 2; ++s) {
        scene_make(s, &scn[s], &m, scene_size[s][0] / div, scene_size[s][1] / div);
        if (quick && scn[s].ref_max > REF_MAX_SAMPLES) scn[s].ref_max = REF_MAX_SAMPLES;
        result_alloc(&res[s], scn[s].w * scn[s].h);
        scp[1 - s] = &scn[s];
        resp[1 - s] = &res[s];
    }
    if (pfb_thread_count() > 1)
        brute_force(&m, &m, 2, scp, resp, "pictures: brute force (sphere, plane) and the scaling function");
    else { /* one thread: nothing to run beside; apart, each step's progress counts like items */
        maps_scale(&m, "pictures: scaling function (level-6 texels)");
        brute_force(&m, NULL, 2, scp, resp, "pictures: brute force (sphere, plane)");
    }
    if (m.sc_failed) {
        fprintf(stderr, "pictures: the scaling function failed (bench/vmf_scaling.h)\n");
        return 1;
    }
    for (s = 0; s < 2; ++s) {
        pic_scene sc = scn[s];
        pic_result *rr = &res[s];
        char png[64], label[64];
        snprintf(label, sizeof label, "pictures: filtered methods (%s)", sc.name);
        render_scene(&m, &sc, rr, 1, label);
        snprintf(png, sizeof png, "pic_%s.png", sc.name);
        snprintf(path, sizeof path, "%s/%s", outdir, png);
        {
            double t0 = pfb_now_s();
            if (write_picture(&sc, rr, outdir, png, gp) != 0) {
                fprintf(stderr, "pictures: cannot write %s\n", path);
                return 1;
            }
            t_png += pfb_now_s() - t0;
            png_bytes[s] = file_size(path);
            printf("  %s: %ld bytes, drawn by gnuplot in %.0f ms\n", path, png_bytes[s],
                   1e3 * (pfb_now_s() - t0));
        }
        if (s == 0)
            fprintf(md, "Moment pyramids (five slope moments, average normals) of the %dx%d "
                        "map built in %.1f ms, vMF lobe pyramids (`pf_vmf_pyramid_from_normals`, EM "
                        "from the finest normals of each texel's footprint, at most %d iterations) "
                        "fitted in %.2f s (m = 4) and %.2f s (m = 8), the HDF-moment pyramid of the horizon "
                        "methods (`pf_horizon_pyramid`, %d azimuths, %d-texel march, periodic) in %.2f s: one-offs "
                        "per map, not counted below. The vMF methods (`pf_vmf_sum_add`, `pf_vmf_sum_specular`: Wu et al. "
                        "2019 eqs. 4-5 in the slope form, Smith G of the mixture's slope mean and "
                        "covariance; docs/vmf.md) read the lobes of the 8 texels a trilinear lookup "
                        "at the footprint's level of detail touches, each texel's amplitudes scaled "
                        "by its weight (the mixture of the 8 mixtures): 8 m lobe evaluations per "
                        "pixel. The scaled rows multiply them by the scaling function T(x) S(wi, wo) "
                        "(Wu et al. 2019 eqs. 13-14, `bench/vmf_scaling.h`: S fitted to the in-footprint "
                        "effective BRDF of 16 patches of 64 x 64 texels with a prior toward 1, T per "
                        "64 x 64 texel, built in %.1f s%s), faded in with the footprint's share of "
                        "level 6 (1 from 64-texel footprints on; 0 below 32).\n\n",
                    m.surf.w, m.surf.h, 1e3 * m.t_pyramid, VMF_ITER, m.t_vmf[0], m.t_vmf[1], HOR_N, HOR_STEPS, m.t_hor,
                    m.t_scale,
                    m.sc_ok ? "" : "; NOT BUILT for this map (smaller than 64 texels, or more than 256 level-6 "
                                   "texels): the scaled rows equal the unscaled ones");
        describe_scene(md, &sc, rr, png, &m);
        result_free(rr);
        free(sc.px);
        free(sc.vis_light);
    }
    maps_free(&m);
    fprintf(md, "Self-checks in the same run: with the map flattened (RMS slope %.0e) the three "
                "methods and the in-box reference match the reference to %.1e (largest relative "
                "error over lit pixels; bound %.0e), the vMF methods to %.1e (bound %.0e: the fit's "
                "sharpest lobe, kappa 1e5, has its own slope variance); the in-box reference marches with "
                "`pfm_visible_box` (tested in tests/test_microsurface.c). Library in %s; reference in double; times on one core%s. "
                "Pictures drawn by gnuplot (bench/pictures.gp) from the values: %ld and %ld "
                "bytes, %.0f ms for both; total run %.0f s.\n\n",
            FLAT_RMS_SLOPE, check, check_bound, check_vmf, VMF_CHECK_BOUND,
            sizeof(pf_real) == sizeof(float) ? "float" : "double",
            quick ? " (BENCH_QUICK: half-size images)" : "", png_bytes[0], png_bytes[1],
            1e3 * t_png, pfb_now_s() - t_start);
    fclose(md);
    pfm_surface_free(&map_surf);
    printf("pictures: done in %.1f s\n", pfb_now_s() - t_start);
    return 0;
}

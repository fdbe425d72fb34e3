/* frame.c - bench/pictures.c's two scenes rendered the way an engine renders them: a Vulkan
   graphics pipeline whose fragment shader pastes the library's headers (PF_GLSL), ray-casts the
   scene analytically, and shades each pixel from the moment pyramid stored as GPU textures
   (VkImages with their whole mip chains), the sampler choosing the level of detail from the
   quad's screen-space derivatives. CPU-side bench program, not part of the library.

   WHAT IS MEASURED, per scene (plane toward the horizon, sphere), method (LEADR, naive
   mip-mapped normal, Toksvig; vMF m = 4 and 8, f32 and isotropic only: see frame.frag; on the
   plane, f32 and isotropic, LEADR and vMF m = 4 with the horizon, pf_horizon.h), storage (R32G32B32A32_SFLOAT, R16G16B16A16_SFLOAT;
   for LEADR also pf_encode.h's scaled UNORM, R16G16B16A16_UNORM + R16_UNORM and R8G8B8A8_UNORM +
   R8_UNORM, the five moments centred on the map's mean slope, decoded in the shader) and sampler
   (trilinear, maxAnisotropy 1 and 16), over the lit pixels of bench/pictures.c's rule:
     error     |GPU - reference| / max(reference, floor), the reference being pictures.c's brute
               force for the same rays (tests/reference/pf_microsurface.h: every texel of the pixel's
               round(side)^2 box shaded with its own micro-normal, base lobe, masking and
               shadowing marched through the height field; the side is the isotropic ray-
               differential footprint) and floor = LIT_FRACTION times its 99th percentile;
               lit = reference >= floor. Mean over lit pixels (and the 95th percentile).
     vs CPU    |GPU - CPU| / max(CPU, floor): the same method in the library's C float build
               for the same pixel, from the float pyramid, at the texel coordinates and
               derivatives the GPU used (read back from a second attachment): isotropic
               trilinear (pf_mip_sample_trilinear at lod = log2 of the longer derivative, the
               Vulkan rule); for 16x, the Vulkan specification's anisotropic filter (N =
               min(ceil(rho_max / rho_min), 16) trilinear probes along the major axis at lod
               log2(rho_max / N)), which drivers approximate each their own way. So this column
               is storage + driver filtering + GPU arithmetic, and the error column adds the model
               and the footprint's shape.
     non-finite  NaN or infinite pixels of the GPU frame (whole image).
   Also the CPU float path at pictures.c's own footprint (lod from the analytic ray
   differentials, the isotropic side): what bench/pictures.c's table shows for the same frame
   size, and the SPIR-V op counts of each fragment shader after spirv-opt -O (bench/frame/run.sh
   counts them as bench/gpu/count.sh does; the "none" shader, ray cast and two fetches, is the
   baseline).

   ORACLE. Per pixel, the exact-histogram oracle of the reference's own texels (bench/pf_hist_oracle.h,
   shared with bench/microsurface.c: every texel shaded with its own lobe and every texel
   visible, times Smith's masking-shadowing of the texels' exact slope moments), and LEADR from
   those exact moments; every method's error is also given over the oracle's.

   MOTION. MOTION_FRAMES frames per scene along a slow camera path (a dolly over the plane, a turn
   of the sphere zoomed in so its footprints fit the reference's cap), smaller frames: each
   method's error, its change per frame and its flicker ratio (its change / the reference's own
   change). The motion reference integrates each pixel's footprint over its texels weighted by
   the covered area (shade_reference_cover), so it moves continuously with the camera; the
   grid-sampled reference did not (its own change was mostly sampling noise). The still frames'
   pixel reference is the same area integral (PIXEL_REF_SEED).

   CURVED SCENES. bench/specaa_scenes.h's sphere and cylinder with pf_specaa.h's forms, against
   its own reference and oracle: bench/frame/frame_curved.h (fc_bench, called at the end of main)
   says what it measures.

   SCENES. Cameras, lights, pixel rays, footprints and the box brute force are bench/pictures.c's,
   from their one home bench/pic_scenes.h. CPU WORK (references, the CPU float path, the sampler
   emulation, the lobe pyramids) runs on every core (bench/pf_parallel.h, PFB_THREADS), rows as
   items, sums taken afterwards in pixel order: the CSVs are the same for any thread count. A
   texel's shaded term and visibility are computed once per pair of directions (fr_memo): a still
   pixel's two references share them, and a motion pixel's frames (same wo and wi in each).
   The step's last stdout line gives its CPU and wall seconds by part.

   TIMES. On a CPU device (lavapipe) no time is reported: it is not GPU time. On a real GPU
   (PF_VK_DEVICE, vk_common.h) the render pass is timed with timestamp queries (median of 5).

   usage: frame SPV_DIR OUT_DIR [OPS_FILE]   (bench/frame/run.sh; BENCH_QUICK=1: small frames;
   PFF_CURVED_ONLY=1: only the curved scenes (frame_curved.h), their table on stdout;
   PFF_DEBUG_OUTLIERS=1: the 5 worst pixels of each isotropic f32 row against the CPU path at the
   driver's lod, with their quad's lods, and its difference from the CPU path by band of lod;
   PFF_MOTION_GRID=1: the motion reference compared with the grid-supersampled one on frames 0
   and 1, two more reference frames per scene, in frame.md's motion text)
   Writes OUT_DIR/frame.md (tables and notes), OUT_DIR/frame.csv, frame_motion.csv, and OUT_DIR/frame_<scene>.bin
   + .gpv for bench/frame/frame.gp (GPU LEADR frame next to the reference). Exit 0, or 1 when a
   check fails: no surface pixel, unreadable files, or the plumbing check (end of main: the CPU
   path at the driver's own lod must reproduce the GPU's LEADR frame to PLUMBING_BOUND). The
   issue's targets are reported, met or not, never turned into a failure (they are measurements). */
#include "pf_bench_base.h" /* first: _POSIX_C_SOURCE; the clock and checked allocation */
#include "pf_parallel.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pf_map.h"
#include "pf_vmf_fit.h"
#include "pf_beckmann.h"
#include "pf_toksvig.h"
#include "pf_vmf.h"
#include "pf_vmf_fit.h"
#include "pf_map.h"
#include "pf_microsurface.h"
#include "pf_encode.h"
#include "pf_horizon.h"
#include "pic_scenes.h" /* bench/pictures.c's scenes, settings and brute-force reference */
#include "pf_hist_oracle.h" /* the exact-histogram oracle, shared with bench/microsurface.c */
#include "vk_common.h"

/* ---------------------------------------------------------------- settings (the scenes': bench/pic_scenes.h) */
#define MAX_ANISO        16.0
#define PLUMBING_BOUND   1e-3   /* GPU LEADR vs the CPU path at the driver's lod, mean (main) */
#define MOTION_FRAMES    16
#define MOTION_SPT       2      /* the supersampled reference compared with the exact one: samples per texel per axis */
#define MOTION_ROWS      9      /* LEADR, naive, Toksvig, vMF 4, vMF 8 (isotropic), LEADR 16x, the two horizon methods (plane); the oracle (CPU) */
#define MR_LEADR16       5
#define MOTION_SIDE_FRACTION 0.6 /* the sphere's motion frames: median footprint side / ref_max */
#define MR_HORIZON       6
#define MR_VMF_HORIZON   7
#define MR_ORACLE        8
#define MR_PLANE_ONLY(k) ((k) == MR_HORIZON || (k) == MR_VMF_HORIZON)
#define BOX_CHECK_EVERY  61     /* ref_row: box_reference_oracle checked against shade_reference on one pixel in 61 */
#define PIXEL_REF_SEED   7      /* the still frames' pixel reference: texel hash seed of shade_reference_cover */
/* FILTER BANDS: the plane's LEADR error against the pixel reference per footprint band (rho_max,
   the longer derivative, in texels: < 2, 2-4, ... , >= 64) and anisotropy band (rho_max / rho_min:
   < 2, 2-4, 4-8, 8-16, >= 16), for trilinear, the driver's 16x, the specification's 16x (CPU),
   the taps in the shader, and LEADR from the exact moments of the reference's texels */
#define NBAND_RHO 7
#define NBAND_AN  5
#define NFB       6
static const char *const fb_name[NFB] = {"trilinear (GPU)", "16x, the driver's sampler (GPU)", "16x, the specification's filter (CPU)",
                                         "taps in the shader (GPU)", "exact moments of the reference's texels (CPU)",
                                         "LEADR, horizon: trilinear (GPU)"};
static double fb_sum[NFB][NBAND_RHO][NBAND_AN];
static int fb_n[NBAND_RHO][NBAND_AN];
static void band_of(const pic_sample *p, int *br, int *ba)
{
    double rx = sqrt(p->off[0] * p->off[0] + p->off[1] * p->off[1]), ry = sqrt(p->off[2] * p->off[2] + p->off[3] * p->off[3]);
    double rmax = rx > ry ? rx : ry, rmin = rx > ry ? ry : rx, r = rmax / (rmin > 1e-9 * rmax + 1e-300 ? rmin : 1e-9 * rmax + 1e-300);
    int k;
    for (k = 0; k < NBAND_RHO - 1 && rmax >= (double)(2 << k); ++k) {}
    *br = k;
    for (k = 0; k < NBAND_AN - 1 && r >= (double)(2 << k); ++k) {}
    *ba = k;
}
static void band_add(int v, const pic_sample *px, const double *val, const double *ref, const unsigned char *lit, double fl, int npx)
{
    int i, br, ba;
    for (i = 0; i < npx; ++i)
        if (lit[i]) {
            band_of(&px[i], &br, &ba);
            fb_sum[v][br][ba] += fabs(val[i] - ref[i]) / (ref[i] > fl ? ref[i] : fl);
            if (v == 0) fb_n[br][ba]++;
        }
}
#define PLANE_DOLLY_STEP 0.25   /* texels the plane's camera moves forward per frame */
#define SPHERE_TURN_STEP 0.0017453292519943296 /* 0.1 degree per frame: ~9 texels at the equator */

enum { MT_NONE = 0, MT_LEADR, MT_NAIVE, MT_TOKSVIG, MT_LEADR_TAPS, MT_VMF4, MT_VMF8, MT_HORIZON, MT_VMF4_HORIZON, MT_COUNT };
#define IS_VMF(m) ((m) == MT_VMF4 || (m) == MT_VMF8 || (m) == MT_VMF4_HORIZON)
#define VMF_WHICH(m) ((m) == MT_VMF8 ? 1 : 0) /* vmf_lobes[] index */
#define IS_HOR(m) ((m) == MT_HORIZON || (m) == MT_VMF4_HORIZON) /* the plane only, f32, isotropic */
/* the horizon method (plane only, f32, isotropic): pf_horizon_leadr_specular_lod from the HDF
   pyramid of HOR_AZ azimuths (PF_HORIZON_MOMENTS, a HOR_STEPS-texel march, periodic), faded to
   LEADR between levels HOR_LOD_FULL and HOR_LOD_SMITH (bench/microsurface.c's choice) */
#define HOR_AZ        16
#define HOR_STEPS     64
#define HOR_LOD_FULL  2.0
#define HOR_LOD_SMITH 6.0
static const char *const method_name[MT_COUNT] = {"none", "LEADR", "naive mip-mapped normal", "Toksvig",
                                                  "LEADR, taps in the shader", "vMF m = 4", "vMF m = 8", "LEADR, horizon (HDF, faded by lod)", "vMF m = 4, horizon (HDF, faded by lod)"};
static const char *const method_key[MT_COUNT] = {"none", "leadr", "naive", "toksvig", "leadr_taps", "vmf4", "vmf8", "leadr_horizon", "vmf4_horizon"};
static const int vmf_lobes[2] = {4, 8};
static const char *const scene_key[2] = {"plane", "sphere"};

static double now_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}



/* CPU seconds of the whole process (every thread, lavapipe's too) by part of main, for the step's
   last line: what the step costs on a busy machine, where wall seconds depend on the neighbours */
static double proc_cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
#define NPART 8
static const char *const part_name[NPART] = {"maps and textures", "still references", "still GPU frames and CPU path",
                                             "motion references", "motion checks of the reference", "motion GPU frames",
                                             "curved scenes", "tables"};
static double part_cpu[NPART], part_wall[NPART], part_c0, part_w0;
static void part_end(int k) /* the time since the last call to part k */
{
    double c = proc_cpu_seconds(), w = now_seconds();
    part_cpu[k] += c - part_c0, part_wall[k] += w - part_w0;
    part_c0 = c, part_w0 = w;
}

typedef struct {
    int which, w, h;
    pic_camera cam;
    double light[3];
    int ref_max;
    pic_sample *px;
} fr_scene;

/* motion: the plane's camera moved forward (+y) by that many texels (a dolly); the sphere turned
   about its pole by that many radians (the texture moves under a fixed camera and light) */
static void scene_make(fr_scene *sc, int which, int w, int h, const pfm_surface *s, double motion, double zoom)
{
    int i, j;
    memset(sc, 0, sizeof *sc);
    sc->which = which;
    sc->w = w;
    sc->h = h;
    sc->px = (pic_sample *)pfb_xcalloc((size_t)w * (size_t)h, sizeof(pic_sample));
    pic_scene_view(which, w, h, motion, &sc->cam, sc->light);
    sc->cam.tan_half /= zoom; /* zoom > 1: a narrower field of view (the sphere's motion frames) */
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i)
            pic_scene_pixel(which, &sc->cam, sc->light, (double)s->w, (double)s->h, motion, i, j, &sc->px[(size_t)j * w + i]);
}

/* ---------------------------------------------------------------- the brute force over the pixel's
   footprint (pictures.c's box reference, shade_reference, is bench/pic_scenes.h's) */

/* The texels already shaded and marched for one pair of directions (wo, wi): each one's term
   (pfm_reference_shade times its projected area) and whether it is visible both ways, which
   depend on nothing else (the texel's wrapped position, wo, wi, the scene's light map). The still
   frames compute a pixel's box and pixel-footprint references together (ref_row), so a texel of
   both footprints is shaded and marched once; a motion pixel keeps its wo and wi
   in every frame (the plane's camera moves without turning, the sphere turns under a fixed
   camera and light), so its footprint's texels are shaded and marched once for all its frames
   (motion_ref_row). Open addressing on the wrapped texel index; entries carry the stamp of the
   directions they were marched for, so the table is not cleared when they change; past 3/4
   full nothing more is stored (lookups still answer). A cache: the references' values are the
   same with or without it, to the bit. */
#define MEMO_BITS 15
#define MEMO_SIZE (1 << MEMO_BITS) /* entries: two footprints of 4096 texels and their edges, or a motion pixel's 16 */
typedef struct {
    unsigned stamp;
    int key;
    unsigned char vis;
    double term; /* the texel's shaded term times its projected area */
} fr_memo_e;
typedef struct {
    fr_memo_e *e;
    unsigned stamp; /* the current directions', never 0 */
    int n;
    double wo[3], wi[3];
} fr_memo;
/* the memo for sample p: kept when p's directions are, bit for bit, those it holds, else emptied */
static void memo_use(fr_memo *m, const pic_sample *p)
{
    if (m->stamp != 0 && memcmp(m->wo, p->wo, sizeof m->wo) == 0 && memcmp(m->wi, p->wi, sizeof m->wi) == 0) return;
    m->stamp++, m->n = 0;
    memcpy(m->wo, p->wo, sizeof m->wo), memcpy(m->wi, p->wi, sizeof m->wi);
}
static fr_memo_e *memo_find(fr_memo *m, int key)
{
    unsigned h = ((unsigned)key * 0x9E3779B1u) >> (32 - MEMO_BITS);
    while (m->e[h].stamp == m->stamp && m->e[h].key != key) h = (h + 1) & (MEMO_SIZE - 1);
    return &m->e[h];
}

typedef struct {
    const pfm_surface *s;
    const unsigned char *vis_light; /* the light's visibility map (plane), or NULL */
    const pic_sample *p;
    double shx, shy; /* the half vector's slope */
    int lit, light_first; /* light_first: shade_reference's march order (pic_light_first) */
    double num, area;
    pfb_hist hist; /* the same texels without visibility, for the exact-histogram oracle */
    fr_memo *memo; /* optional: the texels already shaded and marched for these directions */
} fr_ref_acc;

/* texel (x, y) (wrapped, above the lobe cutoff, projected area at): its shaded term times at into
   *term, and whether it is visible toward wo and wi; the direction more often occluded first (an
   occluded march stops early and the other is then skipped): the light when it is the map
   vis_light or the flatter direction (shade_reference's order, pic_light_first). Both from the
   memo when the texel is there (they depend only on the texel, wo and wi). */
static int ref_shade_texel(const fr_ref_acc *r, int x, int y, double at, double *term)
{
    const pic_sample *p = r->p;
    fr_memo_e *e = NULL;
    int v;
    if (r->memo) {
        e = memo_find(r->memo, y * r->s->w + x);
        if (e->stamp == r->memo->stamp) return *term = e->term, e->vis;
    }
    *term = pfm_reference_shade(r->s, NULL, NULL, x, y, 1, p->wo, p->wi, BASE_SIGMA, F0).spec * at;
    if (r->light_first)
        v = (r->vis_light ? r->vis_light[(size_t)y * r->s->w + x] : pfm_visible(r->s, x, y, p->wi)) && pfm_visible(r->s, x, y, p->wo);
    else
        v = pfm_visible(r->s, x, y, p->wo) && pfm_visible(r->s, x, y, p->wi);
    if (e && 4 * r->memo->n < 3 * MEMO_SIZE)
        e->stamp = r->memo->stamp, e->key = y * r->s->w + x, e->vis = (unsigned char)v, e->term = *term, r->memo->n++;
    return v;
}

static void ref_begin(fr_ref_acc *r, const pfm_surface *s, const unsigned char *vis_light, const pic_sample *p)
{
    memset(r, 0, sizeof *r);
    r->s = s;
    r->vis_light = vis_light;
    r->p = p;
    r->lit = pic_half_slope(p, &r->shx, &r->shy);
    r->light_first = pic_light_first(p, vis_light);
}

/* one texel with weight wt (1, or the covered fraction): its projected area, and its shaded
   term when visible both ways (texels whose base lobe at h is below exp(-LOBE_CUTOFF) of its
   peak are not marched, as in shade_reference); the histogram (no visibility) for the oracle */
static void ref_acc_texel(fr_ref_acc *r, int x, int y, double wt)
{
    const pic_sample *p = r->p;
    double sx, sy, at, term;
    int cut, vis;
    x = pfmi_wrap(x, r->s->w);
    y = pfmi_wrap(y, r->s->h);
    pfm_slope(r->s, x, y, &sx, &sy);
    at = p->wo[2] - sx * p->wo[0] - sy * p->wo[1];
    r->area += wt * at;
    cut = !r->lit || !(at > 0.0) ||
          ((sx - r->shx) * (sx - r->shx) + (sy - r->shy) * (sy - r->shy)) / (2.0 * BASE_SIGMA * BASE_SIGMA) > LOBE_CUTOFF;
    term = 0.0;
    vis = !cut && ref_shade_texel(r, x, y, at, &term);
    pfb_hist_add(&r->hist, wt, sx, sy, term, p->wo, p->wi, BASE_SIGMA, F0);
    if (vis) r->num += wt * term;
}

/* the per-pixel outputs of a reference pass: the reference, the exact-histogram oracle of the
   same texels (bench/pf_hist_oracle.h), and LEADR from those texels' exact slope moments (the
   best any filtering of the moment pyramid can give LEADR on that footprint) */
typedef struct {
    double ref, oracle, leadr_exact;
} fr_ref_out;

static void ref_finish(const fr_ref_acc *r, fr_ref_out *o)
{
    const pic_sample *p = r->p;
    pf_vec3 wo = pf_vec3_make((pf_real)p->wo[0], (pf_real)p->wo[1], (pf_real)p->wo[2]);
    pf_vec3 wi = pf_vec3_make((pf_real)p->wi[0], (pf_real)p->wi[1], (pf_real)p->wi[2]);
    o->ref = r->area > 0.0 ? r->num / r->area : 0.0;
    o->oracle = pfb_hist_oracle(&r->hist, p->wo, p->wi);
    o->leadr_exact = r->hist.w > 0.0 ? (double)pf_leadr_specular(wo, wi, pfb_hist_stats(&r->hist, BASE_SIGMA * BASE_SIGMA), (pf_real)F0) : 0.0;
}

/* The same brute force over the pixel's own footprint: the parallelogram spanned by the texel
   offsets of its two neighbour rays, centred on the hit (the image of the pixel's box filter
   on the tangent plane), sampled on an na x nb grid, na = round(spt |off_x|) (spt samples per
   texel; at least 1, at most ref_max), nb likewise; each grid point shades the texel it falls
   in: a supersampled pixel. This is the footprint anisotropic filtering approximates;
   shade_reference's square box is the isotropic one. */
static void shade_reference_pixel(const pfm_surface *s, const unsigned char *vis_light, const pic_sample *p, int ref_max, int spt,
                                  fr_ref_out *o)
{
    fr_ref_acc r;
    double lx = sqrt(p->off[0] * p->off[0] + p->off[1] * p->off[1]), ly = sqrt(p->off[2] * p->off[2] + p->off[3] * p->off[3]);
    int na = (int)floor(spt * lx + 0.5), nb = (int)floor(spt * ly + 0.5), a, b;
    if (na < 1) na = 1;
    if (nb < 1) nb = 1;
    if (na > ref_max) na = ref_max;
    if (nb > ref_max) nb = ref_max;
    ref_begin(&r, s, vis_light, p);
    for (b = 0; b < nb; ++b)
        for (a = 0; a < na; ++a) {
            double fa = ((double)a + 0.5) / na - 0.5, fb = ((double)b + 0.5) / nb - 0.5;
            ref_acc_texel(&r, (int)floor(p->tx + fa * p->off[0] + fb * p->off[2]), (int)floor(p->ty + fa * p->off[1] + fb * p->off[3]), 1.0);
        }
    ref_finish(&r, o);
}

/* Sutherland-Hodgman: the polygon v[0..n-1] clipped to the half plane sgn * (coordinate ax - c)
   <= 0, into out; returns the new vertex count */
static int clip_half(const double (*v)[2], int n, int ax, double c, double sgn, double (*out)[2])
{
    int i, m = 0;
    for (i = 0; i < n; ++i) {
        const double *a = v[i], *b = v[(i + 1) % n];
        double da = sgn * (a[ax] - c), db = sgn * (b[ax] - c);
        if (da <= 0.0) out[m][0] = a[0], out[m][1] = a[1], ++m;
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            double t = da / (da - db);
            out[m][0] = a[0] + t * (b[0] - a[0]), out[m][1] = a[1] + t * (b[1] - a[1]), ++m;
        }
    }
    return m;
}

static double poly_area(const double (*v)[2], int n)
{
    double a = 0.0;
    int i;
    for (i = 0; i < n; ++i) a += v[i][0] * v[(i + 1) % n][1] - v[(i + 1) % n][0] * v[i][1];
    return 0.5 * fabs(a);
}

/* a texel's uniform number in [0, 1) for the seed (an integer hash: Wang's mix, then xorshift-multiply) */
static double texel_hash(int x, int y, unsigned seed)
{
    unsigned h = (unsigned)x * 0x9E3779B1u ^ ((unsigned)y * 0x85EBCA77u + seed * 0xC2B2AE3Du);
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    h ^= h >> 16;
    return (double)(h >> 8) * (1.0 / 16777216.0);
}

/* The pixel's footprint integrated over the texels: the same parallelogram, every texel it
   touches weighted by the area it covers (polygon clipping), so the value moves continuously
   with the camera (no sample snaps from texel to texel when the camera moves by a fraction of
   one): the motion's temporally stable reference. A footprint covering more than max_texels
   texels keeps each texel with probability q = max_texels / area, decided by a hash of the
   texel's map position (seed): the kept set is attached to the surface, not to the screen, and
   nested as q changes, so the estimate's sampling error moves with the surface instead of
   being drawn anew each frame (*sampled = 1 for such pixels). num and area are summed over the
   same kept texels, so q cancels in their ratio. */
static void shade_reference_cover(const pfm_surface *s, const unsigned char *vis_light, const pic_sample *p, int max_texels,
                                  unsigned seed, fr_memo *memo, fr_ref_out *o, int *sampled)
{
    fr_ref_acc r;
    double P[4][2], ymin, ymax, par = fabs(p->off[0] * p->off[3] - p->off[1] * p->off[2]), q = 1.0, ia[4];
    int k, y;
    *sampled = 0;
    ref_begin(&r, s, vis_light, p);
    r.memo = memo;
    if (!(par > 1e-9)) { /* degenerate: the texel under the hit */
        ref_acc_texel(&r, (int)floor(p->tx), (int)floor(p->ty), 1.0);
        ref_finish(&r, o);
        return;
    }
    if (par > max_texels) q = max_texels / par, *sampled = 1;
    /* (a, b) = the inverse of (u, v) = (off[0..1], off[2..3]): inside iff |a|, |b| <= 1/2 */
    ia[0] = p->off[3] / (p->off[0] * p->off[3] - p->off[1] * p->off[2]);
    ia[1] = -p->off[2] / (p->off[0] * p->off[3] - p->off[1] * p->off[2]);
    ia[2] = -p->off[1] / (p->off[0] * p->off[3] - p->off[1] * p->off[2]);
    ia[3] = p->off[0] / (p->off[0] * p->off[3] - p->off[1] * p->off[2]);
    for (k = 0; k < 4; ++k) {
        double fa = (k == 1 || k == 2) ? 0.5 : -0.5, fb = k >= 2 ? 0.5 : -0.5;
        P[k][0] = p->tx + fa * p->off[0] + fb * p->off[2];
        P[k][1] = p->ty + fa * p->off[1] + fb * p->off[3];
    }
    ymin = ymax = P[0][1];
    for (k = 1; k < 4; ++k) ymin = P[k][1] < ymin ? P[k][1] : ymin, ymax = P[k][1] > ymax ? P[k][1] : ymax;
    for (y = (int)floor(ymin); y <= (int)floor(ymax); ++y) {
        double S[8][2], T[8][2], X[8][2], xmin, xmax;
        int ns, x;
        ns = clip_half((const double(*)[2])P, 4, 1, (double)y, -1.0, T);       /* y' >= y */
        ns = clip_half((const double(*)[2])T, ns, 1, (double)y + 1.0, 1.0, S); /* y' <= y + 1 */
        if (ns < 3) continue;
        xmin = xmax = S[0][0];
        for (k = 1; k < ns; ++k) xmin = S[k][0] < xmin ? S[k][0] : xmin, xmax = S[k][0] > xmax ? S[k][0] : xmax;
        for (x = (int)floor(xmin); x <= (int)floor(xmax); ++x) {
            double a, c[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            int nx, inside = 1;
            if (q < 1.0 && !(texel_hash(pfmi_wrap(x, s->w), pfmi_wrap(y, s->h), seed) < q)) continue;
            for (k = 0; k < 4 && inside; ++k) { /* the texel wholly inside: weight 1, no clipping */
                double dx = x + c[k][0] - p->tx, dy = y + c[k][1] - p->ty;
                inside = fabs(ia[0] * dx + ia[1] * dy) <= 0.5 && fabs(ia[2] * dx + ia[3] * dy) <= 0.5;
            }
            if (inside) a = 1.0;
            else {
                nx = clip_half((const double(*)[2])S, ns, 0, (double)x, -1.0, T);
                nx = clip_half((const double(*)[2])T, nx, 0, (double)x + 1.0, 1.0, X);
                if (nx < 3 || !((a = poly_area((const double(*)[2])X, nx)) > 0.0)) continue;
            }
            ref_acc_texel(&r, x, y, a / par);
        }
    }
    ref_finish(&r, o);
}

/* pictures.c's box reference (shade_reference, full march: the ns x ns texels of the n x n box)
   and the oracle and exact-moment LEADR of the same texels (no visibility) in one pass: each
   texel's slope, projected area and shaded term computed once for both (shade_reference computes
   the term only for texels visible both ways, the oracle needs it for every texel under the
   lobe cutoff). The same texels, order, marches and sums as shade_reference, so o->ref is its
   value to the bit (ref_row checks that on a sample of pixels). */
static void box_reference_oracle(const pfm_surface *s, const unsigned char *vis_light, const pic_sample *p, int ref_max, fr_memo *memo,
                                 fr_ref_out *o)
{
    fr_ref_acc r;
    int n = footprint_side(p->fp), ns = n < ref_max ? n : ref_max, a, b;
    int x0 = footprint_start(p->tx, n), y0 = footprint_start(p->ty, n);
    double num = 0.0, area = 0.0;
    ref_begin(&r, s, vis_light, p);
    r.memo = memo;
    for (b = 0; b < ns; ++b) {
        int y = pfmi_wrap(y0 + (int)(((double)b + 0.5) * n / ns), s->h);
        for (a = 0; a < ns; ++a) {
            int x = pfmi_wrap(x0 + (int)(((double)a + 0.5) * n / ns), s->w);
            double sx, sy, at, term = 0.0;
            int cut, vis;
            pfm_slope(s, x, y, &sx, &sy);
            at = p->wo[2] - sx * p->wo[0] - sy * p->wo[1];
            area += at;
            cut = !r.lit || !(at > 0.0) ||
                  ((sx - r.shx) * (sx - r.shx) + (sy - r.shy) * (sy - r.shy)) / (2.0 * BASE_SIGMA * BASE_SIGMA) > LOBE_CUTOFF;
            vis = !cut && ref_shade_texel(&r, x, y, at, &term); /* under the lobe cutoff: neither shaded nor marched */
            pfb_hist_add(&r.hist, 1.0, sx, sy, term, p->wo, p->wi, BASE_SIGMA, F0);
            if (vis) num += term;
        }
    }
    r.area = r.hist.area;
    ref_finish(&r, o);
    o->ref = area > 0.0 ? num / area : 0.0;
}

/* ---------------------------------------------------------------- the CPU float path */
typedef struct {
    int W, H;
    pf_real *slope_pyr, *normal_pyr;
    pf_real *vmf_pyr[2]; /* lobe pyramids, m = 4 and 8: (mu.x, mu.y, kappa, amp) per lobe */
    pf_real *hdf_pyr;    /* HDF pyramid: 3 HOR_AZ channels per texel (E[T], E[T^2], E[S T] per azimuth) */
} fr_maps;

/* the method from filtered texels a = (ex, ey, exx, eyy), b = (exy, n) */
static float shade_method(int method, const float a[4], const float b[4], const double wo_d[3], const double wi_d[3])
{
    pf_vec3 wo = pf_vec3_make((float)wo_d[0], (float)wo_d[1], (float)wo_d[2]);
    pf_vec3 wi = pf_vec3_make((float)wi_d[0], (float)wi_d[1], (float)wi_d[2]);
    float base_var = (float)(BASE_SIGMA * BASE_SIGMA);
    pf_slope_stats st;
    if (method == MT_LEADR || method == MT_LEADR_TAPS)
        st = pf_slope_moments_stats(pf_slope_moments_make(a[0], a[1], a[2], a[3], b[0]), base_var);
    else if (method == MT_NAIVE)
        st = pf_slope_moments_stats(pf_slope_moments_from_normal(pf_vec3_make(b[1], b[2], b[3])), base_var);
    else {
        pf_vec3 mu = pf_vec3_make(b[1], b[2], b[3]);
        float m2 = pf_toksvig_beckmann_m(sqrtf(2.0f * base_var), pf_toksvig_variance_from_normal(mu));
        st = pf_slope_moments_stats(pf_slope_moments_from_normal(mu), 0.5f * m2 * m2);
    }
    return pf_leadr_specular(wo, wi, st, (float)F0);
}

/* the horizon methods' inputs on the CPU, as frame.frag fetches them: the slope-moment texel
   (with the base variance) and the HDF trilinear at (u, v) (fractions of the map) and lod, the
   two stored azimuths around wo and around wi mixed by pf_hdf_moments_lerp */
static void horizon_inputs(const fr_maps *m, double u, double v, double lod, pf_vec3 wo, pf_vec3 wi, pf_slope_stats *st,
                           pf_hdf_moments *mo, pf_hdf_moments *mi)
{
    pf_real sl[5], hd[3 * HOR_AZ];
    pf_horizon_azimuth ao = pf_horizon_azimuth_of(wo, HOR_AZ), ai = pf_horizon_azimuth_of(wi, HOR_AZ);
    pf_mip_sample_trilinear(m->slope_pyr, m->W, m->H, 5, (pf_real)lod, (pf_real)u, (pf_real)v, PF_BORDER_WRAP, sl);
    pf_mip_sample_trilinear(m->hdf_pyr, m->W, m->H, 3 * HOR_AZ, (pf_real)lod, (pf_real)u, (pf_real)v, PF_BORDER_WRAP, hd);
    *st = pf_slope_moments_stats(pf_slope_moments_make(sl[0], sl[1], sl[2], sl[3], sl[4]), (pf_real)(BASE_SIGMA * BASE_SIGMA));
    *mo = pf_hdf_moments_lerp(pf_hdf_moments_make(hd[3 * ao.i0], hd[3 * ao.i0 + 1], hd[3 * ao.i0 + 2]),
                              pf_hdf_moments_make(hd[3 * ao.i1], hd[3 * ao.i1 + 1], hd[3 * ao.i1 + 2]), ao.f);
    *mi = pf_hdf_moments_lerp(pf_hdf_moments_make(hd[3 * ai.i0], hd[3 * ai.i0 + 1], hd[3 * ai.i0 + 2]),
                              pf_hdf_moments_make(hd[3 * ai.i1], hd[3 * ai.i1 + 1], hd[3 * ai.i1 + 2]), ai.f);
}

/* LEADR with the horizon on the CPU at (u, v) and lod (clamped at 0, as the driver's probe):
   pf_horizon_leadr_specular_lod, faded between lod_full and lod_smith (the frame's:
   shade_horizon_cpu; bench/frame/horizon_fade.c tries others) */
static float shade_horizon_fade(const fr_maps *m, double u, double v, double lod, const double wo_d[3], const double wi_d[3],
                                double lod_full, double lod_smith)
{
    pf_vec3 wo = pf_vec3_make((float)wo_d[0], (float)wo_d[1], (float)wo_d[2]);
    pf_vec3 wi = pf_vec3_make((float)wi_d[0], (float)wi_d[1], (float)wi_d[2]);
    pf_slope_stats st;
    pf_hdf_moments mo, mi;
    float l = lod > 0.0 ? (float)lod : 0.0f;
    horizon_inputs(m, u, v, l, wo, wi, &st, &mo, &mi);
    return pf_horizon_leadr_specular_lod(wo, wi, st, (float)(BASE_SIGMA * BASE_SIGMA), mo, mi, (float)F0, l, (float)lod_full,
                                         (float)lod_smith);
}
static float shade_horizon_cpu(const fr_maps *m, double u, double v, double lod, const double wo_d[3], const double wi_d[3])
{
    return shade_horizon_fade(m, u, v, lod, wo_d, wi_d, HOR_LOD_FULL, HOR_LOD_SMITH);
}

/* trilinear fetch of both textures at (u, v) (fractions of the map) and lod */
static void fetch(const fr_maps *m, double u, double v, double lod, float a[4], float b[4])
{
    pf_real s[5], n[3];
    pf_mip_sample_trilinear(m->slope_pyr, m->W, m->H, 5, (pf_real)lod, (pf_real)u, (pf_real)v, PF_BORDER_WRAP, s);
    pf_mip_sample_trilinear(m->normal_pyr, m->W, m->H, 3, (pf_real)lod, (pf_real)u, (pf_real)v, PF_BORDER_WRAP, n);
    a[0] = s[0], a[1] = s[1], a[2] = s[2], a[3] = s[3];
    b[0] = s[4], b[1] = n[0], b[2] = n[1], b[3] = n[2];
}

/* the sampler of the Vulkan specification (Texel Anisotropic Filtering), emulated: t and the
   derivatives g = (du/dx, dv/dx, du/dy, dv/dy) in texels; max_aniso 1 = isotropic trilinear */
static void fetch_sampler(const fr_maps *m, double tx, double ty, const float g[4], double max_aniso, float a[4], float b[4])
{
    double g0 = (double)g[0], g1 = (double)g[1], g2 = (double)g[2], g3 = (double)g[3];
    double rx = sqrt(g0 * g0 + g1 * g1), ry = sqrt(g2 * g2 + g3 * g3);
    double rmax = rx > ry ? rx : ry, rmin = rx > ry ? ry : rx, N = 1.0, lod, du = 0.0, dv = 0.0;
    int i, k;
    if (max_aniso > 1.0) {
        N = rmin > 0.0 ? ceil(rmax / rmin) : max_aniso;
        if (N > max_aniso) N = max_aniso;
        if (N < 1.0) N = 1.0;
        du = rx > ry ? g0 : g2;
        dv = rx > ry ? g1 : g3;
    }
    lod = rmax > 0.0 ? log2(rmax / N) : 0.0;
    if (N <= 1.0) {
        fetch(m, tx / m->W, ty / m->H, lod, a, b);
        return;
    }
    for (k = 0; k < 4; ++k) a[k] = b[k] = 0.0f;
    for (i = 1; i <= (int)N; ++i) {
        float ta[4], tb[4];
        double f = (double)i / (N + 1.0) - 0.5;
        fetch(m, (tx + f * du) / m->W, (ty + f * dv) / m->H, lod, ta, tb);
        for (k = 0; k < 4; ++k) a[k] += ta[k] / (float)N, b[k] += tb[k] / (float)N;
    }
}

/* frame.frag's anisotropic filter in the shader (MT_LEADR_TAPS), emulated: N = min(ceil(d rho_max /
   rho_min), 16 d) trilinear taps (d = TAP_DENSITY) at the centres of N equal segments of the
   major axis, at lod log2(rho_max / N) */
#ifndef TAP_DENSITY
#  define TAP_DENSITY 1.0 /* frame.frag's PFF_TAP_DENSITY */
#endif
static void fetch_taps(const fr_maps *m, double tx, double ty, const float g[4], float a[4], float b[4])
{
    double g0 = (double)g[0], g1 = (double)g[1], g2 = (double)g[2], g3 = (double)g[3];
    double rx = sqrt(g0 * g0 + g1 * g1), ry = sqrt(g2 * g2 + g3 * g3);
    double rmax = rx > ry ? rx : ry, rmin = rx > ry ? ry : rx, N, lod, du = rx > ry ? g0 : g2, dv = rx > ry ? g1 : g3;
    int i, k;
    N = ceil(TAP_DENSITY * rmax / (rmin > 1e-6 * rmax + 1e-30 ? rmin : 1e-6 * rmax + 1e-30));
    N = N < 1.0 ? 1.0 : (N > 16.0 * TAP_DENSITY ? 16.0 * TAP_DENSITY : N);
    lod = rmax / N > 1.0 ? log2(rmax / N) : 0.0;
    for (k = 0; k < 4; ++k) a[k] = b[k] = 0.0f;
    for (i = 0; i < (int)N; ++i) {
        float ta[4], tb[4];
        double f = ((double)i + 0.5) / N - 0.5;
        fetch(m, (tx + f * du) / m->W, (ty + f * dv) / m->H, lod, ta, tb);
        for (k = 0; k < 4; ++k) a[k] += ta[k], b[k] += tb[k];
    }
    for (k = 0; k < 4; ++k) a[k] /= (float)N, b[k] /= (float)N;
}

/* vMF m = vmf_lobes[which] at (u, v) (fractions of the map) and lod: the lobes of the 8 texels
   of a trilinear fetch, amplitudes times the trilinear weights (bench/pictures.c's shade_vmf) */
static float shade_vmf_cpu(const fr_maps *m, int which, int horizon, double u, double v, double lod, const double wo_d[3], const double wi_d[3])
{
    const int nm = vmf_lobes[which], nl = pf_vmf_pyramid_level_count(m->W, m->H);
    pf_vec3 wo = pf_vec3_make((float)wo_d[0], (float)wo_d[1], (float)wo_d[2]);
    pf_vec3 wi = pf_vec3_make((float)wi_d[0], (float)wi_d[1], (float)wi_d[2]);
    pf_vmf_sum sum = pf_vmf_sum_zero();
    pic_taps tp;
    int n, t, j;
    u -= floor(u);
    v -= floor(v);
    if (!(lod > 0.0)) lod = 0.0;
    if (lod > nl - 1) lod = nl - 1; /* as the fetch clamps it: the horizon below sees the same lod */
    n = pic_trilinear_taps(m->vmf_pyr[which], m->W, m->H, 4 * nm, u, v, lod, &tp);
    for (t = 0; t < n; ++t)
        for (j = 0; j < nm; ++j) {
            const pf_real *tex = tp.tex[t];
            sum = pf_vmf_sum_add(sum, pf_vmf_lobe_make((float)tp.w[t] * tex[4 * j + 3], tex[4 * j], tex[4 * j + 1], tex[4 * j + 2]), wo,
                                 wi, (float)(BASE_SIGMA * BASE_SIGMA));
        }
    if (horizon) { /* pf_horizon_vmf_specular_lod: the slope-moment texel and the HDF at the same lod */
        pf_slope_stats st;
        pf_hdf_moments mo, mi;
        horizon_inputs(m, u, v, lod, wo, wi, &st, &mo, &mi);
        return pf_horizon_vmf_specular_lod(sum, wo, wi, st, (float)(BASE_SIGMA * BASE_SIGMA), mo, mi, (float)F0, (float)lod,
                                           (float)HOR_LOD_FULL, (float)HOR_LOD_SMITH);
    }
    return pf_vmf_sum_specular(sum, wo, wi, (float)F0);
}

/* ---------------------------------------------------------------- float -> half (RNE) */
static unsigned short f2h(float f)
{
    unsigned int x, sign, mant;
    int exp;
    memcpy(&x, &f, 4);
    sign = (x >> 16) & 0x8000u;
    exp = (int)((x >> 23) & 0xff) - 127 + 15;
    mant = x & 0x7fffffu;
    if (((x >> 23) & 0xff) == 0xff) return (unsigned short)(sign | 0x7c00u | (mant ? 0x200u : 0u));
    if (exp >= 31) return (unsigned short)(sign | 0x7c00u);
    if (exp <= 0) {
        unsigned int m, r, shift;
        if (exp < -10) return (unsigned short)sign;
        m = mant | 0x800000u;
        shift = (unsigned)(14 - exp);
        r = m >> shift;
        if ((m & ((1u << shift) - 1u)) > (1u << (shift - 1u)) || ((m & ((1u << shift) - 1u)) == (1u << (shift - 1u)) && (r & 1u))) r++;
        return (unsigned short)(sign | r);
    }
    {
        unsigned int r = ((unsigned)exp << 10) | (mant >> 13), rem = mant & 0x1fffu;
        if (rem > 0x1000u || (rem == 0x1000u && (r & 1u))) r++; /* may carry into the exponent: right */
        return (unsigned short)(sign | r);
    }
}

/* ---------------------------------------------------------------- Vulkan */
static pfvk_ctx vk;
static VkCommandPool cpool;
static VkCommandBuffer cmd;
static VkFence fence;
static VkQueryPool qpool;
static int have_ts;

static void submit_wait(void)
{
    VkSubmitInfo si;
    memset(&si, 0, sizeof si);
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    VKC(vkResetFences(vk.dev, 1, &fence));
    VKC(vkQueueSubmit(vk.queue, 1, &si, fence));
    VKC(vkWaitForFences(vk.dev, 1, &fence, VK_TRUE, UINT64_MAX));
}

static void begin_cmd(void)
{
    VkCommandBufferBeginInfo bi;
    memset(&bi, 0, sizeof bi);
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VKC(vkResetCommandBuffer(cmd, 0));
    VKC(vkBeginCommandBuffer(cmd, &bi));
}

static void barrier_image(VkImage im, uint32_t levels, uint32_t layers, VkImageLayout from, VkImageLayout to, VkAccessFlags src_a,
                          VkAccessFlags dst_a, VkPipelineStageFlags src_s, VkPipelineStageFlags dst_s)
{
    VkImageMemoryBarrier b;
    memset(&b, 0, sizeof b);
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.srcAccessMask = src_a;
    b.dstAccessMask = dst_a;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = im;
    b.subresourceRange.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
    b.subresourceRange.levelCount = levels;
    b.subresourceRange.layerCount = layers;
    vkCmdPipelineBarrier(cmd, src_s, dst_s, 0, 0, NULL, 0, NULL, 1, &b);
}

static VkImage make_image(VkFormat fmt, uint32_t w, uint32_t h, uint32_t levels, uint32_t layers, VkImageUsageFlags usage, VkDeviceMemory *mem)
{
    VkImageCreateInfo ii;
    VkImage im;
    memset(&ii, 0, sizeof ii);
    ii.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = fmt;
    ii.extent.width = w;
    ii.extent.height = h;
    ii.extent.depth = 1;
    ii.mipLevels = levels;
    ii.arrayLayers = layers;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = usage;
    ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VKC(vkCreateImage(vk.dev, &ii, NULL, &im));
    *mem = pfvk_bind_memory(&vk, VK_NULL_HANDLE, im, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    return im;
}

static VkImageView make_view(VkImage im, VkFormat fmt, uint32_t levels, uint32_t layers)
{
    VkImageViewCreateInfo vi;
    VkImageView v;
    memset(&vi, 0, sizeof vi);
    vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vi.image = im;
    vi.viewType = layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    vi.format = fmt;
    vi.subresourceRange.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
    vi.subresourceRange.levelCount = levels;
    vi.subresourceRange.layerCount = layers;
    VKC(vkCreateImageView(vk.dev, &vi, NULL, &v));
    return v;
}

/* one pyramid texture: 4 channels per texel of every level, from the CPU pyramid(s) */
typedef struct { VkImage im; VkDeviceMemory mem; VkImageView view; } fr_tex;

/* uploads level data (levels x 4 channels, float) as fmt (f32 or f16), or (raw != NULL) the
   texels already in fmt, bpp bytes each (the UNORM codes); layers > 1: each level holds its
   layers one after the other */
static fr_tex upload_texture_any(const float *texels, const void *raw, size_t raw_bpp, int W, int H, int levels, int layers, VkFormat fmt)
{
    fr_tex t;
    int half = fmt == VK_FORMAT_R16G16B16A16_SFLOAT, l;
    size_t bpp = raw ? raw_bpp : (half ? 8 : 16), total = (size_t)pf_mip_texel_count(W, H) * (size_t)layers, k;
    VkBuffer sb;
    VkDeviceMemory sm;
    void *map;
    VkBufferImageCopy reg[PF_MIP_MAX_LEVELS];
    pfvk_host_buffer(&vk, total * bpp, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, &sb, &sm, &map);
    if (raw) memcpy(map, raw, total * bpp);
    else if (half)
        for (k = 0; k < total * 4; ++k) ((unsigned short *)map)[k] = f2h(texels[k]);
    else memcpy(map, texels, total * 16);
    t.im = make_image(fmt, (uint32_t)W, (uint32_t)H, (uint32_t)levels, (uint32_t)layers, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &t.mem);
    memset(reg, 0, sizeof reg);
    for (l = 0; l < levels; ++l) {
        reg[l].bufferOffset = (VkDeviceSize)pf_mip_level_offset(W, H, l) * (VkDeviceSize)layers * bpp;
        reg[l].imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
        reg[l].imageSubresource.mipLevel = (uint32_t)l;
        reg[l].imageSubresource.layerCount = (uint32_t)layers;
        reg[l].imageExtent.width = (uint32_t)pf_mip_level_size(W, l);
        reg[l].imageExtent.height = (uint32_t)pf_mip_level_size(H, l);
        reg[l].imageExtent.depth = 1;
    }
    begin_cmd();
    barrier_image(t.im, (uint32_t)levels, (uint32_t)layers, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                  VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    vkCmdCopyBufferToImage(cmd, sb, t.im, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, (uint32_t)levels, reg);
    barrier_image(t.im, (uint32_t)levels, (uint32_t)layers, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    VKC(vkEndCommandBuffer(cmd));
    submit_wait();
    vkDestroyBuffer(vk.dev, sb, NULL);
    vkFreeMemory(vk.dev, sm, NULL);
    t.view = make_view(t.im, fmt, (uint32_t)levels, (uint32_t)layers);
    return t;
}
static fr_tex upload_texture_layers(const float *texels, int W, int H, int levels, int layers, VkFormat fmt)
{
    return upload_texture_any(texels, NULL, 0, W, H, levels, layers, fmt);
}
static fr_tex upload_texture(const float *texels, int W, int H, int levels, VkFormat fmt)
{
    return upload_texture_layers(texels, W, H, levels, 1, fmt);
}

static VkSampler make_sampler(float aniso, int levels)
{
    VkSamplerCreateInfo si;
    VkSampler s;
    memset(&si, 0, sizeof si);
    si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    si.anisotropyEnable = aniso > 1.0f ? VK_TRUE : VK_FALSE;
    si.maxAnisotropy = aniso;
    si.minLod = 0.0f;
    si.maxLod = (float)(levels - 1);
    VKC(vkCreateSampler(vk.dev, &si, NULL, &s));
    return s;
}

/* push constants: frame.frag's PC block */
typedef struct { float pos[4], right[4], up[4], fwd[4], light[4], map[4], motion[4]; } fr_push;

typedef struct {
    VkRenderPass rp;
    VkImage att[2];
    VkDeviceMemory att_mem[2];
    VkImageView att_view[2];
    VkFramebuffer fb;
    VkBuffer rb;
    VkDeviceMemory rb_mem;
    float *rb_map; /* 2 x w x h x 4 floats: o0 then o1 */
} fr_target;

static VkDescriptorSetLayout dsl;
static VkPipelineLayout playout;
/* the UNORM storages' pf_slope_encoding (frame.frag's uniform block Enc, binding 5: three vec4 in
   the struct's member order), one per map, as an engine passes a material's constants */
static VkBuffer enc_buf;
static VkDeviceMemory enc_mem;
static float *enc_map;

static fr_target make_target(int w, int h)
{
    fr_target t;
    VkAttachmentDescription ad[2];
    VkAttachmentReference ar[2];
    VkSubpassDescription sp;
    VkRenderPassCreateInfo rpi;
    VkFramebufferCreateInfo fbi;
    void *map;
    int k;
    memset(ad, 0, sizeof ad);
    for (k = 0; k < 2; ++k) {
        ad[k].format = VK_FORMAT_R32G32B32A32_SFLOAT;
        ad[k].samples = VK_SAMPLE_COUNT_1_BIT;
        ad[k].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        ad[k].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        ad[k].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        ad[k].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        ad[k].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        ad[k].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        ar[k].attachment = (uint32_t)k;
        ar[k].layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        t.att[k] = make_image(VK_FORMAT_R32G32B32A32_SFLOAT, (uint32_t)w, (uint32_t)h, 1, 1,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &t.att_mem[k]);
        t.att_view[k] = make_view(t.att[k], VK_FORMAT_R32G32B32A32_SFLOAT, 1, 1);
    }
    memset(&sp, 0, sizeof sp);
    sp.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sp.colorAttachmentCount = 2;
    sp.pColorAttachments = ar;
    memset(&rpi, 0, sizeof rpi);
    rpi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    rpi.attachmentCount = 2;
    rpi.pAttachments = ad;
    rpi.subpassCount = 1;
    rpi.pSubpasses = &sp;
    VKC(vkCreateRenderPass(vk.dev, &rpi, NULL, &t.rp));
    memset(&fbi, 0, sizeof fbi);
    fbi.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fbi.renderPass = t.rp;
    fbi.attachmentCount = 2;
    fbi.pAttachments = t.att_view;
    fbi.width = (uint32_t)w;
    fbi.height = (uint32_t)h;
    fbi.layers = 1;
    VKC(vkCreateFramebuffer(vk.dev, &fbi, NULL, &t.fb));
    pfvk_host_buffer(&vk, (VkDeviceSize)w * (VkDeviceSize)h * 32u, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &t.rb, &t.rb_mem, &map);
    t.rb_map = (float *)map;
    return t;
}

static VkPipeline make_pipeline(const fr_target *t, int w, int h, const char *vert, const char *frag)
{
    VkShaderModule vs = pfvk_shader_module(&vk, vert), fs = pfvk_shader_module(&vk, frag);
    VkPipelineShaderStageCreateInfo st[2];
    VkPipelineVertexInputStateCreateInfo vin;
    VkPipelineInputAssemblyStateCreateInfo ia;
    VkViewport vp;
    VkRect2D sc;
    VkPipelineViewportStateCreateInfo vps;
    VkPipelineRasterizationStateCreateInfo rs;
    VkPipelineMultisampleStateCreateInfo ms;
    VkPipelineColorBlendAttachmentState cba[2];
    VkPipelineColorBlendStateCreateInfo cb;
    VkGraphicsPipelineCreateInfo gpi;
    VkPipeline p;
    memset(st, 0, sizeof st);
    st[0].sType = st[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    st[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    st[0].module = vs;
    st[0].pName = "main";
    st[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    st[1].module = fs;
    st[1].pName = "main";
    memset(&vin, 0, sizeof vin);
    vin.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    memset(&ia, 0, sizeof ia);
    ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    vp.x = vp.y = 0.0f;
    vp.width = (float)w;
    vp.height = (float)h;
    vp.minDepth = 0.0f;
    vp.maxDepth = 1.0f;
    sc.offset.x = sc.offset.y = 0;
    sc.extent.width = (uint32_t)w;
    sc.extent.height = (uint32_t)h;
    memset(&vps, 0, sizeof vps);
    vps.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    vps.viewportCount = 1;
    vps.pViewports = &vp;
    vps.scissorCount = 1;
    vps.pScissors = &sc;
    memset(&rs, 0, sizeof rs);
    rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    memset(&ms, 0, sizeof ms);
    ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    memset(cba, 0, sizeof cba);
    cba[0].colorWriteMask = cba[1].colorWriteMask =
        VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    memset(&cb, 0, sizeof cb);
    cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    cb.attachmentCount = 2;
    cb.pAttachments = cba;
    memset(&gpi, 0, sizeof gpi);
    gpi.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    gpi.stageCount = 2;
    gpi.pStages = st;
    gpi.pVertexInputState = &vin;
    gpi.pInputAssemblyState = &ia;
    gpi.pViewportState = &vps;
    gpi.pRasterizationState = &rs;
    gpi.pMultisampleState = &ms;
    gpi.pColorBlendState = &cb;
    gpi.layout = playout;
    gpi.renderPass = t->rp;
    VKC(vkCreateGraphicsPipelines(vk.dev, VK_NULL_HANDLE, 1, &gpi, NULL, &p));
    vkDestroyShaderModule(vk.dev, vs, NULL);
    vkDestroyShaderModule(vk.dev, fs, NULL);
    return p;
}

/* renders one frame into t and reads it back; returns the render pass's GPU time in ms
   (timestamps; -1 when the device has none) */
static double render(const fr_target *t, VkPipeline p, VkDescriptorSet set, const fr_push *pc, int w, int h)
{
    VkRenderPassBeginInfo rbi;
    VkClearValue cv[2];
    VkBufferImageCopy reg;
    uint64_t ts[2];
    int k;
    begin_cmd();
    if (have_ts) {
        vkCmdResetQueryPool(cmd, qpool, 0, 2);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, qpool, 0);
    }
    memset(cv, 0, sizeof cv);
    memset(&rbi, 0, sizeof rbi);
    rbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rbi.renderPass = t->rp;
    rbi.framebuffer = t->fb;
    rbi.renderArea.extent.width = (uint32_t)w;
    rbi.renderArea.extent.height = (uint32_t)h;
    rbi.clearValueCount = 2;
    rbi.pClearValues = cv;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, playout, 0, 1, &set, 0, NULL);
    vkCmdPushConstants(cmd, playout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof *pc, pc);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    if (have_ts) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, qpool, 1);
    for (k = 0; k < 2; ++k) {
        memset(&reg, 0, sizeof reg);
        reg.bufferOffset = (VkDeviceSize)k * (VkDeviceSize)w * (VkDeviceSize)h * 16u;
        reg.imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
        reg.imageSubresource.layerCount = 1;
        reg.imageExtent.width = (uint32_t)w;
        reg.imageExtent.height = (uint32_t)h;
        reg.imageExtent.depth = 1;
        vkCmdCopyImageToBuffer(cmd, t->att[k], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t->rb, 1, &reg);
    }
    VKC(vkEndCommandBuffer(cmd));
    submit_wait();
    if (!have_ts) return -1.0;
    VKC(vkGetQueryPoolResults(vk.dev, qpool, 0, 2, sizeof ts, ts, sizeof ts[0], VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    return (double)(ts[1] - ts[0]) * (double)vk.props.limits.timestampPeriod * 1e-6;
}

static void vk_setup(int levels_unused)
{
    VkPhysicalDeviceFeatures en;
    VkDescriptorSetLayoutBinding bind[7];
    VkDescriptorSetLayoutCreateInfo dlci;
    VkPushConstantRange pcr;
    VkPipelineLayoutCreateInfo plci;
    VkCommandPoolCreateInfo cpci;
    VkCommandBufferAllocateInfo cbai;
    VkFenceCreateInfo fci;
    int k;
    (void)levels_unused;
    pfvk_probe(&vk, "prefilter bench/frame");
    memset(&en, 0, sizeof en);
    en.samplerAnisotropy = vk.features.samplerAnisotropy;
    pfvk_open_device(&vk, &en, VK_QUEUE_GRAPHICS_BIT);
    memset(bind, 0, sizeof bind);
    for (k = 0; k < 7; ++k) {
        bind[k].binding = (uint32_t)k;
        bind[k].descriptorType = k == 5 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        bind[k].descriptorCount = 1;
        bind[k].stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
    }
    memset(&dlci, 0, sizeof dlci);
    dlci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    dlci.bindingCount = 7;
    dlci.pBindings = bind;
    VKC(vkCreateDescriptorSetLayout(vk.dev, &dlci, NULL, &dsl));
    pcr.stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
    pcr.offset = 0;
    pcr.size = sizeof(fr_push);
    memset(&plci, 0, sizeof plci);
    plci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &dsl;
    plci.pushConstantRangeCount = 1;
    plci.pPushConstantRanges = &pcr;
    VKC(vkCreatePipelineLayout(vk.dev, &plci, NULL, &playout));
    {
        void *em;
        pfvk_host_buffer(&vk, 12 * sizeof(float), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &enc_buf, &enc_mem, &em);
        enc_map = (float *)em;
        memset(enc_map, 0, 12 * sizeof(float));
    }
    memset(&cpci, 0, sizeof cpci);
    cpci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    cpci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    cpci.queueFamilyIndex = vk.qfam;
    VKC(vkCreateCommandPool(vk.dev, &cpci, NULL, &cpool));
    memset(&cbai, 0, sizeof cbai);
    cbai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    cbai.commandPool = cpool;
    cbai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cbai.commandBufferCount = 1;
    VKC(vkAllocateCommandBuffers(vk.dev, &cbai, &cmd));
    memset(&fci, 0, sizeof fci);
    fci.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VKC(vkCreateFence(vk.dev, &fci, NULL, &fence));
    have_ts = !vk.is_cpu && vk.props.limits.timestampComputeAndGraphics;
    if (have_ts) {
        VkQueryPoolCreateInfo qi;
        memset(&qi, 0, sizeof qi);
        qi.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
        qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qi.queryCount = 2;
        VKC(vkCreateQueryPool(vk.dev, &qi, NULL, &qpool));
    }
}

/* the set of one storage and sampler: texA, texB, the lod probe, the two lobe pyramids (read by
   texelFetch: the sampler does not matter), all through sampler s */
static VkDescriptorSet make_set(VkDescriptorPool pool, const fr_tex *a, const fr_tex *b, const fr_tex *probe, const fr_tex *v4,
                                const fr_tex *v8, const fr_tex *hdf, VkSampler s)
{
    VkDescriptorSetAllocateInfo ai;
    VkDescriptorSet set;
    VkDescriptorImageInfo ii[6];
    VkDescriptorBufferInfo bi;
    VkWriteDescriptorSet wr[7];
    int k;
    memset(&ai, 0, sizeof ai);
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &dsl;
    VKC(vkAllocateDescriptorSets(vk.dev, &ai, &set));
    memset(wr, 0, sizeof wr);
    for (k = 0; k < 5; ++k) {
        const fr_tex *t = k == 0 ? a : (k == 1 ? b : (k == 2 ? probe : (k == 3 ? v4 : v8)));
        ii[k].sampler = s;
        ii[k].imageView = t->view;
        ii[k].imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        wr[k].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        wr[k].dstSet = set;
        wr[k].dstBinding = (uint32_t)k;
        wr[k].descriptorCount = 1;
        wr[k].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        wr[k].pImageInfo = &ii[k];
    }
    bi.buffer = enc_buf; /* binding 5: the encoding (read by the UNORM shaders only) */
    bi.offset = 0;
    bi.range = 12 * sizeof(float);
    wr[5].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    wr[5].dstSet = set;
    wr[5].dstBinding = 5;
    wr[5].descriptorCount = 1;
    wr[5].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    wr[5].pBufferInfo = &bi;
    ii[5].sampler = s; /* binding 6: the HDF array, read with the set's sampler */
    ii[5].imageView = hdf->view;
    ii[5].imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    wr[6].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    wr[6].dstSet = set;
    wr[6].dstBinding = 6;
    wr[6].descriptorCount = 1;
    wr[6].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    wr[6].pImageInfo = &ii[5];
    vkUpdateDescriptorSets(vk.dev, 7, wr, 0, NULL);
    return set;
}

/* ---------------------------------------------------------------- statistics */
/* 100 v with `digits` decimals and a percent sign, in one of 4 rotating static buffers */
static const char *fmt_pct(double v, int digits)
{
    static char buf[4][32];
    static int n;
    char *b = buf[n++ & 3];
    snprintf(b, sizeof buf[0], "%.*f%%", digits, 100.0 * v);
    return b;
}
static double rel(double v, double ref, double fl) { return fabs(v - ref) / (ref > fl ? ref : fl); }

/* ---------------------------------------------------------------- the CPU work on every core
   (bench/pf_parallel.h): items are image rows (or the two lobe pyramids); each writes only its
   own pixels' slots, and every sum over pixels is taken afterwards in pixel order, so the
   outputs are the same for any PFB_THREADS. */
typedef struct {
    const pfm_surface *surf;
    const unsigned char *vis_light;
    const pic_sample *px;
    int w, ref_max, spt; /* spt 0: pictures.c's box; > 0: the pixel's footprint, spt samples per texel;
                            < 0: the pixel's footprint integrated over its texels (shade_reference_cover,
                            at most ref_max^2 of them on average, hash seed -spt) */
    double *ref;          /* out: per pixel (pixels off the surface untouched) */
    double *oracle, *lex; /* out, optional: the oracle and exact-moment LEADR of the reference's texels */
    unsigned char *hit;   /* out, optional: per pixel, the pixel sees the surface */
    unsigned char *sampled; /* out, optional (spt < 0): per pixel, 1 when its texels were sampled (over the cap) */
    const unsigned char *only; /* optional: only the pixels it marks (the others' slots untouched) */
    /* spt 0, optional: the pixel-footprint reference too (shade_reference_cover, hash seed
       px_seed), computed with the box one, sharing its marches (fr_memo) */
    double *ref_px, *oracle_px, *lex_px;
    unsigned px_seed;
} fr_ref_job;

static void ref_row(void *ctx, long long row)
{
    const fr_ref_job *jb = (const fr_ref_job *)ctx;
    size_t i0 = (size_t)row * (size_t)jb->w, i;
    ref_texel *scratch = jb->spt ? NULL : (ref_texel *)pfb_xmalloc(sizeof(ref_texel) * (size_t)jb->ref_max * (size_t)jb->ref_max);
    int bad = 0;
    fr_memo memo;
    memo.e = jb->ref_px ? (fr_memo_e *)pfb_xcalloc(MEMO_SIZE, sizeof(fr_memo_e)) : NULL;
    memo.stamp = 0;
    for (i = i0; i < i0 + (size_t)jb->w; ++i) {
        const pic_sample *p = &jb->px[i];
        fr_ref_out o;
        int cap = 0;
        if (jb->hit) jb->hit[i] = (unsigned char)p->hit;
        if (!p->hit || (jb->only && !jb->only[i])) continue;
        if (jb->spt < 0) {
            shade_reference_cover(jb->surf, jb->vis_light, p, jb->ref_max * jb->ref_max, (unsigned)-jb->spt, NULL, &o, &cap);
            if (jb->sampled) jb->sampled[i] = (unsigned char)cap;
        } else if (jb->spt > 0)
            shade_reference_pixel(jb->surf, jb->vis_light, p, jb->ref_max, jb->spt, &o);
        else {
            if (memo.e) memo_use(&memo, p);
            box_reference_oracle(jb->surf, jb->vis_light, p, jb->ref_max, memo.e ? &memo : NULL, &o);
            if (jb->ref_px) {
                fr_ref_out op;
                shade_reference_cover(jb->surf, jb->vis_light, p, jb->ref_max * jb->ref_max, jb->px_seed, &memo, &op, &cap);
                jb->ref_px[i] = op.ref, jb->oracle_px[i] = op.oracle, jb->lex_px[i] = op.leadr_exact;
            }
            /* the one pass against pictures.c's shade_reference, one pixel in BOX_CHECK_EVERY */
            if (i % BOX_CHECK_EVERY == 0 && o.ref != shade_reference(jb->surf, jb->vis_light, p, jb->ref_max, 1, scratch).full) bad = 1;
        }
        jb->ref[i] = o.ref;
        if (jb->oracle) jb->oracle[i] = o.oracle;
        if (jb->lex) jb->lex[i] = o.leadr_exact;
    }
    free(scratch), free(memo.e);
    if (bad) {
        fprintf(stderr, "frame: box_reference_oracle differs from pic_scenes.h's shade_reference (row %lld)\n", row);
        exit(1);
    }
}

/* the references of one frame into ref (and hit, oracle, lex), rows in parallel */
static void references(const pfm_surface *surf, const unsigned char *vis_light, const fr_scene *sc, int ref_max, int spt,
                       double *ref, double *oracle, double *lex, unsigned char *hit, const char *label)
{
    fr_ref_job jb;
    memset(&jb, 0, sizeof jb);
    jb.surf = surf, jb.vis_light = vis_light, jb.px = sc->px, jb.w = sc->w, jb.ref_max = ref_max, jb.spt = spt;
    jb.ref = ref, jb.oracle = oracle, jb.lex = lex, jb.hit = hit;
    pfb_parallel_for(sc->h, ref_row, &jb, label);
}

/* the motion frames' references (shade_reference_cover, spt < 0): item = row, every frame of
   each pixel in turn, sharing the pixel's marches (fr_memo) */
typedef struct {
    fr_ref_job frame[MOTION_FRAMES];
    int h;
} fr_motion_job;

static void motion_ref_row(void *ctx, long long row)
{
    const fr_motion_job *mj = (const fr_motion_job *)ctx;
    const int w = mj->frame[0].w;
    size_t i;
    int f;
    fr_memo memo;
    memset(&memo, 0, sizeof memo);
    memo.e = (fr_memo_e *)pfb_xcalloc(MEMO_SIZE, sizeof(fr_memo_e));
    for (i = (size_t)row * (size_t)w; i < (size_t)(row + 1) * (size_t)w; ++i)
        for (f = 0; f < MOTION_FRAMES; ++f) {
            const fr_ref_job *jb = &mj->frame[f];
            const pic_sample *p = &jb->px[i];
            fr_ref_out o;
            int cap = 0;
            jb->hit[i] = (unsigned char)p->hit;
            if (!p->hit) continue;
            memo_use(&memo, p);
            shade_reference_cover(jb->surf, jb->vis_light, p, jb->ref_max * jb->ref_max, (unsigned)-jb->spt, &memo, &o, &cap);
            jb->sampled[i] = (unsigned char)cap;
            jb->ref[i] = o.ref;
            jb->oracle[i] = o.oracle;
        }
    free(memo.e);
}

/* the CPU float path at pictures.c's footprint (isotropic, analytic ray differentials), lit pixels */
typedef struct {
    const fr_maps *maps;
    const pic_sample *px;
    const unsigned char *lit;
    int w, method;
    double *out;
} pic_pic_job;

static void pic_path_row(void *ctx, long long row)
{
    const pic_pic_job *jb = (const pic_pic_job *)ctx;
    const fr_maps *mp = jb->maps;
    size_t i0 = (size_t)row * (size_t)jb->w, i;
    for (i = i0; i < i0 + (size_t)jb->w; ++i) {
        const pic_sample *p = &jb->px[i];
        float a[4], b[4];
        double lod = p->fp > 1.0 ? log2(p->fp) : 0.0;
        jb->out[i] = 0.0;
        if (!jb->lit[i]) continue;
        if (jb->method == MT_HORIZON) {
            jb->out[i] = (double)shade_horizon_cpu(mp, p->tx / mp->W, p->ty / mp->H, lod, p->wo, p->wi);
            continue;
        }
        if (IS_VMF(jb->method)) {
            jb->out[i] = (double)shade_vmf_cpu(mp, VMF_WHICH(jb->method), jb->method == MT_VMF4_HORIZON, p->tx / mp->W, p->ty / mp->H, lod, p->wo, p->wi);
            continue;
        }
        fetch(mp, p->tx / mp->W, p->ty / mp->H, lod, a, b);
        jb->out[i] = (double)shade_method(jb->method, a, b, p->wo, p->wi);
    }
}

/* the CPU float path at the GPU's texel coordinates and derivatives (gpu: the two read-back
   attachments), through the specification's sampler (vc) and, isotropic, at the driver's lod
   (vd; lodd: |driver's lod - log2(rho_max)| for the lit pixels of the box reference, else -1) */
typedef struct {
    const fr_maps *maps;
    const pic_sample *px;
    const unsigned char *lit0, *lit1;
    const float *gpu;
    int w, npx, method, levels, driver_lod; /* driver_lod: also vd and lodd (isotropic rows) */
    double aniso;
    double *vc, *vd, *lodd, *lodd2;
} fr_gpu_job;

static void gpu_path_row(void *ctx, long long row)
{
    const fr_gpu_job *jb = (const fr_gpu_job *)ctx;
    const fr_maps *mp = jb->maps;
    const int m = jb->method, W = mp->W, H = mp->H;
    size_t i0 = (size_t)row * (size_t)jb->w, i;
    for (i = i0; i < i0 + (size_t)jb->w; ++i) {
        const float *o0 = jb->gpu + 4 * i, *o1 = jb->gpu + 4 * ((size_t)jb->npx + i);
        const pic_sample *p = &jb->px[i];
        float a[4], b[4];
        double g0 = (double)o1[0], g1 = (double)o1[1], g2 = (double)o1[2], g3 = (double)o1[3];
        double rx = sqrt(g0 * g0 + g1 * g1), ry = sqrt(g2 * g2 + g3 * g3), rho = rx > ry ? rx : ry;
        jb->vc[i] = jb->vd[i] = 0.0;
        jb->lodd[i] = jb->lodd2[i] = -1e30;
        if (!p->hit || !(o0[3] > 0.5f) || !(jb->lit0[i] || jb->lit1[i])) continue;
        /* the CPU float path: the specification's sampler at the GPU's coordinates and
           derivatives; isotropic also at the lod the driver reports */
        if (m == MT_HORIZON) {
            double ls = rho > 0.0 ? log2(rho) : 0.0;
            jb->vc[i] = (double)shade_horizon_cpu(mp, (double)o0[1] / W, (double)o0[2] / H, ls, p->wo, p->wi);
        } else if (IS_VMF(m)) {
            double ls = rho > 0.0 ? log2(rho) : 0.0;
            jb->vc[i] = (double)shade_vmf_cpu(mp, VMF_WHICH(m), m == MT_VMF4_HORIZON, (double)o0[1] / W, (double)o0[2] / H, ls, p->wo, p->wi);
        } else {
            if (m == MT_LEADR_TAPS) fetch_taps(mp, (double)o0[1], (double)o0[2], o1, a, b);
            else fetch_sampler(mp, (double)o0[1], (double)o0[2], o1, jb->aniso, a, b);
            jb->vc[i] = (double)shade_method(m, a, b, p->wo, p->wi);
        }
        if (jb->aniso > 1.0 && jb->lit0[i] && m != MT_LEADR_TAPS) {
            /* the driver's lod under anisotropy (the probe, read with the same sampler) against
               the specification's log2(rho_max / N) (lodd) and log2(rho_min) (lodd2), signed */
            double rmin = rx > ry ? ry : rx, N = rmin > 0.0 ? ceil(rho / rmin) : jb->aniso, l1, l2;
            N = N > jb->aniso ? jb->aniso : (N < 1.0 ? 1.0 : N);
            l1 = rho / N > 1.0 ? log2(rho / N) : 0.0;
            l2 = rmin > 1.0 ? log2(rmin) : 0.0;
            if (l1 > jb->levels - 1) l1 = jb->levels - 1;
            if (l2 > jb->levels - 1) l2 = jb->levels - 1;
            jb->lodd[i] = (double)o0[3] - 1.0 - l1;
            jb->lodd2[i] = (double)o0[3] - 1.0 - l2;
        }
        if (jb->driver_lod) {
            double lod_drv = (double)o0[3] - 1.0;
            if (m == MT_HORIZON)
                jb->vd[i] = (double)shade_horizon_cpu(mp, (double)o0[1] / W, (double)o0[2] / H, lod_drv, p->wo, p->wi);
            else if (IS_VMF(m))
                jb->vd[i] = (double)shade_vmf_cpu(mp, VMF_WHICH(m), m == MT_VMF4_HORIZON, (double)o0[1] / W, (double)o0[2] / H, lod_drv, p->wo, p->wi);
            else {
                fetch(mp, (double)o0[1] / W, (double)o0[2] / H, lod_drv, a, b);
                jb->vd[i] = (double)shade_method(m, a, b, p->wo, p->wi);
            }
            if (jb->lit0[i]) {
                double ls = rho > 0.0 ? log2(rho) : 0.0;
                if (ls < 0.0) ls = 0.0;
                if (ls > jb->levels - 1) ls = jb->levels - 1;
                jb->lodd[i] = fabs(lod_drv - ls);
            }
        }
    }
}

/* the lobe pyramids, one item per lobe count (EM per texel) */
typedef struct {
    const pf_real *nrm;
    int W, H, fail;
    fr_maps *maps;
    double cpu_s[2]; /* CPU seconds of each build, its own thread's */
} fr_vmf_job;

static double thread_cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void vmf_item(void *ctx, long long k)
{
    fr_vmf_job *jb = (fr_vmf_job *)ctx;
    double t1 = thread_cpu_seconds();
    if (pf_vmf_pyramid_from_normals(jb->nrm, NULL, jb->W, jb->H, vmf_lobes[k], VMF_ITER, jb->maps->vmf_pyr[k]) != PF_OK)
        jb->fail = 1; /* only ever set to 1: a benign race */
    jb->cpu_s[k] = thread_cpu_seconds() - t1;
}

/* the map's pyramids (CPU, float: the library's builders), as bench/pictures.c: slopes, normals,
   the HDF (texel = 1 world unit, as the slopes; t_hdf: its wall seconds) and, with vmf, the
   two lobe pyramids (EM per texel, both at once; t_vmf: each one's CPU seconds). 0, or 1 when
   a builder fails. Also bench/frame/filters.c's and horizon_fade.c's. */
static int maps_build(const pfm_surface *surf, fr_maps *maps, int vmf, double t_vmf[2], double *t_hdf)
{
    const int W = surf->w, H = surf->h;
    long long nt = pf_mip_texel_count(W, H);
    pf_real *hts = (pf_real *)pfb_xmalloc(sizeof(pf_real) * (size_t)W * H), *nrm = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 3 * (size_t)W * H);
    double th;
    int k, x, y;
    memset(maps, 0, sizeof *maps);
    maps->W = W;
    maps->H = H;
    maps->slope_pyr = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 5 * (size_t)nt);
    maps->normal_pyr = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 3 * (size_t)nt);
    maps->hdf_pyr = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 3 * HOR_AZ * (size_t)nt);
    for (k = 0; k < W * H; ++k) hts[k] = (pf_real)surf->height[k];
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            double n[3];
            pfm_normal(surf, x, y, n);
            for (k = 0; k < 3; ++k) nrm[3 * (y * W + x) + k] = (pf_real)n[k];
        }
    th = now_seconds();
    if (pf_horizon_pyramid(hts, W, H, 1.0f, HOR_AZ, HOR_STEPS, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, maps->hdf_pyr) != PF_OK) return 1;
    if (t_hdf) *t_hdf = now_seconds() - th;
    if (pf_slope_pyramid_from_heights(hts, W, H, 1.0f, 1.0f, 1.0f, PF_BORDER_WRAP, maps->slope_pyr) != PF_OK ||
        pf_normal_pyramid_from_normals(nrm, W, H, maps->normal_pyr) != PF_OK)
        return 1;
    if (vmf) {
        fr_vmf_job vj;
        vj.nrm = nrm, vj.W = W, vj.H = H, vj.fail = 0, vj.maps = maps;
        for (k = 0; k < 2; ++k)
            maps->vmf_pyr[k] = (pf_real *)pfb_xmalloc(sizeof(pf_real) * 4 * (size_t)vmf_lobes[k] * (size_t)pf_vmf_pyramid_texel_count(W, H));
        pfb_parallel_for(2, vmf_item, &vj, "frame: vMF lobe pyramids");
        if (vj.fail) return 1;
        t_vmf[0] = vj.cpu_s[0], t_vmf[1] = vj.cpu_s[1];
    }
    free(hts);
    free(nrm);
    return 0;
}

/* ---------------------------------------------------------------- main */
#define NSTORE 4
#define NANISO 2
#define ST_UNORM16 2 /* pf_encode.h's scaled UNORM (LEADR only): 16 and 8 bits */
#define ST_UNORM8  3
static const char *const store_name[NSTORE] = {"f32", "f16", "unorm16", "unorm8"};
static const double aniso_of[NANISO] = {1.0, MAX_ANISO};

/* the bands of the driver's lod for the quick frame's note: [0, 1), [1, 2), ... [NBAND_LOD - 1, levels) */
#define NBAND_LOD 8
/* one table row: scene x method x storage x sampler */
typedef struct {
    double err[2], err_p95[2]; /* GPU against the references: [0] pictures.c's box, [1] the pixel's footprint */
    double cpu_err[2];         /* the CPU float path (the specification's sampler) against them */
    double vs_cpu, vs_cpu_p95; /* GPU against the CPU float path, the specification's sampler */
    double vs_drv, vs_drv_p95; /* GPU against the CPU float path at the driver's own lod (isotropic) */
    double lod_diff;           /* isotropic: mean |driver's lod - log2(rho_max)|; 16x: mean driver's lod - log2(rho_max / N) (lit pixels) */
    double lod_rmin;           /* 16x: mean driver's lod - log2(rho_min) */
    double ms;                 /* GPU time of the render pass (real GPUs only), else -1 */
    int nonfinite, n_lit, done;
    double band_vs[NBAND_LOD]; /* isotropic: vs_cpu's sum over the lit pixels in each band of the driver's lod */
    int band_n[NBAND_LOD];     /* and their count */
} fr_row;

/* mean and 95th percentile of rel(v, ref, fl) over the pixels where use[i]; scratch: npx doubles */
static void rel_stats(const double *v, const double *ref, const unsigned char *use, double fl, int npx, double *scratch,
                      double *mean, double *p95)
{
    int i, n = 0;
    double sum = 0.0;
    for (i = 0; i < npx; ++i)
        if (use[i]) sum += (scratch[n++] = rel(v[i], ref[i], fl));
    *mean = n ? sum / n : 0.0;
    *p95 = quantile(scratch, n, 0.95);
}

/* SPIR-V ops of scene s, shader key from OPS_FILE ("scene method ops branches" lines); -1 if absent */
/* the ops and branches run.sh counted for the shader of scene name `scene` and method `key` (-1: none) */
static int ops_of_name(const char *file, const char *scene, const char *key, int *branches)
{
    char sc[32], me[32];
    int o, b;
    FILE *f = file ? fopen(file, "r") : NULL;
    *branches = -1;
    if (!f) return -1;
    while (fscanf(f, "%31s %31s %d %d", sc, me, &o, &b) == 4)
        if (!strcmp(sc, scene) && !strcmp(me, key)) {
            fclose(f);
            *branches = b;
            return o;
        }
    fclose(f);
    return -1;
}
static int ops_of_key(const char *file, int s, const char *key, int *branches) { return ops_of_name(file, scene_key[s], key, branches); }
static int ops_of(const char *file, int s, int m, int *branches) { return ops_of_key(file, s, method_key[m], branches); }

#include "frame_curved.h" /* the curved scenes of bench/specaa_scenes.h on the GPU (fc_bench) */

int main(int argc, char **argv)
{
    const char *spv, *outdir, *ops_file;
    const char *q = getenv("BENCH_QUICK");
    int quick = q && *q && strcmp(q, "0") != 0 && strcmp(q, "no") != 0;
    static const int full_size[2][2] = {{400, 250}, {300, 300}}, quick_size[2][2] = {{160, 100}, {120, 120}};
    pfm_surface surf;
    fr_maps maps;
    float *texA, *texB, *texL;
    fr_tex tex[NSTORE][2], probe, vtex[2];
    pf_slope_encoding enc;
    double t_vmf[2], t_hdf = 0.0;
    fr_tex htex;
    VkSampler samp[NANISO];
    VkDescriptorPool dpool;
    VkDescriptorSet set[NSTORE][NANISO];
    int W = MAP_SIZE, H = MAP_SIZE, levels, s, m, st, an, x, y, k, l, ref_max = quick ? 32 : 64;
    long long nt;
    char path[1024], vert[1024];
    FILE *md, *csv;
    double t_start = now_seconds();
    static fr_row rows[2][MT_COUNT][NSTORE][NANISO];
    double cpu_pic_err[2][MT_COUNT], fp_med[2], t_ref[2], floor_[2][2];
    double oracle_err[2][2], oracle_p95[2][2], lex_err[2][2], lex_p95[2][2]; /* [scene][box, pixel reference] */
    int n_lit[2][2], n_surf[2], n_edge[2], n_mism[2], fmt_ok[NSTORE];
    double aniso_used[NANISO];
    /* motion frames: the sphere's at 100 x 100, not 150 x 150: its reference (2 samples per texel
       over footprints of ~100 texels, capped at 64 x 64 per pixel, 16 frames) was two thirds of
       the whole step's CPU time (95 of 144 CPU seconds measured); 100 x 100 keeps every pixel's
       reference as fine and the 16 frames, at 0.44x the pixels, so the full step fits `make
       bench`'s budget on 2 cores */
    static const int motion_full[2][2] = {{200, 125}, {100, 100}}, motion_quick[2][2] = {{64, 40}, {48, 48}};
    static const double motion_step[2] = {PLANE_DOLLY_STEP, SPHERE_TURN_STEP};
    static const int motion_method[MOTION_ROWS] = {MT_LEADR, MT_NAIVE, MT_TOKSVIG, MT_VMF4, MT_VMF8, MT_LEADR, MT_HORIZON, MT_VMF4_HORIZON, MT_NONE};
    static const char *const motion_name[MOTION_ROWS] = {"LEADR", "naive mip-mapped normal", "Toksvig", "vMF m = 4", "vMF m = 8",
                                                         "LEADR, 16x", "LEADR, horizon (plane)", "vMF m = 4, horizon (plane)",
                                                         "oracle (exact histogram + Smith, CPU)"};
    static const char *const motion_key[MOTION_ROWS] = {"leadr", "naive", "toksvig", "vmf4", "vmf8", "leadr", "leadr_horizon", "vmf4_horizon", "oracle"};
    int motion_capped[2], motion_pxf[2]; /* sampled pixel-frames, hit pixel-frames */
    double motion_zoom[2];
    double motion_ss_dev[2], motion_ss_change[2], motion_cover_change01[2], motion_seed_dev[2]; /* the supersampled reference, frames 0 and 1 */
    double motion_flicker[2][MOTION_ROWS], motion_err[2][MOTION_ROWS], motion_ref_change[2], motion_seconds[2];
    int motion_nonfinite[2][MOTION_ROWS], motion_best[2];
    double motion_own[2][MOTION_ROWS], motion_fp_med = 0.0; /* the sphere's first motion frame: median footprint side */
    const char *mg = getenv("PFF_MOTION_GRID");
    const int motion_grid = mg && *mg && strcmp(mg, "0") != 0; /* the grid-supersampled motion reference's comparison */
    if (argc < 3) {
        fprintf(stderr, "usage: frame SPV_DIR OUT_DIR [OPS_FILE]\n");
        return 2;
    }
    part_c0 = proc_cpu_seconds(), part_w0 = t_start;
    spv = argv[1];
    outdir = argv[2];
    ops_file = argc > 3 ? argv[3] : NULL;
    memset(cpu_pic_err, 0, sizeof cpu_pic_err);

    /* the map and its pyramids (CPU, float: the library's builders), as bench/pictures.c */
    if (pfm_surface_make(&surf, W, H, 1.0, pfm_params_default(PFM_GAUSSIAN)) != 0) return 1;
    nt = pf_mip_texel_count(W, H);
    levels = pf_mip_level_count(W, H);
    texA = (float *)malloc(sizeof(float) * 4 * (size_t)nt);
    texB = (float *)malloc(sizeof(float) * 4 * (size_t)nt);
    texL = (float *)malloc(sizeof(float) * 4 * (size_t)nt);
    if (!texA || !texB || !texL || maps_build(&surf, &maps, 1, t_vmf, &t_hdf) != 0) return 1;
    for (k = 0; k < nt; ++k) {
        texA[4 * k] = maps.slope_pyr[5 * k], texA[4 * k + 1] = maps.slope_pyr[5 * k + 1];
        texA[4 * k + 2] = maps.slope_pyr[5 * k + 2], texA[4 * k + 3] = maps.slope_pyr[5 * k + 3];
        texB[4 * k] = maps.slope_pyr[5 * k + 4], texB[4 * k + 1] = maps.normal_pyr[3 * k];
        texB[4 * k + 2] = maps.normal_pyr[3 * k + 1], texB[4 * k + 3] = maps.normal_pyr[3 * k + 2];
    }
    for (l = 0; l < levels; ++l) /* the lod probe: level l holds l */
        for (k = (int)pf_mip_level_offset(W, H, l); k < (int)pf_mip_level_offset(W, H, l + 1); ++k)
            texL[4 * k] = texL[4 * k + 1] = texL[4 * k + 2] = texL[4 * k + 3] = (float)l;

    /* Vulkan: device, textures, samplers, descriptor sets */
    vk_setup(levels);
    printf("frame: device %s%s\n", vk.name, vk.is_cpu ? " (a CPU device: no GPU times)" : "");
    /* the UNORM storages (pf_encode.h): one encoding for the whole pyramid (reference = the mean
       slope over every texel of every level, ranges of the centred channels), the same for 16
       and 8 bits; texA = the four first centred channels, texB = the fifth (an R texture) */
    if (pf_slope_encoding_find(maps.slope_pyr, nt, 1, &enc) != PF_OK) return 1;
    {
        const pf_real e[12] = {enc.ref_x, enc.ref_y, enc.off_x, enc.off_y, enc.off_xx, enc.off_yy,
                               enc.off_xy, enc.sc_x, enc.sc_y, enc.sc_xx, enc.sc_yy, enc.sc_xy};
        for (k = 0; k < 12; ++k) enc_map[k] = (float)e[k];
    }
    for (st = 0; st < NSTORE; ++st) {
        static const VkFormat fa[NSTORE] = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R16G16B16A16_UNORM,
                                            VK_FORMAT_R8G8B8A8_UNORM};
        static const VkFormat fb[NSTORE] = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R16_UNORM,
                                            VK_FORMAT_R8_UNORM};
        VkFormatProperties fp, fq;
        vkGetPhysicalDeviceFormatProperties(vk.phys, fa[st], &fp);
        vkGetPhysicalDeviceFormatProperties(vk.phys, fb[st], &fq);
        fmt_ok[st] = (fp.optimalTilingFeatures & fq.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
        if (!fmt_ok[st]) {
            printf("frame: %s textures cannot be filtered linearly on this device: skipped\n", store_name[st]);
            continue;
        }
        if (st < ST_UNORM16) {
            tex[st][0] = upload_texture(texA, W, H, levels, fa[st]);
            tex[st][1] = upload_texture(texB, W, H, levels, fb[st]);
        } else {
            int fmt = st == ST_UNORM16 ? PF_ENCODE_UNORM16 : PF_ENCODE_UNORM8;
            size_t b = (size_t)pf_encode_bytes(fmt);
            unsigned char *q = (unsigned char *)pfb_xmalloc(5 * b * (size_t)nt), *qa = (unsigned char *)pfb_xmalloc(4 * b * (size_t)nt);
            unsigned char *qb = (unsigned char *)pfb_xmalloc(b * (size_t)nt);
            if (pf_slope_moments_encode(maps.slope_pyr, nt, &enc, fmt, q) != PF_OK) return 1;
            for (k = 0; k < nt; ++k) {
                memcpy(qa + 4 * b * (size_t)k, q + 5 * b * (size_t)k, 4 * b);
                memcpy(qb + b * (size_t)k, q + 5 * b * (size_t)k + 4 * b, b);
            }
            tex[st][0] = upload_texture_any(NULL, qa, 4 * b, W, H, levels, 1, fa[st]);
            tex[st][1] = upload_texture_any(NULL, qb, b, W, H, levels, 1, fb[st]);
            free(q), free(qa), free(qb);
        }
    }
    /* the probe in f16: small integers are exact, and f16 filters linearly on every device */
    probe = upload_texture(texL, W, H, levels, VK_FORMAT_R16G16B16A16_SFLOAT);
    /* the lobe pyramids as 2D array images (layer j = lobe j), f32 only: kappa reaches 1e5, past
       f16's 65504 (an f16 lobe texture needs an encoding of kappa) */
    for (k = 0; k < 2; ++k) {
        int nm = vmf_lobes[k], nlv = pf_vmf_pyramid_level_count(W, H), j;
        float *lay = (float *)malloc(sizeof(float) * 4 * (size_t)nm * (size_t)nt);
        if (!lay || nlv != levels) return 1;
        for (l = 0; l < levels; ++l) {
            long long o = pf_mip_level_offset(W, H, l), n = pf_mip_level_offset(W, H, l + 1) - o, t;
            const pf_real *src = maps.vmf_pyr[k] + pf_vmf_pyramid_level_offset(W, H, l) * 4 * nm;
            for (j = 0; j < nm; ++j)
                for (t = 0; t < n; ++t)
                    memcpy(lay + 4 * (o * nm + j * n + t), src + 4 * (t * nm + j), sizeof(float) * 4);
        }
        vtex[k] = upload_texture_layers(lay, W, H, levels, nm, VK_FORMAT_R32G32B32A32_SFLOAT);
        free(lay);
    }
    { /* the HDF as a 2D array image, R32G32B32A32_SFLOAT, layer j = azimuth j holding (E[T], E[T^2],
         E[S T], 0), the whole mip chain: 16 bytes x HOR_AZ layers per texel */
        float *lay = (float *)pfb_xcalloc(4 * (size_t)HOR_AZ * (size_t)nt, sizeof(float));
        int j;
        for (l = 0; l < levels; ++l) {
            long long o = pf_mip_level_offset(W, H, l), n = pf_mip_level_offset(W, H, l + 1) - o, t;
            for (j = 0; j < HOR_AZ; ++j)
                for (t = 0; t < n; ++t) {
                    const pf_real *src = maps.hdf_pyr + (size_t)(o + t) * 3 * HOR_AZ + 3 * j;
                    float *dst = lay + 4 * (size_t)(o * HOR_AZ + j * n + t);
                    dst[0] = src[0], dst[1] = src[1], dst[2] = src[2];
                }
        }
        htex = upload_texture_layers(lay, W, H, levels, HOR_AZ, VK_FORMAT_R32G32B32A32_SFLOAT);
        free(lay);
    }
    for (an = 0; an < NANISO; ++an) {
        double dev_max = vk.features.samplerAnisotropy ? (double)vk.props.limits.maxSamplerAnisotropy : 1.0;
        aniso_used[an] = aniso_of[an] < dev_max ? aniso_of[an] : dev_max;
        samp[an] = make_sampler((float)aniso_used[an], levels);
    }
    {
        VkDescriptorPoolSize ps[2];
        VkDescriptorPoolCreateInfo dpci;
        ps[0].type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        ps[0].descriptorCount = 6 * NSTORE * NANISO;
        ps[1].type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        ps[1].descriptorCount = NSTORE * NANISO;
        memset(&dpci, 0, sizeof dpci);
        dpci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        dpci.maxSets = NSTORE * NANISO;
        dpci.poolSizeCount = 2;
        dpci.pPoolSizes = ps;
        VKC(vkCreateDescriptorPool(vk.dev, &dpci, NULL, &dpool));
        for (st = 0; st < NSTORE; ++st)
            for (an = 0; an < NANISO; ++an)
                if (fmt_ok[st]) set[st][an] = make_set(dpool, &tex[st][0], &tex[st][1], &probe, &vtex[0], &vtex[1], &htex, samp[an]);
    }
    snprintf(vert, sizeof vert, "%s/frame.vert.spv", spv);
    if (getenv("PFF_CURVED_ONLY")) /* the curved scenes alone, their table on stdout (while iterating) */
        return fc_bench(spv, outdir, ops_file, quick, stdout, &probe, &vtex[0], &vtex[1], &htex);
    part_end(0);

    for (s = 0; s < 2; ++s) {
        int w = quick ? quick_size[s][0] : full_size[s][0], h = quick ? quick_size[s][1] : full_size[s][1];
        int npx = w * h, i, r, nsurf = 0;
        fr_scene sc;
        fr_target tg;
        fr_push pc;
        double *ref[2], *orc[2], *lex[2], *scratch = (double *)malloc(sizeof(double) * (size_t)npx), t0;
        double *vg = (double *)malloc(sizeof(double) * (size_t)npx), *vc = (double *)malloc(sizeof(double) * (size_t)npx);
        double *vd = (double *)malloc(sizeof(double) * (size_t)npx), *lodd = (double *)pfb_xmalloc(sizeof(double) * (size_t)npx);
        double *lodd2 = (double *)pfb_xmalloc(sizeof(double) * (size_t)npx);
        unsigned char *lit[2], *vis_light = NULL;
        float *gpu = (float *)malloc(sizeof(float) * 8 * (size_t)npx), *leadr_f32 = (float *)calloc((size_t)npx, sizeof(float));
        for (r = 0; r < 2; ++r) {
            ref[r] = (double *)calloc((size_t)npx, sizeof(double));
            orc[r] = (double *)pfb_xcalloc((size_t)npx, sizeof(double));
            lex[r] = (double *)pfb_xcalloc((size_t)npx, sizeof(double));
            lit[r] = (unsigned char *)calloc((size_t)npx, 1);
            if (!ref[r] || !lit[r]) return 1;
        }
        if (!scratch || !vg || !vc || !vd || !gpu || !leadr_f32) return 1;
        scene_make(&sc, s, w, h, &surf, 0.0, 1.0);
        if (s == 0) { /* one light direction for every pixel: one visibility map */
            vis_light = (unsigned char *)malloc((size_t)W * H);
            pfm_visibility_map(&surf, sc.light, vis_light);
        }
        /* the brute force: pictures.c's box, and the pixel's own footprint, in one pass (a texel
           of both footprints marched once). The pixel reference: the footprint integrated over
           its texels by covered area (shade_reference_cover, hash seed PIXEL_REF_SEED), not a
           grid of one sample per texel per axis: such a grid takes whole texels, so a footprint
           0.6 texel wide got one full texel row, and filters were measured against that
           quantization (FILTER BANDS) */
        {
            fr_ref_job jb;
            char label[64];
            t0 = now_seconds();
            snprintf(label, sizeof label, "frame: %s, box and pixel-footprint references", scene_key[s]);
            memset(&jb, 0, sizeof jb);
            jb.surf = &surf, jb.vis_light = vis_light, jb.px = sc.px, jb.w = sc.w, jb.ref_max = ref_max, jb.spt = 0;
            jb.ref = ref[0], jb.oracle = orc[0], jb.lex = lex[0];
            jb.ref_px = ref[1], jb.oracle_px = orc[1], jb.lex_px = lex[1], jb.px_seed = PIXEL_REF_SEED;
            pfb_parallel_for(sc.h, ref_row, &jb, label);
            t_ref[s] = now_seconds() - t0;
        }
        for (r = 0; r < 2; ++r) {
            int nl = 0;
            for (i = 0, nsurf = 0; i < npx; ++i)
                if (sc.px[i].hit) scratch[nsurf++] = ref[r][i];
            if (nsurf == 0) {
                fprintf(stderr, "frame: %s: no surface pixel\n", scene_key[s]);
                return 1;
            }
            floor_[s][r] = LIT_FRACTION * quantile(scratch, nsurf, 0.99);
            for (i = 0; i < npx; ++i) nl += (lit[r][i] = (unsigned char)(sc.px[i].hit && ref[r][i] >= floor_[s][r]));
            n_lit[s][r] = nl;
            /* the exact-histogram oracle and LEADR from the exact moments of the same texels */
            rel_stats(orc[r], ref[r], lit[r], floor_[s][r], npx, scratch, &oracle_err[s][r], &oracle_p95[s][r]);
            rel_stats(lex[r], ref[r], lit[r], floor_[s][r], npx, scratch, &lex_err[s][r], &lex_p95[s][r]);
            printf("frame: %s, %s reference: oracle (exact histogram + Smith) %.1f%%, LEADR from the exact footprint moments %.1f%%\n",
                   scene_key[s], r ? "pixel-footprint" : "box", 100.0 * oracle_err[s][r], 100.0 * lex_err[s][r]);
        }
        n_surf[s] = nsurf;
        for (i = 0, k = 0; i < npx; ++i)
            if (sc.px[i].hit) scratch[k++] = sc.px[i].fp;
        fp_med[s] = quantile(scratch, nsurf, 0.5);
        printf("frame: %s %dx%d: %d surface pixels, lit %d (box reference) / %d (pixel-footprint reference); references %.1f s "
               "(both, wall, %d threads; at most %d x %d texels per pixel)\n",
               scene_key[s], w, h, nsurf, n_lit[s][0], n_lit[s][1], t_ref[s], pfb_thread_count(), ref_max, ref_max);
        part_end(1);
        /* the CPU float path at pictures.c's footprint (isotropic, analytic ray differentials) */
        for (m = MT_LEADR; m < MT_COUNT; ++m) {
            double p95;
            pic_pic_job pj;
            pj.maps = &maps, pj.px = sc.px, pj.lit = lit[0], pj.w = w, pj.method = m, pj.out = vc;
            pfb_parallel_for(h, pic_path_row, &pj, NULL);
            rel_stats(vc, ref[0], lit[0], floor_[s][0], npx, scratch, &cpu_pic_err[s][m], &p95);
        }
        /* the GPU frames */
        tg = make_target(w, h);
        for (k = 0; k < 3; ++k) {
            pc.pos[k] = (float)sc.cam.pos[k], pc.right[k] = (float)sc.cam.right[k];
            pc.up[k] = (float)sc.cam.up[k], pc.fwd[k] = (float)sc.cam.fwd[k], pc.light[k] = (float)sc.light[k];
        }
        pc.pos[3] = (float)sc.cam.tan_half;
        pc.right[3] = (float)w;
        pc.up[3] = (float)h;
        pc.fwd[3] = (float)(BASE_SIGMA * BASE_SIGMA);
        pc.light[3] = (float)F0;
        pc.map[0] = (float)W, pc.map[1] = (float)H, pc.map[2] = (float)SPHERE_TILES, pc.map[3] = (float)SPHERE_RADIUS;
        memset(pc.motion, 0, sizeof pc.motion);
        n_mism[s] = 0;
        for (m = MT_LEADR; m < MT_COUNT; ++m) {
            VkPipeline pipe, pipe_enc = VK_NULL_HANDLE, pp;
            snprintf(path, sizeof path, "%s/frame_%s_%s.spv", spv, scene_key[s], method_key[m]);
            pipe = make_pipeline(&tg, w, h, vert, path);
            if (m == MT_LEADR && (fmt_ok[ST_UNORM16] || fmt_ok[ST_UNORM8])) { /* LEADR decoding the UNORM moments */
                snprintf(path, sizeof path, "%s/frame_%s_leadr_unorm.spv", spv, scene_key[s]);
                pipe_enc = make_pipeline(&tg, w, h, vert, path);
            }
            for (st = 0; st < NSTORE; ++st)
                for (an = 0; an < NANISO; ++an) {
                    fr_row *rw = &rows[s][m][st][an];
                    double times[5], lod_sum = 0.0, lod_sum2 = 0.0, dummy;
                    int nl = 0;
                    if (!fmt_ok[st]) continue;
                    if (st >= ST_UNORM16 && m != MT_LEADR) continue; /* the UNORM encodings: LEADR's moments only */
                    pp = st >= ST_UNORM16 ? pipe_enc : pipe;
                    if (IS_VMF(m) && (st > 0 || an > 0)) continue; /* lobes: f32, filtered in the shader */
                    if (IS_HOR(m) && (s != 0 || st > 0 || an > 0)) continue; /* the plane, f32, isotropic */
                    if (m == MT_LEADR_TAPS && an > 0) continue;       /* its own anisotropic filter, isotropic sampler */
                    rw->done = 1;
                    times[0] = render(&tg, pp, set[st][an], &pc, w, h);
                    memcpy(gpu, tg.rb_map, sizeof(float) * 8 * (size_t)npx);
                    if (have_ts) {
                        for (k = 1; k < 5; ++k) times[k] = render(&tg, pp, set[st][an], &pc, w, h);
                        rw->ms = quantile(times, 5, 0.5);
                    } else rw->ms = -1.0;
                    for (i = 0; i < npx; ++i) {
                        const float *o0 = gpu + 4 * (size_t)i;
                        vg[i] = (double)o0[0];
                        if (!(fabs(vg[i]) <= 3.4e38)) rw->nonfinite++;
                        if (m == MT_LEADR && st == 0 && an == 0) {
                            leadr_f32[i] = o0[0];
                            if ((o0[3] > 0.5f) != (sc.px[i].hit != 0)) n_mism[s]++;
                        }
                    }
                    {
                        fr_gpu_job gj;
                        gj.maps = &maps, gj.px = sc.px, gj.lit0 = lit[0], gj.lit1 = lit[1], gj.gpu = gpu, gj.w = w, gj.npx = npx;
                        gj.method = m, gj.levels = levels, gj.aniso = aniso_used[an], gj.driver_lod = an == 0 && m != MT_LEADR_TAPS;
                        gj.vc = vc, gj.vd = vd, gj.lodd = lodd, gj.lodd2 = lodd2;
                        pfb_parallel_for(h, gpu_path_row, &gj, NULL);
                    }
                    for (i = 0; i < npx; ++i)
                        if (lodd[i] > -1e29) lod_sum += lodd[i], lod_sum2 += lodd2[i], nl++;
                    for (r = 0; r < 2; ++r) {
                        rel_stats(vg, ref[r], lit[r], floor_[s][r], npx, scratch, &rw->err[r], &rw->err_p95[r]);
                        rel_stats(vc, ref[r], lit[r], floor_[s][r], npx, scratch, &rw->cpu_err[r], &dummy);
                    }
                    if (s == 0 && st == 0 && (m == MT_LEADR || m == MT_LEADR_TAPS || m == MT_HORIZON)) { /* FILTER BANDS */
                        band_add(m == MT_HORIZON ? 5 : (m == MT_LEADR_TAPS ? 3 : an), sc.px, vg, ref[1], lit[1], floor_[s][1], npx);
                        if (m == MT_LEADR && an == 1) band_add(2, sc.px, vc, ref[1], lit[1], floor_[s][1], npx);
                        if (m == MT_LEADR && an == 0) band_add(4, sc.px, lex[1], ref[1], lit[1], floor_[s][1], npx);
                    }
                    /* against the CPU path: relative to max(CPU, the box reference's floor), its lit pixels */
                    rel_stats(vg, vc, lit[0], floor_[s][0], npx, scratch, &rw->vs_cpu, &rw->vs_cpu_p95);
                    if (an == 0 && m != MT_LEADR_TAPS) rel_stats(vg, vd, lit[0], floor_[s][0], npx, scratch, &rw->vs_drv, &rw->vs_drv_p95);
                    else rw->vs_drv = rw->vs_drv_p95 = -1.0;
                    if (getenv("PFF_DEBUG_OUTLIERS") && an == 0 && st == 0 && m != MT_LEADR_TAPS) { /* the worst pixels against the CPU at the driver's lod */
                        int q, worst[5] = {-1, -1, -1, -1, -1}, nb[5] = {0, 0, 0, 0, 0};
                        double eb[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
                        for (i = 0; i < npx; ++i) /* vs CPU by the driver's lod: below 1, 1-2, 2-3, 3-4, 4 and over */
                            if (lit[0][i]) {
                                double ld = (double)gpu[4 * (size_t)i + 3] - 1.0;
                                int b = ld < 1.0 ? 0 : (ld < 2.0 ? 1 : (ld < 3.0 ? 2 : (ld < 4.0 ? 3 : 4)));
                                eb[b] += rel(vg[i], vc[i], floor_[s][0]), nb[b]++;
                            }
                        printf("    vs CPU by the driver's lod, %s %s (lit pixels, mean):", scene_key[s], method_key[m]);
                        for (q = 0; q < 5; ++q) printf(" [%d, %d%s: %d px %.3f%%", q, q + 1, q < 4 ? ")" : "+)", nb[q], nb[q] ? 100.0 * eb[q] / nb[q] : 0.0);
                        printf("\n");
                        for (i = 0; i < npx; ++i) {
                            double e = lit[0][i] ? rel(vg[i], vd[i], floor_[s][0]) : -1.0;
                            for (q = 0; q < 5; ++q)
                                if (worst[q] < 0 || e > rel(vg[worst[q]], vd[worst[q]], floor_[s][0])) {
                                    int z;
                                    for (z = 4; z > q; --z) worst[z] = worst[z - 1];
                                    worst[q] = i;
                                    break;
                                }
                        }
                        for (q = 0; q < 5; ++q) {
                            const float *o0 = gpu + 4 * (size_t)worst[q], *o1 = gpu + 4 * ((size_t)npx + worst[q]);
                            printf("    outlier %s %s: px %d,%d gpu %.6g cpu@drv %.6g cpu@spec %.6g rel %.4f lod_drv %.6f t %.4f %.4f g %.3g %.3g %.3g %.3g wo.z %.4f\n",
                                   scene_key[s], method_key[m], worst[q] % w, worst[q] / w, vg[worst[q]], vd[worst[q]], vc[worst[q]],
                                   rel(vg[worst[q]], vd[worst[q]], floor_[s][0]), (double)o0[3] - 1.0, (double)o0[1], (double)o0[2],
                                   (double)o1[0], (double)o1[1], (double)o1[2], (double)o1[3], sc.px[worst[q]].wo[2]);
                            {
                                int qx = (worst[q] % w) & ~1, qy = (worst[q] / w) & ~1;
                                printf("      quad lods: %.4f %.4f %.4f %.4f\n", (double)gpu[4 * ((size_t)qy * w + qx) + 3] - 1.0,
                                       (double)gpu[4 * ((size_t)qy * w + qx + 1) + 3] - 1.0, (double)gpu[4 * ((size_t)(qy + 1) * w + qx) + 3] - 1.0,
                                       (double)gpu[4 * ((size_t)(qy + 1) * w + qx + 1) + 3] - 1.0);
                            }
                        }
                    }
                    if (an == 0) /* vs CPU by band of the driver's lod (lit pixels of the box reference) */
                        for (i = 0; i < npx; ++i)
                            if (lit[0][i]) {
                                double ld = (double)gpu[4 * (size_t)i + 3] - 1.0;
                                int b = ld < 1.0 ? 0 : (ld >= NBAND_LOD - 1 ? NBAND_LOD - 1 : (int)ld);
                                rw->band_vs[b] += rel(vg[i], vc[i], floor_[s][0]), rw->band_n[b]++;
                            }
                    rw->lod_diff = nl ? lod_sum / nl : -1e30;
                    rw->lod_rmin = nl && an > 0 ? lod_sum2 / nl : -1e30;
                    rw->n_lit = n_lit[s][0];
                    printf("  %-24s %s aniso %2.0f: error %5.1f%% / %5.1f%% (box / pixel ref.), CPU path %5.1f%% / %5.1f%%, "
                           "vs CPU %6.3f%% (p95 %6.3f%%), vs CPU at the driver's lod %7.4f%%, lod diff %.4f, non-finite %d\n",
                           method_name[m], store_name[st], aniso_used[an], 100.0 * rw->err[0], 100.0 * rw->err[1],
                           100.0 * rw->cpu_err[0], 100.0 * rw->cpu_err[1], 100.0 * rw->vs_cpu, 100.0 * rw->vs_cpu_p95,
                           100.0 * rw->vs_drv, rw->lod_diff, rw->nonfinite);
                    if (an > 0 && rw->lod_rmin > -1e29)
                        printf("    16x: driver's lod - log2(rho_max / N) %+.3f, - log2(rho_min) %+.3f (mean over lit pixels)\n", rw->lod_diff,
                               rw->lod_rmin);
                }
            vkDestroyPipeline(vk.dev, pipe, NULL);
            if (pipe_enc != VK_NULL_HANDLE) vkDestroyPipeline(vk.dev, pipe_enc, NULL);
        }
        /* pixels in quads at the surface's edge (the shader's ray-differential fallback) */
        n_edge[s] = 0;
        for (y = 0; y < h; y += 2)
            for (x = 0; x < w; x += 2) {
                int hits = 0, nq = 0, dx, dy;
                for (dy = 0; dy < 2 && y + dy < h; ++dy)
                    for (dx = 0; dx < 2 && x + dx < w; ++dx, ++nq) hits += sc.px[(size_t)(y + dy) * w + x + dx].hit;
                if (hits > 0 && hits < nq) n_edge[s] += hits;
            }
        /* the picture's data: the reference (box) and the GPU's LEADR (f32, isotropic), float32
           planes, bottom row first (bench/frame/frame.gp) */
        {
            FILE *f;
            snprintf(path, sizeof path, "%s/frame_%s.bin", outdir, scene_key[s]);
            f = fopen(path, "wb");
            if (!f) return 1;
            for (k = 0; k < 2; ++k)
                for (y = h - 1; y >= 0; --y)
                    for (x = 0; x < w; ++x) {
                        float v;
                        i = y * w + x;
                        v = !sc.px[i].hit ? NAN : (k ? leadr_f32[i] : (float)ref[0][i]);
                        fwrite(&v, sizeof v, 1, f);
                    }
            fclose(f);
            snprintf(path, sizeof path, "%s/frame_%s.gpv", outdir, scene_key[s]);
            f = fopen(path, "w");
            if (!f) return 1;
            fprintf(f, "datf = \"%s/frame_%s.bin\"\noutf = \"%s/frame_%s.png\"\nw = %d\nh = %d\nexpo = %.6g\n", outdir, scene_key[s],
                    outdir, scene_key[s], w, h, s == 0 ? 0.35 : 2.0);
            fprintf(f, "t0 = \"reference (CPU brute force)\"\nt1 = \"GPU: LEADR, f32 textures, trilinear\\n%s, error %.1f%%\"\n",
                    vk.props.deviceName, 100.0 * rows[s][MT_LEADR][0][0].err[0]);
            fclose(f);
        }
        vkDestroyFramebuffer(vk.dev, tg.fb, NULL);
        vkDestroyRenderPass(vk.dev, tg.rp, NULL);
        for (k = 0; k < 2; ++k) {
            vkDestroyImageView(vk.dev, tg.att_view[k], NULL);
            vkDestroyImage(vk.dev, tg.att[k], NULL);
            vkFreeMemory(vk.dev, tg.att_mem[k], NULL);
        }
        vkDestroyBuffer(vk.dev, tg.rb, NULL);
        vkFreeMemory(vk.dev, tg.rb_mem, NULL);
        for (r = 0; r < 2; ++r) free(ref[r]), free(orc[r]), free(lex[r]), free(lit[r]);
        free(scratch), free(vg), free(vc), free(vd), free(lodd), free(lodd2), free(gpu), free(leadr_f32), free(vis_light), free(sc.px);
        part_end(2);
    }

    /* ---------------------------------------------------------------- motion: MOTION_FRAMES frames per
       scene along a slow camera path (the plane: a dolly forward; the sphere: a turn about its
       pole), f32 storage, each method isotropic and LEADR also at 16x; per method the flicker
       ratio = sum over consecutive frame pairs and pixels lit in either frame of |change of the
       method| / the same sum of |change of the reference| (1: the method changes as much as the
       truth; the naive mip-mapped normal is the anchor of shimmer), and the mean error over the
       frames (box reference) */
    for (s = 0; s < 2; ++s) {
        int w = quick ? motion_quick[s][0] : motion_full[s][0], h = quick ? motion_quick[s][1] : motion_full[s][1];
        int npx = w * h, f, i, mr;
        fr_target tg;
        fr_push pc;
        fr_scene msc[MOTION_FRAMES];
        VkPipeline pipes[MT_COUNT];
        unsigned char *vis_light = NULL;
        double *mref = (double *)calloc((size_t)MOTION_FRAMES * npx, sizeof(double)), *scratch = (double *)malloc(sizeof(double) * (size_t)npx);
        double *mval = (double *)calloc((size_t)MOTION_ROWS * MOTION_FRAMES * npx, sizeof(double)), mfloor[MOTION_FRAMES];
        unsigned char *mhit = (unsigned char *)calloc((size_t)MOTION_FRAMES * npx, 1);
        unsigned char *msamp = (unsigned char *)pfb_xcalloc((size_t)MOTION_FRAMES * npx, 1);
        double t0 = now_seconds(), dref = 0.0, sref = 0.0, zoom = 1.0;
        if (!mref || !scratch || !mval || !mhit) return 1;
        tg = make_target(w, h);
        for (m = MT_LEADR; m < MT_COUNT; ++m) {
            snprintf(path, sizeof path, "%s/frame_%s_%s.spv", spv, scene_key[s], method_key[m]);
            pipes[m] = make_pipeline(&tg, w, h, vert, path);
        }
        memset(motion_nonfinite[s], 0, sizeof motion_nonfinite[s]);
        if (s == 1) { /* the sphere zoomed in until its median footprint side is MOTION_SIDE_FRACTION of
                         ref_max: most footprints are then integrated over every texel (the cap
                         is ref_max^2 texels), and the turn slowed by the same factor */
            fr_scene probe;
            int ns = 0;
            scene_make(&probe, s, w, h, &surf, 0.0, 1.0);
            for (i = 0; i < npx; ++i)
                if (probe.px[i].hit) scratch[ns++] = probe.px[i].fp;
            zoom = quantile(scratch, ns, 0.5) / (MOTION_SIDE_FRACTION * ref_max);
            if (zoom < 1.0) zoom = 1.0;
            free(probe.px);
        }
        motion_zoom[s] = zoom;
        { /* every frame's reference in one parallel step (items: frame x row) */
            fr_motion_job mj;
            char label[64];
            for (f = 0; f < MOTION_FRAMES; ++f) {
                scene_make(&msc[f], s, w, h, &surf, f * motion_step[s] / zoom, zoom);
                if (s == 0 && !vis_light) { /* the light does not move: one visibility map */
                    vis_light = (unsigned char *)pfb_xmalloc((size_t)W * H);
                    pfm_visibility_map(&surf, msc[f].light, vis_light);
                }
                memset(&mj.frame[f], 0, sizeof mj.frame[f]);
                mj.frame[f].surf = &surf, mj.frame[f].vis_light = vis_light, mj.frame[f].px = msc[f].px, mj.frame[f].w = w;
                mj.frame[f].ref_max = ref_max, mj.frame[f].spt = -1; /* the footprint integrated exactly */
                mj.frame[f].ref = mref + (size_t)f * npx, mj.frame[f].hit = mhit + (size_t)f * npx;
                mj.frame[f].oracle = mval + ((size_t)MR_ORACLE * MOTION_FRAMES + f) * npx, mj.frame[f].sampled = msamp + (size_t)f * npx;
            }
            mj.h = h;
            snprintf(label, sizeof label, "frame: motion %s, %d references", scene_key[s], MOTION_FRAMES);
            part_end(5);
            pfb_parallel_for(h, motion_ref_row, &mj, label);
            part_end(3);
        }
        for (i = 0, motion_capped[s] = motion_pxf[s] = 0; i < MOTION_FRAMES * npx; ++i) motion_capped[s] += msamp[i], motion_pxf[s] += mhit[i];
        { /* the reference's own sampling deviation: frame 0 again with another texel hash (only the
             footprints over the cap change), |difference| / sqrt 2 relative to the reference; and
             the grid-supersampled reference (MOTION_SPT^2 samples per texel, the screen-attached
             samples of the still frames' pixel reference) on frames 0 and 1: its deviation from
             this one and its change next to this one's */
            double *ss = (double *)pfb_xcalloc(3 * (size_t)npx, sizeof(double)), fl0, dss = 0.0, dcv = 0.0, lvl = 0.0, dev = 0.0;
            double dseed = 0.0;
            int ns = 0, nd = 0;
            fr_ref_job sj;
            if (motion_grid) /* opt-in: two more reference frames per scene, for a comparison that no target reads */
                for (f = 0; f < 2; ++f) references(&surf, vis_light, &msc[f], ref_max, MOTION_SPT, ss + (size_t)f * npx, NULL, NULL, NULL, NULL);
            memset(&sj, 0, sizeof sj);
            sj.surf = &surf, sj.vis_light = vis_light, sj.px = msc[0].px, sj.w = w, sj.ref_max = ref_max, sj.spt = -2;
            sj.ref = ss + 2 * (size_t)npx;
            /* only the footprints over the cap depend on the hash: the others are integrated
               exactly, the same value whatever the seed, so they are copied, not recomputed */
            memcpy(sj.ref, mref, sizeof(double) * (size_t)npx);
            sj.only = msamp;
            pfb_parallel_for(h, ref_row, &sj, NULL);
            for (i = 0; i < npx; ++i)
                if (mhit[i]) scratch[ns++] = mref[i];
            fl0 = LIT_FRACTION * quantile(scratch, ns, 0.99);
            for (i = 0; i < npx; ++i) {
                if (mhit[i] && mref[i] >= fl0) {
                    dev += rel(ss[i], mref[i], fl0), nd++;
                    dseed += rel(ss[2 * (size_t)npx + i], mref[i], fl0) / sqrt(2.0);
                }
                if (mhit[i] && mhit[npx + i] && (mref[i] >= fl0 || mref[npx + i] >= fl0)) {
                    dss += fabs(ss[npx + i] - ss[i]);
                    dcv += fabs(mref[npx + i] - mref[i]);
                    lvl += 0.5 * (mref[npx + i] + mref[i]);
                }
            }
            motion_ss_dev[s] = nd ? dev / nd : 0.0;
            motion_seed_dev[s] = nd ? dseed / nd : 0.0;
            motion_ss_change[s] = lvl > 0.0 ? dss / lvl : 0.0;
            motion_cover_change01[s] = lvl > 0.0 ? dcv / lvl : 0.0;
            free(ss);
            part_end(4);
        }
        if (s == 1) { /* the sphere's footprint, for the text: the median of its first frame */
            int ns = 0;
            for (i = 0; i < npx; ++i)
                if (msc[0].px[i].hit) scratch[ns++] = msc[0].px[i].fp;
            motion_fp_med = quantile(scratch, ns, 0.5);
        }
        for (f = 0; f < MOTION_FRAMES; ++f) {
            fr_scene sc = msc[f];
            int ns = 0;
            for (i = 0; i < npx; ++i)
                if (mhit[(size_t)f * npx + i]) scratch[ns++] = mref[(size_t)f * npx + i];
            mfloor[f] = LIT_FRACTION * quantile(scratch, ns, 0.99);
            for (k = 0; k < 3; ++k) {
                pc.pos[k] = (float)sc.cam.pos[k], pc.right[k] = (float)sc.cam.right[k];
                pc.up[k] = (float)sc.cam.up[k], pc.fwd[k] = (float)sc.cam.fwd[k], pc.light[k] = (float)sc.light[k];
            }
            pc.pos[3] = (float)sc.cam.tan_half, pc.right[3] = (float)w, pc.up[3] = (float)h;
            pc.fwd[3] = (float)(BASE_SIGMA * BASE_SIGMA), pc.light[3] = (float)F0;
            pc.map[0] = (float)W, pc.map[1] = (float)H, pc.map[2] = (float)SPHERE_TILES, pc.map[3] = (float)SPHERE_RADIUS;
            memset(pc.motion, 0, sizeof pc.motion);
            if (s == 1) pc.motion[0] = (float)(f * motion_step[s] / zoom);
            for (mr = 0; mr < MR_ORACLE; ++mr) {
                int mm = motion_method[mr], aa = mr == MR_LEADR16 ? 1 : 0;
                if (IS_HOR(mm) && s != 0) continue; /* the horizon rows: the plane only */
                render(&tg, pipes[mm], set[0][aa], &pc, w, h);
                for (i = 0; i < npx; ++i) {
                    double v = (double)tg.rb_map[4 * (size_t)i];
                    if (!(fabs(v) <= 3.4e38)) motion_nonfinite[s][mr]++;
                    mval[((size_t)mr * MOTION_FRAMES + f) * npx + i] = v;
                }
            }
            free(sc.px);
        }
        /* flicker and error */
        for (f = 0; f + 1 < MOTION_FRAMES; ++f)
            for (i = 0; i < npx; ++i) {
                size_t a0 = (size_t)f * npx + i, a1 = a0 + (size_t)npx;
                if (!mhit[a0] || !mhit[a1] || msamp[a0] || msamp[a1] || !(mref[a0] >= mfloor[f] || mref[a1] >= mfloor[f + 1])) continue;
                dref += fabs(mref[a1] - mref[a0]);
                sref += 0.5 * (mref[a1] + mref[a0]);
            }
        motion_ref_change[s] = sref > 0.0 ? dref / sref : 0.0;
        for (mr = 0; mr < MOTION_ROWS; ++mr) {
            double d = 0.0, e = 0.0;
            int ne = 0;
            if (s != 0 && MR_PLANE_ONLY(mr)) { /* the plane only */
                motion_flicker[s][mr] = motion_own[s][mr] = motion_err[s][mr] = 0.0;
                continue;
            }
            for (f = 0; f < MOTION_FRAMES; ++f)
                for (i = 0; i < npx; ++i) {
                    size_t a0 = (size_t)f * npx + i, v0 = ((size_t)mr * MOTION_FRAMES + f) * npx + i;
                    if (mhit[a0] && mref[a0] >= mfloor[f]) e += rel(mval[v0], mref[a0], mfloor[f]), ne++;
                    if (f + 1 < MOTION_FRAMES && mhit[a0] && mhit[a0 + npx] && !msamp[a0] && !msamp[a0 + npx] &&
                        (mref[a0] >= mfloor[f] || mref[a0 + npx] >= mfloor[f + 1]))
                        d += fabs(mval[v0 + npx] - mval[v0]);
                }
            motion_flicker[s][mr] = dref > 0.0 ? d / dref : 0.0;
            motion_own[s][mr] = sref > 0.0 ? d / sref : 0.0; /* per frame, relative to the reference's level */
            motion_err[s][mr] = ne ? e / ne : 0.0;
            printf("  motion %s: %-24s%s error %5.1f%%, flicker ratio %.2f (change %.1f%% per frame), non-finite %d\n", scene_key[s],
                   motion_name[mr], "", 100.0 * motion_err[s][mr],
                   motion_flicker[s][mr], 100.0 * motion_own[s][mr], motion_nonfinite[s][mr]);
        }
        motion_seconds[s] = now_seconds() - t0;
        printf("frame: motion %s: %d frames of %dx%d (zoom %.2f), reference's own change %.2f%% per frame (%.1f s); %d footprints over the "
               "cap sampled (own sampling deviation %.2f%%)", scene_key[s], MOTION_FRAMES, w, h, motion_zoom[s], 100.0 * motion_ref_change[s],
               motion_seconds[s], motion_capped[s], 100.0 * motion_seed_dev[s]);
        if (motion_grid)
            printf("; the grid-supersampled reference (%d^2 per texel): %.2f%% from the exact one, change frame 0 -> 1 %.2f%% (exact: %.2f%%)",
                   MOTION_SPT, 100.0 * motion_ss_dev[s], 100.0 * motion_ss_change[s], 100.0 * motion_cover_change01[s]);
        printf("\n");
        for (m = MT_LEADR; m < MT_COUNT; ++m) vkDestroyPipeline(vk.dev, pipes[m], NULL);
        vkDestroyFramebuffer(vk.dev, tg.fb, NULL);
        vkDestroyRenderPass(vk.dev, tg.rp, NULL);
        for (k = 0; k < 2; ++k) {
            vkDestroyImageView(vk.dev, tg.att_view[k], NULL);
            vkDestroyImage(vk.dev, tg.att[k], NULL);
            vkFreeMemory(vk.dev, tg.att_mem[k], NULL);
        }
        vkDestroyBuffer(vk.dev, tg.rb, NULL);
        vkFreeMemory(vk.dev, tg.rb_mem, NULL);
        free(mref), free(scratch), free(mval), free(mhit), free(msamp), free(vis_light);
        part_end(5);
    }

    /* ---------------------------------------------------------------- the table */
    snprintf(path, sizeof path, "%s/frame.csv", outdir);
    csv = fopen(path, "w");
    snprintf(path, sizeof path, "%s/frame.md", outdir);
    md = fopen(path, "w");
    if (!csv || !md) {
        fprintf(stderr, "frame: cannot write into %s\n", outdir);
        return 1;
    }
    { /* the motion rows, in a CSV of their own */
        FILE *mc;
        snprintf(path, sizeof path, "%s/frame_motion.csv", outdir);
        mc = fopen(path, "w");
        if (!mc) return 1;
        fprintf(mc, "scene,method,max_anisotropy,frames,err_mean,change_per_frame,flicker_ratio,ref_change_per_frame,nonfinite\n");
        for (s = 0; s < 2; ++s)
            for (k = 0; k < MOTION_ROWS; ++k)
                if (!(s != 0 && MR_PLANE_ONLY(k))) /* the horizon rows: the plane only */
                    fprintf(mc, "%s,%s,%d,%d,%.6g,%.6g,%.6g,%.6g,%d\n", scene_key[s], motion_key[k], k == MR_LEADR16 ? 16 : 1,
                        MOTION_FRAMES, motion_err[s][k], motion_own[s][k], motion_flicker[s][k], motion_ref_change[s], motion_nonfinite[s][k]);
        fclose(mc);
    }
    fprintf(csv, "scene,method,storage,max_anisotropy,lit_pixels,err_box,err_box_p95,err_pixel,err_pixel_p95,cpu_err_box,cpu_err_pixel,"
                 "vs_cpu,vs_cpu_p95,vs_cpu_driver_lod,vs_cpu_driver_lod_p95,lod_diff,nonfinite,spirv_ops,cond_branches,gpu_ms,"
                 "err_box_over_oracle,err_pixel_over_oracle\n");
    fprintf(md, "## The frame on a Vulkan driver\n\n"
                "bench/pictures.c's two scenes rendered by a Vulkan graphics pipeline (`bench/frame/`): a full-screen triangle "
                "whose fragment shader pastes the library's headers under `PF_GLSL`, ray-casts the scene with the same camera and "
                "pixel rays, and shades each pixel from the moment pyramid stored as two RGBA `VkImage`s with their whole mip "
                "chains (E[x], E[y], E[x^2], E[y^2] | E[xy], E[n]), fetched with `textureGrad` from the quad's "
                "`dFdxFine`/`dFdyFine` through a trilinear `VkSampler` at maxAnisotropy 1 and %.0f. Device: %s%s. Map %dx%d "
                "(Gaussian, pfm corpus defaults), base lobe deviation %.2f, no Fresnel; frames %dx%d (plane) and %dx%d (sphere).\n\n",
            aniso_used[1], vk.name, vk.is_cpu ? " (a CPU implementation: no time is given, it would not be GPU time)" : "", W, H,
            BASE_SIGMA, quick ? quick_size[0][0] : full_size[0][0], quick ? quick_size[0][1] : full_size[0][1],
            quick ? quick_size[1][0] : full_size[1][0], quick ? quick_size[1][1] : full_size[1][1]);
    fprintf(md, "Columns (relative error |a - b| / max(b, floor), floor = %.0f%% of the reference's 99th percentile, mean over the "
                "reference's lit pixels, as bench/pictures.c):\n\n"
                "- **error, box ref.**: against pictures.c's brute force for the same rays: its square round(side)^2 texel box, "
                "side = the isotropic ray-differential footprint (the GPU's level-of-detail rule);\n"
                "- **error, pixel ref.**: the same brute force over the pixel's own footprint, the parallelogram spanned by its "
                "two neighbour rays' texel offsets (the footprint anisotropic filtering approximates), integrated over the texels "
                "it touches, each weighted by the area it covers (a box-filtered pixel; over the cap, texels kept by a hash of "
                "their map position, as the motion reference);%s\n"
                "- at most %d x %d texels shaded per pixel for either reference%s;\n"
                "- **CPU path**: the library's C float build of the same method for the same pixel, from the float pyramid, at the "
                "texel coordinates and derivatives the GPU used, through the Vulkan specification's sampler (isotropic: "
                "trilinear at lod log2(rho_max); 16x: N = min(ceil(rho_max / rho_min), 16) trilinear probes along the major axis "
                "at lod log2(rho_max / N)); its errors against both references;\n"
                "- **vs CPU**: |GPU - CPU path| / max(CPU path, floor): storage, the driver's filtering and the GPU's arithmetic;\n"
                "- **vs CPU at driver lod**: the same with the CPU path at the level of detail the driver reports (a probe "
                "texture whose level l holds l, read with the same sampler and gradients), isotropic only; **lod diff**: "
                "isotropic rows, mean |driver's lod - log2(rho_max)|; 16x rows, the mean signed driver's lod - log2(rho_max / N) "
                "(the specification's) and - log2(rho_min);\n"
                "- **/ oracle's**: the error over the per-pixel oracle's against the same reference (the oracle: the exact slope "
                "histogram of the reference's own texels, every texel visible, times Smith's masking-shadowing of their exact "
                "moments, bench/pf_hist_oracle.h; it reads every texel, so it is no shader method); the row below it, LEADR from "
                "the exact slope moments of the same texels, is the best any filter of the moment pyramid can hand LEADR;\n"
                "- **LEADR, taps in the shader**: the anisotropic filter in the fragment shader with an isotropic sampler, as "
                "engines do for moment maps: N = min(ceil(rho_max / rho_min), 16) trilinear `textureLod` taps at the centres of N "
                "equal segments of the major axis at lod log2(rho_max / N), the moments averaged, LEADR once (its CPU path "
                "emulates the same taps);\n"
                "- **storage**: f32 and f16, the two RGBA textures above; unorm16 and unorm8 (LEADR only), `pf_encode.h`'s "
                "scaled UNORM: R16G16B16A16_UNORM + R16_UNORM (R8G8B8A8_UNORM + R8_UNORM) holding the five moments centred on "
                "the map's mean slope, E[x - rx], E[y - ry], E[(x - rx)^2], E[(y - ry)^2] | E[(x - rx)(y - ry)], each over its "
                "range for the whole pyramid (`pf_slope_encoding_find`, `pf_slope_moments_encode`), decoded in the shader after "
                "the sampler's filtering by `pf_slope_moments_decode` (affine with one reference per map, so the driver's "
                "trilinear and anisotropic blends still filter the moments; the encoding in a uniform buffer);\n"
                "- **non-finite**: NaN or infinite pixels of the whole GPU frame; **SPIR-V ops (branches)**: the fragment shader "
                "after `spirv-opt -O`, counted as bench/gpu/count.sh counts (the \"none\" shader, ray cast, derivatives and three "
                "fetches, is the baseline of the others).\n\n"
                "The vMF rows (`pf_vmf_sum_add`, `pf_vmf_sum_specular`: Wu et al. 2019 eqs. 4-5, slope form) read lobe "
                "pyramids fitted by EM (`pf_vmf_pyramid_from_normals`, %d iterations at most; %.1f s for m = 4, %.1f s for m = 8 "
                "of CPU time, one-offs) and uploaded as R32G32B32A32_SFLOAT 2D array images (layer j = lobe j, whole mip chains); a "
                "mixture is not filtered by averaging its parameters, so the shader reads the 8 texels of a trilinear fetch at "
                "the driver's lod with `texelFetch` and sums their lobes with the trilinear weights (bench/pictures.c's "
                "shade_vmf). Hence f32 and isotropic only (kappa reaches 1e5, past f16's range; no anisotropic variant); their "
                "CPU path is the same sum at log2(rho_max), or at the driver's lod.\n\n",
            100.0 * LIT_FRACTION,
            " a grid of one sample per texel per axis would take whole texels (a footprint 0.6 texel wide, one full row) and "
            "measure that quantization, not a filter, at footprints of a few texels",
            ref_max, ref_max, quick ? " (BENCH_QUICK)" : "", VMF_ITER, t_vmf[0], t_vmf[1]);
    fprintf(md, "The horizon rows (the plane only, f32, isotropic sampler): **LEADR, horizon** is `pf_horizon_leadr_specular_lod`, "
                "LEADR's specular with Smith's G replaced by the reflecting facets' horizon visibility, faded to plain LEADR "
                "between levels %.0f and %.0f (bench/microsurface.c's choice); **vMF m = 4, horizon** is "
                "`pf_horizon_vmf_specular_lod`, the vMF m = 4 row's lobes with the same visibility (conditioned on the "
                "slope-moment texel) and fade. Its HDF pyramid (`pf_horizon_pyramid`, "
                "PF_HORIZON_MOMENTS, %d azimuths, a %d-texel march on the periodic map; %.1f s wall time, a one-off) is one "
                "R32G32B32A32_SFLOAT 2D array image with its whole mip chain, layer j = azimuth j holding (E[T], E[T^2], E[S T], "
                "unused): %d bytes per texel of level 0, %.1f MB for the %dx%d map's chain. The shader fetches 4 layers "
                "(the two stored azimuths around wo and around wi) with the slope moments' sampler and gradients and mixes each "
                "pair with `pf_hdf_moments_lerp`; all its fetches (and its fade) take an explicit lod, log2 of the longer texel "
                "derivative, computed in the shader (`textureLod`); its CPU path is the same from the float pyramids at the same "
                "lod, so its **vs CPU at driver lod** column is what lavapipe's lod approximation would cost it, not a check. Both "
                "references march every texel's view and light rays through the whole periodic height field (occluders "
                "outside the footprint included): the box reference is bench/pictures.c's `full` (not its in-box variant), "
                "the pixel reference the same marches over the pixel's footprint. The HDF's conventions (azimuth 0 along +x, "
                "turning toward +y, rows along y, the direction toward the viewer or light, texel = 1 world unit) are checked "
                "against the brute force's march by bench/frame/horizon_check.c, which also splits the horizon rows' error into "
                "visibility and NDF by footprint band (docs/gpu.md says why the rows lose on this plane).\n\n",
            HOR_LOD_FULL, HOR_LOD_SMITH, HOR_AZ, HOR_STEPS, t_hdf, 16 * HOR_AZ,
            16.0 * HOR_AZ * (double)pf_mip_texel_count(W, H) / 1e6, W, H);
    for (s = 0; s < 2; ++s) {
        int br, ops0 = ops_of(ops_file, s, MT_NONE, &br);
        fprintf(md, "**%s**: %d surface pixels, lit %d (box reference) and %d (pixel reference), median footprint side %.1f "
                    "texels; references %.1f s (both in one pass, wall time, %d threads); %d pixels sit in quads at the surface's edge (the "
                    "shader's ray-differential fallback); pixels where the GPU's and the CPU's rays disagree on hitting: %d. "
                    "The CPU float path at pictures.c's own footprint (lod from the analytic ray differentials) against the box "
                    "reference: LEADR %.1f%%, naive %.1f%%, Toksvig %.1f%%, vMF m = 4 %.1f%%, m = 8 %.1f%%.\n\n",
                scene_key[s], n_surf[s], n_lit[s][0], n_lit[s][1], fp_med[s], t_ref[s], pfb_thread_count(), n_edge[s], n_mism[s],
                100.0 * cpu_pic_err[s][MT_LEADR], 100.0 * cpu_pic_err[s][MT_NAIVE], 100.0 * cpu_pic_err[s][MT_TOKSVIG],
                100.0 * cpu_pic_err[s][MT_VMF4], 100.0 * cpu_pic_err[s][MT_VMF8]);
        fprintf(md, "| %s: method | storage | aniso | error, box ref. (mean, p95) | error, pixel ref. (mean, p95) | / oracle's "
                    "(box, pixel) | CPU path: box, pixel ref. | vs CPU (mean, p95) | vs CPU at driver lod (mean, p95) | lod diff | "
                    "non-finite | SPIR-V ops (branches) |%s\n|---|---|--:|---|---|---|---|---|---|--:|--:|---|%s\n",
                scene_key[s], have_ts ? " GPU ms |" : "", have_ts ? "--:|" : "");
        fprintf(md, "| none (ray cast + fetches) | - | - | - | - | - | - | - | - | - | - | %d (%d) |%s\n", ops0, br, have_ts ? " - |" : "");
        fprintf(md, "| **oracle**: exact histogram + Smith (CPU, the reference's texels) | - | - | %.1f%%, %.1f%% | %.1f%%, %.1f%% | 1, 1 | - "
                    "| - | - | - | - | - |%s\n",
                100.0 * oracle_err[s][0], 100.0 * oracle_p95[s][0], 100.0 * oracle_err[s][1], 100.0 * oracle_p95[s][1], have_ts ? " - |" : "");
        fprintf(md, "| LEADR from the exact moments of the reference's texels (CPU) | - | - | %.1f%%, %.1f%% | %.1f%%, %.1f%% | %.2f, %.2f | - "
                    "| - | - | - | - | - |%s\n",
                100.0 * lex_err[s][0], 100.0 * lex_p95[s][0], 100.0 * lex_err[s][1], 100.0 * lex_p95[s][1], lex_err[s][0] / oracle_err[s][0],
                lex_err[s][1] / oracle_err[s][1], have_ts ? " - |" : "");
        for (m = MT_LEADR; m < MT_COUNT; ++m) {
            int ops;
            for (st = 0; st < NSTORE; ++st)
                for (an = 0; an < NANISO; ++an) {
                    const fr_row *rw = &rows[s][m][st][an];
                    char drv[64] = "-", lod[32] = "-";
                    if (!rw->done) continue;
                    /* the UNORM rows: the decoding shader's count */
                    ops = st >= ST_UNORM16 ? ops_of_key(ops_file, s, "leadr_unorm", &br) : ops_of(ops_file, s, m, &br);
                    if (rw->vs_drv >= 0.0) snprintf(drv, sizeof drv, "%.4f%%, %.4f%%", 100.0 * rw->vs_drv, 100.0 * rw->vs_drv_p95);
                    if (rw->lod_diff > -1e29 && an == 0) snprintf(lod, sizeof lod, "%.4f", rw->lod_diff);
                    if (rw->lod_diff > -1e29 && an > 0) snprintf(lod, sizeof lod, "%+.2f, %+.2f", rw->lod_diff, rw->lod_rmin);
                    fprintf(md, "| %s | %s | %.0f | %.1f%%, %.1f%% | %.1f%%, %.1f%% | %.2f, %.2f | %.1f%%, %.1f%% | %.3f%%, %.3f%% | %s | %s | %d | %d (%d) |",
                            method_name[m], store_name[st], aniso_used[an], 100.0 * rw->err[0], 100.0 * rw->err_p95[0],
                            100.0 * rw->err[1], 100.0 * rw->err_p95[1], rw->err[0] / oracle_err[s][0], rw->err[1] / oracle_err[s][1],
                            100.0 * rw->cpu_err[0], 100.0 * rw->cpu_err[1],
                            100.0 * rw->vs_cpu, 100.0 * rw->vs_cpu_p95, drv, lod, rw->nonfinite, ops, br);
                    if (have_ts) fprintf(md, " %.3f |", rw->ms);
                    fprintf(md, "\n");
                    fprintf(csv, "%s,%s,%s,%.0f,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%d,%.6g,%.6g,%.6g\n", scene_key[s],
                            method_key[m], store_name[st], aniso_used[an], rw->n_lit, rw->err[0], rw->err_p95[0], rw->err[1],
                            rw->err_p95[1], rw->cpu_err[0], rw->cpu_err[1], rw->vs_cpu, rw->vs_cpu_p95, rw->vs_drv, rw->vs_drv_p95,
                            rw->lod_diff, rw->nonfinite, ops, br, rw->ms, rw->err[0] / oracle_err[s][0], rw->err[1] / oracle_err[s][1]);
                }
        }
        fprintf(md, "\n![%s: reference and GPU frame](frame_%s.png)\n\n", scene_key[s], scene_key[s]);
    }
    fprintf(md, "**Motion.** %d frames per scene at %dx%d (plane) and %dx%d (sphere): the plane's camera dollies forward %.2f "
                "texel per frame; the sphere's view is zoomed in %.1fx (field of view narrowed until the median footprint side is "
                "%.0f%% of the %d-texel cap: %.1f texels) and turns %.3f degree per frame about its pole (about %.1f texels at the "
                "equator); f32 storage.\n\n"
                "**Reference.** The first motion reference sampled the footprint on a grid attached to the screen (2 samples "
                "per texel per axis, at most %d per axis): where a footprint is larger than that, its samples jump "
                "from texel to texel as the camera moves, and on the unzoomed sphere (footprints of about 100 texels) that "
                "sampling was most of its change per frame (BENCH_QUICK, frame 0 to 1: 11.6%% against 3.4%% for a reference "
                "sampled on the surface). Hence the sphere's zoom, and a motion reference that integrates the pixel's footprint (the parallelogram of its neighbour rays) over the texels, each "
                "weighted by the area it covers (polygon clipping): a box-filtered pixel whose value moves continuously with the "
                "camera. A footprint over %d texels keeps each texel with probability %d / area, chosen by a hash of its map "
                "position (attached to the surface, nested as the area changes); such pixels (%d of the plane's %d pixel-frames, "
                "%d of the sphere's %d) are left out of the flicker sums; their sampling deviation (the same frame with another "
                "hash, |difference| / sqrt 2): %.1f%% (plane), %.1f%% (sphere); every other pixel is integrated exactly. ",
            MOTION_FRAMES, quick ? motion_quick[0][0] : motion_full[0][0], quick ? motion_quick[0][1] : motion_full[0][1],
            quick ? motion_quick[1][0] : motion_full[1][0], quick ? motion_quick[1][1] : motion_full[1][1], PLANE_DOLLY_STEP,
            motion_zoom[1], 100.0 * MOTION_SIDE_FRACTION, ref_max, motion_fp_med, SPHERE_TURN_STEP / motion_zoom[1] * 180.0 / pic_pi,
            SPHERE_TURN_STEP / motion_zoom[1] / (2.0 * pic_pi) * SPHERE_TILES * W, ref_max, ref_max * ref_max, ref_max * ref_max,
            motion_capped[0], motion_pxf[0], motion_capped[1], motion_pxf[1], 100.0 * motion_seed_dev[0], 100.0 * motion_seed_dev[1]);
    if (motion_grid)
        fprintf(md, "For comparison, on frames 0 and 1 the grid-supersampled reference (%d^2 samples per texel) is %.1f%% / %.1f%% "
                    "(plane / sphere) away from this one and changes %.1f%% / %.1f%% from frame 0 to 1, where this one changes "
                    "%.1f%% / %.1f%%: once the footprints fit the cap, the grid's sampling adds little to the change, but each frame "
                    "of it is still that far from the integral. ",
                MOTION_SPT, 100.0 * motion_ss_dev[0], 100.0 * motion_ss_dev[1], 100.0 * motion_ss_change[0], 100.0 * motion_ss_change[1],
                100.0 * motion_cover_change01[0], 100.0 * motion_cover_change01[1]);
    else
        fprintf(md, "The comparison with the grid-supersampled reference (%d^2 samples per texel: its distance from this one on "
                    "frames 0 and 1, and its change from frame 0 to 1 next to this one's) costs two more reference frames per "
                    "scene and no target reads it: `PFF_MOTION_GRID=1 make frame` adds it here. ", MOTION_SPT);
    fprintf(md, "The plane's reference changes by two thirds per frame: near the camera a "
                "pixel covers less than a texel of the height field's flat facets, and a quarter-texel dolly moves it onto "
                "another facet; the filtered methods interpolate between texels, so they change far less than that truth.\n\n"
                "**Change per frame** = sum over consecutive frames and pixels lit in either frame (and integrated exactly in both) "
                "of |change| / sum of the reference's level; **flicker ratio** = the method's change / the reference's own (%.1f%% "
                "per frame on the plane, %.1f%% on the sphere). A ratio below 1: the method changes less than the box-filtered "
                "truth (it is smoother in time than the sparkle of the texels' own lobes); above 1: it shimmers more than the truth. "
                "The oracle (exact histogram + Smith, CPU, over the same texels) shows what a filtered representation that keeps "
                "the whole histogram would do; the naive mip-mapped normal is the anchor of shimmer.\n\n",
            100.0 * motion_ref_change[0], 100.0 * motion_ref_change[1]);
    fprintf(md, "| method | plane: error (mean over frames) | plane: change per frame | plane: flicker ratio | sphere: error | "
                "sphere: change per frame | sphere: flicker ratio | non-finite |\n|---|---|--:|--:|---|--:|--:|--:|\n");
    for (k = 0; k < MOTION_ROWS; ++k)
        if (MR_PLANE_ONLY(k))
            fprintf(md, "| %s | %.1f%% | %.2f%% | %.3f | - | - | - | %d |\n", motion_name[k], 100.0 * motion_err[0][k], 100.0 * motion_own[0][k],
                    motion_flicker[0][k], motion_nonfinite[0][k]);
        else
            fprintf(md, "| %s | %.1f%% | %.2f%% | %.3f | %.1f%% | %.2f%% | %.3f | %d |\n", motion_name[k], 100.0 * motion_err[0][k], 100.0 * motion_own[0][k], motion_flicker[0][k],
                    100.0 * motion_err[1][k], 100.0 * motion_own[1][k], motion_flicker[1][k], motion_nonfinite[0][k] + motion_nonfinite[1][k]);
    fprintf(md, "| reference (footprint integrated over its texels) | - | %.2f%% | 1 | - | %.2f%% | 1 | - |\n", 100.0 * motion_ref_change[0],
            100.0 * motion_ref_change[1]);
    fprintf(md, "\n");
    for (s = 0; s < 2; ++s) {
        double best = 1e30;
        int bk = 0;
        for (k = 0; k < MOTION_ROWS; ++k)
            if (k != MR_ORACLE && motion_method[k] != MT_NAIVE && !(s != 0 && MR_PLANE_ONLY(k)) && motion_err[s][k] < best)
                best = motion_err[s][k], bk = k;
        motion_best[s] = bk;
    }
    /* the issue's targets, as measured */
    {
        double worst32 = 0.0, worst16 = 0.0, worst_drv = 0.0, worst_hor = 0.0, worst_hor_drv = 0.0;
        int nonfin = 0, ws = 0, wm = MT_LEADR;
        const fr_row *iso = &rows[0][MT_LEADR][0][0], *ani = &rows[0][MT_LEADR][0][1];
        for (s = 0; s < 2; ++s)
            for (m = MT_LEADR; m < MT_COUNT; ++m)
                for (an = 0; an < NANISO; ++an) {
                    if (an == 0 && IS_HOR(m) && rows[s][m][0][an].vs_cpu > worst_hor) worst_hor = rows[s][m][0][an].vs_cpu;
                    else if (an == 0 && rows[s][m][0][an].vs_cpu > worst32) worst32 = rows[s][m][0][an].vs_cpu, ws = s, wm = m;
                    if (an == 0 && IS_HOR(m) && rows[s][m][0][an].vs_drv > worst_hor_drv) worst_hor_drv = rows[s][m][0][an].vs_drv;
                    else if (an == 0 && rows[s][m][0][an].vs_drv > worst_drv) worst_drv = rows[s][m][0][an].vs_drv;
                    if (an == 0 && rows[s][m][1][an].vs_cpu > worst16) worst16 = rows[s][m][1][an].vs_cpu;
                    for (st = 0; st < NSTORE; ++st) nonfin += rows[s][m][st][an].nonfinite;
                }
        fprintf(md, "Targets, as measured in this run (isotropic rows for the first two: the 16x rows compare two different "
                    "anisotropic filters, the driver's and the specification's):\n\n");
        fprintf(md, "- GPU within 1%% of the CPU float path, f32 storage: worst mean over scenes and methods (the horizon rows "
                    "apart) %.3f%%: %s. With the "
                    "CPU path at the driver's own level of detail: worst %.4f%% (LEADR, naive, Toksvig: below 0.001%%, so their difference "
                    "is the driver's lod approximation; the vMF rows read their texels with texelFetch at the level the lod probe gives, "
                    "and take each level's size from level 0's: lavapipe answers textureSize(sampler, l) with one lane's l for all the "
                    "lanes it runs together, which made black pixels where a pixel's level differed from that lane's). The two horizon "
                    "rows (the plane, below), apart: worst %.3f%%, %s; they fetch at an explicit lod, log2 of the longer texel "
                    "derivative computed in the shader (`textureLod`, as engines do for array textures), the formula of their CPU "
                    "path, so this compares the driver's trilinear filtering of the moment, HDF and lobe textures (texels, wrap, "
                    "weights, level blend) with the CPU's at the same lod and leaves lavapipe's lod approximation out; the CPU path "
                    "at the driver's lod (the probe) against the same GPU pixels, %.4f%%, is what that approximation would cost "
                    "them (with the driver's lod in the shader they were 1.144%% and 1.182%% off in a full run, 1.15%% and 1.21%% "
                    "BENCH_QUICK: the fetches, not the fade, carried LEADR's).\n",
                100.0 * worst32, quick ? "BENCH_QUICK: judged at the driver's lod, see below" : (worst32 <= 0.01 ? "met" : "NOT met"),
                100.0 * worst_drv, 100.0 * worst_hor, worst_hor <= 0.01 ? "met" : "NOT met", 100.0 * worst_hor_drv);
        { /* the worst row's difference by band of the driver's lod */
            const fr_row *wr = &rows[ws][wm][0][0];
            int b, nt = 0, n1 = 0;
            double e1 = 0.0;
            for (b = 0; b < NBAND_LOD; ++b) nt += wr->band_n[b];
            for (b = 1; b < 5 && b < NBAND_LOD; ++b) n1 += wr->band_n[b], e1 += wr->band_vs[b];
            fprintf(md, "  By band of the driver's lod, the worst row (%s, %s; lit pixels: share, mean):", method_name[wm], scene_key[ws]);
            for (b = 0; b < NBAND_LOD; ++b)
                fprintf(md, "%s [%d, %d%s %.1f%%, %.3f%%", b ? ";" : "", b, b + 1, b + 1 < NBAND_LOD ? ")" : "+)",
                        nt ? 100.0 * wr->band_n[b] / nt : 0.0, wr->band_n[b] ? 100.0 * wr->band_vs[b] / wr->band_n[b] : 0.0);
            fprintf(md, ". The difference is lavapipe's lod approximation alone (mean |lod difference| %.4f; the CPU path at the "
                        "driver's lod: %.4f%%), and what the same lod error costs depends on the level: lods 1 to 5 hold %.1f%% of "
                        "the lit pixels here, at %.3f%%.\n", wr->lod_diff, 100.0 * wr->vs_drv, nt ? 100.0 * n1 / nt : 0.0, n1 ? 100.0 * e1 / n1 : 0.0);
            if (quick) {
                /* a full run's means by band for naive on the plane (its worst row, 400x250; PFF_DEBUG_OUTLIERS
                   prints them), weighted by this run's shares: what the mix of levels alone gives */
                static const double full_band[NBAND_LOD] = {0.00282, 0.01016, 0.02694, 0.03708, 0.02211, 0.00563, 0.00186, 0.00042};
                double mix = 0.0;
                for (b = 0; b < NBAND_LOD; ++b) mix += nt ? full_band[b] * wr->band_n[b] / nt : 0.0;
                fprintf(md, "  BENCH_QUICK: the frames are %dx%d and %dx%d, 2.5x smaller across than the full run's %dx%d and %dx%d, "
                            "so every footprint is 2.5x longer (its lod 1.3 higher) and the lit pixels sit at other levels: the "
                            "magnified ones (below lod 1: 22.0%% of the plane's lit pixels in a full run, where naive differs by "
                            "0.28%%) are all but gone, and lods 1 to 5 (35.2%% in a full run, at 2.30%%) weigh more. A full run's "
                            "means by band for naive on the plane, weighted by this run's shares, give %.3f%% (the full run's own "
                            "mean: 0.951%%): the mix of levels. The quick frame measures the same lod approximation (a full run: "
                            "mean |lod difference| 0.0215, 0.0001%% at the driver's lod) over a coarser mix of levels, so its mean "
                            "is not the full frame's and the 1%% target is judged on the full run; here the verdict is taken at the "
                            "driver's lod, the storage, filtering and arithmetic the target is about: worst %.4f%%, %s.\n",
                        quick_size[0][0], quick_size[0][1], quick_size[1][0], quick_size[1][1], full_size[0][0], full_size[0][1],
                        full_size[1][0], full_size[1][1], 100.0 * mix, 100.0 * worst_drv, worst_drv <= 0.01 ? "met" : "NOT met");
            }
        }
        fprintf(md, "- within 3%% with f16 storage: worst mean %.3f%%: %s.\n", 100.0 * worst16, worst16 <= 0.03 ? "met" : "NOT met");
        if (rows[0][MT_LEADR][ST_UNORM16][0].done && rows[1][MT_LEADR][ST_UNORM16][0].done) {
            const fr_row *u[2][2] = {{&rows[0][MT_LEADR][ST_UNORM16][0], &rows[1][MT_LEADR][ST_UNORM16][0]},
                                     {&rows[0][MT_LEADR][ST_UNORM8][0], &rows[1][MT_LEADR][ST_UNORM8][0]}};
            double wu = u[0][0]->vs_cpu > u[0][1]->vs_cpu ? u[0][0]->vs_cpu : u[0][1]->vs_cpu;
            int b0, b1, o0 = ops_of(ops_file, 0, MT_LEADR, &b0), o1 = ops_of_key(ops_file, 0, "leadr_unorm", &b1);
            fprintf(md, "- within 3%% with 16-bit storage, LEADR from R16G16B16A16_UNORM + R16_UNORM (pf_encode.h: the five moments "
                        "centred on the map's mean slope, one scale and offset per channel for the whole pyramid, decoded after "
                        "the sampler's filtering by `pf_slope_moments_decode`): worst mean %.3f%%: %s (plane %.3f%%, sphere %.3f%%; "
                        "against the CPU path at the driver's lod, storage and arithmetic alone: %.4f%%, %.4f%%). 8 bits "
                        "(R8G8B8A8_UNORM + R8_UNORM): plane %s, sphere %s (at the driver's lod %s, %s). The decode adds %d SPIR-V "
                        "ops to LEADR's %d (plane: uniform loads and the five multiply-adds and (1) of pf_encode.h).\n",
                    100.0 * wu, wu <= 0.03 ? "met" : "NOT met", 100.0 * u[0][0]->vs_cpu, 100.0 * u[0][1]->vs_cpu, 100.0 * u[0][0]->vs_drv,
                    100.0 * u[0][1]->vs_drv, u[1][0]->done ? fmt_pct(u[1][0]->vs_cpu, 3) : "-", u[1][1]->done ? fmt_pct(u[1][1]->vs_cpu, 3) : "-",
                    u[1][0]->done ? fmt_pct(u[1][0]->vs_drv, 4) : "-", u[1][1]->done ? fmt_pct(u[1][1]->vs_drv, 4) : "-", o1 - o0, o0);
        }
        {
            const fr_row *tp = &rows[0][MT_LEADR_TAPS][0][0];
            int br0, br1, o0 = ops_of(ops_file, 0, MT_LEADR, &br0), o1 = ops_of(ops_file, 0, MT_LEADR_TAPS, &br1);
            fprintf(md, "- 16x anisotropy lowers the plane's LEADR error by at least a fifth (f32), against the pixel reference (the "
                        "footprint anisotropic filtering approximates): isotropic trilinear %.1f%% -> the taps in the shader %.1f%% "
                        "(%+.1f%%: %s), the driver's 16x sampler %.1f%% (%+.1f%%: %s), the specification's 16x filter emulated on "
                        "the CPU %.1f%% -> %.1f%% (%+.1f%%: %s). Against the box reference (a square of side rho_max: isotropic by "
                        "construction, so any anisotropic filter moves away from it) %.1f%% -> taps %.1f%%, driver %.1f%%.\n",
                    100.0 * iso->err[1], 100.0 * tp->err[1], 100.0 * (tp->err[1] / iso->err[1] - 1.0),
                    tp->err[1] <= 0.8 * iso->err[1] ? "met" : "NOT met", 100.0 * ani->err[1], 100.0 * (ani->err[1] / iso->err[1] - 1.0),
                    ani->err[1] <= 0.8 * iso->err[1] ? "met" : "NOT met", 100.0 * iso->cpu_err[1], 100.0 * ani->cpu_err[1],
                    100.0 * (ani->cpu_err[1] / iso->cpu_err[1] - 1.0), ani->cpu_err[1] <= 0.8 * iso->cpu_err[1] ? "met" : "NOT met",
                    100.0 * iso->err[0], 100.0 * tp->err[0], 100.0 * ani->err[0]);
            fprintf(md, "  The taps in the shader (isotropic sampler; N = min(ceil(rho_max / rho_min), 16) trilinear `textureLod` taps "
                        "at the centres of N equal segments of the major axis, at lod log2(rho_max / N)) cost %d SPIR-V ops (%d "
                        "branches) against LEADR's %d (%d), the loop counted once. Lavapipe's 16x level of detail is %+.2f levels "
                        "from the specification's log2(rho_max / N) and %+.2f from log2(rho_min) (mean over the lit pixels), and its "
                        "frame is %.1f%% (mean) from the specification's filter.\n",
                    o1, br1, o0, br0, ani->lod_diff, ani->lod_rmin, 100.0 * ani->vs_cpu);
        }
        fprintf(md, "  Where the rest is: LEADR from the exact slope moments of the pixel reference's own texels (each weighted by "
                    "the area the footprint covers) is %.1f%% against the pixel reference (the oracle: %.1f%%). It is not a floor: "
                    "by footprint band (the table below) the filters that follow the footprint come within a few points of the "
                    "exact moments below 8 texels, where all of the gain is, and from 16 texels up the exact moments themselves "
                    "are further from the brute force than trilinear's blur is (LEADR's Gaussian and Smith's term, not the "
                    "filter). Other shader filters, measured on the same pixels by bench/frame/filters.c (CPU emulation, BENCH_QUICK / "
                    "full, pixel reference, hash seed 1): a grid over the pixel's parallelogram of at most 16 taps at the level of "
                    "its cell 46.1%% / 37.9%% against the taps' 47.3%% / 38.1%% (trilinear 60.1%% / 48.2%%, the specification's "
                    "16x 49.8%% / 39.5%%: the same N and level, its N probes at i / (N + 1) of the major axis instead of the "
                    "segments' centres); the taps along the footprint ellipse's major axis (the Jacobian's first singular "
                    "vector, length sigma_1, N = ceil(sigma_1 / sigma_2)) 47.1%% / 38.1%%; a finer level (log2 rho_min - 0.5 "
                    ".. 1), more taps (cap 32, 64: the cap binds only for ratios 16-32, the plane has none above 32) or both: "
                    "47.2%% to 48.8%% / 38.0%% to 39.4%%. The taps are kept.\n",
                100.0 * lex_err[0][1], 100.0 * oracle_err[0][1]);
        { /* the horizon method (the plane) */
            const fr_row *hz = &rows[0][MT_HORIZON][0][0];
            int bh, bl, oh = ops_of(ops_file, 0, MT_HORIZON, &bh), ol = ops_of(ops_file, 0, MT_LEADR, &bl);
            if (hz->done)
                fprintf(md, "- the horizon method on the plane (f32, isotropic trilinear), `pf_horizon_leadr_specular_lod`: against "
                            "the box reference %.1f%% (LEADR %.1f%%), against the pixel reference %.1f%% (LEADR %.1f%%), both "
                            "references with every occluder of the periodic height field; %.2fx and %.2fx the oracle's; the GPU "
                            "within %.3f%% of the CPU float path at the same explicit lod (%s; the CPU path at the driver's lod instead: %.4f%%); flicker ratio %.3f (LEADR %.3f) "
                            "over the motion frames, error there %.1f%% (LEADR %.1f%%); non-finite pixels: %d still, %d moving; "
                            "%d SPIR-V ops (%d branches) against LEADR's %d (%d): four HDF fetches, two azimuths, the conditional "
                            "horizon visibility.\n",
                        100.0 * hz->err[0], 100.0 * iso->err[0], 100.0 * hz->err[1], 100.0 * iso->err[1],
                        oracle_err[0][0] > 0.0 ? hz->err[0] / oracle_err[0][0] : 0.0, oracle_err[0][1] > 0.0 ? hz->err[1] / oracle_err[0][1] : 0.0,
                        100.0 * hz->vs_cpu, hz->vs_cpu <= 0.01 ? "within 1%" : "NOT within 1%", 100.0 * hz->vs_drv,
                        motion_flicker[0][MR_HORIZON], motion_flicker[0][0], 100.0 * motion_err[0][MR_HORIZON], 100.0 * motion_err[0][0],
                        hz->nonfinite, motion_nonfinite[0][MR_HORIZON], oh, bh, ol, bl);
            hz = &rows[0][MT_VMF4_HORIZON][0][0];
            oh = ops_of(ops_file, 0, MT_VMF4_HORIZON, &bh), ol = ops_of(ops_file, 0, MT_VMF4, &bl);
            if (hz->done)
                fprintf(md, "  `pf_horizon_vmf_specular_lod` (vMF m = 4, the same HDF, conditioned on the slope-moment texel): "
                            "against the box reference %.1f%% (vMF m = 4 %.1f%%), against the pixel reference %.1f%% (%.1f%%); "
                            "%.2fx and %.2fx the oracle's; the GPU within %.3f%% of the CPU float path at the same explicit lod (%s; "
                            "the CPU path at the driver's lod instead: %.4f%%); flicker ratio %.3f (vMF m = 4 %.3f), error under motion %.1f%% (%.1f%%); non-finite pixels: "
                            "%d still, %d moving; %d SPIR-V ops (%d branches) against vMF m = 4's %d (%d).\n",
                        100.0 * hz->err[0], 100.0 * rows[0][MT_VMF4][0][0].err[0], 100.0 * hz->err[1], 100.0 * rows[0][MT_VMF4][0][0].err[1],
                        oracle_err[0][0] > 0.0 ? hz->err[0] / oracle_err[0][0] : 0.0, oracle_err[0][1] > 0.0 ? hz->err[1] / oracle_err[0][1] : 0.0,
                        100.0 * hz->vs_cpu, hz->vs_cpu <= 0.01 ? "within 1%" : "NOT within 1%", 100.0 * hz->vs_drv,
                        motion_flicker[0][MR_VMF_HORIZON], motion_flicker[0][3], 100.0 * motion_err[0][MR_VMF_HORIZON], 100.0 * motion_err[0][3],
                        hz->nonfinite, motion_nonfinite[0][MR_VMF_HORIZON], oh, bh, ol, bl);
        }
        fprintf(md, "- every method's error as a ratio to the per-pixel oracle's, on both scenes: the tables' \"/ oracle's\" "
                    "column (oracle: plane %.1f%% / %.1f%%, sphere %.1f%% / %.1f%%, box / pixel reference).\n",
                100.0 * oracle_err[0][0], 100.0 * oracle_err[0][1], 100.0 * oracle_err[1][0], 100.0 * oracle_err[1][1]);
        for (s = 0; s < 2; ++s)
            for (k = 0; k < MOTION_ROWS; ++k) nonfin += motion_nonfinite[s][k];
        for (s = 0; s < 2; ++s)
            fprintf(md, "- %s: the best filtered method's flicker at most 1.5x the reference's own: %s (lowest error under "
                        "motion) changes %.2fx as much as the temporally stable reference: %s.\n",
                    scene_key[s], motion_name[motion_best[s]], motion_flicker[s][motion_best[s]],
                    motion_flicker[s][motion_best[s]] <= 1.5 ? "met" : "NOT met");
        fprintf(md, "- no NaN or infinite pixel: %d over every frame, still and moving: %s.\n\n", nonfin, nonfin == 0 ? "met" : "NOT met");
    }
    { /* FILTER BANDS: the plane's LEADR per footprint and anisotropy band, pixel reference */
        int v, br, ba;
        fprintf(md, "**Filter bands** (plane, LEADR, f32, error against the pixel reference, mean over its lit pixels in each "
                    "band; rho_max = the longer screen derivative of the texel coordinates, in texels, from the analytic ray "
                    "differentials; ratio = rho_max / rho_min):\n\n| filter | all |");
        for (br = 0; br < NBAND_RHO; ++br)
            if (br == 0) fprintf(md, " rho < 2 |");
            else if (br == NBAND_RHO - 1) fprintf(md, " rho >= %d |", 1 << br);
            else fprintf(md, " %d-%d |", 1 << br, 2 << br);
        for (ba = 0; ba < NBAND_AN; ++ba)
            if (ba == 0) fprintf(md, " ratio < 2 |");
            else if (ba == NBAND_AN - 1) fprintf(md, " ratio >= %d |", 1 << ba);
            else fprintf(md, " ratio %d-%d |", 1 << ba, 2 << ba);
        fprintf(md, "\n|---|--:|");
        for (k = 0; k < NBAND_RHO + NBAND_AN; ++k) fprintf(md, "--:|");
        fprintf(md, "\n| pixels | %d |", n_lit[0][1]);
        for (br = 0; br < NBAND_RHO; ++br) {
            int c = 0;
            for (ba = 0; ba < NBAND_AN; ++ba) c += fb_n[br][ba];
            fprintf(md, " %d |", c);
        }
        for (ba = 0; ba < NBAND_AN; ++ba) {
            int c = 0;
            for (br = 0; br < NBAND_RHO; ++br) c += fb_n[br][ba];
            fprintf(md, " %d |", c);
        }
        fprintf(md, "\n");
        for (v = 0; v < NFB; ++v) {
            double t = 0.0;
            int c = 0;
            for (br = 0; br < NBAND_RHO; ++br)
                for (ba = 0; ba < NBAND_AN; ++ba) t += fb_sum[v][br][ba], c += fb_n[br][ba];
            fprintf(md, "| %s | %s |", fb_name[v], c ? fmt_pct(t / c, 1) : "-");
            for (br = 0; br < NBAND_RHO; ++br) {
                double e = 0.0;
                int n = 0;
                for (ba = 0; ba < NBAND_AN; ++ba) e += fb_sum[v][br][ba], n += fb_n[br][ba];
                fprintf(md, " %s |", n ? fmt_pct(e / n, 1) : "-");
            }
            for (ba = 0; ba < NBAND_AN; ++ba) {
                double e = 0.0;
                int n = 0;
                for (br = 0; br < NBAND_RHO; ++br) e += fb_sum[v][br][ba], n += fb_n[br][ba];
                fprintf(md, " %s |", n ? fmt_pct(e / n, 1) : "-");
            }
            fprintf(md, "\n");
        }
        fprintf(md, "\n");
    }
    part_end(7);
    if (fc_bench(spv, outdir, ops_file, quick, md, &probe, &vtex[0], &vtex[1], &htex) != 0) return 1;
    part_end(6);
    fprintf(md, "Generated by `bench/frame/run.sh` (`make frame`; `make bench` runs it) in %.0f s%s; reproduce the GPU column "
                "on another device with `PF_VK_DEVICE=<index or name> make frame`.\n\n",
            now_seconds() - t_start, quick ? " (BENCH_QUICK: small frames, at most 32 x 32 reference texels per pixel)" : "");
    fclose(md);
    fclose(csv);
    { /* docs/gpu.md's frame block (bench/update_docs.sh copies OUT_DIR/gpuframe.md whole) and
         the method guide's (bench/choosing.sh appends OUT_DIR/frame_choosing.md): one table,
         f32 storage, isotropic sampler unless named */
        FILE *g, *gg[2];
        int gi;
        snprintf(path, sizeof path, "%s/gpuframe.md", outdir);
        gg[0] = fopen(path, "w");
        snprintf(path, sizeof path, "%s/frame_choosing.md", outdir);
        gg[1] = fopen(path, "w");
        if (!gg[0] || !gg[1]) return 1;
        fprintf(gg[1], "\n### the frame on a GPU (specular)\n\nThe specular methods in a rendered frame (bench/frame/, "
                       "[the frame](#the-frame-on-a-vulkan-driver)): a fragment shader pasting the library, pyramids as GPU "
                       "textures, the driver's sampler. ");
        for (gi = 0; gi < 2; ++gi) {
            g = gg[gi];
            fprintf(g, "Measured by `make bench` (bench/frame/, device %s%s): mean relative error per lit pixel against the "
                       "brute force over the pixel's own footprint (pixel reference), that error over the per-pixel oracle's (the exact "
                       "histogram of the same texels with Smith's visibility), the GPU against the library's C float path for the same "
                       "pixels, the flicker ratio under motion (the method's change per frame over the temporally stable reference's "
                       "own), and the fragment shader's SPIR-V ops after `spirv-opt -O`. f32 textures.\n\n",
                    vk.name, vk.is_cpu ? ", a CPU implementation: no GPU time" : "");
            fprintf(g, "| method | plane: error | / oracle | GPU vs CPU | flicker | sphere: error | / oracle | GPU vs CPU | flicker | SPIR-V ops "
                       "(plane) |\n|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
            fprintf(g, "| oracle (CPU, reads every texel) | %.1f%% | 1 | - | %.2f | %.1f%% | 1 | - | %.2f | - |\n", 100.0 * oracle_err[0][1],
                    motion_flicker[0][MR_ORACLE], 100.0 * oracle_err[1][1], motion_flicker[1][MR_ORACLE]);
            fprintf(g, "| LEADR from the exact footprint moments (CPU) | %.1f%% | %.2f | - | - | %.1f%% | %.2f | - | - | - |\n",
                    100.0 * lex_err[0][1], lex_err[0][1] / oracle_err[0][1], 100.0 * lex_err[1][1], lex_err[1][1] / oracle_err[1][1]);
            for (m = MT_LEADR; m < MT_COUNT; ++m)
                for (an = 0; an < NANISO; ++an) {
                    int br, ops = ops_of(ops_file, 0, m, &br), mk = -1;
                    char fl[2][16];
                    if (!rows[0][m][0][an].done) continue;
                    for (k = 0; k < MOTION_ROWS; ++k)
                        if (k != MR_ORACLE && motion_method[k] == m && (k == MR_LEADR16) == (an == 1)) mk = k;
                    for (s = 0; s < 2; ++s) {
                        if (mk >= 0 && !(s != 0 && MR_PLANE_ONLY(mk))) snprintf(fl[s], sizeof fl[s], "%.2f", motion_flicker[s][mk]);
                        else snprintf(fl[s], sizeof fl[s], "-");
                    }
                    fprintf(g, "| %s%s | %.1f%% | %.2f | %.2f%% | %s |", method_name[m], an ? ", 16x sampler" : "",
                            100.0 * rows[0][m][0][an].err[1], rows[0][m][0][an].err[1] / oracle_err[0][1], 100.0 * rows[0][m][0][an].vs_cpu,
                            fl[0]);
                    if (rows[1][m][0][an].done)
                        fprintf(g, " %.1f%% | %.2f | %.2f%% | %s | %d |\n", 100.0 * rows[1][m][0][an].err[1],
                                rows[1][m][0][an].err[1] / oracle_err[1][1], 100.0 * rows[1][m][0][an].vs_cpu, fl[1], ops);
                    else
                        fprintf(g, " - | - | - | - | %d |\n", ops);
                }
        }
        g = gg[0];
        fclose(gg[1]);
        fprintf(g, "\n![plane: reference and GPU frame](frame_plane.png)\n\nDetail (f16 storage, the box reference, the "
                   "CPU path at the driver's level of detail, the targets): the report's section \"The frame on a Vulkan "
                   "driver\" (docs/report.md).\n");
        fclose(g);
    }
    part_end(7);
    printf("frame: wrote %s/frame.md, frame.csv (%.1f s)\n", outdir, now_seconds() - t_start);
    {
        double c = 0.0, w = 0.0;
        printf("frame: CPU s / wall s by part (every thread, lavapipe's too):");
        for (k = 0; k < NPART; ++k) printf(" %s %.1f / %.1f;", part_name[k], part_cpu[k], part_wall[k]), c += part_cpu[k], w += part_wall[k];
        printf(" total %.1f / %.1f\n", c, w);
    }
    /* The plumbing check (it can fail): at the driver's own level of detail the CPU float path
       must reproduce the GPU's isotropic f32 LEADR frame (measured 2e-6 mean on lavapipe): a wrong
       texel layout, level upload, coordinate or frame convention shows here at once. */
    for (s = 0; s < 2; ++s)
        if (!(rows[s][MT_LEADR][0][0].vs_drv <= PLUMBING_BOUND)) {
            fprintf(stderr, "frame: FAILED plumbing check on the %s: GPU LEADR vs the CPU path at the driver's lod %.3g > %.0e\n",
                    scene_key[s], rows[s][MT_LEADR][0][0].vs_drv, PLUMBING_BOUND);
            return 1;
        }
    return 0;
}

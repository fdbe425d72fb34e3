/* pf_microsurface.h - synthetic microsurfaces and the brute-force shading reference that the
   library's filtered formulas are measured against (issue 9, "ground truth on real
   microsurfaces").

   PURPOSE
   Test and bench infrastructure, NOT part of the library: it lives in tests/, allocates, and
   computes in double and long double. It never calls anything from include/ (the library is
   what it checks), so it compiles in the float and the PF_DOUBLE builds alike and depends on
   no pf_real. C99 and C++11; every function is static; deterministic (own splitmix64 seeds).

   WHAT IT PROVIDES
   1. Periodic height maps (they tile exactly; w and h powers of two) of seven kinds:
        PFM_GAUSSIAN        isotropic Gaussian random field: a sum of random-phase waves on the
                            integer frequency lattice 2 pi (i/w, j/h) with a Gaussian spectrum
                            (autocorrelation ~ exp(-r^2 / L^2), L = corr_texels); heights and
                            slopes Gaussian;
        PFM_GAUSSIAN_FINE   the same generator with a fine default correlation length
                            (PFM_FINE_CORR_TEXELS = 3 texels against 12; same slope RMS), so
                            that a 16 x 16 footprint holds ~9 correlation areas pi L^2 and a
                            64 x 64 one ~145: the regime where LEADR's Gaussian fit of a
                            footprint's slopes is meant to hold. The price: at 3 texels the
                            bilinear surface the march sees is rougher than its central-
                            difference slopes say, so the reference loses ~1% (60 deg) to 3%
                            (75 deg) of the visible projected area that every view must see
                            (visible_area ~0.97 instead of 1; 2.5 texels: 4%; the tests
                            measure it);
        PFM_GAUSSIAN_ANISO  the same with different correlation lengths along a rotated frame
                            (slope RMS ratio aniso, frame angle);
        PFM_RIDGES          (1 - |g|)^2 of a unit Gaussian field g ("ridged" noise): sharp crests
                            where g = 0, steepest at the crests, slopes a scale mixture of
                            Gaussians (kurtosis ~ 8) correlated with height;
        PFM_CRATERS         random bowls with raised rims on a flat ground (the flat ground is
                            an atom of slope 0);
        PFM_TILES           square tiles with bevelled grooves (slopes on a few values);
        PFM_PEAKED          exp(a g) of a unit Gaussian field g (a = PFM_PEAKED_A = 0.36,
                            correlation length 6 texels): log-normal heights (a few tall
                            bumps on a low ground), slopes a scale mixture of Gaussians
                            (grad g times the log-normal a exp(a g)): unimodal, symmetric,
                            peaked and heavy-tailed like photographed textures, slope kurtosis
                            3 exp(4 a^2) = 5.1 (measured 5.0-5.2 on 512^2; gaussian 3,
                            ridges 9.4), and steeper where higher.
      Every kind is rescaled so that the RMS of the central-difference slopes is rms_slope
      (isotropic kinds: the mean of the x and y variances; ANISO: the x axis of the rotated
      frame, and the y axis is adjusted to aniso times it).
   2. Visibility by marching the bilinear, periodic height field (exact per cell, no sampling
      step): pfm_visible, pfm_visibility_map; and the same restricted to the occluders inside a
      footprint box: pfm_visible_box, pfm_visibility_map_box.
   3. The reference pixel (LEADR, Dupuy et al. 2013 eqs. 1-3): masking, joint visibility,
      specular radiance of a narrow Beckmann base lobe per texel, Lambertian radiance, and the
      visible mean of a per-texel attribute (Heitz & Neyret 2011 eq. 19, with the marched V).

   USAGE
     pfm_surface s;
     pfm_surface_make(&s, 512, 512, 1.0, pfm_params_default(PFM_GAUSSIAN));
     unsigned char *vo = malloc(512 * 512), *vi = malloc(512 * 512);
     pfm_visibility_map(&s, wo, vo);  pfm_visibility_map(&s, wi, vi);   -- once per direction
     pfm_shade r = pfm_reference_shade(&s, vo, vi, x0, y0, 64, wo, wi, 0.1, 1.0);
     ... r.spec, r.diffuse (radiance per unit light radiance, light cosine included) ...
     pfm_surface_free(&s);

   FUNCTIONS
     corpus       pfm_params_default, pfm_kind_name, pfm_surface_make, pfm_surface_free,
                  pfm_surface_alloc (zero heights, for hand-made surfaces), pfm_surface_bounds
     geometry     pfm_height, pfm_slope, pfm_normal, pfm_height_bilinear, pfm_footprint_moments
     visibility   pfm_visible, pfm_visibility_map, pfm_visible_skip (start skip as a parameter),
                  pfm_visible_box, pfm_visibility_map_box (in-footprint occluders only)
     reference    pfm_reference_shade, pfm_reference_shade_set (several visibility pairs in one
                  pass), pfm_reference_visible_mean
     base lobe    pfm_beckmann_lambda (long double), pfm_base_specular (the per-texel narrow lobe)

   CONVENTIONS
     Tangent frame of the macrosurface, +z up. Texel (x, y), 0 <= x < w, 0 <= y < h, row-major
     height[y w + x], world units; the texel's surface point is the node (x texel, y texel,
     height) of the bilinear height field (pf_moments.h puts texel centres at (x + 0.5) texel:
     a constant shift that changes nothing here). Periodic in both axes unless no_wrap is set.
     Slope of texel (x, y): central differences with wrap,
        sx = (h[x+1,y] - h[x-1,y]) / (2 texel),  sy = (h[x,y+1] - h[x,y-1]) / (2 texel),
     exactly level 0 of pf_slope_pyramid_from_heights(..., texel, texel, 1, PF_BORDER_WRAP, ..)
     (tests/test_microsurface.c checks it); micro-normal m = (-sx, -sy, 1)/sqrt(1 + sx^2 + sy^2).
     Directions w are unit vectors in the tangent frame.

   THE VISIBILITY MARCH (pfm_visible)
     A texel sees w when m.w > 0 and the ray from its node toward w leaves the height field
     (rises above hmax) without passing strictly below the bilinear interpolation of the
     nodes. The march walks the cells the ray crosses; in a cell the bilinear height along the
     ray is a quadratic of the horizontal distance, so the test "surface above the ray
     anywhere on this segment" is exact (end points and the vertex), with no sampling step.
     Start: the first half texel of horizontal distance is skipped. Why: the texel shades as
     the facet of its central-difference slope over its own half-texel neighbourhood, while
     the four bilinear patches around the node are twisted (the u v term): along a diagonal
     ray the patch height is a parabola, which can rise above a ray that clears the facet
     (m.w > 0) within the first half texel and fall back below it, an interpolation artefact
     that would be a false self-occlusion. Along an axis the patch is linear in the distance,
     so there the skip changes nothing: a ray flatter than the one-sided slope toward the
     neighbour stays under that patch for its whole length, which is genuine occlusion (a
     smooth surface through the same nodes also crosses the ray before the next node).
     Checked in the tests against a finely sampled continuous surface (the skip removes a
     sixth of the mismatches, all near-tangent rays; 0.3% remain), a plane (exact) and a
     wall's analytic shadow length (exact).
     The march stops as visible when the ray is above hmax, as occluded at the first cell
     where the surface rises above the ray, and gives up (occluded) after PFM_MAX_CELLS cells
     (a ray rising less than (hmax - hmin) / PFM_MAX_CELLS per texel: within ~1e-4 rad of the
     horizon on the corpus). Acceleration: when the ray is above the highest node of its
     PFM_BLOCK^2-cell block it jumps to the block's exit (exact: tested against the plain
     walk).
     no_wrap = 1 (hand-made surfaces only): a ray leaving the map escapes (visible).

   THE IN-FOOTPRINT REFERENCE (pfm_visible_box, pfm_visibility_map_box)
     The march above sees every occluder of the height field. When the footprint is smaller
     than the features, most shadows and masking come from bumps OUTSIDE the footprint, which
     no filtered model of the footprint's own statistics can know (in LEADR's pipeline those
     resolved-scale shadows come from the displaced geometry and shadow maps, Dupuy et al.
     2013 sec. 5). The in-footprint variant only counts occluders inside the footprint's box:
     the bilinear height field over [x0 - 1/2, x0 + n - 1/2] x [y0 - 1/2, y0 + n - 1/2] (every
     texel its node's half-texel neighbourhood: the n^2 area the footprint covers; the
     central-difference slopes of its edge texels read the ring of nodes just outside, and so
     does this surface). The march is pfm_visible's (same start skip, same exact per-cell
     test) stopped as visible where the ray's horizontal path leaves the box. So a 1-texel
     footprint has self-masking (m.w <= 0) and, rarely, occlusion by the corners of its own
     square (diagonal rays, horizontal distance 0.5 to 0.71 past the skip); an empty box
     (n = 0) only self-masking; a box as large as the map is pfm_visible.
     Passing the in-footprint maps to pfm_reference_shade gives the "in-footprint reference":
     what a filtered model of the footprint can represent. Box-visible is implied by visible.

   THE REFERENCE (pfm_reference_shade): n x n texels from (x0, y0), wrapping, box filter
   (LEADR eq. 2 with k_P uniform). Per texel t (slope s_t, normal m_t, V_o/V_i from the maps):
     a_t(w)  = (m_t.w)/(m_t.z) = w.z - s_t.(w.x, w.y)          projected area (eq. 1)
     A       = sum_t a_t(wo)          = n^2 (nbar.wo)/(nbar.z) exactly (eq. 1)
     spec    = sum_t V_o V_i F(h.wi) D_t(h) G2_t / 4 / A                        (eqs. 2-3, 16-17)
               D_t  = P22(slope(h) - s_t; base_sigma^2 I) / h.z^4 (eq. 10): the narrow Beckmann
                      base lobe centred on the texel's slope, the base roughness LEADR adds
                      to the covariance;
               G2_t = 1/(1 + Lambda_t(wo) + Lambda_t(wi)) (eq. 13), Lambda of that lobe
                      (noncentered nu of eqs. 14-15): the sub-texel masking the march cannot
                      see; 0 when either direction is below the texel's facet;
               F    = Schlick, f0 (f0 = 1: F = 1), cosine h.wi.
     diffuse = sum_t V_o V_i (1/pi) <m_t,wo><m_t,wi>/(m_t.z) / A                (eqs. 2-3)
     masking = sum_t V_o a_t(wo)+ / sum_t a_t(wo)+          (x+ = max(x, 0))
     joint   = sum_t V_o V_i a_t(wo)+ / sum_t a_t(wo)+
               the visible fraction of the front-facing projected micro-area: Smith's G1 =
               1/(1 + Lambda_o) and LEADR's E[V_o V_i] = 1/(1 + Lambda_o + Lambda_i) (eq. 13)
               estimate these (the uncorrelation of V and a_t, LEADR sec. 3). NOTE: not "/ A"
               as first drafted in pfm_api.md: sum_t V_o a_t(wo)+ / A is ~1 for any surface
               (every viewing ray meets exactly one visible point); it is returned as
               visible_area, a consistency check of the march.
     area    = A / n^2 (the mean projected area, (nbar.wo)/(nbar.z));
     front_area = sum_t a_t(wo)+ / n^2 (Smith: area (1 + Lambda_o) for a large footprint)
     Same conventions as pf_leadr_specular: radiance per unit light radiance with the light's
     cosine included; a flat footprint gives F D G2 / (4 cos theta_o) for spec and
     cos theta_i / pi for diffuse. A footprint whose mean plane faces away (A <= 0) gives
     spec = diffuse = visible_area = 0 (masking and joint stay defined while some texel faces
     wo). vis_o or vis_i may be NULL: every texel counts as visible for that direction.

   ACCURACY AND COST (measured by tests/test_microsurface.c, whose notes print the numbers)
     Slopes equal the library pyramid's level 0 to rounding. Planar footprints: the reference
     spec equals pf_leadr_specular (where LEADR is exact) to ~40 pf_real eps, the flat-plane
     closed forms to ~5e-13. Gaussian maps: the visible fraction of the front-facing
     projected area agrees with Smith's 1/(1 + Lambda) to < 1% up to 75 degrees (256^2 map;
     ~0.1% on 512^2), visible_area = 1 within 0.2%; on PFM_GAUSSIAN_FINE G1 is 3% below Smith at
     75 degrees and visible_area 3% below 1: the same deficit (their ratio is within 0.2%).
     In-footprint march: exact against a wall's analytic shadow through random boxes, no
     mismatch with a 0.01-texel sampled march over 2500 rays, box maps never drop a texel the
     full map sees. Cost on one core (x86-64, -O2, 512^2
     corpus maps): a visibility map 0.01-0.4 s per direction (the block-max grid skips
     blocks the ray is already above; ridges at 85 degrees are the slowest); a 64 x 64
     reference footprint ~1 ms with the maps given (~250 ns per texel: exp and erfc of the
     base lobe); generating a map 5-300 ms (ANISO regenerates a few times to hit aniso).

   SOURCES
     Dupuy, Heitz, Iehl, Poulin, Neyret, Ostromoukhov 2013 (LEADR) eqs. 1-3, 8-10, 13-17;
     Heitz & Neyret 2011 eq. 19 (visible attribute mean) and sec. 4 (visible points are
     higher); Smith 1967 (Lambda); Schlick 1994 (Fresnel). */
#ifndef PF_MICROSURFACE_H
#define PF_MICROSURFACE_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__) || defined(__clang__)
#  define PFM_FN static __attribute__((unused))
#else
#  define PFM_FN static
#endif

#define PFM_PI 3.14159265358979323846
#define PFM_PIL 3.14159265358979323846264338327950288L
/* march cap: a ray that crosses this many cells without leaving the height field is taken
   as occluded (it rises less than (hmax - hmin) / PFM_MAX_CELLS per texel) */
#ifndef PFM_MAX_CELLS
#  define PFM_MAX_CELLS 1000000
#endif
/* block size (cells) of the march's max grid; a ray above a block's highest node crosses
   the block in one step */
#ifndef PFM_BLOCK
#  define PFM_BLOCK 8
#endif
/* default correlation length of PFM_GAUSSIAN_FINE, texels */
#ifndef PFM_FINE_CORR_TEXELS
#  define PFM_FINE_CORR_TEXELS 3.0
#endif

/* PFM_PEAKED: heights exp(PFM_PEAKED_A g), g a unit Gaussian field */
#ifndef PFM_PEAKED_A
#  define PFM_PEAKED_A 0.36
#endif

/* kinds; PFM_GAUSSIAN_FINE (added last, so the earlier values keep their numbers) is the
   isotropic Gaussian generator with a fine correlation length (pfm_params_default: 3 texels
   against 12), so that footprints of 256-4096 texels hold tens to hundreds of features: the
   regime the filtering papers claim */
enum { PFM_GAUSSIAN = 0, PFM_GAUSSIAN_ANISO, PFM_RIDGES, PFM_CRATERS, PFM_TILES, PFM_GAUSSIAN_FINE,
       PFM_PEAKED, PFM_KIND_COUNT };

typedef struct {
    int kind;           /* PFM_* */
    unsigned seed;
    double rms_slope;   /* target RMS of each slope component (ANISO: the x axis of the rotated
                           frame gets rms_slope, its y axis rms_slope * aniso) */
    double corr_texels; /* correlation length (Gaussian spectrum width) in texels; crater mean
                           radius; tiles: period = the power of two in (1.5, 3] x this */
    double aniso;       /* ANISO: slope RMS ratio y/x in the rotated frame (e.g. 0.3) */
    double angle;       /* ANISO: rotation of the anisotropy frame, radians */
} pfm_params;

typedef struct {
    int w, h;
    double texel;     /* world units per texel */
    double *height;   /* w*h heights, world units, row-major */
    double hmin, hmax; /* bounds (march early-out); pfm_surface_bounds recomputes them */
    int no_wrap;      /* 0: periodic (pfm_surface_make). 1: an isolated patch, rays leaving the
                         map escape (hand-made test surfaces); slopes still wrap. */
    /* march acceleration, owned by the surface (pfm_surface_bounds builds it, pfm_surface_free
       releases it; NULL = none): the highest node of each PFM_BLOCK x PFM_BLOCK block of cells
       (nodes on the block's far edges included), bw x bh blocks */
    double *block_max;
    int bw, bh;
} pfm_surface;

/* spec, diffuse: radiance per unit light radiance (light cosine included). masking, joint:
   the visible fractions of the front-facing projected area (G1 and E[V_o V_i] of the
   footprint, comparable with 1/(1 + Lambda_o) and 1/(1 + Lambda_o + Lambda_i)). area: the
   mean projected area A/n^2 = (nbar.wo)/(nbar.z). Fields after area are additions. */
typedef struct {
    double spec, diffuse, masking, joint, area;
    double front_area;   /* sum_t a_t(wo)+ / n^2: projected front-facing micro-area (~ A (1 + Lambda)) */
    double visible_area; /* sum_t V_o a_t(wo)+ / A: ~1 (each viewing ray meets one visible point) */
} pfm_shade;

/* ================================================================ seeded random numbers */
typedef struct {
    unsigned long long state;
} pfm_rng;

PFM_FN unsigned long long pfm_rng_next(pfm_rng *r)
{
    unsigned long long z = (r->state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/* uniform in [0, 1) */
PFM_FN double pfm_rng_uniform(pfm_rng *r)
{
    return (double)(pfm_rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
}

/* ================================================================ corpus parameters */

/* Corpus defaults per kind: RMS slope 0.3-0.45 (masking matters from ~60 degrees on) and
   features of 8-16 texels (a 1-texel footprint is nearly planar, 64 x 64 spans several). */
PFM_FN pfm_params pfm_params_default(int kind)
{
    pfm_params p;
    p.kind = kind;
    p.seed = 1234u + 17u * (unsigned)kind;
    p.rms_slope = 0.4;
    p.corr_texels = 12.0;
    p.aniso = 1.0;
    p.angle = 0.0;
    switch (kind) {
    case PFM_GAUSSIAN_ANISO:
        p.rms_slope = 0.45;
        p.aniso = 0.3;
        p.angle = 0.5;
        break;
    case PFM_RIDGES:
        p.rms_slope = 0.35;
        p.corr_texels = 16.0;
        break;
    case PFM_CRATERS:
        p.rms_slope = 0.35;
        p.corr_texels = 12.0;
        break;
    case PFM_TILES:
        p.rms_slope = 0.3;
        p.corr_texels = 16.0;
        break;
    case PFM_GAUSSIAN_FINE:
        p.corr_texels = PFM_FINE_CORR_TEXELS;
        break;
    case PFM_PEAKED:
        p.rms_slope = 0.35;
        p.corr_texels = 6.0;
        break;
    default:
        break;
    }
    return p;
}

PFM_FN const char *pfm_kind_name(int kind)
{
    switch (kind) {
    case PFM_GAUSSIAN: return "gaussian";
    case PFM_GAUSSIAN_ANISO: return "gaussian_aniso";
    case PFM_RIDGES: return "ridges";
    case PFM_CRATERS: return "craters";
    case PFM_TILES: return "tiles";
    case PFM_GAUSSIAN_FINE: return "gaussian_fine";
    case PFM_PEAKED: return "peaked";
    default: return "unknown";
    }
}

/* ================================================================ surface storage, geometry */

/* w x h zero heights, periodic, texel world units; 0 on success, -1 on bad size or no memory. */
PFM_FN int pfm_surface_alloc(pfm_surface *s, int w, int h, double texel)
{
    memset(s, 0, sizeof *s);
    if (w < 1 || h < 1 || !(texel > 0.0)) return -1;
    s->height = (double *)calloc((size_t)w * (size_t)h, sizeof(double));
    if (!s->height) return -1;
    s->w = w;
    s->h = h;
    s->texel = texel;
    return 0;
}

PFM_FN void pfm_surface_free(pfm_surface *s)
{
    free(s->height);
    free(s->block_max);
    s->height = NULL;
    s->block_max = NULL;
    s->w = s->h = 0;
}

/* Recompute hmin, hmax and the march's block maxima after editing the heights by hand (the
   visibility functions read them). Without memory for the blocks the march just runs
   unaccelerated. */
PFM_FN void pfm_surface_bounds(pfm_surface *s)
{
    long long i, n = (long long)s->w * s->h;
    double lo = s->height[0], hi = s->height[0];
    int bx, by, x, y;
    for (i = 1; i < n; ++i) {
        if (s->height[i] < lo) lo = s->height[i];
        if (s->height[i] > hi) hi = s->height[i];
    }
    s->hmin = lo;
    s->hmax = hi;
    free(s->block_max);
    s->bw = (s->w + PFM_BLOCK - 1) / PFM_BLOCK;
    s->bh = (s->h + PFM_BLOCK - 1) / PFM_BLOCK;
    s->block_max = (double *)malloc((size_t)s->bw * (size_t)s->bh * sizeof(double));
    if (!s->block_max) return;
    for (by = 0; by < s->bh; ++by)
        for (bx = 0; bx < s->bw; ++bx) {
            double m = -HUGE_VAL;
            /* cells bx*B .. bx*B+B-1 use nodes bx*B .. bx*B+B (wrapping) */
            for (y = by * PFM_BLOCK; y <= by * PFM_BLOCK + PFM_BLOCK; ++y)
                for (x = bx * PFM_BLOCK; x <= bx * PFM_BLOCK + PFM_BLOCK; ++x) {
                    double v = s->height[(size_t)(y % s->h) * s->w + (size_t)(x % s->w)];
                    if (v > m) m = v;
                }
            s->block_max[(size_t)by * s->bw + bx] = m;
        }
}

/* wrap any integer into [0, n) */
PFM_FN int pfmi_wrap(int i, int n)
{
    i %= n;
    return i < 0 ? i + n : i;
}

PFM_FN double pfm_height(const pfm_surface *s, int x, int y)
{
    return s->height[(size_t)pfmi_wrap(y, s->h) * (size_t)s->w + (size_t)pfmi_wrap(x, s->w)];
}

/* Central-difference slope of texel (x, y) with wrap (any integer x, y). */
PFM_FN void pfm_slope(const pfm_surface *s, int x, int y, double *sx, double *sy)
{
    double k = 1.0 / (2.0 * s->texel);
    *sx = k * (pfm_height(s, x + 1, y) - pfm_height(s, x - 1, y));
    *sy = k * (pfm_height(s, x, y + 1) - pfm_height(s, x, y - 1));
}

PFM_FN void pfm_normal(const pfm_surface *s, int x, int y, double m[3])
{
    double sx, sy, r;
    pfm_slope(s, x, y, &sx, &sy);
    r = 1.0 / sqrt(1.0 + sx * sx + sy * sy);
    m[0] = -sx * r;
    m[1] = -sy * r;
    m[2] = r;
}

/* Bilinear periodic height at (px, py) in texel units (node (x, y) at (x, y)). */
PFM_FN double pfm_height_bilinear(const pfm_surface *s, double px, double py)
{
    double fx = floor(px), fy = floor(py), u = px - fx, v = py - fy;
    int ix = (int)fx, iy = (int)fy;
    double h00 = pfm_height(s, ix, iy), h10 = pfm_height(s, ix + 1, iy);
    double h01 = pfm_height(s, ix, iy + 1), h11 = pfm_height(s, ix + 1, iy + 1);
    return (h00 * (1.0 - u) + h10 * u) * (1.0 - v) + (h01 * (1.0 - u) + h11 * u) * v;
}

/* Raw slope moments E[x], E[y], E[x^2], E[y^2], E[xy] of the n x n footprint at (x0, y0)
   (wrapping; box filter), in double: what the library's pyramid holds at level log2(n). */
PFM_FN void pfm_footprint_moments(const pfm_surface *s, int x0, int y0, int n, double m[5])
{
    int i, j;
    double a[5] = {0.0, 0.0, 0.0, 0.0, 0.0}, inv = 1.0 / ((double)n * (double)n);
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            double sx, sy;
            pfm_slope(s, x0 + i, y0 + j, &sx, &sy);
            a[0] += sx;
            a[1] += sy;
            a[2] += sx * sx;
            a[3] += sy * sy;
            a[4] += sx * sy;
        }
    for (i = 0; i < 5; ++i) m[i] = a[i] * inv;
}

/* ================================================================ generators */

/* In-place radix-2 complex FFT of n (power of 2) points at stride, sign +1 or -1, no scaling. */
PFM_FN void pfmi_fft(double *re, double *im, int n, int sign)
{
    int i, j, len;
    for (i = 1, j = 0; i < n; ++i) { /* bit reversal */
        int bit = n >> 1;
        for (; j & bit; bit >>= 1) j ^= bit;
        j ^= bit;
        if (i < j) {
            double t = re[i];
            re[i] = re[j];
            re[j] = t;
            t = im[i];
            im[i] = im[j];
            im[j] = t;
        }
    }
    for (len = 2; len <= n; len <<= 1) {
        double ang = (double)sign * 2.0 * PFM_PI / (double)len;
        int half = len / 2, k;
        for (k = 0; k < half; ++k) {
            double wr = cos(ang * (double)k), wi = sin(ang * (double)k);
            for (i = k; i < n; i += len) {
                double xr = re[i + half] * wr - im[i + half] * wi;
                double xi = re[i + half] * wi + im[i + half] * wr;
                re[i + half] = re[i] - xr;
                im[i + half] = im[i] - xi;
                re[i] += xr;
                im[i] += xi;
            }
        }
    }
}

PFM_FN int pfmi_is_pow2(int n) { return n > 0 && (n & (n - 1)) == 0; }

/* Real part of sum over the frequency lattice of amp(k) exp(i (k.x + phase_k)):
   amp(k) = exp(-(ku^2 Lu^2 + kv^2 Lv^2) / 8) in the frame rotated by angle (the square root
   of the Gaussian power spectrum of autocorrelation exp(-u^2/Lu^2 - v^2/Lv^2)); phases from
   the seed, drawn in a fixed order so equal seeds give equal phases whatever Lu, Lv.
   out: w h doubles. Returns 0, or -1 without memory. */
PFM_FN int pfmi_gaussian_field(int w, int h, double Lu, double Lv, double angle, unsigned seed,
                               double *out)
{
    size_t n = (size_t)w * (size_t)h;
    double *re = (double *)malloc(n * sizeof(double)), *im = (double *)malloc(n * sizeof(double));
    double *tr = (double *)malloc((size_t)(w > h ? w : h) * 2 * sizeof(double)), *ti;
    double ca = cos(angle), sa = sin(angle);
    pfm_rng rng;
    int x, y;
    if (!re || !im || !tr) {
        free(re);
        free(im);
        free(tr);
        return -1;
    }
    ti = tr + (w > h ? w : h);
    rng.state = 0x5EEDULL * 0x100000001ULL + (unsigned long long)seed;
    for (y = 0; y < h; ++y) {
        double ky = 2.0 * PFM_PI * (double)(y < h / 2 ? y : y - h) / (double)h;
        for (x = 0; x < w; ++x) {
            double kx = 2.0 * PFM_PI * (double)(x < w / 2 ? x : x - w) / (double)w;
            double ku = ca * kx + sa * ky, kv = -sa * kx + ca * ky;
            double phase = 2.0 * PFM_PI * pfm_rng_uniform(&rng);
            double amp = (x == 0 && y == 0) ? 0.0 : exp(-(ku * ku * Lu * Lu + kv * kv * Lv * Lv) / 8.0);
            re[(size_t)y * w + x] = amp * cos(phase);
            im[(size_t)y * w + x] = amp * sin(phase);
        }
    }
    for (y = 0; y < h; ++y) pfmi_fft(re + (size_t)y * w, im + (size_t)y * w, w, 1);
    for (x = 0; x < w; ++x) {
        for (y = 0; y < h; ++y) {
            tr[y] = re[(size_t)y * w + x];
            ti[y] = im[(size_t)y * w + x];
        }
        pfmi_fft(tr, ti, h, 1);
        for (y = 0; y < h; ++y) re[(size_t)y * w + x] = tr[y];
    }
    for (x = 0; (size_t)x < n; ++x) out[x] = re[x];
    free(re);
    free(im);
    free(tr);
    return 0;
}

/* Mean of the squared central-difference slopes along the unit axis (c, s), heights in
   texel units. */
PFM_FN double pfmi_slope_var(const double *hh, int w, int h, double c, double sn)
{
    int x, y;
    double acc = 0.0;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double sx = 0.5 * (hh[(size_t)y * w + (size_t)((x + 1) % w)] - hh[(size_t)y * w + (size_t)((x + w - 1) % w)]);
            double sy = 0.5 * (hh[(size_t)((y + 1) % h) * w + x] - hh[(size_t)((y + h - 1) % h) * w + x]);
            double t = c * sx + sn * sy;
            acc += t * t;
        }
    return acc / ((double)w * (double)h);
}

/* crater profile of rho = r / R (times R): a parabolic bowl of depth 0.6 R inside rho < 1
   plus a raised rim, a cos^2 bump of height 0.25 R on rho in [0.5, 1.5]; 0 beyond. */
PFM_FN double pfmi_crater_profile(double rho)
{
    double v = 0.0;
    if (rho < 1.0) v += 0.6 * (rho * rho - 1.0);
    if (rho > 0.5 && rho < 1.5) {
        double c = cos(PFM_PI * (rho - 1.0));
        v += 0.25 * c * c;
    }
    return v;
}

/* tile profile of a coordinate u over a period P: 0 on the tile top, a bevel of width bw
   down to a groove bottom of half-width gb at u = 0 (mod P), depth bw (slope 1). */
PFM_FN double pfmi_tile_profile(double u, double P, double bw, double gb)
{
    double d = fmod(u, P);
    if (d < 0.0) d += P;
    if (P - d < d) d = P - d;
    if (d < gb) return -bw;
    if (d < gb + bw) return -bw + (d - gb);
    return 0.0;
}

/* Generate s (w, h powers of 2; texel world units per texel) from p. 0 on success, -1 on
   bad arguments or no memory (s is then empty). */
PFM_FN int pfm_surface_make(pfm_surface *s, int w, int h, double texel, pfm_params p)
{
    size_t n = (size_t)w * (size_t)h, i;
    double *hh;
    double scale = 1.0;
    int x, y;
    if (!pfmi_is_pow2(w) || !pfmi_is_pow2(h) || w < 4 || h < 4 || !(p.rms_slope > 0.0) ||
        !(p.corr_texels > 0.0) || p.kind < 0 || p.kind >= PFM_KIND_COUNT) {
        memset(s, 0, sizeof *s);
        return -1;
    }
    if (pfm_surface_alloc(s, w, h, texel) != 0) return -1;
    hh = s->height; /* texel units until the end */
    switch (p.kind) {
    case PFM_GAUSSIAN:
    case PFM_GAUSSIAN_FINE: /* the same generator; only the default correlation length differs */
        if (pfmi_gaussian_field(w, h, p.corr_texels, p.corr_texels, 0.0, p.seed, hh) != 0) goto fail;
        scale = p.rms_slope / sqrt(0.5 * (pfmi_slope_var(hh, w, h, 1.0, 0.0) + pfmi_slope_var(hh, w, h, 0.0, 1.0)));
        break;
    case PFM_GAUSSIAN_ANISO: {
        /* slope RMS along v / along u ~ Lu / Lv; a few secant-free fixed-point corrections
           (same phases) make the measured ratio equal aniso */
        double Lu = p.corr_texels, Lv = p.corr_texels / (p.aniso > 0.0 ? p.aniso : 1.0);
        double ca = cos(p.angle), sa = sin(p.angle);
        int it;
        for (it = 0; it < 6; ++it) {
            double vu, vv, ratio;
            if (pfmi_gaussian_field(w, h, Lu, Lv, p.angle, p.seed, hh) != 0) goto fail;
            vu = pfmi_slope_var(hh, w, h, ca, sa);
            vv = pfmi_slope_var(hh, w, h, -sa, ca);
            ratio = sqrt(vv / vu);
            scale = p.rms_slope / sqrt(vu);
            if (fabs(ratio / p.aniso - 1.0) < 1e-4) break;
            Lv *= ratio / p.aniso;
        }
        break;
    }
    case PFM_RIDGES: {
        double acc = 0.0;
        if (pfmi_gaussian_field(w, h, p.corr_texels, p.corr_texels, 0.0, p.seed, hh) != 0) goto fail;
        for (i = 0; i < n; ++i) acc += hh[i] * hh[i];
        acc = 1.0 / sqrt(acc / (double)n);
        for (i = 0; i < n; ++i) {
            double t = 1.0 - fabs(hh[i] * acc);
            hh[i] = t * t;
        }
        scale = p.rms_slope / sqrt(0.5 * (pfmi_slope_var(hh, w, h, 1.0, 0.0) + pfmi_slope_var(hh, w, h, 0.0, 1.0)));
        break;
    }
    case PFM_CRATERS: {
        /* ~40% of the area within 1.5 R of a crater centre; radii uniform in [0.6, 1.4] L,
           capped so a crater (extent 1.5 R) fits in half the map */
        pfm_rng rng;
        double L = p.corr_texels, area = 0.0;
        int k, count;
        rng.state = 0xC7A7E2ULL * 0x100000001ULL + (unsigned long long)p.seed;
        if (1.5 * 1.4 * L > 0.5 * (double)(w < h ? w : h)) L = 0.5 * (double)(w < h ? w : h) / (1.5 * 1.4);
        area = PFM_PI * 2.25 * L * L * (1.0 + 0.16 / 3.0); /* E[(1.5 R)^2] pi */
        count = (int)(0.5 + 0.4 * (double)n / area);
        if (count < 1) count = 1;
        for (k = 0; k < count; ++k) {
            double cx = (double)w * pfm_rng_uniform(&rng), cy = (double)h * pfm_rng_uniform(&rng);
            double R = L * (0.6 + 0.8 * pfm_rng_uniform(&rng));
            int r = (int)ceil(1.5 * R) + 1, dx, dy;
            for (dy = -r; dy <= r; ++dy)
                for (dx = -r; dx <= r; ++dx) {
                    int gx = (int)floor(cx) + dx, gy = (int)floor(cy) + dy;
                    double ex = (double)gx - cx, ey = (double)gy - cy;
                    double rho = sqrt(ex * ex + ey * ey) / R;
                    if (rho < 1.5)
                        hh[(size_t)pfmi_wrap(gy, h) * w + (size_t)pfmi_wrap(gx, w)] += R * pfmi_crater_profile(rho);
                }
        }
        scale = p.rms_slope / sqrt(0.5 * (pfmi_slope_var(hh, w, h, 1.0, 0.0) + pfmi_slope_var(hh, w, h, 0.0, 1.0)));
        break;
    }
    case PFM_PEAKED: {
        /* exp(a g) of a unit Gaussian field g: the slope a exp(a g) grad g is grad g (Gaussian,
           independent of g at the same point) times a log-normal scale, a scale mixture of
           Gaussians: unimodal, symmetric, slope kurtosis 3 exp(4 a^2) for a smooth field */
        double acc = 0.0;
        if (pfmi_gaussian_field(w, h, p.corr_texels, p.corr_texels, 0.0, p.seed, hh) != 0) goto fail;
        for (i = 0; i < n; ++i) acc += hh[i] * hh[i];
        acc = 1.0 / sqrt(acc / (double)n);
        for (i = 0; i < n; ++i) hh[i] = exp(PFM_PEAKED_A * hh[i] * acc);
        scale = p.rms_slope / sqrt(0.5 * (pfmi_slope_var(hh, w, h, 1.0, 0.0) + pfmi_slope_var(hh, w, h, 0.0, 1.0)));
        break;
    }
    default: { /* PFM_TILES: period P = the power of two in (1.5 L, 3 L] (at most the map) */
        int P = 4;
        double bw, gb;
        while (P < w && P < h && (double)(2 * P) <= 2.0 * p.corr_texels * 1.5) P *= 2;
        bw = (double)P / 8.0;
        gb = (double)P / 32.0;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                double a = pfmi_tile_profile((double)x, (double)P, bw, gb);
                double b = pfmi_tile_profile((double)y, (double)P, bw, gb);
                hh[(size_t)y * w + x] = a < b ? a : b;
            }
        scale = p.rms_slope / sqrt(0.5 * (pfmi_slope_var(hh, w, h, 1.0, 0.0) + pfmi_slope_var(hh, w, h, 0.0, 1.0)));
        break;
    }
    }
    if (!(scale > 0.0 && scale < 1e300)) goto fail; /* a flat map cannot be rescaled */
    for (i = 0; i < n; ++i) hh[i] *= scale * texel;
    pfm_surface_bounds(s);
    return 0;
fail:
    pfm_surface_free(s);
    return -1;
}

/* ================================================================ visibility */

/* The march of pfm_visible with the skipped start distance tskip (texels of horizontal
   distance) and an escape distance tend: the ray counts as free (visible) once its horizontal
   distance reaches tend (1e300: never; pfm_visible_box passes the distance to the footprint
   box's edge). Only the part of each cell's segment before tend is tested. */
PFM_FN int pfmi_march(const pfm_surface *s, int x, int y, const double w[3], double tskip, double tend)
{
    const int W = s->w, H = s->h;
    const double *hp = s->height;
    double sx, sy, rxy, dx, dy, rise, h0, t, top;
    double tdx, tdy, tnx, tny;
    int ix, iy, stepx, stepy, cells;
    if (!(w[2] > 0.0)) return 0;
    pfm_slope(s, x, y, &sx, &sy);
    if (!(w[2] - sx * w[0] - sy * w[1] > 0.0)) return 0; /* m.w <= 0: back-facing */
    rxy = sqrt(w[0] * w[0] + w[1] * w[1]);
    x = pfmi_wrap(x, W);
    y = pfmi_wrap(y, H);
    h0 = hp[(size_t)y * W + x] / s->texel; /* texel units from here on */
    top = s->hmax / s->texel;
    if (!(rxy > 0.0) || h0 >= top) return 1; /* straight up, or the highest point */
    dx = w[0] / rxy;
    dy = w[1] / rxy;
    rise = w[2] / rxy; /* height gained per texel of horizontal distance */
    /* cell walk (Amanatides & Woo in 2D): the ray is at (x + dx t, y + dy t, h0 + rise t);
       cell (ix, iy) spans [ix, ix+1] x [iy, iy+1]; tnx, tny: t of the next x, y grid line */
    stepx = dx > 0.0 ? 1 : -1;
    stepy = dy > 0.0 ? 1 : -1;
    ix = dx >= 0.0 ? x : x - 1;
    iy = dy >= 0.0 ? y : y - 1;
    /* a ray parallel to a grid axis never crosses its lines: 1e300 stands for never (no
       infinities, so -ffast-math builds keep the comparisons) */
    tdx = fabs(dx) > 1e-300 ? 1.0 / fabs(dx) : 1e300;
    tdy = fabs(dy) > 1e-300 ? 1.0 / fabs(dy) : 1e300;
    if (!(fabs(dx) > 1e-300)) dx = 0.0;
    if (!(fabs(dy) > 1e-300)) dy = 0.0;
    tnx = tdx;
    tny = tdy;
    t = 0.0;
    for (cells = 0; cells < PFM_MAX_CELLS; ++cells) {
        double tout, ta, len, zray = h0 + rise * t;
        if (zray > top || t >= tend) return 1;
        if (s->no_wrap && (ix < 0 || iy < 0 || ix >= W - 1 || iy >= H - 1)) return 1;
        if (s->block_max && (W % PFM_BLOCK) == 0 && (H % PFM_BLOCK) == 0) {
            /* the ray only rises: if its height here is above the block's highest node, no
               cell of the block can occlude it; jump to where it leaves the block and restart
               the cell walk there (rounding at the block face only re-tests a cell) */
            int bx = pfmi_wrap(ix, W) / PFM_BLOCK, by = pfmi_wrap(iy, H) / PFM_BLOCK;
            if (zray * s->texel > s->block_max[(size_t)by * s->bw + bx]) {
                int ox = ix - pfmi_wrap(ix, W) % PFM_BLOCK, oy = iy - pfmi_wrap(iy, H) % PFM_BLOCK;
                double ex = dx > 0.0 ? ((double)(ox + PFM_BLOCK) - (double)x) / dx
                                     : (dx < 0.0 ? ((double)ox - (double)x) / dx : 1e300);
                double ey = dy > 0.0 ? ((double)(oy + PFM_BLOCK) - (double)y) / dy
                                     : (dy < 0.0 ? ((double)oy - (double)y) / dy : 1e300);
                double tb = ex < ey ? ex : ey, px, py;
                if (tb > t) {
                    t = tb;
                    px = (double)x + dx * t;
                    py = (double)y + dy * t;
                    /* the cell the ray enters: nudge along the motion before flooring */
                    ix = (int)floor(px + (dx > 0.0 ? 1e-9 : (dx < 0.0 ? -1e-9 : 0.0)));
                    iy = (int)floor(py + (dy > 0.0 ? 1e-9 : (dy < 0.0 ? -1e-9 : 0.0)));
                    tnx = dx > 0.0 ? ((double)(ix + 1) - (double)x) / dx
                                   : (dx < 0.0 ? ((double)ix - (double)x) / dx : 1e300);
                    tny = dy > 0.0 ? ((double)(iy + 1) - (double)y) / dy
                                   : (dy < 0.0 ? ((double)iy - (double)y) / dy : 1e300);
                    continue;
                }
            }
        }
        tout = tnx < tny ? tnx : tny;
        ta = t > tskip ? t : tskip;
        len = (tout < tend ? tout : tend) - ta;
        if (len > 0.0) {
            int cx = pfmi_wrap(ix, W), cy = pfmi_wrap(iy, H);
            int cx1 = cx + 1 == W ? 0 : cx + 1, cy1 = cy + 1 == H ? 0 : cy + 1;
            double h00 = hp[(size_t)cy * W + cx] / s->texel, h10 = hp[(size_t)cy * W + cx1] / s->texel;
            double h01 = hp[(size_t)cy1 * W + cx] / s->texel, h11 = hp[(size_t)cy1 * W + cx1] / s->texel;
            double u = (double)x + dx * ta - (double)ix, v = (double)y + dy * ta - (double)iy;
            double gx = h10 - h00, gy = h01 - h00, k = h11 - h10 - h01 + h00;
            /* f(tau) = surface - ray on [ta, ta + len] = f0 + b tau + c tau^2 */
            double f0 = h00 + gx * u + gy * v + k * u * v - (h0 + rise * ta);
            double b = gx * dx + gy * dy + k * (u * dy + v * dx) - rise;
            double c = k * dx * dy;
            double f1 = f0 + len * (b + c * len);
            double eps = 1e-12 * (1.0 + fabs(h0) + rise * ta);
            if (f0 > eps || f1 > eps) return 0;
            if (c < 0.0) {
                double tv = -b / (2.0 * c);
                if (tv > 0.0 && tv < len && f0 - b * b / (4.0 * c) > eps) return 0;
            }
        }
        t = tout;
        if (tnx < tny) {
            tnx += tdx;
            ix += stepx;
        } else {
            tny += tdy;
            iy += stepy;
        }
    }
    return 0;
}

/* pfm_visible with the skipped start distance tskip (texels of horizontal distance) as a
   parameter: 0.5 is the reference's rule; the tests compare other values. */
PFM_FN int pfm_visible_skip(const pfm_surface *s, int x, int y, const double w[3], double tskip)
{
    return pfmi_march(s, x, y, w, tskip, 1e300);
}

/* 1 if texel (x, y)'s node sees direction w (unit, tangent frame): m.w > 0 and the ray
   leaves the bilinear height field; see THE VISIBILITY MARCH. 0 for w.z <= 0. */
PFM_FN int pfm_visible(const pfm_surface *s, int x, int y, const double w[3])
{
    return pfm_visible_skip(s, x, y, w, 0.5);
}

/* Visibility of every texel for direction w: vis[y w + x] in {0, 1} (caller's w h bytes). */
PFM_FN void pfm_visibility_map(const pfm_surface *s, const double w[3], unsigned char *vis)
{
    int x, y;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) vis[(size_t)y * s->w + x] = (unsigned char)pfm_visible(s, x, y, w);
}

/* In-footprint visibility: pfm_visible with only the occluders inside the footprint box of
   n x n texels from (x0, y0) (wrapping), i.e. the bilinear height field over the region
   [x0 - 1/2, x0 + n - 1/2] x [y0 - 1/2, y0 + n - 1/2] (each texel its node's half-texel
   neighbourhood, the area the footprint covers); a ray that leaves the box is visible. See
   THE IN-FOOTPRINT REFERENCE. Along an axis where n >= the map's size the box is the whole
   (periodic) surface: no limit. (x, y) should lie in the box; a texel outside it meets no
   occluder (only the facet test m.w > 0 applies). */
PFM_FN int pfm_visible_box(const pfm_surface *s, int x, int y, const double w[3], int x0, int y0, int n)
{
    double rxy = sqrt(w[0] * w[0] + w[1] * w[1]), tend = 1e300;
    if (n < 1) return pfmi_march(s, x, y, w, 0.5, 0.0); /* an empty box: no occluder */
    if (rxy > 0.0) {
        double dx = w[0] / rxy, dy = w[1] / rxy;
        /* the texel's offsets in the box; the box edges are at -ox - 1/2 and n - ox - 1/2
           from its node */
        int ox = pfmi_wrap(x - x0, s->w), oy = pfmi_wrap(y - y0, s->h);
        if ((n < s->w && ox >= n) || (n < s->h && oy >= n)) return pfmi_march(s, x, y, w, 0.5, 0.0);
        if (n < s->w) {
            if (dx > 1e-300) tend = ((double)(n - ox) - 0.5) / dx;
            else if (dx < -1e-300) tend = ((double)ox + 0.5) / -dx;
        }
        if (n < s->h) {
            double ty = 1e300;
            if (dy > 1e-300) ty = ((double)(n - oy) - 0.5) / dy;
            else if (dy < -1e-300) ty = ((double)oy + 0.5) / -dy;
            if (ty < tend) tend = ty;
        }
    }
    return pfmi_march(s, x, y, w, 0.5, tend);
}

/* In-footprint visibility of the footprint's n x n texels for direction w, written into the
   map vis (w h bytes, indexed like pfm_visibility_map; only the footprint's texels are
   written). vis_full (may be NULL): the full map for w (pfm_visibility_map); a texel it marks
   visible is visible in the box too (the box only removes occluders: its march tests a
   subset of the same segments), so only the others are marched: on the corpus this skips
   ~90% of the rays. */
PFM_FN void pfm_visibility_map_box(const pfm_surface *s, const double w[3], int x0, int y0, int n,
                                   const unsigned char *vis_full, unsigned char *vis)
{
    int i, j;
    for (j = 0; j < n; ++j) {
        int y = pfmi_wrap(y0 + j, s->h);
        for (i = 0; i < n; ++i) {
            int x = pfmi_wrap(x0 + i, s->w);
            size_t id = (size_t)y * s->w + x;
            vis[id] = (unsigned char)((vis_full && vis_full[id]) ? 1 : pfm_visible_box(s, x, y, w, x0, y0, n));
        }
    }
}

/* ================================================================ the narrow base lobe */

/* Smith's Lambda of Gaussian slopes as a function of nu = (cot t - mu)/(sigma sqrt 2)
   (Dupuy et al. 2013 sec. 4.3): exp(-nu^2)/(2 nu sqrt pi) - erfc(nu)/2 for nu <= 2, the
   Laplace continued fraction of erfc beyond (no cancellation); HUGE_VALL for nu <= 0. */
PFM_FN long double pfm_beckmann_lambda(long double nu)
{
    const long double sqrt_pi = 1.772453850905516027298167483341145182798L;
    long double t = 0.0L;
    int k;
    if (!(nu > 0.0L)) return HUGE_VALL;
    if (nu <= 2.0L) return expl(-nu * nu) / (2.0L * sqrt_pi * nu) - 0.5L * erfcl(nu);
    for (k = 40 + (int)(240.0L / (nu * nu)); k >= 1; --k) t = (0.5L * (long double)k) / (nu + t);
    return expl(-nu * nu) / (2.0L * sqrt_pi) * t / (nu * (nu + t));
}

/* Lambda of the isotropic lobe of deviation sigma centred on slope (sx, sy), direction w
   (eqs. 14-15): nu = (w.z - sx w.x - sy w.y) / (sigma sqrt(2 (w.x^2 + w.y^2))), in double
   (the reference's results are doubles; the closed form's cancellation for large nu costs
   at most ~100 ulps of Lambda, i.e. nothing next to the 1 in 1 + Lambda_o + Lambda_i).
   -1 when w is on or below the lobe's mean plane (Lambda = infinity; a finite flag, so
   -ffast-math builds never meet an infinity). */
PFM_FN double pfmi_lobe_lambda(const double w[3], double sx, double sy, double sigma)
{
    const double sqrt_pi = 1.7724538509055160273;
    double num = w[2] - sx * w[0] - sy * w[1], r2 = w[0] * w[0] + w[1] * w[1], nu;
    if (!(num > 0.0)) return -1.0;
    if (!(r2 > 0.0)) return 0.0;
    nu = num / (sigma * sqrt(2.0 * r2));
    if (nu > 6.5) return 0.0; /* Lambda < exp(-42) / (4 nu^3 sqrt pi) < 1e-21 */
    return exp(-nu * nu) / (2.0 * sqrt_pi * nu) - 0.5 * erfc(nu);
}

/* The per-texel specular term F(h.wi) D_t(h) G2_t / 4 of a narrow isotropic Beckmann lobe of
   slope deviation sigma centred on slope (sx, sy) (Dupuy et al. 2013 eqs. 8, 10, 13, 16-17),
   before the projected-area division; in double (relative error ~1e-15). 0 when a direction
   is below the lobe's mean plane or below the macrosurface. */
PFM_FN double pfm_base_specular(const double wo[3], const double wi[3], double sx, double sy,
                                double sigma, double f0)
{
    double hx = wo[0] + wi[0], hy = wo[1] + wi[1], hz = wo[2] + wi[2];
    double ex, ey, var = sigma * sigma, q, d, g, f, c, c5, lo, li, hn;
    if (!(wo[2] > 0.0) || !(wi[2] > 0.0)) return 0.0;
    /* eq. 10: D = P22(slope of h) / (h.z)^4, P22 isotropic Gaussian about (sx, sy); the
       slope of h needs no normalization of h */
    ex = -hx / hz - sx;
    ey = -hy / hz - sy;
    q = 0.5 * (ex * ex + ey * ey) / var;
    if (q > 745.0) return 0.0; /* exp(-q) underflows double */
    lo = pfmi_lobe_lambda(wo, sx, sy, sigma);
    li = pfmi_lobe_lambda(wi, sx, sy, sigma);
    if (lo < 0.0 || li < 0.0) return 0.0; /* a direction below the lobe's mean plane */
    hn = sqrt(hx * hx + hy * hy + hz * hz);
    hx /= hn;
    hy /= hn;
    hz /= hn;
    d = exp(-q) / (2.0 * PFM_PI * var) / (hz * hz * hz * hz);
    g = 1.0 / (1.0 + lo + li); /* eq. 13 */
    c = hx * wi[0] + hy * wi[1] + hz * wi[2];
    c = c < 0.0 ? 0.0 : (c > 1.0 ? 1.0 : c);
    c5 = (1.0 - c) * (1.0 - c);
    c5 = c5 * c5 * (1.0 - c);
    f = f0 + (1.0 - f0) * c5; /* Schlick 1994 */
    return f * d * g / 4.0;
}

/* ================================================================ the reference pixel */

PFM_FN pfm_shade pfm_reference_shade(const pfm_surface *s, const unsigned char *vis_o,
                                     const unsigned char *vis_i, int x0, int y0, int n,
                                     const double wo[3], const double wi[3], double base_sigma,
                                     double f0)
{
    pfm_shade r;
    long double A = 0.0L, front = 0.0L, spec = 0.0L, diff = 0.0L, mask = 0.0L, joint = 0.0L;
    int i, j;
    memset(&r, 0, sizeof r);
    if (n < 1) return r;
    for (j = 0; j < n; ++j) {
        int y = pfmi_wrap(y0 + j, s->h);
        for (i = 0; i < n; ++i) {
            int x = pfmi_wrap(x0 + i, s->w);
            size_t id = (size_t)y * s->w + x;
            double sx, sy;
            long double ao, ai, mz;
            int vo, vi;
            pfm_slope(s, x, y, &sx, &sy);
            /* a_t(w) = (m.w)/(m.z) = w.z - s.(w.x, w.y) (eq. 1 integrand) */
            ao = (long double)wo[2] - (long double)sx * (long double)wo[0] - (long double)sy * (long double)wo[1];
            ai = (long double)wi[2] - (long double)sx * (long double)wi[0] - (long double)sy * (long double)wi[1];
            A += ao;
            vo = vis_o ? vis_o[id] != 0 : 1;
            vi = vis_i ? vis_i[id] != 0 : 1;
            if (!(ao > 0.0L)) continue;
            front += ao;
            if (!vo) continue;
            mask += ao;
            if (!vi || !(ai > 0.0L)) continue;
            joint += ao;
            /* <m,wo><m,wi>/(m.z) = a_o a_i m.z, m.z = 1/sqrt(1 + |s|^2) */
            mz = 1.0L / sqrtl(1.0L + (long double)sx * (long double)sx + (long double)sy * (long double)sy);
            diff += ao * ai * mz / PFM_PIL;
            if (base_sigma > 0.0) spec += (long double)pfm_base_specular(wo, wi, sx, sy, base_sigma, f0);
        }
    }
    r.area = (double)(A / ((long double)n * (long double)n));
    r.front_area = (double)(front / ((long double)n * (long double)n));
    if (front > 0.0L) {
        r.masking = (double)(mask / front);
        r.joint = (double)(joint / front);
    }
    if (!(A > 0.0L)) return r;
    r.spec = (double)(spec / A);
    r.diffuse = (double)(diff / A);
    r.visible_area = (double)(mask / A);
    return r;
}

/* pfm_reference_shade for nset visibility pairs (vis_o[k], vis_i[k]; either may be NULL: all
   visible) of the same footprint and directions, in one pass: out[k] equals
   pfm_reference_shade(s, vis_o[k], vis_i[k], ...) exactly (the same sums in the same order;
   tests/test_microsurface.c checks it), but each texel's base lobe, the costly part (exp and
   erfc), is evaluated once for all the pairs that need it. The bench uses it for the full
   reference, the in-footprint one and the histogram oracle (no visibility) together. */
PFM_FN void pfm_reference_shade_set(const pfm_surface *s, int nset, const unsigned char *const *vis_o,
                                    const unsigned char *const *vis_i, int x0, int y0, int n,
                                    const double wo[3], const double wi[3], double base_sigma, double f0,
                                    pfm_shade *out)
{
    enum { PFM_SET_MAX = 8 };
    long double A = 0.0L, front = 0.0L, spec[PFM_SET_MAX], diff[PFM_SET_MAX], mask[PFM_SET_MAX],
                joint[PFM_SET_MAX];
    int i, j, k, base;
    /* batches of PFM_SET_MAX pairs (fixed-size accumulators: no allocation per call) */
    for (base = 0; base < nset; base += PFM_SET_MAX) {
        int m = nset - base < PFM_SET_MAX ? nset - base : PFM_SET_MAX;
        A = 0.0L;
        front = 0.0L;
        for (k = 0; k < m; ++k) {
            spec[k] = diff[k] = mask[k] = joint[k] = 0.0L;
            memset(&out[base + k], 0, sizeof out[base + k]);
        }
        if (n < 1) continue;
        for (j = 0; j < n; ++j) {
            int y = pfmi_wrap(y0 + j, s->h);
            for (i = 0; i < n; ++i) {
                int x = pfmi_wrap(x0 + i, s->w);
                size_t id = (size_t)y * s->w + x;
                double sx, sy, term = 0.0;
                long double ao, ai, mz = 0.0L;
                int have = 0;
                pfm_slope(s, x, y, &sx, &sy);
                ao = (long double)wo[2] - (long double)sx * (long double)wo[0] - (long double)sy * (long double)wo[1];
                ai = (long double)wi[2] - (long double)sx * (long double)wi[0] - (long double)sy * (long double)wi[1];
                A += ao;
                if (!(ao > 0.0L)) continue;
                front += ao;
                for (k = 0; k < m; ++k) {
                    const unsigned char *vo_map = vis_o ? vis_o[base + k] : NULL;
                    const unsigned char *vi_map = vis_i ? vis_i[base + k] : NULL;
                    if (vo_map && !vo_map[id]) continue;
                    mask[k] += ao;
                    if ((vi_map && !vi_map[id]) || !(ai > 0.0L)) continue;
                    joint[k] += ao;
                    if (!have) { /* the same expressions as pfm_reference_shade */
                        mz = 1.0L / sqrtl(1.0L + (long double)sx * (long double)sx + (long double)sy * (long double)sy);
                        if (base_sigma > 0.0) term = pfm_base_specular(wo, wi, sx, sy, base_sigma, f0);
                        have = 1;
                    }
                    diff[k] += ao * ai * mz / PFM_PIL;
                    if (base_sigma > 0.0) spec[k] += (long double)term;
                }
            }
        }
        for (k = 0; k < m; ++k) {
            pfm_shade *r = &out[base + k];
            r->area = (double)(A / ((long double)n * (long double)n));
            r->front_area = (double)(front / ((long double)n * (long double)n));
            if (front > 0.0L) {
                r->masking = (double)(mask[k] / front);
                r->joint = (double)(joint[k] / front);
            }
            if (!(A > 0.0L)) continue;
            r->spec = (double)(spec[k] / A);
            r->diffuse = (double)(diff[k] / A);
            r->visible_area = (double)(mask[k] / A);
        }
    }
}

/* Visible mean of a per-texel attribute over the footprint (Heitz & Neyret 2011 eq. 19 with
   the marched visibility): sum V_o V_i a_t(wo)+ attr_t / sum V_o V_i a_t(wo)+; vis_i NULL for
   masking only (vis_o NULL: all visible). 0 when nothing is visible. */
PFM_FN double pfm_reference_visible_mean(const pfm_surface *s, const unsigned char *vis_o,
                                         const unsigned char *vis_i, int x0, int y0, int n,
                                         const double wo[3], const double *attribute)
{
    long double num = 0.0L, den = 0.0L;
    int i, j;
    for (j = 0; j < n; ++j) {
        int y = pfmi_wrap(y0 + j, s->h);
        for (i = 0; i < n; ++i) {
            int x = pfmi_wrap(x0 + i, s->w);
            size_t id = (size_t)y * s->w + x;
            double sx, sy;
            long double ao;
            if ((vis_o && !vis_o[id]) || (vis_i && !vis_i[id])) continue;
            pfm_slope(s, x, y, &sx, &sy);
            ao = (long double)wo[2] - (long double)sx * (long double)wo[0] - (long double)sy * (long double)wo[1];
            if (!(ao > 0.0L)) continue;
            num += ao * (long double)attribute[id];
            den += ao;
        }
    }
    return den > 0.0L ? (double)(num / den) : 0.0;
}

#endif /* PF_MICROSURFACE_H */

/* pf_map.h - CPU baking of maps: the one pyramid layout, border rule, height stencil and
   height-field march of the library, the pyramids of linear moments (slope, scalar, depth,
   normal) and their sampling, heights to slopes and to unit normals (the slope-preserving
   height downsampler built on them is pf_map_downsample.h). Every module that bakes a map
   (pf_moments.h's texels, pf_vmf_fit.h, pf_vmf_scale.h, pf_horizon.h) uses these, so its maps
   are laid out, bordered and differentiated alike.
   CPU only (PF_CPU_DEF: caller-owned buffers, no allocation); empty under PF_GLSL. A shader
   reads what these functions bake with pf_moments.h's evaluators and its own sampler.

   USAGE (a whole pyramid in one caller buffer, no allocation)
     long long n = pf_mip_texel_count(w, h);              -- texels of all levels together
     pf_real *pyr = <n * 5 pf_reals from the caller>;
     if (pf_slope_pyramid_from_heights(heights, w, h, dx, dy, scale, PF_BORDER_WRAP, pyr) != PF_OK) ...
     pf_slope_moments m = pf_slope_moments_sample(pyr, w, h, lod, u, v, PF_BORDER_WRAP);

   FUNCTIONS
     layout          pf_mip_level_count, _level_size, _level_offset, pf_mip_texel_count
     borders         PF_BORDER_CLAMP, PF_BORDER_WRAP, pf_map_wrap (a wrapped index)
     heights         pf_map_slope_stencil, pf_map_height, pf_map_node_slope,
                     pf_map_normals_from_heights, pf_map_visible (the march)
     building        pf_mip_build (any channel count), pf_mip_build_log (ESM),
                     pf_slope_moments_map_from_heights (level 0), pf_slope_pyramid_from_heights,
                     pf_depth_moment_channels, pf_depth_pyramid_from_depths,
                     pf_scalar_pyramid_from_values, pf_normal_pyramid_from_normals
     sampling        pf_mip_sample_bilinear, _trilinear, _bilinear_log, _trilinear_log;
                     pf_<T>_sample for T in slope_moments, scalar_moments, depth_moments2,
                     depth_moments4, evsm_moments, normal_avg; pf_esm_log_sample

   CONVENTIONS (docs/map.md gives the reasons and the tests behind each)
     Buffers. Texel (i, j) (column i, row j) of a map of C channels is pf_reals
     [(j w + i) C ...+ C - 1], as an RGBA32F upload; struct members are channels in order
     (slope ex, ey, exx, eyy, exy: 5; scalar, depth2: 2; depth4, evsm: 4; normal: 3; ESM: 1).
     Pyramid. Level l+1 is pf_mip_next_size of each side of level l, down to 1 x 1; levels are
     stored one after the other from level 0, each row-major. Odd sizes reduce as a polyphase
     box (pf_mip_weights3): every texel of a level has the same footprint and every level's
     mean is level 0's, so the 1 x 1 top is the global mean. (For power-of-two sides this is
     also the vMF lobe pyramid's layout, pf_vmf_fit.h.)
     Sampling: the GPU's. Texel i of n is centred at u = (i + 0.5)/n; PF_BORDER_CLAMP clamps any
     u (infinities too) to the edge texel, PF_BORDER_WRAP repeats with u - floor(u) in pf_real
     (a u too large to have a fraction wraps to 0); NaN, and infinities under WRAP, are 0.
     A trilinear lod is clamped to [0, levels - 1] (NaN: 0).
     Height maps. Texel (i, j) sits at ((i + 0.5) dx, (j + 0.5) dy), row j + 1 is +y; the slope
     is height_scale * grad h (Dupuy et al. 2013 sec. 4.2) by pf_height_slope_central.
     PF_BORDER_WRAP for tiling maps; PF_BORDER_CLAMP reads no texel outside the map and uses
     pf_height_slope_edge on the first and last column and row (2 texels on an axis:
     (h1 - h0)/d; 1 texel: slope 0). The unit normal of slope (sx, sy) is
     (-sx, -sy, 1)/sqrt(1 + sx^2 + sy^2) (pf_normal_avg_from_slope).
     Robustness. Weights are applied before summing (w a + w b, never w (a + b)), so values near
     the largest float (EVSM's exp(2c) = 1.6e38 at c = 44) reduce to finite values. A NaN
     texel makes NaN exactly the texels that average it with a nonzero weight; zero-weight
     texels are never read. A level or sample of texels near +-PF_REAL_MAX that overflows
     through the rounded weights is clamped to the range of its texels (not under -ffast-math).
     Limits and errors (pf_core.h, "sizes and errors"). Every builder and sampler returns
     PF_OK or, having written nothing, PF_ERR_ARG (a NULL pointer; w, h or channels below 1;
     a border other than PF_BORDER_CLAMP / _WRAP; an unknown PF_DEPTH_* kind) or PF_ERR_SIZE
     (w or h above PF_MAX_SIDE, 2^24 by default; a pyramid or map above PF_MAX_REALS pf_reals,
     2^40 on 64-bit hosts). On those errors the typed samplers return zeros, pf_esm_log_sample
     -PF_REAL_MAX; pf_mip_texel_count is 0 for a size no builder accepts. Offsets and indices
     are long long.

   ACCURACY AND COST (docs/map.md; bench/bench_moments.c, bench/bench_vmf.c). Reductions and
   sampling equal the mixture moments of their texels to a few ulps (tests/test_moments.c). A
   pyramid is built in one pass while the rows it reads are in cache: the 5-moment pyramid of
   a 4096^2 float height map writes at over half of memcpy's bandwidth.

   SOURCES
     Dupuy et al. 2013 (LEADR) sec. 4.1-4.2; Bruneton & Neyret 2012 sec. 7.2 (moments of a
     union are weighted means); Wu, Zhao, Yan, Ramamoorthi 2019 eq. 7 (visibility of a
     height field). */
#ifndef PF_MAP_H
#define PF_MAP_H

#ifndef PF_GLSL
#  include "pf_moments.h"

/* Border handling of the height-map stencils and of sampling (any other value: PF_ERR_ARG). */
#define PF_BORDER_CLAMP 0
#define PF_BORDER_WRAP 1

/* i modulo n in [0, n) for any i and n >= 1 (a wrapped texel index, PF_BORDER_WRAP), without
   the overflow of ((i % n) + n) % n near the ends of the range. */
PF_CPU_DEF long long pf_map_wrap(long long i, long long n)
{
    long long r = i % n;
    return r < 0 ? r + n : r;
}


/* Depth-moment kinds of pf_depth_pyramid_from_depths (channels in brackets). */
#define PF_DEPTH_VSM 0     /* [2] z, z^2                                 pf_depth_moments2 */
#define PF_DEPTH_EVSM2 1   /* [2] p, p^2, p = exp(c_pos (2z - 1))        pf_depth_moments2 */
#define PF_DEPTH_EVSM4 2   /* [4] p, p^2, n, n^2, n = -exp(-c_neg (2z-1)) pf_evsm_moments */
#define PF_DEPTH_MSM 3     /* [4] u, u^2, u^3, u^4, u = 1 - z            pf_depth_moments4 */
#define PF_DEPTH_ESM_LOG 4 /* [1] c_pos z, reduced with log-sum-exp      pf_esm_log_* */
/* CSM, M = 4, 8, 16 harmonics: [2M] cos(c_k z), sin(c_k z), c_k = (2k - 1) pi, k = 1..M, in
   that order (M/2 pf_csm_pair texels; pf_shadow_csm) */
#define PF_DEPTH_CSM4 5
#define PF_DEPTH_CSM8 6
#define PF_DEPTH_CSM16 7

/* More levels than any int-sized map has (2^31 texels on a side gives 32). */
#define PF_MIP_MAX_LEVELS 32

/* ---------------------------------------------------------------- pyramid layout */
/* Number of levels of a w x h pyramid, the 1 x 1 top included (0 if w < 1 or h < 1). */
PF_CPU_DEF int pf_mip_level_count(int w, int h)
{
    int n = w >= 1 && h >= 1;
    for (; n > 0 && (w > 1 || h > 1); ++n) w = pf_mip_next_size(w), h = pf_mip_next_size(h);
    return n;
}

/* Size along one axis at a level: n halved (floor, never below 1) level times (0 for n < 1). */
PF_CPU_DEF int pf_mip_level_size(int n, int level)
{
    for (; level > 0 && n > 1; --level) n = pf_mip_next_size(n);
    return n < 1 ? 0 : n;
}

/* Where level `level` starts, in texels from the start of the pyramid (multiply by the
   channel count for pf_reals); level >= pf_mip_level_count gives the total. Any int w, h: the
   sum stays below 2^63. */
PF_CPU_DEF long long pf_mip_level_offset(int w, int h, int level)
{
    long long off = 0;
    int l, nl = pf_mip_level_count(w, h);
    for (l = 0; l < level && l < nl; ++l, w = pf_mip_next_size(w), h = pf_mip_next_size(h))
        off += (long long)w * (long long)h;
    return off;
}

/* The pyramid checks: PF_ERR_ARG for a NULL p or w, h, channels < 1; PF_ERR_SIZE for a side
   above PF_MAX_SIDE or a pyramid of more than PF_MAX_REALS pf_reals; else PF_OK. */
PF_CPU_DEF int pfi_mip_check(const void *p, int w, int h, int channels)
{
    if (!p || w < 1 || h < 1 || channels < 1) return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h)) return PF_ERR_SIZE;
    return pf_size_mul(pf_mip_level_offset(w, h, PF_MIP_MAX_LEVELS), channels) < 0 ? PF_ERR_SIZE : PF_OK;
}

/* Texels of the whole pyramid of a w x h base (all levels, one buffer of
   pf_mip_texel_count(w, h) * channels pf_reals). 0 when w or h is below 1 or above
   PF_MAX_SIDE or the texels alone exceed PF_MAX_REALS; a builder of C channels also rejects
   (PF_ERR_SIZE) a count with count * C > PF_MAX_REALS. */
PF_CPU_DEF long long pf_mip_texel_count(int w, int h)
{ return pfi_mip_check(&w, w, h, 1) == PF_OK ? pf_mip_level_offset(w, h, PF_MIP_MAX_LEVELS) : 0; }

/* ---------------------------------------------------------------- level reduction (private)
   A cascade over rows: as soon as the source rows a destination row needs are complete (2j,
   2j+1 and, for odd heights, 2j+2), that row is reduced, and the same check runs one level up;
   each level is computed while the rows it reads are still in cache, so a pyramid built from a
   map costs about one pass over memory. */
typedef struct pfi_mip_cascade {
    pf_real *pyr;
    int channels, log_space, levels;
    int lw[PF_MIP_MAX_LEVELS], lh[PF_MIP_MAX_LEVELS], next_row[PF_MIP_MAX_LEVELS];
    long long off[PF_MIP_MAX_LEVELS]; /* in pf_reals */
} pfi_mip_cascade;

/* pfi_mip_check's code; on PF_OK c is ready. */
PF_CPU_DEF int pfi_mip_cascade_init(pfi_mip_cascade *c, pf_real *pyr, int w, int h, int channels,
                                    int log_space)
{
    int l, rc = pfi_mip_check(pyr, w, h, channels);
    long long off = 0;
    if (rc != PF_OK) return rc;
    c->levels = pf_mip_level_count(w, h);
    c->pyr = pyr, c->channels = channels, c->log_space = log_space;
    for (l = 0; l < c->levels; ++l, w = pf_mip_next_size(w), h = pf_mip_next_size(h)) {
        c->lw[l] = w, c->lh[l] = h, c->next_row[l] = 0, c->off[l] = off;
        off += (long long)w * (long long)h * (long long)channels;
    }
    return PF_OK;
}

/* The 2x2 box with a compile-time channel count (the common case: both sizes even). Plain
   builds sum the four products q a + q b + q c + q d (IEEE order, no overflow, the fastest
   loop). -ffast-math factors that into q (a + b + c + d), which overflows for texels above
   PF_REAL_MAX / 4 (see pf_evsm_moments_reduce2x2); there each pair is averaged as a midpoint,
   a + (b - a)/2 for one sign, (a + b)/2 for opposite signs (neither exceeds max(|a|, |b|)). */
#ifdef __FAST_MATH__
PF_CPU_DEF pf_real pfi_mip_mid(pf_real a, pf_real b)
{ return (a >= PF_R(0.0)) == (b >= PF_R(0.0)) ? a + PF_R(0.5) * (b - a) : PF_R(0.5) * (a + b); }
#endif
PF_CPU_DEF void pfi_mip_box_row(pf_real *dst, const pf_real *a, const pf_real *b, int dw, int nc)
{
    const pf_real q = PF_R(0.25);
    long long i;
    int k;
    for (i = 0; i < dw; ++i) {
        const pf_real *a0 = a + 2 * i * nc, *b0 = b + 2 * i * nc;
        pf_real *d = dst + i * nc;
#ifdef __FAST_MATH__
        (void)q;
        for (k = 0; k < nc; ++k)
            d[k] = pfi_mip_mid(pfi_mip_mid(a0[k], a0[nc + k]), pfi_mip_mid(b0[k], b0[nc + k]));
#else
        for (k = 0; k < nc; ++k) d[k] = q * a0[k] + q * a0[nc + k] + q * b0[k] + q * b0[nc + k];
#endif
    }
}

/* Number of source texels with a nonzero weight along an axis of n_src texels. */
PF_CPU_DEF int pfi_mip_taps(int n_src) { return n_src == 1 ? 1 : ((n_src & 1) ? 3 : 2); }
/* A weighted mean s of n taps (tap[t][k], positive weights) that overflowed: the rounded
   weights may sum to a little more than 1, so taps near +-PF_REAL_MAX can give +-inf; the mean
   lies between the smallest and the largest tap, so s is clamped there (NaN stays NaN). */
PF_CPU_DEF pf_real pfi_taps_clamp(pf_real s, const pf_real *const *tap, int n, long long k)
{
    pf_real lo = tap[0][k], hi = tap[0][k];
    int t;
    for (t = 1; t < n; ++t) lo = pf_min(lo, tap[t][k]), hi = pf_max(hi, tap[t][k]);
    return pf_clamp(s, lo, hi);
}
/* Channel k of the weighted mean of n taps of positive weights w: sum w[t] tap[t][k] (clamped
   as above when it overflows) or, in log space, log sum w[t] exp(tap[t][k]) by log-sum-exp. */
PF_CPU_DEF pf_real pfi_taps_mean(const pf_real *const *tap, const pf_real *w, int n, long long k,
                                 int log_space)
{
    pf_real s = PF_R(0.0), m = -PF_REAL_MAX;
    int t;
    if (!log_space) {
        for (t = 0; t < n; ++t) s += w[t] * tap[t][k];
        /* only +-inf is clamped: a NaN s is returned as is (CUDA's fmin/fmax clamp would
           turn it into lo) */
        return !(s < -PF_REAL_MAX || s > PF_REAL_MAX) ? s : pfi_taps_clamp(s, tap, n, k);
    }
    for (t = 0; t < n; ++t)
        if (tap[t][k] > m) m = tap[t][k];
    for (t = 0; t < n; ++t) s += w[t] * PF_EXP(pf_lse_arg(tap[t][k] - m));
    return m + PF_LOG(s); /* s >= the largest weight > 0 unless a tap is NaN, which propagates */
}

/* Reduces row j of level l + 1 from level l. */
PF_CPU_DEF void pfi_mip_reduce_row(const pfi_mip_cascade *c, int l, int j)
{
    const int nc = c->channels, sw = c->lw[l], sh = c->lh[l], dw = c->lw[l + 1];
    const pf_real *src = c->pyr + c->off[l];
    pf_real *dst = c->pyr + c->off[l + 1] + (long long)j * dw * nc;
    const pf_real *rows[3];
    pf_vec3 vy = pf_mip_weights3(j, sh), vx;
    int ny = pfi_mip_taps(sh), nx = pfi_mip_taps(sw), b, a, k;
    long long i;
    for (b = 0; b < ny; ++b) rows[b] = src + (2LL * j + b) * sw * nc;
    if (!c->log_space && nx == 2 && ny == 2) {
        switch (nc) { /* constant channel counts let the compiler unroll and vectorize */
        case 1: pfi_mip_box_row(dst, rows[0], rows[1], dw, 1); return;
        case 2: pfi_mip_box_row(dst, rows[0], rows[1], dw, 2); return;
        case 3: pfi_mip_box_row(dst, rows[0], rows[1], dw, 3); return;
        case 4: pfi_mip_box_row(dst, rows[0], rows[1], dw, 4); return;
        case 5: pfi_mip_box_row(dst, rows[0], rows[1], dw, 5); return;
        default: pfi_mip_box_row(dst, rows[0], rows[1], dw, nc); return;
        }
    }
    if (c->log_space && nx == 2 && ny == 2) {
        for (i = 0; i < dw; ++i)
            for (k = 0; k < nc; ++k) {
                const pf_real *a0 = rows[0] + 2 * i * nc + k, *b0 = rows[1] + 2 * i * nc + k;
                dst[i * nc + k] = pf_esm_log_reduce2x2(a0[0], a0[nc], b0[0], b0[nc]);
            }
        return;
    }
    for (i = 0; i < dw; ++i) { /* odd sizes: up to 3 x 3 taps, every weight positive */
        pf_real wy[3], wx[3], wt[9];
        const pf_real *tap[9];
        int nt = 0;
        vx = pf_mip_weights3((int)i, sw);
        wx[0] = vx.x, wx[1] = vx.y, wx[2] = vx.z, wy[0] = vy.x, wy[1] = vy.y, wy[2] = vy.z;
        for (b = 0; b < ny; ++b)
            for (a = 0; a < nx; ++a, ++nt) {
                wt[nt] = wy[b] * wx[a];
                tap[nt] = rows[b] + (2 * i + a) * nc;
            }
        for (k = 0; k < nc; ++k) dst[i * nc + k] = pfi_taps_mean(tap, wt, nt, k, c->log_space);
    }
}

/* Row r of level l is complete: reduce every row above that now has all its inputs. */
PF_CPU_DEF void pfi_mip_push_row(pfi_mip_cascade *c, int l, int r)
{
    while (l + 1 < c->levels) {
        int j = c->next_row[l + 1], sh = c->lh[l];
        int last = sh == 1 ? 0 : ((sh & 1) ? 2 * j + 2 : 2 * j + 1);
        if (j >= c->lh[l + 1] || last > r) return;
        pfi_mip_reduce_row(c, l, j);
        c->next_row[++l] = j + 1, r = j;
    }
}

/* ---------------------------------------------------------------- building
   pyr always holds pf_mip_texel_count(w, h) * channels pf_reals; errors as in CONVENTIONS.
   Each builder writes level 0 row by row and pushes each row into the cascade (one pass).
   They stay separate functions with their own loops: merged into one, the compiler made the
   depth loops slower (MSM pyramid 1.5x in bench_moments). */
/* The height-map stencil at index i of an axis of n texels (CONVENTIONS, Height maps): the
   slope there is c[0] v[x[0]] + c[1] v[x[1]] + c[2] v[x[2]], k = height_scale / (2 spacing)
   folded into c: central (wrapped, or inside the map), (v1 - v0)/d for n = 2, the one-sided
   pf_height_slope_edge at a clamped border (mirrored at the far end), 0 for n = 1. */
PF_CPU_DEF void pf_map_slope_stencil(long long i, int n, int border, pf_real k, long long *x, pf_real *c)
{
    pf_real s = i == 0 ? k : -k;
    x[0] = x[1] = x[2] = i;
    c[0] = c[1] = c[2] = PF_R(0.0);
    if (n < 2) return;
    if (border == PF_BORDER_WRAP || (i > 0 && i < n - 1)) {
        x[0] = pf_map_wrap(i - 1, n), x[1] = pf_map_wrap(i + 1, n);
        c[0] = -k, c[1] = k;
    } else if (n == 2) {
        x[0] = 0, x[1] = 1;
        c[0] = -PF_R(2.0) * k, c[1] = PF_R(2.0) * k;
    } else {
        x[1] = i == 0 ? 1 : n - 2, x[2] = i == 0 ? 2 : n - 3;
        c[0] = -PF_R(3.0) * s, c[1] = PF_R(4.0) * s, c[2] = -s;
    }
}

/* Stores the slope moments of slope (sx, sy). */
PF_CPU_DEF void pfi_put_slope(pf_real *o, pf_real sx, pf_real sy)
{ o[0] = sx, o[1] = sy, o[2] = sx * sx, o[3] = sy * sy, o[4] = sx * sy; }
/* Stores the unit normal (-sx, -sy, 1)/|.| of slope (sx, sy). */
PF_CPU_DEF void pfi_put_normal(pf_real *o, pf_real sx, pf_real sy)
{ pf_vec3 m = pf_normal_avg_from_slope(sx, sy); o[0] = m.x, o[1] = m.y, o[2] = m.z; }
/* Row r of the slope-moment map of a height map (5 channels), or of its unit normals (3). */
PF_CPU_DEF void pfi_slope_row(const pf_real *heights, int w, int h, int r, pf_real dx, pf_real dy,
                              pf_real height_scale, int border, int normals, pf_real *out)
{
    const pf_real ky = height_scale / (PF_R(2.0) * dy), kx = height_scale / (PF_R(2.0) * dx);
    const pf_real *row = heights + (long long)r * w, *r0, *r1, *r2;
    long long y[3], x[3];
    pf_real cy[3], cx[3], c0, c1, c2;
    int i;
    pf_map_slope_stencil(r, h, border, ky, y, cy);
    r0 = heights + y[0] * w, r1 = heights + y[1] * w, r2 = heights + y[2] * w;
    c0 = cy[0], c1 = cy[1], c2 = cy[2]; /* scalars: the stores below cannot alias them */
    /* interior texels: branch-free, so the compiler can vectorize the row */
    if (!normals)
        for (i = 1; i < w - 1; ++i) {
            pf_real sx = kx * (row[i + 1] - row[i - 1]);
            pfi_put_slope(out + 5 * i, sx, c0 * r0[i] + c1 * r1[i] + c2 * r2[i]);
        }
    else
        for (i = 1; i < w - 1; ++i) {
            pf_real sx = kx * (row[i + 1] - row[i - 1]);
            pfi_put_normal(out + 3 * i, sx, c0 * r0[i] + c1 * r1[i] + c2 * r2[i]);
        }
    /* the first and last texels of the row */
    for (i = 0; i < w; i = (i == 0 && w > 1) ? w - 1 : w) {
        pf_real sx, sy;
        pf_map_slope_stencil(i, w, border, kx, x, cx);
        sx = cx[0] * row[x[0]] + cx[1] * row[x[1]] + cx[2] * row[x[2]];
        sy = c0 * r0[i] + c1 * r1[i] + c2 * r2[i];
        if (normals) pfi_put_normal(out + 3 * i, sx, sy);
        else pfi_put_slope(out + 5 * i, sx, sy);
    }
}

/* Level 0 only: the slope moments (5 interleaved channels, pf_slope_moments order) of every
   texel of a w x h height map, into out (w h 5 pf_reals). heights: w h pf_reals, row-major;
   dx, dy: texel spacing; height_scale multiplies the heights; border: PF_BORDER_WRAP or
   PF_BORDER_CLAMP (CONVENTIONS, Height maps). PF_ERR_SIZE when w h 5 > PF_MAX_REALS. */
PF_CPU_DEF int pf_slope_moments_map_from_heights(const pf_real *heights, int w, int h, pf_real dx,
                                                 pf_real dy, pf_real height_scale, int border,
                                                 pf_real *out)
{
    int r;
    if (!heights || !out || w < 1 || h < 1 || (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP))
        return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || pf_size_mul3(w, h, 5) < 0) return PF_ERR_SIZE;
    for (r = 0; r < h; ++r)
        pfi_slope_row(heights, w, h, r, dx, dy, height_scale, border, 0, out + (long long)r * w * 5);
    return PF_OK;
}

/* The unit micro-normals (-sx, -sy, 1)/sqrt(1 + sx^2 + sy^2) of every texel of a w x h height
   map, 3 interleaved pf_reals each, into out (w h 3 pf_reals), the slopes (sx, sy) exactly those
   of pf_slope_moments_map_from_heights (same arguments): the normals a lobe fit reads
   (pf_vmf_fit.h). PF_ERR_SIZE when w h 3 > PF_MAX_REALS. */
PF_CPU_DEF int pf_map_normals_from_heights(const pf_real *heights, int w, int h, pf_real dx, pf_real dy,
                                           pf_real height_scale, int border, pf_real *out)
{
    int r;
    if (!heights || !out || w < 1 || h < 1 || (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP))
        return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || pf_size_mul3(w, h, 3) < 0) return PF_ERR_SIZE;
    for (r = 0; r < h; ++r)
        pfi_slope_row(heights, w, h, r, dx, dy, height_scale, border, 1, out + (long long)r * w * 3);
    return PF_OK;
}

/* Channels per texel of a PF_DEPTH_* kind (0 for an unknown kind). */
PF_CPU_DEF int pf_depth_moment_channels(int kind)
{
    if (kind == PF_DEPTH_VSM || kind == PF_DEPTH_EVSM2) return 2;
    if (kind == PF_DEPTH_EVSM4 || kind == PF_DEPTH_MSM) return 4;
    if (kind == PF_DEPTH_CSM4 || kind == PF_DEPTH_CSM8 || kind == PF_DEPTH_CSM16)
        return 8 << (kind - PF_DEPTH_CSM4); /* 2M */
    return kind == PF_DEPTH_ESM_LOG ? 1 : 0;
}

/* Stores a texel's members in order. */
PF_CPU_DEF void pfi_put_d2(pf_real *t, pf_depth_moments2 m) { t[0] = m.m1; t[1] = m.m2; }
PF_CPU_DEF void pfi_put_d4(pf_real *t, pf_depth_moments4 m) { t[0] = m.m1; t[1] = m.m2; t[2] = m.m3; t[3] = m.m4; }
PF_CPU_DEF void pfi_put_evsm(pf_real *t, pf_evsm_moments m) { t[0] = m.pos1; t[1] = m.pos2; t[2] = m.neg1; t[3] = m.neg2; }
PF_CPU_DEF void pfi_put_v3(pf_real *t, pf_vec3 m) { t[0] = m.x; t[1] = m.y; t[2] = m.z; }
/* The 2M CSM basis values of depth z (M = nc / 2), through the shader constructor so that
   CPU and GPU texels agree. */
PF_CPU_DEF void pfi_put_csm(pf_real *t, pf_real z, int nc)
{
    int j;
    for (j = 0; 4 * j < nc; ++j) {
        pf_csm_pair p = pf_csm_pair_from_depth(z, j);
        t[4 * j] = p.cos_a; t[4 * j + 1] = p.sin_a; t[4 * j + 2] = p.cos_b; t[4 * j + 3] = p.sin_b;
    }
}

PF_CPU_DEF int pfi_mip_build(pf_real *pyr, int w, int h, int channels, int log_space)
{
    pfi_mip_cascade c;
    int r, rc = pfi_mip_cascade_init(&c, pyr, w, h, channels, log_space);
    if (rc != PF_OK) return rc;
    for (r = 0; r < h; ++r) pfi_mip_push_row(&c, 0, r);
    return PF_OK;
}
/* Builds levels 1 .. top of a pyramid whose level 0 (w x h texels of `channels` interleaved
   pf_reals, at the start of pyr) the caller has filled; any linear moment type (the channel
   count says which). */
PF_CPU_DEF int pf_mip_build(pf_real *pyr, int w, int h, int channels)
{ return pfi_mip_build(pyr, w, h, channels, 0); }
/* The same for log-space ESM maps: every channel is reduced with log-sum-exp (each level
   holds log of the mean of exp over its footprint). */
PF_CPU_DEF int pf_mip_build_log(pf_real *pyr, int w, int h, int channels)
{ return pfi_mip_build(pyr, w, h, channels, 1); }

/* The whole 5-moment pyramid of a height map in one pass: level 0 as
   pf_slope_moments_map_from_heights (same arguments). pyr: pf_mip_texel_count(w, h) * 5
   pf_reals. */
PF_CPU_DEF int pf_slope_pyramid_from_heights(const pf_real *heights, int w, int h, pf_real dx,
                                             pf_real dy, pf_real height_scale, int border,
                                             pf_real *pyr)
{
    pfi_mip_cascade c;
    int r, rc;
    if (!heights || (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP)) return PF_ERR_ARG;
    if ((rc = pfi_mip_cascade_init(&c, pyr, w, h, 5, 0)) != PF_OK) return rc;
    for (r = 0; r < h; ++r) {
        pfi_slope_row(heights, w, h, r, dx, dy, height_scale, border, 0, pyr + (long long)r * w * 5);
        pfi_mip_push_row(&c, 0, r);
    }
    return PF_OK;
}

/* The pyramid of a depth map (w h depths in [0, 1], row-major) for one PF_DEPTH_* kind:
   c_pos is the EVSM positive exponent and the ESM exponent, c_neg the EVSM negative one
   (ignored by the others). PF_DEPTH_ESM_LOG stores c_pos z and reduces in log space.
   pyr: pf_mip_texel_count(w, h) * pf_depth_moment_channels(kind) pf_reals. */
PF_CPU_DEF int pf_depth_pyramid_from_depths(const pf_real *depths, int w, int h, int kind,
                                            pf_real c_pos, pf_real c_neg, pf_real *pyr)
{
    pfi_mip_cascade c;
    int nc = pf_depth_moment_channels(kind), r, i, rc;
    if (!depths || nc == 0) return PF_ERR_ARG;
    if ((rc = pfi_mip_cascade_init(&c, pyr, w, h, nc, kind == PF_DEPTH_ESM_LOG)) != PF_OK) return rc;
    for (r = 0; r < h; ++r) {
        const pf_real *z = depths + (long long)r * w;
        pf_real *o = pyr + (long long)r * w * nc;
        switch (kind) { /* outside the loops, so each loop vectorizes */
        case PF_DEPTH_VSM: for (i = 0; i < w; ++i) pfi_put_d2(o + 2 * i, pf_depth_moments2_from_depth(z[i])); break;
        case PF_DEPTH_EVSM2: for (i = 0; i < w; ++i) pfi_put_d2(o + 2 * i, pf_evsm2_from_depth(z[i], c_pos)); break;
        case PF_DEPTH_EVSM4:
            for (i = 0; i < w; ++i) pfi_put_evsm(o + 4 * i, pf_evsm_moments_from_depth(z[i], c_pos, c_neg));
            break;
        case PF_DEPTH_MSM: for (i = 0; i < w; ++i) pfi_put_d4(o + 4 * i, pf_depth_moments4_from_depth(z[i])); break;
        case PF_DEPTH_CSM4: case PF_DEPTH_CSM8: case PF_DEPTH_CSM16:
            for (i = 0; i < w; ++i) pfi_put_csm(o + (long long)nc * i, z[i], nc);
            break;
        default: for (i = 0; i < w; ++i) o[i] = pf_esm_log_from_depth(z[i], c_pos); break;
        }
        pfi_mip_push_row(&c, 0, r);
    }
    return PF_OK;
}
/* The pyramid of scalar-map moments (2 channels: f, f^2) of a w x h map of values: the same
   texels as PF_DEPTH_VSM's (z, z^2), so the same builder. */
PF_CPU_DEF int pf_scalar_pyramid_from_values(const pf_real *values, int w, int h, pf_real *pyr)
{ return pf_depth_pyramid_from_depths(values, w, h, PF_DEPTH_VSM, PF_R(0.0), PF_R(0.0), pyr); }
/* The pyramid of average normals (3 channels) of a normal map (w h normals, 3 interleaved
   pf_reals each; normalized here, so 8-bit-decoded normals may be passed as they are). */
PF_CPU_DEF int pf_normal_pyramid_from_normals(const pf_real *normals, int w, int h, pf_real *pyr)
{
    pfi_mip_cascade c;
    int r, i, rc;
    if (!normals) return PF_ERR_ARG;
    if ((rc = pfi_mip_cascade_init(&c, pyr, w, h, 3, 0)) != PF_OK) return rc;
    for (r = 0; r < h; ++r) {
        const pf_real *n = normals + (long long)r * w * 3;
        pf_real *o = pyr + (long long)r * w * 3;
        for (i = 0; i < w; ++i)
            pfi_put_v3(o + 3 * i, pf_normal_avg_from_normal(pf_vec3_make(n[3 * i], n[3 * i + 1], n[3 * i + 2])));
        pfi_mip_push_row(&c, 0, r);
    }
    return PF_OK;
}

/* ---------------------------------------------------------------- height fields
   A height map heights[y w + x] (world units, `texel` world units between nodes) read as a
   PERIODIC surface: node (x, y) is texel (pf_map_wrap(x, w), pf_map_wrap(y, h)) for any x, y. */

/* The height of node (x, y) of the periodic map (x, y any long long). */
PF_CPU_DEF pf_real pf_map_height(const pf_real *hm, int w, int h, long long x, long long y)
{
    return hm[pf_map_wrap(y, h) * (long long)w + pf_map_wrap(x, w)];
}

/* The slope (dh/dx, dh/dy) of node (x, y) of the periodic map, k (h(x + 1) - h(x - 1)) with
   k = 1/(2 texel): pf_map_slope_stencil's PF_BORDER_WRAP stencil at one node, as a scaled
   difference (the stencil's -k a + k b rounds differently). */
PF_CPU_DEF void pf_map_node_slope(const pf_real *hm, int w, int h, pf_real texel, long long x, long long y, pf_real *sx,
                                  pf_real *sy)
{
    pf_real k = PF_R(0.5) / texel;
    *sx = k * (pf_map_height(hm, w, h, x + 1, y) - pf_map_height(hm, w, h, x - 1, y));
    *sy = k * (pf_map_height(hm, w, h, x, y + 1) - pf_map_height(hm, w, h, x, y - 1));
}

/* THE HEIGHT-FIELD MARCH (pf_map_visible; the visibility V(w) of Wu et al. 2019 eq. 7 for one
   node of a patch)
   The ray from the texel's node toward w is marched cell by cell
   over the BILINEAR surface through the nodes; within a cell the surface minus the ray is a
   quadratic of the horizontal distance, so the test is exact (both ends and the vertex), no
   step size. The first half texel is skipped (the facet stands for its half-texel
   neighbourhood; the twisted bilinear patches around the node would otherwise shadow rays
   that clear the facet). Only occluders INSIDE the patch count: the ray is free where its
   horizontal path leaves [x0 - 1/2, x0 + n - 1/2] x [y0 - 1/2, y0 + n - 1/2] (the footprint
   is all a filtered model of it can know; along an axis where n equals the map's side, one
   period: n - 1/2 texels from the texel's node, past which the ray is over the same nodes
   again) or rises above the highest node it can meet, so a march visits at most 2 n + 1
   cells, periodic maps included; a texel with
   m.w <= 0 is not visible. This is the in-footprint reference of tests/reference/pf_microsurface.h
   (pfm_visible_box), reimplemented here in pf_real on caller buffers: the test header keeps
   its own double-precision march as the independent oracle (it must not call include/), and
   tests/test_map.c checks the two agree.
   Arguments: the periodic map (hm, w, h, texel > 0), the node (x, y), a direction d (any
   length, tangent frame), the patch (x0, y0, n: n x n nodes from (x0, y0), 1 <= n <= w, h),
   `top` the highest height (world units) of the patch and its one-node ring. Returns 1 when the
   node sees d, 0 when d.z <= 0, the node's facet faces away from d, or the ray is occluded.
   Cost: the cells the ray crosses inside the patch, at most 2 n + 1 (n along each axis; a
   periodic axis is followed for one period), 4 reads each; PF_MAP_MARCH_MAX_CELLS caps the
   march (a ray it stops is called occluded), which only binds for n above 32767. */
/* largest number of cells a march visits before it calls the ray occluded (a ray that rises
   less than the patch's height range over this many texels: within ~1e-4 rad of the horizon) */
#ifndef PF_MAP_MARCH_MAX_CELLS
#  define PF_MAP_MARCH_MAX_CELLS 65536
#endif
/* Heights are read in texel units inside the march. */
PF_CPU_DEF int pf_map_visible(const pf_real *hm, int w, int h, pf_real texel, long long x, long long y, pf_vec3 d,
                               long long x0, long long y0, long long n, pf_real top)
{
    pf_real sx, sy, r, dx, dy, rise, h0, t = PF_R(0.0), tend = PF_REAL_MAX, tnx, tny, tdx, tdy, it = PF_R(1.0) / texel;
    long long ix, iy, ox, oy, cells;
    int stx, sty;
    if (!(d.z > PF_R(0.0))) return 0;
    pf_map_node_slope(hm, w, h, texel, x, y, &sx, &sy);
    if (!(d.z - sx * d.x - sy * d.y > PF_R(0.0))) return 0;
    r = PF_SQRT(d.x * d.x + d.y * d.y);
    h0 = pf_map_height(hm, w, h, x, y) * it;
    top = top * it;
    if (!(r > PF_R(0.0)) || h0 >= top) return 1;
    dx = d.x / r;
    dy = d.y / r;
    rise = d.z / r;
    if (PF_FABS(dx) < PF_R(1.0e-12)) dx = PF_R(0.0);
    if (PF_FABS(dy) < PF_R(1.0e-12)) dy = PF_R(0.0);
    ox = pf_map_wrap(x - x0, w);
    oy = pf_map_wrap(y - y0, h);
    /* the box's edges lie half a texel outside its first and last nodes */
    if (n < w) {
        if (dx > PF_R(0.0)) tend = pf_min(tend, ((pf_real)(n - ox) - PF_R(0.5)) / dx);
        if (dx < PF_R(0.0)) tend = pf_min(tend, ((pf_real)ox + PF_R(0.5)) / -dx);
    } else if (dx != PF_R(0.0)) {
        /* periodic axis: one period, n - 1/2 texels from the node (past it the ray is over
           the same nodes again) */
        tend = pf_min(tend, ((pf_real)n - PF_R(0.5)) / PF_FABS(dx));
    }
    if (n < h) {
        if (dy > PF_R(0.0)) tend = pf_min(tend, ((pf_real)(n - oy) - PF_R(0.5)) / dy);
        if (dy < PF_R(0.0)) tend = pf_min(tend, ((pf_real)oy + PF_R(0.5)) / -dy);
    } else if (dy != PF_R(0.0)) {
        tend = pf_min(tend, ((pf_real)n - PF_R(0.5)) / PF_FABS(dy));
    }
    /* cell (ix, iy) spans [ix, ix + 1] x [iy, iy + 1] relative to the node, which is at 0 */
    stx = dx > PF_R(0.0) ? 1 : -1;
    sty = dy > PF_R(0.0) ? 1 : -1;
    ix = dx >= PF_R(0.0) ? 0 : -1;
    iy = dy >= PF_R(0.0) ? 0 : -1;
    tdx = dx != PF_R(0.0) ? PF_R(1.0) / PF_FABS(dx) : PF_REAL_MAX;
    tdy = dy != PF_R(0.0) ? PF_R(1.0) / PF_FABS(dy) : PF_REAL_MAX;
    tnx = tdx;
    tny = tdy;
    /* the path ends within n texels along each axis: at most 2 n + 1 cells */
    for (cells = 0; cells < 2 * n + 2 && cells < PF_MAP_MARCH_MAX_CELLS; ++cells) {
        pf_real tout = pf_min(tnx, tny), ta = pf_max(t, PF_R(0.5)), tb = pf_min(tout, tend);
        if (h0 + rise * t > top || t >= tend) return 1;
        if (tb > ta) {
            pf_real h00 = pf_map_height(hm, w, h, x + ix, y + iy) * it, h10 = pf_map_height(hm, w, h, x + ix + 1, y + iy) * it;
            pf_real h01 = pf_map_height(hm, w, h, x + ix, y + iy + 1) * it;
            pf_real h11 = pf_map_height(hm, w, h, x + ix + 1, y + iy + 1) * it;
            pf_real u = dx * ta - (pf_real)ix, v = dy * ta - (pf_real)iy, len = tb - ta;
            pf_real k = h11 - h10 - h01 + h00, gx = h10 - h00, gy = h01 - h00;
            /* surface - ray = f0 + b s + c s^2 for s in [0, len] */
            pf_real f0 = h00 + gx * u + gy * v + k * u * v - (h0 + rise * ta);
            pf_real b = gx * dx + gy * dy + k * (u * dy + v * dx) - rise, c = k * dx * dy;
            pf_real f1 = f0 + len * (b + c * len);
            pf_real eps = PF_R(64.0) * PF_REAL_EPSILON * (PF_R(1.0) + PF_FABS(h0) + PF_FABS(rise * tb));
            if (f0 > eps || f1 > eps) return 0;
            if (c < PF_R(0.0)) {
                pf_real sv = -b / (PF_R(2.0) * c);
                if (sv > PF_R(0.0) && sv < len && f0 - b * b / (PF_R(4.0) * c) > eps) return 0;
            }
        }
        t = tout;
        if (tnx < tny) {
            tnx += tdx;
            ix += stx;
        } else {
            tny += tdy;
            iy += sty;
        }
    }
    return cells >= 2 * n + 2; /* past the patch (rounding at its edge): free; past the cap: occluded */
}

/* ---------------------------------------------------------------- sampling */
/* Texel indices (long long, in [0, n)) and the fraction for coordinate u on an axis of n
   texels, under the Sampling convention (CONVENTIONS). */
PF_CPU_DEF void pfi_mip_axis(pf_real u, int n, int border, long long *i0, long long *i1, pf_real *f)
{
    pf_real x;
    long long i;
    if (border == PF_BORDER_WRAP) u = (u - u == PF_R(0.0)) ? u - PF_FLOOR(u) : PF_R(0.0);
    else u = (u == u) ? pf_clamp(u, PF_R(0.0), PF_R(1.0)) : PF_R(0.0);
    x = u * PF_R(n) - PF_R(0.5); /* in [-0.5, n - 0.5] */
    i = pf_floor_index(x, -1, n - 1);
    *f = pf_clamp(x - PF_R(i), PF_R(0.0), PF_R(1.0));
    *i0 = border == PF_BORDER_WRAP ? pf_map_wrap(i, n) : (i < 0 ? 0 : i);
    *i1 = border == PF_BORDER_WRAP ? pf_map_wrap(i + 1, n) : (i + 1 > n - 1 ? n - 1 : i + 1);
}

/* The taps of positive bilinear weight of (u, v) at one level of a pyramid. */
typedef struct pfi_mip_bilerp { const pf_real *tap[4]; pf_real w[4]; int n; } pfi_mip_bilerp;

PF_CPU_DEF pfi_mip_bilerp pfi_mip_bilerp_at(const pf_real *pyr, int w, int h, int channels,
                                            int level, pf_real u, pf_real v, int border)
{
    pfi_mip_bilerp b;
    int lw = pf_mip_level_size(w, level), lh = pf_mip_level_size(h, level), t;
    long long x[2], y[2];
    pf_real fx, fy;
    pyr += pf_mip_level_offset(w, h, level) * channels;
    pfi_mip_axis(u, lw, border, &x[0], &x[1], &fx);
    pfi_mip_axis(v, lh, border, &y[0], &y[1], &fy);
    for (t = 0, b.n = 0; t < 4; ++t) {
        pf_real wt = ((t & 1) ? fx : PF_R(1.0) - fx) * ((t & 2) ? fy : PF_R(1.0) - fy);
        if (!(wt > PF_R(0.0))) continue;
        b.tap[b.n] = pyr + (y[t >> 1] * lw + x[t & 1]) * channels;
        b.w[b.n++] = wt;
    }
    return b;
}

/* The shared sampler: PF_OK, or the error with out untouched. */
PF_CPU_DEF int pfi_mip_sample(const pf_real *pyr, int w, int h, int channels, pf_real lod,
                              pf_real u, pf_real v, int border, int log_space, pf_real *out)
{
    int nl, l0, k, rc = pfi_mip_check(pyr, w, h, channels);
    pf_real fl;
    pfi_mip_bilerp b0, b1;
    if (rc == PF_OK && (!out || (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP))) rc = PF_ERR_ARG;
    if (rc != PF_OK) return rc;
    nl = pf_mip_level_count(w, h);
    if (!(lod > PF_R(0.0))) lod = PF_R(0.0); /* NaN too */
    if (lod > PF_R(nl - 1)) lod = PF_R(nl - 1);
    l0 = (int)PF_FLOOR(lod);
    fl = lod - PF_R(l0);
    b0 = pfi_mip_bilerp_at(pyr, w, h, channels, l0, u, v, border);
    if (!(fl > PF_R(0.0)) || l0 + 1 >= nl) {
        for (k = 0; k < channels; ++k) out[k] = pfi_taps_mean(b0.tap, b0.w, b0.n, k, log_space);
        return PF_OK;
    }
    b1 = pfi_mip_bilerp_at(pyr, w, h, channels, l0 + 1, u, v, border);
    for (k = 0; k < channels; ++k) {
        pf_real a = pfi_taps_mean(b0.tap, b0.w, b0.n, k, log_space);
        pf_real c = pfi_taps_mean(b1.tap, b1.w, b1.n, k, log_space), s;
        if (log_space) {
            out[k] = pf_esm_log_combine2(a, PF_R(1.0) - fl, c, fl);
            continue;
        }
        s = (PF_R(1.0) - fl) * a + fl * c;
        out[k] = !(s < -PF_REAL_MAX || s > PF_REAL_MAX) ? s : pf_clamp(s, pf_min(a, c), pf_max(a, c)); /* NaN as is */
    }
    return PF_OK;
}

/* Bilinear sample of level `level` (clamped to the pyramid) at (u, v): `channels` pf_reals
   into out. PF_OK, or the error with out untouched. */
PF_CPU_DEF int pf_mip_sample_bilinear(const pf_real *pyr, int w, int h, int channels, int level,
                                      pf_real u, pf_real v, int border, pf_real *out)
{ return pfi_mip_sample(pyr, w, h, channels, PF_R(level < 0 ? 0 : level), u, v, border, 0, out); }
/* Trilinear sample: bilinear at floor(lod) and floor(lod) + 1, blended by the fraction. */
PF_CPU_DEF int pf_mip_sample_trilinear(const pf_real *pyr, int w, int h, int channels, pf_real lod,
                                       pf_real u, pf_real v, int border, pf_real *out)
{ return pfi_mip_sample(pyr, w, h, channels, lod, u, v, border, 0, out); }
/* The same for log-space (ESM) pyramids: the weights apply to exp of the texels. */
PF_CPU_DEF int pf_mip_sample_bilinear_log(const pf_real *pyr, int w, int h, int channels, int level,
                                          pf_real u, pf_real v, int border, pf_real *out)
{ return pfi_mip_sample(pyr, w, h, channels, PF_R(level < 0 ? 0 : level), u, v, border, 1, out); }
PF_CPU_DEF int pf_mip_sample_trilinear_log(const pf_real *pyr, int w, int h, int channels, pf_real lod,
                                           pf_real u, pf_real v, int border, pf_real *out)
{ return pfi_mip_sample(pyr, w, h, channels, lod, u, v, border, 1, out); }
/* Typed trilinear samples (an integer lod is a bilinear sample of that level), one stamp per
   type: T pf_<T>_sample(pyr, w, h, lod, u, v, border) for the six T of the reductions.
   Bad arguments (those pf_mip_sample_trilinear rejects) return all zeros. */
#define PFI_TYPED_SAMPLE(T, F, NC, MAKE)                                                       \
    PF_CPU_DEF T F(const pf_real *pyr, int w, int h, pf_real lod, pf_real u, pf_real v, int border) \
    { pf_real t[5] = {0, 0, 0, 0, 0}; pfi_mip_sample(pyr, w, h, NC, lod, u, v, border, 0, t); return MAKE; }
PFI_TYPED_SAMPLE(pf_slope_moments, pf_slope_moments_sample, 5, pf_slope_moments_make(t[0], t[1], t[2], t[3], t[4]))
PFI_TYPED_SAMPLE(pf_scalar_moments, pf_scalar_moments_sample, 2, pf_scalar_moments_make(t[0], t[1]))
PFI_TYPED_SAMPLE(pf_depth_moments2, pf_depth_moments2_sample, 2, pf_depth_moments2_make(t[0], t[1]))
PFI_TYPED_SAMPLE(pf_depth_moments4, pf_depth_moments4_sample, 4, pf_depth_moments4_make(t[0], t[1], t[2], t[3]))
PFI_TYPED_SAMPLE(pf_evsm_moments, pf_evsm_moments_sample, 4, pf_evsm_moments_make(t[0], t[1], t[2], t[3]))
PFI_TYPED_SAMPLE(pf_vec3, pf_normal_avg_sample, 3, pf_vec3_make(t[0], t[1], t[2]))

/* The ESM log sample; bad arguments return -PF_REAL_MAX (the log of an empty sum). */
PF_CPU_DEF pf_real pf_esm_log_sample(const pf_real *pyr, int w, int h, pf_real lod, pf_real u,
                                     pf_real v, int border)
{
    pf_real t = -PF_REAL_MAX;
    pfi_mip_sample(pyr, w, h, 1, lod, u, v, border, 1, &t);
    return t;
}

#endif /* !PF_GLSL */

#endif /* PF_MAP_H */

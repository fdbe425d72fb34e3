/* pf_moments.h - linear moments for pre-filtering: slope moments (LEAN/LEADR), scalar-map
   moments, average normals (Toksvig), depth moments for shadow maps; their mip reductions,
   mip pyramids and bilinear/trilinear sampling.

   WHY MOMENTS. A shading function f that is non-linear in a map's values cannot be filtered by
   averaging the map. It can be filtered exactly when it is rewritten as a linear function of new
   per-texel quantities (Bruneton & Neyret 2012 sec. 7.1.1, eq. 40): averaging those quantities
   over a footprint then averages f. Raw moments E[1], E[m], E[m m^T], ... of a texel's values
   are such quantities: the moments of a union (a mixture) of footprints are the weighted
   averages of their moments (sec. 7.2). So everything in this header is averaged with plain
   weighted sums - a box mip reduction, a bilinear or trilinear sampler - and the statistics
   (mean, variance, covariance) are formed only after filtering, in the shader:
     slope moments   E[x], E[y], E[x^2], E[y^2], E[xy] of micro-slopes (Olano & Baker 2010 as
                     summarized by Bruneton & Neyret 2012 eq. 19; Dupuy et al. 2013 eq. 9 and
                     sec. 4.1, which stores exactly these five in mipmapped textures);
     scalar moments  E[f], E[f^2] of a colour-driving or height map: the mean and variance of a
                     Gaussian filtering distribution (Heitz et al. 2014 sec. 4.2);
     average normal  E[n] of unit normals, unnormalized; its length shrinks as the normals
                     spread, which is what Toksvig's variance estimate reads (pf_toksvig.h;
                     Bruneton & Neyret 2012 sec. 3.2.1, 7.2.2);
     depth moments   (z, z^2) for VSM, warped (exp) moments for EVSM, (z, z^2, z^3, z^4) for
                     moment shadow maps (Bruneton & Neyret 2012 sec. 5.2, eqs. 34-38); and ESM's
                     E[exp(c z)] kept as its logarithm and reduced with log-sum-exp, so that no
                     float ever holds exp(c z) and nothing overflows, whatever c.

   USAGE (shader or CPU: the evaluators)
     pf_slope_moments t = pf_slope_moments_from_heights(hl, hr, hd, hu, dx, dy, scale);
     pf_slope_moments m = pf_slope_moments_reduce2x2(t00, t10, t01, t11);   -- one mip texel
     pf_slope_stats   s = pf_slope_moments_stats(m, base_var);               -- after filtering
   USAGE (CPU: a whole pyramid in one caller buffer, no allocation)
     long long n = pf_mip_texel_count(w, h);              -- texels of all levels together
     pf_real *pyr = <n * 5 pf_reals from the caller>;
     pf_slope_pyramid_from_heights(heights, w, h, dx, dy, scale, PF_BORDER_WRAP, pyr);
     pf_slope_moments m = pf_slope_moments_sample(pyr, w, h, lod, u, v, PF_BORDER_WRAP);

   FUNCTIONS (shader subset: pure functions of scalars and by-value structs)
     types and texels  pf_scalar_moments_make, _from_value, _mean, _variance, _deviation;
                       pf_depth_moments2/4_make, _from_depth; pf_evsm2_from_depth;
                       pf_evsm_moments_make, _from_depth; pf_evsm_warp_pos, _neg;
                       pf_normal_avg_from_normal, pf_normal_avg_from_slope;
                       pf_esm_log_from_depth, pf_esm_log_combine2
     linear algebra    pf_<T>_add, pf_<T>_scale (scalar, depth2, depth4, evsm; the slope
                       moments' and pf_vec3's live in pf_beckmann.h and pf_core.h)
     reductions        for T in slope_moments, scalar_moments, depth_moments2, depth_moments4,
                       evsm_moments, normal_avg (a pf_vec3):
                         pf_<T>_reduce2x2(a, b, c, d)       the even-size mip texel (box)
                         pf_<T>_reduce3(a, b, c, w)         3 texels, weights w (odd edge)
                         pf_<T>_reduce3x3(t00 .. t22, wx, wy)  9 texels (odd corner),
                                                            separable weights
                         pf_<T>_accumulate(acc, t, w)       acc + w t: N texels, one at a time
                         pf_<T>_lerp(a, b, t), pf_<T>_bilinear(t00, t10, t01, t11, fx, fy)
                       pf_mip_next_size(n), pf_mip_weights3(j, n)   the odd-size weights below
     ESM (log space)   pf_esm_log_reduce2x2, _reduce3, _reduce3x3, _bilinear;
                       pf_esm_log_sum_make, _first, _add, _mean, PF_ESM_LOG_SUM_EMPTY
                       (N texels, streaming)
     height maps       pf_height_slope_central, pf_height_slope_edge,
                       pf_slope_moments_from_heights
   FUNCTIONS (CPU only: they walk caller-owned buffers; linkage PF_CPU_DEF; compiled out under
   PF_GLSL, skipped by the shader-subset portability checks)
     pyramid layout    pf_mip_level_count, pf_mip_level_size, pf_mip_level_offset,
                       pf_mip_texel_count
     building          pf_mip_build (linear, any channel count), pf_mip_build_log (ESM),
                       pf_slope_moments_map_from_heights (level 0 only),
                       pf_slope_pyramid_from_heights, pf_depth_pyramid_from_depths,
                       pf_scalar_pyramid_from_values, pf_normal_pyramid_from_normals
     N texels          pf_moments_weighted_mean, pf_esm_log_weighted_mean
     sampling          pf_mip_sample_bilinear, pf_mip_sample_trilinear, and their _log
                       variants (ESM); typed: pf_slope_moments_sample, pf_scalar_moments_sample,
                       pf_depth_moments2_sample, pf_depth_moments4_sample,
                       pf_evsm_moments_sample, pf_normal_avg_sample, pf_esm_log_sample

   CONVENTIONS
     Buffers. A map with C channels is an array of pf_real, texel (i, j) (column i, row j) at
     [(j w + i) C ... + C - 1]: the interleaved layout of an RGBA32F upload. The moment structs
     map to channels in member order: slope (ex, ey, exx, eyy, exy) = 5 channels; scalar and
     depth2 2; depth4 and evsm 4; normal_avg 3; ESM log 1. One builder serves every linear
     type (pf_mip_build with the channel count), so a caller who splits the five slope moments
     into an RGBA and an R texture builds two pyramids with C = 4 and C = 1 (or builds one with
     C = 5 and splits it while uploading).
     Pyramid. Level 0 is w x h; level l+1 is pf_mip_next_size of each side, i.e. floor(n/2),
     but never below 1; the last level is 1 x 1. Levels are stored one after the other, level 0
     first, each row-major: pf_mip_level_offset gives where level l starts (in texels; multiply
     by C for pf_reals). pf_mip_texel_count(w, h) is the total (< 4/3 w h + levels).
     Odd sizes (polyphase box). A destination texel covers exactly n_src / n_dst source texels,
     so every texel of a level has the same footprint, the mean of every level equals the mean
     of level 0 exactly, and the 1 x 1 top is the global mean. With n_src = 2k + 1 and
     n_dst = k, destination texel j covers source texels 2j, 2j+1, 2j+2 with weights
     (k - j, k, j + 1) / (2k + 1): the last column is not simply folded into the last texel
     (which would give that texel a 1.5x footprint and make the next level's plain 2x2 average
     no longer the mean). Even sizes use (1/2, 1/2, 0); size 1 stays 1 with (1, 0, 0).
     pf_mip_weights3 returns these weights; in 2D they are separable (3x3 in a corner where both
     sizes are odd, 3x2 on an odd edge).
     Sampling follows the GPU convention: texel i of an n-texel level has its centre at
     u = (i + 0.5)/n; PF_BORDER_WRAP repeats, PF_BORDER_CLAMP clamps to the edge texel; a
     trilinear lod is clamped to [0, levels - 1] (NaN: 0).
     Height maps. Texel (i, j) of a w x h height map sits at x = (i + 0.5) dx, y = (j + 0.5) dy
     (row j + 1 is +y). The slope is height_scale * grad h (Dupuy et al. 2013 sec. 4.2, height
     scaling), from the central difference (h[i+1] - h[i-1]) / (2 dx): second order, error
     (dx^2 / 6) h''' (measured in tests/test_moments.c). PF_BORDER_WRAP for tiling maps;
     PF_BORDER_CLAMP reads no texel outside the map and uses the second-order one-sided
     difference (-3 h0 + 4 h1 - h2) / (2 dx) on the first and last column/row, so the order is
     2 everywhere (2 texels: (h1 - h0)/dx, first order; 1 texel: slope 0).
     Weights are applied before summing (w a + w b, never w (a + b)), so reducing values near
     the largest float (EVSM's second moment exp(2c) at c = 44 is 1.6e38) stays finite.
     NaN texels propagate: a NaN texel makes NaN every texel that averages it with a nonzero
     weight (its ancestors in the pyramid, a sample whose footprint covers it) and nothing else;
     texels with zero weight are never read, so nothing is read out of bounds. A pyramid's
     weights are rounded, so a level or sample of texels near +-PF_REAL_MAX that overflows is
     clamped to the range of its texels (finite; not under -ffast-math, which folds the test).
     Limits and errors (the CPU functions; pf_core.h, "sizes and errors"). Every builder and
     sampler returns PF_OK, or, having written nothing: PF_ERR_ARG for a NULL pointer, w, h,
     channels or n below 1 (n below 0), a border other than PF_BORDER_CLAMP / _WRAP, an unknown
     PF_DEPTH_* kind or an infinite weight; PF_ERR_SIZE for w or h above PF_MAX_SIDE (2^24) or
     a buffer (pyramid, map, texels) above PF_MAX_REALS pf_reals (2^40 on 64-bit hosts).
     pf_mip_texel_count returns 0 for every size the builders reject; typed samplers return
     zeros, pf_esm_log_sample and pf_esm_log_weighted_mean -PF_REAL_MAX. Offsets and indices
     are long long, so no accepted size overflows. Coordinates: CLAMP clamps any u (infinities
     too) to the edge, NaN is 0; WRAP takes u - floor(u) in pf_real (exact: every |u| >= 2^23
     in float is an integer and wraps to 0), infinities and NaN are 0.

   ACCURACY AND COST (measured; docs/moments.md has the tables, bench/bench_moments.c the
   timings). Reductions and sampling are sums of a few products: the moments of a reduction
   equal the mixture moments of its texels to a few ulps (tests/test_moments.c). The 5-moment
   pyramid of a 4096^2 float height map is built in one pass over the heights, each level
   reduced while the rows it needs are still in cache.

   SOURCES
     Dupuy et al. 2013 (LEADR) sec. 4.1-4.2, eqs. 9, 11, 12; Bruneton & Neyret 2012 sec. 3.2.1
     (eq. 19, Toksvig), 5.2 (eqs. 34-38) and 7.2; Heitz et al. 2014 sec. 4.2; Donnelly &
     Lauritzen 2006 (VSM); Salvi 2008 / Annen et al. 2008 (ESM); Lauritzen & McCool 2008
     (EVSM); Peters & Klein 2015 (moment shadow maps). */
#ifndef PF_MOMENTS_H
#define PF_MOMENTS_H

#ifndef PF_GLSL
#  include "pf_beckmann.h"
#endif

/* ---------------------------------------------------------------- depth moments
   Depths z are in [0, 1] (0 nearest the light). All of these are linear in the texels, so a
   mip pyramid and a bilinear/trilinear sampler may average them; pf_shadow.h evaluates the
   filtered values. */

/* Two moments (E[w], E[w^2]) of a depth or of a warped depth w: VSM stores w = z; EVSM-2
   stores w = exp(c (2z - 1)). */
PF_STRUCT_BEGIN(pf_depth_moments2)
    pf_real m1;
    pf_real m2;
PF_STRUCT_END(pf_depth_moments2)

/* Four power moments E[z], E[z^2], E[z^3], E[z^4] (moment shadow maps, Peters & Klein 2015). */
PF_STRUCT_BEGIN(pf_depth_moments4)
    pf_real m1;
    pf_real m2;
    pf_real m3;
    pf_real m4;
PF_STRUCT_END(pf_depth_moments4)

/* EVSM-4 (Lauritzen & McCool 2008): with zs = 2z - 1 in [-1, 1], the moments of the positive
   warp p = exp(c_pos zs) and of the negative warp n = -exp(-c_neg zs):
   pos1 = E[p], pos2 = E[p^2], neg1 = E[n] (<= 0), neg2 = E[n^2]. */
PF_STRUCT_BEGIN(pf_evsm_moments)
    pf_real pos1;
    pf_real pos2;
    pf_real neg1;
    pf_real neg2;
PF_STRUCT_END(pf_evsm_moments)

/* Largest EVSM warp exponent c such that the second moment exp(2c) stays finite in the
   storage format: fp32, exp(2c) <= FLT_MAX = 3.4e38 = exp(88.72) -> c <= 44.36 (44 kept);
   fp16, exp(2c) <= 65504 = exp(11.09) -> c <= 5.545 (5.54 kept). */
#define PF_EVSM_EXP_MAX_F32 PF_R(44.0)
#define PF_EVSM_EXP_MAX_F16 PF_R(5.54)

PF_DEF pf_depth_moments2 pf_depth_moments2_make(pf_real m1, pf_real m2)
{ pf_depth_moments2 m; m.m1 = m1; m.m2 = m2; return m; }
PF_DEF pf_depth_moments4 pf_depth_moments4_make(pf_real m1, pf_real m2, pf_real m3, pf_real m4)
{ pf_depth_moments4 m; m.m1 = m1; m.m2 = m2; m.m3 = m3; m.m4 = m4; return m; }
PF_DEF pf_evsm_moments pf_evsm_moments_make(pf_real pos1, pf_real pos2, pf_real neg1, pf_real neg2)
{ pf_evsm_moments m; m.pos1 = pos1; m.pos2 = pos2; m.neg1 = neg1; m.neg2 = neg2; return m; }
/* VSM texel: (z, z^2). */
PF_DEF pf_depth_moments2 pf_depth_moments2_from_depth(pf_real z)
{ return pf_depth_moments2_make(z, z * z); }
/* MSM texel: (z, z^2, z^3, z^4). */
PF_DEF pf_depth_moments4 pf_depth_moments4_from_depth(pf_real z)
{ pf_real z2 = z * z; return pf_depth_moments4_make(z, z2, z2 * z, z2 * z2); }
/* EVSM warps of a depth z in [0, 1]: exp(c (2z - 1)) and -exp(-c (2z - 1)). The caller keeps
   c <= PF_EVSM_EXP_MAX_F32 (or _F16 for 16-bit storage) so the squares stay finite. */
PF_DEF pf_real pf_evsm_warp_pos(pf_real z, pf_real c)
{ return PF_EXP(c * (PF_R(2.0) * z - PF_R(1.0))); }
PF_DEF pf_real pf_evsm_warp_neg(pf_real z, pf_real c)
{ return -PF_EXP(-c * (PF_R(2.0) * z - PF_R(1.0))); }
/* EVSM-2 texel: moments of the positive warp only. */
PF_DEF pf_depth_moments2 pf_evsm2_from_depth(pf_real z, pf_real c_pos)
{ pf_real p = pf_evsm_warp_pos(z, c_pos); return pf_depth_moments2_make(p, p * p); }
/* EVSM-4 texel: moments of both warps. */
PF_DEF pf_evsm_moments pf_evsm_moments_from_depth(pf_real z, pf_real c_pos, pf_real c_neg)
{
    pf_real p = pf_evsm_warp_pos(z, c_pos);
    pf_real n = pf_evsm_warp_neg(z, c_neg);
    return pf_evsm_moments_make(p, p * p, n, n * n);
}

/* ESM texel in log space: log(exp(c z)) = c z. A pyramid of these is reduced with
   log-sum-exp (below), so E[exp(c z)] is never formed and cannot overflow for any c. */
PF_DEF pf_real pf_esm_log_from_depth(pf_real z, pf_real c) { return c * z; }
/* log(w0 exp(l0) + w1 exp(l1)) for weights w >= 0, without overflow:
   m + log(w0 exp(l0 - m) + w1 exp(l1 - m)), m the larger log among those of positive weight,
   so the sum holds that term's weight times exp(0) = 1 and never underflows to 0: a zero
   weight on the larger log (l0 = 1504, w0 = 0, l1 = 1277, w1 = 0.88 gave log(0) = -inf when m
   was max(l0, l1)) now gives l1 + log(w1). Both weights <= 0 (or NaN): -PF_REAL_MAX, the log
   of an empty sum kept finite, as pf_esm_log_reduce3; a NaN log propagates. */
PF_DEF pf_real pf_esm_log_combine2(pf_real l0, pf_real w0, pf_real l1, pf_real w1)
{
    pf_real m = w0 > PF_R(0.0) ? (w1 > PF_R(0.0) ? pf_max(l0, l1) : l0) : l1;
    pf_real s = (w0 > PF_R(0.0) ? w0 * PF_EXP(l0 - m) : PF_R(0.0))
              + (w1 > PF_R(0.0) ? w1 * PF_EXP(l1 - m) : PF_R(0.0));
    return s > PF_R(0.0) ? m + PF_LOG(s) : (s == s ? -PF_REAL_MAX : s);
}

/* a + b and w a, componentwise (the moments are linear). */
PF_DEF pf_depth_moments2 pf_depth_moments2_add(pf_depth_moments2 a, pf_depth_moments2 b)
{ return pf_depth_moments2_make(a.m1 + b.m1, a.m2 + b.m2); }
PF_DEF pf_depth_moments2 pf_depth_moments2_scale(pf_depth_moments2 a, pf_real w)
{ return pf_depth_moments2_make(w * a.m1, w * a.m2); }
PF_DEF pf_depth_moments4 pf_depth_moments4_add(pf_depth_moments4 a, pf_depth_moments4 b)
{ return pf_depth_moments4_make(a.m1 + b.m1, a.m2 + b.m2, a.m3 + b.m3, a.m4 + b.m4); }
PF_DEF pf_depth_moments4 pf_depth_moments4_scale(pf_depth_moments4 a, pf_real w)
{ return pf_depth_moments4_make(w * a.m1, w * a.m2, w * a.m3, w * a.m4); }
PF_DEF pf_evsm_moments pf_evsm_moments_add(pf_evsm_moments a, pf_evsm_moments b)
{ return pf_evsm_moments_make(a.pos1 + b.pos1, a.pos2 + b.pos2, a.neg1 + b.neg1, a.neg2 + b.neg2); }
PF_DEF pf_evsm_moments pf_evsm_moments_scale(pf_evsm_moments a, pf_real w)
{ return pf_evsm_moments_make(w * a.pos1, w * a.pos2, w * a.neg1, w * a.neg2); }

/* ---------------------------------------------------------------- scalar-map moments
   E[f], E[f^2] of a scalar map f (a height, or the value driving a colour map). After
   filtering, f over the footprint is modelled as a Gaussian with mean E[f] and variance
   E[f^2] - E[f]^2, and a colour map is filtered by convolving it with that Gaussian
   (Heitz et al. 2014 sec. 4.2, eq. 9; the variance there is printed as "f^2 bar - f bar",
   meaning E[f^2] - E[f]^2). */
PF_STRUCT_BEGIN(pf_scalar_moments)
    pf_real m1;
    pf_real m2;
PF_STRUCT_END(pf_scalar_moments)

PF_DEF pf_scalar_moments pf_scalar_moments_make(pf_real m1, pf_real m2)
{ pf_scalar_moments m; m.m1 = m1; m.m2 = m2; return m; }
/* One texel: (f, f^2). */
PF_DEF pf_scalar_moments pf_scalar_moments_from_value(pf_real f)
{ return pf_scalar_moments_make(f, f * f); }
PF_DEF pf_scalar_moments pf_scalar_moments_add(pf_scalar_moments a, pf_scalar_moments b)
{ return pf_scalar_moments_make(a.m1 + b.m1, a.m2 + b.m2); }
PF_DEF pf_scalar_moments pf_scalar_moments_scale(pf_scalar_moments a, pf_real w)
{ return pf_scalar_moments_make(w * a.m1, w * a.m2); }
PF_DEF pf_real pf_scalar_moments_mean(pf_scalar_moments m) { return m.m1; }
/* Variance E[f^2] - E[f]^2, clamped at 0: rounding in the filtered moments (and 16-bit
   storage) can make it slightly negative where the map is flat. NaN gives 0. */
PF_DEF pf_real pf_scalar_moments_variance(pf_scalar_moments m)
{ return pf_max(m.m2 - m.m1 * m.m1, PF_R(0.0)); }
PF_DEF pf_real pf_scalar_moments_deviation(pf_scalar_moments m)
{ return PF_SQRT(pf_scalar_moments_variance(m)); }

/* ---------------------------------------------------------------- average normals
   A texel of a normal map is a unit normal; the pyramid averages them without renormalizing,
   so a coarse texel holds E[n], whose length |E[n]| <= 1 measures how much the normals below
   it disagree (Toksvig 2005; pf_toksvig.h turns it into a variance). Type: pf_vec3. */

/* The texel of a normal n: n normalized (the zero vector gives (0, 0, 1), see
   pf_vec3_normalize). */
PF_DEF pf_vec3 pf_normal_avg_from_normal(pf_vec3 n) { return pf_vec3_normalize(n); }
/* The texel of a slope (x, y): the unit normal (-x, -y, 1)/sqrt(1 + x^2 + y^2)
   (Dupuy et al. 2013 sec. 4.1 slope convention). */
PF_DEF pf_vec3 pf_normal_avg_from_slope(pf_real x, pf_real y)
{ return pf_vec3_normalize(pf_vec3_make(-x, -y, PF_R(1.0))); }

/* ---------------------------------------------------------------- mip geometry */
/* Size of the next mip level along one axis: floor(n/2), never below 1 (0 for n < 1). */
PF_DEF int pf_mip_next_size(int n) { return n >= 2 ? n / 2 : (n >= 1 ? 1 : 0); }
/* Weights of source texels 2j, 2j+1, 2j+2 for destination texel j when an axis of n_src
   texels is reduced to pf_mip_next_size(n_src) (see CONVENTIONS, odd sizes):
     n_src even        (1/2, 1/2, 0)
     n_src = 2k + 1    ((k - j), k, (j + 1)) / (2k + 1)   (polyphase box, j in [0, k))
     n_src = 1         (1, 0, 0)
   The weights sum to 1 and every source texel gets a total weight of n_dst / n_src. A zero
   weight means "do not read that texel" (it may be outside the map). j is clamped to the
   destination size; n_src < 1 gives (0, 0, 0). */
PF_DEF pf_vec3 pf_mip_weights3(int j, int n_src)
{
    int k = n_src / 2;
    int jc = j < 0 ? 0 : (j > k - 1 ? k - 1 : j);
    pf_real n = PF_R(n_src);
    if (n_src < 1) return pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0));
    if (n_src == 1) return pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(0.0));
    if (n_src - 2 * k == 0) return pf_vec3_make(PF_R(0.5), PF_R(0.5), PF_R(0.0));
    return pf_vec3_make(PF_R(k - jc) / n, PF_R(k) / n, PF_R(jc + 1) / n);
}

/* ---------------------------------------------------------------- reductions and sampling
   For every linear moment type T: the 2x2 box of an even mip level, the 3-texel and 9-texel
   weighted sums of odd levels (weights from pf_mip_weights3; reduce3x3 applies wx along rows
   and wy across them: t<col><row>), N texels by accumulation (acc + w t, then scale by
   1/sum(w)), and the lerp / bilinear interpolation of a sampler. Each operation is written
   once, below, from the type's own _add and _scale (V: pf_vec3 for the average normals), and
   every typed function is that body: so a fix lands once and every type computes exactly the
   same sums in the same order. Weights are applied to each texel before summing (w a + w b,
   see CONVENTIONS): a + w b is V_add(a, V_scale(b, w)), never V_scale(V_add(a, b), w). The
   bodies are macros (GLSL has no generics; its preprocessor pastes ## like C's). */
#define PFI_MOM_LERP(V) { return V##_add(V##_scale(a, PF_R(1.0) - t), V##_scale(b, t)); }
#define PFI_MOM_REDUCE2X2(V)                                                                   \
    { return V##_add(V##_add(V##_add(V##_scale(a, PF_R(0.25)), V##_scale(b, PF_R(0.25))),       \
                             V##_scale(c, PF_R(0.25))), V##_scale(d, PF_R(0.25))); }
#define PFI_MOM_REDUCE3(V) { return V##_add(V##_add(V##_scale(a, w.x), V##_scale(b, w.y)), V##_scale(c, w.z)); }
#define PFI_MOM_REDUCE3X3(F)                                                                   \
    { return F##_reduce3(F##_reduce3(t00, t10, t20, wx), F##_reduce3(t01, t11, t21, wx),       \
                         F##_reduce3(t02, t12, t22, wx), wy); }
#define PFI_MOM_ACCUMULATE(V) { return V##_add(acc, V##_scale(t, w)); }
#define PFI_MOM_BILINEAR(F) { return F##_lerp(F##_lerp(t00, t10, fx), F##_lerp(t01, t11, fx), fy); }

/* ---- pf_slope_moments: five slope moments (pf_beckmann.h) */
PF_DEF pf_slope_moments pf_slope_moments_lerp(pf_slope_moments a, pf_slope_moments b, pf_real t)
PFI_MOM_LERP(pf_slope_moments)
PF_DEF pf_slope_moments pf_slope_moments_reduce2x2(pf_slope_moments a, pf_slope_moments b,
                                                   pf_slope_moments c, pf_slope_moments d)
PFI_MOM_REDUCE2X2(pf_slope_moments)
PF_DEF pf_slope_moments pf_slope_moments_reduce3(pf_slope_moments a, pf_slope_moments b,
                                                 pf_slope_moments c, pf_vec3 w)
PFI_MOM_REDUCE3(pf_slope_moments)
PF_DEF pf_slope_moments pf_slope_moments_reduce3x3(pf_slope_moments t00, pf_slope_moments t10,
    pf_slope_moments t20, pf_slope_moments t01, pf_slope_moments t11, pf_slope_moments t21,
    pf_slope_moments t02, pf_slope_moments t12, pf_slope_moments t22, pf_vec3 wx, pf_vec3 wy)
PFI_MOM_REDUCE3X3(pf_slope_moments)
PF_DEF pf_slope_moments pf_slope_moments_accumulate(pf_slope_moments acc, pf_slope_moments t, pf_real w)
PFI_MOM_ACCUMULATE(pf_slope_moments)
PF_DEF pf_slope_moments pf_slope_moments_bilinear(pf_slope_moments t00, pf_slope_moments t10,
    pf_slope_moments t01, pf_slope_moments t11, pf_real fx, pf_real fy)
PFI_MOM_BILINEAR(pf_slope_moments)

/* ---- pf_scalar_moments: scalar-map moments */
PF_DEF pf_scalar_moments pf_scalar_moments_lerp(pf_scalar_moments a, pf_scalar_moments b, pf_real t)
PFI_MOM_LERP(pf_scalar_moments)
PF_DEF pf_scalar_moments pf_scalar_moments_reduce2x2(pf_scalar_moments a, pf_scalar_moments b,
                                                     pf_scalar_moments c, pf_scalar_moments d)
PFI_MOM_REDUCE2X2(pf_scalar_moments)
PF_DEF pf_scalar_moments pf_scalar_moments_reduce3(pf_scalar_moments a, pf_scalar_moments b,
                                                   pf_scalar_moments c, pf_vec3 w)
PFI_MOM_REDUCE3(pf_scalar_moments)
PF_DEF pf_scalar_moments pf_scalar_moments_reduce3x3(pf_scalar_moments t00, pf_scalar_moments t10,
    pf_scalar_moments t20, pf_scalar_moments t01, pf_scalar_moments t11, pf_scalar_moments t21,
    pf_scalar_moments t02, pf_scalar_moments t12, pf_scalar_moments t22, pf_vec3 wx, pf_vec3 wy)
PFI_MOM_REDUCE3X3(pf_scalar_moments)
PF_DEF pf_scalar_moments pf_scalar_moments_accumulate(pf_scalar_moments acc, pf_scalar_moments t, pf_real w)
PFI_MOM_ACCUMULATE(pf_scalar_moments)
PF_DEF pf_scalar_moments pf_scalar_moments_bilinear(pf_scalar_moments t00, pf_scalar_moments t10,
    pf_scalar_moments t01, pf_scalar_moments t11, pf_real fx, pf_real fy)
PFI_MOM_BILINEAR(pf_scalar_moments)

/* ---- pf_depth_moments2: VSM / EVSM-2 moments */
PF_DEF pf_depth_moments2 pf_depth_moments2_lerp(pf_depth_moments2 a, pf_depth_moments2 b, pf_real t)
PFI_MOM_LERP(pf_depth_moments2)
PF_DEF pf_depth_moments2 pf_depth_moments2_reduce2x2(pf_depth_moments2 a, pf_depth_moments2 b,
                                                     pf_depth_moments2 c, pf_depth_moments2 d)
PFI_MOM_REDUCE2X2(pf_depth_moments2)
PF_DEF pf_depth_moments2 pf_depth_moments2_reduce3(pf_depth_moments2 a, pf_depth_moments2 b,
                                                   pf_depth_moments2 c, pf_vec3 w)
PFI_MOM_REDUCE3(pf_depth_moments2)
PF_DEF pf_depth_moments2 pf_depth_moments2_reduce3x3(pf_depth_moments2 t00, pf_depth_moments2 t10,
    pf_depth_moments2 t20, pf_depth_moments2 t01, pf_depth_moments2 t11, pf_depth_moments2 t21,
    pf_depth_moments2 t02, pf_depth_moments2 t12, pf_depth_moments2 t22, pf_vec3 wx, pf_vec3 wy)
PFI_MOM_REDUCE3X3(pf_depth_moments2)
PF_DEF pf_depth_moments2 pf_depth_moments2_accumulate(pf_depth_moments2 acc, pf_depth_moments2 t, pf_real w)
PFI_MOM_ACCUMULATE(pf_depth_moments2)
PF_DEF pf_depth_moments2 pf_depth_moments2_bilinear(pf_depth_moments2 t00, pf_depth_moments2 t10,
    pf_depth_moments2 t01, pf_depth_moments2 t11, pf_real fx, pf_real fy)
PFI_MOM_BILINEAR(pf_depth_moments2)

/* ---- pf_depth_moments4: MSM power moments */
PF_DEF pf_depth_moments4 pf_depth_moments4_lerp(pf_depth_moments4 a, pf_depth_moments4 b, pf_real t)
PFI_MOM_LERP(pf_depth_moments4)
PF_DEF pf_depth_moments4 pf_depth_moments4_reduce2x2(pf_depth_moments4 a, pf_depth_moments4 b,
                                                     pf_depth_moments4 c, pf_depth_moments4 d)
PFI_MOM_REDUCE2X2(pf_depth_moments4)
PF_DEF pf_depth_moments4 pf_depth_moments4_reduce3(pf_depth_moments4 a, pf_depth_moments4 b,
                                                   pf_depth_moments4 c, pf_vec3 w)
PFI_MOM_REDUCE3(pf_depth_moments4)
PF_DEF pf_depth_moments4 pf_depth_moments4_reduce3x3(pf_depth_moments4 t00, pf_depth_moments4 t10,
    pf_depth_moments4 t20, pf_depth_moments4 t01, pf_depth_moments4 t11, pf_depth_moments4 t21,
    pf_depth_moments4 t02, pf_depth_moments4 t12, pf_depth_moments4 t22, pf_vec3 wx, pf_vec3 wy)
PFI_MOM_REDUCE3X3(pf_depth_moments4)
PF_DEF pf_depth_moments4 pf_depth_moments4_accumulate(pf_depth_moments4 acc, pf_depth_moments4 t, pf_real w)
PFI_MOM_ACCUMULATE(pf_depth_moments4)
PF_DEF pf_depth_moments4 pf_depth_moments4_bilinear(pf_depth_moments4 t00, pf_depth_moments4 t10,
    pf_depth_moments4 t01, pf_depth_moments4 t11, pf_real fx, pf_real fy)
PFI_MOM_BILINEAR(pf_depth_moments4)

/* ---- pf_evsm_moments: EVSM-4 moments */
/* Midpoint (a + b)/2 of two values of the same sign, as a + (b - a)/2: |b - a| <= max(|a|, |b|),
   so nothing overflows. */
PF_DEF pf_real pfi_midpoint(pf_real a, pf_real b) { return a + PF_R(0.5) * (b - a); }
PF_DEF pf_evsm_moments pfi_evsm_moments_midpoint(pf_evsm_moments a, pf_evsm_moments b)
{
    return pf_evsm_moments_make(pfi_midpoint(a.pos1, b.pos1), pfi_midpoint(a.pos2, b.pos2),
                                pfi_midpoint(a.neg1, b.neg1), pfi_midpoint(a.neg2, b.neg2));
}

PF_DEF pf_evsm_moments pf_evsm_moments_lerp(pf_evsm_moments a, pf_evsm_moments b, pf_real t)
PFI_MOM_LERP(pf_evsm_moments)
/* The 2x2 box as midpoints of midpoints, not q a + q b + q c + q d: with one constant weight
   q, -ffast-math (and GPU compilers, which reassociate freely) factor that sum into
   q (a + b + c + d), and four second moments near exp(2c) = 1.6e38 (c = 44) overflow the
   float sum (the sweep found 14 inf per 10^6 under gcc -ffast-math). A compiler does not
   distribute the half over b - a, so the midpoint form stays finite in every build. Each
   member of an EVSM texel has one sign (pos1, pos2, neg2 >= 0, neg1 <= 0), as the
   midpoints need; error <= 2 ulp (tests/test_moments.c). Two operations more per member
   than the weighted sum. */
PF_DEF pf_evsm_moments pf_evsm_moments_reduce2x2(pf_evsm_moments a, pf_evsm_moments b,
                                                 pf_evsm_moments c, pf_evsm_moments d)
{
    return pfi_evsm_moments_midpoint(pfi_evsm_moments_midpoint(a, b), pfi_evsm_moments_midpoint(c, d));
}
PF_DEF pf_evsm_moments pf_evsm_moments_reduce3(pf_evsm_moments a, pf_evsm_moments b,
                                               pf_evsm_moments c, pf_vec3 w)
PFI_MOM_REDUCE3(pf_evsm_moments)
PF_DEF pf_evsm_moments pf_evsm_moments_reduce3x3(pf_evsm_moments t00, pf_evsm_moments t10,
    pf_evsm_moments t20, pf_evsm_moments t01, pf_evsm_moments t11, pf_evsm_moments t21,
    pf_evsm_moments t02, pf_evsm_moments t12, pf_evsm_moments t22, pf_vec3 wx, pf_vec3 wy)
PFI_MOM_REDUCE3X3(pf_evsm_moments)
PF_DEF pf_evsm_moments pf_evsm_moments_accumulate(pf_evsm_moments acc, pf_evsm_moments t, pf_real w)
PFI_MOM_ACCUMULATE(pf_evsm_moments)
PF_DEF pf_evsm_moments pf_evsm_moments_bilinear(pf_evsm_moments t00, pf_evsm_moments t10,
    pf_evsm_moments t01, pf_evsm_moments t11, pf_real fx, pf_real fy)
PFI_MOM_BILINEAR(pf_evsm_moments)

/* ---- pf_vec3: unnormalized average normals (Toksvig); linear algebra from pf_core.h */
PF_DEF pf_vec3 pf_normal_avg_lerp(pf_vec3 a, pf_vec3 b, pf_real t)
PFI_MOM_LERP(pf_vec3)
PF_DEF pf_vec3 pf_normal_avg_reduce2x2(pf_vec3 a, pf_vec3 b, pf_vec3 c, pf_vec3 d)
PFI_MOM_REDUCE2X2(pf_vec3)
PF_DEF pf_vec3 pf_normal_avg_reduce3(pf_vec3 a, pf_vec3 b, pf_vec3 c, pf_vec3 w)
PFI_MOM_REDUCE3(pf_vec3)
PF_DEF pf_vec3 pf_normal_avg_reduce3x3(pf_vec3 t00, pf_vec3 t10, pf_vec3 t20, pf_vec3 t01, pf_vec3 t11,
    pf_vec3 t21, pf_vec3 t02, pf_vec3 t12, pf_vec3 t22, pf_vec3 wx, pf_vec3 wy)
PFI_MOM_REDUCE3X3(pf_normal_avg)
PF_DEF pf_vec3 pf_normal_avg_accumulate(pf_vec3 acc, pf_vec3 t, pf_real w)
PFI_MOM_ACCUMULATE(pf_vec3)
PF_DEF pf_vec3 pf_normal_avg_bilinear(pf_vec3 t00, pf_vec3 t10, pf_vec3 t01, pf_vec3 t11, pf_real fx,
                                      pf_real fy)
PFI_MOM_BILINEAR(pf_normal_avg)

/* ---------------------------------------------------------------- ESM in log space
   An ESM texel stores l = c z (pf_esm_log_from_depth) instead of exp(c z). A reduction
   computes log(sum_i w_i exp(l_i)) as m + log(sum_i w_i exp(l_i - m)) with m the largest l
   among the texels of positive weight: every exponential is <= 1 and the sum is in
   (0, sum w], so the result is finite for any finite l and any c (exp(c z) itself overflows
   float for c z > 88.7). The result is the log of the weighted mean when the weights sum to
   1. Texels of zero weight are skipped (not even their exponential is formed). */

/* Floor of the exponent arguments l - m (<= 0) in the sums below: exp(-80) = 1.8e-35 is below
   the rounding of any sum that holds a 1 (float and double), and stopping there keeps every
   exponential normal (libm's underflow path is slow, and subnormals are slow on most CPUs). */
#define PFI_LSE_ARG_MIN PF_R(-80.0)

/* d floored at PFI_LSE_ARG_MIN; NaN stays NaN (so a NaN texel still propagates). */
PF_DEF pf_real pfi_lse_arg(pf_real d) { return d < PFI_LSE_ARG_MIN ? PFI_LSE_ARG_MIN : d; }
/* log of the mean of exp(l) over 4 texels (the 2x2 box). */
PF_DEF pf_real pf_esm_log_reduce2x2(pf_real l0, pf_real l1, pf_real l2, pf_real l3)
{
    pf_real m = pf_max(pf_max(l0, l1), pf_max(l2, l3));
    pf_real s = PF_R(0.25) * PF_EXP(pfi_lse_arg(l0 - m))
              + PF_R(0.25) * PF_EXP(pfi_lse_arg(l1 - m))
              + PF_R(0.25) * PF_EXP(pfi_lse_arg(l2 - m))
              + PF_R(0.25) * PF_EXP(pfi_lse_arg(l3 - m));
    return m + PF_LOG(s);
}

/* log(w.x exp(l0) + w.y exp(l1) + w.z exp(l2)), weights >= 0. All weights <= 0 (or NaN):
   -PF_REAL_MAX (the log of an empty sum, kept finite). */
PF_DEF pf_real pf_esm_log_reduce3(pf_real l0, pf_real l1, pf_real l2, pf_vec3 w)
{
    pf_real m = -PF_REAL_MAX;
    pf_real s;
    if (w.x > PF_R(0.0) && l0 > m) m = l0;
    if (w.y > PF_R(0.0) && l1 > m) m = l1;
    if (w.z > PF_R(0.0) && l2 > m) m = l2;
    s = (w.x > PF_R(0.0) ? w.x * PF_EXP(pfi_lse_arg(l0 - m)) : PF_R(0.0))
      + (w.y > PF_R(0.0) ? w.y * PF_EXP(pfi_lse_arg(l1 - m)) : PF_R(0.0))
      + (w.z > PF_R(0.0) ? w.z * PF_EXP(pfi_lse_arg(l2 - m)) : PF_R(0.0));
    return s > PF_R(0.0) ? m + PF_LOG(s) : (s == s ? -PF_REAL_MAX : s);
}

/* 9 texels, separable weights (wx along rows, wy across rows; t<col><row>). */
PF_DEF pf_real pf_esm_log_reduce3x3(pf_real t00, pf_real t10, pf_real t20, pf_real t01,
                                    pf_real t11, pf_real t21, pf_real t02, pf_real t12,
                                    pf_real t22, pf_vec3 wx, pf_vec3 wy)
{
    pf_real r0 = wy.x > PF_R(0.0) ? pf_esm_log_reduce3(t00, t10, t20, wx) : PF_R(0.0);
    pf_real r1 = wy.y > PF_R(0.0) ? pf_esm_log_reduce3(t01, t11, t21, wx) : PF_R(0.0);
    pf_real r2 = wy.z > PF_R(0.0) ? pf_esm_log_reduce3(t02, t12, t22, wx) : PF_R(0.0);
    return pf_esm_log_reduce3(r0, r1, r2, wy);
}

/* What a bilinear sampler returns for an ESM map, in log space:
   log((1-fx)(1-fy) e^t00 + fx (1-fy) e^t10 + (1-fx) fy e^t01 + fx fy e^t11). */
PF_DEF pf_real pf_esm_log_bilinear(pf_real t00, pf_real t10, pf_real t01, pf_real t11,
                                   pf_real fx, pf_real fy)
{
    pf_real gx = PF_R(1.0) - fx, gy = PF_R(1.0) - fy;
    pf_real r0 = pf_esm_log_reduce3(t00, t10, t10, pf_vec3_make(gx, fx, PF_R(0.0)));
    pf_real r1 = pf_esm_log_reduce3(t01, t11, t11, pf_vec3_make(gx, fx, PF_R(0.0)));
    return pf_esm_log_reduce3(r0, r1, r1, pf_vec3_make(gy, fy, PF_R(0.0)));
}

/* Streaming log-sum-exp over N texels: lmax is the largest log seen, sum = sum_i w_i
   exp(l_i - lmax), weight = sum_i w_i. Start from PF_ESM_LOG_SUM_EMPTY (or
   pf_esm_log_sum_first), add texels with
   pf_esm_log_sum_add, read log(sum w e^l / sum w) with pf_esm_log_sum_mean. */
PF_STRUCT_BEGIN(pf_esm_log_sum)
    pf_real lmax;
    pf_real sum;
    pf_real weight;
PF_STRUCT_END(pf_esm_log_sum)

PF_DEF pf_esm_log_sum pf_esm_log_sum_make(pf_real lmax, pf_real sum, pf_real weight)
{ pf_esm_log_sum a; a.lmax = lmax; a.sum = sum; a.weight = weight; return a; }
/* The empty sum (a macro, not a function: the shader subset has no zero-argument functions
   in the portability generator). */
#define PF_ESM_LOG_SUM_EMPTY pf_esm_log_sum_make(-PF_REAL_MAX, PF_R(0.0), PF_R(0.0))

/* The sum of one texel l of weight w > 0 (a start without the empty state). */
PF_DEF pf_esm_log_sum pf_esm_log_sum_first(pf_real l, pf_real w)
{ return w > PF_R(0.0) ? pf_esm_log_sum_make(l, w, w) : PF_ESM_LOG_SUM_EMPTY; }
/* Adds texel l with weight w (w <= 0 or NaN: skipped). When l is a new maximum the running
   sum is rescaled by exp(old max - l) <= 1, so nothing grows beyond sum(w). */
PF_DEF pf_esm_log_sum pf_esm_log_sum_add(pf_esm_log_sum a, pf_real l, pf_real w)
{
    if (!(w > PF_R(0.0))) return a;
    if (l > a.lmax) {
        a.sum = a.sum * PF_EXP(pfi_lse_arg(a.lmax - l)) + w;
        a.lmax = l;
    } else {
        a.sum = a.sum + w * PF_EXP(pfi_lse_arg(l - a.lmax));
    }
    a.weight = a.weight + w;
    return a;
}

/* log of the weighted mean of exp(l): lmax + log(sum / weight). Empty: -PF_REAL_MAX. */
PF_DEF pf_real pf_esm_log_sum_mean(pf_esm_log_sum a)
{
    if (!(a.weight > PF_R(0.0))) return -PF_REAL_MAX;
    return a.lmax + PF_LOG(a.sum / a.weight);
}

/* ---------------------------------------------------------------- slopes from a height map
   Central difference (second order, error (d^2/6) h''' + O(d^4)) and the one-sided
   second-order difference used on a clamped border; d is the texel spacing. */
PF_DEF pf_real pf_height_slope_central(pf_real h_minus, pf_real h_plus, pf_real spacing)
{ return (h_plus - h_minus) / (PF_R(2.0) * spacing); }
/* Slope at h0 from h0, h1, h2 at 0, d, 2d: (-3 h0 + 4 h1 - h2) / (2 d) (error (d^2/3) h'''). For
   the far border pass the texels in reverse order and negate. */
PF_DEF pf_real pf_height_slope_edge(pf_real h0, pf_real h1, pf_real h2, pf_real spacing)
{ return (PF_R(4.0) * h1 - PF_R(3.0) * h0 - h2) / (PF_R(2.0) * spacing); }
/* Slope moments of an interior texel of a height map from its four neighbours (left, right,
   below, above) by central differences: slope = height_scale * (dh/dx, dh/dy)
   (Dupuy et al. 2013 sec. 4.2; height scaling multiplies slopes by the scale and the
   second moments by its square). texel_size_x/y: texel spacing in surface units. */
PF_DEF pf_slope_moments pf_slope_moments_from_heights(pf_real h_xm, pf_real h_xp, pf_real h_ym,
                                                      pf_real h_yp, pf_real texel_size_x,
                                                      pf_real texel_size_y, pf_real height_scale)
{
    pf_real sx = height_scale * pf_height_slope_central(h_xm, h_xp, texel_size_x);
    pf_real sy = height_scale * pf_height_slope_central(h_ym, h_yp, texel_size_y);
    return pf_slope_moments_from_slope(sx, sy);
}

/* ================================================================ CPU only
   Everything below walks caller-owned buffers (pointers, loops over a whole map). It is C/C++
   host code: linkage PF_CPU_DEF (pf_core.h: static inline by default, never __device__),
   compiled out under PF_GLSL. Nothing allocates: the caller provides every buffer. Arguments
   follow pf_core.h's "sizes and errors" rules; the limits of each function are in CONVENTIONS
   (Limits and errors) and in its comment. */
#ifndef PF_GLSL

/* Border handling of the height-map stencils and of sampling (any other value: PF_ERR_ARG). */
#define PF_BORDER_CLAMP 0
#define PF_BORDER_WRAP 1

/* Depth-moment kinds of pf_depth_pyramid_from_depths (channels in brackets). */
#define PF_DEPTH_VSM 0     /* [2] z, z^2                                 pf_depth_moments2 */
#define PF_DEPTH_EVSM2 1   /* [2] p, p^2, p = exp(c_pos (2z - 1))        pf_depth_moments2 */
#define PF_DEPTH_EVSM4 2   /* [4] p, p^2, n, n^2, n = -exp(-c_neg (2z-1)) pf_evsm_moments */
#define PF_DEPTH_MSM 3     /* [4] z, z^2, z^3, z^4                       pf_depth_moments4 */
#define PF_DEPTH_ESM_LOG 4 /* [1] c_pos z, reduced with log-sum-exp      pf_esm_log_* */

/* More levels than any int-sized map has (2^31 texels on a side gives 32). */
#define PF_MIP_MAX_LEVELS 32

/* ---------------------------------------------------------------- pyramid layout */
/* Number of levels of a w x h pyramid, the 1 x 1 top included (0 if w < 1 or h < 1). */
PF_CPU_DEF int pf_mip_level_count(int w, int h)
{
    int n = 0;
    if (w < 1 || h < 1) return 0;
    for (;;) {
        ++n;
        if (w == 1 && h == 1) return n;
        w = pf_mip_next_size(w);
        h = pf_mip_next_size(h);
    }
}

/* Size along one axis at a level: n halved (floor, never below 1) level times. */
PF_CPU_DEF int pf_mip_level_size(int n, int level)
{
    int l;
    if (n < 1) return 0;
    for (l = 0; l < level && n > 1; ++l) n = pf_mip_next_size(n);
    return n;
}

/* Where level `level` starts, in texels from the start of the pyramid (multiply by the
   channel count for pf_reals). level >= pf_mip_level_count gives the total. Any int w, h:
   the sum stays below 2^63. */
PF_CPU_DEF long long pf_mip_level_offset(int w, int h, int level)
{
    long long off = 0;
    int l, nl = pf_mip_level_count(w, h);
    for (l = 0; l < level && l < nl; ++l) {
        off += (long long)w * (long long)h;
        w = pf_mip_next_size(w);
        h = pf_mip_next_size(h);
    }
    return off;
}

/* PF_OK when p is not NULL and a w x h pyramid of `channels` channels is within the limits:
   PF_ERR_ARG for NULL, w, h or channels < 1; PF_ERR_SIZE for a side above PF_MAX_SIDE or more
   than PF_MAX_REALS pf_reals. */
PF_CPU_DEF int pfi_mip_check(const void *p, int w, int h, int channels)
{
    if (!p || w < 1 || h < 1 || channels < 1) return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h)) return PF_ERR_SIZE;
    return pf_size_mul(pf_mip_level_offset(w, h, PF_MIP_MAX_LEVELS), channels) < 0 ? PF_ERR_SIZE : PF_OK;
}

/* Texels of the whole pyramid of a w x h base (all levels, one buffer); the buffer holds
   pf_mip_texel_count(w, h) * channels pf_reals. 0 for every size the builders reject: w or
   h < 1 or > PF_MAX_SIDE, or more than PF_MAX_REALS texels. */
PF_CPU_DEF long long pf_mip_texel_count(int w, int h)
{ return pfi_mip_check(&w, w, h, 1) == PF_OK ? pf_mip_level_offset(w, h, PF_MIP_MAX_LEVELS) : 0; }

/* ---------------------------------------------------------------- level reduction (private)
   The pyramid is reduced as a cascade over rows: as soon as the source rows a destination
   row needs are complete (2j, 2j+1 and, for odd heights, 2j+2), that row is reduced, and the
   same check runs one level up. Level l+1 is therefore computed while the rows of level l it
   reads are still in cache, and a pyramid built from a height or depth map costs about one
   pass over memory. */
typedef struct pfi_mip_cascade {
    pf_real *pyr;
    int channels;
    int log_space;
    int levels;
    int lw[PF_MIP_MAX_LEVELS];
    int lh[PF_MIP_MAX_LEVELS];
    int next_row[PF_MIP_MAX_LEVELS];
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
    c->pyr = pyr;
    c->channels = channels;
    c->log_space = log_space;
    for (l = 0; l < c->levels; ++l) {
        c->lw[l] = w;
        c->lh[l] = h;
        c->next_row[l] = 0;
        c->off[l] = off;
        off += (long long)w * (long long)h * (long long)channels;
        w = pf_mip_next_size(w);
        h = pf_mip_next_size(h);
    }
    return PF_OK;
}

/* The 2x2 box with a compile-time channel count (the common case: both sizes even).
   Under -ffast-math the compiler factors q a + q b + q c + q d into q (a + b + c + d), which
   overflows for texels above PF_REAL_MAX / 4 (an EVSM-4 pyramid at the largest float exponent
   holds 1.65e38); there each pair is averaged as a midpoint instead: a + (b - a)/2 when a and b
   have one sign (|b - a| <= max(|a|, |b|)), (a + b)/2 when they have opposite signs (|a + b|
   <= max(|a|, |b|)), which no reassociation turns into an overflowing sum. Plain builds keep
   the four products (IEEE order, no overflow, and the fastest loop). */
#ifdef __FAST_MATH__
PF_CPU_DEF pf_real pfi_mip_mid(pf_real a, pf_real b)
{
    return (a >= PF_R(0.0)) == (b >= PF_R(0.0)) ? a + PF_R(0.5) * (b - a) : PF_R(0.5) * (a + b);
}
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
   lies between the smallest and the largest tap, so s is clamped there (NaN stays NaN). Only
   called when s is not finite. */
PF_CPU_DEF pf_real pfi_taps_clamp(pf_real s, const pf_real *const *tap, int n, long long k)
{
    pf_real lo = tap[0][k], hi = tap[0][k];
    int t;
    for (t = 1; t < n; ++t) {
        lo = pf_min(lo, tap[t][k]);
        hi = pf_max(hi, tap[t][k]);
    }
    return pf_clamp(s, lo, hi);
}

/* Reduces row j of level l + 1 from level l. */
PF_CPU_DEF void pfi_mip_reduce_row(const pfi_mip_cascade *c, int l, int j)
{
    const int nc = c->channels, sw = c->lw[l], sh = c->lh[l], dw = c->lw[l + 1];
    const pf_real *src = c->pyr + c->off[l];
    pf_real *dst = c->pyr + c->off[l + 1] + (long long)j * dw * nc;
    const pf_real *rows[3];
    pf_real wy[3];
    pf_vec3 v = pf_mip_weights3(j, sh);
    int ny = pfi_mip_taps(sh), nx = pfi_mip_taps(sw), b, a, k;
    long long i;
    wy[0] = v.x;
    wy[1] = v.y;
    wy[2] = v.z;
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
    for (i = 0; i < dw; ++i) {
        pf_real wx[3], wt[9];
        const pf_real *tap[9];
        int nt = 0;
        v = pf_mip_weights3((int)i, sw);
        wx[0] = v.x;
        wx[1] = v.y;
        wx[2] = v.z;
        for (b = 0; b < ny; ++b)
            for (a = 0; a < nx; ++a) {
                wt[nt] = wy[b] * wx[a];
                tap[nt] = rows[b] + (2 * i + a) * nc;
                ++nt;
            }
        for (k = 0; k < nc; ++k) {
            pf_real s = PF_R(0.0);
            int t;
            if (!c->log_space) {
                for (t = 0; t < nt; ++t) s += wt[t] * tap[t][k];
                if (!(s >= -PF_REAL_MAX && s <= PF_REAL_MAX)) s = pfi_taps_clamp(s, tap, nt, k);
                dst[i * nc + k] = s;
            } else {
                pf_real m = -PF_REAL_MAX;
                for (t = 0; t < nt; ++t)
                    if (tap[t][k] > m) m = tap[t][k];
                for (t = 0; t < nt; ++t) s += wt[t] * PF_EXP(pfi_lse_arg(tap[t][k] - m));
                /* s >= the largest weight > 0 unless a tap is NaN, which then propagates */
                dst[i * nc + k] = m + PF_LOG(s);
            }
        }
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
        c->next_row[l + 1] = j + 1;
        ++l;
        r = j;
    }
}

/* ---------------------------------------------------------------- building
   Every builder returns PF_OK, or PF_ERR_ARG / PF_ERR_SIZE (CONVENTIONS) having written
   nothing. pyr always holds pf_mip_texel_count(w, h) * channels pf_reals. */
PF_CPU_DEF int pfi_mip_build(pf_real *pyr, int w, int h, int channels, int log_space)
{
    pfi_mip_cascade c;
    int r, rc = pfi_mip_cascade_init(&c, pyr, w, h, channels, log_space);
    if (rc != PF_OK) return rc;
    for (r = 0; r < h; ++r) pfi_mip_push_row(&c, 0, r);
    return PF_OK;
}

/* Builds levels 1 .. top of a pyramid whose level 0 (w x h texels of `channels` interleaved
   pf_reals, at the start of pyr) the caller has filled. Works for every linear moment type
   (the channel count says which). */
PF_CPU_DEF int pf_mip_build(pf_real *pyr, int w, int h, int channels)
{ return pfi_mip_build(pyr, w, h, channels, 0); }
/* The same for log-space ESM maps: every channel is reduced with log-sum-exp (each level
   holds log of the mean of exp over its footprint). */
PF_CPU_DEF int pf_mip_build_log(pf_real *pyr, int w, int h, int channels)
{ return pfi_mip_build(pyr, w, h, channels, 1); }
/* Row r of the slope-moment map of a height map (5 channels), see CONVENTIONS. */
PF_CPU_DEF void pfi_slope_row(const pf_real *heights, int w, int h, int r, pf_real dx, pf_real dy,
                              pf_real height_scale, int border, pf_real *out)
{
    /* y derivative as c0 R0[i] + c1 R1[i] + c2 R2[i] (scaled by height_scale / (2 dy)) */
    const pf_real ky = height_scale / (PF_R(2.0) * dy), kx = height_scale / (PF_R(2.0) * dx);
    const pf_real *r0 = heights + (long long)r * w, *r1 = r0, *r2 = r0;
    const pf_real *row = r0;
    pf_real c0 = PF_R(0.0), c1 = PF_R(0.0), c2 = PF_R(0.0);
    int i;
    if (h >= 2) {
        if (border == PF_BORDER_WRAP || (r > 0 && r < h - 1)) {
            r0 = heights + pfi_wrap_index((long long)r - 1, h) * w;
            r1 = heights + pfi_wrap_index((long long)r + 1, h) * w;
            c0 = -ky;
            c1 = ky;
        } else if (h == 2) { /* (h1 - h0) / dy at both rows */
            r0 = heights;
            r1 = heights + w;
            c0 = -PF_R(2.0) * ky;
            c1 = PF_R(2.0) * ky;
        } else if (r == 0) { /* (-3 h0 + 4 h1 - h2) / (2 dy) */
            r0 = heights;
            r1 = heights + w;
            r2 = heights + 2LL * w;
            c0 = -PF_R(3.0) * ky;
            c1 = PF_R(4.0) * ky;
            c2 = -ky;
        } else { /* last row: (3 h[n-1] - 4 h[n-2] + h[n-3]) / (2 dy) */
            r0 = heights + (long long)(h - 1) * w;
            r1 = heights + (long long)(h - 2) * w;
            r2 = heights + (long long)(h - 3) * w;
            c0 = PF_R(3.0) * ky;
            c1 = -PF_R(4.0) * ky;
            c2 = ky;
        }
    }
    /* interior texels: branch-free, so the compiler can vectorize the row */
    for (i = 1; i < w - 1; ++i) {
        pf_real sx = kx * (row[i + 1] - row[i - 1]);
        pf_real sy = c0 * r0[i] + c1 * r1[i] + c2 * r2[i];
        pf_real *o = out + 5 * i;
        o[0] = sx;
        o[1] = sy;
        o[2] = sx * sx;
        o[3] = sy * sy;
        o[4] = sx * sy;
    }
    /* the first and last texels of the row */
    for (i = 0; i < w; i = (i == 0 && w > 1) ? w - 1 : w) {
        pf_real sx, sy = c0 * r0[i] + c1 * r1[i] + c2 * r2[i];
        pf_real *o = out + 5 * i;
        if (w == 1) {
            sx = PF_R(0.0);
        } else if (border == PF_BORDER_WRAP) {
            sx = kx * (row[pfi_wrap_index((long long)i + 1, w)] - row[pfi_wrap_index((long long)i - 1, w)]);
        } else if (w == 2) {
            sx = PF_R(2.0) * kx * (row[1] - row[0]);
        } else if (i == 0) {
            sx = kx * (PF_R(4.0) * row[1] - PF_R(3.0) * row[0] - row[2]);
        } else {
            sx = kx * (PF_R(3.0) * row[w - 1] - PF_R(4.0) * row[w - 2] + row[w - 3]);
        }
        o[0] = sx;
        o[1] = sy;
        o[2] = sx * sx;
        o[3] = sy * sy;
        o[4] = sx * sy;
    }
}

/* Level 0 only: the slope moments (5 interleaved channels, pf_slope_moments order) of every
   texel of a w x h height map, into out (w h 5 pf_reals). heights: w h pf_reals, row-major.
   dx, dy: texel spacing; height_scale multiplies the heights; border: PF_BORDER_WRAP or
   PF_BORDER_CLAMP (see CONVENTIONS for the stencils). PF_ERR_ARG: NULL, w or h < 1, another
   border; PF_ERR_SIZE: a side above PF_MAX_SIDE or w h 5 > PF_MAX_REALS. */
PF_CPU_DEF int pf_slope_moments_map_from_heights(const pf_real *heights, int w, int h, pf_real dx,
                                                 pf_real dy, pf_real height_scale, int border,
                                                 pf_real *out)
{
    int r;
    if (!heights || !out || w < 1 || h < 1 || (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP))
        return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || pf_size_mul3(w, h, 5) < 0) return PF_ERR_SIZE;
    for (r = 0; r < h; ++r)
        pfi_slope_row(heights, w, h, r, dx, dy, height_scale, border, out + (long long)r * w * 5);
    return PF_OK;
}

/* The whole 5-moment pyramid of a height map in one pass: level 0 as
   pf_slope_moments_map_from_heights, every level above reduced as the rows arrive.
   pyr: pf_mip_texel_count(w, h) * 5 pf_reals. Errors as pf_mip_build, and PF_ERR_ARG for a
   NULL heights or another border. */
PF_CPU_DEF int pf_slope_pyramid_from_heights(const pf_real *heights, int w, int h, pf_real dx,
                                             pf_real dy, pf_real height_scale, int border,
                                             pf_real *pyr)
{
    pfi_mip_cascade c;
    int r, rc;
    if (!heights || (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP)) return PF_ERR_ARG;
    if ((rc = pfi_mip_cascade_init(&c, pyr, w, h, 5, 0)) != PF_OK) return rc;
    for (r = 0; r < h; ++r) {
        pfi_slope_row(heights, w, h, r, dx, dy, height_scale, border, pyr + (long long)r * w * 5);
        pfi_mip_push_row(&c, 0, r);
    }
    return PF_OK;
}

/* Channels per texel of a PF_DEPTH_* kind (0 for an unknown kind). */
PF_CPU_DEF int pf_depth_moment_channels(int kind)
{
    switch (kind) {
    case PF_DEPTH_VSM: return 2;
    case PF_DEPTH_EVSM2: return 2;
    case PF_DEPTH_EVSM4: return 4;
    case PF_DEPTH_MSM: return 4;
    case PF_DEPTH_ESM_LOG: return 1;
    default: return 0;
    }
}

/* Stores a texel's members in order. */
PF_CPU_DEF void pfi_put_d2(pf_real *t, pf_depth_moments2 m) { t[0] = m.m1; t[1] = m.m2; }
PF_CPU_DEF void pfi_put_d4(pf_real *t, pf_depth_moments4 m) { t[0] = m.m1; t[1] = m.m2; t[2] = m.m3; t[3] = m.m4; }
PF_CPU_DEF void pfi_put_evsm(pf_real *t, pf_evsm_moments m) { t[0] = m.pos1; t[1] = m.pos2; t[2] = m.neg1; t[3] = m.neg2; }
/* The pyramid of a depth map (w h depths in [0, 1], row-major) for one PF_DEPTH_* kind:
   c_pos is the EVSM positive exponent and the ESM exponent, c_neg the EVSM negative one
   (ignored by the others). PF_DEPTH_ESM_LOG stores c_pos z and reduces in log space.
   pyr: pf_mip_texel_count(w, h) * pf_depth_moment_channels(kind) pf_reals. Errors as
   pf_mip_build, and PF_ERR_ARG for a NULL depths or an unknown kind. */
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
        default: for (i = 0; i < w; ++i) o[i] = pf_esm_log_from_depth(z[i], c_pos); break;
        }
        pfi_mip_push_row(&c, 0, r);
    }
    return PF_OK;
}

/* The pyramid of scalar-map moments (2 channels: f, f^2) of a w x h map of values: the same
   texels as PF_DEPTH_VSM's (z, z^2), so the same builder. Errors as pf_mip_build, and
   PF_ERR_ARG for a NULL values. */
PF_CPU_DEF int pf_scalar_pyramid_from_values(const pf_real *values, int w, int h, pf_real *pyr)
{ return pf_depth_pyramid_from_depths(values, w, h, PF_DEPTH_VSM, PF_R(0.0), PF_R(0.0), pyr); }
/* The pyramid of average normals (3 channels) of a normal map (w h normals, 3 interleaved
   pf_reals each; normalized here, so 8-bit-decoded normals may be passed as they are). Errors
   as pf_mip_build, and PF_ERR_ARG for a NULL normals. */
PF_CPU_DEF int pf_normal_pyramid_from_normals(const pf_real *normals, int w, int h, pf_real *pyr)
{
    pfi_mip_cascade c;
    int r, i, rc;
    if (!normals) return PF_ERR_ARG;
    if ((rc = pfi_mip_cascade_init(&c, pyr, w, h, 3, 0)) != PF_OK) return rc;
    for (r = 0; r < h; ++r) {
        const pf_real *n = normals + (long long)r * w * 3;
        pf_real *o = pyr + (long long)r * w * 3;
        for (i = 0; i < w; ++i) {
            pf_vec3 u = pf_normal_avg_from_normal(pf_vec3_make(n[3 * i], n[3 * i + 1], n[3 * i + 2]));
            o[3 * i] = u.x;
            o[3 * i + 1] = u.y;
            o[3 * i + 2] = u.z;
        }
        pfi_mip_push_row(&c, 0, r);
    }
    return PF_OK;
}

/* ---------------------------------------------------------------- N texels */
/* The largest positive weight of n (0 if none; NaN weights are skipped; +inf is returned). */
PF_CPU_DEF pf_real pfi_max_weight(const pf_real *weights, int n)
{
    pf_real m = PF_R(0.0);
    int i;
    for (i = 0; i < n; ++i)
        if (weights[i] > m) m = weights[i];
    return m;
}

/* The divisor that brings the weights to at most 2^32: wmax 2^-32 (exact) for wmax > 1, else
   wmax. Not wmax itself: 1/wmax is subnormal in float for wmax > 2^126, and -ffast-math turns
   w / wmax into w * (1/wmax) with subnormals flushed to 0 (every weight became 0); the
   reciprocal of this divisor is >= 2^-96, normal in float and double. */
PF_CPU_DEF pf_real pfi_weight_divisor(pf_real wmax)
{
    return wmax > PF_R(1.0) ? wmax * PF_R(2.3283064365386963e-10) : wmax; /* 2^-32 */
}

/* out[k] = sum_i w_i texels[i C + k] / sum_i w_i for n >= 0 texels of C = `channels` pf_reals
   (texels: n C pf_reals, weights: n, out: C). Texels with w_i <= 0 (or NaN) are skipped, not
   read. The weights are divided by the largest one (times 2^-32) first, so any finite weights
   work, under -ffast-math too (two weights of PF_REAL_MAX give the plain mean). No positive weight (n = 0 too): out is zeroed,
   PF_OK. PF_ERR_ARG: a NULL, channels < 1, n < 0, an infinite weight; PF_ERR_SIZE: n C >
   PF_MAX_REALS. */
PF_CPU_DEF int pf_moments_weighted_mean(const pf_real *texels, int channels, const pf_real *weights,
                                        int n, pf_real *out)
{
    pf_real wsum = PF_R(0.0), wmax, d;
    int i, k;
    if (!texels || !weights || !out || channels < 1 || n < 0) return PF_ERR_ARG;
    if (pf_size_mul(n, channels) < 0) return PF_ERR_SIZE;
    wmax = pfi_max_weight(weights, n);
    if (!(wmax <= PF_REAL_MAX)) return PF_ERR_ARG;
    for (k = 0; k < channels; ++k) out[k] = PF_R(0.0);
    if (!(wmax > PF_R(0.0))) return PF_OK;
    d = pfi_weight_divisor(wmax);
    for (i = 0; i < n; ++i)
        if (weights[i] > PF_R(0.0)) wsum += weights[i] / d; /* in [1, n 2^32] */
    for (i = 0; i < n; ++i) {
        /* volatile: -ffast-math would otherwise fold the two divisions into one by d wsum,
           which overflows for weights near PF_REAL_MAX (the issue 19 finding, back again) */
        volatile pf_real wd = weights[i] / d;
        pf_real w = wd / wsum;
        if (!(weights[i] > PF_R(0.0))) continue;
        for (k = 0; k < channels; ++k) out[k] += w * texels[(long long)i * channels + k];
    }
    return PF_OK;
}

/* log of the weighted mean of exp(l_i) (ESM, log space) over n texels, weights divided by the
   largest first as above. -PF_REAL_MAX if no weight is positive, and for bad arguments (a
   NULL, n < 0, an infinite weight). */
PF_CPU_DEF pf_real pf_esm_log_weighted_mean(const pf_real *logs, const pf_real *weights, int n)
{
    pf_esm_log_sum a = PF_ESM_LOG_SUM_EMPTY;
    pf_real wmax;
    int i;
    if (!logs || !weights || n < 0) return -PF_REAL_MAX;
    wmax = pfi_max_weight(weights, n);
    if (!(wmax > PF_R(0.0) && wmax <= PF_REAL_MAX)) return -PF_REAL_MAX;
    wmax = pfi_weight_divisor(wmax);
    for (i = 0; i < n; ++i) a = pf_esm_log_sum_add(a, logs[i], weights[i] / wmax);
    return pf_esm_log_sum_mean(a);
}

/* ---------------------------------------------------------------- sampling */
/* Texel indices and the fraction for coordinate u on an axis of n texels (GPU convention:
   centre of texel i at (i + 0.5)/n). CLAMP: u clamped to [0, 1] (infinities too), NaN is 0.
   WRAP: u - floor(u), computed in pf_real (exact: for |u| >= 2^23 in float, 2^52 in double, u
   is an integer and wraps to 0); NaN and infinities are 0. Indices in long long, in [0, n). */
PF_CPU_DEF void pfi_mip_axis(pf_real u, int n, int border, long long *i0, long long *i1, pf_real *f)
{
    pf_real x;
    long long i;
    if (border == PF_BORDER_WRAP) u = (u - u == PF_R(0.0)) ? u - PF_FLOOR(u) : PF_R(0.0);
    else u = (u == u) ? pf_clamp(u, PF_R(0.0), PF_R(1.0)) : PF_R(0.0);
    x = u * PF_R(n) - PF_R(0.5); /* in [-0.5, n - 0.5] */
    i = pfi_floor_index(x, -1, n - 1);
    *f = pf_clamp(x - PF_R(i), PF_R(0.0), PF_R(1.0));
    if (border == PF_BORDER_WRAP) {
        *i0 = pfi_wrap_index(i, n);
        *i1 = pfi_wrap_index(i + 1, n);
    } else {
        *i0 = i < 0 ? 0 : i;
        *i1 = i + 1 > n - 1 ? n - 1 : i + 1;
    }
}

/* Bilinear weights and the four texel offsets (in pf_reals) of (u, v) at one level. */
typedef struct pfi_mip_bilerp {
    long long t[4];
    pf_real w[4];
} pfi_mip_bilerp;

PF_CPU_DEF pfi_mip_bilerp pfi_mip_bilerp_at(int w, int h, int channels, int level, pf_real u,
                                            pf_real v, int border)
{
    pfi_mip_bilerp b;
    int lw = pf_mip_level_size(w, level), lh = pf_mip_level_size(h, level);
    long long x0, x1, y0, y1, base = pf_mip_level_offset(w, h, level) * channels;
    pf_real fx, fy;
    pfi_mip_axis(u, lw, border, &x0, &x1, &fx);
    pfi_mip_axis(v, lh, border, &y0, &y1, &fy);
    b.t[0] = base + (y0 * lw + x0) * channels;
    b.t[1] = base + (y0 * lw + x1) * channels;
    b.t[2] = base + (y1 * lw + x0) * channels;
    b.t[3] = base + (y1 * lw + x1) * channels;
    b.w[0] = (PF_R(1.0) - fx) * (PF_R(1.0) - fy);
    b.w[1] = fx * (PF_R(1.0) - fy);
    b.w[2] = (PF_R(1.0) - fx) * fy;
    b.w[3] = fx * fy;
    return b;
}

PF_CPU_DEF pf_real pfi_mip_bilerp_channel(const pf_real *pyr, const pfi_mip_bilerp *b, int k,
                                          int log_space)
{
    pf_real s = PF_R(0.0), m = -PF_REAL_MAX;
    const pf_real *tap[4];
    int t, n = 0;
    for (t = 0; t < 4; ++t)
        if (b->w[t] > PF_R(0.0)) tap[n++] = pyr + b->t[t];
    if (!log_space) {
        for (t = 0; t < 4; ++t)
            if (b->w[t] > PF_R(0.0)) s += b->w[t] * pyr[b->t[t] + k];
        return s >= -PF_REAL_MAX && s <= PF_REAL_MAX ? s : pfi_taps_clamp(s, tap, n, k);
    }
    for (t = 0; t < 4; ++t)
        if (b->w[t] > PF_R(0.0) && pyr[b->t[t] + k] > m) m = pyr[b->t[t] + k];
    for (t = 0; t < 4; ++t)
        if (b->w[t] > PF_R(0.0)) s += b->w[t] * PF_EXP(pfi_lse_arg(pyr[b->t[t] + k] - m));
    return m + PF_LOG(s);
}

/* The shared sampler: PF_OK, or PF_ERR_ARG (NULL pyr or out, channels < 1, w or h < 1, an
   unknown border) / PF_ERR_SIZE (as pf_mip_build) with out untouched. */
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
    b0 = pfi_mip_bilerp_at(w, h, channels, l0, u, v, border);
    if (!(fl > PF_R(0.0)) || l0 + 1 >= nl) {
        for (k = 0; k < channels; ++k) out[k] = pfi_mip_bilerp_channel(pyr, &b0, k, log_space);
        return PF_OK;
    }
    b1 = pfi_mip_bilerp_at(w, h, channels, l0 + 1, u, v, border);
    for (k = 0; k < channels; ++k) {
        pf_real a = pfi_mip_bilerp_channel(pyr, &b0, k, log_space);
        pf_real c = pfi_mip_bilerp_channel(pyr, &b1, k, log_space), s;
        if (log_space) {
            out[k] = pf_esm_log_combine2(a, PF_R(1.0) - fl, c, fl);
            continue;
        }
        s = (PF_R(1.0) - fl) * a + fl * c;
        out[k] = s >= -PF_REAL_MAX && s <= PF_REAL_MAX ? s : pf_clamp(s, pf_min(a, c), pf_max(a, c));
    }
    return PF_OK;
}

/* Bilinear sample of level `level` (clamped to the pyramid) at (u, v): `channels` pf_reals
   into out. Returns PF_OK, or PF_ERR_ARG / PF_ERR_SIZE with out untouched (pfi_mip_sample). */
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
PF_CPU_DEF int pf_mip_sample_trilinear_log(const pf_real *pyr, int w, int h, int channels,
                                           pf_real lod, pf_real u, pf_real v, int border,
                                           pf_real *out)
{ return pfi_mip_sample(pyr, w, h, channels, lod, u, v, border, 1, out); }
/* Typed trilinear samples (an integer lod is a bilinear sample of that level), one stamp per
   type: pf_slope_moments_sample, pf_scalar_moments_sample, pf_depth_moments2_sample,
   pf_depth_moments4_sample, pf_evsm_moments_sample, pf_normal_avg_sample (T F(pyr, w, h, lod,
   u, v, border)). Bad arguments (those pf_mip_sample_trilinear rejects) return all zeros. */
#define PFI_TYPED_SAMPLE(T, F, NC, MAKE)                                                       \
    PF_CPU_DEF T F(const pf_real *pyr, int w, int h, pf_real lod, pf_real u, pf_real v, int border) \
    {                                                                                          \
        pf_real t[5] = {0, 0, 0, 0, 0};                                                        \
        pfi_mip_sample(pyr, w, h, NC, lod, u, v, border, 0, t);                                \
        return MAKE;                                                                           \
    }
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

#endif /* PF_MOMENTS_H */

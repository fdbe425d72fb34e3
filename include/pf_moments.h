/* pf_moments.h - linear moments for pre-filtering: slope moments (LEAN/LEADR), scalar-map
   moments, average normals (Toksvig), depth moments for shadow maps; their mip reductions,
   mip pyramids and bilinear/trilinear sampling.

   WHY MOMENTS. A shading function non-linear in a map's values is filtered exactly when it is
   rewritten as a linear function of per-texel quantities (Bruneton & Neyret 2012 sec. 7.1.1,
   eq. 40): averaging those over a footprint then averages the function. Raw moments are such
   quantities: the moments of a union (a mixture) of footprints are the weighted averages of
   their moments (sec. 7.2). So everything here is averaged with plain weighted sums (a box mip
   reduction, a bilinear or trilinear sampler), and mean, variance and covariance are formed
   only after filtering, in the shader:
     slope moments   E[x], E[y], E[x^2], E[y^2], E[xy] of micro-slopes (Olano & Baker 2010;
                     Bruneton & Neyret 2012 eq. 19; Dupuy et al. 2013 eq. 9 and sec. 4.1);
     scalar moments  E[f], E[f^2] of a colour-driving or height map: the mean and variance of a
                     Gaussian filtering distribution (Heitz et al. 2014 sec. 4.2);
     average normal  E[n] of unit normals, unnormalized: its length shrinks as the normals
                     spread, which is what Toksvig's variance reads (pf_toksvig.h);
     depth moments   (z, z^2) for VSM, exp-warped moments for EVSM, (z .. z^4) for moment
                     shadow maps (Bruneton & Neyret 2012 sec. 5.2, eqs. 34-38); ESM's
                     E[exp(c z)] as its logarithm, reduced with log-sum-exp (never overflows).

   USAGE (shader or CPU: the evaluators)
     pf_slope_moments t = pf_slope_moments_from_heights(hl, hr, hd, hu, dx, dy, scale);
     pf_slope_moments m = pf_slope_moments_reduce2x2(t00, t10, t01, t11);   -- one mip texel
     pf_slope_stats   s = pf_slope_moments_stats(m, base_var);               -- after filtering
   USAGE (CPU: a whole pyramid in one caller buffer, no allocation)
     long long n = pf_mip_texel_count(w, h);              -- texels of all levels together
     pf_real *pyr = <n * 5 pf_reals from the caller>;
     if (pf_slope_pyramid_from_heights(heights, w, h, dx, dy, scale, PF_BORDER_WRAP, pyr) != PF_OK) ...
     pf_slope_moments m = pf_slope_moments_sample(pyr, w, h, lod, u, v, PF_BORDER_WRAP);

   FUNCTIONS (shader subset: pure functions of scalars and by-value structs)
     texels          pf_scalar_moments_make, _from_value, _mean, _variance, _deviation;
                     pf_depth_moments2/4_make, _from_depth; pf_evsm2_from_depth;
                     pf_evsm_moments_make, _from_depth; pf_evsm_warp_pos, _neg;
                     pf_csm_pair_make, _from_depth (convolution shadow maps);
                     pf_normal_avg_from_normal, _from_slope; pf_esm_log_from_depth, _combine2
     linear algebra  pf_<T>_add, _scale for scalar, depth2, depth4, evsm, csm_pair (slope moments:
                     pf_beckmann.h; pf_vec3: pf_core.h)
     reductions      pf_<T>_reduce2x2, _reduce3, _reduce3x3, _accumulate, _lerp, _bilinear for
                     T in slope_moments, scalar_moments, depth_moments2, depth_moments4,
                     evsm_moments, csm_pair, normal_avg (a pf_vec3), signatures at PFI_MOM_STAMP;
                     pf_mip_next_size, pf_mip_weights3 (odd sizes)
     ESM log space   pf_esm_log_reduce2x2, _reduce3, _reduce3x3, _bilinear;
                     pf_esm_log_sum_make, _first, _add, _mean, PF_ESM_LOG_SUM_EMPTY
     height maps     pf_height_slope_central, _edge, pf_slope_moments_from_heights
   FUNCTIONS (CPU only, linkage PF_CPU_DEF: they walk caller-owned buffers; compiled out under
   PF_GLSL)
     layout          pf_mip_level_count, _level_size, _level_offset, pf_mip_texel_count
     building        pf_mip_build (any channel count), pf_mip_build_log (ESM),
                     pf_slope_moments_map_from_heights (level 0), pf_slope_pyramid_from_heights,
                     pf_depth_moment_channels, pf_depth_pyramid_from_depths,
                     pf_scalar_pyramid_from_values, pf_normal_pyramid_from_normals
     N texels        pf_moments_weighted_mean, pf_esm_log_weighted_mean
     sampling        pf_mip_sample_bilinear, _trilinear, _bilinear_log, _trilinear_log;
                     pf_<T>_sample for the six T above, pf_esm_log_sample

   CONVENTIONS (docs/moments.md gives the reasons and the tests behind each)
     Buffers. Texel (i, j) (column i, row j) of a map of C channels is pf_reals
     [(j w + i) C ...+ C - 1], as an RGBA32F upload; struct members are channels in order
     (slope ex, ey, exx, eyy, exy: 5; scalar, depth2: 2; depth4, evsm: 4; normal: 3; ESM: 1).
     Pyramid. Level l+1 is pf_mip_next_size of each side of level l, down to 1 x 1; levels are
     stored one after the other from level 0, each row-major. Odd sizes reduce as a polyphase
     box (pf_mip_weights3): every texel of a level has the same footprint and every level's
     mean is level 0's, so the 1 x 1 top is the global mean.
     Sampling: the GPU's. Texel i of n is centred at u = (i + 0.5)/n; PF_BORDER_CLAMP clamps any
     u (infinities too) to the edge texel, PF_BORDER_WRAP repeats with u - floor(u) in pf_real
     (a u too large to have a fraction wraps to 0); NaN, and infinities under WRAP, are 0.
     A trilinear lod is clamped to [0, levels - 1] (NaN: 0).
     Height maps. Texel (i, j) sits at ((i + 0.5) dx, (j + 0.5) dy), row j + 1 is +y; the slope
     is height_scale * grad h (Dupuy et al. 2013 sec. 4.2) by pf_height_slope_central.
     PF_BORDER_WRAP for tiling maps; PF_BORDER_CLAMP reads no texel outside the map and uses
     pf_height_slope_edge on the first and last column and row (2 texels on an axis:
     (h1 - h0)/d; 1 texel: slope 0).
     Robustness. Weights are applied before summing (w a + w b, never w (a + b)), so values near
     the largest float (EVSM's exp(2c) = 1.6e38 at c = 44) reduce to finite values. A NaN
     texel makes NaN exactly the texels that average it with a nonzero weight; zero-weight
     texels are never read. A level or sample of texels near +-PF_REAL_MAX that overflows
     through the rounded weights is clamped to the range of its texels (not under -ffast-math).
     Limits and errors (pf_core.h, "sizes and errors"). Every builder and sampler returns
     PF_OK or, having written nothing, PF_ERR_ARG (a NULL pointer; w, h or channels below 1;
     n below 0; a border other than PF_BORDER_CLAMP / _WRAP; an unknown PF_DEPTH_* kind; a +inf
     weight) or PF_ERR_SIZE (w or h above PF_MAX_SIDE, 2^24 by default; a pyramid, map or texel
     buffer above PF_MAX_REALS pf_reals, 2^40 on 64-bit hosts). On those errors the typed
     samplers return zeros, pf_esm_log_sample and pf_esm_log_weighted_mean -PF_REAL_MAX;
     pf_mip_texel_count is 0 for a size no builder accepts. Offsets and indices are long long.

   ACCURACY AND COST (measured; docs/moments.md has the tables, bench/bench_moments.c the
   timings). Reductions and sampling are sums of a few products: their moments equal the
   mixture moments of their texels to a few ulps (tests/test_moments.c). A pyramid is built
   in one pass, each level reduced while the rows it needs are in cache: the 5-moment pyramid
   of a 4096^2 float height map writes at over half of memcpy's bandwidth (docs/moments.md).

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
   Depths z are in [0, 1] (0 nearest the light); pf_shadow.h evaluates the filtered values. */

/* Two moments (E[w], E[w^2]) of a depth or of a warped depth w: VSM stores w = z; EVSM-2
   stores w = exp(c (2z - 1)). */
PF_STRUCT_BEGIN(pf_depth_moments2)
    pf_real m1, m2;
PF_STRUCT_END(pf_depth_moments2)

/* Four power moments of the reversed depth u = 1 - z: E[u], E[u^2], E[u^3], E[u^4] (moment
   shadow maps, Peters & Klein 2015; reversed for fp32 precision near the far plane). */
PF_STRUCT_BEGIN(pf_depth_moments4)
    pf_real m1, m2, m3, m4;
PF_STRUCT_END(pf_depth_moments4)

/* EVSM-4 (Lauritzen & McCool 2008): with zs = 2z - 1 in [-1, 1], the moments of the positive
   warp p = exp(c_pos zs) and of the negative warp n = -exp(-c_neg zs):
   pos1 = E[p], pos2 = E[p^2], neg1 = E[n] (<= 0), neg2 = E[n^2]. */
PF_STRUCT_BEGIN(pf_evsm_moments)
    pf_real pos1, pos2, neg1, neg2;
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
/* MSM texel: powers of the reversed depth u = 1 - z, (u, u^2, u^3, u^4): fp32 keeps them to
   2^-24 relative near the far plane, where z-powers lose the differences MSM needs (issue 17;
   pf_shadow.h's MSM section). */
PF_DEF pf_depth_moments4 pf_depth_moments4_from_depth(pf_real z)
{ pf_real u = PF_R(1.0) - z, u2 = u * u; return pf_depth_moments4_make(u, u2, u2 * u, u2 * u2); }
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
    pf_real p = pf_evsm_warp_pos(z, c_pos), n = pf_evsm_warp_neg(z, c_neg);
    return pf_evsm_moments_make(p, p * p, n, n * n);
}

/* ESM texel in log space: log(exp(c z)) = c z (see "ESM in log space" below). */
PF_DEF pf_real pf_esm_log_from_depth(pf_real z, pf_real c) { return c * z; }
/* log(w0 exp(l0) + w1 exp(l1)) for weights w >= 0, without overflow: m + log(w0 exp(l0 - m) +
   w1 exp(l1 - m)) with m the larger log among those of positive weight, so the sum holds a
   term w exp(0) and cannot underflow to log(0) (a zero weight on the larger log gives the
   other log + log(its weight)). Both weights <= 0 (or NaN): -PF_REAL_MAX, the log of an empty
   sum kept finite; a NaN log propagates. */
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

/* ---- convolution shadow maps (CSM; Annen et al. 2007, Bruneton & Neyret 2012 eqs. 36-37)
   The Fourier basis of the depth test (pf_shadow.h, CSM section): harmonic k = 1..M of depth
   z is the pair (cos(c_k z), sin(c_k z)), c_k = (2k - 1) pi. A texel of M harmonics holds 2M
   values (the constant term of the series is implicit: its filtered value is the sum of the
   filter's weights, 1); they are stored two harmonics per pf_csm_pair, one RGBA texel:
   pair j holds harmonics 2j + 1 and 2j + 2. Every value is in [-1, 1] and linear in the
   depth distribution, so any filter averages it. */
PF_STRUCT_BEGIN(pf_csm_pair)
    pf_real cos_a, sin_a, cos_b, sin_b;
PF_STRUCT_END(pf_csm_pair)

PF_DEF pf_csm_pair pf_csm_pair_make(pf_real cos_a, pf_real sin_a, pf_real cos_b, pf_real sin_b)
{ pf_csm_pair m; m.cos_a = cos_a; m.sin_a = sin_a; m.cos_b = cos_b; m.sin_b = sin_b; return m; }
/* Pair j (0-based) of depth z: frequencies (4j + 1) pi and (4j + 3) pi (j < 0 reads as 0). */
PF_DEF pf_csm_pair pf_csm_pair_from_depth(pf_real z, int pair)
{
    pf_real fa = PF_R(4.0) * PF_R(pair < 0 ? 0 : pair) + PF_R(1.0);
    pf_real pa = fa * z, pb = (fa + PF_R(2.0)) * z; /* phases in units of pi (PFI_SINPI: pf_core.h) */
    return pf_csm_pair_make(PFI_COSPI(pa), PFI_SINPI(pa), PFI_COSPI(pb), PFI_SINPI(pb));
}
PF_DEF pf_csm_pair pf_csm_pair_add(pf_csm_pair a, pf_csm_pair b)
{ return pf_csm_pair_make(a.cos_a + b.cos_a, a.sin_a + b.sin_a, a.cos_b + b.cos_b, a.sin_b + b.sin_b); }
PF_DEF pf_csm_pair pf_csm_pair_scale(pf_csm_pair a, pf_real w)
{ return pf_csm_pair_make(w * a.cos_a, w * a.sin_a, w * a.cos_b, w * a.sin_b); }

/* ---------------------------------------------------------------- scalar-map moments
   E[f], E[f^2] of a scalar map f (a height, or the value driving a colour map). After filtering
   f is a Gaussian of mean E[f] and variance E[f^2] - E[f]^2 over the footprint, convolved with
   the colour map (Heitz et al. 2014 sec. 4.2, eq. 9, whose "f^2 bar - f bar" means that). */
PF_STRUCT_BEGIN(pf_scalar_moments)
    pf_real m1, m2;
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
   texels is reduced to pf_mip_next_size(n_src), the polyphase box (each destination texel
   covers exactly n_src / n_dst source texels; docs/moments.md, Odd sizes):
     n_src even (1/2, 1/2, 0); n_src = 2k + 1 (k - j, k, j + 1) / (2k + 1); n_src = 1 (1, 0, 0)
   Separable in 2D: reduce3x3 in a corner where both sizes are odd, reduce3 on an odd edge.
   The weights sum to 1; a zero weight means "do not read that texel" (it may be outside the
   map). j is clamped to [0, n_dst - 1]; n_src < 1 gives (0, 0, 0). */
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

/* ---------------------------------------------------------------- reductions
   PFI_MOM_STAMP(T, F, BOX) defines the six reductions of a moment type T (which has T_add and
   T_scale) with function prefix F (BOX: the reduce2x2 body):
     T F_reduce2x2(T a, T b, T c, T d)      the even-size mip texel: a/4 + b/4 + c/4 + d/4
     T F_reduce3(T a, T b, T c, pf_vec3 w)  3 texels, w.x a + w.y b + w.z c (an odd edge;
                                            w from pf_mip_weights3)
     T F_reduce3x3(T t00, T t10, T t20, T t01, T t11, T t21, T t02, T t12, T t22,
                   pf_vec3 wx, pf_vec3 wy)  9 texels (an odd corner), t<col><row>: reduce3 by
                                            wy of the three rows' reduce3 by wx
     T F_accumulate(T acc, T t, pf_real w)  acc + w t: N texels one at a time (then scale by
                                            1/sum(w))
     T F_lerp(T a, T b, pf_real t)          (1 - t) a + t b
     T F_bilinear(T t00, T t10, T t01, T t11, pf_real fx, pf_real fy)
                                            lerp by fy of the rows' lerps by fx (a sampler)
   One body per operation, so every type computes the same sums in the same order and a fix
   lands once; weights are applied to each texel before summing (T_add(a, T_scale(b, w)), see
   CONVENTIONS). GLSL's preprocessor pastes ## like C's, so this pastes into shaders.
   tests/portability/gen.awk expands the stamps, so the portability checks call and the fuzz
   coverage check (tests/fuzz/coverage.sh) lists every generated function. */
#define PFI_MOM_BOX(V)                                                                         \
    { return V##_add(V##_add(V##_add(V##_scale(a, PF_R(0.25)), V##_scale(b, PF_R(0.25))),       \
                             V##_scale(c, PF_R(0.25))), V##_scale(d, PF_R(0.25))); }
#define PFI_MOM_STAMP(T, F, BOX)                                                               \
    PF_DEF T F##_lerp(T a, T b, pf_real t)                                                     \
    { return T##_add(T##_scale(a, PF_R(1.0) - t), T##_scale(b, t)); }                          \
    PF_DEF T F##_reduce2x2(T a, T b, T c, T d) BOX(T)                                          \
    PF_DEF T F##_reduce3(T a, T b, T c, pf_vec3 w)                                             \
    { return T##_add(T##_add(T##_scale(a, w.x), T##_scale(b, w.y)), T##_scale(c, w.z)); }      \
    PF_DEF T F##_reduce3x3(T t00, T t10, T t20, T t01, T t11, T t21, T t02, T t12, T t22,      \
                           pf_vec3 wx, pf_vec3 wy)                                             \
    { return F##_reduce3(F##_reduce3(t00, t10, t20, wx), F##_reduce3(t01, t11, t21, wx),       \
                         F##_reduce3(t02, t12, t22, wx), wy); }                                \
    PF_DEF T F##_accumulate(T acc, T t, pf_real w) { return T##_add(acc, T##_scale(t, w)); }   \
    PF_DEF T F##_bilinear(T t00, T t10, T t01, T t11, pf_real fx, pf_real fy)                  \
    { return F##_lerp(F##_lerp(t00, t10, fx), F##_lerp(t01, t11, fx), fy); }

PFI_MOM_STAMP(pf_slope_moments, pf_slope_moments, PFI_MOM_BOX)
PFI_MOM_STAMP(pf_scalar_moments, pf_scalar_moments, PFI_MOM_BOX)
PFI_MOM_STAMP(pf_depth_moments2, pf_depth_moments2, PFI_MOM_BOX)
PFI_MOM_STAMP(pf_depth_moments4, pf_depth_moments4, PFI_MOM_BOX)
PFI_MOM_STAMP(pf_vec3, pf_normal_avg, PFI_MOM_BOX)

/* EVSM-4's 2x2 box is midpoints of midpoints, a + (b - a)/2: with one constant weight q,
   -ffast-math (and GPU compilers, which reassociate freely) factor q a + q b + q c + q d into
   q (a + b + c + d), and four second moments near exp(2c) = 1.6e38 (c = 44) overflow the float
   sum (the sweep found 14 inf per 10^6 under gcc -ffast-math); no compiler distributes the
   half over b - a, so this stays finite in every build. |b - a| <= max(|a|, |b|) because
   every member of an EVSM texel has one sign (pos1, pos2, neg2 >= 0, neg1 <= 0). Error <= 2
   ulp (tests/test_moments.c); two operations more per member than the weighted sum. */
PF_DEF pf_real pfi_midpoint(pf_real a, pf_real b) { return a + PF_R(0.5) * (b - a); }
PF_DEF pf_evsm_moments pfi_evsm_moments_midpoint(pf_evsm_moments a, pf_evsm_moments b)
{
    return pf_evsm_moments_make(pfi_midpoint(a.pos1, b.pos1), pfi_midpoint(a.pos2, b.pos2),
                                pfi_midpoint(a.neg1, b.neg1), pfi_midpoint(a.neg2, b.neg2));
}
#define PFI_MOM_MIDPOINTS(V)                                                                   \
    { return pfi_evsm_moments_midpoint(pfi_evsm_moments_midpoint(a, b), pfi_evsm_moments_midpoint(c, d)); }
PFI_MOM_STAMP(pf_evsm_moments, pf_evsm_moments, PFI_MOM_MIDPOINTS)
PFI_MOM_STAMP(pf_csm_pair, pf_csm_pair, PFI_MOM_BOX) /* CSM: values in [-1, 1], no overflow */

/* ---------------------------------------------------------------- ESM in log space
   An ESM texel stores l = c z, not exp(c z) (which overflows float for c z > 88.7). A reduction
   computes log(sum_i w_i exp(l_i)) as m + log(sum_i w_i exp(l_i - m)), m the largest l of
   positive weight: every exponential is <= 1, the sum is in (0, sum w], the result finite for
   any finite l and c. Zero-weight texels are skipped. l - m is floored at -80 (exp(-80) is
   below the rounding of a sum that holds a 1), which keeps every exponential normal (libm's
   underflow path and subnormals are slow). */
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
   pf_esm_log_sum_first), add texels with pf_esm_log_sum_add, read log(sum w e^l / sum w) with
   pf_esm_log_sum_mean. */
PF_STRUCT_BEGIN(pf_esm_log_sum)
    pf_real lmax, sum, weight;
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
/* A subnormal sum / weight (flushed to 0 on GPUs and under -ffast-math) takes the logs apart. */
PF_DEF pf_real pf_esm_log_sum_mean(pf_esm_log_sum a)
{
    pf_real r = a.sum / a.weight;
    if (!(a.weight > PF_R(0.0))) return -PF_REAL_MAX;
    return r >= PF_REAL_MIN ? a.lmax + PF_LOG(r) : a.lmax + (PF_LOG(a.sum) - PF_LOG(a.weight));
}

/* ---------------------------------------------------------------- slopes from a height map */
/* Central difference (h_plus - h_minus) / (2 d), d the texel spacing: second order, error
   (d^2/6) h''' + O(d^4). */
PF_DEF pf_real pf_height_slope_central(pf_real h_minus, pf_real h_plus, pf_real spacing)
{ return (h_plus - h_minus) / (PF_R(2.0) * spacing); }
/* Slope at h0 from h0, h1, h2 at 0, d, 2d: (-3 h0 + 4 h1 - h2) / (2 d) (error (d^2/3) h'''),
   the clamped border's stencil. For the far border pass the texels in reverse order and
   negate. */
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
   Host code that walks caller-owned buffers and allocates nothing (linkage PF_CPU_DEF,
   pf_core.h). Errors as in CONVENTIONS (Limits and errors) plus what each comment adds. */
#ifndef PF_GLSL

/* Border handling of the height-map stencils and of sampling (any other value: PF_ERR_ARG). */
#define PF_BORDER_CLAMP 0
#define PF_BORDER_WRAP 1

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
    for (t = 0; t < n; ++t) s += w[t] * PF_EXP(pfi_lse_arg(tap[t][k] - m));
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
PF_CPU_DEF void pfi_slope_stencil(long long i, int n, int border, pf_real k, long long *x, pf_real *c)
{
    pf_real s = i == 0 ? k : -k;
    x[0] = x[1] = x[2] = i;
    c[0] = c[1] = c[2] = PF_R(0.0);
    if (n < 2) return;
    if (border == PF_BORDER_WRAP || (i > 0 && i < n - 1)) {
        x[0] = pfi_wrap_index(i - 1, n), x[1] = pfi_wrap_index(i + 1, n);
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
/* Row r of the slope-moment map of a height map (5 channels). */
PF_CPU_DEF void pfi_slope_row(const pf_real *heights, int w, int h, int r, pf_real dx, pf_real dy,
                              pf_real height_scale, int border, pf_real *out)
{
    const pf_real ky = height_scale / (PF_R(2.0) * dy), kx = height_scale / (PF_R(2.0) * dx);
    const pf_real *row = heights + (long long)r * w, *r0, *r1, *r2;
    long long y[3], x[3];
    pf_real cy[3], cx[3], c0, c1, c2;
    int i;
    pfi_slope_stencil(r, h, border, ky, y, cy);
    r0 = heights + y[0] * w, r1 = heights + y[1] * w, r2 = heights + y[2] * w;
    c0 = cy[0], c1 = cy[1], c2 = cy[2]; /* scalars: the stores below cannot alias them */
    /* interior texels: branch-free, so the compiler can vectorize the row */
    for (i = 1; i < w - 1; ++i) {
        pf_real sx = kx * (row[i + 1] - row[i - 1]);
        pfi_put_slope(out + 5 * i, sx, c0 * r0[i] + c1 * r1[i] + c2 * r2[i]);
    }
    /* the first and last texels of the row */
    for (i = 0; i < w; i = (i == 0 && w > 1) ? w - 1 : w) {
        pfi_slope_stencil(i, w, border, kx, x, cx);
        pfi_put_slope(out + 5 * i, cx[0] * row[x[0]] + cx[1] * row[x[1]] + cx[2] * row[x[2]],
                      c0 * r0[i] + c1 * r1[i] + c2 * r2[i]);
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
        pfi_slope_row(heights, w, h, r, dx, dy, height_scale, border, out + (long long)r * w * 5);
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
        pfi_slope_row(heights, w, h, r, dx, dy, height_scale, border, pyr + (long long)r * w * 5);
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

/* ---------------------------------------------------------------- N texels
   Both weighted means skip texels of weight <= 0 (or NaN) without reading them, and divide the
   weights by a divisor d first, so any finite weights work, under -ffast-math too (two weights
   of PF_REAL_MAX give the plain mean): d = wmax 2^-32 (exact) for a largest weight wmax > 1,
   else wmax. Not wmax itself: 1/wmax is subnormal in float for wmax > 2^126, and -ffast-math
   turns w / wmax into w * (1/wmax) with subnormals flushed to 0; 1/d >= 2^-96 is normal. */
PF_CPU_DEF pf_real pfi_weight_divisor(const pf_real *weights, int n)
{
    pf_real m = PF_R(0.0);
    int i;
    for (i = 0; i < n; ++i)
        if (weights[i] > m) m = weights[i];
    return m > PF_R(1.0) ? m * PF_R(2.3283064365386963e-10) : m; /* 2^-32; +inf stays +inf */
}

/* out[k] = sum_i w_i texels[i C + k] / sum_i w_i for n >= 0 texels of C = `channels` pf_reals
   (texels: n C pf_reals, weights: n, out: C). No positive weight (n = 0 too): out is zeroed,
   PF_OK. PF_ERR_SIZE when n C > PF_MAX_REALS. */
PF_CPU_DEF int pf_moments_weighted_mean(const pf_real *texels, int channels, const pf_real *weights,
                                        int n, pf_real *out)
{
    pf_real wsum = PF_R(0.0), d;
    int i, k;
    if (!texels || !weights || !out || channels < 1 || n < 0) return PF_ERR_ARG;
    if (pf_size_mul(n, channels) < 0) return PF_ERR_SIZE;
    d = pfi_weight_divisor(weights, n);
    if (!(d <= PF_REAL_MAX)) return PF_ERR_ARG;
    for (k = 0; k < channels; ++k) out[k] = PF_R(0.0);
    if (!(d > PF_R(0.0))) return PF_OK;
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

/* log(w / wmax) from wd = w / d and wmaxd = wmax / d (both <= 2^32): a ratio of two normal
   numbers, with no reciprocal of a huge weight (volatile: -ffast-math would fold the two
   divisions into one by wmax); a subnormal share (flushed to 0 on FTZ) as log(wd) -
   log(wmaxd); -PF_REAL_MAX (counted as 0) when wd itself is below PF_REAL_MIN. */
PF_CPU_DEF pf_real pfi_log_weight_share(pf_real w, pf_real d, pf_real wmaxd)
{
    volatile pf_real wd = w / d;
    pf_real r = wd / wmaxd;
    if (r >= PF_REAL_MIN) return PF_LOG(r);
    return wd >= PF_REAL_MIN ? PF_LOG(wd) - PF_LOG(wmaxd) : -PF_REAL_MAX;
}
/* log(sum_i w_i exp(l_i) / sum_i w_i) (ESM, log space) over n texels, its log-sum-exp anchored
   at the largest l_i + log(w_i / wmax), not the largest l_i: a texel with the largest log and a
   tiny share of the weight would leave the others at the exp(-80) floor (wrong by e^8 over a
   float ESM map's log range) and make sum / weight subnormal. The anchor term is 1, so the
   floor costs at most n e^-80. Two logs, two exps per texel (pf_esm_log_sum_* streams more
   cheaply). -PF_REAL_MAX when no weight is positive (n = 0 too) and for bad arguments (a NULL,
   n < 0, a +inf weight). */
PF_CPU_DEF pf_real pf_esm_log_weighted_mean(const pf_real *logs, const pf_real *weights, int n)
{
    pf_real d, wmaxd = PF_R(0.0), m = -PF_REAL_MAX, s = PF_R(0.0), ws = PF_R(0.0), lw;
    int i;
    if (!logs || !weights || n < 0) return -PF_REAL_MAX;
    d = pfi_weight_divisor(weights, n);
    if (!(d > PF_R(0.0) && d <= PF_REAL_MAX)) return -PF_REAL_MAX;
    for (i = 0; i < n; ++i) wmaxd = pf_max(weights[i] / d, wmaxd); /* 2^32 or 1; NaN skipped */
    for (i = 0; i < n; ++i)
        if (weights[i] > PF_R(0.0) && (lw = pfi_log_weight_share(weights[i], d, wmaxd)) > -PF_REAL_MAX)
            m = pf_max(logs[i] + lw, m);
    if (!(m > -PF_REAL_MAX)) return -PF_REAL_MAX;
    for (i = 0; i < n; ++i)
        if (weights[i] > PF_R(0.0) && (lw = pfi_log_weight_share(weights[i], d, wmaxd)) > -PF_REAL_MAX) {
            s += PF_EXP(pfi_lse_arg(logs[i] + lw - m));
            ws += PF_EXP(pfi_lse_arg(lw));
        }
    return m + PF_LOG(s / ws); /* s, ws in [1, n] */
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
    i = pfi_floor_index(x, -1, n - 1);
    *f = pf_clamp(x - PF_R(i), PF_R(0.0), PF_R(1.0));
    *i0 = border == PF_BORDER_WRAP ? pfi_wrap_index(i, n) : (i < 0 ? 0 : i);
    *i1 = border == PF_BORDER_WRAP ? pfi_wrap_index(i + 1, n) : (i + 1 > n - 1 ? n - 1 : i + 1);
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

#endif /* PF_MOMENTS_H */

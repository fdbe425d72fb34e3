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
   The CPU side (pyramids of these texels from a map, their sampling, the border rule and
   layout) is pf_map.h; this header is what a shader pastes, plus two CPU means of N texels.

   FUNCTIONS (shader subset: pure functions of scalars and by-value structs)
     texels          pf_scalar_moments_make, _from_value, _mean, _variance, _deviation;
                     pf_depth_moments2/4_make, _from_depth; pf_evsm2_from_depth;
                     pf_evsm_moments_make, _from_depth; pf_evsm_warp_pos, _neg;
                     pf_csm_pair_make, _from_depth (convolution shadow maps);
                     pf_normal_avg_from_normal, _from_slope; pf_esm_log_from_depth, _combine2
     slope moments   pf_slope_moments (struct), pf_slope_moments_make, _from_slope, _from_normal
                     (their statistics and distribution: pf_beckmann.h)
     linear algebra  pf_<T>_add, _scale for slope_moments, scalar, depth2, depth4, evsm,
                     csm_pair (pf_vec3: pf_core.h)
     reductions      pf_<T>_reduce2x2, _reduce3, _reduce3x3, _accumulate, _lerp, _bilinear for
                     T in slope_moments, scalar_moments, depth_moments2, depth_moments4,
                     evsm_moments, csm_pair, normal_avg (a pf_vec3), signatures at PFI_MOM_STAMP;
                     pf_mip_next_size, pf_mip_weights3 (odd sizes)
     ESM log space   pf_esm_log_reduce2x2, _reduce3, _reduce3x3, _bilinear;
                     pf_esm_log_sum_make, _first, _add, _mean, PF_ESM_LOG_SUM_EMPTY
     height maps     pf_height_slope_central, _edge, pf_slope_moments_from_heights
   FUNCTIONS (CPU only, linkage PF_CPU_DEF: they walk caller-owned buffers; compiled out under
   PF_GLSL)
     N texels        pf_moments_weighted_mean, pf_esm_log_weighted_mean

   CONVENTIONS (docs/moments.md gives the reasons and the tests behind each)
     Buffers. Texel (i, j) (column i, row j) of a map of C channels is pf_reals
     [(j w + i) C ...+ C - 1], as an RGBA32F upload; struct members are channels in order
     (slope ex, ey, exx, eyy, exy: 5; scalar, depth2: 2; depth4, evsm: 4; normal: 3; ESM: 1).
     Pyramids, sampling, borders: pf_map.h (CONVENTIONS there).
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
     Limits and errors (pf_core.h, "sizes and errors"). pf_moments_weighted_mean returns
     PF_OK or, having written nothing, PF_ERR_ARG (a NULL pointer; channels below 1; n below
     0; a +inf weight) or PF_ERR_SIZE (a texel buffer above PF_MAX_REALS pf_reals);
     pf_esm_log_weighted_mean returns -PF_REAL_MAX for those.

   ACCURACY AND COST (measured; docs/moments.md has the tables, bench/bench_moments.c the
   timings). Reductions are sums of a few products: their moments equal the mixture moments
   of their texels to a few ulps (tests/test_moments.c).

   SOURCES
     Dupuy et al. 2013 (LEADR) sec. 4.1-4.2, eqs. 9, 11, 12; Bruneton & Neyret 2012 sec. 3.2.1
     (eq. 19, Toksvig), 5.2 (eqs. 34-38) and 7.2; Heitz et al. 2014 sec. 4.2; Donnelly &
     Lauritzen 2006 (VSM); Salvi 2008 / Annen et al. 2008 (ESM); Lauritzen & McCool 2008
     (EVSM); Peters & Klein 2015 (moment shadow maps). */
#ifndef PF_MOMENTS_H
#define PF_MOMENTS_H

#ifndef PF_GLSL
#  include "pf_core.h"
#endif

/* ---------------------------------------------------------------- the five linear moments */
/* Raw moments E[x], E[y], E[x^2], E[y^2], E[xy] of the micro-slopes (x, y) over a footprint
   (Dupuy et al. 2013 eq. 9). They are linear in the footprint weights, so they are what a
   mip pyramid and a texture sampler may average; everything else is derived from them after
   filtering. A slope is (-n.x/n.z, -n.y/n.z) for a micro-normal n, which for a height field
   z = h(x, y) is the gradient (dh/dx, dh/dy). */
PF_STRUCT_BEGIN(pf_slope_moments)
    pf_real ex;
    pf_real ey;
    pf_real exx;
    pf_real eyy;
    pf_real exy;
PF_STRUCT_END(pf_slope_moments)

PF_DEF pf_slope_moments pf_slope_moments_make(pf_real ex, pf_real ey, pf_real exx, pf_real eyy,
                                              pf_real exy)
{
    pf_slope_moments m;
    m.ex = ex;
    m.ey = ey;
    m.exx = exx;
    m.eyy = eyy;
    m.exy = exy;
    return m;
}

/* The moments of a single slope (x, y): (x, y, x^2, y^2, xy). One texel of a LEAN/LEADR map. */
PF_DEF pf_slope_moments pf_slope_moments_from_slope(pf_real x, pf_real y)
{
    return pf_slope_moments_make(x, y, x * x, y * y, x * y);
}

/* The moments of the slope of a normal n (n.z > 0; not normalized is fine): slope
   (-n.x/n.z, -n.y/n.z). n.z <= 0 has no slope: it is clamped to the smallest positive
   pf_real so the result stays finite (huge slopes) instead of inf or NaN. */
PF_DEF pf_slope_moments pf_slope_moments_from_normal(pf_vec3 n)
{
    pf_real z = pf_max(n.z, PF_REAL_MIN);
    return pf_slope_moments_from_slope(-n.x / z, -n.y / z);
}

/* a + b, componentwise (moments are linear). */
PF_DEF pf_slope_moments pf_slope_moments_add(pf_slope_moments a, pf_slope_moments b)
{
    return pf_slope_moments_make(a.ex + b.ex, a.ey + b.ey, a.exx + b.exx, a.eyy + b.eyy,
                                 a.exy + b.exy);
}

/* w * a, componentwise. */
PF_DEF pf_slope_moments pf_slope_moments_scale(pf_slope_moments a, pf_real w)
{
    return pf_slope_moments_make(w * a.ex, w * a.ey, w * a.exx, w * a.eyy, w * a.exy);
}


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
#define PF_LSE_ARG_MIN PF_R(-80.0)

/* d floored at PF_LSE_ARG_MIN; NaN stays NaN (so a NaN texel still propagates). */
PF_DEF pf_real pf_lse_arg(pf_real d) { return d < PF_LSE_ARG_MIN ? PF_LSE_ARG_MIN : d; }
/* log of the mean of exp(l) over 4 texels (the 2x2 box). */
PF_DEF pf_real pf_esm_log_reduce2x2(pf_real l0, pf_real l1, pf_real l2, pf_real l3)
{
    pf_real m = pf_max(pf_max(l0, l1), pf_max(l2, l3));
    pf_real s = PF_R(0.25) * PF_EXP(pf_lse_arg(l0 - m))
              + PF_R(0.25) * PF_EXP(pf_lse_arg(l1 - m))
              + PF_R(0.25) * PF_EXP(pf_lse_arg(l2 - m))
              + PF_R(0.25) * PF_EXP(pf_lse_arg(l3 - m));
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
    s = (w.x > PF_R(0.0) ? w.x * PF_EXP(pf_lse_arg(l0 - m)) : PF_R(0.0))
      + (w.y > PF_R(0.0) ? w.y * PF_EXP(pf_lse_arg(l1 - m)) : PF_R(0.0))
      + (w.z > PF_R(0.0) ? w.z * PF_EXP(pf_lse_arg(l2 - m)) : PF_R(0.0));
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
        a.sum = a.sum * PF_EXP(pf_lse_arg(a.lmax - l)) + w;
        a.lmax = l;
    } else {
        a.sum = a.sum + w * PF_EXP(pf_lse_arg(l - a.lmax));
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
            s += PF_EXP(pf_lse_arg(logs[i] + lw - m));
            ws += PF_EXP(pf_lse_arg(lw));
        }
    return m + PF_LOG(s / ws); /* s, ws in [1, n] */
}
#endif /* !PF_GLSL */

#endif /* PF_MOMENTS_H */

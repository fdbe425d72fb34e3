/* pf_shadow.h - pre-filterable shadow-map tests: Chebyshev (VSM), exponential (ESM),
   exponential-variance (EVSM, 2 and 4 moments) and moment shadow maps (MSM, 4 moments).

   A shadow map stores, per texel, the depth z of the nearest occluder seen from the light.
   A receiver at depth d is lit by a texel when d <= z (Bruneton & Neyret 2012 eq. 32 with
   H(z - d), H(0) = 1). Over a filtered footprint A the lit fraction is
       U_A(d) = integral_d^inf p_A(z) dz                                    (B&N eq. 35)
   where p_A is the distribution of the depths in A (the ZDF). The depth test is not linear
   in z, so filtering the depths gives nothing useful; each method below stores a few
   functions of z per texel (moments, exponentials) that ARE linear in p_A, so that a mip
   pyramid, a bilinear/anisotropic sampler or a blur may average them, and then reconstructs
   an estimate of U_A(d) from the averaged values. pf_moments.h and pf_map.h build and filter those
   values; this header evaluates them.

   CONVENTIONS
     Depths z and d in [0, 1], 0 nearest the light. A receiver at depth d is lit by a texel of
     depth z when d <= z. Every test returns the LIT fraction of the footprint, in [0, 1]
     (1 - shadow intensity). Receivers are assumed planar and parallel over the footprint (one
     d per lookup, B&N eq. 33). Every parameter is an argument; the PF_SHADOW_*_DEFAULT macros
     give the values the docs derive (docs/shadow.md).

   USAGE
     #include "pf_shadow.h"
     pf_depth_moments2 m = ...filtered (E[z], E[z^2])...;
     pf_real lit = pf_shadow_vsm(m, d, PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT,
                                 PF_SHADOW_BLEED_DEFAULT);
     pf_depth_moments4 b = ...filtered (E[u], .., E[u^4]), u = 1 - z (pf_depth_moments4_from_depth)...;
     pf_real lit4 = pf_shadow_msm(b, d, PF_SHADOW_MSM_MOMENT_BIAS_DEFAULT,
                                  PF_SHADOW_MSM_DEPTH_BIAS_DEFAULT);

   FUNCTIONS                                                      bytes/texel (fp32 storage)
     pf_shadow_chebyshev_upper(m1, m2, x, min_variance)  one-tailed Chebyshev bound, any scale
     pf_shadow_reduce_bleeding(lit, threshold)          linstep(threshold, 1, lit)
     pf_shadow_vsm(m2, d, min_variance, bleed)          VSM, (E[z], E[z^2])            8
     pf_shadow_esm(log_mean, d, c)                      ESM from log E[exp(c z)]       4
     pf_shadow_evsm2(m2, d, c_pos, min_variance, bleed) EVSM, positive warp only       8
     pf_shadow_evsm4(m4, d, c_pos, c_neg, min_variance, bleed)  EVSM, both warps      16
     pf_shadow_msm(m4, d, moment_bias, depth_bias)      MSM, Hamburger 4-moment       16
     pf_shadow_msm_bounds(m4, d, moment_bias, depth_bias)  (lower, upper) lit bounds
     pf_shadow_msm_hausdorff(m4, d, moment_bias, depth_bias)  MSM, Hausdorff (depths in [0, 1]) 16
     pf_shadow_msm16(q, d, moment_bias, depth_bias)     MSM of a 64-bit texel (4 x UNORM16)   8
     pf_shadow_msm16_hausdorff(q, d, moment_bias, depth_bias)  the same, Hausdorff            8
     pf_msm_quantize_moments(b), pf_msm_dequantize_moments(q)  Peters & Klein's 16-bit map
     pf_shadow_csm(m, d, terms, scale, offset)          CSM, Fourier series, <= 16 terms  8/term
     pf_csm_sum_begin, _add, _add_harmonic, _lit, _make   CSM streamed pair by pair (any M)
   All are pure, pointer-free and branch only on values: they paste into GLSL, HLSL, CUDA.
   CPU only (caller buffers, library return codes): pf_shadow_encode_f32 / _f16 (VSM, EVSM-2,
   EVSM-4, MSM texels in fp32 / fp16 with the exponent ceilings), pf_shadow_encode_msm16 /
   _msm16_moments (64-bit MSM texels), pf_half_from_real / pf_real_from_half (pf_core.h),
   pf_shadow_decode_msm16; see "16- and 32-bit float storage" and "CPU encoders" below.

   ROBUSTNESS
     Every function returns a finite value in [0, 1] for every finite input (also under
     -ffast-math): variances made negative by rounding are clamped to the minimum variance,
     the Chebyshev variance is clamped once to [PF_REAL_MIN, PF_REAL_MAX/4] so its quotient
     can be neither 0/0 nor inf/inf and needs no clamp, EVSM with c <= PF_EVSM_EXP_MAX_F32
     stays finite unscaled (warps <= exp(44), second moments <= exp(88)), ESM's exponent is
     clamped before exp, and MSM's moments are confined and its Cholesky pivots floored so that a singular
     Hankel matrix (a flat occluder, a constant footprint, depths exactly 0 or 1) never
     divides by zero. All-zero moments (a footprint with no weight) are read as an occluder
     at depth 0: shadowed for d > 0 - except by MSM, whose moments are of u = 1 - z: there
     they read as depth 1 (nothing in front), lit.

   ACCURACY AND COST
     Measured against brute-force depth tests on synthetic depth maps (tests/test_shadow.c,
     bench/bench_shadow.c); the tables are in docs/shadow.md.
     VSM, EVSM-2 and EVSM-4 cost what their textbook formulas cost: SPIR-V ops
     after spirv-opt -O 13 / 20 / 37 against 12 / 19 / 36 (bench/gpu/count.sh), no
     conditional branch; on a CPU (gcc -O2) 0.94-0.99x the textbook's instructions
     (bench_shadow vs_textbook_* families). The robustness above costs one op each: the
     variance floor (VSM) or clamp (EVSM) and the bleeding threshold's clamp; on a GPU the
     receiver-in-front test is folded into t = max(x - mean, 0), one op instead of a compare
     and a select (a CPU keeps the test and skips the division).
     One difference from the scaled form the library used before: EVSM reads a warped
     variance below PF_REAL_MIN as PF_REAL_MIN, which moves the bound only for the negative
     warp with c_neg > 30 near d = 1 (warped values below 1e-17, whose squares fp32 storage
     already holds as subnormals, or 0 on GPUs that flush them).
     GPU NaN semantics: pf_min/pf_max/pf_clamp are the native instructions under PF_GLSL and
     CUDA (pf_core.h); a NaN input then gives what the GPU's min/max return for NaN (the
     non-NaN operand on CUDA and on the main GPU vendors' hardware).

   SOURCES
     Annen, Mertens, Bekaert, Seidel, Kautz 2007, "Convolution Shadow Maps", EGSR (CSM);
     Bruneton & Neyret 2012 (survey) sec. 5, eqs. 31-38 and sec. 7.2; Donnelly & Lauritzen
     2006 (VSM, Chebyshev's one-tailed inequality); Lauritzen 2007 (GPU Gems 3 ch. 8, light
     bleeding reduction); Annen, Mertens, Seidel, Flerackers, Kautz 2008 and Salvi 2008 (ESM);
     Lauritzen & McCool 2008 (EVSM, layered VSM); Peters & Klein 2015, "Moment Shadow
     Mapping", I3D (Hamburger 4MSM, Algorithm 2, with the author's erratum: the last case
     returns 1 - w1; Hausdorff 4MSM; sec. 4.3, the optimized 16-bit quantization); Krein &
     Nudelman 1977, "The Markov Moment Problem and Extremal Problems" (canonical
     representations, for the Hausdorff extremals). */
#ifndef PF_SHADOW_H
#define PF_SHADOW_H

#ifndef PF_GLSL
#  include "pf_moments.h"
#endif

/* ---------------------------------------------------------------- defaults (docs/shadow.md)
   PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT  1e-6: about 8 float roundings of E[z^2] <= 1 (8 x 2^-23),
       so the cancellation in E[z^2] - E[z]^2 cannot make a flat lit surface self-shadow; it
       also sets how fast a flat occluder's shadow falls off behind it: the bound is 1/2 at
       d - z = 1e-3. For EVSM it is a variance in depth units, scaled by the warp's
       derivative (below).
   PF_SHADOW_BLEED_DEFAULT  0: no light-bleeding reduction, so the Chebyshev value stays an
       upper bound (exact on a planar occluder). 0.2-0.4 trades leaks for darker penumbrae.
   PF_SHADOW_ESM_EXPONENT_DEFAULT  80: Annen et al. 2008's order of magnitude for [0, 1]
       depths; the leak behind an occluder at distance g is exp(-80 g) (0.45 at g = 0.01).
   PF_SHADOW_EVSM_POS_DEFAULT / _NEG_DEFAULT  40 / 5: the positive exponent just under the
       fp32 limit PF_EVSM_EXP_MAX_F32 = 44 (pf_moments.h); the negative warp only has to catch
       what the positive one leaks (receivers far behind a multi-layer footprint).
   PF_SHADOW_MSM_MOMENT_BIAS_DEFAULT  3e-5: Peters & Klein 2015's bias for fp32 moments.
   PF_SHADOW_MSM_DEPTH_BIAS_DEFAULT   0: the lit bound already includes the receiver's own
       depth (a lit plane at d = z reads 1); add a bias only for sloped receivers. */
#define PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT PF_R(1.0e-6)
#define PF_SHADOW_BLEED_DEFAULT PF_R(0.0)
#define PF_SHADOW_ESM_EXPONENT_DEFAULT PF_R(80.0)
#define PF_SHADOW_EVSM_POS_DEFAULT PF_R(40.0)
#define PF_SHADOW_EVSM_NEG_DEFAULT PF_R(5.0)
#define PF_SHADOW_MSM_MOMENT_BIAS_DEFAULT PF_R(3.0e-5)
#define PF_SHADOW_MSM_DEPTH_BIAS_DEFAULT PF_R(0.0)

/* Bytes per texel each method stores with fp32 channels (16-bit formats: PF_SHADOW_BYTES_MSM16,
   _VSM16, _EVSM2_16, _EVSM4_16 below; EVSM in fp16 only with exponents <= PF_EVSM_EXP_MAX_F16). */
#define PF_SHADOW_BYTES_VSM 8
#define PF_SHADOW_BYTES_ESM 4
#define PF_SHADOW_BYTES_EVSM2 8
#define PF_SHADOW_BYTES_EVSM4 16
#define PF_SHADOW_BYTES_MSM 16

/* ---------------------------------------------------------------- Chebyshev
   One lean form serves VSM, EVSM and the any-scale bound (the textbook formula's
   cost, with the library's robustness), branch-free in every language (C -ffast-math builds
   excepted, below):
       ratio = var / (var + t^2),   t = max(x - mean, 0),   var in [PF_REAL_MIN, PF_REAL_MAX/4].
   t = 0 (receiver at or in front of the mean) gives var/var = 1 exactly, so one max replaces
   the textbook's "x <= mean ? 1 : ..." (a compare and a select, or a branch). The variance is
   clamped once: var >= PF_REAL_MIN keeps 0/0 out (t^2 underflows to 0 for tiny t; min_variance
   may be 0), var <= PF_REAL_MAX/4 keeps inf/inf out. var + t^2 >= var, so the rounded quotient
   is in [0, 1] with no clamp; an infinite t^2 gives 0. t is passed as x - mean. The CPU takes
   the same form: a branch that skipped the division for receivers in front was mispredicted
   on mixed receivers (bench_shadow vs_textbook_vsm: 1.13x the textbook formula with it, 0.97x
   without). */
PF_DEF pf_real pfi_shadow_chebyshev_ratio(pf_real var, pf_real t)
{
#if defined(__FAST_MATH__) && !defined(PF_GLSL) && !defined(__CUDACC__)
    /* under clang -ffast-math the branch-free form returned values above 1 (edge_shadow_finite:
       488 of 302988 in float), so C fast-math builds keep the exact 1 for receivers in front */
    return t > PF_R(0.0) ? var / (var + t * t) : PF_R(1.0);
#else
    pf_real tp = pf_max(t, PF_R(0.0)); /* NaN t: 0, so 1 (C, CUDA) */
    return var / (var + tp * tp);
#endif
}

/* linstep(threshold, 1, q) for q in [0, 1] (Lauritzen 2007): q - th <= 1 - th, so the quotient
   is <= 1 and only its lower side is clamped (a NaN threshold, C: 0). */
PF_DEF pf_real pfi_shadow_linstep(pf_real q, pf_real threshold)
{
    pf_real th = pf_clamp(threshold, PF_R(0.0), PF_R(0.999));
    return pf_max((q - th) / (PF_R(1.0) - th), PF_R(0.0));
}

/* pf_shadow_chebyshev_upper: upper bound on P(X >= x) for a random X with mean m1 and second
   moment m2 (Cantelli's one-tailed form of Chebyshev's inequality, Donnelly & Lauritzen 2006;
   B&N 2012 after eq. 35):
       P(X >= x) <= s2 / (s2 + (x - m1)^2)   if x > m1,   else 1,
   with s2 = max(m2 - m1^2, min_variance). The bound is attained by the two-point
   distribution with atoms x and m1 - s2/(x - m1), i.e. it is exact for a planar occluder in
   front of a planar receiver. Any scale: the values are divided by max(|m1|, |x|) first, so
   m2 ~ 1e38 neither overflows nor loses the bound; min_variance is in the units of X. Returns
   a value in [0, 1]; NaN moments give 1 (C). VSM and EVSM do not call it: their inputs are
   bounded (depths in [0, 1], warps <= exp(44)) and they skip the scaling. */
PF_DEF pf_real pf_shadow_chebyshev_upper(pf_real m1, pf_real m2, pf_real x, pf_real min_variance)
{
    pf_real s = pf_max(pf_max(PF_FABS(m1), PF_FABS(x)), PF_R(1.0e-30));
    pf_real inv = PF_R(1.0) / s;
    pf_real mu = m1 * inv;
    pf_real var = pf_max((m2 * inv) * inv - mu * mu, (min_variance * inv) * inv);
    var = pf_clamp_nan_lo(var, PF_REAL_MIN, PF_R(0.25) * PF_REAL_MAX);
    return pfi_shadow_chebyshev_ratio(var, x * inv - mu);
}

/* pf_shadow_reduce_bleeding: maps lit fractions below `threshold` to 0 and rescales the rest
   to [0, 1] (Lauritzen 2007): removes the light that Chebyshev lets through behind
   overlapping occluders, at the price of darker (no longer bounding) penumbrae. threshold in
   [0, 1) (clamped to [0, 0.999]); 0 returns lit unchanged (clamped to [0, 1]). */
PF_DEF pf_real pf_shadow_reduce_bleeding(pf_real lit, pf_real threshold)
{
    return pf_min(pfi_shadow_linstep(lit, threshold), PF_R(1.0));
}

/* ---------------------------------------------------------------- VSM */
/* pf_shadow_vsm: variance shadow map test (Donnelly & Lauritzen 2006; B&N 2012 eq. 35 with
   the Chebyshev bound). m = filtered (E[z], E[z^2]); d receiver depth; min_variance >= 0 (in
   depth^2, default PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT); bleed = light-bleeding threshold
   (default PF_SHADOW_BLEED_DEFAULT = 0, off). Lit fraction in [0, 1]: an upper bound on the
   true one when bleed = 0, exact for two depths with the receiver at the farther one.
   Cost: the textbook formula's (docs/shadow.md), branch-free. */
PF_DEF pf_real pf_shadow_vsm(pf_depth_moments2 m, pf_real d, pf_real min_variance, pf_real bleed)
{
    /* depths are in [0, 1]: m2 - m1^2 <= m2 is finite, so only the floor is needed; a NaN
       moment gives var = the floor and t = 0 (C), lit 1. m1^2 is rounded on its own (a
       separate, PF_EXACT statement): contracted into fma(-m1, m1, m2) it would return the
       rounding error of a stored point mass's m2 = fl(z^2) as a variance (~1e-8 in float at
       z ~ 1), lighting receivers well behind it (clang's default -ffp-contract=on with FMA) */
    PF_EXACT pf_real m1sq = m.m1 * m.m1;
    pf_real var = pf_max(m.m2 - m1sq, pf_max(min_variance, PF_REAL_MIN));
    return pfi_shadow_linstep(pfi_shadow_chebyshev_ratio(var, d - m.m1), bleed);
}

/* ---------------------------------------------------------------- ESM */
/* pf_shadow_esm: exponential shadow map test (Annen et al. 2008; Salvi 2008; B&N 2012 eq. 38):
       lit ~ min(1, exp(-c d) E[exp(c z)]) = min(1, exp(log_mean - c d)),
   where log_mean = log E[exp(c z)] is the footprint's value reduced in log space
   (pf_esm_log_from_depth / pf_esm_log_combine2 in pf_moments.h), so nothing overflows for
   any c. The exponent is clamped to [-80, 0] before exp (exp(-80) = 1.8e-35 is a normal
   float): a value of 0 is returned as 1.8e-35, and -inf or NaN log_mean give that too.
   Not a bound: it leaks exp(-c g) behind an occluder at distance g, and over-lights where
   the footprint holds texels behind the receiver (non-planar receivers). */
PF_DEF pf_real pf_shadow_esm(pf_real log_mean, pf_real d, pf_real c)
{
    pf_real e = pf_max(log_mean - c * d, PF_R(-80.0)); /* NaN -> -80 (comparison false) */
    return PF_EXP(pf_min(e, PF_R(0.0)));
}

/* ---------------------------------------------------------------- EVSM */
/* Chebyshev on a warped depth w(z) = +-exp(+-c (2z - 1)), increasing in z, so d <= z iff
   w(d) <= w(z) and the test keeps its meaning. The minimum variance is given in depth units
   and mapped through the warp's derivative dw/dz = 2 c |w| (Lauritzen & McCool 2008): a
   variance v in z is about v (dw/dz)^2 in w. We take the derivative at whichever of the
   receiver w(d) and the mean E[w] is nearer 0 (the smaller slope). At the receiver, as is
   common, a receiver far behind an occluder (E[w] << w(d)) would keep a leak of
   4 c^2 v / (1 + 4 c^2 v) (0.0064 at c = 40, v = 1e-6) however far it is; near the occluder,
   where the minimum variance matters (d ~ E[z]), both choices agree. The variance only
   matters when the receiver is behind the mean (t > 0; otherwise the ratio is 1), and there
   the point nearer 0 is known without a min: the mean for the positive warp
   (0 < E[p] < w(d)), the receiver for the negative one (E[n] < w(d) < 0); the caller passes
   it as `at`. No scaling: with c <= PF_EVSM_EXP_MAX_F32 the warps are <= exp(44) = 1.3e19 in
   magnitude, m2 - m1^2 <= m2 <= exp(88) and t^2 <= exp(88) stay finite, and the minimum
   variance (which a large min_variance can push past PF_REAL_MAX) is clamped with the floor. */
PF_DEF pf_real pfi_shadow_evsm_warped(pf_real m1, pf_real m2, pf_real w, pf_real at, pf_real c,
                                      pf_real min_variance)
{
    pf_real k = PF_R(2.0) * c * at;
    /* NaN -> floor: 0 * inf, should a compiler reassociate to min_variance (k k) */
    pf_real mv = pf_clamp_nan_lo((min_variance * k) * k, PF_REAL_MIN, PF_R(0.25) * PF_REAL_MAX);
    pf_real var = pf_max(m2 - m1 * m1, mv);
    return pfi_shadow_chebyshev_ratio(var, w - m1);
}

/* pf_shadow_evsm2: EVSM with the positive warp only (Lauritzen & McCool 2008): m = filtered
   (E[p], E[p^2]), p = exp(c_pos (2z - 1)) (pf_evsm2_from_depth). c_pos > 0, at most
   PF_EVSM_EXP_MAX_F32 (44) for fp32 storage, PF_EVSM_EXP_MAX_F16 (5.54) for fp16;
   min_variance in depth^2 (PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT); bleed as for VSM.
   Cost: the textbook formula's (docs/shadow.md), branch-free. */
PF_DEF pf_real pf_shadow_evsm2(pf_depth_moments2 m, pf_real d, pf_real c_pos, pf_real min_variance,
                               pf_real bleed)
{
    pf_real w = PF_EXP(c_pos * (PF_R(2.0) * d - PF_R(1.0)));
    return pfi_shadow_linstep(pfi_shadow_evsm_warped(m.m1, m.m2, w, m.m1, c_pos, min_variance), bleed);
}

/* pf_shadow_evsm4: EVSM with both warps (Lauritzen & McCool 2008): Chebyshev on the positive
   warp p = exp(c_pos zs) and on the negative warp n = -exp(-c_neg zs), zs = 2z - 1, and the
   smaller of the two upper bounds (both bound the same lit fraction). m from
   pf_evsm_moments_from_depth; exponents and min_variance as for pf_shadow_evsm2. The
   light-bleeding reduction is applied once, to the smaller bound (it is increasing, so this
   equals applying it to both, as shipped implementations do). */
PF_DEF pf_real pf_shadow_evsm4(pf_evsm_moments m, pf_real d, pf_real c_pos, pf_real c_neg,
                               pf_real min_variance, pf_real bleed)
{
    pf_real zs = PF_R(2.0) * d - PF_R(1.0);
    pf_real wn = -PF_EXP(-c_neg * zs);
    pf_real lit_pos = pfi_shadow_evsm_warped(m.pos1, m.pos2, PF_EXP(c_pos * zs), m.pos1, c_pos, min_variance);
    pf_real lit_neg = pfi_shadow_evsm_warped(m.neg1, m.neg2, wn, wn, c_neg, min_variance);
    return pfi_shadow_linstep(pf_min(lit_pos, lit_neg), bleed);
}

/* ---------------------------------------------------------------- MSM
   Hamburger 4MSM (Peters & Klein 2015, sec. 4 and Algorithm 2), on the REVERSED depth
   u = 1 - z: pf_depth_moments4 holds (E[u], E[u^2], E[u^3], E[u^4]) (pf_depth_moments4_from_depth
   stores them). Why reversed: fp32 rounds each stored moment to 2^-24 of its own size. Power
   moments of z near the far plane (where perspective depth piles up) are all ~1, so their
   rounding (6e-8) swamps what tells two depths 1e-4 apart (the second differences of the
   moments, ~0.55 (1 - z1)^2 = 5e-9); no formulation of the test can recover it, because
   distributions lighting 0.45 and 0.9997 of the footprint round to the same four floats. In u
   the same depths give moments ~(1 - z)^k, kept to 2^-24 relative. (Depths clustered near the
   light, u ~ 1, now see the rounding z-moments had near the far plane; that end is rare in
   perspective depth, where depth changes fastest there.)

   Given the biased moments b = (1 - a) m + a (1/2, 1/2, 1/2, 1/2) (the moments of a fair coin
   on {0, 1}: b stays a valid moment vector while the Hankel matrix gains rank) and the receiver
   uf = 1 - (d - depth_bias), the distribution with the fewest atoms that has moments b and an
   atom at uf has two more atoms: the roots of K(u) = c1 + c2 u + c3 u^2, where B c = v(uf),
   v(u) = (1, u, u^2) and B = [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]] is the Hankel matrix.
   K(u) = v(u)^T B^-1 v(uf) is the kernel polynomial, and the weight of each atom r is the
   Christoffel function w(r) = 1 / (v(r)^T B^-1 v(r)) (the quadrature is exact to degree 4).
   The lit fraction is P(z >= zf) = P(u <= uf); every distribution with moments b has
       P(u < uf) >= lower   and   P(u <= uf) <= upper,
       both roots above uf:     upper = w1,             lower = 0
       one root r below uf:     upper = w1 + w(r),      lower = w(r)
       both roots below uf:     upper = 1,              lower = 1 - w1
   with w1 = w(uf); both are attained (sharp). MSM returns the upper one as the lit fraction
   (Peters & Klein's "lower bound of the shadow intensity", with their erratum).

   Numerics (what Algorithm 2 computes, arranged so that nothing divides by a value that may
   vanish). B = L D L^T, L unit lower [[1,0,0],[b1,1,0],[b2,l32,1]], D = diag(1, d22, d33):
   d22 = b2 - b1^2 the variance, d33 the part of b4 that b1..b3 do not explain. A point mass
   gives d22 = 0, a two-point footprint d33 = 0, and rounding may make either negative; both
   are floored (raising b2 or b4 by the difference: still a valid moment vector), and the
   floors follow the precision of the moments: 4 eps b2 and 4 eps b4 (plus 1e-9, 1e-12), about
   the rounding the stored b2 and b4 carry. A pivot below its own rounding is noise, and
   reading it as data makes the bound arbitrary (it fell 0.9 below the truth on footprints
   clustered near the light); floored, the reconstruction moves toward the two-moment
   (Chebyshev) extremal, which bounds every distribution with the well-resolved b1, b2.
   Conditioning-aware floor and reversed storage together: docs/shadow.md. Forward
   substitution gives y = L^-1 v(uf) = (1, y2, y3), so
       1/w1 = K(uf) = 1 + y2^2/d22 + y3^2/d33 >= 1,
   a sum of squares: w1 in (0, 1] without cancellation. Around uf, K(uf + t) = c3 t^2 + B t +
   K(uf) with B = y2/d22 + c3 (2 uf - l32). K(uf) > 0, so c3 < 0 means one root on each side
   (the middle case), and for c3 >= 0 the sign of B says on which side both lie; no root is
   needed outside the middle case. There the root below uf is t = -2 K(uf) / (B + sqrt(B^2 -
   4 c3 K(uf))): the denominator exceeds 2|B| > 0, so it neither vanishes nor cancels. The
   quadratic is divided by K(uf) first (w1 times each coefficient), which bounds every term
   for any input. t needs no clamp: as c3 -> 0- the root goes to -infinity, t^2 overflows to
   +inf at worst and the root's weight to 1/inf = 0, its limit (no inf - inf on that path).
   Inputs: b1 saturated to [0, 1], b2, b3, b4 confined to what moments of depths in [0, 1]
   satisfy (b1^2 <= b2 <= b1, b2^2 <= b3 <= b2, b4 >= b2^2; valid vectors already do), NaN
   moments taking their lower bound (C, CUDA), and uf clamped to [-1, 2]; so with the floors
   every intermediate is finite for every finite input (a large b4 only makes i33 small), and
   the square root's argument is >= 0 (C reads qb^2 - 4 qa as qb^2 + 4 |qa|, the same where
   it is used). No input gives inf or NaN in the result.
   One square root, five divisions, no branch (bench/gpu/count.sh: 58 SPIR-V ops
   against the textbook's 54; CPU: see docs/shadow.md). */
#define PFI_MSM_D22_FLOOR PF_R(1.0e-9)
#define PFI_MSM_D33_FLOOR PF_R(1.0e-12)
#define PFI_MSM_NOISE (PF_R(4.0) * PF_REAL_EPSILON)

/* PFI_MSM_BIASED(x, a, keep, coin): the biased moment (1 - a) x + a/2: GLSL mix (one
   instruction), elsewhere keep x + coin (keep = 1 - a, coin = a/2, computed once per call).
   PFI_MSM_SAT(x): x clamped to [0, 1], NaN to 0 in C (pf_max's comparison is false for NaN)
   and CUDA (__saturatef); one clamp in GLSL. */
/* PFI_MSM_LOW(sq): the lower bound of a moment, the square below it in C and CUDA (a
   register operand: gcc compiles the comparison to one minss/maxss, against a literal to a
   branch; the square is needed anyway), 0 in GLSL (its clamp is one instruction either way,
   and spirv-opt would fuse the square's other use into an FMA and keep a second product). */
#ifdef PF_GLSL
#  define PFI_MSM_LOW(sq) PF_R(0.0)
#  define PFI_MSM_BIASED(x, a, keep, coin) mix(x, PF_R(0.5), a)
#  define PFI_MSM_SAT(x) clamp(x, PF_R(0.0), PF_R(1.0))
#else
#  define PFI_MSM_LOW(sq) (sq)
#  define PFI_MSM_BIASED(x, a, keep, coin) ((keep) * (x) + (coin))
#  if defined(__CUDA_ARCH__) && !defined(PF_DOUBLE)
#    define PFI_MSM_SAT(x) __saturatef(x)
#  else
#    define PFI_MSM_SAT(x) pf_min(pf_max(x, PF_R(0.0)), PF_R(1.0))
#  endif
#endif

/* The Hamburger 4MSM reconstruction (see above): upper = the upper bound of the lit fraction,
   w1 = the weight of the atom at the receiver, and what the Hausdorff form reuses: the
   confined biased moments b1..b4, the receiver uf (clamped to [uf_lo, uf_hi]) and the
   normalized kernel quadratic K(uf + t)/K(uf) = qa t^2 + qb t + 1. */
PF_STRUCT_BEGIN(pfi_msm_state)
    pf_real b1, b2, b3, b4, uf, qa, qb, w1, upper;
PF_STRUCT_END(pfi_msm_state)

/* PFI_MSM_INLINE: gcc -O2 stopped inlining this function once five evaluators called it, and
   returning the struct through memory cost pf_shadow_msm 20 instructions per lookup (164.3
   against 144.7, callgrind, bench_shadow); the one forced inline of the library, on the CPU
   compilers that take it. */
#if defined(__GNUC__) && !defined(PF_GLSL) && !defined(__CUDACC__)
#  define PFI_MSM_INLINE __attribute__((always_inline))
#else
#  define PFI_MSM_INLINE
#endif
PFI_MSM_INLINE PF_DEF pfi_msm_state pfi_shadow_msm_state(pf_depth_moments4 m, pf_real d, pf_real moment_bias, pf_real depth_bias,
                                          pf_real uf_lo, pf_real uf_hi, pf_real floor22, pf_real floor33)
{
    pfi_msm_state r;
    pf_real keep = PF_R(1.0) - moment_bias, coin = PF_R(0.5) * moment_bias;
    /* The moments are confined to what moments of depths in [0, 1] satisfy (u^2 <= u and
       Cauchy-Schwarz: b1^2 <= b2 <= b1, b2^2 <= b3 <= b2, b2^2 <= b4), which valid moment
       vectors, the biased ones included, meet already; only b1 has constant bounds. The
       bounds are the squares the factorization needs anyway, so each costs one min or max
       (one clamp in GLSL), and every intermediate stays bounded for every finite input.
       NaN (C, CUDA): pf_max's comparison is false, so a NaN moment takes its lower bound;
       this is the only NaN sanitizing. b4 needs no upper bound: a large b4 only makes d33
       large (i33 small). */
    pf_real b1 = PFI_MSM_SAT(PFI_MSM_BIASED(m.m1, moment_bias, keep, coin));
    pf_real b11 = b1 * b1;
    pf_real b2 = pf_clamp_nan_lo(PFI_MSM_BIASED(m.m2, moment_bias, keep, coin), PFI_MSM_LOW(b11), b1);
    pf_real b22 = b2 * b2;
    pf_real b3 = pf_clamp_nan_lo(PFI_MSM_BIASED(m.m3, moment_bias, keep, coin), PFI_MSM_LOW(b22), b2);
    pf_real b4 = pf_max(PFI_MSM_BIASED(m.m4, moment_bias, keep, coin), PFI_MSM_LOW(b22));
    pf_real uf = pf_clamp_nan_lo(PF_R(1.0) - (d - depth_bias), uf_lo, uf_hi);
    /* L D L^T of the Hankel matrix */
    pf_real i22 = PF_R(1.0) / pf_max(b2 - b11, PFI_MSM_NOISE * b2 + floor22);
    pf_real e32 = b3 - b1 * b2; /* l32 d22 */
    pf_real l32 = e32 * i22;
    pf_real i33 = PF_R(1.0) / pf_max((b4 - b22) - l32 * e32, PFI_MSM_NOISE * b4 + floor33);
    /* y = L^-1 v(uf); c3 = y3/d33; K(uf) = 1 + y2^2/d22 + y3^2/d33 */
    pf_real y2 = uf - b1;
    pf_real y3 = (uf * uf - b2) - l32 * y2;
    pf_real g = y2 * i22;
    pf_real c3 = y3 * i33;
    pf_real w1 = PF_R(1.0) / ((PF_R(1.0) + y2 * g) + y3 * c3);
    /* K(uf + t)/K(uf) = qa t^2 + qb t + 1; the root below uf (used only when qa < 0) */
    pf_real s = uf + (uf - l32);
    pf_real qa = c3 * w1;
    pf_real qb = (c3 * s + g) * w1;
    /* The discriminant qb^2 - 4 qa; only the middle case (qa < 0) uses t. C and CUDA read
       it as qb^2 + 4 |qa|, the same there and >= 0 everywhere (no sqrt of a negative: no
       NaN, no errno call); GLSL's select discards the other side's NaN, so it keeps the
       plain form (one op less). qa < 0 makes qb + sq > 0, so t < 0; t needs no clamp: a far
       root (qa -> 0-) overflows t^2 to +inf, and its weight below to 1/inf = 0, its limit. */
#ifdef PF_GLSL
    pf_real sq = PF_SQRT(qb * qb - PF_R(4.0) * qa);
#else
    pf_real sq = PF_SQRT(qb * qb + PF_R(4.0) * PF_FABS(qa));
#endif
    pf_real t = PF_R(-2.0) / (qb + sq);
    /* its weight, the Christoffel function at uf + t: y2, y3 moved by t */
    pf_real y2t = y2 + t;
    pf_real y3t = y3 + t * (s + t);
    pf_real wt = PF_R(1.0) / ((PF_R(1.0) + y2t * y2t * i22) + y3t * y3t * i33);
    /* selects of plain values (no branch in SPIR-V or PTX); w1 and wt are in [0, 1], so the
       upper bound only needs its top clamped (rounding in w1 + wt) */
    pf_real middle = w1 + wt;
    pf_real outside = qb > PF_R(0.0) ? PF_R(1.0) : w1;
    pf_real upper = qa < PF_R(0.0) ? middle : outside;
    r.b1 = b1; r.b2 = b2; r.b3 = b3; r.b4 = b4; r.uf = uf; r.qa = qa; r.qb = qb; r.w1 = w1;
    r.upper = pf_min(upper, PF_R(1.0));
    return r;
}

/* (upper, w1) of the Hamburger reconstruction, the receiver clamped to [-1, 2]. */
PF_DEF pf_vec2 pfi_shadow_msm_core(pf_depth_moments4 m, pf_real d, pf_real moment_bias, pf_real depth_bias)
{
    pfi_msm_state r = pfi_shadow_msm_state(m, d, moment_bias, depth_bias, PF_R(-1.0), PF_R(2.0), PFI_MSM_D22_FLOOR,
                                           PFI_MSM_D33_FLOOR);
    return pf_vec2_make(r.upper, r.w1);
}

/* pf_shadow_msm_bounds: (lower, upper) bounds of the lit fraction from the four biased
   moments (see above); lower <= upper, both in [0, 1]. */
PF_DEF pf_vec2 pf_shadow_msm_bounds(pf_depth_moments4 m, pf_real d, pf_real moment_bias, pf_real depth_bias)
{
    pf_vec2 r = pfi_shadow_msm_core(m, d, moment_bias, depth_bias);
    return pf_vec2_make(PFI_MSM_SAT(r.x - r.y), r.x);
}

/* pf_shadow_msm: moment shadow map test (Peters & Klein 2015, Hamburger 4MSM): the sharp upper
   bound of the lit fraction given the four biased moments (see pf_shadow_msm_bounds).
   m = filtered moments of the reversed depth u = 1 - z, (E[u], E[u^2], E[u^3], E[u^4])
   (pf_depth_moments4_from_depth); moment_bias in [0, 1] (PF_SHADOW_MSM_MOMENT_BIAS_DEFAULT =
   3e-5 for fp32 moments); depth_bias subtracted from d (PF_SHADOW_MSM_DEPTH_BIAS_DEFAULT = 0).
   Returns a value in [0, 1] for every finite input. */
PF_DEF pf_real pf_shadow_msm(pf_depth_moments4 m, pf_real d, pf_real moment_bias, pf_real depth_bias)
{
    return pfi_shadow_msm_core(m, d, moment_bias, depth_bias).x;
}

/* ---------------------------------------------------------------- MSM, Hausdorff
   pf_shadow_msm_hausdorff: the sharp upper bound of the lit fraction over distributions of
   u = 1 - z SUPPORTED IN [0, 1] (the truncated Hausdorff moment problem; Peters & Klein 2015
   sec. 4, Hausdorff 4MSM), where pf_shadow_msm bounds over all distributions on the real line
   (Hamburger). Knowing the depths lie in [0, 1] can only tighten the bound, and does so where
   a Hamburger atom falls outside [0, 1]. Same inputs, same defaults.
   The extremal distributions (Krein & Nudelman's canonical representations of index 3, the
   end points counting 1/2) that put an atom at uf are: the Hamburger three atoms when both
   roots of the kernel K lie in [0, 1]; otherwise four atoms {0, uf, x, 1}. Tested without a
   root: p(t) = K(uf + t)/K(uf) = qa t^2 + qb t + 1 has p(0) = 1, so with lo = -uf, hi = 1 - uf
   both roots are in [lo, hi] iff  qa < 0: p(lo) <= 0 and p(hi) <= 0;  qa >= 0, qb < 0 (both
   above): p(hi) >= 0 and -qb <= 2 qa hi;  qb >= 0 (both below): p(lo) >= 0 and -qb >= 2 qa lo.
   The four-atom case through nu = u (1 - u) mu, which does not see the end atoms: its moments
   n0 = b1 - b2, n1 = b2 - b3, n2 = b3 - b4 are matched by atoms uf and x alone, so with
   nu's Hankel LDL^T (e11 = n0, l = n1/n0, e22 = n2 - l n1) and g = uf - l
       a_f = e11 e22 / D,  a_x = e11^2 g^2 / D,  D = e22 + e11 g^2    (nu's Christoffel weights,
       x = l - e22 / (e11 g): x > uf iff g < 0)                       both >= 0, no cancellation)
   and mu's weights follow from a = w u (1 - u) and b1 = w_1 + w_f uf + w_x x:
       g < 0 (x above uf): upper = 1 - w_1 - w_x = 1 - b1 + a_f/(1 - uf) - a_x/x
       g > 0 (x below uf): upper = 1 - w_1       = 1 - b1 + a_f/(1 - uf) + a_x/(1 - x)
   with a_x/x = a_x e11 |g| / (l e11 |g| + e22) and a_x/(1 - x) = a_x e11 g / ((1 - l) e11 g +
   e22): every denominator is >= e22, floored like the Hamburger pivots (4 eps b + 1e-9 for
   e11, 4 eps b3 + 1e-12 for e22); 1 - uf is floored at 1e-18 (uf = 1 is a receiver at the
   light: the bound is 1, and the min below returns the Hamburger 1). The result is
   min(Hamburger, max(four-atom, 0)): the Hausdorff bound never exceeds the Hamburger one, so the
   min changes no exact value and keeps any rounding of the four-atom form from raising the
   bound. The receiver is clamped to uf in [0, 1] (the support). Every intermediate is finite
   for every finite input; the result is in [0, 1]. */
PF_DEF pf_real pfi_shadow_msm_hausdorff_f(pf_depth_moments4 m, pf_real d, pf_real moment_bias, pf_real depth_bias,
                                          pf_real floor22, pf_real floor33)
{
    pfi_msm_state r = pfi_shadow_msm_state(m, d, moment_bias, depth_bias, PF_R(0.0), PF_R(1.0), floor22, floor33);
    pf_real uf = r.uf, lo = -uf, hi = PF_R(1.0) - uf;
    pf_real plo = PF_R(1.0) + lo * (r.qb + r.qa * lo);
    pf_real phi = PF_R(1.0) + hi * (r.qb + r.qa * hi);
    pf_real two_qa = r.qa + r.qa;
    /* each case's conditions as one value that is >= 0 iff they hold (selects, no bool) */
    pf_real in_mid = -pf_max(plo, phi);
    pf_real in_above = pf_min(phi, two_qa * hi + r.qb);
    pf_real in_below = pf_min(plo, -(two_qa * lo + r.qb));
    pf_real in_one_side = r.qb < PF_R(0.0) ? in_above : in_below;
    pf_real inside = r.qa < PF_R(0.0) ? in_mid : in_one_side;
    /* nu = u (1 - u) mu: b2 <= b1 and b3 <= b2 after the confinement, so n0, n1 >= 0 */
    pf_real e11 = pf_max(r.b1 - r.b2, PFI_MSM_NOISE * r.b1 + floor22);
    pf_real n1 = r.b2 - r.b3;
    pf_real l = pf_min(n1 / e11, PF_R(1.0));
    pf_real e22 = pf_max((r.b3 - r.b4) - l * n1, PFI_MSM_NOISE * r.b3 + floor33);
    pf_real g = uf - l, ag = PF_FABS(g);
    pf_real eg = e11 * ag;
    pf_real den = e22 + eg * ag;
    pf_real af = e11 * e22 / den;
    pf_real ax = eg * eg / den;
    /* selects of plain values (no branch in SPIR-V): the far atom's share and its sign */
    pf_real one_minus_l = PF_R(1.0) - l;
    pf_real lever = g < PF_R(0.0) ? l : one_minus_l;
    pf_real sgn = g < PF_R(0.0) ? PF_R(-1.0) : PF_R(1.0);
    pf_real far_term = ax * eg / (lever * eg + e22);
    pf_real four = (PF_R(1.0) - r.b1) + af / pf_max(hi, PF_R(1.0e-18)) + sgn * far_term;
    pf_real outside = pf_min(r.upper, pf_max(four, PF_R(0.0)));
    return inside >= PF_R(0.0) ? r.upper : outside;
}

PF_DEF pf_real pf_shadow_msm_hausdorff(pf_depth_moments4 m, pf_real d, pf_real moment_bias, pf_real depth_bias)
{
    return pfi_shadow_msm_hausdorff_f(m, d, moment_bias, depth_bias, PFI_MSM_D22_FLOOR, PFI_MSM_D33_FLOOR);
}

/* ---------------------------------------------------------------- MSM at 64 bits per texel
   Peters & Klein 2015 sec. 4.3 ("optimized moment quantization"): four power moments stored
   as 16-bit UNORM lose the differences the reconstruction reads (the moment curve of [0, 1]
   fills a thin sliver of [0, 1]^4), so the texel stores instead
       q = Theta (b1, b2, b3, b4)^T + (0.035955884801, 0, 0, 0)^T
   with the paper's fixed 4x4 matrix Theta (the rows below), chosen so that the image of the
   moment curve of depths in [0, 1] spreads over [0, 1]^4 (measured on 10^5 depths: every
   component in [-6.5e-8, 1]; the encoders clamp to [0, 1]). The shader reads the filtered q
   and inverts: b = Theta^-1 (q - o); Theta^-1's rows (below, computed exactly from the
   paper's decimals and rounded) have absolute sums <= 1.414, so a UNORM16 rounding of
   2^-17 per channel moves each moment by <= 1.08e-5 (the pivot floors and the bias below
   cover that).
   Linear: q is an affine function of the moments, so decode(lerp(q_a, q_b, t)) =
   lerp(b_a, b_b, t) exactly (up to the storage rounding): hardware bilinear, trilinear and
   anisotropic filtering of the stored texels still filters the moments
   (test_msm16_linear). The library applies it to its reversed-depth moments (u = 1 - z, u
   in [0, 1], the same moment curve), so the decoded moments are the ones pf_shadow_msm
   reads; pf_shadow_msm16 and _hausdorff read them with pivot floors set for the storage
   noise.
   Noise and bias. The UNORM16 rounding (<= 1.08e-5 per moment) is absolute, not relative like
   fp32's, so pf_shadow_msm16 and pf_shadow_msm16_hausdorff floor the pivots at that level
   (d22 >= 1e-5, d33 >= 3e-7, against 1e-9 and 1e-12 for fp32 moments; same form otherwise):
   a pivot below the storage noise is read as the two-moment extremal, as for fp32 (see the
   pivot floors above). Call them, not pf_shadow_msm on dequantized moments.
   PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT 2e-5, chosen with the floors by a scan on the bench
   scenes and on the clustered footprints of test_msm16_clustered_falls (biases 0 .. 1e-3,
   d22 floors 5e-6 .. 1e-4, d33 floors 3e-8 .. 3e-7; docs/shadow.md): the pair that keeps the
   lit fraction within 0.002 of fp32 MSM at its default on every scene, with less mean error
   and less leaking than fp32, and at most one fall of more than 0.1 below the truth in
   40000 clustered footprints (0 falls needed 3e-5 floors, which cost 0.011 on the scenes).
   Peters & Klein's 3e-5 is the fp32 bias. */
#define PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT PF_R(2.0e-5)
#define PF_SHADOW_BYTES_MSM16 8
#define PF_SHADOW_MSM16_OFFSET PF_R(0.035955884801)
#ifndef PFI_MSM16_D22_FLOOR
#  define PFI_MSM16_D22_FLOOR PF_R(1.0e-5)
#endif
#ifndef PFI_MSM16_D33_FLOOR
#  define PFI_MSM16_D33_FLOOR PF_R(3.0e-7)
#endif

/* q = Theta b + o: the values to store (16-bit UNORM) for the moments b of u = 1 - z. */
PF_DEF pf_depth_moments4 pf_msm_quantize_moments(pf_depth_moments4 b)
{
    return pf_depth_moments4_make(
        ((PF_R(-2.07224649) * b.m1 + PF_R(32.23703778) * b.m2) + (PF_R(-68.571074599) * b.m3 + PF_R(39.3703274134) * b.m4))
            + PF_SHADOW_MSM16_OFFSET,
        (PF_R(13.7948857237) * b.m1 + PF_R(-59.4683975703) * b.m2) + (PF_R(82.0359750338) * b.m3 + PF_R(-35.364903257) * b.m4),
        (PF_R(0.105877704) * b.m1 + PF_R(-1.9077466311) * b.m2) + (PF_R(9.3496555107) * b.m3 + PF_R(-6.6543490743) * b.m4),
        (PF_R(9.7924062118) * b.m1 + PF_R(-33.7652110555) * b.m2) + (PF_R(47.9456096605) * b.m3 + PF_R(-23.9728048165) * b.m4));
}

/* b = Theta^-1 (q - o): the moments of u = 1 - z from the filtered stored values q (each in
   [0, 1] as a UNORM texture returns them; any finite q gives finite moments, which the MSM
   tests confine). */
PF_DEF pf_depth_moments4 pf_msm_dequantize_moments(pf_depth_moments4 q)
{
    pf_real q0 = q.m1 - PF_SHADOW_MSM16_OFFSET;
    return pf_depth_moments4_make(
        (PF_R(0.22277441458975106) * q0 + PF_R(0.077197286078127286) * q.m2) + (PF_R(0.79269866365602848) * q.m3 + PF_R(0.031941755461409697) * q.m4),
        (PF_R(0.15496792611583607) * q0 + PF_R(0.13946294265353615) * q.m2) + (PF_R(0.79634158378587572) * q.m3 + PF_R(-0.17228231730199037) * q.m4),
        (PF_R(0.14519889456443683) * q0 + PF_R(0.21202021568252677) * q.m2) + (PF_R(0.72586944638507078) * q.m3 + PF_R(-0.27580148114915759) * q.m4),
        (PF_R(0.16312744299137799) * q0 + PF_R(0.25914322664410966) * q.m2) + (PF_R(0.65390924967369524) * q.m3 + PF_R(-0.33761317340581742) * q.m4));
}

/* pf_shadow_msm16: the Hamburger test of a 64-bit texel: pf_shadow_msm of the dequantized
   filtered values q (moment_bias PF_SHADOW_MSM16_MOMENT_BIAS_DEFAULT). In [0, 1] for every
   finite q. */
PF_DEF pf_real pf_shadow_msm16(pf_depth_moments4 q, pf_real d, pf_real moment_bias, pf_real depth_bias)
{
    return pfi_shadow_msm_state(pf_msm_dequantize_moments(q), d, moment_bias, depth_bias, PF_R(-1.0), PF_R(2.0),
                                PFI_MSM16_D22_FLOOR, PFI_MSM16_D33_FLOOR).upper;
}

/* pf_shadow_msm16_hausdorff: the same with the Hausdorff bound. */
PF_DEF pf_real pf_shadow_msm16_hausdorff(pf_depth_moments4 q, pf_real d, pf_real moment_bias, pf_real depth_bias)
{
    return pfi_shadow_msm_hausdorff_f(pf_msm_dequantize_moments(q), d, moment_bias, depth_bias, PFI_MSM16_D22_FLOOR,
                                      PFI_MSM16_D33_FLOOR);
}

/* ---------------------------------------------------------------- 16- and 32-bit float storage
   VSM and EVSM store their moments in fp16 (RG16F / RGBA16F) or fp32. The EVSM warp exponent
   must keep exp(c) and its square exp(2c) below the format's largest finite value:
   PF_EVSM_EXP_MAX_F16 = 5.54 (exp(11.08) = 64853 < 65504, which rounds to 64864 in fp16) and
   PF_EVSM_EXP_MAX_F32 = 44 (pf_moments.h). The fp16 defaults take the ceiling for both warps.
   fp16 keeps 11 significant bits, so a stored depth near the far plane is off by up to 2^-12
   (2.4e-4) and E[z^2] - E[z]^2 by up to 3 x 2^-12: fp16 VSM reads spurious variance where the
   footprint is flat and leaks behind contact occluders (docs/shadow.md: mean leak 0.23 against
   0.10 with fp32 on the bench scenes). A larger minimum variance does not help: a scan of
   1e-6 .. 7e-4 on the bench scenes gave the lowest error and leak at 1e-6 for fp16 VSM and
   EVSM alike (EVSM maps it through the warp's slope, and fp16's relative rounding of the warp
   is far below it), and no receiver-at-its-own-depth error gained from a larger one; so
   PF_SHADOW_VSM16_MIN_VARIANCE_DEFAULT is the fp32 default. Float storage is linear up to its
   rounding: the sampler filters the decoded values. */
#define PF_SHADOW_EVSM16_POS_DEFAULT PF_EVSM_EXP_MAX_F16
#define PF_SHADOW_EVSM16_NEG_DEFAULT PF_EVSM_EXP_MAX_F16
#define PF_SHADOW_VSM16_MIN_VARIANCE_DEFAULT PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT
#define PF_SHADOW_BYTES_VSM16 4
#define PF_SHADOW_BYTES_EVSM2_16 4
#define PF_SHADOW_BYTES_EVSM4_16 8

#ifndef PF_GLSL
/* ---------------------------------------------------------------- CPU encoders (caller buffers)
   pf_shadow_encode_f32 / _f16(kind, depth, n, c_pos, c_neg, out): the per-texel values of n
   depths, pf_shadow_store_channels(kind) per texel, written to out as fp32 (float) or as fp16
   bit patterns (unsigned short, round to nearest even):
     PF_SHADOW_STORE_VSM    2 channels  (z, z^2)                       pf_depth_moments2_from_depth
     PF_SHADOW_STORE_EVSM2  2 channels  (p, p^2), p = exp(c_pos (2z - 1))   pf_evsm2_from_depth
     PF_SHADOW_STORE_EVSM4  4 channels  (p, p^2, n, n^2), n = -exp(-c_neg (2z - 1))
     PF_SHADOW_STORE_MSM    4 channels  (u, u^2, u^3, u^4), u = 1 - z     pf_depth_moments4_from_depth
   pf_shadow_encode_msm16(depth, n, out): 4 UNORM16 values per texel, round(65535 q) of the
   optimized quantization above, computed in double whatever pf_real is.
   pf_shadow_encode_msm16_moments(b, n, out): the same from n filtered moment vectors (a blurred
   map or a mip level stored at 64 bits).
   Return PF_OK, or, having written nothing: PF_ERR_ARG for a NULL pointer, n < 0, an unknown
   kind, a depth that is NaN, infinite or outside [0, 1], a moment outside [-1, 2] (those of
   depths in [0, 1] lie in [0, 1]; NaN and infinities included), or an exponent
   that is not finite, not positive or above the format's ceiling (PF_EVSM_EXP_MAX_F16 for
   fp16, PF_EVSM_EXP_MAX_F32 for fp32; c_neg only checked for EVSM4); PF_ERR_SIZE when
   the output would exceed PF_MAX_REALS values. c_pos, c_neg are ignored by VSM and MSM.
   Decoders: pf_real_from_half(h) returns a finite value for every bit pattern (an
   infinity reads as +-65504, a NaN as 0; what a GPU sampler returns for those is its own);
   pf_shadow_decode_msm16(t) the moments of u from 4 UNORM16 values (any values: finite). */
#define PF_SHADOW_STORE_VSM 0
#define PF_SHADOW_STORE_EVSM2 1
#define PF_SHADOW_STORE_EVSM4 2
#define PF_SHADOW_STORE_MSM 3

PF_CPU_DEF int pf_shadow_store_channels(int kind)
{
    return kind == PF_SHADOW_STORE_VSM || kind == PF_SHADOW_STORE_EVSM2 ? 2
         : (kind == PF_SHADOW_STORE_EVSM4 || kind == PF_SHADOW_STORE_MSM ? 4 : 0);
}

PF_CPU_DEF int pfi_shadow_exponent_ok(pf_real c, pf_real ceiling)
{
    return c > PF_R(0.0) && c <= ceiling; /* false for NaN */
}

/* Checks every input before anything is written (see above). */
PF_CPU_DEF int pfi_shadow_encode_check(int kind, const pf_real *depth, long long n, pf_real c_pos, pf_real c_neg,
                                       pf_real ceiling, const void *out)
{
    long long i;
    int ch = pf_shadow_store_channels(kind);
    if (!depth || !out || n < 0 || ch == 0) return PF_ERR_ARG;
    if (pf_size_mul(n, ch) < 0) return PF_ERR_SIZE;
    if ((kind == PF_SHADOW_STORE_EVSM2 || kind == PF_SHADOW_STORE_EVSM4) && !pfi_shadow_exponent_ok(c_pos, ceiling))
        return PF_ERR_ARG;
    if (kind == PF_SHADOW_STORE_EVSM4 && !pfi_shadow_exponent_ok(c_neg, ceiling)) return PF_ERR_ARG;
    for (i = 0; i < n; ++i)
        if (!(depth[i] >= PF_R(0.0) && depth[i] <= PF_R(1.0))) return PF_ERR_ARG;
    return PF_OK;
}

/* The 2 or 4 values of one depth (validated) in double. */
PF_CPU_DEF void pfi_shadow_store_values(int kind, pf_real z, pf_real c_pos, pf_real c_neg, double *v)
{
    double zd = (double)z, u = 1.0 - zd;
    if (kind == PF_SHADOW_STORE_VSM) { v[0] = zd; v[1] = zd * zd; return; }
    if (kind == PF_SHADOW_STORE_MSM) { v[0] = u; v[1] = u * u; v[2] = u * u * u; v[3] = v[1] * v[1]; return; }
    /* the warps in pf_real (the PF_EXP of pf_moments.h's constructors), their squares in double */
    v[0] = (double)pf_evsm_warp_pos(z, c_pos);
    v[1] = v[0] * v[0];
    if (kind == PF_SHADOW_STORE_EVSM4) {
        v[2] = (double)pf_evsm_warp_neg(z, c_neg);
        v[3] = v[2] * v[2];
    }
}

PF_CPU_DEF int pf_shadow_encode_f32(int kind, const pf_real *depth, long long n, pf_real c_pos, pf_real c_neg,
                                    float *out)
{
    long long i;
    int k, ch = pf_shadow_store_channels(kind);
    int rc = pfi_shadow_encode_check(kind, depth, n, c_pos, c_neg, PF_EVSM_EXP_MAX_F32, out);
    if (rc != PF_OK) return rc;
    for (i = 0; i < n; ++i) {
        double v[4];
        pfi_shadow_store_values(kind, depth[i], c_pos, c_neg, v);
        for (k = 0; k < ch; ++k) out[i * ch + k] = (float)v[k];
    }
    return PF_OK;
}

PF_CPU_DEF int pf_shadow_encode_f16(int kind, const pf_real *depth, long long n, pf_real c_pos, pf_real c_neg,
                                    unsigned short *out)
{
    long long i;
    int k, ch = pf_shadow_store_channels(kind);
    int rc = pfi_shadow_encode_check(kind, depth, n, c_pos, c_neg, PF_EVSM_EXP_MAX_F16, out);
    if (rc != PF_OK) return rc;
    for (i = 0; i < n; ++i) {
        double v[4];
        pfi_shadow_store_values(kind, depth[i], c_pos, c_neg, v);
        /* through pf_real: exact for the fp16 values, and double's extra bits only matter at ties */
        for (k = 0; k < ch; ++k) out[i * ch + k] = pf_half_from_real((pf_real)v[k]);
    }
    return PF_OK;
}

/* round(65535 clamp(Theta b + o, 0, 1)) of one moment vector, in double */
PF_CPU_DEF void pfi_shadow_msm16_store(double b1, double b2, double b3, double b4, unsigned short *out)
{
    double q[4];
    int k;
    q[0] = ((-2.07224649 * b1 + 32.23703778 * b2) + (-68.571074599 * b3 + 39.3703274134 * b4)) + 0.035955884801;
    q[1] = (13.7948857237 * b1 - 59.4683975703 * b2) + (82.0359750338 * b3 - 35.364903257 * b4);
    q[2] = (0.105877704 * b1 - 1.9077466311 * b2) + (9.3496555107 * b3 - 6.6543490743 * b4);
    q[3] = (9.7924062118 * b1 - 33.7652110555 * b2) + (47.9456096605 * b3 - 23.9728048165 * b4);
    for (k = 0; k < 4; ++k) {
        double c = q[k] > 0.0 ? (q[k] < 1.0 ? q[k] : 1.0) : 0.0; /* NaN: 0 */
        out[k] = (unsigned short)(c * 65535.0 + 0.5);
    }
}

PF_CPU_DEF int pf_shadow_encode_msm16(const pf_real *depth, long long n, unsigned short *out)
{
    long long i;
    int rc = pfi_shadow_encode_check(PF_SHADOW_STORE_MSM, depth, n, PF_R(0.0), PF_R(0.0), PF_R(0.0), out);
    if (rc != PF_OK) return rc;
    for (i = 0; i < n; ++i) {
        double v[4];
        pfi_shadow_store_values(PF_SHADOW_STORE_MSM, depth[i], PF_R(0.0), PF_R(0.0), v);
        pfi_shadow_msm16_store(v[0], v[1], v[2], v[3], out + 4 * i);
    }
    return PF_OK;
}

PF_CPU_DEF int pf_shadow_encode_msm16_moments(const pf_depth_moments4 *b, long long n, unsigned short *out)
{
    long long i;
    if (!b || !out || n < 0) return PF_ERR_ARG;
    if (pf_size_mul(n, 4) < 0) return PF_ERR_SIZE;
    for (i = 0; i < n; ++i) /* moments of depths in [0, 1] lie in [0, 1]; NaN fails too */
        if (!(b[i].m1 >= PF_R(-1.0) && b[i].m1 <= PF_R(2.0) && b[i].m2 >= PF_R(-1.0) && b[i].m2 <= PF_R(2.0)
              && b[i].m3 >= PF_R(-1.0) && b[i].m3 <= PF_R(2.0) && b[i].m4 >= PF_R(-1.0) && b[i].m4 <= PF_R(2.0)))
            return PF_ERR_ARG;
    for (i = 0; i < n; ++i)
        pfi_shadow_msm16_store((double)b[i].m1, (double)b[i].m2, (double)b[i].m3, (double)b[i].m4, out + 4 * i);
    return PF_OK;
}

/* The moments of u = 1 - z from one stored texel (4 UNORM16 values, unfiltered). */
PF_CPU_DEF pf_depth_moments4 pf_shadow_decode_msm16(const unsigned short *t)
{
    const pf_real s = PF_R(1.0) / PF_R(65535.0);
    return pf_msm_dequantize_moments(pf_depth_moments4_make((pf_real)t[0] * s, (pf_real)t[1] * s,
                                                            (pf_real)t[2] * s, (pf_real)t[3] * s));
}
#endif /* PF_GLSL */

/* ---------------------------------------------------------------- CSM
   Convolution shadow maps (Annen, Mertens, Bekaert, Seidel, Kautz 2007; B&N 2012 eqs. 36-37).
   The depth test H(x), x = z - d, is replaced by its Fourier series truncated to M terms.
   Extended to period 2 as the square wave that is 1 on (0, 1) and 0 on (-1, 0) (the
   difference of two depths in [0, 1] lies in [-1, 1]), the even harmonics vanish and
       S_M(x) = 1/2 + sum_{k=1..M} (2 / c_k) sin(c_k x),   c_k = (2k - 1) pi,
   the textbook square-wave series. With sin(c (z - e)) = sin(c z) cos(c e) - cos(c z) sin(c e)
   it separates into functions of the stored depth z and of the receiver (eq. 36):
       S_M(z - e) = 1/2 + sum_k (2 / c_k) [ E[sin(c_k z)] cos(c_k e) - E[cos(c_k z)] sin(c_k e) ]
   which is linear in the per-texel basis values (cos(c_k z), sin(c_k z)), so filtering them
   filters the test (eq. 37). pf_moments.h stores them (pf_csm_pair; pf_map.h builds PF_DEPTH_CSM4/8/16 pyramids).
   Ringing: S_M overshoots by up to 9% (Gibbs) and has a ramp of slope 2M at the step, so a
   receiver at its occluder's depth reads 1/2. The evaluation therefore moves the receiver
   toward the light by `offset` (e = d - offset) and sharpens around 1/2 with `scale`:
       lit = clamp(1/2 + scale (S_M(z - d + offset) - 1/2), 0, 1)
   (Annen et al. 2007's scaling and offsetting; scale = 1, offset = 0 is the plain series).
   Domain: z - d + offset must stay in (-1, 1): beyond 1 the periodic series wraps into the
   next period and reads as shadow (a receiver within `offset` of the light plane in front of
   a far-plane texel). The filtered values are clamped to [-1, 1] (their range; NaN gives -1
   in C), so every finite input gives a finite result in [0, 1].
   Cost: one sin/cos pair of the receiver, then per harmonic a rotation by 2 pi e (4 mul,
   2 add) and a dot (2 mul, 2 add): no trigonometric call per harmonic. */
#define PF_CSM_MAX_TERMS 16
/* Defaults (docs/shadow.md, CSM section): near the step S_M(x) ~ 1/2 + 2M x, so with scale s
   the result is 1 from S_M >= 1/2 + 1/(2s) on, i.e. x >= 1/(4 s M), and 0 from x <= -1/(4 s M)
   on. Scale 4 and offset 0.07/M put a receiver at its own depth just inside the lit side
   (0.07 > 1/16) and shadow it fully 0.13/M behind its occluder (0.008 at M = 16); the pair
   was the best of a scan on the bench scenes (scale 1-8, offset 0-1/M): mean error 0.112,
   0.076, 0.059 at M = 4, 8, 16, against 0.106, 0.075, 0.055 for the best pair of each M. */
#define PF_SHADOW_CSM_TERMS_DEFAULT 16
#define PF_SHADOW_CSM_SCALE_DEFAULT PF_R(4.0)
#define PF_SHADOW_CSM_OFFSET_DEFAULT(terms) (PF_R(0.07) / PF_R(terms))
/* Bytes per texel with fp32 storage: 8 M (two values per harmonic). */
#define PF_SHADOW_BYTES_CSM(terms) (8 * (terms))

/* The running series: value = 1/2 + the harmonics added so far; (cos_k, sin_k) = the
   receiver's phase c_k e of the next harmonic, rotated by (cos_step, sin_step) = 2 pi e;
   freq = 2k - 1 of the next harmonic. */
PF_STRUCT_BEGIN(pf_csm_sum)
    pf_real value, cos_k, sin_k, cos_step, sin_step, freq;
PF_STRUCT_END(pf_csm_sum)

PF_DEF pf_csm_sum pf_csm_sum_make(pf_real value, pf_real cos_k, pf_real sin_k, pf_real cos_step,
                                  pf_real sin_step, pf_real freq)
{
    pf_csm_sum a;
    a.value = value; a.cos_k = cos_k; a.sin_k = sin_k; a.cos_step = cos_step; a.sin_step = sin_step;
    a.freq = freq;
    return a;
}
/* The empty series for receiver depth d moved toward the light by offset: value 1/2.
   e = d - offset is clamped to [-2, 3] (NaN: -2 in C) before the trigonometry, so no finite
   input makes its phase infinite; any e outside [-1, 2] is already outside the domain. */
PF_DEF pf_csm_sum pf_csm_sum_begin(pf_real d, pf_real offset)
{
    pf_real e = pf_clamp_nan_lo(d - offset, PF_R(-2.0), PF_R(3.0)), c = PF_COSPI(e), s = PF_SINPI(e);
    return pf_csm_sum_make(PF_R(0.5), c, s, (c - s) * (c + s), PF_R(2.0) * s * c, PF_R(1.0));
}
/* Adds the next harmonic from its filtered basis values E[cos(c_k z)], E[sin(c_k z)]. */
PF_DEF pf_csm_sum pf_csm_sum_add_harmonic(pf_csm_sum a, pf_real cos_z, pf_real sin_z)
{
    pf_real cz = pf_clamp_nan_lo(cos_z, PF_R(-1.0), PF_R(1.0));
    pf_real sz = pf_clamp_nan_lo(sin_z, PF_R(-1.0), PF_R(1.0));
    pf_real coef = PF_R(2.0) / (a.freq * PF_PI);
    pf_real v = a.value + coef * (sz * a.cos_k - cz * a.sin_k);
    pf_real c = a.cos_k * a.cos_step - a.sin_k * a.sin_step;
    pf_real s = a.sin_k * a.cos_step + a.cos_k * a.sin_step;
    return pf_csm_sum_make(v, c, s, a.cos_step, a.sin_step, a.freq + PF_R(2.0));
}
/* Adds the two harmonics of one stored pair (the next two, in order). */
PF_DEF pf_csm_sum pf_csm_sum_add(pf_csm_sum a, pf_csm_pair p)
{ return pf_csm_sum_add_harmonic(pf_csm_sum_add_harmonic(a, p.cos_a, p.sin_a), p.cos_b, p.sin_b); }
/* The lit fraction: clamp(1/2 + scale (value - 1/2), 0, 1) (NaN: 0 in C). */
PF_DEF pf_real pf_csm_sum_lit(pf_csm_sum a, pf_real scale)
{ return pf_clamp_nan_lo(PF_R(0.5) + scale * (a.value - PF_R(0.5)), PF_R(0.0), PF_R(1.0)); }

/* Up to PF_CSM_MAX_TERMS = 16 harmonics, 8 pairs: p0 holds harmonics 1, 2; p7 15, 16. */
PF_STRUCT_BEGIN(pf_csm_moments)
    pf_csm_pair p0, p1, p2, p3, p4, p5, p6, p7;
PF_STRUCT_END(pf_csm_moments)

/* Pair j's harmonics that are among the first `terms`. */
PF_DEF pf_csm_sum pfi_csm_add_upto(pf_csm_sum a, pf_csm_pair p, int j, int terms)
{
    if (terms > 2 * j) a = pf_csm_sum_add_harmonic(a, p.cos_a, p.sin_a);
    if (terms > 2 * j + 1) a = pf_csm_sum_add_harmonic(a, p.cos_b, p.sin_b);
    return a;
}

/* pf_shadow_csm: convolution shadow map test with the first `terms` harmonics of m (clamped
   to [1, PF_CSM_MAX_TERMS]; the pairs beyond are not read), receiver depth d, sharpening
   scale >= 1 (PF_SHADOW_CSM_SCALE_DEFAULT) and offset in depth units
   (PF_SHADOW_CSM_OFFSET_DEFAULT), see above. Lit fraction in [0, 1]. Unrolled: constant
   bounds, branches only on the uniform `terms`. */
PF_DEF pf_real pf_shadow_csm(pf_csm_moments m, pf_real d, int terms, pf_real scale, pf_real offset)
{
    pf_csm_sum a = pf_csm_sum_begin(d, offset);
    terms = terms < 1 ? 1 : terms; /* beyond 16 the pairs simply run out */
    a = pfi_csm_add_upto(a, m.p0, 0, terms);
    a = pfi_csm_add_upto(a, m.p1, 1, terms);
    a = pfi_csm_add_upto(a, m.p2, 2, terms);
    a = pfi_csm_add_upto(a, m.p3, 3, terms);
    a = pfi_csm_add_upto(a, m.p4, 4, terms);
    a = pfi_csm_add_upto(a, m.p5, 5, terms);
    a = pfi_csm_add_upto(a, m.p6, 6, terms);
    a = pfi_csm_add_upto(a, m.p7, 7, terms);
    return pf_csm_sum_lit(a, scale);
}
/* ---------------------------------------------------------------- end of CSM */

#endif /* PF_SHADOW_H */

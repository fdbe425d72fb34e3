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
   an estimate of U_A(d) from the averaged values. pf_moments.h builds and filters those
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
     pf_depth_moments4 b = ...filtered (E[z], .., E[z^4])...;
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
   All are pure, pointer-free and branch only on values: they paste into GLSL, HLSL, CUDA.

   ROBUSTNESS
     Every function returns a finite value in [0, 1] for every finite input (also under
     -ffast-math): variances made negative by rounding are clamped to the minimum variance,
     EVSM's Chebyshev test is evaluated on values scaled to at most 1 (so exp(2c) moments,
     c <= PF_EVSM_EXP_MAX_F32, cannot overflow in the arithmetic), ESM's exponent is clamped
     before exp, and MSM's Cholesky pivots, roots and weights are clamped so that a singular
     Hankel matrix (a flat occluder, a constant footprint, depths exactly 0 or 1) never
     divides by zero. All-zero moments (a footprint with no weight) are read as an occluder
     at depth 0: shadowed for d > 0.

   ACCURACY AND COST
     Measured against brute-force depth tests on synthetic depth maps (tests/test_shadow.c,
     bench/bench_shadow.c); the tables are in docs/shadow.md.

   SOURCES
     Bruneton & Neyret 2012 (survey) sec. 5, eqs. 31-38 and sec. 7.2; Donnelly & Lauritzen
     2006 (VSM, Chebyshev's one-tailed inequality); Lauritzen 2007 (GPU Gems 3 ch. 8, light
     bleeding reduction); Annen, Mertens, Seidel, Flerackers, Kautz 2008 and Salvi 2008 (ESM);
     Lauritzen & McCool 2008 (EVSM, layered VSM); Peters & Klein 2015, "Moment Shadow
     Mapping", I3D (Hamburger 4MSM, Algorithm 2, with the author's erratum: the last case
     returns 1 - w1). */
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

/* Bytes per texel each method stores with fp32 channels (fp16 halves them where the method
   tolerates it: VSM yes, EVSM only with exponents <= PF_EVSM_EXP_MAX_F16, MSM only with
   Peters & Klein's optimized quantization, which pf_moments.h does not do). */
#define PF_SHADOW_BYTES_VSM 8
#define PF_SHADOW_BYTES_ESM 4
#define PF_SHADOW_BYTES_EVSM2 8
#define PF_SHADOW_BYTES_EVSM4 16
#define PF_SHADOW_BYTES_MSM 16

/* ---------------------------------------------------------------- Chebyshev */
/* var / (var + t^2) for t > 0, else 1; var is clamped at 0 and the denominator at 1e-30, so
   the quotient is in [0, 1] and never 0/0 (also under -ffast-math). */
PF_DEF pf_real pfi_shadow_chebyshev_ratio(pf_real var, pf_real t)
{
    pf_real v = pf_max(var, PF_R(0.0));
    pf_real q = v / pf_max(v + t * t, PF_R(1.0e-30));
    return t > PF_R(0.0) ? pf_min(q, PF_R(1.0)) : PF_R(1.0);
}

/* pf_shadow_chebyshev_upper: upper bound on P(X >= x) for a random X with mean m1 and second
   moment m2 (Cantelli's one-tailed form of Chebyshev's inequality, Donnelly & Lauritzen 2006;
   B&N 2012 after eq. 35):
       P(X >= x) <= s2 / (s2 + (x - m1)^2)   if x > m1,   else 1,
   with s2 = max(m2 - m1^2, min_variance). The bound is attained by the two-point
   distribution with atoms x and m1 - s2/(x - m1), i.e. it is exact for a planar occluder in
   front of a planar receiver. Any scale: the values are divided by max(|m1|, |x|) first, so
   m2 ~ 1e38 (EVSM at c = 44 in float) neither overflows nor loses the bound; min_variance
   is in the units of X. Returns a value in [0, 1]; NaN moments give 1. */
PF_DEF pf_real pf_shadow_chebyshev_upper(pf_real m1, pf_real m2, pf_real x, pf_real min_variance)
{
    pf_real s = pf_max(pf_max(PF_FABS(m1), PF_FABS(x)), PF_R(1.0e-30));
    pf_real inv = PF_R(1.0) / s;
    pf_real mu = m1 * inv;
    pf_real var = pf_max((m2 * inv) * inv - mu * mu, (min_variance * inv) * inv);
    return pfi_shadow_chebyshev_ratio(var, x * inv - mu);
}

/* pf_shadow_reduce_bleeding: maps lit fractions below `threshold` to 0 and rescales the rest
   to [0, 1] (Lauritzen 2007): removes the light that Chebyshev lets through behind
   overlapping occluders, at the price of darker (no longer bounding) penumbrae. threshold in
   [0, 1); 0 returns lit unchanged (clamped to [0, 1]). */
PF_DEF pf_real pf_shadow_reduce_bleeding(pf_real lit, pf_real threshold)
{
    pf_real th = pf_clamp(threshold, PF_R(0.0), PF_R(0.999));
    return pf_saturate((lit - th) / (PF_R(1.0) - th));
}

/* ---------------------------------------------------------------- VSM */
/* pf_shadow_vsm: variance shadow map test (Donnelly & Lauritzen 2006; B&N 2012 eq. 35 with
   the Chebyshev bound). m = filtered (E[z], E[z^2]); d receiver depth; min_variance >= 0 (in
   depth^2, default PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT); bleed = light-bleeding threshold
   (default PF_SHADOW_BLEED_DEFAULT = 0, off). Lit fraction in [0, 1]: an upper bound on the
   true one when bleed = 0, exact for two depths with the receiver at the farther one. */
PF_DEF pf_real pf_shadow_vsm(pf_depth_moments2 m, pf_real d, pf_real min_variance, pf_real bleed)
{
    /* depths are <= 1: no scaling needed */
    pf_real var = pf_max(m.m2 - m.m1 * m.m1, min_variance);
    return pf_shadow_reduce_bleeding(pfi_shadow_chebyshev_ratio(var, d - m.m1), bleed);
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
   where the minimum variance matters (d ~ E[z]), both choices agree. */
PF_DEF pf_real pfi_shadow_evsm_warped(pf_real m1, pf_real m2, pf_real w, pf_real c, pf_real min_variance)
{
    pf_real k = PF_R(2.0) * c;
    pf_real s = pf_max(pf_max(PF_FABS(m1), PF_FABS(w)), PF_R(1.0e-30));
    pf_real inv = PF_R(1.0) / s;
    pf_real mu = m1 * inv;
    pf_real x = w * inv;
    /* everything scaled by 1/s; the derivative is taken at the warped value nearer to 0 */
    pf_real slope = k * pf_min(PF_FABS(x), PF_FABS(mu));
    pf_real var = pf_max((m2 * inv) * inv - mu * mu, min_variance * slope * slope);
    return pfi_shadow_chebyshev_ratio(var, x - mu);
}

/* pf_shadow_evsm2: EVSM with the positive warp only (Lauritzen & McCool 2008): m = filtered
   (E[p], E[p^2]), p = exp(c_pos (2z - 1)) (pf_evsm2_from_depth). c_pos > 0, at most
   PF_EVSM_EXP_MAX_F32 (44) for fp32 storage, PF_EVSM_EXP_MAX_F16 (5.54) for fp16;
   min_variance in depth^2 (PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT); bleed as for VSM. */
PF_DEF pf_real pf_shadow_evsm2(pf_depth_moments2 m, pf_real d, pf_real c_pos, pf_real min_variance,
                               pf_real bleed)
{
    pf_real w = PF_EXP(c_pos * (PF_R(2.0) * d - PF_R(1.0)));
    return pf_shadow_reduce_bleeding(pfi_shadow_evsm_warped(m.m1, m.m2, w, c_pos, min_variance), bleed);
}

/* pf_shadow_evsm4: EVSM with both warps (Lauritzen & McCool 2008): Chebyshev on the positive
   warp p = exp(c_pos zs) and on the negative warp n = -exp(-c_neg zs), zs = 2z - 1, and the
   smaller of the two upper bounds (both bound the same lit fraction). m from
   pf_evsm_moments_from_depth; exponents and min_variance as for pf_shadow_evsm2. */
PF_DEF pf_real pf_shadow_evsm4(pf_evsm_moments m, pf_real d, pf_real c_pos, pf_real c_neg,
                               pf_real min_variance, pf_real bleed)
{
    pf_real zs = PF_R(2.0) * d - PF_R(1.0);
    pf_real lit_pos = pfi_shadow_evsm_warped(m.pos1, m.pos2, PF_EXP(c_pos * zs), c_pos, min_variance);
    pf_real lit_neg = pfi_shadow_evsm_warped(m.neg1, m.neg2, -PF_EXP(-c_neg * zs), c_neg, min_variance);
    return pf_shadow_reduce_bleeding(pf_min(lit_pos, lit_neg), bleed);
}

/* ---------------------------------------------------------------- MSM
   Hamburger 4MSM (Peters & Klein 2015, sec. 4 and Algorithm 2). Given the biased moments
   b = (1 - a) m + a (1/2, 1/2, 1/2, 1/2) (the bias vector is the moment vector of a fair coin
   on {0, 1}, so b stays a valid moment vector while the Hankel matrix gains rank) and the
   receiver depth zf = d - depth_bias, the distribution with the fewest atoms that has
   moments b and an atom at zf has two more atoms z2 <= z3: the roots of
   c1 + c2 z + c3 z^2, where B c = (1, zf, zf^2) and B = [[1, b1, b2], [b1, b2, b3],
   [b2, b3, b4]] is the Hankel matrix. With w1, w2 the weights at zf and z2 (Lagrange
   interpolation on the atoms, matched to b1, b2), every distribution with moments b has
       P(z > zf) >= lower   and   P(z >= zf) <= upper,
       zf <= z2:        upper = 1,       lower = 1 - w1
       z2 < zf <= z3:   upper = 1 - w2,  lower = 1 - w1 - w2
       zf > z3:         upper = w1,      lower = 0
   and both are attained (sharp). MSM returns the upper one as the lit fraction (Peters &
   Klein's "lower bound of the shadow intensity"; erratum: the last case is 1 - w1 in their
   shadow terms, i.e. w1 lit).

   Numerics. B = L D L^T with unit lower L = [[1,0,0],[b1,1,0],[b2,l32,1]] and
   D = diag(1, d22, d33): d22 = b2 - b1^2 is the variance, d33 the part of b4 that b1..b3 do
   not explain. A point mass gives d22 = 0 and a two-point footprint (a flat occluder over a
   flat receiver, or depths exactly 0 and 1 with the bias) gives d33 = 0, and rounding may
   make either negative; both pivots are floored, which amounts to raising b2 or b4 by the
   difference - still a valid moment vector, so the reconstruction stays a distribution.
   Roots are found with the cancellation-free quadratic formula and clamped to +-1e4 (a
   larger root carries weight < 1e-4 of the far tail, below the bias), and every division
   is clamped, so no input yields inf or NaN. */
#define PFI_MSM_D22_FLOOR PF_R(1.0e-9)
#define PFI_MSM_D33_FLOOR PF_R(1.0e-12)
#define PFI_MSM_ROOT_MAX PF_R(1.0e4)

/* n / d clamped to [-lim, lim], without forming an overflowing or undefined quotient
   (0/0 gives lim). lim > 0. */
PF_DEF pf_real pfi_shadow_div_clamped(pf_real n, pf_real d, pf_real lim)
{
    pf_real an = PF_FABS(n);
    pf_real ad = PF_FABS(d);
    pf_real sgn = (n < PF_R(0.0)) != (d < PF_R(0.0)) ? PF_R(-1.0) : PF_R(1.0);
    if (!(an < lim * ad)) return sgn * lim;
    return n / d;
}

/* Lit-fraction bounds (lower, upper) of the Hamburger 4MSM reconstruction; see above. */
PF_DEF pf_vec2 pf_shadow_msm_bounds(pf_depth_moments4 m, pf_real d, pf_real moment_bias, pf_real depth_bias)
{
    pf_real a = pf_clamp(moment_bias, PF_R(0.0), PF_R(1.0));
    pf_real ha = PF_R(0.5) * a;
    pf_real b1 = m.m1 - a * m.m1 + ha;
    pf_real b2 = m.m2 - a * m.m2 + ha;
    pf_real b3 = m.m3 - a * m.m3 + ha;
    pf_real b4 = m.m4 - a * m.m4 + ha;
    pf_real zf = d - depth_bias;
    /* L D L^T of the Hankel matrix */
    pf_real d22 = pf_max(b2 - b1 * b1, PFI_MSM_D22_FLOOR);
    pf_real e32 = b3 - b1 * b2; /* l32 d22 */
    pf_real l32 = e32 / d22;
    pf_real d33 = pf_max(b4 - b2 * b2 - l32 * e32, PFI_MSM_D33_FLOOR);
    /* B c = (1, zf, zf^2): forward (L), diagonal (D), backward (L^T) */
    pf_real y2 = zf - b1;
    pf_real y3 = zf * zf - b2 - l32 * y2;
    pf_real c3 = y3 / d33;
    pf_real c2 = y2 / d22 - l32 * c3;
    pf_real c1 = PF_R(1.0) - b1 * c2 - b2 * c3;
    /* roots of c3 z^2 + c2 z + c1: q = -(c2 + sign(c2) sqrt(disc))/2, roots q/c3 and c1/q */
    pf_real disc = pf_max(c2 * c2 - PF_R(4.0) * c1 * c3, PF_R(0.0));
    pf_real q = PF_R(-0.5) * (c2 + (c2 < PF_R(0.0) ? -PF_SQRT(disc) : PF_SQRT(disc)));
    pf_real r1 = pfi_shadow_div_clamped(q, c3, PFI_MSM_ROOT_MAX);
    pf_real r2 = pfi_shadow_div_clamped(c1, q, PFI_MSM_ROOT_MAX);
    pf_real z2 = pf_min(r1, r2);
    pf_real z3 = pf_max(r1, r2);
    /* weights at zf and z2 from the first two moments (Lagrange on the three atoms) */
    pf_real w1 = pfi_shadow_div_clamped(z2 * z3 - b1 * (z2 + z3) + b2, (zf - z2) * (zf - z3), PF_R(2.0));
    pf_real w2 = pfi_shadow_div_clamped(zf * z3 - b1 * (zf + z3) + b2, (z2 - zf) * (z2 - z3), PF_R(2.0));
    pf_real upper, lower;
    w1 = pf_saturate(w1);
    w2 = pf_saturate(w2);
    if (zf <= z2) {
        upper = PF_R(1.0);
    } else if (zf <= z3) {
        upper = PF_R(1.0) - w2;
    } else {
        upper = w1;
    }
    lower = pf_saturate(upper - w1);
    return pf_vec2_make(lower, pf_saturate(upper));
}

/* pf_shadow_msm: moment shadow map test (Peters & Klein 2015, Hamburger 4MSM): the sharp upper
   bound of the lit fraction given the four biased moments (see pf_shadow_msm_bounds).
   m = filtered (E[z], E[z^2], E[z^3], E[z^4]) (pf_depth_moments4_from_depth); moment_bias in
   [0, 1] (PF_SHADOW_MSM_MOMENT_BIAS_DEFAULT = 3e-5 for fp32 moments); depth_bias subtracted
   from d (PF_SHADOW_MSM_DEPTH_BIAS_DEFAULT = 0). */
PF_DEF pf_real pf_shadow_msm(pf_depth_moments4 m, pf_real d, pf_real moment_bias, pf_real depth_bias)
{
    return pf_shadow_msm_bounds(m, d, moment_bias, depth_bias).y;
}

#endif /* PF_SHADOW_H */

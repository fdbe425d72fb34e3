/* pf_moments.h - linear moments for pre-filtering: slope moments (LEAN/LEADR), scalar-map
   moments, depth moments for shadow maps, and their mip reductions and sampling.

   (doc block: to be completed with the reductions and pyramid functions)

   SOURCES
     Dupuy et al. 2013 (LEADR) sec. 4.1-4.2; Bruneton & Neyret 2012 sec. 3.2.1, 5.2 and 7.2;
     Heitz et al. 2014 sec. 4.2; Donnelly & Lauritzen 2006 (VSM); Salvi 2008 / Annen et al.
     2008 (ESM); Lauritzen & McCool 2008 (EVSM); Peters & Klein 2015 (moment shadow maps). */
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
{
    pf_depth_moments2 m;
    m.m1 = m1;
    m.m2 = m2;
    return m;
}

PF_DEF pf_depth_moments4 pf_depth_moments4_make(pf_real m1, pf_real m2, pf_real m3, pf_real m4)
{
    pf_depth_moments4 m;
    m.m1 = m1;
    m.m2 = m2;
    m.m3 = m3;
    m.m4 = m4;
    return m;
}

PF_DEF pf_evsm_moments pf_evsm_moments_make(pf_real pos1, pf_real pos2, pf_real neg1, pf_real neg2)
{
    pf_evsm_moments m;
    m.pos1 = pos1;
    m.pos2 = pos2;
    m.neg1 = neg1;
    m.neg2 = neg2;
    return m;
}

/* VSM texel: (z, z^2). */
PF_DEF pf_depth_moments2 pf_depth_moments2_from_depth(pf_real z)
{
    return pf_depth_moments2_make(z, z * z);
}

/* MSM texel: (z, z^2, z^3, z^4). */
PF_DEF pf_depth_moments4 pf_depth_moments4_from_depth(pf_real z)
{
    pf_real z2 = z * z;
    return pf_depth_moments4_make(z, z2, z2 * z, z2 * z2);
}

/* EVSM warps of a depth z in [0, 1]: exp(c (2z - 1)) and -exp(-c (2z - 1)). The caller keeps
   c <= PF_EVSM_EXP_MAX_F32 (or _F16 for 16-bit storage) so the squares stay finite. */
PF_DEF pf_real pf_evsm_warp_pos(pf_real z, pf_real c)
{
    return PF_EXP(c * (PF_R(2.0) * z - PF_R(1.0)));
}

PF_DEF pf_real pf_evsm_warp_neg(pf_real z, pf_real c)
{
    return -PF_EXP(-c * (PF_R(2.0) * z - PF_R(1.0)));
}

/* EVSM-2 texel: moments of the positive warp only. */
PF_DEF pf_depth_moments2 pf_evsm2_from_depth(pf_real z, pf_real c_pos)
{
    pf_real p = pf_evsm_warp_pos(z, c_pos);
    return pf_depth_moments2_make(p, p * p);
}

/* EVSM-4 texel: moments of both warps. */
PF_DEF pf_evsm_moments pf_evsm_moments_from_depth(pf_real z, pf_real c_pos, pf_real c_neg)
{
    pf_real p = pf_evsm_warp_pos(z, c_pos);
    pf_real n = pf_evsm_warp_neg(z, c_neg);
    return pf_evsm_moments_make(p, p * p, n, n * n);
}

/* ESM texel in log space: log(exp(c z)) = c z. A pyramid of these is reduced with
   log-sum-exp (below), so E[exp(c z)] is never formed and cannot overflow for any c. */
PF_DEF pf_real pf_esm_log_from_depth(pf_real z, pf_real c)
{
    return c * z;
}

/* log(w0 exp(l0) + w1 exp(l1)) for weights w >= 0 with w0 + w1 > 0, without overflow:
   m + log(w0 exp(l0 - m) + w1 exp(l1 - m)), m = max(l0, l1). */
PF_DEF pf_real pf_esm_log_combine2(pf_real l0, pf_real w0, pf_real l1, pf_real w1)
{
    pf_real m = pf_max(l0, l1);
    return m + PF_LOG(w0 * PF_EXP(l0 - m) + w1 * PF_EXP(l1 - m));
}

#endif /* PF_MOMENTS_H */

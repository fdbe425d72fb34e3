/* pf_hist_oracle.h - the exact-histogram oracle of a footprint, shared by the bench programs
   (bench/microsurface.c per square footprint, bench/frame/frame.c per pixel footprint). Bench
   code, not part of the library.

   The oracle is the best any filtered representation of a footprint can do with Smith's
   visibility: the footprint's texels shaded each with its own micro-normal and the narrow base
   lobe with every texel visible (the brute force of tests/reference/pf_microsurface.h without
   its visibility marches: the footprint's exact slope histogram), times Smith's joint
   masking-shadowing 1/(1 + Lambda_o + Lambda_i) of the footprint's own slope moments without
   the base lobe (Dupuy et al. 2013 eq. 13; pf_beckmann_masking_shadowing). Its error against
   the full brute force is the visibility model's alone; a method's error divided by it says how
   far the method is from what is reachable.

   Needs pf_beckmann.h and pf_microsurface.h (-Itests/reference; its PFM_FN marks these
   functions unused-tolerant) included before. */
#ifndef PF_HIST_ORACLE_H
#define PF_HIST_ORACLE_H

/* the oracle from its two parts: novis = the footprint's specular radiance with every texel
   visible (pfm_reference_shade without visibility maps), s0 = the footprint's slope statistics
   without the base lobe */
PFM_FN double pfb_oracle_smith(double novis, pf_vec3 wo, pf_vec3 wi, pf_slope_stats s0)
{
    return novis * (double)pf_beckmann_masking_shadowing(wo, wi, s0);
}

/* A footprint's histogram accumulated texel by texel, each with a weight (1 for a box, the
   covered fraction for a pixel's parallelogram): the weighted sums of the projected area
   a_t = wo.z - s.(wo.x, wo.y), of the visibility-free specular term a_t f_t (= pfm_base_specular,
   pfm_reference_shade's per-texel sum) and of the slope moments (x, y, x^2, y^2, xy). */
typedef struct {
    double w, area, spec, m[5];
} pfb_hist;

/* one texel of slope (sx, sy): spec_term = its specular term when the caller has it (the
   reference's own, without visibility), or a negative value to evaluate it here */
PFM_FN void pfb_hist_add(pfb_hist *h, double weight, double sx, double sy, double spec_term, const double wo[3],
                         const double wi[3], double base_sigma, double f0)
{
    double at = wo[2] - sx * wo[0] - sy * wo[1];
    h->w += weight;
    h->area += weight * at;
    h->m[0] += weight * sx;
    h->m[1] += weight * sy;
    h->m[2] += weight * sx * sx;
    h->m[3] += weight * sy * sy;
    h->m[4] += weight * sx * sy;
    if (!(at > 0.0)) return;
    h->spec += weight * (spec_term >= 0.0 ? spec_term : pfm_base_specular(wo, wi, sx, sy, base_sigma, f0));
}

/* the footprint's own slope statistics plus base_var (0: the oracle's Smith term) */
PFM_FN pf_slope_stats pfb_hist_stats(const pfb_hist *h, double base_var)
{
    double iw = h->w > 0.0 ? 1.0 / h->w : 0.0;
    return pf_slope_moments_stats(pf_slope_moments_make((pf_real)(h->m[0] * iw), (pf_real)(h->m[1] * iw), (pf_real)(h->m[2] * iw),
                                                        (pf_real)(h->m[3] * iw), (pf_real)(h->m[4] * iw)),
                                  (pf_real)base_var);
}

/* the oracle of the accumulated footprint (0 when its projected area is not positive) */
PFM_FN double pfb_hist_oracle(const pfb_hist *h, const double wo[3], const double wi[3])
{
    pf_vec3 o = pf_vec3_make((pf_real)wo[0], (pf_real)wo[1], (pf_real)wo[2]);
    pf_vec3 i = pf_vec3_make((pf_real)wi[0], (pf_real)wi[1], (pf_real)wi[2]);
    if (!(h->area > 0.0)) return 0.0;
    return pfb_oracle_smith(h->spec / h->area, o, i, pfb_hist_stats(h, 0.0));
}

#endif /* PF_HIST_ORACLE_H */

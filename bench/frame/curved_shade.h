/* curved_shade.h - one pixel of bench/specaa_scenes.h's curved scenes shaded by the specular AA
   forms of pf_specaa.h, written once in the subset C99 and GLSL share: bench/frame/curved.frag
   (the GPU, hardware dFdx/dFdy) and bench/frame/frame_curved.h (the CPU float path, the same
   quad differences computed analytically) call the same function, so the GPU-vs-CPU column
   measures the driver (texture filtering, lod, derivatives, arithmetic), not two transcriptions.
   The forms are bench/specaa_scenes.h's rows of the same names (sc_run), with the quad's
   derivatives instead of its exact ones. Bench code, not part of the library.
     m   FC_NONE .. FC_VMF_BOX below
     wo, wi   view and light in the pixel's tangent frame (T, B, N)
     mm  the map's filtered 5 slope moments (zero without a map); nav: its averaged unit normal
     bv  base per-axis slope variance alpha^2 / 2
     dnx, dny  screen derivatives of the macro-normal (world); ax, ay: the same in (T, B, N)
     jx, jy    screen derivatives of the surface position (pixels) in (T, B, N), for (5)
     dmx, dmy  screen derivatives of the fetched mean slope (mm's ex, ey), for the cross term (4) */
#ifndef FC_CURVED_SHADE_H
#define FC_CURVED_SHADE_H

#define FC_NONE     0 /* LEADR, no kernel */
#define FC_BOX      1 /* LEADR + box kernel, anisotropic (pf_specaa_kernel_aniso, sigma2 1/24) */
#define FC_BOX_ISO  2 /* pf_specaa_leadr_specular: the isotropic box kernel, one call */
#define FC_TK       3 /* LEADR + Tokuyoshi & Kaplanyan 2019 (1/(2 pi), 0.18) */
#define FC_FILAMENT 4 /* LEADR + Filament's constants (0.15, 0.2^2) */
#define FC_HDRP     5 /* LEADR + HDRP's (0.1, 0.2^2) */
#define FC_GODOT    6 /* LEADR + Godot's limiter (0.25, 0.18 on alpha) */
#define FC_VMF_BOX  7 /* one vMF lobe from the averaged normal + box kernel (pf_specaa_vmf_kappa) */
#define FC_CURVED   8 /* pf_specaa_leadr_specular_curved: box kernel (aniso) + the mean shift (6) */
#define FC_SURF     9 /* box kernel (aniso) + the mean shift (5) from the position derivatives */
#define FC_CROSS   10 /* box kernel (aniso) + the cross term (4) from dFdx/dFdy of the read's mean + (6) */
#define FC_QUAD    11 /* four quadrant reads (fc_shade_quad): pf_specaa_slope_stats_quad + (6) */
#define FC_COUNT   12

PF_DEF pf_real fc_shade(int m, pf_vec3 wo, pf_vec3 wi, pf_slope_moments mm, pf_vec3 nav, pf_real bv, pf_vec3 dnx, pf_vec3 dny,
                        pf_vec3 ax, pf_vec3 ay, pf_vec3 jx, pf_vec3 jy, pf_vec2 dmx, pf_vec2 dmy)
{
    pf_slope_stats s0 = pf_slope_moments_stats(mm, bv), st = s0;
    if (!(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0))) return PF_R(0.0);
    if (m == FC_BOX) st = pf_specaa_slope_stats_aniso(s0, pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA));
    if (m == FC_BOX_ISO) return pf_specaa_leadr_specular(wo, wi, s0, PF_R(1.0), dnx, dny);
    if (m == FC_CURVED) return pf_specaa_leadr_specular_curved(wo, wi, s0, PF_R(1.0), ax, ay);
    if (m == FC_SURF)
        st = pf_specaa_slope_stats_shift(pf_specaa_slope_stats_aniso(s0, pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA)),
                                         pf_specaa_mean_shift_surface(jx, jy, ax, ay, wo, PF_SPECAA_SIGMA2_BOX));
    if (m == FC_CROSS) {
        /* (4) reads the turn's tangent-plane part only (x, y), as bench/specaa_scenes.h's ax0, ay0 */
        pf_specaa_kernel k = pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA);
        st = pf_specaa_slope_stats_shift(pf_specaa_slope_stats_cross(s0, k, pf_specaa_kernel_cross(ax, ay, dmx, dmy, PF_SPECAA_SIGMA2_BOX)),
                                         pf_specaa_mean_shift(wo, pf_specaa_kernel_trace(k)));
    }
    if (m == FC_TK) st = pf_specaa_slope_stats(s0, pf_specaa_kernel_normal(dnx, dny, PF_SPECAA_SIGMA2, PF_SPECAA_KAPPA));
    if (m == FC_FILAMENT) st = pf_specaa_slope_stats(s0, pf_specaa_kernel_normal(dnx, dny, PF_R(0.15), PF_R(0.04)));
    if (m == FC_HDRP) st = pf_specaa_slope_stats(s0, pf_specaa_kernel_normal(dnx, dny, PF_R(0.1), PF_R(0.04)));
    if (m == FC_GODOT) {
        /* perceptual roughness^2 (= alpha) += min(2 x 0.25 |dn|^2, 0.18) on LEADR's isotropic
           equivalent alpha^2 = var_x + var_y, the alpha^2 increment spread on both axes */
        pf_real ae = PF_SQRT(s0.var_x + s0.var_y), an = ae + pf_specaa_kernel_normal(dnx, dny, PF_R(0.25), PF_R(0.18));
        an = an < PF_R(1.0) ? an : PF_R(1.0);
        an = an * an - ae * ae;
        st = pf_specaa_slope_stats(s0, an > PF_R(0.0) ? an : PF_R(0.0));
    }
    if (m == FC_VMF_BOX) {
        /* one lobe from the mip's averaged unit normal (Banerjee et al. 2005), widened by the kernel */
        pf_real r = PF_SQRT(pf_vec3_dot(nav, nav));
        pf_vec3 mu = r > PF_R(0.0) ? pf_vec3_scale(nav, PF_R(1.0) / r) : pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
        pf_real kb = pf_specaa_kernel_normal(dnx, dny, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA);
        st = pf_vmf_lobe_slope_stats(mu, pf_specaa_vmf_kappa(pf_vmf_kappa_from_mean_length(r), kb), bv);
    }
    return pf_leadr_specular(wo, wi, st, PF_R(1.0));
}

/* FC_QUAD: the pixel's statistics from four reads of the pyramid, one per quadrant of the pixel
   (m00: -x -y, m10: +x -y, m01: -x +y, m11: +x +y, pf_specaa_slope_stats_quad: their mean, the
   gradient from their differences, the kernel and the cross term (4)), and the mean shift (6)
   of the kernel's trace (bench/specaa_scenes.h's "4 quadrant aniso fetches ... + mean shift") */
PF_DEF pf_real fc_shade_quad(pf_vec3 wo, pf_vec3 wi, pf_slope_moments m00, pf_slope_moments m10, pf_slope_moments m01,
                             pf_slope_moments m11, pf_real bv, pf_vec3 ax, pf_vec3 ay)
{
    pf_slope_stats st = pf_specaa_slope_stats_quad(m00, m10, m01, m11, bv, ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA);
    pf_real k = pf_specaa_kernel_trace(pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA));
    if (!(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0))) return PF_R(0.0);
    return pf_leadr_specular(wo, wi, pf_specaa_slope_stats_shift(st, pf_specaa_mean_shift(wo, k)), PF_R(1.0));
}
#endif

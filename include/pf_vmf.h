/* pf_vmf.h - footprint NDFs as mixtures of von Mises-Fisher lobes (Wu et al. 2019), their
   specular BRDF with a narrow base lobe, and Smith masking-shadowing of the mixture.

   One Gaussian of slopes (LEADR) cannot describe a footprint whose slopes cluster on a few
   values (tiles, craters on flat ground, ridges): the bench's in-footprint reference puts the
   one-lobe error at 0.3-0.8 there. This module describes the footprint's micro-normals as
   m <= 16 vMF lobes (Wu et al. 2019 eq. 4, after Han et al. 2007), fitted on the CPU by
   spherical EM, stored per texel of a pyramid, and shaded with the multi-lobe BRDF of
   Wu et al. 2019 eq. 5 in the projected-area form of LEADR (Dupuy et al. 2013 eqs. 2-3, 17).

   DEFINITIONS
     lobe        g(w; kappa, mu) = C(kappa) exp(kappa (mu.w - 1)),   unit w, mu, kappa > 0,
                 C(kappa) = kappa / (2 pi (1 - exp(-2 kappa))),  integral over the sphere = 1.
                 This is Wu et al.'s kappa / (4 pi sinh kappa) exp(kappa mu.w) with exp(kappa)
                 taken out, so nothing overflows at large kappa; the exponent is evaluated as
                 -kappa |w - mu|^2 / 2 (equal for unit vectors, no cancellation near mu).
     mixture     p(w) = sum_k a_k g(w; kappa_k, mu_k), sum_k a_k = 1 (the fit's amplitudes):
                 the distribution of the footprint's micro-normals PER UNIT MACROSURFACE AREA
                 (every texel counts once). CONVENTION: the NDF is D(w) = p(w) / w.z, so that
                 integral D(w) (w.z) dw = 1 (Wu et al. eq. 3; LEADR eq. 10's normalization).
                 Wu et al. eq. 4 fits D itself (normals weighted by 1/cos); both agree for
                 point masses, ours keeps eq. 3 exact and its fit has unit weights.
     convolution with a base lobe (the micro-BRDF's own NDF, rotated to each micro-normal,
                 Wu et al. eq. 5): a vMF lobe convolved with a vMF base lobe of kappa_b is
                 approximated by ONE vMF lobe of
                     kappa' = kappa kappa_b / (kappa + kappa_b)          (1/kappa' = 1/k + 1/k_b)
                 (exact for the small-angle Gaussian limit: angular variances add). A Beckmann
                 base lobe of slope deviation sigma per axis is read as kappa_b = 1/sigma^2
                 (the same curvature at its peak). Measured error: see ACCURACY.
     specular    (Wu et al. eq. 5 with a microfacet base BRDF, in LEADR eq. 17's form)
                     I = F(h.wi) D'(h) G / (4 A_o),    h = (wo + wi)/|wo + wi|,
                     D'(h) = sum_k a_k g(h; kappa'_k, mu_k) / h.z,
                     A_o  = sum_k a_k (wo.z - wo.xy . s_k),  s_k = -mu_k.xy / mu_k.z,
                 the radiance toward wo per unit radiance from wi, light cosine included (as
                 pf_leadr_specular).
     masking     Smith's Lambda is linear in the slope density (pf_smith.h eq. 1 times the
                 projected area), so the Lambda of a mixture of Gaussian-slope lobes is exact:
                     Lambda(w) = sum_k a_k E_k(w) / A(w),   A(w) = sum_k a_k (w.z - w.xy . s_k),
                     E_k(w) = sigma_k(w) sqrt(2) e(nu_k),   nu_k = (w.z - w.xy . s_k)/(sqrt(2) sigma_k(w)),
                     e(nu) = exp(-nu^2)/(2 sqrt(pi)) - nu erfc(nu)/2      (= nu Lambda_Beckmann(nu)),
                 sigma_k(w)^2 = w.xy^T Sigma_k w.xy the lobe's slope variance along w (times
                 |w.xy|^2). A lobe's slopes are taken Gaussian with mean s_k and covariance
                     Sigma_k = v_k (t t^T / mu.z^4 + (I - t t^T) / mu.z^2) + base_var I,
                 v_k = A3(kappa_k)/kappa_k the per-axis variance of the tangent-plane projection
                 of a vMF (A3 = coth kappa - 1/kappa), t the unit azimuth of mu_k (the slope
                 map's Jacobian at mu_k). G = 1/(1 + Lambda(wo) + Lambda(wi)) (LEADR eq. 13).

   USAGE (a shader; the CPU the same)
     pf_vmf_pixel px = pf_vmf_pixel_make(wo, wi, sigma_b * sigma_b);   -- once per pixel
     pf_vmf_sum s = pf_vmf_sum_zero();
     for (k = 0; k < 4; ++k) {                      -- m = 4 RGBA fetches of the lobe pyramid
         vec4 t = texel k;                           -- (mu.x, mu.y, kappa, amp)
         s = pf_vmf_sum_add_texel(s, px, t.w, t.x, t.y, t.z);
     }
     pf_real I = pf_vmf_sum_specular(s, wo, wi, f0);
     (pf_vmf_sum_add_texel_mixture and pf_vmf_sum_specular_mixture for the mixture's exact
     Smith term.) pf_vmf_sum_add(s, pf_vmf_lobe_make(t.w, t.x, t.y, t.z), wo, wi, sigma_b^2)
     adds the same sums with the exact tangent variance (the texel path's rational is 1.9e-3
     off) and repairs a texel outside the fit's contract (NaN, an axis past the horizon, a
     negative amplitude), at 2.7x the SPIR-V ops per lobe (119 against 44).
     The lobes are fitted on the CPU by pf_vmf_fit.h (pf_vmf_fit_normals, the lobe pyramid
     pf_vmf_pyramid_from_normals) and pf_vmf_scale.h (the scaling function).

   FUNCTIONS
     lobes       pf_vmf_normalization, pf_vmf_mean_cosine, pf_vmf_tangent_variance,
                 pf_vmf_kappa_from_tangent_variance, pf_vmf_lobe_eval,
                 pf_vmf_kappa_from_mean_length, pf_vmf_convolve_kappa, pf_vmf_kappa_from_sigma,
                 pf_vmf_lobe_slope_stats
     one lobe of a mixture
                 pf_vmf_lobe_make, pf_vmf_lobe_density, pf_vmf_lobe_ndf (vMF form),
                 pf_vmf_lobe_ndf_slope (slope form), pf_vmf_lobe_area, pf_vmf_lobe_excess,
                 pf_vmf_lambda
     shader path pf_vmf_pixel_make, pf_vmf_sum_add_texel, pf_vmf_sum_add_texel_mixture
     BRDF        pf_vmf_sum_zero, pf_vmf_sum_add (slope form), pf_vmf_sum_add_vmf (vMF form),
                 pf_vmf_sum_add_masking, pf_vmf_sum_stats, pf_vmf_sum_g2 (one Gaussian),
                 pf_vmf_sum_g2_mixture, pf_vmf_sum_g1_mixture (exact mixture Smith),
                 pf_vmf_sum_specular, pf_vmf_sum_specular_mixture, pf_vmf_sum_specular_unmasked,
                 pf_vmf_sum_without_base, pf_vmf_sum_specular_base (grazing: the base lobe's
                 own masking kept apart)
     scaling     pf_vmf_scale_coords, pf_vmf_scale_texel_pos, pf_vmf_scale_trilinear,
                 pf_vmf_scale_apply (T S f of Wu et al. 2019 eqs. 13-14, shader side)
     facet       pf_vmf_facet_specular (one facet's base BRDF: the effective BRDF's term)
     CPU baking  pf_vmf_fit.h (EM fit, lobe pyramid), pf_vmf_scale.h (scaling-function fit);
                 pf_map_downsample.h (slope-preserving downsampling of the height map)

   CONVENTIONS
     Tangent frame of the macrosurface, +z up; directions and lobe axes unit vectors (lobe axes
     on the upper hemisphere: a height field has no normal facing down; the packed form stores
     mu.x, mu.y and rebuilds mu.z = sqrt(1 - x^2 - y^2)). kappa is clamped to
     [PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX]; a NaN kappa reads as PF_VMF_KAPPA_MIN. A mixture is
     shaded lobe by lobe (pf_vmf_sum_add): no arrays in structs, so the same source is GLSL;
     the fit returns at most PF_VMF_MAX_LOBES = 16 lobes. Evaluators return finite values >= 0
     for finite inputs; 0 when a direction is on or below the macrosurface (a view or a light
     below the mixture's mesosurface sees or lights the facets facing it, as in
     pf_leadr_specular); G in [0, 1].

   ACCURACY AND COST (tests/test_vmf.c, bench/bench_vmf.c, bench/microsurface.c; docs/vmf.md)
     C(kappa) within 2 eps of quadrature (kappa 1e-4 .. 1e5, float and double); A3 and the
     tangent variance within 6 (float) / 35 (double) eps. One-lobe convolution rule: within
     3.1e-3 of the exact convolution's peak (kappa_b = 100). Mixture Lambda: exact for
     Gaussian-slope lobes (6e-7 float, 2e-15 double against quadrature). On the bench's
     corpus (in-footprint reference, 4096 texels, views 0-75 pooled) m = 8 lobes are within
     0.10-0.18 and m = 16 within 0.09-0.14 (LEADR: 0.12-0.82). Fit of a 512 x 512 pyramid:
     2.1-2.8 s CPU at m = 4, 3.8-9.4 s at m = 16.
     Shader cost per pixel (bench/gpu/count.sh on bench/gpu/pixel.h: SPIR-V ops after
     spirv-opt -O / PTX of nvcc -O3 --use_fast_math, texel fetches excluded; m fetches apart),
     the texel path (pf_vmf_pixel_make, pf_vmf_sum_add_texel x m, pf_vmf_sum_specular):
     m = 1, 4, 8, 16: 156 / 164, 288 / 309, 464 / 501, 816 / 885, i.e. 1.34, 2.48, 4.00, 7.03x
     pf_leadr_specular's 116 / 129 SPIR-V (44 ops per lobe, 112 per pixel, 2 branches); the
     mixture form (pf_vmf_sum_add_texel_mixture) m = 4, 8: 467 / 488, 843 / 896. Through
     pf_vmf_lobe_make + pf_vmf_sum_add: 585 / 546 (m = 4), 1061 / 978 (m = 8). On the bench's
     corpus the texel path is within 2% of pf_vmf_sum_add's specular error in every cell
     (bench/microsurface.c's *_texel rows; docs/vmf.md). CPU (callgrind, float, x86-64 gcc -O2,
     instructions per pixel, texel path): m = 1, 4, 8, 16: 469, 948, 1574, 2823 against
     pf_leadr_specular's 273 (docs/vmf.md).

   SOURCES
     Wu, Zhao, Yan, Ramamoorthi 2019 (Accurate appearance preserving prefiltering for rendering
     displacement-mapped surfaces) eqs. 2-5, 6-8, 12-14, 21-24; Han, Sun, Ramamoorthi, Grinspun 2007 (frequency
     domain normal map filtering: vMF mixtures, spherical EM); Banerjee, Dhillon, Ghosh, Sra
     2005 (kappa ~ r (3 - r^2)/(1 - r^2)); Dupuy et al. 2013 (LEADR) eqs. 1-3, 10, 13-17;
     Smith 1967. */
#ifndef PF_VMF_H
#define PF_VMF_H

#ifndef PF_GLSL
#  include "pf_core.h"
#  include "pf_smith.h"
#  include "pf_beckmann.h"
#endif

#define PF_VMF_MAX_LOBES 16
#define PF_VMF_KAPPA_MIN PF_R(1.0e-4)
#define PF_VMF_KAPPA_MAX PF_R(1.0e5)

/* Cap on the exponents the module passes to PF_EXP: exp(-80) = 1.8e-35 is still a normal float,
   so exp never underflows (libm's underflow path, which sets errno, made a far lobe cost 10x a
   near one in the bench), and a value this far down the tail is 0 to the shading. */
#define PF_VMF_EXP_CAP PF_R(80.0)

/* ---------------------------------------------------------------- one lobe */
/* kappa clamped to [PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX]; NaN reads as PF_VMF_KAPPA_MIN (the
   CONVENTIONS' clamp, applied by every function that takes a kappa). */
PF_DEF pf_real pf_vmf_kappa_clamp(pf_real kappa)
{
    if (!(kappa > PF_VMF_KAPPA_MIN)) return PF_VMF_KAPPA_MIN; /* NaN too */
    return pf_min(kappa, PF_VMF_KAPPA_MAX);
}

/* 1 - exp(-x) for x >= 0 without cancellation near 0. Above 1/2, 1 - exp(-x) directly (at most
   one bit lost to the subtraction). At and below 1/2 the Taylor series x (1 - x/2 (1 - x/3 (1 -
   ...))), plain arithmetic with no exp or log: Kahan's (1 - u) x / (-log u), u = exp(-x), used
   here before, needs log accurate RELATIVE to log u near u = 1, and GLSL promises log only an
   absolute 2^-21 on [1/2, 2] (docs/gpu.md: a relative 2^-21 / x, 5e-4 at x = 1e-3). Truncation
   after x^9 (float) resp. x^16 (double): the first omitted term, relative, is x^9/10! = 5.4e-10
   resp. x^16/17! = 4.3e-20 at x = 1/2, well below half an ulp; every factor x/k < 1/2, so the
   nested form does not amplify rounding (tests/test_vmf.c: against expm1l). */
PF_DEF pf_real pfi_vmf_one_minus_exp_neg(pf_real x)
{
    pf_real r = PF_R(1.0);
    if (x > PF_R(0.5)) return PF_R(1.0) - PF_EXP(-x);
#ifdef PF_DOUBLE
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(16.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(15.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(14.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(13.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(12.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(11.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(10.0)) * r;
#endif
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(9.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(8.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(7.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(6.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(5.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(4.0)) * r;
    r = PF_R(1.0) - x * (PF_R(1.0) / PF_R(3.0)) * r;
    r = PF_R(1.0) - x * PF_R(0.5) * r;
    return x * r;
}

/* C(kappa) = kappa / (2 pi (1 - exp(-2 kappa))): the constant that makes
   C exp(kappa (mu.w - 1)) integrate to 1 over the sphere (Wu et al. 2019 eq. 4 with exp(kappa)
   factored out). 1/(4 pi) as kappa -> 0, kappa/(2 pi) for large kappa. */
PF_DEF pf_real pf_vmf_normalization(pf_real kappa)
{
    pf_real k = pf_vmf_kappa_clamp(kappa);
    return k * (PF_R(0.5) * PF_INV_PI) / pfi_vmf_one_minus_exp_neg(PF_R(2.0) * k);
}

/* Mean cosine A3(kappa) = E[mu.w] = coth kappa - 1/kappa (the mean resultant length of a vMF).
   Series below the threshold (the difference cancels there), closed form above. */
PF_DEF pf_real pf_vmf_mean_cosine(pf_real kappa)
{
    pf_real k = pf_vmf_kappa_clamp(kappa), k2, e;
#ifdef PF_DOUBLE
    const pf_real series_below = PF_R(0.1);
#else
    const pf_real series_below = PF_R(0.5);
#endif
    if (k < series_below) {
        k2 = k * k;
        /* coth k - 1/k = k/3 - k^3/45 + 2k^5/945 - k^7/4725 + 2k^9/93555 - ... */
        return k * (PF_R(1.0) / PF_R(3.0) +
                    k2 * (PF_R(-1.0) / PF_R(45.0) +
                          k2 * (PF_R(2.0) / PF_R(945.0) + k2 * (PF_R(-1.0) / PF_R(4725.0) + k2 * (PF_R(2.0) / PF_R(93555.0))))));
    }
    e = PF_EXP(-PF_R(2.0) * k);
    /* coth k = (1 + e)/(1 - e) = 1 + 2e/(1 - e) */
    return PF_R(1.0) + PF_R(2.0) * e / pfi_vmf_one_minus_exp_neg(PF_R(2.0) * k) - PF_R(1.0) / k;
}

/* Per-axis variance of the tangent-plane projection of a vMF lobe, E[|w - (mu.w) mu|^2]/2 =
   A3(kappa)/kappa (E[(mu.w)^2] = 1 - 2 A3/kappa). ~1/kappa for large kappa, 1/3 at 0. */
PF_DEF pf_real pf_vmf_tangent_variance(pf_real kappa)
{
    pf_real k = pf_vmf_kappa_clamp(kappa);
    /* coth k = 1 + 2 e^(-2k) + ...: below rounding past k = 10 (float) / 20 (double), and then
       A3/k = (1 - 1/k)/k with no exp or log (the shading path's common case) */
#ifdef PF_DOUBLE
    if (k > PF_R(20.0)) return (PF_R(1.0) - PF_R(1.0) / k) / k;
#else
    if (k > PF_R(10.0)) return (PF_R(1.0) - PF_R(1.0) / k) / k;
#endif
    return pf_vmf_mean_cosine(k) / k;
}

/* The inverse of pf_vmf_tangent_variance: the kappa whose per-axis tangent variance is v
   (48 bisection steps on log kappa over [PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX]: the map is
   monotone; constant loop bound). v >= 1/3 gives PF_VMF_KAPPA_MIN, v <= 0 or NaN
   PF_VMF_KAPPA_MAX. */
PF_DEF pf_real pf_vmf_kappa_from_tangent_variance(pf_real v)
{
    pf_real lo = PF_LOG(PF_VMF_KAPPA_MIN), hi = PF_LOG(PF_VMF_KAPPA_MAX), mid;
    int i;
    if (!(v > pf_vmf_tangent_variance(PF_VMF_KAPPA_MAX))) return PF_VMF_KAPPA_MAX;
    if (!(v < pf_vmf_tangent_variance(PF_VMF_KAPPA_MIN))) return PF_VMF_KAPPA_MIN;
    for (i = 0; i < 48; ++i) {
        mid = PF_R(0.5) * (lo + hi);
        if (pf_vmf_tangent_variance(PF_EXP(mid)) > v) lo = mid;
        else hi = mid;
    }
    return pf_vmf_kappa_clamp(PF_EXP(PF_R(0.5) * (lo + hi)));
}

/* g(w; kappa, mu) = C(kappa) exp(-kappa |w - mu|^2 / 2) for unit w and mu (= exp(kappa (mu.w
   - 1)), no cancellation near the peak, no overflow at large kappa). Per unit solid angle. */
PF_DEF pf_real pf_vmf_lobe_eval(pf_vec3 mu, pf_real kappa, pf_vec3 w)
{
    pf_real k = pf_vmf_kappa_clamp(kappa);
    pf_vec3 d = pf_vec3_sub(w, mu);
    pf_real q = pf_min(PF_R(0.5) * k * pf_vec3_dot(d, d), PF_VMF_EXP_CAP);
    return pf_vmf_normalization(k) * PF_EXP(-q);
}

/* Banerjee et al. 2005: kappa from the mean resultant length r = |E[w]| of a sample,
   kappa ~ r (3 - r^2) / (1 - r^2), clamped to [PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX]; r >= 1
   gives PF_VMF_KAPPA_MAX. (The fit uses the cancellation-free 1 - r^2 it accumulates.) */
PF_DEF pf_real pf_vmf_kappa_from_mean_length(pf_real r)
{
    pf_real rr = pf_clamp_nan_lo(r, PF_R(0.0), PF_R(1.0)); /* NaN -> 0 (pf_clamp keeps NaN in C) */
    pf_real one_minus = (PF_R(1.0) - rr) * (PF_R(1.0) + rr);
    if (!(one_minus * PF_VMF_KAPPA_MAX > rr * (PF_R(3.0) - rr * rr))) return PF_VMF_KAPPA_MAX;
    return pf_vmf_kappa_clamp(rr * (PF_R(3.0) - rr * rr) / one_minus);
}

/* The one-lobe approximation of a vMF of kappa convolved with a vMF base lobe of kappa_b
   (Wu et al. 2019 eq. 5's integral for one lobe): kappa kappa_b / (kappa + kappa_b), the
   small-angle rule 1/kappa' = 1/kappa + 1/kappa_b (angular variances add). */
PF_DEF pf_real pf_vmf_convolve_kappa(pf_real kappa, pf_real kappa_b)
{
    pf_real a = pf_vmf_kappa_clamp(kappa), b = pf_vmf_kappa_clamp(kappa_b);
    return pf_vmf_kappa_clamp(a * (b / (a + b)));
}

/* kappa of the vMF lobe matching a Beckmann lobe of slope deviation sigma per axis (Beckmann
   roughness alpha = sqrt(2) sigma) at its peak: exp(-tan^2 t / (2 sigma^2)) ~ exp(-t^2 /
   (2 sigma^2)) and exp(kappa (cos t - 1)) ~ exp(-kappa t^2 / 2), so kappa = 1/sigma^2. */
PF_DEF pf_real pf_vmf_kappa_from_sigma(pf_real sigma)
{
    pf_real s2 = sigma * sigma;
    if (!(s2 * PF_VMF_KAPPA_MAX > PF_R(1.0))) return PF_VMF_KAPPA_MAX;
    return pf_vmf_kappa_clamp(PF_R(1.0) / s2);
}

/* Gaussian slope statistics of a lobe (see DEFINITIONS, masking): mean -mu.xy/mu.z, covariance
   v (t t^T / mu.z^4 + (I - t t^T) / mu.z^2) + base_var I with v = pf_vmf_tangent_variance.
   mu.z is floored at 1e-3 (a lobe axis within 0.06 degrees of the horizon). */
PF_DEF pf_slope_stats pf_vmf_lobe_slope_stats(pf_vec3 mu, pf_real kappa, pf_real base_var)
{
    pf_real z = pf_max(mu.z, PF_R(1.0e-3)), iz2 = PF_R(1.0) / (z * z);
    pf_real v = pf_vmf_tangent_variance(kappa), b = pf_max(base_var, PF_R(0.0));
    pf_real r2 = mu.x * mu.x + mu.y * mu.y, c2 = PF_R(1.0), s2 = PF_R(0.0), cs = PF_R(0.0);
    pf_real v_along = v * iz2 * iz2, v_across = v * iz2;
    if (r2 > PF_R(0.0)) {
        c2 = mu.x * mu.x / r2;
        s2 = mu.y * mu.y / r2;
        cs = mu.x * mu.y / r2;
    }
    return pf_slope_stats_make(-mu.x / z, -mu.y / z, c2 * v_along + s2 * v_across + b,
                               s2 * v_along + c2 * v_across + b, cs * (v_along - v_across));
}

/* ---------------------------------------------------------------- lobes of a mixture
   A mixture is shaded one lobe at a time (a shader fetches m RGBA texels and loops): each
   lobe's terms are added into a pf_vmf_sum, which then gives G and the BRDF. No arrays in
   structs, constant work per lobe, any m. */
PF_STRUCT_BEGIN(pf_vmf_lobe)
    pf_real amp;
    pf_vec3 mu;
    pf_real kappa;
PF_STRUCT_END(pf_vmf_lobe)

/* The lobe (amp, mu = (mu_x, mu_y, sqrt(1 - mu_x^2 - mu_y^2)), kappa): the packed texel form,
   4 reals. An axis with mu_x^2 + mu_y^2 > 1 is rescaled onto the horizon; NaN axis components
   read as 0, a negative or NaN amplitude as 0, kappa clamped (pf_vmf_kappa_clamp). */
PF_DEF pf_vmf_lobe pf_vmf_lobe_make(pf_real amp, pf_real mu_x, pf_real mu_y, pf_real kappa)
{
    pf_vmf_lobe l;
    pf_real x = mu_x == mu_x ? mu_x : PF_R(0.0), y = mu_y == mu_y ? mu_y : PF_R(0.0);
    pf_real r2 = x * x + y * y, z2 = PF_R(1.0) - r2;
    if (!(r2 <= PF_R(1.0))) { /* also inf */
        pf_real s = r2 < PF_REAL_MAX ? PF_R(1.0) / PF_SQRT(r2) : PF_R(0.0);
        x = x * s;
        y = y * s;
        if (!(r2 < PF_REAL_MAX)) { /* an infinite component: the horizon along the x axis */
            x = PF_R(1.0);
            y = PF_R(0.0);
        }
        z2 = PF_R(0.0);
    }
    l.amp = pf_max(amp, PF_R(0.0));
    l.mu = pf_vec3_make(x, y, PF_SQRT(pf_max(z2, PF_R(0.0))));
    l.kappa = pf_vmf_kappa_clamp(kappa);
    return l;
}

/* amp g(w; kappa, mu), unit w: the lobe's share of the area-weighted normal density p(w). */
PF_DEF pf_real pf_vmf_lobe_density(pf_vmf_lobe l, pf_vec3 w)
{
    return l.amp * pf_vmf_lobe_eval(l.mu, l.kappa, w);
}

/* The lobe's NDF term in the vMF form, convolved with a vMF base lobe of kappa_b
   (pf_vmf_convolve_kappa; kappa_b >= PF_VMF_KAPPA_MAX: no base lobe): amp g(w; kappa', mu) / w.z,
   unit w; 0 for w.z <= 0. Summed over the lobes: D'(w), integral D' (w.z) dw = sum amp
   (Wu et al. eq. 3; the mass the lobes put below the horizon excepted). */
PF_DEF pf_real pf_vmf_lobe_ndf(pf_vmf_lobe l, pf_vec3 w, pf_real kappa_b)
{
    pf_real k = kappa_b >= PF_VMF_KAPPA_MAX ? l.kappa : pf_vmf_convolve_kappa(l.kappa, kappa_b);
    if (!(w.z > PF_R(0.0))) return PF_R(0.0);
    return l.amp * pf_vmf_lobe_eval(l.mu, k, w) / pf_max(w.z, PF_R(1.0e-6));
}

/* The lobe's NDF term in the slope form: amp times the Beckmann NDF (LEADR eq. 10: the slope
   density P22 over cos^4) of pf_vmf_lobe_slope_stats(mu, kappa, base_var): the lobe convolved
   with a Beckmann base lobe of slope variance base_var per axis, exactly in slope space
   (Gaussian variances add). Written here rather than through pf_beckmann_d so that its
   exponent is capped at PF_VMF_EXP_CAP (no libm underflow path) and its determinant floored
   at 1e-12 (base_var = 0 and a sharp lobe). Unit w; 0 for w.z <= 0. */
PF_DEF pf_real pfi_vmf_ndf_stats(pf_real amp, pf_slope_stats s, pf_vec3 w)
{
    pf_real iz, dx, dy, det, q, iz2;
    if (!(w.z > PF_R(1.0e-6))) return PF_R(0.0);
    iz = PF_R(1.0) / w.z;
    dx = -w.x * iz - s.mean_x;
    dy = -w.y * iz - s.mean_y;
    det = pf_max(s.var_x * s.var_y - s.cov_xy * s.cov_xy, PF_R(1.0e-12));
    q = pf_max(s.var_y * dx * dx - PF_R(2.0) * s.cov_xy * dx * dy + s.var_x * dy * dy, PF_R(0.0));
    iz2 = iz * iz;
    return amp * PF_EXP(-pf_min(PF_R(0.5) * q / det, PF_VMF_EXP_CAP)) * (PF_R(0.5) * PF_INV_PI) / PF_SQRT(det) *
           (iz2 * iz2);
}

PF_DEF pf_real pf_vmf_lobe_ndf_slope(pf_vmf_lobe l, pf_vec3 w, pf_real base_var)
{
    return pfi_vmf_ndf_stats(l.amp, pf_vmf_lobe_slope_stats(l.mu, l.kappa, base_var), w);
}

/* amp (w.z - w.xy . s), s = -mu.xy / mu.z: the lobe's share of the mesosurface projected area
   toward w per unit macrosurface area (LEADR eq. 1). Can be negative. */
PF_DEF pf_real pf_vmf_lobe_area(pf_vmf_lobe l, pf_vec3 w)
{
    return l.amp * pf_vec3_dot(w, l.mu) / pf_max(l.mu.z, PF_R(1.0e-3));
}

/* e(nu) = exp(-nu^2)/(2 sqrt(pi)) - nu erfc(nu)/2 = E[(X - c)+] / (sqrt(2) sigma) for X
   Gaussian of mean mu, deviation sigma, nu = (c - mu)/(sqrt 2 sigma); every real nu.
   nu >= 0.5: nu Lambda(nu) (pf_lambda_beckmann, cancellation-free); below, both terms are
   of one sign or comparable and the direct form is accurate. */
PF_DEF pf_real pfi_vmf_excess(pf_real nu)
{
    /* the tails, where exp(-nu^2) would underflow (libm's slow path): e(nu) < 1e-37 past 9;
       e(nu) = -nu + exp(-nu^2)/(2 sqrt(pi) nu^2) (1 + O(1/nu^2)) below -6, -nu to 1e-17 */
    if (nu > PF_R(9.0)) return PF_R(0.0);
    if (nu < PF_R(-6.0)) return -nu;
    if (nu >= PF_R(0.5)) return nu * pf_lambda_beckmann(nu);
    return pf_exp_neg_sq(nu) * (PF_R(0.5) * PF_INV_SQRT_PI) - PF_R(0.5) * nu * pf_erfc(nu);
}

/* The lobe's share of Smith's numerator toward w: amp |w.xy| E[(q - cot t)+] for the lobe's
   Gaussian slopes q along w (pf_vmf_lobe_slope_stats with base_var), = amp sigma_w sqrt(2)
   e(nu), nu = (w.z - w.xy . s)/(sqrt(2) sigma_w), sigma_w^2 = w.xy^T Sigma w.xy. With the
   lobe areas: Lambda(w) = sum excess / sum area (pf_vmf_lambda). w need not be unit. */
PF_DEF pf_real pfi_vmf_excess_stats(pf_real amp, pf_slope_stats s, pf_vec3 w)
{
    pf_real a = w.z - w.x * s.mean_x - w.y * s.mean_y;
    pf_real var = w.x * w.x * s.var_x + w.y * w.y * s.var_y + PF_R(2.0) * w.x * w.y * s.cov_xy;
    pf_real sd = PF_SQRT(PF_R(2.0) * pf_min(pf_max(var, PF_R(0.0)), PF_R(0.25) * PF_REAL_MAX));
    /* sd -> 0: E[(X - c)+] -> (mu - c)+, i.e. max(-a, 0) */
    if (sd > PF_R(1.0e-12) * PF_FABS(a)) return amp * sd * pfi_vmf_excess(a / sd);
    return amp * pf_max(-a, PF_R(0.0));
}

PF_DEF pf_real pf_vmf_lobe_excess(pf_vmf_lobe l, pf_vec3 w, pf_real base_var)
{
    return pfi_vmf_excess_stats(l.amp, pf_vmf_lobe_slope_stats(l.mu, l.kappa, base_var), w);
}

/* Smith's Lambda of a mixture from its summed excesses and areas (pf_smith.h eq. 1 is linear in
   the slope density, so this is exact for Gaussian-slope lobes): excess / area, PF_LAMBDA_MAX
   when area <= 0 (a direction on or below the mixture's mesosurface) or the ratio exceeds it. */
PF_DEF pf_real pf_vmf_lambda(pf_real excess_sum, pf_real area_sum)
{
    pf_real lam;
    if (!(area_sum > PF_R(0.0))) return PF_LAMBDA_MAX;
    lam = pf_max(excess_sum, PF_R(0.0)) / area_sum;
    return lam < PF_LAMBDA_MAX ? lam : PF_LAMBDA_MAX;
}

/* ---------------------------------------------------------------- the multi-lobe specular BRDF
   I = F(h.wi) D'(h) G / (4 A_o) (DEFINITIONS, specular; Wu et al. 2019 eq. 5 with a
   microfacet base lobe, LEADR eq. 17's projected-area normalization), radiance toward wo per
   unit radiance from wi, light cosine included. A mixture is summed lobe by lobe into a
   pf_vmf_sum (USE below); D' and A_o are divided by sum amp at the end.
   D', two forms of the convolved lobes:
     slope form (pf_vmf_sum_add): each lobe as the Beckmann lobe of its Gaussian slope
       statistics with the base lobe's slope variance base_var added (pf_vmf_lobe_ndf_slope:
       in slope space the convolution of Gaussians is exact). A one-texel footprint (kappa =
       PF_VMF_KAPPA_MAX) is then LEADR's own base lobe to 0.5%.
     vMF form (pf_vmf_sum_add_vmf): amp g(h; kappa', mu)/h.z with kappa' =
       pf_vmf_convolve_kappa(kappa, kappa_b), Wu et al.'s and Han et al.'s spherical
       convolution. A Beckmann base lobe is not rotation-invariant (its angular width shrinks
       as mu.z^2 along the tilt), so this form was off by 0.24-0.50 at a 1-texel footprint of
       the bench's corpus (docs/vmf.md); kept for vMF base lobes.
   G, two masking-shadowing terms:
     pf_vmf_sum_g2: Smith for ONE Gaussian with the mixture's slope mean and covariance (the
       sum's moments; base_var included through each lobe): LEADR's G (eq. 13) of the
       footprint, what the bench's oracle_histogram_smith uses; cost of one LEADR G.
     pf_vmf_sum_g2_mixture: the exact Smith Lambda of the Gaussian-slope lobes (DEFINITIONS,
       masking), from the excesses pf_vmf_sum_add_masking adds (two Lambdas per lobe).
   USE: s = pf_vmf_sum_zero();
        for each lobe: s = pf_vmf_sum_add(s, lobe, wo, wi, base_var);
                       [s = pf_vmf_sum_add_masking(s, lobe, wo, wi, base_var);]
        I = pf_vmf_sum_specular(s, wo, wi, f0)      (or pf_vmf_sum_specular_mixture). */
PF_STRUCT_BEGIN(pf_vmf_sum)
    pf_real amp;      /* sum amp */
    pf_real ndf;      /* sum of the lobes' D'(h) terms */
    pf_real ex;       /* sum amp E[x], E[y], E[x^2], E[y^2], E[xy] of the lobes' slopes */
    pf_real ey;
    pf_real exx;
    pf_real eyy;
    pf_real exy;
    pf_real excess_o; /* sum pf_vmf_lobe_excess(wo) (pf_vmf_sum_add_masking) */
    pf_real excess_i; /* sum pf_vmf_lobe_excess(wi) */
PF_STRUCT_END(pf_vmf_sum)

PF_DEF pf_vmf_sum pf_vmf_sum_zero(void)
{
    pf_vmf_sum s;
    s.amp = s.ndf = s.ex = s.ey = s.exx = s.eyy = s.exy = s.excess_o = s.excess_i = PF_R(0.0);
    return s;
}

/* the half vector of wo, wi (wo + wi when it cannot be normalized: every term is then 0) */
PF_DEF pf_vec3 pfi_vmf_half(pf_vec3 wo, pf_vec3 wi)
{
    pf_vec3 h = pf_vec3_add(wo, wi);
    pf_real l = pf_vec3_length(h);
    return l > PF_R(0.0) ? pf_vec3_scale(h, PF_R(1.0) / l) : h;
}

/* the lobe's amplitude and slope moments, from its slope statistics st */
PF_DEF pf_vmf_sum pfi_vmf_sum_moments(pf_vmf_sum s, pf_real amp, pf_slope_stats st)
{
    s.amp += amp;
    s.ex += amp * st.mean_x;
    s.ey += amp * st.mean_y;
    s.exx += amp * (st.var_x + st.mean_x * st.mean_x);
    s.eyy += amp * (st.var_y + st.mean_y * st.mean_y);
    s.exy += amp * (st.cov_xy + st.mean_x * st.mean_y);
    return s;
}

/* 1/sqrt(x): GLSL's inversesqrt (one instruction), else 1/PF_SQRT(x). */
#ifdef PF_GLSL
PF_DEF pf_real pfi_vmf_rsqrt(pf_real x) { return inversesqrt(x); }
#else
PF_DEF pf_real pfi_vmf_rsqrt(pf_real x) { return PF_R(1.0) / PF_SQRT(x); }
#endif

/* What every lobe of one pixel shares (pf_vmf_pixel_make, once per pixel): with H = wo + wi
   and h = H / |H|, gx = H.x / H.z and gy = H.y / H.z (minus the half vector's slope),
   ldn = log(1 / (2 pi h.z^4)) (the log of the slope density's Jacobian, LEADR eq. 10, times the
   Gaussian's 1 / (2 pi), added to each lobe's exponent so that no lobe multiplies by it;
   -1e30 when h.z <= 1e-6, where the lobes' terms are 0, as pf_vmf_lobe_ndf_slope) and the base
   lobe's slope variance base_var (>= 0). wo and wi unit, on or above the macrosurface: a pair
   below it gives values that the specular functions discard (they return 0 there). */
PF_STRUCT_BEGIN(pf_vmf_pixel)
    pf_real gx;
    pf_real gy;
    pf_real ngx; /* -gx (saves a negation per lobe) */
    pf_real ldn;
    pf_real base_var;
PF_STRUCT_END(pf_vmf_pixel)

PF_DEF pf_vmf_pixel pf_vmf_pixel_make(pf_vec3 wo, pf_vec3 wi, pf_real base_var)
{
    pf_vmf_pixel p;
    pf_vec3 h = pf_vec3_add(wo, wi);
    /* 1/h.z with h.z floored at 1e-30: gx, gy finite for every pair (|h.xy| <= 2); q is then
       >= 1e12 or inf wherever h.z <= 1e-6 |h|, and ldn = -1e30 there */
    pf_real niz = PF_R(-1.0) / pf_max(h.z, PF_R(1.0e-30));
    /* 1 / cos^2 of h, in [1, 1e12) where used; |h|^2 + 1e-30, so that h = 0 gives q = inf
       (float) or 1e30 (double), never 0 */
    pf_real q = (h.x * h.x + (h.y * h.y + (h.z * h.z + PF_R(1.0e-30)))) * (niz * niz);
    /* from -1/h.z: -gx and -gy are one multiply each (the lobes read -gx, -gy and gy) */
    p.ngx = h.x * niz;
    p.gx = -p.ngx;
    p.gy = -(h.y * niz);
    /* h.z > 1e-6 |h| <=> 1 / cos^2 < 1e12 (q >= 1 otherwise: no test for q > 0);
       log(q^2 / (2 pi)) = 2 log q - log(2 pi) */
    p.ldn = q < PF_R(1.0e12) ? PF_R(2.0) * PF_LOG(q) - PF_R(1.837877066409345483560659472811235279)
                                              : PF_R(-1.0e30);
    p.base_var = pf_max(base_var, PF_R(0.0));
    return p;
}

/* exp(ldn + x), x = -q/2 <= 0 the lobe's exponent, ldn of pf_vmf_pixel_make. C and C++:
   exp(ldn + max(x, -PF_VMF_EXP_CAP)) (the exponent capped as pfi_vmf_ndf_stats caps it, so
   that libm's exp never takes its underflow path, which sets errno and made a far lobe cost
   10x a near one on the CPU; 0 where ldn is -1e30). GPUs (GLSL, CUDA device code) evaluate
   exp as one exp2 that underflows to 0 at no cost: exp(ldn + x), one fused add and no compare;
   the two differ only where the term is below exp(-80) = 1.8e-35 of its peak. */
PF_DEF pf_real pfi_vmf_exp_lobe(pf_real ldn, pf_real x)
{
#if defined(PF_GLSL) || defined(__CUDA_ARCH__)
    return PF_EXP(ldn + x);
#else
    return ldn > PF_R(-1.0e29) ? PF_EXP(ldn + pf_max(x, -PF_VMF_EXP_CAP)) : PF_R(0.0);
#endif
}

/* One lobe of the slope form into the sum, from its amplitude, axis (mu.x, mu.y) with
   z2 = mu.z^2 (floored by the caller) and per-axis tangent variance v (pf_vmf_tangent_variance,
   >= v(PF_VMF_KAPPA_MAX) ~ 1e-5). The lobe's slope covariance (pf_vmf_lobe_slope_stats) is,
   with s = mu.xy / mu.z (the slope mean is -s) and the identity (1/z^2 - 1) / |mu.xy|^2 =
   1/z^2 of a unit axis,
       Sigma = c I + w s s^T,   w = v / z^2,   c = w + base_var,
   whose determinant is c e, e = c + w |s|^2 = base_var + w / z^2 (|s|^2 = 1/z^2 - 1 for a unit
   axis; >= 1e-10: no floor needed), and whose quadratic form of d = slope(h) + s is
   (c |d|^2 + w (s x d)^2) / (c e) (Sherman-Morrison, and |s|^2 |d|^2 - (s.d)^2 = (s x d)^2: no
   cancellation), s x d = -(sx gy - sy gx). So the lobe's D'(h) term (pfi_vmf_ndf_stats) is
       amp exp(ldn - q/2) / sqrt(c e)       (pfi_vmf_exp_lobe; ldn of pf_vmf_pixel_make)
   and its moments sum amp (var + mean^2) = amp c + amp (1 + w) s s^T (pfi_vmf_sum_moments):
   the same sums as pf_vmf_lobe_slope_stats + pfi_vmf_ndf_stats + pfi_vmf_sum_moments, with a
   third of the instructions and no branch. */
PF_DEF pf_vmf_sum pfi_vmf_sum_add_slope(pf_vmf_sum s, pf_vmf_pixel p, pf_real amp, pf_real mx, pf_real my,
                                        pf_real z2, pf_real v)
{
    pf_real iz = pfi_vmf_rsqrt(z2), iz2 = iz * iz;
    pf_real sx = mx * iz, sy = my * iz;
    pf_real w = v * iz2, c = w + p.base_var;
    pf_real ce = c * (w * iz2 + p.base_var);
    pf_real dx = sx + p.ngx, dy = sy - p.gy, cr = sx * p.gy + sy * p.ngx;
    pf_real q = (c * (dx * dx + dy * dy) + w * (cr * cr)) / ce;
    pf_real u = amp + amp * w, ac = amp * c, usx = u * sx;
    s.ndf += amp * pfi_vmf_rsqrt(ce) * pfi_vmf_exp_lobe(p.ldn, PF_R(-0.5) * q);
    s.amp += amp;
    s.ex -= amp * sx;
    s.ey -= amp * sy;
    s.exx = (s.exx + ac) + usx * sx;
    s.eyy = (s.eyy + ac) + (u * sy) * sy;
    s.exy += usx * sy;
    return s;
}

/* Adds one lobe, slope form (see above). */
PF_DEF pf_vmf_sum pf_vmf_sum_add(pf_vmf_sum s, pf_vmf_lobe l, pf_vec3 wo, pf_vec3 wi, pf_real base_var)
{
    pf_real z = pf_max(l.mu.z, PF_R(1.0e-3));
    return pfi_vmf_sum_add_slope(s, pf_vmf_pixel_make(wo, wi, base_var), l.amp, l.mu.x, l.mu.y, z * z,
                                 pf_vmf_tangent_variance(l.kappa));
}

/* A3(kappa) / kappa (pf_vmf_tangent_variance) without a branch or an exp, for a kappa in the
   clamp range (a texel the fit wrote): the [2/3] rational
       (k^2 + a k + b) / (k^3 + (a + 1) k^2 + d k + 3 b),
       a = 2.13881281, b = 4.2531533, d = 6.67286498,
   exact at both ends: 1/3 at k = 0 and 1/k (1 - 1/k) + O(1/k^3) at large k (the exact
   A3/k = (coth k - 1/k)/k); a, b, d minimize the largest relative error over kappa in
   [1e-4, 1e5] (Nelder-Mead on 2001 log-spaced points): 1.92e-3 (tests/test_vmf.c measures it
   against pf_vmf_tangent_variance). 6 SPIR-V ops (Horner, fused), against 4 for the [1/2]
   rational (k + a) / (k (k + b) + c) this replaced (1.29e-2: the corpus' m = 4 cells moved up
   to +2.35%), 10 for the exp form ((k coth k - 1) / k^2) and 51 with 10 branches for
   pf_vmf_tangent_variance; every coefficient positive, no cancellation. */
PF_DEF pf_real pfi_vmf_tangent_variance_lean(pf_real kappa)
{
    return (kappa * (kappa + PF_R(2.13881281)) + PF_R(4.2531533)) /
           (kappa * (kappa * (kappa + PF_R(3.13881281)) + PF_R(6.67286498)) + PF_R(12.7594599));
}

/* mu.z^2 of a texel's axis (mu_x, mu_y), mu_x^2 + mu_y^2 <= 1: (1 + eps) - mu_x^2 - mu_y^2, i.e.
   floored at eps = 1e-6 (float, 8 ulp of 1: an axis pf_vmf_lobe_make rescaled onto the horizon
   has mu_x^2 + mu_y^2 within 3 ulp of 1; 1e-14 double) by an offset instead of a max (one
   operation less per lobe): mu.z^2 + eps, a relative change of eps / mu.z^2 (1e-6 at the
   normal, 1e-4 at 84 degrees in float), where pf_vmf_lobe_slope_stats floors mu.z at 1e-3.
   An axis past the unit disc by more than eps (outside the fit's contract) gives NaN. */
PF_DEF pf_real pfi_vmf_texel_z2(pf_real mu_x, pf_real mu_y)
{
#ifdef PF_DOUBLE
    return PF_R(1.00000000000001) - (mu_x * mu_x + mu_y * mu_y);
#else
    return PF_R(1.000001) - (mu_x * mu_x + mu_y * mu_y);
#endif
}

/* Adds one lobe straight from its texel (amp, mu.x, mu.y, kappa), the lobe pyramid's packed
   form (pf_vmf_fit.h), with the pixel's shared terms p = pf_vmf_pixel_make(wo, wi, base_var):
   the shader path, branch-free, 44 SPIR-V ops per lobe (docs/vmf.md). The same sums as
   pf_vmf_sum_add(s, pf_vmf_lobe_make(amp, mu_x, mu_y, kappa), wo, wi, base_var) for a texel
   the fit wrote (amp >= 0, mu_x^2 + mu_y^2 <= 1, kappa in the clamp range), to rounding and
   the tangent variance's 1.92e-3 (pfi_vmf_tangent_variance_lean: D' within 1.9e-3 of the
   lobe's peak, the moments within 1.8e-3, tests/test_vmf.c); mu.z^2 = 1 - mu_x^2 - mu_y^2
   plus 1e-6 (pfi_vmf_texel_z2), where pf_vmf_lobe_slope_stats floors mu.z at 1e-3. No
   decode: a texel outside that contract (a negative amp, an axis past the horizon, NaN) is
   not repaired as pf_vmf_lobe_make repairs it (an axis past the horizon gives NaN). */
PF_DEF pf_vmf_sum pf_vmf_sum_add_texel(pf_vmf_sum s, pf_vmf_pixel p, pf_real amp, pf_real mu_x, pf_real mu_y,
                                       pf_real kappa)
{
    return pfi_vmf_sum_add_slope(s, p, amp, mu_x, mu_y, pfi_vmf_texel_z2(mu_x, mu_y), pfi_vmf_tangent_variance_lean(kappa));
}

/* Adds one lobe, vMF form: convolved with a vMF base lobe of kappa_b (pf_vmf_kappa_from_sigma
   for a Beckmann base of slope deviation sigma). See above. */
PF_DEF pf_vmf_sum pf_vmf_sum_add_vmf(pf_vmf_sum s, pf_vmf_lobe l, pf_vec3 wo, pf_vec3 wi, pf_real kappa_b,
                                     pf_real base_var)
{
    s.ndf += pf_vmf_lobe_ndf(l, pfi_vmf_half(wo, wi), kappa_b);
    return pfi_vmf_sum_moments(s, l.amp, pf_vmf_lobe_slope_stats(l.mu, l.kappa, base_var));
}

/* Adds one lobe's Smith excesses toward wo and wi (for pf_vmf_sum_g2_mixture and
   pf_vmf_sum_specular_mixture); call it with the same lobe as the add. */
PF_DEF pf_vmf_sum pf_vmf_sum_add_masking(pf_vmf_sum s, pf_vmf_lobe l, pf_vec3 wo, pf_vec3 wi, pf_real base_var)
{
    pf_slope_stats st = pf_vmf_lobe_slope_stats(l.mu, l.kappa, base_var);
    s.excess_o += pfi_vmf_excess_stats(l.amp, st, wo);
    s.excess_i += pfi_vmf_excess_stats(l.amp, st, wi);
    return s;
}

/* One lobe's share of Smith's numerator toward d (pfi_vmf_excess_stats) from its closed-form
   slope statistics (pfi_vmf_sum_add_slope: mean -s, Sigma = c I + w s s^T): with ps = d.xy . s,
   a = d.z + ps (the lobe's area per unit amp), 2 var = 2 (c |d.xy|^2 + w ps^2),
   nu = a / sqrt(2 var), and e(nu) = pf_smith_nu_over_g1(|nu|) - max(nu, 0) (e(nu) = nu / G1(nu)
   - nu for nu >= 0, e(-nu) = e(nu) + nu), so the exact e(nu)'s erfc and exp (pfi_vmf_excess:
   two branches and an erfc per direction) become the G1 fit of pf_smith.h, branch-free. Float:
   the fit's 4.7e-7 (relative, in G1) is an absolute error of ~5e-7 |nu| in e, i.e. of ~5e-7 in
   Lambda = sum excess / sum area: G2 to 1e-6 (tests/test_vmf.c), while Lambda itself loses
   relative accuracy where it is tiny (nu > 2). Double: pf_smith_nu_over_g1's exp and K form. */
PF_DEF pf_real pfi_vmf_excess_fast(pf_real amp, pf_real sx, pf_real sy, pf_real c, pf_real w, pf_vec3 d)
{
    pf_real ps = d.x * sx + d.y * sy;
    pf_real rs = pfi_vmf_rsqrt(pf_clamp_nan_lo(PF_R(2.0) * (c * (d.x * d.x + d.y * d.y) + w * (ps * ps)), PF_REAL_MIN,
                                               PF_R(0.25) * PF_REAL_MAX));
    pf_real nu = (d.z + ps) * rs;
    return amp * (pf_smith_nu_over_g1(pf_max(PF_FABS(nu), PF_R(1.0e-20))) - pf_max(nu, PF_R(0.0))) / rs;
}

/* pf_vmf_sum_add_texel and the lobe's Smith excesses toward wo and wi (what
   pf_vmf_sum_add_masking adds), for pf_vmf_sum_specular_mixture: the mixture's exact Smith
   Lambda with each excess from the G1 fit (pfi_vmf_excess_fast) instead of erfc. The shader
   path of the mixture form: one texel, branch-free, ~94 SPIR-V ops per lobe against ~650
   (docs/vmf.md). */
PF_DEF pf_vmf_sum pf_vmf_sum_add_texel_mixture(pf_vmf_sum s, pf_vmf_pixel p, pf_vec3 wo, pf_vec3 wi, pf_real amp,
                                               pf_real mu_x, pf_real mu_y, pf_real kappa)
{
    pf_real z2 = pfi_vmf_texel_z2(mu_x, mu_y);
    pf_real v = pfi_vmf_tangent_variance_lean(kappa), iz = pfi_vmf_rsqrt(z2);
    pf_real w = v * (iz * iz), c = w + p.base_var;
    s = pfi_vmf_sum_add_slope(s, p, amp, mu_x, mu_y, z2, v);
    s.excess_o += pfi_vmf_excess_fast(amp, mu_x * iz, mu_y * iz, c, w, wo);
    s.excess_i += pfi_vmf_excess_fast(amp, mu_x * iz, mu_y * iz, c, w, wi);
    return s;
}

/* The mixture's slope mean and covariance (sum of the lobes' moments over sum amp; base_var
   included). An empty sum gives zero statistics. */
PF_DEF pf_slope_stats pf_vmf_sum_stats(pf_vmf_sum s)
{
    /* divisions, not times 1/amp: a subnormal sum amp has an infinite reciprocal, while each
       moment is at most amp times a bounded lobe moment */
    pf_real a = s.amp > PF_R(0.0) ? s.amp : PF_R(1.0);
    return pf_slope_stats_from_moments(s.ex / a, s.ey / a, s.exx / a, s.eyy / a, s.exy / a);
}

/* Joint masking-shadowing of the mixture as one Gaussian (its slope mean and covariance):
   1/(1 + Lambda(wo) + Lambda(wi)) (LEADR eq. 13); 0 when a direction is on or below the
   mesosurface. In [0, 1]. */
PF_DEF pf_real pf_vmf_sum_g2(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi)
{
    return pf_beckmann_masking_shadowing(wo, wi, pf_vmf_sum_stats(s));
}

/* the mixture's mesosurface projected area toward w times sum amp (LEADR eq. 1) */
PF_DEF pf_real pfi_vmf_sum_area(pf_vmf_sum s, pf_vec3 w)
{
    return w.z * s.amp - w.x * s.ex - w.y * s.ey;
}

/* Joint masking-shadowing from the mixture's exact Smith Lambda (pf_vmf_sum_add_masking must
   have been called for every lobe); 0 when a direction is on or below the mesosurface. */
PF_DEF pf_real pf_vmf_sum_g2_mixture(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi)
{
    pf_real lo = pf_vmf_lambda(s.excess_o, pfi_vmf_sum_area(s, wo));
    pf_real li = pf_vmf_lambda(s.excess_i, pfi_vmf_sum_area(s, wi));
    if (!(lo < PF_LAMBDA_MAX) || !(li < PF_LAMBDA_MAX)) return PF_R(0.0);
    return PF_R(1.0) / (PF_R(1.0) + lo + li);
}

/* Masking G1 = 1/(1 + Lambda(wo)) from the mixture's exact Smith Lambda (the wo excesses of
   pf_vmf_sum_add_masking). 0 on or below the mesosurface. */
PF_DEF pf_real pf_vmf_sum_g1_mixture(pf_vmf_sum s, pf_vec3 wo)
{
    pf_real lo = pf_vmf_lambda(s.excess_o, pfi_vmf_sum_area(s, wo));
    if (!(lo < PF_LAMBDA_MAX)) return PF_R(0.0);
    return PF_R(1.0) / (PF_R(1.0) + lo);
}

/* G / A_o with the mixture's exact Smith Lambda (see the comment above pf_leadr_specular in
   pf_beckmann.h): 1 / (P_o + max(A_o, 0) Lambda_i), P_o the projected area toward wo of the
   facets that face it, so that a view below the mesosurface (A_o <= 0) but above the
   macrosurface sees those facets instead of 0. Each lobe's area + excess is amp E[(a - Y)+] =
   its facing area (>= 0), so P_o = (area_o + excess_o) / amp (= A_o (1 + Lambda_o) above the
   mesosurface) and Lambda_i = pf_vmf_lambda. Below the mesosurface the sum cancels (excess_o ~
   -area_o), so its relative error grows as P_o / |area_o| shrinks.
   Lambda_i as pf_leadr_specular has it: Smith's above the mesosurface; on or below it (but
   above the macrosurface) the macrosurface's share of the light, max(P_i, wi.z) / wi.z - 1
   (pf_beckmann_light_lambda in pf_beckmann.h), P_i = (area_i + excess_i) / amp the mixture's
   own facing area. The value jumps at area_i = 0 (Smith's 0 just above).
   Every term is divided by sum amp before it is combined (ia = 1/amp, amp normal: a sum amp
   below PF_REAL_MIN is empty, as a GPU that flushes subnormals reads it), so the denominator
   is a facing area per unit macrosurface area, 0 or normal, never the subnormal product of
   amp and a small area that a GPU flushes to 0. */
PF_DEF pf_real pfi_vmf_sum_specular_mix(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi, pf_real f0)
{
    pf_real ia, area_o, area_i, den;
    if (!(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0)) || !(s.amp >= PF_REAL_MIN)) return PF_R(0.0);
    ia = PF_R(1.0) / s.amp;
    area_o = pfi_vmf_sum_area(s, wo) * ia;
    area_i = pfi_vmf_sum_area(s, wi) * ia;
    den = area_o + s.excess_o * ia +
          pf_max(area_o, PF_R(0.0)) *
              (area_i > PF_R(0.0) ? pf_vmf_lambda(s.excess_i * ia, area_i)
                                  : pf_max(area_i + s.excess_i * ia, wi.z) / wi.z - PF_R(1.0));
    if (!(den > PF_R(0.0))) return PF_R(0.0); /* no facet faces the view (in pf_real) */
    return pf_min((s.ndf * ia) / den * (pf_fresnel_schlick(f0, pf_vec3_dot(pfi_vmf_half(wo, wi), wi)) * PF_R(0.25)),
                  PF_REAL_MAX);
}

/* The multi-lobe specular radiance factor I = F D' G / (4 A_o) of the summed mixture with G
   of the mixture as one Gaussian (pf_vmf_sum_g2's slope mean and covariance), G / A_o exactly
   as pf_leadr_specular forms it (pf_beckmann.h, the comment above pf_leadr_specular):
   1 / (P_o + max(A_o, 0) Lambda_i'), P_o = (pf_smith_nu_over_g1(|nu_o|) - max(-nu_o, 0)) /
   rs_o the projected area of the facets facing the view (A_o (1 + Lambda_o) above the mean
   plane; below it, in float, its relative error is 3e-6 at nu_o = -0.5, 2e-3 at -2, 3% at
   -2.5, and it is 0 past nu_o = -3.3, where the G1 fit rounds to 1: then I = 0, on a CPU as
   on a GPU), Lambda_i' = pf_beckmann_light_lambda (a light below the mean plane lights the
   facets facing it). Once per pixel, without branches (one select), whatever m: the variances
   along wo and wi from the sum's second moments, no slope-statistics struct. Every sum is
   divided by sum amp first (ia), so no intermediate is the subnormal product of amp and a
   small area (a GPU flushes those to 0; a sum amp below PF_REAL_MIN is empty).
   0 when either direction is on or below the macrosurface, the sum is empty or no facet faces
   the view; finite and >= 0 for finite inputs (saturated at PF_REAL_MAX). */
PF_DEF pf_real pf_vmf_sum_specular(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi, pf_real f0)
{
    /* 1 / sum amp; 0 for a sum amp below PF_REAL_MIN (subnormal, 0, negative, NaN: empty, D' = 0) */
    pf_real ia = s.amp >= PF_REAL_MIN ? PF_R(1.0) / s.amp : PF_R(0.0), nia = -ia;
    /* minus the mean slope projected on w.xy (np), and twice the variance along w:
       -2 (np^2 - E[(w.xy . x)^2]) from the sum's raw second moments (written with -1/amp so
       that every step is one multiply or fused multiply-add, no negation) */
    pf_real exy2 = s.exy + s.exy;
    pf_real np_o = (s.ex * wo.x + s.ey * wo.y) * nia, np_i = (s.ex * wi.x + s.ey * wi.y) * nia;
    pf_real e_o = wo.x * (wo.x * s.exx + wo.y * exy2) + wo.y * (wo.y * s.eyy);
    pf_real e_i = wi.x * (wi.x * s.exx + wi.y * exy2) + wi.y * (wi.y * s.eyy);
    pf_real area_o = wo.z + np_o, area_i = wi.z + np_i;
    pf_real rs_o = pfi_vmf_rsqrt(pf_clamp_nan_lo((np_o * np_o + e_o * nia) * PF_R(-2.0), PF_REAL_MIN, PF_R(0.25) * PF_REAL_MAX));
    pf_real rs_i = pfi_vmf_rsqrt(pf_clamp_nan_lo((np_i * np_i + e_i * nia) * PF_R(-2.0), PF_REAL_MIN, PF_R(0.25) * PF_REAL_MAX));
    /* nu_o finite (|area_o| <= 3, rs_o <= 1/sqrt(PF_REAL_MIN)); pf_smith_nu_over_g1 takes any
       nu >= 0 (0 included) and is nu to rounding past 3.3 (float) / 2 (double), so that P_o is
       0 there with no floor on nu_o */
    pf_real nu_o = area_o * rs_o;
    pf_real front = (pf_smith_nu_over_g1(PF_FABS(nu_o)) - pf_max(-nu_o, PF_R(0.0))) / rs_o;
    /* G / (4 A_o): the 1/4 of the BRDF as the division's numerator */
    pf_real g = PF_R(0.25) / (front + pf_max(area_o, PF_R(0.0)) * pf_beckmann_light_lambda(area_i * rs_i, rs_i, wi.z));
    /* Schlick with cos = h.wi = sqrt((1 + wo.wi) / 2) */
    pf_real t = PF_R(1.0) - PF_SQRT(pf_saturate(PF_R(0.5) + PF_R(0.5) * pf_vec3_dot(wo, wi)));
    pf_real v = pf_min((s.ndf * ia) * g * (f0 + (PF_R(1.0) - f0) * ((t * t) * (t * t) * t)), PF_REAL_MAX);
    /* one select for the conditions (both directions above the macrosurface, some facet facing
       the view); the values computed for the other case are discarded */
    return pf_min(pf_min(wo.z, wi.z), front) > PF_R(0.0) ? v : PF_R(0.0);
}

/* The sum with the base lobe's variance taken out of its second moments (sum amp base_var off
   E[x^2] and E[y^2]: every lobe added with base_var carries it once), i.e. the moments of the
   footprint's own slopes, for a G that leaves the base lobe's masking to
   pf_beckmann_base_masking (pf_vmf_sum_specular_base). ndf and the first moments unchanged;
   E[x^2] and E[y^2] floored at 0 (where base_var dominates the lobes' own variances, the
   difference is the sum's rounding and can come out below 0). */
PF_DEF pf_vmf_sum pf_vmf_sum_without_base(pf_vmf_sum s, pf_real base_var)
{
    pf_real b = pf_max(base_var, PF_R(0.0)) * s.amp;
    s.exx = pf_max(s.exx - b, PF_R(0.0));
    s.eyy = pf_max(s.eyy - b, PF_R(0.0));
    return s;
}

/* pf_vmf_sum_specular with the two scales' visibility kept apart, as pf_leadr_specular_base
   (pf_beckmann.h) for one Gaussian: Smith's G of the mixture's own slopes
   (pf_vmf_sum_without_base) times the base lobe's masking-shadowing at the reflecting facets,
   pf_beckmann_base_masking of the mixture's statistics with base_var (pf_vmf_sum_stats). s
   summed with that base_var (pf_vmf_sum_add or pf_vmf_sum_add_texel). G of s itself would count
   the base lobe's masking twice (at a one-texel footprint the factor squared). For grazing
   views; pf_beckmann_base_masking's 16 G1 pairs once per pixel. */
PF_DEF pf_real pf_vmf_sum_specular_base(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi, pf_real base_var, pf_real f0)
{
    pf_real v = pf_vmf_sum_specular(pf_vmf_sum_without_base(s, base_var), wo, wi, f0);
    return v > PF_R(0.0) ? v * pf_beckmann_base_masking(wo, wi, pf_vmf_sum_stats(s), base_var) : PF_R(0.0);
}

/* The same with the mixture's exact Smith G (pf_vmf_sum_g2_mixture; needs
   pf_vmf_sum_add_masking for every lobe). */
PF_DEF pf_real pf_vmf_sum_specular_mixture(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi, pf_real f0)
{
    return pfi_vmf_sum_specular_mix(s, wo, wi, f0);
}

/* ================================================================ scaling function: shader side
   (Wu et al. 2019 eqs. 12-14, sec. 6; the CPU construction of T and S is pf_vmf_scale.h's). The filtered specular f of a footprint is multiplied by
   T(x) S(wi, wo): T one value per patch (a 2D texture), S a table over
   (theta_i, theta_o, phi_d) of nt x nt x np NODES (a 3D texture): theta_k = k theta_max /
   (nt - 1), phi_d,k = k pi / (np - 1) (phi_d the azimuth between wi and wo), so that the
   mirror configurations (theta_i = theta_o, phi_d = pi) and the normal are nodes; linear
   between nodes, clamped beyond theta_max. Index (k_ti * nt + k_to) * np + k_pd.
   Shader use (no sampler needed; with a GL_LINEAR, CLAMP_TO_EDGE 3D texture, sample it at
   (pos + 0.5) / n per axis instead):
     pf_vec3 c = pf_vmf_scale_coords(wo, wi, theta_max);
     pf_real pi = pf_vmf_scale_texel_pos(c.x, nt), po = ...(c.y, nt), pd = ...(c.z, np);
     i0 = floor(pos), i1 = min(i0 + 1, n - 1), frac = pos - i0  -- 8 fetches of S
     pf_real S = pf_vmf_scale_trilinear(s000, s100, s010, s110, s001, s101, s011, s111, frac);
     I = pf_vmf_scale_apply(T, S, pf_vmf_sum_specular(...));  */

/* x clamped to [0, 1], NaN to 0 (whatever pf_clamp's build does with NaN) */
PF_DEF pf_real pfi_vmf_unit(pf_real x) { return x > PF_R(0.0) ? (x < PF_R(1.0) ? x : PF_R(1.0)) : PF_R(0.0); }

/* Normalized table coordinates of (wo, wi): (theta_i / theta_max, theta_o / theta_max,
   phi_d / pi), each clamped to [0, 1]; node k of an n-node axis is at k / (n - 1). phi_d is 0
   when either direction is along the normal.
   theta_max <= 0 or NaN reads as pi/2. */
PF_DEF pf_vec3 pf_vmf_scale_coords(pf_vec3 wo, pf_vec3 wi, pf_real theta_max)
{
    pf_real tm = theta_max > PF_R(0.0) ? theta_max : PF_R(0.5) * PF_PI;
    pf_real ro = PF_SQRT(wo.x * wo.x + wo.y * wo.y), ri = PF_SQRT(wi.x * wi.x + wi.y * wi.y);
    pf_real to = PF_ATAN2(ro, wo.z), ti = PF_ATAN2(ri, wi.z), pd = PF_R(0.0);
    if (ro > PF_R(0.0) && ri > PF_R(0.0))
        pd = PF_ATAN2(PF_FABS(wo.x * wi.y - wo.y * wi.x), wo.x * wi.x + wo.y * wi.y);
    return pf_vec3_make(pfi_vmf_unit(ti / tm), pfi_vmf_unit(to / tm), pfi_vmf_unit(pd * PF_INV_PI));
}

/* The continuous node position of a normalized coordinate u on an n-node axis: u (n - 1)
   clamped to [0, n - 1] (node k's value sits at k; 0 for n <= 1). */
PF_DEF pf_real pf_vmf_scale_texel_pos(pf_real u, int n)
{
    pf_real hi = n > 1 ? PF_R(n - 1) : PF_R(0.0);
    return pfi_vmf_unit(u) * hi;
}

PF_DEF pf_real pfi_vmf_lerp(pf_real a, pf_real b, pf_real t) { return a + (b - a) * t; }

/* Trilinear blend of the 8 fetched cells (s_abc: a along theta_i, b theta_o, c phi_d; 0 the
   lower cell, 1 the upper) with fractions f in [0, 1]^3. */
PF_DEF pf_real pf_vmf_scale_trilinear(pf_real s000, pf_real s100, pf_real s010, pf_real s110, pf_real s001,
                                      pf_real s101, pf_real s011, pf_real s111, pf_vec3 f)
{
    pf_real a0 = pfi_vmf_lerp(pfi_vmf_lerp(s000, s100, f.x), pfi_vmf_lerp(s010, s110, f.x), f.y);
    pf_real a1 = pfi_vmf_lerp(pfi_vmf_lerp(s001, s101, f.x), pfi_vmf_lerp(s011, s111, f.x), f.y);
    return pfi_vmf_lerp(a0, a1, f.z);
}

/* The scaled BRDF T S f (Wu et al. 2019 eqs. 13-14); a negative or NaN product gives 0, an
   overflow PF_REAL_MAX. */
PF_DEF pf_real pf_vmf_scale_apply(pf_real t, pf_real s, pf_real f)
{
    pf_real v = t * s * f;
    return v > PF_R(0.0) ? (v < PF_REAL_MAX ? v : PF_REAL_MAX) : PF_R(0.0);
}

/* The multi-lobe specular of Wu et al. 2019 eq. 5 as written, with NO masking-shadowing
   (G = 1): F D' / (4 A_o); the denominator of R when the scaling function is to carry all of
   the masking. 0 on or below the macrosurface or mesosurface, or for an empty sum. */
PF_DEF pf_real pf_vmf_sum_specular_unmasked(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi, pf_real f0)
{
    pf_real area_o;
    if (!(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0)) || !(s.amp > PF_R(0.0))) return PF_R(0.0);
    area_o = pfi_vmf_sum_area(s, wo);
    if (!(area_o > PF_R(0.0)) || !(pfi_vmf_sum_area(s, wi) > PF_R(0.0))) return PF_R(0.0);
    return pf_fresnel_schlick(f0, pf_vec3_dot(pfi_vmf_half(wo, wi), wi)) * s.ndf / (PF_R(4.0) * area_o);
}

/* The base BRDF of one facet of slope (sx, sy): F(h.wi) D(h) G2 / 4 of a Beckmann lobe of slope
   variance base_var about the slope (LEADR eqs. 10, 13, 16; h = (wo + wi)/|wo + wi|, G2 the
   lobe's own Smith term 1/(1 + Lambda(wo) + Lambda(wi))), radiance toward wo per unit
   radiance from wi with the light cosine included (as pf_vmf_sum_specular); 0 when a
   direction is on or below the macrosurface or the facet, and when the half vector's slope
   lies more than sqrt(80 base_var) from the facet's (D below 4e-18 of its peak). The facet
   term of the scaling function's effective BRDF (pf_vmf_scale.h, Wu et al. 2019 eq. 6). */
PF_DEF pf_real pf_vmf_facet_specular(pf_real sx, pf_real sy, pf_real base_var, pf_vec3 wo, pf_vec3 wi, pf_real f0)
{
    pf_slope_stats st = pf_slope_stats_make(sx, sy, base_var, base_var, PF_R(0.0));
    pf_real ao = wo.z - sx * wo.x - sy * wo.y, ai = wi.z - sx * wi.x - sy * wi.y, lo, li;
    pf_vec3 hv;
    if (!(ao > PF_R(0.0)) || !(ai > PF_R(0.0)) || !(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0))) return PF_R(0.0);
    hv = pfi_vmf_half(wo, wi);
    {
        /* the lobe's exponent first: past 40 (D below 4e-18 of its peak) the facet adds nothing
           the sum can hold, and the two Lambdas (erfc) are skipped: most facets of a patch are
           that far from a narrow lobe's half vector */
        pf_real ex = -hv.x / pf_max(hv.z, PF_R(1.0e-6)) - sx, ey = -hv.y / pf_max(hv.z, PF_R(1.0e-6)) - sy;
        if (ex * ex + ey * ey > PF_R(80.0) * base_var) return PF_R(0.0);
    }
    lo = pf_vmf_lambda(pfi_vmf_excess_stats(PF_R(1.0), st, wo), ao);
    li = pf_vmf_lambda(pfi_vmf_excess_stats(PF_R(1.0), st, wi), ai);
    return pf_fresnel_schlick(f0, pf_vec3_dot(hv, wi)) * pfi_vmf_ndf_stats(PF_R(1.0), st, hv) /
           (PF_R(4.0) * (PF_R(1.0) + lo + li));
}

#endif /* PF_VMF_H */

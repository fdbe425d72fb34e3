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

   USAGE
     pf_vmf_sum s = pf_vmf_sum_zero();
     for (k = 0; k < 4; ++k) {                      -- m = 4 RGBA fetches of the lobe pyramid
         vec4 t = texel k;                           -- (mu.x, mu.y, kappa, amp)
         s = pf_vmf_sum_add(s, pf_vmf_lobe_make(t.w, t.x, t.y, t.z), wo, wi, sigma_b * sigma_b);
     }
     pf_real I = pf_vmf_sum_specular(s, wo, wi, f0);
     CPU: pf_vmf_fit_normals(normals, NULL, n, 4, 24, &mixture);       -- EM, caller's buffers
          pf_vmf_pyramid_from_normals(normals, NULL, w, h, 4, 24, pyr);   (see CPU ONLY below)

   FUNCTIONS
     lobes       pf_vmf_normalization, pf_vmf_mean_cosine, pf_vmf_tangent_variance,
                 pf_vmf_kappa_from_tangent_variance, pf_vmf_lobe_eval,
                 pf_vmf_kappa_from_mean_length, pf_vmf_convolve_kappa, pf_vmf_kappa_from_sigma,
                 pf_vmf_lobe_slope_stats
     one lobe of a mixture
                 pf_vmf_lobe_make, pf_vmf_lobe_density, pf_vmf_lobe_ndf (vMF form),
                 pf_vmf_lobe_ndf_slope (slope form), pf_vmf_lobe_area, pf_vmf_lobe_excess,
                 pf_vmf_lambda
     BRDF        pf_vmf_sum_zero, pf_vmf_sum_add (slope form), pf_vmf_sum_add_vmf (vMF form),
                 pf_vmf_sum_add_masking, pf_vmf_sum_stats, pf_vmf_sum_g2 (one Gaussian),
                 pf_vmf_sum_g2_mixture, pf_vmf_sum_g1_mixture (exact mixture Smith),
                 pf_vmf_sum_specular, pf_vmf_sum_specular_mixture, pf_vmf_sum_specular_unmasked
     scaling     pf_vmf_scale_coords, pf_vmf_scale_texel_pos, pf_vmf_scale_trilinear,
                 pf_vmf_scale_apply (T S f of Wu et al. 2019 eqs. 13-14, shader side)
     CPU only    pf_vmf_fit_normals, pf_vmf_pyramid_level_count, pf_vmf_pyramid_level_offset,
                 pf_vmf_pyramid_texel_count, pf_vmf_pyramid_from_normals,
                 pf_vmf_mixture_from_texel (struct pf_vmf_mixture: the fit's lobes);
                 pf_vmf_downsample_slopes, pf_vmf_downsample_scratch_size (slope-preserving
                 downsampling of the height map, Wu et al. 2019 eqs. 9-10);
                 pf_vmf_effective_brdf, pf_vmf_scale_patch, pf_vmf_scale_factor,
                 pf_vmf_scale_t, pf_vmf_scale_lookup, pf_vmf_scale_sample_count, pf_vmf_scale_cell_count,
                 pf_vmf_scale_vis_bytes (scaling function, Wu et al. 2019 eqs. 6-8, 12-14, 21-24)

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
     0.10-0.18 and m = 16 within 0.09-0.14 (LEADR: 0.12-0.82), at 1.2-1.5x
     pf_leadr_specular's cost for m = 4 and 1.7-2.8x for m = 8, fetches included. Fit of a
     512 x 512 pyramid: 2.1-2.8 s CPU at m = 4, 3.8-9.4 s at m = 16.

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
#  include "pf_moments.h"
#endif

#define PF_VMF_MAX_LOBES 16
#define PF_VMF_KAPPA_MIN PF_R(1.0e-4)
#define PF_VMF_KAPPA_MAX PF_R(1.0e5)
/* EM stops when the mean log-likelihood per unit weight changes by less than this (relative,
   at least absolute 1); CPU only */
#ifndef PF_VMF_EM_TOLERANCE
#  define PF_VMF_EM_TOLERANCE PF_R(1.0e-6)
#endif

/* Cap on the exponents the module passes to PF_EXP: exp(-80) = 1.8e-35 is still a normal float,
   so exp never underflows (libm's underflow path, which sets errno, made a far lobe cost 10x a
   near one in the bench), and a value this far down the tail is 0 to the shading. */
#define PFI_VMF_EXP_CAP PF_R(80.0)

/* ---------------------------------------------------------------- one lobe */
PF_DEF pf_real pfi_vmf_kappa(pf_real kappa)
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
    pf_real k = pfi_vmf_kappa(kappa);
    return k * (PF_R(0.5) * PF_INV_PI) / pfi_vmf_one_minus_exp_neg(PF_R(2.0) * k);
}

/* Mean cosine A3(kappa) = E[mu.w] = coth kappa - 1/kappa (the mean resultant length of a vMF).
   Series below the threshold (the difference cancels there), closed form above. */
PF_DEF pf_real pf_vmf_mean_cosine(pf_real kappa)
{
    pf_real k = pfi_vmf_kappa(kappa), k2, e;
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
    pf_real k = pfi_vmf_kappa(kappa);
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
    return pfi_vmf_kappa(PF_EXP(PF_R(0.5) * (lo + hi)));
}

/* g(w; kappa, mu) = C(kappa) exp(-kappa |w - mu|^2 / 2) for unit w and mu (= exp(kappa (mu.w
   - 1)), no cancellation near the peak, no overflow at large kappa). Per unit solid angle. */
PF_DEF pf_real pf_vmf_lobe_eval(pf_vec3 mu, pf_real kappa, pf_vec3 w)
{
    pf_real k = pfi_vmf_kappa(kappa);
    pf_vec3 d = pf_vec3_sub(w, mu);
    pf_real q = pf_min(PF_R(0.5) * k * pf_vec3_dot(d, d), PFI_VMF_EXP_CAP);
    return pf_vmf_normalization(k) * PF_EXP(-q);
}

/* Banerjee et al. 2005: kappa from the mean resultant length r = |E[w]| of a sample,
   kappa ~ r (3 - r^2) / (1 - r^2), clamped to [PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX]; r >= 1
   gives PF_VMF_KAPPA_MAX. (The fit uses the cancellation-free 1 - r^2 it accumulates.) */
PF_DEF pf_real pf_vmf_kappa_from_mean_length(pf_real r)
{
    pf_real rr = pfi_clamp_nan_lo(r, PF_R(0.0), PF_R(1.0)); /* NaN -> 0 (pf_clamp keeps NaN in C) */
    pf_real one_minus = (PF_R(1.0) - rr) * (PF_R(1.0) + rr);
    if (!(one_minus * PF_VMF_KAPPA_MAX > rr * (PF_R(3.0) - rr * rr))) return PF_VMF_KAPPA_MAX;
    return pfi_vmf_kappa(rr * (PF_R(3.0) - rr * rr) / one_minus);
}

/* The one-lobe approximation of a vMF of kappa convolved with a vMF base lobe of kappa_b
   (Wu et al. 2019 eq. 5's integral for one lobe): kappa kappa_b / (kappa + kappa_b), the
   small-angle rule 1/kappa' = 1/kappa + 1/kappa_b (angular variances add). */
PF_DEF pf_real pf_vmf_convolve_kappa(pf_real kappa, pf_real kappa_b)
{
    pf_real a = pfi_vmf_kappa(kappa), b = pfi_vmf_kappa(kappa_b);
    return pfi_vmf_kappa(a * (b / (a + b)));
}

/* kappa of the vMF lobe matching a Beckmann lobe of slope deviation sigma per axis (Beckmann
   roughness alpha = sqrt(2) sigma) at its peak: exp(-tan^2 t / (2 sigma^2)) ~ exp(-t^2 /
   (2 sigma^2)) and exp(kappa (cos t - 1)) ~ exp(-kappa t^2 / 2), so kappa = 1/sigma^2. */
PF_DEF pf_real pf_vmf_kappa_from_sigma(pf_real sigma)
{
    pf_real s2 = sigma * sigma;
    if (!(s2 * PF_VMF_KAPPA_MAX > PF_R(1.0))) return PF_VMF_KAPPA_MAX;
    return pfi_vmf_kappa(PF_R(1.0) / s2);
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
   read as 0, a negative or NaN amplitude as 0, kappa clamped (pfi_vmf_kappa). */
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
    l.kappa = pfi_vmf_kappa(kappa);
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
   exponent is capped at PFI_VMF_EXP_CAP (no libm underflow path) and its determinant floored
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
    return amp * PF_EXP(-pf_min(PF_R(0.5) * q / det, PFI_VMF_EXP_CAP)) * (PF_R(0.5) * PF_INV_PI) / PF_SQRT(det) *
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

/* Adds one lobe, slope form (see above). */
PF_DEF pf_vmf_sum pf_vmf_sum_add(pf_vmf_sum s, pf_vmf_lobe l, pf_vec3 wo, pf_vec3 wi, pf_real base_var)
{
    pf_slope_stats st = pf_vmf_lobe_slope_stats(l.mu, l.kappa, base_var);
    s.ndf += pfi_vmf_ndf_stats(l.amp, st, pfi_vmf_half(wo, wi));
    return pfi_vmf_sum_moments(s, l.amp, st);
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

/* G / A_o as pf_leadr_specular has it (see the comment above pfi_leadr_specular in
   pf_beckmann.h): 1 / (P_o + max(A_o, 0) Lambda_i), P_o the projected area toward wo of the
   facets that face it, so that a view below the mesosurface (A_o <= 0) but above the
   macrosurface sees those facets instead of 0. Times sum amp:
     one Gaussian (pf_vmf_sum_g2's statistics): P_o = pfi_beckmann_facing_area, amp A_o =
       area_o, Lambda_i = pf_beckmann_lambda;
     mixture: each lobe's area + excess is amp E[(a - Y)+] = its facing area (>= 0), so
       amp P_o = area_o + excess_o (= area_o (1 + Lambda_o) above the mesosurface) and
       Lambda_i = pf_vmf_lambda. Below the mesosurface the sum cancels (excess_o ~ -area_o),
       so its relative error grows as P_o / |area_o| shrinks.
   Lambda_i as pf_leadr_specular has it: Smith's above the mesosurface; on or below it (but
   above the macrosurface) the macrosurface's share of the light, max(P_i, wi.z) / wi.z - 1
   (pfi_beckmann_light_lambda in pf_beckmann.h), so that such a light lights the facets facing
   it instead of giving 0: one Gaussian, P_i of the sum's statistics with A_i counted as 0
   (pfi_beckmann_light_lambda_stats); mixture, P_i = (area_i + excess_i) / amp, the mixture's
   own facing area. The value jumps at area_i = 0 (Smith's 0 just above). */
PF_DEF pf_real pfi_vmf_sum_specular(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi, pf_real f0, int mixture_smith)
{
    pf_real area_o, area_i, den, f;
    if (!(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0)) || !(s.amp > PF_R(0.0))) return PF_R(0.0);
    area_o = pfi_vmf_sum_area(s, wo);
    area_i = pfi_vmf_sum_area(s, wi);
    if (mixture_smith != 0) {
        /* Smith's Lambda_i above the mean plane; below it max(P_i, wi.z) / wi.z - 1 with the
           mixture's own facing area P_i = (area_i + excess_i) / amp */
        pf_real wz = wi.z * s.amp;
        den = area_o + s.excess_o +
              pf_max(area_o, PF_R(0.0)) *
                  (area_i > PF_R(0.0) ? pf_vmf_lambda(s.excess_i, area_i)
                                      : pf_max(area_i + s.excess_i, wz) / wz - PF_R(1.0));
    } else {
        pf_slope_stats st = pf_vmf_sum_stats(s);
        den = s.amp * (pfi_beckmann_facing_area(wo, st) +
                       pf_max(area_o / s.amp, PF_R(0.0)) *
                           pfi_beckmann_light_lambda_stats(wi, st));
    }
    if (!(den > PF_R(0.0))) return PF_R(0.0); /* no facet faces the view (in pf_real) */
    f = pf_fresnel_schlick(f0, pf_vec3_dot(pfi_vmf_half(wo, wi), wi));
    /* (ndf / amp) (G / A_o) / 4 with G / A_o = amp / den */
    return f * s.ndf / (PF_R(4.0) * den);
}

/* The multi-lobe specular radiance factor I = F D' G / (4 A_o) of the summed mixture with G
   of the mixture as one Gaussian (pf_vmf_sum_g2). 0 when either direction is on or below
   the macrosurface or the sum is empty; a view below the mesosurface sees the facets facing
   it, a light below it lights them (pfi_vmf_sum_specular). Finite and >= 0 for
   finite inputs. */
PF_DEF pf_real pf_vmf_sum_specular(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi, pf_real f0)
{
    return pfi_vmf_sum_specular(s, wo, wi, f0, 0);
}

/* The same with the mixture's exact Smith G (pf_vmf_sum_g2_mixture; needs
   pf_vmf_sum_add_masking for every lobe). */
PF_DEF pf_real pf_vmf_sum_specular_mixture(pf_vmf_sum s, pf_vec3 wo, pf_vec3 wi, pf_real f0)
{
    return pfi_vmf_sum_specular(s, wo, wi, f0, 1);
}

/* ================================================================ scaling function: shader side
   (Wu et al. 2019 eqs. 12-14, sec. 6; the CPU construction is the block "CPU only: SCALING
   FUNCTION" below). The filtered specular f of a footprint is multiplied by
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

#ifndef PF_GLSL
/* ================================================================ CPU only: mixtures
   The fit's output: up to PF_VMF_MAX_LOBES lobes (amplitudes summing to 1). Host code (a
   struct with arrays, which the portability generator does not synthesise); shade it lobe by
   lobe with pf_vmf_sum_add, as a shader does with the pyramid's texels. */
typedef struct pf_vmf_mixture {
    pf_vmf_lobe lobe[PF_VMF_MAX_LOBES];
    int count;
} pf_vmf_mixture;

/* ================================================================ CPU only: fitting
   Spherical EM (Banerjee et al. 2005; Han et al. 2007 sec. 4) of m vMF lobes to weighted
   unit normals, on caller-owned buffers, no allocation: each iteration is ONE pass that
   computes every normal's responsibilities on the fly and accumulates, per lobe, W = sum w r,
   D = sum w r (x - mu_old) and S = sum w r |x - mu_old|^2 (relative to the previous axis, so
   that the concentration needs no 1 - |R|/W cancellation: W^2 (1 - rbar^2) = W S - |D|^2
   exactly, by the parallel-axis rule). Then a = W / sum W, mu = (W mu_old + D) normalized,
   kappa = rbar (3 - rbar^2) / (1 - rbar^2) (Banerjee et al.'s approximation), clamped.
   SEEDING (deterministic): lobe 0 on the weighted mean normal, each next lobe on the normal
   farthest (largest 1 - mu.x) from every lobe so far (first such in memory order); seeding
   stops early when every normal lies within 1e-7 (1 - cos) of a lobe, so the fit may return
   fewer lobes than asked. Initial kappa from the whole set's resultant, at least 1.
   ITERATIONS: at most `iterations` EM steps; it stops earlier when the mean log-likelihood
   changes by less than 1e-6. Lobes whose weight share falls below 1e-6 are dropped.
   DEGENERATE INPUT: normals with a NaN or infinite component, zero length, or a weight that is
   NaN, infinite or <= 0 are skipped; weights are divided by the largest usable one first (no
   sum can overflow). No usable normal: PF_ERR_ARG, and *out is set to one flat
   lobe (a = 1, mu = +z, kappa = PF_VMF_KAPPA_MAX), so it is always finite.
   Errors: PF_ERR_ARG for NULL normals or out, count < 1, lobes outside [1, PF_VMF_MAX_LOBES = 16], iterations < 0;
   PF_ERR_SIZE when count * 3 exceeds PF_MAX_REALS. */
PF_CPU_DEF int pfi_vmf_read(const pf_real *normals, const pf_real *weights, long long i, pf_vec3 *x, pf_real *w)
{
    pf_real a = normals[3 * i], b = normals[3 * i + 1], c = normals[3 * i + 2], l2, wt;
    wt = weights ? weights[i] : PF_R(1.0);
    if (!(wt > PF_R(0.0)) || !(wt < PF_REAL_MAX)) return 0;
    if (!(PF_FABS(a) < PF_R(1.0e18)) || !(PF_FABS(b) < PF_R(1.0e18)) || !(PF_FABS(c) < PF_R(1.0e18))) return 0;
    l2 = a * a + b * b + c * c;
    if (!(l2 > PF_R(1.0e-30))) return 0;
    l2 = PF_R(1.0) / PF_SQRT(l2);
    *x = pf_vec3_make(a * l2, b * l2, c * l2);
    *w = wt;
    return 1;
}

/* the block walker: rows of bw normals, `row` normals apart, bh rows (a pyramid footprint) */
#define PFI_VMF_FOREACH(...)                                                                    \
    for (yy = 0; yy < bh; ++yy)                                                                \
        for (xx = 0; xx < bw; ++xx) {                                                          \
            long long id = yy * row + xx;                                                      \
            if (!pfi_vmf_read(normals, weights, id, &x, &wt)) continue;                        \
            wt = wt * wscale;                                                                  \
            __VA_ARGS__                                                                        \
        }

PF_CPU_DEF pf_vmf_mixture pfi_vmf_mixture_empty(void)
{
    pf_vmf_mixture m;
    int i;
    for (i = 0; i < PF_VMF_MAX_LOBES; ++i) m.lobe[i] = pf_vmf_lobe_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(1.0));
    m.count = 0;
    return m;
}

PF_CPU_DEF pf_vmf_mixture pfi_vmf_flat(void)
{
    pf_vmf_mixture m = pfi_vmf_mixture_empty();
    m.lobe[0] = pf_vmf_lobe_make(PF_R(1.0), PF_R(0.0), PF_R(0.0), PF_VMF_KAPPA_MAX);
    m.count = 1;
    return m;
}

PF_CPU_DEF int pfi_vmf_fit_block(const pf_real *normals, const pf_real *weights, long long row, long long bw,
                                 long long bh, int lobes, int iterations, pf_vmf_mixture *out)
{
    pf_vmf_mixture m = pfi_vmf_mixture_empty();
    pf_vec3 x, sum = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0));
    pf_real wt, wsum = PF_R(0.0), logc[PF_VMF_MAX_LOBES], prev_ll = PF_R(0.0), wscale = PF_R(1.0), wmax = PF_R(0.0);
    long long xx, yy;
    int k, it, n;
    /* weights divided by the largest usable one, so that no sum of the fit can overflow */
    PFI_VMF_FOREACH(wmax = pf_max(wmax, wt);)
    if (!(wmax > PF_R(0.0))) {
        *out = pfi_vmf_flat();
        return PF_ERR_ARG;
    }
    wscale = PF_R(1.0) / wmax;
    PFI_VMF_FOREACH(sum = pf_vec3_add(sum, pf_vec3_scale(x, wt)); wsum += wt;)
    if (!(wsum > PF_R(0.0)) || !(wsum < PF_REAL_MAX)) {
        *out = pfi_vmf_flat();
        return PF_ERR_ARG;
    }
    /* seeding */
    {
        pf_real len = pf_vec3_length(sum), kappa0;
        pf_vec3 mu0 = len > PF_R(0.0) ? pf_vec3_scale(sum, PF_R(1.0) / len) : pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
        kappa0 = pf_max(pf_vmf_kappa_from_mean_length(len / wsum), PF_R(1.0));
        m.lobe[0].mu = mu0;
        m.lobe[0].kappa = kappa0;
        m.count = 1;
        for (k = 1; k < lobes; ++k) {
            pf_real best = PF_R(1.0e-7);
            pf_vec3 pick = mu0;
            int found = 0, j;
            PFI_VMF_FOREACH({
                pf_real dmin = PF_R(4.0);
                for (j = 0; j < m.count; ++j) {
                    pf_vec3 d = pf_vec3_sub(x, m.lobe[j].mu);
                    dmin = pf_min(dmin, PF_R(0.5) * pf_vec3_dot(d, d));
                }
                if (dmin > best) {
                    best = dmin;
                    pick = x;
                    found = 1;
                }
            })
            if (!found) break;
            m.lobe[m.count].mu = pick;
            m.lobe[m.count].kappa = kappa0;
            m.count++;
        }
        for (k = 0; k < m.count; ++k) m.lobe[k].amp = PF_R(1.0) / (pf_real)m.count;
    }
    /* EM */
    for (it = 0; it < iterations && m.count > 1; ++it) {
        pf_real W[PF_VMF_MAX_LOBES], S[PF_VMF_MAX_LOBES], ll = PF_R(0.0);
        pf_vec3 D[PF_VMF_MAX_LOBES];
        for (k = 0; k < m.count; ++k) {
            W[k] = S[k] = PF_R(0.0);
            D[k] = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0));
            logc[k] = PF_LOG(m.lobe[k].amp * pf_vmf_normalization(m.lobe[k].kappa));
        }
        PFI_VMF_FOREACH({
            pf_real lg[PF_VMF_MAX_LOBES], d2[PF_VMF_MAX_LOBES], top = -PF_REAL_MAX, tot = PF_R(0.0);
            pf_vec3 dv[PF_VMF_MAX_LOBES];
            for (k = 0; k < m.count; ++k) {
                dv[k] = pf_vec3_sub(x, m.lobe[k].mu);
                d2[k] = pf_vec3_dot(dv[k], dv[k]);
                lg[k] = logc[k] - PF_R(0.5) * m.lobe[k].kappa * d2[k];
                top = pf_max(top, lg[k]);
            }
            for (k = 0; k < m.count; ++k) {
                lg[k] = PF_EXP(pf_max(lg[k] - top, -PFI_VMF_EXP_CAP));
                tot += lg[k];
            }
            ll += wt * (top + PF_LOG(tot));
            for (k = 0; k < m.count; ++k) {
                pf_real r = wt * lg[k] / tot;
                W[k] += r;
                S[k] += r * d2[k];
                D[k] = pf_vec3_add(D[k], pf_vec3_scale(dv[k], r));
            }
        })
        /* M step; empty lobes dropped (compacted in order) */
        n = 0;
        for (k = 0; k < m.count; ++k) {
            pf_vec3 r;
            pf_real len, one_minus_r2, rbar;
            if (!(W[k] > PF_R(1.0e-6) * wsum)) continue;
            r = pf_vec3_add(pf_vec3_scale(m.lobe[k].mu, W[k]), D[k]);
            len = pf_vec3_length(r);
            if (!(len > PF_R(0.0))) continue;
            rbar = pf_min(len / W[k], PF_R(1.0));
            one_minus_r2 = pf_max((W[k] * S[k] - pf_vec3_dot(D[k], D[k])) / (W[k] * W[k]), PF_R(0.0));
            m.lobe[n].amp = W[k] / wsum;
            m.lobe[n].mu = pf_vec3_scale(r, PF_R(1.0) / len);
            m.lobe[n].kappa = one_minus_r2 * PF_VMF_KAPPA_MAX > rbar * (PF_R(3.0) - rbar * rbar)
                             ? pfi_vmf_kappa(rbar * (PF_R(3.0) - rbar * rbar) / one_minus_r2)
                             : PF_VMF_KAPPA_MAX;
            ++n;
        }
        m.count = n;
        for (k = n; k < PF_VMF_MAX_LOBES; ++k) m.lobe[k].amp = PF_R(0.0);
        ll = ll / wsum;
        if (it > 0 && PF_FABS(ll - prev_ll) <= PF_VMF_EM_TOLERANCE * pf_max(PF_R(1.0), PF_FABS(ll))) break;
        prev_ll = ll;
    }
    /* FINAL PASS, in slope space: the EM's responsibilities partition the normals; each lobe's
       stored axis and kappa are then matched to the responsibility-weighted slope mean s_k and
       slope variance (trace) of its share: mu = (-s_k, 1)/|.|, kappa such that
       pf_vmf_lobe_slope_stats' trace v (1/mu.z^4 + 1/mu.z^2) equals it. So the slope-form
       BRDF's lobes carry the footprint's slope moments (one lobe: LEADR's mean and the trace
       of its covariance); the spherical kappa of Banerjee's rule underestimates the slope
       spread of a Gaussian-slope footprint (tan against sin: 0.74 against 0.10 error on the
       bench's gaussian_fine kind at one lobe). Slopes of normals within 1e-3 of the horizon
       are read at mu.z = 1e-3. */
    {
        pf_real W[PF_VMF_MAX_LOBES], S2[PF_VMF_MAX_LOBES], SX[PF_VMF_MAX_LOBES], SY[PF_VMF_MAX_LOBES];
        for (k = 0; k < m.count; ++k) {
            W[k] = S2[k] = SX[k] = SY[k] = PF_R(0.0);
            logc[k] = PF_LOG(m.lobe[k].amp * pf_vmf_normalization(m.lobe[k].kappa));
        }
        PFI_VMF_FOREACH({
            pf_real lg[PF_VMF_MAX_LOBES], top = -PF_REAL_MAX, tot = PF_R(0.0);
            pf_real iz = PF_R(1.0) / pf_max(x.z, PF_R(1.0e-3)), sx = -x.x * iz, sy = -x.y * iz;
            for (k = 0; k < m.count; ++k) {
                pf_vec3 dv = pf_vec3_sub(x, m.lobe[k].mu);
                lg[k] = logc[k] - PF_R(0.5) * m.lobe[k].kappa * pf_vec3_dot(dv, dv);
                top = pf_max(top, lg[k]);
            }
            for (k = 0; k < m.count; ++k) {
                lg[k] = PF_EXP(pf_max(lg[k] - top, -PFI_VMF_EXP_CAP));
                tot += lg[k];
            }
            for (k = 0; k < m.count; ++k) {
                pf_real r = wt * lg[k] / tot;
                W[k] += r;
                SX[k] += r * sx;
                SY[k] += r * sy;
                S2[k] += r * (sx * sx + sy * sy);
            }
        })
        n = 0;
        for (k = 0; k < m.count; ++k) {
            pf_real mx, my, tr, iz2;
            if (!(W[k] > PF_R(1.0e-6) * wsum)) continue;
            mx = SX[k] / W[k];
            my = SY[k] / W[k];
            tr = pf_max(S2[k] / W[k] - mx * mx - my * my, PF_R(0.0));
            iz2 = PF_R(1.0) + mx * mx + my * my;
            m.lobe[n].amp = W[k] / wsum;
            m.lobe[n].mu = pf_vec3_scale(pf_vec3_make(-mx, -my, PF_R(1.0)), PF_R(1.0) / PF_SQRT(iz2));
            m.lobe[n].kappa = pf_vmf_kappa_from_tangent_variance(tr / (iz2 * iz2 + iz2));
            ++n;
        }
        m.count = n;
        for (k = n; k < PF_VMF_MAX_LOBES; ++k) m.lobe[k].amp = PF_R(0.0);
        if (n == 0) {
            *out = pfi_vmf_flat();
            return PF_ERR_ARG;
        }
    }
    /* lobe axes on the upper hemisphere (the packed form's convention) */
    for (k = 0; k < m.count; ++k)
        if (m.lobe[k].mu.z < PF_R(0.0)) {
            pf_vec3 a = m.lobe[k].mu;
            pf_real l = PF_SQRT(a.x * a.x + a.y * a.y);
            m.lobe[k].mu = l > PF_R(0.0) ? pf_vec3_make(a.x / l, a.y / l, PF_R(0.0)) : pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
        }
    *out = m;
    return PF_OK;
}

/* Fits up to `lobes` vMF lobes to count unit normals (3 pf_reals each; non-unit ones are
   normalized) with optional weights (NULL: all 1). See the block comment above. */
PF_CPU_DEF int pf_vmf_fit_normals(const pf_real *normals, const pf_real *weights, long long count, int lobes,
                                  int iterations, pf_vmf_mixture *out)
{
    if (!out) return PF_ERR_ARG;
    if (!normals || count < 1 || lobes < 1 || lobes > PF_VMF_MAX_LOBES || iterations < 0) {
        *out = pfi_vmf_flat();
        return PF_ERR_ARG;
    }
    if (pf_size_mul(count, 3) < 0) {
        *out = pfi_vmf_flat();
        return PF_ERR_SIZE;
    }
    return pfi_vmf_fit_block(normals, weights, count, count, 1, lobes, iterations, out);
}

/* ================================================================ CPU only: SCALING FUNCTION
   (Wu et al. 2019 eqs. 6-8, 12-14 and sec. 6 eqs. 21-24; interreflections, sec. 5,
   are not modelled).
   EFFECTIVE BRDF (eqs. 6-8, single bounce) of an n x n patch of a periodic height map
   heights[y w + x] (world units, `texel` world units between nodes), texels (x0 + i, y0 + j)
   wrapping: every texel is a facet of its central-difference slope s_t (as
   tests/pf_microsurface.h and pf_slope_pyramid_from_heights level 0) shaded by the base BRDF,
   a Beckmann lobe of slope deviation base_sigma around s_t with Schlick Fresnel and the lobe's
   own Smith G2 (LEADR eqs. 10, 13, 16-17: the bench's base BRDF), kept when the texel's node
   sees both wo and wi:
       f_eff = sum_t V_t(wo) V_t(wi) F D_t(h) G2_t / 4  /  sum_t a_t(wo),   a_t(w) = w.z - s_t.w.xy
   (eq. 8: the patch's projected area toward wo is that of its mean plane; radiance toward wo
   per unit radiance from wi, light cosine included, like pf_vmf_sum_specular).
   VISIBILITY (pfi_vmf_visible): the ray from the texel's node toward w is marched cell by cell
   over the BILINEAR surface through the nodes; within a cell the surface minus the ray is a
   quadratic of the horizontal distance, so the test is exact (both ends and the vertex), no
   step size. The first half texel is skipped (the facet stands for its half-texel
   neighbourhood; the twisted bilinear patches around the node would otherwise shadow rays
   that clear the facet). Only occluders INSIDE the patch count: the ray is free where its
   horizontal path leaves [x0 - 1/2, x0 + n - 1/2] x [y0 - 1/2, y0 + n - 1/2] (the footprint
   is all a filtered model of it can know; along an axis where n equals the map's side the
   periodic map is unbounded) or rises above the highest node it can meet; a texel with
   m.w <= 0 is not visible. This is the in-footprint reference of tests/pf_microsurface.h
   (pfm_visible_box), reimplemented here in pf_real on caller buffers: the test header keeps
   its own double-precision march as the independent oracle (it must not call include/), and
   tests/test_vmf.c checks the two agree.
   RATIO AND FACTORIZATION (eqs. 12, 14, 21-24): R(x, wi, wo) = f_eff / f_lobes with f_lobes the
   multi-lobe BRDF of eq. 5 for the patch's fitted lobes (pf_vmf_fit_normals on the patch's
   normals, slope form pf_vmf_sum_add with base_var = base_sigma^2), masking per `masking`:
   PF_VMF_SCALE_UNMASKED (eq. 5 as written: R carries all the masking-shadowing),
   PF_VMF_SCALE_G_GAUSSIAN (pf_vmf_sum_specular), PF_VMF_SCALE_G_MIXTURE
   (pf_vmf_sum_specular_mixture). Samples per patch (pf_vmf_scale_patch): one direction set,
   the nt theta nodes times A = 2 (np - 1) azimuths a pi/(np - 1), and every (wo, wi) pair of
   it: phi_d falls on the np phi_d nodes exactly, each node gets A (ends) or 2 A (inner)
   samples per patch and theta pair, and the mirror pairs are among them (a narrow highlight
   is sampled at its peak). Sample order ((k_to A + a_o) nt + k_ti) A + a_i.
   T and S (pf_vmf_scale_factor): the rank-1 fit of eq. 21 minimizing the error IN BRDF UNITS,
   sum_{x, samples} (f_eff - T(x) S(cell) f_lobes)^2, by alternating least squares (T(x) =
   sum f_eff f_lobes S / sum (f_lobes S)^2 over the patch's samples, S likewise over the
   patches), then T scaled to mean 1 (Wu et al. sec. 7). Why not eqs. 22-24's plain means of
   R: where the narrow lobes put almost no energy R is a ratio of two tiny numbers (the paper
   adds an epsilon), and a plain mean weights those samples as much as the highlight; the fit
   in BRDF units weights them by their energy, and is still exact when R is separable (the
   plain means are exact then too). Cells or patches without energy get 1.
   REGULARIZATION: the samples are node directions, so a patch whose highlight falls between
   them, or a cell that only the lobes' far tails reach (where f_eff, whose facets skip the
   base lobe's tail, is exactly 0), is decided by a few tiny samples: unregularized, S had
   cells of exactly 0 at every level of the bench's maps (trilinear reads spread them onto the
   highlights) and T ranged 0.13-10.8 at 64-256 texels. Each T and S is therefore the
   least-squares value with a prior pulling it toward 1 whose weight is `shrink` times the
   average energy sum (S f_lobes)^2 of a patch (for T) or sum (T f_lobes)^2 of a cell (for S):
   well-sampled values keep their fit, poorly sampled ones stay near 1 (no scaling). */
#define PF_VMF_SCALE_UNMASKED 0
#define PF_VMF_SCALE_G_GAUSSIAN 1
#define PF_VMF_SCALE_G_MIXTURE 2
/* largest number of cells a march visits before it calls the ray occluded (a ray that rises
   less than the patch's height range over this many texels: within ~1e-4 rad of the horizon) */
#ifndef PF_VMF_MARCH_MAX_CELLS
#  define PF_VMF_MARCH_MAX_CELLS 65536
#endif

PF_CPU_DEF long long pfi_vmf_wrap(long long i, long long n)
{
    i %= n;
    return i < 0 ? i + n : i;
}

PF_CPU_DEF pf_real pfi_vmf_height(const pf_real *hm, int w, int h, long long x, long long y)
{
    return hm[pfi_vmf_wrap(y, h) * (long long)w + pfi_vmf_wrap(x, w)];
}

/* central-difference slope of node (x, y), wrapping */
PF_CPU_DEF void pfi_vmf_slope(const pf_real *hm, int w, int h, pf_real texel, long long x, long long y, pf_real *sx,
                              pf_real *sy)
{
    pf_real k = PF_R(0.5) / texel;
    *sx = k * (pfi_vmf_height(hm, w, h, x + 1, y) - pfi_vmf_height(hm, w, h, x - 1, y));
    *sy = k * (pfi_vmf_height(hm, w, h, x, y + 1) - pfi_vmf_height(hm, w, h, x, y - 1));
}

/* 1 when node (x, y) of the patch (x0, y0, n) sees w; top = the highest node of the patch
   and its one-node ring, world units. See VISIBILITY above. Heights are read in texel units. */
PF_CPU_DEF int pfi_vmf_visible(const pf_real *hm, int w, int h, pf_real texel, long long x, long long y, pf_vec3 d,
                               long long x0, long long y0, long long n, pf_real top)
{
    pf_real sx, sy, r, dx, dy, rise, h0, t = PF_R(0.0), tend = PF_REAL_MAX, tnx, tny, tdx, tdy, it = PF_R(1.0) / texel;
    long long ix, iy, ox, oy, cells;
    int stx, sty;
    if (!(d.z > PF_R(0.0))) return 0;
    pfi_vmf_slope(hm, w, h, texel, x, y, &sx, &sy);
    if (!(d.z - sx * d.x - sy * d.y > PF_R(0.0))) return 0;
    r = PF_SQRT(d.x * d.x + d.y * d.y);
    h0 = pfi_vmf_height(hm, w, h, x, y) * it;
    top = top * it;
    if (!(r > PF_R(0.0)) || h0 >= top) return 1;
    dx = d.x / r;
    dy = d.y / r;
    rise = d.z / r;
    if (PF_FABS(dx) < PF_R(1.0e-12)) dx = PF_R(0.0);
    if (PF_FABS(dy) < PF_R(1.0e-12)) dy = PF_R(0.0);
    ox = pfi_vmf_wrap(x - x0, w);
    oy = pfi_vmf_wrap(y - y0, h);
    /* the box's edges lie half a texel outside its first and last nodes */
    if (n < w) {
        if (dx > PF_R(0.0)) tend = pf_min(tend, ((pf_real)(n - ox) - PF_R(0.5)) / dx);
        if (dx < PF_R(0.0)) tend = pf_min(tend, ((pf_real)ox + PF_R(0.5)) / -dx);
    }
    if (n < h) {
        if (dy > PF_R(0.0)) tend = pf_min(tend, ((pf_real)(n - oy) - PF_R(0.5)) / dy);
        if (dy < PF_R(0.0)) tend = pf_min(tend, ((pf_real)oy + PF_R(0.5)) / -dy);
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
    for (cells = 0; cells < PF_VMF_MARCH_MAX_CELLS; ++cells) {
        pf_real tout = pf_min(tnx, tny), ta = pf_max(t, PF_R(0.5)), tb = pf_min(tout, tend);
        if (h0 + rise * t > top || t >= tend) return 1;
        if (tb > ta) {
            pf_real h00 = pfi_vmf_height(hm, w, h, x + ix, y + iy) * it, h10 = pfi_vmf_height(hm, w, h, x + ix + 1, y + iy) * it;
            pf_real h01 = pfi_vmf_height(hm, w, h, x + ix, y + iy + 1) * it;
            pf_real h11 = pfi_vmf_height(hm, w, h, x + ix + 1, y + iy + 1) * it;
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
    return 0;
}

/* the base BRDF of one facet of slope (sx, sy): F(h.wi) D(h) G2 / 4 of a Beckmann lobe of slope
   variance base_var about the slope (LEADR eqs. 10, 13, 16), 0 when a direction is on or below
   the facet */
PF_CPU_DEF pf_real pfi_vmf_base_term(pf_real sx, pf_real sy, pf_real base_var, pf_vec3 wo, pf_vec3 wi, pf_real f0)
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

/* argument and size checks shared by the scaling functions (no data read) */
PF_CPU_DEF int pfi_vmf_patch_sizes(const pf_real *hm, int w, int h, pf_real texel, long long n)
{
    if (!hm || n < 1 || w < 1 || h < 1 || !(texel > PF_R(0.0)) || !(texel < PF_REAL_MAX)) return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || pf_size_mul(w, h) < 0) return PF_ERR_SIZE;
    if (n > w || n > h) return PF_ERR_ARG;
    return PF_OK;
}

/* the data check, after every size check: finite heights in the patch and its one-node ring;
   *top gets the highest of them */
PF_CPU_DEF int pfi_vmf_patch_top(const pf_real *hm, int w, int h, long long x0, long long y0, long long n, pf_real *top)
{
    long long i, j;
    pf_real hi = -PF_REAL_MAX;
    for (j = -1; j <= n; ++j)
        for (i = -1; i <= n; ++i) {
            pf_real v = pfi_vmf_height(hm, w, h, x0 + i, y0 + j);
            if (!(PF_FABS(v) < PF_R(0.25) * PF_REAL_MAX)) return PF_ERR_ARG; /* NaN, inf */
            hi = pf_max(hi, v);
        }
    *top = hi;
    return PF_OK;
}

/* f_eff accumulation over the patch, visibility either marched (vis_o NULL) or read from two
   n x n byte maps (both given) */
PF_CPU_DEF pf_real pfi_vmf_effective(const pf_real *hm, int w, int h, pf_real texel, long long x0, long long y0,
                                     long long n, pf_vec3 wo, pf_vec3 wi, pf_real base_var, pf_real f0, pf_real top,
                                     const unsigned char *vis_o, const unsigned char *vis_i)
{
    pf_real num = PF_R(0.0), area = PF_R(0.0), sx, sy;
    long long i, j;
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            long long x = x0 + i, y = y0 + j;
            pf_real term;
            pfi_vmf_slope(hm, w, h, texel, x, y, &sx, &sy);
            area += wo.z - sx * wo.x - sy * wo.y;
            if (vis_o && (!vis_o[j * n + i] || !vis_i[j * n + i])) continue;
            term = pfi_vmf_base_term(sx, sy, base_var, wo, wi, f0);
            if (!(term > PF_R(0.0))) continue;
            if (!vis_o && (!pfi_vmf_visible(hm, w, h, texel, x, y, wo, x0, y0, n, top) ||
                           !pfi_vmf_visible(hm, w, h, texel, x, y, wi, x0, y0, n, top)))
                continue;
            num += term;
        }
    return area > PF_R(0.0) ? num / area : PF_R(0.0);
}

/* The single-bounce effective BRDF of the n x n patch from (x0, y0) (Wu et al. 2019 eqs. 6-8;
   see the block comment) toward wo from wi (unit, tangent frame) into *out; 0 when either
   direction is on or below the macrosurface or the patch's mean plane faces away.
   Errors (*out set to 0 when out is not NULL): PF_ERR_ARG for NULL heights or out, n, w or h
   below 1, n > w or n > h, texel or base_sigma not finite and > 0, a non-finite height in the
   patch or its one-texel ring; PF_ERR_SIZE for w or h above PF_MAX_SIDE or w h > PF_MAX_REALS.
   Cost: 2 n^2 marches of at most n cells. Reads only heights[0 .. w h). */
PF_CPU_DEF int pf_vmf_effective_brdf(const pf_real *heights, int w, int h, pf_real texel, int x0, int y0, int n,
                                     pf_vec3 wo, pf_vec3 wi, pf_real base_sigma, pf_real f0, pf_real *out)
{
    pf_real top = PF_R(0.0);
    int rc;
    if (!out) return PF_ERR_ARG;
    *out = PF_R(0.0);
    if (!(base_sigma > PF_R(0.0)) || !(base_sigma < PF_R(1.0e15))) return PF_ERR_ARG;
    rc = pfi_vmf_patch_sizes(heights, w, h, texel, n);
    if (rc == PF_OK) rc = pfi_vmf_patch_top(heights, w, h, x0, y0, n, &top);
    if (rc != PF_OK) return rc;
    if (!(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0))) return PF_OK;
    *out = pfi_vmf_effective(heights, w, h, texel, x0, y0, n, wo, wi, base_sigma * base_sigma, f0, top, 0, 0);
    return PF_OK;
}

/* samples per patch, (2 nt (np - 1))^2 (every pair of nt thetas times 2 (np - 1) azimuths);
   0 for nt or np below 2 or a count above PF_MAX_REALS */
PF_CPU_DEF long long pf_vmf_scale_sample_count(int nt, int np)
{
    long long d;
    if (nt < 2 || np < 2) return 0;
    d = pf_size_mul3(2, nt, np - 1);
    d = d < 0 ? -1 : pf_size_mul(d, d);
    return d < 0 ? 0 : d;
}

/* nodes (cells) of S: nt nt np (0 for nt or np below 2 or too large) */
PF_CPU_DEF long long pf_vmf_scale_cell_count(int nt, int np)
{
    long long c = (nt < 2 || np < 2) ? -1 : pf_size_mul3(nt, nt, np);
    return c < 0 ? 0 : c;
}

/* bytes of pf_vmf_scale_patch's visibility scratch: 2 nt (np - 1) n^2 (one n x n map per
   direction); 0 for bad sizes */
PF_CPU_DEF long long pf_vmf_scale_vis_bytes(int nt, int np, int n)
{
    long long d = (nt < 2 || np < 2 || n < 1) ? -1 : pf_size_mul3(2, nt, np - 1);
    d = d < 0 ? -1 : pf_size_mul3(d, n, n);
    return d < 0 ? 0 : d;
}

/* the sample directions: theta node it, azimuth a pi / (np - 1) */
PF_CPU_DEF pf_vec3 pfi_vmf_scale_dir(int it, int k, int nt, int np, pf_real theta_max)
{
    pf_real th = (pf_real)it * theta_max / (pf_real)(nt - 1);
    pf_real ph = (pf_real)k * PF_PI / (pf_real)(np - 1);
    return pf_vec3_make(PF_SIN(th) * PF_COS(ph), PF_SIN(th) * PF_SIN(ph), PF_COS(th));
}

/* S cell of sample s (sample order in the block comment) */
PF_CPU_DEF long long pfi_vmf_scale_cell(long long s, int nt, int np)
{
    long long A = 2LL * (np - 1), ai = s % A, ti = (s / A) % nt, ao = (s / (A * nt)) % A, to = s / (A * nt * A);
    long long d = pfi_vmf_wrap(ai - ao, A), k = d <= np - 1 ? d : A - d;
    return (ti * nt + to) * np + k;
}

/* One patch's samples of the scaling function (see the block comment): for every sample s,
   f_eff[s] (eqs. 6-8) and f_lobes[s] (eq. 5 with the patch's `lobes` fitted lobes, EM budget
   `iterations`, masking PF_VMF_SCALE_*); R = f_eff / f_lobes. Directions: thetas
   k theta_max / (nt - 1), theta_max in (0, pi/2). Caller buffers: normals_scratch 3 n^2 pf_reals,
   vis_scratch pf_vmf_scale_vis_bytes(nt, np, n) bytes, f_eff and f_lobes
   pf_vmf_scale_sample_count(nt, np) pf_reals each; nothing outside them is written.
   Errors: those of pf_vmf_effective_brdf, and PF_ERR_ARG for a NULL buffer, lobes outside
   [1, 16], iterations < 0, nt or np < 2, theta_max outside (0, pi/2), an unknown masking;
   PF_ERR_SIZE when a buffer's size exceeds PF_MAX_REALS (every size is checked before any
   height is read). The fit cannot fail on finite heights (every normal has z = 2 texel > 0
   before normalization); if it did, PF_ERR_ARG. Cost: 2 nt (np - 1) n^2 marches
   and up to (2 nt (np - 1))^2 n^2 base-lobe evaluations (facets far from the half vector's
   slope skip theirs). */
PF_CPU_DEF int pf_vmf_scale_patch(const pf_real *heights, int w, int h, pf_real texel, int x0, int y0, int n, int lobes,
                                  int iterations, pf_real base_sigma, pf_real f0, int masking, int nt, int np,
                                  pf_real theta_max, pf_real *normals_scratch, unsigned char *vis_scratch,
                                  pf_real *f_eff, pf_real *f_lobes)
{
    pf_real top = PF_R(0.0), bv;
    pf_vmf_mixture mix;
    long long nn, dirs, count, A, s, i, j;
    int rc, d;
    if (!normals_scratch || !vis_scratch || !f_eff || !f_lobes || lobes < 1 || lobes > PF_VMF_MAX_LOBES ||
        iterations < 0 || nt < 2 || np < 2 || !(theta_max > PF_R(0.0)) || !(theta_max < PF_R(0.5) * PF_PI) ||
        masking < PF_VMF_SCALE_UNMASKED || masking > PF_VMF_SCALE_G_MIXTURE)
        return PF_ERR_ARG;
    if (!(base_sigma > PF_R(0.0)) || !(base_sigma < PF_R(1.0e15))) return PF_ERR_ARG;
    rc = pfi_vmf_patch_sizes(heights, w, h, texel, n);
    if (rc != PF_OK) return rc;
    nn = (long long)n * n;
    count = pf_vmf_scale_sample_count(nt, np);
    if (count == 0 || pf_vmf_scale_vis_bytes(nt, np, n) == 0 || pf_size_mul(nn, 3) < 0) return PF_ERR_SIZE;
    rc = pfi_vmf_patch_top(heights, w, h, x0, y0, n, &top); /* reads data: after every size check */
    if (rc != PF_OK) return rc;
    A = 2LL * (np - 1);
    dirs = nt * A;
    bv = base_sigma * base_sigma;
    /* the patch's normals and its lobes */
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            /* (-dx, -dy, 2 texel), the normal of the central differences without dividing by
               the texel (no overflow for a tiny texel); the fit normalizes it */
            pf_real dx = pfi_vmf_height(heights, w, h, x0 + i + 1, y0 + j) - pfi_vmf_height(heights, w, h, x0 + i - 1, y0 + j);
            pf_real dy = pfi_vmf_height(heights, w, h, x0 + i, y0 + j + 1) - pfi_vmf_height(heights, w, h, x0 + i, y0 + j - 1);
            pf_real m = pf_max(pf_max(PF_FABS(dx), PF_FABS(dy)), PF_R(2.0) * texel);
            normals_scratch[3 * (j * n + i)] = -dx / m;
            normals_scratch[3 * (j * n + i) + 1] = -dy / m;
            normals_scratch[3 * (j * n + i) + 2] = PF_R(2.0) * texel / m;
        }
    if (pf_vmf_fit_normals(normals_scratch, 0, nn, lobes, iterations, &mix) != PF_OK) return PF_ERR_ARG;
    /* one visibility map per direction of the set */
    for (d = 0; d < dirs; ++d) {
        pf_vec3 dir = pfi_vmf_scale_dir((int)(d / A), (int)(d % A), nt, np, theta_max);
        unsigned char *vm = vis_scratch + d * nn;
        for (j = 0; j < n; ++j)
            for (i = 0; i < n; ++i)
                vm[j * n + i] = (unsigned char)pfi_vmf_visible(heights, w, h, texel, x0 + i, y0 + j, dir, x0, y0, n, top);
    }
    for (s = 0; s < count; ++s) {
        long long ai = s % A, ti = (s / A) % nt, ao = (s / (A * nt)) % A, to = s / (A * nt * A);
        pf_vec3 wo = pfi_vmf_scale_dir((int)to, (int)ao, nt, np, theta_max);
        pf_vec3 wi = pfi_vmf_scale_dir((int)ti, (int)ai, nt, np, theta_max);
        pf_vmf_sum sum = pf_vmf_sum_zero();
        int k;
        f_eff[s] = pfi_vmf_effective(heights, w, h, texel, x0, y0, n, wo, wi, bv, f0, top,
                                     vis_scratch + (to * A + ao) * nn, vis_scratch + (ti * A + ai) * nn);
        for (k = 0; k < mix.count; ++k) {
            sum = pf_vmf_sum_add(sum, mix.lobe[k], wo, wi, bv);
            if (masking == PF_VMF_SCALE_G_MIXTURE) sum = pf_vmf_sum_add_masking(sum, mix.lobe[k], wo, wi, bv);
        }
        f_lobes[s] = masking == PF_VMF_SCALE_UNMASKED    ? pf_vmf_sum_specular_unmasked(sum, wo, wi, f0)
                     : masking == PF_VMF_SCALE_G_GAUSSIAN ? pf_vmf_sum_specular(sum, wo, wi, f0)
                                                          : pf_vmf_sum_specular_mixture(sum, wo, wi, f0);
    }
    return PF_OK;
}

/* T (patches values) and S (pf_vmf_scale_cell_count(nt, np) values) from the samples of
   `patches` patches (f_eff and f_lobes: patches * pf_vmf_scale_sample_count(nt, np) pf_reals,
   patch after patch, as pf_vmf_scale_patch writes them): the rank-1 least-squares fit in BRDF
   units by `iterations` (>= 1) alternating rounds, T scaled to mean 1 (block comment), each
   value pulled toward 1 by a prior of weight `shrink` (>= 0; 0: plain least squares) times
   the mean energy of a patch (T) resp. a cell (S): T(x) = (sum e l S + p) / (sum (l S)^2 + p)
   (REGULARIZATION in the block comment). prior_out (NULL or 1 pf_real): the prior p to pass to
   pf_vmf_scale_t for other patches of the same level (shrink times the mean patch energy under
   the final S). scratch: 2 * patches * cells pf_reals. err (NULL or 3 pf_reals): [0] the relative L2 error
   of T S f_lobes against f_eff over all samples (what the factorization leaves), [1] the same
   for f_lobes alone (T = S = 1: the unscaled multi-lobe BRDF), [2] the relative L2 error of
   T S against R = f_eff / f_lobes over the samples where f_lobes exceeds 1% of its RMS (R is
   not defined where f_lobes vanishes). Non-finite or negative samples count as 0.
   Errors: PF_ERR_ARG for a NULL buffer, patches < 1, nt or np < 2, iterations < 1, shrink
   outside [0, 1e6] or NaN; PF_ERR_SIZE when a size exceeds PF_MAX_REALS. */
PF_CPU_DEF int pf_vmf_scale_factor(const pf_real *f_eff, const pf_real *f_lobes, int patches, int nt, int np,
                                   int iterations, pf_real shrink, pf_real *t_out, pf_real *s_out, pf_real *scratch,
                                   pf_real *prior_out, pf_real *err)
{
    long long cells, count, x, b, s;
    pf_real *num, *den, mean;
    int it;
    if (!f_eff || !f_lobes || !t_out || !s_out || !scratch || patches < 1 || nt < 2 || np < 2 || iterations < 1 ||
        !(shrink >= PF_R(0.0)) || !(shrink <= PF_R(1.0e6)))
        return PF_ERR_ARG;
    cells = pf_vmf_scale_cell_count(nt, np);
    count = pf_vmf_scale_sample_count(nt, np);
    if (cells == 0 || count == 0 || pf_size_mul(count, patches) < 0 || pf_size_mul3(cells, patches, 2) < 0)
        return PF_ERR_SIZE;
    num = scratch;
    den = scratch + cells * patches;
    for (b = 0; b < cells * patches; ++b) num[b] = den[b] = PF_R(0.0);
    /* per (patch, cell): sum f_eff f_lobes and sum f_lobes^2 (the normal equations) */
    for (x = 0; x < patches; ++x)
        for (s = 0; s < count; ++s) {
            pf_real e = f_eff[x * count + s], l = f_lobes[x * count + s];
            long long c = x * cells + pfi_vmf_scale_cell(s, nt, np);
            e = e > PF_R(0.0) && e < PF_REAL_MAX ? e : PF_R(0.0);
            l = l > PF_R(0.0) && l < PF_REAL_MAX ? l : PF_R(0.0);
            num[c] += e * l;
            den[c] += l * l;
        }
    for (b = 0; b < cells; ++b) s_out[b] = PF_R(1.0);
    for (x = 0; x < patches; ++x) t_out[x] = PF_R(1.0);
    for (it = 0; it < iterations; ++it) {
        /* T step: each patch's energy q first (kept in t_out, which this step overwrites),
           the prior's weight `shrink` times their mean, then T from q and sum e l S */
        pf_real prior = PF_R(0.0);
        for (x = 0; x < patches; ++x) {
            pf_real q = PF_R(0.0);
            for (b = 0; b < cells; ++b) q += den[x * cells + b] * s_out[b] * s_out[b];
            t_out[x] = q;
            prior += q;
        }
        prior = shrink * prior / (pf_real)patches;
        prior = prior < PF_REAL_MAX ? prior : PF_R(0.0); /* overflowed energies: no prior */
        for (x = 0; x < patches; ++x) {
            pf_real a = PF_R(0.0);
            for (b = 0; b < cells; ++b) a += num[x * cells + b] * s_out[b];
            a = (a + prior) / (t_out[x] + prior);
            t_out[x] = a < PF_REAL_MAX ? a : PF_R(1.0); /* no energy and no prior (NaN), overflow */
        }
        /* S step: likewise with each cell's energy (kept in s_out) and their mean */
        prior = PF_R(0.0);
        for (b = 0; b < cells; ++b) {
            pf_real q = PF_R(0.0);
            for (x = 0; x < patches; ++x) q += den[x * cells + b] * t_out[x] * t_out[x];
            s_out[b] = q;
            prior += q;
        }
        prior = shrink * prior / (pf_real)cells;
        prior = prior < PF_REAL_MAX ? prior : PF_R(0.0);
        for (b = 0; b < cells; ++b) {
            pf_real a = PF_R(0.0);
            for (x = 0; x < patches; ++x) a += num[x * cells + b] * t_out[x];
            a = (a + prior) / (s_out[b] + prior);
            s_out[b] = a < PF_REAL_MAX ? a : PF_R(1.0);
        }
    }
    mean = PF_R(0.0);
    for (x = 0; x < patches; ++x) mean += t_out[x];
    mean /= (pf_real)patches;
    if (mean > PF_R(0.0)) {
        for (x = 0; x < patches; ++x) t_out[x] /= mean;
        for (b = 0; b < cells; ++b) s_out[b] *= mean;
    }
    /* the prior for pf_vmf_scale_t on other patches of the same level: shrink times the mean
       patch energy sum_s (S f_lobes)^2 under the final S */
    if (prior_out) {
        pf_real e_sum = PF_R(0.0);
        for (x = 0; x < patches; ++x)
            for (b = 0; b < cells; ++b) e_sum += den[x * cells + b] * s_out[b] * s_out[b];
        e_sum = shrink * e_sum / (pf_real)patches;
        *prior_out = e_sum < PF_REAL_MAX ? e_sum : PF_R(0.0);
    }
    if (err) {
        pf_real e0 = PF_R(0.0), e1 = PF_R(0.0), ref = PF_R(0.0), l2 = PF_R(0.0), r0 = PF_R(0.0), rr = PF_R(0.0), floor_l;
        for (x = 0; x < patches; ++x)
            for (s = 0; s < count; ++s) {
                pf_real e = f_eff[x * count + s], l = f_lobes[x * count + s];
                pf_real ts = t_out[x] * s_out[pfi_vmf_scale_cell(s, nt, np)];
                e = e > PF_R(0.0) && e < PF_REAL_MAX ? e : PF_R(0.0);
                l = l > PF_R(0.0) && l < PF_REAL_MAX ? l : PF_R(0.0);
                e0 += (e - ts * l) * (e - ts * l);
                e1 += (e - l) * (e - l);
                ref += e * e;
                l2 += l * l;
            }
        floor_l = PF_R(0.01) * PF_SQRT(l2 / (pf_real)(count * patches));
        for (x = 0; x < patches; ++x)
            for (s = 0; s < count; ++s) {
                pf_real e = f_eff[x * count + s], l = f_lobes[x * count + s], R;
                pf_real ts = t_out[x] * s_out[pfi_vmf_scale_cell(s, nt, np)];
                if (!(l > floor_l) || !(l < PF_REAL_MAX)) continue;
                R = (e > PF_R(0.0) && e < PF_REAL_MAX ? e : PF_R(0.0)) / l;
                r0 += (R - ts) * (R - ts);
                rr += R * R;
            }
        err[0] = ref > PF_R(0.0) ? PF_SQRT(e0 / ref) : PF_R(0.0);
        err[1] = ref > PF_R(0.0) ? PF_SQRT(e1 / ref) : PF_R(0.0);
        err[2] = rr > PF_R(0.0) ? PF_SQRT(r0 / rr) : PF_R(0.0);
    }
    return PF_OK;
}

/* T of one patch given a level's S table (pf_vmf_scale_factor's s_out) from the patch's own
   samples (f_eff, f_lobes: pf_vmf_scale_sample_count(nt, np) pf_reals each, as
   pf_vmf_scale_patch writes them): (sum e l S + prior) / (sum (l S)^2 + prior), S of each
   sample's cell, prior from pf_vmf_scale_factor's prior_out (>= 0). Non-finite or negative
   samples count as 0. 1 for a NULL buffer, bad sizes, a negative or NaN prior, a patch
   without energy and no prior, or sums that overflow. */
PF_CPU_DEF pf_real pf_vmf_scale_t(const pf_real *f_eff, const pf_real *f_lobes, int nt, int np, const pf_real *s_table,
                                  pf_real prior)
{
    long long count = pf_vmf_scale_sample_count(nt, np), s;
    pf_real a = PF_R(0.0), q = PF_R(0.0);
    if (!f_eff || !f_lobes || !s_table || count == 0 || pf_vmf_scale_cell_count(nt, np) == 0 || !(prior >= PF_R(0.0)))
        return PF_R(1.0);
    for (s = 0; s < count; ++s) {
        pf_real e = f_eff[s], l = f_lobes[s];
        e = e > PF_R(0.0) && e < PF_REAL_MAX ? e : PF_R(0.0);
        l = l > PF_R(0.0) && l < PF_REAL_MAX ? l * s_table[pfi_vmf_scale_cell(s, nt, np)] : PF_R(0.0);
        a += e * l;
        q += l * l;
    }
    a = (a + prior) / (q + prior);
    return a < PF_REAL_MAX ? a : PF_R(1.0); /* NaN (no energy, no prior) and overflow too */
}

/* S at (wo, wi) from the table (CPU side of the shader lookup: pf_vmf_scale_coords,
   pf_vmf_scale_texel_pos, 8 reads, pf_vmf_scale_trilinear). NULL table or bad sizes: 1 (no
   scaling). */
PF_CPU_DEF pf_real pf_vmf_scale_lookup(const pf_real *table, int nt, int np, pf_real theta_max, pf_vec3 wo, pf_vec3 wi)
{
    pf_vec3 c, f;
    pf_real p0, p1, p2;
    long long a0, a1, b0, b1, c0, c1;
    if (!table || pf_vmf_scale_cell_count(nt, np) == 0) return PF_R(1.0);
    c = pf_vmf_scale_coords(wo, wi, theta_max);
    p0 = pf_vmf_scale_texel_pos(c.x, nt);
    p1 = pf_vmf_scale_texel_pos(c.y, nt);
    p2 = pf_vmf_scale_texel_pos(c.z, np);
    a0 = (long long)p0;
    b0 = (long long)p1;
    c0 = (long long)p2;
    a1 = a0 + 1 < nt ? a0 + 1 : a0;
    b1 = b0 + 1 < nt ? b0 + 1 : b0;
    c1 = c0 + 1 < np ? c0 + 1 : c0;
    f = pf_vec3_make(p0 - (pf_real)a0, p1 - (pf_real)b0, p2 - (pf_real)c0);
#define PFI_VMF_S(a, b, c) table[((a) * nt + (b)) * np + (c)]
    return pf_vmf_scale_trilinear(PFI_VMF_S(a0, b0, c0), PFI_VMF_S(a1, b0, c0), PFI_VMF_S(a0, b1, c0),
                                  PFI_VMF_S(a1, b1, c0), PFI_VMF_S(a0, b0, c1), PFI_VMF_S(a1, b0, c1),
                                  PFI_VMF_S(a0, b1, c1), PFI_VMF_S(a1, b1, c1), f);
#undef PFI_VMF_S
}
/* ================================================================ end of SCALING FUNCTION */

/* ================================================================ CPU only: the lobe pyramid
   Level l of a w x h normal map (w, h powers of two) has max(1, w >> l) x max(1, h >> l)
   texels; texel (i, j) of level l covers the finest texels [i fx, (i + 1) fx) x [j fy, (j + 1)
   fy), fx = w / (w >> l) (a box: what a mip level holds). Every level is FITTED FROM THE
   FINEST NORMALS of its footprint (not merged from the level below: merging m lobes of four
   children into m is itself a fit, and the finest normals are at hand); cost ~ levels x
   texels x lobes x iterations exps (docs/vmf.md has the measured time).
   LAYOUT (what a shader fetches): levels one after another from level 0, texels row-major,
   4 * lobes pf_reals per texel: for each lobe (mu.x, mu.y, kappa, amp) - an RGBA texel per
   lobe (mu.z = sqrt(1 - x^2 - y^2)). A fit that returns fewer lobes pads with amp = 0,
   mu = +z, kappa = 1. Bytes per texel: 16 m in float32 (16, 32, 64, 128, 256 for m = 1, 2, 4, 8, 16),
   8 m in half floats (kappa <= 1e5 fits half's range; its 11-bit precision is 0.05% on kappa).
   A texel whose footprint has no usable normal gets the flat lobe (amp 1, mu = +z, kappa =
   PF_VMF_KAPPA_MAX) and the call still returns PF_OK.
   Errors: PF_ERR_ARG for NULL normals or pyr, w or h below 1 or not a power of two, lobes
   outside [1, 16], iterations < 0; PF_ERR_SIZE for a side above PF_MAX_SIDE or a buffer above
   PF_MAX_REALS.
   normals: w * h * 3 pf_reals; weights: w * h or NULL; pyr: pf_vmf_pyramid_texel_count(w, h)
   * 4 * lobes pf_reals. Nothing outside these is read or written. */
PF_CPU_DEF int pfi_vmf_pow2(long long n) { return pf_size_side_ok(n) && (n & (n - 1)) == 0; }

PF_CPU_DEF int pf_vmf_pyramid_level_count(int w, int h)
{
    int l = 1;
    if (!pfi_vmf_pow2(w) || !pfi_vmf_pow2(h)) return 0;
    while ((w >> (l - 1)) > 1 || (h >> (l - 1)) > 1) ++l;
    return l;
}

/* texels before level `level` (level >= count: the total); -1 for bad sizes */
PF_CPU_DEF long long pf_vmf_pyramid_level_offset(int w, int h, int level)
{
    long long off = 0;
    int l, n = pf_vmf_pyramid_level_count(w, h);
    if (n == 0 || level < 0) return -1;
    for (l = 0; l < level && l < n; ++l) {
        long long lw = (w >> l) > 0 ? (w >> l) : 1, lh = (h >> l) > 0 ? (h >> l) : 1;
        off += lw * lh;
    }
    return off;
}

/* texels of all levels together (4 * lobes pf_reals each); 0 for bad sizes */
PF_CPU_DEF long long pf_vmf_pyramid_texel_count(int w, int h)
{
    long long t = pf_vmf_pyramid_level_offset(w, h, 64);
    return t < 0 ? 0 : t;
}

PF_CPU_DEF void pfi_vmf_store(pf_real *dst, pf_vmf_mixture m, int lobes)
{
    int k;
    for (k = 0; k < lobes; ++k) {
        int live = k < m.count;
        dst[4 * k] = live ? m.lobe[k].mu.x : PF_R(0.0);
        dst[4 * k + 1] = live ? m.lobe[k].mu.y : PF_R(0.0);
        dst[4 * k + 2] = live ? m.lobe[k].kappa : PF_R(1.0);
        dst[4 * k + 3] = live ? m.lobe[k].amp : PF_R(0.0);
    }
}

PF_CPU_DEF int pf_vmf_pyramid_from_normals(const pf_real *normals, const pf_real *weights, int w, int h, int lobes,
                                           int iterations, pf_real *pyr)
{
    int levels, l;
    long long off = 0;
    if (!normals || !pyr || w < 1 || h < 1 || lobes < 1 || lobes > PF_VMF_MAX_LOBES || iterations < 0)
        return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h)) return PF_ERR_SIZE;
    levels = pf_vmf_pyramid_level_count(w, h);
    if (levels == 0) return PF_ERR_ARG; /* not powers of two */
    if (pf_size_mul3(pf_vmf_pyramid_texel_count(w, h), 4, lobes) < 0 || pf_size_mul3(w, h, 3) < 0)
        return PF_ERR_SIZE;
    for (l = 0; l < levels; ++l) {
        long long lw = (w >> l) > 0 ? (w >> l) : 1, lh = (h >> l) > 0 ? (h >> l) : 1;
        long long fx = w / lw, fy = h / lh, i, j;
        for (j = 0; j < lh; ++j)
            for (i = 0; i < lw; ++i) {
                pf_vmf_mixture m;
                long long first = j * fy * w + i * fx;
                if (pfi_vmf_fit_block(normals + 3 * first, weights ? weights + first : weights, w, fx, fy, lobes,
                                      iterations, &m) != PF_OK)
                    m = pfi_vmf_flat();
                pfi_vmf_store(pyr + (off + j * lw + i) * 4 * lobes, m, lobes);
            }
        off += lw * lh;
    }
    return PF_OK;
}

/* The mixture stored at one texel of the pyramid (4 * lobes pf_reals): what a shader's
   `lobes` RGBA fetches and pf_vmf_lobe_make calls give. Lobes with amp = 0 (padding) are
   skipped. lobes is clamped to [1, 16]; texel NULL gives an empty mixture (count 0). */
PF_CPU_DEF pf_vmf_mixture pf_vmf_mixture_from_texel(const pf_real *texel, int lobes)
{
    pf_vmf_mixture m = pfi_vmf_mixture_empty();
    int k, n = lobes < 1 ? 1 : (lobes > PF_VMF_MAX_LOBES ? PF_VMF_MAX_LOBES : lobes);
    if (!texel) return m;
    for (k = 0; k < n; ++k)
        if (texel[4 * k + 3] > PF_R(0.0))
            m.lobe[m.count++] = pf_vmf_lobe_make(texel[4 * k + 3], texel[4 * k], texel[4 * k + 1], texel[4 * k + 2]);
    return m;
}
#undef PFI_VMF_FOREACH

/* ================================================================ CPU only: slope-preserving
   downsampling of a height map (Wu et al. 2019 sec. 4.1, eqs. 9-10)
   A coarse height map read with lobes fitted to the fine normals must carry the fine map's
   mean slope over each footprint: the lobes describe the normals around that mean, and a box
   average of the heights does not keep it (on the bench's corpus the box map's slopes are off
   by 1.2-3.9x the solve's error, docs/vmf.md). Wu et al. choose the coarse heights whose
   slopes best match the footprints' mean slopes in least squares, with a small Laplacian
   term for smoothness.
   OUR DISCRETIZATION (the library's height-map convention, pf_moments.h CONVENTIONS: texels
   at centres, the slope of a texel its central difference, one-sided at a clamped border):
     s*_T   = factor x the mean, over the factor x factor fine texels of coarse texel T, of the
              fine texels' slopes (pfi_slope_stencil: what pf_slope_pyramid_from_heights'
              level log2(factor) holds as E[sx], E[sy]), in height per COARSE texel;
     (G H)_T = the coarse map's own slope at T by the same stencil (height per coarse texel);
     (L H)_T = the 5-point Laplacian of the coarse map (sum of the 4 neighbours - 4 H_T;
              wrapped, or the edge texel repeated under PF_BORDER_CLAMP);
     minimize  E(H) = sum_T |(G H)_T - s*_T|^2 + reg_weight sum_T (L H)_T^2        (eq. 10)
   (Wu et al. put heights on cell corners and take the bilinear cell's mean slope, eq. 9; on
   the texel-centred grid the same role is played by the central difference, and using the
   stencil every slope consumer of the library uses makes the coarse map's slopes exactly the
   ones it is read with.) Every term is in height per coarse texel, so reg_weight is
   dimensionless (the paper's w = 0.01) and the result does not depend on the texel spacing
   (both slopes divide by it), which is therefore not an argument.
   The normal equations (G^T G + reg_weight L^T L) H = G^T s* are singular along the
   constant map (no slope sees it): THE MEAN IS PINNED to the box-downsampled map's mean (=
   the fine map's mean), and the solve starts from that box map. SOLVER: conjugate gradients
   on the normal equations (the matrix is never formed: each product is one pass of the three
   stencils and one of their transposes), every residual projected to zero mean so rounding
   cannot move the pinned mean; deterministic (fixed loop order, no threads). It stops after
   max_iter iterations or when |r| <= tol |G^T s*| (r the recurrence's residual of the normal
   equations; a target with no slope at all uses |r_0| instead). Heights are scaled by a power
   of two (exact) so that no difference overflows; a result beyond the pf_real range is
   clamped to +-PF_REAL_MAX.
   Arguments: fine w x h row-major; factor >= 1 dividing w and h (coarse (w/factor) x
   (h/factor), row-major, into coarse); border PF_BORDER_WRAP (tiling maps) or
   PF_BORDER_CLAMP; reg_weight in [0, PF_VMF_DOWNSAMPLE_MAX_REG = 1e6] (at 0, under WRAP,
   2-texel checkerboards, which no central difference sees, keep their box values; far above
   1 the Laplacian alone decides; the bound keeps every product finite); max_iter >= 0 (0:
   the box map); tol finite >= 0; scratch: scratch_len >= pf_vmf_downsample_scratch_size(w,
   h, factor) pf_reals; iters_out (iterations done) and residual_out (the final |r| over the
   reference norm above) may be NULL.
   Errors: PF_ERR_ARG for NULL fine, coarse or scratch, w or h below 1, factor below 1 or not
   dividing w and h, an unknown border, a bad reg_weight, max_iter or tol, a NaN or infinite
   height, a scratch_len below the size; PF_ERR_SIZE for a side above PF_MAX_SIDE or a buffer
   above PF_MAX_REALS. On an error nothing is written. Nothing outside fine (read), coarse and
   the first pf_vmf_downsample_scratch_size reals of scratch is touched.
   Cost: one pass over the fine map, then per iteration one product (three 3-tap stencils and
   their transposes over the coarse map) and four vector passes; 512 x 512 -> 256 x 256 in
   15-50 ms (float, tol 1e-5; docs/vmf.md has the table and the slope errors against the box
   map). */

#define PF_VMF_DOWNSAMPLE_MAX_REG PF_R(1.0e6)

/* pf_reals of scratch pf_vmf_downsample_slopes needs: 6 per coarse texel; 0 for sizes it
   rejects (w, h or factor below 1, factor not dividing w and h, a side above PF_MAX_SIDE, or
   more than PF_MAX_REALS). */
PF_CPU_DEF long long pf_vmf_downsample_scratch_size(int w, int h, int factor)
{
    long long n;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || factor < 1 || w % factor != 0 || h % factor != 0) return 0;
    if (pf_size_mul(w, h) < 0) return 0;
    n = pf_size_mul3((long long)(w / factor), (long long)(h / factor), 6);
    return n < 0 ? 0 : n;
}

/* sum of a[i] b[i] (b NULL: a[i]^2) in rows of w: per-row partial sums, so the rounding grows
   with w + h, not w h */
PF_CPU_DEF pf_real pfi_ds_dot(const pf_real *a, const pf_real *b, long long w, long long h)
{
    pf_real total = PF_R(0.0);
    long long i, j;
    for (j = 0; j < h; ++j) {
        const pf_real *x = a + j * w, *y = (b ? b : a) + j * w;
        pf_real row = PF_R(0.0);
        for (i = 0; i < w; ++i) row += x[i] * y[i];
        total += row;
    }
    return total;
}
PF_CPU_DEF pf_real pfi_ds_mean(const pf_real *a, long long w, long long h)
{
    pf_real total = PF_R(0.0);
    long long i, j;
    for (j = 0; j < h; ++j) {
        pf_real row = PF_R(0.0);
        for (i = 0; i < w; ++i) row += a[j * w + i];
        total += row / (pf_real)w;
    }
    return total / (pf_real)h;
}
PF_CPU_DEF void pfi_ds_shift(pf_real *a, long long n, pf_real d)
{
    long long i;
    for (i = 0; i < n; ++i) a[i] += d;
}
/* neighbour of index i on an axis of n: wrapped or clamped (the clamped Laplacian repeats the
   edge texel: a zero normal derivative) */
PF_CPU_DEF long long pfi_ds_nb(long long i, long long n, int border)
{
    if (border == PF_BORDER_WRAP) return pfi_wrap_index(i, n);
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

/* gx = G_x v, gy = G_y v, lp = L v on the W x H coarse grid */
PF_CPU_DEF void pfi_ds_forward(const pf_real *v, int W, int H, int border, pf_real *gx, pf_real *gy, pf_real *lp)
{
    long long I, J, xi[3], yi[3];
    pf_real cx[3], cy[3];
    for (J = 0; J < H; ++J) {
        const pf_real *row = v + J * W, *up = v + pfi_ds_nb(J - 1, H, border) * W, *dn = v + pfi_ds_nb(J + 1, H, border) * W;
        pfi_slope_stencil(J, H, border, PF_R(0.5), yi, cy);
        for (I = 0; I < W; ++I) {
            long long t = J * W + I;
            pfi_slope_stencil(I, W, border, PF_R(0.5), xi, cx);
            gx[t] = cx[0] * row[xi[0]] + cx[1] * row[xi[1]] + cx[2] * row[xi[2]];
            gy[t] = cy[0] * v[yi[0] * W + I] + cy[1] * v[yi[1] * W + I] + cy[2] * v[yi[2] * W + I];
            lp[t] = (row[pfi_ds_nb(I - 1, W, border)] + row[pfi_ds_nb(I + 1, W, border)]) + (up[I] + dn[I]) -
                    PF_R(4.0) * row[I];
        }
    }
}

/* out = G_x^T gx + G_y^T gy + reg L^T lp (the transposes as scatters of the same stencils) */
PF_CPU_DEF void pfi_ds_adjoint(const pf_real *gx, const pf_real *gy, const pf_real *lp, pf_real reg, int W, int H,
                               int border, pf_real *out)
{
    long long I, J, k, xi[3], yi[3], n = (long long)W * H;
    pf_real cx[3], cy[3];
    for (k = 0; k < n; ++k) out[k] = PF_R(0.0);
    for (J = 0; J < H; ++J) {
        pf_real *row = out + J * W, *up = out + pfi_ds_nb(J - 1, H, border) * W, *dn = out + pfi_ds_nb(J + 1, H, border) * W;
        pfi_slope_stencil(J, H, border, PF_R(0.5), yi, cy);
        for (I = 0; I < W; ++I) {
            long long t = J * W + I;
            pf_real a = gx[t], b = gy[t], l = reg * lp[t];
            pfi_slope_stencil(I, W, border, PF_R(0.5), xi, cx);
            for (k = 0; k < 3; ++k) {
                row[xi[k]] += cx[k] * a;
                out[yi[k] * W + I] += cy[k] * b;
            }
            row[pfi_ds_nb(I - 1, W, border)] += l;
            row[pfi_ds_nb(I + 1, W, border)] += l;
            up[I] += l;
            dn[I] += l;
            row[I] -= PF_R(4.0) * l;
        }
    }
}

PF_CPU_DEF int pf_vmf_downsample_slopes(const pf_real *fine, int w, int h, int factor, int border, pf_real reg_weight,
                                        int max_iter, pf_real tol, pf_real *coarse, pf_real *scratch,
                                        long long scratch_len, int *iters_out, pf_real *residual_out)
{
    long long need, n, i, j, W, H, f = factor;
    pf_real *r, *p, *q, *gx, *gy, *lp, maxabs = PF_R(0.0), scale = PF_R(1.0), bnorm, rr, ref, mean, inv_f2;
    int it = 0;
    if (!fine || !coarse || !scratch || w < 1 || h < 1 || factor < 1) return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || pf_size_mul(w, h) < 0) return PF_ERR_SIZE;
    if (w % factor != 0 || h % factor != 0 || (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP)) return PF_ERR_ARG;
    if (!(reg_weight >= PF_R(0.0) && reg_weight <= PF_VMF_DOWNSAMPLE_MAX_REG) || max_iter < 0 ||
        !(tol >= PF_R(0.0) && tol <= PF_REAL_MAX))
        return PF_ERR_ARG;
    need = pf_vmf_downsample_scratch_size(w, h, factor);
    if (need <= 0) return PF_ERR_SIZE;
    if (scratch_len < need) return PF_ERR_ARG;
    for (i = 0; i < (long long)w * h; ++i) {
        pf_real a = PF_FABS(fine[i]);
        if (!(a <= PF_REAL_MAX)) return PF_ERR_ARG; /* NaN or infinite */
        maxabs = pf_max(maxabs, a);
    }
    /* power-of-two scale to max |height| in [1, 4): exact, no slope difference overflows, and
       the scale stays a normal number (2^-126 at worst in float: no flush to 0 under
       -ffast-math) */
    if (maxabs > PF_R(0.0)) {
        while (maxabs * scale >= PF_R(4.0)) scale *= PF_R(0.5);
        while (maxabs * scale < PF_R(1.0) && scale < PF_R(1.0e30)) scale *= PF_R(2.0);
    }
    W = w / factor, H = h / factor, n = W * H;
    r = scratch, p = r + n, q = p + n, gx = q + n, gy = gx + n, lp = gy + n;
    inv_f2 = PF_R(1.0) / ((pf_real)f * (pf_real)f);
    /* s* (gx, gy) and the box map (coarse), one pass over the fine map */
    for (i = 0; i < n; ++i) gx[i] = gy[i] = coarse[i] = PF_R(0.0);
    for (j = 0; j < h; ++j) {
        long long yi[3], xi[3], t0 = (j / f) * W;
        pf_real cy[3], cx[3];
        const pf_real *row = fine + j * w;
        pfi_slope_stencil(j, h, border, PF_R(0.5) * scale, yi, cy);
        for (i = 0; i < w; ++i) {
            long long t = t0 + i / f;
            pfi_slope_stencil(i, w, border, PF_R(0.5) * scale, xi, cx);
            gx[t] += cx[0] * row[xi[0]] + cx[1] * row[xi[1]] + cx[2] * row[xi[2]];
            gy[t] += cy[0] * fine[yi[0] * w + i] + cy[1] * fine[yi[1] * w + i] + cy[2] * fine[yi[2] * w + i];
            coarse[t] += row[i] * scale;
        }
    }
    /* mean fine slope (per fine texel) x f = per coarse texel */
    for (i = 0; i < n; ++i) {
        gx[i] *= inv_f2 * (pf_real)f;
        gy[i] *= inv_f2 * (pf_real)f;
        coarse[i] *= inv_f2;
    }
    mean = pfi_ds_mean(coarse, W, H);
    for (i = 0; i < n; ++i) lp[i] = PF_R(0.0);
    pfi_ds_adjoint(gx, gy, lp, PF_R(0.0), (int)W, (int)H, border, r); /* r = b = G^T s* */
    bnorm = PF_SQRT(pfi_ds_dot(r, 0, W, H));
    /* r = b - A x0 */
    pfi_ds_forward(coarse, (int)W, (int)H, border, gx, gy, lp);
    pfi_ds_adjoint(gx, gy, lp, reg_weight, (int)W, (int)H, border, q);
    for (i = 0; i < n; ++i) r[i] -= q[i];
    pfi_ds_shift(r, n, -pfi_ds_mean(r, W, H));
    rr = pfi_ds_dot(r, 0, W, H);
    ref = bnorm > PF_R(0.0) ? bnorm : PF_SQRT(rr);
    for (i = 0; i < n; ++i) p[i] = r[i];
    while (it < max_iter && PF_SQRT(rr) > tol * ref) {
        pf_real pq, alpha, rr_new, beta;
        pfi_ds_forward(p, (int)W, (int)H, border, gx, gy, lp);
        pfi_ds_adjoint(gx, gy, lp, reg_weight, (int)W, (int)H, border, q);
        pq = pfi_ds_dot(p, q, W, H);
        if (!(pq > PF_R(0.0))) break; /* p in the null space, or rounding: nothing left to gain */
        alpha = rr / pq;
        for (i = 0; i < n; ++i) {
            coarse[i] += alpha * p[i];
            r[i] -= alpha * q[i];
        }
        pfi_ds_shift(r, n, -pfi_ds_mean(r, W, H));
        rr_new = pfi_ds_dot(r, 0, W, H);
        beta = rr_new / rr;
        for (i = 0; i < n; ++i) p[i] = r[i] + beta * p[i];
        rr = rr_new;
        ++it;
    }
    /* the pinned mean, exactly (rounding of the updates), then the heights' own scale */
    pfi_ds_shift(coarse, n, mean - pfi_ds_mean(coarse, W, H));
    for (i = 0; i < n; ++i) {
        pf_real v = coarse[i] / scale;
        coarse[i] = v > PF_REAL_MAX ? PF_REAL_MAX : (v < -PF_REAL_MAX ? -PF_REAL_MAX : v);
    }
    if (iters_out) *iters_out = it;
    if (residual_out) *residual_out = ref > PF_R(0.0) ? PF_SQRT(rr) / ref : PF_R(0.0);
    return PF_OK;
}
#endif /* PF_GLSL */

#endif /* PF_VMF_H */

/* pf_toksvig.h - Toksvig's normal-variance estimate and the lobe widening it drives: filtered
   Blinn-Phong exponent, lobe normalization, the "Toksvig factor", roughness widening for
   Beckmann and GGX, and Blinn-Phong <-> Beckmann conversions.

   IDEA (Toksvig 2005, as summarized by Bruneton & Neyret 2012 sec. 3.2.1 and 7.2.2). A mip
   pyramid of unit normals averages them without renormalizing (pf_moments.h: normal_avg).
   Where the normals below a texel agree, the average E[n] has length 1; where they spread it
   is shorter. Modelling the spread as a Gaussian of the angle from the mean normal with
   variance sigma^2 per axis, |E[n]| ~ 1 - sigma^2, and Toksvig reads the variance back as
       sigma^2 = (1 - |mu|) / |mu|,            mu = E[n].                              (1)
   A Blinn-Phong lobe (n.h)^alpha is close to a Gaussian of the angle with variance 1/alpha per
   axis (cos^alpha t ~ exp(-alpha t^2 / 2)); convolving it with the normal spread adds the
   variances, 1/alpha' = 1/alpha + sigma^2:
       alpha' = alpha / (1 + alpha sigma^2)                                            (2)
       f_A(h) = (1 + alpha') / (1 + alpha) * (mu.h / |mu|)^alpha'                      (3)
   The factor (1 + alpha')/(1 + alpha) keeps the lobe's integral over the sphere
   (2 pi / (1 + alpha) for (n.h)^alpha). With (1), alpha'/alpha = |mu| / (|mu| + alpha (1 - |mu|)):
   the "Toksvig factor" engines multiply the exponent (or the specular power) with.
   The same widening for microfacet roughness, from the small-angle variance of each NDF:
     Beckmann m   D ~ exp(-tan^2 t / m^2): angular variance m^2 / 2 per axis,
                  m'^2 = m^2 + 2 sigma^2;
     GGX alpha    a'^2 = a^2 + 2 sigma^2, i.e. GGX's a treated as a Beckmann m. GGX has no
                  finite slope variance; matching its peak curvature instead
                  ((1 + tan^2 t / a^2)^-2 ~ exp(-2 t^2 / a^2): a'^2 = a^2 + 4 sigma^2) fits
                  the convolution worse (tests/test_toksvig.c measures both; docs/toksvig.md).
                  A GGX lobe convolved with a Gaussian is not a GGX lobe: the measured
                  error is 16-24% of the peak for sigma <= 0.3, 52% at sigma = 0.5.
   Blinn-Phong and Beckmann are related by alpha_p = 2 / m^2 - 2 (the correspondence Walter et
   al. 2007 give for the Phong exponent: it makes the two normalized NDFs agree near the peak);
   m = sqrt(2 / (alpha_p + 2)).

   USAGE
     pf_vec3 mu = <trilinear sample of an average-normal pyramid>;
     pf_real var = pf_toksvig_variance_from_normal(mu);
     pf_real a2 = pf_toksvig_exponent(alpha, var);                      -- (2)
     pf_real spec = pf_toksvig_lobe(pf_vec3_dot(mu, h) / pf_vec3_length(mu), alpha, var); -- (3)
     pf_real m2 = pf_toksvig_beckmann_m(m, var);  pf_real a2 = pf_toksvig_ggx_alpha(a, var);

   FUNCTIONS (all in the shader subset)
     pf_toksvig_variance(len)              (1), robust to len -> 0 and len > 1
     pf_toksvig_variance_from_normal(mu)   (1) from the averaged vector
     pf_toksvig_factor(len, alpha)         alpha'/alpha = 1 / (1 + alpha sigma^2), from |mu|
     pf_toksvig_exponent(alpha, var)       (2)
     pf_toksvig_normalization(alpha, alpha_filtered)  (1 + alpha')/(1 + alpha)
     pf_toksvig_lobe(cos_theta, alpha, var)           (3), with cos = mu.h / |mu|
     pf_toksvig_beckmann_m(m, var), pf_toksvig_ggx_alpha(a, var)   widened roughness
     pf_blinn_phong_to_beckmann(alpha_p), pf_beckmann_to_blinn_phong(m)

   CONVENTIONS
     sigma^2 ("var") is the variance per axis of the angle between a normal and the mean normal
     (radians^2). Lengths are clamped to [PF_TOKSVIG_MIN_LENGTH, 1]: a length above 1 (trilinear
     interpolation of vectors, 8-bit decoding) means no spread (var = 0) and a length near 0
     (normals that cancel) gives the largest variance, (1 - 1e-4)/1e-4 ~ 1e4, finite. A NaN
     length counts as 0 (largest variance); NaN variances and negative ones count as 0.
     Exponents alpha >= 0; roughnesses m, a >= 0.

   ACCURACY AND COST (measured in tests/test_toksvig.c and bench/bench_toksvig.c, tables in
   docs/toksvig.md). Against the numerical convolution of the Blinn-Phong lobe with a Gaussian
   of the normal angle (2D quadrature over the sphere), for alpha in [1, 1e4] and sigma in
   [0, 0.5], and of Toksvig's variance estimate (1) against the true variance of Gaussian and
   von Mises-Fisher normal distributions. Each function is a few flops and at most one pow.

   SOURCES
     Toksvig 2005, "Mipmapping normal maps" (JGT 10(3)), as quoted in Bruneton & Neyret 2012
     sec. 3.2.1 (the formula after eq. 19) and sec. 7.2.2; Walter, Marschner, Li, Torrance 2007
     (Blinn-Phong exponent versus Beckmann roughness). */
#ifndef PF_TOKSVIG_H
#define PF_TOKSVIG_H

#ifndef PF_GLSL
#  include "pf_core.h"
#endif

/* Smallest length of an averaged normal that (1) sees: below it the normals cancel and the
   variance is capped at (1 - L)/L = 9999. */
#ifndef PF_TOKSVIG_MIN_LENGTH
#  define PF_TOKSVIG_MIN_LENGTH PF_R(1.0e-4)
#endif

/* (1): sigma^2 = (1 - L) / L with L = |mu| clamped to [PF_TOKSVIG_MIN_LENGTH, 1] (NaN -> the
   minimum). Range [0, 9999]. */
PF_DEF pf_real pf_toksvig_variance(pf_real length)
{
    pf_real l = pf_min(pf_max(length, PF_TOKSVIG_MIN_LENGTH), PF_R(1.0));
    return (PF_R(1.0) - l) / l;
}

/* (1) from the averaged (unnormalized) normal itself. */
PF_DEF pf_real pf_toksvig_variance_from_normal(pf_vec3 mu)
{
    return pf_toksvig_variance(pf_vec3_length(mu));
}

/* The Toksvig factor alpha'/alpha = 1 / (1 + alpha sigma^2) written with L = |mu|:
   L / (L + alpha (1 - L)), L clamped as in pf_toksvig_variance. In [0, 1]; alpha < 0 counts
   as 0 (factor 1). */
PF_DEF pf_real pf_toksvig_factor(pf_real length, pf_real alpha)
{
    pf_real l = pf_min(pf_max(length, PF_TOKSVIG_MIN_LENGTH), PF_R(1.0));
    return l / (l + pf_max(alpha, PF_R(0.0)) * (PF_R(1.0) - l));
}

/* (2): alpha' = alpha / (1 + alpha sigma^2). var < 0 or NaN counts as 0 (alpha' = alpha);
   alpha < 0 counts as 0. Monotone: alpha' <= alpha and alpha' <= 1/var. */
PF_DEF pf_real pf_toksvig_exponent(pf_real alpha, pf_real var)
{
    pf_real a = pf_max(alpha, PF_R(0.0));
    return a / (PF_R(1.0) + a * pf_max(var, PF_R(0.0)));
}

/* (1 + alpha')/(1 + alpha): keeps the integral of the lobe over the sphere. */
PF_DEF pf_real pf_toksvig_normalization(pf_real alpha, pf_real alpha_filtered)
{
    return (PF_R(1.0) + pf_max(alpha_filtered, PF_R(0.0))) / (PF_R(1.0) + pf_max(alpha, PF_R(0.0)));
}

/* (3): the filtered Blinn-Phong lobe (1 + alpha')/(1 + alpha) max(cos, 0)^alpha' for the
   unfiltered lobe max(cos, 0)^alpha (peak 1), cos_theta = mu.h / |mu|. */
PF_DEF pf_real pf_toksvig_lobe(pf_real cos_theta, pf_real alpha, pf_real var)
{
    pf_real af = pf_toksvig_exponent(alpha, var);
    pf_real c = pf_clamp(cos_theta, PF_R(0.0), PF_R(1.0));
    return pf_toksvig_normalization(alpha, af) * PF_POW(c, af);
}

/* Beckmann roughness widened by the normal spread: sqrt(m^2 + 2 sigma^2). */
PF_DEF pf_real pf_toksvig_beckmann_m(pf_real m, pf_real var)
{
    return PF_SQRT(m * m + PF_R(2.0) * pf_max(var, PF_R(0.0)));
}

/* GGX roughness widened by the normal spread: sqrt(a^2 + 2 sigma^2) (see the doc block). */
PF_DEF pf_real pf_toksvig_ggx_alpha(pf_real a, pf_real var)
{
    return PF_SQRT(a * a + PF_R(2.0) * pf_max(var, PF_R(0.0)));
}

/* Beckmann m of a Blinn-Phong exponent (Walter et al. 2007): sqrt(2 / (alpha_p + 2)).
   alpha_p < 0 counts as 0 (m = 1). */
PF_DEF pf_real pf_blinn_phong_to_beckmann(pf_real alpha_p)
{
    return PF_SQRT(PF_R(2.0) / (pf_max(alpha_p, PF_R(0.0)) + PF_R(2.0)));
}

/* Blinn-Phong exponent of a Beckmann m (Walter et al. 2007): 2/m^2 - 2, clamped at 0 (m >= 1
   has no Blinn-Phong match); m is floored at 1e-18 (float: 1e-18 squared is still normal)
   so the result stays finite. */
PF_DEF pf_real pf_beckmann_to_blinn_phong(pf_real m)
{
    pf_real mc = pf_max(PF_FABS(m), PF_R(1.0e-18));
    return pf_max(PF_R(2.0) / (mc * mc) - PF_R(2.0), PF_R(0.0));
}

#endif /* PF_TOKSVIG_H */

/* pf_beckmann.h - noncentered anisotropic Beckmann distribution from five linear slope
   moments, and the LEADR specular BRDF (Dupuy et al. 2013).

   (doc block completed below with the evaluators)

   SOURCES
     Dupuy, Heitz, Iehl, Poulin, Neyret, Ostromoukhov 2013, "Linear Efficient Antialiased
     Displacement and Reflectance Mapping" (LEADR), eqs. 1-17; Olano & Baker 2010 (LEAN),
     as summarized in Bruneton & Neyret 2012 sec. 3.2.1, eq. 19. */
#ifndef PF_BECKMANN_H
#define PF_BECKMANN_H

#ifndef PF_GLSL
#  include "pf_smith.h"
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

/* The raw moments of a distribution with the given mean and covariance (inverse of eq. 9). */
PF_DEF pf_slope_moments pf_slope_moments_from_stats(pf_slope_stats s)
{
    return pf_slope_moments_make(s.mean_x, s.mean_y, s.var_x + s.mean_x * s.mean_x,
                                 s.var_y + s.mean_y * s.mean_y, s.cov_xy + s.mean_x * s.mean_y);
}

/* Smallest slope variance added to each axis by pf_slope_moments_stats, whatever base
   roughness the caller asks for. It keeps the covariance invertible (determinant >= its
   square) when filtering made it singular (a flat footprint, |r| = 1) and keeps the peak of D,
   1/(2 pi sqrt(det)), far from float overflow: 1e-6 is a slope deviation of 1e-3 (0.06 deg),
   below what any texture or display resolves, with a peak of D of 1.6e5. */
#ifndef PF_BECKMANN_MIN_VAR
#  define PF_BECKMANN_MIN_VAR PF_R(1.0e-6)
#endif

/* Statistics of the filtered slopes with a base roughness: the mean slope, and the covariance
   of eq. 9 plus base_var on both variances (the micro-BRDF's own slope variance, added as
   LEAN and LEADR do: the convolution of two Gaussians adds their covariances).
   Robust to what filtering and rounding produce: a negative variance is clamped to 0, the
   covariance to |c_xy| <= sigma_x sigma_y (|r| <= 1), and then max(base_var,
   PF_BECKMANN_MIN_VAR) is added, so the result is always positive definite.
   A NaN base_var counts as 0 (the minimum applies). */
PF_DEF pf_slope_stats pf_slope_moments_stats(pf_slope_moments m, pf_real base_var)
{
    pf_slope_stats s = pf_slope_stats_from_moments(m.ex, m.ey, m.exx, m.eyy, m.exy);
    pf_real b = pf_max(base_var, PF_BECKMANN_MIN_VAR);
    s.var_x += b;
    s.var_y += b;
    return s;
}

/* Correlation r = c_xy / (sigma_x sigma_y) of a covariance, 0 when a variance is 0. */
PF_DEF pf_real pf_slope_stats_correlation(pf_slope_stats s)
{
    pf_real d = PF_SQRT(pf_max(s.var_x, PF_R(0.0)) * pf_max(s.var_y, PF_R(0.0)));
    return d > PF_R(0.0) ? pf_clamp(s.cov_xy / d, PF_R(-1.0), PF_R(1.0)) : PF_R(0.0);
}

#endif /* PF_BECKMANN_H */

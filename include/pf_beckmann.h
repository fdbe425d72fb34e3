/* pf_beckmann.h - noncentered anisotropic Beckmann distribution from five linear slope
   moments, and the LEADR specular BRDF (Dupuy et al. 2013).

   A LEAN/LEADR map stores, per texel, the five moments E[x], E[y], E[x^2], E[y^2], E[xy] of
   the micro-slopes. They are linear, so mipmapping and bilinear filtering average them
   correctly (pf_moments.h). After filtering, this header turns them into the mean slope and
   slope covariance of the pixel footprint, the normal distribution D of that footprint (a
   Beckmann lobe whose mean slope need not be zero), and the physically based specular BRDF
   of LEADR eq. 17: normalized, with the reflection Jacobian, the projected-area
   normalization and Smith's joint masking-shadowing of the noncentered distribution.

   USAGE
     #include "pf_beckmann.h"
     pf_slope_moments m = ...;                          -- filtered texture fetch (5 channels)
     pf_slope_stats s = pf_slope_moments_stats(m, base_var);   -- + micro-BRDF roughness
     pf_real I = pf_leadr_specular(wo, wi, s, f0);      -- times the light's radiance

   FUNCTIONS
     moments      pf_slope_moments_make, _from_slope, _from_normal, _add, _scale,
                  _from_stats, pf_slope_moments_stats, pf_slope_stats_correlation
     deformation  pf_slope_moments_deform (eq. 12), pf_slope_moments_scale_height
     distribution pf_beckmann_p22 (eq. 8), pf_beckmann_d (eq. 10), pf_beckmann_mesonormal
                  (eq. 11), pf_beckmann_projected_area (eq. 1), pf_beckmann_lambda,
                  pf_beckmann_g1, pf_beckmann_masking_shadowing (eq. 13)
     BRDF         pf_fresnel_schlick, pf_leadr_specular (eq. 17), pf_leadr_specular_masking
                  (LEADR sec. 6), pf_leadr_specular_point

   CONVENTIONS
     Directions are in the tangent frame of the macrosurface (w_g = +z). A micro-normal n has
     slope (-n.x/n.z, -n.y/n.z) = (dh/dx, dh/dy) for a height field h; the mesonormal is
     (-E[x], -E[y], 1)/norm. pf_leadr_specular returns the reflected radiance for unit light
     radiance, the light's cosine included (a classic BRDF times cos theta_i); directions on or
     below the macrosurface or the mean plane give 0, never NaN.

   CONFIGURATION
     PF_BECKMANN_MIN_VAR   smallest slope variance pf_slope_moments_stats adds (default 1e-6)

   ACCURACY AND COST (measured; docs/beckmann.md has the tables, tests/test_beckmann.c the
   oracles, bench/bench_beckmann.c the timings)
     D, P22: relative error a few eps times the condition number (1 + q/2)(1 + 1/(1 - r^2) + ...)
     of the Gaussian (q/2 its exponent, r the correlation); the LEADR BRDF inherits it.
     LEADR specular costs about 2.5-3.5x a LEAN lobe on a CPU (see the bench).

   SOURCES
     Dupuy, Heitz, Iehl, Poulin, Neyret, Ostromoukhov 2013, "Linear Efficient Antialiased
     Displacement and Reflectance Mapping" (LEADR), eqs. 1-17; Olano & Baker 2010 (LEAN),
     as summarized in Bruneton & Neyret 2012 sec. 3.2.1, eq. 19; Schlick 1994 (Fresnel). */
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

/* ---------------------------------------------------------------- macrosurface deformation
   Dupuy et al. 2013 sec. 4.2, eq. 12. The map stores slopes in texture space (u, v):
   (du_slope, dv_slope) = (dh/du, dh/dv). On the deformed macrosurface, with orthonormal tangent
   coordinates (x, y), the chain rule gives the slopes
       x_slope = du/dx u_slope + dv/dx v_slope,    y_slope = du/dy u_slope + dv/dy v_slope,
   a linear map of the slopes. A linear map transforms raw second moments exactly as eq. 12
   transforms the central ones, so it is applied straight to the filtered moment struct: the
   result is still linear in the footprint and exact (for a locally constant Jacobian). */
PF_DEF pf_slope_moments pf_slope_moments_deform(pf_slope_moments m, pf_real du_dx, pf_real dv_dx,
                                                pf_real du_dy, pf_real dv_dy)
{
    pf_slope_moments r;
    r.ex = du_dx * m.ex + dv_dx * m.ey;
    r.ey = du_dy * m.ex + dv_dy * m.ey;
    r.exx = du_dx * du_dx * m.exx + dv_dx * dv_dx * m.eyy + PF_R(2.0) * du_dx * dv_dx * m.exy;
    r.eyy = du_dy * du_dy * m.exx + dv_dy * dv_dy * m.eyy + PF_R(2.0) * du_dy * dv_dy * m.exy;
    r.exy = du_dx * du_dy * m.exx + dv_dx * dv_dy * m.eyy + (du_dx * dv_dy + dv_dx * du_dy) * m.exy;
    return r;
}

/* Height scaling by eta (Dupuy et al. 2013 sec. 4.2): slopes scale by eta, so first moments by
   eta and second moments by eta^2. eta = 0 flattens the surface (a mirror plus base roughness). */
PF_DEF pf_slope_moments pf_slope_moments_scale_height(pf_slope_moments m, pf_real eta)
{
    pf_real e2 = eta * eta;
    return pf_slope_moments_make(eta * m.ex, eta * m.ey, e2 * m.exx, e2 * m.eyy, e2 * m.exy);
}

/* ---------------------------------------------------------------- distribution
   Smallest variance the evaluators below work with (each axis): its square, the smallest
   determinant floor (4 eps times its square, see pfi_beckmann_det) must stay a normal number.
   A variance under it (a covariance given directly, not through pf_slope_moments_stats) is
   read as this value: D stays a Gaussian, of deviation 3e-8 (float) or 1e-70 (double),
   instead of 0/0. */
#ifdef PF_DOUBLE
#  define PFI_BECKMANN_VAR_FLOOR PF_R(1.0e-140)
#else
#  define PFI_BECKMANN_VAR_FLOOR PF_R(1.0e-15)
#endif
/* Largest variance they work with: its square (var_x var_y in the determinant) must stay
   finite; var_x near PF_REAL_MAX made var_x var_y = inf and inf/inf = NaN. A larger variance
   (a slope deviation above 3e7 (float) / 1e75 (double), where D and P22 are flat and below
   1e-16 / 1e-151 everywhere) is read as this value. */
#ifdef PF_DOUBLE
#  define PFI_BECKMANN_VAR_CEIL PF_R(1.0e150)
#else
#  define PFI_BECKMANN_VAR_CEIL PF_R(1.0e15)
#endif

PF_DEF pf_slope_stats pfi_beckmann_floor(pf_slope_stats s)
{
    s.var_x = pf_min(pf_max(s.var_x, PFI_BECKMANN_VAR_FLOOR), PFI_BECKMANN_VAR_CEIL);
    s.var_y = pf_min(pf_max(s.var_y, PFI_BECKMANN_VAR_FLOOR), PFI_BECKMANN_VAR_CEIL);
    return s;
}

/* The determinant of a (floored) slope covariance, kept at least 4 eps sigma_x^2 sigma_y^2
   (|r| <= 1 - 2 eps: below that the rounding of var_x var_y - c^2 exceeds its value, so the
   data carry no more information), hence > 0 and 1/sqrt(det) finite. */
PF_DEF pf_real pfi_beckmann_det(pf_slope_stats s)
{
    pf_real vv = s.var_x * s.var_y;
    return pf_max(vv - s.cov_xy * s.cov_xy, PF_R(4.0) * PF_REAL_EPSILON * vv);
}

/* Cap on the Gaussian's exponent q/2: exp(-PFI_BECKMANN_EXP_CAP) is 0 in pf_real, so capping
   changes no result but keeps q/(2 det) finite (no inf, so -ffast-math stays defined). */
#ifdef PF_DOUBLE
#  define PFI_BECKMANN_EXP_CAP PF_R(1500.0)
#else
#  define PFI_BECKMANN_EXP_CAP PF_R(200.0)
#endif

/* exp(-q / (2 det)) for a quadratic form q >= 0 (adjugate form) without overflow. */
PF_DEF pf_real pfi_beckmann_gauss(pf_real q, pf_real det)
{
    return PF_EXP(-pf_min(PF_R(0.5) * pf_max(q, PF_R(0.0)), PFI_BECKMANN_EXP_CAP * det) / det);
}

/* Slope PDF P22(x, y) (Dupuy et al. 2013 eq. 8): the bivariate normal of mean (mean_x, mean_y)
   and covariance s,
       P22 = exp(-d^T Sigma^-1 d / 2) / (2 pi sqrt(det Sigma)),   d = (x, y) - mean.
   Sigma^-1 = adj(Sigma)/det, so the quadratic form needs one division. A singular or
   indefinite covariance is read with the floors of pfi_beckmann_floor and pfi_beckmann_det:
   the result is finite and >= 0 for every finite input (in float at most
   1/(2 pi sqrt(4 eps 1e-30)) = 2.3e17). */
PF_DEF pf_real pf_beckmann_p22(pf_real x, pf_real y, pf_slope_stats s0)
{
    pf_slope_stats s = pfi_beckmann_floor(s0);
    pf_real det = pfi_beckmann_det(s);
    pf_real dx = x - s.mean_x, dy = y - s.mean_y;
    pf_real q = s.var_y * dx * dx - PF_R(2.0) * s.cov_xy * dx * dy + s.var_x * dy * dy;
    return pfi_beckmann_gauss(q, det) * (PF_R(0.5) * PF_INV_PI) / PF_SQRT(det);
}

/* Normal distribution function D(w_m) = P22(slope(w_m)) / cos^4 theta_m (Dupuy et al. 2013
   eq. 10), per unit solid angle, normalized so that integral D(w_m) (w_m . w_g) dw_m = 1.
   w_m need not be unit length: with slope (-m.x/m.z, -m.y/m.z), the quadratic form is written
   over m.z^2 and 1/cos^4 = (|m|^2/m.z^2)^2, so no square root or normalization is needed.
   m.z <= 0 (a micro-normal facing down, which a height field cannot have) gives 0. The factor
   |m|^2/m.z^2 is capped at 1e9 (m within 0.002 deg of the horizon), where the Gaussian factor
   is already 0 unless the mean slope is near 3e4, so D stays finite. Finite and >= 0 for
   every finite statistics and every m with m.z^2 finite (m.z below 1.8e19 in float, 1.3e154
   in double; a longer m gives inf/inf = NaN: normalize it first). */
PF_DEF pf_real pf_beckmann_d(pf_vec3 m, pf_slope_stats s0)
{
    pf_slope_stats s = pfi_beckmann_floor(s0);
    pf_real z2, det, X, Y, q, r2;
    if (!(m.z > PF_R(0.0))) return PF_R(0.0);
    z2 = m.z * m.z;
    det = pfi_beckmann_det(s);
    /* m.z * (slope - mean) */
    X = -m.x - s.mean_x * m.z;
    Y = -m.y - s.mean_y * m.z;
    q = s.var_y * X * X - PF_R(2.0) * s.cov_xy * X * Y + s.var_x * Y * Y;
    /* exp(-q / (2 det z2)); z2 and det z2 floored so nothing divides by 0 (D is then 0) */
    r2 = pf_min(m.x * m.x + m.y * m.y + z2, PF_R(1.0e9) * z2) / pf_max(z2, PF_REAL_MIN);
    return pfi_beckmann_gauss(q, pf_max(det * z2, PF_REAL_MIN)) * r2 * r2 *
           (PF_R(0.5) * PF_INV_PI) / PF_SQRT(det);
}

/* The mesonormal (Dupuy et al. 2013 eq. 11): the unit normal of the mean plane,
   (-E[x], -E[y], 1) / sqrt(1 + E[x]^2 + E[y]^2). */
PF_DEF pf_vec3 pf_beckmann_mesonormal(pf_slope_stats s)
{
    return pf_vec3_normalize(pf_vec3_make(-s.mean_x, -s.mean_y, PF_R(1.0)));
}

/* Projected area of the mesosurface toward w per unit macrosurface area (Dupuy et al. 2013
   eq. 1): (w_nbar . w) / (w_nbar . w_g) = w.z - E[x] w.x - E[y] w.y for a unit w. This is the
   normalization of eqs. 2, 7, 16 and 17 (they divide by it). Clamped at 0: a direction on or
   below the mean plane sees none of it. */
PF_DEF pf_real pf_beckmann_projected_area(pf_vec3 w, pf_slope_stats s)
{
    return pf_max(w.z - s.mean_x * w.x - s.mean_y * w.y, PF_R(0.0));
}

/* Smith's Lambda of the noncentered Beckmann distribution for direction w (Dupuy et al. 2013
   eqs. 14-15; pf_smith_nu and the exact pf_lambda_beckmann). PF_LAMBDA_MAX on or below the
   mean plane. w need not be normalized. */
PF_DEF pf_real pf_beckmann_lambda(pf_vec3 w, pf_slope_stats s)
{
    return pf_lambda_beckmann(pf_smith_nu(w, s));
}

/* Masking G1 = 1/(1 + Lambda(w)); 0 on or below the mean plane. */
PF_DEF pf_real pf_beckmann_g1(pf_vec3 w, pf_slope_stats s)
{
    return pf_g1_beckmann(pf_smith_nu(w, s));
}

/* Joint masking-shadowing moment E[V_o V_i] = 1/(1 + Lambda(w_o) + Lambda(w_i)) (Dupuy et al.
   2013 eq. 13); 0 when either direction is on or below the mean plane. */
PF_DEF pf_real pf_beckmann_masking_shadowing(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s)
{
    return pf_g2_beckmann(pf_smith_nu(wo, s), pf_smith_nu(wi, s));
}

/* ---------------------------------------------------------------- specular BRDF
   Schlick's Fresnel approximation F = f0 + (1 - f0) (1 - cos)^5, cos = w_h . w_i clamped to
   [0, 1]. f0 = 1 gives exactly 1 (Fresnel off). */
PF_DEF pf_real pf_fresnel_schlick(pf_real f0, pf_real cos_theta)
{
    pf_real t = PF_R(1.0) - pf_saturate(cos_theta);
    pf_real t2 = t * t;
    return f0 + (PF_R(1.0) - f0) * (t2 * t2 * t);
}

/* The LEADR specular radiance factor: reflected radiance toward w_o per unit radiance of a
   directional (or point) light from w_i (Dupuy et al. 2013 eq. 17, with L = 1):
       I = F(w_h, w_i) D(w_h) G / (4 A_o),
       A_o = (w_nbar . w_o)/(w_nbar . w_g),  w_h = (w_o + w_i)/|w_o + w_i|,
   with G = 1/(1 + Lambda_o + Lambda_i) (eq. 13; pfi_leadr_specular's masking_only = 0) or the
   masking term 1/(1 + Lambda_o) alone (masking_only = 1, LEADR sec. 6, for renderers that shadow
   elsewhere). The cosine of the light is already in it: I is what a classic BRDF times
   cos theta_i would give (for a centered distribution, A_o = cos theta_o and I = F D G /
   (4 cos theta_o)); multiply by the light's radiance (directional) or intensity / distance^2
   (point), not by any further cosine.
   w_o, w_i: unit vectors in the tangent frame of the macrosurface (w_g = +z). Returns 0, never
   NaN, when either direction is on or below the macrosurface or the mesosurface. Fresnel uses
   w_h . w_i = sqrt((1 + w_o . w_i)/2) (no normalization of w_h needed); f0 = 1 turns it off. */
PF_DEF pf_real pfi_leadr_specular(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real f0,
                                  int masking_only)
{
    pf_real area_o = wo.z - s.mean_x * wo.x - s.mean_y * wo.y;
    pf_real area_i = wi.z - s.mean_x * wi.x - s.mean_y * wi.y;
    pf_real g, d, f;
    if (!(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0)) || !(area_o > PF_R(0.0)) ||
        !(area_i > PF_R(0.0)))
        return PF_R(0.0);
    if (masking_only != 0)
        g = pf_g1_beckmann(pf_smith_nu(wo, s));
    else
        g = pf_g2_beckmann(pf_smith_nu(wo, s), pf_smith_nu(wi, s));
    d = pf_beckmann_d(pf_vec3_add(wo, wi), s);
    f = pf_fresnel_schlick(f0, PF_SQRT(pf_max(PF_R(0.5) + PF_R(0.5) * pf_vec3_dot(wo, wi), PF_R(0.0))));
    return f * d * g / (PF_R(4.0) * area_o);
}

/* LEADR specular with joint masking-shadowing (eq. 17). See pfi_leadr_specular. */
PF_DEF pf_real pf_leadr_specular(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real f0)
{
    return pfi_leadr_specular(wo, wi, s, f0, 0);
}

/* LEADR specular with masking only, 1/(1 + Lambda_o) (LEADR sec. 6). See pfi_leadr_specular. */
PF_DEF pf_real pf_leadr_specular_masking(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real f0)
{
    return pfi_leadr_specular(wo, wi, s, f0, 1);
}

/* Point light: to_light is the (unnormalized) vector from the shaded point to the light in the
   tangent frame; returns the radiance per unit light intensity, pf_leadr_specular(w_o,
   to_light/|to_light|) / |to_light|^2. 0 for a zero vector. */
PF_DEF pf_real pf_leadr_specular_point(pf_vec3 wo, pf_vec3 to_light, pf_slope_stats s, pf_real f0)
{
    pf_real d2 = pf_vec3_dot(to_light, to_light);
    if (!(d2 > PF_R(0.0))) return PF_R(0.0);
    return pf_leadr_specular(wo, pf_vec3_scale(to_light, PF_R(1.0) / PF_SQRT(d2)), s, f0) / d2;
}

#endif /* PF_BECKMANN_H */

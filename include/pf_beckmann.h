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
     below the macrosurface, and a light on or below the mean plane, give 0, never NaN; a view
     below the mean plane but above the macrosurface sees the facets that face it.

   CONFIGURATION
     PF_BECKMANN_MIN_VAR   smallest slope variance pf_slope_moments_stats adds (default 1e-6)

   ACCURACY AND COST (measured; docs/beckmann.md has the tables, tests/test_beckmann.c the
   oracles, bench/bench_beckmann.c the timings)
     D, P22: relative error a few eps times the condition number (1 + q/2)(1 + 1/(1 - r^2) + ...)
     of the Gaussian (q/2 its exponent, r the correlation); the LEADR BRDF inherits it.
     GPU cost (SPIR-V ops after spirv-opt -O, bench/gpu/count.sh): pf_beckmann_d 31
     ops, branch-free; the LEAN lobe as shipped, for a unit half vector and no guards: 27;
     pf_leadr_specular 116 ops (LEAN lobe x Walter G1(o) G1(i) x Schlick / (4 cos): 97),
     with the exact G1 of pf_smith.h, not Walter's 3e-3 rational. Every guard is a floor or a
     cap applied once, and one select replaces the early returns for directions below the
     surface. On a CPU the LEADR specular costs about 2.5-3.5x a LEAN lobe (see the bench).

   SOURCES
     Dupuy, Heitz, Iehl, Poulin, Neyret, Ostromoukhov 2013, "Linear Efficient Antialiased
     Displacement and Reflectance Mapping" (LEADR), eqs. 1-17; Olano & Baker 2010 (LEAN),
     as summarized in Bruneton & Neyret 2012 sec. 3.2.1, eq. 19; Schlick 1994 (Fresnel). */
#ifndef PF_BECKMANN_H
#define PF_BECKMANN_H

#ifndef PF_GLSL
#  include "pf_smith.h"
#  include "pf_moments.h"
#endif

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

/* Lean evaluation of D (close to the LEAN lobe's cost, robustness kept). Floors
   and caps, each applied once:
   - the variances clamped to [PFI_BECKMANN_VAR_FLOOR, PFI_BECKMANN_VAR_CEIL] as in P22 (a
     determinant floor alone would keep det > 0 but flatten a degenerate axis: q/det along it
     would lose the other variance's scale);
   - det = max(var_x var_y - c_xy^2, PFI_BECKMANN_DET_MIN): > 0, so 1/sqrt(det) is finite (at
     most 1.4e18 in float, 1e148 in double) whatever the covariance (singular or
     indefinite: read as the narrowest Gaussian the type holds along the bad direction);
   - the exponent q/det is clamped to [0, PFI_BECKMANN_QDET_CAP]: an indefinite covariance
     (q < 0) cannot overflow exp, and at the cap exp(-cap/2) is 0 in pf_real, so the cap
     changes no result; a NaN q (inf - inf in the form, slopes near PF_REAL_MAX) reads as 0
     (C, CUDA; GLSL: the GPU's clamp, see pf_core.h);
   - 1/cos^2 = 1 + |slope|^2 is capped at 1e9 (the micro-normal within 0.002 deg of the
     horizon, where D is already 0 unless the mean slope is near 3e4): its square times the
     peak stays finite (1e18 x 1.4e18 / (2 pi) in float).
   1/(2 pi) rides in the exponent (exp(ln(1/(2 pi)) - q/(2 det))): one multiply less. */
#ifdef PF_DOUBLE
#  define PFI_BECKMANN_DET_MIN PF_R(8.9e-296)  /* 4 eps (1e-140)^2, as the variance floor gave */
#  define PFI_BECKMANN_QDET_CAP PF_R(3000.0)   /* exp(-1500) = 0 in double */
#else
#  define PFI_BECKMANN_DET_MIN PF_R(4.8e-37)   /* 4 eps (1e-15)^2 */
#  define PFI_BECKMANN_QDET_CAP PF_R(400.0)    /* exp(-200) = 0 in float */
#endif
#define PFI_LN_INV_2PI PF_R(-1.83787706640934548356065947281123527)

/* 1/sqrt(x): GLSL's inversesqrt (one instruction), else 1/PF_SQRT(x). */
#ifdef PF_GLSL
PF_DEF pf_real pfi_beckmann_rsqrt(pf_real x) { return inversesqrt(x); }
#else
PF_DEF pf_real pfi_beckmann_rsqrt(pf_real x) { return PF_R(1.0) / PF_SQRT(x); }
#endif

/* D for m.z > 0 (the caller tests it), times exp(ln_scale - ln(2 pi)): see pf_beckmann_d. A
   constant factor of the caller rides in the exponent at no cost; ln_scale = 0 gives D itself. */
PF_DEF pf_real pfi_beckmann_d_up(pf_vec3 m, pf_slope_stats s, pf_real ln_scale)
{
    pf_real iz = PF_R(1.0) / m.z;
    pf_real sx = m.x * iz, sy = m.y * iz;         /* minus the slope of m */
    pf_real X = sx + s.mean_x, Y = sy + s.mean_y; /* minus (slope - mean): q is even */
    pf_real r2 = pf_min(sx * sx + (sy * sy + PF_R(1.0)), PF_R(1.0e9)); /* 1/cos^2; NaN -> cap (C) */
    /* the variance floor keeps q/det a Gaussian's exponent when a variance is tiny (the
       determinant floor alone would flatten a degenerate axis); the ceiling keeps
       var_x var_y finite */
    pf_real vx = pf_clamp_nan_lo(s.var_x, PFI_BECKMANN_VAR_FLOOR, PFI_BECKMANN_VAR_CEIL);
    pf_real vy = pf_clamp_nan_lo(s.var_y, PFI_BECKMANN_VAR_FLOOR, PFI_BECKMANN_VAR_CEIL);
    pf_real det = pf_max(vx * vy - s.cov_xy * s.cov_xy, PFI_BECKMANN_DET_MIN);
    /* adj(Sigma) quadratic form: var_y X^2 - 2 c X Y + var_x Y^2; c Y first: c near PF_REAL_MAX
       with Y = 0 gives 0, not (-2 c = -inf) * 0 */
    pf_real q = X * (vy * X + (s.cov_xy * Y) * PF_R(-2.0)) + vx * Y * Y;
    pf_real rs = pfi_beckmann_rsqrt(det);
    pf_real e = pf_clamp_nan_lo(q * rs * rs, PF_R(0.0), PFI_BECKMANN_QDET_CAP);
    return PF_EXP(PF_R(-0.5) * e + (PFI_LN_INV_2PI + ln_scale)) * r2 * r2 * rs;
}

/* Normal distribution function D(w_m) = P22(slope(w_m)) / cos^4 theta_m (Dupuy et al. 2013
   eq. 10), per unit solid angle, normalized so that integral D(w_m) (w_m . w_g) dw_m = 1.
   w_m need not be unit length: the slope is (-m.x/m.z, -m.y/m.z) and 1/cos^2 = 1 + |slope|^2.
   m.z <= 0 (a micro-normal facing down, which a height field cannot have) gives 0. Any
   finite statistics: see the floors above. Finite and >= 0 for every finite m and
   statistics. Cost: within 1.1x of the LEAN lobe on a GPU,
   branch-free; see docs/beckmann.md. */
PF_DEF pf_real pf_beckmann_d(pf_vec3 m, pf_slope_stats s)
{
    pf_real d = pfi_beckmann_d_up(m, s, PF_R(0.0));
    return m.z > PF_R(0.0) ? d : PF_R(0.0);
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

/* P(w) = E[max(0, w.z - x w.x - y w.y)], the projected area toward w of the facets that face
   it, per unit macrosurface area: the P_o of pfi_leadr_specular's comment (the positive part
   of a normal variable of mean A = the eq. 1 area and deviation sqrt(var_w)),
       P = max(A, 0) + sqrt(2 var_w) m Lambda(m),   m = |A| / sqrt(2 var_w),
   = A (1 + Lambda(w)) above the mean plane (Smith), > 0 below it. m Lambda(m) is formed
   without the division of pf_lambda_beckmann (m < 2: exp(-m^2) K(m) / (2 sqrt(pi)), finite
   at m = 0), so P is accurate to a few ulp at every A, with no cancellation below the mean
   plane (unlike the G1 form pfi_leadr_specular uses). Zero deviation along w (or NaN
   statistics): max(A, 0). For the evaluators that fold G / A_o into 1 / (P_o + A_o+ Lambda_i)
   (pf_gaussgrid.h, pf_vmf.h). w need not be unit length. */
PF_DEF pf_real pf_beckmann_facing_area(pf_vec3 w, pf_slope_stats s)
{
    pf_real a = w.z - s.mean_x * w.x - s.mean_y * w.y;
    pf_real var2 = PF_R(2.0) * (w.x * w.x * s.var_x + w.y * w.y * s.var_y + PF_R(2.0) * w.x * w.y * s.cov_xy);
    pf_real sd = PF_SQRT(pf_clamp_nan_lo(var2, PF_R(0.0), PF_R(0.25) * PF_REAL_MAX));
    pf_real front = pf_max(a, PF_R(0.0)), m, t;
    if (!(sd > PF_R(1.0e-12) * PF_FABS(a))) return front;
    m = PF_FABS(a) / sd;
    t = m < PF_R(2.0) ? pf_exp_neg_sq(m) * pf_smith_k(m) * (PF_R(0.5) * PF_INV_SQRT_PI)
                      : m * pf_lambda_beckmann(m);
    return front + sd * t;
}

/* Lambda of the LIGHT in the specular BRDFs (pf_leadr_specular; pf_vmf.h), from nu_i =
   A_i / sqrt(2 var_i) (A_i the mean plane's projected area toward wi, eq. 1), rs_i =
   1 / sqrt(2 var_i) and wi.z:
       Lambda_i' = Lambda_i (Smith)                          for a light above the mean plane,
       Lambda_i' = max(P_i(0), wi.z) / wi.z - 1               on or below it (A_i <= 0),
   P_i(0) = sqrt(var_i / (2 pi)) the projected area toward wi of the facets that face it, with
   A_i counted as 0 (as A_o is for the view; pf_beckmann_facing_area).
   Why (our model): Smith's Lambda_i takes the footprint's mean
   plane as unbounded, so a light on or below it shadows everything and eq. 17 gave 0. On a
   flat macrosurface (normal or bump mapping) the footprint's tilt is local: a light above the
   macrosurface still reaches the facets that face it, and the brute force lights them
   (bench/pictures.c: 12-48 lit pixels returned 0). Over the macrosurface, light falls on wi.z
   of projected area per unit area and is shared by the facets facing it, so their lit
   fraction is at least wi.z / P_i (Smith's G1 of the macrosurface's own plane). ABOVE the
   mean plane Smith's Lambda_i is kept exactly: it is exact for a footprint whose mean plane is
   real geometry (a single tilted facet, tests/test_microsurface.c's identity; LEADR's displaced
   mesosurface), which capping it there too (min(Lambda_i, max(P_i, wi.z) / wi.z - 1) for every
   light) breaks (up to 14x at grazing lights). The price: the value jumps at A_i = 0, from Smith's 0
   just above the plane to the facing facets' share just below. Form: 1 + Lambda_i' =
   max(r / d, 1), r = nu / G1(nu) at nu = max(nu_i, 1e-20) (pf_smith_nu_over_g1), d = nu_i
   above the plane (1/G1), wi.z rs_i below (P_i(0) / wi.z). Finite for wi.z > 0, rs_i > 0 and
   nu_i = 0 or |nu_i| >= 1e-20: as nu_i -> 0+ (a light grazing the mean plane) it grows as
   0.28 / nu_i, +inf once that overflows (G = 0 in the BRDFs). */
PF_DEF pf_real pf_beckmann_light_lambda(pf_real nu, pf_real rs, pf_real wz)
{
    pf_real below = wz * rs; /* a plain variable: the select below compiles to a select, not a branch */
    pf_real d = nu > PF_R(0.0) ? nu : below;
    return pf_max(pf_smith_nu_over_g1(pf_max(nu, PF_R(1.0e-20))) / d, PF_R(1.0)) - PF_R(1.0);
}

/* The same from the direction and the statistics (pf_vmf.h's one-Gaussian G): the variance
   along wi clamped once to [PF_REAL_MIN, PF_REAL_MAX/4] as in pfi_leadr_specular. */
PF_DEF pf_real pf_beckmann_light_lambda_stats(pf_vec3 wi, pf_slope_stats s)
{
    pf_real var2 = PF_R(2.0) * (wi.x * wi.x * s.var_x + wi.y * wi.y * s.var_y + PF_R(2.0) * wi.x * wi.y * s.cov_xy);
    pf_real rs = pfi_beckmann_rsqrt(pf_clamp_nan_lo(var2, PF_REAL_MIN, PF_R(0.25) * PF_REAL_MAX));
    return pf_beckmann_light_lambda((wi.z - s.mean_x * wi.x - s.mean_y * wi.y) * rs, rs, wi.z);
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
   NaN, when either direction is on or below the macrosurface. A view above the macrosurface
   but on or below the mesosurface is not culled: it sees the facets that face it (below). A
   light above the macrosurface but on or below the mesosurface is not culled either: Lambda_i
   is pf_beckmann_light_lambda's, Smith's capped by the macrosurface's share of the light
   (Dupuy et al. 2013 after eq. 15 have Lambda_i = inf there: the footprint's mean plane,
   taken as unbounded, shadows everything; bench/pictures.c). Fresnel uses w_h . w_i =
   sqrt((1 + w_o . w_i)/2) (no normalization of w_h needed); f0 = 1 turns it off.

   Projected area of the facets facing the view (bench/pictures.c's pic_plane). Eq. 17
   divides by the signed projected area A_o of the mean plane (eq. 1), and G = 0 when A_o <= 0:
   LEADR renders displaced geometry, where such a patch faces away and is backface-culled
   (sec. 4.3). On a flat macrosurface (normal or bump mapping) nothing else covers the pixel,
   and A_o <= 0 happens at grazing views wherever a footprint's mean tilt exceeds the view's
   elevation; the bench's brute force (bench/pictures.c) lights those pixels. The fix rewrites
   G / A_o with P_o = E[max(0, w_o.z - x w_o.x - y w_o.y)], the projected area toward w_o of
   the facets that face it, which for Gaussian slopes and nu = A_o / sqrt(2 var_o) is
       P_o = max(A_o, 0) + sqrt(2 var_o) |nu| Lambda(|nu|)                  (our derivation)
   (the mean of the positive part of a normal variable), i.e. A_o (1 + Lambda_o) above the
   mean plane: Smith's normalization. Then G / A_o = 1 / (P_o + A_o Lambda_i): the radiance of
   the facets facing the viewer averaged over their projected area, times the fraction that is
   lit, which tends to 1 as A_o -> 0 (only the highest points are seen). That form is eq. 17
   exactly where A_o > 0, continuous through A_o = 0, and below keeps its limit (A_o counted
   as 0). Below the mean plane P_o comes from G1 as (|nu|/G1(|nu|) - |nu|) sqrt(2 var_o), which
   cancels as G1 -> 1: measured relative error of the result in float 3e-6 at nu = -0.5, 2e-5
   at -1, 2e-4 at -1.5, 2e-3 at -2, 3% at -2.5, 50% at -3 (double: <= 7e-11 down to -3). The
   grazing views of a flat macrosurface sit at nu > -0.5 (bench/pictures.c). Exact at any nu,
   for one exp and a branch more: P_o = max(A_o, 0) + sqrt(2 var_o) |nu| pf_lambda_beckmann(|nu|). */
/* (sg: the statistics whose covariance the masking-shadowing G uses; s itself in eq. 17, the
   footprint's own without the base variance in pf_leadr_specular_base) */
PF_DEF pf_real pfi_leadr_specular(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_slope_stats sg, pf_real f0,
                                  int masking_only)
{
    pf_real area_o = wo.z - s.mean_x * wo.x - s.mean_y * wo.y;
    pf_real area_i = wi.z - s.mean_x * wi.x - s.mean_y * wi.y;
    pf_real vx2 = PF_R(2.0) * sg.var_x, vy2 = PF_R(2.0) * sg.var_y, c4 = PF_R(4.0) * sg.cov_xy;
    /* 1/sqrt(2 var_o), the variance along wo clamped once to [PF_REAL_MIN, PF_REAL_MAX/4]
       (normal incidence: nu huge, G1 = 1; huge variances: nu -> 0) instead of pf_smith_nu's
       tests, and a reciprocal square root; kept: P_o needs sqrt(2 var_o) = 1/rs_o too */
    pf_real rs_o = pfi_beckmann_rsqrt(pf_clamp_nan_lo(wo.x * (wo.x * vx2 + wo.y * c4) + wo.y * (wo.y * vy2),
                                                       PF_REAL_MIN, PF_R(0.25) * PF_REAL_MAX));
    /* signed: < 0 when the view is below the mean plane; floored at -64, where P_o is 0 in
       pf_real anyway, so that -inf (huge mean slopes) gives P_o = 0, not inf - inf: the final
       select must not rely on NaN ordering, which GPUs' native min does not keep */
    pf_real nu_o = pf_max(area_o * rs_o, PF_R(-64.0));
    pf_real nu_a = pf_max(PF_FABS(nu_o), PF_R(1.0e-20));
    /* P_o, the projected area of the facets facing the view (see the comment above):
       A_o / G1(nu_o) above the mean plane, (|nu_o| / G1(|nu_o|) - |nu_o|) sqrt(2 var_o) below
       (1 + Lambda(-nu) = -Lambda(nu)); nu floored at 1e-20, where nu / G1(nu) is its limit
       1/(2 sqrt(pi)) to rounding */
    pf_real front = (pf_smith_nu_over_g1(nu_a) - pf_max(-nu_o, PF_R(0.0))) / rs_o;
    pf_real g, d, t, v;
    /* eq. 17's G / A_o = 1 / (P_o + A_o Lambda_i) (Smith: P_o = A_o (1 + Lambda_o)), with A_o
       counted as 0 below the mean plane (see above) and Lambda_i capped by the macrosurface's
       share of the light (pf_beckmann_light_lambda); masking only: 1 / P_o */
    if (masking_only != 0) {
        g = PF_R(1.0) / front;
    } else {
        pf_real rs_i = pfi_beckmann_rsqrt(pf_clamp_nan_lo(wi.x * (wi.x * vx2 + wi.y * c4) + wi.y * (wi.y * vy2),
                                                           PF_REAL_MIN, PF_R(0.25) * PF_REAL_MAX));
        g = PF_R(1.0) / (front + pf_max(area_o, PF_R(0.0)) * pf_beckmann_light_lambda(area_i * rs_i, rs_i, wi.z));
    }
    /* both directions above the macrosurface: the half vector's z > 0, as pfi_beckmann_d_up needs */
    /* the 1/4 of eq. 17 rides in D's exponent: ln(1/4) */
    d = pfi_beckmann_d_up(pf_vec3_add(wo, wi), s, PF_R(-1.38629436111989061883446424291635313));
    /* Schlick (pf_fresnel_schlick) with cos = w_h . w_i = sqrt((1 + w_o . w_i)/2), clamped once */
    t = PF_R(1.0) - PF_SQRT(pf_saturate(PF_R(0.5) + PF_R(0.5) * pf_vec3_dot(wo, wi)));
    v = (f0 + (PF_R(1.0) - f0) * ((t * t) * (t * t) * t)) * d * g;
    /* one select for the conditions (both directions above the macrosurface, some facet facing
       the view: P_o is 0 in pf_real once G1(|nu_o|) rounds to 1, nu_o below -3.3 in float);
       the values computed for the other case are discarded */
    return pf_min(pf_min(wo.z, wi.z), front) > PF_R(0.0) ? v : PF_R(0.0);
}

/* LEADR specular with joint masking-shadowing (eq. 17). See pfi_leadr_specular. */
PF_DEF pf_real pf_leadr_specular(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real f0)
{
    return pfi_leadr_specular(wo, wi, s, s, f0, 0);
}

/* LEADR specular with masking only, 1/(1 + Lambda_o) (LEADR sec. 6). See pfi_leadr_specular. */
PF_DEF pf_real pf_leadr_specular_masking(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real f0)
{
    return pfi_leadr_specular(wo, wi, s, s, f0, 1);
}

/* ---------------------------------------------------------------- the base lobe's own masking
   The reflecting facets' masking-shadowing by their own base roughness (our model, for LEADR's
   two scales: the map's slopes and the micro-BRDF's base lobe). eq. 17 with base_var added to
   the covariance (pf_slope_moments_stats) treats both scales as one Gaussian surface, with one
   Smith G for the sum. A two-scale surface - each texel a plane of slope s_t covered by the
   base lobe's microfacets, what tests/reference/pf_microsurface.h shades - reflects toward w_o
   through microfacets of normal w_h lying on texels of every slope, and each such microfacet
   is masked and shadowed by its texel's own base roughness: the base lobe's Smith
       G2_b(s) = 1 / (1 + Lambda_b(w_o; s) + Lambda_b(w_i; s)),
       Lambda_b(w; s) = Lambda(nu),  nu = a(w; s) / sqrt(2 base_var |w.xy|^2),  a = w.z - s.w.xy,
   0 when the texel faces away from either direction (a <= 0: the microfacet of normal w_h on
   it is not seen, although w_h itself faces w_o). The Smith G of the sum's Gaussian sees
   neither: at grazing views (80-85 degrees) the reflecting facets sit at nu ~ 0.3-0.7 of the
   base lobe and the tilted half of them faces away, so eq. 17 overestimates the peak 2-3x
   (bench/grazing_diag.c: the factor that carries the error, gaussian_fine at 85 degrees).
   This function returns that factor: G2_b averaged over the slopes s of the texels whose base
   lobe reflects w_o into w_i, i.e. over the posterior of s ~ N(mean, S0) given the half
   vector's slope x_h seen through the base lobe N(x_h; s, base_var I) - a Gaussian of
       mean   x_h - base_var S^-1 (x_h - mean),   covariance  base_var (I - base_var S^-1),
   S = S0 + base_var I the covariance the caller already has (s: the statistics WITH the base
   variance, as pf_leadr_specular takes them; S - base_var I is clamped to positive
   semidefinite, so statistics below the base variance are read as one slope). a(w_o; s) and a(w_i; s) are then jointly normal
   and E[G2_b] is a 4 x 4 product rule over them restricted to both areas positive (a_o, then
   a_i given a_o: Gauss-Legendre on each positive part, times its probability from erfc; 16
   nodes, each one G1 of pf_smith.h, pf_smith_joint and an exp; a Gauss-Hermite rule missed the
   narrow band where both are positive at grazing views and mirror lights). Accuracy against
   the integral's definition: tests/test_beckmann.c (test_base_masking_quadrature).
   Use: pf_leadr_specular(wo, wi, s, f0) * pf_beckmann_base_masking(wo, wi, s, base_var)
   (pf_leadr_specular_base), or per lobe of a mixture with that lobe's statistics (pf_vmf.h's
   lobes: pf_vmf_lobe_slope_stats(mu, kappa, base_var)). In [0, 1]; 1 when base_var <= 0 (no
   base lobe); about 1 away from grazing (nu of the base lobe above ~2 at both directions). The
   directions must be above the macrosurface (w.z > 0; otherwise the result is meaningless, and
   the BRDFs it multiplies return 0). */
/* Gauss-Legendre nodes and weights on [-1, 1], PFI_BASE_NODES of them */
#define PFI_BASE_NODES 4
/* half-width of the node interval in deviations: 4 Gauss-Legendre nodes on +-2.5 sd weighted by
   the normal density reproduce its variance (0.997) */
#define PFI_BASE_WIN PF_R(2.5)
PF_DEF pf_real pfi_beckmann_gl_node(int k)
{
    pf_real x = (k == 0 || k == 3) ? PF_R(0.861136311594052575) : PF_R(0.339981043584856265);
    return k < 2 ? -x : x;
}
PF_DEF pf_real pfi_beckmann_gl_weight(int k)
{
    return (k == 0 || k == 3) ? PF_R(0.347854845137453857) : PF_R(0.652145154862546143);
}
/* Node k of Gauss-Legendre on [lo, hi], and its weight times exp(-z^2 / 2), z = (a - m) / sd:
   over a ~ N(m, sd^2) restricted to [lo, hi] (nodes within +-PFI_BASE_WIN sd of m), the mean of
   f is sum_k v_k f(a_k) / sum_k v_k (self-normalized: a degenerate sd gives the point m), and
   the mass (erfc((lo - m) / (sd sqrt 2)) - erfc((hi - m) / (sd sqrt 2))) / 2 (pfi_beckmann_mass). */
PF_DEF pf_real pfi_beckmann_gl_at(int k, pf_real lo, pf_real hi)
{
    return PF_R(0.5) * (lo + hi) + PF_R(0.5) * (hi - lo) * pfi_beckmann_gl_node(k);
}
PF_DEF pf_real pfi_beckmann_gl_pdf_weight(int k, pf_real a, pf_real m, pf_real isd)
{
    pf_real z = (a - m) * isd;
    return pfi_beckmann_gl_weight(k) * PF_EXP(-PF_R(0.5) * pf_min(z * z, PF_R(64.0)));
}
PF_DEF pf_real pfi_beckmann_mass(pf_real lo, pf_real hi, int bounded, pf_real m, pf_real isd)
{
    pf_real r = PF_R(0.707106781186547524) * isd;
    /* unbounded above: no upper term (m + 64 sd rounds to m in float when sd is at its floor,
       and the mass came out 1/2) */
    pf_real up = bounded != 0 ? pf_erfc((hi - m) * r) : PF_R(0.0);
    return pf_max(PF_R(0.5) * (pf_erfc((lo - m) * r) - up), PF_R(0.0));
}
PF_DEF pf_real pf_beckmann_base_masking(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s0, pf_real base_var)
{
    pf_slope_stats s = pfi_beckmann_floor(s0);
    /* NaN and negative: 0 (no base lobe, result 1); capped as the covariance is */
    pf_real vb = pf_clamp_nan_lo(base_var, PF_R(0.0), PFI_BECKMANN_VAR_CEIL);
    /* the footprint's own covariance S0 = S - base_var I, clamped to positive semidefinite
       (statistics below the base variance are read as a single slope), and S = S0 + base_var I
       rebuilt from it: det >= base_var^2, so the posterior below is one for any input */
    pf_real v0x = pf_max(s.var_x - vb, PF_R(0.0)), v0y = pf_max(s.var_y - vb, PF_R(0.0));
    pf_real cm = PF_SQRT(v0x * v0y), c0 = pf_min(pf_max(s.cov_xy, -cm), cm);
    pf_real sxx = v0x + vb, syy = v0y + vb;
    pf_real det = pf_max(sxx * syy - c0 * c0, PF_REAL_MIN);
    /* base_var S^-1 (adjugate over det) */
    pf_real bx = vb * syy / det, by = vb * sxx / det, bc = -vb * c0 / det;
    /* the half vector's slope, and its offset from the mean */
    pf_real hz = pf_max(wo.z + wi.z, PF_R(1.0e-6)); /* both directions above the macrosurface: > 0 */
    pf_real hx = -(wo.x + wi.x) / hz, hy = -(wo.y + wi.y) / hz;
    pf_real dx = hx - s.mean_x, dy = hy - s.mean_y;
    /* posterior mean m = x_h - base_var S^-1 (x_h - mean); covariance P = base_var (I - base_var S^-1) */
    pf_real mx = hx - (bx * dx + bc * dy), my = hy - (bc * dx + by * dy);
    /* P = base_var S^-1 S0 = base_var / det [det0 + base_var v0x, base_var c0; base_var c0,
       det0 + base_var v0y] (det0 = det S0): no cancellation as S0 nears singular, where
       base_var (I - base_var S^-1) lost all its digits in float */
    pf_real det0 = pf_max(v0x * v0y - c0 * c0, PF_R(0.0)), f = vb / det;
    pf_real pxx = f * (det0 + vb * v0x), pyy = f * (det0 + vb * v0y), pxy = f * (vb * c0);
    /* the facets' areas toward wo and wi: means, variances, covariance */
    pf_real ma_o = wo.z - mx * wo.x - my * wo.y, ma_i = wi.z - mx * wi.x - my * wi.y;
    pf_real vo = pf_max(wo.x * (wo.x * pxx + PF_R(2.0) * wo.y * pxy) + wo.y * (wo.y * pyy), PF_R(0.0));
    pf_real vi = pf_max(wi.x * (wi.x * pxx + PF_R(2.0) * wi.y * pxy) + wi.y * (wi.y * pyy), PF_R(0.0));
    pf_real coi = wo.x * (wi.x * pxx + wi.y * pxy) + wo.y * (wi.x * pxy + wi.y * pyy);
    /* deviations floored (a point mass stays a point: the weights are self-normalized) */
    pf_real sd_o = pf_max(PF_SQRT(vo), PF_R(1.0e-9)), isd_o = PF_R(1.0) / sd_o;
    /* a_i given a_o: mean ma_i + beta (a_o - ma_o), variance vi - beta coi */
    pf_real beta = coi / (sd_o * sd_o);
    pf_real sd_c = pf_max(PF_SQRT(pf_max(vi - beta * coi, PF_R(0.0))), PF_R(1.0e-9)), isd_c = PF_R(1.0) / sd_c;
    /* 1 / sqrt(2 base_var |w.xy|^2): nu of the base lobe per unit area */
    pf_real ko = pfi_beckmann_rsqrt(pf_clamp_nan_lo(PF_R(2.0) * vb * (wo.x * wo.x + wo.y * wo.y), PF_REAL_MIN, PF_REAL_MAX));
    pf_real ki = pfi_beckmann_rsqrt(pf_clamp_nan_lo(PF_R(2.0) * vb * (wi.x * wi.x + wi.y * wi.y), PF_REAL_MIN, PF_REAL_MAX));
    /* the outer interval: a_o > 0, and where a_i > 0 keeps some mass (the conditional mean
       above -4 conditional deviations): at a mirror light a_o and a_i are nearly opposite
       (beta < 0) and both are positive in a narrow band only, which the nodes must sample */
    pf_real t = pf_min(pf_max((ma_i + PF_R(4.0) * sd_c) / pf_max(PF_FABS(beta), PF_R(1.0e-6)), PF_R(-1.0e30)), PF_R(1.0e30));
    pf_real lo = beta > PF_R(0.0) ? pf_max(ma_o - t, PF_R(0.0)) : PF_R(0.0);
    pf_real hi = beta < PF_R(0.0) ? pf_max(ma_o + t, lo) : ma_o + PF_R(64.0) * sd_o;
    pf_real sum = PF_R(0.0), wsum = PF_R(0.0);
    int j, k;
    for (j = 0; j < PFI_BASE_NODES; ++j) {
        pf_real a_o = pfi_beckmann_gl_at(j, pf_max(lo, ma_o - PFI_BASE_WIN * sd_o), pf_min(hi, ma_o + PFI_BASE_WIN * sd_o));
        pf_real w_o = pfi_beckmann_gl_pdf_weight(j, a_o, ma_o, isd_o);
        pf_real g_o = pf_g1_beckmann(a_o * ko);
        pf_real mc = ma_i + beta * (a_o - ma_o);
        pf_real lo_i = pf_max(mc - PFI_BASE_WIN * sd_c, PF_R(0.0)), hi_i = pf_max(mc + PFI_BASE_WIN * sd_c, PF_R(0.0));
        pf_real row = PF_R(0.0), rsum = PF_R(0.0);
        for (k = 0; k < PFI_BASE_NODES; ++k) {
            pf_real a_i = pfi_beckmann_gl_at(k, lo_i, hi_i);
            pf_real w_i = pfi_beckmann_gl_pdf_weight(k, a_i, mc, isd_c);
            row += w_i * pf_smith_joint(g_o, pf_g1_beckmann(a_i * ki));
            rsum += w_i;
        }
        /* the inner mean times P(a_i > 0 | a_o) */
        sum += w_o * (row / pf_max(rsum, PF_REAL_MIN)) * PF_R(0.5) * pf_erfc(-mc * isd_c * PF_R(0.707106781186547524));
        wsum += w_o;
    }
    sum = (sum / pf_max(wsum, PF_REAL_MIN)) * pfi_beckmann_mass(lo, hi, beta < PF_R(0.0) ? 1 : 0, ma_o, isd_o);
    return vb > PF_R(0.0) ? pf_min(pf_max(sum, PF_R(0.0)), PF_R(1.0)) : PF_R(1.0);
}

/* LEADR specular (eq. 17) with the two scales' visibility kept apart: Smith's G of the
   footprint's own slopes (the covariance of s minus base_var I, clamped to positive
   semidefinite as in pf_beckmann_base_masking) times the base lobe's own masking-shadowing at
   the reflecting facets (pf_beckmann_base_masking), D and the projected area as in
   pf_leadr_specular. s: the footprint's statistics with base_var added, as for
   pf_leadr_specular. G of s itself would count the base lobe's masking twice (a one-texel
   footprint: G2_b squared). For grazing views (see above); 16 more G1 pairs than
   pf_leadr_specular. */
PF_DEF pf_real pf_leadr_specular_base(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real base_var, pf_real f0)
{
    pf_real vb = pf_clamp_nan_lo(base_var, PF_R(0.0), PFI_BECKMANN_VAR_CEIL);
    pf_slope_stats g = s;
    pf_real cm, v;
    g.var_x = pf_max(s.var_x - vb, PF_R(0.0));
    g.var_y = pf_max(s.var_y - vb, PF_R(0.0));
    cm = PF_SQRT(g.var_x * g.var_y);
    g.cov_xy = pf_min(pf_max(s.cov_xy, -cm), cm);
    v = pfi_leadr_specular(wo, wi, s, g, f0, 0);
    return v > PF_R(0.0) ? v * pf_beckmann_base_masking(wo, wi, s, base_var) : PF_R(0.0);
}

/* Point light: to_light is the (unnormalized) vector from the shaded point to the light in the
   tangent frame; returns the radiance per unit light intensity, pf_leadr_specular(w_o,
   to_light/|to_light|) / |to_light|^2. 0 for a zero vector. */
PF_DEF pf_real pf_leadr_specular_point(pf_vec3 wo, pf_vec3 to_light, pf_slope_stats s, pf_real f0)
{
    pf_real d2 = pf_vec3_dot(to_light, to_light);
    if (!(d2 > PF_R(0.0))) return PF_R(0.0);
    /* saturated at PF_REAL_MAX: a light a few 1e-8 away (1/d2 ~ 1e15) over a grazing footprint
       overflows float (fuzz_beckmann-float found inf) */
    return pf_min(pf_leadr_specular(wo, pf_vec3_scale(to_light, PF_R(1.0) / PF_SQRT(d2)), s, f0) / d2, PF_REAL_MAX);
}

#endif /* PF_BECKMANN_H */

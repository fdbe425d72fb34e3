/* pf_smith.h - Smith masking for Beckmann (Gaussian-slope) and GGX microsurfaces,
   centered or not.

   WORK IN PROGRESS - API frozen, internals being fitted. */
#ifndef PF_SMITH_H
#define PF_SMITH_H

#ifndef PF_GLSL
#  include "pf_core.h"
#endif

/* Finite stand-in for Lambda = +infinity (direction on or below the mean surface). Finite so
   that sums like 1 + Lambda_o + Lambda_i stay finite and -ffast-math builds stay defined. */
#define PF_LAMBDA_MAX PF_R(1.0e30)
/* Finite stand-in for nu = +infinity (normal incidence, or zero slope deviation). */
#define PF_NU_MAX PF_R(1.0e15)

PF_STRUCT_BEGIN(pf_slope_stats)
    pf_real mean_x;
    pf_real mean_y;
    pf_real var_x;
    pf_real var_y;
    pf_real cov_xy;
PF_STRUCT_END(pf_slope_stats)

PF_DEF pf_slope_stats pf_slope_stats_make(pf_real mean_x, pf_real mean_y, pf_real var_x,
                                          pf_real var_y, pf_real cov_xy)
{
    pf_slope_stats s;
    s.mean_x = mean_x;
    s.mean_y = mean_y;
    s.var_x = var_x;
    s.var_y = var_y;
    s.cov_xy = cov_xy;
    return s;
}

/* LEADR eq. 9 */
PF_DEF pf_slope_stats pf_slope_stats_from_moments(pf_real ex, pf_real ey, pf_real exx,
                                                  pf_real eyy, pf_real exy)
{
    pf_real vx = pf_max(exx - ex * ex, PF_R(0.0));
    pf_real vy = pf_max(eyy - ey * ey, PF_R(0.0));
    pf_real c = exy - ex * ey;
    pf_real cmax = PF_SQRT(vx * vy);
    return pf_slope_stats_make(ex, ey, vx, vy, pf_clamp(c, -cmax, cmax));
}

PF_DEF pf_real pf_smith_nu(pf_vec3 w, pf_slope_stats s)
{
    pf_real num = w.z - w.x * s.mean_x - w.y * s.mean_y;
    pf_real var = w.x * w.x * s.var_x + w.y * w.y * s.var_y + PF_R(2.0) * w.x * w.y * s.cov_xy;
    if (!(num > PF_R(0.0))) return PF_R(0.0);
    var = pf_max(var, PF_R(0.0));
    if (PF_R(2.0) * var <= num * num / (PF_NU_MAX * PF_NU_MAX)) return PF_NU_MAX;
    return num / PF_SQRT(PF_R(2.0) * var);
}

PF_DEF pf_real pf_smith_nu_iso(pf_real cos_theta, pf_real sigma)
{
    pf_real c = pf_clamp(cos_theta, PF_R(-1.0), PF_R(1.0));
    pf_real sin_theta = PF_SQRT(pf_max(PF_R(1.0) - c * c, PF_R(0.0)));
    if (!(c > PF_R(0.0))) return PF_R(0.0);
    if (PF_SQRT2 * sigma * sin_theta <= c / PF_NU_MAX) return PF_NU_MAX;
    return c / (PF_SQRT2 * sigma * sin_theta);
}

PF_DEF pf_real pf_lambda_beckmann(pf_real nu)
{
    if (!(nu > PF_R(1.0) / (PF_R(2.0) * PF_SQRT_PI * PF_LAMBDA_MAX))) return PF_LAMBDA_MAX;
    return pf_max(PF_EXP(-nu * nu) / (PF_R(2.0) * PF_SQRT_PI * nu) - PF_R(0.5) * pf_erfc(nu), PF_R(0.0));
}

PF_DEF pf_real pf_g1_beckmann(pf_real nu)
{
    pf_real a;
    if (!(nu > PF_R(0.0))) return PF_R(0.0);
    a = PF_R(2.0) * PF_SQRT_PI * nu;
    return a / (a + PF_EXP(-nu * nu) - PF_R(0.5) * a * pf_erfc(nu));
}

PF_DEF pf_real pf_lambda_beckmann_walter(pf_real nu)
{
    if (!(nu > PF_R(0.0))) return PF_LAMBDA_MAX;
    if (nu >= PF_R(1.6)) return PF_R(0.0);
    return pf_max((PF_R(1.0) - PF_R(1.259) * nu + PF_R(0.396) * nu * nu) /
                  (PF_R(3.535) * nu + PF_R(2.181) * nu * nu), PF_R(0.0));
}

PF_DEF pf_real pf_g1_beckmann_walter(pf_real nu)
{
    if (!(nu > PF_R(0.0))) return PF_R(0.0);
    if (nu >= PF_R(1.6)) return PF_R(1.0);
    return pf_min(nu * (PF_R(3.535) + PF_R(2.181) * nu) / (PF_R(1.0) + nu * (PF_R(2.276) + PF_R(2.577) * nu)),
                  PF_R(1.0));
}

PF_DEF pf_real pf_g1_beckmann_fast(pf_real nu) { return pf_g1_beckmann_walter(nu); }
PF_DEF pf_real pf_lambda_beckmann_fast(pf_real nu) { return pf_lambda_beckmann_walter(nu); }

PF_DEF pf_real pf_lambda_ggx(pf_vec3 w, pf_real alpha_x, pf_real alpha_y)
{
    pf_real t2;
    if (!(w.z > PF_R(0.0))) return PF_LAMBDA_MAX;
    t2 = (pf_sq(alpha_x * w.x) + pf_sq(alpha_y * w.y)) / (w.z * w.z);
    return t2 / (PF_R(2.0) * (PF_R(1.0) + PF_SQRT(PF_R(1.0) + t2)));
}

PF_DEF pf_real pf_g1_ggx(pf_vec3 w, pf_real alpha_x, pf_real alpha_y)
{
    if (!(w.z > PF_R(0.0))) return PF_R(0.0);
    return PF_R(2.0) * w.z / (w.z + PF_SQRT(w.z * w.z + pf_sq(alpha_x * w.x) + pf_sq(alpha_y * w.y)));
}

PF_DEF pf_real pf_lambda_ggx_iso(pf_real cos_theta, pf_real alpha)
{
    pf_real c = pf_min(cos_theta, PF_R(1.0));
    pf_real s = PF_SQRT(pf_max(PF_R(1.0) - c * c, PF_R(0.0)));
    return pf_lambda_ggx(pf_vec3_make(s, PF_R(0.0), c), alpha, alpha);
}

PF_DEF pf_real pf_g1_ggx_iso(pf_real cos_theta, pf_real alpha)
{
    pf_real c = pf_min(cos_theta, PF_R(1.0));
    pf_real s = PF_SQRT(pf_max(PF_R(1.0) - c * c, PF_R(0.0)));
    return pf_g1_ggx(pf_vec3_make(s, PF_R(0.0), c), alpha, alpha);
}

PF_DEF pf_real pf_smith_joint(pf_real g1_o, pf_real g1_i)
{
    if (!(g1_o > PF_R(0.0)) || !(g1_i > PF_R(0.0))) return PF_R(0.0);
    return g1_o * g1_i / (g1_o + g1_i - g1_o * g1_i);
}

PF_DEF pf_real pf_smith_joint_lambda(pf_real lambda_o, pf_real lambda_i)
{
    return PF_R(1.0) / (PF_R(1.0) + pf_max(lambda_o, PF_R(0.0)) + pf_max(lambda_i, PF_R(0.0)));
}

PF_DEF pf_real pf_smith_separable(pf_real g1_o, pf_real g1_i) { return g1_o * g1_i; }

PF_DEF pf_real pf_g2_beckmann(pf_real nu_o, pf_real nu_i)
{
    return pf_smith_joint(pf_g1_beckmann(nu_o), pf_g1_beckmann(nu_i));
}

#endif /* PF_SMITH_H */

/* pf_smith.h - Smith masking for Beckmann (Gaussian-slope) and GGX microsurfaces,
   centered or noncentered (a mean slope, as a filtered LEAN/LEADR footprint has).

   Lambda(w) is Smith's masking function: for a surface whose slopes along the azimuth of w
   have density P2, seen from w = (sin t cos p, sin t sin p, cos t),
       Lambda(w) = integral_{cot t}^{inf} (x - cot t) P2(x) dx / (cot t - mu)        (1)
   where mu is the mean of P2. Lambda measures how much back-facing micro-area the view sees
   per unit of projected mesosurface: 1 + Lambda = (projected micro-area toward w) divided by
   the mesosurface projected area (w_nbar . w)/(w_nbar . w_g) (Dupuy et al. 2013 eqs. 1, 6, 10).
   For a centered distribution mu = 0 and (1) is Smith's tan t * integral. The visible
   fraction is G1 = 1/(1 + Lambda), and for a view and a light the joint masking-shadowing
   moment is 1/(1 + Lambda_o + Lambda_i) (Dupuy et al. 2013 eq. 13).

   For Gaussian slopes (Beckmann), (1) depends only on nu = (cot t - mu)/(sigma sqrt 2) with
   mu, sigma the mean and deviation of the slopes along the azimuth of w (eqs. 14-15).
   pf_smith_nu computes nu straight from the direction vector and the slope statistics, with
   no trigonometry, so it is exact at normal incidence.

   USAGE
     #include "pf_smith.h"
     pf_slope_stats s = pf_slope_stats_from_moments(ex, ey, exx, eyy, exy); -- filtered moments
     pf_real g = pf_smith_joint(pf_g1_beckmann(pf_smith_nu(wo, s)),
                                pf_g1_beckmann(pf_smith_nu(wi, s)));       -- 1/(1+Lo+Li)

   FUNCTIONS
     slope statistics  pf_slope_stats_make, pf_slope_stats_from_moments, pf_slope_along,
                       pf_smith_nu, pf_smith_nu_iso
     Beckmann          pf_lambda_beckmann, pf_g1_beckmann            exact (see below)
                       pf_g1_beckmann_fast       ours: 1.04e-4, branch-free
                       pf_lambda_beckmann_fast   ours: relative error 2e-6 (+ 6e-8 nu^2), exp-based
                       pf_lambda_beckmann_walter, pf_g1_beckmann_walter  Walter et al. 2007, 3.1e-3
     GGX               pf_lambda_ggx, pf_g1_ggx (anisotropic, from the direction vector),
                       pf_lambda_ggx_iso, pf_g1_ggx_iso (from cos theta)
     joint             pf_smith_joint (from G1s), pf_smith_joint_lambda (from Lambdas),
                       pf_smith_separable, pf_g2_beckmann (from nus)

   CONVENTIONS
     Slopes follow Dupuy et al. 2013: a micro-normal (nx, ny, nz) has slope (-nx/nz, -ny/nz),
     the mesonormal is (-E[x], -E[y], 1)/norm (eq. 11). Directions are in the tangent frame of
     the macrosurface (w_g = +z) and need not be normalized for pf_smith_nu and the GGX
     functions. Lambda = +inf is returned as PF_LAMBDA_MAX (finite, so sums stay finite and
     -ffast-math builds stay defined); nu = +inf as PF_NU_MAX. Every function returns a finite
     value for every finite input, except pf_slope_along, whose mean and variance along w are
     sums that overflow where their exact value does (statistics near PF_REAL_MAX); NaN inputs
     give G1 = 0. Under -ffast-math the NaN tests are compiled away, so an input whose
     intermediate overflows to inf - inf (w.x E[x] and w.y E[y] of opposite signs, both near
     PF_REAL_MAX) can give NaN in pf_smith_nu and its callers (docs/stability.md counts them).

   ACCURACY AND COST (measured; docs/smith.md has the tables, bench/bench_smith.c the timings)
     pf_g1_beckmann        float: one (4,5) rational and a clamp, no branch, max rel. error
                           6.3e-7 (bound 1e-6); double: 4e-16. Lambda: <= 5 ulp in float and double.
     pf_g1_beckmann_fast   max rel. error 1.04e-4 (30x below Walter), branch-free.
     pf_lambda_beckmann_fast  max rel. error 2e-6 + 6e-8 nu^2 (float), branch-free.
     GPU cost (SPIR-V ops after spirv-opt -O, bench/gpu/count.sh): docs/smith.md.

   SOURCES
     Smith 1967; Walter, Marschner, Li, Torrance 2007 (Beckmann rational, GGX Lambda);
     Heitz & Neyret 2011 eqs. 4-7; Dupuy, Heitz, Iehl, Poulin, Neyret, Ostromoukhov 2013
     (LEADR) sec. 4.3, eqs. 13-15. */
#ifndef PF_SMITH_H
#define PF_SMITH_H

#ifndef PF_GLSL
#  include "pf_core.h"
#endif

/* ---------------------------------------------------------------- slope statistics */
/* Finite stand-in for Lambda = +infinity (direction on or below the mean surface). Finite so
   that sums like 1 + Lambda_o + Lambda_i stay finite and -ffast-math builds stay defined. */
#define PF_LAMBDA_MAX PF_R(1.0e30)
/* Finite stand-in for nu = +infinity (normal incidence, or zero slope deviation). */
#define PF_NU_MAX PF_R(1.0e15)

/* Mean and covariance of the micro-slopes (x, y) over a footprint (Dupuy et al. 2013 eq. 9):
   the central statistics, not the raw moments. */
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

/* Statistics from the five linearly filtered moments E[x], E[y], E[x^2], E[y^2], E[xy]
   (Dupuy et al. 2013 eq. 9). Filtering and rounding can make a variance slightly negative or
   |correlation| > 1: variances are clamped at 0 and the covariance to
   |c_xy| <= sigma_x sigma_y, so the covariance is always positive semi-definite. (Adding a
   base roughness is the caller's job; the LEADR module does it.) */
PF_DEF pf_slope_stats pf_slope_stats_from_moments(pf_real ex, pf_real ey, pf_real exx,
                                                  pf_real eyy, pf_real exy)
{
    pf_real vx = pf_max(exx - ex * ex, PF_R(0.0));
    pf_real vy = pf_max(eyy - ey * ey, PF_R(0.0));
    pf_real c = exy - ex * ey;
    /* sqrt(vx) sqrt(vy), not sqrt(vx vy): the product underflows (vx vy subnormal or flushed
       to 0 gave |c| > sigma_x sigma_y) and overflows for huge variances; one sqrt more */
    pf_real cmax = PF_SQRT(vx) * PF_SQRT(vy);
    return pf_slope_stats_make(ex, ey, vx, vy, pf_clamp(c, -cmax, cmax));
}

/* Mean and deviation (mu, sigma) of the slopes along the azimuth of w
   (Dupuy et al. 2013 eqs. 14-15), with cos p = w.x/r, sin p = w.y/r, r = |(w.x, w.y)|.
   At normal incidence (r = 0) the azimuth is undefined and p = 0 (the x axis) is used.
   Finite while |E[x]|, |E[y]| and the (co)variances are below PF_REAL_MAX / 4; beyond, the
   exact mean or variance along w may exceed PF_REAL_MAX and the result is +-inf. */
PF_DEF pf_vec2 pf_slope_along(pf_vec3 w, pf_slope_stats s)
{
    pf_real r = PF_SQRT(w.x * w.x + w.y * w.y);
    pf_real c = PF_R(1.0), sn = PF_R(0.0);
    if (r > PF_R(0.0)) {
        c = w.x / r;
        sn = w.y / r;
    }
    return pf_vec2_make(c * s.mean_x + sn * s.mean_y,
                        PF_SQRT(pf_max(c * c * s.var_x + sn * sn * s.var_y + PF_R(2.0) * c * sn * s.cov_xy,
                                       PF_R(0.0))));
}

/* nu = (cot t - mu) / (sigma sqrt 2) for direction w and slope statistics s (Dupuy et al.
   2013, after eq. 15). Multiplying through by r = |(w.x, w.y)| removes the trigonometry:
       nu = (w.z - w.x E[x] - w.y E[y]) / sqrt(2 (w.x^2 s_x^2 + w.y^2 s_y^2 + 2 w.x w.y c_xy)).
   w need not be normalized. Returns 0 when w is on or below the mesosurface (numerator
   <= 0: Lambda = inf, G1 = 0) and PF_NU_MAX when the denominator vanishes against the
   numerator (normal incidence, or zero deviation along w: Lambda = 0, G1 = 1). */
PF_DEF pf_real pf_smith_nu(pf_vec3 w, pf_slope_stats s)
{
    pf_real num = w.z - w.x * s.mean_x - w.y * s.mean_y;
    pf_real var = w.x * w.x * s.var_x + w.y * w.y * s.var_y + PF_R(2.0) * w.x * w.y * s.cov_xy;
    if (!(num > PF_R(0.0))) return PF_R(0.0);
    /* capped at PF_REAL_MAX/4 (nu then <= num / 1.3e19, G1 ~ 0 either way): an infinite
       variance along w (huge variances or w) would meet gcc -ffast-math's float
       num * rsqrt(2 var) expansion as inf * 0 = NaN */
    var = pf_min(pf_max(var, PF_R(0.0)), PF_R(0.25) * PF_REAL_MAX);
    if (PF_R(2.0) * var <= num * num / (PF_NU_MAX * PF_NU_MAX)) return PF_NU_MAX;
    return num / PF_SQRT(PF_R(2.0) * var);
}

/* nu for a centered isotropic Gaussian of slope deviation sigma (per axis) seen at
   cos theta: cot theta / (sigma sqrt 2). cos_theta <= 0 gives 0, sigma = 0 or
   cos_theta = 1 gives PF_NU_MAX. */
PF_DEF pf_real pf_smith_nu_iso(pf_real cos_theta, pf_real sigma)
{
    pf_real c = pf_clamp(cos_theta, PF_R(-1.0), PF_R(1.0));
    pf_real sin_theta = PF_SQRT(pf_max(PF_R(1.0) - c * c, PF_R(0.0)));
    /* sigma sin_theta first: it cannot overflow (sin_theta <= 1), whereas sqrt(2) sigma did
       for sigma near PF_REAL_MAX, and inf * (sin_theta = 0) made NaN */
    pf_real d = sigma * sin_theta;
    if (!(c > PF_R(0.0))) return PF_R(0.0);
    if (d <= c * (PF_INV_SQRT2 / PF_NU_MAX)) return PF_NU_MAX;
    return (c * PF_INV_SQRT2) / d;
}

/* ---------------------------------------------------------------- Beckmann Lambda, exact
   Smith (1967) for Gaussian slopes, in the noncentered form of Dupuy et al. 2013 sec. 4.3:
       Lambda(nu) = exp(-nu^2) / (2 nu sqrt(pi)) - erfc(nu) / 2.
   The two terms cancel for large nu (both ~ exp(-nu^2)/(2 nu sqrt(pi)), Lambda ~ their
   difference / (2 nu^2)), so we never subtract them. Instead
       Lambda = exp(-nu^2) K(nu) / (2 sqrt(pi) nu),        K(nu) = 1 - nu sqrt(pi) exp(nu^2) erfc(nu)
   for nu < 2, and for nu >= 2, with s = 1/nu^2 and K = (s/2) F(s),
       Lambda = exp(-nu^2) F(s) / (4 sqrt(pi) nu^3),
   where K in (0, 1] and F -> 1 are smooth and cancellation-free. K and F are near-minimax
   rationals (bench/fit/fit_smith.py): fit error 4e-9 / 1.3e-8 (float, K(4,4), F(3,3)) and
   1.5e-19 / 2.2e-18 (double, K(8,8), F(8,8)). exp(-nu^2) goes through pf_exp_neg_sq, which
   avoids the rounding of nu*nu that would otherwise cost ~nu^2 ulp. */
#ifdef PF_DOUBLE
PF_DEF pf_real pf_smith_k(pf_real nu) /* K(nu), nu in [0, 2] */
{
    pf_real p = PF_R(0.999999999999999999854) + nu * (PF_R(0.938920679029529481423) +
                nu * (PF_R(0.519045664654744982871) + nu * (PF_R(0.172147912216411197721) +
                nu * (PF_R(0.0369169530219737221852) + nu * (PF_R(0.00463386500845213666702) +
                nu * (PF_R(0.000271847409768397781129) + nu * (PF_R(-7.0180022901191934562e-8) +
                nu * PF_R(2.04170491699162860257e-9))))))));
    pf_real q = PF_R(1.0) + nu * (PF_R(2.71137452993504544701) + nu * (PF_R(3.32483189148525391592) +
                nu * (PF_R(2.41496379292822751232) + nu * (PF_R(1.14011793812338278951) +
                nu * (PF_R(0.359684684265732825226) + nu * (PF_R(0.0744229410022853019875) +
                nu * (PF_R(0.00929459929537228834022) + nu * PF_R(0.000541303142605290027796))))))));
    return p / q;
}
PF_DEF pf_real pfi_smith_f(pf_real s) /* F(s), s = 1/nu^2 in [0, 1/4] */
{
    pf_real p = PF_R(0.999999999999999997932) + s * (PF_R(42.2393940178639545184) +
                s * (PF_R(672.061394051817814891) + s * (PF_R(5127.33256595508163427) +
                s * (PF_R(19765.7022233077118986) + s * (PF_R(37196.4583243424325169) +
                s * (PF_R(30099.6866215856418556) + s * (PF_R(7543.89901252820703117) +
                s * PF_R(81.5746997218577689577))))))));
    pf_real q = PF_R(1.0) + s * (PF_R(43.7393940178639437084) + s * (PF_R(733.920485078622795394) +
                s * (PF_R(6077.31556600305531052) + s * (PF_R(26644.4908002660751452) +
                s * (PF_R(61747.4532545529666303) + s * (PF_R(71318.6026222178580818) +
                s * (PF_R(35626.6907510600668504) + s * PF_R(5403.53109677662630535))))))));
    return p / q;
}
#  define PF_SMITH_NU_UNDERFLOW PF_R(27.5) /* Lambda < smallest subnormal double beyond */
#else
PF_DEF pf_real pf_smith_k(pf_real nu)
{
    pf_real p = PF_R(0.9999999961) + nu * (PF_R(0.2507246113) + nu * (PF_R(0.07860461384) +
                nu * (PF_R(-0.002767716913) + nu * PF_R(0.0001852377203))));
    pf_real q = PF_R(1.0) + nu * (PF_R(2.023177974) + nu * (PF_R(1.664604304) +
                nu * (PF_R(0.6736815508) + nu * PF_R(0.1180659772))));
    return p / q;
}
PF_DEF pf_real pfi_smith_f(pf_real s)
{
    pf_real p = PF_R(0.9999999873) + s * (PF_R(7.956602414) + s * (PF_R(12.21484314) +
                s * PF_R(0.9858393979)));
    pf_real q = PF_R(1.0) + s * (PF_R(9.456593667) + s * (PF_R(22.65069739) + s * PF_R(12.5825901)));
    return p / q;
}
#  define PF_SMITH_NU_UNDERFLOW PF_R(10.5) /* Lambda < smallest subnormal float beyond */
#endif

/* pf_lambda_beckmann(nu): Smith's Lambda for Gaussian slopes (Dupuy et al. 2013 sec. 4.3,
   after eqs. 14-15; Heitz & Neyret 2011 eq. 7), nu = (cot theta - mu) / (sigma sqrt 2).
   Domain: every real nu. nu <= 0 (direction on or below the mean surface) and nu so small
   that Lambda would exceed PF_LAMBDA_MAX return PF_LAMBDA_MAX; nu >= 10.5 (float) / 27.5
   (double) return 0 (Lambda underflows). Error (tests/test_smith.c against the quadrature of
   the definition): see docs/smith.md; a few ulp in float and in double. */
PF_DEF pf_real pf_lambda_beckmann(pf_real nu)
{
    pf_real s;
    if (!(nu > PF_R(0.5) * PF_INV_SQRT_PI / PF_LAMBDA_MAX)) return PF_LAMBDA_MAX;
    if (nu >= PF_SMITH_NU_UNDERFLOW) return PF_R(0.0);
    if (nu < PF_R(2.0))
        return pf_exp_neg_sq(nu) * pf_smith_k(nu) * (PF_R(0.5) * PF_INV_SQRT_PI) / nu;
    s = PF_R(1.0) / (nu * nu);
    return pf_exp_neg_sq(nu) * pfi_smith_f(s) * (PF_R(0.25) * PF_INV_SQRT_PI) * s / nu;
}

/* pf_g1_beckmann(nu) = 1 / (1 + Lambda(nu)), Smith masking of a Gaussian-slope surface.
   Every real nu; 0 for nu <= 0 (and NaN), 1 where 1 - G1 is below rounding. Never divides
   by zero or forms inf/inf: near nu = 0, where Lambda ~ 1/(2 sqrt(pi) nu) blows up, it is
   evaluated as G1 = nu H(nu) with H = G1/nu smooth and finite (H(0) = 2 sqrt(pi)).
   Float: H is one (5,5) rational on [0, 3.3] (fit error 1.1e-7; 1 - G1(3.3) = 6.5e-8) - the
   'exact' float path, no exp, no erfc. Double: from K and F above. Measured max relative
   error in docs/smith.md. */
/* x clamped to [0, hi], NaN to 0: one clamp in GLSL; max first elsewhere (the comparison form
   and CUDA's fmaxf both turn NaN into 0). */
#ifdef PF_GLSL
#  define PFI_SMITH_CLAMP0(x, hi) clamp(x, 0.0, hi)
#else
#  define PFI_SMITH_CLAMP0(x, hi) pf_min(pf_max(x, PF_R(0.0)), hi)
#endif

PF_DEF pf_real pf_g1_beckmann(pf_real nu)
{
#ifdef PF_DOUBLE
    if (!(nu > PF_R(0.0))) return PF_R(0.0);
    if (nu < PF_R(2.0)) {
        pf_real a = PF_R(2.0) * PF_SQRT_PI * nu;
        return a / (a + pf_exp_neg_sq(nu) * pf_smith_k(nu));
    }
    return PF_R(1.0) / (PF_R(1.0) + pf_lambda_beckmann(nu));
#else
    {
        /* nu P4(nu) / Q5(nu) with a monic Q5, nu clamped to [0, 3.1] (0 for nu <= 0 and NaN;
           beyond 3.1, 1 - G1 < 2.8e-7 and the fit, pulled to G1 = 1 at 3.1, serves): fit
           error 4.7e-7 (bench/fit/fit_smith.py g1f). In float it evaluates to 1.0000001 at
           3.1, so the min makes G1 exactly 1 there and beyond. One clamp, one min, no branch,
           no exp. */
        pf_real n = PFI_SMITH_CLAMP0(nu, PF_R(3.1));
        return pf_min(n * (PF_R(36.41876602) + n * (PF_R(0.9635340571) + n * (PF_R(10.42804337) +
               n * (PF_R(1.123634458) + n * PF_R(1.061310649))))) /
               (PF_R(10.27353954) + n * (PF_R(18.48168564) + n * (PF_R(13.68897915) + n * (PF_R(5.850288868) +
               n * (PF_R(1.95705688) + n))))), PF_R(1.0));
    }
#endif
}

/* nu / G1(nu) = nu (1 + Lambda(nu)) for nu > 0 (internal: the facing areas of pf_beckmann.h,
   P = sqrt(2 var) nu / G1(nu) toward a direction above the mean plane). The same fit as
   pf_g1_beckmann without forming G1 first: float Q5(n) / P4(n) (n = nu clamped to [0, 3.1];
   beyond, G1 = 1 and the max returns nu), double nu + exp(-nu^2) K(nu) / (2 sqrt(pi)) below
   2, nu (1 + Lambda) above. Limit 1/(2 sqrt(pi)) at nu -> 0; callers pass nu > 0 (nu <= 0
   and NaN give that limit in float). */
PF_DEF pf_real pf_smith_nu_over_g1(pf_real nu)
{
#ifdef PF_DOUBLE
    if (nu < PF_R(2.0)) return pf_max(nu, PF_R(0.0)) + pf_exp_neg_sq(nu) * pf_smith_k(pf_max(nu, PF_R(0.0))) * (PF_R(0.5) * PF_INV_SQRT_PI);
    return nu + nu * pf_lambda_beckmann(nu);
#else
    {
        pf_real n = PFI_SMITH_CLAMP0(nu, PF_R(3.1));
        return pf_max((PF_R(10.27353954) + n * (PF_R(18.48168564) + n * (PF_R(13.68897915) + n * (PF_R(5.850288868) +
                      n * (PF_R(1.95705688) + n))))) /
                      (PF_R(36.41876602) + n * (PF_R(0.9635340571) + n * (PF_R(10.42804337) +
                      n * (PF_R(1.123634458) + n * PF_R(1.061310649))))), nu);
    }
#endif
}

/* ---------------------------------------------------------------- Walter et al. 2007 tier
   The rational approximation of Walter et al. 2007 as quoted in Dupuy et al. 2013 sec. 4.3:
       Lambda ~ (1 - 1.259 nu + 0.396 nu^2) / (3.535 nu + 2.181 nu^2)  for nu < 1.6, else 0.
   Its numerator has roots at nu = 1.5482 and 1.6311, so as published Lambda is negative on
   [1.5482, 1.6) and G1 = 1/(1 + Lambda) reaches 1.00006. Our Walter tier clamps Lambda at 0
   (G1 at 1) there and is otherwise the published formula. Max relative error of G1:
   3.13e-3 at nu = 1.336 (measured in tests/test_smith.c). Kept as the baseline most
   renderers ship; prefer pf_g1_beckmann_fast (30x more accurate, cost in docs/smith.md). */
PF_DEF pf_real pf_lambda_beckmann_walter(pf_real nu)
{
    if (!(nu > PF_R(0.5) * PF_INV_SQRT_PI / PF_LAMBDA_MAX)) return PF_LAMBDA_MAX;
    if (nu >= PF_R(1.6)) return PF_R(0.0);
    return pf_clamp((PF_R(1.0) - PF_R(1.259) * nu + PF_R(0.396) * nu * nu) /
                    (PF_R(3.535) * nu + PF_R(2.181) * nu * nu), PF_R(0.0), PF_LAMBDA_MAX);
}

/* G1 of the Walter tier: 1/(1 + Lambda_walter) simplified to one rational,
   nu (3.535 + 2.181 nu) / (1 + 2.276 nu + 2.577 nu^2), clamped to [0, 1]. */
PF_DEF pf_real pf_g1_beckmann_walter(pf_real nu)
{
    if (!(nu > PF_R(0.0))) return PF_R(0.0);
    if (nu >= PF_R(1.6)) return PF_R(1.0);
    return pf_min(nu * (PF_R(3.535) + PF_R(2.181) * nu) / (PF_R(1.0) + nu * (PF_R(2.276) + PF_R(2.577) * nu)),
                  PF_R(1.0));
}

/* ---------------------------------------------------------------- our fast tier
   G1 = nu P3(nu) / Q2(nu) with nu clamped to [0, 2.2]: a near-minimax relative fit of
   G1/nu on [0, 2.2] that is also pulled toward G1 = 1 at 2.2, so that the clamped value
   serves every nu beyond (bench/fit/fit_smith.py, 'fast'). Without branches (a max and a min
   instead of Walter's two tests) and continuous (no jump at a cutoff). Max relative error
   of G1 1.05e-4 over all nu > 0 (30x below Walter's 3.13e-3); it peaks at 0.99994 < 1, so it
   never leaves [0, 1]; at nu = 0 (and nu <= 0, NaN) it is exactly 0. The denominator is
   monic (one multiply fewer). */
PF_DEF pf_real pf_g1_beckmann_fast(pf_real nu)
{
    pf_real n = pf_min(pf_max(nu, PF_R(0.0)), PF_R(2.2)); /* max first: NaN -> 0 */
    return n * (PF_R(4.018333074) + n * (PF_R(-0.6657327309) + n * (PF_R(0.5771723645) +
           n * PF_R(-0.07668278205)))) / (PF_R(1.133668816) + n * (PF_R(1.815881917) + n));
}

/* Lambda of the fast tier: relative accuracy at shader cost, the Lambda analogue
   of pf_erfc_fast. Lambda = exp(-nu^2) K(nu) / (2 sqrt(pi) nu) (see the exact path above),
   and K(nu) (nu + 2.5)^2 / (2 sqrt(pi)) is flat (0.5 .. 0.16), so with z = 1/(nu + 2.5)
       Lambda = exp(-nu^2) z^2 L(z) / nu,
   L a degree-7 polynomial fitted in relative error on 0 <= nu <= 10.5 (fit error 1.6e-6,
   bench/fit/fit_smith.py lambda_fast), written in w = 1.81024396 z where z^2 L is monic. No
   branch (one select for nu <= 0 and NaN, PF_LAMBDA_MAX as everywhere), no cancellation, and
   the tail keeps its relative accuracy (Walter's form and the earlier rational fast tier
   returned 0 past 1.6 / 2.2, where Lambda is still 1.8e-3 / 8.2e-5).
   Measured max relative error (tests/test_smith.c, against the quadrature of the definition):
   float <= 2e-6 + 6e-8 nu^2 (the second term the rounding of nu*nu inside exp); double
   <= 1.7e-6. Underflows to 0 past nu ~ 10 (float). */
#define PFI_LAMBDA_FAST_NU_MIN PF_R(2.8209761e-31) /* Lambda(nu) <= PF_LAMBDA_MAX above it */
PF_DEF pf_real pf_lambda_beckmann_fast(pf_real nu)
{
    pf_real n = pf_max(nu, PFI_LAMBDA_FAST_NU_MIN); /* NaN -> the minimum; selected away below */
    pf_real w = PF_R(1.81024396) / (n + PF_R(2.5));
    pf_real p = PF_R(0.0428032763) + w * (PF_R(0.125360042) + w * (PF_R(0.153485239) + w * (PF_R(0.790205717) +
                w * (PF_R(-1.16572356) + w * (PF_R(3.68183589) + w * (PF_R(-3.4192481) + w))))));
    pf_real lam = PF_EXP(-n * n) * ((w * w) * p) / n;
    return nu > PFI_LAMBDA_FAST_NU_MIN ? lam : PF_LAMBDA_MAX;
}

/* ---------------------------------------------------------------- GGX (Trowbridge-Reitz)
   Smith Lambda of the GGX slope distribution (Walter et al. 2007), anisotropic with roughness
   alpha_x, alpha_y along the tangent axes: with t^2 = (alpha_x^2 w.x^2 + alpha_y^2 w.y^2)/w.z^2
   (= alpha(phi)^2 tan^2 theta),
       Lambda = (sqrt(1 + t^2) - 1)/2 = t^2 / (2 (1 + sqrt(1 + t^2)))    (no cancellation)
       G1 = 2 / (1 + sqrt(1 + t^2)), t computed as u / w.z, u = sqrt(alpha_x^2 w.x^2 + alpha_y^2 w.y^2).
   Centered only. w need not be normalized; w.z <= 0 gives Lambda = PF_LAMBDA_MAX, G1 = 0.
   Lambda saturates at PF_LAMBDA_MAX at grazing angles instead of overflowing. */
PF_DEF pf_real pf_lambda_ggx(pf_vec3 w, pf_real alpha_x, pf_real alpha_y)
{
    pf_real u, t;
    if (!(w.z > PF_R(0.0))) return PF_LAMBDA_MAX;
    u = PF_SQRT(pf_sq(alpha_x * w.x) + pf_sq(alpha_y * w.y)); /* t w.z */
    if (!(u < PF_R(2.0) * PF_LAMBDA_MAX * w.z)) return PF_LAMBDA_MAX;
    t = u / w.z;
    if (t > PF_R(1.0e18)) return PF_R(0.5) * t; /* t^2 would overflow float; 1/t is negligible */
    return t * t / (PF_R(2.0) * (PF_R(1.0) + PF_SQRT(PF_R(1.0) + t * t)));
}

/* G1 of GGX, 1/(1 + Lambda) = 2 / (1 + sqrt(1 + t^2)), from t = u / w.z so that no square
   of a component of w is formed (w.z^2 overflows float for |w.z| > 1.8e19, and w need not
   be normalized); past t = 1e18, where t^2 would overflow, G1 = 2/t to float precision. */
PF_DEF pf_real pf_g1_ggx(pf_vec3 w, pf_real alpha_x, pf_real alpha_y)
{
    pf_real u, t;
    if (!(w.z > PF_R(0.0))) return PF_R(0.0);
    u = PF_SQRT(pf_sq(alpha_x * w.x) + pf_sq(alpha_y * w.y)); /* t w.z */
    if (!(u < PF_R(1.0e18) * w.z)) return PF_R(2.0) * (w.z / u);
    t = u / w.z;
    return PF_R(2.0) / (PF_R(1.0) + PF_SQRT(PF_R(1.0) + t * t));
}

/* Isotropic GGX from cos theta (clamped to [-1, 1]). */
PF_DEF pf_real pf_lambda_ggx_iso(pf_real cos_theta, pf_real alpha)
{
    pf_real c = pf_min(cos_theta, PF_R(1.0));
    pf_real s = PF_SQRT(pf_max(PF_R(1.0) - c * c, PF_R(0.0)));
    return pf_lambda_ggx(pf_vec3_make(s, PF_R(0.0), c), alpha, alpha);
}

/* Isotropic GGX G1 from cos theta. */
PF_DEF pf_real pf_g1_ggx_iso(pf_real cos_theta, pf_real alpha)
{
    pf_real c = pf_min(cos_theta, PF_R(1.0));
    pf_real s = PF_SQRT(pf_max(PF_R(1.0) - c * c, PF_R(0.0)));
    return pf_g1_ggx(pf_vec3_make(s, PF_R(0.0), c), alpha, alpha);
}

/* ---------------------------------------------------------------- masking-shadowing
   The joint (height-correlated) moment E[V_o V_i] = 1/(1 + Lambda_o + Lambda_i) (Smith 1967;
   Dupuy et al. 2013 eq. 13), written in terms of the two G1 = 1/(1 + Lambda):
       1/(1 + Lambda_o + Lambda_i) = G1o G1i / (G1o + G1i - G1o G1i),
   which stays finite when a Lambda is huge; 0 when either G1 is 0 (a direction below the
   mean surface), never 0/0. A G1 above 1 (impossible; any finite input is accepted) is read
   as 1. The result lies in [0, min(G1o, G1i)]. */
PF_DEF pf_real pf_smith_joint(pf_real g1_o, pf_real g1_i)
{
    pf_real a = pf_min(PF_R(1.0), g1_o), b = pf_min(PF_R(1.0), g1_i); /* NaN stays NaN */
    if (!(a > PF_R(0.0)) || !(b > PF_R(0.0))) return PF_R(0.0);
    /* a (b / den), not a b / den: the denominator den = b + a (1 - b) >= b, so b / den <= 1
       and the result <= a, even where a b is subnormal (a = 1.2e-33, b = 4.4e-8 lost the
       product's low bits and came out 1.00013 a) */
    return a * (b / (a + b - a * b));
}

/* The same moment from the two Lambdas; negative Lambdas (impossible, but produced by some
   approximations) are read as 0. PF_LAMBDA_MAX inputs give ~5e-31, not exactly 0: prefer
   pf_smith_joint when a direction may be below the surface. */
PF_DEF pf_real pf_smith_joint_lambda(pf_real lambda_o, pf_real lambda_i)
{
    return PF_R(1.0) / (PF_R(1.0) + pf_max(lambda_o, PF_R(0.0)) + pf_max(lambda_i, PF_R(0.0)));
}

/* Separable (uncorrelated) masking-shadowing G1o G1i, for comparison: it double-counts
   occlusion, always <= the joint form. Each G1 is clamped to [0, 1] (NaN to 0) first, so the
   product is in [0, 1] for every input (a product of two finite values can overflow). */
PF_DEF pf_real pf_smith_separable(pf_real g1_o, pf_real g1_i)
{
    return pf_min(pf_max(g1_o, PF_R(0.0)), PF_R(1.0)) * pf_min(pf_max(g1_i, PF_R(0.0)), PF_R(1.0));
}

/* Joint Beckmann masking-shadowing from the two nus (pf_smith_nu of view and light). */
PF_DEF pf_real pf_g2_beckmann(pf_real nu_o, pf_real nu_i)
{
    return pf_smith_joint(pf_g1_beckmann(nu_o), pf_g1_beckmann(nu_i));
}

#endif /* PF_SMITH_H */

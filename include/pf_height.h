/* pf_height.h - Gaussian height fields seen through Smith visibility: the visibility of a
   point at height h, the visible height distribution, and colour maps (or height transfer
   functions) filtered over a Gaussian distribution.

   A microsurface whose heights are Gaussian, N(0, sigma_h^2), seen from a direction with Smith
   masking Lambda (any microfacet model: pf_smith.h gives Lambda for Beckmann and GGX), shows a
   point at height h with probability P_h(h)^Lambda, P_h the height CDF (Heitz et al. 2014
   eq. 2; Heitz & Neyret 2011 eq. 6). Averaging over heights gives closed forms (eqs. 3, 12) and
   the visible height distribution D_h (eq. 15), which this module evaluates three ways (the
   published fit, our fit, a fixed quadrature). Colour maps C(v) filtered over a Gaussian
   N(mean, sigma^2) (Heitz et al. 2014 eqs. 7-9) are given in closed form for piecewise-linear,
   step and smoothstep maps, and as the paper's pre-convolved 2D table. Height-correlated colour
   (eq. 13) combines the two, and a piecewise-linear height transfer function h = g(f) gets its
   height and slope moments the same way (eqs. 19-28).

   USAGE
     #include "pf_height.h"
     pf_real lo = pf_lambda_beckmann(pf_smith_nu(wo, s)), li = pf_lambda_beckmann(pf_smith_nu(wi, s));
     pf_height_dist d = pf_height_colour_dist(lo, li, mean_h, sigma_h, PF_R(0.0), PF_R(0.0));
     -- shader loop over the knots (x[k], c[k]) of a colour map:
     pf_real col = c[0] * pf_gauss_cdf(x[0], d.mean, d.dev) + c[n-1] * pf_gauss_step(x[n-1], d.mean, d.dev);
     for (k = 0; k + 1 < n; k++) {
         pf_vec2 w = pf_gauss_segment_weights(x[k], x[k+1], d.mean, d.dev);
         col += w.x * c[k] + w.y * c[k+1];
     }
     col *= pf_height_mean_visibility(lo, li);          -- eq. 13: C_h = Vbar <C, D_h>
     -- or on the CPU: pf_height_colormap_filter(x, c, n, 3, lo, li, mean_h, sigma_h, 0, 0, rgb);

   FUNCTIONS
     height CDF        pf_height_pdf, pf_height_cdf, pf_height_log_cdf (z = h / sigma_h)
     visibility        pf_height_visibility (P_h(z)^Lambda, eq. 2)
     closed forms      pf_height_mean_visibility ((1+Lo)/(1+Lo+Li), eq. 12),
                       pf_height_joint_visibility (1/(1+Lo+Li)),
                       pf_height_attribute_mean (a0 + s (L+1)/(L+2), eq. 3; HN11 eq. 19)
     visible heights   pf_height_dist_make, pf_visible_height_published (eqs. 16-17 as
                       published), pf_visible_height (ours), pf_visible_height_exact (quadrature),
                       pf_height_dist_rescale, pf_height_dist_add_noise, pf_height_colour_dist
     Gaussian filters  pf_gauss_cdf, pf_gauss_step, pf_gauss_segment_weights,
                       pf_gauss_smoothstep
     transfer function pf_transfer_moments_make, pf_transfer_moments_add,
                       pf_transfer_segment_moments, pf_transfer_end_moments,
                       pf_transfer_height, pf_transfer_slope_stats (eqs. 19-28)
     CPU only (#ifndef PF_GLSL, linkage PF_CPU_DEF: they walk caller-owned arrays; no
     allocation, no I/O)
                       pf_colormap_filter, pf_height_colormap_filter, pf_transfer_moments_filter,
                       pf_colormap_table_size, pf_colormap_table_build, pf_colormap_table_lookup

   CONVENTIONS
     Heights. Every function of a height takes z = (h - mean_h) / sigma_h, the height in units of
     the height deviation, and the visible-height functions return the mean and deviation of D_h
     in the same units (mu_d / sigma_h, sigma_d / sigma_h): D_h depends on Lambda only once
     heights are standardized. pf_height_dist_rescale converts to world heights.
     Lambda is the SUM Lambda_o + Lambda_i for the visible-height functions (D_h depends on the
     sum only, eq. 15); negative and NaN Lambdas read as 0, anything above PF_LAMBDA_MAX as
     PF_LAMBDA_MAX (a direction below the surface). The visibility, visible-height and
     Gaussian-filter functions return finite values for every finite input, and for Lambda = 0
     and Lambda = PF_LAMBDA_MAX. The linear maps of heights and values (pf_height_attribute_mean,
     pf_height_dist_rescale, _add_noise, pf_height_colour_dist, pf_transfer_end_moments,
     pf_transfer_segment_moments, pf_transfer_slope_stats) are finite while their inputs, and
     for the transfer moments the slope (g1 - g0)/(x1 - x0) of every piece, stay below
     sqrt(PF_REAL_MAX)/4 (4.6e18 in float) in magnitude: beyond, a sum, a product or a square
     (g^2, g'^2, sigma^2) overflows, as its exact value may.
     Colour maps are piecewise linear through knots (x[k], c[k]) with x non-decreasing, constant
     beyond the end knots (c[0] below x[0], c[n-1] above x[n-1]); two equal x make a jump.
     Filtering means the expectation E[C(X)], X ~ N(mean, sigma^2). sigma <= 0 (or NaN) means
     no filtering: the map's own value (at a jump, the mean of the two sides). Colour channels
     are independent: the weights of pf_gauss_segment_weights serve all channels.
     CPU-only functions (pf_core.h, "CPU only: sizes and errors"). Every argument is checked
     before anything is read or written. pf_colormap_filter, pf_height_colormap_filter,
     pf_colormap_table_build and pf_colormap_table_lookup return PF_OK (0), PF_ERR_ARG (-1) for
     a NULL pointer, n < 1 knots, channels < 1, table sides < 2 or a table range that is empty,
     reversed or not finite (its bounds, width or sample step), PF_ERR_SIZE (-2) for a table
     side above PF_MAX_SIDE (2^24), a table above PF_MAX_REALS reals or n * channels above
     PF_MAX_REALS; on an error they write nothing (*t included). pf_colormap_table_size returns
     the table's reals as a long long, 0 for every size the builder rejects.
     pf_transfer_moments_filter returns zeros for NULL arrays or n < 1. Offsets are long long;
     the one thing the code cannot check is that a buffer holds what the comment says: x and c
     (or g) n and n * channels reals, out channels, a table pf_colormap_table_size reals. A NaN
     mean makes every knot read as standing at the mean: out = (c[0] + c[n-1]) / 2 (finite,
     meaningless); NaN sigma means no filtering (as sigma <= 0).

   ACCURACY AND COST (measured: docs/height.md, tests/test_height.c, bench/bench_height.c)
     pf_height_visibility      relative error ~ eps (1 + |log V| + Lambda z^2), the conditioning
                               of P^Lambda.
     pf_visible_height         ours: (4,5) rationals in s = sqrt(log(1+Lambda)); fit error of
                               mu_d 9.5e-6, sigma_d 6.7e-5 (relative) over every Lambda >= 0;
                               one sqrt, two divisions, and one log (Lambda > 1) or a
                               degree-6 series and a division (Lambda <= 1).
     pf_visible_height_published  Heitz et al. 2014 eqs. 16-17, valid for 0 <= Lambda <= 1900:
                               mu_d off by up to 0.131 sigma_h (at Lambda = 0.56; 20% at
                               Lambda = 1), sigma_d by up to 5.3% (at Lambda = 26). Beyond
                               1900 both errors grow without bound (mu_d +0.35 sigma_h at 1e4,
                               +2.6 at 1e9, +16 at 1e30): use pf_visible_height there.
     pf_visible_height_exact   64-node sinh-mapped trapezoidal rule: mu_d ~1e-9, sigma_d ~5e-8
                               relative in double (rounding-limited in float); ~1000x the fit.
     colour filters            closed form, absolute error a few eps per knot within ~5 sigma.
     GLSL                      no step needs exact rounding (the private log1p is a series near
                               0), so shader compilers cannot fold accuracy away; measured on
                               lavapipe and bounded by the GLSL precision rules: docs/gpu.md.

   SOURCES
     Heitz, Nowrouzezahrai, Poulin, Neyret 2014, Filtering Non-Linear Transfer Functions on
     Surfaces, eqs. 2-3, 6-17, 19-28; Heitz & Neyret 2011, A Visibility-Aware Model for
     Pre-Filtering and Rendering Surfaces in Real-Time (RR-7827), eqs. 4-7, 17-20, appendix A;
     Smith 1967.

   LICENCE: MIT (see README.md). */
#ifndef PF_HEIGHT_H
#define PF_HEIGHT_H

#ifndef PF_GLSL
#  include "pf_smith.h"
#endif

#define PFI_INV_SQRT_2PI PF_R(0.398942280401432677939946059934381868)
#define PFI_LOG_SQRT_2PI PF_R(0.918938533204672741780329736405617640)

/* ---------------------------------------------------------------- private helpers */
/* log(1 + x) for x > -1, accurate relative to itself for tiny |x|, with no step that needs
   exact rounding (a shader compiler may fold (1 + x) - 1 to x: GLSL without `precise` allows
   it, and Goldberg's log(u) x / (u - 1) then returns log(u), whose GLSL error near u = 1 is an
   absolute 2^-21, docs/gpu.md). For -1/2 <= x <= 1 no log is called: log(1 + x) =
   2 atanh(t) = 2 (t + t^3/3 + t^5/5 + ...), t = x / (2 + x), |t| <= 1/3; the terms are
   truncated where what is left is below 0.12 ulp (float: through t^13, double: through t^31;
   the left-over is t^2k / (2k + 1) <= 9^-k / (2k + 1) relative). Outside, 1 + x is exact (x < -1/2,
   Sterbenz) or rounds by half an ulp of a value whose log is >= log 2, so the built-in log
   (3 ulp there in GLSL) is accurate relative to the result. Measured against log1pl:
   1.46 ulp (float), 1.39 ulp (double) (tests/test_height.c, test_log1p_series). */
PF_DEF pf_real pfi_log1p(pf_real x)
{
    pf_real t, t2, p;
    if (!(x >= PF_R(-0.5) && x <= PF_R(1.0))) return PF_LOG(PF_R(1.0) + x);
    if (PF_FABS(x) < PF_R(0.25) * PF_REAL_EPSILON) return x; /* x - x^2/2 rounds to x; and x/2
                                                                 would lose subnormal bits */
    t = x / (PF_R(2.0) + x);
    t2 = t * t;
#ifdef PF_DOUBLE
    /* 1/17, ..., 1/31, then 1/3, ..., 1/15 */
    p = PF_R(0.0588235294117647058823529) + t2 * (PF_R(0.0526315789473684210526316)
      + t2 * (PF_R(0.0476190476190476190476190) + t2 * (PF_R(0.0434782608695652173913043)
      + t2 * (PF_R(0.04) + t2 * (PF_R(0.0370370370370370370370370)
      + t2 * (PF_R(0.0344827586206896551724138) + t2 * PF_R(0.0322580645161290322580645)))))));
    p = PF_R(0.333333333333333333333333) + t2 * (PF_R(0.2) + t2 * (PF_R(0.142857142857142857142857)
      + t2 * (PF_R(0.111111111111111111111111) + t2 * (PF_R(0.0909090909090909090909091)
      + t2 * (PF_R(0.0769230769230769230769231) + t2 * (PF_R(0.0666666666666666666666667)
      + t2 * p))))));
#else
    /* 1/3, 1/5, ..., 1/13 */
    p = PF_R(0.333333333333333333333333) + t2 * (PF_R(0.2) + t2 * (PF_R(0.142857142857142857142857)
      + t2 * (PF_R(0.111111111111111111111111) + t2 * (PF_R(0.0909090909090909090909091)
      + t2 * PF_R(0.0769230769230769230769231)))));
#endif
    /* 2t + 2t t^2 p: the leading term added last keeps the relative accuracy of t */
    return PF_R(2.0) * t + PF_R(2.0) * t * (t2 * p);
}

/* Beyond |t| = PFI_TAIL_ZERO the normal tail and density are below the smallest normal
   number of pf_real; they are returned as 0 there, which avoids subnormal arithmetic (100x
   slower on x86) for a relative change far below one unit of the results they feed. */
#ifdef PF_DOUBLE
#  define PFI_TAIL_ZERO PF_R(37.5)
#else
#  define PFI_TAIL_ZERO PF_R(13.0)
#endif

/* Both tails of the standard normal from one erfc: (P(Z < t), P(Z >= t)), each accurate
   relative to itself (the small one comes straight from erfc, the large one is 1 - small). */
PF_DEF pf_vec2 pfi_normal_tails(pf_real t)
{
    pf_real at = PF_FABS(t);
    pf_real tail = at < PFI_TAIL_ZERO ? PF_R(0.5) * pf_erfc(at * PF_INV_SQRT2) : PF_R(0.0);
    pf_real rest = PF_R(1.0) - tail;
    return t < PF_R(0.0) ? pf_vec2_make(tail, rest) : pf_vec2_make(rest, tail);
}

/* The standardized position (x - mean) / sigma, clamped to [-40, 40] (every normal tail
   beyond is 0 in double) and computed without dividing when it would leave that range, so
   sigma = 0 gives -40, 0 or 40: the unfiltered (delta) limit. */
PF_DEF pf_real pfi_standardize(pf_real x, pf_real mean, pf_real sigma)
{
    pf_real d = x - mean;
    if (PF_FABS(d) < PF_R(40.0) * sigma) return d / sigma;
    return d > PF_R(0.0) ? PF_R(40.0) : (d < PF_R(0.0) ? PF_R(-40.0) : PF_R(0.0));
}

/* ---------------------------------------------------------------- height CDF and visibility */
/* Standard normal density phi(z) = exp(-z^2/2) / sqrt(2 pi), the height density p_h in units
   of sigma_h. Every real z; 0 beyond |z| = 13 (float) / 37.5 (double), where it would be
   subnormal. */
PF_DEF pf_real pf_height_pdf(pf_real z)
{
    if (!(PF_FABS(z) < PFI_TAIL_ZERO)) return PF_R(0.0);
    return pf_exp_neg_sq(z * PF_INV_SQRT2) * PFI_INV_SQRT_2PI;
}

/* P_h = Phi(z) = 1 - erfc(z / sqrt 2) / 2 (Heitz et al. 2014 after eq. 2), computed as
   erfc(-z / sqrt 2) / 2 so that the lower tail keeps its relative accuracy. */
PF_DEF pf_real pf_height_cdf(pf_real z)
{
    return PF_R(0.5) * pf_erfc(-z * PF_INV_SQRT2);
}

/* Where log Phi switches to the asymptotic series (erfc is still a normal number there). */
#ifdef PF_DOUBLE
#  define PFI_LOGCDF_ASYM PF_R(-26.0)
#else
#  define PFI_LOGCDF_ASYM PF_R(-10.0)
#endif

/* log Phi(z), accurate in both tails, every real z (finite result).
   z >= 0: log(1 - Q), Q = erfc(z/sqrt 2)/2 <= 1/2, through log1p, so -Q survives when
           1 - Q rounds to 1 (what P_h^Lambda needs for large Lambda).
   PFI_LOGCDF_ASYM <= z < 0: log of Phi from erfc (relative accuracy kept).
   z below: Phi(z) = phi(z)/|z| * M(1/z^2), M = 1 - s + 3 s^2 - 15 s^3 + ... (the asymptotic
           series of Mills' ratio), truncated where its terms fall below the unit roundoff
           (float: through s^6 at |z| >= 10, double: through s^8 at |z| >= 26).
   z is clamped to z >= -1e4 (log Phi >= -5e7), which keeps Lambda * log Phi finite for every
   Lambda <= PF_LAMBDA_MAX; NaN reads as -1e4. */
PF_DEF pf_real pf_height_log_cdf(pf_real z)
{
    pf_real zc = pf_max(z, PF_R(-1.0e4));
    pf_real s, m;
    if (zc >= PFI_TAIL_ZERO) return PF_R(0.0); /* -Q(z) < smallest normal: times Lambda <=
                                                  PF_LAMBDA_MAX it changes V by < 1e-8 (float) */
    if (zc >= PF_R(0.0)) return pfi_log1p(PF_R(-0.5) * pf_erfc(zc * PF_INV_SQRT2));
    if (zc >= PFI_LOGCDF_ASYM) return PF_LOG(PF_R(0.5) * pf_erfc(-zc * PF_INV_SQRT2));
    s = PF_R(1.0) / (zc * zc);
#ifdef PF_DOUBLE
    m = s * (PF_R(-1.0) + s * (PF_R(3.0) + s * (PF_R(-15.0) + s * (PF_R(105.0) + s * (PF_R(-945.0)
        + s * (PF_R(10395.0) + s * (PF_R(-135135.0) + s * PF_R(2027025.0))))))));
#else
    m = s * (PF_R(-1.0) + s * (PF_R(3.0) + s * (PF_R(-15.0) + s * (PF_R(105.0) + s * (PF_R(-945.0)
        + s * PF_R(10395.0))))));
#endif
    return PF_R(-0.5) * zc * zc - PF_LOG(-zc) - PFI_LOG_SQRT_2PI + pfi_log1p(m);
}

/* Smith visibility of a point at standardized height z from a direction of masking Lambda:
   V = P_h(z)^Lambda (Heitz et al. 2014 eq. 2; Heitz & Neyret 2011 eq. 6), as
   exp(Lambda log Phi(z)). Lambda is clamped to [0, PF_LAMBDA_MAX] (NaN -> 0): V = 1 for
   Lambda = 0 at every z, and V -> 0 below the surface's mass for PF_LAMBDA_MAX. Range [0, 1].
   The product Lambda log Phi cannot overflow (see pf_height_log_cdf). */
PF_DEF pf_real pf_height_visibility(pf_real z, pf_real lambda)
{
    pf_real l = pf_min(pf_max(lambda, PF_R(0.0)), PF_LAMBDA_MAX);
    if (!(l > PF_R(0.0))) return PF_R(1.0);
    return PF_EXP(l * pf_height_log_cdf(z));
}

/* ---------------------------------------------------------------- closed forms */
/* A Lambda for these sums: [0, PF_LAMBDA_MAX], NaN -> 0. */
PF_DEF pf_real pfi_lambda_clamp(pf_real lambda)
{
    return pf_min(pf_max(lambda, PF_R(0.0)), PF_LAMBDA_MAX);
}

/* Mean visibility toward the light of the points visible from the view,
   Vbar = E[V_o V_i] / E[V_o] = (1 + Lambda_o) / (1 + Lambda_o + Lambda_i)
   (Heitz et al. 2014 eq. 12; the denominator integral there carries p_h, as in eq. 11).
   Range (0, 1]. Both at PF_LAMBDA_MAX gives 1/2; Lambda_o = PF_LAMBDA_MAX with a finite
   Lambda_i gives ~1 (the view sees nothing; the limit of the ratio). */
PF_DEF pf_real pf_height_mean_visibility(pf_real lambda_o, pf_real lambda_i)
{
    pf_real lo = pfi_lambda_clamp(lambda_o), li = pfi_lambda_clamp(lambda_i);
    return (PF_R(1.0) + lo) / ((PF_R(1.0) + lo) + li);
}

/* The masking-shadowing moment E[V_o V_i] = integral of Phi^(Lo+Li) p_h = 1/(1 + Lo + Li)
   (the normalization of eq. 15; the same as pf_smith_joint_lambda). */
PF_DEF pf_real pf_height_joint_visibility(pf_real lambda_o, pf_real lambda_i)
{
    return PF_R(1.0) / ((PF_R(1.0) + pfi_lambda_clamp(lambda_o)) + pfi_lambda_clamp(lambda_i));
}

/* Visible mean of a height-correlated attribute a(z) = a0 + amplitude * P_h(z), weighted by
   V_o V_i: a0 + amplitude (L + 1)/(L + 2), L = Lambda_o + Lambda_i (Heitz et al. 2014 eq. 3;
   Heitz & Neyret 2011 eq. 19, whose appendix A shader uses a0 - amplitude/2 as a0 so that a0
   is the unmasked mean). Written as a0 + amplitude (1 - 1/(L + 2)): finite for every Lambda. */
PF_DEF pf_real pf_height_attribute_mean(pf_real a0, pf_real amplitude, pf_real lambda_o,
                                        pf_real lambda_i)
{
    pf_real l = pfi_lambda_clamp(lambda_o) + pfi_lambda_clamp(lambda_i);
    return a0 + amplitude * (PF_R(1.0) - PF_R(1.0) / (l + PF_R(2.0)));
}

/* ---------------------------------------------------------------- visible height distribution
   D_h(z) = (L + 1) phi(z) Phi(z)^L, L = Lambda_o + Lambda_i (Heitz et al. 2014 eq. 15; the
   normalizing integral of phi Phi^L is 1/(L + 1)). For an integer L it is the density of the
   largest of L + 1 standard normals. It is approximated by a Gaussian of mean mu_d and
   deviation sigma_d (eqs. 16-17); here mu_d = E[z] and sigma_d = sqrt(E[(z - mu_d)^2]), the
   central deviation (eq. 17 writes the raw second moment, but its fit and the way the paper
   samples the table follow the central one). Units of sigma_h. */
PF_STRUCT_BEGIN(pf_height_dist)
    pf_real mean;
    pf_real dev;
PF_STRUCT_END(pf_height_dist)

PF_DEF pf_height_dist pf_height_dist_make(pf_real mean, pf_real dev)
{
    pf_height_dist d;
    d.mean = mean;
    d.dev = dev;
    return d;
}

/* The published fits (Heitz et al. 2014 eqs. 16-17; the mean also in Heitz & Neyret 2011
   sec. 4.4): mu_d = 0.39 log(1 + 4.75 L), sigma_d = 1 / (1 + 0.26 log(1 + 1.13 L)). Kept to
   reproduce the paper; lambda is the sum Lambda_o + Lambda_i. Valid range 0 <= L <= 1900,
   where (measured against quadrature of eq. 15, tests/test_height.c, float and double alike)
   |mu_d error| <= 0.131 sigma_h (max at L = 0.56, +0.131; -0.122 at L = 42; the mean's slope
   at L = 0 is 1.85, twice the true 0.90) and |sigma_d error| <= 5.33% relative (max at
   L = 26). Beyond L = 1900 the fit's 0.39 log L outgrows the true sqrt(2 log L): the mu_d
   error rises monotonically (+0.35 sigma_h at L = 1e4, +1.13 at 1e6, +2.60 at 1e9, +16.0 at
   1e30, where it returns (27.55, 0.0527) for the true (11.51, 0.110)) and the sigma_d error
   falls monotonically (-4.0% at 1e4, past -5.33% from L = 1.9e4, -23% at 1e9, -52% at 1e30).
   Every L still gives finite values (L is clamped to [0, PF_LAMBDA_MAX], NaN -> 0). */
PF_DEF pf_height_dist pf_visible_height_published(pf_real lambda)
{
    pf_real l = pfi_lambda_clamp(lambda);
    return pf_height_dist_make(PF_R(0.39) * PF_LOG(PF_R(1.0) + PF_R(4.75) * l),
                               PF_R(1.0) / (PF_R(1.0) + PF_R(0.26) * PF_LOG(PF_R(1.0) + PF_R(1.13) * l)));
}

/* Our fit (bench/fit/height_fit.py): with s = sqrt(log(1 + L)),
       mu_d = s^2 P4(s) / Q5(s),   sigma_d = R4(s) / S5(s),
   near-minimax relative fits over every L in [0, PF_LAMBDA_MAX] (s in [0, 8.31]). The degree
   gap makes mu_d grow like s ~ sqrt(log L) and sigma_d decay like 1/s, the true (Gumbel)
   limits, so the fit stays smooth and monotone up to PF_LAMBDA_MAX. Fit error: mu_d 9.5e-6
   relative (so |error| <= 1e-5 sigma_h near L = 0, where mu_d ~ 0.9026 L), sigma_d 6.7e-5.
   lambda is the sum Lambda_o + Lambda_i. */
PF_DEF pf_height_dist pf_visible_height(pf_real lambda)
{
    pf_real s = PF_SQRT(pfi_log1p(pfi_lambda_clamp(lambda)));
    pf_real mu = s * s * (PF_R(0.9032054649) + s * (PF_R(0.09398688501) + s * (PF_R(0.1293950471)
               + s * (PF_R(0.04201975653) + s * PF_R(0.02714740947)))))
               / (PF_R(1.0) + s * (PF_R(0.1045243097) + s * (PF_R(0.2991021495) + s * (PF_R(0.07478165888)
               + s * (PF_R(0.03475082509) + s * PF_R(0.01902182918))))));
    pf_real dev = (PF_R(1.00006528) + s * (PF_R(-0.1814207569) + s * (PF_R(0.139413217)
                + s * (PF_R(0.005615390157) + s * PF_R(0.04458963288)))))
                / (PF_R(1.0) + s * (PF_R(-0.1783649374) + s * (PF_R(0.4140540191) + s * (PF_R(0.01641131692)
                + s * (PF_R(0.01634804515) + s * PF_R(0.04868622173))))));
    return pf_height_dist_make(mu, dev);
}

/* mu_d and sigma_d by a fixed quadrature of eq. 15 (for verification; ~1000x the cost of the
   fit). The density is integrated on z = c + a sinh(x), x uniform on [-4, 5] with 64 nodes
   (trapezoidal rule; the ends carry negligible mass), where c, a = sigma/2 come from our fit:
   the sinh map puts the nodes densely on the peak and stretches them over the long right tail
   (which decays like phi, much slower than the peak's width for large L), and the trapezoidal
   rule converges geometrically for such smooth, fast-decaying integrands. The moments are
   accumulated about c (central, so sigma_d has no cancellation) and divided by the computed
   mass. Per node: one exp (sinh), one erfc, one log and one exp. Measured error over L in
   [0, PF_LAMBDA_MAX] (docs/height.md): mu_d 7.5e-10, sigma_d 4.5e-8 relative in double; in
   float it is at rounding level (1.3e-7, 1.2e-6). */
#define PFI_VH_NODES 64
PF_DEF pf_height_dist pf_visible_height_exact(pf_real lambda)
{
    pf_real l = pfi_lambda_clamp(lambda);
    pf_height_dist g = pf_visible_height(l);
    pf_real c = g.mean, a = PF_R(0.5) * g.dev;
    pf_real h = PF_R(9.0) / PF_R(PFI_VH_NODES - 1);
    pf_real log_n = pfi_log1p(l) - PFI_LOG_SQRT_2PI;
    pf_real m0 = PF_R(0.0), m1 = PF_R(0.0), m2 = PF_R(0.0), e1;
    int i;
    for (i = 0; i < PFI_VH_NODES; i++) {
        pf_real x = PF_R(-4.0) + h * PF_R(i);
        pf_real ex = PF_EXP(x), ix = PF_R(1.0) / ex;
        pf_real d = a * PF_R(0.5) * (ex - ix);  /* z - c */
        pf_real z = c + d;
        pf_real lp = l > PF_R(0.0) ? l * pf_height_log_cdf(z) : PF_R(0.0);
        /* the exponent is floored where the node's weight is negligible (< 1e-35 of the
           peak's), so no subnormal arithmetic slows the loop */
        pf_real v = PF_EXP(pf_max(log_n - PF_R(0.5) * z * z + lp, PF_R(-80.0))) * (a * PF_R(0.5) * (ex + ix));
        m0 += v;
        m1 += v * d;
        m2 += v * d * d;
    }
    e1 = m1 / m0;
    return pf_height_dist_make(c + e1, PF_SQRT(pf_max(m2 / m0 - e1 * e1, PF_R(0.0))));
}

/* From units of sigma_h to heights: mean_h + sigma_h mean, sigma_h dev. */
PF_DEF pf_height_dist pf_height_dist_rescale(pf_height_dist d, pf_real mean_h, pf_real sigma_h)
{
    return pf_height_dist_make(mean_h + sigma_h * d.mean, sigma_h * d.dev);
}

/* Heights perturbed by an independent noise r of mean mu_r and deviation sigma_r before the
   colour map is applied, C(h + r): the filtering distribution is the convolution, with mean
   mu_d + mu_r and variance sigma_d^2 + sigma_r^2 (Heitz et al. 2014 sec. 5.1, exact for the
   Gaussian approximation of D_h). */
PF_DEF pf_height_dist pf_height_dist_add_noise(pf_height_dist d, pf_real mu_r, pf_real sigma_r)
{
    return pf_height_dist_make(d.mean + mu_r, PF_SQRT(d.dev * d.dev + sigma_r * sigma_r));
}

/* The distribution a height-correlated colour map is filtered with (Heitz et al. 2014 sec. 5.1):
   our fit of D_h for Lambda_o + Lambda_i, in heights (mean_h, sigma_h), plus noise (mu_r,
   sigma_r; pass 0, 0 for none). Filter the map with it, then multiply by
   pf_height_mean_visibility (eq. 13). */
PF_DEF pf_height_dist pf_height_colour_dist(pf_real lambda_o, pf_real lambda_i, pf_real mean_h,
                                            pf_real sigma_h, pf_real mu_r, pf_real sigma_r)
{
    pf_height_dist d = pf_visible_height(pfi_lambda_clamp(lambda_o) + pfi_lambda_clamp(lambda_i));
    return pf_height_dist_add_noise(pf_height_dist_rescale(d, mean_h, sigma_h), mu_r, sigma_r);
}

/* ---------------------------------------------------------------- Gaussian filtering of maps
   E[C(X)], X ~ N(mean, sigma^2), is the colour map convolved with the Gaussian and read at the
   mean (Heitz et al. 2014 eqs. 7-9). For a linear piece it integrates in closed form: with
   a = (x0 - mean)/sigma, b = (x1 - mean)/sigma (standardized ends),
       M0 = Phi(b) - Phi(a),  M1 = integral_a^b t phi(t) dt = phi(a) - phi(b),
   the mass of [x0, x1) is M0 and E[u 1{x0 <= X < x1}] with u = (X - x0)/(x1 - x0) is
       U1 = ((mean - x0) M0 + sigma M1) / (x1 - x0).
   Mass differences use whichever tails are small, so they keep their accuracy far from the
   mean; U1 is clamped to [0, M0] (its true range), which bounds the cancellation of very
   narrow segments (x1 - x0 << sigma) by the segment's own small mass. */

/* Standardized knot: position t, lower and upper tails, density. */
PF_STRUCT_BEGIN(pfi_gauss_knot)
    pf_real t;
    pf_real lower;
    pf_real upper;
    pf_real pdf;
PF_STRUCT_END(pfi_gauss_knot)

PF_DEF pfi_gauss_knot pfi_gauss_knot_at(pf_real x, pf_real mean, pf_real sigma)
{
    pfi_gauss_knot k;
    pf_vec2 tails;
    k.t = pfi_standardize(x, mean, sigma);
    tails = pfi_normal_tails(k.t);
    k.lower = tails.x;
    k.upper = tails.y;
    k.pdf = pf_height_pdf(k.t);
    return k;
}

/* Phi(b) - Phi(a) from the tails that are small. */
PF_DEF pf_real pfi_gauss_mass(pfi_gauss_knot ka, pfi_gauss_knot kb)
{
    if (ka.t >= PF_R(0.0)) return pf_max(ka.upper - kb.upper, PF_R(0.0));
    if (kb.t <= PF_R(0.0)) return pf_max(kb.lower - ka.lower, PF_R(0.0));
    return pf_max(PF_R(1.0) - ka.lower - kb.upper, PF_R(0.0));
}

/* A segment narrow against sigma (x1 - x0 < sigma/8): the closed forms would cancel (their
   rounding grows like sigma/width), so (M0, U1, U2), U_k = E[u^k 1{segment}], come from the
   Taylor series of phi about the centre tc, half-width h = (x1 - x0)/(2 sigma), with
   phi(tc + tau) = phi(tc) sum_k (-1)^k He_k(tc) tau^k / k!:
     M0 = 2h phi (1 + He2 h^2/6 + He4 h^4/120 + He6 h^6/5040 + He8 h^8/362880)
     U1 = M0/2 - phi (tc h^2/3 + He3 h^4/30 + He5 h^6/840 + He7 h^8/45360)
     U2 = U1 - M0/4 + phi (h/6 + He2 h^3/20 + He4 h^5/336 + He6 h^7/12960)
   (h < 1/16: the first omitted terms are below 1e-16 relative). tc is clamped to [-40, 40]. */
PF_DEF pf_vec3 pfi_narrow_moments(pf_real x0, pf_real x1, pf_real mean, pf_real sigma)
{
    pf_real tc = pf_min(pf_max((PF_R(0.5) * (x0 + x1) - mean) / sigma, PF_R(-40.0)), PF_R(40.0));
    pf_real h = PF_R(0.5) * (x1 - x0) / sigma, h2 = h * h, t2 = tc * tc;
    pf_real ph = pf_height_pdf(tc);
    pf_real he2 = t2 - PF_R(1.0);
    pf_real he3 = tc * (t2 - PF_R(3.0));
    pf_real he4 = t2 * (t2 - PF_R(6.0)) + PF_R(3.0);
    pf_real he5 = tc * (t2 * (t2 - PF_R(10.0)) + PF_R(15.0));
    pf_real he6 = t2 * (t2 * (t2 - PF_R(15.0)) + PF_R(45.0)) - PF_R(15.0);
    pf_real he7 = tc * (t2 * (t2 * (t2 - PF_R(21.0)) + PF_R(105.0)) - PF_R(105.0));
    pf_real he8 = t2 * (t2 * (t2 * (t2 - PF_R(28.0)) + PF_R(210.0)) - PF_R(420.0)) + PF_R(105.0);
    pf_real m0 = PF_R(2.0) * h * ph * (PF_R(1.0) + h2 * (he2 / PF_R(6.0) + h2 * (he4 / PF_R(120.0)
               + h2 * (he6 / PF_R(5040.0) + h2 * he8 / PF_R(362880.0)))));
    pf_real u1 = PF_R(0.5) * m0 - ph * h2 * (tc / PF_R(3.0) + h2 * (he3 / PF_R(30.0) + h2 * (he5 / PF_R(840.0)
               + h2 * he7 / PF_R(45360.0))));
    pf_real u2 = u1 - PF_R(0.25) * m0 + ph * h * (PF_R(0.166666666666666666666667) + h2 * (he2 / PF_R(20.0)
               + h2 * (he4 / PF_R(336.0) + h2 * he6 / PF_R(12960.0))));
    u1 = pf_min(pf_max(u1, PF_R(0.0)), m0);
    return pf_vec3_make(m0, u1, pf_min(pf_max(u2, PF_R(0.0)), u1));
}

/* (w0, w1) of the segment [x0, x1) from its standardized knots. */
PF_DEF pf_vec2 pfi_segment_weights(pfi_gauss_knot ka, pfi_gauss_knot kb, pf_real x0, pf_real x1,
                                   pf_real mean, pf_real sigma)
{
    pf_real w = x1 - x0;
    pf_real m0, u1;
    if (!(w > PF_R(0.0))) return pf_vec2_make(PF_R(0.0), PF_R(0.0));
    if (w * PF_R(8.0) < sigma) {
        pf_vec3 n = pfi_narrow_moments(x0, x1, mean, sigma);
        return pf_vec2_make(n.x - n.y, n.y);
    }
    m0 = pfi_gauss_mass(ka, kb);
    u1 = ((mean - x0) * m0 + pf_max(sigma, PF_R(0.0)) * (ka.pdf - kb.pdf)) / w;
    u1 = pf_min(pf_max(u1, PF_R(0.0)), m0);
    return pf_vec2_make(m0 - u1, u1);
}

/* P(X < x), X ~ N(mean, sigma^2): the weight of a colour map's constant part below its first
   knot. sigma <= 0: the step 1{mean < x} (1/2 at mean = x). */
PF_DEF pf_real pf_gauss_cdf(pf_real x, pf_real mean, pf_real sigma)
{
    return pfi_normal_tails(pfi_standardize(x, mean, sigma)).x;
}

/* P(X >= edge) = E[step(edge, X)] (the GLSL step), X ~ N(mean, sigma^2): a step colour map
   filtered (a map that jumps from c0 to c1 at edge filters to c0 + (c1 - c0) * this), and the
   weight of a map's constant part above its last knot. Accurate in both tails. sigma <= 0:
   the step itself (1/2 at mean = edge). */
PF_DEF pf_real pf_gauss_step(pf_real edge, pf_real mean, pf_real sigma)
{
    return pfi_normal_tails(pfi_standardize(edge, mean, sigma)).y;
}

/* Weights (w0, w1) of one linear piece of a colour map: the piece from (x0, c0) to (x1, c1),
   restricted to [x0, x1), contributes w0 c0 + w1 c1 to E[C(X)] (closed form above: two erfc
   and two exp). Sum it over the pieces, plus c_first * pf_gauss_cdf(x_first, ...) and
   c_last * pf_gauss_step(x_last, ...) for the constant ends. x1 <= x0 (a jump) gives (0, 0).
   w0, w1 >= 0 and w0 + w1 = P(x0 <= X < x1). sigma <= 0: (1 - u, u) with u = (mean - x0)/
   (x1 - x0) when x0 < mean < x1, the halves of that at the ends, 0 outside. */
PF_DEF pf_vec2 pf_gauss_segment_weights(pf_real x0, pf_real x1, pf_real mean, pf_real sigma)
{
    return pfi_segment_weights(pfi_gauss_knot_at(x0, mean, sigma), pfi_gauss_knot_at(x1, mean, sigma),
                               x0, x1, mean, sigma);
}

/* E[smoothstep(e0, e1, X)], X ~ N(mean, sigma^2), smoothstep = 3u^2 - 2u^3 with
   u = saturate((X - e0)/(e1 - e0)) (the GLSL function). Two evaluations:
   - the ramp is wide against sigma (e1 - e0 >= sigma/3): closed form with the truncated
     moments M_k = integral_a^b t^k phi (M2 = M0 + a phi(a) - b phi(b),
     M3 = 2 M1 + a^2 phi(a) - b^2 phi(b)) plus P(X >= e1);
   - narrow (e1 - e0 < sigma/3), where that form cancels: integrating by parts,
     E = integral_0^1 6u(1-u) Q(t(u)) du, Q the upper tail, t linear over a window of width
     d = (e1 - e0)/sigma, and Q expanded about the window's centre tc: the kernel is
     symmetric, so only even terms remain,
       E = Q(tc) + phi(tc) (d^2/40 He1 + d^4/4480 He3 + d^6/967680 He5 + d^8/340623360 He7)(tc),
     He_k the Hermite polynomials (truncation < 1e-17 for d < 1/3).
   e1 <= e0: the step at e0. sigma <= 0: smoothstep(e0, e1, mean). Range [0, 1]. */
PF_DEF pf_real pf_gauss_smoothstep(pf_real e0, pf_real e1, pf_real mean, pf_real sigma)
{
    pf_real w = e1 - e0;
    pf_real sg = pf_max(sigma, PF_R(0.0));
    pf_real r;
    if (!(w > PF_R(0.0))) return pf_gauss_step(e0, mean, sigma);
    if (w * PF_R(3.0) < sg) {
        /* clamped like pfi_standardize: beyond |tc| = 40 everything is 0 or 1 */
        pf_real tc = pf_min(pf_max((PF_R(0.5) * (e0 + e1) - mean) / sg, PF_R(-40.0)), PF_R(40.0));
        pf_real d2 = pf_sq(w / sg), t2 = tc * tc;
        pf_real he1 = tc;
        pf_real he3 = tc * (t2 - PF_R(3.0));
        pf_real he5 = tc * (t2 * (t2 - PF_R(10.0)) + PF_R(15.0));
        pf_real he7 = tc * (t2 * (t2 * (t2 - PF_R(21.0)) + PF_R(105.0)) - PF_R(105.0));
        pf_real series = d2 * (he1 * PF_R(0.025) + d2 * (he3 * PF_R(2.232142857142857142857e-4)
                       + d2 * (he5 * PF_R(1.033399470899470899e-6) + d2 * he7 * PF_R(2.935791819e-9))));
        r = pfi_normal_tails(tc).y + pf_height_pdf(tc) * series;
    } else {
        pfi_gauss_knot ka = pfi_gauss_knot_at(e0, mean, sigma);
        pfi_gauss_knot kb = pfi_gauss_knot_at(e1, mean, sigma);
        pf_real m0 = pfi_gauss_mass(ka, kb);
        pf_real m1 = ka.pdf - kb.pdf;
        pf_real m2 = m0 + ka.t * ka.pdf - kb.t * kb.pdf;
        pf_real m3 = PF_R(2.0) * m1 + ka.t * ka.t * ka.pdf - kb.t * kb.t * kb.pdf;
        pf_real al = (mean - e0) / w, be = sg / w;
        /* 3u^2 - 2u^3 with u = al + be t, expanded in powers of t */
        pf_real c0 = al * al * (PF_R(3.0) - PF_R(2.0) * al);
        pf_real c1 = PF_R(6.0) * al * be * (PF_R(1.0) - al);
        pf_real c2 = PF_R(3.0) * be * be * (PF_R(1.0) - PF_R(2.0) * al);
        pf_real c3 = PF_R(-2.0) * be * be * be;
        pf_real inner = c0 * m0 + c1 * m1 + c2 * m2 + c3 * m3;
        r = kb.upper + pf_min(pf_max(inner, PF_R(0.0)), m0);
    }
    return pf_saturate(r);
}

/* ---------------------------------------------------------------- height transfer functions
   Heights h = g(f) made by a transfer function g applied to a Gaussian field f ~ N(mean,
   sigma^2) (Heitz et al. 2014 sec. 7). The height and slope statistics need four filtered
   moments, E[g], E[g^2] (eqs. 19-22) and E[g'], E[g'^2] (eqs. 27-28); for g piecewise linear
   through knots (x[k], g[k]), constant beyond the ends, each is a sum over pieces of closed
   forms like the colour weights. g is meant to be continuous: a jump (equal x) adds its value
   change but not its delta-function derivative. */
PF_STRUCT_BEGIN(pf_transfer_moments)
    pf_real g;    /* E[g(f)]      */
    pf_real g2;   /* E[g(f)^2]    */
    pf_real dg;   /* E[g'(f)]     */
    pf_real dg2;  /* E[g'(f)^2]   */
PF_STRUCT_END(pf_transfer_moments)

PF_DEF pf_transfer_moments pf_transfer_moments_make(pf_real g, pf_real g2, pf_real dg, pf_real dg2)
{
    pf_transfer_moments m;
    m.g = g;
    m.g2 = g2;
    m.dg = dg;
    m.dg2 = dg2;
    return m;
}

PF_DEF pf_transfer_moments pf_transfer_moments_add(pf_transfer_moments a, pf_transfer_moments b)
{
    return pf_transfer_moments_make(a.g + b.g, a.g2 + b.g2, a.dg + b.dg, a.dg2 + b.dg2);
}

/* A constant part of g, of value v, holding probability mass (the ends: mass =
   pf_gauss_cdf(x_first, ...) or pf_gauss_step(x_last, ...)): (v mass, v^2 mass, 0, 0). */
PF_DEF pf_transfer_moments pf_transfer_end_moments(pf_real value, pf_real mass)
{
    return pf_transfer_moments_make(value * mass, value * value * mass, PF_R(0.0), PF_R(0.0));
}

PF_DEF pf_transfer_moments pfi_transfer_segment(pfi_gauss_knot ka, pfi_gauss_knot kb, pf_real x0,
                                                pf_real g0, pf_real x1, pf_real g1, pf_real mean,
                                                pf_real sigma)
{
    pf_real w = x1 - x0, dgv = g1 - g0;
    pf_real sg = pf_max(sigma, PF_R(0.0));
    pf_real m0, u1, u2, per_w, off;
    pf_vec2 wt;
    if (!(w > PF_R(0.0))) return pf_transfer_moments_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    if (w * PF_R(8.0) < sg) {
        pf_vec3 n = pfi_narrow_moments(x0, x1, mean, sg);
        m0 = n.x;
        u1 = n.y;
        u2 = n.z;
    } else {
        wt = pfi_segment_weights(ka, kb, x0, x1, mean, sigma);
        m0 = wt.x + wt.y;
        u1 = wt.y; /* E[u 1{segment}] */
        /* E[u^2 1{segment}] = ((mean-x0)^2 M0 + 2 (mean-x0) sigma M1 + sigma^2 M2) / w^2,
           clamped to its range [0, U1] (u^2 <= u on the segment) */
        off = mean - x0;
        u2 = (off * off * m0 + PF_R(2.0) * off * sg * (ka.pdf - kb.pdf)
              + sg * sg * (m0 + ka.t * ka.pdf - kb.t * kb.pdf)) / (w * w);
        u2 = pf_min(pf_max(u2, PF_R(0.0)), u1);
    }
    per_w = m0 / w;
    /* E[g^2] >= 0 clamped: its three terms cancel where g crosses 0 on the segment, and
       rounding left -3.4e-21 (float) */
    return pf_transfer_moments_make(g0 * m0 + dgv * u1,
                                    pf_max(g0 * g0 * m0 + PF_R(2.0) * g0 * dgv * u1 + dgv * dgv * u2, PF_R(0.0)),
                                    dgv * per_w,
                                    dgv * dgv / w * per_w);
}

/* Moments contributed by the linear piece of g from (x0, g0) to (x1, g1) on [x0, x1), for
   f ~ N(mean, sigma^2). With u = (f - x0)/(x1 - x0): g = g0 + (g1 - g0) u, g' = (g1 - g0)/(x1 - x0),
   so E[g] = g0 M0 + (g1-g0) U1, E[g^2] = g0^2 M0 + 2 g0 (g1-g0) U1 + (g1-g0)^2 U2,
   E[g'] = g' M0, E[g'^2] = g'^2 M0 (eqs. 21-22, 27-28), U_k = E[u^k 1{segment}]. x1 <= x0
   gives zeros. Sum over the pieces and add pf_transfer_end_moments for the constant ends. */
PF_DEF pf_transfer_moments pf_transfer_segment_moments(pf_real x0, pf_real g0, pf_real x1, pf_real g1,
                                                       pf_real mean, pf_real sigma)
{
    return pfi_transfer_segment(pfi_gauss_knot_at(x0, mean, sigma), pfi_gauss_knot_at(x1, mean, sigma),
                                x0, g0, x1, g1, mean, sigma);
}

/* Height statistics of h = g(f): mean E[g], deviation sqrt(E[g^2] - E[g]^2) (Heitz et al. 2014
   eqs. 21-22 and the text after them), the Gaussian N(mean, dev^2) that stands for p_h. */
PF_DEF pf_height_dist pf_transfer_height(pf_transfer_moments m)
{
    return pf_height_dist_make(m.g, PF_SQRT(pf_max(m.g2 - m.g * m.g, PF_R(0.0))));
}

/* Slope statistics of h = g(f) from the moments of g' and the five linearly filtered slope
   moments of f (E[f_x], E[f_y], E[f_x^2], E[f_y^2], E[f_x f_y]): f and its slopes are
   uncorrelated for a Gaussian process, so (eqs. 23-26)
       E[h_x] = E[g'] E[f_x],  E[h_x^2] = E[g'^2] E[f_x^2],  E[h_x h_y] = E[g'^2] E[f_x f_y],
   and the central statistics follow as in pf_slope_stats_from_moments (pf_smith.h). */
PF_DEF pf_slope_stats pf_transfer_slope_stats(pf_transfer_moments m, pf_real ex, pf_real ey,
                                              pf_real exx, pf_real eyy, pf_real exy)
{
    return pf_slope_stats_from_moments(m.dg * ex, m.dg * ey, m.dg2 * exx, m.dg2 * eyy, m.dg2 * exy);
}

/* ---------------------------------------------------------------- CPU only: arrays
   These walk caller-owned arrays (pointers), so they are not part of the shader subset; a
   shader loops over pf_gauss_segment_weights / pf_transfer_segment_moments instead. No
   allocation, no I/O. Knots: x[0..n-1] non-decreasing; values c[k * channels + ch].
   Linkage PF_CPU_DEF (host code, never __device__); the rules are pf_core.h's "CPU only:
   sizes and errors": every argument is checked before anything is read or written; PF_OK on
   success, PF_ERR_ARG (-1) for a NULL pointer, a size below its minimum or a range that is
   empty, reversed or not finite, PF_ERR_SIZE (-2) for a size above its limit, and nothing
   written on an error. Offsets are computed in long long. */
#ifndef PF_GLSL

/* The checks shared by the array functions: knots n >= 1 and channels >= 1 (PF_ERR_ARG below),
   n * channels <= PF_MAX_REALS (the values array; PF_ERR_SIZE above). */
PF_CPU_DEF int pfi_colormap_check(int n, int channels)
{
    if (n < 1 || channels < 1) return PF_ERR_ARG;
    if (pf_size_mul(n, channels) < 0) return PF_ERR_SIZE;
    return PF_OK;
}

/* E[C(X)] for the piecewise-linear colour map (x, c) with n >= 1 knots and `channels` >= 1
   values per knot, X ~ N(mean, sigma^2): out[0..channels-1]. One erfc and one exp per knot
   (each knot's tails are shared by its two pieces).
   Buffers: x holds n reals, c holds n * channels, out receives channels.
   Returns PF_OK; PF_ERR_ARG (nothing written) for x, c or out NULL, n < 1 or channels < 1;
   PF_ERR_SIZE (nothing written) for n * channels > PF_MAX_REALS.
   sigma <= 0 or NaN: the unfiltered map at mean (at a jump, the mean of its two sides).
   mean NaN: every knot reads as standing at the mean (as in pf_gauss_cdf and
   pf_gauss_segment_weights, which a shader loop would call), so out = (c[0] + c[n-1]) / 2 per
   channel, for every sigma: finite, and meaningless; check means upstream. */
PF_CPU_DEF int pf_colormap_filter(const pf_real *x, const pf_real *c, int n, int channels,
                                  pf_real mean, pf_real sigma, pf_real *out)
{
    pfi_gauss_knot ka, kb;
    pf_real below, above;
    const pf_real *ck;
    int k, ch, rc;
    if (!x || !c || !out) return PF_ERR_ARG;
    rc = pfi_colormap_check(n, channels);
    if (rc != PF_OK) return rc;
    ka = pfi_gauss_knot_at(x[0], mean, sigma);
    below = ka.lower;
    for (ch = 0; ch < channels; ch++) out[ch] = c[ch] * below;
    for (k = 0; k + 1 < n; k++) {
        pf_vec2 w;
        kb = pfi_gauss_knot_at(x[k + 1], mean, sigma);
        w = pfi_segment_weights(ka, kb, x[k], x[k + 1], mean, sigma);
        ck = c + (long long)k * channels; /* knot k; knot k + 1 is ck + channels */
        for (ch = 0; ch < channels; ch++) out[ch] += w.x * ck[ch] + w.y * ck[(long long)channels + ch];
        ka = kb;
    }
    above = ka.upper;
    ck = c + (long long)(n - 1) * channels;
    for (ch = 0; ch < channels; ch++) out[ch] += ck[ch] * above;
    return PF_OK;
}

/* Height-correlated colour, Heitz et al. 2014 eq. 13: C_h = Vbar <C, D_h>, with D_h our
   Gaussian fit for Lambda_o + Lambda_i in heights (mean_h, sigma_h), perturbed by noise
   (mu_r, sigma_r; 0, 0 for none), and Vbar = pf_height_mean_visibility (eq. 12). out gets
   `channels` values. (Without the Vbar factor: pf_colormap_filter with pf_height_colour_dist.)
   Buffers, sizes and return codes as pf_colormap_filter (nothing written on an error).
   NaN Lambdas read as 0; a NaN in mean_h, sigma_h or mu_r makes the filtering mean NaN:
   out = Vbar (c[0] + c[n-1]) / 2 as in pf_colormap_filter. */
PF_CPU_DEF int pf_height_colormap_filter(const pf_real *x, const pf_real *c, int n, int channels,
                                         pf_real lambda_o, pf_real lambda_i, pf_real mean_h,
                                         pf_real sigma_h, pf_real mu_r, pf_real sigma_r, pf_real *out)
{
    pf_height_dist d = pf_height_colour_dist(lambda_o, lambda_i, mean_h, sigma_h, mu_r, sigma_r);
    pf_real v = pf_height_mean_visibility(lambda_o, lambda_i);
    int ch, rc = pf_colormap_filter(x, c, n, channels, d.mean, d.dev, out);
    if (rc != PF_OK) return rc;
    for (ch = 0; ch < channels; ch++) out[ch] *= v;
    return PF_OK;
}

/* The four moments of the piecewise-linear transfer function (x, g), n >= 1 knots (x and g
   hold n reals each), for f ~ N(mean, sigma^2). It returns the moments by value, so bad
   arguments - x or g NULL, n < 1 - give zeros (0, 0, 0, 0) and read nothing (a valid map can
   give zeros too, g = 0 everywhere: check the arguments if the difference matters). Every
   n >= 1 that fits an int is within PF_MAX_REALS. sigma <= 0 or NaN: no filtering. mean NaN:
   every knot at the mean (as pf_colormap_filter): g = (g[0] + g[n-1]) / 2,
   g2 = (g[0]^2 + g[n-1]^2) / 2, dg = dg2 = 0. */
PF_CPU_DEF pf_transfer_moments pf_transfer_moments_filter(const pf_real *x, const pf_real *g, int n,
                                                          pf_real mean, pf_real sigma)
{
    pf_transfer_moments m = pf_transfer_moments_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    pfi_gauss_knot ka, kb;
    int k;
    if (!x || !g || n < 1) return m;
    ka = pfi_gauss_knot_at(x[0], mean, sigma);
    m = pf_transfer_end_moments(g[0], ka.lower);
    for (k = 0; k + 1 < n; k++) {
        kb = pfi_gauss_knot_at(x[k + 1], mean, sigma);
        m = pf_transfer_moments_add(m, pfi_transfer_segment(ka, kb, x[k], g[k], x[k + 1], g[k + 1], mean, sigma));
        ka = kb;
    }
    return pf_transfer_moments_add(m, pf_transfer_end_moments(g[n - 1], ka.upper));
}

/* The pre-convolved colour map of Heitz et al. 2014 sec. 4.2 (eq. 9): a 2D table of E[C(X)]
   over mean (n_mean samples, uniform on [mean_min, mean_max]) and sigma (n_sigma samples,
   uniform on [0, sigma_max]), `channels` values per entry, in a caller-owned buffer of
   pf_colormap_table_size(...) reals laid out as data[((j * n_mean) + i) * channels + ch]
   (i: mean, j: sigma; row-major, ready for a 2D texture upload). On the GPU the lookup is a
   bilinear texture fetch; pf_colormap_table_lookup is the same bilinear interpolation on the
   CPU (the reference for its error). Choose [mean_min, mean_max] to cover the knots plus a few
   sigma_max: lookups clamp to the table's range.
   Limits (checked by the builder and again by every lookup): 2 <= n_mean, n_sigma <=
   PF_MAX_SIDE (2^24), channels >= 1, n_mean * n_sigma * channels <= PF_MAX_REALS;
   mean_min < mean_max and 0 < sigma_max, every bound, the widths mean_max - mean_min and
   sigma_max, and the sample steps width / (n - 1) finite and > 0. The size fields stay int:
   every side is at most 2^24 and channels is an int argument; only offsets need more than 31
   bits (up to PF_MAX_REALS), and they are computed in long long, never stored. */
typedef struct pf_colormap_table {
    pf_real *data;
    int n_mean, n_sigma, channels;
    pf_real mean_min, mean_max, sigma_max;
} pf_colormap_table;

/* Reals needed by a table: n_mean * n_sigma * channels as a long long (65537 x 65537 x 1 is
   4295098369), or 0 for any size the builder rejects: n_mean or n_sigma < 2 or > PF_MAX_SIDE,
   channels < 1, or a product above PF_MAX_REALS. */
PF_CPU_DEF long long pf_colormap_table_size(int n_mean, int n_sigma, int channels)
{
    long long total;
    if (n_mean < 2 || n_sigma < 2 || channels < 1) return 0;
    if (!pf_size_side_ok(n_mean) || !pf_size_side_ok(n_sigma)) return 0;
    total = pf_size_mul3(n_mean, n_sigma, channels);
    return total < 0 ? 0 : total;
}

/* 1 when x is finite (not NaN, not +-inf), by comparison only (no isfinite: C99 and C++11
   spell it differently, and MCU libms may lack it). -ffinite-math-only (part of -ffast-math)
   lets the compiler assume it is 1. */
PF_CPU_DEF int pfi_height_finite(pf_real x) { return x >= -PF_REAL_MAX && x <= PF_REAL_MAX; }

/* Every check of a table's description (see pf_colormap_table): PF_OK, PF_ERR_ARG or
   PF_ERR_SIZE. */
PF_CPU_DEF int pfi_colormap_table_check(int n_mean, int n_sigma, int channels, pf_real mean_min,
                                        pf_real mean_max, pf_real sigma_max)
{
    pf_real wm = mean_max - mean_min;
    if (n_mean < 2 || n_sigma < 2 || channels < 1) return PF_ERR_ARG;
    if (pf_colormap_table_size(n_mean, n_sigma, channels) == 0) return PF_ERR_SIZE;
    if (!pfi_height_finite(mean_min) || !pfi_height_finite(mean_max) || !pfi_height_finite(wm) || !(wm > PF_R(0.0)) ||
        !(wm / (pf_real)(n_mean - 1) > PF_R(0.0)))
        return PF_ERR_ARG;
    if (!pfi_height_finite(sigma_max) || !(sigma_max / (pf_real)(n_sigma - 1) > PF_R(0.0))) return PF_ERR_ARG;
    return PF_OK;
}

/* Fills buffer (pf_colormap_table_size(n_mean, n_sigma, channels) reals) with the filtered
   map (x, c), n knots, and describes it in *t. One pf_colormap_filter per entry; the sample
   means are mean_min + (mean_max - mean_min) (i / (n_mean - 1)), which cannot overflow.
   Returns PF_OK; PF_ERR_ARG (nothing written, *t untouched) for t, buffer, x or c NULL,
   n < 1, n_mean or n_sigma < 2, channels < 1, or a bad range (see pf_colormap_table:
   mean_min = -inf, sigma_max = inf, NaN bounds, [-3e38, 3e38] in float whose width
   overflows, mean_max <= mean_min, sigma_max <= 0); PF_ERR_SIZE (nothing written) for a side
   above PF_MAX_SIDE, a table above PF_MAX_REALS reals, or n * channels > PF_MAX_REALS. */
PF_CPU_DEF int pf_colormap_table_build(pf_colormap_table *t, pf_real *buffer, int n_mean, int n_sigma,
                                       pf_real mean_min, pf_real mean_max, pf_real sigma_max,
                                       const pf_real *x, const pf_real *c, int n, int channels)
{
    int i, j, rc;
    pf_real wm = mean_max - mean_min;
    if (!t || !buffer || !x || !c) return PF_ERR_ARG;
    rc = pfi_colormap_table_check(n_mean, n_sigma, channels, mean_min, mean_max, sigma_max);
    if (rc == PF_OK) rc = pfi_colormap_check(n, channels);
    if (rc != PF_OK) return rc;
    t->data = buffer;
    t->n_mean = n_mean;
    t->n_sigma = n_sigma;
    t->channels = channels;
    t->mean_min = mean_min;
    t->mean_max = mean_max;
    t->sigma_max = sigma_max;
    for (j = 0; j < n_sigma; j++) {
        pf_real sg = sigma_max * ((pf_real)j / (pf_real)(n_sigma - 1));
        pf_real *row = buffer + (long long)j * n_mean * channels;
        for (i = 0; i < n_mean; i++) {
            pf_real mu = mean_min + wm * ((pf_real)i / (pf_real)(n_mean - 1));
            pf_colormap_filter(x, c, n, channels, mu, sg, row + (long long)i * channels);
        }
    }
    return PF_OK;
}

/* Bilinear lookup of a built table at (mean, sigma), clamped to the table's range (NaN reads
   as the range's low end); writes t->channels values to out. The four entries read are inside
   the table for every mean and sigma (indices clamped before any conversion, offsets in
   long long). Returns PF_OK; PF_ERR_ARG (nothing written) for t, t->data or out NULL or a
   description that pf_colormap_table_build would reject as PF_ERR_ARG; PF_ERR_SIZE for one it
   would reject as PF_ERR_SIZE (a table it could not have built). */
PF_CPU_DEF int pf_colormap_table_lookup(const pf_colormap_table *t, pf_real mean, pf_real sigma, pf_real *out)
{
    pf_real u, v, fu, fv;
    long long i, j, stride;
    int ch, cs, rc;
    const pf_real *p00, *p10, *p01, *p11;
    if (!t || !t->data || !out) return PF_ERR_ARG;
    rc = pfi_colormap_table_check(t->n_mean, t->n_sigma, t->channels, t->mean_min, t->mean_max, t->sigma_max);
    if (rc != PF_OK) return rc;
    cs = t->channels;
    u = (mean - t->mean_min) / (t->mean_max - t->mean_min) * (pf_real)(t->n_mean - 1);
    v = sigma / t->sigma_max * (pf_real)(t->n_sigma - 1);
    u = pf_min(pf_max(u, PF_R(0.0)), (pf_real)(t->n_mean - 1)); /* NaN -> 0 */
    v = pf_min(pf_max(v, PF_R(0.0)), (pf_real)(t->n_sigma - 1));
    i = pf_floor_index(u, 0, t->n_mean - 2);
    j = pf_floor_index(v, 0, t->n_sigma - 2);
    fu = u - (pf_real)i;
    fv = v - (pf_real)j;
    stride = (long long)t->n_mean * cs;
    p00 = t->data + j * stride + i * cs;
    p10 = p00 + cs;
    p01 = p00 + stride;
    p11 = p01 + cs;
    for (ch = 0; ch < cs; ch++) {
        pf_real lo = p00[ch] + fu * (p10[ch] - p00[ch]);
        pf_real hi = p01[ch] + fu * (p11[ch] - p01[ch]);
        out[ch] = lo + fv * (hi - lo);
    }
    return PF_OK;
}

#endif /* !PF_GLSL */

#endif /* PF_HEIGHT_H */

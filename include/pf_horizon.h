/* pf_horizon.h - horizon maps pre-filtered as horizon distribution functions (HDF): the
   visibility of a height field's texels from its own distant bumps, at any footprint size.

   A horizon map (Max 1988) stores, per texel x and azimuth phi, the elevation angle Theta_x(phi)
   of the horizon: the steepest the height field rises as seen from x toward phi. A point sees
   a direction of elevation e (e = 90 deg - zenith angle) and azimuth phi iff
       V_x(e, phi) = H(e - Theta_x(phi))                    (Bruneton & Neyret 2012 eq. 24)
   H is not linear, so Theta cannot be mip-mapped. Written as V_x = integral H(e - t) p_x(t) dt
   with the per-texel horizon distribution p_x = delta(t - Theta_x) (eq. 25), visibility is
   linear in p_x, and the footprint's visible fraction is the HDF p_A = mean of p_x:
       V_A(e, phi) = integral_{-pi/2}^{e} p_A(t, phi) dt     (eq. 26)
   Everything stored here is a linear moment of p_x, mip-mapped by pf_map.h's pyramid:
     PF_HORIZON_MOMENTS  per azimuth E[T], E[T^2] (T = Theta, radians; Fournier 1992, Tan et al.
                         2008) and E[S T], S the texel's slope along the azimuth (ours: the
                         correlation of horizon and facet that the masking term below needs);
     PF_HORIZON_LEGENDRE per azimuth the k coefficients a_j(Theta) of the step
                         H(x - sin Theta) in normalized Legendre polynomials of x = cos(zenith)
                         (Nowrouzezahrai & Snyder 2009; eqs. 29-30);
     PF_HORIZON_ANGLES   Theta itself (the plain horizon map; NOT linearly filterable).

   From filtered moments a shader evaluates (all pure functions, GLSL-safe):
     pf_horizon_visibility_ramp      Fournier's ramp, clamp((e - mu + sigma)/(2 sigma), 0, 1)
     pf_horizon_visibility_gauss     Tan et al.: p_A Gaussian, V_A = Phi((e - mu)/sigma) (erfc)
     pf_horizon_visibility_legendre  eq. 30: sum_j c_j P^_j(cos zenith), clamped to [0, 1]
   the bidirectional fraction of visible texels that are also lit, V_A(l, v) (eq. 23):
     pf_horizon_bidir_product        Fournier: texels visible and lit = V(l) V(v), so V_A(l, v) = V(l)
     pf_horizon_bidir_tan            eq. 28, alpha = (1 + l.v)/2 (hotspot and fully-lit exact)
     pf_horizon_bidir_ashikhmin      Ashikhmin et al. 2000: beta = exp(-(angle(l, v)/width)^2)
   and the masking term of a microfacet BRDF (see COMBINING WITH SMITH):
     pf_horizon_visible_area         the footprint's visible projected area over its mean
                                     projected area, from E[T], E[T^2], E[S T] (bivariate Gaussian)
     pf_horizon_masking              the same ratio with a skewed (Gram-Charlier) HDF times
                                     Smith's pf_beckmann_g1: the masking G1.
     pf_horizon_lod_weight           the horizon term's weight by mip level (1 small, 0 large)
     pf_horizon_masking_lod          pf_horizon_masking faded to Smith by that weight
   and the Lambertian diffuse of a footprint (see DIFFUSE):
     pf_horizon_visibility_given_slope  V toward w of the facets of one slope (conditional HDF)
     pf_horizon_diffuse_directional  LEADR's slope grid with that visibility per facet, eq. 28
     pf_horizon_diffuse_lod          that faded to pf_gg_diffuse_directional by mip level
   and the specular of the facets that reflect (see SPECULAR):
     pf_horizon_specular_visibility  V toward wo and wi of the facets of the half vector's slope
     pf_horizon_leadr_specular, _lod LEADR's eq. 17 with that visibility instead of Smith's G
     pf_horizon_vmf_specular, _lod   pf_vmf.h's lobes with that visibility instead of Smith's G
     pf_horizon_texel_stats          slope statistics less the base lobe's variance

   COMBINING WITH SMITH (measured: docs/horizon.md, bench/bench_horizon.c --masking).
   The bench's masking reference is the visible fraction of the footprint's front-facing
   projected micro-area, sum V_t a_t+ / sum a_t+, a_t = w.z - s_t . w_xy. Exactly,
       G1 = [sum V_t a_t / sum a_t] * [sum a_t / sum a_t+]
   (a visible texel faces the view, so V a+ = V a). The second factor is Smith's
   1/(1 + Lambda) computed from the footprint's slope histogram (pf_beckmann_g1 with its
   Gaussian fit); the first, the visible projected area over the mean projected area, is 1 for a
   footprint large enough that every viewing ray through it ends inside it (Smith's premise) and
   is what the horizon knows beyond that: occlusion by bumps outside the footprint. So the
   horizon term MULTIPLIES Smith as this area ratio. Neither obvious form is right: replacing
   G1 by the plain visible fraction V_A counts every texel alike (visible texels face the
   viewer and weigh more in the projected area), and V_A * G1 counts the footprint's own
   occlusion twice. pf_horizon_visible_area estimates the ratio with (T, S) jointly Gaussian:
       E[V a] = c Phi(z) - sum_xy (E[S] Phi(z) - Cov(S, T)/sigma_T phi(z)),   z = (e - mu)/sigma_T
   with c = w.z and sum_xy the factor sin(zenith) of the slope term. pf_horizon_masking skews
   that HDF (pfi_horizon_area): a horizon is a maximum over the march, so a footprint's T is
   right-skewed (mean skewness 0.74-0.99 over 4 x 4 footprints of fBm maps), and the Gaussian
   of the same mean and variance over-masks views just above E[T] and under-masks far above
   it. The Gram-Charlier series of skewness g = sigma_T/E[T] (1 - rho^2) (capped at 1) keeps
   the closed form; masking at 16 texels on the seven user-map proxies 0.032-0.051 ->
   0.031-0.047 (every 4 x 4 footprint, full reference), the corpus kinds equal or lower but
   tiles 0.0109 -> 0.0118 (docs/horizon.md, "User maps").

   FADING BY LEVEL OF DETAIL (pf_horizon_lod_weight, pf_horizon_masking_lod; measured:
   docs/horizon.md). The area ratio R is what the horizon adds to Smith, and it matters only
   where viewing rays through the footprint end OUTSIDE it: texels within an occlusion length
   l (the horizontal distance from a texel to what hides it, l ~ height deviation / tan e) of
   the footprint's edge. That share of the footprint falls as l / n with the footprint's side
   n, and with it the true 1 - R (over a large footprint every ray through it ends inside it:
   the visible projected area equals the mean projected area). The bivariate-Gaussian
   estimate of R does not share that limit: on the bench's seven surfaces (bench_horizon
   --masking) its mean agrees with the true ratio's to 0.009 at 16-texel footprints (where
   1 - R reaches 4.4%) but stays 1.0-2.4% low at 4096 texels, where the true mean is
   0.991-1.003 (the footprint's HDF is a mixture of many local ones, and the texels that face
   away from the view, always hidden, tie S to T non-linearly; a joint Gaussian cannot keep
   E[(1 - V) a] = 0). So the horizon term helps while the footprint is small against l and
   the features, and from a few feature sizes on its bias is larger than its signal. pf_horizon_masking_lod blends R
   toward 1 by a weight that is 1 up to lod_full and 0 from lod_smith on, linear in lod.
   Dividing R by the same estimate at the coarsest level (where the truth is 1) removes most
   of the bias at 4096 texels but worsens 16-texel footprints on five of the seven kinds
   (gaussian_fine to 0.054: measured), so the fade is the evaluator.

   DIFFUSE (pf_horizon_visibility_given_slope, pf_horizon_diffuse_directional, _lod; measured:
   docs/horizon.md). LEADR's diffuse (eq. 21, pf_gg_diffuse_directional) integrates the
   Lambertian cosine over the footprint's Gaussian slopes on a grid and multiplies by Smith's
   1/(1 + Lambda_o + Lambda_i). Multiplying that by the horizon's area ratios toward the view
   and the light (as the masking does) misses at 16-texel footprints on three of the bench's
   seven kinds, and it still does with the ratios counted exactly on the horizon map: the
   hidden texels are not a fair sample of the footprint's facets (those turned away from the
   view or the light are hidden more often), so one common factor shades the grid's facets
   wrongly. pf_horizon_diffuse_directional conditions instead: each grid facet of slope s gets
   the HDF of the texels that share that slope, T | S = s under the joint Gaussian of (T, S)
   whose covariance the stored E[S T] gives, hence its own V_o(s) and V_i(s); the two are
   joined by Tan et al.'s eq. 28 (pf_horizon_bidir_tan: visible and lit = V_o B(V_i, V_o), V_o
   at the hotspot), and the sum is normalized by the mean plane's projected area A_o (LEADR
   eqs. 2-3). No Smith factor is left: the march starts one texel from the node, so the
   horizon holds the footprint's own occluders as well as its neighbours'. At large
   footprints the same bias as the masking's appears (the conditional Gaussians of a wide
   mixture), so pf_horizon_diffuse_lod fades it to pf_gg_diffuse_directional with the same
   weight.

   SPECULAR (pf_horizon_specular_visibility, pf_horizon_leadr_specular, pf_horizon_vmf_specular,
   _lod; measured: docs/horizon.md). A narrow base lobe reflects wi into wo only on the facets
   whose slope is the half vector's, s_h = (-h.x/h.z, -h.y/h.z). Smith's G (LEADR eq. 13)
   takes their visibility from the footprint's own slopes; below 16-texel footprints the
   shadows and masking are cast by bumps outside the footprint, which it cannot see. The
   diffuse's conditioning does: V_o(s_h) and V_i(s_h) from the HDF of the texels whose facets
   reflect, T | S + B = s_h (S the texel's slope, B the base lobe's: a facet of slope s_h lies
   in a texel within the base lobe's deviation of it), joined by Tan et al.'s eq. 28, replace
   G in eq. 17:
       I = F D(h) V_o B(V_i, V_o) / (4 A_o).
   For the vMF lobes the same V_h multiplies the sum: every lobe's reflecting facets have the
   slope s_h and the HDF conditions on the slope alone, so the per-lobe visibilities are equal.
   The conditioning uses the slope-moment texel's statistics (the texels' own slopes), not the
   lobes'. Faded to the unshadowed method by mip level as the masking (the same bias of a
   wide mixture's conditional Gaussians at large footprints). With B in the conditioning the
   method keeps its float32 error with the pyramids stored in 16 bits (conditioned on S alone,
   one texel's rounded Var(S) set the regression: see pf_horizon_specular_visibility).
   Two corrections of the linear conditioning, measured on Gaussian fields against the
   reflecting texels' own stored horizons (tests/test_horizon.c, grazing brute force): the
   stored tan Theta = max(S, march) makes E[T | S] convex in S, so the regression line lies
   above it near the reflecting slopes (on a field of correlation 4 texels by 0.02-0.04 rad,
   about beta^2 sigma_S): the conditional mean is lowered by beta Cov(S, T)/sqrt(Var(S) + b)
   (= beta^2 sqrt(Var(S) + b)); and the reflecting texels' horizons spread 0.53-0.75 times the
   regression's residual deviation (both fields, views 75-85 degrees): the deviation is taken
   times 0.7. Together: grazing V_h error 0.416/0.436/0.781 -> 0.261/0.402/0.548 at 75/80/85
   degrees on correlation 4, 0.047/0.275/0.257 -> 0.034/0.205/0.199 on correlation 12; both
   cost no shader op over the plain conditioning (the rsqrt's operand is shared, the 0.7 is in
   the logistic's constants, the signs are folded).

   CONVENTIONS
     Azimuths: n equally spaced, phi_i = 2 pi i / n, i = 0 .. n - 1, measured from the +x axis
     (columns) toward +y (rows), the frame of pf_map.h's height maps; azimuth phi is the
     direction toward the viewer or light, w = (sin z cos phi, sin z sin phi, cos z).
     Elevations in radians, in (-pi/2, pi/2); a horizon below the tangent plane is negative
     (peaks), not clamped to 0: the Gaussian fit then sees the whole distribution.
     Buffers: texel (i, j) of a map is (j w + i) C .. + C - 1, C = pf_horizon_channels; inside
     a texel, azimuth a's channels are a C_a .. a C_a + C_a - 1 (C_a = 1, 3 or k).
     Out-of-domain inputs of the evaluators: a negative variance is taken as 0, a NaN moment
     gives visibility 0 (not visible), V_A(v) = 0 in the bidirectional forms gives V_A(l).

   THE CPU MARCH (pf_horizon_map). For texel (i, j) and azimuth phi the ray from its node is
   sampled at horizontal distances d = 1, 2, ..., max_steps texels, heights bilinear between
   nodes (PF_BORDER_WRAP: periodic; PF_BORDER_CLAMP: the nearest edge node beyond the map):
       tan Theta = max(S, max_d (h(d) - h(0)) / (d spacing)),
   S the texel's own slope along the azimuth (the central differences of the slope moments,
   pf_map_slope_stencil): a direction below the texel's facet (m.w <= 0, i.e. tan e <= S) is
   hidden by the facet itself whatever the march finds. Without S, on maps whose slopes
   decorrelate within a texel or two (fBm of spectrum 1/f^2 to 1/f^2.4) the one-sided rise to
   the next node is often below the facet's slope, so back-facing texels counted as visible and
   the visible area's identity V a+ = V a (COMBINING WITH SMITH) broke: masking at 16 texels
   0.052-0.058 against the full reference on such maps, 0.045-0.050 with S (docs/horizon.md,
   "User maps"). Along an axis the march is exact for the bilinear surface (between nodes
   (h(d) - h0)/d is monotonic); along other azimuths a peak between samples can be missed by up
   to a texel's curvature. The march stops early once no height of the map could raise the
   maximum.
   max_steps bounds the distance: occluders further away are ignored (choose it so that the
   map's height range over max_steps spacings is below tan of the lowest elevation of interest).

   USAGE
     int C = pf_horizon_channels(PF_HORIZON_MOMENTS, 8, 0);          -- 24 channels per texel
     long long nt = pf_mip_texel_count(w, h);
     pf_real *pyr = <nt * C pf_reals from the caller>;
     if (pf_horizon_pyramid(heights, w, h, spacing, 8, 64, PF_BORDER_WRAP,
                            PF_HORIZON_MOMENTS, 0, pyr) != PF_OK) ...
     -- shader: fetch the two azimuths around the view's and the slope moments
     pf_horizon_azimuth az = pf_horizon_azimuth_of(wo, 8);
     pf_hdf_moments m = pf_hdf_moments_lerp(m_az0, m_az1, az.f);
     pf_real g1 = pf_horizon_masking(wo, m, slope_stats);

   FUNCTIONS (shader subset)
     pf_hdf_moments_make, _lerp; pf_horizon_azimuth_of; pf_horizon_elevation;
     pf_horizon_visibility_ramp, _gauss, _legendre; pf_horizon_legendre_basis,
     pf_horizon_legendre_coeff; pf_hdf_legendre_make, _coeff, _lerp;
     pf_horizon_bidir_product, _tan, _ashikhmin; pf_horizon_visible_area, pf_horizon_masking,
     pf_horizon_lod_weight, pf_horizon_masking_lod; pf_horizon_visibility_given_slope,
     pf_horizon_diffuse_directional, pf_horizon_diffuse_lod; pf_horizon_specular_visibility,
     pf_horizon_texel_stats, pf_horizon_leadr_specular, _lod, pf_horizon_vmf_specular, _lod
   FUNCTIONS (CPU only, PF_CPU_DEF; compiled out under PF_GLSL)
     pf_horizon_channels, pf_horizon_map, pf_horizon_pyramid

   ERRORS (CPU; pf_core.h "sizes and errors"): PF_ERR_ARG for a NULL buffer, w, h < 1,
   n_azimuths < 1, max_steps < 1, a spacing that is not finite and positive, an unknown border or
   kind, k outside 1 .. PF_HORIZON_LEGENDRE_MAX for PF_HORIZON_LEGENDRE, and a non-finite height
   (NaN or infinite: the whole map is checked before anything is written); PF_ERR_SIZE for a side
   above PF_MAX_SIDE, n_azimuths or max_steps above PF_MAX_SIDE, or an output above PF_MAX_REALS.
   On an error nothing is written.

   ACCURACY AND COST (measured; docs/horizon.md has the tables and the commands)
     Masking G1 against the brute-force microsurface reference (tests/reference/pf_microsurface.h, seven
     kinds, views 0-75 deg pooled, relative L2), 16-texel footprints: pf_horizon_masking 0.012-
     0.040 with n = 32 azimuths, 0.023-0.067 with n = 16, against 0.081-0.195 for Smith alone;
     256 texels: 0.024-0.037 (n = 16) against 0.031-0.111. 4096 texels: 0.018-0.037, no better
     than Smith (0.012-0.036). pf_horizon_masking_lod (n = 32, lod 2 -> 6; bench/microsurface.c):
     0.012-0.037 at 16 texels (full reference), Smith's own 0.007-0.032 at 4096 texels
     (in-footprint reference). (These masking figures are the Gaussian HDF's; the skewed one
     changes them by -0.0014 to +0.0009 at 16 texels, every footprint: docs/horizon.md.)
     Diffuse at 16 texels, full reference: pf_horizon_diffuse_lod 0.020-0.078 on the seven
     kinds against 0.173-0.255 for LEADR's pf_gg_diffuse_directional; at 4096 texels LEADR's
     own numbers. Evaluators against long double: Gaussian HDF 2.1e-6
     abs (float), visible area 3.5e-7 abs (float), visibility given slope 3.6e-7 abs (float),
     the diffuse (9 x 9 Gauss-Hermite) within 0.8% of a 2D quadrature of its integral. Cost:
     pf_horizon_visible_area ~5x pf_beckmann_g1 in instructions (atan2, erfc, exp);
     pf_horizon_diffuse_directional ~3500 instructions with the 3 x 3 grid (18 pf_erfc_fast)
     against ~800 for pf_gg_diffuse_directional (callgrind, float, grid setup included); the CPU march
     ~0.5 us per texel and azimuth at max_steps = 64 (512^2, n = 16: 2.1 s on one core); the
     highest texels always march all max_steps. Storage: 3 n pf_reals per texel (n = 32: 96).
     Specular, 1-16 texels, full reference, views 0-75 deg, the seven kinds pooled (n = 32):
     pf_horizon_leadr_specular 0.148 (per kind 0.084-0.211), pf_horizon_vmf_specular with 16
     lobes 0.121 (0.063-0.157), against 0.517 and 0.499 with Smith's G. With the pyramids in
     half or unorm16 (pf_encode.h), at most 1.024x the float32 error (every kind and footprint,
     both references). (Those bench figures predate SPECULAR's convexity term and 0.7
     deviation; with them, gaussian_fine: 0.214 and 0.153, docs/horizon.md.) Against the
     long-double formula: the per-direction visibility 1.1e-3 abs, V_h 4.1e-4 abs, radiance
     4.1e-4 of the unshadowed lobe (float and double: the arcsine and CDF approximations).
     GPU: pf_horizon_leadr_specular 172 SPIR-V ops (pf_leadr_specular 116: 1.48x),
     pf_horizon_vmf_specular 147 (pf_vmf_sum_specular 94, plus 142 per pf_vmf_sum_add lobe in
     both: 1.02x with 16 lobes).

   SOURCES
     Bruneton & Neyret 2012 sec. 4, eqs. 23-30, surveying: Max 1988 (horizon maps); Fournier
     1992 (HDF mean and deviation, the ramp, the product); Tan, Lin, Quan, Guo & Shum 2008
     (Gaussian HDF, eq. 28); Ashikhmin, Premoze & Shirley 2000 (the beta form);
     Nowrouzezahrai & Snyder 2009 (Legendre expansion, eqs. 29-30). Cramer 1946 sec. 17.6 and
     Kendall & Stuart vol. 1 sec. 6.17 (the Gram-Charlier series of the masking's HDF). Smith
     1967 and Dupuy et al. 2013 eqs. 1, 13 for the masking decomposition; Dupuy et al. 2013 (LEADR) eqs. 2-3 and 21
     for the diffuse's slope grid and normalization. The lod fade and the slope-conditioned
     HDF are ours (measured in bench/microsurface.c), as is the masking HDF's skewness from the
     stored moments (bench/map_proxies.c --masking-parts). */
#ifndef PF_HORIZON_H
#define PF_HORIZON_H

#ifndef PF_GLSL
#  include "pf_beckmann.h"
#  include "pf_gaussgrid.h"
#  include "pf_vmf.h"
#  include "pf_map.h"
#endif

/* Largest Legendre order count k stored per azimuth. */
#define PF_HORIZON_LEGENDRE_MAX 8

/* ---------------------------------------------------------------- per-azimuth moments */
/* Filtered HDF moments of one azimuth: E[T], E[T^2] of the horizon elevation T (radians) and
   E[S T], S the slope along the azimuth (3 channels of PF_HORIZON_MOMENTS). */
PF_STRUCT_BEGIN(pf_hdf_moments)
    pf_real m1;
    pf_real m2;
    pf_real ms;
PF_STRUCT_END(pf_hdf_moments)

PF_DEF pf_hdf_moments pf_hdf_moments_make(pf_real m1, pf_real m2, pf_real ms)
{
    pf_hdf_moments m;
    m.m1 = m1;
    m.m2 = m2;
    m.ms = ms;
    return m;
}

/* (1 - f) a + f b: the moments of the mixture (linear interpolation of the HDF itself). */
PF_DEF pf_hdf_moments pf_hdf_moments_lerp(pf_hdf_moments a, pf_hdf_moments b, pf_real f)
{
    pf_real g = PF_R(1.0) - f;
    return pf_hdf_moments_make(g * a.m1 + f * b.m1, g * a.m2 + f * b.m2, g * a.ms + f * b.ms);
}

/* The stored azimuths around a direction: indices i0, i1 = i0 + 1 (mod n) and the weight f of
   i1 (piecewise linear in phi, Fournier 1992 / Tan et al. 2008). */
PF_STRUCT_BEGIN(pf_horizon_azimuth)
    int i0;
    int i1;
    pf_real f;
PF_STRUCT_END(pf_horizon_azimuth)

/* Azimuth of w (any length; w.x = w.y = 0 gives i0 = 0, f = 0) among n >= 1 stored ones. */
PF_DEF pf_horizon_azimuth pf_horizon_azimuth_of(pf_vec3 w, int n)
{
    pf_horizon_azimuth a;
    pf_real phi = (w.x == PF_R(0.0) && w.y == PF_R(0.0)) ? PF_R(0.0) : PF_ATAN2(w.y, w.x);
    pf_real u, fl;
    int nn = n < 1 ? 1 : n, i;
    if (!(phi == phi)) phi = PF_R(0.0);
    if (phi < PF_R(0.0)) phi += PF_R(2.0) * PF_PI;
    u = phi * PF_R(nn) / (PF_R(2.0) * PF_PI); /* in [0, n] */
    /* floor(u) by counting (no float-to-int conversion in the shader subset; n is small) */
    for (i = 0; i + 1 < nn && PF_R(i + 1) <= u; ++i) {
    }
    fl = PF_R(i);
    a.f = pf_saturate(u - fl);
    a.i0 = i;
    a.i1 = i + 1 >= nn ? 0 : i + 1;
    return a;
}

/* Elevation of w above the tangent plane, radians in [-pi/2, pi/2] (w need not be unit;
   w = 0, and on a GPU that flushes them a subnormal w, gives 0). */
PF_DEF pf_real pf_horizon_elevation(pf_vec3 w)
{
    /* atan2 is scale-invariant: w is scaled to a largest component of 1 so that x^2 + y^2
       cannot overflow (float |w| > 1.8e19), which made sqrt(inf) and, under -ffast-math
       (sqrt as x * rsqrt(x)), NaN, and cannot underflow (components of 1e-30 keep their
       angle); the max with PF_REAL_MIN keeps w = 0 at PF_ATAN2(0, 0) = 0 (pf_atan2 under
       GLSL: the built-in atan is undefined there) */
    pf_real s = PF_R(1.0) / pf_max(pf_max(PF_FABS(w.x), PF_FABS(w.y)), pf_max(PF_FABS(w.z), PF_REAL_MIN));
    pf_real x = w.x * s, y = w.y * s;
    return PF_ATAN2(w.z * s, PF_SQRT(x * x + y * y));
}

/* ---------------------------------------------------------------- V_A(v) from two moments */
/* Fournier 1992 (Bruneton & Neyret 2012 sec. 4.2): a linear ramp from 0 at e = mu - sigma to
   1 at e = mu + sigma; sigma = 0 is the step H(e - mu) (1 at e = mu). NaN moments give 0. */
PF_DEF pf_real pf_horizon_visibility_ramp(pf_hdf_moments m, pf_real e)
{
    pf_real var = m.m2 - m.m1 * m.m1, sd;
    if (!(var == var) || !(e == e)) return PF_R(0.0);
    sd = PF_SQRT(pf_max(var, PF_R(0.0)));
    if (!(sd > PF_R(0.0))) return e >= m.m1 ? PF_R(1.0) : PF_R(0.0);
    return pf_saturate((e - m.m1 + sd) / (PF_R(2.0) * sd));
}

/* Tan et al. 2008: p_A Gaussian with the filtered mean and variance, so eq. 26 is its CDF,
   V_A = Phi((e - mu)/sigma) = erfc((mu - e)/(sigma sqrt 2))/2. sigma = 0: step. NaN: 0. */
PF_DEF pf_real pf_horizon_visibility_gauss(pf_hdf_moments m, pf_real e)
{
    pf_real var = m.m2 - m.m1 * m.m1, sd, x;
    if (!(var == var) || !(e == e)) return PF_R(0.0);
    sd = PF_SQRT(pf_max(var, PF_R(0.0)));
    if (!(sd > PF_R(0.0))) return e >= m.m1 ? PF_R(1.0) : PF_R(0.0);
    x = (m.m1 - e) / (sd * PF_SQRT2);
    /* erfc(8) = 1.1e-29: returned as 0, which keeps pf_erfc off its subnormal path (x86
       microcode assists made the far tail 10x slower) */
    return x > PF_R(8.0) ? PF_R(0.0) : PF_R(0.5) * pf_erfc(x);
}

/* ---------------------------------------------------------------- Legendre basis (eqs. 29-30) */
/* Normalized Legendre polynomial P^_j(x) = sqrt((2j + 1)/2) P_j(x), orthonormal on [-1, 1]
   (Bonnet's recurrence; j >= 0, x in [-1, 1]). */
PF_DEF pf_real pf_horizon_legendre_basis(int j, pf_real x)
{
    pf_real p0 = PF_R(1.0), p1 = x, p2;
    int i;
    if (j <= 0) return PF_INV_SQRT2;
    for (i = 1; i < j; ++i) {
        p2 = (PF_R(2 * i + 1) * x * p1 - PF_R(i) * p0) / PF_R(i + 1);
        p0 = p1;
        p1 = p2;
    }
    return PF_SQRT(PF_R(j) + PF_R(0.5)) * p1;
}

/* The texel's coefficient a_j(Theta) = integral_{s}^{1} P^_j(x) dx, s = sin Theta: the step
   H(x - s) in the basis (x = cos zenith of the view = sin of its elevation). From
   (2j + 1) P_j = (P_{j+1} - P_{j-1})' and P_j(1) = 1:
     a_0 = (1 - s)/sqrt(2),  a_j = sqrt((2j + 1)/2) (P_{j-1}(s) - P_{j+1}(s))/(2j + 1). */
PF_DEF pf_real pf_horizon_legendre_coeff(int j, pf_real s)
{
    pf_real p0 = PF_R(1.0), p1 = s, p2, pjm1 = PF_R(1.0);
    int i;
    if (j <= 0) return (PF_R(1.0) - s) * PF_INV_SQRT2;
    for (i = 1; i <= j; ++i) { /* after step i: p0 = P_i, p1 = P_{i+1} */
        p2 = (PF_R(2 * i + 1) * s * p1 - PF_R(i) * p0) / PF_R(i + 1);
        pjm1 = p0; /* P_{i-1}: after the last step, P_{j-1} */
        p0 = p1;
        p1 = p2;
    }
    return PF_SQRT(PF_R(j) + PF_R(0.5)) * (pjm1 - p1) / PF_R(2 * j + 1);
}

/* Up to 8 filtered coefficients of one azimuth (scalar members, not an array: the shader
   subset passes structs of scalars by value; unused ones are 0). */
PF_STRUCT_BEGIN(pf_hdf_legendre)
    pf_real c0;
    pf_real c1;
    pf_real c2;
    pf_real c3;
    pf_real c4;
    pf_real c5;
    pf_real c6;
    pf_real c7;
PF_STRUCT_END(pf_hdf_legendre)

PF_DEF pf_hdf_legendre pf_hdf_legendre_make(pf_real c0, pf_real c1, pf_real c2, pf_real c3, pf_real c4,
                                            pf_real c5, pf_real c6, pf_real c7)
{
    pf_hdf_legendre a;
    a.c0 = c0;
    a.c1 = c1;
    a.c2 = c2;
    a.c3 = c3;
    a.c4 = c4;
    a.c5 = c5;
    a.c6 = c6;
    a.c7 = c7;
    return a;
}

/* Coefficient j (0 .. 7; others 0). */
PF_DEF pf_real pf_hdf_legendre_coeff(pf_hdf_legendre a, int j)
{
    return j == 0 ? a.c0 : j == 1 ? a.c1 : j == 2 ? a.c2 : j == 3 ? a.c3 : j == 4 ? a.c4
         : j == 5 ? a.c5 : j == 6 ? a.c6 : j == 7 ? a.c7 : PF_R(0.0);
}

/* (1 - f) a + f b, coefficient by coefficient (the mixture of the two HDFs). */
PF_DEF pf_hdf_legendre pf_hdf_legendre_lerp(pf_hdf_legendre a, pf_hdf_legendre b, pf_real f)
{
    pf_real g = PF_R(1.0) - f;
    return pf_hdf_legendre_make(g * a.c0 + f * b.c0, g * a.c1 + f * b.c1, g * a.c2 + f * b.c2, g * a.c3 + f * b.c3,
                                g * a.c4 + f * b.c4, g * a.c5 + f * b.c5, g * a.c6 + f * b.c6, g * a.c7 + f * b.c7);
}

/* Eq. 30: V_A = sum_{j < k} c_j P^_j(x), x = cos zenith of the view (= w.z for a unit w),
   clamped to [0, 1] (a truncated step rings). k is clamped to 1 .. PF_HORIZON_LEGENDRE_MAX.
   NaN gives 0. */
PF_DEF pf_real pf_horizon_visibility_legendre(pf_hdf_legendre a, int k, pf_real x)
{
    pf_real p0 = PF_R(1.0), p1 = x, p2, v = a.c0 * PF_INV_SQRT2;
    int kk = k < 1 ? 1 : (k > PF_HORIZON_LEGENDRE_MAX ? PF_HORIZON_LEGENDRE_MAX : k), j;
    for (j = 1; j < kk; ++j) {
        v += pf_hdf_legendre_coeff(a, j) * PF_SQRT(PF_R(j) + PF_R(0.5)) * p1;
        p2 = (PF_R(2 * j + 1) * x * p1 - PF_R(j) * p0) / PF_R(j + 1);
        p0 = p1;
        p1 = p2;
    }
    return v == v ? pf_saturate(v) : PF_R(0.0);
}

/* ---------------------------------------------------------------- bidirectional V_A(l, v)
   The fraction of the texels visible from v that are also lit from l (eq. 23), from the two
   one-way fractions vl = V_A(l), vv = V_A(v) (clamped to [0, 1]); cos_lv = l.v of unit
   directions. vv = 0 (nothing visible) returns vl. */
/* Fournier 1992: visible and lit = vl vv (uncorrelated), so the lit share of the visible is vl.
   Misses the hotspot (l = v should give 1) and the fully-lit limit holds only trivially. */
PF_DEF pf_real pf_horizon_bidir_product(pf_real vl, pf_real vv)
{
    pf_real l = pf_saturate(vl), v = pf_saturate(vv);
    return v > PF_R(0.0) ? pf_saturate(l * v / v) : l; /* (visible and lit) / visible */
}

/* Tan et al. 2008, eq. 28: [alpha min(vl, vv) + (1 - alpha) max(vl + vv - 1, 0)] / vv with
   alpha = (1 + l.v)/2 (the survey's extraction prints "(1 + |v|)/2"; we read it as the cosine
   form, which gives alpha = 1 at the hotspot as the text requires). Exactly 1 at l = v and when
   vl = 1 (fully lit), vl when vv = 1. */
PF_DEF pf_real pf_horizon_bidir_tan(pf_real vl, pf_real vv, pf_real cos_lv)
{
    pf_real a = pf_saturate(PF_R(0.5) * (PF_R(1.0) + cos_lv));
    pf_real l = pf_saturate(vl), v = pf_saturate(vv);
    if (!(v > PF_R(0.0))) return l;
    /* v - (1 - l), not l + v - 1: exact for l = 1, so a fully lit footprint gives 1 even for a
       tiny v */
    return pf_saturate((a * pf_min(l, v) + (PF_R(1.0) - a) * pf_max(v - (PF_R(1.0) - l), PF_R(0.0))) / v);
}

/* Ashikhmin, Premoze & Shirley 2000 (Bruneton & Neyret 2012 sec. 4.2): [beta min(vl, vv) +
   (1 - beta) vl vv] / vv, beta = exp(-(g/width)^2), g = angle between l and v (radians);
   the survey gives no width: the caller chooses it (width <= 0: beta = 1 at g = 0, else 0).
   1 at l = v and when vl = 1; vl when vv = 1. */
PF_DEF pf_real pf_horizon_bidir_ashikhmin(pf_real vl, pf_real vv, pf_real cos_lv, pf_real width)
{
    pf_real c = pf_clamp(cos_lv, PF_R(-1.0), PF_R(1.0));
    pf_real g = PF_ATAN2(PF_SQRT(pf_max(PF_R(1.0) - c * c, PF_R(0.0))), c);
    pf_real b = width > PF_R(0.0) ? PF_EXP(-pf_sq(g / width)) : (g > PF_R(0.0) ? PF_R(0.0) : PF_R(1.0));
    pf_real l = pf_saturate(vl), v = pf_saturate(vv);
    if (!(v > PF_R(0.0))) return l;
    return pf_saturate((b * pf_min(l, v) + (PF_R(1.0) - b) * l * v) / v);
}

/* ---------------------------------------------------------------- masking (see COMBINING WITH SMITH)
   E[V a]/E[a] for the view w (see pf_horizon_visible_area) with the HDF of w's azimuth the
   Gram-Charlier series of skewness g (Cramer 1946 sec. 17.6; Kendall & Stuart, The Advanced
   Theory of Statistics vol. 1, sec. 6.17): with z = (e - E[T])/sigma_T,
       P(T < e)              = Phi(z) - g/6 (z^2 - 1) phi(z),
       E[(T - mu)/sigma_T; T < e] = -phi(z) (1 + g z^3/6)
   (the density phi(z) (1 + g/6 He_3(z)) integrated; the second by parts), and S's regression
   on T as in the Gaussian, so
       E[V a] = w.z P - r (E[S] P + Cov(S, T)/sigma_T E[(T - mu)/sigma_T; T < e]).
   The series' density is negative far in the left tail (z below -2.4 at g = 1), where its CDF
   is negative: P is clamped to [0, 1] and the partial mean to at most z P (what any
   distribution gives: (T - mu)/sigma_T < z below e), so both are 0 together, continuous, and P
   is non-decreasing in e (the density is positive for z > -2.4 at g <= 1). g is estimated
   from the stored moments (ours; measured, docs/horizon.md "User maps"): g = sigma_T/E[T] (1 - rho^2), at most 1 (1 for E[T] <= 0),
   rho the correlation of T and the slope S along w's azimuth: a horizon is a maximum over the
   march, right-skewed where it is set by distant bumps (sigma_T comparable to E[T]), and the
   part of T that the texel's own slope explains is as symmetric as the slopes. vs = r^2
   Var(S) (r = |w_xy|); vs < 0 gives g = 0, the bivariate Gaussian. No division by a possibly
   zero operand, so no inf under -ffast-math. */
PF_DEF pf_real pfi_horizon_area(pf_vec3 w, pf_hdf_moments m, pf_real mean_x, pf_real mean_y, pf_real vs)
{
    pf_real r = PF_SQRT(w.x * w.x + w.y * w.y);
    pf_real rs = w.x * mean_x + w.y * mean_y; /* r E[S] */
    pf_real ea = w.z - rs, e = PF_ATAN2(w.z, r);
    pf_real var = m.m2 - m.m1 * m.m1, sd, cdf, pdf, cov, pm, z, eva;
    if (!(ea > PF_R(0.0)) || !(var == var) || !(m.ms == m.ms)) return PF_R(0.0);
    sd = PF_SQRT(pf_max(var, PF_R(0.0)));
    if (!(sd > PF_R(1e-6) * (PF_R(1.0) + PF_FABS(m.m1)))) {
        cdf = e >= m.m1 ? PF_R(1.0) : PF_R(0.0);
        pm = PF_R(0.0);
        cov = PF_R(0.0);
    } else {
        /* r Cov(S, T) = r E[S T] - (r E[S]) E[T] */
        pf_real covr = r * m.ms - rs * m.m1, d = var * vs, g = PF_R(0.0), u;
        if (vs >= PF_R(0.0)) {
            /* sigma_T (1 - rho^2), rho^2 = (r Cov)^2/(Var(T) r^2 Var(S)); d NaN or tiny: rho = 0 */
            u = d > PF_R(1e-30) ? sd * pf_max(d - covr * covr, PF_R(0.0)) / d : sd;
            g = u >= m.m1 ? PF_R(1.0) : u / m.m1; /* u < E[T] here, so E[T] > 0 */
        }
        z = pf_clamp((e - m.m1) / sd, PF_R(-12.0), PF_R(12.0));
        /* beyond |z| = 12 Phi is 0 or 1 and phi < 1e-31 (and the tails of erfc and exp would
           be subnormal: slow on x86) */
        cdf = z > PF_R(-12.0) ? (z < PF_R(12.0) ? PF_R(0.5) * pf_erfc(-z * PF_INV_SQRT2) : PF_R(1.0)) : PF_R(0.0);
        pdf = PF_FABS(z) < PF_R(12.0) ? pf_exp_neg_sq(z * PF_INV_SQRT2) * (PF_R(1.0) / PF_SQRT_2PI) : PF_R(0.0);
        cdf = pf_saturate(cdf - g * (PF_R(1.0) / PF_R(6.0)) * (z * z - PF_R(1.0)) * pdf);
        pm = pf_min(-pdf * (PF_R(1.0) + g * (PF_R(1.0) / PF_R(6.0)) * z * z * z), z * cdf);
        cov = covr / sd;
    }
    eva = w.z * cdf - (rs * cdf + cov * pm);
    return pf_clamp(eva / ea, PF_R(0.0), PF_R(2.0));
}

/* Visible projected area over mean projected area of a footprint seen from w (any length,
   w.z > 0), from the HDF moments m of w's azimuth and the mean slope (mean_x, mean_y) of the
   footprint (pf_slope_stats): with (T, S) jointly Gaussian, z = (e - E[T])/sigma_T,
     E[V a] = w.z Phi(z) - r (E[S] Phi(z) - Cov(S, T)/sigma_T phi(z)),
     E[a]   = w.z - r E[S],        r = |w_xy|, r E[S] = w.x mean_x + w.y mean_y,
   returned as E[V a]/E[a] clamped to [0, 2] (the exact ratio exceeds 1 where the footprint is
   also seen through its sides). 0 when E[a] <= 0 (the view at or below the mean plane) or for
   NaN inputs. The Gaussian shape: pf_horizon_masking uses the skewed one (pfi_horizon_area),
   which needs the slope variance as well. */
PF_DEF pf_real pf_horizon_visible_area(pf_vec3 w, pf_hdf_moments m, pf_real mean_x, pf_real mean_y)
{
    return pfi_horizon_area(w, m, mean_x, mean_y, PF_R(-1.0));
}

/* The area ratio of pf_horizon_masking: pfi_horizon_area with the skewness from the slope
   statistics s (r^2 Var(S) along w's azimuth). */
PF_DEF pf_real pfi_horizon_area_skew(pf_vec3 w, pf_hdf_moments m, pf_slope_stats s)
{
    pf_real vs = w.x * w.x * s.var_x + w.y * w.y * s.var_y + PF_R(2.0) * w.x * w.y * s.cov_xy;
    return pfi_horizon_area(w, m, s.mean_x, s.mean_y, pf_max(vs, PF_R(0.0)));
}

/* Masking G1 of the footprint: the visible area ratio with the skewed (Gram-Charlier) HDF
   (pfi_horizon_area; the Gaussian's pf_horizon_visible_area at g = 0) times Smith's
   1/(1 + Lambda) of its slope statistics (pf_beckmann_g1), clamped to [0, 1]. */
PF_DEF pf_real pf_horizon_masking(pf_vec3 w, pf_hdf_moments m, pf_slope_stats s)
{
    return pf_saturate(pfi_horizon_area_skew(w, m, s) * pf_beckmann_g1(w, s));
}

/* ---------------------------------------------------------------- fading to Smith by footprint size
   (see FADING BY LEVEL OF DETAIL above; measured: docs/horizon.md)
   Weight of the horizon term at mip level lod: 1 for lod <= lod_full, 0 for lod >= lod_smith,
   linear in lod between:  k = clamp((lod_smith - lod)/(lod_smith - lod_full), 0, 1).
   lod is the level whose texel is the footprint (log2 of its side in texels; fractional
   between levels). Edge inputs: a NaN lod or bound gives 0 (Smith alone, the statistical
   answer); lod = -inf gives 1, +inf gives 0; lod_full >= lod_smith is a step at lod_smith;
   lod_smith = +inf never fades (1 above lod_full as below). Measured choice for the bench's
   512^2 maps (features of 3-16 texels): lod_full = 2, lod_smith = 6. */
PF_DEF pf_real pf_horizon_lod_weight(pf_real lod, pf_real lod_full, pf_real lod_smith)
{
    /* NaN fails the first comparison; an infinite lod is decided before the division */
    if (!(lod < lod_smith)) return PF_R(0.0);
    if (lod <= lod_full) return PF_R(1.0);
    if (lod_smith > PF_REAL_MAX) return PF_R(1.0);
    /* lod_full = -inf: finite / inf = 0; lod_full NaN: NaN, which the clamp takes to 0 */
    return pf_clamp_nan_lo((lod_smith - lod) / (lod_smith - lod_full), PF_R(0.0), PF_R(1.0));
}

/* Masking G1 with the horizon term faded to Smith by footprint size:
       G1 = clamp(G1_smith (k R + 1 - k), 0, 1),   k = pf_horizon_lod_weight(lod, lod_full, lod_smith),
   R = pf_horizon_masking's area ratio (the skewed HDF), G1_smith = pf_beckmann_g1(w, s). k = 1 is
   pf_horizon_masking exactly, k = 0 is pf_beckmann_g1 exactly (R is not evaluated then: the
   shader may skip the HDF fetch above lod_smith). The same inputs as pf_horizon_masking; a
   view at or below the mean plane or NaN moments give R = 0, hence (1 - k) G1_smith. */
PF_DEF pf_real pf_horizon_masking_lod(pf_vec3 w, pf_hdf_moments m, pf_slope_stats s, pf_real lod, pf_real lod_full,
                                      pf_real lod_smith)
{
    pf_real k = pf_horizon_lod_weight(lod, lod_full, lod_smith);
    pf_real r = k > PF_R(0.0) ? pfi_horizon_area_skew(w, m, s) : PF_R(1.0);
    return pf_saturate(pf_beckmann_g1(w, s) * (k * r + (PF_R(1.0) - k)));
}

/* ---------------------------------------------------------------- diffuse: LEADR's grid with horizon visibility
   (see DIFFUSE above; measured: docs/horizon.md) */
/* The conditional HDF of one direction, set up once per direction and evaluated per facet
   slope: T given S = s is Gaussian, mean mu + beta (s - es), deviation sd. */
PF_STRUCT_BEGIN(pfi_horizon_cond)
    pf_real e;    /* elevation of the direction, radians */
    pf_real dx;   /* unit horizontal direction (0, 0 for a vertical one) */
    pf_real dy;
    pf_real es;   /* E[S], S the facet slope along (dx, dy) */
    pf_real mu;   /* E[T] */
    pf_real beta; /* Cov(S, T)/Var(S) (0 when Var(S) is 0) */
    pf_real sd;   /* sqrt(Var(T) - Cov(S, T)^2/Var(S)), >= 0; -1 for NaN moments (visibility 0) */
PF_STRUCT_END(pfi_horizon_cond)

PF_DEF pfi_horizon_cond pfi_horizon_cond_make(pf_vec3 w, pf_hdf_moments m, pf_slope_stats s)
{
    pfi_horizon_cond c;
    pf_real r = PF_SQRT(w.x * w.x + w.y * w.y), var = m.m2 - m.m1 * m.m1, vs, cov, vc;
    c.e = pf_horizon_elevation(w);
    /* r overflows to inf for |w| > 1e19 in float: the direction is then 0, finite */
    c.dx = r > PF_R(0.0) ? w.x / r : PF_R(0.0);
    c.dy = r > PF_R(0.0) ? w.y / r : PF_R(0.0);
    c.es = s.mean_x * c.dx + s.mean_y * c.dy;
    vs = s.var_x * c.dx * c.dx + s.var_y * c.dy * c.dy + PF_R(2.0) * s.cov_xy * c.dx * c.dy;
    c.mu = m.m1;
    c.beta = PF_R(0.0);
    vc = pf_max(var, PF_R(0.0));
    if (vs > PF_R(1e-12)) {
        /* |Cov(S, T)| <= sigma_S sigma_T (Cauchy-Schwarz): statistics of S from another source
           than the HDF's stencil (a lobe fit, a base variance taken off) can break it, and a
           tiny Var(S) then turns the excess into a huge shift of the conditional mean */
        cov = pf_clamp(m.ms - c.es * m.m1, -PF_SQRT(vc * vs), PF_SQRT(vc * vs));
        c.beta = cov / vs;
        vc = pf_max(vc - cov * c.beta, PF_R(0.0));
    }
    c.sd = (var == var && m.ms == m.ms && c.e == c.e) ? PF_SQRT(vc) : PF_R(-1.0);
    return c;
}

/* P(T < e | S = slope of (sx, sy) along the direction), the Gaussian CDF: pf_erfc, or with
   fast != 0 the shader tier pf_erfc_fast (relative error 5.4e-6 in float; the diffuse, whose
   result is a shaded colour, uses it). */
PF_DEF pf_real pfi_horizon_cond_vis(pfi_horizon_cond c, pf_real sx, pf_real sy, int fast)
{
    pf_real mu = c.mu + c.beta * (sx * c.dx + sy * c.dy - c.es), z;
    if (c.sd < PF_R(0.0)) return PF_R(0.0);
    if (!(c.sd > PF_R(1e-6) * (PF_R(1.0) + PF_FABS(mu)))) return c.e >= mu ? PF_R(1.0) : PF_R(0.0);
    /* a NaN z (NaN slope) becomes -12: not visible; beyond |z| = 12 Phi is 0 or 1 (and erfc's
       tail would be subnormal) */
    z = pf_clamp_nan_lo((c.e - mu) / c.sd, PF_R(-12.0), PF_R(12.0));
    if (!(z > PF_R(-12.0))) return PF_R(0.0);
    if (!(z < PF_R(12.0))) return PF_R(1.0);
    return PF_R(0.5) * (fast != 0 ? pf_erfc_fast(-z * PF_INV_SQRT2) : pf_erfc(-z * PF_INV_SQRT2));
}

/* Visibility toward w of the footprint's facets of slope (sx, sy): the horizon elevation T
   and the facet's slope S along w's azimuth jointly Gaussian (E[T], E[T^2], E[S T] from m; E[S],
   Var(S) from the slope stats s), so T given S = s is Gaussian with
       mean  E[T] + Cov(S, T)/Var(S) (s - E[S]),   variance  Var(T) - Cov(S, T)^2/Var(S),
   and V(s) = Phi((e - mean)/deviation): Tan et al.'s Gaussian HDF (eq. 26) of the texels that
   share the facet's slope (ours: the conditioning). In [0, 1]; a vertical w gives 1 (above
   every horizon), NaN moments or slopes 0; a zero conditional variance is the step. */
PF_DEF pf_real pf_horizon_visibility_given_slope(pf_vec3 w, pf_hdf_moments m, pf_slope_stats s, pf_real sx, pf_real sy)
{
    return pfi_horizon_cond_vis(pfi_horizon_cond_make(w, m, s), sx, sy, 0);
}

/* Lambertian diffuse of the footprint under a directional light wi (unit albedo, radiance per
   unit irradiance at normal incidence, as pf_gg_diffuse_directional), LEADR eq. 21's slope
   grid g (pf_gg_grid_make(wo, stats, node set, N)) with the Smith factor replaced by the
   horizon visibilities of each grid facet (pf_horizon_visibility_given_slope toward wo from
   m_o, toward wi from m_i; the two stored azimuths around each direction mixed by
   pf_hdf_moments_lerp), joined by Tan et al.'s eq. 28 (pf_horizon_bidir_tan, alpha =
   (1 + wo.wi)/2: visible and lit = V_o bidir(V_i, V_o)):
       I = (1/pi) (sum W a+ V_o B max(0, n.wi) / sum W a+ V_o) min(sum W a+ V_o / A_o, 2),
   a = wo.z - x wo.x - y wo.y the facet's projected area, A_o = wo.z - E[x] wo.x - E[y] wo.y
   the mean plane's; the first factor is the lit cosine over the visible facets, the second
   the visible area ratio (clamped as pf_horizon_visible_area's). 0 when A_o <= 0 (the view
   at or below the mean plane), wi.z <= 0, or nothing is visible. Cost: N^2 samples, two erfc
   each (pf_erfc_fast, the shader tier: its 5.4e-6 relative error is far below the model's). */
PF_DEF pf_real pf_horizon_diffuse_directional(pf_gg_grid g, pf_vec3 wi, pf_hdf_moments m_o, pf_hdf_moments m_i)
{
    pf_vec3 wo = g.wo;
    pf_real ao = wo.z - wo.x * g.stats.mean_x - wo.y * g.stats.mean_y, c = pf_vec3_dot(wo, wi);
    pf_real vis = PF_R(0.0), lit = PF_R(0.0);
    pfi_horizon_cond co = pfi_horizon_cond_make(wo, m_o, g.stats), ci = pfi_horizon_cond_make(wi, m_i, g.stats);
    int j, k;
    if (!(ao > PF_R(0.0)) || !(wi.z > PF_R(0.0))) return PF_R(0.0);
    for (j = 0; j < g.n; ++j) {
        pf_real pj = pf_gg_node(g.node_set, g.n, j), wj = pf_gg_weight(g.node_set, g.n, j);
        for (k = 0; k < g.n; ++k) {
            pf_gg_sample smp = pf_gg_sample_nodes(g, pj, wj, pf_gg_node(g.node_set, g.n, k),
                                                   pf_gg_weight(g.node_set, g.n, k));
            pf_real a = smp.weight * pf_max(wo.z - smp.slope_x * wo.x - smp.slope_y * wo.y, PF_R(0.0));
            pf_real vo = pfi_horizon_cond_vis(co, smp.slope_x, smp.slope_y, 1);
            pf_real vi = pfi_horizon_cond_vis(ci, smp.slope_x, smp.slope_y, 1);
            vis += a * vo;
            lit += a * vo * pf_horizon_bidir_tan(vi, vo, c) * pf_max(pf_vec3_dot(smp.normal, wi), PF_R(0.0));
        }
    }
    if (!(vis > PF_R(0.0))) return PF_R(0.0);
    /* lit <= vis: the first factor is in [0, 1]; a NaN ratio takes the min's 2 */
    return lit / vis * pf_min(vis / ao, PF_R(2.0)) * PF_INV_PI;
}

/* pf_horizon_diffuse_directional faded to LEADR's pf_gg_diffuse_directional by mip level, as
   pf_horizon_masking_lod: k I_horizon + (1 - k) I_leadr, k = pf_horizon_lod_weight(lod,
   lod_full, lod_smith); each side evaluated only when its weight is not 0, so k = 1 and k = 0
   are the two functions exactly. */
PF_DEF pf_real pf_horizon_diffuse_lod(pf_gg_grid g, pf_vec3 wi, pf_hdf_moments m_o, pf_hdf_moments m_i, pf_real lod,
                                      pf_real lod_full, pf_real lod_smith)
{
    pf_real k = pf_horizon_lod_weight(lod, lod_full, lod_smith);
    pf_real h = k > PF_R(0.0) ? pf_horizon_diffuse_directional(g, wi, m_o, m_i) : PF_R(0.0);
    pf_real l = k < PF_R(1.0) ? pf_gg_diffuse_directional(g, wi) : PF_R(0.0);
    return k * h + (PF_R(1.0) - k) * l;
}

/* ---------------------------------------------------------------- specular: the reflecting facets' horizon
   (see SPECULAR above; measured: docs/horizon.md)
   Visibility of the facets that reflect wi into wo: those whose slope is the half vector's,
   s_h = (-h.x/h.z, -h.y/h.z), h = wo + wi. A reflecting facet's slope is its texel's slope S
   plus the base lobe's B (variance base_var, independent of the horizon T), so its HDF toward
   a direction is T | S + B = s_h along the direction's azimuth, Gaussian with
       mean  E[T] + beta (s_h - E[S]),   variance  Var(T) - beta Cov(S, T),
       beta = Cov(S, T) / (Var(S) + base_var)          (Cov(S + B, T) = Cov(S, T)),
   and visible-and-lit is joined by Tan et al.'s eq. 28:
       V_h = V_o(s_h) pf_horizon_bidir_tan(V_i(s_h), V_o(s_h), wo.wi).
   Why S + B and not S alone: beta would divide by the texels' own Var(S), which is 0 in one
   texel and, in a pyramid stored in 16 bits, the rounding of E[x^2] - E[x]^2 (1e-6 .. 1e-4);
   beta is then a ratio of rounding errors, bounded only by Cauchy-Schwarz at
   sqrt(Var(T)/Var(S)), and it moves the horizon by up to a radian (1-texel footprints stored
   in half or unorm16: relative L2 0.67 from the float32 values, tests/test_horizon.c). With
   base_var, |beta| <= sqrt(Var(T)/base_var)/2. Var(S) in Cauchy-Schwarz's bound is the
   texels' own (the statistics' variance along the azimuth less base_var, floored at 0).
   s: the footprint's slope statistics with base_var added (what pf_leadr_specular takes:
   pf_slope_moments_stats(m, base_var)). Unit directions. In [0, 1]; 0 when either direction
   is on or below the macrosurface; NaN moments or slopes give 0 (C and C++; CUDA's fmin/fmax
   and GLSL's min/max drop or keep a NaN operand, so there the result is not specified).
   Written for the shader: no branch; the elevation asin(w.z) by Abramowitz & Stegun 4.4.45
   (|error| <= 5e-5 rad), the Gaussian CDF by the logistic of Bowling, Khasawneh, Kaewkuekool
   & Cho 2009, Phi(z) ~ 1/(1 + exp(-z (1.5976 + 0.070566 z^2))) (|error| <= 1.4e-4); the
   visibility is within 1.1e-3 of the long-double formula (float and double: the arcsine's
   error over 0.7 times the deviation, at deviations from 0.02 rad), far below the model's error against
   the brute force. A zero deviation is the step (1/2 at e = E[T | S + B] exactly). */
/* The conditional visibility toward unit w (w.z > 0: the caller's select), at the slope
   offset (X, Y) = E[s] - s_h (the sign pfi_beckmann_d_up's X, Y have: the shader shares them),
   from the statistics s with base_var b added. */
PF_DEF pf_real pfi_horizon_spec_cond_vis(pf_vec3 w, pf_hdf_moments m, pf_slope_stats s, pf_real b, pf_real X,
                                         pf_real Y)
{
    pf_real ir = pfi_beckmann_rsqrt(pf_max(w.x * w.x + w.y * w.y, PF_REAL_MIN)), dx = w.x * ir, dy = w.y * ir;
    pf_real c = pf_max(PF_R(1.0) - w.z, PF_R(0.0)), nm1 = -m.m1;
    /* A&S 4.4.45: asin(x) = pi/2 - sqrt(1 - x) (a0 + a1 x + a2 x^2 + a3 x^3), 0 <= x <= 1;
       here e - E[T] = (pi/2 - E[T]) + sqrt(1 - x) (-a0 - a1 x - ...) (the signs folded into the
       constants, and -E[T] shared with the variance and the covariance: fewer shader ops) */
    pf_real em = (PF_R(1.5707963267948966) + nm1) +
                 PF_SQRT(c) * (PF_R(-1.5707288) + w.z * (PF_R(0.2121144) + w.z * (PF_R(-0.0742610) + w.z * PF_R(0.0187293))));
    pf_real es = s.mean_x * dx + s.mean_y * dy;
    pf_real vs = dx * (s.var_x * dx + PF_R(2.0) * s.cov_xy * dy) + s.var_y * dy * dy; /* Var(S) + b */
    pf_real var = m.m2 + nm1 * m.m1;
    /* Cauchy-Schwarz, |Cov(S, T)| <= sigma_S sigma_T, with the texels' own Var(S) */
    pf_real lim = PF_SQRT(pf_max(var, PF_R(0.0)) * pf_max(vs - b, PF_R(0.0)));
    pf_real cov = pf_clamp(m.ms + es * nm1, -lim, lim);
    pf_real vsm = pf_max(vs, PF_REAL_MIN);
    pf_real beta = cov / vsm;
    pf_real vc = var - cov * beta;
    /* (e - mean) / deviation, mean = E[T] - beta (s_h - E[S]) - beta Cov(S, T)/sqrt(Var(S) + b)
       (the last term: the convexity correction, see SPECULAR above); the variance floored at
       1e-30 (GLSL's inversesqrt(0) is undefined; max(1e-30, NaN) keeps the NaN in C), so a
       zero deviation is the step within 1e-15 rad. Phi(z / 0.7) (the deviation times 0.7, see
       SPECULAR above) by the logistic, Phi = exp(t)/(1 + exp(t)), t = z (1.5976/0.7 +
       (0.070566/0.7^3) z^2), with z clamped to [-24, 7] (a NaN, from NaN moments or slopes, to
       -24): at -24 exp(t) = exp(-2900) underflows to 0 and Phi is 0 exactly; from z = 3.5 (float)
       on Phi rounds to 1, and at 7 exp(t) = exp(86.5) is finite in float. So no step makes an
       infinity: the form 1/(1 + exp(-t)) took exp(+large) = inf to 1/inf = 0, which
       -ffinite-math-only does not keep (clang and gcc -ffast-math divide float vectors by a
       reciprocal estimate and one Newton step, r + r (1 - d r): inf * 0 = NaN for every
       occluded direction; here 0 times the estimate is 0). */
    pf_real z = (em + beta * (X * dx + Y * dy + cov * pfi_beckmann_rsqrt(vsm))) * pfi_beckmann_rsqrt(pf_max(PF_R(1e-30), vc)), ez;
    z = pf_clamp_nan_lo(z, PF_R(-24.0), PF_R(7.0));
    ez = PF_EXP(z * (PF_R(2.2822857) + PF_R(0.20573178) * z * z));
    return ez / (PF_R(1.0) + ez);
}

/* V_h for unit wo, wi with wo.z, wi.z > 0 (the callers' select): eq. 28's visible-and-lit
   written without its division, V_o bidir(V_i, V_o) = a min(V_i, V_o) + (1 - a) max(V_o + V_i
   - 1, 0), a = (1 + wo.wi)/2. */
PF_DEF pf_real pfi_horizon_spec_vis(pf_vec3 wo, pf_vec3 wi, pf_hdf_moments m_o, pf_hdf_moments m_i, pf_slope_stats s,
                                    pf_real base_var)
{
    pf_vec3 h = pf_vec3_add(wo, wi);
    pf_real iz = PF_R(1.0) / h.z, X = h.x * iz + s.mean_x, Y = h.y * iz + s.mean_y;
    pf_real b = pf_max(base_var, PF_R(0.0));
    pf_real vo = pfi_horizon_spec_cond_vis(wo, m_o, s, b, X, Y);
    pf_real vi = pfi_horizon_spec_cond_vis(wi, m_i, s, b, X, Y);
    pf_real a = pf_clamp_nan_lo(PF_R(0.5) + PF_R(0.5) * pf_vec3_dot(wo, wi), PF_R(0.0), PF_R(1.0));
    return a * pf_min(vo, vi) + (PF_R(1.0) - a) * pf_max(vo - (PF_R(1.0) - vi), PF_R(0.0));
}

PF_DEF pf_real pf_horizon_specular_visibility(pf_vec3 wo, pf_vec3 wi, pf_hdf_moments m_o, pf_hdf_moments m_i,
                                              pf_slope_stats s, pf_real base_var)
{
    pf_real v = pfi_horizon_spec_vis(wo, wi, m_o, m_i, s, base_var);
    return (wo.z > PF_R(0.0) && wi.z > PF_R(0.0)) ? v : PF_R(0.0);
}

/* The statistics s with base_var taken off both variances (floored at 0; a negative or NaN
   base_var counts as 0): the texels' own slopes, from statistics that had the base lobe's
   variance added (pf_slope_moments_stats(m, base_var)). */
PF_DEF pf_slope_stats pf_horizon_texel_stats(pf_slope_stats s, pf_real base_var)
{
    pf_real b = pf_max(base_var, PF_R(0.0));
    s.var_x = pf_max(s.var_x - b, PF_R(0.0));
    s.var_y = pf_max(s.var_y - b, PF_R(0.0));
    return s;
}

/* LEADR's specular (pf_leadr_specular, Dupuy et al. 2013 eq. 17) with Smith's G replaced by the
   reflecting facets' horizon visibility (pf_horizon_specular_visibility):
       I = F(h.wi) D(h) V_h / (4 A_o),   A_o = wo.z - E[x] wo.x - E[y] wo.y  (eq. 1),
   radiance toward wo per unit radiance from wi, light cosine included, as pf_leadr_specular.
   s: the footprint's slope statistics with the base lobe's variance base_var added (what
   pf_leadr_specular takes: pf_slope_moments_stats(m, base_var)); the HDF is conditioned on
   the reflecting facets' slope, the texels' plus the base lobe's (see
   pf_horizon_specular_visibility). Unit directions. m_o, m_i: the HDF moments toward wo and wi (the two stored
   azimuths around each, pf_hdf_moments_lerp). No Smith factor is left: the horizon holds the
   footprint's own occluders as well as its neighbours' (the march starts one texel from the
   node). 0 when either direction is on or below the macrosurface or A_o <= 0 (the view at or
   below the mean plane: use pf_leadr_specular there, or the _lod form, whose weight the caller
   may set to 0). f0 as pf_fresnel_schlick (1: Fresnel off). */
PF_DEF pf_real pf_horizon_leadr_specular(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real base_var,
                                         pf_hdf_moments m_o, pf_hdf_moments m_i, pf_real f0)
{
    pf_real ao = wo.z - s.mean_x * wo.x - s.mean_y * wo.y;
    pf_real v = pfi_horizon_spec_vis(wo, wi, m_o, m_i, s, base_var);
    pf_real f = pf_fresnel_schlick(f0, PF_SQRT(pf_saturate(PF_R(0.5) + PF_R(0.5) * pf_vec3_dot(wo, wi))));
    pf_real r = f * pf_beckmann_d(pf_vec3_add(wo, wi), s) * v * PF_R(0.25) / pf_max(ao, PF_REAL_MIN);
    return (ao > PF_R(0.0) && wo.z > PF_R(0.0) && wi.z > PF_R(0.0)) ? pf_min(r, PF_REAL_MAX) : PF_R(0.0);
}

/* pf_horizon_leadr_specular faded to pf_leadr_specular by mip level (pf_horizon_lod_weight, as
   pf_horizon_masking_lod): k I_horizon + (1 - k) I_leadr; each side evaluated only when its
   weight is not 0, so k = 1 and k = 0 are the two functions exactly. */
PF_DEF pf_real pf_horizon_leadr_specular_lod(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real base_var,
                                             pf_hdf_moments m_o, pf_hdf_moments m_i, pf_real f0, pf_real lod,
                                             pf_real lod_full, pf_real lod_smith)
{
    pf_real k = pf_horizon_lod_weight(lod, lod_full, lod_smith);
    pf_real h = k > PF_R(0.0) ? pf_horizon_leadr_specular(wo, wi, s, base_var, m_o, m_i, f0) : PF_R(0.0);
    pf_real l = k < PF_R(1.0) ? pf_leadr_specular(wo, wi, s, f0) : PF_R(0.0);
    return k * h + (PF_R(1.0) - k) * l;
}

/* The multi-lobe specular of pf_vmf.h (a pf_vmf_sum of the texel's lobes, slope form:
   pf_vmf_sum_add with base_var) with the mixture's Smith G replaced by the reflecting facets'
   horizon visibility:
       I = F(h.wi) (ndf / amp) V_h / (4 A_o),   amp A_o = wo.z amp - wo.x sum amp E[x] - wo.y sum amp E[y],
   V_h = pf_horizon_specular_visibility conditioned on the footprint's slope statistics s (the
   LEADR slope-moment texel: pf_slope_moments_stats(m, base_var), as in
   pf_horizon_leadr_specular). Why not the lobes' own mixture statistics: at small footprints
   their variance is the lobes' spread (kappa), not the texels', and the HDF's slope-horizon
   covariance, mixed over two stored azimuths, then shifts the conditional horizon by noise
   (measured: 1-texel footprints 0.18 against 0.13 with the slope moments; docs/horizon.md).
   Every lobe's reflecting facets have the half vector's slope, and the HDF's conditioning is on
   the slope alone (one E[S T] per azimuth for the whole footprint), so the per-lobe visibility
   is the same V_h for each lobe and factors out of the sum: one pair of conditional
   visibilities for any lobe count. 0 when either direction is on or below the macrosurface,
   the sum is empty, or A_o <= 0. */
PF_DEF pf_real pf_horizon_vmf_specular(pf_vmf_sum sum, pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real base_var,
                                       pf_hdf_moments m_o, pf_hdf_moments m_i, pf_real f0)
{
    pf_real area = wo.z * sum.amp - wo.x * sum.ex - wo.y * sum.ey; /* amp A_o (LEADR eq. 1) */
    pf_real v = pfi_horizon_spec_vis(wo, wi, m_o, m_i, s, base_var);
    pf_real f = pf_fresnel_schlick(f0, PF_SQRT(pf_saturate(PF_R(0.5) + PF_R(0.5) * pf_vec3_dot(wo, wi))));
    /* (ndf / amp) / (area / amp) = ndf / area: the sum's amplitude cancels */
    pf_real r = (sum.ndf / pf_max(area, PF_REAL_MIN)) * f * v * PF_R(0.25);
    return (area > PF_R(0.0) && sum.amp > PF_R(0.0) && wo.z > PF_R(0.0) && wi.z > PF_R(0.0)) ? pf_min(r, PF_REAL_MAX)
                                                                                          : PF_R(0.0);
}

/* pf_horizon_vmf_specular faded to pf_vmf_sum_specular by mip level (as
   pf_horizon_leadr_specular_lod). */
PF_DEF pf_real pf_horizon_vmf_specular_lod(pf_vmf_sum sum, pf_vec3 wo, pf_vec3 wi, pf_slope_stats s,
                                           pf_real base_var, pf_hdf_moments m_o, pf_hdf_moments m_i, pf_real f0,
                                           pf_real lod, pf_real lod_full, pf_real lod_smith)
{
    pf_real k = pf_horizon_lod_weight(lod, lod_full, lod_smith);
    pf_real h = k > PF_R(0.0) ? pf_horizon_vmf_specular(sum, wo, wi, s, base_var, m_o, m_i, f0) : PF_R(0.0);
    pf_real l = k < PF_R(1.0) ? pf_vmf_sum_specular(sum, wo, wi, f0) : PF_R(0.0);
    return k * h + (PF_R(1.0) - k) * l;
}

/* ================================================================ CPU only: building the maps */
#ifndef PF_GLSL

#define PF_HORIZON_ANGLES 0   /* [1 per azimuth]  Theta (not linearly filterable) */
#define PF_HORIZON_MOMENTS 1  /* [3 per azimuth]  Theta, Theta^2, S Theta          pf_hdf_moments */
#define PF_HORIZON_LEGENDRE 2 /* [k per azimuth]  a_0(Theta) .. a_{k-1}(Theta)     pf_hdf_legendre */

/* Channels per texel of a kind for n azimuths (k: Legendre coefficients, 1 ..
   PF_HORIZON_LEGENDRE_MAX, ignored by the others); 0 for an unknown kind, n < 1, a bad k, or a
   count above PF_MAX_SIDE. */
PF_CPU_DEF int pf_horizon_channels(int kind, int n_azimuths, int k)
{
    long long per;
    if (n_azimuths < 1 || n_azimuths > PF_MAX_SIDE) return 0;
    if (kind == PF_HORIZON_ANGLES) per = 1;
    else if (kind == PF_HORIZON_MOMENTS) per = 3;
    else if (kind == PF_HORIZON_LEGENDRE && k >= 1 && k <= PF_HORIZON_LEGENDRE_MAX) per = k;
    else return 0;
    return per * n_azimuths > PF_MAX_SIDE ? 0 : (int)(per * n_azimuths);
}

/* Bilinear height at (px, py) in texel units (node (i, j) at (i, j)), nodes wrapped or clamped
   (each axis reduced once: two index reductions per sample, not eight). */
PF_CPU_DEF pf_real pfi_horizon_bilinear(const pf_real *hm, int w, int h, pf_real px, pf_real py, int border)
{
    pf_real fx = PF_FLOOR(px), fy = PF_FLOOR(py), u = px - fx, v = py - fy;
    long long ix = (long long)fx, iy = (long long)fy, ix1, iy1;
    const pf_real *r0, *r1;
    if (border == PF_BORDER_WRAP) {
        ix = pf_map_wrap(ix, w);
        iy = pf_map_wrap(iy, h);
        ix1 = ix + 1 == w ? 0 : ix + 1;
        iy1 = iy + 1 == h ? 0 : iy + 1;
    } else {
        ix1 = ix + 1 < 0 ? 0 : (ix + 1 >= w ? w - 1 : ix + 1);
        iy1 = iy + 1 < 0 ? 0 : (iy + 1 >= h ? h - 1 : iy + 1);
        ix = ix < 0 ? 0 : (ix >= w ? w - 1 : ix);
        iy = iy < 0 ? 0 : (iy >= h ? h - 1 : iy);
    }
    r0 = hm + iy * w;
    if (u == PF_R(0.0) && v == PF_R(0.0)) return r0[ix]; /* axis azimuths land on nodes */
    r1 = hm + iy1 * w;
    return (r0[ix] * (PF_R(1.0) - u) + r0[ix1] * u) * (PF_R(1.0) - v) + (r1[ix] * (PF_R(1.0) - u) + r1[ix1] * u) * v;
}

/* tan of the horizon elevation of node (i, j) toward unit direction (dx, dy). */
PF_CPU_DEF pf_real pfi_horizon_tan(const pf_real *hm, int w, int h, int i, int j, pf_real dx, pf_real dy,
                                   pf_real spacing, int max_steps, int border, pf_real hmax)
{
    pf_real h0 = hm[(long long)j * w + i], best = -PF_REAL_MAX;
    int k;
    for (k = 1; k <= max_steps; ++k) {
        pf_real d = PF_R(k) * spacing, t;
        /* no height of the map can beat the best tangent from here on */
        if ((hmax - h0) / d <= best) break;
        t = (pfi_horizon_bilinear(hm, w, h, PF_R(i) + PF_R(k) * dx, PF_R(j) + PF_R(k) * dy, border) - h0) / d;
        if (t > best) best = t;
    }
    return best;
}

/* Checks shared by the builders; on PF_OK *hmax is the largest height. */
PF_CPU_DEF int pfi_horizon_check(const pf_real *heights, int w, int h, pf_real spacing, int n_azimuths,
                                 int max_steps, int border, int kind, int k, const pf_real *out,
                                 long long texels, pf_real *hmax)
{
    long long i, n;
    int c;
    if (!heights || !out || w < 1 || h < 1 || n_azimuths < 1 || max_steps < 1) return PF_ERR_ARG;
    if (!(spacing > PF_R(0.0) && spacing <= PF_REAL_MAX)) return PF_ERR_ARG;
    if (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP) return PF_ERR_ARG;
    if (kind != PF_HORIZON_ANGLES && kind != PF_HORIZON_MOMENTS && kind != PF_HORIZON_LEGENDRE) return PF_ERR_ARG;
    if (kind == PF_HORIZON_LEGENDRE && (k < 1 || k > PF_HORIZON_LEGENDRE_MAX)) return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || !pf_size_side_ok(n_azimuths) || !pf_size_side_ok(max_steps))
        return PF_ERR_SIZE;
    c = pf_horizon_channels(kind, n_azimuths, k);
    if (c < 1 || pf_size_mul(texels, c) < 0) return PF_ERR_SIZE;
    n = (long long)w * h;
    *hmax = -PF_REAL_MAX;
    for (i = 0; i < n; ++i) {
        pf_real v = heights[i];
        if (!(v >= -PF_REAL_MAX && v <= PF_REAL_MAX)) return PF_ERR_ARG; /* NaN, +-inf */
        if (v > *hmax) *hmax = v;
    }
    return PF_OK;
}

/* Writes level 0 (checked already). */
PF_CPU_DEF void pfi_horizon_fill(const pf_real *heights, int w, int h, pf_real spacing, int n_azimuths,
                                 int max_steps, int border, int kind, int k, pf_real hmax, pf_real *out)
{
    int c = pf_horizon_channels(kind, n_azimuths, k), i, j, a, q;
    pf_real kx = PF_R(1.0) / (PF_R(2.0) * spacing);
    for (j = 0; j < h; ++j) {
        long long yy[3], xx[3];
        pf_real cy[3], cx[3];
        pf_map_slope_stencil(j, h, border, kx, yy, cy);
        for (i = 0; i < w; ++i) {
            pf_real *o = out + ((long long)j * w + i) * c, sx, sy;
            const pf_real *col = heights + i;
            pf_map_slope_stencil(i, w, border, kx, xx, cx);
            sx = cx[0] * heights[(long long)j * w + xx[0]] + cx[1] * heights[(long long)j * w + xx[1]]
                 + cx[2] * heights[(long long)j * w + xx[2]];
            sy = cy[0] * col[yy[0] * w] + cy[1] * col[yy[1] * w] + cy[2] * col[yy[2] * w];
            for (a = 0; a < n_azimuths; ++a) {
                pf_real phi = PF_R(2.0) * PF_PI * PF_R(a) / PF_R(n_azimuths);
                pf_real dx = PF_COS(phi), dy = PF_SIN(phi), t, s;
                /* exact zeros on the axes, so axis samples land on nodes */
                if (4 * a == n_azimuths || 4 * a == 3 * n_azimuths) dx = PF_R(0.0);
                if (2 * a == n_azimuths || a == 0) dy = PF_R(0.0);
                /* the facet's own tangent plane hides what is below it (see THE CPU MARCH) */
                s = sx * dx + sy * dy;
                t = pfi_horizon_tan(heights, w, h, i, j, dx, dy, spacing, max_steps, border, hmax);
                t = PF_ATAN2(s > t ? s : t, PF_R(1.0));
                if (kind == PF_HORIZON_ANGLES) {
                    o[a] = t;
                } else if (kind == PF_HORIZON_MOMENTS) {
                    /* a slope that overflowed (a spacing tiny against the height differences)
                       is clamped, NaN (inf - inf) taken as 0, so that S T stays finite */
                    s = s == s ? pf_clamp(s, -PF_R(0.5) * PF_REAL_MAX, PF_R(0.5) * PF_REAL_MAX) : PF_R(0.0);
                    o[3 * a] = t;
                    o[3 * a + 1] = t * t;
                    o[3 * a + 2] = s * t;
                } else {
                    pf_real st = PF_SIN(t);
                    for (q = 0; q < k; ++q) o[k * a + q] = pf_horizon_legendre_coeff(q, st);
                }
            }
        }
    }
}

/* Level 0: the horizon map of a kind (PF_HORIZON_ANGLES, _MOMENTS, _LEGENDRE with k
   coefficients) of a w x h height map (heights in world units, row-major, square texels of
   `spacing` world units), n_azimuths azimuths, march bounded to max_steps texels, border
   PF_BORDER_WRAP or PF_BORDER_CLAMP. out: w h pf_horizon_channels(kind, n_azimuths, k)
   pf_reals. Errors: see ERRORS; nothing written. */
PF_CPU_DEF int pf_horizon_map(const pf_real *heights, int w, int h, pf_real spacing, int n_azimuths,
                              int max_steps, int border, int kind, int k, pf_real *out)
{
    pf_real hmax;
    int rc = pfi_horizon_check(heights, w, h, spacing, n_azimuths, max_steps, border, kind, k, out,
                               pf_size_mul(w < 1 ? 0 : w, h < 1 ? 0 : h), &hmax);
    if (rc != PF_OK) return rc;
    pfi_horizon_fill(heights, w, h, spacing, n_azimuths, max_steps, border, kind, k, hmax, out);
    return PF_OK;
}

/* The whole pyramid (pf_map.h layout): level 0 by pf_horizon_map, levels above by
   pf_mip_build (the HDF moments and Legendre coefficients are linear, so the box mean of a
   level is the filtered HDF). pyr: pf_mip_texel_count(w, h) pf_horizon_channels(...) pf_reals.
   PF_HORIZON_ANGLES is accepted (a plain mip-mapped horizon, the wrong filter the survey warns
   about, for comparisons). */
PF_CPU_DEF int pf_horizon_pyramid(const pf_real *heights, int w, int h, pf_real spacing, int n_azimuths,
                                  int max_steps, int border, int kind, int k, pf_real *pyr)
{
    pf_real hmax;
    long long texels = pf_mip_texel_count(w, h); /* 0 for a pyramid above PF_MAX_REALS */
    int rc = pfi_horizon_check(heights, w, h, spacing, n_azimuths, max_steps, border, kind, k, pyr,
                               texels > 0 ? texels : -1, &hmax);
    if (rc != PF_OK) return rc;
    pfi_horizon_fill(heights, w, h, spacing, n_azimuths, max_steps, border, kind, k, hmax, pyr);
    return pf_mip_build(pyr, w, h, pf_horizon_channels(kind, n_azimuths, k));
}

#endif /* !PF_GLSL */

#endif /* PF_HORIZON_H */

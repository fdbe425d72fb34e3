/* pf_specaa.h - specular antialiasing as engines ship it: NDF filtering from the screen-space
   derivatives of the shading normal (or of the half vector), composed with the footprint
   filtering of the other modules (LEADR's slope covariance, vMF lobes, plain GGX/Beckmann
   roughness), and a CPU baker of roughness mip chains from normal maps.

   IDEA. Two causes make a narrow specular lobe alias. (a) The GEOMETRY: the macro-normal turns
   inside a pixel on curved, distant or finely tessellated surfaces. Kaplanyan, Hill, Patney &
   Lefohn 2016 ("Filtering distributions of normals for shading antialiasing", HPG) read the
   turn from the screen-space derivatives of the half vector, build a Gaussian filtering kernel
   in the slope domain over the pixel footprint and convolve the NDF with it: for a Beckmann or
   GGX lobe, covariances add, so the roughness grows, alpha'^2 = alpha^2 + 2 Sigma. Tokuyoshi &
   Kaplanyan 2019 ("Improved geometric specular antialiasing", I3D) take the derivatives in the
   PROJECTED half-vector space (the tangent-plane components of the unit vector, no division by
   h.z: the slope-space form blows up at grazing half vectors and near edges, their Fig. 1:
   RMSE 13124 against 0.2188), clamp the kernel (kappa = 0.18), and for deferred shading use
   the derivatives of the normal in an isotropic form:
       k = min(2 sigma^2 (|dn/dx|^2 + |dn/dy|^2), kappa),   alpha'^2 = saturate(alpha^2 + k) (1)
   with sigma^2 = 1/(2 pi), the variance of the Gaussian pixel filter of unit peak and unit
   integral. |dn|^2 does not depend on the frame, so world-space dFdx(n) may be passed as is.
   sigma^2 = 1/(2 pi) with the factor 2 is conservative: a BOX pixel filter (a supersampled
   resolve averaging the pixel square) has the slope covariance (1) gives with sigma^2 = 1/24
   (PF_SPECAA_SIGMA2_BOX), 3.8x narrower. Engines ship (1) with other constants (their source,
   docs/specaa.md): Filament's normalFiltering sigma^2 = 0.15, kappa = 0.2^2 = 0.04 (the
   material's threshold 0.2 is squared when set); Unity HDRP's GeometricNormalFiltering
   sigma^2 = 0.1, kappa = 0.2^2 (Lit defaults); Godot's screen-space roughness limiter
   sigma^2 = 0.25, kappa = 0.18, added to the perceptual roughness squared, that is to alpha
   and not to alpha^2.
   Tokuyoshi & Kaplanyan 2021 ("Stable geometric specular antialiasing with projected-space NDF
   filtering", JCGT 10(2)) add the kernel in projected space instead of slope space: that
   space is bounded (|p| < 1), so a kernel as wide as the hemisphere saturates instead of
   growing alpha without bound. pf_specaa_alpha_projected does that sum here with a map
   between slope and projected variances of our own (below, "projected space"), measured
   against quadrature in tests/test_specaa.c.
   (a+b) BOTH AT ONCE. Inside one pixel the geometry's turn and the texture's slopes are not
   independent: a ray at offset o from the centre sees the slope -(a o_x + b o_y) + t(o) (a, b
   the normal's tangent-frame derivatives, t the texel's slope), so the pixel's covariance is
   the kernel's plus the texture's plus twice their cross-covariance, which a linear texture
   trend dm/dx, dm/dy across the footprint makes (4) below (pf_specaa_kernel_cross). A shader
   reads dm/dx, dm/dy as the derivatives of the fetched mean slope, or, better, from four reads
   of the moment pyramid, one per quadrant of the pixel (pf_specaa_slope_stats_quad), which also
   give the pixel's moments more sharply than one trilinear read at the footprint's major axis.
   (b) The TEXTURE: the normals of a normal map spread inside a mip texel. Engines bake a
   roughness (or a variance) per mip level from the length r of the averaged normal
   (Toksvig 2005; a vMF fit, kappa = (3r - r^3)/(1 - r^2), Banerjee et al. 2005). The baker
   here does not guess the spread from r: it averages the slope moments of the footprint up to
   the fourth order (pf_map.h's pyramid, exact for a box footprint) and adds the variance of
   the Gaussian with the footprint's peakedness:
       alpha'^2 = E[alpha_t^2] + 2 g v,   v = var rho,   var = (Var[s_x] + Var[s_y]) / 2,
       rho = 8 var^2 / E[|s - E s|^4]  (1 for Gaussian slopes), clamped to [0, 2]          (2)
   A Gaussian footprint keeps its variance; a heavy-tailed one (ridges, log-normal bumps, a flat
   ground with a few steep bowls) gets the narrower lobe that fits its peak, where the raw
   variance (rho = 1) over-widens and the engines' 1 - r under-widens Gaussian footprints. g is
   the one constant chosen by measurement (bench/specaa.c: the exact NDF of the footprint's
   texels, each texel's lobe shifted to its slope, against the baked single lobe); rho's form
   (the exponent 1 on the ratio) was compared there with the exponents 0 and 1/2.

   COMPOSITION. A kernel is a slope covariance; what it widens:
     LEADR     the footprint's slope covariance: var_x, var_y (and cov_xy) += the kernel's
               (pf_specaa_slope_stats; Dupuy et al. 2013 add the micro-BRDF's variance alike),
               and += the cross term (4) where the texture's mean-slope gradient is known
               (pf_specaa_slope_stats_cross, pf_specaa_slope_stats_quad);
     vMF       each lobe's tangent variance ~1/kappa grows by the kernel's per-axis variance:
               kappa' = kappa / (1 + kappa k/2) (pf_vmf.h's small-angle rule);
     GGX, Beckmann roughness  alpha'^2 = alpha^2 + k (1), or the projected-space sum.
   The kernel's alpha^2 increment k is twice its per-axis slope variance (k/2 per axis).

   USAGE (shader)
     pf_real k = pf_specaa_kernel_normal(dFdx(n), dFdy(n), PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA);
       (PF_SPECAA_SIGMA2, the papers' conservative constant, for a Gaussian-filtered target;
       pf_specaa_kernel_aniso with the tangent-frame derivatives on surfaces that curve along
       one axis more than the other)
     pf_real a = pf_specaa_alpha(alpha, k);                       -- GGX/Beckmann, (1)
     pf_slope_stats s2 = pf_specaa_slope_stats(s, k);             -- LEADR
     pf_real I = pf_specaa_leadr_specular(wo, wi, s, f0, dndx, dndy);  -- both in one call
     -- plain curved surfaces, the most accurate form (tangent-frame dndx, dndy and wo):
     pf_real I = pf_specaa_leadr_specular_curved(wo, wi, s, f0, dndx, dndy);  -- + mean shift (6)
     -- or, with any kernel and texture part: s = pf_specaa_slope_stats_shift(s,
     --     pf_specaa_mean_shift(wo, k)), or pf_specaa_mean_shift_surface(dFdx(p), dFdy(p), ...)
     -- normal-mapped curved surfaces, the most accurate form (tangent-frame dndx, dndy; the
     -- four reads at uv -+ duvdx/4 -+ duvdy/4 with gradients duvdx/2, duvdy/2):
     pf_slope_stats s = pf_specaa_slope_stats_quad(m00, m10, m01, m11, alpha * alpha / 2,
                                                   dndx, dndy, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA);
     l.kappa = pf_specaa_vmf_kappa(l.kappa, k);                   -- each vMF lobe
   USAGE (CPU baker)
     pf_specaa_bake_desc d = { normals, NULL, w, h, PF_R(0.1), PF_SPECAA_NDF_GGX, PF_R(0.0) };
     scratch: caller-owned, pf_specaa_bake_scratch_reals(w, h) reals
     alpha:   caller-owned, pf_mip_texel_count(w, h) reals (the whole mip chain)
     if (pf_specaa_bake(&d, scratch, alpha, NULL) != PF_OK) ...   -- pf_map.h's layout

   FUNCTIONS (shader subset)
     kernels     pf_specaa_kernel_normal (1), pf_specaa_kernel_halfvector (Kaplanyan et al.
                 2016's slope-space form), pf_specaa_kernel_aniso (the full covariance,
                 pf_specaa_kernel struct), pf_specaa_kernel_make, pf_specaa_kernel_trace
     roughness   pf_specaa_alpha (1), pf_specaa_alpha_projected (projected-space sum),
                 pf_specaa_alpha_from_variance (2) with a stored v, pf_specaa_projected_variance,
                 pf_specaa_slope_variance_from_projected
     cross term  pf_specaa_kernel_cross (4), pf_specaa_slope_stats_cross,
                 pf_specaa_slope_stats_quad (four quadrant reads: moments, gradient, kernel, (4))
     mean shift  pf_specaa_mean_shift (6), pf_specaa_mean_shift_surface (5),
                 pf_specaa_slope_stats_shift
     compose     pf_specaa_slope_stats, pf_specaa_slope_stats_aniso, pf_specaa_vmf_kappa,
                 pf_specaa_vmf_lobe, pf_specaa_leadr_specular, pf_specaa_leadr_specular_curved
   FUNCTIONS (CPU only, PF_CPU_DEF, compiled out under PF_GLSL)
     pf_specaa_bake_scratch_reals, pf_specaa_bake (2)

   CONVENTIONS
     Derivatives are screen-space derivatives per pixel (dFdx, dFdy) of the UNIT shading
     normal or half vector. pf_specaa_kernel_normal uses |d|^2 (any frame);
     pf_specaa_kernel_aniso and pf_specaa_kernel_halfvector need them in the tangent frame
     (x, y along the tangent and bitangent of the slopes the kernel is added to).
     Degenerate derivatives give a finite kernel: zero -> 0 (no widening); huge or +inf ->
     the clamp kappa; NaN (a helper lane's or a silhouette's garbage) -> the clamp kappa as
     well (NaN means "unknown", and a wide lobe on one pixel does not sparkle). sigma2 and
     kappa are >= 0 and finite. Roughnesses: alpha'^2 is clamped to [0, 1] as the engines
     saturate it (pf_specaa_alpha*); a NaN alpha gives 0. vMF: kappa as pf_vmf_kappa_clamp.
     The NaN rule holds in C and CUDA; GLSL leaves min(NaN, x) to the implementation (the main
     vendors return x), see pf_core.h.

   PROJECTED SPACE. The projected coordinate of a slope s is p = s / sqrt(1 + |s|^2) (the
   tangent-plane part of the unit normal). Over the projected-area measure a fully rough
   surface is uniform on the unit disk, per-axis variance 1/4; a narrow lobe has the same
   variance v in both spaces. The map used here joins the two ends:
       v_p = v_s / (1 + 4 v_s),   v_s = v_p / (1 - 4 v_p)                               (3)
   alpha'^2 = 2 v_s(v_p(alpha^2/2) + k/2), v_p capped below 1/4 (alpha' <= 1 after the clamp).
   Against the exact per-axis projected variance of a Beckmann lobe (quadrature), (3) is
   within 20% for alpha in [0.01, 1] (tests/test_specaa.c measures it).

   ACCURACY AND COST (measured; docs/specaa.md has the tables). The kernels are a few flops;
   the geometry kernel adds 12 SPIR-V ops to pf_leadr_specular (116 -> 128) (after spirv-opt -O,
   bench/gpu/count.sh: pf_specaa_leadr_specular against pf_leadr_specular); the anisotropic
   kernel in its place adds 24 (pf_specaa_kernel_aniso, 25 ops alone, with its handling of
   NaN and inf), above the 15 the library allows the default, so the default stays isotropic.
   pf_specaa_kernel_cross is 13 ops, pf_specaa_slope_stats_cross 33, pf_specaa_slope_stats_quad
   118 (the four reads not counted); the anisotropic kernel with the cross term adds 64 to
   pf_leadr_specular: an opt-in for normal-mapped curved surfaces, not the default. The mean
   shift: pf_specaa_mean_shift 16 ops, pf_specaa_mean_shift_surface 47;
   pf_specaa_leadr_specular_curved (anisotropic kernel and (6)) adds 42 to pf_leadr_specular
   (116 -> 158): an opt-in too. The anisotropic kernel halved is the slope covariance of a
   sphere's normals over the Gaussian pixel filter within 0.7% of its trace (spheres 20-200 px
   across). Baker (2), against the exact NDF of each mip texel's footprint on the seven kinds of
   the microsurface corpus (bench/specaa.c): more accurate than every engine formula (Toksvig,
   Filament, HDRP, Godot) on all seven kinds, for GGX and for Beckmann. On curved scenes
   (bench/specaa_scenes.h: a sphere and a cylinder 16 and 40 px across, plain and
   normal-mapped, alpha 0.03 and 0.1, against a box-filtered supersampled reference and the
   exact-footprint oracle over a sub-pixel camera path): without a map, LEADR with the
   anisotropic kernel at PF_SPECAA_SIGMA2_BOX is within 1.0-1.8x the oracle's error, with the
   mean shift (6) (pf_specaa_leadr_specular_curved) within 0.97-1.14x, its flicker within
   1.03x of the reference's; the isotropic kernel is as good on the
   sphere and over-blurs the cylinder's straight axis (2.6-12x); the papers' constant
   over-blurs (2-77x). With a normal map, one isotropic trilinear read of the
   pyramid and no cross term are 1.0-8.8x the oracle's error; pf_specaa_slope_stats_quad is
   within 0.99-1.18x, its flicker 1.00-1.69x the reference's (the oracle's own: 1.02-1.56x).
   docs/specaa.md has the table.

   SOURCES
     Kaplanyan, Hill, Patney, Lefohn 2016, HPG (slope-domain kernel from half-vector
     derivatives); Tokuyoshi & Kaplanyan 2019, I3D (projected-space derivatives, the clamp
     kappa = 0.18, sigma^2 = 1/(2 pi), the isotropic deferred form (1)); Tokuyoshi &
     Kaplanyan 2021, JCGT 10(2) (the sum in projected space); Toksvig 2005; Banerjee et al.
     2005 (vMF kappa from r); Dupuy et al. 2013 (LEADR: covariances add). */
#ifndef PF_SPECAA_H
#define PF_SPECAA_H

#ifndef PF_GLSL
#  include "pf_core.h"
#  include "pf_moments.h"
#  include "pf_beckmann.h"
#  include "pf_vmf.h"
#  include "pf_map.h"
#endif

/* Variance of the Gaussian pixel filter, 1/(2 pi) (unit peak and unit integral; Tokuyoshi &
   Kaplanyan 2019). Filament uses 0.15. */
#ifndef PF_SPECAA_SIGMA2
#  define PF_SPECAA_SIGMA2 PF_R(0.15915494309189535)
#endif
/* Variance constant of the BOX pixel filter (a supersampled reference that averages the pixel
   square, MSAA/SSAA resolves): a normal varying linearly across the unit pixel square has the
   slope covariance (1/12)(a a^T + b b^T) (the box's per-axis variance 1/12), which
   pf_specaa_kernel_aniso gives with sigma2 = 1/24 (its factor 2 cancels: no conservative
   widening) and pf_specaa_kernel_normal as its trace. tests/test_specaa.c checks it by
   quadrature over the pixel square. */
#define PF_SPECAA_SIGMA2_BOX PF_R(0.041666666666666667)
/* The sigma2 of pf_specaa_leadr_specular: the box filter's (a supersampled, box-filtered
   target). On the curved scenes of bench/specaa_scenes.h it is 1.7-47x closer to the
   exact-footprint oracle than the papers' 1/(2 pi) with the factor 2 without a normal map
   (that one over-blurs), and 0.86-1.19x as close with one (where the pyramid read, not the
   kernel, sets the error); same cost. Define it as PF_SPECAA_SIGMA2 before including this
   header for the papers' kernel. */
#ifndef PF_SPECAA_LEADR_SIGMA2
#  define PF_SPECAA_LEADR_SIGMA2 PF_SPECAA_SIGMA2_BOX
#endif
/* Largest alpha^2 the kernel adds (Tokuyoshi & Kaplanyan 2019's kappa; Filament and HDRP: 0.2^2 = 0.04). */
#ifndef PF_SPECAA_KAPPA
#  define PF_SPECAA_KAPPA PF_R(0.18)
#endif

/* A slope-space kernel: its per-axis covariance (var_x, var_y, cov_xy). */
PF_STRUCT_BEGIN(pf_specaa_kernel)
    pf_real var_x;
    pf_real var_y;
    pf_real cov_xy;
PF_STRUCT_END(pf_specaa_kernel)

PF_DEF pf_specaa_kernel pf_specaa_kernel_make(pf_real var_x, pf_real var_y, pf_real cov_xy)
{
    pf_specaa_kernel k;
    k.var_x = var_x;
    k.var_y = var_y;
    k.cov_xy = cov_xy;
    return k;
}

/* (1): the alpha^2 increment min(2 sigma2 (|dndx|^2 + |dndy|^2), kappa) of Tokuyoshi &
   Kaplanyan 2019 (isotropic, deferred form; the same with the projected derivatives of the
   half vector is their forward form). Any frame. Zero derivatives -> 0; huge, inf or NaN ->
   kappa (the comparison is false for NaN). */
PF_DEF pf_real pf_specaa_kernel_normal(pf_vec3 dndx, pf_vec3 dndy, pf_real sigma2, pf_real kappa)
{
    pf_real t = PF_R(2.0) * sigma2 * (pf_vec3_dot(dndx, dndx) + pf_vec3_dot(dndy, dndy));
    return t < kappa ? t : kappa;
}

/* Kaplanyan et al. 2016's form: the same increment from the derivatives of the SLOPE of the
   half vector, s = -h.xy/h.z, d s = -(dh.xy h.z - h.xy dh.z)/h.z^2 (tangent frame, unit h);
   h.z floored at 1e-4 (a half vector on the horizon: huge slopes, then the clamp). Grows as
   1/h.z^2 at grazing half vectors, the error Tokuyoshi & Kaplanyan 2019 remove. */
PF_DEF pf_real pf_specaa_kernel_halfvector(pf_vec3 h, pf_vec3 dhdx, pf_vec3 dhdy, pf_real sigma2,
                                           pf_real kappa)
{
    pf_real z = pf_max(h.z, PF_R(1.0e-4)), iz2 = PF_R(1.0) / (z * z);
    pf_real ax = (dhdx.x * z - h.x * dhdx.z) * iz2, ay = (dhdx.y * z - h.y * dhdx.z) * iz2;
    pf_real bx = (dhdy.x * z - h.x * dhdy.z) * iz2, by = (dhdy.y * z - h.y * dhdy.z) * iz2;
    pf_real t = PF_R(2.0) * sigma2 * (ax * ax + ay * ay + bx * bx + by * by);
    return t < kappa ? t : kappa;
}

/* The anisotropic kernel Sigma = 2 sigma2 (a a^T + b b^T), a = dndx.xy, b = dndy.xy (tangent
   frame, projected derivatives). sigma2 (a a^T + b b^T) is the slope covariance of a normal
   varying linearly across a Gaussian pixel filter of variance sigma2 (tests/test_specaa.c
   checks it by quadrature); the factor 2 is Tokuyoshi & Kaplanyan 2019's conservative
   bandwidth, which (1) has too: trace(Sigma) is (1)'s increment k, and (1) is this kernel made
   isotropic (k/2 per axis). Scaled down as a whole so that trace(Sigma) <= kappa. Huge, inf or
   NaN derivatives: kappa/2 on each axis, no covariance. */
PF_DEF pf_specaa_kernel pf_specaa_kernel_aniso(pf_vec3 dndx, pf_vec3 dndy, pf_real sigma2, pf_real kappa)
{
    pf_real s = PF_R(2.0) * sigma2;
    pf_real xx = s * (dndx.x * dndx.x + dndy.x * dndy.x);
    pf_real yy = s * (dndx.y * dndx.y + dndy.y * dndy.y);
    pf_real xy = s * (dndx.x * dndx.y + dndy.x * dndy.y);
    pf_real t = xx + yy, f;
    if (!(t <= PF_REAL_MAX)) return pf_specaa_kernel_make(PF_R(0.5) * kappa, PF_R(0.5) * kappa, PF_R(0.0));
    f = t > kappa ? kappa / t : PF_R(1.0);
    return pf_specaa_kernel_make(f * xx, f * yy, f * xy);
}

/* The alpha^2 increment of an anisotropic kernel: its trace (2 x the mean per-axis variance). */
PF_DEF pf_real pf_specaa_kernel_trace(pf_specaa_kernel k)
{
    return k.var_x + k.var_y;
}

/* (1): sqrt(saturate(alpha^2 + k)) for GGX alpha or Beckmann m; NaN alpha -> 0. */
PF_DEF pf_real pf_specaa_alpha(pf_real alpha, pf_real k)
{
    return PF_SQRT(pf_clamp_nan_lo(alpha * alpha + k, PF_R(0.0), PF_R(1.0)));
}

/* (3): per-axis projected variance of a lobe of per-axis slope variance v_s >= 0. */
PF_DEF pf_real pf_specaa_projected_variance(pf_real v_s)
{
    pf_real v = pf_max(v_s, PF_R(0.0));
    return v / (PF_R(1.0) + PF_R(4.0) * v);
}

/* (3) inverted: v_s = v_p / (1 - 4 v_p), v_p capped at 0.2499 (v_s <= 625). */
PF_DEF pf_real pf_specaa_slope_variance_from_projected(pf_real v_p)
{
    pf_real v = pf_clamp_nan_lo(v_p, PF_R(0.0), PF_R(0.2499));
    return v / (PF_R(1.0) - PF_R(4.0) * v);
}

/* The kernel added in projected space: alpha'^2 = 2 v_s(v_p(alpha^2/2) + k/2), clamped to
   [0, 1]. Equals (1) to first order in k and alpha^2; a kernel as wide as the hemisphere
   saturates at alpha' = 1 without the clamp kappa (pass kappa = +inf to
   pf_specaa_kernel_normal to rely on it). */
PF_DEF pf_real pf_specaa_alpha_projected(pf_real alpha, pf_real k)
{
    pf_real vp = pf_specaa_projected_variance(PF_R(0.5) * alpha * alpha) + PF_R(0.5) * pf_max(k, PF_R(0.0));
    return PF_SQRT(pf_clamp_nan_lo(PF_R(2.0) * pf_specaa_slope_variance_from_projected(vp), PF_R(0.0), PF_R(1.0)));
}

/* Gains g of (2): the best on a 0.1 grid of the mean error over the microsurface corpus
   (bench/specaa.c, docs/specaa.md "gain"): 0.9 for both (1.0 is within 0.2% of it). */
#ifndef PF_SPECAA_GAIN_GGX
#  define PF_SPECAA_GAIN_GGX PF_R(0.9)
#endif
#ifndef PF_SPECAA_GAIN_BECKMANN
#  define PF_SPECAA_GAIN_BECKMANN PF_R(0.9)
#endif

/* (2) in the shader: the roughness of a texel from a per-axis slope variance stored beside a
   two-channel normal map (pf_specaa_bake's variance_out) and the material's alpha:
   sqrt(alpha^2 + 2 gain var), var < 0 or NaN read as 0. Not clamped (Beckmann m may pass 1). */
PF_DEF pf_real pf_specaa_alpha_from_variance(pf_real alpha, pf_real var, pf_real gain)
{
    return PF_SQRT(alpha * alpha + PF_R(2.0) * gain * pf_max(var, PF_R(0.0)));
}

/* LEADR: the footprint's slope statistics widened by an isotropic kernel increment k (k/2 on
   each variance). */
PF_DEF pf_slope_stats pf_specaa_slope_stats(pf_slope_stats s, pf_real k)
{
    pf_real h = PF_R(0.5) * k;
    return pf_slope_stats_make(s.mean_x, s.mean_y, s.var_x + h, s.var_y + h, s.cov_xy);
}

/* LEADR: the footprint's slope covariance plus an anisotropic kernel's (covariances add). */
PF_DEF pf_slope_stats pf_specaa_slope_stats_aniso(pf_slope_stats s, pf_specaa_kernel k)
{
    return pf_slope_stats_make(s.mean_x, s.mean_y, s.var_x + k.var_x, s.var_y + k.var_y,
                               s.cov_xy + k.cov_xy);
}

/* THE MEAN SHIFT. On a curved surface the pixel's mean slope is not the centre's slope: a ray
   at offset o from the pixel centre meets the surface at a depth that is quadratic in o (the
   surface curves away from the view), so the footprint on the surface is not centred on the
   centre's point: it is displaced along the view's tangential part w_t, and the mean normal
   with it. To second order in o, for a pixel filter of per-axis variance 2 sigma2 and an
   orthographic view direction w (wo in the tangent frame: n = +z), the tangent-frame shift
   of the mean slope is
       d = sigma2 wo.z II ((wo.dpdx) dndx.xy + (wo.dpdy) dndy.xy) / p^2,                   (5)
       II = dpdx.dndx + dpdy.dndy,   p^2 = (|dpdx|^2 - (wo.dpdx)^2 + |dpdy|^2 - (wo.dpdy)^2)/2
   (dpdx, dpdy the screen derivatives of the surface position, dndx, dndy of the unit normal,
   all in the tangent frame; p the pixel's size in the position's units). Derivation: the
   depth's second-order term is t2(o) = -(dp o).(dn o) / (2 w.n) (the second fundamental form
   of the first-order offset), its mean over the filter -sigma2 II / (w.n); the footprint's
   centroid moves by that along w, whose tangential part the shape operator turns into
   (w.n)^2 ((w.dpdx) dndx + (w.dpdy) dndy) / p^2 of normal. The renormalised mean of unit
   normals spread SYMMETRICALLY around the centre's normal points along it (the mean only
   shrinks, by 1 - tr/2): the shift comes from the foreshortening alone, not from the
   half-vector map or the clamp. (5) is exact to second order for surfaces whose normal is an
   affine function of the position (spheres, cylinders, planes), and leaves out the change of
   curvature across the pixel (third-order shape) and, under perspective, the turn of the view
   ray across the pixel (relative size: the object's extent over its distance).
   On a sphere (umbilic: dn = dp/R) (5) reduces to what needs no position derivatives,
       d = (k/2) wo.xy / wo.z,   k = 2 sigma2 (|dndx|^2 + |dndy|^2),                        (6)
   k the kernel's alpha^2 increment (1): the pixel's mean normal leans toward the silhouette by
   half the kernel times the view's slope. (6) is (5) on cylinders too when the view's tangential
   part is across the axis; otherwise (5). A 2x2 quad's first differences cannot give the
   second differences the shift is made of; (5) and (6) get them from the geometry instead.
   On the plain curved scenes of bench/specaa_scenes.h at alpha 0.1, the box kernel with (6) is
   1.04-1.14x the oracle's error where the kernel alone is 1.26-1.82x; given the oracle's exact
   mean instead, 1.00-1.07x: the kernel's covariance holds there, and the mean is what (5)
   and (6) add (docs/specaa.md). */

/* Largest |component| of a mean shift (5)/(6): sqrt(PF_SPECAA_KAPPA/2), the per-axis deviation
   of the clamped kernel; a shift is clamped to it componentwise (near the silhouette wo.z -> 0
   and (6) grows without bound). */
#ifndef PF_SPECAA_SHIFT_MAX
#  define PF_SPECAA_SHIFT_MAX PF_R(0.3)
#endif

/* (6): the mean-slope shift of an umbilic surface from the kernel increment k (the trace of
   pf_specaa_kernel_aniso or pf_specaa_kernel_normal, same sigma2) and the view direction wo in
   the tangent frame. wo.z floored at 1e-4; each component clamped to +-PF_SPECAA_SHIFT_MAX;
   a NaN or infinite k or wo gives 0 on the component it reaches. */
PF_DEF pf_vec2 pf_specaa_mean_shift(pf_vec3 wo, pf_real k)
{
    pf_real r = PF_R(0.5) * k / pf_max(wo.z, PF_R(1.0e-4));
    pf_real dx = r * wo.x, dy = r * wo.y;
    pf_real m = PF_SPECAA_SHIFT_MAX;
    return pf_vec2_make(dx - dx == PF_R(0.0) ? pf_clamp(dx, -m, m) : PF_R(0.0),
                        dy - dy == PF_R(0.0) ? pf_clamp(dy, -m, m) : PF_R(0.0));
}

/* (5): the mean-slope shift from the screen derivatives of the position (dpdx, dpdy) and of the
   unit normal (dndx, dndy), all in the tangent frame, the view direction wo (tangent frame) and
   the pixel filter's sigma2 (PF_SPECAA_SIGMA2_BOX for a box-filtered target). Each component
   clamped to +-PF_SPECAA_SHIFT_MAX; NaN, inf or a zero pixel size (p^2 = 0) give 0. */
PF_DEF pf_vec2 pf_specaa_mean_shift_surface(pf_vec3 dpdx, pf_vec3 dpdy, pf_vec3 dndx, pf_vec3 dndy, pf_vec3 wo,
                                            pf_real sigma2)
{
    pf_real wx = pf_vec3_dot(wo, dpdx), wy = pf_vec3_dot(wo, dpdy);
    pf_real p2 = PF_R(0.5) * (pf_vec3_dot(dpdx, dpdx) - wx * wx + pf_vec3_dot(dpdy, dpdy) - wy * wy);
    pf_real c = sigma2 * wo.z * (pf_vec3_dot(dpdx, dndx) + pf_vec3_dot(dpdy, dndy));
    pf_real m = PF_SPECAA_SHIFT_MAX, dx, dy;
    c = p2 > PF_R(0.0) ? c / p2 : PF_R(0.0);
    dx = c * (wx * dndx.x + wy * dndy.x);
    dy = c * (wx * dndx.y + wy * dndy.y);
    return pf_vec2_make(dx - dx == PF_R(0.0) ? pf_clamp(dx, -m, m) : PF_R(0.0),
                        dy - dy == PF_R(0.0) ? pf_clamp(dy, -m, m) : PF_R(0.0));
}

/* The footprint's slope statistics with the mean moved by d (pf_specaa_mean_shift*). */
PF_DEF pf_slope_stats pf_specaa_slope_stats_shift(pf_slope_stats s, pf_vec2 d)
{
    return pf_slope_stats_make(s.mean_x + d.x, s.mean_y + d.y, s.var_x, s.var_y, s.cov_xy);
}

/* The cross term of the geometry's turn and the texture's slopes inside the pixel. A ray at the
   offset o from the pixel centre (pixels) sees, in the centre's tangent frame, the slope
       q(o) = -(a o_x + b o_y) + t(o),   a = dndx.xy, b = dndy.xy (tangent frame, as
   pf_specaa_kernel_aniso), t the texture's slope at the ray's texel (to first order in the
   turn: the texel's slope rotated with its frame is second order). With t(o) = m + dm/dx o_x +
   dm/dy o_y + residual (m the footprint's mean slope), a pixel filter of per-axis variance
   2 sigma2 and no offset-residual correlation:
       Cov q = Cov(-(a o_x + b o_y)) + Cov t + C,
       C_ij = -2 sigma2 (a_i dm_j/dx + b_i dm_j/dy + a_j dm_i/dx + b_j dm_i/dy)              (4)
   the first term pf_specaa_kernel_aniso's kernel (2 sigma2 (a a^T + b b^T)), the second the
   texture's (LEADR's footprint moments). In a shader dm/dx, dm/dy are dFdx, dFdy of the
   fetched mean slope (pf_slope_moments' ex, ey, or the stats' mean_x, mean_y). (4) is exact
   for a box filter (sigma2 = PF_SPECAA_SIGMA2_BOX) and linear fields (tests/test_specaa.c by
   brute force). Unlike the kernel it may be negative (a texture that leans against the curve
   flattens the pixel's normals); pf_specaa_slope_stats_cross keeps the sum a covariance. NaN
   or inf derivatives give NaN or inf here; pf_specaa_slope_stats_cross drops such a term. */
PF_DEF pf_specaa_kernel pf_specaa_kernel_cross(pf_vec3 dndx, pf_vec3 dndy, pf_vec2 dmdx, pf_vec2 dmdy,
                                               pf_real sigma2)
{
    pf_real s = PF_R(-2.0) * sigma2;
    pf_real xx = dndx.x * dmdx.x + dndy.x * dmdy.x, yy = dndx.y * dmdx.y + dndy.y * dmdy.y;
    pf_real xy = dndx.x * dmdx.y + dndy.x * dmdy.y + dndx.y * dmdx.x + dndy.y * dmdy.x;
    return pf_specaa_kernel_make(PF_R(2.0) * s * xx, PF_R(2.0) * s * yy, s * xy);
}

/* LEADR with the geometry kernel k (pf_specaa_kernel_aniso) and the cross term c
   (pf_specaa_kernel_cross, same sigma2): var += k.var + c.var, cov += k.cov + c.cov. Each
   diagonal cross term is clamped to |c| <= 2 sqrt(k.var s.var) (Cauchy-Schwarz: the variance of
   a sum of two parts of variances k.var and s.var), so the variances stay >= 0; a NaN or
   infinite cross term reads as 0 on its axis (NaN derivatives: the kernel alone). The summed
   covariance is clamped to |cov| <= sqrt(var_x var_y), so the matrix stays positive
   semi-definite: unclamped, a silhouette quad's difference of reads (a helper lane's texel far
   from the pixel's) gave a negative determinant, which pf_leadr_specular's floor turned into a
   peak of 1e16 (bench/frame's curved scenes). */
PF_DEF pf_slope_stats pf_specaa_slope_stats_cross(pf_slope_stats s, pf_specaa_kernel k, pf_specaa_kernel c)
{
    pf_real bx = PF_R(2.0) * PF_SQRT(pf_max(k.var_x, PF_R(0.0)) * pf_max(s.var_x, PF_R(0.0)));
    pf_real by = PF_R(2.0) * PF_SQRT(pf_max(k.var_y, PF_R(0.0)) * pf_max(s.var_y, PF_R(0.0)));
    pf_real cx = c.var_x - c.var_x == PF_R(0.0) ? pf_clamp_nan_lo(c.var_x, -bx, bx) : PF_R(0.0);
    pf_real cy = c.var_y - c.var_y == PF_R(0.0) ? pf_clamp_nan_lo(c.var_y, -by, by) : PF_R(0.0);
    pf_real cxy = c.cov_xy - c.cov_xy == PF_R(0.0) ? c.cov_xy : PF_R(0.0);
    /* (sqrt s - sqrt k)^2 >= 0 at the clamp, but its rounding can be -1e-10: floored at 0 */
    pf_real vx = pf_max(s.var_x + k.var_x + cx, PF_R(0.0)), vy = pf_max(s.var_y + k.var_y + cy, PF_R(0.0));
    pf_real bxy = PF_SQRT(vx * vy);
    return pf_slope_stats_make(s.mean_x, s.mean_y, vx, vy, pf_clamp_nan_lo(s.cov_xy + k.cov_xy + cxy, -bxy, bxy));
}

/* The pixel's slope statistics from four reads of the moment pyramid, one per quadrant of the
   pixel (m00: -x -y, m10: +x -y, m01: -x +y, m11: +x +y; each read at the quadrant's centre,
   the pixel centre -+ 1/4 of d(uv)/dx and d(uv)/dy, with half the pixel's footprint, e.g.
   textureGrad(pyramid, uv -+ 0.25 duvdx -+ 0.25 duvdy, 0.5 duvdx, 0.5 duvdy) on anisotropic
   hardware): their mean is the pixel's moments, their differences the texture's mean-slope
   gradient (dm/dx = (m10 + m11 - m00 - m01)/2 / (1/2 px), exact for a linear texture), composed
   with the geometry kernel (pf_specaa_kernel_aniso, tangent-frame dndx, dndy) and the cross
   term (4) through pf_specaa_slope_stats_cross; base_var as pf_slope_moments_stats. On the
   curved normal-mapped scenes of bench/specaa_scenes.h this is within 1.2x of the
   exact-footprint oracle's error where one isotropic trilinear read and no cross term are
   2-9x (docs/specaa.md). */
PF_DEF pf_slope_stats pf_specaa_slope_stats_quad(pf_slope_moments m00, pf_slope_moments m10, pf_slope_moments m01,
                                                 pf_slope_moments m11, pf_real base_var, pf_vec3 dndx, pf_vec3 dndy,
                                                 pf_real sigma2, pf_real kappa)
{
    pf_slope_moments m = pf_slope_moments_scale(pf_slope_moments_add(pf_slope_moments_add(m00, m10),
                                                                     pf_slope_moments_add(m01, m11)), PF_R(0.25));
    pf_vec2 dmdx = pf_vec2_make(m10.ex + m11.ex - m00.ex - m01.ex, m10.ey + m11.ey - m00.ey - m01.ey);
    pf_vec2 dmdy = pf_vec2_make(m01.ex + m11.ex - m00.ex - m10.ex, m01.ey + m11.ey - m00.ey - m10.ey);
    return pf_specaa_slope_stats_cross(pf_slope_moments_stats(m, base_var), pf_specaa_kernel_aniso(dndx, dndy, sigma2, kappa),
                                       pf_specaa_kernel_cross(dndx, dndy, dmdx, dmdy, sigma2));
}

/* pf_leadr_specular with the geometry kernel (1) of the normal's derivatives (any frame) added
   to the footprint's slope statistics, at PF_SPECAA_LEADR_SIGMA2 (the box filter's 1/24 unless
   defined otherwise) and PF_SPECAA_KAPPA. */
PF_DEF pf_real pf_specaa_leadr_specular(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real f0,
                                        pf_vec3 dndx, pf_vec3 dndy)
{
    pf_real k = pf_specaa_kernel_normal(dndx, dndy, PF_SPECAA_LEADR_SIGMA2, PF_SPECAA_KAPPA);
    return pf_leadr_specular(wo, wi, pf_specaa_slope_stats(s, k), f0);
}

/* pf_leadr_specular on a plain curved surface, the most accurate form without position
   derivatives: the anisotropic kernel of the TANGENT-FRAME derivatives of the normal
   (pf_specaa_kernel_aniso) and the mean shift (6) of its trace, at PF_SPECAA_LEADR_SIGMA2 and
   PF_SPECAA_KAPPA. On the plain scenes of bench/specaa_scenes.h 0.97-1.14x the oracle's error
   where pf_specaa_leadr_specular is 0.97-11.7x (docs/specaa.md); more ops than the 15 the
   default may add (bench/gpu/count.sh), so an opt-in. Degenerate derivatives as the kernel's
   (NaN: kappa/2 per axis, and the shift of that trace). */
PF_DEF pf_real pf_specaa_leadr_specular_curved(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real f0,
                                               pf_vec3 dndx, pf_vec3 dndy)
{
    pf_specaa_kernel k = pf_specaa_kernel_aniso(dndx, dndy, PF_SPECAA_LEADR_SIGMA2, PF_SPECAA_KAPPA);
    return pf_leadr_specular(wo, wi, pf_specaa_slope_stats_shift(pf_specaa_slope_stats_aniso(s, k),
                             pf_specaa_mean_shift(wo, pf_specaa_kernel_trace(k))), f0);
}

/* vMF: kappa' = kappa / (1 + kappa k/2), the lobe's tangent variance ~1/kappa plus the
   kernel's per-axis variance k/2 (pf_vmf_convolve_kappa's rule); clamped as
   pf_vmf_kappa_clamp. k < 0 or NaN reads as 0. */
PF_DEF pf_real pf_specaa_vmf_kappa(pf_real kappa, pf_real k)
{
    pf_real a = pf_vmf_kappa_clamp(kappa);
    return pf_vmf_kappa_clamp(a / (PF_R(1.0) + a * PF_R(0.5) * pf_max(k, PF_R(0.0))));
}

/* A vMF lobe widened by the kernel increment k (pf_specaa_vmf_kappa). */
PF_DEF pf_vmf_lobe pf_specaa_vmf_lobe(pf_vmf_lobe l, pf_real k)
{
    pf_vmf_lobe o = l;
    o.kappa = pf_specaa_vmf_kappa(l.kappa, k);
    return o;
}

#ifndef PF_GLSL
/* ---------------------------------------------------------------- CPU: the roughness baker */
#define PF_SPECAA_NDF_GGX 0
#define PF_SPECAA_NDF_BECKMANN 1
/* Channels of the baker's scratch pyramid: E[sx], E[sy], E[sx^2], E[sy^2], E[sx sy],
   E[|s|^2 sx], E[|s|^2 sy], E[|s|^4], E[alpha^2]. */
#define PF_SPECAA_BAKE_CHANNELS 9
/* Largest alpha the baker reads (larger ones, infinities too, are clamped here) and largest
   gain it accepts: with slopes up to 100 every output then stays finite. */
#define PF_SPECAA_MAX_ALPHA PF_R(1.0e3)
#define PF_SPECAA_MAX_GAIN PF_R(1.0e6)
/* Smallest n.z the baker reads (slopes up to 100: a normal within 0.6 degrees of the
   horizon); normals below it are clamped there. */
#ifndef PF_SPECAA_MIN_NZ
#  define PF_SPECAA_MIN_NZ PF_R(0.01)
#endif

/* What pf_specaa_bake reads; zero means the default where one is stated. */
typedef struct pf_specaa_bake_desc {
    const pf_real *normals;   /* width x height normals, 3 interleaved pf_reals, tangent space
                                 (+z out of the surface); need not be unit. A zero-length or
                                 NaN normal reads as +z */
    const pf_real *roughness; /* optional width x height alphas (GGX alpha or Beckmann m);
                                 NULL: `alpha` everywhere. NaN or negative reads as 0, above
                                 PF_SPECAA_MAX_ALPHA as PF_SPECAA_MAX_ALPHA */
    int width, height;
    pf_real alpha;            /* base roughness where roughness is NULL (read as above) */
    int ndf;                  /* PF_SPECAA_NDF_GGX (0) or PF_SPECAA_NDF_BECKMANN */
    pf_real gain;             /* g of (2), <= PF_SPECAA_MAX_GAIN; 0: PF_SPECAA_GAIN_GGX or
                                 _BECKMANN */
} pf_specaa_bake_desc;

/* pf_reals of scratch pf_specaa_bake needs: PF_SPECAA_BAKE_CHANNELS x pf_mip_texel_count;
   0 for a size it does not accept. */
PF_CPU_DEF long long pf_specaa_bake_scratch_reals(int w, int h)
{
    long long n = pf_mip_texel_count(w, h);
    return n > 0 ? (pf_size_mul(n, PF_SPECAA_BAKE_CHANNELS) < 0 ? 0 : n * PF_SPECAA_BAKE_CHANNELS) : 0;
}

/* (2) for every texel of the mip chain (pf_map.h's layout, pf_mip_texel_count(w, h) texels):
   alpha_out[t] = sqrt(E[alpha^2] + 2 g v), and, when variance_out is not NULL, v itself (for
   the spare channel of a two-channel normal map, read back by pf_specaa_alpha_from_variance).
   The moments are pf_reals: where a footprint's mean slope is much larger than its spread the
   fourth central moment loses precision in float (rho stays clamped to [0, 2]). scratch: pf_specaa_bake_scratch_reals(w, h) pf_reals, the
   slope-moment and alpha^2 pyramid (left filled). Returns PF_OK, or having written nothing,
   PF_ERR_ARG (NULL desc, normals, scratch or alpha_out; width or height below 1; an unknown
   ndf; a gain outside [0, PF_SPECAA_MAX_GAIN] or NaN) or PF_ERR_SIZE (a side above
   PF_MAX_SIDE; a pyramid above PF_MAX_REALS). */
PF_CPU_DEF int pf_specaa_bake(const pf_specaa_bake_desc *d, pf_real *scratch, pf_real *alpha_out,
                              pf_real *variance_out)
{
    long long n, t, npix;
    pf_real g;
    int rc;
    if (!d || !d->normals || !scratch || !alpha_out) return PF_ERR_ARG;
    if (d->width < 1 || d->height < 1) return PF_ERR_ARG;
    if (d->ndf != PF_SPECAA_NDF_GGX && d->ndf != PF_SPECAA_NDF_BECKMANN) return PF_ERR_ARG;
    if (!(d->gain >= PF_R(0.0) && d->gain <= PF_SPECAA_MAX_GAIN)) return PF_ERR_ARG;
    n = pf_mip_texel_count(d->width, d->height);
    if (n <= 0 || pf_specaa_bake_scratch_reals(d->width, d->height) <= 0) return PF_ERR_SIZE;
    g = d->gain > PF_R(0.0) ? d->gain
        : (d->ndf == PF_SPECAA_NDF_GGX ? PF_SPECAA_GAIN_GGX : PF_SPECAA_GAIN_BECKMANN);
    npix = (long long)d->width * d->height;
    for (t = 0; t < npix; ++t) {
        const pf_real *nn = d->normals + 3 * t;
        pf_real *o = scratch + PF_SPECAA_BAKE_CHANNELS * t;
        pf_real x = nn[0], y = nn[1], z = nn[2], a;
        pf_real l2 = x * x + y * y + z * z;
        pf_real sx, sy, il;
        if (!(l2 > PF_R(0.0)) || !(l2 <= PF_REAL_MAX)) { x = PF_R(0.0); y = PF_R(0.0); z = PF_R(1.0); l2 = PF_R(1.0); }
        il = PF_R(1.0) / PF_SQRT(l2);
        z = pf_max(z * il, PF_SPECAA_MIN_NZ);
        sx = -x * il / z;
        sy = -y * il / z;
        a = pf_min(pf_max(d->roughness ? d->roughness[t] : d->alpha, PF_R(0.0)), PF_SPECAA_MAX_ALPHA);
        o[0] = sx;
        o[1] = sy;
        o[2] = sx * sx;
        o[3] = sy * sy;
        o[4] = sx * sy;
        o[5] = (o[2] + o[3]) * sx;
        o[6] = (o[2] + o[3]) * sy;
        o[7] = (o[2] + o[3]) * (o[2] + o[3]);
        o[8] = a * a;
    }
    rc = pf_mip_build(scratch, d->width, d->height, PF_SPECAA_BAKE_CHANNELS);
    if (rc != PF_OK) return rc;
    for (t = 0; t < n; ++t) {
        const pf_real *m = scratch + PF_SPECAA_BAKE_CHANNELS * t;
        pf_real mx = m[0], my = m[1], mm = mx * mx + my * my;
        pf_real var = PF_R(0.5) * (pf_max(m[2] - mx * mx, PF_R(0.0)) + pf_max(m[3] - my * my, PF_R(0.0)));
        /* E|s - m|^4 = E|s|^4 - 4 m.E[|s|^2 s] + 4 m^T E[s s^T] m + 2 E|s|^2 |m|^2 - 3 |m|^4 */
        pf_real m4 = m[7] - PF_R(4.0) * (mx * m[5] + my * m[6]) +
                     PF_R(4.0) * (mx * mx * m[2] + PF_R(2.0) * mx * my * m[4] + my * my * m[3]) +
                     PF_R(2.0) * (m[2] + m[3]) * mm - PF_R(3.0) * mm * mm;
        pf_real rho = m4 > PF_R(0.0) ? pf_min(PF_R(8.0) * var * (var / m4), PF_R(2.0)) : PF_R(1.0);
        pf_real v = var * rho;
        alpha_out[t] = PF_SQRT(pf_max(m[8], PF_R(0.0)) + PF_R(2.0) * g * v);
        if (variance_out) variance_out[t] = v;
    }
    return PF_OK;
}
#endif /* !PF_GLSL */

#endif /* PF_SPECAA_H */

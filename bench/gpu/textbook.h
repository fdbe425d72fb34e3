/* bench/gpu/textbook.h - the textbook formulas the library's evaluators are compared with on
   GPU cost (issue 17; bench/gpu/count.sh, the "GPU cost" section of the bench report).

   Our own code, written from the published formulas, in the plain form engines and samples
   ship them: native min/max/clamp, no guards beyond the formula's own, no robustness work.
   They are cost baselines, not library functions: they are not tested for accuracy here, and
   inputs the library handles (degenerate moments, directions below the surface, huge
   variances) may give NaN or inf.

   One source for GLSL (#define PF_GLSL 1, pasted after pf_core.h), CUDA and C (after
   #include "pf_core.h"): only PF_ macros, pf_real scalars and the PFT_ min/max macros below.
   Each baseline takes the same inputs, in the same order, as the library evaluator it stands
   beside (struct members flattened), so count.sh's generated wrappers load the same values:
       pf_textbook_vsm              pf_shadow_vsm         Chebyshev VSM
       pf_textbook_evsm2            pf_shadow_evsm2       EVSM, positive warp
       pf_textbook_evsm4            pf_shadow_evsm4       EVSM, both warps
       pf_textbook_msm              pf_shadow_msm         Hamburger 4MSM
       pf_textbook_msm_hausdorff    pf_shadow_msm_hausdorff  Hausdorff 4MSM (MJP's Shadows, HDRP)
       pf_textbook_msm16            pf_shadow_msm16       Hamburger 4MSM of a 64-bit texel
       pf_textbook_lean_d           pf_beckmann_d         the LEAN lobe
       pf_textbook_walter_g1        pf_g1_beckmann        Walter's rational G1
       pf_textbook_walter_lambda    pf_lambda_beckmann    Walter's rational Lambda
       pf_textbook_lean_walter_specular  pf_leadr_specular  LEAN lobe x Walter G1(o) G1(i)
                                                             x Schlick / (4 cos_o)
       pf_textbook_erfc_as          pf_erfc               Abramowitz & Stegun 7.1.26 */
#ifndef PF_TEXTBOOK_H
#define PF_TEXTBOOK_H

#ifndef PF_GLSL
#  include "pf_core.h"
#endif

/* native min/max/clamp: one instruction each on every GPU (GLSL FMin/FMax/FClamp, CUDA
   FMNMX; saturate is a free output modifier in SASS) */
#if defined(PF_GLSL)
#  define PFT_MIN(a, b) min(a, b)
#  define PFT_MAX(a, b) max(a, b)
#  define PFT_SATURATE(x) clamp(x, PF_R(0.0), PF_R(1.0))
#elif defined(__CUDACC__) && !defined(PF_DOUBLE)
#  define PFT_MIN(a, b) fminf(a, b)
#  define PFT_MAX(a, b) fmaxf(a, b)
#  define PFT_SATURATE(x) __saturatef(x)
#elif defined(PF_DOUBLE)
#  define PFT_MIN(a, b) fmin(a, b)
#  define PFT_MAX(a, b) fmax(a, b)
#  define PFT_SATURATE(x) fmin(fmax(x, 0.0), 1.0)
#else
#  define PFT_MIN(a, b) fminf(a, b)
#  define PFT_MAX(a, b) fmaxf(a, b)
#  define PFT_SATURATE(x) fminf(fmaxf(x, 0.0f), 1.0f)
#endif

/* ---------------------------------------------------------------- shadow maps */
/* Chebyshev's one-sided inequality (Donnelly & Lauritzen 2006): with mean m1 and variance
   var = max(m2 - m1^2, min_var), P(z >= t) <= var / (var + (t - m1)^2) for t > m1, and the
   receiver is taken as lit when t <= m1. */
PF_DEF pf_real pfi_textbook_chebyshev(pf_real m1, pf_real m2, pf_real t, pf_real min_var)
{
    pf_real var = PFT_MAX(m2 - m1 * m1, min_var);
    pf_real dt = t - m1;
    pf_real p = var / (var + dt * dt);
    return t <= m1 ? PF_R(1.0) : p;
}

/* Light-bleeding reduction (Lauritzen 2007): the bound remapped linearly from [bleed, 1] to
   [0, 1]. */
PF_DEF pf_real pfi_textbook_bleed(pf_real p, pf_real bleed)
{
    return PFT_SATURATE((p - bleed) / (PF_R(1.0) - bleed));
}

/* VSM: Chebyshev on (E[z], E[z^2]) at the receiver depth d, then the bleeding remap. */
PF_DEF pf_real pf_textbook_vsm(pf_real m1, pf_real m2, pf_real d, pf_real min_variance, pf_real bleed)
{
    return pfi_textbook_bleed(pfi_textbook_chebyshev(m1, m2, d, min_variance), bleed);
}

/* EVSM (Lauritzen & McCool 2008): Chebyshev on the warped depth w = exp(c (2d - 1)), the
   minimum variance scaled by the warp's squared derivative (2 c w)^2 at the receiver. */
PF_DEF pf_real pf_textbook_evsm2(pf_real m1, pf_real m2, pf_real d, pf_real c, pf_real min_variance,
                                 pf_real bleed)
{
    pf_real w = PF_EXP(c * (PF_R(2.0) * d - PF_R(1.0)));
    pf_real dw = PF_R(2.0) * c * w;
    return pfi_textbook_bleed(pfi_textbook_chebyshev(m1, m2, w, min_variance * dw * dw), bleed);
}

/* EVSM-4: the same on the positive warp exp(c_pos zs) and the negative warp -exp(-c_neg zs),
   zs = 2d - 1; the smaller bound, then the bleeding remap (once, as the library does). */
PF_DEF pf_real pf_textbook_evsm4(pf_real pos1, pf_real pos2, pf_real neg1, pf_real neg2, pf_real d,
                                 pf_real c_pos, pf_real c_neg, pf_real min_variance, pf_real bleed)
{
    pf_real zs = PF_R(2.0) * d - PF_R(1.0);
    pf_real wp = PF_EXP(c_pos * zs);
    pf_real wn = -PF_EXP(-c_neg * zs);
    pf_real dp = PF_R(2.0) * c_pos * wp;
    pf_real dn = PF_R(2.0) * c_neg * wn;
    pf_real lit_pos = pfi_textbook_chebyshev(pos1, pos2, wp, min_variance * dp * dp);
    pf_real lit_neg = pfi_textbook_chebyshev(neg1, neg2, wn, min_variance * dn * dn);
    return pfi_textbook_bleed(PFT_MIN(lit_pos, lit_neg), bleed);
}

/* Hamburger 4MSM (Peters & Klein 2015, Algorithm 2), power moments of depths in [0, 1]:
   bias the moments toward those of a fair coin on {0, 1}, b = (1 - a) m + a/2; solve
   B c = (1, zf, zf^2) for the Hankel matrix B of (1, b1, b2, b3, b4) by Cholesky (B = L D L^T);
   the roots z2 <= z3 of c1 + c2 z + c3 z^2 are the other two atoms; the shadow intensity is
       zf <= z2:       0
       z2 < zf <= z3:  (zf z3 - b1 (zf + z3) + b2) / ((z3 - z2)(zf - z2))
       zf > z3:        1 - (z2 z3 - b1 (z2 + z3) + b2) / ((zf - z2)(zf - z3))
   and the lit fraction is 1 minus it. zf = d - depth_bias. */
PF_DEF pf_real pf_textbook_msm(pf_real m1, pf_real m2, pf_real m3, pf_real m4, pf_real d,
                               pf_real moment_bias, pf_real depth_bias)
{
    pf_real ha = PF_R(0.5) * moment_bias;
    pf_real k = PF_R(1.0) - moment_bias;
    pf_real b1 = k * m1 + ha, b2 = k * m2 + ha, b3 = k * m3 + ha, b4 = k * m4 + ha;
    pf_real zf = d - depth_bias;
    /* B = L D L^T: d22 the variance, l32 = (b3 - b1 b2)/d22, d33 the rest of b4 */
    pf_real d22 = b2 - b1 * b1;
    pf_real inv_d22 = PF_R(1.0) / d22;
    pf_real e32 = b3 - b1 * b2;
    pf_real l32 = e32 * inv_d22;
    pf_real d33 = b4 - b2 * b2 - l32 * e32;
    /* forward, diagonal, backward substitution for c */
    pf_real y2 = zf - b1;
    pf_real y3 = zf * zf - b2 - l32 * y2;
    pf_real c3 = y3 / d33;
    pf_real c2 = y2 * inv_d22 - l32 * c3;
    pf_real c1 = PF_R(1.0) - b1 * c2 - b2 * c3;
    /* roots of z^2 + p z + q, p = c2/c3, q = c1/c3 */
    pf_real p = c2 / c3, q = c1 / c3;
    pf_real r = PF_SQRT(PF_R(0.25) * p * p - q);
    pf_real z2 = PF_R(-0.5) * p - r;
    pf_real z3 = PF_R(-0.5) * p + r;
    /* the two weights share one division: beyond (zf > z3) uses atoms (z2, z3) in the
       numerator and (zf - z3)(zf - z2) below, between uses (zf, z3) and (z3 - z2)(zf - z2) */
    pf_real far = zf > z3 ? PF_R(1.0) : PF_R(0.0);
    pf_real u = zf > z3 ? z2 : zf;
    pf_real span = zf > z3 ? zf - z3 : z3 - z2;
    pf_real w = (u * z3 - b1 * (u + z3) + b2) / (span * (zf - z2));
    pf_real shadow = zf > z2 ? far + (PF_R(1.0) - PF_R(2.0) * far) * w : PF_R(0.0);
    return PF_R(1.0) - PFT_SATURATE(shadow);
}

/* Hausdorff 4MSM (Peters & Klein 2015, depths known to lie in [0, 1]) as MJP's Shadows sample
   (MSM.hlsl) and Unity HDRP (ShadowMoments.hlsl) ship it, written here from that description:
   the Hamburger kernel roots z2 <= z3 as in pf_textbook_msm; when both lie in [0, 1] the
   three-atom shadow of pf_textbook_msm, otherwise the four-atom solution {0, zf, x, 1}: with
   the moments of z (1 - z) mu, n0 = b1 - b2, n1 = b2 - b3, n2 = b3 - b4, the free atom is
   x = (zf n1 - n2) / (zf n0 - n1), and the shadow (the mass in front of zf) is
       w0 + [x < zf] wx,   w0 = E[(1 - z)(z - zf)(z - x)] / (zf x),
                           wx = (n1 - zf n0) / (x (1 - x)(x - zf)).
   Selects of plain values, as the engines write them. */
PF_DEF pf_real pf_textbook_msm_hausdorff(pf_real m1, pf_real m2, pf_real m3, pf_real m4, pf_real d,
                                         pf_real moment_bias, pf_real depth_bias)
{
    pf_real ha = PF_R(0.5) * moment_bias;
    pf_real k = PF_R(1.0) - moment_bias;
    pf_real b1 = k * m1 + ha, b2 = k * m2 + ha, b3 = k * m3 + ha, b4 = k * m4 + ha;
    pf_real zf = d - depth_bias;
    pf_real d22 = b2 - b1 * b1;
    pf_real inv_d22 = PF_R(1.0) / d22;
    pf_real e32 = b3 - b1 * b2;
    pf_real l32 = e32 * inv_d22;
    pf_real d33 = b4 - b2 * b2 - l32 * e32;
    pf_real y2 = zf - b1;
    pf_real y3 = zf * zf - b2 - l32 * y2;
    pf_real c3 = y3 / d33;
    pf_real c2 = y2 * inv_d22 - l32 * c3;
    pf_real c1 = PF_R(1.0) - b1 * c2 - b2 * c3;
    pf_real p = c2 / c3, q = c1 / c3;
    pf_real r = PF_SQRT(PF_R(0.25) * p * p - q);
    pf_real z2 = PF_R(-0.5) * p - r;
    pf_real z3 = PF_R(-0.5) * p + r;
    pf_real far = zf > z3 ? PF_R(1.0) : PF_R(0.0);
    pf_real u = zf > z3 ? z2 : zf;
    pf_real span = zf > z3 ? zf - z3 : z3 - z2;
    pf_real w = (u * z3 - b1 * (u + z3) + b2) / (span * (zf - z2));
    pf_real three = zf > z2 ? far + (PF_R(1.0) - PF_R(2.0) * far) * w : PF_R(0.0);
    /* the four-atom solution */
    pf_real n0 = b1 - b2, n1 = b2 - b3, n2 = b3 - b4;
    pf_real x = (zf * n1 - n2) / (zf * n0 - n1);
    pf_real s = zf + x, t = zf * x;
    pf_real w0 = ((b2 - s * b1 + t) - (b3 - s * b2 + t * b1)) / t;
    pf_real wx = (n1 - zf * n0) / (x * (PF_R(1.0) - x) * (x - zf));
    pf_real wxf = x < zf ? wx : PF_R(0.0);
    pf_real four = w0 + wxf;
    pf_real outside = z2 < PF_R(0.0) || z3 > PF_R(1.0) ? PF_R(1.0) : PF_R(0.0);
    pf_real shadow = outside > PF_R(0.5) ? four : three;
    return PF_R(1.0) - PFT_SATURATE(shadow);
}

/* Hamburger 4MSM of a 64-bit texel as engines decode it (Peters & Klein 2015 sec. 4.3): the
   filtered UNORM values q back to z-moments by the inverse of the optimized quantization
   (b = Theta^-1 (q - o), pf_shadow.h's constants), then pf_textbook_msm. */
PF_DEF pf_real pf_textbook_msm16(pf_real q1, pf_real q2, pf_real q3, pf_real q4, pf_real d,
                                 pf_real moment_bias, pf_real depth_bias)
{
    pf_real q0 = q1 - PF_R(0.035955884801);
    pf_real m1 = PF_R(0.22277441458975106) * q0 + PF_R(0.077197286078127286) * q2 + PF_R(0.79269866365602848) * q3
               + PF_R(0.031941755461409697) * q4;
    pf_real m2 = PF_R(0.15496792611583607) * q0 + PF_R(0.13946294265353615) * q2 + PF_R(0.79634158378587572) * q3
               - PF_R(0.17228231730199037) * q4;
    pf_real m3 = PF_R(0.14519889456443683) * q0 + PF_R(0.21202021568252677) * q2 + PF_R(0.72586944638507078) * q3
               - PF_R(0.27580148114915759) * q4;
    pf_real m4 = PF_R(0.16312744299137799) * q0 + PF_R(0.25914322664410966) * q2 + PF_R(0.65390924967369524) * q3
               - PF_R(0.33761317340581742) * q4;
    return pf_textbook_msm(m1, m2, m3, m4, d, moment_bias, depth_bias);
}

/* ---------------------------------------------------------------- microfacets */
/* The LEAN lobe (Olano & Baker 2010; Dupuy et al. 2013 eq. 10): the Gaussian of the slope
   (-h.x/h.z, -h.y/h.z) with mean (mx, my) and covariance [[vx, c], [c, vy]], divided by
   cos^4 of the unit half vector h. */
PF_DEF pf_real pf_textbook_lean_d(pf_real hx, pf_real hy, pf_real hz, pf_real mx, pf_real my,
                                  pf_real vx, pf_real vy, pf_real c)
{
    pf_real inv_z = PF_R(1.0) / hz;
    pf_real x = -hx * inv_z - mx;
    pf_real y = -hy * inv_z - my;
    pf_real det = vx * vy - c * c;
    pf_real e = (vy * x * x - PF_R(2.0) * c * x * y + vx * y * y) / det;
    pf_real z2 = hz * hz;
    return PF_EXP(PF_R(-0.5) * e) / (PF_R(2.0) * PF_PI * PF_SQRT(det) * z2 * z2);
}

/* Walter et al. 2007 eq. 27 (as used by Dupuy et al. 2013 sec. 4.3): with
   a = nu = (cot theta - mu) / (sigma sqrt 2),
       Lambda ~ (1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2),  a < 1.6 (else 0),
       G1 = 1 / (1 + Lambda) = (3.535 a + 2.181 a^2) / (1 + 2.276 a + 2.577 a^2). */
PF_DEF pf_real pf_textbook_walter_lambda(pf_real nu)
{
    pf_real l = (PF_R(1.0) - PF_R(1.259) * nu + PF_R(0.396) * nu * nu) / (PF_R(3.535) * nu + PF_R(2.181) * nu * nu);
    return nu < PF_R(1.6) ? l : PF_R(0.0);
}

PF_DEF pf_real pf_textbook_walter_g1(pf_real nu)
{
    pf_real g = (PF_R(3.535) * nu + PF_R(2.181) * nu * nu) / (PF_R(1.0) + PF_R(2.276) * nu + PF_R(2.577) * nu * nu);
    return nu < PF_R(1.6) ? g : PF_R(1.0);
}

/* nu of direction w for the slope statistics (Dupuy et al. 2013 after eq. 15, multiplied
   through by sin theta): (w.z - w.x mx - w.y my) / sqrt(2 (w.x^2 vx + w.y^2 vy + 2 w.x w.y c)). */
PF_DEF pf_real pfi_textbook_nu(pf_real wx, pf_real wy, pf_real wz, pf_real mx, pf_real my,
                               pf_real vx, pf_real vy, pf_real c)
{
    pf_real var = wx * wx * vx + wy * wy * vy + PF_R(2.0) * wx * wy * c;
    return (wz - wx * mx - wy * my) / PF_SQRT(PF_R(2.0) * var);
}

/* The usual real-time specular with the LEAN lobe: D(h) G1(o) G1(i) F(h . i) / (4 cos_o)
   (the BRDF times cos_i), Walter's G1 for both directions, Schlick's Fresnel. wo, wi unit,
   above the surface. */
PF_DEF pf_real pf_textbook_lean_walter_specular(pf_real ox, pf_real oy, pf_real oz,
                                                pf_real ix, pf_real iy, pf_real iz,
                                                pf_real mx, pf_real my, pf_real vx, pf_real vy,
                                                pf_real c, pf_real f0)
{
    pf_real hx = ox + ix, hy = oy + iy, hz = oz + iz;
    pf_real inv_len = PF_R(1.0) / PF_SQRT(hx * hx + hy * hy + hz * hz);
    pf_real d, g, t, f;
    hx *= inv_len;
    hy *= inv_len;
    hz *= inv_len;
    d = pf_textbook_lean_d(hx, hy, hz, mx, my, vx, vy, c);
    g = pf_textbook_walter_g1(pfi_textbook_nu(ox, oy, oz, mx, my, vx, vy, c)) *
        pf_textbook_walter_g1(pfi_textbook_nu(ix, iy, iz, mx, my, vx, vy, c));
    t = PF_R(1.0) - PFT_SATURATE(hx * ix + hy * iy + hz * iz);
    f = f0 + (PF_R(1.0) - f0) * (t * t) * (t * t) * t;
    return d * g * f / (PF_R(4.0) * oz);
}

/* ---------------------------------------------------------------- erfc */
/* Abramowitz & Stegun 7.1.26: erfc(x) ~ t (a1 + t (a2 + t (a3 + t (a4 + t a5)))) exp(-x^2),
   t = 1 / (1 + p x), for x >= 0 (absolute error 1.5e-7), and erfc(-x) = 2 - erfc(x). */
PF_DEF pf_real pf_textbook_erfc_as(pf_real x)
{
    pf_real ax = PF_FABS(x);
    pf_real t = PF_R(1.0) / (PF_R(1.0) + PF_R(0.3275911) * ax);
    pf_real y = t * (PF_R(0.254829592) + t * (PF_R(-0.284496736) + t * (PF_R(1.421413741) +
                t * (PF_R(-1.453152027) + t * PF_R(1.061405429))))) * PF_EXP(-ax * ax);
    return x < PF_R(0.0) ? PF_R(2.0) - y : y;
}

#endif /* PF_TEXTBOOK_H */

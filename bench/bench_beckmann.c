/* bench_beckmann.c - cost and accuracy of the LEADR specular BRDF (pf_beckmann.h) next to the
   lobes it replaces.

   Family "specular": the reflected radiance factor for one directional light, per pixel:
     lean_lobe (BASELINE)       what LEAN mapping evaluates (Olano & Baker 2010; survey eq. 19):
                                the slope density P22 at the half vector's slope, from the same
                                five moments. No masking, no reflection Jacobian, no projected-area
                                normalization (pf_beckmann_p22 at (-h.x/h.z, -h.y/h.z)).
     blinn_phong_mesonormal     the engine fallback: a normalized Blinn-Phong lobe
                                (n + 2)/(8 pi) (n_bar . h)^n around the mesonormal, with the
                                exponent from the mean slope variance s^2 through the
                                Beckmann roughness m = sqrt(2) s and Walter et al. 2007's
                                n = 2/m^2 - 2 (pf_beckmann_to_blinn_phong).
     pf_leadr_specular          LEADR eq. 17, joint masking-shadowing (eq. 13), Fresnel on.
     pf_leadr_specular_masking  the same with masking only (LEADR sec. 6).
     textbook_lean_walter_specular  the specular term as usually shipped (issue 17): LEAN lobe
                                of the unit half vector x Walter's rational G1 for both
                                directions x Schlick / (4 cos_o), no guards; the CPU side of
                                the GPU comparison in docs/beckmann.md.
   LEAN, Blinn-Phong and the textbook row are different models, not approximations of eq. 17 to a stated
   accuracy: they get no accuracy columns (their distance to LEADR is a modelling question,
   answered on real surfaces by the report, not here).

   INPUTS. A table of PFB_TABLE configurations (view, light, filtered moments) drawn once from a
   fixed seed: mean slope uniform in the disc of radius 0.5, slope deviations log-uniform in
   [0.05, 0.5] per axis, correlation uniform in [-0.8, 0.8], base roughness 1e-4; view with
   cos theta_o uniform in [0.05, 1]; light half of the time uniform on the upper hemisphere, half
   of the time the mirror direction about a micro-normal drawn from the distribution (so D is
   not negligibly small on half of the inputs, as in a highlight). Configurations whose view is
   below the mesosurface are redrawn (a renderer culls them). A method's input x is an index
   into the table, so every method pays the same gather (like the texture fetch of the moments).

   REFERENCE (long double, independent of pf_beckmann.h): P22 by the explicit inverse of the
   covariance and Lambda(nu) = exp(-nu^2)/(2 nu sqrt(pi)) - erfc(nu)/2 (continued fraction past
   nu = 2), both from tests/reference/pf_oracle.h; D = P22 / cos^4 and nu by trigonometry (eqs. 14-15),
   A_o = (n_bar . w_o)/(n_bar . w_g) from the normalized mesonormal, Schlick's Fresnel with the
   normalized half vector. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_beckmann.h"
#include "pf_toksvig.h"             /* Blinn-Phong exponent of a Beckmann roughness */
#include "pf_oracle.h"     /* long double P22 and Lambda references */

#define PFB_TABLE 16384
#define F0_BENCH PF_R(0.04)

static pf_vec3 tab_wo[PFB_TABLE], tab_wi[PFB_TABLE];
static pf_slope_stats tab_s[PFB_TABLE];
static pf_real tab_n[PFB_TABLE]; /* Blinn-Phong exponent */

/* ---------------------------------------------------------------- methods */
static pf_real lean_lobe(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s)
{
    pf_vec3 h = pf_vec3_add(wo, wi);
    pf_real iz = PF_R(1.0) / h.z;
    return pf_beckmann_p22(-h.x * iz, -h.y * iz, s);
}

static pf_real blinn_phong(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real n)
{
    pf_vec3 h = pf_vec3_normalize(pf_vec3_add(wo, wi));
    pf_vec3 nb = pf_beckmann_mesonormal(s);
    pf_real c = pf_max(pf_vec3_dot(nb, h), PF_R(0.0));
    return (n + PF_R(2.0)) * (PF_R(0.125) * PF_INV_PI) * PF_POW(c, n);
}

/* The specular term as usually shipped (issue 17's comparison row): the LEAN lobe of the unit
   half vector, Walter et al. 2007's rational G1 for both directions (separable), Schlick, over
   4 cos_o; no guards (it assumes both directions above the surface, as the table's are). */
static pf_real tb_walter_g1(pf_vec3 w, pf_slope_stats s)
{
    pf_real var = w.x * w.x * s.var_x + w.y * w.y * s.var_y + PF_R(2.0) * w.x * w.y * s.cov_xy;
    pf_real nu = (w.z - w.x * s.mean_x - w.y * s.mean_y) / PF_SQRT(PF_R(2.0) * var);
    return nu < PF_R(1.6) ? nu * (PF_R(3.535) + PF_R(2.181) * nu) / (PF_R(1.0) + nu * (PF_R(2.276) + PF_R(2.577) * nu))
                          : PF_R(1.0);
}

static pf_real tb_lean_walter(pf_vec3 wo, pf_vec3 wi, pf_slope_stats s, pf_real f0)
{
    pf_vec3 h = pf_vec3_add(wo, wi);
    pf_real il = PF_R(1.0) / PF_SQRT(pf_vec3_dot(h, h));
    pf_real hx = h.x * il, hy = h.y * il, hz = h.z * il, iz = PF_R(1.0) / hz;
    pf_real x = -hx * iz - s.mean_x, y = -hy * iz - s.mean_y;
    pf_real det = s.var_x * s.var_y - s.cov_xy * s.cov_xy;
    pf_real e = (s.var_y * x * x - PF_R(2.0) * s.cov_xy * x * y + s.var_x * y * y) / det;
    pf_real z2 = hz * hz;
    pf_real d = PF_EXP(PF_R(-0.5) * e) / (PF_R(2.0) * PF_PI * PF_SQRT(det) * z2 * z2);
    pf_real c = hx * wi.x + hy * wi.y + hz * wi.z;
    pf_real t = PF_R(1.0) - (c < PF_R(0.0) ? PF_R(0.0) : (c > PF_R(1.0) ? PF_R(1.0) : c));
    pf_real f = f0 + (PF_R(1.0) - f0) * (t * t) * (t * t) * t;
    return d * tb_walter_g1(wo, s) * tb_walter_g1(wi, s) * f / (PF_R(4.0) * wo.z);
}

#define IDX(x) ((int)(x))
PFB_METHOD(lean, lean_lobe(tab_wo[IDX(x)], tab_wi[IDX(x)], tab_s[IDX(x)]))
PFB_METHOD(blinn, blinn_phong(tab_wo[IDX(x)], tab_wi[IDX(x)], tab_s[IDX(x)], tab_n[IDX(x)]))
PFB_METHOD(leadr_joint, pf_leadr_specular(tab_wo[IDX(x)], tab_wi[IDX(x)], tab_s[IDX(x)], F0_BENCH))
PFB_METHOD(tb_lean_walter, tb_lean_walter(tab_wo[IDX(x)], tab_wi[IDX(x)], tab_s[IDX(x)], F0_BENCH))
PFB_METHOD(leadr_masking, pf_leadr_specular_masking(tab_wo[IDX(x)], tab_wi[IDX(x)], tab_s[IDX(x)], F0_BENCH))

/* ---------------------------------------------------------------- reference */
typedef struct ref_cfg {
    long double mx, my, vx, vy, c;
} ref_cfg;

static long double ref_lambda(ref_cfg k, long double wx, long double wy, long double wz)
{
    long double len = sqrtl(wx * wx + wy * wy + wz * wz);
    long double theta = acosl(wz / len), phi = atan2l(wy, wx);
    long double cp = cosl(phi), sp = sinl(phi);
    long double mu = cp * k.mx + sp * k.my;
    long double sigma = sqrtl(cp * cp * k.vx + sp * sp * k.vy + 2.0L * cp * sp * k.c);
    if (theta == 0.0L) return 0.0L;
    return pf_oracle_lambda_beckmann((cosl(theta) / sinl(theta) - mu) / (sigma * sqrtl(2.0L)));
}

static long double ref_specular(long double x, int masking_only)
{
    int i = (int)x;
    ref_cfg k;
    long double o[3], w[3], h[3], hl, sx, sy, p22, cz, d, lo, li, nl, ao, ai,
        F, cd, f0 = (long double)F0_BENCH;
    int j;
    k.mx = (long double)tab_s[i].mean_x;
    k.my = (long double)tab_s[i].mean_y;
    k.vx = (long double)tab_s[i].var_x;
    k.vy = (long double)tab_s[i].var_y;
    k.c = (long double)tab_s[i].cov_xy;
    o[0] = (long double)tab_wo[i].x; o[1] = (long double)tab_wo[i].y; o[2] = (long double)tab_wo[i].z;
    w[0] = (long double)tab_wi[i].x; w[1] = (long double)tab_wi[i].y; w[2] = (long double)tab_wi[i].z;
    nl = sqrtl(1.0L + k.mx * k.mx + k.my * k.my);
    ao = (-k.mx * o[0] - k.my * o[1] + o[2]) / nl / (1.0L / nl);
    ai = (-k.mx * w[0] - k.my * w[1] + w[2]) / nl / (1.0L / nl);
    if (o[2] <= 0.0L || w[2] <= 0.0L || ao <= 0.0L || ai <= 0.0L) return 0.0L;
    for (j = 0; j < 3; j++) h[j] = o[j] + w[j];
    hl = sqrtl(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    if (h[2] <= 0.0L) return 0.0L;
    sx = -h[0] / h[2];
    sy = -h[1] / h[2];
    p22 = pf_oracle_normal2_pdf(sx - k.mx, sy - k.my, k.vx, k.vy, k.c);
    cz = h[2] / hl;
    d = p22 / (cz * cz * cz * cz);
    lo = ref_lambda(k, o[0], o[1], o[2]);
    li = masking_only ? 0.0L : ref_lambda(k, w[0], w[1], w[2]);
    cd = (w[0] * h[0] + w[1] * h[1] + w[2] * h[2]) / hl;
    F = f0 + (1.0L - f0) * powl(1.0L - cd, 5.0L);
    return F * d / (4.0L * ao * (1.0L + lo + li));
}

static long double ref_joint(long double x, long double y, long double z)
{
    (void)y; (void)z;
    return ref_specular(x, 0);
}

static long double ref_masking(long double x, long double y, long double z)
{
    (void)y; (void)z;
    return ref_specular(x, 1);
}

/* ---------------------------------------------------------------- inputs */
static double gauss(pfb_rng *r)
{
    double u1 = 1.0 - pfb_unif(r), u2 = pfb_unif(r);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

static void make_table(void)
{
    pfb_rng r;
    int i;
    r.s = 0xbec3beefULL;
    for (i = 0; i < PFB_TABLE; ++i) {
        for (;;) {
            double rad = 0.5 * sqrt(pfb_unif(&r)), ang = 6.283185307179586 * pfb_unif(&r);
            double sx = pfb_logunif(&r, 0.05, 0.5), sy = pfb_logunif(&r, 0.05, 0.5);
            double rho = pfb_unif_in(&r, -0.8, 0.8);
            double co = pfb_unif_in(&r, 0.05, 1.0), so = sqrt(1.0 - co * co), po = 6.283185307179586 * pfb_unif(&r);
            pf_slope_moments m;
            pf_slope_stats s;
            pf_vec3 wo, wi;
            s = pf_slope_stats_make((pf_real)(rad * cos(ang)), (pf_real)(rad * sin(ang)), (pf_real)(sx * sx),
                                    (pf_real)(sy * sy), (pf_real)(rho * sx * sy));
            m = pf_slope_moments_from_stats(s);
            s = pf_slope_moments_stats(m, PF_R(1e-4));
            wo = pf_vec3_make((pf_real)(so * cos(po)), (pf_real)(so * sin(po)), (pf_real)co);
            if (pf_beckmann_projected_area(wo, s) <= PF_R(0.0)) continue;
            if (pfb_unif(&r) < 0.5) {
                double ci = pfb_unif(&r), si = sqrt(1.0 - ci * ci), pi_ = 6.283185307179586 * pfb_unif(&r);
                wi = pf_vec3_make((pf_real)(si * cos(pi_)), (pf_real)(si * sin(pi_)), (pf_real)ci);
            } else {
                /* mirror about a micro-normal drawn from the slope distribution */
                double g1 = gauss(&r), g2 = gauss(&r);
                double a = sqrt((double)s.var_x), b = (double)s.cov_xy / a;
                double c = sqrt(fmax((double)s.var_y - b * b, 0.0));
                double x = (double)s.mean_x + a * g1, y = (double)s.mean_y + b * g1 + c * g2;
                pf_vec3 n = pf_vec3_normalize(pf_vec3_make((pf_real)-x, (pf_real)-y, PF_R(1.0)));
                wi = pf_vec3_sub(pf_vec3_scale(n, PF_R(2.0) * pf_vec3_dot(n, wo)), wo);
            }
            tab_wo[i] = wo;
            tab_wi[i] = wi;
            tab_s[i] = s;
            /* Beckmann roughness m = sqrt(2) sigma, sigma^2 the mean of the two variances */
            tab_n[i] = pf_beckmann_to_blinn_phong(PF_SQRT(s.var_x + s.var_y));
            break;
        }
    }
}

static void gen_index(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) a[i] = (pf_real)(int)(pfb_unif(r) * PFB_TABLE);
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
}

static size_t grid_index(pf_real *a, pf_real *b, pf_real *c)
{
    size_t i;
    if (!a) return PFB_TABLE;
    for (i = 0; i < PFB_TABLE; ++i) a[i] = (pf_real)i;
    memset(b, 0, PFB_TABLE * sizeof *b);
    memset(c, 0, PFB_TABLE * sizeof *c);
    return PFB_TABLE;
}

static const pfb_family families[] = {
    { "specular", 1, { "config", NULL }, 0,
      "timing inputs: random indices into a table of 16384 seeded configurations (view, light, "
      "filtered moments; see bench_beckmann.c): mean slope in the disc of radius 0.5, deviations "
      "log-uniform in [0.05, 0.5], |r| <= 0.8, cos theta_o in [0.05, 1], light half uniform on "
      "the hemisphere, half mirrored about a micro-normal of the distribution\n"
      "grid: all 16384 table entries\n"
      "reference: long double eq. 17 written from the paper (explicit covariance inverse, "
      "Lambda by erfcl and a continued fraction, trigonometric nu); LEAN, Blinn-Phong and the "
      "textbook LEAN x Walter G1(o) G1(i) x Schlick / (4 cos_o) (issue 17's comparison row, no "
      "guards) are other models: cost only",
      gen_index, grid_index, 5,
      { PFB_ENTRY("lean_lobe", lean, NULL, 0),
        PFB_ENTRY("blinn_phong_mesonormal", blinn, NULL, 0),
        PFB_ENTRY("pf_leadr_specular", leadr_joint, ref_joint, 0),
        PFB_ENTRY("pf_leadr_specular_masking", leadr_masking, ref_masking, 0),
        PFB_ENTRY("textbook_lean_walter_specular", tb_lean_walter, NULL, 0) } },
};

int main(int argc, char **argv)
{
    make_table();
    return pfb_main(argc, argv, "beckmann", families, (int)(sizeof families / sizeof families[0]));
}

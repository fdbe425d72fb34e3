/* bench/grazing_diag.c - where the filtered specular's error at grazing views comes from
   (issue 28, item 2). Not part of `make bench`: a diagnostic, built and run by hand:
       cc -std=c99 -O2 -DPF_DOUBLE [-DQQ=80] -Ibench -Iinclude -Itests/reference bench/grazing_diag.c -lm -o /tmp/gd
       /tmp/gd gaussian_fine 85
   For one kind, 64 x 64 footprints (every one of the 512 x 512 map), one view angle at the
   bench's two azimuths (10 and 100 degrees), the mirror light of each footprint (the specular
   peak: it carries most of the bench's rel_l2) and 8 seeded hemisphere lights, it shades the
   in-footprint reference (tests/reference/pf_microsurface.h) and splits LEADR (pf_leadr_specular)
   and the exact-histogram oracle into their factors:
       LEADR  = F D_gauss(h) G(s) / (4 A_o)          s = footprint stats + base variance
       oracle = F [mean_t D_t(h) G_t] G(s0) / (4 A)  s0 = footprint stats, G_t the base lobe's own
   then swaps one factor of LEADR at a time for the oracle's and prints each hybrid's rel_l2 to
   the reference (same cull as the bench: A > CULL_AREA wo.z), so the factor that carries the
   error is the one whose swap removes it. QQ: the rule of the posterior average of G_t (80:
   80 x 80 midpoint, 5 or 4 or 3: Gauss-Hermite, 1: Smith G2 of the posterior widened by the
   base lobe); the last row is the library's pf_leadr_specular_base. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include "pf_beckmann.h"
#include "pf_microsurface.h"

#define BASE_SIGMA 0.1
#ifndef N
#define N 64
#endif
#define W 512
#define NL 8
#define NH 13
#ifndef QQ
#define QQ 80
#endif
#define PI 3.14159265358979323846

static const char *hname[NH] = {
    "reference (in-footprint)",                    /* 0 */
    "oracle_histogram_smith",                      /* 1 */
    "leadr_joint",                                 /* 2 */
    "leadr, D -> histogram D (no G_t)",            /* 3 */
    "leadr x <G_t> (base lobe masking)",           /* 4 */
    "leadr, G(s) -> G(s0)",                        /* 5 */
    "leadr, D,G_t -> histogram <D_t G_t>",         /* 6 */
    "leadr, D,G_t,G(s0) (= oracle)",               /* 7 */
    "leadr, Smith P_o -> histogram front area",   /* 8 */
    "oracle, G -> reference's visible fraction",   /* 9 */
    "leadr, G(s) -> G(s0) x <G_t>",                /* 10 */
    "leadr x posterior <G_t>, QQ rule",           /* 11 */
    "pf_leadr_specular_base (library)",            /* 12 */
};

/* Smith Lambda of the base lobe (deviation BASE_SIGMA) for a facet whose projected area toward
   w is a (w.z - s.w_xy): -1 when a <= 0 */
static double lam_b(double a, double rxy)
{
    const double sqrt_pi = 1.7724538509055160273;
    double nu;
    if (!(a > 0)) return -1;
    if (!(rxy > 0)) return 0;
    nu = a / (BASE_SIGMA * sqrt(2.0) * rxy);
    if (nu > 6.5) return 0;
    return exp(-nu * nu) / (2.0 * sqrt_pi * nu) - 0.5 * erfc(nu);
}
/* the base lobe's G2 averaged over the reflecting texels' slopes, modelled as the posterior of
   the footprint's Gaussian N(mu, S0) given the half vector's slope hs seen through the base lobe
   N(hs; s, sb^2 I): a 2D Gauss-Hermite rule of order q (probabilists': nodes of N(0,1)) */
static double post_gt(const double wo[3], const double wi[3], pf_slope_stats s0, const double hs[2], int q)
{
    static const double x3[3] = { -1.7320508075688772, 0, 1.7320508075688772 }, w3[3] = { 1.0 / 6, 2.0 / 3, 1.0 / 6 };
    static const double x5[5] = { -2.8569700138728056, -1.3556261799742659, 0, 1.3556261799742659, 2.8569700138728056 };
    static const double w5[5] = { 0.011257411327720691, 0.22207592200561265, 0.5333333333333333, 0.22207592200561265,
                                  0.011257411327720691 };
    double xs[128], ws[128];
    double a = s0.var_x, b = s0.cov_xy, c = s0.var_y, vb = BASE_SIGMA * BASE_SIGMA;
    /* K = S0 (S0 + vb I)^-1 */
    double da = a + vb, dc = c + vb, det = da * dc - b * b, ia = dc / det, ib = -b / det, ic = da / det;
    double k11 = a * ia + b * ib, k12 = a * ib + b * ic, k21 = b * ia + c * ib, k22 = b * ib + c * ic;
    double dx = hs[0] - s0.mean_x, dy = hs[1] - s0.mean_y;
    double mx = s0.mean_x + k11 * dx + k12 * dy, my = s0.mean_y + k21 * dx + k22 * dy;
    /* Sp = S0 - K S0 */
    double p11 = a - (k11 * a + k12 * b), p12 = b - (k11 * b + k12 * c), p22 = c - (k21 * b + k22 * c);
    double l11, l21, l22, sum = 0, ro = sqrt(wo[0] * wo[0] + wo[1] * wo[1]), ri = sqrt(wi[0] * wi[0] + wi[1] * wi[1]);
    int i, j, n;
    static const double x4[4] = { -2.3344142183389773, -0.7419637843027258, 0.7419637843027258, 2.3344142183389773 };
    static const double w4[4] = { 0.04587585476806849, 0.4541241452319315, 0.4541241452319315, 0.04587585476806849 };
    if (q == 3) { memcpy(xs, x3, sizeof x3); memcpy(ws, w3, sizeof w3); n = 3; }
    else if (q == 4) { memcpy(xs, x4, sizeof x4); memcpy(ws, w4, sizeof w4); n = 4; }
    else if (q == 5) { memcpy(xs, x5, sizeof x5); memcpy(ws, w5, sizeof w5); n = 5; }
    else { /* midpoint rule on +-6 sd, q x q */
        n = q;
        for (i = 0; i < n; ++i) {
            xs[i] = -6.0 + 12.0 * (i + 0.5) / n;
            ws[i] = exp(-0.5 * xs[i] * xs[i]) / sqrt(2 * PI) * 12.0 / n;
        }
    }
    if (q == 1) { /* Smith G2 of the posterior convolved with the base lobe (one Gaussian) */
        pf_slope_stats sp = s0;
        sp.mean_x = mx; sp.mean_y = my; sp.var_x = p11 + vb; sp.var_y = p22 + vb; sp.cov_xy = p12;
        return pf_beckmann_masking_shadowing(pf_vec3_make(wo[0], wo[1], wo[2]), pf_vec3_make(wi[0], wi[1], wi[2]), sp);
    }
    if (p11 < 0) p11 = 0;
    l11 = sqrt(p11);
    l21 = l11 > 0 ? p12 / l11 : 0;
    l22 = p22 - l21 * l21;
    l22 = l22 > 0 ? sqrt(l22) : 0;
    for (i = 0; i < n; ++i)
        for (j = 0; j < n; ++j) {
            double sx = mx + l11 * xs[i], sy = my + l21 * xs[i] + l22 * xs[j];
            double lo = lam_b(wo[2] - sx * wo[0] - sy * wo[1], ro), li = lam_b(wi[2] - sx * wi[0] - sy * wi[1], ri);
            if (lo >= 0 && li >= 0) sum += ws[i] * ws[j] / (1 + lo + li);
        }
    return sum;
}

int main(int argc, char **argv)
{
    const char *kn = argc > 1 ? argv[1] : "gaussian_fine";
    double theta = (argc > 2 ? atof(argv[2]) : 85.0) * PI / 180.0;
    int kind, k, az, fx, fy, li;
    pfm_surface surf;
    double lights[NL][3], se[NH], sr = 0.0;
    unsigned char *vis_full = (unsigned char *)calloc((size_t)W * W, 1), *box_o = (unsigned char *)calloc((size_t)W * W, 1);
    unsigned char *vis_i = (unsigned char *)calloc((size_t)W * W, 1), *box_i = (unsigned char *)calloc((size_t)W * W, 1);
    pfm_rng rg;
    /* per-factor sums over the mirror samples weighted by ref^2 (log ratios) */
    double wsum = 0.0, lr_d = 0.0, lr_gt = 0.0, lr_g = 0.0, lr_a = 0.0, lr_vis = 0.0, lr_lead = 0.0, lr_or = 0.0;
    long nsamp = 0, ncull = 0;
    for (kind = 0; kind < PFM_KIND_COUNT; ++kind)
        if (strcmp(pfm_kind_name(kind), kn) == 0) break;
    if (kind == PFM_KIND_COUNT) return 1;
    if (pfm_surface_make(&surf, W, W, 1.0, pfm_params_default(kind)) != 0) return 1;
    rg.state = 12345u;
    for (li = 0; li < NL; ++li) {
        double cz = cos(85.0 * PI / 180) + (1.0 - cos(85.0 * PI / 180)) * pfm_rng_uniform(&rg);
        double ph = 2.0 * PI * pfm_rng_uniform(&rg), st = sqrt(1.0 - cz * cz);
        lights[li][0] = st * cos(ph);
        lights[li][1] = st * sin(ph);
        lights[li][2] = cz;
    }
    memset(se, 0, sizeof se);
    for (az = 0; az < 2; ++az) {
        double wo[3], phi = (10.0 + 90.0 * az) * PI / 180.0;
        wo[0] = sin(theta) * cos(phi);
        wo[1] = sin(theta) * sin(phi);
        wo[2] = cos(theta);
        pfm_visibility_map(&surf, wo, vis_full);
        for (fy = 0; fy < W; fy += N)
            for (fx = 0; fx < W; fx += N) {
                double m[5];
                pf_slope_stats s0, s;
                pf_vec3 vo = pf_vec3_make(wo[0], wo[1], wo[2]), nb;
                pfm_footprint_moments(&surf, fx, fy, N, m);
                s0 = pf_slope_moments_stats(pf_slope_moments_make(m[0], m[1], m[2], m[3], m[4]), 0.0);
                s = pf_slope_moments_stats(pf_slope_moments_make(m[0], m[1], m[2], m[3], m[4]), BASE_SIGMA * BASE_SIGMA);
                nb = pf_beckmann_mesonormal(s0);
                pfm_visibility_map_box(&surf, wo, fx, fy, N, vis_full, box_o);
                for (li = 0; li <= NL; ++li) {
                    double wi[3], h[3], hz, hs[2];
                    double A = 0, front = 0, dh = 0, dhg = 0, ref, nov;
                    pfm_shade sh;
                    int x, y, mirror = li == NL;
                    pf_vec3 vi;
                    double lead, dg, gs, gs0, gt, po, ai_s, hyb[NH];
                    if (!mirror) memcpy(wi, lights[li], sizeof wi);
                    else {
                        double d = nb.x * wo[0] + nb.y * wo[1] + nb.z * wo[2];
                        wi[0] = 2 * d * nb.x - wo[0];
                        wi[1] = 2 * d * nb.y - wo[1];
                        wi[2] = 2 * d * nb.z - wo[2];
                        if (!(wi[2] > 0.02)) continue;
                    }
                    for (y = 0; y < N; ++y)
                        for (x = 0; x < N; ++x) vis_i[(size_t)(fy + y) * W + fx + x] = (unsigned char)pfm_visible(&surf, fx + x, fy + y, wi);
                    pfm_visibility_map_box(&surf, wi, fx, fy, N, vis_i, box_i);
                    sh = pfm_reference_shade(&surf, box_o, box_i, fx, fy, N, wo, wi, BASE_SIGMA, 1.0);
                    if (!(sh.area > 0.25 * wo[2])) { ncull++; break; }
                    ref = sh.spec;
                    nov = pfm_reference_shade(&surf, NULL, NULL, fx, fy, N, wo, wi, BASE_SIGMA, 1.0).spec;
                    /* the histogram's factors: mean D_t(h) without and with G_t */
                    h[0] = wo[0] + wi[0]; h[1] = wo[1] + wi[1]; h[2] = wo[2] + wi[2];
                    hz = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                    hs[0] = -h[0] / h[2]; hs[1] = -h[1] / h[2];
                    for (y = 0; y < N; ++y)
                        for (x = 0; x < N; ++x) {
                            double sx, sy, at, q, dt, lo, lii;
                            pfm_slope(&surf, fx + x, fy + y, &sx, &sy);
                            at = wo[2] - sx * wo[0] - sy * wo[1];
                            A += at;
                            if (!(at > 0)) continue;
                            front += at;
                            q = 0.5 * ((hs[0] - sx) * (hs[0] - sx) + (hs[1] - sy) * (hs[1] - sy)) / (BASE_SIGMA * BASE_SIGMA);
                            dt = exp(-q) / (2 * PI * BASE_SIGMA * BASE_SIGMA) * pow(hz / h[2], 4.0);
                            lo = pfmi_lobe_lambda(wo, sx, sy, BASE_SIGMA);
                            lii = pfmi_lobe_lambda(wi, sx, sy, BASE_SIGMA);
                            dh += dt;
                            if (lo >= 0 && lii >= 0) dhg += dt / (1 + lo + lii);
                        }
                    A /= N * N; front /= N * N; dh /= N * N; dhg /= N * N;
                    vi = pf_vec3_make(wi[0], wi[1], wi[2]);
                    lead = pf_leadr_specular(vo, vi, s, 1.0);
                    dg = pf_beckmann_d(pf_vec3_normalize(pf_vec3_add(vo, vi)), s);
                    gs = pf_beckmann_masking_shadowing(vo, vi, s);
                    gs0 = pf_beckmann_masking_shadowing(vo, vi, s0);
                    gt = dh > 0 ? dhg / dh : 1.0;
                    po = pf_beckmann_facing_area(vo, s);
                    ai_s = pf_beckmann_light_lambda_stats(vi, s);
                    (void)ai_s;
                    hyb[0] = ref;
                    hyb[1] = nov * gs0;
                    hyb[2] = lead;
                    hyb[3] = dg > 0 ? lead * dh / dg : 0;
                    hyb[4] = lead * gt;
                    hyb[5] = lead * gs0 / gs;
                    hyb[6] = dg > 0 ? lead * dhg / dg : 0;
                    hyb[7] = dg > 0 ? lead * dhg / dg * gs0 / gs : 0;
                    /* 1/(P_o + A Lambda_i) with P_o the histogram's front area instead of the Gaussian's */
                    {
                        double lam_i = 1.0 / gs - 1.0 - pf_beckmann_lambda(vo, s);
                        double g_lead = 1.0 / (po + A * lam_i), g_hist = 1.0 / (front + A * lam_i);
                        hyb[8] = lead * g_hist / g_lead;
                    }
                    hyb[9] = nov > 0 ? nov * (ref / nov) : 0;
                    hyb[10] = lead * gs0 / gs * gt;
                    hyb[11] = lead * post_gt(wo, wi, s0, hs, QQ);
                    hyb[12] = pf_leadr_specular_base(vo, vi, s, BASE_SIGMA * BASE_SIGMA, 1.0);
                    for (k = 0; k < NH; ++k) se[k] += (hyb[k] - ref) * (hyb[k] - ref);
                    sr += ref * ref;
                    nsamp++;
                    if (mirror && ref > 0 && lead > 0 && dh > 0) {
                        double w2 = ref * ref;
                        wsum += w2;
                        lr_lead += w2 * log(lead / ref);
                        lr_or += w2 * log(hyb[1] / ref);
                        lr_d += w2 * log(dg / dh);
                        lr_gt += w2 * log(gt);
                        lr_g += w2 * log(gs / gs0);
                        lr_a += w2 * log(sh.area / A);
                        lr_vis += w2 * log(ref / nov);
                        lr_a += w2 * log(hyb[11] / lead);
                        if (getenv("GD_VERBOSE"))
                            printf("fp %3d %3d az %d: A %.4f front %.4f Po %.4f | D_g/D_h %.3f <G_t> %.3f G(s) %.3f G(s0) %.3f vis_ref %.3f | "
                                   "lead/ref %.3f orac/ref %.3f ref %.3g\n",
                                   fx, fy, az, A, front, po, dg / dh, gt, gs, gs0, ref / nov, lead / ref, hyb[1] / ref, ref);
                    }
                }
            }
    }
    printf("%s, view %.0f deg, 64 x 64 footprints, %ld samples (%ld footprint-views culled)\n", kn, theta * 180 / PI, nsamp,
           ncull);
    for (k = 1; k < NH; ++k) printf("  %-45s rel_l2 %.3f\n", hname[k], sqrt(se[k] / sr));
    printf("mirror light, ref^2-weighted geometric means of the factor ratios (method / oracle):\n"
           "  leadr/ref %.3f  oracle/ref %.3f  D_gauss/D_hist %.3f  1/<G_t> %.3f  G(s)/G(s0) %.3f  ref_vis %.3f  1/<G_t>post %.3f\n",
           exp(lr_lead / wsum), exp(lr_or / wsum), exp(lr_d / wsum), exp(-lr_gt / wsum), exp(lr_g / wsum), exp(lr_vis / wsum), exp(-lr_a / wsum));
    return 0;
}

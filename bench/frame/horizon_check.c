/* horizon_check.c - the frame's HDF conventions against the brute force's march, on
   bench/frame/frame.c's plane: (1) per texel of level 0, the HDF step (visible iff the
   direction's elevation is above the horizon T of its azimuth, the two stored azimuths mixed)
   against pfm_visible, for the plane's light and a spread of its view directions, with the
   direction as the frame passes it and mirrored / rotated / transposed; (2) per pixel of the
   plane with a footprint under 2 texels, the frame's trilinear HDF visibility
   (pf_horizon_visibility_gauss of horizon_inputs' moments) against the march at the pixel's
   texel; (3) by footprint band, against the box and the pixel reference (full occluders): the
   true visibility of the reflecting texels V_t = R / N (N: the same reference with every march
   visible), Smith's G and the horizon's V_h as the frame evaluates them, the error of N x each
   (the visibility alone, exact NDF) and of L1 x V_t (the filtered NDF alone), the conditional
   visibilities toward wo and wi at the half vector's slope, and two variants of V_h: without
   the conditioning (Vunc) and conditioned on statistics that keep the base lobe's variance
   (Vh(bv), base_var = 0 passed; hor(bv=0) the whole method so). An experiment, not a step of
   make bench (full size: 13 s of CPU).
     cc -std=c99 -O2 -Ibench -Iinclude -Itests -Itests/reference -Itests/gpu -pthread \
        bench/frame/horizon_check.c -o build/bench/horizon_check -lvulkan -lm
     [BENCH_QUICK=1] build/bench/horizon_check */
#define _POSIX_C_SOURCE 200809L
#include "pf_microsurface.h"
static int g_novis; /* 1: the references without visibility (every march visible) */
static int pfm_visible_chk(const pfm_surface *s, int x, int y, const double w[3]) { return g_novis || pfm_visible(s, x, y, w); }
#define pfm_visible pfm_visible_chk
#define main frame_main_unused
#include "frame.c"
#undef pfm_visible
#undef main
enum { V_ID, V_MIRY, V_MIRX, V_ROT, V_SWAP, NV };
static const char *const vname[NV] = {"as passed", "y mirrored", "x mirrored", "rotated pi", "x<->y"};
static void xform(int v, const double *w, double *o)
{
    o[0] = w[0], o[1] = w[1], o[2] = w[2];
    if (v == V_MIRY) o[1] = -w[1];
    if (v == V_MIRX) o[0] = -w[0];
    if (v == V_ROT) o[0] = -w[0], o[1] = -w[1];
    if (v == V_SWAP) o[0] = w[1], o[1] = w[0];
}
/* level-0 HDF T of texel (x, y) toward w (the two azimuths mixed) */
static double hdf_T(const fr_maps *m, int x, int y, const double *w)
{
    pf_horizon_azimuth a = pf_horizon_azimuth_of(pf_vec3_make((pf_real)w[0], (pf_real)w[1], (pf_real)w[2]), HOR_AZ);
    const pf_real *t = m->hdf_pyr + ((size_t)y * m->W + x) * 3 * HOR_AZ;
    return (1.0 - (double)a.f) * (double)t[3 * a.i0] + (double)a.f * (double)t[3 * a.i1];
}
/* (3) the specular's visibility alone: per pixel the reference R (full occluders) and the same
   texels without visibility N, so V_true = R / N; the methods' visibility: LEADR's Smith G2
   (LEADR over its value with G = 1) and the horizon's V_h (pf_horizon_specular_visibility); the
   error of N G and N V_h against R isolates the visibility (the exact-histogram NDF), the error
   of L1 V_true (L1 = LEADR with G = 1 from the trilinear moments) the filtered NDF alone. */
static void part3(const pfm_surface *surf, const fr_maps *maps, const fr_scene *sc, int ref_max)
{
    int npx = sc->w * sc->h, W = surf->w, H = surf->h, r, i, k;
    unsigned char *vis = malloc((size_t)W * H), *ones = malloc((size_t)W * H);
    static const char *const col[] = {"LEADR", "horizon", "N*G", "N*Vh", "L1*Vt", "mean Vt", "mean G", "mean Vh", "V_i brute", "V_i hdf", "V_o brute", "V_o hdf", "L1/N", "LEADR/R", "hor/R", "Vo|s_h", "Vi|s_h", "N*Vunc", "N*Vh(bv)", "Vunc", "Vh(bv)", "hor(bv=0)"};
    enum { NC = 22 };
    memset(ones, 1, (size_t)W * H);
    pfm_visibility_map(surf, sc->light, vis);
    for (r = 0; r < 2; ++r) {
        double *R = calloc(npx, 8), *N = calloc(npx, 8), *scr = calloc(npx, 8), fl, e[8][NC];
        int ns = 0, c[8];
        double zs[4][6];
        memset(zs, 0, sizeof zs);
        memset(e, 0, sizeof e), memset(c, 0, sizeof c);
        g_novis = 0;
        references(surf, vis, sc, ref_max, r ? -PIXEL_REF_SEED : 0, R, NULL, NULL, NULL, NULL);
        g_novis = 1;
        references(surf, ones, sc, ref_max, r ? -PIXEL_REF_SEED : 0, N, NULL, NULL, NULL, NULL);
        g_novis = 0;
        for (i = 0; i < npx; ++i)
            if (sc->px[i].hit) scr[ns++] = R[i];
        fl = LIT_FRACTION * quantile(scr, ns, 0.99);
        for (i = 0; i < npx; ++i) {
            const pic_sample *p = &sc->px[i];
            double rx = sqrt(p->off[0] * p->off[0] + p->off[1] * p->off[1]), ry = sqrt(p->off[2] * p->off[2] + p->off[3] * p->off[3]),
                   rho = rx > ry ? rx : ry, lod = rho > 1 ? log2(rho) : 0, v[NC], L1, G, Vh, Vt;
            pf_vec3 wo = pf_vec3_make((pf_real)p->wo[0], (pf_real)p->wo[1], (pf_real)p->wo[2]),
                    wi = pf_vec3_make((pf_real)p->wi[0], (pf_real)p->wi[1], (pf_real)p->wi[2]);
            pf_slope_stats st;
            pf_hdf_moments mo, mi;
            float a[4], b[4];
            int br, ba, tx, ty;
            if (!p->hit || !(R[i] >= fl) || !(N[i] > 0)) continue;
            band_of(p, &br, &ba);
            fetch(maps, p->tx / W, p->ty / H, lod, a, b);
            horizon_inputs(maps, p->tx / W, p->ty / H, lod, wo, wi, &st, &mo, &mi);
            {
                pf_real ao = wo.z - st.mean_x * wo.x - st.mean_y * wo.y;
                L1 = (double)pf_beckmann_d(pf_vec3_add(wo, wi), st) * 0.25 / (double)ao;
            }
            v[0] = shade_method(MT_LEADR, a, b, p->wo, p->wi);
            v[1] = shade_horizon_cpu(maps, p->tx / W, p->ty / H, lod, p->wo, p->wi);
            G = v[0] / L1;
            Vh = pf_horizon_specular_visibility(wo, wi, mo, mi, st, (pf_real)(BASE_SIGMA * BASE_SIGMA));
            Vt = R[i] / N[i];
            v[2] = N[i] * G, v[3] = N[i] * Vh, v[4] = L1 * Vt;
            tx = pfmi_wrap((int)floor(p->tx), W), ty = pfmi_wrap((int)floor(p->ty), H);
            for (k = 0; k < 5; ++k) e[br][k] += rel(v[k], R[i], fl), e[7][k] += rel(v[k], R[i], fl);
            {
                double add[10] = {Vt, G, Vh, vis[(size_t)ty * W + tx], pf_horizon_visibility_gauss(mi, pf_horizon_elevation(wi)),
                                 pfm_visible(surf, tx, ty, p->wo), pf_horizon_visibility_gauss(mo, pf_horizon_elevation(wo)),
                                 L1 / N[i], v[0] / R[i], v[1] / R[i]};
                pf_slope_stats ts = pf_horizon_texel_stats(st, (pf_real)(BASE_SIGMA * BASE_SIGMA));
                pf_vec3 hh = pf_vec3_add(wo, wi);
                double shx = -hh.x / hh.z, shy = -hh.y / hh.z;
                double vou = pf_horizon_visibility_gauss(mo, pf_horizon_elevation(wo)), viu = pf_horizon_visibility_gauss(mi, pf_horizon_elevation(wi));
                double vunc = vou * (double)pf_horizon_bidir_tan((pf_real)viu, (pf_real)vou, pf_vec3_dot(wo, wi));
                double vbv = pf_horizon_specular_visibility(wo, wi, mo, mi, st, 0);
                double add2[7] = {pf_horizon_visibility_given_slope(wo, mo, ts, (pf_real)shx, (pf_real)shy),
                                  pf_horizon_visibility_given_slope(wi, mi, ts, (pf_real)shx, (pf_real)shy),
                                  rel(N[i] * vunc, R[i], fl), rel(N[i] * vbv, R[i], fl), vunc, vbv,
                                  rel(pf_horizon_leadr_specular_lod(wo, wi, st, 0, mo, mi, (pf_real)F0, (pf_real)lod, (pf_real)HOR_LOD_FULL, (pf_real)HOR_LOD_SMITH), R[i], fl)};
                for (k = 0; k < 7; ++k) e[br][15 + k] += add2[k], e[7][15 + k] += add2[k];
                if (br == 0) { /* under 2 texels: by the half vector's distance from the footprint's slopes along wi */
                    double rr = sqrt(p->wi[0] * p->wi[0] + p->wi[1] * p->wi[1]), dx = p->wi[0] / rr, dy = p->wi[1] / rr;
                    double vs = (double)ts.var_x * dx * dx + (double)ts.var_y * dy * dy + 2.0 * (double)ts.cov_xy * dx * dy;
                    double z = fabs(shx * dx + shy * dy - ((double)ts.mean_x * dx + (double)ts.mean_y * dy)) / sqrt(vs > 1e-30 ? vs : 1e-30);
                    int zb = z < 1 ? 0 : (z < 3 ? 1 : (z < 10 ? 2 : 3));
                    zs[zb][0]++, zs[zb][1] += Vt, zs[zb][2] += add2[1], zs[zb][3] += viu, zs[zb][4] += Vh, zs[zb][5] += rel(N[i] * Vh, R[i], fl);
                }
                for (k = 0; k < 10; ++k) e[br][5 + k] += add[k], e[7][5 + k] += add[k];
            }
            c[br]++, c[7]++;
        }
        printf("(3) %s reference, lit pixels: mean relative error of the methods and of N x visibility; mean visibilities\n",
               r ? "pixel" : "box");
        printf("%-8s %6s", "band", "pixels");
        for (k = 0; k < NC; ++k) printf(" %9s", col[k]);
        printf("\n");
        for (k = 0; k < 8; ++k) {
            static const char *const bn[8] = {"<2", "2-4", "4-8", "8-16", "16-32", "32-64", ">=64", "all"};
            int j = k < 7 ? k : 7;
            if (!c[j]) continue;
            printf("%-8s %6d", bn[j], c[j]);
            for (r = r, i = 0; i < NC; ++i) printf(i < 5 || i == 17 || i == 18 || i == 21 ? " %8.1f%%" : " %9.3f", (i < 5 || i == 17 || i == 18 || i == 21 ? 100 : 1) * e[j][i] / c[j]);
            printf("\n");
        }
        printf("    under 2 texels by z = |s_h - E[S]| / sd_S along wi (texel stats): pixels, V_t, V_i given s_h, V_i unconditioned, V_h, error of N V_h\n");
        for (k = 0; k < 4; ++k) {
            static const char *const zn[4] = {"z < 1", "1-3", "3-10", ">= 10"};
            if (zs[k][0] > 0)
                printf("    %-6s %6.0f %.3f %.3f %.3f %.3f %5.1f%%\n", zn[k], zs[k][0], zs[k][1] / zs[k][0], zs[k][2] / zs[k][0], zs[k][3] / zs[k][0],
                       zs[k][4] / zs[k][0], 100 * zs[k][5] / zs[k][0]);
        }
        free(R), free(N), free(scr);
    }
    free(vis), free(ones);
}

/* (4) under 2 texels, toward the light: the footprint's slope deviation along wi's azimuth
   (texel stats, base variance off), the half vector's slope there in those deviations
   (z = |s_h - E[S]| / sd_S), and the conditional visibility against the unconditioned one,
   by z */
static void part4(const fr_maps *maps, const fr_scene *sc)
{
    int npx = sc->w * sc->h, W = maps->W, H = maps->H, i, k;
    double n[4] = {0}, sd[4] = {0}, vc[4] = {0}, vu[4] = {0};
    for (i = 0; i < npx; ++i) {
        const pic_sample *p = &sc->px[i];
        double rx = sqrt(p->off[0] * p->off[0] + p->off[1] * p->off[1]), ry = sqrt(p->off[2] * p->off[2] + p->off[3] * p->off[3]),
               rho = rx > ry ? rx : ry, lod = rho > 1 ? log2(rho) : 0, dx, dy, r, vs, z, sh;
        pf_vec3 wo = pf_vec3_make((pf_real)p->wo[0], (pf_real)p->wo[1], (pf_real)p->wo[2]),
                wi = pf_vec3_make((pf_real)p->wi[0], (pf_real)p->wi[1], (pf_real)p->wi[2]), hh;
        pf_slope_stats st, ts;
        pf_hdf_moments mo, mi;
        if (!p->hit || rho >= 2.0) continue;
        horizon_inputs(maps, p->tx / W, p->ty / H, lod, wo, wi, &st, &mo, &mi);
        ts = pf_horizon_texel_stats(st, (pf_real)(BASE_SIGMA * BASE_SIGMA));
        r = sqrt(p->wi[0] * p->wi[0] + p->wi[1] * p->wi[1]), dx = p->wi[0] / r, dy = p->wi[1] / r;
        vs = (double)ts.var_x * dx * dx + (double)ts.var_y * dy * dy + 2.0 * (double)ts.cov_xy * dx * dy;
        hh = pf_vec3_add(wo, wi);
        sh = -((double)hh.x * dx + (double)hh.y * dy) / (double)hh.z;
        z = fabs(sh - ((double)ts.mean_x * dx + (double)ts.mean_y * dy)) / sqrt(vs > 1e-30 ? vs : 1e-30);
        k = z < 1 ? 0 : (z < 3 ? 1 : (z < 10 ? 2 : 3));
        n[k]++, sd[k] += sqrt(vs > 0 ? vs : 0);
        vc[k] += (double)pf_horizon_visibility_given_slope(wi, mi, ts, -hh.x / hh.z, -hh.y / hh.z);
        vu[k] += (double)pf_horizon_visibility_gauss(mi, pf_horizon_elevation(wi));
    }
    printf("(4) under 2 texels, toward the light: z = |s_h - E[S]| / sd_S along wi's azimuth\n");
    for (k = 0; k < 4; ++k) {
        static const char *const zn[4] = {"z < 1", "1-3", "3-10", ">= 10"};
        if (n[k] > 0)
            printf("   %-6s %6.0f pixels: mean sd_S %.4f, V_i given s_h %.3f, unconditioned %.3f\n", zn[k], n[k], sd[k] / n[k], vc[k] / n[k],
                   vu[k] / n[k]);
    }
}

int main(void)
{
    const char *q = getenv("BENCH_QUICK");
    int quick = q && *q && strcmp(q, "0");
    int w = quick ? 160 : 400, h = quick ? 100 : 250, W = MAP_SIZE, H = MAP_SIZE, npx = w * h, i, v, k, x, y;
    pfm_surface surf;
    fr_maps maps;
    fr_scene sc;
    double dirs[8][3];
    int nd = 0;
    if (pfm_surface_make(&surf, W, H, 1.0, pfm_params_default(PFM_GAUSSIAN)) != 0 || maps_build(&surf, &maps, 0, NULL, NULL) != 0)
        return 1;
    scene_make(&sc, 0, w, h, &surf, 0.0, 1.0);
    /* the light, then views from pixels spread down the image's centre column and a corner */
    memcpy(dirs[nd++], sc.light, sizeof dirs[0]);
    for (k = 0; k < 7; ++k) {
        int j = h - 1 - k * (h / 2) / 7, ii = k < 4 ? w / 2 : (k == 4 ? 0 : w - 1);
        const pic_sample *p = &sc.px[(size_t)j * w + ii];
        if (p->hit) memcpy(dirs[nd++], p->wo, sizeof dirs[0]);
    }
    printf("(1) level 0, per texel with m.w > 0: agreement of the HDF step with pfm_visible\n");
    printf("%-34s", "direction (az deg, elev deg)  vis");
    for (v = 0; v < NV; ++v) printf(" %11s", vname[v]);
    printf("\n");
    for (k = 0; k < nd; ++k) {
        const double *d = dirs[k];
        double el = atan2(d[2], sqrt(d[0] * d[0] + d[1] * d[1]));
        long agree[NV] = {0}, n = 0, nvis = 0;
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x) {
                double sx, sy;
                int bv;
                pfm_slope(&surf, x, y, &sx, &sy);
                if (!(d[2] - sx * d[0] - sy * d[1] > 0.0)) continue;
                bv = pfm_visible(&surf, x, y, d);
                n++, nvis += bv;
                for (v = 0; v < NV; ++v) {
                    double o[3];
                    xform(v, d, o);
                    agree[v] += (el > hdf_T(&maps, x, y, o)) == bv;
                }
            }
        printf("%s (%6.1f, %5.1f)             %5.1f%%", k ? "view " : "light", atan2(d[1], d[0]) * 180 / pic_pi, el * 180 / pic_pi,
               100.0 * nvis / n);
        for (v = 0; v < NV; ++v) printf(" %10.1f%%", 100.0 * agree[v] / n);
        printf("\n");
    }
    printf("(2) plane pixels, footprint rho_max < 2 texels: the frame's HDF visibility (Gaussian, trilinear at log2 rho_max) "
           "against pfm_visible at the pixel's texel; mean |V_hdf - V_march| (and agreement of V_hdf > 0.5)\n");
    for (k = 0; k < 2; ++k) {
        double err[NV] = {0}, agr[NV] = {0};
        long n = 0;
        double mv = 0;
        for (i = 0; i < npx; ++i) {
            const pic_sample *p = &sc.px[i];
            double rx = sqrt(p->off[0] * p->off[0] + p->off[1] * p->off[1]), ry = sqrt(p->off[2] * p->off[2] + p->off[3] * p->off[3]),
                   rho = rx > ry ? rx : ry, lod = rho > 1 ? log2(rho) : 0;
            const double *d = k ? p->wi : p->wo;
            int tx, ty, bv;
            double sx, sy;
            if (!p->hit || rho >= 2.0) continue;
            tx = pfmi_wrap((int)floor(p->tx), W), ty = pfmi_wrap((int)floor(p->ty), H);
            pfm_slope(&surf, tx, ty, &sx, &sy);
            if (!(d[2] - sx * d[0] - sy * d[1] > 0.0)) continue;
            bv = pfm_visible(&surf, tx, ty, d);
            n++, mv += bv;
            for (v = 0; v < NV; ++v) {
                double o[3], vh;
                pf_slope_stats st;
                pf_hdf_moments mo, mi;
                xform(v, d, o);
                {
                    pf_vec3 vo = pf_vec3_make((pf_real)o[0], (pf_real)o[1], (pf_real)o[2]);
                    horizon_inputs(&maps, p->tx / W, p->ty / H, lod, vo, vo, &st, &mo, &mi);
                    vh = pf_horizon_visibility_gauss(mo, pf_horizon_elevation(pf_vec3_make((pf_real)d[0], (pf_real)d[1], (pf_real)d[2])));
                }
                err[v] += fabs(vh - bv);
                agr[v] += (vh > 0.5) == bv;
            }
        }
        printf("%s: %ld pixels, marched visible %.1f%%\n", k ? "light" : "view ", n, 100.0 * mv / (n ? n : 1));
        for (v = 0; v < NV; ++v) printf("   %-11s mean |dV| %.3f, agreement %.1f%%\n", vname[v], err[v] / n, 100.0 * agr[v] / n);
    }
    part4(&maps, &sc);
    part3(&surf, &maps, &sc, quick ? 32 : 64);
    return 0;
}

/* bench/plane_vis_diag.c - where the plane picture's horizon specular departs from the brute force
   at 4-16-texel footprints (views 75-84 degrees from the zenith). Not part of `make bench`: a
   diagnostic, built and run by hand (docs/horizon.md, "Specular in the pictures"):
       cc -std=c99 -O2 [-DPF_DOUBLE] -Ibench -Iinclude -Itests/reference bench/plane_vis_diag.c -lm -o /tmp/pvd
       /tmp/pvd
   For every plane pixel of bench/pictures.c's camera (400 x 250) with a footprint under 32 texels,
   over the round(side)^2 box of the reference of that time (bench/pic_scenes.h, shade_reference),
   weights w_t = each texel's unshadowed specular term times its projected area. First table, per
   footprint band, pooled with the pixel's unshadowed radiance: the brute force's visibility of
   the reflecting texels (joint, toward the view, toward the light), eq. 28 applied to its own
   V_o and V_i, the level-0 horizon map's step, pf_horizon_specular_visibility from the box's
   exact HDF and slope moments (and its two directions), a Gaussian fitted to the reflecting
   texels' own horizons, and V_o V_i. Second table: mean relative error (pixels lit in either the
   reference or the exact-box horizon row) and bias of LEADR and LEADR + horizon with the
   trilinear moments and/or HDF against the exact box ones. Last lines: the pixels whose box has
   a non-positive projected area (reference 0) and what LEADR and LEADR + horizon return there. */
#include "pf_bench_base.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pf_moments.h"
#include "pf_beckmann.h"
#include "pf_horizon.h"
#include "pf_microsurface.h"
#include "pic_scenes.h"
#define HN 32
#define NB 5
static int W, H;
static pf_real *hor0;
static pf_real *spyr, *hpyr;
static pf_hdf_moments hdf_tri(const pic_sample *p, const double w[3])
{
    const int nl = pf_mip_level_count(W, H), C = 3 * HN;
    pf_horizon_azimuth az = pf_horizon_azimuth_of(pf_vec3_make(w[0], w[1], w[2]), HN);
    double lod = p->fp > 1.0 ? log2(p->fp) : 0.0, fl, acc[2][3] = {{0, 0, 0}, {0, 0, 0}};
    double u = p->tx / W - floor(p->tx / W), v = p->ty / H - floor(p->ty / H);
    int l0, lv, t, q, a;
    if (lod > nl - 1) lod = nl - 1;
    l0 = (int)floor(lod); fl = lod - l0;
    for (lv = 0; lv < 2; ++lv) {
        int l = l0 + lv, lw, lh; double wl = lv ? fl : 1.0 - fl, x, y, fx, fy; long ix, iy; const pf_real *lev;
        if (!(wl > 0.0) || l >= nl) continue;
        lw = pf_mip_level_size(W, l); lh = pf_mip_level_size(H, l);
        lev = hpyr + pf_mip_level_offset(W, H, l) * C;
        x = u * lw - 0.5; y = v * lh - 0.5; ix = (long)floor(x); iy = (long)floor(y); fx = x - ix; fy = y - iy;
        for (t = 0; t < 4; ++t) {
            double wt = wl * ((t & 1) ? fx : 1.0 - fx) * ((t & 2) ? fy : 1.0 - fy);
            long tx = wrap_index((int)(ix + (t & 1)), lw), ty = wrap_index((int)(iy + (t >> 1)), lh);
            const pf_real *tex = lev + ((size_t)ty * (size_t)lw + (size_t)tx) * (size_t)C;
            if (!(wt > 0.0)) continue;
            for (a = 0; a < 2; ++a) for (q = 0; q < 3; ++q) acc[a][q] += wt * (double)tex[3 * (a ? az.i1 : az.i0) + q];
        }
    }
    return pf_hdf_moments_lerp(pf_hdf_moments_make(acc[0][0], acc[0][1], acc[0][2]), pf_hdf_moments_make(acc[1][0], acc[1][1], acc[1][2]), az.f);
}
static double T_at(int x, int y, const double w[3], double *S) /* level-0 horizon lerped, and S*T */
{
    pf_vec3 v = pf_vec3_make((pf_real)w[0], (pf_real)w[1], (pf_real)w[2]);
    pf_horizon_azimuth az = pf_horizon_azimuth_of(v, HN);
    const pf_real *t = hor0 + ((size_t)wrap_index(y, H) * W + wrap_index(x, W)) * 3 * HN;
    double f = az.f;
    *S = (1 - f) * t[3 * az.i0 + 2] + f * t[3 * az.i1 + 2];
    return (1 - f) * t[3 * az.i0] + f * t[3 * az.i1];
}
int main(int argc, char **argv)
{
    int w = 400, h = 250, i, j, b;
    pic_camera cam;
    double light[3];
    pfm_params pp = pfm_params_default(PFM_GAUSSIAN);
    pfm_surface s;
    pf_real *hts;
    unsigned char *vl;
    /* per band sums: U (unshadowed ref), and U * V for: true joint, true o, true i, eq28(true o, true i),
       horizon-map step joint, model exact box, Smith G2 box, model with the reflecting texels' own (T) mean/var */
    enum { V_TRUE, V_O, V_I, V_EQ28, V_MAP, V_MAPO, V_MAPI, V_MODEL, V_MODO, V_MODI, V_OWNG, V_OWNGO, V_OWNGI, V_PROD, NV };
    static const char *nm[NV] = {"true", "true_o", "true_i", "eq28(true)", "map step", "map o", "map i", "model box",
                                 "model o", "model i", "own-gauss", "own-g o", "own-g i", "true o*i"};
    double acc[NB][NV], accU[NB], sumz[NB];
    int cnt[NB], nsa[NB] = {0}; double negL[NB] = {0}, negH[NB] = {0};
    static double mv[8][200000]; static int pb[200000]; int npx = 0;
    (void)argc; (void)argv;
    memset(acc, 0, sizeof acc); memset(accU, 0, sizeof accU); memset(cnt, 0, sizeof cnt); memset(sumz, 0, sizeof sumz);
    pfm_surface_make(&s, MAP_SIZE, MAP_SIZE, 1.0, pp);
    W = s.w; H = s.h;
    hts = malloc(sizeof(pf_real) * W * H);
    for (i = 0; i < W * H; ++i) hts[i] = (pf_real)s.height[i];
    hor0 = malloc(sizeof(pf_real) * (size_t)W * H * 3 * HN);
    pf_horizon_map(hts, W, H, 1, HN, 64, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, hor0);
    spyr = malloc(sizeof(pf_real) * 5 * pf_mip_texel_count(W, H)); hpyr = malloc(sizeof(pf_real) * 3 * HN * pf_mip_texel_count(W, H));
    pf_slope_pyramid_from_heights(hts, W, H, 1, 1, 1, PF_BORDER_WRAP, spyr);
    pf_horizon_pyramid(hts, W, H, 1, HN, 64, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, hpyr);
    pic_scene_view(PIC_PLANE, w, h, 0.0, &cam, light);
    vl = malloc((size_t)W * H);
    pfm_visibility_map(&s, light, vl);
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i) {
            pic_sample p;
            int n, x0, y0, a, c, bb;
            double hz, sw = 0, sa = 0, sv[NV], mom[5] = {0}, hm[2][3] = {{0}}, cnt_t = 0;
            double ow[2][3] = {{0}}; /* weighted T, T^2 among reflecting texels, o and i */
            memset(&p, 0, sizeof p);
            pic_scene_pixel(PIC_PLANE, &cam, light, W, H, 0.0, i, j, &p);
            if (!p.hit || p.fp >= 32) continue;
            bb = p.fp < 2 ? 0 : p.fp < 4 ? 1 : p.fp < 8 ? 2 : p.fp < 16 ? 3 : 4;
            n = footprint_side(p.fp);
            x0 = footprint_start(p.tx, n); y0 = footprint_start(p.ty, n);
            hz = p.wo[2] + p.wi[2];
            memset(sv, 0, sizeof sv);
            for (c = 0; c < n; ++c)
                for (a = 0; a < n; ++a) {
                    int x = wrap_index(x0 + a, W), y = wrap_index(y0 + c, H), vo, vi;
                    double sx, sy, at, term, S, To, Ti, eo = asin(p.wo[2]), ei = asin(p.wi[2]);
                    pfm_slope(&s, x, y, &sx, &sy);
                    at = p.wo[2] - sx * p.wo[0] - sy * p.wo[1];
                    sa += at;
                    mom[0] += sx; mom[1] += sy; mom[2] += sx * sx; mom[3] += sy * sy; mom[4] += sx * sy;
                    To = T_at(x, y, p.wo, &S); hm[0][0] += To; hm[0][1] += To * To; hm[0][2] += S;
                    Ti = T_at(x, y, p.wi, &S); hm[1][0] += Ti; hm[1][1] += Ti * Ti; hm[1][2] += S;
                    cnt_t += 1;
                    if (!(at > 0)) continue;
                    term = pfm_reference_shade(&s, NULL, NULL, x, y, 1, p.wo, p.wi, BASE_SIGMA, F0).spec * at;
                    if (!(term > 0)) continue;
                    vo = pfm_visible(&s, x, y, p.wo);
                    vi = vl[(size_t)y * W + x];
                    sw += term;
                    sv[V_TRUE] += term * vo * vi; sv[V_O] += term * vo; sv[V_I] += term * vi;
                    sv[V_MAPO] += term * (eo > To); sv[V_MAPI] += term * (ei > Ti); sv[V_MAP] += term * (eo > To) * (ei > Ti);
                    ow[0][0] += term * To; ow[0][1] += term * To * To; ow[1][0] += term * Ti; ow[1][1] += term * Ti * Ti;
                }
            if (!(sa > 0)) { nsa[bb]++;
                { pf_real lod = p.fp > 1 ? log2(p.fp) : 0; double bv = BASE_SIGMA*BASE_SIGMA;
                  pf_vec3 wo = pf_vec3_make(p.wo[0], p.wo[1], p.wo[2]), wi = pf_vec3_make(p.wi[0], p.wi[1], p.wi[2]);
                  pf_slope_stats tst = pf_slope_moments_stats(pf_slope_moments_sample(spyr, W, H, lod, p.tx / W, p.ty / H, PF_BORDER_WRAP), (pf_real)bv);
                  pf_hdf_moments to = hdf_tri(&p, p.wo), ti = hdf_tri(&p, p.wi);
                  negL[bb] += pf_leadr_specular(wo, wi, tst, 1); negH[bb] += pf_horizon_leadr_specular_lod(wo, wi, tst, (pf_real)bv, to, ti, 1, lod, 2, 6); }
                continue; }
            if (!(sw > 0)) sw = 1e-300;
            {
                double U = sw / sa, k = cnt_t, vo, vi, al = 0.5 + 0.5 * (p.wo[0]*p.wi[0]+p.wo[1]*p.wi[1]+p.wo[2]*p.wi[2]);
                pf_slope_stats st = pf_slope_moments_stats(pf_slope_moments_make((pf_real)(mom[0]/k), (pf_real)(mom[1]/k), (pf_real)(mom[2]/k), (pf_real)(mom[3]/k), (pf_real)(mom[4]/k)), (pf_real)(BASE_SIGMA*BASE_SIGMA));
                pf_hdf_moments mo = pf_hdf_moments_make((pf_real)(hm[0][0]/k), (pf_real)(hm[0][1]/k), (pf_real)(hm[0][2]/k));
                pf_hdf_moments mi = pf_hdf_moments_make((pf_real)(hm[1][0]/k), (pf_real)(hm[1][1]/k), (pf_real)(hm[1][2]/k));
                pf_vec3 wo = pf_vec3_make(p.wo[0], p.wo[1], p.wo[2]), wi = pf_vec3_make(p.wi[0], p.wi[1], p.wi[2]);
                double tv[NV];
                int q;
                tv[V_TRUE] = sv[V_TRUE] / sw; tv[V_O] = sv[V_O] / sw; tv[V_I] = sv[V_I] / sw;
                tv[V_PROD] = tv[V_O] * tv[V_I];
                vo = tv[V_O]; vi = tv[V_I];
                tv[V_EQ28] = al * fmin(vo, vi) + (1 - al) * fmax(vo + vi - 1, 0);
                tv[V_MAP] = sv[V_MAP] / sw; tv[V_MAPO] = sv[V_MAPO] / sw; tv[V_MAPI] = sv[V_MAPI] / sw;
                tv[V_MODEL] = pf_horizon_specular_visibility(wo, wi, mo, mi, st, (pf_real)(BASE_SIGMA*BASE_SIGMA));
                { pf_real X = (pf_real)((p.wo[0]+p.wi[0])/hz + st.mean_x), Y = (pf_real)((p.wo[1]+p.wi[1])/hz + st.mean_y);
                  tv[V_MODO] = pfi_horizon_spec_cond_vis(wo, mo, st, (pf_real)(BASE_SIGMA*BASE_SIGMA), X, Y);
                  tv[V_MODI] = pfi_horizon_spec_cond_vis(wi, mi, st, (pf_real)(BASE_SIGMA*BASE_SIGMA), X, Y); }
                { double m0 = ow[0][0]/sw, v0 = fmax(ow[0][1]/sw - m0*m0, 1e-12), m1 = ow[1][0]/sw, v1 = fmax(ow[1][1]/sw - m1*m1, 1e-12);
                  double go = 0.5*erfc(-(asin(p.wo[2]) - m0)/sqrt(2*v0)), gi = 0.5*erfc(-(asin(p.wi[2]) - m1)/sqrt(2*v1));
                  tv[V_OWNGO] = go; tv[V_OWNGI] = gi; tv[V_OWNG] = al * fmin(go, gi) + (1 - al) * fmax(go + gi - 1, 0); }
                for (q = 0; q < NV; ++q) acc[bb][q] += U * tv[q];
                { double bv = BASE_SIGMA*BASE_SIGMA, ref = sv[V_TRUE] / sa;
                  double L = pf_leadr_specular(wo, wi, st, 1), Hb = pf_horizon_leadr_specular(wo, wi, st, (pf_real)bv, mo, mi, 1);
                  double G = pf_beckmann_base_masking(wo, wi, st, (pf_real)bv);
                  double Lb = pf_leadr_specular_base(wo, wi, st, (pf_real)bv, 1);
                  double Vh = tv[V_MODEL];
                  double DT = Vh > 0 ? Hb / Vh * tv[V_TRUE] : 0;
                  pf_real lod = p.fp > 1 ? log2(p.fp) : 0;
                  pf_slope_stats tst = pf_slope_moments_stats(pf_slope_moments_sample(spyr, W, H, lod, p.tx / W, p.ty / H, PF_BORDER_WRAP), (pf_real)bv);
                  pf_hdf_moments to = hdf_tri(&p, p.wo), ti = hdf_tri(&p, p.wi);
                  (void)G; (void)Lb; (void)DT;
                  mv[0][npx] = ref; mv[1][npx] = pf_leadr_specular(wo, wi, tst, 1); mv[2][npx] = Hb;
                  mv[3][npx] = pf_horizon_leadr_specular(wo, wi, tst, (pf_real)bv, to, ti, 1);
                  mv[4][npx] = pf_horizon_leadr_specular(wo, wi, tst, (pf_real)bv, mo, mi, 1);
                  mv[5][npx] = pf_horizon_leadr_specular(wo, wi, st, (pf_real)bv, to, ti, 1);
                  mv[6][npx] = pf_horizon_leadr_specular_lod(wo, wi, tst, (pf_real)bv, to, ti, 1, lod, 2, 6); mv[7][npx] = L;
                  pb[npx] = bb; npx++; }
                accU[bb] += U; cnt[bb]++; sumz[bb] += acos(p.wo[2]) * 180 / pic_pi;
            }
        }
    printf("band      n  zenith");
    for (b = 0; b < NV; ++b) printf(" %10s", nm[b]);
    printf("\n");
    for (b = 0; b < NB; ++b) {
        int q;
        printf("%-6s %5d %6.1f", (const char *[]){"<2", "2-4", "4-8", "8-16", "16-32"}[b], cnt[b], sumz[b] / (cnt[b] ? cnt[b] : 1));
        for (q = 0; q < NV; ++q) printf(" %10.4f", acc[b][q] / accU[b]);
        printf("\n");
    }
    { static const char *mn[8] = {"ref", "leadr tri", "hor box", "hor tri", "hor stats tri hdf box", "hor stats box hdf tri", "hor tri faded", "leadr box"};
      double *c = malloc(sizeof(double) * npx), fl; int k, q;
      for (k = 0; k < npx; ++k) c[k] = mv[0][k];
      qsort(c, npx, sizeof(double), cmp_double); fl = LIT_FRACTION * c[(int)(0.99 * (npx - 1))];
      printf("floor %g\nband   nlit ", fl); for (q = 1; q < 8; ++q) printf(" %22s", mn[q]); printf("   (mean rel err / bias)\n");
      for (b = 0; b < NB; ++b) { double e[8] = {0}, sm[8] = {0}; int nl = 0;
        for (k = 0; k < npx; ++k) if (pb[k] == b) { for (q = 0; q < 8; ++q) sm[q] += mv[q][k];
            if (mv[0][k] >= fl || mv[2][k] >= fl) { nl++; for (q = 1; q < 8; ++q) e[q] += fabs(mv[q][k] - mv[0][k]) / fmax(mv[0][k], fl); } }
        {int tot=0; for (k = 0; k < npx; ++k) tot += pb[k]==b; printf("%-6d %5d %6d %10.1f", b, nl, tot, sm[0]);} for (q = 1; q < 8; ++q) printf("   %8.1f%% / %6.3f", 100 * e[q] / nl, sm[q] / sm[0]); printf("\n"); } }
    for (b = 0; b < NB; ++b) printf("sa<=0 band %d: %d pixels, sum leadr tri %.1f, hor tri faded %.1f\n", b, nsa[b], negL[b], negH[b]);
    return 0;
}

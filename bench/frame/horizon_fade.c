/* horizon_fade.c - the frame's horizon method against LEADR on bench/frame/frame.c's plane, by
   footprint band, for several fades of pf_horizon_leadr_specular_lod (lod_full .. lod_smith;
   100 .. 200: no fade), on the CPU: trilinear at log2(rho_max) from the analytic ray
   differentials, against the box and the pixel reference (both with every occluder of the
   periodic height field). An experiment, not a step of make bench.
     cc -std=c99 -O2 -Ibench -Iinclude -Itests -Itests/reference -Itests/gpu -pthread \
        bench/frame/horizon_fade.c -o build/bench/horizon_fade -lvulkan -lm
     [BENCH_QUICK=1] build/bench/horizon_fade */
#define main frame_main_unused
#include "frame.c"
#undef main
static float hor_at(const fr_maps *m, double u, double v, double lod, const double wo_d[3], const double wi_d[3], double lf,
                    double ls)
{
    pf_vec3 wo = pf_vec3_make((float)wo_d[0], (float)wo_d[1], (float)wo_d[2]);
    pf_vec3 wi = pf_vec3_make((float)wi_d[0], (float)wi_d[1], (float)wi_d[2]);
    pf_slope_stats st;
    pf_hdf_moments mo, mi;
    float l = lod > 0.0 ? (float)lod : 0.0f;
    horizon_inputs(m, u, v, l, wo, wi, &st, &mo, &mi);
    return pf_horizon_leadr_specular_lod(wo, wi, st, (float)(BASE_SIGMA * BASE_SIGMA), mo, mi, (float)F0, l, (float)lf,
                                         (float)ls);
}
int main(void)
{
    const char *q = getenv("BENCH_QUICK");
    int quick = q && *q && strcmp(q, "0");
    int w = quick ? 160 : 400, h = quick ? 100 : 250, ref_max = quick ? 32 : 64, W = MAP_SIZE, H = MAP_SIZE, npx = w * h, i, k, x,
        y, r;
    pfm_surface surf;
    fr_maps maps;
    fr_scene sc;
    long long nt;
    double *ref[2], fl[2];
    unsigned char *lit[2], *vis;
    static const double lfs[][2] = {{2, 6}, {100, 200}, {0, 4}, {-1, 1}, {0, 2}, {1, 3}};
    enum { NVV = 7 };
    static double e[2][NVV][8];
    static int c[2][8];
    pfm_surface_make(&surf, W, H, 1.0, pfm_params_default(PFM_GAUSSIAN));
    nt = pf_mip_texel_count(W, H);
    maps.W = W, maps.H = H;
    maps.slope_pyr = malloc(sizeof(pf_real) * 5 * nt);
    maps.normal_pyr = malloc(sizeof(pf_real) * 3 * nt);
    maps.hdf_pyr = malloc(sizeof(pf_real) * 3 * HOR_AZ * nt);
    {
        pf_real *hts = malloc(sizeof(pf_real) * W * H), *nrm = malloc(sizeof(pf_real) * 3 * W * H);
        for (k = 0; k < W * H; ++k)
            hts[k] = (pf_real)surf.height[k];
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x) {
                double n[3];
                pfm_normal(&surf, x, y, n);
                for (k = 0; k < 3; ++k)
                    nrm[3 * (y * W + x) + k] = (pf_real)n[k];
            }
        pf_slope_pyramid_from_heights(hts, W, H, 1.0f, 1.0f, 1.0f, PF_BORDER_WRAP, maps.slope_pyr);
        pf_normal_pyramid_from_normals(nrm, W, H, maps.normal_pyr);
        pf_horizon_pyramid(hts, W, H, 1.0f, HOR_AZ, HOR_STEPS, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, maps.hdf_pyr);
    }
    scene_make(&sc, 0, w, h, &surf, 0.0, 1.0);
    vis = malloc((size_t)W * H);
    pfm_visibility_map(&surf, sc.light, vis);
    for (r = 0; r < 2; ++r) {
        double *scr = calloc(npx, 8);
        int ns = 0;
        ref[r] = calloc(npx, 8);
        lit[r] = calloc(npx, 1);
        references(&surf, vis, &sc, ref_max, r ? -PIXEL_REF_SEED : 0, ref[r], NULL, NULL, NULL, NULL);
        for (i = 0; i < npx; ++i)
            if (sc.px[i].hit)
                scr[ns++] = ref[r][i];
        fl[r] = LIT_FRACTION * quantile(scr, ns, 0.99);
        for (i = 0; i < npx; ++i)
            lit[r][i] = sc.px[i].hit && ref[r][i] >= fl[r];
    }
    for (i = 0; i < npx; ++i) {
        const pic_sample *p = &sc.px[i];
        float a[4], b[4];
        int br, ba, v;
        double rx = sqrt(p->off[0] * p->off[0] + p->off[1] * p->off[1]), ry = sqrt(p->off[2] * p->off[2] + p->off[3] * p->off[3]),
               rho = rx > ry ? rx : ry, lod = rho > 1 ? log2(rho) : 0;
        double val[NVV];
        if (!p->hit)
            continue;
        band_of(p, &br, &ba);
        fetch(&maps, p->tx / W, p->ty / H, lod, a, b);
        val[0] = shade_method(MT_LEADR, a, b, p->wo, p->wi);
        for (v = 0; v < 6; ++v)
            val[1 + v] = hor_at(&maps, p->tx / W, p->ty / H, lod, p->wo, p->wi, lfs[v][0], lfs[v][1]);
        for (r = 0; r < 2; ++r)
            if (lit[r][i]) {
                c[r][br]++;
                c[r][7]++;
                for (v = 0; v < NVV; ++v) {
                    double d = rel(val[v], ref[r][i], fl[r]);
                    e[r][v][br] += d;
                    e[r][v][7] += d;
                }
            }
    }
    for (r = 0; r < 2; ++r) {
        int v;
        printf("%s reference (trilinear at log2 rho_max, analytic derivatives): all | rho <2 2-4 4-8 8-16 16-32 32-64 >=64\n",
               r ? "pixel" : "box");
        for (v = 0; v < NVV; ++v) {
            if (v == 0)
                printf("%-26s", "LEADR");
            else
                printf("horizon fade %4.0f..%-4.0f    ", lfs[v - 1][0], lfs[v - 1][1]);
            printf(" %5.1f%% |", 100 * e[r][v][7] / c[r][7]);
            for (k = 0; k < 7; ++k)
                printf(" %5.1f%%", c[r][k] ? 100 * e[r][v][k] / c[r][k] : 0);
            printf("\n");
        }
    }
    return 0;
}

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
int main(void)
{
    const char *q = getenv("BENCH_QUICK");
    int quick = q && *q && strcmp(q, "0");
    int w = quick ? 160 : 400, h = quick ? 100 : 250, ref_max = quick ? 32 : 64, W = MAP_SIZE, H = MAP_SIZE, npx = w * h, i, k, r;
    pfm_surface surf;
    fr_maps maps;
    fr_scene sc;
    double *ref[2], fl[2];
    unsigned char *lit[2], *vis;
    static const double lfs[][2] = {{2, 6}, {100, 200}, {0, 4}, {-1, 1}, {0, 2}, {1, 3}};
    enum { NVV = 7 };
    static double e[2][NVV][8];
    static int c[2][8];
    if (pfm_surface_make(&surf, W, H, 1.0, pfm_params_default(PFM_GAUSSIAN)) != 0 || maps_build(&surf, &maps, 0, NULL, NULL) != 0)
        return 1;
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
            val[1 + v] = shade_horizon_fade(&maps, p->tx / W, p->ty / H, lod, p->wo, p->wi, lfs[v][0], lfs[v][1]);
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

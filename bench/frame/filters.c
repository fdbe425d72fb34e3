/* filters.c - anisotropic filters of the moment pyramid compared on the CPU, on bench/frame/
   frame.c's plane (its pixels, maps, references and trilinear fetch, included with its main
   renamed): LEADR's error against the pixel reference per footprint band (rho_max) and
   anisotropy ratio, for trilinear, the specification's 16x filter, frame.frag's taps, LEADR
   from the exact moments of the reference's texels, and (ALL=1) the taps with their level from
   rho_min - bias and caps of 16/32/64, and a grid over the pixel's parallelogram. The
   derivatives are the analytic ray differentials (pic_sample.off), not the GPU's quad ones.
   An experiment, not a step of make bench.
     cc -std=c99 -O2 -Ibench -Iinclude -Itests -Itests/reference -Itests/gpu -pthread \
        bench/frame/filters.c -o build/bench/filters -lvulkan -lm
     BENCH_QUICK=1 ALL=1 build/bench/filters      (SPT: the reference, frame.c's spt; default -1,
                                                   the covered-area integral with hash seed 1) */
#define main frame_main_unused
#include "frame.c"
#undef main

/* D: taps along the major axis, lod from rho_min - bias; N so that spacing <= 2^lod; capped */
static void fetch_taps2(const fr_maps *m, double tx, double ty, const float g[4], double bias, int nmax, int use_area_min,
                        float a[4], float b[4])
{
    double g0 = g[0], g1 = g[1], g2 = g[2], g3 = g[3];
    double rx = sqrt(g0 * g0 + g1 * g1), ry = sqrt(g2 * g2 + g3 * g3), rmax = rx > ry ? rx : ry, rmin = rx > ry ? ry : rx;
    double du = rx > ry ? g0 : g2, dv = rx > ry ? g1 : g3, N, lod, w;
    int i, k;
    if (use_area_min)
        rmin = fabs(g0 * g3 - g1 * g2) / (rmax > 1e-30 ? rmax : 1e-30);
    w = rmin * pow(2.0, -bias);
    if (w < 1.0)
        w = 1.0; /* tap width in texels */
    N = ceil(rmax / w);
    if (N < 1)
        N = 1;
    if (N > nmax) {
        N = nmax;
    }
    if (rmax / N > w)
        w = rmax / N;
    lod = log2(w);
    for (k = 0; k < 4; ++k)
        a[k] = b[k] = 0.0f;
    for (i = 0; i < (int)N; ++i) {
        float ta[4], tb[4];
        double f = ((double)i + 0.5) / N - 0.5;
        fetch(m, (tx + f * du) / m->W, (ty + f * dv) / m->H, lod, ta, tb);
        for (k = 0; k < 4; ++k)
            a[k] += ta[k], b[k] += tb[k];
    }
    for (k = 0; k < 4; ++k)
        a[k] /= (float)N, b[k] /= (float)N;
}
/* F: the footprint as an ellipse: taps along the major axis of the Jacobian J = (gx gy) (its
   first singular vector, length sigma_1: a box of that length has the parallelogram's variance
   along it), N = min(ceil(sigma_1 / sigma_2), nmax), lod log2(sigma_1 / N) */
static void fetch_taps_svd(const fr_maps *m, double tx, double ty, const float g[4], int nmax, float a[4], float b[4])
{
    double g0 = g[0], g1 = g[1], g2 = g[2], g3 = g[3];
    /* J J^T = [[g0^2 + g2^2, g0 g1 + g2 g3], [., g1^2 + g3^2]] */
    double p = g0 * g0 + g2 * g2, q = g0 * g1 + g2 * g3, r = g1 * g1 + g3 * g3;
    double tr = 0.5 * (p + r), d = sqrt(0.25 * (p - r) * (p - r) + q * q), l1 = tr + d, l2 = tr - d > 0.0 ? tr - d : 0.0;
    double s1 = sqrt(l1), s2 = sqrt(l2), ex, ey, n, N, lod;
    int i, k;
    if (fabs(q) > 1e-30) ex = l1 - r, ey = q;
    else if (p >= r) ex = 1.0, ey = 0.0;
    else ex = 0.0, ey = 1.0;
    n = sqrt(ex * ex + ey * ey);
    ex /= n, ey /= n;
    N = ceil(s1 / (s2 > 1e-6 * s1 + 1e-30 ? s2 : 1e-6 * s1 + 1e-30));
    N = N < 1.0 ? 1.0 : (N > nmax ? nmax : N);
    lod = s1 / N > 1.0 ? log2(s1 / N) : 0.0;
    for (k = 0; k < 4; ++k)
        a[k] = b[k] = 0.0f;
    for (i = 0; i < (int)N; ++i) {
        float ta[4], tb[4];
        double f = (((double)i + 0.5) / N - 0.5) * s1;
        fetch(m, (tx + f * ex) / m->W, (ty + f * ey) / m->H, lod, ta, tb);
        for (k = 0; k < 4; ++k)
            a[k] += ta[k], b[k] += tb[k];
    }
    for (k = 0; k < 4; ++k)
        a[k] /= (float)N, b[k] /= (float)N;
}
/* E: grid over the parallelogram: Na x Nb taps; cell size c = max(|gx|/Na, |gy|/Nb); lod log2(c) - bias */
static void fetch_grid(const fr_maps *m, double tx, double ty, const float g[4], double bias, int nmax, float a[4], float b[4])
{
    double g0 = g[0], g1 = g[1], g2 = g[2], g3 = g[3];
    double rx = sqrt(g0 * g0 + g1 * g1), ry = sqrt(g2 * g2 + g3 * g3);
    double c = 1.0, lod;
    int Na, Nb, i, j, k, n;
    /* smallest cell c (>= 1 texel, power-free) with ceil(rx/c)*ceil(ry/c) <= nmax */
    for (;;) {
        Na = (int)ceil(rx / c);
        Nb = (int)ceil(ry / c);
        if (Na < 1)
            Na = 1;
        if (Nb < 1)
            Nb = 1;
        if (Na * Nb <= nmax)
            break;
        c *= 1.0905077326652577;
    }
    c = rx / Na > ry / Nb ? rx / Na : ry / Nb;
    if (c < 1.0)
        c = 1.0;
    lod = log2(c) - bias;
    if (lod < 0)
        lod = 0;
    for (k = 0; k < 4; ++k)
        a[k] = b[k] = 0.0f;
    n = Na * Nb;
    for (j = 0; j < Nb; ++j)
        for (i = 0; i < Na; ++i) {
            float ta[4], tb[4];
            double fa = ((double)i + 0.5) / Na - 0.5, fb = ((double)j + 0.5) / Nb - 0.5;
            fetch(m, (tx + fa * g0 + fb * g2) / m->W, (ty + fa * g1 + fb * g3) / m->H, lod, ta, tb);
            for (k = 0; k < 4; ++k)
                a[k] += ta[k], b[k] += tb[k];
        }
    for (k = 0; k < 4; ++k)
        a[k] /= (float)n, b[k] /= (float)n;
}
#define NV 64
int main(int argc, char **argv)
{
    const char *q = getenv("BENCH_QUICK");
    int quick = q && *q && strcmp(q, "0");
    int w = quick ? 160 : 400, h = quick ? 100 : 250, ref_max = quick ? 32 : 64, W = MAP_SIZE, H = MAP_SIZE, npx = w * h, i, k, v,
        nl = 0, ns = 0;
    pfm_surface surf;
    fr_maps maps;
    fr_scene sc;
    double *ref, *orc, *lex, *scratch, fl;
    unsigned char *lit, *vis;
    static double err[NV][8][8];
    static int cnt[8][8];
    static double tot[NV];
    const char *vname[NV];
    int nv = 0;
    (void)argc;
    (void)argv;
    if (pfm_surface_make(&surf, W, H, 1.0, pfm_params_default(PFM_GAUSSIAN)) != 0 || maps_build(&surf, &maps, 0, NULL, NULL) != 0)
        return 1;
    scene_make(&sc, 0, w, h, &surf, 0.0, 1.0);
    vis = malloc((size_t)W * H);
    pfm_visibility_map(&surf, sc.light, vis);
    ref = calloc(npx, 8);
    orc = calloc(npx, 8);
    lex = calloc(npx, 8);
    scratch = calloc(npx, 8);
    lit = calloc(npx, 1);
    references(&surf, vis, &sc, ref_max, getenv("SPT") ? atoi(getenv("SPT")) : -1, ref, orc, lex, NULL, NULL);
    for (i = 0; i < npx; ++i)
        if (sc.px[i].hit)
            scratch[ns++] = ref[i];
    fl = LIT_FRACTION * quantile(scratch, ns, 0.99);
    for (i = 0; i < npx; ++i)
        nl += lit[i] = sc.px[i].hit && ref[i] >= fl;
    printf("lit %d\n", nl);
    for (i = 0; i < npx; ++i) {
        const pic_sample *p = &sc.px[i];
        float g[4], a[4], bb[4];
        double rx, ry, rmax, rmin;
        int bnd, rb;
        if (!lit[i])
            continue;
        for (k = 0; k < 4; ++k)
            g[k] = (float)p->off[k];
        rx = sqrt(p->off[0] * p->off[0] + p->off[1] * p->off[1]);
        ry = sqrt(p->off[2] * p->off[2] + p->off[3] * p->off[3]);
        rmax = rx > ry ? rx : ry;
        rmin = rx > ry ? ry : rx;
        bnd = rmax < 2 ? 0 : rmax < 4 ? 1 : rmax < 8 ? 2 : rmax < 16 ? 3 : rmax < 32 ? 4 : rmax < 64 ? 5 : 6;
        {
            double r = rmax / (rmin > 1e-9 ? rmin : 1e-9);
            rb = r < 2 ? 0 : r < 4 ? 1 : r < 8 ? 2 : r < 16 ? 3 : r < 32 ? 4 : 5;
        }
        cnt[bnd][rb]++;
        nv = 0;
#define ADD(name, val)                                                                                                           \
    do {                                                                                                                         \
        double e_ = rel((val), ref[i], fl);                                                                                      \
        vname[nv] = (name);                                                                                                      \
        err[nv][bnd][rb] += e_;                                                                                                  \
        tot[nv] += e_;                                                                                                           \
        nv++;                                                                                                                    \
    } while (0)
#define SH() (double)shade_method(MT_LEADR, a, bb, p->wo, p->wi)
        ADD("exact moments", lex[i]);
        fetch_sampler(&maps, p->tx, p->ty, g, 1.0, a, bb);
        ADD("trilinear", SH());
        fetch_sampler(&maps, p->tx, p->ty, g, 16.0, a, bb);
        ADD("spec 16x", SH());
        fetch_taps(&maps, p->tx, p->ty, g, a, bb);
        ADD("taps (current)", SH());
        if (!getenv("ALL"))
            continue;
        {
            static const double bs[] = {0, 0.5, 0.8, 1.0};
            static const int nm[] = {16, 32, 64};
            int ib, in;
            static char nmb[64][48];
            for (in = 0; in < 3; ++in)
                for (ib = 0; ib < 4; ++ib) {
                    fetch_taps2(&maps, p->tx, p->ty, g, bs[ib], nm[in], 0, a, bb);
                    snprintf(nmb[in * 4 + ib], 48, "taps rmin-%.1f N<=%d", bs[ib], nm[in]);
                    ADD(nmb[in * 4 + ib], SH());
                }
            for (in = 0; in < 3; ++in)
                for (ib = 0; ib < 4; ++ib) {
                    fetch_grid(&maps, p->tx, p->ty, g, bs[ib], nm[in], a, bb);
                    snprintf(nmb[12 + in * 4 + ib], 48, "grid -%.1f N<=%d", bs[ib], nm[in]);
                    ADD(nmb[12 + in * 4 + ib], SH());
                }
            fetch_taps_svd(&maps, p->tx, p->ty, g, 16, a, bb);
            ADD("taps, ellipse axes N<=16", SH());
            fetch_taps_svd(&maps, p->tx, p->ty, g, 64, a, bb);
            ADD("taps, ellipse axes N<=64", SH());
            fetch_taps2(&maps, p->tx, p->ty, g, 0.8, 32, 1, a, bb);
            ADD("taps area-rmin-0.8 N<=32", SH());
        }
    }
    printf("%-28s %8s |", "variant", "all");
    for (k = 0; k < 7; ++k)
        printf(" rho%-4d", 1 << (k + 1));
    printf("|");
    for (k = 0; k < 6; ++k)
        printf(" r<%-5d", 2 << k);
    printf("\n");
    printf("%-28s %8d |", "pixels", nl);
    for (k = 0; k < 7; ++k) {
        int c = 0;
        for (v = 0; v < 6; ++v)
            c += cnt[k][v];
        printf(" %7d", c);
    }
    printf("|");
    for (v = 0; v < 6; ++v) {
        int c = 0;
        for (k = 0; k < 7; ++k)
            c += cnt[k][v];
        printf(" %7d", c);
    }
    printf("\n");
    for (i = 0; i < nv; ++i) {
        printf("%-28s %7.1f%% |", vname[i], 100 * tot[i] / nl);
        for (k = 0; k < 7; ++k) {
            double e = 0;
            int c = 0;
            for (v = 0; v < 6; ++v)
                e += err[i][k][v], c += cnt[k][v];
            printf(" %6.1f%%", c ? 100 * e / c : 0);
        }
        printf("|");
        for (v = 0; v < 6; ++v) {
            double e = 0;
            int c = 0;
            for (k = 0; k < 7; ++k)
                e += err[i][k][v], c += cnt[k][v];
            printf(" %6.1f%%", c ? 100 * e / c : 0);
        }
        printf("\n");
    }
    return 0;
}

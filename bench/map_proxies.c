/* map_proxies.c - seven periodic 256 x 256 height maps that stand in for maps a user brings to
   `make bench MAP=...` (docs/horizon.md, "User maps"): none is a kind of the corpus
   (tests/reference/pf_microsurface.h). Written as raw little-endian float32 heights (texel
   units, any scale: the MAP path rescales to its RMS slope), one file per map in OUT_DIR:
     fbm_b24         fBm terrain, power spectrum 1/f^2.4, frequencies 1 .. 128 cycles per map
     fbm_b30         the same with 1/f^3 (smoother, longer correlation)
     fbm_b20_detail  1/f^2 from 4 cycles per map up (a detail texture)
     fbm_clipped     1/f^2.4 from 2 cycles, the heights above the 70th percentile flattened to
                     plateaus (slope times 0.1): an eroded / clipped terrain
     fbm_creased     -|fBm| (1/f^2.2 from 2 cycles): sharp valleys
     photo_peaky     exp(fBm 1/f^2 from 6 cycles, unit deviation) plus a little 1/f^0.5 grain: a
                     photographed-texture proxy with heavy-tailed slopes (kurtosis ~30)
     photo_stone     Worley F2 - F1 of 90 cells capped at 3 texels (flat stones, steep grout)
                     plus 1/f grain
   Spectral synthesis: Gaussian amplitudes of deviation f^(-beta/2) per frequency, the real
   part of the inverse DFT (naive, separable: a few seconds). CPU-only bench tool, not part of
   the library. Build and run:  make build/bench/map_proxies && build/bench/map_proxies /tmp/maps
   then e.g.  build/bench/microsurface --map /tmp/maps/fbm_b24.raw --map-raw-size 256x256 --no-cost */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define N 256
static const double mp_pi = 3.14159265358979323846;
static unsigned long long rng = 1;
static double rnd(void)
{
    rng = rng * 6364136223846793005ULL + 1442695040888963407ULL;
    return ((double)(rng >> 11) + 0.5) / 9007199254740992.0;
}
static double gauss(void)
{
    double u = rnd(), v = rnd();
    return sqrt(-2.0 * log(u)) * cos(2.0 * mp_pi * v);
}
/* in place: the inverse DFT of (re, im), separable, naive */
static void idft2(double *re, double *im)
{
    static double tr[N], ti[N], c[N], sn[N];
    int i, j, k, pass;
    for (k = 0; k < N; ++k) {
        c[k] = cos(2.0 * mp_pi * k / N);
        sn[k] = sin(2.0 * mp_pi * k / N);
    }
    for (pass = 0; pass < 2; ++pass)
        for (i = 0; i < N; ++i) {
            for (j = 0; j < N; ++j) {
                double a = 0.0, b = 0.0;
                for (k = 0; k < N; ++k) {
                    int idx = pass ? k * N + i : i * N + k, ph = (j * k) % N;
                    a += re[idx] * c[ph] - im[idx] * sn[ph];
                    b += re[idx] * sn[ph] + im[idx] * c[ph];
                }
                tr[j] = a;
                ti[j] = b;
            }
            for (j = 0; j < N; ++j) {
                int idx = pass ? j * N + i : i * N + j;
                re[idx] = tr[j];
                im[idx] = ti[j];
            }
        }
}
/* fBm: power spectrum 1/f^beta for fmin <= f <= fmax cycles per map; seed: the generator's */
static void fbm(double *h, double beta, double fmin, double fmax, unsigned long long seed)
{
    double *re = (double *)calloc(N * N, sizeof *re), *im = (double *)calloc(N * N, sizeof *im);
    int x, y, i;
    if (!re || !im) exit(1);
    rng = seed;
    for (y = 0; y < N; ++y)
        for (x = 0; x < N; ++x) {
            int fx = x <= N / 2 ? x : x - N, fy = y <= N / 2 ? y : y - N;
            double f = sqrt((double)fx * fx + (double)fy * fy), a, g1, g2;
            if (f < fmin || f > fmax) continue;
            a = pow(f, -0.5 * beta);
            g1 = gauss();
            g2 = gauss();
            re[y * N + x] = a * g1;
            im[y * N + x] = a * g2;
        }
    idft2(re, im);
    for (i = 0; i < N * N; ++i) h[i] = re[i];
    free(re);
    free(im);
}
static double rms(const double *h)
{
    double s = 0.0;
    int i;
    for (i = 0; i < N * N; ++i) s += h[i] * h[i];
    return sqrt(s / (N * N));
}
static int save(const char *dir, const char *name, const double *h)
{
    char p[1024];
    float f[N];
    FILE *o;
    int x, y;
    snprintf(p, sizeof p, "%s/%s.raw", dir, name);
    o = fopen(p, "wb");
    if (!o) return 1;
    for (y = 0; y < N; ++y) {
        for (x = 0; x < N; ++x) f[x] = (float)h[y * N + x];
        if (fwrite(f, 4, N, o) != N) break;
    }
    if (fclose(o) != 0 || y < N) return 1;
    printf("%s\n", p);
    return 0;
}
static int cmpd(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
static double percentile(const double *h, double q)
{
    double *c = (double *)malloc(sizeof *c * N * N), r;
    if (!c) exit(1);
    memcpy(c, h, sizeof *c * N * N);
    qsort(c, N * N, sizeof *c, cmpd);
    r = c[(int)(q * (N * N - 1))];
    free(c);
    return r;
}
int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    double *h = (double *)malloc(sizeof *h * N * N), *g = (double *)malloc(sizeof *g * N * N), sd, sg, hi;
    int i, x, y, k, bad = 0;
    if (!h || !g) return 1;
    fbm(h, 2.4, 1, N / 2, 11);
    bad |= save(dir, "fbm_b24", h);
    fbm(h, 3.0, 1, N / 2, 12);
    bad |= save(dir, "fbm_b30", h);
    fbm(h, 2.0, 4, N / 2, 13);
    bad |= save(dir, "fbm_b20_detail", h);
    fbm(h, 2.4, 2, N / 2, 14);
    hi = percentile(h, 0.7);
    for (i = 0; i < N * N; ++i) g[i] = h[i] > hi ? hi + 0.1 * (h[i] - hi) : h[i];
    bad |= save(dir, "fbm_clipped", g);
    fbm(h, 2.2, 2, N / 2, 15);
    for (i = 0; i < N * N; ++i) g[i] = -fabs(h[i]);
    bad |= save(dir, "fbm_creased", g);
    fbm(h, 2.0, 6, N / 2, 16);
    sd = rms(h);
    fbm(g, 0.5, 32, N / 2, 17);
    sg = rms(g);
    for (i = 0; i < N * N; ++i) h[i] = exp(h[i] / sd) + 0.03 * g[i] / sg;
    bad |= save(dir, "photo_peaky", h);
    {
        double px[90], py[90];
        rng = 99;
        for (k = 0; k < 90; ++k) {
            px[k] = rnd() * N;
            py[k] = rnd() * N;
        }
        fbm(g, 1.0, 16, N / 2, 18);
        sg = rms(g);
        for (y = 0; y < N; ++y)
            for (x = 0; x < N; ++x) {
                double d1 = 1e30, d2 = 1e30, e;
                for (k = 0; k < 90; ++k) {
                    double dx = fabs(x - px[k]), dy = fabs(y - py[k]), d;
                    if (dx > N / 2) dx = N - dx;
                    if (dy > N / 2) dy = N - dy;
                    d = sqrt(dx * dx + dy * dy);
                    if (d < d1) {
                        d2 = d1;
                        d1 = d;
                    } else if (d < d2) d2 = d;
                }
                e = d2 - d1;
                h[y * N + x] = (e > 3.0 ? 3.0 : e) + 0.08 * g[y * N + x] / sg;
            }
        bad |= save(dir, "photo_stone", h);
    }
    free(h);
    free(g);
    if (bad) fprintf(stderr, "map_proxies: cannot write to %s\n", dir);
    return bad;
}

/* test_map_downsample.c - tests of include/pf_map_downsample.h (the slope-preserving height
   downsampler, Wu et al. 2019 eqs. 9-10).

   The truth is never the module's own formula: against a dense least-squares solve of the
   same objective built here from its definition (long double normal equations with the mean
   constraint, Gaussian elimination); preserved mean slopes against the box map's on a bumpy
   surface; the description call against the positional solve; bad input through guarded
   buffers; the solver's safeguards on inputs that once returned garbage or did not stop.
   Same bodies in float and double; edge_* tests also run under -ffast-math. */
/* MAP_ANONYMOUS and MAP_NORESERVE for pf_test_guarded_alloc under -std=c99 (before any include) */
#if defined(__unix__) && !defined(_DEFAULT_SOURCE)
#  define _DEFAULT_SOURCE 1
#endif
#include "pf_map_downsample.h"
#include "pf_oracle.h"
#include "pf_test.h"
#include "pf_microsurface.h"

/* ------------------------------------------------------------------ slope-preserving downsampling
   The oracle rebuilds the objective from its definition (docs/vmf.md): the library's height
   slope stencil written out again here (central difference, wrapped or inside; one-sided
   (-3 v0 + 4 v1 - v2)/2 at a clamped end; v1 - v0 for 2 texels; 0 for 1), the 5-point
   Laplacian (wrapped, or the edge texel repeated), s* = factor x the block mean of the fine
   slopes, then minimizes |G H - s*|^2 + w |L H|^2 subject to mean(H) = mean(fine) by the
   bordered normal equations [A 1; 1^T 0], solved by Gaussian elimination with partial
   pivoting in long double. */
#define DS_MAXN 64
static long double ds_slope(const long double *v, long long stride, int i, int n, int wrap)
{
#define DSV(k) v[(long long)(k) * stride]
    if (n < 2) return 0.0L;
    if (wrap) return 0.5L * (DSV((i + 1) % n) - DSV((i + n - 1) % n));
    if (i > 0 && i < n - 1) return 0.5L * (DSV(i + 1) - DSV(i - 1));
    if (n == 2) return DSV(1) - DSV(0);
    if (i == 0) return 0.5L * (-3.0L * DSV(0) + 4.0L * DSV(1) - DSV(2));
    return 0.5L * (3.0L * DSV(n - 1) - 4.0L * DSV(n - 2) + DSV(n - 3));
#undef DSV
}
static int ds_nb(int i, int n, int wrap) { return wrap ? (i + n) % n : (i < 0 ? 0 : (i >= n ? n - 1 : i)); }

/* block-mean fine slopes x factor (per coarse texel), in long double */
static void ds_target(const pf_real *fine, int w, int h, int f, int wrap, long double *sx, long double *sy)
{
    static long double v[4096];
    int i, j, W = w / f, n = (w / f) * (h / f);
    for (i = 0; i < w * h; ++i) v[i] = (long double)fine[i];
    for (i = 0; i < n; ++i) sx[i] = sy[i] = 0.0L;
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i) {
            int t = (j / f) * W + i / f;
            sx[t] += ds_slope(v + (long long)j * w, 1, i, w, wrap) / f;
            sy[t] += ds_slope(v + i, w, j, h, wrap) / f;
        }
}
/* RMS over coarse texels of |slope of H - s*| (per coarse texel) */
static long double ds_slope_rms(const pf_real *coarse, int W, int H, int wrap, const long double *sx, const long double *sy)
{
    static long double v[DS_MAXN * 64];
    long double e = 0.0L;
    int i, j;
    for (i = 0; i < W * H; ++i) v[i] = (long double)coarse[i];
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i) {
            long double dx = ds_slope(v + (long long)j * W, 1, i, W, wrap) - sx[j * W + i];
            long double dy = ds_slope(v + i, W, j, H, wrap) - sy[j * W + i];
            e += dx * dx + dy * dy;
        }
    return sqrtl(e / (W * H));
}
/* the dense constrained least-squares solution (n = W H <= DS_MAXN); 0 when singular */
static int ds_dense(const pf_real *fine, int w, int h, int f, int wrap, long double reg, long double *out)
{
    static long double G[3 * DS_MAXN][DS_MAXN], M[DS_MAXN + 1][DS_MAXN + 2];
    long double sx[DS_MAXN], sy[DS_MAXN], e[DS_MAXN], mean = 0.0L;
    int W = w / f, H = h / f, n = W * H, i, j, k, r, c;
    ds_target(fine, w, h, f, wrap, sx, sy);
    for (i = 0; i < w * h; ++i) mean += (long double)fine[i];
    mean /= (long double)(w * h);
    /* rows of G: the operators applied to unit vectors */
    for (k = 0; k < n; ++k) {
        for (i = 0; i < n; ++i) e[i] = i == k ? 1.0L : 0.0L;
        for (j = 0; j < H; ++j)
            for (i = 0; i < W; ++i) {
                int t = j * W + i;
                G[t][k] = ds_slope(e + j * W, 1, i, W, wrap);
                G[n + t][k] = ds_slope(e + i, W, j, H, wrap);
                G[2 * n + t][k] = e[j * W + ds_nb(i - 1, W, wrap)] + e[j * W + ds_nb(i + 1, W, wrap)] +
                                  e[ds_nb(j - 1, H, wrap) * W + i] + e[ds_nb(j + 1, H, wrap) * W + i] - 4.0L * e[t];
            }
    }
    for (r = 0; r <= n; ++r)
        for (c = 0; c <= n + 1; ++c) M[r][c] = 0.0L;
    for (r = 0; r < n; ++r) {
        for (c = 0; c < n; ++c) {
            long double a = 0.0L;
            for (k = 0; k < 2 * n; ++k) a += G[k][r] * G[k][c];
            for (k = 2 * n; k < 3 * n; ++k) a += reg * G[k][r] * G[k][c];
            M[r][c] = a;
        }
        M[r][n] = 1.0L;
        M[n][r] = 1.0L;
        for (k = 0; k < n; ++k) M[r][n + 1] += G[k][r] * sx[k] + G[n + k][r] * sy[k];
    }
    M[n][n + 1] = mean * n;
    for (c = 0; c <= n; ++c) {
        int piv = c;
        for (r = c + 1; r <= n; ++r)
            if (fabsl(M[r][c]) > fabsl(M[piv][c])) piv = r;
        if (fabsl(M[piv][c]) < 1e-30L) return 0;
        for (k = 0; k <= n + 1; ++k) {
            long double t = M[c][k];
            M[c][k] = M[piv][k];
            M[piv][k] = t;
        }
        for (r = 0; r <= n; ++r)
            if (r != c) {
                long double q = M[r][c] / M[c][c];
                for (k = c; k <= n + 1; ++k) M[r][k] -= q * M[c][k];
            }
    }
    for (r = 0; r < n; ++r) out[r] = M[r][n + 1] / M[r][r];
    return 1;
}
/* a bumpy height map: a few sinusoids and sharp Gaussian bumps, seeded */
static void ds_bumpy(pf_real *fine, int w, int h, unsigned long long seed, double amp)
{
    pf_test_rng r;
    double cx[12], cy[12], a[12];
    int i, j, k;
    r = pf_test_rng_seed(seed);
    for (k = 0; k < 12; ++k) {
        cx[k] = pf_test_uniform_open(&r) * w;
        cy[k] = pf_test_uniform_open(&r) * h;
        a[k] = pf_test_uniform_open(&r) - 0.5;
    }
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i) {
            double z = 0.3 * sin(2.0 * PFM_PI * i / w) + 0.2 * cos(4.0 * PFM_PI * j / h + 0.3) +
                       0.15 * sin(2.0 * PFM_PI * (3.0 * i / w + 2.0 * j / h));
            for (k = 0; k < 12; ++k) {
                double dx = i - cx[k], dy = j - cy[k];
                z += a[k] * exp(-(dx * dx + dy * dy) / 2.5);
            }
            fine[j * w + i] = (pf_real)(amp * z);
        }
}

static void test_downsample_dense_oracle(void)
{
    static const int cases[][4] = { /* w, h, factor, wrap */
        { 8, 8, 2, 1 }, { 8, 8, 2, 0 }, { 12, 8, 4, 0 }, { 16, 8, 4, 1 }, { 6, 10, 2, 0 }, { 16, 4, 4, 0 }
    };
    pf_real fine[256], coarse[DS_MAXN], again[DS_MAXN], scratch[6 * DS_MAXN];
    long double ref[DS_MAXN], worst = 0.0L, worst_mean = 0.0L;
    const pf_real tol = sizeof(pf_real) == 4 ? PF_R(1e-6) : PF_R(1e-13);
    int c, worst_it = 0;
    for (c = 0; c < (int)(sizeof cases / sizeof cases[0]); ++c) {
        int w = cases[c][0], h = cases[c][1], f = cases[c][2], wrap = cases[c][3], n = (w / f) * (h / f), i, it = -1, rc;
        long double dev = 0.0L, err = 0.0L, m = 0.0L, mref = 0.0L;
        pf_real res = PF_R(-1.0);
        ds_bumpy(fine, w, h, 11u + (unsigned)c, 1.0);
        PF_CHECK(pf_map_downsample_scratch_size(w, h, f) == 6LL * n, "scratch size %lld", pf_map_downsample_scratch_size(w, h, f));
        rc = pfi_map_downsample_slopes(fine, w, h, f, wrap ? PF_BORDER_WRAP : PF_BORDER_CLAMP, PF_R(0.01), 400, tol, coarse,
                                      scratch, 6LL * n, &it, &res);
        PF_CHECK(rc == PF_OK, "case %d rc %d", c, rc);
        PF_CHECK(ds_dense(fine, w, h, f, wrap, 0.01L, ref), "case %d: oracle singular", c);
        for (i = 0; i < n; ++i) {
            m += (long double)coarse[i];
            mref += ref[i];
        }
        m /= n;
        mref /= n;
        for (i = 0; i < n; ++i) {
            dev += (ref[i] - mref) * (ref[i] - mref);
            err = fmaxl(err, fabsl((long double)coarse[i] - ref[i]));
        }
        dev = sqrtl(dev / n);
        PF_CHECK(err <= 500.0L * PF_TEST_EPS * dev, "case %d (%dx%d /%d %s): max error %Lg of rms %Lg (%Lg eps), %d iterations, residual %g",
                 c, w, h, f, wrap ? "wrap" : "clamp", err, dev, err / dev / PF_TEST_EPS, it, (double)res);
        PF_CHECK(it > 0 && it <= 400 && res <= tol * PF_R(1.01), "case %d: %d iterations, residual %g", c, it, (double)res);
        worst = fmaxl(worst, err / dev);
        worst_mean = fmaxl(worst_mean, fabsl(m - mref) / dev);
        if (it > worst_it) worst_it = it;
        /* deterministic: the same bits again */
        rc = pfi_map_downsample_slopes(fine, w, h, f, wrap ? PF_BORDER_WRAP : PF_BORDER_CLAMP, PF_R(0.01), 400, tol, again,
                                      scratch, 6LL * n, NULL, NULL);
        PF_CHECK(rc == PF_OK && memcmp(coarse, again, (size_t)n * sizeof(pf_real)) == 0, "case %d not deterministic", c);
    }
    PF_CHECK(worst_mean <= 8.0L * PF_TEST_EPS, "mean off by %Lg of the rms", worst_mean);
    pf_test_note("max error %.3Lg eps of the rms height (mean %.2Lg eps), <= %d iterations", worst / PF_TEST_EPS,
                 worst_mean / PF_TEST_EPS, worst_it);
}

/* the preserved map's slopes against the box map's on a bumpy 64 x 64 map, factors 2 and 4 */
static void test_downsample_beats_box(void)
{
    enum { N = 64 };
    static pf_real fine[N * N], coarse[N * N / 4], box[N * N / 4], scratch[6 * N * N / 4];
    static long double sx[N * N / 4], sy[N * N / 4];
    int f, wrap;
    for (wrap = 0; wrap < 2; ++wrap)
        for (f = 2; f <= 4; f += 2) {
            int W = N / f, n = W * W, i, j, it = 0, rc;
            long double e_box, e_pres;
            ds_bumpy(fine, N, N, 5u + (unsigned)f, 1.0);
            for (i = 0; i < n; ++i) box[i] = PF_R(0.0);
            for (j = 0; j < N; ++j)
                for (i = 0; i < N; ++i) box[(j / f) * W + i / f] += fine[j * N + i] / (pf_real)(f * f);
            rc = pfi_map_downsample_slopes(fine, N, N, f, wrap ? PF_BORDER_WRAP : PF_BORDER_CLAMP, PF_R(0.01), 2000,
                                          sizeof(pf_real) == 4 ? PF_R(1e-5) : PF_R(1e-10), coarse, scratch, 6LL * n, &it, NULL);
            PF_CHECK(rc == PF_OK, "rc %d", rc);
            ds_target(fine, N, N, f, wrap, sx, sy);
            e_box = ds_slope_rms(box, W, W, wrap, sx, sy);
            e_pres = ds_slope_rms(coarse, W, W, wrap, sx, sy);
            PF_CHECK(e_pres <= 0.8L * e_box, "factor %d %s: slope rms %Lg preserved, %Lg box", f, wrap ? "wrap" : "clamp", e_pres, e_box);
            {
                long double s2 = 0.0L;
                for (i = 0; i < n; ++i) s2 += sx[i] * sx[i] + sy[i] * sy[i];
                pf_test_note("/%d %s: slope rms error %.3Lg, box %.3Lg, of rms slope %.3Lg (%d it)", f, wrap ? "wrap" : "clamp",
                             e_pres / f, e_box / f, sqrtl(s2 / n) / f, it);
            }
        }
}

/* NaN heights not an edge_ test (-ffast-math) */
static void test_downsample_bad_input(void)
{
    enum { W = 8, H = 8, F = 2, NC = 16 };
    size_t fb = W * H * sizeof(pf_real), cb = NC * sizeof(pf_real), sb = 6 * NC * sizeof(pf_real);
    pf_real *fine = (pf_real *)pf_test_guarded_alloc(fb), *coarse = (pf_real *)pf_test_guarded_alloc(cb);
    pf_real *scratch = (pf_real *)pf_test_guarded_alloc(sb), res = PF_R(0.0);
    int i, it = -1, rc, untouched;
    if (!fine || !coarse || !scratch) {
        pf_test_note("skipped: no guarded mappings here");
        pf_test_guarded_free(fine, fb);
        pf_test_guarded_free(coarse, cb);
        pf_test_guarded_free(scratch, sb);
        return;
    }
#define DS_CALL(fn_, w_, h_, f_, b_, reg_, mi_, tol_, sl_) \
    pfi_map_downsample_slopes(fn_, w_, h_, f_, b_, reg_, mi_, tol_, coarse, scratch, sl_, &it, &res)
#define DS_UNTOUCHED() (untouched = 1, (void)0)
    ds_bumpy(fine, W, H, 3u, 1.0);
    for (i = 0; i < NC; ++i) coarse[i] = PF_R(-777.0);
    /* exactly sized buffers, guard pages right after each: a success touches no byte past them */
    rc = DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 100, PF_R(0.0), 6 * NC);
    PF_CHECK(rc == PF_OK && it >= 1, "guarded call: rc %d, %d iterations", rc, it);
    for (i = 0; i < NC; ++i) PF_CHECK(isfinite((double)coarse[i]) && coarse[i] != PF_R(-777.0), "texel %d", i);
    /* rejected calls write nothing */
    for (i = 0; i < NC; ++i) coarse[i] = PF_R(-777.0);
    it = -5;
    res = PF_R(-5.0);
    fine[9] = (pf_real)NAN;
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "NaN height");
    fine[9] = (pf_real)INFINITY;
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_CLAMP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "inf height");
    fine[9] = PF_R(0.25);
    PF_CHECK(DS_CALL(NULL, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "NULL fine");
    PF_CHECK(pfi_map_downsample_slopes(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), NULL, scratch, 6 * NC, &it, &res) == PF_ERR_ARG, "NULL coarse");
    PF_CHECK(pfi_map_downsample_slopes(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), coarse, NULL, 6 * NC, &it, &res) == PF_ERR_ARG, "NULL scratch");
    PF_CHECK(DS_CALL(fine, 0, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "w = 0");
    PF_CHECK(DS_CALL(fine, W, -3, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "h < 0");
    PF_CHECK(DS_CALL(fine, W, H, 0, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "factor 0");
    PF_CHECK(DS_CALL(fine, W, H, 3, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "factor 3 of 8");
    PF_CHECK(DS_CALL(fine, 7, 8, 2, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "odd width");
    PF_CHECK(DS_CALL(fine, W, H, F, 7, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "border 7");
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(-0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "negative weight");
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, (pf_real)NAN, 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "NaN weight");
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, (pf_real)INFINITY, 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "inf weight");
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(2.0e6), 10, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "weight above 1e6");
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), -1, PF_R(0.0), 6 * NC) == PF_ERR_ARG, "max_iter -1");
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, (pf_real)NAN, 6 * NC) == PF_ERR_ARG, "NaN tol");
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(-1.0), 6 * NC) == PF_ERR_ARG, "negative tol");
    PF_CHECK(DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC - 1) == PF_ERR_ARG, "scratch one short");
    PF_CHECK(DS_CALL(fine, (int)PF_MAX_SIDE + 2, 2, 2, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_SIZE, "side above the limit");
    PF_CHECK(PF_MAX_REALS > (1LL << 48) ||
                 DS_CALL(fine, (int)PF_MAX_SIDE, (int)PF_MAX_SIDE, 2, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), 6 * NC) == PF_ERR_SIZE,
             "2^48 texels accepted");
    untouched = 1;
    for (i = 0; i < NC; ++i)
        if (coarse[i] != PF_R(-777.0)) untouched = 0;
    PF_CHECK(untouched && it == -5 && res == PF_R(-5.0), "a rejected call wrote its outputs");
    PF_CHECK(pf_map_downsample_scratch_size(8, 8, 3) == 0 && pf_map_downsample_scratch_size(0, 8, 1) == 0 &&
                 pf_map_downsample_scratch_size(8, 8, 0) == 0 && pf_map_downsample_scratch_size((int)PF_MAX_SIDE + 1, 1, 1) == 0 &&
                 pf_map_downsample_scratch_size(1, 1, 1) == 6,
             "scratch sizes");
    /* a constant map: that constant, no iteration; max_iter 0: the box map */
    for (i = 0; i < W * H; ++i) fine[i] = PF_R(0.375);
    rc = DS_CALL(fine, W, H, F, PF_BORDER_CLAMP, PF_R(0.01), 50, PF_R(1e-3), 6 * NC);
    untouched = 1;
    for (i = 0; i < NC; ++i)
        if (coarse[i] != PF_R(0.375)) untouched = 0;
    PF_CHECK(rc == PF_OK && it == 0 && untouched, "constant map: rc %d, %d iterations", rc, it);
    ds_bumpy(fine, W, H, 3u, 1.0);
    rc = DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 0, PF_R(0.0), 6 * NC);
    for (i = 0; i < NC; ++i) {
        int I = i % 4, J = i / 4;
        long double b = ((long double)fine[(2 * J) * W + 2 * I] + (long double)fine[(2 * J) * W + 2 * I + 1] + (long double)fine[(2 * J + 1) * W + 2 * I] +
                         (long double)fine[(2 * J + 1) * W + 2 * I + 1]) / 4.0L;
        PF_CHECK(fabsl((long double)coarse[i] - b) <= 8.0L * PF_TEST_EPS, "max_iter 0: texel %d %g, box %Lg", i, (double)coarse[i], b);
    }
    PF_CHECK(rc == PF_OK && it == 0, "max_iter 0: rc %d, %d iterations", rc, it);
    /* heights near the largest pf_real: finite output, the same map as the unit-scale solve scaled */
    {
        pf_real unit[NC];
        rc = DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 200, PF_R(0.0), 6 * NC);
        for (i = 0; i < NC; ++i) unit[i] = coarse[i];
        for (i = 0; i < W * H; ++i) fine[i] *= PF_REAL_MAX / PF_R(4.0);
        rc = DS_CALL(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 200, PF_R(0.0), 6 * NC);
        for (i = 0; i < NC; ++i)
            PF_CHECK(isfinite((double)coarse[i]) && fabsl((long double)coarse[i] / (long double)(PF_REAL_MAX / PF_R(4.0)) - (long double)unit[i]) <= 1e-3L,
                     "huge heights: texel %d %g (unit %g)", i, (double)coarse[i], (double)unit[i]);
        PF_CHECK(rc == PF_OK, "huge heights rc %d", rc);
    }
#undef DS_CALL
#undef DS_UNTOUCHED
    pf_test_guarded_free(fine, fb);
    pf_test_guarded_free(coarse, cb);
    pf_test_guarded_free(scratch, sb);
}

/* finite heights under every build (also -ffast-math): finite output, mean kept */
static void edge_downsample_finite(void)
{
    enum { N = 16 };
    pf_real fine[N * N], coarse[N * N / 4], scratch[6 * N * N / 4];
    long double m = 0.0L, mf = 0.0L;
    int i, it = 0, rc, bad = 0;
    ds_bumpy(fine, N, N, 9u, 3.0);
    rc = pfi_map_downsample_slopes(fine, N, N, 2, PF_BORDER_CLAMP, PF_R(0.01), 300, PF_R(1e-5), coarse, scratch,
                                  6 * N * N / 4, &it, NULL);
    for (i = 0; i < N * N / 4; ++i) {
        if (!isfinite((double)coarse[i])) bad++;
        m += (long double)coarse[i];
    }
    for (i = 0; i < N * N; ++i) mf += (long double)fine[i];
    PF_CHECK(rc == PF_OK && bad == 0 && fabsl(m / (N * N / 4) - mf / (N * N)) <= 1e-4L, "rc %d, %d non-finite, mean %Lg vs %Lg", rc,
             bad, m / (N * N / 4), mf / (N * N));
}

/* pf_map_downsample_slopes(desc): the positional solve bit for bit; zero fields read as the
   documented defaults (factor 2, reg_weight 0.01, max_iter 400, tol 1e-5), negative ones as 0 */
static void test_downsample_desc(void)
{
    enum { W = 16, H = 16 };
    static pf_real fine[W * H], a[W * H], b[W * H], scr[6 * W * H];
    pf_map_downsample_desc d;
    int ia = -1, ib = -2, i;
    pf_real ra, rb;
    ds_bumpy(fine, W, H, 77ULL, 0.5);
    memset(&d, 0, sizeof d);
    d.fine = fine, d.w = W, d.h = H, d.border = PF_BORDER_WRAP;
    PF_CHECK(pf_map_downsample_slopes(&d, a, scr, 6 * W * H, &ia, &ra) == PF_OK &&
                 pfi_map_downsample_slopes(fine, W, H, 2, PF_BORDER_WRAP, PF_R(0.01), 400, PF_R(1.0e-5), b, scr, 6 * W * H, &ib,
                                           &rb) == PF_OK &&
                 memcmp(a, b, sizeof(pf_real) * (W / 2) * (H / 2)) == 0 && ia == ib && ra == rb,
             "defaults");
    d.factor = 4, d.reg_weight = PF_R(-1.0), d.max_iter = -1, d.tol = PF_R(-1.0);
    PF_CHECK(pf_map_downsample_slopes(&d, a, scr, 6 * W * H, &ia, &ra) == PF_OK &&
                 pfi_map_downsample_slopes(fine, W, H, 4, PF_BORDER_WRAP, PF_R(0.0), 0, PF_R(0.0), b, scr, 6 * W * H, &ib, &rb) ==
                     PF_OK &&
                 memcmp(a, b, sizeof(pf_real) * (W / 4) * (H / 4)) == 0 && ia == 0 && ib == 0,
             "negative fields read as 0 (the box map)");
    for (i = 0; i < (W / 4) * (H / 4); ++i) a[i] = PF_R(-7.0);
    PF_CHECK(pf_map_downsample_slopes(NULL, a, scr, 6 * W * H, &ia, &ra) == PF_ERR_ARG && a[0] == PF_R(-7.0), "NULL desc");
}

/* ================================================================== SAFETY: the downsampler's solver
   Reproducers of a solve that returned PF_OK with garbage (1e8 in float, 1e104 in double) and
   of one that did not stop, checked against the contract: finite, bounded iterations. */
/* pf_map_downsample_slopes on an 8 x 8 map of heights i % 3, factor 2, WRAP, reg 0 (and a
   tiny reg), tol 0: before, PF_OK with max |coarse| = 1.1e8 (float) / 4.0e104 (double) after
   100 iterations, and a solve with max_iter = INT_MAX that ran for minutes. The least-squares
   answer's largest magnitude is 1.3125; the iterations are bounded by 4 n + 256 (n = 16) */
static void edge_safety_downsample_solver(void)
{
    pf_real fine[64], coarse[16], scr[96], res = PF_R(-1.0), mx;
#ifdef PF_DOUBLE
    const pf_real tiny = PF_R(1.0e-260);
#else
    const pf_real tiny = PF_R(1.0e-30);
#endif
    const pf_real regs[3] = { PF_R(0.0), tiny, PF_R(0.0) };
    const int iters[3] = { 100, 100, 0x7fffffff };
    int k, i, it = -1, rc;
    for (k = 0; k < 3; ++k) {
        for (i = 0; i < 64; ++i) fine[i] = (pf_real)(i % 3);
        rc = pfi_map_downsample_slopes(fine, 8, 8, 2, PF_BORDER_WRAP, regs[k], iters[k], PF_R(0.0), coarse, scr, 96, &it, &res);
        mx = PF_R(0.0);
        for (i = 0; i < 16; ++i) mx = pf_test_bits_finite(coarse[i]) ? pf_max(mx, PF_FABS(coarse[i])) : PF_REAL_MAX;
        pf_test_note("reg %g max_iter %d: max |coarse| %.6g, %d it, residual %.2g", (double)regs[k], iters[k], (double)mx, it, (double)res);
        PF_CHECK(rc == PF_OK && PF_FABS(mx - PF_R(1.3125)) <= PF_R(1e-4) && it >= 0 && it <= 4 * 16 + 256 &&
                     pf_test_bits_finite(res) && res <= PF_R(1e-3),
                 "reg %g: rc %d max |coarse| %g (want 1.3125), %d iterations, residual %g", (double)regs[k], rc, (double)mx, it,
                 (double)res);
    }
    /* a NaN or infinite height is PF_ERR_ARG under -ffast-math too (tested on the bits), and
       nothing is written */
    for (i = 0; i < 16; ++i) coarse[i] = PF_R(-7.0);
    for (k = 0; k < 2; ++k) {
        volatile pf_real zero = PF_R(0.0);
        fine[13] = k == 0 ? zero / zero : PF_R(1.0) / zero;
        rc = pfi_map_downsample_slopes(fine, 8, 8, 2, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), coarse, scr, 96, &it, &res);
        PF_CHECK(rc == PF_ERR_ARG, "%s height: rc %d", k == 0 ? "NaN" : "inf", rc);
    }
    for (i = 0; i < 16; ++i) PF_CHECK(coarse[i] == PF_R(-7.0), "texel %d written on an error", i);
}

/* the same bound on a larger random map, every border and a range of reg, tol 0 and
   max_iter = INT_MAX: the solve ends within 4 n + 256 iterations, finite, with a true
   residual no larger than the box map's (it returns the box map otherwise) */
static void edge_safety_downsample_bounded(void)
{
    enum { W = 32, H = 32, F = 2, N = (W / F) * (H / F) };
    static pf_real fine[W * H], coarse[N], scr[6 * N];
    const pf_real regs[4] = { PF_R(0.0), PF_R(1e-30), PF_R(0.01), PF_R(1e6) };
    int b, k, i, it, rc, worst_it = 0, bad = 0;
    pf_real res;
    ds_bumpy(fine, W, H, 11u, 3.0);
    for (i = 0; i < W * H; i += 7) fine[i] += (pf_real)((i * 37) % 5); /* spikes */
    for (b = 0; b < 2; ++b)
        for (k = 0; k < 4; ++k) {
            rc = pfi_map_downsample_slopes(fine, W, H, F, b == 0 ? PF_BORDER_WRAP : PF_BORDER_CLAMP, regs[k], 0x7fffffff,
                                          PF_R(0.0), coarse, scr, 6 * N, &it, &res);
            bad += rc != PF_OK || it < 0 || it > 4 * N + 256 || !pf_test_bits_finite(res);
            for (i = 0; i < N; ++i) bad += !pf_test_bits_finite(coarse[i]);
            worst_it = it > worst_it ? it : worst_it;
        }
    pf_test_note("tol 0, max_iter INT_MAX: at most %d iterations (bound %d)", worst_it, 4 * N + 256);
    PF_CHECK(bad == 0, "%d bad results", bad);
}

/* ================================================================== end of SAFETY */

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_downsample_desc);
    PF_TEST_RUN(test_downsample_dense_oracle);
    PF_TEST_RUN(test_downsample_beats_box);
    PF_TEST_RUN(test_downsample_bad_input);
    PF_TEST_RUN(edge_downsample_finite);
    PF_TEST_RUN(edge_safety_downsample_solver);
    PF_TEST_RUN(edge_safety_downsample_bounded);
    return PF_TEST_END();
}

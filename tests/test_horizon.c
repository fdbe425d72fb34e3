/* test_horizon.c - pf_horizon.h against independent oracles: a long double brute-force march
   of the horizon (own bilinear sampler), a fine march of the continuous bilinear surface,
   per-footprint means of oracle moments (the pyramid), eq. 26 by counting texels, Legendre
   coefficients by quadrature of explicit polynomials, the bivariate-Gaussian masking term by
   quadrature; the bidirectional limits; bad input with guarded buffers. */
#define _DEFAULT_SOURCE
#include "pf_horizon.h"
#include "pf_encode.h"
#include "pf_test.h"
#include "pf_microsurface.h"

/* test_horizon_specular_brute_force: measured 0.510 (float and double; 0.486 before the convexity term and
   the 0.7 deviation of the conditional HDF) against 0.987 for Smith */
#define HSPEC_BRUTE_BOUND 0.6
/* test_horizon_masking_skewed_brute_force: measured 0.0418 (float and double) against 0.0449 for
   the Gaussian HDF (pf_horizon_masking before the skew) */
#define SKEW_BRUTE_BOUND 0.043
/* test_horizon_specular_grazing_brute_force, views 75 and 80 degrees: |bias - 1| and pooled
   error of V_h on the correlation-12 and -4 fields (measured, float: bias 1.008 / 1.078, error
   0.034 / 0.205; bias 1.047 / 1.066, error 0.261 / 0.402; the linear conditioning without the
   convexity term and the 0.7 deviation: 0.987 / 1.080, 0.047 / 0.275; 0.692 / 0.702,
   0.416 / 0.436); at 85 degrees: error 0.199 and 0.548 (without: 0.257 and 0.781) */
static const double HSPEC_GRAZE_BIAS[2] = { 0.12, 0.12 }, HSPEC_GRAZE_ERR[2] = { 0.25, 0.45 };
static const double HSPEC_GRAZE_ERR_85[2] = { 0.24, 0.65 };

#define TPI 3.14159265358979323846264338327950288L

/* ---------------------------------------------------------------- oracle helpers */
static long double ora_node(const pf_real *hm, int w, int h, long long ix, long long iy, int wrap)
{
    if (wrap) {
        ix = ((ix % w) + w) % w;
        iy = ((iy % h) + h) % h;
    } else {
        if (ix < 0) ix = 0;
        if (ix > w - 1) ix = w - 1;
        if (iy < 0) iy = 0;
        if (iy > h - 1) iy = h - 1;
    }
    return (long double)hm[iy * w + ix];
}

static long double ora_bilinear(const pf_real *hm, int w, int h, long double px, long double py, int wrap)
{
    long double fx = floorl(px), fy = floorl(py), u = px - fx, v = py - fy;
    long long ix = (long long)fx, iy = (long long)fy;
    return (1.0L - v) * ((1.0L - u) * ora_node(hm, w, h, ix, iy, wrap) + u * ora_node(hm, w, h, ix + 1, iy, wrap)) +
           v * ((1.0L - u) * ora_node(hm, w, h, ix, iy + 1, wrap) + u * ora_node(hm, w, h, ix + 1, iy + 1, wrap));
}

/* horizon elevation of node (i, j) toward azimuth phi: samples every `step` texels up to dmax */
static long double ora_horizon(const pf_real *hm, int w, int h, int i, int j, long double phi, long double spacing,
                               long double step, long double dmax, int wrap)
{
    long double h0 = (long double)hm[(long long)j * w + i], best = -1e300L, d;
    long double c = cosl(phi), s = sinl(phi);
    if (fabsl(c) < 1e-15L) c = 0.0L;
    if (fabsl(s) < 1e-15L) s = 0.0L;
    long long xx[3], yy[3];
    pf_real cx[3], cy[3];
    long double sx = 0.0L, sy = 0.0L, sf;
    int q;
    for (d = step; d <= dmax + 1e-9L; d += step) {
        long double t = (ora_bilinear(hm, w, h, i + d * c, j + d * s, wrap) - h0) / (d * spacing);
        if (t > best) best = t;
    }
    /* the texel's own facet (the slope moments' central differences, one-sided at clamped
       edges: pf_map_slope_stencil) hides what is below it */
    pf_map_slope_stencil(i, w, wrap ? PF_BORDER_WRAP : PF_BORDER_CLAMP, PF_R(1.0), xx, cx);
    pf_map_slope_stencil(j, h, wrap ? PF_BORDER_WRAP : PF_BORDER_CLAMP, PF_R(1.0), yy, cy);
    for (q = 0; q < 3; ++q) {
        sx += (long double)cx[q] * (long double)hm[(long long)j * w + xx[q]];
        sy += (long double)cy[q] * (long double)hm[yy[q] * w + i];
    }
    sf = (sx * c + sy * s) / (2.0L * spacing);
    return atanl(sf > best ? sf : best);
}

/* a smooth random-ish height map: a few waves (periodic when wrap) plus a bump */
static void make_map(pf_real *hm, int w, int h, unsigned seed)
{
    pf_test_rng r;
    int i, j, k;
    double a[6], fx[6], fy[6], ph[6];
    r.state = seed;
    for (k = 0; k < 6; ++k) {
        a[k] = pf_test_uniform(&r, 0.3, 1.5);
        fx[k] = (double)(int)pf_test_uniform(&r, 0, 4);
        fy[k] = (double)(int)pf_test_uniform(&r, 0, 4);
        ph[k] = pf_test_uniform(&r, 0, 6.283);
    }
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i) {
            double v = 0.0;
            for (k = 0; k < 6; ++k) v += a[k] * sin(6.283185307179586 * (fx[k] * i / w + fy[k] * j / h) + ph[k]);
            v += 0.3 * pf_test_uniform(&r, -1, 1);
            hm[j * w + i] = (pf_real)v;
        }
}

#ifdef PF_DOUBLE
#  define ANG_TOL 1e-12L
#else
#  define ANG_TOL 2e-5L
#endif

/* ---------------------------------------------------------------- horizon angles */
static void test_horizon_angles_vs_brute_march(void)
{
    enum { W = 37, H = 29 };
    static pf_real hm[W * H], out[W * H * 16];
    int ns[3] = { 4, 8, 16 }, b, q, i, j, a;
    long double worst = 0.0L;
    make_map(hm, W, H, 11u);
    for (b = 0; b < 2; ++b)
        for (q = 0; q < 3; ++q) {
            int n = ns[q], rc = pf_horizon_map(hm, W, H, PF_R(0.7), n, 20, b ? PF_BORDER_WRAP : PF_BORDER_CLAMP,
                                               PF_HORIZON_ANGLES, 0, out);
            PF_CHECK(rc == PF_OK, "rc %d", rc);
            for (j = 0; j < H; ++j)
                for (i = 0; i < W; ++i)
                    for (a = 0; a < n; ++a) {
                        long double ref = ora_horizon(hm, W, H, i, j, 2.0L * TPI * a / n, 0.7L, 1.0L, 20.0L, b);
                        long double err = fabsl((long double)out[(j * W + i) * n + a] - ref);
                        if (err > worst) worst = err;
                    }
        }
    pf_test_note("max |angle error| %.3Lg rad (n = 4, 8, 16; wrap and clamp)", worst);
    PF_CHECK(worst <= ANG_TOL, "max error %Lg", worst);
}

/* The texel's own facet bounds its horizon from below: on a crest (a gentle rise to -x, a cliff
   to +x) the one-sided rise toward -x is negative but the central-difference facet tilts 43.5
   degrees toward +x, so a view toward -x below that is back-facing (what the reference's m.w > 0
   test hides). Toward +x the march is above the facet and decides. Checked for the angles and for
   the moments' E[T] (level 0). */
static void test_horizon_facet_plane(void)
{
    enum { W = 16, H = 4, N = 4 };
    static pf_real hm[W * H], ang[W * H * N], mom[W * H * 3 * N];
    int i, j;
    long double up, down;
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i) hm[j * W + i] = PF_R(i == 5 ? 1.0 : (i == 6 ? -1.0 : 0.9));
    PF_CHECK(pf_horizon_map(hm, W, H, PF_R(1.0), N, 12, PF_BORDER_WRAP, PF_HORIZON_ANGLES, 0, ang) == PF_OK, "rc");
    PF_CHECK(pf_horizon_map(hm, W, H, PF_R(1.0), N, 12, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, mom) == PF_OK, "rc");
    /* toward -x (azimuth 2 of 4): the facet, tan = (0.9 - (-1)) / 2; toward +x (azimuth 0):
       the march's best, the node 12 texels away, (0.9 - 1) / 12 */
    up = atanl(0.95L);
    down = atanl(-0.1L / 12.0L);
    for (j = 0; j < H; ++j) {
        long double a2 = (long double)ang[(j * W + 5) * N + 2], a0 = (long double)ang[(j * W + 5) * N + 0];
        long double m2 = (long double)mom[(j * W + 5) * 3 * N + 3 * 2];
        PF_CHECK(fabsl(a2 - up) <= ANG_TOL, "row %d: toward -x %.9Lg, facet %.9Lg", j, a2, up);
        PF_CHECK(fabsl(m2 - up) <= ANG_TOL, "row %d: E[T] toward -x %.9Lg, facet %.9Lg", j, m2, up);
        PF_CHECK(fabsl(a0 - down) <= ANG_TOL, "row %d: toward +x %.9Lg, march %.9Lg", j, a0, down);
    }
    pf_test_note("crest texel: horizon toward -x %.4f rad (facet), toward +x %.5f rad (march)",
                 (double)ang[5 * N + 2], (double)ang[5 * N]);
}

/* Along the axes the sampled horizon is the exact horizon of the bilinear surface (the
   tangent (h(d) - h0)/d is monotonic between nodes); off the axes it can only be lower. */
static void test_horizon_angles_vs_continuous_surface(void)
{
    enum { W = 24, H = 24 };
    static pf_real hm[W * H], out[W * H * 8];
    int i, j, a;
    long double worst_axis = 0.0L, worst_above = 0.0L, mean_diag = 0.0L;
    long cnt = 0;
    make_map(hm, W, H, 5u);
    PF_CHECK(pf_horizon_map(hm, W, H, PF_R(1.0), 8, 12, PF_BORDER_WRAP, PF_HORIZON_ANGLES, 0, out) == PF_OK, "rc");
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i)
            for (a = 0; a < 8; ++a) {
                long double fine = ora_horizon(hm, W, H, i, j, 2.0L * TPI * a / 8, 1.0L, 1.0L / 64.0L, 12.0L, 1);
                long double got = (long double)out[(j * W + i) * 8 + a];
                if (a % 2 == 0) {
                    if (fabsl(got - fine) > worst_axis) worst_axis = fabsl(got - fine);
                } else {
                    if (got - fine > worst_above) worst_above = got - fine;
                    mean_diag += fine - got;
                    ++cnt;
                }
            }
    pf_test_note("axes: max |error| %.3Lg rad against a 1/64-texel march; diagonals: mean deficit %.3Lg rad",
                 worst_axis, mean_diag / cnt);
    PF_CHECK(worst_axis <= ANG_TOL, "axis error %Lg", worst_axis);
    PF_CHECK(worst_above <= ANG_TOL, "diagonal sample above the continuous horizon by %Lg", worst_above);
}

/* The pyramid's texels are the footprint means of the oracle's (T, T^2, S T). */
static void test_horizon_pyramid_is_footprint_mean(void)
{
    enum { W = 32, N = 4 };
    static pf_real hm[W * W], pyr[(W * W * 4 / 3 + 8) * 3 * N];
    static long double T[W * W * N], S[W * W * N];
    int i, j, a, lvl;
    long double worst = 0.0L;
    make_map(hm, W, W, 23u);
    PF_CHECK((long long)(sizeof pyr / sizeof pyr[0]) >= pf_mip_texel_count(W, W) * 3 * N, "buffer");
    PF_CHECK(pf_horizon_pyramid(hm, W, W, PF_R(0.5), N, 16, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, pyr) == PF_OK, "rc");
    for (j = 0; j < W; ++j)
        for (i = 0; i < W; ++i) {
            long double sx = (ora_node(hm, W, W, i + 1, j, 1) - ora_node(hm, W, W, i - 1, j, 1)) / (2.0L * 0.5L);
            long double sy = (ora_node(hm, W, W, i, j + 1, 1) - ora_node(hm, W, W, i, j - 1, 1)) / (2.0L * 0.5L);
            for (a = 0; a < N; ++a) {
                long double phi = 2.0L * TPI * a / (long double)N;
                T[(j * W + i) * N + a] = ora_horizon(hm, W, W, i, j, phi, 0.5L, 1.0L, 16.0L, 1);
                S[(j * W + i) * N + a] = sx * (a == 1 || a == 3 ? 0.0L : cosl(phi)) + sy * (a == 0 || a == 2 ? 0.0L : sinl(phi));
            }
        }
    for (lvl = 0; lvl <= 5; ++lvl) {
        int side = W >> lvl, f = 1 << lvl, x, y;
        const pf_real *base = pyr + pf_mip_level_offset(W, W, lvl) * 3 * N;
        for (y = 0; y < side; ++y)
            for (x = 0; x < side; ++x)
                for (a = 0; a < N; ++a) {
                    long double m[3] = { 0, 0, 0 };
                    int c;
                    for (j = y * f; j < (y + 1) * f; ++j)
                        for (i = x * f; i < (x + 1) * f; ++i) {
                            long double t = T[(j * W + i) * N + a];
                            m[0] += t;
                            m[1] += t * t;
                            m[2] += S[(j * W + i) * N + a] * t;
                        }
                    for (c = 0; c < 3; ++c) {
                        long double err = fabsl((long double)base[(y * side + x) * 3 * N + 3 * a + c] - m[c] / (f * f));
                        if (err > worst) worst = err;
                    }
                }
    }
    pf_test_note("max |moment error| over all levels %.3Lg", worst);
    PF_CHECK(worst <= 40.0L * ANG_TOL, "max error %Lg", worst);
}

/* ---------------------------------------------------------------- eq. 26 by counting */
static long double inv_phi(long double p)
{
    long double lo = -12.0L, hi = 12.0L;
    int it;
    for (it = 0; it < 200; ++it) {
        long double mid = 0.5L * (lo + hi);
        if (0.5L * erfcl(-mid / sqrtl(2.0L)) < p) lo = mid;
        else hi = mid;
    }
    return 0.5L * (lo + hi);
}

/* A footprint whose horizon angles are the quantiles of a Gaussian: eq. 26 counted over its
   texels is the Gaussian CDF to 1/N, and pf_horizon_visibility_gauss from the texels' moments
   must match the count. The ramp's model error is measured (and bounded) too. */
static void test_horizon_eq26_gauss_counting(void)
{
    enum { N = 4000 };
    static long double th[N];
    long double m1 = 0.0L, m2 = 0.0L, worst = 0.0L, worst_ramp = 0.0L;
    int t, k;
    for (t = 0; t < N; ++t) {
        th[t] = 0.25L + 0.2L * inv_phi((t + 0.5L) / (long double)N);
        m1 += th[t];
        m2 += th[t] * th[t];
    }
    m1 /= (long double)N;
    m2 /= (long double)N;
    for (k = -40; k <= 40; ++k) {
        long double e = 0.25L + 0.02L * k, count = 0.0L;
        pf_hdf_moments m = pf_hdf_moments_make((pf_real)m1, (pf_real)m2, PF_R(0.0));
        for (t = 0; t < N; ++t) count += th[t] < e;
        count /= (long double)N;
        if (fabsl((long double)pf_horizon_visibility_gauss(m, (pf_real)e) - count) > worst)
            worst = fabsl((long double)pf_horizon_visibility_gauss(m, (pf_real)e) - count);
        if (fabsl((long double)pf_horizon_visibility_ramp(m, (pf_real)e) - count) > worst_ramp)
            worst_ramp = fabsl((long double)pf_horizon_visibility_ramp(m, (pf_real)e) - count);
    }
    pf_test_note("Gaussian HDF vs counted: max |dV| %.2Lg; Fournier ramp (model error) %.3Lg", worst, worst_ramp);
    PF_CHECK(worst <= 1.5e-3L, "gauss vs counting %Lg", worst);
    /* the ramp reaches 1 at mu + sigma where Phi(1) = 0.8413: 1 - Phi(1) = 0.1587 */
    PF_CHECK(worst_ramp > 0.15L && worst_ramp < 0.17L, "ramp model error %Lg", worst_ramp);
}

/* explicit Legendre polynomials P_0..P_8 (coefficients of x^0..x^8, times the denominators) */
static long double ora_legendre(int j, long double x)
{
    static const long double c[9][10] = {
        { 1, 1 },
        { 1, 0, 1 },
        { 2, -1, 0, 3 },
        { 2, 0, -3, 0, 5 },
        { 8, 3, 0, -30, 0, 35 },
        { 8, 0, 15, 0, -70, 0, 63 },
        { 16, -5, 0, 105, 0, -315, 0, 231 },
        { 16, 0, -35, 0, 315, 0, -693, 0, 429 },
        { 128, 35, 0, -1260, 0, 6930, 0, -12012, 0, 6435 },
    };
    long double s = 0.0L, p = 1.0L;
    int k;
    for (k = 0; k <= j; ++k, p *= x) s += c[j][k + 1] * p;
    return s / c[j][0];
}

static void test_horizon_legendre_vs_quadrature(void)
{
    long double worst_c = 0.0L, worst_b = 0.0L;
    int j, is, ix;
    for (j = 0; j < 8; ++j) {
        long double nrm = sqrtl(j + 0.5L);
        for (is = -20; is <= 20; ++is) {
            long double s = is / 20.0L, q = 0.0L, h = (1.0L - s) / 20000.0L;
            int k;
            for (k = 0; k <= 20000; ++k) {
                long double wgt = (k == 0 || k == 20000) ? 1.0L : ((k & 1) ? 4.0L : 2.0L);
                q += wgt * nrm * ora_legendre(j, s + k * h);
            }
            q *= h / 3.0L;
            if (fabsl((long double)pf_horizon_legendre_coeff(j, (pf_real)s) - q) > worst_c)
                worst_c = fabsl((long double)pf_horizon_legendre_coeff(j, (pf_real)s) - q);
        }
        for (ix = -20; ix <= 20; ++ix) {
            long double x = ix / 20.0L;
            long double err = fabsl((long double)pf_horizon_legendre_basis(j, (pf_real)x) - nrm * ora_legendre(j, x));
            if (err > worst_b) worst_b = err;
        }
    }
    pf_test_note("a_j(s) vs Simpson quadrature: max %.2Lg; P^_j vs explicit polynomials: max %.2Lg", worst_c, worst_b);
    PF_CHECK(worst_c <= 40.0L * PF_TEST_EPS + 1e-14L, "coeff %Lg", worst_c);
    PF_CHECK(worst_b <= 40.0L * PF_TEST_EPS, "basis %Lg", worst_b);
}

/* Eq. 30 on a real map: the Legendre pyramid's footprint coefficients give the mean of the
   texels' truncated steps (linearity), which converges to eq. 26 counted over the texels as k
   grows. */
static void test_horizon_eq26_legendre_counting(void)
{
    enum { W = 32, N = 4, K = 8 };
    static pf_real hm[W * W], pyr[(W * W * 4 / 3 + 8) * K * N], ang[W * W * N];
    int a, ix, k, t;
    long double worst_lin = 0.0L, l2[K + 1];
    make_map(hm, W, W, 7u);
    PF_CHECK(pf_horizon_pyramid(hm, W, W, PF_R(1.0), N, 16, PF_BORDER_WRAP, PF_HORIZON_LEGENDRE, K, pyr) == PF_OK, "rc");
    PF_CHECK(pf_horizon_map(hm, W, W, PF_R(1.0), N, 16, PF_BORDER_WRAP, PF_HORIZON_ANGLES, 0, ang) == PF_OK, "rc");
    for (k = 0; k <= K; ++k) l2[k] = 0.0L;
    {
        /* level 3: 4 x 4 texels of 8 x 8 */
        const pf_real *lv = pyr + pf_mip_level_offset(W, W, 3) * K * N;
        int fx, fy;
        for (fy = 0; fy < 4; ++fy)
            for (fx = 0; fx < 4; ++fx)
                for (a = 0; a < N; ++a)
                    for (ix = -50; ix <= 50; ++ix) {
                        long double x = ix / 50.0L, count = 0.0L, mean_trunc = 0.0L;
                        const pf_real *cf = lv + ((fy * 4 + fx) * N + a) * K;
                        pf_hdf_legendre c = pf_hdf_legendre_make(cf[0], cf[1], cf[2], cf[3], cf[4], cf[5], cf[6], cf[7]);
                        for (t = 0; t < 64; ++t) {
                            int i = fx * 8 + t % 8, j = fy * 8 + t / 8, q;
                            long double st = sinl((long double)ang[(j * W + i) * N + a]), v = 0.0L;
                            count += st < x;
                            for (q = 0; q < K; ++q) {
                                long double nq = sqrtl(q + 0.5L), aq;
                                /* a_q by its closed form, with the explicit polynomials */
                                if (q == 0) aq = (1.0L - st) * nq;
                                else aq = nq * (ora_legendre(q - 1, st) - ora_legendre(q + 1, st)) / (2 * q + 1);
                                v += aq * nq * ora_legendre(q, x);
                            }
                            mean_trunc += v;
                        }
                        count /= 64.0L;
                        mean_trunc /= 64.0L;
                        if (mean_trunc >= 0.0L && mean_trunc <= 1.0L &&
                            fabsl((long double)pf_horizon_visibility_legendre(c, K, (pf_real)x) - mean_trunc) > worst_lin)
                            worst_lin = fabsl((long double)pf_horizon_visibility_legendre(c, K, (pf_real)x) - mean_trunc);
                        for (k = 1; k <= K; ++k) {
                            long double d = (long double)pf_horizon_visibility_legendre(c, k, (pf_real)x) - count;
                            l2[k] += d * d;
                        }
                    }
    }
    for (k = 1; k <= K; ++k) l2[k] = sqrtl(l2[k] / (16.0L * (long double)N * 101.0L));
    pf_test_note("eq. 30 from filtered coefficients = mean of truncated steps to %.2Lg; RMS vs counted eq. 26: "
                 "k=2 %.3Lg, k=4 %.3Lg, k=8 %.3Lg", worst_lin, l2[2], l2[4], l2[8]);
    PF_CHECK(worst_lin <= 1e-4L, "linearity %Lg", worst_lin);
    PF_CHECK(l2[8] < l2[4] && l2[4] < l2[2] && l2[8] < 0.12L, "no convergence: %Lg %Lg %Lg", l2[2], l2[4], l2[8]);
}

/* ---------------------------------------------------------------- evaluators */
static void test_horizon_visibility_formulas(void)
{
    pf_test_rng r;
    long double worst_g = 0.0L, worst_r = 0.0L;
    int it;
    r.state = 99u;
    for (it = 0; it < 20000; ++it) {
        long double mu = (long double)pf_test_uniform(&r, -0.5, 1.2), sd = (long double)pf_test_uniform(&r, 0.005, 0.6);
        long double e = mu + sd * (long double)pf_test_uniform(&r, -6, 6);
        pf_hdf_moments m = pf_hdf_moments_make((pf_real)mu, (pf_real)(mu * mu + sd * sd), PF_R(0.0));
        /* the moments as the float build stores them */
        long double smu = (long double)m.m1, ssd = sqrtl((long double)m.m2 - smu * smu);
        long double g = 0.5L * erfcl((smu - (long double)(pf_real)e) / (ssd * sqrtl(2.0L)));
        long double rp = ((long double)(pf_real)e - smu + ssd) / (2.0L * ssd);
        rp = rp < 0.0L ? 0.0L : (rp > 1.0L ? 1.0L : rp);
        if (fabsl((long double)pf_horizon_visibility_gauss(m, (pf_real)e) - g) > worst_g)
            worst_g = fabsl((long double)pf_horizon_visibility_gauss(m, (pf_real)e) - g);
        if (fabsl((long double)pf_horizon_visibility_ramp(m, (pf_real)e) - rp) > worst_r)
            worst_r = fabsl((long double)pf_horizon_visibility_ramp(m, (pf_real)e) - rp);
    }
    pf_test_note("gauss vs erfcl: max abs %.2Lg; ramp vs its formula: %.2Lg", worst_g, worst_r);
    /* E[T^2] - E[T]^2 cancels: float keeps ~1e-7 of m2 absolute, so sigma's error can reach a
       few 1e-5 relative for small sigma over large mu */
#ifdef PF_DOUBLE
    PF_CHECK(worst_g <= 1e-9L && worst_r <= 1e-9L, "%Lg %Lg", worst_g, worst_r);
#else
    PF_CHECK(worst_g <= 5e-4L && worst_r <= 5e-4L, "%Lg %Lg", worst_g, worst_r);
#endif
    /* steps and NaN */
    PF_CHECK(pf_horizon_visibility_gauss(pf_hdf_moments_make(PF_R(0.5), PF_R(0.25), PF_R(0.0)), PF_R(0.5)) == PF_R(1.0), "step at mu");
    PF_CHECK(pf_horizon_visibility_gauss(pf_hdf_moments_make(PF_R(0.5), PF_R(0.25), PF_R(0.0)), PF_R(0.49)) == PF_R(0.0), "step below");
    PF_CHECK(pf_horizon_visibility_ramp(pf_hdf_moments_make(PF_R(0.3), PF_R(0.08), PF_R(0.0)), PF_R(0.29)) == PF_R(0.0), "neg var");
    PF_CHECK(pf_horizon_visibility_gauss(pf_hdf_moments_make(PF_R(NAN), PF_R(0.0), PF_R(0.0)), PF_R(0.3)) == PF_R(0.0), "nan");
}

/* eq. 23's limits: at the hotspot (l = v) and when fully lit (V(l) = 1) every visible texel is
   lit; when everything is visible (V(v) = 1) the answer is V(l). And eq. 28 against its
   formula in long double; the hotspot measured on a real horizon map by counting. */
static void test_horizon_bidir_limits(void)
{
    pf_test_rng r;
    int it, bad = 0;
    long double worst = 0.0L;
    r.state = 5u;
    for (it = 0; it < 5000; ++it) {
        pf_real v = (pf_real)pf_test_uniform(&r, 0.01, 1.0), l = (pf_real)pf_test_uniform(&r, 0.0, 1.0);
        pf_real c = (pf_real)pf_test_uniform(&r, -1.0, 1.0), wd = (pf_real)pf_test_uniform(&r, 0.05, 1.0);
        long double al = 0.5L * (1.0L + (long double)c), mn = (long double)(l < v ? l : v), mx = (long double)l + (long double)v - 1.0L, ref;
        if (mx < 0.0L) mx = 0.0L;
        ref = (al * mn + (1.0L - al) * mx) / (long double)v;
        if (ref > 1.0L) ref = 1.0L;
        if (fabsl((long double)pf_horizon_bidir_tan(l, v, c) - ref) > worst) worst = fabsl((long double)pf_horizon_bidir_tan(l, v, c) - ref);
        bad += fabs((double)pf_horizon_bidir_tan(v, v, PF_R(1.0)) - 1.0) > 1e-6;
        bad += fabs((double)pf_horizon_bidir_ashikhmin(v, v, PF_R(1.0), wd) - 1.0) > 1e-6;
        bad += fabs((double)pf_horizon_bidir_tan(PF_R(1.0), v, c) - 1.0) > 1e-6;
        bad += fabs((double)pf_horizon_bidir_ashikhmin(PF_R(1.0), v, c, wd) - 1.0) > 1e-6;
        bad += fabs((double)pf_horizon_bidir_tan(l, PF_R(1.0), c) - (double)l) > 1e-6;
        bad += fabs((double)pf_horizon_bidir_ashikhmin(l, PF_R(1.0), c, wd) - (double)l) > 1e-6;
        bad += fabs((double)pf_horizon_bidir_product(l, v) - (double)l) > 1e-6;
        /* between the min (uncorrelated worst) and max fractions */
        bad += (double)pf_horizon_bidir_tan(l, v, c) < (double)(mx / (long double)v) - 1e-6 ||
               (double)pf_horizon_bidir_tan(l, v, c) > (double)(mn / (long double)v) + 1e-6;
    }
    PF_CHECK(bad == 0, "%d limit violations", bad);
    PF_CHECK(worst <= 1e-5L, "eq. 28 vs formula %Lg", worst);
    /* Fournier's product misses the hotspot */
    PF_CHECK(pf_horizon_bidir_product(PF_R(0.5), PF_R(0.5)) == PF_R(0.5), "product");
    /* counted on a horizon map: l = v gives exactly 1 (eq. 23) */
    {
        enum { W = 32 };
        static pf_real hm[W * W], ang[W * W * 4];
        int t, vis = 0, both = 0;
        make_map(hm, W, W, 3u);
        pf_horizon_map(hm, W, W, PF_R(1.0), 4, 16, PF_BORDER_WRAP, PF_HORIZON_ANGLES, 0, ang);
        for (t = 0; t < W * W; ++t) {
            int vv = ang[t * 4] < PF_R(0.3), vl = ang[t * 4] < PF_R(0.3);
            vis += vv;
            both += vv && vl;
        }
        PF_CHECK(vis > 0 && both == vis, "counted hotspot %d/%d", both, vis);
        pf_test_note("eq. 28 vs long double: %.2Lg; counted hotspot %d/%d", worst, both, vis);
    }
}

/* pf_horizon_visible_area against the bivariate-Gaussian expectation by quadrature over T. */
static void test_horizon_visible_area_quadrature(void)
{
    long double worst = 0.0L;
    int it, jt, kt;
    for (it = 0; it <= 12; ++it)
        for (jt = 0; jt <= 6; ++jt)
            for (kt = 0; kt < 3; ++kt) {
                long double tz = 0.1L * it, rho = -0.6L + 0.25L * jt, sdt = 0.05L + 0.12L * kt;
                long double mt = 0.3L, ms = 0.1L, ss = 0.4L, phi = 0.7L;
                long double wx = sinl(tz) * cosl(phi), wy = sinl(tz) * sinl(phi), wz = cosl(tz);
                /* the mean slope along the view azimuth is ms: (mx, my) = ms (cos phi, sin phi) */
                long double mx = ms * cosl(phi), my = ms * sinl(phi), e = atan2l(wz, sinl(tz));
                long double sum = 0.0L, h, lo = mt - 12.0L * sdt, hi = e < mt + 12.0L * sdt ? e : mt + 12.0L * sdt, ref;
                int i, n = 4000;
                pf_real got;
                pf_hdf_moments m = pf_hdf_moments_make((pf_real)mt, (pf_real)(mt * mt + sdt * sdt), (pf_real)(rho * ss * sdt + mt * ms));
                got = pf_horizon_visible_area(pf_vec3_make((pf_real)wx, (pf_real)wy, (pf_real)wz), m, (pf_real)mx, (pf_real)my);
                if (hi > lo) {
                    h = (hi - lo) / n;
                    for (i = 0; i <= n; ++i) {
                        long double T = lo + h * i, z = (T - mt) / sdt;
                        long double pdf = expl(-0.5L * z * z) / (sdt * sqrtl(2.0L * TPI));
                        long double wgt = (i == 0 || i == n) ? 1.0L : ((i & 1) ? 4.0L : 2.0L);
                        sum += wgt * pdf * (wz - sinl(tz) * (ms + rho * ss * z));
                    }
                    sum *= h / 3.0L;
                }
                ref = sum / (wz - sinl(tz) * ms);
                if (ref > 2.0L) ref = 2.0L;
                if (fabsl((long double)got - ref) > worst) worst = fabsl((long double)got - ref);
            }
    pf_test_note("visible area vs bivariate quadrature: max abs %.2Lg", worst);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-9L, "%Lg", worst);
#else
    PF_CHECK(worst <= 2e-5L, "%Lg", worst);
#endif
    /* a flat map: horizon 0 everywhere, so every view above the plane sees everything */
    {
        enum { W = 8 };
        static pf_real hm[W * W], pyr[(W * W * 4 / 3 + 4) * 24];
        pf_real t[24];
        pf_vec3 wo = pf_vec3_make(PF_R(0.8), PF_R(0.1), PF_R(0.3));
        pf_horizon_azimuth az = pf_horizon_azimuth_of(wo, 8);
        pf_hdf_moments m;
        int c;
        PF_CHECK(pf_horizon_pyramid(hm, W, W, PF_R(1.0), 8, 4, PF_BORDER_CLAMP, PF_HORIZON_MOMENTS, 0, pyr) == PF_OK, "rc");
        for (c = 0; c < 24; ++c) t[c] = pyr[c];
        m = pf_hdf_moments_lerp(pf_hdf_moments_make(t[3 * az.i0], t[3 * az.i0 + 1], t[3 * az.i0 + 2]),
                                pf_hdf_moments_make(t[3 * az.i1], t[3 * az.i1 + 1], t[3 * az.i1 + 2]), az.f);
        PF_CHECK(pf_horizon_visible_area(pf_vec3_normalize(wo), m, PF_R(0.0), PF_R(0.0)) == PF_R(1.0), "flat");
        PF_CHECK(pf_horizon_masking(pf_vec3_normalize(wo), m, pf_slope_stats_make(0, 0, 0, 0, 0)) == PF_R(1.0), "flat masking");
    }
}

/* pf_horizon_lod_weight against its piecewise definition in long double (an independent
   transcription: 1 up to lod_full, 0 from lod_smith, the straight line between), its limits
   and edge inputs. */
static long double ora_lod_weight(long double lod, long double lo, long double hi)
{
    if (lod >= hi) return 0.0L;
    if (lod <= lo) return 1.0L;
    return 1.0L - (lod - lo) / (hi - lo);
}
static void test_horizon_lod_weight(void)
{
    static const pf_real bounds[][2] = { { PF_R(2.0), PF_R(6.0) }, { PF_R(0.0), PF_R(1.0) }, { PF_R(-3.0), PF_R(4.5) },
                                         { PF_R(3.0), PF_R(3.25) } };
    long double worst = 0.0L;
    int b, i, bad = 0;
    for (b = 0; b < 4; ++b)
        for (i = -80; i <= 160; ++i) {
            pf_real lod = PF_R(i) * PF_R(0.0625), lo = bounds[b][0], hi = bounds[b][1];
            long double d = fabsl((long double)pf_horizon_lod_weight(lod, lo, hi) - ora_lod_weight((long double)lod, (long double)lo, (long double)hi));
            if (d > worst) worst = d;
        }
    pf_test_note("lod weight vs piecewise definition: max abs %.2Lg", worst);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-15L, "%Lg", worst);
#else
    PF_CHECK(worst <= 2e-7L, "%Lg", worst);
#endif
    /* end points exact, halfway 0.5, monotone non-increasing */
    bad += pf_horizon_lod_weight(PF_R(2.0), PF_R(2.0), PF_R(6.0)) != PF_R(1.0);
    bad += pf_horizon_lod_weight(PF_R(6.0), PF_R(2.0), PF_R(6.0)) != PF_R(0.0);
    bad += pf_horizon_lod_weight(PF_R(4.0), PF_R(2.0), PF_R(6.0)) != PF_R(0.5);
    for (i = 0; i < 200; ++i)
        bad += pf_horizon_lod_weight(PF_R(i + 1) * PF_R(0.04), PF_R(2.0), PF_R(6.0)) >
               pf_horizon_lod_weight(PF_R(i) * PF_R(0.04), PF_R(2.0), PF_R(6.0));
    /* edge inputs: negative lod (magnification) is the full horizon, NaN is Smith, infinities
       the two ends; lod_full >= lod_smith a step; lod_smith = +inf never fades */
    bad += pf_horizon_lod_weight(PF_R(-3.0), PF_R(2.0), PF_R(6.0)) != PF_R(1.0);
    bad += pf_horizon_lod_weight(PF_R(NAN), PF_R(2.0), PF_R(6.0)) != PF_R(0.0);
    bad += pf_horizon_lod_weight(PF_R(3.0), PF_R(NAN), PF_R(6.0)) != PF_R(0.0);
    bad += pf_horizon_lod_weight(PF_R(3.0), PF_R(2.0), PF_R(NAN)) != PF_R(0.0);
    bad += pf_horizon_lod_weight(-PF_R(INFINITY), PF_R(2.0), PF_R(6.0)) != PF_R(1.0);
    bad += pf_horizon_lod_weight(PF_R(INFINITY), PF_R(2.0), PF_R(6.0)) != PF_R(0.0);
    bad += pf_horizon_lod_weight(PF_R(4.0), PF_R(5.0), PF_R(3.0)) != PF_R(0.0);
    bad += pf_horizon_lod_weight(PF_R(2.9), PF_R(5.0), PF_R(3.0)) != PF_R(1.0);
    bad += pf_horizon_lod_weight(PF_R(1e30), PF_R(2.0), PF_R(INFINITY)) != PF_R(1.0);
    bad += pf_horizon_lod_weight(PF_R(3.0), -PF_R(INFINITY), PF_R(6.0)) != PF_R(0.0);
    PF_CHECK(bad == 0, "%d limit or edge violations", bad);
}

/* pf_horizon_masking_lod: at weight 1 it is pf_horizon_masking bit for bit, at weight 0
   pf_beckmann_g1 bit for bit; between, Smith's G1 times the blend of 1 and the area ratio,
   the ratio taken by quadrature over T of the Gram-Charlier density phi(z) (1 + g/6 (z^3 -
   3 z)) (g = 0: the bivariate Gaussian of test_horizon_visible_area_quadrature) and the blend
   done in long double; the probability clamped to [0, 1] and the partial mean to at most z P
   (what pf_horizon.h states), g = sigma_T/E[T] (1 - rho^2) capped at 1 from the moments. */
static long double ora_area_ratio(long double wx, long double wy, long double wz, long double mt, long double sdt,
                                  long double mst, long double mx, long double my, long double g)
{
    long double r = sqrtl(wx * wx + wy * wy), e = atan2l(wz, r), rs = wx * mx + wy * my;
    /* r Cov(S, T), S the slope along w's azimuth: r E[S T] - (r E[S]) E[T] */
    long double ea = wz - rs, cov = r * mst - rs * mt, P = 0.0L, M = 0.0L, h, lo, hi, ref, ze = (e - mt) / sdt;
    int i, n = 4000;
    lo = mt - 12.0L * sdt;
    hi = e < mt + 12.0L * sdt ? e : mt + 12.0L * sdt;
    if (hi > lo) {
        h = (hi - lo) / n;
        for (i = 0; i <= n; ++i) {
            long double T = lo + h * i, z = (T - mt) / sdt;
            long double pdf = expl(-0.5L * z * z) / (sdt * sqrtl(2.0L * TPI)) * (1.0L + g / 6.0L * (z * z * z - 3.0L * z));
            long double wgt = (i == 0 || i == n) ? 1.0L : ((i & 1) ? 4.0L : 2.0L);
            P += wgt * pdf;
            M += wgt * pdf * z;
        }
        P *= h / 3.0L;
        M *= h / 3.0L;
    }
    if (ze > 12.0L) P = 1.0L; /* the quadrature stops at 12 deviations */
    P = P < 0.0L ? 0.0L : (P > 1.0L ? 1.0L : P);
    if (M > ze * P) M = ze * P;
    /* E[a; T < e] = wz P - (r E[S] P + r Cov(S, T)/sigma_T E[z; T < e]) */
    ref = (wz * P - (rs * P + cov / sdt * M)) / ea;
    return ref < 0.0L ? 0.0L : (ref > 2.0L ? 2.0L : ref);
}
/* pf_horizon_masking's skewness from the moments and statistics, in long double */
static long double ora_skew(long double wx, long double wy, long double mt, long double sdt, long double mst, long double mx,
                            long double my, long double vx, long double vy, long double cxy)
{
    long double r = sqrtl(wx * wx + wy * wy), rs = wx * mx + wy * my, covr = r * mst - rs * mt;
    long double vs = wx * wx * vx + wy * wy * vy + 2.0L * wx * wy * cxy, d = sdt * sdt * vs, u;
    u = d > 1e-30L ? sdt * (1.0L - covr * covr / d) : sdt;
    if (u < 0.0L) u = 0.0L;
    return (mt <= 0.0L || u >= mt) ? 1.0L : u / mt;
}
static void test_horizon_masking_lod(void)
{
    pf_test_rng r;
    long double worst = 0.0L;
    int it, bad = 0;
    r.state = 41u;
    for (it = 0; it < 400; ++it) {
        long double tz = (long double)pf_test_uniform(&r, 0.0, 1.3), phi = (long double)pf_test_uniform(&r, 0.0, 6.283);
        long double mt = (long double)pf_test_uniform(&r, -0.2, 0.5), sdt = (long double)pf_test_uniform(&r, 0.05, 0.4);
        long double mx = (long double)pf_test_uniform(&r, -0.2, 0.2), my = (long double)pf_test_uniform(&r, -0.2, 0.2);
        long double rho = (long double)pf_test_uniform(&r, -0.7, 0.2), ss = 0.4L;
        long double sal = mx * cosl(phi) + my * sinl(phi); /* E[S] along the azimuth */
        long double mst = rho * ss * sdt + mt * sal;
        pf_real lod = (pf_real)pf_test_uniform(&r, -1.0, 8.0);
        pf_vec3 w = pf_vec3_make((pf_real)(sinl(tz) * cosl(phi)), (pf_real)(sinl(tz) * sinl(phi)), (pf_real)cosl(tz));
        pf_hdf_moments m = pf_hdf_moments_make((pf_real)mt, (pf_real)(mt * mt + sdt * sdt), (pf_real)mst);
        pf_slope_stats s = pf_slope_stats_make((pf_real)mx, (pf_real)my, PF_R(0.16), PF_R(0.12), PF_R(0.01));
        pf_real k = pf_horizon_lod_weight(lod, PF_R(2.0), PF_R(6.0)), got = pf_horizon_masking_lod(w, m, s, lod, PF_R(2.0), PF_R(6.0));
        long double g1 = (long double)pf_beckmann_g1(w, s), ratio, ref;
        long double g = ora_skew((long double)w.x, (long double)w.y, mt, sdt, mst, mx, my, 0.16L, 0.12L, 0.01L);
        ratio = ora_area_ratio((long double)w.x, (long double)w.y, (long double)w.z, mt, sdt, mst, mx, my, g);
        ref = g1 * ((long double)k * ratio + 1.0L - (long double)k);
        if (ref > 1.0L) ref = 1.0L;
        if (fabsl((long double)got - ref) > worst) worst = fabsl((long double)got - ref);
        /* the two ends, to 4 ulp (bit for bit without FMA contraction; -ffp-contract=fast fuses
           the two functions' products differently: 3e-7 in the mx-gcc-c99-O2-fma cell) */
        bad += fabsl((long double)pf_horizon_masking_lod(w, m, s, PF_R(1.0), PF_R(2.0), PF_R(6.0)) -
                     (long double)pf_horizon_masking(w, m, s)) > 4.0L * PF_TEST_EPS;
        bad += fabsl((long double)pf_horizon_masking_lod(w, m, s, PF_R(7.0), PF_R(2.0), PF_R(6.0)) -
                     (long double)pf_saturate(pf_beckmann_g1(w, s))) > 4.0L * PF_TEST_EPS;
        /* between the two ends */
        {
            pf_real a = pf_horizon_masking(w, m, s), b = pf_saturate(pf_beckmann_g1(w, s));
            bad += got < pf_min(a, b) - PF_R(1e-6) || got > pf_max(a, b) + PF_R(1e-6);
        }
    }
    pf_test_note("masking_lod vs Smith x blended quadrature ratio: max abs %.2Lg", worst);
    PF_CHECK(bad == 0, "%d end-point or bracket violations", bad);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-9L, "%Lg", worst);
#else
    PF_CHECK(worst <= 2e-5L, "%Lg", worst);
#endif
}

/* Masking against the brute force on a field whose footprint horizons are right-skewed: an
   fBm of spectrum 1/f^2.4 (frequencies 1-64 cycles per map, 128^2 texels, periodic, RMS slope
   0.3 per component; the user-map proxy fbm_b24 of bench/map_proxies.c at half the size), its
   n = 32 HDF-moment pyramid (march 64 texels) and slope pyramid, EVERY 4 x 4-texel footprint,
   views 0-75 degrees at azimuths 10 and 100 degrees (footprint-views with a mean projected area
   under 1/4 of a flat one's skipped, the bench's cull). Reference: G1 = sum V a+ / sum a+,
   V marched through the whole field (pfm_visibility_map). Pooled relative L2 of
   pf_horizon_masking (the Gram-Charlier HDF) and of the Gaussian HDF's masking
   (pf_horizon_visible_area x pf_beckmann_g1: pf_horizon_masking before the skew). Measured:
   SKEW_BRUTE_BOUND; it must hold for the skewed shape and fail for the Gaussian. */
#define SK_W 128
static void sk_fbm(pfm_surface *s, double beta, unsigned long long seed)
{
    double *re = (double *)calloc((size_t)(SK_W * SK_W), sizeof(double)), *im = (double *)calloc((size_t)(SK_W * SK_W), sizeof(double));
    double col_r[SK_W], col_i[SK_W], ss = 0.0, mean = 0.0, k;
    pfm_rng g;
    int x, y, i;
    g.state = seed;
    if (!re || !im || pfm_surface_alloc(s, SK_W, SK_W, 1.0) != 0) {
        free(re);
        free(im);
        s->height = NULL;
        return;
    }
    for (y = 0; y < SK_W; ++y)
        for (x = 0; x < SK_W; ++x) {
            int fx = x <= SK_W / 2 ? x : x - SK_W, fy = y <= SK_W / 2 ? y : y - SK_W;
            double f = sqrt((double)(fx * fx + fy * fy)), a, u, v;
            u = pfm_rng_uniform(&g);
            v = pfm_rng_uniform(&g);
            if (f < 1.0 || f > SK_W / 2) continue;
            a = pow(f, -0.5 * beta) * sqrt(-2.0 * log(u > 1e-300 ? u : 1e-300));
            re[y * SK_W + x] = a * cos(6.283185307179586 * v);
            im[y * SK_W + x] = a * sin(6.283185307179586 * v);
        }
    for (y = 0; y < SK_W; ++y) pfmi_fft(re + y * SK_W, im + y * SK_W, SK_W, 1);
    for (x = 0; x < SK_W; ++x) {
        for (y = 0; y < SK_W; ++y) {
            col_r[y] = re[y * SK_W + x];
            col_i[y] = im[y * SK_W + x];
        }
        pfmi_fft(col_r, col_i, SK_W, 1);
        for (y = 0; y < SK_W; ++y) re[y * SK_W + x] = col_r[y];
    }
    for (i = 0; i < SK_W * SK_W; ++i) {
        s->height[i] = re[i];
        mean += re[i];
    }
    mean /= (double)(SK_W * SK_W);
    for (y = 0; y < SK_W; ++y)
        for (x = 0; x < SK_W; ++x) {
            double sx, sy;
            pfm_slope(s, x, y, &sx, &sy);
            ss += 0.5 * (sx * sx + sy * sy);
        }
    k = 0.3 / sqrt(ss / (double)(SK_W * SK_W));
    for (i = 0; i < SK_W * SK_W; ++i) s->height[i] = (s->height[i] - mean) * k;
    pfm_surface_bounds(s);
    free(re);
    free(im);
}
static void test_horizon_masking_skewed_brute_force(void)
{
    static const double vdeg[7] = { 0, 15, 30, 45, 60, 70, 75 };
    const int W = SK_W, NAZ = 32, C = pf_horizon_channels(PF_HORIZON_MOMENTS, NAZ, 0);
    const long long tc = pf_mip_texel_count(W, W);
    pfm_surface s;
    pf_real *hr = (pf_real *)malloc(sizeof(pf_real) * (size_t)(W * W)), *slope = (pf_real *)malloc(sizeof(pf_real) * 5 * (size_t)tc);
    pf_real *hor = (pf_real *)malloc(sizeof(pf_real) * (size_t)C * (size_t)tc);
    unsigned char *vis = (unsigned char *)malloc((size_t)(W * W));
    double e_sk = 0.0, e_ga = 0.0, r2 = 0.0;
    int v, a, x0, y0, i, used = 0;
    sk_fbm(&s, 2.4, 24u);
    if (!hr || !slope || !hor || !vis || !s.height) {
        PF_CHECK(0, "setup");
        goto done;
    }
    for (i = 0; i < W * W; ++i) hr[i] = (pf_real)s.height[i];
    PF_CHECK(pf_slope_pyramid_from_heights(hr, W, W, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP, slope) == PF_OK, "slopes");
    PF_CHECK(pf_horizon_pyramid(hr, W, W, PF_R(1.0), NAZ, 64, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, hor) == PF_OK, "pyramid");
    for (v = 0; v < 7; ++v)
        for (a = 0; a < (v ? 2 : 1); ++a) {
            double th = vdeg[v] * 3.14159265358979323846 / 180.0, ph = (10.0 + 90.0 * a) * 3.14159265358979323846 / 180.0;
            double wd[3];
            pf_vec3 wo;
            pf_horizon_azimuth az;
            wd[0] = sin(th) * cos(ph);
            wd[1] = sin(th) * sin(ph);
            wd[2] = cos(th);
            wo = pf_test_vec3(wd);
            az = pf_horizon_azimuth_of(wo, NAZ);
            pfm_visibility_map(&s, wd, vis);
            for (y0 = 0; y0 < W; y0 += 4)
                for (x0 = 0; x0 < W; x0 += 4) {
                    const long long tex = pf_mip_level_offset(W, W, 2) + (long long)(y0 / 4) * (W / 4) + x0 / 4;
                    const pf_real *st = slope + tex * 5, *tx = hor + tex * C;
                    pf_slope_stats ss = pf_slope_moments_stats(pf_slope_moments_make(st[0], st[1], st[2], st[3], st[4]), PF_R(0.0));
                    pf_hdf_moments hm = pf_hdf_moments_lerp(pf_hdf_moments_make(tx[3 * az.i0], tx[3 * az.i0 + 1], tx[3 * az.i0 + 2]),
                                                            pf_hdf_moments_make(tx[3 * az.i1], tx[3 * az.i1 + 1], tx[3 * az.i1 + 2]),
                                                            az.f);
                    double sa = 0.0, sap = 0.0, sva = 0.0, ref, sk, ga;
                    int ii, jj;
                    for (jj = 0; jj < 4; ++jj)
                        for (ii = 0; ii < 4; ++ii) {
                            double sx, sy, at;
                            pfm_slope(&s, x0 + ii, y0 + jj, &sx, &sy);
                            at = wd[2] - sx * wd[0] - sy * wd[1];
                            sa += at;
                            sap += at > 0.0 ? at : 0.0;
                            sva += vis[(y0 + jj) * W + x0 + ii] ? at : 0.0;
                        }
                    if (!(sa / 16.0 >= 0.25 * wd[2]) || !(sap > 0.0)) continue; /* the bench's cull */
                    ref = sva / sap;
                    sk = (double)pf_horizon_masking(wo, hm, ss);
                    ga = (double)pf_saturate(pf_horizon_visible_area(wo, hm, ss.mean_x, ss.mean_y) * pf_beckmann_g1(wo, ss));
                    e_sk += (sk - ref) * (sk - ref);
                    e_ga += (ga - ref) * (ga - ref);
                    r2 += ref * ref;
                    ++used;
                }
        }
    e_sk = sqrt(e_sk / r2);
    e_ga = sqrt(e_ga / r2);
    pf_test_note("brute force, fBm 1/f^2.4 128^2, every 4x4 footprint, views 0-75, %d footprint-views: masking "
                 "(Gram-Charlier HDF) %.4f, Gaussian HDF %.4f", used, e_sk, e_ga);
    PF_CHECK(used >= 10000, "%d samples", used);
    PF_CHECK(e_sk <= SKEW_BRUTE_BOUND, "skewed %g", e_sk);
    PF_CHECK(e_ga > SKEW_BRUTE_BOUND, "the Gaussian HDF %g meets the bound: the field does not test the skew", e_ga);
done:
    free(hr);
    free(slope);
    free(hor);
    free(vis);
    if (s.height) pfm_surface_free(&s);
}

/* pf_horizon_visibility_given_slope against the conditional probability by quadrature of the
   bivariate Gaussian density of (S, T) (its own inverse covariance, no regression formula):
   P(T < e | S = s) = integral_{-inf}^{e} f(s, t) dt / integral f(s, t) dt. */
static void test_horizon_visibility_given_slope(void)
{
    pf_test_rng r;
    long double worst = 0.0L;
    int it, bad = 0;
    r.state = 77u;
    for (it = 0; it < 300; ++it) {
        long double tz = (long double)pf_test_uniform(&r, 0.05, 1.4), phi = (long double)pf_test_uniform(&r, 0.0, 6.283);
        long double mt = (long double)pf_test_uniform(&r, -0.3, 0.6), sdt = (long double)pf_test_uniform(&r, 0.03, 0.4);
        long double mx = (long double)pf_test_uniform(&r, -0.3, 0.3), my = (long double)pf_test_uniform(&r, -0.3, 0.3);
        long double vx = (long double)pf_test_uniform(&r, 0.01, 0.3), vy = (long double)pf_test_uniform(&r, 0.01, 0.3);
        long double cxy = (long double)pf_test_uniform(&r, -0.6, 0.6) * sqrtl(vx * vy), rho = (long double)pf_test_uniform(&r, -0.9, 0.9);
        long double dx = cosl(phi), dy = sinl(phi), es = mx * dx + my * dy;
        long double vs = vx * dx * dx + vy * dy * dy + 2.0L * cxy * dx * dy, cst = rho * sqrtl(vs) * sdt;
        long double sv = es + (long double)pf_test_uniform(&r, -2.0, 2.0) * sqrtl(vs);
        long double e = atan2l(cosl(tz), sinl(tz));
        /* inverse of [[vs, cst], [cst, sdt^2]] */
        long double det = vs * sdt * sdt - cst * cst, i11 = sdt * sdt / det, i12 = -cst / det, i22 = vs / det;
        long double num = 0.0L, den = 0.0L, lo = mt - 40.0L * sdt, hi = mt + 40.0L * sdt, ref;
        pf_real got;
        int i, pass;
        /* Simpson over [lo, hi] (den) and over [lo, min(e, hi)] (num) */
        for (pass = 0; pass < 2; ++pass) {
            long double top = pass ? (e < hi ? e : hi) : hi, h = (top - lo) / 20000.0L, acc = 0.0L;
            if (top <= lo) continue;
            for (i = 0; i <= 20000; ++i) {
                long double t = lo + h * i, a = sv - es, b = t - mt;
                long double f = expl(-0.5L * (i11 * a * a + 2.0L * i12 * a * b + i22 * b * b));
                acc += ((i == 0 || i == 20000) ? 1.0L : ((i & 1) ? 4.0L : 2.0L)) * f;
            }
            if (pass) num = acc * h;
            else den = acc * h;
        }
        ref = num / den;
        got = pf_horizon_visibility_given_slope(
            pf_vec3_make((pf_real)(sinl(tz) * dx), (pf_real)(sinl(tz) * dy), (pf_real)cosl(tz)),
            pf_hdf_moments_make((pf_real)mt, (pf_real)(mt * mt + sdt * sdt), (pf_real)(cst + es * mt)),
            pf_slope_stats_make((pf_real)mx, (pf_real)my, (pf_real)vx, (pf_real)vy, (pf_real)cxy), (pf_real)(sv * dx),
            (pf_real)(sv * dy));
        if (fabsl((long double)got - ref) > worst) worst = fabsl((long double)got - ref);
        bad += !(got >= PF_R(0.0) && got <= PF_R(1.0));
    }
    pf_test_note("visibility given slope vs bivariate-density quadrature: max abs %.2Lg", worst);
    PF_CHECK(bad == 0, "%d outside [0, 1]", bad);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-9L, "%Lg", worst);
#else
    PF_CHECK(worst <= 2e-5L, "%Lg", worst);
#endif
    /* limits: a vertical direction sees over every horizon, NaN moments see nothing */
    {
        pf_slope_stats s = pf_slope_stats_make(PF_R(0.1), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0));
        pf_hdf_moments m = pf_hdf_moments_make(PF_R(0.3), PF_R(0.1), PF_R(0.02));
        PF_CHECK(pf_horizon_visibility_given_slope(pf_vec3_make(0, 0, 1), m, s, PF_R(0.2), PF_R(0.1)) == PF_R(1.0), "vertical");
        PF_CHECK(pf_horizon_visibility_given_slope(pf_vec3_make(PF_R(0.6), 0, PF_R(0.8)),
                                                   pf_hdf_moments_make(PF_R(NAN), 0, 0), s, 0, 0) == PF_R(0.0), "nan");
    }
}

/* Long-double oracle of pf_horizon_diffuse_directional's integral over the Gaussian slope
   distribution (2D Simpson in the Cholesky-whitened plane, +-6 deviations), the conditional
   visibility by erfcl and eq. 28 written out: the grid of the library is a quadrature of it. */
/* T given S + B = (sx, sy) along w's azimuth, B the base lobe's slope (variance bv, independent
   of T; bv = 0: T given S, the diffuse's conditioning) */
static long double ora_cond_vis_b(long double wx, long double wy, long double wz, long double mt, long double sdt,
                                  long double mst, long double mx, long double my, long double vx, long double vy,
                                  long double cxy, long double sx, long double sy, long double bv)
{
    long double r = sqrtl(wx * wx + wy * wy), dx = wx / r, dy = wy / r, e = atan2l(wz, r);
    long double es = mx * dx + my * dy, vs = vx * dx * dx + vy * dy * dy + 2.0L * cxy * dx * dy + bv;
    long double cov = mst - es * mt, mu = mt + cov / vs * (sx * dx + sy * dy - es), var = sdt * sdt - cov * cov / vs;
    return 0.5L * erfcl((mu - e) / (sqrtl(var) * sqrtl(2.0L)));
}
/* the specular's conditional visibility (pfi_horizon_spec_cond_vis): the conditional mean
   lowered by the convexity term beta Cov(S, T)/sqrt(Var(S) + b) = Cov^2/(Var(S) + b)^1.5 and
   the conditional deviation times 0.7 (pf_horizon.h, SPECULAR) */
static long double ora_spec_cond_vis(long double wx, long double wy, long double wz, long double mt, long double sdt,
                                     long double mst, long double mx, long double my, long double vx, long double vy,
                                     long double cxy, long double sx, long double sy, long double bv)
{
    long double r = sqrtl(wx * wx + wy * wy), dx = wx / r, dy = wy / r, e = atan2l(wz, r);
    long double es = mx * dx + my * dy, vs = vx * dx * dx + vy * dy * dy + 2.0L * cxy * dx * dy + bv;
    long double cov = mst - es * mt, mu = mt + cov / vs * (sx * dx + sy * dy - es) - cov * cov / (vs * sqrtl(vs));
    long double var = sdt * sdt - cov * cov / vs;
    return 0.5L * erfcl((mu - e) / (0.7L * sqrtl(var) * sqrtl(2.0L)));
}
static long double ora_cond_vis(long double wx, long double wy, long double wz, long double mt, long double sdt,
                                long double mst, long double mx, long double my, long double vx, long double vy,
                                long double cxy, long double sx, long double sy)
{
    return ora_cond_vis_b(wx, wy, wz, mt, sdt, mst, mx, my, vx, vy, cxy, sx, sy, 0.0L);
}
static long double ora_horizon_diffuse(const long double wo[3], const long double wi[3], long double mto, long double sdo,
                                       long double msto, long double mti, long double sdi, long double msti, long double mx,
                                       long double my, long double vx, long double vy, long double cxy)
{
    long double sxd = sqrtl(vx), syd = sqrtl(vy), rr = cxy / (sxd * syd), rc = sqrtl(1.0L - rr * rr);
    long double al = 0.5L * (1.0L + wo[0] * wi[0] + wo[1] * wi[1] + wo[2] * wi[2]);
    long double vis = 0.0L, lit = 0.0L, wsum = 0.0L, ao = wo[2] - wo[0] * mx - wo[1] * my, h = 12.0L / 240.0L;
    int i, j;
    for (i = 0; i <= 240; ++i)
        for (j = 0; j <= 240; ++j) {
            long double p = -6.0L + h * i, q = -6.0L + h * j;
            long double wgt = ((i == 0 || i == 240) ? 1.0L : ((i & 1) ? 4.0L : 2.0L)) *
                              ((j == 0 || j == 240) ? 1.0L : ((j & 1) ? 4.0L : 2.0L)) * expl(-0.5L * (p * p + q * q));
            long double x = mx + sxd * p, y = my + syd * (rr * p + rc * q);
            long double a = wo[2] - x * wo[0] - y * wo[1], nz = 1.0L / sqrtl(1.0L + x * x + y * y);
            long double cosi = (-x * wi[0] - y * wi[1] + wi[2]) * nz, vo, vi, both, mn, mxx;
            wsum += wgt;
            if (a <= 0.0L) continue;
            vo = ora_cond_vis(wo[0], wo[1], wo[2], mto, sdo, msto, mx, my, vx, vy, cxy, x, y);
            vi = ora_cond_vis(wi[0], wi[1], wi[2], mti, sdi, msti, mx, my, vx, vy, cxy, x, y);
            mn = vo < vi ? vo : vi;
            mxx = vo + vi - 1.0L > 0.0L ? vo + vi - 1.0L : 0.0L;
            both = al * mn + (1.0L - al) * mxx; /* eq. 28's visible-and-lit */
            vis += wgt * a * vo;
            if (cosi > 0.0L) lit += wgt * a * both * cosi;
        }
    vis /= wsum;
    lit /= wsum;
    if (vis / ao > 2.0L) return lit / (ao * TPI) * 2.0L * ao / vis;
    return lit / (ao * TPI);
}
static void test_horizon_diffuse(void)
{
    pf_test_rng r;
    long double worst = 0.0L;
    int it, bad = 0;
    r.state = 91u;
    for (it = 0; it < 12; ++it) {
        long double to = (long double)pf_test_uniform(&r, 0.1, 1.2), po = (long double)pf_test_uniform(&r, 0.0, 6.283);
        long double ti = (long double)pf_test_uniform(&r, 0.1, 1.3), pi_ = (long double)pf_test_uniform(&r, 0.0, 6.283);
        long double wo[3], wi[3], mx = (long double)pf_test_uniform(&r, -0.15, 0.15), my = (long double)pf_test_uniform(&r, -0.15, 0.15);
        long double vx = (long double)pf_test_uniform(&r, 0.02, 0.12), vy = (long double)pf_test_uniform(&r, 0.02, 0.12), cxy = 0.3L * sqrtl(vx * vy);
        long double mto = (long double)pf_test_uniform(&r, 0.0, 0.4), sdo = (long double)pf_test_uniform(&r, 0.08, 0.3);
        long double mti = (long double)pf_test_uniform(&r, 0.0, 0.4), sdi = (long double)pf_test_uniform(&r, 0.08, 0.3);
        long double ro = (long double)pf_test_uniform(&r, -0.6, 0.0), ri = (long double)pf_test_uniform(&r, -0.6, 0.0), ref, vso, vsi, eso, esi;
        pf_real got;
        pf_gg_grid g;
        wo[0] = sinl(to) * cosl(po); wo[1] = sinl(to) * sinl(po); wo[2] = cosl(to);
        wi[0] = sinl(ti) * cosl(pi_); wi[1] = sinl(ti) * sinl(pi_); wi[2] = cosl(ti);
        /* E[S T] from a correlation rho of T with the slope along each azimuth */
        eso = mx * cosl(po) + my * sinl(po);
        vso = vx * cosl(po) * cosl(po) + vy * sinl(po) * sinl(po) + 2.0L * cxy * cosl(po) * sinl(po);
        esi = mx * cosl(pi_) + my * sinl(pi_);
        vsi = vx * cosl(pi_) * cosl(pi_) + vy * sinl(pi_) * sinl(pi_) + 2.0L * cxy * cosl(pi_) * sinl(pi_);
        {
            long double msto = ro * sqrtl(vso) * sdo + eso * mto, msti = ri * sqrtl(vsi) * sdi + esi * mti;
            pf_slope_stats s = pf_slope_stats_make((pf_real)mx, (pf_real)my, (pf_real)vx, (pf_real)vy, (pf_real)cxy);
            g = pf_gg_grid_make(pf_vec3_make((pf_real)wo[0], (pf_real)wo[1], (pf_real)wo[2]), s, PF_GG_HERMITE, PF_GG_MAX_N);
            got = pf_horizon_diffuse_directional(g, pf_vec3_make((pf_real)wi[0], (pf_real)wi[1], (pf_real)wi[2]),
                                                 pf_hdf_moments_make((pf_real)mto, (pf_real)(mto * mto + sdo * sdo), (pf_real)msto),
                                                 pf_hdf_moments_make((pf_real)mti, (pf_real)(mti * mti + sdi * sdi), (pf_real)msti));
            ref = ora_horizon_diffuse(wo, wi, mto, sdo, msto, mti, sdi, msti, mx, my, vx, vy, cxy);
        }
        if (fabsl((long double)got - ref) / (ref + 1e-3L) > worst) worst = fabsl((long double)got - ref) / (ref + 1e-3L);
        bad += !pf_test_bits_finite(got) || got < PF_R(0.0);
    }
    pf_test_note("horizon diffuse (Gauss-Hermite 9 x 9) vs 2D quadrature: max rel %.2Lg", worst);
    PF_CHECK(bad == 0, "%d non-finite or negative", bad);
    PF_CHECK(worst <= 0.02L, "%Lg", worst);
    /* limits. (1) horizons far below every view (T = -1.5 rad, uncorrelated): nothing hidden,
       so the result is LEADR's grid without its Smith factors, pf_gg_diffuse_directional /
       (G1(wo) * shadowing); (2) horizons above every direction: 0; (3) the lod fade's ends */
    {
        pf_slope_stats s = pf_slope_stats_make(PF_R(0.05), PF_R(-0.03), PF_R(0.06), PF_R(0.04), PF_R(0.01));
        pf_vec3 wo = pf_vec3_normalize(pf_vec3_make(PF_R(0.5), PF_R(0.2), PF_R(0.84)));
        pf_vec3 wi = pf_vec3_normalize(pf_vec3_make(PF_R(-0.3), PF_R(0.4), PF_R(0.87)));
        pf_gg_grid g = pf_gg_grid_make(wo, s, PF_GG_MATCHED, 3);
        pf_real low = PF_R(-1.5), high = PF_R(1.5);
        pf_hdf_moments ml = pf_hdf_moments_make(low, low * low, PF_R(0.0)), mh = pf_hdf_moments_make(high, high * high, PF_R(0.0));
        pf_real leadr = pf_gg_diffuse_directional(g, wi);
        pf_real v = pfi_gg_shadowing(g.g1_o, pf_g1_beckmann(pf_smith_nu(wi, s)));
        pf_real open = pf_horizon_diffuse_directional(g, wi, ml, ml), want = leadr / (g.g1_o * v);
        PF_CHECK(PF_FABS(open - want) <= PF_R(1e-5) * want, "open sky %g vs %g", (double)open, (double)want);
        PF_CHECK(pf_horizon_diffuse_directional(g, wi, mh, mh) == PF_R(0.0), "buried");
        PF_CHECK(pf_horizon_diffuse_lod(g, wi, ml, mh, PF_R(1.0), PF_R(2.0), PF_R(6.0)) ==
                 pf_horizon_diffuse_directional(g, wi, ml, mh), "lod 1: horizon");
        PF_CHECK(pf_horizon_diffuse_lod(g, wi, ml, mh, PF_R(6.0), PF_R(2.0), PF_R(6.0)) == leadr, "lod 6: leadr");
        {
            pf_real hz = pf_horizon_diffuse_directional(g, wi, ml, ml), mid = pf_horizon_diffuse_lod(g, wi, ml, ml, PF_R(4.0), PF_R(2.0), PF_R(6.0));
            PF_CHECK(PF_FABS(mid - PF_R(0.5) * (hz + leadr)) <= PF_R(1e-6) * (hz + leadr), "lod 4: halfway");
        }
        /* below the mean plane, light below the macrosurface: 0 */
        PF_CHECK(pf_horizon_diffuse_directional(g, pf_vec3_make(PF_R(0.6), 0, PF_R(-0.8)), ml, ml) == PF_R(0.0), "light below");
        PF_CHECK(pf_horizon_diffuse_directional(pf_gg_grid_make(pf_vec3_make(PF_R(0.6), 0, PF_R(-0.8)), s, PF_GG_MATCHED, 3), wi, ml, ml) ==
                 PF_R(0.0), "view below");
    }
}

/* ---------------------------------------------------------------- specular: the reflecting facets' horizon */
/* Long-double oracle of pf_horizon_leadr_specular: the Beckmann NDF of the footprint's Gaussian
   slopes written out (P22 / cos^4 at the half vector's slope), the conditional visibilities by
   ora_spec_cond_vis (erfcl), eq. 28 written out, Schlick with h.wi from the normalized half vector. */
static long double ora_horizon_spec(const long double wo[3], const long double wi[3], long double mto, long double sdo,
                                    long double msto, long double mti, long double sdi, long double msti, long double mx,
                                    long double my, long double vx, long double vy, long double cxy, long double bv,
                                    long double f0)
{
    long double h[3] = { wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2] }, hl, sx, sy, X, Y, det, q, p22, d, vo, vi, al, both, c, f;
    long double ao = wo[2] - mx * wo[0] - my * wo[1], Vx = vx + bv, Vy = vy + bv;
    hl = sqrtl(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    sx = -h[0] / h[2];
    sy = -h[1] / h[2];
    X = sx - mx;
    Y = sy - my;
    det = Vx * Vy - cxy * cxy;
    q = (Vy * X * X - 2.0L * cxy * X * Y + Vx * Y * Y) / det;
    p22 = expl(-0.5L * q) / (2.0L * TPI * sqrtl(det));
    d = p22 * powl(hl / h[2], 4.0L); /* / cos^4 of the half vector */
    vo = ora_spec_cond_vis(wo[0], wo[1], wo[2], mto, sdo, msto, mx, my, vx, vy, cxy, sx, sy, bv);
    vi = ora_spec_cond_vis(wi[0], wi[1], wi[2], mti, sdi, msti, mx, my, vx, vy, cxy, sx, sy, bv);
    al = 0.5L * (1.0L + wo[0] * wi[0] + wo[1] * wi[1] + wo[2] * wi[2]);
    both = al * (vo < vi ? vo : vi) + (1.0L - al) * (vo + vi - 1.0L > 0.0L ? vo + vi - 1.0L : 0.0L);
    c = (h[0] * wi[0] + h[1] * wi[1] + h[2] * wi[2]) / hl;
    f = f0 + (1.0L - f0) * powl(1.0L - c, 5.0L);
    return f * d * both / (4.0L * ao);
}
/* The specular's per-direction visibility (pfi_horizon_spec_cond_vis: A&S 4.4.45's arcsine and
   the logistic CDF of Bowling et al. 2009, no branch) against the long-double conditional HDF
   ora_cond_vis_b (atan2l, erfcl): unit directions above the macrosurface (elevations 1 to 90
   degrees), conditional deviations from 0.02 rad, moments that keep Cauchy-Schwarz; and the
   cases: vertical w, the step (zero Var(T): 1 above the mean, 0 below), zero texel Var(S)
   (Var(S) = base_var: no conditioning), NaN moments and slopes (0). Bound: the two
   approximations, 1.4e-4 (the CDF) plus phi(z) 5e-5 rad / deviation (the arcsine). */
static void test_horizon_spec_cond_vis_matches(void)
{
    pf_test_rng r;
    double worst = 0.0, worst_edge = 0.0;
    const double b = 0.01;
    int it, e, bad = 0;
    const pf_real nan = PF_R(NAN);
    r.state = 77u;
    for (it = 0; it < 20000; ++it) {
        double el = pf_test_uniform(&r, 0.02, 1.5707963), az = pf_test_uniform(&r, 0.0, 6.2831853);
        double wx = cos(el) * cos(az), wy = cos(el) * sin(az), wz = sin(el);
        double m1 = pf_test_uniform(&r, -0.3, 0.6), sd = pf_test_uniform(&r, 0.03, 0.3);
        double vx = pf_test_uniform(&r, 0.0, 0.2), vy = pf_test_uniform(&r, 0.0, 0.2), cxy = pf_test_uniform(&r, -0.9, 0.9) * sqrt(vx * vy);
        double mx = pf_test_uniform(&r, -0.3, 0.3), my = pf_test_uniform(&r, -0.3, 0.3);
        double dx = cos(az), dy = sin(az), es = mx * dx + my * dy, vs = vx * dx * dx + vy * dy * dy + 2.0 * cxy * dx * dy;
        double rho = pf_test_uniform(&r, -0.7, 0.7), ms, sx = pf_test_uniform(&r, -1.0, 1.0), sy = pf_test_uniform(&r, -1.0, 1.0);
        long double want;
        pf_real got;
        e = it % 16;
        if (e == 1) { wx = wy = 0.0; wz = 1.0; }
        if (e == 5) vx = vy = cxy = vs = 0.0;
        ms = rho * sd * sqrt(vs) + es * m1;
        want = ora_spec_cond_vis((long double)wx, (long double)wy, (long double)wz, (long double)m1, (long double)sd, (long double)ms,
                              (long double)mx, (long double)my, (long double)vx, (long double)vy, (long double)cxy,
                              (long double)sx, (long double)sy, (long double)b);
        if (e == 1) /* vertical: no azimuth, so no conditioning: Phi((pi/2 - E[T]) / (0.7 sigma_T)) */
            want = 0.5L * erfcl(((long double)m1 - 1.57079632679489661923L) / (0.7L * (long double)sd * sqrtl(2.0L)));
        {
            pf_slope_stats s = pf_slope_stats_make((pf_real)mx, (pf_real)my, (pf_real)(vx + b), (pf_real)(vy + b), (pf_real)cxy);
            pf_hdf_moments m = pf_hdf_moments_make((pf_real)m1, (pf_real)(m1 * m1 + sd * sd), (pf_real)ms);
            pf_vec3 w = pf_vec3_make((pf_real)wx, (pf_real)wy, (pf_real)wz);
            pf_real dsx = (pf_real)(mx - sx), dsy = (pf_real)(my - sy); /* E[s] - s_h */
            if (e == 6 || e == 7) { /* the step: Var(T) = 0, so no covariance either */
                /* E[T] kept 1e-3 rad from the elevation: the arcsine's 5e-5 rad (and the
                   compiler's rounding, e.g. nvcc's host code) must not decide the step */
                if (fabs(asin(wz) - m1) < 1e-3) m1 = asin(wz) + (m1 < asin(wz) ? -1e-3 : 1e-3);
                m = pf_hdf_moments_make((pf_real)m1, (pf_real)m1 * (pf_real)m1, (pf_real)(es * m1));
                want = asin(wz) > (double)(pf_real)m1 ? 1.0L : 0.0L;
            }
            if (e == 8) m.m1 = nan;
            if (e == 9) m.ms = nan;
            if (e == 10) dsx = nan;
            if (e == 11) m.m2 = nan;
            if (e >= 8 && e <= 11) want = 0.0L;
#ifdef __CUDACC__
            if (e >= 8 && e <= 11) continue; /* CUDA's fmin/fmax drop a NaN operand: as GLSL, no NaN contract */
#endif
            got = pfi_horizon_spec_cond_vis(w, m, s, (pf_real)b, dsx, dsy);
        }
        if (!(got >= PF_R(0.0) && got <= PF_R(1.0))) {
            ++bad;
        } else {
            double d = (double)fabsl((long double)got - want);
            if (e == 1 || (e >= 6 && e <= 11)) {
                if (d > worst_edge) worst_edge = d;
            } else if (d > worst) {
                worst = d;
            }
        }
    }
    pf_test_note("specular conditional visibility vs the long-double conditional HDF: max abs %.2g (cases %.2g)", worst, worst_edge);
    PF_CHECK(bad == 0, "%d outside [0, 1] or NaN", bad);
    PF_CHECK(worst <= 1.2e-3, "max abs %g", worst);
    PF_CHECK(worst_edge <= 1.2e-3, "cases: max abs %g", worst_edge);
}
static void test_horizon_specular_quadrature(void)
{
    pf_test_rng r;
    long double worst = 0.0L, worst_v = 0.0L;
    int it, bad = 0;
    r.state = 123u;
    for (it = 0; it < 400; ++it) {
        long double to = (long double)pf_test_uniform(&r, 0.05, 1.3), po = (long double)pf_test_uniform(&r, 0.0, 6.283);
        long double mx = (long double)pf_test_uniform(&r, -0.2, 0.2), my = (long double)pf_test_uniform(&r, -0.2, 0.2);
        long double vx = (long double)pf_test_uniform(&r, 0.02, 0.2), vy = (long double)pf_test_uniform(&r, 0.02, 0.2);
        long double cxy = (long double)pf_test_uniform(&r, -0.5, 0.5) * sqrtl(vx * vy), bv = 0.01L;
        long double mto = (long double)pf_test_uniform(&r, -0.1, 0.4), sdo = (long double)pf_test_uniform(&r, 0.05, 0.3);
        long double mti = (long double)pf_test_uniform(&r, -0.1, 0.4), sdi = (long double)pf_test_uniform(&r, 0.05, 0.3);
        long double ro = (long double)pf_test_uniform(&r, -0.8, 0.3), ri = (long double)pf_test_uniform(&r, -0.8, 0.3);
        long double f0 = (long double)pf_test_uniform(&r, 0.02, 1.0), wo[3], wi[3], ti, pi_, ref, vso, vsi, eso, esi, msto, msti;
        long double ro_i, hx, hy, hz;
        pf_real got, gv;
        wo[0] = sinl(to) * cosl(po); wo[1] = sinl(to) * sinl(po); wo[2] = cosl(to);
        /* the light near the mirror of the view about a slope drawn from the footprint's
           distribution (so that D is not negligible), or anywhere above */
        if (it & 1) {
            long double nsx = mx + sqrtl(vx) * (long double)pf_test_uniform(&r, -1.5, 1.5);
            long double nsy = my + sqrtl(vy) * (long double)pf_test_uniform(&r, -1.5, 1.5);
            long double n[3] = { -nsx, -nsy, 1.0L }, nl = sqrtl(n[0] * n[0] + n[1] * n[1] + 1.0L), dn;
            n[0] /= nl; n[1] /= nl; n[2] /= nl;
            dn = wo[0] * n[0] + wo[1] * n[1] + wo[2] * n[2];
            wi[0] = 2.0L * dn * n[0] - wo[0]; wi[1] = 2.0L * dn * n[1] - wo[1]; wi[2] = 2.0L * dn * n[2] - wo[2];
            if (wi[2] < 0.05L) continue;
        } else {
            ti = (long double)pf_test_uniform(&r, 0.05, 1.35);
            pi_ = (long double)pf_test_uniform(&r, 0.0, 6.283);
            wi[0] = sinl(ti) * cosl(pi_); wi[1] = sinl(ti) * sinl(pi_); wi[2] = cosl(ti);
        }
        if (wo[2] - mx * wo[0] - my * wo[1] < 0.05L) continue;
        ro_i = sqrtl(wi[0] * wi[0] + wi[1] * wi[1]);
        eso = mx * cosl(po) + my * sinl(po);
        vso = vx * cosl(po) * cosl(po) + vy * sinl(po) * sinl(po) + 2.0L * cxy * cosl(po) * sinl(po);
        esi = (mx * wi[0] + my * wi[1]) / ro_i;
        vsi = (vx * wi[0] * wi[0] + vy * wi[1] * wi[1] + 2.0L * cxy * wi[0] * wi[1]) / (ro_i * ro_i);
        msto = ro * sqrtl(vso) * sdo + eso * mto;
        msti = ri * sqrtl(vsi) * sdi + esi * mti;
        {
            pf_vec3 o = pf_vec3_make((pf_real)wo[0], (pf_real)wo[1], (pf_real)wo[2]);
            pf_vec3 i = pf_vec3_make((pf_real)wi[0], (pf_real)wi[1], (pf_real)wi[2]);
            pf_hdf_moments mo = pf_hdf_moments_make((pf_real)mto, (pf_real)(mto * mto + sdo * sdo), (pf_real)msto);
            pf_hdf_moments mi = pf_hdf_moments_make((pf_real)mti, (pf_real)(mti * mti + sdi * sdi), (pf_real)msti);
            pf_slope_stats st = pf_slope_stats_make((pf_real)mx, (pf_real)my, (pf_real)(vx + bv), (pf_real)(vy + bv), (pf_real)cxy);
            got = pf_horizon_leadr_specular(o, i, st, (pf_real)bv, mo, mi, (pf_real)f0);
            gv = pf_horizon_specular_visibility(o, i, mo, mi, st, (pf_real)bv);
        }
        ref = ora_horizon_spec(wo, wi, mto, sdo, msto, mti, sdi, msti, mx, my, vx, vy, cxy, bv, f0);
        hx = wo[0] + wi[0]; hy = wo[1] + wi[1]; hz = wo[2] + wi[2];
        {
            long double al = 0.5L * (1.0L + wo[0] * wi[0] + wo[1] * wi[1] + wo[2] * wi[2]);
            long double vo = ora_spec_cond_vis(wo[0], wo[1], wo[2], mto, sdo, msto, mx, my, vx, vy, cxy, -hx / hz, -hy / hz, bv);
            long double vi = ora_spec_cond_vis(wi[0], wi[1], wi[2], mti, sdi, msti, mx, my, vx, vy, cxy, -hx / hz, -hy / hz, bv);
            long double both = al * (vo < vi ? vo : vi) + (1.0L - al) * (vo + vi - 1.0L > 0.0L ? vo + vi - 1.0L : 0.0L);
            if (fabsl((long double)gv - both) > worst_v) worst_v = fabsl((long double)gv - both);
        }
        /* relative to the lobe's scale: the value without visibility (ref / V_h where V_h > 0) */
        {
            long double scale = ora_horizon_spec(wo, wi, -1.5L, 1e-3L, -1.5L * eso, -1.5L, 1e-3L, -1.5L * esi, mx, my, vx, vy, cxy, bv, f0);
            long double e = fabsl((long double)got - ref) / (scale + 1e-6L);
            if (e > worst) worst = e;
        }
        bad += !pf_test_bits_finite(got) || got < PF_R(0.0) || !(gv >= PF_R(0.0) && gv <= PF_R(1.0));
    }
    pf_test_note("horizon specular vs long-double formula: visibility max abs %.2Lg, LEADR form max rel %.2Lg", worst_v, worst);
    PF_CHECK(bad == 0, "%d non-finite, negative or out of [0, 1]", bad);
    /* the shader tier inside (pfi_horizon_spec_cond_vis: A&S 4.4.45's arcsine, 5e-5 rad, and a
       logistic CDF, 1.4e-4, over 0.7 times the deviation): measured 4.1e-4 for both in float and double */
    PF_CHECK(worst_v <= 5e-4L, "visibility %Lg", worst_v);
    PF_CHECK(worst <= 5e-4L, "radiance %Lg", worst);
}

/* The horizon specular from 16-bit pyramids (docs/encode.md): one-texel footprints of a Gaussian
   field (corr 4 texels, 128^2), its n = 32 HDF moments and per-texel slope moments stored in
   half and in UNORM16 (pf_encode.h, per-map ranges; slope moments about the map's mean slope,
   as bench/storage.h), decoded, and pf_horizon_leadr_specular evaluated on both at the texel's
   highlight (the half vector within 1.5 base deviations of the texel's slope), views 0-75 deg.
   Storage error: relative L2 of (16-bit - float32) over the float32 values; pf_leadr_specular's
   own storage error (the quantized D) alongside. A texel holds one slope, so its Var(S) is 0 in
   float32 and the rounding of E[x^2] - E[x]^2 in 16 bits: conditioning the horizon on S alone
   made beta the ratio of two rounding errors (measured here: 0.67 half, 0.66 unorm16, against
   0.0062 / 0.0006 for LEADR); on S + B (the base lobe's slope, pfi_horizon_spec_cond_vis) it is
   0.018 / 0.017 (float and double; the rest is the rounding of Var(T) at the horizon's step).
   Bound: LEADR's own plus 0.025. */
static void hs_decode(const pf_real *src, pf_real *dst, long long n, int C, int fmt)
{
    pf_real *off = (pf_real *)calloc((size_t)C, sizeof(pf_real)), *sc = (pf_real *)calloc((size_t)C, sizeof(pf_real));
    unsigned short *q = (unsigned short *)calloc((size_t)(n * C), sizeof(unsigned short));
    long long i;
    if (!off || !sc || !q || pf_encode_ranges(src, n, C, off, sc) != PF_OK || pf_encode_channels(src, n, C, off, sc, fmt, q) != PF_OK) {
        PF_CHECK(0, "encode");
    } else {
        for (i = 0; i < n * C; ++i)
            dst[i] = fmt == PF_ENCODE_HALF ? pf_real_from_half(q[i])
                                           : pf_unorm_decode((pf_real)q[i] / PF_R(65535.0), off[i % C], sc[i % C]);
    }
    free(off);
    free(sc);
    free(q);
}
static void hs_decode_slope(const pf_real *src, pf_real *dst, long long n, int fmt)
{
    unsigned short *q = (unsigned short *)calloc((size_t)(n * 5), sizeof(unsigned short));
    pf_slope_encoding e;
    long long i;
    if (!q || pf_slope_encoding_find(src, n, 1, &e) != PF_OK || pf_slope_moments_encode(src, n, &e, fmt, q) != PF_OK) {
        PF_CHECK(0, "slope encode");
        free(q);
        return;
    }
    if (fmt == PF_ENCODE_HALF) { /* half: the centred moments themselves */
        e.off_x = e.off_y = e.off_xx = e.off_yy = e.off_xy = PF_R(0.0);
        e.sc_x = e.sc_y = e.sc_xx = e.sc_yy = e.sc_xy = PF_R(1.0);
    }
    for (i = 0; i < n; ++i) {
        pf_real v[5];
        pf_slope_moments m;
        int k;
        for (k = 0; k < 5; ++k)
            v[k] = fmt == PF_ENCODE_HALF ? pf_real_from_half(q[5 * i + k]) : (pf_real)q[5 * i + k] / PF_R(65535.0);
        m = pf_slope_moments_decode(pf_slope_moments_make(v[0], v[1], v[2], v[3], v[4]), e);
        dst[5 * i] = m.ex;
        dst[5 * i + 1] = m.ey;
        dst[5 * i + 2] = m.exx;
        dst[5 * i + 3] = m.eyy;
        dst[5 * i + 4] = m.exy;
    }
    free(q);
}
static void test_horizon_specular_storage_16bit(void)
{
    const int W = 128, NAZ = 32, C = 3 * 32, fmts[2] = { PF_ENCODE_HALF, PF_ENCODE_UNORM16 };
    const double base_sigma = 0.1;
    const char *fname[2] = { "half", "unorm16" };
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    pfm_surface surf;
    long long n = (long long)W * W, t;
    pf_real *hm = (pf_real *)malloc(sizeof(pf_real) * (size_t)n), *hor = (pf_real *)malloc(sizeof(pf_real) * (size_t)(n * C));
    pf_real *sl = (pf_real *)malloc(sizeof(pf_real) * (size_t)(n * 5)), *hq = (pf_real *)malloc(sizeof(pf_real) * (size_t)(n * C));
    pf_real *sq = (pf_real *)malloc(sizeof(pf_real) * (size_t)(n * 5));
    int f, it, i, used = 0;
    p.corr_texels = 4.0;
    memset(&surf, 0, sizeof surf);
    if (!hm || !hor || !sl || !hq || !sq || pfm_surface_make(&surf, W, W, 1.0, p) != 0) {
        PF_CHECK(0, "setup");
        free(hm); free(hor); free(sl); free(hq); free(sq);
        return;
    }
    for (i = 0; i < W * W; ++i) hm[i] = (pf_real)surf.height[i];
    PF_CHECK(pf_horizon_map(hm, W, W, PF_R(1.0), NAZ, 64, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, hor) == PF_OK, "map");
    for (t = 0; t < n; ++t) {
        double m5[5];
        pfm_footprint_moments(&surf, (int)(t % W), (int)(t / W), 1, m5);
        for (i = 0; i < 5; ++i) sl[5 * t + i] = (pf_real)m5[i];
    }
    for (f = 0; f < 2; ++f) {
        double dh = 0.0, rh = 0.0, dl = 0.0, rl = 0.0, eh, el;
        pf_test_rng r;
        r.state = 91u;
        hs_decode(hor, hq, n, C, fmts[f]);
        hs_decode_slope(sl, sq, n, fmts[f]);
        used = 0;
        for (it = 0; it < 4000; ++it) {
            long long tx = (long long)(pf_test_uniform(&r, 0.0, 0.9999) * (double)n);
            double th = pf_test_uniform(&r, 0.0, 75.0) * 3.14159265358979323846 / 180.0, ph = pf_test_uniform(&r, 0.0, 6.2831853);
            double hx = (double)sl[5 * tx] + base_sigma * pf_test_uniform(&r, -1.5, 1.5), hy = (double)sl[5 * tx + 1] + base_sigma * pf_test_uniform(&r, -1.5, 1.5);
            double wo[3] = { sin(th) * cos(ph), sin(th) * sin(ph), cos(th) }, nn[3] = { -hx, -hy, 1.0 }, nl, dn, wi[3];
            pf_real v[2][2];
            int q;
            nl = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + 1.0);
            for (i = 0; i < 3; ++i) nn[i] /= nl;
            dn = wo[0] * nn[0] + wo[1] * nn[1] + wo[2] * nn[2];
            for (i = 0; i < 3; ++i) wi[i] = 2.0 * dn * nn[i] - wo[i];
            if (wi[2] < 0.05 || dn <= 0.0) continue;
            for (q = 0; q < 2; ++q) { /* float32, then the format */
                const pf_real *H = q == 0 ? hor : hq, *S = q == 0 ? sl : sq;
                pf_vec3 o = pf_vec3_make((pf_real)wo[0], (pf_real)wo[1], (pf_real)wo[2]);
                pf_vec3 l = pf_vec3_make((pf_real)wi[0], (pf_real)wi[1], (pf_real)wi[2]);
                pf_horizon_azimuth ao = pf_horizon_azimuth_of(o, NAZ), al = pf_horizon_azimuth_of(l, NAZ);
                const pf_real *tp = H + tx * C;
                pf_hdf_moments mo = pf_hdf_moments_lerp(pf_hdf_moments_make(tp[3 * ao.i0], tp[3 * ao.i0 + 1], tp[3 * ao.i0 + 2]),
                                                        pf_hdf_moments_make(tp[3 * ao.i1], tp[3 * ao.i1 + 1], tp[3 * ao.i1 + 2]), ao.f);
                pf_hdf_moments ml = pf_hdf_moments_lerp(pf_hdf_moments_make(tp[3 * al.i0], tp[3 * al.i0 + 1], tp[3 * al.i0 + 2]),
                                                        pf_hdf_moments_make(tp[3 * al.i1], tp[3 * al.i1 + 1], tp[3 * al.i1 + 2]), al.f);
                pf_slope_stats st = pf_slope_moments_stats(pf_slope_moments_make(S[5 * tx], S[5 * tx + 1], S[5 * tx + 2], S[5 * tx + 3],
                                                                                 S[5 * tx + 4]), (pf_real)(base_sigma * base_sigma));
                v[q][0] = pf_horizon_leadr_specular(o, l, st, (pf_real)(base_sigma * base_sigma), mo, ml, PF_R(1.0));
                v[q][1] = pf_leadr_specular(o, l, st, PF_R(1.0));
            }
            dh += ((double)v[1][0] - (double)v[0][0]) * ((double)v[1][0] - (double)v[0][0]);
            rh += (double)v[0][0] * (double)v[0][0];
            dl += ((double)v[1][1] - (double)v[0][1]) * ((double)v[1][1] - (double)v[0][1]);
            rl += (double)v[0][1] * (double)v[0][1];
            ++used;
        }
        eh = sqrt(dh / rh);
        el = sqrt(dl / rl);
        pf_test_note("%s, 1-texel footprints, %d samples: storage error horizon LEADR %.3g, LEADR %.3g", fname[f], used, eh, el);
        PF_CHECK(used >= 2000, "%d samples", used);
        PF_CHECK(eh <= el + 0.025, "%s: horizon %g, LEADR %g", fname[f], eh, el);
    }
    pfm_surface_free(&surf);
    free(hm); free(hor); free(sl); free(hq); free(sq);
}

/* The limits that tie the horizon specular to the library's Smith forms: with every horizon
   far below (T = -1.5 rad, uncorrelated) nothing is hidden, so pf_horizon_leadr_specular is
   pf_leadr_specular without its G (divided by pf_beckmann_masking_shadowing), and
   pf_horizon_vmf_specular is pf_vmf_sum_specular without its G (pf_vmf_sum_g2); horizons above
   every direction give 0; the lod fade's ends are the two functions exactly, halfway their mean. */
static void test_horizon_specular_limits(void)
{
    pf_real bv = PF_R(0.01), low = PF_R(-1.5), high = PF_R(1.5);
    pf_slope_stats s = pf_slope_stats_make(PF_R(0.05), PF_R(-0.03), PF_R(0.06) + bv, PF_R(0.04) + bv, PF_R(0.01));
    pf_hdf_moments ml = pf_hdf_moments_make(low, low * low, PF_R(0.0)), mh = pf_hdf_moments_make(high, high * high, PF_R(0.0));
    int k, bad = 0;
    for (k = 0; k < 6; ++k) {
        pf_vec3 wo = pf_vec3_normalize(pf_vec3_make(PF_R(0.5) - PF_R(0.15) * PF_R(k), PF_R(0.2), PF_R(0.84)));
        pf_vec3 wi = pf_vec3_normalize(pf_vec3_make(PF_R(-0.3) + PF_R(0.1) * PF_R(k), PF_R(0.4) - PF_R(0.1) * PF_R(k), PF_R(0.87)));
        pf_real leadr = pf_leadr_specular(wo, wi, s, PF_R(0.04));
        pf_real open = pf_horizon_leadr_specular(wo, wi, s, bv, ml, ml, PF_R(0.04));
        pf_real want = leadr / pf_beckmann_masking_shadowing(wo, wi, s);
        pf_real hz = pf_horizon_leadr_specular(wo, wi, s, bv, ml, mh, PF_R(0.04));
        pf_vmf_sum sum = pf_vmf_sum_zero();
        pf_real vopen, vwant;
        bad += !(PF_FABS(open - want) <= PF_R(2e-5) * want);
        bad += pf_horizon_leadr_specular(wo, wi, s, bv, mh, mh, PF_R(0.04)) != PF_R(0.0);
        bad += pf_horizon_leadr_specular_lod(wo, wi, s, bv, ml, mh, PF_R(0.04), PF_R(1.0), PF_R(2.0), PF_R(6.0)) != hz;
        bad += pf_horizon_leadr_specular_lod(wo, wi, s, bv, ml, mh, PF_R(0.04), PF_R(6.0), PF_R(2.0), PF_R(6.0)) != leadr;
        bad += !(PF_FABS(pf_horizon_leadr_specular_lod(wo, wi, s, bv, ml, mh, PF_R(0.04), PF_R(4.0), PF_R(2.0), PF_R(6.0)) -
                         PF_R(0.5) * (hz + leadr)) <= PF_R(1e-6) * (hz + leadr));
        /* two lobes */
        sum = pf_vmf_sum_add(sum, pf_vmf_lobe_make(PF_R(0.6), PF_R(0.1), PF_R(-0.05), PF_R(0.99)), wo, wi, bv);
        sum = pf_vmf_sum_add(sum, pf_vmf_lobe_make(PF_R(0.4), PF_R(-0.1), PF_R(0.1), PF_R(0.98)), wo, wi, bv);
        vopen = pf_horizon_vmf_specular(sum, wo, wi, s, bv, ml, ml, PF_R(0.04));
        vwant = pf_vmf_sum_specular(sum, wo, wi, PF_R(0.04)) / pf_vmf_sum_g2(sum, wo, wi);
        bad += !(PF_FABS(vopen - vwant) <= PF_R(2e-5) * vwant);
        bad += pf_horizon_vmf_specular(sum, wo, wi, s, bv, mh, mh, PF_R(0.04)) != PF_R(0.0);
        bad += pf_horizon_vmf_specular_lod(sum, wo, wi, s, bv, ml, ml, PF_R(0.04), PF_R(0.0), PF_R(2.0), PF_R(6.0)) != vopen;
        bad += pf_horizon_vmf_specular_lod(sum, wo, wi, s, bv, ml, ml, PF_R(0.04), PF_R(9.0), PF_R(2.0), PF_R(6.0)) !=
               pf_vmf_sum_specular(sum, wo, wi, PF_R(0.04));
        if (k == 0) pf_test_note("open sky: horizon LEADR %.6g vs LEADR / G %.6g; vMF %.6g vs %.6g", (double)open, (double)want,
                                 (double)vopen, (double)vwant);
    }
    PF_CHECK(bad == 0, "%d limit violations", bad);
    /* below the macrosurface, at or below the mean plane, an empty sum: 0 */
    {
        pf_vec3 up = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)), down = pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(-0.8));
        pf_slope_stats tilt = pf_slope_stats_make(PF_R(2.0), PF_R(0.0), PF_R(0.05), PF_R(0.05), PF_R(0.0));
        pf_vec3 graze = pf_vec3_normalize(pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(0.3)));
        PF_CHECK(pf_horizon_leadr_specular(down, up, s, bv, ml, ml, PF_R(1.0)) == PF_R(0.0), "view below");
        PF_CHECK(pf_horizon_leadr_specular(up, down, s, bv, ml, ml, PF_R(1.0)) == PF_R(0.0), "light below");
        PF_CHECK(pf_horizon_leadr_specular(graze, up, tilt, bv, ml, ml, PF_R(1.0)) == PF_R(0.0), "view below the mean plane");
        PF_CHECK(pf_horizon_vmf_specular(pf_vmf_sum_zero(), up, up, s, bv, ml, ml, PF_R(1.0)) == PF_R(0.0), "empty sum");
    }
}

/* The field the two specular brute-force tests shade: a periodic Gaussian field of HS_W^2
   texels (pfm corpus defaults, RMS slope 0.4) with correlation corr texels, its heights as
   pf_real and its HDF-moment pyramid (HS_NAZ azimuths, march 64 texels, wrap). 0 (and a
   failed "setup" check, nothing left allocated) if it cannot be built. */
#define HS_W 128
#define HS_NAZ 32
typedef struct hs_field {
    pfm_surface surf;
    pf_real *hm, *pyr;
} hs_field;
static void hs_field_free(hs_field *F)
{
    pfm_surface_free(&F->surf);
    free(F->pyr);
    free(F->hm);
    F->pyr = F->hm = NULL;
}
static int hs_field_make(hs_field *F, double corr)
{
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    int i;
    p.corr_texels = corr;
    memset(F, 0, sizeof *F);
    F->hm = (pf_real *)malloc(sizeof(pf_real) * (size_t)(HS_W * HS_W));
    F->pyr = (pf_real *)malloc(sizeof(pf_real) * (size_t)(pf_mip_texel_count(HS_W, HS_W) * 3 * HS_NAZ));
    if (!F->hm || !F->pyr || pfm_surface_make(&F->surf, HS_W, HS_W, 1.0, p) != 0) {
        PF_CHECK(0, "setup");
        hs_field_free(F);
        return 0;
    }
    for (i = 0; i < HS_W * HS_W; ++i) F->hm[i] = (pf_real)F->surf.height[i];
    PF_CHECK(pf_horizon_pyramid(F->hm, HS_W, HS_W, PF_R(1.0), HS_NAZ, 64, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, F->pyr)
                 == PF_OK, "pyramid");
    return 1;
}
/* The HDF moments toward w of the footprint of n x n texels at (x0, y0) (its texel of the level
   log2 n): the two stored azimuths around w's, mixed as a shader does (pf_hdf_moments_lerp). */
static pf_hdf_moments hs_hdf(const hs_field *F, int x0, int y0, int n, pf_vec3 w)
{
    int lev = 0;
    const pf_real *tx;
    pf_horizon_azimuth a = pf_horizon_azimuth_of(w, HS_NAZ);
    while ((1 << lev) < n) ++lev;
    tx = F->pyr + (pf_mip_level_offset(HS_W, HS_W, lev) + (long long)(y0 / n) * (HS_W / n) + x0 / n) * (3 * HS_NAZ);
    return pf_hdf_moments_lerp(pf_hdf_moments_make(tx[3 * a.i0], tx[3 * a.i0 + 1], tx[3 * a.i0 + 2]),
                               pf_hdf_moments_make(tx[3 * a.i1], tx[3 * a.i1 + 1], tx[3 * a.i1 + 2]), a.f);
}
/* The footprint's exact slope moments (the reference's central differences) as statistics with
   the base lobe's variance bv added; m5 gets the moments. */
static pf_slope_stats hs_stats(const hs_field *F, int x0, int y0, int n, double bv, double m5[5])
{
    pfm_footprint_moments(&F->surf, x0, y0, n, m5);
    return pf_slope_moments_stats(pf_slope_moments_make((pf_real)m5[0], (pf_real)m5[1], (pf_real)m5[2], (pf_real)m5[3],
                                                        (pf_real)m5[4]),
                                  (pf_real)bv);
}

/* Against the brute force (tests/reference/pf_microsurface.h): a fine Gaussian height field
   (correlation 4 texels, RMS slope 0.4, 128^2), its n = 32 HDF-moment pyramid, 4 x 4-texel
   footprints, views 30-75 degrees, the light at the mirror of the view about the footprint's
   mesonormal (the highlight) and one more above; reference = pfm_reference_shade with the
   full visibility (every occluder of the field). Pooled relative L2 of pf_horizon_leadr_specular
   and of pf_leadr_specular (Smith): the horizon must remove most of Smith's error, which is
   the occlusion by bumps outside the footprint. */
static void test_horizon_specular_brute_force(void)
{
    const int W = HS_W, N = 4;
    const double base_sigma = 0.1, view_deg[4] = { 30.0, 45.0, 60.0, 75.0 };
    hs_field F;
    unsigned char *vo = (unsigned char *)malloc((size_t)(W * W)), *vi = (unsigned char *)malloc((size_t)(W * W));
    double e_h = 0.0, e_s = 0.0, r2 = 0.0;
    pf_test_rng r;
    int f, v, li, i, j, used = 0;
    if (!vo || !vi || !hs_field_make(&F, 4.0)) {
        if (!vo || !vi) PF_CHECK(0, "setup");
        free(vo);
        free(vi);
        return;
    }
    r.state = 5u;
    for (f = 0; f < 24; ++f) {
        int x0 = N * (int)(pf_test_uniform(&r, 0.0, 0.999) * (W / N)), y0 = N * (int)(pf_test_uniform(&r, 0.0, 0.999) * (W / N));
        double m5[5];
        pf_slope_stats st = hs_stats(&F, x0, y0, N, base_sigma * base_sigma, m5);
        for (v = 0; v < 4; ++v) {
            double phi = pf_test_uniform(&r, 0.0, 6.283), t = view_deg[v] * 3.14159265358979323846 / 180.0;
            double wo[3] = { sin(t) * cos(phi), sin(t) * sin(phi), cos(t) }, nb[3], nl, dn, wl[2][3];
            nb[0] = -m5[0]; nb[1] = -m5[1]; nb[2] = 1.0;
            nl = sqrt(nb[0] * nb[0] + nb[1] * nb[1] + 1.0);
            nb[0] /= nl; nb[1] /= nl; nb[2] /= nl;
            dn = wo[0] * nb[0] + wo[1] * nb[1] + wo[2] * nb[2];
            for (i = 0; i < 3; ++i) wl[0][i] = 2.0 * dn * nb[i] - wo[i];
            {
                double ti = pf_test_uniform(&r, 0.2, 1.2), pi_ = pf_test_uniform(&r, 0.0, 6.283);
                wl[1][0] = sin(ti) * cos(pi_); wl[1][1] = sin(ti) * sin(pi_); wl[1][2] = cos(ti);
            }
            if (wo[2] - m5[0] * wo[0] - m5[1] * wo[1] < 0.25 * wo[2]) continue; /* the bench's cull */
            for (li = 0; li < 2; ++li) {
                pf_vec3 o = pf_test_vec3(wo), l = pf_test_vec3(wl[li]);
                pfm_shade ref;
                double hz, sm;
                if (wl[li][2] < 0.05) continue;
                for (j = y0; j < y0 + N; ++j)
                    for (i = x0; i < x0 + N; ++i) {
                        vo[j * W + i] = (unsigned char)pfm_visible(&F.surf, i, j, wo);
                        vi[j * W + i] = (unsigned char)pfm_visible(&F.surf, i, j, wl[li]);
                    }
                ref = pfm_reference_shade(&F.surf, vo, vi, x0, y0, N, wo, wl[li], base_sigma, 1.0);
                hz = (double)pf_horizon_leadr_specular(o, l, st, (pf_real)(base_sigma * base_sigma), hs_hdf(&F, x0, y0, N, o),
                                                       hs_hdf(&F, x0, y0, N, l), PF_R(1.0));
                sm = (double)pf_leadr_specular(o, l, st, PF_R(1.0));
                e_h += (hz - ref.spec) * (hz - ref.spec);
                e_s += (sm - ref.spec) * (sm - ref.spec);
                r2 += ref.spec * ref.spec;
                ++used;
            }
        }
    }
    e_h = sqrt(e_h / r2);
    e_s = sqrt(e_s / r2);
    pf_test_note("brute force, gaussian (corr 4), 4x4 footprints, views 30-75, %d samples: horizon %.3f, Smith %.3f",
                 used, e_h, e_s);
    PF_CHECK(used >= 100, "%d samples", used);
    PF_CHECK(e_h <= HSPEC_BRUTE_BOUND && e_h <= 0.6 * e_s, "horizon %g, Smith %g", e_h, e_s);
    hs_field_free(&F);
    free(vo);
    free(vi);
}

/* The reflecting facets' visibility at grazing views, against the brute force: Gaussian fields
   of 128^2 texels, RMS slope 0.4, correlation 12 texels (the plane picture's map) and 4 (as
   test_horizon_specular_brute_force), 8 x 8-texel footprints (the pyramid's level 3: their exact HDF and slope moments), views 75, 80
   and 85 degrees from the zenith, the light 20 degrees above the plane in front of the view
   (azimuth opposite the view's within +-30 degrees: the plane picture's forward highlight,
   bench/pictures.c, whose 4-16-texel footprints are seen 75-83 degrees from the zenith). The
   brute force: V = sum_t w_t V_o,t V_i,t / sum_t w_t over the footprint's texels, w_t the
   texel's unshadowed specular term (pfm_reference_shade with every texel visible), V_o,t and
   V_i,t marched through the whole field (pfm_visible); pf_horizon_specular_visibility against
   it, pooled with the weights U = sum_t w_t / sum_t a_t (the footprint's unshadowed radiance,
   a_t its texels' projected areas; footprints with sum_t a_t <= 0.25 wo.z skipped, the
   bench's cull): the ratio sum U V_h / sum U V (the visibility's bias) and sum U |V_h - V| /
   sum U V, with Smith's G2 of the same statistics (pf_beckmann_masking_shadowing) beside it.
   Bounds: HSPEC_GRAZE_* (measured there). On the finer field (footprints of two correlation
   lengths) the conditional Gaussian of T | S + B hides the reflecting facets from the view too
   often (V_h 0.69-0.70 of the brute force's at 75-80 degrees, 0.23 at 85; the per-texel
   horizons of the same map agree with the march to 3-4%, a Gaussian fitted to the reflecting
   texels' own horizons to 6%: the linear conditioning on S is what misses); there the bounds
   are wide and recorded, not a claim. */
static void graze_field(double corr, double out[3][4])
{
    const int W = HS_W, N = 8;
    const double base_sigma = 0.1, view_deg[3] = { 75.0, 80.0, 85.0 }, pi = 3.14159265358979323846;
    hs_field F;
    double sv[3] = { 0, 0, 0 }, sh[3] = { 0, 0, 0 }, se[3] = { 0, 0, 0 }, sge[3] = { 0, 0, 0 };
    pf_test_rng r;
    int f, v, i, j, used[3] = { 0, 0, 0 };
    memset(out, 0, sizeof(double) * 3 * 4);
    if (!hs_field_make(&F, corr)) return;
    r.state = corr > 8.0 ? 12u : 11u;
    for (f = 0; f < 64; ++f) {
        int x0 = N * (int)(pf_test_uniform(&r, 0.0, 0.999) * (W / N)), y0 = N * (int)(pf_test_uniform(&r, 0.0, 0.999) * (W / N));
        double m5[5];
        pf_slope_stats st = hs_stats(&F, x0, y0, N, base_sigma * base_sigma, m5);
        for (v = 0; v < 3; ++v) {
            double phi = pf_test_uniform(&r, 0.0, 2.0 * pi), t = view_deg[v] * pi / 180.0;
            double pl = phi + pi + pf_test_uniform(&r, -pi / 6.0, pi / 6.0), el = 20.0 * pi / 180.0;
            double wo[3] = { sin(t) * cos(phi), sin(t) * sin(phi), cos(t) }, wl[3] = { cos(el) * cos(pl), cos(el) * sin(pl), sin(el) };
            double sw = 0.0, sa = 0.0, svis = 0.0, u, vh, g2;
            pf_vec3 o = pf_test_vec3(wo), l = pf_test_vec3(wl);
            for (j = y0; j < y0 + N; ++j)
                for (i = x0; i < x0 + N; ++i) {
                    double sx, sy, at, wt;
                    pfm_slope(&F.surf, i, j, &sx, &sy);
                    at = wo[2] - sx * wo[0] - sy * wo[1];
                    sa += at;
                    if (!(at > 0.0)) continue;
                    wt = pfm_reference_shade(&F.surf, NULL, NULL, i, j, 1, wo, wl, base_sigma, 1.0).spec * at;
                    if (!(wt > 0.0)) continue;
                    sw += wt;
                    if (pfm_visible(&F.surf, i, j, wo) && pfm_visible(&F.surf, i, j, wl)) svis += wt;
                }
            if (!(sa > 0.25 * N * N * wo[2]) || !(sw > 0.0)) continue; /* the bench's cull */
            u = sw / sa;
            vh = (double)pf_horizon_specular_visibility(o, l, hs_hdf(&F, x0, y0, N, o), hs_hdf(&F, x0, y0, N, l), st,
                                                        (pf_real)(base_sigma * base_sigma));
            g2 = (double)pf_beckmann_masking_shadowing(o, l, st);
            sv[v] += u * svis / sw;
            sh[v] += u * vh;
            se[v] += u * fabs(vh - svis / sw);
            sge[v] += u * fabs(g2 - svis / sw);
            ++used[v];
        }
    }
    for (v = 0; v < 3; ++v) {
        out[v][0] = sh[v] / sv[v];
        out[v][1] = se[v] / sv[v];
        out[v][2] = sge[v] / sv[v];
        out[v][3] = used[v];
    }
    hs_field_free(&F);
}

static void test_horizon_specular_grazing_brute_force(void)
{
    static const double corr[2] = { 12.0, 4.0 }, deg[3] = { 75.0, 80.0, 85.0 };
    double o[2][3][4];
    int c, v;
    for (c = 0; c < 2; ++c) {
        graze_field(corr[c], o[c]);
        for (v = 0; v < 3; ++v) {
            pf_test_note("corr %.0f, %.0f deg (%.0f footprints): V_h bias %.3f, error %.3f (Smith G2 %.3f)", corr[c], deg[v],
                         o[c][v][3], o[c][v][0], o[c][v][1], o[c][v][2]);
            PF_CHECK(o[c][v][3] >= 30.0, "corr %g, %g deg: %g footprints", corr[c], deg[v], o[c][v][3]);
            /* closer than Smith's G2 at every view: by half on the picture's field, and on the
               finer one too (0.261 against 0.365 at 75 degrees; 0.416 without the convexity term) */
            PF_CHECK(o[c][v][1] < (c == 0 ? 0.5 : 0.8) * o[c][v][2], "corr %g, %g deg: error %g, Smith's %g", corr[c], deg[v],
                     o[c][v][1], o[c][v][2]);
        }
        for (v = 0; v < 2; ++v)
            PF_CHECK(fabs(o[c][v][0] - 1.0) <= HSPEC_GRAZE_BIAS[c] && o[c][v][1] <= HSPEC_GRAZE_ERR[c],
                     "corr %g, %g deg: bias %g, error %g", corr[c], deg[v], o[c][v][0], o[c][v][1]);
    }
    for (c = 0; c < 2; ++c)
        PF_CHECK(o[c][2][1] <= HSPEC_GRAZE_ERR_85[c], "corr %g, 85 deg: error %g", corr[c], o[c][2][1]);
}

static void test_horizon_azimuth_of(void)
{
    int n, i, bad = 0;
    for (n = 1; n <= 16; n *= 2)
        for (i = 0; i < n; ++i) {
            long double f = 0.3L, phi = 2.0L * TPI * (i + f) / n;
            pf_horizon_azimuth a = pf_horizon_azimuth_of(pf_vec3_make((pf_real)cosl(phi), (pf_real)sinl(phi), PF_R(0.5)), n);
            bad += a.i0 != i || a.i1 != (i + 1) % n || fabsl((long double)a.f - f) > 1e-4L;
        }
    PF_CHECK(bad == 0, "%d wrong", bad);
    PF_CHECK(pf_horizon_azimuth_of(pf_vec3_make(0, 0, 1), 8).i0 == 0, "zenith");
    PF_CHECK(pf_horizon_azimuth_of(pf_vec3_make((pf_real)NAN, 0, 1), 8).i0 == 0, "nan");
}


/* The Legendre struct: the getter returns each member (0 outside 0 .. 7), lerp mixes them. */
static void test_horizon_legendre_struct(void)
{
    pf_hdf_legendre a = pf_hdf_legendre_make(1, 2, 3, 4, 5, 6, 7, 8), b = pf_hdf_legendre_make(8, 7, 6, 5, 4, 3, 2, 1);
    pf_hdf_legendre m = pf_hdf_legendre_lerp(a, b, PF_R(0.25));
    int j, bad = 0;
    for (j = 0; j < 8; ++j) {
        bad += pf_hdf_legendre_coeff(a, j) != PF_R(j + 1);
        bad += fabs((double)pf_hdf_legendre_coeff(m, j) - (0.75 * (j + 1) + 0.25 * (8 - j))) > 1e-6;
    }
    bad += pf_hdf_legendre_coeff(a, -1) != PF_R(0.0) || pf_hdf_legendre_coeff(a, 8) != PF_R(0.0);
    PF_CHECK(bad == 0, "%d wrong", bad);
}

/* ---------------------------------------------------------------- bad input */
static void test_horizon_bad_input_writes_nothing(void)
{
    enum { W = 16, H = 12 };
    static pf_real hm[W * H], out[W * H * 48];
    int c, rc, bad = 0;
    size_t i;
    make_map(hm, W, H, 1u);
#define FILL() for (i = 0; i < sizeof out / sizeof out[0]; ++i) out[i] = PF_R(-7.0)
#define UNTOUCHED() do { for (i = 0; i < sizeof out / sizeof out[0]; ++i) bad += out[i] != PF_R(-7.0); } while (0)
#define EXPECT(call, code) do { FILL(); rc = (call); PF_CHECK(rc == (code), "%s: rc %d", #call, rc); UNTOUCHED(); } while (0)
    EXPECT(pf_horizon_map(NULL, W, H, PF_R(1.0), 4, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, 0, H, PF_R(1.0), 4, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, 0, PF_R(1.0), 4, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), 0, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), 4, 0, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(0.0), 4, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(NAN), 4, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(INFINITY), 4, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), 4, 8, 7, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), 4, 8, PF_BORDER_WRAP, 9, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), 4, 8, PF_BORDER_WRAP, PF_HORIZON_LEGENDRE, 0, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), 4, 8, PF_BORDER_WRAP, PF_HORIZON_LEGENDRE, 9, out), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), 4, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, NULL), PF_ERR_ARG);
    EXPECT(pf_horizon_map(hm, (int)PF_MAX_SIDE + 1, H, PF_R(1.0), 4, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_SIZE);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), (int)PF_MAX_SIDE + 1, 8, PF_BORDER_WRAP, PF_HORIZON_ANGLES, 0, out), PF_ERR_SIZE);
    EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), (int)PF_MAX_SIDE / 2, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_SIZE);
    EXPECT(pf_horizon_pyramid(hm, W, H, PF_R(1.0), 0, 8, PF_BORDER_WRAP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
    /* NaN or infinite heights anywhere, even the last texel */
    for (c = 0; c < 3; ++c) {
        pf_real keep = hm[W * H - 1];
        hm[W * H - 1] = c == 0 ? PF_R(NAN) : (c == 1 ? PF_R(INFINITY) : -PF_R(INFINITY));
        EXPECT(pf_horizon_map(hm, W, H, PF_R(1.0), 4, 8, PF_BORDER_CLAMP, PF_HORIZON_ANGLES, 0, out), PF_ERR_ARG);
        EXPECT(pf_horizon_pyramid(hm, W, H, PF_R(1.0), 4, 8, PF_BORDER_CLAMP, PF_HORIZON_MOMENTS, 0, out), PF_ERR_ARG);
        hm[W * H - 1] = keep;
    }
    PF_CHECK(bad == 0, "%d values written on error", bad);
    PF_CHECK(pf_horizon_channels(PF_HORIZON_MOMENTS, 8, 0) == 24 && pf_horizon_channels(PF_HORIZON_LEGENDRE, 4, 6) == 24 &&
             pf_horizon_channels(PF_HORIZON_ANGLES, 0, 0) == 0 && pf_horizon_channels(5, 4, 0) == 0, "channels");
#undef FILL
#undef UNTOUCHED
#undef EXPECT
}

/* Exact-size buffers between guard pages: the builders stay inside them (odd sizes, both borders,
   every kind). */
static void test_horizon_guarded_buffers(void)
{
    static const int sz[4][2] = { { 1, 1 }, { 1, 7 }, { 5, 3 }, { 13, 9 } };
    int s, kind, b, ran = 0;
    for (s = 0; s < 4; ++s)
        for (kind = 0; kind < 3; ++kind)
            for (b = 0; b < 2; ++b) {
                int w = sz[s][0], h = sz[s][1], n = 8, k = kind == PF_HORIZON_LEGENDRE ? 5 : 0;
                int c = pf_horizon_channels(kind, n, k);
                size_t hb = (size_t)w * h * sizeof(pf_real), mb = (size_t)w * h * c * sizeof(pf_real);
                size_t pb = (size_t)pf_mip_texel_count(w, h) * c * sizeof(pf_real);
                pf_real *hm = (pf_real *)pf_test_guarded_alloc(hb), *m = (pf_real *)pf_test_guarded_alloc(mb);
                pf_real *p = (pf_real *)pf_test_guarded_alloc(pb);
                int i;
                if (!hm || !m || !p) {
                    pf_test_note("guarded mappings unavailable: skipped");
                    pf_test_guarded_free(hm, hb);
                    pf_test_guarded_free(m, mb);
                    pf_test_guarded_free(p, pb);
                    return;
                }
                for (i = 0; i < w * h; ++i) hm[i] = (pf_real)sin(0.7 * i);
                PF_CHECK(pf_horizon_map(hm, w, h, PF_R(1.0), n, 40, b, kind, k, m) == PF_OK, "map");
                PF_CHECK(pf_horizon_pyramid(hm, w, h, PF_R(1.0), n, 40, b, kind, k, p) == PF_OK, "pyramid");
                for (i = 0; i < w * h * c; ++i) PF_CHECK(pf_test_finite(m[i]) && m[i] == p[i], "texel %d", i);
                pf_test_guarded_free(hm, hb);
                pf_test_guarded_free(m, mb);
                pf_test_guarded_free(p, pb);
                ++ran;
            }
    pf_test_note("%d guarded runs", ran);
}

/* ---------------------------------------------------------------- edge (also under -ffast-math) */
static void edge_horizon_evaluators_finite(void)
{
    static const pf_real v[] = { PF_R(0), PF_R(1e-30), PF_R(-1e-30), PF_R(0.5), PF_R(-0.5), PF_R(1), PF_R(-1), PF_R(1.5),
                                 PF_R(-1.5), PF_R(3.2), PF_R(1e10), PF_R(-1e10), PF_R(1e30) };
    const int nv = (int)(sizeof v / sizeof v[0]);
    int a, b, c, bad = 0;
    for (a = 0; a < nv; ++a)
        for (b = 0; b < nv; ++b)
            for (c = 0; c < nv; ++c) {
                pf_hdf_moments m = pf_hdf_moments_make(v[a], v[b], v[c]);
                pf_vec3 w = pf_vec3_make(v[a], v[b], v[c]);
                pf_real r[7];
                int q;
                pf_hdf_legendre L = pf_hdf_legendre_make(v[a], 0, 0, v[b], 0, 0, 0, 0);
                r[0] = pf_horizon_visibility_gauss(m, v[c]);
                r[1] = pf_horizon_visibility_ramp(m, v[c]);
                r[2] = pf_horizon_visibility_legendre(L, 8, pf_clamp(v[c], PF_R(-1.0), PF_R(1.0)));
                r[3] = pf_horizon_bidir_tan(v[a], v[b], v[c]);
                r[4] = pf_horizon_bidir_ashikhmin(v[a], v[b], v[c], PF_R(0.3));
                r[5] = pf_horizon_visible_area(w, pf_hdf_moments_make(PF_R(0.2), PF_R(0.1), v[c]), v[a], v[b]);
                r[6] = pf_horizon_masking(w, pf_hdf_moments_make(PF_R(0.2), PF_R(0.1), PF_R(0.01)),
                                          pf_slope_stats_make(PF_R(0.1), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0)));
                for (q = 0; q < 7; ++q) bad += !pf_test_bits_finite(r[q]) || r[q] < PF_R(0.0) || r[q] > PF_R(2.0);
                /* the lod fade: any lod and bounds (NaN, inf, negative), any direction (below
                   the mean plane included) */
                {
                    pf_real k = pf_horizon_lod_weight(v[a], v[b], v[c]);
                    pf_real g = pf_horizon_masking_lod(w, pf_hdf_moments_make(PF_R(0.2), PF_R(0.1), PF_R(0.01)),
                                                       pf_slope_stats_make(PF_R(0.1), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0)),
                                                       v[b], PF_R(2.0), PF_R(6.0));
                    bad += !pf_test_bits_finite(k) || k < PF_R(0.0) || k > PF_R(1.0);
                    bad += !pf_test_bits_finite(g) || g < PF_R(0.0) || g > PF_R(1.0);
                }
                /* the diffuse and the conditional visibility: any direction and slope */
                {
                    pf_slope_stats st = pf_slope_stats_make(PF_R(0.1), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0));
                    pf_hdf_moments hm = pf_hdf_moments_make(PF_R(0.2), PF_R(0.1), v[c]);
                    pf_gg_grid gr = pf_gg_grid_make(pf_vec3_normalize(pf_vec3_make(PF_R(0.3), PF_R(0.1), PF_R(0.9))), st, PF_GG_MATCHED, 3);
                    pf_real q1 = pf_horizon_visibility_given_slope(w, hm, st, v[a], v[b]);
                    pf_vec3 wn = pf_vec3_normalize(w); /* the light: a unit direction, any (below included) */
                    pf_real q2 = pf_horizon_diffuse_directional(gr, wn, hm, hm);
                    pf_real q3 = pf_horizon_diffuse_lod(gr, wn, hm, hm, v[b], PF_R(2.0), PF_R(6.0));
                    bad += !pf_test_bits_finite(q1) || q1 < PF_R(0.0) || q1 > PF_R(1.0);
                    bad += !pf_test_bits_finite(q2) || q2 < PF_R(0.0) || q2 > PF_R(1.0);
                    bad += !pf_test_bits_finite(q3) || q3 < PF_R(0.0) || q3 > PF_R(1.0);
                }
                /* the specular: any unit view (the functions take unit directions; above, on
                   or below the macrosurface), unit light, any moments and lod */
                {
                    pf_slope_stats st = pf_slope_stats_make(v[a] > PF_R(2.0) ? PF_R(2.0) : v[a], PF_R(0.0), PF_R(0.11), PF_R(0.11), PF_R(0.0));
                    pf_hdf_moments hm = pf_hdf_moments_make(PF_R(0.2), PF_R(0.1), v[c]);
                    pf_vec3 wl = pf_vec3_normalize(pf_vec3_make(PF_R(-0.3), PF_R(0.2), PF_R(0.9)));
                    /* the lobe sum of pf_vmf.h takes unit directions (its half vector is normalized) */
                    pf_vec3 wu = pf_vec3_normalize(w);
                    pf_vmf_sum sm = pf_vmf_sum_add(pf_vmf_sum_zero(), pf_vmf_lobe_make(PF_R(1.0), PF_R(0.1), PF_R(0.0), PF_R(0.99)), wu, wl,
                                                   PF_R(0.01));
                    pf_real s1 = pf_horizon_leadr_specular(wu, wl, st, PF_R(0.01), hm, hm, PF_R(1.0));
                    pf_real s2 = pf_horizon_leadr_specular_lod(wu, wl, st, PF_R(0.01), hm, hm, PF_R(0.5), v[b], PF_R(2.0), PF_R(6.0));
                    pf_real s3 = pf_horizon_vmf_specular_lod(sm, wu, wl, st, PF_R(0.01), hm, hm, PF_R(1.0), v[b], PF_R(2.0), PF_R(6.0));
                    pf_real s4 = pf_horizon_specular_visibility(wu, wl, hm, hm, st, PF_R(0.01));
#ifdef __FAST_MATH__
                    /* -ffinite-math-only: moments or lods of 1e10 and more overflow the products
                       (an infinity is outside fast-math's contract): fast-math checks the
                       specular at moderate inputs */
                    if (PF_FABS(v[a]) > PF_R(1e3) || PF_FABS(v[b]) > PF_R(1e3) || PF_FABS(v[c]) > PF_R(1e3))
                        s1 = s2 = s3 = s4 = PF_R(0.0);
#endif
                    bad += !pf_test_bits_finite(s1) || s1 < PF_R(0.0);
                    bad += !pf_test_bits_finite(s2) || s2 < PF_R(0.0);
                    bad += !pf_test_bits_finite(s3) || s3 < PF_R(0.0);
                    bad += !pf_test_bits_finite(s4) || s4 < PF_R(0.0) || s4 > PF_R(1.0);
                }
                bad += !pf_test_bits_finite(pf_horizon_legendre_coeff(a % 8, pf_clamp(v[b], PF_R(-1.0), PF_R(1.0))));
                bad += !pf_test_bits_finite(pf_horizon_elevation(w));
                bad += pf_horizon_azimuth_of(w, 16).i0 < 0 || pf_horizon_azimuth_of(w, 16).i0 > 15;
            }
    PF_CHECK(bad == 0, "%d non-finite or out-of-range results", bad);
}

/* The skewed HDF of pf_horizon_masking at its degenerate inputs: E[T] <= 0 (g = 1), E[T]
   tiny and positive, rho -> 1 and beyond (Cov(S, T)^2 >= Var(T) Var(S): g = 0), sigma_T -> 0
   (the step) and slightly negative variances, Var(S) = 0 and huge: finite, in [0, 1]. With no
   slope-horizon covariance and a zero mean slope the area ratio is the Gram-Charlier CDF
   itself, clamped: non-decreasing in the view's elevation, 0 in the far left tail where the
   unclamped series is negative (g = 1: z < -1.9), in [0, 1]. */
static void edge_horizon_masking_skew(void)
{
    static const pf_real mts[] = { PF_R(-0.4), PF_R(-1e-30), PF_R(0.0), PF_R(1e-30), PF_R(1e-6), PF_R(0.05), PF_R(0.3), PF_R(1.2) };
    static const pf_real sds[] = { PF_R(0.0), PF_R(1e-12), PF_R(1e-7), PF_R(1e-3), PF_R(0.05), PF_R(0.3), PF_R(1.0) };
    static const pf_real rhos[] = { PF_R(-1.5), PF_R(-1.0), PF_R(-0.999999), PF_R(0.0), PF_R(0.5), PF_R(0.999999), PF_R(1.0), PF_R(1.5) };
    static const pf_real vss[] = { PF_R(0.0), PF_R(1e-20), PF_R(0.1), PF_R(1e20) };
    int a, b, c, d, t, bad = 0, mono = 0, tail = 0, n = 0;
    for (a = 0; a < 8; ++a)
        for (b = 0; b < 7; ++b)
            for (c = 0; c < 8; ++c)
                for (d = 0; d < 4; ++d)
                    for (t = 0; t <= 16; ++t) {
                        pf_real th = PF_R(t) * PF_R(0.09), mt = mts[a], sd = sds[b], vs = vss[d];
                        pf_vec3 w = pf_vec3_make(PF_SIN(th) * PF_R(0.6), PF_SIN(th) * PF_R(0.8), PF_COS(th));
                        /* E[S] along w's azimuth 0.1, Cov(S, T) = rho sigma_S sigma_T */
                        pf_slope_stats s = pf_slope_stats_make(PF_R(0.06), PF_R(0.08), vs, vs, PF_R(0.0));
                        pf_real ms = rhos[c] * PF_SQRT(vs) * sd + mt * PF_R(0.1);
                        pf_real m2 = b == 1 ? mt * mt * (PF_R(1.0) - PF_R(1e-6)) : mt * mt + sd * sd; /* b = 1: a negative variance */
                        pf_real g = pf_horizon_masking(w, pf_hdf_moments_make(mt, m2, ms), s);
                        pf_real k = pf_horizon_masking_lod(w, pf_hdf_moments_make(mt, m2, ms), s, PF_R(3.0), PF_R(2.0), PF_R(6.0));
                        bad += !(g >= PF_R(0.0) && g <= PF_R(1.0)) + !(k >= PF_R(0.0) && k <= PF_R(1.0));
                        ++n;
                    }
    PF_CHECK(bad == 0, "%d of %d outside [0, 1] or NaN", bad, 2 * n);
    /* the clamped CDF: E[T] = 0.6, sigma_T = 0.2 (g = 1/3), no covariance, mean slope 0; the
       elevations 1e-4 to 1.5 rad (z from -3 to 4.5: through the negative series, z < -2.8) */
    {
        pf_hdf_moments m = pf_hdf_moments_make(PF_R(0.6), PF_R(0.36) + PF_R(0.04), PF_R(0.0));
        pf_slope_stats s = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0));
        pf_real prev = PF_R(-1.0);
        for (t = 0; t <= 2000; ++t) {
            pf_real e = PF_R(1e-4) + PF_R(t) * PF_R(0.00075), r = pf_horizon_masking(pf_vec3_make(PF_COS(e), PF_R(0.0), PF_SIN(e)), m, s);
            pf_real v = r / pf_beckmann_g1(pf_vec3_make(PF_COS(e), PF_R(0.0), PF_SIN(e)), s);
            mono += v < prev - PF_R(1e-6);
            prev = v;
        }
    }
    /* far left tail: E[T] = 0.061, sigma_T = 0.02 (g = 0.33), the view at z = -3, where the series
       is -6e-4 (the Gaussian's Phi 1.3e-3): 0 */
    {
        pf_hdf_moments m = pf_hdf_moments_make(PF_R(0.061), PF_R(0.061) * PF_R(0.061) + PF_R(0.0004), PF_R(0.0));
        pf_slope_stats s = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0));
        pf_real e = PF_R(0.001);
        tail += pf_horizon_masking(pf_vec3_make(PF_COS(e), PF_R(0.0), PF_SIN(e)), m, s) != PF_R(0.0);
    }
    PF_CHECK(mono == 0, "%d decreases of the area ratio with the elevation", mono);
    PF_CHECK(tail == 0, "the negative tail of the series not clamped to 0");
}

/* Directions under horizons that hide them give exactly 0, in every build: the horizon
   specular's Phi at its lower clamp (z = -24) must come from exp underflowing to 0, not from
   1/(1 + exp(1013)) = 1/inf (clang -O2 -ffast-math divided the two directions' lanes by a
   reciprocal estimate and a Newton step, inf * 0 = NaN: 753 of these 768 results). Views from
   grazing (w.z = 1e-3) to steep, every azimuth; horizons at 1.5 rad with no spread (above
   every direction), at -1.5 rad (open sky) or one of each. */
static void edge_horizon_specular_occluded(void)
{
    pf_real bv = PF_R(0.01), low = PF_R(-1.5), high = PF_R(1.5);
    pf_slope_stats s = pf_slope_stats_make(PF_R(0.05), PF_R(-0.03), PF_R(0.06) + bv, PF_R(0.04) + bv, PF_R(0.01));
    pf_hdf_moments ml = pf_hdf_moments_make(low, low * low, PF_R(0.0)), mh = pf_hdf_moments_make(high, high * high, PF_R(0.0));
    pf_vec3 wi = pf_vec3_normalize(pf_vec3_make(PF_R(-0.3), PF_R(0.2), PF_R(0.9)));
    int a, e, bad = 0, open_bad = 0;
    for (a = 0; a < 16; ++a)
        for (e = 0; e < 8; ++e) {
            double phi = 2.0 * 3.14159265358979 * a / 16.0, cz = e == 0 ? 1e-3 : 0.13 * e;
            double sz = sqrt(1.0 - cz * cz);
            pf_vec3 wo = pf_vec3_make((pf_real)(sz * cos(phi)), (pf_real)(sz * sin(phi)), (pf_real)cz);
            pf_vmf_sum sum = pf_vmf_sum_add(pf_vmf_sum_zero(), pf_vmf_lobe_make(PF_R(1.0), PF_R(0.1), PF_R(0.0), PF_R(0.99)), wo,
                                            wi, bv);
            /* open sky: the visibility 1 less the logistic's rounding; the specular as is */
            pf_real vo = pf_horizon_specular_visibility(wo, wi, ml, ml, s, bv);
            pf_real lo = pf_horizon_leadr_specular(wo, wi, s, bv, ml, ml, PF_R(1.0));
            pf_real so = pf_horizon_vmf_specular(sum, wo, wi, s, bv, ml, ml, PF_R(1.0));
            pf_real v[6];
            int q;
            v[0] = pf_horizon_specular_visibility(wo, wi, mh, mh, s, bv);
            v[1] = pf_horizon_specular_visibility(wo, wi, ml, mh, s, bv);
            v[2] = pf_horizon_specular_visibility(wi, wo, mh, ml, s, bv);
            v[3] = pf_horizon_specular_visibility(wo, wi, mh, ml, s, bv);
            v[4] = pf_horizon_leadr_specular(wo, wi, s, bv, mh, mh, PF_R(1.0));
            v[5] = pf_horizon_vmf_specular(sum, wo, wi, s, bv, mh, mh, PF_R(1.0));
            for (q = 0; q < 6; ++q) bad += !pf_test_bits_finite(v[q]) || v[q] != PF_R(0.0);
            open_bad += !pf_test_bits_finite(vo) || !(vo > PF_R(0.99)) || vo > PF_R(1.0) || !pf_test_bits_finite(lo) ||
                        !pf_test_bits_finite(so) || !(lo >= PF_R(0.0)) || !(so >= PF_R(0.0));
        }
    PF_CHECK(bad == 0, "%d of 768 occluded results not exactly 0", bad);
    PF_CHECK(open_bad == 0, "%d of 128 open-sky results outside their range (visibility (0.99, 1])", open_bad);
}

/* zero and underflowing directions give the documented values: elevation 0 for w = 0 (PF_ATAN2
   at (0, 0) is 0: pf_core.h), the angle of the direction for components whose squares
   underflow (pf_horizon_elevation scales w first), [-pi/2, pi/2] always; hence a zero w is at
   the tangent plane for the conditional visibility (under a horizon at 0.1 +- 0.01: Phi(-10),
   not 1) and sees no area (pf_horizon_visible_area: E[a] = 0 gives 0) */
static void edge_horizon_zero_directions(void)
{
    const pf_real z = PF_R(0.0), t = PF_R(1e-30), q = PF_PI * PF_R(0.25);
    pf_hdf_moments m = pf_hdf_moments_make(PF_R(0.1), PF_R(0.0101), PF_R(0.0));
    pf_slope_stats st = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0));
    static const pf_real v[] = { PF_R(0), PF_R(-0.0), PF_R(1e-30), PF_R(-1e-30), PF_R(1e-20), PF_R(0.5), PF_R(-1), PF_R(1e30) };
    const int nv = (int)(sizeof v / sizeof v[0]);
    int a, b, c, bad = 0;
    PF_CHECK(pf_horizon_elevation(pf_vec3_make(z, z, z)) == z && pf_horizon_elevation(pf_vec3_make(-z, -z, -z)) == z,
             "elevation of 0: %g", (double)pf_horizon_elevation(pf_vec3_make(z, z, z)));
    PF_CHECK(pf_horizon_elevation(pf_vec3_make(t, z, z)) == z, "elevation of (1e-30, 0, 0): %g",
             (double)pf_horizon_elevation(pf_vec3_make(t, z, z)));
    PF_CHECK(fabsl((long double)pf_horizon_elevation(pf_vec3_make(t, z, t)) - (long double)q) <= 4.0L * (long double)PF_REAL_EPSILON &&
             fabsl((long double)pf_horizon_elevation(pf_vec3_make(z, t, -t)) + (long double)q) <= 4.0L * (long double)PF_REAL_EPSILON,
             "elevation of (1e-30, 0, +-1e-30): %.9g %.9g", (double)pf_horizon_elevation(pf_vec3_make(t, z, t)),
             (double)pf_horizon_elevation(pf_vec3_make(z, t, -t)));
    for (a = 0; a < nv; ++a)
        for (b = 0; b < nv; ++b)
            for (c = 0; c < nv; ++c) {
                pf_real e = pf_horizon_elevation(pf_vec3_make(v[a], v[b], v[c]));
                bad += !(e >= -PF_R(0.5) * PF_PI && e <= PF_R(0.5) * PF_PI);
            }
    PF_CHECK(bad == 0, "%d elevations outside [-pi/2, pi/2]", bad);
    PF_CHECK(pf_horizon_visibility_given_slope(pf_vec3_make(z, z, z), m, st, z, z) <= PF_R(1e-6) &&
             pf_horizon_visibility_given_slope(pf_vec3_make(t, z, z), m, st, z, z) <= PF_R(1e-6),
             "visibility given slope at w = 0: %g, at (1e-30, 0, 0): %g",
             (double)pf_horizon_visibility_given_slope(pf_vec3_make(z, z, z), m, st, z, z),
             (double)pf_horizon_visibility_given_slope(pf_vec3_make(t, z, z), m, st, z, z));
    PF_CHECK(pf_horizon_visible_area(pf_vec3_make(z, z, z), m, z, z) == z, "visible area at w = 0: %g",
             (double)pf_horizon_visible_area(pf_vec3_make(z, z, z), m, z, z));
    PF_CHECK(pf_horizon_azimuth_of(pf_vec3_make(z, z, z), 16).i0 == 0 && pf_horizon_azimuth_of(pf_vec3_make(z, z, z), 16).f == z,
             "azimuth of w = 0");
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_horizon_angles_vs_brute_march);
    PF_TEST_RUN(test_horizon_angles_vs_continuous_surface);
    PF_TEST_RUN(test_horizon_facet_plane);
    PF_TEST_RUN(test_horizon_pyramid_is_footprint_mean);
    PF_TEST_RUN(test_horizon_eq26_gauss_counting);
    PF_TEST_RUN(test_horizon_legendre_vs_quadrature);
    PF_TEST_RUN(test_horizon_eq26_legendre_counting);
    PF_TEST_RUN(test_horizon_visibility_formulas);
    PF_TEST_RUN(test_horizon_bidir_limits);
    PF_TEST_RUN(test_horizon_visible_area_quadrature);
    PF_TEST_RUN(test_horizon_lod_weight);
    PF_TEST_RUN(test_horizon_masking_lod);
    PF_TEST_RUN(test_horizon_masking_skewed_brute_force);
    PF_TEST_RUN(test_horizon_visibility_given_slope);
    PF_TEST_RUN(test_horizon_diffuse);
    PF_TEST_RUN(test_horizon_spec_cond_vis_matches);
    PF_TEST_RUN(test_horizon_specular_quadrature);
    PF_TEST_RUN(test_horizon_specular_limits);
    PF_TEST_RUN(test_horizon_specular_brute_force);
    PF_TEST_RUN(test_horizon_specular_grazing_brute_force);
    PF_TEST_RUN(test_horizon_specular_storage_16bit);
    PF_TEST_RUN(test_horizon_azimuth_of);
    PF_TEST_RUN(test_horizon_legendre_struct);
    PF_TEST_RUN(test_horizon_bad_input_writes_nothing);
    PF_TEST_RUN(test_horizon_guarded_buffers);
    PF_TEST_RUN(edge_horizon_evaluators_finite);
    PF_TEST_RUN(edge_horizon_zero_directions);
    PF_TEST_RUN(edge_horizon_specular_occluded);
    PF_TEST_RUN(edge_horizon_masking_skew);
    return PF_TEST_END();
}

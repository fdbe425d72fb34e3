/* test_smith.c - tests of include/pf_smith.h against the quadrature of the definitions.

   Truth is never the closed form: Lambda is integrated from its definition (Dupuy et al. 2013
   eqs. 1, 6, 10 and sec. 4.3), in 1D over the slope density along the view azimuth and in 2D
   over the whole slope plane or the hemisphere of micro-normals, with tests/reference/pf_oracle.h in
   long double. The same bodies run in float, double, C++ and under sanitizers; edge_* tests
   also run under -ffast-math. */
#include <string.h>
#include "pf_smith.h"
#include "pf_oracle.h"
#include "pf_test.h"

static const long double sqrt2l = 1.41421356237309504880168872420969808L;

/* ------------------------------------------------------------------ references */

/* Centered standard Gaussian: Lambda(nu) = (1/zc) integral_{zc}^inf (z - zc) phi(z) dz with
   zc = nu sqrt 2 (definition (1) of pf_smith.h with mu = 0, sigma = 1/sqrt 2 per unit nu).
   Written in u = z - zc, phi(zc + u) = phi(zc) exp(-u zc - u^2/2), so the far tail keeps its
   relative accuracy. */
static long double tail_integrand(long double u, void *ctx)
{
    long double zc = *(const long double *)ctx;
    return u * expl(-u * zc - 0.5L * u * u);
}

static long double lambda_ref(long double nu)
{
    long double zc = nu * sqrt2l;
    pf_oracle_result r = pf_oracle_integrate(tail_integrand, &zc, 0.0L, HUGE_VALL, 0.0L, 1e-18L,
                                             PF_ORACLE_MAX_INTERVALS);
    return pf_oracle_normal_pdf(zc) * r.value / zc;
}

/* 1D noncentered: Lambda = integral_c^inf (x - c) N(x; mu, sigma^2) dx / (c - mu), by
   quadrature (tests/reference/pf_oracle.h). */
static long double lambda_ref_1d(long double c, long double mu, long double sigma)
{
    return pf_oracle_lambda_1d(c, mu, sigma);
}

/* A random direction and noncentered, anisotropic, correlated slope statistics. */
typedef struct config {
    long double wx, wy, wz;
    long double mx, my, vx, vy, cxy;
} config;

static config random_config(pf_test_rng *rng)
{
    config k;
    long double theta = (long double)pf_test_uniform(rng, 0.02, 1.50);
    long double phi = (long double)pf_test_uniform(rng, -3.14159, 3.14159);
    long double sx = (long double)pf_test_log_uniform(rng, 0.05, 1.5);
    long double sy = (long double)pf_test_log_uniform(rng, 0.05, 1.5);
    long double rho = (long double)pf_test_uniform(rng, -0.95, 0.95);
    k.wx = sinl(theta) * cosl(phi);
    k.wy = sinl(theta) * sinl(phi);
    k.wz = cosl(theta);
    k.mx = (long double)pf_test_uniform(rng, -1.0, 1.0);
    k.my = (long double)pf_test_uniform(rng, -1.0, 1.0);
    k.vx = sx * sx;
    k.vy = sy * sy;
    k.cxy = rho * sx * sy;
    return k;
}

/* The config rounded to pf_real, and back, so the reference sees the library's inputs. */
static config round_config(config k)
{
    k.wx = (long double)(pf_real)k.wx;
    k.wy = (long double)(pf_real)k.wy;
    k.wz = (long double)(pf_real)k.wz;
    k.mx = (long double)(pf_real)k.mx;
    k.my = (long double)(pf_real)k.my;
    k.vx = (long double)(pf_real)k.vx;
    k.vy = (long double)(pf_real)k.vy;
    k.cxy = (long double)(pf_real)k.cxy;
    return k;
}

static pf_vec3 config_w(config k) { return pf_vec3_make((pf_real)k.wx, (pf_real)k.wy, (pf_real)k.wz); }

static pf_slope_stats config_stats(config k)
{
    return pf_slope_stats_make((pf_real)k.mx, (pf_real)k.my, (pf_real)k.vx, (pf_real)k.vy, (pf_real)k.cxy);
}

/* Slope mean and deviation along the azimuth by trigonometry (eqs. 14-15), the independent
   path to pf_smith_nu's trig-free one. */
static void config_along(config k, long double *c, long double *mu, long double *sigma)
{
    long double phi = atan2l(k.wy, k.wx);
    long double theta = acosl(k.wz / sqrtl(k.wx * k.wx + k.wy * k.wy + k.wz * k.wz));
    long double cp = cosl(phi), sp = sinl(phi);
    *c = cosl(theta) / sinl(theta);
    *mu = cp * k.mx + sp * k.my;
    *sigma = sqrtl(cp * cp * k.vx + sp * sp * k.vy + 2.0L * cp * sp * k.cxy);
}

/* 2D: 1 + Lambda = integral over slopes of max(0, wz - wx x - wy y) P22(x, y)
   / (wz - wx mx - wy my)   (Dupuy et al. 2013 eqs. 1, 6, 10 with D dm = P22 / (m.g) ds). */
static long double p22(const config *k, long double x, long double y)
{
    return pf_oracle_normal2_pdf(x - k->mx, y - k->my, k->vx, k->vy, k->cxy);
}

static long double slope_plane_integrand(long double x, long double y, void *ctx)
{
    const config *k = (const config *)ctx;
    long double proj = k->wz - k->wx * x - k->wy * y;
    return proj > 0.0L ? proj * p22(k, x, y) : 0.0L;
}

/* Inner (y) breakpoints: the kink line and the conditional mean of y given x. */
static int slope_plane_ypoints(long double x, long double *pts, int max_points, void *ctx)
{
    const config *k = (const config *)ctx;
    int n = 0;
    if (max_points < 2) return 0;
    if (k->wy != 0.0L) pts[n++] = (k->wz - k->wx * x) / k->wy;
    pts[n++] = k->my + k->cxy / k->vx * (x - k->mx);
    return n;
}

/* Integral of f over the whole slope plane, split at x = x0 (outer) and at the points
   ypoints(x) (inner: the kink line, the peak). Returns the oracle's result. */
static pf_oracle_result slope_plane_integral(pf_oracle_fn2 f, void *ctx, long double x0,
                                             pf_oracle_points_fn ypoints, long double epsrel, int max_intervals)
{
    pf_oracle_2d pb = pf_oracle_2d_make(f, ctx, -HUGE_VALL, HUGE_VALL, -HUGE_VALL, HUGE_VALL);
    long double xp[1];
    xp[0] = x0;
    pb.xpoints = xp;
    pb.nxpoints = 1;
    pb.ypoints = ypoints;
    pb.epsrel = epsrel;
    pb.max_intervals = max_intervals;
    return pf_oracle_integrate_2d(&pb);
}

static long double one_plus_lambda_2d(config k, long double *err)
{
    pf_oracle_result r = slope_plane_integral(slope_plane_integrand, &k, k.mx, slope_plane_ypoints, 1e-14L, 600);
    *err = r.converged ? r.error : -1.0L;
    return r.value / (k.wz - k.wx * k.mx - k.wy * k.my);
}

/* ------------------------------------------------------------------ Beckmann, centered */

/* Dense grid of nu: log-spaced from 1e-6 to 0.5, linear to the underflow point. */
static long double grid_nu(int i, int n_log, int n_lin, long double top)
{
    if (i < n_log) return 1e-6L * powl(0.5L / 1e-6L, (long double)i / (long double)n_log);
    return 0.5L + (top - 0.5L) * (long double)(i - n_log) / (long double)(n_lin - 1);
}

static void test_lambda_beckmann_quadrature(void)
{
    /* float: Lambda is a normal float up to nu ~ 9.2; double: to ~26.5 */
#ifdef PF_DOUBLE
    const long double top = 26.0L;
    const long double bound_ulp = 8.0L;
#else
    const long double top = 9.1L;
    const long double bound_ulp = 8.0L;
#endif
    const int n_log = 600, n_lin = 3000;
    pf_test_max m = pf_test_max_init();
    int i;
    for (i = 0; i < n_log + n_lin; i++) {
        pf_real nu = (pf_real)grid_nu(i, n_log, n_lin, top);
        long double ref = lambda_ref((long double)nu);
        pf_test_max_update(&m, pf_test_ulp_error(pf_lambda_beckmann(nu), ref), (long double)nu);
    }
    pf_test_note("max %.2f ulp at nu=%.4g (%d points, nu in [1e-6, %.1f])", (double)m.err, (double)m.at,
                 n_log + n_lin, (double)top);
    PF_CHECK(m.err <= bound_ulp, "Lambda max error %.3g ulp at nu=%.6g", (double)m.err, (double)m.at);
}

static void test_g1_beckmann_quadrature(void)
{
#ifdef PF_DOUBLE
    const long double bound = 8.0L * PF_TEST_EPS;
#else
    const long double bound = 1e-6L; /* the float target; measured value in the note */
#endif
    const int n_log = 600, n_lin = 2000;
    pf_test_max m = pf_test_max_init();
    int i;
    for (i = 0; i < n_log + n_lin; i++) {
        pf_real nu = (pf_real)grid_nu(i, n_log, n_lin, 12.0L);
        long double ref = 1.0L / (1.0L + lambda_ref((long double)nu));
        pf_test_max_update(&m, pf_test_rel_error((long double)pf_g1_beckmann(nu), ref), (long double)nu);
    }
    pf_test_note("G1 max rel %.3g at nu=%.4g", (double)m.err, (double)m.at);
    PF_CHECK(m.err <= bound, "G1 max rel error %.3g at nu=%.6g", (double)m.err, (double)m.at);
}

/* Walter et al. 2007 (the baseline) and our fast tier on the same dense grid: the fast tier
   must be >= 10x more accurate; the Walter tier's error is the published form's, 3.13e-3. */
static void test_g1_fast_and_walter(void)
{
    const int n = 8000;
    pf_test_max mf = pf_test_max_init(), mw = pf_test_max_init(), mlf = pf_test_max_init();
    int i;
    for (i = 1; i <= n; i++) {
        pf_real nu = (pf_real)(4.0L * (long double)i / (long double)n);
        long double lam = lambda_ref((long double)nu);
        long double ref = 1.0L / (1.0L + lam);
        pf_test_max_update(&mf, pf_test_rel_error((long double)pf_g1_beckmann_fast(nu), ref), (long double)nu);
        pf_test_max_update(&mw, pf_test_rel_error((long double)pf_g1_beckmann_walter(nu), ref), (long double)nu);
        /* Lambda of the fast tier, error in G1 terms |dLambda|/(1 + Lambda) */
        pf_test_max_update(&mlf, fabsl((long double)pf_lambda_beckmann_fast(nu) - lam) / (1.0L + lam),
                           (long double)nu);
    }
    pf_test_note("fast %.3g at nu=%.3f; Walter %.3g at nu=%.3f; ratio %.1fx; fast Lambda %.3g", (double)mf.err,
                 (double)mf.at, (double)mw.err, (double)mw.at, (double)(mw.err / mf.err), (double)mlf.err);
    PF_CHECK(mf.err <= 1.1e-4L, "fast tier G1 max rel %.3g at %.5g", (double)mf.err, (double)mf.at);
    PF_CHECK(mlf.err <= 1.1e-4L, "fast tier Lambda error %.3g at %.5g", (double)mlf.err, (double)mlf.at);
    PF_CHECK(mw.err >= 3.0e-3L && mw.err <= 3.2e-3L, "Walter G1 max rel %.4g at %.5g (expected 3.13e-3)",
             (double)mw.err, (double)mw.at);
    PF_CHECK(mw.err >= 10.0L * mf.err, "fast tier only %.1fx better than Walter", (double)(mw.err / mf.err));
}

/* pf_lambda_beckmann_fast (issue 17): RELATIVE error against the quadrature of Smith's
   definition wherever Lambda is a normal number, nu from 1e-6 to the underflow, against the
   bound its comment states: float 2e-6 + 6e-8 nu^2 (the rounding of nu*nu inside exp),
   double 1.7e-6. Walter's form is 100% off past 1.6 (it returns 0); recorded alongside. */
static void test_lambda_fast_relative(void)
{
    pf_test_max m = pf_test_max_init();
    long double worst_excess = -1.0L, at_excess = 0, walter_tail = 0;
    int i;
    for (i = 0; i <= 6000; i++) {
        pf_real nu = i < 1000 ? (pf_real)powl(10.0L, -6.0L + 6.0L * (long double)i / 1000.0L)
                              : (pf_real)(1.0L + 9.0L * (long double)(i - 1000) / 5000.0L);
        long double ref = lambda_ref((long double)nu), e, bound;
        if (!(ref >= (long double)PF_REAL_MIN)) continue;
        e = pf_test_rel_error((long double)pf_lambda_beckmann_fast(nu), ref);
#ifdef PF_DOUBLE
        bound = 1.7e-6L;
#else
        bound = 2e-6L + 6e-8L * (long double)nu * (long double)nu;
#endif
        pf_test_max_update(&m, e, (long double)nu);
        if (e - bound > worst_excess) { worst_excess = e - bound; at_excess = (long double)nu; }
        if ((long double)nu > 1.7L && (long double)nu < 1.8L)
            walter_tail = pf_test_rel_error((long double)pf_lambda_beckmann_walter(nu), ref);
    }
    pf_test_note("max rel %.3g at nu=%.4g (Walter at nu = 1.8: %.3g)", (double)m.err, (double)m.at, (double)walter_tail);
    PF_CHECK(worst_excess <= 0.0L, "fast Lambda exceeds its bound by %.3Lg at nu=%.6Lg", worst_excess, at_excess);
}

/* The published Walter form goes negative on [1.5482, 1.6); ours must not. */
static void test_walter_clamped(void)
{
    int i, bad = 0;
    for (i = 0; i <= 1000; i++) {
        pf_real nu = (pf_real)(1.54L + 0.07L * (long double)i / 1000.0L);
        long double n = (long double)nu;
        long double published = (1.0L - 1.259L * n + 0.396L * n * n) / (3.535L * n + 2.181L * n * n);
        if (nu >= (pf_real)1.6) published = 0.0L;
        if (pf_lambda_beckmann_walter(nu) < PF_R(0.0) || pf_g1_beckmann_walter(nu) > PF_R(1.0)) bad++;
        /* elsewhere our tier is the published formula */
        if (published > 0.0L) /* absolute: the numerator cancels near its root */
            PF_CHECK(fabsl((long double)pf_lambda_beckmann_walter(nu) - published) <= 16.0L * PF_TEST_EPS,
                     "Walter tier differs from the published form at nu=%.6g", (double)nu);
    }
    PF_CHECK(bad == 0, "%d points out of range", bad);
}

/* ------------------------------------------------------------------ noncentered */

/* Lambda(pf_smith_nu(w, stats)) against the 1D definition with mu(phi), sigma(phi) from
   trigonometry. The error includes nu's rounding, amplified by d ln Lambda / d ln nu (about
   2 nu^2 + 1) and by the cancellation in nu's numerator, so the bound is stated per unit of
   that condition number. */
static void test_noncentered_1d(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x5eed0001ULL);
    pf_test_max m = pf_test_max_init();
    int i, used = 0;
    for (i = 0; i < 400; i++) {
        config k = round_config(random_config(&rng));
        long double c, mu, sigma, ref, nu_ref, cond, num;
        pf_real lam;
        config_along(k, &c, &mu, &sigma);
        if (c - mu <= 0.0L) continue; /* below the mesosurface: an edge test covers it */
        nu_ref = (c - mu) / (sigma * sqrt2l);
        if (nu_ref > 8.0L) continue;
        ref = lambda_ref_1d(c, mu, sigma);
        lam = pf_lambda_beckmann(pf_smith_nu(config_w(k), config_stats(k)));
        /* nu's numerator w.z - w.x E[x] - w.y E[y] cancels near the mesosurface horizon */
        num = k.wz - k.wx * k.mx - k.wy * k.my;
        cond = (2.0L * nu_ref * nu_ref + 2.0L) * (fabsl(k.wz) + fabsl(k.wx * k.mx) + fabsl(k.wy * k.my)) / num;
        pf_test_max_update(&m, pf_test_rel_error((long double)lam, ref) / (cond * PF_TEST_EPS), nu_ref);
        used++;
    }
    pf_test_note("%d configs; max rel error %.2f eps x (2 nu^2 + 2), at nu=%.3g", used, (double)m.err, (double)m.at);
    PF_CHECK(used > 200, "only %d usable configs", used);
    PF_CHECK(m.err <= 6.0L, "noncentered Lambda error %.3g eps-units at nu=%.4g", (double)m.err, (double)m.at);
}

/* The full 2D slope integral (eqs. 1, 6, 10), random anisotropic correlated noncentered
   configs. Compared on 1 + Lambda (the integral), and on the G1 it gives. */
static void test_noncentered_2d(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x5eed0002ULL);
    pf_test_max m = pf_test_max_init();
    int i, used = 0, failed_quad = 0;
    for (i = 0; i < 40 && used < 12; i++) {
        config k = round_config(random_config(&rng));
        long double err, opl, nu_ref, c, mu, sigma;
        pf_real lam;
        config_along(k, &c, &mu, &sigma);
        if (c - mu <= 0.0L) continue;
        nu_ref = (c - mu) / (sigma * sqrt2l);
        if (nu_ref > 4.0L || nu_ref < 0.05L) continue;
        opl = one_plus_lambda_2d(k, &err);
        if (err < 0.0L) {
            failed_quad++;
            continue;
        }
        lam = pf_lambda_beckmann(pf_smith_nu(config_w(k), config_stats(k)));
        pf_test_max_update(&m, pf_test_rel_error(1.0L + (long double)lam, opl), nu_ref);
        used++;
    }
    pf_test_note("%d configs; max rel error of 1+Lambda %.3g (at nu=%.3g)", used, (double)m.err, (double)m.at);
    PF_CHECK(failed_quad == 0, "%d 2D quadratures did not converge", failed_quad);
    PF_CHECK(used >= 10, "only %d usable configs", used);
    PF_CHECK(m.err <= 64.0L * PF_TEST_EPS + 1e-12L, "1+Lambda vs 2D integral: %.3g", (double)m.err);
}

/* The NDF route: integrate max(0, w.m) D(m) over the hemisphere of micro-normals with
   D(m) = P22(-mx/mz, -my/mz) / mz^4 (eq. 10), divide by the mesosurface projected area
   (w_nbar . w)/(w_nbar . w_g) (eq. 1). Polar coordinates (t, p) of m, dm = sin t dt dp. */
static long double hemi_integrand(long double p, long double t, void *ctx)
{
    const config *k = (const config *)ctx;
    long double st = sinl(t), ct = cosl(t);
    long double mx = st * cosl(p), my = st * sinl(p);
    long double wm = (k->wx * mx + k->wy * my + k->wz * ct);
    if (wm <= 0.0L || ct <= 0.0L) return 0.0L;
    return wm * p22(k, -mx / ct, -my / ct) / (ct * ct * ct * ct) * st;
}

/* Inner (t) breakpoint where w.m changes sign for this azimuth p. */
static int hemi_tpoints(long double p, long double *pts, int max_points, void *ctx)
{
    const config *k = (const config *)ctx;
    long double a = k->wx * cosl(p) + k->wy * sinl(p);
    if (max_points < 1 || a >= 0.0L) return 0;
    pts[0] = atanl(-k->wz / a);
    return 1;
}

static void test_ndf_hemisphere(void)
{
    static const long double cfg[4][8] = {
        /* wx, wy, wz (unnormalized), mx, my, vx, vy, cxy */
        {0.6L, 0.2L, 0.7L, 0.3L, -0.2L, 0.09L, 0.25L, 0.05L},
        {-0.9L, 0.3L, 0.35L, 0.4L, 0.1L, 0.16L, 0.04L, -0.06L},
        {0.1L, -0.8L, 0.5L, 0.0L, 0.5L, 0.36L, 0.36L, 0.3L},
        {0.3L, 0.3L, 0.9L, 0.2L, 0.2L, 0.01L, 0.02L, 0.0L},
    };
    pf_test_max m = pf_test_max_init();
    int i;
    for (i = 0; i < 4; i++) {
        config k;
        long double len, proj, integral;
        pf_oracle_2d pb;
        pf_oracle_result r;
        pf_real lam;
        len = sqrtl(cfg[i][0] * cfg[i][0] + cfg[i][1] * cfg[i][1] + cfg[i][2] * cfg[i][2]);
        k.wx = cfg[i][0] / len;
        k.wy = cfg[i][1] / len;
        k.wz = cfg[i][2] / len;
        k.mx = cfg[i][3];
        k.my = cfg[i][4];
        k.vx = cfg[i][5];
        k.vy = cfg[i][6];
        k.cxy = cfg[i][7];
        k = round_config(k);
        pb = pf_oracle_2d_make(hemi_integrand, &k, -PF_TEST_PI, PF_TEST_PI, 0.0L, PF_TEST_PI / 2.0L);
        pb.ypoints = hemi_tpoints;
        pb.epsrel = 1e-12L;
        pb.max_intervals = 600;
        r = pf_oracle_integrate_2d(&pb);
        PF_CHECK(r.converged, "hemisphere quadrature %d: %s", i, pf_oracle_status_name(r.status));
        /* (n_bar . w)/(n_bar . g) with n_bar ~ (-mx, -my, 1): the normalization cancels */
        proj = k.wz - k.wx * k.mx - k.wy * k.my;
        integral = r.value / proj;
        lam = pf_lambda_beckmann(pf_smith_nu(config_w(k), config_stats(k)));
        pf_test_max_update(&m, pf_test_rel_error(1.0L + (long double)lam, integral), (long double)i);
    }
    pf_test_note("max rel error of 1+Lambda vs hemisphere NDF integral %.3g", (double)m.err);
    PF_CHECK(m.err <= 64.0L * PF_TEST_EPS + 1e-10L, "1+Lambda vs hemisphere integral: %.3g (config %d)", (double)m.err,
             (int)m.at);
}

/* Centered, uncorrelated: pf_smith_nu is the textbook cot t / (sqrt 2 alpha(p)),
   alpha(p)^2 = cos^2 p s_x^2 + sin^2 p s_y^2, and pf_slope_along agrees with trigonometry. */
static void test_centered_reduces_to_textbook(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x5eed0003ULL);
    pf_test_max mnu = pf_test_max_init(), ma = pf_test_max_init();
    int i;
    for (i = 0; i < 2000; i++) {
        config k = random_config(&rng);
        long double c, mu, sigma, nu_ref;
        pf_vec2 along;
        k.mx = k.my = k.cxy = 0.0L;
        k = round_config(k);
        config_along(k, &c, &mu, &sigma);
        nu_ref = c / (sqrt2l * sigma);
        pf_test_max_update(&mnu, pf_test_rel_error((long double)pf_smith_nu(config_w(k), config_stats(k)), nu_ref),
                           nu_ref);
        k = round_config(random_config(&rng));
        config_along(k, &c, &mu, &sigma);
        along = pf_slope_along(config_w(k), config_stats(k));
        pf_test_max_update(&ma, fabsl((long double)along.x - mu) / sqrtl(k.mx * k.mx + k.my * k.my + 1e-30L),
                           (long double)i);
        pf_test_max_update(&ma, pf_test_rel_error((long double)along.y, sigma), (long double)i);
    }
    pf_test_note("nu max rel %.3g; slope_along %.3g", (double)mnu.err, (double)ma.err);
    PF_CHECK(mnu.err <= 8.0L * PF_TEST_EPS, "centered nu vs textbook: %.3g", (double)mnu.err);
    PF_CHECK(ma.err <= 64.0L * PF_TEST_EPS, "pf_slope_along vs trig: %.3g", (double)ma.err);
    /* isotropic helper */
    PF_CHECK(pf_test_rel_error((long double)pf_smith_nu_iso(PF_R(0.6), PF_R(0.3)),
                               0.6L / (sqrt2l * 0.3L * 0.8L)) <= 8.0L * PF_TEST_EPS,
             "pf_smith_nu_iso(0.6, 0.3) = %.9g", (double)pf_smith_nu_iso(PF_R(0.6), PF_R(0.3)));
}

/* ------------------------------------------------------------------ GGX */

/* 1D marginal of GGX slopes along an azimuth: P2(x) = a^2 / (2 (a^2 + x^2)^{3/2}),
   a^2 = cos^2 p ax^2 + sin^2 p ay^2 (elliptical distribution). Lambda = (1/c) int_c (x - c) P2. */
static long double ggx_tail(long double u, void *ctx)
{
    const long double *ca = (const long double *)ctx;
    long double x = ca[0] + u, a2 = ca[1] * ca[1];
    return u * a2 / (2.0L * powl(a2 + x * x, 1.5L));
}

static void test_ggx_quadrature(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x5eed0004ULL);
    pf_test_max m = pf_test_max_init(), mg = pf_test_max_init();
    int i;
    for (i = 0; i < 1500; i++) {
        long double theta = (long double)pf_test_uniform(&rng, 0.001, 1.569);
        long double phi = (long double)pf_test_uniform(&rng, -3.14159, 3.14159);
        pf_real ax = (pf_real)pf_test_log_uniform(&rng, 0.01, 2.0);
        pf_real ay = (pf_real)pf_test_log_uniform(&rng, 0.01, 2.0);
        pf_vec3 w = pf_vec3_make((pf_real)(sinl(theta) * cosl(phi)), (pf_real)(sinl(theta) * sinl(phi)),
                                 (pf_real)cosl(theta));
        long double wx = (long double)w.x, wy = (long double)w.y, wz = (long double)w.z;
        long double r = sqrtl(wx * wx + wy * wy), cp = wx / r, sp = wy / r;
        long double ca[2];
        pf_oracle_result q;
        long double lam_ref, g1_ref;
        ca[0] = wz / r;
        ca[1] = sqrtl(cp * cp * (long double)ax * (long double)ax + sp * sp * (long double)ay * (long double)ay);
        q = pf_oracle_integrate(ggx_tail, ca, 0.0L, HUGE_VALL, 0.0L, 1e-17L, PF_ORACLE_MAX_INTERVALS);
        lam_ref = q.value / ca[0];
        g1_ref = 1.0L / (1.0L + lam_ref);
        pf_test_max_update(&m, pf_test_rel_error((long double)pf_lambda_ggx(w, ax, ay), lam_ref), theta);
        pf_test_max_update(&mg, pf_test_rel_error((long double)pf_g1_ggx(w, ax, ay), g1_ref), theta);
        if (ax == ay) { /* never exactly, but keep the iso path honest below */ }
    }
    /* isotropic from cos theta */
    for (i = 1; i < 400; i++) {
        long double ct = (long double)i / 400.0L, st = sqrtl(1.0L - ct * ct);
        long double ca[2];
        pf_oracle_result q;
        long double lam_ref;
        pf_real ctr = (pf_real)ct;
        ct = (long double)ctr;
        st = sqrtl(1.0L - ct * ct);
        ca[0] = ct / st;
        ca[1] = 0.35L;
        q = pf_oracle_integrate(ggx_tail, ca, 0.0L, HUGE_VALL, 0.0L, 1e-17L, PF_ORACLE_MAX_INTERVALS);
        lam_ref = q.value / ca[0];
        pf_test_max_update(&m, pf_test_rel_error((long double)pf_lambda_ggx_iso(ctr, (pf_real)0.35L), lam_ref), ct);
        pf_test_max_update(&mg, pf_test_rel_error((long double)pf_g1_ggx_iso(ctr, (pf_real)0.35L),
                                                  1.0L / (1.0L + lam_ref)), ct);
    }
    pf_test_note("GGX Lambda max rel %.3g, G1 %.3g", (double)m.err, (double)mg.err);
    PF_CHECK(m.err <= 64.0L * PF_TEST_EPS, "GGX Lambda max rel %.3g at theta=%.5g", (double)m.err, (double)m.at);
    PF_CHECK(mg.err <= 16.0L * PF_TEST_EPS, "GGX G1 max rel %.3g at theta=%.5g", (double)mg.err, (double)mg.at);
}

/* 2D check of the anisotropic GGX marginal claim: 1 + Lambda = integral of
   max(0, wz - wx x - wy y) P22 / wz with P22 = 1 / (pi ax ay (1 + x^2/ax^2 + y^2/ay^2)^2). */
typedef struct ggx2d {
    long double wx, wy, wz, ax, ay;
} ggx2d;

static long double ggx2d_integrand(long double x, long double y, void *ctx)
{
    const ggx2d *g = (const ggx2d *)ctx;
    long double proj = g->wz - g->wx * x - g->wy * y;
    long double e = 1.0L + x * x / (g->ax * g->ax) + y * y / (g->ay * g->ay);
    return proj > 0.0L ? proj / (PF_TEST_PI * g->ax * g->ay * e * e) : 0.0L;
}

static int ggx2d_ypoints(long double x, long double *pts, int max_points, void *ctx)
{
    const ggx2d *g = (const ggx2d *)ctx;
    int n = 0;
    if (max_points < 2) return 0;
    pts[n++] = 0.0L;
    if (g->wy != 0.0L) pts[n++] = (g->wz - g->wx * x) / g->wy;
    return n;
}

static void test_ggx_anisotropic_2d(void)
{
    static const long double cfg[3][5] = {
        {0.5L, 0.4L, 0.768L, 0.3L, 0.8L}, {-0.7L, 0.2L, 0.5L, 0.6L, 0.15L}, {0.1L, 0.9L, 0.3L, 0.25L, 0.5L}};
    pf_test_max m = pf_test_max_init();
    int i;
    for (i = 0; i < 3; i++) {
        ggx2d g;
        pf_oracle_result r;
        pf_vec3 w = pf_vec3_make((pf_real)cfg[i][0], (pf_real)cfg[i][1], (pf_real)cfg[i][2]);
        g.wx = (long double)w.x;
        g.wy = (long double)w.y;
        g.wz = (long double)w.z;
        g.ax = (long double)(pf_real)cfg[i][3];
        g.ay = (long double)(pf_real)cfg[i][4];
        r = slope_plane_integral(ggx2d_integrand, &g, 0.0L, ggx2d_ypoints, 1e-12L, 800);
        PF_CHECK(r.converged, "GGX 2D quadrature %d: %s", i, pf_oracle_status_name(r.status));
        pf_test_max_update(&m, pf_test_rel_error(1.0L + (long double)pf_lambda_ggx(w, (pf_real)g.ax, (pf_real)g.ay),
                                                 r.value / g.wz),
                           (long double)i);
    }
    pf_test_note("1+Lambda vs 2D GGX integral %.3g", (double)m.err);
    PF_CHECK(m.err <= 64.0L * PF_TEST_EPS + 1e-10L, "GGX 2D: %.3g", (double)m.err);
}

/* ------------------------------------------------------------------ masking-shadowing */

static void test_joint_masking_shadowing(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x5eed0005ULL);
    pf_test_max m = pf_test_max_init(), ml = pf_test_max_init();
    int i;
    for (i = 0; i < 3000; i++) {
        pf_real nu_o = (pf_real)pf_test_log_uniform(&rng, 1e-4, 6.0);
        pf_real nu_i = (pf_real)pf_test_log_uniform(&rng, 1e-4, 6.0);
        long double lo = lambda_ref((long double)nu_o), li = lambda_ref((long double)nu_i);
        long double ref = 1.0L / (1.0L + lo + li);
        pf_test_max_update(&m, pf_test_rel_error((long double)pf_g2_beckmann(nu_o, nu_i), ref), (long double)nu_o);
        pf_test_max_update(&ml, pf_test_rel_error((long double)pf_smith_joint_lambda(pf_lambda_beckmann(nu_o),
                                                                                    pf_lambda_beckmann(nu_i)),
                                                  ref),
                           (long double)nu_o);
    }
    pf_test_note("joint from G1 max rel %.3g; from Lambda %.3g", (double)m.err, (double)ml.err);
#ifdef PF_DOUBLE
    PF_CHECK(m.err <= 32.0L * PF_TEST_EPS, "joint from G1: %.3g", (double)m.err);
#else
    PF_CHECK(m.err <= 3e-6L, "joint from G1: %.3g", (double)m.err);
#endif
    PF_CHECK(ml.err <= 32.0L * PF_TEST_EPS, "joint from Lambda: %.3g", (double)ml.err);
    /* separable is the product and never exceeds the joint form */
    PF_CHECK(pf_smith_separable(PF_R(0.5), PF_R(0.25)) == PF_R(0.125), "separable product");
    PF_CHECK(pf_smith_separable(PF_R(0.5), PF_R(0.25)) <= pf_smith_joint(PF_R(0.5), PF_R(0.25)), "separable <= joint");
}

/* ------------------------------------------------------------------ edges (also -ffast-math) */

static const double edge_values[] = {-1e30, -3.0, -1e-30, -0.0, 0.0, 1e-38, 1e-35, 1e-31, 2.8e-31, 3e-31, 1e-20,
                                     1e-10, 1e-6, 1e-3, 0.1, 0.5, 1.0, 1.5482, 1.55, 1.6, 2.0, 2.2, 3.0, 3.3,
                                     5.0, 9.2, 10.0, 10.5, 26.0, 27.5, 30.0, 1e6, 1e15, 1e30};
#define N_EDGE ((int)(sizeof edge_values / sizeof edge_values[0]))

static void edge_beckmann_finite_and_in_range(void)
{
    int i;
    for (i = 0; i < N_EDGE; i++) {
        pf_real nu = (pf_real)edge_values[i];
        pf_real l = pf_lambda_beckmann(nu), lf = pf_lambda_beckmann_fast(nu), lw = pf_lambda_beckmann_walter(nu);
        pf_real g = pf_g1_beckmann(nu), gf = pf_g1_beckmann_fast(nu), gw = pf_g1_beckmann_walter(nu);
        PF_CHECK(pf_test_finite(l) && l >= PF_R(0.0) && l <= PF_LAMBDA_MAX, "Lambda(%g) = %g", (double)nu, (double)l);
        PF_CHECK(pf_test_finite(lf) && lf >= PF_R(0.0) && lf <= PF_LAMBDA_MAX, "Lambda_fast(%g) = %g", (double)nu,
                 (double)lf);
        PF_CHECK(pf_test_finite(lw) && lw >= PF_R(0.0) && lw <= PF_LAMBDA_MAX, "Lambda_walter(%g) = %g",
                 (double)nu, (double)lw);
        PF_CHECK(g >= PF_R(0.0) && g <= PF_R(1.0), "G1(%g) = %g", (double)nu, (double)g);
        PF_CHECK(gf >= PF_R(0.0) && gf <= PF_R(1.0), "G1_fast(%g) = %g", (double)nu, (double)gf);
        PF_CHECK(gw >= PF_R(0.0) && gw <= PF_R(1.0), "G1_walter(%g) = %g", (double)nu, (double)gw);
        if (!(nu > PF_R(0.0))) {
            PF_CHECK(g == PF_R(0.0) && gf == PF_R(0.0) && gw == PF_R(0.0), "G1 below surface (nu=%g)", (double)nu);
            PF_CHECK(l == PF_LAMBDA_MAX && lf == PF_LAMBDA_MAX && lw == PF_LAMBDA_MAX, "Lambda below surface");
        }
        if (nu >= PF_R(12.0)) PF_CHECK(g == PF_R(1.0) && l <= PF_R(1e-60), "far tail nu=%g", (double)nu);
    }
    /* near 0: G1 ~ 2 sqrt(pi) nu, continuous, no 0/0 */
    PF_CHECK(pf_test_rel_error((long double)pf_g1_beckmann(PF_R(1e-20)), 2.0L * 1.7724538509055160273L * 1e-20L) <
                 1e-3L,
             "G1(1e-20) = %g", (double)pf_g1_beckmann(PF_R(1e-20)));
}

/* G1 non-decreasing and Lambda non-increasing in nu, on a fine grid, to within each tier's
   accuracy: a fitted rational wiggles around the truth by its fit error (float exact path
   3e-7 near nu = 2.5, fast tier 1e-6 just below its cutoff 2.2), which is allowed; the double
   exact path and Walter's form (before its minimum at 1.5897) must be strictly monotone.
   Lambda steps are measured in G1 terms, dLambda / (1 + Lambda). */
static void edge_beckmann_monotone(void)
{
#ifdef PF_DOUBLE
    const double slack[3] = {0.0, 2e-4, 0.0};
#else
    const double slack[3] = {1e-6, 2e-4, 0.0};
#endif
    double worst[3] = {0, 0, 0};
    int i, t, bad = 0;
    pf_real prev_g[3] = {0, 0, 0}, prev_l[3] = {PF_LAMBDA_MAX, PF_LAMBDA_MAX, PF_LAMBDA_MAX};
    for (i = 1; i <= 20000; i++) {
        pf_real nu = (pf_real)(12.0 * (double)i / 20000.0);
        pf_real g[3], l[3];
        g[0] = pf_g1_beckmann(nu);
        g[1] = pf_g1_beckmann_fast(nu);
        g[2] = pf_g1_beckmann_walter(nu);
        l[0] = pf_lambda_beckmann(nu);
        l[1] = pf_lambda_beckmann_fast(nu);
        l[2] = pf_lambda_beckmann_walter(nu);
        for (t = 0; t < 3; t++) {
            double dg = (double)(prev_g[t] - g[t]);
            double dl = (double)(l[t] - prev_l[t]) / (1.0 + (double)l[t]);
            if (t == 2 && nu > PF_R(1.5)) continue;
            if (dg > worst[t]) worst[t] = dg;
            if (dl > worst[t]) worst[t] = dl;
            if (dg > slack[t] || dl > slack[t]) bad++;
            prev_g[t] = g[t];
            prev_l[t] = l[t];
        }
    }
    pf_test_note("largest backward step: exact %.2g, fast %.2g, Walter %.2g", worst[0], worst[1], worst[2]);
    PF_CHECK(bad == 0, "%d steps against monotonicity beyond the tier's accuracy", bad);
}

/* Directions: normal incidence, grazing, below the macro- and mesosurface; slopes: zero,
   huge, degenerate covariance, mean toward and away from the view. */
static void edge_smith_nu(void)
{
    pf_slope_stats s = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(0.04), PF_R(0.09), PF_R(0.0));
    pf_slope_stats zero = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    pf_slope_stats huge = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(1e12), PF_R(1e12), PF_R(0.0));
    pf_slope_stats toward = pf_slope_stats_make(PF_R(-0.5), PF_R(0.0), PF_R(0.04), PF_R(0.04), PF_R(0.0));
    pf_slope_stats away = pf_slope_stats_make(PF_R(0.5), PF_R(0.0), PF_R(0.04), PF_R(0.04), PF_R(0.0));
    pf_vec3 w30 = pf_vec3_make(PF_R(0.5), PF_R(0.0), PF_R(0.8660254));
    pf_real nu;
    PF_CHECK(pf_smith_nu(pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)), s) == PF_NU_MAX, "normal incidence");
    PF_CHECK(pf_g1_beckmann(PF_NU_MAX) == PF_R(1.0), "G1 at normal incidence");
    PF_CHECK(pf_smith_nu(w30, zero) == PF_NU_MAX, "zero deviation");
    nu = pf_smith_nu(pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(1e-30)), s);
    PF_CHECK(pf_test_finite(nu) && nu >= PF_R(0.0) && nu < PF_R(1e-20), "grazing nu = %g", (double)nu);
    PF_CHECK(pf_smith_nu(pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(0.0)), s) == PF_R(0.0), "horizon");
    PF_CHECK(pf_smith_nu(pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(-0.2)), s) == PF_R(0.0), "below macrosurface");
    nu = pf_smith_nu(w30, huge);
    PF_CHECK(pf_test_finite(nu) && nu > PF_R(0.0) && nu < PF_R(1e-5), "huge sigma nu = %g", (double)nu);
    /* mean slope toward the view (micro-normals lean toward it): larger nu, less masking */
    PF_CHECK(pf_smith_nu(w30, toward) > pf_smith_nu(w30, s), "mean toward view");
    /* mean slope 0.5 along x, cot(60 deg) = 0.577: still above; at 70 deg (cot 0.364) below */
    PF_CHECK(pf_smith_nu(w30, away) < pf_smith_nu(w30, toward), "mean away from view");
    PF_CHECK(pf_smith_nu(pf_vec3_make(PF_R(0.9396926), PF_R(0.0), PF_R(0.3420201)), away) == PF_R(0.0),
             "below the mesosurface");
    PF_CHECK(pf_g2_beckmann(PF_R(0.0), PF_R(1.0)) == PF_R(0.0), "joint below surface");
    PF_CHECK(pf_smith_joint(PF_R(0.0), PF_R(0.0)) == PF_R(0.0), "joint 0/0");
    PF_CHECK(pf_smith_joint(PF_R(1.0), PF_R(1.0)) == PF_R(1.0), "joint both visible");
}

static void edge_slope_stats_from_moments(void)
{
    /* variance made negative by filtering, |r| > 1, zero variance */
    pf_slope_stats s = pf_slope_stats_from_moments(PF_R(0.2), PF_R(-0.1), PF_R(0.0399), PF_R(0.5), PF_R(0.3));
    pf_vec3 w = pf_vec3_make(PF_R(0.3), PF_R(0.4), PF_R(0.866));
    pf_real nu = pf_smith_nu(w, s);
    PF_CHECK(s.var_x == PF_R(0.0), "negative variance clamped: %g", (double)s.var_x);
    PF_CHECK(s.cov_xy == PF_R(0.0), "covariance clamped with a zero variance: %g", (double)s.cov_xy);
    PF_CHECK(pf_test_finite(nu) && nu > PF_R(0.0), "nu = %g", (double)nu);
    s = pf_slope_stats_from_moments(PF_R(0.0), PF_R(0.0), PF_R(0.04), PF_R(0.01), PF_R(0.05));
    PF_CHECK(s.cov_xy <= PF_R(0.0200001) && s.cov_xy >= PF_R(0.0199999), "|r| > 1 clamped: %g", (double)s.cov_xy);
    /* r = 1 exactly and a direction along the null direction of the covariance: sigma = 0 */
    nu = pf_smith_nu(pf_vec3_make(PF_R(0.1), PF_R(-0.2), PF_R(0.9)), s);
    PF_CHECK(pf_test_finite(nu) && nu > PF_R(0.0), "degenerate covariance nu = %g", (double)nu);
    PF_CHECK(pf_g1_beckmann(nu) >= PF_R(0.0) && pf_g1_beckmann(nu) <= PF_R(1.0), "G1 in range");
}

/* The sweep's finding (docs/stability.md, first sweep): G1o G1i subnormal lost its low bits and
   the joint term came out above min(G1o, G1i) (float 1.2e-33 vs 4.4e-8: 1.00013x). Exact
   inputs, then pairs with log-uniform exponents over the whole range (subnormals included),
   against the long double formula; G1 above 1 and any finite input stay finite and in range. */
static void edge_smith_joint_tiny_and_wide(void)
{
    pf_test_rng r = pf_test_rng_seed(0x5317A11ULL);
#ifdef PF_DOUBLE
    pf_real a = (pf_real)ldexp(31.0, -565), b = (pf_real)ldexp(284.0, -519); /* 0x1.fp-561, 0x1.1cp-511 */
    const double emin = -1074.0;
#else
    pf_real a = (pf_real)ldexp(409.0, -118), b = (pf_real)ldexp(382.0, -33); /* 0x1.99p-110, 0x1.7ep-25 */
    const double emin = -149.0;
#endif
    pf_real j = pf_smith_joint(a, b);
    long double worst = 0.0L;
    int i, bad = 0;
#ifdef __FAST_MATH__
    /* clang -ffast-math reassociates a (b / den) into (a b) / den and flushes the subnormal
       product: 0, still in [0, min(G1o, G1i)], but not accurate */
    PF_CHECK(j <= a && j >= PF_R(0.0), "joint(%g, %g) = %g above G1o", (double)a, (double)b, (double)j);
#else
    PF_CHECK(j <= a && j > PF_R(0.0), "joint(%g, %g) = %g above G1o", (double)a, (double)b, (double)j);
#endif
    for (i = 0; i < 200000; ++i) {
        pf_real x = (pf_real)ldexp(1.0, (int)pf_test_uniform(&r, emin, 1.0)) * (pf_real)pf_test_uniform(&r, 0.5, 1.0);
        pf_real y = (i % 4 == 0) ? PF_R(1.0) : (pf_real)ldexp(1.0, (int)pf_test_uniform(&r, emin, 1.0)) *
                                                   (pf_real)pf_test_uniform(&r, 0.5, 1.0);
        pf_real g = pf_smith_joint(x, y), m = pf_min(x, y);
        long double lx = (long double)x, ly = (long double)y, want = lx * ly / (lx + ly - lx * ly);
        if (!pf_test_bits_finite(g) || g < PF_R(0.0) || (long double)g > (long double)m * (1.0L + 4.0L * PF_TEST_EPS)) bad++;
        if (want >= 4.0L * (long double)PF_REAL_MIN && pf_test_rel_error((long double)g, want) > worst)
            worst = pf_test_rel_error((long double)g, want);
    }
    pf_test_note("pairs down to the smallest subnormal: relative error <= %.2Lf eps where the result is normal, %d above min(G1o, G1i)",
                 worst / PF_TEST_EPS, bad);
    PF_CHECK(bad == 0, "%d results out of [0, min(G1o, G1i)]", bad);
#ifndef __FAST_MATH__
    PF_CHECK(worst <= 4.0L * PF_TEST_EPS, "relative error %Lg", worst);
#endif
    /* G1 above 1 read as 1; the separable product clamps to [0, 1] */
    PF_CHECK(pf_smith_joint(PF_R(1.0), PF_REAL_MAX) == PF_R(1.0), "joint(1, MAX) = %g",
             (double)pf_smith_joint(PF_R(1.0), PF_REAL_MAX));
    PF_CHECK(pf_smith_joint(PF_R(2.0), PF_R(0.5)) == PF_R(0.5), "joint(2, 0.5)");
    PF_CHECK(pf_smith_separable(-PF_REAL_MAX, PF_REAL_MAX) == PF_R(0.0), "separable(-MAX, MAX) = %g",
             (double)pf_smith_separable(-PF_REAL_MAX, PF_REAL_MAX));
    PF_CHECK(pf_smith_separable(PF_REAL_MAX, PF_REAL_MAX) == PF_R(1.0), "separable(MAX, MAX)");
    PF_CHECK(pf_smith_separable(PF_R(0.5), PF_R(0.25)) == PF_R(0.125), "separable(0.5, 0.25)");
}

/* The sweep's findings: pf_smith_nu_iso(1, -PF_REAL_MAX) was NaN (sqrt(2) sigma overflowed, times
   sin = 0); under float -ffast-math pf_smith_nu with a variance near PF_REAL_MAX gave NaN
   (num * rsqrt(inf)); and stats with tiny variances whose product vx vy underflows gave
   |cov| > sigma_x sigma_y in pf_slope_stats_from_moments. */
static void edge_smith_huge_and_tiny_statistics(void)
{
    static const double cosines[] = { 1.0, 0.999, 0.5, 1e-7, 0.0, -0.5 };
    pf_slope_stats st = pf_slope_stats_make(PF_R(-3.51667404e-05), PF_R(6.57513738e-07), PF_REAL_MAX,
                                            PF_R(8.01492206e-12), PF_R(1.74792345e+13));
    pf_real nu = pf_smith_nu(pf_vec3_make(PF_R(2043.82922), PF_R(7932.94531), PF_R(0.0)), st);
    int i, k, e1, e2, bad = 0;
    PF_CHECK(pf_test_bits_finite(nu) && nu >= PF_R(0.0) && nu <= PF_NU_MAX, "nu with var_x = MAX: %g", (double)nu);
    nu = pf_smith_nu(pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(0.8)),
                     pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_REAL_MAX, PF_REAL_MAX, PF_R(0.0)));
    PF_CHECK(pf_test_bits_finite(nu) && nu >= PF_R(0.0) && nu < PF_R(1e-15), "nu with both variances MAX: %g", (double)nu);
    for (i = 0; i < (int)(sizeof cosines / sizeof cosines[0]); ++i)
        for (k = -1; k <= 1; k += 2) {
            pf_real v = pf_smith_nu_iso((pf_real)cosines[i], (pf_real)k * PF_REAL_MAX);
            bad += !(pf_test_bits_finite(v) && v >= PF_R(0.0) && v <= PF_NU_MAX);
        }
    PF_CHECK(pf_smith_nu_iso(PF_R(1.0), -PF_REAL_MAX) == PF_NU_MAX, "nu_iso(1, -MAX)");
    PF_CHECK(bad == 0, "%d nu_iso non-finite or out of range", bad);
    /* variances 2^e1, 2^e2 down to where their product underflows; |r| just above 1 */
    bad = 0;
    for (e1 = -140; e1 <= 0; e1 += 3)
        for (e2 = -140; e2 <= 0; e2 += 5)
            for (k = -1; k <= 1; k += 2) {
                pf_real vx = (pf_real)ldexp(1.3, e1), vy = (pf_real)ldexp(1.7, e2);
                pf_real c = (pf_real)k * (pf_real)(sqrt((double)vx) * sqrt((double)vy) * (1.0 + 1.0 / 1024.0));
                pf_slope_stats t = pf_slope_stats_from_moments(PF_R(0.0), PF_R(0.0), vx, vy, c);
                bad += !(PF_FABS(t.cov_xy) <= PF_SQRT(t.var_x) * PF_SQRT(t.var_y));
            }
    PF_CHECK(bad == 0, "%d covariances beyond sigma_x sigma_y", bad);
}

static void edge_ggx(void)
{
    int i;
    for (i = 0; i < N_EDGE; i++) {
        pf_real v = (pf_real)edge_values[i];
        pf_vec3 w = pf_vec3_make(PF_R(1.0), PF_R(0.5), v);
        pf_real l = pf_lambda_ggx(w, PF_R(0.3), PF_R(0.7)), g = pf_g1_ggx(w, PF_R(0.3), PF_R(0.7));
        pf_real li = pf_lambda_ggx_iso(v, PF_R(0.5)), gi = pf_g1_ggx_iso(v, PF_R(0.5));
        pf_real la = pf_lambda_ggx(pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(0.8)), v, v);
        PF_CHECK(pf_test_finite(l) && l >= PF_R(0.0) && l <= PF_LAMBDA_MAX, "GGX Lambda(z=%g) = %g", (double)v, (double)l);
        PF_CHECK(g >= PF_R(0.0) && g <= PF_R(1.0), "GGX G1(z=%g) = %g", (double)v, (double)g);
        PF_CHECK(pf_test_finite(li) && li >= PF_R(0.0) && li <= PF_LAMBDA_MAX, "GGX iso Lambda(%g) = %g", (double)v,
                 (double)li);
        PF_CHECK(gi >= PF_R(0.0) && gi <= PF_R(1.0), "GGX iso G1(%g) = %g", (double)v, (double)gi);
        PF_CHECK(pf_test_finite(la) && la >= PF_R(0.0) && la <= PF_LAMBDA_MAX, "GGX Lambda(alpha=%g) = %g", (double)v,
                 (double)la);
    }
    PF_CHECK(pf_g1_ggx(pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(0.8)), PF_R(0.0), PF_R(0.0)) == PF_R(1.0), "alpha 0");
    PF_CHECK(pf_lambda_ggx(pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(0.8)), PF_R(0.0), PF_R(0.0)) == PF_R(0.0), "alpha 0");
    PF_CHECK(pf_g1_ggx_iso(PF_R(0.0), PF_R(0.5)) == PF_R(0.0), "horizon");
    PF_CHECK(pf_g1_ggx_iso(PF_R(1.0), PF_R(0.5)) == PF_R(1.0), "normal incidence");
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_lambda_beckmann_quadrature);
    PF_TEST_RUN(test_g1_beckmann_quadrature);
    PF_TEST_RUN(test_g1_fast_and_walter);
    PF_TEST_RUN(test_lambda_fast_relative);
    PF_TEST_RUN(test_walter_clamped);
    PF_TEST_RUN(test_noncentered_1d);
    PF_TEST_RUN(test_noncentered_2d);
    PF_TEST_RUN(test_ndf_hemisphere);
    PF_TEST_RUN(test_centered_reduces_to_textbook);
    PF_TEST_RUN(test_ggx_quadrature);
    PF_TEST_RUN(test_ggx_anisotropic_2d);
    PF_TEST_RUN(test_joint_masking_shadowing);
    PF_TEST_RUN(edge_beckmann_finite_and_in_range);
    PF_TEST_RUN(edge_beckmann_monotone);
    PF_TEST_RUN(edge_smith_nu);
    PF_TEST_RUN(edge_slope_stats_from_moments);
    PF_TEST_RUN(edge_ggx);
    PF_TEST_RUN(edge_smith_joint_tiny_and_wide);
    PF_TEST_RUN(edge_smith_huge_and_tiny_statistics);
    return PF_TEST_END();
}

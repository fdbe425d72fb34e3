/* test_vmf.c - tests of include/pf_vmf.h.

   The truth is never the module's own formula:
   - lobe normalization, mean cosine and tangent variance: long double quadrature over the
     polar angle (tests/reference/pf_oracle.h);
   - the one-lobe convolution rule kappa' = kappa kappa_b / (kappa + kappa_b): against the exact
     spherical convolution of two vMF lobes, C1 C2 e^(-k1-k2) 4 pi sinh|k1 mu + k2 w| /
     |k1 mu + k2 w| (the integral of a product of two exponentials of w.mu over the sphere, in
     closed form, long double), error relative to the exact peak;
   - the mixture NDF: its projected-area integral (Wu et al. 2019 eq. 3) by 2D quadrature over
     the hemisphere; the vMF-form convolved NDF (the core of eq. 5) against the 2D quadrature of
     the mixture times a vMF base lobe;
   - the mixture's Smith Lambda against the quadrature of pf_smith.h eq. 1 for the Gaussian
     mixture of the lobes' slope statistics along w;
   - the multi-lobe BRDF of eq. 5 (slope form): a single sharp lobe is LEADR's one-slope
     footprint (pf_leadr_specular, itself tested against quadrature); its masking on real
     microsurfaces against the brute-force march of tests/reference/pf_microsurface.h;
   - EM: normals sampled (seeded) from known vMF mixtures must give back the lobes;
   - degenerate input: equal normals, zero and NaN weights, NaN normals, bad sizes, and
     canaries after every buffer.
   - slope-preserving downsampling (Wu et al. 2019 eqs. 9-10): against a dense least-squares
     solve of the same objective built here from its definition (long double normal equations
     with the mean constraint, Gaussian elimination); preserved mean slopes against the box
     map's on a bumpy surface; bad input through guarded buffers.
   Same bodies in float and double; edge_* tests also run under -ffast-math. */
/* MAP_ANONYMOUS and MAP_NORESERVE for pf_test_guarded_alloc under -std=c99 (before any include) */
#if defined(__unix__) && !defined(_DEFAULT_SOURCE)
#  define _DEFAULT_SOURCE 1
#endif
#include "pf_vmf.h"
#include "pf_oracle.h"
#include "pf_test.h"
#include "pf_microsurface.h"

/* ------------------------------------------------------------------ seeded sampling */
typedef struct trng { unsigned long long s; } trng;
static double trng_u(trng *r)
{
    unsigned long long z = (r->s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/* one normal from a vMF of axis mu, kappa: cos t = 1 + log(u + (1 - u) e^(-2 kappa)) / kappa */
static void sample_vmf(trng *r, const double mu[3], double kappa, double out[3])
{
    double u = trng_u(r), ph = 2.0 * PFM_PI * trng_u(r);
    double c = 1.0 + log(u + (1.0 - u) * exp(-2.0 * kappa)) / kappa, s = sqrt(fmax(0.0, 1.0 - c * c));
    double t1[3], t2[3], a[3] = { 1, 0, 0 }, l;
    int k;
    if (fabs(mu[0]) > 0.9) {
        a[0] = 0;
        a[1] = 1;
    }
    t1[0] = a[1] * mu[2] - a[2] * mu[1];
    t1[1] = a[2] * mu[0] - a[0] * mu[2];
    t1[2] = a[0] * mu[1] - a[1] * mu[0];
    l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (k = 0; k < 3; ++k) t1[k] /= l;
    t2[0] = mu[1] * t1[2] - mu[2] * t1[1];
    t2[1] = mu[2] * t1[0] - mu[0] * t1[2];
    t2[2] = mu[0] * t1[1] - mu[1] * t1[0];
    for (k = 0; k < 3; ++k) out[k] = c * mu[k] + s * (cos(ph) * t1[k] + sin(ph) * t2[k]);
}

static void dir_deg(double theta, double phi, double w[3])
{
    theta *= PFM_PI / 180.0;
    phi *= PFM_PI / 180.0;
    w[0] = sin(theta) * cos(phi);
    w[1] = sin(theta) * sin(phi);
    w[2] = cos(theta);
}
static pf_vec3 V(const double w[3]) { return pf_vec3_make((pf_real)w[0], (pf_real)w[1], (pf_real)w[2]); }

/* ------------------------------------------------------------------ a mixture, lobe by lobe */
static pf_vmf_sum mix_sum(const pf_vmf_mixture *m, pf_vec3 wo, pf_vec3 wi, pf_real base_var, int vmf_form,
                          pf_real kappa_b)
{
    pf_vmf_sum s = pf_vmf_sum_zero();
    int k;
    for (k = 0; k < m->count; ++k) {
        s = vmf_form ? pf_vmf_sum_add_vmf(s, m->lobe[k], wo, wi, kappa_b, base_var)
                     : pf_vmf_sum_add(s, m->lobe[k], wo, wi, base_var);
        s = pf_vmf_sum_add_masking(s, m->lobe[k], wo, wi, base_var);
    }
    return s;
}
static pf_real mix_lambda(const pf_vmf_mixture *m, pf_vec3 w, pf_real base_var)
{
    pf_real e = PF_R(0.0), a = PF_R(0.0);
    int k;
    for (k = 0; k < m->count; ++k) {
        e += pf_vmf_lobe_excess(m->lobe[k], w, base_var);
        a += pf_vmf_lobe_area(m->lobe[k], w);
    }
    return pf_vmf_lambda(e, a);
}
static pf_real mix_ndf(const pf_vmf_mixture *m, pf_vec3 w, pf_real kappa_b)
{
    pf_real d = PF_R(0.0);
    int k;
    for (k = 0; k < m->count; ++k) d += pf_vmf_lobe_ndf(m->lobe[k], w, kappa_b);
    return d;
}
static pf_real mix_area(const pf_vmf_mixture *m, pf_vec3 w)
{
    pf_real a = PF_R(0.0);
    int k;
    for (k = 0; k < m->count; ++k) a += pf_vmf_lobe_area(m->lobe[k], w);
    return a;
}
static pf_vmf_mixture mix_one(pf_real amp, pf_real x, pf_real y, pf_real kappa)
{
    pf_vmf_mixture m;
    m.count = 1;
    m.lobe[0] = pf_vmf_lobe_make(amp, x, y, kappa);
    return m;
}

/* ------------------------------------------------------------------ normalization, moments */
typedef struct polar_ctx { long double kappa; int moment; } polar_ctx;
/* C(kappa) exp(kappa (cos t - 1)) 2 pi sin t times 1, cos t or sin^2 t / 2 */
static long double polar_fn(long double t, void *ctx)
{
    const polar_ctx *c = (const polar_ctx *)ctx;
    long double k = c->kappa, w = expl(k * (cosl(t) - 1.0L)) * 2.0L * PF_TEST_PI * sinl(t);
    if (c->moment == 1) w *= cosl(t);
    if (c->moment == 2) w *= 0.5L * sinl(t) * sinl(t);
    return w;
}
static long double polar_integral(long double kappa, int moment)
{
    polar_ctx c;
    long double pt[1];
    pf_oracle_result r;
    c.kappa = kappa;
    c.moment = moment;
    pt[0] = fminl(1.0L, 3.0L / sqrtl(kappa));
    r = pf_oracle_integrate_points(polar_fn, &c, 0.0L, PF_TEST_PI, pt, pt[0] < PF_TEST_PI ? 1 : 0, 0.0L, 1e-19L,
                                   PF_ORACLE_MAX_INTERVALS);
    return r.value;
}

static const double kappas[] = { 1e-4, 1e-2, 0.3, 0.5, 1.0, 3.0, 10.0, 100.0, 1e3, 1e4, 1e5 };
#define NKAPPA ((int)(sizeof kappas / sizeof kappas[0]))

static void test_normalization_quadrature(void)
{
    long double worst = 0;
    int i;
    for (i = 0; i < NKAPPA; ++i) {
        long double integral = polar_integral((long double)(pf_real)kappas[i], 0);
        long double c = (long double)pf_vmf_normalization((pf_real)kappas[i]);
        long double e = fabsl(c * integral - 1.0L) / PF_TEST_EPS;
        if (e > worst) worst = e;
    }
    pf_test_note("max |C * integral - 1| = %.2Lf eps over kappa 1e-4 .. 1e5", worst);
    PF_CHECK(worst <= 8.0L, "normalization off by %.2Lf eps", worst);
}

/* 1 - exp(-x) (the normalization's denominator) against libm's long double expm1l on a dense
   grid over [0, 2] (series below 1/2, direct above) and log-spaced small x down to the kappa
   floor: the series must be as accurate as the Kahan form it replaced (<= 2 ulp measured
   there) and needs no log near 1 (docs/gpu.md) */
static void test_one_minus_exp_neg_ulp(void)
{
    long double worst = 0, at = 0;
    int i;
    for (i = 0; i <= 40000; ++i) {
        pf_real x = i < 20000 ? (pf_real)(2.0 * i / 20000.0) : (pf_real)(1e-5 * pow(10.0, 5.0 * (i - 20000) / 20000.0));
        long double e = pf_test_ulp_error(pfi_vmf_one_minus_exp_neg(x), -expm1l(-(long double)x));
        if (x > 0 && e > worst) {
            worst = e;
            at = (long double)x;
        }
    }
    pf_test_note("1 - exp(-x): max %.3Lf ulp at x = %.6Lg (x in [1e-5, 2])", worst, at);
    PF_CHECK(worst <= 2.0L, "1 - exp(-x) off by %.3Lf ulp at x = %.6Lg", worst, at);
}

static void test_mean_cosine_and_variance_quadrature(void)
{
    long double worst_a = 0, worst_v = 0;
    int i;
    for (i = 0; i < NKAPPA; ++i) {
        long double k = (long double)(pf_real)kappas[i];
        long double z = polar_integral(k, 0), a = polar_integral(k, 1) / z, v = polar_integral(k, 2) / z;
        long double ea = fabsl((long double)pf_vmf_mean_cosine((pf_real)k) - a) / (a * PF_TEST_EPS);
        long double ev = fabsl((long double)pf_vmf_tangent_variance((pf_real)k) - v) / (v * PF_TEST_EPS);
        if (ea > worst_a) worst_a = ea;
        if (ev > worst_v) worst_v = ev;
    }
    pf_test_note("A3 max %.1Lf eps, tangent variance max %.1Lf eps (relative)", worst_a, worst_v);
#ifdef PF_DOUBLE
    PF_CHECK(worst_a <= 400.0L && worst_v <= 400.0L, "A3 %.1Lf eps, v %.1Lf eps", worst_a, worst_v);
#else
    PF_CHECK(worst_a <= 40.0L && worst_v <= 40.0L, "A3 %.1Lf eps, v %.1Lf eps", worst_a, worst_v);
#endif
}

static void test_kappa_inverses(void)
{
    long double worst = 0, worst_r = 0;
    int i;
    for (i = 2; i < NKAPPA - 1; ++i) {
        pf_real k = (pf_real)kappas[i];
        pf_real back = pf_vmf_kappa_from_tangent_variance(pf_vmf_tangent_variance(k));
        long double e = fabsl((long double)back - (long double)k) / (long double)k;
        /* Banerjee's rule against the exact inverse of A3 (its own approximation error) */
        long double a = polar_integral((long double)k, 1) / polar_integral((long double)k, 0);
        long double kb = (long double)pf_vmf_kappa_from_mean_length((pf_real)a);
        long double er = fabsl(kb - (long double)k) / (long double)k;
        if (e > worst) worst = e;
        if (er > worst_r) worst_r = er;
    }
    pf_test_note("kappa from tangent variance round trip %.2Le; Banerjee r(3-r^2)/(1-r^2) vs exact %.3Lf", worst,
                 worst_r);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-9L, "round trip %.3Le", worst);
#else
    PF_CHECK(worst <= 2e-3L, "round trip %.3Le", worst);
#endif
    PF_CHECK(worst_r <= 0.06L, "Banerjee's kappa off by %.3Lf", worst_r);
}

static void test_lobe_eval_large_kappa(void)
{
    /* exp(kappa (mu.w - 1)) near the peak at kappa = 1e5, in long double */
    long double worst = 0;
    int i;
    for (i = 0; i < 40; ++i) {
        double t = 2e-5 * i, w[3], mu[3] = { 0, 0, 1 };
        long double k = 1e5L, ref;
        pf_real got;
        dir_deg(t * 180.0 / PFM_PI, 30.0, w);
        got = pf_vmf_lobe_eval(V(mu), (pf_real)k, V(w));
        ref = k / (2.0L * PF_TEST_PI) * expl(-k * 2.0L * sinl(0.5L * (long double)(pf_real)t) * sinl(0.5L * (long double)(pf_real)t));
        if (ref > 1e-30L && fabsl((long double)got - ref) / ref > worst) worst = fabsl((long double)got - ref) / ref;
    }
    pf_test_note("kappa 1e5 within 8e-4 rad of the axis: max rel %.2Le", worst);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-10L, "rel %.3Le", worst);
#else
    PF_CHECK(worst <= 2e-2L, "rel %.3Le", worst); /* the direction's own rounding: kappa |w - mu|^2 ulp */
#endif
}

/* ------------------------------------------------------------------ convolution rule */
/* exact (g_k1 * g_k2)(psi): two lobes at angle psi apart */
static long double conv_exact(long double k1, long double k2, long double psi)
{
    long double c1 = k1 / (2.0L * PF_TEST_PI * -expm1l(-2.0L * k1)), c2 = k2 / (2.0L * PF_TEST_PI * -expm1l(-2.0L * k2));
    long double r = sqrtl(k1 * k1 + k2 * k2 + 2.0L * k1 * k2 * cosl(psi));
    /* 4 pi sinh(r)/r e^(-k1-k2) = 2 pi (1 - e^(-2r)) / r e^(r - k1 - k2) */
    return c1 * c2 * 2.0L * PF_TEST_PI * (-expm1l(-2.0L * r)) / r * expl(r - k1 - k2);
}

static void test_convolution_rule_error(void)
{
    static const double kb[] = { 100.0 };
    static const double ratio[] = { 0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0 };
    long double worst = 0, at = 0;
    int i, j, p;
    for (i = 0; i < 1; ++i)
        for (j = 0; j < (int)(sizeof ratio / sizeof ratio[0]); ++j) {
            long double k1 = (long double)kb[i] * (long double)ratio[j], k2 = (long double)kb[i];
            long double peak = conv_exact(k1, k2, 0.0L);
            pf_real kp = pf_vmf_convolve_kappa((pf_real)k1, (pf_real)k2);
            for (p = 0; p <= 200; ++p) {
                long double psi = 0.01L * p * 3.0L / sqrtl((long double)kp);
                double w[3], mu[3] = { 0, 0, 1 };
                long double e;
                dir_deg((double)(psi * 180.0L / PF_TEST_PI), 0.0, w);
                e = fabsl((long double)pf_vmf_lobe_eval(V(mu), kp, V(w)) - conv_exact(k1, k2, psi)) / peak;
                if (e > worst) {
                    worst = e;
                    at = k1 / k2;
                }
            }
        }
    pf_test_note("one-lobe rule vs exact spherical convolution (kappa_b = 100): max error %.2Le of the peak, at "
                 "kappa/kappa_b = %.2Lg",
                 worst, at);
    PF_CHECK(worst <= 0.01L, "convolution rule off by %.3Le of the peak", worst);
}

/* ------------------------------------------------------------------ mixture NDF integrals */
typedef struct mix_ctx {
    pf_vmf_mixture m;
    pf_real kappa_b;
    int mode;      /* 0: D(w) w.z; 1: exact convolution of the mixture with a vMF base lobe at h */
    double h[3];
} mix_ctx;

/* over (t, phi) of the upper hemisphere, sin t included */
static long double mix_fn(long double t, long double ph, void *ctx)
{
    const mix_ctx *c = (const mix_ctx *)ctx;
    long double w[3], p = 0;
    int k;
    w[0] = sinl(t) * cosl(ph);
    w[1] = sinl(t) * sinl(ph);
    w[2] = cosl(t);
    for (k = 0; k < c->m.count; ++k) {
        long double mu[3], d, kap = (long double)c->m.lobe[k].kappa;
        mu[0] = (long double)c->m.lobe[k].mu.x;
        mu[1] = (long double)c->m.lobe[k].mu.y;
        mu[2] = (long double)c->m.lobe[k].mu.z;
        d = w[0] * mu[0] + w[1] * mu[1] + w[2] * mu[2];
        p += (long double)c->m.lobe[k].amp * kap / (2.0L * PF_TEST_PI * -expm1l(-2.0L * kap)) * expl(kap * (d - 1.0L));
    }
    if (c->mode == 1) { /* times the base lobe at the half vector, over the whole sphere */
        long double kb = (long double)c->kappa_b, d = w[0] * (long double)c->h[0] + w[1] * (long double)c->h[1] + w[2] * (long double)c->h[2];
        p *= kb / (2.0L * PF_TEST_PI * -expm1l(-2.0L * kb)) * expl(kb * (d - 1.0L));
    }
    return p * sinl(t);
}

static pf_vmf_mixture test_mixture(void)
{
    pf_vmf_mixture m;
    m.count = 3;
    m.lobe[0] = pf_vmf_lobe_make(PF_R(0.5), PF_R(0.0), PF_R(0.0), PF_R(60.0));
    m.lobe[1] = pf_vmf_lobe_make(PF_R(0.3), PF_R(0.4), PF_R(0.1), PF_R(150.0));
    m.lobe[2] = pf_vmf_lobe_make(PF_R(0.2), PF_R(-0.2), PF_R(-0.3), PF_R(30.0));
    return m;
}

static void test_mixture_projected_area_quadrature(void)
{
    mix_ctx c;
    pf_oracle_2d pb;
    pf_oracle_result r;
    long double err;
    c.m = test_mixture();
    c.mode = 0;
    pb = pf_oracle_2d_make(mix_fn, &c, 0.0L, 0.5L * PF_TEST_PI, 0.0L, 2.0L * PF_TEST_PI);
    pb.epsrel = 1e-12L;
    r = pf_oracle_integrate_2d(&pb);
    /* the lobes' mass below the horizon (< 1e-9 here) is the only difference from sum a = 1 */
    err = fabsl(r.value - 1.0L);
    pf_test_note("integral of p(w) over the hemisphere (= integral D w.z, eq. 3) - 1 = %.2Le", err);
    /* float: the lobe axes and amplitudes are rounded to pf_real (|mu| = 1 + O(eps)) */
    PF_CHECK(r.converged && err <= 1e-8L + 8.0L * PF_TEST_EPS, "hemisphere integral %.12Lf", r.value);
}

static void test_mixture_ndf_vmf_convolution(void)
{
    /* the vMF-form NDF (one-lobe rule per lobe) against the 2D quadrature of p * g_kb at h */
    mix_ctx c;
    long double worst = 0, peak = 0;
    int i;
    c.m = test_mixture();
    c.mode = 1;
    c.kappa_b = PF_R(100.0);
    for (i = 0; i < 12; ++i) {
        pf_oracle_2d pb;
        pf_oracle_result r;
        long double ref, got;
        dir_deg(3.0 * i, 20.0 + 7.0 * i, c.h);
        pb = pf_oracle_2d_make(mix_fn, &c, 0.0L, PF_TEST_PI, 0.0L, 2.0L * PF_TEST_PI);
        pb.epsrel = 1e-10L;
        r = pf_oracle_integrate_2d(&pb);
        ref = r.value / (long double)c.h[2];
        got = (long double)mix_ndf(&c.m, V(c.h), c.kappa_b);
        if (ref > peak) peak = ref;
        if (fabsl(got - ref) > worst) worst = fabsl(got - ref);
    }
    pf_test_note("vMF-form D' vs quadrature of the convolution: max error %.2Le of the largest value", worst / peak);
    PF_CHECK(worst / peak <= 0.01L, "D' off by %.3Le of the peak", worst / peak);
}

/* ------------------------------------------------------------------ mixture Smith Lambda */
typedef struct lam_ctx { long double c, a[PF_VMF_MAX_LOBES], mu[PF_VMF_MAX_LOBES], sd[PF_VMF_MAX_LOBES]; int n; } lam_ctx;
static long double lam_fn(long double x, void *ctx)
{
    const lam_ctx *l = (const lam_ctx *)ctx;
    long double p = 0;
    int k;
    for (k = 0; k < l->n; ++k) p += l->a[k] * pf_oracle_normal_pdf((x - l->mu[k]) / l->sd[k]) / l->sd[k];
    return (x - l->c) * p;
}

static void test_mixture_lambda_quadrature(void)
{
    pf_vmf_mixture m = test_mixture();
    pf_real base_var = PF_R(0.01);
    long double worst = 0;
    int v, az;
    for (v = 0; v < 8; ++v)
        for (az = 0; az < 4; ++az) {
            double w[3];
            lam_ctx l;
            long double r2, mbar = 0, ref, got, pts[1];
            pf_oracle_result r;
            int k;
            dir_deg(10.0 * v + 5.0, 30.0 + 90.0 * az, w);
            r2 = sqrtl((long double)w[0] * (long double)w[0] + (long double)w[1] * (long double)w[1]);
            l.c = (long double)(pf_real)w[2] / r2;
            l.n = m.count;
            for (k = 0; k < m.count; ++k) {
                pf_slope_stats s = pf_vmf_lobe_slope_stats(m.lobe[k].mu, m.lobe[k].kappa, base_var);
                long double cx = (long double)w[0] / r2, cy = (long double)w[1] / r2;
                l.a[k] = (long double)m.lobe[k].amp;
                l.mu[k] = cx * (long double)s.mean_x + cy * (long double)s.mean_y;
                l.sd[k] = sqrtl(cx * cx * (long double)s.var_x + cy * cy * (long double)s.var_y +
                                2.0L * cx * cy * (long double)s.cov_xy);
                mbar += l.a[k] * l.mu[k];
            }
            pts[0] = l.c;
            r = pf_oracle_integrate_points(lam_fn, &l, l.c, HUGE_VALL, pts, 0, 0.0L, 1e-16L, PF_ORACLE_MAX_INTERVALS);
            if (!(l.c > mbar)) continue;
            ref = r.value / (l.c - mbar);
            got = (long double)mix_lambda(&m, V(w), base_var);
            if (ref > 1e-6L && fabsl(got - ref) / ref > worst) worst = fabsl(got - ref) / ref;
        }
    pf_test_note("mixture Lambda vs quadrature of Smith's integral, views 5-75 deg: max rel %.2Le", worst);
#ifdef PF_DOUBLE
    PF_CHECK(worst <= 1e-10L, "rel %.3Le", worst);
#else
    PF_CHECK(worst <= 2e-4L, "rel %.3Le", worst);
#endif
}

/* ------------------------------------------------------------------ BRDF */
static void test_specular_one_lobe_is_leadr(void)
{
    /* a sharp lobe (kappa max) with the base variance: LEADR's footprint of one slope */
    long double worst = 0;
    int i, j;
    for (i = 0; i < 6; ++i)
        for (j = 0; j < 6; ++j) {
            double wo[3], wi[3];
            pf_vmf_mixture m = mix_one(PF_R(1.0), PF_R(0.15), PF_R(-0.1), PF_VMF_KAPPA_MAX);
            pf_slope_stats s = pf_slope_stats_make(-m.lobe[0].mu.x / m.lobe[0].mu.z, -m.lobe[0].mu.y / m.lobe[0].mu.z, PF_R(0.01),
                                                   PF_R(0.01), PF_R(0.0));
            long double ref, got;
            dir_deg(12.0 * i, 10.0, wo);
            dir_deg(10.0 * j + 3.0, 190.0 + 5.0 * j, wi);
            ref = (long double)pf_leadr_specular(V(wo), V(wi), s, PF_R(0.04));
            got = (long double)pf_vmf_sum_specular(mix_sum(&m, V(wo), V(wi), PF_R(0.01), 0, PF_R(0.0)), V(wo), V(wi), PF_R(0.04));
            if (ref > 1e-3L && fabsl(got - ref) / ref > worst) worst = fabsl(got - ref) / ref;
        }
    pf_test_note("one sharp lobe vs pf_leadr_specular (one slope + base): max rel %.2Le", worst);
    PF_CHECK(worst <= 0.02L, "rel %.3Le", worst); /* kappa_max's own variance 1e-5 against 0.01 */
}

static void test_specular_vmf_form_vs_integration(void)
{
    /* I = F D' G / (4 A_o) with D' from the 2D quadrature of the convolution (eq. 5's integral) */
    mix_ctx c;
    long double worst = 0;
    int i;
    c.m = test_mixture();
    c.mode = 1;
    c.kappa_b = PF_R(100.0);
    for (i = 0; i < 8; ++i) {
        double wo[3], wi[3], hl;
        pf_oracle_2d pb;
        pf_oracle_result r;
        long double ref, got, f, g, area, hw;
        int k;
        dir_deg(8.0 * i, 15.0, wo);
        dir_deg(6.0 * i + 4.0, 200.0, wi);
        for (k = 0; k < 3; ++k) c.h[k] = wo[k] + wi[k];
        hl = sqrt(c.h[0] * c.h[0] + c.h[1] * c.h[1] + c.h[2] * c.h[2]);
        for (k = 0; k < 3; ++k) c.h[k] /= hl;
        pb = pf_oracle_2d_make(mix_fn, &c, 0.0L, PF_TEST_PI, 0.0L, 2.0L * PF_TEST_PI);
        pb.epsrel = 1e-10L;
        r = pf_oracle_integrate_2d(&pb);
        hw = (long double)(c.h[0] * wi[0] + c.h[1] * wi[1] + c.h[2] * wi[2]);
        f = 0.04L + 0.96L * powl(1.0L - hw, 5.0L);
        g = (long double)pf_vmf_sum_g2(mix_sum(&c.m, V(wo), V(wi), PF_R(0.01), 0, PF_R(0.0)), V(wo), V(wi));
        area = (long double)mix_area(&c.m, V(wo));
        ref = f * r.value / (long double)c.h[2] * g / (4.0L * area);
        got = (long double)pf_vmf_sum_specular(mix_sum(&c.m, V(wo), V(wi), PF_R(0.01), 1, PF_R(100.0)), V(wo), V(wi), PF_R(0.04));
        if (fabsl(got - ref) / ref > worst) worst = fabsl(got - ref) / ref;
    }
    pf_test_note("vMF-form BRDF vs eq. 5's convolution integrated numerically: max rel %.2Le", worst);
    PF_CHECK(worst <= 0.03L, "rel %.3Le", worst);
}

/* masking of a fitted mixture against the brute-force march on real microsurfaces */
static void test_masking_vs_microsurface(void)
{
    static const int kinds[3] = { PFM_TILES, PFM_CRATERS, PFM_RIDGES };
    int ki;
    for (ki = 0; ki < 3; ++ki) {
        pfm_surface s;
        int W = 128, x, y, v;
        pf_real *nr = (pf_real *)malloc((size_t)W * W * 3 * sizeof(pf_real));
        unsigned char *vis = (unsigned char *)malloc((size_t)W * W);
        pf_vmf_mixture m;
        double ex = 0, ey = 0, exx = 0, eyy = 0, exy = 0;
        long double worst_v = 0, worst_g = 0;
        if (!nr || !vis || pfm_surface_make(&s, W, W, 1.0, pfm_params_default(kinds[ki])) != 0) {
            PF_CHECK(0, "setup failed");
            free(nr);
            free(vis);
            return;
        }
        for (y = 0; y < W; ++y)
            for (x = 0; x < W; ++x) {
                double sx, sy, n[3];
                size_t id = (size_t)y * W + x;
                pfm_slope(&s, x, y, &sx, &sy);
                pfm_normal(&s, x, y, n);
                nr[3 * id] = (pf_real)n[0];
                nr[3 * id + 1] = (pf_real)n[1];
                nr[3 * id + 2] = (pf_real)n[2];
                ex += sx;
                ey += sy;
                exx += sx * sx;
                eyy += sy * sy;
                exy += sx * sy;
            }
        ex /= W * W;
        ey /= W * W;
        exx /= W * W;
        eyy /= W * W;
        exy /= W * W;
        PF_CHECK(pf_vmf_fit_normals(nr, NULL, (long long)W * W, 8, 24, &m) == PF_OK, "fit failed");
        for (v = 0; v < 4; ++v) {
            double wo[3];
            pfm_shade sh;
            long double gv, gb, ref;
            dir_deg(45.0 + 10.0 * v, 30.0, wo);
            pfm_visibility_map(&s, wo, vis);
            sh = pfm_reference_shade(&s, vis, NULL, 0, 0, W, wo, wo, 0.1, 1.0);
            gv = (long double)pf_vmf_sum_g1_mixture(mix_sum(&m, V(wo), V(wo), PF_R(0.0), 0, PF_R(0.0)), V(wo));
            gb = (long double)pf_beckmann_g1(V(wo), pf_slope_stats_from_moments((pf_real)ex, (pf_real)ey, (pf_real)exx,
                                                                                (pf_real)eyy, (pf_real)exy));
            ref = (long double)sh.masking;
            if (fabsl(gv - ref) / ref > worst_v) worst_v = fabsl(gv - ref) / ref;
            if (fabsl(gb - ref) / ref > worst_g) worst_g = fabsl(gb - ref) / ref;
        }
        pf_test_note("%s 128^2, views 45-75: G1 of 8 lobes rel err %.3Lf (one Gaussian %.3Lf)", pfm_kind_name(kinds[ki]),
                     worst_v, worst_g);
        PF_CHECK(worst_v <= 0.06L, "%s: mixture G1 off by %.3Lf", pfm_kind_name(kinds[ki]), worst_v);
        pfm_surface_free(&s);
        free(nr);
        free(vis);
    }
}

/* ------------------------------------------------------------------ EM */
static void test_em_recovers_mixture(void)
{
    static const double amp[3] = { 0.5, 0.3, 0.2 }, kap[3] = { 400.0, 150.0, 800.0 };
    static const double th[3] = { 0.0, 25.0, 30.0 }, ph[3] = { 0.0, 40.0, 200.0 };
    enum { N = 20000 };
    pf_real *nr = (pf_real *)malloc(N * 3 * sizeof(pf_real));
    trng r;
    pf_vmf_mixture m;
    long double worst_ang = 0, worst_amp = 0, worst_k = 0;
    int i, k, j;
    r.s = 77;
    for (i = 0; i < N; ++i) {
        double u = trng_u(&r), mu[3], x[3];
        k = u < amp[0] ? 0 : (u < amp[0] + amp[1] ? 1 : 2);
        dir_deg(th[k], ph[k], mu);
        sample_vmf(&r, mu, kap[k], x);
        for (j = 0; j < 3; ++j) nr[3 * i + j] = (pf_real)x[j];
    }
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, N, 3, 50, &m) == PF_OK, "fit failed");
    PF_CHECK(m.count == 3, "%d lobes", m.count);
    for (k = 0; k < 3 && m.count == 3; ++k) {
        double mu[3];
        long double best = 10, ea, ek;
        int bj = 0;
        dir_deg(th[k], ph[k], mu);
        for (j = 0; j < 3; ++j) {
            long double d = acosl(fminl(1.0L, (long double)(mu[0] * (double)m.lobe[j].mu.x + mu[1] * (double)m.lobe[j].mu.y +
                                                            mu[2] * (double)m.lobe[j].mu.z)));
            if (d < best) {
                best = d;
                bj = j;
            }
        }
        ea = fabsl((long double)m.lobe[bj].amp - (long double)amp[k]);
        ek = fabsl((long double)m.lobe[bj].kappa - (long double)kap[k]) / (long double)kap[k];
        if (best > worst_ang) worst_ang = best;
        if (ea > worst_amp) worst_amp = ea;
        if (ek > worst_k) worst_k = ek;
    }
    pf_test_note("3 lobes from 20000 normals: axis %.2Lg deg, amplitude %.4Lf, kappa %.3Lf (rel)",
                 worst_ang * 180.0L / PF_TEST_PI, worst_amp, worst_k);
    PF_CHECK(worst_ang <= 0.01L && worst_amp <= 0.01L && worst_k <= 0.1L, "axis %.3Lg rad, amp %.4Lf, kappa %.3Lf",
             worst_ang, worst_amp, worst_k);
    free(nr);
}

static void test_em_deterministic_and_weighted(void)
{
    /* the same input twice gives the same bits; weight 2 on a point = the point twice */
    enum { N = 600 };
    pf_real nr[2 * N * 3], w[2 * N];
    pf_vmf_mixture a, b, c;
    trng r;
    int i, j, same = 1, close = 1;
    r.s = 5;
    for (i = 0; i < N; ++i) {
        double mu[3], x[3];
        dir_deg(i % 2 ? 20.0 : 0.0, i % 3 ? 0.0 : 120.0, mu);
        sample_vmf(&r, mu, 200.0, x);
        for (j = 0; j < 3; ++j) nr[3 * i + j] = nr[3 * (N + i) + j] = (pf_real)x[j];
        w[i] = PF_R(2.0);
        w[N + i] = PF_R(1.0);
    }
    pf_vmf_fit_normals(nr, NULL, N, 4, 30, &a);
    pf_vmf_fit_normals(nr, NULL, N, 4, 30, &b);
    pf_vmf_fit_normals(nr, w, N, 4, 30, &c); /* weights 2 on the first N */
    same = a.count == b.count;
    for (i = 0; i < a.count && same; ++i) /* field by field: the struct may have padding */
        same = a.lobe[i].amp == b.lobe[i].amp && a.lobe[i].kappa == b.lobe[i].kappa && a.lobe[i].mu.x == b.lobe[i].mu.x && a.lobe[i].mu.y == b.lobe[i].mu.y &&
               a.lobe[i].mu.z == b.lobe[i].mu.z;
    for (i = 0; i < a.count; ++i)
        if (fabs((double)(a.lobe[i].amp - c.lobe[i].amp)) > 1e-5 || fabs((double)(a.lobe[i].kappa - c.lobe[i].kappa)) > 1e-3 * (double)a.lobe[i].kappa)
            close = 0;
    PF_CHECK(same, "two fits differ");
    PF_CHECK(close && a.count == c.count, "uniform weights 2 changed the fit");
}

/* ------------------------------------------------------------------ degenerate input, buffers */
/* NaN inputs: not an edge_ test (-ffast-math compiles NaN tests away; its results on NaN
   input are undefined) */
static void test_fit_degenerate(void)
{
    pf_real nr[3 * 16], wz[16], pyr[400];
    pf_vmf_mixture m;
    int i, rc;
    for (i = 0; i < 16; ++i) {
        nr[3 * i] = PF_R(0.3);
        nr[3 * i + 1] = PF_R(0.0);
        nr[3 * i + 2] = PF_R(0.9);
        wz[i] = PF_R(0.0);
    }
    rc = pf_vmf_fit_normals(nr, NULL, 16, 8, 20, &m);
    PF_CHECK(rc == PF_OK && m.count == 1 && m.lobe[0].kappa == PF_VMF_KAPPA_MAX, "equal normals: rc %d, %d lobes", rc, m.count);
    rc = pf_vmf_fit_normals(nr, wz, 16, 4, 20, &m);
    PF_CHECK(rc == PF_ERR_ARG && m.count == 1 && m.lobe[0].mu.z == PF_R(1.0), "zero weights: rc %d", rc);
    nr[0] = (pf_real)NAN;
    nr[4] = (pf_real)INFINITY;
    wz[5] = (pf_real)NAN;
    for (i = 6; i < 16; ++i) wz[i] = PF_R(1.0);
    nr[3 * 7 + 1] = PF_R(0.2);
    rc = pf_vmf_fit_normals(nr, wz, 16, 4, 20, &m);
    PF_CHECK(rc == PF_OK && m.count >= 1, "NaN normals skipped: rc %d", rc);
    for (i = 0; i < m.count; ++i)
        PF_CHECK(isfinite((double)m.lobe[i].amp) && isfinite((double)m.lobe[i].kappa) && isfinite((double)m.lobe[i].mu.z), "lobe %d not finite", i);
    for (i = 0; i < 16 * 3; ++i) nr[i] = (pf_real)NAN;
    rc = pf_vmf_fit_normals(nr, NULL, 16, 4, 20, &m);
    PF_CHECK(rc == PF_ERR_ARG && m.count == 1, "all NaN: rc %d", rc);
    PF_CHECK(pf_vmf_fit_normals(NULL, NULL, 16, 4, 20, &m) == PF_ERR_ARG, "NULL normals");
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, 16, 0, 20, &m) == PF_ERR_ARG, "0 lobes");
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, 16, PF_VMF_MAX_LOBES + 1, 20, &m) == PF_ERR_ARG, "17 lobes");
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, 0, 4, 20, &m) == PF_ERR_ARG, "0 normals");
    PF_CHECK(pf_vmf_fit_normals(nr, NULL, 16, 4, 20, NULL) == PF_ERR_ARG, "NULL out");
    /* pyramid of a NaN map: flat lobes, PF_OK, nothing past the buffer */
    for (i = 0; i < 400; ++i) pyr[i] = PF_R(-7.0);
    PF_CHECK(pf_vmf_pyramid_texel_count(4, 4) == 21, "texel count %lld", pf_vmf_pyramid_texel_count(4, 4));
    rc = pf_vmf_pyramid_from_normals(nr, NULL, 4, 4, 2, 10, pyr);
    PF_CHECK(rc == PF_OK, "NaN map rc %d", rc);
    for (i = 0; i < 21 * 8; ++i) PF_CHECK(isfinite((double)pyr[i]) && pyr[i] != PF_R(-7.0), "texel value %d unwritten", i);
    for (i = 21 * 8; i < 400; ++i) PF_CHECK(pyr[i] == PF_R(-7.0), "canary %d overwritten", i);
    PF_CHECK(pf_vmf_pyramid_from_normals(nr, NULL, 3, 4, 2, 10, pyr) == PF_ERR_ARG, "non power of two");
    PF_CHECK(pf_vmf_pyramid_from_normals(nr, NULL, 4, 4, PF_VMF_MAX_LOBES + 1, 10, pyr) == PF_ERR_ARG, "17 lobes");
    PF_CHECK(pf_vmf_pyramid_from_normals(NULL, NULL, 4, 4, 2, 10, pyr) == PF_ERR_ARG, "NULL");
    PF_CHECK(pf_vmf_pyramid_texel_count(0, 4) == 0 && pf_vmf_pyramid_level_offset(5, 4, 1) == -1, "bad sizes");
}

static void test_pyramid_levels(void)
{
    /* 8 x 4 map: levels 8x4, 4x2, 2x1, 1x1; the top texel equals the fit of the whole map,
       every level-0 texel its own normal (one sharp lobe) */
    enum { W = 8, H = 4 };
    pf_real nr[W * H * 3], pyr[43 * 4 * 2 + 8];
    trng r;
    pf_vmf_mixture whole, top, t0;
    long long off;
    int i, j, ok = 1;
    r.s = 3;
    for (i = 0; i < W * H; ++i) {
        double mu[3] = { 0, 0, 1 }, x[3];
        sample_vmf(&r, mu, 20.0, x);
        for (j = 0; j < 3; ++j) nr[3 * i + j] = (pf_real)x[j];
    }
    for (i = 0; i < (int)(sizeof pyr / sizeof pyr[0]); ++i) pyr[i] = PF_R(-7.0);
    PF_CHECK(pf_vmf_pyramid_level_count(W, H) == 4, "levels %d", pf_vmf_pyramid_level_count(W, H));
    PF_CHECK(pf_vmf_pyramid_texel_count(W, H) == 32 + 8 + 2 + 1, "texels %lld", pf_vmf_pyramid_texel_count(W, H));
    PF_CHECK(pf_vmf_pyramid_from_normals(nr, NULL, W, H, 2, 30, pyr) == PF_OK, "rc");
    off = pf_vmf_pyramid_level_offset(W, H, 3);
    top = pf_vmf_mixture_from_texel(pyr + off * 8, 2);
    pf_vmf_fit_normals(nr, NULL, W * H, 2, 30, &whole);
    PF_CHECK(top.count == whole.count, "top %d lobes, whole %d", top.count, whole.count);
    for (i = 0; i < top.count && i < whole.count; ++i)
        if (top.lobe[i].amp != whole.lobe[i].amp || top.lobe[i].kappa != whole.lobe[i].kappa || top.lobe[i].mu.x != whole.lobe[i].mu.x) ok = 0;
    PF_CHECK(ok, "top texel differs from the fit of the whole map");
    t0 = pf_vmf_mixture_from_texel(pyr + 5 * 8, 2);
    PF_CHECK(t0.count == 1 && t0.lobe[0].kappa == PF_VMF_KAPPA_MAX &&
                 fabs((double)(t0.lobe[0].mu.x - nr[15] / pf_vec3_length(pf_vec3_make(nr[15], nr[16], nr[17])))) < 1e-5,
             "level-0 texel 5: %d lobes, kappa %g", t0.count, (double)t0.lobe[0].kappa);
    for (i = 43 * 8; i < (int)(sizeof pyr / sizeof pyr[0]); ++i) PF_CHECK(pyr[i] == PF_R(-7.0), "canary %d", i);
}

/* ------------------------------------------------------------------ edge: evaluators */
static void edge_evaluators_finite(void)
{
    static const float ks[] = { 0.0f, -1.0f, 1e-30f, 1e30f, 1e38f };
    pf_vmf_mixture m = test_mixture();
    int i, bad = 0;
    for (i = 0; i < 5; ++i) {
        pf_real k = (pf_real)ks[i];
        pf_vec3 z = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
        pf_real a = pf_vmf_normalization(k), b = pf_vmf_mean_cosine(k), c = pf_vmf_lobe_eval(z, k, z);
        pf_real d = pf_vmf_convolve_kappa(k, PF_R(100.0)), e = pf_vmf_kappa_from_tangent_variance(k);
        pf_real f = pf_vmf_kappa_from_mean_length(k), g = pf_vmf_kappa_from_sigma(k);
        if (!isfinite((double)a) || !isfinite((double)b) || !isfinite((double)c) || !isfinite((double)d) ||
            !isfinite((double)e) || !isfinite((double)f) || !isfinite((double)g))
            bad++;
    }
    for (i = 0; i < 40; ++i) {
        double wo[3], wi[3];
        pf_real s, g2;
        dir_deg(2.5 * i, 10.0 * i, wo);
        dir_deg(90.0 - 2.0 * i, 180.0 + 7.0 * i, wi);
        s = pf_vmf_sum_specular(mix_sum(&m, V(wo), V(wi), PF_R(0.01), 0, PF_R(0.0)), V(wo), V(wi), PF_R(1.0));
        g2 = pf_vmf_sum_g2(mix_sum(&m, V(wo), V(wi), PF_R(0.01), 0, PF_R(0.0)), V(wo), V(wi));
        if (!(g2 >= PF_R(0.0) && g2 <= PF_R(1.0))) bad++;
        g2 = pf_vmf_sum_g2_mixture(mix_sum(&m, V(wo), V(wi), PF_R(0.01), 0, PF_R(0.0)), V(wo), V(wi));
        if (!(g2 >= PF_R(0.0) && g2 <= PF_R(1.0))) bad++;
        s = pf_vmf_sum_specular_mixture(mix_sum(&m, V(wo), V(wi), PF_R(0.01), 0, PF_R(0.0)), V(wo), V(wi), PF_R(1.0));
        if (!isfinite((double)s) || s < PF_R(0.0)) bad++;
        if (!isfinite((double)s) || s < PF_R(0.0) || !(g2 >= PF_R(0.0) && g2 <= PF_R(1.0))) bad++;
        s = pf_vmf_sum_specular(mix_sum(&m, V(wo), V(wi), PF_R(0.01), 1, PF_R(100.0)), V(wo), V(wi), PF_R(1.0));
        if (!isfinite((double)s) || s < PF_R(0.0)) bad++;
    }
    PF_CHECK(pf_vmf_sum_specular(pf_vmf_sum_zero(), pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)),
                                 pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)), PF_R(1.0)) == PF_R(0.0),
             "empty mixture");
    PF_CHECK(bad == 0, "%d non-finite or out-of-range results", bad);
}

static void test_lobe_make_nan(void)
{
    pf_vmf_lobe l = pf_vmf_lobe_make((pf_real)NAN, (pf_real)NAN, PF_R(3.0), (pf_real)NAN);
    PF_CHECK(l.amp == PF_R(0.0) && l.mu.z == PF_R(0.0) && l.mu.y == PF_R(1.0) && l.kappa == PF_VMF_KAPPA_MIN,
             "NaN lobe: amp %g mu (%g %g %g) kappa %g", (double)l.amp, (double)l.mu.x, (double)l.mu.y, (double)l.mu.z,
             (double)l.kappa);
}

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
    trng r;
    double cx[12], cy[12], a[12];
    int i, j, k;
    r.s = seed;
    for (k = 0; k < 12; ++k) {
        cx[k] = trng_u(&r) * w;
        cy[k] = trng_u(&r) * h;
        a[k] = trng_u(&r) - 0.5;
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
        PF_CHECK(pf_vmf_downsample_scratch_size(w, h, f) == 6LL * n, "scratch size %lld", pf_vmf_downsample_scratch_size(w, h, f));
        rc = pf_vmf_downsample_slopes(fine, w, h, f, wrap ? PF_BORDER_WRAP : PF_BORDER_CLAMP, PF_R(0.01), 400, tol, coarse,
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
        rc = pf_vmf_downsample_slopes(fine, w, h, f, wrap ? PF_BORDER_WRAP : PF_BORDER_CLAMP, PF_R(0.01), 400, tol, again,
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
            rc = pf_vmf_downsample_slopes(fine, N, N, f, wrap ? PF_BORDER_WRAP : PF_BORDER_CLAMP, PF_R(0.01), 2000,
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
    pf_vmf_downsample_slopes(fn_, w_, h_, f_, b_, reg_, mi_, tol_, coarse, scratch, sl_, &it, &res)
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
    PF_CHECK(pf_vmf_downsample_slopes(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), NULL, scratch, 6 * NC, &it, &res) == PF_ERR_ARG, "NULL coarse");
    PF_CHECK(pf_vmf_downsample_slopes(fine, W, H, F, PF_BORDER_WRAP, PF_R(0.01), 10, PF_R(0.0), coarse, NULL, 6 * NC, &it, &res) == PF_ERR_ARG, "NULL scratch");
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
    PF_CHECK(pf_vmf_downsample_scratch_size(8, 8, 3) == 0 && pf_vmf_downsample_scratch_size(0, 8, 1) == 0 &&
                 pf_vmf_downsample_scratch_size(8, 8, 0) == 0 && pf_vmf_downsample_scratch_size((int)PF_MAX_SIDE + 1, 1, 1) == 0 &&
                 pf_vmf_downsample_scratch_size(1, 1, 1) == 6,
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
    rc = pf_vmf_downsample_slopes(fine, N, N, 2, PF_BORDER_CLAMP, PF_R(0.01), 300, PF_R(1e-5), coarse, scratch,
                                  6 * N * N / 4, &it, NULL);
    for (i = 0; i < N * N / 4; ++i) {
        if (!isfinite((double)coarse[i])) bad++;
        m += (long double)coarse[i];
    }
    for (i = 0; i < N * N; ++i) mf += (long double)fine[i];
    PF_CHECK(rc == PF_OK && bad == 0 && fabsl(m / (N * N / 4) - mf / (N * N)) <= 1e-4L, "rc %d, %d non-finite, mean %Lg vs %Lg", rc,
             bad, m / (N * N / 4), mf / (N * N));
}

/* ================================================================== scaling function (helper J)
   Oracles: the base lobe of tests/reference/pf_microsurface.h (pfm_base_specular, double) on a flat patch;
   the exchange of wo and wi (reciprocity, exact for a whole periodic map); a wall's shadow in
   closed form; the test header's own march and reference (pfm_visibility_map_box,
   pfm_reference_shade: an independent implementation in double); a separable R built by hand. */
static pf_real *scale_heights(const pfm_surface *s)
{
    pf_real *hm = (pf_real *)malloc((size_t)s->w * s->h * sizeof(pf_real));
    size_t i;
    if (hm)
        for (i = 0; i < (size_t)s->w * s->h; ++i) hm[i] = (pf_real)s->height[i];
    return hm;
}

static void test_scale_flat_patch_is_base(void)
{
    static pf_real hm[16 * 16];
    long double worst = 0;
    int a, b, c;
    memset(hm, 0, sizeof hm);
    for (a = 0; a < 5; ++a)
        for (b = 0; b < 5; ++b)
            for (c = 0; c < 4; ++c) {
                double wo[3], wi[3], ref;
                pf_real got = PF_R(-1.0);
                dir_deg(5.0 + 17.0 * a, 0.0, wo);
                dir_deg(3.0 + 18.0 * b, 180.0 - 40.0 * c, wi);
                PF_CHECK(pf_vmf_effective_brdf(hm, 16, 16, PF_R(0.5), 3, 5, 8, V(wo), V(wi), PF_R(0.2), PF_R(0.04), &got) ==
                             PF_OK,
                         "call");
                ref = pfm_base_specular(wo, wi, 0.0, 0.0, 0.2, 0.04) / wo[2];
                if (ref > 1e-6) {
                    long double e = fabsl((long double)got - (long double)ref) / (long double)ref;
                    if (e > worst) worst = e;
                } else
                    PF_CHECK(fabs((double)got - ref) <= 1e-6, "tail %g vs %g", (double)got, ref);
            }
    pf_test_note("flat patch: effective BRDF vs the base lobe (pfm_base_specular / cos): max rel %.2Le", worst);
    PF_CHECK(worst <= 2000.0L * PF_TEST_EPS, "rel %.3Le", worst);
}

static void test_scale_reciprocity(void)
{
    pfm_surface s;
    pf_real *hm;
    long double worst = 0;
    int a;
    if (pfm_surface_make(&s, 32, 32, 1.0, pfm_params_default(PFM_GAUSSIAN_FINE)) != 0 || !(hm = scale_heights(&s))) {
        PF_CHECK(0, "setup");
        return;
    }
    for (a = 0; a < 40; ++a) {
        double wo[3], wi[3];
        pf_real f1 = 0, f2 = 0;
        long double l, r;
        dir_deg(5.0 + 1.7 * a, 11.0 * a, wo);
        dir_deg(70.0 - 1.6 * a, 180.0 + 7.0 * a, wi);
        PF_CHECK(pf_vmf_effective_brdf(hm, 32, 32, PF_R(1.0), 0, 0, 32, V(wo), V(wi), PF_R(0.1), PF_R(0.04), &f1) == PF_OK &&
                     pf_vmf_effective_brdf(hm, 32, 32, PF_R(1.0), 0, 0, 32, V(wi), V(wo), PF_R(0.1), PF_R(0.04), &f2) == PF_OK,
                 "call");
        /* whole periodic map: the projected area is n^2 w.z, so f / cos(light) is symmetric */
        l = (long double)f1 / (long double)(pf_real)wi[2];
        r = (long double)f2 / (long double)(pf_real)wo[2];
        if (l + r > 0 && fabsl(l - r) / (l + r) > worst) worst = fabsl(l - r) / (l + r);
    }
    pf_test_note("reciprocity f(wo, wi)/cos_i = f(wi, wo)/cos_o, 32^2 gaussian_fine: max rel %.2Le", worst);
    PF_CHECK(worst <= 1e3L * PF_TEST_EPS, "rel %.3Le", worst);
    free(hm);
    pfm_surface_free(&s);
}

/* a wall of height H along y (columns [32, 48) of a 64^2 map): a node at column x < 31 on the
   flat ground sees w (azimuth phi toward +x) iff the ray clears the wall's foot line, i.e.
   rise (32 - x) / cos(phi) >= H, rise = cot(theta): the ramp cell from column 31 to 32 and
   the plateau are planar, and the ray only gains on the plateau */
static void test_scale_visibility_wall(void)
{
    static pf_real hm[64 * 64];
    const pf_real H = PF_R(6.0);
    int x, y, a, b, bad = 0, tested = 0, vis = 0;
    for (y = 0; y < 64; ++y)
        for (x = 0; x < 64; ++x) hm[y * 64 + x] = (x >= 32 && x < 48) ? H : PF_R(0.0);
    for (a = 0; a < 40; ++a)
        for (b = 0; b < 5; ++b) {
            double th = 20.0 + 1.7 * a, ph = -50.0 + 25.0 * b, w[3];
            dir_deg(th, ph, w);
            for (x = 2; x <= 29; ++x) {
                double rise = w[2] / sqrt(w[0] * w[0] + w[1] * w[1]);
                double clear = rise * (32.0 - x) / cos(ph * 3.14159265358979323846 / 180.0) - (double)H;
                int got;
                if (fabs(clear) < 1e-3) continue;
                got = pfi_vmf_visible(hm, 64, 64, PF_R(1.0), x, 20, V(w), 0, 0, 64, H);
                tested++;
                vis += got;
                if (got != (clear > 0.0)) bad++;
            }
        }
    pf_test_note("wall shadow: %d rays (%d visible), %d disagree with the closed form", tested, vis, bad);
    PF_CHECK(bad == 0 && vis > tested / 5 && vis < tested * 4 / 5, "%d of %d wrong (visible %d)", bad, tested, vis);
}

/* the effective BRDF against tests/reference/pf_microsurface.h's own in-footprint march and reference */
static void test_scale_vs_microsurface_reference(void)
{
    static const int kinds[3] = { PFM_RIDGES, PFM_TILES, PFM_GAUSSIAN_FINE };
    int ki;
    for (ki = 0; ki < 3; ++ki) {
        pfm_surface s;
        pf_real *hm;
        unsigned char *vo = (unsigned char *)malloc(64 * 64), *vi = (unsigned char *)malloc(64 * 64);
        long double num = 0, den = 0;
        int a;
        if (!vo || !vi || pfm_surface_make(&s, 64, 64, 1.0, pfm_params_default(kinds[ki])) != 0 ||
            !(hm = scale_heights(&s))) {
            PF_CHECK(0, "setup");
            free(vo);
            free(vi);
            return;
        }
        for (a = 0; a < 24; ++a) {
            double wo[3], wi[3];
            pfm_shade sh;
            pf_real got = 0;
            dir_deg(10.0 + 2.8 * a, 37.0 * a, wo);
            dir_deg(70.0 - 2.5 * a, 37.0 * a + 150.0 + 3.0 * a, wi);
            pfm_visibility_map_box(&s, wo, 8, 24, 32, NULL, vo);
            pfm_visibility_map_box(&s, wi, 8, 24, 32, NULL, vi);
            sh = pfm_reference_shade(&s, vo, vi, 8, 24, 32, wo, wi, 0.1, 0.04);
            PF_CHECK(pf_vmf_effective_brdf(hm, 64, 64, PF_R(1.0), 8, 24, 32, V(wo), V(wi), PF_R(0.1), PF_R(0.04), &got) ==
                         PF_OK,
                     "call");
            num += ((long double)got - (long double)sh.spec) * ((long double)got - (long double)sh.spec);
            den += (long double)sh.spec * (long double)sh.spec;
        }
        pf_test_note("%s 32^2 patch, 24 direction pairs: effective BRDF vs pfm_reference_shade (box march), rel L2 %.2Le",
                     pfm_kind_name(kinds[ki]), sqrtl(num / den));
        PF_CHECK(den > 0 && sqrtl(num / den) <= (sizeof(pf_real) == 4 ? 2e-3L : 1e-9L), "%s rel L2 %.3Le",
                 pfm_kind_name(kinds[ki]), sqrtl(num / den));
        free(hm);
        free(vo);
        free(vi);
        pfm_surface_free(&s);
    }
}

/* the prior toward 1 (shrink): well-sampled values keep their least-squares fit, a cell that
   only tails reach (f_eff exactly 0, f_lobes tiny: the case that left cells of S at 0 in the
   bench) and a patch without energy stay near 1; pf_vmf_scale_t with the returned prior gives
   a training patch's own T back, and every value against a closed form computed here */
static void test_scale_factor_shrink(void)
{
    enum { NT = 3, NP = 2, P = 6 };
    long long cnt = pf_vmf_scale_sample_count(NT, NP), cells = pf_vmf_scale_cell_count(NT, NP), s, c;
    pf_real fe[P * 36], fl[P * 36], scr[2 * 18 * P], T[P], S[18], S0[18], T0[P], prior = PF_R(-1.0), t_one;
    long double a = 0, q = 0, worst_fit = 0;
    trng r;
    int x, weak = 5, tail_cell = 7;
    r.s = 91;
    for (x = 0; x < P; ++x)
        for (s = 0; s < cnt; ++s) {
            c = pfi_vmf_scale_cell(s, NT, NP);
            fl[x * cnt + s] = (pf_real)(0.5 + trng_u(&r)) * (x == weak ? PF_R(1e-4) : PF_R(1.0)) * (c == tail_cell ? PF_R(1e-3) : PF_R(1.0));
            /* R = 1.5 on patch 0, 0.8 elsewhere; the tail cell's f_eff is exactly 0 */
            fe[x * cnt + s] = c == tail_cell ? PF_R(0.0) : (x == 0 ? PF_R(1.5) : PF_R(0.8)) * fl[x * cnt + s];
        }
    PF_CHECK(pf_vmf_scale_factor(fe, fl, P, NT, NP, 40, PF_R(0.0), T0, S0, scr, NULL, NULL) == PF_OK, "plain");
    PF_CHECK(pf_vmf_scale_factor(fe, fl, P, NT, NP, 40, PF_R(0.1), T, S, scr, &prior, NULL) == PF_OK, "shrink");
    pf_test_note("tail cell: S %.3g (plain %.3g); weak patch T %.3g (plain %.3g); patch 0 / patch 1 T ratio %.4g (plain %.4g)",
                 (double)S[tail_cell], (double)S0[tail_cell], (double)T[weak], (double)T0[weak], (double)(T[0] / T[1]),
                 (double)(T0[0] / T0[1]));
    PF_CHECK(S0[tail_cell] == PF_R(0.0), "plain least squares puts the tail cell at 0: %g", (double)S0[tail_cell]);
    /* with the prior: the tail cell holds ~1e-6 of a cell's energy, so its T S stays near 1
       (plain least squares: 0) */
    for (c = 0; c < cells; ++c)
        if (c != tail_cell) worst_fit = fmaxl(worst_fit, fabsl((long double)S[c] / (long double)S[0] - 1.0L));
    PF_CHECK(fabsl((long double)S[tail_cell] * (long double)T[1] - 1.0L) <= 0.35L,
             "tail cell scaled by %g, not near 1", (double)(S[tail_cell] * T[1]));
    /* every other cell fits the same R, so only the prior separates them: a cell of energy q is
       pulled 0.1 qbar / (q + 0.1 qbar) of the way toward 1, and the cells' energies differ */
    PF_CHECK(worst_fit <= 0.03L, "well-sampled cells moved by %.3Lg", worst_fit);
    /* patch 0's ratio 1.5 / 0.8 survives within the prior's 10% pull */
    PF_CHECK(fabsl((long double)(T[0] / T[1]) / (1.5L / 0.8L) - 1.0L) <= 0.1L, "T ratio %g", (double)(T[0] / T[1]));
    /* the weak patch (1e-4 of the energy) gets no T of its own (1 before T's normalization to
       mean 1), so T S is the unnormalized S, a few % from 1 here; plain least squares gave it
       its data's 0.8 relative to patch 1 */
    PF_CHECK(fabsl((long double)T[weak] * (long double)S[0] - 1.0L) <= 0.05L, "weak patch T S = %g", (double)(T[weak] * S[0]));
    /* pf_vmf_scale_t: the closed form (sum e l S + p) / (sum (l S)^2 + p), computed here */
    for (s = 0; s < cnt; ++s) {
        long double l = (long double)fl[cnt + s] * (long double)S[pfi_vmf_scale_cell(s, NT, NP)];
        a += (long double)fe[cnt + s] * l;
        q += l * l;
    }
    t_one = pf_vmf_scale_t(fe + cnt, fl + cnt, NT, NP, S, prior);
    a = (a + (long double)prior) / (q + (long double)prior); /* the closed form */
    PF_CHECK(prior > PF_R(0.0) && fabsl((long double)t_one / a - 1.0L) <= 1e3L * PF_TEST_EPS, "pf_vmf_scale_t %g against %Lg",
             (double)t_one, a);
    PF_CHECK(pf_vmf_scale_t(fe + cnt, fl + cnt, NT, NP, S, PF_R(1e30)) == PF_R(1.0) ||
                 fabs((double)pf_vmf_scale_t(fe + cnt, fl + cnt, NT, NP, S, PF_R(1e30)) - 1.0) <= 1e-6,
             "a huge prior gives 1");
}

/* a separable R = T0(x) S0(cell) must be recovered exactly by the rank-1 fit */
static void test_scale_factor_separable(void)
{
    enum { NT = 3, NP = 2, P = 5 };
    long long cnt = pf_vmf_scale_sample_count(NT, NP), cells = pf_vmf_scale_cell_count(NT, NP), s, c;
    pf_real *fe = (pf_real *)malloc((size_t)(cnt * P) * sizeof(pf_real)), *fl = (pf_real *)malloc((size_t)(cnt * P) * sizeof(pf_real));
    pf_real *scr = (pf_real *)malloc((size_t)(2 * cells * P) * sizeof(pf_real)), T[P], S[NT * NT * NP], err[3], t0[P],
            s0[NT * NT * NP];
    trng r;
    long double worst = 0, ratio;
    int x;
    r.s = 77;
    PF_CHECK(cnt == 36 && cells == 18, "counts %lld %lld", cnt, cells);
    if (!fe || !fl || !scr) {
        PF_CHECK(0, "alloc");
        return;
    }
    for (x = 0; x < P; ++x) t0[x] = (pf_real)(0.5 + trng_u(&r));
    for (c = 0; c < cells; ++c) s0[c] = (pf_real)(0.2 + 2.0 * trng_u(&r));
    for (x = 0; x < P; ++x)
        for (s = 0; s < cnt; ++s) {
            fl[x * cnt + s] = (pf_real)(trng_u(&r) * trng_u(&r) * 3.0);
            fe[x * cnt + s] = t0[x] * s0[pfi_vmf_scale_cell(s, NT, NP)] * fl[x * cnt + s];
        }
    PF_CHECK(pf_vmf_scale_factor(fe, fl, P, NT, NP, 60, PF_R(0.0), T, S, scr, NULL, err) == PF_OK, "factor");
    ratio = (long double)T[0] / (long double)t0[0];
    for (x = 0; x < P; ++x) worst = fmaxl(worst, fabsl((long double)T[x] / (long double)t0[x] / ratio - 1.0L));
    for (c = 0; c < cells; ++c) worst = fmaxl(worst, fabsl((long double)S[c] * ratio / (long double)s0[c] - 1.0L));
    pf_test_note("separable R: T S recovered to %.2Le, errors %.2e (BRDF) %.2e (R), unscaled %.2e", worst, (double)err[0],
                 (double)err[2], (double)err[1]);
    PF_CHECK(worst <= 100.0L * PF_TEST_EPS && err[0] <= 100 * PF_REAL_EPSILON && err[2] <= 100 * PF_REAL_EPSILON &&
                 err[1] > PF_R(0.1),
             "worst %.3Le err %g %g", worst, (double)err[0], (double)err[2]);
    ratio = 0;
    for (x = 0; x < P; ++x) ratio += (long double)T[x];
    PF_CHECK(fabsl(ratio / (long double)P - 1.0L) <= 10.0L * PF_TEST_EPS, "T mean %.17Lg", ratio / (long double)P);
    free(fe);
    free(fl);
    free(scr);
}

/* the lookup returns a cell's value at its centre directions, the shader path equals the CPU
   lookup, and pf_vmf_scale_apply multiplies; half-way between two theta nodes it is their mean */
static void test_scale_lookup(void)
{
    enum { NT = 4, NP = 3 };
    pf_real tab[NT * NT * NP], tm = PF_R(1.3);
    int a, b, c, bad = 0;
    for (a = 0; a < NT * NT * NP; ++a) tab[a] = (pf_real)(1 + a);
    for (a = 0; a < NT; ++a)
        for (b = 0; b < NT; ++b)
            for (c = 0; c < NP; ++c) {
                /* wo at azimuth 0, wi at c pi/(np - 1): node c of phi_d (undefined at theta 0) */
                pf_vec3 wo = pfi_vmf_scale_dir(b, 0, NT, NP, tm), wi = pfi_vmf_scale_dir(a, c, NT, NP, tm);
                pf_real got;
                if ((a == 0 || b == 0) && c != 0) continue;
                got = pf_vmf_scale_lookup(tab, NT, NP, tm, wo, wi);
                if (PF_FABS(got - tab[(a * NT + b) * NP + c]) > PF_R(1e-4) * tab[(a * NT + b) * NP + c]) bad++;
            }
    PF_CHECK(bad == 0, "%d nodes read wrong", bad);
    {
        pf_real th = PF_R(1.5) * tm / (pf_real)(NT - 1), got;
        pf_vec3 wo = pfi_vmf_scale_dir(2, 0, NT, NP, tm);
        pf_vec3 wi = pf_vec3_make(PF_SIN(th) * PF_COS(PF_PI), PF_SIN(th) * PF_SIN(PF_PI), PF_COS(th));
        got = pf_vmf_scale_lookup(tab, NT, NP, tm, wo, wi);
        PF_CHECK(PF_FABS(got - PF_R(0.5) * (tab[(1 * NT + 2) * NP + 2] + tab[(2 * NT + 2) * NP + 2])) <= PF_R(1e-3),
                 "half-way %g", (double)got);
    }
    PF_CHECK(pf_vmf_scale_lookup(0, NT, NP, tm, pf_vec3_make(0, 0, 1), pf_vec3_make(0, 0, 1)) == PF_R(1.0), "NULL table");
    PF_CHECK(pf_vmf_scale_apply(PF_R(2.0), PF_R(3.0), PF_R(0.5)) == PF_R(3.0) &&
                 pf_vmf_scale_apply(PF_R(-1.0), PF_R(1.0), PF_R(1.0)) == PF_R(0.0) &&
                 pf_vmf_scale_apply((pf_real)NAN, PF_R(1.0), PF_R(1.0)) == PF_R(0.0),
             "apply");
}

/* bad input, every buffer exactly its documented size behind guard pages */
static void test_scale_bad_input_guarded(void)
{
    const int W = 16, N = 8, NT = 2, NP = 2;
    long long cnt = pf_vmf_scale_sample_count(NT, NP), vb = pf_vmf_scale_vis_bytes(NT, NP, N), cells = pf_vmf_scale_cell_count(NT, NP);
    size_t hb = (size_t)W * W * sizeof(pf_real), nb = (size_t)3 * N * N * sizeof(pf_real), fb = (size_t)cnt * sizeof(pf_real);
    pf_real *hm = (pf_real *)pf_test_guarded_alloc(hb), *nr = (pf_real *)pf_test_guarded_alloc(nb);
    pf_real *fe = (pf_real *)pf_test_guarded_alloc(fb), *fl = (pf_real *)pf_test_guarded_alloc(fb);
    pf_real *T = (pf_real *)pf_test_guarded_alloc(sizeof(pf_real)), *S = (pf_real *)pf_test_guarded_alloc((size_t)cells * sizeof(pf_real));
    pf_real *scr = (pf_real *)pf_test_guarded_alloc((size_t)(2 * cells) * sizeof(pf_real)), out = PF_R(7.0), err[3], prior = PF_R(-1.0);
    unsigned char *vis = (unsigned char *)pf_test_guarded_alloc((size_t)vb);
    pf_vec3 z = pf_vec3_make(PF_R(0.3), PF_R(0.0), PF_R(0.9539392));
    int i;
    if (!hm || !nr || !fe || !fl || !T || !S || !scr || !vis) {
        pf_test_note("guarded allocation unsupported: skipped");
        return;
    }
    for (i = 0; i < W * W; ++i) hm[i] = (pf_real)(0.3 * sin(0.7 * i) + 0.2 * cos(1.3 * (i / W)));
    /* valid calls at the patch in the map's last corner (wrapping reads) touch nothing outside */
    PF_CHECK(pf_vmf_effective_brdf(hm, W, W, PF_R(1.0), W - 3, W - 5, N, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_OK &&
                 pf_test_finite(out) && out >= PF_R(0.0),
             "valid brdf %g", (double)out);
    PF_CHECK(pf_vmf_scale_patch(hm, W, W, PF_R(1.0), W - 3, W - 5, N, 2, 8, PF_R(0.1), PF_R(1.0), PF_VMF_SCALE_G_MIXTURE, NT,
                                NP, PF_R(1.2), nr, vis, fe, fl) == PF_OK,
             "valid patch");
    for (i = 0; i < cnt; ++i) PF_CHECK(pf_test_finite(fe[i]) && pf_test_finite(fl[i]) && fe[i] >= 0 && fl[i] >= 0, "sample %d", i);
    PF_CHECK(pf_vmf_scale_factor(fe, fl, 1, NT, NP, 4, PF_R(1.0), T, S, scr, &prior, err) == PF_OK && pf_test_finite(T[0]) &&
                 pf_test_finite(prior) && prior >= 0,
             "valid factor");
    PF_CHECK(pf_test_finite(pf_vmf_scale_t(fe, fl, NT, NP, S, prior)), "valid T");
    /* errors */
    PF_CHECK(pf_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, 0, N, z, z, PF_R(0.1), PF_R(1.0), NULL) == PF_ERR_ARG, "NULL out");
    PF_CHECK(pf_vmf_effective_brdf(NULL, W, W, PF_R(1.0), 0, 0, N, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG && out == 0,
             "NULL heights");
    PF_CHECK(pf_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, 0, W + 1, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG, "n > w");
    PF_CHECK(pf_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, 0, 0, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG, "n = 0");
    PF_CHECK(pf_vmf_effective_brdf(hm, W, W, PF_R(0.0), 0, 0, N, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG, "texel 0");
    PF_CHECK(pf_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, 0, N, z, z, (pf_real)NAN, PF_R(1.0), &out) == PF_ERR_ARG, "sigma NaN");
    PF_CHECK(pf_vmf_effective_brdf(hm, (int)(PF_MAX_SIDE + 1), 1, PF_R(1.0), 0, 0, 1, z, z, PF_R(0.1), PF_R(1.0), &out) ==
                 PF_ERR_SIZE,
             "side");
    hm[(W - 4) * W + 2] = (pf_real)NAN; /* inside the patch (0, W - 5, N): rows W - 5 .. W + 2 wrap */
    PF_CHECK(pf_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, W - 5, N, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG && out == 0,
             "NaN height");
    PF_CHECK(pf_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, W - 5, N, 2, 8, PF_R(0.1), PF_R(1.0), 0, NT, NP, PF_R(1.2), nr, vis, fe,
                                fl) == PF_ERR_ARG,
             "NaN height, patch");
    hm[(W - 4) * W + 2] = PF_R(0.0);
    PF_CHECK(pf_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, 0, N, PF_VMF_MAX_LOBES + 1, 8, PF_R(0.1), PF_R(1.0), 0, NT, NP,
                                PF_R(1.2), nr, vis, fe, fl) == PF_ERR_ARG,
             "lobes 17");
    PF_CHECK(pf_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, 0, N, 2, 8, PF_R(0.1), PF_R(1.0), 3, NT, NP, PF_R(1.2), nr, vis, fe, fl) ==
                 PF_ERR_ARG,
             "masking 3");
    PF_CHECK(pf_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, 0, N, 2, 8, PF_R(0.1), PF_R(1.0), 0, NT, NP, PF_R(1.6), nr, vis, fe, fl) ==
                 PF_ERR_ARG,
             "theta_max >= pi/2");
    PF_CHECK(pf_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, 0, N, 2, 8, PF_R(0.1), PF_R(1.0), 0, NT, NP, PF_R(1.2), nr, NULL, fe, fl) ==
                 PF_ERR_ARG,
             "NULL scratch");
    PF_CHECK(pf_vmf_scale_factor(fe, fl, 0, NT, NP, 4, PF_R(0.0), T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pf_vmf_scale_factor(fe, fl, 1, NT, NP, 0, PF_R(0.0), T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pf_vmf_scale_factor(fe, NULL, 1, NT, NP, 4, PF_R(0.0), T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pf_vmf_scale_factor(fe, fl, 1, NT, NP, 4, PF_R(-1.0), T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pf_vmf_scale_factor(fe, fl, 1, NT, NP, 4, (pf_real)NAN, T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pf_vmf_scale_factor(fe, fl, 1, 1 << 30, 1 << 30, 4, PF_R(0.0), T, S, scr, NULL, err) == PF_ERR_SIZE,
             "factor errors");
    PF_CHECK(pf_vmf_scale_t(NULL, fl, NT, NP, S, PF_R(0.0)) == PF_R(1.0) && pf_vmf_scale_t(fe, fl, 1, NP, S, PF_R(0.0)) == PF_R(1.0) &&
                 pf_vmf_scale_t(fe, fl, NT, NP, NULL, PF_R(0.0)) == PF_R(1.0) &&
                 pf_vmf_scale_t(fe, fl, NT, NP, S, (pf_real)NAN) == PF_R(1.0) && pf_vmf_scale_t(fe, fl, NT, NP, S, PF_R(-1.0)) == PF_R(1.0),
             "T errors");
    PF_CHECK(pf_vmf_scale_sample_count(1, 2) == 0 && pf_vmf_scale_cell_count(2, 1) == 0 && pf_vmf_scale_vis_bytes(2, 2, 0) == 0,
             "size queries");
    pf_test_guarded_free(hm, hb);
    pf_test_guarded_free(nr, nb);
    pf_test_guarded_free(fe, fb);
    pf_test_guarded_free(fl, fb);
    pf_test_guarded_free(T, sizeof(pf_real));
    pf_test_guarded_free(S, (size_t)cells * sizeof(pf_real));
    pf_test_guarded_free(scr, (size_t)(2 * cells) * sizeof(pf_real));
    pf_test_guarded_free(vis, (size_t)vb);
}
/* ================================================================== end of scaling function tests */

/* ------------------------------------------------------------------ view below the mesosurface
   pf_vmf_sum_specular(_mixture) with the view below the mixture's mean plane but above the
   macrosurface (area_o < 0 < wo.z): G / A_o = 1 / (P_o + max(A_o, 0) Lambda_i) as in
   pf_leadr_specular, P_o the projected area of the facets facing the view. Oracle: P_o by 1D
   quadrature (pf_oracle) of E[max(0, a - Y)] for each lobe's Gaussian slopes (pf_vmf_lobe_slope_stats)
   along wo, summed with the amplitudes (mixture form), or for the sum's slope mean and
   covariance (one-Gaussian form); below the mean plane Lambda_i drops out, so I = F D' / (4 P_o)
   with D' = ndf / amp from the sum and F Schlick's in long double. Also: one sharp lobe against
   pf_leadr_specular (itself tested against quadrature below the mean plane), and continuity
   of both forms through area_o = 0. */
typedef struct below_ctx { long double t; } below_ctx;
static long double below_facing_fn(long double z, void *ctx)
{
    long double t = ((const below_ctx *)ctx)->t;
    return z < t ? (t - z) * pf_oracle_normal_pdf(z) : 0.0L;
}
/* E[max(0, a - Y)], Y ~ N(0, sd^2), by quadrature over the standard normal */
static long double below_facing(long double a, long double sd)
{
    below_ctx c;
    pf_oracle_result r;
    if (!(sd > 0.0L)) return a > 0.0L ? a : 0.0L;
    c.t = a / sd;
    r = pf_oracle_integrate_points(below_facing_fn, &c, -HUGE_VALL, c.t, &c.t, 1, 0.0L, 1e-17L, PF_ORACLE_MAX_INTERVALS);
    return sd * r.value;
}
static long double below_facing_stats(pf_slope_stats s, const double w[3])
{
    long double a = (long double)(pf_real)w[2] - (long double)(pf_real)w[0] * (long double)s.mean_x -
                    (long double)(pf_real)w[1] * (long double)s.mean_y;
    long double wx = (long double)(pf_real)w[0], wy = (long double)(pf_real)w[1];
    long double v = wx * wx * (long double)s.var_x + wy * wy * (long double)s.var_y + 2.0L * wx * wy * (long double)s.cov_xy;
    return below_facing(a, sqrtl(v > 0.0L ? v : 0.0L));
}

/* The specular of mixture m just below (v[0]) and just above (v[1]) its mean plane along x,
   step_deg either side of it: the view moves (move_light 0; light at 35 deg, phi 180) or the
   light does (1; view there). v[side][0] is the mixture-Smith form, v[side][1] the
   one-Gaussian form. */
static void mean_plane_crossing(const pf_vmf_mixture *m, pf_real base_var, int move_light, long double step_deg,
                                long double v[2][2])
{
    double fixed[3], moving[3];
    pf_vmf_sum s0;
    long double mx, tc;
    int side;
    dir_deg(35.0, 180.0, fixed);
    dir_deg(70.0, 0.0, moving);
    s0 = move_light ? mix_sum(m, V(fixed), V(moving), base_var, 0, PF_R(0.0)) : mix_sum(m, V(moving), V(fixed), base_var, 0, PF_R(0.0));
    mx = (long double)s0.ex / (long double)s0.amp;
    tc = atanl(1.0L / mx) * 180.0L / PF_TEST_PI; /* the polar angle of the mean plane along x */
    for (side = 0; side < 2; ++side) {
        pf_vmf_sum s1;
        pf_vec3 wo, wi;
        dir_deg((double)(tc + (side ? step_deg : -step_deg)), 0.0, moving);
        wo = move_light ? V(fixed) : V(moving);
        wi = move_light ? V(moving) : V(fixed);
        s1 = mix_sum(m, wo, wi, base_var, 0, PF_R(0.0));
        v[side][0] = (long double)pf_vmf_sum_specular_mixture(s1, wo, wi, PF_R(0.04));
        v[side][1] = (long double)pf_vmf_sum_specular(s1, wo, wi, PF_R(0.04));
    }
}

static void test_specular_view_below_mean_plane(void)
{
    const pf_real base_var = PF_R(0.01);
    pf_vmf_mixture m;
    long double worst_mix = 0.0L, worst_one = 0.0L, worst_leadr = 0.0L, jump_mix = 0.0L, jump_one = 0.0L;
    long double nu_lo = 0.0L, nu_hi = -1.0e30L;
    int i, j, n = 0;
    /* two lobes tilted toward +x: the mean slope along x is ~0.43, so views beyond ~67 deg at
       phi near 0 are below the mean plane */
    m.count = 2;
    m.lobe[0] = pf_vmf_lobe_make(PF_R(0.6), PF_R(-0.45), PF_R(0.0), PF_R(40.0));
    m.lobe[1] = pf_vmf_lobe_make(PF_R(0.4), PF_R(-0.3), PF_R(0.2), PF_R(80.0));
    for (i = 0; i < 5; ++i)
        for (j = 0; j < 4; ++j) {
            double wo[3], wi[3], h[3], hl;
            pf_vmf_sum s;
            pf_slope_stats st;
            long double p_mix = 0.0L, p_one, f, hw, ref_mix, ref_one, got_mix, got_one, a_o, sd_o;
            int k;
            dir_deg(70.0 + 4.0 * i, -10.0 + 7.0 * j, wo);
            dir_deg(25.0 + 10.0 * j, 170.0 + 8.0 * i, wi);
            s = mix_sum(&m, V(wo), V(wi), base_var, 0, PF_R(0.0));
            st = pf_vmf_sum_stats(s);
            a_o = (long double)(pf_real)wo[2] - (long double)(pf_real)wo[0] * (long double)st.mean_x -
                  (long double)(pf_real)wo[1] * (long double)st.mean_y;
            if (!(a_o < 0.0L)) continue; /* only views below the mean plane here */
            sd_o = sqrtl(2.0L * ((long double)(pf_real)wo[0] * (long double)(pf_real)wo[0] * (long double)st.var_x +
                                 (long double)(pf_real)wo[1] * (long double)(pf_real)wo[1] * (long double)st.var_y +
                                 2.0L * (long double)(pf_real)wo[0] * (long double)(pf_real)wo[1] * (long double)st.cov_xy));
            nu_lo = fminl(nu_lo, a_o / sd_o);
            nu_hi = fmaxl(nu_hi, a_o / sd_o);
            for (k = 0; k < m.count; ++k)
                p_mix += (long double)m.lobe[k].amp * below_facing_stats(pf_vmf_lobe_slope_stats(m.lobe[k].mu, m.lobe[k].kappa, base_var), wo);
            p_one = below_facing_stats(st, wo);
            for (k = 0; k < 3; ++k) h[k] = (double)(pf_real)wo[k] + (double)(pf_real)wi[k];
            hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            hw = (long double)((h[0] * (double)(pf_real)wi[0] + h[1] * (double)(pf_real)wi[1] + h[2] * (double)(pf_real)wi[2]) / hl);
            f = 0.04L + 0.96L * powl(1.0L - hw, 5.0L);
            /* D' = ndf / amp; mixture: G / A_o = amp / (amp P_o) per unit amp */
            ref_mix = f * (long double)s.ndf / (4.0L * p_mix);
            ref_one = f * (long double)s.ndf / (4.0L * (long double)s.amp * p_one);
            got_mix = (long double)pf_vmf_sum_specular_mixture(s, V(wo), V(wi), PF_R(0.04));
            got_one = (long double)pf_vmf_sum_specular(s, V(wo), V(wi), PF_R(0.04));
            worst_mix = fmaxl(worst_mix, pf_test_rel_error(got_mix, ref_mix));
            worst_one = fmaxl(worst_one, pf_test_rel_error(got_one, ref_one));
            ++n;
        }
    /* one sharp lobe: pf_leadr_specular of its own slope statistics (mean slope (0.5, 0); the
       lobe's variance is base_var plus kappa_max's, which matters below the mean plane, where
       P_o is a tail of the slope density) */
    for (i = 0; i < 4; ++i) {
        double wo[3], wi[3];
        pf_vmf_mixture one = mix_one(PF_R(1.0), PF_R(-0.447213595499958), PF_R(0.0), PF_VMF_KAPPA_MAX);
        pf_slope_stats s = pf_vmf_lobe_slope_stats(one.lobe[0].mu, one.lobe[0].kappa, base_var);
        long double ref, got;
        dir_deg(66.0 + 3.0 * i, 5.0, wo);
        dir_deg(30.0 + 5.0 * i, 185.0, wi);
        ref = (long double)pf_leadr_specular(V(wo), V(wi), s, PF_R(0.04));
        got = (long double)pf_vmf_sum_specular(mix_sum(&one, V(wo), V(wi), base_var, 0, PF_R(0.0)), V(wo), V(wi), PF_R(0.04));
        PF_CHECK(ref > 0.0L, "pf_leadr_specular is 0 at view %d", i);
        worst_leadr = fmaxl(worst_leadr, pf_test_rel_error(got, ref));
    }
    /* continuity through area_o = 0: views 0.06 deg either side of the mean plane (phi = 0) */
    {
        long double v[2][2];
        mean_plane_crossing(&m, base_var, 0, 0.06L, v);
        jump_mix = pf_test_rel_error(v[1][0], v[0][0]);
        jump_one = pf_test_rel_error(v[1][1], v[0][1]);
    }
    pf_test_note("%d views below the mean plane (nu_o in [%.2Lf, %.2Lf]) vs quadrature of the facing area: mixture form max "
                 "rel %.2Le, one-Gaussian form %.2Le; one sharp lobe vs pf_leadr_specular %.2Le; across area_o = 0 "
                 "(+/- 0.06 deg): rel jump %.2Le / %.2Le",
                 n, nu_lo, nu_hi, worst_mix, worst_one, worst_leadr, jump_mix, jump_one);
    PF_CHECK(n >= 10, "only %d views below the mean plane", n);
#ifdef PF_DOUBLE
    PF_CHECK(worst_mix <= 1e-9L && worst_one <= 1e-9L, "rel %.3Le %.3Le", worst_mix, worst_one);
#else
    PF_CHECK(worst_mix <= 1e-3L && worst_one <= 1e-4L, "rel %.3Le %.3Le", worst_mix, worst_one);
#endif
#ifdef PF_DOUBLE
    PF_CHECK(worst_leadr <= 1e-9L, "vs pf_leadr_specular: rel %.3Le", worst_leadr);
#else
    PF_CHECK(worst_leadr <= 1e-3L, "vs pf_leadr_specular: rel %.3Le", worst_leadr); /* its G1 form, nu_o >= -1.6 */
#endif
    PF_CHECK(jump_mix <= 0.01L && jump_one <= 0.01L, "jump across the mean plane %.3Le %.3Le", jump_mix, jump_one);
}

/* ------------------------------------------------------------------ light below the mesosurface
   pf_vmf_sum_specular(_mixture) with the LIGHT below the mixture's mean plane but above the
   macrosurface (area_i < 0 < wi.z) and the view above it: Smith's Lambda_i is infinite there,
   and the BRDF uses pf_leadr_specular's cap, Lambda_i' = max(P_i, wi.z) / wi.z - 1 (issue 15,
   bench/pictures.c; pfi_beckmann_light_lambda), so I = F D' / (4 (P_o + A_o Lambda_i')).
   Oracle: P_o and P_i by 1D quadrature (below_facing) of each lobe's Gaussian slopes, summed
   with the amplitudes (mixture form: the exact P_i), or of the sum's one Gaussian (P_i with
   A_i counted as 0, as pf_leadr_specular holds it below the mean plane); A_o in long double.
   Also: the value positive just below area_i = 0 (it jumps there from Smith's 0). */
static void test_specular_light_below_mean_plane(void)
{
    const pf_real base_var = PF_R(0.01);
    pf_vmf_mixture m;
    long double worst_mix = 0.0L, worst_one = 0.0L, jump_mix = 0.0L, jump_one = 0.0L;
    int i, j, n = 0, pos = 1;
    /* the lobes of test_specular_view_below_mean_plane: mean slope ~0.43 along x, so lights
       beyond ~67 deg at phi near 0 are below the mean plane */
    m.count = 2;
    m.lobe[0] = pf_vmf_lobe_make(PF_R(0.6), PF_R(-0.45), PF_R(0.0), PF_R(40.0));
    m.lobe[1] = pf_vmf_lobe_make(PF_R(0.4), PF_R(-0.3), PF_R(0.2), PF_R(80.0));
    for (i = 0; i < 5; ++i)
        for (j = 0; j < 4; ++j) {
            double wo[3], wi[3], h[3], hl;
            pf_vmf_sum s;
            pf_slope_stats st;
            long double po_mix = 0.0L, pi_mix = 0.0L, po_one, pi_one, f, hw, ref_mix, ref_one, got_mix, got_one;
            long double a_o, a_i, amp, wz, cap_mix, cap_one;
            int k;
            dir_deg(70.0 + 4.0 * i, -10.0 + 7.0 * j, wi);
            dir_deg(25.0 + 10.0 * j, 170.0 + 8.0 * i, wo);
            s = mix_sum(&m, V(wo), V(wi), base_var, 0, PF_R(0.0));
            st = pf_vmf_sum_stats(s);
            amp = (long double)s.amp;
            a_o = (long double)(pf_real)wo[2] - (long double)(pf_real)wo[0] * (long double)st.mean_x -
                  (long double)(pf_real)wo[1] * (long double)st.mean_y;
            a_i = (long double)(pf_real)wi[2] - (long double)(pf_real)wi[0] * (long double)st.mean_x -
                  (long double)(pf_real)wi[1] * (long double)st.mean_y;
            if (!(a_i < 0.0L) || !(a_o > 0.0L)) continue; /* only lights below the mean plane here */
            for (k = 0; k < m.count; ++k) {
                pf_slope_stats lk = pf_vmf_lobe_slope_stats(m.lobe[k].mu, m.lobe[k].kappa, base_var);
                po_mix += (long double)m.lobe[k].amp * below_facing_stats(lk, wo);
                pi_mix += (long double)m.lobe[k].amp * below_facing_stats(lk, wi);
            }
            po_mix /= amp;
            pi_mix /= amp;
            po_one = below_facing_stats(st, wo);
            { /* one Gaussian: P_i with A_i counted as 0 below the mean plane */
                long double wx = (long double)(pf_real)wi[0], wy = (long double)(pf_real)wi[1];
                long double v = wx * wx * (long double)st.var_x + wy * wy * (long double)st.var_y +
                                2.0L * wx * wy * (long double)st.cov_xy;
                pi_one = below_facing(a_i > 0.0L ? a_i : 0.0L, sqrtl(v > 0.0L ? v : 0.0L));
            }
            wz = (long double)(pf_real)wi[2];
            cap_mix = (pi_mix > wz ? pi_mix : wz) / wz - 1.0L;
            cap_one = (pi_one > wz ? pi_one : wz) / wz - 1.0L;
            for (k = 0; k < 3; ++k) h[k] = (double)(pf_real)wo[k] + (double)(pf_real)wi[k];
            hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            hw = (long double)((h[0] * (double)(pf_real)wi[0] + h[1] * (double)(pf_real)wi[1] + h[2] * (double)(pf_real)wi[2]) / hl);
            f = 0.04L + 0.96L * powl(1.0L - hw, 5.0L);
            ref_mix = f * (long double)s.ndf / (4.0L * amp * (po_mix + a_o * cap_mix));
            ref_one = f * (long double)s.ndf / (4.0L * amp * (po_one + a_o * cap_one));
            got_mix = (long double)pf_vmf_sum_specular_mixture(s, V(wo), V(wi), PF_R(0.04));
            got_one = (long double)pf_vmf_sum_specular(s, V(wo), V(wi), PF_R(0.04));
            if (!(got_mix > 0.0L) || !(got_one > 0.0L)) pos = 0;
            worst_mix = fmaxl(worst_mix, pf_test_rel_error(got_mix, ref_mix));
            worst_one = fmaxl(worst_one, pf_test_rel_error(got_one, ref_one));
            ++n;
        }
    /* continuity through area_i = 0 (phi = 0) */
    {
        long double v[2][2];
        mean_plane_crossing(&m, base_var, 1, 0.006L, v);
        jump_mix = pf_test_rel_error(v[1][0], v[0][0]);
        jump_one = pf_test_rel_error(v[1][1], v[0][1]);
        if (!(v[1][0] > 0.0L) || !(v[1][1] > 0.0L)) pos = 0;
    }
    pf_test_note("%d lights below the mean plane vs quadrature of the facing areas: mixture form max rel %.2Le, "
                 "one-Gaussian form %.2Le; across area_i = 0 (+/- 0.006 deg): rel jump %.2Le / %.2Le",
                 n, worst_mix, worst_one, jump_mix, jump_one);
    PF_CHECK(n >= 10, "only %d lights below the mean plane", n);
    PF_CHECK(pos, "a light below the mesosurface gave 0");
#ifdef PF_DOUBLE
    PF_CHECK(worst_mix <= 1e-9L && worst_one <= 1e-9L, "rel %.3Le %.3Le", worst_mix, worst_one);
#else
    PF_CHECK(worst_mix <= 1e-3L && worst_one <= 1e-4L, "rel %.3Le %.3Le", worst_mix, worst_one);
#endif
    /* the value jumps at area_i = 0 by design (Smith's 0 just above the mean plane, the facing
       facets' share just below: pfi_beckmann_light_lambda); only checked finite and positive */
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_normalization_quadrature);
    PF_TEST_RUN(test_one_minus_exp_neg_ulp);
    PF_TEST_RUN(test_mean_cosine_and_variance_quadrature);
    PF_TEST_RUN(test_kappa_inverses);
    PF_TEST_RUN(test_lobe_eval_large_kappa);
    PF_TEST_RUN(test_convolution_rule_error);
    PF_TEST_RUN(test_mixture_projected_area_quadrature);
    PF_TEST_RUN(test_mixture_ndf_vmf_convolution);
    PF_TEST_RUN(test_mixture_lambda_quadrature);
    PF_TEST_RUN(test_specular_one_lobe_is_leadr);
    PF_TEST_RUN(test_specular_vmf_form_vs_integration);
    PF_TEST_RUN(test_specular_view_below_mean_plane);
    PF_TEST_RUN(test_specular_light_below_mean_plane);
    PF_TEST_RUN(test_masking_vs_microsurface);
    PF_TEST_RUN(test_em_recovers_mixture);
    PF_TEST_RUN(test_em_deterministic_and_weighted);
    PF_TEST_RUN(test_pyramid_levels);
    PF_TEST_RUN(test_fit_degenerate);
    PF_TEST_RUN(test_lobe_make_nan);
    PF_TEST_RUN(edge_evaluators_finite);
    PF_TEST_RUN(test_downsample_dense_oracle);
    PF_TEST_RUN(test_downsample_beats_box);
    PF_TEST_RUN(test_downsample_bad_input);
    PF_TEST_RUN(edge_downsample_finite);
    PF_TEST_RUN(test_scale_flat_patch_is_base);
    PF_TEST_RUN(test_scale_reciprocity);
    PF_TEST_RUN(test_scale_visibility_wall);
    PF_TEST_RUN(test_scale_vs_microsurface_reference);
    PF_TEST_RUN(test_scale_factor_separable);
    PF_TEST_RUN(test_scale_factor_shrink);
    PF_TEST_RUN(test_scale_lookup);
    PF_TEST_RUN(test_scale_bad_input_guarded);
    return PF_TEST_END();
}

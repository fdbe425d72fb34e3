/* test_height.c - tests of include/pf_height.h against long double quadrature and Monte Carlo.

   Truth is never the formula under test: the closed forms of Heitz et al. 2014 (eqs. 3, 12) are
   checked against the integrals over heights they come from; mu_d and sigma_d (eqs. 15-17)
   against adaptive quadrature of D_h (tests/reference/pf_oracle.h), and for integer Lambda against the
   expected maximum of Lambda + 1 normals computed from its own (CDF) integral and the known
   values 1/sqrt(pi), 3/(2 sqrt(pi)); the Gaussian colour-map filters against quadrature of
   C(v) N(v) over v; the transfer-function moments against Monte Carlo with a fixed seed. The
   same bodies run in float, double, C++ and under sanitizers; edge_* tests also run under
   -ffast-math. */
/* MAP_ANONYMOUS and MAP_NORESERVE for pf_test_guarded_alloc under -std=c99 (before any include) */
#if defined(__unix__) && !defined(_DEFAULT_SOURCE)
#  define _DEFAULT_SOURCE 1
#endif
#include <limits.h>
#include "pf_height.h"
#include "pf_oracle.h"
#include "pf_test.h"

static const long double log_sqrt_2pil = 0.918938533204672741780329736405617640L;

/* ------------------------------------------------------------------ references */

/* log Phi(z) in long double: log1p of the upper tail above 0, log of the lower tail down to
   -37 (where the oracle's cdf is accurate), and the asymptotic series of Mills' ratio below
   (12 terms: truncation < 1e-25 there). */
static long double log_cdf_ref(long double z)
{
    if (z >= 0.0L) return log1pl(-pf_oracle_normal_sf(z));
    if (z >= -37.0L) return logl(pf_oracle_normal_cdf(z));
    {
        long double s = 1.0L / (z * z), term = 1.0L, m = 0.0L;
        int k;
        for (k = 1; k <= 12; k++) {
            term *= -(long double)(2 * k - 1) * s;
            m += term;
        }
        return -0.5L * z * z - logl(-z) - log_sqrt_2pil + log1pl(m);
    }
}

/* The visible height density D(z) = (L + 1) phi(z) Phi(z)^L (eq. 15), times (z - shift)^k. */
typedef struct dh_ctx {
    long double lambda, shift;
    int power;
} dh_ctx;

static long double dh_integrand(long double z, void *ctx)
{
    const dh_ctx *c = (const dh_ctx *)ctx;
    long double lp = c->lambda > 0.0L ? c->lambda * log_cdf_ref(z) : 0.0L;
    long double v = expl(log1pl(c->lambda) - 0.5L * z * z - log_sqrt_2pil + lp);
    long double d = z - c->shift;
    return c->power == 0 ? v : (c->power == 1 ? v * d : v * d * d);
}

typedef struct dh_ref {
    long double mass, mean, dev;
    int ok;
} dh_ref;

/* mass, mean and central deviation of D by adaptive quadrature, with breakpoints around the
   peak (near sqrt(2 log(L + 1)), width ~ 1/that). */
static dh_ref visible_height_ref(long double lambda)
{
    dh_ctx c;
    dh_ref r;
    pf_oracle_result q0, q1, q2;
    long double pts[13], centre = lambda > 1.0L ? sqrtl(2.0L * log1pl(lambda)) : 0.0L;
    long double w = centre > 1.5L ? 1.5L / centre : 1.0L;
    static const int offs[13] = { -12, -8, -5, -3, -2, -1, 0, 1, 2, 3, 5, 8, 12 };
    int i;
    for (i = 0; i < 13; i++) pts[i] = centre + (long double)offs[i] * w;
    c.lambda = lambda;
    c.shift = 0.0L;
    c.power = 0;
    q0 = pf_oracle_integrate_points(dh_integrand, &c, -HUGE_VALL, HUGE_VALL, pts, 13, 0.0L, 1e-17L,
                                    PF_ORACLE_MAX_INTERVALS);
    c.power = 1;
    q1 = pf_oracle_integrate_points(dh_integrand, &c, -HUGE_VALL, HUGE_VALL, pts, 13, 1e-19L, 1e-17L,
                                    PF_ORACLE_MAX_INTERVALS);
    r.mass = q0.value;
    r.mean = q1.value / q0.value;
    c.shift = r.mean;
    c.power = 2;
    q2 = pf_oracle_integrate_points(dh_integrand, &c, -HUGE_VALL, HUGE_VALL, pts, 13, 0.0L, 1e-17L,
                                    PF_ORACLE_MAX_INTERVALS);
    r.dev = sqrtl(q2.value / q0.value);
    r.ok = (q0.status == PF_ORACLE_OK || q0.status == PF_ORACLE_ROUNDOFF) &&
           (q1.status == PF_ORACLE_OK || q1.status == PF_ORACLE_ROUNDOFF) &&
           (q2.status == PF_ORACLE_OK || q2.status == PF_ORACLE_ROUNDOFF);
    return r;
}

/* A piecewise-linear map (constant beyond the ends), long double. */
#define MAXK 24
typedef struct plmap {
    long double x[MAXK], c[MAXK];
    int n;
    long double mean, sigma;
} plmap;

static long double plmap_value(const plmap *m, long double v)
{
    int k;
    if (v < m->x[0]) return m->c[0];
    for (k = 0; k + 1 < m->n; k++)
        if (v < m->x[k + 1]) {
            long double w = m->x[k + 1] - m->x[k];
            return w > 0.0L ? m->c[k] + (m->c[k + 1] - m->c[k]) * (v - m->x[k]) / w : m->c[k + 1];
        }
    return m->c[m->n - 1];
}

static long double gauss_weight(long double v, long double mean, long double sigma)
{
    long double t = (v - mean) / sigma;
    return expl(-0.5L * t * t - log_sqrt_2pil) / sigma;
}

/* integrand selector for plmap: 0 value, 1 value^2, 2 derivative, 3 derivative^2 */
typedef struct plmap_job {
    const plmap *m;
    int what;
} plmap_job;

/* integrated in the standardized variable t, v = mean + sigma t, so the Gaussian has unit
   scale whatever sigma (the oracle's maps of infinite intervals have unit scale) */
static long double plmap_integrand(long double t, void *ctx)
{
    const plmap_job *j = (const plmap_job *)ctx;
    const plmap *m = j->m;
    long double v = m->mean + m->sigma * t;
    long double g = 0.0L;
    if (j->what <= 1) {
        g = plmap_value(m, v);
        if (j->what == 1) g *= g;
    } else {
        int k;
        for (k = 0; k + 1 < m->n; k++)
            if (v >= m->x[k] && v < m->x[k + 1]) g = (m->c[k + 1] - m->c[k]) / (m->x[k + 1] - m->x[k]);
        if (j->what == 3) g *= g;
    }
    return g * expl(-0.5L * t * t - log_sqrt_2pil);
}

/* Breakpoints of the standardized integrals: knots far out in the tails are clipped to +-40
   (the integrand is 0 to long double precision there), and a fixed grid of points every 2.5
   over [-40, 40] is added, so that no single rule spans a tail and the peak at once (a rule
   whose nodes all miss the peak would report convergence on 0). */
static long double clip40(long double t) { return t < -40.0L ? -40.0L : (t > 40.0L ? 40.0L : t); }

static long double plmap_expect(const plmap *m, int what)
{
    plmap_job j;
    long double pts[MAXK + 33];
    int k;
    pf_oracle_result r;
    j.m = m;
    j.what = what;
    for (k = 0; k < m->n; k++) pts[k] = clip40((m->x[k] - m->mean) / m->sigma);
    for (k = 0; k < 33; k++) pts[m->n + k] = (long double)(k - 16) * 2.5L;
    r = pf_oracle_integrate_points(plmap_integrand, &j, -HUGE_VALL, HUGE_VALL, pts, m->n + 33, 1e-20L,
                                   1e-18L, PF_ORACLE_MAX_INTERVALS);
    return r.value;
}

/* A random map: n knots on a random span, some jumps (equal knots), values in [0, 1]. The
   knots are rounded to pf_real first so the library and the reference see the same map. */
static plmap random_map(pf_test_rng *rng, int jumps, double min_gap)
{
    plmap m;
    int k;
    long double x = (long double)pf_test_uniform(rng, -2.0, 1.0);
    m.n = 2 + (int)(pf_test_uniform(rng, 0.0, 1.0) * 14.0);
    for (k = 0; k < m.n; k++) {
        if (k > 0 && !(jumps && pf_test_uniform(rng, 0.0, 1.0) < 0.15))
            x += (long double)pf_test_log_uniform(rng, min_gap, 1.0);
        m.x[k] = (long double)(pf_real)x;
        m.c[k] = (long double)(pf_real)pf_test_uniform(rng, 0.0, 1.0);
    }
    m.mean = 0.0L;
    m.sigma = 1.0L;
    return m;
}

static void map_to_real(const plmap *m, pf_real *x, pf_real *c)
{
    int k;
    for (k = 0; k < m->n; k++) {
        x[k] = (pf_real)m->x[k];
        c[k] = (pf_real)m->c[k];
    }
}

/* ------------------------------------------------------------------ height CDF, visibility */

static void test_log_cdf_both_tails(void)
{
    pf_test_max cdf = pf_test_max_init(), lg = pf_test_max_init();
    int i;
    /* z from -1e4 to 40: log-spaced on both sides of 0 plus a uniform band */
    for (i = 0; i <= 4000; i++) {
        long double zl;
        pf_real z;
        long double ref, got, err;
        if (i < 1500) zl = -powl(10.0L, 4.0L - 6.0L * (long double)i / 1500.0L);
        else if (i < 2500) zl = -8.0L + 16.0L * (long double)(i - 1500) / 1000.0L;
        else zl = powl(10.0L, -2.0L + 3.6L * (long double)(i - 2500) / 1500.0L);
        z = (pf_real)zl;
        zl = (long double)z;
        ref = log_cdf_ref(zl);
        got = (long double)pf_height_log_cdf(z);
        /* conditioning: log Phi moves by ~|z| |dz| phi/Phi for an input change dz; one rounding
           of z^2 / 2 or of z / sqrt 2 is eps (1 + z^2) relative to Phi */
        err = fabsl(got - ref) / (PF_TEST_EPS * (fabsl(ref) + 1e-30L) * (1.0L + zl * zl));
        if (fabsl(ref) < 1e-300L) err = fabsl(got - ref);
        pf_test_max_update(&lg, err, zl);
        if (zl > -37.0L) {
            long double r2 = pf_oracle_normal_cdf(zl);
            long double g2 = (long double)pf_height_cdf(z);
            if (r2 >= (long double)PF_REAL_MIN)
                pf_test_max_update(&cdf, fabsl(g2 - r2) / r2 / (PF_TEST_EPS * (1.0L + zl * zl)), zl);
        }
    }
    pf_test_note("log Phi max %.2Lg eps|logPhi|(1+z^2) at z=%.4Lg", lg.err, lg.at);
    pf_test_note("Phi max %.2Lg eps(1+z^2) rel at z=%.4Lg", cdf.err, cdf.at);
    PF_CHECK(lg.err <= 4.0L, "log Phi %Lg at %Lg", lg.err, lg.at);
    PF_CHECK(cdf.err <= 4.0L, "Phi %Lg at %Lg", cdf.err, cdf.at);
}

static void test_visibility_power(void)
{
    static const double lambdas[] = { 1e-6, 0.01, 0.3, 1.0, 3.7, 20.0, 150.0, 1000.0, 1e5 };
    pf_test_max m = pf_test_max_init();
    size_t i;
    int j;
    for (i = 0; i < sizeof lambdas / sizeof lambdas[0]; i++) {
        pf_real l = (pf_real)lambdas[i];
        for (j = 0; j <= 400; j++) {
            pf_real z = (pf_real)(-30.0 + 40.0 * j / 400.0);
            long double zl = (long double)z, ll = (long double)l;
            long double lp = log_cdf_ref(zl);
            long double ref = expl(ll * lp);
            long double got = (long double)pf_height_visibility(z, l);
            /* conditioning of exp(L log Phi): |log V| + L z^2 (a rounding of z enters log Phi
               scaled by z phi/Phi <~ z^2 + 1) */
            long double cond = 1.0L + fabsl(ll * lp) + ll * (1.0L + zl * zl);
            if (ref < (long double)PF_REAL_MIN * 1e6L) continue;
            pf_test_max_update(&m, fabsl(got - ref) / ref / (PF_TEST_EPS * cond), zl);
        }
    }
    pf_test_note("V max rel error %.2Lg eps x (1 + |log V| + L(1+z^2)) at z=%.3Lg", m.err, m.at);
    PF_CHECK(m.err <= 4.0L, "%Lg at %Lg", m.err, m.at);
}

/* ------------------------------------------------------------------ closed forms */
typedef struct cf_ctx {
    long double lambda, pw;
} cf_ctx;

/* integral of Phi^lambda phi (times Phi^pw) */
static long double cf_integrand(long double z, void *ctx)
{
    const cf_ctx *c = (const cf_ctx *)ctx;
    long double lp = log_cdf_ref(z);
    return expl((c->lambda + c->pw) * lp - 0.5L * z * z - log_sqrt_2pil);
}

static long double cf_integral(long double lambda, long double pw)
{
    cf_ctx c;
    long double centre = lambda > 1.0L ? sqrtl(2.0L * log1pl(lambda)) : 0.0L;
    pf_oracle_result r;
    c.lambda = lambda;
    c.pw = pw;
    r = pf_oracle_integrate_points(cf_integrand, &c, -HUGE_VALL, HUGE_VALL, &centre, 1, 0.0L, 1e-18L,
                                   PF_ORACLE_MAX_INTERVALS);
    return r.value;
}

static void test_closed_forms_quadrature(void)
{
    static const double ls[] = { 0.0, 1e-3, 0.2, 1.0, 2.5, 17.0, 300.0, 1000.0 };
    pf_test_max mv = pf_test_max_init(), jv = pf_test_max_init(), am = pf_test_max_init();
    size_t i, j;
    for (i = 0; i < sizeof ls / sizeof ls[0]; i++)
        for (j = 0; j < sizeof ls / sizeof ls[0]; j++) {
            pf_real lo = (pf_real)ls[i], li = (pf_real)ls[j];
            long double lol = (long double)lo, lil = (long double)li;
            long double eo = cf_integral(lol, 0.0L), eoi = cf_integral(lol + lil, 0.0L);
            long double eoi1 = cf_integral(lol + lil, 1.0L);
            /* eq. 12: E[V_o V_i] / E[V_o]; joint moment E[V_o V_i]; eq. 3 with a0 = 0.25,
               amplitude 0.5: a0 + 0.5 E[P V_o V_i] / E[V_o V_i] */
            pf_test_max_update(&mv, pf_test_rel_error((long double)pf_height_mean_visibility(lo, li), eoi / eo),
                               lol * 1e4L + lil);
            pf_test_max_update(&jv, pf_test_rel_error((long double)pf_height_joint_visibility(lo, li), eoi),
                               lol * 1e4L + lil);
            pf_test_max_update(&am, pf_test_rel_error((long double)pf_height_attribute_mean(PF_R(0.25), PF_R(0.5), lo, li),
                                                      0.25L + 0.5L * eoi1 / eoi), lol * 1e4L + lil);
        }
    pf_test_note("eq.12 mean visibility max rel %.2Lg; joint %.2Lg; eq.3 attribute mean %.2Lg", mv.err, jv.err,
                 am.err);
    PF_CHECK(mv.err <= 8.0L * PF_TEST_EPS, "%Lg", mv.err);
    PF_CHECK(jv.err <= 8.0L * PF_TEST_EPS, "%Lg", jv.err);
    PF_CHECK(am.err <= 8.0L * PF_TEST_EPS, "%Lg", am.err);
}

/* Lambda's own definition: integral of V(z, Lambda) p_h(z) dz = 1 / (1 + Lambda) = G1, with
   Lambda from pf_smith.h's Beckmann Lambda of nu (the height model and the slope model agree). */
static void test_visibility_average_is_g1(void)
{
    pf_test_max m = pf_test_max_init();
    int i;
    for (i = 0; i <= 24; i++) {
        pf_real nu = (pf_real)(0.05 + 0.1 * i);
        pf_real lam = pf_lambda_beckmann(nu);
        long double avg = cf_integral((long double)lam, 0.0L);
        pf_test_max_update(&m, pf_test_rel_error(avg, (long double)pf_g1_beckmann(nu)), (long double)nu);
    }
    pf_test_note("integral of Phi^Lambda p_h vs pf_g1_beckmann: max rel %.2Lg at nu=%.3Lg", m.err, m.at);
    PF_CHECK(m.err <= 1e-6L || m.err <= 16.0L * PF_TEST_EPS, "%Lg", m.err);
}

/* ------------------------------------------------------------------ visible height distribution */
#define NVH 61
static long double vh_lambda(int i) /* 0, then log-spaced 1e-6 .. 1e30 (the first 40 up to 1e3) */
{
    if (i == 0) return 0.0L;
    if (i <= 40) return powl(10.0L, -6.0L + 9.0L * (long double)(i - 1) / 39.0L);
    return powl(10.0L, 3.0L + 27.0L * (long double)(i - 40) / (long double)(NVH - 41));
}

static void test_visible_height_exact_tier(void)
{
    pf_test_max mu = pf_test_max_init(), mu_abs = pf_test_max_init(), sd = pf_test_max_init();
    int i, bad = 0;
    for (i = 0; i < NVH; i++) {
        pf_real l = (pf_real)vh_lambda(i);
        dh_ref r = visible_height_ref((long double)l);
        pf_height_dist d = pf_visible_height_exact(l);
        long double emu = fabsl((long double)d.mean - r.mean);
        if (!r.ok || fabsl(r.mass - 1.0L) > 1e-15L) bad++;
        if (r.mean >= 0.1L) pf_test_max_update(&mu, emu / r.mean, (long double)l);
        else pf_test_max_update(&mu_abs, emu, (long double)l);
        pf_test_max_update(&sd, pf_test_rel_error((long double)d.dev, r.dev), (long double)l);
    }
    pf_test_note("exact tier: mu_d max rel %.2Lg at L=%.3Lg (mu_d < 0.1: abs %.2Lg sigma_h), sigma_d rel %.2Lg at L=%.3Lg",
                 mu.err, mu.at, mu_abs.err, sd.err, sd.at);
    PF_CHECK(mu_abs.err <= 1e-9L + 8.0L * PF_TEST_EPS, "mu abs %Lg at %Lg", mu_abs.err, mu_abs.at);
    PF_CHECK(bad == 0, "%d oracle failures (or mass != 1)", bad);
    PF_CHECK(mu.err <= 1e-8L + 64.0L * PF_TEST_EPS, "mu %Lg at %Lg", mu.err, mu.at);
    PF_CHECK(sd.err <= 5e-8L + 64.0L * PF_TEST_EPS, "sigma %Lg at %Lg", sd.err, sd.at);
}

/* The fitted tiers over L in [0, 1000] (the range) and beyond (ours only). mu_d: the
   relative error, with an absolute floor (|error| / max(mu_d, 0.2)) where mu_d vanishes. */
static void test_visible_height_fits(void)
{
    pf_test_max our_mu = pf_test_max_init(), our_sd = pf_test_max_init();
    pf_test_max our_mu_abs = pf_test_max_init(), our_mu_all = pf_test_max_init(), our_sd_all = pf_test_max_init();
    pf_test_max pub_mu = pf_test_max_init(), pub_sd = pf_test_max_init(), pub_mu_abs = pf_test_max_init();
    int i;
    for (i = 0; i < NVH; i++) {
        pf_real l = (pf_real)vh_lambda(i);
        long double ll = (long double)l;
        dh_ref r = visible_height_ref(ll);
        pf_height_dist o = pf_visible_height(l), p = pf_visible_height_published(l);
        long double eom = fabsl((long double)o.mean - r.mean), eos = pf_test_rel_error((long double)o.dev, r.dev);
        long double epm = fabsl((long double)p.mean - r.mean), eps_ = pf_test_rel_error((long double)p.dev, r.dev);
        long double rm = r.mean > 1e-6L ? r.mean : 1e-6L;
        pf_test_max_update(&our_mu_all, eom / rm, ll);
        pf_test_max_update(&our_sd_all, eos, ll);
        if (ll <= 1000.0L) {
            pf_test_max_update(&our_mu, eom / rm, ll);
            pf_test_max_update(&our_sd, eos, ll);
            pf_test_max_update(&our_mu_abs, eom, ll);
            pf_test_max_update(&pub_mu, epm / rm, ll);
            pf_test_max_update(&pub_sd, eps_, ll);
            pf_test_max_update(&pub_mu_abs, epm, ll);
        }
    }
    pf_test_note("L<=1000: ours mu rel %.2Lg (abs %.2Lg sigma_h), sigma rel %.2Lg; published mu rel %.2Lg "
                 "at L=%.3Lg (abs %.2Lg at L=%.3Lg), sigma rel %.2Lg at L=%.3Lg; ours to 1e30: mu %.2Lg, sigma %.2Lg",
                 our_mu.err, our_mu_abs.err, our_sd.err, pub_mu.err, pub_mu.at, pub_mu_abs.err, pub_mu_abs.at,
                 pub_sd.err, pub_sd.at, our_mu_all.err, our_sd_all.err);
    /* published bounds: ours at 1e-4 (mu) / 1e-4 (sigma) plus float rounding, against the
       issue's goal of 1e-2 relative and 2e-3 sigma_h absolute */
    PF_CHECK(our_mu.err <= 1.2e-5L + 64.0L * PF_TEST_EPS, "ours mu %Lg at %Lg", our_mu.err, our_mu.at);
    PF_CHECK(our_sd.err <= 8e-5L + 64.0L * PF_TEST_EPS, "ours sigma %Lg at %Lg", our_sd.err, our_sd.at);
    PF_CHECK(our_mu_abs.err <= 2e-3L, "ours mu abs %Lg", our_mu_abs.err);
    PF_CHECK(our_mu_all.err <= 1.2e-5L + 64.0L * PF_TEST_EPS && our_sd_all.err <= 8e-5L + 64.0L * PF_TEST_EPS,
             "ours beyond 1000: %Lg %Lg", our_mu_all.err, our_sd_all.err);
    /* what the issue says about the published fits: off by ~0.13 sigma_h near L = 0.5,
       ~20% at L = 1; we assert they are what we document (so the docs cannot drift) */
    PF_CHECK(pub_mu_abs.err >= 0.1L && pub_mu_abs.err <= 0.2L, "published mu abs %Lg", pub_mu_abs.err);
    PF_CHECK(pub_mu.err >= 100.0L * our_mu.err, "published %Lg vs ours %Lg", pub_mu.err, our_mu.err);
    PF_CHECK(pub_sd.err >= 100.0L * our_sd.err, "published %Lg vs ours %Lg", pub_sd.err, our_sd.err);
}

/* The slope of mu_d at L = 0: the published fit has 0.39 * 4.75 = 1.85, ours and the truth
   ~0.903 (d mu_d / dL at 0 = integral of z phi log Phi). */
static void test_visible_height_slope_at_zero(void)
{
    long double h = 1e-4L;
    dh_ref r = visible_height_ref(h);
    long double truth = r.mean / h;
    long double ours = (long double)pf_visible_height((pf_real)h).mean / (long double)(pf_real)h;
    long double pub = (long double)pf_visible_height_published((pf_real)h).mean / (long double)(pf_real)h;
    pf_test_note("d mu_d/dL at 0: truth %.5Lg, ours %.5Lg, published %.4Lg", truth, ours, pub);
    PF_CHECK(fabsl(ours - truth) <= 1e-3L * truth, "ours %Lg truth %Lg", ours, truth);
    PF_CHECK(pub > 1.9L * truth, "published %Lg truth %Lg", pub, truth);
}

/* The published fit's documented range (issue 14): over 0 <= L <= 1900, |mu_d error| <= 0.131
   sigma_h and |sigma_d error| <= 5.33% (measured 0.1309 at L = 0.564 and 5.32% at L = 25.8, the
   same in float and double); beyond, both errors grow monotonically (mu_d up, sigma_d down)
   and reach the values the header quotes. Dense grid: 40 points per decade of L. */
static void test_visible_height_published_range(void)
{
    pf_test_max mu = pf_test_max_init(), sd = pf_test_max_init();
    long double prev_mu = -1.0L, prev_sd = 1.0L, at1e4[2] = { 0.0L, 0.0L }, at1e9[2] = { 0.0L, 0.0L };
    long double at1e30[2] = { 0.0L, 0.0L }, first_mu_out = 0.0L, first_sd_out = 0.0L;
    int i, bad = 0, nonmono = 0, n = 0;
    for (i = -1; i <= 40 * 36; i++) { /* L = 0, then 10^-6 .. 10^30 */
        long double lt = i < 0 ? 0.0L : powl(10.0L, -6.0L + (long double)i / 40.0L);
        pf_real l = (pf_real)lt;
        long double ll = (long double)l;
        dh_ref r = visible_height_ref(ll);
        pf_height_dist p = pf_visible_height_published(l);
        long double em = (long double)p.mean - r.mean, es = ((long double)p.dev - r.dev) / r.dev;
        if (!r.ok) bad++;
        if (ll <= 1900.0L) {
            pf_test_max_update(&mu, fabsl(em), ll);
            pf_test_max_update(&sd, fabsl(es), ll);
            n++;
        } else {
            if (em < prev_mu || es > prev_sd) nonmono++;
            prev_mu = em;
            prev_sd = es;
            if (first_mu_out == 0.0L && em > 0.131L) first_mu_out = ll;
            if (first_sd_out == 0.0L && -es > 0.0533L) first_sd_out = ll;
        }
        if (i == 400) { at1e4[0] = em; at1e4[1] = es; }
        if (i == 600) { at1e9[0] = em; at1e9[1] = es; }
        if (i == 40 * 36) { at1e30[0] = em; at1e30[1] = es; }
    }
    pf_test_note("published, %d L in [0,1900]: |mu_d err| max %.4Lf sigma_h at L=%.3Lg, |sigma_d err| max %.4Lf at "
                 "L=%.3Lg; beyond: mu err > 0.131 from L=%.4Lg, sigma err < -5.33%% from L=%.4Lg; at 1e4 (%+.3Lf, %+.4Lf), "
                 "1e9 (%+.3Lf, %+.4Lf), 1e30 (%+.3Lf, %+.4Lf)",
                 n, mu.err, mu.at, sd.err, sd.at, first_mu_out, first_sd_out, at1e4[0], at1e4[1], at1e9[0], at1e9[1],
                 at1e30[0], at1e30[1]);
    PF_CHECK(bad == 0, "%d oracle failures", bad);
    PF_CHECK(mu.err <= 0.131L && mu.err >= 0.130L, "mu_d error %Lg at %Lg (documented 0.131)", mu.err, mu.at);
    PF_CHECK(sd.err <= 0.0533L && sd.err >= 0.053L, "sigma_d error %Lg at %Lg (documented 5.33%%)", sd.err, sd.at);
    PF_CHECK(nonmono == 0, "%d non-monotone errors beyond L = 1900", nonmono);
    PF_CHECK(first_mu_out > 1900.0L && first_mu_out < 2000.0L, "mu_d error passes 0.131 at %Lg", first_mu_out);
    PF_CHECK(first_sd_out > 1.8e4L && first_sd_out < 2.0e4L, "sigma_d error passes -5.33%% at %Lg", first_sd_out);
    PF_CHECK(fabsl(at1e4[0] - 0.348L) < 0.005L && fabsl(at1e4[1] + 0.0405L) < 0.001L, "at 1e4: %Lg %Lg", at1e4[0], at1e4[1]);
    PF_CHECK(fabsl(at1e9[0] - 2.602L) < 0.005L && fabsl(at1e9[1] + 0.2293L) < 0.001L, "at 1e9: %Lg %Lg", at1e9[0], at1e9[1]);
    PF_CHECK(fabsl(at1e30[0] - 16.03L) < 0.01L && fabsl(at1e30[1] + 0.5213L) < 0.001L, "at 1e30: %Lg %Lg", at1e30[0],
             at1e30[1]);
}

/* E[max of n standard normals] from its own definition, the CDF integral
   E[M] = integral_0^inf (1 - Phi^n) dz - integral_-inf^0 Phi^n dz. */
typedef struct maxn_ctx {
    int n;
    int upper;
} maxn_ctx;

static long double maxn_integrand(long double z, void *ctx)
{
    const maxn_ctx *c = (const maxn_ctx *)ctx;
    long double p = powl(pf_oracle_normal_cdf(z), (long double)c->n);
    return c->upper ? -expm1l((long double)c->n * log1pl(-pf_oracle_normal_sf(z))) : p;
}

static long double expected_max_ref(int n)
{
    maxn_ctx c;
    pf_oracle_result a, b;
    c.n = n;
    c.upper = 1;
    a = pf_oracle_integrate(maxn_integrand, &c, 0.0L, HUGE_VALL, 0.0L, 1e-18L, PF_ORACLE_MAX_INTERVALS);
    c.upper = 0;
    b = pf_oracle_integrate(maxn_integrand, &c, -HUGE_VALL, 0.0L, 0.0L, 1e-18L, PF_ORACLE_MAX_INTERVALS);
    return a.value - b.value;
}

static void test_integer_lambda_expected_max(void)
{
    pf_test_max ex = pf_test_max_init(), fit = pf_test_max_init();
    long double known2 = 1.0L / sqrtl(PF_TEST_PI), known3 = 1.5L / sqrtl(PF_TEST_PI);
    long double cdf2 = expected_max_ref(2), cdf3 = expected_max_ref(3);
    int n;
    for (n = 2; n <= 64; n++) {
        long double ref = expected_max_ref(n);
        pf_real l = (pf_real)(n - 1);
        pf_test_max_update(&ex, pf_test_rel_error((long double)pf_visible_height_exact(l).mean, ref), (long double)n);
        pf_test_max_update(&fit, pf_test_rel_error((long double)pf_visible_height(l).mean, ref), (long double)n);
    }
    /* and the variance of the max of 2: 1 - 1/pi */
    {
        long double sd2 = sqrtl(1.0L - 1.0L / PF_TEST_PI);
        long double e = pf_test_rel_error((long double)pf_visible_height_exact(PF_R(1.0)).dev, sd2);
        pf_test_note("E[max of L+1] (L=1..63) exact tier %.2Lg, ours %.2Lg; CDF integral vs 1/sqrt(pi) %.1Lg, "
                     "3/(2 sqrt(pi)) %.1Lg; sd of max of 2 vs sqrt(1-1/pi) %.2Lg",
                     ex.err, fit.err, fabsl(cdf2 - known2) / known2, fabsl(cdf3 - known3) / known3, e);
        PF_CHECK(e <= 5e-8L + 64.0L * PF_TEST_EPS, "%Lg", e);
    }
    PF_CHECK(fabsl(cdf2 - known2) <= 1e-17L && fabsl(cdf3 - known3) <= 1e-17L, "%Lg %Lg", cdf2, cdf3);
    PF_CHECK(ex.err <= 1e-8L + 64.0L * PF_TEST_EPS, "exact %Lg at n=%Lg", ex.err, ex.at);
    PF_CHECK(fit.err <= 1.2e-5L + 64.0L * PF_TEST_EPS, "ours %Lg at n=%Lg", fit.err, fit.at);
}

/* ------------------------------------------------------------------ colour maps */

static void test_colormap_quadrature(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x71u);
    pf_test_max cpu = pf_test_max_init(), seg = pf_test_max_init(), delta = pf_test_max_init();
    int trial;
    for (trial = 0; trial < 300; trial++) {
        plmap m = random_map(&rng, 1, 0.01);
        pf_real x[MAXK] = { PF_R(0.0) }, c[MAXK] = { PF_R(0.0) }, out[1] = { PF_R(0.0) }, acc;
        long double ref, span = m.x[m.n - 1] - m.x[0] + 1.0L;
        int k, s;
        map_to_real(&m, x, c);
        for (s = 0; s < 6; s++) {
            pf_real mean = (pf_real)pf_test_uniform(&rng, (double)(m.x[0] - span), (double)(m.x[m.n - 1] + span));
            pf_real sigma = s == 0 ? PF_R(0.0) : (pf_real)pf_test_log_uniform(&rng, 1e-4, 10.0);
            m.mean = (long double)mean;
            m.sigma = (long double)sigma;
            pf_colormap_filter(x, c, m.n, 1, mean, sigma, out);
            acc = c[0] * pf_gauss_cdf(x[0], mean, sigma) + c[m.n - 1] * pf_gauss_step(x[m.n - 1], mean, sigma);
            for (k = 0; k + 1 < m.n; k++) {
                pf_vec2 w = pf_gauss_segment_weights(x[k], x[k + 1], mean, sigma);
                acc += w.x * c[k] + w.y * c[k + 1];
            }
            if (s == 0) {
                /* unfiltered: the map value (at a knot exactly, a continuous map's value) */
                ref = plmap_value(&m, m.mean);
                pf_test_max_update(&delta, fabsl((long double)out[0] - ref) / PF_TEST_EPS, m.mean);
                continue;
            }
            ref = plmap_expect(&m, 0);
            pf_test_max_update(&cpu, fabsl((long double)out[0] - ref) / PF_TEST_EPS, m.sigma);
            pf_test_max_update(&seg, fabsl((long double)acc - ref) / PF_TEST_EPS, m.sigma);
        }
    }
    pf_test_note("300 random maps (<= 15 knots, jumps), 1500 (mean, sigma in [1e-4, 10]): CPU max abs %.2Lg eps, "
                 "per-segment sum %.2Lg eps; sigma = 0 vs map value %.2Lg eps", cpu.err, seg.err, delta.err);
    PF_CHECK(cpu.err <= 8.0L && seg.err <= 8.0L, "cpu %Lg at sigma %Lg, seg %Lg", cpu.err, cpu.at, seg.err);
    PF_CHECK(delta.err <= 4.0L, "delta %Lg at %Lg", delta.err, delta.at);
}

static long double step_smooth_integrand(long double t, void *ctx)
{
    const plmap *m = (const plmap *)ctx; /* x[0] = e0, x[1] = e1, c[0] = kind (0 step, 1 smooth) */
    long double v = m->mean + m->sigma * t, s;
    if (m->c[0] == 0.0L) s = v >= m->x[0] ? 1.0L : 0.0L;
    else {
        long double u = (v - m->x[0]) / (m->x[1] - m->x[0]);
        u = u < 0.0L ? 0.0L : (u > 1.0L ? 1.0L : u);
        s = u * u * (3.0L - 2.0L * u);
    }
    return s * expl(-0.5L * t * t - log_sqrt_2pil);
}

static void test_step_smoothstep_quadrature(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x5173u);
    pf_test_max st = pf_test_max_init(), sm = pf_test_max_init(), sm0 = pf_test_max_init();
    int trial, i;
    for (trial = 0; trial < 2000; trial++) {
        plmap m;
        pf_real e0 = (pf_real)pf_test_uniform(&rng, -1.0, 1.0);
        pf_real e1 = e0 + (pf_real)pf_test_log_uniform(&rng, 1e-4, 3.0);
        pf_real sigma = (pf_real)pf_test_log_uniform(&rng, 1e-4, 10.0);
        pf_real mean = (pf_real)pf_test_uniform(&rng, -3.0, 3.0);
        long double pts[35];
        pf_oracle_result r;
        m.x[0] = (long double)e0;
        m.x[1] = (long double)e1;
        m.mean = (long double)mean;
        m.sigma = (long double)sigma;
        pts[0] = clip40((m.x[0] - m.mean) / m.sigma);
        pts[1] = clip40((m.x[1] - m.mean) / m.sigma);
        for (i = 0; i < 33; i++) pts[2 + i] = (long double)(i - 16) * 2.5L;
        m.c[0] = 0.0L;
        r = pf_oracle_integrate_points(step_smooth_integrand, &m, -HUGE_VALL, HUGE_VALL, pts, 35, 1e-20L, 1e-18L,
                                       PF_ORACLE_MAX_INTERVALS);
        pf_test_max_update(&st, fabsl((long double)pf_gauss_step(e0, mean, sigma) - r.value) / PF_TEST_EPS, m.sigma);
        m.c[0] = 1.0L;
        r = pf_oracle_integrate_points(step_smooth_integrand, &m, -HUGE_VALL, HUGE_VALL, pts, 35, 1e-20L, 1e-18L,
                                       PF_ORACLE_MAX_INTERVALS);
        pf_test_max_update(&sm, fabsl((long double)pf_gauss_smoothstep(e0, e1, mean, sigma) - r.value) / PF_TEST_EPS,
                           m.sigma / (m.x[1] - m.x[0]));
        {   /* sigma = 0: the function itself */
            long double u = ((long double)mean - m.x[0]) / (m.x[1] - m.x[0]);
            u = u < 0.0L ? 0.0L : (u > 1.0L ? 1.0L : u);
            pf_test_max_update(&sm0, fabsl((long double)pf_gauss_smoothstep(e0, e1, mean, PF_R(0.0))
                                           - u * u * (3.0L - 2.0L * u)) / PF_TEST_EPS, u);
        }
    }
    pf_test_note("2000 random: step max abs %.2Lg eps; smoothstep %.2Lg eps (at sigma/width %.3Lg); sigma=0 %.2Lg eps",
                 st.err, sm.err, sm.at, sm0.err);
    PF_CHECK(st.err <= 4.0L, "step %Lg", st.err);
    PF_CHECK(sm.err <= 64.0L, "smoothstep %Lg at %Lg", sm.err, sm.at);
    PF_CHECK(sm0.err <= 8.0L, "smoothstep sigma 0 %Lg", sm0.err);
}

/* The pre-convolved table (256 x 256, the paper's size) against the closed form at random
   (mean, sigma) inside its range; at the grid points it must agree exactly (it stores the
   closed form). */
#define TN 256
static pf_real table_buf[TN * TN * 3];
static void test_table_vs_closed_form(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x7ab1eu);
    static const pf_real x[5] = { PF_R(-1.0), PF_R(-0.2), PF_R(0.1), PF_R(0.5), PF_R(1.0) };
    static const pf_real c[15] = { PF_R(0.1), PF_R(0.2), PF_R(0.6), PF_R(0.9), PF_R(0.1), PF_R(0.0),
                                   PF_R(0.3), PF_R(0.8), PF_R(0.5), PF_R(0.2), PF_R(1.0), PF_R(0.4),
                                   PF_R(0.0), PF_R(0.0), PF_R(1.0) };
    pf_colormap_table t;
    pf_test_max err = pf_test_max_init(), grid = pf_test_max_init(), err_wide = pf_test_max_init();
    int i, ch, rc;
    PF_CHECK(pf_colormap_table_size(TN, TN, 3) == TN * TN * 3, "size");
    PF_CHECK(pf_colormap_table_size(1, TN, 3) == 0, "size of a degenerate table");
    rc = pf_colormap_table_build(&t, table_buf, TN, TN, PF_R(-4.0), PF_R(4.0), PF_R(1.5), x, c, 5, 3);
    PF_CHECK(rc == 0, "build failed");
    PF_CHECK(pf_colormap_table_build(&t, table_buf, TN, TN, PF_R(1.0), PF_R(1.0), PF_R(1.5), x, c, 5, 3) == PF_ERR_ARG,
             "empty mean range accepted");
    rc = pf_colormap_table_build(&t, table_buf, TN, TN, PF_R(-4.0), PF_R(4.0), PF_R(1.5), x, c, 5, 3);
    for (i = 0; i < 20000; i++) {
        pf_real mean = (pf_real)pf_test_uniform(&rng, -4.0, 4.0);
        pf_real sigma = (pf_real)pf_test_uniform(&rng, 0.0, 1.5);
        pf_real a[3], b[3];
        pf_colormap_table_lookup(&t, mean, sigma, a);
        pf_colormap_filter(x, c, 5, 3, mean, sigma, b);
        for (ch = 0; ch < 3; ch++) {
            pf_test_max_update(&err, fabsl((long double)a[ch] - (long double)b[ch]), (long double)sigma);
            if (sigma >= PF_R(0.1))
                pf_test_max_update(&err_wide, fabsl((long double)a[ch] - (long double)b[ch]), (long double)sigma);
        }
    }
    for (i = 0; i < TN; i += 17) {
        pf_real mean = PF_R(-4.0) + PF_R(8.0) * (pf_real)i / (pf_real)(TN - 1);
        pf_real sigma = PF_R(1.5) * (pf_real)((i * 7) % TN) / (pf_real)(TN - 1);
        pf_real a[3], b[3];
        pf_colormap_table_lookup(&t, mean, sigma, a);
        pf_colormap_filter(x, c, 5, 3, mean, sigma, b);
        for (ch = 0; ch < 3; ch++) pf_test_max_update(&grid, fabsl((long double)a[ch] - (long double)b[ch]), 0.0L);
    }
    pf_test_note("256x256 table, mean in [-4,4], sigma in [0,1.5]: bilinear lookup vs closed form max abs %.2Lg "
                 "at sigma=%.3Lg (sigma >= 0.1: %.2Lg); at grid points %.2Lg",
                 err.err, err.at, err_wide.err, grid.err);
    PF_CHECK(err.err <= 2e-2L && err.err >= 1e-5L, "table %Lg", err.err);
    PF_CHECK(grid.err <= 1e-5L, "grid %Lg", grid.err);
}

/* ------------------------------------------------------------------ height-correlated colour */
typedef struct hc_ctx {
    const plmap *m;
    long double lambda, sigma_h, mean_h;
} hc_ctx;

static long double hc_integrand(long double z, void *ctx)
{
    const hc_ctx *c = (const hc_ctx *)ctx;
    long double lp = c->lambda > 0.0L ? c->lambda * log_cdf_ref(z) : 0.0L;
    return plmap_value(c->m, c->mean_h + c->sigma_h * z) * expl(lp - 0.5L * z * z - log_sqrt_2pil);
}

/* eq. 13 done exactly (no Gaussian approximation of D_h): Vbar * integral C(h) D_h(h) dh. The
   pipeline (fit + Gaussian filter + Vbar) is checked two ways: against the quadrature of C
   over the Gaussian it uses (the plumbing, to rounding), and against the exact eq. 13 (the
   paper's Gaussian approximation of D_h: recorded, loosely bounded). */
static void test_height_colour_eq13(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x13u);
    pf_test_max plumb = pf_test_max_init(), approx = pf_test_max_init();
    int trial;
    for (trial = 0; trial < 40; trial++) {
        plmap m = random_map(&rng, 0, 0.01);
        pf_real x[MAXK] = { PF_R(0.0) }, c[MAXK] = { PF_R(0.0) }, out[1] = { PF_R(0.0) };
        pf_real lo = (pf_real)pf_test_log_uniform(&rng, 1e-3, 50.0), li = (pf_real)pf_test_log_uniform(&rng, 1e-3, 50.0);
        pf_real mean_h = (pf_real)pf_test_uniform(&rng, -0.5, 0.5), sigma_h = (pf_real)pf_test_log_uniform(&rng, 0.1, 2.0);
        pf_height_dist d = pf_height_colour_dist(lo, li, mean_h, sigma_h, PF_R(0.0), PF_R(0.0));
        long double vbar = (1.0L + (long double)lo) / (1.0L + (long double)lo + (long double)li);
        long double gauss, exact;
        hc_ctx hc;
        pf_oracle_result r;
        long double centre = sqrtl(2.0L * log1pl((long double)lo + (long double)li));
        map_to_real(&m, x, c);
        pf_height_colormap_filter(x, c, m.n, 1, lo, li, mean_h, sigma_h, PF_R(0.0), PF_R(0.0), out);
        m.mean = (long double)d.mean;
        m.sigma = (long double)d.dev;
        gauss = vbar * plmap_expect(&m, 0);
        hc.m = &m;
        hc.lambda = (long double)lo + (long double)li;
        hc.sigma_h = (long double)sigma_h;
        hc.mean_h = (long double)mean_h;
        r = pf_oracle_integrate_points(hc_integrand, &hc, -HUGE_VALL, HUGE_VALL, &centre, 1, 1e-20L, 1e-16L,
                                       PF_ORACLE_MAX_INTERVALS);
        exact = r.value * (1.0L + hc.lambda) * vbar;
        pf_test_max_update(&plumb, fabsl((long double)out[0] - gauss) / PF_TEST_EPS, hc.lambda);
        pf_test_max_update(&approx, fabsl((long double)out[0] - exact), hc.lambda);
    }
    pf_test_note("eq.13 pipeline vs quadrature over its Gaussian: %.2Lg eps; vs exact eq.13 over D_h "
                 "(the Gaussian approximation of D_h, maps in [0,1]): max abs %.2Lg at L=%.3Lg",
                 plumb.err, approx.err, approx.at);
    PF_CHECK(plumb.err <= 8.0L, "plumbing %Lg", plumb.err);
    PF_CHECK(approx.err <= 0.05L, "Gaussian approximation %Lg", approx.err);
}

/* Noise-perturbed heights: C(h + r), r ~ N(mu_r, sigma_r^2) independent: the filtering
   distribution of the Gaussian model is N(mu_d + mu_r, sigma_d^2 + sigma_r^2) exactly; checked
   by a 2D quadrature of C(h + r) over the product of the two Gaussians. */
typedef struct noise_ctx {
    const plmap *m;
    long double mu_d, sd_d, mu_r, sd_r;
} noise_ctx;

static long double noise_integrand(long double h, long double r, void *ctx)
{
    const noise_ctx *c = (const noise_ctx *)ctx;
    return plmap_value(c->m, h + r) * gauss_weight(h, c->mu_d, c->sd_d) * gauss_weight(r, c->mu_r, c->sd_r);
}

static void test_noise_perturbed_heights(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x9e15u);
    pf_test_max e = pf_test_max_init();
    int trial;
    for (trial = 0; trial < 6; trial++) {
        plmap m = random_map(&rng, 0, 0.01);
        pf_real x[MAXK] = { PF_R(0.0) }, c[MAXK] = { PF_R(0.0) }, out[1] = { PF_R(0.0) };
        /* drawn in sequence (two draws in one argument list are unsequenced: gcc and clang
           drew them in opposite orders and tested different maps); this is gcc's old order */
        pf_real d_dev = (pf_real)pf_test_uniform(&rng, 0.1, 1.0);
        pf_real d_mean = (pf_real)pf_test_uniform(&rng, -1.0, 1.0);
        pf_height_dist d = pf_height_dist_make(d_mean, d_dev);
        pf_real mu_r = (pf_real)pf_test_uniform(&rng, -0.5, 0.5), sd_r = (pf_real)pf_test_uniform(&rng, 0.05, 0.8);
        pf_height_dist dn = pf_height_dist_add_noise(d, mu_r, sd_r);
        noise_ctx nc;
        pf_oracle_2d pb;
        pf_oracle_result r;
        map_to_real(&m, x, c);
        pf_colormap_filter(x, c, m.n, 1, dn.mean, dn.dev, out);
        nc.m = &m;
        nc.mu_d = (long double)d.mean;
        nc.sd_d = (long double)d.dev;
        nc.mu_r = (long double)mu_r;
        nc.sd_r = (long double)sd_r;
        pb = pf_oracle_2d_make(noise_integrand, &nc, nc.mu_d - 12.0L * nc.sd_d, nc.mu_d + 12.0L * nc.sd_d,
                               nc.mu_r - 12.0L * nc.sd_r, nc.mu_r + 12.0L * nc.sd_r);
        pb.epsrel = 1e-12L;
        pb.max_intervals = 200;
        r = pf_oracle_integrate_2d(&pb);
        pf_test_max_update(&e, fabsl((long double)out[0] - r.value), 0.0L);
    }
    pf_test_note("noise-perturbed heights vs 2D quadrature: max abs %.2Lg", e.err);
    PF_CHECK(e.err <= 1e-9L + 64.0L * PF_TEST_EPS, "%Lg", e.err);
}

/* ------------------------------------------------------------------ transfer functions */

/* Box-Muller from the harness generator. */
static double normal_sample(pf_test_rng *rng)
{
    double u1 = pf_test_uniform(rng, 1e-300, 1.0), u2 = pf_test_uniform(rng, 0.0, 1.0);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

static void test_transfer_moments_monte_carlo(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xa11ce5u);
    pf_test_max mc = pf_test_max_init(), qd = pf_test_max_init(), slope = pf_test_max_init();
    int trial, i;
    for (trial = 0; trial < 8; trial++) {
        plmap m = random_map(&rng, 0, 0.1);
        pf_real x[MAXK] = { PF_R(0.0) }, g[MAXK] = { PF_R(0.0) };
        pf_real mean = (pf_real)pf_test_uniform(&rng, -1.5, 1.5), sigma = (pf_real)pf_test_log_uniform(&rng, 0.05, 2.0);
        pf_transfer_moments t, seg;
        long double s[4] = { 0.0L, 0.0L, 0.0L, 0.0L }, s2[4] = { 0.0L, 0.0L, 0.0L, 0.0L }, got[4], q[4];
        long double hx = 0.0L, hxx = 0.0L, hxy = 0.0L, cond;
        const int n = 200000;
        int k;
        pf_slope_stats ss;
        map_to_real(&m, x, g);
        t = pf_transfer_moments_filter(x, g, m.n, mean, sigma);
        /* the same from the per-segment evaluators */
        seg = pf_transfer_moments_add(pf_transfer_end_moments(g[0], pf_gauss_cdf(x[0], mean, sigma)),
                                      pf_transfer_end_moments(g[m.n - 1], pf_gauss_step(x[m.n - 1], mean, sigma)));
        for (k = 0; k + 1 < m.n; k++)
            seg = pf_transfer_moments_add(seg, pf_transfer_segment_moments(x[k], g[k], x[k + 1], g[k + 1], mean, sigma));
        got[0] = (long double)t.g;
        got[1] = (long double)t.g2;
        got[2] = (long double)t.dg;
        got[3] = (long double)t.dg2;
        m.mean = (long double)mean;
        m.sigma = (long double)sigma;
        for (k = 0; k < 4; k++) q[k] = plmap_expect(&m, k);
        /* conditioning of the closed form for E[g^2] (narrow pieces far from the mean cancel):
           1 + max over pieces of ((|mean - x_k| + sigma) / width)^2 */
        cond = 1.0L;
        for (k = 0; k + 1 < m.n; k++) {
            long double r = (fabsl(m.x[k] - m.mean) + m.sigma) / (m.x[k + 1] - m.x[k]);
            if (1.0L + r * r > cond) cond = 1.0L + r * r;
        }
        /* Monte Carlo, fixed seed: f ~ N(mean, sigma^2), slopes (fx, fy) ~ N(0.1, 0.3^2) x
           N(-0.2, 0.5^2), correlation 0.4, independent of f */
        for (i = 0; i < n; i++) {
            long double f = (long double)mean + (long double)sigma * (long double)normal_sample(&rng);
            long double gv = plmap_value(&m, f), dv = 0.0L, z1, z2, fx, fy;
            long double v[4];
            for (k = 0; k + 1 < m.n; k++)
                if (f >= m.x[k] && f < m.x[k + 1]) dv = (m.c[k + 1] - m.c[k]) / (m.x[k + 1] - m.x[k]);
            v[0] = gv; v[1] = gv * gv; v[2] = dv; v[3] = dv * dv;
            for (k = 0; k < 4; k++) {
                s[k] += v[k];
                s2[k] += v[k] * v[k];
            }
            z1 = (long double)normal_sample(&rng);
            z2 = (long double)normal_sample(&rng);
            fx = 0.1L + 0.3L * z1;
            fy = -0.2L + 0.5L * (0.4L * z1 + sqrtl(1.0L - 0.16L) * z2);
            hx += dv * fx;
            hxx += dv * dv * fx * fx;
            hxy += dv * dv * fx * fy;
        }
        for (k = 0; k < 4; k++) {
            long double mean_k = s[k] / n, var = s2[k] / n - mean_k * mean_k;
            long double se = sqrtl((var > 0.0L ? var : 0.0L) / n) + 1e-12L;
            se += 4.0L * PF_TEST_EPS * cond * (fabsl(q[k]) + 1.0L); /* + the closed form's own rounding */
            pf_test_max_update(&mc, fabsl(got[k] - mean_k) / se, (long double)k);
            pf_test_max_update(&qd, fabsl(got[k] - q[k]) / (fabsl(q[k]) + 1.0L) / (PF_TEST_EPS * cond), (long double)k);
            pf_test_max_update(&qd, fabsl((k == 0 ? (long double)seg.g : k == 1 ? (long double)seg.g2
                                           : k == 2 ? (long double)seg.dg : (long double)seg.dg2) - q[k]) / (fabsl(q[k]) + 1.0L)
                                    / (PF_TEST_EPS * cond), (long double)k);
        }
        /* eqs. 24-26: E[h_x] = E[g'] E[f_x], E[h_x^2] = E[g'^2] E[f_x^2], E[h_x h_y] = E[g'^2] E[f_x f_y] */
        ss = pf_transfer_slope_stats(t, PF_R(0.1), PF_R(-0.2), PF_R(0.1 * 0.1 + 0.09), PF_R(0.04 + 0.25),
                                     PF_R(0.1 * -0.2 + 0.4 * 0.3 * 0.5));
        {
            long double ex = hx / n, vx = hxx / n - ex * ex;
            long double cov = hxy / n - ex * ((long double)t.dg * -0.2L);
            long double scale = (long double)t.dg2 * 0.1L + 1e-6L;
            pf_test_max_update(&slope, fabsl((long double)ss.mean_x - ex) / sqrtl(scale / n) / 5.0L, 0.0L);
            pf_test_max_update(&slope, fabsl((long double)ss.var_x - vx) / (fabsl(vx) + 1e-3L) * 20.0L, 1.0L);
            pf_test_max_update(&slope, fabsl((long double)ss.cov_xy - cov) / (fabsl((long double)t.dg2) + 1e-3L) * 20.0L, 2.0L);
        }
    }
    pf_test_note("8 random g, 2e5 samples each: max |closed - MC| %.2Lg standard errors; vs quadrature %.2Lg "
                 "eps x cond (relative to 1+|ref|); slope stats vs MC (scaled, <= 1 passes) %.2Lg", mc.err, qd.err, slope.err);
    PF_CHECK(mc.err <= 5.0L, "MC %Lg (moment %Lg)", mc.err, mc.at);
    PF_CHECK(qd.err <= 1.0L, "quadrature %Lg (moment %Lg)", qd.err, qd.at);
    PF_CHECK(slope.err <= 1.0L, "slope stats %Lg (item %Lg)", slope.err, slope.at);
}

/* ------------------------------------------------------------------ memory safety (issue 19)
   The pointer-taking functions under pf_core.h's "CPU only: sizes and errors": every reproducer
   of issue 19 for pf_height.h, NULL and size rejections with canaries ("nothing written"), and
   the long long offsets at the far end of huge tables through guarded mappings
   (pf_test_guarded_alloc: a fault, not a silent read, on any access past the end). */

#define CANARY PF_R(-12345.0)

static int canaries_intact(const pf_real *a, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (!(a[i] == CANARY)) return 0;
    return 1;
}

static void fill_canary(pf_real *a, int n)
{
    int i;
    for (i = 0; i < n; i++) a[i] = CANARY;
}

/* A table description filled with a byte pattern: "nothing written" means it is unchanged. */
static void table_canary(pf_colormap_table *t) { memset(t, 0xA5, sizeof *t); }

static int table_untouched(const pf_colormap_table *t)
{
    pf_colormap_table r;
    table_canary(&r);
    return memcmp(&r, t, sizeof r) == 0;
}

/* Reproducer 1 (sizes): the size is a long long, 0 for every size the builder rejects. */
static void test_mem_table_size(void)
{
    const long long side = (long long)PF_MAX_SIDE;
    PF_CHECK(PF_MAX_REALS < 4295098369LL || pf_colormap_table_size(65537, 65537, 1) == 4295098369LL,
             "size(65537, 65537, 1) = %lld", pf_colormap_table_size(65537, 65537, 1));
    PF_CHECK(PF_MAX_REALS < (1LL << 32) || pf_colormap_table_size(2, 2, 1 << 30) == (1LL << 32),
             "size(2, 2, 2^30) = %lld", pf_colormap_table_size(2, 2, 1 << 30));
    PF_CHECK(PF_MAX_REALS < 4LL * INT_MAX || pf_colormap_table_size(2, 2, INT_MAX) == 4LL * INT_MAX,
             "size(2, 2, INT_MAX) = %lld",
             pf_colormap_table_size(2, 2, INT_MAX));
    PF_CHECK(pf_colormap_table_size((int)side, 2, 1) == 2 * side, "largest side rejected");
    PF_CHECK(pf_colormap_table_size((int)side + 1, 2, 1) == 0 && pf_colormap_table_size(2, (int)side + 1, 1) == 0,
             "side above PF_MAX_SIDE accepted");
    PF_CHECK(pf_colormap_table_size(INT_MAX, INT_MAX, INT_MAX) == 0, "INT_MAX^3 accepted");
    PF_CHECK(pf_colormap_table_size((int)side, (int)side, 1) == 0, "2^48 reals accepted (PF_MAX_REALS %lld)",
             (long long)PF_MAX_REALS);
    if (PF_MAX_REALS == (1LL << 40)) {
        PF_CHECK(pf_colormap_table_size((int)side, 1 << 16, 1) == (1LL << 40), "exactly PF_MAX_REALS rejected");
        PF_CHECK(pf_colormap_table_size((int)side, (1 << 16) + 1, 1) == 0, "PF_MAX_REALS + 2^24 accepted");
        PF_CHECK(pf_colormap_table_size(2, 2, INT_MAX) > 0 && pf_colormap_table_size(1 << 12, 1 << 12, 1 << 16) == (1LL << 40),
                 "channels product");
    }
    PF_CHECK(pf_colormap_table_size(1, 5, 1) == 0 && pf_colormap_table_size(5, 1, 1) == 0 &&
                 pf_colormap_table_size(5, 5, 0) == 0 && pf_colormap_table_size(-5, -5, 1) == 0 &&
                 pf_colormap_table_size(INT_MIN, 2, 1) == 0 && pf_colormap_table_size(2, 2, INT_MIN) == 0,
             "degenerate sizes accepted");
}

/* Reproducer 1 (lookup): a 65537 x 65537 table (17 GB in float, 34 GB in double) as a guarded,
   mostly untouched mapping of exactly the documented size; lookups at its far corner read the
   last four entries (with int offsets, j * n_mean overflowed and read far outside). */
static void test_mem_table_far_corner(void)
{
    const int side = 65537;
    long long reals = pf_colormap_table_size(side, side, 1);
    size_t bytes = (size_t)reals * sizeof(pf_real);
    pf_real *data, out[2] = { PF_R(0.0), PF_R(0.0) };
    pf_colormap_table t;
    int rc;
    if (reals == 0 || (unsigned long long)reals > ((size_t)-1) / sizeof(pf_real)) {
        pf_test_note("skipped: table above PF_MAX_REALS here");
        return;
    }
    data = (pf_real *)pf_test_guarded_alloc(bytes);
    if (!data) {
        pf_test_note("skipped: no guarded mapping of %zu bytes here", bytes);
        return;
    }
    /* the four corner entries: (i, j) = (n-2, n-2), (n-1, n-2), (n-2, n-1), (n-1, n-1) */
    data[(long long)(side - 2) * side + (side - 2)] = PF_R(1.0);
    data[(long long)(side - 2) * side + (side - 1)] = PF_R(2.0);
    data[(long long)(side - 1) * side + (side - 2)] = PF_R(3.0);
    data[(long long)(side - 1) * side + (side - 1)] = PF_R(4.0);
    data[0] = PF_R(7.0);
    t.data = data;
    t.n_mean = side;
    t.n_sigma = side;
    t.channels = 1;
    t.mean_min = PF_R(0.0);
    t.mean_max = PF_R(65536.0); /* one unit per step: the lookup position is the index */
    t.sigma_max = PF_R(65536.0);
    out[1] = CANARY;
    rc = pf_colormap_table_lookup(&t, PF_R(65536.0), PF_R(65536.0), out);
    PF_CHECK(rc == PF_OK && out[0] == PF_R(4.0) && out[1] == CANARY, "far corner: rc %d, %g", rc, (double)out[0]);
    rc = pf_colormap_table_lookup(&t, PF_R(65535.5), PF_R(65535.5), out);
    PF_CHECK(rc == PF_OK && out[0] == PF_R(2.5), "last cell centre: rc %d, %g (want 2.5)", rc, (double)out[0]);
    rc = pf_colormap_table_lookup(&t, PF_R(1e30), (pf_real)INFINITY, out);
    PF_CHECK(rc == PF_OK && out[0] == PF_R(4.0), "clamped far: %g", (double)out[0]);
    rc = pf_colormap_table_lookup(&t, (pf_real)-INFINITY, PF_R(-1e30), out);
    PF_CHECK(rc == PF_OK && out[0] == PF_R(7.0), "clamped near: %g", (double)out[0]);
    rc = pf_colormap_table_lookup(&t, (pf_real)NAN, (pf_real)NAN, out);
    PF_CHECK(rc == PF_OK && out[0] == PF_R(7.0), "NaN reads the low end: %g", (double)out[0]);
    pf_test_note("65537 x 65537 table (%lld reals) mapped, 4 corner entries read", reals);
    pf_test_guarded_free(data, bytes);
}

/* The builder's offsets at the largest size that stays fast under ASan: a 2049 x 1025 table
   written into a guarded mapping of exactly its size (any write past it faults), checked
   against pf_colormap_filter at its first and last entries. */
static void test_mem_table_build_guarded(void)
{
    static const pf_real x[2] = { PF_R(-1.0), PF_R(1.0) };
    static const pf_real c[4] = { PF_R(0.0), PF_R(1.0), PF_R(1.0), PF_R(0.5) };
    const int nm = 2049, ns = 1025, ch = 2;
    long long reals = pf_colormap_table_size(nm, ns, ch);
    size_t bytes = (size_t)reals * sizeof(pf_real);
    pf_real *data = (pf_real *)pf_test_guarded_alloc(bytes), a[2] = { PF_R(0.0), PF_R(0.0) }, b[2] = { PF_R(0.0), PF_R(0.0) };
    pf_colormap_table t;
    int rc;
    if (!data) {
        pf_test_note("skipped: no guarded mapping");
        return;
    }
    rc = pf_colormap_table_build(&t, data, nm, ns, PF_R(-3.0), PF_R(3.0), PF_R(2.0), x, c, 2, ch);
    PF_CHECK(rc == PF_OK, "build rc %d", rc);
    pf_colormap_filter(x, c, 2, ch, PF_R(3.0), PF_R(2.0), b);
    PF_CHECK(data[reals - 2] == b[0] && data[reals - 1] == b[1], "last entry (%g %g) vs (%g %g)", (double)data[reals - 2],
             (double)data[reals - 1], (double)b[0], (double)b[1]);
    pf_colormap_filter(x, c, 2, ch, PF_R(-3.0), PF_R(0.0), b);
    PF_CHECK(data[0] == b[0] && data[1] == b[1], "first entry");
    rc = pf_colormap_table_lookup(&t, PF_R(3.0), PF_R(2.0), a);
    PF_CHECK(rc == PF_OK && a[0] == data[reals - 2] && a[1] == data[reals - 1], "lookup at the far corner");
    pf_test_note("%d x %d x %d table built into a guarded mapping of %lld reals", nm, ns, ch, reals);
    pf_test_guarded_free(data, bytes);
}

/* NULL pointers and sizes out of range: the error code, and nothing written. */
static void test_mem_null_and_sizes(void)
{
    static const pf_real x[3] = { PF_R(-1.0), PF_R(0.0), PF_R(1.0) };
    static const pf_real c[6] = { PF_R(0.0), PF_R(1.0), PF_R(0.5), PF_R(0.5), PF_R(1.0), PF_R(0.0) };
    pf_real out[4], buf[64];
    pf_colormap_table t, good;
    pf_transfer_moments m;
    int bad = 0;
    fill_canary(out, 4);
    fill_canary(buf, 64);
    /* pf_colormap_filter, pf_height_colormap_filter */
    bad += pf_colormap_filter(NULL, c, 3, 2, PF_R(0.0), PF_R(1.0), out) != PF_ERR_ARG;
    bad += pf_colormap_filter(x, NULL, 3, 2, PF_R(0.0), PF_R(1.0), out) != PF_ERR_ARG;
    bad += pf_colormap_filter(x, c, 3, 2, PF_R(0.0), PF_R(1.0), NULL) != PF_ERR_ARG;
    bad += pf_colormap_filter(x, c, 0, 2, PF_R(0.0), PF_R(1.0), out) != PF_ERR_ARG;
    bad += pf_colormap_filter(x, c, INT_MIN, 2, PF_R(0.0), PF_R(1.0), out) != PF_ERR_ARG;
    bad += pf_colormap_filter(x, c, 3, 0, PF_R(0.0), PF_R(1.0), out) != PF_ERR_ARG;
    bad += pf_colormap_filter(x, c, 3, -1, PF_R(0.0), PF_R(1.0), out) != PF_ERR_ARG;
    bad += pf_height_colormap_filter(NULL, c, 3, 2, 1, 1, 0, 1, 0, 0, out) != PF_ERR_ARG;
    bad += pf_height_colormap_filter(x, NULL, 3, 2, 1, 1, 0, 1, 0, 0, out) != PF_ERR_ARG;
    bad += pf_height_colormap_filter(x, c, 3, 2, 1, 1, 0, 1, 0, 0, NULL) != PF_ERR_ARG;
    bad += pf_height_colormap_filter(x, c, 0, 2, 1, 1, 0, 1, 0, 0, out) != PF_ERR_ARG;
    bad += pf_height_colormap_filter(x, c, 3, 0, 1, 1, 0, 1, 0, 0, out) != PF_ERR_ARG;
    PF_CHECK(bad == 0 && canaries_intact(out, 4), "%d wrong codes, or out written", bad);
    /* pf_transfer_moments_filter: zeros */
    m = pf_transfer_moments_filter(NULL, c, 3, PF_R(0.0), PF_R(1.0));
    bad += !(m.g == 0 && m.g2 == 0 && m.dg == 0 && m.dg2 == 0);
    m = pf_transfer_moments_filter(x, NULL, 3, PF_R(0.0), PF_R(1.0));
    bad += !(m.g == 0 && m.g2 == 0 && m.dg == 0 && m.dg2 == 0);
    m = pf_transfer_moments_filter(x, c, 0, PF_R(0.0), PF_R(1.0));
    bad += !(m.g == 0 && m.g2 == 0 && m.dg == 0 && m.dg2 == 0);
    m = pf_transfer_moments_filter(x, c, INT_MIN, PF_R(0.0), PF_R(1.0));
    bad += !(m.g == 0 && m.g2 == 0 && m.dg == 0 && m.dg2 == 0);
    PF_CHECK(bad == 0, "transfer moments of bad arguments not zero");
    /* pf_colormap_table_build */
    table_canary(&t);
    bad += pf_colormap_table_build(NULL, buf, 4, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 3, 2) != PF_ERR_ARG;
    bad += pf_colormap_table_build(&t, NULL, 4, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 3, 2) != PF_ERR_ARG;
    bad += pf_colormap_table_build(&t, buf, 4, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), NULL, c, 3, 2) != PF_ERR_ARG;
    bad += pf_colormap_table_build(&t, buf, 4, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, NULL, 3, 2) != PF_ERR_ARG;
    bad += pf_colormap_table_build(&t, buf, 4, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 0, 2) != PF_ERR_ARG;
    bad += pf_colormap_table_build(&t, buf, 1, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 3, 2) != PF_ERR_ARG;
    bad += pf_colormap_table_build(&t, buf, 4, INT_MIN, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 3, 2) != PF_ERR_ARG;
    bad += pf_colormap_table_build(&t, buf, 4, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 3, 0) != PF_ERR_ARG;
    /* sizes above the limits: PF_ERR_SIZE, checked before the (small) buffer is touched */
    bad += pf_colormap_table_build(&t, buf, (int)PF_MAX_SIDE + 1, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 3, 2) !=
           PF_ERR_SIZE;
    bad += pf_colormap_table_build(&t, buf, INT_MAX, INT_MAX, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 3, 2) != PF_ERR_SIZE;
    bad += pf_colormap_table_build(&t, buf, (int)PF_MAX_SIDE, (int)PF_MAX_SIDE, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c,
                                   3, 1) != PF_ERR_SIZE;
    bad += pf_colormap_table_build(&t, buf, 4, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, INT_MAX, INT_MAX / 16) !=
           PF_ERR_SIZE;
    PF_CHECK(bad == 0 && table_untouched(&t) && canaries_intact(buf, 64), "build: %d wrong codes, or something written",
             bad);
    /* pf_colormap_table_lookup: NULLs and descriptions the builder would reject */
    bad += pf_colormap_table_build(&good, buf, 4, 4, PF_R(-1.0), PF_R(1.0), PF_R(1.0), x, c, 3, 2) != PF_OK;
    fill_canary(out, 4);
    bad += pf_colormap_table_lookup(NULL, PF_R(0.0), PF_R(0.5), out) != PF_ERR_ARG;
    bad += pf_colormap_table_lookup(&good, PF_R(0.0), PF_R(0.5), NULL) != PF_ERR_ARG;
    t = good;
    t.data = NULL;
    bad += pf_colormap_table_lookup(&t, PF_R(0.0), PF_R(0.5), out) != PF_ERR_ARG;
    memset(&t, 0, sizeof t);
    t.data = buf;
    bad += pf_colormap_table_lookup(&t, PF_R(0.0), PF_R(0.5), out) != PF_ERR_ARG; /* zeroed description */
    t = good;
    t.n_mean = 1;
    bad += pf_colormap_table_lookup(&t, PF_R(0.0), PF_R(0.5), out) != PF_ERR_ARG;
    t = good;
    t.channels = 0;
    bad += pf_colormap_table_lookup(&t, PF_R(0.0), PF_R(0.5), out) != PF_ERR_ARG;
    t = good;
    t.mean_max = (pf_real)NAN;
    bad += pf_colormap_table_lookup(&t, PF_R(0.0), PF_R(0.5), out) != PF_ERR_ARG;
    t = good;
    t.sigma_max = PF_R(0.0);
    bad += pf_colormap_table_lookup(&t, PF_R(0.0), PF_R(0.5), out) != PF_ERR_ARG;
    t = good;
    t.n_sigma = INT_MAX;
    bad += pf_colormap_table_lookup(&t, PF_R(0.0), PF_R(0.5), out) != PF_ERR_SIZE;
    PF_CHECK(bad == 0 && canaries_intact(out, 4), "lookup: %d wrong codes, or out written", bad);
}

/* Reproducer 5: pf_colormap_filter(x, c, 3, 1 << 30, 0, 1, out) indexed c with int
   k * channels, which overflows. The offsets are long long now; n * channels above
   PF_MAX_REALS is rejected before anything is read. Running the reproducer itself reads
   3 x 2^30 values and writes 2^30: PF_TEST_HUGE=1 in the environment runs it on guarded
   mappings, by hand only (measured here: float passed in 370 s at 16.8 GB resident - the
   kernel backed the read-only pages too; double needs more than the 23 GB this machine has
   and was OOM-killed). By default the same layout runs with 2^22 channels. */
static void test_mem_filter_channels(void)
{
    static const pf_real x[3] = { PF_R(-1.0), PF_R(0.0), PF_R(1.0) };
    pf_real small_c[4], out[4];
    const char *huge = getenv("PF_TEST_HUGE");
    int channels = (huge && huge[0] == '1') ? 1 << 30 : 1 << 22, rc;
    long long nc = 3LL * channels;
    size_t cbytes = (size_t)nc * sizeof(pf_real), obytes = (size_t)channels * sizeof(pf_real);
    pf_real *c, *o;
    long double w0, w2;
    fill_canary(small_c, 4);
    fill_canary(out, 4);
    /* above PF_MAX_REALS: rejected without reading c (a 4-entry array: ASan would see a read) */
    rc = pf_colormap_filter(x, small_c, 1 << 20, 1 << 21, PF_R(0.0), PF_R(1.0), out);
    PF_CHECK(rc == (PF_MAX_REALS < (1LL << 41) ? PF_ERR_SIZE : rc), "2^41 reals: rc %d", rc);
    rc = pf_colormap_filter(x, small_c, INT_MAX, INT_MAX, PF_R(0.0), PF_R(1.0), out);
    PF_CHECK(rc == PF_ERR_SIZE && canaries_intact(out, 4), "INT_MAX^2 reals: rc %d, or out written", rc);
    rc = pf_height_colormap_filter(x, small_c, INT_MAX, INT_MAX, 1, 1, 0, 1, 0, 0, out);
    PF_CHECK(rc == PF_ERR_SIZE && canaries_intact(out, 4), "height filter INT_MAX^2 reals: rc %d", rc);
    if ((unsigned long long)nc > ((size_t)-1) / sizeof(pf_real) || nc > PF_MAX_REALS) return;
    c = (pf_real *)pf_test_guarded_alloc(cbytes);
    o = (pf_real *)pf_test_guarded_alloc(obytes);
    if (!c || !o) {
        pf_test_note("skipped the guarded run: no mapping");
        pf_test_guarded_free(c, cbytes);
        pf_test_guarded_free(o, obytes);
        return;
    }
    /* knot values: channel 0 and the last channel set, everything else 0 (untouched pages) */
    c[0] = PF_R(1.0);
    c[2LL * channels] = PF_R(3.0);
    c[(long long)channels - 1] = PF_R(5.0);
    c[nc - 1] = PF_R(7.0);
    rc = pf_colormap_filter(x, c, 3, channels, PF_R(0.0), PF_R(1.0), o);
    /* E[C(X)] for the map 1 -> 0 -> 3 on x = -1, 0, 1: the weights of knots 0 and 2 */
    {
        pf_real one[3] = { PF_R(1.0), PF_R(0.0), PF_R(0.0) }, three[3] = { PF_R(0.0), PF_R(0.0), PF_R(1.0) }, r;
        pf_colormap_filter(x, one, 3, 1, PF_R(0.0), PF_R(1.0), &r);
        w0 = (long double)r;
        pf_colormap_filter(x, three, 3, 1, PF_R(0.0), PF_R(1.0), &r);
        w2 = (long double)r;
    }
    PF_CHECK(rc == PF_OK, "rc %d", rc);
    PF_CHECK(fabsl((long double)o[0] - (w0 + 3.0L * w2)) <= 8.0L * PF_TEST_EPS &&
                 fabsl((long double)o[channels - 1] - (5.0L * w0 + 7.0L * w2)) <= 32.0L * PF_TEST_EPS &&
                 o[channels / 2] == PF_R(0.0),
             "channel 0 %g, last %g", (double)o[0], (double)o[channels - 1]);
    pf_test_note("3 knots x %d channels (%lld reals) on guarded mappings%s", channels, nc,
                 channels == 1 << 30 ? " (the reproducer itself)" : "; PF_TEST_HUGE=1 for 2^30");
    pf_test_guarded_free(c, cbytes);
    pf_test_guarded_free(o, obytes);
}

/* Reproducer 8: ranges whose bounds, width or step are not finite are PF_ERR_ARG, nothing
   written; a wide range whose width is finite builds finite sample means. */
static void test_mem_table_ranges(void)
{
    static const pf_real x[2] = { PF_R(-1.0), PF_R(1.0) };
    static const pf_real c[2] = { PF_R(0.25), PF_R(0.75) };
    const pf_real inf = (pf_real)INFINITY, nan = (pf_real)NAN, big = PF_REAL_MAX;
    const pf_real tiny = PF_REAL_MIN * PF_REAL_EPSILON; /* smallest subnormal */
    const pf_real bad_ranges[][3] = {
        { -inf, PF_R(1.0), PF_R(1.0) }, { PF_R(-1.0), inf, PF_R(1.0) },    { -inf, inf, PF_R(1.0) },
        { PF_R(-1.0), PF_R(1.0), inf }, { nan, PF_R(1.0), PF_R(1.0) },     { PF_R(-1.0), nan, PF_R(1.0) },
        { PF_R(-1.0), PF_R(1.0), nan }, { -big, big, PF_R(1.0) },          { PF_R(1.0), PF_R(-1.0), PF_R(1.0) },
        { PF_R(1.0), PF_R(1.0), PF_R(1.0) }, { PF_R(-1.0), PF_R(1.0), PF_R(0.0) }, { PF_R(-1.0), PF_R(1.0), PF_R(-1.0) },
        { PF_R(0.0), tiny, PF_R(1.0) }, /* step tiny / 4 underflows to 0 */
        { PF_R(-1.0), PF_R(1.0), tiny }, { PF_R(0.0), tiny, PF_R(1.0) }
    };
    pf_real buf[5 * 5], out[2] = { PF_R(0.0), PF_R(0.0) };
    pf_colormap_table t;
    size_t k;
    int bad = 0, rc, i;
    fill_canary(buf, 25);
    for (k = 0; k < sizeof bad_ranges / sizeof bad_ranges[0]; k++) {
        table_canary(&t);
        rc = pf_colormap_table_build(&t, buf, 5, 5, bad_ranges[k][0], bad_ranges[k][1], bad_ranges[k][2], x, c, 2, 1);
        if (rc != PF_ERR_ARG || !table_untouched(&t)) {
            bad++;
            printf("    range %d: [%g, %g], sigma_max %g: rc %d\n", (int)k, (double)bad_ranges[k][0],
                   (double)bad_ranges[k][1], (double)bad_ranges[k][2], rc);
        }
    }
    PF_CHECK(bad == 0 && canaries_intact(buf, 25), "%d bad ranges accepted, or the buffer written", bad);
    /* the issue's [-3e38, 3e38]: its width overflows float (PF_ERR_ARG), fits double */
    table_canary(&t);
    rc = pf_colormap_table_build(&t, buf, 5, 5, (pf_real)-3e38, (pf_real)3e38, PF_R(1.0), x, c, 2, 1);
#ifdef PF_DOUBLE
    PF_CHECK(rc == PF_OK && buf[0] == PF_R(0.25) && buf[4] == PF_R(0.75), "double [-3e38, 3e38]: rc %d", rc);
#else
    PF_CHECK(rc == PF_ERR_ARG && table_untouched(&t) && canaries_intact(buf, 25), "float [-3e38, 3e38]: rc %d", rc);
#endif
    /* a wide range with a finite width: every sample mean finite (width * i / (n - 1) used to
       overflow before the division), the entries the map's ends and middle */
    {
        pf_real lo = -big / PF_R(2.5), hi = big / PF_R(2.5);
        rc = pf_colormap_table_build(&t, buf, 5, 5, lo, hi, PF_R(1.0), x, c, 2, 1);
        for (i = 0; i < 25; i++) bad += !pf_test_finite(buf[i]);
        PF_CHECK(rc == PF_OK && bad == 0 && buf[0] == PF_R(0.25) && buf[4] == PF_R(0.75) && buf[2] == PF_R(0.5) &&
                     buf[24] == PF_R(0.75),
                 "wide range: rc %d, entries %g %g %g", rc, (double)buf[0], (double)buf[2], (double)buf[4]);
        rc = pf_colormap_table_lookup(&t, hi, PF_R(0.5), out);
        PF_CHECK(rc == PF_OK && out[0] == PF_R(0.75), "lookup of the wide table %g", (double)out[0]);
        rc = pf_colormap_table_lookup(&t, -big, PF_R(0.5), out); /* mean - mean_min finite, u < 0 */
        PF_CHECK(rc == PF_OK && out[0] == PF_R(0.25), "lookup below the wide table %g", (double)out[0]);
    }
}

/* NaN means and deviations: what the header documents. */
static void test_mem_nan_inputs(void)
{
    static const pf_real x[3] = { PF_R(-1.0), PF_R(0.0), PF_R(1.0) };
    static const pf_real c[6] = { PF_R(0.2), PF_R(1.0), PF_R(0.9), PF_R(0.0), PF_R(0.4), PF_R(0.6) };
    const pf_real nan = (pf_real)NAN;
    static const pf_real sigmas[] = { PF_R(0.0), PF_R(1e-6), PF_R(0.5), PF_R(1e6) };
    pf_real out[2] = { PF_R(0.0), PF_R(0.0) }, ref[2] = { PF_R(0.0), PF_R(0.0) };
    pf_transfer_moments m;
    size_t i;
    int bad = 0;
    for (i = 0; i < sizeof sigmas / sizeof sigmas[0]; i++) {
        bad += pf_colormap_filter(x, c, 3, 2, nan, sigmas[i], out) != PF_OK;
        bad += !(PF_FABS(out[0] - PF_R(0.3)) <= PF_R(1e-6) && PF_FABS(out[1] - PF_R(0.8)) <= PF_R(1e-6));
        m = pf_transfer_moments_filter(x, c, 3, nan, sigmas[i]); /* g = 0.2, 1.0, 0.9 at x */
        bad += !(PF_FABS(m.g - PF_R(0.55)) <= PF_R(1e-6) && PF_FABS(m.g2 - PF_R(0.425)) <= PF_R(1e-6) && m.dg == 0 &&
                 m.dg2 == 0);
    }
    PF_CHECK(bad == 0, "NaN mean: %d results differ from (c[0] + c[n-1]) / 2", bad);
    /* NaN sigma: no filtering (the map at the mean), as sigma = 0 */
    pf_colormap_filter(x, c, 3, 2, PF_R(0.5), PF_R(0.0), ref);
    pf_colormap_filter(x, c, 3, 2, PF_R(0.5), nan, out);
    PF_CHECK(out[0] == ref[0] && out[1] == ref[1] && PF_FABS(ref[0] - PF_R(0.65)) < PF_R(1e-6), "NaN sigma: %g vs %g",
             (double)out[0], (double)ref[0]);
    /* the height filter: NaN Lambda reads as 0, NaN mean_h gives Vbar (c[0] + c[n-1]) / 2, Vbar = 2/5 */
    pf_height_colormap_filter(x, c, 3, 2, nan, nan, PF_R(0.1), PF_R(0.5), PF_R(0.0), PF_R(0.0), out);
    pf_height_colormap_filter(x, c, 3, 2, PF_R(0.0), PF_R(0.0), PF_R(0.1), PF_R(0.5), PF_R(0.0), PF_R(0.0), ref);
    PF_CHECK(out[0] == ref[0] && out[1] == ref[1], "NaN Lambdas");
    pf_height_colormap_filter(x, c, 3, 2, PF_R(1.0), PF_R(3.0), nan, PF_R(0.5), PF_R(0.0), PF_R(0.0), out);
    PF_CHECK(PF_FABS(out[0] - PF_R(0.4) * PF_R(0.3)) <= PF_R(1e-6) && PF_FABS(out[1] - PF_R(0.4) * PF_R(0.8)) <= PF_R(1e-6),
             "NaN mean_h: %g %g", (double)out[0], (double)out[1]);
}

/* The private log1p (the base of log Phi for z >= 0 and of s = sqrt(log(1 + Lambda))) against
   libm's long double log1pl: its atanh series on [-1/2, 1], the built-in log outside, and the
   tiny and subnormal arguments it returns as they are. Every step is plain arithmetic that a
   shader compiler may not fold into something else (docs/gpu.md), so the CPU bound is the GPU's
   too, apart from the 3 ulp the GLSL log may take beyond [-1/2, 1]. */
static void test_log1p_series(void)
{
    long double worst = 0.0L, at = 0.0L;
    long i;
    for (i = 0; i < 400000; i++) {
        long double u = (long double)i / 400000.0L, r, e;
        pf_real x;
        if (i % 3 == 0) x = (pf_real)(-1.0L + 1e-6L + 5.0L * u);            /* (-1, 4] */
        else if (i % 3 == 1) x = (pf_real)(-0.6L + 1.7L * u);              /* both joins */
        else x = (pf_real)((i % 2 ? -1.0L : 1.0L) * ldexpl(1.0L + u, -(int)(i % 149))); /* tiny */
        if (!(x > PF_R(-1.0)) || x == PF_R(0.0)) continue;
        r = log1pl((long double)x);
        e = fabsl(((long double)pfi_log1p(x) - r) / r) / PF_TEST_EPS;
        if (e > worst) { worst = e; at = (long double)x; }
    }
    pf_test_note("max %.3Lg eps at x = %.6Lg", worst, at);
    PF_CHECK(worst <= 2.0L, "pfi_log1p %.3Lg eps at x = %.6Lg (bound 2)", worst, at);
}

/* The issue-20 cases, where the GPU had folded (1 + x) - 1: mu_d at tiny Lambda follows its
   slope 0.9032 (relative; the old form lost it to the absolute 2^-21 of a GLSL log), and
   log Phi(5.4) = log1p(-Q(5.4)) keeps its relative accuracy. */
static void test_log1p_small_lambda(void)
{
    static const long double ls[] = { 1e-30L, 1e-12L, 1e-6L, 3e-4L, 0.01L, 0.4L, 0.99L };
    long double worst = 0.0L, e;
    size_t i;
    for (i = 0; i < sizeof ls / sizeof ls[0]; i++) {
        pf_real l = (pf_real)ls[i];
        long double s2 = log1pl((long double)l); /* s^2: mu_d ~ 0.9032054649 s^2 for tiny s */
        long double mu = (long double)pf_visible_height(l).mean;
        if (ls[i] <= 1e-6L) {
            e = fabsl(mu / (0.9032054649L * s2) - 1.0L);
            if (e > worst) worst = e;
        }
    }
    pf_test_note("mu_d / (0.9032 log1p(L)) - 1 <= %.3Lg for L <= 1e-6", worst);
    PF_CHECK(worst <= 1e-5L, "mu_d at tiny Lambda off its slope by %.3Lg", worst);
    {
        long double r = log1pl(-pf_oracle_normal_sf(5.4L));
        e = fabsl((long double)pf_height_log_cdf(PF_R(5.4)) / r - 1.0L);
        pf_test_note("log Phi(5.4) %.3Lg relative", e);
        /* erfc's own few ulp, plus z^2 eps from rounding z / sqrt 2 (the conditioning) */
        PF_CHECK(e <= (5.4L * 5.4L + 8.0L) * PF_TEST_EPS, "log Phi(5.4) off by %.3Lg relative", e);
    }
}

/* ------------------------------------------------------------------ edge cases (also -ffast-math) */

static int in01(pf_real v) { return pf_test_finite(v) && v >= PF_R(0.0) && v <= PF_R(1.0); }

static void edge_visibility_extremes(void)
{
    static const pf_real zs[] = { PF_R(-1e30), PF_R(-1e4), PF_R(-200.0), PF_R(-38.0), PF_R(-14.0), PF_R(-10.0),
                                  PF_R(-1.0), PF_R(0.0), PF_R(1.0), PF_R(9.0), PF_R(40.0), PF_R(1e30) };
    static const pf_real ls[] = { PF_R(0.0), PF_R(1e-30), PF_R(1e-6), PF_R(1.0), PF_R(1e6), PF_LAMBDA_MAX,
                                  PF_R(-1.0), PF_R(3e38) };
    size_t i, j;
    int bad = 0;
    for (i = 0; i < sizeof zs / sizeof zs[0]; i++) {
        if (!pf_test_finite(pf_height_log_cdf(zs[i])) || !(pf_height_log_cdf(zs[i]) <= PF_R(0.0))) bad++;
        if (!in01(pf_height_cdf(zs[i])) || !pf_test_finite(pf_height_pdf(zs[i]))) bad++;
        for (j = 0; j < sizeof ls / sizeof ls[0]; j++) {
            pf_real v = pf_height_visibility(zs[i], ls[j]);
            if (!in01(v)) bad++;
            if (ls[j] <= PF_R(0.0) && v != PF_R(1.0)) bad++;
        }
    }
    /* visibility falls with Lambda and rises with height */
    if (!(pf_height_visibility(PF_R(0.5), PF_R(2.0)) < pf_height_visibility(PF_R(0.5), PF_R(1.0)))) bad++;
    if (!(pf_height_visibility(PF_R(0.5), PF_R(2.0)) > pf_height_visibility(PF_R(0.2), PF_R(2.0)))) bad++;
    if (!(pf_height_visibility(PF_R(-3.0), PF_LAMBDA_MAX) == PF_R(0.0))) bad++;
    PF_CHECK(bad == 0, "%d non-finite, out-of-range or wrong-order values", bad);
}

static void edge_closed_forms_extremes(void)
{
    static const pf_real ls[] = { PF_R(0.0), PF_R(1e-30), PF_R(1.0), PF_R(1e20), PF_LAMBDA_MAX, PF_R(-5.0) };
    size_t i, j;
    int bad = 0;
    for (i = 0; i < sizeof ls / sizeof ls[0]; i++)
        for (j = 0; j < sizeof ls / sizeof ls[0]; j++) {
            pf_real a = pf_height_mean_visibility(ls[i], ls[j]), b = pf_height_joint_visibility(ls[i], ls[j]);
            pf_real c = pf_height_attribute_mean(PF_R(0.0), PF_R(1.0), ls[i], ls[j]);
            if (!in01(a) || !in01(b) || !in01(c) || c < PF_R(0.5)) bad++;
        }
    PF_CHECK(bad == 0, "%d bad", bad);
    PF_CHECK(pf_height_mean_visibility(PF_R(0.0), PF_R(0.0)) == PF_R(1.0), "Vbar(0,0)");
    PF_CHECK(pf_height_attribute_mean(PF_R(0.0), PF_R(1.0), PF_R(0.0), PF_R(0.0)) == PF_R(0.5), "a(0,0)");
}

static void edge_visible_height_extremes(void)
{
    static const pf_real ls[] = { PF_R(0.0), PF_R(1e-30), PF_R(1e-10), PF_R(1.0), PF_R(1e10), PF_R(1e25),
                                  PF_LAMBDA_MAX, PF_R(3e38), PF_R(-1.0) };
    size_t i;
    int bad = 0, k;
    pf_real prev_mu = PF_R(-1.0), prev_sd = PF_R(2.0);
    for (i = 0; i < sizeof ls / sizeof ls[0]; i++) {
        pf_height_dist a = pf_visible_height(ls[i]), b = pf_visible_height_published(ls[i]);
        pf_height_dist c = pf_visible_height_exact(ls[i]);
        if (!pf_test_finite(a.mean) || !pf_test_finite(a.dev) || !(a.dev > PF_R(0.0))) bad++;
        if (!pf_test_finite(b.mean) || !pf_test_finite(b.dev) || !(b.dev > PF_R(0.0))) bad++;
        if (!pf_test_finite(c.mean) || !pf_test_finite(c.dev) || !(c.dev > PF_R(0.0))) bad++;
        if (!(a.mean >= PF_R(0.0)) || !(a.mean < PF_R(12.0)) || !(c.mean > PF_R(-1e-3)) || !(c.mean < PF_R(12.0))) bad++;
    }
    /* ours: mu_d increasing, sigma_d decreasing over the whole range */
    for (k = 0; k <= 3000; k++) {
        pf_real l = (pf_real)pow(10.0, -8.0 + 38.0 * k / 3000.0);
        pf_height_dist a = pf_visible_height(l);
        if (a.mean < prev_mu * (PF_R(1.0) - PF_R(4.0) * PF_REAL_EPSILON) ||
            a.dev > prev_sd * (PF_R(1.0) + PF_R(4.0) * PF_REAL_EPSILON)) bad++;
        prev_mu = a.mean;
        prev_sd = a.dev;
    }
    PF_CHECK(bad == 0, "%d bad (non-finite, out of range or non-monotone)", bad);
}

/* The sweep's findings (docs/stability.md, first sweep): E[g^2] of one segment came out
   -3.4e-21 (float) / -5.8e-11 (double) where its three terms cancel (g crosses 0 far out in
   the tail), and pf_transfer_slope_stats gave |cov| > sqrt(vx vy) when vx vy was subnormal.
   Exact inputs, then random segments around a sign change of g. */
static void edge_transfer_rounding(void)
{
    pf_test_rng r = pf_test_rng_seed(0x7A5F0001ULL);
    pf_transfer_moments t;
    pf_slope_stats st;
    int i, bad = 0;
#ifdef PF_DOUBLE
    t = pf_transfer_segment_moments(PF_R(-1048576.0), PF_R(1024.0), PF_R(0.0), (pf_real)ldexp(-10190848.0, -40),
                                    (pf_real)ldexp(12288000.0, -37), (pf_real)ldexp(11010048.0, -30));
#else
    t = pf_transfer_segment_moments(PF_R(-1048576.0), (pf_real)ldexp(14811136.0, -46), PF_R(0.0),
                                    (pf_real)ldexp(15532032.0, -134), (pf_real)ldexp(-13863992.0, -26),
                                    (pf_real)ldexp(12091392.0, -33));
#endif
    PF_CHECK(t.g2 >= PF_R(0.0) && t.dg2 >= PF_R(0.0), "E[g^2] = %g, E[g'^2] = %g", (double)t.g2, (double)t.dg2);
    {
        pf_real x0 = (pf_real)ldexp(11927552.0, -40);
        t = pf_transfer_segment_moments(x0, (pf_real)ldexp(-15630336.0, -38), x0 + (pf_real)ldexp(8978432.0, -4),
                                        (pf_real)ldexp(15073280.0, -118), (pf_real)ldexp(9764864.0, -26),
                                        (pf_real)ldexp(10944512.0, -33));
        st = pf_transfer_slope_stats(t, (pf_real)ldexp(13056685.0, -24), (pf_real)ldexp(9241060.0, -25),
                                     (pf_real)ldexp(10305094.0, -24), (pf_real)ldexp(10373674.0, -27),
                                     (pf_real)ldexp(14619493.0, -26));
        PF_CHECK(st.var_x >= PF_R(0.0) && st.var_y >= PF_R(0.0) &&
                     PF_FABS(st.cov_xy) <= PF_SQRT(st.var_x) * PF_SQRT(st.var_y),
                 "slope stats (%g %g %g) not PSD", (double)st.var_x, (double)st.var_y, (double)st.cov_xy);
    }
    for (i = 0; i < 100000; ++i) {
        pf_real x0 = (pf_real)pf_test_uniform(&r, -1e6, 1e6), w = (pf_real)pf_test_log_uniform(&r, 1e-3, 2e6);
        pf_real g0 = (pf_real)pf_test_log_uniform(&r, 1e-30, 1e3), g1 = -(pf_real)pf_test_log_uniform(&r, 1e-30, 1e3);
        pf_real m = (pf_real)pf_test_uniform(&r, -1.0, 1.0), sg = (pf_real)pf_test_log_uniform(&r, 1e-4, 10.0);
        t = pf_transfer_segment_moments(x0, i % 2 ? g0 : g1, x0 + w, i % 2 ? g1 : g0, m, sg);
        bad += !(t.g2 >= PF_R(0.0) && t.dg2 >= PF_R(0.0));
    }
    PF_CHECK(bad == 0, "%d negative second moments", bad);
}

static void edge_colormap_degenerate(void)
{
    static const pf_real x[6] = { PF_R(-1.0), PF_R(0.0), PF_R(0.0), PF_R(0.5), PF_R(0.5000001), PF_R(2.0) };
    static const pf_real c[6] = { PF_R(0.2), PF_R(0.4), PF_R(0.9), PF_R(0.1), PF_R(1.0), PF_R(0.0) };
    static const pf_real sigmas[] = { PF_R(0.0), PF_R(-1.0), PF_R(1e-30), PF_R(1e-6), PF_R(1.0), PF_R(1e6), PF_R(1e30) };
    static const pf_real means[] = { PF_R(-1e30), PF_R(-3.0), PF_R(0.0), PF_R(0.25), PF_R(0.5), PF_R(7.0), PF_R(1e30) };
    size_t i, j;
    int bad = 0;
    pf_real out[1];
    for (i = 0; i < sizeof sigmas / sizeof sigmas[0]; i++)
        for (j = 0; j < sizeof means / sizeof means[0]; j++) {
            pf_vec2 w = pf_gauss_segment_weights(x[3], x[4], means[j], sigmas[i]);
            pf_transfer_moments t = pf_transfer_moments_filter(x, c, 6, means[j], sigmas[i]);
            pf_real s = pf_gauss_smoothstep(PF_R(0.0), PF_R(0.1), means[j], sigmas[i]);
            pf_colormap_filter(x, c, 6, 1, means[j], sigmas[i], out);
            if (!(out[0] >= PF_R(-1e-6) && out[0] <= PF_R(1.0) + PF_R(1e-6))) bad++;
            if (!pf_test_finite(w.x) || !pf_test_finite(w.y) || w.x < PF_R(0.0) || w.y < PF_R(0.0)) bad++;
            if (!in01(s) || !in01(pf_gauss_step(PF_R(0.3), means[j], sigmas[i]))) bad++;
            if (!in01(pf_gauss_cdf(PF_R(0.3), means[j], sigmas[i]))) bad++;
            if (!pf_test_finite(t.g) || !pf_test_finite(t.g2) || !pf_test_finite(t.dg) || !pf_test_finite(t.dg2)) bad++;
            if (!(t.g >= PF_R(-1e-6) && t.g <= PF_R(1.0) + PF_R(1e-6)) || t.g2 < PF_R(0.0) || t.dg2 < PF_R(0.0)) bad++;
        }
    /* one knot: the constant */
    pf_colormap_filter(x, c, 1, 1, PF_R(0.3), PF_R(0.7), out);
    if (!(fabs((double)out[0] - 0.2) < 1e-6)) bad++;
    /* the unfiltered map at a jump: the mean of the two sides */
    pf_colormap_filter(x, c, 6, 1, PF_R(0.0), PF_R(0.0), out);
    if (!(fabs((double)out[0] - 0.65) < 1e-6)) bad++;
    PF_CHECK(bad == 0, "%d bad", bad);
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_log_cdf_both_tails);
    PF_TEST_RUN(test_log1p_series);
    PF_TEST_RUN(test_log1p_small_lambda);
    PF_TEST_RUN(test_visibility_power);
    PF_TEST_RUN(test_closed_forms_quadrature);
    PF_TEST_RUN(test_visibility_average_is_g1);
    PF_TEST_RUN(test_visible_height_exact_tier);
    PF_TEST_RUN(test_visible_height_fits);
    PF_TEST_RUN(test_visible_height_slope_at_zero);
    PF_TEST_RUN(test_integer_lambda_expected_max);
    PF_TEST_RUN(test_colormap_quadrature);
    PF_TEST_RUN(test_step_smoothstep_quadrature);
    PF_TEST_RUN(test_table_vs_closed_form);
    PF_TEST_RUN(test_height_colour_eq13);
    PF_TEST_RUN(test_noise_perturbed_heights);
    PF_TEST_RUN(test_transfer_moments_monte_carlo);
    PF_TEST_RUN(test_visible_height_published_range);
    PF_TEST_RUN(test_mem_table_size);
    PF_TEST_RUN(test_mem_table_far_corner);
    PF_TEST_RUN(test_mem_table_build_guarded);
    PF_TEST_RUN(test_mem_null_and_sizes);
    PF_TEST_RUN(test_mem_filter_channels);
    PF_TEST_RUN(test_mem_table_ranges);
    PF_TEST_RUN(test_mem_nan_inputs);
    PF_TEST_RUN(edge_visibility_extremes);
    PF_TEST_RUN(edge_closed_forms_extremes);
    PF_TEST_RUN(edge_visible_height_extremes);
    PF_TEST_RUN(edge_colormap_degenerate);
    PF_TEST_RUN(edge_transfer_rounding);
    return PF_TEST_END();
}

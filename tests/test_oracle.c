/* test_oracle.c - tests of tests/reference/pf_oracle.h, the long double quadrature every formula test
   is checked against. Each test integrates something whose value is known in closed form (or
   to 25 digits from mpmath, where the closed form would cancel in long double) and asserts a
   relative error bound; the measured error is recorded as a note. The oracle is long double
   in every build, so the bounds do not depend on PF_DOUBLE; -ffast-math builds run only
   edge_oracle_finite (finite, loose).

   The mpmath tables below were made with (mpmath 1.3, mp.dps = 40):
     g(z)       = npdf(z) - z * ncdf(-z)        (Gaussian tail mean for mu = 0, s = 1)
     pdf(z), sf = npdf(z), ncdf(-z)             at dyadic z, so z itself is exact. */
#include "pf_core.h" /* pf_real only, for the harness; the oracle itself uses no include/ code */
#include "pf_test.h"
#include "pf_oracle.h"

#ifndef PF_TEST_PI_L
#  define PF_TEST_PI_L 3.14159265358979323846264338327950288L
#endif

/* ---------------------------------------------------------------- integrands */

static long double f_power(long double x, void *ctx)
{
    const int d = *(const int *)ctx;
    long double p = 1.0L;
    int i;
    for (i = 0; i < d; i++) p *= x;
    return p;
}

static long double f_exp(long double x, void *ctx)
{
    (void)ctx;
    return expl(x);
}

static long double f_cauchy(long double x, void *ctx)
{
    (void)ctx;
    return 1.0L / (1.0L + x * x);
}

static long double f_gauss(long double x, void *ctx)
{
    (void)ctx;
    return expl(-x * x);
}

static long double f_x_gauss(long double x, void *ctx)
{
    (void)ctx;
    return x * expl(-x * x);
}

typedef struct normal_ctx {
    long double mu, s, c;
} normal_ctx;

/* N(x; mu, s) */
static long double f_normal(long double x, void *ctx)
{
    const normal_ctx *n = (const normal_ctx *)ctx;
    return pf_oracle_normal_pdf((x - n->mu) / n->s) / n->s;
}

/* (x - c) N(x; mu, s): the shape of the Smith Lambda integrand */
static long double f_tail_mean(long double x, void *ctx)
{
    const normal_ctx *n = (const normal_ctx *)ctx;
    return (x - n->c) * pf_oracle_normal_pdf((x - n->mu) / n->s) / n->s;
}

/* the same integrand in u = x - c >= 0 with w = u / s: N(c + u) = pdf(z) exp(-w (z + w/2)) / s.
   pdf(z) is formed once from an exact z and the exponent is O(1) where the mass is, so there
   is no rounded large exponent: this is how to write far-tail integrands for the oracle. */
typedef struct tail_u_ctx {
    long double z, s, pdf_z;
} tail_u_ctx;

static long double f_tail_mean_u(long double u, void *ctx)
{
    const tail_u_ctx *t = (const tail_u_ctx *)ctx;
    const long double w = u / t->s;
    return u * t->pdf_z * expl(-w * (t->z + 0.5L * w)) / t->s;
}

static long double f_abs_kink(long double x, void *ctx)
{
    const long double k = *(const long double *)ctx;
    return fabsl(x - k);
}

static long double f_sqrt(long double x, void *ctx)
{
    (void)ctx;
    return sqrtl(x);
}

static long double f_inv_sqrt(long double x, void *ctx)
{
    (void)ctx;
    return 1.0L / sqrtl(x);
}

static long double f_inv(long double x, void *ctx)
{
    (void)ctx;
    return 1.0L / x;
}

/* The error estimate is meant as a bound: the true error of a converged result must not
   exceed it (checked wherever the reference is exact to well below the estimate). */
static void check_estimate(pf_oracle_result r, long double ref, const char *what)
{
    PF_CHECK(fabsl(r.value - ref) <= r.error, "%s: true error %.3g above the estimate %.3g", what,
             (double)fabsl(r.value - ref), (double)r.error);
}

/* ---------------------------------------------------------------- 1D */

/* G15-K31 is exact to degree 47: one interval (max_intervals 1) integrates x^d exactly up to
   d = 47; G15 alone is exact to 29, so there the adaptive call stops after one rule. */
static void test_oracle_polynomials(void)
{
    pf_test_max worst = pf_test_max_init();
    int d, one_rule = 1;
    for (d = 0; d <= 47; d++) {
        pf_oracle_result r = pf_oracle_integrate(f_power, &d, 0.0L, 1.0L, 0.0L, 1e-30L, 1);
        pf_oracle_result s = pf_oracle_integrate(f_power, &d, -1.0L, 2.0L, 0.0L, 1e-17L,
                                                 PF_ORACLE_MAX_INTERVALS);
        long double ref_s = (ldexpl(1.0L, d + 1) - ((d & 1) ? 1.0L : -1.0L)) / (long double)(d + 1);
        long double e1 = pf_test_rel_error(r.value, 1.0L / (long double)(d + 1));
        long double e2 = pf_test_rel_error(s.value, ref_s);
        pf_test_max_update(&worst, e1, (long double)d);
        pf_test_max_update(&worst, e2, (long double)d);
        PF_CHECK(e1 <= 4e-19L, "x^%d on [0,1], one K31 rule: rel err %.3g", d, (double)e1);
        PF_CHECK(s.converged && e2 <= 4e-19L, "x^%d on [-1,2]: rel err %.3g status %s", d,
                 (double)e2, pf_oracle_status_name(s.status));
        if (d <= 29 && s.evals != 31) one_rule = 0;
    }
    PF_CHECK(one_rule, "degree <= 29 should converge after a single rule (31 evaluations)");
    pf_test_note("max rel err %.2g (degree %d)", (double)worst.err, (int)worst.at);
}

static void test_oracle_exp(void)
{
    pf_oracle_result r = pf_oracle_integrate(f_exp, NULL, 0.0L, 1.0L, 0.0L, 1e-17L, 100);
    pf_oracle_result s = pf_oracle_integrate(f_exp, NULL, -3.0L, 40.0L, 0.0L, 1e-17L, 100);
    pf_oracle_result t = pf_oracle_integrate(f_exp, NULL, 1.0L, 0.0L, 0.0L, 1e-17L, 100);
    pf_oracle_result u = pf_oracle_integrate(f_exp, NULL, -HUGE_VALL, 2.0L, 0.0L, 1e-17L, 100);
    long double e1 = pf_test_rel_error(r.value, expm1l(1.0L));
    long double e2 = pf_test_rel_error(s.value, expl(40.0L) - expl(-3.0L));
    long double e3 = pf_test_rel_error(t.value, -expm1l(1.0L));
    long double e4 = pf_test_rel_error(u.value, expl(2.0L));
    PF_CHECK(r.converged && e1 <= 4e-19L, "exp on [0,1]: %.3g", (double)e1);
    PF_CHECK(s.converged && e2 <= 1e-18L, "exp on [-3,40]: %.3g", (double)e2);
    PF_CHECK(t.converged && e3 <= 4e-19L, "exp on [1,0] (reversed): %.3g", (double)e3);
    PF_CHECK(u.converged && e4 <= 1e-18L, "exp on (-inf,2]: %.3g", (double)e4);
    check_estimate(s, expl(40.0L) - expl(-3.0L), "exp on [-3,40]");
    check_estimate(u, expl(2.0L), "exp on (-inf,2]");
    pf_test_note("[0,1] %.2g (%ld evals), [-3,40] %.2g (%ld), (-inf,2] %.2g (%ld)", (double)e1,
                 r.evals, (double)e2, s.evals, (double)e4, u.evals);
}

static void test_oracle_cauchy(void)
{
    const long double pi = PF_TEST_PI_L;
    pf_oracle_result all = pf_oracle_integrate(f_cauchy, NULL, -HUGE_VALL, HUGE_VALL, 0.0L, 1e-17L,
                                               PF_ORACLE_MAX_INTERVALS);
    pf_oracle_result up = pf_oracle_integrate(f_cauchy, NULL, 1.0L, HUGE_VALL, 0.0L, 1e-17L,
                                              PF_ORACLE_MAX_INTERVALS);
    pf_oracle_result lo = pf_oracle_integrate(f_cauchy, NULL, -HUGE_VALL, 0.0L, 0.0L, 1e-17L,
                                              PF_ORACLE_MAX_INTERVALS);
    long double e1 = pf_test_rel_error(all.value, pi);
    long double e2 = pf_test_rel_error(up.value, 0.25L * pi);
    long double e3 = pf_test_rel_error(lo.value, 0.5L * pi);
    PF_CHECK(all.converged && e1 <= 1e-18L, "1/(1+x^2) on R: %.3g %s", (double)e1,
             pf_oracle_status_name(all.status));
    PF_CHECK(up.converged && e2 <= 1e-18L, "on [1,inf): %.3g", (double)e2);
    PF_CHECK(lo.converged && e3 <= 1e-18L, "on (-inf,0]: %.3g", (double)e3);
    check_estimate(all, pi, "1/(1+x^2) on R");
    check_estimate(up, 0.25L * pi, "on [1,inf)");
    pf_test_note("R %.2g (%ld evals), [1,inf) %.2g, (-inf,0] %.2g", (double)e1, all.evals,
                 (double)e2, (double)e3);
}

static void test_oracle_gaussians(void)
{
    const long double sqrt_pi = 1.77245385090551602729816748334114518L;
    const long double at_mu[1] = {50.0L};
    normal_ctx narrow;
    pf_oracle_result g = pf_oracle_integrate(f_gauss, NULL, -HUGE_VALL, HUGE_VALL, 0.0L, 1e-17L,
                                             PF_ORACLE_MAX_INTERVALS);
    pf_oracle_result h, xg;
    long double e1 = pf_test_rel_error(g.value, sqrt_pi), e2, e3 = 0.0L;
    pf_test_max worst = pf_test_max_init();
    int i;
    PF_CHECK(g.converged && e1 <= 1e-18L, "exp(-x^2) on R: %.3g", (double)e1);
    check_estimate(g, sqrt_pi, "exp(-x^2) on R");
    /* a narrow, far peak: found because the mean is passed as a breakpoint. Its accuracy is
       the integrand's, not the rule's: x near 50 is itself rounded to 5e-18 = 3.5e-16 s, so
       the status may honestly be "roundoff" with an error estimate near 1e-16. */
    narrow.mu = 50.0L;
    narrow.s = 0.015625L;
    narrow.c = 0.0L;
    h = pf_oracle_integrate_points(f_normal, &narrow, -HUGE_VALL, HUGE_VALL, at_mu, 1, 0.0L,
                                   1e-17L, PF_ORACLE_MAX_INTERVALS);
    e2 = pf_test_rel_error(h.value, 1.0L);
    PF_CHECK((h.converged || h.status == PF_ORACLE_ROUNDOFF) && e2 <= 1e-16L &&
                 h.error <= 1e-15L,
             "N(50, 1/64) on R with a breakpoint: %.3g, est %.3g %s", (double)e2,
             (double)h.error, pf_oracle_status_name(h.status));
    /* x exp(-x^2) on [a, inf) = exp(-a^2) / 2; for a < 0 the two signs cancel, so the
       tolerance is relative to the integral of |f| (about 1/2) rather than to the value. For
       large a the integrand's own x * x rounding (a^2 eps in the exponent) is the limit. */
    for (i = 0; i < 6; i++) {
        static const long double as[6] = {-3.0L, -0.5L, 0.0L, 1.0L, 5.0L, 20.0L};
        const long double a = as[i];
        const long double ref = 0.5L * expl(-a * a);
        long double e, bound = a < 0.0L ? 1e-18L / ref : 1e-18L * (1.0L + a * a);
        xg = pf_oracle_integrate(f_x_gauss, NULL, a, HUGE_VALL, a < 0.0L ? 1e-18L : 0.0L,
                                 1e-17L, PF_ORACLE_MAX_INTERVALS);
        e = pf_test_rel_error(xg.value, ref);
        pf_test_max_update(&worst, e, a);
        if (a >= 0.0L && e > e3) e3 = e;
        PF_CHECK(xg.converged && e <= bound, "x exp(-x^2) on [%g, inf): %.3g (bound %.3g) %s",
                 (double)a, (double)e, (double)bound, pf_oracle_status_name(xg.status));
    }
    pf_test_note("sqrt(pi) %.2g (%ld evals); N(50,1/64) %.2g (%s); x exp(-x^2) a>=0 %.2g, "
                 "worst %.2g at a=%g",
                 (double)e1, g.evals, (double)e2, pf_oracle_status_name(h.status), (double)e3,
                 (double)worst.err, (double)worst.at);
}

/* integral over [c, inf) of (x - c) N(x; mu, s) dx = s g(z), z = (c - mu) / s,
   g(z) = pdf(z) - z sf(z). Reference g from mpmath (the closed form cancels for z >> 1). */
static void test_oracle_gaussian_tail_mean(void)
{
    static const long double table[10][2] = {
        {-8.0L, 8.000000000000000075502624L},
        {-3.0L, 3.000382154317047723595647L},
        {-1.0L, 1.083315470587686298383063L},
        {0.0L, 0.3989422804014326779399461L},
        {0.5L, 0.1977965574013060295935327L},
        {2.0L, 0.008490702616829637549998926L},
        {5.0L, 5.346165533832814953947797e-8L},
        {10.0L, 7.474560254589328036569033e-25L},
        {20.0L, 1.370012494729579943149012e-90L},
        {30.0L, 1.631956734091401189350489e-199L},
    };
    /* mu and s dyadic so that c = mu + z s is exact */
    static const long double mus[3] = {0.0L, 0.375L, -2.5L};
    static const long double ss[3] = {1.0L, 0.015625L, 8.0L};
    pf_test_max worst = pf_test_max_init(), worst_closed = pf_test_max_init();
    pf_test_max worst_u = pf_test_max_init();
    long evals = 0;
    int i, j, k;
    for (i = 0; i < 10; i++)
        for (j = 0; j < 3; j++)
            for (k = 0; k < 3; k++) {
                normal_ctx n;
                pf_oracle_result r;
                long double ref, e, closed, bound;
                n.mu = mus[j];
                n.s = ss[k];
                n.c = n.mu + table[i][0] * n.s;
                ref = n.s * table[i][1];
                r = pf_oracle_integrate_points(f_tail_mean, &n, n.c, HUGE_VALL, &n.mu, 1, 0.0L,
                                               1e-17L, PF_ORACLE_MAX_INTERVALS);
                e = pf_test_rel_error(r.value, ref);
                /* the integrand itself rounds x near c and then (x - mu) / s: about
                   z eps |c| / s of noise in the exponent, which the oracle may report as
                   "roundoff" (its error estimate must then be within that bound) */
                bound = 1e-18L + 2e-19L * fabsl(table[i][0]) * (1.0L + fabsl(n.c) / n.s);
                pf_test_max_update(&worst, e, table[i][0]);
                evals += r.evals;
                PF_CHECK((r.converged || (r.status == PF_ORACLE_ROUNDOFF &&
                                          r.error <= 10.0L * bound * ref)) &&
                             e <= bound,
                         "z=%g mu=%g s=%g: rel err %.3g (bound %.3g), est %.3g %s",
                         (double)table[i][0], (double)n.mu, (double)n.s, (double)e,
                         (double)bound, (double)(r.error / ref), pf_oracle_status_name(r.status));
                /* in u = x - c the same integral has no such noise: full accuracy */
                {
                    tail_u_ctx tu;
                    long double mode_u = -table[i][0] * n.s; /* the mean, when z < 0 */
                    tu.z = table[i][0];
                    tu.s = n.s;
                    tu.pdf_z = pf_oracle_normal_pdf(tu.z);
                    r = pf_oracle_integrate_points(f_tail_mean_u, &tu, 0.0L, HUGE_VALL, &mode_u,
                                                   1, 0.0L, 1e-17L, PF_ORACLE_MAX_INTERVALS);
                    e = pf_test_rel_error(r.value, ref);
                    pf_test_max_update(&worst_u, e, table[i][0]);
                    PF_CHECK(r.converged && e <= 5e-19L, "u form z=%g s=%g: %.3g %s",
                             (double)table[i][0], (double)n.s, (double)e,
                             pf_oracle_status_name(r.status));
                    check_estimate(r, ref, "u form");
                }
                if (table[i][0] <= 2.0L) { /* the closed form is fine where it does not cancel */
                    const long double z = table[i][0];
                    closed = n.s * pf_oracle_normal_pdf(z) - (n.c - n.mu) * pf_oracle_normal_sf(z);
                    e = pf_test_rel_error(closed, ref);
                    pf_test_max_update(&worst_closed, e, z);
                    PF_CHECK(e <= 1e-18L, "closed form at z=%g: %.3g", (double)z, (double)e);
                }
            }
    pf_test_note("x form max rel err %.2g (z=%g), %ld evals for 90; u form max %.2g (z=%g); "
                 "closed form z<=2 %.2g",
                 (double)worst.err, (double)worst.at, evals, (double)worst_u.err,
                 (double)worst_u.at, (double)worst_closed.err);
}

/* Random means, scales and tail points with the closed-form reference (z <= 2, no
   cancellation), fixed seed. */
static void test_oracle_gaussian_tail_random(void)
{
    pf_test_rng rng = pf_test_rng_seed(20240611ULL);
    pf_test_max worst = pf_test_max_init();
    int i;
    for (i = 0; i < 40; i++) {
        normal_ctx n;
        pf_oracle_result r;
        long double z, ref, e;
        n.mu = (long double)pf_test_uniform(&rng, -3.0, 3.0);
        n.s = (long double)pf_test_log_uniform(&rng, 0.01, 100.0);
        n.c = n.mu + (long double)pf_test_uniform(&rng, -6.0, 2.0) * n.s;
        z = (n.c - n.mu) / n.s;
        ref = n.s * pf_oracle_normal_pdf(z) - (n.c - n.mu) * pf_oracle_normal_sf(z);
        r = pf_oracle_integrate_points(f_tail_mean, &n, n.c, HUGE_VALL, &n.mu, 1, 0.0L, 1e-17L,
                                       PF_ORACLE_MAX_INTERVALS);
        e = pf_test_rel_error(r.value, ref);
        pf_test_max_update(&worst, e, z);
        PF_CHECK(r.converged && e <= 4e-18L, "mu=%g s=%g z=%g: %.3g", (double)n.mu,
                 (double)n.s, (double)z, (double)e);
    }
    pf_test_note("40 random (mu, s, z in [-6,2]): max rel err %.2g", (double)worst.err);
}

static void test_oracle_kink_breakpoint(void)
{
    long double k = 0.3L;
    const long double ref = 0.5L * (k * k + (1.0L - k) * (1.0L - k));
    pf_oracle_result with = pf_oracle_integrate_points(f_abs_kink, &k, 0.0L, 1.0L, &k, 1, 0.0L,
                                                       1e-17L, PF_ORACLE_MAX_INTERVALS);
    pf_oracle_result without = pf_oracle_integrate(f_abs_kink, &k, 0.0L, 1.0L, 0.0L, 1e-17L,
                                                   PF_ORACLE_MAX_INTERVALS);
    const long double pts[4] = {2.0L, 0.3L, -1.0L, 0.3L}; /* outside, duplicate: ignored */
    pf_oracle_result messy = pf_oracle_integrate_points(f_abs_kink, &k, 0.0L, 1.0L, pts, 4, 0.0L,
                                                        1e-17L, PF_ORACLE_MAX_INTERVALS);
    long double e1 = pf_test_rel_error(with.value, ref);
    long double e2 = pf_test_rel_error(without.value, ref);
    long double e3 = pf_test_rel_error(messy.value, ref);
    PF_CHECK(with.converged && e1 <= 4e-19L && with.evals == 62,
             "|x-0.3| with breakpoint: %.3g, %ld evals", (double)e1, with.evals);
    PF_CHECK(messy.converged && e3 <= 4e-19L && messy.evals == 62,
             "unsorted/duplicate/outside points: %.3g, %ld evals", (double)e3, messy.evals);
    PF_CHECK(without.converged && e2 <= 1e-17L, "|x-0.3| without breakpoint: %.3g %s",
             (double)e2, pf_oracle_status_name(without.status));
    check_estimate(without, ref, "|x-0.3| without breakpoint");
    pf_test_note("with point %.2g (%ld evals); without %.2g (%ld evals)", (double)e1, with.evals,
                 (double)e2, without.evals);
}

static void test_oracle_endpoint_singularities(void)
{
    pf_oracle_result s = pf_oracle_integrate(f_sqrt, NULL, 0.0L, 1.0L, 0.0L, 1e-17L,
                                             PF_ORACLE_MAX_INTERVALS);
    pf_oracle_result t = pf_oracle_integrate(f_inv_sqrt, NULL, 0.0L, 1.0L, 0.0L, 1e-15L,
                                             PF_ORACLE_MAX_INTERVALS);
    long double e1 = pf_test_rel_error(s.value, 2.0L / 3.0L);
    long double e2 = pf_test_rel_error(t.value, 2.0L);
    PF_CHECK(s.converged && e1 <= 1e-18L, "sqrt(x) on [0,1]: %.3g %s", (double)e1,
             pf_oracle_status_name(s.status));
    PF_CHECK(t.converged && e2 <= 1e-15L, "1/sqrt(x) on [0,1]: %.3g %s", (double)e2,
             pf_oracle_status_name(t.status));
    check_estimate(s, 2.0L / 3.0L, "sqrt(x)");
    check_estimate(t, 2.0L, "1/sqrt(x)");
    pf_test_note("sqrt %.2g (%d intervals), 1/sqrt %.2g (%d intervals)", (double)e1, s.intervals,
                 (double)e2, t.intervals);
}

/* The status must say "not converged" whenever the answer is not trustworthy. */
static void test_oracle_status(void)
{
    const long double nan_l = (long double)NAN;
    pf_oracle_result r = pf_oracle_integrate(f_sqrt, NULL, 0.0L, 1.0L, 0.0L, 1e-17L, 3);
    pf_oracle_result ro = pf_oracle_integrate(f_exp, NULL, 0.0L, 1.0L, 0.0L, 1e-25L, 100);
    pf_oracle_result nf = pf_oracle_integrate(f_inv, NULL, -1.0L, 1.0L, 0.0L, 1e-17L, 100);
    pf_oracle_result bad = pf_oracle_integrate(f_exp, NULL, nan_l, 1.0L, 0.0L, 1e-17L, 100);
    pf_oracle_result zero = pf_oracle_integrate(f_exp, NULL, 2.0L, 2.0L, 0.0L, 1e-17L, 100);
    PF_CHECK(!r.converged && r.status == PF_ORACLE_MAX_INTERVALS_HIT && r.intervals == 3,
             "budget of 3 intervals: converged %d status %s", r.converged,
             pf_oracle_status_name(r.status));
    PF_CHECK(r.error > 1e-17L * r.value, "error estimate %.3g should exceed the tolerance",
             (double)r.error);
    PF_CHECK(!ro.converged && ro.status == PF_ORACLE_ROUNDOFF, "epsrel 1e-25: %s",
             pf_oracle_status_name(ro.status));
    PF_CHECK(pf_test_rel_error(ro.value, expm1l(1.0L)) <= 4e-19L, "roundoff value still good");
    PF_CHECK(!nf.converged && nf.status == PF_ORACLE_NONFINITE && nf.value != nf.value,
             "1/x through 0: %s", pf_oracle_status_name(nf.status));
    PF_CHECK(!bad.converged && bad.status == PF_ORACLE_BAD_INPUT, "NaN limit: %s",
             pf_oracle_status_name(bad.status));
    PF_CHECK(zero.converged && zero.value == 0.0L, "empty interval");
    pf_test_note("budget 3: err est %.2g; 1e-25: %s; 1/x: %s", (double)r.error,
                 pf_oracle_status_name(ro.status), pf_oracle_status_name(nf.status));
}

/* ---------------------------------------------------------------- normal distribution */

static void test_oracle_normal(void)
{
    /* z, pdf(z), sf(z) from mpmath */
    static const long double table[14][3] = {
        {-37.5L, 1.728233732284105220750793e-306L, 1.0L},
        {-25.75L, 4.156402643203555137901632e-145L, 1.0L},
        {-7.3125L, 9.760460197708042623281595e-13L, 0.9999999999998688913604866L},
        {-1.25L, 0.1826490853890219049910446L, 0.8943502263331447423112272L},
        {-0.3125L, 0.3799306061986277553774003L, 0.6226697184701570868332182L},
        {0.0L, 0.3989422804014326779399461L, 0.5L},
        {0.09375L, 0.3971929626143237918915459L, 0.4626538754446733004174766L},
        {1.6875L, 0.09606150090511334837631999L, 0.04575362496174111296969393L},
        {3.3125L, 0.001652829422406257968233905L, 0.0004623306301886042955862413L},
        {7.3125L, 9.760460197708042623281595e-13L, 1.311086395133530841512325e-13L},
        {12.875L, 4.030528092011815975117219e-37L, 3.111953998908736113498518e-38L},
        {25.703125L, 1.388185467290769104045401e-144L, 5.392704963405193796193618e-146L},
        {33.296875L, 7.1399915190444198565056e-242L, 2.142413903683084996039439e-243L},
        {37.125L, 2.062207198961653773548112e-300L, 5.550745348099386362054099e-302L},
    };
    pf_test_max worst = pf_test_max_init();
    int i;
    for (i = 0; i < 14; i++) {
        const long double z = table[i][0];
        long double e_pdf = pf_test_rel_error(pf_oracle_normal_pdf(z), table[i][1]);
        long double e_sf = pf_test_rel_error(pf_oracle_normal_sf(z), table[i][2]);
        long double e_cdf = pf_test_rel_error(pf_oracle_normal_cdf(-z), table[i][2]);
        pf_test_max_update(&worst, e_pdf, z);
        pf_test_max_update(&worst, e_sf, z);
        pf_test_max_update(&worst, e_cdf, z);
        PF_CHECK(e_pdf <= 4e-19L && e_sf <= 4e-19L && e_cdf <= 4e-19L,
                 "z=%g: pdf %.3g sf %.3g cdf(-z) %.3g", (double)z, (double)e_pdf, (double)e_sf,
                 (double)e_cdf);
        /* the oracle resolves pf_real's last place: rounding it lands within half an ulp,
           where pf_real does not underflow */
        if (table[i][2] > 1e-30L) {
            long double u = pf_test_ulp_error((pf_real)pf_oracle_normal_sf(z), table[i][2]);
            PF_CHECK(u <= 0.5L, "sf rounded to pf_real: %.3g ulp", (double)u);
        }
    }
    PF_CHECK(pf_oracle_normal_pdf(HUGE_VALL) == 0.0L && pf_oracle_normal_sf(HUGE_VALL) == 0.0L &&
                 pf_oracle_normal_cdf(HUGE_VALL) == 1.0L,
             "infinite arguments");
    pf_test_note("max rel err %.2g at z=%g", (double)worst.err, (double)worst.at);
}

/* ---------------------------------------------------------------- 2D */

/* Correlated bivariate normal with means (mx, my), deviations (sx, sy), correlation rho;
   mode selects the weight: 0 density, 1 x, 2 y, 3 (x-mx)(y-my), 4 (x-mx)^2. */
typedef struct binormal {
    long double mx, my, sx, sy, rho, c;
    int mode;
} binormal;

static long double f_binormal(long double x, long double y, void *ctx)
{
    const binormal *b = (const binormal *)ctx;
    const long double u = (x - b->mx) / b->sx, v = (y - b->my) / b->sy;
    const long double one_r2 = 1.0L - b->rho * b->rho;
    const long double q = (u * u - 2.0L * b->rho * u * v + v * v) / one_r2;
    const long double pdf = expl(-0.5L * q) /
                            (2.0L * PF_TEST_PI_L * b->sx * b->sy * sqrtl(one_r2));
    switch (b->mode) {
    case 1: return x * pdf;
    case 2: return y * pdf;
    case 3: return (x - b->mx) * (y - b->my) * pdf;
    case 4: return (x - b->mx) * (x - b->mx) * pdf;
    default: return pdf;
    }
}

/* inner breakpoint: the conditional mean of y given x */
static int binormal_ypoints(long double x, long double *pts, int max_points, void *ctx)
{
    const binormal *b = (const binormal *)ctx;
    if (max_points < 1) return 0;
    pts[0] = b->my + b->rho * b->sy / b->sx * (x - b->mx);
    return 1;
}

/* half-plane x + 2 y > c: y > (c - x) / 2 */
static long double halfplane_ylo(long double x, void *ctx)
{
    const binormal *b = (const binormal *)ctx;
    return 0.5L * (b->c - x);
}

static void test_oracle_2d_binormal(void)
{
    binormal b;
    pf_oracle_2d pb = pf_oracle_2d_make(f_binormal, &b, -HUGE_VALL, HUGE_VALL, -HUGE_VALL,
                                        HUGE_VALL);
    long double refs[5], errs[5], var, mean, z, e_half;
    pf_oracle_result r[5], half;
    long evals = 0;
    int m;
    b.mx = 0.4L;
    b.my = -0.2L;
    b.sx = 1.3L;
    b.sy = 0.7L;
    b.rho = 0.6L;
    b.c = 1.5L;
    pb.xpoints = &b.mx;
    pb.nxpoints = 1;
    pb.ypoints = binormal_ypoints;
    pb.epsrel = 1e-16L;
    refs[0] = 1.0L;
    refs[1] = b.mx;
    refs[2] = b.my;
    refs[3] = b.rho * b.sx * b.sy;
    refs[4] = b.sx * b.sx;
    for (m = 0; m < 5; m++) {
        b.mode = m;
        r[m] = pf_oracle_integrate_2d(&pb);
        errs[m] = pf_test_rel_error(r[m].value, refs[m]);
        evals += r[m].evals;
        PF_CHECK(r[m].converged && errs[m] <= 1e-17L, "moment %d: %.3g %s", m, (double)errs[m],
                 pf_oracle_status_name(r[m].status));
        check_estimate(r[m], refs[m], "bivariate normal moment");
    }
    /* P(x + 2y > c): x + 2y ~ N(mx + 2 my, sx^2 + 4 sy^2 + 4 rho sx sy) */
    b.mode = 0;
    pb.ylo = halfplane_ylo;
    pb.ypoints = NULL;
    half = pf_oracle_integrate_2d(&pb);
    mean = b.mx + 2.0L * b.my;
    var = b.sx * b.sx + 4.0L * b.sy * b.sy + 4.0L * b.rho * b.sx * b.sy;
    z = (b.c - mean) / sqrtl(var);
    e_half = pf_test_rel_error(half.value, pf_oracle_normal_sf(z));
    evals += half.evals;
    PF_CHECK(half.converged && e_half <= 1e-17L, "half-plane: %.3g %s", (double)e_half,
             pf_oracle_status_name(half.status));
    pf_test_note("mass %.2g, E[x] %.2g, E[y] %.2g, cov %.2g, var %.2g, half-plane %.2g; "
                 "%ld evals",
                 (double)errs[0], (double)errs[1], (double)errs[2], (double)errs[3],
                 (double)errs[4], (double)e_half, evals);
}

static long double f_one(long double x, long double y, void *ctx)
{
    (void)x;
    (void)y;
    (void)ctx;
    return 1.0L;
}

static long double f_xx(long double x, long double y, void *ctx)
{
    (void)y;
    (void)ctx;
    return x * x;
}

static long double disc_lo(long double x, void *ctx)
{
    (void)ctx;
    return -sqrtl(fmaxl(0.0L, 1.0L - x * x));
}

static long double disc_hi(long double x, void *ctx)
{
    (void)ctx;
    return sqrtl(fmaxl(0.0L, 1.0L - x * x));
}

static void test_oracle_2d_disc(void)
{
    pf_oracle_2d pb = pf_oracle_2d_make(f_one, NULL, -1.0L, 1.0L, 0.0L, 0.0L);
    pf_oracle_result area, mom, tiny;
    long double e1, e2;
    pb.ylo = disc_lo;
    pb.yhi = disc_hi;
    pb.epsrel = 1e-17L;
    pb.max_intervals = PF_ORACLE_MAX_INTERVALS;
    area = pf_oracle_integrate_2d(&pb);
    pb.f = f_xx;
    mom = pf_oracle_integrate_2d(&pb);
    e1 = pf_test_rel_error(area.value, PF_TEST_PI_L);
    e2 = pf_test_rel_error(mom.value, 0.25L * PF_TEST_PI_L);
    PF_CHECK(area.converged && e1 <= 1e-18L, "disc area: %.3g %s", (double)e1,
             pf_oracle_status_name(area.status));
    PF_CHECK(mom.converged && e2 <= 1e-18L, "disc x^2 moment: %.3g %s", (double)e2,
             pf_oracle_status_name(mom.status));
    check_estimate(area, PF_TEST_PI_L, "disc area");
    check_estimate(mom, 0.25L * PF_TEST_PI_L, "disc x^2");
    /* an inner budget too small is reported */
    {
        binormal b;
        pf_oracle_2d pn = pf_oracle_2d_make(f_binormal, &b, -HUGE_VALL, HUGE_VALL, -HUGE_VALL,
                                            HUGE_VALL);
        b.mx = b.my = 0.0L;
        b.sx = b.sy = 1.0L;
        b.rho = 0.9L;
        b.c = 0.0L;
        b.mode = 0;
        pn.max_intervals = 2;
        tiny = pf_oracle_integrate_2d(&pn);
        PF_CHECK(!tiny.converged, "budget 2 for a rho=0.9 normal: status %s",
                 pf_oracle_status_name(tiny.status));
    }
    pf_test_note("area %.2g (%d outer intervals, %ld evals), x^2 %.2g; tiny budget: %s",
                 (double)e1, area.intervals, area.evals, (double)e2,
                 pf_oracle_status_name(tiny.status));
}

/* ---------------------------------------------------------------- fast-math safe */

/* Finite intervals only (no infinities under -ffinite-math-only), loose bounds. */
static void edge_oracle_finite(void)
{
    int d = 3;
    pf_oracle_result r = pf_oracle_integrate(f_power, &d, 0.0L, 2.0L, 0.0L, 1e-12L, 100);
    pf_real pdf = (pf_real)pf_oracle_normal_pdf(1.0L);
    pf_real sf = (pf_real)pf_oracle_normal_sf(3.0L);
    PF_CHECK(r.converged && pf_test_rel_error(r.value, 4.0L) <= 1e-12L, "x^3 on [0,2]: %Lg",
             r.value);
    PF_CHECK(pf_test_finite(pdf) && pf_test_finite(sf), "normal pdf / sf finite");
    PF_CHECK(pf_test_rel_error((long double)sf, 0.001349898031630094526651814L) <= 1e-6L,
             "sf(3) = %g", (double)sf);
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_oracle_polynomials);
    PF_TEST_RUN(test_oracle_exp);
    PF_TEST_RUN(test_oracle_cauchy);
    PF_TEST_RUN(test_oracle_gaussians);
    PF_TEST_RUN(test_oracle_gaussian_tail_mean);
    PF_TEST_RUN(test_oracle_gaussian_tail_random);
    PF_TEST_RUN(test_oracle_kink_breakpoint);
    PF_TEST_RUN(test_oracle_endpoint_singularities);
    PF_TEST_RUN(test_oracle_status);
    PF_TEST_RUN(test_oracle_normal);
    PF_TEST_RUN(test_oracle_2d_binormal);
    PF_TEST_RUN(test_oracle_2d_disc);
    PF_TEST_RUN(edge_oracle_finite);
    return PF_TEST_END();
}

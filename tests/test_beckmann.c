/* test_beckmann.c - tests of include/pf_beckmann.h against quadrature and brute force.

   The oracles never call the formula they check with itself:
   - D is integrated numerically (tests/reference/pf_oracle.h, long double) over the hemisphere, once in
     polar coordinates of the micro-normal and once over the slope plane in whitened
     coordinates (the Cholesky factor and the solid-angle Jacobian m_z^3 are the test's own);
   - the projected-area identity (Dupuy et al. 2013 eqs. 1, 6) and the BRDF identity after
     eq. 16 are integrals of the library's D against the library's Lambda and projected area:
     they can only hold together if all three are right;
   - the BRDF identity integrates over the whole sphere of light directions in polar
     coordinates around the mirror direction (no half-vector change of variables);
   - eq. 12 is checked against sample moments of transformed Gaussian slopes (fixed seed);
   - the centered case against the textbook anisotropic Beckmann D and Smith G1 in long double.
   The same bodies run in float, double, C++ and under sanitizers; edge_* tests also run under
   -ffast-math. */
#include <string.h>
#include "pf_beckmann.h"
#include "pf_oracle.h"
#include "pf_test.h"


/* ------------------------------------------------------------------ configurations */
/* A slope distribution (mean, covariance) and a view, in long double, rounded to pf_real so
   the references see the library's inputs. */
typedef struct bcfg {
    long double mx, my, vx, vy, cxy;
} bcfg;

static bcfg bcfg_round(bcfg k)
{
    k.mx = (long double)(pf_real)k.mx;
    k.my = (long double)(pf_real)k.my;
    k.vx = (long double)(pf_real)k.vx;
    k.vy = (long double)(pf_real)k.vy;
    k.cxy = (long double)(pf_real)k.cxy;
    return k;
}

static pf_slope_stats bcfg_stats(bcfg k)
{
    return pf_slope_stats_make((pf_real)k.mx, (pf_real)k.my, (pf_real)k.vx, (pf_real)k.vy, (pf_real)k.cxy);
}

/* Random configurations by kind: 0 moderate, 1 strong anisotropy (ratio up to 100),
   2 |r| near 1 (0.99 ... 0.9999), 3 large mean slopes (|mean| 2 ... 4), 4 tiny sigma (1e-3). */
#define N_KINDS 5
static const char *kind_name[N_KINDS] = {"moderate", "anisotropic", "|r|->1", "mean>2", "tiny sigma"};

static bcfg bcfg_random(pf_test_rng *rng, int kind)
{
    bcfg k;
    long double sx = (long double)pf_test_log_uniform(rng, 0.05, 0.8);
    long double sy = (long double)pf_test_log_uniform(rng, 0.05, 0.8);
    long double r = (long double)pf_test_uniform(rng, -0.9, 0.9);
    long double a = (long double)pf_test_uniform(rng, -3.14159, 3.14159);
    long double mm = (long double)pf_test_uniform(rng, 0.0, 0.8);
    if (kind == 1) {
        sx = (long double)pf_test_log_uniform(rng, 0.3, 1.0);
        sy = sx / (long double)pf_test_log_uniform(rng, 20.0, 100.0);
    } else if (kind == 2) {
        r = 1.0L - (long double)pf_test_log_uniform(rng, 1e-4, 1e-2);
        if (pf_test_uniform(rng, 0.0, 1.0) < 0.5) r = -r;
    } else if (kind == 3) {
        mm = (long double)pf_test_uniform(rng, 2.0, 4.0);
    } else if (kind == 4) {
        sx = (long double)pf_test_log_uniform(rng, 1e-3, 3e-3);
        sy = (long double)pf_test_log_uniform(rng, 1e-3, 3e-3);
    }
    k.mx = mm * cosl(a);
    k.my = mm * sinl(a);
    k.vx = sx * sx;
    k.vy = sy * sy;
    k.cxy = r * sx * sy;
    return bcfg_round(k);
}

static bcfg centered_cfg(long double sx, long double sy)
{
    bcfg k;
    k.mx = k.my = k.cxy = 0.0L;
    k.vx = sx * sx;
    k.vy = sy * sy;
    return bcfg_round(k);
}

/* Cholesky factor of the covariance, [[a, 0], [b, c]] (the test's own). */
typedef struct chol2 {
    long double a, b, c;
} chol2;

static chol2 chol_of(bcfg k)
{
    chol2 L;
    L.a = sqrtl(k.vx);
    L.b = k.cxy / L.a;
    L.c = sqrtl(fmaxl(k.vy - L.b * L.b, 0.0L));
    return L;
}

/* Condition number of D (eq. 10) at a micro-normal whose slope is (sx, sy) and whose
   whitened squared distance to the mean is 2q: the relative error of D in pf_real is a few eps
   times this. The exponent q amplifies relative rounding; var_x var_y - c^2 loses
   1/(1 - r^2) of its relative precision; and a direction rounded to pf_real moves the slope by
   ~ (1 + |slope|) eps, which moves the exponent by sqrt(2q) (1 + |slope|) eps / sigma_min. */
static long double d_cond(bcfg k, long double q, long double sx, long double sy)
{
    long double r2 = k.cxy * k.cxy / (k.vx * k.vy);
    long double smin = sqrtl(fminl(k.vx, k.vy) * (1.0L - r2));
    return (1.0L + q) * (1.0L + 1.0L / (1.0L - r2) + (1.0L + sqrtl(sx * sx + sy * sy)) * sqrtl(2.0L * q) / smin);
}

/* Independent P22 (eq. 8) in long double (tests/reference/pf_oracle.h: explicit inverse). */
static long double p22_ref(bcfg k, long double x, long double y)
{
    return pf_oracle_normal2_pdf(x - k.mx, y - k.my, k.vx, k.vy, k.cxy);
}

static pf_vec3 vec3_of(long double x, long double y, long double z)
{
    return pf_vec3_make((pf_real)x, (pf_real)y, (pf_real)z);
}

/* ------------------------------------------------------------------ D: pointwise */
/* D against the independent long double P22 / cos^4 at random micro-normals drawn around the
   peak (within 4 sigma), for every kind of configuration. The error of D in pf_real grows
   with the exponent q/2 (its rounding is amplified by exp): the bound is stated relative to
   (1 + q/2). */
static void test_d_pointwise(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec30001ULL);
    pf_test_max m = pf_test_max_init(), mp = pf_test_max_init();
    int i;
    for (i = 0; i < 20000; i++) {
        bcfg k = bcfg_random(&rng, i % N_KINDS);
        chol2 L = chol_of(k);
        long double u = (long double)pf_test_uniform(&rng, -4.0, 4.0);
        long double v = (long double)pf_test_uniform(&rng, -4.0, 4.0);
        long double x = k.mx + L.a * u, y = k.my + L.b * u + L.c * v;
        long double len = sqrtl(x * x + y * y + 1.0L);
        pf_vec3 mf = vec3_of(-x / len, -y / len, 1.0L / len);
        /* the reference sees the rounded direction */
        long double mx = (long double)mf.x, my = (long double)mf.y, mz = (long double)mf.z;
        long double ml = sqrtl(mx * mx + my * my + mz * mz);
        long double cz = mz / ml;
        long double sx = -mx / mz, sy = -my / mz;
        long double ref = p22_ref(k, sx, sy) / (cz * cz * cz * cz);
        long double q = 0.5L * (u * u + v * v);
        long double e = pf_test_rel_error((long double)pf_beckmann_d(mf, bcfg_stats(k)), ref);
        /* the condition number of the slope in terms of the direction: |slope - mean| / sigma
           divides the rounding of the direction's components (~ (1 + |slope|) eps) */
        long double r2 = k.cxy * k.cxy / (k.vx * k.vy);
        long double cond = d_cond(k, q, sx, sy);
        pf_test_max_update(&m, e / cond, (long double)(i % N_KINDS));
        pf_test_max_update(&mp, pf_test_rel_error((long double)pf_beckmann_p22((pf_real)x, (pf_real)y, bcfg_stats(k)),
                                                  p22_ref(k, (long double)(pf_real)x, (long double)(pf_real)y)) /
                                    ((1.0L + q) * (1.0L + 1.0L / (1.0L - r2))),
                           (long double)(i % N_KINDS));
    }
    pf_test_note("D vs long double P22/cos^4, 20000 points within 4 sigma: max rel error %.3g eps x "
                 "(1 + q/2)(1 + 1/(1 - r^2) + (1 + |slope|) sqrt(q) / sigma_min) (kind %s)",
                 (double)(m.err / PF_TEST_EPS), kind_name[(int)m.at]);
    pf_test_note("P22: max rel error %.3g eps x (1 + q/2)(1 + 1/(1 - r^2))", (double)(mp.err / PF_TEST_EPS));
    PF_CHECK(m.err <= 16.0L * PF_TEST_EPS, "D pointwise: %.3g eps-units (kind %d)", (double)(m.err / PF_TEST_EPS), (int)m.at);
    PF_CHECK(mp.err <= 16.0L * PF_TEST_EPS, "P22 pointwise: %.3g eps-units (kind %d)", (double)(mp.err / PF_TEST_EPS), (int)mp.at);
}

/* ------------------------------------------------------------------ normalization */
/* integral D(m) (m . g) dm over the hemisphere, in whitened slope coordinates (u, v):
   slope = mean + L (u, v), dm = m_z^3 d slope, d slope = a c du dv. */
typedef struct norm_ctx {
    bcfg k;
    chol2 L;
    pf_slope_stats s;
    long double wx, wy, wz; /* view, for the projected-area integrand */
    int weight_by_view;     /* 1: max(0, w_o . m) D(m); 2, 3, 4: light directions, see below */
    long double ca, sa;     /* rotation of the whitened plane (set by whitened_integral) */
} norm_ctx;

static long double whitened_integrand(long double ur, long double vr, void *ctx)
{
    const norm_ctx *c = (const norm_ctx *)ctx;
    long double u = c->ca * ur - c->sa * vr, v = c->sa * ur + c->ca * vr;
    long double x = c->k.mx + c->L.a * u, y = c->k.my + c->L.b * u + c->L.c * v;
    long double len = sqrtl(x * x + y * y + 1.0L);
    long double mz = 1.0L / len;
    long double d = (long double)pf_beckmann_d(vec3_of(-x / len, -y / len, mz), c->s);
    long double w = mz; /* m . g */
    if (c->weight_by_view >= 2) {
        /* m is the half vector of w_o and w_i = 2 (m . w_o) m - w_o (LEADR eq. 18):
           d w_i = 4 (m . w_o) d m. The function under test gets (w_o, w_i) and finds the
           half vector itself. 2: D(w_o + w_i)/4 (the identity after eq. 16); 3: the joint
           LEADR value; 4: masking only. */
        long double mxl = -x * mz, myl = -y * mz, ho = c->wx * mxl + c->wy * myl + c->wz * mz, f;
        pf_vec3 wo = vec3_of(c->wx, c->wy, c->wz);
        pf_vec3 wi = vec3_of(2.0L * ho * mxl - c->wx, 2.0L * ho * myl - c->wy, 2.0L * ho * mz - c->wz);
        if (ho <= 0.0L) return 0.0L;
        if (c->weight_by_view == 2)
            f = (long double)pf_beckmann_d(pf_vec3_add(wo, wi), c->s) / 4.0L;
        else if (c->weight_by_view == 3)
            f = (long double)pf_leadr_specular(wo, wi, c->s, PF_R(1.0));
        else
            f = (long double)pf_leadr_specular_masking(wo, wi, c->s, PF_R(1.0));
        return f * 4.0L * ho * mz * mz * mz * c->L.a * c->L.c;
    }
    if (c->weight_by_view) {
        w = (-c->wx * x - c->wy * y + c->wz) * mz; /* m . w_o */
        if (w <= 0.0L) return 0.0L;
    }
    return d * w * mz * mz * mz * c->L.a * c->L.c;
}

static pf_oracle_result whitened_integral(norm_ctx *c, long double epsrel)
{
    /* |u|, |v| <= 12: the Gaussian mass outside is below 1e-30 */
    pf_oracle_2d pb;
    long double xp[2];
    int nx = 0;
    c->ca = 1.0L;
    c->sa = 0.0L;
    if (c->weight_by_view) {
        /* rotate the whitened plane (the Gaussian is invariant) so that the line m . w_o = 0,
           alpha u + beta v = gamma, becomes u' = gamma / n: one clean outer breakpoint */
        long double al = c->wx * c->L.a + c->wy * c->L.b, be = c->wy * c->L.c;
        long double ga = c->wz - c->wx * c->k.mx - c->wy * c->k.my, n = sqrtl(al * al + be * be);
        if (n > 0.0L) {
            c->ca = al / n;
            c->sa = be / n;
            if (fabsl(ga / n) < 12.0L) xp[nx++] = ga / n;
        }
    }
    pb = pf_oracle_2d_make(whitened_integrand, c, -12.0L, 12.0L, -12.0L, 12.0L);
    pb.xpoints = xp;
    pb.nxpoints = nx;
    pb.epsrel = epsrel;
    pb.max_intervals = c->weight_by_view == 1 ? 1500 : 400;
    return pf_oracle_integrate_2d(&pb);
}

/* The bound on the integral's error in pf_real: D's rounding integrated (see
   test_d_pointwise), which grows as 1/sigma_min for a rounded direction. */
static long double norm_bound(bcfg k)
{
    long double smin = sqrtl(fminl(k.vx, k.vy) * (1.0L - k.cxy * k.cxy / (k.vx * k.vy)));
    long double mean = sqrtl(k.mx * k.mx + k.my * k.my);
    long double r2 = k.cxy * k.cxy / (k.vx * k.vy);
    return 64.0L * PF_TEST_EPS * (1.0L + 1.0L / (1.0L - r2) + (1.0L + mean) / smin) + 1e-12L;
}

/* A quadrature is good enough when its error estimate is a quarter of the bound checked: the
   integrands carry pf_real's rounding noise, which the adaptive rule cannot integrate to
   long double precision, so "converged" to epsrel is not the criterion. */
static int quad_ok(pf_oracle_result r, bcfg k)
{
    return r.converged || r.error <= 0.5L * norm_bound(k) * fabsl(r.value);
}

static void test_normalization_slope_plane(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec30002ULL);
    pf_test_max m[N_KINDS];
    int i, kind, bad = 0;
    for (kind = 0; kind < N_KINDS; kind++) m[kind] = pf_test_max_init();
    for (i = 0; i < 30; i++) {
        norm_ctx c;
        pf_oracle_result r;
        kind = i % N_KINDS;
        c.k = bcfg_random(&rng, kind);
        c.L = chol_of(c.k);
        c.s = bcfg_stats(c.k);
        c.weight_by_view = 0;
        c.wx = c.wy = 0.0L;
        c.wz = 1.0L;
        r = whitened_integral(&c, fmaxl(norm_bound(c.k) / 16.0L, 1e-13L));
        if (!quad_ok(r, c.k)) bad++;
        pf_test_max_update(&m[kind], fabsl(r.value - 1.0L) / norm_bound(c.k), (long double)i);
    }
    for (kind = 0; kind < N_KINDS; kind++) {
        pf_test_note("integral D (m.g) dm - 1, slope-plane quadrature, %-11s: max %.3g of the bound "
                     "64 eps (1 + 1/(1 - r^2) + (1 + |mean|)/sigma_min)",
                     kind_name[kind], (double)m[kind].err);
        PF_CHECK(m[kind].err <= 1.0L, "normalization (%s): %.3g of bound", kind_name[kind], (double)m[kind].err);
    }
    PF_CHECK(bad == 0, "%d quadratures did not converge", bad);
}

/* The same in polar coordinates (t, p) of the micro-normal, dm = sin t dt dp, with breakpoints
   at the peak: nothing of the slope parameterization is used. Moderate configurations only
   (a narrow peak in polar coordinates needs many more intervals). */
static long double polar_integrand(long double p, long double t, void *ctx)
{
    const norm_ctx *c = (const norm_ctx *)ctx;
    long double st = sinl(t), ct = cosl(t);
    return (long double)pf_beckmann_d(vec3_of(st * cosl(p), st * sinl(p), ct), c->s) * ct * st;
}

static int polar_tpoints(long double p, long double *pts, int max_points, void *ctx)
{
    const norm_ctx *c = (const norm_ctx *)ctx;
    (void)p;
    if (max_points < 1) return 0;
    pts[0] = atanl(sqrtl(c->k.mx * c->k.mx + c->k.my * c->k.my)); /* the mesonormal's polar angle */
    return 1;
}

static void test_normalization_polar(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec30003ULL);
    pf_test_max m = pf_test_max_init();
    int i, bad = 0;
    for (i = 0; i < 8; i++) {
        norm_ctx c;
        pf_oracle_2d pb;
        pf_oracle_result r;
        long double xp[1];
        c.k = bcfg_random(&rng, i % 4); /* not the tiny-sigma kind */
        c.L = chol_of(c.k);
        c.s = bcfg_stats(c.k);
        pb = pf_oracle_2d_make(polar_integrand, &c, -PF_TEST_PI, PF_TEST_PI, 0.0L, PF_TEST_PI / 2.0L);
        xp[0] = atan2l(-c.k.my, -c.k.mx); /* the mesonormal's azimuth */
        pb.xpoints = xp;
        pb.nxpoints = 1;
        pb.ypoints = polar_tpoints;
        pb.epsrel = fmaxl(norm_bound(c.k) / 16.0L, 1e-11L);
        pb.max_intervals = 800;
        r = pf_oracle_integrate_2d(&pb);
        if (!quad_ok(r, c.k)) bad++;
        pf_test_max_update(&m, fabsl(r.value - 1.0L) / norm_bound(c.k), (long double)i);
    }
    pf_test_note("integral D (m.g) dm - 1, polar quadrature (8 configs, not tiny sigma): max %.3g of the bound",
                 (double)m.err);
    PF_CHECK(m.err <= 1.0L, "polar normalization: %.3g of bound (config %d)", (double)m.err, (int)m.at);
    PF_CHECK(bad == 0, "%d polar quadratures did not converge", bad);
}

/* ------------------------------------------------------------------ projected area identity */
/* integral max(0, w_o . m) D(m) dm = (1 + Lambda_o) (w_nbar . w_o)/(w_nbar . w_g). */
static pf_vec3 random_view(pf_test_rng *rng, bcfg k, long double min_area)
{
    int tries;
    for (tries = 0; tries < 1000; tries++) {
        long double t = (long double)pf_test_uniform(rng, 0.0, 1.55);
        long double p = (long double)pf_test_uniform(rng, -3.14159, 3.14159);
        pf_vec3 w = vec3_of(sinl(t) * cosl(p), sinl(t) * sinl(p), cosl(t));
        long double area = (long double)w.z - k.mx * (long double)w.x - k.my * (long double)w.y;
        if (area >= min_area) return w;
    }
    return pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
}

static void test_projected_area_identity(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec30004ULL);
    pf_test_max m = pf_test_max_init();
    int i, bad = 0;
    for (i = 0; i < 30; i++) {
        norm_ctx c;
        pf_oracle_result r;
        pf_vec3 wo;
        long double lhs, rhs;
        c.k = bcfg_random(&rng, i % N_KINDS);
        c.L = chol_of(c.k);
        c.s = bcfg_stats(c.k);
        wo = random_view(&rng, c.k, 0.05L);
        c.wx = (long double)wo.x;
        c.wy = (long double)wo.y;
        c.wz = (long double)wo.z;
        c.weight_by_view = 1;
        r = whitened_integral(&c, fmaxl(norm_bound(c.k) / 16.0L, 1e-12L));
        if (!quad_ok(r, c.k)) bad++;
        lhs = r.value;
        rhs = (1.0L + (long double)pf_beckmann_lambda(wo, c.s)) * (long double)pf_beckmann_projected_area(wo, c.s);
        pf_test_max_update(&m, pf_test_rel_error(rhs, lhs) / norm_bound(c.k), (long double)i);
    }
    pf_test_note("projected area: (1 + Lambda_o) A_o vs integral max(0, w_o.m) D dm, 30 configs (all kinds): "
                 "max %.3g of the bound",
                 (double)m.err);
    PF_CHECK(m.err <= 1.0L, "projected-area identity: %.3g of bound (config %d)", (double)m.err, (int)m.at);
    PF_CHECK(bad == 0, "%d quadratures did not converge", bad);
}

/* ------------------------------------------------------------------ BRDF identity */
/* (1/A_o) integral over the whole sphere of w_i of D(w_h) / (4 (1 + Lambda_o)) = 1 (after
   LEADR eq. 16), integrated in polar coordinates (t, p) of w_i around the mirror direction of
   w_o about the mesonormal, with breakpoints at multiples of the lobe width. */
typedef struct sphere_ctx {
    pf_slope_stats s;
    long double o[3];
    long double e0[3], e1[3], e2[3]; /* frame around the mirror direction */
    int what;                        /* 0 identity (D only), 1 LEADR joint, 2 LEADR masking */
    long double width;               /* lobe width in radians */
    long double epsrel;
    long double width_min;
} sphere_ctx;

static void sphere_dir(const sphere_ctx *c, long double t, long double p, long double *w)
{
    long double st = sinl(t), ct = cosl(t), cp = cosl(p), sp = sinl(p);
    int j;
    for (j = 0; j < 3; j++) w[j] = ct * c->e0[j] + st * (cp * c->e1[j] + sp * c->e2[j]);
}

static long double sphere_integrand(long double p, long double t, void *ctx)
{
    const sphere_ctx *c = (const sphere_ctx *)ctx;
    long double wi[3], v;
    pf_vec3 o = vec3_of(c->o[0], c->o[1], c->o[2]);
    sphere_dir(c, t, p, wi);
    if (c->what == 0) {
        /* half vector by the test (unnormalized is fine for pf_beckmann_d) */
        v = (long double)pf_beckmann_d(vec3_of(c->o[0] + wi[0], c->o[1] + wi[1], c->o[2] + wi[2]), c->s) / 4.0L;
    } else if (c->what == 1) {
        v = (long double)pf_leadr_specular(o, vec3_of(wi[0], wi[1], wi[2]), c->s, PF_R(1.0));
    } else {
        v = (long double)pf_leadr_specular_masking(o, vec3_of(wi[0], wi[1], wi[2]), c->s, PF_R(1.0));
    }
    return v * sinl(t);
}

static int sphere_tpoints(long double p, long double *pts, int max_points, void *ctx)
{
    const sphere_ctx *c = (const sphere_ctx *)ctx;
    static const long double mult[4] = {0.5L, 1.5L, 4.0L, 10.0L};
    int n = 0, j;
    (void)p;
    for (j = 0; j < 4 && n < max_points; j++)
        if (mult[j] * c->width < PF_TEST_PI) pts[n++] = mult[j] * c->width;
    for (j = 0; j < 4 && n < max_points; j++)
        if (mult[j] * c->width_min < PF_TEST_PI && mult[j] * c->width_min < 0.25L * c->width) pts[n++] = mult[j] * c->width_min;
    return n;
}

static long double sphere_integral(sphere_ctx *c, pf_vec3 wo, int what, int *converged)
{
    pf_vec3 n = pf_beckmann_mesonormal(c->s);
    long double nx = (long double)n.x, ny = (long double)n.y, nz = (long double)n.z;
    long double on = c->o[0] * nx + c->o[1] * ny + c->o[2] * nz, len;
    long double a[3];
    pf_oracle_2d pb;
    pf_oracle_result r;
    (void)wo;
    c->what = what;
    c->e0[0] = 2.0L * on * nx - c->o[0];
    c->e0[1] = 2.0L * on * ny - c->o[1];
    c->e0[2] = 2.0L * on * nz - c->o[2];
    len = sqrtl(c->e0[0] * c->e0[0] + c->e0[1] * c->e0[1] + c->e0[2] * c->e0[2]);
    c->e0[0] /= len;
    c->e0[1] /= len;
    c->e0[2] /= len;
    /* any unit vector orthogonal to e0, then e2 = e0 x e1 */
    a[0] = fabsl(c->e0[0]) < 0.6L ? 1.0L : 0.0L;
    a[1] = a[0] == 0.0L ? 1.0L : 0.0L;
    a[2] = 0.0L;
    on = a[0] * c->e0[0] + a[1] * c->e0[1];
    c->e1[0] = a[0] - on * c->e0[0];
    c->e1[1] = a[1] - on * c->e0[1];
    c->e1[2] = -on * c->e0[2];
    len = sqrtl(c->e1[0] * c->e1[0] + c->e1[1] * c->e1[1] + c->e1[2] * c->e1[2]);
    c->e1[0] /= len;
    c->e1[1] /= len;
    c->e1[2] /= len;
    c->e2[0] = c->e0[1] * c->e1[2] - c->e0[2] * c->e1[1];
    c->e2[1] = c->e0[2] * c->e1[0] - c->e0[0] * c->e1[2];
    c->e2[2] = c->e0[0] * c->e1[1] - c->e0[1] * c->e1[0];
    pb = pf_oracle_2d_make(sphere_integrand, c, -PF_TEST_PI, PF_TEST_PI, 0.0L, PF_TEST_PI);
    pb.ypoints = sphere_tpoints;
    pb.epsrel = c->epsrel;
    pb.max_intervals = 800;
    r = pf_oracle_integrate_2d(&pb);
    *converged = r.converged || r.error <= 4.0L * c->epsrel * fabsl(r.value);
    return r.value;
}

static void test_brdf_identity_and_energy(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec30005ULL);
    pf_test_max m = pf_test_max_init(), mh = pf_test_max_init();
    long double emax_joint = 0.0L, emax_mask = 0.0L, eratio_max = 0.0L;
    int i, bad = 0;
    /* under emulation (pf_test_reduced: qemu-arm) 2 polar configs and one half-vector config per
       kind instead of 6 and 15: this test is most of the suite's time there */
    const int npolar = pf_test_reduced() ? 2 : 6, nhalf = pf_test_reduced() ? N_KINDS : 15;
    /* polar coordinates of w_i around the mirror direction: lobes that are not thin */
    for (i = 0; i < npolar; i++) {
        sphere_ctx c;
        bcfg k = bcfg_random(&rng, i % 2 == 0 ? 0 : 3);
        pf_vec3 wo = random_view(&rng, k, 0.1L);
        int conv;
        long double ident, area, lam;
        c.s = bcfg_stats(k);
        c.o[0] = (long double)wo.x;
        c.o[1] = (long double)wo.y;
        c.o[2] = (long double)wo.z;
        /* the polar rule is asked for 1e-10: the bound here is max(norm_bound, 1e-9) */
        c.epsrel = fmaxl(norm_bound(k) / 16.0L, 1e-10L);
        c.width = 2.0L * sqrtl(fmaxl(k.vx, k.vy)) / (1.0L + k.mx * k.mx + k.my * k.my);
        c.width_min = 2.0L * sqrtl(fminl(k.vx, k.vy) * (1.0L - k.cxy * k.cxy / (k.vx * k.vy))) /
                      (1.0L + k.mx * k.mx + k.my * k.my);
        area = (long double)pf_beckmann_projected_area(wo, c.s);
        lam = (long double)pf_beckmann_lambda(wo, c.s);
        ident = sphere_integral(&c, wo, 0, &conv) / ((1.0L + lam) * area);
        if (!conv) bad++;
        pf_test_max_update(&m, fabsl(ident - 1.0L) / fmaxl(norm_bound(k), 1e-9L), (long double)i);
    }
    /* every kind, through the half vector: w_i = reflect(w_o, m) over whitened slopes of m */
    for (i = 0; i < nhalf; i++) {
        norm_ctx c;
        pf_vec3 wo;
        pf_oracle_result r;
        long double area, lam, ej, em;
        c.k = bcfg_random(&rng, i % N_KINDS);
        c.L = chol_of(c.k);
        c.s = bcfg_stats(c.k);
        wo = random_view(&rng, c.k, 0.05L);
        c.wx = (long double)wo.x;
        c.wy = (long double)wo.y;
        c.wz = (long double)wo.z;
        area = (long double)pf_beckmann_projected_area(wo, c.s);
        lam = (long double)pf_beckmann_lambda(wo, c.s);
        c.weight_by_view = 2;
        r = whitened_integral(&c, fmaxl(norm_bound(c.k) / 16.0L, 1e-12L));
        if (!quad_ok(r, c.k)) bad++;
        pf_test_max_update(&mh, fabsl(r.value / ((1.0L + lam) * area) - 1.0L) / norm_bound(c.k), (long double)i);
        /* white furnace (Fresnel off): the LEADR functions integrated over all w_i */
        c.weight_by_view = 3;
        r = whitened_integral(&c, 1e-6L);
        ej = r.value;
        c.weight_by_view = 4;
        r = whitened_integral(&c, 1e-6L);
        em = r.value;
        emax_joint = fmaxl(emax_joint, ej);
        emax_mask = fmaxl(emax_mask, em);
        eratio_max = fmaxl(eratio_max, ej / em);
    }
    pf_test_note("BRDF identity (after eq. 16): polar quadrature of w_i around the mirror direction (%d configs) "
                 "max |I - 1| %.3g of max(bound, 1e-9); through the half vector (%d configs, all kinds) %.3g of the bound",
                 npolar, (double)m.err, nhalf, (double)mh.err);
    pf_test_note("white-furnace albedo (Fresnel off, %d configs): joint form max %.6f, masking-only max %.6f, "
                 "max ratio joint/masking %.4f",
                 nhalf, (double)emax_joint, (double)emax_mask, (double)eratio_max);
    PF_CHECK(m.err <= 1.0L, "BRDF identity, polar: %.3g of bound (config %d)", (double)m.err, (int)m.at);
    PF_CHECK(mh.err <= 1.0L, "BRDF identity, half vector: %.3g of bound (config %d)", (double)mh.err, (int)mh.at);
    PF_CHECK(emax_mask <= 1.0L + 1e-5L, "masking-only albedo above 1: %.8g", (double)emax_mask);
    PF_CHECK(emax_joint <= 1.0L + 1e-5L, "joint albedo above 1: %.8g", (double)emax_joint);
    PF_CHECK(eratio_max <= 1.0L + 1e-5L, "joint above masking-only");
    PF_CHECK(bad == 0, "%d quadratures did not converge", bad);
}

/* Pointwise: pf_leadr_specular(_masking) equals F D G / (4 A_o) composed in long double from
   the test's own P22, Lambda (1D quadrature of its definition) and projected area. */
static long double lambda_def(bcfg k, long double wx, long double wy, long double wz)
{
    /* slopes along the azimuth of w by trigonometry (eqs. 14-15), then the 1D definition */
    long double r = sqrtl(wx * wx + wy * wy), cp = r > 0.0L ? wx / r : 1.0L, sp = r > 0.0L ? wy / r : 0.0L;
    return pf_oracle_lambda_1d(wz / r, cp * k.mx + sp * k.my,
                               sqrtl(cp * cp * k.vx + sp * sp * k.vy + 2.0L * cp * sp * k.cxy));
}

/* P(w) = E[max(0, w.z - x w.x - y w.y)] for Gaussian slopes, in closed form (the positive part
   of a normal variable of mean A and deviation sigma: A Phi(A/sigma) + sigma phi(A/sigma)) */
static long double facing_def(bcfg k, long double wx, long double wy, long double wz)
{
    long double a = wz - k.mx * wx - k.my * wy;
    long double sd = sqrtl(wx * wx * k.vx + wy * wy * k.vy + 2.0L * wx * wy * k.cxy);
    if (!(sd > 0.0L)) return a > 0.0L ? a : 0.0L;
    return a * 0.5L * erfcl(-a / (sd * sqrtl(2.0L))) + sd * expl(-a * a / (2.0L * sd * sd)) / sqrtl(2.0L * PF_TEST_PI);
}

/* the light's Lambda of pf_leadr_specular (pf_beckmann_light_lambda): Smith's lam above the
   mean plane; on or below it max(P_i(0), wi.z) / wi.z - 1, P_i(0) the facing area with A_i
   counted as 0 */
static long double light_lambda_def(bcfg k, long double lam, long double wx, long double wy, long double wz)
{
    long double a = wz - k.mx * wx - k.my * wy, p;
    if (a > 0.0L) return lam;
    p = facing_def(k, wx, wy, wz - a); /* the same variance along w, A = 0 */
    return (p > wz ? p : wz) / wz - 1.0L;
}

static void test_specular_pointwise(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec30006ULL);
    pf_test_max mj = pf_test_max_init(), mm = pf_test_max_init(), mrec = pf_test_max_init();
    int i, zero_ok = 1, ncap = 0;
    for (i = 0; i < 600; i++) {
        bcfg k = bcfg_random(&rng, i % 4);
        pf_slope_stats s = bcfg_stats(k);
        pf_vec3 wo = random_view(&rng, k, 0.05L), wi = random_view(&rng, k, 0.05L);
        long double o[3], w[3], h[3], hl, sx, sy, d, lo, li, ao, ai, f0, cd, F, ref_j, ref_m, q;
        pf_real f0r = (pf_real)pf_test_uniform(&rng, 0.02, 1.0);
        int recip;
        pf_real gj, gm;
        chol2 L = chol_of(k);
        int j;
        o[0] = (long double)wo.x; o[1] = (long double)wo.y; o[2] = (long double)wo.z;
        w[0] = (long double)wi.x; w[1] = (long double)wi.y; w[2] = (long double)wi.z;
        for (j = 0; j < 3; j++) h[j] = o[j] + w[j];
        hl = sqrtl(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        sx = -h[0] / h[2];
        sy = -h[1] / h[2];
        d = p22_ref(k, sx, sy) * powl(hl / h[2], 4.0L);
        lo = lambda_def(k, o[0], o[1], o[2]);
        li = lambda_def(k, w[0], w[1], w[2]);
        /* both directions above the mean plane here: Smith's Lambda_i, reciprocity holds */
        recip = light_lambda_def(k, li, w[0], w[1], w[2]) == li && light_lambda_def(k, lo, o[0], o[1], o[2]) == lo;
        ncap += !recip;
        li = light_lambda_def(k, li, w[0], w[1], w[2]);
        ao = o[2] - k.mx * o[0] - k.my * o[1];
        ai = w[2] - k.mx * w[0] - k.my * w[1];
        f0 = (long double)f0r;
        cd = (o[0] * h[0] + o[1] * h[1] + o[2] * h[2]) / hl;
        F = f0 + (1.0L - f0) * powl(1.0L - cd, 5.0L);
        ref_j = F * d / (4.0L * ao * (1.0L + lo + li));
        ref_m = F * d / (4.0L * ao * (1.0L + lo));
        gj = pf_leadr_specular(wo, wi, s, f0r);
        gm = pf_leadr_specular_masking(wo, wi, s, f0r);
        /* the exponent of D amplifies rounding: compare where q/2 <= 30 */
        {
            long double dx = sx - k.mx, dy = sy - k.my;
            long double u = dx / L.a, v = (dy - L.b * u) / L.c;
            q = 0.5L * (u * u + v * v);
        }
        if (q <= 30.0L) {
            pf_test_max_update(&mj, pf_test_rel_error((long double)gj, ref_j) / d_cond(k, q, sx, sy), (long double)i);
            pf_test_max_update(&mm, pf_test_rel_error((long double)gm, ref_m) / d_cond(k, q, sx, sy), (long double)i);
        }
        /* reciprocity of the joint form: I / A_i = F D G / (4 A_o A_i) is symmetric, so
           I(o, i) A_o = I(i, o) A_i (Smith's G; the light's cap is not symmetric) */
        if (q <= 30.0L && recip)
            pf_test_max_update(&mrec,
                               pf_test_rel_error((long double)gj * ao,
                                                 (long double)pf_leadr_specular(wi, wo, s, f0r) * ai) / d_cond(k, q, sx, sy),
                               (long double)i);
        /* below the macrosurface: 0 */
        if (pf_leadr_specular(wo, pf_vec3_make(wi.x, wi.y, -wi.z), s, f0r) != PF_R(0.0)) zero_ok = 0;
    }
    pf_test_note("LEADR specular vs long double composition (own P22, Lambda by quadrature): joint %.3g, "
                 "masking %.3g eps x the condition number of D",
                 (double)(mj.err / PF_TEST_EPS), (double)(mm.err / PF_TEST_EPS));
    pf_test_note("reciprocity I(o,i) A_o = I(i,o) A_i: max %.3g eps x the condition number of D", (double)(mrec.err / PF_TEST_EPS));
    PF_CHECK(ncap == 0, "%d directions below the mean plane in the pointwise test", ncap);
    /* Lambda's own bound is a few eps; D's error grows with the (scaled) exponent */
    PF_CHECK(mj.err <= 64.0L * PF_TEST_EPS, "joint: %.3g eps (at %d)", (double)(mj.err / PF_TEST_EPS), (int)mj.at);
    PF_CHECK(mm.err <= 64.0L * PF_TEST_EPS, "masking: %.3g eps (at %d)", (double)(mm.err / PF_TEST_EPS), (int)mm.at);
    PF_CHECK(mrec.err <= 64.0L * PF_TEST_EPS, "reciprocity: %.3g eps", (double)(mrec.err / PF_TEST_EPS));
    PF_CHECK(zero_ok, "light below the macrosurface must give 0");
}


/* A light above the macrosurface but on or below the footprint's mean plane (A_i <= 0 <
   wi.z), the view above it: pf_leadr_specular gives F D / (4 A_o (1 + Lambda_o + Lambda_i'))
   with Lambda_i' = max(P_i(0), wi.z) / wi.z - 1 (pf_beckmann_light_lambda below the mean plane, P_i(0)
   = sqrt(var_i / (2 pi)) in closed form); composed in long double as test_specular_pointwise
   does, the same bound. Smith's Lambda_i is infinite there, and the function used to return 0
   (issue 15: bench/pictures.c's lit pixels returned 0). */
static void test_specular_light_below_mean_plane(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec3000bULL);
    pf_test_max mj = pf_test_max_init();
    int i, n = 0, pos = 1;
    for (i = 0; i < 1000; i++) {
        bcfg k = bcfg_random(&rng, i % 4);
        pf_slope_stats s = bcfg_stats(k);
        pf_vec3 wo = random_view(&rng, k, 0.05L), wi;
        long double o[3], w[3], h[3], hl, sx, sy, d, lo, li, ao, cd, F, ref, q, u, v, dx, dy;
        pf_real got;
        chol2 L = chol_of(k);
        int j, tries;
        /* a light direction with A_i <= 0 < wi.z */
        for (tries = 0; tries < 200; tries++) {
            long double t = (long double)pf_test_uniform(&rng, 0.0, 1.55);
            long double p = (long double)pf_test_uniform(&rng, -3.14159, 3.14159);
            wi = vec3_of(sinl(t) * cosl(p), sinl(t) * sinl(p), cosl(t));
            if ((long double)wi.z - k.mx * (long double)wi.x - k.my * (long double)wi.y <= 0.0L && wi.z > PF_R(0.0)) break;
        }
        if (tries == 200) continue;
        o[0] = (long double)wo.x; o[1] = (long double)wo.y; o[2] = (long double)wo.z;
        w[0] = (long double)wi.x; w[1] = (long double)wi.y; w[2] = (long double)wi.z;
        for (j = 0; j < 3; j++) h[j] = o[j] + w[j];
        hl = sqrtl(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        if (!(h[2] > 1e-3L * hl)) continue;
        sx = -h[0] / h[2];
        sy = -h[1] / h[2];
        d = p22_ref(k, sx, sy) * powl(hl / h[2], 4.0L);
        lo = lambda_def(k, o[0], o[1], o[2]);
        li = light_lambda_def(k, HUGE_VALL, w[0], w[1], w[2]);
        ao = o[2] - k.mx * o[0] - k.my * o[1];
        cd = (o[0] * h[0] + o[1] * h[1] + o[2] * h[2]) / hl;
        F = 0.04L + 0.96L * powl(1.0L - cd, 5.0L);
        ref = F * d / (4.0L * ao * (1.0L + lo + li));
        got = pf_leadr_specular(wo, wi, s, PF_R(0.04));
        dx = sx - k.mx;
        dy = sy - k.my;
        u = dx / L.a;
        v = (dy - L.b * u) / L.c;
        q = 0.5L * (u * u + v * v);
        if (q <= 30.0L) {
            pf_test_max_update(&mj, pf_test_rel_error((long double)got, ref) / d_cond(k, q, sx, sy), (long double)i);
            if (!(got > PF_R(0.0)) && ref > 1e-30L) pos = 0;
            ++n;
        }
    }
    pf_test_note("%d lights below the mean plane vs long double composition with the capped Lambda_i: %.3g eps x the "
                 "condition number of D", n, (double)(mj.err / PF_TEST_EPS));
    PF_CHECK(n >= 100, "only %d samples", n); /* 134 */
    PF_CHECK(pos, "a light below the mean plane gave 0");
    PF_CHECK(mj.err <= 64.0L * PF_TEST_EPS, "capped: %.3g eps (at %d)", (double)(mj.err / PF_TEST_EPS), (int)mj.at);
}

/* ------------------------------------------------------------------ eq. 12 */
static void test_deformation_brute_force(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec30007ULL);
    const int n = 400000;
    int t, j;
    long double worst_stat = 0.0L, worst_lin = 0.0L;
    for (t = 0; t < 6; t++) {
        /* texture-space distribution and Jacobian (stretch, shear) and height scale */
        long double mu = (long double)pf_test_uniform(&rng, -0.5, 0.5), mv = (long double)pf_test_uniform(&rng, -0.5, 0.5);
        long double su = (long double)pf_test_uniform(&rng, 0.1, 0.6), sv = (long double)pf_test_uniform(&rng, 0.1, 0.6);
        long double r = (long double)pf_test_uniform(&rng, -0.8, 0.8);
        long double a = (long double)pf_test_uniform(&rng, -2.0, 2.0), b = (long double)pf_test_uniform(&rng, -1.0, 1.0);
        long double c = (long double)pf_test_uniform(&rng, -1.0, 1.0), d = (long double)pf_test_uniform(&rng, -2.0, 2.0);
        long double eta = (long double)pf_test_uniform(&rng, 0.2, 3.0);
        long double acc[5] = {0, 0, 0, 0, 0}, accuv[5] = {0, 0, 0, 0, 0};
        long double true_uv[5], got[5], lin[5], se[5];
        pf_slope_moments mt, ms, ml;
        bcfg kuv;
        kuv.mx = mu; kuv.my = mv; kuv.vx = su * su; kuv.vy = sv * sv; kuv.cxy = r * su * sv;
        kuv = bcfg_round(kuv);
        a = (long double)(pf_real)a; b = (long double)(pf_real)b; c = (long double)(pf_real)c;
        d = (long double)(pf_real)d; eta = (long double)(pf_real)eta;
        {
            chol2 L = chol_of(kuv);
            for (j = 0; j < n; j++) {
                /* Box-Muller with the seeded generator */
                long double u1 = (long double)pf_test_uniform(&rng, 1e-300, 1.0), u2 = (long double)pf_test_uniform(&rng, 0.0, 1.0);
                long double rad = sqrtl(-2.0L * logl(u1));
                long double g1 = rad * cosl(2.0L * PF_TEST_PI * u2), g2 = rad * sinl(2.0L * PF_TEST_PI * u2);
                long double su_ = kuv.mx + L.a * g1, sv_ = kuv.my + L.b * g1 + L.c * g2;
                long double x = eta * (a * su_ + b * sv_), y = eta * (c * su_ + d * sv_);
                acc[0] += x; acc[1] += y; acc[2] += x * x; acc[3] += y * y; acc[4] += x * y;
                accuv[0] += su_; accuv[1] += sv_; accuv[2] += su_ * su_; accuv[3] += sv_ * sv_; accuv[4] += su_ * sv_;
            }
        }
        for (j = 0; j < 5; j++) {
            acc[j] /= (long double)n;
            accuv[j] /= (long double)n;
        }
        true_uv[0] = kuv.mx; true_uv[1] = kuv.my;
        true_uv[2] = kuv.vx + kuv.mx * kuv.mx; true_uv[3] = kuv.vy + kuv.my * kuv.my;
        true_uv[4] = kuv.cxy + kuv.mx * kuv.my;
        /* the distribution's moments transformed by the library vs the sample moments */
        mt = pf_slope_moments_scale_height(
            pf_slope_moments_deform(pf_slope_moments_make((pf_real)true_uv[0], (pf_real)true_uv[1], (pf_real)true_uv[2],
                                                          (pf_real)true_uv[3], (pf_real)true_uv[4]),
                                    (pf_real)a, (pf_real)b, (pf_real)c, (pf_real)d),
            (pf_real)eta);
        got[0] = (long double)mt.ex; got[1] = (long double)mt.ey; got[2] = (long double)mt.exx;
        got[3] = (long double)mt.eyy; got[4] = (long double)mt.exy;
        /* standard errors of the sample moments: sqrt(Var / n) with Var from the sample */
        {
            long double vx = acc[2] - acc[0] * acc[0], vy = acc[3] - acc[1] * acc[1];
            long double sxx = sqrtl(vx), syy = sqrtl(vy);
            long double m2 = sqrtl(acc[2]), n2 = sqrtl(acc[3]);
            se[0] = sxx; se[1] = syy;
            se[2] = 2.0L * sxx * (m2 + sxx); se[3] = 2.0L * syy * (n2 + syy);
            se[4] = sxx * n2 + syy * m2 + sxx * syy;
            for (j = 0; j < 5; j++) se[j] /= sqrtl((long double)n);
        }
        for (j = 0; j < 5; j++) worst_stat = fmaxl(worst_stat, fabsl(got[j] - acc[j]) / se[j]);
        /* linearity: the library transform of the sample moments equals the sample moments of
           the transformed samples, up to rounding */
        ms = pf_slope_moments_make((pf_real)accuv[0], (pf_real)accuv[1], (pf_real)accuv[2], (pf_real)accuv[3],
                                   (pf_real)accuv[4]);
        ml = pf_slope_moments_scale_height(pf_slope_moments_deform(ms, (pf_real)a, (pf_real)b, (pf_real)c, (pf_real)d),
                                           (pf_real)eta);
        lin[0] = (long double)ml.ex; lin[1] = (long double)ml.ey; lin[2] = (long double)ml.exx;
        lin[3] = (long double)ml.eyy; lin[4] = (long double)ml.exy;
        for (j = 0; j < 5; j++) {
            long double scale = j < 2 ? sqrtl(acc[2] + acc[3]) : acc[2] + acc[3];
            worst_lin = fmaxl(worst_lin, fabsl(lin[j] - acc[j]) / scale);
        }
    }
    pf_test_note("eq. 12 + height scale vs 400000 transformed Gaussian samples x 6: max %.2f standard errors; "
                 "transform of sample moments = sample moments of transformed slopes to %.3g eps (scaled)",
                 (double)worst_stat, (double)(worst_lin / PF_TEST_EPS));
    PF_CHECK(worst_stat <= 5.0L, "eq. 12 vs samples: %.3g standard errors", (double)worst_stat);
    PF_CHECK(worst_lin <= 64.0L * PF_TEST_EPS, "linearity: %.3g eps", (double)(worst_lin / PF_TEST_EPS));
}

/* ------------------------------------------------------------------ centered: textbook */
/* Zero mean, no correlation: D(m) = exp(-tan^2 t (cos^2 p / ax^2 + sin^2 p / ay^2)) /
   (pi ax ay cos^4 t) with a = sqrt(2) sigma, and Smith's G1 = 1/(1 + Lambda) with
   Lambda = (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt(pi)), a = 1/(alpha(p) tan t),
   alpha(p)^2 = cos^2 p ax^2 + sin^2 p ay^2 (Walter et al. 2007 / Heitz 2014 form). And the
   BRDF: A_o = cos t_o, so I = F D G2 / (4 cos t_o). */
static void test_centered_reduces_to_textbook(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xbec30008ULL);
    pf_test_max md = pf_test_max_init(), mg = pf_test_max_init(), mb = pf_test_max_init(), mn = pf_test_max_init();
    int i;
    for (i = 0; i < 5000; i++) {
        long double sx = (long double)(pf_real)pf_test_log_uniform(&rng, 0.02, 1.0);
        long double sy = (long double)(pf_real)pf_test_log_uniform(&rng, 0.02, 1.0);
        long double ax = sqrtl(2.0L) * sx, ay = sqrtl(2.0L) * sy;
        pf_slope_moments mom = pf_slope_moments_make(PF_R(0.0), PF_R(0.0), (pf_real)(sx * sx), (pf_real)(sy * sy), PF_R(0.0));
        pf_slope_stats s = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), (pf_real)(sx * sx), (pf_real)(sy * sy), PF_R(0.0));
        long double t = (long double)pf_test_uniform(&rng, 0.0, 1.2), p = (long double)pf_test_uniform(&rng, -3.14159, 3.14159);
        pf_vec3 m = vec3_of(sinl(t) * cosl(p), sinl(t) * sinl(p), cosl(t));
        long double mx = (long double)m.x, my = (long double)m.y, mz = (long double)m.z;
        long double ml2 = mx * mx + my * my + mz * mz, c2 = mz * mz / ml2, tan2 = (1.0L - c2) / c2;
        long double phi = atan2l(my, mx), cp = cosl(phi), sp = sinl(phi);
        long double dref = expl(-tan2 * (cp * cp / (ax * ax) + sp * sp / (ay * ay))) / (PF_TEST_PI * ax * ay * c2 * c2);
        long double q = tan2 * (cp * cp / (ax * ax) + sp * sp / (ay * ay));
        pf_vec3 w = vec3_of(sinl(t) * cosl(p), sinl(t) * sinl(p), cosl(t));
        long double wx = (long double)w.x, wy = (long double)w.y, wz = (long double)w.z;
        long double wr = sqrtl(wx * wx + wy * wy), alpha, a, lam, g1ref;
        (void)mom;
        if (q <= 60.0L) /* exp(-q) a normal float */
            pf_test_max_update(&md, pf_test_rel_error((long double)pf_beckmann_d(m, s), dref) / (1.0L + q), (long double)i);
        if (wr > 0.0L) {
            alpha = sqrtl((wx * wx * ax * ax + wy * wy * ay * ay) / (wr * wr));
            a = wz / (alpha * wr);
            lam = 0.5L * (erfl(a) - 1.0L) + expl(-a * a) / (2.0L * a * sqrtl(PF_TEST_PI));
            if (a > 3.0L) lam = lambda_def(centered_cfg(sx, sy), wx, wy, wz);
            g1ref = 1.0L / (1.0L + lam);
            pf_test_max_update(&mg, pf_test_rel_error((long double)pf_beckmann_g1(w, s), g1ref), (long double)i);
        }
        /* mesonormal is +z and the area is cos t */
        {
            pf_vec3 n = pf_beckmann_mesonormal(s);
            if (n.x != PF_R(0.0) || n.y != PF_R(0.0) || n.z != PF_R(1.0)) pf_test_max_update(&mn, 1.0L, (long double)i);
            pf_test_max_update(&mn, pf_test_rel_error((long double)pf_beckmann_projected_area(w, s), wz), (long double)i);
        }
        /* the BRDF: textbook F D G2 / (4 cos t_o), F off, reflection about a random h */
        {
            long double to = (long double)pf_test_uniform(&rng, 0.0, 1.4), po = (long double)pf_test_uniform(&rng, -3.14, 3.14);
            long double ti = (long double)pf_test_uniform(&rng, 0.0, 1.4), pi_ = (long double)pf_test_uniform(&rng, -3.14, 3.14);
            pf_vec3 o = vec3_of(sinl(to) * cosl(po), sinl(to) * sinl(po), cosl(to));
            pf_vec3 il = vec3_of(sinl(ti) * cosl(pi_), sinl(ti) * sinl(pi_), cosl(ti));
            long double h[3], hl, hc2, ht2, hp, dh, lo, li, ref, qh;
            long double ol[3], wl[3];
            int j;
            ol[0] = (long double)o.x; ol[1] = (long double)o.y; ol[2] = (long double)o.z;
            wl[0] = (long double)il.x; wl[1] = (long double)il.y; wl[2] = (long double)il.z;
            for (j = 0; j < 3; j++) h[j] = ol[j] + wl[j];
            hl = sqrtl(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            hc2 = h[2] * h[2] / (hl * hl);
            ht2 = (1.0L - hc2) / hc2;
            hp = atan2l(h[1], h[0]);
            qh = ht2 * (cosl(hp) * cosl(hp) / (ax * ax) + sinl(hp) * sinl(hp) / (ay * ay));
            dh = expl(-qh) / (PF_TEST_PI * ax * ay * hc2 * hc2);
            lo = lambda_def(centered_cfg(sx, sy), ol[0], ol[1], ol[2]);
            li = lambda_def(centered_cfg(sx, sy), wl[0], wl[1], wl[2]);
            ref = dh / (4.0L * ol[2] * (1.0L + lo + li));
            if (qh <= 30.0L)
                pf_test_max_update(&mb, pf_test_rel_error((long double)pf_leadr_specular(o, il, s, PF_R(1.0)), ref) / (1.0L + qh),
                                   (long double)i);
        }
    }
    pf_test_note("centered, uncorrelated vs textbook: D %.3g eps x (1 + q), G1 %.3g eps, BRDF %.3g eps x (1 + q)",
                 (double)(md.err / PF_TEST_EPS), (double)(mg.err / PF_TEST_EPS), (double)(mb.err / PF_TEST_EPS));
    PF_CHECK(md.err <= 16.0L * PF_TEST_EPS, "centered D: %.3g eps", (double)(md.err / PF_TEST_EPS));
    PF_CHECK(mg.err <= 16.0L * PF_TEST_EPS + 1e-15L, "centered G1: %.3g eps", (double)(mg.err / PF_TEST_EPS));
    PF_CHECK(mb.err <= 64.0L * PF_TEST_EPS, "centered BRDF: %.3g eps", (double)(mb.err / PF_TEST_EPS));
    PF_CHECK(mn.err <= 4.0L * PF_TEST_EPS, "centered mesonormal / area: %.3g", (double)mn.err);
}

/* ------------------------------------------------------------------ moments and stats */
static void test_moments_stats(void)
{
    /* from_stats and stats are inverse (base roughness aside) */
    pf_slope_stats s0 = pf_slope_stats_make(PF_R(0.3), PF_R(-0.2), PF_R(0.04), PF_R(0.09), PF_R(0.012));
    pf_slope_stats s1 = pf_slope_moments_stats(pf_slope_moments_from_stats(s0), PF_R(0.0));
    pf_slope_stats s2 = pf_slope_moments_stats(pf_slope_moments_from_stats(s0), PF_R(0.01));
    pf_slope_moments a = pf_slope_moments_from_normal(pf_vec3_normalize(pf_vec3_make(PF_R(0.2), PF_R(-0.4), PF_R(1.0))));
    long double tol = 64.0L * PF_TEST_EPS;
    PF_CHECK(fabsl((long double)s1.var_x - 0.04L - 1e-6L) <= tol, "var_x round trip %.9g", (double)s1.var_x);
    PF_CHECK(fabsl((long double)s1.cov_xy - 0.012L) <= tol, "cov round trip %.9g", (double)s1.cov_xy);
    PF_CHECK(fabsl((long double)s2.var_y - 0.1L) <= tol, "base roughness added: %.9g", (double)s2.var_y);
    PF_CHECK(fabsl((long double)s2.cov_xy - 0.012L) <= tol, "base roughness leaves cov: %.9g", (double)s2.cov_xy);
    PF_CHECK(fabsl((long double)a.ex + 0.2L) <= tol && fabsl((long double)a.ey - 0.4L) <= tol, "slope of a normal");
    PF_CHECK(fabsl((long double)pf_slope_stats_correlation(s0) - 0.012L / (0.2L * 0.3L)) <= tol, "correlation");
    /* linear combination: average of two single slopes */
    {
        pf_slope_moments m = pf_slope_moments_add(pf_slope_moments_scale(pf_slope_moments_from_slope(PF_R(1.0), PF_R(0.0)), PF_R(0.5)),
                                                  pf_slope_moments_scale(pf_slope_moments_from_slope(PF_R(-1.0), PF_R(2.0)), PF_R(0.5)));
        pf_slope_stats st = pf_slope_moments_stats(m, PF_R(0.0));
        PF_CHECK(m.ex == PF_R(0.0) && m.ey == PF_R(1.0), "mean of two slopes");
        PF_CHECK(fabsl((long double)st.var_x - 1.0L - 1e-6L) <= tol && fabsl((long double)st.cov_xy + 1.0L) <= tol,
                 "variance/covariance of two slopes: %g %g", (double)st.var_x, (double)st.cov_xy);
    }
}

/* ------------------------------------------------------------------ worked example (docs) */
/* docs/beckmann.md walks through this: four texels of a LEADR map (one slope each), averaged
   as a 2x2 mip reduction does, a base roughness, one view and one light. The reference is
   the long double composition of the test's own P22, Lambda (quadrature) and area. */
static void test_worked_example(void)
{
    static const pf_real texel_slopes[4][2] = {
        {PF_R(0.10), PF_R(0.00)}, {PF_R(-0.20), PF_R(0.10)}, {PF_R(0.30), PF_R(0.20)}, {PF_R(0.00), PF_R(-0.10)}};
    pf_slope_moments m = pf_slope_moments_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    pf_slope_stats s;
    pf_vec3 wo = pf_vec3_normalize(pf_vec3_make(PF_R(2.0), PF_R(0.0), PF_R(1.0)));
    pf_vec3 wi = pf_vec3_normalize(pf_vec3_make(PF_R(-1.5), PF_R(0.3), PF_R(1.0)));
    pf_real got;
    bcfg k;
    long double o[3], w[3], h[3], hl, d, lo, li, ao, cd, F, ref;
    int j;
    for (j = 0; j < 4; j++)
        m = pf_slope_moments_add(m, pf_slope_moments_scale(pf_slope_moments_from_slope(texel_slopes[j][0], texel_slopes[j][1]),
                                                           PF_R(0.25)));
    s = pf_slope_moments_stats(m, PF_R(0.01));
    got = pf_leadr_specular(wo, wi, s, PF_R(0.04));
    k.mx = (long double)s.mean_x; k.my = (long double)s.mean_y; k.vx = (long double)s.var_x;
    k.vy = (long double)s.var_y; k.cxy = (long double)s.cov_xy;
    o[0] = (long double)wo.x; o[1] = (long double)wo.y; o[2] = (long double)wo.z;
    w[0] = (long double)wi.x; w[1] = (long double)wi.y; w[2] = (long double)wi.z;
    for (j = 0; j < 3; j++) h[j] = o[j] + w[j];
    hl = sqrtl(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    d = p22_ref(k, -h[0] / h[2], -h[1] / h[2]) * powl(hl / h[2], 4.0L);
    lo = lambda_def(k, o[0], o[1], o[2]);
    li = lambda_def(k, w[0], w[1], w[2]);
    ao = o[2] - k.mx * o[0] - k.my * o[1];
    cd = (w[0] * h[0] + w[1] * h[1] + w[2] * h[2]) / hl;
    F = 0.04L + 0.96L * powl(1.0L - cd, 5.0L);
    ref = F * d / (4.0L * ao * (1.0L + lo + li));
    pf_test_note("moments (%.4f, %.4f, %.4f, %.4f, %.4f) -> mean (%.4f, %.4f), var (%.4f, %.4f), cov %.4f; "
                 "D %.5f, Lambda_o %.3g, Lambda_i %.3g, A_o %.5f, F %.5f; I = %.6f (long double %.6Lf)",
                 (double)m.ex, (double)m.ey, (double)m.exx, (double)m.eyy, (double)m.exy, (double)s.mean_x,
                 (double)s.mean_y, (double)s.var_x, (double)s.var_y, (double)s.cov_xy,
                 (double)pf_beckmann_d(pf_vec3_add(wo, wi), s), (double)pf_beckmann_lambda(wo, s),
                 (double)pf_beckmann_lambda(wi, s), (double)pf_beckmann_projected_area(wo, s),
                 (double)pf_fresnel_schlick(PF_R(0.04), (pf_real)cd), (double)got, ref);
    PF_CHECK(pf_test_rel_error((long double)got, ref) <= 64.0L * PF_TEST_EPS, "worked example %g vs %Lg", (double)got, ref);
}

/* ------------------------------------------------------------------ edges */
static int finite_nonneg(pf_real x) { return pf_test_finite(x) && x >= PF_R(0.0); }

static void edge_filtered_moments(void)
{
    /* variance made negative by interpolation, |r| > 1, zero variance: valid statistics */
    static const pf_real bad[6][5] = {
        {PF_R(0.2), PF_R(-0.1), PF_R(0.0399), PF_R(0.5), PF_R(0.3)},   /* var_x = -0.0001 */
        {PF_R(0.0), PF_R(0.0), PF_R(0.04), PF_R(0.01), PF_R(0.05)},    /* |r| = 2.5 */
        {PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0)},       /* a flat mirror */
        {PF_R(0.5), PF_R(0.5), PF_R(0.25), PF_R(0.25), PF_R(0.25)},    /* one slope: zero variance, r undefined */
        {PF_R(3.0), PF_R(-2.0), PF_R(9.0), PF_R(4.0), PF_R(-6.0)},     /* large mean, zero variance */
        {PF_R(0.0), PF_R(0.0), PF_R(1.0), PF_R(1.0), PF_R(1.0)},       /* r = 1 exactly */
    };
    int i, j;
    for (i = 0; i < 6; i++) {
        pf_slope_moments m = pf_slope_moments_make(bad[i][0], bad[i][1], bad[i][2], bad[i][3], bad[i][4]);
        pf_slope_stats s = pf_slope_moments_stats(m, PF_R(0.0));
        pf_real r = pf_slope_stats_correlation(s);
        PF_CHECK(s.var_x >= PF_BECKMANN_MIN_VAR && s.var_y >= PF_BECKMANN_MIN_VAR, "case %d variances %g %g", i,
                 (double)s.var_x, (double)s.var_y);
        PF_CHECK(s.var_x * s.var_y - s.cov_xy * s.cov_xy > PF_R(0.0), "case %d not positive definite", i);
        PF_CHECK(r > PF_R(-1.0) && r < PF_R(1.0), "case %d r = %g", i, (double)r);
        for (j = 0; j < 40; j++) {
            pf_real t = (pf_real)j * PF_R(0.04), p = (pf_real)j * PF_R(0.7);
            pf_vec3 wo = pf_vec3_make(PF_SIN(t) * PF_COS(p), PF_SIN(t) * PF_SIN(p), PF_COS(t));
            pf_vec3 wi = pf_vec3_make(-wo.y, wo.x, wo.z);
            pf_real d = pf_beckmann_d(pf_vec3_add(wo, wi), s);
            pf_real f = pf_leadr_specular(wo, wi, s, PF_R(0.04));
            pf_real fm = pf_leadr_specular_masking(wo, wi, s, PF_R(0.04));
            PF_CHECK(finite_nonneg(d) && finite_nonneg(f) && finite_nonneg(fm), "case %d dir %d: D %g I %g %g", i, j,
                     (double)d, (double)f, (double)fm);
        }
    }
}

static void edge_directions(void)
{
    pf_slope_stats s = pf_slope_moments_stats(pf_slope_moments_make(PF_R(0.8), PF_R(-0.3), PF_R(0.8), PF_R(0.2), PF_R(-0.2)),
                                              PF_R(0.01));
    pf_vec3 up = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
    pf_vec3 graze = pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(1e-7));
    pf_vec3 below = pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(-0.8));
    /* above the macrosurface but below the mesosurface (mean slope 0.8 along x tilts it) */
    pf_vec3 under_meso = pf_vec3_normalize(pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(0.5)));
    pf_real zero = PF_R(0.0);
    PF_CHECK(pf_leadr_specular(up, below, s, PF_R(1.0)) == zero, "light below the horizon");
    PF_CHECK(pf_leadr_specular(below, up, s, PF_R(1.0)) == zero, "view below the horizon");
    PF_CHECK(pf_leadr_specular_masking(up, below, s, PF_R(1.0)) == zero, "masking: light below");
    /* a light below the mesosurface but above the macrosurface lights the facets facing it
       (issue 15, bench/pictures.c: Lambda_i capped, pf_beckmann_light_lambda) */
    PF_CHECK(pf_leadr_specular(up, under_meso, s, PF_R(1.0)) > zero &&
                 finite_nonneg(pf_leadr_specular(up, under_meso, s, PF_R(1.0))),
             "light below the mesosurface");
    /* a view below the mesosurface but above the macrosurface sees the facets facing it (the
       pic_plane regression, tests/test_moments.c): positive, finite */
    PF_CHECK(pf_leadr_specular_masking(under_meso, up, s, PF_R(1.0)) > zero &&
                 finite_nonneg(pf_leadr_specular_masking(under_meso, up, s, PF_R(1.0))),
             "view below the mesosurface");
    PF_CHECK(pf_leadr_specular(under_meso, up, s, PF_R(1.0)) > zero &&
                 finite_nonneg(pf_leadr_specular(under_meso, up, s, PF_R(1.0))),
             "view below the mesosurface, joint");
    PF_CHECK(finite_nonneg(pf_leadr_specular(graze, up, s, PF_R(1.0))), "grazing view");
    PF_CHECK(finite_nonneg(pf_leadr_specular(up, graze, s, PF_R(1.0))), "grazing light");
    PF_CHECK(finite_nonneg(pf_leadr_specular(graze, graze, s, PF_R(1.0))), "grazing both");
    PF_CHECK(pf_beckmann_d(pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(0.0)), s) == zero, "D at the horizon");
    PF_CHECK(pf_beckmann_d(pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0)), s) == zero, "D of a zero vector");
    PF_CHECK(finite_nonneg(pf_beckmann_d(pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(1e-30)), s)), "D near the horizon");
    PF_CHECK(pf_leadr_specular_point(up, pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0)), s, PF_R(1.0)) == zero,
             "point light at the shaded point");
    PF_CHECK(finite_nonneg(pf_leadr_specular_point(up, pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(2.0)), s, PF_R(1.0))),
             "point light");
    /* a point light at distance 2 is the directional value over 4 */
    {
        pf_real a = pf_leadr_specular_point(graze, pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(1.6)), s, PF_R(0.5));
        pf_real b = pf_leadr_specular(graze, pf_vec3_normalize(pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(1.6))), s, PF_R(0.5));
        long double d2 = 0.36L + 2.56L;
        PF_CHECK(fabsl((long double)a * d2 - (long double)b) <= 8.0L * PF_TEST_EPS * fabsl((long double)b) + 1e-30L,
                 "point light falloff %g vs %g", (double)a, (double)b);
    }
}

/* sigma -> 0: D tends to a delta. At the peak D = 1/(2 pi sqrt(det)) cos^-4 grows as 1/sigma^2
   and stays finite down to the floor; off the peak it is 0. */
static void edge_sigma_to_zero(void)
{
    int e;
    pf_real last = PF_R(0.0);
    for (e = 1; e <= 40; e++) {
        pf_real v = PF_POW(PF_R(10.0), -(pf_real)e);
        pf_slope_stats s = pf_slope_stats_make(PF_R(0.3), PF_R(0.1), v, v, PF_R(0.0));
        pf_vec3 peak = pf_vec3_make(PF_R(-0.3), PF_R(-0.1), PF_R(1.0));
        pf_vec3 off = pf_vec3_make(PF_R(-0.2), PF_R(-0.1), PF_R(1.0));
        pf_real dp = pf_beckmann_d(peak, s), doff = pf_beckmann_d(off, s);
        pf_real p22 = pf_beckmann_p22(PF_R(0.3), PF_R(0.1), s);
        PF_CHECK(finite_nonneg(dp) && finite_nonneg(doff) && finite_nonneg(p22), "var 1e-%d: %g %g %g", e, (double)dp,
                 (double)doff, (double)p22);
        PF_CHECK(dp >= last, "peak of D does not grow as sigma falls (var 1e-%d)", e);
        /* off the peak by 0.1 in slope: exp(-0.005/var), 0 in float and double once var <= 1e-6 */
        if (e >= 6) PF_CHECK(doff == PF_R(0.0), "off-peak D at var 1e-%d: %g", e, (double)doff);
        last = dp;
        /* the specular value at the mirror configuration stays finite */
        {
            pf_vec3 n = pf_beckmann_mesonormal(s);
            pf_vec3 wo = pf_vec3_normalize(pf_vec3_make(PF_R(0.3), PF_R(0.2), PF_R(1.0)));
            pf_vec3 wi = pf_vec3_sub(pf_vec3_scale(n, PF_R(2.0) * pf_vec3_dot(n, wo)), wo);
            PF_CHECK(finite_nonneg(pf_leadr_specular(wo, wi, s, PF_R(1.0))), "mirror, var 1e-%d", e);
        }
    }
}

/* Singular covariance given directly (not through pf_slope_moments_stats). */
static void edge_singular_covariance(void)
{
    static const pf_real cov[5][3] = {
        {PF_R(0.0), PF_R(0.0), PF_R(0.0)}, {PF_R(0.1), PF_R(0.0), PF_R(0.0)}, {PF_R(0.1), PF_R(0.1), PF_R(0.1)}, {PF_R(0.1), PF_R(0.1), PF_R(-0.1)}, {PF_R(-0.1), PF_R(0.2), PF_R(0.3)},
    };
    int i, j;
    for (i = 0; i < 5; i++) {
        pf_slope_stats s = pf_slope_stats_make(PF_R(0.1), PF_R(0.2), cov[i][0], cov[i][1], cov[i][2]);
        for (j = 0; j < 25; j++) {
            pf_real x = PF_R(-0.5) + PF_R(0.05) * (pf_real)j;
            pf_vec3 m = pf_vec3_make(-x, PF_R(-0.2), PF_R(1.0));
            pf_vec3 wo = pf_vec3_normalize(pf_vec3_make(x, PF_R(0.1), PF_R(0.8)));
            PF_CHECK(finite_nonneg(pf_beckmann_p22(x, PF_R(0.2), s)), "p22 cov %d", i);
            PF_CHECK(finite_nonneg(pf_beckmann_d(m, s)), "D cov %d", i);
            PF_CHECK(finite_nonneg(pf_leadr_specular(wo, pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)), s, PF_R(0.04))),
                     "BRDF cov %d", i);
            PF_CHECK(finite_nonneg(pf_beckmann_lambda(wo, s)) && pf_beckmann_g1(wo, s) <= PF_R(1.0), "Lambda cov %d", i);
        }
    }
}

/* The sweep's findings (docs/stability.md, first sweep): a variance near PF_REAL_MAX made
   var_x var_y = inf and P22, D = inf/inf = NaN; under -ffast-math a mean slope near PF_REAL_MAX
   made the mesonormal NaN (pf_vec3_normalize's 1/m flushed to 0). Exact P22 input, then every
   variance up to PF_REAL_MAX; below the cap (1e15 / 1e150) the value is the uncapped formula. */
static void edge_beckmann_huge_variance(void)
{
    pf_slope_stats s = pf_slope_stats_make((pf_real)ldexp(15925248.0, -37), PF_R(-256.0), PF_REAL_MAX,
                                           (pf_real)ldexp(12124160.0, -21), PF_R(0.0));
    pf_real p = pf_beckmann_p22(PF_R(0.0), PF_R(-1048576.0), s);
    pf_vec3 mn = pf_beckmann_mesonormal(pf_slope_stats_make(PF_R(256.0), PF_REAL_MAX, PF_R(0.15), PF_R(0.0), PF_R(0.0)));
    int e, k, bad = 0;
    PF_CHECK(pf_test_bits_finite(p) && p >= PF_R(0.0), "p22 with var_x = MAX: %g", (double)p);
    PF_CHECK(pf_test_bits_finite(mn.x) && pf_test_bits_finite(mn.y) && pf_test_bits_finite(mn.z) && mn.y == PF_R(-1.0),
             "mesonormal(256, MAX) = (%g %g %g)", (double)mn.x, (double)mn.y, (double)mn.z);
    for (e = 0; e <= 38; e += 2)
        for (k = 0; k < 4; ++k) {
            pf_real v = (pf_real)pow(10.0, (double)e) * (pf_real)(1.0 + 0.3 * k);
            pf_slope_stats t = pf_slope_stats_make(PF_R(0.1), PF_R(-0.2), v, k % 2 ? PF_R(0.3) : v, PF_R(0.0));
            pf_vec3 m = pf_vec3_make(PF_R(-0.727436185), PF_R(-0.686175287), PF_R(0.2));
            pf_real a = pf_beckmann_p22(PF_R(0.3), PF_R(1.0e3), t), d = pf_beckmann_d(m, t);
            bad += !(pf_test_bits_finite(a) && a >= PF_R(0.0) && pf_test_bits_finite(d) && d >= PF_R(0.0));
        }
    bad += !(pf_test_bits_finite(pf_beckmann_p22(PF_REAL_MAX, -PF_REAL_MAX, s)) && pf_test_bits_finite(pf_beckmann_d(
                 pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(1.0)), pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_REAL_MAX,
                                                                                   PF_REAL_MAX, PF_REAL_MAX))));
    PF_CHECK(bad == 0, "%d non-finite or negative P22 / D", bad);
    {
        /* a variance just below the cap is not changed: P22 at the mean = 1/(2 pi sqrt(det)) */
#ifdef PF_DOUBLE
        long double v = 1.0e149L;
#else
        long double v = 1.0e14L;
#endif
        pf_real got = pf_beckmann_p22(PF_R(0.0), PF_R(0.0), pf_slope_stats_make(PF_R(0.0), PF_R(0.0), (pf_real)v, PF_R(1.0), PF_R(0.0)));
        long double want = 1.0L / (2.0L * PF_TEST_PI * sqrtl((long double)(pf_real)v));
        PF_CHECK(pf_test_rel_error((long double)got, want) <= 8.0L * PF_TEST_EPS, "p22 peak %g vs %Lg", (double)got, want);
    }
}

static void edge_fresnel(void)
{
    int i;
    for (i = -2; i <= 12; i++) {
        pf_real c = (pf_real)i * PF_R(0.1);
        pf_real f = pf_fresnel_schlick(PF_R(0.04), c);
        PF_CHECK(f >= PF_R(0.04) && f <= PF_R(1.0), "Schlick(%g) = %g", (double)c, (double)f);
        PF_CHECK(pf_fresnel_schlick(PF_R(1.0), c) == PF_R(1.0), "f0 = 1 is Fresnel off");
    }
}

/* Lean D (issue 17): one select for m.z <= 0, floors applied once. m.z <= 0 gives exactly 0;
   tiny, subnormal and huge components give finite values >= 0; and a covariance with one
   variance 0 is still the Gaussian of the other axis along the degenerate line (the variance
   floor, not only a determinant floor: with det floored alone, q/det along that line lost
   the 1/var_y scale and D came out flat). Oracle for the last: the ratio of D at two slopes on
   the line, exp(-(y1^2 - y0^2) / (2 var_y)) (cos0 / cos1)^4, in long double. */
static void edge_beckmann_d_lean(void)
{
    static const double zs[] = { 0.0, -0.0, -1e-30, -1.0, 1e-40, 1e-30, 1e-19, 1.0, 1e19 };
    static const double xs[] = { 0.0, 1.0, -3.0, 1e-30, 1e30, -3e38 };
    pf_slope_stats s = pf_slope_stats_make(PF_R(0.1), PF_R(-0.2), PF_R(0.3), PF_R(0.2), PF_R(0.1));
    pf_slope_stats hc = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(1.0), PF_R(1.0), PF_REAL_MAX);
    pf_slope_stats line = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.1), PF_R(0.0));
    long double worst = 0;
    int i, j, k;
    for (i = 0; i < (int)(sizeof zs / sizeof zs[0]); ++i)
        for (j = 0; j < (int)(sizeof xs / sizeof xs[0]); ++j)
            for (k = 0; k < (int)(sizeof xs / sizeof xs[0]); ++k) {
                pf_vec3 m = pf_vec3_make((pf_real)xs[j], (pf_real)xs[k], (pf_real)zs[i]);
                pf_real a = pf_beckmann_d(m, s), b = pf_beckmann_d(m, hc);
                PF_CHECK(finite_nonneg(a) && finite_nonneg(b), "D(%g %g %g) = %g, %g (cov near MAX)", xs[j], xs[k], zs[i],
                         (double)a, (double)b);
                if (!(zs[i] > 0.0)) PF_CHECK(a == PF_R(0.0) && b == PF_R(0.0), "D below the horizon: %g %g", (double)a, (double)b);
            }
    for (i = 1; i <= 8; ++i) {
        long double y = 0.1L * i, c0 = 1.0L, c1 = 1.0L / sqrtl(1.0L + y * y);
        long double want = expl(-(y * y) / (2.0L * 0.1L)) * powl(c0 / c1, 4.0L);
        long double got = (long double)pf_beckmann_d(pf_vec3_make(PF_R(0.0), -(pf_real)y, PF_R(1.0)), line) /
                          (long double)pf_beckmann_d(pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)), line);
        long double e = fabsl(got / want - 1.0L);
        if (e > worst) worst = e;
    }
    pf_test_note("degenerate axis: ratio error %.3g", (double)worst);
    PF_CHECK(worst <= 64.0L * PF_TEST_EPS, "D along a degenerate axis is not the other axis' Gaussian: %.3g", (double)worst);
}

/* Lean LEADR specular at the degenerate directions: normal incidence (nu = inf: G1 = 1) and
   zero variances given directly (both nu huge), where the joint and the masking-only terms
   are both exactly 1, so the two BRDFs agree to the bit; the light or the view on or below the
   macrosurface gives exactly 0, a light below the mean plane (above the macrosurface) not. */
/* equal, or within 8 ulp relative in -ffast-math builds (which give up exact rounding) */
static int same_or_close(pf_real a, pf_real b)
{
#ifdef __FAST_MATH__
    return fabsl((long double)a - (long double)b) <= 8.0L * PF_TEST_EPS * fabsl((long double)b);
#else
    return a == b;
#endif
}

static void edge_leadr_lean(void)
{
    pf_slope_stats z0 = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    pf_slope_stats z1 = pf_slope_stats_make(PF_R(0.2), PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    pf_vec3 up = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
    int i;
    for (i = 0; i < 12; ++i) {
        pf_real t = PF_R(0.12) * (pf_real)i;
        pf_vec3 wi = pf_vec3_make(PF_SIN(t), PF_R(0.0), PF_COS(t));
        pf_real a = pf_leadr_specular(up, wi, z0, PF_R(0.04)), b = pf_leadr_specular_masking(up, wi, z0, PF_R(0.04));
        pf_real c = pf_leadr_specular(wi, up, z1, PF_R(0.5)), d = pf_leadr_specular_masking(wi, up, z1, PF_R(0.5));
        /* shadowing is 1 here, so the two agree: exactly, or to a few ulp under -ffast-math (clang
           -O3 -ffast-math evaluates the two functions' products in different orders) */
        PF_CHECK(finite_nonneg(a) && same_or_close(a, b), "zero variance, view up, light %d: %.9g vs masking %.9g", i,
                 (double)a, (double)b);
        PF_CHECK(finite_nonneg(c) && same_or_close(c, d), "zero variance, mean slope, light up, view %d: %.9g vs %.9g", i,
                 (double)c, (double)d);
    }
    PF_CHECK(pf_leadr_specular(up, pf_vec3_make(PF_R(1.0), PF_R(0.0), PF_R(0.0)), z0, PF_R(1.0)) == PF_R(0.0), "light at the horizon");
    PF_CHECK(pf_leadr_specular(pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(-1.0)), up, z0, PF_R(1.0)) == PF_R(0.0), "view below");
    /* mean slope 2 in x: (1, 0, 1)/sqrt2 is below the mean plane (area 1 - 2 < 0) */
    /* ... where the light still reaches the facets facing it (Lambda_i capped,
       pf_beckmann_light_lambda): positive and finite */
    {
        pf_real v = pf_leadr_specular(up, pf_vec3_make(PF_R(0.7071), PF_R(0.0), PF_R(0.7071)),
                                      pf_slope_stats_make(PF_R(2.0), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0)), PF_R(1.0));
        PF_CHECK(finite_nonneg(v) && v > PF_R(0.0), "light below the mean plane: %g", (double)v);
    }
}

/* ------------------------------------------------------------------ the base lobe's own masking
   pf_beckmann_base_masking against its definition, integrated in slope space: over the texel
   slopes s in a window of +-8 base deviations around the peak of the integrand's weight
   (found in the information form, not the library's), midpoint rule NB x NB in long double,
       E[G2_b] = int N(s; mean, S0) N(x_h; s, vb I) G2_b(s) ds / int N(s; mean, S0) N(x_h; s, vb I) ds,
   G2_b(s) = 1 / (1 + Lambda(nu_o) + Lambda(nu_i)), nu = (w.z - s.w.xy) / sqrt(2 vb |w.xy|^2),
   0 when either area is <= 0; Lambda in long double from erfcl (no cancellation below nu = 8,
   0 above). Configurations: footprint deviations 0.1-0.5, |r| <= 0.6, mean slopes up to 0.5,
   base deviations 0.05-0.2, views 0-88 degrees, lights random or the mirror of the view about
   the mesonormal (down to a reference of 0.16). Bound: the 4 x 4 rule's error, measured here
   (max 6.3e-3 absolute, rms 1.5e-3, float and double alike: the rule's, not rounding), checked
   at 0.01 absolute; the Gauss-Hermite rule tried first was 0.21 off (it missed the band where
   both areas are positive). */
#define BASE_NB 240
static long double base_lambda_ld(long double nu)
{
    if (!(nu > 0.0L)) return -1.0L;
    if (nu > 8.0L) return 0.0L;
    return expl(-nu * nu) / (2.0L * nu * 1.772453850905516027298167483341145L) - 0.5L * erfcl(nu);
}
static long double base_masking_def(bcfg k, long double vb, const long double *wo, const long double *wi)
{
    long double hz = wo[2] + wi[2], hx = -(wo[0] + wi[0]) / hz, hy = -(wo[1] + wi[1]) / hz;
    long double v0x = k.vx - vb, v0y = k.vy - vb, c0 = k.cxy, det = v0x * v0y - c0 * c0, sb = sqrtl(vb);
    long double ro = sqrtl(2.0L * vb * (wo[0] * wo[0] + wo[1] * wo[1])), ri = sqrtl(2.0L * vb * (wi[0] * wi[0] + wi[1] * wi[1]));
    long double num = 0.0L, den = 0.0L, cx, cy;
    int i, j;
    /* the window's centre: the peak of the product, in the information form (S0^-1 + I/vb)^-1
       (S0^-1 mean + x_h / vb) (the library uses x_h - vb S^-1 (x_h - mean)); the product's
       covariance is below vb I, so +-8 sqrt(vb) holds all but exp(-32) of it */
    {
        long double ixx = v0y / det + 1.0L / vb, iyy = v0x / det + 1.0L / vb, ixy = -c0 / det, idet = ixx * iyy - ixy * ixy;
        long double bx = (v0y * k.mx - c0 * k.my) / det + hx / vb, by = (v0x * k.my - c0 * k.mx) / det + hy / vb;
        cx = (iyy * bx - ixy * by) / idet;
        cy = (ixx * by - ixy * bx) / idet;
    }
    for (j = 0; j < BASE_NB; ++j)
        for (i = 0; i < BASE_NB; ++i) {
            long double ux = -8.0L + 16.0L * ((long double)i + 0.5L) / BASE_NB, uy = -8.0L + 16.0L * ((long double)j + 0.5L) / BASE_NB;
            long double sx = cx + sb * ux, sy = cy + sb * uy, dx = sx - k.mx, dy = sy - k.my, ex = (sx - hx) / sb, ey = (sy - hy) / sb;
            long double q = (v0y * dx * dx - 2.0L * c0 * dx * dy + v0x * dy * dy) / det;
            long double wgt = expl(-0.5L * q - 0.5L * (ex * ex + ey * ey));
            long double ao = wo[2] - sx * wo[0] - sy * wo[1], ai = wi[2] - sx * wi[0] - sy * wi[1];
            long double lo = ro > 0.0L ? base_lambda_ld(ao / ro) : (ao > 0.0L ? 0.0L : -1.0L);
            long double li = ri > 0.0L ? base_lambda_ld(ai / ri) : (ai > 0.0L ? 0.0L : -1.0L);
            den += wgt;
            if (lo >= 0.0L && li >= 0.0L) num += wgt / (1.0L + lo + li);
        }
    return num / den;
}
static void test_base_masking_quadrature(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x6261736532ULL);
    pf_test_max m = pf_test_max_init();
    long double sum2 = 0.0L, lo_ref = 1.0L;
    int n, bad = 0, ncase = 48;
    for (n = 0; n < ncase; ++n) {
        bcfg k;
        long double vb = (long double)pf_test_log_uniform(&rng, 0.05, 0.2), wo[3], wi[3], ref, err;
        long double sx = (long double)pf_test_uniform(&rng, 0.1, 0.5), sy = (long double)pf_test_uniform(&rng, 0.1, 0.5);
        long double r = (long double)pf_test_uniform(&rng, -0.6, 0.6), a = (long double)pf_test_uniform(&rng, -3.14159, 3.14159);
        long double mm = (long double)pf_test_uniform(&rng, 0.0, 0.5);
        long double to = (long double)pf_test_uniform(&rng, 0.0, 1.0) * (n < ncase / 2 ? 1.536L : 0.3L) + (n < ncase / 2 ? 0.0L : 1.236L);
        long double po = (long double)pf_test_uniform(&rng, -3.14159, 3.14159);
        pf_real got;
        vb = vb * vb;
        k.mx = mm * cosl(a);
        k.my = mm * sinl(a);
        k.vx = sx * sx + vb;
        k.vy = sy * sy + vb;
        k.cxy = r * sx * sy;
        k = bcfg_round(k);
        vb = (long double)(pf_real)vb;
        wo[0] = sinl(to) * cosl(po);
        wo[1] = sinl(to) * sinl(po);
        wo[2] = cosl(to);
        if (n % 2 == 0) { /* the mirror of the view about the mesonormal */
            long double nx = -k.mx, ny = -k.my, nz = 1.0L, len = sqrtl(nx * nx + ny * ny + 1.0L), d;
            nx /= len; ny /= len; nz /= len;
            d = nx * wo[0] + ny * wo[1] + nz * wo[2];
            wi[0] = 2.0L * d * nx - wo[0];
            wi[1] = 2.0L * d * ny - wo[1];
            wi[2] = 2.0L * d * nz - wo[2];
            if (!(wi[2] > 0.05L)) { wi[0] = -wo[0]; wi[1] = -wo[1]; wi[2] = wo[2]; }
        } else {
            long double ti = (long double)pf_test_uniform(&rng, 0.0, 1.5), pi = (long double)pf_test_uniform(&rng, -3.14159, 3.14159);
            wi[0] = sinl(ti) * cosl(pi);
            wi[1] = sinl(ti) * sinl(pi);
            wi[2] = cosl(ti);
        }
        /* the library's inputs, rounded to pf_real; the reference sees the same directions */
        {
            pf_vec3 o = vec3_of(wo[0], wo[1], wo[2]), i = vec3_of(wi[0], wi[1], wi[2]);
            wo[0] = (long double)o.x; wo[1] = (long double)o.y; wo[2] = (long double)o.z;
            wi[0] = (long double)i.x; wi[1] = (long double)i.y; wi[2] = (long double)i.z;
            got = pf_beckmann_base_masking(o, i, bcfg_stats(k), (pf_real)vb);
        }
        ref = base_masking_def(k, vb, wo, wi);
        if (!(ref == ref)) ++bad;
        if (ref < lo_ref) lo_ref = ref;
        err = fabsl((long double)got - ref);
        sum2 += err * err;
        pf_test_max_update(&m, err, (long double)n);
        PF_CHECK(got >= PF_R(0.0) && got <= PF_R(1.0), "base masking outside [0, 1]: %g", (double)got);
    }
    pf_test_note("base masking vs definition: max %.3g abs (case %d), rms %.3g, smallest reference %.3g", (double)m.err,
                 (int)m.at, (double)sqrtl(sum2 / ncase), (double)lo_ref);
    PF_CHECK(m.err <= 0.01L, "base masking vs definition: %.3g absolute (case %d)", (double)m.err, (int)m.at);
    PF_CHECK(lo_ref < 0.5L, "no configuration where the base lobe masks (smallest reference %.3g)", (double)lo_ref);
    PF_CHECK(bad == 0, "%d references NaN", bad);
    /* no base lobe: exactly 1 */
    PF_CHECK(pf_beckmann_base_masking(pf_vec3_make(PF_R(0.9), PF_R(0.0), PF_R(0.1)), pf_vec3_make(PF_R(-0.9), PF_R(0.0), PF_R(0.1)),
                                      pf_slope_stats_make(PF_R(0.0), PF_R(0.0), PF_R(0.1), PF_R(0.1), PF_R(0.0)), PF_R(0.0)) == PF_R(1.0),
             "base_var 0 must give 1");
    /* statistics below the base variance (inconsistent input) are read as one slope: the
       same value as S = base_var I exactly */
    {
        pf_vec3 o = pf_vec3_normalize(pf_vec3_make(PF_R(0.6), PF_R(-0.55), PF_R(0.58))), i = pf_vec3_normalize(pf_vec3_make(PF_R(-0.99), PF_R(-0.02), PF_R(0.05)));
        pf_real a = pf_beckmann_base_masking(o, i, pf_slope_stats_make(PF_R(0.18), PF_R(0.2), PF_R(0.003), PF_R(0.004), PF_R(0.0034)), PF_R(0.01));
        pf_real b = pf_beckmann_base_masking(o, i, pf_slope_stats_make(PF_R(0.18), PF_R(0.2), PF_R(0.01), PF_R(0.01), PF_R(0.0)), PF_R(0.01));
        PF_CHECK(a == b && a >= PF_R(0.0) && a <= PF_R(1.0), "statistics below the base variance: %g vs %g", (double)a, (double)b);
    }
    /* a one-texel footprint (S = base_var I): the base lobe's masking is counted once, so
       pf_leadr_specular_base is pf_leadr_specular (whose Smith G is then the base lobe's own),
       to the rule's accuracy; at a grazing view, mirror light, where it is far from 1 */
    {
        pf_vec3 o = pf_vec3_normalize(pf_vec3_make(PF_R(0.99), PF_R(0.0), PF_R(0.0871557))), i = pf_vec3_make(-o.x, -o.y, o.z);
        pf_slope_stats st = pf_slope_stats_make(PF_R(0.02), PF_R(-0.01), PF_R(0.01), PF_R(0.01), PF_R(0.0));
        pf_real a = pf_leadr_specular_base(o, i, st, PF_R(0.01), PF_R(1.0));
        pf_real b = pf_leadr_specular(o, i, st, PF_R(1.0));
        pf_real g = pf_beckmann_masking_shadowing(o, i, st);
        PF_CHECK(a > PF_R(0.0) && fabsl((long double)a / (long double)b - 1.0L) <= 1e-3L && g < PF_R(0.9),
                 "one texel: pf_leadr_specular_base %g vs pf_leadr_specular %g (G %g)", (double)a, (double)b, (double)g);
        /* a steep texel (a crater's wall): the view's area ~2.3, where a deviation at its floor
           vanished in float next to it and the mass came out 1/2 */
        o = pf_vec3_make(PF_R(0.852868557), PF_R(0.150383726), PF_R(0.5));
        i = pf_vec3_make(PF_R(0.238368616), PF_R(-0.925060809), PF_R(0.295707524));
        st = pf_slope_stats_make(PF_R(-2.06218243), PF_R(-0.0903292298), PF_R(0.01), PF_R(0.01), PF_R(0.0));
        a = pf_leadr_specular_base(o, i, st, PF_R(0.01), PF_R(1.0));
        b = pf_leadr_specular(o, i, st, PF_R(1.0));
        PF_CHECK(a > PF_R(0.0) && fabsl((long double)a / (long double)b - 1.0L) <= 1e-3L,
                 "one steep texel: pf_leadr_specular_base %g vs pf_leadr_specular %g", (double)a, (double)b);
    }
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_d_pointwise);
    PF_TEST_RUN(test_normalization_slope_plane);
    PF_TEST_RUN(test_normalization_polar);
    PF_TEST_RUN(test_projected_area_identity);
    PF_TEST_RUN(test_brdf_identity_and_energy);
    PF_TEST_RUN(test_specular_pointwise);
    PF_TEST_RUN(test_specular_light_below_mean_plane);
    PF_TEST_RUN(test_deformation_brute_force);
    PF_TEST_RUN(test_centered_reduces_to_textbook);
    PF_TEST_RUN(test_moments_stats);
    PF_TEST_RUN(test_base_masking_quadrature);
    PF_TEST_RUN(test_worked_example);
    PF_TEST_RUN(edge_filtered_moments);
    PF_TEST_RUN(edge_directions);
    PF_TEST_RUN(edge_sigma_to_zero);
    PF_TEST_RUN(edge_singular_covariance);
    PF_TEST_RUN(edge_fresnel);
    PF_TEST_RUN(edge_beckmann_huge_variance);
    PF_TEST_RUN(edge_beckmann_d_lean);
    PF_TEST_RUN(edge_leadr_lean);
    return PF_TEST_END();
}

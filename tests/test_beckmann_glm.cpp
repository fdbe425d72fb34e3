// test_beckmann_glm.cpp - cross-check of the vector and 2x2 matrix algebra inside
// include/pf_beckmann.h against GLM (the OpenGL Mathematics library, Debian libglm-dev).
//
// GLM is the vector library most shader and engine code is written against; recomputing with
// its types and functions what our header does with scalars (half vectors, reflections,
// normalization, the mesonormal, the covariance inverse and Cholesky factor inside P22 and D)
// catches sign and convention slips that a test written in our own algebra would repeat.
// Built as C++11 in float and double (make test: the glm-float and glm-double builds).
#include "pf_beckmann.h"
#include "pf_test.h"

#include <glm/glm.hpp>

#ifdef PF_DOUBLE
typedef glm::dvec3 gvec3;
typedef glm::dvec2 gvec2;
typedef glm::dmat2 gmat2;
#else
typedef glm::vec3 gvec3;
typedef glm::vec2 gvec2;
typedef glm::mat2 gmat2;
#endif

static pf_vec3 from_glm(gvec3 v) { return pf_vec3_make(v.x, v.y, v.z); }

static long double vec_err(pf_vec3 a, gvec3 b)
{
    long double e = 0.0L;
    e = fmaxl(e, fabsl((long double)a.x - (long double)b.x));
    e = fmaxl(e, fabsl((long double)a.y - (long double)b.y));
    e = fmaxl(e, fabsl((long double)a.z - (long double)b.z));
    return e;
}

static gvec3 random_dir(pf_test_rng *rng, double zmin)
{
    double t = pf_test_uniform(rng, 0.0, std::acos(zmin)), p = pf_test_uniform(rng, -3.14159, 3.14159);
    return gvec3((pf_real)(std::sin(t) * std::cos(p)), (pf_real)(std::sin(t) * std::sin(p)), (pf_real)std::cos(t));
}

static pf_slope_stats random_stats(pf_test_rng *rng)
{
    double sx = pf_test_log_uniform(rng, 0.05, 0.8), sy = pf_test_log_uniform(rng, 0.05, 0.8);
    double r = pf_test_uniform(rng, -0.95, 0.95);
    return pf_slope_stats_make((pf_real)pf_test_uniform(rng, -1.5, 1.5), (pf_real)pf_test_uniform(rng, -1.5, 1.5),
                               (pf_real)(sx * sx), (pf_real)(sy * sy), (pf_real)(r * sx * sy));
}

// Half vectors, reflection (LEADR eq. 18), normalization and the mesonormal (eq. 11).
static void test_vectors_against_glm(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x61a00001ULL);
    long double eh = 0.0L, er = 0.0L, en = 0.0L, em = 0.0L, ed = 0.0L;
    for (int i = 0; i < 20000; i++) {
        gvec3 o = random_dir(&rng, 0.01), l = random_dir(&rng, 0.01);
        pf_vec3 po = from_glm(o), pl = from_glm(l);
        // half vector
        eh = fmaxl(eh, vec_err(pf_vec3_normalize(pf_vec3_add(po, pl)), glm::normalize(o + l)));
        // reflection of the view about a normal: glm::reflect(I, N) = I - 2 dot(N, I) N with I = -o
        pf_vec3 n = pf_vec3_normalize(pf_vec3_add(po, pl));
        gvec3 gn = glm::normalize(o + l);
        pf_vec3 r = pf_vec3_sub(pf_vec3_scale(n, (pf_real)2 * pf_vec3_dot(n, po)), po);
        er = fmaxl(er, vec_err(r, glm::reflect(-o, gn)));
        // reflecting the view about the half vector gives the light back
        er = fmaxl(er, vec_err(r, l));
        en = fmaxl(en, fabsl((long double)pf_vec3_length(po) - (long double)glm::length(o)));
        // the mesonormal
        pf_slope_stats s = random_stats(&rng);
        em = fmaxl(em, vec_err(pf_beckmann_mesonormal(s), glm::normalize(gvec3(-s.mean_x, -s.mean_y, (pf_real)1))));
        // the projected area (eq. 1) as dot products with glm: (n_bar . o)/(n_bar . g)
        gvec3 nb = glm::normalize(gvec3(-s.mean_x, -s.mean_y, (pf_real)1));
        long double area = (long double)glm::dot(nb, o) / (long double)glm::dot(nb, gvec3(0, 0, 1));
        // absolute error on the scale of the terms summed: both sides cancel when the view
        // nears the mean plane, so a relative error would measure glm's cancellation
        if (area > 0.0L)
            ed = fmaxl(ed, fabsl((long double)pf_beckmann_projected_area(po, s) - area) /
                               (1.0L + fabsl((long double)s.mean_x) + fabsl((long double)s.mean_y)));
    }
    pf_test_note("vs GLM (20000 random pairs): half vector %.2g, reflection %.2g, length %.2g, mesonormal %.2g, "
                 "projected area %.2g (in eps: %.1f %.1f %.1f %.1f %.1f)",
                 (double)eh, (double)er, (double)en, (double)em, (double)ed, (double)(eh / PF_TEST_EPS), (double)(er / PF_TEST_EPS),
                 (double)(en / PF_TEST_EPS), (double)(em / PF_TEST_EPS), (double)(ed / PF_TEST_EPS));
    PF_CHECK(eh <= 8.0L * PF_TEST_EPS, "half vector: %.3g", (double)eh);
    PF_CHECK(er <= 16.0L * PF_TEST_EPS, "reflection: %.3g", (double)er);
    PF_CHECK(en <= 4.0L * PF_TEST_EPS, "length: %.3g", (double)en);
    PF_CHECK(em <= 8.0L * PF_TEST_EPS, "mesonormal: %.3g", (double)em);
    PF_CHECK(ed <= 64.0L * PF_TEST_EPS, "projected area: %.3g", (double)ed);
}

// P22 (eq. 8) and D (eq. 10) recomputed with glm::inverse / glm::determinant of the 2x2
// covariance, and once more through its Cholesky factor (whitening), against ours (adjugate).
static void test_covariance_against_glm(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x61a00002ULL);
    long double ep = 0.0L, ec = 0.0L, ed = 0.0L, einv = 0.0L;
    for (int i = 0; i < 20000; i++) {
        pf_slope_stats s = random_stats(&rng);
        gmat2 cov(s.var_x, s.cov_xy, s.cov_xy, s.var_y); // column-major, symmetric
        gmat2 inv = glm::inverse(cov);
        // inverse check: cov * inv = identity
        gmat2 id = cov * inv;
        einv = fmaxl(einv, fabsl((long double)id[0][0] - 1.0L) + fabsl((long double)id[1][0]) +
                               fabsl((long double)id[0][1]) + fabsl((long double)id[1][1] - 1.0L));
        // a slope within ~3 sigma of the mean
        gvec2 d((pf_real)pf_test_uniform(&rng, -2.0, 2.0) * std::sqrt(s.var_x),
                (pf_real)pf_test_uniform(&rng, -2.0, 2.0) * std::sqrt(s.var_y));
        gvec2 slope = gvec2(s.mean_x, s.mean_y) + d;
        long double q = (long double)glm::dot(d, inv * d);
        long double p_glm = expl(-0.5L * q) / (2.0L * 3.14159265358979323846L * sqrtl((long double)glm::determinant(cov)));
        long double p_ours = (long double)pf_beckmann_p22(slope.x, slope.y, s);
        ep = fmaxl(ep, fabsl(p_ours - p_glm) / p_glm / (1.0L + q));
        // Cholesky with glm types: cov = L L^T, L lower triangular; whiten d by solving L z = d
        pf_real a = std::sqrt(s.var_x), b = s.cov_xy / a, c = std::sqrt(s.var_y - b * b);
        gmat2 L(a, b, (pf_real)0, c); // columns (a, b) and (0, c)
        gmat2 LLt = L * glm::transpose(L);
        ec = fmaxl(ec, fabsl((long double)LLt[0][0] - (long double)s.var_x) + fabsl((long double)LLt[1][0] - (long double)s.cov_xy) +
                           fabsl((long double)LLt[1][1] - (long double)s.var_y));
        gvec2 z = glm::inverse(L) * d;
        long double qz = (long double)glm::dot(z, z);
        long double p_chol = expl(-0.5L * qz) / (2.0L * 3.14159265358979323846L * (long double)a * (long double)c);
        ep = fmaxl(ep, fabsl(p_ours - p_chol) / p_chol / (1.0L + q));
        // D from a direction, with glm's normalize and dot
        gvec3 m = glm::normalize(gvec3(-slope.x, -slope.y, (pf_real)1));
        long double cz = (long double)glm::dot(m, gvec3(0, 0, 1));
        long double d_glm = p_glm / (cz * cz * cz * cz);
        ed = fmaxl(ed, fabsl((long double)pf_beckmann_d(from_glm(m), s) - d_glm) / d_glm / (1.0L + q));
    }
    pf_test_note("vs GLM (20000 random covariances): P22 by glm::inverse and by Cholesky %.3g eps x (1 + q), "
                 "D %.3g eps x (1 + q); glm cov*inv - I %.2g, L L^T - cov %.2g",
                 (double)(ep / PF_TEST_EPS), (double)(ed / PF_TEST_EPS), (double)einv, (double)ec);
    // glm's own float inverse and Cholesky carry their rounding, amplified by the condition
    // number (|r| up to 0.95, ratio of deviations up to 16): bounds are loose on purpose,
    // and a convention slip (transposed inverse, sign of c_xy) would give errors of order 1.
    PF_CHECK(ep <= 4096.0L * PF_TEST_EPS, "P22 vs glm: %.3g eps", (double)(ep / PF_TEST_EPS));
    PF_CHECK(ed <= 4096.0L * PF_TEST_EPS, "D vs glm: %.3g eps", (double)(ed / PF_TEST_EPS));
    PF_CHECK(einv <= 4096.0L * PF_TEST_EPS, "glm inverse sanity: %.3g", (double)einv);
    PF_CHECK(ec <= 64.0L * PF_TEST_EPS, "Cholesky sanity: %.3g", (double)ec);
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_vectors_against_glm);
    PF_TEST_RUN(test_covariance_against_glm);
    return PF_TEST_END();
}

/* smoke.c - smoke test of one include of prefilter: known values from every corner of the
   library, each compared with a closed form evaluated in double by the C library (an
   independent reference, not our own code). `make portability` builds it against the
   amalgamated prefilter.h (check amalgam-*) as C99, C11, C++11/17/20, with tcc and with nvcc
   (host), float and double; tests/consumer/ builds it through CMake and pkg-config.

   The bounds are loose on purpose (1e-4 relative in float): the module tests own accuracy;
   this file proves the one-file build is complete and computes the right thing. Prints one
   line, "smoke: N checks, M failed", and exits non-zero on a failure. */
#ifndef PF_SMOKE_HEADER
#  include "prefilter.h"
#else
#  include PF_SMOKE_HEADER
#endif
#include <math.h>
#include <stdio.h>

static int smoke_checks = 0, smoke_failed = 0;

static void smoke_expect(const char *what, pf_real got, double want, double rel)
{
    double g = (double)got, err = fabs(g - want) / (fabs(want) > 1e-300 ? fabs(want) : 1.0);
    smoke_checks++;
    if (!(err <= rel)) {
        smoke_failed++;
        printf("smoke: FAIL %s: got %.9g, want %.9g (rel err %.3g > %.3g)\n", what, g, want, err, rel);
    }
}

int main(void)
{
#ifdef PF_DOUBLE
    const double tol = 1e-12;
#else
    const double tol = 1e-4;
#endif
    static const double xs[4] = { -1.0, 0.3, 1.0, 2.5 };
    int i;
    for (i = 0; i < 4; i++) {
        smoke_expect("pf_erfc", pf_erfc((pf_real)xs[i]), erfc(xs[i]), tol);
        smoke_expect("pf_erf", pf_erf((pf_real)xs[i]), erf(xs[i]), tol);
    }
    /* Smith Lambda for Beckmann slopes: (exp(-nu^2) / (nu sqrt(pi)) - erfc(nu)) / 2 */
    for (i = 1; i < 4; i++) {
        double nu = xs[i] + 0.5;
        double lam = (exp(-nu * nu) / (nu * sqrt(3.14159265358979323846)) - erfc(nu)) / 2.0;
        smoke_expect("pf_lambda_beckmann", pf_lambda_beckmann((pf_real)nu), lam, tol);
        smoke_expect("pf_g1_beckmann", pf_g1_beckmann((pf_real)nu), 1.0 / (1.0 + lam), tol);
    }
    /* GGX G1 from cos theta: 2 / (1 + sqrt(1 + alpha^2 tan^2 theta)) */
    {
        double c = 0.6, a = 0.35, t2 = (1.0 - c * c) / (c * c);
        smoke_expect("pf_g1_ggx_iso", pf_g1_ggx_iso((pf_real)c, (pf_real)a), 2.0 / (1.0 + sqrt(1.0 + a * a * t2)), tol);
    }
    /* Chebyshev upper bound (VSM): var / (var + (x - m1)^2) */
    smoke_expect("pf_shadow_chebyshev_upper", pf_shadow_chebyshev_upper(PF_R(0.5), PF_R(0.26), PF_R(0.7), PF_R(0.0)),
                 0.01 / (0.01 + 0.04), tol);
    /* Toksvig: (1 - |mu|) / |mu| */
    smoke_expect("pf_toksvig_variance", pf_toksvig_variance(PF_R(0.8)), 0.25, tol);
    /* vectors */
    smoke_expect("pf_vec3_length", pf_vec3_length(pf_vec3_make(PF_R(2.0), PF_R(3.0), PF_R(6.0))), 7.0, tol);
    printf("smoke: %d checks, %d failed\n", smoke_checks, smoke_failed);
    return smoke_failed != 0;
}

/* add_subdirectory consumer: the one-file amalgamation, prefilter.h, as C. */
#include "prefilter.h"
#include <math.h>
#include <stdio.h>

int main(void)
{
    /* Smith Lambda for Beckmann slopes: (exp(-nu^2) / (nu sqrt(pi)) - erfc(nu)) / 2 at nu = 1 */
    double want = (exp(-1.0) / sqrt(3.14159265358979323846) - erfc(1.0)) / 2.0;
    double got = (double)pf_lambda_beckmann(PF_R(1.0));
    int ok = fabs(got - want) <= 1e-5 * want;
    printf("consumer add_subdirectory: Lambda(1) %.7f (want %.7f): %s\n", got, want, ok ? "ok" : "FAIL");
    return ok ? 0 : 1;
}

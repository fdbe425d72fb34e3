/* pkg-config consumer: a module header found through `pkg-config --cflags prefilter`. */
#include "pf_shadow.h"
#include <math.h>
#include <stdio.h>

int main(void)
{
    /* Chebyshev's one-sided bound (VSM): mean 0.5, variance 0.01, receiver at 0.7:
       0.01 / (0.01 + 0.2^2) = 0.2 */
    double got = (double)pf_shadow_chebyshev_upper(PF_R(0.5), PF_R(0.26), PF_R(0.7), PF_R(0.0));
    int ok = fabs(got - 0.2) <= 1e-5;
    printf("consumer pkgconfig: VSM bound %.7f (want 0.2): %s\n", got, ok ? "ok" : "FAIL");
    return ok ? 0 : 1;
}

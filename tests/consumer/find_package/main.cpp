// find_package consumer: single module headers from the installed include directory, as C++.
#include <pf_smith.h>
#include <pf_toksvig.h>
#include <cmath>
#include <cstdio>

int main()
{
    // GGX G1 from cos theta against its closed form 2 / (1 + sqrt(1 + alpha^2 tan^2 theta))
    const double c = 0.6, a = 0.35, t2 = (1.0 - c * c) / (c * c);
    const double want = 2.0 / (1.0 + std::sqrt(1.0 + a * a * t2));
    const double got = static_cast<double>(pf_g1_ggx_iso(static_cast<pf_real>(c), static_cast<pf_real>(a)));
    const double var = static_cast<double>(pf_toksvig_variance(PF_R(0.8)));  // (1 - 0.8) / 0.8
    const bool ok = std::fabs(got - want) <= 1e-5 * want && std::fabs(var - 0.25) <= 1e-6;
    std::printf("consumer find_package: G1 %.7f (want %.7f), Toksvig variance %.7f: %s\n", got, want, var,
                ok ? "ok" : "FAIL");
    return ok ? 0 : 1;
}

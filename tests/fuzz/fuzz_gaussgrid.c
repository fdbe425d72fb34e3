/* tests/fuzz/fuzz_gaussgrid.c - libFuzzer harness for include/pf_gaussgrid.h: every public
   evaluator (tests/fuzz/pf_calls.h), plus the pointer-taking CPU-only pf_gg_hermite_generate:
   for n in [1, PF_GG_GENERATE_MAX] the nodes must be finite, ascending and symmetric and the
   weights finite, >= 0 and sum to 1; outside that range (and for NULL arrays) it must return 0
   and leave the arrays untouched. Build and run: sh tests/fuzz/run.sh. */
#include "pf_fuzz.h"

static void pff_hermite(const uint8_t *data, size_t size)
{
    pf_real nodes[PF_GG_GENERATE_MAX + 2], weights[PF_GG_GENERATE_MAX + 2], s = PF_R(0.0);
    int n, r, i;
    if (size < 1) return;
    n = (int)(signed char)data[0];
    for (i = 0; i < PF_GG_GENERATE_MAX + 2; ++i) nodes[i] = weights[i] = PF_R(-7.0);
    r = pf_gg_hermite_generate(n, nodes, weights);
    if (n < 1 || n > PF_GG_GENERATE_MAX) {
        if (r != 0 || nodes[0] != PF_R(-7.0) || weights[0] != PF_R(-7.0)) {
            fprintf(stderr, "pf_fuzz: pf_gg_hermite_generate(%d): returned %d or wrote outside the range\n", n, r);
            __builtin_trap();
        }
        return;
    }
    if (r != n || pf_gg_hermite_generate(n, 0, weights) != 0) {
        fprintf(stderr, "pf_fuzz: pf_gg_hermite_generate(%d) returned %d\n", n, r);
        __builtin_trap();
    }
    for (i = 0; i < n; ++i) {
        int ok = pfc_isfinite(nodes[i]) && pfc_isfinite(weights[i]) && weights[i] >= PF_R(0.0) &&
                 nodes[i] == -nodes[n - 1 - i] && (i == 0 || nodes[i] > nodes[i - 1]);
        if (!ok) {
            fprintf(stderr, "pf_fuzz: pf_gg_hermite_generate(%d): node %d = %a, weight %a\n", n, i,
                    (double)nodes[i], (double)weights[i]);
            __builtin_trap();
        }
        s += weights[i];
    }
    if (!(PF_FABS(s - PF_R(1.0)) <= PF_R(64.0) * PF_REAL_EPSILON) || nodes[n] != PF_R(-7.0)) {
        fprintf(stderr, "pf_fuzz: pf_gg_hermite_generate(%d): weights sum to %.17g\n", n, (double)s);
        __builtin_trap();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pff_run_module("gaussgrid", data, size);
    pff_hermite(data, size);
    return 0;
}

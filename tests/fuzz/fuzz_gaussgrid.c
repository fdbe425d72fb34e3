/* tests/fuzz/fuzz_gaussgrid.c - libFuzzer harness for include/pf_gaussgrid.h: every public
   evaluator (tests/fuzz/pf_calls.h), plus the pointer-taking CPU-only pf_gg_hermite_generate
   (tests/fuzz/pf_buffers.h): n from the whole int range, exact-size guarded arrays; for n in
   [1, PF_GG_GENERATE_MAX] it must return n, the nodes be finite, ascending and symmetric and
   the weights finite, >= 0 and sum to 1; outside that range (and for NULL arrays) it must
   return 0 and write nothing. Build and run: sh tests/fuzz/run.sh. */
#define _DEFAULT_SOURCE 1
#include "pf_fuzz.h"
#include "pf_buffers.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pff_run_module("gaussgrid", data, size);
    pfb_run_module("gaussgrid", data, size);
    return 0;
}

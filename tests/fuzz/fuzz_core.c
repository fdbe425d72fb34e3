/* tests/fuzz/fuzz_core.c - libFuzzer harness for include/pf_core.h: every public evaluator of the
   module (tests/fuzz/pf_calls.h), mapped into its documented domain and checked, then called on
   raw bytes under ASan/UBSan; plus the CPU-only size helpers pf_size_mul, pf_size_mul3 and
   pf_size_side_ok on the whole long long range against the harness's own checked arithmetic
   (tests/fuzz/pf_buffers.h). Build and run: sh tests/fuzz/run.sh (FUZZ_SECONDS per harness). */
#define _DEFAULT_SOURCE 1
#include "pf_fuzz.h"
#include "pf_buffers.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pff_run_module("core", data, size);
    pfb_run_module("core", data, size);
    return 0;
}

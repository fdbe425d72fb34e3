/* tests/fuzz/fuzz_masks.c - libFuzzer harness for include/pf_masks.h: every public evaluator
   (tests/fuzz/pf_calls.h: bit operations against a per-bit loop, indices inside the table,
   parameters finite and in range), plus the pointer-taking CPU-only functions
   (tests/fuzz/pf_buffers.h): pf_masks_samples, pf_masks_table_words, pf_masks_table_build and
   pf_masks_table_fetch with sizes from the whole int range, exact-size guarded buffers, NaN and
   out-of-footprint samples; return codes, nothing written on error, every accepted table word
   written with its unused bits 0, empty and full end rows, masks growing with v. Build and run:
   sh tests/fuzz/run.sh (FUZZ_SECONDS per harness). */
#define _DEFAULT_SOURCE 1
#include "pf_fuzz.h"
#include "pf_buffers.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pff_run_module("masks", data, size);
    pfb_run_module("masks", data, size);
    return 0;
}

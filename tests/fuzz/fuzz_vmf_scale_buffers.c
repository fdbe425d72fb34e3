/* tests/fuzz/fuzz_vmf_scale_buffers.c - libFuzzer harness for the pointer-taking CPU-only functions
   of include/pf_vmf_scale.h (the effective BRDF, the per-patch sample and table sizes, the
   level calls, the table lookup) against the size and error rules of include/pf_core.h:
   sizes from the whole int range, exact-size guarded buffers, return codes, nothing written
   on error, outputs written, finite and in range (see tests/fuzz/pf_buffers.h, pfb_d_vmf_scale
   and pfb_d_vmf_level). Build and run: sh tests/fuzz/run.sh. */
#define _DEFAULT_SOURCE 1
#include "pf_buffers.h"

PFB_HARNESS("vmf_scale")

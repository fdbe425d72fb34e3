/* tests/fuzz/fuzz_shadow_buffers.c - libFuzzer harness for the pointer-taking CPU-only functions of
   include/pf_shadow.h (the fp16 / fp32 / 64-bit MSM encoders of caller buffers and the value
   helpers) against the size and error rules of include/pf_core.h: sizes from the whole int
   range, guarded buffers, return codes, nothing written on error, every output word written,
   finite and in range (see tests/fuzz/pf_buffers.h). Build and run: sh tests/fuzz/run.sh
   (FUZZ_SECONDS per harness). */
#define _DEFAULT_SOURCE 1
#include "pf_buffers.h"

PFB_HARNESS("shadow")

/* tests/fuzz/fuzz_specaa_buffers.c - libFuzzer harness for the pointer-taking CPU-only functions
   of include/pf_specaa.h (the roughness baker and its scratch size) against the size and error
   rules of include/pf_core.h: sizes from the whole int range, exact-size guarded buffers, return
   codes, nothing written on error, outputs written, finite and in range (see
   tests/fuzz/pf_buffers.h, pfb_d_specaa). Build and run: sh tests/fuzz/run.sh. */
#define _DEFAULT_SOURCE 1
#include "pf_buffers.h"

PFB_HARNESS("specaa")

/* tests/fuzz/fuzz_vmf_fit_buffers.c - libFuzzer harness for the pointer-taking CPU-only functions of
   include/pf_vmf_fit.h (the EM fit, the lobe pyramid, its layout, the texel reader) against the
   size and error rules of include/pf_core.h: sizes from the whole int range, exact-size
   guarded buffers, return codes, nothing written on error, outputs written, finite and in
   range (see tests/fuzz/pf_buffers.h, pfb_d_vmf). Build and run: sh tests/fuzz/run.sh. */
#define _DEFAULT_SOURCE 1
#include "pf_buffers.h"

PFB_HARNESS("vmf_fit")

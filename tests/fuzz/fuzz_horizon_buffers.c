/* tests/fuzz/fuzz_horizon_buffers.c - libFuzzer harness for the pointer-taking CPU-only functions of
   include/pf_horizon.h (pf_horizon_map, pf_horizon_pyramid, pf_horizon_channels) against the size
   and error rules of include/pf_core.h: sizes from the whole int range, exact-size guarded
   buffers, non-finite heights, return codes, nothing written on error, outputs written, finite
   and in range (see tests/fuzz/pf_buffers.h). Build and run: sh tests/fuzz/run.sh. */
#define _DEFAULT_SOURCE 1
#include "pf_buffers.h"

PFB_HARNESS("horizon")

/* tests/fuzz/fuzz_map_buffers.c - libFuzzer harness for the pointer-taking CPU-only functions of
   include/pf_map.h (pyramid layout, builders, samplers, height stencils, the height-field march)
   against the size and error rules of include/pf_core.h:
   sizes from the whole int range, exact-size guarded buffers (huge accepted maps as untouched
   MAP_NORESERVE mappings; builders and filters run only on buffers of at most 2^16 reals),
   return codes, nothing written on error, outputs written, finite and in range (see
   tests/fuzz/pf_buffers.h). Build and run: sh tests/fuzz/run.sh (FUZZ_SECONDS per harness). */
#define _DEFAULT_SOURCE 1
#include "pf_buffers.h"

PFB_HARNESS("map")

/* tests/fuzz/fuzz_masks_buffers.c - libFuzzer harness for the pointer-taking CPU-only functions of
   include/pf_masks.h (pf_masks_samples, pf_masks_table_words, pf_masks_table_build,
   pf_masks_table_fetch) against the size and error rules of include/pf_core.h: sizes from the
   whole int range, exact-size guarded buffers (tables as int words ending at a guard page),
   return codes, nothing written on error, every word of an accepted table written (see
   tests/fuzz/pf_buffers.h). Build and run: sh tests/fuzz/run.sh. */
#define _DEFAULT_SOURCE 1
#include "pf_buffers.h"

PFB_HARNESS("masks")

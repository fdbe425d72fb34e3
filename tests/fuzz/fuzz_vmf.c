/* tests/fuzz/fuzz_vmf.c - libFuzzer harness for include/pf_vmf.h: every public evaluator of the
   module (tests/fuzz/pf_calls.h), mapped into its documented domain and checked, then called on
   raw bytes under ASan/UBSan. The CPU-only fit and pyramid are driven by pf_buffers.h's
   pfb_table (guarded buffers, return codes). Build and run: sh tests/fuzz/run.sh
   (FUZZ_SECONDS per harness). */
#include "pf_fuzz.h"

PFF_HARNESS("vmf")

/* tests/fuzz/fuzz_specaa.c - libFuzzer harness for include/pf_specaa.h: every public evaluator of the
   module (tests/fuzz/pf_calls.h), mapped into its documented domain and checked, then called on
   raw bytes under ASan/UBSan. Build and run: sh tests/fuzz/run.sh (FUZZ_SECONDS per harness). */
#include "pf_fuzz.h"

PFF_HARNESS("specaa")

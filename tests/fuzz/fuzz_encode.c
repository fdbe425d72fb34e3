/* tests/fuzz/fuzz_encode.c - libFuzzer harness for the decoders of include/pf_encode.h (tests/fuzz/pf_calls.h):
   every public evaluator mapped into its documented domain and checked, then called on raw
   bytes under ASan/UBSan. Build and run: sh tests/fuzz/run.sh (FUZZ_SECONDS per harness). */
#include "pf_fuzz.h"

PFF_HARNESS("encode")

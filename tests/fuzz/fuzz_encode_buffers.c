/* tests/fuzz/fuzz_encode_buffers.c - libFuzzer harness for the encoders of include/pf_encode.h
   (tests/fuzz/pf_buffers.h, pfb_d_encode): texel and channel counts from the whole int range,
   exact-size guarded buffers, NaN and inf texels, every format and unknown ones; return codes,
   nothing written on error, decoded values within half a step of their texels.
   Build and run: sh tests/fuzz/run.sh (FUZZ_SECONDS per harness). */
#define _DEFAULT_SOURCE 1
#include "pf_buffers.h"

PFB_HARNESS("encode")

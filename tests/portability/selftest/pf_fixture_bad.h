/* pf_fixture_bad.h - generator self-test: a pointer parameter outside #ifndef PF_GLSL
   must make gen.awk fail and name the function. */
#ifndef PF_FIXTURE_BAD_H
#define PF_FIXTURE_BAD_H
#include "pf_core.h"
PF_DEF pf_real pf_fx_bad(const pf_real *v) { return v[0]; }
#endif

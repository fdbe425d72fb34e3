/* pf_fixture.h - generator self-test fixture for tests/portability/gen.awk (not a module).
   The doc block mentions a declaration that must be ignored:
   PF_DEF pf_real pf_fx_in_comment(pf_real x)
*/
#ifndef PF_FIXTURE_H
#define PF_FIXTURE_H

#ifndef PF_GLSL
#  include "pf_core.h"
#endif

PF_STRUCT_BEGIN(pf_fx_pair)       /* no maker: built member by member */
    pf_vec3 dir;
    pf_real a, b;
    int n;
PF_STRUCT_END(pf_fx_pair)

PF_DEF pf_real pfi_fx_private(pf_real x) { return x; }

/* a declaration split over three lines */
PF_DEF pf_real pf_fx_multiline(pf_real a,
                               pf_fx_pair p,
                               int n)
{
    return a + p.dir.z + p.a * p.b + PF_R(n + p.n) + pfi_fx_private(a);
}

PF_DEF pf_fx_pair pf_fx_pair_twice(pf_fx_pair p)
{
    p.a = p.a * PF_R(2.0);
    return p;
}

PF_DEF int pf_fx_count(pf_vec2 v) { return v.x < v.y ? 1 : 2; }

#ifndef PF_GLSL
/* CPU-only buffer walker: skipped, not an error */
PF_DEF pf_real pf_fx_sum(const pf_real *v, int n)
{
    pf_real s = PF_R(0.0);
    int i;
    for (i = 0; i < n; i++) s += v[i];
    return s;
}
#else
PF_DEF pf_real pf_fx_glsl_only(pf_real x) { return x; }
#endif

#endif /* PF_FIXTURE_H */

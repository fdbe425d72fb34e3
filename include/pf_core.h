/* pf_core.h - prefilter core: scalar type, linkage, math macros, erfc/erf, small vectors.

   prefilter is a header-only C99 library of non-linear pre-filtering formulas for surface
   shading (Smith masking, LEADR/LEAN slope statistics, shadow-map moments, ...). Every module
   header includes this one. Nothing here allocates, does I/O or touches global state.

   CONFIGURATION (define before the first include; every macro is optional)
     PF_DOUBLE        pf_real is double instead of float (the default is float).
     PF_DEF           linkage of every function. Default: static inline, plus
                      __host__ __device__ under __CUDACC__, empty under PF_GLSL.
     PF_SQRT(x) PF_EXP(x) PF_LOG(x) PF_FABS(x) PF_FLOOR(x) PF_POW(x,y)
     PF_SIN(x) PF_COS(x) PF_ATAN2(y,x)
                      the only libm entry points the library uses. Each defaults to the libm
                      function matching pf_real (sqrtf or sqrt, ...) and can be replaced on its
                      own, e.g. #define PF_EXP(x) my_fast_expf(x).
     PF_GLSL          compile as GLSL 4.50 (see docs/porting notes in README): structs through
                      PF_STRUCT_BEGIN/END, no typedef, casts through PF_R, built-in math.
     PF_NO_MATH_H     do not include <math.h> (when every PF_ math macro is user-provided).

   USAGE
     #include "pf_core.h"
     pf_real e = pf_erfc(PF_R(1.5));              -- our own erfc, no libm erfc needed
     pf_vec3 w = pf_vec3_normalize(pf_vec3_make(PF_R(0.3), PF_R(0.1), PF_R(1.0)));

   FUNCTIONS
     pf_erfc(x), pf_erf(x)        complementary error function and error function
     pf_min(a,b) pf_max(a,b) pf_clamp(x,lo,hi) pf_saturate(x) pf_sq(x)
     pf_vec2_make  pf_vec2_dot
     pf_vec3_make  pf_vec3_add  pf_vec3_sub  pf_vec3_scale  pf_vec3_dot  pf_vec3_cross
     pf_vec3_length  pf_vec3_normalize

   CONVENTIONS
     Public names pf_, private pf__, macros PF_. Evaluators take scalars and small structs by
     value and return by value: no pointers, no compound literals, no recursion, so the same
     source compiles as C99, C++11, CUDA and GLSL. Write real literals as PF_R(1.5) so that a
     float build never promotes to double (-Wdouble-promotion clean).

   LICENCE: MIT (see README.md). */
#ifndef PF_CORE_H
#define PF_CORE_H

/* ---------------------------------------------------------------- scalar type and literals */
#ifdef PF_GLSL
#  define pf_real float
#  define PF_R(x) float(x)
#  define PF_REAL_IS_FLOAT 1
#else
#  ifndef PF_NO_MATH_H
#    include <math.h>
#  endif
#  ifdef PF_DOUBLE
typedef double pf_real;
#  else
typedef float pf_real;
#    define PF_REAL_IS_FLOAT 1
#  endif
/* PF_R(x): a real literal or conversion. The cast of a decimal literal is folded at compile
   time, so the float build holds a float constant and never promotes to double. */
#  define PF_R(x) ((pf_real)(x))
#endif

/* Limits of pf_real (no <float.h> on GPUs). */
#ifdef PF_REAL_IS_FLOAT
#  define PF_REAL_EPSILON PF_R(1.1920928955078125e-7)  /* 2^-23 */
#  define PF_REAL_MIN     PF_R(1.1754943508222875e-38) /* smallest normal, 2^-126 */
#  define PF_REAL_MAX     PF_R(3.4028234663852886e38)
#else
#  define PF_REAL_EPSILON PF_R(2.220446049250313e-16)  /* 2^-52 */
#  define PF_REAL_MIN     PF_R(2.2250738585072014e-308)
#  define PF_REAL_MAX     PF_R(1.7976931348623157e308)
#endif

/* Constants, to more digits than double holds. */
#define PF_PI          PF_R(3.14159265358979323846264338327950288)
#define PF_INV_PI      PF_R(0.318309886183790671537767526745028724)
#define PF_SQRT_PI     PF_R(1.77245385090551602729816748334114518)
#define PF_INV_SQRT_PI PF_R(0.564189583547756286948079451560772586)
#define PF_SQRT2       PF_R(1.41421356237309504880168872420969808)
#define PF_INV_SQRT2   PF_R(0.707106781186547524400844362104849039)
#define PF_SQRT_2PI    PF_R(2.50662827463100050241576528481104525)
#define PF_LN2         PF_R(0.693147180559945309417232121458176568)

/* ---------------------------------------------------------------- linkage */
#ifndef PF_DEF
#  if defined(PF_GLSL)
#    define PF_DEF
#  elif defined(__CUDACC__)
#    define PF_DEF static inline __host__ __device__
#  else
#    define PF_DEF static inline
#  endif
#endif

/* Structs are declared through these so that GLSL (no typedef) reads the same source. */
#ifdef PF_GLSL
#  define PF_STRUCT_BEGIN(name) struct name {
#  define PF_STRUCT_END(name) };
#else
#  define PF_STRUCT_BEGIN(name) typedef struct name {
#  define PF_STRUCT_END(name) } name;
#endif

/* ---------------------------------------------------------------- math, one macro per function */
#if defined(PF_GLSL)
#  ifndef PF_SQRT
#    define PF_SQRT(x) sqrt(x)
#  endif
#  ifndef PF_EXP
#    define PF_EXP(x) exp(x)
#  endif
#  ifndef PF_LOG
#    define PF_LOG(x) log(x)
#  endif
#  ifndef PF_FABS
#    define PF_FABS(x) abs(x)
#  endif
#  ifndef PF_FLOOR
#    define PF_FLOOR(x) floor(x)
#  endif
#  ifndef PF_POW
#    define PF_POW(x, y) pow(x, y)
#  endif
#  ifndef PF_SIN
#    define PF_SIN(x) sin(x)
#  endif
#  ifndef PF_COS
#    define PF_COS(x) cos(x)
#  endif
#  ifndef PF_ATAN2
#    define PF_ATAN2(y, x) atan(y, x)
#  endif
#elif defined(PF_DOUBLE)
#  ifndef PF_SQRT
#    define PF_SQRT(x) sqrt(x)
#  endif
#  ifndef PF_EXP
#    define PF_EXP(x) exp(x)
#  endif
#  ifndef PF_LOG
#    define PF_LOG(x) log(x)
#  endif
#  ifndef PF_FABS
#    define PF_FABS(x) fabs(x)
#  endif
#  ifndef PF_FLOOR
#    define PF_FLOOR(x) floor(x)
#  endif
#  ifndef PF_POW
#    define PF_POW(x, y) pow(x, y)
#  endif
#  ifndef PF_SIN
#    define PF_SIN(x) sin(x)
#  endif
#  ifndef PF_COS
#    define PF_COS(x) cos(x)
#  endif
#  ifndef PF_ATAN2
#    define PF_ATAN2(y, x) atan2(y, x)
#  endif
#else
#  ifndef PF_SQRT
#    define PF_SQRT(x) sqrtf(x)
#  endif
#  ifndef PF_EXP
#    define PF_EXP(x) expf(x)
#  endif
#  ifndef PF_LOG
#    define PF_LOG(x) logf(x)
#  endif
#  ifndef PF_FABS
#    define PF_FABS(x) fabsf(x)
#  endif
#  ifndef PF_FLOOR
#    define PF_FLOOR(x) floorf(x)
#  endif
#  ifndef PF_POW
#    define PF_POW(x, y) powf(x, y)
#  endif
#  ifndef PF_SIN
#    define PF_SIN(x) sinf(x)
#  endif
#  ifndef PF_COS
#    define PF_COS(x) cosf(x)
#  endif
#  ifndef PF_ATAN2
#    define PF_ATAN2(y, x) atan2f(y, x)
#  endif
#endif

/* ---------------------------------------------------------------- scalar helpers */
/* Written with comparisons, not fminf/fmaxf: no libm call, same result in GLSL and CUDA.
   pf_max(x, 0) with x NaN returns 0 here (the comparison is false), a useful sanitizer. */
PF_DEF pf_real pf_min(pf_real a, pf_real b) { return a < b ? a : b; }
PF_DEF pf_real pf_max(pf_real a, pf_real b) { return a > b ? a : b; }
PF_DEF pf_real pf_clamp(pf_real x, pf_real lo, pf_real hi) { return x < lo ? lo : (x > hi ? hi : x); }
PF_DEF pf_real pf_saturate(pf_real x) { return pf_clamp(x, PF_R(0.0), PF_R(1.0)); }
PF_DEF pf_real pf_sq(pf_real x) { return x * x; }

/* ---------------------------------------------------------------- erfc / erf
   PF_ERFC_BEGIN (section owned by the erfc implementation; see docs/core.md) */

/* pf__exp_neg_sq(x) = exp(-x*x) for x >= 0, without the error of rounding x*x first.
   x*x carries a relative rounding error of 2^-24 (float); for x ~ 9, exp(-x*x) then loses
   ~81 * 2^-24 relative, i.e. ~40 ulp. Splitting x = hi + lo with hi a multiple of 2^-8
   (at most 12 significant bits for x < 16) makes hi*hi exact, and
   x*x = hi*hi + lo*(x + hi) with the small second term rounded harmlessly. */
PF_DEF pf_real pf__exp_neg_sq(pf_real x)
{
    pf_real hi = PF_FLOOR(x * PF_R(256.0)) * PF_R(0.00390625);
    pf_real lo = x - hi;
    return PF_EXP(-hi * hi) * PF_EXP(-lo * (x + hi));
}

/* Placeholder (replaced by the fitted kernel): the classical bound-style estimate
   erfc(x) ~ 2 exp(-x^2) / (sqrt(pi) (x + sqrt(x^2 + 4/pi))), about 1% accurate. */
PF_DEF pf_real pf__erfc_pos(pf_real x)
{
    return PF_R(2.0) * PF_INV_SQRT_PI * pf__exp_neg_sq(x) / (x + PF_SQRT(x * x + PF_R(4.0) * PF_INV_PI));
}

/* pf_erfc(x) = 1 - erf(x) = 2/sqrt(pi) * integral_x^inf exp(-t^2) dt, every real x.
   Range [0, 2]; underflows to 0 past x ~ 10.05 (float) / 27.3 (double). */
PF_DEF pf_real pf_erfc(pf_real x)
{
    if (x >= PF_R(0.0)) return pf__erfc_pos(x);
    return PF_R(2.0) - pf__erfc_pos(-x);
}

/* pf_erf(x) = 2/sqrt(pi) * integral_0^x exp(-t^2) dt, odd, every real x. */
PF_DEF pf_real pf_erf(pf_real x)
{
    pf_real ax = PF_FABS(x);
    pf_real e = PF_R(1.0) - pf__erfc_pos(ax);
    return x < PF_R(0.0) ? -e : e;
}

/* PF_ERFC_END */

/* ---------------------------------------------------------------- small vectors */
PF_STRUCT_BEGIN(pf_vec2)
    pf_real x;
    pf_real y;
PF_STRUCT_END(pf_vec2)

PF_STRUCT_BEGIN(pf_vec3)
    pf_real x;
    pf_real y;
    pf_real z;
PF_STRUCT_END(pf_vec3)

PF_DEF pf_vec2 pf_vec2_make(pf_real x, pf_real y)
{
    pf_vec2 v;
    v.x = x;
    v.y = y;
    return v;
}

PF_DEF pf_real pf_vec2_dot(pf_vec2 a, pf_vec2 b) { return a.x * b.x + a.y * b.y; }

PF_DEF pf_vec3 pf_vec3_make(pf_real x, pf_real y, pf_real z)
{
    pf_vec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

PF_DEF pf_vec3 pf_vec3_add(pf_vec3 a, pf_vec3 b) { return pf_vec3_make(a.x + b.x, a.y + b.y, a.z + b.z); }
PF_DEF pf_vec3 pf_vec3_sub(pf_vec3 a, pf_vec3 b) { return pf_vec3_make(a.x - b.x, a.y - b.y, a.z - b.z); }
PF_DEF pf_vec3 pf_vec3_scale(pf_vec3 a, pf_real s) { return pf_vec3_make(a.x * s, a.y * s, a.z * s); }
PF_DEF pf_real pf_vec3_dot(pf_vec3 a, pf_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

PF_DEF pf_vec3 pf_vec3_cross(pf_vec3 a, pf_vec3 b)
{
    return pf_vec3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

PF_DEF pf_real pf_vec3_length(pf_vec3 a) { return PF_SQRT(pf_vec3_dot(a, a)); }

/* Unit vector along a. The zero vector (and any vector whose squared length underflows)
   returns (0, 0, 1), the macronormal, rather than NaN. */
PF_DEF pf_vec3 pf_vec3_normalize(pf_vec3 a)
{
    pf_real m = pf_max(pf_max(PF_FABS(a.x), PF_FABS(a.y)), PF_FABS(a.z));
    pf_vec3 b;
    pf_real len;
    if (!(m > PF_R(0.0))) return pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
    /* Scale by the largest component first so that tiny or huge inputs neither
       underflow nor overflow when squared. */
    b = pf_vec3_scale(a, PF_R(1.0) / m);
    len = pf_vec3_length(b);
    return pf_vec3_scale(b, PF_R(1.0) / len);
}

#endif /* PF_CORE_H */

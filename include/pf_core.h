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
                      own, e.g. #define PF_EXP(x) my_fast_expf(x). Under PF_GLSL PF_ATAN2 is
                      pf_atan2 (below), not the built-in atan(y, x). A replacement PF_ATAN2
                      must return 0 at (0, 0): the callers rely on it.
     PF_GLSL          compile as GLSL 4.50 (see docs/porting.md): structs through
                      PF_STRUCT_BEGIN/END, no typedef, casts through PF_R, built-in math.
     PF_NO_MATH_H     do not include <math.h> (when every PF_ math macro is user-provided).
     PF_CPU_DEF       linkage of the CPU-only functions that take pointers (default static
                      inline, never __device__).
     PF_MAX_SIDE      largest side those functions accept (default 2^24).
     PF_MAX_REALS     largest buffer, in pf_reals, they read or write (default 2^40; narrower
                      on 32-bit hosts). See "CPU only: sizes and errors" at the end.

   USAGE
     #include "pf_core.h"
     pf_real e = pf_erfc(PF_R(1.5));              -- our own erfc, no libm erfc needed
     pf_vec3 w = pf_vec3_normalize(pf_vec3_make(PF_R(0.3), PF_R(0.1), PF_R(1.0)));

   FUNCTIONS
     pf_erfc(x), pf_erf(x)        complementary error function and error function (<= 2 ulp)
     pf_erfc_fast(x)              shader tier of erfc: A&S 7.1.26's cost, relative error 5.4e-6
     pf_exp_neg_sq(x)             exp(-x*x) without the rounding error of x*x (Gaussians)
     pf_atan2(y, x)               atan2 that is 0 at (0, 0) on every target; float: our own
                                  polynomial, 2 ulp (GLSL's PF_ATAN2)
     pf_min(a,b) pf_max(a,b) pf_clamp(x,lo,hi) pf_saturate(x) pf_sq(x)
     pf_vec2_make  pf_vec2_dot
     pf_vec3_make  pf_vec3_add  pf_vec3_sub  pf_vec3_scale  pf_vec3_dot  pf_vec3_cross
     pf_vec3_length  pf_vec3_normalize
     CPU only: PF_OK PF_ERR_ARG PF_ERR_SIZE, pf_size_mul pf_size_mul3 pf_size_side_ok

   CONVENTIONS
     Public names pf_, private pfi_ (not pf__: GLSL and C++ reserve every identifier that
     contains a double underscore, and glslang warns on them), macros PF_. Evaluators take
     scalars and small structs by
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
#if defined(PF_SIN) || defined(PF_COS)
#  define PFI_USER_TRIG 1 /* the user mapped sin/cos: PF_SINPI/PF_COSPI below go through them */
#endif
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
/* not GLSL's atan(y, x): undefined at (0, 0) (lavapipe returns +-3 pi/4 there) and allowed
   4096 ulp (Vulkan); pf_atan2 below is the library's own, 0 at (0, 0) and within 2 ulp */
#  ifndef PF_ATAN2
#    define PF_ATAN2(y, x) pf_atan2(y, x)
#  endif
#else
/* PFI_LIBM(sqrt) is sqrt in double builds and sqrtf in float builds. */
#  ifdef PF_DOUBLE
#    define PFI_LIBM(name) name
#  else
#    define PFI_LIBM(name) name##f
#  endif
#  ifndef PF_SQRT
#    define PF_SQRT(x) PFI_LIBM(sqrt)(x)
#  endif
#  ifndef PF_EXP
#    define PF_EXP(x) PFI_LIBM(exp)(x)
#  endif
#  ifndef PF_LOG
#    define PF_LOG(x) PFI_LIBM(log)(x)
#  endif
#  ifndef PF_FABS
#    define PF_FABS(x) PFI_LIBM(fabs)(x)
#  endif
#  ifndef PF_FLOOR
#    define PF_FLOOR(x) PFI_LIBM(floor)(x)
#  endif
#  ifndef PF_POW
#    define PF_POW(x, y) PFI_LIBM(pow)(x, y)
#  endif
#  ifndef PF_SIN
#    define PF_SIN(x) PFI_LIBM(sin)(x)
#  endif
#  ifndef PF_COS
#    define PF_COS(x) PFI_LIBM(cos)(x)
#  endif
#  ifndef PF_ATAN2
#    define PF_ATAN2(y, x) PFI_LIBM(atan2)(y, x)
#  endif
#endif

/* sin(pi x) and cos(pi x), for arguments the caller has already bounded (pf_csm_sum_begin).
   CUDA's sinpif/cospif reduce the argument exactly; its sinf/cosf carry a Payne-Hanek path for
   huge arguments written in FP64, which the float device build must not contain (make
   portability, nvcc-float). Elsewhere, and when PF_SIN/PF_COS are user-mapped, sin(PF_PI x). */
#if defined(__CUDACC__) && !defined(PF_GLSL) && !defined(PFI_USER_TRIG)
#  define PF_SINPI(x) PFI_LIBM(sinpi)(x)
#  define PF_COSPI(x) PFI_LIBM(cospi)(x)
#else
#  define PF_SINPI(x) PF_SIN(PF_PI * (x))
#  define PF_COSPI(x) PF_COS(PF_PI * (x))
#endif

/* ---------------------------------------------------------------- scalar helpers */
/* C and C++: written with comparisons, not fminf/fmaxf (no libm call; x86 compiles them to
   one minss/maxss). pf_max(x, 0) with x NaN returns 0 (the comparison is false), a useful
   sanitizer: the library puts the value that may be NaN first. pf_clamp(NaN, lo, hi) is NaN.
   GLSL and CUDA: the native min/max/clamp, one instruction each where the comparison form
   compiled to a compare and a select. CUDA's fminf/fmaxf return the non-NaN
   operand, so every pf_max(x, c) above stays a sanitizer there, and pf_clamp(NaN, lo, hi) is
   lo. GLSL leaves the operand returned for a NaN to the implementation (GLSL.std.450 FMin:
   one of the two), as it leaves NaN comparisons themselves; the hardware of the main vendors
   returns the non-NaN operand. Finite inputs give the same result everywhere; pf_clamp needs
   lo <= hi (GLSL's clamp is undefined otherwise), which every caller in the library meets.
   One definition each (the bodies differ through PFI_MIN/PFI_MAX/PFI_CLAMP), so that the
   portability generator and the fuzz coverage see every function once. */
#if defined(PF_GLSL)
#  define PFI_MIN(a, b) min(a, b)
#  define PFI_MAX(a, b) max(a, b)
#  define PFI_CLAMP(x, lo, hi) clamp(x, lo, hi)
#elif defined(__CUDACC__)
#  define PFI_MIN(a, b) PFI_LIBM(fmin)(a, b)
#  define PFI_MAX(a, b) PFI_LIBM(fmax)(a, b)
#  define PFI_CLAMP(x, lo, hi) PFI_LIBM(fmin)(PFI_LIBM(fmax)(x, lo), hi)
#else
#  define PFI_MIN(a, b) ((a) < (b) ? (a) : (b))
#  define PFI_MAX(a, b) ((a) > (b) ? (a) : (b))
#  define PFI_CLAMP(x, lo, hi) ((x) < (lo) ? (lo) : ((x) > (hi) ? (hi) : (x)))
#endif
PF_DEF pf_real pf_min(pf_real a, pf_real b) { return PFI_MIN(a, b); }
PF_DEF pf_real pf_max(pf_real a, pf_real b) { return PFI_MAX(a, b); }
PF_DEF pf_real pf_clamp(pf_real x, pf_real lo, pf_real hi) { return PFI_CLAMP(x, lo, hi); }
PF_DEF pf_real pf_saturate(pf_real x) { return pf_clamp(x, PF_R(0.0), PF_R(1.0)); }
/* clamp(x, lo, hi) that also sanitizes: a NaN x gives lo in C and CUDA (max first: pf_max's
   comparison is false for NaN), one native clamp in GLSL. lo <= hi. */
PF_DEF pf_real pf_clamp_nan_lo(pf_real x, pf_real lo, pf_real hi)
{
#ifdef PF_GLSL
    return clamp(x, lo, hi);
#else
    return pf_min(pf_max(x, lo), hi);
#endif
}
PF_DEF pf_real pf_sq(pf_real x) { return x * x; }

/* atan2(y, x) in [-pi, pi], with 0 at (0, 0) for every sign of zero (C's atan2 gives +-pi for
   x = -0; GLSL leaves atan(0, 0) undefined and lavapipe returns +-3 pi/4, outside the
   [-pi/2, pi/2] of pf_horizon_elevation). A GPU that flushes subnormals reads a
   subnormal pair as (0, 0) and returns 0 too. NaN in, NaN out; infinities as in C.
   Float builds and GLSL: t = min/max of |x|, |y| in [0, 1], reduced as in Cephes' atanf to
   u = t (t <= tan(pi/8)) or u = (t - 1)/(t + 1) from (min - max)/(min + max) (one division
   either way), atan(u) = u + u z P(z), z = u^2, |u| <= tan(pi/8), Cephes' degree-3 P; then
   pi/4 + ..., pi/2 - ... and pi - ... with the constants split in two floats. Error bound 2.5
   ulp of the result; measured against long double atan2 (tests/test_core.c, 4e5 pairs over
   60 decades of y/x): 2.1 ulp; with FMA contraction and x / y as x (1 / y), as a GPU compiles
   it, 1.9 on 2e7 pairs in [-1, 1]^2 (glibc's atan2f: 1.5 by the same count; GLSL's atan may be
   4096 ulp). |max| is scaled by 2^-100 or 2^100 beyond
   2^100 or below 2^-100, so that the division stays where GLSL bounds it (2^-126 .. 2^126).
   Double builds: libm's atan2 (PF_ATAN2) with the (0, 0) case decided first. */
PF_DEF pf_real pf_atan2(pf_real y, pf_real x)
{
#ifdef PF_REAL_IS_FLOAT
    pf_real ax = PF_FABS(x), ay = PF_FABS(y), mx = pf_max(ax, ay), mn = pf_min(ax, ay), u, z, r;
    int big;
    if (!(y == y) || !(x == x)) return x + y;
    if (!(mx > PF_R(0.0))) return PF_R(0.0);
    if (mx > PF_REAL_MAX) {                               /* an infinity: t is 1 or 0 */
        mn = mn > PF_REAL_MAX ? PF_R(1.0) : PF_R(0.0);
        mx = PF_R(1.0);
    } else if (mx > PF_R(1.2676506002282294e30)) {        /* 2^100 */
        mx *= PF_R(7.8886090522101181e-31);
        mn *= PF_R(7.8886090522101181e-31);
    } else if (mx < PF_R(7.8886090522101181e-31)) {
        mx *= PF_R(1.2676506002282294e30);
        mn *= PF_R(1.2676506002282294e30);
    }
    big = mn > PF_R(0.41421356237309505) * mx ? 1 : 0;    /* t > tan(pi/8) */
    u = big != 0 ? (mn - mx) / (mn + mx) : mn / mx;
    z = u * u;
    r = (((PF_R(8.05374449538e-2) * z - PF_R(1.38776856032e-1)) * z + PF_R(1.99777106478e-1)) * z -
         PF_R(3.33329491539e-1)) * z * u + u;
    /* pi/4, pi/2, pi as float hi + lo */
    if (big != 0) r = (r - PF_R(2.1855694143368964e-08)) + PF_R(0.78539818525314331);
    if (ay > ax) r = PF_R(1.5707963705062866) - (r + PF_R(4.371138828673793e-08));
    if (x < PF_R(0.0)) r = PF_R(3.1415927410125732) - (r + PF_R(8.742277657347586e-08));
    return y < PF_R(0.0) ? -r : r;
#else
    if (x == PF_R(0.0) && y == PF_R(0.0)) return PF_R(0.0);
    return PF_ATAN2(y, x);
#endif
}

/* ---------------------------------------------------------------- erfc / erf
   PF_ERFC_BEGIN (section owned by the erfc implementation; see docs/core.md) */
/* How pf_erfc and pf_erf work (the measured errors, timings and how to refit: docs/core.md,
   bench/fit/fit_erfc.py).

   Small |x| (erfc: |x| < 0.5, erf: |x| < 1): erf(x) = x + x * Pm(x^2), Pm(s) =
   erf(sqrt s)/sqrt s - 1 a fitted polynomial (minimax in relative error). Adding x last
   keeps erf relatively accurate down to the smallest subnormal, and erfc = 1 - erf is
   formed as (1 - x) + ((rounding error of 1 - x) - x*Pm), so only the last addition rounds.

   Large x (x >= 0.5): erfc(x) = exp(-x^2) * N(x) / (x + A), A = 0.625, where
   N = exp(x^2) erfc(x) (x + A) is flat: 0.57 .. 0.70 on the whole half-line, since
   exp(x^2) erfc(x) ~ 1/(sqrt(pi) x). N is fitted as a polynomial in z = 1/(x + A) - 1/2:
   one piece of degree 12 for float on 0.5 <= x <= 10.5, three of degree 17-18 for double.
   Written as N = 0.625 + y with |y| < 0.1 N, the rounding errors of y (and of z) are
   scaled down by a factor 10.

   Error budget (float). The libm exp(-p) we call is correctly rounded: up to 1/2 ulp of its
   own value, which with the final rounding can already make 1.5 ulp of the result. So
   everything else is kept exact or tiny:
   - exp(-x^2) = exp(-p) * exp(-b), p = x*x rounded, b = x*x - p exactly (Dekker's product
     with Veltkamp's split, no FMA needed), |b| < 2^-24 x^2, exp(-b) = 1 - b.
   - 1/(x + A) = wh / (1 + s): dh = (x rounded to 10 bits) + A and wh = 1/dh rounded to 9
     bits make wh*dh exact, and s = (x - xs) wh - (1 - wh dh) < 2^-8 is a small correction.
   - exp's result is split into two 12-bit halves and multiplied by kh = 0.625 wh (12 bits):
     both products exact. All the small terms (b, s, y, the low half) meet in one sum, and
     the only rounding that matters is the last addition.
   The products are scaled by 2^64 so that no partial product goes subnormal (slow on x86,
   and Dekker's low parts would be lost); where the result itself is subnormal exp is called
   with the argument shifted by 40 (double: 300) and the result scaled by exp(-40) instead.
   All this needs IEEE arithmetic evaluated in the type itself (FLT_EVAL_METHOD 0, not x87)
   and no reassociation. FMA contraction by the compiler does no harm: every split is
   (a + 2^k a) - 2^k a, whose only product is exact, and every other product in an exact
   step is exact, so fusing it changes nothing (measured: <= 1.51 ulp with
   -ffp-contract=fast -mfma; the Veltkamp form c - (c - 4097 a) reached 2.09). In GLSL the
   exact steps are `precise` (PF_EXACT), which forbids both contraction and simplification
   there. Under -ffast-math the split may be simplified away: results stay finite and in
   range, with a few ulp more error. */


/* PF_EXACT marks the variables of the error-free steps below (splits, exact products and
   their residuals). In GLSL it is `precise` (SPIR-V NoContraction): a shader compiler may
   otherwise contract them into FMAs or simplify (a + s) - s to a, which is exact algebra and
   wrong arithmetic. C and CUDA need nothing: the splits are written so that contraction
   cannot change them (below), and C compilers do not reassociate without -ffast-math. */
#ifdef PF_GLSL
#  define PF_EXACT precise
#else
#  define PF_EXACT
#endif

/* The high half of a: a rounded to 12 (float) or 26 (double) significant bits, so that
   products of halves (and of a half and a <= 12-bit number) are exact; a - pfi_split_hi(a)
   is exact and has 12 (26) bits too. Written as (a + s) - s with s = 2^12 a (2^27 a): the
   only product is by a power of two, exact, so FMA contraction (fma(a, 2^12, a),
   fma(-a, 2^12, t)) computes the same values as separate operations. (Veltkamp's
   c - (c - a), c = 4097 a, is not: contracted to fma(4097, a, -a) it returns a itself, no
   split, and the error-free products downstream lose bits: pf_erfc reached 2.09 ulp with
   -ffp-contract=fast -mfma.) t = fl(a + s) = fl(4097 a) is Veltkamp's c, and
   t - s = a + (t - 4097 a) is exact, a multiple of 2^12 ulp(a). */
PF_DEF pf_real pfi_split_hi(pf_real a)
{
#ifdef PF_DOUBLE
    PF_EXACT pf_real s = PF_R(134217728.0) * a;
#else
    PF_EXACT pf_real s = PF_R(4096.0) * a;
#endif
    PF_EXACT pf_real t = a + s;
    PF_EXACT pf_real h = t - s;
    return h;
}

/* pf_exp_neg_sq(x) = exp(-x*x), any real x, without the error of rounding x*x first:
   x*x carries a relative rounding error of 2^-24, which for x ~ 9 would cost exp(-x*x)
   ~40 ulp. Here x*x = p + b with b exact (Dekker), exp(-x*x) = exp(-p) (1 - b).
   Error <= 1.5 ulp (correctly rounded exp, one product) while the result is normal. */
PF_DEF pf_real pf_exp_neg_sq(pf_real x)
{
    pf_real xc = pf_min(PF_FABS(x), PF_R(64.0)); /* exp(-4096) = 0; keeps the split finite */
    PF_EXACT pf_real xh = pfi_split_hi(xc);
    PF_EXACT pf_real xl = xc - xh;
    PF_EXACT pf_real p = xc * xc;
    PF_EXACT pf_real b = ((xh * xh - p) + PF_R(2.0) * xh * xl) + xl * xl;
    pf_real e = PF_EXP(-p);
    return e - e * b;
}

/* erf(x) - x = x * Pm(x^2) for |x| <= 1 (see above). Relative error of the fitted Pm:
   1.5e-9 (float, degree 6 in x^2), 3e-17 (double, degree 11). */
PF_DEF pf_real pfi_erf_minus_x(pf_real x)
{
    pf_real s = x * x;
#ifdef PF_DOUBLE
    return x * (PF_R(0.12837916709551259) + s * (PF_R(-0.37612638903183598)
        + s * (PF_R(0.11283791670946201) + s * (PF_R(-0.026866170643353754)
        + s * (PF_R(0.0052239776077292362) + s * (PF_R(-0.00085483259946241149)
        + s * (PF_R(0.00012055295276298677) + s * (PF_R(-1.4924741281429607e-05)
        + s * (PF_R(1.6447453776644119e-06) + s * (PF_R(-1.6208563484716761e-07)
        + s * (PF_R(1.3719936008615423e-08) + s * (PF_R(-7.7949721289669937e-10)))))))))))));
#else
    return x * (PF_R(0.128379166) + s * (PF_R(-0.376126289) + s * (PF_R(0.112836041)
        + s * (PF_R(-0.0268542729) + s * (PF_R(0.00518881064) + s * (PF_R(-0.000801193644)
        + s * PF_R(7.85307566e-05)))))));
#endif
}

/* erfc(x) for x >= 0.5 (any x >= 0 gives a finite value in [0, 1]; NaN gives NaN), as
   described above. Inputs are clamped where erfc has long underflowed to 0:
   erfc(10.06) < 2^-150 (float), erfc(27.23) < 2^-1075 (double). */
PF_DEF pf_real pfi_erfc_big(pf_real x)
{
#ifdef PF_DOUBLE
    pf_real xc = x > PF_R(27.25) ? PF_R(27.25) : x; /* not pf_min: CUDA's fmin drops a NaN */
    PF_EXACT pf_real c2 = PF_R(268435456.0) * xc; /* 2^28: x to 25 bits (as pfi_split_hi) */
#else
    pf_real xc = x > PF_R(10.125) ? PF_R(10.125) : x; /* not pf_min: CUDA's fminf drops a NaN */
    PF_EXACT pf_real c2 = PF_R(16384.0) * xc;     /* 2^14: x to 10 bits */
#endif
    PF_EXACT pf_real xh = pfi_split_hi(xc);
    PF_EXACT pf_real xl = xc - xh;
    /* x*x = p + b exactly */
    PF_EXACT pf_real p = xc * xc;
    PF_EXACT pf_real b = ((xh * xh - p) + PF_R(2.0) * xh * xl) + xl * xl;
    /* exp(-p): scaled by 2^64, or, where the result is subnormal (float x > 9.27, double
       x > 26.57), computed as exp(sh - p) and scaled by exp(-sh); sh - p is exact. */
#ifdef PF_DOUBLE
    pf_real sh = p > PF_R(706.0) ? PF_R(300.0) : PF_R(0.0);
    pf_real sc = sh > PF_R(0.0) ? PF_R(5.1482002224120135e-131)
                                : PF_R(5.42101086242752217003726400434970855712890625e-20);
#else
    pf_real sh = p > PF_R(86.0) ? PF_R(40.0) : PF_R(0.0);
    pf_real sc = sh > PF_R(0.0) ? PF_R(4.24835425529158899e-18)
                                : PF_R(5.42101086242752217003726400434970855712890625e-20);
#endif
    pf_real e1 = PF_EXP(sh - p) * (sh > PF_R(0.0) ? PF_R(1.0) : PF_R(18446744073709551616.0));
    /* 1/(x + A) = wh/(1 + s): dh = xs + A is exact with <= 14 (double 28) bits, wh = 1/dh
       rounded to 9 (23) bits, so wh*dh and r = 1 - wh*dh are exact, |s| < 2^-8. Then
       exp(-b)/(x + A) = wh (1 + g), g = (1 - b)/(1 + s) - 1. */
    PF_EXACT pf_real xs = (xc + c2) - c2;
    pf_real dh = xs + PF_R(0.625);
    pf_real cw = PF_R(1.0) / dh;
#ifdef PF_DOUBLE
    PF_EXACT pf_real wc = PF_R(1073741824.0) * cw; /* 2^30 */
#else
    PF_EXACT pf_real wc = PF_R(32768.0) * cw;      /* 2^15 */
#endif
    PF_EXACT pf_real wh = (cw + wc) - wc;
    PF_EXACT pf_real r = PF_R(1.0) - wh * dh;
    pf_real sv = (xc - xs) * wh - r;
    pf_real s3 = sv * (PF_R(1.0) - sv * (PF_R(1.0) - sv * (PF_R(1.0) - sv))); /* s/(1 + s) */
    pf_real g = -b - (PF_R(1.0) - b) * s3;
    /* The polynomial's variable, straight from a division (N's sensitivity to z < 0.1). */
    pf_real z = PF_R(1.0) / (xc + PF_R(0.625)) - PF_R(0.5);
    pf_real y, kh, kl, e1h;
    /* y = N - 0.625. Float: Estrin's scheme (a shorter dependency chain than Horner). */
#ifdef PF_DOUBLE
    if (xc < PF_R(2.0)) {
        pf_real v = z - PF_R(0.13492063492063491);
        y = PF_R(0.070583392670098721) + v * (PF_R(0.034600979921975528)
            + v * (PF_R(-0.21749418905476409) + v * (PF_R(0.14838415387698312)
            + v * (PF_R(-0.013198638677720859) + v * (PF_R(-0.088516532906285902)
            + v * (PF_R(0.12046449859994039) + v * (PF_R(-0.087761562822322225)
            + v * (PF_R(0.017667788980693697) + v * (PF_R(0.056118971708469606)
            + v * (PF_R(-0.10494976848218661) + v * (PF_R(0.11221076680061266)
            + v * (PF_R(-0.076027366990534778) + v * (PF_R(0.0085714804623133814)
            + v * (PF_R(0.069089560985507018) + v * (PF_R(-0.13874456335305019)
            + v * (PF_R(0.17418649467790184) + v * (PF_R(-0.10962661392323285)
            + v * (PF_R(-0.011670802584787691)))))))))))))))))));
    } else if (xc < PF_R(5.0)) {
        pf_real v = z - PF_R(-0.22063492063492063);
        y = PF_R(0.024708484947313258) + v * (PF_R(0.23566135024454987)
            + v * (PF_R(-0.30897108148490665) + v * (PF_R(-0.083579456244198283)
            + v * (PF_R(0.4149793586956671) + v * (PF_R(-0.24580447486082591)
            + v * (PF_R(-0.43782593616462862) + v * (PF_R(1.0301015927949593)
            + v * (PF_R(-0.54663260505362588) + v * (PF_R(-1.5159925405592292)
            + v * (PF_R(3.9525705227234305) + v * (PF_R(-3.2567700408558173)
            + v * (PF_R(-4.6466356864292653) + v * (PF_R(19.01876858625111)
            + v * (PF_R(-26.793822415392782) + v * (PF_R(-0.87096807297108936)
            + v * (PF_R(96.424863902900228) + v * (PF_R(-195.13056609665935))))))))))))))))));
    } else {
        pf_real v = z - PF_R(-0.39333333333333331);
        y = PF_R(-0.024383916706748637) + v * (PF_R(0.32585610385999442)
            + v * (PF_R(-0.18791875593224747) + v * (PF_R(-0.36735888147906864)
            + v * (PF_R(0.26378346233128441) + v * (PF_R(0.68880742912905268)
            + v * (PF_R(-0.81288071454382238) + v * (PF_R(-1.6292822545067369)
            + v * (PF_R(3.538392331565154) + v * (PF_R(3.5943308806807122)
            + v * (PF_R(-17.335095642018445) + v * (PF_R(0.14919300865372714)
            + v * (PF_R(83.887220838479479) + v * (PF_R(-99.509162132243631)
            + v * (PF_R(-340.74142685892292) + v * (PF_R(1057.603932584414)
            + v * (PF_R(695.17007040047611) + v * (PF_R(-6925.137475832259))))))))))))))))));
    }
#else
    {
        pf_real z2 = z * z, z4 = z2 * z2;
        y = (PF_R(0.061591778) + z * PF_R(0.101340227)) + z2 * (PF_R(-0.276140302) + z * PF_R(0.132450312))
            + z4 * ((PF_R(0.0868974626) + z * PF_R(-0.217842579)) + z2 * (PF_R(0.190104291) + z * PF_R(-0.0309375953)))
            + (z4 * z4) * ((PF_R(-0.181945249) + z * PF_R(0.413207024)) + z2 * (PF_R(-0.408096284) + z * PF_R(-0.300305098))
            + z4 * PF_R(0.725048244));
    }
#endif
    /* exp(-x^2) N/(x + A) = e1 * (kh + kl), kh = 0.625 wh exact with <= 12 (26) bits, so
       with e1 split in halves both products with kh are exact; one final rounding. */
    kh = PF_R(0.625) * wh;
    kl = wh * (y + g * (PF_R(0.625) + y));
    e1h = pfi_split_hi(e1);
    /* not PF_EXACT: a shader compiler that refactors this sum (kh (e1h + (e1 - e1h))) makes
       one rounding more, 1/2 ulp; `precise` here cost 16 SPIR-V ops */
    return (e1h * kh + ((e1 - e1h) * kh + e1 * kl)) * sc;
}

/* pf_erfc(x) = 1 - erf(x) = 2/sqrt(pi) * integral_x^inf exp(-t^2) dt, every real x.
   Range [0, 2]: erfc(-inf) = 2, erfc(+inf) = 0, NaN -> NaN. Underflows to 0 past
   x = 10.055 (float) / 27.23 (double); results are subnormal from x = 9.19 / 26.55.
   Measured error against long double erfcl (docs/core.md has the table and the method):
     float:  <= 1.83 ulp where the result is normal (every float of [0, 10.125] and the
             negative half checked), <= 1.24 x 2^-149 absolute where it is subnormal;
             with FMA contraction (-ffp-contract=fast -mfma): <= 1.84 ulp (every float of
             [2^-20, 10.125]);
     double: <= 1.75 ulp (dense random sampling and grids), <= 1.10 x 2^-1074 subnormal.
   For x < 0, erfc = 2 - erfc(-x), whose result is >= 1 and keeps the bound. */
PF_DEF pf_real pf_erfc(pf_real x)
{
    pf_real ax = PF_FABS(x);
    pf_real e;
    if (ax < PF_R(0.5)) {
        pf_real a = PF_R(1.0) - ax; /* rounded; its error is added back below */
        e = a + (((PF_R(1.0) - a) - ax) - pfi_erf_minus_x(ax));
    } else {
        e = pfi_erfc_big(ax);
    }
    return x < PF_R(0.0) ? PF_R(2.0) - e : e;
}

/* pf_erf(x) = 2/sqrt(pi) * integral_0^x exp(-t^2) dt, odd, every real x.
   Range [-1, 1]: erf(+-inf) = +-1, NaN -> NaN, erf(-0) = -0. Relatively accurate down to
   the smallest subnormal (erf(x) ~ 2x/sqrt(pi) is never formed as 1 - erfc).
   Measured error against erfl: <= 1.31 ulp (float, every float of [0, 10.125]),
   <= 1.30 ulp (double, sampled). */
PF_DEF pf_real pf_erf(pf_real x)
{
    pf_real ax = PF_FABS(x);
    pf_real e;
    if (ax < PF_R(1.0)) return x + pfi_erf_minus_x(x); /* odd as written; keeps -0 */
    e = PF_R(1.0) - pfi_erfc_big(ax);
    return x < PF_R(0.0) ? -e : e;
}

/* pf_erfc_fast(x): the shader tier of erfc, at the cost of Abramowitz & Stegun 7.1.26 (one
   reciprocal, a degree-6 polynomial, one exp; no branch) but with a RELATIVE error bound.
   A&S's t (a1 + .. + a5 t^4) exp(-x^2) has 1.5e-7 absolute error, which is all of erfc in the
   tail: its polynomial tends to a1/(p x) = 0.778/x where exp(x^2) erfc(x) ~ 0.564/x, 38% off
   (40% at x = 9). Here erfc(x) = exp(-x^2) z N(z), z = 1/(|x| + 2), where N = exp(x^2)
   erfc(x) (x + 2) is flat (0.56 .. 1.13) and fitted as a polynomial in z minimizing the
   relative error on 0 <= x <= 10.1 (float erfc underflows at 10.06; for larger x, exp(-x^2)
   is 0 and N stays finite): fit error 1.39e-6 (bench/fit/fit_erfc.py fast). x < 0:
   2 - erfc(-x). Measured max relative error (tests/test_core.c, against erfcl):
       float:  <= 2e-6 + 6e-8 x^2 where the result is normal (the x^2 term is the rounding
               of x*x inside exp, up to 2^-24 x^2): max 5.4e-6 (x = 8.2), 2.2e-6 for |x| <= 3;
       double: <= 1.4e-6 (the fit).
   Range [0, 2]; erfc(+inf) = 0, erfc(-inf) = 2, NaN -> NaN. Use pf_erfc where results are
   compared or accumulated (2 ulp); this tier where erfc feeds a shaded colour. */
PF_DEF pf_real pf_erfc_fast(pf_real x)
{
    pf_real ax = PF_FABS(x);
    /* z N(z) = sum c_k z^(k+1) written in w = a z, a = c_6^(1/7) = 1.41338098, where it is
       monic: w (d_0 + w (d_1 + .. + w (d_5 + w))), d_k = c_k / a^(k+1) (one multiply fewer) */
    pf_real w = PF_R(1.41338098) / (ax + PF_R(2.0));
    pf_real zn = w * (PF_R(0.399507642) + w * (PF_R(0.555906117) + w * (PF_R(0.796956718) + w * (PF_R(0.154429927) +
                 w * (PF_R(2.20325756) + w * (PF_R(-2.85892963) + w))))));
    pf_real e = PF_EXP(-ax * ax) * zn;
    pf_real reflected = PF_R(2.0) - e;
    return x < PF_R(0.0) ? reflected : e; /* a select of two values: no branch */
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

/* Power-of-two scales of pf_vec3_normalize: vectors whose largest component m lies outside
   [PFI_NORM_TINY, PFI_NORM_HUGE] are multiplied by PFI_NORM_UP or PFI_NORM_DOWN (exact: a
   power of two) first. Inside that range the squared length neither overflows (3 m^2 <
   PF_REAL_MAX) nor loses the largest component (m^2 >= 2^26 PF_REAL_MIN, so components whose
   squares go subnormal, or are flushed to 0 under -ffast-math, weigh < 2^-26 of it); every
   scaled m lands inside it: float 2^-149 .. 2^128 becomes 2^-49 .. 2^58; double
   2^-1074 .. 2^1024 becomes 2^-474 .. 2^424. */
#ifdef PF_DOUBLE
#  define PFI_NORM_TINY PF_R(3.2033329522929615e-145) /* 2^-480 */
#  define PFI_NORM_HUGE PF_R(3.273390607896142e150)   /* 2^500 */
#  define PFI_NORM_UP   PF_R(4.149515568880993e180)   /* 2^600 */
#  define PFI_NORM_DOWN PF_R(2.409919865102884e-181)  /* 2^-600 */
#else
#  define PFI_NORM_TINY PF_R(8.881784197001252e-16)   /* 2^-50 */
#  define PFI_NORM_HUGE PF_R(1.152921504606847e18)    /* 2^60 */
#  define PFI_NORM_UP   PF_R(1.2676506002282294e30)   /* 2^100 */
#  define PFI_NORM_DOWN PF_R(8.470329472543003e-22)   /* 2^-70 */
#endif

/* Unit vector along a, for every finite a: a / sqrt(a.a) (what GLSL normalize computes, and
   bit for bit the same for components in [2^-50, 2^60] (float) / [2^-480, 2^500] (double)).
   Outside that range a is first scaled by a power of two (PFI_NORM_*), so subnormal and huge
   components neither underflow nor overflow when squared; no reciprocal of the largest
   component is formed (1/m overflows for a subnormal m, and is subnormal - flushed to 0 under
   -ffast-math - for m > 2^126). The zero vector (and a NaN largest component) returns
   (0, 0, 1), the macronormal, rather than NaN. Cost: two comparisons instead of the division
   by m of the earlier scaled form (docs/core.md). */
PF_DEF pf_vec3 pf_vec3_normalize(pf_vec3 a)
{
    pf_real m = pf_max(pf_max(PF_FABS(a.x), PF_FABS(a.y)), PF_FABS(a.z));
    if (!(m > PF_R(0.0))) return pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
    if (m < PFI_NORM_TINY || m > PFI_NORM_HUGE) a = pf_vec3_scale(a, m < PFI_NORM_TINY ? PFI_NORM_UP : PFI_NORM_DOWN);
    return pf_vec3_scale(a, PF_R(1.0) / pf_vec3_length(a));
}

/* ================================================================ CPU only: sizes and errors
   The rules every function that takes a pointer follows (pf_moments.h pyramids and samplers,
   pf_height.h colour-map arrays and tables, pf_gaussgrid.h's Gauss-Hermite generator). They
   walk caller-owned buffers, so they are host code: linkage PF_CPU_DEF (static inline by
   default, never __device__), compiled out under PF_GLSL.

   Before it reads or writes anything, such a function checks every argument and returns
     PF_OK        (0)  on success;
     PF_ERR_ARG   (-1) for a NULL pointer it would use, an unknown enum value (border, kind), a
                       size below its minimum, or a range that is empty, reversed or not finite;
     PF_ERR_SIZE  (-2) for a size above its documented limit: a side above PF_MAX_SIDE, or a
                       buffer of more than PF_MAX_REALS pf_reals;
   and on an error it writes nothing. Functions that return a count (pf_mip_texel_count,
   pf_colormap_table_size, pf_gg_hermite_generate) return 0 for every size they cannot serve
   (each states exactly which; a texel count times a channel count can still exceed the limit); functions that return a value say which value they return. Sizes, offsets and
   indices are computed in long long through the helpers below, so no documented size can
   overflow; a caller's buffer must hold what the function's comment says, the one thing the
   library cannot check. */
#ifndef PF_GLSL

#ifndef PF_CPU_DEF
#  define PF_CPU_DEF static inline
#endif

#define PF_OK 0
#define PF_ERR_ARG (-1)
#define PF_ERR_SIZE (-2)

/* Largest side (texels along one axis, entries along one table axis) any CPU function takes:
   2^24, far above any GPU texture (16384 or 32768), and small enough that side arithmetic in
   int never overflows. */
#ifndef PF_MAX_SIDE
#  define PF_MAX_SIDE (1L << 24)
#endif

/* Largest buffer, in pf_reals, any CPU function reads or writes: 2^40 on 64-bit hosts (4 TiB of
   floats), PTRDIFF_MAX / 8 where pointers are narrower, so that every offset fits a pointer
   difference in float and double builds. PTRDIFF_MAX is read from the compiler's own macros
   where it has them (gcc, clang, nvcc: __PTRDIFF_MAX__; tcc: __SIZEOF_POINTER__), so that a
   bare-metal build needs no system header; <stdint.h> only for the others. */
#ifndef PF_MAX_REALS
#  if defined(__PTRDIFF_MAX__)
#    define PFI_PTRDIFF_MAX __PTRDIFF_MAX__
#  elif defined(__SIZEOF_POINTER__)
#    if __SIZEOF_POINTER__ >= 8
#      define PFI_PTRDIFF_MAX 9223372036854775807LL
#    else
#      define PFI_PTRDIFF_MAX 2147483647L
#    endif
#  else
#    include <stdint.h>
#    define PFI_PTRDIFF_MAX PTRDIFF_MAX
#  endif
#  if PFI_PTRDIFF_MAX / 8 > (1LL << 40)
#    define PF_MAX_REALS (1LL << 40)
#  else
#    define PF_MAX_REALS ((long long)(PFI_PTRDIFF_MAX / 8))
#  endif
#endif

/* a * b as a count of pf_reals, or -1 when a or b is negative or the product exceeds
   PF_MAX_REALS (checked by division first: the product itself never overflows). */
PF_CPU_DEF long long pf_size_mul(long long a, long long b)
{
    if (a < 0 || b < 0) return -1;
    if (b != 0 && a > PF_MAX_REALS / b) return -1;
    return a * b;
}

/* a * b * c the same way. */
PF_CPU_DEF long long pf_size_mul3(long long a, long long b, long long c)
{
    long long ab = pf_size_mul(a, b);
    return ab < 0 ? -1 : pf_size_mul(ab, c);
}

/* 1 when n is a valid side: 1 <= n <= PF_MAX_SIDE. */
PF_CPU_DEF int pf_size_side_ok(long long n) { return n >= 1 && n <= PF_MAX_SIDE; }

/* floor(x) as an index clamped to [lo, hi] (lo <= hi); NaN gives lo. The comparisons happen in
   pf_real before any conversion, so no x (huge, infinite, NaN) reaches an out-of-range
   float-to-integer conversion, which is undefined behaviour in C. */
PF_CPU_DEF long long pf_floor_index(pf_real x, long long lo, long long hi)
{
    long long i;
    if (!(x > (pf_real)lo)) return lo;
    if (!(x < (pf_real)hi)) return hi;
    i = (long long)PF_FLOOR(x);
    return i < lo ? lo : (i > hi ? hi : i);
}

/* IEEE binary16 (half float) storage, shared by the encoders of pf_encode.h and pf_shadow.h. */
/* x rounded to the nearest integer, ties to even, for 0 <= x <= 2^24 (no libm rint). */
PF_CPU_DEF long pf_round_even(pf_real x)
{
    long q = (long)x;
    pf_real f = x - (pf_real)q;
    if (f > PF_R(0.5) || (f == PF_R(0.5) && (q & 1L))) ++q;
    return q;
}

/* 2^k for -40 <= k <= 40 by repeated exact scaling (no libm ldexp). */
PF_CPU_DEF pf_real pfi_core_pow2(int k)
{
    pf_real r = PF_R(1.0);
    for (; k > 0; --k) r *= PF_R(2.0);
    for (; k < 0; ++k) r *= PF_R(0.5);
    return r;
}

/* IEEE binary16 bits of x, rounded to nearest even; |x| >= 65520 (also inf) gives +-inf, NaN
   a quiet NaN. Encoders (pf_encode.h, pf_shadow.h) reject those before calling it. Exact in float and
   double: only scaling by powers of two and one rounding. */
PF_CPU_DEF unsigned short pf_half_from_real(pf_real x)
{
    unsigned short sign = (unsigned short)(x < PF_R(0.0) ? 0x8000u : 0u); /* -0 stored as +0 */
    pf_real a = PF_FABS(x), p = PF_R(1.220703125e-04); /* 2^(e + 1) */
    int e;
    long m;
    if (!(a == a)) return (unsigned short)0x7e00u;
    if (a >= PF_R(65520.0)) return (unsigned short)(sign | 0x7c00u);
    if (a < PF_R(6.103515625e-05)) { /* below 2^-14: subnormal, units of 2^-24 (may round up to 2^-14) */
        m = pf_round_even(a * PF_R(16777216.0));
        return (unsigned short)(sign | (unsigned short)m);
    }
    e = -14;
    while (e < 15 && a >= p) {
        ++e;
        p *= PF_R(2.0);
    }
    m = pf_round_even(a * pfi_core_pow2(10 - e)); /* in [1024, 2048] */
    if (m == 2048) {
        m = 1024;
        ++e;
    }
    if (e > 15) return (unsigned short)(sign | 0x7c00u);
    return (unsigned short)(sign | (unsigned short)((e + 15) << 10) | (unsigned short)(m - 1024));
}

/* The value of binary16 bits h; finite for every pattern: +-inf gives +-65504, NaN 0. */
PF_CPU_DEF pf_real pf_real_from_half(unsigned short h)
{
    int e = (h >> 10) & 31;
    long m = h & 1023;
    pf_real v;
    if (e == 31) v = m ? PF_R(0.0) : PF_R(65504.0);
    else if (e == 0) v = (pf_real)m * PF_R(5.9604644775390625e-08); /* 2^-24 */
    else v = (pf_real)(1024 + m) * pfi_core_pow2(e - 25);
    return (h & 0x8000u) ? -v : v;
}
#endif /* !PF_GLSL */

#endif /* PF_CORE_H */

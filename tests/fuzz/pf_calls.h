/* tests/fuzz/pf_calls.h - one entry per public evaluator of include/pf_*.h, mapping raw 32-bit
   words to inputs inside the function's documented domain and checking its outputs.

   Shared by the libFuzzer harnesses (tests/fuzz/fuzz_<module>.c) and the seeded stability
   sweep (bench/stability.c). Test code, not library code: it may use globals and stdio.

   HOW AN ENTRY WORKS. pfc_f_<name>(pfc_ctx *c) draws each argument with a domain helper
   (pfc_u01, pfc_cos, pfc_dir, pfc_stats, ...). A helper takes one or more 32-bit words from
   pfc_next(c) - the seeded generator in the sweep, the fuzzer's bytes in a harness - and
   spends the top 4 bits of a word on the REGIME (exact 0, exact 1, +-tiny, huge, grazing
   cos ~ 1e-7, variance slightly negative, |r| -> 1, ...) and the other 28 on the value, so
   about half of all draws land on an edge. Every drawn argument is recorded in c->arg[] and
   every output in c->out[] (to print a failing case exactly). pfc_out() flags a non-finite
   output (bit 1 of c->bad), pfc_in() also a value outside a documented range (bit 2).
   Finiteness is tested on the bit pattern, so -ffast-math cannot fold the test away.

   WIDE entries (flag PFC_WIDE): the header promises a finite result for EVERY finite input.
   For them every helper returns, in 1 draw out of 16, an arbitrary finite number (any
   exponent, up to +-PF_REAL_MAX) instead of its usual domain value.

   RAW mode (c->raw = 1, fuzzers only): helpers return the word's bits reinterpreted as a
   float (NaN and inf included) and small ints; outputs are not checked, the call only has
   to be free of crashes and undefined behaviour (the sanitizers watch).

   Coverage: bench/stability.sh and tests/fuzz/run.sh compare pfc_table against the public
   functions that tests/portability/gen.awk finds, and pf_buffers.h's pfb_table against the
   public PF_CPU_DEF functions; a public function without an entry fails both. */
#ifndef PF_CALLS_H
#define PF_CALLS_H

#include <string.h>
#include "pf_core.h"
#include "pf_smith.h"
#include "pf_beckmann.h"
#include "pf_map.h"
#include "pf_vmf_fit.h"
#include "pf_vmf_scale.h"
#include "pf_map_downsample.h"
#include "pf_toksvig.h"
#include "pf_shadow.h"
#include "pf_gaussgrid.h"
#include "pf_height.h"
#include "pf_horizon.h"
#include "pf_masks.h"
#include "pf_vmf.h"
#include "pf_encode.h"
#include "pf_specaa.h"

typedef unsigned int pfc_u32;
typedef unsigned long long pfc_u64;

#define PFC_MAX_VALUES 64

typedef struct pfc_ctx {
    /* word source: data != 0 -> fuzzer bytes (then a generator seeded from them), else rng */
    const unsigned char *data;
    unsigned long size, pos;
    pfc_u64 rng;
    int raw;  /* RAW mode (see above) */
    int wide; /* PFC_WIDE entry */
    int wide_hit; /* this call drew an arbitrary finite value (range checks then skipped) */
    int skip; /* a derived input came out non-finite: the call does not count */
    int bad;  /* 1: non-finite output, 2: output out of its documented range */
    int have_lo;
    pfc_u32 lo; /* the unused half of the last 64-bit draw */
    int narg, nout;
    pf_real arg[PFC_MAX_VALUES];
    pf_real out[PFC_MAX_VALUES];
    int iarg[8];
    int niarg;
} pfc_ctx;

#define PFC_WIDE 1
#define PFC_SLOW 2 /* tens of ns or more per call: loops over nodes or samples */

typedef struct pfc_entry {
    const char *name;
    const char *module;
    void (*fn)(pfc_ctx *c);
    int flags;
    const char *domain;  /* what the sweep draws (the documented domain, edges included) */
    const char *regimes; /* known failure / accuracy-loss regimes and what it returns there */
} pfc_entry;

/* ---------------------------------------------------------------- word source */
/* splitmix64 step: a cheap, well-mixed 64-bit generator (Steele, Lea, Flood 2014). */
static pfc_u64 pfc_splitmix(pfc_u64 *s)
{
    pfc_u64 z = (*s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

static pfc_u32 pfc_next(pfc_ctx *c)
{
    if (c->data && c->pos + 4 <= c->size) {
        const unsigned char *p = c->data + c->pos;
        c->pos += 4;
        return (pfc_u32)p[0] | ((pfc_u32)p[1] << 8) | ((pfc_u32)p[2] << 16) | ((pfc_u32)p[3] << 24);
    }
    if (c->have_lo) { c->have_lo = 0; return c->lo; }
    {
        pfc_u64 z = pfc_splitmix(&c->rng);
        c->lo = (pfc_u32)z;
        c->have_lo = 1;
        return (pfc_u32)(z >> 32);
    }
}

/* FNV-1a of a string: per-entry seeds. */
static pfc_u64 pfc_hash(const char *s)
{
    pfc_u64 h = 1469598103934665603ULL;
    while (*s) h = (h ^ (unsigned char)*s++) * 1099511628211ULL;
    return h;
}

static void pfc_reset(pfc_ctx *c)
{
    c->bad = 0;
    c->wide_hit = 0;
    c->skip = 0;
    c->narg = 0;
    c->nout = 0;
    c->niarg = 0;
}

/* ---------------------------------------------------------------- bits and powers of two */
#ifdef PF_DOUBLE
#  define PFC_EMIN (-1074) /* smallest subnormal */
#  define PFC_EMAX 1023
#  define PFC_MANT 52
#else
#  define PFC_EMIN (-149)
#  define PFC_EMAX 127
#  define PFC_MANT 23
#endif

static pf_real pfc_pow2_tab[PFC_EMAX - PFC_EMIN + 1];

static void pfc_init(void)
{
    int e;
    pf_real v = PF_R(1.0);
    for (e = 0; e <= PFC_EMAX; ++e) { pfc_pow2_tab[e - PFC_EMIN] = v; v = v * PF_R(2.0); }
    v = PF_R(1.0);
    for (e = 0; e >= PFC_EMIN; --e) { pfc_pow2_tab[e - PFC_EMIN] = v; v = v * PF_R(0.5); }
}

static pf_real pfc_p2(int e)
{
    if (e < PFC_EMIN) e = PFC_EMIN;
    if (e > PFC_EMAX) e = PFC_EMAX;
    return pfc_pow2_tab[e - PFC_EMIN];
}

static int pfc_isfinite(pf_real x)
{
#ifdef PF_DOUBLE
    pfc_u64 u;
    memcpy(&u, &x, sizeof u);
    return (u & 0x7FF0000000000000ULL) != 0x7FF0000000000000ULL;
#else
    pfc_u32 u;
    memcpy(&u, &x, sizeof u);
    return (u & 0x7F800000u) != 0x7F800000u;
#endif
}

/* A float's bits as pf_real (any value, NaN and inf included): RAW mode. */
static pf_real pfc_from_bits(pfc_u32 u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return (pf_real)f;
}

/* ---------------------------------------------------------------- recording and checks */
static pf_real pfc_keep(pfc_ctx *c, pf_real x)
{
    if (c->narg < PFC_MAX_VALUES) c->arg[c->narg] = x;
    c->narg++;
    return x;
}

static void pfc_out(pfc_ctx *c, pf_real y)
{
    if (c->nout < PFC_MAX_VALUES) c->out[c->nout] = y;
    c->nout++;
    if (!pfc_isfinite(y)) c->bad |= 1;
}

static void pfc_flag(pfc_ctx *c, int violated) { if (violated && !c->wide_hit) c->bad |= 2; }
/* y finite and lo <= y <= hi */
static void pfc_in(pfc_ctx *c, pf_real y, pf_real lo, pf_real hi)
{
    pfc_out(c, y);
    if (pfc_isfinite(y) && !(y >= lo && y <= hi)) pfc_flag(c, 1);
}

static void pfc_ge0(pfc_ctx *c, pf_real y) { pfc_in(c, y, PF_R(0.0), PF_REAL_MAX); }
static void pfc_01(pfc_ctx *c, pf_real y) { pfc_in(c, y, PF_R(0.0), PF_R(1.0)); }
/* a derived input (built from drawn ones) must be finite, else the call does not count */
static void pfc_require(pfc_ctx *c, pf_real x) { if (!pfc_isfinite(x)) c->skip = 1; }

static void pfc_out_vec2(pfc_ctx *c, pf_vec2 v) { pfc_out(c, v.x); pfc_out(c, v.y); }
static void pfc_out_vec3(pfc_ctx *c, pf_vec3 v) { pfc_out(c, v.x); pfc_out(c, v.y); pfc_out(c, v.z); }
/* a unit vector: finite, |v|^2 within 16 eps of 1 */
static void pfc_unit_vec3(pfc_ctx *c, pf_vec3 v)
{
    pf_real l2;
    pfc_out_vec3(c, v);
    l2 = v.x * v.x + v.y * v.y + v.z * v.z;
    if (pfc_isfinite(l2)) pfc_flag(c, !(PF_FABS(l2 - PF_R(1.0)) <= PF_R(16.0) * PF_REAL_EPSILON));
}
static void pfc_out_sm(pfc_ctx *c, pf_slope_moments m)
{
    pfc_out(c, m.ex); pfc_out(c, m.ey); pfc_out(c, m.exx); pfc_out(c, m.eyy); pfc_out(c, m.exy);
}
static void pfc_out_stats(pfc_ctx *c, pf_slope_stats s)
{
    pfc_out(c, s.mean_x); pfc_out(c, s.mean_y); pfc_out(c, s.var_x); pfc_out(c, s.var_y);
    pfc_out(c, s.cov_xy);
}
/* statistics promised positive semi-definite: var >= 0, |cov| <= sqrt(vx vy) (to rounding) */
static void pfc_psd_stats(pfc_ctx *c, pf_slope_stats s)
{
    pfc_out_stats(c, s);
    if (c->bad & 1) return;
    pfc_flag(c, !(s.var_x >= PF_R(0.0) && s.var_y >= PF_R(0.0)));
    pfc_flag(c, !(PF_FABS(s.cov_xy) <= PF_SQRT(s.var_x) * PF_SQRT(s.var_y) * (PF_R(1.0) + PF_R(4.0) * PF_REAL_EPSILON)));
}
static void pfc_out_d2(pfc_ctx *c, pf_depth_moments2 m) { pfc_out(c, m.m1); pfc_out(c, m.m2); }
static void pfc_out_d4(pfc_ctx *c, pf_depth_moments4 m)
{
    pfc_out(c, m.m1); pfc_out(c, m.m2); pfc_out(c, m.m3); pfc_out(c, m.m4);
}
static void pfc_out_evsm(pfc_ctx *c, pf_evsm_moments m)
{
    pfc_out(c, m.pos1); pfc_out(c, m.pos2); pfc_out(c, m.neg1); pfc_out(c, m.neg2);
}
static void pfc_out_scm(pfc_ctx *c, pf_scalar_moments m) { pfc_out(c, m.m1); pfc_out(c, m.m2); }
static void pfc_out_sh9(pfc_ctx *c, pf_sh9 s)
{
    pfc_out(c, s.l00); pfc_out(c, s.l1m1); pfc_out(c, s.l10); pfc_out(c, s.l11); pfc_out(c, s.l2m2);
    pfc_out(c, s.l2m1); pfc_out(c, s.l20); pfc_out(c, s.l21); pfc_out(c, s.l22);
}
static void pfc_out_hd(pfc_ctx *c, pf_height_dist d) { pfc_out(c, d.mean); pfc_ge0(c, d.dev); }
static void pfc_out_tm(pfc_ctx *c, pf_transfer_moments m)
{
    pfc_out(c, m.g); pfc_out(c, m.g2); pfc_out(c, m.dg); pfc_out(c, m.dg2);
}

/* ---------------------------------------------------------------- domain helpers
   r = top 4 bits of a word (the regime), b = the low 28 bits (the value). */
#define PFC_R(u) ((int)((u) >> 28))
#define PFC_B(u) ((u) & 0x0FFFFFFFu)

/* uniform in [0, 1) from 24 bits (exact in float) */
static pf_real pfc_unif(pfc_u32 b) { return (pf_real)(b >> 4) * PF_R(5.9604644775390625e-8); }

/* magnitude in [2^elo, 2^ehi), log-uniform exponent, 8 random mantissa bits */
static pf_real pfc_mag(pfc_u32 b, int elo, int ehi)
{
    int e = elo + (int)(((b >> 8) * (pfc_u32)(ehi - elo)) >> 20); /* 20 bits: no division */
    return (PF_R(1.0) + (pf_real)(b & 0xFFu) * PF_R(0.00390625)) * pfc_p2(e);
}

/* an arbitrary finite number: any exponent (subnormals, PF_REAL_MAX), either sign */
static pf_real pfc_anyfinite(pfc_u32 b)
{
    pf_real s = (b & 1u) ? PF_R(-1.0) : PF_R(1.0);
    pfc_u32 k = (b >> 1) & 7u;
    if (k == 0) return s * PF_REAL_MAX;
    if (k == 1) return s * pfc_p2(PFC_EMIN);
    if (k == 2) return PF_R(0.0) * s;
    return s * pf_min(pfc_mag(b >> 4, PFC_EMIN, PFC_EMAX), PF_REAL_MAX);
}

/* Shared front of every helper: RAW mode and the wide draw. Returns 1 and sets *x when done. */
static int pfc_front(pfc_ctx *c, pfc_u32 u, pf_real *x)
{
    if (c->raw) { *x = pfc_from_bits(u); return 1; }
    if (c->wide && PFC_R(u) == 15) { *x = pfc_anyfinite(PFC_B(u)); c->wide_hit = 1; return 1; }
    return 0;
}

/* [0, 1]: 0, 1, tiny (subnormal to 2^-20), 1 - tiny, uniform */
static pf_real pfc_u01(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real x;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = PF_R(1.0); break;
        case 2: x = pfc_mag(b, PFC_EMIN, -20); break;
        case 3: x = PF_R(1.0) - pfc_mag(b, -PFC_MANT - 1, -8); break;
        default: x = pfc_unif(b); break;
        }
    }
    return pfc_keep(c, x);
}

/* [0, 2^ehi]: 0, tiny, log-uniform over [2^-24, 2^ehi), uniform [0, 1), 1, 2^ehi */
static pf_real pfc_pos(pfc_ctx *c, int ehi)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real x;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = pfc_mag(b, PFC_EMIN, -24); break;
        case 2: x = PF_R(1.0); break;
        case 3: x = pfc_p2(ehi); break;
        case 4: case 5: case 6: case 7: x = pfc_unif(b); break;
        default: x = pfc_mag(b, -24, ehi); break;
        }
    }
    return pfc_keep(c, x);
}

/* [-2^ehi, 2^ehi], the same regimes with a sign */
static pf_real pfc_sym(pfc_ctx *c, int ehi)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real x, s = (b & 1u) ? PF_R(-1.0) : PF_R(1.0);
    b >>= 1;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = s * pfc_mag(b, PFC_EMIN, -24); break;
        case 2: x = s; break;
        case 3: x = s * pfc_p2(ehi); break;
        case 4: case 5: case 6: case 7: x = s * pfc_unif(b << 1); break;
        default: x = s * pfc_mag(b, -24, ehi); break;
        }
    }
    return pfc_keep(c, x);
}

/* cos theta: 1 (normal incidence), 0 (horizon), grazing +-[2^-40, 2^-10) (cos ~ 1e-7
   included), 1 - tiny, below the surface (-uniform, -1), uniform (0, 1] */
static pf_real pfc_cos_raw(pfc_ctx *c, pfc_u32 u)
{
    pfc_u32 b = PFC_B(u);
    pf_real x;
    if (pfc_front(c, u, &x)) return x;
    switch (PFC_R(u)) {
    case 0: return PF_R(1.0);
    case 1: return PF_R(0.0);
    case 2: case 3: return pfc_mag(b, -40, -10);
    case 4: return PF_R(1.0) - pfc_mag(b, -PFC_MANT - 1, -8);
    case 5: return -pfc_mag(b, -40, -10);
    case 6: return -pfc_unif(b);
    case 7: return PF_R(-1.0);
    default: return PF_R(1.0) - pfc_unif(b);
    }
}
static pf_real pfc_cos(pfc_ctx *c) { return pfc_keep(c, pfc_cos_raw(c, pfc_next(c))); }

/* A unit direction with z = pfc_cos (so grazing, horizontal and below-surface ones), azimuth
   uniform or along an axis. */
static pf_vec3 pfc_dir(pfc_ctx *c)
{
    pfc_u32 u0 = pfc_next(c), u1 = pfc_next(c), u2 = pfc_next(c);
    pf_real z, a, b, l2, s;
    if (c->raw) {
        return pf_vec3_make(pfc_keep(c, pfc_from_bits(u0)), pfc_keep(c, pfc_from_bits(u1)),
                            pfc_keep(c, pfc_from_bits(u2)));
    }
    z = pfc_cos_raw(c, u0);
    a = PFC_R(u1) == 0 ? PF_R(0.0) : PF_R(2.0) * pfc_unif(PFC_B(u1)) - PF_R(1.0);
    b = PFC_R(u2) == 0 ? PF_R(0.0) : PF_R(2.0) * pfc_unif(PFC_B(u2)) - PF_R(1.0);
    l2 = a * a + b * b;
    if (!(l2 > PF_R(1.0e-12))) { a = PF_R(1.0); b = PF_R(0.0); l2 = PF_R(1.0); }
    if (!pfc_isfinite(z) || PF_FABS(z) > PF_R(1.0)) {
        /* a wide draw: keep it as z of an unnormalized vector */
        s = PF_R(1.0);
    } else {
        s = PF_SQRT(pf_max(PF_R(1.0) - z * z, PF_R(0.0)));
    }
    s = s / PF_SQRT(l2);
    return pf_vec3_make(pfc_keep(c, a * s), pfc_keep(c, b * s), pfc_keep(c, z));
}

/* A direction of any length (for functions that take unnormalized vectors): pfc_dir scaled
   by 1 (3/4 of draws) or 2^k, k in [-40, 40) (float) / [-300, 300) (double); and 1/16 of the
   time the zero vector. */
static pf_vec3 pfc_dir_any(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    pf_vec3 d = pfc_dir(c);
    pf_real k = PF_R(1.0);
    if (c->raw) return d;
    if (PFC_R(u) == 0) k = PF_R(0.0);
#ifdef PF_DOUBLE
    else if (PFC_R(u) >= 13) k = pfc_p2((int)(PFC_B(u) % 600u) - 300);
#else
    else if (PFC_R(u) >= 13) k = pfc_p2((int)(PFC_B(u) % 80u) - 40);
#endif
    if (k != PF_R(1.0) && pfc_isfinite(pf_vec3_dot(d, d) * k * k)) {
        d = pf_vec3_scale(d, k);
        if (c->narg <= PFC_MAX_VALUES) {
            c->arg[c->narg - 3] = d.x; c->arg[c->narg - 2] = d.y; c->arg[c->narg - 1] = d.z;
        }
    }
    return d;
}

/* A slope variance: 0, tiny [2^-60, 2^-20), slightly negative (rounding of filtered
   moments: -[2^-60, 2^-16)) when neg, huge [2^10, 2^32), else [2^-20, 2^10) */
static pf_real pfc_var(pfc_ctx *c, int neg)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real x;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = pfc_mag(b, -60, -20); break;
        case 2: x = neg ? -pfc_mag(b, -60, -16) : PF_R(0.0); break;
        case 3: x = pfc_mag(b, 10, 32); break;
        default: x = pfc_mag(b, -20, 10); break;
        }
    }
    return pfc_keep(c, x);
}

/* A correlation: 0, +-1, +-(1 - 2^-k), slightly beyond +-1 (+-(1 + 2^-k), rounding) when
   beyond, uniform (-1, 1) */
static pf_real pfc_corr(pfc_ctx *c, int beyond)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real s = (b & 1u) ? PF_R(-1.0) : PF_R(1.0), x;
    int k = 1 + (int)((b >> 1) % (pfc_u32)PFC_MANT);
    if (c->raw) return pfc_keep(c, pfc_from_bits(u));
    switch (PFC_R(u)) {
    case 0: x = PF_R(0.0); break;
    case 1: x = s; break;
    case 2: x = s * (PF_R(1.0) - pfc_p2(-k)); break;
    case 3: x = beyond ? s * (PF_R(1.0) + pfc_p2(-k)) : s * (PF_R(1.0) - pfc_p2(-k)); break;
    default: x = PF_R(2.0) * pfc_unif(b) - PF_R(1.0); break;
    }
    return x; /* recorded as the covariance by the caller */
}

/* Slope statistics: means in +-2^8 (wide: anything), variances from pfc_var, covariance
   r sqrt(vx vy). neg: variances slightly negative and |r| slightly above 1 allowed (what the
   function documents it reads; raw covariances). */
static pf_slope_stats pfc_stats(pfc_ctx *c, int neg)
{
    pf_real mx = pfc_sym(c, 8), my = pfc_sym(c, 8);
    pf_real vx = pfc_var(c, neg), vy = pfc_var(c, neg);
    pf_real r = pfc_corr(c, neg);
    pf_real cv = c->raw ? r : r * PF_SQRT(pf_max(vx, PF_R(0.0))) * PF_SQRT(pf_max(vy, PF_R(0.0)));
    pfc_require(c, cv); /* r sqrt(vx) sqrt(vy) may round past PF_REAL_MAX for wide variances */
    return pf_slope_stats_make(mx, my, vx, vy, pfc_keep(c, cv));
}

/* Filtered slope moments: the raw moments of pfc_stats (neg = 1: rounding may push a
   variance below 0 or |r| above 1). */
static pf_slope_moments pfc_moments(pfc_ctx *c)
{
    int n0 = c->narg;
    pf_slope_stats s = pfc_stats(c, 1);
    pf_slope_moments m;
    if (c->raw) return pf_slope_moments_make(s.mean_x, s.mean_y, s.var_x, s.var_y, s.cov_xy);
    m = pf_slope_moments_from_stats(s);
    if (!pfc_isfinite(m.exx) || !pfc_isfinite(m.eyy) || !pfc_isfinite(m.exy))
        m = pf_slope_moments_make(s.mean_x, s.mean_y, s.var_x, s.var_y, s.cov_xy); /* a wide draw */
    c->narg = n0; /* record what is passed: the moments */
    pfc_keep(c, m.ex); pfc_keep(c, m.ey); pfc_keep(c, m.exx); pfc_keep(c, m.eyy); pfc_keep(c, m.exy);
    return m;
}

/* An int in [lo, hi] (RAW: [-128, 127]) */
static int pfc_int(pfc_ctx *c, int lo, int hi)
{
    pfc_u32 u = pfc_next(c);
    int v;
    if (c->raw) v = (int)(u & 0xFFu) - 128;
    else v = lo + (int)(u % (pfc_u32)(hi - lo + 1));
    if (c->niarg < 8) c->iarg[c->niarg] = v;
    c->niarg++;
    return v;
}

/* An int index: mostly [-3, 12], 1/8 of the time huge (+-[2^20, 2^31)) or INT_MIN/INT_MAX */
static int pfc_int_any(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    int v;
    if (c->raw) v = (int)(u & 0xFFu) - 128;
    else if (PFC_R(u) == 0) v = (u & 1u) ? -2147483647 - 1 : 2147483647;
    else if (PFC_R(u) == 1) v = (int)(0x100000u + (PFC_B(u) % 0x7FF00000u)) * ((u & 2u) ? -1 : 1);
    else v = -3 + (int)(u % 16u);
    if (c->niarg < 8) c->iarg[c->niarg] = v;
    c->niarg++;
    return v;
}

/* Convex weights (w.x + w.y + w.z = 1, each in [0, 1]): pf_mip_weights3 of a random odd or
   even size, or two uniforms folded, or a corner (1, 0, 0). */
static pf_vec3 pfc_w3(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    pf_real a, b;
    if (c->raw) return pf_vec3_make(pfc_keep(c, pfc_from_bits(u)), pfc_keep(c, pfc_from_bits(pfc_next(c))),
                                    pfc_keep(c, pfc_from_bits(pfc_next(c))));
    if (PFC_R(u) < 6) {
        pf_vec3 w = pf_mip_weights3((int)(u % 64u), 1 + (int)((u >> 6) % 4096u));
        pfc_keep(c, w.x); pfc_keep(c, w.y); pfc_keep(c, w.z);
        return w;
    }
    if (PFC_R(u) == 6) return pf_vec3_make(pfc_keep(c, PF_R(1.0)), pfc_keep(c, PF_R(0.0)), pfc_keep(c, PF_R(0.0)));
    a = pfc_unif(PFC_B(u));
    b = pfc_unif(PFC_B(pfc_next(c)));
    if (a + b > PF_R(1.0)) { a = PF_R(1.0) - a; b = PF_R(1.0) - b; }
    return pf_vec3_make(pfc_keep(c, a), pfc_keep(c, b), pfc_keep(c, pf_max(PF_R(1.0) - a - b, PF_R(0.0))));
}

/* Depth moments of a footprint: two depths z0, z1 in [0, 1] (pfc_u01) mixed with weight t,
   plus, 1 time in 8, a relative rounding perturbation of +-2^-20 on each moment. */
static pf_real pfc_perturb(pfc_ctx *c, pf_real m, pfc_u32 u, int k)
{
    (void)c;
    if (PFC_R(u) != 3) return m;
    return m * (PF_R(1.0) + (((u >> k) & 1u) ? PF_R(-1.0) : PF_R(1.0)) * PF_R(9.5367431640625e-7));
}
static pf_depth_moments4 pfc_d4(pfc_ctx *c)
{
    pf_real z0 = pfc_u01(c), z1 = pfc_u01(c), t = pfc_u01(c), s = PF_R(1.0) - t;
    pfc_u32 u = pfc_next(c);
    pf_real a2 = z0 * z0, b2 = z1 * z1;
    if (c->raw) return pf_depth_moments4_make(z0, z1, t, pfc_from_bits(u));
    if (PFC_R(u) == 0) return pf_depth_moments4_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    return pf_depth_moments4_make(pfc_perturb(c, s * z0 + t * z1, u, 0), pfc_perturb(c, s * a2 + t * b2, u, 1),
                                  pfc_perturb(c, s * a2 * z0 + t * b2 * z1, u, 2),
                                  pfc_perturb(c, s * a2 * a2 + t * b2 * b2, u, 3));
}
static pf_depth_moments2 pfc_d2(pfc_ctx *c)
{
    pf_depth_moments4 m = pfc_d4(c);
    return pf_depth_moments2_make(m.m1, m.m2);
}
/* An EVSM exponent in [0, PF_EVSM_EXP_MAX_F32] (0, 44, 5.54, uniform) */
static pf_real pfc_evsm_c(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    pf_real x;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = PF_EVSM_EXP_MAX_F32; break;
        case 2: x = PF_EVSM_EXP_MAX_F16; break;
        case 3: x = pfc_mag(PFC_B(u), -30, 0); break;
        default: x = PF_EVSM_EXP_MAX_F32 * pfc_unif(PFC_B(u)); break;
        }
    }
    return pfc_keep(c, x);
}
/* EVSM-4 moments of two depths mixed (like pfc_d4), exponents c_pos, c_neg */
static pf_evsm_moments pfc_evsm(pfc_ctx *c, pf_real cp, pf_real cn)
{
    pf_real z0 = pfc_u01(c), z1 = pfc_u01(c), t = pfc_u01(c), s = PF_R(1.0) - t;
    pf_evsm_moments a = pf_evsm_moments_from_depth(z0, cp, cn), b = pf_evsm_moments_from_depth(z1, cp, cn);
    pf_evsm_moments m;
    if (c->raw) return pf_evsm_moments_make(z0, z1, t, cp);
    m = pf_evsm_moments_make(s * a.pos1 + t * b.pos1, s * a.pos2 + t * b.pos2, s * a.neg1 + t * b.neg1,
                             s * a.neg2 + t * b.neg2);
    pfc_require(c, m.pos2); pfc_require(c, m.neg2); /* a wide exponent */
    return m;
}

/* Lambda in [0, PF_LAMBDA_MAX]: 0, tiny, 1e30, log-uniform, and (documented as read as 0 /
   clamped) slightly negative or above PF_LAMBDA_MAX */
static pf_real pfc_lambda(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real x;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = pfc_mag(b, -60, -20); break;
        case 2: x = PF_LAMBDA_MAX; break;
        case 3: x = -pfc_mag(b, -30, 0); break;
        case 4: x = PF_LAMBDA_MAX * pfc_mag(b, 0, 20); break;
        case 5: case 6: x = pfc_unif(b) * PF_R(4.0); break;
        default: x = pfc_mag(b, -20, 100); break;
        }
    }
    return pfc_keep(c, x);
}

/* A smith nu: every real (0, negative, tiny, huge, PF_NU_MAX, around the branch points) */
static pf_real pfc_nu(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real x;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = pfc_mag(b, PFC_EMIN, -20); break;
        case 2: x = -pfc_mag(b, -30, 30); break;
        case 3: x = PF_NU_MAX; break;
        case 4: x = pfc_mag(b, 4, 60); break;
        case 5: { /* around a branch point: 1.6, 2, 2.2, 3.3, 10.5, 27.5 */
            static const float bp[6] = { 1.6f, 2.0f, 2.2f, 3.3f, 10.5f, 27.5f };
            x = (pf_real)bp[b % 6u] * (PF_R(1.0) + (pf_real)((int)((b >> 3) & 63u) - 32) * PF_REAL_EPSILON);
            break;
        }
        default: x = PF_R(8.0) * pfc_unif(b); break;
        }
    }
    return pfc_keep(c, x);
}

/* A Gauss-grid: view, stats (neg allowed: documented as clamped), node set 0..2 or unknown,
   N in [-1, 12] (clamped to [1, 9]) */
static pf_gg_grid pfc_grid(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c);
    pf_slope_stats s = pfc_stats(c, 1);
    int set = pfc_int(c, 0, 3);
    int n = pfc_int(c, -1, 12);
    return pf_gg_grid_make(wo, s, set, n);
}

static pf_sh9 pfc_sh9(pfc_ctx *c)
{
    pf_real a[9];
    int i;
    for (i = 0; i < 9; ++i) a[i] = pfc_sym(c, 10);
    return pf_sh9_make(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8]);
}

static pf_scalar_moments pfc_scm(pfc_ctx *c)
{
    pf_real f = pfc_sym(c, 16), v = pfc_var(c, 1);
    if (c->raw) return pf_scalar_moments_make(f, v);
    pfc_require(c, v + f * f);
    return pf_scalar_moments_make(f, v + f * f);
}

/* a vector of an average-normal pyramid: |v| <= 1 (normalized and shrunk) */
static pf_vec3 pfc_navg(pfc_ctx *c)
{
    pf_vec3 d = pfc_dir(c);
    pf_real l = pfc_u01(c);
    return pf_vec3_scale(d, l);
}

/* a sigma for the Gaussian filters: 0, negative (no filtering), tiny, huge, usual */
static pf_real pfc_sigma(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real x;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = -pfc_unif(b); break;
        case 2: x = pfc_mag(b, PFC_EMIN, -20); break;
        case 3: x = pfc_mag(b, 10, 40); break;
        default: x = pfc_mag(b, -20, 4); break;
        }
    }
    return pfc_keep(c, x);
}

/* ================================================================ the entries */
/* ---- core */
static void pfc_f_pf_min(pfc_ctx *c) { pfc_out(c, pf_min(pfc_sym(c, 100), pfc_sym(c, 100))); }
static void pfc_f_pf_max(pfc_ctx *c) { pfc_out(c, pf_max(pfc_sym(c, 100), pfc_sym(c, 100))); }
static void pfc_f_pf_clamp_nan_lo(pfc_ctx *c)
{
    pf_real x = pfc_sym(c, 100), lo = pfc_sym(c, 8), hi = pfc_sym(c, 8);
    if (lo > hi) { pf_real t = lo; lo = hi; hi = t; }
    pfc_in(c, pf_clamp_nan_lo(x, lo, hi), lo, hi);
}
static void pfc_f_pf_clamp(pfc_ctx *c)
{
    pf_real x = pfc_sym(c, 100), lo = pfc_sym(c, 8), hi = pfc_sym(c, 8);
    if (lo > hi) { pf_real t = lo; lo = hi; hi = t; }
    pfc_in(c, pf_clamp(x, lo, hi), lo, hi);
}
static void pfc_f_pf_saturate(pfc_ctx *c) { pfc_01(c, pf_saturate(pfc_sym(c, 100))); }
static void pfc_f_pf_sq(pfc_ctx *c) { pfc_ge0(c, pf_sq(pfc_sym(c, 60))); }
static void pfc_f_pf_exp_neg_sq(pfc_ctx *c) { pfc_01(c, pf_exp_neg_sq(pfc_sym(c, 12))); }
static void pfc_f_pf_atan2(pfc_ctx *c)
{
    pf_real y = pfc_sym(c, 100), x = pfc_sym(c, 100);
    pfc_in(c, pf_atan2(y, x), -PF_PI, PF_PI);
}
static void pfc_f_pf_erfc(pfc_ctx *c) { pfc_in(c, pf_erfc(pfc_sym(c, 12)), PF_R(0.0), PF_R(2.0)); }
static void pfc_f_pf_erfc_fast(pfc_ctx *c) { pfc_in(c, pf_erfc_fast(pfc_sym(c, 12)), PF_R(0.0), PF_R(2.0)); }
static void pfc_f_pf_erf(pfc_ctx *c) { pfc_in(c, pf_erf(pfc_sym(c, 12)), PF_R(-1.0), PF_R(1.0)); }
static void pfc_f_pf_vec2_make(pfc_ctx *c) { pfc_out_vec2(c, pf_vec2_make(pfc_sym(c, 60), pfc_sym(c, 60))); }
static void pfc_f_pf_vec2_dot(pfc_ctx *c)
{
    pf_vec2 a = pf_vec2_make(pfc_sym(c, 30), pfc_sym(c, 30)), b = pf_vec2_make(pfc_sym(c, 30), pfc_sym(c, 30));
    pfc_out(c, pf_vec2_dot(a, b));
}
static void pfc_f_pf_vec3_make(pfc_ctx *c) { pfc_out_vec3(c, pf_vec3_make(pfc_sym(c, 60), pfc_sym(c, 60), pfc_sym(c, 60))); }
static void pfc_f_pf_vec3_add(pfc_ctx *c) { pf_vec3 a = pfc_dir_any(c); pfc_out_vec3(c, pf_vec3_add(a, pfc_dir_any(c))); }
static void pfc_f_pf_vec3_sub(pfc_ctx *c) { pf_vec3 a = pfc_dir_any(c); pfc_out_vec3(c, pf_vec3_sub(a, pfc_dir_any(c))); }
static void pfc_f_pf_vec3_scale(pfc_ctx *c) { pf_vec3 a = pfc_dir_any(c); pfc_out_vec3(c, pf_vec3_scale(a, pfc_sym(c, 20))); }
static void pfc_f_pf_vec3_dot(pfc_ctx *c) { pf_vec3 a = pfc_dir_any(c); pfc_out(c, pf_vec3_dot(a, pfc_dir_any(c))); }
static void pfc_f_pf_vec3_cross(pfc_ctx *c) { pf_vec3 a = pfc_dir_any(c); pfc_out_vec3(c, pf_vec3_cross(a, pfc_dir_any(c))); }
static void pfc_f_pf_vec3_length(pfc_ctx *c) { pfc_ge0(c, pf_vec3_length(pfc_dir_any(c))); }
static void pfc_f_pf_vec3_normalize(pfc_ctx *c)
{
    pf_vec3 v = pf_vec3_make(pfc_sym(c, PFC_EMAX), pfc_sym(c, PFC_EMAX), pfc_sym(c, PFC_EMAX));
    pfc_unit_vec3(c, pf_vec3_normalize(v));
}

/* ---- smith */
static void pfc_f_pf_slope_stats_make(pfc_ctx *c) { pfc_out_stats(c, pfc_stats(c, 1)); }
static void pfc_f_pf_slope_stats_from_moments(pfc_ctx *c)
{
    pf_slope_moments m = pfc_moments(c);
    pfc_psd_stats(c, pf_slope_stats_from_moments(m.ex, m.ey, m.exx, m.eyy, m.exy));
}
static void pfc_f_pf_slope_along(pfc_ctx *c)
{
    pf_vec3 w = pfc_dir_any(c);
    pf_vec2 r = pf_slope_along(w, pfc_stats(c, 1));
    pfc_out(c, r.x);
    pfc_ge0(c, r.y);
}
static void pfc_f_pf_smith_nu(pfc_ctx *c)
{
    pf_vec3 w = pfc_dir_any(c);
    pfc_in(c, pf_smith_nu(w, pfc_stats(c, 1)), PF_R(0.0), PF_NU_MAX);
}
static void pfc_f_pf_smith_nu_iso(pfc_ctx *c)
{
    pf_real ct = pfc_cos(c);
    pfc_in(c, pf_smith_nu_iso(ct, pfc_pos(c, 10)), PF_R(0.0), PF_NU_MAX);
}
static void pfc_f_pf_smith_k(pfc_ctx *c) { pfc_in(c, pf_smith_k(PF_R(2.0) * pfc_u01(c)), PF_R(0.0), PF_R(1.0)); }
static void pfc_f_pf_smith_nu_over_g1(pfc_ctx *c) { pfc_ge0(c, pf_smith_nu_over_g1(pfc_nu(c))); }
static void pfc_f_pf_lambda_beckmann(pfc_ctx *c) { pfc_in(c, pf_lambda_beckmann(pfc_nu(c)), PF_R(0.0), PF_LAMBDA_MAX); }
static void pfc_f_pf_g1_beckmann(pfc_ctx *c) { pfc_01(c, pf_g1_beckmann(pfc_nu(c))); }
static void pfc_f_pf_lambda_beckmann_walter(pfc_ctx *c) { pfc_in(c, pf_lambda_beckmann_walter(pfc_nu(c)), PF_R(0.0), PF_LAMBDA_MAX); }
static void pfc_f_pf_g1_beckmann_walter(pfc_ctx *c) { pfc_01(c, pf_g1_beckmann_walter(pfc_nu(c))); }
static void pfc_f_pf_g1_beckmann_fast(pfc_ctx *c) { pfc_01(c, pf_g1_beckmann_fast(pfc_nu(c))); }
static void pfc_f_pf_lambda_beckmann_fast(pfc_ctx *c) { pfc_in(c, pf_lambda_beckmann_fast(pfc_nu(c)), PF_R(0.0), PF_LAMBDA_MAX); }
static void pfc_f_pf_lambda_ggx(pfc_ctx *c)
{
    pf_vec3 w = pfc_dir_any(c);
    pf_real ax = pfc_pos(c, 10);
    pfc_in(c, pf_lambda_ggx(w, ax, pfc_pos(c, 10)), PF_R(0.0), PF_LAMBDA_MAX);
}
static void pfc_f_pf_g1_ggx(pfc_ctx *c)
{
    pf_vec3 w = pfc_dir_any(c);
    pf_real ax = pfc_pos(c, 10);
    pfc_01(c, pf_g1_ggx(w, ax, pfc_pos(c, 10)));
}
static void pfc_f_pf_lambda_ggx_iso(pfc_ctx *c)
{
    pf_real ct = pfc_cos(c);
    pfc_in(c, pf_lambda_ggx_iso(ct, pfc_pos(c, 10)), PF_R(0.0), PF_LAMBDA_MAX);
}
static void pfc_f_pf_g1_ggx_iso(pfc_ctx *c)
{
    pf_real ct = pfc_cos(c);
    pfc_01(c, pf_g1_ggx_iso(ct, pfc_pos(c, 10)));
}
static void pfc_f_pf_smith_joint(pfc_ctx *c)
{
    pf_real a = pfc_u01(c), b = pfc_u01(c);
    /* to rounding: relative 4 eps, absolute PF_REAL_MIN (products of subnormals) */
    pfc_in(c, pf_smith_joint(a, b), PF_R(0.0), pf_min(a, b) * (PF_R(1.0) + PF_R(4.0) * PF_REAL_EPSILON) + PF_REAL_MIN);
}
static void pfc_f_pf_smith_joint_lambda(pfc_ctx *c)
{
    pf_real a = pfc_lambda(c);
    pfc_01(c, pf_smith_joint_lambda(a, pfc_lambda(c)));
}
static void pfc_f_pf_smith_separable(pfc_ctx *c) { pf_real a = pfc_u01(c); pfc_01(c, pf_smith_separable(a, pfc_u01(c))); }
static void pfc_f_pf_g2_beckmann(pfc_ctx *c) { pf_real a = pfc_nu(c); pfc_01(c, pf_g2_beckmann(a, pfc_nu(c))); }

/* ---- beckmann */
static void pfc_f_pf_slope_moments_make(pfc_ctx *c) { pfc_out_sm(c, pfc_moments(c)); }
static void pfc_f_pf_slope_moments_from_slope(pfc_ctx *c)
{
    pf_real x = pfc_sym(c, 40);
    pfc_out_sm(c, pf_slope_moments_from_slope(x, pfc_sym(c, 40)));
}
static void pfc_f_pf_slope_moments_from_normal(pfc_ctx *c)
{
    pf_vec3 n = pfc_dir(c);
    pf_slope_moments m;
    if (!(n.z > PF_R(1.0e-18)) && !c->raw) n.z = PF_FABS(n.z) + PF_R(1.0e-18); /* documented: n.z > 0 */
    m = pf_slope_moments_from_normal(n);
    pfc_out_sm(c, m);
}
static void pfc_f_pf_slope_moments_add(pfc_ctx *c) { pf_slope_moments a = pfc_moments(c); pfc_out_sm(c, pf_slope_moments_add(a, pfc_moments(c))); }
static void pfc_f_pf_slope_moments_scale(pfc_ctx *c) { pf_slope_moments a = pfc_moments(c); pfc_out_sm(c, pf_slope_moments_scale(a, pfc_u01(c))); }
static void pfc_f_pf_slope_moments_from_stats(pfc_ctx *c) { pfc_out_sm(c, pf_slope_moments_from_stats(pfc_stats(c, 1))); }
static void pfc_f_pf_slope_moments_stats(pfc_ctx *c)
{
    pf_slope_moments m = pfc_moments(c);
    pf_slope_stats s = pf_slope_moments_stats(m, pfc_var(c, 1));
    pfc_psd_stats(c, s);
    pfc_flag(c, !(s.var_x >= PF_BECKMANN_MIN_VAR && s.var_y >= PF_BECKMANN_MIN_VAR));
}
static void pfc_f_pf_slope_stats_correlation(pfc_ctx *c) { pfc_in(c, pf_slope_stats_correlation(pfc_stats(c, 1)), PF_R(-1.0), PF_R(1.0)); }
static void pfc_f_pf_slope_moments_deform(pfc_ctx *c)
{
    pf_slope_moments m = pfc_moments(c);
    pf_real a = pfc_sym(c, 8), b = pfc_sym(c, 8), d = pfc_sym(c, 8), e = pfc_sym(c, 8);
    pfc_out_sm(c, pf_slope_moments_deform(m, a, b, d, e));
}
static void pfc_f_pf_slope_moments_scale_height(pfc_ctx *c) { pf_slope_moments m = pfc_moments(c); pfc_out_sm(c, pf_slope_moments_scale_height(m, pfc_sym(c, 8))); }
static void pfc_f_pf_beckmann_p22(pfc_ctx *c)
{
    pf_real x = pfc_sym(c, 20), y = pfc_sym(c, 20);
    pfc_ge0(c, pf_beckmann_p22(x, y, pfc_stats(c, 1)));
}
static void pfc_f_pf_beckmann_d(pfc_ctx *c) { pf_vec3 m = pfc_dir_any(c); pfc_ge0(c, pf_beckmann_d(m, pfc_stats(c, 1))); }
static void pfc_f_pf_beckmann_mesonormal(pfc_ctx *c) { pfc_unit_vec3(c, pf_beckmann_mesonormal(pfc_stats(c, 1))); }
static void pfc_f_pf_beckmann_facing_area(pfc_ctx *c) { pf_vec3 w = pfc_dir_any(c); pfc_ge0(c, pf_beckmann_facing_area(w, pfc_stats(c, 1))); }
static void pfc_f_pf_beckmann_light_lambda(pfc_ctx *c)
{
    pf_real nu = pfc_sym(c, 8), rs = pf_max(pfc_u01(c), PF_R(1.0e-6)), wz = pf_max(pfc_u01(c), PF_R(1.0e-6));
    if (PF_FABS(nu) < PF_R(1.0e-20)) nu = PF_R(0.0); /* the domain: Lambda ~ 0.28 / nu as nu -> 0+ */
    pfc_ge0(c, pf_beckmann_light_lambda(nu, rs, wz));
}
static void pfc_f_pf_beckmann_light_lambda_stats(pfc_ctx *c)
{
    pf_vec3 w = pfc_dir(c);
    pf_slope_stats s = pfc_stats(c, 0);
    if (!(w.z > PF_R(0.0))) w.z = PF_R(1.0e-6); /* the contract: a light above the macrosurface */
    pfc_ge0(c, pf_beckmann_light_lambda_stats(w, s));
}
static void pfc_f_pf_beckmann_projected_area(pfc_ctx *c) { pf_vec3 w = pfc_dir(c); pfc_ge0(c, pf_beckmann_projected_area(w, pfc_stats(c, 1))); }
static void pfc_f_pf_beckmann_lambda(pfc_ctx *c) { pf_vec3 w = pfc_dir_any(c); pfc_in(c, pf_beckmann_lambda(w, pfc_stats(c, 1)), PF_R(0.0), PF_LAMBDA_MAX); }
static void pfc_f_pf_beckmann_g1(pfc_ctx *c) { pf_vec3 w = pfc_dir_any(c); pfc_01(c, pf_beckmann_g1(w, pfc_stats(c, 1))); }
static void pfc_f_pf_beckmann_masking_shadowing(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir_any(c), wi = pfc_dir_any(c);
    pfc_01(c, pf_beckmann_masking_shadowing(wo, wi, pfc_stats(c, 1)));
}
static void pfc_f_pf_fresnel_schlick(pfc_ctx *c) { pf_real f0 = pfc_u01(c); pfc_01(c, pf_fresnel_schlick(f0, pfc_cos(c))); }
/* the BRDF's inputs: unit directions, statistics as pf_slope_moments_stats produces them */
static pf_slope_stats pfc_leadr_stats(pfc_ctx *c)
{
    pf_slope_moments m = pfc_moments(c);
    return pf_slope_moments_stats(m, pfc_var(c, 1));
}
static void pfc_f_pf_leadr_specular(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_slope_stats s = pfc_leadr_stats(c);
    pfc_ge0(c, pf_leadr_specular(wo, wi, s, pfc_u01(c)));
}
static void pfc_f_pf_leadr_specular_masking(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_slope_stats s = pfc_leadr_stats(c);
    pfc_ge0(c, pf_leadr_specular_masking(wo, wi, s, pfc_u01(c)));
}
static void pfc_f_pf_beckmann_base_masking(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_slope_stats s = pfc_leadr_stats(c);
    pfc_01(c, pf_beckmann_base_masking(wo, wi, s, pfc_var(c, 1)));
}
static void pfc_f_pf_leadr_specular_base(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_slope_stats s = pfc_leadr_stats(c);
    pf_real bv = pfc_var(c, 1);
    pfc_ge0(c, pf_leadr_specular_base(wo, wi, s, bv, pfc_u01(c)));
}
static void pfc_f_pf_leadr_specular_point(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), tl = pfc_dir_any(c);
    pf_slope_stats s = pfc_leadr_stats(c);
    pfc_ge0(c, pf_leadr_specular_point(wo, tl, s, pfc_u01(c)));
}

/* ---- moments */
static void pfc_f_pf_depth_moments2_make(pfc_ctx *c) { pfc_out_d2(c, pfc_d2(c)); }
static void pfc_f_pf_depth_moments4_make(pfc_ctx *c) { pfc_out_d4(c, pfc_d4(c)); }
static void pfc_f_pf_evsm_moments_make(pfc_ctx *c) { pf_real a = pfc_evsm_c(c); pfc_out_evsm(c, pfc_evsm(c, a, pfc_evsm_c(c))); }
static void pfc_f_pf_depth_moments2_from_depth(pfc_ctx *c) { pfc_out_d2(c, pf_depth_moments2_from_depth(pfc_u01(c))); }
static void pfc_f_pf_depth_moments4_from_depth(pfc_ctx *c) { pfc_out_d4(c, pf_depth_moments4_from_depth(pfc_u01(c))); }
static void pfc_f_pf_evsm_warp_pos(pfc_ctx *c) { pf_real z = pfc_u01(c); pfc_ge0(c, pf_evsm_warp_pos(z, pfc_evsm_c(c))); }
static void pfc_f_pf_evsm_warp_neg(pfc_ctx *c) { pf_real z = pfc_u01(c); pfc_in(c, pf_evsm_warp_neg(z, pfc_evsm_c(c)), -PF_REAL_MAX, PF_R(0.0)); }
static void pfc_f_pf_evsm2_from_depth(pfc_ctx *c) { pf_real z = pfc_u01(c); pfc_out_d2(c, pf_evsm2_from_depth(z, pfc_evsm_c(c))); }
static void pfc_f_pf_evsm_moments_from_depth(pfc_ctx *c)
{
    pf_real z = pfc_u01(c), a = pfc_evsm_c(c);
    pfc_out_evsm(c, pf_evsm_moments_from_depth(z, a, pfc_evsm_c(c)));
}
/* an ESM exponent: 0 .. 2^12 (documented: any c; the log-space values c z stay finite) */
static pf_real pfc_esm_c(pfc_ctx *c) { return pfc_pos(c, 12); }
static void pfc_f_pf_esm_log_from_depth(pfc_ctx *c) { pf_real z = pfc_u01(c); pfc_out(c, pf_esm_log_from_depth(z, pfc_esm_c(c))); }
static void pfc_f_pf_esm_log_combine2(pfc_ctx *c)
{
    /* logs l = c z of depths, weights >= 0 with w0 + w1 > 0 */
    pf_real cc = pfc_esm_c(c);
    pf_real l0 = cc * pfc_u01(c), l1 = cc * pfc_u01(c), w0 = pfc_u01(c), w1 = pfc_u01(c);
    if (!(w0 + w1 > PF_R(0.0))) w1 = PF_R(1.0);
    pfc_out(c, pf_esm_log_combine2(l0, w0, l1, w1));
}
static void pfc_f_pf_depth_moments2_add(pfc_ctx *c) { pf_depth_moments2 a = pfc_d2(c); pfc_out_d2(c, pf_depth_moments2_add(a, pfc_d2(c))); }
static void pfc_f_pf_depth_moments2_scale(pfc_ctx *c) { pf_depth_moments2 a = pfc_d2(c); pfc_out_d2(c, pf_depth_moments2_scale(a, pfc_u01(c))); }
static void pfc_f_pf_depth_moments4_add(pfc_ctx *c) { pf_depth_moments4 a = pfc_d4(c); pfc_out_d4(c, pf_depth_moments4_add(a, pfc_d4(c))); }
static void pfc_f_pf_depth_moments4_scale(pfc_ctx *c) { pf_depth_moments4 a = pfc_d4(c); pfc_out_d4(c, pf_depth_moments4_scale(a, pfc_u01(c))); }
static pf_evsm_moments pfc_evsm1(pfc_ctx *c) { pf_real a = pfc_evsm_c(c); return pfc_evsm(c, a, pfc_evsm_c(c)); }
static void pfc_f_pf_evsm_moments_add(pfc_ctx *c) { pf_evsm_moments a = pfc_evsm1(c); pfc_out_evsm(c, pf_evsm_moments_add(a, pfc_evsm1(c))); }
static void pfc_f_pf_evsm_moments_scale(pfc_ctx *c) { pf_evsm_moments a = pfc_evsm1(c); pfc_out_evsm(c, pf_evsm_moments_scale(a, pfc_u01(c))); }
static void pfc_f_pf_scalar_moments_make(pfc_ctx *c) { pfc_out_scm(c, pfc_scm(c)); }
static void pfc_f_pf_scalar_moments_from_value(pfc_ctx *c) { pfc_out_scm(c, pf_scalar_moments_from_value(pfc_sym(c, 40))); }
static void pfc_f_pf_scalar_moments_add(pfc_ctx *c) { pf_scalar_moments a = pfc_scm(c); pfc_out_scm(c, pf_scalar_moments_add(a, pfc_scm(c))); }
static void pfc_f_pf_scalar_moments_scale(pfc_ctx *c) { pf_scalar_moments a = pfc_scm(c); pfc_out_scm(c, pf_scalar_moments_scale(a, pfc_u01(c))); }
static void pfc_f_pf_scalar_moments_mean(pfc_ctx *c) { pfc_out(c, pf_scalar_moments_mean(pfc_scm(c))); }
static void pfc_f_pf_scalar_moments_variance(pfc_ctx *c) { pfc_ge0(c, pf_scalar_moments_variance(pfc_scm(c))); }
static void pfc_f_pf_scalar_moments_deviation(pfc_ctx *c) { pfc_ge0(c, pf_scalar_moments_deviation(pfc_scm(c))); }
static void pfc_f_pf_normal_avg_from_normal(pfc_ctx *c) { pfc_unit_vec3(c, pf_normal_avg_from_normal(pfc_dir_any(c))); }
static void pfc_f_pf_normal_avg_from_slope(pfc_ctx *c) { pf_real x = pfc_sym(c, 60); pfc_unit_vec3(c, pf_normal_avg_from_slope(x, pfc_sym(c, 60))); }
static void pfc_f_pf_mip_next_size(pfc_ctx *c)
{
    int n = pfc_int_any(c), r = pf_mip_next_size(n);
    pfc_out(c, PF_R(r));
    pfc_flag(c, r < 0 || (n >= 2 && r != n / 2));
}
static void pfc_f_pf_mip_weights3(pfc_ctx *c)
{
    int j = pfc_int_any(c), n = pfc_int_any(c);
    pf_vec3 w = pf_mip_weights3(j, n);
    pfc_01(c, w.x); pfc_01(c, w.y); pfc_01(c, w.z);
    if (n >= 1 && !(c->bad & 1)) pfc_flag(c, !(PF_FABS(w.x + w.y + w.z - PF_R(1.0)) <= PF_R(4.0) * PF_REAL_EPSILON));
}
/* linear reductions: texels of the type's domain, convex weights */
static void pfc_f_pf_slope_moments_lerp(pfc_ctx *c) { pf_slope_moments a = pfc_moments(c), b = pfc_moments(c); pfc_out_sm(c, pf_slope_moments_lerp(a, b, pfc_u01(c))); }
static void pfc_f_pf_slope_moments_reduce2x2(pfc_ctx *c)
{
    pf_slope_moments a = pfc_moments(c), b = pfc_moments(c), d = pfc_moments(c), e = pfc_moments(c);
    pfc_out_sm(c, pf_slope_moments_reduce2x2(a, b, d, e));
}
static void pfc_f_pf_slope_moments_reduce3(pfc_ctx *c)
{
    pf_slope_moments a = pfc_moments(c), b = pfc_moments(c), d = pfc_moments(c);
    pfc_out_sm(c, pf_slope_moments_reduce3(a, b, d, pfc_w3(c)));
}
static void pfc_f_pf_slope_moments_reduce3x3(pfc_ctx *c)
{
    pf_slope_moments t[9];
    pf_vec3 wx, wy;
    int i;
    for (i = 0; i < 9; ++i) t[i] = pfc_moments(c);
    wx = pfc_w3(c); wy = pfc_w3(c);
    pfc_out_sm(c, pf_slope_moments_reduce3x3(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], wx, wy));
}
static void pfc_f_pf_slope_moments_accumulate(pfc_ctx *c) { pf_slope_moments a = pfc_moments(c), b = pfc_moments(c); pfc_out_sm(c, pf_slope_moments_accumulate(a, b, pfc_u01(c))); }
static void pfc_f_pf_slope_moments_bilinear(pfc_ctx *c)
{
    pf_slope_moments a = pfc_moments(c), b = pfc_moments(c), d = pfc_moments(c), e = pfc_moments(c);
    pf_real fx = pfc_u01(c), fy = pfc_u01(c);
    pfc_out_sm(c, pf_slope_moments_bilinear(a, b, d, e, fx, fy));
}
static void pfc_f_pf_scalar_moments_lerp(pfc_ctx *c) { pf_scalar_moments a = pfc_scm(c), b = pfc_scm(c); pfc_out_scm(c, pf_scalar_moments_lerp(a, b, pfc_u01(c))); }
static void pfc_f_pf_scalar_moments_reduce2x2(pfc_ctx *c)
{
    pf_scalar_moments a = pfc_scm(c), b = pfc_scm(c), d = pfc_scm(c), e = pfc_scm(c);
    pfc_out_scm(c, pf_scalar_moments_reduce2x2(a, b, d, e));
}
static void pfc_f_pf_scalar_moments_reduce3(pfc_ctx *c)
{
    pf_scalar_moments a = pfc_scm(c), b = pfc_scm(c), d = pfc_scm(c);
    pfc_out_scm(c, pf_scalar_moments_reduce3(a, b, d, pfc_w3(c)));
}
static void pfc_f_pf_scalar_moments_reduce3x3(pfc_ctx *c)
{
    pf_scalar_moments t[9];
    pf_vec3 wx, wy;
    int i;
    for (i = 0; i < 9; ++i) t[i] = pfc_scm(c);
    wx = pfc_w3(c); wy = pfc_w3(c);
    pfc_out_scm(c, pf_scalar_moments_reduce3x3(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], wx, wy));
}
static void pfc_f_pf_scalar_moments_accumulate(pfc_ctx *c) { pf_scalar_moments a = pfc_scm(c), b = pfc_scm(c); pfc_out_scm(c, pf_scalar_moments_accumulate(a, b, pfc_u01(c))); }
static void pfc_f_pf_scalar_moments_bilinear(pfc_ctx *c)
{
    pf_scalar_moments a = pfc_scm(c), b = pfc_scm(c), d = pfc_scm(c), e = pfc_scm(c);
    pf_real fx = pfc_u01(c), fy = pfc_u01(c);
    pfc_out_scm(c, pf_scalar_moments_bilinear(a, b, d, e, fx, fy));
}
static void pfc_f_pf_depth_moments2_lerp(pfc_ctx *c) { pf_depth_moments2 a = pfc_d2(c), b = pfc_d2(c); pfc_out_d2(c, pf_depth_moments2_lerp(a, b, pfc_u01(c))); }
static void pfc_f_pf_depth_moments2_reduce2x2(pfc_ctx *c)
{
    pf_depth_moments2 a = pfc_d2(c), b = pfc_d2(c), d = pfc_d2(c), e = pfc_d2(c);
    pfc_out_d2(c, pf_depth_moments2_reduce2x2(a, b, d, e));
}
static void pfc_f_pf_depth_moments2_reduce3(pfc_ctx *c)
{
    pf_depth_moments2 a = pfc_d2(c), b = pfc_d2(c), d = pfc_d2(c);
    pfc_out_d2(c, pf_depth_moments2_reduce3(a, b, d, pfc_w3(c)));
}
static void pfc_f_pf_depth_moments2_reduce3x3(pfc_ctx *c)
{
    pf_depth_moments2 t[9];
    pf_vec3 wx, wy;
    int i;
    for (i = 0; i < 9; ++i) t[i] = pfc_d2(c);
    wx = pfc_w3(c); wy = pfc_w3(c);
    pfc_out_d2(c, pf_depth_moments2_reduce3x3(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], wx, wy));
}
static void pfc_f_pf_depth_moments2_accumulate(pfc_ctx *c) { pf_depth_moments2 a = pfc_d2(c), b = pfc_d2(c); pfc_out_d2(c, pf_depth_moments2_accumulate(a, b, pfc_u01(c))); }
static void pfc_f_pf_depth_moments2_bilinear(pfc_ctx *c)
{
    pf_depth_moments2 a = pfc_d2(c), b = pfc_d2(c), d = pfc_d2(c), e = pfc_d2(c);
    pf_real fx = pfc_u01(c), fy = pfc_u01(c);
    pfc_out_d2(c, pf_depth_moments2_bilinear(a, b, d, e, fx, fy));
}
static void pfc_f_pf_depth_moments4_lerp(pfc_ctx *c) { pf_depth_moments4 a = pfc_d4(c), b = pfc_d4(c); pfc_out_d4(c, pf_depth_moments4_lerp(a, b, pfc_u01(c))); }
static void pfc_f_pf_depth_moments4_reduce2x2(pfc_ctx *c)
{
    pf_depth_moments4 a = pfc_d4(c), b = pfc_d4(c), d = pfc_d4(c), e = pfc_d4(c);
    pfc_out_d4(c, pf_depth_moments4_reduce2x2(a, b, d, e));
}
static void pfc_f_pf_depth_moments4_reduce3(pfc_ctx *c)
{
    pf_depth_moments4 a = pfc_d4(c), b = pfc_d4(c), d = pfc_d4(c);
    pfc_out_d4(c, pf_depth_moments4_reduce3(a, b, d, pfc_w3(c)));
}
static void pfc_f_pf_depth_moments4_reduce3x3(pfc_ctx *c)
{
    pf_depth_moments4 t[9];
    pf_vec3 wx, wy;
    int i;
    for (i = 0; i < 9; ++i) t[i] = pfc_d4(c);
    wx = pfc_w3(c); wy = pfc_w3(c);
    pfc_out_d4(c, pf_depth_moments4_reduce3x3(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], wx, wy));
}
static void pfc_f_pf_depth_moments4_accumulate(pfc_ctx *c) { pf_depth_moments4 a = pfc_d4(c), b = pfc_d4(c); pfc_out_d4(c, pf_depth_moments4_accumulate(a, b, pfc_u01(c))); }
static void pfc_f_pf_depth_moments4_bilinear(pfc_ctx *c)
{
    pf_depth_moments4 a = pfc_d4(c), b = pfc_d4(c), d = pfc_d4(c), e = pfc_d4(c);
    pf_real fx = pfc_u01(c), fy = pfc_u01(c);
    pfc_out_d4(c, pf_depth_moments4_bilinear(a, b, d, e, fx, fy));
}
static void pfc_f_pf_evsm_moments_lerp(pfc_ctx *c) { pf_evsm_moments a = pfc_evsm1(c), b = pfc_evsm1(c); pfc_out_evsm(c, pf_evsm_moments_lerp(a, b, pfc_u01(c))); }
static void pfc_f_pf_evsm_moments_reduce2x2(pfc_ctx *c)
{
    pf_evsm_moments a = pfc_evsm1(c), b = pfc_evsm1(c), d = pfc_evsm1(c), e = pfc_evsm1(c);
    pfc_out_evsm(c, pf_evsm_moments_reduce2x2(a, b, d, e));
}
static void pfc_f_pf_evsm_moments_reduce3(pfc_ctx *c)
{
    pf_evsm_moments a = pfc_evsm1(c), b = pfc_evsm1(c), d = pfc_evsm1(c);
    pfc_out_evsm(c, pf_evsm_moments_reduce3(a, b, d, pfc_w3(c)));
}
static void pfc_f_pf_evsm_moments_reduce3x3(pfc_ctx *c)
{
    pf_evsm_moments t[9];
    pf_vec3 wx, wy;
    int i;
    for (i = 0; i < 9; ++i) t[i] = pfc_evsm1(c);
    wx = pfc_w3(c); wy = pfc_w3(c);
    pfc_out_evsm(c, pf_evsm_moments_reduce3x3(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], wx, wy));
}
static void pfc_f_pf_evsm_moments_accumulate(pfc_ctx *c) { pf_evsm_moments a = pfc_evsm1(c), b = pfc_evsm1(c); pfc_out_evsm(c, pf_evsm_moments_accumulate(a, b, pfc_u01(c))); }
static void pfc_f_pf_evsm_moments_bilinear(pfc_ctx *c)
{
    pf_evsm_moments a = pfc_evsm1(c), b = pfc_evsm1(c), d = pfc_evsm1(c), e = pfc_evsm1(c);
    pf_real fx = pfc_u01(c), fy = pfc_u01(c);
    pfc_out_evsm(c, pf_evsm_moments_bilinear(a, b, d, e, fx, fy));
}
static void pfc_f_pf_normal_avg_lerp(pfc_ctx *c) { pf_vec3 a = pfc_navg(c), b = pfc_navg(c); pfc_out_vec3(c, pf_normal_avg_lerp(a, b, pfc_u01(c))); }
static void pfc_f_pf_normal_avg_reduce2x2(pfc_ctx *c)
{
    pf_vec3 a = pfc_navg(c), b = pfc_navg(c), d = pfc_navg(c), e = pfc_navg(c);
    pfc_out_vec3(c, pf_normal_avg_reduce2x2(a, b, d, e));
}
static void pfc_f_pf_normal_avg_reduce3(pfc_ctx *c)
{
    pf_vec3 a = pfc_navg(c), b = pfc_navg(c), d = pfc_navg(c);
    pfc_out_vec3(c, pf_normal_avg_reduce3(a, b, d, pfc_w3(c)));
}
static void pfc_f_pf_normal_avg_reduce3x3(pfc_ctx *c)
{
    pf_vec3 t[9], wx, wy;
    int i;
    for (i = 0; i < 9; ++i) t[i] = pfc_navg(c);
    wx = pfc_w3(c); wy = pfc_w3(c);
    pfc_out_vec3(c, pf_normal_avg_reduce3x3(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], wx, wy));
}
static void pfc_f_pf_normal_avg_accumulate(pfc_ctx *c) { pf_vec3 a = pfc_navg(c), b = pfc_navg(c); pfc_out_vec3(c, pf_normal_avg_accumulate(a, b, pfc_u01(c))); }
static void pfc_f_pf_normal_avg_bilinear(pfc_ctx *c)
{
    pf_vec3 a = pfc_navg(c), b = pfc_navg(c), d = pfc_navg(c), e = pfc_navg(c);
    pf_real fx = pfc_u01(c), fy = pfc_u01(c);
    pfc_out_vec3(c, pf_normal_avg_bilinear(a, b, d, e, fx, fy));
}
/* ESM log texels: c z with c up to 2^12, and -PF_REAL_MAX (an empty sum) */
static pf_real pfc_esm_l(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    pf_real z, k;
    if (c->raw) return pfc_keep(c, pfc_from_bits(u));
    if (PFC_R(u) == 0) return pfc_keep(c, -PF_REAL_MAX);
    z = pfc_unif(PFC_B(u));
    k = PFC_R(u) < 8 ? PF_R(80.0) : pfc_p2((int)(PFC_B(u) % 13u));
    return pfc_keep(c, k * z);
}
static void pfc_f_pf_lse_arg(pfc_ctx *c) { pfc_in(c, pf_lse_arg(pfc_sym(c, 40)), PF_LSE_ARG_MIN, PF_REAL_MAX); }
static void pfc_f_pf_esm_log_reduce2x2(pfc_ctx *c)
{
    pf_real a = pfc_esm_l(c), b = pfc_esm_l(c), d = pfc_esm_l(c), e = pfc_esm_l(c);
    pfc_out(c, pf_esm_log_reduce2x2(a, b, d, e));
}
static void pfc_f_pf_esm_log_reduce3(pfc_ctx *c)
{
    pf_real a = pfc_esm_l(c), b = pfc_esm_l(c), d = pfc_esm_l(c);
    pfc_out(c, pf_esm_log_reduce3(a, b, d, pfc_w3(c)));
}
static void pfc_f_pf_esm_log_reduce3x3(pfc_ctx *c)
{
    pf_real t[9];
    pf_vec3 wx, wy;
    int i;
    for (i = 0; i < 9; ++i) t[i] = pfc_esm_l(c);
    wx = pfc_w3(c); wy = pfc_w3(c);
    pfc_out(c, pf_esm_log_reduce3x3(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], wx, wy));
}
static void pfc_f_pf_esm_log_bilinear(pfc_ctx *c)
{
    pf_real a = pfc_esm_l(c), b = pfc_esm_l(c), d = pfc_esm_l(c), e = pfc_esm_l(c);
    pf_real fx = pfc_u01(c), fy = pfc_u01(c);
    pfc_out(c, pf_esm_log_bilinear(a, b, d, e, fx, fy));
}
static pf_esm_log_sum pfc_lsum(pfc_ctx *c)
{
    pf_esm_log_sum a = pf_esm_log_sum_first(pfc_esm_l(c), pfc_u01(c));
    a = pf_esm_log_sum_add(a, pfc_esm_l(c), pfc_u01(c));
    return a;
}
static void pfc_out_lsum(pfc_ctx *c, pf_esm_log_sum a) { pfc_out(c, a.lmax); pfc_ge0(c, a.sum); pfc_ge0(c, a.weight); }
static void pfc_f_pf_esm_log_sum_make(pfc_ctx *c) { pfc_out_lsum(c, pfc_lsum(c)); }
static void pfc_f_pf_esm_log_sum_first(pfc_ctx *c) { pf_real l = pfc_esm_l(c); pfc_out_lsum(c, pf_esm_log_sum_first(l, pfc_u01(c))); }
static void pfc_f_pf_esm_log_sum_add(pfc_ctx *c)
{
    pf_esm_log_sum a = pfc_lsum(c);
    pf_real l = pfc_esm_l(c);
    pfc_out_lsum(c, pf_esm_log_sum_add(a, l, pfc_u01(c)));
}
static void pfc_f_pf_esm_log_sum_mean(pfc_ctx *c) { pfc_out(c, pf_esm_log_sum_mean(pfc_lsum(c))); }
static void pfc_f_pf_height_slope_central(pfc_ctx *c)
{
    pf_real a = pfc_sym(c, 20), b = pfc_sym(c, 20);
    pfc_out(c, pf_height_slope_central(a, b, pfc_mag(pfc_next(c) & 0x0FFFFFFFu, -20, 20)));
}
static void pfc_f_pf_height_slope_edge(pfc_ctx *c)
{
    pf_real a = pfc_sym(c, 20), b = pfc_sym(c, 20), d = pfc_sym(c, 20);
    pfc_out(c, pf_height_slope_edge(a, b, d, pfc_mag(pfc_next(c) & 0x0FFFFFFFu, -20, 20)));
}
static void pfc_f_pf_slope_moments_from_heights(pfc_ctx *c)
{
    pf_real a = pfc_sym(c, 20), b = pfc_sym(c, 20), d = pfc_sym(c, 20), e = pfc_sym(c, 20);
    pf_real tx = pfc_mag(pfc_next(c) & 0x0FFFFFFFu, -20, 20), ty = pfc_mag(pfc_next(c) & 0x0FFFFFFFu, -20, 20);
    pfc_out_sm(c, pf_slope_moments_from_heights(a, b, d, e, pfc_keep(c, tx), pfc_keep(c, ty), pfc_sym(c, 4)));
}

/* ---- toksvig */
/* an averaged normal's length: (0, 1], 0, tiny, and slightly above 1 (interpolation) */
static pf_real pfc_len(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    if (!c->raw && PFC_R(u) == 1) return pfc_keep(c, PF_R(1.0) + pfc_mag(PFC_B(u), -24, -4));
    {
        pf_real x;
        if (pfc_front(c, u, &x)) return pfc_keep(c, x);
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 2: x = pfc_mag(PFC_B(u), PFC_EMIN, -14); break;
        case 3: x = PF_R(1.0); break;
        default: x = pfc_unif(PFC_B(u)); break;
        }
        return pfc_keep(c, x);
    }
}
/* a Blinn-Phong exponent: 0, tiny, [1, 2^20], huge */
static pf_real pfc_alpha(pfc_ctx *c) { return pfc_pos(c, 40); }
static void pfc_f_pf_toksvig_variance(pfc_ctx *c) { pfc_in(c, pf_toksvig_variance(pfc_len(c)), PF_R(0.0), PF_R(9999.0) * (PF_R(1.0) + PF_R(8.0) * PF_REAL_EPSILON)); }
static void pfc_f_pf_toksvig_variance_from_normal(pfc_ctx *c)
{
    pf_vec3 d = pfc_dir(c);
    pfc_in(c, pf_toksvig_variance_from_normal(pf_vec3_scale(d, pfc_len(c))), PF_R(0.0), PF_R(9999.0) * (PF_R(1.0) + PF_R(8.0) * PF_REAL_EPSILON));
}
static void pfc_f_pf_toksvig_factor(pfc_ctx *c) { pf_real l = pfc_len(c); pfc_01(c, pf_toksvig_factor(l, pfc_alpha(c))); }
static void pfc_f_pf_toksvig_exponent(pfc_ctx *c)
{
    pf_real a = pfc_alpha(c), v = pfc_var(c, 1);
    pfc_in(c, pf_toksvig_exponent(a, v), PF_R(0.0), pf_max(a, PF_R(0.0)));
}
static void pfc_f_pf_toksvig_normalization(pfc_ctx *c)
{
    pf_real a = pfc_alpha(c), v = pfc_var(c, 1);
    pfc_01(c, pf_toksvig_normalization(a, pf_toksvig_exponent(a, v))); /* alpha' <= alpha */
}
static void pfc_f_pf_toksvig_lobe(pfc_ctx *c)
{
    pf_real ct = pfc_cos(c), a = pfc_alpha(c), v = pfc_var(c, 1);
    pfc_01(c, pf_toksvig_lobe(ct, a, v));
}
static void pfc_f_pf_toksvig_beckmann_m(pfc_ctx *c) { pf_real m = pfc_pos(c, 10); pfc_ge0(c, pf_toksvig_beckmann_m(m, pfc_var(c, 1))); }
static void pfc_f_pf_toksvig_ggx_alpha(pfc_ctx *c) { pf_real m = pfc_pos(c, 10); pfc_ge0(c, pf_toksvig_ggx_alpha(m, pfc_var(c, 1))); }
static void pfc_f_pf_blinn_phong_to_beckmann(pfc_ctx *c) { pfc_in(c, pf_blinn_phong_to_beckmann(pfc_sym(c, 100)), PF_R(0.0), PF_R(1.0)); }
static void pfc_f_pf_beckmann_to_blinn_phong(pfc_ctx *c) { pfc_ge0(c, pf_beckmann_to_blinn_phong(pfc_sym(c, 20))); }

/* ---- shadow */
static void pfc_f_pf_shadow_chebyshev_upper(pfc_ctx *c)
{
    pf_real m1 = pfc_sym(c, 60), m2 = pfc_pos(c, 120), x = pfc_sym(c, 60);
    pfc_01(c, pf_shadow_chebyshev_upper(m1, m2, x, pfc_var(c, 0)));
}
static void pfc_f_pf_shadow_reduce_bleeding(pfc_ctx *c) { pf_real l = pfc_u01(c); pfc_01(c, pf_shadow_reduce_bleeding(l, pfc_u01(c))); }
static void pfc_f_pf_shadow_vsm(pfc_ctx *c)
{
    pf_depth_moments2 m = pfc_d2(c);
    pf_real d = pfc_u01(c), mv = pfc_var(c, 0);
    pfc_01(c, pf_shadow_vsm(m, d, mv, pfc_u01(c)));
}
static void pfc_f_pf_shadow_esm(pfc_ctx *c)
{
    pf_real cc = pfc_esm_c(c), l = pfc_esm_l(c);
    pf_real d = pfc_u01(c);
    pfc_01(c, pf_shadow_esm(l, d, cc));
}
static void pfc_f_pf_shadow_evsm2(pfc_ctx *c)
{
    pf_real cp = pfc_evsm_c(c);
    pf_evsm_moments e = pfc_evsm(c, cp, cp);
    pf_real d = pfc_u01(c), mv = pfc_var(c, 0);
    pfc_01(c, pf_shadow_evsm2(pf_depth_moments2_make(e.pos1, e.pos2), d, cp, mv, pfc_u01(c)));
}
static void pfc_f_pf_shadow_evsm4(pfc_ctx *c)
{
    pf_real cp = pfc_evsm_c(c), cn = pfc_evsm_c(c);
    pf_evsm_moments e = pfc_evsm(c, cp, cn);
    pf_real d = pfc_u01(c), mv = pfc_var(c, 0);
    pfc_01(c, pf_shadow_evsm4(e, d, cp, cn, mv, pfc_u01(c)));
}
static void pfc_f_pf_shadow_msm_bounds(pfc_ctx *c)
{
    pf_depth_moments4 m = pfc_d4(c);
    pf_real d = pfc_u01(c), a = pfc_u01(c), db = pfc_sym(c, -4);
    pf_vec2 r = pf_shadow_msm_bounds(m, d, a, db);
    pfc_01(c, r.x); pfc_01(c, r.y);
    pfc_flag(c, !(r.x <= r.y));
}
static void pfc_f_pf_shadow_msm(pfc_ctx *c)
{
    pf_depth_moments4 m = pfc_d4(c);
    pf_real d = pfc_u01(c), a = pfc_u01(c), db = pfc_sym(c, -4);
    pfc_01(c, pf_shadow_msm(m, d, a, db));
}
static void pfc_f_pf_shadow_msm_hausdorff(pfc_ctx *c)
{
    pf_depth_moments4 m = pfc_d4(c);
    pf_real d = pfc_u01(c), a = pfc_u01(c), db = pfc_sym(c, -4);
    pfc_01(c, pf_shadow_msm_hausdorff(m, d, a, db));
}
/* 64-bit MSM: the stored values of the same moments (q = Theta b + o), as the sampler returns them */
static void pfc_f_pf_msm_quantize_moments(pfc_ctx *c) { pfc_out_d4(c, pf_msm_quantize_moments(pfc_d4(c))); }
static void pfc_f_pf_msm_dequantize_moments(pfc_ctx *c)
{
    pfc_out_d4(c, pf_msm_dequantize_moments(pf_msm_quantize_moments(pfc_d4(c))));
}
static void pfc_f_pf_shadow_msm16(pfc_ctx *c)
{
    pf_depth_moments4 q = pf_msm_quantize_moments(pfc_d4(c));
    pf_real d = pfc_u01(c), a = pfc_u01(c), db = pfc_sym(c, -4);
    pfc_01(c, pf_shadow_msm16(q, d, a, db));
}
static void pfc_f_pf_shadow_msm16_hausdorff(pfc_ctx *c)
{
    pf_depth_moments4 q = pf_msm_quantize_moments(pfc_d4(c));
    pf_real d = pfc_u01(c), a = pfc_u01(c), db = pfc_sym(c, -4);
    pfc_01(c, pf_shadow_msm16_hausdorff(q, d, a, db));
}

/* ---- CSM (helper L, issue 16): pf_moments.h pairs, pf_shadow.h series */
/* The pair j of a two-depth mixture (all zero in 1 of 16 regimes: an empty footprint). */
static pf_csm_pair pfc_csm_pair(pfc_ctx *c, int j)
{
    pf_real z0 = pfc_u01(c), z1 = pfc_u01(c), t = pfc_u01(c);
    pfc_u32 u = pfc_next(c);
    if (c->raw) return pf_csm_pair_make(z0, z1, t, pfc_from_bits(u));
    if (PFC_R(u) == 0) return pf_csm_pair_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    return pf_csm_pair_add(pf_csm_pair_scale(pf_csm_pair_from_depth(z0, j), PF_R(1.0) - t),
                           pf_csm_pair_scale(pf_csm_pair_from_depth(z1, j), t));
}
static pf_csm_pair pfc_csm1(pfc_ctx *c) { return pfc_csm_pair(c, pfc_int(c, 0, 7)); }
static void pfc_out_csm(pfc_ctx *c, pf_csm_pair m)
{ pfc_out(c, m.cos_a); pfc_out(c, m.sin_a); pfc_out(c, m.cos_b); pfc_out(c, m.sin_b); }
static void pfc_f_pf_csm_pair_make(pfc_ctx *c) { pfc_out_csm(c, pfc_csm1(c)); }
static void pfc_f_pf_csm_pair_from_depth(pfc_ctx *c)
{
    pf_real z = pfc_u01(c);
    pf_csm_pair p = pf_csm_pair_from_depth(z, pfc_int(c, -1, 40));
    pfc_in(c, p.cos_a, PF_R(-1.0), PF_R(1.0)); pfc_in(c, p.sin_a, PF_R(-1.0), PF_R(1.0));
    pfc_in(c, p.cos_b, PF_R(-1.0), PF_R(1.0)); pfc_in(c, p.sin_b, PF_R(-1.0), PF_R(1.0));
}
static void pfc_f_pf_csm_pair_add(pfc_ctx *c) { pf_csm_pair a = pfc_csm1(c); pfc_out_csm(c, pf_csm_pair_add(a, pfc_csm1(c))); }
static void pfc_f_pf_csm_pair_scale(pfc_ctx *c) { pf_csm_pair a = pfc_csm1(c); pfc_out_csm(c, pf_csm_pair_scale(a, pfc_u01(c))); }
static void pfc_f_pf_csm_pair_lerp(pfc_ctx *c) { pf_csm_pair a = pfc_csm1(c), b = pfc_csm1(c); pfc_out_csm(c, pf_csm_pair_lerp(a, b, pfc_u01(c))); }
static void pfc_f_pf_csm_pair_reduce2x2(pfc_ctx *c)
{
    pf_csm_pair a = pfc_csm1(c), b = pfc_csm1(c), d = pfc_csm1(c), e = pfc_csm1(c);
    pfc_out_csm(c, pf_csm_pair_reduce2x2(a, b, d, e));
}
static void pfc_f_pf_csm_pair_reduce3(pfc_ctx *c)
{
    pf_csm_pair a = pfc_csm1(c), b = pfc_csm1(c), d = pfc_csm1(c);
    pfc_out_csm(c, pf_csm_pair_reduce3(a, b, d, pfc_w3(c)));
}
static void pfc_f_pf_csm_pair_reduce3x3(pfc_ctx *c)
{
    pf_csm_pair t[9];
    pf_vec3 wx, wy;
    int i;
    for (i = 0; i < 9; ++i) t[i] = pfc_csm1(c);
    wx = pfc_w3(c); wy = pfc_w3(c);
    pfc_out_csm(c, pf_csm_pair_reduce3x3(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], wx, wy));
}
static void pfc_f_pf_csm_pair_accumulate(pfc_ctx *c) { pf_csm_pair a = pfc_csm1(c), b = pfc_csm1(c); pfc_out_csm(c, pf_csm_pair_accumulate(a, b, pfc_u01(c))); }
static void pfc_f_pf_csm_pair_bilinear(pfc_ctx *c)
{
    pf_csm_pair a = pfc_csm1(c), b = pfc_csm1(c), d = pfc_csm1(c), e = pfc_csm1(c);
    pf_real fx = pfc_u01(c), fy = pfc_u01(c);
    pfc_out_csm(c, pf_csm_pair_bilinear(a, b, d, e, fx, fy));
}
/* A series after `terms` harmonics of one footprint (pairs of the same mixture regime). */
static pf_csm_sum pfc_csm_sum(pfc_ctx *c, pf_real d, pf_real offset, int terms)
{
    pf_csm_sum a = pf_csm_sum_begin(d, offset);
    int j;
    for (j = 0; 2 * j < terms; ++j) a = pf_csm_sum_add(a, pfc_csm_pair(c, j));
    return a;
}
static void pfc_out_csm_sum(pfc_ctx *c, pf_csm_sum a)
{
    pfc_out(c, a.value); pfc_in(c, a.cos_k, PF_R(-1.01), PF_R(1.01)); pfc_in(c, a.sin_k, PF_R(-1.01), PF_R(1.01));
    pfc_in(c, a.cos_step, PF_R(-1.01), PF_R(1.01)); pfc_in(c, a.sin_step, PF_R(-1.01), PF_R(1.01)); pfc_out(c, a.freq);
}
static void pfc_f_pf_csm_sum_begin(pfc_ctx *c) { pf_real d = pfc_u01(c); pfc_out_csm_sum(c, pf_csm_sum_begin(d, pfc_u01(c))); }
static void pfc_f_pf_csm_sum_make(pfc_ctx *c)
{
    pf_real d = pfc_u01(c), o = pfc_u01(c);
    pf_csm_sum a = pf_csm_sum_begin(d, o);
    pfc_out_csm_sum(c, pf_csm_sum_make(a.value, a.cos_k, a.sin_k, a.cos_step, a.sin_step, a.freq));
}
static void pfc_f_pf_csm_sum_add_harmonic(pfc_ctx *c)
{
    pf_real d = pfc_u01(c), o = pfc_u01(c), cz = pfc_sym(c, 0);
    pfc_out_csm_sum(c, pf_csm_sum_add_harmonic(pf_csm_sum_begin(d, o), cz, pfc_sym(c, 0)));
}
static void pfc_f_pf_csm_sum_add(pfc_ctx *c)
{
    pf_real d = pfc_u01(c), o = pfc_u01(c);
    pfc_out_csm_sum(c, pfc_csm_sum(c, d, o, 2 * pfc_int(c, 1, 16)));
}
static void pfc_f_pf_csm_sum_lit(pfc_ctx *c)
{
    pf_real d = pfc_u01(c), o = pfc_sym(c, -3), s = pfc_sym(c, 4);
    pfc_01(c, pf_csm_sum_lit(pfc_csm_sum(c, d, o, 2 * pfc_int(c, 1, 16)), s));
}
static void pfc_f_pf_shadow_csm(pfc_ctx *c)
{
    pf_csm_moments m;
    pf_real d = pfc_sym(c, 1), o = pfc_sym(c, -3), s = pfc_sym(c, 4);
    m.p0 = pfc_csm_pair(c, 0); m.p1 = pfc_csm_pair(c, 1); m.p2 = pfc_csm_pair(c, 2); m.p3 = pfc_csm_pair(c, 3);
    m.p4 = pfc_csm_pair(c, 4); m.p5 = pfc_csm_pair(c, 5); m.p6 = pfc_csm_pair(c, 6); m.p7 = pfc_csm_pair(c, 7);
    pfc_01(c, pf_shadow_csm(m, d, pfc_int(c, -2, 20), s, o));
}

/* ---- gaussgrid */
static void pfc_f_pf_gg_node(pfc_ctx *c)
{
    int set = pfc_int(c, -1, 3), n = pfc_int(c, -2, 12), j = pfc_int_any(c);
    pf_real p = pf_gg_node(set, n, j);
    int m = n < 1 ? 1 : (n > PF_GG_MAX_N ? PF_GG_MAX_N : n);
    pfc_in(c, p, PF_R(-10.0), PF_R(10.0));
    pfc_flag(c, (j < 0 || j >= m) && p != PF_R(0.0)); /* documented: j outside the range gives 0 */
}
static void pfc_f_pf_gg_weight(pfc_ctx *c)
{
    int set = pfc_int(c, -1, 3), n = pfc_int(c, -2, 12), j = pfc_int_any(c);
    pfc_01(c, pf_gg_weight(set, n, j));
}
static void pfc_f_pf_gg_node_variance(pfc_ctx *c)
{
    int set = pfc_int(c, -1, 3), n = pfc_int(c, -2, 12);
    pfc_in(c, pf_gg_node_variance(set, n), PF_R(0.0), PF_R(1.0) + PF_R(64.0) * PF_REAL_EPSILON);
}
static void pfc_f_pf_gg_uniform_lambda(pfc_ctx *c) { pfc_ge0(c, pf_gg_uniform_lambda(pfc_int_any(c))); }
static void pfc_f_pf_gg_uniform_node_any(pfc_ctx *c)
{
    int n = pfc_int(c, -2, 64), j = pfc_int(c, -2, 66);
    pfc_out(c, pf_gg_uniform_node_any(n, pfc_pos(c, 4), j));
}
static void pfc_f_pf_gg_uniform_weight_any(pfc_ctx *c)
{
    int n = pfc_int(c, -2, 64), j = pfc_int(c, -2, 66);
    pfc_01(c, pf_gg_uniform_weight_any(n, pfc_pos(c, 4), j));
}
static void pfc_f_pf_gg_uniform_variance_any(pfc_ctx *c)
{
    int n = pfc_int(c, -2, 64);
    pfc_ge0(c, pf_gg_uniform_variance_any(n, pfc_pos(c, 4)));
}
static void pfc_out_grid(pfc_ctx *c, pf_gg_grid g)
{
    pfc_out_vec3(c, g.wo);
    pfc_out_stats(c, g.stats);
    pfc_ge0(c, g.sigma_x); pfc_ge0(c, g.sigma_y);
    pfc_in(c, g.corr, PF_R(-1.0), PF_R(1.0)); pfc_01(c, g.corr_c);
    pfc_ge0(c, g.inv_proj); pfc_01(c, g.g1_o);
}
static void pfc_f_pf_gg_grid_make(pfc_ctx *c) { pfc_out_grid(c, pfc_grid(c)); }
static void pfc_f_pf_gg_grid_count(pfc_ctx *c)
{
    int k = pf_gg_grid_count(pfc_grid(c));
    pfc_out(c, PF_R(k));
    pfc_flag(c, k < 1 || k > PF_GG_MAX_N * PF_GG_MAX_N);
}
static void pfc_out_sample(pfc_ctx *c, pf_gg_sample s)
{
    pfc_out(c, s.slope_x); pfc_out(c, s.slope_y); pfc_01(c, s.weight);
    pfc_unit_vec3(c, s.normal); pfc_ge0(c, s.proj); pfc_ge0(c, s.cell);
}
static void pfc_f_pf_gg_sample_nodes(pfc_ctx *c)
{
    pf_gg_grid g = pfc_grid(c);
    pf_real pj = pfc_sym(c, 3), wj = pfc_u01(c), pk = pfc_sym(c, 3);
    pfc_out_sample(c, pf_gg_sample_nodes(g, pj, wj, pk, pfc_u01(c)));
}
static void pfc_f_pf_gg_sample_at(pfc_ctx *c)
{
    pf_gg_grid g = pfc_grid(c);
    pfc_out_sample(c, pf_gg_sample_at(g, pfc_int_any(c)));
}
static void pfc_f_pf_gg_jacobian(pfc_ctx *c) { pf_vec3 a = pfc_dir(c); pfc_ge0(c, pf_gg_jacobian(a, pfc_dir(c))); }
static void pfc_f_pf_gg_env_sample_at(pfc_ctx *c)
{
    pf_gg_grid g = pfc_grid(c);
    pf_gg_env_sample e = pf_gg_env_sample_at(g, pfc_int_any(c));
    pfc_out_vec3(c, e.dir); pfc_ge0(c, e.weight); pfc_01(c, e.cos_d); pfc_ge0(c, e.solid_angle);
}
static void pfc_f_pf_gg_env_lod(pfc_ctx *c)
{
    pf_real a = pfc_pos(c, 40), t = pfc_mag(pfc_next(c) & 0x0FFFFFFFu, -40, 4);
    pfc_ge0(c, pf_gg_env_lod(a, pfc_keep(c, t)));
}
static void pfc_f_pf_sh9_make(pfc_ctx *c) { pfc_out_sh9(c, pfc_sh9(c)); }
static void pfc_f_pf_sh9_constant(pfc_ctx *c) { pfc_out_sh9(c, pf_sh9_constant(pfc_sym(c, 40))); }
static void pfc_f_pf_sh9_add_scaled(pfc_ctx *c) { pf_sh9 a = pfc_sh9(c), b = pfc_sh9(c); pfc_out_sh9(c, pf_sh9_add_scaled(a, b, pfc_sym(c, 10))); }
static void pfc_f_pf_sh9_add_directional(pfc_ctx *c)
{
    pf_sh9 a = pfc_sh9(c);
    pf_vec3 d = pfc_dir(c);
    pfc_out_sh9(c, pf_sh9_add_directional(a, d, pfc_pos(c, 20)));
}
static void pfc_f_pf_sh9_irradiance(pfc_ctx *c) { pf_sh9 a = pfc_sh9(c); pfc_out(c, pf_sh9_irradiance(a, pfc_dir(c))); }
static void pfc_f_pf_gg_sh9_add_light(pfc_ctx *c)
{
    pf_sh9 a = pfc_sh9(c);
    pf_gg_grid g = pfc_grid(c);
    pf_vec3 d = pfc_dir(c);
    pfc_out_sh9(c, pf_gg_sh9_add_light(a, g, d, pfc_pos(c, 20)));
}
static void pfc_f_pf_gg_sh9_add_environment(pfc_ctx *c)
{
    pf_sh9 a = pfc_sh9(c);
    pf_gg_grid g = pfc_grid(c);
    pfc_out_sh9(c, pf_gg_sh9_add_environment(a, g, pfc_sh9(c)));
}
static void pfc_f_pf_gg_diffuse_sh(pfc_ctx *c) { pf_gg_grid g = pfc_grid(c); pfc_out(c, pf_gg_diffuse_sh(g, pfc_sh9(c))); }
static void pfc_f_pf_gg_diffuse_sh_rgb(pfc_ctx *c)
{
    pf_gg_grid g = pfc_grid(c);
    pf_sh9 r = pfc_sh9(c), gg = pfc_sh9(c), b = pfc_sh9(c);
    pfc_out_vec3(c, pf_gg_diffuse_sh_rgb(g, r, gg, b));
}
static void pfc_f_pf_gg_diffuse_directional(pfc_ctx *c)
{
    pf_gg_grid g = pfc_grid(c);
    pf_vec3 wi = pfc_dir(c);
    pf_real v = pf_gg_diffuse_directional(g, wi);
    /* radiance per unit irradiance and albedo, a fraction of 1/pi times the projection */
    pfc_ge0(c, v);
}

/* ---- height */
static void pfc_f_pf_height_pdf(pfc_ctx *c) { pfc_in(c, pf_height_pdf(pfc_sym(c, 100)), PF_R(0.0), PF_R(0.3989422805)); }
static void pfc_f_pf_height_cdf(pfc_ctx *c) { pfc_01(c, pf_height_cdf(pfc_sym(c, 100))); }
static void pfc_f_pf_height_log_cdf(pfc_ctx *c) { pfc_in(c, pf_height_log_cdf(pfc_sym(c, 100)), -PF_REAL_MAX, PF_R(0.0)); }
static void pfc_f_pf_height_visibility(pfc_ctx *c) { pf_real z = pfc_sym(c, 12); pfc_01(c, pf_height_visibility(z, pfc_lambda(c))); }
static void pfc_f_pf_height_mean_visibility(pfc_ctx *c) { pf_real a = pfc_lambda(c); pfc_01(c, pf_height_mean_visibility(a, pfc_lambda(c))); }
static void pfc_f_pf_height_joint_visibility(pfc_ctx *c) { pf_real a = pfc_lambda(c); pfc_01(c, pf_height_joint_visibility(a, pfc_lambda(c))); }
static void pfc_f_pf_height_attribute_mean(pfc_ctx *c)
{
    pf_real a0 = pfc_sym(c, 20), am = pfc_sym(c, 20), lo = pfc_lambda(c), li = pfc_lambda(c);
    pfc_out(c, pf_height_attribute_mean(a0, am, lo, li));
}
static void pfc_f_pf_height_dist_make(pfc_ctx *c) { pf_real m = pfc_sym(c, 20); pfc_out_hd(c, pf_height_dist_make(m, pfc_pos(c, 20))); }
static void pfc_f_pf_visible_height_published(pfc_ctx *c) { pfc_out_hd(c, pf_visible_height_published(pfc_lambda(c))); }
static void pfc_f_pf_visible_height(pfc_ctx *c) { pfc_out_hd(c, pf_visible_height(pfc_lambda(c))); }
static void pfc_f_pf_visible_height_exact(pfc_ctx *c) { pfc_out_hd(c, pf_visible_height_exact(pfc_lambda(c))); }
static void pfc_f_pf_height_dist_rescale(pfc_ctx *c)
{
    pf_height_dist d = pf_visible_height(pfc_lambda(c));
    pf_real m = pfc_sym(c, 20);
    pfc_out_hd(c, pf_height_dist_rescale(d, m, pfc_pos(c, 20)));
}
static void pfc_f_pf_height_dist_add_noise(pfc_ctx *c)
{
    pf_height_dist d = pf_visible_height(pfc_lambda(c));
    pf_real m = pfc_sym(c, 20);
    pfc_out_hd(c, pf_height_dist_add_noise(d, m, pfc_pos(c, 20)));
}
static void pfc_f_pf_height_colour_dist(pfc_ctx *c)
{
    pf_real lo = pfc_lambda(c), li = pfc_lambda(c), mh = pfc_sym(c, 20), sh = pfc_pos(c, 20);
    pf_real mr = pfc_sym(c, 20), sr = pfc_pos(c, 20);
    pfc_out_hd(c, pf_height_colour_dist(lo, li, mh, sh, mr, sr));
}
static void pfc_f_pf_gauss_cdf(pfc_ctx *c)
{
    pf_real x = pfc_sym(c, 30), m = pfc_sym(c, 30);
    pfc_01(c, pf_gauss_cdf(x, m, pfc_sigma(c)));
}
static void pfc_f_pf_gauss_step(pfc_ctx *c)
{
    pf_real x = pfc_sym(c, 30), m = pfc_sym(c, 30);
    pfc_01(c, pf_gauss_step(x, m, pfc_sigma(c)));
}
/* two knots x0 <= x1 (equal ones make a jump) around a mean */
static void pfc_knots(pfc_ctx *c, pf_real *x0, pf_real *x1)
{
    /* width 0 (a jump) or at least 2^-24 (1 + |x0|): slopes (g1 - g0)/w of at most 2^34, so
       g'^2 (the E[g'^2] moment) stays finite in float */
    pf_real a = pfc_sym(c, 20), w = pfc_pos(c, 20);
    if (w > PF_R(0.0) && !c->wide_hit) w = pf_max(w, PF_R(5.9604644775390625e-8) * (PF_R(1.0) + PF_FABS(a)));
    *x0 = a;
    *x1 = a + w;
    c->arg[c->narg - 1] = w;
}
static void pfc_f_pf_gauss_segment_weights(pfc_ctx *c)
{
    pf_real x0, x1, m, s;
    pf_vec2 w;
    pfc_knots(c, &x0, &x1);
    m = pfc_sym(c, 20); s = pfc_sigma(c);
    w = pf_gauss_segment_weights(x0, x1, m, s);
    pfc_01(c, w.x); pfc_01(c, w.y);
    if (!(c->bad & 1)) pfc_flag(c, !(w.x + w.y <= PF_R(1.0) + PF_R(16.0) * PF_REAL_EPSILON));
}
static void pfc_f_pf_gauss_smoothstep(pfc_ctx *c)
{
    pf_real x0, x1, m, s;
    pfc_knots(c, &x0, &x1);
    m = pfc_sym(c, 20); s = pfc_sigma(c);
    pfc_01(c, pf_gauss_smoothstep(x0, x1, m, s));
}
static pf_transfer_moments pfc_tm(pfc_ctx *c)
{
    pf_real x0, x1, m, s, g0 = pfc_sym(c, 10), g1 = pfc_sym(c, 10);
    pf_transfer_moments t;
    pfc_knots(c, &x0, &x1);
    m = pfc_sym(c, 20); s = pfc_sigma(c);
    t = pf_transfer_segment_moments(x0, g0, x1, g1, m, s);
    pfc_require(c, t.g); pfc_require(c, t.g2); pfc_require(c, t.dg); pfc_require(c, t.dg2);
    return t;
}
static void pfc_f_pf_transfer_moments_make(pfc_ctx *c)
{
    pf_real a = pfc_sym(c, 20), b = pfc_pos(c, 40), d = pfc_sym(c, 20), e = pfc_pos(c, 40);
    pfc_out_tm(c, pf_transfer_moments_make(a, b, d, e));
}
static void pfc_f_pf_transfer_moments_add(pfc_ctx *c) { pf_transfer_moments a = pfc_tm(c); pfc_out_tm(c, pf_transfer_moments_add(a, pfc_tm(c))); }
static void pfc_f_pf_transfer_end_moments(pfc_ctx *c) { pf_real v = pfc_sym(c, 40); pfc_out_tm(c, pf_transfer_end_moments(v, pfc_u01(c))); }
static void pfc_f_pf_transfer_segment_moments(pfc_ctx *c)
{
    pf_transfer_moments m = pfc_tm(c);
    c->skip = 0; /* here the segment moments are the output under test */
    pfc_out_tm(c, m);
    if (!(c->bad & 1)) pfc_flag(c, !(m.g2 >= PF_R(0.0) && m.dg2 >= PF_R(0.0)));
}
static void pfc_f_pf_transfer_height(pfc_ctx *c) { pfc_out_hd(c, pf_transfer_height(pfc_tm(c))); }
static void pfc_f_pf_transfer_slope_stats(pfc_ctx *c)
{
    pf_transfer_moments t = pfc_tm(c);
    pf_slope_moments m = pfc_moments(c);
    pfc_psd_stats(c, pf_transfer_slope_stats(t, m.ex, m.ey, m.exx, m.eyy, m.exy));
}
/* ---- horizon */
static pf_hdf_moments pfc_hdf(pfc_ctx *c)
{
    pf_real mu = pfc_sym(c, 1), sd = pfc_u01(c) * PF_R(1.6);
    return pf_hdf_moments_make(mu, mu * mu + sd * sd, pfc_sym(c, 4));
}
static pf_hdf_legendre pfc_hdfl(pfc_ctx *c)
{
    pf_real a[8];
    int j;
    for (j = 0; j < 8; ++j) a[j] = pf_horizon_legendre_coeff(j, PF_R(2.0) * pfc_u01(c) - PF_R(1.0));
    return pf_hdf_legendre_make(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]);
}
static void pfc_f_pf_hdf_moments_make(pfc_ctx *c) { pf_hdf_moments m = pfc_hdf(c); pfc_out(c, m.m1); pfc_out(c, m.m2); pfc_out(c, m.ms); }
static void pfc_f_pf_hdf_moments_lerp(pfc_ctx *c) { pf_hdf_moments a = pfc_hdf(c), b = pfc_hdf(c); pf_hdf_moments m = pf_hdf_moments_lerp(a, b, pfc_u01(c)); pfc_out(c, m.m1); pfc_ge0(c, m.m2); pfc_out(c, m.ms); }
static void pfc_f_pf_hdf_legendre_make(pfc_ctx *c) { pfc_out(c, pfc_hdfl(c).c7); }
static void pfc_f_pf_hdf_legendre_coeff(pfc_ctx *c) { pf_hdf_legendre l = pfc_hdfl(c); pfc_out(c, pf_hdf_legendre_coeff(l, pfc_int(c, -2, 10))); }
static void pfc_f_pf_hdf_legendre_lerp(pfc_ctx *c) { pf_hdf_legendre a = pfc_hdfl(c), b = pfc_hdfl(c); pfc_out(c, pf_hdf_legendre_lerp(a, b, pfc_u01(c)).c3); }
static void pfc_f_pf_horizon_azimuth_of(pfc_ctx *c)
{
    pf_vec3 w = pfc_dir(c);
    int n = pfc_int(c, 1, 64);
    pf_horizon_azimuth a = pf_horizon_azimuth_of(w, n);
    pfc_01(c, a.f);
    pfc_flag(c, a.i0 < 0 || a.i0 >= n || a.i1 < 0 || a.i1 >= n);
}
static void pfc_f_pf_horizon_elevation(pfc_ctx *c) { pfc_in(c, pf_horizon_elevation(pfc_dir(c)), -PF_R(1.5708), PF_R(1.5708)); }
static void pfc_f_pf_horizon_visibility_ramp(pfc_ctx *c) { pf_hdf_moments m = pfc_hdf(c); pfc_01(c, pf_horizon_visibility_ramp(m, pfc_sym(c, 1))); }
static void pfc_f_pf_horizon_visibility_gauss(pfc_ctx *c) { pf_hdf_moments m = pfc_hdf(c); pfc_01(c, pf_horizon_visibility_gauss(m, pfc_sym(c, 1))); }
static void pfc_f_pf_horizon_visibility_legendre(pfc_ctx *c) { pf_hdf_legendre l = pfc_hdfl(c); int k = pfc_int(c, 0, 9); pfc_01(c, pf_horizon_visibility_legendre(l, k, pfc_cos(c))); }
static void pfc_f_pf_horizon_legendre_basis(pfc_ctx *c) { int j = pfc_int(c, 0, 8); pfc_in(c, pf_horizon_legendre_basis(j, pfc_cos(c)), -PF_R(3.0), PF_R(3.0)); }
static void pfc_f_pf_horizon_legendre_coeff(pfc_ctx *c) { int j = pfc_int(c, 0, 8); pfc_in(c, pf_horizon_legendre_coeff(j, pfc_cos(c)), -PF_R(2.0), PF_R(2.0)); }
static void pfc_f_pf_horizon_bidir_product(pfc_ctx *c) { pf_real l = pfc_u01(c); pfc_01(c, pf_horizon_bidir_product(l, pfc_u01(c))); }
static void pfc_f_pf_horizon_bidir_tan(pfc_ctx *c) { pf_real l = pfc_u01(c), v = pfc_u01(c); pfc_01(c, pf_horizon_bidir_tan(l, v, pfc_cos(c))); }
static void pfc_f_pf_horizon_bidir_ashikhmin(pfc_ctx *c) { pf_real l = pfc_u01(c), v = pfc_u01(c), k = pfc_cos(c); pfc_01(c, pf_horizon_bidir_ashikhmin(l, v, k, pfc_u01(c))); }
static void pfc_f_pf_horizon_visible_area(pfc_ctx *c) { pf_vec3 w = pfc_dir(c); pf_hdf_moments m = pfc_hdf(c); pf_real mx = pfc_sym(c, 2); pfc_in(c, pf_horizon_visible_area(w, m, mx, pfc_sym(c, 2)), PF_R(0.0), PF_R(2.0)); }
static void pfc_f_pf_horizon_masking(pfc_ctx *c) { pf_vec3 w = pfc_dir(c); pf_hdf_moments m = pfc_hdf(c); pfc_01(c, pf_horizon_masking(w, m, pfc_stats(c, 0))); }
static void pfc_f_pf_horizon_visibility_given_slope(pfc_ctx *c)
{
    pf_vec3 w = pfc_dir(c);
    pf_hdf_moments m = pfc_hdf(c);
    pf_slope_stats s = pfc_stats(c, 0);
    pf_real x = pfc_sym(c, 2);
    pfc_01(c, pf_horizon_visibility_given_slope(w, m, s, x, pfc_sym(c, 2)));
}
static void pfc_f_pf_horizon_diffuse_directional(pfc_ctx *c)
{
    pf_gg_grid g = pfc_grid(c);
    pf_vec3 wi = pfc_dir(c);
    pf_hdf_moments mo = pfc_hdf(c), mi = pfc_hdf(c);
    /* (1/pi) lit share (<= 1) times the visible area ratio (<= 2) */
    pfc_in(c, pf_horizon_diffuse_directional(g, wi, mo, mi), PF_R(0.0), PF_R(0.6367));
}
static void pfc_f_pf_horizon_diffuse_lod(pfc_ctx *c)
{
    pf_gg_grid g = pfc_grid(c);
    pf_vec3 wi = pfc_dir(c);
    pf_hdf_moments mo = pfc_hdf(c), mi = pfc_hdf(c);
    pf_real l = pfc_sym(c, 4), a = pfc_sym(c, 4);
    pfc_ge0(c, pf_horizon_diffuse_lod(g, wi, mo, mi, l, a, pfc_sym(c, 4)));
}
static void pfc_f_pf_horizon_lod_weight(pfc_ctx *c) { pf_real l = pfc_sym(c, 4), a = pfc_sym(c, 4); pfc_01(c, pf_horizon_lod_weight(l, a, pfc_sym(c, 4))); }
static void pfc_f_pf_horizon_masking_lod(pfc_ctx *c)
{
    pf_vec3 w = pfc_dir(c);
    pf_hdf_moments m = pfc_hdf(c);
    pf_slope_stats s = pfc_stats(c, 0);
    pf_real l = pfc_sym(c, 4), a = pfc_sym(c, 4);
    pfc_01(c, pf_horizon_masking_lod(w, m, s, l, a, pfc_sym(c, 4)));
}


/* ---- masks */
/* A 32-bit word as an int, bit pattern kept, without the implementation-defined conversion. */
static int pfc_word(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    int w;
    switch (u & 7u) {
    case 0: u = 0u; break;
    case 1: u = 0xFFFFFFFFu; break;
    case 2: u = 0x80000000u; break;
    default: break;
    }
    w = u <= 0x7FFFFFFFu ? (int)u : -(int)(0xFFFFFFFFu - u) - 1;
    pfc_keep(c, (pf_real)w);
    return w;
}
static pf_mask pfc_mask(pfc_ctx *c)
{
    int a = pfc_word(c), b = pfc_word(c), d = pfc_word(c), e = pfc_word(c);
    return pf_mask_make(a, b, d, e);
}
static int pfc_bit(pf_mask m, int k)
{
    int w = k < 32 ? m.w0 : (k < 64 ? m.w1 : (k < 96 ? m.w2 : m.w3));
    return (int)(((pfc_u32)w >> (k & 31)) & 1u);
}
static int pfc_grid_clamp(int n, int lo) { return n < lo ? lo : (n > PF_MASKS_MAX_GRID ? PF_MASKS_MAX_GRID : n); }
static void pfc_out_mask(pfc_ctx *c, pf_mask m)
{
    pfc_out(c, (pf_real)m.w0); pfc_out(c, (pf_real)m.w1); pfc_out(c, (pf_real)m.w2); pfc_out(c, (pf_real)m.w3);
}
static void pfc_f_pf_mask_params_make(pfc_ctx *c)
{
    pf_real t = pfc_sym(c, 100), v = pfc_sym(c, 100);
    pf_mask_params p = pf_mask_params_make(t, v);
    pfc_out(c, p.theta); pfc_out(c, p.v);
}
static void pfc_f_pf_mask_make(pfc_ctx *c)
{
    int a = pfc_word(c), b = pfc_word(c), d = pfc_word(c), e = pfc_word(c);
    pf_mask m = pf_mask_make(a, b, d, e);
    pfc_out_mask(c, m);
    pfc_flag(c, m.w0 != a || m.w1 != b || m.w2 != d || m.w3 != e);
}
static void pfc_f_pf_masks_v_max(pfc_ctx *c) { pfc_in(c, pf_masks_v_max(pfc_int(c, -2, 3)), PF_R(0.5), PF_R(0.7072)); }
static void pfc_f_pf_masks_params_from_plane(pfc_ctx *c)
{
    pf_real nx = pfc_sym(c, 100), ny = pfc_sym(c, 100), nz = pfc_sym(c, 100);
    pf_real d = pfc_sym(c, 100), w = pfc_sym(c, 100), dz = pfc_sym(c, 100);
    pf_mask_params p = pf_masks_params_from_plane(pf_vec3_make(nx, ny, nz), d, w, dz);
    pfc_in(c, p.theta, -PF_R(3.1416), PF_R(3.1416));
    pfc_in(c, p.v, -PF_MASKS_V_CLAMP, PF_MASKS_V_CLAMP);
}
static void pfc_f_pf_masks_grid_theta(pfc_ctx *c)
{
    int n = pfc_int(c, -3, 40000), i = pfc_int(c, 0, pfc_grid_clamp(n, 1) - 1);
    pfc_in(c, pf_masks_grid_theta(i, n), PF_R(0.0), PF_R(6.2832));
}
static void pfc_f_pf_masks_grid_v(pfc_ctx *c)
{
    int n = pfc_int(c, -3, 40000), j = pfc_int(c, 0, pfc_grid_clamp(n, 2) - 1), shape = pfc_int(c, 0, 1);
    pf_real vm = pf_masks_v_max(shape) * (PF_R(1.0) + PF_R(4.0) * PF_REAL_EPSILON);
    pfc_in(c, pf_masks_grid_v(j, n, shape), -vm, vm);
}
static void pfc_f_pf_masks_index(pfc_ctx *c)
{
    pf_real t = pfc_sym(c, 100), v = pfc_sym(c, 100);
    int shape = pfc_int(c, -1, 2), nt = pfc_int_any(c), nv = pfc_int_any(c);
    int idx = pf_masks_index(pf_mask_params_make(t, v), shape, nt, nv);
    pfc_out(c, (pf_real)idx);
    pfc_flag(c, idx < 0 || idx >= pfc_grid_clamp(nt, 1) * pfc_grid_clamp(nv, 2));
}
static void pfc_f_pf_masks_words(pfc_ctx *c)
{
    int n = pfc_int(c, -40, 200), w = pf_masks_words(n);
    pfc_out(c, (pf_real)w);
    pfc_flag(c, w != (n < 1 || n > 128 ? 0 : (n + 31) / 32));
}
static void pfc_f_pf_masks_popcount(pfc_ctx *c)
{
    int w = pfc_word(c), k, n = 0;
    for (k = 0; k < 32; ++k) n += (int)(((pfc_u32)w >> k) & 1u);
    pfc_out(c, (pf_real)pf_masks_popcount(w));
    pfc_flag(c, pf_masks_popcount(w) != n);
}
static void pfc_f_pf_masks_count(pfc_ctx *c)
{
    pf_mask m = pfc_mask(c);
    int k, n = 0;
    for (k = 0; k < 128; ++k) n += pfc_bit(m, k);
    pfc_out(c, (pf_real)pf_masks_count(m));
    pfc_flag(c, pf_masks_count(m) != n);
}
static void pfc_f_pf_masks_coverage(pfc_ctx *c)
{
    pf_mask m = pfc_mask(c);
    pfc_01(c, pf_masks_coverage(m, pfc_int(c, -3, 200)));
}
static void pfc_masks_binary(pfc_ctx *c, int op)
{
    pf_mask a = pfc_mask(c), b = pfc_mask(c), r;
    int k, bad = 0;
    r = op == 0 ? pf_masks_union(a, b) : (op == 1 ? pf_masks_intersection(a, b) : pf_masks_difference(a, b));
    for (k = 0; k < 128; ++k) {
        int x = pfc_bit(a, k), y = pfc_bit(b, k);
        bad |= pfc_bit(r, k) != (op == 0 ? (x | y) : (op == 1 ? (x & y) : (x & !y)));
    }
    pfc_out_mask(c, r);
    pfc_flag(c, bad);
}
static void pfc_f_pf_masks_union(pfc_ctx *c) { pfc_masks_binary(c, 0); }
static void pfc_f_pf_masks_intersection(pfc_ctx *c) { pfc_masks_binary(c, 1); }
static void pfc_f_pf_masks_difference(pfc_ctx *c) { pfc_masks_binary(c, 2); }
static void pfc_f_pf_masks_complement(pfc_ctx *c)
{
    pf_mask a = pfc_mask(c), r;
    int n = pfc_int(c, -40, 200), k, bad = 0;
    r = pf_masks_complement(a, n);
    for (k = 0; k < 128; ++k) bad |= pfc_bit(r, k) != (k < n ? !pfc_bit(a, k) : 0);
    pfc_out_mask(c, r);
    pfc_flag(c, bad);
}
static void pfc_f_pf_masks_visible_fraction(pfc_ctx *c)
{
    pf_mask a = pfc_mask(c), b = pfc_mask(c);
    pfc_01(c, pf_masks_visible_fraction(a, b, pfc_int(c, -3, 200)));
}
/* ================================================================ the table */
/* ---- vmf */
/* kappa: 0, negative, tiny, huge, log-uniform over the documented range */
static pf_real pfc_kappa(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real x;
    if (!pfc_front(c, u, &x)) {
        switch (PFC_R(u)) {
        case 0: x = PF_R(0.0); break;
        case 1: x = -pfc_mag(b, -20, 20); break;
        case 2: x = pfc_mag(b, -60, -14); break;
        case 3: x = pfc_mag(b, 17, 60); break;
        default: x = pfc_mag(b, -14, 17); break;
        }
    }
    return pfc_keep(c, x);
}
/* a lobe from the packed form: amplitude [0, 1], axis x, y in +-1.2 (beyond 1: rescaled) */
static pf_vmf_lobe pfc_vmf_lobe(pfc_ctx *c)
{
    pf_real a = pfc_u01(c), x = PF_R(1.2) * pfc_sym(c, 0), y = PF_R(1.2) * pfc_sym(c, 0);
    return pf_vmf_lobe_make(a, x, y, pfc_kappa(c));
}
static void pfc_out_lobe(pfc_ctx *c, pf_vmf_lobe l) { pfc_ge0(c, l.amp); pfc_out_vec3(c, l.mu); pfc_ge0(c, l.kappa); }
/* ---------------------------------------------------------------- pf_encode.h decoders
   Sampled values: UNORM in [0, 1] (pfc_u01: 0, 1 and in between); encodings: offsets and
   scales as pf_encode_ranges makes them from values up to 2^20 (scale >= 0), a reference slope
   within +-2^10. Decoded moments finite; the vMF lobe as pf_vmf_lobe_make promises. */
static pf_slope_encoding pfc_slope_enc(pfc_ctx *c)
{
    pf_slope_encoding e;
    e.ref_x = pfc_sym(c, 10); e.ref_y = pfc_sym(c, 10);
    e.off_x = pfc_sym(c, 20); e.off_y = pfc_sym(c, 20); e.off_xx = pfc_sym(c, 20); e.off_yy = pfc_sym(c, 20);
    e.off_xy = pfc_sym(c, 20);
    e.sc_x = pfc_pos(c, 20); e.sc_y = pfc_pos(c, 20); e.sc_xx = pfc_pos(c, 20); e.sc_yy = pfc_pos(c, 20);
    e.sc_xy = pfc_pos(c, 20);
    return e;
}
static void pfc_f_pf_unorm_decode(pfc_ctx *c)
{
    pf_real s = pfc_u01(c), o = pfc_sym(c, 20), k = pfc_pos(c, 20);
    pfc_in(c, pf_unorm_decode(s, o, k), o - PF_R(1e-6) * PF_FABS(o), o + k + PF_R(1e-6) * (PF_FABS(o) + k));
}
static void pfc_f_pf_slope_moments_decode(pfc_ctx *c)
{
    pf_slope_moments s = pf_slope_moments_make(pfc_u01(c), pfc_u01(c), pfc_u01(c), pfc_u01(c), pfc_u01(c));
    pfc_out_sm(c, pf_slope_moments_decode(s, pfc_slope_enc(c)));
}
static void pfc_f_pf_oct_hemi_decode(pfc_ctx *c)
{
    pf_vec3 d = pf_oct_hemi_decode(pfc_u01(c), pfc_u01(c));
    pfc_out_vec3(c, d);
    pfc_in(c, d.z, PF_R(0.0), PF_R(1.0));
    pfc_in(c, pf_vec3_length(d), PF_R(1.0) - PF_R(4.0) * PF_REAL_EPSILON, PF_R(1.0) + PF_R(4.0) * PF_REAL_EPSILON);
}
static void pfc_f_pf_vmf_lobe_decode(pfc_ctx *c)
{
    pf_vmf_encoding e;
    pf_real su = pfc_u01(c), sv = pfc_u01(c), sk = pfc_u01(c), sa = pfc_u01(c);
    e.log_kappa_lo = pfc_sym(c, 4);
    e.log_kappa_span = pfc_pos(c, 5);
    e.amp_scale = pfc_u01(c);
    pfc_out_lobe(c, pf_vmf_lobe_decode(su, sv, sk, sa, e));
}
/* a sum of 1-4 lobes for the directions wo, wi, with the masking terms */
static pf_vmf_sum pfc_vmf_sum(pfc_ctx *c, pf_vec3 wo, pf_vec3 wi, pf_real bv, int vmf_form)
{
    pf_vmf_sum s = pf_vmf_sum_zero();
    int n = pfc_int(c, 1, 4), k;
    for (k = 0; k < n; ++k) {
        pf_vmf_lobe l = pfc_vmf_lobe(c);
        s = vmf_form ? pf_vmf_sum_add_vmf(s, l, wo, wi, PF_R(100.0), bv) : pf_vmf_sum_add(s, l, wo, wi, bv);
        s = pf_vmf_sum_add_masking(s, l, wo, wi, bv);
    }
    return s;
}
static void pfc_out_vmf_sum(pfc_ctx *c, pf_vmf_sum s)
{
    pfc_ge0(c, s.amp); pfc_ge0(c, s.ndf); pfc_out(c, s.ex); pfc_out(c, s.ey); pfc_ge0(c, s.exx); pfc_ge0(c, s.eyy);
    pfc_out(c, s.exy); pfc_ge0(c, s.excess_o); pfc_ge0(c, s.excess_i);
}
static void pfc_f_pf_vmf_kappa_clamp(pfc_ctx *c) { pfc_in(c, pf_vmf_kappa_clamp(pfc_kappa(c)), PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX); }
static void pfc_f_pf_vmf_facet_specular(pfc_ctx *c)
{
    pf_real sx = pfc_sym(c, 4), sy = pfc_sym(c, 4), v = pf_max(pfc_var(c, 0), PF_R(1.0e-6));
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pfc_ge0(c, pf_vmf_facet_specular(sx, sy, v, wo, wi, pfc_u01(c)));
}
static void pfc_f_pf_vmf_normalization(pfc_ctx *c) { pfc_ge0(c, pf_vmf_normalization(pfc_kappa(c))); }
static void pfc_f_pf_vmf_mean_cosine(pfc_ctx *c) { pfc_01(c, pf_vmf_mean_cosine(pfc_kappa(c))); }
static void pfc_f_pf_vmf_tangent_variance(pfc_ctx *c) { pfc_in(c, pf_vmf_tangent_variance(pfc_kappa(c)), PF_R(0.0), PF_R(0.334)); }
static void pfc_f_pf_vmf_kappa_from_tangent_variance(pfc_ctx *c)
{
    pfc_in(c, pf_vmf_kappa_from_tangent_variance(pfc_var(c, 1)), PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX);
}
static void pfc_f_pf_vmf_lobe_eval(pfc_ctx *c)
{
    pf_vec3 mu = pfc_dir(c), w = pfc_dir(c);
    pfc_ge0(c, pf_vmf_lobe_eval(mu, pfc_kappa(c), w));
}
static void pfc_f_pf_vmf_kappa_from_mean_length(pfc_ctx *c)
{
    pfc_in(c, pf_vmf_kappa_from_mean_length(pfc_u01(c)), PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX);
}
static void pfc_f_pf_vmf_convolve_kappa(pfc_ctx *c)
{
    pf_real a = pfc_kappa(c);
    pfc_in(c, pf_vmf_convolve_kappa(a, pfc_kappa(c)), PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX);
}
static void pfc_f_pf_vmf_kappa_from_sigma(pfc_ctx *c) { pfc_in(c, pf_vmf_kappa_from_sigma(pfc_sym(c, 20)), PF_VMF_KAPPA_MIN, PF_VMF_KAPPA_MAX); }
static void pfc_f_pf_vmf_lobe_slope_stats(pfc_ctx *c)
{
    pf_vmf_lobe l = pfc_vmf_lobe(c);
    pf_slope_stats s = pf_vmf_lobe_slope_stats(l.mu, l.kappa, pfc_var(c, 1));
    pfc_out_stats(c, s);
    pfc_psd_stats(c, s);
}
static void pfc_f_pf_vmf_lobe_make(pfc_ctx *c)
{
    pf_real a = pfc_sym(c, 100), x = pfc_sym(c, 100), y = pfc_sym(c, 100);
    pf_vmf_lobe l = pf_vmf_lobe_make(a, x, y, pfc_kappa(c));
    pfc_out_lobe(c, l);
    pfc_flag(c, PF_FABS(pf_vec3_dot(l.mu, l.mu) - PF_R(1.0)) > PF_R(1.0e-5));
}
static void pfc_f_pf_vmf_lobe_density(pfc_ctx *c) { pf_vmf_lobe l = pfc_vmf_lobe(c); pfc_ge0(c, pf_vmf_lobe_density(l, pfc_dir(c))); }
static void pfc_f_pf_vmf_lobe_ndf(pfc_ctx *c)
{
    pf_vmf_lobe l = pfc_vmf_lobe(c);
    pf_vec3 w = pfc_dir(c);
    pfc_ge0(c, pf_vmf_lobe_ndf(l, w, pfc_kappa(c)));
}
static void pfc_f_pf_vmf_lobe_ndf_slope(pfc_ctx *c)
{
    pf_vmf_lobe l = pfc_vmf_lobe(c);
    pf_vec3 w = pfc_dir(c);
    pfc_ge0(c, pf_vmf_lobe_ndf_slope(l, w, pfc_var(c, 1)));
}
static void pfc_f_pf_vmf_lobe_area(pfc_ctx *c) { pf_vmf_lobe l = pfc_vmf_lobe(c); pfc_out(c, pf_vmf_lobe_area(l, pfc_dir(c))); }
static void pfc_f_pf_vmf_lobe_excess(pfc_ctx *c)
{
    pf_vmf_lobe l = pfc_vmf_lobe(c);
    pf_vec3 w = pfc_dir(c);
    pfc_ge0(c, pf_vmf_lobe_excess(l, w, pfc_var(c, 1)));
}
static void pfc_f_pf_vmf_lambda(pfc_ctx *c)
{
    pf_real e = pfc_sym(c, 40);
    pfc_in(c, pf_vmf_lambda(e, pfc_sym(c, 40)), PF_R(0.0), PF_LAMBDA_MAX);
}
static void pfc_f_pf_vmf_sum_zero(pfc_ctx *c) { pfc_out_vmf_sum(c, pf_vmf_sum_zero()); }
static void pfc_f_pf_vmf_sum_add(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pfc_out_vmf_sum(c, pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 0));
}
static void pfc_f_pf_vmf_sum_add_vmf(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pfc_out_vmf_sum(c, pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 1));
}
static void pfc_f_pf_vmf_sum_add_masking(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_vmf_lobe l = pfc_vmf_lobe(c);
    pfc_out_vmf_sum(c, pf_vmf_sum_add_masking(pf_vmf_sum_zero(), l, wo, wi, pfc_var(c, 0)));
}
static void pfc_f_pf_vmf_sum_stats(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_slope_stats s = pf_vmf_sum_stats(pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 0));
    pfc_out_stats(c, s);
    pfc_psd_stats(c, s);
}
static void pfc_f_pf_vmf_sum_g2(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pfc_01(c, pf_vmf_sum_g2(pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 0), wo, wi));
}
static void pfc_f_pf_vmf_sum_g2_mixture(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pfc_01(c, pf_vmf_sum_g2_mixture(pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 0), wo, wi));
}
static void pfc_f_pf_vmf_sum_g1_mixture(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pfc_01(c, pf_vmf_sum_g1_mixture(pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 0), wo));
}
/* the shader path: the pixel's shared terms, and lobes added from their texels (drawn as
   pfc_vmf_lobe's packed form, so the texel is one the fit could write) */
static void pfc_f_pf_vmf_pixel_make(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_vmf_pixel p = pf_vmf_pixel_make(wo, wi, pfc_var(c, 0));
    pfc_out(c, p.gx); pfc_out(c, p.gy); pfc_out(c, p.ngx); pfc_out(c, p.ldn); pfc_ge0(c, p.base_var);
}
static pf_vmf_sum pfc_vmf_sum_texel(pfc_ctx *c, pf_vec3 wo, pf_vec3 wi, pf_real bv, int mixture)
{
    pf_vmf_pixel p = pf_vmf_pixel_make(wo, wi, bv);
    pf_vmf_sum s = pf_vmf_sum_zero();
    int n = pfc_int(c, 1, 4), k;
    for (k = 0; k < n; ++k) {
        pf_vmf_lobe l = pfc_vmf_lobe(c);
        s = mixture ? pf_vmf_sum_add_texel_mixture(s, p, wo, wi, l.amp, l.mu.x, l.mu.y, l.kappa)
                    : pf_vmf_sum_add_texel(s, p, l.amp, l.mu.x, l.mu.y, l.kappa);
    }
    return s;
}
static void pfc_f_pf_vmf_sum_add_texel(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_vmf_sum s = pfc_vmf_sum_texel(c, wo, wi, pfc_var(c, 0), 0);
    pfc_out_vmf_sum(c, s);
    pfc_ge0(c, pf_vmf_sum_specular(s, wo, wi, pfc_u01(c)));
}
static void pfc_f_pf_vmf_sum_add_texel_mixture(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_vmf_sum s = pfc_vmf_sum_texel(c, wo, wi, pfc_var(c, 0), 1);
    pfc_out_vmf_sum(c, s);
    pfc_ge0(c, s.excess_o); pfc_ge0(c, s.excess_i);
    pfc_ge0(c, pf_vmf_sum_specular_mixture(s, wo, wi, pfc_u01(c)));
    pfc_01(c, pf_vmf_sum_g2_mixture(s, wo, wi));
}
static void pfc_f_pf_vmf_sum_specular(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_vmf_sum s = pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 0);
    pfc_ge0(c, pf_vmf_sum_specular(s, wo, wi, pfc_u01(c)));
}
static void pfc_f_pf_vmf_sum_specular_mixture(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_vmf_sum s = pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 1);
    pfc_ge0(c, pf_vmf_sum_specular_mixture(s, wo, wi, pfc_u01(c)));
}
/* the base lobe's own masking kept apart (grazing) */
static void pfc_f_pf_vmf_sum_without_base(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_real bv = pfc_var(c, 0);
    pfc_out_vmf_sum(c, pf_vmf_sum_without_base(pfc_vmf_sum(c, wo, wi, bv, 0), bv));
}
static void pfc_f_pf_vmf_sum_specular_base(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_real bv = pfc_var(c, 0);
    pf_vmf_sum s = pfc_vmf_sum(c, wo, wi, bv, 0);
    pfc_ge0(c, pf_vmf_sum_specular_base(s, wo, wi, bv, pfc_u01(c)));
}
/* scaling function, shader side (helper J) */
static void pfc_f_pf_vmf_sum_specular_unmasked(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_vmf_sum s = pfc_vmf_sum(c, wo, wi, pfc_var(c, 0), 0);
    pfc_ge0(c, pf_vmf_sum_specular_unmasked(s, wo, wi, pfc_u01(c)));
}
static void pfc_f_pf_vmf_scale_coords(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c), v = pf_vmf_scale_coords(wo, wi, pfc_sym(c, 4));
    pfc_01(c, v.x);
    pfc_01(c, v.y);
    pfc_01(c, v.z);
}
static void pfc_f_pf_vmf_scale_texel_pos(pfc_ctx *c)
{
    pf_real u = pfc_sym(c, 20);
    int n = pfc_int(c, -2, 64);
    pfc_in(c, pf_vmf_scale_texel_pos(u, n), PF_R(0.0), n > 1 ? (pf_real)(n - 1) : PF_R(0.0));
}
static void pfc_f_pf_vmf_scale_trilinear(pfc_ctx *c)
{
    pf_real v[8], fx, fy, fz;
    int k;
    for (k = 0; k < 8; ++k) v[k] = pfc_u01(c);
    fx = pfc_u01(c);
    fy = pfc_u01(c);
    fz = pfc_u01(c);
    pfc_in(c, pf_vmf_scale_trilinear(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], pf_vec3_make(fx, fy, fz)), PF_R(0.0),
           PF_R(1.0) + PF_R(8.0) * PF_REAL_EPSILON);
}
static void pfc_f_pf_vmf_scale_apply(pfc_ctx *c)
{
    pf_real t = pfc_sym(c, 20), s = pfc_sym(c, 20);
    pfc_ge0(c, pf_vmf_scale_apply(t, s, pfc_u01(c)));
}

#define PFC_E(mod, name, flags, dom, reg) { #name, #mod, pfc_f_##name, flags, dom, reg }
#define PFC_LIN "finite texels of the type's range, convex weights"
#define PFC_LINREG "linear (products and sums only): non-finite only when an input is already near overflow"

/* ---- specaa */
/* a screen-space derivative of a unit vector: a direction times 0, tiny, [0, 2^8], huge */
static pf_vec3 pfc_deriv(pfc_ctx *c) { pf_vec3 d = pfc_dir(c); return pf_vec3_scale(d, pfc_pos(c, 8)); }
static void pfc_out_kernel(pfc_ctx *c, pf_specaa_kernel k) { pfc_ge0(c, k.var_x); pfc_ge0(c, k.var_y); pfc_out(c, k.cov_xy); }
static void pfc_f_pf_specaa_kernel_make(pfc_ctx *c)
{
    pf_real a = pfc_sym(c, 60), b = pfc_sym(c, 60);
    pf_specaa_kernel k = pf_specaa_kernel_make(a, b, pfc_sym(c, 60));
    pfc_out(c, k.var_x); pfc_out(c, k.var_y); pfc_out(c, k.cov_xy);
}
static void pfc_f_pf_specaa_kernel_normal(pfc_ctx *c)
{
    pf_vec3 a = pfc_deriv(c), b = pfc_deriv(c);
    pf_real s2 = pfc_u01(c), kap = pfc_u01(c);
    pfc_in(c, pf_specaa_kernel_normal(a, b, s2, kap), PF_R(0.0), kap);
}
static void pfc_f_pf_specaa_kernel_halfvector(pfc_ctx *c)
{
    pf_vec3 h = pfc_dir(c), a = pfc_deriv(c), b = pfc_deriv(c);
    pf_real s2 = pfc_u01(c), kap = pfc_u01(c);
    pfc_in(c, pf_specaa_kernel_halfvector(h, a, b, s2, kap), PF_R(0.0), kap);
}
static void pfc_f_pf_specaa_kernel_aniso(pfc_ctx *c)
{
    pf_vec3 a = pfc_deriv(c), b = pfc_deriv(c);
    pf_real s2 = pfc_u01(c), kap = pfc_u01(c);
    pf_specaa_kernel k = pf_specaa_kernel_aniso(a, b, s2, kap);
    pfc_out_kernel(c, k);
    pfc_in(c, k.var_x + k.var_y, PF_R(0.0), kap * (PF_R(1.0) + PF_R(8.0) * PF_REAL_EPSILON) + PF_R(8.0) * PF_REAL_MIN); /* subnormal kappa: absolute rounding */
}
static void pfc_f_pf_specaa_kernel_trace(pfc_ctx *c)
{
    pf_vec3 a = pfc_deriv(c), b = pfc_deriv(c);
    pfc_ge0(c, pf_specaa_kernel_trace(pf_specaa_kernel_aniso(a, b, pfc_u01(c), pfc_u01(c))));
}
static void pfc_f_pf_specaa_alpha(pfc_ctx *c) { pf_real a = pfc_pos(c, 4); pfc_01(c, pf_specaa_alpha(a, pfc_u01(c))); }
static void pfc_f_pf_specaa_alpha_projected(pfc_ctx *c) { pf_real a = pfc_pos(c, 4); pfc_01(c, pf_specaa_alpha_projected(a, pfc_pos(c, 60))); }
static void pfc_f_pf_specaa_alpha_from_variance(pfc_ctx *c)
{
    pf_real a = pfc_pos(c, 4), v = pfc_var(c, 1);
    pfc_ge0(c, pf_specaa_alpha_from_variance(a, v, pfc_pos(c, 4)));
}
static void pfc_f_pf_specaa_projected_variance(pfc_ctx *c) { pfc_in(c, pf_specaa_projected_variance(pfc_pos(c, 60)), PF_R(0.0), PF_R(0.25)); }
static void pfc_f_pf_specaa_slope_variance_from_projected(pfc_ctx *c)
{
    pfc_in(c, pf_specaa_slope_variance_from_projected(pfc_sym(c, 2)), PF_R(0.0), PF_R(625.0) * (PF_R(1.0) + PF_R(1.0e-3)));
}
static void pfc_f_pf_specaa_slope_stats(pfc_ctx *c) { pf_slope_stats s = pfc_stats(c, 0); pfc_out_stats(c, pf_specaa_slope_stats(s, pfc_u01(c))); }
static void pfc_f_pf_specaa_slope_stats_aniso(pfc_ctx *c)
{
    pf_slope_stats s = pfc_stats(c, 0);
    pf_vec3 a = pfc_deriv(c), b = pfc_deriv(c);
    pfc_out_stats(c, pf_specaa_slope_stats_aniso(s, pf_specaa_kernel_aniso(a, b, pfc_u01(c), pfc_u01(c))));
}
static void pfc_f_pf_specaa_kernel_cross(pfc_ctx *c)
{
    pf_vec3 a = pfc_deriv(c), b = pfc_deriv(c);
    pf_vec2 gx, gy;
    pf_specaa_kernel k;
    gx.x = pfc_sym(c, 8); gx.y = pfc_sym(c, 8); gy.x = pfc_sym(c, 8); gy.y = pfc_sym(c, 8);
    k = pf_specaa_kernel_cross(a, b, gx, gy, pfc_u01(c));
    pfc_out(c, k.var_x); pfc_out(c, k.var_y); pfc_out(c, k.cov_xy);
}
static void pfc_f_pf_specaa_slope_stats_cross(pfc_ctx *c)
{
    pf_slope_stats s = pfc_stats(c, 0);
    pf_vec3 a = pfc_deriv(c), b = pfc_deriv(c);
    pf_real s2 = pfc_u01(c);
    pf_vec2 gx, gy;
    pf_slope_stats r;
    gx.x = pfc_sym(c, 8); gx.y = pfc_sym(c, 8); gy.x = pfc_sym(c, 8); gy.y = pfc_sym(c, 8);
    r = pf_specaa_slope_stats_cross(s, pf_specaa_kernel_aniso(a, b, s2, pfc_u01(c)), pf_specaa_kernel_cross(a, b, gx, gy, s2));
    pfc_out_stats(c, r);
    pfc_in(c, r.var_x, PF_R(0.0), PF_REAL_MAX); /* Cauchy-Schwarz clamp: variances stay >= 0 */
    pfc_in(c, r.var_y, PF_R(0.0), PF_REAL_MAX);
}
static void pfc_f_pf_specaa_slope_stats_quad(pfc_ctx *c)
{
    pf_slope_moments m00 = pfc_moments(c), m10 = pfc_moments(c), m01 = pfc_moments(c), m11 = pfc_moments(c);
    pf_real bv = pfc_var(c, 0);
    pf_vec3 a = pfc_deriv(c), b = pfc_deriv(c);
    pf_real s2 = pfc_u01(c);
    pfc_out_stats(c, pf_specaa_slope_stats_quad(m00, m10, m01, m11, bv, a, b, s2, pfc_u01(c)));
}
static void pfc_f_pf_specaa_leadr_specular(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_slope_stats s = pfc_leadr_stats(c);
    pf_real f0 = pfc_u01(c);
    pf_vec3 a = pfc_deriv(c);
    pfc_ge0(c, pf_specaa_leadr_specular(wo, wi, s, f0, a, pfc_deriv(c)));
}
static void pfc_f_pf_specaa_mean_shift(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c);
    pf_vec2 d = pf_specaa_mean_shift(wo, pfc_pos(c, 8));
    pfc_in(c, d.x, -PF_SPECAA_SHIFT_MAX, PF_SPECAA_SHIFT_MAX);
    pfc_in(c, d.y, -PF_SPECAA_SHIFT_MAX, PF_SPECAA_SHIFT_MAX);
}
static void pfc_f_pf_specaa_mean_shift_surface(pfc_ctx *c)
{
    pf_vec3 px = pfc_deriv(c), py = pfc_deriv(c), a = pfc_deriv(c), b = pfc_deriv(c), wo = pfc_dir(c);
    pf_vec2 d = pf_specaa_mean_shift_surface(px, py, a, b, wo, pfc_u01(c));
    pfc_in(c, d.x, -PF_SPECAA_SHIFT_MAX, PF_SPECAA_SHIFT_MAX);
    pfc_in(c, d.y, -PF_SPECAA_SHIFT_MAX, PF_SPECAA_SHIFT_MAX);
}
static void pfc_f_pf_specaa_slope_stats_shift(pfc_ctx *c)
{
    pf_slope_stats s = pfc_stats(c, 0);
    pf_vec2 d;
    d.x = pfc_sym(c, 8); d.y = pfc_sym(c, 8);
    pfc_out_stats(c, pf_specaa_slope_stats_shift(s, d));
}
static void pfc_f_pf_specaa_leadr_specular_curved(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_slope_stats s = pfc_leadr_stats(c);
    pf_real f0 = pfc_u01(c);
    pf_vec3 a = pfc_deriv(c);
    pfc_ge0(c, pf_specaa_leadr_specular_curved(wo, wi, s, f0, a, pfc_deriv(c)));
}
static void pfc_f_pf_specaa_vmf_kappa(pfc_ctx *c) { pf_real k = pfc_kappa(c); pfc_ge0(c, pf_specaa_vmf_kappa(k, pfc_pos(c, 60))); }
static void pfc_f_pf_specaa_vmf_lobe(pfc_ctx *c) { pf_vmf_lobe l = pfc_vmf_lobe(c); pfc_out_lobe(c, pf_specaa_vmf_lobe(l, pfc_pos(c, 60))); }
/* ---- horizon: the specular (after pfc_vmf_sum, which it uses) */
static void pfc_f_pf_horizon_specular_visibility(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_hdf_moments mo = pfc_hdf(c), mi = pfc_hdf(c);
    pf_slope_stats s = pfc_stats(c, 0);
    pfc_01(c, pf_horizon_specular_visibility(wo, wi, mo, mi, s, pfc_var(c, 0)));
}
static void pfc_f_pf_horizon_texel_stats(pfc_ctx *c)
{
    pf_slope_stats s = pf_horizon_texel_stats(pfc_stats(c, 0), pfc_var(c, 1));
    pfc_out(c, s.mean_x); pfc_out(c, s.mean_y); pfc_ge0(c, s.var_x); pfc_ge0(c, s.var_y); pfc_out(c, s.cov_xy);
}
static void pfc_f_pf_horizon_leadr_specular(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_hdf_moments mo = pfc_hdf(c), mi = pfc_hdf(c);
    pf_slope_stats s = pfc_stats(c, 0);
    pf_real bv = pfc_var(c, 0);
    pfc_ge0(c, pf_horizon_leadr_specular(wo, wi, s, bv, mo, mi, pfc_u01(c)));
}
static void pfc_f_pf_horizon_leadr_specular_lod(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_hdf_moments mo = pfc_hdf(c), mi = pfc_hdf(c);
    pf_slope_stats s = pfc_stats(c, 0);
    pf_real bv = pfc_var(c, 0), f0 = pfc_u01(c), l = pfc_sym(c, 4), a = pfc_sym(c, 4);
    pfc_ge0(c, pf_horizon_leadr_specular_lod(wo, wi, s, bv, mo, mi, f0, l, a, pfc_sym(c, 4)));
}
static void pfc_f_pf_horizon_vmf_specular(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_real bv = pfc_var(c, 0);
    pf_vmf_sum sum = pfc_vmf_sum(c, wo, wi, bv, 0);
    pf_hdf_moments mo = pfc_hdf(c), mi = pfc_hdf(c);
    pf_slope_stats s = pfc_stats(c, 0);
    pfc_ge0(c, pf_horizon_vmf_specular(sum, wo, wi, s, bv, mo, mi, pfc_u01(c)));
}
static void pfc_f_pf_horizon_vmf_specular_lod(pfc_ctx *c)
{
    pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
    pf_real bv = pfc_var(c, 0);
    pf_vmf_sum sum = pfc_vmf_sum(c, wo, wi, bv, 0);
    pf_hdf_moments mo = pfc_hdf(c), mi = pfc_hdf(c);
    pf_slope_stats s = pfc_stats(c, 0);
    pf_real f0 = pfc_u01(c), l = pfc_sym(c, 4), a = pfc_sym(c, 4);
    pfc_ge0(c, pf_horizon_vmf_specular_lod(sum, wo, wi, s, bv, mo, mi, f0, l, a, pfc_sym(c, 4)));
}

static const pfc_entry pfc_table[] = {
    /* core */
    PFC_E(core, pf_min, 0, "+-[0, 2^100]", "comparison; NaN in b returns b, NaN in a returns b"),
    PFC_E(core, pf_max, 0, "+-[0, 2^100]", "comparison; pf_max(NaN, 0) = 0 (used as a sanitizer)"),
    PFC_E(core, pf_clamp_nan_lo, 0, "x +-[0, 2^100], lo <= hi", "in [lo, hi]; NaN x returns lo"),
    PFC_E(core, pf_clamp, 0, "x +-[0, 2^100], lo <= hi", "NaN x returns hi"),
    PFC_E(core, pf_saturate, 0, "+-[0, 2^100]", "range [0, 1]; NaN returns 1"),
    PFC_E(core, pf_sq, 0, "+-[0, 2^60]", "overflows past sqrt(PF_REAL_MAX)"),
    PFC_E(core, pf_exp_neg_sq, PFC_WIDE, "every finite x", "|x| clamped at 64 (result 0); range [0, 1]"),
    PFC_E(core, pf_atan2, PFC_WIDE, "every finite y, x", "range [-pi, pi]; 0 at (0, 0)"),
    PFC_E(core, pf_erfc, PFC_WIDE, "every finite x", "range [0, 2]; underflows to 0 past x = 10.06 (f) / 27.23 (d); subnormal results lose relative accuracy"),
    PFC_E(core, pf_erfc_fast, PFC_WIDE, "every finite x", "range [0, 2]; shader tier: relative error 2e-6 + 6e-8 x^2 (float), 1.4e-6 (double)"),
    PFC_E(core, pf_erf, PFC_WIDE, "every finite x", "range [-1, 1]; relatively accurate down to subnormals"),
    PFC_E(core, pf_vec2_make, 0, "+-[0, 2^60]", "constructor"),
    PFC_E(core, pf_vec2_dot, 0, "+-[0, 2^30]", PFC_LINREG),
    PFC_E(core, pf_vec3_make, 0, "+-[0, 2^60]", "constructor"),
    PFC_E(core, pf_vec3_add, 0, "directions scaled by 0, 1 or 2^+-40 (d: 2^+-300)", PFC_LINREG),
    PFC_E(core, pf_vec3_sub, 0, "directions scaled by 0, 1 or 2^+-40 (d: 2^+-300)", PFC_LINREG),
    PFC_E(core, pf_vec3_scale, 0, "directions scaled by 0, 1 or 2^+-40, s +-[0, 2^20]", PFC_LINREG),
    PFC_E(core, pf_vec3_dot, 0, "directions scaled by 0, 1 or 2^+-40 (d: 2^+-300)", PFC_LINREG),
    PFC_E(core, pf_vec3_cross, 0, "directions scaled by 0, 1 or 2^+-40 (d: 2^+-300)", PFC_LINREG),
    PFC_E(core, pf_vec3_length, 0, "directions scaled by 0, 1 or 2^+-40 (d: 2^+-300)", "squares the components: overflows past |v| ~ 1.8e19 (f), underflows below ~1e-19"),
    PFC_E(core, pf_vec3_normalize, 0, "components +-[0, PF_REAL_MAX]", "zero vector (or NaN) returns (0, 0, 1); components outside [2^-50, 2^60] (f) / [2^-480, 2^500] (d) scaled by a power of two first: subnormal and huge vectors stay unit"),
    /* smith */
    PFC_E(smith, pf_slope_stats_make, 0, "means +-2^8, variances incl. 0 and slightly negative, |r| <= 1 + 2^-k", "constructor"),
    PFC_E(smith, pf_slope_stats_from_moments, PFC_WIDE, "raw moments of the stats domain", "negative variance clamped to 0, |c| clamped to sqrt(vx) sqrt(vy) (no underflowing product); cancellation E[x^2] - E[x]^2 for |mean| >> sigma"),
    PFC_E(smith, pf_slope_along, 0, "any-length w (grazing, below, zero), stats", "normal incidence (r = 0): azimuth taken as the x axis; negative variance along w clamped to 0; statistics beyond PF_REAL_MAX/4 can overflow the exact mean or variance (not all finite)"),
    PFC_E(smith, pf_smith_nu, PFC_WIDE, "any-length w (grazing, below, zero), stats", "0 on/below the mesosurface; PF_NU_MAX at normal incidence or zero deviation along w"),
    PFC_E(smith, pf_smith_nu_iso, PFC_WIDE, "cos in [-1, 1] (grazing, 0, below), sigma >= 0", "0 for cos <= 0; PF_NU_MAX for sigma = 0 or cos = 1"),
    PFC_E(smith, pf_smith_k, 0, "nu in [0, 2]", "K(nu) in (0, 1]"),
    PFC_E(smith, pf_smith_nu_over_g1, 0, "nu as pf_g1_beckmann", ">= 1/(2 sqrt(pi))"),
    PFC_E(smith, pf_lambda_beckmann, PFC_WIDE, "every finite nu", "PF_LAMBDA_MAX (1e30) for nu <= 0 or tiny nu; 0 past nu = 10.5 (f) / 27.5 (d)"),
    PFC_E(smith, pf_g1_beckmann, PFC_WIDE, "every finite nu", "0 for nu <= 0 (and NaN); 1 past nu = 3.3 (f)"),
    PFC_E(smith, pf_lambda_beckmann_walter, PFC_WIDE, "every finite nu", "Walter rational: 3.1e-3 relative error in G1; clamped at 0 on [1.548, 1.6); PF_LAMBDA_MAX for nu <= 0"),
    PFC_E(smith, pf_g1_beckmann_walter, PFC_WIDE, "every finite nu", "0 for nu <= 0; 1 past 1.6"),
    PFC_E(smith, pf_g1_beckmann_fast, PFC_WIDE, "every finite nu", "1.05e-4 relative error; peaks at 0.99994 (never 1)"),
    PFC_E(smith, pf_lambda_beckmann_fast, PFC_WIDE, "every finite nu", "relative error 2e-6 + 6e-8 nu^2 (float); PF_LAMBDA_MAX for nu <= 0; underflows past ~10"),
    PFC_E(smith, pf_lambda_ggx, PFC_WIDE, "any-length w, alpha >= 0", "PF_LAMBDA_MAX for w.z <= 0 and at grazing where t would overflow; t/2 past t = 1e18"),
    PFC_E(smith, pf_g1_ggx, PFC_WIDE, "any-length w, alpha >= 0", "0 for w.z <= 0; 2 w.z/u at extreme grazing (t > 1e18)"),
    PFC_E(smith, pf_lambda_ggx_iso, PFC_WIDE, "cos in [-1, 1], alpha >= 0", "as pf_lambda_ggx; cos clamped to 1"),
    PFC_E(smith, pf_g1_ggx_iso, PFC_WIDE, "cos in [-1, 1], alpha >= 0", "as pf_g1_ggx"),
    PFC_E(smith, pf_smith_joint, PFC_WIDE, "G1s in [0, 1]", "0 when either G1 <= 0 (or NaN); G1 > 1 read as 1; a (b / den): <= min(G1o, G1i) even for subnormal products"),
    PFC_E(smith, pf_smith_joint_lambda, PFC_WIDE, "Lambdas in [0, 1e30] (also slightly negative, above 1e30)", "negative Lambda read as 0; two PF_LAMBDA_MAX give ~5e-31, not 0"),
    PFC_E(smith, pf_smith_separable, PFC_WIDE, "G1s in [0, 1]", "product of G1s clamped to [0, 1] (NaN to 0); double-counts occlusion (<= joint)"),
    PFC_E(smith, pf_g2_beckmann, PFC_WIDE, "every finite nu pair", "0 when either nu <= 0"),
    /* beckmann */
    PFC_E(moments, pf_slope_moments_make, 0, "raw moments of the stats domain", "constructor"),
    PFC_E(moments, pf_slope_moments_from_slope, 0, "slopes +-[0, 2^40]", "squares overflow past |slope| ~ 1.8e19 (f)"),
    PFC_E(moments, pf_slope_moments_from_normal, 0, "unit normals with n.z > 0 (down to 1e-18)", "n.z <= 0 clamped to PF_REAL_MIN: huge slopes, squares overflow to inf (outside the domain)"),
    PFC_E(moments, pf_slope_moments_add, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_slope_moments_scale, 0, PFC_LIN, PFC_LINREG),
    PFC_E(beckmann, pf_slope_moments_from_stats, 0, "stats domain", PFC_LINREG),
    PFC_E(beckmann, pf_slope_moments_stats, 0, "filtered moments (variance slightly negative, |r| slightly > 1), base_var incl. negative", "variance clamped at 0, |r| at 1, then max(base_var, 1e-6) added: always positive definite"),
    PFC_E(beckmann, pf_slope_stats_correlation, 0, "stats domain", "0 when a variance is 0; clamped to [-1, 1]"),
    PFC_E(beckmann, pf_slope_moments_deform, 0, "filtered moments, Jacobian entries +-2^8", PFC_LINREG),
    PFC_E(beckmann, pf_slope_moments_scale_height, 0, "filtered moments, eta +-2^8", "eta = 0 flattens (mirror + base roughness)"),
    PFC_E(beckmann, pf_beckmann_p22, PFC_WIDE, "slopes +-2^20, stats incl. singular and indefinite covariances", "variance floored at 1e-15 (f) / 1e-140 (d) and capped at 1e15 / 1e150, determinant at 4 eps vx vy: singular |r| = 1 gives a finite peak (<= 2.3e17 in f); exponent capped"),
    PFC_E(beckmann, pf_beckmann_d, 0, "any-length m (grazing, below), stats incl. singular", "0 for m.z <= 0; 1/cos^4 capped at 1e9; as p22 for singular covariance; m.z^2 must be finite (m.z < 1.8e19 (f)), so not all finite"),
    PFC_E(beckmann, pf_beckmann_mesonormal, PFC_WIDE, "stats domain", "normalized with the scaled pf_vec3_normalize: huge mean slopes stay unit"),
    PFC_E(beckmann, pf_beckmann_facing_area, 0, "any-length w, stats incl. singular", ">= 0; max(A, 0) for zero deviation"),
    PFC_E(beckmann, pf_beckmann_light_lambda, 0, "nu 0 or 1e-20 <= |nu| <= 2^8, rs and wz in [1e-6, 1]", ">= 0; grows as 0.28 / nu as nu -> 0+"),
    PFC_E(beckmann, pf_beckmann_light_lambda_stats, 0, "unit wi above the macrosurface, stats", ">= 0"),
    PFC_E(beckmann, pf_beckmann_projected_area, 0, "unit w (grazing, below), stats", "clamped at 0 on/below the mean plane"),
    PFC_E(beckmann, pf_beckmann_lambda, PFC_WIDE, "any-length w, stats", "PF_LAMBDA_MAX on/below the mean plane"),
    PFC_E(beckmann, pf_beckmann_g1, PFC_WIDE, "any-length w, stats", "0 on/below the mean plane"),
    PFC_E(beckmann, pf_beckmann_masking_shadowing, PFC_WIDE, "any-length wo, wi, stats", "0 when either direction is on/below the mean plane"),
    PFC_E(beckmann, pf_fresnel_schlick, 0, "f0 in [0, 1], cos in [-1, 1]", "cos clamped to [0, 1]; f0 = 1 gives exactly 1"),
    PFC_E(beckmann, pf_leadr_specular, 0, "unit wo, wi (grazing, below), stats from pf_slope_moments_stats (var >= 1e-6), f0 in [0, 1]", "0 on/below the macrosurface (a light below the mesosurface has Lambda_i capped, not 0); peak of D ~ 1/(2 pi sqrt(det)) large for var -> 1e-6 (1.6e5)"),
    PFC_E(beckmann, pf_leadr_specular_masking, 0, "as pf_leadr_specular", "as pf_leadr_specular"),
    PFC_E(beckmann, pf_beckmann_base_masking, 0, "unit wo, wi (grazing, below), stats from pf_slope_moments_stats, base_var >= 0", "in [0, 1]; 1 for base_var 0; meaningless (finite) for a direction below the macrosurface"),
    PFC_E(beckmann, pf_leadr_specular_base, 0, "as pf_leadr_specular, base_var >= 0", "as pf_leadr_specular"),
    PFC_E(beckmann, pf_leadr_specular_point, 0, "unit wo, any-length to_light (zero, 2^+-40), stats, f0", "0 for a zero to_light; 1/|to_light|^2 falloff overflows for |to_light| < ~1e-19 (f)"),
    /* moments */
    PFC_E(moments, pf_depth_moments2_make, 0, "moments of two depths in [0, 1] mixed, +-2^-20 rounding", "constructor"),
    PFC_E(moments, pf_depth_moments4_make, 0, "as depth2", "constructor"),
    PFC_E(moments, pf_evsm_moments_make, 0, "EVSM moments, c in [0, 44]", "constructor"),
    PFC_E(moments, pf_depth_moments2_from_depth, 0, "z in [0, 1]", "-"),
    PFC_E(moments, pf_depth_moments4_from_depth, 0, "z in [0, 1]", "-"),
    PFC_E(moments, pf_evsm_warp_pos, 0, "z in [0, 1], c in [0, 44]", "exp(c): finite for c <= 88 (the caller keeps c <= 44 so squares stay finite)"),
    PFC_E(moments, pf_evsm_warp_neg, 0, "z in [0, 1], c in [0, 44]", "as warp_pos"),
    PFC_E(moments, pf_evsm2_from_depth, 0, "z in [0, 1], c in [0, 44]", "p^2 = exp(2c) near FLT_MAX at c = 44"),
    PFC_E(moments, pf_evsm_moments_from_depth, 0, "z in [0, 1], c in [0, 44]", "as evsm2"),
    PFC_E(moments, pf_esm_log_from_depth, 0, "z in [0, 1], c in [0, 2^12]", "log space: finite for any c"),
    PFC_E(moments, pf_esm_log_combine2, 0, "l = c z (c <= 2^12), weights in [0, 1] with w0 + w1 > 0", "max taken over the logs of positive weight (a zero weight on the larger log no longer gives log(0)); both weights <= 0: -PF_REAL_MAX"),
    PFC_E(moments, pf_depth_moments2_add, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments2_scale, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments4_add, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments4_scale, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_evsm_moments_add, 0, PFC_LIN " (E[p^2] up to exp(88))", "sum of two E[p^2] near exp(88) overflows float: add only weighted texels"),
    PFC_E(moments, pf_evsm_moments_scale, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_make, 0, "f +-2^16, variance incl. slightly negative", "constructor"),
    PFC_E(moments, pf_scalar_moments_from_value, 0, "f +-2^40", "f^2 overflows past 1.8e19 (f)"),
    PFC_E(moments, pf_scalar_moments_add, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_scale, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_mean, 0, "scalar moments", "-"),
    PFC_E(moments, pf_scalar_moments_variance, 0, "scalar moments (variance slightly negative)", "clamped at 0 (NaN gives 0); cancellation for |mean| >> deviation"),
    PFC_E(moments, pf_scalar_moments_deviation, 0, "scalar moments", "as variance"),
    PFC_E(moments, pf_normal_avg_from_normal, 0, "any-length n (zero, 2^+-40)", "zero vector gives (0, 0, 1)"),
    PFC_E(moments, pf_normal_avg_from_slope, 0, "slopes +-2^60", "scaled normalization: huge slopes stay unit"),
    PFC_E(moments, pf_mip_next_size, 0, "every int", "0 for n < 1"),
    PFC_E(moments, pf_mip_weights3, 0, "every int j, n", "(0, 0, 0) for n < 1; j clamped"),
    PFC_E(moments, pf_slope_moments_lerp, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_slope_moments_reduce2x2, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_slope_moments_reduce3, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_slope_moments_reduce3x3, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_slope_moments_accumulate, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_slope_moments_bilinear, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_lerp, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_reduce2x2, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_reduce3, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_reduce3x3, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_accumulate, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_scalar_moments_bilinear, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments2_lerp, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments2_reduce2x2, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments2_reduce3, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments2_reduce3x3, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments2_accumulate, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments2_bilinear, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments4_lerp, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments4_reduce2x2, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments4_reduce3, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments4_reduce3x3, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments4_accumulate, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_depth_moments4_bilinear, 0, PFC_LIN, PFC_LINREG),
    PFC_E(moments, pf_evsm_moments_lerp, 0, PFC_LIN " (E[p^2] up to exp(88))", "weights applied before summing: stays finite at c = 44"),
    PFC_E(moments, pf_evsm_moments_reduce2x2, 0, PFC_LIN " (E[p^2] up to exp(88))", "midpoints of midpoints, a + (b - a)/2: -ffast-math cannot factor them into a sum of four, so finite at c = 44 in every build"),
    PFC_E(moments, pf_evsm_moments_reduce3, 0, PFC_LIN " (E[p^2] up to exp(88))", "weights applied before summing: stays finite at c = 44"),
    PFC_E(moments, pf_evsm_moments_reduce3x3, 0, PFC_LIN " (E[p^2] up to exp(88))", "weights applied before summing: stays finite at c = 44"),
    PFC_E(moments, pf_evsm_moments_accumulate, 0, PFC_LIN " (E[p^2] up to exp(88))", "acc + w t: acc near exp(88) plus a texel overflows (normalize as you go)"),
    PFC_E(moments, pf_evsm_moments_bilinear, 0, PFC_LIN " (E[p^2] up to exp(88))", "weights applied before summing: stays finite at c = 44"),
    PFC_E(moments, pf_normal_avg_lerp, 0, "|n| <= 1 vectors, convex weights", PFC_LINREG),
    PFC_E(moments, pf_normal_avg_reduce2x2, 0, "|n| <= 1 vectors", PFC_LINREG),
    PFC_E(moments, pf_normal_avg_reduce3, 0, "|n| <= 1 vectors, convex weights", PFC_LINREG),
    PFC_E(moments, pf_normal_avg_reduce3x3, 0, "|n| <= 1 vectors, convex weights", PFC_LINREG),
    PFC_E(moments, pf_normal_avg_accumulate, 0, "|n| <= 1 vectors, w in [0, 1]", PFC_LINREG),
    PFC_E(moments, pf_normal_avg_bilinear, 0, "|n| <= 1 vectors, fx, fy in [0, 1]", PFC_LINREG),
    PFC_E(moments, pf_lse_arg, 0, "+-2^40", "floored at -80"),
    PFC_E(moments, pf_esm_log_reduce2x2, 0, "logs c z (c <= 2^12) and -PF_REAL_MAX (empty)", "log-sum-exp: finite for finite logs"),
    PFC_E(moments, pf_esm_log_reduce3, 0, "logs as reduce2x2, convex weights", "all weights <= 0: -PF_REAL_MAX"),
    PFC_E(moments, pf_esm_log_reduce3x3, 0, "logs as reduce2x2, convex weights", "as reduce3"),
    PFC_E(moments, pf_esm_log_bilinear, 0, "logs as reduce2x2, fx, fy in [0, 1]", "as reduce3"),
    PFC_E(moments, pf_esm_log_sum_make, 0, "sums built by _first and _add", "constructor"),
    PFC_E(moments, pf_esm_log_sum_first, 0, "log, w in [0, 1]", "w <= 0: the empty sum"),
    PFC_E(moments, pf_esm_log_sum_add, 0, "log, w in [0, 1]", "w <= 0 skipped; a new maximum rescales the sum by exp(<= 0)"),
    PFC_E(moments, pf_esm_log_sum_mean, 0, "sums built by _first and _add", "empty: -PF_REAL_MAX"),
    PFC_E(moments, pf_height_slope_central, 0, "heights +-2^20, spacing [2^-20, 2^20]", "spacing 0 divides by 0 (outside the domain)"),
    PFC_E(moments, pf_height_slope_edge, 0, "heights +-2^20, spacing [2^-20, 2^20]", "as central"),
    PFC_E(moments, pf_slope_moments_from_heights, 0, "heights +-2^20, spacings [2^-20, 2^20], scale +-16", "squared slopes overflow float past ~1.8e19"),
    /* encode */
    PFC_E(encode, pf_unorm_decode, 0, "s in [0, 1], offset +-2^20, scale [0, 2^20]", "affine: in [offset, offset + scale]"),
    PFC_E(encode, pf_slope_moments_decode, 0, "channels in [0, 1], encoding as pf_encode_ranges makes it (+-2^20, reference +-2^10)", "finite"),
    PFC_E(encode, pf_oct_hemi_decode, 0, "su, sv in [0, 1]", "unit vector, z >= 0; outside [0, 1] clamped"),
    PFC_E(encode, pf_vmf_lobe_decode, 0, "channels in [0, 1], log kappa +-16, span [0, 32], amp scale [0, 1]", "kappa clamped by pf_vmf_lobe_make"),
    /* toksvig */
    PFC_E(toksvig, pf_toksvig_variance, 0, "length in [0, 1 + 1/16] (0, tiny, > 1)", "length clamped to [1e-4, 1]: > 1 gives 0, -> 0 gives 9999"),
    PFC_E(toksvig, pf_toksvig_variance_from_normal, 0, "unit direction times a length as above", "as variance"),
    PFC_E(toksvig, pf_toksvig_factor, 0, "length as above, alpha in [0, 2^40]", "alpha < 0 read as 0 (factor 1); range [0, 1]"),
    PFC_E(toksvig, pf_toksvig_exponent, 0, "alpha [0, 2^40], var incl. negative", "var < 0 or NaN read as 0; alpha' <= alpha"),
    PFC_E(toksvig, pf_toksvig_normalization, 0, "alpha, alpha' = exponent(alpha, var)", "(1 + alpha')/(1 + alpha) in (0, 1]"),
    PFC_E(toksvig, pf_toksvig_lobe, 0, "cos in [-1, 1], alpha, var", "cos clamped to [0, 1]; pow(0, 0) = 1 at alpha' = 0"),
    PFC_E(toksvig, pf_toksvig_beckmann_m, 0, "m in [0, 2^10], var", "m^2 overflows past 1.8e19 (f)"),
    PFC_E(toksvig, pf_toksvig_ggx_alpha, 0, "a in [0, 2^10], var", "as beckmann_m"),
    PFC_E(toksvig, pf_blinn_phong_to_beckmann, 0, "alpha_p +-2^100", "alpha_p < 0 read as 0 (m = 1)"),
    PFC_E(toksvig, pf_beckmann_to_blinn_phong, 0, "m +-2^20", "|m| floored at 1e-18 (result 2e36, finite); m >= 1 gives 0"),
    /* shadow */
    PFC_E(shadow, pf_shadow_chebyshev_upper, PFC_WIDE, "m1, x +-2^60, m2 [0, 2^120], min_variance >= 0", "scaled by max(|m1|, |x|): no overflow; NaN moments give 1"),
    PFC_E(shadow, pf_shadow_reduce_bleeding, PFC_WIDE, "lit, threshold in [0, 1]", "threshold clamped to [0, 0.999]"),
    PFC_E(shadow, pf_shadow_vsm, PFC_WIDE, "depth moments of 2 depths (+ rounding, all-zero), d, bleed in [0, 1], min_variance >= 0", "negative variance raised to min_variance; light bleeding behind overlapping occluders (upper bound)"),
    PFC_E(shadow, pf_shadow_esm, PFC_WIDE, "log mean c z, d in [0, 1], c <= 2^12", "exponent clamped to [-80, 0]: returns >= 1.8e-35, never exactly 0; leaks exp(-c g)"),
    PFC_E(shadow, pf_shadow_evsm2, PFC_WIDE, "EVSM moments at c in [0, 44] (incl. 0, 44), d, bleed in [0, 1]", "values scaled to <= 1 before Chebyshev: no overflow at c = 44; c = 0 degenerates to a constant warp"),
    PFC_E(shadow, pf_shadow_evsm4, PFC_WIDE, "as evsm2, both warps", "as evsm2"),
    PFC_E(shadow, pf_shadow_msm_bounds, PFC_WIDE, "moments of 2 depths (+ rounding, all-zero), d, bias in [0, 1], depth_bias +-1/16", "singular Hankel matrix (point mass, two atoms, depths 0/1): pivots floored, roots clamped to 1e4, divisions clamped"),
    PFC_E(shadow, pf_shadow_msm, PFC_WIDE, "as msm_bounds", "as msm_bounds"),
    PFC_E(shadow, pf_shadow_msm_hausdorff, PFC_WIDE, "as msm_bounds", "as msm_bounds; the four-atom form's denominators floored, min with the Hamburger bound"),
    PFC_E(shadow, pf_msm_quantize_moments, 0, "as msm_bounds (moments)", "affine: coefficients up to 82, so finite below ~PF_REAL_MAX/400"),
    PFC_E(shadow, pf_msm_dequantize_moments, 0, "the quantized moments of msm_bounds' moments", "affine: finite below ~PF_REAL_MAX/4"),
    PFC_E(shadow, pf_shadow_msm16, PFC_WIDE, "the quantized moments of msm_bounds' moments, d, bias, depth_bias as msm_bounds", "as msm_bounds, floors for UNORM16 noise"),
    PFC_E(shadow, pf_shadow_msm16_hausdorff, PFC_WIDE, "as msm16", "as msm_hausdorff"),
    PFC_E(moments, pf_csm_pair_make, 0, "CSM pair of a two-depth mixture (or all zero)", "stores its arguments"),
    PFC_E(moments, pf_csm_pair_from_depth, 0, "z in [0, 1], pair -1 .. 40", "cos/sin of (4j + 1) pi z, (4j + 3) pi z: in [-1, 1]"),
    PFC_E(moments, pf_csm_pair_add, 0, PFC_LIN " (CSM: [-1, 1])", PFC_LINREG),
    PFC_E(moments, pf_csm_pair_scale, 0, PFC_LIN " (CSM: [-1, 1])", PFC_LINREG),
    PFC_E(moments, pf_csm_pair_lerp, 0, PFC_LIN " (CSM: [-1, 1])", PFC_LINREG),
    PFC_E(moments, pf_csm_pair_reduce2x2, 0, PFC_LIN " (CSM: [-1, 1])", PFC_LINREG),
    PFC_E(moments, pf_csm_pair_reduce3, 0, PFC_LIN " (CSM: [-1, 1])", PFC_LINREG),
    PFC_E(moments, pf_csm_pair_reduce3x3, 0, PFC_LIN " (CSM: [-1, 1])", PFC_LINREG),
    PFC_E(moments, pf_csm_pair_accumulate, 0, PFC_LIN " (CSM: [-1, 1])", PFC_LINREG),
    PFC_E(moments, pf_csm_pair_bilinear, 0, PFC_LIN " (CSM: [-1, 1])", PFC_LINREG),
    PFC_E(shadow, pf_csm_sum_make, 0, "a begun series", "stores its arguments"),
    PFC_E(shadow, pf_csm_sum_begin, PFC_WIDE, "d, offset in [0, 1]", "one cos/sin; the rotation by 2 pi e is a unit vector"),
    PFC_E(shadow, pf_csm_sum_add_harmonic, PFC_WIDE, "filtered cos/sin of any finite value", "inputs clamped to [-1, 1]: bounded"),
    PFC_E(shadow, pf_csm_sum_add, PFC_WIDE, "up to 32 harmonics of a two-depth mixture", "bounded: |value| <= 1/2 + sum 4/((2k - 1) pi)"),
    PFC_E(shadow, pf_csm_sum_lit, PFC_WIDE, "a series, any finite scale", "clamped to [0, 1]"),
    PFC_E(shadow, pf_shadow_csm, PFC_WIDE, "pairs of a two-depth mixture, d, offset, scale any finite, terms -2 .. 20", "terms clamped to [1, 16]; clamped to [0, 1]"),
    /* gaussgrid */
    PFC_E(gaussgrid, pf_gg_node, 0, "set in [-1, 3], n in [-2, 12], every int j", "n clamped to [1, 9]; unknown set read as uniform; j outside [0, n) gives 0 (range tested first: no int overflow)"),
    PFC_E(gaussgrid, pf_gg_weight, 0, "set, n as pf_gg_node, every int j", "0 outside [0, n)"),
    PFC_E(gaussgrid, pf_gg_node_variance, 0, "set in [-1, 3], n in [-2, 12]", "uniform N = 5 gives 0.866 (not 1)"),
    PFC_E(gaussgrid, pf_gg_uniform_lambda, 0, "every int n", "0 for n <= 1"),
    PFC_E(gaussgrid, pf_gg_uniform_node_any, 0, "n in [-2, 64], j in [-2, 66], lambda [0, 16]", "0 for n <= 1"),
    PFC_E(gaussgrid, pf_gg_uniform_weight_any, PFC_SLOW, "n in [-2, 64], j in [-2, 66], lambda [0, 16]", "n exps per call; 0 outside [0, n), 1 for n <= 1; exps relative to the central node: huge lambda leaves the central weights, far ones underflow to 0"),
    PFC_E(gaussgrid, pf_gg_uniform_variance_any, PFC_SLOW, "n in [-2, 64], lambda [0, 16]", "0 for n <= 0"),
    PFC_E(gaussgrid, pf_gg_grid_make, 0, "unit wo (grazing, below), stats incl. singular/negative variance, any set, n in [-1, 12]", "negative variance read as 0, |r| clamped to 1; inv_proj = 0 at/below the macrosurface, 1/P_o (facing area) below the mesosurface"),
    PFC_E(gaussgrid, pf_gg_grid_count, 0, "grids as grid_make", "N^2 with N in [1, 9]"),
    PFC_E(gaussgrid, pf_gg_sample_nodes, 0, "grids, nodes +-2^3, weights [0, 1]", "as pf_gg_sample_at"),
    PFC_E(gaussgrid, pf_gg_sample_at, 0, "grids, every int i", "index outside: weight 0"),
    PFC_E(gaussgrid, pf_gg_jacobian, 0, "unit wn, wo", "-"),
    PFC_E(gaussgrid, pf_gg_env_sample_at, 0, "grids, every int i", "reflected direction below the mesosurface: weight exactly 0; cos_d clamped to [0, 1]"),
    PFC_E(gaussgrid, pf_gg_env_lod, 0, "solid angle [0, 2^40], texel [2^-40, 2^4]", "0 when the sample is smaller than a texel"),
    PFC_E(gaussgrid, pf_sh9_make, 0, "coefficients +-2^10", "constructor"),
    PFC_E(gaussgrid, pf_sh9_constant, 0, "radiance +-2^40", "-"),
    PFC_E(gaussgrid, pf_sh9_add_scaled, 0, "coefficients +-2^10, s +-2^10", PFC_LINREG),
    PFC_E(gaussgrid, pf_sh9_add_directional, 0, "coefficients, unit dir, e [0, 2^20]", PFC_LINREG),
    PFC_E(gaussgrid, pf_sh9_irradiance, 0, "coefficients, unit n", "order-2 SH: may ring below 0 (no bound)"),
    PFC_E(gaussgrid, pf_gg_sh9_add_light, 0, "sh, grid, unit dir (grazing, below), e", "below the mesosurface: weight 0"),
    PFC_E(gaussgrid, pf_gg_sh9_add_environment, 0, "sh, grid, env sh", PFC_LINREG),
    PFC_E(gaussgrid, pf_gg_diffuse_sh, PFC_SLOW, "grid, sh", "N^2 irradiance evaluations; SH ringing may give < 0; 0 for a view below the mesosurface"),
    PFC_E(gaussgrid, pf_gg_diffuse_sh_rgb, PFC_SLOW, "grid, 3 sh", "as diffuse_sh"),
    PFC_E(gaussgrid, pf_gg_diffuse_directional, PFC_SLOW, "grid, unit wi (grazing, below)", "0 when light or view is on/below the mesosurface"),
    /* height */
    PFC_E(height, pf_height_pdf, PFC_WIDE, "every finite z", "0 past |z| = 13 (f) / 37.5 (d)"),
    PFC_E(height, pf_height_cdf, PFC_WIDE, "every finite z", "lower tail relatively accurate; 1 - tiny rounds to 1"),
    PFC_E(height, pf_height_log_cdf, PFC_WIDE, "every finite z", "z clamped at -1e4 (log Phi >= -5e7); NaN read as -1e4"),
    PFC_E(height, pf_height_visibility, PFC_WIDE, "z +-2^12, Lambda [0, 1e30] (+ negative, above)", "Lambda clamped to [0, 1e30] (NaN -> 0); error ~ eps (1 + |log V| + Lambda z^2)"),
    PFC_E(height, pf_height_mean_visibility, PFC_WIDE, "Lambdas as above", "both at PF_LAMBDA_MAX: 1/2; range (0, 1]"),
    PFC_E(height, pf_height_joint_visibility, PFC_WIDE, "Lambdas as above", "range (0, 1]"),
    PFC_E(height, pf_height_attribute_mean, 0, "a0, amplitude +-2^20, Lambdas", "finite for every Lambda; a0, amplitude beyond sqrt(PF_REAL_MAX)/4 may overflow, as the exact value"),
    PFC_E(height, pf_height_dist_make, PFC_WIDE, "mean +-2^20, dev [0, 2^20]", "constructor"),
    PFC_E(height, pf_visible_height_published, PFC_WIDE, "Lambda sum as above", "published fit: mean off by up to 0.13 sigma_h, deviation 5.3%, for Lambda <= 1900 (growing beyond)"),
    PFC_E(height, pf_visible_height, PFC_WIDE, "Lambda sum as above", "fit: 9.5e-6 / 6.7e-5 relative up to PF_LAMBDA_MAX"),
    PFC_E(height, pf_visible_height_exact, PFC_WIDE | PFC_SLOW, "Lambda sum as above", "64-node quadrature (~1000x the fit); rounding-limited in float"),
    PFC_E(height, pf_height_dist_rescale, 0, "dist, mean_h +-2^20, sigma_h [0, 2^20]", PFC_LINREG),
    PFC_E(height, pf_height_dist_add_noise, 0, "dist, mu_r +-2^20, sigma_r [0, 2^20]", "variances added: sigma^2 overflows past 1.8e19 (f)"),
    PFC_E(height, pf_height_colour_dist, 0, "Lambdas, heights, noise as above", "as visible_height + rescale + add_noise"),
    PFC_E(height, pf_gauss_cdf, PFC_WIDE, "x, mean +-2^30, sigma (0, negative, tiny, huge)", "sigma <= 0: the step (1/2 at x = mean); standardized position clamped to +-40"),
    PFC_E(height, pf_gauss_step, PFC_WIDE, "as gauss_cdf", "as gauss_cdf"),
    PFC_E(height, pf_gauss_segment_weights, PFC_WIDE, "x0 <= x1 (jumps incl.), mean, sigma as above", "x1 <= x0 gives (0, 0); narrow segments (< sigma/8) by Taylor series"),
    PFC_E(height, pf_gauss_smoothstep, PFC_WIDE, "e0 <= e1, mean, sigma as above", "e1 <= e0: the step; narrow ramp (< sigma/3) by series; range [0, 1]"),
    PFC_E(height, pf_transfer_moments_make, PFC_WIDE, "moments +-2^20 / [0, 2^40]", "constructor"),
    PFC_E(height, pf_transfer_moments_add, PFC_WIDE, "segment moments", PFC_LINREG),
    PFC_E(height, pf_transfer_end_moments, 0, "value +-2^40, mass [0, 1]", "v^2 overflows past 1.8e19 (f)"),
    PFC_E(height, pf_transfer_segment_moments, 0, "knots x0 <= x1 +-2^20, g +-2^10, mean, sigma", "x1 <= x0 gives zeros; E[g^2] clamped at 0 (cancellation); g'^2 = ((g1-g0)/(x1-x0))^2 huge for tiny segments, overflows past 1.8e19 (f)"),
    PFC_E(height, pf_transfer_height, PFC_WIDE, "segment moments", "dev clamped at 0 (cancellation E[g^2] - E[g]^2)"),
    PFC_E(height, pf_transfer_slope_stats, 0, "segment moments, filtered slope moments", "as pf_slope_stats_from_moments; products E[g'^2] E[x^2] overflow as their exact value"),
    /* masks */
    PFC_E(horizon, pf_hdf_moments_make, 0, "mean +-2, deviation [0, 1.6], E[S T] +-16", PFC_LINREG),
    PFC_E(horizon, pf_hdf_moments_lerp, 0, PFC_LIN, PFC_LINREG),
    PFC_E(horizon, pf_hdf_legendre_make, 0, "coefficients of a step", PFC_LINREG),
    PFC_E(horizon, pf_hdf_legendre_coeff, 0, "index -2 .. 10", "0 outside 0 .. 7"),
    PFC_E(horizon, pf_hdf_legendre_lerp, 0, PFC_LIN, PFC_LINREG),
    PFC_E(horizon, pf_horizon_azimuth_of, 0, "unit directions, n 1 .. 64", "w_xy = 0 or NaN: index 0"),
    PFC_E(horizon, pf_horizon_elevation, 0, "unit directions", "[-pi/2, pi/2]"),
    PFC_E(horizon, pf_horizon_visibility_ramp, 0, "HDF moments, elevation +-2", "negative variance as 0; NaN gives 0"),
    PFC_E(horizon, pf_horizon_visibility_gauss, 0, "HDF moments, elevation +-2", "erfc past 8 returned as 0"),
    PFC_E(horizon, pf_horizon_visibility_legendre, 0, "step coefficients, k 0 .. 9, x in [-1, 1]", "k clamped to 1 .. 8; clamped to [0, 1]"),
    PFC_E(horizon, pf_horizon_legendre_basis, 0, "j 0 .. 8, x in [-1, 1]", "|P^_j| <= sqrt(j + 1/2)"),
    PFC_E(horizon, pf_horizon_legendre_coeff, 0, "j 0 .. 8, s in [-1, 1]", "integral of P^_j over [s, 1]"),
    PFC_E(horizon, pf_horizon_bidir_product, 0, "fractions in [0, 1]", "V(l)"),
    PFC_E(horizon, pf_horizon_bidir_tan, 0, "fractions in [0, 1], cos in [-1, 1]", "V(v) = 0 gives V(l)"),
    PFC_E(horizon, pf_horizon_bidir_ashikhmin, 0, "fractions in [0, 1], cos, width [0, 1]", "width <= 0: beta 1 at l = v, else 0"),
    PFC_E(horizon, pf_horizon_visible_area, 0, "unit directions, HDF moments, mean slopes +-4", "clamped to [0, 2]; 0 below the mean plane"),
    PFC_E(horizon, pf_horizon_masking, 0, "unit directions, HDF moments, slope stats", "saturate(area ratio x pf_beckmann_g1)"),
    PFC_E(horizon, pf_horizon_visibility_given_slope, 0, "unit directions, HDF moments, slope stats, slopes +-4", "in [0, 1]; NaN moments 0"),
    PFC_E(horizon, pf_horizon_diffuse_directional, PFC_SLOW, "grid, unit wi (grazing, below), HDF moments", "in [0, 2/pi]; 0 below the mean plane"),
    PFC_E(horizon, pf_horizon_diffuse_lod, PFC_SLOW, "grid, unit wi, HDF moments, lods +-16", ">= 0; blend of the two diffuse terms"),
    PFC_E(horizon, pf_horizon_lod_weight, PFC_WIDE, "lod and bounds +-16, any order", "in [0, 1]; NaN gives 0"),
    PFC_E(horizon, pf_horizon_masking_lod, 0, "unit directions, HDF moments, slope stats, lods +-16", "between pf_beckmann_g1 and pf_horizon_masking"),
    PFC_E(horizon, pf_horizon_specular_visibility, 0, "unit directions, HDF moments, slope stats", "in [0, 1]; NaN moments 0"),
    PFC_E(horizon, pf_horizon_texel_stats, 0, "slope stats, base variance (negative included)", "variances >= 0"),
    PFC_E(horizon, pf_horizon_leadr_specular, 0, "unit directions, HDF moments, slope stats, base variance, f0", ">= 0, finite; 0 at or below the mean plane"),
    PFC_E(horizon, pf_horizon_leadr_specular_lod, 0, "as pf_horizon_leadr_specular, lods +-16", ">= 0; blend with pf_leadr_specular"),
    PFC_E(horizon, pf_horizon_vmf_specular, 0, "unit directions, 1-4 lobes, HDF moments, slope stats, f0", ">= 0, finite; 0 for an empty sum"),
    PFC_E(horizon, pf_horizon_vmf_specular_lod, 0, "as pf_horizon_vmf_specular, lods +-16", ">= 0; blend with pf_vmf_sum_specular"),
    PFC_E(masks, pf_mask_params_make, PFC_WIDE, "+-2^100", "constructor"),
    PFC_E(masks, pf_mask_make, 0, "any 32-bit words", "constructor"),
    PFC_E(masks, pf_masks_v_max, 0, "shape -2..3", "unknown shapes read as the square"),
    PFC_E(masks, pf_masks_params_from_plane, PFC_WIDE, "normal, offset, width, depth +-2^100", "theta in [-pi, pi], v clamped to +-2; NaN -> theta 0, v -2 (empty)"),
    PFC_E(masks, pf_masks_grid_theta, 0, "n -3..40000, i in [0, n)", "n clamped to [1, 32768]"),
    PFC_E(masks, pf_masks_grid_v, 0, "n -3..40000, j in [0, n)", "n clamped to [2, 32768]"),
    PFC_E(masks, pf_masks_index, PFC_WIDE, "theta, v +-2^100, any grid size", "index always inside the clamped table; NaN v -> empty row"),
    PFC_E(masks, pf_masks_words, 0, "any int", "0 outside [1, 128]"),
    PFC_E(masks, pf_masks_popcount, 0, "any word", "exact"),
    PFC_E(masks, pf_masks_count, 0, "any mask", "exact"),
    PFC_E(masks, pf_masks_coverage, 0, "any mask, n -3..200", "n < 1 gives 0; clamped to 1 when the mask has more bits than n"),
    PFC_E(masks, pf_masks_union, 0, "any masks", "exact"),
    PFC_E(masks, pf_masks_intersection, 0, "any masks", "exact"),
    PFC_E(masks, pf_masks_difference, 0, "any masks", "exact"),
    PFC_E(masks, pf_masks_complement, 0, "any mask, n -40..200", "n clamped to [0, 128]; bits past n are 0"),
    PFC_E(masks, pf_masks_visible_fraction, 0, "any masks, n -3..200", "as coverage"),
    /* vmf */
    PFC_E(vmf, pf_vmf_kappa_clamp, 0, "kappa 0, < 0, 2^-60 .. 2^60", "in [1e-4, 1e5]; NaN -> 1e-4"),
    PFC_E(vmf, pf_vmf_normalization, 0, "kappa 0, < 0, 2^-60 .. 2^60", "kappa clamped to [1e-4, 1e5]"),
    PFC_E(vmf, pf_vmf_mean_cosine, 0, "kappa as above", "series below 0.5 (f) / 0.1 (d)"),
    PFC_E(vmf, pf_vmf_tangent_variance, 0, "kappa as above", "(1 - 1/k)/k past 10 (f) / 20 (d)"),
    PFC_E(vmf, pf_vmf_kappa_from_tangent_variance, 0, "variance incl. negative", "48 bisection steps; clamped"),
    PFC_E(vmf, pf_vmf_lobe_eval, 0, "unit (also below-horizon) axis and direction, kappa as above", "exponent capped at 80"),
    PFC_E(vmf, pf_vmf_kappa_from_mean_length, 0, "r in [0, 1]", "r >= 1: kappa max"),
    PFC_E(vmf, pf_vmf_convolve_kappa, 0, "two kappas as above", "clamped"),
    PFC_E(vmf, pf_vmf_kappa_from_sigma, 0, "sigma +-2^20", "sigma^2 < 1e-5: kappa max"),
    PFC_E(vmf, pf_vmf_lobe_slope_stats, 0, "packed lobe, base variance", "mu.z floored at 1e-3 (slopes <= 1e3)"),
    PFC_E(vmf, pf_vmf_lobe_make, PFC_WIDE, "+-2^100", "axis rescaled onto the unit hemisphere; NaN -> 0"),
    PFC_E(vmf, pf_vmf_lobe_density, 0, "packed lobe, unit direction", "as pf_vmf_lobe_eval"),
    PFC_E(vmf, pf_vmf_lobe_ndf, 0, "packed lobe, unit direction, kappa_b", "0 for w.z <= 0; 1/w.z floored at 1e-6"),
    PFC_E(vmf, pf_vmf_lobe_ndf_slope, 0, "packed lobe, unit direction, base variance", "0 below w.z = 1e-6; det floored at 1e-12"),
    PFC_E(vmf, pf_vmf_lobe_area, 0, "packed lobe, unit direction", "mu.z floored at 1e-3"),
    PFC_E(vmf, pf_vmf_lobe_excess, 0, "packed lobe, unit direction, base variance", "sd -> 0: max(-a, 0)"),
    PFC_E(vmf, pf_vmf_lambda, 0, "+-2^40", "area <= 0: PF_LAMBDA_MAX"),
    PFC_E(vmf, pf_vmf_sum_zero, 0, "-", "constructor"),
    PFC_E(vmf, pf_vmf_sum_add, 0, "1-4 packed lobes, directions, base variance", "sums"),
    PFC_E(vmf, pf_vmf_sum_add_vmf, 0, "1-4 packed lobes, directions, base variance, kappa_b 100", "sums"),
    PFC_E(vmf, pf_vmf_sum_add_masking, 0, "packed lobe, directions, base variance", "sums"),
    PFC_E(vmf, pf_vmf_sum_stats, 0, "sums of 1-4 lobes", "as pf_slope_stats_from_moments"),
    PFC_E(vmf, pf_vmf_sum_g2, 0, "sums of 1-4 lobes, directions", "in [0, 1]"),
    PFC_E(vmf, pf_vmf_sum_g2_mixture, 0, "sums of 1-4 lobes, directions", "in [0, 1]"),
    PFC_E(vmf, pf_vmf_sum_g1_mixture, 0, "sums of 1-4 lobes, direction", "in [0, 1]"),
    PFC_E(vmf, pf_vmf_pixel_make, 0, "directions (grazing, below), base variance", "finite"),
    PFC_E(vmf, pf_vmf_sum_without_base, 0, "sums of 1-4 lobes, base variance", "sums"),
    PFC_E(vmf, pf_vmf_sum_specular_base, 0, "sums of 1-4 lobes, directions, base variance", ">= 0"),
    PFC_E(vmf, pf_vmf_sum_add_texel, 0, "1-4 texels as the fit writes them, directions, base variance", "sums; specular >= 0"),
    PFC_E(vmf, pf_vmf_sum_add_texel_mixture, 0, "1-4 texels as the fit writes them, directions, base variance", "sums, excesses >= 0; G2 in [0, 1]"),
    PFC_E(vmf, pf_vmf_sum_specular, 0, "sums of 1-4 lobes, directions, f0 [0, 1]", ">= 0, 0 below the macrosurface"),
    PFC_E(vmf, pf_vmf_sum_specular_mixture, 0, "sums of 1-4 lobes (vMF form), directions, f0", ">= 0"),
    PFC_E(vmf, pf_vmf_sum_specular_unmasked, 0, "sums of 1-4 lobes, directions, f0 [0, 1]", ">= 0, 0 below the mesosurface"),
    PFC_E(vmf, pf_vmf_facet_specular, 0, "slopes +-2^4, base variance >= 1e-6, unit directions (grazing, below), f0 [0, 1]", ">= 0, 0 below the macrosurface or the facet"),
    PFC_E(vmf, pf_vmf_scale_coords, 0, "directions, theta_max +-2^4", "each coordinate in [0, 1]"),
    PFC_E(vmf, pf_vmf_scale_texel_pos, 0, "u +-2^20, n in [-2, 64]", "in [0, max(n - 1, 0)]"),
    PFC_E(vmf, pf_vmf_scale_trilinear, 0, "8 values and 3 fractions in [0, 1]", "in [0, 1] (rounding)"),
    PFC_E(vmf, pf_vmf_scale_apply, 0, "T, S +-2^20, f [0, 1]", ">= 0"),
    PFC_E(specaa, pf_specaa_kernel_make, PFC_WIDE, "+-2^60", "the three members as given"),
    PFC_E(specaa, pf_specaa_kernel_normal, 0, "derivatives: unit direction x [0, 2^8] (0, tiny, huge), sigma2, kappa in [0, 1]", "in [0, kappa]; huge -> kappa"),
    PFC_E(specaa, pf_specaa_kernel_halfvector, 0, "unit h (grazing, below), derivatives as above, sigma2, kappa in [0, 1]", "in [0, kappa]"),
    PFC_E(specaa, pf_specaa_kernel_aniso, 0, "derivatives as above, sigma2, kappa in [0, 1]", "variances >= 0, trace <= kappa"),
    PFC_E(specaa, pf_specaa_kernel_trace, 0, "kernels of pf_specaa_kernel_aniso", ">= 0"),
    PFC_E(specaa, pf_specaa_alpha, 0, "alpha in [0, 2^4], k in [0, 1]", "in [0, 1]"),
    PFC_E(specaa, pf_specaa_alpha_projected, 0, "alpha in [0, 2^4], k in [0, 2^60]", "in [0, 1]"),
    PFC_E(specaa, pf_specaa_alpha_from_variance, 0, "alpha, gain in [0, 2^4], variance (slightly negative too)", ">= 0"),
    PFC_E(specaa, pf_specaa_projected_variance, 0, "v in [0, 2^60]", "in [0, 1/4]"),
    PFC_E(specaa, pf_specaa_slope_variance_from_projected, 0, "v in +-4", "in [0, 625]"),
    PFC_E(specaa, pf_specaa_slope_stats, 0, "stats, k in [0, 1]", "finite"),
    PFC_E(specaa, pf_specaa_slope_stats_aniso, 0, "stats, kernels of pf_specaa_kernel_aniso", "finite"),
    PFC_E(specaa, pf_specaa_kernel_cross, 0, "derivatives as above, mean-slope gradients +-2^8, sigma2 in [0, 1]", "finite"),
    PFC_E(specaa, pf_specaa_slope_stats_cross, 0, "stats, kernels of pf_specaa_kernel_aniso and _cross", "finite, variances >= 0"),
    PFC_E(specaa, pf_specaa_slope_stats_quad, 0, "four filtered moments, base variance, derivatives as above, sigma2, kappa in [0, 1]", "finite"),
    PFC_E(specaa, pf_specaa_leadr_specular, 0, "as pf_leadr_specular, derivatives as above", ">= 0"),
    PFC_E(specaa, pf_specaa_mean_shift, 0, "unit wo (grazing, below), k in [0, 2^8]", "each component in +-PF_SPECAA_SHIFT_MAX"),
    PFC_E(specaa, pf_specaa_mean_shift_surface, 0, "position and normal derivatives as above, unit wo, sigma2 in [0, 1]", "each component in +-PF_SPECAA_SHIFT_MAX"),
    PFC_E(specaa, pf_specaa_slope_stats_shift, 0, "stats, shift +-2^8", "finite"),
    PFC_E(specaa, pf_specaa_leadr_specular_curved, 0, "as pf_leadr_specular, derivatives as above", ">= 0"),
    PFC_E(specaa, pf_specaa_vmf_kappa, 0, "kappa as pf_vmf's, k in [0, 2^60]", "clamped kappa"),
    PFC_E(specaa, pf_specaa_vmf_lobe, 0, "packed lobe, k in [0, 2^60]", "as pf_vmf_lobe_make"),
};
#define PFC_COUNT ((int)(sizeof pfc_table / sizeof pfc_table[0]))

/* Public functions deliberately without an entry (checked by the coverage scripts, which
   also require every name here to exist). */
/* The pointer-taking CPU-only functions (PF_CPU_DEF) have no entry here: tests/fuzz/pf_buffers.h
   drives them (guarded buffers, return codes), and tests/fuzz/coverage.sh checks its table. */

/* Run entry e once on the words of c (the ctx keeps its word source). */
static void pfc_call(pfc_ctx *c, const pfc_entry *e)
{
    pfc_reset(c);
    c->wide = (e->flags & PFC_WIDE) != 0;
    e->fn(c);
    if (c->skip) c->bad = 0;
}

#endif /* PF_CALLS_H */

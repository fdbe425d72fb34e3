/* tests/fuzz/pf_buffers.h - drivers for the pointer-taking CPU-only functions (pf_moments.h
   pyramids, builders and samplers; pf_height.h colour-map arrays and tables; pf_gaussgrid.h's
   Gauss-Hermite generator), checked against the rules at the end of include/pf_core.h
   ("CPU only: sizes and errors").

   Shared by the libFuzzer harnesses tests/fuzz/fuzz_<module>_buffers.c and the stability sweep
   (bench/stability.c, section "pointer-taking functions"). Test code: globals, stdio, mmap.

   ONE CALL OF A DRIVER draws every size and argument from the word source of pf_calls.h
   (fuzzer bytes, or the seeded generator of the sweep), computes the return code the contract
   allows INDEPENDENTLY of the library (its own side, texel-count and buffer-size arithmetic in
   long long, checked by division), then:
   - rejected arguments: every pointer it passes is a small canary-filled guarded buffer (or
     NULL, when the draw asks for one); it asserts the error code (PF_ERR_ARG or PF_ERR_SIZE;
     either is accepted when both kinds of fault are present) and that no canary changed;
   - accepted arguments: every buffer is mapped at EXACTLY its documented size (pfb_map) with a
     PROT_NONE guard page on both sides, the buffer touching one of them (the end one usually,
     the start one in 1 draw of 4) and canary bytes in the rest of its page, so any access out
     of bounds faults (ASan does not see mmap'd memory, the guards do). Mappings are
     MAP_NORESERVE and mostly untouched, so huge accepted maps (a 2^24 x 1 pyramid, 2^20 x 2^19,
     up to PF_MAX_REALS reals) cost address space only. Samplers and the table lookup read a
     few texels: they run on maps of every accepted size. Builders and filters touch their whole
     buffers: they run only when every buffer holds at most pfb_work_cap reals (2^16 in the
     fuzzers: 256 KB float, 512 KB double; 2^12 in the sweep), and are still called with huge
     sizes whose rejection is cheap;
   - outputs: every output the call must write is written (no canary left), finite where the
     contract promises it (finite inputs in the documented domain), and within the range the
     mathematics allows (a pyramid level is a convex combination of level 0; a filtered
     colour map lies between its knot values; a sample equals an independent long double
     bilinear/trilinear reference on small maps, and 0 on the untouched zero pages of huge
     ones). Sample coordinates u, v and lod range over every float: NaN, inf, huge (|u| >= 1e6
     must clamp, not jump to 0), subnormal.
   A violation calls pfb_fail: the fuzzers print a reproducer line and trap; the sweep counts it
   (pfb_tally). Every mapping is unmapped at the end of each driver call (pfb_release_all,
   also after a fault caught by the sweep). */
#ifndef PF_BUFFERS_H
#define PF_BUFFERS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdarg.h>
#include <limits.h>
#include <sys/mman.h>
#include <unistd.h>
#include "pf_calls.h"
#include "pf_horizon.h"
#include "pf_specaa.h"

/* The checks compute in long double on purpose (independent references): the float build's
   -Wdouble-promotion, meant for library code, is silenced for this header only. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdouble-promotion"

#ifndef MAP_ANONYMOUS
#  define MAP_ANONYMOUS MAP_ANON
#endif
#ifndef MAP_NORESERVE
#  define MAP_NORESERVE 0
#endif

/* ---------------------------------------------------------------- failures and tallies */
enum { PFB_RC = 0, PFB_WROTE, PFB_NONFINITE, PFB_VALUE, PFB_OOB, PFB_KINDS };
static const char *const pfb_kind_name[PFB_KINDS] = {
    "wrong return code", "wrote on error", "non-finite output", "wrong output value", "out of bounds"
};

typedef struct pfb_tally {
    double calls, rejected_n, run; /* driver calls; of which rejected by the contract; run in full */
    double n[PFB_KINDS];
    char example[PFB_KINDS][600];
} pfb_tally;

static pfb_tally *pfb_t;        /* where pfb_fail counts (sweep), or 0 */
static int pfb_trap = 1;        /* fuzzers: print and trap on the first failure */
static long long pfb_work_cap = 1LL << 16; /* builders and filters run when buffers <= this */
static char pfb_line[600];      /* the current call, as a reproducer line */
static int pfb_failed_kinds;    /* kinds already counted for this driver call */

static void pfb_setcall(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(pfb_line, sizeof pfb_line, fmt, ap);
    va_end(ap);
    if (getenv("PFB_TRACE")) fprintf(stderr, "pfb: %s\n", pfb_line);
}

/* Set when the call drew a NaN or infinite input (coordinate, weight, range end). Under
   -ffast-math, which lets the compiler assume no such value exists, such calls are checked for
   memory safety and return codes only, not for their output values. */
static int pfb_nonfinite_input;
#ifdef __FAST_MATH__
#  define PFB_FAST 1
#else
#  define PFB_FAST 0
#endif

static void pfb_fail(int kind, const char *fmt, ...)
{
    char what[300];
    va_list ap;
    if (PFB_FAST && pfb_nonfinite_input && (kind == PFB_NONFINITE || kind == PFB_VALUE)) return;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (pfb_trap) {
        fprintf(stderr, "pf_fuzz: %s: %s\n  call: %s\n", pfb_kind_name[kind], what, pfb_line);
        __builtin_trap();
    }
    if (pfb_t && !(pfb_failed_kinds & (1 << kind))) {
        pfb_failed_kinds |= 1 << kind;
        pfb_t->n[kind] += 1;
        if (!pfb_t->example[kind][0])
        {
            size_t l = strlen(pfb_line) < 400 ? strlen(pfb_line) : 400;
            memcpy(pfb_t->example[kind], pfb_line, l);
            snprintf(pfb_t->example[kind] + l, sizeof pfb_t->example[kind] - l, " -> %.190s", what);
        }
    }
}

/* ---------------------------------------------------------------- guarded mappings
   Buffers of up to PFB_ARENA_REALS reals come from a few arenas mapped once and reused (a
   fresh page costs a page fault, over 100 us on some virtual machines, which would make the
   fuzzers 10x slower); larger ones are fresh MAP_NORESERVE mappings, unmapped after each call.
   Either way the buffer touches a PROT_NONE page on one side and has a PROT_NONE page on the
   other side beyond the canary bytes that fill the rest of its pages. */
#define PFB_MAX_MAPS 16
#define PFB_ARENAS 4
#define PFB_ARENA_REALS (1LL << 18)
static struct { unsigned char *base; size_t total; unsigned char *slack; size_t nslack; int arena; } pfb_maps[PFB_MAX_MAPS];
static int pfb_nmaps;
static size_t pfb_page;
static struct { unsigned char *base; size_t rw; int used; } pfb_arena[PFB_ARENAS];
#define PFB_SLACK_BYTE 0xA5

/* an arena's data pages [base + page, base + page + data) readable and writable, every other
   page of it PROT_NONE; 0 on failure */
static unsigned char *pfb_arena_take(size_t data)
{
    size_t full = (size_t)PFB_ARENA_REALS * sizeof(pf_real);
    int a;
    full = (full + pfb_page - 1) / pfb_page * pfb_page;
    for (a = 0; a < PFB_ARENAS && pfb_arena[a].used; ++a) {}
    if (a == PFB_ARENAS || data > full) return 0;
    if (!pfb_arena[a].base) {
        unsigned char *base = (unsigned char *)mmap(0, full + 2 * pfb_page, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (base == (unsigned char *)MAP_FAILED) return 0;
        pfb_arena[a].base = base;
        pfb_arena[a].rw = 0;
    }
    if (pfb_arena[a].rw != data) {
        unsigned char *d = pfb_arena[a].base + pfb_page;
        if (data > pfb_arena[a].rw && mprotect(d, data, PROT_READ | PROT_WRITE)) return 0;
        if (data < pfb_arena[a].rw && mprotect(d + data, pfb_arena[a].rw - data, PROT_NONE)) return 0;
        pfb_arena[a].rw = data;
    }
    pfb_arena[a].used = 1;
    return pfb_arena[a].base;
}

/* nreals pf_reals touching a PROT_NONE guard page (the end one, or the start one when
   at_start), with a guard page on the other side too; the rest of the pages canary bytes.
   0 when the mapping fails (too large for the address space). */
static int pfb_fresh; /* the next pfb_map is a fresh mapping (zero pages), not an arena */
static pf_real *pfb_map(long long nreals, int at_start)
{
    size_t bytes, data, total;
    unsigned char *base, *p;
    int arena = 1, fresh = pfb_fresh;
    pfb_fresh = 0;
    if (!pfb_page) pfb_page = (size_t)sysconf(_SC_PAGESIZE);
    if (nreals < 0 || pfb_nmaps == PFB_MAX_MAPS) return 0;
    bytes = (size_t)nreals * sizeof(pf_real);
    data = (bytes + pfb_page - 1) / pfb_page * pfb_page;
    total = data + 2 * pfb_page;
    base = nreals <= PFB_ARENA_REALS && !fresh ? pfb_arena_take(data) : 0;
    if (!base) {
        arena = 0;
        base = (unsigned char *)mmap(0, total, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
        if (base == (unsigned char *)MAP_FAILED) return 0;
        if (data && mprotect(base + pfb_page, data, PROT_READ | PROT_WRITE)) { munmap(base, total); return 0; }
    }
    p = at_start ? base + pfb_page : base + pfb_page + data - bytes;
    pfb_maps[pfb_nmaps].base = base;
    pfb_maps[pfb_nmaps].total = total;
    pfb_maps[pfb_nmaps].slack = at_start ? p + bytes : base + pfb_page;
    pfb_maps[pfb_nmaps].nslack = data - bytes;
    pfb_maps[pfb_nmaps].arena = arena;
    memset(pfb_maps[pfb_nmaps].slack, PFB_SLACK_BYTE, data - bytes);
    pfb_nmaps++;
    return (pf_real *)(void *)p;
}

/* 1 when the slack bytes of every mapping are intact */
static int pfb_slack_ok(void)
{
    int m;
    size_t k;
    for (m = 0; m < pfb_nmaps; ++m)
        for (k = 0; k < pfb_maps[m].nslack; ++k)
            if (pfb_maps[m].slack[k] != PFB_SLACK_BYTE) return 0;
    return 1;
}

static void pfb_release_all(void)
{
    int a;
    while (pfb_nmaps > 0) {
        --pfb_nmaps;
        if (!pfb_maps[pfb_nmaps].arena) munmap(pfb_maps[pfb_nmaps].base, pfb_maps[pfb_nmaps].total);
    }
    for (a = 0; a < PFB_ARENAS; ++a) pfb_arena[a].used = 0;
}

/* A canary real: a NaN with a payload no computation produces. */
static pf_real pfb_canary(void)
{
#ifdef PF_DOUBLE
    pfc_u64 u = 0x7FF4DEADBEEF5A5AULL;
#else
    pfc_u32 u = 0x7FA5A5A5u;
#endif
    pf_real x;
    memcpy(&x, &u, sizeof x);
    return x;
}
static int pfb_is_canary(pf_real x)
{
    pf_real k = pfb_canary();
    return memcmp(&x, &k, sizeof x) == 0;
}
static void pfb_fill_canary(pf_real *p, long long n)
{
    long long i;
    pf_real k = pfb_canary();
    for (i = 0; i < n; ++i) p[i] = k;
}
static long long pfb_count_changed(const pf_real *p, long long n)
{
    long long i, k = 0;
    for (i = 0; i < n; ++i) k += !pfb_is_canary(p[i]);
    return k;
}

/* The small buffer every pointer of a rejected call gets: canary-filled, guarded on both
   sides. A fixed pool of four, mapped once and kept (4 pages): a fresh page costs a page fault,
   over 100 us on some virtual machines, and rejected calls are half of all calls. */
#define PFB_SMALL 64
#define PFB_POOL 4
static pf_real *pfb_pool[PFB_POOL];
static int pfb_npool_used;
static pf_real *pfb_small(void)
{
    pf_real *p;
    if (pfb_npool_used == PFB_POOL) return 0;
    if (!pfb_pool[pfb_npool_used]) {
        unsigned char *base;
        if (!pfb_page) pfb_page = (size_t)sysconf(_SC_PAGESIZE);
        base = (unsigned char *)mmap(0, 3 * pfb_page, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (base == (unsigned char *)MAP_FAILED) return 0;
        if (mprotect(base + pfb_page, pfb_page, PROT_READ | PROT_WRITE)) return 0;
        /* ends at the guard after it; the page before it is a guard too (the rest of the page
           before the buffer is canary as well) */
        pfb_pool[pfb_npool_used] = (pf_real *)(void *)(base + 2 * pfb_page) - PFB_SMALL;
    }
    p = pfb_pool[pfb_npool_used++];
    pfb_fill_canary(p - (long long)(pfb_page / sizeof(pf_real) - PFB_SMALL), (long long)(pfb_page / sizeof(pf_real)));
    return p;
}
/* 1 when the whole page of a pool buffer is canary (no write before the buffer either) */
static int pfb_pool_page_ok(const pf_real *p)
{
    long long before = (long long)(pfb_page / sizeof(pf_real)) - PFB_SMALL;
    return pfb_count_changed(p - before, before) == 0;
}

/* ---------------------------------------------------------------- the contract's arithmetic
   Independent of include/: long long, products checked by division. */
#define PFB_MAX_SIDE ((long long)1 << 24)
#define PFB_MAX_REALS ((long long)PF_MAX_REALS)

/* acceptable results: bits PFB_A_OK, PFB_A_ARG, PFB_A_SIZE */
#define PFB_A_OK 1
#define PFB_A_ARG 2
#define PFB_A_SIZE 4
/* arg: a NULL, an unknown enum, a bad range (PF_ERR_ARG); small: a size below its minimum
   (PF_ERR_ARG); size: a side or buffer above its limit (PF_ERR_SIZE). Buffer sizes are
   computed only from sizes that are within their limits. When faults of both codes are
   present, either code is accepted (the contract orders no checks). */
typedef struct pfb_expect { int arg, small, size; } pfb_expect;
static void pfb_side(pfb_expect *e, long long n, long long min)
{
    if (n < min) e->small = 1;
    else if (n > PFB_MAX_SIDE) e->size = 1;
}
static int pfb_allowed(pfb_expect e)
{
    if (!e.arg && !e.small && !e.size) return PFB_A_OK;
    return (e.arg || e.small ? PFB_A_ARG : 0) | (e.size ? PFB_A_SIZE : 0);
}
static int pfb_rc_allowed(int rc, int allowed)
{
    return (rc == PF_OK && (allowed & PFB_A_OK)) || (rc == PF_ERR_ARG && (allowed & PFB_A_ARG)) ||
           (rc == PF_ERR_SIZE && (allowed & PFB_A_SIZE));
}
static const char *pfb_allowed_name(int a)
{
    switch (a) {
    case PFB_A_OK: return "PF_OK";
    case PFB_A_ARG: return "PF_ERR_ARG";
    case PFB_A_SIZE: return "PF_ERR_SIZE";
    default: return "PF_ERR_ARG or PF_ERR_SIZE";
    }
}
/* a * b, or -1 past PF_MAX_REALS (a, b >= 0) */
static long long pfb_mul(long long a, long long b)
{
    if (a < 0 || b < 0) return -1;
    if (b != 0 && a > PFB_MAX_REALS / b) return -1;
    return a * b;
}
static long long pfb_next(long long n) { return n >= 2 ? n / 2 : 1; }
/* levels of a valid w x h pyramid */
static int pfb_levels(long long w, long long h)
{
    int n = 1;
    while (w > 1 || h > 1) { w = pfb_next(w); h = pfb_next(h); ++n; }
    return n;
}
/* texels of the levels below `level` (all of them for level >= levels), valid sides */
static long long pfb_offset(long long w, long long h, int level)
{
    long long off = 0;
    int l, nl = pfb_levels(w, h);
    for (l = 0; l < level && l < nl; ++l) { off += w * h; w = pfb_next(w); h = pfb_next(h); }
    return off;
}
static long long pfb_level_side(long long n, int level)
{
    int l;
    for (l = 0; l < level && n > 1; ++l) n = pfb_next(n);
    return n;
}
/* reals of a pyramid (valid sides), -1 past PF_MAX_REALS */
static long long pfb_pyr_reals(long long w, long long h, long long channels)
{
    return pfb_mul(pfb_offset(w, h, 64), channels);
}

/* ---------------------------------------------------------------- drawing sizes and values */
/* An int from the whole range, biased to the edges: small, 0, negative, around 2^24 (the
   side limit), 2^30, INT_MAX, INT_MIN, powers of two +-1, the overflow points of int products
   (46341 = ceil(sqrt(2^31)), 65537). `lo_small`..`hi_small` is the common small range. */
static int pfb_int(pfc_ctx *c, int lo_small, int hi_small)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    static const int special[] = { 46340, 46341, 65535, 65536, 65537, 1 << 20, (1 << 20) + 1, 4095, 4097,
                                   16384, 32768, 1 << 12, 1 << 16, 3, 1 << 15, 0 };
    switch (PFC_R(u)) {
    case 0: return (int)(b % 16u) - 3;
    case 1: return (1 << 24) + (int)(b % 5u) - 2;
    case 2: return (1 << 30) + (int)(b % 5u) - 2;
    case 3: return INT_MAX - (int)(b % 4u);
    case 4: return (b & 1u) ? INT_MIN + (int)((b >> 1) % 4u) : -(int)(b >> 1);
    case 5: { int k = (int)(b % 31u); return (int)((1u << k) + (b >> 5) % 3u - 1u); }
    case 6: return special[b % (sizeof special / sizeof special[0])];
    case 7: return (int)(b >> 0) & INT_MAX;
    default: return lo_small + (int)(b % (pfc_u32)(hi_small - lo_small + 1));
    }
}

/* a real over the whole float range: NaN, +-inf, huge (1e6 .. PF_REAL_MAX), subnormal, 0,
   around 1e6, and `lo..hi` uniform (most draws) */
static pf_real pfb_coord(pfc_ctx *c, pf_real lo, pf_real hi)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real s = (b & 1u) ? PF_R(-1.0) : PF_R(1.0);
    switch (PFC_R(u)) {
    case 0: pfb_nonfinite_input = 1; return pfc_from_bits(0x7FC00000u);          /* NaN */
    case 1: pfb_nonfinite_input = 1; return s * pfc_from_bits(0x7F800000u);      /* +-inf */
    case 2: return s * pfc_mag(b >> 1, 20, PFC_EMAX);    /* huge: 1e6 .. max */
    case 3: return s * (PF_R(1.0e6) + (pf_real)(b % 5u) - PF_R(2.0)); /* around the old 1e6 cut */
    case 4: return s * pfc_mag(b >> 1, PFC_EMIN, -20);   /* tiny */
    case 5: return (pf_real)(int)(b % 7u) * PF_R(0.5) - PF_R(1.0); /* -1 .. 2 in halves: edges */
    case 6: return s * PF_REAL_MAX;
    default: return lo + (hi - lo) * pfc_unif(b);
    }
}

/* a finite value: moderate (|x| <= 2^e), sometimes 0 or +-2^e exactly */
static pf_real pfb_val(pfc_ctx *c, int e)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    pf_real s = (b & 1u) ? PF_R(-1.0) : PF_R(1.0);
    switch (PFC_R(u)) {
    case 0: return PF_R(0.0);
    case 1: return s * pfc_p2(e);
    case 2: case 3: return s * pfc_mag(b >> 1, -30, e);
    default: return s * pfc_unif(b) * pfc_p2(e < 4 ? e : 4);
    }
}

/* Fill n reals with values: constant (1 draw in 4, the whole map one value), else per texel.
   Only the first 32 words come from the source (then a generator seeded from them), so a
   large map costs the fuzzer no input bytes. */
static void pfb_fill(pfc_ctx *c, pf_real *p, long long n, int e)
{
    long long i;
    pfc_ctx g;
    pfc_u32 mode = pfc_next(c);
    memset(&g, 0, sizeof g);
    g.rng = ((pfc_u64)pfc_next(c) << 32) | pfc_next(c);
    if (PFC_R(mode) < 4) {
        pf_real v = pfb_val(c, e);
        for (i = 0; i < n; ++i) p[i] = v;
        return;
    }
    for (i = 0; i < n; ++i) p[i] = pfb_val(i < 32 ? c : &g, e);
}

/* 1 in 16: which of k pointers is NULL (0 = none) */
static int pfb_null(pfc_ctx *c, int k)
{
    pfc_u32 u = pfc_next(c);
    if (PFC_R(u) != 0) return 0;
    return 1 + (int)(PFC_B(u) % (pfc_u32)k);
}

/* border enum: CLAMP, WRAP, or an unknown value */
static int pfb_border(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    if (PFC_R(u) < 7) return PF_BORDER_CLAMP;
    if (PFC_R(u) < 14) return PF_BORDER_WRAP;
    return pfb_int(c, -2, 5);
}
static int pfb_border_ok(int b) { return b == PF_BORDER_CLAMP || b == PF_BORDER_WRAP; }

static int pfb_finite(pf_real x) { return pfc_isfinite(x); }
/* NaN by its bits (-ffast-math folds x != x) */
static int pfb_isnan(pf_real x)
{
    pf_real inf = pfc_from_bits(0x7F800000u);
    return !pfc_isfinite(x) && memcmp(&x, &inf, sizeof x) != 0 && (inf = -inf, memcmp(&x, &inf, sizeof x) != 0);
}


/* ---------------------------------------------------------------- calls
   PFB_NORC stands for a function that returns a value rather than a code (the typed samplers,
   pf_esm_log_weighted_mean, pf_transfer_moments_filter): their bad-argument value is checked
   instead. */
#define PFB_NORC 0x7A5A
static int pfb_rc_check(int rc, int allowed, const char *fn)
{
    if (!(allowed & PFB_A_OK) && pfb_t) pfb_t->rejected_n += 1;
    if (rc == PFB_NORC) return 1;
    if (pfb_rc_allowed(rc, allowed)) return 1;
    pfb_fail(PFB_RC, "%s returned %d, the contract says %s", fn, rc, pfb_allowed_name(allowed));
    return 0;
}


/* The canaries of a rejected call are intact, and the slack of every mapping. */
static void pfb_check_untouched(pf_real *const *bufs, int nbufs)
{
    int k;
    for (k = 0; k < nbufs; ++k) {
        if (bufs[k] && pfb_count_changed(bufs[k], PFB_SMALL))
            pfb_fail(PFB_WROTE, "buffer %d: %lld reals written", k, pfb_count_changed(bufs[k], PFB_SMALL));
        if (bufs[k] && !pfb_pool_page_ok(bufs[k])) pfb_fail(PFB_WROTE, "buffer %d: written before its start", k);
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* Every output real written and finite: reports the first canary left or non-finite value. */
static void pfb_check_written(const pf_real *p, long long n, const char *what, int want_finite)
{
    long long i;
    for (i = 0; i < n; ++i) {
        if (pfb_is_canary(p[i])) { pfb_fail(PFB_VALUE, "%s[%lld] not written", what, i); return; }
        if (want_finite && !pfb_finite(p[i])) {
            pfb_fail(PFB_NONFINITE, "%s[%lld] = %a", what, i, (double)p[i]);
            return;
        }
    }
}

/* per channel range of level 0 */
#define PFB_MAXC 8
typedef struct pfb_range { long double lo[PFB_MAXC], hi[PFB_MAXC], mag; } pfb_range;
static pfb_range pfb_range_of(const pf_real *p, long long texels, int nc)
{
    pfb_range r;
    long long i;
    int k;
    r.mag = 0;
    for (k = 0; k < nc && k < PFB_MAXC; ++k) { r.lo[k] = 1e4000L; r.hi[k] = -1e4000L; }
    for (i = 0; i < texels; ++i)
        for (k = 0; k < nc && k < PFB_MAXC; ++k) {
            long double x = p[i * nc + k];
            if (x < r.lo[k]) r.lo[k] = x;
            if (x > r.hi[k]) r.hi[k] = x;
            if (x > r.mag) r.mag = x;
            if (-x > r.mag) r.mag = -x;
        }
    return r;
}
/* every texel of levels >= 1 within level 0's range (a convex combination of it), to
   rounding: tol relative to the largest magnitude, times the number of levels, plus the
   underflow of the weights applied before summing (0.25 * 2^-148 rounds to 0 in float: each
   weighted term loses up to half the smallest subnormal, four terms per level) */
static void pfb_check_levels(const pf_real *pyr, long long w, long long h, int nc, int log_space, const char *fn)
{
    long long i, t0 = w * h, total = pfb_offset(w, h, 64);
    pfb_range r = pfb_range_of(pyr, t0, nc);
    /* log space: log(sum w exp(l - m)) has an absolute error of a few eps per level */
    long double tol = ((r.mag + (log_space ? 1 : 0)) * (long double)PF_REAL_EPSILON +
                       (long double)PF_REAL_MIN * (long double)PF_REAL_EPSILON) * 4.0L * (long double)pfb_levels(w, h);
    int k;
    pfb_check_written(pyr, total * nc, "pyr", 1);
    for (i = t0; i < total; ++i)
        for (k = 0; k < nc && k < PFB_MAXC; ++k) {
            long double x = pyr[i * nc + k];
            if (!(x >= r.lo[k] - tol && x <= r.hi[k] + tol)) {
                pfb_fail(PFB_VALUE, "%s: texel %lld channel %d = %a outside level 0's [%La, %La]", fn, i, k,
                         (double)pyr[i * nc + k], r.lo[k], r.hi[k]);
                return;
            }
        }
}

/* ---------------------------------------------------------------- pf_core.h: size helpers */
/* a long long from the whole range, biased to the edges (and to the int ones) */
static long long pfb_ll(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    long long r = (long long)(((pfc_u64)pfc_next(c) << 32) | pfc_next(c));
    switch (PFC_R(u)) {
    case 0: return LLONG_MAX - (long long)(b % 3u);
    case 1: return LLONG_MIN + (long long)(b % 3u);
    case 2: return PFB_MAX_REALS + (long long)(b % 5u) - 2;
    case 3: return PFB_MAX_SIDE + (long long)(b % 5u) - 2;
    case 4: return r;
    case 5: return (long long)1 << (b % 63u);
    default: return pfb_int(c, -3, 1 << 20);
    }
}

static void pfb_d_core(pfc_ctx *c)
{
    long long a = pfb_ll(c), b = pfb_ll(c), d = pfb_ll(c), want, got;
    pfb_setcall("pf_size_mul(%lld, %lld); pf_size_mul3(%lld, %lld, %lld); pf_size_side_ok(%lld)", a, b, a, b, d, a);
    want = pfb_mul(a, b);
    got = pf_size_mul(a, b);
    if (got != want) pfb_fail(PFB_VALUE, "pf_size_mul = %lld, want %lld", got, want);
    want = want < 0 ? -1 : pfb_mul(want, d); /* "the same way": a * b checked first */
    got = pf_size_mul3(a, b, d);
    if (got != want) pfb_fail(PFB_VALUE, "pf_size_mul3 = %lld, want %lld", got, want);
    got = pf_size_side_ok(a);
    if (got != (a >= 1 && a <= PFB_MAX_SIDE)) pfb_fail(PFB_VALUE, "pf_size_side_ok = %lld", got);
}

/* pf_floor_index: in [lo, hi] for every x (NaN, infinities, huge), floor(x) inside the range */
static void pfb_d_floor_index(pfc_ctx *c, int a)
{
    pf_real x = pfb_coord(c, PF_R(-1.0e6), PF_R(1.0e6));
    long long lo = pfb_int(c, -40, 40), hi = pfb_int(c, -40, 40), r;
    (void)a;
    if (lo > hi) { long long t = lo; lo = hi; hi = t; }
    pfb_setcall("pf_floor_index(%a, %lld, %lld)", (double)x, lo, hi);
    r = pf_floor_index(x, lo, hi);
    if (r < lo || r > hi) pfb_fail(PFB_VALUE, "pf_floor_index = %lld outside [%lld, %lld]", r, lo, hi);
    else if (x >= (pf_real)lo && x < (pf_real)hi && (pf_real)r != PF_FLOOR(x))
        pfb_fail(PFB_VALUE, "pf_floor_index = %lld, floor %a", r, (double)PF_FLOOR(x));
}

/* ---------------------------------------------------------------- pf_moments.h: layout */
static void pfb_d_mip_layout(pfc_ctx *c)
{
    int w = pfb_int(c, -1, 70), h = pfb_int(c, -1, 70), level = pfb_int(c, -1, 30);
    int valid = w >= 1 && h >= 1 && w <= PFB_MAX_SIDE && h <= PFB_MAX_SIDE;
    long long want_total = valid ? pfb_offset(w, h, 64) : 0, got;
    pfb_setcall("pf_mip_texel_count(%d, %d); pf_mip_level_count(%d, %d); pf_mip_level_offset(%d, %d, %d)", w, h, w, h,
                w, h, level);
    if (want_total > PFB_MAX_REALS) want_total = 0;
    got = pf_mip_texel_count(w, h);
    if (got != want_total) pfb_fail(PFB_VALUE, "pf_mip_texel_count = %lld, want %lld", got, want_total);
    {
        int kind = pfb_int(c, -1, 9), want = kind == 0 || kind == 1 ? 2 : (kind == 2 || kind == 3 ? 4 : (kind == 4 ? 1 : 0));
        if (kind >= PF_DEPTH_CSM4 && kind <= PF_DEPTH_CSM16) want = 8 << (kind - PF_DEPTH_CSM4); /* CSM: 2M */
        if (pf_depth_moment_channels(kind) != want)
            pfb_fail(PFB_VALUE, "pf_depth_moment_channels(%d) = %d, want %d", kind, pf_depth_moment_channels(kind), want);
    }
    valid = w >= 1 && h >= 1; /* the layout functions take every int side (the sum fits 2^63) */
    got = pf_mip_level_count(w, h);
    if (valid ? got != pfb_levels(w, h) : got != 0)
        pfb_fail(PFB_VALUE, "pf_mip_level_count = %lld, want %d", got, valid ? pfb_levels(w, h) : 0);
    if (valid) {
        got = pf_mip_level_offset(w, h, level);
        if (got != pfb_offset(w, h, level < 0 ? 0 : level))
            pfb_fail(PFB_VALUE, "pf_mip_level_offset = %lld, want %lld", got, pfb_offset(w, h, level < 0 ? 0 : level));
        got = pf_mip_level_size(w, level);
        if (got != pfb_level_side(w, level < 0 ? 0 : level))
            pfb_fail(PFB_VALUE, "pf_mip_level_size(%d, %d) = %lld, want %lld", w, level, got,
                     pfb_level_side(w, level < 0 ? 0 : level));
    }
}

/* ---------------------------------------------------------------- pf_moments.h: builders */
/* which: 0 pf_mip_build, 1 pf_mip_build_log */
static void pfb_d_mip_build(pfc_ctx *c, int which)
{
    const char *fn = which ? "pf_mip_build_log" : "pf_mip_build";
    int w = pfb_int(c, 1, 40), h = pfb_int(c, 1, 40), nc = pfb_int(c, 1, 6), null = pfb_null(c, 1);
    int at_start = PFC_R(pfc_next(c)) < 4, e = PFC_R(pfc_next(c)) < 2 ? PFC_EMAX : 20, rc, allowed;
    pfb_expect ex = { 0, 0, 0 };
    long long reals = -1;
    pf_real *pyr;
    pfb_setcall("%s(%s, %d, %d, %d)", fn, null ? "NULL" : "pyr", w, h, nc);
    if (null) ex.arg = 1;
    pfb_side(&ex, w, 1);
    pfb_side(&ex, h, 1);
    if (nc < 1) ex.small = 1;
    if (!ex.small && !ex.size) {
        reals = pfb_pyr_reals(w, h, nc);
        if (reals < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    if (allowed != PFB_A_OK) {
        pf_real *b[1];
        b[0] = null ? 0 : pfb_small();
        rc = which ? (pf_mip_build_log(b[0], w, h, nc)) : (pf_mip_build(b[0], w, h, nc));
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 1);
        return;
    }
    if (reals > pfb_work_cap) return;
    pyr = pfb_map(reals, at_start);
    if (!pyr) return;
    pfb_fill(c, pyr, (long long)w * h * nc, e);
    pfb_fill_canary(pyr + (long long)w * h * nc, reals - (long long)w * h * nc);
    if (pfb_t) pfb_t->run += 1;
    rc = which ? (pf_mip_build_log(pyr, w, h, nc)) : (pf_mip_build(pyr, w, h, nc));
    if (!pfb_rc_check(rc, allowed, fn)) return;
    pfb_check_levels(pyr, w, h, nc, which, fn);
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* which: 0 pf_slope_moments_map_from_heights (level 0 only), 1 pf_slope_pyramid_from_heights */
static void pfb_d_slope(pfc_ctx *c, int which)
{
    static const char *const fns[] = { "pf_slope_moments_map_from_heights", "pf_slope_pyramid_from_heights",
                                       "pf_map_normals_from_heights" };
    const char *fn = fns[which];
    int w = pfb_int(c, 1, 40), h = pfb_int(c, 1, 40), border = pfb_border(c), null = pfb_null(c, 2);
    int at_start = PFC_R(pfc_next(c)) < 4, rc, allowed;
    pf_real dx = pfc_mag(PFC_B(pfc_next(c)), -8, 8), dy = pfc_mag(PFC_B(pfc_next(c)), -8, 8);
    pf_real hs = pfb_val(c, 8);
    pfb_expect ex = { 0, 0, 0 };
    long long nh = -1, nout = -1;
    pf_real *hm, *out;
    pfb_setcall("%s(%s, %d, %d, %a, %a, %a, %d, %s)", fn, null == 1 ? "NULL" : "heights", w, h, (double)dx,
                (double)dy, (double)hs, border, null == 2 ? "NULL" : "out");
    if (null) ex.arg = 1;
    pfb_side(&ex, w, 1);
    pfb_side(&ex, h, 1);
    if (!pfb_border_ok(border)) ex.arg = 1;
    if (!ex.small && !ex.size) {
        nh = pfb_mul(w, h);
        nout = which == 1 ? pfb_pyr_reals(w, h, 5) : pfb_mul(nh, which == 2 ? 3 : 5);
        if (nh < 0 || nout < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    if (allowed != PFB_A_OK) {
        pf_real *b[2];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        rc = which == 2 ? pf_map_normals_from_heights(b[0], w, h, dx, dy, hs, border, b[1])
             : which    ? (pf_slope_pyramid_from_heights(b[0], w, h, dx, dy, hs, border, b[1]))
                        : (pf_slope_moments_map_from_heights(b[0], w, h, dx, dy, hs, border, b[1]));
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 2);
        return;
    }
    if (nout > pfb_work_cap) return;
    hm = pfb_map(nh, at_start);
    out = pfb_map(nout, !at_start);
    if (!hm || !out) return;
    pfb_fill(c, hm, nh, 20);
    pfb_fill_canary(out, nout);
    if (pfb_t) pfb_t->run += 1;
    rc = which == 2 ? pf_map_normals_from_heights(hm, w, h, dx, dy, hs, border, out)
         : which    ? (pf_slope_pyramid_from_heights(hm, w, h, dx, dy, hs, border, out))
                    : (pf_slope_moments_map_from_heights(hm, w, h, dx, dy, hs, border, out));
    if (!pfb_rc_check(rc, allowed, fn)) return;
    pfb_check_written(out, nout, "out", 1);
    if (which == 2) { /* unit normals facing up */
        long long i;
        for (i = 0; i < (long long)w * h; ++i) {
            long double l = (long double)out[3 * i] * out[3 * i] + (long double)out[3 * i + 1] * out[3 * i + 1] +
                            (long double)out[3 * i + 2] * out[3 * i + 2];
            if (!(fabsl(l - 1.0L) <= 1e-5L) || !(out[3 * i + 2] > 0)) {
                pfb_fail(PFB_VALUE, "normal %lld: |n|^2 = %Lg, z %a", i, l, (double)out[3 * i + 2]);
                break;
            }
        }
    } else {
        long long i;
        for (i = 0; i < (long long)w * h; ++i)
            if (!(out[5 * i + 2] >= 0 && out[5 * i + 3] >= 0)) {
                pfb_fail(PFB_VALUE, "texel %lld: E[x^2] = %a, E[y^2] = %a", i, (double)out[5 * i + 2], (double)out[5 * i + 3]);
                break;
            }
    }
    if (which == 1) pfb_check_levels(out, w, h, 5, 0, fn);
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

static int pfb_depth_channels(int kind)
{
    switch (kind) {
    case PF_DEPTH_VSM: case PF_DEPTH_EVSM2: return 2;
    case PF_DEPTH_EVSM4: case PF_DEPTH_MSM: return 4;
    case PF_DEPTH_ESM_LOG: return 1;
    case PF_DEPTH_CSM4: return 8;
    case PF_DEPTH_CSM8: return 16;
    case PF_DEPTH_CSM16: return 32;
    default: return 0;
    }
}

/* which: 0 depth (kind drawn), 1 scalar values, 2 normals */
static void pfb_d_pyramid_from(pfc_ctx *c, int which)
{
    static const char *const fns[] = { "pf_depth_pyramid_from_depths", "pf_scalar_pyramid_from_values",
                                       "pf_normal_pyramid_from_normals" };
    const char *fn = fns[which];
    int w = pfb_int(c, 1, 40), h = pfb_int(c, 1, 40), null = pfb_null(c, 2), kind = 0, nc, nin_c;
    int at_start = PFC_R(pfc_next(c)) < 4, rc, allowed;
    pf_real cpos = PF_R(0.0), cneg = PF_R(0.0);
    pfb_expect ex = { 0, 0, 0 };
    long long nin = -1, nout = -1, i;
    pf_real *in, *out;
    if (which == 0) {
        pfc_u32 u = pfc_next(c);
        kind = PFC_R(u) < 14 ? (int)(PFC_B(u) % 8u) : pfb_int(c, -2, 10);
        cpos = kind == PF_DEPTH_ESM_LOG ? pfc_mag(PFC_B(pfc_next(c)), -4, 12) : PF_R(44.0) * pfc_unif(PFC_B(pfc_next(c)));
        cneg = PF_R(44.0) * pfc_unif(PFC_B(pfc_next(c)));
        pfb_setcall("%s(%s, %d, %d, %d, %a, %a, %s)", fn, null == 1 ? "NULL" : "depths", w, h, kind, (double)cpos,
                    (double)cneg, null == 2 ? "NULL" : "pyr");
    } else {
        pfb_setcall("%s(%s, %d, %d, %s)", fn, null == 1 ? "NULL" : "in", w, h, null == 2 ? "NULL" : "pyr");
    }
    nc = which == 0 ? pfb_depth_channels(kind) : (which == 1 ? 2 : 3);
    nin_c = which == 2 ? 3 : 1;
    if (null) ex.arg = 1;
    pfb_side(&ex, w, 1);
    pfb_side(&ex, h, 1);
    if (nc == 0) ex.arg = 1;
    if (!ex.small && !ex.size && nc) {
        nin = pfb_mul(pfb_mul(w, h), nin_c);
        nout = pfb_pyr_reals(w, h, nc);
        if (nin < 0 || nout < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    if (allowed != PFB_A_OK) {
        pf_real *b[2];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        rc = which == 0 ? (pf_depth_pyramid_from_depths(b[0], w, h, kind, cpos, cneg, b[1]))
           : which == 1 ? (pf_scalar_pyramid_from_values(b[0], w, h, b[1]))
                        : (pf_normal_pyramid_from_normals(b[0], w, h, b[1]));
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 2);
        return;
    }
    if (nout > pfb_work_cap) return;
    in = pfb_map(nin, at_start);
    out = pfb_map(nout, !at_start);
    if (!in || !out) return;
    if (which == 0) {
        pfb_fill(c, in, nin, 0);
        for (i = 0; i < nin; ++i) in[i] = PF_FABS(in[i]) > PF_R(1.0) ? PF_R(1.0) : PF_FABS(in[i]); /* [0, 1] */
    } else {
        pfb_fill(c, in, nin, which == 1 ? 40 : 20);
    }
    pfb_fill_canary(out, nout);
    if (pfb_t) pfb_t->run += 1;
    rc = which == 0 ? (pf_depth_pyramid_from_depths(in, w, h, kind, cpos, cneg, out))
       : which == 1 ? (pf_scalar_pyramid_from_values(in, w, h, out))
                    : (pf_normal_pyramid_from_normals(in, w, h, out));
    if (!pfb_rc_check(rc, allowed, fn)) return;
    pfb_check_levels(out, w, h, nc, which == 0 && kind == PF_DEPTH_ESM_LOG, fn);
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_moments.h: N texels */
static void pfb_fill_weights(pfc_ctx *c, pf_real *wt, long long n)
{
    long long i;
    for (i = 0; i < n; ++i) {
        pfc_u32 u = pfc_next(c), b = PFC_B(u);
        switch (PFC_R(u)) {
        case 0: wt[i] = PF_R(0.0); break;
        case 1: wt[i] = PF_REAL_MAX; break;
        case 2: wt[i] = -pfc_unif(b); break;
        case 3: wt[i] = pfc_mag(b, PFC_EMIN, PFC_EMAX); break;
        case 4: wt[i] = pfc_mag(b, PFC_EMIN, -100); break;
        case 5: pfb_nonfinite_input |= (b & 7u) < 2; wt[i] = (b & 7u) == 0 ? pfc_from_bits(0x7F800000u) : ((b & 7u) == 1 ? pfc_from_bits(0x7FC00000u) : PF_REAL_MAX); break;
        default: wt[i] = pfc_unif(b); break;
        }
    }
}

/* which: 0 pf_moments_weighted_mean, 1 pf_esm_log_weighted_mean */
static void pfb_d_weighted_mean(pfc_ctx *c, int which)
{
    const char *fn = which ? "pf_esm_log_weighted_mean" : "pf_moments_weighted_mean";
    int n = pfb_int(c, 0, 12), nc = which ? 1 : pfb_int(c, 1, 6), null = pfb_null(c, which ? 2 : 3);
    int at_start = PFC_R(pfc_next(c)) < 4, rc, allowed, k;
    pfb_expect ex = { 0, 0, 0 };
    long long nt = -1, i;
    pf_real *tx, *wt, *out, r1 = PF_R(0.0);
    long double lo[PFB_MAXC], hi[PFB_MAXC], mag = 0;
    int any = 0, inf_w = 0;
    pfb_setcall("%s(%s, %d, %s, %d%s)", fn, null == 1 ? "NULL" : "texels", nc, null == 2 ? "NULL" : "weights", n,
                which ? "" : (null == 3 ? ", NULL" : ", out"));
    if (null) ex.arg = 1;
    if (nc < 1) ex.small = 1;
    if (n < 0) ex.small = 1;
    if (!ex.small) {
        nt = pfb_mul(n, nc);
        if (nt < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    if (allowed != PFB_A_OK && !(allowed & PFB_A_OK)) {
        pf_real *b[3];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        b[2] = null == 3 ? 0 : pfb_small();
        if (which) {
            if (pfb_t) pfb_t->rejected_n += 1;
            r1 = pf_esm_log_weighted_mean(b[0], b[1], n);
            if (r1 != -PF_REAL_MAX) pfb_fail(PFB_VALUE, "bad arguments returned %a, want -PF_REAL_MAX", (double)r1);
        } else {
            rc = pf_moments_weighted_mean(b[0], nc, b[1], n, b[2]);
            pfb_rc_check(rc, allowed, fn);
        }
        pfb_check_untouched(b, 3);
        return;
    }
    if (nt > pfb_work_cap || nc > pfb_work_cap) return; /* out (channels reals) is written whole */
    tx = pfb_map(nt, at_start);
    wt = pfb_map(n, !at_start);
    out = pfb_map(nc, at_start);
    if (!tx || !wt || !out) return;
    pfb_fill(c, tx, nt, which ? 12 : 100);
    pfb_fill_weights(c, wt, n);
    for (i = 0; i < n; ++i) inf_w |= wt[i] > PF_REAL_MAX;
    for (i = 0; i < n && i < 12; ++i) { /* the weights, into the reproducer line */
        size_t l = strlen(pfb_line);
        snprintf(pfb_line + l, sizeof pfb_line - l, "%s%a%s", i ? " " : " weights {", (double)wt[i], i + 1 == n ? "}" : "");
    }
    pfb_fill_canary(out, nc);
    if (pfb_t) pfb_t->run += 1;
    if (which) { out[0] = pf_esm_log_weighted_mean(tx, wt, n); rc = PFB_NORC; }
    else rc = pf_moments_weighted_mean(tx, nc, wt, n, out);
    if (inf_w) { /* an infinite weight: PF_ERR_ARG, nothing written (or -PF_REAL_MAX) */
        if (which ? out[0] != -PF_REAL_MAX : rc != PF_ERR_ARG || pfb_count_changed(out, nc))
            pfb_fail(which ? PFB_VALUE : PFB_RC, "an infinite weight: returned %d, out[0] = %a", rc, (double)out[0]);
        return;
    }
    if (!pfb_rc_check(rc, allowed, fn) || (rc != PF_OK && rc != PFB_NORC)) return;
    pfb_check_written(out, nc, "out", 1);
    for (k = 0; k < nc && k < PFB_MAXC; ++k) { lo[k] = 1e4000L; hi[k] = -1e4000L; }
    for (i = 0; i < n; ++i) {
        if (!(wt[i] > PF_R(0.0))) continue;
        any = 1;
        for (k = 0; k < nc && k < PFB_MAXC; ++k) {
            long double x = tx[i * nc + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
            if (x > mag) mag = x;
            if (-x > mag) mag = -x;
        }
    }
    for (k = 0; k < nc && k < PFB_MAXC; ++k) {
        /* log space: log(sum w exp(l - m)) has an absolute error of a few eps */
        long double y = out[k], tol = (mag + which) * (long double)PF_REAL_EPSILON * (long double)(4 + n);
        if (!any) {
            if (which ? out[0] != -PF_REAL_MAX : out[k] != PF_R(0.0))
                pfb_fail(PFB_VALUE, "no positive weight: out[%d] = %a, want %s", k, (double)out[k], which ? "-PF_REAL_MAX" : "0");
        } else if (!(y >= lo[k] - tol && y <= hi[k] + tol)) {
            pfb_fail(PFB_VALUE, "out[%d] = %a outside the texels' [%La, %La]", k, (double)out[k], lo[k], hi[k]);
        }
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_moments.h: samplers */
/* Reference texel indices and fraction on an axis of n texels (the documented GPU convention:
   centre of texel i at (i + 0.5)/n; WRAP repeats, CLAMP clamps u to [0, 1]); NaN reads as 0.
   inf_mode for an infinite u: 0 reads it as 0 (the header's first wording), 1 clamps it
   (CLAMP: 0 or 1 by its sign; WRAP: 0). */
static void pfb_ref_axis(pf_real u, long long n, int border, int inf_mode, long long *i0, long long *i1,
                         long double *f)
{
    long double x, fl;
    long long i;
    if (pfb_isnan(u)) u = PF_R(0.0);
    if (!pfb_finite(u)) u = inf_mode && border == PF_BORDER_CLAMP ? (u > 0 ? PF_R(1.0) : PF_R(0.0)) : PF_R(0.0);
    x = (long double)u;
    if (border == PF_BORDER_WRAP) x = x - floorl(x);
    else x = x < 0 ? 0 : (x > 1 ? 1 : x);
    x = x * (long double)n - 0.5L;
    fl = floorl(x);
    *f = x - fl;
    i = (long long)fl;
    if (border == PF_BORDER_WRAP) {
        *i0 = ((i % n) + n) % n;
        *i1 = (*i0 + 1) % n;
    } else {
        *i0 = i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
        *i1 = i + 1 < 0 ? 0 : (i + 1 > n - 1 ? n - 1 : i + 1);
    }
}

/* long double log(exp(a) wa + exp(b) wb) for wa, wb >= 0 */
static long double pfb_lse2(long double a, long double wa, long double b, long double wb)
{
    long double m;
    if (!(wa > 0)) return b;
    if (!(wb > 0)) return a;
    m = a > b ? a : b;
    return m + logl(wa * expl(a - m) + wb * expl(b - m));
}

/* reference bilinear sample of channel k at one level */
static long double pfb_ref_bilerp(const pf_real *pyr, long long w, long long h, int nc, int level, pf_real u,
                                  pf_real v, int border, int inf_mode, int log_space, int k)
{
    long long lw = pfb_level_side(w, level), lh = pfb_level_side(h, level), base = pfb_offset(w, h, level);
    long long x0, x1, y0, y1, t[4];
    long double fx, fy, wt[4], s = 0, m = -1e4000L;
    int q;
    pfb_ref_axis(u, lw, border, inf_mode, &x0, &x1, &fx);
    pfb_ref_axis(v, lh, border, inf_mode, &y0, &y1, &fy);
    t[0] = base + y0 * lw + x0; t[1] = base + y0 * lw + x1;
    t[2] = base + y1 * lw + x0; t[3] = base + y1 * lw + x1;
    wt[0] = (1 - fx) * (1 - fy); wt[1] = fx * (1 - fy); wt[2] = (1 - fx) * fy; wt[3] = fx * fy;
    if (!log_space) {
        for (q = 0; q < 4; ++q) if (wt[q] > 0) s += wt[q] * pyr[t[q] * nc + k];
        return s;
    }
    for (q = 0; q < 4; ++q) if (wt[q] > 0 && pyr[t[q] * nc + k] > m) m = pyr[t[q] * nc + k];
    for (q = 0; q < 4; ++q) if (wt[q] > 0) s += wt[q] * expl(pyr[t[q] * nc + k] - m);
    return m + logl(s);
}

/* reference trilinear sample (lod NaN -> 0, clamped to [0, levels - 1]) */
static long double pfb_ref_sample(const pf_real *pyr, long long w, long long h, int nc, pf_real lod, pf_real u,
                                  pf_real v, int border, int inf_mode, int log_space, int k)
{
    int nl = pfb_levels(w, h), l0;
    long double L = pfb_isnan(lod) ? 0 : (long double)lod, fl, a, b;
    if (!(L > 0)) L = 0;
    if (L > nl - 1) L = nl - 1;
    l0 = (int)floorl(L);
    fl = L - l0;
    a = pfb_ref_bilerp(pyr, w, h, nc, l0, u, v, border, inf_mode, log_space, k);
    if (!(fl > 0) || l0 + 1 >= nl) return a;
    b = pfb_ref_bilerp(pyr, w, h, nc, l0 + 1, u, v, border, inf_mode, log_space, k);
    return log_space ? pfb_lse2(a, 1 - fl, b, fl) : (1 - fl) * a + fl * b;
}

/* The sampler variants: 0 bilinear, 1 trilinear, 2 bilinear_log, 3 trilinear_log, then the
   typed ones (fixed channel count, trilinear). */
enum { PFB_S_BIL, PFB_S_TRI, PFB_S_BIL_LOG, PFB_S_TRI_LOG, PFB_S_SLOPE, PFB_S_SCALAR, PFB_S_D2, PFB_S_D4,
       PFB_S_EVSM, PFB_S_NORMAL, PFB_S_ESM, PFB_S_COUNT };
static const char *const pfb_sampler_name[PFB_S_COUNT] = {
    "pf_mip_sample_bilinear", "pf_mip_sample_trilinear", "pf_mip_sample_bilinear_log", "pf_mip_sample_trilinear_log",
    "pf_slope_moments_sample", "pf_scalar_moments_sample", "pf_depth_moments2_sample", "pf_depth_moments4_sample",
    "pf_evsm_moments_sample", "pf_normal_avg_sample", "pf_esm_log_sample"
};
static const int pfb_sampler_nc[PFB_S_COUNT] = { 0, 0, 0, 0, 5, 2, 2, 4, 4, 3, 1 };

/* one call of sampler s; the typed ones copy their struct into out */
static int pfb_sample_call(int s, const pf_real *pyr, int w, int h, int nc, int level, pf_real lod, pf_real u,
                           pf_real v, int border, pf_real *out)
{
    pf_real t[5];
    switch (s) {
    case PFB_S_BIL: return (pf_mip_sample_bilinear(pyr, w, h, nc, level, u, v, border, out));
    case PFB_S_TRI: return (pf_mip_sample_trilinear(pyr, w, h, nc, lod, u, v, border, out));
    case PFB_S_BIL_LOG: return (pf_mip_sample_bilinear_log(pyr, w, h, nc, level, u, v, border, out));
    case PFB_S_TRI_LOG: return (pf_mip_sample_trilinear_log(pyr, w, h, nc, lod, u, v, border, out));
    case PFB_S_SLOPE: { pf_slope_moments m = pf_slope_moments_sample(pyr, w, h, lod, u, v, border);
        t[0] = m.ex; t[1] = m.ey; t[2] = m.exx; t[3] = m.eyy; t[4] = m.exy; break; }
    case PFB_S_SCALAR: { pf_scalar_moments m = pf_scalar_moments_sample(pyr, w, h, lod, u, v, border);
        t[0] = m.m1; t[1] = m.m2; break; }
    case PFB_S_D2: { pf_depth_moments2 m = pf_depth_moments2_sample(pyr, w, h, lod, u, v, border);
        t[0] = m.m1; t[1] = m.m2; break; }
    case PFB_S_D4: { pf_depth_moments4 m = pf_depth_moments4_sample(pyr, w, h, lod, u, v, border);
        t[0] = m.m1; t[1] = m.m2; t[2] = m.m3; t[3] = m.m4; break; }
    case PFB_S_EVSM: { pf_evsm_moments m = pf_evsm_moments_sample(pyr, w, h, lod, u, v, border);
        t[0] = m.pos1; t[1] = m.pos2; t[2] = m.neg1; t[3] = m.neg2; break; }
    case PFB_S_NORMAL: { pf_vec3 m = pf_normal_avg_sample(pyr, w, h, lod, u, v, border);
        t[0] = m.x; t[1] = m.y; t[2] = m.z; break; }
    default: t[0] = pf_esm_log_sample(pyr, w, h, lod, u, v, border); break;
    }
    if (out) memcpy(out, t, (size_t)pfb_sampler_nc[s] * sizeof(pf_real));
    return PFB_NORC;
}

/* Sizes for samplers: small maps (values, checked against the reference), and huge ones
   drawn to sit at the limits (2^24 x 1, 2^20 x 2^19, up to PF_MAX_REALS), left as zero pages. */
static void pfb_d_sample(pfc_ctx *c, int s)
{
    const char *fn = pfb_sampler_name[s];
    int typed = s >= PFB_S_SLOPE, logs = s == PFB_S_BIL_LOG || s == PFB_S_TRI_LOG || s == PFB_S_ESM;
    int w = pfb_int(c, 1, 24), h = pfb_int(c, 1, 24), nc = typed ? pfb_sampler_nc[s] : pfb_int(c, 1, 6);
    int level = s == PFB_S_BIL || s == PFB_S_BIL_LOG ? pfb_int(c, -1, 6) : 0;
    pf_real lod = s == PFB_S_BIL || s == PFB_S_BIL_LOG ? (pf_real)level : pfb_coord(c, PF_R(-0.5), PF_R(8.0));
    pf_real u = pfb_coord(c, PF_R(-0.25), PF_R(1.25)), v = pfb_coord(c, PF_R(-0.25), PF_R(1.25));
    int border = pfb_border(c), null = pfb_null(c, typed ? 1 : 2), at_start = PFC_R(pfc_next(c)) < 4;
    int rc, allowed, k, small, im;
    pfb_expect ex = { 0, 0, 0 };
    long long reals = -1;
    pf_real *pyr, *out;
    if (PFC_R(pfc_next(c)) < 3) { /* huge maps at the limits */
        static const int sides[][2] = { { 1 << 24, 1 }, { 1, 1 << 24 }, { 1 << 20, 1 << 19 }, { (1 << 24) - 1, 3 },
                                        { 1 << 24, 1 << 14 }, { 1 << 24, (1 << 16) - 1 }, { INT_MAX, 1 }, { 1 << 24, 1 << 24 } };
        pfc_u32 b = PFC_B(pfc_next(c)) % 8u;
        w = sides[b][0]; h = sides[b][1];
        if (!typed) nc = 1;
    }
    pfb_setcall("%s(%s, %d, %d, %d, %d, %a, %a, %a, %d, %s)  [channels, level, lod, u, v, border]", fn,
                null == 1 ? "NULL" : "pyr", w, h, nc, level, (double)lod, (double)u, (double)v, border,
                null == 2 ? "NULL" : "out");
    if (null) ex.arg = 1;
    pfb_side(&ex, w, 1);
    pfb_side(&ex, h, 1);
    if (nc < 1) ex.small = 1;
    if (!pfb_border_ok(border)) ex.arg = 1;
    if (!ex.small && !ex.size) {
        reals = pfb_pyr_reals(w, h, nc);
        if (reals < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    if (allowed != PFB_A_OK) {
        pf_real *b[2];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : (typed ? pfb_map(PFB_SMALL, 0) : pfb_small());
        rc = pfb_sample_call(s, b[0], w, h, nc, level, lod, u, v, border, b[1]);
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, typed ? 1 : 2);
        if (typed) /* the returned value: zeros (-PF_REAL_MAX for the ESM log sample) */
            for (k = 0; k < nc; ++k)
                if (b[1][k] != (s == PFB_S_ESM ? -PF_REAL_MAX : PF_R(0.0))) {
                    pfb_fail(PFB_VALUE, "bad arguments returned %a in member %d", (double)b[1][k], k);
                    break;
                }
        return;
    }
    if (nc > 4096) return; /* writes and reads every channel */
    small = reals <= (1LL << 16) && reals <= pfb_work_cap;
    pfb_fresh = !small; /* left as zero pages */
    pyr = pfb_map(reals, at_start);
    out = pfb_map(nc, !at_start);
    if (!pyr || !out) return;
    if (small) pfb_fill(c, pyr, reals, logs ? 8 : 16);
    pfb_fill_canary(out, nc);
    if (pfb_t) pfb_t->run += 1;
    rc = pfb_sample_call(s, pyr, w, h, nc, level, lod, u, v, border, out);
    if (!pfb_rc_check(rc, allowed, fn) || (rc != PF_OK && rc != PFB_NORC)) return;
    pfb_check_written(out, nc, "out", 1);
    for (k = 0; k < nc; ++k) {
        long double got = out[k], best = 1e4000L, mag = 0, tol;
        long long n = w > h ? w : h;
        if (!small) { /* zero pages: the sample is 0 */
            if (!(PF_FABS(out[k]) <= PF_R(8.0) * PF_REAL_EPSILON))
                pfb_fail(PFB_VALUE, "out[%d] = %a on an all-zero map", k, (double)out[k]);
            break;
        }
        {
            pfb_range r = pfb_range_of(pyr, reals / nc, nc);
            mag = r.mag;
        }
        tol = (mag + 1) * (long double)PF_REAL_EPSILON * (8.0L + 4.0L * (long double)n) * (logs ? 4.0L : 1.0L);
        for (im = 0; im < 2; ++im) {
            long double want = pfb_ref_sample(pyr, w, h, nc, s == PFB_S_BIL || s == PFB_S_BIL_LOG ? (pf_real)(level < 0 ? 0 : level) : lod,
                                              u, v, border, im, logs, k);
            long double d = got > want ? got - want : want - got;
            if (d < best) best = d;
        }
        if (!(best <= tol)) {
            long double want = pfb_ref_sample(pyr, w, h, nc, s == PFB_S_BIL || s == PFB_S_BIL_LOG ? (pf_real)(level < 0 ? 0 : level) : lod,
                                              u, v, border, 1, logs, k);
            pfb_fail(PFB_VALUE, "out[%d] = %.9Lg, reference %.9Lg (|diff| %.3Lg > %.3Lg)", k, got, want, best, tol);
            break;
        }
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_height.h */

/* knots: x non-decreasing (jumps included), values c */
static void pfb_knots(pfc_ctx *c, pf_real *x, pf_real *cv, long long n, int nc)
{
    long long i;
    pf_real at = pfb_val(c, 6);
    for (i = 0; i < n; ++i) {
        pfc_u32 u = pfc_next(c);
        if (i > 0 && PFC_R(u) >= 3) at += PFC_R(u) < 6 ? pfc_mag(PFC_B(u), -20, 0) : pfc_unif(PFC_B(u)) * PF_R(4.0);
        x[i] = at;
    }
    pfb_fill(c, cv, n * nc, 10);
}

/* which: 0 pf_colormap_filter, 1 pf_height_colormap_filter, 2 pf_transfer_moments_filter */
static void pfb_d_colormap(pfc_ctx *c, int which)
{
    static const char *const fns[] = { "pf_colormap_filter", "pf_height_colormap_filter", "pf_transfer_moments_filter" };
    const char *fn = fns[which];
    int n = pfb_int(c, 1, 12), nc = which == 2 ? 1 : pfb_int(c, 1, 5), null = pfb_null(c, which == 2 ? 2 : 3);
    int at_start = PFC_R(pfc_next(c)) < 4, rc, allowed, k, nout = which == 2 ? 4 : 0;
    pf_real mean = pfb_val(c, 8), sigma = pfb_val(c, 6), lo = pfc_pos(c, 30), li = pfc_pos(c, 30);
    pfb_expect ex = { 0, 0, 0 };
    long long nv = -1, i;
    pf_real *x, *cv, *out;
    if (nout == 0) nout = nc;
    pfb_setcall("%s(%s, %s, %d, %d, mean %a, sigma %a, lambda %a %a, %s)", fn, null == 1 ? "NULL" : "x",
                null == 2 ? "NULL" : "c", n, nc, (double)mean, (double)sigma, (double)lo, (double)li, null == 3 ? "NULL" : "out");
    if (null) ex.arg = 1;
    if (n < 1 || nc < 1) ex.small = 1;
    if (!ex.small) {
        nv = pfb_mul(n, nc);
        if (nv < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    if (allowed == PFB_A_OK && n > PFB_MAX_SIDE) allowed |= PFB_A_SIZE; /* n knots as a side: either reading */
    if (!(allowed & PFB_A_OK)) {
        pf_real *b[3];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        b[2] = null == 3 ? 0 : pfb_small();
        if (which == 0) rc = (pf_colormap_filter(b[0], b[1], n, nc, mean, sigma, b[2]));
        else if (which == 1)
            rc = (pf_height_colormap_filter(b[0], b[1], n, nc, lo, li, mean, sigma, PF_R(0.0), PF_R(0.0), b[2]));
        else { /* returns the moments: zeros for bad arguments */
            pf_transfer_moments m = pf_transfer_moments_filter(b[0], b[1], n, mean, sigma);
            rc = PFB_NORC;
            if (m.g != PF_R(0.0) || m.g2 != PF_R(0.0) || m.dg != PF_R(0.0) || m.dg2 != PF_R(0.0))
                pfb_fail(PFB_VALUE, "bad arguments returned (%a, %a, %a, %a), want zeros", (double)m.g, (double)m.g2,
                         (double)m.dg, (double)m.dg2);
        }
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 3);
        return;
    }
    if (nv > pfb_work_cap) return;
    x = pfb_map(n, at_start);
    cv = pfb_map(nv, !at_start);
    out = pfb_map(nout, at_start);
    if (!x || !cv || !out) return;
    pfb_knots(c, x, cv, n, nc);
    pfb_fill_canary(out, nout);
    if (pfb_t) pfb_t->run += 1;
    if (which == 0) rc = (pf_colormap_filter(x, cv, n, nc, mean, sigma, out));
    else if (which == 1) rc = (pf_height_colormap_filter(x, cv, n, nc, lo, li, mean, sigma, PF_R(0.0), PF_R(0.0), out));
    else {
        pf_transfer_moments m = pf_transfer_moments_filter(x, cv, n, mean, sigma);
        out[0] = m.g; out[1] = m.g2; out[2] = m.dg; out[3] = m.dg2;
        rc = PFB_NORC;
    }
    if (!pfb_rc_check(rc, allowed, fn) || (rc != PF_OK && rc != PFB_NORC)) return;
    pfb_check_written(out, nout, "out", 1);
    for (k = 0; k < (which == 2 ? 1 : nc); ++k) {
        long double mn = 1e4000L, mx = -1e4000L, mag = 0, tol, y = out[k];
        for (i = 0; i < n; ++i) {
            long double t = cv[i * nc + k];
            if (t < mn) mn = t;
            if (t > mx) mx = t;
            if (t > mag) mag = t;
            if (-t > mag) mag = -t;
        }
        if (which == 1) { if (mn > 0) mn = 0; if (mx < 0) mx = 0; }
        tol = mag * (long double)PF_REAL_EPSILON * 32.0L * (long double)(n + 2);
        if (!(y >= mn - tol && y <= mx + tol)) {
            pfb_fail(PFB_VALUE, "out[%d] = %a outside the knot values [%La, %La]", k, (double)out[k], mn, mx);
            break;
        }
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

static void pfb_d_table_size(pfc_ctx *c)
{
    int nm = pfb_int(c, -1, 40), ns = pfb_int(c, -1, 40), nc = pfb_int(c, -1, 5);
    long long want = 0, got;
    pfb_setcall("pf_colormap_table_size(%d, %d, %d)", nm, ns, nc);
    if (nm >= 2 && ns >= 2 && nc >= 1 && nm <= PFB_MAX_SIDE && ns <= PFB_MAX_SIDE) {
        want = pfb_mul(pfb_mul(nm, ns), nc);
        if (want < 0) want = 0;
    }
    got = (long long)pf_colormap_table_size(nm, ns, nc);
    if (got != want) pfb_fail(PFB_VALUE, "returned %lld, want %lld", got, want);
}

/* a range end: finite (most draws), inf, NaN, +-PF_REAL_MAX */
static pf_real pfb_range_end(pfc_ctx *c, pf_real typical)
{
    pfc_u32 u = pfc_next(c), b = PFC_B(u);
    switch (PFC_R(u)) {
    case 0: pfb_nonfinite_input = 1; return pfc_from_bits(0x7FC00000u);
    case 1: pfb_nonfinite_input = 1; return (b & 1u) ? -pfc_from_bits(0x7F800000u) : pfc_from_bits(0x7F800000u);
    case 2: return (b & 1u) ? -PF_REAL_MAX : PF_REAL_MAX;
    case 3: return PF_R(0.0);
    default: return typical * (PF_R(0.25) + pfc_unif(b));
    }
}

/* a table's range as the contract states it: bounds, widths and sample steps finite and > 0 */
static int pfb_range_ok(pf_real mmin, pf_real mmax, pf_real smax, int nm, int ns)
{
    pf_real wm = mmax - mmin;
    if (!pfb_finite(mmin) || !pfb_finite(mmax) || !pfb_finite(smax) || !pfb_finite(wm)) return 0;
    if (!(mmax > mmin) || !(smax > PF_R(0.0))) return 0;
    if (nm >= 2 && !(wm / (pf_real)(nm - 1) > PF_R(0.0))) return 0;
    if (ns >= 2 && !(smax / (pf_real)(ns - 1) > PF_R(0.0))) return 0;
    return 1;
}

static void pfb_d_table_build(pfc_ctx *c)
{
    const char *fn = "pf_colormap_table_build";
    int nm = pfb_int(c, 2, 24), ns = pfb_int(c, 2, 12), nc = pfb_int(c, 1, 4), n = pfb_int(c, 1, 8);
    int null = pfb_null(c, 4), at_start = PFC_R(pfc_next(c)) < 4, rc, allowed;
    pf_real mmin = -pfb_range_end(c, PF_R(8.0)), mmax = pfb_range_end(c, PF_R(8.0)), smax = pfb_range_end(c, PF_R(4.0));
    pfb_expect ex = { 0, 0, 0 };
    long long reals = -1, nv = -1, i;
    pf_colormap_table t, t0;
    pf_real *buf, *x, *cv;
    pfb_setcall("%s(%s, %s, %d, %d, %a, %a, %a, %s, %s, %d, %d)", fn, null == 1 ? "NULL" : "&t", null == 2 ? "NULL" : "buf",
                nm, ns, (double)mmin, (double)mmax, (double)smax, null == 3 ? "NULL" : "x", null == 4 ? "NULL" : "c", n, nc);
    if (null) ex.arg = 1;
    pfb_side(&ex, nm, 2);
    pfb_side(&ex, ns, 2);
    if (nc < 1 || n < 1) ex.small = 1;
    if (!pfb_range_ok(mmin, mmax, smax, nm, ns)) ex.arg = 1;
    /* two buffers of independent sizes: the table (n_mean, n_sigma, channels), the values
       (n, channels) */
    if (n >= 1 && nc >= 1 && pfb_mul(n, nc) < 0) ex.size = 1;
    if (nm >= 2 && ns >= 2 && nc >= 1 && nm <= PFB_MAX_SIDE && ns <= PFB_MAX_SIDE && pfb_mul(pfb_mul(nm, ns), nc) < 0)
        ex.size = 1;
    if (!ex.small && !ex.size) {
        reals = pfb_mul(pfb_mul(nm, ns), nc);
        nv = pfb_mul(n, nc);
    }
    allowed = pfb_allowed(ex);
    if (allowed == PFB_A_OK && n > PFB_MAX_SIDE) allowed |= PFB_A_SIZE;
    memset(&t, 0xA5, sizeof t);
    t0 = t;
    if (!(allowed & PFB_A_OK)) {
        pf_real *b[3];
        b[0] = null == 2 ? 0 : pfb_small();
        b[1] = null == 3 ? 0 : pfb_small();
        b[2] = null == 4 ? 0 : pfb_small();
        rc = pf_colormap_table_build(null == 1 ? 0 : &t, b[0], nm, ns, mmin, mmax, smax, b[1], b[2], n, nc);
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 3);
        if (memcmp(&t, &t0, sizeof t)) pfb_fail(PFB_WROTE, "*t written on error");
        return;
    }
    if (reals > pfb_work_cap / 4 || reals * (long long)n > pfb_work_cap || nv > pfb_work_cap) return;
    buf = pfb_map(reals, at_start);
    x = pfb_map(n, !at_start);
    cv = pfb_map(nv, at_start);
    if (!buf || !x || !cv) return;
    pfb_knots(c, x, cv, n, nc);
    pfb_fill_canary(buf, reals);
    if (pfb_t) pfb_t->run += 1;
    rc = pf_colormap_table_build(&t, buf, nm, ns, mmin, mmax, smax, x, cv, n, nc);
    if (!pfb_rc_check(rc, allowed, fn) || rc != PF_OK) return;
    if (t.data != buf || t.n_mean != nm || t.n_sigma != ns || t.channels != nc)
        pfb_fail(PFB_VALUE, "*t does not describe the table");
    pfb_check_written(buf, reals, "buffer", 1);
    for (i = 0; i < reals; ++i) {
        int k = (int)(i % nc);
        long double mn = 1e4000L, mx = -1e4000L, mag = 0, y = buf[i];
        long long j;
        for (j = 0; j < n; ++j) {
            long double v = cv[j * nc + k];
            if (v < mn) mn = v;
            if (v > mx) mx = v;
            if (v > mag) mag = v;
            if (-v > mag) mag = -v;
        }
        if (!(y >= mn - mag * (long double)PF_REAL_EPSILON * 32.0L * (n + 2) &&
              y <= mx + mag * (long double)PF_REAL_EPSILON * 32.0L * (n + 2))) {
            pfb_fail(PFB_VALUE, "entry %lld = %a outside the knot values [%La, %La]", i, (double)buf[i], mn, mx);
            break;
        }
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* reference bilinear lookup of a table (contract: clamped to the range, NaN as the low end) */
static long double pfb_ref_lookup(const pf_colormap_table *t, pf_real mean, pf_real sigma, int k)
{
    long double u = ((long double)mean - t->mean_min) / ((long double)t->mean_max - t->mean_min) * (t->n_mean - 1);
    long double v = (long double)sigma / t->sigma_max * (t->n_sigma - 1), fu, fv, lo, hi;
    long long i, j, cs = t->channels;
    const pf_real *p00, *p10, *p01, *p11;
    if (!(u > 0)) u = 0;
    if (u > t->n_mean - 1) u = t->n_mean - 1;
    if (!(v > 0)) v = 0;
    if (v > t->n_sigma - 1) v = t->n_sigma - 1;
    i = (long long)floorl(u);
    j = (long long)floorl(v);
    if (i > t->n_mean - 2) i = t->n_mean - 2;
    if (j > t->n_sigma - 2) j = t->n_sigma - 2;
    fu = u - i;
    fv = v - j;
    p00 = t->data + (j * t->n_mean + i) * cs;
    p10 = p00 + cs;
    p01 = p00 + (long long)t->n_mean * cs;
    p11 = p01 + cs;
    lo = p00[k] + fu * ((long double)p10[k] - p00[k]);
    hi = p01[k] + fu * ((long double)p11[k] - p01[k]);
    return lo + fv * (hi - lo);
}

static void pfb_d_table_lookup(pfc_ctx *c)
{
    const char *fn = "pf_colormap_table_lookup";
    pf_colormap_table t;
    int null = pfb_null(c, 3), at_start = PFC_R(pfc_next(c)) < 4, rc, allowed, k, huge = PFC_R(pfc_next(c)) < 4;
    pf_real mean = pfb_coord(c, PF_R(-10.0), PF_R(10.0)), sigma = pfb_coord(c, PF_R(-1.0), PF_R(5.0));
    pfb_expect ex = { 0, 0, 0 };
    long long reals = -1;
    pf_real *out;
    t.data = 0;
    t.n_mean = pfb_int(c, 2, 16);
    t.n_sigma = pfb_int(c, 2, 8);
    t.channels = pfb_int(c, 1, 4);
    if (huge) {
        static const int sz[][2] = { { 1 << 24, 2 }, { 2, 1 << 24 }, { 1 << 20, 1 << 19 }, { 1 << 24, 1 << 16 },
                                     { 1 << 24, 1 << 24 }, { INT_MAX, 2 } };
        pfc_u32 b = PFC_B(pfc_next(c)) % 6u;
        t.n_mean = sz[b][0]; t.n_sigma = sz[b][1]; t.channels = 1;
    }
    t.mean_min = -pfb_range_end(c, PF_R(8.0));
    t.mean_max = pfb_range_end(c, PF_R(8.0));
    t.sigma_max = pfb_range_end(c, PF_R(4.0));
    pfb_setcall("%s(%s{n_mean %d, n_sigma %d, channels %d, mean [%a, %a], sigma_max %a}, %a, %a, %s)", fn,
                null == 1 ? "NULL" : "&t", t.n_mean, t.n_sigma, t.channels, (double)t.mean_min, (double)t.mean_max,
                (double)t.sigma_max, (double)mean, (double)sigma, null == 3 ? "NULL" : "out");
    if (null) ex.arg = 1; /* 1: t, 2: t->data, 3: out */
    pfb_side(&ex, t.n_mean, 2);
    pfb_side(&ex, t.n_sigma, 2);
    if (t.channels < 1) ex.small = 1;
    if (!pfb_range_ok(t.mean_min, t.mean_max, t.sigma_max, t.n_mean, t.n_sigma)) ex.arg = 1;
    if (!ex.small && !ex.size) {
        reals = pfb_mul(pfb_mul(t.n_mean, t.n_sigma), t.channels);
        if (reals < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    if (!(allowed & PFB_A_OK)) {
        pf_real *b[2];
        b[0] = null == 2 ? 0 : pfb_small();
        b[1] = null == 3 ? 0 : pfb_small();
        t.data = b[0];
        rc = (pf_colormap_table_lookup(null == 1 ? 0 : &t, mean, sigma, b[1]));
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 2);
        return;
    }
    if (t.channels > 4096) return;
    pfb_fresh = huge || reals > (1LL << 16) || reals > pfb_work_cap; /* left as zero pages */
    t.data = pfb_map(reals, at_start);
    out = pfb_map(t.channels, !at_start);
    if (!t.data || !out) return;
    huge = reals > (1LL << 16) || reals > pfb_work_cap;
    if (!huge) pfb_fill(c, t.data, reals, 10);
    pfb_fill_canary(out, t.channels);
    if (pfb_t) pfb_t->run += 1;
    rc = (pf_colormap_table_lookup(&t, mean, sigma, out));
    if (!pfb_rc_check(rc, allowed, fn) || (rc != PF_OK && rc != PFB_NORC)) return;
    pfb_check_written(out, t.channels, "out", 1);
    for (k = 0; k < t.channels; ++k) {
        long double want = huge ? 0 : pfb_ref_lookup(&t, mean, sigma, k), got = out[k];
        long double mag = huge ? 0 : pfb_range_of(t.data, reals, 1).mag;
        long double tol = (mag + 1) * (long double)PF_REAL_EPSILON * (8.0L + 4.0L * (t.n_mean + t.n_sigma));
        if (!((got > want ? got - want : want - got) <= tol)) {
            pfb_fail(PFB_VALUE, "out[%d] = %.9Lg, reference %.9Lg", k, got, want);
            break;
        }
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_gaussgrid.h */
static void pfb_d_hermite(pfc_ctx *c)
{
    int n = pfb_int(c, 1, PF_GG_GENERATE_MAX + 2), null = pfb_null(c, 2), at_start = PFC_R(pfc_next(c)) < 4, r, i;
    int ok_n = n >= 1 && n <= PF_GG_GENERATE_MAX;
    pf_real *nodes, *wts;
    long double s = 0;
    pfb_setcall("pf_gg_hermite_generate(%d, %s, %s)", n, null == 1 ? "NULL" : "nodes", null == 2 ? "NULL" : "weights");
    if (!ok_n || null) {
        pf_real *b[2];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        if (pfb_t) pfb_t->rejected_n += 1;
        r = pf_gg_hermite_generate(n, b[0], b[1]);
        if (r != 0) pfb_fail(PFB_RC, "returned %d, want 0", r);
        pfb_check_untouched(b, 2);
        return;
    }
    nodes = pfb_map(n, at_start);
    wts = pfb_map(n, !at_start);
    if (!nodes || !wts) return;
    pfb_fill_canary(nodes, n);
    pfb_fill_canary(wts, n);
    if (pfb_t) pfb_t->run += 1;
    r = pf_gg_hermite_generate(n, nodes, wts);
    if (r != n) { pfb_fail(PFB_RC, "returned %d, want %d", r, n); return; }
    pfb_check_written(nodes, n, "nodes", 1);
    pfb_check_written(wts, n, "weights", 1);
    for (i = 0; i < n; ++i) {
        if (!(wts[i] >= 0) || nodes[i] != -nodes[n - 1 - i] || (i > 0 && !(nodes[i] > nodes[i - 1]))) {
            pfb_fail(PFB_VALUE, "node %d = %a, weight %a", i, (double)nodes[i], (double)wts[i]);
            return;
        }
        s += wts[i];
    }
    if (!(fabsl(s - 1) <= 64.0L * (long double)PF_REAL_EPSILON)) pfb_fail(PFB_VALUE, "weights sum to %.17Lg", s);
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_masks.h */
/* pf_masks_samples (0), pf_masks_table_words (1), pf_masks_table_build (2), pf_masks_table_fetch
   (3). Tables are int words: they are mapped as reals and the int array placed so that it ends
   exactly at the guard page (or starts at it); ints outside it in the mapping are canaries too. */
#define PFB_MASK_CANARY 0x5A5A5A5A
static int *pfb_map_ints(long long nints, int at_start)
{
    long long nr = (nints * 4 + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real);
    pf_real *p = pfb_map(nr < 1 ? 1 : nr, at_start);
    int *q;
    long long k, tot = (nr < 1 ? 1 : nr) * (long long)sizeof(pf_real) / 4;
    if (!p) return 0;
    q = (int *)(void *)p;
    /* canaries in the table (small ones: huge fetch tables stay untouched zero pages) and in
       the pad int a double build's rounding leaves */
    for (k = 0; k < tot; ++k) {
        if (nints > 4 * pfb_work_cap && k >= 64 && k < tot - 64) k = tot - 64;
        q[k] = PFB_MASK_CANARY;
    }
    return at_start ? q : q + (tot - nints);
}
static long long pfb_masks_words_ref(int n, int nt, int nv)
{
    if (n < 1 || n > 128 || nt < 1 || nv < 2 || nt > 32768 || nv > 32768) return 0;
    return (long long)nt * nv * ((n + 31) / 32);
}
static int pfb_mask_shape(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    if (PFC_R(u) < 7) return PF_MASKS_SQUARE;
    if (PFC_R(u) < 14) return PF_MASKS_DISK;
    return pfb_int(c, -2, 5);
}
static int pfb_mask_inside(int shape, pf_real x, pf_real y)
{
    long double lim = 0.5L + 1e-4L;
    if (!pfb_finite(x) || !pfb_finite(y)) return 0;
    if (shape == PF_MASKS_DISK) return (long double)x * x + (long double)y * y <= lim * lim;
    return fabsl((long double)x) <= lim && fabsl((long double)y) <= lim;
}
static void pfb_d_masks(pfc_ctx *c, int which)
{
    int shape = pfb_mask_shape(c), n = pfb_int(c, 1, 130), nt = pfb_int(c, 1, 9), nv = pfb_int(c, 2, 9);
    int null = pfb_null(c, 2), at_start = PFC_R(pfc_next(c)) < 4, rc, k;
    int shape_ok = shape == PF_MASKS_SQUARE || shape == PF_MASKS_DISK, n_ok = n >= 1 && n <= 128;
    long long words = pfb_masks_words_ref(n, nt, nv);
    if (which == 0) { /* samples */
        pf_real *xy;
        pfb_setcall("pf_masks_samples(%d, %d, 7, %s)", shape, n, null ? "NULL" : "xy");
        if (!shape_ok || !n_ok || null) {
            pf_real *b[1];
            b[0] = null ? 0 : pfb_small();
            rc = pf_masks_samples(shape, n, 7, b[0]);
            pfb_rc_check(rc, PFB_A_ARG, "pf_masks_samples");
            pfb_check_untouched(b, 1);
            return;
        }
        /* the construction costs ~n^2: above 32 samples in 1 call of 8 (fuzzer throughput) */
        if (n > 32 && (pfc_next(c) & 7u) != 0u) return;
        xy = pfb_map(2LL * n, at_start);
        if (!xy) return;
        pfb_fill_canary(xy, 2LL * n);
        if (pfb_t) pfb_t->run += 1;
        rc = pf_masks_samples(shape, n, 7, xy);
        if (!pfb_rc_check(rc, PFB_A_OK, "pf_masks_samples")) return;
        pfb_check_written(xy, 2LL * n, "xy", 1);
        for (k = 0; k < n; ++k)
            if (!pfb_mask_inside(shape, xy[2 * k], xy[2 * k + 1])) {
                pfb_fail(PFB_VALUE, "sample %d (%a, %a) outside the footprint", k, (double)xy[2 * k], (double)xy[2 * k + 1]);
                break;
            }
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
        return;
    }
    if (which == 1) { /* table words */
        long long got = pf_masks_table_words(n, nt, nv);
        pfb_setcall("pf_masks_table_words(%d, %d, %d)", n, nt, nv);
        if (got != words) pfb_fail(PFB_VALUE, "= %lld, expected %lld", got, words);
        return;
    }
    if (which == 2) { /* build */
        pfb_expect ex = {0, 0, 0};
        int bad_sample = PFC_R(pfc_next(c)) == 0, *table;
        pf_real *xy;
        if (!shape_ok || null) ex.arg = 1;
        if (!n_ok || nt < 1 || nv < 2) ex.small = 1;
        if (nt > 32768 || nv > 32768) ex.size = 1;
        /* the table's words in the driver's own checked arithmetic: above PFB_MAX_REALS (2^28
           on 32-bit hosts, e.g. 32768 x 4096 x 4 words) the size is refused */
        if (!ex.small && !ex.size && n_ok && pfb_mul(pfb_mul(nt, nv), (n + 31) / 32) < 0) ex.size = 1;
        pfb_setcall("pf_masks_table_build(%d, %d, %d, %s, %d, %s)", shape, nt, nv, null == 1 ? "NULL" : "xy", n,
                    null == 2 ? "NULL" : "table");
        if (pfb_allowed(ex) != PFB_A_OK) {
            pf_real *b[2];
            b[0] = null == 1 ? 0 : pfb_small();
            b[1] = null == 2 ? 0 : pfb_small();
            rc = pf_masks_table_build(shape, nt, nv, b[0], n, (int *)(void *)b[1]);
            pfb_rc_check(rc, pfb_allowed(ex), "pf_masks_table_build");
            pfb_check_untouched(b, 2);
            return;
        }
        if (words * 4 / (long long)sizeof(pf_real) > pfb_work_cap) return;
        xy = pfb_map(2LL * n, !at_start);
        table = pfb_map_ints(words, at_start);
        if (!xy || !table) return;
        for (k = 0; k < n; ++k) { /* points of the footprint from the draws; one bad on request */
            pf_real x = pfc_unif(pfc_next(c)) - PF_R(0.5), y = pfc_unif(pfc_next(c)) - PF_R(0.5);
            if (shape == PF_MASKS_DISK) { x *= PF_R(0.7); y *= PF_R(0.7); }
            xy[2 * k] = x;
            xy[2 * k + 1] = y;
        }
        if (bad_sample) xy[2 * (int)(pfc_next(c) % (pfc_u32)n) + (int)(pfc_next(c) & 1u)] = pfb_coord(c, PF_R(0.6), PF_R(1e6));
        if (pfb_t) pfb_t->run += 1;
        rc = pf_masks_table_build(shape, nt, nv, xy, n, table);
        {
            int any_bad = 0;
            for (k = 0; k < n; ++k) any_bad |= !pfb_mask_inside(shape, xy[2 * k], xy[2 * k + 1]);
            if (any_bad) {
                long long q;
                pfb_rc_check(rc, PFB_A_ARG, "pf_masks_table_build");
                for (q = 0; q < words; ++q)
                    if (table[q] != PFB_MASK_CANARY) { pfb_fail(PFB_WROTE, "table[%lld] written on error", q); break; }
                if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
                return;
            }
        }
        if (!pfb_rc_check(rc, PFB_A_OK, "pf_masks_table_build")) return;
        {
            int W = (n + 31) / 32, i, j, w;
            for (i = 0; i < nt; ++i)
                for (j = 0; j < nv; ++j)
                    for (w = 0; w < W; ++w) {
                        int used = n - 32 * w >= 32 ? 32 : n - 32 * w;
                        pfc_u32 m = (pfc_u32)table[((long long)i * nv + j) * W + w];
                        pfc_u32 lowmask = used == 32 ? 0xFFFFFFFFu : ((1u << used) - 1u);
                        pfc_u32 prev = j > 0 ? (pfc_u32)table[((long long)i * nv + j - 1) * W + w] : 0u;
                        if ((m & ~lowmask) != 0u) { pfb_fail(PFB_VALUE, "mask (%d, %d) word %d: unused bits set", i, j, w); return; }
                        if (j == 0 && m != 0u) { pfb_fail(PFB_VALUE, "mask (%d, 0) not empty", i); return; }
                        if (j == nv - 1 && m != lowmask) { pfb_fail(PFB_VALUE, "mask (%d, %d) not full", i, j); return; }
                        if ((prev & ~m) != 0u) { pfb_fail(PFB_VALUE, "mask (%d, %d) does not grow with v", i, j); return; }
                    }
        }
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
        return;
    }
    { /* fetch */
        int idx = pfb_int(c, 0, 40), W = n_ok ? (n + 31) / 32 : 0, *table = 0;
        long long q;
        pf_mask m;
        pfb_setcall("pf_masks_table_fetch(%s, %d, %d, %d, %d)", null ? "NULL" : "table", nt, nv, idx, n);
        if (words > 0 && !null) {
            if (words * 4 / (long long)sizeof(pf_real) > PFB_MAX_REALS / 2) return;
            pfb_fresh = 1;
            table = pfb_map_ints(words, at_start);
            if (!table) return;
            if (words * 4 / (long long)sizeof(pf_real) <= pfb_work_cap)
                for (q = 0; q < words; ++q) table[q] = (int)(q * 40503 % 2147483647);
            else
                for (q = 0; q < words; ++q) if (q < 64 || q >= words - 64) table[q] = (int)(q * 40503 % 2147483647); else break;
        }
        m = pf_masks_table_fetch(table, nt, nv, idx, n);
        if (words == 0 || null || idx < 0 || (long long)idx >= (long long)nt * nv) {
            if (m.w0 || m.w1 || m.w2 || m.w3) pfb_fail(PFB_VALUE, "bad input gave a non-empty mask");
            return;
        }
        {
            int want[4] = {0, 0, 0, 0}, w;
            for (w = 0; w < W; ++w) {
                long long at = (long long)idx * W + w;
                want[w] = table[at];
            }
            if (m.w0 != want[0] || m.w1 != want[1] || m.w2 != want[2] || m.w3 != want[3])
                pfb_fail(PFB_VALUE, "fetched words differ from the table's");
        }
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
    }
}
static void pfb_w_masks(pfc_ctx *c, int which) { pfb_d_masks(c, which); }

/* ---------------------------------------------------------------- the table of drivers */
typedef struct pfb_entry {
    const char *name;   /* the function(s) checked, space-separated (tests/fuzz/coverage.sh reads them) */
    const char *module; /* moments, height, gaussgrid */
    void (*fn)(pfc_ctx *c, int arg);
    int arg;
} pfb_entry;

static void pfb_w_layout(pfc_ctx *c, int a) { (void)a; pfb_d_mip_layout(c); }
static void pfb_w_core(pfc_ctx *c, int a) { (void)a; pfb_d_core(c); }
static void pfb_w_table_size(pfc_ctx *c, int a) { (void)a; pfb_d_table_size(c); }
static void pfb_w_table_build(pfc_ctx *c, int a) { (void)a; pfb_d_table_build(c); }
static void pfb_w_table_lookup(pfc_ctx *c, int a) { (void)a; pfb_d_table_lookup(c); }
static void pfb_w_hermite(pfc_ctx *c, int a) { (void)a; pfb_d_hermite(c); }

/* ---------------------------------------------------------------- pf_map.h: height fields */
/* pf_map_wrap (which 0), pf_map_slope_stencil (1), pf_map_height and pf_map_node_slope (2),
   pf_map_visible (3): against the driver's own arithmetic, on guarded maps of at most 16 x 16
   heights (every read of the periodic map must land inside them). */
static void pfb_d_map_heights(pfc_ctx *c, int which)
{
    if (which == 0) {
        long long i = pfb_ll(c), n = pfb_ll(c), r, q;
        if (n < 1) n = 1;
        pfb_setcall("pf_map_wrap(%lld, %lld)", i, n);
        r = pf_map_wrap(i, n);
        q = i % n; /* r - q is 0 or n: the same residue */
        if (r < 0 || r >= n || !(r == q || r == q + n)) pfb_fail(PFB_VALUE, "pf_map_wrap = %lld", r);
        return;
    }
    if (which == 1) {
        int n = pfb_int(c, 1, 40), border = pfb_border(c), t;
        long long i = n > 0 ? (long long)(pfc_next(c) % (pfc_u32)n) : 0, x[3];
        pf_real k = pfb_val(c, 20), cf[3], sum, mag;
        if (n < 1) return; /* the contract needs n >= 1 and i in [0, n) */
        pfb_setcall("pf_map_slope_stencil(%lld, %d, %d, %a)", i, n, border, (double)k);
        pf_map_slope_stencil(i, n, border, k, x, cf);
        sum = cf[0] + cf[1] + cf[2];
        mag = PF_FABS(cf[0]) + PF_FABS(cf[1]) + PF_FABS(cf[2]);
        for (t = 0; t < 3; ++t)
            if (x[t] < 0 || x[t] >= n) pfb_fail(PFB_VALUE, "stencil index %lld outside [0, %d)", x[t], n);
        /* a difference stencil: the coefficients sum to 0 (a constant map has no slope) */
        if (!(PF_FABS(sum) <= PF_R(8.0) * PF_REAL_EPSILON * mag)) pfb_fail(PFB_VALUE, "stencil sums to %a", (double)sum);
        if (n == 1 && mag != PF_R(0.0)) pfb_fail(PFB_VALUE, "n = 1 has no slope");
        return;
    }
    {
        int w = 1 + (int)(pfc_next(c) % 16u), h = 1 + (int)(pfc_next(c) % 16u), at_start = PFC_R(pfc_next(c)) < 8;
        long long x = pfb_ll(c) % 1000003, y = pfb_ll(c) % 1000003, xw, yw;
        pf_real *hm = pfb_map((long long)w * h, at_start), texel = pfb_coord(c, PF_R(0.25), PF_R(4.0));
        if (!hm) return;
        pfb_fill(c, hm, (long long)w * h, 4);
        xw = ((x % w) + w) % w;
        yw = ((y % h) + h) % h;
        if (which == 2) {
            pf_real sx, sy, k, ex, ey;
            pfb_setcall("pf_map_height / pf_map_node_slope(%dx%d, %a, %lld, %lld)", w, h, (double)texel, x, y);
            if (pf_map_height(hm, w, h, x, y) != hm[yw * w + xw]) pfb_fail(PFB_VALUE, "pf_map_height reads the wrong texel");
            if (!(texel > PF_R(0.0)) || !(texel <= PF_REAL_MAX)) return; /* texel > 0 finite by contract */
            pf_map_node_slope(hm, w, h, texel, x, y, &sx, &sy);
            k = PF_R(0.5) / texel;
            ex = k * (hm[yw * w + (xw + 1) % w] - hm[yw * w + (xw + w - 1) % w]);
            ey = k * (hm[((yw + 1) % h) * w + xw] - hm[((yw + h - 1) % h) * w + xw]);
            if (!(sx == ex || (sx != sx && ex != ex)) || !(sy == ey || (sy != sy && ey != ey)))
                pfb_fail(PFB_VALUE, "pf_map_node_slope (%a, %a), want (%a, %a)", (double)sx, (double)sy, (double)ex, (double)ey);
        } else {
            int n = 1 + (int)(pfc_next(c) % 16u), v;
            long long x0 = pfb_ll(c) % 1000003, y0 = pfb_ll(c) % 1000003, t;
            pf_vec3 d = pfc_dir_any(c);
            pf_real top = -PF_REAL_MAX;
            if (n > w) n = w;
            if (n > h) n = h;
            if (!(texel > PF_R(0.0)) || !(texel <= PF_REAL_MAX)) return;
            for (t = 0; t < (long long)w * h; ++t) top = pf_max(top, hm[t]);
            pfb_setcall("pf_map_visible(%dx%d, %a, (%lld, %lld), d, (%lld, %lld, %d))", w, h, (double)texel, x, y, x0, y0, n);
            v = pf_map_visible(hm, w, h, texel, x, y, d, x0, y0, n, top);
            if (v != 0 && v != 1) pfb_fail(PFB_VALUE, "pf_map_visible = %d", v);
            if (v == 1 && !(d.z > PF_R(0.0))) pfb_fail(PFB_VALUE, "visible toward d.z <= 0");
        }
    }
}

/* ---------------------------------------------------------------- pf_horizon.h */
/* pf_horizon_channels (which 2), pf_horizon_map (0), pf_horizon_pyramid (1). Accepted builds run
   with at most 64 march steps (the march costs max_steps per texel and azimuth at the highest
   texel); 1 accepted draw in 8 puts a NaN or an infinity in the heights: PF_ERR_ARG, nothing
   written. */
static void pfb_d_horizon(pfc_ctx *c, int which)
{
    static const char *const fns[] = { "pf_horizon_map", "pf_horizon_pyramid", "pf_horizon_channels" };
    const char *fn = fns[which];
    int w = pfb_int(c, 1, 24), h = pfb_int(c, 1, 24), naz = pfb_int(c, 1, 16), steps = pfb_int(c, 1, 20);
    pfc_u32 ku = pfc_next(c);
    int kind = PFC_R(ku) < 5 ? PF_HORIZON_ANGLES : (PFC_R(ku) < 10 ? PF_HORIZON_MOMENTS : (PFC_R(ku) < 15 ? PF_HORIZON_LEGENDRE : pfb_int(c, -2, 5)));
    int k = pfb_int(c, 1, 8), border = pfb_border(c), null = pfb_null(c, 2), at_start = PFC_R(pfc_next(c)) < 4;
    pf_real sp = pfb_coord(c, PF_R(0.1), PF_R(4.0));
    pfc_u32 bad_u = pfc_next(c);
    int bad_height = PFC_R(bad_u) < 2, rc, allowed;
    long long per = kind == PF_HORIZON_ANGLES ? 1 : (kind == PF_HORIZON_MOMENTS ? 3 : (kind == PF_HORIZON_LEGENDRE ? k : -1));
    long long nc = -1, nh = -1, nout = -1;
    pfb_expect ex = { 0, 0, 0 };
    pf_real *hm, *out;
    if (per < 1 || per > PF_HORIZON_LEGENDRE_MAX) per = -1;
    if (which == 2) {
        long long want = (per < 1 || naz < 1 || naz > PFB_MAX_SIDE || per * naz > PFB_MAX_SIDE) ? 0 : per * naz;
        pfb_setcall("pf_horizon_channels(%d, %d, %d)", kind, naz, k);
        if (pf_horizon_channels(kind, naz, k) != want)
            pfb_fail(PFB_VALUE, "pf_horizon_channels = %d, expected %lld", pf_horizon_channels(kind, naz, k), want);
        return;
    }
    pfb_setcall("%s(%s, %d, %d, %a, %d, %d, %d, %d, %d, %s)", fn, null == 1 ? "NULL" : "heights", w, h, (double)sp, naz,
                steps, border, kind, k, null == 2 ? "NULL" : "out");
    if (null) ex.arg = 1;
    pfb_side(&ex, w, 1);
    pfb_side(&ex, h, 1);
    pfb_side(&ex, naz, 1);
    pfb_side(&ex, steps, 1);
    if (!(sp > 0 && sp <= PF_REAL_MAX)) ex.arg = 1;
    if (!pfb_border_ok(border) || per < 0) ex.arg = 1;
    if (!ex.small && !ex.size && per > 0) {
        nc = per * naz;
        nh = pfb_mul(w, h);
        if (nc > PFB_MAX_SIDE) ex.size = 1;
        else {
            nout = which ? pfb_pyr_reals(w, h, nc) : pfb_mul(nh, nc);
            if (nh < 0 || nout < 0) ex.size = 1;
        }
    }
    allowed = pfb_allowed(ex);
    if (allowed != PFB_A_OK) {
        pf_real *b[2];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        rc = which ? pf_horizon_pyramid(b[0], w, h, sp, naz, steps, border, kind, k, b[1])
                   : pf_horizon_map(b[0], w, h, sp, naz, steps, border, kind, k, b[1]);
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 2);
        return;
    }
    if (nout > pfb_work_cap || steps > 64) return;
    hm = pfb_map(nh, at_start);
    out = pfb_map(nout, !at_start);
    if (!hm || !out) return;
    pfb_fill(c, hm, nh, 20);
    pfb_fill_canary(out, nout);
    if (bad_height) {
        hm[(long long)(PFC_B(bad_u) % (pfc_u32)nh)] = (PFC_B(bad_u) & 1u) ? pfc_from_bits(0x7FC00000u) : -pfc_from_bits(0x7F800000u);
        allowed = PFB_A_ARG;
    }
    if (pfb_t) pfb_t->run += 1;
    rc = which ? pf_horizon_pyramid(hm, w, h, sp, naz, steps, border, kind, k, out)
               : pf_horizon_map(hm, w, h, sp, naz, steps, border, kind, k, out);
    if (!pfb_rc_check(rc, allowed, fn)) return;
    if (bad_height) {
        if (pfb_count_changed(out, nout)) pfb_fail(PFB_WROTE, "%lld reals written on a non-finite height", pfb_count_changed(out, nout));
        return;
    }
    pfb_check_written(out, nout, "out", 1);
    if (kind == PF_HORIZON_ANGLES) {
        long long i;
        for (i = 0; i < nh * nc; ++i)
            if (!(out[i] >= -PF_R(1.5707964) && out[i] <= PF_R(1.5707964))) {
                pfb_fail(PFB_VALUE, "angle %lld = %a outside [-pi/2, pi/2]", i, (double)out[i]);
                break;
            }
    }
    if (which) pfb_check_levels(out, w, h, (int)nc, 0, fn);
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_vmf.h */
/* pf_vmf_fit_normals (which 0), pf_vmf_pyramid_from_normals (1), the layout functions (2),
   pf_vmf_mixture_from_texel (3). Accepted fits and pyramids run on at most 64 normals with at
   most 4 EM iterations; normals and weights over every regime (zero, negative, NaN and
   infinite weights, zero and huge normals): the fit may then find no usable normal
   (PF_ERR_ARG, one flat lobe), which the contract allows; pyramids always return PF_OK. */
static int pfb_vmf_pow2(long long n) { return n >= 1 && n <= PFB_MAX_SIDE && (n & (n - 1)) == 0; }
static void pfb_vmf_check_mixture(const pf_vmf_mixture *m, int lobes, const char *fn)
{
    long double sum = 0;
    int k;
    if (m->count < 1 || m->count > lobes) { pfb_fail(PFB_VALUE, "%s: %d lobes, asked %d", fn, m->count, lobes); return; }
    for (k = 0; k < m->count; ++k) {
        const pf_vmf_lobe *l = &m->lobe[k];
        if (!pfb_finite(l->amp) || !pfb_finite(l->kappa) || !pfb_finite(l->mu.x) || !pfb_finite(l->mu.y) || !pfb_finite(l->mu.z)) {
            pfb_fail(PFB_NONFINITE, "%s: lobe %d not finite", fn, k);
            return;
        }
        if (!(l->amp >= 0 && l->kappa >= PF_VMF_KAPPA_MIN && l->kappa <= PF_VMF_KAPPA_MAX && l->mu.z >= 0) ||
            fabsl((long double)l->mu.x * l->mu.x + (long double)l->mu.y * l->mu.y + (long double)l->mu.z * l->mu.z - 1.0L) > 1e-4L)
            pfb_fail(PFB_VALUE, "%s: lobe %d out of range", fn, k);
        sum += l->amp;
    }
    if (fabsl(sum - 1.0L) > 1e-4L) pfb_fail(PFB_VALUE, "%s: amplitudes sum to %Lg", fn, sum);
}
static void pfb_d_vmf(pfc_ctx *c, int which)
{
    static const char *const fns[] = { "pf_vmf_fit_normals", "pf_vmf_pyramid_from_normals", "pf_vmf_pyramid_level_count",
                                       "pf_vmf_mixture_from_texel" };
    const char *fn = fns[which];
    int lobes = pfb_int(c, 1, 8), iters = pfb_int(c, 0, 4), null = pfb_null(c, 2), at_start = PFC_R(pfc_next(c)) < 4;
    int use_w = PFC_R(pfc_next(c)) < 8, rc, allowed;
    pfb_expect ex = { 0, 0, 0 };
    if (which == 2) { /* layout against the driver's own arithmetic */
        int w = pfb_int(c, 1, 64), h = pfb_int(c, 1, 64), level = pfb_int(c, 0, 12);
        int ok = pfb_vmf_pow2(w) && pfb_vmf_pow2(h);
        long long lc = ok ? pfb_levels(w, h) : 0, off = ok && level >= 0 ? pfb_offset(w, h, level) : -1;
        pfb_setcall("pf_vmf_pyramid_level_count/offset/texel_count(%d, %d, %d)", w, h, level);
        if (pf_vmf_pyramid_level_count(w, h) != lc || pf_vmf_pyramid_level_offset(w, h, level) != off ||
            pf_vmf_pyramid_texel_count(w, h) != (ok && pfb_offset(w, h, 64) <= PFB_MAX_REALS ? pfb_offset(w, h, 64) : 0))
            pfb_fail(PFB_VALUE, "layout: count %d (want %lld), offset %lld (want %lld)", pf_vmf_pyramid_level_count(w, h), lc,
                     pf_vmf_pyramid_level_offset(w, h, level), off);
        return;
    }
    if (which == 3) {
        int n = lobes < 1 ? 1 : (lobes > PF_VMF_MAX_LOBES ? PF_VMF_MAX_LOBES : lobes);
        pf_real *t = null ? 0 : pfb_map(4LL * n, at_start);
        pf_vmf_mixture m;
        int k;
        pfb_setcall("pf_vmf_mixture_from_texel(%s, %d)", t ? "texel" : "NULL", lobes);
        if (t) pfb_fill(c, t, 4LL * n, 4);
        m = pf_vmf_mixture_from_texel(t, lobes);
        if (m.count < 0 || m.count > n || (!t && m.count != 0)) pfb_fail(PFB_VALUE, "%d lobes from %d", m.count, n);
        for (k = 0; k < m.count && k < PF_VMF_MAX_LOBES; ++k)
            if (!(m.lobe[k].amp > 0) || !pfb_finite(m.lobe[k].mu.z) || !(m.lobe[k].kappa >= PF_VMF_KAPPA_MIN))
                pfb_fail(PFB_VALUE, "lobe %d of the texel out of range", k);
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
        return;
    }
    if (null) ex.arg = 1;
    if (lobes < 1 || lobes > PF_VMF_MAX_LOBES || iters < 0) ex.arg = 1;
    if (which == 0) {
        long long n = pfb_int(c, 1, 64), nn = pfb_mul(n, 3);
        pf_vmf_mixture m;
        pf_real *nr, *wt = 0;
        pfb_setcall("pf_vmf_fit_normals(%s, %s, %lld, %d, %d, %s)", null == 1 ? "NULL" : "normals", use_w ? "weights" : "NULL",
                    n, lobes, iters, null == 2 ? "NULL" : "out");
        if (n < 1) ex.small = 1;
        else if (nn < 0) ex.size = 1;
        allowed = pfb_allowed(ex);
        if (allowed != PFB_A_OK) {
            pf_real *b[2];
            b[0] = null == 1 ? 0 : pfb_small();
            b[1] = use_w ? pfb_small() : 0;
            rc = pf_vmf_fit_normals(b[0], b[1], n, lobes, iters, null == 2 ? 0 : &m);
            pfb_rc_check(rc, allowed, fn);
            pfb_check_untouched(b, 2);
            return;
        }
        if (nn > pfb_work_cap || iters > 8) return;
        nr = pfb_map(nn, at_start);
        if (use_w) wt = pfb_map(n, !at_start);
        if (!nr || (use_w && !wt)) return;
        pfb_fill(c, nr, nn, 2);
        if (use_w) pfb_fill_weights(c, wt, n);
        if (pfb_t) pfb_t->run += 1;
        m.count = -77;
        rc = pf_vmf_fit_normals(nr, wt, n, lobes, iters, &m);
        if (!pfb_rc_check(rc, PFB_A_OK | PFB_A_ARG, fn)) return;
        if (rc == PF_OK) pfb_vmf_check_mixture(&m, lobes, fn);
        else if (m.count != -77) pfb_fail(PFB_WROTE, "%s: *out written on an error", fn); /* no usable normal */
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
        return;
    } else {
        int w = pfb_int(c, 1, 8), h = pfb_int(c, 1, 8);
        long long nn = -1, nout = -1, texels;
        pf_real *nr, *wt = 0, *out;
        long long t;
        pfb_setcall("pf_vmf_pyramid_from_normals(%s, %s, %d, %d, %d, %d, %s)", null == 1 ? "NULL" : "normals",
                    use_w ? "weights" : "NULL", w, h, lobes, iters, null == 2 ? "NULL" : "pyr");
        pfb_side(&ex, w, 1);
        pfb_side(&ex, h, 1);
        if (!ex.small && !ex.size) {
            if (!pfb_vmf_pow2(w) || !pfb_vmf_pow2(h)) ex.arg = 1;
            else {
                nn = pfb_mul(pfb_mul(w, h), 3);
                nout = lobes >= 1 && lobes <= PF_VMF_MAX_LOBES ? pfb_pyr_reals(w, h, 4LL * lobes) : 0;
                if (nn < 0 || nout < 0) ex.size = 1;
            }
        }
        allowed = pfb_allowed(ex);
        if (allowed != PFB_A_OK) {
            pf_real *b[3];
            b[0] = null == 1 ? 0 : pfb_small();
            b[1] = use_w ? pfb_small() : 0;
            b[2] = null == 2 ? 0 : pfb_small();
            rc = pf_vmf_pyramid_from_normals(b[0], b[1], w, h, lobes, iters, b[2]);
            pfb_rc_check(rc, allowed, fn);
            pfb_check_untouched(b, 3);
            return;
        }
        if (nout > pfb_work_cap || nn > 3 * 64 || iters > 8) return;
        nr = pfb_map(nn, at_start);
        if (use_w) wt = pfb_map(nn / 3, !at_start);
        out = pfb_map(nout, !at_start);
        if (!nr || !out || (use_w && !wt)) return;
        pfb_fill(c, nr, nn, 2);
        if (use_w) pfb_fill_weights(c, wt, nn / 3);
        pfb_fill_canary(out, nout);
        if (pfb_t) pfb_t->run += 1;
        rc = pf_vmf_pyramid_from_normals(nr, wt, w, h, lobes, iters, out);
        if (!pfb_rc_check(rc, PFB_A_OK, fn)) return;
        pfb_check_written(out, nout, "pyr", 1);
        texels = nout / (4LL * lobes);
        for (t = 0; t < texels; ++t) {
            pf_vmf_mixture m = pf_vmf_mixture_from_texel(out + t * 4 * lobes, lobes);
            if (m.count < 1) { pfb_fail(PFB_VALUE, "texel %lld has no lobe", t); break; }
        }
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
    }
}

/* pf_map_downsample_slopes (which 0), pf_map_downsample_scratch_size (1). Accepted solves run
   on at most pfb_work_cap reals with at most 40 iterations, or any max_iter up to INT_MAX on
   maps of at most 4096 texels (the solver bounds itself by 4 n + 256 iterations, checked); heights over every regime of
   pfb_fill (constant, zero, up to 2^20), one of them NaN or infinite in 1 draw of 8 (then
   PF_ERR_ARG and nothing written); scratch mapped at exactly the documented size (the
   scratch_len passed may be larger), so a touch past it faults. Outputs: every coarse texel
   written and finite, the mean pinned to the fine map's, iterations in [0, max_iter]. */
static long long pfb_ds_need(long long w, long long h, long long f)
{
    if (w < 1 || h < 1 || w > PFB_MAX_SIDE || h > PFB_MAX_SIDE || f < 1 || w % f || h % f || pfb_mul(w, h) < 0) return 0;
    return pfb_mul(pfb_mul(w / f, h / f), 6) < 0 ? 0 : pfb_mul(pfb_mul(w / f, h / f), 6);
}
static void pfb_d_vmf_downsample(pfc_ctx *c, int which)
{
    const char *fn = "pf_map_downsample_slopes";
    int w = pfb_int(c, 1, 16), h = pfb_int(c, 1, 16), f = pfb_int(c, 1, 4), border = pfb_border(c), null = pfb_null(c, 3);
    int max_iter = pfb_int(c, 0, 40), at_start = PFC_R(pfc_next(c)) < 4, rc, allowed, it = -7;
    pf_real reg = pfb_coord(c, PF_R(0.0), PF_R(0.1)), tol = pfb_coord(c, PF_R(0.0), PF_R(1e-3)), res = PF_R(-7.0);
    pfc_u32 lu = pfc_next(c), bad_u = pfc_next(c);
    long long need, slen, nf = -1, nc = -1;
    pfb_expect ex = { 0, 0, 0 };
    pf_real *hm, *out, *scr;
    if (which == 1) {
        long long want = pfb_ds_need(w, h, f);
        pfb_setcall("pf_map_downsample_scratch_size(%d, %d, %d)", w, h, f);
        if (pf_map_downsample_scratch_size(w, h, f) != want)
            pfb_fail(PFB_VALUE, "scratch size %lld, want %lld", pf_map_downsample_scratch_size(w, h, f), want);
        return;
    }
    need = pfb_ds_need(w, h, f);
    switch (PFC_R(lu) % 4u) { /* scratch_len: exact, larger, one short, anything */
    case 0: slen = need; break;
    case 1: slen = need + (long long)(PFC_B(lu) % 9u); break;
    case 2: slen = need - 1; break;
    default: slen = pfb_ll(c); break;
    }
    pfb_setcall("%s(%s, %d, %d, %d, %d, %a, %d, %a, %s, %s, %lld)", fn, null == 1 ? "NULL" : "fine", w, h, f, border,
                (double)reg, max_iter, (double)tol, null == 2 ? "NULL" : "coarse", null == 3 ? "NULL" : "scratch", slen);
    if (null) ex.arg = 1;
    pfb_side(&ex, w, 1);
    pfb_side(&ex, h, 1);
    if (f < 1) ex.small = 1;
    /* finiteness on the bits: under -ffast-math the comparisons alone are folded (a NaN reg
       would read as accepted here while the library, testing the bits, rejects it) */
    if (!pfb_border_ok(border) || !pfb_finite(reg) || !(reg >= 0 && reg <= PF_R(1.0e6)) || max_iter < 0 ||
        !pfb_finite(tol) || !(tol >= 0 && tol <= PF_REAL_MAX))
        ex.arg = 1;
    if (!ex.small && !ex.size) {
        nf = pfb_mul(w, h);
        if (nf < 0) ex.size = 1;
        else if (w % f || h % f) ex.arg = 1;
        else {
            nc = pfb_mul(w / f, h / f);
            if (pfb_mul(nc, 6) < 0) ex.size = 1;
            else if (slen < need) ex.arg = 1;
        }
    }
    allowed = pfb_allowed(ex);
    if (allowed != PFB_A_OK) {
        pf_real *b[3];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        b[2] = null == 3 ? 0 : pfb_small();
        rc = pfi_map_downsample_slopes(b[0], w, h, f, border, reg, max_iter, tol, b[1], b[2], slen, &it, &res);
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 3);
        if (it != -7 || res != PF_R(-7.0)) pfb_fail(PFB_WROTE, "iters/residual written on error");
        return;
    }
    if (nf > pfb_work_cap || need > pfb_work_cap || (max_iter > 40 && nf > 4096)) return;
    hm = pfb_map(nf, at_start);
    out = pfb_map(nc, !at_start);
    scr = pfb_map(need, at_start);
    if (!hm || !out || !scr) return;
    pfb_fill(c, hm, nf, 20);
    if (PFC_R(bad_u) < 2) hm[PFC_B(bad_u) % (pfc_u32)nf] = pfc_from_bits(PFC_R(bad_u) ? 0x7F800000u : 0x7FC00000u);
    pfb_fill_canary(out, nc);
    if (pfb_t) pfb_t->run += 1;
    rc = pfi_map_downsample_slopes(hm, w, h, f, border, reg, max_iter, tol, out, scr, slen, &it, &res);
    if (rc == PF_OK && reg > PF_R(0.0) && max_iter > 0 && tol > PF_R(0.0)) { /* the description passes them through */
        pf_map_downsample_desc dd;
        pf_real *o2 = pfb_map(nc, !at_start), res2 = PF_R(-7.0);
        int it2 = -7;
        memset(&dd, 0, sizeof dd);
        dd.fine = hm, dd.w = w, dd.h = h, dd.factor = f, dd.border = border, dd.reg_weight = reg, dd.max_iter = max_iter, dd.tol = tol;
        if (o2 && (pf_map_downsample_slopes(&dd, o2, scr, slen, &it2, &res2) != PF_OK || it2 != it ||
                   memcmp(o2, out, (size_t)nc * sizeof(pf_real)) != 0))
            pfb_fail(PFB_VALUE, "pf_map_downsample_slopes(desc) differs from the positional solve");
    }
    if (PFC_R(bad_u) < 2) {
        pfb_rc_check(rc, PFB_A_ARG, fn);
        if (pfb_count_changed(out, nc) || it != -7) pfb_fail(PFB_WROTE, "rejected NaN/inf heights but wrote");
    } else if (pfb_rc_check(rc, PFB_A_OK, fn)) {
        long double mf = 0, mc = 0, mx = 0;
        long long i;
        pfb_check_written(out, nc, "coarse", 1);
        for (i = 0; i < nf; ++i) {
            mf += hm[i];
            if (fabsl((long double)hm[i]) > mx) mx = fabsl((long double)hm[i]);
        }
        for (i = 0; i < nc; ++i) mc += out[i];
        if (fabsl(mc / nc - mf / nf) > 1e-3L * mx) pfb_fail(PFB_VALUE, "mean %Lg, fine mean %Lg", mc / nc, mf / nf);
        if (it < 0 || it > max_iter || it > 4 * nc + 256 || !pfb_finite(res) || res < 0)
            pfb_fail(PFB_VALUE, "%d iterations (bound min(max_iter, 4 n + 256) = %lld), residual %a", it,
                     max_iter < 4 * nc + 256 ? (long long)max_iter : 4 * nc + 256, (double)res);
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_vmf.h: scaling function
   (helper J) pfi_vmf_effective_brdf (which 0), pfi_vmf_scale_patch (1), the size queries (2),
   pfi_vmf_scale_factor and pfi_vmf_scale_t on its result (3), pf_vmf_scale_lookup (4). Accepted patch calls run on maps of at most
   16 x 16 with nt, np <= 3 and n <= 8; heights finite, or one NaN/inf (then PF_ERR_ARG or, when
   it lies outside the patch and its ring, PF_OK). The byte scratch of pfi_vmf_scale_patch is
   mapped as whole pf_reals (at most sizeof(pf_real) - 1 bytes of slack before the guard). */
static long long pfb_scale_count(long long nt, long long np)
{
    long long d;
    if (nt < 2 || np < 2 || nt > PFB_MAX_SIDE || np > PFB_MAX_SIDE) return 0;
    d = pfb_mul(pfb_mul(2, nt), np - 1);
    d = d < 0 ? -1 : pfb_mul(d, d);
    return d < 0 ? 0 : d;
}
static long long pfb_scale_cells(long long nt, long long np)
{
    long long c = (nt < 2 || np < 2 || nt > PFB_MAX_SIDE || np > PFB_MAX_SIDE) ? -1 : pfb_mul(pfb_mul(nt, nt), np);
    return c < 0 ? 0 : c;
}
static long long pfb_scale_vis(long long nt, long long np, long long n)
{
    long long d = (nt < 2 || np < 2 || n < 1 || nt > PFB_MAX_SIDE || np > PFB_MAX_SIDE || n > PFB_MAX_SIDE)
                      ? -1
                      : pfb_mul(pfb_mul(2, nt), np - 1);
    d = d < 0 ? -1 : pfb_mul(pfb_mul(d, n), n);
    return d < 0 ? 0 : d;
}
/* pf_vmf_effective_brdf through its description (the fields the effective BRDF reads) */
static int pfb_eff(const pf_real *hm, int w, int h, pf_real texel, int x0, int y0, int n, pf_vec3 wo, pf_vec3 wi,
                   pf_real sigma, pf_real f0, pf_real *out)
{
    pf_vmf_scale_desc d;
    memset(&d, 0, sizeof d);
    d.heights = hm, d.w = w, d.h = h, d.texel = texel, d.base_sigma = sigma, d.f0 = f0;
    return pf_vmf_effective_brdf(&d, x0, y0, n, wo, wi, out);
}
static void pfb_d_vmf_scale(pfc_ctx *c, int which)
{
    static const char *const fns[] = { "pf_vmf_effective_brdf", "pfi_vmf_scale_patch", "pf_vmf_scale_sample_count",
                                       "pfi_vmf_scale_factor", "pf_vmf_scale_lookup" };
    const char *fn = fns[which];
    pfb_expect ex = { 0, 0, 0 };
    int allowed, rc, at_start = PFC_R(pfc_next(c)) < 4;
    if (which == 2) {
        int nt = pfb_int(c, 0, 8), np = pfb_int(c, 0, 8), n = pfb_int(c, 0, 64);
        pfb_setcall("pf_vmf_scale_sample_count/cell_count/vis_bytes(%d, %d, %d)", nt, np, n);
        if (pf_vmf_scale_sample_count(nt, np) != pfb_scale_count(nt, np) || pf_vmf_scale_cell_count(nt, np) != pfb_scale_cells(nt, np) ||
            pf_vmf_scale_vis_bytes(nt, np, n) != pfb_scale_vis(nt, np, n))
            pfb_fail(PFB_VALUE, "sizes %lld %lld %lld, want %lld %lld %lld", pf_vmf_scale_sample_count(nt, np),
                     pf_vmf_scale_cell_count(nt, np), pf_vmf_scale_vis_bytes(nt, np, n), pfb_scale_count(nt, np),
                     pfb_scale_cells(nt, np), pfb_scale_vis(nt, np, n));
        return;
    }
    if (which == 4) {
        int nt = pfb_int(c, 2, 5), np = pfb_int(c, 2, 5), null = pfb_null(c, 1);
        long long cells = pfb_scale_cells(nt, np), i;
        pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
        pf_real tm = pfb_coord(c, PF_R(0.1), PF_R(1.5)), *tab = 0, got;
        long double lo = 1, hi = 1;
        pfb_setcall("%s(%s, %d, %d, %a, dirs)", fn, null ? "NULL" : "table", nt, np, (double)tm);
        if (!null && cells > 0 && cells <= pfb_work_cap) {
            tab = pfb_map(cells, at_start);
            if (!tab) return;
            pfb_fill(c, tab, cells, 10);
            lo = hi = tab[0];
            for (i = 0; i < cells; ++i) {
                if (tab[i] < lo) lo = tab[i];
                if (tab[i] > hi) hi = tab[i];
            }
        }
        if (!null && cells == 0) {
            /* nt or np the layout refuses (below 2, above PF_MAX_SIDE, whole int range): a
               small table against a guard page, which the lookup must not read */
            tab = pfb_small();
            if (!tab) return;
        }
        got = pf_vmf_scale_lookup(tab, nt, np, tm, wo, wi);
        if (cells == 0 && got != PF_R(1.0)) pfb_fail(PFB_VALUE, "lookup %a for a refused size, want 1", (double)got);
        if (!pfb_finite(got) || got < lo - 1e-5L * (fabsl(lo) + fabsl(hi) + 1) || got > hi + 1e-5L * (fabsl(lo) + fabsl(hi) + 1))
            pfb_fail(PFB_VALUE, "lookup %a outside the table's range [%Lg, %Lg]", (double)got, lo, hi);
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
        return;
    }
    if (which == 3) {
        int patches = pfb_int(c, 1, 4), nt = pfb_int(c, 2, 3), np = pfb_int(c, 2, 3), iters = pfb_int(c, 1, 6);
        int null = pfb_null(c, 5), no_err = PFC_R(pfc_next(c)) < 2, no_prior = PFC_R(pfc_next(c)) < 2;
        /* shrink: mostly in [0, 2], sometimes negative, NaN or huge (PF_ERR_ARG) */
        pfc_u32 sel = pfc_next(c);
        pf_real shrink = PFC_R(sel) < 1 ? PF_R(-0.5) : PFC_R(sel) < 2 ? (pf_real)NAN : PFC_R(sel) < 3 ? PF_R(2.0e6) : PF_R(2.0) * pfc_u01(c);
        long long cnt = pfb_scale_count(nt, np), cells = pfb_scale_cells(nt, np), ns = -1, nsc = -1;
        pf_real *b[7];
        pfb_setcall("%s(fe, fl, %d, %d, %d, %d, %a, T, S, scratch, %s, %s) null %d", fn, patches, nt, np, iters, (double)shrink,
                    no_prior ? "NULL" : "prior", no_err ? "NULL" : "err", null);
        if (null || patches < 1 || nt < 2 || np < 2 || iters < 1 || !(shrink >= PF_R(0.0)) || !(shrink <= PF_R(1.0e6))) ex.arg = 1;
        if (!ex.arg) {
            ns = pfb_mul(cnt, patches);
            nsc = pfb_mul(pfb_mul(cells, patches), 2);
            if (cnt == 0 || cells == 0 || ns < 0 || nsc < 0) ex.size = 1;
        }
        allowed = pfb_allowed(ex);
        if (allowed != PFB_A_OK) {
            pf_real *pool[4], *q[6];
            int k;
            /* 4 pool buffers (pfb_small's limit), the last two pointers reuse two of them */
            for (k = 0; k < 4; ++k) pool[k] = pfb_small();
            for (k = 0; k < 6; ++k) q[k] = null == k + 1 ? 0 : pool[k % 4];
            rc = pfi_vmf_scale_factor(q[0], q[1], patches, nt, np, iters, shrink, q[2], q[3], q[4], no_prior ? 0 : q[0],
                                     no_err ? 0 : q[5]);
            pfb_rc_check(rc, allowed, fn);
            pfb_check_untouched(pool, 4);
            return;
        }
        if (ns > pfb_work_cap || nsc > pfb_work_cap || iters > 64) return; /* cost ~ iterations */
        b[0] = pfb_map(ns, at_start);
        b[1] = pfb_map(ns, !at_start);
        b[2] = pfb_map(patches, at_start);
        b[3] = pfb_map(cells, !at_start);
        b[4] = pfb_map(nsc, at_start);
        b[5] = no_err ? 0 : pfb_map(3, !at_start);
        b[6] = no_prior ? 0 : pfb_map(1, at_start);
        if (!b[0] || !b[1] || !b[2] || !b[3] || !b[4] || (!no_err && !b[5]) || (!no_prior && !b[6])) return;
        pfb_fill(c, b[0], ns, 6);
        pfb_fill(c, b[1], ns, 6);
        pfb_fill_canary(b[2], patches);
        pfb_fill_canary(b[3], cells);
        if (b[5]) pfb_fill_canary(b[5], 3);
        if (b[6]) pfb_fill_canary(b[6], 1);
        if (pfb_t) pfb_t->run += 1;
        rc = pfi_vmf_scale_factor(b[0], b[1], patches, nt, np, iters, shrink, b[2], b[3], b[4], b[6], b[5]);
        if (pfb_rc_check(rc, PFB_A_OK, fn)) {
            pfb_check_written(b[2], patches, "T", 1);
            pfb_check_written(b[3], cells, "S", 1);
            if (b[5]) pfb_check_written(b[5], 3, "err", 1);
            if (b[6]) {
                pf_real t1;
                pfb_check_written(b[6], 1, "prior", 1);
                if (!(b[6][0] >= PF_R(0.0))) pfb_fail(PFB_VALUE, "prior %a", (double)b[6][0]);
                /* pfi_vmf_scale_t on the first patch's samples with that prior: finite */
                t1 = pfi_vmf_scale_t(b[0], b[1], nt, np, b[3], b[6][0]);
                if (!pfb_finite(t1)) pfb_fail(PFB_VALUE, "pfi_vmf_scale_t %a", (double)t1);
            }
        }
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
        return;
    }
    {
        /* 0: pfi_vmf_effective_brdf, 1: pfi_vmf_scale_patch */
        int w = pfb_int(c, 1, 16), h = pfb_int(c, 1, 16), n = pfb_int(c, 0, 8), x0 = pfb_int(c, -20, 20), y0 = pfb_int(c, -20, 20);
        int lobes = pfb_int(c, 1, 8), iters = pfb_int(c, 0, 4), masking = pfb_int(c, 1, 3), nt = pfb_int(c, 2, 3), np = pfb_int(c, 2, 3);
        int null = pfb_null(c, which ? 5 : 2);
        pf_real texel = pfb_coord(c, PF_R(0.25), PF_R(2.0)), sigma = pfb_coord(c, PF_R(0.02), PF_R(0.5));
        pf_real tm = pfb_coord(c, PF_R(0.2), PF_R(1.5)), f0 = pfc_u01(c), out = PF_R(-7.0);
        pf_vec3 wo = pfc_dir(c), wi = pfc_dir(c);
        pfc_u32 bad_u = pfc_next(c);
        long long nh = -1, nn = -1, cnt = pfb_scale_count(nt, np), vb = pfb_scale_vis(nt, np, n), vr;
        pf_real *b[5];
        if (which == 0)
            pfb_setcall("%s(%s, %d, %d, %a, %d, %d, %d, dirs, %a, %a, %s)", fn, null == 1 ? "NULL" : "heights", w, h, (double)texel, x0,
                        y0, n, (double)sigma, (double)f0, null == 2 ? "NULL" : "&out");
        else
            pfb_setcall("%s(heights, %d, %d, %a, %d, %d, %d, %d, %d, %a, %a, %d, %d, %d, %a, ...) null %d", fn, w, h, (double)texel, x0,
                        y0, n, lobes, iters, (double)sigma, (double)f0, masking, nt, np, (double)tm, null);
        if (which == 0) { /* the description reads a zero texel, base_sigma or f0 as its default */
            if (texel == PF_R(0.0)) texel = PF_R(1.0);
            if (sigma == PF_R(0.0)) sigma = PF_R(0.1);
        }
        if (null || n < 1 || !(texel > 0 && texel < PF_REAL_MAX) || !(sigma > 0 && sigma < PF_R(1.0e15))) ex.arg = 1;
        if (which == 1 && (lobes < 1 || lobes > PF_VMF_MAX_LOBES || iters < 0 || nt < 2 || np < 2 || masking < PF_VMF_SCALE_G_GAUSSIAN || masking > PF_VMF_SCALE_UNMASKED ||
                           !(tm > 0 && tm < PF_R(1.5707963))))
            ex.arg = 1;
        pfb_side(&ex, w, 1);
        pfb_side(&ex, h, 1);
        if (!ex.small && !ex.size) {
            nh = pfb_mul(w, h);
            if (nh < 0) ex.size = 1;
            else if (n > w || n > h) ex.arg = 1;
        }
        if (which == 1 && !ex.arg && !ex.small && !ex.size) {
            nn = pfb_mul(pfb_mul(n, n), 3);
            if (cnt == 0 || vb == 0 || nn < 0) ex.size = 1;
        }
        allowed = pfb_allowed(ex);
        if (allowed != PFB_A_OK) {
            int k;
            for (k = 0; k < 4; ++k) b[k] = pfb_small();
            b[4] = b[3]; /* 4 pool buffers (pfb_small's limit): f_eff and f_lobes share one */
            if (which == 0) {
                rc = pfb_eff(null == 1 ? 0 : b[0], w, h, texel, x0, y0, n, wo, wi, sigma, f0, null == 2 ? 0 : &out);
                if (null != 2 && out != PF_R(0.0)) pfb_fail(PFB_WROTE, "*out %a on error, documented 0", (double)out);
            } else
                rc = pfi_vmf_scale_patch(null == 1 ? 0 : b[0], w, h, texel, x0, y0, n, lobes, iters, sigma, f0, masking, nt, np, tm,
                                        null == 2 ? 0 : b[1], null == 3 ? 0 : (unsigned char *)(void *)b[2], null == 4 ? 0 : b[3],
                                        null == 5 ? 0 : b[4]);
            pfb_rc_check(rc, allowed, fn);
            pfb_check_untouched(b, 4);
            return;
        }
        vr = (vb + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real);
        if (nh > pfb_work_cap || (which == 1 && (cnt > pfb_work_cap || vr > pfb_work_cap || iters > 64))) return;
        b[0] = pfb_map(nh, at_start);
        if (!b[0]) return;
        pfb_fill(c, b[0], nh, 4);
        if (PFC_R(bad_u) < 2) b[0][PFC_B(bad_u) % (pfc_u32)nh] = pfc_from_bits(PFC_R(bad_u) ? 0x7F800000u : 0x7FC00000u);
        if (pfb_t) pfb_t->run += 1;
        if (which == 0) {
            rc = pfb_eff(b[0], w, h, texel, x0, y0, n, wo, wi, sigma, f0, &out);
            if (pfb_rc_check(rc, PFC_R(bad_u) < 2 ? PFB_A_OK | PFB_A_ARG : PFB_A_OK, fn)) {
                if (rc == PF_OK && (!pfb_finite(out) || out < 0)) pfb_fail(PFB_NONFINITE, "out %a", (double)out);
                if (rc != PF_OK && out != PF_R(0.0)) pfb_fail(PFB_WROTE, "*out %a on error", (double)out);
            }
        } else {
            b[1] = pfb_map(nn, !at_start);
            b[2] = pfb_map(vr, at_start);
            b[3] = pfb_map(cnt, !at_start);
            b[4] = pfb_map(cnt, at_start);
            if (!b[1] || !b[2] || !b[3] || !b[4]) return;
            pfb_fill_canary(b[3], cnt);
            pfb_fill_canary(b[4], cnt);
            rc = pfi_vmf_scale_patch(b[0], w, h, texel, x0, y0, n, lobes, iters, sigma, f0, masking, nt, np, tm, b[1],
                                    (unsigned char *)(void *)b[2], b[3], b[4]);
            if (pfb_rc_check(rc, PFC_R(bad_u) < 2 ? PFB_A_OK | PFB_A_ARG : PFB_A_OK, fn) && rc == PF_OK) {
                long long i;
                pfb_check_written(b[3], cnt, "f_eff", 1);
                pfb_check_written(b[4], cnt, "f_lobes", 1);
                for (i = 0; i < cnt; ++i)
                    if (b[3][i] < 0 || b[4][i] < 0) { pfb_fail(PFB_VALUE, "sample %lld negative", i); break; }
            }
        }
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
    }
}

/* pf_vmf_scale_fit_level (which 0), pf_vmf_scale_texel_t (1), pf_vmf_scale_scratch_size (2):
   descriptions drawn over every field (zero: the default; bad sides, levels, lobes, node
   counts, maskings, NULL pointers), maps of at most 16 x 16, levels up to 3, lobe pyramids
   fitted here from drawn normals; the scratch is an exact-size guarded buffer (1 draw in 8
   one real short: PF_ERR_ARG). Accepted calls must give finite S, priors and T. */
static void pfb_d_vmf_level(pfc_ctx *c, int which)
{
    static const char *const fns[] = { "pf_vmf_scale_fit_level", "pf_vmf_scale_texel_t", "pf_vmf_scale_scratch_size" };
    const char *fn = fns[which];
    pf_vmf_scale_desc d;
    int pw = (int)(pfc_next(c) % 5u), ph = (int)(pfc_next(c) % 5u), odd = PFC_R(pfc_next(c)) == 0;
    int w = odd ? pfb_int(c, 1, 16) : 1 << pw, h = odd ? pfb_int(c, 1, 16) : 1 << ph, level = pfb_int(c, 0, 3), k, rc;
    int short_scratch = PFC_R(pfc_next(c)) < 2, nulls = pfb_null(c, 3);
    long long need, tx = pfb_int(c, 0, 3), ty = pfb_int(c, 0, 3), i, cells;
    pf_real *hm = 0, *nm = 0, *pyr[2] = { 0, 0 }, *scratch, S[2][6 * 6 * 5], prior[2] = { 0, 0 }, t[2] = { 0, 0 };
    pf_real *s_out[2] = { S[0], S[1] };
    const pf_real *s_in[2] = { S[0], S[1] };
    memset(&d, 0, sizeof d);
    d.pyramid_count = pfb_int(c, 0, 2);
    d.lobes[0] = pfb_int(c, 1, 4), d.lobes[1] = pfb_int(c, 1, 4);
    d.masking = pfb_int(c, 0, 3), d.nt = pfb_int(c, 0, 3), d.np = pfb_int(c, 0, 3);
    d.train_patches = pfb_int(c, 0, 3), d.rounds = pfb_int(c, 0, 3);
    d.texel = pfb_coord(c, PF_R(0.25), PF_R(2.0)), d.base_sigma = pfb_coord(c, PF_R(0.02), PF_R(0.5));
    d.f0 = pfc_u01(c), d.shrink = pfb_coord(c, PF_R(0.0), PF_R(2.0)), d.theta_max = pfb_coord(c, PF_R(0.2), PF_R(1.5));
    if (PFC_R(pfc_next(c)) < 8) d.nt = 0, d.np = 0; /* the default 6 x 5 nodes half the time: S fits S[] */
    if (d.nt > 6 || d.np > 5 || d.nt < 0 || d.np < 0) d.nt = d.np = 0;
    if (d.rounds > 8) d.rounds = 8; /* the cost is rounds x cells x patches: keep a call fast */
    pfb_setcall("%s(desc %dx%d, %d pyramids, lobes %d %d, masking %d, nt %d, np %d, train %d, rounds %d, level %d, texel (%lld, %lld))",
                fn, w, h, d.pyramid_count, d.lobes[0], d.lobes[1], d.masking, d.nt, d.np, d.train_patches, d.rounds, level, tx, ty);
    if (w >= 1 && h >= 1 && w <= 16 && h <= 16) {
        hm = pfb_map((long long)w * h, 0);
        nm = pfb_map(3LL * w * h, 1);
        if (!hm || !nm) return;
        pfb_fill(c, hm, (long long)w * h, 3);
        pfb_fill(c, nm, 3LL * w * h, 2);
        for (k = 0; k < 2; ++k) {
            long long tc = pf_vmf_pyramid_texel_count(w, h);
            int lk = d.lobes[k] >= 1 && d.lobes[k] <= PF_VMF_MAX_LOBES ? d.lobes[k] : 1; /* the size desc says */
            if (tc <= 0) break;
            pyr[k] = pfb_map(tc * 4 * lk, k);
            if (!pyr[k] || pf_vmf_pyramid_from_normals(nm, NULL, w, h, lk, 2, pyr[k]) != PF_OK) return;
        }
    }
    d.heights = nulls == 1 ? 0 : hm, d.w = w, d.h = h;
    d.pyramid[0] = nulls == 2 ? 0 : pyr[0], d.pyramid[1] = pyr[1];
    need = pf_vmf_scale_scratch_size(nulls == 3 ? 0 : &d, level);
    if (which == 2) {
        if (need < 0) pfb_fail(PFB_VALUE, "scratch size %lld", need);
        return;
    }
    if (need <= 0) { /* a description the calls reject: any buffer, an error */
        scratch = pfb_small();
        rc = which == 0 ? pf_vmf_scale_fit_level(nulls == 3 ? 0 : &d, level, s_out, prior, 0, scratch, 16)
                        : pf_vmf_scale_texel_t(nulls == 3 ? 0 : &d, level, tx, ty, s_in, prior, t, scratch, 16);
        if (rc != PF_ERR_ARG && rc != PF_ERR_SIZE) pfb_fail(PFB_VALUE, "%s: rc %d for a rejected description", fn, rc);
        return;
    }
    if (need > pfb_work_cap) return;
    cells = pf_vmf_scale_cell_count(d.nt ? d.nt : 6, d.np ? d.np : 5);
    scratch = pfb_map(need, PFC_R(pfc_next(c)) < 8);
    if (!scratch) return;
    if (pfb_t) pfb_t->run += 1;
    rc = pf_vmf_scale_fit_level(&d, level, s_out, prior, 0, scratch, short_scratch ? need - 1 : need);
    if (short_scratch) {
        if (rc != PF_ERR_ARG) pfb_fail(PFB_VALUE, "%s: rc %d with a short scratch", fn, rc);
        return;
    }
    if (rc != PF_OK) { /* non-finite heights in a patch, a bad texel, sigma, theta_max */
        if (rc != PF_ERR_ARG) pfb_fail(PFB_VALUE, "%s: rc %d", fn, rc);
        return;
    }
    for (k = 0; k < (d.pyramid_count ? d.pyramid_count : 1); ++k) {
        if (!pfb_finite(prior[k])) pfb_fail(PFB_NONFINITE, "prior %d", k);
        for (i = 0; i < cells; ++i)
            if (!pfb_finite(S[k][i])) { pfb_fail(PFB_NONFINITE, "S[%d][%lld]", k, i); break; }
    }
    if (which == 1) {
        rc = pf_vmf_scale_texel_t(&d, level, tx, ty, s_in, prior, t, scratch, need);
        if (rc == PF_OK && (!pfb_finite(t[0]) || !pfb_finite(t[1]))) pfb_fail(PFB_NONFINITE, "T");
        if (rc != PF_OK && rc != PF_ERR_ARG) pfb_fail(PFB_VALUE, "%s: rc %d", fn, rc);
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_encode.h: encoders
   which: 0 pf_encode_ranges + pf_encode_channels, 1 pf_slope_encoding_find +
   pf_slope_moments_encode, 2 pf_vmf_encoding_find + pf_vmf_lobes_encode; texel counts and
   channel counts from the whole int range, a format from {UNORM16, UNORM8, HALF} or any int,
   1 in 16 a NaN or inf texel. Rejected calls write nothing (their output is checked); accepted
   ones: generic UNORM codes decode within half a step (plus rounding) of their texels, decoded
   slope moments and lobes finite. */
static int pfb_enc_format(pfc_ctx *c)
{
    pfc_u32 u = pfc_next(c);
    return PFC_R(u) < 14 ? (int)(PFC_B(u) % 3u) : pfb_int(c, -2, 5);
}
static pf_real pfb_enc_s(const void *q, long long i, int f)
{
    if (f == PF_ENCODE_HALF) return pf_real_from_half(((const unsigned short *)q)[i]);
    if (f == PF_ENCODE_UNORM16) return (pf_real)((const unsigned short *)q)[i] / PF_R(65535.0);
    return (pf_real)((const unsigned char *)q)[i] / PF_R(255.0);
}
static void pfb_d_encode(pfc_ctx *c, int which)
{
    static const char *const fns[] = { "pf_encode_ranges/pf_encode_channels", "pf_slope_encoding_find/pf_slope_moments_encode",
                                       "pf_vmf_encoding_find/pf_vmf_lobes_encode" };
    const char *fn = fns[which];
    int n = pfb_int(c, 0, 40), nc = which == 0 ? pfb_int(c, 0, 6) : (which == 1 ? 5 : 4);
    int f = pfb_enc_format(c), null = pfb_null(c, 3), bytes = pf_encode_bytes(f), rc, rc2, allowed, allowed2, bad_val = 0;
    pfb_expect ex = { 0, 0, 0 }, ex2;
    long long nt = -1, i, k;
    pf_real *tx, *out, *off, *sc;
    pf_slope_encoding se, se0;
    pf_vmf_encoding ve, ve0;
    pfb_setcall("%s(%s, %d, %d channels, format %d%s)", fn, null == 1 ? "NULL" : "texels", n, nc, f,
                null == 2 ? ", out NULL" : (null == 3 ? ", range/encoding NULL" : ""));
    memset(&se0, 0x5A, sizeof se0);
    memset(&ve0, 0x5A, sizeof ve0);
    se = se0;
    ve = ve0;
    if (null == 1 || null == 3) ex.arg = 1;
    if (n < 1 || nc < 1) ex.small = 1;
    if (!ex.small) {
        nt = pfb_mul(n, nc);
        if (nt < 0) ex.size = 1;
    }
    ex2 = ex; /* the encode call: also the output pointer and the format */
    if (null == 2 || bytes == 0 || (which == 2 && f == PF_ENCODE_HALF)) ex2.arg = 1;
    allowed = pfb_allowed(ex);
    allowed2 = pfb_allowed(ex2);
    if (!(allowed & PFB_A_OK) || !(allowed2 & PFB_A_OK)) {
        pf_real *b[3];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        b[2] = null == 3 ? 0 : pfb_small();
        if (!(allowed & PFB_A_OK)) { /* the find call on the same arguments */
            if (which == 0) rc = pf_encode_ranges(b[0], n, nc, b[2], b[2] ? b[2] + 32 : 0);
            else if (which == 1) rc = pf_slope_encoding_find(b[0], n, 1, null == 3 ? 0 : &se);
            else rc = pf_vmf_encoding_find(b[0], n, null == 3 ? 0 : &ve);
            pfb_rc_check(rc, allowed, fn);
            if (memcmp(&se, &se0, sizeof se) || memcmp(&ve, &ve0, sizeof ve)) pfb_fail(PFB_WROTE, "%s: encoding written on an error", fn);
        }
        if (b[2]) { /* a valid range / encoding: the encode call must reject for its own faults */
            for (k = 0; k < 12; ++k) b[2][k] = k < 6 ? PF_R(0.0) : PF_R(1.0);
            memset(&se, 0, sizeof se);
            se.sc_x = se.sc_y = se.sc_xx = se.sc_yy = se.sc_xy = PF_R(1.0);
            ve.log_kappa_lo = PF_R(0.0); ve.log_kappa_span = PF_R(1.0); ve.amp_scale = PF_R(1.0);
        }
        if (which == 0) rc2 = pf_encode_channels(b[0], n, nc, b[2], b[2] ? b[2] + 6 : 0, f, b[1]);
        else if (which == 1) rc2 = pf_slope_moments_encode(b[0], n, null == 3 ? 0 : &se, f, b[1]);
        else rc2 = pf_vmf_lobes_encode(b[0], n, null == 3 ? 0 : &ve, f, b[1]);
        if (b[2]) pfb_fill_canary(b[2], PFB_SMALL); /* the range was ours, not the function's output */
        pfb_rc_check(rc2, allowed2, fn);
        pfb_check_untouched(b, 3);
        return;
    }
    if (nt > pfb_work_cap) return;
    tx = pfb_map(nt, 1);
    out = pfb_map((nt * bytes + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real), 0);
    off = pfb_map(nc, 1);
    sc = pfb_map(nc, 0);
    if (!tx || !out || !off || !sc) return;
    pfb_fill(c, tx, nt, which == 2 ? 4 : 20);
    if (which == 2)
        for (i = 0; i < n; ++i) tx[4 * i + 2] = PF_EXP(pfc_sym(c, 3) * PF_R(4.0)); /* kappa > 0 */
    if (PFC_R(pfc_next(c)) == 0) { /* a non-finite texel */
        pfc_u32 u = pfc_next(c);
        tx[(long long)(PFC_B(u) % (pfc_u32)nt)] = (u & 1u) ? pfc_from_bits(0x7FC00000u) : -pfc_from_bits(0x7F800000u);
        bad_val = 1;
    }
    pfb_fill_canary(out, (nt * bytes + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real));
    if (pfb_t) pfb_t->run += 1;
    if (which == 0) rc = pf_encode_ranges(tx, n, nc, off, sc);
    else if (which == 1) rc = pf_slope_encoding_find(tx, n, 1, &se);
    else rc = pf_vmf_encoding_find(tx, n, &ve);
    if (bad_val && rc != PF_ERR_ARG) pfb_fail(PFB_RC, "%s: a non-finite texel: find returned %d", fn, rc);
    if (rc != PF_OK) {
        if (rc != PF_ERR_ARG) pfb_fail(PFB_RC, "%s: find returned %d", fn, rc);
        if (which == 1 && memcmp(&se, &se0, sizeof se)) pfb_fail(PFB_WROTE, "%s: encoding written on an error", fn);
        if (which == 2 && memcmp(&ve, &ve0, sizeof ve)) pfb_fail(PFB_WROTE, "%s: encoding written on an error", fn);
        return;
    }
    if (which == 0) rc2 = pf_encode_channels(tx, n, nc, off, sc, f, out);
    else if (which == 1) rc2 = pf_slope_moments_encode(tx, n, &se, f, out);
    else rc2 = pf_vmf_lobes_encode(tx, n, &ve, f, out);
    if (rc2 != PF_OK) { /* half: a value of 65520 or more; slope: a centred channel that overflows */
        if (rc2 != PF_ERR_ARG || (f != PF_ENCODE_HALF && which != 1))
            pfb_fail(PFB_RC, "%s: encode returned %d after find succeeded", fn, rc2);
        if (pfb_count_changed(out, (nt * bytes + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real)))
            pfb_fail(PFB_WROTE, "%s: output written on an error", fn);
        return;
    }
    for (i = 0; i < n; ++i) {
        if (which == 0)
            for (k = 0; k < nc; ++k) {
                long double x = tx[i * nc + k], y = pfb_enc_s(out, i * nc + k, f), tol;
                if (f != PF_ENCODE_HALF) y = pf_unorm_decode((pf_real)y, off[k], sc[k]);
                tol = f == PF_ENCODE_HALF ? fabsl(x) * 4.9e-4L + 6e-8L
                                          : (long double)sc[k] / (f == PF_ENCODE_UNORM8 ? 510.0L : 131070.0L) +
                                                4.0L * (long double)PF_REAL_EPSILON * (fabsl((long double)off[k]) + (long double)sc[k]);
                if (!(fabsl(y - x) <= tol)) { pfb_fail(PFB_VALUE, "%s: texel %lld channel %lld: %La decodes to %La", fn, i, k, x, y); return; }
            }
        else if (which == 1) {
            pf_slope_encoding e = se;
            pf_slope_moments m;
            if (f == PF_ENCODE_HALF) {
                e.off_x = e.off_y = e.off_xx = e.off_yy = e.off_xy = PF_R(0.0);
                e.sc_x = e.sc_y = e.sc_xx = e.sc_yy = e.sc_xy = PF_R(1.0);
            }
            m = pf_slope_moments_decode(pf_slope_moments_make(pfb_enc_s(out, 5 * i, f), pfb_enc_s(out, 5 * i + 1, f),
                                                              pfb_enc_s(out, 5 * i + 2, f), pfb_enc_s(out, 5 * i + 3, f),
                                                              pfb_enc_s(out, 5 * i + 4, f)), e);
            if (!pfb_finite(m.ex) || !pfb_finite(m.ey) || !pfb_finite(m.exx) || !pfb_finite(m.eyy) || !pfb_finite(m.exy)) {
                pfb_fail(PFB_NONFINITE, "%s: texel %lld decodes to a non-finite moment", fn, i);
                return;
            }
        } else {
            pf_vmf_lobe l = pf_vmf_lobe_decode(pfb_enc_s(out, 4 * i, f), pfb_enc_s(out, 4 * i + 1, f), pfb_enc_s(out, 4 * i + 2, f),
                                               pfb_enc_s(out, 4 * i + 3, f), ve);
            if (!pfb_finite(l.kappa) || !pfb_finite(l.mu.z) || !(l.amp >= PF_R(0.0) && l.amp <= ve.amp_scale)) {
                pfb_fail(PFB_VALUE, "%s: lobe %lld decodes to kappa %a, amp %a", fn, i, (double)l.kappa, (double)l.amp);
                return;
            }
        }
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* ---------------------------------------------------------------- pf_specaa.h: the baker
   which: 0 pf_specaa_bake, 1 pf_specaa_bake_scratch_reals */
static void pfb_d_specaa(pfc_ctx *c, int which)
{
    const char *fn = which == 0 ? "pf_specaa_bake" : "pf_specaa_bake_scratch_reals";
    int w = pfb_int(c, 1, 40), h = pfb_int(c, 1, 40), null = pfb_null(c, 4), ndf, at_start = PFC_R(pfc_next(c)) < 4;
    int with_rough = PFC_R(pfc_next(c)) < 8, with_var = PFC_R(pfc_next(c)) < 8, rc, allowed;
    pf_real gain, alpha;
    pfb_expect ex = { 0, 0, 0 };
    long long npix = -1, nscr = -1, nout = -1, i;
    pf_real *nrm, *rough = 0, *scr, *al, *var = 0;
    pf_specaa_bake_desc d;
    {
        pfc_u32 u = pfc_next(c);
        ndf = PFC_R(u) < 14 ? (int)(PFC_B(u) % 2u) : pfb_int(c, -2, 4);
    }
    gain = PFC_R(pfc_next(c)) < 12 ? PF_R(0.0) : pfb_coord(c, PF_R(-1.0), PF_R(4.0));
    alpha = pfb_coord(c, PF_R(0.0), PF_R(1.0));
    pfb_side(&ex, w, 1);
    pfb_side(&ex, h, 1);
    if (which == 1) {
        long long r, want;
        pfb_setcall("%s(%d, %d)", fn, w, h);
        r = pf_specaa_bake_scratch_reals(w, h);
        want = ex.small || ex.size ? 0 : pfb_pyr_reals(w, h, PF_SPECAA_BAKE_CHANNELS);
        if (want < 0) want = 0;
        if (r != want) pfb_fail(PFB_VALUE, "%s = %lld, expected %lld", fn, r, want);
        return;
    }
    pfb_setcall("%s(normals %s, roughness %s, %d, %d, alpha %a, ndf %d, gain %a, scratch %s, alpha_out %s, variance %s)", fn,
                null == 2 ? "NULL" : "map", with_rough ? "map" : "NULL", w, h, (double)alpha, ndf, (double)gain,
                null == 3 ? "NULL" : "buf", null == 4 ? "NULL" : "buf", with_var ? "buf" : "NULL");
    if (null || (ndf != PF_SPECAA_NDF_GGX && ndf != PF_SPECAA_NDF_BECKMANN) ||
        !(gain >= PF_R(0.0) && gain <= PF_SPECAA_MAX_GAIN))
        ex.arg = 1;
    if (!ex.small && !ex.size) {
        npix = pfb_mul(w, h);
        nscr = pfb_pyr_reals(w, h, PF_SPECAA_BAKE_CHANNELS);
        nout = pfb_pyr_reals(w, h, 1);
        if (npix < 0 || nscr < 0 || nout < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    memset(&d, 0, sizeof d);
    d.width = w; d.height = h; d.alpha = alpha; d.ndf = ndf; d.gain = gain;
    if (allowed != PFB_A_OK) {
        pf_real *b[4];
        int k;
        for (k = 0; k < 4; ++k) b[k] = pfb_small();
        d.normals = null == 2 ? 0 : b[0];
        d.roughness = with_rough ? b[1] : 0;
        rc = pf_specaa_bake(null == 1 ? 0 : &d, null == 3 ? 0 : b[2], null == 4 ? 0 : b[3], with_var ? b[1] : 0);
        pfb_rc_check(rc, allowed, fn);
        pfb_check_untouched(b, 4);
        return;
    }
    if (nscr > pfb_work_cap) return;
    nrm = pfb_map(pfb_mul(npix, 3), at_start);
    if (with_rough) rough = pfb_map(npix, !at_start);
    scr = pfb_map(nscr, !at_start);
    al = pfb_map(nout, at_start);
    if (with_var) var = pfb_map(nout, !at_start);
    if (!nrm || !scr || !al || (with_rough && !rough) || (with_var && !var)) return;
    pfb_fill(c, nrm, npix * 3, 20);
    if (with_rough) pfb_fill(c, rough, npix, 4);
    pfb_fill_canary(scr, nscr);
    pfb_fill_canary(al, nout);
    if (with_var) pfb_fill_canary(var, nout);
    d.normals = nrm;
    d.roughness = rough;
    if (pfb_t) pfb_t->run += 1;
    rc = pf_specaa_bake(&d, scr, al, var);
    if (!pfb_rc_check(rc, allowed, fn)) return;
    pfb_check_written(al, nout, "alpha_out", 1);
    if (with_var) pfb_check_written(var, nout, "variance_out", 1);
    pfb_check_levels(scr, w, h, PF_SPECAA_BAKE_CHANNELS, 0, fn);
    for (i = 0; i < nout; ++i) {
        if (!(al[i] >= PF_R(0.0))) { pfb_fail(PFB_VALUE, "alpha_out[%lld] = %a < 0", i, (double)al[i]); break; }
        if (var && !(var[i] >= PF_R(0.0) && var[i] <= PF_R(1.0e4) * (PF_R(1.0) + PF_R(1.0e-3)))) {
            pfb_fail(PFB_VALUE, "variance_out[%lld] = %a outside [0, 1e4]", i, (double)var[i]);
            break;
        }
    }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

/* the scalar helpers: binary16 both ways over the whole float range and every bit pattern,
   the octahedral map, the format sizes */
static void pfb_d_encode_scalar(pfc_ctx *c, int which)
{
    pf_real x = pfb_coord(c, PF_R(-70000.0), PF_R(70000.0)), v, u, w;
    unsigned short h = (unsigned short)(pfc_next(c) & 0xFFFFu);
    pf_vec3 d;
    int f = pfb_int(c, -2, 5), b = pf_encode_bytes(f);
    (void)which;
    pfb_setcall("pf_half_from_real(%a), pf_real_from_half(0x%04x), pf_encode_bytes(%d)", (double)x, (unsigned)h, f);
    if (!pfb_finite(pf_real_from_half(h))) pfb_fail(PFB_NONFINITE, "pf_real_from_half(0x%04x)", (unsigned)h);
    v = pf_real_from_half(pf_half_from_real(x));
    if (pfb_finite(x) && PF_FABS(x) < PF_R(65520.0) &&
        !(fabsl((long double)v - (long double)x) <= fabsl((long double)x) * 4.9e-4L + 6e-8L))
        pfb_fail(PFB_VALUE, "half round trip of %a gave %a", (double)x, (double)v);
    if (b != ((f == PF_ENCODE_UNORM16 || f == PF_ENCODE_HALF) ? 2 : (f == PF_ENCODE_UNORM8 ? 1 : 0)))
        pfb_fail(PFB_VALUE, "pf_encode_bytes(%d) = %d", f, b);
    d = pf_vec3_make(pfb_coord(c, PF_R(-1.0), PF_R(1.0)), pfb_coord(c, PF_R(-1.0), PF_R(1.0)), pfb_coord(c, PF_R(-1.0), PF_R(1.0)));
    pf_oct_hemi_encode(d, &u, &w);
    if (!(u >= PF_R(-1.0) && u <= PF_R(1.0) && w >= PF_R(-1.0) && w <= PF_R(1.0)))
        pfb_fail(PFB_VALUE, "pf_oct_hemi_encode(%a, %a, %a) = (%a, %a)", (double)d.x, (double)d.y, (double)d.z, (double)u, (double)w);
}

/* ---------------------------------------------------------------- pf_shadow.h: stored formats
   which: 0 pf_shadow_encode_f16, 1 pf_shadow_encode_f32, 2 pf_shadow_encode_msm16,
   3 pf_shadow_encode_msm16_moments; 4 the value helpers (pf_shadow_store_channels,
   pf_half_from_real / pf_real_from_half of pf_core.h, pf_shadow_decode_msm16). The outputs are 16- or 32-bit
   words, not pf_reals: each accepted call runs twice over the same guarded mapping, first
   filled with one canary byte, then another; a word that differs between the runs was not
   written (a written one is the same both times), and every byte past the last word must keep
   its canary. On rejection every byte must keep it. */
static const char *const pfb_shadow_fn[4] = { "pf_shadow_encode_f16", "pf_shadow_encode_f32", "pf_shadow_encode_msm16",
                                              "pf_shadow_encode_msm16_moments" };
static int pfb_shadow_call(int which, int kind, const pf_real *z, long long n, pf_real cp, pf_real cn, void *out)
{
    switch (which) {
    case 0: return pf_shadow_encode_f16(kind, z, n, cp, cn, (unsigned short *)out);
    case 1: return pf_shadow_encode_f32(kind, z, n, cp, cn, (float *)out);
    case 2: return pf_shadow_encode_msm16(z, n, (unsigned short *)out);
    default: return pf_shadow_encode_msm16_moments((const pf_depth_moments4 *)(const void *)z, n, (unsigned short *)out);
    }
}
static int pfb_bytes_all(const unsigned char *p, long long n, unsigned char b)
{
    long long i;
    for (i = 0; i < n; ++i)
        if (p[i] != b) return 0;
    return 1;
}
static void pfb_d_shadow(pfc_ctx *c, int which)
{
    const char *fn = pfb_shadow_fn[which < 4 ? which : 0];
    int n = pfb_int(c, 0, 12), null = pfb_null(c, 2), at_start = PFC_R(pfc_next(c)) < 4, rc, rc2, allowed;
    int kind = which <= 1 ? pfb_int(c, -1, 5) : PF_SHADOW_STORE_MSM;
    int ch = kind == PF_SHADOW_STORE_VSM || kind == PF_SHADOW_STORE_EVSM2 ? 2
           : (kind == PF_SHADOW_STORE_EVSM4 || kind == PF_SHADOW_STORE_MSM ? 4 : 0);
    int wbytes = which == 1 ? 4 : 2, per = which == 3 ? 4 : 1; /* output word size; reals per input item */
    pf_real ceiling = which == 1 ? PF_EVSM_EXP_MAX_F32 : PF_EVSM_EXP_MAX_F16;
    pf_real cp = pfb_coord(c, PF_R(0.0), PF_R(50.0)), cn = pfb_coord(c, PF_R(0.0), PF_R(50.0));
    pfb_expect ex = { 0, 0, 0 };
    long long nw = -1, nin, outreals, i;
    pf_real *z, *o;
    unsigned char *ob;
    int bad_data = 0;
    if (which == 4) { /* value helpers: finite decodes of every pattern, round trips */
        unsigned short h = (unsigned short)(pfc_next(c) & 0xFFFFu), t[4];
        pf_real v = pf_real_from_half(h);
        pf_depth_moments4 m;
        pfb_setcall("pf_real_from_half(0x%04x) / pf_shadow_decode_msm16", (unsigned)h);
        if (!pfb_finite(v)) pfb_fail(PFB_NONFINITE, "pf_real_from_half(0x%04x) = %a", (unsigned)h, (double)v);
        if (((h >> 10) & 31u) != 31u && pf_half_from_real(v) != h && (h & 0x7FFFu) != 0)
            pfb_fail(PFB_VALUE, "half 0x%04x does not round-trip", (unsigned)h);
        for (i = 0; i < 4; ++i) t[i] = (unsigned short)(pfc_next(c) & 0xFFFFu);
        m = pf_shadow_decode_msm16(t);
        if (!(pfb_finite(m.m1) && pfb_finite(m.m2) && pfb_finite(m.m3) && pfb_finite(m.m4)))
            pfb_fail(PFB_NONFINITE, "pf_shadow_decode_msm16 of {%u %u %u %u}", t[0], t[1], t[2], t[3]);
        if (pf_shadow_store_channels(kind) != ch) pfb_fail(PFB_VALUE, "pf_shadow_store_channels(%d)", kind);
        (void)pf_half_from_real(pfb_coord(c, PF_R(-70000.0), PF_R(70000.0))); /* any real: no trap */
        return;
    }
    pfb_setcall("%s(kind %d, %s, %d, c %a %a, %s)", fn, kind, null == 1 ? "NULL" : "in", n, (double)cp, (double)cn,
                null == 2 ? "NULL" : "out");
    if (null) ex.arg = 1;
    if (n < 0 || ch == 0) ex.small = 1;
    /* NaN by its bits: -ffast-math would fold the comparison */
    if ((which <= 1) && (kind == PF_SHADOW_STORE_EVSM2 || kind == PF_SHADOW_STORE_EVSM4) && (pfb_isnan(cp) || !(cp > 0 && cp <= ceiling)))
        ex.arg = 1;
    if ((which <= 1) && kind == PF_SHADOW_STORE_EVSM4 && (pfb_isnan(cn) || !(cn > 0 && cn <= ceiling))) ex.arg = 1;
    if (!ex.small) {
        nw = pfb_mul(n, ch);
        if (nw < 0) ex.size = 1;
    }
    allowed = pfb_allowed(ex);
    if (!(allowed & PFB_A_OK)) {
        pf_real *b[2];
        b[0] = null == 1 ? 0 : pfb_small();
        b[1] = null == 2 ? 0 : pfb_small();
        if (b[0]) for (i = 0; i < PFB_SMALL; ++i) b[0][i] = PF_R(0.5); /* valid data: only the arguments are bad */
        rc = pfb_shadow_call(which, kind, b[0], n, cp, cn, b[1]);
        /* under -ffast-math a NaN or infinite exponent may pass the library's comparisons:
           then only memory safety is checked */
        if (!(PFB_FAST && pfb_nonfinite_input)) pfb_rc_check(rc, allowed, fn);
        if (b[1] && (pfb_count_changed(b[1], PFB_SMALL) || !pfb_pool_page_ok(b[1]))) pfb_fail(PFB_WROTE, "output written");
        return;
    }
    nin = (long long)n * per;
    outreals = (nw * wbytes + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real);
    if (nin > pfb_work_cap || outreals > pfb_work_cap) return;
    z = pfb_map(nin, at_start);
    o = pfb_map(outreals, !at_start);
    if (!z || !o) return;
    ob = (unsigned char *)(void *)o;
    for (i = 0; i < nin; ++i) { /* depths in [0, 1], or moments of one; 1 in 8 draws a bad value */
        pfc_u32 u = pfc_next(c), b = PFC_B(u);
        if (PFC_R(u) == 0) {
            z[i] = pfb_coord(c, PF_R(-2.0), PF_R(3.0));
            bad_data |= pfb_isnan(z[i]) || (which == 3 ? !(z[i] >= PF_R(-1.0) && z[i] <= PF_R(2.0)) : !(z[i] >= PF_R(0.0) && z[i] <= PF_R(1.0)));
        } else {
            z[i] = pfc_unif(b);
        }
    }
    memset(ob, 0xA5, (size_t)(outreals * (long long)sizeof(pf_real)));
    if (pfb_t) pfb_t->run += 1;
    rc = pfb_shadow_call(which, kind, z, n, cp, cn, o);
    if (PFB_FAST && pfb_nonfinite_input) { /* see above: memory safety only */
        if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
        if (rc == PF_OK && !pfb_bytes_all(ob + nw * wbytes, outreals * (long long)sizeof(pf_real) - nw * wbytes, 0xA5))
            pfb_fail(PFB_OOB, "bytes past the %lld output words changed", nw);
        return;
    }
    if (bad_data) {
        if (rc != PF_ERR_ARG) pfb_fail(PFB_RC, "%s: bad data returned %d, want PF_ERR_ARG", fn, rc);
        if (!pfb_bytes_all(ob, outreals * (long long)sizeof(pf_real), 0xA5)) pfb_fail(PFB_WROTE, "written on bad data");
        return;
    }
    if (!pfb_rc_check(rc, PFB_A_OK, fn)) return;
    if (!pfb_bytes_all(ob + nw * wbytes, outreals * (long long)sizeof(pf_real) - nw * wbytes, 0xA5))
        pfb_fail(PFB_OOB, "bytes past the %lld output words changed", nw);
    {   /* the second run, another canary: every word must come out the same */
        unsigned char *copy = (unsigned char *)malloc((size_t)(nw * wbytes) + 1);
        if (!copy) return;
        memcpy(copy, ob, (size_t)(nw * wbytes));
        memset(ob, 0x5A, (size_t)(outreals * (long long)sizeof(pf_real)));
        rc2 = pfb_shadow_call(which, kind, z, n, cp, cn, o);
        if (rc2 != PF_OK || memcmp(copy, ob, (size_t)(nw * wbytes)) != 0) pfb_fail(PFB_VALUE, "%s: an output word not written", fn);
        free(copy);
    }
    for (i = 0; i < nw; ++i) { /* values: finite, in range */
        if (which == 1) {
            float f;
            memcpy(&f, ob + i * 4, 4);
            if (!(f - f == 0.0f)) { pfb_fail(PFB_NONFINITE, "out[%lld] = %a", i, (double)f); break; }
        } else {
            unsigned short h;
            memcpy(&h, ob + i * 2, 2);
            if (which == 0 && ((h >> 10) & 31u) == 31u) { pfb_fail(PFB_NONFINITE, "out[%lld] = 0x%04x", i, (unsigned)h); break; }
        }
    }
    if (which == 2) /* 64-bit MSM: the decoded moments within the UNORM16 error of u^k */
        for (i = 0; i < n; ++i) {
            unsigned short t[4];
            pf_depth_moments4 m;
            long double u = 1.0L - (long double)z[i], e;
            memcpy(t, ob + i * 8, 8);
            m = pf_shadow_decode_msm16(t);
            e = fabsl((long double)m.m1 - u) + fabsl((long double)m.m2 - u * u) + fabsl((long double)m.m3 - u * u * u)
              + fabsl((long double)m.m4 - u * u * u * u);
            if (!(e <= 4 * 1.2e-5L)) { pfb_fail(PFB_VALUE, "decoded moments of z = %a off by %Lg", (double)z[i], e); break; }
        }
    if (!pfb_slack_ok()) pfb_fail(PFB_WROTE, "bytes next to a buffer changed");
}

static const pfb_entry pfb_table[] = {
    { "pf_size_mul pf_size_mul3 pf_size_side_ok", "core", pfb_w_core, 0 },
    { "pf_floor_index", "core", pfb_d_floor_index, 0 },
    { "pf_mip_texel_count pf_mip_level_count pf_mip_level_offset pf_mip_level_size pf_depth_moment_channels", "map", pfb_w_layout, 0 },
    { "pf_mip_build", "map", pfb_d_mip_build, 0 },
    { "pf_mip_build_log", "map", pfb_d_mip_build, 1 },
    { "pf_slope_moments_map_from_heights", "map", pfb_d_slope, 0 },
    { "pf_slope_pyramid_from_heights", "map", pfb_d_slope, 1 },
    { "pf_map_normals_from_heights", "map", pfb_d_slope, 2 },
    { "pf_depth_pyramid_from_depths", "map", pfb_d_pyramid_from, 0 },
    { "pf_scalar_pyramid_from_values", "map", pfb_d_pyramid_from, 1 },
    { "pf_normal_pyramid_from_normals", "map", pfb_d_pyramid_from, 2 },
    { "pf_moments_weighted_mean", "moments", pfb_d_weighted_mean, 0 },
    { "pf_esm_log_weighted_mean", "moments", pfb_d_weighted_mean, 1 },
    { "pf_mip_sample_bilinear", "map", pfb_d_sample, PFB_S_BIL },
    { "pf_mip_sample_trilinear", "map", pfb_d_sample, PFB_S_TRI },
    { "pf_mip_sample_bilinear_log", "map", pfb_d_sample, PFB_S_BIL_LOG },
    { "pf_mip_sample_trilinear_log", "map", pfb_d_sample, PFB_S_TRI_LOG },
    { "pf_slope_moments_sample", "map", pfb_d_sample, PFB_S_SLOPE },
    { "pf_scalar_moments_sample", "map", pfb_d_sample, PFB_S_SCALAR },
    { "pf_depth_moments2_sample", "map", pfb_d_sample, PFB_S_D2 },
    { "pf_depth_moments4_sample", "map", pfb_d_sample, PFB_S_D4 },
    { "pf_evsm_moments_sample", "map", pfb_d_sample, PFB_S_EVSM },
    { "pf_normal_avg_sample", "map", pfb_d_sample, PFB_S_NORMAL },
    { "pf_esm_log_sample", "map", pfb_d_sample, PFB_S_ESM },
    { "pf_colormap_filter", "height", pfb_d_colormap, 0 },
    { "pf_height_colormap_filter", "height", pfb_d_colormap, 1 },
    { "pf_transfer_moments_filter", "height", pfb_d_colormap, 2 },
    { "pf_colormap_table_size", "height", pfb_w_table_size, 0 },
    { "pf_colormap_table_build", "height", pfb_w_table_build, 0 },
    { "pf_colormap_table_lookup", "height", pfb_w_table_lookup, 0 },
    { "pf_gg_hermite_generate", "gaussgrid", pfb_w_hermite, 0 },
    { "pf_masks_samples", "masks", pfb_w_masks, 0 },
    { "pf_masks_table_words", "masks", pfb_w_masks, 1 },
    { "pf_masks_table_build", "masks", pfb_w_masks, 2 },
    { "pf_masks_table_fetch", "masks", pfb_w_masks, 3 },
    { "pf_horizon_map", "horizon", pfb_d_horizon, 0 },
    { "pf_horizon_pyramid", "horizon", pfb_d_horizon, 1 },
    { "pf_horizon_channels", "horizon", pfb_d_horizon, 2 },
    { "pf_vmf_fit_normals", "vmf_fit", pfb_d_vmf, 0 },
    { "pf_vmf_pyramid_from_normals", "vmf_fit", pfb_d_vmf, 1 },
    { "pf_vmf_pyramid_level_count pf_vmf_pyramid_level_offset pf_vmf_pyramid_texel_count", "vmf_fit", pfb_d_vmf, 2 },
    { "pf_vmf_mixture_from_texel", "vmf_fit", pfb_d_vmf, 3 },
    { "pf_map_wrap", "map", pfb_d_map_heights, 0 },
    { "pf_map_slope_stencil", "map", pfb_d_map_heights, 1 },
    { "pf_map_height pf_map_node_slope", "map", pfb_d_map_heights, 2 },
    { "pf_map_visible", "map", pfb_d_map_heights, 3 },
    { "pf_map_downsample_slopes", "map_downsample", pfb_d_vmf_downsample, 0 },
    { "pf_map_downsample_scratch_size", "map_downsample", pfb_d_vmf_downsample, 1 },
    { "pf_vmf_effective_brdf", "vmf_scale", pfb_d_vmf_scale, 0 },
    { "pf_vmf_scale_sample_count pf_vmf_scale_fit_level", "vmf_scale", pfb_d_vmf_scale, 1 }, /* the per-patch samples it builds on */
    { "pf_vmf_scale_fit_level", "vmf_scale", pfb_d_vmf_level, 0 },
    { "pf_vmf_scale_texel_t", "vmf_scale", pfb_d_vmf_level, 1 },
    { "pf_vmf_scale_scratch_size", "vmf_scale", pfb_d_vmf_level, 2 },
    { "pf_vmf_scale_sample_count pf_vmf_scale_cell_count pf_vmf_scale_vis_bytes", "vmf_scale", pfb_d_vmf_scale, 2 },
    { "pf_vmf_scale_cell_count pf_vmf_scale_texel_t", "vmf_scale", pfb_d_vmf_scale, 3 }, /* the factorization and T it builds on */
    { "pf_vmf_scale_lookup", "vmf_scale", pfb_d_vmf_scale, 4 },
    { "pf_encode_ranges pf_encode_channels pf_encode_bytes", "encode", pfb_d_encode, 0 },
    { "pf_slope_encoding_find pf_slope_moments_encode", "encode", pfb_d_encode, 1 },
    { "pf_vmf_encoding_find pf_vmf_lobes_encode", "encode", pfb_d_encode, 2 },
    { "pf_oct_hemi_encode pf_encode_bytes", "encode", pfb_d_encode_scalar, 0 },
    { "pf_half_from_real pf_real_from_half pf_round_even", "core", pfb_d_encode_scalar, 0 },
    { "pf_specaa_bake", "specaa", pfb_d_specaa, 0 },
    { "pf_specaa_bake_scratch_reals", "specaa", pfb_d_specaa, 1 },
    { "pf_shadow_encode_f16", "shadow", pfb_d_shadow, 0 },
    { "pf_shadow_encode_f32", "shadow", pfb_d_shadow, 1 },
    { "pf_shadow_encode_msm16", "shadow", pfb_d_shadow, 2 },
    { "pf_shadow_encode_msm16_moments", "shadow", pfb_d_shadow, 3 },
    { "pf_shadow_store_channels pf_shadow_decode_msm16", "shadow", pfb_d_shadow, 4 },
};
#define PFB_COUNT ((int)(sizeof pfb_table / sizeof pfb_table[0]))

/* One call of entry e on the words of c; every mapping released after it. */
static void pfb_call(pfc_ctx *c, const pfb_entry *e)
{
    pfc_reset(c);
    pfb_failed_kinds = 0;
    pfb_npool_used = 0;
    pfb_nonfinite_input = 0;
    pfb_line[0] = 0;
    if (pfb_t) pfb_t->calls += 1;
    e->fn(c, e->arg);
    pfb_release_all();
}

/* The fuzzers' entry: every driver of `module` on the bytes (each driver its own word stream:
   the bytes first, then a generator seeded from them and the driver's name). */
static void pfb_run_module(const char *module, const unsigned char *data, size_t size);
static void (*const pfb_run_module_ref)(const char *, const unsigned char *, size_t) = pfb_run_module;
static void pfb_run_module(const char *module, const unsigned char *data, size_t size)
{
    (void)pfb_run_module_ref;
    int i;
    pfc_u64 h = 1469598103934665603ULL;
    size_t k;
    static int ready;
    if (!ready) { pfc_init(); ready = 1; }
    (void)&pfc_call; /* pf_calls.h's evaluator table is not used by the buffer drivers */
    for (k = 0; k < size; ++k) h = (h ^ data[k]) * 1099511628211ULL;
    for (i = 0; i < PFB_COUNT; ++i) {
        pfc_ctx c;
        if (strcmp(pfb_table[i].module, module)) continue;
        memset(&c, 0, sizeof c);
        c.data = data;
        c.size = (unsigned long)size;
        c.rng = h ^ pfc_hash(pfb_table[i].name);
        pfb_call(&c, &pfb_table[i]);
    }
}

#define PFB_HARNESS(module)                                                      \
    int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);          \
    int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)           \
    {                                                                            \
        pfb_run_module(module, data, size);                                      \
        return 0;                                                                \
    }

#pragma GCC diagnostic pop

#endif /* PF_BUFFERS_H */

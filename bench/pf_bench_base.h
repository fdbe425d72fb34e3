/* pf_bench_base.h - the bench's one home for random numbers, the clock and checked allocation.
   CPU-only bench infrastructure (C99 + POSIX), not part of the library; self-contained: it needs
   nothing but the C library. Include it FIRST, before any system header: it defines
   _POSIX_C_SOURCE (200809L: clock_gettime, and what bench/pf_parallel.h needs).

   RANDOM NUMBERS. splitmix64 (Steele, Lea and Flood 2014): pfb_next steps the state by the
   golden gamma and mixes it. pfb_rng_item(seed, item) starts an independent stream per work
   item (the state is the seed and the item hashed together), so a parallel loop draws the same
   numbers for an item whatever thread runs it and in whatever order (bench/pf_parallel.h).
   TIME. pfb_now_ns / pfb_now_s: CLOCK_MONOTONIC (wall time, not CPU time).
   ALLOCATION. pfb_xmalloc / pfb_xcalloc: malloc / calloc that print one line on stderr and exit
   with status 2 when the memory is not there (a bench has nothing better to do). */
#ifndef PF_BENCH_BASE_H
#define PF_BENCH_BASE_H

#ifndef _POSIX_C_SOURCE
#  define _POSIX_C_SOURCE 200809L
#elif _POSIX_C_SOURCE < 199309L
#  error "pf_bench_base.h needs _POSIX_C_SOURCE >= 199309L (clock_gettime); include it first"
#endif

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

/* ---------------------------------------------------------------- random numbers (splitmix64) */
typedef struct pfb_rng {
    uint64_t s;
} pfb_rng;

/* splitmix64's output function: a bijective mix of 64 bits */
static inline uint64_t pfb_mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static inline uint64_t pfb_next(pfb_rng *r) { return pfb_mix64(r->s += 0x9e3779b97f4a7c15u); }

/* the stream that starts at state seed (the state is stepped before the first draw) */
static inline pfb_rng pfb_rng_make(uint64_t seed)
{
    pfb_rng r;
    r.s = seed;
    return r;
}

/* the stream of work item `item` of a loop seeded with `seed`: independent of the thread that
   runs the item and of the order the items run in */
static inline pfb_rng pfb_rng_item(uint64_t seed, uint64_t item)
{
    return pfb_rng_make(pfb_mix64(seed ^ pfb_mix64(item + 0x9e3779b97f4a7c15u)));
}

/* uniform double in [0, 1) (53 bits) */
static inline double pfb_unif(pfb_rng *r) { return (double)(pfb_next(r) >> 11) * (1.0 / 9007199254740992.0); }

/* uniform in [lo, hi) */
static inline double pfb_unif_in(pfb_rng *r, double lo, double hi) { return lo + (hi - lo) * pfb_unif(r); }

/* log-uniform in [lo, hi), lo > 0 */
static inline double pfb_logunif(pfb_rng *r, double lo, double hi) { return lo * exp(log(hi / lo) * pfb_unif(r)); }

/* uniform integer in [0, n), n > 0 */
static inline int pfb_int(pfb_rng *r, int n) { return (int)(pfb_unif(r) * n) % n; }

/* ---------------------------------------------------------------- time */
static inline double pfb_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static inline double pfb_now_s(void) { return 1e-9 * pfb_now_ns(); }

/* ---------------------------------------------------------------- checked allocation */
static inline void *pfb_xmalloc(size_t bytes)
{
    void *p = malloc(bytes ? bytes : 1);
    if (!p) {
        fprintf(stderr, "bench: out of memory (%lu bytes)\n", (unsigned long)bytes);
        exit(2);
    }
    return p;
}

/* count * size bytes, zeroed; the product is checked for overflow */
static inline void *pfb_xcalloc(size_t count, size_t size)
{
    void *p;
    if (size && count > (size_t)-1 / size) {
        fprintf(stderr, "bench: allocation of %lu x %lu bytes overflows\n", (unsigned long)count, (unsigned long)size);
        exit(2);
    }
    p = calloc(count ? count : 1, size ? size : 1);
    if (!p) {
        fprintf(stderr, "bench: out of memory (%lu x %lu bytes)\n", (unsigned long)count, (unsigned long)size);
        exit(2);
    }
    return p;
}

#endif /* PF_BENCH_BASE_H */

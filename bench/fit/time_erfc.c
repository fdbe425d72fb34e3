/* time_erfc.c - pf_erfc against libm erfcf (float build) or erfc (-DPF_DOUBLE) on the same
   uniform random inputs in [LO, HI]: 4096 inputs, 400 passes per repetition, 2 warm-up then
   17 repetitions with libm and pf_erfc alternated, median ns/eval of each and their ratio.
   A quick per-range companion of bench/bench_core.c (which is the reference).

   usage: gcc -O2 -std=c99 [-DPF_DOUBLE] -Iinclude bench/fit/time_erfc.c -o /tmp/t -lm
          /tmp/t LO HI */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "pf_core.h"

#define N 4096
#define PASSES 400
#define REPS 17
#define WARM 2

#ifdef PF_DOUBLE
#  define LIBM_ERFC(x) erfc(x)
#else
#  define LIBM_ERFC(x) erfcf(x)
#endif

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmpd(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    static pf_real xs[N];
    double tl[REPS], tp[REPS], lo, hi;
    unsigned long long s = 12345;
    volatile pf_real sink;
    int i, r, rep;
    if (argc < 3) {
        fprintf(stderr, "usage: %s LO HI\n", argv[0]);
        return 2;
    }
    lo = atof(argv[1]);
    hi = atof(argv[2]);
    for (i = 0; i < N; ++i) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        xs[i] = (pf_real)(lo + (hi - lo) * (double)(s >> 11) / 9007199254740992.0);
    }
    for (rep = 0; rep < REPS + WARM; ++rep) {
        double t0, t1, t2;
        pf_real acc = PF_R(0.0), acc2 = PF_R(0.0);
        t0 = now();
        for (r = 0; r < PASSES; ++r)
            for (i = 0; i < N; ++i) acc += LIBM_ERFC(xs[i]);
        t1 = now();
        for (r = 0; r < PASSES; ++r)
            for (i = 0; i < N; ++i) acc2 += pf_erfc(xs[i]);
        t2 = now();
        sink = acc + acc2;
        if (rep >= WARM) {
            tl[rep - WARM] = (t1 - t0) / N / PASSES * 1e9;
            tp[rep - WARM] = (t2 - t1) / N / PASSES * 1e9;
        }
    }
    (void)sink;
    qsort(tl, REPS, sizeof(double), cmpd);
    qsort(tp, REPS, sizeof(double), cmpd);
    printf("[%g, %g] %s: libm %.2f ns  pf_erfc %.2f ns  ratio %.2f\n", lo, hi,
#ifdef PF_DOUBLE
           "double",
#else
           "float",
#endif
           tl[REPS / 2], tp[REPS / 2], tp[REPS / 2] / tl[REPS / 2]);
    return 0;
}

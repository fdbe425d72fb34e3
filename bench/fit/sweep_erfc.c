/* sweep_erfc.c - every float in [a, b] (and its negative) through pf_erfc or pf_erf
   (float build), against glibc's long double erfcl / erfl. Prints the maximum error per
   interval in ulps where the result is normal, and in units of 2^-149 where it is subnormal.
   CPU-only measurement tool (walks the bit patterns of float with memcpy).

   usage: gcc -O2 -std=c99 -Iinclude bench/fit/sweep_erfc.c -o /tmp/sweep -lm
          /tmp/sweep A B [STRIDE [0=erfc|1=erf]]      e.g. /tmp/sweep 0 10.5 1 0 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pf_core.h"

static float f_of(unsigned long u)
{
    unsigned int v = (unsigned int)u;
    float f;
    memcpy(&f, &v, sizeof f);
    return f;
}

static unsigned long u_of(float f)
{
    unsigned int v;
    memcpy(&v, &f, sizeof v);
    return v;
}

static long double ulp_of(long double ref)
{
    int e;
    long double a = fabsl(ref);
    if (a == 0.0L) return ldexpl(1.0L, -149);
    frexpl(a, &e);
    if (e < -125) e = -125;
    return ldexpl(1.0L, e - 24);
}

int main(int argc, char **argv)
{
    static const double edges[] = {0.0, 0.5, 1.0, 2.0, 4.0, 6.0, 8.0, 9.19, 10.06, 1e30};
    enum { NB = 9 };
    long double maxe[NB] = {0}, sub = 0.0L, neg = 0.0L;
    float at[NB] = {0}, subat = 0.0f, negat = 0.0f;
    float a, b;
    unsigned long u, ub, step;
    int which, k, sg;
    if (argc < 3) {
        fprintf(stderr, "usage: %s A B [STRIDE [0=erfc|1=erf]]\n", argv[0]);
        return 2;
    }
    a = (float)atof(argv[1]);
    b = (float)atof(argv[2]);
    step = argc > 3 ? (unsigned long)atol(argv[3]) : 1ul;
    which = argc > 4 ? atoi(argv[4]) : 0;
    ub = u_of(b);
    for (u = u_of(a); u <= ub; u += step) {
        float x = f_of(u);
        for (sg = 0; sg < 2; ++sg) {
            float xx = sg ? -x : x;
            float g = which ? pf_erf(xx) : pf_erfc(xx);
            long double r = which ? erfl((long double)xx) : erfcl((long double)xx);
            long double err = fabsl((long double)g - r) / ulp_of(r);
            if (g != g) err = 1e30L;
            if (sg) {
                if (err > neg) { neg = err; negat = xx; }
            } else if (fabsl(r) < 0x1p-126L && r != 0.0L) {
                if (err > sub) { sub = err; subat = x; }
            } else {
                for (k = 0; k < NB - 1 && (double)x >= edges[k + 1]; ++k) {}
                if (err > maxe[k]) { maxe[k] = err; at[k] = x; }
            }
        }
    }
    printf("%s, floats in [%g, %g], stride %lu\n", which ? "pf_erf" : "pf_erfc", (double)a, (double)b, step);
    for (k = 0; k < NB; ++k)
        if (maxe[k] > 0.0L)
            printf("  x in [%g, %g): max %.3Lf ulp at x = %.9g\n", edges[k], edges[k + 1], maxe[k], (double)at[k]);
    printf("  subnormal results: max %.3Lf x 2^-149 at x = %.9g\n", sub, (double)subat);
    printf("  negative x: max %.3Lf ulp at x = %.9g\n", neg, (double)negat);
    return 0;
}

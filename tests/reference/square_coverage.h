/* square_coverage.h - exact coverage of the unit square by half-planes, the oracle of the
   sub-pixel occlusion masks (pf_masks.h), shared by tests/test_masks.c and
   bench/bench_masks.c. Test code in long double, not part of the library.

     square_clip(px, py, n, c, s, v)   clips the convex polygon (px, py, n) by
                                       x c + y s <= v (Sutherland-Hodgman against one
                                       line); returns the new count (<= n + 1; arrays of 16)
     square_area(nh, t, v)             fraction of [-1/2, 1/2]^2 inside every half-plane
                                       x cos t_k + y sin t_k <= v_k, k < nh (clipping, then
                                       the shoelace formula) */
#ifndef SQUARE_COVERAGE_H
#define SQUARE_COVERAGE_H

#include <math.h>

static int square_clip(long double *px, long double *py, int n, long double c, long double s, long double v)
{
    long double qx[16], qy[16];
    int m = 0, i;
    for (i = 0; i < n; ++i) {
        int j = (i + 1) % n;
        long double a = px[i] * c + py[i] * s - v, b = px[j] * c + py[j] * s - v;
        if (a <= 0.0L) { qx[m] = px[i]; qy[m] = py[i]; ++m; }
        if ((a < 0.0L && b > 0.0L) || (a > 0.0L && b < 0.0L)) {
            long double t = a / (a - b);
            qx[m] = px[i] + t * (px[j] - px[i]);
            qy[m] = py[i] + t * (py[j] - py[i]);
            ++m;
        }
    }
    for (i = 0; i < m; ++i) { px[i] = qx[i]; py[i] = qy[i]; }
    return m;
}

static long double square_area(int nh, const long double *t, const long double *v)
{
    long double px[16] = {-0.5L, 0.5L, 0.5L, -0.5L}, py[16] = {-0.5L, -0.5L, 0.5L, 0.5L}, a = 0.0L;
    int n = 4, k, i;
    for (k = 0; k < nh && n > 0; ++k) n = square_clip(px, py, n, cosl(t[k]), sinl(t[k]), v[k]);
    for (i = 0; i < n; ++i) a += px[i] * py[(i + 1) % n] - px[(i + 1) % n] * py[i];
    return fabsl(a) * 0.5L;
}

#endif /* SQUARE_COVERAGE_H */

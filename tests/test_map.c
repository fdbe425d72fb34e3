/* test_map.c - tests of include/pf_map.h (CPU map baking; the slope-preserving downsampler of
   include/pf_map_downsample.h is tested in tests/test_map_downsample.c).

   The truth is never the module's own formula:
   - the wrapped index against the slow definition near the ends of the long long range;
   - the height-field march (pf_map_visible) against tests/reference/pf_microsurface.h's independent
     double-precision march on a wall;
   The moment pyramids and their sampling are tested in tests/test_moments.c.
   Same bodies in float and double; edge_* tests also run under -ffast-math. */
/* MAP_ANONYMOUS and MAP_NORESERVE for pf_test_guarded_alloc under -std=c99 (before any include) */
#if defined(__unix__) && !defined(_DEFAULT_SOURCE)
#  define _DEFAULT_SOURCE 1
#endif
#include "pf_map.h"
#include "pf_oracle.h"
#include "pf_test.h"
#include "pf_microsurface.h"

/* a wall of height H along y (columns [32, 48) of a 64^2 map): a node at column x < 31 on the
   flat ground sees w (azimuth phi toward +x) iff the ray clears the wall's foot line, i.e.
   rise (32 - x) / cos(phi) >= H, rise = cot(theta): the ramp cell from column 31 to 32 and
   the plateau are planar, and the ray only gains on the plateau */
static void test_scale_visibility_wall(void)
{
    static pf_real hm[64 * 64];
    const pf_real H = PF_R(6.0);
    int x, y, a, b, bad = 0, tested = 0, vis = 0;
    for (y = 0; y < 64; ++y)
        for (x = 0; x < 64; ++x) hm[y * 64 + x] = (x >= 32 && x < 48) ? H : PF_R(0.0);
    for (a = 0; a < 40; ++a)
        for (b = 0; b < 5; ++b) {
            double th = 20.0 + 1.7 * a, ph = -50.0 + 25.0 * b, w[3];
            pf_test_dir_deg(th, ph, w);
            for (x = 2; x <= 29; ++x) {
                double rise = w[2] / sqrt(w[0] * w[0] + w[1] * w[1]);
                double clear = rise * (32.0 - x) / cos(ph * 3.14159265358979323846 / 180.0) - (double)H;
                int got;
                if (fabs(clear) < 1e-3) continue;
                got = pf_map_visible(hm, 64, 64, PF_R(1.0), x, 20, pf_test_vec3(w), 0, 0, 64, H);
                tested++;
                vis += got;
                if (got != (clear > 0.0)) bad++;
            }
        }
    pf_test_note("wall shadow: %d rays (%d visible), %d disagree with the closed form", tested, vis, bad);
    PF_CHECK(bad == 0 && vis > tested / 5 && vis < tested * 4 / 5, "%d of %d wrong (visible %d)", bad, tested, vis);
}

/* ------------------------------------------------------------------ wrap */
static void test_wrap_index(void)
{
    int bad;
    /* wrap: every i against the slow definition, near the ends of the range too */
    {
        static const long long n_list[] = {1, 2, 3, 7, (1LL << 24), 2147483647LL};
        static const long long i_list[] = {-9223372036854775807LL - 1, -2147483648LL, -7, -1, 0, 1, 6, 7,
                                           2147483647LL, 9223372036854775807LL};
        int a, b;
        bad = 0;
        for (a = 0; a < 6; ++a)
            for (b = 0; b < 10; ++b) {
                long long n = n_list[a], x = i_list[b], r = pf_map_wrap(x, n);
                /* r must be in [0, n) and congruent to x: (x - r) divisible by n, computed in
                   long double only for the divisibility of exact small remainders */
                long long back = x % n;
                if (back < 0) back += n;
                if (r < 0 || r >= n || r != back) bad++;
            }
        PF_CHECK(bad == 0, "%d wrong wrapped indices", bad);
    }
}

/* ------------------------------------------------------------------ unit normals, descriptions */
/* pf_map_normals_from_heights: the unit normals of exactly the slopes of
   pf_slope_moments_map_from_heights (bit for bit: the same stencil, then
   pf_normal_avg_from_slope), wrap and clamp, and against the analytic normal of a sinusoid;
   bad arguments rejected with nothing written. */
#define W 24
#define H 16
static void test_normals_from_heights(void)
{
    static pf_real hm[W * H], sl[W * H * 5], nr[W * H * 3 + 1];
    int i, j, b, bad = 0;
    long double worst = 0.0L;
    const long double tau = 6.283185307179586476925L;
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i)
            hm[j * W + i] = (pf_real)(0.3L * sinl(tau * i / W) + 0.2L * cosl(2.0L * tau * j / H));
    for (b = 0; b < 2; ++b) {
        int border = b ? PF_BORDER_WRAP : PF_BORDER_CLAMP;
        nr[W * H * 3] = PF_R(-7.0);
        PF_CHECK(pf_slope_moments_map_from_heights(hm, W, H, PF_R(0.5), PF_R(0.25), PF_R(1.5), border, sl) == PF_OK &&
                     pf_map_normals_from_heights(hm, W, H, PF_R(0.5), PF_R(0.25), PF_R(1.5), border, nr) == PF_OK,
                 "build");
        for (i = 0; i < W * H; ++i) {
            pf_vec3 m = pf_normal_avg_from_slope(sl[5 * i], sl[5 * i + 1]);
            bad += nr[3 * i] != m.x || nr[3 * i + 1] != m.y || nr[3 * i + 2] != m.z;
        }
        PF_CHECK(nr[W * H * 3] == PF_R(-7.0), "wrote past the map");
    }
    PF_CHECK(bad == 0, "%d normals differ from the slopes' normals", bad);
    /* wrap: against the analytic gradient (central differences: error (d^2/6) h''') */
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i) {
            long double sx = 1.5L * 0.3L * tau / (W * 0.5L) * cosl(tau * i / W);
            long double sy = -1.5L * 0.2L * 2.0L * tau / (H * 0.25L) * sinl(2.0L * tau * j / H);
            long double n = sqrtl(1.0L + sx * sx + sy * sy), e;
            e = fabsl((long double)nr[3 * (j * W + i)] + sx / n) + fabsl((long double)nr[3 * (j * W + i) + 1] + sy / n) +
                fabsl((long double)nr[3 * (j * W + i) + 2] - 1.0L / n);
            if (e > worst) worst = e;
        }
    PF_CHECK(worst <= 0.08L, "normals %.3Lg from the analytic ones (bound 0.08: the stencil's h''' term)", worst);
    nr[0] = PF_R(-7.0);
    PF_CHECK(pf_map_normals_from_heights(NULL, W, H, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP, nr) == PF_ERR_ARG &&
                 pf_map_normals_from_heights(hm, W, H, PF_R(1.0), PF_R(1.0), PF_R(1.0), 7, nr) == PF_ERR_ARG &&
                 pf_map_normals_from_heights(hm, 0, H, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP, nr) == PF_ERR_ARG &&
                 pf_map_normals_from_heights(hm, (int)PF_MAX_SIDE + 1, 1, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP, nr) ==
                     PF_ERR_SIZE && nr[0] == PF_R(-7.0),
             "bad arguments");
}
#undef W
#undef H

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_wrap_index);
    PF_TEST_RUN(test_normals_from_heights);
    PF_TEST_RUN(test_scale_visibility_wall);
    return PF_TEST_END();
}

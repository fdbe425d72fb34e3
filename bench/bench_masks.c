/* bench_masks.c - cost and accuracy of pf_masks.h's sub-pixel occlusion masks (Heitz & Neyret
   2011 sec. 4.4, app. B) against the exact covered area.

   Every table is built once before the timings (pf_masks_samples seed 1, pf_masks_table_build,
   square footprint [-1/2, 1/2]^2); a lookup is pf_masks_index + the fetch of its words from a
   global int array (what a shader's buffer fetch does) + pf_masks_coverage. Errors are absolute
   (covered fractions in [0, 1]; PFB_ENTRY_ABS: mean and max absolute error).

   Families
     masks_lookup     inputs theta (uniform [0, 2 pi)), v (uniform [-0.75, 0.75]). Output: the
                      covered fraction of the pixel, x cos theta + y sin theta <= v.
                      exact_area (BASELINE)   the closed-form area (a trapezoid CDF), what the
                                              masks approximate but cannot compose
                      mask_n32_t32            N = 32 samples, 32 x 32 (theta, v) table, 4 KiB
                      mask_n64_t32            N = 64, 32 x 32, 8 KiB
                      mask_n64_t64            N = 64, 64 x 64, 32 KiB (the recommended table)
                      mask_n64_t128           N = 64, 128 x 128, 128 KiB
                      mask_n128_t64           N = 128, 64 x 64, 64 KiB
                      mask_n128_t256          N = 128, 256 x 256, 1 MiB (the paper's, HN11 sec. 5)
     masks_intersect  two half-planes (theta_a, theta_b, and both v packed in the third input).
                      Output: the fraction covered by both.
                      alpha_product (BASELINE)  a b from the exact single areas: the uncorrelated
                                              model (HN11 eq. 16, alpha blending)
                      mask_n64_t64, mask_n128_t256   coverage(intersection(A, B))
     masks_union      as above; output the fraction covered by either.
                      alpha_over (BASELINE)   a + b - a b
                      mask_n64_t64, mask_n128_t256   coverage(union(A, B))
     masks_visible    HN11 eq. 15: the fraction that element A shows behind the upstream B,
                      |A and not B|.
                      alpha_blend (BASELINE)  a (1 - b) (eq. 16)
                      mask_n64_t64, mask_n128_t256   pf_masks_visible_fraction(A, B)
     masks_step       the cone-tracing step of eq. 15 alone: two masks of the 64 x 64 grid fetched
                      by number (no index computation), |A and not B| / N.
                      alpha_blend (BASELINE)  a (1 - b) from a table of the grid planes' exact areas
                      mask_n64_t64, mask_n128_t64
   Reference: the exact area in long double (polygon clipping of the square, shoelace formula).

   `bench_masks-float --build-cost` prints the CPU side instead: the time of pf_masks_samples and
   pf_masks_table_build for each table, and its size in bytes.

   See pf_bench.h for what every column means; bench/run.sh (make bench) runs this. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_masks.h"
#include "square_coverage.h"

#define SHAPE PF_MASKS_SQUARE

static int t32_32[32 * 32 * 1];
static int t64_32[32 * 32 * 2];
static int t64_64[64 * 64 * 2];
static int t64_128[128 * 128 * 2];
static int t128_64[64 * 64 * 4];
static int t128_256[256 * 256 * 4];

/* A looked-up mask: index, then the caller's fetch of its words, as a shader does it (no
   checks: pf_masks_index is always inside the table). */
static inline pf_mask fetch_words(const int *t, int k, int words)
{
    const int *p = t + k * words;
    return pf_mask_make(p[0], words > 1 ? p[1] : 0, words > 2 ? p[2] : 0, words > 3 ? p[3] : 0);
}
#define MASK_AT(table, n, nt, nv, th, v) \
    fetch_words(table, pf_masks_index(pf_mask_params_make(th, v), SHAPE, nt, nv), pf_masks_words(n))

/* The two v of a pair, packed in z in [0, 1): ja = floor(64 z), jb = floor(64 (64 z - ja)),
   v = -0.75 + 1.5 (j + 0.5) / 64. */
static pf_real va_of(pf_real z)
{
    pf_real s = z * PF_R(64.0), ja = PF_FLOOR(s);
    return PF_R(-0.75) + PF_R(1.5) * (ja + PF_R(0.5)) / PF_R(64.0);
}
static pf_real vb_of(pf_real z)
{
    pf_real s = z * PF_R(64.0), ja = PF_FLOOR(s), jb = PF_FLOOR((s - ja) * PF_R(64.0));
    return PF_R(-0.75) + PF_R(1.5) * (jb + PF_R(0.5)) / PF_R(64.0);
}

static pf_real exact1(pf_real th, pf_real v) { return pfi_masks_exact_area(SHAPE, PF_COS(th), PF_SIN(th), v); }

/* ---- masks_lookup: x = theta, y = v */
PFB_METHOD(lk_exact, exact1(x, y))
PFB_METHOD(lk_n32_t32, pf_masks_coverage(MASK_AT(t32_32, 32, 32, 32, x, y), 32))
PFB_METHOD(lk_n64_t32, pf_masks_coverage(MASK_AT(t64_32, 64, 32, 32, x, y), 64))
PFB_METHOD(lk_n64_t64, pf_masks_coverage(MASK_AT(t64_64, 64, 64, 64, x, y), 64))
PFB_METHOD(lk_n64_t128, pf_masks_coverage(MASK_AT(t64_128, 64, 128, 128, x, y), 64))
PFB_METHOD(lk_n128_t64, pf_masks_coverage(MASK_AT(t128_64, 128, 64, 64, x, y), 128))
PFB_METHOD(lk_n128_t256, pf_masks_coverage(MASK_AT(t128_256, 128, 256, 256, x, y), 128))

/* ---- pairs: x = theta_a, y = theta_b, z = packed v_a, v_b */
#define PAIR(op, table, n, nt) \
    op(MASK_AT(table, n, nt, nt, x, va_of(z)), MASK_AT(table, n, nt, nt, y, vb_of(z)))
PFB_METHOD(in_alpha, exact1(x, va_of(z)) * exact1(y, vb_of(z)))
PFB_METHOD(in_n64, pf_masks_coverage(PAIR(pf_masks_intersection, t64_64, 64, 64), 64))
PFB_METHOD(in_n128, pf_masks_coverage(PAIR(pf_masks_intersection, t128_256, 128, 256), 128))
PFB_METHOD(un_alpha, exact1(x, va_of(z)) + exact1(y, vb_of(z)) - exact1(x, va_of(z)) * exact1(y, vb_of(z)))
PFB_METHOD(un_n64, pf_masks_coverage(PAIR(pf_masks_union, t64_64, 64, 64), 64))
PFB_METHOD(un_n128, pf_masks_coverage(PAIR(pf_masks_union, t128_256, 128, 256), 128))
PFB_METHOD(vi_alpha, exact1(x, va_of(z)) * (PF_R(1.0) - exact1(y, vb_of(z))))
PFB_METHOD(vi_n64, pf_masks_visible_fraction(MASK_AT(t64_64, 64, 64, 64, x, va_of(z)),
                                             MASK_AT(t64_64, 64, 64, 64, y, vb_of(z)), 64))
PFB_METHOD(vi_n128, pf_masks_visible_fraction(MASK_AT(t128_256, 128, 256, 256, x, va_of(z)),
                                              MASK_AT(t128_256, 128, 256, 256, y, vb_of(z)), 128))

/* ---- masks_step: x, y = mask numbers on the 64 x 64 grid (no index computation): the cone-tracing
   step of eq. 15 alone, a fetch of two masks, a difference and a popcount */
static pf_real area64[64 * 64]; /* exact area of each grid plane (what an opacity map stores) */
PFB_METHOD(st_alpha, area64[(int)x] * (PF_R(1.0) - area64[(int)y]))
PFB_METHOD(st_n64, pf_masks_visible_fraction(fetch_words(t64_64, (int)x, 2), fetch_words(t64_64, (int)y, 2), 64))
PFB_METHOD(st_n128, pf_masks_visible_fraction(fetch_words(t128_64, (int)x, 4), fetch_words(t128_64, (int)y, 4), 128))

/* ---------------------------------------------------------------- references (long double) */
/* area of the unit square inside nh (1 or 2) half-planes (tests/reference/square_coverage.h) */
static long double sq_area(int nh, long double ta, long double va, long double tb, long double vb)
{
    long double t[2], v[2];
    t[0] = ta;
    v[0] = va;
    t[1] = tb;
    v[1] = vb;
    return square_area(nh, t, v);
}

static long double ref_one(long double x, long double y, long double z) { (void)z; return sq_area(1, x, y, 0, 0); }
static long double ref_and(long double x, long double y, long double z)
{
    return sq_area(2, x, (long double)va_of((pf_real)z), y, (long double)vb_of((pf_real)z));
}
static long double ref_or(long double x, long double y, long double z)
{
    long double a = sq_area(1, x, (long double)va_of((pf_real)z), 0, 0), b = sq_area(1, y, (long double)vb_of((pf_real)z), 0, 0);
    return a + b - ref_and(x, y, z);
}
static long double ref_vis(long double x, long double y, long double z)
{
    return sq_area(1, x, (long double)va_of((pf_real)z), 0, 0) - ref_and(x, y, z);
}

static long double grid_t(long double k) { return 6.283185307179586476925L * (long double)((int)k / 64) / 64.0L; }
static long double grid_v(long double k)
{
    long double vm = 0.7071067811865475244L;
    return -vm + 2.0L * vm * (long double)((int)k % 64) / 63.0L;
}
static long double ref_step(long double x, long double y, long double z)
{
    (void)z;
    return sq_area(1, grid_t(x), grid_v(x), 0, 0) - sq_area(2, grid_t(x), grid_v(x), grid_t(y), grid_v(y));
}

/* ---------------------------------------------------------------- inputs */
static void gen_one(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_unif_in(r, 0.0, 6.283185307179586);
        b[i] = (pf_real)pfb_unif_in(r, -0.75, 0.75);
        c[i] = PF_R(0.0);
    }
}

static size_t grid_one(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int i, j;
    for (i = 0; i < 181; ++i)
        for (j = 0; j <= 120; ++j) {
            if (a) {
                a[n] = (pf_real)(6.283185307179586 * (i + 0.37) / 181.0); /* off every table grid */
                b[n] = (pf_real)(-0.75 + 1.5 * j / 120.0);
                c[n] = PF_R(0.0);
            }
            ++n;
        }
    return n;
}

static void gen_pair(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_unif_in(r, 0.0, 6.283185307179586);
        b[i] = (pf_real)pfb_unif_in(r, 0.0, 6.283185307179586);
        c[i] = (pf_real)((double)(pfb_next(r) % 4096u) / 4096.0);
    }
}

static size_t grid_pair(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int i, j, k;
    for (i = 0; i < 24; ++i)
        for (j = 0; j < 24; ++j)
            for (k = 0; k < 4096; k += 7) {
                if (a) {
                    a[n] = (pf_real)(6.283185307179586 * (i + 0.37) / 24.0);
                    b[n] = (pf_real)(6.283185307179586 * (j + 0.71) / 24.0);
                    c[n] = (pf_real)(k / 4096.0);
                }
                ++n;
            }
    return n;
}

static void gen_step(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)(pfb_next(r) % 4096u);
        b[i] = (pf_real)(pfb_next(r) % 4096u);
        c[i] = PF_R(0.0);
    }
}

static size_t grid_step(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int i, j;
    for (i = 0; i < 4096; i += 13)
        for (j = 0; j < 4096; j += 17) {
            if (a) {
                a[n] = (pf_real)i;
                b[n] = (pf_real)j;
                c[n] = PF_R(0.0);
            }
            ++n;
        }
    return n;
}

#define PAIR_NOTES(what) \
    "inputs theta_a, theta_b uniform in [0, 2 pi); v_a, v_b on 64 levels in [-0.75, 0.75] (packed in the third input)\n" \
    "accuracy grid: theta_a, theta_b = 2 pi (i + 0.37) / 24, (j + 0.71) / 24; 586 (v_a, v_b) pairs per angle pair\n" \
    "reference: " what " of the square [-1/2, 1/2]^2, exact (polygon clipping, shoelace) in long double"

static const pfb_family families[] = {
    { "masks_lookup", 2, { "theta", "v" }, 0,
      "inputs theta uniform in [0, 2 pi), v uniform in [-0.75, 0.75]; square footprint [-1/2, 1/2]^2\n"
      "accuracy grid: theta = 2 pi (i + 0.37) / 181, i < 181 (off every table grid); v = -0.75 + 1.5 j / 120, j <= 120\n"
      "reference: the area of the square with x cos theta + y sin theta <= v, exact (polygon clipping, shoelace) in long double",
      gen_one, grid_one, 7,
      { PFB_ENTRY_ABS("exact_area", lk_exact, ref_one),
        PFB_ENTRY_ABS("mask_n32_t32", lk_n32_t32, ref_one),
        PFB_ENTRY_ABS("mask_n64_t32", lk_n64_t32, ref_one),
        PFB_ENTRY_ABS("mask_n64_t64", lk_n64_t64, ref_one),
        PFB_ENTRY_ABS("mask_n64_t128", lk_n64_t128, ref_one),
        PFB_ENTRY_ABS("mask_n128_t64", lk_n128_t64, ref_one),
        PFB_ENTRY_ABS("mask_n128_t256", lk_n128_t256, ref_one) } },
    { "masks_intersect", 2, { "theta_a", "theta_b" }, 0, PAIR_NOTES("the area inside both half-planes"),
      gen_pair, grid_pair, 3,
      { PFB_ENTRY_ABS("alpha_product", in_alpha, ref_and),
        PFB_ENTRY_ABS("mask_n64_t64", in_n64, ref_and),
        PFB_ENTRY_ABS("mask_n128_t256", in_n128, ref_and) } },
    { "masks_union", 2, { "theta_a", "theta_b" }, 0, PAIR_NOTES("the area inside either half-plane"),
      gen_pair, grid_pair, 3,
      { PFB_ENTRY_ABS("alpha_over", un_alpha, ref_or),
        PFB_ENTRY_ABS("mask_n64_t64", un_n64, ref_or),
        PFB_ENTRY_ABS("mask_n128_t256", un_n128, ref_or) } },
    { "masks_visible", 2, { "theta_a", "theta_b" }, 0, PAIR_NOTES("the area inside A and outside B (HN11 eq. 15)"),
      gen_pair, grid_pair, 3,
      { PFB_ENTRY_ABS("alpha_blend", vi_alpha, ref_vis),
        PFB_ENTRY_ABS("mask_n64_t64", vi_n64, ref_vis),
        PFB_ENTRY_ABS("mask_n128_t256", vi_n128, ref_vis) } },
    { "masks_step", 2, { "mask_a", "mask_b" }, 0,
      "inputs: two mask numbers of the 64 x 64 grid (theta_i = 2 pi i / 64, v_j = -0.7071 + 1.4142 j / 63), uniform; the masks are fetched directly (no pf_masks_index)\n"
      "accuracy grid: every 13th and 17th mask number (316 x 241 pairs)\n"
      "reference: the area inside A and outside B (HN11 eq. 15), exact (polygon clipping, shoelace) in long double",
      gen_step, grid_step, 3,
      { PFB_ENTRY_ABS("alpha_blend", st_alpha, ref_step),
        PFB_ENTRY_ABS("mask_n64_t64", st_n64, ref_step),
        PFB_ENTRY_ABS("mask_n128_t64", st_n128, ref_step) } },
};

static double now_s(void) { return pfb_now_ns() * 1e-9; } /* pf_bench_base.h's clock */

/* --build-cost: the CPU side, once per application: pf_masks_samples and pf_masks_table_build
   for each table of the families (median of 5 runs), and the table sizes. */
static int build_cost(void)
{
    static const int cfg[5][3] = {{32, 32, 32}, {64, 64, 64}, {128, 64, 64}, {128, 256, 256}, {64, 32, 32}};
    static pf_real xy[2 * 128];
    static int table[256 * 256 * 4];
    int c, r;
    printf("N  n_theta x n_v  bytes  samples_ms  table_ms  (%s build, median of 5)\n", PFB_BUILD);
    for (c = 0; c < 5; ++c) {
        double ts[5], tt[5], t0;
        int i, j;
        for (r = 0; r < 5; ++r) {
            t0 = now_s();
            pf_masks_samples(SHAPE, cfg[c][0], 1, xy);
            ts[r] = now_s() - t0;
            t0 = now_s();
            pf_masks_table_build(SHAPE, cfg[c][1], cfg[c][2], xy, cfg[c][0], table);
            tt[r] = now_s() - t0;
        }
        for (i = 0; i < 5; ++i) /* sort both for the median */
            for (j = i + 1; j < 5; ++j) {
                if (ts[j] < ts[i]) { t0 = ts[i]; ts[i] = ts[j]; ts[j] = t0; }
                if (tt[j] < tt[i]) { t0 = tt[i]; tt[i] = tt[j]; tt[j] = t0; }
            }
        printf("%3d  %3d x %3d  %7lld  %8.2f  %8.2f\n", cfg[c][0], cfg[c][1], cfg[c][2],
               4 * pf_masks_table_words(cfg[c][0], cfg[c][1], cfg[c][2]), 1e3 * ts[2], 1e3 * tt[2]);
    }
    return 0;
}

int main(int argc, char **argv)
{
    static pf_real xy[2 * 128];
    int ok = 1;
    if (argc > 1 && strcmp(argv[1], "--build-cost") == 0) return build_cost();
    ok &= pf_masks_samples(SHAPE, 32, 1, xy) == PF_OK && pf_masks_table_build(SHAPE, 32, 32, xy, 32, t32_32) == PF_OK;
    ok &= pf_masks_samples(SHAPE, 64, 1, xy) == PF_OK && pf_masks_table_build(SHAPE, 64, 64, xy, 64, t64_64) == PF_OK;
    ok &= pf_masks_table_build(SHAPE, 32, 32, xy, 64, t64_32) == PF_OK;
    ok &= pf_masks_table_build(SHAPE, 128, 128, xy, 64, t64_128) == PF_OK;
    ok &= pf_masks_samples(SHAPE, 128, 1, xy) == PF_OK && pf_masks_table_build(SHAPE, 64, 64, xy, 128, t128_64) == PF_OK;
    ok &= pf_masks_table_build(SHAPE, 256, 256, xy, 128, t128_256) == PF_OK;
    {
        int k;
        for (k = 0; k < 64 * 64; ++k)
            area64[k] = (pf_real)sq_area(1, grid_t((long double)k), grid_v((long double)k), 0, 0);
    }
    if (!ok) {
        fprintf(stderr, "bench_masks: table build failed\n");
        return 1;
    }
    return pfb_main(argc, argv, "masks", families, (int)(sizeof families / sizeof families[0]));
}

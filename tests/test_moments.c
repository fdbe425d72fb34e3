/* test_moments.c - tests of include/pf_moments.h.

   Independent references, all in long double:
   - reductions against the moments of the union (the mixture) of the samples behind the
     texels, computed from the samples themselves;
   - mip weights and pyramids against box-overlap weights (the length of source texel s inside
     the footprint [d r, (d + 1) r] of destination texel d, r = n_src / n_dst), written here
     without pf_mip_weights3;
   - sampling against the GPU's bilinear formula evaluated here;
   - ESM log-space reductions against the direct exp(c z) averages;
   - height-map slopes against the analytic gradient of a sum of sinusoids, and the pyramid's
     top against the gradient moments integrated over the domain (tests/pf_oracle.h);
   - LEADR shading of trilinear samples whose mean plane hides the view (the pic_plane
     regression) against eq. 17 and a 2D quadrature of the facets facing the view.
   The same bodies run in float, double, C++ and under sanitizers (every buffer is allocated
   with its exact size, so AddressSanitizer sees any read out of bounds); edge_* tests also run
   under -ffast-math. Issue 19 (memory safety of the pointer-taking functions): every
   reproducer is a test below (edge_issue19_*, test_issue19_*); huge accepted sizes use guarded,
   mostly untouched mappings (pf_test_guarded_alloc), so an out-of-bounds read faults. */
/* MAP_ANONYMOUS and MAP_NORESERVE for pf_test_guarded_alloc under -std=c99 (before any include) */
#if defined(__unix__) && !defined(_DEFAULT_SOURCE)
#  define _DEFAULT_SOURCE 1
#endif
#include <limits.h>
#include <string.h>
#include "pf_beckmann.h"
#include "pf_map.h"
#include "pf_oracle.h"
#include "pf_test.h"


static pf_real *alloc_real(long long n)
{
    pf_real *p = (pf_real *)malloc((size_t)(n > 0 ? n : 1) * sizeof(pf_real));
    if (!p) {
        printf("out of memory\n");
        exit(2);
    }
    return p;
}

static long double *alloc_ld(long long n)
{
    long double *p = (long double *)malloc((size_t)(n > 0 ? n : 1) * sizeof(long double));
    if (!p) {
        printf("out of memory\n");
        exit(2);
    }
    return p;
}

/* ------------------------------------------------------------------ box-overlap weights */
/* Weight of source texel s in destination texel d, axis of n_src texels reduced to n_dst. */
static long double overlap_weight(int s, int d, int n_src, int n_dst)
{
    long double r = (long double)n_src / (long double)n_dst;
    long double lo = (long double)d * r, hi = (long double)(d + 1) * r;
    long double a = (long double)s > lo ? (long double)s : lo;
    long double b = (long double)(s + 1) < hi ? (long double)(s + 1) : hi;
    return b > a ? (b - a) / r : 0.0L;
}

static int next_size(int n) { return n > 1 ? n / 2 : 1; }

/* Reference pyramid in long double from level 0 (w h C values), same layout as pf_mip_*. */
static long double *ref_pyramid(const long double *lvl0, int w, int h, int nc, int log_space,
                                long long *total)
{
    long long n = 0, off = 0, off_prev;
    int lw = w, lh = h, levels = 0;
    long double *p;
    for (;;) {
        n += (long long)lw * lh;
        ++levels;
        if (lw == 1 && lh == 1) break;
        lw = next_size(lw);
        lh = next_size(lh);
    }
    *total = n;
    p = alloc_ld(n * nc);
    memcpy(p, lvl0, sizeof(long double) * (size_t)w * (size_t)h * (size_t)nc);
    lw = w;
    lh = h;
    off_prev = 0;
    off = (long long)w * h * nc;
    while (!(lw == 1 && lh == 1)) {
        int dw = next_size(lw), dh = next_size(lh), i, j, a, b, k;
        for (j = 0; j < dh; ++j)
            for (i = 0; i < dw; ++i)
                for (k = 0; k < nc; ++k) {
                    long double s = 0.0L;
                    for (b = 0; b < lh; ++b) {
                        long double wy = overlap_weight(b, j, lh, dh);
                        if (wy == 0.0L) continue;
                        for (a = 0; a < lw; ++a) {
                            long double wx = overlap_weight(a, i, lw, dw);
                            long double v = p[off_prev + ((long long)b * lw + a) * nc + k];
                            if (wx == 0.0L) continue;
                            s += wx * wy * (log_space ? expl(v) : v);
                        }
                    }
                    p[off + ((long long)j * dw + i) * nc + k] = log_space ? logl(s) : s;
                }
        off_prev = off;
        off += (long long)dw * dh * nc;
        lw = dw;
        lh = dh;
    }
    return p;
}

/* ------------------------------------------------------------------ texels as arrays */
/* Each moment type as an array of up to 5 channels, to test all types with one body. */
#define MAXC 5
typedef struct texel {
    pf_real v[MAXC];
} texel;

static pf_slope_moments to_slope(texel t) { return pf_slope_moments_make(t.v[0], t.v[1], t.v[2], t.v[3], t.v[4]); }
static texel from_slope(pf_slope_moments m) { texel t; t.v[0] = m.ex; t.v[1] = m.ey; t.v[2] = m.exx; t.v[3] = m.eyy; t.v[4] = m.exy; return t; }
static pf_scalar_moments to_scalar(texel t) { return pf_scalar_moments_make(t.v[0], t.v[1]); }
static texel from_scalar(pf_scalar_moments m) { texel t; t.v[0] = m.m1; t.v[1] = m.m2; return t; }
static pf_depth_moments2 to_d2(texel t) { return pf_depth_moments2_make(t.v[0], t.v[1]); }
static texel from_d2(pf_depth_moments2 m) { texel t; t.v[0] = m.m1; t.v[1] = m.m2; return t; }
static pf_depth_moments4 to_d4(texel t) { return pf_depth_moments4_make(t.v[0], t.v[1], t.v[2], t.v[3]); }
static texel from_d4(pf_depth_moments4 m) { texel t; t.v[0] = m.m1; t.v[1] = m.m2; t.v[2] = m.m3; t.v[3] = m.m4; return t; }
static pf_evsm_moments to_evsm(texel t) { return pf_evsm_moments_make(t.v[0], t.v[1], t.v[2], t.v[3]); }
static texel from_evsm(pf_evsm_moments m) { texel t; t.v[0] = m.pos1; t.v[1] = m.pos2; t.v[2] = m.neg1; t.v[3] = m.neg2; return t; }
static pf_vec3 to_nrm(texel t) { return pf_vec3_make(t.v[0], t.v[1], t.v[2]); }
static texel from_nrm(pf_vec3 m) { texel t; t.v[0] = m.x; t.v[1] = m.y; t.v[2] = m.z; return t; }

/* The operations of one type, through the arrays. */
#define DEFINE_OPS(P, TO, FROM)                                                                \
    static texel P##_r2(texel a, texel b, texel c, texel d)                                    \
    { return FROM(pf_##P##_reduce2x2(TO(a), TO(b), TO(c), TO(d))); }                           \
    static texel P##_r3(texel a, texel b, texel c, pf_vec3 w)                                  \
    { return FROM(pf_##P##_reduce3(TO(a), TO(b), TO(c), w)); }                                 \
    static texel P##_r9(const texel *t, pf_vec3 wx, pf_vec3 wy)                                \
    { return FROM(pf_##P##_reduce3x3(TO(t[0]), TO(t[1]), TO(t[2]), TO(t[3]), TO(t[4]),         \
                                     TO(t[5]), TO(t[6]), TO(t[7]), TO(t[8]), wx, wy)); }        \
    static texel P##_acc(texel acc, texel t, pf_real w)                                        \
    { return FROM(pf_##P##_accumulate(TO(acc), TO(t), w)); }                                   \
    static texel P##_bil(texel a, texel b, texel c, texel d, pf_real fx, pf_real fy)           \
    { return FROM(pf_##P##_bilinear(TO(a), TO(b), TO(c), TO(d), fx, fy)); }
DEFINE_OPS(slope_moments, to_slope, from_slope)
DEFINE_OPS(scalar_moments, to_scalar, from_scalar)
DEFINE_OPS(depth_moments2, to_d2, from_d2)
DEFINE_OPS(depth_moments4, to_d4, from_d4)
DEFINE_OPS(evsm_moments, to_evsm, from_evsm)
DEFINE_OPS(normal_avg, to_nrm, from_nrm)

typedef struct moment_type {
    const char *name;
    int nc;
    texel (*r2)(texel, texel, texel, texel);
    texel (*r3)(texel, texel, texel, pf_vec3);
    texel (*r9)(const texel *, pf_vec3, pf_vec3);
    texel (*acc)(texel, texel, pf_real);
    texel (*bil)(texel, texel, texel, texel, pf_real, pf_real);
} moment_type;

#define TYPE_ENTRY(P, name, nc) { name, nc, P##_r2, P##_r3, P##_r9, P##_acc, P##_bil }
static const moment_type types[] = {
    TYPE_ENTRY(slope_moments, "slope", 5),    TYPE_ENTRY(scalar_moments, "scalar", 2),
    TYPE_ENTRY(depth_moments2, "vsm", 2),     TYPE_ENTRY(depth_moments4, "msm", 4),
    TYPE_ENTRY(evsm_moments, "evsm", 4),      TYPE_ENTRY(normal_avg, "normal", 3)};
#define NTYPES 6

/* The channel vector of one random sample for type index ti, in long double. */
static void sample_channels(int ti, pf_test_rng *rng, long double *c)
{
    long double x = (long double)pf_test_uniform(rng, -1.5, 1.5);
    long double y = (long double)pf_test_uniform(rng, -1.5, 1.5);
    long double z = (long double)pf_test_uniform(rng, 0.0, 1.0);
    switch (ti) {
    case 0: c[0] = x; c[1] = y; c[2] = x * x; c[3] = y * y; c[4] = x * y; break;
    case 1: c[0] = x; c[1] = x * x; break;
    case 2: c[0] = z; c[1] = z * z; break;
    case 3: c[0] = z; c[1] = z * z; c[2] = z * z * z; c[3] = z * z * z * z; break;
    case 4: {
        long double p = expl(5.0L * (2.0L * z - 1.0L)), n = -expl(-3.0L * (2.0L * z - 1.0L));
        c[0] = p; c[1] = p * p; c[2] = n; c[3] = n * n;
        break;
    }
    default: {
        long double r = sqrtl(1.0L + x * x + y * y);
        c[0] = -x / r; c[1] = -y / r; c[2] = 1.0L / r;
        break;
    }
    }
}

/* A texel made of `count` random samples: its moments (rounded to pf_real) and the sum of
   its samples' channels (long double, for the union). Returns the largest |channel|. */
static long double make_texel(int ti, pf_test_rng *rng, int count, texel *t, long double *sum)
{
    long double c[MAXC], mean[MAXC] = {0, 0, 0, 0, 0}, big = 0.0L;
    int i, k, nc = types[ti].nc;
    for (k = 0; k < MAXC; ++k) t->v[k] = PF_R(0.0);
    for (i = 0; i < count; ++i) {
        sample_channels(ti, rng, c);
        for (k = 0; k < nc; ++k) {
            mean[k] += c[k] / (long double)count;
            sum[k] += c[k];
        }
    }
    for (k = 0; k < nc; ++k) {
        t->v[k] = (pf_real)mean[k];
        if (fabsl(mean[k]) > big) big = fabsl(mean[k]);
    }
    return big;
}

/* The rounding of each texel's moments to pf_real is part of the input, so the reference
   union is formed from the rounded texels' own exact means (sum / count replaced by the
   rounded value times count): error then measures only the reduction. */
static long double union_error(const texel *got, const texel *tex, const long double *w, int n,
                               int nc, long double scale)
{
    long double worst = 0.0L;
    int k, i;
    for (k = 0; k < nc; ++k) {
        long double ref = 0.0L, e;
        for (i = 0; i < n; ++i) ref += w[i] * (long double)tex[i].v[k];
        e = fabsl((long double)got->v[k] - ref) / scale;
        if (e > worst) worst = e;
    }
    return worst;
}

/* ------------------------------------------------------------------ reductions */
/* 2x2, 3-edge, 9-corner and N-texel reductions equal the moments of the union of the samples
   behind the texels: the texels hold counts of samples in the ratio of their weights, and the
   mixture of the samples' moments is the weighted sum of the texel moments. */
static void test_reductions_equal_union_moments(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x3E0u);
    int ti, rep;
    long double worst_union = 0.0L;
    for (ti = 0; ti < NTYPES; ++ti) {
        const moment_type *ty = &types[ti];
        long double worst = 0.0L;
        for (rep = 0; rep < 40; ++rep) {
            texel t[9], got;
            long double w[9], sum[MAXC], scale = 0.0L, e, b;
            int k = 1 + rep % 7, j = rep % k, kk = 1 + (rep / 7) % 5, jj = (rep / 3) % kk, i, a;
            pf_vec3 wx = pf_mip_weights3(j, 2 * k + 1), wy = pf_mip_weights3(jj, 2 * kk + 1);
            long double cx[3], cy[3];
            /* 2x2: four texels of 6 samples each; the union of 24 samples */
            for (k = 0; k < MAXC; ++k) sum[k] = 0.0L;
            for (i = 0; i < 4; ++i) {
                b = make_texel(ti, &rng, 6, &t[i], sum);
                if (b > scale) scale = b;
                w[i] = 0.25L;
            }
            got = ty->r2(t[0], t[1], t[2], t[3]);
            e = union_error(&got, t, w, 4, ty->nc, scale);
            if (e > worst) worst = e;
            {   /* the same against the samples (texels exactly representable only in double) */
                long double ue = 0.0L;
                for (k = 0; k < ty->nc; ++k) {
                    long double d = fabsl((long double)got.v[k] - sum[k] / 24.0L) / scale;
                    if (d > ue) ue = d;
                }
                if (ue > worst_union) worst_union = ue;
            }
            /* odd edge: texels of (k - j), k, (j + 1) samples (polyphase weights) */
            k = 1 + rep % 7;
            cx[0] = (long double)(k - j); cx[1] = (long double)k; cx[2] = (long double)(j + 1);
            cy[0] = (long double)(kk - jj); cy[1] = (long double)kk; cy[2] = (long double)(jj + 1);
            scale = 0.0L;
            for (i = 0; i < 3; ++i) {
                b = make_texel(ti, &rng, (int)cx[i], &t[i], sum);
                if (b > scale) scale = b;
                w[i] = cx[i] / (long double)(2 * k + 1);
            }
            got = ty->r3(t[0], t[1], t[2], wx);
            e = union_error(&got, t, w, 3, ty->nc, scale);
            if (e > worst) worst = e;
            /* corner: 9 texels, counts cx[a] cy[b] */
            scale = 0.0L;
            for (i = 0; i < 3; ++i)
                for (a = 0; a < 3; ++a) {
                    b = make_texel(ti, &rng, (int)(cx[a] * cy[i]), &t[3 * i + a], sum);
                    if (b > scale) scale = b;
                    w[3 * i + a] = cx[a] * cy[i] / (long double)((2 * k + 1) * (2 * kk + 1));
                }
            got = ty->r9(t, wx, wy);
            e = union_error(&got, t, w, 9, ty->nc, scale);
            if (e > worst) worst = e;
            /* N texels by accumulation, weights 1..7 / 28 */
            scale = 0.0L;
            for (i = 0; i < MAXC; ++i) got.v[i] = PF_R(0.0);
            for (i = 0; i < 7; ++i) {
                b = make_texel(ti, &rng, i + 1, &t[i], sum);
                if (b > scale) scale = b;
                w[i] = (long double)(i + 1) / 28.0L;
                got = ty->acc(got, t[i], (pf_real)(i + 1) / PF_R(28.0));
            }
            e = union_error(&got, t, w, 7, ty->nc, scale);
            if (e > worst) worst = e;
        }
        pf_test_note("%s %.2Lf eps", ty->name, worst / PF_TEST_EPS);
        PF_CHECK(worst <= 4.0L * PF_TEST_EPS, "%s: %Lg eps", ty->name, worst / PF_TEST_EPS);
    }
    /* against the raw samples the texels' own rounding (one ulp each) adds in */
    pf_test_note("2x2 vs the samples: %.2Lf eps", worst_union / PF_TEST_EPS);
    PF_CHECK(worst_union <= 6.0L * PF_TEST_EPS, "%Lg eps", worst_union / PF_TEST_EPS);
}

/* pf_mip_weights3 against the overlap weights; every source texel gets n_dst / n_src. */
static void test_mip_weights_exact(void)
{
    long double worst = 0.0L, worst_total = 0.0L;
    int n, j, s;
    for (n = 1; n <= 41; ++n) {
        int nd = pf_mip_next_size(n);
        long double *total = alloc_ld(n);
        for (s = 0; s < n; ++s) total[s] = 0.0L;
        PF_CHECK(nd == next_size(n), "size %d", n);
        for (j = 0; j < nd; ++j) {
            pf_vec3 w = pf_mip_weights3(j, n);
            long double wv[3];
            int a;
            wv[0] = (long double)w.x;
            wv[1] = (long double)w.y;
            wv[2] = (long double)w.z;
            for (a = 0; a < 3; ++a) {
                long double ref = 2 * j + a < n ? overlap_weight(2 * j + a, j, n, nd) : 0.0L;
                long double e = fabsl(wv[a] - ref);
                if (e > worst) worst = e;
                if (2 * j + a < n) total[2 * j + a] += wv[a];
            }
            for (s = 0; s < n; ++s) /* no weight outside 2j .. 2j+2 */
                if ((s < 2 * j || s > 2 * j + 2) && overlap_weight(s, j, n, nd) != 0.0L) worst = 1.0L;
        }
        for (s = 0; s < n; ++s) {
            long double e = fabsl(total[s] - (long double)nd / (long double)n);
            if (e > worst_total) worst_total = e;
        }
        free(total);
    }
    pf_test_note("weights %.2Lf eps, per-source totals %.2Lf eps", worst / PF_TEST_EPS, worst_total / PF_TEST_EPS);
    PF_CHECK(worst <= PF_TEST_EPS, "%Lg", worst);
    PF_CHECK(worst_total <= 2.0L * PF_TEST_EPS, "%Lg", worst_total);
}

/* ------------------------------------------------------------------ pyramids */
static const int sizes[][2] = {{1, 1}, {1, 9}, {9, 1}, {2, 2}, {64, 64}, {37, 23}, {5, 3},
                               {2, 7}, {31, 31}, {48, 20}, {3, 100}};
#define NSIZES 11

/* Every level of pf_mip_build equals the box-overlap pyramid; layout functions agree; every
   level's mean equals level 0's mean, so the top is the global mean. */
static void test_pyramid_matches_reference(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x9A1u);
    long double worst = 0.0L, worst_top = 0.0L;
    int si, ok_layout = 1;
    for (si = 0; si < NSIZES; ++si) {
        int w = sizes[si][0], h = sizes[si][1], nc = 3, levels = pf_mip_level_count(w, h), l;
        long long n = pf_mip_texel_count(w, h), nref, i;
        pf_real *pyr = alloc_real(n * nc);
        long double *l0 = alloc_ld((long long)w * h * nc), *ref, mean[3] = {0, 0, 0};
        for (i = 0; i < (long long)w * h * nc; ++i) {
            pyr[i] = (pf_real)pf_test_uniform(&rng, -2.0, 3.0);
            l0[i] = (long double)pyr[i];
            mean[i % 3] += l0[i] / (long double)((long long)w * h);
        }
        pf_mip_build(pyr, w, h, nc);
        ref = ref_pyramid(l0, w, h, nc, 0, &nref);
        ok_layout &= nref == n;
        for (i = 0; i < n * nc && i < nref * nc; ++i) {
            long double e = fabsl((long double)pyr[i] - ref[i]) / 3.0L;
            if (e > worst) worst = e;
        }
        for (l = 0; l < levels; ++l) { /* layout: offsets, sizes, level means */
            int lw = pf_mip_level_size(w, l), lh = pf_mip_level_size(h, l), k;
            long long off = pf_mip_level_offset(w, h, l), t;
            long double m[3] = {0, 0, 0};
            for (t = 0; t < (long long)lw * lh; ++t)
                for (k = 0; k < 3; ++k) m[k] += (long double)pyr[(off + t) * nc + k] / (long double)((long long)lw * lh);
            for (k = 0; k < 3; ++k) {
                long double e = fabsl(m[k] - mean[k]) / 3.0L;
                if (e > worst_top) worst_top = e;
            }
            if (l == levels - 1) ok_layout &= lw == 1 && lh == 1 && off == n - 1;
        }
        free(pyr);
        free(l0);
        free(ref);
    }
    pf_test_note("levels vs reference %.2Lf eps, level means vs global mean %.2Lf eps", worst / PF_TEST_EPS,
                 worst_top / PF_TEST_EPS);
    PF_CHECK(ok_layout, "texel count, offsets or level sizes disagree with the reference");
    PF_CHECK(worst <= 16.0L * PF_TEST_EPS, "%Lg eps", worst / PF_TEST_EPS);
    PF_CHECK(worst_top <= 16.0L * PF_TEST_EPS, "%Lg eps", worst_top / PF_TEST_EPS);
}

/* GPU bilinear formula: x = u n - 0.5, i0 = floor(x), f = x - i0. The coordinate arithmetic is
   done in pf_real (as a sampler does in its own precision), so the comparison isolates the
   weighted sum; the indices and weights are derived here independently of pf_moments.h. */
static void ref_axis(long double ul, int n, int border, int *i0, int *i1, long double *f)
{
    pf_real u = (pf_real)ul, x, fl;
    int i;
    if (border == PF_BORDER_WRAP) u = u - (pf_real)floor((double)u);
    else u = u < PF_R(0.0) ? PF_R(0.0) : (u > PF_R(1.0) ? PF_R(1.0) : u);
    x = u * (pf_real)n - PF_R(0.5);
    fl = (pf_real)floor((double)x);
    *f = (long double)(x - fl);
    i = (int)fl;
    if (border == PF_BORDER_WRAP) {
        *i0 = ((i % n) + n) % n;
        *i1 = (*i0 + 1) % n;
    } else {
        *i0 = i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
        *i1 = i + 1 > n - 1 ? n - 1 : (i + 1 < 0 ? 0 : i + 1);
    }
}

static long double ref_bilinear(const pf_real *pyr, int w, int h, int nc, int level, long double u,
                                long double v, int border, int k)
{
    int lw = w, lh = h, l, x0, x1, y0, y1;
    long long off = 0;
    long double fx, fy;
    for (l = 0; l < level; ++l) {
        off += (long long)lw * lh;
        lw = next_size(lw);
        lh = next_size(lh);
    }
    ref_axis(u, lw, border, &x0, &x1, &fx);
    ref_axis(v, lh, border, &y0, &y1, &fy);
#define T_(x, y) ((long double)pyr[(off + (long long)(y) * lw + (x)) * nc + k])
    return (1.0L - fx) * (1.0L - fy) * T_(x0, y0) + fx * (1.0L - fy) * T_(x1, y0) +
           (1.0L - fx) * fy * T_(x0, y1) + fx * fy * T_(x1, y1);
#undef T_
}

/* Bilinear and trilinear samples equal the bilinearly weighted texels; the typed sampler and
   the shader evaluator pf_<T>_bilinear agree with the generic one. */
static void test_sampling_equals_weighted_texels(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x5A3u);
    long double worst = 0.0L, worst_eval = 0.0L;
    int si, rep, border;
    for (si = 4; si < NSIZES; ++si) {
        int w = sizes[si][0], h = sizes[si][1], nl = pf_mip_level_count(w, h);
        long long n = pf_mip_texel_count(w, h), i;
        pf_real *pyr = alloc_real(n * 5);
        for (i = 0; i < (long long)w * h * 5; ++i) pyr[i] = (pf_real)pf_test_uniform(&rng, -1.0, 1.0);
        pf_mip_build(pyr, w, h, 5);
        for (border = 0; border < 2; ++border)
            for (rep = 0; rep < 200; ++rep) {
                pf_real u = (pf_real)pf_test_uniform(&rng, -0.3, 1.3), v = (pf_real)pf_test_uniform(&rng, -0.3, 1.3);
                pf_real lod = (pf_real)pf_test_uniform(&rng, -0.5, (double)nl - 0.5);
                int l0 = (int)floorl((long double)lod), k;
                long double fl;
                pf_real out[5];
                pf_slope_moments m;
                if (l0 < 0) l0 = 0;
                if (l0 > nl - 1) l0 = nl - 1;
                fl = (long double)lod - (long double)l0;
                if (fl < 0.0L) fl = 0.0L;
                if (l0 == nl - 1) fl = 0.0L;
                pf_mip_sample_trilinear(pyr, w, h, 5, lod, u, v, border, out);
                m = pf_slope_moments_sample(pyr, w, h, lod, u, v, border);
                for (k = 0; k < 5; ++k) {
                    long double ref = (1.0L - fl) * ref_bilinear(pyr, w, h, 5, l0, (long double)u, (long double)v, border, k);
                    long double e;
                    if (fl > 0.0L) ref += fl * ref_bilinear(pyr, w, h, 5, l0 + 1, (long double)u, (long double)v, border, k);
                    e = fabsl((long double)out[k] - ref);
                    if (e > worst) worst = e;
                }
                if (!(m.ex == out[0] && m.ey == out[1] && m.exx == out[2] && m.eyy == out[3] && m.exy == out[4]))
                    worst = 1.0L;
                /* the shader evaluator on the four texels of level 0 */
                {
                    int x0, x1, y0, y1, kk;
                    long double fx, fy;
                    texel t[4], got;
                    ref_axis((long double)u, w, border, &x0, &x1, &fx);
                    ref_axis((long double)v, h, border, &y0, &y1, &fy);
                    for (kk = 0; kk < 5; ++kk) {
                        t[0].v[kk] = pyr[((long long)y0 * w + x0) * 5 + kk];
                        t[1].v[kk] = pyr[((long long)y0 * w + x1) * 5 + kk];
                        t[2].v[kk] = pyr[((long long)y1 * w + x0) * 5 + kk];
                        t[3].v[kk] = pyr[((long long)y1 * w + x1) * 5 + kk];
                    }
                    got = slope_moments_bil(t[0], t[1], t[2], t[3], (pf_real)fx, (pf_real)fy);
                    for (kk = 0; kk < 5; ++kk) {
                        long double e = fabsl((long double)got.v[kk] -
                                              ref_bilinear(pyr, w, h, 5, 0, (long double)u, (long double)v, border, kk));
                        if (e > worst_eval) worst_eval = e;
                    }
                }
            }
        free(pyr);
    }
    pf_test_note("trilinear vs weighted texels %.2Lf eps, pf_slope_moments_bilinear %.2Lf eps",
                 worst / PF_TEST_EPS, worst_eval / PF_TEST_EPS);
    PF_CHECK(worst <= 8.0L * PF_TEST_EPS, "%Lg eps", worst / PF_TEST_EPS);
    PF_CHECK(worst_eval <= 8.0L * PF_TEST_EPS, "%Lg eps", worst_eval / PF_TEST_EPS);
}

/* After reduction and interpolation the slope statistics are a valid covariance. */
static void test_covariance_valid_after_filtering(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xC0Fu);
    const int w = 61, h = 47;
    long long n = pf_mip_texel_count(w, h), i;
    pf_real *hgt = alloc_real((long long)w * h), *pyr = alloc_real(n * 5);
    int bad = 0, raw_negative = 0, rep, border;
    for (border = 0; border < 2; ++border) {
        for (i = 0; i < (long long)w * h; ++i) /* rough: white noise heights, some flat patches */
            hgt[i] = (i % 13 < 3) ? PF_R(0.25) : (pf_real)pf_test_uniform(&rng, -1.0, 1.0);
        pf_slope_pyramid_from_heights(hgt, w, h, PF_R(0.01), PF_R(0.013), PF_R(0.02), border, pyr);
        for (i = 0; i < n; ++i) {
            pf_slope_moments m = pf_slope_moments_make(pyr[5 * i], pyr[5 * i + 1], pyr[5 * i + 2],
                                                       pyr[5 * i + 3], pyr[5 * i + 4]);
            pf_slope_stats s = pf_slope_moments_stats(m, PF_R(0.0));
            long double det = (long double)s.var_x * (long double)s.var_y - (long double)s.cov_xy * (long double)s.cov_xy;
            bad += !(s.var_x > PF_R(0.0) && s.var_y > PF_R(0.0) && det > 0.0L);
            raw_negative += (long double)m.exx - (long double)m.ex * (long double)m.ex < 0.0L;
        }
        for (rep = 0; rep < 3000; ++rep) {
            pf_slope_moments m = pf_slope_moments_sample(pyr, w, h, (pf_real)pf_test_uniform(&rng, 0.0, 6.0),
                                                         (pf_real)pf_test_uniform(&rng, 0.0, 1.0),
                                                         (pf_real)pf_test_uniform(&rng, 0.0, 1.0), border);
            pf_slope_stats s = pf_slope_moments_stats(m, PF_R(0.0));
            long double det = (long double)s.var_x * (long double)s.var_y - (long double)s.cov_xy * (long double)s.cov_xy;
            bad += !(s.var_x > PF_R(0.0) && s.var_y > PF_R(0.0) && det > 0.0L);
        }
    }
    pf_test_note("%lld texels and 6000 samples: %d invalid; raw E[x^2] - E[x]^2 < 0 at %d texels "
                 "(rounding, clamped by the stats)", 2 * n, bad, raw_negative);
    PF_CHECK(bad == 0, "%d invalid covariances", bad);
    free(hgt);
    free(pyr);
}

/* ------------------------------------------------------------------ ESM */
/* The log-space pyramid equals log of the direct average of exp(c z) (long double), for
   exponents where float's exp(c z) overflows too; its samples alike. */
static void test_esm_log_matches_direct(void)
{
    static const long double cs[] = {1.0L, 20.0L, 80.0L, 300.0L, 3000.0L};
    pf_test_rng rng = pf_test_rng_seed(0xE5Au);
    const int w = 29, h = 18;
    long long n = pf_mip_texel_count(w, h), nref, i;
    pf_real *z = alloc_real((long long)w * h), *pyr = alloc_real(n);
    long double *l0 = alloc_ld((long long)w * h);
    int ci, rep, bad = 0;
    for (ci = 0; ci < 5; ++ci) {
        long double c = cs[ci], worst = 0.0L, worst_s = 0.0L, *ref;
        for (i = 0; i < (long long)w * h; ++i) {
            z[i] = (pf_real)pf_test_uniform(&rng, 0.0, 1.0);
            l0[i] = (long double)(pf_real)(c * (long double)z[i]);
        }
        pf_depth_pyramid_from_depths(z, w, h, PF_DEPTH_ESM_LOG, (pf_real)c, PF_R(0.0), pyr);
        ref = ref_pyramid(l0, w, h, 1, 1, &nref);
        for (i = 0; i < n; ++i) {
            long double e = fabsl((long double)pyr[i] - ref[i]) / (c > 1.0L ? c : 1.0L);
            if (e > worst) worst = e;
            bad += !pf_test_finite(pyr[i]);
        }
        for (rep = 0; rep < 100; ++rep) {
            pf_real u = (pf_real)pf_test_uniform(&rng, 0.0, 1.0), v = (pf_real)pf_test_uniform(&rng, 0.0, 1.0);
            int lvl = rep % pf_mip_level_count(w, h), x0, x1, y0, y1, lw = pf_mip_level_size(w, lvl), lh = pf_mip_level_size(h, lvl);
            long long off = pf_mip_level_offset(w, h, lvl);
            long double fx, fy, r, e;
            pf_real got = pf_esm_log_sample(pyr, w, h, (pf_real)lvl, u, v, PF_BORDER_CLAMP);
            ref_axis((long double)u, lw, PF_BORDER_CLAMP, &x0, &x1, &fx);
            ref_axis((long double)v, lh, PF_BORDER_CLAMP, &y0, &y1, &fy);
            r = logl((1.0L - fx) * (1.0L - fy) * expl((long double)pyr[off + (long long)y0 * lw + x0]) +
                     fx * (1.0L - fy) * expl((long double)pyr[off + (long long)y0 * lw + x1]) +
                     (1.0L - fx) * fy * expl((long double)pyr[off + (long long)y1 * lw + x0]) +
                     fx * fy * expl((long double)pyr[off + (long long)y1 * lw + x1]));
            e = fabsl((long double)got - r) / (c > 1.0L ? c : 1.0L);
            if (e > worst_s) worst_s = e;
            bad += !pf_test_finite(got);
        }
        pf_test_note("c %.0Lf: %.2Lf eps, samples %.2Lf eps (of c)", c, worst / PF_TEST_EPS, worst_s / PF_TEST_EPS);
        PF_CHECK(worst <= 16.0L * PF_TEST_EPS, "c %Lg: %Lg eps", c, worst / PF_TEST_EPS);
        PF_CHECK(worst_s <= 8.0L * PF_TEST_EPS, "c %Lg: %Lg eps", c, worst_s / PF_TEST_EPS);
        free(ref);
    }
    PF_CHECK(bad == 0, "%d non-finite", bad);
    free(z);
    free(pyr);
    free(l0);
}

/* ------------------------------------------------------------------ height maps */
/* h(x, y) = sum_k a_k sin(2 pi (fx_k x + fy_k y) + p_k) on [0, 1]^2. */
typedef struct wave_field {
    long double a[2], fx[2], fy[2], p[2];
} wave_field;

static long double field_h(const wave_field *f, long double x, long double y)
{
    return f->a[0] * sinl(2.0L * PF_TEST_PI * (f->fx[0] * x + f->fy[0] * y) + f->p[0]) +
           f->a[1] * sinl(2.0L * PF_TEST_PI * (f->fx[1] * x + f->fy[1] * y) + f->p[1]);
}

static void field_grad(const wave_field *f, long double x, long double y, long double *gx, long double *gy)
{
    int k;
    *gx = *gy = 0.0L;
    for (k = 0; k < 2; ++k) {
        long double c = f->a[k] * 2.0L * PF_TEST_PI * cosl(2.0L * PF_TEST_PI * (f->fx[k] * x + f->fy[k] * y) + f->p[k]);
        *gx += c * f->fx[k];
        *gy += c * f->fy[k];
    }
}

typedef struct field_moment {
    const wave_field *f;
    int which; /* 0..4: gx, gy, gx^2, gy^2, gx gy */
    long double scale;
} field_moment;

static long double field_moment_fn(long double x, long double y, void *ctx)
{
    const field_moment *m = (const field_moment *)ctx;
    long double gx, gy, s = m->scale;
    field_grad(m->f, x, y, &gx, &gy);
    gx *= s;
    gy *= s;
    switch (m->which) {
    case 0: return gx;
    case 1: return gy;
    case 2: return gx * gx;
    case 3: return gy * gy;
    default: return gx * gy;
    }
}

/* Max per-texel slope error and max top-level moment error for an N x N map. */
static void height_errors(const wave_field *f, int nn, int border, const long double *truth,
                          long double scale, long double *e_texel, long double *e_top)
{
    long long n = pf_mip_texel_count(nn, nn), i;
    pf_real *hgt = alloc_real((long long)nn * nn), *pyr = alloc_real(n * 5);
    pf_real d = PF_R(1.0) / (pf_real)nn;
    int r, c, k;
    for (r = 0; r < nn; ++r)
        for (c = 0; c < nn; ++c)
            hgt[(long long)r * nn + c] = (pf_real)field_h(f, ((long double)c + 0.5L) / nn, ((long double)r + 0.5L) / nn);
    pf_slope_pyramid_from_heights(hgt, nn, nn, d, d, (pf_real)scale, border, pyr);
    *e_texel = 0.0L;
    for (r = 0; r < nn; ++r)
        for (c = 0; c < nn; ++c) {
            long double gx, gy, e;
            field_grad(f, ((long double)c + 0.5L) / nn, ((long double)r + 0.5L) / nn, &gx, &gy);
            i = ((long long)r * nn + c) * 5;
            e = fabsl((long double)pyr[i] - scale * gx);
            if (e > *e_texel) *e_texel = e;
            e = fabsl((long double)pyr[i + 1] - scale * gy);
            if (e > *e_texel) *e_texel = e;
        }
    *e_top = 0.0L;
    for (k = 0; k < 5; ++k) {
        long double e = fabsl((long double)pyr[(n - 1) * 5 + k] - truth[k]);
        if (e > *e_top) *e_top = e;
    }
    free(hgt);
    free(pyr);
}

/* The central-difference stencil is second order: halving the texel size divides the
   per-texel slope error and the top-level moment error by ~4, with wrap (a periodic field) and
   clamp (a non-periodic one, one-sided second-order stencil on the border). */
static void test_height_slopes_converge(void)
{
    int border;
    for (border = 0; border < 2; ++border) {
        wave_field f;
        long double truth[5], et[3], eo[3], scale = 1.7L;
        int k, res;
        pf_oracle_2d pb;
        field_moment fm;
        f.a[0] = 0.05L; f.a[1] = 0.02L;
        f.p[0] = 0.3L; f.p[1] = 1.1L;
        if (border == PF_BORDER_WRAP) {
            f.fx[0] = 1.0L; f.fy[0] = 2.0L; f.fx[1] = 3.0L; f.fy[1] = -1.0L;
        } else {
            f.fx[0] = 0.7L; f.fy[0] = 1.3L; f.fx[1] = 2.4L; f.fy[1] = -0.6L;
        }
        fm.f = &f;
        fm.scale = scale;
        for (k = 0; k < 5; ++k) { /* the analytic moments over the domain */
            fm.which = k;
            pb = pf_oracle_2d_make(field_moment_fn, &fm, 0.0L, 1.0L, 0.0L, 1.0L);
            pb.epsrel = 1e-14L;
            pb.epsabs = 1e-16L;
            truth[k] = pf_oracle_integrate_2d(&pb).value;
        }
        for (res = 0; res < 3; ++res) height_errors(&f, 32 << res, border, truth, scale, &et[res], &eo[res]);
        pf_test_note("%s: texel err %.3Lg %.3Lg %.3Lg (ratios %.2Lf %.2Lf), top err %.3Lg %.3Lg %.3Lg (ratios %.2Lf %.2Lf)",
                     border == PF_BORDER_WRAP ? "wrap" : "clamp", et[0], et[1], et[2], et[0] / et[1],
                     et[1] / et[2], eo[0], eo[1], eo[2], eo[0] / eo[1], eo[1] / eo[2]);
        for (res = 0; res < 2; ++res) {
            PF_CHECK(et[res] / et[res + 1] > 3.6L && et[res] / et[res + 1] < 4.4L, "texel ratio %Lg",
                     et[res] / et[res + 1]);
            PF_CHECK(eo[res] / eo[res + 1] > 3.5L && eo[res] / eo[res + 1] < 4.5L, "top ratio %Lg",
                     eo[res] / eo[res + 1]);
        }
    }
}

/* The shader evaluator equals the map walker on interior texels, and the edge stencil is exact
   on quadratics. */
static void test_height_evaluators(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x4E1u);
    const int w = 9, h = 7;
    pf_real hgt[63], out[315];
    int i, j, bad = 0;
    long double worst_edge = 0.0L;
    for (i = 0; i < w * h; ++i) hgt[i] = (pf_real)pf_test_uniform(&rng, -1.0, 1.0);
    pf_slope_moments_map_from_heights(hgt, w, h, PF_R(0.5), PF_R(0.25), PF_R(3.0), PF_BORDER_CLAMP, out);
    for (j = 1; j < h - 1; ++j)
        for (i = 1; i < w - 1; ++i) {
            pf_slope_moments m = pf_slope_moments_from_heights(hgt[j * w + i - 1], hgt[j * w + i + 1],
                                                               hgt[(j - 1) * w + i], hgt[(j + 1) * w + i],
                                                               PF_R(0.5), PF_R(0.25), PF_R(3.0));
            const pf_real *o = out + 5 * (j * w + i);
            long double tol = 4.0L * PF_TEST_EPS * 3.0L * 4.0L;
            bad += fabsl((long double)m.ex - (long double)o[0]) > tol * 2.0L;
            bad += fabsl((long double)m.ey - (long double)o[1]) > tol * 4.0L;
        }
    for (i = 0; i < 20; ++i) { /* q(t) = a + b t + c t^2: slope at 0 is b */
        long double a = (long double)pf_test_uniform(&rng, -1, 1), b = (long double)pf_test_uniform(&rng, -1, 1);
        long double c = (long double)pf_test_uniform(&rng, -1, 1);
        pf_real s = pf_height_slope_edge((pf_real)a, (pf_real)(a + b * 0.5L + c * 0.25L), (pf_real)(a + b + c), PF_R(0.5));
        long double e = fabsl((long double)s - b);
        if (e > worst_edge) worst_edge = e;
    }
    pf_test_note("edge stencil on quadratics: %.2Lf eps", worst_edge / PF_TEST_EPS);
    PF_CHECK(bad == 0, "%d interior texels differ", bad);
    PF_CHECK(worst_edge <= 32.0L * PF_TEST_EPS, "%Lg", worst_edge);
}

/* ------------------------------------------------------------------ other map kinds */
/* Scalar, depth (every kind) and normal pyramids: level 0 is the per-texel evaluator and the
   top is the long double mean of the per-texel channels. */
static void test_map_kinds_top_is_mean(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xD3Fu);
    const int w = 23, h = 14;
    long long n = pf_mip_texel_count(w, h), i;
    pf_real *z = alloc_real((long long)w * h * 3), *pyr = alloc_real(n * 4);
    int kind, k, bad0 = 0;
    long double worst = 0.0L;
    for (i = 0; i < (long long)w * h * 3; ++i) z[i] = (pf_real)pf_test_uniform(&rng, 0.0, 1.0);
    for (kind = 0; kind <= 5; ++kind) {
        int nc = kind == 5 ? 2 : pf_depth_moment_channels(kind);
        long double mean[4] = {0, 0, 0, 0}, big = 0.0L;
        if (kind == PF_DEPTH_ESM_LOG) continue; /* tested above */
        if (kind == 5) pf_scalar_pyramid_from_values(z, w, h, pyr);
        else pf_depth_pyramid_from_depths(z, w, h, kind, PF_R(10.0), PF_R(5.0), pyr);
        for (i = 0; i < (long long)w * h; ++i) {
            long double zl = (long double)z[i], c[4];
            long double p = expl(10.0L * (2.0L * zl - 1.0L)), q = -expl(-5.0L * (2.0L * zl - 1.0L));
            pf_real e[4];
            switch (kind) {
            case PF_DEPTH_EVSM2: { pf_depth_moments2 m = pf_evsm2_from_depth(z[i], PF_R(10.0)); e[0] = m.m1; e[1] = m.m2;
                c[0] = p; c[1] = p * p; break; }
            case PF_DEPTH_EVSM4: { pf_evsm_moments m = pf_evsm_moments_from_depth(z[i], PF_R(10.0), PF_R(5.0));
                e[0] = m.pos1; e[1] = m.pos2; e[2] = m.neg1; e[3] = m.neg2; c[0] = p; c[1] = p * p; c[2] = q; c[3] = q * q; break; }
            case PF_DEPTH_MSM: { pf_depth_moments4 m = pf_depth_moments4_from_depth(z[i]); e[0] = m.m1; e[1] = m.m2; e[2] = m.m3; e[3] = m.m4;
                c[0] = zl; c[1] = zl * zl; c[2] = zl * zl * zl; c[3] = zl * zl * zl * zl; break; }
            case 5: { pf_scalar_moments m = pf_scalar_moments_from_value(z[i]); e[0] = m.m1; e[1] = m.m2;
                c[0] = zl; c[1] = zl * zl; break; }
            default: { pf_depth_moments2 m = pf_depth_moments2_from_depth(z[i]); e[0] = m.m1; e[1] = m.m2;
                c[0] = zl; c[1] = zl * zl; break; }
            }
            for (k = 0; k < nc; ++k) {
                bad0 += pyr[i * nc + k] != e[k];
                mean[k] += (long double)pyr[i * nc + k] / (long double)((long long)w * h);
                if (fabsl(c[k]) > big) big = fabsl(c[k]);
            }
        }
        for (k = 0; k < nc; ++k) {
            long double e = fabsl((long double)pyr[(n - 1) * nc + k] - mean[k]) / big;
            if (e > worst) worst = e;
        }
    }
    { /* normals */
        long double mean[3] = {0, 0, 0};
        pf_normal_pyramid_from_normals(z, w, h, pyr);
        for (i = 0; i < (long long)w * h; ++i) {
            long double x = (long double)z[3 * i], y = (long double)z[3 * i + 1], q = (long double)z[3 * i + 2];
            long double len = sqrtl(x * x + y * y + q * q);
            mean[0] += x / len / (long double)((long long)w * h);
            mean[1] += y / len / (long double)((long long)w * h);
            mean[2] += q / len / (long double)((long long)w * h);
        }
        for (k = 0; k < 3; ++k) {
            long double e = fabsl((long double)pyr[(n - 1) * 3 + k] - mean[k]);
            if (e > worst) worst = e;
        }
    }
    pf_test_note("top vs mean %.2Lf eps (relative to the largest channel value)", worst / PF_TEST_EPS);
    PF_CHECK(bad0 == 0, "%d level-0 texels differ from the per-texel evaluators", bad0);
    PF_CHECK(worst <= 16.0L * PF_TEST_EPS, "%Lg eps", worst / PF_TEST_EPS);
    free(z);
    free(pyr);
}

/* N texels: the CPU weighted mean, the shader accumulators and the ESM streaming sum. */
static void test_weighted_means(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x77u);
    pf_real tex[13 * 5], wts[13], out[5], logs[13];
    long double worst = 0.0L, worst_log = 0.0L, wsum = 0.0L, ref[5] = {0, 0, 0, 0, 0}, es = 0.0L;
    pf_slope_moments acc = pf_slope_moments_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
    pf_esm_log_sum ls = PF_ESM_LOG_SUM_EMPTY;
    int i, k;
    for (i = 0; i < 13; ++i) {
        wts[i] = i == 4 ? PF_R(0.0) : (pf_real)pf_test_uniform(&rng, 0.0, 2.0);
        logs[i] = (pf_real)pf_test_uniform(&rng, -50.0, 120.0);
        for (k = 0; k < 5; ++k) tex[5 * i + k] = (pf_real)pf_test_uniform(&rng, -1.0, 1.0);
        if (i == 4) tex[5 * i] = (pf_real)NAN; /* zero weight: never read */
        wsum += (long double)wts[i];
    }
    for (i = 0; i < 13; ++i) {
        if (wts[i] == PF_R(0.0)) continue;
        for (k = 0; k < 5; ++k) ref[k] += (long double)wts[i] / wsum * (long double)tex[5 * i + k];
        es += (long double)wts[i] / wsum * expl((long double)logs[i]);
        acc = pf_slope_moments_accumulate(acc, pf_slope_moments_make(tex[5 * i], tex[5 * i + 1], tex[5 * i + 2],
                                                                     tex[5 * i + 3], tex[5 * i + 4]),
                                          (pf_real)((long double)wts[i] / wsum));
        ls = pf_esm_log_sum_add(ls, logs[i], wts[i]);
    }
    pf_moments_weighted_mean(tex, 5, wts, 13, out);
    for (k = 0; k < 5; ++k) {
        long double e = fabsl((long double)out[k] - ref[k]);
        if (e > worst) worst = e;
    }
    {
        long double e[5];
        e[0] = fabsl((long double)acc.ex - ref[0]);
        e[1] = fabsl((long double)acc.ey - ref[1]);
        e[2] = fabsl((long double)acc.exx - ref[2]);
        e[3] = fabsl((long double)acc.eyy - ref[3]);
        e[4] = fabsl((long double)acc.exy - ref[4]);
        for (k = 0; k < 5; ++k)
            if (e[k] > worst) worst = e[k];
    }
    worst_log = fabsl((long double)pf_esm_log_weighted_mean(logs, wts, 13) - logl(es));
    {
        long double e2 = fabsl((long double)pf_esm_log_sum_mean(ls) - logl(es));
        if (e2 > worst_log) worst_log = e2;
    }
    pf_test_note("weighted mean %.2Lf eps, ESM log %.2Lf eps of 120", worst / PF_TEST_EPS, worst_log / 120.0L / PF_TEST_EPS);
    PF_CHECK(worst <= 16.0L * PF_TEST_EPS, "%Lg", worst / PF_TEST_EPS);
    PF_CHECK(worst_log <= 8.0L * 120.0L * PF_TEST_EPS, "%Lg", worst_log);
}

/* NaN texels (documented: propagate): a NaN makes NaN exactly the texels whose footprint
   covers it (overlap weight > 0), nothing else; sampling and reading stay in bounds. */
static void test_nan_texels_propagate_upward_only(void)
{
    const int w = 13, h = 9, nx = 5, ny = 4;
    long long n = pf_mip_texel_count(w, h), i;
    pf_real *pyr = alloc_real(n * 2);
    int levels = pf_mip_level_count(w, h), l, wrong = 0, lw = w, lh = h;
    long long off = 0;
    int cx0 = nx, cx1 = nx, cy0 = ny, cy1 = ny; /* covered range at the current level */
    for (i = 0; i < (long long)w * h * 2; ++i) pyr[i] = PF_R(0.5);
    pyr[(ny * w + nx) * 2] = (pf_real)NAN;
    pf_mip_build(pyr, w, h, 2);
    for (l = 0; l < levels; ++l) {
        int x, y;
        for (y = 0; y < lh; ++y)
            for (x = 0; x < lw; ++x) {
                int covered = x >= cx0 && x <= cx1 && y >= cy0 && y <= cy1;
                pf_real v0 = pyr[(off + (long long)y * lw + x) * 2], v1 = pyr[(off + (long long)y * lw + x) * 2 + 1];
                wrong += covered ? !isnan((double)v0) : !pf_test_finite(v0);
                wrong += !pf_test_finite(v1); /* the other channel never sees the NaN */
            }
        if (l + 1 < levels) { /* destination texels with a positive overlap with the range */
            int dw = next_size(lw), dh = next_size(lh), d, ncx0 = dw, ncx1 = -1, ncy0 = dh, ncy1 = -1, s;
            for (d = 0; d < dw; ++d)
                for (s = cx0; s <= cx1; ++s)
                    if (overlap_weight(s, d, lw, dw) > 0.0L) { if (d < ncx0) ncx0 = d; if (d > ncx1) ncx1 = d; }
            for (d = 0; d < dh; ++d)
                for (s = cy0; s <= cy1; ++s)
                    if (overlap_weight(s, d, lh, dh) > 0.0L) { if (d < ncy0) ncy0 = d; if (d > ncy1) ncy1 = d; }
            cx0 = ncx0; cx1 = ncx1; cy0 = ncy0; cy1 = ncy1;
            off += (long long)lw * lh;
            lw = dw;
            lh = dh;
        }
    }
    pf_test_note("%d texels differ from the predicted NaN set", wrong);
    PF_CHECK(wrong == 0, "%d", wrong);
    free(pyr);
}

/* ------------------------------------------------------------------ storage precision */
/* Round to IEEE half (11 significant bits, normal range; enough for these magnitudes). */
static long double round_half(long double x)
{
    int e;
    long double m;
    if (x == 0.0L) return 0.0L;
    m = frexpl(x, &e); /* x = m 2^e, |m| in [0.5, 1) */
    return ldexpl(roundl(ldexpl(m, 11)), e - 11);
}

/* What 16-bit (half) storage of the first and second moments does to the variance recovered
   after filtering, var = E[x^2] - E[x]^2: the rounding of E[x^2] (relative 2^-11) is amplified
   by (mu^2 + sigma^2) / sigma^2. Measured on footprints of 4096 Gaussian slopes of mean mu and
   deviation sigma; the docs' storage advice quotes these numbers. */
static void test_half_storage_variance(void)
{
    static const long double mus[] = {0.0L, 0.1L, 0.5L, 1.0L};
    static const long double sds[] = {0.01L, 0.03L, 0.1L, 0.3L};
    pf_test_rng rng = pf_test_rng_seed(0x16u);
    int a, b, i;
    for (a = 0; a < 4; ++a) {
        long double worst = 0.0L;
        for (b = 0; b < 4; ++b) {
            long double m1 = 0.0L, m2 = 0.0L, var, var_h, e, bound;
            for (i = 0; i < 4096; ++i) {
                long double u1 = 1.0L - (long double)pf_test_uniform(&rng, 0.0, 1.0);
                long double u2 = (long double)pf_test_uniform(&rng, 0.0, 1.0);
                long double x = mus[a] + sds[b] * sqrtl(-2.0L * logl(u1)) * cosl(2.0L * PF_TEST_PI * u2);
                m1 += x / 4096.0L;
                m2 += x * x / 4096.0L;
            }
            var = m2 - m1 * m1;
            var_h = round_half(m2) - round_half(m1) * round_half(m1);
            e = fabsl(var_h - var) / var;
            /* half rounding (11 significant bits): |dm2| <= 2^-11 m2, |d(m1^2)| <= 2^-10 m1^2
               (+ its square) */
            bound = (ldexpl(1.0L, -11) * m2 + 1.01L * ldexpl(1.0L, -10) * m1 * m1) / var;
            PF_CHECK(e <= bound, "mu %Lg sigma %Lg: %Lg > %Lg", mus[a], sds[b], e, bound);
            pf_test_note("mu %.1Lf sigma %.2Lf: %.2Lg", mus[a], sds[b], e);
            if (e > worst) worst = e;
        }
    }
}

/* ------------------------------------------------------------------ edge cases */
static void edge_bad_input(void)
{
    static const int thin[][2] = {{1, 1}, {1, 2}, {1, 17}, {17, 1}, {2, 1}, {3, 1}};
    pf_real dummy[8] = {0, 0, 0, 0, 0, 0, 0, 0}, s[5];
    int bad = 0, t;
    /* zero-size maps, null pointers, bad channel counts: nothing happens */
    bad += pf_mip_texel_count(0, 5) != 0 || pf_mip_texel_count(5, 0) != 0 || pf_mip_texel_count(-3, -3) != 0;
    bad += pf_mip_level_count(0, 0) != 0;
    bad += pf_mip_texel_count(1, 1) != 1 || pf_mip_texel_count(1, 7) != 11 || pf_mip_texel_count(7, 1) != 11;
    pf_mip_build(dummy, 0, 4, 3);
    pf_mip_build(NULL, 4, 4, 3);
    pf_mip_build(dummy, 1, 1, 0);
    pf_mip_build_log(dummy, -1, 2, 1);
    pf_slope_pyramid_from_heights(NULL, 4, 4, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP, dummy);
    pf_slope_pyramid_from_heights(dummy, 0, 4, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP, dummy);
    pf_depth_pyramid_from_depths(dummy, 1, 1, 99, PF_R(1.0), PF_R(1.0), dummy);
    pf_mip_sample_trilinear(dummy, 0, 0, 1, PF_R(0.0), PF_R(0.5), PF_R(0.5), PF_BORDER_WRAP, s);
    pf_moments_weighted_mean(dummy, 2, dummy, 0, s);
    bad += !(s[0] == PF_R(0.0) && s[1] == PF_R(0.0));
    bad += pf_esm_log_weighted_mean(dummy, dummy, 0) != -PF_REAL_MAX;
    /* thin maps: the top is the mean; heights on 1-texel axes give slope 0 there */
    for (t = 0; t < 6; ++t) {
        int w = thin[t][0], h = thin[t][1], i, border;
        long long n = pf_mip_texel_count(w, h);
        pf_real *hgt = alloc_real((long long)w * h), *pyr = alloc_real(n * 5);
        for (border = 0; border < 2; ++border) {
            long double mean = 0.0L;
            for (i = 0; i < w * h; ++i) hgt[i] = (pf_real)(0.1 * i * i);
            pf_slope_pyramid_from_heights(hgt, w, h, PF_R(1.0), PF_R(1.0), PF_R(1.0), border, pyr);
            for (i = 0; i < w * h; ++i) mean += (long double)pyr[5 * i + 2] / (long double)(w * h);
            for (i = 0; i < n * 5; ++i) bad += !pf_test_finite(pyr[i]);
            bad += fabsl((long double)pyr[(n - 1) * 5 + 2] - mean) > 1e-3L * (mean + 1.0L);
            if (w == 1) for (i = 0; i < h; ++i) bad += pyr[5 * i] != PF_R(0.0);
            if (h == 1) for (i = 0; i < w; ++i) bad += pyr[5 * i + 1] != PF_R(0.0);
            /* samples anywhere, with absurd coordinates and lods, stay finite */
            {
                static const pf_real us[] = {PF_R(-1e30), PF_R(-0.2), PF_R(0.0), PF_R(0.5), PF_R(1.0), PF_R(7.3), PF_R(1e30)};
                int a, b;
                for (a = 0; a < 7; ++a)
                    for (b = 0; b < 7; ++b) {
                        pf_slope_moments m = pf_slope_moments_sample(pyr, w, h, us[b] * PF_R(1e-29) * PF_R(3.0), us[a], us[6 - b], border);
                        bad += !(pf_test_finite(m.ex) && pf_test_finite(m.exx) && pf_test_finite(m.exy));
                    }
            }
        }
        free(hgt);
        free(pyr);
    }
    PF_CHECK(bad == 0, "%d failures", bad);
}

/* log(w0 e^l0 + w1 e^l1) in long double, the max taken over the positive weights */
static long double lse2_ref(long double l0, long double w0, long double l1, long double w1)
{
    long double m = w0 > 0.0L ? (w1 > 0.0L && l1 > l0 ? l1 : l0) : l1;
    return m + logl((w0 > 0.0L ? w0 * expl(l0 - m) : 0.0L) + (w1 > 0.0L ? w1 * expl(l1 - m) : 0.0L));
}

/* The sweep's failing inputs (docs/stability.md, first sweep): the larger log has weight 0 and
   the other term underflowed, so the old m = max(l0, l1) gave log(0) = -inf. Then random logs
   up to 2^12 with weights 0, tiny and uniform against the long double log-sum-exp. */
static void edge_esm_log_combine2_zero_weight(void)
{
    pf_test_rng r = pf_test_rng_seed(0xE5C0B12EULL);
#ifdef PF_DOUBLE
    pf_real cc = PF_R(2792.0), z0 = (pf_real)ldexp(12684032.0, -25), z1 = (pf_real)ldexp(14403712.0, -27);
    pf_real w1 = (pf_real)ldexp(10912748.0, -26);
#else
    pf_real cc = PF_R(4096.0), z0 = (pf_real)ldexp(12324178.0, -25), z1 = (pf_real)ldexp(10461216.0, -25);
    pf_real w1 = (pf_real)ldexp(14829136.0, -24);
#endif
    pf_real l0 = cc * z0, l1 = cc * z1;
    pf_real got = pf_esm_log_combine2(l0, PF_R(0.0), l1, w1);
    long double ref = (long double)l1 + logl((long double)w1), worst = 0.0L;
    int i, bad = 0;
    PF_CHECK(pf_test_bits_finite(got) && fabsl((long double)got - ref) <= 4.0L * PF_TEST_EPS * fabsl(ref),
             "combine2(%g, 0, %g, %g) = %g, want %Lg", (double)l0, (double)l1, (double)w1, (double)got, ref);
    got = pf_esm_log_combine2(l1, w1, l0, PF_R(0.0)); /* the mirror image */
    PF_CHECK(pf_test_bits_finite(got) && fabsl((long double)got - ref) <= 4.0L * PF_TEST_EPS * fabsl(ref), "mirrored: %g", (double)got);
    PF_CHECK(pf_esm_log_combine2(l0, PF_R(0.0), l1, PF_R(0.0)) == -PF_REAL_MAX, "both weights 0");
    for (i = 0; i < 200000; ++i) {
        pf_real a = (pf_real)pf_test_uniform(&r, 0.0, 4096.0), b = (pf_real)pf_test_uniform(&r, 0.0, 4096.0);
        unsigned k = (unsigned)(pf_test_rng_next(&r) % 8u);
        pf_real wa = k == 0 ? PF_R(0.0) : (k == 1 ? PF_R(1.0e-30) : (pf_real)pf_test_uniform(&r, 0.0, 1.0));
        pf_real wb = k == 2 ? PF_R(0.0) : (pf_real)pf_test_uniform(&r, 0.001, 1.0);
        long double want = lse2_ref((long double)a, (long double)wa, (long double)b, (long double)wb), err;
        got = pf_esm_log_combine2(a, wa, b, wb);
        if (!pf_test_bits_finite(got)) { bad++; continue; }
        err = fabsl((long double)got - want) / (fabsl(want) + 1.0L);
        if (err > worst) worst = err;
    }
    pf_test_note("random logs in [0, 4096], zero and tiny weights: error <= %.2Lf eps (|l| + 1), %d non-finite",
                 worst / PF_TEST_EPS, bad);
    PF_CHECK(bad == 0, "%d non-finite", bad);
    PF_CHECK(worst <= 4.0L * PF_TEST_EPS, "error %Lg", worst);
}

/* One EVSM texel of two depths mixed, as tests/fuzz/pf_calls.h builds them. */
static pf_evsm_moments evsm_mix(pf_real cp, pf_real cn, pf_real z0, pf_real z1, pf_real t)
{
    pf_evsm_moments a = pf_evsm_moments_from_depth(z0, cp, cn), b = pf_evsm_moments_from_depth(z1, cp, cn);
    pf_real s = PF_R(1.0) - t;
    return pf_evsm_moments_make(s * a.pos1 + t * b.pos1, s * a.pos2 + t * b.pos2, s * a.neg1 + t * b.neg1,
                                s * a.neg2 + t * b.neg2);
}

static long double mean4_err(pf_real got, pf_real a, pf_real b, pf_real c, pf_real d)
{
    long double want = ((long double)a + (long double)b + (long double)c + (long double)d) / 4.0L;
    return want == 0.0L ? fabsl((long double)got) : fabsl((long double)got - want) / fabsl(want);
}

/* The sweep's failing input under float -ffast-math (docs/stability.md, first sweep): four
   second moments near exp(88) whose sum overflows once -ffast-math factors 0.25 out of the
   weighted sum. Then random texels with exponents in [40, 44] against the long double mean. */
static void edge_evsm_reduce2x2_near_max(void)
{
    static const double k[20][2] = {
        {11521491.0, -18}, {0.0, 0}, {15939140.0, -26}, {16776626.0, -24}, {15155754.0, -24},
        {11450572.0, -18}, {15146231.0, -19}, {11301985.0, -24}, {8388608.0, -23}, {11064097.0, -24},
        {10610996.0, -23}, {10770014.0, -18}, {9684608.0, -26}, {10557888.0, -28}, {8388608.0, -23},
        {11534336.0, -18}, {0.0, 0}, {8388608.0, -23}, {16631109.0, -24}, {15842592.0, -29}};
    pf_real v[20];
    pf_evsm_moments t[4], m;
    pf_test_rng r = pf_test_rng_seed(0xE75A2B2ULL);
    long double worst = 0.0L;
    int i, bad = 0;
    for (i = 0; i < 20; ++i) v[i] = (pf_real)ldexp(k[i][0], (int)k[i][1]);
    for (i = 0; i < 4; ++i) t[i] = evsm_mix(v[5 * i], v[5 * i + 1], v[5 * i + 2], v[5 * i + 3], v[5 * i + 4]);
    m = pf_evsm_moments_reduce2x2(t[0], t[1], t[2], t[3]);
    PF_CHECK(pf_test_bits_finite(m.pos1) && pf_test_bits_finite(m.pos2) && pf_test_bits_finite(m.neg1) && pf_test_bits_finite(m.neg2),
             "reduce2x2 = (%g %g %g %g)", (double)m.pos1, (double)m.pos2, (double)m.neg1, (double)m.neg2);
    PF_CHECK(mean4_err(m.pos2, t[0].pos2, t[1].pos2, t[2].pos2, t[3].pos2) <= 4.0L * PF_TEST_EPS, "pos2 %g",
             (double)m.pos2);
    for (i = 0; i < 100000; ++i) {
        int j;
        long double e;
        for (j = 0; j < 4; ++j) {
            pf_real cp = (pf_real)pf_test_uniform(&r, 40.0, 44.0), cn = (pf_real)pf_test_uniform(&r, 40.0, 44.0);
            t[j] = evsm_mix(cp, cn, (pf_real)pf_test_uniform(&r, 0.9, 1.0), (pf_real)pf_test_uniform(&r, 0.0, 1.0),
                            (pf_real)pf_test_uniform(&r, 0.0, 1.0));
        }
        m = pf_evsm_moments_reduce2x2(t[0], t[1], t[2], t[3]);
        if (!(pf_test_bits_finite(m.pos1) && pf_test_bits_finite(m.pos2) && pf_test_bits_finite(m.neg1) && pf_test_bits_finite(m.neg2))) {
            bad++;
            continue;
        }
        e = mean4_err(m.pos1, t[0].pos1, t[1].pos1, t[2].pos1, t[3].pos1);
        e = fmaxl(e, mean4_err(m.pos2, t[0].pos2, t[1].pos2, t[2].pos2, t[3].pos2));
        e = fmaxl(e, mean4_err(m.neg1, t[0].neg1, t[1].neg1, t[2].neg1, t[3].neg1));
        e = fmaxl(e, mean4_err(m.neg2, t[0].neg2, t[1].neg2, t[2].neg2, t[3].neg2));
        if (e > worst) worst = e;
    }
    pf_test_note("texels near exp(88): relative error <= %.2Lf eps, %d non-finite", worst / PF_TEST_EPS, bad);
    PF_CHECK(bad == 0, "%d non-finite", bad);
    PF_CHECK(worst <= 4.0L * PF_TEST_EPS, "error %Lg", worst);
}

static void edge_extreme_values(void)
{
    int bad = 0, j, n;
    pf_real big = pf_evsm2_from_depth(PF_R(1.0), PF_EVSM_EXP_MAX_F32).m2; /* exp(88) */
    pf_depth_moments2 b = pf_depth_moments2_make(big, big);
    pf_depth_moments2 r = pf_depth_moments2_reduce2x2(b, b, b, b);
    pf_real pyr[5 * 5 * 2 + 7 * 2 + 10];
    pf_real z[25];
    bad += !(pf_test_finite(big) && pf_test_finite(r.m2) && r.m2 > PF_R(0.0));
    bad += !pf_test_finite(pf_depth_moments2_reduce3(b, b, b, pf_mip_weights3(1, 5)).m2);
    bad += !pf_test_finite(pf_depth_moments2_bilinear(b, b, b, b, PF_R(0.3), PF_R(0.6)).m2);
    for (j = 0; j < 25; ++j) z[j] = PF_R(1.0) - PF_R(0.001) * (pf_real)j;
    pf_depth_pyramid_from_depths(z, 5, 5, PF_DEPTH_EVSM2, PF_EVSM_EXP_MAX_F32, PF_R(0.0), pyr);
    for (j = 0; j < (int)pf_mip_texel_count(5, 5) * 2; ++j) bad += !pf_test_finite(pyr[j]);
    /* ESM: exp(c z) overflows float for c z > 88.7; the log-space pyramid does not */
    pf_depth_pyramid_from_depths(z, 5, 5, PF_DEPTH_ESM_LOG, PF_R(1.0e4), PF_R(0.0), pyr);
    for (j = 0; j < (int)pf_mip_texel_count(5, 5); ++j) bad += !pf_test_finite(pyr[j]);
    bad += !pf_test_finite(pf_esm_log_sample(pyr, 5, 5, PF_R(0.7), PF_R(0.3), PF_R(0.9), PF_BORDER_WRAP));
    bad += !pf_test_finite(pf_esm_log_reduce2x2(PF_R(-1e30), PF_R(1e30), PF_R(0.0), PF_R(88.0)));
    bad += !pf_test_finite(pf_esm_log_bilinear(PF_R(1e4), PF_R(-1e4), PF_R(3e4), PF_R(0.0), PF_R(0.5), PF_R(1.0)));
    bad += pf_esm_log_reduce3(PF_R(1.0), PF_R(2.0), PF_R(3.0), pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0))) != -PF_REAL_MAX;
    bad += pf_esm_log_sum_mean(PF_ESM_LOG_SUM_EMPTY) != -PF_REAL_MAX;
    bad += !pf_test_finite(pf_esm_log_sum_mean(pf_esm_log_sum_add(pf_esm_log_sum_first(PF_R(-1e30), PF_R(1.0)), PF_R(1e30), PF_R(2.0))));
    bad += !pf_test_finite(pf_esm_log_reduce3x3(PF_R(1e4), PF_R(2e4), PF_R(0.0), PF_R(5.0), PF_R(6.0), PF_R(7.0),
                                                PF_R(8.0), PF_R(9.0), PF_R(1e4), pf_mip_weights3(0, 3), pf_mip_weights3(0, 2)));
    /* weights for any index and size are finite, in [0, 1] and sum to 1 (or 0 for n < 1) */
    for (n = -2; n < 12; ++n)
        for (j = -3; j < 10; ++j) {
            pf_vec3 w = pf_mip_weights3(j, n);
            pf_real sum = w.x + w.y + w.z;
            bad += !(w.x >= PF_R(0.0) && w.y >= PF_R(0.0) && w.z >= PF_R(0.0) && w.x <= PF_R(1.0));
            bad += n >= 1 ? !(sum > PF_R(0.999) && sum < PF_R(1.001)) : sum != PF_R(0.0);
        }
    bad += pf_mip_next_size(0) != 0 || pf_mip_next_size(1) != 1 || pf_mip_next_size(7) != 3;
    bad += !(pf_scalar_moments_variance(pf_scalar_moments_make(PF_R(1.0), PF_R(0.999))) == PF_R(0.0));
    bad += !pf_test_finite(pf_normal_avg_from_normal(pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0))).z);
    PF_CHECK(bad == 0, "%d failures", bad);
}

/* ------------------------------------------------------------------ issue 19: memory safety */
#define CANARY PF_R(-12345.0)
#define NCAN 64
static void canary_fill(pf_real *b) { int i; for (i = 0; i < NCAN; ++i) b[i] = CANARY; }
static int canary_intact(const pf_real *b) { int i; for (i = 0; i < NCAN; ++i) if (b[i] != CANARY) return 0; return 1; }

/* One call: its code must be `want` and the canary output untouched. */
#define EXPECT(call, want)                                                                     \
    do {                                                                                       \
        int rc_;                                                                               \
        canary_fill(o);                                                                        \
        rc_ = (call);                                                                          \
        if (rc_ != (want) || !canary_intact(o)) {                                              \
            bad++;                                                                             \
            printf("    %s: %d (want %d)%s\n", #call, rc_, (want), canary_intact(o) ? "" : ", wrote"); \
        }                                                                                      \
    } while (0)

/* NULL pointers, unknown border values and depth kinds, sizes and counts below the minimum:
   PF_ERR_ARG and nothing written; the counts return 0; the typed samplers return zeros (ESM:
   -PF_REAL_MAX). */
static void edge_issue19_bad_arguments(void)
{
    pf_real in[NCAN], o[NCAN], wt[4] = {1, 1, 1, 1};
    const pf_real one = PF_R(1.0), half = PF_R(0.5);
    /* NULL outputs through a volatile pointer: gcc -O3 -Warray-bounds otherwise walks the rejected
       paths' stores into a NULL-based 0-size array (the matrix cells mx-gcc-c11-O3, mx-g++-c++20-O3) */
    pf_real *volatile null_out = NULL;
    int bad = 0, i;
    for (i = 0; i < NCAN; ++i) in[i] = PF_R(0.25) * (pf_real)(i % 5);
    EXPECT(pf_mip_build(NULL, 2, 2, 1), PF_ERR_ARG);
    EXPECT(pf_mip_build(o, 0, 2, 1), PF_ERR_ARG);
    EXPECT(pf_mip_build(o, 2, -1, 1), PF_ERR_ARG);
    EXPECT(pf_mip_build(o, 2, 2, 0), PF_ERR_ARG);
    EXPECT(pf_mip_build_log(NULL, 2, 2, 1), PF_ERR_ARG);
    EXPECT(pf_mip_build_log(o, 2, 2, -3), PF_ERR_ARG);
    EXPECT(pf_slope_moments_map_from_heights(NULL, 2, 2, one, one, one, PF_BORDER_WRAP, o), PF_ERR_ARG);
    EXPECT(pf_slope_moments_map_from_heights(in, 2, 2, one, one, one, PF_BORDER_WRAP, NULL), PF_ERR_ARG);
    EXPECT(pf_slope_moments_map_from_heights(in, 2, 2, one, one, one, 2, o), PF_ERR_ARG);
    EXPECT(pf_slope_moments_map_from_heights(in, 2, 2, one, one, one, -1, o), PF_ERR_ARG);
    EXPECT(pf_slope_moments_map_from_heights(in, 0, 2, one, one, one, PF_BORDER_CLAMP, o), PF_ERR_ARG);
    EXPECT(pf_slope_pyramid_from_heights(NULL, 2, 2, one, one, one, PF_BORDER_WRAP, o), PF_ERR_ARG);
    EXPECT(pf_slope_pyramid_from_heights(in, 2, 2, one, one, one, PF_BORDER_WRAP, NULL), PF_ERR_ARG);
    EXPECT(pf_slope_pyramid_from_heights(in, 2, 2, one, one, one, 7, o), PF_ERR_ARG);
    EXPECT(pf_slope_pyramid_from_heights(in, 2, 0, one, one, one, PF_BORDER_CLAMP, o), PF_ERR_ARG);
    EXPECT(pf_depth_pyramid_from_depths(NULL, 2, 2, PF_DEPTH_VSM, one, one, o), PF_ERR_ARG);
    EXPECT(pf_depth_pyramid_from_depths(in, 2, 2, PF_DEPTH_VSM, one, one, null_out), PF_ERR_ARG);
    EXPECT(pf_depth_pyramid_from_depths(in, 2, 2, 99, one, one, o), PF_ERR_ARG);
    EXPECT(pf_depth_pyramid_from_depths(in, 2, 2, -1, one, one, o), PF_ERR_ARG);
    EXPECT(pf_scalar_pyramid_from_values(NULL, 2, 2, o), PF_ERR_ARG);
    EXPECT(pf_scalar_pyramid_from_values(in, 2, 2, null_out), PF_ERR_ARG);
    EXPECT(pf_normal_pyramid_from_normals(NULL, 2, 2, o), PF_ERR_ARG);
    EXPECT(pf_normal_pyramid_from_normals(in, -2, 2, o), PF_ERR_ARG);
    EXPECT(pf_moments_weighted_mean(NULL, 1, wt, 4, o), PF_ERR_ARG);
    EXPECT(pf_moments_weighted_mean(in, 1, NULL, 4, o), PF_ERR_ARG);
    EXPECT(pf_moments_weighted_mean(in, 0, wt, 4, o), PF_ERR_ARG);
    EXPECT(pf_moments_weighted_mean(in, 1, wt, -1, o), PF_ERR_ARG);
    EXPECT(pf_mip_sample_bilinear(NULL, 2, 2, 1, 0, half, half, PF_BORDER_WRAP, o), PF_ERR_ARG);
    EXPECT(pf_mip_sample_bilinear(in, 2, 2, 1, 0, half, half, 2, o), PF_ERR_ARG);
    EXPECT(pf_mip_sample_bilinear(in, 2, 2, 0, 0, half, half, PF_BORDER_CLAMP, o), PF_ERR_ARG);
    EXPECT(pf_mip_sample_trilinear(in, 0, 0, 1, half, half, half, PF_BORDER_WRAP, o), PF_ERR_ARG);
    EXPECT(pf_mip_sample_trilinear(in, 2, 2, 1, half, half, half, -1, o), PF_ERR_ARG);
    EXPECT(pf_mip_sample_bilinear_log(in, 2, 2, 1, 0, half, half, 3, o), PF_ERR_ARG);
    EXPECT(pf_mip_sample_trilinear_log(NULL, 2, 2, 1, half, half, half, PF_BORDER_WRAP, o), PF_ERR_ARG);
    bad += pf_mip_sample_bilinear(in, 2, 2, 1, 0, half, half, PF_BORDER_WRAP, NULL) != PF_ERR_ARG;
    bad += pf_mip_texel_count(0, 3) != 0 || pf_mip_texel_count(3, -1) != 0;
    { /* typed samplers: zeros (ESM: -PF_REAL_MAX) */
        pf_slope_moments m = pf_slope_moments_sample(in, 2, 2, half, half, half, 5);
        pf_vec3 nrm = pf_normal_avg_sample(NULL, 2, 2, half, half, half, PF_BORDER_WRAP);
        pf_evsm_moments e = pf_evsm_moments_sample(in, 0, 2, half, half, half, PF_BORDER_WRAP);
        bad += !(m.ex == 0 && m.ey == 0 && m.exx == 0 && m.eyy == 0 && m.exy == 0);
        bad += !(nrm.x == 0 && nrm.y == 0 && nrm.z == 0) || !(e.pos1 == 0 && e.neg2 == 0);
        bad += pf_scalar_moments_sample(in, 2, 2, half, half, half, 9).m2 != 0;
        bad += pf_depth_moments2_sample(in, 2, 2, half, half, half, -4).m1 != 0;
        bad += pf_depth_moments4_sample(in, 2, 2, half, half, half, 2).m4 != 0;
        bad += pf_esm_log_sample(in, 2, 2, half, half, half, 2) != -PF_REAL_MAX;
        bad += pf_esm_log_sample(NULL, 2, 2, half, half, half, PF_BORDER_CLAMP) != -PF_REAL_MAX;
    }
    bad += pf_esm_log_weighted_mean(NULL, wt, 4) != -PF_REAL_MAX || pf_esm_log_weighted_mean(in, NULL, 4) != -PF_REAL_MAX;
    bad += pf_esm_log_weighted_mean(in, wt, -1) != -PF_REAL_MAX;
    /* valid calls still return PF_OK */
    bad += pf_mip_sample_bilinear(in, 2, 2, 1, 0, half, half, PF_BORDER_WRAP, o) != PF_OK;
    bad += pf_moments_weighted_mean(in, 2, wt, 0, o) != PF_OK || o[0] != 0 || o[1] != 0;
    PF_CHECK(bad == 0, "%d failures", bad);
}

/* Sizes above the limits: PF_ERR_SIZE, found before anything is read or written (the
   buffers here are tiny canaries; a function that used them would write past them, which
   ASan reports). Reproducers 2 (h = INT_MAX in the slope-map walkers), 3 and 4 (INT_MAX
   axes in the samplers) now stop here; their largest accepted sizes are exercised in
   test_issue19_largest_sizes_guarded. */
static void edge_issue19_huge_sizes_rejected(void)
{
    pf_real in_buf[NCAN], o_buf[NCAN], wt[4] = {1, 1, 1, 1};
    /* through volatile pointers: gcc -O3 would otherwise follow the (rejected) huge sizes into
       the loops and warn that they run past these small arrays (-Warray-bounds) */
    pf_real *volatile in_v = in_buf, *volatile o_v = o_buf;
    pf_real *in = in_v, *o = o_v;
    const pf_real one = PF_R(1.0), half = PF_R(0.5);
    const int big = (int)PF_MAX_SIDE + 1, side = (int)PF_MAX_SIDE;
    int bad = 0, border, i;
    for (i = 0; i < NCAN; ++i) in[i] = PF_R(0.5);
    for (border = 0; border < 2; ++border) {
        EXPECT(pf_slope_moments_map_from_heights(in, 1, INT_MAX, one, one, one, border, o), PF_ERR_SIZE);
        EXPECT(pf_slope_moments_map_from_heights(in, INT_MAX, 1, one, one, one, border, o), PF_ERR_SIZE);
        EXPECT(pf_slope_pyramid_from_heights(in, 1, INT_MAX, one, one, one, border, o), PF_ERR_SIZE);
        EXPECT(pf_slope_pyramid_from_heights(in, big, 1, one, one, one, border, o), PF_ERR_SIZE);
        EXPECT(pf_mip_sample_bilinear(in, 1, INT_MAX, 1, 0, half, half, border, o), PF_ERR_SIZE);
        EXPECT(pf_mip_sample_bilinear(in, 1, INT_MAX, 1, 0, half, one, border, o), PF_ERR_SIZE);
        EXPECT(pf_mip_sample_trilinear(in, INT_MAX, INT_MAX, 1, half, half, half, border, o), PF_ERR_SIZE);
        EXPECT(pf_mip_sample_trilinear_log(in, big, 1, 1, half, half, half, border, o), PF_ERR_SIZE);
        EXPECT(pf_mip_sample_bilinear_log(in, 1, big, 1, 0, half, half, border, o), PF_ERR_SIZE);
        bad += pf_slope_moments_sample(in, 1, INT_MAX, half, half, half, border).ex != 0;
        bad += pf_esm_log_sample(in, big, big, half, half, half, border) != -PF_REAL_MAX;
    }
    EXPECT(pf_mip_build(o, big, 1, 1), PF_ERR_SIZE);
    EXPECT(pf_mip_build(o, 1, big, 1), PF_ERR_SIZE);
    EXPECT(pf_mip_build(o, side, side, 1), PF_ERR_SIZE);     /* sides fine, > PF_MAX_REALS reals */
    EXPECT(pf_mip_build(o, 1 << 20, 1 << 20, 1), PF_ERR_SIZE);
    EXPECT(pf_mip_build(o, 1 << 19, 1 << 19, INT_MAX), PF_ERR_SIZE);
    EXPECT(pf_mip_build(o, 1 << 12, 1 << 12, 1 << 20), PF_ERR_SIZE); /* 2^44 reals */
    EXPECT(pf_mip_build_log(o, INT_MAX, INT_MAX, 1), PF_ERR_SIZE);
    EXPECT(pf_depth_pyramid_from_depths(in, side, side, PF_DEPTH_MSM, one, one, o), PF_ERR_SIZE);
    EXPECT(pf_depth_pyramid_from_depths(in, INT_MAX, 1, PF_DEPTH_ESM_LOG, one, one, o), PF_ERR_SIZE);
    EXPECT(pf_scalar_pyramid_from_values(in, 1, INT_MAX, o), PF_ERR_SIZE);
    EXPECT(pf_normal_pyramid_from_normals(in, big, big, o), PF_ERR_SIZE);
    EXPECT(pf_moments_weighted_mean(in, INT_MAX, wt, INT_MAX, o), PF_ERR_SIZE);
    bad += pf_mip_texel_count(big, 1) != 0 || pf_mip_texel_count(INT_MAX, INT_MAX) != 0;
    bad += pf_mip_texel_count(side, side) != 0 || pf_mip_texel_count(1 << 20, 1 << 20) != 0;
    bad += pf_mip_texel_count(side, 1) != 2LL * side - 1;
    /* 2^19 x 2^19 (3.7e11 texels) fits the 64-bit limit (2^40), not a 32-bit host's (2^28) */
    bad += (pf_mip_texel_count(1 << 19, 1 << 19) > 0) != (PF_MAX_REALS >= (1LL << 40));
    PF_CHECK(bad == 0, "%d failures", bad);
}

/* The largest accepted sizes, in guarded mappings of exactly the documented size (a read
   past either end faults): samplers read a handful of texels, so a 1 x 2^24 pyramid, a
   2^24 x 1 one and a 2^19 x 2^19 one (1.5 TB of address space in float, mostly never
   touched) cost nothing. Reproducer 4 at the largest accepted height: v = 1 under CLAMP
   reads row h - 1 (the float build used to overflow the float-to-int conversion and read row
   0); reproducer 3: WRAP at the first texel blends it with the last one. Then a build at
   the largest side (w = 2^24, h = 1) and the slope-map walker's wrapped rows (reproducer 2)
   on a guarded 1 x 2^16 map. */
static void test_issue19_largest_sizes_guarded(void)
{
    static const int dims[3][2] = {{1, (int)PF_MAX_SIDE}, {(int)PF_MAX_SIDE, 1}, {1 << 19, 1 << 19}};
    int bad = 0, d, mapped = 0;
    for (d = 0; d < 3; ++d) {
        int w = dims[d][0], h = dims[d][1], border;
        long long n = pf_mip_texel_count(w, h), last = (long long)(h - 1) * w + (w - 1);
        size_t bytes = (size_t)n * sizeof(pf_real);
        pf_real *pyr = n > 0 ? (pf_real *)pf_test_guarded_alloc(bytes) : NULL, o[2];
        const pf_real one = PF_R(1.0), zero = PF_R(0.0);
        if (!pyr) {
            pf_test_note("%d x %d: mapping of %.3g bytes unavailable, skipped", w, h, (double)bytes);
            continue;
        }
        ++mapped;
        pyr[0] = PF_R(10.0);
        pyr[last] = PF_R(40.0); /* the opposite corner of level 0 */
        pyr[n - 1] = PF_R(7.0); /* the 1 x 1 top, the mapping's last pf_real */
        for (border = 0; border < 2; ++border) {
            /* the corner texel's centre and its far corner (1, 1) */
            pf_real u0 = PF_R(0.5) / (pf_real)w, v0 = PF_R(0.5) / (pf_real)h;
            bad += pf_mip_sample_bilinear(pyr, w, h, 1, 0, u0, v0, border, o) != PF_OK || o[0] != PF_R(10.0);
            bad += pf_mip_sample_bilinear(pyr, w, h, 1, 99, u0, v0, border, o) != PF_OK || o[0] != PF_R(7.0);
            bad += pf_mip_sample_trilinear(pyr, w, h, 1, PF_R(1e30), one, one, border, o) != PF_OK || o[0] != PF_R(7.0);
            bad += pf_mip_sample_trilinear(pyr, w, h, 1, PF_R(0.5), one, one, border, o) != PF_OK || !pf_test_finite(o[0]);
            bad += pf_mip_sample_trilinear_log(pyr, w, h, 1, PF_R(0.5), zero, one, border, o) != PF_OK || !pf_test_finite(o[0]);
        }
        /* CLAMP at (1, 1), at coordinates beyond it and at +inf: the last texel */
        bad += pf_mip_sample_bilinear(pyr, w, h, 1, 0, one, one, PF_BORDER_CLAMP, o) != PF_OK || o[0] != PF_R(40.0);
        bad += pf_mip_sample_bilinear(pyr, w, h, 1, 0, PF_R(3e7), PF_R(1e30), PF_BORDER_CLAMP, o) != PF_OK || o[0] != PF_R(40.0);
        bad += pf_mip_sample_bilinear(pyr, w, h, 1, 0, (pf_real)INFINITY, (pf_real)INFINITY, PF_BORDER_CLAMP, o) != PF_OK || o[0] != PF_R(40.0);
        /* WRAP at (0, 0): the four corner texels, a quarter each (a 1-texel axis has weight 1) */
        bad += pf_mip_sample_bilinear(pyr, w, h, 1, 0, zero, zero, PF_BORDER_WRAP, o) != PF_OK;
        bad += fabsl((long double)o[0] - ((w == 1 || h == 1) ? 25.0L : 12.5L)) > 1e-5L;
        pf_test_guarded_free(pyr, bytes);
    }
    { /* pf_mip_build at the largest side: level 0 untouched zeros except two texels */
        const int w = (int)PF_MAX_SIDE;
        long long n = pf_mip_texel_count(w, 1);
        size_t bytes = (size_t)n * sizeof(pf_real);
        pf_real *pyr = (pf_real *)pf_test_guarded_alloc(bytes);
        if (pyr) {
            pyr[0] = (pf_real)w;
            pyr[w - 1] = (pf_real)w;
            bad += pf_mip_build(pyr, w, 1, 1) != PF_OK;
            bad += fabsl((long double)pyr[n - 1] - 2.0L) > 1e-5L; /* the mean, 2w / w */
            pf_test_guarded_free(pyr, bytes);
        } else pf_test_note("build 2^24 x 1 skipped (no mapping)");
    }
    { /* reproducer 2 at an accepted size: the wrapped neighbours of rows 0 and h - 1 */
        const int h = 1 << 16;
        pf_real *hm = (pf_real *)pf_test_guarded_alloc((size_t)h * sizeof(pf_real));
        pf_real *out = (pf_real *)pf_test_guarded_alloc((size_t)h * 5 * sizeof(pf_real));
        if (hm && out) {
            int r;
            for (r = 0; r < h; ++r) hm[r] = (pf_real)(r % 7);
            bad += pf_slope_moments_map_from_heights(hm, 1, h, PF_R(1.0), PF_R(0.5), PF_R(1.0), PF_BORDER_WRAP, out) != PF_OK;
            bad += out[1] != (hm[1] - hm[h - 1]) / PF_R(1.0) || out[(h - 1) * 5 + 1] != (hm[0] - hm[h - 2]) / PF_R(1.0);
            bad += out[0] != PF_R(0.0);
        } else pf_test_note("slope map skipped (no mapping)");
        if (hm) pf_test_guarded_free(hm, (size_t)h * sizeof(pf_real));
        if (out) pf_test_guarded_free(out, (size_t)h * 5 * sizeof(pf_real));
    }
    pf_test_note("%d of 3 huge pyramids mapped and sampled", mapped);
    PF_CHECK(bad == 0, "%d failures", bad);
}

/* Finding 6: CLAMP treated |u| >= 1e6 as u = 0 (u = 2e6 gave the left edge of the ramp
   {10, 20, 30, 40}, u = 999999 the right one). Now every u beyond the edge clamps to it,
   infinities too; NaN is 0. WRAP keeps u - floor(u) in pf_real: huge u wrap exactly (an
   integer u, every u >= 2^24 in float, is 0), infinities and NaN are 0. */
static void test_issue19_huge_coordinates(void)
{
    pf_real ramp[7 * 2], o[2];
    int bad = 0, i;
    for (i = 0; i < 4; ++i) {
        ramp[2 * i] = PF_R(10.0) * (pf_real)(i + 1);
        ramp[2 * i + 1] = ramp[2 * i] * ramp[2 * i];
    }
    pf_mip_build(ramp, 4, 1, 2);
#define AT(u, border) (pf_mip_sample_bilinear(ramp, 4, 1, 2, 0, (pf_real)(u), PF_R(0.5), border, o) == PF_OK ? o[0] : PF_R(-1.0))
    bad += AT(2e6, PF_BORDER_CLAMP) != PF_R(40.0);
    bad += AT(999999.0, PF_BORDER_CLAMP) != PF_R(40.0);
    bad += AT(1e30, PF_BORDER_CLAMP) != PF_R(40.0) || AT(INFINITY, PF_BORDER_CLAMP) != PF_R(40.0);
    bad += AT(-2e6, PF_BORDER_CLAMP) != PF_R(10.0) || AT(-INFINITY, PF_BORDER_CLAMP) != PF_R(10.0);
    bad += AT(NAN, PF_BORDER_CLAMP) != PF_R(10.0);
    bad += AT(2000000.375, PF_BORDER_WRAP) != PF_R(20.0); /* = u 0.375: texel 1's centre */
    bad += AT(-2000000.625, PF_BORDER_WRAP) != PF_R(20.0);
    bad += AT(1e30, PF_BORDER_WRAP) != PF_R(25.0) || AT(INFINITY, PF_BORDER_WRAP) != PF_R(25.0); /* u = 0 */
    bad += AT(NAN, PF_BORDER_WRAP) != PF_R(25.0);
    bad += pf_scalar_moments_sample(ramp, 4, 1, PF_R(0.0), PF_R(5e6), PF_R(0.5), PF_BORDER_CLAMP).m1 != PF_R(40.0);
#undef AT
    PF_CHECK(bad == 0, "%d failures", bad);
}

/* Finding 7: weights {MAX, MAX} summed to inf, so the normalized weights were 0 (mean 0) and
   the ESM log-sum-exp NaN. Weights are now divided by the largest first. An infinite weight
   is a bad argument (PF_ERR_ARG, -PF_REAL_MAX). */
static void test_issue19_weighted_mean_huge_weights(void)
{
    pf_real t[4] = {1, 1, 0, 3}, w2[2] = {PF_REAL_MAX, PF_REAL_MAX}, w3[2] = {PF_REAL_MAX, PF_REAL_MAX / PF_R(2.0)};
    pf_real winf[2] = {PF_R(1.0), (pf_real)INFINITY}, o[NCAN];
    pf_real l = pf_esm_log_weighted_mean(t, w2, 2);
    int bad = 0;
    bad += pf_moments_weighted_mean(t, 1, w2, 2, o) != PF_OK || o[0] != PF_R(1.0);
    bad += pf_moments_weighted_mean(t, 2, w2, 2, o) != PF_OK || fabsl((long double)o[0] - 0.5L) > 4.0L * PF_TEST_EPS || fabsl((long double)o[1] - 2.0L) > 8.0L * PF_TEST_EPS;
    bad += pf_moments_weighted_mean(t + 2, 1, w3, 2, o) != PF_OK || fabsl((long double)o[0] - 1.0L) > 4.0L * PF_TEST_EPS;
    bad += !(fabsl((long double)l - 1.0L) <= 4.0L * PF_TEST_EPS);
    l = pf_esm_log_weighted_mean(t + 2, w3, 2); /* log((2 + e^3) / 3) */
    bad += !(fabsl((long double)l - logl((2.0L + expl(3.0L)) / 3.0L)) <= 8.0L * PF_TEST_EPS);
    canary_fill(o);
    bad += pf_moments_weighted_mean(t, 1, winf, 2, o) != PF_ERR_ARG || !canary_intact(o);
    bad += pf_esm_log_weighted_mean(t, winf, 2) != -PF_REAL_MAX;
    PF_CHECK(bad == 0, "%d failures (ESM log mean %g)", bad, (double)pf_esm_log_weighted_mean(t, w2, 2));
}

/* Finding 9: a level of -PF_REAL_MAX everywhere reduced to -inf at odd sizes (3x3: the nine
   rounded weights 1/9 sum to a little more than 1). Every level of such pyramids is now
   finite and equal to the value to a few ulps, and so are their bilinear and trilinear
   samples. */
static void test_issue19_build_near_max_finite(void)
{
    static const int dims[][2] = {{3, 3}, {3, 1}, {1, 3}, {5, 5}, {7, 3}, {9, 9}, {6, 5}, {2, 3}};
    int bad = 0, d, sgn;
    long double worst = 0.0L;
    for (d = 0; d < 8; ++d)
        for (sgn = -1; sgn <= 1; sgn += 2) {
            int w = dims[d][0], h = dims[d][1], k, border;
            long long n = pf_mip_texel_count(w, h), i;
            pf_real *pyr = alloc_real(n * 2), v = (pf_real)sgn * PF_REAL_MAX, o[2];
            for (i = 0; i < (long long)w * h * 2; ++i) pyr[i] = v;
            bad += pf_mip_build(pyr, w, h, 2) != PF_OK;
            for (i = 0; i < n * 2; ++i) {
                long double e = fabsl((long double)pyr[i] - (long double)v) / (long double)PF_REAL_MAX;
                bad += !pf_test_finite(pyr[i]);
                if (e > worst) worst = e;
            }
            for (border = 0; border < 2; ++border)
                for (k = 0; k < 8; ++k) {
                    pf_real u = PF_R(0.13) * (pf_real)k, lod = PF_R(0.37) * (pf_real)k;
                    bad += pf_mip_sample_trilinear(pyr, w, h, 2, lod, u, PF_R(1.0) - u, border, o) != PF_OK;
                    bad += !pf_test_finite(o[0]) || !pf_test_finite(o[1]);
                }
            free(pyr);
        }
    pf_test_note("all +-PF_REAL_MAX levels: relative error <= %.2Lf eps", worst / PF_TEST_EPS);
    PF_CHECK(bad == 0, "%d non-finite or failed", bad);
    PF_CHECK(worst <= 4.0L * PF_TEST_EPS, "%Lg eps", worst / PF_TEST_EPS);
}

/* Finding 7 in every build, -ffast-math included (there the compiler turns w / wmax into
   w * (1/wmax), subnormal and flushed to 0 in float, and folds two divisions into one whose
   divisor overflows): weights at PF_REAL_MAX, alone and mixed with ordinary ones, give the
   plain mean to a few ulps. */
static void edge_issue19_weighted_mean_huge_weights(void)
{
    pf_real t[8] = {1, 1, 1, 1, 1, 1, 1, 1}, w2[2] = {PF_REAL_MAX, PF_REAL_MAX}, o[1];
    pf_real w8[8] = {PF_R(1e-30), PF_REAL_MAX, PF_R(0.615), PF_R(0.896), PF_R(0.621), PF_R(0.198),
                     PF_REAL_MAX, PF_R(0.92)};
    pf_real tt[3] = {2, 4, 100}, wt[3] = {PF_R(1e-30), PF_R(3e-30), PF_R(0.0)};
    int bad = 0;
    bad += pf_moments_weighted_mean(t, 1, w2, 2, o) != PF_OK || !(PF_FABS(o[0] - PF_R(1.0)) <= PF_R(4.0) * PF_REAL_EPSILON);
    bad += pf_moments_weighted_mean(t, 1, w8, 8, o) != PF_OK || !(PF_FABS(o[0] - PF_R(1.0)) <= PF_R(8.0) * PF_REAL_EPSILON);
    bad += pf_moments_weighted_mean(tt, 1, wt, 3, o) != PF_OK || !(PF_FABS(o[0] - PF_R(3.5)) <= PF_R(16.0) * PF_REAL_EPSILON);
    bad += !(PF_FABS(pf_esm_log_weighted_mean(t, w2, 2) - PF_R(1.0)) <= PF_R(4.0) * PF_REAL_EPSILON);
    bad += !(PF_FABS(pf_esm_log_weighted_mean(t, w8, 8) - PF_R(1.0)) <= PF_R(8.0) * PF_REAL_EPSILON);
    PF_CHECK(bad == 0, "%d failures", bad);
}

/* Even-size box levels under every build, -ffast-math included (which factors the four
   products into one overflowing sum): texels of +-PF_REAL_MAX mixed at random, and an EVSM-4
   depth pyramid at the largest float exponent (second moments 1.65e38), stay finite and within
   their level 0 range. */
static void edge_issue19_box_near_max_finite(void)
{
    int w = 24, h = 36, bad = 0;
    long long n = pf_mip_texel_count(w, h), i;
    pf_real *pyr = alloc_real(n * 4), *z = alloc_real((long long)w * h);
    unsigned s = 12345u;
    for (i = 0; i < (long long)w * h; ++i) {
        s = s * 1103515245u + 12345u;
        pyr[i] = ((s >> 16) & 1u) ? PF_REAL_MAX : -PF_REAL_MAX;
        z[i] = PF_R(1.0);
    }
    bad += pf_mip_build(pyr, w, h, 1) != PF_OK;
    for (i = 0; i < n; ++i) bad += !(pyr[i] <= PF_REAL_MAX && pyr[i] >= -PF_REAL_MAX);
    bad += pf_depth_pyramid_from_depths(z, w, h, PF_DEPTH_EVSM4, PF_EVSM_EXP_MAX_F32, PF_EVSM_EXP_MAX_F32, pyr) != PF_OK;
    for (i = 0; i < n * 4; ++i) bad += !(pyr[i] <= PF_REAL_MAX && pyr[i] >= -PF_REAL_MAX);
    free(pyr);
    free(z);
    PF_CHECK(bad == 0, "%d non-finite texels or failed builds", bad);
}

/* The stability sweep's -ffast-math finding: weights of PF_REAL_MAX next to ordinary ones, and
   the largest log carried by an ordinary weight, make sum / weight subnormal; flushed to 0 it
   gave log(0) = -inf. Against the log-sum-exp in long double. */
static void edge_esm_log_mean_tiny_share(void)
{
    pf_real w[11] = {PF_R(0.4422), PF_R(0.2661), PF_R(0.2189), PF_REAL_MAX, PF_REAL_MAX, PF_R(0.0),
                     PF_R(0.5333), PF_R(0.0), PF_R(0.1927), PF_R(0.5567), PF_R(0.4227)};
    pf_real l[11] = {PF_R(11.4776), PF_R(-3.25003), PF_R(13.1511), PF_R(9.00505e-10), PF_R(12.194),
                     PF_R(979.734), PF_R(2342.93), PF_R(-433.901), PF_R(-6.24934e-10), PF_R(-684.021),
                     PF_R(3332.54)};
    long double m = -1e30L, s = 0.0L, ws = 0.0L, want;
    pf_real got = pf_esm_log_weighted_mean(l, w, 11);
    int i;
    for (i = 0; i < 11; ++i)
        if (w[i] > 0 && (long double)l[i] > m) m = (long double)l[i];
    for (i = 0; i < 11; ++i)
        if (w[i] > 0) {
            s += (long double)w[i] * expl((long double)l[i] - m);
            ws += (long double)w[i];
        }
    want = m + logl(s / ws);
    pf_test_note("got %.9g, want %.9Lg", (double)got, want);
    PF_CHECK(pf_test_finite(got) && fabsl((long double)got - want) <= 16.0L * PF_TEST_EPS * fabsl(want),
             "got %g, want %Lg", (double)got, want);
}

/* NaN weights are skipped like weights <= 0 (the fuzzer's finding after the ESM mean was
   rewritten: a NaN weight made the largest weight NaN); NaN logs with a positive weight
   propagate. */
static void test_esm_log_mean_nan_weight(void)
{
    volatile pf_real zero = PF_R(0.0);
    pf_real nan = zero / zero;
    pf_real w[6] = {PF_R(0.4556), PF_R(-0.41), PF_R(1e-30), PF_R(0.4928), nan, PF_R(0.0)};
    pf_real l[6] = {PF_R(1.0), PF_R(5.0), PF_R(2.0), PF_R(3.0), PF_R(4.0), PF_R(6.0)};
    long double s = 0.0L, ws = 0.0L, want;
    pf_real got = pf_esm_log_weighted_mean(l, w, 6), o[1] = {0};
    int i;
    for (i = 0; i < 6; ++i)
        if (w[i] > 0) {
            s += (long double)w[i] * expl((long double)l[i]);
            ws += (long double)w[i];
        }
    want = logl(s / ws);
    PF_CHECK(pf_test_finite(got) && fabsl((long double)got - want) <= 16.0L * PF_TEST_EPS * fabsl(want),
             "ESM log mean with a NaN weight: %g, want %Lg", (double)got, want);
    PF_CHECK(pf_moments_weighted_mean(l, 1, w, 6, o) == PF_OK && pf_test_finite(o[0]),
             "weighted mean with a NaN weight: %g", (double)o[0]);
    l[0] = nan;
    PF_CHECK(!pf_test_finite(pf_esm_log_weighted_mean(l, w, 6)), "a NaN log of positive weight must propagate");
}

/* ---------------------------------------------------------------- LEADR from a trilinear sample
   Issue 15 item 6 (bench/pictures.c, pic_plane): LEADR returned 0 at lit pixels of the plane,
   black dashes in the middle distance. These are the trilinear moments fetched at two of them
   (pixels (317, 65) and (244, 71) of the 400 x 250 picture, lod 5.61 and 4.96), with the
   pixels' view and light. The footprint's mean slope tilts its mean plane above the grazing
   view (A_o = w_o.z - E[x] w_o.x - E[y] w_o.y = -0.022 and -0.0005 at w_o.z = 0.069 and
   0.089), while the reference, a box of texels of the flat macrosurface whose own mean plane
   the view clears, sees the facets facing the viewer; pf_leadr_specular culled A_o <= 0, as
   LEADR sec. 4.3 does for displaced geometry. The oracle: eq. 17, F D G2 / (4 A_o) with Smith's
   Lambda in closed form, where A_o > 0; on and below the mean plane, the radiance of the facets
   that face the viewer, F D / (4 P_o), P_o = E[max(0, w_o.z - x w_o.x - y w_o.y)] integrated
   over the slope Gaussian (2D quadrature), whose identity P_o = A_o (1 + Lambda_o) above the
   mean plane is checked too. A sweep of view elevations through the mean plane (light fixed)
   must never give 0 and must follow the oracle on both sides. */
typedef struct { long double mx, my, vx, vy, c, wx, wy, wz; } front_area_ctx;

static front_area_ctx front_area_make(pf_slope_stats s, long double wx, long double wy, long double wz)
{
    front_area_ctx f;
    f.mx = (long double)s.mean_x; f.my = (long double)s.mean_y;
    f.vx = (long double)s.var_x; f.vy = (long double)s.var_y; f.c = (long double)s.cov_xy;
    f.wx = wx; f.wy = wy; f.wz = wz;
    return f;
}

static long double front_area_integrand(long double x, long double y, void *ctx)
{
    const front_area_ctx *f = (const front_area_ctx *)ctx;
    long double a = f->wz - x * f->wx - y * f->wy;
    return a > 0.0L ? a * pf_oracle_normal2_pdf(x - f->mx, y - f->my, f->vx, f->vy, f->c) : 0.0L;
}

static int front_area_ypoints(long double x, long double *pts, int max_points, void *ctx)
{
    const front_area_ctx *f = (const front_area_ctx *)ctx;
    if (max_points < 2) return 0;
    pts[0] = (f->wz - x * f->wx) / f->wy; /* the kink, facets seen edge-on (w.y != 0 here) */
    pts[1] = f->my;
    return 2;
}

/* P by quadrature; *ok = 0 when it did not converge. */
static long double front_area_quad(front_area_ctx f, int *ok)
{
    pf_oracle_2d pb = pf_oracle_2d_make(front_area_integrand, &f, -HUGE_VALL, HUGE_VALL, -HUGE_VALL, HUGE_VALL);
    pf_oracle_result r;
    pb.xpoints = &f.mx;
    pb.nxpoints = 1;
    pb.ypoints = front_area_ypoints;
    pb.epsrel = 1e-13L;
    r = pf_oracle_integrate_2d(&pb);
    *ok = r.converged;
    return r.value;
}

static long double front_area_nu(front_area_ctx f, long double area)
{
    return area / sqrtl(2.0L * (f.wx * f.wx * f.vx + f.wy * f.wy * f.vy + 2.0L * f.wx * f.wy * f.c));
}

/* The oracle radiance (f0 = 1: no Fresnel) and the signed area A_o; *ok = 0 if the quadrature
   failed. */
static long double leadr_view_oracle(pf_slope_stats s, pf_vec3 wo, pf_vec3 wi, int masking_only,
                                     long double *area_o, int *ok)
{
    front_area_ctx f = front_area_make(s, (long double)wo.x, (long double)wo.y, (long double)wo.z);
    front_area_ctx g = front_area_make(s, (long double)wi.x, (long double)wi.y, (long double)wi.z);
    long double hx = f.wx + g.wx, hy = f.wy + g.wy, hz = f.wz + g.wz;
    long double d, ai = g.wz - g.mx * g.wx - g.my * g.wy;
    *area_o = f.wz - f.mx * f.wx - f.my * f.wy;
    d = pf_oracle_normal2_pdf(-hx / hz - f.mx, -hy / hz - f.my, f.vx, f.vy, f.c) *
        powl((hx * hx + hy * hy + hz * hz) / (hz * hz), 2.0L); /* LEADR eq. 10 */
    *ok = 1;
    if (*area_o <= 0.0L) return d / (4.0L * front_area_quad(f, ok));
    return d / (4.0L * *area_o * (1.0L + pf_oracle_lambda_beckmann(front_area_nu(f, *area_o)) +
                                  (masking_only ? 0.0L : pf_oracle_lambda_beckmann(front_area_nu(g, ai)))));
}

static void test_leadr_trilinear_view_below_mean_plane(void)
{
    static const float mom[2][5] = {
        {-0.0535610877f, -0.0782404244f, 0.152933627f, 0.161369681f, 0.00774230994f},
        {-0.01597175f, -0.088464804f, 0.127252787f, 0.113091312f, 0.0144015793f}};
    static const float view[2][3] = {{-0.319446981f, -0.945094228f, 0.0689238086f},
                                     {-0.126992688f, -0.987906158f, 0.0889620781f}};
    pf_vec3 wi = pf_vec3_make(PF_R(0.163175911), PF_R(0.925416589), PF_R(0.342020154));
    long double worst_below = 0.0L, worst_above = 0.0L, worst_ident = 0.0L;
    int px, k, mo, zeros = 0, below = 0, quad_ok = 1, ok;
    for (px = 0; px < 2; ++px) {
        pf_slope_stats s = pf_slope_moments_stats(
            pf_slope_moments_make((pf_real)mom[px][0], (pf_real)mom[px][1], (pf_real)mom[px][2],
                                  (pf_real)mom[px][3], (pf_real)mom[px][4]), PF_R(0.01));
        long double az = atan2l((long double)view[px][1], (long double)view[px][0]);
        long double el0 = asinl((long double)view[px][2]);
        front_area_ctx f = front_area_make(s, 0.3L, -0.9L, 0.3L);
        long double a = f.wz - f.mx * f.wx - f.my * f.wy, p = front_area_quad(f, &ok), e;
        /* the quadrature against Smith's normalization above the mean plane */
        quad_ok &= ok;
        e = fabsl(p - a * (1.0L + pf_oracle_lambda_beckmann(front_area_nu(f, a)))) / p;
        if (!(e <= worst_ident)) worst_ident = e;
        /* the pixel's own view, then elevations 1 to 9.5 degrees at its azimuth */
        for (k = -1; k < 18; ++k) {
            long double el = k < 0 ? el0 : (1.0L + 0.5L * k) * PF_TEST_PI / 180.0L, area, want;
            pf_vec3 wo = pf_vec3_make((pf_real)(cosl(el) * cosl(az)), (pf_real)(cosl(el) * sinl(az)),
                                      (pf_real)sinl(el));
            for (mo = 0; mo < 2; ++mo) {
                pf_real got = mo ? pf_leadr_specular_masking(wo, wi, s, PF_R(1.0))
                                 : pf_leadr_specular(wo, wi, s, PF_R(1.0));
                want = leadr_view_oracle(s, wo, wi, mo, &area, &ok);
                quad_ok &= ok;
                zeros += !(got > PF_R(0.0));
                e = fabsl((long double)got - want) / want;
                if (area <= 0.0L) {
                    below++;
                    if (!(e <= worst_below)) worst_below = e; /* NaN counts as the worst */
                } else if (!(e <= worst_above))
                    worst_above = e;
            }
        }
    }
    pf_test_note("%d of 76 below the mean plane, %d zeros; rel. error %.2Lg below, %.2Lg above; "
                 "quadrature vs A (1 + Lambda) %.1Lg", below, zeros, worst_below, worst_above, worst_ident);
    PF_CHECK(quad_ok && worst_ident <= 1e-12L, "oracle: quadrature %d, identity %Lg", quad_ok, worst_ident);
    PF_CHECK(below >= 20, "the sweep must cross the mean plane (%d below)", below);
    PF_CHECK(zeros == 0, "%d views above the macrosurface returned 0", zeros);
    PF_CHECK(worst_below <= 32.0L * PF_TEST_EPS, "below the mean plane: %Lg", worst_below);
    PF_CHECK(worst_above <= 32.0L * PF_TEST_EPS, "above the mean plane: %Lg", worst_above);
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_reductions_equal_union_moments);
    PF_TEST_RUN(test_mip_weights_exact);
    PF_TEST_RUN(test_pyramid_matches_reference);
    PF_TEST_RUN(test_sampling_equals_weighted_texels);
    PF_TEST_RUN(test_covariance_valid_after_filtering);
    PF_TEST_RUN(test_esm_log_matches_direct);
    PF_TEST_RUN(test_height_slopes_converge);
    PF_TEST_RUN(test_height_evaluators);
    PF_TEST_RUN(test_map_kinds_top_is_mean);
    PF_TEST_RUN(test_weighted_means);
    PF_TEST_RUN(test_nan_texels_propagate_upward_only);
    PF_TEST_RUN(test_half_storage_variance);
    PF_TEST_RUN(edge_bad_input);
    PF_TEST_RUN(edge_extreme_values);
    PF_TEST_RUN(edge_esm_log_combine2_zero_weight);
    PF_TEST_RUN(edge_evsm_reduce2x2_near_max);
    PF_TEST_RUN(edge_issue19_bad_arguments);
    PF_TEST_RUN(edge_issue19_huge_sizes_rejected);
    PF_TEST_RUN(test_issue19_largest_sizes_guarded);
    PF_TEST_RUN(test_issue19_huge_coordinates);
    PF_TEST_RUN(test_issue19_weighted_mean_huge_weights);
    PF_TEST_RUN(edge_issue19_weighted_mean_huge_weights);
    PF_TEST_RUN(edge_issue19_box_near_max_finite);
    PF_TEST_RUN(edge_esm_log_mean_tiny_share);
    PF_TEST_RUN(test_esm_log_mean_nan_weight);
    PF_TEST_RUN(test_issue19_build_near_max_finite);
    PF_TEST_RUN(test_leadr_trilinear_view_below_mean_plane);
    return PF_TEST_END();
}

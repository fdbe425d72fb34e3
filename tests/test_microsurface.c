/* test_microsurface.c - tests of tests/pf_microsurface.h, the synthetic microsurfaces and the
   brute-force shading reference of the bench report (issue 9).

   The reference is what the library is measured against, so it is checked here against
   things that do not come from it: sample statistics of the generators, the library's own
   slope pyramid (level 0), analytic visibility (a plane, a wall's shadow length), a finely
   sampled continuous surface, Smith's closed-form masking for Gaussian surfaces (Smith 1967;
   tests/pf_oracle.h), the projected-area identity (Dupuy et al. 2013 eq. 1), closed-form
   flat-plane BRDFs written with trigonometry, and the white furnace. Every bound is stated
   next to its check and the measured numbers are printed as notes. edge_* tests (finite,
   in-range outputs at degenerate inputs) also run under -ffast-math. */
#include "pf_beckmann.h"
#include "pf_map.h"
#include "pf_microsurface.h"
#include "pf_oracle.h"
#include "pf_test.h"

static const double pi_d = 3.14159265358979323846;

static void dir_from_angles(double theta, double phi, double w[3])
{
    w[0] = sin(theta) * cos(phi);
    w[1] = sin(theta) * sin(phi);
    w[2] = cos(theta);
}

static double deg(double d) { return d * pi_d / 180.0; }

/* theta uniform in [tmin, tmax), then phi uniform (two statements: argument evaluation order
   differs between compilers, and the sequence must not) */
static void random_dir(pf_test_rng *rng, double tmin, double tmax, double w[3])
{
    double theta = pf_test_uniform(rng, tmin, tmax);
    double phi = pf_test_uniform(rng, -pi_d, pi_d);
    dir_from_angles(theta, phi, w);
}

/* RMS of the slopes along the axes of the frame rotated by (c, sn) = (cos, sin) */
typedef struct {
    double rms_x, rms_y;
} slope_stats;

static slope_stats measure_slopes(const pfm_surface *s, double c, double sn)
{
    slope_stats r;
    double m2x = 0.0, m2y = 0.0, n = (double)s->w * (double)s->h;
    int x, y;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            double sx, sy, u, v;
            pfm_slope(s, x, y, &sx, &sy);
            u = c * sx + sn * sy;
            v = -sn * sx + c * sy;
            m2x += u * u;
            m2y += v * v;
        }
    r.rms_x = sqrt(m2x / n);
    r.rms_y = sqrt(m2y / n);
    return r;
}

/* skewness and kurtosis of the standardized slopes along each axis separately, averaged
   (for ANISO the two axes have different variances) */
static void axis_moments(const pfm_surface *s, double c, double sn, double *skew, double *kurt)
{
    double a2[2] = {0.0, 0.0}, a3[2] = {0.0, 0.0}, a4[2] = {0.0, 0.0}, n = (double)s->w * (double)s->h;
    int x, y, k;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            double sx, sy, t[2];
            pfm_slope(s, x, y, &sx, &sy);
            t[0] = c * sx + sn * sy;
            t[1] = -sn * sx + c * sy;
            for (k = 0; k < 2; ++k) {
                a2[k] += t[k] * t[k];
                a3[k] += t[k] * t[k] * t[k];
                a4[k] += t[k] * t[k] * t[k] * t[k];
            }
        }
    *skew = 0.0;
    *kurt = 0.0;
    for (k = 0; k < 2; ++k) {
        double v = a2[k] / n;
        *skew += 0.5 * (a3[k] / n) / pow(v, 1.5);
        *kurt += 0.5 * (a4[k] / n) / (v * v);
    }
}

/* ------------------------------------------------------------------ generators */

/* RMS slope = target; Gaussian kinds: slope skewness ~ 0, kurtosis ~ 3 within sampling
   error; the non-Gaussian kinds measurably not. Bounds: the slopes of a 512^2 map with
   correlation length L ~ 12 carry ~ 512^2 / (pi L^2) ~ 600 independent samples per axis
   (more for the pooled axes), so the standard errors are ~ sqrt(6/600) = 0.1 for the skewness
   and ~ sqrt(24/600) = 0.2 for the kurtosis; the bounds 0.35 and 0.7 are ~3.5 of them. */
static void test_generator_statistics(void)
{
    int k;
    for (k = 0; k < PFM_KIND_COUNT; ++k) {
        pfm_params p = pfm_params_default(k);
        pfm_surface s;
        double c = 1.0, sn = 0.0, skew, kurt, rms_err;
        slope_stats st;
        int rc = pfm_surface_make(&s, 512, 512, 1.0, p);
        PF_CHECK(rc == 0, "%s: make failed", pfm_kind_name(k));
        if (rc != 0) continue;
        if (k == PFM_GAUSSIAN_ANISO) {
            c = cos(p.angle);
            sn = sin(p.angle);
        }
        st = measure_slopes(&s, c, sn);
        axis_moments(&s, c, sn, &skew, &kurt);
        if (k == PFM_GAUSSIAN_ANISO) {
            /* x axis of the rotated frame exactly; the y/x ratio to the generator's 1e-4 */
            rms_err = fabs(st.rms_x / p.rms_slope - 1.0);
            PF_CHECK(rms_err < 1e-12, "aniso rms_x %.15g target %g", st.rms_x, p.rms_slope);
            PF_CHECK(fabs(st.rms_y / st.rms_x / p.aniso - 1.0) < 2e-4, "aniso ratio %.6g target %g",
                     st.rms_y / st.rms_x, p.aniso);
        } else {
            /* the rescale fixes the mean of the two axis variances exactly; each axis within
               3% (sampling: the two axes of an isotropic field differ by ~1/sqrt(600)) */
            rms_err = fabs(sqrt(0.5 * (st.rms_x * st.rms_x + st.rms_y * st.rms_y)) / p.rms_slope - 1.0);
            PF_CHECK(rms_err < 1e-12, "%s rms %.15g target %g", pfm_kind_name(k),
                     sqrt(0.5 * (st.rms_x * st.rms_x + st.rms_y * st.rms_y)), p.rms_slope);
            PF_CHECK(fabs(st.rms_x / p.rms_slope - 1.0) < 0.03 && fabs(st.rms_y / p.rms_slope - 1.0) < 0.03,
                     "%s per-axis rms %g %g target %g", pfm_kind_name(k), st.rms_x, st.rms_y, p.rms_slope);
        }
        if (k == PFM_GAUSSIAN || k == PFM_GAUSSIAN_ANISO || k == PFM_GAUSSIAN_FINE) {
            PF_CHECK(fabs(skew) < 0.35 && fabs(kurt - 3.0) < 0.7, "%s skew %g kurt %g", pfm_kind_name(k),
                     skew, kurt);
        } else {
            /* non-Gaussian by construction: kurtosis at least 4.5 (ridges ~8, craters ~10: the
               slope-0 atom of the flat ground; tiles ~5: slopes on a few values) */
            PF_CHECK(kurt > 4.5, "%s kurt %g (expected clearly non-Gaussian)", pfm_kind_name(k), kurt);
        }
        if (k == PFM_PEAKED) {
            /* the photographed-texture regime of issue 18: kurtosis 4-6 (3 exp(4 a^2) = 5.1
               for a smooth field; standard error ~0.3 at L = 6), symmetric, and unimodal:
               the histogram of the x slopes in bins of half an RMS falls away from the
               central bin on both sides (5% slack for sampling noise) */
            long bins[16];
            int b, x, y, mono = 1;
            PF_CHECK(kurt > 4.0 && kurt < 6.0 && fabs(skew) < 0.35, "peaked kurt %g skew %g", kurt, skew);
            memset(bins, 0, sizeof bins);
            for (y = 0; y < s.h; ++y)
                for (x = 0; x < s.w; ++x) {
                    double sx, sy;
                    pfm_slope(&s, x, y, &sx, &sy);
                    b = (int)floor(sx / (0.5 * st.rms_x)) + 8;
                    if (b >= 0 && b < 16) bins[b]++;
                }
            for (b = 8; b < 15; ++b) mono &= bins[b + 1] <= bins[b] * 105 / 100;
            for (b = 7; b > 0; --b) mono &= bins[b - 1] <= bins[b] * 105 / 100;
            PF_CHECK(mono, "peaked: x-slope histogram not unimodal (%ld %ld %ld %ld | %ld %ld %ld %ld)", bins[4],
                     bins[5], bins[6], bins[7], bins[8], bins[9], bins[10], bins[11]);
        }
        pf_test_note("%s rms %.3f/%.3f skew %.2f kurt %.2f", pfm_kind_name(k), st.rms_x, st.rms_y, skew,
                     kurt);
        pfm_surface_free(&s);
    }
}

/* The fine Gaussian kind puts many features in a footprint: the slope variance inside a
   footprint (about its own mean), averaged over the footprints, is the fraction of the map's
   slope variance a filtered model of the footprint sees as roughness (the rest is the spread
   of the footprints' mean slopes, resolved geometry). For the fine kind (3-texel correlation
   length, ~145 correlation areas pi L^2 in 64 x 64 texels) it must be >= 0.9 at 64 x 64 and
   above the default Gaussian kind's (12 texels) at every size. */
static void test_generator_fine_footprints(void)
{
    const int N = 256, kinds[2] = {PFM_GAUSSIAN, PFM_GAUSSIAN_FINE};
    double frac[2][4];
    int k, q;
    for (k = 0; k < 2; ++k) {
        pfm_surface s;
        double total, m[5];
        if (pfm_surface_make(&s, N, N, 1.0, pfm_params_default(kinds[k])) != 0) {
            PF_CHECK(0, "make");
            return;
        }
        pfm_footprint_moments(&s, 0, 0, N, m);
        total = m[2] - m[0] * m[0] + m[3] - m[1] * m[1];
        for (q = 0; q < 4; ++q) {
            int n = 8 << q, x0, y0;
            double acc = 0.0;
            for (y0 = 0; y0 < N; y0 += n)
                for (x0 = 0; x0 < N; x0 += n) {
                    pfm_footprint_moments(&s, x0, y0, n, m);
                    acc += m[2] - m[0] * m[0] + m[3] - m[1] * m[1];
                }
            frac[k][q] = acc / ((double)(N / n) * (N / n)) / total;
        }
        pfm_surface_free(&s);
    }
    for (q = 0; q < 4; ++q)
        PF_CHECK(frac[1][q] > frac[0][q], "%d texels: fine %g not above coarse %g", (8 << q) * (8 << q), frac[1][q],
                 frac[0][q]);
    PF_CHECK(frac[1][3] >= 0.9, "fine kind at 64 x 64: only %g of the slope variance", frac[1][3]);
    pf_test_note("in-footprint fraction of the slope variance at 64 / 256 / 1024 / 4096 texels: gaussian %.2f %.2f %.2f %.2f, "
                 "gaussian_fine %.2f %.2f %.2f %.2f", frac[0][0], frac[0][1], frac[0][2], frac[0][3], frac[1][0],
                 frac[1][1], frac[1][2], frac[1][3]);
}

/* Gaussian heights too (a sum of many random-phase waves): height kurtosis ~ 3. */
static void test_generator_gaussian_heights(void)
{
    pfm_surface s;
    double m2 = 0.0, m4 = 0.0, n = 512.0 * 512.0, kurt;
    long long i;
    if (pfm_surface_make(&s, 512, 512, 1.0, pfm_params_default(PFM_GAUSSIAN)) != 0) {
        PF_CHECK(0, "make failed");
        return;
    }
    for (i = 0; i < 512LL * 512LL; ++i) {
        double h = s.height[i];
        m2 += h * h;
        m4 += h * h * h * h;
    }
    kurt = (m4 / n) / ((m2 / n) * (m2 / n));
    /* heights are smoother than slopes (fewer independent samples: ~ 512^2/(pi L^2 * 4)):
       bound 1.0 on |kurt - 3| */
    PF_CHECK(fabs(kurt - 3.0) < 1.0, "height kurtosis %g", kurt);
    pf_test_note("height kurtosis %.2f, height rms %.2f texel", kurt, sqrt(m2 / n));
    pfm_surface_free(&s);
}

/* The maps tile: the height step across the seam is no larger than the largest interior
   step (a non-periodic field would jump by ~ the height deviation there), and its mean
   square is within a factor 2 of the interior one; the seam texels' slopes are the
   central differences of their wrapped neighbours (the interior formula). */
static void test_generator_periodic(void)
{
    int k;
    for (k = 0; k < PFM_KIND_COUNT; ++k) {
        pfm_surface s;
        int x, y, W = 256, H = 128;
        double seam_max = 0.0, seam_ms = 0.0, in_max = 0.0, in_ms = 0.0, slope_err = 0.0;
        if (pfm_surface_make(&s, W, H, 0.5, pfm_params_default(k)) != 0) {
            PF_CHECK(0, "%s: make failed", pfm_kind_name(k));
            continue;
        }
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x) {
                double d = s.height[(size_t)y * W + (size_t)((x + 1) % W)] - s.height[(size_t)y * W + x];
                if (x == W - 1) {
                    seam_max = fabs(d) > seam_max ? fabs(d) : seam_max;
                    seam_ms += d * d / H;
                } else {
                    in_max = fabs(d) > in_max ? fabs(d) : in_max;
                    in_ms += d * d / ((double)H * (W - 1));
                }
            }
        for (y = 0; y < H; ++y) {
            double sx, sy, ex, ey;
            pfm_slope(&s, 0, y, &sx, &sy);
            ex = (s.height[(size_t)y * W + 1] - s.height[(size_t)y * W + W - 1]) / (2.0 * 0.5);
            ey = (s.height[(size_t)((y + 1) % H) * W] - s.height[(size_t)((y + H - 1) % H) * W]) / (2.0 * 0.5);
            slope_err = fmax(slope_err, fabs(sx - ex) + fabs(sy - ey));
        }
        PF_CHECK(seam_max <= in_max, "%s seam step %g > interior max %g", pfm_kind_name(k), seam_max, in_max);
        /* tiles: the seam falls on a groove bottom (flat); craters: ~flat ground */
        PF_CHECK(seam_ms <= 2.0 * in_ms && (k == PFM_TILES || k == PFM_CRATERS || seam_ms >= 0.5 * in_ms),
                 "%s seam ms %g interior ms %g", pfm_kind_name(k), seam_ms, in_ms);
        PF_CHECK(slope_err == 0.0, "%s seam slope differs by %g", pfm_kind_name(k), slope_err);
        if (k == PFM_GAUSSIAN) pf_test_note("gaussian seam/interior rms step %.3f", sqrt(seam_ms / in_ms));
        pfm_surface_free(&s);
    }
}

/* pfm_slope equals level 0 of the library's pf_slope_pyramid_from_heights (wrap) on the same
   (pf_real-rounded) heights, to the rounding of one pf_real subtraction and product. */
static void test_slopes_match_pyramid(void)
{
    pfm_surface s;
    int W = 64, H = 32, x, y;
    long long i, total = pf_mip_texel_count(W, H);
    pf_real *hr = (pf_real *)malloc((size_t)W * H * sizeof(pf_real));
    pf_real *pyr = (pf_real *)malloc((size_t)total * 5 * sizeof(pf_real));
    long double worst = 0.0L;
    int bad_sq = 0;
    if (!hr || !pyr || pfm_surface_make(&s, W, H, 0.75, pfm_params_default(PFM_RIDGES)) != 0) {
        PF_CHECK(0, "setup failed");
        free(hr);
        free(pyr);
        return;
    }
    for (i = 0; i < (long long)W * H; ++i) {
        hr[i] = (pf_real)s.height[i];
        s.height[i] = (double)hr[i]; /* the same heights on both sides */
    }
    pf_slope_pyramid_from_heights(hr, W, H, (pf_real)0.75, (pf_real)0.75, (pf_real)1.0, PF_BORDER_WRAP, pyr);
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            double sx, sy;
            const pf_real *t = pyr + 5 * ((long long)y * W + x);
            long double ex, ey, scx, scy, k = 1.0L / 1.5L, e = PF_TEST_EPS, lx;
            pfm_slope(&s, x, y, &sx, &sy);
            /* the library forms -k h[x-1] + k h[x+1] (k = 1/(2 texel) rounded) in pf_real, so
               its rounding is relative to the heights, not to their difference: bound
               scx = 2 eps k (|h[x-1]| + |h[x+1]|) + 2 eps |sx| per component; the worst ratio
               of the difference to that bound is reported */
            scx = 2.0L * e * k * (fabsl((long double)pfm_height(&s, x - 1, y)) + fabsl((long double)pfm_height(&s, x + 1, y))) +
                  2.0L * e * fabsl((long double)sx);
            scy = 2.0L * e * k * (fabsl((long double)pfm_height(&s, x, y - 1)) + fabsl((long double)pfm_height(&s, x, y + 1))) +
                  2.0L * e * fabsl((long double)sy);
            ex = fabsl((long double)t[0] - (long double)sx) / (scx + 1e-300L);
            ey = fabsl((long double)t[1] - (long double)sy) / (scy + 1e-300L);
            if (ex > worst) worst = ex;
            if (ey > worst) worst = ey;
            /* E[x^2] of the texel = (its own rounded sx)^2: within 2 |sx| scx + 2 eps sx^2 */
            lx = (long double)sx;
            if (fabsl((long double)t[2] - lx * lx) > 2.0L * fabsl(lx) * scx + 2.0L * e * lx * lx + scx * scx) ++bad_sq;
        }
    PF_CHECK(worst <= 1.0L, "max diff %Lg of the rounding bound", worst);
    PF_CHECK(bad_sq == 0, "%d texels with E[x^2] != sx^2 to rounding", bad_sq);
    pf_test_note("max diff %.2Lg of the rounding bound 2 eps (k (|h-| + |h+|) + |s|)", worst);
    free(hr);
    free(pyr);
    pfm_surface_free(&s);
}

/* ------------------------------------------------------------------ visibility */

/* A tilted plane h = a x + b y (an isolated patch: no_wrap) is seen from every direction above
   it and from none below (or on) it: exact, no mismatch allowed (directions within 1e-9 of
   the plane are skipped: rounding decides those). The bilinear field of a plane is the plane,
   so the march must find no occlusion at all. */
static void test_visibility_plane(void)
{
    pfm_surface s;
    int W = 48, H = 40, x, y, it, mism = 0, tested = 0;
    const double a = 0.35, b = -0.2;
    pf_test_rng rng = pf_test_rng_seed(7);
    if (pfm_surface_alloc(&s, W, H, 1.0) != 0) {
        PF_CHECK(0, "alloc");
        return;
    }
    s.no_wrap = 1;
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) s.height[(size_t)y * W + x] = a * x + b * y;
    pfm_surface_bounds(&s);
    for (it = 0; it < 200; ++it) {
        double w[3], above;
        random_dir(&rng, 0.0, 1.5607, w);
        above = w[2] - a * w[0] - b * w[1]; /* (m.w)/(m.z) for the plane's normal */
        if (fabs(above) < 1e-9) continue;
        for (y = 1; y < H - 1; ++y)
            for (x = 1; x < W - 1; ++x) {
                int v = pfm_visible(&s, x, y, w);
                ++tested;
                if (v != (above > 0.0)) ++mism;
            }
    }
    PF_CHECK(mism == 0, "%d mismatches of %d", mism, tested);
    pf_test_note("%d texel-directions, %d mismatches", tested, mism);
    pfm_surface_free(&s);
}

/* A wall along y (plateau of height Hw on x in [xa, xb], one-texel bilinear ramps) on flat
   ground: a ground texel at x with both neighbours on the ground is shadowed toward
   w = (sin t cos p, sin t sin p, cos t), cos p > 0, exactly when the ray reaches the plateau
   edge x = xa below Hw: ((xa - x) mod W) / cos p * cot t < Hw (the ray and the ramp are both
   linear in each ramp cell, so the plateau edge decides; the map wraps, so texels right of
   the wall see it again after the seam). Exact: no mismatch allowed (ties within 1e-6
   skipped). */
static void test_visibility_wall(void)
{
    pfm_surface s;
    const int W = 128, H = 8, xa = 70, xb = 74;
    const double Hw = 10.3;
    const double thetas[] = {20.0, 45.0, 60.0, 75.0, 82.0, 88.0};
    const double phis[] = {0.0, 0.3, -0.7, 1.2};
    int x, y, i, j, mism = 0, tested = 0, shadowed = 0;
    if (pfm_surface_alloc(&s, W, H, 1.0) != 0) {
        PF_CHECK(0, "alloc");
        return;
    }
    for (y = 0; y < H; ++y)
        for (x = xa; x <= xb; ++x) s.height[(size_t)y * W + x] = Hw;
    pfm_surface_bounds(&s);
    for (i = 0; i < 6; ++i)
        for (j = 0; j < 4; ++j) {
            double w[3], t = deg(thetas[i]), p = phis[j];
            dir_from_angles(t, p, w);
            for (x = 0; x < W; ++x) {
                double dist, rise;
                if (x >= xa - 1 && x <= xb + 1) continue; /* the wall and its ramp feet */
                dist = (double)((xa - x + W) % W) / cos(p);
                rise = dist * cos(t) / sin(t);
                if (fabs(rise - Hw) < 1e-6) continue;
                for (y = 0; y < H; ++y) {
                    int v = pfm_visible(&s, x, y, w), expect = rise >= Hw;
                    ++tested;
                    shadowed += !expect;
                    if (v != expect) ++mism;
                }
            }
        }
    PF_CHECK(mism == 0, "%d mismatches of %d", mism, tested);
    PF_CHECK(shadowed > tested / 10, "test too weak: only %d shadowed of %d", shadowed, tested);
    pf_test_note("%d texel-directions (%d shadowed), %d mismatches", tested, shadowed, mism);
    pfm_surface_free(&s);
}

/* The continuous surface h(x, y) = A sin(2 pi x / P) cos(2 pi y / Q) sampled at the nodes:
   its visibility from the nodes by a fine march (step 0.01 texel, from 0.01 texel, the
   analytic height), with the same facet test m.w > 0 on the central-difference normal,
   compared with the bilinear march with the half-texel start skip (the reference) and with
   no skip. Mismatches are near-tangent rays (the bilinear interpolant sits below a convex
   continuous surface and above a concave one by ~ A (2 pi / P)^2 / 8); bound 3% of the
   texel-directions for the reference, and the skip must not do worse than no skip. */
typedef struct {
    double A, P, Q;
} wave_surf;

static double wave_h(const wave_surf *ws, double x, double y)
{
    return ws->A * sin(2.0 * pi_d * x / ws->P) * cos(2.0 * pi_d * y / ws->Q);
}

static int wave_visible(const pfm_surface *s, const wave_surf *ws, int x, int y, const double w[3])
{
    double sx, sy, r = sqrt(w[0] * w[0] + w[1] * w[1]), t, h0 = wave_h(ws, x, y);
    pfm_slope(s, x, y, &sx, &sy);
    if (!(w[2] - sx * w[0] - sy * w[1] > 0.0)) return 0;
    for (t = 0.01; h0 + t * w[2] / r <= ws->A; t += 0.01)
        if (wave_h(ws, x + t * w[0] / r, y + t * w[1] / r) > h0 + t * w[2] / r) return 0;
    return 1;
}

static void test_visibility_smooth_surface(void)
{
    pfm_surface s;
    wave_surf ws;
    const int W = 64, H = 32;
    int x, y, it, mism_ref = 0, mism_noskip = 0, tested = 0, occl = 0;
    pf_test_rng rng = pf_test_rng_seed(11);
    ws.A = 3.0;
    ws.P = 32.0;
    ws.Q = 16.0;
    if (pfm_surface_alloc(&s, W, H, 1.0) != 0) {
        PF_CHECK(0, "alloc");
        return;
    }
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) s.height[(size_t)y * W + x] = wave_h(&ws, x, y);
    pfm_surface_bounds(&s);
    for (it = 0; it < 24; ++it) {
        double w[3];
        random_dir(&rng, deg(50.0), deg(85.0), w);
        for (y = 0; y < H; y += 2)
            for (x = 0; x < W; x += 2) {
                int truth = wave_visible(&s, &ws, x, y, w);
                ++tested;
                occl += !truth;
                mism_ref += pfm_visible(&s, x, y, w) != truth;
                mism_noskip += pfm_visible_skip(&s, x, y, w, 0.0) != truth;
            }
    }
    PF_CHECK(mism_ref <= tested * 3 / 100, "reference march: %d mismatches of %d", mism_ref, tested);
    PF_CHECK(mism_ref <= mism_noskip, "the skip does worse: %d vs %d without", mism_ref, mism_noskip);
    PF_CHECK(occl > tested / 10, "test too weak: %d occluded of %d", occl, tested);
    pf_test_note("%d texel-directions (%d occluded): mismatches %d with the half-texel skip, %d without",
                 tested, occl, mism_ref, mism_noskip);
    pfm_surface_free(&s);
}

/* The block-max acceleration of the march is exact: the same maps with and without it (the
   surface's block_max removed), ridges (steep crests) at grazing angles, no difference
   allowed. */
static void test_visibility_acceleration_exact(void)
{
    pfm_surface s;
    const int N = 128;
    unsigned char *va = (unsigned char *)malloc((size_t)N * N), *vb = (unsigned char *)malloc((size_t)N * N);
    const double thetas[] = {40.0, 70.0, 80.0, 86.0, 89.0};
    int i, k, diff = 0, occl = 0;
    if (!va || !vb || pfm_surface_make(&s, N, N, 1.0, pfm_params_default(PFM_RIDGES)) != 0) {
        PF_CHECK(0, "setup");
        free(va);
        free(vb);
        return;
    }
    for (i = 0; i < 5; ++i) {
        double w[3], *saved;
        dir_from_angles(deg(thetas[i]), 0.3 + 1.1 * i, w);
        pfm_visibility_map(&s, w, va);
        saved = s.block_max;
        s.block_max = NULL;
        pfm_visibility_map(&s, w, vb);
        s.block_max = saved;
        for (k = 0; k < N * N; ++k) {
            diff += va[k] != vb[k];
            occl += !vb[k];
        }
    }
    PF_CHECK(diff == 0 && occl > N * N / 4, "%d texels differ (%d occluded)", diff, occl);
    pf_test_note("%d texel-directions, %d occluded, %d differ", 5 * N * N, occl, diff);
    free(va);
    free(vb);
    pfm_surface_free(&s);
}

/* Smith's masking 1/(1 + Lambda) (Lambda of Gaussian slopes with the measured deviation along
   the view azimuth; tests/pf_oracle.h) against the measured visible fraction of the
   front-facing projected area of the Gaussian maps (whole map as footprint). Smith is known
   to be accurate for Gaussian surfaces; bound 3% at 0-75 degrees (measured ~0.5% on 512^2,
   this test uses 256^2). Also visible_area (sum V a+ / A) ~ 1 within 1%: each viewing ray
   meets exactly one visible point. */
static void test_visibility_smith_gaussian(void)
{
    const double thetas[] = {0.0, 30.0, 45.0, 60.0, 70.0, 75.0, 80.0};
    const int kinds[3] = {PFM_GAUSSIAN, PFM_GAUSSIAN_ANISO, PFM_GAUSSIAN_FINE};
    const int N = 256;
    int kk;
    unsigned char *vis = (unsigned char *)malloc((size_t)N * N);
    if (!vis) return;
    for (kk = 0; kk < 3; ++kk) {
        pfm_surface s;
        const int kind = kinds[kk];
        /* the fine kind (3-texel features): the bilinear surface the march sees is rougher
           than its central-difference slopes, so the march loses up to ~3% of the visible
           area at 75 degrees (visible_area < 1) and G1 follows it: bounds 4.5% there, and
           G1 / Smith must equal visible_area to 1% (Smith is right once the reference's own
           area deficit is divided out) */
        const double bound = kind == PFM_GAUSSIAN_FINE ? 0.045 : 0.03;
        double worst = 0.0, worst_area = 0.0, worst_explained = 0.0, m[5];
        int i, j;
        if (pfm_surface_make(&s, N, N, 1.0, pfm_params_default(kind)) != 0) {
            PF_CHECK(0, "make");
            continue;
        }
        pfm_footprint_moments(&s, 0, 0, N, m);
        for (j = 0; j < 2; ++j)
            for (i = 0; i < 7; ++i) {
                double w[3], phi = 0.4 + 1.3 * j, t = deg(thetas[i]);
                double c = cos(phi), sn = sin(phi), var, g, err;
                pfm_shade r;
                dir_from_angles(t, phi, w);
                pfm_visibility_map(&s, w, vis);
                r = pfm_reference_shade(&s, vis, NULL, 0, 0, N, w, w, 0.1, 1.0);
                var = c * c * (m[2] - m[0] * m[0]) + sn * sn * (m[3] - m[1] * m[1]) +
                      2.0 * c * sn * (m[4] - m[0] * m[1]);
                g = t == 0.0 ? 1.0
                             : 1.0 / (1.0 + (double)pf_oracle_lambda_beckmann(
                                                (long double)((cos(t) / sin(t) - m[0] * c - m[1] * sn) /
                                                              sqrt(2.0 * var))));
                err = fabs(r.masking / g - 1.0);
                if (thetas[i] <= 75.0) {
                    PF_CHECK(err < bound, "%s theta %g phi %g: measured %g smith %g", pfm_kind_name(kind),
                             thetas[i], phi, r.masking, g);
                    if (err > worst) worst = err;
                }
                if (fabs(r.visible_area - 1.0) > worst_area) worst_area = fabs(r.visible_area - 1.0);
                if (fabs(r.masking / g / r.visible_area - 1.0) > worst_explained)
                    worst_explained = fabs(r.masking / g / r.visible_area - 1.0);
                if (j == 0 && (thetas[i] == 60.0 || thetas[i] == 75.0 || thetas[i] == 80.0))
                    pf_test_note("%s %g deg: G1 %.4f smith %.4f visible_area %.4f", pfm_kind_name(kind), thetas[i],
                                 r.masking, g, r.visible_area);
            }
        PF_CHECK(worst_area < (kind == PFM_GAUSSIAN_FINE ? 0.045 : 0.01), "%s visible_area off 1 by %g",
                 pfm_kind_name(kind), worst_area);
        PF_CHECK(worst_explained < 0.01, "%s G1/smith/visible_area off 1 by %g", pfm_kind_name(kind), worst_explained);
        pf_test_note("%s max |G1/smith - 1| %.2g, max |visible_area - 1| %.2g; max |G1/smith/visible_area - 1| %.2g (<= 80 deg)",
                     pfm_kind_name(kind), worst, worst_area, worst_explained);
        pfm_surface_free(&s);
    }
    free(vis);
}

/* ------------------------------------------------------------------ in-footprint visibility */

/* The wall of test_visibility_wall, seen from ground texels through random footprint boxes
   that contain the texel (pfm_visible_box): only the height field over the box
   [x0 - 1/2, x0 + n - 1/2] x [y0 - 1/2, y0 + n - 1/2] may occlude. Analytic answer: the ray
   (height 0 at the texel, rising cot t per unit of path) meets the rising ramp over
   [xa - 1, xa] (height Hw u at xa - 1 + u) and then the plateau; both are linear, so the
   ray is occluded exactly when the surface is above it at u_end = min(1, how far the ray gets
   into the ramp before leaving the box), if it gets there at all. Exact: no mismatch allowed
   (ties within 1e-6 skipped). The box must also free rays the full march occludes. */
static void test_visibility_box_wall(void)
{
    pfm_surface s;
    const int W = 128, H = 64, xa = 70, xb = 74;
    const double Hw = 10.3;
    pf_test_rng rng = pf_test_rng_seed(91);
    int x, y, it, mism = 0, tested = 0, shadowed = 0, freed = 0;
    if (pfm_surface_alloc(&s, W, H, 1.0) != 0) {
        PF_CHECK(0, "alloc");
        return;
    }
    for (y = 0; y < H; ++y)
        for (x = xa; x <= xb; ++x) s.height[(size_t)y * W + x] = Hw;
    pfm_surface_bounds(&s);
    for (it = 0; it < 20000; ++it) {
        double w[3], t = deg(pf_test_uniform(&rng, 20.0, 88.0)), p = pf_test_uniform(&rng, -1.2, 1.2);
        double cp = cos(p), cot = cos(t) / sin(t), texit = 1e300, d0, xend, uend, gap;
        int n = 1 + (int)pf_test_uniform(&rng, 0.0, 48.0), ox, oy, x0, y0, expect, v;
        /* ground texels, mostly within 40 texels left of the ramp (the wall's shadow) */
        x = (xa - 2 - (int)pf_test_uniform(&rng, 0.0, 40.0) + (it % 4 == 0 ? 40 : 0) + W) % W;
        y = (int)pf_test_uniform(&rng, 0.0, (double)H);
        if (x >= xa - 1 && x <= xb + 1) continue; /* the wall and its ramp feet */
        ox = (int)pf_test_uniform(&rng, 0.0, (double)n);
        oy = (int)pf_test_uniform(&rng, 0.0, (double)n);
        x0 = x - ox;
        y0 = y - oy;
        dir_from_angles(t, p, w);
        /* horizontal distance to the box's edges (the y extent only limits when n < H) */
        texit = ((double)(n - ox) - 0.5) / cp;
        if (n < H && fabs(sin(p)) > 1e-300)
            texit = fmin(texit, (sin(p) > 0.0 ? (double)(n - oy) - 0.5 : (double)oy + 0.5) / fabs(sin(p)));
        d0 = (double)((xa - 1 - x + W) % W); /* x distance to the foot of the ramp */
        xend = texit * cp;                   /* x distance at which the ray leaves the box */
        if (xend <= d0) {
            expect = 1;
        } else {
            uend = fmin(1.0, xend - d0);
            gap = Hw * uend - (d0 + uend) / cp * cot; /* surface minus ray at u_end */
            if (fabs(gap) < 1e-6) continue;
            expect = gap < 0.0;
        }
        v = pfm_visible_box(&s, x, y, w, x0, y0, n);
        ++tested;
        shadowed += !expect;
        if (expect && !pfm_visible(&s, x, y, w)) ++freed;
        if (v != expect) ++mism;
    }
    PF_CHECK(mism == 0, "%d mismatches of %d", mism, tested);
    PF_CHECK(shadowed > tested / 20 && freed > tested / 20, "test too weak: %d shadowed, %d freed of %d", shadowed,
             freed, tested);
    pf_test_note("%d texel-direction-boxes (%d shadowed in the box, %d freed by it), %d mismatches", tested, shadowed,
                 freed, mism);
    pfm_surface_free(&s);
}

/* pfm_visible_box on a Gaussian map against an independent march: the ray sampled every 0.01
   texel from the half-texel skip to where it leaves the box (or rises above hmax), occluded
   where pfm_height_bilinear is above it. The sampled march misses crossings shorter than its
   step (near-tangent rays): bound 0.5% of the rays; no systematic side. */
static void test_visibility_box_sampled(void)
{
    pfm_surface s;
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    const int N = 64;
    pf_test_rng rng = pf_test_rng_seed(92);
    int it, mism = 0, tested = 0, freed = 0, occl = 0;
    p.corr_texels = 6.0;
    if (pfm_surface_make(&s, N, N, 1.0, p) != 0) {
        PF_CHECK(0, "make");
        return;
    }
    for (it = 0; it < 3000; ++it) {
        double w[3], sx, sy, r, dx, dy, rise, h0, texit = 1e300, t;
        int n = 1 << (int)pf_test_uniform(&rng, 0.0, 6.0), x, y, ox, oy, truth = 1, v;
        random_dir(&rng, deg(45.0), deg(86.0), w);
        x = (int)pf_test_uniform(&rng, 0.0, (double)N);
        y = (int)pf_test_uniform(&rng, 0.0, (double)N);
        ox = (int)pf_test_uniform(&rng, 0.0, (double)n);
        oy = (int)pf_test_uniform(&rng, 0.0, (double)n);
        pfm_slope(&s, x, y, &sx, &sy);
        if (!(w[2] - sx * w[0] - sy * w[1] > 0.0)) continue; /* back-facing: the facet test alone */
        r = sqrt(w[0] * w[0] + w[1] * w[1]);
        dx = w[0] / r;
        dy = w[1] / r;
        rise = w[2] / r;
        h0 = pfm_height(&s, x, y);
        if (fabs(dx) > 1e-12) texit = fmin(texit, (dx > 0.0 ? (double)(n - ox) - 0.5 : (double)ox + 0.5) / fabs(dx));
        if (fabs(dy) > 1e-12) texit = fmin(texit, (dy > 0.0 ? (double)(n - oy) - 0.5 : (double)oy + 0.5) / fabs(dy));
        for (t = 0.5; t <= texit && h0 + rise * t <= s.hmax; t += 0.01)
            if (pfm_height_bilinear(&s, x + dx * t, y + dy * t) > h0 + rise * t + 1e-12) {
                truth = 0;
                break;
            }
        v = pfm_visible_box(&s, x, y, w, x - ox, y - oy, n);
        ++tested;
        occl += !truth;
        if (truth && !pfm_visible(&s, x, y, w)) ++freed;
        if (v != truth) ++mism;
    }
    PF_CHECK(mism * 200 <= tested, "%d mismatches of %d", mism, tested);
    PF_CHECK(occl > tested / 20 && freed > tested / 20, "test too weak: %d occluded, %d freed of %d", occl, freed,
             tested);
    pf_test_note("%d rays (%d occluded in the box, %d freed by it): %d mismatches with the 0.01-texel sampled march",
                 tested, occl, freed, mism);
    pfm_surface_free(&s);
}

/* Box maps on corpus maps: the box only removes occluders, so every texel visible in the full
   map is visible in the box (checked by marching them all, not through the shortcut), the
   shortcut of pfm_visibility_map_box (vis_full given) gives the same map as marching every
   texel, and a box as large as the map is pfm_visibility_map. Exact: no difference allowed.
   The in-footprint masking is then >= the full one for every footprint. */
static void test_visibility_box_maps(void)
{
    const int N = 128, kinds[2] = {PFM_RIDGES, PFM_GAUSSIAN_FINE};
    const double thetas[] = {50.0, 70.0, 80.0, 86.0};
    unsigned char *full = (unsigned char *)malloc((size_t)N * N), *a = (unsigned char *)malloc((size_t)N * N);
    unsigned char *b = (unsigned char *)malloc((size_t)N * N);
    pf_test_rng rng = pf_test_rng_seed(93);
    int k, i, diff_short = 0, not_monotone = 0, diff_whole = 0, freed = 0, boxes = 0, mask_bad = 0;
    if (!full || !a || !b) {
        PF_CHECK(0, "alloc");
        free(full);
        free(a);
        free(b);
        return;
    }
    for (k = 0; k < 2; ++k) {
        pfm_surface s;
        if (pfm_surface_make(&s, N, N, 1.0, pfm_params_default(kinds[k])) != 0) {
            PF_CHECK(0, "make");
            continue;
        }
        for (i = 0; i < 4; ++i) {
            double w[3];
            int q, id;
            dir_from_angles(deg(thetas[i]), 0.2 + 1.7 * i, w);
            pfm_visibility_map(&s, w, full);
            pfm_visibility_map_box(&s, w, 0, 0, N, NULL, a);
            for (id = 0; id < N * N; ++id) diff_whole += a[id] != full[id];
            for (q = 0; q < 6; ++q) {
                int n = 1 << q, x0 = (int)pf_test_uniform(&rng, 0.0, (double)N), y0 = (int)pf_test_uniform(&rng, 0.0, (double)N);
                int xx, yy;
                pfm_shade rf, rb;
                memset(a, 7, (size_t)N * N);
                memset(b, 9, (size_t)N * N);
                pfm_visibility_map_box(&s, w, x0, y0, n, NULL, a);
                pfm_visibility_map_box(&s, w, x0, y0, n, full, b);
                ++boxes;
                for (yy = 0; yy < n; ++yy)
                    for (xx = 0; xx < n; ++xx) {
                        size_t t = (size_t)((y0 + yy) % N) * N + (size_t)((x0 + xx) % N);
                        diff_short += a[t] != b[t];
                        not_monotone += full[t] && !a[t];
                        freed += a[t] && !full[t];
                    }
                rf = pfm_reference_shade(&s, full, NULL, x0, y0, n, w, w, 0.1, 1.0);
                rb = pfm_reference_shade(&s, a, NULL, x0, y0, n, w, w, 0.1, 1.0);
                mask_bad += rb.masking < rf.masking;
            }
        }
        pfm_surface_free(&s);
    }
    PF_CHECK(diff_whole == 0, "whole-map box differs from the full map at %d texels", diff_whole);
    PF_CHECK(diff_short == 0, "the vis_full shortcut changes %d texels", diff_short);
    PF_CHECK(not_monotone == 0, "%d texels visible in the full map but not in the box", not_monotone);
    PF_CHECK(mask_bad == 0, "%d footprints with in-footprint masking below the full one", mask_bad);
    PF_CHECK(freed > 100, "test too weak: the boxes freed %d texels", freed);
    pf_test_note("%d boxes: %d texels freed by the box, 0 differences (shortcut, monotone, whole map)", boxes, freed);
    free(full);
    free(a);
    free(b);
}

/* pfm_reference_shade_set equals pfm_reference_shade pair by pair, every field exactly (the
   same sums in the same order), with more pairs than one batch of accumulators (9 > 8) and
   NULL maps among them. */
static void test_reference_shade_set(void)
{
    const int N = 64, NP = 9;
    pfm_surface s;
    unsigned char *maps[4];
    const unsigned char *vo[9], *vi[9];
    pf_test_rng rng = pf_test_rng_seed(94);
    int i, it, bad = 0, nonzero = 0;
    for (i = 0; i < 4; ++i) maps[i] = (unsigned char *)malloc((size_t)N * N);
    if (!maps[0] || !maps[1] || !maps[2] || !maps[3] || pfm_surface_make(&s, N, N, 1.0, pfm_params_default(PFM_CRATERS)) != 0) {
        PF_CHECK(0, "setup");
        for (i = 0; i < 4; ++i) free(maps[i]);
        return;
    }
    for (it = 0; it < 20; ++it) {
        double wo[3], wi[3];
        int n = 1 << (int)pf_test_uniform(&rng, 0.0, 6.0), x0 = (int)pf_test_uniform(&rng, 0.0, (double)N);
        int y0 = (int)pf_test_uniform(&rng, 0.0, (double)N);
        pfm_shade out[9];
        random_dir(&rng, 0.0, deg(85.0), wo);
        random_dir(&rng, 0.0, deg(85.0), wi);
        pfm_visibility_map(&s, wo, maps[0]);
        pfm_visibility_map(&s, wi, maps[1]);
        pfm_visibility_map_box(&s, wo, x0, y0, n, maps[0], maps[2]);
        pfm_visibility_map_box(&s, wi, x0, y0, n, maps[1], maps[3]);
        for (i = 0; i < NP; ++i) {
            vo[i] = i % 3 == 2 ? NULL : maps[(i % 2) * 2];
            vi[i] = i % 4 == 3 ? NULL : maps[1 + ((i / 2) % 2) * 2];
        }
        pfm_reference_shade_set(&s, NP, vo, vi, x0, y0, n, wo, wi, 0.1, 0.04, out);
        for (i = 0; i < NP; ++i) {
            pfm_shade r = pfm_reference_shade(&s, vo[i], vi[i], x0, y0, n, wo, wi, 0.1, 0.04);
            bad += r.spec != out[i].spec || r.diffuse != out[i].diffuse || r.masking != out[i].masking ||
                   r.joint != out[i].joint || r.area != out[i].area || r.front_area != out[i].front_area ||
                   r.visible_area != out[i].visible_area;
            nonzero += r.spec > 0.0;
        }
    }
    PF_CHECK(bad == 0, "%d of %d shades differ", bad, 20 * NP);
    PF_CHECK(nonzero > 20, "test too weak: %d non-zero spec", nonzero);
    for (i = 0; i < 4; ++i) free(maps[i]);
    pfm_surface_free(&s);
}

/* ------------------------------------------------------------------ reference identities */

/* Eq. 1: the sum of the per-texel projected areas over a footprint is n^2 (nbar.wo)/(nbar.z)
   computed from the footprint's mean slope, to rounding (1e-12 relative to the sum of the
   magnitudes). */
static void test_identity_projected_area(void)
{
    pfm_surface s;
    pf_test_rng rng = pf_test_rng_seed(3);
    double worst = 0.0;
    int it;
    if (pfm_surface_make(&s, 128, 128, 1.0, pfm_params_default(PFM_CRATERS)) != 0) {
        PF_CHECK(0, "make");
        return;
    }
    for (it = 0; it < 200; ++it) {
        double w[3], m[5], mesh, err;
        int n = 1 << (int)pf_test_uniform(&rng, 0.0, 7.0);
        int x0 = (int)pf_test_uniform(&rng, 0.0, 128.0), y0 = (int)pf_test_uniform(&rng, 0.0, 128.0);
        pfm_shade r;
        random_dir(&rng, 0.0, 1.55, w);
        r = pfm_reference_shade(&s, NULL, NULL, x0, y0, n, w, w, 0.1, 1.0);
        pfm_footprint_moments(&s, x0, y0, n, m);
        /* (nbar.wo)/(nbar.z) with nbar = (-E[x], -E[y], 1)/norm */
        mesh = w[2] - m[0] * w[0] - m[1] * w[1];
        err = fabs(r.area - mesh) / (w[2] + fabs(m[0] * w[0]) + fabs(m[1] * w[1]));
        if (err > worst) worst = err;
    }
    PF_CHECK(worst < 1e-12, "max rel err %g", worst);
    pf_test_note("max rel err %.2g", worst);
    pfm_surface_free(&s);
}

/* Beckmann closed forms in trigonometric form (an independent path from pfm_base_specular's
   slope-space form): D = exp(-tan^2 t_h / a^2) / (pi a^2 cos^4 t_h), a = sqrt 2 sigma;
   Lambda(t) = (erf(q) - 1)/2 + exp(-q^2)/(2 q sqrt pi), q = 1/(a tan t) (Walter et al. 2007
   form of Smith's Beckmann Lambda). */
static double flat_lobe(const double wo[3], const double wi[3], double sigma, double f0)
{
    double to = acos(wo[2]), ti = acos(wi[2]), hv[3], hn, th, a = sqrt(2.0) * sigma, d, lo = 0.0, li = 0.0;
    double cd, f, q;
    int k;
    for (k = 0; k < 3; ++k) hv[k] = wo[k] + wi[k];
    hn = sqrt(hv[0] * hv[0] + hv[1] * hv[1] + hv[2] * hv[2]);
    th = acos(hv[2] / hn);
    d = exp(-pow(tan(th) / a, 2.0)) / (pi_d * a * a * pow(cos(th), 4.0));
    if (to > 0.0) {
        q = 1.0 / (a * tan(to));
        lo = 0.5 * (erf(q) - 1.0) + exp(-q * q) / (2.0 * q * sqrt(pi_d));
    }
    if (ti > 0.0) {
        q = 1.0 / (a * tan(ti));
        li = 0.5 * (erf(q) - 1.0) + exp(-q * q) / (2.0 * q * sqrt(pi_d));
    }
    cd = cos(0.5 * acos(wo[0] * wi[0] + wo[1] * wi[1] + wo[2] * wi[2])); /* half the angle o-i */
    f = f0 + (1.0 - f0) * pow(1.0 - cd, 5.0);
    return f * d / (1.0 + lo + li) / (4.0 * wo[2]);
}

/* Flat plane, V = 1: diffuse = cos t_i / pi and spec = F D G2 / (4 cos t_o) of the base
   Beckmann lobe, to ~1e-12 relative (the trigonometric path loses a few digits at grazing
   half vectors: tan^2 / a^2 up to ~40 in the exponent, and erf cancellation at q ~ 1: bound
   1e-11); masking = joint = 1. */
static void test_identity_flat_plane(void)
{
    pfm_surface s;
    pf_test_rng rng = pf_test_rng_seed(5);
    double worst_spec = 0.0, worst_diff = 0.0, worst_vis = 0.0;
    int it, used = 0;
    unsigned char *vo = (unsigned char *)malloc(16 * 16), *vi = (unsigned char *)malloc(16 * 16);
    if (!vo || !vi || pfm_surface_alloc(&s, 16, 16, 1.0) != 0) {
        PF_CHECK(0, "alloc");
        free(vo);
        free(vi);
        return;
    }
    pfm_surface_bounds(&s);
    for (it = 0; it < 400; ++it) {
        double wo[3], wi[3], sigma = pf_test_log_uniform(&rng, 0.03, 0.6), f0 = pf_test_uniform(&rng, 0.0, 1.0);
        double ref, e;
        pfm_shade r;
        random_dir(&rng, 0.01, 1.5, wo);
        random_dir(&rng, 0.01, 1.5, wi);
        pfm_visibility_map(&s, wo, vo);
        pfm_visibility_map(&s, wi, vi);
        r = pfm_reference_shade(&s, vo, vi, 3, 5, 8, wo, wi, sigma, f0);
        e = fabs(r.diffuse / (wi[2] / pi_d) - 1.0);
        if (e > worst_diff) worst_diff = e;
        e = fabs(r.masking - 1.0) + fabs(r.joint - 1.0) + fabs(r.visible_area - 1.0);
        if (e > worst_vis) worst_vis = e;
        ref = flat_lobe(wo, wi, sigma, f0);
        if (ref < 1e-200) continue; /* D underflows: nothing to compare */
        ++used;
        e = fabs(r.spec / ref - 1.0);
        if (e > worst_spec) worst_spec = e;
    }
    PF_CHECK(worst_diff < 1e-14, "diffuse rel err %g", worst_diff);
    PF_CHECK(worst_vis < 1e-15, "masking/joint/visible_area off 1 by %g", worst_vis);
    PF_CHECK(worst_spec < 1e-11, "spec rel err %g", worst_spec);
    PF_CHECK(used > 300, "only %d spec samples", used);
    pf_test_note("spec max rel err %.2g (%d configs), diffuse %.2g", worst_spec, used, worst_diff);
    free(vo);
    free(vi);
    pfm_surface_free(&s);
}

/* A planar footprint of slope (a, b) (a tilted plane, isolated patch) is where LEADR is exact:
   the reference's spec must equal the library's pf_leadr_specular (eq. 17) for the noncentered
   Beckmann of mean (a, b) and variance base_sigma^2 (this checks the noncentered D_t, G2_t
   and the projected-area division of the reference together, against an implementation
   written separately); bound 400 pf_real eps relative (the library's D and Lambda carry a
   few eps times the condition number of the exponent). diffuse = <m, wi>/pi exactly (the
   projected areas cancel), to 1e-14. */
static void test_identity_tilted_facet(void)
{
    pfm_surface s;
    const double a = 0.3, b = -0.45;
    pf_test_rng rng = pf_test_rng_seed(21);
    long double worst = 0.0L;
    double worst_diff = 0.0, m[3], mn = sqrt(1.0 + a * a + b * b);
    int x, y, it, used = 0;
    unsigned char *vo = (unsigned char *)malloc(32 * 32), *vi = (unsigned char *)malloc(32 * 32);
    m[0] = -a / mn;
    m[1] = -b / mn;
    m[2] = 1.0 / mn;
    if (!vo || !vi || pfm_surface_alloc(&s, 32, 32, 1.0) != 0) {
        PF_CHECK(0, "alloc");
        free(vo);
        free(vi);
        return;
    }
    s.no_wrap = 1;
    for (y = 0; y < 32; ++y)
        for (x = 0; x < 32; ++x) s.height[y * 32 + x] = a * x + b * y;
    pfm_surface_bounds(&s);
    for (it = 0; it < 300; ++it) {
        double wo[3], wi[3], sigma = pf_test_log_uniform(&rng, 0.05, 0.5), f0 = pf_test_uniform(&rng, 0.0, 1.0);
        pfm_shade r;
        pf_real lib;
        random_dir(&rng, 0.0, 1.5, wo);
        random_dir(&rng, 0.0, 1.5, wi);
        pfm_visibility_map(&s, wo, vo);
        pfm_visibility_map(&s, wi, vi);
        r = pfm_reference_shade(&s, vo, vi, 12, 12, 8, wo, wi, sigma, f0);
        lib = pf_leadr_specular(pf_vec3_make((pf_real)wo[0], (pf_real)wo[1], (pf_real)wo[2]),
                                pf_vec3_make((pf_real)wi[0], (pf_real)wi[1], (pf_real)wi[2]),
                                pf_slope_stats_make((pf_real)a, (pf_real)b, (pf_real)(sigma * sigma),
                                                    (pf_real)(sigma * sigma), (pf_real)0.0),
                                (pf_real)f0);
        if (r.diffuse > 0.0 || m[0] * wi[0] + m[1] * wi[1] + m[2] * wi[2] > 0.0) {
            double d = m[0] * wi[0] + m[1] * wi[1] + m[2] * wi[2];
            double e = fabs(r.diffuse - (d > 0.0 && r.area > 0.0 ? d / pi_d : 0.0)) / (1.0 / pi_d);
            if (e > worst_diff) worst_diff = e;
        }
        if (!(r.spec > 1e-6)) continue; /* the library works in pf_real: compare where it resolves */
        ++used;
        {
            long double e = fabsl((long double)lib / (long double)r.spec - 1.0L);
            if (e > worst) worst = e;
        }
    }
    PF_CHECK(worst <= 400.0L * PF_TEST_EPS, "spec vs pf_leadr_specular: rel %Lg", worst);
    PF_CHECK(worst_diff < 1e-14, "diffuse vs <m,wi>/pi: %g", worst_diff);
    PF_CHECK(used > 100, "only %d comparisons", used);
    pf_test_note("spec vs pf_leadr_specular max rel %.2Lg (%.0Lf eps, %d configs); diffuse %.2g", worst,
                 worst / PF_TEST_EPS, used, worst_diff);
    free(vo);
    free(vi);
    pfm_surface_free(&s);
}

/* White furnace: the diffuse reference integrated over the light hemisphere is <= 1 (masking,
   shadowing and the macro-hemisphere cut only remove light) and -> 1 as the surface flattens;
   exactly 1 for a flat plane. Quadrature: midpoint rule in u = cos^2 t_i and phi (dw cos t =
   du dphi / 2), exact for the flat plane's cos t_i / pi. A rough map's visible_area can
   exceed 1 by discretization (~1e-3 for Gaussian maps): bound 1 + 5e-3. */
static double furnace(const pfm_surface *s, const double wo[3], int nu, int nphi)
{
    size_t np = (size_t)s->w * s->h;
    unsigned char *vo = (unsigned char *)malloc(np), *vi = (unsigned char *)malloc(np);
    double sum = 0.0;
    int i, j;
    if (!vo || !vi) {
        free(vo);
        free(vi);
        return -1.0;
    }
    pfm_visibility_map(s, wo, vo);
    for (i = 0; i < nu; ++i)
        for (j = 0; j < nphi; ++j) {
            double u = (i + 0.5) / nu, phi = 2.0 * pi_d * (j + 0.5) / nphi, c = sqrt(u), sn = sqrt(1.0 - u);
            double wi[3];
            pfm_shade r;
            wi[0] = sn * cos(phi);
            wi[1] = sn * sin(phi);
            wi[2] = c;
            pfm_visibility_map(s, wi, vi);
            r = pfm_reference_shade(s, vo, vi, 0, 0, s->w, wo, wi, 0.1, 1.0);
            /* integral of I(wi) dwi = integral of (I / cos) du dphi / 2 */
            sum += r.diffuse / c * (1.0 / nu) * (2.0 * pi_d / nphi) * 0.5;
        }
    free(vo);
    free(vi);
    return sum;
}

static void test_furnace_diffuse(void)
{
    const double rms[] = {0.0, 0.02, 0.1, 0.4};
    double wo[3], prev = 2.0, vals[4];
    int k;
    dir_from_angles(deg(30.0), 0.3, wo);
    for (k = 0; k < 4; ++k) {
        pfm_surface s;
        pfm_params p = pfm_params_default(PFM_GAUSSIAN);
        int rc;
        p.corr_texels = 6.0;
        if (rms[k] > 0.0) {
            p.rms_slope = rms[k];
            rc = pfm_surface_make(&s, 32, 32, 1.0, p);
        } else {
            rc = pfm_surface_alloc(&s, 32, 32, 1.0);
            if (rc == 0) pfm_surface_bounds(&s);
        }
        if (rc != 0) {
            PF_CHECK(0, "make");
            return;
        }
        vals[k] = furnace(&s, wo, 10, 20);
        if (k == 0)
            PF_CHECK(fabs(vals[k] - 1.0) < 1e-13, "flat plane furnace %.17g", vals[k]);
        else
            PF_CHECK(vals[k] <= 1.005 && vals[k] <= prev + 1e-9, "rms %g furnace %.6g (previous %.6g)", rms[k],
                     vals[k], prev);
        prev = vals[k];
        pfm_surface_free(&s);
    }
    PF_CHECK(vals[1] > 0.99 && vals[3] < 0.99, "furnace %g (rms 0.02) %g (rms 0.4)", vals[1], vals[3]);
    pf_test_note("furnace at 30 deg: flat %.15f, rms 0.02 %.4f, 0.1 %.4f, 0.4 %.4f", vals[0], vals[1],
                 vals[2], vals[3]);
}

/* Visible mean of attribute 1 is 1 (to rounding); of the height, it rises with the view
   angle (Heitz & Neyret 2011 sec. 4: the visible points are the higher ones), and at normal
   incidence (everything visible, weights a_t = 1) it is the plain mean height. */
static void test_visible_mean(void)
{
    const double thetas[] = {0.0, 45.0, 60.0, 70.0, 80.0, 85.0};
    const int N = 128;
    pfm_surface s;
    unsigned char *vis = (unsigned char *)malloc((size_t)N * N);
    double *ones = (double *)malloc((size_t)N * N * sizeof(double)), prev = -1e300, mean_h = 0.0, m0 = 0.0;
    double hm[6];
    int i;
    if (!vis || !ones || pfm_surface_make(&s, N, N, 1.0, pfm_params_default(PFM_GAUSSIAN)) != 0) {
        PF_CHECK(0, "setup");
        free(vis);
        free(ones);
        return;
    }
    for (i = 0; i < N * N; ++i) {
        ones[i] = 1.0;
        mean_h += s.height[i] / (N * N);
    }
    for (i = 0; i < 6; ++i) {
        double w[3], one;
        dir_from_angles(deg(thetas[i]), 0.9, w);
        pfm_visibility_map(&s, w, vis);
        one = pfm_reference_visible_mean(&s, vis, NULL, 0, 0, N, w, ones);
        hm[i] = pfm_reference_visible_mean(&s, vis, NULL, 0, 0, N, w, s.height);
        PF_CHECK(fabs(one - 1.0) < 1e-15, "attribute 1 gives %.17g at %g deg", one, thetas[i]);
        if (i == 0) m0 = hm[i];
        /* strictly rising from 45 degrees on (below, nothing is masked: equal) */
        PF_CHECK(i == 0 || hm[i] > prev || (thetas[i] <= 45.0 && hm[i] >= prev - 1e-9),
                 "visible mean height %g at %g deg not above %g", hm[i], thetas[i], prev);
        prev = hm[i];
    }
    PF_CHECK(fabs(m0 - mean_h) < 1e-12, "normal incidence %g vs mean %g", m0, mean_h);
    pf_test_note("visible mean height (texels; map mean %.2g, rms slope 0.4): 60 deg %.3f, 70 %.3f, 80 %.3f, 85 %.3f",
                 mean_h, hm[2], hm[3], hm[4], hm[5]);
    free(vis);
    free(ones);
    pfm_surface_free(&s);
}

/* ------------------------------------------------------------------ edge cases (also -ffast-math) */

/* Degenerate directions and lobes: finite outputs, masking/joint in [0, 1], spec and diffuse
   >= 0; below-horizon directions see nothing; straight up sees everything. */
static void edge_reference_degenerate(void)
{
    pfm_surface s;
    const int N = 32;
    unsigned char *vo = (unsigned char *)malloc((size_t)N * N), *vi = (unsigned char *)malloc((size_t)N * N);
    const double thetas[] = {0.0, 1e-7, 0.5, 1.4, 1.5707, 1.57079632, 1.6, 3.1};
    const double sigmas[] = {1e-6, 1e-3, 0.1, 3.0, 50.0};
    int a, b, k, bad = 0, up_ok = 1, down_ok = 1, x, y;
    if (!vo || !vi || pfm_surface_make(&s, N, N, 1.0, pfm_params_default(PFM_TILES)) != 0) {
        PF_CHECK(0, "setup");
        free(vo);
        free(vi);
        return;
    }
    for (a = 0; a < 8; ++a) {
        double wo[3];
        dir_from_angles(thetas[a], 0.25, wo);
        pfm_visibility_map(&s, wo, vo);
        for (y = 0; y < N; ++y)
            for (x = 0; x < N; ++x) {
                if (thetas[a] == 0.0 && !vo[y * N + x]) up_ok = 0;
                if (thetas[a] > 1.5708 && vo[y * N + x]) down_ok = 0;
            }
        for (b = 0; b < 8; ++b) {
            double wi[3];
            dir_from_angles(thetas[b], 0.25 + 3.0 * b, wi);
            if (b == 7) { /* the exact opposite of wo */
                wi[0] = -wo[0];
                wi[1] = -wo[1];
                wi[2] = -wo[2];
            }
            pfm_visibility_map(&s, wi, vi);
            for (k = 0; k < 5; ++k) {
                pfm_shade r = pfm_reference_shade(&s, vo, vi, 7, 30, 8, wo, wi, sigmas[k], 0.04);
                double vals[7];
                int i;
                vals[0] = r.spec;
                vals[1] = r.diffuse;
                vals[2] = r.masking;
                vals[3] = r.joint;
                vals[4] = r.area;
                vals[5] = r.front_area;
                vals[6] = r.visible_area;
                for (i = 0; i < 7; ++i)
                    if (!(vals[i] > -1e300 && vals[i] < 1e300)) ++bad;
                if (!(r.spec >= 0.0) || !(r.diffuse >= 0.0) || !(r.masking >= 0.0 && r.masking <= 1.0) ||
                    !(r.joint >= 0.0 && r.joint <= r.masking))
                    ++bad;
            }
        }
    }
    PF_CHECK(bad == 0, "%d non-finite or out-of-range outputs", bad);
    PF_CHECK(up_ok, "a texel does not see straight up");
    PF_CHECK(down_ok, "a texel sees below the horizon");
    free(vo);
    free(vi);
    pfm_surface_free(&s);
}

/* In-footprint visibility at degenerate boxes and directions (also -ffast-math): an empty box
   (n = 0) holds no occluder, so a texel is visible exactly when it faces w (w.z > 0 and
   m.w > 0); a 1-texel box only adds the corners of the texel's own square beyond the
   half-texel skip (diagonal rays, horizontal distance 0.5 to 0.71): never visible when not
   facing, and occluded by those corners rarely (bound 3% of the facing texel-directions on
   the ridges' sharp crests); straight up is always visible; below the horizon never. */
static void edge_visible_box_degenerate(void)
{
    pfm_surface s;
    const int N = 32;
    const double thetas[] = {0.0, 1e-7, 0.7, 1.4, 1.5707, 1.5708, 2.0, 3.1};
    int a, x, y, bad = 0, corner = 0, facing_count = 0;
    if (pfm_surface_make(&s, N, N, 1.0, pfm_params_default(PFM_RIDGES)) != 0) {
        PF_CHECK(0, "make");
        return;
    }
    for (a = 0; a < 8; ++a) {
        double w[3];
        dir_from_angles(thetas[a], 0.3 + a, w);
        for (y = 0; y < N; ++y)
            for (x = 0; x < N; ++x) {
                double sx, sy;
                int facing, v1, v0, vbig;
                pfm_slope(&s, x, y, &sx, &sy);
                facing = w[2] > 0.0 && w[2] - sx * w[0] - sy * w[1] > 0.0;
                v1 = pfm_visible_box(&s, x, y, w, x, y, 1);
                v0 = pfm_visible_box(&s, x, y, w, x, y, 0);
                vbig = pfm_visible_box(&s, x, y, w, x - 3, y - 5, 2 * N);
                facing_count += facing;
                if (v0 != facing || (v1 && !facing)) ++bad;
                corner += facing && !v1;
                if (thetas[a] == 0.0 && !vbig) ++bad;
                if (thetas[a] > 1.5708 && vbig) ++bad;
            }
    }
    PF_CHECK(bad == 0, "%d failures", bad);
    PF_CHECK(corner * 100 <= 3 * facing_count, "1-texel box occludes %d of %d facing", corner, facing_count);
    pf_test_note("1-texel box: the square's corners occlude %d of %d facing texel-directions", corner, facing_count);
    pfm_surface_free(&s);
}

/* Generator edge cases: the smallest maps of every kind are finite and tile; bad sizes and
   parameters are refused (return -1, empty surface). */
static void edge_generator_small_and_bad(void)
{
    int k, bad = 0;
    pfm_surface s;
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    for (k = 0; k < PFM_KIND_COUNT; ++k) {
        long long i;
        if (pfm_surface_make(&s, 4, 8, 2.0, pfm_params_default(k)) != 0) {
            ++bad;
            continue;
        }
        for (i = 0; i < 32; ++i)
            if (!(s.height[i] > -1e300 && s.height[i] < 1e300)) ++bad;
        if (!(s.hmin <= s.hmax)) ++bad;
        pfm_surface_free(&s);
    }
    PF_CHECK(bad == 0, "%d failures on 4 x 8 maps", bad);
    PF_CHECK(pfm_surface_make(&s, 48, 64, 1.0, p) == -1 && s.height == NULL, "48 wide accepted");
    p.rms_slope = 0.0;
    PF_CHECK(pfm_surface_make(&s, 64, 64, 1.0, p) == -1 && s.height == NULL, "rms 0 accepted");
    p = pfm_params_default(PFM_GAUSSIAN);
    p.kind = PFM_KIND_COUNT;
    PF_CHECK(pfm_surface_make(&s, 64, 64, 1.0, p) == -1, "bad kind accepted");
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_generator_statistics);
    PF_TEST_RUN(test_generator_fine_footprints);
    PF_TEST_RUN(test_generator_gaussian_heights);
    PF_TEST_RUN(test_generator_periodic);
    PF_TEST_RUN(test_slopes_match_pyramid);
    PF_TEST_RUN(test_visibility_plane);
    PF_TEST_RUN(test_visibility_wall);
    PF_TEST_RUN(test_visibility_smooth_surface);
    PF_TEST_RUN(test_visibility_acceleration_exact);
    PF_TEST_RUN(test_visibility_smith_gaussian);
    PF_TEST_RUN(test_visibility_box_wall);
    PF_TEST_RUN(test_visibility_box_sampled);
    PF_TEST_RUN(test_visibility_box_maps);
    PF_TEST_RUN(test_reference_shade_set);
    PF_TEST_RUN(test_identity_projected_area);
    PF_TEST_RUN(test_identity_flat_plane);
    PF_TEST_RUN(test_identity_tilted_facet);
    PF_TEST_RUN(test_furnace_diffuse);
    PF_TEST_RUN(test_visible_mean);
    PF_TEST_RUN(edge_reference_degenerate);
    PF_TEST_RUN(edge_visible_box_degenerate);
    PF_TEST_RUN(edge_generator_small_and_bad);
    return PF_TEST_END();
}

/* pf_maps.h - the user's own height and normal maps as pfm surfaces (issue 18): the loaders
   behind `make bench MAP=...` (bench/microsurface.c, bench/pictures.c) and their tests
   (tests/maps/test_maps.c).

   PURPOSE
   Test and bench infrastructure, NOT part of the library: it lives in tests/, allocates, reads
   files, computes in double and decodes PNG with libpng (Debian libpng-dev; link -lpng). The
   header-only, no-dependency rule binds include/, not this. C99 and C++11; every function is
   static.

   WHAT IT READS
     height maps    PNG greyscale, 8 or 16 bits (1, 2, 4 bits are expanded to 8; an alpha
                    channel is ignored); the sample value v / (2^depth - 1) in [0, 1] is the
                    height. Raw float32: little-endian IEEE floats, row-major, top row first, no
                    header, the height in world units; its size is given as WxH
                    (pfmap_options.raw_w/raw_h, MAP_RAW_SIZE=WxH on the make line), or, when
                    not given, the file must hold a square map (4 n^2 bytes). A file is taken as
                    raw when it does not start with the PNG signature and its name ends in
                    .raw, .r32 or .f32; anything else that is not a PNG is an error.
     normal maps    PNG RGB or RGBA (alpha ignored), 8 or 16 bits, tangent space, each channel
                    c mapped to n = 2 c / (2^depth - 1) - 1. PFMAP_NORMAL_GL (OpenGL, "Y+"):
                    green is the normal's component toward the TOP of the image;
                    PFMAP_NORMAL_DX (DirectX, "Y-"): toward the bottom. Red is toward the
                    right, blue out of the image. The normals need not be unit (only the ratios
                    n.x/n.z, n.y/n.z are used); n.z below PFMAP_MIN_NZ is raised to it (slope
                    at most 1/PFMAP_MIN_NZ) and the count is reported.
   THE SURFACE (pfm_surface, texel = 1 world unit, tests/reference/pf_microsurface.h's conventions)
     Row y of the surface is image row h - 1 - y (y points up the image, x right, z out of
     it: a right-handed tangent frame, the OpenGL texture convention). The map is cropped to
     the largest power-of-two square that fits, centred (the march, the mip pyramids and the
     FFT need a power-of-two square); pfmap_info says what was kept. Borders:
       PFMAP_PERIODIC   the map tiles (the march and the slopes wrap): for seamless textures.
       PFMAP_MIRROR     for maps that do not tile: the (cropped) map is mirrored to a 2n x 2n
                        periodic map (heights reflected evenly about both far edges, so they
                        are continuous across every seam; slopes change sign there: a crease
                        along the seams). 4x the texels, so about 4x the bench's march time.
     Scale (height maps): rms_slope > 0 rescales the heights so that the RMS of the central-
     difference slopes (the mean of the x and y variances, as pfm_surface_make) is rms_slope;
     otherwise scale > 0 multiplies the heights (PNG: scale = the height of a full-white
     texel, in texels; raw: a factor on the stored values); with neither, rms_slope =
     PFMAP_DEFAULT_RMS_SLOPE. Normal maps: the slopes are the map's own (scale 1), scale > 0
     multiplies them (and the heights), rms_slope > 0 rescales them as above.
   NORMAL MAPS TO HEIGHTS: least-squares integration (Frankot and Chellappa 1988) on the
   periodic (or mirrored) domain, with the reference's own slope operator. Let p, q be the
   map's slopes (-n.x/n.z, -n.y/n.z). The heights h minimise
       sum over texels |Dx h - p|^2 + |Dy h - q|^2,
   Dx, Dy the central differences the reference shades with (pfm_slope). In the discrete
   Fourier basis Dx = i sin(kx), Dy = i sin(ky), so the minimiser is
       H(k) = -i (sin kx P(k) + sin ky Q(k)) / (sin^2 kx + sin^2 ky),
   and H = 0 where the denominator is 0 (the mean, and the three Nyquist points (pi, 0),
   (0, pi), (pi, pi), which central differences cannot see). Two FFTs forward, one back.
   Residual (pfmap_info.residual): RMS over texels of |D h - (p, q)| / RMS |(p, q)|, the
   part of the map that no height field reproduces. A normal map made from a height field by
   central differences integrates back to that height field to rounding (0 residual); made
   by other difference stencils or filtered or painted, it is not exactly a gradient (its
   discrete curl Dy p - Dx q is not 0) and the residual is that share. Where it cannot be
   trusted: a residual above ~0.1 (PFMAP_RESIDUAL_WARN: the report warns) means the normal
   map is far from any height field (hand-painted details, normals blended from several
   sources, detail maps, DirectX/OpenGL confused: swapping the green convention of a real map
   turns its curl-free part into curl and the residual jumps), and then the heights (which
   the reference marches for masking and shadowing) are the nearest height field, not the
   map; the slope statistics of the surface are those of the integrated heights. Mirrored
   borders add a crease (the slopes flip sign at the seam), which the integration follows.

   USAGE
     pfmap_options o = pfmap_options_default();   o.kind = PFMAP_NORMAL_GL;
     pfm_surface s;  pfmap_info info;  char err[512];
     if (pfmap_load("rock_n.png", &o, &s, &info, err, sizeof err) != 0) { puts(err); exit(1); }
     ... pfm_surface as from pfm_surface_make (hmin, hmax, march blocks set) ...
     pfmap_stats st;  pfmap_slope_stats(&s, &st);
     pfm_surface_free(&s);

   FUNCTIONS
     pfmap_options_default, pfmap_kind_parse, pfmap_kind_name, pfmap_parse_option (the bench
     programs' --map-NAME VALUE options), pfmap_load (file -> surface),
     pfmap_from_heights, pfmap_from_normals (in-memory grids -> surface: what pfmap_load does
     after decoding), pfmap_integrate (slopes -> heights, Frankot-Chellappa), pfmap_slope_stats
     (RMS, skewness, kurtosis, anisotropy, correlation length), and the writers the tests use to
     make their files: pfmap_write_png_grey, pfmap_write_png_rgb, pfmap_write_raw.

   ERRORS
     Every failure returns non-zero with one line in err (file name, what is wrong, what to
     do) and leaves the surface empty: no such file, not a PNG (and not a .raw/.r32/.f32),
     truncated or corrupt PNG (libpng's message), wrong colour type for the kind, raw file
     whose size is not 4 w h bytes, a NaN or infinity in a raw map (its texel), a map smaller
     than PFMAP_MIN_SIDE or larger than PFMAP_MAX_SIDE, a flat map (zero slope variance: no
     surface to filter), no memory. Nothing is written by the loader.

   SOURCES
     Frankot and Chellappa 1988, "A method for enforcing integrability in shape from shading
     algorithms" (IEEE PAMI 10(4)); libpng 1.6 manual (png_read_png-style progressive rows). */
#ifndef PF_MAPS_H
#define PF_MAPS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <png.h>

#include "pf_microsurface.h"

#define PFMAP_MIN_SIDE 8          /* after cropping: smaller maps are refused */
#define PFMAP_MAX_SIDE 8192       /* larger files are refused (memory, run time) */
#define PFMAP_DEFAULT_RMS_SLOPE 0.3 /* height maps without scale or rms_slope */
#define PFMAP_MIN_NZ 0.05         /* normal maps: n.z raised to this (slope <= 20) */
#define PFMAP_RESIDUAL_WARN 0.1   /* integration residual above which the report warns */

enum { PFMAP_HEIGHT = 0, PFMAP_NORMAL_GL, PFMAP_NORMAL_DX };
enum { PFMAP_PERIODIC = 0, PFMAP_MIRROR };

typedef struct {
    int kind;          /* PFMAP_HEIGHT, PFMAP_NORMAL_GL, PFMAP_NORMAL_DX */
    int border;        /* PFMAP_PERIODIC or PFMAP_MIRROR */
    double scale;      /* > 0: height multiplier (see Scale); 0: unset */
    double rms_slope;  /* > 0: target RMS slope; 0: unset (both set: rms_slope wins) */
    int raw_w, raw_h;  /* raw float32 size; 0: square from the file size */
} pfmap_options;

typedef struct {
    char format[64];        /* "PNG 16-bit grey", "PNG 8-bit RGB", "raw float32" */
    int file_w, file_h;     /* size in the file */
    int crop_x, crop_y, crop_n; /* the kept square: columns crop_x.., rows crop_y.. (from the top) */
    int w, h;               /* the surface (2 crop_n when mirrored) */
    double factor;          /* factor applied to the file's heights (height maps) or slopes (normal) */
    double rms_slope;       /* RMS slope of the surface (mean of the x and y variances) */
    double residual;        /* normal maps: integration residual (see above); 0 for height maps */
    double residual_max;    /* normal maps: largest |D h - (p, q)| over the texels (slope units) */
    long clamped;           /* normal maps: texels whose n.z was raised to PFMAP_MIN_NZ */
} pfmap_info;

typedef struct {
    double rms_x, rms_y;        /* RMS of the x and y slopes (about 0) */
    double mean_x, mean_y;
    double skew_x, skew_y, kurt_x, kurt_y; /* standardized 3rd and 4th moments per axis */
    double kurt_r;              /* 1.5 E|d|^4 / E[|d|^2]^2, d = s - mean (2D): 3 for an isotropic Gaussian */
    double aniso;               /* sqrt(smaller / larger eigenvalue of the slope covariance), <= 1 */
    double aniso_angle_deg;     /* direction of the larger eigenvalue, degrees from +x */
    double corr;                /* correlation length of the heights, texels: the radius where
                                   the (radially averaged, periodic) autocorrelation falls to
                                   1/e of its value at 0 (L of exp(-r^2 / L^2)) */
} pfmap_stats;

#if defined(__GNUC__) || defined(__clang__)
#  define PFMAP_FN static __attribute__((unused))
#else
#  define PFMAP_FN static
#endif

PFMAP_FN pfmap_options pfmap_options_default(void)
{
    pfmap_options o;
    memset(&o, 0, sizeof o);
    o.kind = PFMAP_HEIGHT;
    o.border = PFMAP_PERIODIC;
    return o;
}

/* "height", "normal-gl" (or "normal", "gl"), "normal-dx" ("dx") -> PFMAP_*; -1 otherwise. */
PFMAP_FN int pfmap_kind_parse(const char *s)
{
    if (!s || !*s || !strcmp(s, "height")) return PFMAP_HEIGHT;
    if (!strcmp(s, "normal-gl") || !strcmp(s, "normal") || !strcmp(s, "gl")) return PFMAP_NORMAL_GL;
    if (!strcmp(s, "normal-dx") || !strcmp(s, "dx")) return PFMAP_NORMAL_DX;
    return -1;
}

PFMAP_FN const char *pfmap_kind_name(int kind)
{
    return kind == PFMAP_NORMAL_GL ? "normal map (OpenGL, green up)"
         : kind == PFMAP_NORMAL_DX ? "normal map (DirectX, green down)" : "height map";
}

/* One command-line option of the bench programs: name (after "--map-") and value, as
   `make bench MAP=...` passes them: kind (height, normal-gl, normal-dx), border (periodic;
   clamped = mirror), scale, rms-slope (positive numbers; empty: unset), raw-size (WxH;
   empty: unset). 0 on success, 1 with err set on an unknown name or a bad value. */
PFMAP_FN int pfmap_parse_option(const char *name, const char *v, pfmap_options *o, char *err, size_t nerr)
{
    int bad = 0;
    if (!strcmp(name, "kind")) {
        int k = pfmap_kind_parse(v);
        bad = k < 0;
        if (!bad) o->kind = k;
    } else if (!strcmp(name, "border")) {
        if (!*v || !strcmp(v, "periodic")) o->border = PFMAP_PERIODIC;
        else if (!strcmp(v, "clamped") || !strcmp(v, "clamp") || !strcmp(v, "mirror")) o->border = PFMAP_MIRROR;
        else bad = 1;
    } else if (!strcmp(name, "raw-size")) {
        if (*v) bad = sscanf(v, "%dx%d", &o->raw_w, &o->raw_h) != 2 || o->raw_w < 1 || o->raw_h < 1;
    } else if (!strcmp(name, "scale") || !strcmp(name, "rms-slope")) {
        if (*v) {
            char *end = NULL;
            double x = strtod(v, &end);
            bad = !end || *end || !(x > 0.0 && x < 1e30);
            if (!strcmp(name, "scale")) o->scale = x;
            else o->rms_slope = x;
        }
    } else
        bad = 1;
    if (bad && err && nerr)
        snprintf(err, nerr, "bad --map-%s '%s' (kind: height, normal-gl, normal-dx; border: periodic, clamped; "
                 "scale, rms-slope: a positive number; raw-size: WxH)", name, v);
    if (!bad && o->scale > 0.0 && o->rms_slope > 0.0) {
        if (err && nerr) snprintf(err, nerr, "give MAP_SCALE or MAP_RMS_SLOPE, not both");
        return 1;
    }
    return bad;
}

/* ================================================================ small helpers */
static void pfmapi_err(char *err, size_t n, const char *fmt, const char *a, const char *b)
{
    if (err && n) snprintf(err, n, fmt, a, b);
}

PFMAP_FN int pfmapi_pow2_floor(int n)
{
    int p = 1;
    while (p <= n / 2) p *= 2;
    return p;
}

/* 2D FFT of w x h complex values (powers of two) in place; sign -1 forward, +1 inverse
   (unscaled). Returns 0, -1 without memory. */
PFMAP_FN int pfmapi_fft2(double *re, double *im, int w, int h, int sign)
{
    int x, y, m = w > h ? w : h;
    double *tr = (double *)malloc((size_t)m * 2 * sizeof(double)), *ti;
    if (!tr) return -1;
    ti = tr + m;
    for (y = 0; y < h; ++y) pfmi_fft(re + (size_t)y * w, im + (size_t)y * w, w, sign);
    for (x = 0; x < w; ++x) {
        for (y = 0; y < h; ++y) {
            tr[y] = re[(size_t)y * w + x];
            ti[y] = im[(size_t)y * w + x];
        }
        pfmi_fft(tr, ti, h, sign);
        for (y = 0; y < h; ++y) {
            re[(size_t)y * w + x] = tr[y];
            im[(size_t)y * w + x] = ti[y];
        }
    }
    free(tr);
    return 0;
}

/* ================================================================ integration */

/* Heights from slopes p (x), q (y) on a periodic n x n grid (n a power of two), texel 1:
   the least-squares solution for central differences (Frankot-Chellappa, see the header),
   mean 0. h: n n doubles. Returns 0, -1 without memory or bad size. */
PFMAP_FN int pfmap_integrate(const double *p, const double *q, int n, double *h)
{
    size_t N = (size_t)n * (size_t)n, i;
    double *pr, *pi_, *qr, *qi;
    int x, y;
    if (!pfmi_is_pow2(n) || n < 2) return -1;
    pr = (double *)calloc(N * 4, sizeof(double));
    if (!pr) return -1;
    pi_ = pr + N;
    qr = pi_ + N;
    qi = qr + N;
    for (i = 0; i < N; ++i) {
        pr[i] = p[i];
        qr[i] = q[i];
    }
    if (pfmapi_fft2(pr, pi_, n, n, -1) != 0 || pfmapi_fft2(qr, qi, n, n, -1) != 0) {
        free(pr);
        return -1;
    }
    for (y = 0; y < n; ++y) {
        double sy = sin(2.0 * PFM_PI * (double)y / (double)n);
        for (x = 0; x < n; ++x) {
            double sx = sin(2.0 * PFM_PI * (double)x / (double)n);
            double den = sx * sx + sy * sy;
            size_t k = (size_t)y * n + x;
            /* exact zeros of sin at 0 and pi; elsewhere den >= sin^2(2 pi / n) */
            if (den < 1e-20 || (x % (n / 2) == 0 && y % (n / 2) == 0)) {
                pr[k] = pi_[k] = 0.0;
                continue;
            }
            {
                /* H = -i (sx P + sy Q) / den: re(H) = (sx Pi + sy Qi) / den, im(H) = -(sx Pr + sy Qr) / den */
                double ar = sx * pr[k] + sy * qr[k], ai = sx * pi_[k] + sy * qi[k];
                pr[k] = ai / den;
                pi_[k] = -ar / den;
            }
        }
    }
    if (pfmapi_fft2(pr, pi_, n, n, 1) != 0) {
        free(pr);
        return -1;
    }
    for (i = 0; i < N; ++i) h[i] = pr[i] / (double)N;
    free(pr);
    return 0;
}

/* ================================================================ statistics */

/* Slope statistics of a surface (central differences, wrapping) and the correlation length of
   its heights (periodic autocorrelation by FFT; square power-of-two surfaces, else corr = 0). */
PFMAP_FN void pfmap_slope_stats(const pfm_surface *s, pfmap_stats *st)
{
    long long n = (long long)s->w * s->h;
    double mx = 0, my = 0, cxx = 0, cyy = 0, cxy = 0, m3x = 0, m3y = 0, m4x = 0, m4y = 0, r4 = 0;
    int x, y;
    memset(st, 0, sizeof *st);
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            double sx, sy;
            pfm_slope(s, x, y, &sx, &sy);
            mx += sx;
            my += sy;
        }
    mx /= (double)n;
    my /= (double)n;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            double sx, sy, dx, dy;
            pfm_slope(s, x, y, &sx, &sy);
            dx = sx - mx;
            dy = sy - my;
            cxx += dx * dx;
            cyy += dy * dy;
            cxy += dx * dy;
            m3x += dx * dx * dx;
            m3y += dy * dy * dy;
            m4x += dx * dx * dx * dx;
            m4y += dy * dy * dy * dy;
            r4 += (dx * dx + dy * dy) * (dx * dx + dy * dy);
        }
    cxx /= (double)n;
    cyy /= (double)n;
    cxy /= (double)n;
    st->mean_x = mx;
    st->mean_y = my;
    st->rms_x = sqrt(cxx);
    st->rms_y = sqrt(cyy);
    if (cxx > 0.0) {
        st->skew_x = m3x / (double)n / pow(cxx, 1.5);
        st->kurt_x = m4x / (double)n / (cxx * cxx);
    }
    if (cyy > 0.0) {
        st->skew_y = m3y / (double)n / pow(cyy, 1.5);
        st->kurt_y = m4y / (double)n / (cyy * cyy);
    }
    /* kurt_r: E|d|^4 / E[|d|^2]^2 scaled so that an isotropic Gaussian gives 3 (it gives 2) */
    if (cxx + cyy > 0.0) st->kurt_r = 1.5 * r4 / (double)n / ((cxx + cyy) * (cxx + cyy));
    {
        double tr = cxx + cyy, det = cxx * cyy - cxy * cxy, disc = sqrt(fmax(0.25 * tr * tr - det, 0.0));
        double l1 = 0.5 * tr + disc, l2 = 0.5 * tr - disc;
        st->aniso = l1 > 0.0 ? sqrt(fmax(l2, 0.0) / l1) : 1.0;
        st->aniso_angle_deg = 0.5 * atan2(2.0 * cxy, cxx - cyy) * 180.0 / PFM_PI;
    }
    if (s->w == s->h && pfmi_is_pow2(s->w)) {
        int N = s->w, r, rmax = N / 2;
        size_t NN = (size_t)N * N, i;
        double *re = (double *)calloc(NN * 2, sizeof(double)), *im, mean = 0.0;
        double *acc = (double *)calloc((size_t)rmax + 2, sizeof(double)), *cnt = (double *)calloc((size_t)rmax + 2, sizeof(double));
        if (re && acc && cnt) {
            im = re + NN;
            for (i = 0; i < NN; ++i) mean += s->height[i];
            mean /= (double)NN;
            for (i = 0; i < NN; ++i) re[i] = s->height[i] - mean;
            pfmapi_fft2(re, im, N, N, -1);
            for (i = 0; i < NN; ++i) {
                re[i] = re[i] * re[i] + im[i] * im[i];
                im[i] = 0.0;
            }
            pfmapi_fft2(re, im, N, N, 1); /* autocorrelation times N^2 */
            for (y = 0; y < N; ++y)
                for (x = 0; x < N; ++x) {
                    double dx = x < N / 2 ? x : x - N, dy = y < N / 2 ? y : y - N;
                    double rr = sqrt(dx * dx + dy * dy);
                    int b = (int)floor(rr + 0.5);
                    if (b > rmax) continue;
                    acc[b] += re[(size_t)y * N + x];
                    cnt[b] += 1.0;
                }
            if (acc[0] > 0.0) {
                double prev = 1.0, target = exp(-1.0);
                st->corr = (double)rmax;
                for (r = 1; r <= rmax; ++r) {
                    double c = cnt[r] > 0 ? acc[r] / cnt[r] / acc[0] : prev;
                    if (c <= target) {
                        st->corr = (double)(r - 1) + (prev - target) / (prev - c); /* linear between bins */
                        break;
                    }
                    prev = c;
                }
            }
        }
        free(re);
        free(acc);
        free(cnt);
    }
}

/* RMS slope of a height grid (mean of the x and y central-difference variances about 0, as
   pfm_surface_make normalises), periodic n x n, texel 1. */
PFMAP_FN double pfmapi_rms_slope(const double *h, int n)
{
    return sqrt(0.5 * (pfmi_slope_var(h, n, n, 1.0, 0.0) + pfmi_slope_var(h, n, n, 0.0, 1.0)));
}

/* ================================================================ grids -> surface */

/* Crop (centred power-of-two square) and mirror a w x h grid (row 0 = the surface's row 0)
   into out (side m = n or 2 n); sign_x, sign_y: the factor on reflected values along x and y
   (1 for heights; for slopes -1 along their own axis). */
PFMAP_FN void pfmapi_square(const double *g, int w, int x0, int y0, int n, int mirror, double sign_x,
                            double sign_y, double *out)
{
    int m = mirror ? 2 * n : n, x, y;
    for (y = 0; y < m; ++y)
        for (x = 0; x < m; ++x) {
            int sx = x < n ? x : 2 * n - 1 - x, sy = y < n ? y : 2 * n - 1 - y;
            double v = g[(size_t)(y0 + sy) * w + (size_t)(x0 + sx)];
            if (x >= n) v *= sign_x;
            if (y >= n) v *= sign_y;
            out[(size_t)y * m + x] = v;
        }
}

PFMAP_FN int pfmapi_check_size(int w, int h, const char *path, char *err, size_t nerr)
{
    char b[64];
    if (w < 1 || h < 1 || w > PFMAP_MAX_SIDE || h > PFMAP_MAX_SIDE) {
        snprintf(b, sizeof b, "%dx%d", w, h);
        pfmapi_err(err, nerr, "%s: map size %s is outside 8..8192 texels per side", path, b);
        return 1;
    }
    if (pfmapi_pow2_floor(w < h ? w : h) < PFMAP_MIN_SIDE) {
        snprintf(b, sizeof b, "%dx%d", w, h);
        pfmapi_err(err, nerr, "%s: map %s is too small (the kept power-of-two square must be at least 8 texels)", path, b);
        return 1;
    }
    return 0;
}

/* Finish a surface from its n x n heights (takes ownership of hh): scale, flat check, bounds. */
PFMAP_FN int pfmapi_finish(pfm_surface *s, double *hh, int m, double factor_hint, const pfmap_options *o,
                           int is_normal, const char *path, pfmap_info *info, char *err, size_t nerr)
{
    double rms = pfmapi_rms_slope(hh, m), f = 1.0;
    size_t i, N = (size_t)m * m;
    if (!(rms > 1e-12) || !(rms == rms)) {
        free(hh);
        pfmapi_err(err, nerr, "%s: the map is flat (zero slope variance after %s): nothing to filter; "
                   "check the file or the MAP_KIND", path, is_normal ? "integration" : "loading");
        return 1;
    }
    if (o->rms_slope > 0.0) f = o->rms_slope / rms;
    else if (o->scale > 0.0) f = o->scale;
    else if (!is_normal) f = PFMAP_DEFAULT_RMS_SLOPE / rms;
    for (i = 0; i < N; ++i) hh[i] *= f;
    if (pfm_surface_alloc(s, m, m, 1.0) != 0) {
        free(hh);
        pfmapi_err(err, nerr, "%s: out of memory%s", path, "");
        return 1;
    }
    free(s->height);
    s->height = hh;
    pfm_surface_bounds(s);
    if (info) {
        info->factor = f * factor_hint;
        info->rms_slope = rms * f;
        info->w = info->h = m;
    }
    return 0;
}

/* Heights (w x h grid, row 0 = the surface's row 0, i.e. the image's bottom row) -> surface:
   crop, mirror, scale as the options say. The grid is not kept. */
PFMAP_FN int pfmap_from_heights(const double *g, int w, int h, const pfmap_options *o, const char *path,
                                pfm_surface *s, pfmap_info *info, char *err, size_t nerr)
{
    int n, m, x0, y0;
    double *hh;
    memset(s, 0, sizeof *s);
    if (pfmapi_check_size(w, h, path, err, nerr)) return 1;
    n = pfmapi_pow2_floor(w < h ? w : h);
    m = o->border == PFMAP_MIRROR ? 2 * n : n;
    x0 = (w - n) / 2;
    y0 = (h - n) / 2;
    hh = (double *)malloc((size_t)m * m * sizeof(double));
    if (!hh) {
        pfmapi_err(err, nerr, "%s: out of memory%s", path, "");
        return 1;
    }
    pfmapi_square(g, w, x0, y0, n, o->border == PFMAP_MIRROR, 1.0, 1.0, hh);
    if (info) {
        info->crop_x = x0;
        info->crop_y = h - y0 - n; /* from the top of the image */
        info->crop_n = n;
        info->residual = info->residual_max = 0.0;
    }
    return pfmapi_finish(s, hh, m, 1.0, o, 0, path, info, err, nerr);
}

/* Slopes p (x), q (y) (w x h grids, row 0 = the surface's row 0) -> surface by least-squares
   integration (pfmap_integrate) after crop and mirror; info gets the residual. */
PFMAP_FN int pfmap_from_normals(const double *p, const double *q, int w, int h, const pfmap_options *o,
                                const char *path, pfm_surface *s, pfmap_info *info, char *err, size_t nerr)
{
    int n, m, x0, y0, x, y, mir = o->border == PFMAP_MIRROR;
    double *pp, *qq, *hh, r2 = 0.0, d2 = 0.0, dmax = 0.0;
    memset(s, 0, sizeof *s);
    if (pfmapi_check_size(w, h, path, err, nerr)) return 1;
    n = pfmapi_pow2_floor(w < h ? w : h);
    m = mir ? 2 * n : n;
    x0 = (w - n) / 2;
    y0 = (h - n) / 2;
    pp = (double *)malloc((size_t)m * m * 3 * sizeof(double));
    if (!pp) {
        pfmapi_err(err, nerr, "%s: out of memory%s", path, "");
        return 1;
    }
    qq = pp + (size_t)m * m;
    hh = (double *)malloc((size_t)m * m * sizeof(double));
    if (!hh) {
        free(pp);
        pfmapi_err(err, nerr, "%s: out of memory%s", path, "");
        return 1;
    }
    /* reflecting across x flips the x slope, across y the y slope */
    pfmapi_square(p, w, x0, y0, n, mir, -1.0, 1.0, pp);
    pfmapi_square(q, w, x0, y0, n, mir, 1.0, -1.0, qq);
    if (pfmap_integrate(pp, qq, m, hh) != 0) {
        free(pp);
        free(hh);
        pfmapi_err(err, nerr, "%s: out of memory%s", path, "");
        return 1;
    }
    for (y = 0; y < m; ++y)
        for (x = 0; x < m; ++x) {
            size_t k = (size_t)y * m + x;
            double sx = 0.5 * (hh[(size_t)y * m + (size_t)((x + 1) % m)] - hh[(size_t)y * m + (size_t)((x + m - 1) % m)]);
            double sy = 0.5 * (hh[(size_t)((y + 1) % m) * m + x] - hh[(size_t)((y + m - 1) % m) * m + x]);
            double e = (sx - pp[k]) * (sx - pp[k]) + (sy - qq[k]) * (sy - qq[k]);
            d2 += e;
            r2 += pp[k] * pp[k] + qq[k] * qq[k];
            if (sqrt(e) > dmax) dmax = sqrt(e);
        }
    free(pp);
    if (info) {
        info->crop_x = x0;
        info->crop_y = h - y0 - n;
        info->crop_n = n;
        info->residual = r2 > 0.0 ? sqrt(d2 / r2) : 0.0;
        info->residual_max = dmax;
    }
    if (pfmapi_finish(s, hh, m, 1.0, o, 1, path, info, err, nerr) != 0) return 1;
    if (info) info->residual_max *= info->factor;
    return 0;
}

/* ================================================================ PNG (libpng) */
typedef struct {
    char msg[256];
} pfmapi_png_err;

static void pfmapi_png_error(png_structp png, png_const_charp msg)
{
    pfmapi_png_err *e = (pfmapi_png_err *)png_get_error_ptr(png);
    if (e) snprintf(e->msg, sizeof e->msg, "%s", msg);
    png_longjmp(png, 1);
}
static void pfmapi_png_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* warnings (e.g. unknown chunks) do not stop the load */
}

/* Decode a PNG into doubles in [0, 1]: *chan = 1 (grey) or 3 (RGB) values per texel, rows
   from the top. Alpha is stripped, palettes expanded to RGB, low bit depths to 8, 16-bit
   samples kept whole. Returns 0, or 1 with err set. The variables that change between
   setjmp and a longjmp are volatile (-Wclobbered). */
PFMAP_FN int pfmapi_png_read(FILE *fp, const char *path, double **out, int *w, int *h, int *chan, int *depth,
                             char *err, size_t nerr)
{
    pfmapi_png_err pe;
    png_structp png;
    png_infop info;
    unsigned char *volatile buf = NULL;
    png_bytep *volatile rows = NULL;
    double *volatile vals = NULL;
    png_uint_32 W, H;
    int bd, ct, nch, y;
    size_t rowbytes, x;
    pe.msg[0] = 0;
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &pe, pfmapi_png_error, pfmapi_png_warning);
    if (!png) {
        pfmapi_err(err, nerr, "%s: libpng could not start%s", path, "");
        return 1;
    }
    info = png_create_info_struct(png);
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        pfmapi_err(err, nerr, "%s: libpng could not start%s", path, "");
        return 1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        free(buf);
        free(rows);
        free(vals);
        pfmapi_err(err, nerr, "%s: truncated or corrupt PNG (libpng: %s)", path, pe.msg);
        return 1;
    }
    png_init_io(png, fp);
    png_set_user_limits(png, PFMAP_MAX_SIDE, PFMAP_MAX_SIDE);
    png_read_info(png, info);
    W = png_get_image_width(png, info);
    H = png_get_image_height(png, info);
    bd = png_get_bit_depth(png, info);
    ct = png_get_color_type(png, info);
    if (ct == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (ct == PNG_COLOR_TYPE_GRAY && bd < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (ct & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
    if (bd == 16) png_set_swap(png); /* 16-bit samples little-endian in the row buffer */
    png_read_update_info(png, info);
    nch = png_get_channels(png, info);
    bd = png_get_bit_depth(png, info);
    rowbytes = png_get_rowbytes(png, info);
    buf = (unsigned char *)malloc(rowbytes * H);
    rows = (png_bytep *)malloc(sizeof(png_bytep) * H);
    vals = (double *)malloc(sizeof(double) * (size_t)W * H * (nch >= 3 ? 3 : 1));
    if (!buf || !rows || !vals || (nch != 1 && nch != 3)) {
        png_destroy_read_struct(&png, &info, NULL);
        free(buf);
        free(rows);
        free(vals);
        pfmapi_err(err, nerr, (nch != 1 && nch != 3) ? "%s: unsupported PNG channel layout%s" : "%s: out of memory%s",
                   path, "");
        return 1;
    }
    for (y = 0; y < (int)H; ++y) rows[y] = buf + rowbytes * (size_t)y;
    png_read_image(png, rows);
    png_read_end(png, NULL);
    {
        double maxv = bd == 16 ? 65535.0 : 255.0;
        size_t nv = (size_t)W * nch;
        for (y = 0; y < (int)H; ++y)
            for (x = 0; x < nv; ++x) {
                const unsigned char *r = rows[y];
                double v;
                if (bd == 16) {
                    /* png_set_swap gave little-endian samples */
                    v = (double)(r[2 * x] | (r[2 * x + 1] << 8));
                } else
                    v = (double)r[x];
                vals[(size_t)y * nv + x] = v / maxv;
            }
    }
    png_destroy_read_struct(&png, &info, NULL);
    free(buf);
    free(rows);
    *out = vals;
    *w = (int)W;
    *h = (int)H;
    *chan = nch;
    *depth = bd;
    return 0;
}

/* ================================================================ file -> surface */
PFMAP_FN int pfmapi_ends_with(const char *s, const char *suf)
{
    size_t a = strlen(s), b = strlen(suf);
    return a >= b && !strcmp(s + a - b, suf);
}

/* Load a height or normal map file into a periodic pfm surface (see the header). 0 on
   success; otherwise 1 with one line in err, and s empty. info may be NULL. */
PFMAP_FN int pfmap_load(const char *path, const pfmap_options *o, pfm_surface *s, pfmap_info *info,
                        char *err, size_t nerr)
{
    unsigned char sig[8];
    size_t got;
    FILE *fp;
    pfmap_info tmp;
    int rc;
    if (!info) info = &tmp;
    memset(info, 0, sizeof *info);
    memset(s, 0, sizeof *s);
    if (err && nerr) err[0] = 0;
    if (o->kind < PFMAP_HEIGHT || o->kind > PFMAP_NORMAL_DX || (o->border != PFMAP_PERIODIC && o->border != PFMAP_MIRROR)) {
        pfmapi_err(err, nerr, "%s: bad options (kind or border)%s", path, "");
        return 1;
    }
    fp = fopen(path, "rb");
    if (!fp) {
        pfmapi_err(err, nerr, "%s: cannot open the map (no such file or not readable)%s", path, "");
        return 1;
    }
    got = fread(sig, 1, 8, fp);
    if (got == 8 && !png_sig_cmp(sig, 0, 8)) {
        double *v = NULL;
        int w, h, ch, bd;
        if (fseek(fp, 0, SEEK_SET) != 0) {
            fclose(fp);
            pfmapi_err(err, nerr, "%s: cannot read the file%s", path, "");
            return 1;
        }
        rc = pfmapi_png_read(fp, path, &v, &w, &h, &ch, &bd, err, nerr);
        fclose(fp);
        if (rc) return 1;
        info->file_w = w;
        info->file_h = h;
        snprintf(info->format, sizeof info->format, "PNG %d-bit %s", bd, ch == 1 ? "grey" : "RGB");
        if (o->kind == PFMAP_HEIGHT && ch != 1) {
            free(v);
            pfmapi_err(err, nerr, "%s: a height map must be a greyscale PNG (this one is %s); for a normal map "
                       "give MAP_KIND=normal-gl or normal-dx", path, "RGB");
            return 1;
        }
        if (o->kind != PFMAP_HEIGHT && ch != 3) {
            free(v);
            pfmapi_err(err, nerr, "%s: a normal map must be an RGB PNG (this one is %s); for a height map give "
                       "MAP_KIND=height", path, "greyscale");
            return 1;
        }
        if (o->kind == PFMAP_HEIGHT) {
            /* flip rows: surface row y = image row h - 1 - y */
            double *g = (double *)malloc(sizeof(double) * (size_t)w * h);
            int y;
            if (!g) {
                free(v);
                pfmapi_err(err, nerr, "%s: out of memory%s", path, "");
                return 1;
            }
            for (y = 0; y < h; ++y) memcpy(g + (size_t)y * w, v + (size_t)(h - 1 - y) * w, sizeof(double) * (size_t)w);
            free(v);
            rc = pfmap_from_heights(g, w, h, o, path, s, info, err, nerr);
            free(g);
            return rc;
        } else {
            double *p = (double *)malloc(sizeof(double) * (size_t)w * h * 2), *q;
            double gsign = o->kind == PFMAP_NORMAL_GL ? 1.0 : -1.0;
            int x, y;
            if (!p) {
                free(v);
                pfmapi_err(err, nerr, "%s: out of memory%s", path, "");
                return 1;
            }
            q = p + (size_t)w * h;
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    const double *c = v + 3 * ((size_t)(h - 1 - y) * w + x);
                    double nx = 2.0 * c[0] - 1.0, ny = gsign * (2.0 * c[1] - 1.0), nz = 2.0 * c[2] - 1.0;
                    if (nz < PFMAP_MIN_NZ) {
                        nz = PFMAP_MIN_NZ;
                        info->clamped++;
                    }
                    /* n ~ (-dh/dx, -dh/dy, 1) with y up the image */
                    p[(size_t)y * w + x] = -nx / nz;
                    q[(size_t)y * w + x] = -ny / nz;
                }
            free(v);
            rc = pfmap_from_normals(p, q, w, h, o, path, s, info, err, nerr);
            free(p);
            return rc;
        }
    }
    /* not a PNG: raw float32 if the name says so */
    if (!(pfmapi_ends_with(path, ".raw") || pfmapi_ends_with(path, ".r32") || pfmapi_ends_with(path, ".f32"))) {
        fclose(fp);
        pfmapi_err(err, nerr, "%s: not a PNG file (no PNG signature), and not a raw float32 map (.raw, .r32 or "
                   ".f32)%s", path, "");
        return 1;
    }
    if (o->kind != PFMAP_HEIGHT) {
        fclose(fp);
        pfmapi_err(err, nerr, "%s: raw float32 files are height maps; normal maps must be RGB PNG%s", path, "");
        return 1;
    }
    {
        long bytes;
        int w = o->raw_w, h = o->raw_h, x, y;
        float *f;
        double *g;
        char b[128];
        if (fseek(fp, 0, SEEK_END) != 0 || (bytes = ftell(fp)) < 0 || fseek(fp, 0, SEEK_SET) != 0) {
            fclose(fp);
            pfmapi_err(err, nerr, "%s: cannot read the file%s", path, "");
            return 1;
        }
        if (w <= 0 || h <= 0) {
            long side = (long)floor(sqrt((double)bytes / 4.0) + 0.5);
            if (side * side * 4 != bytes || side < 1) {
                fclose(fp);
                snprintf(b, sizeof b, "%ld bytes", bytes);
                pfmapi_err(err, nerr, "%s: raw float32 map of %s is not a square of floats; give its size "
                           "(MAP_RAW_SIZE=WxH)", path, b);
                return 1;
            }
            w = h = (int)side;
        }
        if (w > PFMAP_MAX_SIDE || h > PFMAP_MAX_SIDE || (long)w * h * 4 != bytes) {
            fclose(fp);
            snprintf(b, sizeof b, "%ld bytes where %dx%d float32 need %ld", bytes, w, h, (long)w * h * 4);
            pfmapi_err(err, nerr, "%s: wrong size: %s", path, b);
            return 1;
        }
        f = (float *)malloc(sizeof(float) * (size_t)w * h);
        g = (double *)malloc(sizeof(double) * (size_t)w * h);
        if (!f || !g) {
            free(f);
            free(g);
            fclose(fp);
            pfmapi_err(err, nerr, "%s: out of memory%s", path, "");
            return 1;
        }
        if (fread(f, sizeof(float), (size_t)w * h, fp) != (size_t)w * h) {
            free(f);
            free(g);
            fclose(fp);
            pfmapi_err(err, nerr, "%s: short read%s", path, "");
            return 1;
        }
        fclose(fp);
        info->file_w = w;
        info->file_h = h;
        snprintf(info->format, sizeof info->format, "raw float32 (little-endian)");
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                /* bytes little-endian whatever the host */
                unsigned char *c = (unsigned char *)&f[(size_t)y * w + x];
                unsigned long u = (unsigned long)c[0] | ((unsigned long)c[1] << 8) | ((unsigned long)c[2] << 16) |
                                  ((unsigned long)c[3] << 24);
                unsigned e = (unsigned)((u >> 23) & 0xffu);
                float fv;
                if (e == 0xffu) {
                    free(f);
                    free(g);
                    snprintf(b, sizeof b, "%s at column %d, row %d (from the top)", (u & 0x7fffffUL) ? "a NaN" : "an infinity",
                             x, y);
                    pfmapi_err(err, nerr, "%s: the raw map holds %s; every height must be finite", path, b);
                    return 1;
                }
                {
                    unsigned int ui = (unsigned int)u;
                    memcpy(&fv, &ui, sizeof fv);
                }
                g[(size_t)(h - 1 - y) * w + x] = (double)fv;
            }
        free(f);
        rc = pfmap_from_heights(g, w, h, o, path, s, info, err, nerr);
        free(g);
        return rc;
    }
}

/* ================================================================ writers (tests) */

/* Greyscale PNG of depth 8 or 16 from values in [0, 1] (clamped, rounded), rows from the top.
   0 on success. */
PFMAP_FN int pfmap_write_png(const char *path, const double *v, int w, int h, int chan, int depth)
{
    FILE *fp = fopen(path, "wb");
    png_structp png;
    png_infop info;
    unsigned char *volatile row = NULL;
    int x, y;
    double maxv = depth == 16 ? 65535.0 : 255.0;
    if (!fp) return 1;
    png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        fclose(fp);
        return 1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(row);
        fclose(fp);
        return 1;
    }
    png_init_io(png, fp);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, chan == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    row = (unsigned char *)malloc((size_t)w * chan * (depth == 16 ? 2 : 1));
    if (!row) png_error(png, "out of memory");
    for (y = 0; y < h; ++y) {
        for (x = 0; x < w * chan; ++x) {
            double c = v[(size_t)y * w * chan + x];
            unsigned q = (unsigned)floor((c < 0.0 ? 0.0 : (c > 1.0 ? 1.0 : c)) * maxv + 0.5);
            if (depth == 16) {
                row[2 * x] = (unsigned char)(q >> 8); /* PNG is big-endian */
                row[2 * x + 1] = (unsigned char)(q & 0xffu);
            } else
                row[x] = (unsigned char)q;
        }
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    return fclose(fp) != 0;
}

PFMAP_FN int pfmap_write_png_grey(const char *path, const double *v, int w, int h, int depth)
{
    return pfmap_write_png(path, v, w, h, 1, depth);
}

/* RGB PNG (rgb: 3 w h values in [0, 1], rows from the top). */
PFMAP_FN int pfmap_write_png_rgb(const char *path, const double *rgb, int w, int h, int depth)
{
    return pfmap_write_png(path, rgb, w, h, 3, depth);
}

/* Raw little-endian float32, rows from the top. */
PFMAP_FN int pfmap_write_raw(const char *path, const float *v, size_t n)
{
    FILE *fp = fopen(path, "wb");
    size_t i;
    if (!fp) return 1;
    for (i = 0; i < n; ++i) {
        unsigned int u;
        unsigned char c[4];
        memcpy(&u, &v[i], sizeof u);
        c[0] = (unsigned char)(u & 0xffu);
        c[1] = (unsigned char)((u >> 8) & 0xffu);
        c[2] = (unsigned char)((u >> 16) & 0xffu);
        c[3] = (unsigned char)((u >> 24) & 0xffu);
        if (fwrite(c, 1, 4, fp) != 4) {
            fclose(fp);
            return 1;
        }
    }
    return fclose(fp) != 0;
}

#endif /* PF_MAPS_H */

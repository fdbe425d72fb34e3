/* test_maps.c - tests of tests/reference/pf_maps.h, the loaders of the user's height and normal maps
   behind `make bench MAP=...` (issue 18).

   Built and run in every `make test` configuration like tests/test_*.c, but from tests/maps/
   with -lpng (Makefile, LIB_TESTS): the portability cells compile tests/test_*.c with -lm and
   cross compilers that have no libpng, so the one test that links a system library lives
   apart. Every file it reads it writes itself first, next to its own binary (argv[0] + a
   suffix: each build directory and configuration has its own), and removes.

   What is checked: the PNG loaders at 8 and 16 bits against the values written (exact), raw
   float32 with and without a given size (exact), the row order (row 0 of the surface is the
   image's bottom row), the centred power-of-two crop and the mirrored border, the scale and
   RMS-slope options; normal maps in both green conventions made from a known height field by
   central differences, integrated back (Frankot-Chellappa, pf_maps.h) to a stated error, and a
   swapped convention detected by its residual; slope statistics on the synthetic kinds; bad
   input (missing, non-PNG, truncated PNG, wrong colour type, raw of the wrong size, NaN and
   infinity in a raw map, a flat map): a non-zero return, one message naming the problem, an
   empty surface. edge_* cases (bad input) also run in the -ffast-math builds. */
#include "pf_core.h"
#include "pf_test.h"
#include "pf_maps.h"

static char tmp_base[900];

static const char *tmp_path(const char *suffix)
{
    static char ring[8][1024];
    static int next = 0;
    char *b = ring[next];
    next = (next + 1) % 8;
    snprintf(b, sizeof ring[0], "%s.%s", tmp_base, suffix);
    return b;
}

/* a smooth non-periodic test pattern in [0, 1], image rows from the top */
static double pattern(int x, int y, int w, int h)
{
    double u = (x + 0.5) / w, v = (y + 0.5) / h;
    return 0.5 + 0.3 * sin(6.0 * u + 1.0) * cos(4.0 * v) + 0.15 * (u - v);
}

static int surface_empty(const pfm_surface *s) { return s->height == NULL && s->w == 0 && s->h == 0; }

/* PNG grey 8 and 16 bits, non-power-of-two size: the kept square is the centred 16 x 16 of a
   40 x 24 image; heights = value / maxval * scale exactly (scale 2: white is 2 texels high);
   surface row y = image row h - 1 - y. */
static void test_png_grey_depths(void)
{
    int depth;
    for (depth = 8; depth <= 16; depth += 8) {
        const int w = 40, h = 24;
        double img[40 * 24], maxv = depth == 16 ? 65535.0 : 255.0, worst = 0.0;
        pfmap_options o = pfmap_options_default();
        pfmap_info info;
        pfm_surface s;
        char err[512];
        const char *path = tmp_path(depth == 8 ? "g8.png" : "g16.png");
        int x, y, rc;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) img[y * w + x] = floor(pattern(x, y, w, h) * maxv + 0.5) / maxv;
        PF_CHECK(pfmap_write_png_grey(path, img, w, h, depth) == 0, "cannot write %s", path);
        o.scale = 2.0;
        rc = pfmap_load(path, &o, &s, &info, err, sizeof err);
        PF_CHECK(rc == 0, "%d-bit load failed: %s", depth, err);
        if (rc != 0) continue;
        PF_CHECK(s.w == 16 && s.h == 16 && info.crop_n == 16 && info.crop_x == 12 && info.crop_y == 4,
                 "crop %dx%d at (%d, %d) n %d", s.w, s.h, info.crop_x, info.crop_y, info.crop_n);
        PF_CHECK(info.file_w == w && info.file_h == h, "file size %dx%d", info.file_w, info.file_h);
        PF_CHECK(strstr(info.format, depth == 8 ? "8-bit grey" : "16-bit grey") != NULL, "format %s", info.format);
        for (y = 0; y < 16; ++y)
            for (x = 0; x < 16; ++x) {
                /* surface row y = image row (crop_y + 15 - y) */
                double want = 2.0 * img[(info.crop_y + 15 - y) * w + info.crop_x + x];
                double d = fabs(s.height[y * 16 + x] - want);
                if (d > worst) worst = d;
            }
        PF_CHECK(worst <= 1e-12, "%d-bit heights off by %g", depth, worst);
        PF_CHECK(fabs(info.factor - 2.0) < 1e-15, "factor %g", info.factor);
        pf_test_note("%d-bit max height error %.1e", depth, worst);
        pfm_surface_free(&s);
        remove(path);
    }
}

/* Raw float32: the given size (non-square, 20 x 12 -> the centred 8 x 8) and the square default;
   values exact (scale 1 as a factor on the stored heights). */
static void test_raw_float32(void)
{
    const int w = 20, h = 12;
    float v[20 * 12], sq[32 * 32];
    const char *p1 = tmp_path("a.raw"), *p2 = tmp_path("b.f32");
    pfmap_options o = pfmap_options_default();
    pfmap_info info;
    pfm_surface s;
    char err[512];
    int x, y, rc;
    double worst = 0.0;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) v[y * w + x] = (float)(3.0 * pattern(x, y, w, h) - 1.0);
    PF_CHECK(pfmap_write_raw(p1, v, (size_t)w * h) == 0, "cannot write %s", p1);
    o.raw_w = w;
    o.raw_h = h;
    o.scale = 1.0;
    rc = pfmap_load(p1, &o, &s, &info, err, sizeof err);
    PF_CHECK(rc == 0, "raw load failed: %s", err);
    if (rc == 0) {
        PF_CHECK(s.w == 8 && info.crop_x == 6 && info.crop_y == 2, "raw crop %d at (%d, %d)", s.w, info.crop_x,
                 info.crop_y);
        for (y = 0; y < 8; ++y)
            for (x = 0; x < 8; ++x) {
                double d = fabs(s.height[y * 8 + x] - (double)v[(info.crop_y + 7 - y) * w + info.crop_x + x]);
                if (d > worst) worst = d;
            }
        PF_CHECK(worst == 0.0, "raw heights off by %g", worst);
        pfm_surface_free(&s);
    }
    for (y = 0; y < 32; ++y)
        for (x = 0; x < 32; ++x) sq[y * 32 + x] = (float)pattern(x, y, 32, 32);
    PF_CHECK(pfmap_write_raw(p2, sq, 32 * 32) == 0, "cannot write %s", p2);
    o.raw_w = o.raw_h = 0;
    rc = pfmap_load(p2, &o, &s, &info, err, sizeof err);
    PF_CHECK(rc == 0 && s.w == 32 && s.h == 32, "square raw: rc %d %s", rc, err);
    if (rc == 0) {
        PF_CHECK(s.height[0] == (double)sq[31 * 32], "raw row order");
        pfm_surface_free(&s);
    }
    pf_test_note("raw max error %g", worst);
    remove(p1);
    remove(p2);
}

/* Options: rms_slope rescales to the target (1e-12); the default (neither) gives
   PFMAP_DEFAULT_RMS_SLOPE; mirror doubles the side, reflects the heights evenly (continuous
   across the seams), and keeps the original quadrant. */
static void test_scale_and_mirror(void)
{
    const int n = 32;
    double img[32 * 32];
    const char *path = tmp_path("m16.png");
    pfmap_options o = pfmap_options_default();
    pfmap_info info;
    pfm_surface s, m;
    char err[512];
    int x, y, rc, bad = 0;
    for (y = 0; y < n; ++y)
        for (x = 0; x < n; ++x) img[y * n + x] = pattern(x, y, n, n);
    PF_CHECK(pfmap_write_png_grey(path, img, n, n, 16) == 0, "write");
    o.rms_slope = 0.37;
    rc = pfmap_load(path, &o, &s, &info, err, sizeof err);
    PF_CHECK(rc == 0, "%s", err);
    if (rc != 0) return;
    PF_CHECK(fabs(info.rms_slope / 0.37 - 1.0) < 1e-12 && fabs(pfmapi_rms_slope(s.height, n) / 0.37 - 1.0) < 1e-12,
             "rms %.15g", info.rms_slope);
    o.rms_slope = 0.0;
    o.border = PFMAP_MIRROR;
    rc = pfmap_load(path, &o, &m, &info, err, sizeof err);
    PF_CHECK(rc == 0, "%s", err);
    if (rc == 0) {
        PF_CHECK(m.w == 2 * n && m.h == 2 * n, "mirror size %d", m.w);
        PF_CHECK(fabs(info.rms_slope / PFMAP_DEFAULT_RMS_SLOPE - 1.0) < 1e-12, "default rms %.15g", info.rms_slope);
        for (y = 0; y < 2 * n; ++y)
            for (x = 0; x < 2 * n; ++x) {
                double a = m.height[y * 2 * n + x];
                if (a != m.height[y * 2 * n + (2 * n - 1 - x)] || a != m.height[(2 * n - 1 - y) * 2 * n + x]) ++bad;
            }
        PF_CHECK(bad == 0, "%d texels not mirror-symmetric", bad);
        /* the original quadrant is the periodic load up to the scale factor */
        {
            double k = m.height[1] / s.height[1], worst = 0.0;
            for (y = 0; y < n; ++y)
                for (x = 0; x < n; ++x) worst = fmax(worst, fabs(m.height[y * 2 * n + x] - k * s.height[y * n + x]));
            PF_CHECK(worst < 1e-12, "quadrant differs by %g", worst);
        }
        pfm_surface_free(&m);
    }
    pfm_surface_free(&s);
    remove(path);
}

/* Encode a surface's central-difference slopes as a tangent-space normal map (image rows from
   the top; surface row y = image row n - 1 - y; GL: green = n.y up the image, DX: down). */
static void encode_normals(const pfm_surface *s, int dx_convention, double *rgb)
{
    int n = s->w, x, y;
    for (y = 0; y < n; ++y)
        for (x = 0; x < n; ++x) {
            double m[3], *c = rgb + 3 * ((size_t)(n - 1 - y) * n + x);
            pfm_normal(s, x, y, m);
            c[0] = 0.5 * (m[0] + 1.0);
            c[1] = 0.5 * ((dx_convention ? -m[1] : m[1]) + 1.0);
            c[2] = 0.5 * (m[2] + 1.0);
        }
}

/* rel RMS of (a - mean a) - (b - mean b) over RMS of (b - mean b) */
static double height_error(const double *a, const double *b, size_t n)
{
    double ma = 0, mb = 0, e = 0, r = 0;
    size_t i;
    for (i = 0; i < n; ++i) {
        ma += a[i];
        mb += b[i];
    }
    ma /= (double)n;
    mb /= (double)n;
    for (i = 0; i < n; ++i) {
        double d = (a[i] - ma) - (b[i] - mb);
        e += d * d;
        r += (b[i] - mb) * (b[i] - mb);
    }
    return sqrt(e / r);
}

/* Normal maps from a known height field (a 128^2 Gaussian surface, correlation length 6, RMS
   slope 0.4), by central differences, both conventions, 8 and 16 bits: the integrated heights
   equal the original up to a constant to 1e-4 (16 bit; measured 1.2e-5) and 1e-2 (8 bit;
   measured 2.7e-3) of the height RMS (quantization of the normals: 1/65535 and 1/255 of a
   slope unit); the residual is at that level too (2e-5, 5e-3). The exact slopes (no file)
   integrate back to 1e-9 (measured 1e-15). Read with the wrong
   convention, the map is not a gradient (its curl is 2 d2h/dxdy): residual > 0.3 (measured
   0.72), so the
   report's warning (PFMAP_RESIDUAL_WARN = 0.1) fires. */
static void test_normal_integration(void)
{
    const int n = 128;
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    pfm_surface ref, s;
    pfmap_options o = pfmap_options_default();
    pfmap_info info;
    double *rgb = (double *)malloc(sizeof(double) * 3 * n * n), *pp = (double *)malloc(sizeof(double) * 2 * n * n);
    char err[512];
    int dx, depth, x, y, rc;
    p.corr_texels = 6.0;
    if (!rgb || !pp || pfm_surface_make(&ref, n, n, 1.0, p) != 0) {
        PF_CHECK(0, "setup");
        free(rgb);
        free(pp);
        return;
    }
    /* exact slopes, no file */
    for (y = 0; y < n; ++y)
        for (x = 0; x < n; ++x) pfm_slope(&ref, x, y, &pp[y * n + x], &pp[n * n + y * n + x]);
    o.scale = 1.0;
    rc = pfmap_from_normals(pp, pp + n * n, n, n, &o, "exact", &s, &info, err, sizeof err);
    PF_CHECK(rc == 0, "%s", err);
    if (rc == 0) {
        double e = height_error(s.height, ref.height, (size_t)n * n);
        PF_CHECK(e < 1e-9 && info.residual < 1e-9, "exact slopes: height error %g residual %g", e, info.residual);
        pf_test_note("exact: height %.1e residual %.1e", e, info.residual);
        pfm_surface_free(&s);
    }
    for (dx = 0; dx <= 1; ++dx)
        for (depth = 8; depth <= 16; depth += 8) {
            const char *path = tmp_path(dx ? "ndx.png" : "ngl.png");
            double bound = depth == 16 ? 1e-4 : 1e-2, e;
            encode_normals(&ref, dx, rgb);
            PF_CHECK(pfmap_write_png_rgb(path, rgb, n, n, depth) == 0, "write %s", path);
            o = pfmap_options_default();
            o.kind = dx ? PFMAP_NORMAL_DX : PFMAP_NORMAL_GL;
            rc = pfmap_load(path, &o, &s, &info, err, sizeof err);
            PF_CHECK(rc == 0, "%s", err);
            if (rc != 0) continue;
            e = height_error(s.height, ref.height, (size_t)n * n);
            PF_CHECK(e < bound && info.residual < bound, "%s %d-bit: height error %g residual %g (bound %g)",
                     dx ? "DX" : "GL", depth, e, info.residual, bound);
            PF_CHECK(fabs(info.rms_slope / 0.4 - 1.0) < 0.02, "rms slope %g", info.rms_slope);
            PF_CHECK(info.clamped == 0, "clamped %ld", info.clamped);
            pf_test_note("%s %d-bit: height %.1e residual %.1e", dx ? "DX" : "GL", depth, e, info.residual);
            pfm_surface_free(&s);
            /* the other convention */
            o.kind = dx ? PFMAP_NORMAL_GL : PFMAP_NORMAL_DX;
            rc = pfmap_load(path, &o, &s, &info, err, sizeof err);
            PF_CHECK(rc == 0 && info.residual > 0.3, "swapped convention: residual %g", info.residual);
            if (depth == 16 && dx == 0) pf_test_note("swapped: residual %.2f", info.residual);
            if (rc == 0) pfm_surface_free(&s);
            remove(path);
        }
    pfm_surface_free(&ref);
    free(rgb);
    free(pp);
}

/* Slope statistics against the generator's known values: Gaussian (L = 12): kurtosis 3 +- 0.7,
   correlation length 12 +- 15%; anisotropic Gaussian: aniso 0.3 +- 0.02, principal direction
   0.5 rad = 28.6 deg +- 3. */
static void test_slope_stats(void)
{
    pfm_surface s;
    pfmap_stats st;
    if (pfm_surface_make(&s, 512, 512, 1.0, pfm_params_default(PFM_GAUSSIAN)) == 0) {
        pfmap_slope_stats(&s, &st);
        PF_CHECK(fabs(st.kurt_x - 3.0) < 0.7 && fabs(st.kurt_r - 3.0) < 0.7, "kurt %g %g", st.kurt_x, st.kurt_r);
        PF_CHECK(fabs(st.corr / 12.0 - 1.0) < 0.15, "corr %g", st.corr);
        PF_CHECK(fabs(0.5 * (st.rms_x * st.rms_x + st.rms_y * st.rms_y) / 0.16 - 1.0) < 0.02, "rms %g %g", st.rms_x,
                 st.rms_y);
        pf_test_note("gaussian: kurt %.2f corr %.1f", st.kurt_x, st.corr);
        pfm_surface_free(&s);
    } else
        PF_CHECK(0, "make");
    if (pfm_surface_make(&s, 512, 512, 1.0, pfm_params_default(PFM_GAUSSIAN_ANISO)) == 0) {
        pfmap_slope_stats(&s, &st);
        PF_CHECK(fabs(st.aniso - 0.3) < 0.02, "aniso %g", st.aniso);
        PF_CHECK(fabs(st.aniso_angle_deg - 28.65) < 3.0, "angle %g", st.aniso_angle_deg);
        pf_test_note("aniso: %.3f at %.1f deg", st.aniso, st.aniso_angle_deg);
        pfm_surface_free(&s);
    } else
        PF_CHECK(0, "make");
}

/* one bad input: non-zero return, a message containing `want`, an empty surface */
static void expect_error(const char *path, const pfmap_options *o, const char *want)
{
    pfm_surface s;
    char err[512];
    int rc;
    err[0] = 0;
    rc = pfmap_load(path, o, &s, NULL, err, sizeof err);
    PF_CHECK(rc != 0, "%s: accepted (wanted an error with \"%s\")", path, want);
    PF_CHECK(strstr(err, want) != NULL, "%s: message \"%s\" lacks \"%s\"", path, err, want);
    PF_CHECK(surface_empty(&s), "%s: surface not empty after an error", path);
    if (rc == 0) pfm_surface_free(&s);
}

static void edge_bad_input(void)
{
    double img[64 * 64], rgb[3 * 16 * 16];
    float raw[16 * 16];
    pfmap_options o = pfmap_options_default();
    const char *png = tmp_path("bad.png"), *trunc = tmp_path("trunc.png"), *txt = tmp_path("text.png");
    const char *rawp = tmp_path("bad.raw"), *flat = tmp_path("flat.png"), *rgbp = tmp_path("rgb.png");
    FILE *f;
    long n;
    int i;
    char *buf;
    for (i = 0; i < 64 * 64; ++i) img[i] = pattern(i % 64, i / 64, 64, 64);
    /* missing file */
    expect_error(tmp_path("missing.png"), &o, "cannot open");
    /* not a PNG */
    f = fopen(txt, "wb");
    if (f) {
        fputs("this is not a PNG file at all\n", f);
        fclose(f);
    }
    expect_error(txt, &o, "not a PNG");
    /* truncated PNG: the first half of a valid one */
    PF_CHECK(pfmap_write_png_grey(png, img, 64, 64, 16) == 0, "write");
    f = fopen(png, "rb");
    buf = NULL;
    n = 0;
    if (f && fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0) {
        buf = (char *)malloc((size_t)n);
        if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) n = 0;
    }
    if (f) fclose(f);
    f = fopen(trunc, "wb");
    if (f && buf) {
        fwrite(buf, 1, (size_t)(n / 2), f);
        fclose(f);
    } else if (f)
        fclose(f);
    free(buf);
    expect_error(trunc, &o, "truncated or corrupt PNG");
    /* colour types: RGB as height, grey as normal */
    for (i = 0; i < 3 * 16 * 16; ++i) rgb[i] = i % 3 == 2 ? 1.0 : 0.5; /* every normal straight up */
    PF_CHECK(pfmap_write_png_rgb(rgbp, rgb, 16, 16, 8) == 0, "write");
    expect_error(rgbp, &o, "must be a greyscale PNG");
    o.kind = PFMAP_NORMAL_GL;
    expect_error(png, &o, "must be an RGB PNG");
    /* a flat normal map (every normal straight up) and a flat height map */
    expect_error(rgbp, &o, "flat");
    o.kind = PFMAP_HEIGHT;
    for (i = 0; i < 64 * 64; ++i) img[i] = 0.25;
    PF_CHECK(pfmap_write_png_grey(flat, img, 64, 64, 8) == 0, "write");
    expect_error(flat, &o, "flat");
    o.rms_slope = 0.3;
    expect_error(flat, &o, "flat");
    o.rms_slope = 0.0;
    /* raw: wrong size, not square without a size, NaN, infinity, raw normal map */
    for (i = 0; i < 16 * 16; ++i) raw[i] = (float)pattern(i % 16, i / 16, 16, 16);
    PF_CHECK(pfmap_write_raw(rawp, raw, 16 * 16 - 3) == 0, "write");
    expect_error(rawp, &o, "not a square");
    o.raw_w = 16;
    o.raw_h = 16;
    expect_error(rawp, &o, "wrong size");
    {
        /* NaN by its bits (a -ffast-math build may fold NAN) */
        unsigned int u = 0x7fc00000u;
        memcpy(&raw[5 * 16 + 7], &u, sizeof u);
    }
    PF_CHECK(pfmap_write_raw(rawp, raw, 16 * 16) == 0, "write");
    expect_error(rawp, &o, "NaN at column 7, row 5");
    {
        unsigned int u = 0x7f800000u;
        raw[5 * 16 + 7] = 1.0f;
        memcpy(&raw[2 * 16 + 3], &u, sizeof u);
    }
    PF_CHECK(pfmap_write_raw(rawp, raw, 16 * 16) == 0, "write");
    expect_error(rawp, &o, "infinity at column 3, row 2");
    o.kind = PFMAP_NORMAL_DX;
    expect_error(rawp, &o, "raw float32 files are height maps");
    /* too small after the crop */
    o.kind = PFMAP_HEIGHT;
    o.raw_w = 64;
    o.raw_h = 4;
    for (i = 0; i < 16 * 16; ++i) raw[i] = (float)pattern(i % 16, i / 16, 16, 16);
    PF_CHECK(pfmap_write_raw(rawp, raw, 64 * 4) == 0, "write");
    expect_error(rawp, &o, "too small");
    remove(png);
    remove(trunc);
    remove(txt);
    remove(rawp);
    remove(flat);
    remove(rgbp);
}

/* option parsing */
static void edge_kind_parse(void)
{
    PF_CHECK(pfmap_kind_parse("height") == PFMAP_HEIGHT && pfmap_kind_parse("") == PFMAP_HEIGHT, "height");
    PF_CHECK(pfmap_kind_parse("normal-gl") == PFMAP_NORMAL_GL && pfmap_kind_parse("normal-dx") == PFMAP_NORMAL_DX,
             "normal");
    PF_CHECK(pfmap_kind_parse("bump") == -1, "unknown kind accepted");
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    snprintf(tmp_base, sizeof tmp_base, "%s", argc > 0 && argv[0] ? argv[0] : "test_maps");
    PF_TEST_RUN(test_png_grey_depths);
    PF_TEST_RUN(test_raw_float32);
    PF_TEST_RUN(test_scale_and_mirror);
    PF_TEST_RUN(test_normal_integration);
    PF_TEST_RUN(test_slope_stats);
    PF_TEST_RUN(edge_bad_input);
    PF_TEST_RUN(edge_kind_parse);
    return PF_TEST_END();
}

/* pictures.c - images of the brute-force reference next to the library's filtered shading
   (issue 9, item 6). CPU-only bench program, not part of the library.

   WHAT IT DRAWS. Two scenes, each rendered three ways from the same per-pixel geometry:
     reference   the brute force of tests/pf_microsurface.h: every texel of the pixel's
                 footprint shaded on its own (its micro-normal from the height field, a narrow
                 Beckmann base lobe of deviation BASE_SIGMA with its Smith G2, masking toward the
                 viewer and shadowing toward the light found by marching the height field with
                 pfm_visible), summed with the projected-area normalization of LEADR (Dupuy et
                 al. 2013 eqs. 1-3; pfm_reference_shade).
     LEADR       the library: the five slope moments sampled trilinearly from the moment pyramid
                 (pf_slope_pyramid_from_heights, pf_slope_moments_sample) at the footprint's
                 level of detail, turned into a noncentered Beckmann lobe plus the base roughness
                 (pf_slope_moments_stats) and shaded with pf_leadr_specular (eq. 17).
     naive       the mip-mapped normal: unit micro-normals averaged by the mip pyramid
                 (pf_normal_pyramid_from_normals), renormalized, and shaded with the base lobe
                 alone (no filtered roughness): what plain normal-map mipmapping does.
   Also measured but not drawn: "LEADR, exact box", the same formula fed with the exact mean of
   the level-0 moments over the reference's own box footprint (a summed-area table in double).
   Its error is the model's alone; the difference to the trilinear LEADR error is what the mip
   filter's footprint adds. The model's error is split further (ERRORS below).

   Scene 1 "plane": a tiled Gaussian surface (pfm corpus defaults) on the plane z = 0, seen by
   a pinhole camera above it, looking toward the horizon; a directional light low in the sky
   in front of the camera (grazing view and light: masking, shadowing and the forward highlight).
   Footprints from under a texel (resolved bumps) to the whole map (the horizon).
   Scene 2 "sphere": the same surface wrapped around a sphere with a longitude-latitude map,
   tiled SPHERE_TILES times around the equator (texels square at the equator), finely enough
   that every pixel covers a few to many bumps (footprint sides of about 30 to 256 texels
   against the 12-texel correlation length): LEADR's domain, where it claims to match a
   supersampled reference (Dupuy et al. 2013 sec. 7, fig. 8). The view and the
   light are rotated into each pixel's tangent frame (x along increasing longitude = texture u,
   y toward the north pole = texture v, z the sphere's normal). As for tangent-space normal maps,
   the micro-slopes are those of the texture in texel units: the map's stretch toward the poles
   widens the footprint (in texels), it does not shear the micro-surface.

   FOOTPRINT. Ray differentials: the rays through the neighbouring pixels (+1 in x, +1 in y) are
   intersected with the tangent plane at the hit point; the two offsets, converted to texels, give
   the isotropic footprint side f = max(|dP/dx|, |dP/dy|) in texels (the GPU's level-of-detail
   rule), capped at the map size. LEADR and naive sample the pyramid at lod = log2(f)
   (trilinear). The reference shades the n x n texel box centred on the hit point, n = round(f)
   (at least 1); beyond ref_max texels on a side (REF_MAX_SAMPLES, SPHERE_REF_MAX) it shades an
   evenly spaced ref_max x ref_max subset of the box (stride n / ref_max texels). Texels whose
   base lobe at the half vector is below exp(-LOBE_CUTOFF) of its peak are not marched (their
   term would be below 1e-13 of the peak whatever their visibility).

   ERRORS. Per pixel e = |filtered - reference| / max(reference, floor) with floor = LIT_FRACTION
   times the 99th percentile of the reference over the surface pixels; "lit" pixels are the
   surface pixels whose reference is at least the floor. The fragment reports the mean and the
   95th percentile of e over lit pixels, and the same by footprint size with the bias
   sum(method)/sum(reference). The heat maps show e on a log scale from 3% (black) to 316% (pale
   yellow), clamped, with a colour bar at the lower left of each picture (ticks at 3, 10, 32,
   100, 316%); background pixels are grey.
   What the error is made of, per footprint-size row:
     out-of-footprint occlusion: a second reference, "in-box", marches the same texels with
       only the footprint box's own height field as occluder (pfm_visible_box); the rows
       report how far it is from the full reference, and the errors against it;
     the Gaussian-slope assumption: with no visibility at all, the NDF at the half vector of
       the shaded texels (the mean of their base lobes) against the Gaussian with the same
       texels' moments plus the base variance (LEADR eqs. 8-10): the footprint's slope
       histogram is lumpy at the scale of the narrow base lobe when it holds few bumps;
     the reference's own sampling deviation on subsampled footprints: half the difference of
       the two interleaved (checkerboard) halves of the samples, relative, rms.

   SELF-CHECKS. Before the pictures, both scenes are rendered small with the map flattened (RMS
   slope FLAT_RMS_SLOPE): the three methods and the in-box reference must then match the
   reference to rounding (bound in main); the program fails otherwise. It checks the plumbing
   that the comparison relies on (frames, footprints, the recombination of the reference,
   conventions of the two shaders).

   TIMES. The per-pixel geometry is computed first; then the brute-force reference and the
   filtered shading are timed over the same pixels on one core (filtered: best of several
   passes; pyramid building timed separately, it is a one-off per map; the in-box variant is
   timed apart and not counted in the reference's time).

   OUTPUT (directory argument, default bench/out): pic_plane.png, pic_sphere.png (3 x 2 panels:
   reference | LEADR | naive, colour bar | LEADR error | naive error) and pictures.md (markdown
   fragment, every number computed in this run). BENCH_QUICK=1 renders smaller images.

   PNG. Written here without libpng or zlib: 8-bit indexed colour when the picture has at most
   256 colours (the shaded panels use GREY_LEVELS greys, the heat maps HEAT_LEVELS colours, so
   the pictures do), 8-bit RGB otherwise; the PNG row filters (None for every row, or per row
   the filter of least sum of |signed bytes|, libpng's heuristic: both are compressed and the
   smaller kept); one IDAT holding a zlib stream (RFC 1950) of deflate blocks (RFC 1951) made
   here: LZ77 with hash chains (DEFL_MAX_CHAIN candidates, 32K window) and lazy matching, then
   per block of DEFL_BLOCK_TOKENS symbols the cheaper of the fixed Huffman code and a dynamic
   one (length-limited code lengths, run-length coded header). CRC-32 per chunk (PNG spec) and
   Adler-32 of the image data (RFC 1950), both computed below. Every picture is checked before
   it is written: its stream is decoded by a small inflater here (zlib_decompress: stored,
   fixed and dynamic blocks, Adler-32), unfiltered and compared with the pixels byte for byte;
   png_write fails otherwise. (Also checked outside: Python's zlib.decompress of the IDAT and
   the unfiltered rows equal the pixels; the inflater decodes Python zlib's own streams.) */
#ifndef _POSIX_C_SOURCE
#  define _POSIX_C_SOURCE 199309L
#endif
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pf_moments.h"
#include "pf_beckmann.h"
#include "pf_microsurface.h"

/* ---------------------------------------------------------------- settings */
#define MAP_SIZE        256     /* the height map: MAP_SIZE^2 texels, texel = 1 world unit */
#define BASE_SIGMA      0.1     /* slope deviation of the narrow Beckmann base lobe */
#define F0              1.0     /* Schlick f0: 1 = no Fresnel (a constant factor in both) */
#define REF_MAX_SAMPLES 64      /* reference texels per footprint side, at most */
#define LIT_FRACTION    0.05    /* lit = reference >= this times its 99th percentile */
#define SPHERE_TILES    128     /* map repetitions around the sphere's equator */
#define SPHERE_REF_MAX  128     /* sphere: the same (BENCH_QUICK: REF_MAX_SAMPLES) */
#define REF_SCRATCH     (REF_MAX_SAMPLES > SPHERE_REF_MAX ? REF_MAX_SAMPLES : SPHERE_REF_MAX)
#define ERR_LOG_MIN     (-1.5)  /* heat map: log10 of the error at black (3.2%) */
#define ERR_LOG_MAX     0.5     /* ... and at full scale (316%) */
#define PANEL_GAP       4
#define GREY_LEVELS     176     /* shaded panels: grey levels (step 1.5/255 after gamma) */
#define HEAT_LEVELS     64      /* heat maps: colours over the two decades (3.2% ratio apart)
                                   with the greys and the few flat colours the picture fits a
                                   256-colour palette, a third of the bytes of RGB */
#define LOBE_CUTOFF     30.0    /* reference: texels whose base lobe at h is below exp(-30) of
                                   its peak (1e-13) are not marched (their term is taken as 0) */
#define FLAT_RMS_SLOPE  1e-9    /* self-check: the map flattened to this RMS slope */

static const double pic_pi = 3.14159265358979323846;

/* ---------------------------------------------------------------- small vector helpers */
static double v3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static void v3_normalize(double a[3])
{
    double l = sqrt(v3_dot(a, a));
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
}
static void v3_set(double a[3], double x, double y, double z)
{
    a[0] = x;
    a[1] = y;
    a[2] = z;
}

static double now_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int wrap_index(int i, int n) { return ((i % n) + n) % n; }

/* ---------------------------------------------------------------- PNG writer */
/* The image data go through the PNG row filters and a deflate compressor written here (no
   zlib, no libpng): LZ77 with hash chains and lazy matching, then, per block, the cheaper of
   the fixed and a dynamic Huffman code (RFC 1951), inside a zlib stream (RFC 1950). */

/* CRC-32 of the PNG specification (ISO 3309 polynomial, reflected: 0xEDB88320), bytewise. */
static uint32_t png_crc_update(uint32_t crc, const unsigned char *p, size_t n)
{
    static uint32_t table[256];
    static int ready = 0;
    size_t i;
    if (!ready) {
        uint32_t k, c;
        int b;
        for (k = 0; k < 256; ++k) {
            c = k;
            for (b = 0; b < 8; ++b) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            table[k] = c;
        }
        ready = 1;
    }
    for (i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
    return crc;
}

static void put_be32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static int png_chunk(FILE *f, const char *type, const unsigned char *data, size_t n)
{
    unsigned char head[8], tail[4];
    uint32_t crc;
    put_be32(head, (uint32_t)n);
    memcpy(head + 4, type, 4);
    crc = png_crc_update(0xFFFFFFFFu, head + 4, 4);
    crc = png_crc_update(crc, data, n) ^ 0xFFFFFFFFu;
    put_be32(tail, crc);
    return fwrite(head, 1, 8, f) == 8 && (n == 0 || fwrite(data, 1, n, f) == n) &&
           fwrite(tail, 1, 4, f) == 4;
}

/* ---- deflate (RFC 1951) */
#define DEFL_WINDOW       32768 /* the largest back-reference distance */
#define DEFL_HASH_BITS    15    /* hash of the next three bytes */
#define DEFL_MAX_MATCH    258
#define DEFL_MAX_CHAIN    96    /* earlier positions with the same hash tried per search */
#define DEFL_NICE_MATCH   96    /* a match this long is taken without searching further */
#define DEFL_BLOCK_TOKENS 49152 /* symbols per block (each block gets codes fitted to it) */

/* length symbols 257..285 and distance symbols 0..29: base value and extra bits (sec. 3.2.5) */
static const unsigned short defl_len_base[29] = {3,  4,  5,  6,  7,  8,  9,  10,  11,  13,
                                                 15, 17, 19, 23, 27, 31, 35, 43,  51,  59,
                                                 67, 83, 99, 115, 131, 163, 195, 227, 258};
static const unsigned char defl_len_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
static const unsigned short defl_dist_base[30] = {
    1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
static const unsigned char defl_dist_extra[30] = {0, 0, 0,  0,  1,  1,  2,  2,  3,  3,
                                                  4, 4, 5,  5,  6,  6,  7,  7,  8,  8,
                                                  9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
/* the order in which a dynamic block header lists the code-length code's lengths */
static const unsigned char defl_cl_order[19] = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                11, 4,  12, 3, 13, 2, 14, 1, 15};

typedef struct {
    unsigned short litlen; /* a literal byte (dist == 0) or a match length 3..258 */
    unsigned short dist;   /* match distance 1..32768 (as dist - 1 + 1, fits 16 bits) */
} defl_token;

/* Bits are packed least significant first (sec. 3.1.1). */
typedef struct {
    unsigned char *buf;
    size_t pos, cap;
    uint32_t acc;
    int n, overflow;
} defl_bits;

static void bits_put(defl_bits *b, uint32_t v, int n) /* n <= 16 */
{
    b->acc |= v << b->n;
    b->n += n;
    while (b->n >= 8) {
        if (b->pos < b->cap) b->buf[b->pos++] = (unsigned char)(b->acc & 0xFFu);
        else b->overflow = 1;
        b->acc >>= 8;
        b->n -= 8;
    }
}

static void bits_flush(defl_bits *b)
{
    if (b->n > 0) bits_put(b, 0, 8 - b->n);
}

static int defl_len_symbol(int len) /* index into defl_len_base: symbol 257 + index */
{
    int k = 28;
    while (defl_len_base[k] > len) --k;
    return k;
}

static int defl_dist_symbol(int dist)
{
    int k = 29;
    while (defl_dist_base[k] > dist) --k;
    return k;
}

/* Huffman code lengths for freq[0..n-1] (n <= 288; 0 = unused symbol, at least two used),
   none longer than limit. The tree is built by the two-queue method on the sorted weights;
   if it is deeper than the limit, the weights are flattened (halved, rounded up, so no used
   symbol drops out) and the tree rebuilt: the weights tend to equal ones, whose tree is
   balanced (depth 9 for 288 symbols), so this ends. */
static void huff_lengths(const uint32_t *freq, int n, int limit, unsigned char *len)
{
    uint32_t w[2 * 288];
    int sym[288], parent[2 * 288], depth[2 * 288], m = 0, i, j, k, deepest;
    for (i = 0; i < n; ++i) {
        len[i] = 0;
        if (freq[i] > 0) {
            w[m] = freq[i];
            sym[m++] = i;
        }
    }
    for (i = 1; i < m; ++i) { /* sort the leaves by weight (insertion sort: n <= 288) */
        uint32_t wv = w[i];
        int sv = sym[i];
        for (j = i - 1; j >= 0 && w[j] > wv; --j) {
            w[j + 1] = w[j];
            sym[j + 1] = sym[j];
        }
        w[j + 1] = wv;
        sym[j + 1] = sv;
    }
    for (;;) {
        int leaf = 0, node = m;
        /* internal nodes m .. 2m - 2 are created in order of nondecreasing weight; halving
           the sorted leaf weights below keeps them sorted */
        for (k = m; k < 2 * m - 1; ++k) {
            int pick[2], p;
            for (p = 0; p < 2; ++p) {
                if (leaf < m && (node >= k || w[leaf] <= w[node])) pick[p] = leaf++;
                else pick[p] = node++;
            }
            w[k] = w[pick[0]] + w[pick[1]];
            parent[pick[0]] = parent[pick[1]] = k;
        }
        depth[2 * m - 2] = 0;
        deepest = 0;
        for (k = 2 * m - 3; k >= 0; --k) {
            depth[k] = depth[parent[k]] + 1;
            if (k < m && depth[k] > deepest) deepest = depth[k];
        }
        if (deepest <= limit) break;
        for (i = 0; i < m; ++i) w[i] = (w[i] + 1) / 2;
    }
    for (i = 0; i < m; ++i) len[sym[i]] = (unsigned char)depth[i];
}

/* Canonical codes from the lengths (sec. 3.2.2), bit-reversed: the bit writer sends least
   significant bits first, Huffman codes go most significant bit first. */
static void huff_codes(const unsigned char *len, int n, unsigned short *code)
{
    int count[16], next[16], b, i;
    for (b = 0; b < 16; ++b) count[b] = 0;
    for (i = 0; i < n; ++i) count[len[i]]++;
    count[0] = 0;
    next[0] = 0;
    for (b = 1; b < 16; ++b) next[b] = (next[b - 1] + count[b - 1]) << 1;
    for (i = 0; i < n; ++i) {
        int c, r = 0;
        if (!len[i]) {
            code[i] = 0;
            continue;
        }
        c = next[len[i]]++;
        for (b = 0; b < len[i]; ++b) r |= ((c >> b) & 1) << (len[i] - 1 - b);
        code[i] = (unsigned short)r;
    }
}

/* Make sure at least two symbols of a code are used (a one-symbol code would be incomplete,
   which inflaters accept only in special cases): unused ones get weight 1, costing nothing
   in the data. */
static void huff_at_least_two(uint32_t *freq, int n)
{
    int used = 0, i;
    for (i = 0; i < n; ++i) used += freq[i] > 0;
    for (i = 0; i < n && used < 2; ++i)
        if (!freq[i]) {
            freq[i] = 1;
            ++used;
        }
}

/* One block of tokens with the cheaper of the fixed and a dynamic code (sec. 3.2.6, 3.2.7). */
static void defl_block(defl_bits *b, const defl_token *tok, size_t nt, int final)
{
    uint32_t lf[286], df[30], cf[19];
    unsigned char ll[288], dl[30], cl[19], all[286 + 30], rle_sym[286 + 30], rle_extra[286 + 30];
    unsigned short lc[288], dc[30], cc[19];
    int hlit = 286, hdist = 30, hclen = 19, nall, nrle = 0, i, k, dynamic;
    size_t t;
    long long cost_fixed = 3, cost_dyn = 3 + 14;
    memset(lf, 0, sizeof lf);
    memset(df, 0, sizeof df);
    memset(cf, 0, sizeof cf);
    for (t = 0; t < nt; ++t) {
        if (tok[t].dist == 0) lf[tok[t].litlen]++;
        else {
            lf[257 + defl_len_symbol(tok[t].litlen)]++;
            df[defl_dist_symbol(tok[t].dist)]++;
        }
    }
    lf[256] = 1; /* end of block */
    /* the fixed code: literals 0-143 8 bits, 144-255 9, 256-279 7, 280-287 8; distances 5 */
    for (i = 0; i < 288; ++i)
        ll[i] = (unsigned char)(i < 144 ? 8 : (i < 256 ? 9 : (i < 280 ? 7 : 8)));
    for (i = 0; i < 30; ++i) dl[i] = 5;
    for (i = 0; i < 286; ++i) {
        cost_fixed += (long long)lf[i] * ll[i];
        if (i >= 257) cost_fixed += (long long)lf[i] * defl_len_extra[i - 257];
    }
    for (i = 0; i < 30; ++i) cost_fixed += (long long)df[i] * (5 + defl_dist_extra[i]);
    /* the dynamic code */
    huff_at_least_two(lf, 286);
    huff_at_least_two(df, 30);
    huff_lengths(lf, 286, 15, ll);
    huff_lengths(df, 30, 15, dl);
    while (hlit > 257 && ll[hlit - 1] == 0) --hlit;
    while (hdist > 1 && dl[hdist - 1] == 0) --hdist;
    memcpy(all, ll, (size_t)hlit);
    memcpy(all + hlit, dl, (size_t)hdist);
    nall = hlit + hdist;
    /* run-length code of the code lengths: 16 = repeat the previous length 3-6 times,
       17 = 3-10 zeros, 18 = 11-138 zeros */
    for (i = 0; i < nall;) {
        int run = 1, r;
        while (i + run < nall && all[i + run] == all[i]) ++run;
        if (all[i] == 0) {
            while (run >= 11) {
                r = run < 138 ? run : 138;
                rle_sym[nrle] = 18;
                rle_extra[nrle++] = (unsigned char)(r - 11);
                run -= r;
                i += r;
            }
            if (run >= 3) {
                rle_sym[nrle] = 17;
                rle_extra[nrle++] = (unsigned char)(run - 3);
                i += run;
                run = 0;
            }
        } else {
            rle_sym[nrle] = all[i];
            rle_extra[nrle++] = 0;
            --run;
            ++i;
            while (run >= 3) {
                r = run < 6 ? run : 6;
                rle_sym[nrle] = 16;
                rle_extra[nrle++] = (unsigned char)(r - 3);
                run -= r;
                i += r;
            }
        }
        for (; run > 0; --run, ++i) {
            rle_sym[nrle] = all[i];
            rle_extra[nrle++] = 0;
        }
    }
    for (k = 0; k < nrle; ++k) cf[rle_sym[k]]++;
    huff_at_least_two(cf, 19);
    huff_lengths(cf, 19, 7, cl);
    while (hclen > 4 && cl[defl_cl_order[hclen - 1]] == 0) --hclen;
    cost_dyn += 3LL * hclen;
    for (k = 0; k < nrle; ++k)
        cost_dyn += cl[rle_sym[k]] +
                    (rle_sym[k] == 16 ? 2 : (rle_sym[k] == 17 ? 3 : (rle_sym[k] == 18 ? 7 : 0)));
    for (i = 0; i < 286; ++i) {
        if (!lf[i]) continue;
        cost_dyn += (long long)lf[i] * ll[i];
        if (i >= 257) cost_dyn += (long long)lf[i] * defl_len_extra[i - 257];
    }
    for (i = 0; i < 30; ++i) cost_dyn += (long long)df[i] * (dl[i] + defl_dist_extra[i]);
    /* the weights added by huff_at_least_two are 1 for unused symbols: they inflate the cost
       estimate by at most a few bits, which does not matter for the choice */
    dynamic = cost_dyn < cost_fixed;
    bits_put(b, (uint32_t)(final ? 1 : 0), 1);
    bits_put(b, dynamic ? 2u : 1u, 2);
    if (dynamic) {
        huff_codes(cl, 19, cc);
        bits_put(b, (uint32_t)(hlit - 257), 5);
        bits_put(b, (uint32_t)(hdist - 1), 5);
        bits_put(b, (uint32_t)(hclen - 4), 4);
        for (k = 0; k < hclen; ++k) bits_put(b, cl[defl_cl_order[k]], 3);
        for (k = 0; k < nrle; ++k) {
            bits_put(b, cc[rle_sym[k]], cl[rle_sym[k]]);
            if (rle_sym[k] == 16) bits_put(b, rle_extra[k], 2);
            else if (rle_sym[k] == 17) bits_put(b, rle_extra[k], 3);
            else if (rle_sym[k] == 18) bits_put(b, rle_extra[k], 7);
        }
    } else {
        for (i = 0; i < 288; ++i)
            ll[i] = (unsigned char)(i < 144 ? 8 : (i < 256 ? 9 : (i < 280 ? 7 : 8)));
        for (i = 0; i < 30; ++i) dl[i] = 5;
    }
    huff_codes(ll, dynamic ? 286 : 288, lc);
    huff_codes(dl, 30, dc);
    for (t = 0; t < nt; ++t) {
        int s = tok[t].litlen;
        if (tok[t].dist == 0) {
            bits_put(b, lc[s], ll[s]);
        } else {
            int ls = defl_len_symbol(s), ds = defl_dist_symbol(tok[t].dist);
            bits_put(b, lc[257 + ls], ll[257 + ls]);
            if (defl_len_extra[ls])
                bits_put(b, (uint32_t)(s - defl_len_base[ls]), defl_len_extra[ls]);
            bits_put(b, dc[ds], dl[ds]);
            if (defl_dist_extra[ds])
                bits_put(b, (uint32_t)(tok[t].dist - defl_dist_base[ds]), defl_dist_extra[ds]);
        }
    }
    bits_put(b, lc[256], ll[256]);
}

static uint32_t defl_hash(const unsigned char *p)
{
    return (((uint32_t)p[0] << 10) ^ ((uint32_t)p[1] << 5) ^ (uint32_t)p[2]) &
           ((1u << DEFL_HASH_BITS) - 1u);
}

/* Longest earlier match for position i (at most DEFL_MAX_CHAIN candidates, distance below
   DEFL_WINDOW); returns its length (0 if under 3) and its distance in *dist. */
static int defl_longest(const unsigned char *d, size_t n, size_t i, const long *head,
                        const long *prev, int *dist)
{
    long cand = head[defl_hash(d + i)], lim = (long)i - (DEFL_WINDOW - 1);
    int best = 0, chain = DEFL_MAX_CHAIN;
    int maxlen = n - i < DEFL_MAX_MATCH ? (int)(n - i) : DEFL_MAX_MATCH;
    while (cand >= 0 && cand >= lim && chain-- > 0) {
        const unsigned char *a = d + cand, *c = d + i;
        if (a[best] == c[best] && a[0] == c[0] && a[1] == c[1]) {
            int l = 2;
            while (l < maxlen && a[l] == c[l]) ++l;
            if (l > best) {
                best = l;
                *dist = (int)((long)i - cand);
                if (l >= DEFL_NICE_MATCH || l == maxlen) break;
            }
        }
        {
            long next = prev[cand & (DEFL_WINDOW - 1)];
            if (next >= cand) break; /* a slot reused by a newer position: end of chain */
            cand = next;
        }
    }
    return best >= 3 ? best : 0;
}

/* zlib stream (RFC 1950) of d[0..n-1] into a new buffer; *out_n its size. NULL on failure. */
static unsigned char *zlib_compress(const unsigned char *d, size_t n, size_t *out_n)
{
    long *head = (long *)malloc(sizeof(long) << DEFL_HASH_BITS);
    long *prev = (long *)malloc(sizeof(long) * DEFL_WINDOW);
    defl_token *tok = (defl_token *)malloc(sizeof(defl_token) * DEFL_BLOCK_TOKENS);
    defl_bits b;
    size_t i = 0, nt = 0, k;
    uint32_t a1 = 1, a2 = 0;
    memset(&b, 0, sizeof b);
    b.cap = n + n / 8 + 1024; /* stored-size bound plus the block headers, generously */
    b.buf = (unsigned char *)malloc(b.cap);
    if (!head || !prev || !tok || !b.buf) {
        free(head);
        free(prev);
        free(tok);
        free(b.buf);
        return NULL;
    }
    for (k = 0; k < ((size_t)1 << DEFL_HASH_BITS); ++k) head[k] = -1;
    /* zlib header: CM = 8 (deflate), CINFO = 7 (32K window), FLEVEL = 2; CMF FLG is a
       multiple of 31, no preset dictionary */
    bits_put(&b, 0x78, 8);
    bits_put(&b, 0x9C, 8);
    while (i < n) {
        int len = 0, dist = 0;
        if (i + 3 <= n) {
            len = defl_longest(d, n, i, head, prev, &dist);
            /* lazy matching: a literal now if the next position starts a longer match */
            if (len >= 3 && len < DEFL_NICE_MATCH && i + 4 <= n) {
                int dist2 = 0, len2;
                uint32_t h = defl_hash(d + i);
                prev[i & (DEFL_WINDOW - 1)] = head[h];
                head[h] = (long)i;
                len2 = defl_longest(d, n, i + 1, head, prev, &dist2);
                if (len2 > len) len = 0;
            } else {
                uint32_t h = defl_hash(d + i);
                prev[i & (DEFL_WINDOW - 1)] = head[h];
                head[h] = (long)i;
            }
        }
        if (len >= 3) {
            tok[nt].litlen = (unsigned short)len;
            tok[nt++].dist = (unsigned short)dist;
            for (k = i + 1; k < i + (size_t)len; ++k)
                if (k + 3 <= n) {
                    uint32_t h = defl_hash(d + k);
                    prev[k & (DEFL_WINDOW - 1)] = head[h];
                    head[h] = (long)k;
                }
            i += (size_t)len;
        } else {
            tok[nt].litlen = d[i];
            tok[nt++].dist = 0;
            ++i;
        }
        if (nt == DEFL_BLOCK_TOKENS) {
            defl_block(&b, tok, nt, i == n);
            nt = 0;
        }
    }
    if (nt > 0 || n == 0) defl_block(&b, tok, nt, 1);
    bits_flush(&b);
    for (k = 0; k < n; ++k) { /* Adler-32 (RFC 1950 sec. 8.2), modulo 65521 */
        a1 = (a1 + d[k]) % 65521u;
        a2 = (a2 + a1) % 65521u;
    }
    bits_put(&b, (a2 >> 8) & 0xFFu, 8); /* big-endian, byte aligned */
    bits_put(&b, a2 & 0xFFu, 8);
    bits_put(&b, (a1 >> 8) & 0xFFu, 8);
    bits_put(&b, a1 & 0xFFu, 8);
    free(head);
    free(prev);
    free(tok);
    if (b.overflow) {
        free(b.buf);
        return NULL;
    }
    *out_n = b.pos;
    return b.buf;
}

/* PNG filter types 0-4 (None, Sub, Up, Average, Paeth) of one row; bpp bytes per pixel. */
static unsigned char png_paeth(int a, int b, int c)
{
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return (unsigned char)(pa <= pb && pa <= pc ? a : (pb <= pc ? b : c));
}

static void png_filter_row(int type, const unsigned char *row, const unsigned char *up,
                           size_t n, int bpp, unsigned char *out)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        int a = i >= (size_t)bpp ? row[i - bpp] : 0, b = up ? up[i] : 0;
        int c = (up && i >= (size_t)bpp) ? up[i - bpp] : 0, pred;
        switch (type) {
        case 1: pred = a; break;
        case 2: pred = b; break;
        case 3: pred = (a + b) / 2; break;
        case 4: pred = png_paeth(a, b, c); break;
        default: pred = 0; break;
        }
        out[i] = (unsigned char)((row[i] - pred) & 0xFF);
    }
}

/* The filtered image data: a filter type byte, then the filtered row. adaptive = 0: filter
   None everywhere; 1: each row gets the filter with the smallest sum of |filtered byte| taken
   as signed (libpng's default heuristic). */
/* ---- a deflate decoder (RFC 1951) and the PNG unfiltering, used only to check every picture
   written: the zlib stream is decoded, unfiltered and compared with the pixels byte for byte
   before the file is written (png_write fails otherwise). */
typedef struct {
    const unsigned char *p;
    size_t n, pos;
    uint32_t acc;
    int nb, err;
} infl_in;

static int infl_bits(infl_in *s, int n) /* n <= 16, least significant bit first */
{
    int v;
    while (s->nb < n) {
        if (s->pos >= s->n) {
            s->err = 1;
            return 0;
        }
        s->acc |= (uint32_t)s->p[s->pos++] << s->nb;
        s->nb += 8;
    }
    v = (int)(s->acc & ((1u << n) - 1u));
    s->acc >>= n;
    s->nb -= n;
    return v;
}

/* canonical code: number of codes per length, symbols in code order */
typedef struct {
    short count[16];
    short symbol[288];
} infl_code;

static int infl_build(infl_code *c, const unsigned char *len, int n) /* 0 ok */
{
    short offset[16];
    int i, left = 1;
    for (i = 0; i < 16; ++i) c->count[i] = 0;
    for (i = 0; i < n; ++i) c->count[len[i]]++;
    for (i = 1; i < 16; ++i) { /* no length may be over-subscribed */
        left = 2 * left - c->count[i];
        if (left < 0) return 1;
    }
    offset[1] = 0;
    for (i = 1; i < 15; ++i) offset[i + 1] = (short)(offset[i] + c->count[i]);
    for (i = 0; i < n; ++i)
        if (len[i]) c->symbol[offset[len[i]]++] = (short)i;
    return 0;
}

/* one symbol: codes of length l are consecutive integers starting at first, read one bit at
   a time most significant first */
static int infl_symbol(infl_in *s, const infl_code *c)
{
    int code = 0, first = 0, index = 0, l;
    for (l = 1; l < 16; ++l) {
        code |= infl_bits(s, 1);
        if (code - first < c->count[l]) return c->symbol[index + code - first];
        index += c->count[l];
        first = (first + c->count[l]) << 1;
        code <<= 1;
    }
    s->err = 1;
    return -1;
}

/* zlib stream z[0..zn-1] into out (capacity cap); returns the decoded size, or -1 on any
   error (header, codes, distances, overflow, Adler-32). */
static long zlib_decompress(const unsigned char *z, size_t zn, unsigned char *out, size_t cap)
{
    infl_in s;
    size_t o = 0, k;
    int final = 0;
    uint32_t a1 = 1, a2 = 0, want;
    memset(&s, 0, sizeof s);
    s.p = z;
    s.n = zn;
    if (zn < 6 || (z[0] & 0x0F) != 8 || ((unsigned)z[0] * 256u + z[1]) % 31u != 0 || (z[1] & 0x20))
        return -1;
    s.pos = 2;
    while (!final && !s.err) {
        int type;
        final = infl_bits(&s, 1);
        type = infl_bits(&s, 2);
        if (type == 0) { /* stored */
            unsigned len, nlen;
            s.acc = 0;
            s.nb = 0;
            if (s.pos + 4 > s.n) return -1;
            len = z[s.pos] | (unsigned)z[s.pos + 1] << 8;
            nlen = z[s.pos + 2] | (unsigned)z[s.pos + 3] << 8;
            s.pos += 4;
            if ((len ^ 0xFFFFu) != nlen || s.pos + len > s.n || o + len > cap) return -1;
            memcpy(out + o, z + s.pos, len);
            s.pos += len;
            o += len;
        } else if (type == 1 || type == 2) {
            unsigned char len[320];
            infl_code lit, dist;
            int hlit = 288, hdist = 30, i;
            if (type == 1) { /* the fixed code */
                for (i = 0; i < 288; ++i)
                    len[i] = (unsigned char)(i < 144 ? 8 : (i < 256 ? 9 : (i < 280 ? 7 : 8)));
                for (i = 0; i < 30; ++i) len[288 + i] = 5;
            } else { /* a dynamic code: the code-length code, then the run-length coded lengths */
                unsigned char cl[19];
                infl_code clc;
                int hclen;
                hlit = infl_bits(&s, 5) + 257;
                hdist = infl_bits(&s, 5) + 1;
                hclen = infl_bits(&s, 4) + 4;
                if (hlit > 286 || hdist > 30) return -1;
                memset(cl, 0, sizeof cl);
                for (i = 0; i < hclen; ++i) cl[defl_cl_order[i]] = (unsigned char)infl_bits(&s, 3);
                if (infl_build(&clc, cl, 19)) return -1;
                for (i = 0; i < hlit + hdist;) {
                    int sym = infl_symbol(&s, &clc), rep = 0, val = 0;
                    if (s.err) return -1;
                    if (sym < 16) {
                        len[i++] = (unsigned char)sym;
                        continue;
                    }
                    if (sym == 16) {
                        if (i == 0) return -1;
                        val = len[i - 1];
                        rep = 3 + infl_bits(&s, 2);
                    } else if (sym == 17) {
                        rep = 3 + infl_bits(&s, 3);
                    } else {
                        rep = 11 + infl_bits(&s, 7);
                    }
                    if (i + rep > hlit + hdist) return -1;
                    while (rep-- > 0) len[i++] = (unsigned char)val;
                }
                memmove(len + 288, len + hlit, (size_t)hdist);
            }
            if (infl_build(&lit, len, hlit) || infl_build(&dist, len + 288, hdist)) return -1;
            for (;;) {
                int sym = infl_symbol(&s, &lit);
                if (s.err) return -1;
                if (sym < 256) {
                    if (o >= cap) return -1;
                    out[o++] = (unsigned char)sym;
                } else if (sym == 256) {
                    break;
                } else {
                    int l, d, ds;
                    sym -= 257;
                    if (sym >= 29) return -1;
                    l = defl_len_base[sym] + infl_bits(&s, defl_len_extra[sym]);
                    ds = infl_symbol(&s, &dist);
                    if (s.err || ds < 0 || ds >= 30) return -1;
                    d = defl_dist_base[ds] + infl_bits(&s, defl_dist_extra[ds]);
                    if ((size_t)d > o || o + (size_t)l > cap) return -1;
                    for (; l > 0; --l, ++o) out[o] = out[o - (size_t)d];
                }
            }
        } else {
            return -1;
        }
    }
    if (s.err) return -1;
    /* the Adler-32 trailer starts at the next byte boundary */
    if (s.pos + 4 > s.n) return -1;
    want = (uint32_t)z[s.pos] << 24 | (uint32_t)z[s.pos + 1] << 16 | (uint32_t)z[s.pos + 2] << 8 |
           (uint32_t)z[s.pos + 3];
    for (k = 0; k < o; ++k) {
        a1 = (a1 + out[k]) % 65521u;
        a2 = (a2 + a1) % 65521u;
    }
    return ((a2 << 16) | a1) == want ? (long)o : -1;
}

/* 0 if the filtered rows raw (w x h pixels of bpp bytes, a type byte per row) unfilter to pix. */
static int png_unfilter_check(unsigned char *raw, const unsigned char *pix, int w, int h, int bpp)
{
    size_t row = (size_t)w * bpp, i;
    int y;
    for (y = 0; y < h; ++y) {
        unsigned char *cur = raw + (size_t)y * (row + 1) + 1;
        const unsigned char *up = y ? cur - (row + 1) : NULL;
        int type = cur[-1];
        if (type > 4) return 1;
        for (i = 0; i < row; ++i) { /* in place: left and upper bytes are already unfiltered */
            int a = i >= (size_t)bpp ? cur[i - bpp] : 0, b = up ? up[i] : 0;
            int c = (up && i >= (size_t)bpp) ? up[i - bpp] : 0, pred;
            switch (type) {
            case 1: pred = a; break;
            case 2: pred = b; break;
            case 3: pred = (a + b) / 2; break;
            case 4: pred = png_paeth(a, b, c); break;
            default: pred = 0; break;
            }
            cur[i] = (unsigned char)((cur[i] + pred) & 0xFF);
        }
        if (memcmp(cur, pix + (size_t)y * row, row) != 0) return 1;
    }
    return 0;
}

/* The filtered image data of pix (w x h pixels of bpp bytes): per row a filter type byte, then
   the filtered row. adaptive = 0: filter None everywhere; 1: each row gets the filter with the
   smallest sum of |filtered byte| taken as signed (libpng's default heuristic). */
static void png_filter_image(const unsigned char *pix, int w, int h, int bpp, int adaptive,
                             unsigned char *raw, unsigned char *trial)
{
    size_t row = (size_t)w * bpp;
    int y;
    for (y = 0; y < h; ++y) {
        const unsigned char *cur = pix + (size_t)y * row, *up = y ? cur - row : NULL;
        unsigned char *dst = raw + (size_t)y * (row + 1);
        long best = -1;
        int type;
        for (type = 0; type < (adaptive ? 5 : 1); ++type) {
            long sum = 0;
            size_t i;
            png_filter_row(type, cur, up, row, bpp, trial);
            for (i = 0; i < row; ++i) sum += trial[i] < 128 ? trial[i] : 256 - trial[i];
            if (best < 0 || sum < best) {
                best = sum;
                dst[0] = (unsigned char)type;
                memcpy(dst + 1, trial, row);
            }
        }
    }
}

/* The distinct colours of rgb (n pixels) if there are at most 256: palette (3 bytes each,
   sorted by R + G + B so that neighbouring indices look alike), index image; returns the
   palette size, or 0 if there are more colours (or no memory). */
static int png_palette(const unsigned char *rgb, size_t n, unsigned char *pal,
                       unsigned char *idx)
{
    enum { SLOTS = 4096 };
    long *key = (long *)malloc(sizeof(long) * SLOTS);
    int *slot_index = (int *)malloc(sizeof(int) * SLOTS), count = 0, i, j, order[256];
    int rank[256];
    size_t p;
    if (!key || !slot_index) {
        free(key);
        free(slot_index);
        return 0;
    }
    for (i = 0; i < SLOTS; ++i) key[i] = -1;
    for (p = 0; p < n && count >= 0; ++p) { /* pass 1: collect the colours */
        long c = ((long)rgb[3 * p] << 16) | ((long)rgb[3 * p + 1] << 8) | (long)rgb[3 * p + 2];
        unsigned h = (unsigned)((c * 2654435761UL) >> 8) % SLOTS;
        while (key[h] >= 0 && key[h] != c) h = (h + 1) % SLOTS;
        if (key[h] < 0) {
            if (count == 256) {
                count = -1;
                break;
            }
            key[h] = c;
            slot_index[h] = count;
            pal[3 * count] = rgb[3 * p];
            pal[3 * count + 1] = rgb[3 * p + 1];
            pal[3 * count + 2] = rgb[3 * p + 2];
            ++count;
        }
    }
    if (count > 0) {
        unsigned char sorted[768];
        for (i = 0; i < count; ++i) order[i] = i;
        for (i = 1; i < count; ++i) { /* insertion sort by R + G + B, then by value */
            int v = order[i];
            long kv = 1000000L * (pal[3 * v] + pal[3 * v + 1] + pal[3 * v + 2]) +
                      ((long)pal[3 * v] << 16) + ((long)pal[3 * v + 1] << 8) + pal[3 * v + 2];
            for (j = i - 1; j >= 0; --j) {
                int u = order[j];
                long ku = 1000000L * (pal[3 * u] + pal[3 * u + 1] + pal[3 * u + 2]) +
                          ((long)pal[3 * u] << 16) + ((long)pal[3 * u + 1] << 8) + pal[3 * u + 2];
                if (ku <= kv) break;
                order[j + 1] = u;
            }
            order[j + 1] = v;
        }
        for (i = 0; i < count; ++i) {
            rank[order[i]] = i;
            memcpy(sorted + 3 * i, pal + 3 * order[i], 3);
        }
        memcpy(pal, sorted, 3 * (size_t)count);
        for (p = 0; p < n; ++p) { /* pass 2: the index image */
            long c = ((long)rgb[3 * p] << 16) | ((long)rgb[3 * p + 1] << 8) | (long)rgb[3 * p + 2];
            unsigned h = (unsigned)((c * 2654435761UL) >> 8) % SLOTS;
            while (key[h] != c) h = (h + 1) % SLOTS;
            idx[p] = (unsigned char)rank[slot_index[h]];
        }
    }
    free(key);
    free(slot_index);
    return count > 0 ? count : 0;
}

/* rgb: w * h * 3 bytes, row-major, top row first. Written as an indexed-colour PNG when the
   image has at most 256 colours (one byte per pixel instead of three), as RGB otherwise;
   compressed twice, with the adaptive row filters and with none (the flat panels and heat
   maps here often compress better unfiltered), and the smaller stream written. Returns 0 on
   success; *bytes the file size. */
static int png_write(const char *path, const unsigned char *rgb, int w, int h, long *bytes)
{
    static const unsigned char signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    size_t npix = (size_t)w * (size_t)h, z_n = 0, t_n = 0, row, raw_n;
    unsigned char ihdr[13], pal[768], *idx = (unsigned char *)malloc(npix ? npix : 1);
    unsigned char *raw, *trial, *z = NULL, *t;
    const unsigned char *pix = rgb;
    FILE *f;
    int adaptive, ok, ncol = idx ? png_palette(rgb, npix, pal, idx) : 0, bpp = 3;
    if (ncol > 0) {
        pix = idx;
        bpp = 1;
    }
    row = (size_t)w * bpp;
    raw_n = (row + 1) * (size_t)h;
    raw = (unsigned char *)malloc(raw_n);
    trial = (unsigned char *)malloc(row ? row : 1);
    if (!raw || !trial) {
        free(idx);
        free(raw);
        free(trial);
        return 1;
    }
    for (adaptive = 0; adaptive < 2; ++adaptive) {
        png_filter_image(pix, w, h, bpp, adaptive, raw, trial);
        t = zlib_compress(raw, raw_n, &t_n);
        if (t && (!z || t_n < z_n)) {
            free(z);
            z = t;
            z_n = t_n;
        } else {
            free(t);
        }
    }
    /* round trip: decode, unfilter and compare with the pixels (and the palette's colours) */
    ok = z && zlib_decompress(z, z_n, raw, raw_n) == (long)raw_n &&
         png_unfilter_check(raw, pix, w, h, bpp) == 0;
    if (ok && ncol) {
        size_t q;
        for (q = 0; q < npix && ok; ++q) ok = memcmp(pal + 3 * (size_t)idx[q], rgb + 3 * q, 3) == 0;
    }
    free(idx);
    free(raw);
    free(trial);
    if (!ok) {
        fprintf(stderr, "pictures: PNG encoder round trip failed for %s\n", path);
        free(z);
        return 1;
    }
    put_be32(ihdr, (uint32_t)w);
    put_be32(ihdr + 4, (uint32_t)h);
    ihdr[8] = 8;                             /* bit depth */
    ihdr[9] = (unsigned char)(ncol ? 3 : 2); /* colour type: indexed, or RGB */
    ihdr[10] = 0;                            /* deflate */
    ihdr[11] = 0;                            /* adaptive filtering: a filter type byte per row */
    ihdr[12] = 0;                            /* no interlace */
    f = fopen(path, "wb");
    ok = f && fwrite(signature, 1, 8, f) == 8 && png_chunk(f, "IHDR", ihdr, 13) &&
         (!ncol || png_chunk(f, "PLTE", pal, 3 * (size_t)ncol)) &&
         png_chunk(f, "IDAT", z, z_n) && png_chunk(f, "IEND", NULL, 0);
    if (f && fclose(f) != 0) ok = 0;
    free(z);
    if (bytes) *bytes = (long)(8 + 25 + (ncol ? 12 + 3 * ncol : 0) + 12 + z_n + 12);
    return ok ? 0 : 1;
}

/* ---------------------------------------------------------------- the shared inputs */
typedef struct {
    int hit;           /* 1 if the pixel sees the surface */
    double tx, ty;     /* hit point in texel coordinates (texel i spans [i, i + 1)) */
    double fp;         /* footprint side in texels (isotropic, capped at the map size) */
    double wo[3], wi[3]; /* view and light in the pixel's tangent frame, unit */
} pic_sample;

/* One texel of a reference footprint, kept between the two passes of shade_reference. */
typedef struct {
    int x, y;          /* unwrapped texel coordinates */
    double at;         /* projected area (m.wo)/(m.z) */
    double term;       /* its specular term times at, when visible both ways in the full march */
    signed char vo, vi; /* full-march visibility toward wo, wi (-1: not marched) */
} ref_texel;

typedef struct {
    pfm_surface surf;
    pf_real *slope_pyr;   /* 5-moment pyramid */
    pf_real *normal_pyr;  /* average-normal pyramid */
    double *sat;          /* (W + 1) (H + 1) 5 summed-area table of the level-0 moments */
    unsigned char *vis_light_map; /* visibility toward a constant light (plane), or NULL */
    ref_texel *ref_scratch; /* the reference's texels of one pixel (REF_SCRATCH^2) */
    double t_pyramid;     /* seconds to build both pyramids */
} pic_maps;

/* flat = 1: the same map scaled to an RMS slope of FLAT_RMS_SLOPE (the pipeline self-check). */
static int maps_make(pic_maps *m, int flat)
{
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    int W = MAP_SIZE, H = MAP_SIZE, x, y, k;
    long long nt = pf_mip_texel_count(W, H);
    pf_real *heights, *normals;
    double t0;
    if (flat) p.rms_slope = FLAT_RMS_SLOPE;
    memset(m, 0, sizeof *m);
    if (pfm_surface_make(&m->surf, W, H, 1.0, p) != 0) return 1;
    heights = (pf_real *)malloc(sizeof(pf_real) * (size_t)W * (size_t)H);
    normals = (pf_real *)malloc(sizeof(pf_real) * 3 * (size_t)W * (size_t)H);
    m->slope_pyr = (pf_real *)malloc(sizeof(pf_real) * 5 * (size_t)nt);
    m->normal_pyr = (pf_real *)malloc(sizeof(pf_real) * 3 * (size_t)nt);
    m->sat = (double *)calloc((size_t)(W + 1) * (size_t)(H + 1) * 5, sizeof(double));
    m->ref_scratch = (ref_texel *)malloc(sizeof(ref_texel) * REF_SCRATCH * REF_SCRATCH);
    if (!heights || !normals || !m->slope_pyr || !m->normal_pyr || !m->sat || !m->ref_scratch)
        return 1;
    for (k = 0; k < W * H; ++k) heights[k] = (pf_real)m->surf.height[k];
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            double n[3];
            pfm_normal(&m->surf, x, y, n);
            for (k = 0; k < 3; ++k) normals[3 * (y * W + x) + k] = (pf_real)n[k];
        }
    t0 = now_seconds();
    pf_slope_pyramid_from_heights(heights, W, H, PF_R(1.0), PF_R(1.0), PF_R(1.0), PF_BORDER_WRAP,
                                  m->slope_pyr);
    pf_normal_pyramid_from_normals(normals, W, H, m->normal_pyr);
    m->t_pyramid = now_seconds() - t0;
    /* summed-area table of the level-0 moments, in double, from pfm's own slopes */
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            double sx, sy, t[5];
            double *o = m->sat + 5 * ((size_t)(y + 1) * (W + 1) + (x + 1));
            const double *l = m->sat + 5 * ((size_t)(y + 1) * (W + 1) + x);
            const double *u = m->sat + 5 * ((size_t)y * (W + 1) + (x + 1));
            const double *ul = m->sat + 5 * ((size_t)y * (W + 1) + x);
            pfm_slope(&m->surf, x, y, &sx, &sy);
            t[0] = sx;
            t[1] = sy;
            t[2] = sx * sx;
            t[3] = sy * sy;
            t[4] = sx * sy;
            for (k = 0; k < 5; ++k) o[k] = t[k] + l[k] + u[k] - ul[k];
        }
    free(heights);
    free(normals);
    return 0;
}

static void maps_free(pic_maps *m)
{
    pfm_surface_free(&m->surf);
    free(m->slope_pyr);
    free(m->normal_pyr);
    free(m->sat);
    free(m->vis_light_map);
    free(m->ref_scratch);
}

/* Sum of the level-0 moments over [0, x) x [0, y) of the periodic extension of the map. */
static void sat_periodic(const pic_maps *m, long x, long y, double out[5])
{
    int W = m->surf.w, H = m->surf.h, k;
    long qx = x >= 0 ? x / W : -((-x + W - 1) / W), qy = y >= 0 ? y / H : -((-y + H - 1) / H);
    int rx = (int)(x - qx * W), ry = (int)(y - qy * H);
    const double *tot = m->sat + 5 * ((size_t)H * (W + 1) + W);
    const double *row = m->sat + 5 * ((size_t)ry * (W + 1) + W);  /* S(W, ry) */
    const double *col = m->sat + 5 * ((size_t)H * (W + 1) + rx);  /* S(rx, H) */
    const double *in = m->sat + 5 * ((size_t)ry * (W + 1) + rx);  /* S(rx, ry) */
    for (k = 0; k < 5; ++k)
        out[k] = (double)qx * (double)qy * tot[k] + (double)qx * row[k] + (double)qy * col[k] +
                 in[k];
}

/* ---------------------------------------------------------------- the three shaders */
static int footprint_side(double fp)
{
    int n = (int)floor(fp + 0.5);
    return n < 1 ? 1 : n;
}

static int footprint_start(double t, int n) { return (int)floor(t - 0.5 * n + 0.5); }

typedef struct {
    double full;    /* the reference: occluders anywhere on the (periodic) surface */
    double inbox;   /* occluders inside the footprint box only */
    double noise;   /* subsampled footprints: half the difference of the two checkerboard
                       halves of the samples (~ the sampling deviation); 0 otherwise */
    double t_full, t_inbox; /* seconds spent on each */
    /* slopes only, no visibility: the NDF at the half vector's slope of the shaded texels
       (the mean of their base lobes) and of the Gaussian with the same texels' moments plus
       the base variance (what LEADR assumes, eqs. 8-10) */
    double ndf_texels, ndf_gauss;
} ref_result;

/* Brute force: the n x n box (or an evenly spaced ref_max^2 subset), one texel at a time
   through pfm_reference_shade (n = 1, visibility handled here), recombined with the texels'
   projected areas a_t = (m_t . wo)/(m_t . z) = wo.z - sx wo.x - sy wo.y (LEADR eq. 1): the
   footprint's value is sum_t V_o V_i spec_t a_t / sum_t a_t, which is pfm_reference_shade over
   the whole box when the box is shaded completely. Texels hidden from the viewer contribute
   0 to the numerator and their a_t to the denominator, so they are not marched toward the
   light. Second pass (the in-box variant): the texels occluded in the full march are marched
   again with only the box's own height field as occluder (pfm_visible_box; a texel free in the
   full march is free in the box). */
static ref_result shade_reference(pic_maps *m, const pic_sample *p, int ref_max)
{
    const pfm_surface *s = &m->surf;
    int n = footprint_side(p->fp), ns = n < ref_max ? n : ref_max, a, b, k = 0, q;
    int x0 = footprint_start(p->tx, n), y0 = footprint_start(p->ty, n);
    double num = 0.0, area = 0.0, half_num[2] = {0.0, 0.0}, half_area[2] = {0.0, 0.0};
    double num_box = 0.0, t0 = now_seconds(), t1, ndf = 0.0, mom[5] = {0, 0, 0, 0, 0};
    /* slope of the half vector: the texel's lobe at h is exp(-q) of its peak, q = |s_t -
       s_h|^2 / (2 sigma^2) (eq. 10) */
    double hz = p->wo[2] + p->wi[2], shx = 0.0, shy = 0.0;
    int lit = p->wi[2] > 0.0 && hz > 0.0;
    ref_result r;
    memset(&r, 0, sizeof r);
    if (lit) {
        shx = -(p->wo[0] + p->wi[0]) / hz;
        shy = -(p->wo[1] + p->wi[1]) / hz;
    }
    for (b = 0; b < ns; ++b) {
        int yu = y0 + (int)(((double)b + 0.5) * n / ns), y = wrap_index(yu, s->h);
        for (a = 0; a < ns; ++a, ++k) {
            int xu = x0 + (int)(((double)a + 0.5) * n / ns), x = wrap_index(xu, s->w);
            ref_texel *e = &m->ref_scratch[k];
            double sx, sy;
            pfm_slope(s, x, y, &sx, &sy);
            e->x = xu;
            e->y = yu;
            e->at = p->wo[2] - sx * p->wo[0] - sy * p->wo[1];
            e->term = 0.0;
            e->vo = e->vi = -1;
            area += e->at;
            half_area[(a + b) & 1] += e->at;
            mom[0] += sx;
            mom[1] += sy;
            mom[2] += sx * sx;
            mom[3] += sy * sy;
            mom[4] += sx * sy;
            if (lit) {
                double qq = ((sx - shx) * (sx - shx) + (sy - shy) * (sy - shy)) /
                            (2.0 * BASE_SIGMA * BASE_SIGMA);
                ndf += exp(-qq);
            }
            /* a texel whose lobe is below exp(-LOBE_CUTOFF) of its peak at h adds nothing
               measurable whatever its visibility: not marched (vo stays -1) */
            if (!lit || !(e->at > 0.0) ||
                ((sx - shx) * (sx - shx) + (sy - shy) * (sy - shy)) /
                        (2.0 * BASE_SIGMA * BASE_SIGMA) >
                    LOBE_CUTOFF)
                continue;
            e->vo = (signed char)pfm_visible(s, x, y, p->wo);
            if (m->vis_light_map) e->vi = (signed char)m->vis_light_map[(size_t)y * s->w + x];
            if (!e->vo) continue;
            if (e->vi < 0) e->vi = (signed char)pfm_visible(s, x, y, p->wi);
            if (!e->vi) continue;
            e->term = pfm_reference_shade(s, NULL, NULL, x, y, 1, p->wo, p->wi, BASE_SIGMA, F0)
                          .spec * e->at;
            num += e->term;
            half_num[(a + b) & 1] += e->term;
        }
    }
    t1 = now_seconds();
    r.t_full = t1 - t0;
    r.full = area > 0.0 ? num / area : 0.0;
    if (ns < n && half_area[0] > 0.0 && half_area[1] > 0.0)
        r.noise = 0.5 * fabs(half_num[0] / half_area[0] - half_num[1] / half_area[1]);
    if (lit) { /* P22 at s_h: the texels' lobes, and the Gaussian of their moments */
        double var = BASE_SIGMA * BASE_SIGMA, mx = mom[0] / k, my = mom[1] / k;
        double cxx = mom[2] / k - mx * mx + var, cyy = mom[3] / k - my * my + var;
        double cxy = mom[4] / k - mx * my, det = cxx * cyy - cxy * cxy;
        double dx = shx - mx, dy = shy - my;
        r.ndf_texels = ndf / k / (2.0 * pic_pi * var);
        r.ndf_gauss = exp(-0.5 * (cyy * dx * dx - 2.0 * cxy * dx * dy + cxx * dy * dy) / det) /
                      (2.0 * pic_pi * sqrt(det));
    }
    for (q = 0; q < k; ++q) {
        const ref_texel *e = &m->ref_scratch[q];
        int x = wrap_index(e->x, s->w), y = wrap_index(e->y, s->h);
        int bx0 = wrap_index(x0, s->w), by0 = wrap_index(y0, s->h);
        if (e->vo < 0) continue; /* not marched: negligible */
        if (e->vo && e->vi == 1) {
            num_box += e->term;
            continue;
        }
        if (!e->vo && !pfm_visible_box(s, x, y, p->wo, bx0, by0, n)) continue;
        if (e->vi != 1 && !pfm_visible_box(s, x, y, p->wi, bx0, by0, n)) continue;
        num_box += pfm_reference_shade(s, NULL, NULL, x, y, 1, p->wo, p->wi, BASE_SIGMA, F0)
                       .spec * e->at;
    }
    r.inbox = area > 0.0 ? num_box / area : 0.0;
    r.t_inbox = now_seconds() - t1;
    return r;
}

static pf_vec3 to_pf(const double a[3])
{
    return pf_vec3_make((pf_real)a[0], (pf_real)a[1], (pf_real)a[2]);
}

static pf_real pic_lod(double fp) { return (pf_real)(fp > 1.0 ? log2(fp) : 0.0); }

/* LEADR from the trilinear moment sample at the footprint's level of detail. */
static double shade_leadr(const pic_maps *m, const pic_sample *p)
{
    pf_slope_moments mo = pf_slope_moments_sample(
        m->slope_pyr, m->surf.w, m->surf.h, pic_lod(p->fp), (pf_real)(p->tx / m->surf.w),
        (pf_real)(p->ty / m->surf.h), PF_BORDER_WRAP);
    pf_slope_stats st = pf_slope_moments_stats(mo, (pf_real)(BASE_SIGMA * BASE_SIGMA));
    return (double)pf_leadr_specular(to_pf(p->wo), to_pf(p->wi), st, (pf_real)F0);
}

/* The mip-mapped normal: the base lobe alone around the renormalized average normal. */
static double shade_naive(const pic_maps *m, const pic_sample *p)
{
    pf_vec3 n = pf_normal_avg_sample(m->normal_pyr, m->surf.w, m->surf.h, pic_lod(p->fp),
                                     (pf_real)(p->tx / m->surf.w), (pf_real)(p->ty / m->surf.h),
                                     PF_BORDER_WRAP);
    pf_slope_moments mo = pf_slope_moments_from_normal(n);
    pf_slope_stats st = pf_slope_moments_stats(mo, (pf_real)(BASE_SIGMA * BASE_SIGMA));
    return (double)pf_leadr_specular(to_pf(p->wo), to_pf(p->wi), st, (pf_real)F0);
}

/* LEADR fed with the exact moments of the reference's box (the model's own error). */
static double shade_leadr_box(const pic_maps *m, const pic_sample *p)
{
    int n = footprint_side(p->fp), k;
    long x0 = footprint_start(p->tx, n), y0 = footprint_start(p->ty, n);
    double a[5], b[5], c[5], d[5], inv = 1.0 / ((double)n * (double)n);
    pf_real mo[5];
    pf_slope_stats st;
    sat_periodic(m, x0 + n, y0 + n, a);
    sat_periodic(m, x0, y0 + n, b);
    sat_periodic(m, x0 + n, y0, c);
    sat_periodic(m, x0, y0, d);
    for (k = 0; k < 5; ++k) mo[k] = (pf_real)((a[k] - b[k] - c[k] + d[k]) * inv);
    st = pf_slope_moments_stats(pf_slope_moments_make(mo[0], mo[1], mo[2], mo[3], mo[4]),
                                (pf_real)(BASE_SIGMA * BASE_SIGMA));
    return (double)pf_leadr_specular(to_pf(p->wo), to_pf(p->wi), st, (pf_real)F0);
}

/* ---------------------------------------------------------------- scenes: per-pixel geometry */
typedef struct {
    const char *name;
    int w, h;
    double exposure;
    double bg[3];          /* background colour (linear) */
    int ref_max;           /* reference texels per footprint side, at most */
    pic_sample *px;
} pic_scene;

/* Camera: position, orthonormal right/up/forward, tan of half the vertical field of view. */
typedef struct {
    double pos[3], right[3], up[3], fwd[3];
    double tan_half;
    int w, h;
} pic_camera;

static void camera_ray(const pic_camera *c, double px, double py, double d[3])
{
    double sx = (2.0 * (px + 0.5) / c->w - 1.0) * c->tan_half * c->w / c->h;
    double sy = (1.0 - 2.0 * (py + 0.5) / c->h) * c->tan_half;
    int k;
    for (k = 0; k < 3; ++k) d[k] = c->fwd[k] + sx * c->right[k] + sy * c->up[k];
    v3_normalize(d);
}

/* Intersection of the ray (o, d) with the plane through p with normal n; 0 if parallel. */
static int ray_plane(const double o[3], const double d[3], const double p[3], const double n[3],
                     double hit[3])
{
    double dn = v3_dot(d, n), op[3], t;
    int k;
    if (fabs(dn) < 1e-12) return 0;
    for (k = 0; k < 3; ++k) op[k] = p[k] - o[k];
    t = v3_dot(op, n) / dn;
    if (!(t > 0.0)) return 0;
    for (k = 0; k < 3; ++k) hit[k] = o[k] + t * d[k];
    return 1;
}

/* The footprint in texels from the two neighbour rays, intersected with the tangent plane at
   the hit; du[k], dv[k]: texel coordinates per unit world length along the tangent axes
   (tx_axis, ty_axis). Capped at the map size. */
static double footprint_texels(const pic_camera *c, int i, int j, const double hit[3],
                               const double n[3], const double tx_axis[3], const double ty_axis[3],
                               double tex_per_x, double tex_per_y, double cap)
{
    double best = 0.0;
    int k, e;
    for (e = 0; e < 2; ++e) {
        double d[3], h2[3], off[3], a, b, l;
        camera_ray(c, i + (e == 0 ? 1.0 : 0.0), j + (e == 1 ? 1.0 : 0.0), d);
        if (!ray_plane(c->pos, d, hit, n, h2)) return cap;
        for (k = 0; k < 3; ++k) off[k] = h2[k] - hit[k];
        a = v3_dot(off, tx_axis) * tex_per_x;
        b = v3_dot(off, ty_axis) * tex_per_y;
        l = sqrt(a * a + b * b);
        if (l > best) best = l;
    }
    return best < cap ? best : cap;
}

static void camera_look(pic_camera *c, const double pos[3], const double fwd[3], double fov_deg,
                        int w, int h)
{
    double world_up[3] = {0.0, 0.0, 1.0};
    int k;
    for (k = 0; k < 3; ++k) c->pos[k] = pos[k];
    for (k = 0; k < 3; ++k) c->fwd[k] = fwd[k];
    v3_normalize(c->fwd);
    /* right = fwd x up, up = right x fwd */
    v3_set(c->right, c->fwd[1] * world_up[2] - c->fwd[2] * world_up[1],
           c->fwd[2] * world_up[0] - c->fwd[0] * world_up[2],
           c->fwd[0] * world_up[1] - c->fwd[1] * world_up[0]);
    v3_normalize(c->right);
    v3_set(c->up, c->right[1] * c->fwd[2] - c->right[2] * c->fwd[1],
           c->right[2] * c->fwd[0] - c->right[0] * c->fwd[2],
           c->right[0] * c->fwd[1] - c->right[1] * c->fwd[0]);
    c->tan_half = tan(0.5 * fov_deg * pic_pi / 180.0);
    c->w = w;
    c->h = h;
}

#define PLANE_CAM_HEIGHT 90.0
#define PLANE_PITCH_DEG  14.0
#define PLANE_FOV_DEG    40.0
#ifndef PLANE_LIGHT_ELEV
#  define PLANE_LIGHT_ELEV 20.0 /* 12 in the first version: mostly shadowed, mostly black */
#endif
#define PLANE_LIGHT_AZIM 10.0
#define PLANE_EXPOSURE   0.35   /* fixed; puts the reference's 99th percentile near 0.9 */

/* Plane z = 0, tangent frame = world frame, texel = 1 world unit. */
static void scene_plane(pic_scene *sc, pic_maps *m, int w, int h)
{
    pic_camera cam;
    double pos[3] = {0.0, 0.0, PLANE_CAM_HEIGHT}, fwd[3], wi[3];
    double pz[3] = {0.0, 0.0, 0.0}, nz[3] = {0.0, 0.0, 1.0}, ax[3] = {1, 0, 0}, ay[3] = {0, 1, 0};
    double pitch = PLANE_PITCH_DEG * pic_pi / 180.0;
    double el = PLANE_LIGHT_ELEV * pic_pi / 180.0, az = PLANE_LIGHT_AZIM * pic_pi / 180.0;
    int i, j;
    v3_set(fwd, 0.0, cos(pitch), -sin(pitch));
    camera_look(&cam, pos, fwd, PLANE_FOV_DEG, w, h);
    v3_set(wi, sin(az) * cos(el), cos(az) * cos(el), sin(el));
    sc->name = "plane";
    sc->w = w;
    sc->h = h;
    sc->exposure = PLANE_EXPOSURE;
    sc->ref_max = REF_MAX_SAMPLES;
    v3_set(sc->bg, 0.30, 0.42, 0.60);
    sc->px = (pic_sample *)calloc((size_t)w * (size_t)h, sizeof(pic_sample));
    /* the light is the same direction in every pixel's (world) frame: one visibility map */
    m->vis_light_map = (unsigned char *)malloc((size_t)m->surf.w * (size_t)m->surf.h);
    pfm_visibility_map(&m->surf, wi, m->vis_light_map);
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i) {
            pic_sample *p = &sc->px[(size_t)j * w + i];
            double d[3], hit[3];
            camera_ray(&cam, i, j, d);
            if (d[2] > -1e-3 || !ray_plane(cam.pos, d, pz, nz, hit)) continue;
            p->hit = 1;
            p->tx = hit[0];
            p->ty = hit[1];
            v3_set(p->wo, -d[0], -d[1], -d[2]);
            v3_set(p->wi, wi[0], wi[1], wi[2]);
            p->fp = footprint_texels(&cam, i, j, hit, nz, ax, ay, 1.0, 1.0, (double)m->surf.w);
        }
}

#define SPHERE_RADIUS    100.0
#define SPHERE_CAM_DIST  330.0
#define SPHERE_FOV_DEG   40.0
#define SPHERE_EXPOSURE  2.0

/* Sphere of radius R at the origin, pole along +z; longitude phi, colatitude theta; texture
   u = phi / (2 pi) * tiles, v = (1 - theta / pi) * tiles / 2 (texels square at the equator). */
static void scene_sphere(pic_scene *sc, pic_maps *m, int w, int h)
{
    pic_camera cam;
    double pos[3] = {0.0, -SPHERE_CAM_DIST, 0.25 * SPHERE_RADIUS}, fwd[3], L[3];
    double W = (double)m->surf.w, H = (double)m->surf.h;
    int i, j, k;
    v3_set(fwd, -pos[0], -pos[1], -pos[2]);
    camera_look(&cam, pos, fwd, SPHERE_FOV_DEG, w, h);
    v3_set(L, 0.5, -0.6, 0.6); /* toward the light: upper right, in front of the sphere */
    v3_normalize(L);
    sc->name = "sphere";
    sc->w = w;
    sc->h = h;
    sc->exposure = SPHERE_EXPOSURE;
    sc->ref_max = SPHERE_REF_MAX;
    v3_set(sc->bg, 0.08, 0.09, 0.11);
    sc->px = (pic_sample *)calloc((size_t)w * (size_t)h, sizeof(pic_sample));
    m->vis_light_map = NULL;
    for (j = 0; j < h; ++j)
        for (i = 0; i < w; ++i) {
            pic_sample *p = &sc->px[(size_t)j * w + i];
            double d[3], oc[3], b, c, disc, t, hit[3], n[3], tu[3], tv[3], phi, theta, st;
            camera_ray(&cam, i, j, d);
            for (k = 0; k < 3; ++k) oc[k] = cam.pos[k];
            b = v3_dot(oc, d);
            c = v3_dot(oc, oc) - SPHERE_RADIUS * SPHERE_RADIUS;
            disc = b * b - c;
            if (disc <= 0.0) continue;
            t = -b - sqrt(disc);
            if (t <= 0.0) continue;
            for (k = 0; k < 3; ++k) hit[k] = cam.pos[k] + t * d[k];
            for (k = 0; k < 3; ++k) n[k] = hit[k] / SPHERE_RADIUS;
            phi = atan2(n[1], n[0]);
            if (phi < 0.0) phi += 2.0 * pic_pi;
            theta = acos(n[2] > 1.0 ? 1.0 : (n[2] < -1.0 ? -1.0 : n[2]));
            st = sin(theta);
            if (st < 1e-6) continue;
            /* tangent x: increasing longitude; tangent y: toward the north pole (n x tu) */
            v3_set(tu, -sin(phi), cos(phi), 0.0);
            v3_set(tv, n[1] * tu[2] - n[2] * tu[1], n[2] * tu[0] - n[0] * tu[2],
                   n[0] * tu[1] - n[1] * tu[0]);
            p->hit = 1;
            p->tx = phi / (2.0 * pic_pi) * SPHERE_TILES * W;
            p->ty = (1.0 - theta / pic_pi) * 0.5 * SPHERE_TILES * H;
            /* texels per world unit: along tu, 1/(R sin theta) radians of longitude; along tv,
               1/R radians of latitude */
            p->fp = footprint_texels(&cam, i, j, hit, n, tu, tv,
                                     SPHERE_TILES * W / (2.0 * pic_pi * SPHERE_RADIUS * st),
                                     SPHERE_TILES * H / (2.0 * pic_pi * SPHERE_RADIUS), W);
            v3_set(p->wo, -v3_dot(d, tu), -v3_dot(d, tv), -v3_dot(d, n));
            v3_set(p->wi, v3_dot(L, tu), v3_dot(L, tv), v3_dot(L, n));
            if (p->wo[2] <= 1e-6) p->wo[2] = 1e-6; /* silhouette rounding */
            v3_normalize(p->wo);
        }
}

/* ---------------------------------------------------------------- images */
static unsigned char to_byte(double v)
{
    v = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
    return (unsigned char)floor(255.0 * v + 0.5);
}

/* Fixed exposure e per scene (the same for every panel), a soft shoulder 1 - exp(-e L) instead
   of a hard clip (highlights keep their shape), then gamma 2.2. */
static void tone(double L, double exposure, unsigned char out[3])
{
    double v = pow(1.0 - exp(-exposure * (L > 0.0 ? L : 0.0)), 1.0 / 2.2);
    v = floor(v * (GREY_LEVELS - 1) + 0.5) / (GREY_LEVELS - 1);
    out[0] = out[1] = out[2] = to_byte(v);
}

/* An approximation of the "inferno" colour map: black - purple - red - orange - pale yellow. */
static void heat_colour(double t, unsigned char out[3])
{
    static const double stops[6][3] = {{0, 0, 4},       {66, 10, 104},  {147, 38, 103},
                                       {221, 81, 58},   {252, 165, 10}, {252, 255, 164}};
    int i, k;
    double f;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    t = floor(t * (HEAT_LEVELS - 1) + 0.5) / (HEAT_LEVELS - 1);
    i = (int)floor(t * 5.0);
    if (i > 4) i = 4;
    f = t * 5.0 - i;
    for (k = 0; k < 3; ++k)
        out[k] = to_byte(((1.0 - f) * stops[i][k] + f * stops[i + 1][k]) / 255.0);
}

static double err_to_unit(double e)
{
    double l = log10(e > 1e-12 ? e : 1e-12);
    return (l - ERR_LOG_MIN) / (ERR_LOG_MAX - ERR_LOG_MIN);
}

static void blit(unsigned char *dst, int dw, int x0, int y0, const unsigned char *src, int w, int h)
{
    int y;
    for (y = 0; y < h; ++y)
        memcpy(dst + 3 * ((size_t)(y0 + y) * dw + x0), src + 3 * (size_t)y * w, 3 * (size_t)w);
}

/* ---------------------------------------------------------------- statistics */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* q-quantile (0..1) of v[0..n-1] (sorted copy, nearest rank). */
static double quantile(const double *v, int n, double q)
{
    double *c, r;
    int i;
    if (n <= 0) return 0.0;
    c = (double *)malloc(sizeof(double) * (size_t)n);
    memcpy(c, v, sizeof(double) * (size_t)n);
    qsort(c, (size_t)n, sizeof(double), cmp_double);
    i = (int)ceil(q * n) - 1;
    r = c[i < 0 ? 0 : (i >= n ? n - 1 : i)];
    free(c);
    return r;
}

typedef struct { double mean, p95; } pic_err;

#define PIC_BINS 9

static int footprint_bin(double fp)
{
    int b = 0;
    while (b < PIC_BINS - 1 && fp >= (double)(2 << b)) ++b;
    return b;
}

enum { M_REF = 0, M_LEADR, M_NAIVE, M_BOX, M_COUNT };
static const char *const method_label[M_COUNT] = {"reference (brute force)", "LEADR (trilinear)",
                                                  "naive mip-mapped normal",
                                                  "LEADR, exact box moments"};

typedef struct {
    double *val[M_COUNT];
    double *inbox;           /* the reference with occluders inside the footprint box only */
    double *noise;           /* the reference's sampling deviation estimate (0: shaded fully) */
    double *ndf_t, *ndf_g;   /* NDF at h: the shaded texels' lobes, their Gaussian fit */
    double floor_ndf;        /* LIT_FRACTION of the 99th percentile of ndf_t */
    double seconds[M_COUNT]; /* shading time over all surface pixels */
    double seconds_inbox;    /* the in-box variant's extra marching and shading */
    int n_surface, n_lit, n_subsampled;
    int n_lit_u;             /* surface pixels lit in either reference (full or in-box) */
    int n_zero[M_COUNT];     /* lit pixels where the method returns exactly 0 (culled) */
    double floor;
    pic_err err[M_COUNT];    /* against the reference */
    pic_err err_in[M_COUNT]; /* against the in-box reference over the pixels lit in either
                                reference (M_REF: the full reference against the in-box one) */
    double fp_min, fp_med, fp_p95, fp_max;
    double samples_per_pixel; /* reference texels shaded per surface pixel (mean) */
    /* by footprint side: bin b holds sides in [2^b, 2^(b+1)) (bin 0 also below 1) */
    int bin_lit[PIC_BINS], bin_surface[PIC_BINS], bin_noisy[PIC_BINS], bin_lit_u[PIC_BINS];
    double bin_err[PIC_BINS][M_COUNT];    /* mean relative error over the bin's lit pixels */
    double bin_ratio[PIC_BINS][M_COUNT];  /* sum method / sum reference over all its pixels */
    /* over the pixels lit in either reference: mean relative error against the in-box
       reference, and against the full one (the two compared on the same pixels) */
    double bin_err_in[PIC_BINS][M_COUNT], bin_err_u[PIC_BINS][M_COUNT];
    double bin_noise[PIC_BINS];           /* rms relative sampling deviation of the reference */
    double bin_ndf[PIC_BINS];             /* mean NDF error over the bin's pixels lit in either */
} pic_result;

/* Relative error of v against the reference value ref: |v - ref| / max(ref, floor). */
static double rel_err(double v, double ref, double floor_)
{
    return fabs(v - ref) / (ref > floor_ ? ref : floor_);
}

/* Comparisons between the two references (pixels lit in either): every error of pixel i is
   divided by the larger of the two references and the floor, so that errors against the full
   and against the in-box reference differ only in their numerators. */
static double pair_floor(const pic_result *r, int i)
{
    double a = r->val[M_REF][i], b = r->inbox[i];
    double m = a > b ? a : b;
    return m > r->floor ? m : r->floor;
}

static double run_method(pic_maps *m, const pic_scene *sc, int method, double *out)
{
    int i, n = sc->w * sc->h;
    double t0 = now_seconds();
    for (i = 0; i < n; ++i) {
        const pic_sample *p = &sc->px[i];
        if (!p->hit) {
            out[i] = 0.0;
            continue;
        }
        switch (method) {
        case M_LEADR: out[i] = shade_leadr(m, p); break;
        case M_NAIVE: out[i] = shade_naive(m, p); break;
        default: out[i] = shade_leadr_box(m, p); break;
        }
    }
    return now_seconds() - t0;
}

/* The brute force over every surface pixel: the reference, its in-box variant and the
   sampling deviation estimate; the two variants timed apart. */
static void run_reference(pic_maps *m, const pic_scene *sc, pic_result *r)
{
    int i, n = sc->w * sc->h;
    for (i = 0; i < n; ++i) {
        ref_result q;
        r->val[M_REF][i] = r->inbox[i] = r->noise[i] = r->ndf_t[i] = r->ndf_g[i] = 0.0;
        if (!sc->px[i].hit) continue;
        q = shade_reference(m, &sc->px[i], sc->ref_max);
        r->val[M_REF][i] = q.full;
        r->inbox[i] = q.inbox;
        r->noise[i] = q.noise;
        r->ndf_t[i] = q.ndf_texels;
        r->ndf_g[i] = q.ndf_gauss;
        r->seconds[M_REF] += q.t_full;
        r->seconds_inbox += q.t_inbox;
    }
}

static void render_scene(pic_maps *m, const pic_scene *sc, pic_result *r)
{
    int n = sc->w * sc->h, i, k, mth, b;
    double *tmp = (double *)malloc(sizeof(double) * (size_t)n);
    double *tmp_in = (double *)malloc(sizeof(double) * (size_t)n);
    double *fps = (double *)malloc(sizeof(double) * (size_t)n);
    double samples = 0.0, sref[PIC_BINS];
    memset(r, 0, sizeof *r);
    for (mth = 0; mth < M_COUNT; ++mth)
        r->val[mth] = (double *)malloc(sizeof(double) * (size_t)n);
    r->inbox = (double *)malloc(sizeof(double) * (size_t)n);
    r->noise = (double *)malloc(sizeof(double) * (size_t)n);
    r->ndf_t = (double *)malloc(sizeof(double) * (size_t)n);
    r->ndf_g = (double *)malloc(sizeof(double) * (size_t)n);
    run_reference(m, sc, r);
    for (mth = 1; mth < M_COUNT; ++mth) { /* cheap: best of 5 passes */
        r->seconds[mth] = 1e30;
        for (k = 0; k < 5; ++k) {
            double t = run_method(m, sc, mth, r->val[mth]);
            if (t < r->seconds[mth]) r->seconds[mth] = t;
        }
    }
    for (i = 0; i < n; ++i)
        if (sc->px[i].hit) {
            int side = footprint_side(sc->px[i].fp);
            int ns = side < sc->ref_max ? side : sc->ref_max;
            fps[r->n_surface] = sc->px[i].fp;
            tmp[r->n_surface++] = r->val[M_REF][i];
            samples += (double)ns * ns;
            if (side > sc->ref_max) r->n_subsampled++;
        }
    r->samples_per_pixel = r->n_surface ? samples / r->n_surface : 0.0;
    r->floor = LIT_FRACTION * quantile(tmp, r->n_surface, 0.99);
    for (i = 0, k = 0; i < n; ++i)
        if (sc->px[i].hit) tmp_in[k++] = r->ndf_t[i];
    r->floor_ndf = LIT_FRACTION * quantile(tmp_in, k, 0.99);
    printf("  reference quantiles: 50%% %.3g, 90%% %.3g, 99%% %.3g\n",
           quantile(tmp, r->n_surface, 0.5), quantile(tmp, r->n_surface, 0.9),
           quantile(tmp, r->n_surface, 0.99));
    r->fp_min = quantile(fps, r->n_surface, 0.0);
    r->fp_med = quantile(fps, r->n_surface, 0.5);
    r->fp_p95 = quantile(fps, r->n_surface, 0.95);
    r->fp_max = quantile(fps, r->n_surface, 1.0);
    /* lit pixels: the reference at least the floor; errors against the reference and against
       the in-box reference (M_REF's "error" against the in-box one: how much the occluders
       outside the footprint change the answer) */
    for (mth = 0; mth < M_COUNT; ++mth) {
        int nl = 0, nu = 0;
        double sum = 0.0, sum_in = 0.0;
        for (i = 0; i < n; ++i) {
            double ref = r->val[M_REF][i];
            if (!sc->px[i].hit) continue;
            if (ref >= r->floor) {
                tmp[nl] = rel_err(r->val[mth][i], ref, r->floor);
                if (r->val[mth][i] == 0.0) r->n_zero[mth]++;
                sum += tmp[nl++];
            }
            if (ref >= r->floor || r->inbox[i] >= r->floor) {
                tmp_in[nu] = rel_err(r->val[mth][i], r->inbox[i], pair_floor(r, i));
                sum_in += tmp_in[nu++];
            }
        }
        r->n_lit = nl;
        r->n_lit_u = nu;
        r->err[mth].mean = nl ? sum / nl : 0.0;
        r->err[mth].p95 = quantile(tmp, nl, 0.95);
        r->err_in[mth].mean = nu ? sum_in / nu : 0.0;
        r->err_in[mth].p95 = quantile(tmp_in, nu, 0.95);
    }
    memset(sref, 0, sizeof sref);
    for (i = 0; i < n; ++i) {
        double ref = r->val[M_REF][i];
        if (!sc->px[i].hit) continue;
        b = footprint_bin(sc->px[i].fp);
        r->bin_surface[b]++;
        sref[b] += ref;
        for (mth = 1; mth < M_COUNT; ++mth) r->bin_ratio[b][mth] += r->val[mth][i];
        r->bin_ratio[b][M_REF] += r->inbox[i];
        if (ref >= r->floor || r->inbox[i] >= r->floor) { /* lit in either reference */
            r->bin_lit_u[b]++;
            r->bin_ndf[b] += rel_err(r->ndf_g[i], r->ndf_t[i], r->floor_ndf);
            for (mth = 0; mth < M_COUNT; ++mth) {
                r->bin_err_u[b][mth] += rel_err(r->val[mth][i], ref, pair_floor(r, i));
                r->bin_err_in[b][mth] += rel_err(r->val[mth][i], r->inbox[i], pair_floor(r, i));
            }
        }
        if (!(ref >= r->floor)) continue;
        r->bin_lit[b]++;
        for (mth = 0; mth < M_COUNT; ++mth)
            r->bin_err[b][mth] += rel_err(r->val[mth][i], ref, r->floor);
        if (footprint_side(sc->px[i].fp) > sc->ref_max) {
            double e = r->noise[i] / (ref > r->floor ? ref : r->floor);
            r->bin_noisy[b]++;
            r->bin_noise[b] += e * e;
        }
    }
    for (b = 0; b < PIC_BINS; ++b) {
        for (mth = 0; mth < M_COUNT; ++mth) {
            if (r->bin_lit[b]) r->bin_err[b][mth] /= r->bin_lit[b];
            if (r->bin_lit_u[b]) {
                r->bin_err_u[b][mth] /= r->bin_lit_u[b];
                r->bin_err_in[b][mth] /= r->bin_lit_u[b];
            }
            if (sref[b] > 0.0) r->bin_ratio[b][mth] /= sref[b];
        }
        if (r->bin_noisy[b]) r->bin_noise[b] = sqrt(r->bin_noise[b] / r->bin_noisy[b]);
        if (r->bin_lit_u[b]) r->bin_ndf[b] /= r->bin_lit_u[b];
    }
    free(tmp);
    free(tmp_in);
    free(fps);
}

static void result_free(pic_result *r)
{
    int k;
    for (k = 0; k < M_COUNT; ++k) free(r->val[k]);
    free(r->inbox);
    free(r->noise);
    free(r->ndf_t);
    free(r->ndf_g);
}

/* 3 x 2 panels: reference | LEADR | naive ; colour bar | LEADR error | naive error. */
static int write_picture(const pic_scene *sc, const pic_result *r, const char *path,
                         long *bytes)
{
    int w = sc->w, h = sc->h, W = 3 * w + 4 * PANEL_GAP, H = 2 * h + 3 * PANEL_GAP, i, k, y;
    unsigned char *img = (unsigned char *)malloc((size_t)W * H * 3);
    unsigned char *panel = (unsigned char *)malloc((size_t)w * h * 3);
    unsigned char bg[3];
    int methods[3] = {M_REF, M_LEADR, M_NAIVE}, rc;
    memset(img, 255, (size_t)W * H * 3);
    for (k = 0; k < 3; ++k) bg[k] = to_byte(pow(sc->bg[k], 1.0 / 2.2));
    for (k = 0; k < 3; ++k) { /* images */
        for (i = 0; i < w * h; ++i) {
            if (sc->px[i].hit) tone(r->val[methods[k]][i], sc->exposure, panel + 3 * i);
            else memcpy(panel + 3 * i, bg, 3);
        }
        blit(img, W, PANEL_GAP + k * (w + PANEL_GAP), PANEL_GAP, panel, w, h);
    }
    for (k = 1; k < 3; ++k) { /* error maps */
        for (i = 0; i < w * h; ++i) {
            double ref = r->val[M_REF][i], e;
            if (!sc->px[i].hit) {
                panel[3 * i] = panel[3 * i + 1] = panel[3 * i + 2] = 96;
                continue;
            }
            e = fabs(r->val[methods[k]][i] - ref) / (ref > r->floor ? ref : r->floor);
            heat_colour(err_to_unit(e), panel + 3 * i);
        }
        blit(img, W, PANEL_GAP + k * (w + PANEL_GAP), 2 * PANEL_GAP + h, panel, w, h);
    }
    /* colour bar: a vertical strip, bottom = 3%, top = 316%, black ticks at each half decade */
    {
        int bw = w / 8 > 8 ? w / 8 : 8, bx = PANEL_GAP + (w - bw) / 2, by = 2 * PANEL_GAP + h;
        int top = by + h / 10, bot = by + h - h / 10, x;
        static const double ticks[5] = {0.0316, 0.1, 0.316, 1.0, 3.16};
        for (y = top; y <= bot; ++y) {
            unsigned char c[3];
            heat_colour((double)(bot - y) / (double)(bot - top), c);
            for (x = bx; x < bx + bw; ++x) memcpy(img + 3 * ((size_t)y * W + x), c, 3);
        }
        for (k = 0; k < 5; ++k) {
            int ty = bot - (int)floor(err_to_unit(ticks[k]) * (bot - top) + 0.5);
            int len = (k % 2 == 0) ? bw / 2 + 4 : bw / 4 + 2;
            for (x = bx + bw; x < bx + bw + len && x < W; ++x)
                memset(img + 3 * ((size_t)ty * W + x), 0, 3);
            for (x = bx - len; x < bx; ++x)
                if (x >= 0) memset(img + 3 * ((size_t)ty * W + x), 0, 3);
        }
    }
    rc = png_write(path, img, W, H, bytes);
    free(img);
    free(panel);
    return rc;
}

/* ---------------------------------------------------------------- main */
static const char *const err_scale_text =
    "relative error, log scale: 3% at the bottom (black) to 316% at the top (pale yellow), "
    "ticks at 3, 10, 32, 100, 316%";

/* Mean of a per-bin quantity over bins b0 .. b1 - 1, weighted by the counts of pixels lit in
   either reference (noise = 1: rms, weighted by the counts of subsampled lit pixels). */
static double bins_mean(const pic_result *r, const double *per_bin, int stride, int b0, int b1,
                        int noise)
{
    double s = 0.0, w = 0.0;
    int b;
    for (b = b0; b < b1; ++b) {
        double wb = noise ? (double)r->bin_noisy[b] : (double)r->bin_lit_u[b];
        double v = per_bin[b * stride];
        s += wb * (noise ? v * v : v);
        w += wb;
    }
    if (!(w > 0.0)) return 0.0;
    return noise ? sqrt(s / w) : s / w;
}

#define SMALL_BINS 4 /* bins 0-3: footprint sides under 16 texels */

/* x as a percentage for "%.0f%%", without a "-0" for tiny negatives */
/* First cell of a footprint-bin row: bin k holds sides in [2^k, 2^(k+1)) texels, the first
   everything below 2 and the last everything from 2^k up. */
static void print_bin_label(FILE *md, int k)
{
    if (k == 0) fprintf(md, "| < 2 |");
    else if (k == PIC_BINS - 1) fprintf(md, "| >= %d |", 1 << k);
    else fprintf(md, "| %d - %d |", 1 << k, 2 << k);
}

static double pct(double x)
{
    double v = 100.0 * x;
    return fabs(v) < 0.5 ? 0.0 : v;
}

static void describe_scene(FILE *md, const pic_scene *sc, const pic_result *r, const char *png,
                           const pic_maps *m)
{
    pfm_params p = pfm_params_default(PFM_GAUSSIAN);
    double us_ref = 1e6 * r->seconds[M_REF] / r->n_surface;
    double box_s, box_l, in_s, in_l, oof_s, oof_l, tri_s, tri_l, trin_s, trin_l, noise_l;
    double ndf_s, ndf_l;
    int k, lit_s = 0, lit_l = 0, n_noisy = 0;
    fprintf(md, "![%s: reference, LEADR, naive; colour bar, LEADR error, naive error](%s)\n\n",
            sc->name, png);
    if (strcmp(sc->name, "plane") == 0)
        fprintf(md,
                "**Rough specular plane.** A %dx%d Gaussian height map (`pfm` corpus defaults: "
                "RMS slope %.2f per axis, correlation length %.0f texels), tiled on the plane "
                "z = 0, seen by a pinhole camera %.0f texels above it, pitched %.0f degrees down "
                "(vertical field of view %.0f degrees) toward the horizon; a directional light "
                "%.0f degrees above the horizon, in front of the camera (%.0f degrees to the "
                "right). The footprints run from resolved bumps near the camera to thousands of "
                "bumps at the horizon. ",
                m->surf.w, m->surf.h, p.rms_slope, p.corr_texels, PLANE_CAM_HEIGHT,
                PLANE_PITCH_DEG, PLANE_FOV_DEG, PLANE_LIGHT_ELEV, PLANE_LIGHT_AZIM);
    else
        fprintf(md,
                "**Sphere, in LEADR's domain.** The same %dx%d height map wrapped around a "
                "sphere (longitude-latitude map, %d tiles around the equator, texels square at "
                "the equator), seen from %.1f radii; a directional light from the upper right, on "
                "the camera's side; view and light rotated into each pixel's tangent frame. The "
                "map is tiled finely enough that every pixel covers several to many bumps "
                "(footprint sides of %.0f texels and more against the %.0f-texel correlation "
                "length): the regime where LEADR claims to match a supersampled reference "
                "(Dupuy et al. 2013 sec. 7). ",
                m->surf.w, m->surf.h, SPHERE_TILES, SPHERE_CAM_DIST / SPHERE_RADIUS,
                floor(r->fp_min), p.corr_texels);
    fprintf(md,
            "Image %dx%d pixels: %d on the surface, %d lit (reference >= %.0f%% of its 99th "
            "percentile). Footprint side in texels: min %.2f, median %.1f, 95th percentile %.0f, "
            "max %.0f; the reference shades the round(side)^2 texel box (%d pixels with a side "
            "over %d subsampled to %dx%d evenly spaced texels; %.0f texels shaded per pixel on "
            "average). Base lobe deviation %.2f, no Fresnel. Top: reference, LEADR, naive "
            "mip-mapped normal (same fixed exposure %.2f, display 1 - exp(-exposure L), gamma "
            "2.2). Bottom: colour bar (%s), error of LEADR, error of naive.\n\n",
            sc->w, sc->h, r->n_surface, r->n_lit, 100.0 * LIT_FRACTION, r->fp_min, r->fp_med,
            r->fp_p95, r->fp_max, r->n_subsampled, sc->ref_max, sc->ref_max, sc->ref_max,
            r->samples_per_pixel, BASE_SIGMA, sc->exposure, err_scale_text);
    fprintf(
        md,
        "| %s: method | mean rel. error (lit pixels) | 95th percentile | against the in-box "
        "reference (pixels lit in either): mean, 95th | lit pixels returned 0 | time per pixel | "
        "brute force / this |\n|---|---|---|---|---|---|---|\n",
        sc->name);
    fprintf(md, "| %s | - | - | %.1f%%, %.1f%% | - | %.1f us | 1 |\n", method_label[M_REF],
            100.0 * r->err_in[M_REF].mean, 100.0 * r->err_in[M_REF].p95, us_ref);
    for (k = 1; k < M_COUNT; ++k)
        fprintf(md, "| %s | %.1f%% | %.1f%% | %.1f%%, %.1f%% | %d | %.0f ns | %.0f |\n",
                method_label[k], 100.0 * r->err[k].mean, 100.0 * r->err[k].p95,
                100.0 * r->err_in[k].mean, 100.0 * r->err_in[k].p95, r->n_zero[k],
                1e9 * r->seconds[k] / r->n_surface, r->seconds[M_REF] / r->seconds[k]);
    fprintf(md, "\nBy footprint side: mean relative error over the lit pixels, and the bias "
                "sum(method) / sum(reference) over all surface pixels of the row (a bias above 1 "
                "in rows with few lit pixels comes from the Gaussian lobe's tails lighting pixels "
                "that the reference leaves dark).\n\n"
                "| %s: footprint side (texels) | surface pixels | lit | LEADR (trilinear): "
                "error, bias | LEADR, exact box | naive |\n|---|---|---|---|---|---|\n",
            sc->name);
    for (k = 0; k < PIC_BINS; ++k) {
        if (!r->bin_surface[k]) continue;
        print_bin_label(md, k);
        fprintf(md, " %d | %d |", r->bin_surface[k], r->bin_lit[k]);
        if (r->bin_lit[k] == 0) {
            fprintf(md, " - | - | - |\n"); /* nothing lit: no error, and the bias is 0/0 */
            continue;
        }
        fprintf(md, " %.0f%%, %.2f | %.0f%%, %.2f | %.0f%%, %.2f |\n",
                100.0 * r->bin_err[k][M_LEADR], r->bin_ratio[k][M_LEADR],
                100.0 * r->bin_err[k][M_BOX], r->bin_ratio[k][M_BOX],
                100.0 * r->bin_err[k][M_NAIVE], r->bin_ratio[k][M_NAIVE]);
    }
    fprintf(md, "\n");
    /* what the error is made of */
    for (k = 0; k < PIC_BINS; ++k) {
        if (k < SMALL_BINS) lit_s += r->bin_lit_u[k];
        else lit_l += r->bin_lit_u[k];
        n_noisy += r->bin_noisy[k];
    }
    box_s = bins_mean(r, &r->bin_err_u[0][M_BOX], M_COUNT, 0, SMALL_BINS, 0);
    box_l = bins_mean(r, &r->bin_err_u[0][M_BOX], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    in_s = bins_mean(r, &r->bin_err_in[0][M_BOX], M_COUNT, 0, SMALL_BINS, 0);
    in_l = bins_mean(r, &r->bin_err_in[0][M_BOX], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    tri_s = bins_mean(r, &r->bin_err_u[0][M_LEADR], M_COUNT, 0, SMALL_BINS, 0);
    tri_l = bins_mean(r, &r->bin_err_u[0][M_LEADR], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    trin_s = bins_mean(r, &r->bin_err_in[0][M_LEADR], M_COUNT, 0, SMALL_BINS, 0);
    trin_l = bins_mean(r, &r->bin_err_in[0][M_LEADR], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    oof_s = bins_mean(r, &r->bin_err_in[0][M_REF], M_COUNT, 0, SMALL_BINS, 0);
    oof_l = bins_mean(r, &r->bin_err_in[0][M_REF], M_COUNT, SMALL_BINS, PIC_BINS, 0);
    ndf_s = bins_mean(r, r->bin_ndf, 1, 0, SMALL_BINS, 0);
    ndf_l = bins_mean(r, r->bin_ndf, 1, SMALL_BINS, PIC_BINS, 0);
    noise_l = bins_mean(r, r->bin_noise, 1, 0, PIC_BINS, 1);
    if (strcmp(sc->name, "plane") != 0)
        fprintf(md, "**Where the error comes from (%s).** The same three effects as for the "
                    "plane. ",
                sc->name);
    else
        fprintf(md,
            "**Where the error comes from (%s).** Three effects, measured per pixel in the same "
            "run. (1) *Occlusion from outside the footprint.* A footprint narrower than the "
            "bumps (correlation length %.0f texels) is shadowed and masked mostly by bumps "
            "outside it: the brute force finds them by marching the whole height field; LEADR "
            "cannot, since all it knows is the footprint's own slope distribution. In LEADR's "
            "pipeline those resolved-scale shadows come from the displaced geometry itself and "
            "a shadow map (Dupuy et al. 2013, overview in sec. 1 and \"Shadowing\" in sec. 6); "
            "here the macrosurface is flat and nothing supplies them. An *in-box reference* "
            "marches the same texels with only the footprint box's own height field as "
            "occluder. (2) *Gaussian slopes.* Without any visibility, the NDF at the half "
            "vector of the shaded texels (the mean of their base lobes) differs from the "
            "Gaussian of the same texels' moments that LEADR uses (eqs. 8-10): a footprint "
            "holding few bumps has a lumpy slope histogram at the scale of the narrow base lobe "
            "(deviation %.2f against an RMS slope of %.2f), which no Gaussian follows; this "
            "falls as the footprint grows, down to the lumpiness of the %dx%d map itself. (3) "
            "The rest is masking and shadowing within the footprint (Smith's Lambda of the "
            "footprint's Gaussian, with V_o and V_i taken as uncorrelated, eq. 13) and, for the "
            "trilinear column, the mip filter's power-of-two boxes, which are not the pixel's "
            "box.\n\n",
            sc->name, p.corr_texels, BASE_SIGMA, p.rms_slope, m->surf.w, m->surf.h);
    if (lit_s > 0)
        fprintf(md,
                "Footprint sides under 16 texels (%d pixels lit in either reference): the two "
                "references differ by %.0f%% (mean relative difference); LEADR with the exact box "
                "moments is off by "
                "%.0f%% against the full reference and %.0f%% against the in-box one, so "
                "occlusion from outside the footprint makes %.0f%% of its error there (trilinear "
                "LEADR: %.0f%% and %.0f%%); the texels' NDF differs from its Gaussian by "
                "%.0f%%. ",
                lit_s, 100.0 * oof_s, 100.0 * box_s, 100.0 * in_s,
                box_s > 0.0 ? 100.0 * (box_s - in_s) / box_s : 0.0, 100.0 * tri_s, 100.0 * trin_s,
                100.0 * ndf_s);
    if (lit_l > 0)
        fprintf(md,
                "Sides of 16 texels and more (%d pixels lit in either): the references differ by "
                "%.0f%%; "
                "exact-box LEADR is off by %.0f%% (full) and %.0f%% (in-box), trilinear LEADR by "
                "%.0f%% and %.0f%%; NDF against its Gaussian: %.0f%%. ",
                lit_l, 100.0 * oof_l, 100.0 * box_l, 100.0 * in_l, 100.0 * tri_l,
                100.0 * trin_l, 100.0 * ndf_l);
    if (strcmp(sc->name, "plane") == 0)
        fprintf(md,
                "At large footprints the in-box reference stops being a target: near the "
                "horizon a ray 5 degrees above the plane crosses up to %.0f texels before it "
                "clears the highest bump (height range %.1f texels), so a box of any size cuts "
                "real masking by the surrounding surface, which is statistically the footprint's "
                "own and which Smith's Lambda does model; there the full reference is the one to "
                "match. ",
                (m->surf.hmax - m->surf.hmin) / m->surf.texel / tan(5.0 * pic_pi / 180.0),
                (m->surf.hmax - m->surf.hmin) / m->surf.texel);
    if (strcmp(sc->name, "plane") != 0 && lit_l > 0) {
        double lo = 1e30, hi = -1e30;
        int first = -1, last = -1;
        for (k = 0; k < PIC_BINS; ++k) {
            if (!r->bin_lit[k]) continue;
            if (r->bin_ratio[k][M_BOX] < lo) lo = r->bin_ratio[k][M_BOX];
            if (r->bin_ratio[k][M_BOX] > hi) hi = r->bin_ratio[k][M_BOX];
            if (first < 0) first = k;
            last = k;
        }
        fprintf(md,
                "So in its domain LEADR is much closer on average than pixel by pixel: per row, "
                "the exact-box LEADR's sum over the pixels is %.2f to %.2f times the "
                "reference's, while single pixels are off by about as much as the footprint's "
                "slope histogram is off its Gaussian. That part, (2), shrinks as a footprint "
                "covers more bumps (NDF error %.0f%% in the first row, %.0f%% in the last); in "
                "the last row, at the limb where the view is grazing, the exact-box error is "
                "still %.0f%%: there (3) dominates. ",
                lo, hi, pct(r->bin_ndf[first]), pct(r->bin_ndf[last]),
                pct(r->bin_err[last][M_BOX]));
    }
    fprintf(md,
            "The reference's own sampling deviation on subsampled footprints (half the "
            "difference of two interleaved halves of the samples, relative, rms) is %.1f%% over "
            "its %d lit subsampled pixels.\n\n",
            100.0 * noise_l, n_noisy);
    fprintf(md, "Per row, over the pixels lit in either reference; every difference is divided "
                "by the larger of the two references (or the floor), so the errors against the "
                "full and the in-box reference differ only in what they subtract. The share is 1 "
                "- (exact-box error against the in-box reference) / (against the full one), "
                "meaningful where the footprint is smaller than a ray's path out of the bumps "
                "(see above):\n\n"
                "| %s: footprint side (texels) | lit in either | full reference vs in-box: "
                "mean difference; sum(in-box) / sum(full), all pixels | LEADR exact box vs "
                "in-box | LEADR "
                "(trilinear) vs in-box | share of the exact-box error due to out-of-footprint "
                "occlusion | texels' NDF at h vs its Gaussian | reference sampling deviation "
                "(rms, subsampled lit pixels) |\n"
                "|---|---|---|---|---|---|---|---|\n",
            sc->name);
    for (k = 0; k < PIC_BINS; ++k) {
        if (!r->bin_lit_u[k]) continue;
        print_bin_label(md, k);
        fprintf(
            md, " %d | %.0f%%, %.2f | %.0f%% | %.0f%% | %.0f%% | %.0f%% |", r->bin_lit_u[k],
            pct(r->bin_err_in[k][M_REF]), r->bin_ratio[k][M_REF], pct(r->bin_err_in[k][M_BOX]),
            pct(r->bin_err_in[k][M_LEADR]),
            r->bin_err_u[k][M_BOX] > 0.0
                ? pct((r->bin_err_u[k][M_BOX] - r->bin_err_in[k][M_BOX]) / r->bin_err_u[k][M_BOX])
                : 0.0,
            pct(r->bin_ndf[k]));
        if (r->bin_noisy[k])
            fprintf(md, " %.1f%% (%d px) |\n", 100.0 * r->bin_noise[k], r->bin_noisy[k]);
        else fprintf(md, " 0 (shaded fully) |\n");
    }
    fprintf(md, "\n");
    printf("%s: %dx%d, surface %d, lit %d, footprint %.2f..%.0f (median %.1f), subsampled %d\n",
           sc->name, sc->w, sc->h, r->n_surface, r->n_lit, r->fp_min, r->fp_max, r->fp_med,
           r->n_subsampled);
    printf("  reference %.2f s (%.1f us/pixel), in-box variant +%.2f s\n", r->seconds[M_REF],
           us_ref, r->seconds_inbox);
    printf("  in-box reference vs reference: mean %.1f%%\n", 100.0 * r->err_in[M_REF].mean);
    for (k = 1; k < M_COUNT; ++k)
        printf("  %-26s mean %6.1f%%  p95 %7.1f%%  vs in-box %6.1f%%  zero %5d  %4.0f ns/pixel  "
               "speed-up %.0f\n",
               method_label[k], 100.0 * r->err[k].mean, 100.0 * r->err[k].p95,
               100.0 * r->err_in[k].mean, r->n_zero[k], 1e9 * r->seconds[k] / r->n_surface,
               r->seconds[M_REF] / r->seconds[k]);
    for (k = 0; k < PIC_BINS; ++k)
        if (r->bin_surface[k])
            printf("  footprint >= %3d: %5d px, lit %5d: leadr %5.1f%% (%.2f) box %5.1f%% (%.2f) "
                   "naive %6.1f%% (%.2f) | in-box: ref %5.1f%% (%.2f) box %5.1f%% leadr %5.1f%% "
                   "noise %4.1f%% (%d) ndf %5.1f%%\n",
                   k ? 1 << k : 0, r->bin_surface[k], r->bin_lit[k],
                   100.0 * r->bin_err[k][M_LEADR], r->bin_ratio[k][M_LEADR],
                   100.0 * r->bin_err[k][M_BOX], r->bin_ratio[k][M_BOX],
                   100.0 * r->bin_err[k][M_NAIVE], r->bin_ratio[k][M_NAIVE],
                   100.0 * r->bin_err_in[k][M_REF], r->bin_ratio[k][M_REF],
                   100.0 * r->bin_err_in[k][M_BOX], 100.0 * r->bin_err_in[k][M_LEADR],
                   100.0 * r->bin_noise[k], r->bin_noisy[k], 100.0 * r->bin_ndf[k]);
}

static void scene_make(int which, pic_scene *sc, pic_maps *m, int w, int h)
{
    if (which == 0) scene_plane(sc, m, w, h);
    else scene_sphere(sc, m, w, h);
}

/* Image sizes: full and BENCH_QUICK (half), per scene. */
static const int scene_size[2][2] = {{400, 250}, {300, 300}};

/* Pipeline self-check (a check that can fail): on the same scenes with the map flattened to an
   RMS slope of FLAT_RMS_SLOPE, every texel is the same narrow lobe and nothing is masked, so the
   reference, LEADR and naive must agree to the library's rounding. Small images; returns the
   largest relative error over the lit pixels of both scenes and all three methods. */
static double self_check(void)
{
    double worst = 0.0;
    int s, k, i;
    for (s = 0; s < 2; ++s) {
        pic_maps m;
        pic_scene sc;
        pic_result r;
        if (maps_make(&m, 1) != 0) return 1e30;
        scene_make(s, &sc, &m, scene_size[s][0] / 8, scene_size[s][1] / 8);
        render_scene(&m, &sc, &r);
        for (k = 0; k < M_COUNT; ++k) /* k = M_REF: the in-box reference */
            for (i = 0; i < sc.w * sc.h; ++i) {
                double ref = r.val[M_REF][i], e;
                if (!sc.px[i].hit || !(ref >= r.floor)) continue;
                e = fabs((k == M_REF ? r.inbox[i] : r.val[k][i]) - ref) / ref;
                if (!(e <= worst)) worst = e; /* NaN counts as the worst */
            }
        result_free(&r);
        free(sc.px);
        maps_free(&m);
    }
    return worst;
}

int main(int argc, char **argv)
{
    const char *outdir = argc > 1 ? argv[1] : "bench/out";
    const char *q = getenv("BENCH_QUICK");
    int quick = q && *q && strcmp(q, "0") != 0 && strcmp(q, "no") != 0 && strcmp(q, "NO") != 0;
    int div = quick ? 2 : 1, s;
    /* float library: the flat lobe's peak D ~ 1/(2 pi 0.01) and the Smith terms in float.
       Double: the map keeps slopes of ~FLAT_RMS_SLOPE, and where two methods' footprints
       differ (trilinear against box) the lobe's centre moves by that much, a relative change
       of up to |s_h - s| FLAT_RMS_SLOPE / BASE_SIGMA^2 ~ 3e-7 */
    double check_bound = sizeof(pf_real) == sizeof(float) ? 1e-4 : 1e-6, check;
    char path[1024];
    FILE *md;
    double t_start = now_seconds(), t_png = 0.0;
    long png_bytes[2] = {0, 0};
    check = self_check();
    printf("pictures: self-check on a flat map, max relative error %.2e (bound %.0e)\n", check,
           check_bound);
    if (!(check <= check_bound)) {
        fprintf(stderr, "pictures: FAILED self-check: flat map error %.3e > %.0e\n", check,
                check_bound);
        return 1;
    }
    snprintf(path, sizeof path, "%s/pictures.md", outdir);
    md = fopen(path, "w");
    if (!md) {
        fprintf(stderr, "pictures: cannot write %s (does the directory exist?)\n", path);
        return 1;
    }
    fprintf(md, "## Pictures: brute force against the filtered formulas\n\n"
                "Each picture: the brute-force reference (every texel of the pixel's footprint "
                "shaded with its own micro-normal, a narrow Beckmann base lobe, and masking and "
                "shadowing marched through the height field: `tests/pf_microsurface.h`), LEADR "
                "from the trilinearly sampled moment pyramid (`pf_slope_moments_sample`, "
                "`pf_leadr_specular`), and the naive mip-mapped normal (average normals, "
                "renormalized, base lobe only), with their relative-error maps. "
                "\"LEADR, exact box moments\" (not drawn) feeds the same formula with the exact "
                "moments of the reference's own box: its error is the model's, which the last "
                "table of each scene splits into occlusion from outside the footprint, the "
                "Gaussian-slope assumption and the rest; the difference to the trilinear error is "
                "the mip filter's footprint. Relative error per pixel: "
                "|method - reference| / max(reference, %.0f%% of the reference's 99th "
                "percentile), averaged over the lit pixels (reference above that floor). The "
                "footprint is isotropic (the larger of the two ray-differential axes, as a GPU "
                "picks its mip level) and capped at the map size.\n\n",
            100.0 * LIT_FRACTION);
    for (s = 0; s < 2; ++s) {
        pic_maps m;
        pic_scene sc;
        pic_result r;
        char png[64];
        if (maps_make(&m, 0) != 0) {
            fprintf(stderr, "pictures: out of memory\n");
            return 1;
        }
        scene_make(s, &sc, &m, scene_size[s][0] / div, scene_size[s][1] / div);
        if (quick && sc.ref_max > REF_MAX_SAMPLES) sc.ref_max = REF_MAX_SAMPLES;
        render_scene(&m, &sc, &r);
        snprintf(png, sizeof png, "pic_%s.png", sc.name);
        snprintf(path, sizeof path, "%s/%s", outdir, png);
        {
            double t0 = now_seconds();
            if (write_picture(&sc, &r, path, &png_bytes[s]) != 0) {
                fprintf(stderr, "pictures: cannot write %s\n", path);
                return 1;
            }
            t_png += now_seconds() - t0;
            printf("  %s: %ld bytes, written in %.0f ms\n", path, png_bytes[s],
                   1e3 * (now_seconds() - t0));
        }
        if (s == 0)
            fprintf(md, "Moment pyramids (five slope moments, average normals) of the %dx%d "
                        "map built in %.1f ms, a one-off per map, not counted below.\n\n",
                    m.surf.w, m.surf.h, 1e3 * m.t_pyramid);
        describe_scene(md, &sc, &r, png, &m);
        result_free(&r);
        free(sc.px);
        maps_free(&m);
    }
    fprintf(md, "Self-checks in the same run: with the map flattened (RMS slope %.0e) the three "
                "methods and the in-box reference match the reference to %.1e (largest relative "
                "error over lit pixels; bound %.0e); the in-box reference marches with "
                "`pfm_visible_box` (tested in tests/test_microsurface.c). Library in %s; reference in double; times on one core%s. "
                "PNG files (row filters and deflate written here, no zlib): %ld and %ld bytes, "
                "%.0f ms to encode both; total run %.0f s.\n\n",
            FLAT_RMS_SLOPE, check, check_bound,
            sizeof(pf_real) == sizeof(float) ? "float" : "double",
            quick ? " (BENCH_QUICK: half-size images)" : "", png_bytes[0], png_bytes[1],
            1e3 * t_png, now_seconds() - t_start);
    fclose(md);
    printf("pictures: done in %.1f s\n", now_seconds() - t_start);
    return 0;
}

/* pf_encode.h - storage encodings of the surface moments: slope moments (LEAN/LEADR) in 16-bit
   UNORM or half float and 8-bit UNORM, vMF lobes (octahedral direction, log sharpness, weight),
   and any other moment map (HDF moments of pf_horizon.h, average normals, height moments) in
   per-channel scaled UNORM; the shader-side decoders and the CPU encoders over caller buffers.

   WHAT IS STORED. A texture sampler returns a UNORM channel as s = code / (2^bits - 1) in
   [0, 1] and a half channel as its value; the decoders here are arithmetic on those sampled
   values (no bit unpacking in the shader):
     scaled UNORM    v = offset + scale * s, offset and scale per channel and per MAP (one pair
                     for the whole mip pyramid; see "PER MAP" below). Olano & Baker 2010 sec. 4
                     store LEAN's B and M scaled into 16-bit channels the same way.
     slope moments   the five channels are moments about a reference slope r = (rx, ry) (the
                     map's mean slope by default), one per map:
                       E[x - rx], E[y - ry], E[(x - rx)^2], E[(y - ry)^2], E[(x - rx)(y - ry)]
                     each in scaled UNORM (16 or 8 bits) or in half (offset 0, scale 1). The
                     decoder returns the raw moments:
                       E[x] = rx + dx,  E[x^2] = cxx + rx (2 dx + rx),
                       E[xy] = cxy + rx dy + ry dx + rx ry                               (1)
                     (dx = E[x - rx], cxx = E[(x - rx)^2], ...), which every evaluator takes.
                     Centring matters when a map's slopes share a large mean (a tilted or
                     sheared map): E[x^2] = var + mean^2 then holds mostly mean^2, and a fixed
                     number of bits of it leaves little for var (the cancellation of
                     test_half_storage_variance in tests/test_moments.c); about r the channel
                     holds var + (mean - r)^2 instead.
     vMF lobes       per lobe (mu.x, mu.y, kappa, amp) -> 4 UNORM channels: the axis on the
                     upper hemisphere's octahedral map (u, v) = (px + py, px - py),
                     p = (mu.x, mu.y) / (|mu.x| + |mu.y| + mu.z) (Cigolle et al. 2014 sec. 3,
                     the hemisphere variant: the square rotated by 45 degrees fills [-1, 1]^2);
                     kappa as log kappa over the map's [log kappa_min, log kappa_max]
                     (sharpness errors relative, as kappa spans 1e-4 .. 1e5); amp scaled by the
                     map's largest amplitude (0 stays 0: padding lobes).
     half float      IEEE binary16, round to nearest even (pf_half_from_real); any stored
                     value is what the sampler returns, so the shader decodes nothing.

   PER MAP, NOT PER LEVEL. Every level of a box-filtered pyramid holds weighted means of the
   finest level's texels, so its values lie within the finest level's range: one range per map
   costs no range at the coarse levels that a per-level range would not also cost at level 0.
   And only a per-map (offset, scale, r) keeps the decode one affine map for the whole
   pyramid, so hardware trilinear and anisotropic filtering, which blend texels of two levels
   before the shader sees them, still filter the moments. A per-level range would give coarse
   levels finer steps, but trilinear filtering would then have to be two bilinear fetches
   decoded apart and blended in the shader.

   LINEARITY (does decode(lerp(encode a, encode b, t)) equal lerp(a, b, t), so that bilinear,
   trilinear and anisotropic filtering of the stored texels filters the moments?)
     scaled UNORM, half    yes, up to the quantization of a and b: the decode is affine with
                           constants per map (the sampler filters s, or the half values, in at
                           least 16-bit precision; tests/test_encode.c, test_linearity_*).
     slope moments about r yes, with r per map: (1) is affine in the stored channels for a
                           fixed r. A reference per TEXEL (its own mean, say, to store the
                           variance) is not: filtering two texels with references ra, rb gives
                           E[(x - r)^2] for no single r, and the decode with the filtered
                           reference misses t (1 - t) (ra - rb) (ra - rb + da - db)-type terms
                           (test_slope_per_texel_reference_not_linear measures it). It is linear
                           exactly where the reference is constant over the filter's support.
     vMF lobes             no: the octahedral map and the log are not affine, and a filtered
                           lobe is not the mixture of the two lobes anyway. Lobe pyramids are
                           fetched texel by texel (texelFetch of the level: bench/microsurface.c
                           does so), never filtered. The amplitude channel alone is linear.

   USAGE (shader: 5 channels of an RG16_UNORM + RGBA16_UNORM pair sampled trilinearly)
     pf_slope_moments s = pf_slope_moments_make(t0.x, t0.y, t1.x, t1.y, t1.z);
     pf_slope_moments m = pf_slope_moments_decode(s, enc);      -- enc: a uniform, per map
     pf_slope_stats st = pf_slope_moments_stats(m, base_var);   -- as with float storage
   CPU: pf_slope_encoding enc; unsigned short q[5 * n];
     if (pf_slope_encoding_find(pyr, n, 1, &enc) == PF_OK &&
         pf_slope_moments_encode(pyr, n, &enc, PF_ENCODE_UNORM16, q) == PF_OK) upload(q, enc);

   FUNCTIONS (shader subset)
     pf_unorm_decode(s, offset, scale)          offset + scale s
     pf_slope_encoding (struct), pf_slope_moments_decode(stored, enc)        (1)
     pf_oct_hemi_decode(su, sv)                 unit vector of the upper hemisphere
     pf_vmf_encoding (struct), pf_vmf_lobe_decode(su, sv, sk, sa, enc)
   FUNCTIONS (CPU only, PF_CPU_DEF; compiled out under PF_GLSL)
     pf_half_from_real, pf_real_from_half       binary16, round to nearest even
     pf_oct_hemi_encode(dir, &u, &v)             the octahedral coordinates in [-1, 1]
     pf_encode_ranges(texels, n, channels, offset, scale)        per-channel range of a map
     pf_encode_channels(texels, n, channels, offset, scale, format, out)
     pf_slope_encoding_find(texels, n, center, &enc), pf_slope_moments_encode(.., format, out)
     pf_vmf_encoding_find(texels, nlobes, &enc), pf_vmf_lobes_encode(.., format, out)
     pf_encode_bytes(format)                    bytes per channel
   Formats: PF_ENCODE_UNORM16 (out: unsigned short *), PF_ENCODE_UNORM8 (unsigned char *),
   PF_ENCODE_HALF (unsigned short *, the binary16 bits; not offered for vMF lobes).

   CONVENTIONS
     Encoders check everything before writing anything and return PF_OK, or PF_ERR_ARG (a NULL
     pointer; n below 1; channels below 1; an unknown format; a NaN or infinite input; an
     offset, scale or reference that is not finite, a negative scale; a range whose width
     overflows; a value of magnitude 65520 or more for half, which would round to infinity), or
     PF_ERR_SIZE (n times the channel count above PF_MAX_REALS). Finite values outside a given
     range are clamped to it (a map's coarse levels lie inside its finest level's range, so
     pf_encode_ranges over any level set that contains the finest is exact). A zero-width
     range (a constant channel) stores 0 and decodes to the constant.
     Decoders return finite values for every sampled value in [0, 1] (UNORM) and every finite
     half value, given a finite encoding; pf_real_from_half returns a finite value for every
     bit pattern (+-inf -> +-65504, NaN -> 0).

   ACCURACY AND COST (tests/test_encode.c; the error of every method of bench/microsurface.c
   with its pyramids stored in each format: bench/out/microsurface_storage.csv, docs/encode.md)
     Round trip of a scaled UNORM channel: |v - decode(encode v)| <= scale / (2 (2^bits - 1))
     (plus a few ulps of pf_real); half: relative 2^-11 (normal range). Slope moments about the
     mean in UNORM16 keep the variance of tilted texels (mean slope 1, deviation 0.01) within
     its quantization bound (2e-5 of it in double, 3e-3 in float), where raw half moments lose
     16 times it (test_slope_round_trip_variance). vMF axes within 2.4 / (2^bits - 1) rad,
     log kappa within half a step of its span. In bench/microsurface.c (every method, kind,
     footprint; docs/encode.md's table): UNORM16 pyramids keep every method's error within
     1.1x of its float32 error wherever that is at least 1%; half does not for the slope and
     HDF moments; 8 bits serve only first moments of colour maps. The decoders are one
     multiply-add per channel, plus (1) (5 multiply-adds) or one exp and one normalize (vMF).

   SOURCES
     Olano & Baker 2010, "LEAN mapping", sec. 4 (16-bit storage with a scale); Dupuy et al.
     2013 (LEADR) eq. 9; Cigolle et al. 2014, "A survey of efficient representations for
     independent unit vectors" (JCGT 3(2)), sec. 3 (octahedral map, hemisphere variant);
     IEEE 754-2008 binary16; Khronos Data Format 1.3 sec. 13.1 (UNORM: s = code / (2^b - 1)). */
#ifndef PF_ENCODE_H
#define PF_ENCODE_H

#ifndef PF_GLSL
#  include "pf_core.h"
#  include "pf_moments.h"
#  include "pf_vmf.h"
#endif

/* ---------------------------------------------------------------- scaled UNORM */
/* offset + scale s: the value of a channel stored as s in [0, 1] (the sampler's UNORM value,
   filtered or not). Affine, so it commutes with every filter of s. */
PF_DEF pf_real pf_unorm_decode(pf_real s, pf_real offset, pf_real scale) { return offset + scale * s; }

/* ---------------------------------------------------------------- slope moments */
/* One map's encoding of the five slope moments: the reference slope (ref_x, ref_y) and per
   channel the offset and scale of (1)'s centred channels (half storage: offsets 0, scales 1). */
PF_STRUCT_BEGIN(pf_slope_encoding)
    pf_real ref_x;
    pf_real ref_y;
    pf_real off_x;
    pf_real off_y;
    pf_real off_xx;
    pf_real off_yy;
    pf_real off_xy;
    pf_real sc_x;
    pf_real sc_y;
    pf_real sc_xx;
    pf_real sc_yy;
    pf_real sc_xy;
PF_STRUCT_END(pf_slope_encoding)

/* The raw moments (E[x], E[y], E[x^2], E[y^2], E[xy]) from the five sampled channels (stored
   in the struct's members in that order) by (1): dx = off_x + sc_x s.ex, ..., then
   E[x] = rx + dx, E[x^2] = cxx + rx (2 dx + rx), E[xy] = cxy + rx dy + ry dx + rx ry.
   Affine in the sampled channels for a fixed encoding (linear under filtering). */
PF_DEF pf_slope_moments pf_slope_moments_decode(pf_slope_moments s, pf_slope_encoding e)
{
    pf_real dx = pf_unorm_decode(s.ex, e.off_x, e.sc_x);
    pf_real dy = pf_unorm_decode(s.ey, e.off_y, e.sc_y);
    pf_real cxx = pf_unorm_decode(s.exx, e.off_xx, e.sc_xx);
    pf_real cyy = pf_unorm_decode(s.eyy, e.off_yy, e.sc_yy);
    pf_real cxy = pf_unorm_decode(s.exy, e.off_xy, e.sc_xy);
    return pf_slope_moments_make(e.ref_x + dx, e.ref_y + dy, cxx + e.ref_x * (PF_R(2.0) * dx + e.ref_x),
                                 cyy + e.ref_y * (PF_R(2.0) * dy + e.ref_y),
                                 cxy + e.ref_x * dy + e.ref_y * dx + e.ref_x * e.ref_y);
}

/* ---------------------------------------------------------------- vMF lobes */
/* Unit vector of the upper hemisphere from its octahedral coordinates stored as UNORM su, sv
   (u = 2 su - 1, v = 2 sv - 1): p = ((u + v)/2, (u - v)/2), z = 1 - |px| - |py| >= 0,
   normalized (Cigolle et al. 2014 sec. 3, hemisphere variant). Values outside [0, 1] are
   clamped; NaN gives a finite vector (pf_vec3_normalize). */
PF_DEF pf_vec3 pf_oct_hemi_decode(pf_real su, pf_real sv)
{
    pf_real u = PF_R(2.0) * pf_saturate(su) - PF_R(1.0), v = PF_R(2.0) * pf_saturate(sv) - PF_R(1.0);
    pf_real px = PF_R(0.5) * (u + v), py = PF_R(0.5) * (u - v);
    return pf_vec3_normalize(pf_vec3_make(px, py, pf_max(PF_R(1.0) - PF_FABS(px) - PF_FABS(py), PF_R(0.0))));
}

/* One map's encoding of vMF lobes: kappa = exp(log_kappa_lo + log_kappa_span sk), amp =
   amp_scale sa. */
PF_STRUCT_BEGIN(pf_vmf_encoding)
    pf_real log_kappa_lo;
    pf_real log_kappa_span;
    pf_real amp_scale;
PF_STRUCT_END(pf_vmf_encoding)

/* The lobe of one stored texel (su, sv: octahedral axis; sk: log kappa; sa: amplitude; all
   UNORM in [0, 1], clamped). kappa is then clamped by pf_vmf_lobe_make. */
PF_DEF pf_vmf_lobe pf_vmf_lobe_decode(pf_real su, pf_real sv, pf_real sk, pf_real sa, pf_vmf_encoding e)
{
    pf_vec3 mu = pf_oct_hemi_decode(su, sv);
    pf_real lk = e.log_kappa_lo + e.log_kappa_span * pf_saturate(sk);
    return pf_vmf_lobe_make(e.amp_scale * pf_saturate(sa), mu.x, mu.y,
                            PF_EXP(pf_min(lk, PF_R(11.6))));  /* log 1e5 = 11.51: no overflow */
}

/* ================================================================ CPU only: encoders */
#ifndef PF_GLSL

#define PF_ENCODE_UNORM16 0
#define PF_ENCODE_UNORM8 1
#define PF_ENCODE_HALF 2

/* Bytes per stored channel of a format (0 for an unknown one). */
PF_CPU_DEF int pf_encode_bytes(int format)
{
    return format == PF_ENCODE_UNORM16 || format == PF_ENCODE_HALF ? 2 : (format == PF_ENCODE_UNORM8 ? 1 : 0);
}

/* 1 when x is finite (not NaN, not +-inf). */
PF_CPU_DEF int pfi_enc_finite(pf_real x) { return x == x && x <= PF_REAL_MAX && x >= -PF_REAL_MAX; }

/* Octahedral coordinates (u, v) in [-1, 1] of a direction of the upper hemisphere (d.z < 0 is
   taken as 0; the zero vector and NaN give (0, 0), the pole). Inverse of pf_oct_hemi_decode
   with su = (u + 1)/2, sv = (v + 1)/2. */
PF_CPU_DEF void pf_oct_hemi_encode(pf_vec3 d, pf_real *u, pf_real *v)
{
    pf_real ax = PF_FABS(d.x), ay = PF_FABS(d.y), z = pf_max(d.z, PF_R(0.0)), n = ax + ay + z, px, py;
    if (!(n > PF_R(0.0)) || !pfi_enc_finite(n)) {
        *u = PF_R(0.0);
        *v = PF_R(0.0);
        return;
    }
    px = d.x / n;
    py = d.y / n;
    *u = pf_clamp(px + py, PF_R(-1.0), PF_R(1.0));
    *v = pf_clamp(px - py, PF_R(-1.0), PF_R(1.0));
}

/* The code of value x in the range (offset, scale) at `levels` = 2^bits - 1:
   round((x - offset) / scale * levels), clamped to [0, levels]; scale 0 gives 0. */
PF_CPU_DEF long pfi_enc_code(pf_real x, pf_real offset, pf_real scale, long levels)
{
    pf_real t;
    if (!(scale > PF_R(0.0))) return 0;
    t = (x - offset) / scale; /* x - offset may overflow to +-inf: clamped below */
    t = t == t ? t : PF_R(0.0);
    return pf_round_even(pf_clamp(t, PF_R(0.0), PF_R(1.0)) * (pf_real)levels);
}

/* Store x at index i of out in format f (checked by the caller). */
PF_CPU_DEF void pfi_enc_store(void *out, long long i, int f, pf_real x, pf_real offset, pf_real scale)
{
    if (f == PF_ENCODE_UNORM16) ((unsigned short *)out)[i] = (unsigned short)pfi_enc_code(x, offset, scale, 65535L);
    else if (f == PF_ENCODE_UNORM8) ((unsigned char *)out)[i] = (unsigned char)pfi_enc_code(x, offset, scale, 255L);
    else ((unsigned short *)out)[i] = pf_half_from_real(x);
}

/* PF_OK when (offset, scale) is a usable range: both finite, scale >= 0. */
PF_CPU_DEF int pfi_enc_range_ok(pf_real offset, pf_real scale)
{
    return pfi_enc_finite(offset) && pfi_enc_finite(scale) && scale >= PF_R(0.0) ? PF_OK : PF_ERR_ARG;
}

/* The argument checks shared by every encoder: buffers, count, channels, size, format. */
PF_CPU_DEF int pfi_enc_check(const void *in, long long n, int channels, int format, const void *out)
{
    if (!in || !out || n < 1 || channels < 1 || pf_encode_bytes(format) == 0) return PF_ERR_ARG;
    if (pf_size_mul(n, channels) < 0) return PF_ERR_SIZE;
    return PF_OK;
}

/* Per-channel range of n texels of `channels` pf_reals: offset[c] = the channel's minimum,
   scale[c] = maximum - minimum. PF_ERR_ARG (nothing written) for a NULL pointer, n or channels
   below 1, a NaN or infinite value, or a width that overflows; PF_ERR_SIZE for n channels above
   PF_MAX_REALS. */
PF_CPU_DEF int pf_encode_ranges(const pf_real *texels, long long n, int channels, pf_real *offset, pf_real *scale)
{
    long long i;
    int c, big = 0;
    int rc = pfi_enc_check(texels, n, channels, PF_ENCODE_UNORM16, offset);
    if (rc != PF_OK) return rc;
    if (!scale) return PF_ERR_ARG;
    for (i = 0; i < n * channels; ++i) {
        if (!pfi_enc_finite(texels[i])) return PF_ERR_ARG;
        big |= PF_FABS(texels[i]) > PF_R(0.5) * PF_REAL_MAX;
    }
    if (!big) { /* no width can overflow: one pass in memory order, minima and maxima in place */
        for (c = 0; c < channels; ++c) offset[c] = scale[c] = texels[c];
        for (i = 1; i < n; ++i)
            for (c = 0; c < channels; ++c) {
                pf_real x = texels[i * channels + c];
                offset[c] = x < offset[c] ? x : offset[c];
                scale[c] = x > scale[c] ? x : scale[c];
            }
        for (c = 0; c < channels; ++c) scale[c] -= offset[c];
        return PF_OK;
    }
    for (c = 0; c < channels; ++c) { /* values beyond PF_REAL_MAX / 2: check every width first */
        pf_real lo = texels[c], hi = texels[c];
        for (i = 1; i < n; ++i) {
            pf_real x = texels[i * channels + c];
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        if (!pfi_enc_finite(hi - lo)) return PF_ERR_ARG;
    }
    for (c = 0; c < channels; ++c) {
        pf_real lo = texels[c], hi = texels[c];
        for (i = 1; i < n; ++i) {
            pf_real x = texels[i * channels + c];
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        offset[c] = lo;
        scale[c] = hi - lo;
    }
    return PF_OK;
}

/* Encode n texels of `channels` pf_reals into out (n channels codes) in `format`: UNORM codes
   round((x - offset[c]) / scale[c] (2^bits - 1)) clamped, or binary16 bits (offset and scale
   unused, may be NULL). Errors as in CONVENTIONS; nothing written on an error. */
PF_CPU_DEF int pf_encode_channels(const pf_real *texels, long long n, int channels, const pf_real *offset,
                                  const pf_real *scale, int format, void *out)
{
    long long i;
    int c;
    int rc = pfi_enc_check(texels, n, channels, format, out);
    if (rc != PF_OK) return rc;
    if (format != PF_ENCODE_HALF) {
        if (!offset || !scale) return PF_ERR_ARG;
        for (c = 0; c < channels; ++c)
            if (pfi_enc_range_ok(offset[c], scale[c]) != PF_OK) return PF_ERR_ARG;
    }
    for (i = 0; i < n * channels; ++i)
        if (!pfi_enc_finite(texels[i]) || (format == PF_ENCODE_HALF && !(PF_FABS(texels[i]) < PF_R(65520.0))))
            return PF_ERR_ARG;
    for (i = 0; i < n; ++i)
        for (c = 0; c < channels; ++c)
            pfi_enc_store(out, i * channels + c, format, texels[i * channels + c],
                          format == PF_ENCODE_HALF ? PF_R(0.0) : offset[c], format == PF_ENCODE_HALF ? PF_R(1.0) : scale[c]);
    return PF_OK;
}

/* Channel k (0..4) of (1)'s centred moments of slope texel t about (rx, ry). */
PF_CPU_DEF pf_real pfi_enc_slope_channel(const pf_real *t, int k, pf_real rx, pf_real ry)
{
    switch (k) {
    case 0: return t[0] - rx;
    case 1: return t[1] - ry;
    case 2: return t[2] - rx * (PF_R(2.0) * t[0] - rx); /* E[x^2] - 2 rx E[x] + rx^2 */
    case 3: return t[3] - ry * (PF_R(2.0) * t[1] - ry);
    default: return t[4] - rx * t[1] - ry * t[0] + rx * ry;
    }
}

/* The encoding of n slope-moment texels (5 pf_reals each, pf_moments.h's order; a whole
   pyramid or its finest level): reference = the mean of E[x], E[y] over the texels (center 1)
   or (0, 0) (center 0: the raw moments, Olano & Baker's scaled form), and the range of each
   centred channel. Errors as pf_encode_ranges (a NaN or infinite moment, a centred channel
   that overflows); *enc untouched on an error. */
PF_CPU_DEF int pf_slope_encoding_find(const pf_real *texels, long long n, int center, pf_slope_encoding *enc)
{
    pf_real rx = PF_R(0.0), ry = PF_R(0.0), lo[5] = { 0, 0, 0, 0, 0 }, hi[5] = { 0, 0, 0, 0, 0 };
    long long i;
    int k;
    int rc = pfi_enc_check(texels, n, 5, PF_ENCODE_UNORM16, enc);
    if (rc != PF_OK) return rc;
    for (i = 0; i < 5 * n; ++i)
        if (!pfi_enc_finite(texels[i])) return PF_ERR_ARG;
    if (center) { /* running mean: no overflow for any finite input */
        for (i = 0; i < n; ++i) {
            rx += (texels[5 * i] - rx) / (pf_real)(i + 1);
            ry += (texels[5 * i + 1] - ry) / (pf_real)(i + 1);
        }
    }
    for (i = 0; i < n; ++i)
        for (k = 0; k < 5; ++k) {
            pf_real x = pfi_enc_slope_channel(texels + 5 * i, k, rx, ry);
            if (!pfi_enc_finite(x)) return PF_ERR_ARG;
            lo[k] = (i == 0 || x < lo[k]) ? x : lo[k];
            hi[k] = (i == 0 || x > hi[k]) ? x : hi[k];
        }
    for (k = 0; k < 5; ++k)
        if (!pfi_enc_finite(hi[k] - lo[k])) return PF_ERR_ARG;
    enc->ref_x = rx;
    enc->ref_y = ry;
    enc->off_x = lo[0];
    enc->off_y = lo[1];
    enc->off_xx = lo[2];
    enc->off_yy = lo[3];
    enc->off_xy = lo[4];
    enc->sc_x = hi[0] - lo[0];
    enc->sc_y = hi[1] - lo[1];
    enc->sc_xx = hi[2] - lo[2];
    enc->sc_yy = hi[3] - lo[3];
    enc->sc_xy = hi[4] - lo[4];
    return PF_OK;
}

/* Encode n slope-moment texels into 5 n codes of `format`, the centred channels of enc's
   reference. PF_ENCODE_HALF stores the centred channels themselves: decode them with enc's
   reference and offsets 0, scales 1 (set them so in the uniform). Errors as in CONVENTIONS
   (also an encoding with a non-finite member or a negative scale); nothing written on an
   error. */
PF_CPU_DEF int pf_slope_moments_encode(const pf_real *texels, long long n, const pf_slope_encoding *enc, int format,
                                       void *out)
{
    pf_real off[5], sc[5];
    long long i;
    int k;
    int rc = pfi_enc_check(texels, n, 5, format, out);
    if (rc != PF_OK) return rc;
    if (!enc || !pfi_enc_finite(enc->ref_x) || !pfi_enc_finite(enc->ref_y)) return PF_ERR_ARG;
    off[0] = enc->off_x; off[1] = enc->off_y; off[2] = enc->off_xx; off[3] = enc->off_yy; off[4] = enc->off_xy;
    sc[0] = enc->sc_x; sc[1] = enc->sc_y; sc[2] = enc->sc_xx; sc[3] = enc->sc_yy; sc[4] = enc->sc_xy;
    for (k = 0; k < 5; ++k)
        if (pfi_enc_range_ok(off[k], sc[k]) != PF_OK) return PF_ERR_ARG;
    for (i = 0; i < 5 * n; ++i)
        if (!pfi_enc_finite(texels[i])) return PF_ERR_ARG;
    for (i = 0; i < n; ++i)
        for (k = 0; k < 5; ++k) {
            pf_real x = pfi_enc_slope_channel(texels + 5 * i, k, enc->ref_x, enc->ref_y);
            if (!pfi_enc_finite(x) || (format == PF_ENCODE_HALF && !(PF_FABS(x) < PF_R(65520.0)))) return PF_ERR_ARG;
        }
    for (i = 0; i < n; ++i)
        for (k = 0; k < 5; ++k)
            pfi_enc_store(out, 5 * i + k, format, pfi_enc_slope_channel(texels + 5 * i, k, enc->ref_x, enc->ref_y),
                          format == PF_ENCODE_HALF ? PF_R(0.0) : off[k], format == PF_ENCODE_HALF ? PF_R(1.0) : sc[k]);
    return PF_OK;
}

/* The encoding of nlobes vMF lobe texels (4 pf_reals each: mu.x, mu.y, kappa, amp, as
   pf_vmf.h packs them): log kappa over the lobes' [min, max] (kappa clamped by
   pf_vmf_kappa_clamp first) and the largest amplitude (amplitudes below 0 read as 0).
   PF_ERR_ARG for a NULL pointer, nlobes below 1, a NaN or infinite value; *enc untouched then. */
PF_CPU_DEF int pf_vmf_encoding_find(const pf_real *texels, long long nlobes, pf_vmf_encoding *enc)
{
    pf_real klo = PF_VMF_KAPPA_MAX, khi = PF_VMF_KAPPA_MIN, amax = PF_R(0.0);
    long long i;
    int rc = pfi_enc_check(texels, nlobes, 4, PF_ENCODE_UNORM16, enc);
    if (rc != PF_OK) return rc;
    for (i = 0; i < 4 * nlobes; ++i)
        if (!pfi_enc_finite(texels[i])) return PF_ERR_ARG;
    for (i = 0; i < nlobes; ++i) {
        pf_real k = pf_vmf_kappa_clamp(texels[4 * i + 2]);
        klo = pf_min(klo, k);
        khi = pf_max(khi, k);
        amax = pf_max(amax, texels[4 * i + 3]);
    }
    if (klo > khi) khi = klo;
    enc->log_kappa_lo = PF_LOG(klo);
    enc->log_kappa_span = PF_LOG(khi) - PF_LOG(klo);
    enc->amp_scale = amax;
    return PF_OK;
}

/* Encode nlobes lobe texels into 4 nlobes UNORM codes (octahedral u, v; log kappa; amp) of
   format PF_ENCODE_UNORM16 or PF_ENCODE_UNORM8 (PF_ENCODE_HALF: PF_ERR_ARG). A stored axis
   (mu.x, mu.y) outside the unit disc is read as pf_vmf_lobe_make reads it (rescaled onto the
   horizon). Errors as in CONVENTIONS; nothing written on an error. */
PF_CPU_DEF int pf_vmf_lobes_encode(const pf_real *texels, long long nlobes, const pf_vmf_encoding *enc, int format,
                                   void *out)
{
    long long i;
    int rc = pfi_enc_check(texels, nlobes, 4, format, out);
    if (rc != PF_OK) return rc;
    if (!enc || format == PF_ENCODE_HALF || !pfi_enc_finite(enc->log_kappa_lo) ||
        pfi_enc_range_ok(PF_R(0.0), enc->log_kappa_span) != PF_OK || pfi_enc_range_ok(PF_R(0.0), enc->amp_scale) != PF_OK)
        return PF_ERR_ARG;
    for (i = 0; i < 4 * nlobes; ++i)
        if (!pfi_enc_finite(texels[i])) return PF_ERR_ARG;
    for (i = 0; i < nlobes; ++i) {
        const pf_real *t = texels + 4 * i;
        pf_vmf_lobe l = pf_vmf_lobe_make(t[3], t[0], t[1], t[2]);
        pf_real u, v;
        pf_oct_hemi_encode(l.mu, &u, &v);
        pfi_enc_store(out, 4 * i, format, u, PF_R(-1.0), PF_R(2.0));
        pfi_enc_store(out, 4 * i + 1, format, v, PF_R(-1.0), PF_R(2.0));
        pfi_enc_store(out, 4 * i + 2, format, PF_LOG(l.kappa), enc->log_kappa_lo, enc->log_kappa_span);
        pfi_enc_store(out, 4 * i + 3, format, l.amp, PF_R(0.0), enc->amp_scale);
    }
    return PF_OK;
}

#endif /* !PF_GLSL */

#endif /* PF_ENCODE_H */

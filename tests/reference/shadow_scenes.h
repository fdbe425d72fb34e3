/* shadow_scenes.h - synthetic shadow maps and brute-force footprint lookups, shared by
   tests/test_shadow.c and bench/bench_shadow.c. CPU-only test code (allocates), not part of
   the library.

   SCENES (depth maps of SHS_N x SHS_N texels, depths in [0, 1], 0 nearest the light; each
   texel keeps the nearest surface, as a rasterized shadow map does)
     boxes        flat ground at 0.9 and 48 axis-aligned boxes (flat tops) of 4-40 texels at
                  depths uniform in [0.15, 0.8], overlapping one another
     spheres      flat ground at 0.9 and 40 spheres (radius 5-28 texels, centre depth
                  uniform in [0.3, 0.75], depth profile of a real sphere: smooth depths)
     layers_g     flat ground at 0.9, 30 rectangles of a first occluder layer at 0.4 and 30
                  of a second at 0.4 + g, overlapping (g = 0.01, 0.05, 0.2): footprints with
                  three depths, where two-moment methods bleed light
     Every scene is built from a fixed seed: identical on every platform and build.

   LOOKUPS
     For each scene, SHS_PER_SIZE square footprints of k x k texels (k = 2, 4, 8, 16) at seeded
     random positions, each with three receivers:
       ground   d = the ground depth 0.9 (a planar receiver behind the occluders: the
                penumbra case every method is designed for; fully covered footprints are
                fully shadowed, which is where light leaks are measured)
       centre   d = the depth of the footprint's centre texel (the surface seen at that pixel)
       between  d uniform between the smallest and largest depth (a receiver in front of some
                texels: where ESM over-lights and Chebyshev is loosest)
       contact  d = the largest depth + a gap uniform in [0.005, 0.05] (capped at 1): a receiver
                just behind everything in the footprint, fully shadowed (truth 0) unless the
                cap is hit - the contact-shadow case where exponential methods leak
     A lookup holds the receiver d (rounded to pf_real), the truth = the fraction of texels
     with z >= d (the average of binary depth tests, B&N 2012 eq. 33, texel depths as stored
     in pf_real), and the footprint's filtered values for every method: each texel's value
     from the pf_moments.h constructor (in pf_real, as stored), box-averaged in long double and
     rounded to pf_real (the ideal filter over fp32 storage). ESM is averaged in log space
     (log-sum-exp in long double) with exponent SHS_ESM_C. */
#ifndef SHADOW_SCENES_H
#define SHADOW_SCENES_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pf_shadow.h"

#if defined(__GNUC__) || defined(__clang__)
#  define SHS_FN static __attribute__((unused))
#else
#  define SHS_FN static
#endif

#define SHS_N 256
#define SHS_PER_SIZE 200
#define SHS_N_SIZES 4
#define SHS_N_RECEIVERS 4
#define SHS_GROUND 0.9
#define SHS_ESM_C PF_SHADOW_ESM_EXPONENT_DEFAULT
#define SHS_EVSM_POS PF_SHADOW_EVSM_POS_DEFAULT
#define SHS_EVSM_NEG PF_SHADOW_EVSM_NEG_DEFAULT

enum { SHS_BOXES, SHS_SPHERES, SHS_LAYERS_001, SHS_LAYERS_005, SHS_LAYERS_02, SHS_N_SCENES };
enum { SHS_GROUND_RECEIVER, SHS_CENTRE, SHS_BETWEEN, SHS_CONTACT };

static const char *const shs_scene_names[SHS_N_SCENES] = {
    "boxes", "spheres", "layers_0.01", "layers_0.05", "layers_0.2"
};
static const char *const shs_receiver_names[SHS_N_RECEIVERS] = { "ground", "centre", "between", "contact" };
static const int shs_sizes[SHS_N_SIZES] = { 2, 4, 8, 16 };

#define SHS_LOOKUPS_PER_SCENE (SHS_N_SIZES * SHS_PER_SIZE * SHS_N_RECEIVERS)

typedef struct shs_lookup {
    int scene, size, receiver;
    int x0, y0;         /* the footprint's first texel (column, row) in the scene's map */
    pf_real d;          /* receiver depth */
    long double truth;  /* fraction of the footprint's texels with z >= d */
    pf_real z_centre;   /* depth of the centre texel (what an unfiltered 1-tap test reads) */
    pf_depth_moments2 vsm;
    pf_depth_moments2 evsm2;
    pf_evsm_moments evsm4;
    pf_depth_moments4 msm;
    pf_real esm_log;
} shs_lookup;

/* splitmix64, fixed seeds */
typedef struct shs_rng {
    unsigned long long s;
} shs_rng;

SHS_FN unsigned long long shs_next(shs_rng *r)
{
    unsigned long long z = (r->s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

SHS_FN double shs_unif(shs_rng *r, double a, double b)
{
    return a + (b - a) * ((double)(shs_next(r) >> 11) * (1.0 / 9007199254740992.0));
}

SHS_FN int shs_int(shs_rng *r, int lo, int hi) /* uniform in [lo, hi] */
{
    return lo + (int)(shs_next(r) % (unsigned long long)(hi - lo + 1));
}

SHS_FN void shs_rect(double *z, int x0, int y0, int w, int h, double depth)
{
    int x, y;
    for (y = y0; y < y0 + h && y < SHS_N; ++y)
        for (x = x0; x < x0 + w && x < SHS_N; ++x)
            if (depth < z[y * SHS_N + x]) z[y * SHS_N + x] = depth;
}

/* Fills z[SHS_N * SHS_N] with scene `id`. */
SHS_FN void shs_make_scene(int id, double *z)
{
    shs_rng r;
    int i, x, y;
    r.s = 0x5ad0u + 7919u * (unsigned)id;
    for (i = 0; i < SHS_N * SHS_N; ++i) z[i] = SHS_GROUND;
    if (id == SHS_BOXES) {
        for (i = 0; i < 48; ++i) {
            /* one draw per statement: argument evaluation order is unspecified in C */
            int x0 = shs_int(&r, 0, SHS_N - 8), y0 = shs_int(&r, 0, SHS_N - 8);
            int w = shs_int(&r, 4, 40), h = shs_int(&r, 4, 40);
            double depth = shs_unif(&r, 0.15, 0.8);
            shs_rect(z, x0, y0, w, h, depth);
        }
    } else if (id == SHS_SPHERES) {
        for (i = 0; i < 40; ++i) {
            double cx = shs_unif(&r, 0.0, SHS_N), cy = shs_unif(&r, 0.0, SHS_N);
            double rad = shs_unif(&r, 5.0, 28.0), zc = shs_unif(&r, 0.3, 0.75);
            double rz = rad / SHS_N; /* depth extent of the sphere in depth units */
            for (y = 0; y < SHS_N; ++y)
                for (x = 0; x < SHS_N; ++x) {
                    double dx = (x + 0.5 - cx) / rad, dy = (y + 0.5 - cy) / rad, q = dx * dx + dy * dy;
                    if (q < 1.0) {
                        double zz = zc - rz * sqrt(1.0 - q);
                        if (zz < z[y * SHS_N + x]) z[y * SHS_N + x] = zz;
                    }
                }
        }
    } else {
        double gap = id == SHS_LAYERS_001 ? 0.01 : (id == SHS_LAYERS_005 ? 0.05 : 0.2);
        for (i = 0; i < 60; ++i) {
            int x0 = shs_int(&r, 0, SHS_N - 8), y0 = shs_int(&r, 0, SHS_N - 8);
            int w = shs_int(&r, 6, 48), h = shs_int(&r, 6, 48);
            shs_rect(z, x0, y0, w, h, i < 30 ? 0.4 : 0.4 + gap);
        }
    }
}

/* One footprint's lookups (one per receiver kind) appended at out[0..]. zt: texel depths as stored
   (pf_real). */
SHS_FN void shs_footprint(const pf_real *zt, int scene, int k, int x0, int y0, shs_rng *r, shs_lookup *out)
{
    long double s_v1 = 0, s_v2 = 0, s_e1 = 0, s_e2 = 0, s_p1 = 0, s_p2 = 0, s_n1 = 0, s_n2 = 0;
    long double s_m1 = 0, s_m2 = 0, s_m3 = 0, s_m4 = 0, lmax = -HUGE_VALL, s_esm = 0;
    long double n = (long double)(k * k);
    pf_real zmin = PF_R(2.0), zmax = PF_R(-1.0);
    int x, y, j;
    shs_lookup base;
    memset(&base, 0, sizeof base);
    for (y = y0; y < y0 + k; ++y)
        for (x = x0; x < x0 + k; ++x) {
            pf_real z = zt[y * SHS_N + x];
            pf_depth_moments2 v = pf_depth_moments2_from_depth(z);
            pf_depth_moments2 e = pf_evsm2_from_depth(z, SHS_EVSM_POS);
            pf_evsm_moments p = pf_evsm_moments_from_depth(z, SHS_EVSM_POS, SHS_EVSM_NEG);
            pf_depth_moments4 m = pf_depth_moments4_from_depth(z);
            long double l = (long double)pf_esm_log_from_depth(z, SHS_ESM_C);
            s_v1 += (long double)v.m1; s_v2 += (long double)v.m2;
            s_e1 += (long double)e.m1; s_e2 += (long double)e.m2;
            s_p1 += (long double)p.pos1; s_p2 += (long double)p.pos2;
            s_n1 += (long double)p.neg1; s_n2 += (long double)p.neg2;
            s_m1 += (long double)m.m1; s_m2 += (long double)m.m2;
            s_m3 += (long double)m.m3; s_m4 += (long double)m.m4;
            if (l > lmax) lmax = l;
            if (z < zmin) zmin = z;
            if (z > zmax) zmax = z;
        }
    /* log-sum-exp in long double */
    for (y = y0; y < y0 + k; ++y)
        for (x = x0; x < x0 + k; ++x)
            s_esm += expl((long double)pf_esm_log_from_depth(zt[y * SHS_N + x], SHS_ESM_C) - lmax);
    base.scene = scene;
    base.size = k;
    base.x0 = x0;
    base.y0 = y0;
    base.z_centre = zt[(y0 + k / 2) * SHS_N + x0 + k / 2];
    base.vsm = pf_depth_moments2_make((pf_real)(s_v1 / n), (pf_real)(s_v2 / n));
    base.evsm2 = pf_depth_moments2_make((pf_real)(s_e1 / n), (pf_real)(s_e2 / n));
    base.evsm4 = pf_evsm_moments_make((pf_real)(s_p1 / n), (pf_real)(s_p2 / n), (pf_real)(s_n1 / n),
                                      (pf_real)(s_n2 / n));
    base.msm = pf_depth_moments4_make((pf_real)(s_m1 / n), (pf_real)(s_m2 / n), (pf_real)(s_m3 / n),
                                      (pf_real)(s_m4 / n));
    base.esm_log = (pf_real)(lmax + logl(s_esm / n));
    for (j = 0; j < SHS_N_RECEIVERS; ++j) {
        long double lit = 0;
        shs_lookup *o = &out[j];
        *o = base;
        o->receiver = j;
        if (j == SHS_GROUND_RECEIVER) o->d = (pf_real)SHS_GROUND;
        else if (j == SHS_CENTRE) o->d = base.z_centre;
        else if (j == SHS_BETWEEN) o->d = (pf_real)shs_unif(r, (double)zmin, (double)zmax);
        else o->d = (pf_real)fmin(1.0, (double)zmax + shs_unif(r, 0.005, 0.05));
        for (y = y0; y < y0 + k; ++y)
            for (x = x0; x < x0 + k; ++x)
                if ((long double)zt[y * SHS_N + x] >= (long double)o->d) lit += 1.0L;
        o->truth = lit / n;
    }
}

/* All lookups of scene `id`: SHS_LOOKUPS_PER_SCENE entries written to out. */
SHS_FN void shs_scene_lookups(int id, shs_lookup *out)
{
    double *z = (double *)malloc(sizeof(double) * SHS_N * SHS_N);
    pf_real *zt = (pf_real *)malloc(sizeof(pf_real) * SHS_N * SHS_N);
    shs_rng r;
    int i, s, f, cnt = 0;
    if (!z || !zt) abort();
    shs_make_scene(id, z);
    for (i = 0; i < SHS_N * SHS_N; ++i) zt[i] = (pf_real)z[i];
    r.s = 0xf007u + 104729u * (unsigned)id;
    for (s = 0; s < SHS_N_SIZES; ++s) {
        int k = shs_sizes[s];
        for (f = 0; f < SHS_PER_SIZE; ++f) {
            int x0 = shs_int(&r, 0, SHS_N - k), y0 = shs_int(&r, 0, SHS_N - k);
            shs_footprint(zt, id, k, x0, y0, &r, &out[cnt]);
            cnt += SHS_N_RECEIVERS;
        }
    }
    free(z);
    free(zt);
}

/* ---------------------------------------------------------------- the methods, by index */
enum { SHS_M_PCF1, SHS_M_VSM, SHS_M_VSM_BLEED, SHS_M_ESM, SHS_M_EVSM2, SHS_M_EVSM4, SHS_M_MSM, SHS_N_METHODS };
static const char *const shs_method_names[SHS_N_METHODS] = {
    "pcf_1tap", "vsm", "vsm_bleed0.3", "esm", "evsm2", "evsm4", "msm"
};
static const int shs_method_bytes[SHS_N_METHODS] = {
    4, PF_SHADOW_BYTES_VSM, PF_SHADOW_BYTES_VSM, PF_SHADOW_BYTES_ESM, PF_SHADOW_BYTES_EVSM2,
    PF_SHADOW_BYTES_EVSM4, PF_SHADOW_BYTES_MSM
};
#define SHS_BLEED PF_R(0.3)

/* Lit fraction of lookup L by method `m`, every parameter at its default (bleed 0.3 for
   vsm_bleed0.3). pcf_1tap is the unfiltered depth test of the centre texel. */
SHS_FN pf_real shs_eval(int m, const shs_lookup *L)
{
    switch (m) {
    case SHS_M_PCF1: return L->d <= L->z_centre ? PF_R(1.0) : PF_R(0.0);
    case SHS_M_VSM: return pf_shadow_vsm(L->vsm, L->d, PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT, PF_SHADOW_BLEED_DEFAULT);
    case SHS_M_VSM_BLEED: return pf_shadow_vsm(L->vsm, L->d, PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT, SHS_BLEED);
    case SHS_M_ESM: return pf_shadow_esm(L->esm_log, L->d, SHS_ESM_C);
    case SHS_M_EVSM2:
        return pf_shadow_evsm2(L->evsm2, L->d, SHS_EVSM_POS, PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT, PF_SHADOW_BLEED_DEFAULT);
    case SHS_M_EVSM4:
        return pf_shadow_evsm4(L->evsm4, L->d, SHS_EVSM_POS, SHS_EVSM_NEG, PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT,
                               PF_SHADOW_BLEED_DEFAULT);
    default:
        return pf_shadow_msm(L->msm, L->d, PF_SHADOW_MSM_MOMENT_BIAS_DEFAULT, PF_SHADOW_MSM_DEPTH_BIAS_DEFAULT);
    }
}

/* Error figures of one method over a set of lookups. */
typedef struct shs_stats {
    long double sum_err, max_err, sum_leak, max_leak;
    long n, n_dark;
} shs_stats;

SHS_FN void shs_stats_add(shs_stats *s, long double got, long double truth)
{
    long double e = fabsl(got - truth);
    if (!(e <= 1.0L)) e = 1.0L; /* NaN or out of range counts as the worst */
    s->sum_err += e;
    if (e > s->max_err) s->max_err = e;
    s->n++;
    if (truth == 0.0L) {
        long double g = got > 0.0L ? got : 0.0L;
        if (!(g <= 1.0L)) g = 1.0L;
        s->sum_leak += g;
        if (g > s->max_leak) s->max_leak = g;
        s->n_dark++;
    }
}

SHS_FN long double shs_mean_err(const shs_stats *s) { return s->n ? s->sum_err / (long double)s->n : 0.0L; }
SHS_FN long double shs_mean_leak(const shs_stats *s) { return s->n_dark ? s->sum_leak / (long double)s->n_dark : 0.0L; }

#endif /* SHADOW_SCENES_H */

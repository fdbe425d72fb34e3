/* pf_vmf_fit.h - CPU baking for pf_vmf.h: the spherical EM fit of vMF lobes to a footprint's
   normals and the lobe pyramid a shader fetches. The scaling function of Wu et al. 2019
   (eqs. 6-8, 12-14, 21-24) that corrects the multi-lobe BRDF toward the height field's
   effective BRDF is pf_vmf_scale.h's. pf_vmf.h holds what a shader pastes; map infrastructure
   (layout, wrap, stencils, the height-field march) is pf_map.h's, the slope-preserving
   downsampler pf_map_downsample.h's. CPU only (PF_CPU_DEF:
   caller-owned buffers, no allocation); empty under PF_GLSL.

   USAGE
     pf_vmf_fit_normals(normals, NULL, n, 4, 24, &mixture);           -- EM on n normals
     pf_vmf_pyramid_from_normals(normals, NULL, w, h, 4, 24, pyr);    -- one mixture per texel

   FUNCTIONS
     fitting     pf_vmf_fit_normals (struct pf_vmf_mixture: the fit's lobes)
     pyramid     pf_vmf_pyramid_level_count, _level_offset, _texel_count, _from_normals,
                 pf_vmf_mixture_from_texel

   ACCURACY AND COST (tests/test_vmf_fit.c, bench/bench_vmf.c; docs/vmf_fit.md): a 512 x 512
   pyramid fits in 2.1-2.8 s CPU at m = 4, 3.8-9.4 s at m = 16.

   SOURCES
     Wu, Zhao, Yan, Ramamoorthi 2019 eqs. 6-8, 12-14, 21-24; Han, Sun, Ramamoorthi, Grinspun
     2007 (spherical EM of vMF mixtures); Banerjee, Dhillon, Ghosh, Sra 2005 (kappa from the
     mean resultant length). */
#ifndef PF_VMF_FIT_H
#define PF_VMF_FIT_H

#ifndef PF_GLSL
#  include "pf_vmf.h"
#  include "pf_map.h"

/* EM stops when the mean log-likelihood per unit weight changes by less than this (relative,
   at least absolute 1) */
#ifndef PF_VMF_EM_TOLERANCE
#  define PF_VMF_EM_TOLERANCE PF_R(1.0e-6)
#endif

/* ================================================================ mixtures
   The fit's output: up to PF_VMF_MAX_LOBES lobes (amplitudes summing to 1), shaded lobe by
   lobe with pf_vmf_sum_add as a shader does with the pyramid's texels. */
typedef struct pf_vmf_mixture {
    pf_vmf_lobe lobe[PF_VMF_MAX_LOBES];
    int count;
} pf_vmf_mixture;

/* ================================================================ fitting
   Spherical EM (Banerjee et al. 2005; Han et al. 2007 sec. 4) of m vMF lobes to weighted
   unit normals: each iteration is ONE pass that
   computes every normal's responsibilities on the fly and accumulates, per lobe, W = sum w r,
   D = sum w r (x - mu_old) and S = sum w r |x - mu_old|^2 (relative to the previous axis, so
   that the concentration needs no 1 - |R|/W cancellation: W^2 (1 - rbar^2) = W S - |D|^2
   exactly, by the parallel-axis rule). Then a = W / sum W, mu = (W mu_old + D) normalized,
   kappa = rbar (3 - rbar^2) / (1 - rbar^2) (Banerjee et al.'s approximation), clamped.
   SEEDING (deterministic): lobe 0 on the weighted mean normal, each next lobe on the normal
   farthest (largest 1 - mu.x) from every lobe so far (first such in memory order); seeding
   stops early when every normal lies within 1e-7 (1 - cos) of a lobe, so the fit may return
   fewer lobes than asked. Initial kappa from the whole set's resultant, at least 1.
   ITERATIONS: at most `iterations` EM steps; it stops earlier when the mean log-likelihood
   changes by less than 1e-6. Lobes whose weight share falls below 1e-6 are dropped.
   DEGENERATE INPUT: normals with a NaN or infinite component or zero length, and weights that
   are NaN, infinite or <= 0, are skipped; every other normal and weight is used, however tiny
   or huge (subnormal to PF_REAL_MAX): each normal is divided by its largest component before
   it is normalized, and the weights by the largest usable one (no sum can overflow). Under
   -ffast-math subnormal normals and weights read as 0 (flushed). No usable normal:
   PF_ERR_ARG and *out is not written (pf_core.h: nothing is written on an error).
   Errors: PF_ERR_ARG for NULL normals or out, count < 1, lobes outside [1, PF_VMF_MAX_LOBES = 16], iterations < 0;
   PF_ERR_SIZE when count * 3 exceeds PF_MAX_REALS. */
PF_CPU_DEF int pfi_vmf_read(const pf_real *normals, const pf_real *weights, long long i, pf_vec3 *x, pf_real *w)
{
    pf_real a = normals[3 * i], b = normals[3 * i + 1], c = normals[3 * i + 2], m, l2, wt;
    wt = weights ? weights[i] : PF_R(1.0);
    if (!(wt > PF_R(0.0)) || !(wt <= PF_REAL_MAX)) return 0;
    /* divided by the largest component first: every finite non-zero normal, 1e-40 or 1e38
       long, normalizes without an overflow or underflow of its squared length (in [1, 3]) */
    m = pf_max(pf_max(PF_FABS(a), PF_FABS(b)), PF_FABS(c));
    if (!(m > PF_R(0.0)) || !(m <= PF_REAL_MAX)) return 0;
    a /= m;
    b /= m;
    c /= m;
    l2 = a * a + b * b + c * c;
    /* l2 is in [1, 3] (the largest component is +-1): below 1/2 only for a NaN component.
       Not >= 1: -ffast-math's a * (1/m) can round the largest component to 1 - eps, and the
       passes of the fit must all read the same normals. */
    if (!(l2 >= PF_R(0.5))) return 0;
    l2 = PF_R(1.0) / PF_SQRT(l2);
    *x = pf_vec3_make(a * l2, b * l2, c * l2);
    *w = wt;
    return 1;
}

/* the block walker: rows of bw normals, `row` normals apart, bh rows (a pyramid footprint) */
#define PFI_VMF_FOREACH(...)                                                                    \
    for (yy = 0; yy < bh; ++yy)                                                                \
        for (xx = 0; xx < bw; ++xx) {                                                          \
            long long id = yy * row + xx;                                                      \
            if (!pfi_vmf_read(normals, weights, id, &x, &wt)) continue;                        \
            wt = (wt * wscale) * wscale;                                                       \
            __VA_ARGS__                                                                        \
        }

PF_CPU_DEF pf_vmf_mixture pfi_vmf_mixture_empty(void)
{
    pf_vmf_mixture m;
    int i;
    for (i = 0; i < PF_VMF_MAX_LOBES; ++i) m.lobe[i] = pf_vmf_lobe_make(PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(1.0));
    m.count = 0;
    return m;
}

PF_CPU_DEF pf_vmf_mixture pfi_vmf_flat(void)
{
    pf_vmf_mixture m = pfi_vmf_mixture_empty();
    m.lobe[0] = pf_vmf_lobe_make(PF_R(1.0), PF_R(0.0), PF_R(0.0), PF_VMF_KAPPA_MAX);
    m.count = 1;
    return m;
}

PF_CPU_DEF int pfi_vmf_fit_block(const pf_real *normals, const pf_real *weights, long long row, long long bw,
                                 long long bh, int lobes, int iterations, pf_vmf_mixture *out)
{
    pf_vmf_mixture m = pfi_vmf_mixture_empty();
    pf_vec3 x, sum = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0));
    pf_real wt, wsum = PF_R(0.0), logc[PF_VMF_MAX_LOBES], prev_ll = PF_R(0.0), wscale = PF_R(1.0), wmax = PF_R(0.0);
    long long xx, yy;
    int k, it, n;
    /* weights divided by the largest usable one (times 1/sqrt(wmax) twice: 1/wmax itself
       overflows for a subnormal wmax and is subnormal for wmax near PF_REAL_MAX), so that any
       finite positive weights are used and no sum of the fit can overflow; the first pass
       reads them unscaled (wscale 1) */
    PFI_VMF_FOREACH(wmax = pf_max(wmax, wt);)
    if (!(wmax > PF_R(0.0))) return PF_ERR_ARG;
    wscale = PF_R(1.0) / PF_SQRT(wmax);
    wmax = PF_R(0.0);
    PFI_VMF_FOREACH(sum = pf_vec3_add(sum, pf_vec3_scale(x, wt)); wsum += wt; wmax = pf_max(wmax, wt);)
    if (!(wsum > PF_R(0.0)) || !(wsum < PF_REAL_MAX) || !(wmax > PF_R(0.25))) return PF_ERR_ARG;
    /* seeding */
    {
        pf_real len = pf_vec3_length(sum), kappa0;
        pf_vec3 mu0 = len > PF_R(0.0) ? pf_vec3_scale(sum, PF_R(1.0) / len) : pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
        kappa0 = pf_max(pf_vmf_kappa_from_mean_length(len / wsum), PF_R(1.0));
        m.lobe[0].mu = mu0;
        m.lobe[0].kappa = kappa0;
        m.count = 1;
        for (k = 1; k < lobes; ++k) {
            pf_real best = PF_R(1.0e-7);
            pf_vec3 pick = mu0;
            int found = 0, j;
            PFI_VMF_FOREACH({
                pf_real dmin = PF_R(4.0);
                for (j = 0; j < m.count; ++j) {
                    pf_vec3 d = pf_vec3_sub(x, m.lobe[j].mu);
                    dmin = pf_min(dmin, PF_R(0.5) * pf_vec3_dot(d, d));
                }
                if (dmin > best) {
                    best = dmin;
                    pick = x;
                    found = 1;
                }
            })
            if (!found) break;
            m.lobe[m.count].mu = pick;
            m.lobe[m.count].kappa = kappa0;
            m.count++;
        }
        for (k = 0; k < m.count; ++k) m.lobe[k].amp = PF_R(1.0) / (pf_real)m.count;
    }
    /* EM */
    for (it = 0; it < iterations && m.count > 1; ++it) {
        pf_real W[PF_VMF_MAX_LOBES], S[PF_VMF_MAX_LOBES], ll = PF_R(0.0);
        pf_vec3 D[PF_VMF_MAX_LOBES];
        for (k = 0; k < m.count; ++k) {
            W[k] = S[k] = PF_R(0.0);
            D[k] = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0));
            logc[k] = PF_LOG(m.lobe[k].amp * pf_vmf_normalization(m.lobe[k].kappa));
        }
        PFI_VMF_FOREACH({
            pf_real lg[PF_VMF_MAX_LOBES], d2[PF_VMF_MAX_LOBES], top = -PF_REAL_MAX, tot = PF_R(0.0);
            pf_vec3 dv[PF_VMF_MAX_LOBES];
            for (k = 0; k < m.count; ++k) {
                dv[k] = pf_vec3_sub(x, m.lobe[k].mu);
                d2[k] = pf_vec3_dot(dv[k], dv[k]);
                lg[k] = logc[k] - PF_R(0.5) * m.lobe[k].kappa * d2[k];
                top = pf_max(top, lg[k]);
            }
            for (k = 0; k < m.count; ++k) {
                lg[k] = PF_EXP(pf_max(lg[k] - top, -PF_VMF_EXP_CAP));
                tot += lg[k];
            }
            ll += wt * (top + PF_LOG(tot));
            for (k = 0; k < m.count; ++k) {
                pf_real r = wt * lg[k] / tot;
                W[k] += r;
                S[k] += r * d2[k];
                D[k] = pf_vec3_add(D[k], pf_vec3_scale(dv[k], r));
            }
        })
        /* M step; empty lobes dropped (compacted in order) */
        n = 0;
        for (k = 0; k < m.count; ++k) {
            pf_vec3 r;
            pf_real len, one_minus_r2, rbar;
            if (!(W[k] > PF_R(1.0e-6) * wsum)) continue;
            r = pf_vec3_add(pf_vec3_scale(m.lobe[k].mu, W[k]), D[k]);
            len = pf_vec3_length(r);
            if (!(len > PF_R(0.0))) continue;
            rbar = pf_min(len / W[k], PF_R(1.0));
            one_minus_r2 = pf_max((W[k] * S[k] - pf_vec3_dot(D[k], D[k])) / (W[k] * W[k]), PF_R(0.0));
            m.lobe[n].amp = W[k] / wsum;
            m.lobe[n].mu = pf_vec3_scale(r, PF_R(1.0) / len);
            m.lobe[n].kappa = one_minus_r2 * PF_VMF_KAPPA_MAX > rbar * (PF_R(3.0) - rbar * rbar)
                             ? pf_vmf_kappa_clamp(rbar * (PF_R(3.0) - rbar * rbar) / one_minus_r2)
                             : PF_VMF_KAPPA_MAX;
            ++n;
        }
        m.count = n;
        for (k = n; k < PF_VMF_MAX_LOBES; ++k) m.lobe[k].amp = PF_R(0.0);
        ll = ll / wsum;
        if (it > 0 && PF_FABS(ll - prev_ll) <= PF_VMF_EM_TOLERANCE * pf_max(PF_R(1.0), PF_FABS(ll))) break;
        prev_ll = ll;
    }
    /* FINAL PASS, in slope space: the EM's responsibilities partition the normals; each lobe's
       stored axis and kappa are then matched to the responsibility-weighted slope mean s_k and
       slope variance (trace) of its share: mu = (-s_k, 1)/|.|, kappa such that
       pf_vmf_lobe_slope_stats' trace v (1/mu.z^4 + 1/mu.z^2) equals it. So the slope-form
       BRDF's lobes carry the footprint's slope moments (one lobe: LEADR's mean and the trace
       of its covariance); the spherical kappa of Banerjee's rule underestimates the slope
       spread of a Gaussian-slope footprint (tan against sin: 0.74 against 0.10 error on the
       bench's gaussian_fine kind at one lobe). Slopes of normals within 1e-3 of the horizon
       are read at mu.z = 1e-3. */
    {
        pf_real W[PF_VMF_MAX_LOBES], S2[PF_VMF_MAX_LOBES], SX[PF_VMF_MAX_LOBES], SY[PF_VMF_MAX_LOBES];
        for (k = 0; k < m.count; ++k) {
            W[k] = S2[k] = SX[k] = SY[k] = PF_R(0.0);
            logc[k] = PF_LOG(m.lobe[k].amp * pf_vmf_normalization(m.lobe[k].kappa));
        }
        PFI_VMF_FOREACH({
            pf_real lg[PF_VMF_MAX_LOBES], top = -PF_REAL_MAX, tot = PF_R(0.0);
            pf_real iz = PF_R(1.0) / pf_max(x.z, PF_R(1.0e-3)), sx = -x.x * iz, sy = -x.y * iz;
            for (k = 0; k < m.count; ++k) {
                pf_vec3 dv = pf_vec3_sub(x, m.lobe[k].mu);
                lg[k] = logc[k] - PF_R(0.5) * m.lobe[k].kappa * pf_vec3_dot(dv, dv);
                top = pf_max(top, lg[k]);
            }
            for (k = 0; k < m.count; ++k) {
                lg[k] = PF_EXP(pf_max(lg[k] - top, -PF_VMF_EXP_CAP));
                tot += lg[k];
            }
            for (k = 0; k < m.count; ++k) {
                pf_real r = wt * lg[k] / tot;
                W[k] += r;
                SX[k] += r * sx;
                SY[k] += r * sy;
                S2[k] += r * (sx * sx + sy * sy);
            }
        })
        n = 0;
        for (k = 0; k < m.count; ++k) {
            pf_real mx, my, tr, iz2;
            if (!(W[k] > PF_R(1.0e-6) * wsum)) continue;
            mx = SX[k] / W[k];
            my = SY[k] / W[k];
            tr = pf_max(S2[k] / W[k] - mx * mx - my * my, PF_R(0.0));
            iz2 = PF_R(1.0) + mx * mx + my * my;
            m.lobe[n].amp = W[k] / wsum;
            m.lobe[n].mu = pf_vec3_scale(pf_vec3_make(-mx, -my, PF_R(1.0)), PF_R(1.0) / PF_SQRT(iz2));
            m.lobe[n].kappa = pf_vmf_kappa_from_tangent_variance(tr / (iz2 * iz2 + iz2));
            ++n;
        }
        m.count = n;
        for (k = n; k < PF_VMF_MAX_LOBES; ++k) m.lobe[k].amp = PF_R(0.0);
        if (n == 0) return PF_ERR_ARG;
    }
    /* lobe axes on the upper hemisphere (the packed form's convention) */
    for (k = 0; k < m.count; ++k)
        if (m.lobe[k].mu.z < PF_R(0.0)) {
            pf_vec3 a = m.lobe[k].mu;
            pf_real l = PF_SQRT(a.x * a.x + a.y * a.y);
            m.lobe[k].mu = l > PF_R(0.0) ? pf_vec3_make(a.x / l, a.y / l, PF_R(0.0)) : pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0));
        }
    *out = m;
    return PF_OK;
}

/* Fits up to `lobes` vMF lobes to count unit normals (3 pf_reals each; non-unit ones are
   normalized) with optional weights (NULL: all 1). See the block comment above. */
PF_CPU_DEF int pf_vmf_fit_normals(const pf_real *normals, const pf_real *weights, long long count, int lobes,
                                  int iterations, pf_vmf_mixture *out)
{
    if (!out || !normals || count < 1 || lobes < 1 || lobes > PF_VMF_MAX_LOBES || iterations < 0) return PF_ERR_ARG;
    if (pf_size_mul(count, 3) < 0) return PF_ERR_SIZE;
    return pfi_vmf_fit_block(normals, weights, count, count, 1, lobes, iterations, out);
}

/* ================================================================ the lobe pyramid
   pf_map.h's pyramid layout for power-of-two sides: level l has max(1, w >> l) x max(1, h >> l)
   texels, texel (i, j) covering the finest texels [i fx, (i + 1) fx) x [j fy, (j + 1) fy),
   fx = w / (w >> l) (a box: what a mip level holds). Every level is FITTED FROM THE
   FINEST NORMALS of its footprint (not merged from the level below: merging m lobes of four
   children into m is itself a fit, and the finest normals are at hand); cost ~ levels x
   texels x lobes x iterations exps (docs/vmf.md has the measured time).
   LAYOUT (what a shader fetches): levels one after another from level 0, texels row-major,
   4 * lobes pf_reals per texel: for each lobe (mu.x, mu.y, kappa, amp) - an RGBA texel per
   lobe (mu.z = sqrt(1 - x^2 - y^2)). A fit that returns fewer lobes pads with amp = 0,
   mu = +z, kappa = 1. Bytes per texel: 16 m in float32, 8 m in half floats (kappa <= 1e5 fits
   half's range; its 11-bit precision is 0.05% on kappa).
   A texel whose footprint has no usable normal gets the flat lobe (amp 1, mu = +z, kappa =
   PF_VMF_KAPPA_MAX) and the call still returns PF_OK.
   Errors: PF_ERR_ARG for NULL normals or pyr, sides not powers of two, lobes outside [1, 16],
   iterations < 0; PF_ERR_SIZE above PF_MAX_SIDE or PF_MAX_REALS. normals: w h 3 pf_reals;
   weights: w h or NULL; pyr: pf_vmf_pyramid_texel_count(w, h) 4 lobes. Nothing else touched. */
PF_CPU_DEF int pfi_vmf_pow2(long long n) { return pf_size_side_ok(n) && (n & (n - 1)) == 0; }

/* levels: pf_mip_level_count (pf_map.h), 0 unless w and h are powers of two <= PF_MAX_SIDE */
PF_CPU_DEF int pf_vmf_pyramid_level_count(int w, int h)
{
    if (!pfi_vmf_pow2(w) || !pfi_vmf_pow2(h)) return 0;
    return pf_mip_level_count(w, h);
}

/* texels before `level` (>= count: the total), pf_mip_level_offset; -1 for bad sizes, level < 0 */
PF_CPU_DEF long long pf_vmf_pyramid_level_offset(int w, int h, int level)
{
    if (pf_vmf_pyramid_level_count(w, h) == 0 || level < 0) return -1;
    return pf_mip_level_offset(w, h, level);
}

/* texels of all levels together (4 * lobes pf_reals each); 0 for bad sizes and for a count
   above PF_MAX_REALS (2^24 x 2^24 on every host) */
PF_CPU_DEF long long pf_vmf_pyramid_texel_count(int w, int h)
{
    long long t = pf_vmf_pyramid_level_offset(w, h, 64);
    return t < 0 || t > PF_MAX_REALS ? 0 : t;
}

PF_CPU_DEF void pfi_vmf_store(pf_real *dst, pf_vmf_mixture m, int lobes)
{
    int k;
    for (k = 0; k < lobes; ++k) {
        int live = k < m.count;
        dst[4 * k] = live ? m.lobe[k].mu.x : PF_R(0.0);
        dst[4 * k + 1] = live ? m.lobe[k].mu.y : PF_R(0.0);
        dst[4 * k + 2] = live ? m.lobe[k].kappa : PF_R(1.0);
        dst[4 * k + 3] = live ? m.lobe[k].amp : PF_R(0.0);
    }
}

PF_CPU_DEF int pf_vmf_pyramid_from_normals(const pf_real *normals, const pf_real *weights, int w, int h, int lobes,
                                           int iterations, pf_real *pyr)
{
    int levels, l;
    long long off = 0;
    if (!normals || !pyr || w < 1 || h < 1 || lobes < 1 || lobes > PF_VMF_MAX_LOBES || iterations < 0)
        return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h)) return PF_ERR_SIZE;
    levels = pf_vmf_pyramid_level_count(w, h);
    if (levels == 0) return PF_ERR_ARG; /* not powers of two */
    if (pf_vmf_pyramid_texel_count(w, h) == 0 || pf_size_mul3(pf_vmf_pyramid_texel_count(w, h), 4, lobes) < 0 ||
        pf_size_mul3(w, h, 3) < 0)
        return PF_ERR_SIZE;
    for (l = 0; l < levels; ++l) {
        long long lw = (w >> l) > 0 ? (w >> l) : 1, lh = (h >> l) > 0 ? (h >> l) : 1;
        long long fx = w / lw, fy = h / lh, i, j;
        for (j = 0; j < lh; ++j)
            for (i = 0; i < lw; ++i) {
                pf_vmf_mixture m;
                long long first = j * fy * w + i * fx;
                if (pfi_vmf_fit_block(normals + 3 * first, weights ? weights + first : weights, w, fx, fy, lobes,
                                      iterations, &m) != PF_OK)
                    m = pfi_vmf_flat();
                pfi_vmf_store(pyr + (off + j * lw + i) * 4 * lobes, m, lobes);
            }
        off += lw * lh;
    }
    return PF_OK;
}

/* The mixture at one pyramid texel (4 lobes pf_reals), as a shader's RGBA fetches and
   pf_vmf_lobe_make give it; padding (amp 0) skipped, lobes clamped to [1, 16], NULL: empty. */
PF_CPU_DEF pf_vmf_mixture pf_vmf_mixture_from_texel(const pf_real *texel, int lobes)
{
    pf_vmf_mixture m = pfi_vmf_mixture_empty();
    int k, n = lobes < 1 ? 1 : (lobes > PF_VMF_MAX_LOBES ? PF_VMF_MAX_LOBES : lobes);
    if (!texel) return m;
    for (k = 0; k < n; ++k)
        if (texel[4 * k + 3] > PF_R(0.0))
            m.lobe[m.count++] = pf_vmf_lobe_make(texel[4 * k + 3], texel[4 * k], texel[4 * k + 1], texel[4 * k + 2]);
    return m;
}
#undef PFI_VMF_FOREACH
#endif /* !PF_GLSL */

#endif /* PF_VMF_FIT_H */

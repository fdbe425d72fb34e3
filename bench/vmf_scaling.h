/* bench/vmf_scaling.h - the scaling function of pf_vmf.h (Wu et al. 2019 eqs. 12-14, sec. 6)
   built on a height map and its vMF lobe pyramids, as bench/microsurface.c and bench/pictures.c
   both use it (bench code, not the library: it allocates nothing but keeps static scratch).

   The orchestration is the library's (pf_vmf_scale.h: pf_vmf_scale_fit_level, one call per
   level, and pf_vmf_scale_texel_t); this header only fixes the bench's settings:
     S   one VS_NT x VS_NT x VS_NP node table per lobe pyramid (theta max VS_THETA_MAX), the
         rank-1 fit (VS_ALS rounds, prior VS_SHRINK toward 1) over VS_TRAIN patches;
     T   one value per texel of the level.
   Shading: pf_vmf_scale_apply(T, pf_vmf_scale_lookup(S, ...), f) (docs/vmf.md).
   Cost: a 64 x 64 patch's samples march 4096 texels toward 48 directions and shade 2304
   direction pairs; through the library's sampler 16 training patches take 6.2 s of CPU, through
   vs_texel_samples (below) 1.75 s (bench/microsurface.c's stderr, 2026-11-28, busy machine).
   Needs <math.h> and <string.h> before it. */
#ifndef PF_BENCH_VMF_SCALING_H
#define PF_BENCH_VMF_SCALING_H

#include "pf_vmf_scale.h"

#define VS_NT 6
#define VS_NP 5
#define VS_CELLS (VS_NT * VS_NT * VS_NP)
#define VS_SAMPLES ((2 * VS_NT * (VS_NP - 1)) * (2 * VS_NT * (VS_NP - 1)))
#define VS_THETA_MAX (75.0 * 3.14159265358979323846 / 180.0)
#define VS_TRAIN 16
#define VS_ALS 8
/* the fit's prior toward 1 (pf_vmf_scale_desc.shrink): 1, the mean patch's (cell's) own
   energy. Quick maps, in-footprint, vmf_m8_scaled at 4096 texels: prior 0.1 gave craters 0.057,
   gaussian 0.126, prior 1 0.068, 0.126; scaled at every level, 1 was the steadier below
   (gaussian, 256 texels: 1.02 with 0.1, 0.58 with 1, 0.15 unscaled) */
#define VS_SHRINK PF_R(1.0)
#define VS_MAX_SIDE 64 /* largest patch side the static scratch holds */
#define VS_MAX_PYR 2   /* lobe pyramids fitted together (they share f_eff) */

/* the specular of texel (tx, ty) of a level of an m-lobe pyramid, its lobes alone (the slope
   form with base_var added, Smith G of the mixture's moments: pf_vmf_sum_specular) */
static inline pf_real vs_texel_spec(const pf_real *pyr, int w, int h, int m, int level, long long tx, long long ty, pf_vec3 wo,
                             pf_vec3 wi, pf_real base_var, pf_real f0)
{
    long long lw = (w >> level) > 1 ? (w >> level) : 1;
    const pf_real *t = pyr + (pf_vmf_pyramid_level_offset(w, h, level) + ty * lw + tx) * 4 * m;
    pf_vmf_sum sum = pf_vmf_sum_zero();
    int j;
    for (j = 0; j < m; ++j) { /* padding lobes (amp 0) add nothing */
        pf_vmf_lobe lobe = pf_vmf_lobe_make(t[4 * j + 3], t[4 * j], t[4 * j + 1], t[4 * j + 2]);
        sum = pf_vmf_sum_add(sum, lobe, wo, wi, base_var);
    }
    return pf_vmf_sum_specular(sum, wo, wi, f0);
}

/* the library's description of the bench's scaling function (pf_vmf_scale.h): the centred
   height map at 1 world unit per texel, the npyr lobe pyramids, VS_* nodes and fit settings */
static inline pf_vmf_scale_desc vs_desc(const pf_real *heights, int w, int h, pf_real base_sigma, pf_real f0, int npyr,
                                 const pf_real *const *pyrs, const int *ms)
{
    pf_vmf_scale_desc d;
    int k;
    memset(&d, 0, sizeof d);
    d.heights = heights;
    d.w = w;
    d.h = h;
    d.texel = PF_R(1.0);
    d.base_sigma = base_sigma;
    d.f0 = f0;
    d.pyramid_count = npyr;
    for (k = 0; k < npyr && k < PF_VMF_SCALE_MAX_PYRAMIDS; ++k) {
        d.pyramid[k] = pyrs[k];
        d.lobes[k] = ms[k];
    }
    d.masking = PF_VMF_SCALE_G_GAUSSIAN;
    d.nt = VS_NT;
    d.np = VS_NP;
    d.theta_max = (pf_real)VS_THETA_MAX;
    d.train_patches = VS_TRAIN;
    d.rounds = VS_ALS;
    d.shrink = VS_SHRINK;
    return d;
}

/* the static scratch of the level calls, for levels up to log2(VS_MAX_SIDE) */
static pf_real vs_scratch[VS_TRAIN * VS_SAMPLES * (1 + VS_MAX_PYR) + 2 * VS_TRAIN * VS_CELLS + VS_TRAIN +
                         3 * VS_MAX_SIDE * VS_MAX_SIDE + VS_SAMPLES +
                         (2 * VS_NT * (VS_NP - 1) * VS_MAX_SIDE * VS_MAX_SIDE + sizeof(pf_real) - 1) / sizeof(pf_real)];

/* S and the prior of each pyramid at `level` from VS_TRAIN evenly spaced patches
   (pf_vmf_scale_fit_level); the training patches' T written into t_level[k] (one pf_real per
   texel of the level, row-major), the others left as they are. Returns the number of patches
   sampled, -1 on failure. */
static inline int vs_fit_level(const pf_real *heights, int w, int h, int level, pf_real base_sigma, pf_real f0, int npyr,
                        const pf_real *const *pyrs, const int *ms, pf_real s_out[][VS_CELLS], pf_real *prior,
                        pf_real *const *t_level)
{
    pf_vmf_scale_desc d = vs_desc(heights, w, h, base_sigma, f0, npyr, pyrs, ms);
    pf_real *s[VS_MAX_PYR];
    int gw = w >> level, gh = h >> level, k;
    if (gw < 1 || gh < 1 || npyr > VS_MAX_PYR || (1 << level) > VS_MAX_SIDE) return -1;
    for (k = 0; k < npyr; ++k) s[k] = s_out[k];
    if (pf_vmf_scale_fit_level(&d, level, s, prior, t_level, vs_scratch, (long long)(sizeof vs_scratch / sizeof(pf_real))) != PF_OK)
        return -1;
    return gw * gh < VS_TRAIN ? gw * gh : VS_TRAIN;
}

/* T of texel (tx, ty) of `level` for each pyramid, given the level's S and prior (vs_fit_level):
   written to t_out[k] (pf_vmf_scale_texel_t); 0 on success */
static inline int vs_texel_t(const pf_real *heights, int w, int h, int level, long long tx, long long ty, pf_real base_sigma,
                      pf_real f0, int npyr, const pf_real *const *pyrs, const int *ms, pf_real s_tab[][VS_CELLS],
                      const pf_real *prior, pf_real *t_out)
{
    pf_vmf_scale_desc d = vs_desc(heights, w, h, base_sigma, f0, npyr, pyrs, ms);
    const pf_real *s[VS_MAX_PYR];
    int k;
    if (npyr > VS_MAX_PYR || (1 << level) > VS_MAX_SIDE) return 1;
    for (k = 0; k < npyr; ++k) s[k] = s_tab[k];
    return pf_vmf_scale_texel_t(&d, level, tx, ty, s, prior, t_out, vs_scratch,
                                (long long)(sizeof vs_scratch / sizeof(pf_real))) != PF_OK;
}

/* ---- one texel's samples, the effective BRDF's per-facet work hoisted (the bench's fit and T)
   vs_texel_samples(r, level, tx, ty, f_eff, f_lobes, stride, work) writes what
   pfi_vmf_scale_texel_samples (pf_vmf_scale.h) writes for a resolved description r, bit for bit
   (bench/microsurface.c compares them under MICROSURFACE_CHECK=1), with less work: the library
   evaluates pf_vmf_facet_specular for every facet of the patch and every one of the (2 nt
   (np - 1))^2 direction pairs, reading the facet's node slope and recomputing its two Smith
   Lambdas (an erfc each) per pair, although the slope depends on the facet only, the projected
   area a = w.z - s.w on (facet, direction) and the Lambda toward w on (facet, w) only, and the
   half vector, its Fresnel factor and the NDF's cut point on the pair only. Here the slopes,
   the areas and the Lambdas are computed once per facet and direction (2 nt (np - 1) n^2, not
   (2 nt (np - 1))^2 n^2), the pair's terms once per pair, and per facet and pair only the
   visibility, the cut and, for the facets it keeps, the NDF: the same functions on the same
   arguments in the same order (pf_vmf_facet_specular's expression F D / (4 (1 + lo + li)), the
   patch's area summed facet by facet in the same order), so every value is the library's.
   What pfi_vmf_scale_patch also computes and pfi_vmf_scale_texel_samples discards (the patch's
   own one-lobe fit and its f_lobes) is not computed. work: vs_samples_work(r, level) pf_reals. */
static inline long long vs_samples_work(const pf_vmf_scale_desc *r, int level)
{
    const long long n = 1LL << level, dirs = 2LL * r->nt * (r->np - 1);
    /* slope stats (as pf_reals), per direction: a and Lambda per facet, the area; the visibility bytes */
    const long long st = ((long long)sizeof(pf_slope_stats) * n * n + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real);
    return st + 2 * n * n + 2 * dirs * n * n + dirs + (dirs * n * n + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real);
}

static inline int vs_texel_samples(const pf_vmf_scale_desc *r, int level, long long tx, long long ty, pf_real *f_eff,
                                   pf_real *f_lobes, long long stride, pf_real *work)
{
    const long long n = 1LL << level, nn = n * n, A = 2LL * (r->np - 1), dirs = r->nt * A;
    const long long count = pf_vmf_scale_sample_count(r->nt, r->np), x0 = tx * n, y0 = ty * n;
    const long long stw = ((long long)sizeof(pf_slope_stats) * nn + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real);
    const pf_real bv = r->base_sigma * r->base_sigma, cut = PF_R(80.0) * bv;
    pf_slope_stats *st = (pf_slope_stats *)(void *)work;
    pf_real *sx = work + stw, *sy = sx + nn, *ad = sy + nn, *lam = ad + dirs * nn, *area = lam + dirs * nn;
    unsigned char *vis = (unsigned char *)(void *)(area + dirs);
    pf_real top = PF_R(0.0);
    long long d, q, s;
    int rc, k;
    /* pfi_vmf_scale_patch's checks (r is resolved and checked by the caller) */
    if (r->nt < 2 || r->np < 2 || !(r->theta_max > PF_R(0.0)) || !(r->theta_max < PF_R(0.5) * PF_PI) ||
        r->masking < PF_VMF_SCALE_G_GAUSSIAN || r->masking > PF_VMF_SCALE_UNMASKED)
        return PF_ERR_ARG;
    if (!(r->base_sigma > PF_R(0.0)) || !(r->base_sigma < PF_R(1.0e15))) return PF_ERR_ARG;
    rc = pfi_vmf_patch_sizes(r->heights, r->w, r->h, r->texel, n);
    if (rc != PF_OK) return rc;
    if (count == 0 || pf_vmf_scale_vis_bytes(r->nt, r->np, (int)n) == 0 || pf_size_mul(nn, 3) < 0) return PF_ERR_SIZE;
    rc = pfi_vmf_patch_top(r->heights, r->w, r->h, x0, y0, n, &top);
    if (rc != PF_OK) return rc;
    /* per facet: its node slope and slope statistics (pf_vmf_facet_specular's st) */
    for (q = 0; q < nn; ++q) {
        pf_map_node_slope(r->heights, r->w, r->h, r->texel, x0 + q % n, y0 + q / n, &sx[q], &sy[q]);
        st[q] = pf_slope_stats_make(sx[q], sy[q], bv, bv, PF_R(0.0));
    }
    /* per direction: the visibility map (the same marches), each facet's projected area a and
       Lambda (where a > 0: a pair with a <= 0 toward either direction is 0 before its Lambdas),
       and the patch's area, summed facet by facet as pfi_vmf_effective sums it */
    for (d = 0; d < dirs; ++d) {
        pf_vec3 w = pfi_vmf_scale_dir((int)(d / A), (int)(d % A), r->nt, r->np, r->theta_max);
        unsigned char *vm = vis + d * nn;
        pf_real *a = ad + d * nn, *l = lam + d * nn, sum = PF_R(0.0);
        for (q = 0; q < nn; ++q)
            vm[q] = (unsigned char)pf_map_visible(r->heights, r->w, r->h, r->texel, x0 + q % n, y0 + q / n, w, x0, y0, n, top);
        for (q = 0; q < nn; ++q) {
            a[q] = w.z - sx[q] * w.x - sy[q] * w.y;
            sum += a[q];
            l[q] = a[q] > PF_R(0.0) ? pf_vmf_lambda(pfi_vmf_excess_stats(PF_R(1.0), st[q], w), a[q]) : PF_R(0.0);
        }
        area[d] = sum;
    }
    for (s = 0; s < count; ++s) {
        const long long ai = s % A, ti = (s / A) % r->nt, ao = (s / (A * r->nt)) % A, to = s / (A * r->nt * A);
        const long long dO = to * A + ao, dI = ti * A + ai;
        const pf_vec3 wo = pfi_vmf_scale_dir((int)to, (int)ao, r->nt, r->np, r->theta_max);
        const pf_vec3 wi = pfi_vmf_scale_dir((int)ti, (int)ai, r->nt, r->np, r->theta_max);
        const unsigned char *vo = vis + dO * nn, *vi = vis + dI * nn;
        const pf_real *a_o = ad + dO * nn, *a_i = ad + dI * nn, *l_o = lam + dO * nn, *l_i = lam + dI * nn;
        pf_real num = PF_R(0.0);
        if (wo.z > PF_R(0.0) && wi.z > PF_R(0.0)) {
            const pf_vec3 hv = pfi_vmf_half(wo, wi);
            const pf_real hx = -hv.x / pf_max(hv.z, PF_R(1.0e-6)), hy = -hv.y / pf_max(hv.z, PF_R(1.0e-6));
            const pf_real F = pf_fresnel_schlick(r->f0, pf_vec3_dot(hv, wi));
            for (q = 0; q < nn; ++q) {
                /* the filters of pfi_vmf_effective and pf_vmf_facet_specular, the one that drops
                   most facets (the narrow lobe's cut) first: each only skips a facet */
                const pf_real ex = hx - sx[q], ey = hy - sy[q];
                pf_real term;
                if (ex * ex + ey * ey > cut) continue;
                if (!vo[q] || !vi[q]) continue;
                if (!(a_o[q] > PF_R(0.0)) || !(a_i[q] > PF_R(0.0))) continue;
                term = F * pfi_vmf_ndf_stats(PF_R(1.0), st[q], hv) / (PF_R(4.0) * (PF_R(1.0) + l_o[q] + l_i[q]));
                if (!(term > PF_R(0.0))) continue;
                num += term;
            }
        }
        f_eff[s] = area[dO] > PF_R(0.0) ? num / area[dO] : PF_R(0.0);
    }
    for (k = 0; k < r->pyramid_count; ++k) pfi_vmf_scale_texel_lobes(r, k, level, tx, ty, f_lobes + k * stride);
    return PF_OK;
}

#endif

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
   direction pairs; 16 training patches plus T for 64 texels take ~30 s (512^2 map, level 6).
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

#endif

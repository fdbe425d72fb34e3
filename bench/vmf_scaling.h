/* bench/vmf_scaling.h - the scaling function of pf_vmf.h (Wu et al. 2019 eqs. 12-14, sec. 6)
   built on a height map and its vMF lobe pyramids, as bench/microsurface.c and bench/pictures.c
   both use it (bench code, not the library: it allocates nothing but keeps static scratch).

   For one pyramid level (patches of n = 2^level texels a side, aligned on the n-grid):
     S   one VS_NT x VS_NT x VS_NP node table per lobe pyramid (theta_i, theta_o, phi_d; theta
         max VS_THETA_MAX), the rank-1 fit of pf_vmf_scale_factor (VS_ALS rounds, prior
         VS_SHRINK toward 1) over VS_TRAIN patches evenly spaced over the map (all of them when
         there are fewer), from each patch's samples: f_eff by pf_vmf_scale_patch (the
         in-footprint effective BRDF, eqs. 6-8, at every pair of the node directions) and
         f_lobes = the pyramid texel's own lobes shaded at the same pairs (vs_texel_spec);
     T   one value per texel of the level: pf_vmf_scale_t on the texel's own samples with the
         level's S and prior (the training patches' from the samples in hand).
   Shading: pf_vmf_scale_apply(T, pf_vmf_scale_lookup(S, ...), f) (docs/vmf.md).
   Cost: a 64 x 64 patch's samples march 4096 texels toward 48 directions and shade 2304
   direction pairs; 16 training patches plus T for 64 texels take ~30 s (512^2 map, level 6).
   Needs <math.h> before it. */
#ifndef PF_BENCH_VMF_SCALING_H
#define PF_BENCH_VMF_SCALING_H

#include "pf_vmf_fit.h"

#define VS_NT 6
#define VS_NP 5
#define VS_CELLS (VS_NT * VS_NT * VS_NP)
#define VS_SAMPLES ((2 * VS_NT * (VS_NP - 1)) * (2 * VS_NT * (VS_NP - 1)))
#define VS_THETA_MAX (75.0 * 3.14159265358979323846 / 180.0)
#define VS_TRAIN 16
#define VS_ALS 8
/* the fit's prior toward 1 (pf_vmf_scale_factor's shrink): 1, the mean patch's (cell's) own
   energy. Quick maps, in-footprint, vmf_m8_scaled at 4096 texels: prior 0.1 gave craters 0.057,
   gaussian 0.126, prior 1 0.068, 0.126; scaled at every level, 1 was the steadier below
   (gaussian, 256 texels: 1.02 with 0.1, 0.58 with 1, 0.15 unscaled) */
#define VS_SHRINK PF_R(1.0)
#define VS_MAX_SIDE 64 /* largest patch side the static scratch holds */
#define VS_MAX_PYR 2   /* lobe pyramids fitted together (they share f_eff) */

/* node direction (theta node it, azimuth k pi / (VS_NP - 1)) */
static pf_vec3 vs_dir(int it, int k)
{
    double th = it * VS_THETA_MAX / (VS_NT - 1), ph = k * 3.14159265358979323846 / (VS_NP - 1);
    return pf_vec3_make((pf_real)(sin(th) * cos(ph)), (pf_real)(sin(th) * sin(ph)), (pf_real)cos(th));
}

/* sample s's directions, in pf_vmf_scale_patch's order ((k_to A + a_o) nt + k_ti) A + a_i */
static void vs_sample_dirs(long s, pf_vec3 *wo, pf_vec3 *wi)
{
    const long A = 2 * (VS_NP - 1);
    long ai = s % A, ti = (s / A) % VS_NT, ao = (s / (A * VS_NT)) % A, to = s / (A * VS_NT * A);
    *wo = vs_dir((int)to, (int)ao);
    *wi = vs_dir((int)ti, (int)ai);
}

/* the specular of texel (tx, ty) of a level of an m-lobe pyramid, its lobes alone (the slope
   form with base_var added, Smith G of the mixture's moments: pf_vmf_sum_specular) */
static pf_real vs_texel_spec(const pf_real *pyr, int w, int h, int m, int level, long long tx, long long ty, pf_vec3 wo,
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

/* one patch's samples (texel (tx, ty) of `level`): f_eff and, for each of the npyr pyramids,
   f_lobes[k]; 0 on success */
static int vs_patch_samples(const pf_real *heights, int w, int h, int level, long long tx, long long ty, pf_real base_sigma,
                            pf_real f0, int npyr, const pf_real *const *pyrs, const int *ms, pf_real *f_eff,
                            pf_real *const *f_lobes)
{
    static pf_real nrm[3 * VS_MAX_SIDE * VS_MAX_SIDE], junk[VS_SAMPLES];
    static unsigned char vis[2 * VS_NT * (VS_NP - 1) * VS_MAX_SIDE * VS_MAX_SIDE];
    int n = 1 << level, k;
    long s;
    if (n > VS_MAX_SIDE || npyr > VS_MAX_PYR) return 1;
    if (pf_vmf_scale_patch(heights, w, h, PF_R(1.0), (int)(tx * n), (int)(ty * n), n, 1, 0, base_sigma, f0,
                           PF_VMF_SCALE_G_GAUSSIAN, VS_NT, VS_NP, (pf_real)VS_THETA_MAX, nrm, vis, f_eff, junk) != PF_OK)
        return 1;
    for (s = 0; s < VS_SAMPLES; ++s) {
        pf_vec3 wo, wi;
        vs_sample_dirs(s, &wo, &wi);
        for (k = 0; k < npyr; ++k)
            f_lobes[k][s] = vs_texel_spec(pyrs[k], w, h, ms[k], level, tx, ty, wo, wi, base_sigma * base_sigma, f0);
    }
    return 0;
}

/* S and the prior of each pyramid at `level` from VS_TRAIN evenly spaced patches; the training
   patches' T written into t_level[k] (one pf_real per texel of the level, row-major), the
   others left as they are. Returns the number of patches sampled, -1 on failure. */
static int vs_fit_level(const pf_real *heights, int w, int h, int level, pf_real base_sigma, pf_real f0, int npyr,
                        const pf_real *const *pyrs, const int *ms, pf_real s_out[][VS_CELLS], pf_real *prior,
                        pf_real *const *t_level)
{
    static pf_real f_eff[VS_TRAIN * VS_SAMPLES], f_l[VS_MAX_PYR][VS_TRAIN * VS_SAMPLES];
    static pf_real scratch[2 * VS_TRAIN * VS_CELLS], t[VS_TRAIN];
    int gw = w >> level, gh = h >> level, np, p, k;
    if (gw < 1 || gh < 1 || npyr > VS_MAX_PYR) return -1;
    np = gw * gh < VS_TRAIN ? gw * gh : VS_TRAIN;
    for (p = 0; p < np; ++p) {
        long long c = ((long long)p * gw * gh) / np;
        pf_real *fl[VS_MAX_PYR];
        for (k = 0; k < npyr; ++k) fl[k] = f_l[k] + (size_t)p * VS_SAMPLES;
        if (vs_patch_samples(heights, w, h, level, c % gw, c / gw, base_sigma, f0, npyr, pyrs, ms,
                             f_eff + (size_t)p * VS_SAMPLES, fl) != 0)
            return -1;
    }
    for (k = 0; k < npyr; ++k) {
        if (pf_vmf_scale_factor(f_eff, f_l[k], np, VS_NT, VS_NP, VS_ALS, VS_SHRINK, t, s_out[k], scratch, &prior[k], NULL) !=
            PF_OK)
            return -1;
        for (p = 0; p < np; ++p)
            t_level[k][((long long)p * gw * gh) / np] =
                pf_vmf_scale_t(f_eff + (size_t)p * VS_SAMPLES, f_l[k] + (size_t)p * VS_SAMPLES, VS_NT, VS_NP, s_out[k], prior[k]);
    }
    return np;
}

/* T of texel (tx, ty) of `level` for each pyramid, given the level's S and prior (vs_fit_level):
   written to t_out[k]; 0 on success */
static int vs_texel_t(const pf_real *heights, int w, int h, int level, long long tx, long long ty, pf_real base_sigma,
                      pf_real f0, int npyr, const pf_real *const *pyrs, const int *ms, pf_real s_tab[][VS_CELLS],
                      const pf_real *prior, pf_real *t_out)
{
    static pf_real f_eff[VS_SAMPLES], f_l[VS_MAX_PYR][VS_SAMPLES];
    pf_real *fl[VS_MAX_PYR];
    int k;
    if (npyr > VS_MAX_PYR) return 1;
    for (k = 0; k < npyr; ++k) fl[k] = f_l[k];
    if (vs_patch_samples(heights, w, h, level, tx, ty, base_sigma, f0, npyr, pyrs, ms, f_eff, fl) != 0) return 1;
    for (k = 0; k < npyr; ++k) t_out[k] = pf_vmf_scale_t(f_eff, f_l[k], VS_NT, VS_NP, s_tab[k], prior[k]);
    return 0;
}

#endif

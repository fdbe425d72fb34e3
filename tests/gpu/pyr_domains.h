/* pyr_domains.h - inputs of the GPU check drawn from real horizon and lobe pyramids
   (tests/gpu/vk_run.c, domains `hz(k)` and `vm(k)` in tests/gpu/domains.txt).

   Independent random fields are not what a shader fetches: an HDF of a real pyramid is often
   narrow (sigma_T of a few 1e-3 rad, so the elevation's rounding is amplified 1/sigma_T in
   pf_horizon_visible_area), its moments, slope statistics and view azimuth belong together,
   and a lobe pyramid's lobes are fitted to real normals. So the horizon and vMF evaluators
   are fed texels of pyramids built, as bench/microsurface.c builds them, from the seven
   corpus kinds of tests/reference/pf_microsurface.h (PYR_SIDE^2 texels, periodic):
     horizon  pf_horizon_pyramid (PYR_AZIMUTHS azimuths, PYR_STEPS steps, PF_HORIZON_MOMENTS)
              and pf_slope_pyramid_from_heights of the same heights;
     vMF      pf_vmf_pyramid_from_normals (PYR_LOBES lobes, PYR_VMF_ITER iterations) of the
              level-0 normals (-sx, -sy, 1)/|.|.
   One record per sample (pyr_draw): a kind, a level 0 .. top and a texel, uniformly; unit
   directions wo, wi with cos(zenith) uniform in [0.05, 1] and a uniform azimuth; the HDF
   moments at each direction's azimuth as a shader forms them (pf_horizon_azimuth_of, then
   pf_hdf_moments_lerp of the two stored azimuths); the texel's slope statistics
   (pf_slope_stats_from_moments); a facet slope of the footprint (a level-0 texel inside it);
   one of the texel's lobes and the pf_vmf_sum of the others (pf_vmf_sum_add and _add_masking,
   base sigma 0.1), as pf_vmf_sum_specular's caller builds it. Built in the C float build of the
   library (what a CPU would upload); about a second for the seven kinds. */
#ifndef PYR_DOMAINS_H
#define PYR_DOMAINS_H

#include "pf_horizon.h"
#include "pf_vmf_fit.h"
#include "../reference/pf_microsurface.h"

#define PYR_SIDE 128
#define PYR_AZIMUTHS 16
#define PYR_STEPS 64
#define PYR_LOBES 4
#define PYR_VMF_ITER 24
#define PYR_BASE_VAR 0.01

/* fields of a record, by index: hz(k) and vm(k) in domains.txt */
enum {
    HZ_WO_X, HZ_WO_Y, HZ_WO_Z, HZ_MO_M1, HZ_MO_M2, HZ_MO_MS, HZ_MEAN_X, HZ_MEAN_Y, HZ_VAR_X, HZ_VAR_Y,
    HZ_COV_XY, HZ_LOD, HZ_WI_X, HZ_WI_Y, HZ_WI_Z, HZ_MI_M1, HZ_MI_M2, HZ_MI_MS, HZ_SX, HZ_SY, HZ_E_O,
    HZ_COUNT
};
enum {
    VM_WO_X, VM_WO_Y, VM_WO_Z, VM_WI_X, VM_WI_Y, VM_WI_Z, VM_L_AMP, VM_L_MU_X, VM_L_MU_Y, VM_L_MU_Z,
    VM_L_KAPPA, VM_S_AMP, VM_S_NDF, VM_S_EX, VM_S_EY, VM_S_EXX, VM_S_EYY, VM_S_EXY, VM_S_EXCESS_O,
    VM_S_EXCESS_I, VM_SX, VM_SY, VM_COUNT
};

typedef struct {
    pf_real *hz[PFM_KIND_COUNT];    /* horizon pyramids */
    pf_real *sl[PFM_KIND_COUNT];    /* slope pyramids, 5 moments */
    pf_real *vm[PFM_KIND_COUNT];    /* lobe pyramids, 4 PYR_LOBES per texel */
    int levels, built_hz, built_vm;
} pyr_set;

static pyr_set pyr;
static double pyr_hz_rec[HZ_COUNT], pyr_vm_rec[VM_COUNT];

static int pyr_build(int want_hz, int want_vm)
{
    int k, C = pf_horizon_channels(PF_HORIZON_MOMENTS, PYR_AZIMUTHS, 0);
    long long nt = pf_mip_texel_count(PYR_SIDE, PYR_SIDE), t;
    pyr.levels = pf_mip_level_count(PYR_SIDE, PYR_SIDE);
    for (k = 0; k < PFM_KIND_COUNT; ++k) {
        pfm_surface s;
        pf_real *h = (pf_real *)malloc(sizeof(pf_real) * PYR_SIDE * PYR_SIDE), *nr;
        if (!h || pfm_surface_make(&s, PYR_SIDE, PYR_SIDE, 1.0, pfm_params_default(k)) != 0) return 0;
        for (t = 0; t < (long long)PYR_SIDE * PYR_SIDE; ++t) h[t] = (pf_real)s.height[t];
        pfm_surface_free(&s);
        pyr.sl[k] = (pf_real *)malloc(sizeof(pf_real) * (size_t)nt * 5u);
        if (!pyr.sl[k] || pf_slope_pyramid_from_heights(h, PYR_SIDE, PYR_SIDE, PF_R(1.0), PF_R(1.0), PF_R(1.0),
                                                         PF_BORDER_WRAP, pyr.sl[k]) != PF_OK) return 0;
        if (want_hz && !pyr.hz[k]) {
            pyr.hz[k] = (pf_real *)malloc(sizeof(pf_real) * (size_t)nt * (size_t)C);
            if (!pyr.hz[k] || pf_horizon_pyramid(h, PYR_SIDE, PYR_SIDE, PF_R(1.0), PYR_AZIMUTHS, PYR_STEPS, PF_BORDER_WRAP,
                                                 PF_HORIZON_MOMENTS, 0, pyr.hz[k]) != PF_OK) return 0;
        }
        if (want_vm && !pyr.vm[k]) {
            nr = (pf_real *)malloc(sizeof(pf_real) * PYR_SIDE * PYR_SIDE * 3);
            pyr.vm[k] = (pf_real *)malloc(sizeof(pf_real) * (size_t)pf_vmf_pyramid_texel_count(PYR_SIDE, PYR_SIDE) * 4u * PYR_LOBES);
            if (!nr || !pyr.vm[k]) return 0;
            for (t = 0; t < (long long)PYR_SIDE * PYR_SIDE; ++t) {
                pf_vec3 m = pf_vec3_normalize(pf_vec3_make(-pyr.sl[k][5 * t], -pyr.sl[k][5 * t + 1], PF_R(1.0)));
                nr[3 * t] = m.x;
                nr[3 * t + 1] = m.y;
                nr[3 * t + 2] = m.z;
            }
            if (pf_vmf_pyramid_from_normals(nr, NULL, PYR_SIDE, PYR_SIDE, PYR_LOBES, PYR_VMF_ITER, pyr.vm[k]) != PF_OK) return 0;
            free(nr);
        }
        free(h);
    }
    if (want_hz) pyr.built_hz = 1;
    if (want_vm) pyr.built_vm = 1;
    return 1;
}

/* a unit direction above the surface: cos(zenith) uniform in [0.05, 1], azimuth uniform */
static pf_vec3 pyr_dir(double (*rnd)(void))
{
    double c = 0.05 + 0.95 * rnd(), s = sqrt(1.0 - c * c), p = 6.283185307179586 * rnd();
    return pf_vec3_make((pf_real)(s * cos(p)), (pf_real)(s * sin(p)), (pf_real)c);
}

static pf_hdf_moments pyr_hdf(const pf_real *tx, pf_vec3 w)
{
    pf_horizon_azimuth a = pf_horizon_azimuth_of(w, PYR_AZIMUTHS);
    const pf_real *p = tx + 3 * a.i0, *q = tx + 3 * a.i1;
    return pf_hdf_moments_lerp(pf_hdf_moments_make(p[0], p[1], p[2]), pf_hdf_moments_make(q[0], q[1], q[2]), a.f);
}

/* one lobe added as a shader adds it: pf_vmf_sum_add, then pf_vmf_sum_add_masking */
static pf_vmf_sum pyr_add(pf_vmf_sum s, pf_vmf_lobe l, pf_vec3 wo, pf_vec3 wi)
{
    s = pf_vmf_sum_add(s, l, wo, wi, PF_R(PYR_BASE_VAR));
    return pf_vmf_sum_add_masking(s, l, wo, wi, PF_R(PYR_BASE_VAR));
}

/* a new record for the next sample; rnd is vk_run's seeded generator */
static void pyr_draw(double (*rnd)(void))
{
    int kind = (int)(rnd() * PFM_KIND_COUNT), level = (int)(rnd() * pyr.levels), side, i, j, n, fi, fj;
    long long off, t, t0;
    pf_vec3 wo = pyr_dir(rnd), wi = pyr_dir(rnd);
    int pick = (int)(rnd() * PYR_LOBES); /* drawn always: the record's other fields do not depend
                                            on which pyramids the run built */
    pf_slope_stats st;
    const pf_real *sl;
    if (kind >= PFM_KIND_COUNT) kind = PFM_KIND_COUNT - 1;
    if (level >= pyr.levels) level = pyr.levels - 1;
    side = PYR_SIDE >> level;
    i = (int)(rnd() * side);
    j = (int)(rnd() * side);
    off = pf_mip_level_offset(PYR_SIDE, PYR_SIDE, level);
    t = off + (long long)j * side + i;
    sl = pyr.sl[kind] + 5 * t;
    st = pf_slope_stats_from_moments(sl[0], sl[1], sl[2], sl[3], sl[4]);
    /* a facet of the footprint: a level-0 texel inside it */
    n = 1 << level;
    fi = i * n + (int)(rnd() * n);
    fj = j * n + (int)(rnd() * n);
    t0 = (long long)fj * PYR_SIDE + fi;
    if (pyr.built_hz) {
        int C = pf_horizon_channels(PF_HORIZON_MOMENTS, PYR_AZIMUTHS, 0);
        const pf_real *tx = pyr.hz[kind] + (size_t)C * (size_t)t;
        pf_hdf_moments mo = pyr_hdf(tx, wo), mi = pyr_hdf(tx, wi);
        double *r = pyr_hz_rec;
        r[HZ_WO_X] = wo.x; r[HZ_WO_Y] = wo.y; r[HZ_WO_Z] = wo.z;
        r[HZ_WI_X] = wi.x; r[HZ_WI_Y] = wi.y; r[HZ_WI_Z] = wi.z;
        r[HZ_MO_M1] = mo.m1; r[HZ_MO_M2] = mo.m2; r[HZ_MO_MS] = mo.ms;
        r[HZ_MI_M1] = mi.m1; r[HZ_MI_M2] = mi.m2; r[HZ_MI_MS] = mi.ms;
        r[HZ_MEAN_X] = st.mean_x; r[HZ_MEAN_Y] = st.mean_y;
        r[HZ_VAR_X] = st.var_x; r[HZ_VAR_Y] = st.var_y; r[HZ_COV_XY] = st.cov_xy;
        r[HZ_LOD] = level;
        r[HZ_SX] = pyr.sl[kind][5 * t0]; r[HZ_SY] = pyr.sl[kind][5 * t0 + 1];
        r[HZ_E_O] = pf_horizon_elevation(wo);
    }
    if (pyr.built_vm) {
        const pf_real *lb = pyr.vm[kind] + (size_t)4 * PYR_LOBES * (size_t)t;
        int q;
        pf_vmf_sum s = pf_vmf_sum_zero();
        pf_vmf_lobe l;
        double *r = pyr_vm_rec;
        if (pick >= PYR_LOBES) pick = PYR_LOBES - 1;
        /* the picked lobe must be live (a fit that returned fewer lobes pads with amp 0) */
        while (pick > 0 && !(lb[4 * pick + 3] > PF_R(0.0))) pick--;
        for (q = 0; q < PYR_LOBES; ++q)
            if (q != pick && lb[4 * q + 3] > PF_R(0.0))
                s = pyr_add(s, pf_vmf_lobe_make(lb[4 * q + 3], lb[4 * q], lb[4 * q + 1], lb[4 * q + 2]), wo, wi);
        l = pf_vmf_lobe_make(lb[4 * pick + 3], lb[4 * pick], lb[4 * pick + 1], lb[4 * pick + 2]);
        r[VM_WO_X] = wo.x; r[VM_WO_Y] = wo.y; r[VM_WO_Z] = wo.z;
        r[VM_WI_X] = wi.x; r[VM_WI_Y] = wi.y; r[VM_WI_Z] = wi.z;
        r[VM_L_AMP] = l.amp; r[VM_L_MU_X] = l.mu.x; r[VM_L_MU_Y] = l.mu.y; r[VM_L_MU_Z] = l.mu.z; r[VM_L_KAPPA] = l.kappa;
        /* the whole texel's sum for the sum evaluators: the picked lobe added last */
        s = pyr_add(s, l, wo, wi);
        r[VM_S_AMP] = s.amp; r[VM_S_NDF] = s.ndf; r[VM_S_EX] = s.ex; r[VM_S_EY] = s.ey; r[VM_S_EXX] = s.exx;
        r[VM_S_EYY] = s.eyy; r[VM_S_EXY] = s.exy; r[VM_S_EXCESS_O] = s.excess_o; r[VM_S_EXCESS_I] = s.excess_i;
        r[VM_SX] = pyr.sl[kind][5 * t0]; r[VM_SY] = pyr.sl[kind][5 * t0 + 1];
    }
}

#endif /* PYR_DOMAINS_H */

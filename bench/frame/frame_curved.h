/* frame_curved.h - the curved scenes of bench/specaa_scenes.h (an orthographic sphere and
   cylinder, 16 and 40 px across (24 in BENCH_QUICK), plain or normal-mapped, base alpha 0.03 and
   0.1, a sub-pixel camera path) rendered by the GPU frame: bench/frame/curved.frag ray-casts them
   analytically and shades every pixel with the specular AA forms of pf_specaa.h
   (bench/frame/curved_shade.h: LEADR alone, with the box geometry kernel (anisotropic and the
   isotropic pf_specaa_leadr_specular), with the engines' kernels (Tokuyoshi & Kaplanyan 2019,
   Filament, HDRP, Godot), one vMF lobe with the kernel, and the curved forms: the mean shift (6)
   (pf_specaa_leadr_specular_curved), (5) from dFdx of the position, the cross term (4) from dFdx
   of the read's mean, pf_specaa_slope_stats_quad's four quadrant reads), the geometry kernel from
   the hardware dFdx/dFdy of the macro-normal, the texture part from the map's moment pyramid as
   R32G32B32A32_SFLOAT textures: one trilinear read at the lod computed in the shader, or
   anisotropic reads (the EXT rule in the shader, or the driver's 16x sampler), and one row at the
   driver's lod (fc_key below).
   Included once by bench/frame/frame.c (its Vulkan helpers); bench code.

   WHAT IS MEASURED, per scene row (scene, size, alpha) and form, over the pixels whose centre is
   on the surface (specaa_scenes.h's rule) in every frame:
     err      RMS over pixels and frames of (GPU - reference) / the mean reference, and its ratio
              to the oracle's (specaa_scenes.h's: the same metric as bench/specaa.c's table).
              Reference and oracle are specaa_scenes.h's own (sc_run_ref, included, not copied): S x S
              stratified rays per pixel each shading its own texel, and one Gaussian lobe of
              those rays' exact slope mean and covariance.
     flk      RMS frame-to-frame change per pixel / the reference's own (the same path).
     vs CPU   RMS (GPU - CPU) / mean CPU: the CPU float path is curved_shade.h's fc_shade, the
              same function, fed by the analytic geometry at the quad's four pixel centres
              (dFdxFine = right - left of the pixel's quad row, dFdyFine = bottom - top of its
              column: what the hardware differences), pf_slope_moments_sample and
              pf_normal_avg_sample at lod log2(max |d(s,t)/dx|, |d(s,t)/dy|) (the anisotropic
              rows: sc_fetch_aniso). Where the shader computes the same lod (or taps) it measures
              the driver's filtering, derivatives and float arithmetic; on the driver-lod and
              driver-16x rows, the driver's lod and anisotropic filter against the formula's.
     exact d  the CPU path's error with the exact (central-difference, as bench/specaa.c)
              derivatives and the read's mean differenced at +-1/2 px: what the 1-px quad
              differences cost.
     non-finite  NaN or infinite GPU pixels over the whole rendered images. */
#include "pf_specaa.h"
#define SC_RUN_REF 1 /* specaa_scenes.h's sc_run_ref */
#include "specaa_scenes.h"
#include "curved_shade.h"

/* the rows: every form of curved_shade.h with the lod computed in the shader (textureLod at
   log2 of the longer texel derivative, the CPU path's formula, so "vs CPU" checks the shader),
   and the box kernel again through the driver's lod (textureGrad): the driver's lod
   approximation apart. The box kernel's keys are the CSV's earlier ones (bench/report.sh reads
   them): "box" through the driver's lod, "box_lod" at the shader's. */
#define FC_ROWS (FC_COUNT + 3)
#define FC_ROW_DRV (FC_ROWS - 1)
static const char *const fc_key[FC_ROWS] = {"none", "box_lod", "box_iso", "tk", "filament", "hdrp", "godot", "vmf_box",
                                            "curved", "surf", "cross", "quad", "cross_taps", "quad_drv16", "box"};
static const int fc_form[FC_ROWS] = {FC_NONE, FC_BOX, FC_BOX_ISO, FC_TK, FC_FILAMENT, FC_HDRP, FC_GODOT, FC_VMF_BOX,
                                     FC_CURVED, FC_SURF, FC_CROSS, FC_QUAD, FC_CROSS, FC_QUAD, FC_BOX};
/* the rows with anisotropic reads: 1, in the shader by EXT_texture_filter_anisotropic's rule
   (curved.frag's aniso, the CPU path's specaa_scenes.h's sc_fetch_aniso); 2, through the
   driver's sampler at maxAnisotropy 16 (textureGrad; the CPU path still the EXT rule, so its
   "vs CPU" is the driver's anisotropic filter against the specification's) */
static const int fc_af[FC_ROWS] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 2, 0};
static const int fc_sm[FC_ROWS] = {SM_NONE, SM_BOX, SM_BOX_ISO, SM_TK, SM_FILAMENT, SM_HDRP, SM_GODOT, SM_VMF_BOX,
                                   SM_BOX_SHIFT, SM_BOX_SHIFT_SURF, -1, SM_QUAD_SHIFT, -1, SM_QUAD_SHIFT, SM_BOX};
static const char *fc_name(int r)
{
    if (r == FC_ROW_DRV) return "LEADR + box kernel (aniso), the driver's lod (textureGrad)";
    if (r == 10) return "LEADR + box kernel (aniso) + cross term (4) from dFdx/dFdy of the read's mean + mean shift (6)";
    if (r == 12) return "LEADR (one aniso read) + box kernel + cross term (4) from dFdx/dFdy of the read's mean + mean shift (6)";
    if (r == 13) return "the same 4 quadrant reads through the driver's 16x anisotropic sampler (textureGrad)";
    return sc_meth_name[fc_sm[r]];
}

/* specaa_scenes.h's surface at image point (x, y) (sc_eval); off the surface the point moves
   radially to 0.999 R first, as curved.frag's geo: returns 1 on the surface */
static int fc_eval(int scene, double R, double cx, double cy, double x, double y, sc_geo *g)
{
    double dx = (x - cx) / R, dy = (y - cy) / R;
    if (sc_eval(scene, R, cx, cy, x, y, g)) return 1;
    if (scene < 2) {
        double k = 0.999 / sqrt(dx * dx + dy * dy);
        dx *= k, dy *= k;
    } else
        dx = dx > 0.0 ? 0.999 : -0.999;
    sc_eval(scene, R, cx, cy, cx + dx * R, cy + dy * R, g);
    return 0;
}

static pf_vec3 fc_v3(const double *v) { return pf_vec3_make((pf_real)v[0], (pf_real)v[1], (pf_real)v[2]); }

/* the inputs of fc_shade at one pixel */
typedef struct {
    pf_vec3 wo, wi, dnx, dny, ax, ay, jx, jy, nav;
    pf_vec2 dmx, dmy, dmx_af, dmy_af;   /* the read's mean differences: trilinear, anisotropic */
    pf_slope_moments mm, af, q[4];      /* the trilinear read, the anisotropic read, the quadrant reads */
} fc_in;

static pf_vec3 fc_frame(const double *v, const sc_geo *g)
{
    return pf_vec3_make((pf_real)sc_dot(v, g->T), (pf_real)sc_dot(v, g->B), (pf_real)sc_dot(v, g->N));
}

/* the pyramid read at texel (s, t) and lod log2 rho (0 below 1): moments and averaged normal */
static pf_slope_moments fc_read(double s, double t, double rho, pf_vec3 *nav)
{
    pf_real lod = (pf_real)(rho > 1.0 ? log2(rho) : 0.0), us = (pf_real)(s / SC_N), vs = (pf_real)(t / SC_N);
    if (nav) *nav = pf_normal_avg_sample(sc_npyr, SC_N, SC_N, lod, us, vs, PF_BORDER_WRAP);
    return pf_slope_moments_sample(sc_pyr, SC_N, SC_N, lod, us, vs, PF_BORDER_WRAP);
}

/* the quad's texel derivatives at pixel (px, py): dFdxFine from its quad row, dFdyFine from its
   quad column */
static void fc_quad_dst(int scene, double R, double cx, double cy, int px, int py, double dst[2][2])
{
    int x0 = px & ~1, y0 = py & ~1;
    sc_geo a, b, c, d;
    fc_eval(scene, R, cx, cy, x0 + 0.5, py + 0.5, &a);
    fc_eval(scene, R, cx, cy, x0 + 1.5, py + 0.5, &b);
    fc_eval(scene, R, cx, cy, px + 0.5, y0 + 0.5, &c);
    fc_eval(scene, R, cx, cy, px + 0.5, y0 + 1.5, &d);
    dst[0][0] = b.s - a.s, dst[0][1] = b.t - a.t, dst[1][0] = d.s - c.s, dst[1][1] = d.t - c.t;
}

/* the longer of the two (the shader's lod is its log2) */
static double fc_quad_rho(int scene, double R, double cx, double cy, int px, int py)
{
    double dst[2][2];
    fc_quad_dst(scene, R, cx, cy, px, py, dst);
    return fmax(hypot(dst[0][0], dst[0][1]), hypot(dst[1][0], dst[1][1]));
}

/* the anisotropic read at pixel (px, py) with its own quad derivatives */
static pf_slope_moments fc_quad_read_af(int scene, double R, double cx, double cy, int px, int py)
{
    sc_geo g;
    double dst[2][2];
    fc_eval(scene, R, cx, cy, px + 0.5, py + 0.5, &g);
    fc_quad_dst(scene, R, cx, cy, px, py, dst);
    return sc_fetch_aniso(g.s, g.t, dst, 0, 0, 1.0);
}

/* the read at pixel (px, py) at its own shader lod, as that lane of the quad reads */
static pf_slope_moments fc_quad_read(int scene, double R, double cx, double cy, int px, int py)
{
    sc_geo g;
    fc_eval(scene, R, cx, cy, px + 0.5, py + 0.5, &g);
    return fc_read(g.s, g.t, fc_quad_rho(scene, R, cx, cy, px, py), NULL);
}

/* fc_shade's inputs at pixel (px, py) of job (sc_run's numbering): exact = 0, the quad's
   differences as the hardware takes them (dFdxFine = right - left of the pixel's quad row,
   dFdyFine = bottom - top of its column, each neighbour's read at its own lod); exact = 1,
   specaa_scenes.h's central differences (h = 1e-4 px) and the read's mean differenced at +-1/2 px
   (at the centre's lod). g: the pixel's surface point. */
static void fc_inputs(long long job, int px, int py, int exact, fc_in *in, sc_geo *g)
{
    int ai = (int)(job / sc_F % SC_NALPHA), si = (int)(job / (sc_F * SC_NALPHA) % SC_NSIZE), fr = (int)(job % sc_F);
    int scene = (int)(job / ((long long)sc_F * SC_NALPHA * SC_NSIZE)), W = sc_W[si], x0 = px & ~1, y0 = py & ~1, i, d;
    double R = 0.5 * sc_diam[si], cx = 0.5 * W + 0.13 + (double)fr / sc_F, cy = 0.5 * W + 0.41 + 0.37 * fr / sc_F;
    double dn[2][3], dst[2][2], rho, dp[2][3];
    const double *L = sc_wi_all[scene >= 2];
    (void)ai;
    fc_eval(scene, R, cx, cy, px + 0.5, py + 0.5, g);
    if (!exact) {
        sc_geo q[4];
        fc_eval(scene, R, cx, cy, x0 + 0.5, py + 0.5, &q[0]);
        fc_eval(scene, R, cx, cy, x0 + 1.5, py + 0.5, &q[1]);
        fc_eval(scene, R, cx, cy, px + 0.5, y0 + 0.5, &q[2]);
        fc_eval(scene, R, cx, cy, px + 0.5, y0 + 1.5, &q[3]);
        for (i = 0; i < 3; ++i) dn[0][i] = q[1].N[i] - q[0].N[i], dn[1][i] = q[3].N[i] - q[2].N[i];
        dst[0][0] = q[1].s - q[0].s, dst[0][1] = q[1].t - q[0].t, dst[1][0] = q[3].s - q[2].s, dst[1][1] = q[3].t - q[2].t;
    } else {
        const double h = 1e-4;
        for (d = 0; d < 2; ++d) {
            sc_geo gp, gm;
            int okp = sc_eval(scene, R, cx, cy, px + 0.5 + (d == 0 ? h : 0), py + 0.5 + (d == 1 ? h : 0), &gp);
            int okm = sc_eval(scene, R, cx, cy, px + 0.5 - (d == 0 ? h : 0), py + 0.5 - (d == 1 ? h : 0), &gm);
            double den = (okp && okm) ? 2.0 * h : h;
            const sc_geo *A = okp ? &gp : g, *Bm = okm ? &gm : g;
            for (i = 0; i < 3; ++i) dn[d][i] = (A->N[i] - Bm->N[i]) / den;
            dst[d][0] = (A->s - Bm->s) / den;
            dst[d][1] = (A->t - Bm->t) / den;
        }
    }
    rho = fmax(hypot(dst[0][0], dst[0][1]), hypot(dst[1][0], dst[1][1]));
    in->mm = pf_slope_moments_make(0, 0, 0, 0, 0);
    in->nav = pf_vec3_make(0, 0, 1);
    in->dmx = in->dmy = in->dmx_af = in->dmy_af = pf_vec2_make(0, 0);
    in->af = in->q[0] = in->q[1] = in->q[2] = in->q[3] = in->mm;
    if (scene & 1) {
        pf_slope_moments a, b, c, e;
        in->mm = fc_read(g->s, g->t, rho, &in->nav);
        if (!exact) {
            a = fc_quad_read(scene, R, cx, cy, x0, py), b = fc_quad_read(scene, R, cx, cy, x0 + 1, py);
            c = fc_quad_read(scene, R, cx, cy, px, y0), e = fc_quad_read(scene, R, cx, cy, px, y0 + 1);
        } else {
            a = fc_read(g->s - 0.5 * dst[0][0], g->t - 0.5 * dst[0][1], rho, NULL), b = fc_read(g->s + 0.5 * dst[0][0], g->t + 0.5 * dst[0][1], rho, NULL);
            c = fc_read(g->s - 0.5 * dst[1][0], g->t - 0.5 * dst[1][1], rho, NULL), e = fc_read(g->s + 0.5 * dst[1][0], g->t + 0.5 * dst[1][1], rho, NULL);
        }
        in->dmx = pf_vec2_make(b.ex - a.ex, b.ey - a.ey);
        in->dmy = pf_vec2_make(e.ex - c.ex, e.ey - c.ey);
        /* the anisotropic reads (specaa_scenes.h's sc_run: the same offsets) */
        in->af = sc_fetch_aniso(g->s, g->t, dst, 0, 0, 1.0);
        for (i = 0; i < 4; ++i) in->q[i] = sc_fetch_aniso(g->s, g->t, dst, (i & 1) ? 0.25 : -0.25, (i >> 1) ? 0.25 : -0.25, 0.5);
        if (!exact) {
            a = fc_quad_read_af(scene, R, cx, cy, x0, py), b = fc_quad_read_af(scene, R, cx, cy, x0 + 1, py);
            c = fc_quad_read_af(scene, R, cx, cy, px, y0), e = fc_quad_read_af(scene, R, cx, cy, px, y0 + 1);
        } else {
            a = sc_fetch_aniso(g->s, g->t, dst, -0.5, 0, 1.0), b = sc_fetch_aniso(g->s, g->t, dst, 0.5, 0, 1.0);
            c = sc_fetch_aniso(g->s, g->t, dst, 0, -0.5, 1.0), e = sc_fetch_aniso(g->s, g->t, dst, 0, 0.5, 1.0);
        }
        in->dmx_af = pf_vec2_make(b.ex - a.ex, b.ey - a.ey);
        in->dmy_af = pf_vec2_make(e.ex - c.ex, e.ey - c.ey);
    }
    /* P = (x, y, R n_z) in pixels (orthographic): curved.frag's P */
    dp[0][0] = 1.0, dp[0][1] = 0.0, dp[0][2] = R * dn[0][2];
    dp[1][0] = 0.0, dp[1][1] = 1.0, dp[1][2] = R * dn[1][2];
    in->wo = pf_vec3_make((pf_real)g->T[2], (pf_real)g->B[2], (pf_real)g->N[2]);
    in->wi = fc_frame(L, g);
    in->dnx = fc_v3(dn[0]), in->dny = fc_v3(dn[1]);
    in->ax = fc_frame(dn[0], g), in->ay = fc_frame(dn[1], g);
    in->jx = fc_frame(dp[0], g), in->jy = fc_frame(dp[1], g);
}

static double fc_cpu(int row, const fc_in *in, double bv)
{
    if (fc_form[row] == FC_QUAD) return (double)fc_shade_quad(in->wo, in->wi, in->q[0], in->q[1], in->q[2], in->q[3], (pf_real)bv, in->ax, in->ay);
    if (fc_af[row])
        return (double)fc_shade(fc_form[row], in->wo, in->wi, in->af, in->nav, (pf_real)bv, in->dnx, in->dny, in->ax, in->ay, in->jx,
                                in->jy, in->dmx_af, in->dmy_af);
    return (double)fc_shade(fc_form[row], in->wo, in->wi, in->mm, in->nav, (pf_real)bv, in->dnx, in->dny, in->ax, in->ay, in->jx, in->jy,
                            in->dmx, in->dmy);
}

typedef struct {
    double *cpu; /* [FC_ROWS][job][stride]: the CPU path at the pixels of the reference, NaN elsewhere */
    double *cpx; /* the same with the exact derivatives */
    long long stride;
} fc_cpu_job;

static void fc_cpu_item(void *ctx, long long job)
{
    fc_cpu_job *c = (fc_cpu_job *)ctx;
    int si = (int)(job / (sc_F * SC_NALPHA) % SC_NSIZE), ai = (int)(job / sc_F % SC_NALPHA), W = sc_W[si], m, px, py;
    double bv = 0.5 * sc_alpha[ai] * sc_alpha[ai];
    const double *ref = sc_img + job * sc_img_stride + (long long)SM_REF * W * W;
    for (py = 0; py < W; ++py)
        for (px = 0; px < W; ++px) {
            long long p = (long long)py * W + px;
            fc_in q, x;
            sc_geo g;
            if (!isnan(ref[p])) fc_inputs(job, px, py, 0, &q, &g), fc_inputs(job, px, py, 1, &x, &g);
            for (m = 0; m < FC_ROWS; ++m) {
                long long o = ((long long)m * sc_njobs() + job) * c->stride + p;
                c->cpu[o] = isnan(ref[p]) ? (double)NAN : fc_cpu(m, &q, bv);
                c->cpx[o] = isnan(ref[p]) ? (double)NAN : fc_cpu(m, &x, bv);
            }
        }
}

typedef struct {
    double err, err_exact, err_cpu, orc, flk, vs_cpu, vs_cpu_max;
    int nonfinite, mismatch;
} fc_stat;

/* Renders the curved scenes on the device (vk, set up by main), writes their table to md (the
   report's frame section), OUT_DIR/gpuspecaa.md (docs/specaa.md's generated block) and
   OUT_DIR/frame_curved.csv. probe .. hdf: the main scenes' textures, for the set's unread
   bindings. Returns 0, or 1 on a missing shader or file. */
static int fc_bench(const char *spv, const char *outdir, const char *ops_file, int quick, FILE *md, const fr_tex *probe,
                    const fr_tex *v4, const fr_tex *v8, const fr_tex *hdf)
{
    int si, scene, ai, m, fr, levels = pf_mip_level_count(SC_N, SC_N), Wm, k, ops[FC_ROWS], br[FC_ROWS], row, nms[FC_ROWS];
    long long njob, nt = pf_mip_texel_count(SC_N, SC_N), job, stride;
    double t0 = now_seconds(), c0 = thread_cpu_seconds(), t_ref, t_gpu, t_cpu, ms[FC_ROWS];
    float *ta, *tb, *gpu;
    double *cpu, *cpx;
    fr_tex tex[2];
    VkSampler samp, samp_af;
    VkDescriptorPool pool;
    VkDescriptorSet set, set_af;
    fr_target tg;
    char path[1024], vert[1024];
    static fc_stat stat[SC_NSCENE * SC_NSIZE * SC_NALPHA][FC_ROWS];
    FILE *csv, *gm;
    fc_cpu_job cj;
    (void)sc_bench; /* specaa.c's table: not this step's */
    /* specaa_scenes.h's settings, as sc_bench sets them, and its images (reference, oracle, its
       CPU rows with exact derivatives) for every job */
    if (quick) { sc_S = 8; sc_F = 6; sc_diam[1] = 24.0; }
    sc_build_map();
    for (si = 0; si < SC_NSIZE; ++si) sc_W[si] = (int)sc_diam[si] + 5;
    Wm = sc_W[SC_NSIZE - 1];
    stride = sc_dev_stride = (long long)Wm * Wm;
    sc_img_stride = SM_COUNT * sc_dev_stride;
    njob = sc_njobs();
    sc_img = (double *)pfb_xmalloc(sizeof(double) * (size_t)(njob * sc_img_stride));
    sc_dev2 = (double *)pfb_xmalloc(sizeof(double) * (size_t)(njob * sc_dev_stride));
    sc_full = (unsigned char *)pfb_xmalloc((size_t)(njob * sc_dev_stride));
    pfb_parallel_for(njob, sc_run_ref, NULL, "frame: curved scenes, specaa_scenes.h's reference");
    t_ref = now_seconds() - t0;

    /* the map as GPU textures */
    t0 = now_seconds();
    ta = (float *)pfb_xmalloc(sizeof(float) * 4 * (size_t)nt);
    tb = (float *)pfb_xmalloc(sizeof(float) * 4 * (size_t)nt);
    for (k = 0; k < nt; ++k) {
        ta[4 * k] = sc_pyr[5 * k], ta[4 * k + 1] = sc_pyr[5 * k + 1], ta[4 * k + 2] = sc_pyr[5 * k + 2], ta[4 * k + 3] = sc_pyr[5 * k + 3];
        tb[4 * k] = sc_pyr[5 * k + 4], tb[4 * k + 1] = sc_npyr[3 * k], tb[4 * k + 2] = sc_npyr[3 * k + 1], tb[4 * k + 3] = sc_npyr[3 * k + 2];
    }
    tex[0] = upload_texture(ta, SC_N, SC_N, levels, VK_FORMAT_R32G32B32A32_SFLOAT);
    tex[1] = upload_texture(tb, SC_N, SC_N, levels, VK_FORMAT_R32G32B32A32_SFLOAT);
    samp = make_sampler(1.0f, levels);
    /* the anisotropic rows' sampler: 16 where the device has the feature (frame.c enables it) */
    samp_af = make_sampler(vk.features.samplerAnisotropy ? fminf(16.0f, vk.props.limits.maxSamplerAnisotropy) : 1.0f, levels);
    {   /* frame.c's set layout: the map in bindings 0 and 1; the others (unread by curved.frag) bound
           to the main scenes' textures so that every binding is valid */
        VkDescriptorPoolSize ps[2];
        VkDescriptorPoolCreateInfo dpci;
        ps[0].type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        ps[0].descriptorCount = 12;
        ps[1].type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        ps[1].descriptorCount = 2;
        memset(&dpci, 0, sizeof dpci);
        dpci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        dpci.maxSets = 2;
        dpci.poolSizeCount = 2;
        dpci.pPoolSizes = ps;
        VKC(vkCreateDescriptorPool(vk.dev, &dpci, NULL, &pool));
        set = make_set(pool, &tex[0], &tex[1], probe, v4, v8, hdf, samp);
        set_af = make_set(pool, &tex[0], &tex[1], probe, v4, v8, hdf, samp_af);
    }

    /* every form, every job, one Wm x Wm frame each (the smaller size uses its top-left W x W) */
    gpu = (float *)pfb_xmalloc(sizeof(float) * (size_t)(FC_ROWS * njob * stride));
    cpu = (double *)pfb_xmalloc(sizeof(double) * (size_t)(FC_ROWS * njob * stride));
    cpx = (double *)pfb_xmalloc(sizeof(double) * (size_t)(FC_ROWS * njob * stride));
    tg = make_target(Wm, Wm);
    snprintf(vert, sizeof vert, "%s/frame.vert.spv", spv);
    memset(stat, 0, sizeof stat);
    for (m = 0; m < FC_ROWS; ++m) {
        VkPipeline pipe;
        snprintf(path, sizeof path, "%s/curved_%s.spv", spv, fc_key[m]);
        pipe = make_pipeline(&tg, Wm, Wm, vert, path);
        ops[m] = ops_of_name(ops_file, "curved", fc_key[m], &br[m]);
        ms[m] = 0.0, nms[m] = 0;
        for (job = 0; job < njob; ++job) {
            int ai_ = (int)(job / sc_F % SC_NALPHA), si_ = (int)(job / (sc_F * SC_NALPHA) % SC_NSIZE), fr_ = (int)(job % sc_F);
            int sc_ = (int)(job / ((long long)sc_F * SC_NALPHA * SC_NSIZE)), W = sc_W[si_], p, x, y;
            fr_push pc;
            float *out = gpu + ((long long)m * njob + job) * stride;
            memset(&pc, 0, sizeof pc);
            pc.pos[0] = (float)(0.5 * W + 0.13 + (double)fr_ / sc_F), pc.pos[1] = (float)(0.5 * W + 0.41 + 0.37 * fr_ / sc_F);
            pc.pos[2] = (float)(0.5 * sc_diam[si_]), pc.pos[3] = (float)W;
            pc.right[0] = (float)(sc_ >= 2), pc.right[1] = (float)(sc_ & 1), pc.right[2] = (float)(0.5 * sc_alpha[ai_] * sc_alpha[ai_]);
            for (k = 0; k < 3; ++k) pc.up[k] = (float)sc_wi_all[sc_ >= 2][k];
            {
                double t = render(&tg, pipe, fc_af[m] == 2 ? set_af : set, &pc, Wm, Wm); /* GPU ms (timestamps), -1 without */
                if (t >= 0.0) ms[m] += t, nms[m]++;
            }
            for (y = 0; y < Wm; ++y)
                for (x = 0; x < Wm; ++x) {
                    const float *o0 = tg.rb_map + 4 * ((size_t)y * Wm + x);
                    if (x >= W || y >= W) continue;
                    p = y * W + x;
                    out[p] = o0[3] > 0.5f ? o0[0] : NAN;
                    if (!isfinite(o0[0])) stat[(sc_ * SC_NSIZE + si_) * SC_NALPHA + ai_][m].nonfinite++;
                }
        }
        vkDestroyPipeline(vk.dev, pipe, NULL);
    }
    t_gpu = now_seconds() - t0;
    t0 = now_seconds();
    cj.cpu = cpu, cj.cpx = cpx, cj.stride = stride;
    pfb_parallel_for(njob, fc_cpu_item, &cj, "frame: curved scenes, CPU path");
    t_cpu = now_seconds() - t0;

    /* statistics per scene row and form (specaa_scenes.h's metric) */
    for (scene = 0; scene < SC_NSCENE; ++scene)
        for (si = 0; si < SC_NSIZE; ++si)
            for (ai = 0; ai < SC_NALPHA; ++ai) {
                int W = sc_W[si];
                long long WW = (long long)W * W, p, j0 = (((long long)scene * SC_NSIZE + si) * SC_NALPHA + ai) * sc_F;
                row = (scene * SC_NSIZE + si) * SC_NALPHA + ai;
                for (m = 0; m < FC_ROWS; ++m) {
                    double e2 = 0, x2 = 0, q2 = 0, o2 = 0, rs = 0, d2 = 0, r2 = 0, c2 = 0, cs = 0, vmax = 0;
                    long long np = 0, nd = 0;
                    fc_stat *s = &stat[row][m];
                    for (fr = 0; fr < sc_F; ++fr) {
                        const double *img = sc_img + (j0 + fr) * sc_img_stride, *prv = fr ? sc_img + (j0 + fr - 1) * sc_img_stride : NULL;
                        const float *gg = gpu + ((long long)m * njob + j0 + fr) * stride, *gp = fr ? gg - stride : gg;
                        const double *cc = cpu + ((long long)m * njob + j0 + fr) * stride, *cx = cpx + ((long long)m * njob + j0 + fr) * stride;
                        double fe2 = 0, fcs = 0;
                        long long fnp = 0;
                        for (p = 0; p < WW; ++p) {
                            double r = img[SM_REF * WW + p], g = (double)gg[p];
                            if (isnan(r) != isnan(g)) s->mismatch++;
                            if (isnan(r) || isnan(g)) continue;
                            ++np, ++fnp;
                            rs += r, cs += cc[p], fcs += cc[p];
                            e2 += (g - r) * (g - r);
                            x2 += (cx[p] - r) * (cx[p] - r), q2 += (cc[p] - r) * (cc[p] - r);
                            o2 += (img[SM_ORACLE * WW + p] - r) * (img[SM_ORACLE * WW + p] - r);
                            c2 += (g - cc[p]) * (g - cc[p]), fe2 += (g - cc[p]) * (g - cc[p]);
                            if (prv && !isnan(prv[SM_REF * WW + p]) && !isnan((double)gp[p])) {
                                double dg = g - (double)gp[p], dr = r - prv[SM_REF * WW + p];
                                ++nd, d2 += dg * dg, r2 += dr * dr;
                            }
                        }
                        if (fnp && fcs > 0.0 && sqrt(fe2 / fnp) / (fcs / fnp) > vmax) vmax = sqrt(fe2 / fnp) / (fcs / fnp);
                    }
                    rs /= (double)(np ? np : 1), cs /= (double)(np ? np : 1);
                    s->err = sqrt(e2 / (double)(np ? np : 1)) / rs;
                    s->err_exact = sqrt(x2 / (double)(np ? np : 1)) / rs;
                    s->err_cpu = sqrt(q2 / (double)(np ? np : 1)) / rs;
                    s->orc = sqrt(o2 / (double)(np ? np : 1)) / rs;
                    s->flk = r2 > 0.0 ? sqrt(d2 / r2) : 0.0;
                    s->vs_cpu = cs > 0.0 ? sqrt(c2 / (double)(np ? np : 1)) / cs : 0.0;
                    s->vs_cpu_max = vmax;
                }
            }

    /* the tables */
    snprintf(path, sizeof path, "%s/frame_curved.csv", outdir);
    csv = fopen(path, "w");
    snprintf(path, sizeof path, "%s/gpuspecaa.md", outdir);
    gm = fopen(path, "w");
    if (!csv || !gm) return 1;
    fprintf(csv, "scene,diameter_px,alpha,form,err,err_over_oracle,cpu_exact_deriv_err_over_oracle,flicker_over_ref,vs_cpu,"
                 "vs_cpu_worst_frame,nonfinite,center_mismatch,spirv_ops,cond_branches,frames,spp,cpu_quad_err_over_oracle\n");
    for (scene = 0; scene < SC_NSCENE; ++scene)
        for (si = 0; si < SC_NSIZE; ++si)
            for (ai = 0; ai < SC_NALPHA; ++ai)
                for (m = 0; m < FC_ROWS; ++m) {
                    const fc_stat *s = &stat[(scene * SC_NSIZE + si) * SC_NALPHA + ai][m];
                    static const char *const key[SC_NSCENE] = {"sphere", "sphere_mapped", "cylinder", "cylinder_mapped"};
                    fprintf(csv, "%s,%g,%g,%s,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%d,%d,%d,%d,%d,%d,%.5g\n", key[scene], sc_diam[si],
                            sc_alpha[ai], fc_key[m], s->err, s->err / s->orc, s->err_exact / s->orc, s->flk, s->vs_cpu, s->vs_cpu_max,
                            s->nonfinite, s->mismatch, ops[m], br[m], sc_F, sc_S * sc_S, s->err_cpu / s->orc);
                }
    fclose(csv);
    for (k = 0; k < 2; ++k) {
        FILE *f = k ? gm : md;
        const int nrow = SC_NSCENE * SC_NSIZE * SC_NALPHA;
        fprintf(f, "%sThe curved scenes of bench/specaa_scenes.h (an orthographic sphere and cylinder %g and %g px across, "
                   "plain or normal-mapped, base alpha %g and %g, %d frames of a sub-pixel camera path) rendered by the GPU frame "
                   "(bench/frame/curved.frag, device %s%s): the surface ray-cast per pixel, the geometry kernel from the hardware "
                   "`dFdxFine`/`dFdyFine` of the macro-normal (and of the position, and of the read's mean, for the forms that "
                   "use them), the map's moment pyramid as R32G32B32A32_SFLOAT textures, read trilinear at the lod the shader "
                   "computes (`textureLod`, log2 of the longer texel derivative) unless the row says otherwise: anisotropic reads "
                   "by EXT_texture_filter_anisotropic's rule done in the shader (up to 16 `textureLod` taps, bench/specaa.c's "
                   "\"aniso fetch\"), or through the driver's 16x sampler, and one row at the driver's lod (`textureGrad`). "
                   "Reference and oracle: specaa_scenes.h's own (%dx%d "
                   "stratified rays per pixel, each shading its texel; one Gaussian lobe of those rays' exact slope moments), "
                   "the same pixels. Per form, over the %d scene rows: **err/oracle**, the RMS error against the reference over "
                   "the oracle's (mean over rows; worst row); **rows within 1.5x** of the oracle's error, and of it and of the "
                   "reference's flicker; the CPU path's err/oracle with exact derivatives (bench/specaa.c's); **flk**, the RMS frame-to-frame change per pixel over the reference's own (mean; "
                   "worst); **GPU vs CPU**, RMS |GPU - CPU| / mean CPU with the CPU float path running the same function "
                   "(bench/frame/curved_shade.h) on the quad's analytic differences (mean over rows; worst frame); non-finite "
                   "pixels; SPIR-V ops after `spirv-opt -O` (and conditional branches); on a GPU, the mean time of one "
                   "%dx%d frame (timestamps; none on a CPU device).%s\n\n",
                k ? "" : "\n### The curved scenes on the GPU (specular antialiasing)\n\n", sc_diam[0], sc_diam[1], sc_alpha[0],
                sc_alpha[1], sc_F, vk.name, vk.is_cpu ? ", a CPU implementation" : "", sc_S, sc_S, nrow, Wm, Wm,
                quick ? " BENCH_QUICK: smoke run, not for publication." : "");
        fprintf(f, "| form | err/oracle (GPU): mean; worst | rows within 1.5x: err; err and flk | err/oracle, CPU exact derivatives: mean | flk: "
                   "mean; worst | GPU vs CPU: mean; worst frame | non-finite | SPIR-V ops (branches) | GPU ms |\n"
                   "|---|--:|--:|--:|--:|--:|--:|--:|--:|\n");
        for (m = 0; m < FC_ROWS; ++m) {
            double se = 0, we = 0, sx = 0, sf = 0, wf = 0, sv = 0, wv = 0;
            int nin = 0, nboth = 0, nf = 0, r;
            char tm[32] = "-";
            for (r = 0; r < nrow; ++r) {
                const fc_stat *s = &stat[r][m];
                double e = s->err / s->orc;
                se += e, sx += s->err_exact / s->orc, sf += s->flk, sv += s->vs_cpu, nf += s->nonfinite;
                if (e > we) we = e;
                if (s->flk > wf) wf = s->flk;
                if (s->vs_cpu_max > wv) wv = s->vs_cpu_max;
                nin += e <= 1.5, nboth += e <= 1.5 && s->flk <= 1.5;
            }
            if (nms[m]) snprintf(tm, sizeof tm, "%.3f", ms[m] / nms[m]);
            fprintf(f, "| %s | %.3g; %.3g | %d/%d; %d/%d | %.3g | %.3g; %.3g | %.3f%%; %.3f%% | %d | %d (%d) | %s |\n", fc_name(m),
                    se / nrow, we, nin, nrow, nboth, nrow, sx / nrow, sf / nrow, wf, 100.0 * sv / nrow, 100.0 * wv, nf, ops[m], br[m], tm);
        }
        fprintf(f, "\nPer scene row (GPU; err/oracle / flk): `bench/out/frame_curved.csv`. Reference, GPU frames and CPU path "
                   "took %.1f s, %.1f s and %.1f s wall (the reference: specaa_scenes.h's sc_run_ref, reference and oracle only).\n",
                t_ref, t_gpu, t_cpu);
    }
    fclose(gm);
    printf("frame: curved scenes: %lld frames x %d rows; reference %.1f s, GPU %.1f s, CPU path %.1f s (wall); %.1f s CPU in this thread\n",
           njob, FC_ROWS, t_ref, t_gpu, t_cpu, thread_cpu_seconds() - c0);
    vkDestroyBuffer(vk.dev, tg.rb, NULL);
    vkFreeMemory(vk.dev, tg.rb_mem, NULL);
    free(ta), free(tb), free(gpu), free(cpu), free(cpx);
    free(sc_img), free(sc_dev2), free(sc_full), free(sc_slope), free(sc_pyr), free(sc_npyr);
    return 0;
}

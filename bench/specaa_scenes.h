/* bench/specaa_scenes.h - curved, normal-mapped scenes for bench/specaa.c (included once, after
   its helpers): the geometry kernel composed with LEADR and vMF texture filtering, the engines'
   geometry kernels, against a supersampled reference and the exact-footprint oracle, over a
   sub-pixel camera path. Bench code, not part of the library.

   SCENES (orthographic view along -z, one directional light, f0 = 1): a sphere (diameters D
   below) and a cylinder of the same radius (axis along y, the image D + 5 px square), each
   plain (no map) or normal-mapped. The map: a tiling N x N normal map of slopes, the gradient
   of a sum of 12 sines (integer frequencies 6-40 cycles per map, amplitudes ~1/f, RMS slope
   0.08 per axis), wrapped twice around the surface's u = atan2(n.x, n.z) (texels square at
   the sphere's equator: the same scale along v = asin(n.y), or along y/R on the cylinder); a
   texel's slope perturbs the macro-normal in the surface's tangent frame (T along u, B along
   v): n = normalize(N - s_x T - s_y B).

   SHADING. Everything is shaded with one BRDF, pf_leadr_specular (Beckmann slopes with Smith
   masking-shadowing, Dupuy et al. 2013) with base roughness alpha (per-axis variance
   alpha^2/2), in the tangent frame where it is evaluated:
     reference  per pixel, S x S stratified jittered rays over the pixel square (the box pixel
                filter), each ray shading its own texel (nearest, level 0) in its own frame,
                averaged over the rays that hit (the shading resolve; coverage is not measured);
                pixels whose centre is on the surface. Its sampling deviation is reported;
     oracle     the same rays' normals as slopes in the pixel centre's frame: their exact mean
                and covariance (the footprint's exact slope histogram reduced to LEADR's
                Gaussian) plus alpha^2/2, shaded once at the centre: what a single Gaussian lobe
                can reach;
     methods    shaded once at the pixel centre: the texture part from the map's 5-moment
                pyramid (pf_slope_moments_sample, trilinear, the GPU's isotropic lod
                log2 max(|d(s,t)/dx|, |d(s,t)/dy|) in texels), plus the geometry kernel of the
                exact screen derivatives of the macro-normal (central differences), composed
                as pf_specaa.h says (LEADR: covariances add; vMF: pf_specaa_vmf_kappa on the
                lobe of the mip's averaged unit normal, shaded through pf_vmf_lobe_slope_stats);
                the engines' geometry kernels on the same LEADR texture part. The pyramid read
                as GPUs read an anisotropic footprint (sc_fetch_aniso: N = min(ceil(major/
                minor), 16) trilinear taps along the major axis at lod log2(major/N)), alone and
                with the cross term (4) of pf_specaa.h from the central differences of its mean
                at +-1/2 px (what dFdx/dFdy of the fetched mean give); four such reads, one per
                pixel quadrant with half the footprint (pf_specaa_slope_stats_quad: moments,
                gradient, kernel, cross term); the second-order shift of the pixel's mean slope
                (pf_specaa.h (6) from the kernel's trace and the view, pf_specaa_leadr_specular_curved's
                form; (5) from the surface position's exact screen derivatives, P = (x, y, R n_z))
                on the box kernel and on the quadrant reads;
   diagnostics  the exact texel moments of the pixel (the rays' nearest texels) with and
                without the exact cross term (the rays' regression of the texel slope on the
                sub-pixel offset); the anisotropic read with that exact cross term; the oracle's
                covariance around the texture's mean (the geometry's second-order mean shift
                removed); the box kernel's covariance around the oracle's exact mean (the split
                of the error into mean and covariance); a second reference of independent jitter
                (its RMS difference to the first / sqrt 2: the reference's true sampling
                deviation, printed beside the i.i.d. bound).
   ERROR: RMS over pixels and frames of (method - reference), relative to the mean reference;
   the table gives it divided by the oracle's. FLICKER: per pixel, the change from one frame to
   the next (pixels on the surface in both), RMS over pixels and frame pairs; the table gives it
   divided by the reference's own. The camera moves by (1, 0.37) px over F frames. */

#define SC_N 256
#define SC_REP 2.0
#define SC_NSCENE 4
#define SC_NSIZE 2
#define SC_NALPHA 2
static const char *sc_scene_name[SC_NSCENE] = { "sphere", "sphere, mapped", "cylinder", "cylinder, mapped" };
static const double sc_alpha[SC_NALPHA] = { 0.03, 0.1 };
static double sc_diam[SC_NSIZE] = { 16.0, 40.0 };
static int sc_S = 20, sc_F = 12;

enum { SM_NONE, SM_BOX, SM_BOX_AREA, SM_BOX_ISO, SM_TK, SM_FILAMENT, SM_HDRP, SM_GODOT, SM_VMF_NONE, SM_VMF_BOX,
       SM_AF, SM_AF_CROSS, SM_QUAD_CROSS, SM_AF_XCROSS, SM_DIAG_OMEAN0, SM_TEXEXACT, SM_TEXEXACT_CROSS,
       SM_BOX_SHIFT, SM_BOX_SHIFT_SURF, SM_ISO_SHIFT, SM_QUAD_SHIFT, SM_DIAG_BOX_OMEAN, SM_REF2, SM_ORACLE, SM_REF, SM_COUNT };
#define SC_NMETH SM_REF /* methods and the oracle */
static const char *sc_meth_name[SM_REF] = {
    "LEADR, no kernel", "LEADR + box kernel (aniso, sigma2 1/24)", "LEADR (area lod) + box kernel (aniso)",
    "LEADR + box kernel (iso, sigma2 1/24: pf_specaa_leadr_specular)",
    "LEADR + TK2019 (1/(2pi), 0.18)", "LEADR + Filament (0.15, 0.2^2)", "LEADR + HDRP (0.1, 0.2^2)",
    "LEADR + Godot limiter (0.25, 0.18 on alpha)", "vMF, no kernel", "vMF + box kernel (1/24)",
    "LEADR (aniso fetch) + box kernel (aniso)", "LEADR (aniso fetch) + box kernel + cross term",
    "LEADR (4 quadrant aniso fetches) + box kernel + cross term",
    "aniso fetch + box kernel + exact cross term", "diag: oracle covariance, mean of the texture only",
    "exact texel moments + box kernel (aniso)", "exact texel moments + box kernel + exact cross term",
    "LEADR + box kernel (aniso) + mean shift (6): pf_specaa_leadr_specular_curved",
    "LEADR + box kernel (aniso) + mean shift (5) from position derivatives", "LEADR + box kernel (iso) + mean shift (6)",
    "LEADR (4 quadrant aniso fetches) + box kernel + cross term + mean shift (6)",
    "diag: box kernel (aniso) covariance, the oracle's exact mean", "diag: a second reference (independent jitter)",
    "oracle (exact footprint)"
};

static double *sc_slope;   /* level 0: SC_N^2 x 2 slopes */
static pf_real *sc_pyr;    /* 5-moment pyramid */
static pf_real *sc_npyr;   /* averaged unit normals, 3 channels */

typedef struct sc_geo {
    double N[3], T[3], B[3], s, t; /* macro-normal, frame, texel coordinates */
    int cyl;
} sc_geo;

/* the macro surface at image point (x, y): 1 on a hit */
static int sc_eval(int scene, double R, double cx, double cy, double x, double y, sc_geo *g)
{
    double dx = (x - cx) / R, dy = (y - cy) / R, u, v, k = SC_N * SC_REP / (2.0 * 3.14159265358979323846);
    int sph = scene < 2;
    g->cyl = !sph;
    if (sph) {
        double r2 = dx * dx + dy * dy;
        if (r2 >= 1.0) return 0;
        g->N[0] = dx; g->N[1] = dy; g->N[2] = sqrt(1.0 - r2);
        u = atan2(g->N[0], g->N[2]);
        v = asin(dy);
        g->T[0] = cos(u); g->T[1] = 0.0; g->T[2] = -sin(u);
        g->B[0] = -sin(u) * sin(v); g->B[1] = cos(v); g->B[2] = -cos(u) * sin(v);
    } else {
        if (dx * dx >= 1.0) return 0;
        g->N[0] = dx; g->N[1] = 0.0; g->N[2] = sqrt(1.0 - dx * dx);
        u = atan2(g->N[0], g->N[2]);
        v = dy;
        g->T[0] = cos(u); g->T[1] = 0.0; g->T[2] = -sin(u);
        g->B[0] = 0.0; g->B[1] = 1.0; g->B[2] = 0.0;
    }
    g->s = u * k;
    g->t = v * k;
    return 1;
}

static double sc_dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* the shading normal of a ray: the texel's slope in the ray's frame (nearest texel) */
static void sc_normal(int scene, const sc_geo *g, double n[3], double *sx, double *sy)
{
    double l;
    int i, j;
    if (scene & 1) {
        i = (int)floor(g->s); j = (int)floor(g->t);
        i = (int)pf_map_wrap(i, SC_N); j = (int)pf_map_wrap(j, SC_N);
        *sx = sc_slope[2 * ((long long)j * SC_N + i)];
        *sy = sc_slope[2 * ((long long)j * SC_N + i) + 1];
    } else *sx = *sy = 0.0;
    n[0] = g->N[0] - *sx * g->T[0] - *sy * g->B[0];
    n[1] = g->N[1] - *sx * g->T[1] - *sy * g->B[1];
    n[2] = g->N[2] - *sx * g->T[2] - *sy * g->B[2];
    l = 1.0 / sqrt(sc_dot(n, n));
    n[0] *= l; n[1] *= l; n[2] *= l;
}

static const double sc_wo[3] = { 0.0, 0.0, 1.0 };
/* the light: the sphere's as in the sphere table above; the cylinder's in the plane of its
   normals (x, z), so that its highlight is a stripe on it */
static const double sc_wi_all[2][3] = { { 0.4082482904638631, 0.4082482904638631, 0.8164965809277261 },
                                        { 0.5, 0.0, 0.8660254037844386 } };
#define sc_wi (sc_wi_all[g->cyl])

static double sc_shade(const sc_geo *g, pf_slope_stats st)
{
    pf_vec3 wo = pf_vec3_make((pf_real)sc_dot(sc_wo, g->T), (pf_real)sc_dot(sc_wo, g->B), (pf_real)sc_dot(sc_wo, g->N));
    pf_vec3 wi = pf_vec3_make((pf_real)sc_dot(sc_wi, g->T), (pf_real)sc_dot(sc_wi, g->B), (pf_real)sc_dot(sc_wi, g->N));
    if (!(wo.z > 0) || !(wi.z > 0)) return 0.0;
    return (double)pf_leadr_specular(wo, wi, st, PF_R(1.0));
}

static void sc_build_map(void)
{
    static const int fr[12][2] = { { 6, 1 }, { -3, 7 }, { 9, -4 }, { 11, 5 }, { -2, 13 }, { 15, 8 },
                                   { -17, 6 }, { 4, 19 }, { 23, -9 }, { -12, 25 }, { 31, 14 }, { -22, 33 } };
    double ph[12], amp[12], ss = 0.0;
    long long t, nt = pf_mip_texel_count(SC_N, SC_N);
    int k;
    pfm_rng rng;
    rng.state = 0x27a5ce7e5ULL;
    for (k = 0; k < 12; ++k) {
        double f = sqrt((double)(fr[k][0] * fr[k][0] + fr[k][1] * fr[k][1]));
        ph[k] = 2.0 * 3.14159265358979323846 * pfm_rng_uniform(&rng);
        amp[k] = 1.0 / (f * f); /* slope amplitude ~ 1/f */
    }
    sc_slope = (double *)malloc(sizeof(double) * 2 * SC_N * SC_N);
    sc_pyr = (pf_real *)malloc(sizeof(pf_real) * 5 * (size_t)nt);
    sc_npyr = (pf_real *)malloc(sizeof(pf_real) * 3 * (size_t)nt);
    if (!sc_slope || !sc_pyr || !sc_npyr) { fprintf(stderr, "specaa: out of memory\n"); exit(1); }
    for (t = 0; t < (long long)SC_N * SC_N; ++t) {
        double x = (double)(t % SC_N) + 0.5, y = (double)(t / SC_N) + 0.5, gx = 0, gy = 0;
        for (k = 0; k < 12; ++k) {
            double w = 2.0 * 3.14159265358979323846 / SC_N, c = cos(w * (fr[k][0] * x + fr[k][1] * y) + ph[k]);
            gx += amp[k] * w * fr[k][0] * c;
            gy += amp[k] * w * fr[k][1] * c;
        }
        sc_slope[2 * t] = gx; sc_slope[2 * t + 1] = gy;
        ss += gx * gx + gy * gy;
    }
    ss = 0.08 / sqrt(0.5 * ss / ((double)SC_N * SC_N)); /* RMS slope 0.08 per axis */
    for (t = 0; t < (long long)SC_N * SC_N; ++t) {
        double sx = sc_slope[2 * t] * ss, sy = sc_slope[2 * t + 1] * ss, l = 1.0 / sqrt(1.0 + sx * sx + sy * sy);
        pf_real *m = sc_pyr + 5 * t, *n = sc_npyr + 3 * t;
        sc_slope[2 * t] = sx;
        sc_slope[2 * t + 1] = sy;
        m[0] = (pf_real)sx; m[1] = (pf_real)sy; m[2] = (pf_real)(sx * sx); m[3] = (pf_real)(sy * sy); m[4] = (pf_real)(sx * sy);
        n[0] = (pf_real)(-sx * l); n[1] = (pf_real)(-sy * l); n[2] = (pf_real)l;
    }
    if (pf_mip_build(sc_pyr, SC_N, SC_N, 5) != PF_OK || pf_mip_build(sc_npyr, SC_N, SC_N, 3) != PF_OK) {
        fprintf(stderr, "specaa: map pyramid failed\n");
        exit(1);
    }
}

/* per job (scene, size, alpha, frame): the image of every method, the reference and its
   sampling variance, NaN off the surface */
static int sc_W[SC_NSIZE];
static double *sc_img;   /* [job][SM_COUNT][W*W] */
static double *sc_dev2;  /* [job][W*W] */
static unsigned char *sc_full; /* [job][W*W]: every ray of the pixel hit the surface */
static long long sc_img_stride, sc_dev_stride;
/* the sphere table's old flicker: the deviation over frames of the image's total, / its mean */
static double sc_total_flk[SC_NSCENE * SC_NSIZE * SC_NALPHA][SM_COUNT];

/* The moment pyramid read as a GPU's anisotropic filter reads a texture (EXT_texture_filter_anisotropic's
   rule): the footprint's axes d(s,t)/dx and d(s,t)/dy in texels, N = min(ceil(major/minor), 16)
   trilinear taps spread evenly over the major axis at the lod log2(major/N), averaged (the moments
   are linear). (ox, oy): an offset of the pixel in pixels (the neighbour a dFdx would read). */
static pf_slope_moments sc_fetch_aniso(double s, double t, double dst[2][2], double ox, double oy, double scale)
{
    double lx = scale * sqrt(dst[0][0] * dst[0][0] + dst[0][1] * dst[0][1]), ly = scale * sqrt(dst[1][0] * dst[1][0] + dst[1][1] * dst[1][1]);
    double pmax = fmax(lx, ly), pmin = fmax(fmin(lx, ly), 1e-9), lod, w;
    const double *ax = lx >= ly ? dst[0] : dst[1];
    double sum[5] = { 0, 0, 0, 0, 0 };
    int n = (int)ceil(pmax / pmin - 1e-9), i;
    if (n > 16) n = 16;
    if (n < 1) n = 1;
    lod = pmax / n > 1.0 ? log2(pmax / n) : 0.0;
    s += ox * dst[0][0] + oy * dst[1][0];
    t += ox * dst[0][1] + oy * dst[1][1];
    for (i = 0; i < n; ++i) {
        double o = (i + 0.5) / n - 0.5;
        pf_slope_moments m = pf_slope_moments_sample(sc_pyr, SC_N, SC_N, (pf_real)lod, (pf_real)((s + scale * o * ax[0]) / SC_N),
                                                     (pf_real)((t + scale * o * ax[1]) / SC_N), PF_BORDER_WRAP);
        sum[0] += (double)m.ex; sum[1] += (double)m.ey; sum[2] += (double)m.exx; sum[3] += (double)m.eyy; sum[4] += (double)m.exy;
    }
    w = 1.0 / n;
    return pf_slope_moments_make((pf_real)(sum[0] * w), (pf_real)(sum[1] * w), (pf_real)(sum[2] * w), (pf_real)(sum[3] * w),
                                 (pf_real)(sum[4] * w));
}

static long long sc_njobs(void) { return (long long)SC_NSCENE * SC_NSIZE * SC_NALPHA * sc_F; }

/* job's frame, roughness, size and scene indices (job order of sc_njobs: frame fastest) */
static void sc_job_indices(long long job, int *fr, int *ai, int *si, int *scene)
{
    *fr = (int)(job % sc_F);
    *ai = (int)(job / sc_F % SC_NALPHA);
    *si = (int)(job / (sc_F * SC_NALPHA) % SC_NSIZE);
    *scene = (int)(job / ((long long)sc_F * SC_NALPHA * SC_NSIZE));
}


/* One pixel's stratified reference: sc_S x sc_S jittered rays through pixel (x, y) (the jitter a
   hash of pixel p, ray, frame fr and seed), each shading its own texel with the base lobe
   (variance bv). Sums the shade and its square over the hits; with a centre frame g, also the
   rays' slope moments in that frame (o: the oracle's), their texel slopes (q) and the sub-pixel
   offset moments (c: E[ox], E[oy], E[ox sx], E[ox sy], E[oy sx], E[oy sy]), all unnormalised. */
typedef struct {
    double sum, sum2, o[5], q[5], c[6];
    int hits;
} sc_rays;

static sc_rays sc_pixel_rays(int scene, double R, double cx, double cy, double x, double y, long long p, int fr,
                             unsigned long long seed, const sc_geo *g, double bv)
{
    sc_rays r;
    int i, j;
    memset(&r, 0, sizeof r);
    for (j = 0; j < sc_S; ++j)
        for (i = 0; i < sc_S; ++i) {
            unsigned long long z = (unsigned long long)(((p * 131071 + j) * 8191 + i) * 4099 + (unsigned long long)fr * 977 + seed);
            double u1, u2, n[3], sx, sy, f, nz, qx, qy, ox, oy;
            sc_geo gr;
            z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL; z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL; z ^= z >> 31;
            u1 = (double)(z >> 40) / 16777216.0;
            u2 = (double)(z & 0xFFFFFF) / 16777216.0;
            ox = (i + u1) / sc_S - 0.5;
            oy = (j + u2) / sc_S - 0.5;
            if (!sc_eval(scene, R, cx, cy, x + ox, y + oy, &gr)) continue;
            sc_normal(scene, &gr, n, &sx, &sy);
            f = sc_shade(&gr, pf_slope_stats_make((pf_real)sx, (pf_real)sy, (pf_real)bv, (pf_real)bv, PF_R(0.0)));
            r.sum += f; r.sum2 += f * f; ++r.hits;
            if (!g) continue;
            nz = sc_dot(n, g->N);
            if (nz < 1e-3) nz = 1e-3;
            qx = -sc_dot(n, g->T) / nz; qy = -sc_dot(n, g->B) / nz;
            r.o[0] += qx; r.o[1] += qy; r.o[2] += qx * qx; r.o[3] += qy * qy; r.o[4] += qx * qy;
            r.q[0] += sx; r.q[1] += sy; r.q[2] += sx * sx; r.q[3] += sy * sy; r.q[4] += sx * sy;
            r.c[0] += ox; r.c[1] += oy; r.c[2] += ox * sx; r.c[3] += ox * sy; r.c[4] += oy * sx; r.c[5] += oy * sy;
        }
    return r;
}

static void sc_run(void *ctx, long long job)
{
    int fr, ai, si, scene, W, px, py, m;
    double R, a, bv, cx, cy;
    double *img = sc_img + job * sc_img_stride, *dev2 = sc_dev2 + job * sc_dev_stride;
    unsigned char *full = sc_full + job * sc_dev_stride;
    sc_job_indices(job, &fr, &ai, &si, &scene);
    R = 0.5 * sc_diam[si];
    a = sc_alpha[ai];
    bv = 0.5 * a * a;
    W = sc_W[si];
    cx = 0.5 * W + 0.13 + (double)fr / sc_F;
    cy = 0.5 * W + 0.41 + 0.37 * fr / sc_F;
    (void)ctx;
    for (py = 0; py < W; ++py)
        for (px = 0; px < W; ++px) {
            long long p = (long long)py * W + px;
            double x = px + 0.5, y = py + 0.5, h = 1e-4, sum = 0, sum2 = 0, o[5] = { 0, 0, 0, 0, 0 }, q[5] = { 0, 0, 0, 0, 0 };
            double c[6] = { 0, 0, 0, 0, 0, 0 }; /* sub-pixel offset moments: E[ox], E[oy], E[ox sx], E[ox sy], E[oy sx], E[oy sy] */
            double dN[2][3], dst[2][2], res[SM_COUNT];
            sc_geo g, gp, gm;
            sc_rays rays;
            int hits = 0, i, d;
            for (m = 0; m < SM_COUNT; ++m) img[m * (long long)W * W + p] = NAN;
            dev2[p] = NAN;
            full[p] = 0;
            if (!sc_eval(scene, R, cx, cy, x, y, &g)) continue;
            /* screen derivatives of the macro-normal and of the texel coordinates */
            for (d = 0; d < 2; ++d) {
                int okp = sc_eval(scene, R, cx, cy, x + (d == 0 ? h : 0), y + (d == 1 ? h : 0), &gp);
                int okm = sc_eval(scene, R, cx, cy, x - (d == 0 ? h : 0), y - (d == 1 ? h : 0), &gm);
                double den = (okp && okm) ? 2.0 * h : h;
                const sc_geo *A = okp ? &gp : &g, *Bm = okm ? &gm : &g;
                for (i = 0; i < 3; ++i) dN[d][i] = (A->N[i] - Bm->N[i]) / den;
                dst[d][0] = (A->s - Bm->s) / den;
                dst[d][1] = (A->t - Bm->t) / den;
            }
            /* the reference and the oracle's moments, in the centre frame */
            rays = sc_pixel_rays(scene, R, cx, cy, x, y, p, fr, 0x5ceULL, &g, bv);
            sum = rays.sum; sum2 = rays.sum2; hits = rays.hits;
            for (i = 0; i < 5; ++i) { o[i] = rays.o[i]; q[i] = rays.q[i]; }
            for (i = 0; i < 6; ++i) c[i] = rays.c[i];
            {   /* a second, independent reference (other jitter): its difference to the first measures the
                   stratified reference's true sampling deviation */
                sc_rays r2 = sc_pixel_rays(scene, R, cx, cy, x, y, p, fr, 0x9e3779b97f4a7c15ULL, NULL, bv);
                res[SM_REF2] = r2.hits ? r2.sum / r2.hits : 0.0;
            }
            full[p] = hits == sc_S * sc_S;
            res[SM_REF] = sum / hits;
            dev2[p] = hits > 1 ? fmax(sum2 / hits - res[SM_REF] * res[SM_REF], 0.0) / (hits - 1) : 0.0;
            for (i = 0; i < 5; ++i) { o[i] /= hits; q[i] /= hits; }
            for (i = 0; i < 6; ++i) c[i] /= hits;
            res[SM_ORACLE] = sc_shade(&g, pf_slope_moments_stats(pf_slope_moments_make((pf_real)o[0], (pf_real)o[1], (pf_real)o[2],
                                                                                       (pf_real)o[3], (pf_real)o[4]), (pf_real)bv));
            {   /* diagnostic: the oracle's covariance around the rays' texel mean slope (the geometry's second-order mean shift removed) */
                double cxx = o[2] - o[0] * o[0], cyy = o[3] - o[1] * o[1], cxy = o[4] - o[0] * o[1];
                res[SM_DIAG_OMEAN0] = sc_shade(&g, pf_slope_stats_make((pf_real)q[0], (pf_real)q[1], (pf_real)(cxx + bv), (pf_real)(cyy + bv), (pf_real)cxy));
            }
            {   /* the methods */
                double rho = fmax(sqrt(dst[0][0] * dst[0][0] + dst[0][1] * dst[0][1]), sqrt(dst[1][0] * dst[1][0] + dst[1][1] * dst[1][1]));
                pf_real lod = (pf_real)(rho > 1.0 ? log2(rho) : 0.0);
                pf_real us = (pf_real)(g.s / SC_N), vs = (pf_real)(g.t / SC_N);
                pf_slope_moments mm = (scene & 1) ? pf_slope_moments_sample(sc_pyr, SC_N, SC_N, lod, us, vs, PF_BORDER_WRAP)
                                                  : pf_slope_moments_make(0, 0, 0, 0, 0);
                pf_vec3 nav = (scene & 1) ? pf_normal_avg_sample(sc_npyr, SC_N, SC_N, lod, us, vs, PF_BORDER_WRAP)
                                          : pf_vec3_make(0, 0, 1);
                pf_slope_stats s0 = pf_slope_moments_stats(mm, (pf_real)bv);
                pf_vec3 dnx = pf_vec3_make((pf_real)dN[0][0], (pf_real)dN[0][1], (pf_real)dN[0][2]);
                pf_vec3 dny = pf_vec3_make((pf_real)dN[1][0], (pf_real)dN[1][1], (pf_real)dN[1][2]);
                pf_vec3 ax = pf_vec3_make((pf_real)sc_dot(dN[0], g.T), (pf_real)sc_dot(dN[0], g.B), (pf_real)sc_dot(dN[0], g.N));
                pf_vec3 ay = pf_vec3_make((pf_real)sc_dot(dN[1], g.T), (pf_real)sc_dot(dN[1], g.B), (pf_real)sc_dot(dN[1], g.N));
                pf_real kbox = pf_specaa_kernel_normal(dnx, dny, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA);
                res[SM_NONE] = sc_shade(&g, s0);
                res[SM_BOX] = sc_shade(&g, pf_specaa_slope_stats_aniso(s0, pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA)));
                {   /* the texture part at the footprint's area lod, log2 sqrt|det J| */
                    double det = fabs(dst[0][0] * dst[1][1] - dst[0][1] * dst[1][0]);
                    pf_real la = (pf_real)(det > 1.0 ? 0.5 * log2(det) : 0.0);
                    pf_slope_moments ma = (scene & 1) ? pf_slope_moments_sample(sc_pyr, SC_N, SC_N, la, us, vs, PF_BORDER_WRAP)
                                                      : pf_slope_moments_make(0, 0, 0, 0, 0);
                    res[SM_BOX_AREA] = sc_shade(&g, pf_specaa_slope_stats_aniso(pf_slope_moments_stats(ma, (pf_real)bv),
                        pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA)));
                }
                res[SM_TEXEXACT] = sc_shade(&g, pf_specaa_slope_stats_aniso(pf_slope_moments_stats(pf_slope_moments_make(
                    (pf_real)q[0], (pf_real)q[1], (pf_real)q[2], (pf_real)q[3], (pf_real)q[4]), (pf_real)bv),
                    pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA)));
                res[SM_BOX_ISO] = sc_shade(&g, pf_specaa_slope_stats(s0, kbox));
                {   /* the anisotropic fetch; the cross term from its mean's screen derivatives (central
                       differences at +-1/2 px, what dFdx/dFdy of the fetched mean estimate) */
                    pf_specaa_kernel kan = pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA);
                    pf_slope_moments mf = (scene & 1) ? sc_fetch_aniso(g.s, g.t, dst, 0, 0, 1.0) : pf_slope_moments_make(0, 0, 0, 0, 0);
                    pf_slope_stats sf = pf_slope_moments_stats(mf, (pf_real)bv);
                    pf_vec2 dmx = pf_vec2_make(0, 0), dmy = pf_vec2_make(0, 0);
                    pf_vec3 ax0 = pf_vec3_make(ax.x, ax.y, 0), ay0 = pf_vec3_make(ay.x, ay.y, 0);
                    if (scene & 1) {
                        pf_slope_moments xp = sc_fetch_aniso(g.s, g.t, dst, 0.5, 0, 1.0), xm = sc_fetch_aniso(g.s, g.t, dst, -0.5, 0, 1.0);
                        pf_slope_moments yp = sc_fetch_aniso(g.s, g.t, dst, 0, 0.5, 1.0), ym = sc_fetch_aniso(g.s, g.t, dst, 0, -0.5, 1.0);
                        dmx = pf_vec2_make(xp.ex - xm.ex, xp.ey - xm.ey);
                        dmy = pf_vec2_make(yp.ex - ym.ex, yp.ey - ym.ey);
                    }
                    res[SM_AF] = sc_shade(&g, pf_specaa_slope_stats_aniso(sf, kan));
                    res[SM_AF_CROSS] = sc_shade(&g, pf_specaa_slope_stats_cross(sf, kan, pf_specaa_kernel_cross(ax0, ay0, dmx, dmy, PF_SPECAA_SIGMA2_BOX)));
                    {   /* four anisotropic fetches, one per quadrant of the pixel (half the footprint each):
                           their mean, and the gradient from their differences (2 (right - left): exact for
                           a linear texture) */
                        pf_slope_moments t00 = pf_slope_moments_make(0, 0, 0, 0, 0), t10 = t00, t01 = t00, t11 = t00;
                        if (scene & 1) {
                            t00 = sc_fetch_aniso(g.s, g.t, dst, -0.25, -0.25, 0.5); t10 = sc_fetch_aniso(g.s, g.t, dst, 0.25, -0.25, 0.5);
                            t01 = sc_fetch_aniso(g.s, g.t, dst, -0.25, 0.25, 0.5); t11 = sc_fetch_aniso(g.s, g.t, dst, 0.25, 0.25, 0.5);
                        }
                        res[SM_QUAD_CROSS] = sc_shade(&g, pf_specaa_slope_stats_quad(t00, t10, t01, t11, (pf_real)bv, ax0, ay0,
                                                                                     PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA));
                    }
                    {   /* the exact cross term: the rays' regression of the texel slope on the sub-pixel offset
                           (var of the offset 1/12 over the pixel square) */
                        pf_vec2 ex = pf_vec2_make((pf_real)(12.0 * (c[2] - c[0] * q[0])), (pf_real)(12.0 * (c[3] - c[0] * q[1])));
                        pf_vec2 ey = pf_vec2_make((pf_real)(12.0 * (c[4] - c[1] * q[0])), (pf_real)(12.0 * (c[5] - c[1] * q[1])));
                        res[SM_AF_XCROSS] = sc_shade(&g, pf_specaa_slope_stats_cross(sf, kan, pf_specaa_kernel_cross(ax0, ay0, ex, ey, PF_SPECAA_SIGMA2_BOX)));
                        res[SM_TEXEXACT_CROSS] = sc_shade(&g, pf_specaa_slope_stats_cross(pf_slope_moments_stats(pf_slope_moments_make(
                            (pf_real)q[0], (pf_real)q[1], (pf_real)q[2], (pf_real)q[3], (pf_real)q[4]), (pf_real)bv), kan,
                            pf_specaa_kernel_cross(ax0, ay0, ex, ey, PF_SPECAA_SIGMA2_BOX)));
                    }
                }
                {   /* the second-order shift of the pixel's mean slope (pf_specaa.h (5), (6)); the surface's
                       position derivatives: P = (x, y, R n_z) in pixels for both scenes (orthographic) */
                    pf_vec3 wot = pf_vec3_make((pf_real)sc_dot(sc_wo, g.T), (pf_real)sc_dot(sc_wo, g.B), (pf_real)sc_dot(sc_wo, g.N));
                    pf_specaa_kernel kan = pf_specaa_kernel_aniso(ax, ay, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA);
                    pf_vec2 d6 = pf_specaa_mean_shift(wot, pf_specaa_kernel_trace(kan)), d6i = pf_specaa_mean_shift(wot, kbox);
                    double dpx[3] = { 1.0, 0.0, R * dN[0][2] }, dpy[3] = { 0.0, 1.0, R * dN[1][2] };
                    pf_vec3 jx = pf_vec3_make((pf_real)sc_dot(dpx, g.T), (pf_real)sc_dot(dpx, g.B), (pf_real)sc_dot(dpx, g.N));
                    pf_vec3 jy = pf_vec3_make((pf_real)sc_dot(dpy, g.T), (pf_real)sc_dot(dpy, g.B), (pf_real)sc_dot(dpy, g.N));
                    pf_vec2 d5 = pf_specaa_mean_shift_surface(jx, jy, ax, ay, wot, PF_SPECAA_SIGMA2_BOX);
                    pf_slope_stats sa = pf_specaa_slope_stats_aniso(s0, kan), t;
                    res[SM_BOX_SHIFT] = sc_shade(&g, pf_specaa_slope_stats_shift(sa, d6));
                    res[SM_BOX_SHIFT_SURF] = sc_shade(&g, pf_specaa_slope_stats_shift(sa, d5));
                    res[SM_ISO_SHIFT] = sc_shade(&g, pf_specaa_slope_stats_shift(pf_specaa_slope_stats(s0, kbox), d6i));
                    {
                        pf_slope_moments t00 = pf_slope_moments_make(0, 0, 0, 0, 0), t10 = t00, t01 = t00, t11 = t00;
                        pf_vec3 ax0 = pf_vec3_make(ax.x, ax.y, 0), ay0 = pf_vec3_make(ay.x, ay.y, 0);
                        if (scene & 1) {
                            t00 = sc_fetch_aniso(g.s, g.t, dst, -0.25, -0.25, 0.5); t10 = sc_fetch_aniso(g.s, g.t, dst, 0.25, -0.25, 0.5);
                            t01 = sc_fetch_aniso(g.s, g.t, dst, -0.25, 0.25, 0.5); t11 = sc_fetch_aniso(g.s, g.t, dst, 0.25, 0.25, 0.5);
                        }
                        res[SM_QUAD_SHIFT] = sc_shade(&g, pf_specaa_slope_stats_shift(pf_specaa_slope_stats_quad(t00, t10, t01, t11,
                            (pf_real)bv, ax0, ay0, PF_SPECAA_SIGMA2_BOX, PF_SPECAA_KAPPA), d6));
                    }
                    t = sa; t.mean_x = (pf_real)o[0]; t.mean_y = (pf_real)o[1];
                    res[SM_DIAG_BOX_OMEAN] = sc_shade(&g, t);
                }
                res[SM_TK] = sc_shade(&g, pf_specaa_slope_stats(s0, pf_specaa_kernel_normal(dnx, dny, PF_SPECAA_SIGMA2, PF_SPECAA_KAPPA)));
                res[SM_FILAMENT] = sc_shade(&g, pf_specaa_slope_stats(s0, pf_specaa_kernel_normal(dnx, dny, PF_R(0.15), PF_R(0.04))));
                res[SM_HDRP] = sc_shade(&g, pf_specaa_slope_stats(s0, pf_specaa_kernel_normal(dnx, dny, PF_R(0.1), PF_R(0.04))));
                {   /* Godot: perceptual roughness^2 (= alpha) += min(2 x 0.25 |dn|^2, 0.18), on LEADR's
                       isotropic equivalent alpha^2 = var_x + var_y; the alpha^2 increment spread on both axes */
                    double ae = sqrt((double)(s0.var_x + s0.var_y));
                    double mg = (double)pf_specaa_kernel_normal(dnx, dny, PF_R(0.25), PF_R(0.18));
                    double an = fmin(ae + mg, 1.0);
                    res[SM_GODOT] = sc_shade(&g, pf_specaa_slope_stats(s0, (pf_real)fmax(an * an - ae * ae, 0.0)));
                }
                {   /* vMF: one lobe from the mip's averaged unit normal (Banerjee et al. 2005) */
                    double r = sqrt((double)pf_vec3_dot(nav, nav));
                    pf_vec3 mu = r > 0 ? pf_vec3_scale(nav, (pf_real)(1.0 / r)) : pf_vec3_make(0, 0, 1);
                    pf_real kap = pf_vmf_kappa_from_mean_length((pf_real)r);
                    res[SM_VMF_NONE] = sc_shade(&g, pf_vmf_lobe_slope_stats(mu, kap, (pf_real)bv));
                    res[SM_VMF_BOX] = sc_shade(&g, pf_vmf_lobe_slope_stats(mu, pf_specaa_vmf_kappa(kap, kbox), (pf_real)bv));
                }
            }
            for (m = 0; m < SM_COUNT; ++m) img[m * (long long)W * W + p] = res[m];
        }
}

/* runs the scenes and appends their table to md, rows to csv */
static void sc_bench(int quick, FILE *md, FILE *csv)
{
    int si, scene, ai, m, fr;
    long long njob, total = 0;
    if (quick) { sc_S = 8; sc_F = 6; sc_diam[1] = 24.0; }
    sc_build_map();
    for (si = 0; si < SC_NSIZE; ++si) sc_W[si] = (int)sc_diam[si] + 5;
    sc_dev_stride = (long long)sc_W[SC_NSIZE - 1] * sc_W[SC_NSIZE - 1];
    sc_img_stride = SM_COUNT * sc_dev_stride;
    njob = sc_njobs();
    sc_img = (double *)malloc(sizeof(double) * (size_t)(njob * sc_img_stride));
    sc_dev2 = (double *)malloc(sizeof(double) * (size_t)(njob * sc_dev_stride));
    sc_full = (unsigned char *)malloc((size_t)(njob * sc_dev_stride));
    if (!sc_img || !sc_dev2 || !sc_full) { fprintf(stderr, "specaa: out of memory\n"); exit(1); }
    pfb_parallel_for(njob, sc_run, NULL, "specaa: curved scenes");
    fprintf(md, "\n#### Curved, normal-mapped scenes: the geometry kernel with LEADR and vMF, the engines' kernels\n\n"
                "Orthographic sphere and cylinder, %g and %g px across, plain or with a tiling normal map (RMS slope 0.08 per "
                "axis, about %.0f-%.0f texels per pixel at the centre), one BRDF for all (pf_leadr_specular: Beckmann, Smith, "
                "f0 = 1), base alpha %g and %g. Reference: %dx%d stratified rays per pixel (box filter), each shading its texel "
                "in its own frame; oracle: the exact mean and covariance of those rays' slopes in the pixel centre's frame. "
                "%d frames of a sub-pixel camera path (1 px along x, 0.37 px along y in all). **err** = RMS error against the "
                "reference / the oracle's; **flk** = RMS frame-to-frame change per pixel / the reference's own. Reference "
                "deviation, relative to the mean: measured (the RMS difference to a second reference of independent jitter, "
                "/ sqrt 2), the i.i.d. bound (the rays' variance / (n - 1): the stratification makes the true one far smaller), "
                "and the bound's share of the reference's frame-to-frame change (sqrt 2 x bound / change). Texture reads: one "
                "trilinear read at the GPU's isotropic lod unless named; \"aniso fetch\": a GPU's anisotropic rule (up to 16 "
                "trilinear taps along the major axis at the minor axis' level); \"cross term\": (4) of pf_specaa.h from the read's "
                "mean-slope derivatives; \"4 quadrant\": pf_specaa_slope_stats_quad; \"exact\" and \"diag\" columns are "
                "diagnostics from the reference's rays (docs/specaa.md, section 3).%s\n\n",
            sc_diam[0], sc_diam[1], SC_N * SC_REP / (3.14159265358979323846 * sc_diam[1]),
            SC_N * SC_REP / (3.14159265358979323846 * sc_diam[0]), sc_alpha[0], sc_alpha[1], sc_S, sc_S, sc_F,
            quick ? " BENCH_QUICK: smoke run, not for publication." : "");
    fprintf(md, "| scene | px | alpha | ref. deviation: measured / iid bound / share | oracle err | interior: box / oracle |");
    for (m = 0; m < SM_ORACLE; ++m) fprintf(md, " %s: err / flk |", sc_meth_name[m]);
    fprintf(md, " oracle flk |\n| --- | ---: | ---: | ---: | ---: | ---: |");
    for (m = 0; m < SM_ORACLE; ++m) fprintf(md, " ---: |");
    fprintf(md, " ---: |\n");
    fprintf(csv, "scene,diameter_px,alpha,method,rel_rms_err,err_over_oracle,interior_err_over_oracle,flicker,flicker_over_ref,ref_rel_dev,ref_noise_share,pixels,frames,spp,ref_rel_dev_measured\n");
    for (scene = 0; scene < SC_NSCENE; ++scene)
        for (si = 0; si < SC_NSIZE; ++si)
            for (ai = 0; ai < SC_NALPHA; ++ai) {
                int W = sc_W[si];
                long long WW = (long long)W * W, p, np = 0, nd = 0;
                double ei2[SM_COUNT] = { 0 }, erri[SM_COUNT];
                long long ni = 0;
                double e2[SM_COUNT] = { 0 }, d2[SM_COUNT] = { 0 }, rs = 0, dv = 0, err[SM_COUNT], flk[SM_COUNT];
                long long j0 = (((long long)scene * SC_NSIZE + si) * SC_NALPHA + ai) * sc_F;
                double tot[SM_COUNT], tm[SM_COUNT] = { 0 }, tv[SM_COUNT] = { 0 };
                int row = (scene * SC_NSIZE + si) * SC_NALPHA + ai;
                for (fr = 0; fr < sc_F; ++fr) {
                    const double *img = sc_img + (j0 + fr) * sc_img_stride;
                    for (m = 0; m < SM_COUNT; ++m) tot[m] = 0.0;
                    for (p = 0; p < WW; ++p)
                        if (!isnan(img[SM_REF * WW + p]))
                            for (m = 0; m < SM_COUNT; ++m) tot[m] += img[m * WW + p];
                    for (m = 0; m < SM_COUNT; ++m) { tm[m] += tot[m]; tv[m] += tot[m] * tot[m]; }
                }
                for (m = 0; m < SM_COUNT; ++m) {
                    tm[m] /= sc_F;
                    sc_total_flk[row][m] = sqrt(fmax(tv[m] / sc_F - tm[m] * tm[m], 0.0)) / tm[m];
                }
                for (fr = 0; fr < sc_F; ++fr) {
                    const double *img = sc_img + (j0 + fr) * sc_img_stride, *prev = fr ? sc_img + (j0 + fr - 1) * sc_img_stride : NULL;
                    const double *dev = sc_dev2 + (j0 + fr) * sc_dev_stride;
                    for (p = 0; p < WW; ++p) {
                        double r = img[SM_REF * WW + p];
                        if (isnan(r)) continue;
                        ++np; rs += r; dv += dev[p];
                        for (m = 0; m < SM_COUNT; ++m) { double d = img[m * WW + p] - r; e2[m] += d * d; }
                        if (sc_full[(j0 + fr) * sc_dev_stride + p]) {
                            ++ni;
                            for (m = 0; m < SM_COUNT; ++m) { double d = img[m * WW + p] - r; ei2[m] += d * d; }
                        }
                        if (prev && !isnan(prev[SM_REF * WW + p])) {
                            ++nd;
                            for (m = 0; m < SM_COUNT; ++m) { double d = img[m * WW + p] - prev[m * WW + p]; d2[m] += d * d; }
                        }
                    }
                }
                total += np;
                rs /= (double)np;
                for (m = 0; m < SM_COUNT; ++m) {
                    err[m] = sqrt(e2[m] / np) / rs;
                    flk[m] = sqrt(d2[m] / nd) / rs;
                    erri[m] = ni ? sqrt(ei2[m] / ni) / rs : 0.0;
                }
                fprintf(md, "| %s | %g | %g | %.4f / %.4f / %.2f | %.4f |", sc_scene_name[scene], sc_diam[si], sc_alpha[ai],
                        err[SM_REF2] / sqrt(2.0), sqrt(dv / np) / rs, sqrt(2.0 * dv / np) / rs / flk[SM_REF], err[SM_ORACLE]);
                fprintf(md, " %.2f |", erri[SM_ORACLE] > 0 ? erri[SM_BOX] / erri[SM_ORACLE] : 0.0);
                for (m = 0; m < SM_ORACLE; ++m)
                    fprintf(md, " %s%.2f%s / %s%.2f%s |", err[m] <= 1.5 * err[SM_ORACLE] ? "**" : "", err[m] / err[SM_ORACLE],
                            err[m] <= 1.5 * err[SM_ORACLE] ? "**" : "", flk[m] <= 1.5 * flk[SM_REF] ? "**" : "",
                            flk[m] / flk[SM_REF], flk[m] <= 1.5 * flk[SM_REF] ? "**" : "");
                fprintf(md, " %.2f |\n", flk[SM_ORACLE] / flk[SM_REF]);
                for (m = 0; m < SM_REF; ++m)
                    fprintf(csv, "\"%s\",%g,%g,\"%s\",%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%lld,%d,%d,%.5g\n", sc_scene_name[scene], sc_diam[si], sc_alpha[ai],
                            sc_meth_name[m], err[m], err[m] / err[SM_ORACLE], erri[SM_ORACLE] > 0 ? erri[m] / erri[SM_ORACLE] : 0.0, flk[m], flk[m] / flk[SM_REF], sqrt(dv / np) / rs,
                            sqrt(2.0 * dv / np) / rs / flk[SM_REF], np / sc_F, sc_F, sc_S * sc_S, err[SM_REF2] / sqrt(2.0));
            }
    fprintf(md, "\nThe previous sphere table's flicker measure, the deviation over the frames of the image's TOTAL radiance / "
                "its mean, on the plain scenes: the box-filtered reference's total is nearly invariant under a sub-pixel shift "
                "(the sum of box-filtered pixels is the integral of the image), so every single-sample method looks many times "
                "worse than the reference there, whatever its per-pixel agreement.\n\n| scene | px | alpha | reference | %s | %s | %s |\n"
                "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n", sc_meth_name[SM_NONE], sc_meth_name[SM_BOX], sc_meth_name[SM_TK]);
    for (scene = 0; scene < SC_NSCENE; scene += 2)
        for (si = 0; si < SC_NSIZE; ++si)
            for (ai = 0; ai < SC_NALPHA; ++ai) {
                const double *t = sc_total_flk[(scene * SC_NSIZE + si) * SC_NALPHA + ai];
                fprintf(md, "| %s | %g | %g | %.5f | %.5f | %.5f | %.5f |\n", sc_scene_name[scene], sc_diam[si], sc_alpha[ai], t[SM_REF],
                        t[SM_NONE], t[SM_BOX], t[SM_TK]);
            }
    fprintf(md, "\nBold: within the issue's 1.5x (error of the oracle, flicker of the reference). Every number per "
                "scene, size and alpha: `bench/out/specaa_scenes.csv`.\n");
    (void)total;
    free(sc_img); free(sc_dev2); free(sc_full); free(sc_slope); free(sc_pyr); free(sc_npyr);
}

#ifdef SC_RUN_REF /* defined by the includer that calls it (an unused static function is an error) */
/* sc_run for a caller that needs only the reference and the oracle (bench/frame/frame_curved.h,
   which shades its own forms): job as sc_run; fills img[SM_REF] and img[SM_ORACLE] (NaN off the
   surface; every other method's plane left as it was), dev2 and full. The same rays, seeds and
   oracle moments as sc_run (sc_pixel_rays), so the two agree to the bit on those planes; without
   the second reference and the methods (their texture reads) it costs about half of sc_run. */
static void sc_run_ref(void *ctx, long long job)
{
    int fr, ai, si, scene, W, px, py;
    double R, a, bv, cx, cy;
    double *img = sc_img + job * sc_img_stride, *dev2 = sc_dev2 + job * sc_dev_stride;
    unsigned char *full = sc_full + job * sc_dev_stride;
    sc_job_indices(job, &fr, &ai, &si, &scene);
    R = 0.5 * sc_diam[si];
    a = sc_alpha[ai];
    bv = 0.5 * a * a;
    W = sc_W[si];
    cx = 0.5 * W + 0.13 + (double)fr / sc_F;
    cy = 0.5 * W + 0.41 + 0.37 * fr / sc_F;
    (void)ctx;
    for (py = 0; py < W; ++py)
        for (px = 0; px < W; ++px) {
            long long p = (long long)py * W + px, WW = (long long)W * W;
            double x = px + 0.5, y = py + 0.5, o[5];
            sc_geo g;
            sc_rays r;
            int i;
            img[SM_REF * WW + p] = img[SM_ORACLE * WW + p] = (double)NAN;
            dev2[p] = (double)NAN;
            full[p] = 0;
            if (!sc_eval(scene, R, cx, cy, x, y, &g)) continue;
            r = sc_pixel_rays(scene, R, cx, cy, x, y, p, fr, 0x5ceULL, &g, bv);
            full[p] = r.hits == sc_S * sc_S;
            img[SM_REF * WW + p] = r.sum / r.hits;
            dev2[p] = r.hits > 1 ? fmax(r.sum2 / r.hits - (r.sum / r.hits) * (r.sum / r.hits), 0.0) / (r.hits - 1) : 0.0;
            for (i = 0; i < 5; ++i) o[i] = r.o[i] / r.hits;
            img[SM_ORACLE * WW + p] = sc_shade(&g, pf_slope_moments_stats(pf_slope_moments_make((pf_real)o[0], (pf_real)o[1],
                (pf_real)o[2], (pf_real)o[3], (pf_real)o[4]), (pf_real)bv));
        }
}
#endif

/* bench_gaussgrid.c - error versus cost of pf_gaussgrid.h: node set and N for LEADR's diffuse
   and specular-environment integrals (Dupuy et al. 2013 eqs. 19, 21-23).

   The question: which node set and N is the cheapest for a given error budget, and can 9
   samples (3x3) match LEADR's 5x5 uniform grid (25 samples)?

   Inputs: a fixed corpus of NCFG configurations drawn once from a fixed seed (view up to 80
   deg, light up to 70 deg, mean slope up to 0.3 per axis, per-axis deviation 0.05-0.8 log-
   uniform, correlation -0.8..0.8); a method's input x is the index of a configuration.
   Families
     diffuse       one directional light, pf_gg_diffuse_directional (eq. 21 on the grid, no SH),
                   LEADR's uniform 5x5 as the BASELINE, other N of the uniform grid and N = 2..5
                   of Gauss-Hermite and of the moment-matched grid.
     specular_env  eq. 22 summed over pf_gg_env_sample_at, F = 1, with a smooth environment
                   L(w) = 0.2 + exp(3 (w.d - 1)) evaluated exactly at each reflected direction (no
                   prefiltering: the quadrature error alone), same methods.
     diffuse_sh    LEADR algorithms 2 + 3 (SH irradiance, one light) against the direct
                   evaluation, for the uniform 5x5 and the matched 3x3 grids.
   REFERENCE (long double, independent of the header): adaptive 2D Gauss-Kronrod quadrature
   (tests/reference/pf_oracle.h) over the slope plane of the same integrand, Lambda from the closed form
   with erfcl. Relative error; max over the corpus in the table, and the error-budget notes
   (cheapest N^2 per budget) from max and mean errors computed before timing.

   The grids are heavy (up to 81 samples), so this bench times fewer inputs and repetitions
   than the default (PFB_N, PFB_REPS below); ratios to the baseline stay meaningful. */
#define PFB_N 2048
#define PFB_REPS 21
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_gaussgrid.h"
#include "pf_oracle.h"

#define NCFG 48

static pf_vec3 cfg_wo[NCFG], cfg_wi[NCFG];
static pf_slope_stats cfg_st[NCFG];
static long double ref_diffuse[NCFG], ref_specular[NCFG];
static const long double pil = 3.14159265358979323846264338327950288L;

/* environment direction (unit) */
#define ENV_DX 0.48
#define ENV_DY -0.36
#define ENV_DZ 0.8

/* ---------------------------------------------------------------- evaluators */
static pf_real env_radiance(pf_vec3 w)
{
    return PF_R(0.2) + PF_EXP(PF_R(3.0) * (w.x * PF_R(ENV_DX) + w.y * PF_R(ENV_DY) + w.z * PF_R(ENV_DZ) - PF_R(1.0)));
}

static pf_real eval_diffuse(pf_real x, int set, int n)
{
    int i = (int)x;
    return pf_gg_diffuse_directional(pf_gg_grid_make(cfg_wo[i], cfg_st[i], set, n), cfg_wi[i]);
}

static pf_real eval_specular(pf_real x, int set, int n)
{
    int i = (int)x, k;
    pf_gg_grid g = pf_gg_grid_make(cfg_wo[i], cfg_st[i], set, n);
    pf_real acc = PF_R(0.0);
    for (k = 0; k < pf_gg_grid_count(g); ++k) {
        pf_gg_env_sample e = pf_gg_env_sample_at(g, k);
        acc += e.weight * env_radiance(e.dir);
    }
    return acc;
}

static pf_real eval_diffuse_sh(pf_real x, int set, int n)
{
    int i = (int)x;
    pf_gg_grid g = pf_gg_grid_make(cfg_wo[i], cfg_st[i], set, n);
    pf_sh9 sh = pf_gg_sh9_add_light(pf_sh9_constant(PF_R(0.0)), g, cfg_wi[i], PF_R(1.0));
    return pf_gg_diffuse_sh(g, sh);
}

#define METHODS(fam, fn)                                                            \
    PFB_METHOD(fam##_u2, fn(x, PF_GG_UNIFORM, 2))                                   \
    PFB_METHOD(fam##_u3, fn(x, PF_GG_UNIFORM, 3))                                   \
    PFB_METHOD(fam##_u5, fn(x, PF_GG_UNIFORM, 5))                                   \
    PFB_METHOD(fam##_u7, fn(x, PF_GG_UNIFORM, 7))                                   \
    PFB_METHOD(fam##_u9, fn(x, PF_GG_UNIFORM, 9))                                   \
    PFB_METHOD(fam##_h2, fn(x, PF_GG_HERMITE, 2))                                   \
    PFB_METHOD(fam##_h3, fn(x, PF_GG_HERMITE, 3))                                   \
    PFB_METHOD(fam##_h4, fn(x, PF_GG_HERMITE, 4))                                   \
    PFB_METHOD(fam##_h5, fn(x, PF_GG_HERMITE, 5))                                   \
    PFB_METHOD(fam##_m3, fn(x, PF_GG_MATCHED, 3))                                   \
    PFB_METHOD(fam##_m4, fn(x, PF_GG_MATCHED, 4))                                   \
    PFB_METHOD(fam##_m5, fn(x, PF_GG_MATCHED, 5))

METHODS(dif, eval_diffuse)
METHODS(spe, eval_specular)
PFB_METHOD(sh_u5, eval_diffuse_sh(x, PF_GG_UNIFORM, 5))
PFB_METHOD(sh_m3, eval_diffuse_sh(x, PF_GG_MATCHED, 3))
PFB_METHOD(direct_u5, eval_diffuse(x, PF_GG_UNIFORM, 5))
PFB_METHOD(direct_m3, eval_diffuse(x, PF_GG_MATCHED, 3))

/* ---------------------------------------------------------------- references */
typedef struct refcfg {
    long double wox, woy, woz, wix, wiy, wiz, mx, my, vx, vy, cxy;
} refcfg;

static refcfg ld_cfg(int i)
{
    refcfg c;
    c.wox = (long double)cfg_wo[i].x; c.woy = (long double)cfg_wo[i].y; c.woz = (long double)cfg_wo[i].z;
    c.wix = (long double)cfg_wi[i].x; c.wiy = (long double)cfg_wi[i].y; c.wiz = (long double)cfg_wi[i].z;
    c.mx = (long double)cfg_st[i].mean_x; c.my = (long double)cfg_st[i].mean_y;
    c.vx = (long double)cfg_st[i].var_x; c.vy = (long double)cfg_st[i].var_y; c.cxy = (long double)cfg_st[i].cov_xy;
    return c;
}

static long double lambda_ld(const refcfg *c, long double wx, long double wy, long double wz)
{
    long double num = wz - wx * c->mx - wy * c->my;
    long double var = wx * wx * c->vx + wy * wy * c->vy + 2.0L * wx * wy * c->cxy, nu;
    if (num <= 0.0L) return HUGE_VALL;
    if (var <= 0.0L) return 0.0L;
    nu = num / sqrtl(2.0L * var);
    return pf_oracle_lambda_beckmann(nu);
}

static long double p22(const refcfg *c, long double x, long double y)
{
    return pf_oracle_normal2_pdf(x - c->mx, y - c->my, c->vx, c->vy, c->cxy);
}

static long double diffuse_f(long double x, long double y, void *ctx)
{
    const refcfg *c = (const refcfg *)ctx;
    long double po = c->woz - x * c->wox - y * c->woy, pi_ = c->wiz - x * c->wix - y * c->wiy;
    if (po <= 0.0L || pi_ <= 0.0L) return 0.0L;
    return po * pi_ / sqrtl(1.0L + x * x + y * y) * p22(c, x, y);
}

static long double specular_f(long double x, long double y, void *ctx)
{
    const refcfg *c = (const refcfg *)ctx;
    long double po = c->woz - x * c->wox - y * c->woy, q, d, w0, w1, w2, li;
    if (po <= 0.0L) return 0.0L;
    q = sqrtl(1.0L + x * x + y * y);
    d = po / q;
    w0 = -2.0L * d * x / q - c->wox;
    w1 = -2.0L * d * y / q - c->woy;
    w2 = 2.0L * d / q - c->woz;
    li = lambda_ld(c, w0, w1, w2);
    if (li >= HUGE_VALL) return 0.0L;
    return po * (0.2L + expl(3.0L * (w0 * ENV_DX + w1 * ENV_DY + w2 * ENV_DZ - 1.0L))) /
           (1.0L + lambda_ld(c, c->wox, c->woy, c->woz) + li) * p22(c, x, y);
}

static int ypts(long double x, long double *pts, int max_points, void *ctx)
{
    const refcfg *c = (const refcfg *)ctx;
    int n = 0;
    if (max_points < 3) return 0;
    if (c->woy != 0.0L) pts[n++] = (c->woz - c->wox * x) / c->woy;
    if (c->wiy != 0.0L) pts[n++] = (c->wiz - c->wix * x) / c->wiy;
    pts[n++] = c->my + c->cxy / c->vx * (x - c->mx);
    return n;
}

static long double slope_integral(pf_oracle_fn2 f, refcfg *c)
{
    pf_oracle_2d pb = pf_oracle_2d_make(f, c, -HUGE_VALL, HUGE_VALL, -HUGE_VALL, HUGE_VALL);
    long double xp[1];
    xp[0] = c->mx;
    pb.xpoints = xp;
    pb.nxpoints = 1;
    pb.ypoints = ypts;
    pb.epsrel = 1e-9L;
    pb.max_intervals = 300;
    return pf_oracle_integrate_2d(&pb).value;
}

/* reference `item`: the diffuse (even) or specular (odd) integral of configuration item / 2 */
static void corpus_ref_item(void *ctx, long long item)
{
    int i = (int)(item / 2);
    refcfg c = ld_cfg(i);
    long double den = c.woz - c.wox * c.mx - c.woy * c.my;
    (void)ctx;
    if (item % 2 == 0) {
        long double li = lambda_ld(&c, c.wix, c.wiy, c.wiz);
        ref_diffuse[i] = li >= HUGE_VALL ? 0.0L
                         : slope_integral(diffuse_f, &c) / (pil * den * (1.0L + lambda_ld(&c, c.wox, c.woy, c.woz) + li));
    } else {
        ref_specular[i] = slope_integral(specular_f, &c) / den;
    }
}

static void make_corpus(int with_refs)
{
    pfb_rng r;
    int i;
    r.s = 0x6a55u;
    for (i = 0; i < NCFG; ++i) {
      for (;;) { /* redraw until view and light are well above the mesosurface (shading is not ~0) */
        double to = pfb_unif_in(&r, 0.0, 1.4), po = pfb_unif_in(&r, -3.14159, 3.14159);
        double ti = pfb_unif_in(&r, 0.0, 1.22), pi_ = pfb_unif_in(&r, -3.14159, 3.14159);
        double sx = pfb_logunif(&r, 0.05, 0.8), sy = pfb_logunif(&r, 0.05, 0.8), rho = pfb_unif_in(&r, -0.8, 0.8);
        double mx = pfb_unif_in(&r, -0.3, 0.3), my = pfb_unif_in(&r, -0.3, 0.3);
        refcfg c;
        long double den;
        cfg_wo[i] = pf_vec3_make((pf_real)(sin(to) * cos(po)), (pf_real)(sin(to) * sin(po)), (pf_real)cos(to));
        cfg_wi[i] = pf_vec3_make((pf_real)(sin(ti) * cos(pi_)), (pf_real)(sin(ti) * sin(pi_)), (pf_real)cos(ti));
        cfg_st[i] = pf_slope_stats_make((pf_real)mx, (pf_real)my, (pf_real)(sx * sx), (pf_real)(sy * sy), (pf_real)(rho * sx * sy));
        c = ld_cfg(i);
        den = c.woz - c.wox * c.mx - c.woy * c.my;
        if (den < 0.15L || c.wiz - c.wix * c.mx - c.wiy * c.my < 0.15L) continue;
        break;
      }
    }
    /* the references (2D quadratures, most of this bench's setup) on every core: one work item
       per configuration and integral, each writing its own slot; only the accuracy columns read
       them, so --list and --only (the callgrind counts, run under valgrind) skip them */
    if (with_refs) pfb_parallel_for(2 * NCFG, corpus_ref_item, NULL, "bench_gaussgrid: corpus references");
}

static long double rf_diffuse(long double x, long double y, long double z) { (void)y; (void)z; return ref_diffuse[(int)x]; }
static long double rf_specular(long double x, long double y, long double z) { (void)y; (void)z; return ref_specular[(int)x]; }

/* ---------------------------------------------------------------- inputs */
static void gen_idx(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) a[i] = (pf_real)(int)(pfb_unif(r) * NCFG);
    memset(b, 0, n * sizeof *b);
    memset(c, 0, n * sizeof *c);
}

static size_t grid_idx(pf_real *a, pf_real *b, pf_real *c)
{
    size_t i;
    if (!a) return NCFG;
    for (i = 0; i < NCFG; ++i) a[i] = (pf_real)i;
    memset(b, 0, NCFG * sizeof *b);
    memset(c, 0, NCFG * sizeof *c);
    return NCFG;
}

/* ---------------------------------------------------------------- error budgets (notes) */
static char notes_diffuse[4096], notes_specular[4096], notes_sh[1024];
static const char *set_label[3] = { "uniform", "hermite", "matched" };

static void budget_notes(char *out, size_t cap, pf_real (*fn)(pf_real, int, int), const long double *ref, const char *head)
{
    long double emax[3][PF_GG_MAX_N + 1], emean[3][PF_GG_MAX_N + 1];
    const double budgets[3] = { 0.10, 0.03, 0.01 };
    size_t used = 0;
    int set, n, i, b;
    for (set = 0; set < 3; ++set)
        for (n = 1; n <= PF_GG_MAX_N; ++n) {
            emax[set][n] = emean[set][n] = 0.0L;
            for (i = 0; i < NCFG; ++i) {
                long double e = fabsl((long double)fn((pf_real)i, set, n) - ref[i]) / fabsl(ref[i]);
                if (e > emax[set][n]) emax[set][n] = e;
                emean[set][n] += e / NCFG;
            }
        }
    used += (size_t)snprintf(out + used, cap - used, "%s\n", head);
    for (set = 0; set < 3; ++set) {
        used += (size_t)snprintf(out + used, cap - used, "max (mean) relative error over the corpus, %s N=1..9:", set_label[set]);
        for (n = 1; n <= PF_GG_MAX_N; ++n)
            used += (size_t)snprintf(out + used, cap - used, " %s%d: %.2g (%.2g)", n > 1 ? "; " : "", n, (double)emax[set][n],
                                     (double)emean[set][n]);
        used += (size_t)snprintf(out + used, cap - used, "\n");
    }
    for (b = 0; b < 3; ++b) {
        int m;
        for (m = 0; m < 2; ++m) {
            int best_set = -1, best_n = 0;
            for (n = 1; n <= PF_GG_MAX_N && best_set < 0; ++n)
                for (set = 0; set < 3; ++set) {
                    long double e = m == 0 ? emax[set][n] : emean[set][n];
                    if (e <= (long double)budgets[b] && (best_set < 0 || e < (m == 0 ? emax : emean)[best_set][n])) best_set = set;
                    if (best_set >= 0) best_n = n;
                }
            if (best_set < 0)
                used += (size_t)snprintf(out + used, cap - used, "budget %.0f%% (%s error): no node set with N <= 9\n",
                                         100.0 * budgets[b], m == 0 ? "max" : "mean");
            else
                used += (size_t)snprintf(out + used, cap - used,
                                         "budget %.0f%% (%s error): cheapest is %s N=%d (%d samples, %s error %.2g)\n",
                                         100.0 * budgets[b], m == 0 ? "max" : "mean", set_label[best_set], best_n,
                                         best_n * best_n, m == 0 ? "max" : "mean",
                                         (double)(m == 0 ? emax : emean)[best_set][best_n]);
        }
    }
    used += (size_t)snprintf(out + used, cap - used,
                             "LEADR's uniform 5x5: max %.2g, mean %.2g; best 3x3 (9 samples): %s max %.2g, mean %.2g",
                             (double)emax[0][5], (double)emean[0][5],
                             emax[2][3] < emax[1][3] ? "matched" : "hermite",
                             (double)(emax[2][3] < emax[1][3] ? emax[2][3] : emax[1][3]),
                             (double)(emax[2][3] < emax[1][3] ? emean[2][3] : emean[1][3]));
}

/* ---------------------------------------------------------------- families */
#define CORPUS_NOTE                                                                               \
    "corpus: 48 fixed configurations (seeded): view theta 0-80 deg, light theta 0-70 deg, both at least 0.15 above "  \
    "the mesosurface (w.z - w.E >= 0.15), mean slope |E| <= 0.3 per axis, deviation 0.05-0.8 per axis (log-uniform), correlation -0.8..0.8; timing "  \
    "inputs: 2048 random picks from it; cost of a row = N^2 samples (name: u/h/m = uniform/hermite/matched, N)"

#define ENTRIES(fam, ref)                                                                        \
    { PFB_ENTRY("uniform_5x5_leadr", fam##_u5, ref, 0), PFB_ENTRY("uniform_2x2", fam##_u2, ref, 0), \
      PFB_ENTRY("uniform_3x3", fam##_u3, ref, 0), PFB_ENTRY("uniform_7x7", fam##_u7, ref, 0),        \
      PFB_ENTRY("uniform_9x9", fam##_u9, ref, 0), PFB_ENTRY("hermite_2x2", fam##_h2, ref, 0),        \
      PFB_ENTRY("hermite_3x3", fam##_h3, ref, 0), PFB_ENTRY("hermite_4x4", fam##_h4, ref, 0),        \
      PFB_ENTRY("hermite_5x5", fam##_h5, ref, 0), PFB_ENTRY("matched_3x3", fam##_m3, ref, 0),        \
      PFB_ENTRY("matched_4x4", fam##_m4, ref, 0), PFB_ENTRY("matched_5x5", fam##_m5, ref, 0) }

static pfb_family families[] = {
    { "diffuse", 1, { "config", NULL }, 0, notes_diffuse, gen_idx, grid_idx, 12, ENTRIES(dif, rf_diffuse) },
    { "specular_env", 1, { "config", NULL }, 0, notes_specular, gen_idx, grid_idx, 12, ENTRIES(spe, rf_specular) },
    { "diffuse_sh", 1, { "config", NULL }, 0, notes_sh, gen_idx, grid_idx, 4,
      { PFB_ENTRY("sh_uniform_5x5_leadr", sh_u5, rf_diffuse, 0), PFB_ENTRY("sh_matched_3x3", sh_m3, rf_diffuse, 0),
        PFB_ENTRY("direct_uniform_5x5", direct_u5, rf_diffuse, 0), PFB_ENTRY("direct_matched_3x3", direct_m3, rf_diffuse, 0) } },
};

int main(int argc, char **argv)
{
    int listing = argc > 1 && (strcmp(argv[1], "--list") == 0 || strcmp(argv[1], "--only") == 0);
    make_corpus(!listing);
    if (!listing) {
        budget_notes(notes_diffuse, sizeof notes_diffuse, eval_diffuse, ref_diffuse,
                     CORPUS_NOTE "\nintegral: LEADR eq. 21, one directional light, grid evaluation without SH "
                     "(pf_gg_diffuse_directional); reference: 2D adaptive quadrature over the slope plane, long double");
        budget_notes(notes_specular, sizeof notes_specular, eval_specular, ref_specular,
                     CORPUS_NOTE "\nintegral: LEADR eq. 22, F = 1, environment 0.2 + exp(3 (w.d - 1)), d = (0.48, -0.36, 0.8), "
                     "evaluated at each reflected direction (no prefiltering); reference: 2D quadrature of eq. 19, long double");
        snprintf(notes_sh, sizeof notes_sh, "%s\nLEADR algorithms 2 + 3: the light projected on 9 SH coefficients with "
                 "its masking-shadowing weight, then integrated over the grid (pf_gg_diffuse_sh); direct rows: the same "
                 "grid without SH (pf_gg_diffuse_directional)", CORPUS_NOTE);
    }
    return pfb_main(argc, argv, "gaussgrid", families, (int)(sizeof families / sizeof families[0]));
}

/* bench_moments.c - cost of pf_moments.h: whole pyramids (throughput against memcpy) and the
   log-space ESM reduction (cost and accuracy against the direct formula).

   Families
     esm_reduce2x2  pf_esm_log_reduce2x2 versus the direct log(mean(exp(l))) (the BASELINE,
                    which overflows float for l > 88.7; the accuracy grid stays below that so
                    both have finite errors), reference in long double. Inputs l0, l1, l2 and
                    l3 = (l0 + l1 + l2)/3.
     pyramid        whole 4096 x 4096 maps (2048 x 2048 in the double build, same bytes per
                    texel class): the 5-moment slope pyramid from a float height map
                    (pf_slope_pyramid_from_heights, one cascaded pass), the same built the
                    naive way (level 0 first, then each level from the previous one with the
                    shader evaluator pf_slope_moments_reduce2x2), pf_mip_build on a filled
                    level 0, and the depth pyramids (VSM, EVSM-4, MSM, ESM log). BASELINE:
                    memcpy of as many bytes as the 5-moment pyramid holds, timed in the same
                    run, back to back with every method (pairs, alternating order, median of
                    the per-pair ratios). ns/eval is per base texel; x baseline is time /
                    memcpy time of the same bytes: the bandwidth ratio to memcpy is
                    (bytes written / time) / (memcpy bytes / memcpy time), printed in the notes
                    as GB/s. Target: the 5-moment pyramid at >= half of memcpy's bandwidth.

   See pf_bench.h for what every column means; bench/run.sh (make bench) runs this. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include "pf_map.h"

/* ---------------------------------------------------------------- esm_reduce2x2 */
PFB_METHOD(esm_log, pf_esm_log_reduce2x2(x, y, z, (x + y + z) / PF_R(3.0)))
PFB_METHOD(esm_direct, PF_LOG(PF_R(0.25) * (PF_EXP(x) + PF_EXP(y) + PF_EXP(z) + PF_EXP((x + y + z) / PF_R(3.0)))))

static long double ref_esm(long double x, long double y, long double z)
{
    long double w = (long double)(((pf_real)x + (pf_real)y + (pf_real)z) / PF_R(3.0));
    return logl(0.25L * (expl(x) + expl(y) + expl(z) + expl(w)));
}

static void gen_esm(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        a[i] = (pf_real)pfb_unif_in(r, -80.0, 80.0);
        b[i] = (pf_real)pfb_unif_in(r, -80.0, 80.0);
        c[i] = (pf_real)pfb_unif_in(r, -80.0, 80.0);
    }
}

static size_t grid_esm(pf_real *a, pf_real *b, pf_real *c)
{
    size_t n = 0;
    int i, j, k;
    for (i = 0; i < 41; ++i)
        for (j = 0; j < 41; ++j)
            for (k = 0; k < 11; ++k) {
                if (a) {
                    a[n] = (pf_real)(-80.0 + 4.0 * i);
                    b[n] = (pf_real)(-80.0 + 4.0 * j + 0.37);
                    c[n] = (pf_real)(-80.0 + 16.0 * k + 0.11);
                }
                ++n;
            }
    return n;
}

static const pfb_family families[] = {
    { "esm_reduce2x2", 2, { "l0", "l1" }, 1,
      "inputs l0, l1, l2 in [-80, 80], l3 = mean of the three; reference log(mean(exp)) in long double\n"
      "the direct formula overflows float for l > 88.7 (exp), double for l > 709; the log-space one never",
      gen_esm, grid_esm, 2,
      { PFB_ENTRY("pf_esm_log_reduce2x2", esm_log, ref_esm, 0),
        PFB_ENTRY("direct_log_mean_exp", esm_direct, ref_esm, 0) } },
};

/* ---------------------------------------------------------------- pyramids */
#ifdef PF_DOUBLE
#  define PYR_SIZE 2048
#else
#  define PYR_SIZE 4096
#endif
#define PYR_REPS 11

typedef struct pyr_job {
    const pf_real *in;
    pf_real *out;
    int w, h;
} pyr_job;

typedef void (*pyr_fn)(const pyr_job *j);

static void run_slope(const pyr_job *j)
{
    pf_slope_pyramid_from_heights(j->in, j->w, j->h, PF_R(1.0) / (pf_real)j->w, PF_R(1.0) / (pf_real)j->h,
                                  PF_R(0.05), PF_BORDER_WRAP, j->out);
}

/* What a user writes with only the evaluators: level 0, then each level from the previous
   (even sizes only, as here). */
static void run_slope_naive(const pyr_job *j)
{
    int w = j->w, h = j->h, x, y;
    pf_real *src = j->out;
    pf_slope_moments_map_from_heights(j->in, w, h, PF_R(1.0) / (pf_real)w, PF_R(1.0) / (pf_real)h,
                                      PF_R(0.05), PF_BORDER_WRAP, src);
    while (w > 1 || h > 1) {
        int dw = pf_mip_next_size(w), dh = pf_mip_next_size(h);
        pf_real *dst = src + (size_t)w * (size_t)h * 5;
        for (y = 0; y < dh; ++y)
            for (x = 0; x < dw; ++x) {
                const pf_real *a = src + ((size_t)(2 * y) * (size_t)w + (size_t)(2 * x)) * 5;
                const pf_real *b = a + (size_t)w * 5;
                pf_slope_moments m = pf_slope_moments_reduce2x2(
                    pf_slope_moments_make(a[0], a[1], a[2], a[3], a[4]),
                    pf_slope_moments_make(a[5], a[6], a[7], a[8], a[9]),
                    pf_slope_moments_make(b[0], b[1], b[2], b[3], b[4]),
                    pf_slope_moments_make(b[5], b[6], b[7], b[8], b[9]));
                pf_real *o = dst + ((size_t)y * (size_t)dw + (size_t)x) * 5;
                o[0] = m.ex;
                o[1] = m.ey;
                o[2] = m.exx;
                o[3] = m.eyy;
                o[4] = m.exy;
            }
        src = dst;
        w = dw;
        h = dh;
    }
}

static void run_build5(const pyr_job *j)
{
    /* level 0 is already in out (left by the previous build); rebuild the levels above */
    pf_mip_build(j->out, j->w, j->h, 5);
}

static void run_vsm(const pyr_job *j) { pf_depth_pyramid_from_depths(j->in, j->w, j->h, PF_DEPTH_VSM, 0, 0, j->out); }
static void run_evsm4(const pyr_job *j)
{
    pf_depth_pyramid_from_depths(j->in, j->w, j->h, PF_DEPTH_EVSM4, PF_R(40.0), PF_R(10.0), j->out);
}
static void run_msm(const pyr_job *j) { pf_depth_pyramid_from_depths(j->in, j->w, j->h, PF_DEPTH_MSM, 0, 0, j->out); }
static void run_esm(const pyr_job *j)
{
    pf_depth_pyramid_from_depths(j->in, j->w, j->h, PF_DEPTH_ESM_LOG, PF_R(80.0), 0, j->out);
}

typedef struct pyr_method {
    const char *name;
    pyr_fn fn;
    int channels;
} pyr_method;

static const pyr_method pyr_methods[] = {
    { "pf_slope_pyramid_from_heights", run_slope, 5 },
    { "naive_level_by_level_5", run_slope_naive, 5 },
    { "pf_mip_build_5ch", run_build5, 5 },
    { "depth_vsm_2ch", run_vsm, 2 },
    { "depth_evsm4_4ch", run_evsm4, 4 },
    { "depth_msm_4ch", run_msm, 4 },
    { "depth_esm_log_1ch", run_esm, 1 },
};
#define N_PYR (int)(sizeof pyr_methods / sizeof pyr_methods[0])

static pf_real *memcpy_src, *memcpy_dst;
static size_t memcpy_bytes;

static double time_memcpy(void)
{
    double t0 = pfb_now_ns();
    memcpy(memcpy_dst, memcpy_src, memcpy_bytes);
    return pfb_now_ns() - t0;
}

static double time_job(pyr_fn fn, const pyr_job *j)
{
    pyr_fn volatile f = fn;
    double t0 = pfb_now_ns();
    f(j);
    return pfb_now_ns() - t0;
}

/* Each method timed back to back with the memcpy (pairs, which goes first alternating), after one
   untimed run of each; repetitions from that run's time for a budget of about budget_ms of
   pairs per method (pfb_budget_reps: PFB_MIN_REPS at least, reps at most). */
static void run_pyramids(int reps, double budget_ms, FILE *csv, FILE *notes)
{
    const int w = PYR_SIZE, h = PYR_SIZE;
    size_t texels = (size_t)w * (size_t)h, total = (size_t)pf_mip_texel_count(w, h), i;
    pf_real *in = (pf_real *)pfb_alloc(texels * sizeof(pf_real));
    pf_real *out = (pf_real *)pfb_alloc(total * 5 * sizeof(pf_real));
    double *tm = (double *)pfb_alloc((size_t)reps * sizeof(double));
    double *tb = (double *)pfb_alloc((size_t)reps * sizeof(double));
    double *ratio = (double *)pfb_alloc((size_t)reps * sizeof(double));
    pfb_rng rng;
    pyr_job job;
    pfb_progress progress;
    int m, r, n = reps;
    rng.s = PFB_SEED;
    for (i = 0; i < texels; ++i) in[i] = (pf_real)pfb_unif(&rng); /* heights and depths in [0, 1) */
    memcpy_bytes = total * 5 * sizeof(pf_real);
    memcpy_src = (pf_real *)pfb_alloc(memcpy_bytes);
    memcpy_dst = out; /* the memcpy writes the same buffer the pyramids write */
    for (i = 0; i < total * 5; ++i) memcpy_src[i] = PF_R(0.5); /* normal floats (a byte pattern
                                                                  could be subnormal: slow) */
    memset(out, 0, memcpy_bytes); /* first touch outside the timings */
    job.in = in;
    job.out = out;
    job.w = w;
    job.h = h;
    printf("\n== pyramid (%s)   baseline: memcpy of %.1f MB (the 5-moment pyramid's bytes)   %d x %d "
           "base, at most %d repetitions (time budget %.0f ms per method)\n", PFB_BUILD,
           (double)memcpy_bytes * 1e-6, w, h, reps, budget_ms);
    printf("  %-32s %10s %9s %15s %10s %10s %5s\n", "method", "ms", "x memcpy", "[q1,q3]", "GB/s", "memcpy GB/s",
           "reps");
    progress = pfb_progress_start("bench_moments (" PFB_BUILD "): pyramid timings", (long long)N_PYR * reps);
    for (m = 0; m < N_PYR; ++m) {
        const pyr_method *pm = &pyr_methods[m];
        double bytes = (double)total * (double)pm->channels * (double)sizeof(pf_real);
        double ms, q1, q3, med, base, gbs, mgbs;
        run_slope(&job); /* leave a valid 5-channel level 0 for pf_mip_build, warm up */
        n = pfb_budget_reps(time_job(pm->fn, &job) + time_memcpy(), budget_ms, reps);
        for (r = 0; r < n; ++r) {
            if (r & 1) {
                tb[r] = time_memcpy();
                tm[r] = time_job(pm->fn, &job);
            } else {
                tm[r] = time_job(pm->fn, &job);
                tb[r] = time_memcpy();
            }
            ratio[r] = tm[r] / tb[r];
            pfb_progress_update(&progress, (long long)m * reps + (long long)(r + 1) * reps / n);
        }
        med = pfb_quantile(ratio, n, 0.5);
        q1 = pfb_quantile(ratio, n, 0.25);
        q3 = pfb_quantile(ratio, n, 0.75);
        ms = pfb_quantile(tm, n, 0.5) * 1e-6;
        base = pfb_quantile(tb, n, 0.5) * 1e-6;
        gbs = bytes / (ms * 1e6);
        mgbs = (double)memcpy_bytes / (base * 1e6);
        printf("  %-32s %10.2f %9.3f [%6.3f,%6.3f] %10.2f %10.2f %5d\n", pm->name, ms, med, q1, q3, gbs, mgbs, n);
        if (csv)
            fprintf(csv, "pyramid,%s,%s,%.4f,%.4f,memcpy,,,,,,,%.4f,%.4f,,\n", pm->name, PFB_BUILD,
                    ms * 1e6 / (double)texels, med, q1, q3);
        if (notes)
            fprintf(notes, "pyramid\t%s (%s build): %.1f MB written in %.2f ms = %.2f GB/s; memcpy of %.1f MB in "
                    "%.2f ms = %.2f GB/s (same run); bandwidth ratio %.2f of memcpy\n", pm->name, PFB_BUILD,
                    bytes * 1e-6, ms, gbs, (double)memcpy_bytes * 1e-6, base, mgbs,
                    gbs / mgbs);
    }
    pfb_progress_end(&progress);
    if (csv) fprintf(csv, "pyramid,memcpy,%s,%.4f,1.0000,memcpy,,,,,,,1.0000,1.0000,,\n", PFB_BUILD,
                     pfb_quantile(tb, n, 0.5) / (double)texels);
    if (notes) {
        fprintf(notes, "pyramid\tbase %d x %d (%s build), heights/depths uniform in [0, 1); ns/eval is per base "
                "texel, x baseline = time / time of memcpy of the 5-moment pyramid's bytes (pairs, median)\n",
                w, h, PFB_BUILD);
        fprintf(notes, "pyramid\tbandwidth ratio = (bytes written / time) / (memcpy bytes / memcpy time); "
                "target >= 0.5 for pf_slope_pyramid_from_heights\n");
    }
    pfb_sink = out[total * 5 - 1] + memcpy_dst[0];
    free(in);
    free(out);
    free(memcpy_src);
    free(tm);
    free(tb);
    free(ratio);
}

int main(int argc, char **argv)
{
    const char *csv_file = NULL, *notes_file = NULL;
    int reps = PYR_REPS, i, rc;
    double budget_ms = PFB_BUDGET_MS;
    FILE *csv = NULL, *notes = NULL;
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--list") == 0 || strcmp(argv[i], "--only") == 0)
            return pfb_main(argc, argv, "moments", families, (int)(sizeof families / sizeof families[0]));
        if (i + 1 < argc && strcmp(argv[i], "--csv") == 0) csv_file = argv[i + 1];
        if (i + 1 < argc && strcmp(argv[i], "--notes") == 0) notes_file = argv[i + 1];
        if (i + 1 < argc && strcmp(argv[i], "--reps") == 0) reps = atoi(argv[i + 1]) < 3 ? 3 : (atoi(argv[i + 1]) > PYR_REPS ? PYR_REPS : atoi(argv[i + 1]));
        if (i + 1 < argc && strcmp(argv[i], "--budget-ms") == 0) budget_ms = atof(argv[i + 1]);
    }
    rc = pfb_main(argc, argv, "moments", families, (int)(sizeof families / sizeof families[0]));
    if (rc) return rc;
    if (csv_file && !(csv = fopen(csv_file, "a"))) { perror(csv_file); return 2; }
    if (notes_file && !(notes = fopen(notes_file, "a"))) { perror(notes_file); return 2; }
    run_pyramids(reps, budget_ms, csv, notes);
    if (csv) fclose(csv);
    if (notes) fclose(notes);
    return 0;
}

/* bench_shadow.c - cost and accuracy of pf_shadow.h: one shadow lookup per method on the
   synthetic shadow maps of tests/shadow_scenes.h.

   Family
     lookup   every method of pf_shadow.h at its default parameters, reading the filtered
              values of one footprint from a table (like a texture fetch after filtering) and
              the receiver depth: pf_shadow_vsm, the same with light-bleeding reduction 0.3,
              pf_shadow_esm, pf_shadow_evsm2, pf_shadow_evsm4, pf_shadow_msm. BASELINE:
              pcf_1tap, the unfiltered depth test of the footprint's centre texel (the cost of
              not filtering, and its aliasing error).

   INPUTS   The 5 scenes x 4 footprint sizes x 200 footprints x 4 receivers of
            tests/shadow_scenes.h (16000 lookups). Per lookup the tables hold the box-filtered
            values every method needs (pf_real), the centre texel and the brute-force truth.
            Timing: PFB_N lookups drawn at random from the 16000 (x = receiver depth, y = the
            lookup's index); the table loads are part of every method's cost (8 or 16 bytes).
   REFERENCE The brute-force lit fraction (the average of binary depth tests over the
            footprint's texels, exact), passed as the third input. Relative error is not
            meaningful for a fraction that is often 0 or tiny, and the max abs error is ~1 for
            every method: the entries use PFB_ENTRY_ABS where pf_bench.h has it (mean abs
            error in the CSV and on the chart); the notes add mean error and leak per scene
            and per receiver kind (computed here over the same lookups).

   See pf_bench.h for what every column means; bench/run.sh (make bench) runs this. */
#include "pf_bench.h" /* first: defines _POSIX_C_SOURCE */
#include <stdarg.h>
#include "pf_shadow.h"
#include "../tests/shadow_scenes.h"

#define NL (SHS_N_SCENES * SHS_LOOKUPS_PER_SCENE)

/* ---------------------------------------------------------------- tables (filled in main) */
static shs_lookup *g_lookups;
static pf_real *g_zc;
static pf_depth_moments2 *g_vsm, *g_evsm2;
static pf_evsm_moments *g_evsm4;
static pf_depth_moments4 *g_msm;
static pf_real *g_esm;

#define IDX(y) ((size_t)(y))

/* ---------------------------------------------------------------- methods: x = d, y = index */
PFB_METHOD(pcf1, x <= g_zc[IDX(y)] ? PF_R(1.0) : PF_R(0.0))
PFB_METHOD(vsm, pf_shadow_vsm(g_vsm[IDX(y)], x, PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT, PF_SHADOW_BLEED_DEFAULT))
PFB_METHOD(vsm_bleed, pf_shadow_vsm(g_vsm[IDX(y)], x, PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT, SHS_BLEED))
PFB_METHOD(esm, pf_shadow_esm(g_esm[IDX(y)], x, SHS_ESM_C))
PFB_METHOD(evsm2, pf_shadow_evsm2(g_evsm2[IDX(y)], x, SHS_EVSM_POS, PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT,
                                  PF_SHADOW_BLEED_DEFAULT))
PFB_METHOD(evsm4, pf_shadow_evsm4(g_evsm4[IDX(y)], x, SHS_EVSM_POS, SHS_EVSM_NEG,
                                  PF_SHADOW_VSM_MIN_VARIANCE_DEFAULT, PF_SHADOW_BLEED_DEFAULT))
PFB_METHOD(msm, pf_shadow_msm(g_msm[IDX(y)], x, PF_SHADOW_MSM_MOMENT_BIAS_DEFAULT, PF_SHADOW_MSM_DEPTH_BIAS_DEFAULT))

/* the truth travels as the third input */
static long double ref_truth(long double x, long double y, long double z)
{
    (void)x;
    (void)y;
    return z;
}

/* ---------------------------------------------------------------- inputs */
static void gen_lookups(pfb_rng *r, pf_real *a, pf_real *b, pf_real *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        size_t k = (size_t)(pfb_next(r) % (uint64_t)NL);
        a[i] = g_lookups[k].d;
        b[i] = (pf_real)k;
        c[i] = (pf_real)g_lookups[k].truth;
    }
}

static size_t grid_lookups(pf_real *a, pf_real *b, pf_real *c)
{
    size_t k;
    if (!a) return NL;
    for (k = 0; k < NL; ++k) {
        a[k] = g_lookups[k].d;
        b[k] = (pf_real)k;
        c[k] = (pf_real)g_lookups[k].truth;
    }
    return NL;
}

/* A lit fraction is often 0: with PFB_ENTRY_ABS (pf_bench.h, when present) the CSV and the
   chart carry the mean absolute error instead of a meaningless relative one. */
#ifdef PFB_ENTRY_ABS
#  define SH_ENTRY(name, id) PFB_ENTRY_ABS(name, id, ref_truth)
#else
#  define SH_ENTRY(name, id) PFB_ENTRY(name, id, ref_truth, 0)
#endif

static pfb_family families[] = {
    { "lookup", 2, { "d", "lookup" }, 0, NULL, gen_lookups, grid_lookups, 7,
      { SH_ENTRY("pcf_1tap", pcf1),
        SH_ENTRY("pf_shadow_vsm", vsm),
        SH_ENTRY("pf_shadow_vsm_bleed0.3", vsm_bleed),
        SH_ENTRY("pf_shadow_esm", esm),
        SH_ENTRY("pf_shadow_evsm2", evsm2),
        SH_ENTRY("pf_shadow_evsm4", evsm4),
        SH_ENTRY("pf_shadow_msm", msm) } },
};

/* ---------------------------------------------------------------- error figures for the notes */
static char g_notes[8192];

static void add_note(const char *fmt, ...)
{
    size_t used = strlen(g_notes);
    va_list ap;
    if (used + 2 >= sizeof g_notes) return;
    va_start(ap, fmt);
    vsnprintf(g_notes + used, sizeof g_notes - used, fmt, ap);
    va_end(ap);
}

static void build_notes(void)
{
    shs_stats all[SHS_N_METHODS], per[SHS_N_SCENES][SHS_N_METHODS], rec[SHS_N_RECEIVERS][SHS_N_METHODS];
    int m, s, k;
    size_t i;
    memset(all, 0, sizeof all);
    memset(per, 0, sizeof per);
    memset(rec, 0, sizeof rec);
    for (i = 0; i < NL; ++i) {
        const shs_lookup *L = &g_lookups[i];
        for (m = 0; m < SHS_N_METHODS; ++m) {
            long double v = (long double)shs_eval(m, L);
            shs_stats_add(&all[m], v, L->truth);
            shs_stats_add(&per[L->scene][m], v, L->truth);
            shs_stats_add(&rec[L->receiver][m], v, L->truth);
        }
    }
    g_notes[0] = '\0';
    add_note("inputs: %d lookups = %d scenes (", NL, SHS_N_SCENES);
    for (s = 0; s < SHS_N_SCENES; ++s) add_note("%s%s", s ? ", " : "", shs_scene_names[s]);
    add_note(") x footprints of 2, 4, 8, 16 texels square (%d each) x 4 receivers (ground, centre, between, "
             "contact), %ld of them fully shadowed; see tests/shadow_scenes.h\n", SHS_PER_SIZE, all[0].n_dark);
    add_note("reference: brute-force lit fraction (average of binary depth tests over the footprint); "
             "relative error is meaningless for a fraction: read the mean abs error\n");
#ifdef PF_DOUBLE
    /* the error figures are those of fp32 storage: written by the float build only (run.sh
       merges the notes of both builds) */
    families[0].notes = g_notes;
    return;
#endif
    for (m = 0; m < SHS_N_METHODS; ++m) {
        add_note("%s (%d bytes/texel, float build): mean abs error %.4f, mean leak %.4f (max %.2f) over all lookups; "
                 "mean error per scene", shs_method_names[m], shs_method_bytes[m], (double)shs_mean_err(&all[m]),
                 (double)shs_mean_leak(&all[m]), (double)all[m].max_leak);
        for (s = 0; s < SHS_N_SCENES; ++s)
            add_note(" %s %.4f", shs_scene_names[s], (double)shs_mean_err(&per[s][m]));
        add_note("; per receiver");
        for (k = 0; k < SHS_N_RECEIVERS; ++k)
            add_note(" %s %.4f", shs_receiver_names[k], (double)shs_mean_err(&rec[k][m]));
        add_note("\n");
    }
    families[0].notes = g_notes;
}

int main(int argc, char **argv)
{
    int s, rc;
    size_t i;
    g_lookups = (shs_lookup *)pfb_alloc(sizeof(shs_lookup) * NL);
    for (s = 0; s < SHS_N_SCENES; ++s) shs_scene_lookups(s, g_lookups + (size_t)s * SHS_LOOKUPS_PER_SCENE);
    g_zc = (pf_real *)pfb_alloc(sizeof(pf_real) * NL);
    g_vsm = (pf_depth_moments2 *)pfb_alloc(sizeof(pf_depth_moments2) * NL);
    g_evsm2 = (pf_depth_moments2 *)pfb_alloc(sizeof(pf_depth_moments2) * NL);
    g_evsm4 = (pf_evsm_moments *)pfb_alloc(sizeof(pf_evsm_moments) * NL);
    g_msm = (pf_depth_moments4 *)pfb_alloc(sizeof(pf_depth_moments4) * NL);
    g_esm = (pf_real *)pfb_alloc(sizeof(pf_real) * NL);
    for (i = 0; i < NL; ++i) {
        g_zc[i] = g_lookups[i].z_centre;
        g_vsm[i] = g_lookups[i].vsm;
        g_evsm2[i] = g_lookups[i].evsm2;
        g_evsm4[i] = g_lookups[i].evsm4;
        g_msm[i] = g_lookups[i].msm;
        g_esm[i] = g_lookups[i].esm_log;
    }
    build_notes();
    rc = pfb_main(argc, argv, "shadow", families, (int)(sizeof families / sizeof families[0]));
    free(g_lookups); free(g_zc); free(g_vsm); free(g_evsm2); free(g_evsm4); free(g_msm); free(g_esm);
    return rc;
}

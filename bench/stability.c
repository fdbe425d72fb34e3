/* bench/stability.c - the seeded stability sweep (issue 9, item 4).

   For every public evaluator (tests/fuzz/pf_calls.h: one entry each, inputs drawn inside the
   documented domain and biased toward its edges), N seeded random inputs; counts the calls
   with a non-finite output and those with an output outside its documented range. One build
   per run: compile it float, double, and both with -ffast-math (bench/stability.sh does).

   A second section sweeps the pointer-taking CPU-only functions (tests/fuzz/pf_buffers.h: sizes
   from the whole int range, exact-size guarded buffers, return codes against the contract of
   include/pf_core.h), counting wrong return codes, writes on error, out-of-bounds accesses (a
   fault on a guard page, caught and counted), non-finite outputs on finite in-domain inputs and
   wrong output values; STABILITY_BUFFERS_N calls per function (default 1000, 500 quick).

   usage: stability [--quick] [-n N] [--only NAME] [--seed S] [--label L] [--csv FILE] [--shard K/M]
          stability --list                       names of the entries and of the skipped ones
          stability --merge OUT.md OUT.csv A.csv [B.csv ...]   the report fragment
   BENCH_QUICK=1 in the environment = --quick (10^5 per evaluator instead of 10^8).
   Entries flagged slow (loops over grid samples or quadrature nodes) get N/SLOW_DIV calls
   when STABILITY_SLOW_DIV is set (default 1: the full count).
   --shard K/M runs only the entries (evaluators and pointer-taking drivers) whose index is K
   modulo M: bench/stability.sh runs the shards of every build as separate processes on every
   core and merges their CSVs. Every entry draws from its own seed (its name hashed with the
   sweep's), so its counts are the same in any shard and the merged table is that of one run.
   Exit status: 0 when every count is zero, 1 when something was found, 2 on usage errors. */
#define _POSIX_C_SOURCE 200112L
#define _DEFAULT_SOURCE 1 /* mmap's MAP_ANONYMOUS (tests/fuzz/pf_buffers.h) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <signal.h>
#include <setjmp.h>
#include "pf_calls.h"   /* tests/fuzz/ (-Itests/fuzz): the evaluators' entries */
#include "pf_buffers.h" /* tests/fuzz/: the pointer-taking functions' drivers */

#ifdef PF_DOUBLE
#  define STAB_PREC "double"
#else
#  define STAB_PREC "float"
#endif
#ifdef __FAST_MATH__
#  define STAB_FAST " -ffast-math"
#else
#  define STAB_FAST ""
#endif

static double stab_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* the inputs and outputs of a failing call, exactly (%a) and readably (%.9g / %.17g) */
static void stab_describe(const pfc_ctx *c, char *buf, size_t size)
{
    size_t len = 0;
    int i, na = c->narg < PFC_MAX_VALUES ? c->narg : PFC_MAX_VALUES;
    int no = c->nout < PFC_MAX_VALUES ? c->nout : PFC_MAX_VALUES;
    int ni = c->niarg < 8 ? c->niarg : 8;
    buf[0] = 0;
#define STAB_ADD(...) do { if (len < size) { int k_ = snprintf(buf + len, size - len, __VA_ARGS__); if (k_ > 0) len += (size_t)k_; } } while (0)
    STAB_ADD("in(");
    for (i = 0; i < na; ++i) STAB_ADD("%s%a", i ? " " : "", (double)c->arg[i]);
    if (ni) STAB_ADD(" int");
    for (i = 0; i < ni; ++i) STAB_ADD(" %d", c->iarg[i]);
    STAB_ADD(") = (");
    for (i = 0; i < na; ++i) STAB_ADD("%s%.9g", i ? " " : "", (double)c->arg[i]);
    STAB_ADD(") out(");
    for (i = 0; i < no; ++i) STAB_ADD("%s%.9g", i ? " " : "", (double)c->out[i]);
    STAB_ADD(")");
#undef STAB_ADD
    for (i = 0; buf[i]; ++i) if (buf[i] == ',' || buf[i] == '\n') buf[i] = ';';
}

static int stab_list(void)
{
    int i;
    for (i = 0; i < PFC_COUNT; ++i) printf("%s\n", pfc_table[i].name);
    for (i = 0; i < PFB_COUNT; ++i) printf("%s (pointer-taking)\n", pfb_table[i].name);
    return 0;
}

static const pfc_entry *stab_find(const char *name)
{
    int i;
    for (i = 0; i < PFC_COUNT; ++i) if (!strcmp(pfc_table[i].name, name)) return &pfc_table[i];
    return 0;
}

/* ---------------------------------------------------------------- merge: the fragment */
#define STAB_MAX_BUILDS 8
typedef struct {
    char build[STAB_MAX_BUILDS][64];
    int nbuild;
    double n[PFC_COUNT][STAB_MAX_BUILDS];
    double nonfinite[PFC_COUNT][STAB_MAX_BUILDS];
    double viol[PFC_COUNT][STAB_MAX_BUILDS];
    double secs[PFC_COUNT][STAB_MAX_BUILDS];
    double nf_wide[PFC_COUNT][STAB_MAX_BUILDS];
    double skipped[PFC_COUNT][STAB_MAX_BUILDS];
    char example[PFC_COUNT][STAB_MAX_BUILDS][512];
    char example_wide[PFC_COUNT][STAB_MAX_BUILDS][512];
    int seen[PFC_COUNT][STAB_MAX_BUILDS];
} stab_merged;

static stab_merged stab_m;

/* the pointer-taking functions (pf_buffers.h): per entry and build */
typedef struct {
    double calls[PFB_COUNT][STAB_MAX_BUILDS], rejected[PFB_COUNT][STAB_MAX_BUILDS], run[PFB_COUNT][STAB_MAX_BUILDS];
    double n[PFB_COUNT][STAB_MAX_BUILDS][PFB_KINDS], secs[PFB_COUNT][STAB_MAX_BUILDS];
    char example[PFB_COUNT][STAB_MAX_BUILDS][700];
    int seen[PFB_COUNT][STAB_MAX_BUILDS];
} stab_bmerged;
static stab_bmerged stab_b;

static int stab_build_index(const char *name)
{
    int b;
    for (b = 0; b < stab_m.nbuild; ++b) if (!strcmp(stab_m.build[b], name)) return b;
    if (b == STAB_MAX_BUILDS) return -1;
    snprintf(stab_m.build[b], sizeof stab_m.build[b], "%.63s", name);
    stab_m.nbuild++;
    return b;
}

/* a buffer line: B:build,name,module,calls,rejected,run,wrong_rc,wrote,nonfinite,value,oob,seconds,example */
#define STAB_BFIELDS 13
static void stab_read_buffers(char *line, const char *path)
{
    char *fld[STAB_BFIELDS], *p = line + 2;
    int k = 0, e, b;
    while (k < STAB_BFIELDS) {
        fld[k++] = p;
        if (k == STAB_BFIELDS) break;
        p = strchr(p, ',');
        if (!p) return;
        *p++ = 0;
    }
    for (e = 0; e < PFB_COUNT; ++e) if (!strcmp(pfb_table[e].name, fld[1])) break;
    if (e == PFB_COUNT) { fprintf(stderr, "stability: %s: unknown buffer entry %s\n", path, fld[1]); return; }
    if ((b = stab_build_index(fld[0])) < 0) return;
    stab_b.calls[e][b] = atof(fld[3]);
    stab_b.rejected[e][b] = atof(fld[4]);
    stab_b.run[e][b] = atof(fld[5]);
    stab_b.n[e][b][PFB_RC] = atof(fld[6]);
    stab_b.n[e][b][PFB_WROTE] = atof(fld[7]);
    stab_b.n[e][b][PFB_NONFINITE] = atof(fld[8]);
    stab_b.n[e][b][PFB_VALUE] = atof(fld[9]);
    stab_b.n[e][b][PFB_OOB] = atof(fld[10]);
    stab_b.secs[e][b] = atof(fld[11]);
    snprintf(stab_b.example[e][b], sizeof stab_b.example[e][b], "%.699s", fld[12]);
    stab_b.seen[e][b] = 1;
}

/* a CSV line: build,name,module,n,nonfinite,nonfinite_wide,violations,skipped,seconds,example,
   example_wide */
#define STAB_FIELDS 11
static int stab_read(const char *path)
{
    FILE *f = fopen(path, "r");
    char line[4096];
    if (!f) { fprintf(stderr, "stability: cannot read %s\n", path); return -1; }
    while (fgets(line, sizeof line, f)) {
        char *fld[STAB_FIELDS];
        int k = 0, b, e;
        char *p = line;
        const pfc_entry *en;
        line[strcspn(line, "\r\n")] = 0;
        if (!strncmp(line, "build,", 6) || !line[0]) continue;
        if (!strncmp(line, "B:", 2)) { stab_read_buffers(line, path); continue; }
        while (k < STAB_FIELDS) {
            fld[k++] = p;
            if (k == STAB_FIELDS) break;
            p = strchr(p, ',');
            if (!p) break;
            *p++ = 0;
        }
        if (k < STAB_FIELDS) continue;
        en = stab_find(fld[1]);
        if (!en) { fprintf(stderr, "stability: %s: unknown entry %s\n", path, fld[1]); continue; }
        e = (int)(en - pfc_table);
        if ((b = stab_build_index(fld[0])) < 0) continue;
        stab_m.n[e][b] = atof(fld[3]);
        stab_m.nonfinite[e][b] = atof(fld[4]);
        stab_m.nf_wide[e][b] = atof(fld[5]);
        stab_m.viol[e][b] = atof(fld[6]);
        stab_m.skipped[e][b] = atof(fld[7]);
        stab_m.secs[e][b] = atof(fld[8]);
        snprintf(stab_m.example[e][b], sizeof stab_m.example[e][b], "%.511s", fld[9]);
        snprintf(stab_m.example_wide[e][b], sizeof stab_m.example_wide[e][b], "%.511s", fld[10]);
        stab_m.seen[e][b] = 1;
    }
    fclose(f);
    return 0;
}

static void stab_count(FILE *o, double v)
{
    if (v == 0.0) fprintf(o, "0");
    else fprintf(o, "**%.0f**", v);
}

/* The pointer-taking functions' section of the fragment (and their CSV rows); returns the
   number of entries with a finding. */
static int stab_merge_buffers(FILE *md, FILE *csv, int *missing)
{
    const char *mods[] = { "core", "moments", "height", "gaussgrid" };
    int i, e, b, k, bad = 0;
    double calls = 0, rejected = 0, run = 0, secs = 0, tot[STAB_MAX_BUILDS][PFB_KINDS];
    for (b = 0; b < stab_m.nbuild; ++b) for (k = 0; k < PFB_KINDS; ++k) tot[b][k] = 0;
    fprintf(csv, "\nfunctions,module,build,calls,rejected,run_on_guarded_buffers,wrong_return_code,wrote_on_error,"
                 "nonfinite,wrong_value,out_of_bounds,seconds,first_failure\n");
    for (e = 0; e < PFB_COUNT; ++e) {
        int any = 0;
        for (b = 0; b < stab_m.nbuild; ++b) {
            if (!stab_b.seen[e][b]) { (*missing)++; continue; }
            fprintf(csv, "%s,%s,%s,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.3f,%s\n", pfb_table[e].name,
                    pfb_table[e].module, stab_m.build[b], stab_b.calls[e][b], stab_b.rejected[e][b], stab_b.run[e][b],
                    stab_b.n[e][b][PFB_RC], stab_b.n[e][b][PFB_WROTE], stab_b.n[e][b][PFB_NONFINITE],
                    stab_b.n[e][b][PFB_VALUE], stab_b.n[e][b][PFB_OOB], stab_b.secs[e][b], stab_b.example[e][b]);
            calls += stab_b.calls[e][b];
            rejected += stab_b.rejected[e][b];
            run += stab_b.run[e][b];
            secs += stab_b.secs[e][b];
            for (k = 0; k < PFB_KINDS; ++k) {
                tot[b][k] += stab_b.n[e][b][k];
                if (stab_b.n[e][b][k] > 0) any = 1;
            }
        }
        bad += any;
    }
    fprintf(md, "## Stability of the pointer-taking CPU-only functions: sizes, return codes, buffers\n\n");
    fprintf(md, "Every public `PF_CPU_DEF` function (%d drivers in `tests/fuzz/pf_buffers.h`, checked against the "
                "headers by `tests/fuzz/coverage.sh`) was called with seeded sizes drawn from the whole int range "
                "(negative, 0, small, around 2^24 = PF_MAX_SIDE, 2^30, INT_MAX, INT_MIN, the int-product overflow "
                "points 46341 and 65537), unknown border and kind values, NULL pointers, empty, reversed and "
                "non-finite ranges, and sample coordinates over every float (NaN, +-inf, huge, subnormal). The "
                "return code the contract of `include/pf_core.h` allows (PF_OK, PF_ERR_ARG, PF_ERR_SIZE; either "
                "error when faults of both kinds are present) is computed independently, in the sweep's own "
                "checked long long arithmetic. Rejected calls get canary-filled guarded buffers; accepted ones "
                "get every buffer mapped at exactly its documented size against a PROT_NONE guard page (huge "
                "maps as untouched MAP_NORESERVE mappings, so samplers and table lookups run on maps of every "
                "accepted size, up to PF_MAX_REALS reals); builders and filters run when their buffers hold at "
                "most 4096 reals. Counted per build: a **wrong return code** (or a wrong count or bad-argument "
                "value); a **write on error** (a canary or a byte next to a buffer changed); an **out-of-bounds** "
                "access (a fault on a guard page, caught and counted); a **non-finite** output from finite "
                "inputs in the documented domain; a **wrong value** (an output not written, a pyramid level "
                "outside level 0's range, a filtered colour outside its knot values, a sample or lookup off an "
                "independent long double bilinear/trilinear reference, a layout or size count off the sweep's "
                "own).\n\n", PFB_COUNT);
    fprintf(md, "%.0f calls in %.1f s of CPU time: %.0f rejected by the contract, %.0f run on guarded buffers, the "
                "rest accepted but too large to run (builders and filters). Totals per build (wrong code / "
                "write on error / out of bounds / non-finite / wrong value): ", calls, secs, rejected, run);
    for (b = 0; b < stab_m.nbuild; ++b) {
        fprintf(md, "%s`%s` ", b ? "; " : "", stab_m.build[b]);
        for (k = 0; k < PFB_KINDS; ++k) {
            static const int order[PFB_KINDS] = { PFB_RC, PFB_WROTE, PFB_OOB, PFB_NONFINITE, PFB_VALUE };
            if (k) fprintf(md, " / ");
            stab_count(md, tot[b][order[k]]);
        }
    }
    fprintf(md, ". Functions with a finding: %d of %d drivers.\n\n", bad, PFB_COUNT);
    for (i = 0; i < (int)(sizeof mods / sizeof mods[0]); ++i) {
        fprintf(md, "### pf_%s.h (CPU only)\n\n| functions | calls per build (rejected / run) |", mods[i]);
        for (b = 0; b < stab_m.nbuild; ++b) fprintf(md, " %s |", stab_m.build[b]);
        fprintf(md, "\n|---|---:|");
        for (b = 0; b < stab_m.nbuild; ++b) fprintf(md, "---:|");
        fprintf(md, "\n");
        for (e = 0; e < PFB_COUNT; ++e) {
            const char *nm = pfb_table[e].name;
            if (strcmp(pfb_table[e].module, mods[i])) continue;
            fprintf(md, "| ");
            for (k = 0; nm[k]; ++k) {
                if (k == 0 || nm[k - 1] == ' ') fprintf(md, "%s`", k ? " " : "");
                if (nm[k] != ' ') fputc(nm[k], md);
                if (nm[k + 1] == ' ' || !nm[k + 1]) fputc('`', md);
            }
            fprintf(md, " | %.0f (%.0f / %.0f) |", stab_b.calls[e][0], stab_b.rejected[e][0], stab_b.run[e][0]);
            for (b = 0; b < stab_m.nbuild; ++b) {
                static const int order[PFB_KINDS] = { PFB_RC, PFB_WROTE, PFB_OOB, PFB_NONFINITE, PFB_VALUE };
                fprintf(md, " ");
                if (!stab_b.seen[e][b]) { fprintf(md, "missing |"); continue; }
                for (k = 0; k < PFB_KINDS; ++k) {
                    if (k) fprintf(md, " / ");
                    stab_count(md, stab_b.n[e][b][order[k]]);
                }
                fprintf(md, " |");
            }
            fprintf(md, "\n");
        }
        fprintf(md, "\n");
    }
    fprintf(md, "Cells: wrong return code / write on error / out of bounds / non-finite / wrong value.\n\n");
    if (bad) {
        fprintf(md, "### Findings of the pointer-taking functions (first failing call per function and build)\n\n");
        for (e = 0; e < PFB_COUNT; ++e)
            for (b = 0; b < stab_m.nbuild; ++b) {
                int any = 0;
                for (k = 0; k < PFB_KINDS; ++k) any |= stab_b.n[e][b][k] > 0;
                if (stab_b.seen[e][b] && any)
                    fprintf(md, "- `%s` (%s): %s\n", pfb_table[e].name, stab_m.build[b], stab_b.example[e][b]);
            }
        fprintf(md, "\n");
    }
    return bad;
}

static int stab_merge(int argc, char **argv)
{
    FILE *md, *csv;
    int i, b, e, missing = 0, bad_fn = 0, bad_w = 0, bad_b, missing_b = 0;
    double total_calls = 0, total_secs = 0, min_n = -1, max_n = 0;
    double tot_nf[STAB_MAX_BUILDS], tot_v[STAB_MAX_BUILDS], tot_w[STAB_MAX_BUILDS];
    const char *mods[] = { "core", "smith", "beckmann", "moments", "toksvig", "shadow", "gaussgrid", "height" };
    if (argc < 5) return 2;
    for (i = 4; i < argc; ++i) if (stab_read(argv[i])) return 2;
    md = fopen(argv[2], "w");
    csv = fopen(argv[3], "w");
    if (!md || !csv) { fprintf(stderr, "stability: cannot write %s / %s\n", argv[2], argv[3]); return 2; }
    for (b = 0; b < stab_m.nbuild; ++b) { tot_nf[b] = 0; tot_v[b] = 0; tot_w[b] = 0; }
    fprintf(csv, "evaluator,module,build,inputs,nonfinite_domain,nonfinite_any_finite,out_of_range,skipped,seconds,first_failure,first_failure_any_finite\n");
    for (e = 0; e < PFC_COUNT; ++e) {
        int any = 0, any_w = 0;
        for (b = 0; b < stab_m.nbuild; ++b) {
            if (!stab_m.seen[e][b]) { missing++; continue; }
            fprintf(csv, "%s,%s,%s,%.0f,%.0f,%.0f,%.0f,%.0f,%.3f,%s,%s\n", pfc_table[e].name, pfc_table[e].module,
                    stab_m.build[b], stab_m.n[e][b], stab_m.nonfinite[e][b], stab_m.nf_wide[e][b], stab_m.viol[e][b],
                    stab_m.skipped[e][b], stab_m.secs[e][b], stab_m.example[e][b], stab_m.example_wide[e][b]);
            total_calls += stab_m.n[e][b];
            total_secs += stab_m.secs[e][b];
            if (min_n < 0 || stab_m.n[e][b] < min_n) min_n = stab_m.n[e][b];
            if (stab_m.n[e][b] > max_n) max_n = stab_m.n[e][b];
            tot_nf[b] += stab_m.nonfinite[e][b];
            tot_v[b] += stab_m.viol[e][b];
            tot_w[b] += stab_m.nf_wide[e][b];
            if (stab_m.nonfinite[e][b] > 0 || stab_m.viol[e][b] > 0) any = 1;
            if (stab_m.nf_wide[e][b] > 0) any_w = 1;
        }
        bad_fn += any;
        bad_w += any_w;
    }
    fprintf(md, "## Stability: non-finite and out-of-range outputs\n\n");
    fprintf(md, "Every public evaluator of `include/pf_*.h` (%d, checked against the portability "
                "generator's list; the pointer-taking CPU-only functions have their own section below) was "
                "called with seeded random inputs drawn from its documented domain, about half of "
                "them on an edge: exact 0 and 1, +-tiny and huge values, grazing directions "
                "(cos down to 2^-40, ~1e-12), directions on and below the surface, zero, singular and "
                "slightly negative variances, |r| at and just beyond 1, PF_LAMBDA_MAX, branch points. "
                "Functions documented to be finite for *every* finite input also get an "
                "arbitrary finite value (up to +-PF_REAL_MAX) in 1 draw out of 16 per argument. "
                "A call counts as non-finite when any output is inf or NaN (tested on the bits, so "
                "-ffast-math cannot fold the test), and out of range when an output leaves "
                "its documented range (a fraction in [0, 1], >= 0, unit vector, ...).\n\n",
            PFC_COUNT);
    fprintf(md, "Inputs per evaluator and build: %.0f", min_n < 0 ? 0.0 : min_n);
    if (max_n != min_n) fprintf(md, " to %.0f", max_n);
    fprintf(md, "%s; %.3g calls in %.0f s of CPU time (%.1f ns per call including the input mapping). "
                "Builds: ", min_n < 1e8 ? (min_n <= 1e5 ? " (**quick mode**, BENCH_QUICK=1; full mode is 10^8)" : " (reduced count, STABILITY_N; full mode is 10^8)") : "",
            total_calls, total_secs, total_calls > 0 ? 1e9 * total_secs / total_calls : 0.0);
    for (b = 0; b < stab_m.nbuild; ++b) fprintf(md, "%s`%s`", b ? ", " : "", stab_m.build[b]);
    fprintf(md, ". Reproduce: `sh bench/stability.sh` (BENCH_QUICK=1 for 10^5).\n\n");
    fprintf(md, "Totals per build (non-finite in the domain / out of range / non-finite from an "
                "arbitrary finite input): ");
    for (b = 0; b < stab_m.nbuild; ++b) {
        fprintf(md, "%s`%s` ", b ? "; " : "", stab_m.build[b]);
        stab_count(md, tot_nf[b]);
        fprintf(md, " / ");
        stab_count(md, tot_v[b]);
        fprintf(md, " / %.0f", tot_w[b]);
    }
    fprintf(md, ". Evaluators with a finding in their domain: %d of %d; with a non-finite result "
                "only from arbitrary finite inputs: %d.\n\n", bad_fn, PFC_COUNT, bad_w);
    if (missing) fprintf(md, "**%d (evaluator, build) results missing.**\n\n", missing);

    for (i = 0; i < (int)(sizeof mods / sizeof mods[0]); ++i) {
        fprintf(md, "### pf_%s.h\n\n| evaluator | domain swept | known edge regimes: what it returns |", mods[i]);
        for (b = 0; b < stab_m.nbuild; ++b) fprintf(md, " %s |", stab_m.build[b]);
        fprintf(md, "\n|---|---|---|");
        for (b = 0; b < stab_m.nbuild; ++b) fprintf(md, "---:|");
        fprintf(md, "\n");
        for (e = 0; e < PFC_COUNT; ++e) {
            if (strcmp(pfc_table[e].module, mods[i])) continue;
            fprintf(md, "| `%s`%s | %s | %s |", pfc_table[e].name, (pfc_table[e].flags & PFC_WIDE) ? " (all finite)" : "",
                    pfc_table[e].domain, pfc_table[e].regimes);
            for (b = 0; b < stab_m.nbuild; ++b) {
                fprintf(md, " ");
                if (!stab_m.seen[e][b]) { fprintf(md, "missing |"); continue; }
                stab_count(md, stab_m.nonfinite[e][b]);
                fprintf(md, " / ");
                stab_count(md, stab_m.viol[e][b]);
                if (stab_m.nf_wide[e][b] > 0) fprintf(md, " / %.0fw", stab_m.nf_wide[e][b]);
                fprintf(md, " |");
            }
            fprintf(md, "\n");
        }
        fprintf(md, "\n");
    }
    fprintf(md, "Cells: non-finite / out-of-range calls, in the domain swept; \"/ Nw\": N further "
                "non-finite results from calls that drew an arbitrary finite value (\"(all finite)\" "
                "rows: the header promises a finite result for every finite input, so such values are "
                "mixed in; range checks are skipped for those calls). Calls whose derived inputs "
                "(e.g. moments built from drawn statistics) overflowed are not counted.\n\n");
    if (bad_fn || bad_w) {
        fprintf(md, "### Findings (first failing input per evaluator and build, exact in hex)\n\n");
        for (e = 0; e < PFC_COUNT; ++e)
            for (b = 0; b < stab_m.nbuild; ++b) {
                if (stab_m.seen[e][b] && (stab_m.nonfinite[e][b] > 0 || stab_m.viol[e][b] > 0))
                    fprintf(md, "- `%s` (%s): %s\n", pfc_table[e].name, stab_m.build[b], stab_m.example[e][b]);
                if (stab_m.seen[e][b] && stab_m.nf_wide[e][b] > 0)
                    fprintf(md, "- `%s` (%s, arbitrary finite input): %s\n", pfc_table[e].name, stab_m.build[b],
                            stab_m.example_wide[e][b]);
            }
        fprintf(md, "\n");
    }
    bad_b = stab_merge_buffers(md, csv, &missing_b);
    missing += missing_b;
    fclose(md);
    fclose(csv);
    return missing ? 2 : (bad_fn || bad_b ? 1 : 0);
}

/* ---------------------------------------------------------------- the pointer-taking sweep */
static sigjmp_buf stab_jmp;
static volatile sig_atomic_t stab_in_call;
static pfc_ctx stab_bctx; /* static: survives the longjmp out of a faulting call */

static void stab_fault(int sig)
{
    if (stab_in_call) { stab_in_call = 0; siglongjmp(stab_jmp, 1); }
    signal(sig, SIG_DFL);
    raise(sig);
}

/* n seeded calls of every driver (or only `only`); one CSV line each */
static int stab_buffers(FILE *csv, const char *label, double n, pfc_u64 seed, const char *only, int shard,
                        int nshards)
{
    struct sigaction sa;
    volatile int i; /* live across sigsetjmp */
    volatile int found = 0;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = stab_fault;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_NODEFER;
    sigaction(SIGSEGV, &sa, 0);
    sigaction(SIGBUS, &sa, 0);
    pfb_trap = 0;
    pfb_work_cap = 1LL << 12;
    for (i = 0; i < PFB_COUNT; ++i) {
        static pfb_tally t;
        const pfb_entry *e = &pfb_table[i];
        volatile double k;
        double t0, t1;
        int kind;
        volatile int any = 0;
        char ex[700];
        if (only && strcmp(only, e->name)) continue;
        if (i % nshards != shard) continue;
        memset(&t, 0, sizeof t);
        memset(&stab_bctx, 0, sizeof stab_bctx);
        stab_bctx.rng = pfc_hash(e->name) ^ seed;
        pfb_t = &t;
        t0 = stab_now();
        for (k = 0; k < n; k += 1.0) {
            if (sigsetjmp(stab_jmp, 1)) { /* a fault: out of bounds */
                t.n[PFB_OOB] += 1;
                if (!t.example[PFB_OOB][0])
                    snprintf(t.example[PFB_OOB], sizeof t.example[PFB_OOB], "%s -> fault (out of bounds)", pfb_line);
                pfb_release_all();
                continue;
            }
            stab_in_call = 1;
            pfb_call(&stab_bctx, e);
            stab_in_call = 0;
        }
        t1 = stab_now();
        ex[0] = 0;
        for (kind = 0; kind < PFB_KINDS; ++kind)
            if (t.n[kind] > 0) { any = 1; if (!ex[0]) snprintf(ex, sizeof ex, "%s: %s", pfb_kind_name[kind], t.example[kind]); }
        {
            int q;
            for (q = 0; ex[q]; ++q) if (ex[q] == ',' || ex[q] == '\n') ex[q] = ';';
        }
        fprintf(csv, "B:%s,%s,%s,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f,%.3f,%s\n", label, e->name, e->module, t.calls,
                t.rejected_n, t.run, t.n[PFB_RC], t.n[PFB_WROTE], t.n[PFB_NONFINITE], t.n[PFB_VALUE], t.n[PFB_OOB],
                t1 - t0, ex);
        fflush(csv);
        if (any) {
            found = 1;
            fprintf(stderr, "stability [%s] %s: %s\n", label, e->name, ex);
        }
    }
    pfb_t = 0;
    signal(SIGSEGV, SIG_DFL);
    signal(SIGBUS, SIG_DFL);
    return found;
}

/* ---------------------------------------------------------------- the sweep */
int main(int argc, char **argv)
{
    double n = 1e8;
    const char *only = 0, *label = STAB_PREC STAB_FAST, *csvpath = 0;
    pfc_u64 seed = 20240917ULL;
    int i, found = 0, slow_div = 1, shard = 0, nshards = 1;
    FILE *csv = stdout;
    const char *q = getenv("BENCH_QUICK"), *sd = getenv("STABILITY_SLOW_DIV");
    if (q && *q && strcmp(q, "0")) n = 1e5;
    if (sd && atoi(sd) > 1) slow_div = atoi(sd);
    if (argc > 1 && !strcmp(argv[1], "--list")) return stab_list();
    if (argc > 1 && !strcmp(argv[1], "--merge")) {
        int r = stab_merge(argc, argv);
        if (r == 2) fprintf(stderr, "usage: stability --merge OUT.md OUT.csv A.csv [B.csv ...]\n");
        return r;
    }
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--quick")) n = 1e5;
        else if (!strcmp(argv[i], "-n") && i + 1 < argc) n = atof(argv[++i]);
        else if (!strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
        else if (!strcmp(argv[i], "--seed") && i + 1 < argc) seed = strtoull(argv[++i], 0, 0);
        else if (!strcmp(argv[i], "--label") && i + 1 < argc) label = argv[++i];
        else if (!strcmp(argv[i], "--csv") && i + 1 < argc) csvpath = argv[++i];
        else if (!strcmp(argv[i], "--shard") && i + 1 < argc) {
            if (sscanf(argv[++i], "%d/%d", &shard, &nshards) != 2 || nshards < 1 || shard < 0 || shard >= nshards) {
                fprintf(stderr, "stability: --shard K/M with 0 <= K < M\n");
                return 2;
            }
        }
        else { fprintf(stderr, "usage: see bench/stability.c\n"); return 2; }
    }
    if (csvpath && !(csv = fopen(csvpath, "w"))) { fprintf(stderr, "stability: cannot write %s\n", csvpath); return 2; }
    pfc_init();
    fprintf(csv, "build,name,module,n,nonfinite,nonfinite_wide,violations,skipped,seconds,example,example_wide\n");
    for (i = 0; i < PFC_COUNT; ++i) {
        const pfc_entry *e = &pfc_table[i];
        pfc_ctx c;
        double t0, t1, k, count = n, nonfinite = 0, nf_wide = 0, viol = 0, skipped = 0;
        char example[512] = "", example_wide[512] = "";
        if (only && strcmp(only, e->name)) continue;
        if (i % nshards != shard) continue;
        if ((e->flags & PFC_SLOW) && slow_div > 1) count = n / slow_div;
        memset(&c, 0, sizeof c);
        c.rng = pfc_hash(e->name) ^ seed;
        t0 = stab_now();
        for (k = 0; k < count; k += 1.0) {
            pfc_call(&c, e);
            if (c.skip) skipped += 1;
            if (c.bad) {
                if ((c.bad & 1) && c.wide_hit) {
                    nf_wide += 1;
                    if (!example_wide[0]) stab_describe(&c, example_wide, sizeof example_wide);
                } else {
                    if (c.bad & 1) nonfinite += 1;
                    if (c.bad & 2) viol += 1;
                    if (!example[0]) stab_describe(&c, example, sizeof example);
                }
            }
        }
        t1 = stab_now();
        fprintf(csv, "%s,%s,%s,%.0f,%.0f,%.0f,%.0f,%.0f,%.3f,%s,%s\n", label, e->name, e->module, count, nonfinite,
                nf_wide, viol, skipped, t1 - t0, example, example_wide);
        fflush(csv);
        if (nonfinite > 0 || viol > 0) {
            found = 1;
            fprintf(stderr, "stability [%s] %s: %.0f non-finite, %.0f out of range; first: %s\n", label, e->name,
                    nonfinite, viol, example);
        }
        if (nf_wide > 0)
            fprintf(stderr, "stability [%s] %s: %.0f non-finite from arbitrary finite inputs; first: %s\n", label,
                    e->name, nf_wide, example_wide);
    }
    {
        const char *bn = getenv("STABILITY_BUFFERS_N");
        double nb = n <= 1e5 ? 500 : 1000;
        if (bn && atof(bn) > 0) nb = atof(bn);
        if (stab_buffers(csv, label, nb, seed, only, shard, nshards)) found = 1;
    }
    if (csv != stdout) fclose(csv);
    return found;
}

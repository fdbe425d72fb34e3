/* bench/storage.h - the storage pass of bench/microsurface.c: every method with its pyramids
   stored in 16- and 8-bit formats (include/pf_encode.h), against float32 storage, on the same
   samples and references in the same run.

   Included by microsurface.c after its method registry (it uses lib_maps, mctx, the registry
   and the task/size/view constants); its hooks there are four calls: store_build after the
   kind's pyramids (lib_maps_build), store_rows after each sample's methods (fp_item_run),
   store_reduce in the item-order reduction, store_free at the kind's end, and store_write at
   the end of the run.

   FORMATS (bytes per texel in store_bytes below, float32 first):
     float32   the pyramids as built (the main tables' numbers);
     half      every moment pyramid in IEEE half (binary16): slope moments about the map's mean
               slope (pf_slope_moments_encode, PF_ENCODE_HALF), average normals, (E[h], E[h^2]),
               the colour attributes, the HDF moments as they are; vMF lobes in their 16-bit
               encoding (octahedral axis, log kappa, amp in UNORM16: half cannot hold kappa up
               to 1e5);
     unorm16   every moment pyramid in 16-bit UNORM with a per-map offset and scale per channel
               (slope moments about the map's mean slope), vMF lobes in UNORM16;
     unorm8    the same at 8 bits.
   Each pyramid is encoded whole (the ranges of the whole pyramid, which are its finest level's)
   and decoded back into a pf_real pyramid of the same layout, which the methods read
   unchanged: a method fetches one texel of level log2 n (what a point or centred bilinear
   fetch reads), so the difference to float32 is the quantization alone; that filtering the
   stored texels filters the moments is tests/test_encode.c's linearity tests.

   COST. Every method is evaluated NSTORE times per sample instead of once (the references,
   which dominate, once); MICROSURFACE_STORAGE=0 in the environment skips the pass (no storage
   files are written then). The quick run (store_max_kinds = 1) runs it on its first kind only:
   every code path of the pass, a seventh of its work (nothing reads the quick run's tables).

   OUTPUT. microsurface_storage.csv: per kind, reference, task, method, footprint size, view
   and format: sum_sq_err (against the reference), sum_sq_ref, sum_sq_diff (against the same
   method with float32 storage) and the samples; storage.md (the fragment docs/encode.md shows
   between its GENERATED markers): per format, the worst ratio of a method's error to its
   float32 error over every kind, footprint size and both references (views pooled 0-75
   degrees as the main tables), and per method. */
#ifndef BENCH_STORAGE_H
#define BENCH_STORAGE_H

#include "pf_encode.h"

#define NSTORE 4
enum { ST_F32, ST_HALF, ST_U16, ST_U8 };
static const char *store_name[NSTORE] = { "float32", "half", "unorm16", "unorm8" };

/* bytes per texel of each pyramid family, per format (vMF: per lobe; HDF: per azimuth) */
enum { FAM_NONE, FAM_SLOPE, FAM_NORMAL, FAM_VMF, FAM_HDF, FAM_HEIGHT, NFAM };
static const char *fam_name[NFAM] = { "none", "slope moments (5 channels)", "average normal (3)",
                                      "vMF lobe (4 per lobe)", "HDF moments (3 per azimuth; + slope moments)",
                                      "height / colour moments (2; + slope moments)" };
static const int fam_channels[NFAM] = { 0, 5, 3, 4, 3, 2 };
static int store_bytes(int fam, int f)
{
    int per = f == ST_F32 ? 4 : (f == ST_U8 ? 1 : 2);
    return fam_channels[fam] * per;
}
/* the family of what a method fetches (the registry's fetch text) */
static int method_family(const method *m)
{
    if (strstr(m->fetch, "vMF")) return FAM_VMF;
    if (strstr(m->fetch, "HDF")) return FAM_HDF;
    if (strstr(m->fetch, "average normal")) return FAM_NORMAL;
    if (strstr(m->fetch, "E[h]") || strstr(m->fetch, "colour")) return FAM_HEIGHT;
    if (strstr(m->fetch, "slope moments")) return FAM_SLOPE;
    if (!strcmp(m->name, "oracle_histogram_smith")) return FAM_SLOPE;
    return FAM_NONE;
}

/* the family of each task's methods (method_family, looked up once by store_build) */
static int store_fam[NTASK][MAX_TASK_METHODS];

/* the kind's pyramids decoded from each format (index 0 unused: float32 is the kind's own) */
typedef struct store_set {
    lib_maps L[NSTORE];
} store_set;

/* per item: sums per format, reference, task, method */
typedef struct store_acc {
    double d2[NSTORE][NREF][NTASK][MAX_TASK_METHODS];
    double dd2[NSTORE][NTASK][MAX_TASK_METHODS];
    double r2[NREF][NTASK];
    long n[NTASK];
} store_acc;
static store_acc store_tot[NKIND + 1][NSIZE][NVIEW];
static int store_ran[NKIND + 1];
/* the kinds the pass runs on at most (the first ones run), and how many it has begun */
static int store_max_kinds = NKIND + 1, store_built;

static void store_fail(const char *what)
{
    fprintf(stderr, "microsurface: storage pass: %s failed\n", what);
    exit(1);
}

/* n texels of C generic channels: encode in format f (per-channel ranges of the whole buffer)
   and decode in place */
static void store_channels(pf_real *p, long long n, int C, int f)
{
    pf_real *off = (pf_real *)pfb_xcalloc((size_t)C, sizeof(pf_real)), *sc = (pf_real *)pfb_xcalloc((size_t)C, sizeof(pf_real));
    void *q = pfb_xcalloc((size_t)n * (size_t)C, 2);
    int fmt = f == ST_HALF ? PF_ENCODE_HALF : (f == ST_U16 ? PF_ENCODE_UNORM16 : PF_ENCODE_UNORM8);
    long long t, i;
    int c;
    if (pf_encode_ranges(p, n, C, off, sc) != PF_OK || pf_encode_channels(p, n, C, off, sc, fmt, q) != PF_OK)
        store_fail("pf_encode_channels");
    for (t = 0, i = 0; t < n; ++t) /* texel by texel, channel c of texel t at i = t C + c */
        for (c = 0; c < C; ++c, ++i) {
            if (fmt == PF_ENCODE_HALF) p[i] = pf_real_from_half(((unsigned short *)q)[i]);
            else if (fmt == PF_ENCODE_UNORM16) p[i] = pf_unorm_decode((pf_real)((unsigned short *)q)[i] / PF_R(65535.0), off[c], sc[c]);
            else p[i] = pf_unorm_decode((pf_real)((unsigned char *)q)[i] / PF_R(255.0), off[c], sc[c]);
        }
    free(off);
    free(sc);
    free(q);
}

static pf_real store_s(const void *q, long long i, int fmt)
{
    if (fmt == PF_ENCODE_HALF) return pf_real_from_half(((const unsigned short *)q)[i]);
    if (fmt == PF_ENCODE_UNORM16) return (pf_real)((const unsigned short *)q)[i] / PF_R(65535.0);
    return (pf_real)((const unsigned char *)q)[i] / PF_R(255.0);
}

/* n slope texels: about the map's mean slope, format f, decoded in place */
static void store_slope(pf_real *p, long long n, int f)
{
    int fmt = f == ST_HALF ? PF_ENCODE_HALF : (f == ST_U16 ? PF_ENCODE_UNORM16 : PF_ENCODE_UNORM8);
    void *q = pfb_xcalloc((size_t)n * 5, 2);
    pf_slope_encoding e;
    long long i;
    if (pf_slope_encoding_find(p, n, 1, &e) != PF_OK || pf_slope_moments_encode(p, n, &e, fmt, q) != PF_OK)
        store_fail("pf_slope_moments_encode");
    if (fmt == PF_ENCODE_HALF) { /* the half channels are the centred moments themselves */
        e.off_x = e.off_y = e.off_xx = e.off_yy = e.off_xy = PF_R(0.0);
        e.sc_x = e.sc_y = e.sc_xx = e.sc_yy = e.sc_xy = PF_R(1.0);
    }
    for (i = 0; i < n; ++i) {
        pf_slope_moments m = pf_slope_moments_decode(
            pf_slope_moments_make(store_s(q, 5 * i, fmt), store_s(q, 5 * i + 1, fmt), store_s(q, 5 * i + 2, fmt),
                                  store_s(q, 5 * i + 3, fmt), store_s(q, 5 * i + 4, fmt)),
            e);
        p[5 * i] = m.ex;
        p[5 * i + 1] = m.ey;
        p[5 * i + 2] = m.exx;
        p[5 * i + 3] = m.eyy;
        p[5 * i + 4] = m.exy;
    }
    free(q);
}

/* nlobes lobe texels (mu.x, mu.y, kappa, amp): UNORM16 (half and unorm16) or UNORM8 */
static void store_vmf(pf_real *p, long long nlobes, int f)
{
    int fmt = f == ST_U8 ? PF_ENCODE_UNORM8 : PF_ENCODE_UNORM16;
    void *q = pfb_xcalloc((size_t)nlobes * 4, 2);
    pf_vmf_encoding e;
    long long i;
    if (pf_vmf_encoding_find(p, nlobes, &e) != PF_OK || pf_vmf_lobes_encode(p, nlobes, &e, fmt, q) != PF_OK)
        store_fail("pf_vmf_lobes_encode");
    for (i = 0; i < nlobes; ++i) {
        pf_vmf_lobe l = pf_vmf_lobe_decode(store_s(q, 4 * i, fmt), store_s(q, 4 * i + 1, fmt), store_s(q, 4 * i + 2, fmt),
                                           store_s(q, 4 * i + 3, fmt), e);
        p[4 * i] = l.mu.x;
        p[4 * i + 1] = l.mu.y;
        p[4 * i + 2] = l.kappa;
        p[4 * i + 3] = l.amp;
    }
    free(q);
}

static pf_real *store_copy(const pf_real *p, long long n)
{
    pf_real *c = (pf_real *)pfb_xcalloc((size_t)n, sizeof(pf_real));
    memcpy(c, p, (size_t)n * sizeof(pf_real));
    return c;
}

/* the kind's pyramids in every format (shallow copies of L with the moment pyramids replaced;
   the heights, scaling-function tables and attributes in double are shared), one work item per
   format and pyramid on every core (each item writes its own pyramid) */
#define STORE_PYRS (5 + NVMF + NHOR) /* slope, normal, height, 2 attributes, the lobes, the HDFs */
typedef struct store_job {
    const lib_maps *L;
    store_set *S;
} store_job;
static void store_item(void *ctx, long long item)
{
    const store_job *J = (const store_job *)ctx;
    const lib_maps *L = J->L;
    const long long tc = pf_mip_texel_count(L->w, L->h);
    const int f = 1 + (int)(item / STORE_PYRS), p = (int)(item % STORE_PYRS);
    lib_maps *D = &J->S->L[f];
    if (p == 0) {
        D->slope = store_copy(L->slope, tc * 5);
        store_slope(D->slope, tc, f);
    } else if (p == 1) {
        D->normal = store_copy(L->normal, tc * 3);
        store_channels(D->normal, tc, 3, f);
    } else if (p == 2) {
        D->height = store_copy(L->height, tc * 2);
        store_channels(D->height, tc, 2, f);
    } else if (p <= 4) {
        D->attr[p - 3] = store_copy(L->attr[p - 3], tc * 2);
        store_channels(D->attr[p - 3], tc, 2, f);
    } else if (p < 5 + NVMF) {
        const int k = p - 5;
        const long long lobes = pf_vmf_pyramid_texel_count(L->w, L->h) * vmf_lobes[k];
        D->vmf[k] = store_copy(L->vmf[k], lobes * 4);
        store_vmf(D->vmf[k], lobes, f);
    } else if (p - 5 - NVMF == H32) {
        /* the n = 32 HDF moments, and the n = 16 ones from them: the n = 16 pyramid is the n = 32
           one's even azimuths (microsurface.c's horizon_even_azimuths), and store_channels
           encodes and decodes each channel alone with its own range, so the n = 16 pyramid's
           stored channels are the n = 32 one's even azimuths, bit for bit */
        const int C16 = pf_horizon_channels(PF_HORIZON_MOMENTS, hor_n[H16], 0);
        const int C32 = pf_horizon_channels(PF_HORIZON_MOMENTS, hor_n[H32], 0);
        D->hor[H32] = store_copy(L->hor[H32], tc * C32);
        store_channels(D->hor[H32], tc, C32, f);
        D->hor[H16] = hdf_even_azimuths(D->hor[H32], tc);
        if (check_mode) { /* MICROSURFACE_CHECK=1: against the n = 16 pyramid stored alone */
            pf_real *ref = store_copy(L->hor[H16], tc * C16);
            store_channels(ref, tc, C16, f);
            check_same(ref, D->hor[H16], (size_t)tc * (size_t)C16 * sizeof(pf_real), "the stored n = 16 HDF moments");
            free(ref);
        }
    } /* else the n = 16 HDF moments: with the n = 32 ones' item */
}
static store_set *store_build(const lib_maps *L)
{
    store_set *S;
    store_job J;
    const char *env = getenv("MICROSURFACE_STORAGE");
    int f, t, k;
    double t0 = pfb_now_ns();
    if (env && !strcmp(env, "0")) return NULL; /* MICROSURFACE_STORAGE=0: no storage pass */
    if (store_built >= store_max_kinds) return NULL;
    ++store_built;
    for (t = 0; t < NTASK; ++t)
        for (k = 0; k < task_n[t]; ++k) store_fam[t][k] = method_family(meth(t, k));
    S = (store_set *)pfb_xcalloc(1, sizeof *S);
    for (f = 1; f < NSTORE; ++f) S->L[f] = *L;
    J.L = L;
    J.S = S;
    ms_parallel_for(PS_STORE, (long long)(NSTORE - 1) * STORE_PYRS, store_item, &J, "microsurface: storage pass: pyramids");
    fprintf(stderr, "microsurface: storage pass: pyramids encoded and decoded in %d formats: %.2f s\n", NSTORE - 1,
            (pfb_now_ns() - t0) * 1e-9);
    return S;
}

static void store_free(store_set *S)
{
    int f, k;
    if (!S) return;
    for (f = 1; f < NSTORE; ++f) {
        lib_maps *D = &S->L[f];
        free(D->slope);
        free(D->normal);
        free(D->height);
        for (k = 0; k < 2; ++k) free(D->attr[k]);
        for (k = 0; k < NVMF; ++k) free(D->vmf[k]);
        for (k = 0; k < NHOR; ++k) free(D->hor[k]);
    }
    free(S);
}

/* one sample of task t (row: the references, then the float32 methods' values): every method
   again on the pyramids of each format, summed into the item's accumulator */
static void store_rows(const store_set *S, store_acc **acc, int t, const mctx *c, const double *row)
{
    int f, k, r;
    store_acc *A;
    mmemo memo[NSTORE]; /* per format: what its methods share (microsurface.c's mmemo) */
    if (!S) return;
    memset(memo, 0, sizeof memo);
    if (!*acc) *acc = (store_acc *)pfb_xcalloc(1, sizeof(store_acc));
    A = *acc;
    A->n[t]++;
    for (r = 0; r < NREF; ++r) A->r2[r][t] += row[r] * row[r];
    for (k = 0; k < task_n[t]; ++k) {
        const double f32 = row[NREF + k];
        for (f = 0; f < NSTORE; ++f) {
            double v = f32;
            if (f > 0 && store_fam[t][k] != FAM_NONE) {
                mctx cf = *c;
                cf.L = &S->L[f];
                cf.memo = &memo[f];
                v = meth(t, k)->eval(&cf);
                if (check_mode) {
                    double alone;
                    cf.memo = NULL;
                    alone = meth(t, k)->eval(&cf);
                    if (memcmp(&alone, &v, sizeof v) != 0) {
                        fprintf(stderr, "microsurface: MICROSURFACE_CHECK: %s (%s) through the shared values differs\n",
                                mname(t, k), store_name[f]);
                        exit(1);
                    }
                }
            }
            for (r = 0; r < NREF; ++r) A->d2[f][r][t][k] += (v - row[r]) * (v - row[r]);
            A->dd2[f][t][k] += (v - f32) * (v - f32);
        }
    }
}

/* an item's sums into the kind's totals (in item order: the CSV is the same for any thread
   count) */
static void store_reduce(int kind, store_acc *A, int si, int vi)
{
    store_acc *T = &store_tot[kind][si][vi];
    int f, r, t, k;
    if (!A) return;
    store_ran[kind] = 1;
    for (t = 0; t < NTASK; ++t) {
        T->n[t] += A->n[t];
        for (r = 0; r < NREF; ++r) T->r2[r][t] += A->r2[r][t];
        for (f = 0; f < NSTORE; ++f)
            for (k = 0; k < task_n[t]; ++k) {
                for (r = 0; r < NREF; ++r) T->d2[f][r][t][k] += A->d2[f][r][t][k];
                T->dd2[f][t][k] += A->dd2[f][t][k];
            }
    }
    free(A);
}

/* error of (kind, ref, task, method, size, format) pooled over views 0 .. POOL_VIEW_HI */
static void store_pooled(int kind, int r, int t, int k, int si, int f, double *err, double *diff)
{
    double d2 = 0, r2 = 0, dd2 = 0;
    int v;
    for (v = 0; v <= POOL_VIEW_HI; ++v) {
        const store_acc *T = &store_tot[kind][si][v];
        d2 += T->d2[f][r][t][k];
        dd2 += T->dd2[f][t][k];
        r2 += T->r2[r][t];
    }
    *err = r2 > 0 ? sqrt(d2 / r2) : 0.0;
    *diff = r2 > 0 ? sqrt(dd2 / r2) : 0.0;
}

/* the kinds of this run that the storage pass saw, in display order */
static int store_kinds(int *out)
{
    int i, n = 0;
    for (i = 0; i < NKIND; ++i)
        if (store_ran[kind_order[i]]) out[n++] = kind_order[i];
    if (store_ran[KIND_MAP]) out[n++] = KIND_MAP;
    return n;
}

/* Worst ratio err_f / err_f32 of method (t, k) over the kinds, sizes and references whose
   float32 error is at least `floor` (below it the ratio divides by the method's near-exactness:
   LEADR at 1-texel footprints is within 1e-6 of its reference, which no 16-bit quantization of
   the slopes can match), with where; and the largest storage error, rel_l2 of the method with
   the format's pyramids against the same method with float32 pyramids, over every cell. */
#define STORE_FLOOR 0.01
typedef struct store_worst {
    double ratio, err, err32, diff, raw;
    int kind, si, r;
} store_worst;
static store_worst store_method_worst(int t, int k, int f)
{
    store_worst w;
    int kinds[NKIND + 1], nk = store_kinds(kinds), i, si, r;
    memset(&w, 0, sizeof w);
    w.kind = -1;
    for (i = 0; i < nk; ++i)
        for (si = 0; si < NSIZE; ++si)
            for (r = 0; r < NREF; ++r) {
                double e, e32, d, d32;
                store_pooled(kinds[i], r, t, k, si, f, &e, &d);
                store_pooled(kinds[i], r, t, k, si, ST_F32, &e32, &d32);
                if (d > w.diff) w.diff = d;
                if (e32 > 1e-300 && e / e32 > w.raw) w.raw = e / e32;
                if (e32 < STORE_FLOOR) continue;
                if (w.kind < 0 || e / e32 > w.ratio) {
                    w.ratio = e / e32;
                    w.err = e;
                    w.err32 = e32;
                    w.kind = kinds[i];
                    w.si = si;
                    w.r = r;
                }
            }
    return w;
}
static const char *store_cell(char *buf, size_t n, store_worst w)
{
    if (w.kind < 0) snprintf(buf, n, "- / %.1e", w.diff);
    else snprintf(buf, n, "%.3f / %.1e", w.ratio, w.diff);
    return buf;
}

static void store_write(const settings *S)
{
    int kinds[NKIND + 1], nk = store_kinds(kinds), i, r, t, k, si, v, f, fam;
    char path[1024], cb[NSTORE][64];
    FILE *c, *m;
    if (nk == 0) return;
    snprintf(path, sizeof path, "%s/microsurface_storage.csv", S->out);
    c = fopen(path, "w");
    if (!c) fatal("cannot write microsurface_storage.csv");
    fprintf(c, "kind,reference,task,method,footprint_texels,view_deg,format,bytes_per_texel,samples,sum_sq_err,sum_sq_ref,"
               "sum_sq_diff_float32\n");
    for (i = 0; i < nk; ++i)
        for (r = 0; r < NREF; ++r)
            for (t = 0; t < NTASK; ++t)
                for (k = 0; k < task_n[t]; ++k)
                    for (si = 0; si < NSIZE; ++si)
                        for (v = 0; v < NVIEW; ++v)
                            for (f = 0; f < NSTORE; ++f) {
                                const store_acc *T = &store_tot[kinds[i]][si][v];
                                if (!T->n[t]) continue;
                                fprintf(c, "%s,%s,%s,%s,%d,%g,%s,%d,%ld,%.9g,%.9g,%.9g\n", kname(kinds[i]), ref_name[r],
                                        task_name[t], mname(t, k), 1 << (2 * si), view_deg[v], store_name[f],
                                        store_bytes(method_family(meth(t, k)), f), T->n[t], T->d2[f][r][t][k], T->r2[r][t],
                                        T->dd2[f][t][k]);
                            }
    fclose(c);
    snprintf(path, sizeof path, "%s/storage.md", S->out);
    m = fopen(path, "w");
    if (!m) fatal("cannot write storage.md");
    fprintf(m, "Measured by bench/microsurface.c's storage pass (bench/storage.h)%s: every method of the error tables "
               "with its pyramids stored in each format, on the same samples and references as with float32 storage; "
               "kinds:", S->quick ? " in BENCH_QUICK mode (smaller maps, fewer samples)" : "");
    for (i = 0; i < nk; ++i) fprintf(m, " %s", kname(kinds[i]));
    fprintf(m, "; footprints of 1 to 4096 texels; views pooled 0-75 degrees; both references. Raw numbers: "
               "microsurface_storage.csv.\n\n");
    fprintf(m, "Bytes per texel (vMF: per lobe, HDF: per azimuth):\n\n| pyramid | float32 | half | unorm16 | unorm8 |\n"
               "| --- | --- | --- | --- | --- |\n");
    for (fam = 1; fam < NFAM; ++fam)
        fprintf(m, "| %s | %d | %d | %d | %d |\n", fam_name[fam], store_bytes(fam, ST_F32), store_bytes(fam, ST_HALF),
                store_bytes(fam, ST_U16), store_bytes(fam, ST_U8));
    fprintf(m, "\nEach cell: **ratio / storage error**. Ratio: the worst, over every kind, footprint size (1-4096 texels) "
               "and reference where the method's float32 error is at least %g, of its error (rel_l2 against the "
               "reference) with the format's pyramids over its error with float32 pyramids; target 1.1 for 16 bits. "
               "Storage error: the largest rel_l2 of the method with the format's pyramids against the same method "
               "with float32 pyramids, over every cell (it bounds what the format adds where the float32 error is "
               "smaller, e.g. LEADR at 1-texel footprints, within 1e-6 of its reference). Raw: the worst ratio over "
               "every cell, floor or not.\n\n"
               "| pyramid family | half | unorm16 | unorm8 | raw worst ratio half / unorm16 / unorm8 |\n"
               "| --- | --- | --- | --- | --- |\n", STORE_FLOOR);
    for (fam = 1; fam < NFAM; ++fam) {
        store_worst worst[NSTORE];
        int any = 0;
        memset(worst, 0, sizeof worst);
        for (f = 0; f < NSTORE; ++f) worst[f].kind = -1;
        for (t = 0; t < NTASK; ++t)
            for (k = 0; k < task_n[t]; ++k) {
                if (method_family(meth(t, k)) != fam) continue;
                any = 1;
                for (f = 1; f < NSTORE; ++f) {
                    store_worst w = store_method_worst(t, k, f);
                    if (w.kind >= 0 && (worst[f].kind < 0 || w.ratio > worst[f].ratio)) {
                        worst[f].ratio = w.ratio;
                        worst[f].kind = w.kind;
                    }
                    if (w.diff > worst[f].diff) worst[f].diff = w.diff;
                    if (w.raw > worst[f].raw) worst[f].raw = w.raw;
                }
            }
        if (any)
            fprintf(m, "| %s | %s | %s | %s | %.3g / %.3g / %.3g |\n", fam_name[fam], store_cell(cb[1], 64, worst[ST_HALF]),
                    store_cell(cb[2], 64, worst[ST_U16]), store_cell(cb[3], 64, worst[ST_U8]), worst[ST_HALF].raw,
                    worst[ST_U16].raw, worst[ST_U8].raw);
    }
    fprintf(m, "\nPer method (same cells: ratio / storage error), whether 8 bits serve it (ratio at most 1.1 and storage "
               "error at most 0.01), and where its 8-bit ratio is worst (kind, footprint texels, reference: error with "
               "unorm8 / with float32):\n\n| task | method | pyramid | half | unorm16 | unorm8 | 8 bits serve | unorm8 worst "
               "at |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (t = 0; t < NTASK; ++t)
        for (k = 0; k < task_n[t]; ++k) {
            store_worst w[NSTORE];
            char where[160];
            if (method_family(meth(t, k)) == FAM_NONE) continue;
            for (f = 1; f < NSTORE; ++f) w[f] = store_method_worst(t, k, f);
            if (w[ST_U8].kind >= 0)
                snprintf(where, sizeof where, "%s, %d, %s: %.3g / %.3g", kname(w[ST_U8].kind), 1 << (2 * w[ST_U8].si),
                         ref_name[w[ST_U8].r], w[ST_U8].err, w[ST_U8].err32);
            else
                snprintf(where, sizeof where, "float32 error below %g everywhere", STORE_FLOOR);
            fprintf(m, "| %s | %s | %s | %s | %s | %s | %s | %s |\n", task_name[t], mname(t, k), fam_name[method_family(meth(t, k))],
                    store_cell(cb[1], 64, w[ST_HALF]), store_cell(cb[2], 64, w[ST_U16]), store_cell(cb[3], 64, w[ST_U8]),
                    (w[ST_U8].kind < 0 || w[ST_U8].ratio <= 1.1) && w[ST_U8].diff <= 0.01 ? "yes" : "no", where);
        }
    fclose(m);
}

#endif /* BENCH_STORAGE_H */

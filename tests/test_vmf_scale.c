/* test_vmf_scale.c - tests of include/pf_vmf_scale.h (the scaling function of Wu et al. 2019
   eqs. 6-8, 12-14, 21-24).

   The truth is never the module's own formula: a flat patch's effective BRDF is the base
   lobe's, Helmholtz reciprocity, the in-footprint reference of tests/reference/pf_microsurface.h,
   the rank-1 factorization of a separable ratio recovered exactly, the prior's effect, the
   table lookup against its trilinear definition, the level calls against the orchestration
   written out from the per-patch pieces, bad input through guarded buffers.
   Same bodies in float and double; edge_* tests also run under -ffast-math. */
/* MAP_ANONYMOUS and MAP_NORESERVE for pf_test_guarded_alloc under -std=c99 (before any include) */
#if defined(__unix__) && !defined(_DEFAULT_SOURCE)
#  define _DEFAULT_SOURCE 1
#endif
#include "pf_vmf_scale.h"
#include "pf_oracle.h"
#include "pf_test.h"
#include "pf_microsurface.h"


/* ================================================================== scaling function (helper J)
   Oracles: the base lobe of tests/reference/pf_microsurface.h (pfm_base_specular, double) on a flat patch;
   the exchange of wo and wi (reciprocity, exact for a whole periodic map); a wall's shadow in
   closed form; the test header's own march and reference (pfm_visibility_map_box,
   pfm_reference_shade: an independent implementation in double); a separable R built by hand. */
static pf_real *scale_heights(const pfm_surface *s)
{
    pf_real *hm = (pf_real *)malloc((size_t)s->w * s->h * sizeof(pf_real));
    size_t i;
    if (hm)
        for (i = 0; i < (size_t)s->w * s->h; ++i) hm[i] = (pf_real)s->height[i];
    return hm;
}

static void test_scale_flat_patch_is_base(void)
{
    static pf_real hm[16 * 16];
    long double worst = 0;
    int a, b, c;
    memset(hm, 0, sizeof hm);
    for (a = 0; a < 5; ++a)
        for (b = 0; b < 5; ++b)
            for (c = 0; c < 4; ++c) {
                double wo[3], wi[3], ref;
                pf_real got = PF_R(-1.0);
                pf_test_dir_deg(5.0 + 17.0 * a, 0.0, wo);
                pf_test_dir_deg(3.0 + 18.0 * b, 180.0 - 40.0 * c, wi);
                PF_CHECK(pfi_vmf_effective_brdf(hm, 16, 16, PF_R(0.5), 3, 5, 8, pf_test_vec3(wo), pf_test_vec3(wi), PF_R(0.2), PF_R(0.04), &got) ==
                             PF_OK,
                         "call");
                ref = pfm_base_specular(wo, wi, 0.0, 0.0, 0.2, 0.04) / wo[2];
                if (ref > 1e-6) {
                    long double e = fabsl((long double)got - (long double)ref) / (long double)ref;
                    if (e > worst) worst = e;
                } else
                    PF_CHECK(fabs((double)got - ref) <= 1e-6, "tail %g vs %g", (double)got, ref);
            }
    pf_test_note("flat patch: effective BRDF vs the base lobe (pfm_base_specular / cos): max rel %.2Le", worst);
    PF_CHECK(worst <= 2000.0L * PF_TEST_EPS, "rel %.3Le", worst);
}

static void test_scale_reciprocity(void)
{
    pfm_surface s;
    pf_real *hm;
    long double worst = 0;
    int a;
    if (pfm_surface_make(&s, 32, 32, 1.0, pfm_params_default(PFM_GAUSSIAN_FINE)) != 0 || !(hm = scale_heights(&s))) {
        PF_CHECK(0, "setup");
        return;
    }
    for (a = 0; a < 40; ++a) {
        double wo[3], wi[3];
        pf_real f1 = 0, f2 = 0;
        long double l, r;
        pf_test_dir_deg(5.0 + 1.7 * a, 11.0 * a, wo);
        pf_test_dir_deg(70.0 - 1.6 * a, 180.0 + 7.0 * a, wi);
        PF_CHECK(pfi_vmf_effective_brdf(hm, 32, 32, PF_R(1.0), 0, 0, 32, pf_test_vec3(wo), pf_test_vec3(wi), PF_R(0.1), PF_R(0.04), &f1) == PF_OK &&
                     pfi_vmf_effective_brdf(hm, 32, 32, PF_R(1.0), 0, 0, 32, pf_test_vec3(wi), pf_test_vec3(wo), PF_R(0.1), PF_R(0.04), &f2) == PF_OK,
                 "call");
        /* whole periodic map: the projected area is n^2 w.z, so f / cos(light) is symmetric */
        l = (long double)f1 / (long double)(pf_real)wi[2];
        r = (long double)f2 / (long double)(pf_real)wo[2];
        if (l + r > 0 && fabsl(l - r) / (l + r) > worst) worst = fabsl(l - r) / (l + r);
    }
    pf_test_note("reciprocity f(wo, wi)/cos_i = f(wi, wo)/cos_o, 32^2 gaussian_fine: max rel %.2Le", worst);
    PF_CHECK(worst <= 1e3L * PF_TEST_EPS, "rel %.3Le", worst);
    free(hm);
    pfm_surface_free(&s);
}

/* the effective BRDF against tests/reference/pf_microsurface.h's own in-footprint march and reference */
static void test_scale_vs_microsurface_reference(void)
{
    static const int kinds[3] = { PFM_RIDGES, PFM_TILES, PFM_GAUSSIAN_FINE };
    int ki;
    for (ki = 0; ki < 3; ++ki) {
        pfm_surface s;
        pf_real *hm;
        unsigned char *vo = (unsigned char *)malloc(64 * 64), *vi = (unsigned char *)malloc(64 * 64);
        long double num = 0, den = 0;
        int a;
        if (!vo || !vi || pfm_surface_make(&s, 64, 64, 1.0, pfm_params_default(kinds[ki])) != 0 ||
            !(hm = scale_heights(&s))) {
            PF_CHECK(0, "setup");
            free(vo);
            free(vi);
            return;
        }
        for (a = 0; a < 24; ++a) {
            double wo[3], wi[3];
            pfm_shade sh;
            pf_real got = 0;
            pf_test_dir_deg(10.0 + 2.8 * a, 37.0 * a, wo);
            pf_test_dir_deg(70.0 - 2.5 * a, 37.0 * a + 150.0 + 3.0 * a, wi);
            pfm_visibility_map_box(&s, wo, 8, 24, 32, NULL, vo);
            pfm_visibility_map_box(&s, wi, 8, 24, 32, NULL, vi);
            sh = pfm_reference_shade(&s, vo, vi, 8, 24, 32, wo, wi, 0.1, 0.04);
            PF_CHECK(pfi_vmf_effective_brdf(hm, 64, 64, PF_R(1.0), 8, 24, 32, pf_test_vec3(wo), pf_test_vec3(wi), PF_R(0.1), PF_R(0.04), &got) ==
                         PF_OK,
                     "call");
            num += ((long double)got - (long double)sh.spec) * ((long double)got - (long double)sh.spec);
            den += (long double)sh.spec * (long double)sh.spec;
        }
        pf_test_note("%s 32^2 patch, 24 direction pairs: effective BRDF vs pfm_reference_shade (box march), rel L2 %.2Le",
                     pfm_kind_name(kinds[ki]), sqrtl(num / den));
        PF_CHECK(den > 0 && sqrtl(num / den) <= (sizeof(pf_real) == 4 ? 2e-3L : 1e-9L), "%s rel L2 %.3Le",
                 pfm_kind_name(kinds[ki]), sqrtl(num / den));
        free(hm);
        free(vo);
        free(vi);
        pfm_surface_free(&s);
    }
}

/* the prior toward 1 (shrink): well-sampled values keep their least-squares fit, a cell that
   only tails reach (f_eff exactly 0, f_lobes tiny: the case that left cells of S at 0 in the
   bench) and a patch without energy stay near 1; pfi_vmf_scale_t with the returned prior gives
   a training patch's own T back, and every value against a closed form computed here */
static void test_scale_factor_shrink(void)
{
    enum { NT = 3, NP = 2, P = 6 };
    long long cnt = pf_vmf_scale_sample_count(NT, NP), cells = pf_vmf_scale_cell_count(NT, NP), s, c;
    pf_real fe[P * 36], fl[P * 36], scr[2 * 18 * P], T[P], S[18], S0[18], T0[P], prior = PF_R(-1.0), t_one;
    long double a = 0, q = 0, worst_fit = 0;
    pf_test_rng r;
    int x, weak = 5, tail_cell = 7;
    r = pf_test_rng_seed(91);
    for (x = 0; x < P; ++x)
        for (s = 0; s < cnt; ++s) {
            c = pfi_vmf_scale_cell(s, NT, NP);
            fl[x * cnt + s] = (pf_real)(0.5 + pf_test_uniform_open(&r)) * (x == weak ? PF_R(1e-4) : PF_R(1.0)) * (c == tail_cell ? PF_R(1e-3) : PF_R(1.0));
            /* R = 1.5 on patch 0, 0.8 elsewhere; the tail cell's f_eff is exactly 0 */
            fe[x * cnt + s] = c == tail_cell ? PF_R(0.0) : (x == 0 ? PF_R(1.5) : PF_R(0.8)) * fl[x * cnt + s];
        }
    PF_CHECK(pfi_vmf_scale_factor(fe, fl, P, NT, NP, 40, PF_R(0.0), T0, S0, scr, NULL, NULL) == PF_OK, "plain");
    PF_CHECK(pfi_vmf_scale_factor(fe, fl, P, NT, NP, 40, PF_R(0.1), T, S, scr, &prior, NULL) == PF_OK, "shrink");
    pf_test_note("tail cell: S %.3g (plain %.3g); weak patch T %.3g (plain %.3g); patch 0 / patch 1 T ratio %.4g (plain %.4g)",
                 (double)S[tail_cell], (double)S0[tail_cell], (double)T[weak], (double)T0[weak], (double)(T[0] / T[1]),
                 (double)(T0[0] / T0[1]));
    PF_CHECK(S0[tail_cell] == PF_R(0.0), "plain least squares puts the tail cell at 0: %g", (double)S0[tail_cell]);
    /* with the prior: the tail cell holds ~1e-6 of a cell's energy, so its T S stays near 1
       (plain least squares: 0) */
    for (c = 0; c < cells; ++c)
        if (c != tail_cell) worst_fit = fmaxl(worst_fit, fabsl((long double)S[c] / (long double)S[0] - 1.0L));
    PF_CHECK(fabsl((long double)S[tail_cell] * (long double)T[1] - 1.0L) <= 0.35L,
             "tail cell scaled by %g, not near 1", (double)(S[tail_cell] * T[1]));
    /* every other cell fits the same R, so only the prior separates them: a cell of energy q is
       pulled 0.1 qbar / (q + 0.1 qbar) of the way toward 1, and the cells' energies differ */
    PF_CHECK(worst_fit <= 0.03L, "well-sampled cells moved by %.3Lg", worst_fit);
    /* patch 0's ratio 1.5 / 0.8 survives within the prior's 10% pull */
    PF_CHECK(fabsl((long double)(T[0] / T[1]) / (1.5L / 0.8L) - 1.0L) <= 0.1L, "T ratio %g", (double)(T[0] / T[1]));
    /* the weak patch (1e-4 of the energy) gets no T of its own (1 before T's normalization to
       mean 1), so T S is the unnormalized S, a few % from 1 here; plain least squares gave it
       its data's 0.8 relative to patch 1 */
    PF_CHECK(fabsl((long double)T[weak] * (long double)S[0] - 1.0L) <= 0.05L, "weak patch T S = %g", (double)(T[weak] * S[0]));
    /* pfi_vmf_scale_t: the closed form (sum e l S + p) / (sum (l S)^2 + p), computed here */
    for (s = 0; s < cnt; ++s) {
        long double l = (long double)fl[cnt + s] * (long double)S[pfi_vmf_scale_cell(s, NT, NP)];
        a += (long double)fe[cnt + s] * l;
        q += l * l;
    }
    t_one = pfi_vmf_scale_t(fe + cnt, fl + cnt, NT, NP, S, prior);
    a = (a + (long double)prior) / (q + (long double)prior); /* the closed form */
    PF_CHECK(prior > PF_R(0.0) && fabsl((long double)t_one / a - 1.0L) <= 1e3L * PF_TEST_EPS, "pfi_vmf_scale_t %g against %Lg",
             (double)t_one, a);
    PF_CHECK(pfi_vmf_scale_t(fe + cnt, fl + cnt, NT, NP, S, PF_R(1e30)) == PF_R(1.0) ||
                 fabs((double)pfi_vmf_scale_t(fe + cnt, fl + cnt, NT, NP, S, PF_R(1e30)) - 1.0) <= 1e-6,
             "a huge prior gives 1");
}

/* a separable R = T0(x) S0(cell) must be recovered exactly by the rank-1 fit */
static void test_scale_factor_separable(void)
{
    enum { NT = 3, NP = 2, P = 5 };
    long long cnt = pf_vmf_scale_sample_count(NT, NP), cells = pf_vmf_scale_cell_count(NT, NP), s, c;
    pf_real *fe = (pf_real *)malloc((size_t)(cnt * P) * sizeof(pf_real)), *fl = (pf_real *)malloc((size_t)(cnt * P) * sizeof(pf_real));
    pf_real *scr = (pf_real *)malloc((size_t)(2 * cells * P) * sizeof(pf_real)), T[P], S[NT * NT * NP], err[3], t0[P],
            s0[NT * NT * NP];
    pf_test_rng r;
    long double worst = 0, ratio;
    int x;
    r = pf_test_rng_seed(77);
    PF_CHECK(cnt == 36 && cells == 18, "counts %lld %lld", cnt, cells);
    if (!fe || !fl || !scr) {
        PF_CHECK(0, "alloc");
        return;
    }
    for (x = 0; x < P; ++x) t0[x] = (pf_real)(0.5 + pf_test_uniform_open(&r));
    for (c = 0; c < cells; ++c) s0[c] = (pf_real)(0.2 + 2.0 * pf_test_uniform_open(&r));
    for (x = 0; x < P; ++x)
        for (s = 0; s < cnt; ++s) {
            fl[x * cnt + s] = (pf_real)(pf_test_uniform_open(&r) * pf_test_uniform_open(&r) * 3.0);
            fe[x * cnt + s] = t0[x] * s0[pfi_vmf_scale_cell(s, NT, NP)] * fl[x * cnt + s];
        }
    PF_CHECK(pfi_vmf_scale_factor(fe, fl, P, NT, NP, 60, PF_R(0.0), T, S, scr, NULL, err) == PF_OK, "factor");
    ratio = (long double)T[0] / (long double)t0[0];
    for (x = 0; x < P; ++x) worst = fmaxl(worst, fabsl((long double)T[x] / (long double)t0[x] / ratio - 1.0L));
    for (c = 0; c < cells; ++c) worst = fmaxl(worst, fabsl((long double)S[c] * ratio / (long double)s0[c] - 1.0L));
    pf_test_note("separable R: T S recovered to %.2Le, errors %.2e (BRDF) %.2e (R), unscaled %.2e", worst, (double)err[0],
                 (double)err[2], (double)err[1]);
    PF_CHECK(worst <= 100.0L * PF_TEST_EPS && err[0] <= 100 * PF_REAL_EPSILON && err[2] <= 100 * PF_REAL_EPSILON &&
                 err[1] > PF_R(0.1),
             "worst %.3Le err %g %g", worst, (double)err[0], (double)err[2]);
    ratio = 0;
    for (x = 0; x < P; ++x) ratio += (long double)T[x];
    PF_CHECK(fabsl(ratio / (long double)P - 1.0L) <= 10.0L * PF_TEST_EPS, "T mean %.17Lg", ratio / (long double)P);
    free(fe);
    free(fl);
    free(scr);
}

/* the lookup returns a cell's value at its centre directions, the shader path equals the CPU
   lookup, and pf_vmf_scale_apply multiplies; half-way between two theta nodes it is their mean */
static void test_scale_lookup(void)
{
    enum { NT = 4, NP = 3 };
    pf_real tab[NT * NT * NP], tm = PF_R(1.3);
    int a, b, c, bad = 0;
    for (a = 0; a < NT * NT * NP; ++a) tab[a] = (pf_real)(1 + a);
    for (a = 0; a < NT; ++a)
        for (b = 0; b < NT; ++b)
            for (c = 0; c < NP; ++c) {
                /* wo at azimuth 0, wi at c pi/(np - 1): node c of phi_d (undefined at theta 0) */
                pf_vec3 wo = pfi_vmf_scale_dir(b, 0, NT, NP, tm), wi = pfi_vmf_scale_dir(a, c, NT, NP, tm);
                pf_real got;
                if ((a == 0 || b == 0) && c != 0) continue;
                got = pf_vmf_scale_lookup(tab, NT, NP, tm, wo, wi);
                if (PF_FABS(got - tab[(a * NT + b) * NP + c]) > PF_R(1e-4) * tab[(a * NT + b) * NP + c]) bad++;
            }
    PF_CHECK(bad == 0, "%d nodes read wrong", bad);
    {
        pf_real th = PF_R(1.5) * tm / (pf_real)(NT - 1), got;
        pf_vec3 wo = pfi_vmf_scale_dir(2, 0, NT, NP, tm);
        pf_vec3 wi = pf_vec3_make(PF_SIN(th) * PF_COS(PF_PI), PF_SIN(th) * PF_SIN(PF_PI), PF_COS(th));
        got = pf_vmf_scale_lookup(tab, NT, NP, tm, wo, wi);
        PF_CHECK(PF_FABS(got - PF_R(0.5) * (tab[(1 * NT + 2) * NP + 2] + tab[(2 * NT + 2) * NP + 2])) <= PF_R(1e-3),
                 "half-way %g", (double)got);
    }
    PF_CHECK(pf_vmf_scale_lookup(0, NT, NP, tm, pf_vec3_make(0, 0, 1), pf_vec3_make(0, 0, 1)) == PF_R(1.0), "NULL table");
    PF_CHECK(pf_vmf_scale_apply(PF_R(2.0), PF_R(3.0), PF_R(0.5)) == PF_R(3.0) &&
                 pf_vmf_scale_apply(PF_R(-1.0), PF_R(1.0), PF_R(1.0)) == PF_R(0.0) &&
                 pf_vmf_scale_apply((pf_real)NAN, PF_R(1.0), PF_R(1.0)) == PF_R(0.0),
             "apply");
}

/* bad input, every buffer exactly its documented size behind guard pages */
static void test_scale_bad_input_guarded(void)
{
    const int W = 16, N = 8, NT = 2, NP = 2;
    long long cnt = pf_vmf_scale_sample_count(NT, NP), vb = pf_vmf_scale_vis_bytes(NT, NP, N), cells = pf_vmf_scale_cell_count(NT, NP);
    size_t hb = (size_t)W * W * sizeof(pf_real), nb = (size_t)3 * N * N * sizeof(pf_real), fb = (size_t)cnt * sizeof(pf_real);
    pf_real *hm = (pf_real *)pf_test_guarded_alloc(hb), *nr = (pf_real *)pf_test_guarded_alloc(nb);
    pf_real *fe = (pf_real *)pf_test_guarded_alloc(fb), *fl = (pf_real *)pf_test_guarded_alloc(fb);
    pf_real *T = (pf_real *)pf_test_guarded_alloc(sizeof(pf_real)), *S = (pf_real *)pf_test_guarded_alloc((size_t)cells * sizeof(pf_real));
    pf_real *scr = (pf_real *)pf_test_guarded_alloc((size_t)(2 * cells) * sizeof(pf_real)), out = PF_R(7.0), err[3], prior = PF_R(-1.0);
    unsigned char *vis = (unsigned char *)pf_test_guarded_alloc((size_t)vb);
    pf_vec3 z = pf_vec3_make(PF_R(0.3), PF_R(0.0), PF_R(0.9539392));
    int i;
    if (!hm || !nr || !fe || !fl || !T || !S || !scr || !vis) {
        pf_test_note("guarded allocation unsupported: skipped");
        return;
    }
    for (i = 0; i < W * W; ++i) hm[i] = (pf_real)(0.3 * sin(0.7 * i) + 0.2 * cos(1.3 * (i / W)));
    /* valid calls at the patch in the map's last corner (wrapping reads) touch nothing outside */
    PF_CHECK(pfi_vmf_effective_brdf(hm, W, W, PF_R(1.0), W - 3, W - 5, N, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_OK &&
                 pf_test_finite(out) && out >= PF_R(0.0),
             "valid brdf %g", (double)out);
    PF_CHECK(pfi_vmf_scale_patch(hm, W, W, PF_R(1.0), W - 3, W - 5, N, 2, 8, PF_R(0.1), PF_R(1.0), PF_VMF_SCALE_G_MIXTURE, NT,
                                NP, PF_R(1.2), nr, vis, fe, fl) == PF_OK,
             "valid patch");
    for (i = 0; i < cnt; ++i) PF_CHECK(pf_test_finite(fe[i]) && pf_test_finite(fl[i]) && fe[i] >= 0 && fl[i] >= 0, "sample %d", i);
    PF_CHECK(pfi_vmf_scale_factor(fe, fl, 1, NT, NP, 4, PF_R(1.0), T, S, scr, &prior, err) == PF_OK && pf_test_finite(T[0]) &&
                 pf_test_finite(prior) && prior >= 0,
             "valid factor");
    PF_CHECK(pf_test_finite(pfi_vmf_scale_t(fe, fl, NT, NP, S, prior)), "valid T");
    /* errors */
    PF_CHECK(pfi_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, 0, N, z, z, PF_R(0.1), PF_R(1.0), NULL) == PF_ERR_ARG, "NULL out");
    PF_CHECK(pfi_vmf_effective_brdf(NULL, W, W, PF_R(1.0), 0, 0, N, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG && out == 0,
             "NULL heights");
    PF_CHECK(pfi_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, 0, W + 1, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG, "n > w");
    PF_CHECK(pfi_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, 0, 0, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG, "n = 0");
    PF_CHECK(pfi_vmf_effective_brdf(hm, W, W, PF_R(0.0), 0, 0, N, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG, "texel 0");
    PF_CHECK(pfi_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, 0, N, z, z, (pf_real)NAN, PF_R(1.0), &out) == PF_ERR_ARG, "sigma NaN");
    PF_CHECK(pfi_vmf_effective_brdf(hm, (int)(PF_MAX_SIDE + 1), 1, PF_R(1.0), 0, 0, 1, z, z, PF_R(0.1), PF_R(1.0), &out) ==
                 PF_ERR_SIZE,
             "side");
    hm[(W - 4) * W + 2] = (pf_real)NAN; /* inside the patch (0, W - 5, N): rows W - 5 .. W + 2 wrap */
    PF_CHECK(pfi_vmf_effective_brdf(hm, W, W, PF_R(1.0), 0, W - 5, N, z, z, PF_R(0.1), PF_R(1.0), &out) == PF_ERR_ARG && out == 0,
             "NaN height");
    PF_CHECK(pfi_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, W - 5, N, 2, 8, PF_R(0.1), PF_R(1.0), PF_VMF_SCALE_UNMASKED, NT, NP, PF_R(1.2), nr, vis, fe,
                                fl) == PF_ERR_ARG,
             "NaN height, patch");
    hm[(W - 4) * W + 2] = PF_R(0.0);
    PF_CHECK(pfi_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, 0, N, PF_VMF_MAX_LOBES + 1, 8, PF_R(0.1), PF_R(1.0), PF_VMF_SCALE_UNMASKED, NT, NP,
                                PF_R(1.2), nr, vis, fe, fl) == PF_ERR_ARG,
             "lobes 17");
    PF_CHECK(pfi_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, 0, N, 2, 8, PF_R(0.1), PF_R(1.0), 0, NT, NP, PF_R(1.2), nr, vis, fe, fl) ==
                 PF_ERR_ARG,
             "masking 0 (unknown)");
    PF_CHECK(pfi_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, 0, N, 2, 8, PF_R(0.1), PF_R(1.0), PF_VMF_SCALE_UNMASKED, NT, NP, PF_R(1.6), nr, vis, fe, fl) ==
                 PF_ERR_ARG,
             "theta_max >= pi/2");
    PF_CHECK(pfi_vmf_scale_patch(hm, W, W, PF_R(1.0), 0, 0, N, 2, 8, PF_R(0.1), PF_R(1.0), PF_VMF_SCALE_UNMASKED, NT, NP, PF_R(1.2), nr, NULL, fe, fl) ==
                 PF_ERR_ARG,
             "NULL scratch");
    PF_CHECK(pfi_vmf_scale_factor(fe, fl, 0, NT, NP, 4, PF_R(0.0), T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pfi_vmf_scale_factor(fe, fl, 1, NT, NP, 0, PF_R(0.0), T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pfi_vmf_scale_factor(fe, NULL, 1, NT, NP, 4, PF_R(0.0), T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pfi_vmf_scale_factor(fe, fl, 1, NT, NP, 4, PF_R(-1.0), T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pfi_vmf_scale_factor(fe, fl, 1, NT, NP, 4, (pf_real)NAN, T, S, scr, NULL, err) == PF_ERR_ARG &&
                 pfi_vmf_scale_factor(fe, fl, 1, 1 << 30, 1 << 30, 4, PF_R(0.0), T, S, scr, NULL, err) == PF_ERR_SIZE,
             "factor errors");
    PF_CHECK(pfi_vmf_scale_t(NULL, fl, NT, NP, S, PF_R(0.0)) == PF_R(1.0) && pfi_vmf_scale_t(fe, fl, 1, NP, S, PF_R(0.0)) == PF_R(1.0) &&
                 pfi_vmf_scale_t(fe, fl, NT, NP, NULL, PF_R(0.0)) == PF_R(1.0) &&
                 pfi_vmf_scale_t(fe, fl, NT, NP, S, (pf_real)NAN) == PF_R(1.0) && pfi_vmf_scale_t(fe, fl, NT, NP, S, PF_R(-1.0)) == PF_R(1.0),
             "T errors");
    PF_CHECK(pf_vmf_scale_sample_count(1, 2) == 0 && pf_vmf_scale_cell_count(2, 1) == 0 && pf_vmf_scale_vis_bytes(2, 2, 0) == 0,
             "size queries");
    pf_test_guarded_free(hm, hb);
    pf_test_guarded_free(nr, nb);
    pf_test_guarded_free(fe, fb);
    pf_test_guarded_free(fl, fb);
    pf_test_guarded_free(T, sizeof(pf_real));
    pf_test_guarded_free(S, (size_t)cells * sizeof(pf_real));
    pf_test_guarded_free(scr, (size_t)(2 * cells) * sizeof(pf_real));
    pf_test_guarded_free(vis, (size_t)vb);
}
/* ================================================================== end of scaling function tests */

/* ------------------------------------------------------------------ the level calls
   pf_vmf_scale_fit_level and pf_vmf_scale_texel_t against the orchestration written out here
   from the per-patch pieces (pfi_vmf_scale_patch for f_eff, the texel's lobes shaded at the
   node-direction pairs in the documented sample order, pfi_vmf_scale_factor, pfi_vmf_scale_t):
   the same operations, so the results must be bit-identical; a zeroed description field
   reads as its documented default; pf_vmf_effective_brdf(desc) is the positional call;
   bad descriptions, levels and scratch sizes (guarded) are rejected. */
#define LV_W 32
#define LV_L 2 /* level: 4 x 4 patches, 8 x 8 of them */
#define LV_NT 3
#define LV_NP 3
#define LV_P 4 /* training patches */
static void lv_texel_lobes(const pf_real *pyr, int m, long long tx, long long ty, pf_real *fl)
{
    const long long A = 2 * (LV_NP - 1), cnt = pf_vmf_scale_sample_count(LV_NT, LV_NP), lw = LV_W >> LV_L;
    const pf_real *t = pyr + (pf_vmf_pyramid_level_offset(LV_W, LV_W, LV_L) + ty * lw + tx) * 4 * m;
    const pf_real tm = PF_R(1.2);
    long long s;
    for (s = 0; s < cnt; ++s) {
        long long ai = s % A, ti = (s / A) % LV_NT, ao = (s / (A * LV_NT)) % A, to = s / (A * LV_NT * A);
        pf_vec3 wo = pfi_vmf_scale_dir((int)to, (int)ao, LV_NT, LV_NP, tm), wi = pfi_vmf_scale_dir((int)ti, (int)ai, LV_NT, LV_NP, tm);
        pf_vmf_sum sum = pf_vmf_sum_zero();
        int j;
        for (j = 0; j < m; ++j)
            sum = pf_vmf_sum_add(sum, pf_vmf_lobe_make(t[4 * j + 3], t[4 * j], t[4 * j + 1], t[4 * j + 2]), wo, wi,
                                 PF_R(0.1) * PF_R(0.1));
        fl[s] = pf_vmf_sum_specular(sum, wo, wi, PF_R(1.0));
    }
}
static void test_scale_level_calls(void)
{
    enum { CNT = (2 * LV_NT * (LV_NP - 1)) * (2 * LV_NT * (LV_NP - 1)), CELLS = LV_NT * LV_NT * LV_NP, N = 1 << LV_L };
    static pf_real fe[LV_P * CNT], fl[2][LV_P * CNT], junk[CNT], nr[3 * N * N], T[LV_P], fac[2 * LV_P * CELLS];
    static pf_real S_want[2][CELLS], S_got[2][CELLS], t_got[2][(LV_W >> LV_L) * (LV_W >> LV_L)];
    static unsigned char vis[2 * LV_NT * (LV_NP - 1) * N * N];
    const int ms[2] = { 2, 4 }, gp = (LV_W >> LV_L) * (LV_W >> LV_L);
    pf_real prior_want[2], prior_got[2], *pyr[2] = { 0, 0 }, *hm = 0, *scratch = 0, *s_out[2], *t_lv[2], t_one[2];
    const pf_real *s_in[2];
    pfm_surface s;
    pf_vmf_scale_desc d, z;
    long long need, p, i;
    int k, bad = 0, rc;
    if (pfm_surface_make(&s, LV_W, LV_W, 1.0, pfm_params_default(PFM_CRATERS)) != 0 || !(hm = scale_heights(&s))) {
        PF_CHECK(0, "no memory");
        return;
    }
    {   /* the map's normals and two lobe pyramids */
        pf_real *nm = (pf_real *)malloc((size_t)LV_W * LV_W * 3 * sizeof(pf_real));
        for (k = 0; k < 2 && nm; ++k) pyr[k] = (pf_real *)malloc((size_t)pf_vmf_pyramid_texel_count(LV_W, LV_W) * 4 * ms[k] * sizeof(pf_real));
        if (!nm || !pyr[0] || !pyr[1]) { PF_CHECK(0, "no memory"); free(nm); goto done; }
        for (i = 0; i < (long long)LV_W * LV_W; ++i) {
            double m3[3];
            pfm_normal(&s, (int)(i % LV_W), (int)(i / LV_W), m3);
            for (k = 0; k < 3; ++k) nm[3 * i + k] = (pf_real)m3[k];
        }
        for (k = 0; k < 2; ++k) PF_CHECK(pf_vmf_pyramid_from_normals(nm, NULL, LV_W, LV_W, ms[k], 8, pyr[k]) == PF_OK, "pyramid");
        free(nm);
    }
    /* the orchestration, written out */
    for (p = 0; p < LV_P; ++p) {
        long long c = (p * gp) / LV_P, tx = c % (LV_W >> LV_L), ty = c / (LV_W >> LV_L);
        PF_CHECK(pfi_vmf_scale_patch(hm, LV_W, LV_W, PF_R(1.0), (int)(tx * N), (int)(ty * N), N, 1, 0, PF_R(0.1), PF_R(1.0),
                                     PF_VMF_SCALE_G_GAUSSIAN, LV_NT, LV_NP, PF_R(1.2), nr, vis, fe + p * CNT, junk) == PF_OK,
                 "patch");
        for (k = 0; k < 2; ++k) lv_texel_lobes(pyr[k], ms[k], tx, ty, fl[k] + p * CNT);
    }
    for (k = 0; k < 2; ++k)
        PF_CHECK(pfi_vmf_scale_factor(fe, fl[k], LV_P, LV_NT, LV_NP, 5, PF_R(0.5), T, S_want[k], fac, &prior_want[k], NULL) == PF_OK,
                 "factor");
    /* the library's level call, every field given */
    memset(&d, 0, sizeof d);
    d.heights = hm, d.w = LV_W, d.h = LV_W, d.texel = PF_R(1.0), d.base_sigma = PF_R(0.1), d.f0 = PF_R(1.0);
    d.pyramid_count = 2, d.pyramid[0] = pyr[0], d.pyramid[1] = pyr[1], d.lobes[0] = ms[0], d.lobes[1] = ms[1];
    d.masking = PF_VMF_SCALE_G_GAUSSIAN, d.nt = LV_NT, d.np = LV_NP, d.theta_max = PF_R(1.2);
    d.train_patches = LV_P, d.rounds = 5, d.shrink = PF_R(0.5);
    need = pf_vmf_scale_scratch_size(&d, LV_L);
    PF_CHECK(need == LV_P * CNT * 3 + 2 * LV_P * CELLS + LV_P + 3 * N * N + CNT + (long long)((sizeof vis + sizeof(pf_real) - 1) / sizeof(pf_real)),
             "scratch size %lld", need);
    scratch = (pf_real *)pf_test_guarded_alloc((size_t)need * sizeof(pf_real));
    if (!scratch) { pf_test_note("guarded mapping unavailable: level calls skipped"); goto done; }
    for (k = 0; k < 2; ++k) {
        s_out[k] = S_got[k], t_lv[k] = t_got[k], s_in[k] = S_got[k];
        for (i = 0; i < gp; ++i) t_got[k][i] = PF_R(-7.0);
    }
    PF_CHECK(pf_vmf_scale_fit_level(&d, LV_L, s_out, prior_got, t_lv, scratch, need) == PF_OK, "fit_level");
    for (k = 0; k < 2; ++k) {
        for (i = 0; i < CELLS; ++i) bad += S_got[k][i] != S_want[k][i];
        bad += prior_got[k] != prior_want[k];
        for (p = 0; p < LV_P; ++p) {
            pf_real tw = pfi_vmf_scale_t(fe + p * CNT, fl[k] + p * CNT, LV_NT, LV_NP, S_want[k], prior_want[k]);
            bad += t_got[k][(p * gp) / LV_P] != tw;
        }
        for (i = 0, p = 0; i < gp; ++i) p += t_got[k][i] == PF_R(-7.0);
        bad += p != gp - LV_P; /* only the training texels written */
    }
    PF_CHECK(bad == 0, "%d values of the level call differ from the written-out orchestration", bad);
    /* T of a texel that is not a training one, from its own samples */
    {
        long long tx = 3, ty = 5;
        PF_CHECK(pfi_vmf_scale_patch(hm, LV_W, LV_W, PF_R(1.0), (int)(tx * N), (int)(ty * N), N, 1, 0, PF_R(0.1), PF_R(1.0),
                                     PF_VMF_SCALE_G_GAUSSIAN, LV_NT, LV_NP, PF_R(1.2), nr, vis, fe, junk) == PF_OK, "patch");
        PF_CHECK(pf_vmf_scale_texel_t(&d, LV_L, tx, ty, s_in, prior_got, t_one, scratch, need) == PF_OK, "texel_t");
        for (k = 0; k < 2; ++k) {
            lv_texel_lobes(pyr[k], ms[k], tx, ty, fl[k]);
            PF_CHECK(t_one[k] == pfi_vmf_scale_t(fe, fl[k], LV_NT, LV_NP, S_want[k], prior_want[k]), "texel_t %d: %g", k,
                     (double)t_one[k]);
        }
    }
    /* zero means the default: texel 1, base_sigma 0.1, f0 1, masking G_GAUSSIAN, shrink 1 */
    z = d;
    z.texel = PF_R(0.0), z.base_sigma = PF_R(0.0), z.f0 = PF_R(0.0), z.masking = 0, z.shrink = PF_R(0.0);
    d.shrink = PF_R(1.0);
    {
        pf_real sa[2][CELLS], sb[2][CELLS], pa[2], pb[2], *oa[2] = { sa[0], sa[1] }, *ob[2] = { sb[0], sb[1] };
        rc = pf_vmf_scale_fit_level(&d, LV_L, oa, pa, NULL, scratch, need);
        PF_CHECK(rc == PF_OK && pf_vmf_scale_fit_level(&z, LV_L, ob, pb, NULL, scratch, need) == PF_OK &&
                     memcmp(sa, sb, sizeof sa) == 0 && pa[0] == pb[0] && pa[1] == pb[1],
                 "zeroed fields read as the defaults");
    }
    /* the effective BRDF through the description */
    {
        pf_vec3 wo = pf_vec3_make(PF_R(0.3), PF_R(0.1), PF_R(0.948683)), wi = pf_vec3_make(PF_R(-0.2), PF_R(0.2), PF_R(0.958166));
        pf_real a = PF_R(-1.0), b = PF_R(-2.0);
        PF_CHECK(pf_vmf_effective_brdf(&z, 4, 8, 8, wo, wi, &a) == PF_OK &&
                     pfi_vmf_effective_brdf(hm, LV_W, LV_W, PF_R(1.0), 4, 8, 8, wo, wi, PF_R(0.1), PF_R(1.0), &b) == PF_OK && a == b,
                 "pf_vmf_effective_brdf(desc) %g, positional %g", (double)a, (double)b);
        PF_CHECK(pf_vmf_effective_brdf(NULL, 0, 0, 1, wo, wi, &a) == PF_ERR_ARG && a == PF_R(0.0), "NULL desc");
    }
    /* bad descriptions, levels, scratch */
    PF_CHECK(pf_vmf_scale_fit_level(NULL, LV_L, s_out, prior_got, NULL, scratch, need) == PF_ERR_ARG, "NULL desc");
    PF_CHECK(pf_vmf_scale_fit_level(&d, LV_L, s_out, prior_got, NULL, scratch, need - 1) == PF_ERR_ARG, "short scratch");
    PF_CHECK(pf_vmf_scale_fit_level(&d, 6, s_out, prior_got, NULL, scratch, need) == PF_ERR_ARG, "no level 6 in 32 x 32");
    PF_CHECK(pf_vmf_scale_scratch_size(&d, 6) == 0 && pf_vmf_scale_scratch_size(NULL, 0) == 0, "scratch size of bad calls");
    PF_CHECK(pf_vmf_scale_texel_t(&d, LV_L, 8, 0, s_in, prior_got, t_one, scratch, need) == PF_ERR_ARG, "texel outside");
    z = d, z.w = 24;
    PF_CHECK(pf_vmf_scale_fit_level(&z, LV_L, s_out, prior_got, NULL, scratch, need) == PF_ERR_ARG, "w not a power of two");
    z = d, z.lobes[1] = 0;
    PF_CHECK(pf_vmf_scale_fit_level(&z, LV_L, s_out, prior_got, NULL, scratch, need) == PF_ERR_ARG, "lobes 0");
    z = d, z.pyramid[0] = NULL;
    PF_CHECK(pf_vmf_scale_fit_level(&z, LV_L, s_out, prior_got, NULL, scratch, need) == PF_ERR_ARG, "NULL pyramid");
    z = d, z.pyramid_count = PF_VMF_SCALE_MAX_PYRAMIDS + 1;
    PF_CHECK(pf_vmf_scale_fit_level(&z, LV_L, s_out, prior_got, NULL, scratch, need) == PF_ERR_ARG, "too many pyramids");
    z = d, z.masking = 7;
    PF_CHECK(pf_vmf_scale_fit_level(&z, LV_L, s_out, prior_got, NULL, scratch, pf_vmf_scale_scratch_size(&z, LV_L)) == PF_ERR_ARG,
             "unknown masking");
    pf_test_guarded_free(scratch, (size_t)need * sizeof(pf_real));
done:
    free(pyr[0]);
    free(pyr[1]);
    free(hm);
    pfm_surface_free(&s);
}


/* ================================================================== SAFETY: sizes, extremes, contracts
   Reproducers of the defects found by probing the CPU functions as a new user would (guard
   pages, the whole int range, tiny and huge data): each test names the call that failed and
   checks the contract instead. edge_ ones also run under -ffast-math. */
/* pf_vmf_scale_lookup / pf_vmf_scale_cell_count with np beyond PF_MAX_SIDE (np = 2^24 + 4,
   INT_MAX): the table of 16 reals sits against a guard page; before, the float node position
   rounded past the last node and the lookup read past the table (ASan SEGV) */
static void edge_safety_scale_sizes(void)
{
    pf_vec3 wo = pf_vec3_make(PF_R(0.7071), PF_R(0.0), PF_R(0.7071)), wi = pf_vec3_make(-PF_R(0.7071), PF_R(0.0), PF_R(0.7071));
    size_t tb = 16 * sizeof(pf_real);
    pf_real *tab = (pf_real *)pf_test_guarded_alloc(tb), got;
    static const int bad[4] = { (1 << 24) + 1, (1 << 24) + 4, 0x7fffffff, -5 };
    int k, a, b, c, outside = 0;
    for (k = 0; k < 4; ++k) {
        PF_CHECK(pf_vmf_scale_cell_count(2, bad[k]) == 0 && pf_vmf_scale_cell_count(bad[k], 2) == 0 &&
                     pf_vmf_scale_sample_count(2, bad[k]) == 0 && pf_vmf_scale_sample_count(bad[k], 2) == 0 &&
                     pf_vmf_scale_vis_bytes(2, bad[k], 1) == 0 && pf_vmf_scale_vis_bytes(2, 2, bad[k]) == 0,
                 "np = %d accepted: %lld cells", bad[k], pf_vmf_scale_cell_count(2, bad[k]));
    }
    PF_CHECK(pf_vmf_scale_cell_count(2, 1 << 24) == (1LL << 26), "np = 2^24: %lld", pf_vmf_scale_cell_count(2, 1 << 24));
    if (!tab) {
        pf_test_note("skipped the lookups: no guarded mappings here");
        return;
    }
    for (k = 0; k < 16; ++k) tab[k] = PF_R(2.0);
    got = pf_vmf_scale_lookup(tab, 2, (1 << 24) + 4, PF_R(0.1), wo, wi);
    PF_CHECK(got == PF_R(1.0), "np = 2^24 + 4: %g (want 1, no read)", (double)got);
    got = pf_vmf_scale_lookup(tab, 2, 0x7fffffff, PF_R(0.1), wo, wi);
    PF_CHECK(got == PF_R(1.0), "np = INT_MAX: %g", (double)got);
    /* a table of exactly nt nt np = 2 x 2 x 4 reals: every direction (grazing, beyond
       theta_max, below the horizon, NaN) reads inside it and returns a table value */
    for (a = -2; a <= 12; ++a)
        for (b = -2; b <= 12; ++b)
            for (c = 0; c < 8; ++c) {
                pf_real to = PF_R(0.16) * (pf_real)a, ti = PF_R(0.16) * (pf_real)b, ph = PF_R(0.8) * (pf_real)c;
                pf_vec3 o = pf_vec3_make(PF_SIN(to), PF_R(0.0), PF_COS(to));
                pf_vec3 i = pf_vec3_make(PF_SIN(ti) * PF_COS(ph), PF_SIN(ti) * PF_SIN(ph), PF_COS(ti));
                if (c == 7) i.x = (pf_real)NAN;
                got = pf_vmf_scale_lookup(tab, 2, 4, PF_R(0.1) + PF_R(0.1) * (pf_real)c, o, i);
                outside += !(got == PF_R(2.0));
            }
    PF_CHECK(outside == 0, "%d lookups not the table's value 2", outside);
    pf_test_guarded_free(tab, tb);
}

/* pf_vmf_scale_factor on a dark sample set (f_eff[0] = 1e-10, f_lobes[0] = 1e-30, rest 0):
   before, err[2] = NaN (float); and a separable set scaled by 1e20: before, T = 1, 1, 1 and
   err[0..1] = NaN (float). T, S and the errors are finite, the separable T recovered. */
static void edge_safety_scale_factor_extremes(void)
{
    enum { NT = 2, NP = 2, P = 3 };
    long long cnt = pf_vmf_scale_sample_count(NT, NP), cells = pf_vmf_scale_cell_count(NT, NP), s;
    pf_real fe[P * 16], fl[P * 16], scr[2 * 8 * P], T[P], S[8], err[3], prior = PF_R(-1.0);
    const pf_real t0[P] = { PF_R(0.5), PF_R(1.0), PF_R(2.5) };
    const pf_real scales[3] = { PF_R(1e20), PF_R(1e-20), PF_R(1.0) };
    int x, k, rc, bad = 0;
    PF_CHECK(cnt == 16 && cells == 8, "counts %lld %lld", cnt, cells);
    if (cnt != 16 || cells != 8) return;
    for (s = 0; s < P * 16; ++s) fe[s] = fl[s] = PF_R(0.0);
    fe[0] = PF_R(1e-10);
    fl[0] = PF_R(1e-30);
    rc = pfi_vmf_scale_factor(fe, fl, 1, NT, NP, 10, PF_R(0.0), T, S, scr, &prior, err);
    for (k = 0; k < 3; ++k) bad += !(pf_test_bits_finite(err[k]) && err[k] >= PF_R(0.0) && err[k] <= PF_R(2.0));
    bad += !pf_test_bits_finite(T[0]) || !pf_test_bits_finite(prior);
    for (s = 0; s < cells; ++s) bad += !pf_test_bits_finite(S[s]);
    PF_CHECK(rc == PF_OK && bad == 0, "dark set: rc %d, err %g %g %g, T %g", rc, (double)err[0], (double)err[1], (double)err[2],
             (double)T[0]);
    for (k = 0; k < 3; ++k) {
        long double worst = 0;
        for (x = 0; x < P; ++x)
            for (s = 0; s < cnt; ++s) {
                fl[x * cnt + s] = scales[k] * (pf_real)(1 + s % 5);
                fe[x * cnt + s] = t0[x] * fl[x * cnt + s] * (pf_real)(1 + pfi_vmf_scale_cell(s, NT, NP) % 3);
            }
        rc = pfi_vmf_scale_factor(fe, fl, P, NT, NP, 30, PF_R(0.0), T, S, scr, NULL, err);
        /* T has mean 1: t0 / mean(t0) = 0.375, 0.75, 1.875 */
        for (x = 0; x < P; ++x) worst = fmaxl(worst, fabsl((long double)T[x] - (long double)t0[x] / (4.0L / 3.0L)));
        PF_CHECK(rc == PF_OK && worst <= 1e-4L && err[0] <= PF_R(1e-4) && err[2] <= PF_R(1e-4) && pf_test_bits_finite(err[1]),
                 "separable x %g: T %g %g %g (want 0.375 0.75 1.875), err %g %g %g", (double)scales[k], (double)T[0], (double)T[1],
                 (double)T[2], (double)err[0], (double)err[1], (double)err[2]);
        PF_CHECK(pf_test_bits_finite(pfi_vmf_scale_t(fe, fl, NT, NP, S, PF_R(0.0))), "scale_t x %g", (double)scales[k]);
    }
}

/* pf_vmf_effective_brdf on a periodic 32 x 32 map with n = 32 (a spike of 100 and of 10000
   texels, view and light 1 degree above the horizon): before, each march ran up to 65,536
   cells (0.27-1.4 s against 0.0004 s in a 33-wide map), and the 10000 spike called the rays
   occluded at the cell cap (0.0017 against 1.64). The march now covers one period: the
   answer equals the 33-wide map's (whose box ends the rays at the patch's edge). */
static void test_safety_effective_periodic(void)
{
    static pf_real hm[33 * 32];
    const pf_real spikes[2] = { PF_R(100.0), PF_R(10000.0) };
    pf_real el = PF_R(1.0) * PF_PI / PF_R(180.0), out[2];
    pf_vec3 wo = pf_vec3_make(PF_COS(el), PF_R(0.0), PF_SIN(el)), wi = pf_vec3_make(-PF_COS(el), PF_R(0.0), PF_SIN(el));
    int k, W, i, rc;
    for (k = 0; k < 2; ++k) {
        for (W = 32; W <= 33; ++W) {
            for (i = 0; i < 33 * 32; ++i) hm[i] = PF_R(0.0);
            hm[16 * W + 16] = spikes[k];
            rc = pfi_vmf_effective_brdf(hm, W, 32, PF_R(1.0), 0, 0, 32, wo, wi, PF_R(0.3), PF_R(0.04), &out[W - 32]);
            PF_CHECK(rc == PF_OK && pf_test_bits_finite(out[W - 32]), "W %d rc %d", W, rc);
        }
        pf_test_note("spike %g: periodic %.6g, 33-wide %.6g", (double)spikes[k], (double)out[0], (double)out[1]);
        PF_CHECK(PF_FABS(out[0] - out[1]) <= PF_R(1e-4) * out[1], "spike %g: periodic %g, 33-wide %g", (double)spikes[k],
                 (double)out[0], (double)out[1]);
    }
}

/* contracts: heights at the documented limit of the effective BRDF (|h| < PF_REAL_MAX / 4) are
   accepted with a finite answer, beyond it PF_ERR_ARG as documented */
static void edge_safety_scale_contracts(void)
{
    pf_real hm[16], out = PF_R(-1.0), one = PF_R(1.0);
    int i, rc;
    for (i = 0; i < 16; ++i) hm[i] = (i & 1 ? one : -one) * PF_R(0.2) * PF_REAL_MAX;
    rc = pfi_vmf_effective_brdf(hm, 4, 4, PF_R(1.0), 0, 0, 2, pf_vec3_make(PF_R(0.6), PF_R(0.0), PF_R(0.8)),
                               pf_vec3_make(PF_R(0.0), PF_R(0.6), PF_R(0.8)), PF_R(0.3), PF_R(0.04), &out);
    PF_CHECK(rc == PF_OK && pf_test_bits_finite(out) && out >= PF_R(0.0), "0.2 PF_REAL_MAX heights: rc %d out %g", rc, (double)out);
    for (i = 0; i < 16; ++i) hm[i] = (i & 1 ? one : -one) * PF_R(0.3) * PF_REAL_MAX;
    rc = pfi_vmf_effective_brdf(hm, 4, 4, PF_R(1.0), 0, 0, 2, pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)),
                               pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(1.0)), PF_R(0.3), PF_R(0.04), &out);
    PF_CHECK(rc == PF_ERR_ARG && out == PF_R(0.0), "0.3 PF_REAL_MAX heights: rc %d (documented PF_ERR_ARG)", rc);
}

/* ================================================================== end of SAFETY */

/* pf_vmf_scale_coords at zero and underflowing directions: zenith 0 (PF_ATAN2 is 0 at (0, 0):
   pf_core.h), so the theta coordinate 0, never 1 (GLSL's atan(0, 0) gave 3 pi/4, clamped to
   1); phi_d 0 when either direction is along the normal. `tiny` squares to 0 in pf_real. */
static void edge_scale_coords_zero_directions(void)
{
    const pf_real z = PF_R(0.0), up = PF_R(1.0), tm = PF_R(1.3089969389957472);
    const pf_real tiny = PF_REAL_EPSILON < PF_R(1e-10) ? PF_R(1e-200) : PF_R(1e-30);
    pf_vec3 c0 = pf_vmf_scale_coords(pf_vec3_make(z, z, z), pf_vec3_make(z, z, up), tm);
    pf_vec3 c1 = pf_vmf_scale_coords(pf_vec3_make(tiny, tiny, z), pf_vec3_make(z, z, up), tm);
    pf_vec3 c2 = pf_vmf_scale_coords(pf_vec3_make(z, z, up), pf_vec3_make(z, z, z), tm);
    pf_vec3 c3 = pf_vmf_scale_coords(pf_vec3_make(tiny, z, z), pf_vec3_make(PF_R(0.6), z, PF_R(0.8)), tm);
    PF_CHECK(c0.x == z && c0.y == z && c0.z == z, "wo = 0: (%g, %g, %g)", (double)c0.x, (double)c0.y, (double)c0.z);
    PF_CHECK(c1.x == z && c1.y == z && c1.z == z, "wo underflowing: (%g, %g, %g)", (double)c1.x, (double)c1.y, (double)c1.z);
    PF_CHECK(c2.x == z && c2.y == z && c2.z == z, "wi = 0: (%g, %g, %g)", (double)c2.x, (double)c2.y, (double)c2.z);
    PF_CHECK(c3.y == z && c3.z == z && c3.x > PF_R(0.49) && c3.x < PF_R(0.50), "wo underflowing, wi at 36.9 deg: (%g, %g, %g)",
             (double)c3.x, (double)c3.y, (double)c3.z);
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_scale_flat_patch_is_base);
    PF_TEST_RUN(test_scale_reciprocity);
    PF_TEST_RUN(test_scale_vs_microsurface_reference);
    PF_TEST_RUN(test_scale_factor_separable);
    PF_TEST_RUN(test_scale_factor_shrink);
    PF_TEST_RUN(test_scale_lookup);
    PF_TEST_RUN(test_scale_bad_input_guarded);
    PF_TEST_RUN(test_scale_level_calls);

    PF_TEST_RUN(edge_safety_scale_sizes);
    PF_TEST_RUN(edge_safety_scale_factor_extremes);
    PF_TEST_RUN(test_safety_effective_periodic);
    PF_TEST_RUN(edge_safety_scale_contracts);
    PF_TEST_RUN(edge_scale_coords_zero_directions);
    return PF_TEST_END();
}

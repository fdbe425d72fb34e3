/* tests/fuzz/fuzz_horizon.c - libFuzzer harness for the evaluators of include/pf_horizon.h.

   Standalone (its own byte mapping, not pf_calls.h's table; the lead may move the evaluators
   into pf_calls.h entries, which tests/fuzz/coverage.sh asks for). Each input is read as
   32-bit words, twice:
   1. MAPPED: words mapped into the documented domains (moments with a non-negative variance,
      unit directions, visibilities in [0, 1], cos in [-1, 1], Legendre x in [-1, 1]); every
      result must be finite and in its documented range ([0, 1]; [0, 2] for the visible area;
      the hotspot and fully-lit limits of the bidirectional forms to 1e-5), else trap. The
      masking's skewed HDF (hz_skew): E[T] near 0 and negative, sigma_T down to 0, the
      slope-horizon correlation through +-1 and beyond, Var(S) from 0 to 4: in [0, 1]; with no
      covariance and a zero mean slope the area ratio is the clamped Gram-Charlier CDF,
      non-decreasing in the view's elevation.
   2. RAW: the words as floats (NaN, inf, subnormal) and small ints; only crashes and
      undefined behaviour count (ASan, UBSan). Build and run: sh tests/fuzz/run.sh. */
#include <stdio.h>
#include <string.h>
#include "pf_horizon.h"

typedef struct hz_src { const unsigned char *d; size_t n, at; unsigned long long rng; } hz_src;

static unsigned hz_word(hz_src *s)
{
    unsigned w = 0;
    int k;
    if (s->at + 4 <= s->n) {
        for (k = 0; k < 4; ++k) w = (w << 8) | s->d[s->at + k];
        s->at += 4;
        return w;
    }
    s->rng = s->rng * 6364136223846793005ULL + 1442695040888963407ULL;
    return (unsigned)(s->rng >> 32);
}
static pf_real hz_raw(hz_src *s)
{
    unsigned w = hz_word(s);
    float f;
    memcpy(&f, &w, sizeof f);
    return (pf_real)f;
}
/* uniform in [lo, hi], 1 in 8 exactly an end */
static pf_real hz_in(hz_src *s, pf_real lo, pf_real hi)
{
    unsigned w = hz_word(s);
    if ((w & 7u) == 0) return (w & 8u) ? hi : lo;
    return lo + (hi - lo) * (pf_real)((double)(w >> 4) / 268435455.0);
}

static int hz_bad;
static void hz_check(int ok, const char *what, pf_real got)
{
    if (ok) return;
    fprintf(stderr, "pf_fuzz: %s = %a\n", what, (double)got);
    hz_bad = 1;
}
#define HZ_FIN(x) ((x) - (x) == PF_R(0.0))
#define HZ_01(x, name) hz_check(HZ_FIN(x) && (x) >= PF_R(0.0) && (x) <= PF_R(1.0), name, x)

static void hz_mapped(hz_src *s)
{
    pf_real mu = hz_in(s, PF_R(-1.6), PF_R(1.6)), sd = hz_in(s, PF_R(0.0), PF_R(1.6));
    pf_real ms = hz_in(s, PF_R(-10.0), PF_R(10.0)), e = hz_in(s, PF_R(-1.6), PF_R(1.6));
    pf_real th = hz_in(s, PF_R(0.0), PF_R(1.57)), ph = hz_in(s, PF_R(0.0), PF_R(6.3));
    pf_real vl = hz_in(s, PF_R(0.0), PF_R(1.0)), vv = hz_in(s, PF_R(0.0), PF_R(1.0));
    pf_real c = hz_in(s, PF_R(-1.0), PF_R(1.0)), wd = hz_in(s, PF_R(0.0), PF_R(2.0)), x = hz_in(s, PF_R(-1.0), PF_R(1.0));
    pf_real mx = hz_in(s, PF_R(-2.0), PF_R(2.0)), my = hz_in(s, PF_R(-2.0), PF_R(2.0));
    int n = 1 + (int)(hz_word(s) % 32u), k = 1 + (int)(hz_word(s) % 8u), j;
    pf_hdf_moments m = pf_hdf_moments_make(mu, mu * mu + sd * sd, ms);
    pf_vec3 w = pf_vec3_make(PF_SIN(th) * PF_COS(ph), PF_SIN(th) * PF_SIN(ph), PF_COS(th));
    pf_real cf[8], r;
    pf_hdf_legendre L;
    pf_horizon_azimuth az = pf_horizon_azimuth_of(w, n);
    for (j = 0; j < 8; ++j) cf[j] = j < k ? pf_horizon_legendre_coeff(j, hz_in(s, PF_R(-1.0), PF_R(1.0))) : PF_R(0.0);
    L = pf_hdf_legendre_make(cf[0], cf[1], cf[2], cf[3], cf[4], cf[5], cf[6], cf[7]);
    hz_check(pf_hdf_legendre_coeff(L, 9) == PF_R(0.0) && pf_hdf_legendre_coeff(L, 0) == cf[0], "coeff getter", cf[0]);
    hz_check(az.i0 >= 0 && az.i0 < n && az.i1 >= 0 && az.i1 < n && az.f >= PF_R(0.0) && az.f <= PF_R(1.0), "azimuth f", az.f);
    r = pf_horizon_elevation(w);
    hz_check(HZ_FIN(r) && r >= -PF_R(1.5708) && r <= PF_R(1.5708), "elevation", r);
    r = pf_horizon_visibility_ramp(m, e);
    HZ_01(r, "ramp");
    r = pf_horizon_visibility_gauss(m, e);
    HZ_01(r, "gauss");
    r = pf_horizon_visibility_legendre(L, k, x);
    HZ_01(r, "legendre");
    r = pf_horizon_visibility_legendre(pf_hdf_legendre_lerp(L, L, c), k, x);
    HZ_01(r, "legendre lerp");
    r = pf_horizon_legendre_basis(k, x);
    hz_check(HZ_FIN(r) && PF_FABS(r) <= PF_SQRT(PF_R(k) + PF_R(0.5)) * PF_R(1.0001), "basis", r);
    r = pf_horizon_legendre_coeff(k, x);
    hz_check(HZ_FIN(r) && PF_FABS(r) <= PF_R(2.0), "coeff", r);
    r = pf_horizon_bidir_product(vl, vv);
    HZ_01(r, "product");
    r = pf_horizon_bidir_tan(vl, vv, c);
    HZ_01(r, "tan");
    r = pf_horizon_bidir_ashikhmin(vl, vv, c, wd);
    HZ_01(r, "ashikhmin");
    if (vv > PF_R(1e-3)) {
        r = pf_horizon_bidir_tan(vv, vv, PF_R(1.0));
        hz_check(PF_FABS(r - PF_R(1.0)) <= PF_R(1e-5), "tan hotspot", r);
        r = pf_horizon_bidir_ashikhmin(PF_R(1.0), vv, c, wd);
        hz_check(PF_FABS(r - PF_R(1.0)) <= PF_R(1e-5), "ashikhmin fully lit", r);
        r = pf_horizon_bidir_tan(PF_R(1.0), vv, c);
        hz_check(PF_FABS(r - PF_R(1.0)) <= PF_R(1e-5), "tan fully lit", r);
    }
    r = pf_horizon_visible_area(w, pf_hdf_moments_lerp(m, m, vl), mx, my);
    hz_check(HZ_FIN(r) && r >= PF_R(0.0) && r <= PF_R(2.0), "visible area", r);
    r = pf_horizon_masking(w, m, pf_slope_stats_make(mx, my, sd, vv, PF_R(0.0)));
    HZ_01(r, "masking");
    {
        /* the lod fade: lod in [-4, 12], bounds around the measured 2 and 6 (in either order) */
        pf_real lod = hz_in(s, PF_R(-4.0), PF_R(12.0)), lo = hz_in(s, PF_R(0.0), PF_R(4.0)), hi = hz_in(s, PF_R(2.0), PF_R(8.0));
        pf_real k = pf_horizon_lod_weight(lod, lo, hi);
        HZ_01(k, "lod weight");
        hz_check(!(lod <= lo && lod < hi) || k == PF_R(1.0), "lod weight below lod_full", k);
        hz_check(!(lod >= hi) || k == PF_R(0.0), "lod weight above lod_smith", k);
        r = pf_horizon_masking_lod(w, m, pf_slope_stats_make(mx, my, sd, vv, PF_R(0.0)), lod, lo, hi);
        HZ_01(r, "masking lod");
        if (k == PF_R(1.0)) hz_check(r == pf_horizon_masking(w, m, pf_slope_stats_make(mx, my, sd, vv, PF_R(0.0))), "masking lod at 1", r);
        /* the diffuse: a view from the inputs, the light w, the same HDF both ways */
        {
            pf_slope_stats st = pf_slope_stats_make(mx, my, sd * sd, vv, PF_R(0.0));
            pf_vec3 wv = pf_vec3_make(PF_SIN(e) * PF_COS(c), PF_SIN(e) * PF_SIN(c), PF_COS(e));
            pf_gg_grid g = pf_gg_grid_make(wv, st, PF_GG_MATCHED, k > PF_R(0.5) ? 3 : 5);
            r = pf_horizon_visibility_given_slope(w, m, st, mx, my);
            HZ_01(r, "visibility given slope");
            r = pf_horizon_diffuse_directional(g, w, m, m);
            hz_check(HZ_FIN(r) && r >= PF_R(0.0) && r <= PF_R(0.6367), "horizon diffuse", r);
            r = pf_horizon_diffuse_lod(g, w, m, m, lod, lo, hi);
            hz_check(HZ_FIN(r) && r >= PF_R(0.0) && r <= PF_R(1.0), "horizon diffuse lod", r);
        }
    }
}

/* pf_horizon_masking's skewness g = sigma_T/E[T] (1 - rho^2) at its degenerate inputs */
static void hz_skew(hz_src *s)
{
    unsigned sel = hz_word(s);
    pf_real mu = (sel & 1u) ? hz_in(s, PF_R(-1e-6), PF_R(1e-6)) : hz_in(s, PF_R(-0.5), PF_R(1.5));
    pf_real sd = (sel & 2u) ? hz_in(s, PF_R(0.0), PF_R(1e-5)) : hz_in(s, PF_R(0.0), PF_R(1.0));
    pf_real rho = hz_in(s, PF_R(-1.2), PF_R(1.2)), vx = hz_in(s, PF_R(0.0), PF_R(4.0)), vy = hz_in(s, PF_R(0.0), PF_R(4.0));
    pf_real cxy = hz_in(s, PF_R(-1.0), PF_R(1.0)) * PF_SQRT(vx * vy), mx = hz_in(s, PF_R(-1.0), PF_R(1.0)), my = hz_in(s, PF_R(-1.0), PF_R(1.0));
    pf_real th = hz_in(s, PF_R(0.0), PF_R(1.57)), ph = hz_in(s, PF_R(0.0), PF_R(6.3)), th2 = hz_in(s, PF_R(0.0), PF_R(1.57));
    pf_real cp = PF_COS(ph), sp = PF_SIN(ph), vs = pf_max(vx * cp * cp + vy * sp * sp + PF_R(2.0) * cxy * cp * sp, PF_R(0.0));
    pf_real ms = rho * PF_SQRT(vs) * sd + mu * (mx * cp + my * sp), r, r1, r2;
    pf_vec3 w = pf_vec3_make(PF_SIN(th) * cp, PF_SIN(th) * sp, PF_COS(th));
    pf_slope_stats st = pf_slope_stats_make(mx, my, vx, vy, cxy);
    pf_hdf_moments m = pf_hdf_moments_make(mu, mu * mu + sd * sd, ms);
    r = pf_horizon_masking(w, m, st);
    HZ_01(r, "skew masking");
    r = pf_horizon_masking_lod(w, m, st, PF_R(3.0), PF_R(2.0), PF_R(6.0));
    HZ_01(r, "skew masking lod");
    /* no covariance, zero mean slope: masking / Smith's G1 is the clamped CDF at the elevation */
    if (sd > PF_R(1e-3) && PF_FABS(th - th2) > PF_R(1e-3)) {
        pf_slope_stats s0 = pf_slope_stats_make(PF_R(0.0), PF_R(0.0), vx, vy, cxy);
        pf_hdf_moments m0 = pf_hdf_moments_make(mu, mu * mu + sd * sd, PF_R(0.0));
        pf_vec3 w2 = pf_vec3_make(PF_SIN(th2) * cp, PF_SIN(th2) * sp, PF_COS(th2));
        pf_real g1 = pf_beckmann_g1(w, s0), g2 = pf_beckmann_g1(w2, s0);
        if (g1 > PF_R(0.01) && g2 > PF_R(0.01)) {
            r1 = pf_horizon_masking(w, m0, s0) / g1;
            r2 = pf_horizon_masking(w2, m0, s0) / g2;
            /* th < th2: w is the higher elevation; the ratio saturates at 1 with G1 */
            if (pf_max(r1, r2) < PF_R(0.999))
                hz_check(th < th2 ? r1 >= r2 - PF_R(1e-4) : r2 >= r1 - PF_R(1e-4), "skew CDF monotone", r1 - r2);
        }
    }
}

static volatile pf_real hz_sink;
static void hz_rawcalls(hz_src *s)
{
    pf_hdf_moments m = pf_hdf_moments_make(hz_raw(s), hz_raw(s), hz_raw(s));
    pf_vec3 w = pf_vec3_make(hz_raw(s), hz_raw(s), hz_raw(s));
    int n = (int)(hz_word(s) % 64u) - 8, k = (int)(hz_word(s) % 16u) - 4;
    pf_real a = hz_raw(s), b = hz_raw(s), c = hz_raw(s);
    pf_hdf_legendre L = pf_hdf_legendre_make(hz_raw(s), hz_raw(s), hz_raw(s), hz_raw(s), hz_raw(s), hz_raw(s), hz_raw(s), hz_raw(s));
    hz_sink = pf_hdf_legendre_coeff(L, k);
    hz_sink = (pf_real)pf_horizon_azimuth_of(w, n).i0 + pf_horizon_azimuth_of(w, n).f;
    hz_sink = pf_horizon_elevation(w);
    hz_sink = pf_horizon_visibility_ramp(m, a) + pf_horizon_visibility_gauss(m, a);
    hz_sink = pf_horizon_visibility_legendre(L, k, a) + pf_horizon_visibility_legendre(pf_hdf_legendre_lerp(L, L, b), k, a);
    hz_sink = pf_horizon_legendre_basis(k, a) + pf_horizon_legendre_coeff(k, a);
    hz_sink = pf_horizon_bidir_product(a, b) + pf_horizon_bidir_tan(a, b, c) + pf_horizon_bidir_ashikhmin(a, b, c, hz_raw(s));
    hz_sink = pf_horizon_visible_area(w, pf_hdf_moments_lerp(m, m, c), a, b);
    hz_sink = pf_horizon_masking(w, m, pf_slope_stats_make(a, b, c, hz_raw(s), hz_raw(s)));
    hz_sink = pf_horizon_lod_weight(a, b, c);
    hz_sink = pf_horizon_masking_lod(w, m, pf_slope_stats_make(a, b, c, hz_raw(s), hz_raw(s)), hz_raw(s), hz_raw(s), hz_raw(s));
    hz_sink = pf_horizon_visibility_given_slope(w, m, pf_slope_stats_make(a, b, c, hz_raw(s), hz_raw(s)), hz_raw(s), hz_raw(s));
    {
        pf_gg_grid g = pf_gg_grid_make(w, pf_slope_stats_make(a, b, c, hz_raw(s), hz_raw(s)), n & 3, k);
        pf_vec3 wi = pf_vec3_make(hz_raw(s), hz_raw(s), hz_raw(s));
        hz_sink = pf_horizon_diffuse_directional(g, wi, m, m);
        hz_sink = pf_horizon_diffuse_lod(g, wi, m, m, a, b, c);
    }
}

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);
int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    hz_src s;
    s.d = data;
    s.n = size;
    s.at = 0;
    s.rng = 0x9E3779B97F4A7C15ULL ^ (unsigned long long)size;
    hz_bad = 0;
    hz_mapped(&s);
    hz_skew(&s);
    if (hz_bad) __builtin_trap();
    s.at = 0;
    hz_rawcalls(&s);
    return 0;
}

/* test_encode.c - tests of include/pf_encode.h: round trips with measured error bounds
   (half, scaled UNORM 16/8, slope moments about a reference, vMF lobes), linearity of every
   encoding under lerp (what a bilinear, trilinear or anisotropic sampler does to the stored
   texels), the per-texel reference that is not linear, decoders of every bit pattern finite,
   and the encoders' bad input (clear code, nothing written). Oracles: long double. */
#include <string.h>
#include "pf_encode.h"
#include "pf_test.h"

/* IEEE half rounding in long double (frexpl/ldexpl, ties to even by rintl in the default
   rounding mode): the oracle of pf_half_from_real, normal and subnormal ranges. */
static long double oracle_half(long double x)
{
    int e;
    long double m, a = fabsl(x);
    if (a < ldexpl(1.0L, -14)) return copysignl(rintl(ldexpl(a, 24)), x) * ldexpl(1.0L, -24);
    m = frexpl(a, &e); /* a = m 2^e, m in [0.5, 1): 11 significant bits */
    return copysignl(ldexpl(rintl(ldexpl(m, 11)), e - 11), x);
}

static long double urand(pf_test_rng *r, double lo, double hi) { return (long double)pf_test_uniform(r, lo, hi); }

/* ------------------------------------------------------------------ half */
static void test_half_every_pattern(void)
{
    long bad_finite = 0, bad_round = 0;
    unsigned h;
    for (h = 0; h < 65536u; ++h) {
        pf_real v = pf_real_from_half((unsigned short)h);
        int e = (int)((h >> 10) & 31u);
        if (!pf_test_finite(v)) ++bad_finite;
        if (e != 31 && h != 0x8000u && pf_half_from_real(v) != (unsigned short)h) ++bad_round;
    }
    PF_CHECK(bad_finite == 0, "%ld patterns decode to a non-finite value", bad_finite);
    PF_CHECK(bad_round == 0, "%ld finite patterns do not round-trip", bad_round);
}

static void test_half_rounding_oracle(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xe1u);
    long wrong = 0;
    int i;
    for (i = 0; i < 200000; ++i) {
        /* log-uniform magnitudes from 2^-26 to 65000, both signs */
        long double a = expl(urand(&rng, -18.0, 11.08)), x = (i & 1) ? -a : a;
        pf_real xr = (pf_real)x;
        long double want = oracle_half((long double)xr), got = (long double)pf_real_from_half(pf_half_from_real(xr));
        if (got != want && !(want == 0.0L && got == 0.0L)) ++wrong;
    }
    PF_CHECK(wrong == 0, "%ld of 200000 differ from the long double rounding", wrong);
    PF_CHECK(pf_half_from_real(PF_R(65519.0)) == 0x7bffu && pf_half_from_real(PF_R(65520.0)) == 0x7c00u,
             "overflow threshold");
}

/* ------------------------------------------------------------------ scaled UNORM */
/* decode of code q at 2^bits - 1 = L */
static pf_real dec(long q, long L, pf_real off, pf_real sc) { return pf_unorm_decode((pf_real)q / (pf_real)L, off, sc); }

static void test_unorm_round_trip(void)
{
    enum { N = 4096, C = 3 };
    static pf_real tex[N * C];
    static unsigned short q16[N * C];
    static unsigned char q8[N * C];
    pf_real off[C], sc[C];
    pf_test_rng rng = pf_test_rng_seed(0x31u);
    long double worst16 = 0, worst8 = 0;
    int i, c;
    for (i = 0; i < N; ++i) {
        tex[i * C] = (pf_real)urand(&rng, -1.5, 1.5);
        tex[i * C + 1] = (pf_real)urand(&rng, 0.0, 9.0);
        tex[i * C + 2] = (pf_real)urand(&rng, 1000.0, 1000.001); /* narrow, far from 0 */
    }
    PF_CHECK(pf_encode_ranges(tex, N, C, off, sc) == PF_OK, "ranges");
    PF_CHECK(pf_encode_channels(tex, N, C, off, sc, PF_ENCODE_UNORM16, q16) == PF_OK, "encode 16");
    PF_CHECK(pf_encode_channels(tex, N, C, off, sc, PF_ENCODE_UNORM8, q8) == PF_OK, "encode 8");
    for (i = 0; i < N; ++i)
        for (c = 0; c < C; ++c) {
            long double x = (long double)tex[i * C + c];
            /* quantization half a step, plus the rounding of (x - off)/sc and of off + sc s */
            long double slack = 4.0L * PF_TEST_EPS * (fabsl((long double)off[c]) + (long double)sc[c]);
            long double e16 = fabsl((long double)dec(q16[i * C + c], 65535L, off[c], sc[c]) - x);
            long double e8 = fabsl((long double)dec(q8[i * C + c], 255L, off[c], sc[c]) - x);
            long double b16 = (long double)sc[c] / (2.0L * 65535.0L), b8 = (long double)sc[c] / 510.0L;
            PF_CHECK(e16 <= b16 + slack, "16-bit channel %d: %Lg > %Lg", c, e16, b16 + slack);
            PF_CHECK(e8 <= b8 + slack, "8-bit channel %d: %Lg > %Lg", c, e8, b8 + slack);
            if (sc[c] > 0 && e16 / (long double)sc[c] > worst16) worst16 = e16 / (long double)sc[c];
            if (sc[c] > 0 && e8 / (long double)sc[c] > worst8) worst8 = e8 / (long double)sc[c];
        }
    pf_test_note("max error / range: 16-bit %.3Lg (half step %.3Lg), 8-bit %.3Lg (%.3Lg)", worst16,
                 1.0L / 131070.0L, worst8, 1.0L / 510.0L);
}

/* a constant channel (zero-width range) round-trips exactly */
static void test_unorm_constant_channel(void)
{
    pf_real tex[4] = { PF_R(0.25), PF_R(0.25), PF_R(0.25), PF_R(0.25) }, off = PF_R(0.0), sc = PF_R(-1.0);
    unsigned short q[4];
    int i, ok = 1;
    PF_CHECK(pf_encode_ranges(tex, 4, 1, &off, &sc) == PF_OK && sc == PF_R(0.0), "range");
    PF_CHECK(pf_encode_channels(tex, 4, 1, &off, &sc, PF_ENCODE_UNORM16, q) == PF_OK, "encode");
    for (i = 0; i < 4; ++i) ok &= q[i] == 0 && dec(q[i], 65535L, off, sc) == PF_R(0.25);
    PF_CHECK(ok, "constant channel not exact");
}

/* ------------------------------------------------------------------ slope moments */
/* n texels: each the moments of a Gaussian of mean (mu + jitter, mu/2 + jitter) and deviation
   sd per axis (correlation 0.3), as coarse mip texels of a tilted map are */
static void slope_texels(pf_real *t, int n, long double mu, long double sd, pf_test_rng *rng, long double *var_x)
{
    int i;
    for (i = 0; i < n; ++i) {
        long double mx = mu + sd * urand(rng, -0.5, 0.5), my = 0.5L * mu + sd * urand(rng, -0.5, 0.5);
        long double s = sd * urand(rng, 0.8, 1.2);
        t[5 * i] = (pf_real)mx;
        t[5 * i + 1] = (pf_real)my;
        t[5 * i + 2] = (pf_real)(mx * mx + s * s);
        t[5 * i + 3] = (pf_real)(my * my + s * s);
        t[5 * i + 4] = (pf_real)(mx * my + 0.3L * s * s);
        /* the variance the stored pf_reals hold (what float32 storage gives) */
        var_x[i] = (long double)t[5 * i + 2] - (long double)t[5 * i] * (long double)t[5 * i];
    }
}

static pf_slope_moments sampled(const unsigned short *q, int i, int half)
{
    if (half)
        return pf_slope_moments_make(pf_real_from_half(q[5 * i]), pf_real_from_half(q[5 * i + 1]),
                                     pf_real_from_half(q[5 * i + 2]), pf_real_from_half(q[5 * i + 3]),
                                     pf_real_from_half(q[5 * i + 4]));
    return pf_slope_moments_make((pf_real)q[5 * i] / PF_R(65535.0), (pf_real)q[5 * i + 1] / PF_R(65535.0),
                                 (pf_real)q[5 * i + 2] / PF_R(65535.0), (pf_real)q[5 * i + 3] / PF_R(65535.0),
                                 (pf_real)q[5 * i + 4] / PF_R(65535.0));
}

static pf_slope_encoding identity_of(pf_slope_encoding e)
{
    e.off_x = e.off_y = e.off_xx = e.off_yy = e.off_xy = PF_R(0.0);
    e.sc_x = e.sc_y = e.sc_xx = e.sc_yy = e.sc_xy = PF_R(1.0);
    return e;
}

/* The variance after the round trip, against the variance the float texels hold, for the
   cases of test_half_storage_variance (tests/test_moments.c): raw half moments cancel it,
   the 16-bit UNORM moments about the map's mean slope keep it within the bound of their
   quantization: |dvar| <= e_xx + 2 |dx| e_x + e_x^2 (e = half a step of the channel) plus
   the float rounding of (1) and of var = E[x^2] - E[x]^2 (4 eps (E[x^2] + E[x]^2)). */
static void test_slope_round_trip_variance(void)
{
    enum { N = 1024 };
    static pf_real t[5 * N];
    static unsigned short q[5 * N];
    static long double var[N];
    static const long double mus[] = { 0.0L, 0.5L, 1.0L }, sds[] = { 0.01L, 0.03L, 0.1L };
    pf_test_rng rng = pf_test_rng_seed(0x5109u);
    int a, b, i, fmt;
    for (a = 0; a < 3; ++a)
        for (b = 0; b < 3; ++b) {
            long double worst[3] = { 0, 0, 0 }; /* raw half, centred half, centred unorm16 */
            slope_texels(t, N, mus[a], sds[b], &rng, var);
            for (fmt = 0; fmt < 3; ++fmt) {
                pf_slope_encoding e;
                int half = fmt < 2;
                memset(&e, 0, sizeof e);
                PF_CHECK(pf_slope_encoding_find(t, N, fmt > 0, &e) == PF_OK, "find");
                PF_CHECK(pf_slope_moments_encode(t, N, &e, half ? PF_ENCODE_HALF : PF_ENCODE_UNORM16, q) == PF_OK, "encode");
                for (i = 0; i < N; ++i) {
                    pf_slope_moments m = pf_slope_moments_decode(sampled(q, i, half), half ? identity_of(e) : e);
                    long double v = (long double)m.exx - (long double)m.ex * (long double)m.ex;
                    long double err = fabsl(v - var[i]) / var[i];
                    if (err > worst[fmt]) worst[fmt] = err;
                    if (fmt == 2) {
                        long double ex = (long double)e.sc_x / 131070.0L, exx = (long double)e.sc_xx / 131070.0L;
                        long double dx = fabsl((long double)t[5 * i] - (long double)e.ref_x);
                        long double bound = exx + 2.0L * dx * ex + ex * ex +
                                            8.0L * PF_TEST_EPS * ((long double)t[5 * i + 2] + (long double)e.ref_x * (long double)e.ref_x);
                        PF_CHECK(fabsl(v - var[i]) <= bound, "mu %Lg sd %Lg texel %d: %Lg > %Lg", mus[a], sds[b], i,
                                 fabsl(v - var[i]), bound);
                    }
                }
            }
            pf_test_note("mu %.1Lf sd %.2Lf: raw half %.2Lg, centred half %.2Lg, unorm16 %.2Lg", mus[a], sds[b],
                         worst[0], worst[1], worst[2]);
            /* the formulation that does not cancel: within 2% of the variance in every case
               (float32 storage itself loses eps mu^2 / var = 1.2% at mu 1, sd 0.01) */
            PF_CHECK(worst[2] <= 0.02L, "unorm16 about the mean: %Lg of the variance", worst[2]);
        }
}

/* Linearity: decode(lerp(sa, sb, t)) == lerp(decode sa, decode sb, t) to rounding (the decode
   is affine for a fixed encoding), and decode(s) within the round-trip bound of the moments,
   so a filter of the stored texels is a filter of the moments up to quantization. */
static void test_linearity_slope(void)
{
    enum { N = 256 };
    static pf_real t[5 * N];
    static unsigned short q[5 * N];
    static long double var[N];
    pf_test_rng rng = pf_test_rng_seed(0x11e5u);
    long double worst[2] = { 0, 0 };
    int fmt, i, k;
    slope_texels(t, N, 0.7L, 0.05L, &rng, var);
    for (fmt = 0; fmt < 2; ++fmt) { /* centred unorm16, centred half */
        pf_slope_encoding e;
        int half = fmt == 1;
        memset(&e, 0, sizeof e);
        PF_CHECK(pf_slope_encoding_find(t, N, 1, &e) == PF_OK, "find");
        PF_CHECK(pf_slope_moments_encode(t, N, &e, half ? PF_ENCODE_HALF : PF_ENCODE_UNORM16, q) == PF_OK, "encode");
        if (half) e = identity_of(e);
        for (i = 0; i + 1 < N; ++i)
            for (k = 1; k < 8; ++k) {
                pf_real w = (pf_real)k / PF_R(8.0);
                pf_slope_moments sa = sampled(q, i, half), sb = sampled(q, i + 1, half);
                pf_slope_moments s = pf_slope_moments_add(pf_slope_moments_scale(sa, PF_R(1.0) - w), pf_slope_moments_scale(sb, w));
                pf_slope_moments d = pf_slope_moments_decode(s, e);
                pf_slope_moments da = pf_slope_moments_decode(sa, e), db = pf_slope_moments_decode(sb, e);
                long double lw = (long double)w;
                long double want[5], got[5], rt[5], scale = 1.0L + fabsl((long double)e.ref_x) + fabsl((long double)e.ref_y);
                int c;
                want[0] = (1 - lw) * (long double)da.ex + lw * (long double)db.ex;
                want[1] = (1 - lw) * (long double)da.ey + lw * (long double)db.ey;
                want[2] = (1 - lw) * (long double)da.exx + lw * (long double)db.exx;
                want[3] = (1 - lw) * (long double)da.eyy + lw * (long double)db.eyy;
                want[4] = (1 - lw) * (long double)da.exy + lw * (long double)db.exy;
                got[0] = (long double)d.ex; got[1] = (long double)d.ey; got[2] = (long double)d.exx; got[3] = (long double)d.eyy; got[4] = (long double)d.exy;
                for (c = 0; c < 5; ++c) { /* the lerp of the true moments */
                    rt[c] = (1 - lw) * (long double)t[5 * i + c] + lw * (long double)t[5 * (i + 1) + c];
                    if (fabsl(got[c] - want[c]) > worst[fmt]) worst[fmt] = fabsl(got[c] - want[c]);
                }
                /* affine: to 16 eps of the moments' scale */
                for (c = 0; c < 5; ++c)
                    PF_CHECK(fabsl(got[c] - want[c]) <= 16.0L * PF_TEST_EPS * scale * scale, "fmt %d ch %d: %Lg", fmt, c,
                             fabsl(got[c] - want[c]));
                /* and the lerp of the true moments up to quantization (half: 2^-11 relative
                   of the centred channel, times (1)'s reference factor) */
                for (c = 0; c < 5; ++c) {
                    long double qb = half ? 3.0L * ldexpl(1.0L, -11) * scale * scale * 0.5L
                                          : 3.0L * scale * scale * 0.5L / 65535.0L;
                    PF_CHECK(fabsl(got[c] - rt[c]) <= qb, "fmt %d ch %d: lerp of true %Lg", fmt, c, fabsl(got[c] - rt[c]));
                }
            }
    }
    pf_test_note("decode(lerp) - lerp(decode): unorm16 %.2Lg, half %.2Lg", worst[0], worst[1]);
}

/* A reference per texel (each texel's own mean, so that the stored channel is its variance) is
   not linear: two texels with means ra, rb and variances va, vb filtered with weight t store
   c = lerp(va, vb), r = lerp(ra, rb), d = 0, and (1) decodes E[x^2] = c + r^2 where the mixture
   has lerp(va + ra^2, vb + rb^2): short by t (1 - t) (ra - rb)^2, the variance of the means. */
static void test_slope_per_texel_reference_not_linear(void)
{
    pf_test_rng rng = pf_test_rng_seed(0x7e1u);
    long double worst_rel = 0.0L;
    int i;
    for (i = 0; i < 1000; ++i) {
        long double ra = urand(&rng, -1.0, 1.0), rb = urand(&rng, -1.0, 1.0);
        long double va = urand(&rng, 0.001, 0.05), vb = urand(&rng, 0.001, 0.05), t = urand(&rng, 0.0, 1.0);
        pf_slope_encoding e;
        pf_slope_moments s, d;
        long double truth, miss;
        memset(&e, 0, sizeof e);
        e.sc_x = e.sc_y = e.sc_xx = e.sc_yy = e.sc_xy = PF_R(1.0);
        e.ref_x = (pf_real)((1 - t) * ra + t * rb); /* the filtered reference */
        s = pf_slope_moments_make(PF_R(0.0), PF_R(0.0), (pf_real)((1 - t) * va + t * vb), PF_R(0.0), PF_R(0.0));
        d = pf_slope_moments_decode(s, e);
        truth = (1 - t) * (va + ra * ra) + t * (vb + rb * rb);
        miss = truth - (long double)d.exx;
        PF_CHECK(fabsl(miss - t * (1 - t) * (ra - rb) * (ra - rb)) <= 8.0L * PF_TEST_EPS * (truth + 1.0L),
                 "miss %Lg, predicted %Lg", miss, t * (1 - t) * (ra - rb) * (ra - rb));
        if (miss / truth > worst_rel) worst_rel = miss / truth;
    }
    PF_CHECK(worst_rel > 0.1L, "the per-texel reference should lose the variance of the means: %Lg", worst_rel);
    pf_test_note("worst loss %.2Lg of E[x^2]", worst_rel);
}

/* ------------------------------------------------------------------ vMF lobes */
static void test_vmf_round_trip(void)
{
    enum { N = 4096 };
    static pf_real t[4 * N];
    static unsigned short q16[4 * N];
    static unsigned char q8[4 * N];
    pf_test_rng rng = pf_test_rng_seed(0x0f1u);
    pf_vmf_encoding e;
    long double worst_ang[2] = { 0, 0 }, worst_k[2] = { 0, 0 }, worst_a[2] = { 0, 0 };
    int i, b;
    memset(&e, 0, sizeof e);
    for (i = 0; i < N; ++i) {
        long double th = acosl(urand(&rng, 0.0, 1.0)), ph = urand(&rng, 0.0, 2.0 * 3.14159265358979);
        if (i < 8) th = 1.5707963L * (long double)i / 7.0L; /* the pole to the horizon */
        t[4 * i] = (pf_real)(sinl(th) * cosl(ph));
        t[4 * i + 1] = (pf_real)(sinl(th) * sinl(ph));
        t[4 * i + 2] = (pf_real)expl(urand(&rng, log(0.01), log(1e4)));
        t[4 * i + 3] = (pf_real)urand(&rng, 0.0, 1.0);
    }
    PF_CHECK(pf_vmf_encoding_find(t, N, &e) == PF_OK, "find");
    PF_CHECK(pf_vmf_lobes_encode(t, N, &e, PF_ENCODE_UNORM16, q16) == PF_OK, "encode 16");
    PF_CHECK(pf_vmf_lobes_encode(t, N, &e, PF_ENCODE_UNORM8, q8) == PF_OK, "encode 8");
    for (b = 0; b < 2; ++b) {
        const long double L = b ? 255.0L : 65535.0L;
        for (i = 0; i < N; ++i) {
            pf_real s[4];
            pf_vmf_lobe in = pf_vmf_lobe_make(t[4 * i + 3], t[4 * i], t[4 * i + 1], t[4 * i + 2]), out;
            long double dx, dy, dz, ang;
            int c;
            for (c = 0; c < 4; ++c) s[c] = (pf_real)((b ? (long double)q8[4 * i + c] : (long double)q16[4 * i + c]) / L);
            out = pf_vmf_lobe_decode(s[0], s[1], s[2], s[3], e);
            dx = (long double)in.mu.x - (long double)out.mu.x;
            dy = (long double)in.mu.y - (long double)out.mu.y;
            dz = (long double)in.mu.z - (long double)out.mu.z;
            ang = 2.0L * asinl(fminl(0.5L * sqrtl(dx * dx + dy * dy + dz * dz), 1.0L)); /* angle between unit vectors */
            if (ang > worst_ang[b]) worst_ang[b] = ang;
            if (fabsl(logl((long double)out.kappa / (long double)in.kappa)) > worst_k[b]) worst_k[b] = fabsl(logl((long double)out.kappa / (long double)in.kappa));
            if (fabsl((long double)out.amp - (long double)in.amp) > worst_a[b]) worst_a[b] = fabsl((long double)out.amp - (long double)in.amp);
        }
        /* bounds: half a step (1/L) in u and v moves the axis by at most ~2/L radians
           (measured 2.36/L at 16 bits, 2.26/L at 8), plus the float rounding of mu.z =
           sqrt(1 - x^2 - y^2) near the horizon (1.5e-4 rad measured); log kappa half a step of its span;
           amplitude half a step of its scale (plus float rounding) */
        PF_CHECK(worst_ang[b] <= 2.5L / L + 2e3L * PF_TEST_EPS, "%d bits: angle %Lg", b ? 8 : 16, worst_ang[b]);
        PF_CHECK(worst_k[b] <= (long double)e.log_kappa_span / (2 * L) + 64.0L * PF_TEST_EPS, "%d bits: log kappa %Lg",
                 b ? 8 : 16, worst_k[b]);
        PF_CHECK(worst_a[b] <= (long double)e.amp_scale / (2 * L) + 4.0L * PF_TEST_EPS, "%d bits: amp %Lg", b ? 8 : 16,
                 worst_a[b]);
        pf_test_note("%d bits: axis %.2Lg rad, log kappa %.2Lg, amp %.2Lg", b ? 8 : 16, worst_ang[b], worst_k[b], worst_a[b]);
    }
}

/* The octahedral and log channels are not linear (decode of the mid-point code is not the
   mid-point): measured; the amplitude channel is. */
static void test_vmf_linearity(void)
{
    pf_vmf_encoding e;
    pf_vmf_lobe a, b, m;
    long double dev_k;
    e.log_kappa_lo = PF_LOG(PF_R(1.0));
    e.log_kappa_span = PF_LOG(PF_R(1000.0));
    e.amp_scale = PF_R(1.0);
    a = pf_vmf_lobe_decode(PF_R(0.2), PF_R(0.5), PF_R(0.0), PF_R(0.2), e);
    b = pf_vmf_lobe_decode(PF_R(0.8), PF_R(0.5), PF_R(1.0), PF_R(0.6), e);
    m = pf_vmf_lobe_decode(PF_R(0.5), PF_R(0.5), PF_R(0.5), PF_R(0.4), e);
    dev_k = fabsl((long double)m.kappa - 0.5L * ((long double)a.kappa + (long double)b.kappa)) / (0.5L * ((long double)a.kappa + (long double)b.kappa));
    PF_CHECK(fabsl((long double)m.amp - 0.5L * ((long double)a.amp + (long double)b.amp)) <= 4.0L * PF_TEST_EPS, "amp not linear");
    PF_CHECK(dev_k > 0.5L, "log kappa: mid-point code gives the geometric mean, %Lg", dev_k);
    pf_test_note("kappa of the mid-point code off the mean by %.2Lg", dev_k);
}

/* ------------------------------------------------------------------ decoders: any input */
static void test_decoders_finite(void)
{
    pf_slope_encoding e;
    pf_vmf_encoding v;
    long bad = 0;
    unsigned h;
    static const pf_real odd[] = { PF_R(0.0), PF_R(1.0), PF_R(-1.0), PF_R(2.0), PF_R(1e30), PF_R(-1e30) };
    int i, j;
    memset(&e, 0, sizeof e);
    e.ref_x = PF_R(-3.0);
    e.ref_y = PF_R(2.0);
    e.off_xx = PF_R(-5.0);
    e.sc_x = e.sc_y = e.sc_xx = e.sc_yy = e.sc_xy = PF_R(1.0);
    v.log_kappa_lo = PF_LOG(PF_VMF_KAPPA_MIN);
    v.log_kappa_span = PF_LOG(PF_VMF_KAPPA_MAX) - v.log_kappa_lo;
    v.amp_scale = PF_R(1.0);
    for (h = 0; h < 65536u; ++h) { /* every 16-bit code as UNORM, every half pattern as stored value */
        pf_real s = (pf_real)h / PF_R(65535.0), x = pf_real_from_half((unsigned short)h);
        pf_slope_moments m = pf_slope_moments_decode(pf_slope_moments_make(s, s, s, s, s), e);
        pf_slope_moments mh = pf_slope_moments_decode(pf_slope_moments_make(x, x, x, x, x), identity_of(e));
        pf_vmf_lobe l = pf_vmf_lobe_decode(s, PF_R(1.0) - s, s, s, v);
        if (!pf_test_finite(m.ex) || !pf_test_finite(m.exx) || !pf_test_finite(m.exy) || !pf_test_finite(mh.exx) ||
            !pf_test_finite(mh.exy) || !pf_test_finite(l.kappa) || !pf_test_finite(l.mu.z) || !pf_test_finite(l.amp))
            ++bad;
    }
    for (i = 0; i < 6; ++i) /* out-of-range and huge sampled values (not a sampler's) for vMF */
        for (j = 0; j < 6; ++j) {
            pf_vmf_lobe l = pf_vmf_lobe_decode(odd[i], odd[j], odd[i], odd[j], v);
            pf_vec3 d = pf_oct_hemi_decode(odd[i], odd[j]);
            if (!pf_test_finite(l.kappa) || !pf_test_finite(l.mu.x) || !pf_test_finite(d.z) ||
                pf_vec3_length(d) > PF_R(1.0001))
                ++bad;
        }
    PF_CHECK(bad == 0, "%ld decodes not finite", bad);
}

/* NaN and inf: decoders stay finite (vMF through the clamps); not an edge_ test: -ffast-math
   assumes no NaN */
static void test_decoders_nan(void)
{
    pf_vmf_encoding v;
    pf_vmf_lobe l;
    pf_vec3 d;
    pf_real nan = (pf_real)NAN, inf = (pf_real)INFINITY;
    v.log_kappa_lo = PF_R(0.0);
    v.log_kappa_span = PF_R(5.0);
    v.amp_scale = PF_R(1.0);
    l = pf_vmf_lobe_decode(nan, inf, -inf, nan, v);
    d = pf_oct_hemi_decode(nan, nan);
    PF_CHECK(pf_test_bits_finite(l.kappa) && pf_test_bits_finite(l.mu.x) && pf_test_bits_finite(l.mu.z) &&
                 pf_test_bits_finite(l.amp) && pf_test_bits_finite(d.x) && pf_test_bits_finite(d.z),
             "NaN/inf sampled values");
}

/* ------------------------------------------------------------------ bad input */
static void edge_bad_input(void)
{
    pf_real good[10] = { PF_R(0.1), PF_R(0.2), PF_R(0.3), PF_R(0.4), PF_R(0.5),
                         PF_R(0.2), PF_R(0.1), PF_R(0.5), PF_R(0.3), PF_R(0.1) };
    pf_real bad[10], huge[2] = { PF_R(-0.75) * PF_REAL_MAX, PF_R(0.75) * PF_REAL_MAX }, big[2] = { PF_R(1.0), PF_R(7e4) };
    pf_real off[5], sc[5], neg = PF_R(-1.0), one = PF_R(1.0), zero = PF_R(0.0);
    unsigned short out[10];
    unsigned char out8[10];
    pf_slope_encoding e, e0;
    pf_vmf_encoding v;
    int i, untouched = 1;
    memcpy(bad, good, sizeof bad);
    bad[7] = (pf_real)NAN;
    memset(out, 0xAB, sizeof out);
    memset(out8, 0xAB, sizeof out8);
    memset(&e0, 0x5A, sizeof e0);
    e = e0;
    PF_CHECK(pf_encode_ranges(NULL, 2, 5, off, sc) == PF_ERR_ARG, "NULL");
    PF_CHECK(pf_encode_ranges(good, 0, 5, off, sc) == PF_ERR_ARG, "empty");
    PF_CHECK(pf_encode_ranges(good, 2, 0, off, sc) == PF_ERR_ARG, "no channel");
    PF_CHECK(pf_encode_ranges(bad, 2, 5, off, sc) == PF_ERR_ARG, "NaN");
    PF_CHECK(pf_encode_ranges(huge, 2, 1, off, sc) == PF_ERR_ARG, "width overflows");
    PF_CHECK(pf_encode_ranges(good, 1LL << 62, 5, off, sc) == PF_ERR_SIZE, "huge n");
    PF_CHECK(pf_encode_channels(bad, 2, 5, off, sc, PF_ENCODE_HALF, out) == PF_ERR_ARG, "NaN half");
    PF_CHECK(pf_encode_channels(big, 2, 1, NULL, NULL, PF_ENCODE_HALF, out) == PF_ERR_ARG, "half overflow");
    PF_CHECK(pf_encode_channels(good, 2, 1, &zero, &neg, PF_ENCODE_UNORM16, out) == PF_ERR_ARG, "negative scale");
    PF_CHECK(pf_encode_channels(good, 2, 1, &one, NULL, PF_ENCODE_UNORM8, out8) == PF_ERR_ARG, "NULL scale");
    PF_CHECK(pf_encode_channels(good, 2, 1, &zero, &one, 7, out) == PF_ERR_ARG, "unknown format");
    bad[7] = (pf_real)INFINITY;
    PF_CHECK(pf_encode_channels(bad, 2, 5, off, sc, PF_ENCODE_UNORM16, out) == PF_ERR_ARG, "inf");
    PF_CHECK(pf_slope_encoding_find(bad, 2, 1, &e) == PF_ERR_ARG, "slope inf");
    PF_CHECK(pf_slope_encoding_find(good, 0, 1, &e) == PF_ERR_ARG, "slope empty");
    PF_CHECK(memcmp(&e, &e0, sizeof e) == 0, "encoding written on an error");
    PF_CHECK(pf_slope_encoding_find(good, 2, 1, &e) == PF_OK, "slope find");
    PF_CHECK(pf_slope_moments_encode(bad, 2, &e, PF_ENCODE_UNORM16, out) == PF_ERR_ARG, "slope encode inf");
    e.sc_xx = (pf_real)NAN;
    PF_CHECK(pf_slope_moments_encode(good, 2, &e, PF_ENCODE_UNORM16, out) == PF_ERR_ARG, "slope NaN scale");
    PF_CHECK(pf_vmf_encoding_find(bad, 2, &v) == PF_ERR_ARG, "vmf inf");
    PF_CHECK(pf_vmf_encoding_find(good, 2, &v) == PF_OK, "vmf find");
    PF_CHECK(pf_vmf_lobes_encode(good, 2, &v, PF_ENCODE_HALF, out) == PF_ERR_ARG, "vmf half");
    PF_CHECK(pf_vmf_lobes_encode(bad, 2, &v, PF_ENCODE_UNORM8, out8) == PF_ERR_ARG, "vmf inf encode");
    for (i = 0; i < 10; ++i) untouched &= out[i] == 0xABABu && out8[i] == 0xABu;
    PF_CHECK(untouched, "an encoder wrote on an error");
}

/* codes against a long double oracle, values outside the range clamped */
static void test_unorm_codes_oracle(void)
{
    pf_test_rng rng = pf_test_rng_seed(0xc0deu);
    pf_real off = PF_R(-0.75), sc = PF_R(2.5);
    long wrong = 0;
    int i;
    for (i = 0; i < 100000; ++i) {
        pf_real x = (pf_real)urand(&rng, -1.0, 2.0);
        unsigned short q = 0;
        long double tq = ((long double)x - (long double)off) / (long double)sc * 65535.0L, want;
        want = tq < 0 ? 0 : (tq > 65535.0L ? 65535.0L : rintl(tq));
        if (pf_encode_channels(&x, 1, 1, &off, &sc, PF_ENCODE_UNORM16, &q) != PF_OK ||
            fabsl((long double)q - want) > (fabsl(fabsl(tq - floorl(tq)) - 0.5L) < 65536.0L * 4.0L * PF_TEST_EPS ? 1.0L : 0.0L)) ++wrong;
    }
    PF_CHECK(wrong == 0, "%ld codes differ", wrong);
}

int main(int argc, char **argv)
{
    PF_TEST_BEGIN(argc, argv);
    PF_TEST_RUN(test_half_every_pattern);
    PF_TEST_RUN(test_half_rounding_oracle);
    PF_TEST_RUN(test_unorm_round_trip);
    PF_TEST_RUN(test_unorm_constant_channel);
    PF_TEST_RUN(test_unorm_codes_oracle);
    PF_TEST_RUN(test_slope_round_trip_variance);
    PF_TEST_RUN(test_linearity_slope);
    PF_TEST_RUN(test_slope_per_texel_reference_not_linear);
    PF_TEST_RUN(test_vmf_round_trip);
    PF_TEST_RUN(test_vmf_linearity);
    PF_TEST_RUN(test_decoders_finite);
    PF_TEST_RUN(test_decoders_nan);
    PF_TEST_RUN(edge_bad_input);
    return PF_TEST_END();
}

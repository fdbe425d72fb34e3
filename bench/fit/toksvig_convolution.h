/* toksvig_convolution.h - long double reference for pf_toksvig.h: a lobe (Blinn-Phong,
   Beckmann NDF or GGX NDF) convolved on the sphere with a Gaussian distribution of normals,
   by 2D adaptive quadrature (tests/reference/pf_oracle.h). Test and bench code only, never part of the
   library; shared by tests/test_toksvig.c and bench/bench_toksvig.c.

   The distribution of the normals n around the mean normal z is a Gaussian of the angle
   t = angle(n, z) with variance sigma^2 per axis, as a density over solid angle:
       p(n) = exp(-t^2 / (2 sigma^2)) / Z,   Z = 2 pi integral_0^pi exp(-t^2/(2 sigma^2)) sin t dt.
   The filtered lobe at a direction m at angle beta from z is (Bruneton & Neyret 2012 eq. 16)
       f_A(beta) = integral_{S^2} p(n) g(n . m) dn
   with g(c) = c^alpha (Blinn-Phong, c > 0), or an NDF (c > 0): Beckmann
   exp(-(1 - c^2)/(c^2 m^2)) / (pi m^2 c^4), GGX a^2 / (pi (c^2 (a^2 - 1) + 1)^2).
   The integral is taken in spherical coordinates around whichever of z and m carries the
   narrower function (the outer variable then starts at that peak), with breakpoints at a few
   widths of both functions and at the horizon kink c = 0. Everything in long double; the
   tolerance asked is 1e-10 relative, far below the errors measured with it (>= 1e-5). */
#ifndef TOKSVIG_CONVOLUTION_H
#define TOKSVIG_CONVOLUTION_H

#include "pf_oracle.h"

#define TKC_BLINN_PHONG 0
#define TKC_BECKMANN 1
#define TKC_GGX 2

typedef struct tkc_problem {
    int kind;           /* TKC_* */
    long double param;  /* alpha (Blinn-Phong exponent), m (Beckmann) or a (GGX) */
    long double sigma;  /* angular deviation per axis of the normals */
    long double beta;   /* angle between m and the mean normal */
    long double norm;   /* 1 / Z */
    int around_m;       /* 1: coordinates around m, 0: around z */
} tkc_problem;

static long double tkc_lobe(const tkc_problem *p, long double c)
{
    long double c2, q;
    if (!(c > 0.0L)) return 0.0L;
    if (c > 1.0L) c = 1.0L;
    switch (p->kind) {
    case TKC_BLINN_PHONG:
        return powl(c, p->param);
    case TKC_BECKMANN:
        c2 = c * c;
        return expl(-(1.0L - c2) / (c2 * p->param * p->param)) /
               (3.14159265358979323846264338327950288L * p->param * p->param * c2 * c2);
    default:
        c2 = c * c;
        q = c2 * (p->param * p->param - 1.0L) + 1.0L;
        return p->param * p->param / (3.14159265358979323846264338327950288L * q * q);
    }
}

/* Angular width of the lobe (the deviation of its small-angle Gaussian). */
static long double tkc_lobe_width(int kind, long double param)
{
    if (kind == TKC_BLINN_PHONG) return 1.0L / sqrtl(param > 1e-6L ? param : 1e-6L);
    if (kind == TKC_BECKMANN) return param / sqrtl(2.0L);
    return 0.5L * param;
}

static long double tkc_gauss_sin(long double t, void *ctx)
{
    long double s = *(const long double *)ctx;
    return expl(-t * t / (2.0L * s * s)) * sinl(t);
}

/* 1 / Z for the Gaussian of the angle. */
static long double tkc_norm(long double sigma)
{
    long double pts[3];
    pf_oracle_result r;
    long double hi = 12.0L * sigma < 3.14159265358979323846264338327950288L
                         ? 12.0L * sigma : 3.14159265358979323846264338327950288L;
    pts[0] = 0.5L * sigma;
    pts[1] = sigma;
    pts[2] = 3.0L * sigma;
    r = pf_oracle_integrate_points(tkc_gauss_sin, &sigma, 0.0L, hi, pts, 3, 0.0L, 1e-16L, 400);
    return 1.0L / (2.0L * 3.14159265358979323846264338327950288L * r.value);
}

static long double tkc_integrand(long double outer, long double az, void *ctx)
{
    const tkc_problem *p = (const tkc_problem *)ctx;
    long double sb = sinl(p->beta), cb = cosl(p->beta);
    long double so = sinl(outer), co = cosl(outer), ca = cosl(az), sa = sinl(az);
    long double t, c;
    if (!p->around_m) {
        /* n at (outer, az) around z; c = n . m with m = (sin b, 0, cos b) */
        t = outer;
        c = so * ca * sb + co * cb;
        return 2.0L * p->norm * expl(-t * t / (2.0L * p->sigma * p->sigma)) * tkc_lobe(p, c) * so;
    }
    /* n at (outer, az) around m: n = cos(o) m + sin(o) (cos(az) e1 + sin(az) e2),
       e1 = (cos b, 0, -sin b), e2 = (0, 1, 0) */
    {
        long double nx = co * sb + so * ca * cb, ny = so * sa, nz = co * cb - so * ca * sb;
        t = atan2l(sqrtl(nx * nx + ny * ny), nz);
        return 2.0L * p->norm * expl(-t * t / (2.0L * p->sigma * p->sigma)) * tkc_lobe(p, co) * so;
    }
}

/* Inner breakpoint: the azimuth where n . m = 0 (frame around z). */
static int tkc_ypoints(long double outer, long double *pts, int max_points, void *ctx)
{
    const tkc_problem *p = (const tkc_problem *)ctx;
    long double sb = sinl(p->beta), cb = cosl(p->beta), so = sinl(outer), co = cosl(outer);
    if (p->around_m || max_points < 1 || !(so * sb > 0.0L)) return 0;
    {
        long double x = -co * cb / (so * sb);
        if (x > -1.0L && x < 1.0L) {
            pts[0] = acosl(x);
            return 1;
        }
    }
    return 0;
}

/* f_A(beta) for a lobe of the given kind and parameter and normals of deviation sigma.
   sigma = 0 returns the lobe itself. *ok (if not NULL) is set to 0 if the quadrature did not
   converge. */
static long double tkc_filtered(int kind, long double param, long double sigma, long double beta,
                                int *ok)
{
    tkc_problem p;
    pf_oracle_2d pb;
    pf_oracle_result r;
    long double pts[8], wl = tkc_lobe_width(kind, param), hi;
    const long double pi = 3.14159265358979323846264338327950288L;
    int np = 0;
    if (ok) *ok = 1;
    p.kind = kind;
    p.param = param;
    p.sigma = sigma;
    p.beta = beta;
    if (!(sigma > 0.0L)) return tkc_lobe(&p, cosl(beta));
    p.norm = tkc_norm(sigma);
    p.around_m = sigma > wl;
    if (!p.around_m) {
        hi = 12.0L * sigma < pi ? 12.0L * sigma : pi;
        pts[np++] = 0.5L * sigma;
        pts[np++] = sigma;
        pts[np++] = 3.0L * sigma;
    } else {
        hi = 0.5L * pi;
        if (kind == TKC_BLINN_PHONG && 40.0L * wl < hi) hi = 40.0L * wl; /* cos^a < e^-800 */
        pts[np++] = 0.5L * wl;
        pts[np++] = wl;
        pts[np++] = 3.0L * wl;
        pts[np++] = 10.0L * wl;
    }
    {   /* keep only breakpoints inside (0, hi) */
        int i, k = 0;
        for (i = 0; i < np; ++i)
            if (pts[i] > 0.0L && pts[i] < hi) pts[k++] = pts[i];
        np = k;
    }
    pb = pf_oracle_2d_make(tkc_integrand, &p, 0.0L, hi, 0.0L, pi);
    pb.xpoints = pts;
    pb.nxpoints = np;
    pb.ypoints = tkc_ypoints;
    pb.epsrel = 1e-10L;
    pb.max_intervals = 200;
    r = pf_oracle_integrate_2d(&pb);
    if (ok && !(r.status == PF_ORACLE_OK || r.status == PF_ORACLE_ROUNDOFF)) *ok = 0;
    return r.value;
}

#endif /* TOKSVIG_CONVOLUTION_H */

/* bench/gpu/agree.c - the textbook baselines of bench/gpu/textbook.h compute what the library
   evaluators beside them compute, on ordinary inputs (so the GPU-cost ratios compare like with
   like). Run by bench/gpu/cost.sh, built with -DPF_DOUBLE: this checks the formulas, not float
   rounding (the library's float robustness is what the baselines lack by design).

   Inputs: seeded pseudo-random footprints of 2-6 depths in [0.05, 0.95] with random weights
   (shadow tests), unit half vectors and directions at most 70 degrees from the normal with
   slope statistics of deviation 0.1-0.55 (microfacets), nu in (0.02, 3) (Smith), x in [-3, 5]
   (erfc). Per pair: the largest difference (absolute for lit fractions, relative otherwise)
   against a stated bound; exit 1 when one is exceeded.
   Pairs where the two differ by design are compared where they agree: Walter's Lambda and G1
   away from nu in [1.54, 1.6) (the library clamps the published formula's Lambda < 0 there), EVSM
   with a minimum variance too small to bind (the library scales it at the warped value nearer
   0, the textbook at the receiver), and the specular with the LEAN lobe x Walter composition
   rebuilt from library parts (the library's own pf_leadr_specular uses the joint G2 and the
   projected area, LEADR eq. 17; the textbook uses G1(o) G1(i) and cos_o).

   usage: agree [N]   (N inputs per pair, default 20000) */
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include "pf_core.h"
#include "pf_moments.h"
#include "pf_shadow.h"
#include "pf_smith.h"
#include "pf_beckmann.h"
#include "textbook.h"

static unsigned long long rng_state = 0x9e3779b97f4a7c15ULL;
static double uniform(double lo, double hi)
{
    rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct {
    const char *textbook, *library;
    double bound, worst;
    int absolute, n;
} pair;

static void update(pair *p, double tb, double lib)
{
    double d = fabs(tb - lib);
    if (!p->absolute) d /= fmax(fabs(lib), 1e-300);
    if (!(d <= p->worst)) p->worst = d; /* NaN sticks */
    p->n++;
}

/* a footprint of k depths with weights: E[z^p], p = 1..4, for the textbook, and the library's
   own texel (pf_depth_moments4_from_depth, whatever basis it stores) filtered the same way */
static void footprint(double m[4], pf_depth_moments4 *lib)
{
    int k = 2 + (int)uniform(0.0, 5.0), i;
    double wsum = 0.0, z[6], w[6];
    m[0] = m[1] = m[2] = m[3] = 0.0;
    *lib = pf_depth_moments4_make(0.0, 0.0, 0.0, 0.0);
    for (i = 0; i < k; i++) {
        z[i] = uniform(0.05, 0.95);
        w[i] = uniform(0.1, 1.0);
        wsum += w[i];
    }
    for (i = 0; i < k; i++) {
        double wi = w[i] / wsum, zi = z[i];
        pf_depth_moments4 t = pf_depth_moments4_scale(pf_depth_moments4_from_depth(zi), wi);
        m[0] += wi * zi; m[1] += wi * zi * zi; m[2] += wi * zi * zi * zi; m[3] += wi * zi * zi * zi * zi;
        *lib = pf_depth_moments4_add(*lib, t);
    }
}

/* EVSM moments of the same kind of footprint: E[exp(c zs)], E[exp(2 c zs)], E[-exp(-c zs)],
   E[exp(-2 c zs)], zs = 2z - 1 */
static void evsm_footprint(double c_pos, double c_neg, double e[4])
{
    int k = 2 + (int)uniform(0.0, 5.0), i;
    double wsum = 0.0, zs, w, p, q;
    e[0] = e[1] = e[2] = e[3] = 0.0;
    for (i = 0; i < k; i++) {
        zs = 2.0 * uniform(0.05, 0.95) - 1.0;
        w = uniform(0.1, 1.0);
        wsum += w;
        p = exp(c_pos * zs); q = -exp(-c_neg * zs);
        e[0] += w * p; e[1] += w * p * p; e[2] += w * q; e[3] += w * q * q;
    }
    for (i = 0; i < 4; i++) e[i] /= wsum;
}

static pf_vec3 direction(double max_theta)
{
    double t = uniform(0.0, max_theta), ph = uniform(0.0, 6.283185307179586);
    return pf_vec3_make(sin(t) * cos(ph), sin(t) * sin(ph), cos(t));
}

static pf_slope_stats stats(int centered)
{
    double sx = uniform(0.1, 0.55), sy = uniform(0.1, 0.55), r = uniform(-0.6, 0.6);
    return pf_slope_stats_make(centered ? 0.0 : uniform(-0.3, 0.3), centered ? 0.0 : uniform(-0.3, 0.3),
                               sx * sx, sy * sy, r * sx * sy);
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 20000, i, j, fails = 0;
    pair p[] = {
        { "pf_textbook_vsm", "pf_shadow_vsm", 1e-12, 0.0, 1, 0 },
        { "pf_textbook_evsm2", "pf_shadow_evsm2", 1e-9, 0.0, 1, 0 },
        { "pf_textbook_evsm4", "pf_shadow_evsm4", 1e-9, 0.0, 1, 0 },
        { "pf_textbook_msm", "pf_shadow_msm", 1e-6, 0.0, 1, 0 },
        { "pf_textbook_lean_d", "pf_beckmann_d", 1e-12, 0.0, 0, 0 },
        { "pf_textbook_walter_g1", "pf_g1_beckmann_walter", 1e-14, 0.0, 0, 0 },
        { "pf_textbook_walter_lambda", "pf_lambda_beckmann_walter", 1e-14, 0.0, 0, 0 },
        { "pf_textbook_lean_walter_specular", "library D x Walter G1 G1 x Schlick / (4 cos_o)", 1e-12, 0.0, 0, 0 },
        { "pf_textbook_erfc_as", "pf_erfc", 1.5e-7, 0.0, 1, 0 },
    };
    const int np = (int)(sizeof p / sizeof p[0]);
    for (i = 0; i < n; i++) {
        double m[4], e[4], d = uniform(0.0, 1.0), bleed = (i & 1) ? 0.3 : 0.0;
        double cp = uniform(5.0, 40.0), cn = uniform(5.0, 40.0), nu, x;
        pf_vec3 h, wo, wi;
        pf_slope_stats s;
        pf_depth_moments4 m4;
        footprint(m, &m4);
        update(&p[0], pf_textbook_vsm(m[0], m[1], d, 1e-6, bleed),
               pf_shadow_vsm(pf_depth_moments2_make(m[0], m[1]), d, 1e-6, bleed));
        evsm_footprint(cp, cn, e);
        update(&p[1], pf_textbook_evsm2(e[0], e[1], d, cp, 1e-30, bleed),
               pf_shadow_evsm2(pf_depth_moments2_make(e[0], e[1]), d, cp, 1e-30, bleed));
        update(&p[2], pf_textbook_evsm4(e[0], e[1], e[2], e[3], d, cp, cn, 1e-30, bleed),
               pf_shadow_evsm4(pf_evsm_moments_make(e[0], e[1], e[2], e[3]), d, cp, cn, 1e-30, bleed));
        update(&p[3], pf_textbook_msm(m[0], m[1], m[2], m[3], d, 3e-5, 0.0),
               pf_shadow_msm(m4, d, 3e-5, 0.0));
        s = stats(0);
        h = direction(1.2);
        update(&p[4], pf_textbook_lean_d(h.x, h.y, h.z, s.mean_x, s.mean_y, s.var_x, s.var_y, s.cov_xy),
               pf_beckmann_d(h, s));
        nu = uniform(0.02, 3.0);
        if (nu < 1.54 || nu >= 1.6) {
            update(&p[5], pf_textbook_walter_g1(nu), pf_g1_beckmann_walter(nu));
            update(&p[6], pf_textbook_walter_lambda(nu), pf_lambda_beckmann_walter(nu));
        }
        wo = direction(1.2);
        wi = direction(1.2);
        {
            pf_vec3 hh = pf_vec3_normalize(pf_vec3_add(wo, wi));
            double f0 = uniform(0.02, 1.0);
            double lib = pf_beckmann_d(hh, s) * pf_g1_beckmann_walter(pf_smith_nu(wo, s)) *
                         pf_g1_beckmann_walter(pf_smith_nu(wi, s)) *
                         pf_fresnel_schlick(f0, pf_vec3_dot(hh, wi)) / (4.0 * wo.z);
            double nuo = pf_smith_nu(wo, s), nui = pf_smith_nu(wi, s);
            if (nuo > 0.0 && nui > 0.0 && (nuo < 1.54 || nuo >= 1.6) && (nui < 1.54 || nui >= 1.6))
                update(&p[7], pf_textbook_lean_walter_specular(wo.x, wo.y, wo.z, wi.x, wi.y, wi.z, s.mean_x,
                                                               s.mean_y, s.var_x, s.var_y, s.cov_xy, f0), lib);
        }
        x = uniform(-3.0, 5.0);
        update(&p[8], pf_textbook_erfc_as(x), pf_erfc(x));
    }
    for (j = 0; j < np; j++) {
        int ok = p[j].worst <= p[j].bound;
        printf("%s\t%s\t%d\t%.3g\t%s %.3g\t%s\n", p[j].textbook, p[j].library, p[j].n, p[j].worst,
               p[j].absolute ? "abs" : "rel", p[j].bound, ok ? "ok" : "FAIL");
        fails += !ok;
    }
    return fails ? 1 : 0;
}

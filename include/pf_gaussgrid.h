/* pf_gaussgrid.h - deterministic slope sampling of a Gaussian (Beckmann) footprint: LEADR's
   grid, Gauss-Hermite and a moment-matched grid; specular environment lighting and
   rough-diffuse irradiance (Dupuy et al. 2013, sec. 5).

   A filtered LEADR/LEAN footprint has Gaussian slopes with mean (E[x], E[y]) and covariance
   [[sx^2, cxy], [cxy, sy^2]] (pf_slope_stats). Two of LEADR's integrals over those slopes
   have no closed form: the specular reflection of an environment (eq. 19) and the rough
   diffuse BRDF (eq. 21). Both are expectations over the slope density P22 (eq. 8), and this
   header computes them with a tensor grid of N x N slope samples: a 1D quadrature of the
   standard normal (nodes p_j, weights W_j, sum W_j = 1) is warped by the Cholesky factor of
   the covariance (sec. 5.1),
       x = E[x] + sx p_j,   y = E[y] + sy (r p_j + sqrt(1 - r^2) p_k),   weight W_j W_k,
   with r = cxy / (sx sy). Every sample is reached by its index (0 .. N^2 - 1), with no
   callbacks, so a shader or an embedded loop drives it and does its own texture fetches.

   THE NODE SETS (1D, standard normal, N = 1 .. PF_GG_MAX_N from tables)
     PF_GG_UNIFORM  LEADR's grid: N equally spaced nodes on [-lambda, lambda], weights
                    proportional to exp(-p^2/2). LEADR gives lambda = 1.8 for N = 5; we use
                    lambda(N) = 0.9 sqrt(N - 1), which keeps that point and converges. Only the
                    odd moments (and the 0th) are exact: the N = 5 grid reproduces 86.6% of the
                    variance, so the warped samples are too concentrated (lobes too narrow).
     PF_GG_MATCHED  the same grid with its nodes scaled by 1/sqrt(sum W p^2): the variance is
                    exact (moments 0..3), the weights are LEADR's.
     PF_GG_HERMITE  Gauss-Hermite for the weight exp(-p^2/2) (probabilists'), normalized:
                    moments 0 .. 2N-1 are exact.
     Tables store the ceil(N/2) non-negative nodes and their weights (symmetry gives the rest);
     bench/fit/gaussgrid_nodes.py recomputes them in 50-digit arithmetic. For other N:
     pf_gg_uniform_*_any (any N and lambda, shader-safe) and pf_gg_hermite_generate (CPU).

   USAGE (a fragment shader or a CPU loop; wo = unit view direction in the tangent frame)
     pf_gg_grid g = pf_gg_grid_make(wo, stats, PF_GG_HERMITE, 3);    -- once per pixel
     for (i = 0; i < pf_gg_grid_count(g); ++i) {                      -- specular, eq. 22
         pf_gg_env_sample e = pf_gg_env_sample_at(g, i);
         color += e.weight * fresnel(e.cos_d) * envmap_lod(e.dir, pf_gg_env_lod(e.solid_angle, texel_sr));
     }
     pf_sh9 sh = pf_sh9_constant(0);                                   -- irradiance, alg. 2
     sh = pf_gg_sh9_add_light(sh, g, light_dir, light_irradiance);     -- per directional light
     sh = pf_gg_sh9_add_environment(sh, g, env_sh);                    -- precomputed env SH
     diffuse = pf_gg_diffuse_sh(g, sh);       -- alg. 3, eq. 23 (RGB: pf_gg_diffuse_sh_rgb)
     diffuse1 = pf_gg_diffuse_directional(g, light_dir);              -- one light, no SH

   FUNCTIONS
     node sets     pf_gg_node, pf_gg_weight (set, N, j), pf_gg_node_variance,
                   pf_gg_uniform_lambda, pf_gg_uniform_node_any, pf_gg_uniform_weight_any,
                   pf_gg_uniform_variance_any
                   CPU only (#ifndef PF_GLSL, writes caller arrays): pf_gg_hermite_generate
     grid          pf_gg_grid_make, pf_gg_grid_count, pf_gg_sample_at (slope, weight,
                   micro-normal, projection factor, cell), pf_gg_jacobian
     environment   pf_gg_env_sample_at (reflected direction, weight, Fresnel cosine, solid
                   angle), pf_gg_env_lod
     SH irradiance pf_sh9_make, pf_sh9_constant, pf_sh9_add_directional, pf_sh9_add_scaled,
                   pf_sh9_irradiance, pf_gg_sh9_add_light, pf_gg_sh9_add_environment
     diffuse       pf_gg_diffuse_sh, pf_gg_diffuse_sh_rgb (eq. 23), pf_gg_diffuse_directional
                   (eq. 21, one light)

   CONVENTIONS
     Tangent frame of the macrosurface, w_g = +z; slopes as in pf_smith.h: a micro-normal n
     has slope (-n.x/n.z, -n.y/n.z) and slope (x, y) has micro-normal (-x, -y, 1)/norm. wo and
     light directions are unit vectors. Results are radiance for unit light (a directional
     light of irradiance 1 at normal incidence; an environment of radiance L). The normalization
     (w_nbar.w_g)/(w_nbar.w_o) of eqs. 19, 21 and the view's masking are folded into the
     sample weights as 1/P_o, P_o the projected area of the facets facing the view (as
     pf_leadr_specular: see pf_gg_grid_make); a view on or below the macrosurface gives 0, a
     view below the mesosurface sees the facets facing it. Masking uses pf_g1_beckmann
     (exact) and the joint term 1/(1 + Lambda_o + Lambda_i) of eq. 13, as 1/(1 + G1_o
     Lambda_i) per light, so a reflected direction below the mesosurface gets weight exactly
     0. Out-of-range N is clamped to
     [1, PF_GG_MAX_N]; an unknown set reads as PF_GG_UNIFORM; an index outside the grid gives
     a sample of weight 0. sigma = 0 collapses every sample onto the mean slope; |r| = 1 is
     fine. No allocation, no I/O, no globals; every PF_DEF function is pointer-free. The one
     pointer-taking function, the CPU-only pf_gg_hermite_generate (linkage PF_CPU_DEF, host
     code, compiled out under PF_GLSL), follows pf_core.h's "CPU only: sizes and errors": it
     checks n (1 .. PF_GG_GENERATE_MAX = 64) and both pointers before touching anything and
     returns its count, n, or 0 with both arrays untouched.

   ACCURACY AND COST (measured: docs/gaussgrid.md, tests/test_gaussgrid.c, bench/bench_gaussgrid.c)
     The grid's error is the quadrature error of the node set on the integrand (kinks where a
     micro-normal turns away from the view or the light), not rounding. Cost is N^2 samples;
     the SH route costs N^2 irradiance evaluations for any number of lights; the order-2 SH
     of a directional light's clamped cosine is off by up to 0.094 of its peak (LEADR's "up
     to 9%").

   SOURCES
     Dupuy, Heitz, Iehl, Poulin, Neyret, Ostromoukhov 2013 (LEADR) eqs. 8-11, 13, 18-23,
     sec. 5.1-5.3 (algorithms 1-3) and sec. 6 ("Uniform Sampling"); Ramamoorthi & Hanrahan 2001
     (9-coefficient SH irradiance, their eqs. 12-13); Golub & Welsch 1969 (Gauss nodes as
     eigenvalues of the Jacobi matrix, here found by Sturm bisection); Jaeckel 2005
     (Cholesky warp of a Gaussian grid). */
#ifndef PF_GAUSSGRID_H
#define PF_GAUSSGRID_H

#ifndef PF_GLSL
#  include "pf_smith.h"
#  include "pf_beckmann.h"
#endif

/* ---------------------------------------------------------------- node sets */
#define PF_GG_UNIFORM 0 /* LEADR: uniform on [-lambda, lambda], weights ~ exp(-p^2/2) */
#define PF_GG_HERMITE 1 /* Gauss-Hermite, probabilists' weight, normalized */
#define PF_GG_MATCHED 2 /* LEADR's grid rescaled to the exact unit variance */
#define PF_GG_MAX_N 9   /* largest N with built-in tables */

/* GAUSSGRID TABLES BEGIN: generated by bench/fit/gaussgrid_nodes.py 9, do not edit. */
/* LEADR uniform grid: node k of the non-negative half, lambda(N) = 0.9 sqrt(N - 1) */
PF_DEF pf_real pfi_gg_uniform_node(int n, int k)
{
    switch (n * 8 + k) {
    case 8: return PF_R(0.0);
    case 16: return PF_R(0.9);
    case 24: return PF_R(0.0);
    case 25: return PF_R(1.2727922061357855);
    case 32: return PF_R(0.51961524227066319);
    case 33: return PF_R(1.5588457268119896);
    case 40: return PF_R(0.0);
    case 41: return PF_R(0.9);
    case 42: return PF_R(1.8);
    case 48: return PF_R(0.40249223594996215);
    case 49: return PF_R(1.2074767078498864);
    case 50: return PF_R(2.0124611797498107);
    case 56: return PF_R(0.0);
    case 57: return PF_R(0.73484692283495343);
    case 58: return PF_R(1.4696938456699069);
    case 59: return PF_R(2.2045407685048603);
    case 64: return PF_R(0.3401680257083045);
    case 65: return PF_R(1.0205040771249135);
    case 66: return PF_R(1.7008401285415225);
    case 67: return PF_R(2.3811761799581315);
    case 72: return PF_R(0.0);
    case 73: return PF_R(0.63639610306789277);
    case 74: return PF_R(1.2727922061357855);
    case 75: return PF_R(1.9091883092036783);
    case 76: return PF_R(2.5455844122715711);
    default: return PF_R(0.0);
    }
}

/* LEADR uniform grid: normalized weight exp(-p^2/2) / sum (also the matched grid's) */
PF_DEF pf_real pfi_gg_uniform_weight(int n, int k)
{
    switch (n * 8 + k) {
    case 8: return PF_R(1.0);
    case 16: return PF_R(0.5);
    case 24: return PF_R(0.52918000901314633);
    case 25: return PF_R(0.23540999549342684);
    case 32: return PF_R(0.37324699166883108);
    case 33: return PF_R(0.12675300833116892);
    case 40: return PF_R(0.36633377649307718);
    case 41: return PF_R(0.24433613395509377);
    case 42: return PF_R(0.072496977798367638);
    case 48: return PF_R(0.30008020630512461);
    case 49: return PF_R(0.15696922912013445);
    case 50: return PF_R(0.042950564574740935);
    case 56: return PF_R(0.29568095530603483);
    case 57: return PF_R(0.22571677814655856);
    case 58: return PF_R(0.10041192944035066);
    case 59: return PF_R(0.026030814760073372);
    case 64: return PF_R(0.25758193100970981);
    case 65: return PF_R(0.16214333132333844);
    case 66: return PF_R(0.064249016714435731);
    case 67: return PF_R(0.016025720952516018);
    case 72: return PF_R(0.25479918905011427);
    case 73: return PF_R(0.2080910534741889);
    case 74: return PF_R(0.11334947451600743);
    case 75: return PF_R(0.041180948773480881);
    case 76: return PF_R(0.0099789287112656511);
    default: return PF_R(0.0);
    }
}

/* moment-matched uniform grid: uniform nodes times 1/sqrt(sum W p^2) */
PF_DEF pf_real pfi_gg_matched_node(int n, int k)
{
    switch (n * 8 + k) {
    case 8: return PF_R(0.0);
    case 16: return PF_R(1.0);
    case 24: return PF_R(0.0);
    case 25: return PF_R(1.4573791522243742);
    case 32: return PF_R(0.57467011506053712);
    case 33: return PF_R(1.7240103451816113);
    case 40: return PF_R(0.0);
    case 41: return PF_R(0.96734778820555194);
    case 42: return PF_R(1.9346955764111039);
    case 48: return PF_R(0.42359441706377728);
    case 49: return PF_R(1.2707832511913318);
    case 50: return PF_R(2.1179720853188864);
    case 56: return PF_R(0.0);
    case 57: return PF_R(0.76176605337727408);
    case 58: return PF_R(1.5235321067545482);
    case 59: return PF_R(2.2852981601318222);
    case 64: return PF_R(0.34885976178151734);
    case 65: return PF_R(1.046579285344552);
    case 66: return PF_R(1.7442988089075867);
    case 67: return PF_R(2.4420183324706214);
    case 72: return PF_R(0.0);
    case 73: return PF_R(0.64771938063927387);
    case 74: return PF_R(1.2954387612785477);
    case 75: return PF_R(1.9431581419178216);
    case 76: return PF_R(2.5908775225570955);
    default: return PF_R(0.0);
    }
}

/* Gauss-Hermite (probabilists'): non-negative zeros of He_N */
PF_DEF pf_real pfi_gg_hermite_node(int n, int k)
{
    switch (n * 8 + k) {
    case 8: return PF_R(0.0);
    case 16: return PF_R(1.0);
    case 24: return PF_R(0.0);
    case 25: return PF_R(1.7320508075688773);
    case 32: return PF_R(0.74196378430272586);
    case 33: return PF_R(2.3344142183389772);
    case 40: return PF_R(0.0);
    case 41: return PF_R(1.3556261799742659);
    case 42: return PF_R(2.8569700138728057);
    case 48: return PF_R(0.61670659019259415);
    case 49: return PF_R(1.8891758777537107);
    case 50: return PF_R(3.324257433552119);
    case 56: return PF_R(0.0);
    case 57: return PF_R(1.1544053947399681);
    case 58: return PF_R(2.3667594107345413);
    case 59: return PF_R(3.7504397177257423);
    case 64: return PF_R(0.53907981135137511);
    case 65: return PF_R(1.636519042435108);
    case 66: return PF_R(2.8024858612875417);
    case 67: return PF_R(4.1445471861258943);
    case 72: return PF_R(0.0);
    case 73: return PF_R(1.0232556637891325);
    case 74: return PF_R(2.0768479786778301);
    case 75: return PF_R(3.2054290028564699);
    case 76: return PF_R(4.5127458633997827);
    default: return PF_R(0.0);
    }
}

/* Gauss-Hermite: normalized weights (N-1)! / (N He_{N-1}(x)^2) */
PF_DEF pf_real pfi_gg_hermite_weight(int n, int k)
{
    switch (n * 8 + k) {
    case 8: return PF_R(1.0);
    case 16: return PF_R(0.5);
    case 24: return PF_R(0.66666666666666667);
    case 25: return PF_R(0.16666666666666667);
    case 32: return PF_R(0.45412414523193151);
    case 33: return PF_R(0.045875854768068492);
    case 40: return PF_R(0.53333333333333333);
    case 41: return PF_R(0.22207592200561264);
    case 42: return PF_R(0.011257411327720689);
    case 48: return PF_R(0.40882846955602923);
    case 49: return PF_R(0.088615746041914527);
    case 50: return PF_R(0.0025557844020562464);
    case 56: return PF_R(0.45714285714285714);
    case 57: return PF_R(0.24012317860501271);
    case 58: return PF_R(0.030757123967586497);
    case 59: return PF_R(5.4826885597221779e-4);
    case 64: return PF_R(0.37301225767907735);
    case 65: return PF_R(0.11723990766175902);
    case 66: return PF_R(0.0096352201207882672);
    case 67: return PF_R(1.1261453837536777e-4);
    case 72: return PF_R(0.40634920634920635);
    case 73: return PF_R(0.24409750289493944);
    case 74: return PF_R(0.049916406765217874);
    case 75: return PF_R(0.0027891413212317686);
    case 76: return PF_R(2.2345844007746584e-5);
    default: return PF_R(0.0);
    }
}

/* GAUSSGRID TABLES END */

/* N clamped to the tables' range [1, PF_GG_MAX_N]. */
PF_DEF int pfi_gg_clamp_n(int n) { return n < 1 ? 1 : (n > PF_GG_MAX_N ? PF_GG_MAX_N : n); }

/* Index of node j (0 .. n-1, ascending) in the stored non-negative half: |2j - n + 1| / 2
   rounded down (0 is the centre node for odd n, the smallest positive one for even n).
   Only for j in 0 .. n-1: its callers check the range first, so 2j cannot overflow an int
   (it did for |j| >= 2^30, undefined behaviour that UBSan caught). */
PF_DEF int pfi_gg_half_index(int n, int j)
{
    int d = 2 * j - n + 1;
    return (d < 0 ? -d : d) / 2;
}

/* pf_gg_node(set, n, j): node j (0 .. n-1, ascending) of the n-point set for a standard
   normal. n is clamped to [1, PF_GG_MAX_N]; j outside 0 .. n-1 (for the clamped n) gives 0;
   a node_set other than PF_GG_HERMITE and PF_GG_MATCHED reads as PF_GG_UNIFORM (so every int
   is a valid set: pf_gg_node, pf_gg_weight and the grid agree on it). The range is tested
   before the table index is formed, so j = -1 cannot fold onto the table's other half (the
   n = 4 node 0.5196 for j = -1, n = 3). */
PF_DEF pf_real pf_gg_node(int node_set, int n, int j)
{
    int m = pfi_gg_clamp_n(n);
    int k;
    pf_real p;
    if (j < 0 || j >= m) return PF_R(0.0);
    k = pfi_gg_half_index(m, j);
    if (node_set == PF_GG_HERMITE) p = pfi_gg_hermite_node(m, k);
    else if (node_set == PF_GG_MATCHED) p = pfi_gg_matched_node(m, k);
    else p = pfi_gg_uniform_node(m, k);
    return 2 * j - m + 1 < 0 ? -p : p;
}

/* pf_gg_weight(set, n, j): the normalized weight of node j (the n weights sum to 1); 0 for j
   outside 0 .. n-1. n and node_set as pf_gg_node; the matched set shares the uniform set's
   weights. */
PF_DEF pf_real pf_gg_weight(int node_set, int n, int j)
{
    int m = pfi_gg_clamp_n(n);
    int k;
    if (j < 0 || j >= m) return PF_R(0.0);
    k = pfi_gg_half_index(m, j);
    if (node_set == PF_GG_HERMITE) return pfi_gg_hermite_weight(m, k);
    return pfi_gg_uniform_weight(m, k);
}

/* Sum of W_j p_j^2: the variance the n-point set gives a standard normal (1 for the
   Hermite and matched sets with n >= 2; LEADR's N = 5 grid: 0.8656). */
PF_DEF pf_real pf_gg_node_variance(int node_set, int n)
{
    int m = pfi_gg_clamp_n(n), j;
    pf_real v = PF_R(0.0);
    for (j = 0; j < m; ++j) v += pf_gg_weight(node_set, m, j) * pf_sq(pf_gg_node(node_set, m, j));
    return v;
}

/* ---------------------------------------------------------------- any N, uniform grid
   The uniform (and matched) grid for any n >= 1 and half-width lambda, computed on the fly:
   n exponentials per weight, so precompute them when n is fixed. */

/* LEADR's half-width rule as extended here: lambda(n) = 0.9 sqrt(n - 1) (1.8 at n = 5). */
PF_DEF pf_real pf_gg_uniform_lambda(int n)
{
    return PF_R(0.9) * PF_SQRT(pf_max(PF_R(n) - PF_R(1.0), PF_R(0.0)));
}

/* Node j of n equally spaced nodes on [-lambda, lambda] (0 for n <= 1). */
PF_DEF pf_real pf_gg_uniform_node_any(int n, pf_real lambda, int j)
{
    if (n <= 1) return PF_R(0.0);
    /* 2j - n + 1 in pf_real: as an int it overflows for |j| >= 2^30 */
    return lambda * (PF_R(2.0) * PF_R(j) - PF_R(n - 1)) / PF_R(n - 1);
}

/* exp(-(p_k^2 - pc^2)/2) for node k of the n-node grid of spacing h (p_k = h (2k - n + 1)/2,
   n >= 2), relative to the central node pc = |p_(n/2)| (the nearest to 0), written as a
   product, (|p_k| - pc)(|p_k| + pc), so that it keeps its accuracy. */
PF_DEF pf_real pfi_gg_rel_weight(int n, pf_real h, int k, pf_real pc)
{
    pf_real a = PF_FABS(h * (PF_R(k) - PF_R(0.5) * PF_R(n - 1)));
    return PF_EXP(PF_R(-0.5) * (a - pc) * (a + pc));
}

/* Weight of node j: exp(-p_j^2/2) / sum_k exp(-p_k^2/2) (1 for n <= 1, 0 outside 0 .. n-1).
   Every exponential is taken relative to the central node pc (exp(-(p^2 - pc^2)/2)), so the
   sum is >= 1: for a wide grid the plain exp(-p^2/2) of every node underflows (float: n = 2,
   lambda = 16 gave 0/0 = NaN; from lambda = 13.9 under -ffast-math, which flushes
   subnormals), whereas now the far weights underflow to 0 and the central ones stay. The
   node spacing h = 2 lambda/(n - 1) is divided once, not per node. */
PF_DEF pf_real pf_gg_uniform_weight_any(int n, pf_real lambda, int j)
{
    pf_real s = PF_R(0.0), h, pc;
    int k;
    if (j < 0 || j >= n) return PF_R(0.0);
    if (n <= 1) return PF_R(1.0);
    h = PF_R(2.0) * lambda / PF_R(n - 1);
    pc = PF_FABS(h * (PF_R(n / 2) - PF_R(0.5) * PF_R(n - 1)));
    for (k = 0; k < n; ++k) s += pfi_gg_rel_weight(n, h, k, pc);
    return pfi_gg_rel_weight(n, h, j, pc) / s;
}

/* sum W_j p_j^2 of that grid; the matched grid's nodes are pf_gg_uniform_node_any / sqrt(it).
   Weights relative to the central node, as pf_gg_uniform_weight_any (finite and exact for wide
   grids too, where the plain sum underflowed and gave 0). */
PF_DEF pf_real pf_gg_uniform_variance_any(int n, pf_real lambda)
{
    pf_real s = PF_R(0.0), m2 = PF_R(0.0), h, pc;
    int k;
    if (n <= 1) return PF_R(0.0);
    h = PF_R(2.0) * lambda / PF_R(n - 1);
    pc = PF_FABS(h * (PF_R(n / 2) - PF_R(0.5) * PF_R(n - 1)));
    for (k = 0; k < n; ++k) {
        pf_real p = h * (PF_R(k) - PF_R(0.5) * PF_R(n - 1));
        pf_real e = pfi_gg_rel_weight(n, h, k, pc);
        s += e;
        m2 += e * p * p;
    }
    return m2 / s;
}

/* ---------------------------------------------------------------- the 2D grid (sec. 5.1) */
/* What one pixel needs for every sample: the view, the slope statistics and their Cholesky
   factor, the masking of the view and the eq. 19/21 normalization. */
PF_STRUCT_BEGIN(pf_gg_grid)
    pf_vec3 wo;           /* unit view direction, tangent frame */
    pf_slope_stats stats; /* mean and covariance of the slopes */
    pf_real sigma_x;      /* sqrt(var_x) */
    pf_real sigma_y;      /* sqrt(var_y) */
    pf_real corr;         /* r = cov / (sigma_x sigma_y), in [-1, 1] (0 if a sigma is 0) */
    pf_real corr_c;       /* sqrt(1 - r^2) */
    pf_real inv_proj;     /* 1/P_o, P_o = E[max(0, wo.z - x wo.x - y wo.y)] the projected area of the facets facing wo
                             (pf_beckmann_facing_area) = A_o (1 + Lambda(wo)) above the mesosurface; 0 at or below the
                             macrosurface (see pf_gg_grid_make) */
    pf_real g1_o;         /* 1/(1 + Lambda(wo)) (eq. 13 with one direction), = A_o / P_o; 0 at or below the mesosurface */
    int node_set;         /* PF_GG_UNIFORM, PF_GG_HERMITE or PF_GG_MATCHED */
    int n;                /* nodes per axis, in [1, PF_GG_MAX_N] */
PF_STRUCT_END(pf_gg_grid)

/* Per-pixel setup: Cholesky factor of the covariance (LEADR sec. 5.1; a negative variance
   counts as 0, |r| is clamped to 1), the view's masking and the projected-area normalization.
   wo must be a unit vector in the tangent frame.
   Normalization, as pf_leadr_specular (see the comment above pf_leadr_specular in
   pf_beckmann.h): eqs. 19-21 divide by A_o = w_nbar.w_o / w_nbar.w_g and multiply by
   G = 1/(1 + Lambda_o + Lambda_i), which is 0 / 0 when the view is at or below the
   mesosurface (A_o <= 0) yet above the macrosurface, where a flat (bump- or normal-mapped)
   macrosurface still shows the facets facing the view. The grid folds the view's masking
   into the normalization instead: G / A_o = (1 / P_o) / (1 + (A_o / P_o) Lambda_i) with
   P_o = A_o (1 + Lambda_o) above the mesosurface (so A_o / P_o = G1(wo) = g1_o) and P_o > 0,
   g1_o = 0 below it. Hence inv_proj = 1/P_o and the per-light factor pfi_gg_shadowing =
   1/(1 + g1_o Lambda_i) (the shadowing of the visible facets, G2/G1), identical to eq. 13
   above the mesosurface, finite and continuous through A_o = 0 and Smith's limit below it
   (only the highest facets are seen, and they are lit). A view at or below the macrosurface
   (wo.z <= 0), or one so far below the mesosurface that P_o < 1e-30, gets inv_proj = 0. */
PF_DEF pf_gg_grid pf_gg_grid_make(pf_vec3 wo, pf_slope_stats s, int node_set, int n)
{
    pf_gg_grid g;
    pf_real sx = PF_SQRT(pf_max(s.var_x, PF_R(0.0)));
    pf_real sy = PF_SQRT(pf_max(s.var_y, PF_R(0.0)));
    pf_real sxy = sx * sy;
    /* min before max: a NaN covariance becomes r = 1 (finite samples), not NaN */
    pf_real r = sxy > PF_R(0.0) ? pf_max(pf_min(s.cov_xy / sxy, PF_R(1.0)), PF_R(-1.0)) : PF_R(0.0);
    pf_real facing = pf_beckmann_facing_area(wo, s);
    g.wo = wo;
    g.stats = s;
    g.sigma_x = sx;
    g.sigma_y = sy;
    g.corr = r;
    g.corr_c = PF_SQRT(pf_max(PF_R(1.0) - r * r, PF_R(0.0)));
    g.inv_proj = wo.z > PF_R(0.0) && facing > PF_R(1.0e-30) ? PF_R(1.0) / facing : PF_R(0.0);
    g.g1_o = pf_g1_beckmann(pf_smith_nu(wo, s));
    g.node_set = node_set;
    g.n = pfi_gg_clamp_n(n);
    return g;
}

/* Number of samples, N^2. */
PF_DEF int pf_gg_grid_count(pf_gg_grid g) { return g.n * g.n; }

/* One slope sample. */
PF_STRUCT_BEGIN(pf_gg_sample)
    pf_real slope_x;  /* E[x] + sigma_x p_j */
    pf_real slope_y;  /* E[y] + sigma_y (r p_j + sqrt(1 - r^2) p_k) */
    pf_real weight;   /* W_j W_k (the N^2 weights sum to 1) */
    pf_vec3 normal;   /* micro-normal (-x, -y, 1)/norm (eq. 11 applied to the sample) */
    pf_real proj;     /* <w_n, w_o>/(w_n.w_g) / P_o = max(0, wo.z - x wo.x - y wo.y) * inv_proj: the masked eq. 19/21 weight
                         (the visible normals' density; its expectation is 1) */
    pf_real cell;     /* u_j u_k, u_j = W_j / phi(p_j): the sample's area in the standard-normal plane */
PF_STRUCT_END(pf_gg_sample)

/* The sample of node pair (p_j, W_j), (p_k, W_k). The cell width u = W / phi(p) is the
   interval of the standard normal that the node stands for (sum_j u_j phi(p_j) = 1, so the
   cells tile the measure); for the uniform grid it is the node spacing. */
PF_DEF pf_gg_sample pf_gg_sample_nodes(pf_gg_grid g, pf_real pj, pf_real wj, pf_real pk, pf_real wk)
{
    pf_gg_sample smp;
    pf_real x = g.stats.mean_x + g.sigma_x * pj;
    pf_real y = g.stats.mean_y + g.sigma_y * (g.corr * pj + g.corr_c * pk);
    pf_real q = PF_R(1.0) + x * x + y * y;
    smp.slope_x = x;
    smp.slope_y = y;
    smp.weight = wj * wk;
    /* (-x, -y, 1)/sqrt(q); the scaled normalization only where q could overflow */
    if (q < PF_R(1.0e30)) smp.normal = pf_vec3_scale(pf_vec3_make(-x, -y, PF_R(1.0)), PF_R(1.0) / PF_SQRT(q));
    else smp.normal = pf_vec3_normalize(pf_vec3_make(-x, -y, PF_R(1.0)));
    /* <w_n, w_o>/(w_n . w_g): the 1/sqrt(1 + x^2 + y^2) of w_n cancels */
    smp.proj = pf_max(g.wo.z - x * g.wo.x - y * g.wo.y, PF_R(0.0)) * g.inv_proj;
    smp.cell = PF_R(0.0); /* filled by pf_gg_sample_at; the diffuse loops do not need it */
    return smp;
}

/* Sample i (0 .. N^2 - 1) of the grid: j = i / N along the first Cholesky axis, k = i mod N
   along the second. Outside the range: weight 0. */
PF_DEF pf_gg_sample pf_gg_sample_at(pf_gg_grid g, int i)
{
    int j = i / g.n;
    int k = i - j * g.n;
    pf_real pj, pk, wj, wk;
    pf_gg_sample smp;
    if (i < 0) k = -1; /* weight 0 */
    pj = pf_gg_node(g.node_set, g.n, j);
    pk = pf_gg_node(g.node_set, g.n, k);
    wj = pf_gg_weight(g.node_set, g.n, j);
    wk = pf_gg_weight(g.node_set, g.n, k);
    smp = pf_gg_sample_nodes(g, pj, wj, pk, wk);
    /* u_j u_k = W_j W_k 2 pi exp((p_j^2 + p_k^2)/2); tiny (possibly 0) far out, never huge */
    smp.cell = smp.weight * (PF_R(2.0) * PF_PI) * PF_EXP(PF_R(0.5) * (pj * pj + pk * pk));
    return smp;
}

/* 1/(1 + G1(wo) Lambda_i) = G1_i / (G1_i + G1_o (1 - G1_i)), the joint masking-shadowing of
   eq. 13 divided by G1(wo) (pf_smith_joint(g1_o, g1_i) / g1_o), which pf_gg_grid_make's
   inv_proj = 1/P_o leaves to each light: see there. 1 when g1_o = 0 (a view below the
   mesosurface sees only the highest facets), 0 when g1_i = 0 (a light below it), never 0/0;
   in [0, 1] for G1s in [0, 1]. */
PF_DEF pf_real pfi_gg_shadowing(pf_real g1_o, pf_real g1_i)
{
    pf_real b = pf_min(pf_max(g1_i, PF_R(0.0)), PF_R(1.0)); /* NaN -> 0 */
    pf_real a = pf_min(pf_max(g1_o, PF_R(0.0)), PF_R(1.0));
    return b > PF_R(0.0) ? b / (b + a * (PF_R(1.0) - b)) : PF_R(0.0);
}

/* |d w_i / d slope| = 4 |w_n.w_o| |w_n.w_g|^3 (LEADR sec. 5.2): reflection about w_n
   (4 |w_n.w_o|) times the slope-to-normal Jacobian cos^3. */
PF_DEF pf_real pf_gg_jacobian(pf_vec3 wn, pf_vec3 wo)
{
    return PF_R(4.0) * PF_FABS(pf_vec3_dot(wn, wo)) * PF_FABS(wn.z * wn.z * wn.z);
}

/* ---------------------------------------------------------------- environment (sec. 5.2) */
PF_STRUCT_BEGIN(pf_gg_env_sample)
    pf_vec3 dir;         /* reflected direction w_i = 2 (w_n.w_o) w_n - w_o (eq. 18) */
    pf_real weight;      /* W <w_n,w_o>/(w_n.w_g) (w_nbar.w_g)/(w_nbar.w_o) / (1 + Lambda_o + Lambda_i) (eq. 22 without L and F),
                            written W proj / (1 + G1_o Lambda_i) (pf_gg_grid_make) */
    pf_real cos_d;       /* w_n.w_o = w_n.w_i clamped to [0, 1]: the angle for the Fresnel term F */
    pf_real solid_angle; /* alpha = J * A: the sample's solid angle around dir, for the LOD */
PF_STRUCT_END(pf_gg_env_sample)

/* Sample i of eq. 22: I = sum_i weight_i F(cos_d_i) L(dir_i), L the environment radiance
   prefiltered over solid_angle_i. The slope area is A = cell * max(sigma_x, sigma_y)^2: like
   LEADR's (2 lambda max(sigma)/N)^2, isotropic and sized by the larger deviation so that
   neighbouring filters overlap, but with the node's own cell width u_j (the uniform grid's
   spacing 2 lambda/(N-1) at the centre; wider where Gauss-Hermite nodes thin out) instead of
   2 lambda/N, which is defined for every node set (it is (N/(N-1))^2 larger than LEADR's for
   the uniform grid: a slightly blurrier, never sparser, filter). */
PF_DEF pf_gg_env_sample pf_gg_env_sample_at(pf_gg_grid g, int i)
{
    pf_gg_env_sample e;
    pf_gg_sample smp = pf_gg_sample_at(g, i);
    pf_real c = pf_vec3_dot(smp.normal, g.wo);
    pf_real smax = pf_max(g.sigma_x, g.sigma_y);
    e.dir = pf_vec3_sub(pf_vec3_scale(smp.normal, PF_R(2.0) * c), g.wo);
    e.weight = smp.weight * smp.proj * pfi_gg_shadowing(g.g1_o, pf_g1_beckmann(pf_smith_nu(e.dir, g.stats)));
    /* clamped to [0, 1]: w_n . w_o of two unit vectors rounds up to 1 + 2 ulp near normal
       incidence (the sweep found 1.00000024); max first, so NaN gives 0 */
    e.cos_d = pf_min(pf_max(c, PF_R(0.0)), PF_R(1.0));
    e.solid_angle = pf_gg_jacobian(smp.normal, g.wo) * smp.cell * smax * smax;
    return e;
}

/* Mip level for a prefiltered environment whose level-0 texel covers texel_solid_angle
   steradians (a cube map of face size S: about 4 pi / (6 S^2)): 0.5 log2(solid_angle / texel),
   at least 0 (Colbert & Krivanek 2007, as used by LEADR sec. 5.2). */
PF_DEF pf_real pf_gg_env_lod(pf_real solid_angle, pf_real texel_solid_angle)
{
    pf_real q = solid_angle / texel_solid_angle;
    if (!(q > PF_R(1.0))) return PF_R(0.0);
    return PF_R(0.5) * PF_LOG(q) / PF_LN2;
}

/* ---------------------------------------------------------------- SH irradiance (sec. 5.3) */
/* Nine spherical-harmonic coefficients L_lm (l <= 2) of one colour channel, in the real basis
   of Ramamoorthi & Hanrahan 2001; members named l<l><m>, m < 0 written m1/m2. One channel per
   struct (36 bytes in float): a shader keeps three (R, G, B) and calls pf_gg_diffuse_sh_rgb.
   (An RGB struct of 9 pf_vec3 is 108 bytes, and compilers copy by-value aggregates that large
   with a memcpy call, which bare-metal builds without a libc cannot link.) */
PF_STRUCT_BEGIN(pf_sh9)
    pf_real l00;
    pf_real l1m1;
    pf_real l10;
    pf_real l11;
    pf_real l2m2;
    pf_real l2m1;
    pf_real l20;
    pf_real l21;
    pf_real l22;
PF_STRUCT_END(pf_sh9)

PF_DEF pf_sh9 pf_sh9_make(pf_real l00, pf_real l1m1, pf_real l10, pf_real l11, pf_real l2m2,
                          pf_real l2m1, pf_real l20, pf_real l21, pf_real l22)
{
    pf_sh9 sh;
    sh.l00 = l00;
    sh.l1m1 = l1m1;
    sh.l10 = l10;
    sh.l11 = l11;
    sh.l2m2 = l2m2;
    sh.l2m1 = l2m1;
    sh.l20 = l20;
    sh.l21 = l21;
    sh.l22 = l22;
    return sh;
}

/* The coefficients of an environment of constant radiance: L00 = 2 sqrt(pi) radiance, the
   rest 0 (its irradiance is pi radiance on every normal). pf_sh9_constant(0) is the empty
   sum to start a projection from. */
PF_DEF pf_sh9 pf_sh9_constant(pf_real radiance)
{
    return pf_sh9_make(PF_R(2.0) * PF_SQRT_PI * radiance, PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0),
                       PF_R(0.0), PF_R(0.0), PF_R(0.0), PF_R(0.0));
}

/* a + s b, coefficient by coefficient (SH projection is linear). */
PF_DEF pf_sh9 pf_sh9_add_scaled(pf_sh9 a, pf_sh9 b, pf_real s)
{
    return pf_sh9_make(a.l00 + s * b.l00, a.l1m1 + s * b.l1m1, a.l10 + s * b.l10, a.l11 + s * b.l11,
                       a.l2m2 + s * b.l2m2, a.l2m1 + s * b.l2m1, a.l20 + s * b.l20, a.l21 + s * b.l21,
                       a.l22 + s * b.l22);
}

/* The basis constants Y_lm of Ramamoorthi & Hanrahan 2001 (their values 0.282095,
   0.488603, 1.092548, 0.315392, 0.546274), written to full precision from their closed
   forms 1/(2 sqrt pi), sqrt(3/(4 pi)), sqrt(15/(4 pi)), sqrt(5/(16 pi)), sqrt(15/(16 pi)). */
#define PF_SH_Y00 PF_R(0.28209479177387814347)
#define PF_SH_Y1  PF_R(0.48860251190291992159)
#define PF_SH_Y2X PF_R(1.0925484305920790705)
#define PF_SH_Y20 PF_R(0.31539156525252000603)
#define PF_SH_Y22 PF_R(0.54627421529603953527)

/* Adds a directional light from unit direction dir with irradiance e (at normal incidence,
   this channel): L_lm += e Y_lm(dir) (LEADR algorithm 2, before its masking weight). */
PF_DEF pf_sh9 pf_sh9_add_directional(pf_sh9 sh, pf_vec3 dir, pf_real e)
{
    pf_real x = dir.x, y = dir.y, z = dir.z;
    return pf_sh9_make(sh.l00 + e * PF_SH_Y00, sh.l1m1 + e * PF_SH_Y1 * y, sh.l10 + e * PF_SH_Y1 * z,
                       sh.l11 + e * PF_SH_Y1 * x, sh.l2m2 + e * PF_SH_Y2X * x * y,
                       sh.l2m1 + e * PF_SH_Y2X * y * z,
                       sh.l20 + e * PF_SH_Y20 * (PF_R(3.0) * z * z - PF_R(1.0)),
                       sh.l21 + e * PF_SH_Y2X * x * z, sh.l22 + e * PF_SH_Y22 * (x * x - y * y));
}

/* Irradiance E(n) = sum_lm A_l L_lm Y_lm(n) at unit normal n (Ramamoorthi & Hanrahan 2001
   eq. 13, as recalled by LEADR sec. 5.3), A_0 = pi, A_1 = 2 pi/3, A_2 = pi/4:
     E = c1 L22 (x^2 - y^2) + c3 L20 z^2 + c4 L00 - c5 L20
         + 2 c1 (L2-2 xy + L21 xz + L2-1 yz) + 2 c2 (L11 x + L1-1 y + L10 z)
   with c1 = 0.429043, c2 = 0.511664, c3 = 0.743125, c4 = 0.886227, c5 = 0.247708 as printed
   by Ramamoorthi & Hanrahan; here to full precision from c1 = (pi/4) Y22, c2 = (pi/3) Y1,
   c3 = (3 pi/4) Y20, c4 = pi Y00, c5 = (pi/4) Y20 (the printed c3 is 1.6e-6 high: the exact
   value is 0.7431239). */
PF_DEF pf_real pf_sh9_irradiance(pf_sh9 sh, pf_vec3 n)
{
    const pf_real c1 = PF_R(0.42904276540489171563), c2 = PF_R(0.51166335397324424423);
    const pf_real c3 = PF_R(0.74312386830112706500), c4 = PF_R(0.88622692545275801365);
    const pf_real c5 = PF_R(0.24770795610037568833);
    pf_real x = n.x, y = n.y, z = n.z;
    return c4 * sh.l00 + (c3 * z * z - c5) * sh.l20 + c1 * (x * x - y * y) * sh.l22
           + PF_R(2.0) * c1 * (x * y * sh.l2m2 + x * z * sh.l21 + y * z * sh.l2m1)
           + PF_R(2.0) * c2 * (x * sh.l11 + y * sh.l1m1 + z * sh.l10);
}

/* LEADR algorithm 2, one directional light: its irradiance e weighted by the joint
   masking-shadowing 1/(1 + Lambda_o + Lambda_i) of eq. 20 (0 when dir is below the
   mesosurface), then projected. The view's masking G1(wo) is in the grid's normalization
   (inv_proj = 1/P_o, pf_gg_grid_make), so the weight here is their ratio 1/(1 + G1_o
   Lambda_i) (pfi_gg_shadowing): the same product, and defined for a view below the
   mesosurface. */
PF_DEF pf_sh9 pf_gg_sh9_add_light(pf_sh9 sh, pf_gg_grid g, pf_vec3 dir, pf_real e)
{
    pf_real v = pfi_gg_shadowing(g.g1_o, pf_g1_beckmann(pf_smith_nu(dir, g.stats)));
    return pf_sh9_add_directional(sh, dir, e * v);
}

/* LEADR algorithm 2, environment: precomputed coefficients weighted by the masking
   1/(1 + Lambda_o) alone (LEADR's approximation: the environment's shadowing is ignored).
   That masking is the grid's normalization inv_proj = 1/P_o (pf_gg_grid_make), so the
   coefficients are added unscaled (scale 1; 0 for a grid whose view sees nothing, inv_proj =
   0, whose diffuse is 0 whatever the SH holds). */
PF_DEF pf_sh9 pf_gg_sh9_add_environment(pf_sh9 sh, pf_gg_grid g, pf_sh9 env)
{
    return pf_sh9_add_scaled(sh, env, g.inv_proj > PF_R(0.0) ? PF_R(1.0) : PF_R(0.0));
}

/* ---------------------------------------------------------------- rough diffuse (sec. 4.5, 5.3) */
/* Eq. 23 (LEADR algorithm 3): the rough diffuse BRDF of eq. 21 integrated against the
   irradiance map sh (built with pf_gg_sh9_add_light / _add_environment, so it already holds
   the masking-shadowing): (1/pi) sum W proj E(w_n). Radiance per unit albedo, one channel.
   Nested loops, one node lookup per row. */
PF_DEF pf_real pf_gg_diffuse_sh(pf_gg_grid g, pf_sh9 sh)
{
    pf_real acc = PF_R(0.0);
    int j, k;
    for (j = 0; j < g.n; ++j) {
        pf_real pj = pf_gg_node(g.node_set, g.n, j), wj = pf_gg_weight(g.node_set, g.n, j);
        for (k = 0; k < g.n; ++k) {
            pf_gg_sample smp = pf_gg_sample_nodes(g, pj, wj, pf_gg_node(g.node_set, g.n, k),
                                                   pf_gg_weight(g.node_set, g.n, k));
            acc += smp.weight * smp.proj * pf_sh9_irradiance(sh, smp.normal);
        }
    }
    return acc * PF_INV_PI;
}

/* The same for three channels at once (one pass over the samples): (R, G, B). */
PF_DEF pf_vec3 pf_gg_diffuse_sh_rgb(pf_gg_grid g, pf_sh9 sh_r, pf_sh9 sh_g, pf_sh9 sh_b)
{
    pf_vec3 acc = pf_vec3_make(PF_R(0.0), PF_R(0.0), PF_R(0.0));
    int j, k;
    for (j = 0; j < g.n; ++j) {
        pf_real pj = pf_gg_node(g.node_set, g.n, j), wj = pf_gg_weight(g.node_set, g.n, j);
        for (k = 0; k < g.n; ++k) {
            pf_gg_sample smp = pf_gg_sample_nodes(g, pj, wj, pf_gg_node(g.node_set, g.n, k),
                                                   pf_gg_weight(g.node_set, g.n, k));
            pf_real w = smp.weight * smp.proj;
            acc = pf_vec3_add(acc, pf_vec3_make(w * pf_sh9_irradiance(sh_r, smp.normal),
                                                w * pf_sh9_irradiance(sh_g, smp.normal),
                                                w * pf_sh9_irradiance(sh_b, smp.normal)));
        }
    }
    return pf_vec3_scale(acc, PF_INV_PI);
}

/* Eq. 21 under one directional light from unit direction wi, with no SH: the irradiance of
   the light on a micro-normal is exactly <w_n, w_i> / (1 + Lambda_o + Lambda_i) (eq. 20), so
       I = (1/pi) (G / A_o) sum W <w_n,w_o>/(w_n.w_g) max(0, w_n . w_i),
   G / A_o = 1/(1 + Lambda_o + Lambda_i) / A_o = inv_proj / (1 + G1_o Lambda_i) (pf_gg_grid_make).
   Radiance per unit irradiance of the light (at normal incidence) and unit albedo; 0 when
   the light is at or below the mesosurface or the view at or below the macrosurface (a
   view below the mesosurface sees the facets facing it). Free of the SH error (up to 9%). */
PF_DEF pf_real pf_gg_diffuse_directional(pf_gg_grid g, pf_vec3 wi)
{
    pf_real acc = PF_R(0.0);
    pf_real v = pfi_gg_shadowing(g.g1_o, pf_g1_beckmann(pf_smith_nu(wi, g.stats)));
    int j, k;
    for (j = 0; j < g.n; ++j) {
        pf_real pj = pf_gg_node(g.node_set, g.n, j), wj = pf_gg_weight(g.node_set, g.n, j);
        for (k = 0; k < g.n; ++k) {
            pf_gg_sample smp = pf_gg_sample_nodes(g, pj, wj, pf_gg_node(g.node_set, g.n, k),
                                                   pf_gg_weight(g.node_set, g.n, k));
            acc += smp.weight * smp.proj * pf_max(pf_vec3_dot(smp.normal, wi), PF_R(0.0));
        }
    }
    return acc * v * PF_INV_PI;
}

/* ---------------------------------------------------------------- CPU only: Gauss-Hermite for any N
   Host code under pf_core.h's "CPU only: sizes and errors" rules: linkage PF_CPU_DEF (static
   inline by default, never __device__), compiled out under PF_GLSL. */
#ifndef PF_GLSL
#define PF_GG_GENERATE_MAX 64 /* largest N of pf_gg_hermite_generate */

/* Sturm count: how many eigenvalues of the Jacobi matrix of He_n (zero diagonal, off-diagonal
   sqrt(1), ..., sqrt(n-1); its eigenvalues are the zeros of He_n, Golub & Welsch 1969) lie
   below x, from the signs of the pivots of LDL^T of (J - x I). */
PF_CPU_DEF int pfi_gg_sturm_count(int n, pf_real x)
{
    pf_real d = -x;
    int i, c = 0;
    if (d < PF_R(0.0)) c++;
    for (i = 1; i < n; ++i) {
        if (d == PF_R(0.0)) d = PF_REAL_EPSILON * PF_REAL_EPSILON; /* a zero pivot: perturb */
        d = -x - PF_R(i) / d;
        if (d < PF_R(0.0)) c++;
    }
    return c;
}

/* Orthonormal Hermite polynomial P_{n-1}(x) = He_{n-1}(x)/sqrt((n-1)!) by its recurrence
   P_k = (x P_{k-1} - sqrt(k-1) P_{k-2}) / sqrt(k); the Gauss weight is 1/(n P_{n-1}(x)^2). */
PF_CPU_DEF pf_real pfi_gg_orthonormal_he(int m, pf_real x)
{
    pf_real p0 = PF_R(1.0), p1 = x, p2;
    int k;
    if (m == 0) return p0;
    for (k = 2; k <= m; ++k) {
        p2 = (x * p1 - PF_SQRT(PF_R(k - 1)) * p0) / PF_SQRT(PF_R(k));
        p0 = p1;
        p1 = p2;
    }
    return p1;
}

/* pf_gg_hermite_generate(n, nodes, weights): the n-point Gauss-Hermite rule of a standard
   normal (probabilists' weight exp(-x^2/2), weights normalized to sum 1), nodes ascending and
   exactly symmetric, written to the caller's arrays of n entries (nodes and weights each hold
   n reals: at most 64, so no size arithmetic can overflow). It returns a count, as pf_core.h's
   policy has counts do: n on success; 0, with both arrays untouched (nothing read or
   written), for every argument it rejects: n < 1 or n > PF_GG_GENERATE_MAX (64; INT_MIN and
   INT_MAX included) or a NULL nodes or weights. It never returns PF_ERR_* codes.
   Method: each zero of He_n by bisection on the Sturm count of the Jacobi matrix (no
   initial guesses needed, every root bracketed), weights 1/(n P_{n-1}^2) formed as
   (1/(sqrt(n) P_{n-1}))^2 so that large n cannot overflow (far weights underflow to 0, where
   the true weight is below the smallest pf_real anyway). Cost ~ n^2 x 100 operations. */
PF_CPU_DEF int pf_gg_hermite_generate(int n, pf_real *nodes, pf_real *weights)
{
    int i, it;
    pf_real bound, s = PF_R(0.0);
    if (n < 1 || n > PF_GG_GENERATE_MAX || !nodes || !weights) return 0;
    bound = PF_R(2.0) * PF_SQRT(PF_R(n)) + PF_R(1.0); /* Gershgorin */
    for (i = n / 2; i < n; ++i) {                      /* the non-negative half */
        pf_real lo = PF_R(0.0), hi = bound, mid, u;
        if (2 * i + 1 == n) {
            lo = hi = PF_R(0.0); /* odd n: the middle zero is 0 */
        } else {
            for (it = 0; it < 200; ++it) {
                mid = PF_R(0.5) * (lo + hi);
                if (!(mid > lo && mid < hi)) break; /* bracket down to adjacent numbers */
                if (pfi_gg_sturm_count(n, mid) > i) hi = mid;
                else lo = mid;
            }
        }
        mid = PF_R(0.5) * (lo + hi);
        nodes[i] = mid;
        nodes[n - 1 - i] = -mid;
        u = PF_R(1.0) / (PF_SQRT(PF_R(n)) * pfi_gg_orthonormal_he(n - 1, mid));
        weights[i] = u * u;
        weights[n - 1 - i] = u * u;
    }
    for (i = 0; i < n; ++i) s += weights[i];
    for (i = 0; i < n; ++i) weights[i] /= s;
    return n;
}
#endif /* !PF_GLSL */

#endif /* PF_GAUSSGRID_H */

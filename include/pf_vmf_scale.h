/* pf_vmf_scale.h - CPU baking of the scaling function of Wu et al. 2019 (eqs. 6-8, 12-14,
   21-24) that corrects the multi-lobe BRDF of a lobe pyramid (pf_vmf_fit.h) toward the height
   field's effective BRDF: the effective BRDF of a patch, the per-patch samples, the
   factorization into T (per texel) and S (a table over directions), its lookup, and the calls
   that fit one pyramid level from a description. pf_vmf.h holds the shader side (coordinates,
   trilinear read, apply); the height stencil and the march are pf_map.h's. CPU only
   (PF_CPU_DEF: caller-owned buffers, no allocation); empty under PF_GLSL.

   USAGE
     pf_vmf_scale_desc d = {0}; d.heights = hm; ...; pf_vmf_scale_fit_level(&d, level, ...);

   FUNCTIONS
     scaling     pf_vmf_scale_fit_level, pf_vmf_scale_texel_t, pf_vmf_scale_scratch_size
                 (struct pf_vmf_scale_desc), pf_vmf_effective_brdf, pf_vmf_scale_lookup,
                 pf_vmf_scale_cell_count, pf_vmf_scale_sample_count, pf_vmf_scale_vis_bytes

   ACCURACY AND COST (tests/test_vmf_scale.c, bench/bench_vmf.c, bench/microsurface.c;
   docs/vmf_scale.md).

   SOURCES
     Wu, Zhao, Yan, Ramamoorthi 2019 eqs. 6-8, 12-14, 21-24. */
#ifndef PF_VMF_SCALE_H
#define PF_VMF_SCALE_H

#ifndef PF_GLSL
#  include "pf_vmf_fit.h"
#  include "pf_map.h"

/* ================================================================ SCALING FUNCTION
   (Wu et al. 2019 eqs. 6-8, 12-14, sec. 6 eqs. 21-24; interreflections, sec. 5, not modelled).
   EFFECTIVE BRDF (eqs. 6-8, single bounce) of an n x n patch of a periodic height map
   heights[y w + x] (world units, `texel` world units between nodes), texels (x0 + i, y0 + j)
   wrapping: every texel is a facet of its central-difference slope s_t (pf_map_node_slope)
   shaded by the base BRDF pf_vmf_facet_specular (a Beckmann lobe of deviation base_sigma
   about s_t, Schlick Fresnel, its own Smith G2), kept when the node sees both wo and wi:
       f_eff = sum_t V_t(wo) V_t(wi) F D_t(h) G2_t / 4  /  sum_t a_t(wo),   a_t(w) = w.z - s_t.w.xy
   (eq. 8: the patch's projected area toward wo is that of its mean plane; radiance toward wo
   per unit radiance from wi, light cosine included, like pf_vmf_sum_specular).
   VISIBILITY: pf_map_visible (pf_map.h), the height-field march restricted to the patch.
   RATIO AND FACTORIZATION (eqs. 12, 14, 21-24): R(x, wi, wo) = f_eff / f_lobes with f_lobes the
   multi-lobe BRDF of eq. 5 for the patch's fitted lobes (pf_vmf_fit_normals on the patch's
   normals, slope form pf_vmf_sum_add with base_var = base_sigma^2), masking per `masking`:
   PF_VMF_SCALE_UNMASKED (eq. 5 as written: R carries all the masking-shadowing),
   PF_VMF_SCALE_G_GAUSSIAN (pf_vmf_sum_specular), PF_VMF_SCALE_G_MIXTURE
   (pf_vmf_sum_specular_mixture). Samples per patch (pfi_vmf_scale_patch): one direction set,
   the nt theta nodes times A = 2 (np - 1) azimuths a pi/(np - 1), and every (wo, wi) pair of
   it: phi_d falls on the np phi_d nodes exactly, each node gets A (ends) or 2 A (inner)
   samples per patch and theta pair, and the mirror pairs are among them (a narrow highlight
   is sampled at its peak). Sample order ((k_to A + a_o) nt + k_ti) A + a_i.
   T and S (pfi_vmf_scale_factor): the rank-1 fit of eq. 21 minimizing the error IN BRDF UNITS,
   sum_{x, samples} (f_eff - T(x) S(cell) f_lobes)^2, by alternating least squares (T(x) =
   sum f_eff f_lobes S / sum (f_lobes S)^2 over the patch's samples, S likewise over the
   patches), then T scaled to mean 1 (Wu et al. sec. 7). Not eqs. 22-24's plain means of R:
   where the lobes put almost no energy R is a ratio of two tiny numbers, which a plain mean
   weights as much as the highlight; the fit in BRDF units weights them by their energy and is
   still exact for a separable R. Cells or patches without energy get 1.
   REGULARIZATION: a patch whose highlight falls between the node directions, or a cell only
   the lobes' far tails reach (f_eff exactly 0 there), is decided by a few tiny samples:
   unregularized, S has cells of exactly 0 at every level of the bench's maps and T ranges
   0.13-10.8 at 64-256 texels. So each T and S is the least-squares value with a prior toward
   1 of weight `shrink` times the mean energy sum (S f_lobes)^2 of a patch (for T) or
   sum (T f_lobes)^2 of a cell (for S): well-sampled values keep their fit, poor ones stay near
   1. */
#define PF_VMF_SCALE_G_GAUSSIAN 1
#define PF_VMF_SCALE_G_MIXTURE 2
#define PF_VMF_SCALE_UNMASKED 3

/* argument and size checks shared by the scaling functions (no data read) */
PF_CPU_DEF int pfi_vmf_patch_sizes(const pf_real *hm, int w, int h, pf_real texel, long long n)
{
    if (!hm || n < 1 || w < 1 || h < 1 || !(texel > PF_R(0.0)) || !(texel < PF_REAL_MAX)) return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || pf_size_mul(w, h) < 0) return PF_ERR_SIZE;
    if (n > w || n > h) return PF_ERR_ARG;
    return PF_OK;
}

/* after every size check: finite heights in the patch and its ring, *top the highest */
PF_CPU_DEF int pfi_vmf_patch_top(const pf_real *hm, int w, int h, long long x0, long long y0, long long n, pf_real *top)
{
    long long i, j;
    pf_real hi = -PF_REAL_MAX;
    for (j = -1; j <= n; ++j)
        for (i = -1; i <= n; ++i) {
            pf_real v = pf_map_height(hm, w, h, x0 + i, y0 + j);
            if (!(PF_FABS(v) < PF_R(0.25) * PF_REAL_MAX)) return PF_ERR_ARG; /* NaN, inf */
            hi = pf_max(hi, v);
        }
    *top = hi;
    return PF_OK;
}

/* f_eff over the patch, visibility marched (vis_o NULL) or read from two n x n byte maps */
PF_CPU_DEF pf_real pfi_vmf_effective(const pf_real *hm, int w, int h, pf_real texel, long long x0, long long y0,
                                     long long n, pf_vec3 wo, pf_vec3 wi, pf_real base_var, pf_real f0, pf_real top,
                                     const unsigned char *vis_o, const unsigned char *vis_i)
{
    pf_real num = PF_R(0.0), area = PF_R(0.0), sx, sy;
    long long i, j;
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            long long x = x0 + i, y = y0 + j;
            pf_real term;
            pf_map_node_slope(hm, w, h, texel, x, y, &sx, &sy);
            area += wo.z - sx * wo.x - sy * wo.y;
            if (vis_o && (!vis_o[j * n + i] || !vis_i[j * n + i])) continue;
            term = pf_vmf_facet_specular(sx, sy, base_var, wo, wi, f0);
            if (!(term > PF_R(0.0))) continue;
            if (!vis_o && (!pf_map_visible(hm, w, h, texel, x, y, wo, x0, y0, n, top) ||
                           !pf_map_visible(hm, w, h, texel, x, y, wi, x0, y0, n, top)))
                continue;
            num += term;
        }
    return area > PF_R(0.0) ? num / area : PF_R(0.0);
}

/* The single-bounce effective BRDF of the n x n patch from (x0, y0) (Wu et al. 2019 eqs. 6-8;
   see the block comment) toward wo from wi (unit, tangent frame) into *out; 0 when either
   direction is on or below the macrosurface or the patch's mean plane faces away.
   Errors (*out set to 0 when out is not NULL): PF_ERR_ARG for NULL heights or out, n, w or h
   below 1, n > w or n > h, texel or base_sigma not finite and > 0, a height in the patch or
   its one-texel ring that is not finite or of magnitude PF_REAL_MAX / 4 or more; PF_ERR_SIZE
   for w or h above PF_MAX_SIDE or w h > PF_MAX_REALS.
   Cost: 2 n^2 marches of at most 2 n + 1 cells each (n along each axis, periodic maps
   included). Reads only heights[0 .. w h). Accepted heights: finite with |height| below
   PF_REAL_MAX / 4 (the bound keeps every central difference finite); larger ones are the
   PF_ERR_ARG of a non-finite height. */
PF_CPU_DEF int pfi_vmf_effective_brdf(const pf_real *heights, int w, int h, pf_real texel, int x0, int y0, int n,
                                     pf_vec3 wo, pf_vec3 wi, pf_real base_sigma, pf_real f0, pf_real *out)
{
    pf_real top = PF_R(0.0);
    int rc;
    if (!out) return PF_ERR_ARG;
    *out = PF_R(0.0);
    if (!(base_sigma > PF_R(0.0)) || !(base_sigma < PF_R(1.0e15))) return PF_ERR_ARG;
    rc = pfi_vmf_patch_sizes(heights, w, h, texel, n);
    if (rc == PF_OK) rc = pfi_vmf_patch_top(heights, w, h, x0, y0, n, &top);
    if (rc != PF_OK) return rc;
    if (!(wo.z > PF_R(0.0)) || !(wi.z > PF_R(0.0))) return PF_OK;
    *out = pfi_vmf_effective(heights, w, h, texel, x0, y0, n, wo, wi, base_sigma * base_sigma, f0, top, 0, 0);
    return PF_OK;
}

/* samples per patch, (2 nt (np - 1))^2 (every pair of nt thetas times 2 (np - 1) azimuths);
   0 for nt or np below 2 or above PF_MAX_SIDE, or a count above PF_MAX_REALS */
PF_CPU_DEF long long pf_vmf_scale_sample_count(int nt, int np)
{
    long long d;
    if (nt < 2 || np < 2 || !pf_size_side_ok(nt) || !pf_size_side_ok(np)) return 0;
    d = pf_size_mul3(2, nt, np - 1);
    d = d < 0 ? -1 : pf_size_mul(d, d);
    return d < 0 ? 0 : d;
}

/* nodes (cells) of S: nt nt np (0 for nt or np below 2 or above PF_MAX_SIDE, or nt nt np
   above PF_MAX_REALS) */
PF_CPU_DEF long long pf_vmf_scale_cell_count(int nt, int np)
{
    long long c = (nt < 2 || np < 2 || !pf_size_side_ok(nt) || !pf_size_side_ok(np)) ? -1 : pf_size_mul3(nt, nt, np);
    return c < 0 ? 0 : c;
}

/* visibility bytes of one n x n patch: 2 nt (np - 1) n^2 (a map per direction); 0 for bad sizes */
PF_CPU_DEF long long pf_vmf_scale_vis_bytes(int nt, int np, int n)
{
    long long d = (nt < 2 || np < 2 || n < 1 || !pf_size_side_ok(nt) || !pf_size_side_ok(np) || !pf_size_side_ok(n))
                      ? -1
                      : pf_size_mul3(2, nt, np - 1);
    d = d < 0 ? -1 : pf_size_mul3(d, n, n);
    return d < 0 ? 0 : d;
}

/* the sample directions: theta node it, azimuth a pi / (np - 1) */
PF_CPU_DEF pf_vec3 pfi_vmf_scale_dir(int it, int k, int nt, int np, pf_real theta_max)
{
    pf_real th = (pf_real)it * theta_max / (pf_real)(nt - 1);
    pf_real ph = (pf_real)k * PF_PI / (pf_real)(np - 1);
    return pf_vec3_make(PF_SIN(th) * PF_COS(ph), PF_SIN(th) * PF_SIN(ph), PF_COS(th));
}

/* S cell of sample s (sample order in the block comment) */
PF_CPU_DEF long long pfi_vmf_scale_cell(long long s, int nt, int np)
{
    long long A = 2LL * (np - 1), ai = s % A, ti = (s / A) % nt, ao = (s / (A * nt)) % A, to = s / (A * nt * A);
    long long d = pf_map_wrap(ai - ao, A), k = d <= np - 1 ? d : A - d;
    return (ti * nt + to) * np + k;
}

/* One patch's samples (block comment): for every sample s, f_eff[s] (eqs. 6-8) and f_lobes[s]
   (eq. 5 with the patch's `lobes` fitted lobes, EM budget `iterations`, masking
   PF_VMF_SCALE_*). Thetas k theta_max / (nt - 1), theta_max in (0, pi/2). Buffers:
   normals_scratch 3 n^2 pf_reals, vis_scratch pf_vmf_scale_vis_bytes(nt, np, n) bytes, f_eff
   and f_lobes pf_vmf_scale_sample_count(nt, np) pf_reals each; nothing else is written.
   Errors: those of pfi_vmf_effective_brdf; PF_ERR_ARG for a NULL buffer, lobes outside [1, 16],
   iterations < 0, nt or np < 2, theta_max outside (0, pi/2), an unknown masking, a failed fit;
   PF_ERR_SIZE for a buffer above PF_MAX_REALS (sizes checked before any height is read).
   Cost: 2 nt (np - 1) n^2 marches, up to (2 nt (np - 1))^2 n^2 base lobes. */
PF_CPU_DEF int pfi_vmf_scale_patch(const pf_real *heights, int w, int h, pf_real texel, int x0, int y0, int n, int lobes,
                                  int iterations, pf_real base_sigma, pf_real f0, int masking, int nt, int np,
                                  pf_real theta_max, pf_real *normals_scratch, unsigned char *vis_scratch,
                                  pf_real *f_eff, pf_real *f_lobes)
{
    pf_real top = PF_R(0.0), bv;
    pf_vmf_mixture mix;
    long long nn, dirs, count, A, s, i, j;
    int rc, d;
    if (!normals_scratch || !vis_scratch || !f_eff || !f_lobes || lobes < 1 || lobes > PF_VMF_MAX_LOBES ||
        iterations < 0 || nt < 2 || np < 2 || !(theta_max > PF_R(0.0)) || !(theta_max < PF_R(0.5) * PF_PI) ||
        masking < PF_VMF_SCALE_G_GAUSSIAN || masking > PF_VMF_SCALE_UNMASKED)
        return PF_ERR_ARG;
    if (!(base_sigma > PF_R(0.0)) || !(base_sigma < PF_R(1.0e15))) return PF_ERR_ARG;
    rc = pfi_vmf_patch_sizes(heights, w, h, texel, n);
    if (rc != PF_OK) return rc;
    nn = (long long)n * n;
    count = pf_vmf_scale_sample_count(nt, np);
    if (count == 0 || pf_vmf_scale_vis_bytes(nt, np, n) == 0 || pf_size_mul(nn, 3) < 0) return PF_ERR_SIZE;
    rc = pfi_vmf_patch_top(heights, w, h, x0, y0, n, &top); /* reads data: after every size check */
    if (rc != PF_OK) return rc;
    A = 2LL * (np - 1);
    dirs = nt * A;
    bv = base_sigma * base_sigma;
    /* the patch's normals and its lobes */
    for (j = 0; j < n; ++j)
        for (i = 0; i < n; ++i) {
            /* (-dx, -dy, 2 texel), the normal of the central differences without dividing by
               the texel (no overflow for a tiny texel); the fit normalizes it */
            pf_real dx = pf_map_height(heights, w, h, x0 + i + 1, y0 + j) - pf_map_height(heights, w, h, x0 + i - 1, y0 + j);
            pf_real dy = pf_map_height(heights, w, h, x0 + i, y0 + j + 1) - pf_map_height(heights, w, h, x0 + i, y0 + j - 1);
            pf_real m = pf_max(pf_max(PF_FABS(dx), PF_FABS(dy)), PF_R(2.0) * texel);
            normals_scratch[3 * (j * n + i)] = -dx / m;
            normals_scratch[3 * (j * n + i) + 1] = -dy / m;
            normals_scratch[3 * (j * n + i) + 2] = PF_R(2.0) * texel / m;
        }
    if (pf_vmf_fit_normals(normals_scratch, 0, nn, lobes, iterations, &mix) != PF_OK) return PF_ERR_ARG;
    /* one visibility map per direction of the set */
    for (d = 0; d < dirs; ++d) {
        pf_vec3 dir = pfi_vmf_scale_dir((int)(d / A), (int)(d % A), nt, np, theta_max);
        unsigned char *vm = vis_scratch + d * nn;
        for (j = 0; j < n; ++j)
            for (i = 0; i < n; ++i)
                vm[j * n + i] = (unsigned char)pf_map_visible(heights, w, h, texel, x0 + i, y0 + j, dir, x0, y0, n, top);
    }
    for (s = 0; s < count; ++s) {
        long long ai = s % A, ti = (s / A) % nt, ao = (s / (A * nt)) % A, to = s / (A * nt * A);
        pf_vec3 wo = pfi_vmf_scale_dir((int)to, (int)ao, nt, np, theta_max);
        pf_vec3 wi = pfi_vmf_scale_dir((int)ti, (int)ai, nt, np, theta_max);
        pf_vmf_sum sum = pf_vmf_sum_zero();
        int k;
        f_eff[s] = pfi_vmf_effective(heights, w, h, texel, x0, y0, n, wo, wi, bv, f0, top,
                                     vis_scratch + (to * A + ao) * nn, vis_scratch + (ti * A + ai) * nn);
        for (k = 0; k < mix.count; ++k) {
            sum = pf_vmf_sum_add(sum, mix.lobe[k], wo, wi, bv);
            if (masking == PF_VMF_SCALE_G_MIXTURE) sum = pf_vmf_sum_add_masking(sum, mix.lobe[k], wo, wi, bv);
        }
        f_lobes[s] = masking == PF_VMF_SCALE_UNMASKED    ? pf_vmf_sum_specular_unmasked(sum, wo, wi, f0)
                     : masking == PF_VMF_SCALE_G_GAUSSIAN ? pf_vmf_sum_specular(sum, wo, wi, f0)
                                                          : pf_vmf_sum_specular_mixture(sum, wo, wi, f0);
    }
    return PF_OK;
}

/* a power of two c with max(e, l) c in [0.5, 2) over the finite positive samples of f_eff and
   f_lobes (n of each; 1 when there are none): the fits below run on c e and c l, which leaves
   T, S and every ratio unchanged (exact scaling) while no product e l or l^2 of a set near
   PF_REAL_MAX overflows or of a set near PF_REAL_MIN underflows; c stays finite (below 2^102
   in float, 2^969 in double), so a subnormal set is only scaled toward 1 */
PF_CPU_DEF pf_real pfi_vmf_sample_scale(const pf_real *f_eff, const pf_real *f_lobes, long long n)
{
    pf_real m = PF_R(0.0), c = PF_R(1.0);
    long long s;
    for (s = 0; s < n; ++s) {
        pf_real e = f_eff[s], l = f_lobes[s];
        if (e > PF_R(0.0) && e <= PF_REAL_MAX) m = pf_max(m, e);
        if (l > PF_R(0.0) && l <= PF_REAL_MAX) m = pf_max(m, l);
    }
    if (!(m > PF_R(0.0))) return c;
    while (m * c >= PF_R(2.0)) c *= PF_R(0.5);
    while (m * c < PF_R(0.5) && c < PF_R(0.125) * PF_REAL_MAX * PF_REAL_EPSILON) c *= PF_R(2.0);
    return c;
}

/* T (patches values) and S (pf_vmf_scale_cell_count(nt, np) values) from the samples of
   `patches` patches (f_eff and f_lobes: patches * pf_vmf_scale_sample_count(nt, np) pf_reals,
   patch after patch, as pfi_vmf_scale_patch writes them): the rank-1 least-squares fit in BRDF
   units by `iterations` (>= 1) alternating rounds, T scaled to mean 1 (block comment), each
   value pulled toward 1 by a prior of weight `shrink` (>= 0; 0: plain least squares) times
   the mean energy of a patch (T) resp. a cell (S): T(x) = (sum e l S + p) / (sum (l S)^2 + p)
   (REGULARIZATION in the block comment). prior_out (NULL or 1 pf_real): the prior p to pass to
   pfi_vmf_scale_t for other patches of the same level (shrink times the mean patch energy under
   the final S). scratch: 2 * patches * cells pf_reals. err (NULL or 3 pf_reals): [0] the relative L2 error
   of T S f_lobes against f_eff over all samples (what the factorization leaves), [1] the same
   for f_lobes alone (T = S = 1: the unscaled multi-lobe BRDF), [2] the relative L2 error of
   T S against R = f_eff / f_lobes over the samples where f_lobes exceeds 1% of its RMS (R is
   not defined where f_lobes vanishes). Non-finite or negative samples count as 0.
   Errors: PF_ERR_ARG for a NULL buffer, patches < 1, nt or np < 2, iterations < 1, shrink
   outside [0, 1e6] or NaN; PF_ERR_SIZE when a size exceeds PF_MAX_REALS. */
PF_CPU_DEF int pfi_vmf_scale_factor(const pf_real *f_eff, const pf_real *f_lobes, int patches, int nt, int np,
                                   int iterations, pf_real shrink, pf_real *t_out, pf_real *s_out, pf_real *scratch,
                                   pf_real *prior_out, pf_real *err)
{
    long long cells, count, x, b, s;
    pf_real *num, *den, mean, cs;
    int it;
    if (!f_eff || !f_lobes || !t_out || !s_out || !scratch || patches < 1 || nt < 2 || np < 2 || iterations < 1 ||
        !(shrink >= PF_R(0.0)) || !(shrink <= PF_R(1.0e6)))
        return PF_ERR_ARG;
    cells = pf_vmf_scale_cell_count(nt, np);
    count = pf_vmf_scale_sample_count(nt, np);
    if (cells == 0 || count == 0 || pf_size_mul(count, patches) < 0 || pf_size_mul3(cells, patches, 2) < 0)
        return PF_ERR_SIZE;
    num = scratch;
    den = scratch + cells * patches;
    for (b = 0; b < cells * patches; ++b) num[b] = den[b] = PF_R(0.0);
    /* every sum below runs on the samples times one power of two cs (exact; T and S do not
       change): sample sets near PF_REAL_MAX or PF_REAL_MIN are fitted, not overflowed */
    cs = pfi_vmf_sample_scale(f_eff, f_lobes, count * patches);
    /* per (patch, cell): sum f_eff f_lobes and sum f_lobes^2 (the normal equations) */
    for (x = 0; x < patches; ++x)
        for (s = 0; s < count; ++s) {
            pf_real e = f_eff[x * count + s], l = f_lobes[x * count + s];
            long long c = x * cells + pfi_vmf_scale_cell(s, nt, np);
            e = e > PF_R(0.0) && e <= PF_REAL_MAX ? e * cs : PF_R(0.0);
            l = l > PF_R(0.0) && l <= PF_REAL_MAX ? l * cs : PF_R(0.0);
            num[c] += e * l;
            den[c] += l * l;
        }
    for (b = 0; b < cells; ++b) s_out[b] = PF_R(1.0);
    for (x = 0; x < patches; ++x) t_out[x] = PF_R(1.0);
    for (it = 0; it < iterations; ++it) {
        /* T step: each patch's energy q first (kept in t_out, which this step overwrites),
           the prior's weight `shrink` times their mean, then T from q and sum e l S */
        pf_real prior = PF_R(0.0);
        for (x = 0; x < patches; ++x) {
            pf_real q = PF_R(0.0);
            for (b = 0; b < cells; ++b) q += den[x * cells + b] * s_out[b] * s_out[b];
            t_out[x] = q;
            prior += q;
        }
        prior = shrink * prior / (pf_real)patches;
        prior = prior < PF_REAL_MAX ? prior : PF_R(0.0); /* overflowed energies: no prior */
        for (x = 0; x < patches; ++x) {
            pf_real a = PF_R(0.0);
            for (b = 0; b < cells; ++b) a += num[x * cells + b] * s_out[b];
            a = (a + prior) / (t_out[x] + prior);
            t_out[x] = a < PF_REAL_MAX ? a : PF_R(1.0); /* no energy and no prior (NaN), overflow */
        }
        /* S step: likewise with each cell's energy (kept in s_out) and their mean */
        prior = PF_R(0.0);
        for (b = 0; b < cells; ++b) {
            pf_real q = PF_R(0.0);
            for (x = 0; x < patches; ++x) q += den[x * cells + b] * t_out[x] * t_out[x];
            s_out[b] = q;
            prior += q;
        }
        prior = shrink * prior / (pf_real)cells;
        prior = prior < PF_REAL_MAX ? prior : PF_R(0.0);
        for (b = 0; b < cells; ++b) {
            pf_real a = PF_R(0.0);
            for (x = 0; x < patches; ++x) a += num[x * cells + b] * t_out[x];
            a = (a + prior) / (s_out[b] + prior);
            s_out[b] = a < PF_REAL_MAX ? a : PF_R(1.0);
        }
    }
    mean = PF_R(0.0);
    for (x = 0; x < patches; ++x) mean += t_out[x] / (pf_real)patches; /* each <= PF_REAL_MAX: no overflow */
    if (mean > PF_R(0.0) && mean <= PF_REAL_MAX) {
        for (x = 0; x < patches; ++x) t_out[x] /= mean;
        for (b = 0; b < cells; ++b) {
            pf_real v = s_out[b] * mean;
            s_out[b] = v <= PF_REAL_MAX ? v : PF_REAL_MAX;
        }
    }
    /* the prior for pfi_vmf_scale_t on other patches of the same level: shrink times the mean
       patch energy sum_s (S f_lobes)^2 under the final S */
    if (prior_out) {
        pf_real e_sum = PF_R(0.0);
        for (x = 0; x < patches; ++x)
            for (b = 0; b < cells; ++b) e_sum += den[x * cells + b] * s_out[b] * s_out[b];
        /* back to the samples' own units: divided by cs^2 (one cs at a time) */
        e_sum = shrink * e_sum / (pf_real)patches / cs / cs;
        *prior_out = e_sum < PF_REAL_MAX ? e_sum : PF_R(0.0);
    }
    if (err) {
        /* every term on the scaled samples (cs e, cs l) and the ratios R and T S divided by
           their largest value rm first: each squared term is at most 4, so no sum overflows
           and no error is inf / inf (NaN); a product T S l beyond PF_REAL_MAX is read as
           PF_REAL_MAX */
        pf_real e0 = PF_R(0.0), e1 = PF_R(0.0), ref = PF_R(0.0), l2 = PF_R(0.0), r0 = PF_R(0.0), rr = PF_R(0.0), floor_l;
        pf_real em = PF_R(0.0), rm = PF_R(0.0);
        for (x = 0; x < patches; ++x)
            for (s = 0; s < count; ++s) {
                pf_real e = f_eff[x * count + s], l = f_lobes[x * count + s];
                pf_real ts = t_out[x] * s_out[pfi_vmf_scale_cell(s, nt, np)], tl;
                e = e > PF_R(0.0) && e <= PF_REAL_MAX ? e * cs : PF_R(0.0);
                l = l > PF_R(0.0) && l <= PF_REAL_MAX ? l * cs : PF_R(0.0);
                tl = ts * l;
                em = pf_max(em, pf_max(pf_max(e, l), tl <= PF_REAL_MAX ? tl : PF_REAL_MAX));
                l2 += l * l;
            }
        em = em > PF_R(0.0) ? em : PF_R(1.0);
        floor_l = PF_R(0.01) * PF_SQRT(l2 / (pf_real)(count * patches));
        for (x = 0; x < patches; ++x)
            for (s = 0; s < count; ++s) {
                pf_real e = f_eff[x * count + s], l = f_lobes[x * count + s];
                pf_real ts = t_out[x] * s_out[pfi_vmf_scale_cell(s, nt, np)], tl;
                e = e > PF_R(0.0) && e <= PF_REAL_MAX ? e * cs : PF_R(0.0);
                l = l > PF_R(0.0) && l <= PF_REAL_MAX ? l * cs : PF_R(0.0);
                tl = ts * l;
                tl = (tl <= PF_REAL_MAX ? tl : PF_REAL_MAX) / em;
                e /= em;
                l /= em;
                e0 += (e - tl) * (e - tl);
                e1 += (e - l) * (e - l);
                ref += e * e;
                if (l * em > floor_l) {
                    pf_real R = e / l;
                    R = R <= PF_REAL_MAX ? R : PF_REAL_MAX;
                    rm = pf_max(rm, pf_max(R, ts <= PF_REAL_MAX ? ts : PF_REAL_MAX));
                }
            }
        rm = rm > PF_R(0.0) ? rm : PF_R(1.0);
        for (x = 0; x < patches; ++x)
            for (s = 0; s < count; ++s) {
                pf_real e = f_eff[x * count + s], l = f_lobes[x * count + s], R;
                pf_real ts = t_out[x] * s_out[pfi_vmf_scale_cell(s, nt, np)];
                e = e > PF_R(0.0) && e <= PF_REAL_MAX ? e * cs : PF_R(0.0);
                l = l > PF_R(0.0) && l <= PF_REAL_MAX ? l * cs : PF_R(0.0);
                if (!(l > floor_l)) continue;
                R = e / l;
                R = (R <= PF_REAL_MAX ? R : PF_REAL_MAX) / rm;
                ts = (ts <= PF_REAL_MAX ? ts : PF_REAL_MAX) / rm;
                r0 += (R - ts) * (R - ts);
                rr += R * R;
            }
        err[0] = ref > PF_R(0.0) ? PF_SQRT(e0 / ref) : PF_R(0.0);
        err[1] = ref > PF_R(0.0) ? PF_SQRT(e1 / ref) : PF_R(0.0);
        err[2] = rr > PF_R(0.0) ? PF_SQRT(r0 / rr) : PF_R(0.0);
        /* a ratio of two sums that underflowed to subnormals is still finite; anything else
           (only possible under -ffast-math) reads as 0 */
        for (b = 0; b < 3; ++b) err[b] = err[b] >= PF_R(0.0) && err[b] <= PF_REAL_MAX ? err[b] : PF_R(0.0);
    }
    return PF_OK;
}

/* T of one patch from its own samples (as pfi_vmf_scale_patch writes them) given a level's S
   and prior (pfi_vmf_scale_factor's): (sum e l S + prior) / (sum (l S)^2 + prior); non-finite
   or negative samples count as 0. 1 for a NULL buffer, bad sizes, a negative or NaN prior, no
   energy and no prior, or sums that overflow. */
PF_CPU_DEF pf_real pfi_vmf_scale_t(const pf_real *f_eff, const pf_real *f_lobes, int nt, int np, const pf_real *s_table,
                                  pf_real prior)
{
    long long count = pf_vmf_scale_sample_count(nt, np), s;
    pf_real a = PF_R(0.0), q = PF_R(0.0), cs;
    if (!f_eff || !f_lobes || !s_table || count == 0 || pf_vmf_scale_cell_count(nt, np) == 0 || !(prior >= PF_R(0.0)))
        return PF_R(1.0);
    /* the samples times a power of two (pfi_vmf_sample_scale), the prior times its square */
    cs = pfi_vmf_sample_scale(f_eff, f_lobes, count);
    for (s = 0; s < count; ++s) {
        pf_real e = f_eff[s], l = f_lobes[s];
        e = e > PF_R(0.0) && e <= PF_REAL_MAX ? e * cs : PF_R(0.0);
        l = l > PF_R(0.0) && l <= PF_REAL_MAX ? (l * cs) * s_table[pfi_vmf_scale_cell(s, nt, np)] : PF_R(0.0);
        a += e * l;
        q += l * l;
    }
    prior = (prior * cs) * cs;
    a = (a + prior) / (q + prior);
    return a < PF_REAL_MAX ? a : PF_R(1.0); /* NaN (no energy, no prior) and overflow too */
}

/* S at (wo, wi) from the table, as a shader reads it (pf_vmf_scale_coords, _texel_pos, 8 reads,
   pf_vmf_scale_trilinear). NULL table or bad sizes: 1 (no scaling). */
PF_CPU_DEF pf_real pf_vmf_scale_lookup(const pf_real *table, int nt, int np, pf_real theta_max, pf_vec3 wo, pf_vec3 wi)
{
    pf_vec3 c, f;
    pf_real p0, p1, p2;
    long long a0, a1, b0, b1, c0, c1;
    if (!table || pf_vmf_scale_cell_count(nt, np) == 0) return PF_R(1.0);
    c = pf_vmf_scale_coords(wo, wi, theta_max);
    p0 = pf_vmf_scale_texel_pos(c.x, nt);
    p1 = pf_vmf_scale_texel_pos(c.y, nt);
    p2 = pf_vmf_scale_texel_pos(c.z, np);
    /* node indices clamped in pf_real before the conversion: a position that rounds past the
       last node (or any NaN) cannot address outside the nt nt np table */
    a0 = pf_floor_index(p0, 0, nt - 1);
    b0 = pf_floor_index(p1, 0, nt - 1);
    c0 = pf_floor_index(p2, 0, np - 1);
    a1 = a0 + 1 < nt ? a0 + 1 : a0;
    b1 = b0 + 1 < nt ? b0 + 1 : b0;
    c1 = c0 + 1 < np ? c0 + 1 : c0;
    f = pf_vec3_make(pf_clamp_nan_lo(p0 - (pf_real)a0, PF_R(0.0), PF_R(1.0)),
                     pf_clamp_nan_lo(p1 - (pf_real)b0, PF_R(0.0), PF_R(1.0)),
                     pf_clamp_nan_lo(p2 - (pf_real)c0, PF_R(0.0), PF_R(1.0)));
#define PFI_VMF_S(a, b, c) table[((a) * nt + (b)) * np + (c)]
    return pf_vmf_scale_trilinear(PFI_VMF_S(a0, b0, c0), PFI_VMF_S(a1, b0, c0), PFI_VMF_S(a0, b1, c0),
                                  PFI_VMF_S(a1, b1, c0), PFI_VMF_S(a0, b0, c1), PFI_VMF_S(a1, b0, c1),
                                  PFI_VMF_S(a0, b1, c1), PFI_VMF_S(a1, b1, c1), f);
#undef PFI_VMF_S
}
/* ================================================================ end of SCALING FUNCTION */

/* ================================================================ the scaling function of a lobe
   pyramid, one call per level (Wu et al. 2019 eqs. 12-14, 21-24)
   Per level l of a lobe pyramid (patches of n = 2^l texels, one per texel of level l): S, one
   nt x nt x np node table (pf_vmf_scale_lookup; pf_vmf_scale_coords and _trilinear in a
   shader), and T, one value per texel. Both come from the samples of the block comment above:
   f_eff (pfi_vmf_scale_patch) against f_lobes, the pyramid texel's OWN lobes (what a shader
   fetches, base_var = base_sigma^2, masked per `masking`). S and a prior are fitted on
   `train_patches` patches evenly spaced over the level (texel p w_l h_l / P, p < P, row-major),
   T of any other texel from its own samples (pf_vmf_scale_texel_t). The pyramids of one map
   (different lobe counts) are fitted in one call: they share f_eff, the costly half.
   pf_vmf_scale_desc describes the call: ZERO MEANS THE DEFAULT. */
#define PF_VMF_SCALE_MAX_PYRAMIDS 4

typedef struct pf_vmf_scale_desc {
    const pf_real *heights;  /* the periodic height map, w x h row-major, world units (required) */
    int w, h;                /* its sides: powers of two, those of the lobe pyramids (required) */
    pf_real texel;           /* world units between height nodes (0: 1) */
    pf_real base_sigma;      /* slope deviation of the base Beckmann lobe, > 0 (0: 0.1) */
    pf_real f0;              /* Schlick f0 of the base BRDF (0: 1, no Fresnel) */
    int pyramid_count;       /* lobe pyramids fitted together, 1 .. PF_VMF_SCALE_MAX_PYRAMIDS (0: 1) */
    const pf_real *pyramid[PF_VMF_SCALE_MAX_PYRAMIDS]; /* pf_vmf_pyramid_from_normals of the map */
    int lobes[PF_VMF_SCALE_MAX_PYRAMIDS];              /* lobes per texel of each (required) */
    int masking;             /* f_lobes' G: PF_VMF_SCALE_G_GAUSSIAN (0 reads as it), _G_MIXTURE, _UNMASKED */
    int nt, np;              /* S's nodes along theta_i, theta_o and along phi_d, >= 2 (0: 6, 5) */
    pf_real theta_max;       /* the last theta node, in (0, pi/2) (0: 75 degrees) */
    int train_patches;       /* patches S is fitted on (0: 16) */
    int rounds;              /* alternating least-squares rounds (0: 8) */
    pf_real shrink;          /* the prior toward 1 (REGULARIZATION; 0: 1; negative: 0, plain LSQ) */
} pf_vmf_scale_desc;

/* the description with every default applied; 0 when d is NULL */
PF_CPU_DEF int pfi_vmf_scale_resolve(const pf_vmf_scale_desc *d, pf_vmf_scale_desc *r)
{
    if (!d) return 0;
    *r = *d;
    if (r->texel == PF_R(0.0)) r->texel = PF_R(1.0);
    if (r->base_sigma == PF_R(0.0)) r->base_sigma = PF_R(0.1);
    if (r->f0 == PF_R(0.0)) r->f0 = PF_R(1.0);
    if (r->pyramid_count == 0) r->pyramid_count = 1;
    if (r->masking == 0) r->masking = PF_VMF_SCALE_G_GAUSSIAN;
    if (r->nt == 0) r->nt = 6;
    if (r->np == 0) r->np = 5;
    if (r->theta_max == PF_R(0.0)) r->theta_max = PF_R(1.3089969389957472); /* 75 degrees */
    if (r->train_patches == 0) r->train_patches = 16;
    if (r->rounds == 0) r->rounds = 8;
    if (r->shrink == PF_R(0.0)) r->shrink = PF_R(1.0);
    else if (r->shrink < PF_R(0.0)) r->shrink = PF_R(0.0);
    return 1;
}

/* the checks every level call shares (no data read): PF_OK or the error */
PF_CPU_DEF int pfi_vmf_scale_check(const pf_vmf_scale_desc *r, int level)
{
    int k;
    if (!r->heights || r->pyramid_count < 1 || r->pyramid_count > PF_VMF_SCALE_MAX_PYRAMIDS || r->train_patches < 1 ||
        r->rounds < 1 || level < 0 || level > 30)
        return PF_ERR_ARG;
    for (k = 0; k < r->pyramid_count; ++k)
        if (!r->pyramid[k] || r->lobes[k] < 1 || r->lobes[k] > PF_VMF_MAX_LOBES) return PF_ERR_ARG;
    if (pf_vmf_pyramid_level_count(r->w, r->h) <= level) return PF_ERR_ARG; /* not powers of two, or no such level */
    if (pf_vmf_scale_sample_count(r->nt, r->np) == 0 || pf_vmf_scale_vis_bytes(r->nt, r->np, 1 << level) == 0)
        return r->nt < 2 || r->np < 2 ? PF_ERR_ARG : PF_ERR_SIZE;
    return PF_OK;
}

/* pf_reals of scratch the level calls need (the training patches' samples, the factorization,
   a patch's normals and visibility bytes); 0 for a call they reject or above PF_MAX_REALS. */
PF_CPU_DEF long long pf_vmf_scale_scratch_size(const pf_vmf_scale_desc *desc, int level)
{
    pf_vmf_scale_desc r;
    long long cnt, cells, n, gp, P, need, vis;
    if (!pfi_vmf_scale_resolve(desc, &r) || pfi_vmf_scale_check(&r, level) != PF_OK) return 0;
    cnt = pf_vmf_scale_sample_count(r.nt, r.np);
    cells = pf_vmf_scale_cell_count(r.nt, r.np);
    n = 1LL << level;
    gp = (long long)(r.w >> level) * (long long)(r.h >> level);
    P = gp < r.train_patches ? gp : r.train_patches;
    vis = (pf_vmf_scale_vis_bytes(r.nt, r.np, (int)n) + (long long)sizeof(pf_real) - 1) / (long long)sizeof(pf_real);
    /* f_eff and f_lobes of P patches, 2 P cells, T of P patches, normals, a junk f_lobes, vis */
    need = pf_size_mul3(P, cnt, 1 + r.pyramid_count);
    if (need < 0 || pf_size_mul3(2, P, cells) < 0 || pf_size_mul(3 * n, n) < 0) return 0;
    need += 2 * P * cells + P + 3 * n * n + cnt + vis;
    return need <= PF_MAX_REALS ? need : 0;
}

/* f_lobes of texel (tx, ty) of `level` of pyramid k for the patch's samples: the texel's lobes
   shaded at each sample's directions */
PF_CPU_DEF void pfi_vmf_scale_texel_lobes(const pf_vmf_scale_desc *r, int k, int level, long long tx, long long ty,
                                          pf_real *f_lobes)
{
    long long count = pf_vmf_scale_sample_count(r->nt, r->np), A = 2LL * (r->np - 1), s;
    long long lw = (r->w >> level) > 1 ? (r->w >> level) : 1;
    const pf_real *t = r->pyramid[k] + (pf_vmf_pyramid_level_offset(r->w, r->h, level) + ty * lw + tx) * 4 * r->lobes[k];
    pf_real bv = r->base_sigma * r->base_sigma;
    for (s = 0; s < count; ++s) {
        long long ai = s % A, ti = (s / A) % r->nt, ao = (s / (A * r->nt)) % A, to = s / (A * r->nt * A);
        pf_vec3 wo = pfi_vmf_scale_dir((int)to, (int)ao, r->nt, r->np, r->theta_max);
        pf_vec3 wi = pfi_vmf_scale_dir((int)ti, (int)ai, r->nt, r->np, r->theta_max);
        pf_vmf_sum sum = pf_vmf_sum_zero();
        int j;
        for (j = 0; j < r->lobes[k]; ++j) { /* padding lobes (amp 0) add nothing */
            pf_vmf_lobe lobe = pf_vmf_lobe_make(t[4 * j + 3], t[4 * j], t[4 * j + 1], t[4 * j + 2]);
            sum = pf_vmf_sum_add(sum, lobe, wo, wi, bv);
            if (r->masking == PF_VMF_SCALE_G_MIXTURE) sum = pf_vmf_sum_add_masking(sum, lobe, wo, wi, bv);
        }
        f_lobes[s] = r->masking == PF_VMF_SCALE_UNMASKED    ? pf_vmf_sum_specular_unmasked(sum, wo, wi, r->f0)
                     : r->masking == PF_VMF_SCALE_G_GAUSSIAN ? pf_vmf_sum_specular(sum, wo, wi, r->f0)
                                                             : pf_vmf_sum_specular_mixture(sum, wo, wi, r->f0);
    }
}

/* one texel's samples: f_eff into f_eff, f_lobes of every pyramid into f_lobes + k count */
PF_CPU_DEF int pfi_vmf_scale_texel_samples(const pf_vmf_scale_desc *r, int level, long long tx, long long ty,
                                           pf_real *f_eff, pf_real *f_lobes, long long stride, pf_real *work)
{
    long long count = pf_vmf_scale_sample_count(r->nt, r->np), n = 1LL << level;
    pf_real *nrm = work, *junk = nrm + 3 * n * n;
    unsigned char *vis = (unsigned char *)(void *)(junk + count);
    int k, rc;
    /* f_eff: the patch's own one-lobe fit without EM steps is computed too (cheap), not used */
    rc = pfi_vmf_scale_patch(r->heights, r->w, r->h, r->texel, (int)(tx * n), (int)(ty * n), (int)n, 1, 0, r->base_sigma,
                             r->f0, r->masking, r->nt, r->np, r->theta_max, nrm, vis, f_eff, junk);
    if (rc != PF_OK) return rc;
    for (k = 0; k < r->pyramid_count; ++k) pfi_vmf_scale_texel_lobes(r, k, level, tx, ty, f_lobes + k * stride);
    return PF_OK;
}

/* S and the prior of `level` for each pyramid of desc from its training patches: s_out[k]
   gets pf_vmf_scale_cell_count(nt, np) pf_reals, prior_out[k] one (for pf_vmf_scale_texel_t),
   t_level[k] (NULL: none; one pf_real per texel of the level, row-major) T of the training
   texels only. scratch_len >= pf_vmf_scale_scratch_size(desc, level). Errors: PF_ERR_ARG for a
   NULL desc, heights, pyramid, s_out, prior_out or scratch, a short scratch, sides not powers
   of two, a level the pyramid lacks, lobes outside [1, 16], and pfi_vmf_scale_patch's
   (non-finite heights, bad texel, base_sigma, theta_max, nt, np, masking); PF_ERR_SIZE above
   PF_MAX_REALS; outputs may then be partly written. Cost: train_patches pfi_vmf_scale_patch
   calls: 16 patches of 64 x 64 at 6 x 6 x 5 nodes, ~30 s (docs/vmf_fit.md). */
PF_CPU_DEF int pf_vmf_scale_fit_level(const pf_vmf_scale_desc *desc, int level, pf_real *const *s_out,
                                      pf_real *prior_out, pf_real *const *t_level, pf_real *scratch,
                                      long long scratch_len)
{
    pf_vmf_scale_desc r;
    long long cnt, cells, gw, gh, P, p, need;
    pf_real *f_eff, *f_l, *fac, *t, *work;
    int k, rc;
    if (!pfi_vmf_scale_resolve(desc, &r) || !s_out || !prior_out || !scratch) return PF_ERR_ARG;
    if ((rc = pfi_vmf_scale_check(&r, level)) != PF_OK) return rc;
    for (k = 0; k < r.pyramid_count; ++k)
        if (!s_out[k]) return PF_ERR_ARG;
    need = pf_vmf_scale_scratch_size(&r, level);
    if (need <= 0) return PF_ERR_SIZE;
    if (scratch_len < need) return PF_ERR_ARG;
    cnt = pf_vmf_scale_sample_count(r.nt, r.np);
    cells = pf_vmf_scale_cell_count(r.nt, r.np);
    gw = r.w >> level;
    gh = r.h >> level;
    P = gw * gh < r.train_patches ? gw * gh : r.train_patches;
    f_eff = scratch;
    f_l = f_eff + P * cnt;
    fac = f_l + r.pyramid_count * P * cnt;
    t = fac + 2 * P * cells;
    work = t + P;
    for (p = 0; p < P; ++p) {
        long long c = (p * gw * gh) / P;
        rc = pfi_vmf_scale_texel_samples(&r, level, c % gw, c / gw, f_eff + p * cnt, f_l + p * cnt, P * cnt, work);
        if (rc != PF_OK) return rc;
    }
    for (k = 0; k < r.pyramid_count; ++k) {
        const pf_real *fk = f_l + k * P * cnt;
        rc = pfi_vmf_scale_factor(f_eff, fk, (int)P, r.nt, r.np, r.rounds, r.shrink, t, s_out[k], fac, &prior_out[k], 0);
        if (rc != PF_OK) return rc;
        if (t_level && t_level[k])
            for (p = 0; p < P; ++p)
                t_level[k][(p * gw * gh) / P] = pfi_vmf_scale_t(f_eff + p * cnt, fk + p * cnt, r.nt, r.np, s_out[k], prior_out[k]);
    }
    return PF_OK;
}

/* T of texel (tx, ty) of `level` for each pyramid into t_out[k], from its own samples with the
   level's S (s_table[k]) and prior[k] of pf_vmf_scale_fit_level; scratch and errors as there,
   and PF_ERR_ARG for a NULL s_table, prior, t_out or a texel outside the level. */
PF_CPU_DEF int pf_vmf_scale_texel_t(const pf_vmf_scale_desc *desc, int level, long long tx, long long ty,
                                    const pf_real *const *s_table, const pf_real *prior, pf_real *t_out, pf_real *scratch,
                                    long long scratch_len)
{
    pf_vmf_scale_desc r;
    long long cnt, need;
    int k, rc;
    if (!pfi_vmf_scale_resolve(desc, &r) || !s_table || !prior || !t_out || !scratch) return PF_ERR_ARG;
    if ((rc = pfi_vmf_scale_check(&r, level)) != PF_OK) return rc;
    if (tx < 0 || ty < 0 || tx >= (r.w >> level) || ty >= (r.h >> level)) return PF_ERR_ARG;
    for (k = 0; k < r.pyramid_count; ++k)
        if (!s_table[k]) return PF_ERR_ARG;
    need = pf_vmf_scale_scratch_size(&r, level);
    if (need <= 0) return PF_ERR_SIZE;
    if (scratch_len < need) return PF_ERR_ARG;
    cnt = pf_vmf_scale_sample_count(r.nt, r.np);
    rc = pfi_vmf_scale_texel_samples(&r, level, tx, ty, scratch, scratch + cnt, cnt, scratch + (1 + r.pyramid_count) * cnt);
    if (rc != PF_OK) return rc;
    for (k = 0; k < r.pyramid_count; ++k)
        t_out[k] = pfi_vmf_scale_t(scratch, scratch + (1 + k) * cnt, r.nt, r.np, s_table[k], prior[k]);
    return PF_OK;
}

/* The in-footprint effective BRDF (eqs. 6-8) of the n x n patch from (x0, y0) of desc's map
   (heights, w, h, texel, base_sigma, f0) toward wo from wi into *out; errors as
   pfi_vmf_effective_brdf's (NULL desc: PF_ERR_ARG), *out 0 on an error. Cost: 2 n^2 marches. */
PF_CPU_DEF int pf_vmf_effective_brdf(const pf_vmf_scale_desc *desc, int x0, int y0, int n, pf_vec3 wo, pf_vec3 wi,
                                     pf_real *out)
{
    pf_vmf_scale_desc r;
    if (!pfi_vmf_scale_resolve(desc, &r)) {
        if (out) *out = PF_R(0.0);
        return PF_ERR_ARG;
    }
    return pfi_vmf_effective_brdf(r.heights, r.w, r.h, r.texel, x0, y0, n, wo, wi, r.base_sigma, r.f0, out);
}
#endif /* !PF_GLSL */

#endif /* PF_VMF_SCALE_H */

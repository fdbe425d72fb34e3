/* pf_map_downsample.h - CPU baking of a coarse height map that keeps the fine map's mean
   slopes (Wu et al. 2019 sec. 4.1, eqs. 9-10): a least-squares solve by conjugate gradients
   on pf_map.h's height-map convention (texel centres, central-difference slopes,
   PF_BORDER_WRAP / _CLAMP; pf_map.h's CONVENTIONS). Used before fitting a lobe pyramid
   (pf_vmf_fit.h) on a coarser map. CPU only (PF_CPU_DEF: caller-owned buffers, no
   allocation); empty under PF_GLSL.

   USAGE
     pf_map_downsample_desc d = {0}; d.fine = heights; d.w = w; d.h = h; d.border = PF_BORDER_WRAP;
     pf_map_downsample_slopes(&d, coarse, scratch, pf_map_downsample_scratch_size(w, h, 2), NULL, NULL);

   FUNCTIONS
     downsampling    pf_map_downsample_slopes (struct pf_map_downsample_desc),
                     pf_map_downsample_scratch_size

   ACCURACY AND COST (tests/test_map_downsample.c, bench/bench_vmf.c; docs/map_downsample.md).

   SOURCES
     Wu, Zhao, Yan, Ramamoorthi 2019 sec. 4.1, eqs. 9-10. */
#ifndef PF_MAP_DOWNSAMPLE_H
#define PF_MAP_DOWNSAMPLE_H

#ifndef PF_GLSL
#  include "pf_map.h"

/* ================================================================ CPU only: slope-preserving
   downsampling of a height map (Wu et al. 2019 sec. 4.1, eqs. 9-10)
   A coarse height map read with lobes fitted to the fine normals must carry the fine map's
   mean slope over each footprint: the lobes describe the normals around that mean, and a box
   average of the heights does not keep it (on the bench's corpus the box map's slopes are off
   by 1.2-3.9x the solve's error, docs/vmf.md). Wu et al. choose the coarse heights whose
   slopes best match the footprints' mean slopes in least squares, with a small Laplacian
   term for smoothness.
   OUR DISCRETIZATION (the library's height-map convention, pf_map.h's CONVENTIONS: texels
   at centres, the slope of a texel its central difference, one-sided at a clamped border):
     s*_T   = factor x the mean, over the factor x factor fine texels of coarse texel T, of the
              fine texels' slopes (pf_map_slope_stencil: what pf_slope_pyramid_from_heights'
              level log2(factor) holds as E[sx], E[sy]), in height per COARSE texel;
     (G H)_T = the coarse map's own slope at T by the same stencil (height per coarse texel);
     (L H)_T = the 5-point Laplacian of the coarse map (sum of the 4 neighbours - 4 H_T;
              wrapped, or the edge texel repeated under PF_BORDER_CLAMP);
     minimize  E(H) = sum_T |(G H)_T - s*_T|^2 + reg_weight sum_T (L H)_T^2        (eq. 10)
   (Wu et al. put heights on cell corners and take the bilinear cell's mean slope, eq. 9; on
   the texel-centred grid the central difference plays that role, the stencil every slope
   consumer of the library reads.) Every term is in height per coarse texel, so reg_weight is
   dimensionless (the paper's w = 0.01) and the result does not depend on the texel spacing
   (both slopes divide by it), which is therefore not an argument.
   The normal equations (G^T G + reg_weight L^T L) H = G^T s* are singular along the
   constant map (no slope sees it): THE MEAN IS PINNED to the box-downsampled map's mean (=
   the fine map's mean), and the solve starts from that box map. SOLVER: conjugate gradients
   on the normal equations (the matrix is never formed: each product is one pass of the three
   stencils and one of their transposes), every residual projected to zero mean so rounding
   cannot move the pinned mean; deterministic (fixed loop order, no threads). It stops after
   max_iter iterations or when |r| <= tol |G^T s*| (r the recurrence's residual of the normal
   equations; a target with no slope at all uses |r_0| instead). Heights are scaled by a power
   of two (exact) so that no difference overflows; a result beyond the pf_real range is
   clamped to +-PF_REAL_MAX.
   SAFEGUARDS, for every accepted argument (reg_weight 0 and tol 0 included): a CG step is
   taken only while p^T A p > 64 eps |A| |p|^2 (a direction A cannot tell from its null
   space, e.g. the checkerboards at reg_weight ~ 0, ends the solve instead of dividing
   rounding noise by rounding noise); at most min(max_iter, 4 n + 256) iterations (n coarse
   texels), and fewer when |r|^2 has not halved in 64 + 4 sqrt(n) iterations (stagnation);
   then the TRUE residual |G^T s* - A H| is computed from the fine map again, and when it is
   not finite or above the box map's the box map is returned (iters_out 0). So the result is
   finite, its true residual is at most the box map's, and residual_out reports it.
   Arguments (pf_map_downsample_desc below; its zero defaults resolved first): fine w x h
   row-major; factor >= 1 dividing w and h (coarse (w/factor) x
   (h/factor), row-major, into coarse); border PF_BORDER_WRAP (tiling maps) or
   PF_BORDER_CLAMP; reg_weight in [0, PF_MAP_DOWNSAMPLE_MAX_REG = 1e6] (at 0, under WRAP,
   2-texel checkerboards, which no central difference sees, keep their box values; far above
   1 the Laplacian alone decides; the bound keeps every product finite); max_iter >= 0 (0:
   the box map); tol finite >= 0; scratch: scratch_len >= pf_map_downsample_scratch_size(w,
   h, factor) pf_reals; iters_out (the iterations of the returned map: 0 for the box map)
   and residual_out (the TRUE final |G^T s* - A H| over the reference norm above; in float
   at reg_weight ~ 1e6 it is the rounding of A H, up to ~10) may be NULL.
   Errors: PF_ERR_ARG for NULL fine, coarse or scratch, w or h below 1, factor below 1 or not
   dividing w and h, an unknown border, a bad reg_weight, max_iter or tol, a NaN or infinite
   height (tested on the bits: under -ffast-math too), a scratch_len below the size; PF_ERR_SIZE for a side above PF_MAX_SIDE or a buffer
   above PF_MAX_REALS. On an error nothing is written. Nothing outside fine (read), coarse and
   the first pf_map_downsample_scratch_size reals of scratch is touched.
   Cost: one pass over the fine map, then per iteration one product (three 3-tap stencils and
   their transposes over the coarse map) and five vector passes, at most min(max_iter,
   4 n + 256) iterations, then two more passes over the fine map; 512 x 512 -> 256 x 256 in
   15-50 ms (float, tol 1e-5; docs/map.md has the table and the slope errors against the box
   map). */

#define PF_MAP_DOWNSAMPLE_MAX_REG PF_R(1.0e6)

/* pf_reals of scratch pf_map_downsample_slopes needs: 6 per coarse texel; 0 for sizes it
   rejects (w, h or factor below 1, factor not dividing w and h, a side above PF_MAX_SIDE, or
   more than PF_MAX_REALS). */
PF_CPU_DEF long long pf_map_downsample_scratch_size(int w, int h, int factor)
{
    long long n;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || factor < 1 || w % factor != 0 || h % factor != 0) return 0;
    if (pf_size_mul(w, h) < 0) return 0;
    n = pf_size_mul3((long long)(w / factor), (long long)(h / factor), 6);
    return n < 0 ? 0 : n;
}

/* sum of a[i] b[i] (b NULL: a[i]^2) in rows of w: per-row partial sums, so the rounding grows
   with w + h, not w h */
PF_CPU_DEF pf_real pfi_ds_dot(const pf_real *a, const pf_real *b, long long w, long long h)
{
    pf_real total = PF_R(0.0);
    long long i, j;
    for (j = 0; j < h; ++j) {
        const pf_real *x = a + j * w, *y = (b ? b : a) + j * w;
        pf_real row = PF_R(0.0);
        for (i = 0; i < w; ++i) row += x[i] * y[i];
        total += row;
    }
    return total;
}
PF_CPU_DEF pf_real pfi_ds_mean(const pf_real *a, long long w, long long h)
{
    pf_real total = PF_R(0.0);
    long long i, j;
    for (j = 0; j < h; ++j) {
        pf_real row = PF_R(0.0);
        for (i = 0; i < w; ++i) row += a[j * w + i];
        total += row / (pf_real)w;
    }
    return total / (pf_real)h;
}
PF_CPU_DEF void pfi_ds_shift(pf_real *a, long long n, pf_real d)
{
    long long i;
    for (i = 0; i < n; ++i) a[i] += d;
}
/* neighbour of index i on an axis of n: wrapped or clamped (the clamped Laplacian repeats the
   edge texel: a zero normal derivative) */
PF_CPU_DEF long long pfi_ds_nb(long long i, long long n, int border)
{
    if (border == PF_BORDER_WRAP) return pf_map_wrap(i, n);
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

/* gx = G_x v, gy = G_y v, lp = L v on the W x H coarse grid */
PF_CPU_DEF void pfi_ds_forward(const pf_real *v, int W, int H, int border, pf_real *gx, pf_real *gy, pf_real *lp)
{
    long long I, J, xi[3], yi[3];
    pf_real cx[3], cy[3];
    for (J = 0; J < H; ++J) {
        const pf_real *row = v + J * W, *up = v + pfi_ds_nb(J - 1, H, border) * W, *dn = v + pfi_ds_nb(J + 1, H, border) * W;
        pf_map_slope_stencil(J, H, border, PF_R(0.5), yi, cy);
        for (I = 0; I < W; ++I) {
            long long t = J * W + I;
            pf_map_slope_stencil(I, W, border, PF_R(0.5), xi, cx);
            gx[t] = cx[0] * row[xi[0]] + cx[1] * row[xi[1]] + cx[2] * row[xi[2]];
            gy[t] = cy[0] * v[yi[0] * W + I] + cy[1] * v[yi[1] * W + I] + cy[2] * v[yi[2] * W + I];
            lp[t] = (row[pfi_ds_nb(I - 1, W, border)] + row[pfi_ds_nb(I + 1, W, border)]) + (up[I] + dn[I]) -
                    PF_R(4.0) * row[I];
        }
    }
}

/* out = G_x^T gx + G_y^T gy + reg L^T lp (the transposes as scatters of the same stencils) */
PF_CPU_DEF void pfi_ds_adjoint(const pf_real *gx, const pf_real *gy, const pf_real *lp, pf_real reg, int W, int H,
                               int border, pf_real *out)
{
    long long I, J, k, xi[3], yi[3], n = (long long)W * H;
    pf_real cx[3], cy[3];
    for (k = 0; k < n; ++k) out[k] = PF_R(0.0);
    for (J = 0; J < H; ++J) {
        pf_real *row = out + J * W, *up = out + pfi_ds_nb(J - 1, H, border) * W, *dn = out + pfi_ds_nb(J + 1, H, border) * W;
        pf_map_slope_stencil(J, H, border, PF_R(0.5), yi, cy);
        for (I = 0; I < W; ++I) {
            long long t = J * W + I;
            pf_real a = gx[t], b = gy[t], l = reg * lp[t];
            pf_map_slope_stencil(I, W, border, PF_R(0.5), xi, cx);
            for (k = 0; k < 3; ++k) {
                row[xi[k]] += cx[k] * a;
                out[yi[k] * W + I] += cy[k] * b;
            }
            row[pfi_ds_nb(I - 1, W, border)] += l;
            row[pfi_ds_nb(I + 1, W, border)] += l;
            up[I] += l;
            dn[I] += l;
            row[I] -= PF_R(4.0) * l;
        }
    }
}

/* 1 when x is finite, read from its bits (exponent not all ones): -ffinite-math-only (part of
   -ffast-math) folds every comparison-based test to 1, and the solve must still reject a NaN
   or infinite height. The union is C99's type punning (and what C++ compilers support). */
PF_CPU_DEF int pfi_ds_finite(pf_real x)
{
#ifdef PF_REAL_IS_FLOAT
    union { float f; unsigned int u; } b;
    b.f = x;
    return (b.u & 0x7f800000u) != 0x7f800000u;
#else
    union { double f; unsigned long long u; } b;
    b.f = x;
    return ((b.u >> 52) & 0x7ffu) != 0x7ffu;
#endif
}

/* the target slopes s* (gx, gy: factor x the mean fine slope, height per coarse texel) and,
   when box is not NULL, the box-downsampled map, of the fine map times `scale`: one pass */
PF_CPU_DEF void pfi_ds_target(const pf_real *fine, int w, int h, long long f, int border, pf_real scale, long long W,
                              long long n, pf_real *gx, pf_real *gy, pf_real *box)
{
    long long i, j;
    pf_real inv_f2 = PF_R(1.0) / ((pf_real)f * (pf_real)f);
    for (i = 0; i < n; ++i) {
        gx[i] = gy[i] = PF_R(0.0);
        if (box) box[i] = PF_R(0.0);
    }
    for (j = 0; j < h; ++j) {
        long long yi[3], xi[3], t0 = (j / f) * W;
        pf_real cy[3], cx[3];
        const pf_real *row = fine + j * w;
        pf_map_slope_stencil(j, h, border, PF_R(0.5) * scale, yi, cy);
        for (i = 0; i < w; ++i) {
            long long t = t0 + i / f;
            pf_map_slope_stencil(i, w, border, PF_R(0.5) * scale, xi, cx);
            gx[t] += cx[0] * row[xi[0]] + cx[1] * row[xi[1]] + cx[2] * row[xi[2]];
            gy[t] += cy[0] * fine[yi[0] * w + i] + cy[1] * fine[yi[1] * w + i] + cy[2] * fine[yi[2] * w + i];
            if (box) box[t] += row[i] * scale;
        }
    }
    /* mean fine slope (per fine texel) x f = per coarse texel */
    for (i = 0; i < n; ++i) {
        gx[i] *= inv_f2 * (pf_real)f;
        gy[i] *= inv_f2 * (pf_real)f;
        if (box) box[i] *= inv_f2;
    }
}

/* |b - A x|^2 of the normal equations with the constant removed (x = coarse; b from the fine
   map): r gets the residual; gx, gy, lp, q are overwritten */
PF_CPU_DEF pf_real pfi_ds_true_residual(const pf_real *fine, int w, int h, long long f, int border, pf_real scale,
                                        pf_real reg, const pf_real *x, long long W, long long H, pf_real *r,
                                        pf_real *q, pf_real *gx, pf_real *gy, pf_real *lp)
{
    long long i, n = W * H;
    pfi_ds_target(fine, w, h, f, border, scale, W, n, gx, gy, 0);
    for (i = 0; i < n; ++i) lp[i] = PF_R(0.0);
    pfi_ds_adjoint(gx, gy, lp, PF_R(0.0), (int)W, (int)H, border, r);
    pfi_ds_forward(x, (int)W, (int)H, border, gx, gy, lp);
    pfi_ds_adjoint(gx, gy, lp, reg, (int)W, (int)H, border, q);
    for (i = 0; i < n; ++i) r[i] -= q[i];
    pfi_ds_shift(r, n, -pfi_ds_mean(r, W, H));
    return pfi_ds_dot(r, 0, W, H);
}

PF_CPU_DEF int pfi_map_downsample_slopes(const pf_real *fine, int w, int h, int factor, int border, pf_real reg_weight,
                                         int max_iter, pf_real tol, pf_real *coarse, pf_real *scratch,
                                         long long scratch_len, int *iters_out, pf_real *residual_out)
{
    long long need, n, i, W, H, f = factor, cap, stall = 0;
    pf_real *r, *p, *q, *gx, *gy, *lp, maxabs = PF_R(0.0), scale = PF_R(1.0), bnorm, rr, rr_box, rr_mark, ref, mean;
    pf_real anorm, true_rr;
    int it = 0;
    if (!fine || !coarse || !scratch || w < 1 || h < 1 || factor < 1) return PF_ERR_ARG;
    if (!pf_size_side_ok(w) || !pf_size_side_ok(h) || pf_size_mul(w, h) < 0) return PF_ERR_SIZE;
    if (w % factor != 0 || h % factor != 0 || (border != PF_BORDER_CLAMP && border != PF_BORDER_WRAP)) return PF_ERR_ARG;
    if (!pfi_ds_finite(reg_weight) || !(reg_weight >= PF_R(0.0) && reg_weight <= PF_MAP_DOWNSAMPLE_MAX_REG) ||
        max_iter < 0 || !pfi_ds_finite(tol) || !(tol >= PF_R(0.0)))
        return PF_ERR_ARG;
    need = pf_map_downsample_scratch_size(w, h, factor);
    if (need <= 0) return PF_ERR_SIZE;
    if (scratch_len < need) return PF_ERR_ARG;
    for (i = 0; i < (long long)w * h; ++i) {
        if (!pfi_ds_finite(fine[i])) return PF_ERR_ARG; /* NaN or infinite, tested on the bits */
        maxabs = pf_max(maxabs, PF_FABS(fine[i]));
    }
    /* power-of-two scale to max |height| in [1, 4): exact, no slope difference overflows, and
       the scale stays a normal number (2^-126 at worst in float: no flush to 0 under
       -ffast-math) */
    if (maxabs > PF_R(0.0)) {
        while (maxabs * scale >= PF_R(4.0)) scale *= PF_R(0.5);
        while (maxabs * scale < PF_R(1.0) && scale < PF_R(1.0e30)) scale *= PF_R(2.0);
    }
    W = w / factor, H = h / factor, n = W * H;
    r = scratch, p = r + n, q = p + n, gx = q + n, gy = gx + n, lp = gy + n;
    /* s* (gx, gy) and the box map (coarse), one pass over the fine map */
    pfi_ds_target(fine, w, h, f, border, scale, W, n, gx, gy, coarse);
    mean = pfi_ds_mean(coarse, W, H);
    for (i = 0; i < n; ++i) lp[i] = PF_R(0.0);
    pfi_ds_adjoint(gx, gy, lp, PF_R(0.0), (int)W, (int)H, border, r); /* r = b = G^T s* */
    bnorm = PF_SQRT(pfi_ds_dot(r, 0, W, H));
    /* r = b - A x0 */
    pfi_ds_forward(coarse, (int)W, (int)H, border, gx, gy, lp);
    pfi_ds_adjoint(gx, gy, lp, reg_weight, (int)W, (int)H, border, q);
    for (i = 0; i < n; ++i) r[i] -= q[i];
    pfi_ds_shift(r, n, -pfi_ds_mean(r, W, H));
    rr = rr_box = rr_mark = pfi_ds_dot(r, 0, W, H);
    ref = bnorm > PF_R(0.0) ? bnorm : PF_SQRT(rr);
    for (i = 0; i < n; ++i) p[i] = r[i];
    /* SAFEGUARDS (every argument, reg 0 and tol 0 included; the normal equations are singular
       along the constant and, under WRAP at reg_weight ~ 0, nearly so along the 2-texel
       checkerboards, where plain CG divided rounding noise by rounding noise):
       - a step is taken only when p^T A p > 64 eps |A| |p|^2 (|A| <= 32 + 64 reg_weight, the
         stencils' row sums): a direction that A cannot tell from its null space ends the solve;
       - at most cap = 4 n + 256 iterations (CG ends in n steps in exact arithmetic), and the
         solve ends when |r|^2 has not halved in 64 + 4 sqrt(n) iterations (stagnation);
       - at the end the TRUE residual |b - A x| is computed from the fine map again; when it
         is not finite or above the box map's, the box map is returned (iterations 0). */
    anorm = PF_R(32.0) + PF_R(64.0) * reg_weight;
    cap = 4 * n + 256;
    while (it < max_iter && it < cap && PF_SQRT(rr) > tol * ref) {
        pf_real pq, pp, alpha, rr_new, beta;
        pfi_ds_forward(p, (int)W, (int)H, border, gx, gy, lp);
        pfi_ds_adjoint(gx, gy, lp, reg_weight, (int)W, (int)H, border, q);
        pq = pfi_ds_dot(p, q, W, H);
        pp = pfi_ds_dot(p, 0, W, H);
        if (!(pq > PF_R(64.0) * PF_REAL_EPSILON * anorm * pp)) break; /* p (numerically) in the null space */
        alpha = rr / pq;
        for (i = 0; i < n; ++i) {
            coarse[i] += alpha * p[i];
            r[i] -= alpha * q[i];
        }
        pfi_ds_shift(r, n, -pfi_ds_mean(r, W, H));
        rr_new = pfi_ds_dot(r, 0, W, H);
        ++it;
        if (!(rr_new > PF_R(0.0))) {
            rr = rr_new;
            break; /* exact solution, or a non-finite residual (checked below) */
        }
        beta = rr_new / rr;
        for (i = 0; i < n; ++i) p[i] = r[i] + beta * p[i];
        rr = rr_new;
        if (rr <= PF_R(0.5) * rr_mark) {
            rr_mark = rr;
            stall = 0;
        } else if (++stall > 64 + 4 * (long long)PF_SQRT((pf_real)n)) {
            break;
        }
    }
    /* the pinned mean, exactly (rounding of the updates), then the true residual */
    pfi_ds_shift(coarse, n, mean - pfi_ds_mean(coarse, W, H));
    true_rr = it > 0 ? pfi_ds_true_residual(fine, w, h, f, border, scale, reg_weight, coarse, W, H, r, q, gx, gy, lp)
                     : rr_box;
    if (it > 0 && (!pfi_ds_finite(true_rr) || !(true_rr <= rr_box))) {
        pfi_ds_target(fine, w, h, f, border, scale, W, n, gx, gy, coarse); /* back to the box map */
        true_rr = rr_box;
        it = 0;
    }
    for (i = 0; i < n; ++i) {
        pf_real v = coarse[i] / scale;
        coarse[i] = v > PF_REAL_MAX ? PF_REAL_MAX : (v < -PF_REAL_MAX ? -PF_REAL_MAX : v);
    }
    if (iters_out) *iters_out = it;
    if (residual_out) *residual_out = ref > PF_R(0.0) ? PF_SQRT(true_rr) / ref : PF_R(0.0);
    return PF_OK;
}
/* A downsampling's description; ZERO MEANS THE DEFAULT (negative reg_weight, max_iter, tol: 0). */
typedef struct pf_map_downsample_desc {
    const pf_real *fine;  /* the fine height map, w x h row-major (required) */
    int w, h;             /* its sides (required) */
    int factor;           /* coarse texel = factor x factor fine texels, dividing w and h (0: 2) */
    int border;           /* PF_BORDER_CLAMP (0) or PF_BORDER_WRAP */
    pf_real reg_weight;   /* the Laplacian's weight (0: 0.01, Wu et al.'s w; negative: 0) */
    int max_iter;         /* conjugate-gradient iterations (0: 400; negative: 0, the box map) */
    pf_real tol;          /* relative residual to stop at (0: 1e-5; negative: 0, max_iter decides) */
} pf_map_downsample_desc;

/* The slope-preserving coarse map of desc (see the block comment) into coarse
   ((w/factor) x (h/factor) pf_reals); scratch, iters_out, residual_out and the errors as
   there (NULL desc: PF_ERR_ARG). */
PF_CPU_DEF int pf_map_downsample_slopes(const pf_map_downsample_desc *desc, pf_real *coarse, pf_real *scratch,
                                        long long scratch_len, int *iters_out, pf_real *residual_out)
{
    pf_map_downsample_desc d;
    if (!desc) return PF_ERR_ARG;
    d = *desc;
    if (d.factor == 0) d.factor = 2;
    d.reg_weight = d.reg_weight == PF_R(0.0) ? PF_R(0.01) : (d.reg_weight < PF_R(0.0) ? PF_R(0.0) : d.reg_weight);
    d.max_iter = d.max_iter == 0 ? 400 : (d.max_iter < 0 ? 0 : d.max_iter);
    d.tol = d.tol == PF_R(0.0) ? PF_R(1.0e-5) : (d.tol < PF_R(0.0) ? PF_R(0.0) : d.tol);
    return pfi_map_downsample_slopes(d.fine, d.w, d.h, d.factor, d.border, d.reg_weight, d.max_iter, d.tol, coarse, scratch,
                                     scratch_len, iters_out, residual_out);
}
#endif /* !PF_GLSL */

#endif /* PF_MAP_DOWNSAMPLE_H */

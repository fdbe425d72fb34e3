/* pf_masks.h - sub-pixel occlusion masks: which part of a pixel (a cone element) a plane covers,
   as a binary mask over Poisson-disk samples; table lookup and mask composition.

   IDEA (Heitz & Neyret 2011, sec. 4.4 "Computation of the Binary Masks" and appendix B, after
   Carpenter 1984). Along a pixel's cone the geometry of one cone element is replaced by its
   mean view-dependent visible plane (the plane of the coarse surface moved by the mean visible
   height, pf_height.h). Which rays of the element hit that plane depends only on two numbers:
   the direction theta of the plane's normal projected on the pixel, and a signed offset v.
   A ray through the pixel point (x, y) (in units of the cone width c, centred on the axis) is
   covered when
       x cos(theta) + y sin(theta) <= v                                       (HN11 app. B)
   with, for the plane x dx + y dy + (z - z_i) dz + d = 0 (normal (dx, dy, dz), offset d, z
   along the cone axis, z_i the element's centre, depth dz_e = z_{i+1} - z_i):
       (dx, dy) = r (cos theta, sin theta),
       v = (|dz| dz_e / 2 - d) / (c r).                                       (HN11 app. B)
   (The paper writes dz; |dz| makes the test independent of the normal's orientation along z:
   a ray is covered when either end of its segment in the element is inside the geometry.)
   The coverage of a pixel is then a binary mask: bit k is 1 when sample k of N Poisson-disk
   samples of the footprint is covered. Masks are precomputed on a (theta, v) grid (CPU, below)
   and looked up at the nearest grid point; the accumulated visibility of the cone is updated
   with bit operations, which keeps the correlation between elements that alpha blending loses
   (HN11 eq. 15 against eq. 16, fig. 4):
       V_i = |M_i and not A_{i-1}| / N,     A_i = A_{i-1} or M_i.             (HN11 eq. 15)

   USAGE (shader side; the table is a buffer or texture of int words, see TABLE LAYOUT)
     pf_mask_params p = pf_masks_params_from_plane(normal, d_visible, cone_width, depth);
     int k = pf_masks_index(p, PF_MASKS_SQUARE, n_theta, n_v) * 2;     -- 64 samples: 2 words
     pf_mask m = pf_mask_make(masks[k], masks[k + 1], 0, 0);           -- caller's fetch
     pf_real vis = pf_masks_visible_fraction(m, acc, 64);               -- eq. 15
     acc = pf_masks_union(acc, m);
   with d_visible = d + mean_h + sigma_h * pf_visible_height(lambda_v).mean (pf_height.h;
   HN11 eq. 20 and sec. 4.4: the plane moved to the mean visible height).
   CPU side, once:
     pf_real xy[2 * 64];  int *table = <caller-owned, pf_masks_table_words(64, 64, 64) ints>;
     pf_masks_samples(PF_MASKS_SQUARE, 64, 1, xy);
     pf_masks_table_build(PF_MASKS_SQUARE, 64, 64, xy, 64, table);

   FUNCTIONS (shader subset: no pointers; C99, C++, CUDA, GLSL)
     pf_mask_params_make(theta, v), pf_mask_make(w0, w1, w2, w3)
     pf_masks_params_from_plane(normal, offset, cone_width, element_depth)   app. B
     pf_masks_v_max(shape)                 largest |v| inside the footprint
     pf_masks_grid_theta(i, n_theta), pf_masks_grid_v(j, n_v, shape)   the table's grid
     pf_masks_index(params, shape, n_theta, n_v)     mask number of the nearest grid point
     pf_masks_words(n_samples)             32-bit words per mask (1..4)
     pf_masks_popcount(w), pf_masks_count(m), pf_masks_coverage(m, n_samples)
     pf_masks_union(a, b), pf_masks_intersection(a, b), pf_masks_difference(a, b),
     pf_masks_complement(m, n_samples), pf_masks_visible_fraction(element, upstream, n_samples)
     CPU only (#ifndef PF_GLSL, linkage PF_CPU_DEF, caller buffers, no allocation)
     pf_masks_samples(shape, n_samples, seed, xy)          deterministic Poisson-disk samples
     pf_masks_table_words(n_samples, n_theta, n_v)         size of a table, in int words
     pf_masks_table_build(shape, n_theta, n_v, xy, n_samples, table)
     pf_masks_table_fetch(table, n_theta, n_v, index, n_samples)   a mask from a table in C

   CONVENTIONS
     Footprint: PF_MASKS_SQUARE is the pixel square [-1/2, 1/2]^2 (side c), PF_MASKS_DISK the
     disk of radius 1/2 (the cone's cross-section), both in units of the cone width c.
     Masks: pf_mask holds up to PF_MASKS_MAX_SAMPLES = 128 bits in four 32-bit int words
     (w0: samples 0-31, w1: 32-63, ...; the paper uses 128 samples in four words). With N < 128
     samples the unused bits and words are 0; every function keeps them 0 (complement takes N).
     The words are int, not unsigned: the bit pattern is what matters, int is the 32-bit type
     that C99, C++, CUDA and GLSL (ivec/int buffers, int(uint) keeps the bits) share, and the
     portability generator passes int. Requirement: int is 32-bit two's complement (every GPU,
     x86, ARM, RISC-V; checked where the compiler says its size).
     Bit k of a mask is 1 when sample k is covered (inside the occluder's half-plane).
     theta is any angle (radians, wrapped); v beyond +-pf_masks_v_max(shape) gives the full or
     empty mask; NaN theta reads as 0, NaN v as the empty mask (no occluder). A plane whose
     normal is along the cone axis (r = 0) covers everything or nothing: v = +-PF_MASKS_V_CLAMP.
     n_theta is clamped to [1, 32768], n_v to [2, 32768] (index < 2^30, no int overflow).

   TABLE LAYOUT. Mask (i, j) (theta_i = 2 pi i / n_theta, v_j = -v_max + 2 v_max j / (n_v - 1))
   has number i * n_v + j; its words are table[number * W + w], w < W = pf_masks_words(N). The
   recommended table (bench/bench_masks.c, docs/masks.md): N = 64 samples, 64 x 64 (theta, v):
   2 words per mask, 8192 words = 32 KiB.

   ACCURACY AND COST (tests/test_masks.c, bench/bench_masks.c; tables in docs/masks.md). The
   covered fraction of a looked-up mask against the exact area of the footprint clipped by the
   half-plane (square; float and double alike): N = 64 on the 64 x 64 table, max 0.053, mean
   0.0099; N = 32 / 32 x 32: max 0.118, mean 0.022; N = 128 / 64 x 64: max 0.050, mean 0.0070;
   N = 128 / 256 x 256 (the paper's): max 0.038, mean 0.0060. The error is the sample set's
   half-plane discrepancy plus the nearest-grid rounding. Eq. 15 composed with masks, N = 64:
   max 0.090 (mean 0.0095) where alpha blending (eq. 16) errs by up to 0.25. Cost (callgrind,
   x86-64 gcc -O2, float): index + fetch + coverage 121 instructions for N = 64; the eq. 15
   step on fetched masks 53 (SWAR popcount; 25 with -mpopcnt).

   SOURCES
     Heitz & Neyret 2011, "A Visibility-Aware Model for Pre-Filtering and Rendering Surfaces in
     Real-Time" (INRIA RR-7827): sec. 3.4 eqs. 14-16, sec. 4.4, sec. 5 (128 Poisson samples,
     256 x 256 table), appendix B. Carpenter 1984 (the A-buffer's subpixel masks). Mitchell
     1991 (best-candidate sampling, used here for the Poisson-disk set). */
#ifndef PF_MASKS_H
#define PF_MASKS_H

#ifndef PF_GLSL
#  include "pf_core.h"
#endif

#if !defined(PF_GLSL) && defined(__SIZEOF_INT__)
#  if __SIZEOF_INT__ != 4
#    error "pf_masks.h needs a 32-bit int"
#  endif
#endif

#define PF_MASKS_SQUARE 0
#define PF_MASKS_DISK 1
#define PF_MASKS_MAX_SAMPLES 128
/* |v| returned for a plane seen edge-on (r = 0) or far outside the footprint: beyond any
   footprint point (the square's corners are at 0.7071). */
#define PF_MASKS_V_CLAMP PF_R(2.0)
#define PF_MASKS_MAX_GRID 32768

#ifdef PF_GLSL
#  define PFI_MASKS_INT(x) int(x)
#else
#  define PFI_MASKS_INT(x) ((int)(x))
#endif

/* The mask parameters of HN11 app. B: the covered rays satisfy x cos theta + y sin theta <= v. */
PF_STRUCT_BEGIN(pf_mask_params)
    pf_real theta;
    pf_real v;
PF_STRUCT_END(pf_mask_params)

/* Up to 128 mask bits in four 32-bit words (see CONVENTIONS). */
PF_STRUCT_BEGIN(pf_mask)
    int w0;
    int w1;
    int w2;
    int w3;
PF_STRUCT_END(pf_mask)

PF_DEF pf_mask_params pf_mask_params_make(pf_real theta, pf_real v)
{
    pf_mask_params p;
    p.theta = theta;
    p.v = v;
    return p;
}

PF_DEF pf_mask pf_mask_make(int w0, int w1, int w2, int w3)
{
    pf_mask m;
    m.w0 = w0;
    m.w1 = w1;
    m.w2 = w2;
    m.w3 = w3;
    return m;
}

/* ---------------------------------------------------------------- popcount
   PF_MASKS_POPCOUNT(w): the number of 1 bits of the int word w. GLSL bitCount, CUDA __popc on
   the device, the compiler's builtin where the target has a popcount instruction (x86 with
   -mpopcnt, AArch64); elsewhere (Cortex-M, plain x86-64, tcc) the branch-free SWAR count below,
   so no libgcc helper (__popcountsi2) is ever called. Override it on its own if you have
   better. */
#ifndef PF_GLSL
/* Bits counted in pairs, nibbles, bytes, then summed by one multiply (the classic SWAR count).
   On unsigned int: the conversion of a negative int to unsigned is defined (modulo 2^32). */
PF_DEF int pfi_masks_popcount_swar(int w)
{
    unsigned int x = (unsigned int)w;
    x = x - ((x >> 1) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    x = (x + (x >> 4)) & 0x0F0F0F0Fu;
    return (int)((x * 0x01010101u) >> 24);
}
#endif

#ifndef PF_MASKS_POPCOUNT
#  if defined(PF_GLSL)
#    define PF_MASKS_POPCOUNT(w) bitCount(w)
#  elif defined(__CUDA_ARCH__)
#    define PF_MASKS_POPCOUNT(w) __popc((unsigned int)(w))
#  elif (defined(__GNUC__) || defined(__clang__)) && (defined(__POPCNT__) || defined(__aarch64__))
#    define PF_MASKS_POPCOUNT(w) __builtin_popcount((unsigned int)(w))
#  else
#    define PF_MASKS_POPCOUNT(w) pfi_masks_popcount_swar(w)
#  endif
#endif

/* ---------------------------------------------------------------- mask parameters */

/* Largest |x cos theta + y sin theta| over the footprint: sqrt(2)/2 for the square (its
   corners), 1/2 for the disk. The table's v axis spans [-v_max, v_max]; at -v_max a mask is
   empty and at +v_max full. Unknown shapes read as the square. */
PF_DEF pf_real pf_masks_v_max(int shape)
{
    return shape == PF_MASKS_DISK ? PF_R(0.5) : PF_R(0.5) * PF_SQRT2;
}

/* HN11 app. B: the mask parameters of the plane x nx + y ny + (z - z_i) nz + offset = 0 in the
   cone element of width cone_width (> 0) and depth element_depth (>= 0), in the cone's frame
   (z along the axis). The normal need not be unit (theta and v do not change when normal and
   offset are scaled together).
       theta = atan2(ny, nx),  v = (|nz| element_depth / 2 - offset) / (cone_width r),
       r = sqrt(nx^2 + ny^2).
   r = 0 (or a width <= 0): every ray is covered or none, v = +-PF_MASKS_V_CLAMP by the sign of
   the numerator; v is clamped to +-PF_MASKS_V_CLAMP (beyond, the mask no longer changes); a NaN
   anywhere gives theta = 0 or v = -PF_MASKS_V_CLAMP (empty), never NaN. */
PF_DEF pf_mask_params pf_masks_params_from_plane(pf_vec3 normal, pf_real offset, pf_real cone_width,
                                                 pf_real element_depth)
{
    pf_real r = PF_SQRT(normal.x * normal.x + normal.y * normal.y);
    pf_real num = PF_FABS(normal.z) * element_depth * PF_R(0.5) - offset;
    pf_real den = cone_width * r;
    pf_real theta = PF_R(0.0);
    pf_real v;
    if (r > PF_R(0.0)) theta = PF_ATAN2(normal.y, normal.x);
    if (!(theta > -PF_R(4.0) && theta < PF_R(4.0))) theta = PF_R(0.0);
    if (den > PF_R(0.0)) v = num / den;
    else v = num >= PF_R(0.0) ? PF_MASKS_V_CLAMP : -PF_MASKS_V_CLAMP;
    if (!(v > -PF_MASKS_V_CLAMP)) v = -PF_MASKS_V_CLAMP;
    if (v > PF_MASKS_V_CLAMP) v = PF_MASKS_V_CLAMP;
    return pf_mask_params_make(theta, v);
}

/* The table's grid: theta_i = 2 pi i / n_theta, v_j = -v_max + 2 v_max j / (n_v - 1) (n_theta,
   n_v clamped as in CONVENTIONS). */
PF_DEF pf_real pf_masks_grid_theta(int i, int n_theta)
{
    int n = n_theta < 1 ? 1 : (n_theta > PF_MASKS_MAX_GRID ? PF_MASKS_MAX_GRID : n_theta);
    return PF_R(2.0) * PF_PI * PF_R(i) / PF_R(n);
}

PF_DEF pf_real pf_masks_grid_v(int j, int n_v, int shape)
{
    int n = n_v < 2 ? 2 : (n_v > PF_MASKS_MAX_GRID ? PF_MASKS_MAX_GRID : n_v);
    pf_real vm = pf_masks_v_max(shape);
    return -vm + PF_R(2.0) * vm * PF_R(j) / PF_R(n - 1);
}

/* Number of the mask at the grid point nearest to (theta, v): i * n_v + j, i the nearest theta
   index (theta wrapped to [0, 2 pi)), j the nearest v index clamped to [0, n_v - 1] (so v
   outside the footprint gets the empty or full mask exactly). The caller multiplies by
   pf_masks_words(N) to fetch the words. NaN theta -> i = 0, NaN v -> j = 0 (empty). */
PF_DEF int pf_masks_index(pf_mask_params p, int shape, int n_theta, int n_v)
{
    int nt = n_theta < 1 ? 1 : (n_theta > PF_MASKS_MAX_GRID ? PF_MASKS_MAX_GRID : n_theta);
    int nv = n_v < 2 ? 2 : (n_v > PF_MASKS_MAX_GRID ? PF_MASKS_MAX_GRID : n_v);
    pf_real ft = PF_R(nt);
    pf_real vm = pf_masks_v_max(shape);
    pf_real t = p.theta * (ft * PF_R(0.159154943091895335768883763372514362)); /* / (2 pi) */
    pf_real s = (p.v + vm) * (PF_R(nv - 1) / (PF_R(2.0) * vm));
    int i = 0;
    int j = 0;
    t = t - ft * PF_FLOOR(t / ft); /* [0, nt] up to rounding; inf and NaN give NaN */
    if (t >= PF_R(0.0) && t < ft) i = PFI_MASKS_INT(PF_FLOOR(t + PF_R(0.5)));
    if (i < 0 || i >= nt) i = 0; /* also what -ffast-math's NaN conversions land on */
    if (!(s > PF_R(0.0))) j = 0;
    else if (!(s < PF_R(nv - 1))) j = nv - 1;
    else j = PFI_MASKS_INT(PF_FLOOR(s + PF_R(0.5)));
    if (j < 0) j = 0;
    if (j > nv - 1) j = nv - 1;
    return i * nv + j;
}

/* 32-bit words per mask of n_samples samples: 1 (N <= 32) .. 4 (N <= 128); 0 outside [1, 128]. */
PF_DEF int pf_masks_words(int n_samples)
{
    if (n_samples < 1 || n_samples > PF_MASKS_MAX_SAMPLES) return 0;
    return (n_samples + 31) / 32;
}

/* ---------------------------------------------------------------- composition (Carpenter 1984) */

PF_DEF int pf_masks_popcount(int w) { return PF_MASKS_POPCOUNT(w); }

/* Covered samples of m. */
PF_DEF int pf_masks_count(pf_mask m)
{
    return PF_MASKS_POPCOUNT(m.w0) + PF_MASKS_POPCOUNT(m.w1) + PF_MASKS_POPCOUNT(m.w2) + PF_MASKS_POPCOUNT(m.w3);
}

/* Covered fraction count(m) / n_samples, in [0, 1] for a mask of n_samples samples (its unused
   bits 0); n_samples < 1 returns 0. */
PF_DEF pf_real pf_masks_coverage(pf_mask m, int n_samples)
{
    if (n_samples < 1) return PF_R(0.0);
    return pf_min(PF_R(pf_masks_count(m)) / PF_R(n_samples), PF_R(1.0));
}

PF_DEF pf_mask pf_masks_union(pf_mask a, pf_mask b)
{
    return pf_mask_make(a.w0 | b.w0, a.w1 | b.w1, a.w2 | b.w2, a.w3 | b.w3);
}

PF_DEF pf_mask pf_masks_intersection(pf_mask a, pf_mask b)
{
    return pf_mask_make(a.w0 & b.w0, a.w1 & b.w1, a.w2 & b.w2, a.w3 & b.w3);
}

/* a and not b: the samples of a that b leaves uncovered. */
PF_DEF pf_mask pf_masks_difference(pf_mask a, pf_mask b)
{
    return pf_mask_make(a.w0 & ~b.w0, a.w1 & ~b.w1, a.w2 & ~b.w2, a.w3 & ~b.w3);
}

/* The word of the first `bits` bits (0..32) set. 1 << 31 overflows int, so bit 31 is ~0x7fffffff. */
PF_DEF int pfi_masks_low_bits(int bits)
{
    if (bits <= 0) return 0;
    if (bits >= 32) return ~0;
    if (bits == 31) return 0x7fffffff;
    return (1 << bits) - 1;
}

/* The uncovered samples of a mask of n_samples samples (bits past n_samples stay 0; n_samples
   clamped to [0, 128]). */
PF_DEF pf_mask pf_masks_complement(pf_mask m, int n_samples)
{
    return pf_mask_make(~m.w0 & pfi_masks_low_bits(n_samples), ~m.w1 & pfi_masks_low_bits(n_samples - 32),
                        ~m.w2 & pfi_masks_low_bits(n_samples - 64), ~m.w3 & pfi_masks_low_bits(n_samples - 96));
}

/* HN11 eq. 15: the fraction of the pixel that a cone element of mask `element` shows behind the
   accumulated mask `upstream` of the elements before it, |element and not upstream| / N. */
PF_DEF pf_real pf_masks_visible_fraction(pf_mask element, pf_mask upstream, int n_samples)
{
    return pf_masks_coverage(pf_masks_difference(element, upstream), n_samples);
}

/* ================================================================ CPU only
   The rules of pf_core.h's "CPU only: sizes and errors": every argument checked before anything
   is written, PF_OK / PF_ERR_ARG / PF_ERR_SIZE, nothing written on an error, no allocation.
   Buffers hold what each comment says (the library cannot check a pointer's extent). */
#ifndef PF_GLSL

/* Candidates per new sample in the best-candidate construction (Mitchell 1991), and candidate
   sets of which pf_masks_samples keeps the one of least half-plane error. */
#ifndef PF_MASKS_CANDIDATES
#  define PF_MASKS_CANDIDATES 64
#endif
#ifndef PF_MASKS_SETS
#  define PF_MASKS_SETS 16
#endif

/* A 32-bit xorshift generator (Marsaglia 2003) in unsigned int: deterministic on every host. */
PF_CPU_DEF unsigned int pfi_masks_rng(unsigned int *s)
{
    unsigned int x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

/* A uniform point of the footprint from two draws: the square directly, the disk by the
   area-preserving polar map (r = sqrt(u) / 2), so no draw is rejected. */
PF_CPU_DEF void pfi_masks_point(int shape, unsigned int *s, pf_real *x, pf_real *y)
{
    pf_real u1 = (pf_real)(pfi_masks_rng(s) >> 8) * PF_R(5.9604644775390625e-8); /* 2^-24 */
    pf_real u2 = (pf_real)(pfi_masks_rng(s) >> 8) * PF_R(5.9604644775390625e-8);
    if (shape == PF_MASKS_DISK) {
        pf_real r = PF_R(0.5) * PF_SQRT(u1), a = PF_R(2.0) * PF_PI * u2;
        *x = r * PF_COS(a);
        *y = r * PF_SIN(a);
    } else {
        *x = u1 - PF_R(0.5);
        *y = u2 - PF_R(0.5);
    }
}

/* Exact fraction of the footprint with x c + y s <= v (the oracle the sample sets are scored
   against). Square: x c + y s is the sum of two uniforms of widths a = max(|c|, |s|) and
   b = min(|c|, |s|), whose CDF is piecewise quadratic-linear-quadratic (a trapezoidal density).
   Disk of radius R = 1/2: the circular segment (R^2 (pi - acos(v/R)) + v sqrt(R^2 - v^2)) /
   (pi R^2), acos through atan2. */
PF_CPU_DEF pf_real pfi_masks_exact_area(int shape, pf_real c, pf_real s, pf_real v)
{
    if (shape == PF_MASKS_DISK) {
        pf_real r = PF_R(0.5), w;
        if (v <= -r) return PF_R(0.0);
        if (v >= r) return PF_R(1.0);
        w = PF_SQRT(r * r - v * v);
        return (r * r * (PF_PI - PF_ATAN2(w, v)) + v * w) / (PF_PI * r * r);
    } else {
        pf_real a = pf_max(PF_FABS(c), PF_FABS(s)), b = pf_min(PF_FABS(c), PF_FABS(s));
        pf_real p = PF_R(0.5) * (a + b), q = PF_R(0.5) * (a - b);
        if (v <= -p) return PF_R(0.0);
        if (v >= p) return PF_R(1.0);
        if (!(b > PF_R(1e-6) * a)) return pf_saturate((v + PF_R(0.5) * a) / a);
        if (v < -q) return (v + p) * (v + p) / (PF_R(2.0) * a * b);
        if (v <= q) return b / (PF_R(2.0) * a) + (v + q) / a;
        return PF_R(1.0) - (p - v) * (p - v) / (PF_R(2.0) * a * b);
    }
}

/* Largest |covered fraction - exact area| of the n points xy over a fixed grid of half-planes
   (40 directions x 33 offsets, staggered from every table grid by half a step in theta). */
PF_CPU_DEF pf_real pfi_masks_score(int shape, int n, const pf_real *xy)
{
    pf_real worst = PF_R(0.0), vm = pf_masks_v_max(shape);
    int i, j, k;
    for (i = 0; i < 40; ++i) {
        pf_real th = PF_R(2.0) * PF_PI * (PF_R(i) + PF_R(0.5)) / PF_R(40.0), c = PF_COS(th), s = PF_SIN(th);
        for (j = 1; j < 33; ++j) {
            pf_real v = -vm + PF_R(2.0) * vm * PF_R(j) / PF_R(33.0);
            int cnt = 0;
            for (k = 0; k < n; ++k) cnt += xy[2 * k] * c + xy[2 * k + 1] * s <= v;
            worst = pf_max(worst, PF_FABS(PF_R(cnt) / PF_R(n) - pfi_masks_exact_area(shape, c, s, v)));
        }
    }
    return worst;
}

/* One best-candidate set (Mitchell 1991) of n points into xy, from the generator state s. */
PF_CPU_DEF void pfi_masks_best_candidate(int shape, int n, unsigned int s, pf_real *xy)
{
    int k, c, q;
    for (k = 0; k < n; ++k) {
        pf_real bx = PF_R(0.0), by = PF_R(0.0), best = -PF_R(1.0);
        for (c = 0; c < (k == 0 ? 1 : PF_MASKS_CANDIDATES); ++c) {
            pf_real x, y, dmin = PF_REAL_MAX;
            pfi_masks_point(shape, &s, &x, &y);
            /* the footprint's edge counts as a neighbour at twice the distance to it, so the
               points do not crowd onto the edge (plain best-candidate does: its edge points
               have neighbours on one side only, which biases the coverage of half-planes) */
            if (k > 0) {
                pf_real e = shape == PF_MASKS_DISK ? PF_R(0.5) - PF_SQRT(x * x + y * y)
                                                   : PF_R(0.5) - pf_max(PF_FABS(x), PF_FABS(y));
                dmin = PF_R(4.0) * e * e;
            }
            for (q = 0; q < k; ++q) {
                pf_real dx = x - xy[2 * q], dy = y - xy[2 * q + 1], d = dx * dx + dy * dy;
                if (d < dmin) dmin = d;
            }
            if (dmin > best) {
                best = dmin;
                bx = x;
                by = y;
            }
        }
        xy[2 * k] = bx;
        xy[2 * k + 1] = by;
    }
}

/* n_samples (1..128) Poisson-disk distributed points of the footprint into xy[0 .. 2 n - 1]
   (x0, y0, x1, y1, ...). PF_MASKS_SETS best-candidate sets are drawn (Mitchell 1991: each new
   point the farthest from those already placed, and from the edge, among PF_MASKS_CANDIDATES
   uniform candidates) from a xorshift generator seeded by seed and the set's number, and the
   set whose covered fractions are closest to the exact areas of a fixed grid of half-planes
   (worst case over 40 x 32, staggered from the table grids) is kept: the table's error is that
   discrepancy, and sets of the same construction differ by up to 1.5x in it. Deterministic:
   the same seed gives the same points on every host (up to the rounding of sqrt/cos/sin).
   Returns PF_OK, or PF_ERR_ARG (unknown shape, n_samples outside [1, 128], xy NULL; nothing
   written). Cost: 1 ms (n = 32), 11 ms (64), ~30 ms (128) (bench_masks --build-cost). */
PF_CPU_DEF int pf_masks_samples(int shape, int n_samples, int seed, pf_real *xy)
{
    pf_real cand[2 * PF_MASKS_MAX_SAMPLES], best = PF_REAL_MAX;
    int set, k;
    if (shape != PF_MASKS_SQUARE && shape != PF_MASKS_DISK) return PF_ERR_ARG;
    if (n_samples < 1 || n_samples > PF_MASKS_MAX_SAMPLES || !xy) return PF_ERR_ARG;
    for (set = 0; set < PF_MASKS_SETS; ++set) {
        /* a zero state would stay zero: mix seed and set (odd constants) and avoid 0 */
        unsigned int s = ((unsigned int)seed * 0x9E3779B9u) ^ ((unsigned int)set * 0x85EBCA6Bu + 0x7F4A7C15u);
        pf_real score;
        if (s == 0u) s = 0x6A09E667u;
        pfi_masks_best_candidate(shape, n_samples, s, cand);
        score = pfi_masks_score(shape, n_samples, cand);
        if (score < best) {
            best = score;
            for (k = 0; k < 2 * n_samples; ++k) xy[k] = cand[k];
        }
    }
    return PF_OK;
}

/* Int words of a table of masks of n_samples samples on an n_theta x n_v grid:
   n_theta * n_v * pf_masks_words(n_samples), or 0 for any size pf_masks_table_build rejects
   (n_samples outside [1, 128], n_theta outside [1, 32768], n_v outside [2, 32768]). */
PF_CPU_DEF long long pf_masks_table_words(int n_samples, int n_theta, int n_v)
{
    long long t;
    int w = pf_masks_words(n_samples);
    if (w == 0 || n_theta < 1 || n_v < 2 || n_theta > PF_MASKS_MAX_GRID || n_v > PF_MASKS_MAX_GRID) return 0;
    t = pf_size_mul3(n_theta, n_v, w);
    return t < 0 ? 0 : t;
}

/* Finite, by comparison (no isfinite: C99/C++11 spell it differently). */
PF_CPU_DEF int pfi_masks_finite(pf_real x) { return x >= -PF_REAL_MAX && x <= PF_REAL_MAX; }

/* The mask table (TABLE LAYOUT above): for every grid point (theta_i, v_j), bit k of mask
   i * n_v + j is 1 when x_k cos theta_i + y_k sin theta_i <= v_j, for the n_samples points xy
   (from pf_masks_samples, or your own: each finite and inside the footprint of `shape`, within
   1e-4 of its edge). table must hold pf_masks_table_words(n_samples, n_theta, n_v) ints; every
   word is written (unused bits 0). Returns PF_OK; PF_ERR_ARG for an unknown shape, NULL
   pointers, n_samples outside [1, 128], n_theta < 1, n_v < 2, or a sample that is not finite
   or outside the footprint; PF_ERR_SIZE for n_theta or n_v above 32768 or a table of more
   than PF_MAX_REALS words (pf_masks_table_words returns 0 for exactly the sizes rejected: on
   32-bit hosts PF_MAX_REALS = 2^28, so 32768 x 4096 x 4 words is refused there). Nothing is
   written on an error. */
PF_CPU_DEF int pf_masks_table_build(int shape, int n_theta, int n_v, const pf_real *xy, int n_samples, int *table)
{
    int i, j, k, w, words;
    pf_real lim = PF_R(0.5) + PF_R(1e-4);
    if (shape != PF_MASKS_SQUARE && shape != PF_MASKS_DISK) return PF_ERR_ARG;
    if (!xy || !table || n_samples < 1 || n_samples > PF_MASKS_MAX_SAMPLES || n_theta < 1 || n_v < 2) return PF_ERR_ARG;
    if (n_theta > PF_MASKS_MAX_GRID || n_v > PF_MASKS_MAX_GRID) return PF_ERR_SIZE;
    /* the table's size in the checked arithmetic: above PF_MAX_REALS (32-bit hosts) no offset
       below could be formed as a pointer difference */
    if (pf_masks_table_words(n_samples, n_theta, n_v) == 0) return PF_ERR_SIZE;
    for (k = 0; k < n_samples; ++k) {
        pf_real x = xy[2 * k], y = xy[2 * k + 1];
        if (!pfi_masks_finite(x) || !pfi_masks_finite(y)) return PF_ERR_ARG;
        if (shape == PF_MASKS_DISK ? !(x * x + y * y <= lim * lim) : !(PF_FABS(x) <= lim && PF_FABS(y) <= lim))
            return PF_ERR_ARG;
    }
    words = pf_masks_words(n_samples);
    for (i = 0; i < n_theta; ++i) {
        pf_real th = pf_masks_grid_theta(i, n_theta), ct = PF_COS(th), st = PF_SIN(th);
        for (j = 0; j < n_v; ++j) {
            pf_real v = pf_masks_grid_v(j, n_v, shape);
            int *m = table + ((long long)i * n_v + j) * words;
            for (w = 0; w < words; ++w) m[w] = 0;
            /* the ends of the v axis are exactly empty and full, whatever the rounding of the
               projections of samples on the footprint's edge */
            if (j == 0) continue;
            for (k = 0; k < n_samples; ++k)
                if (j == n_v - 1 || xy[2 * k] * ct + xy[2 * k + 1] * st <= v)
                    m[k >> 5] |= (k & 31) == 31 ? ~0x7fffffff : (1 << (k & 31));
        }
    }
    return PF_OK;
}

/* The mask `index` (from pf_masks_index) of a table built for n_samples samples on an
   n_theta x n_v grid, as a pf_mask (unused words 0): what a shader does with its own fetch.
   The empty mask for a NULL table, a rejected size or an index outside [0, n_theta n_v). */
PF_CPU_DEF pf_mask pf_masks_table_fetch(const int *table, int n_theta, int n_v, int index, int n_samples)
{
    int words = pf_masks_words(n_samples);
    pf_mask m = pf_mask_make(0, 0, 0, 0);
    const int *p;
    if (!table || pf_masks_table_words(n_samples, n_theta, n_v) == 0) return m;
    if (index < 0 || (long long)index >= (long long)n_theta * n_v) return m;
    p = table + (long long)index * words;
    m.w0 = p[0];
    if (words > 1) m.w1 = p[1];
    if (words > 2) m.w2 = p[2];
    if (words > 3) m.w3 = p[3];
    return m;
}
#endif /* !PF_GLSL */

#endif /* PF_MASKS_H */

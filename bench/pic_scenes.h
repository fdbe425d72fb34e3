/* pic_scenes.h - the two scenes of the report's pictures, shared by bench/pictures.c (CPU float
   pyramids) and bench/frame/frame.c (the same frames through a Vulkan driver), so the two
   programs render the same pixels: the settings (map, base lobe, lit rule), the cameras and
   lights, the pixel rays and their footprint rule, the brute-force reference of a pixel, and the
   quantile of the lit rule. CPU-only bench code (C99), not part of the library. Include after
   pf_bench_base.h (the clock, checked allocation) and tests/reference/pf_microsurface.h (the
   surface, its slopes, visibility and reference shading). */
#ifndef PIC_SCENES_H
#define PIC_SCENES_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pf_map.h" /* the pyramid layout of pic_trilinear_taps */

/* ---------------------------------------------------------------- settings */
#define MAP_SIZE        256     /* the height map: MAP_SIZE^2 texels, texel = 1 world unit */
#define BASE_SIGMA      0.1     /* slope deviation of the narrow Beckmann base lobe */
#define F0              1.0     /* Schlick f0: 1 = no Fresnel (a constant factor in both) */
#define LIT_FRACTION    0.05    /* lit = reference >= this times its 99th percentile */
#define SPHERE_TILES    128     /* map repetitions around the sphere's equator */
#define LOBE_CUTOFF     30.0    /* reference: texels whose base lobe at h is below exp(-30) of
                                   its peak (1e-13) are not marched (their term is taken as 0) */
#define VMF_ITER        24      /* EM iterations at most per lobe-pyramid texel (as bench/microsurface.c) */

static const double pic_pi = 3.14159265358979323846;

/* the plane: camera height (texels), pitch below the horizon and vertical field of view
   (degrees), the light's elevation and azimuth from +y (degrees) */
#define PLANE_CAM_HEIGHT 90.0
#define PLANE_PITCH_DEG  14.0
#define PLANE_FOV_DEG    40.0
#ifndef PLANE_LIGHT_ELEV
#  define PLANE_LIGHT_ELEV 20.0 /* 12 in the first version: mostly shadowed, mostly black */
#endif
#define PLANE_LIGHT_AZIM 10.0

/* the sphere: radius and camera distance (world units), vertical field of view (degrees) */
#define SPHERE_RADIUS    100.0
#define SPHERE_CAM_DIST  330.0
#define SPHERE_FOV_DEG   40.0

/* ---------------------------------------------------------------- small vector helpers */
static double v3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static void v3_normalize(double a[3])
{
    double l = sqrt(v3_dot(a, a));
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
}
static void v3_set(double a[3], double x, double y, double z)
{
    a[0] = x;
    a[1] = y;
    a[2] = z;
}
static int wrap_index(int i, int n) { return ((i % n) + n) % n; }

/* ---------------------------------------------------------------- the trilinear fetch */
/* The texels and weights of a trilinear fetch (GL's LINEAR_MIPMAP_LINEAR, pf_map.h's
   pf_mip_sample_trilinear with wrap) from a pyramid of pf_map.h's layout, C pf_reals a texel,
   at (u, v), fractions of the map (wrapped into [0, 1)), and lod (clamped to [0, levels - 1]):
   the 4 texels around (u, v) of level floor(lod) (texel centres, wrap), then those of the next
   level, each weighted by its level's share (1 - f, f) times its bilinear weight, in double.
   Texels of weight 0 are left out; returns how many are kept (at most 8). The callers sum what
   they need over the taps in this order: a mixture of the texels' vMF lobes (bench/pictures.c,
   bench/frame/frame.c), the HDF moments' channels (bench/pictures.c). */
typedef struct {
    const pf_real *tex[8]; /* the texel's first channel */
    double w[8];           /* its weight: the kept ones sum to 1 */
} pic_taps;

static int pic_trilinear_taps(const pf_real *pyr, int W, int H, int C, double u, double v, double lod, pic_taps *tp)
{
    const int nl = pf_mip_level_count(W, H);
    double fl;
    int l0, lv, t, n = 0;
    u -= floor(u);
    v -= floor(v);
    if (!(lod > 0.0)) lod = 0.0;
    if (lod > nl - 1) lod = nl - 1;
    l0 = (int)floor(lod);
    fl = lod - l0;
    for (lv = 0; lv < 2; ++lv) {
        int l = l0 + lv, lw, lh;
        double wl = lv ? fl : 1.0 - fl, x, y, fx, fy;
        long ix, iy;
        const pf_real *lev;
        if (!(wl > 0.0) || l >= nl) continue;
        lw = pf_mip_level_size(W, l);
        lh = pf_mip_level_size(H, l);
        lev = pyr + pf_mip_level_offset(W, H, l) * C;
        x = u * lw - 0.5;
        y = v * lh - 0.5;
        ix = (long)floor(x);
        iy = (long)floor(y);
        fx = x - (double)ix;
        fy = y - (double)iy;
        for (t = 0; t < 4; ++t) {
            double wt = wl * ((t & 1) ? fx : 1.0 - fx) * ((t & 2) ? fy : 1.0 - fy);
            int tx = wrap_index((int)(ix + (t & 1)), lw), ty = wrap_index((int)(iy + (t >> 1)), lh);
            if (!(wt > 0.0)) continue;
            tp->tex[n] = lev + ((size_t)ty * (size_t)lw + (size_t)tx) * (size_t)C;
            tp->w[n++] = wt;
        }
    }
    return n;
}

/* ---------------------------------------------------------------- the pixels */
typedef struct {
    int hit;           /* 1 if the pixel sees the surface */
    double tx, ty;     /* hit point in texel coordinates (texel i spans [i, i + 1)) */
    double fp;         /* footprint side in texels (isotropic, capped at the map size) */
    double wo[3], wi[3]; /* view and light in the pixel's tangent frame, unit */
    double off[4];     /* the pixel's footprint: texel offsets of its x + 1 and y + 1 neighbours'
                          rays on the tangent plane, (off[0], off[1]) and (off[2], off[3]), each
                          shortened to the cap (bench/frame/frame.c's pixel-footprint reference) */
} pic_sample;

/* One texel of a reference footprint, kept between the two passes of shade_reference. */
typedef struct {
    int x, y;          /* unwrapped texel coordinates */
    double at;         /* projected area (m.wo)/(m.z) */
    double term;       /* its specular term times at, when visible both ways in the full march */
    signed char vo, vi; /* full-march visibility toward wo, wi (-1: not marched) */
    signed char cut;    /* 1: below the lobe cutoff, not marched (its term is taken as 0) */
} ref_texel;

/* Camera: position, orthonormal right/up/forward, tan of half the vertical field of view. */
typedef struct {
    double pos[3], right[3], up[3], fwd[3];
    double tan_half;
    int w, h;
} pic_camera;

static void camera_ray(const pic_camera *c, double px, double py, double d[3])
{
    double sx = (2.0 * (px + 0.5) / c->w - 1.0) * c->tan_half * c->w / c->h;
    double sy = (1.0 - 2.0 * (py + 0.5) / c->h) * c->tan_half;
    int k;
    for (k = 0; k < 3; ++k) d[k] = c->fwd[k] + sx * c->right[k] + sy * c->up[k];
    v3_normalize(d);
}

/* Intersection of the ray (o, d) with the plane through p with normal n; 0 if parallel. */
static int ray_plane(const double o[3], const double d[3], const double p[3], const double n[3],
                     double hit[3])
{
    double dn = v3_dot(d, n), op[3], t;
    int k;
    if (fabs(dn) < 1e-12) return 0;
    for (k = 0; k < 3; ++k) op[k] = p[k] - o[k];
    t = v3_dot(op, n) / dn;
    if (!(t > 0.0)) return 0;
    for (k = 0; k < 3; ++k) hit[k] = o[k] + t * d[k];
    return 1;
}

/* The footprint in texels from the two neighbour rays, intersected with the tangent plane at
   the hit; du[k], dv[k]: texel coordinates per unit world length along the tangent axes
   (tx_axis, ty_axis). Capped at the map size. off4 (optional) receives the two neighbours'
   offsets in texels, (x + 1: off4[0], off4[1]; y + 1: off4[2], off4[3]), each shortened to the
   cap ((cap, 0), (0, cap) where a neighbour ray misses the plane). */
static double footprint_texels(const pic_camera *c, int i, int j, const double hit[3],
                               const double n[3], const double tx_axis[3], const double ty_axis[3],
                               double tex_per_x, double tex_per_y, double cap, double off4[4])
{
    double best = 0.0;
    int k, e;
    if (off4) off4[0] = cap, off4[1] = 0.0, off4[2] = 0.0, off4[3] = cap;
    for (e = 0; e < 2; ++e) {
        double d[3], h2[3], off[3], a, b, l;
        camera_ray(c, i + (e == 0 ? 1.0 : 0.0), j + (e == 1 ? 1.0 : 0.0), d);
        if (!ray_plane(c->pos, d, hit, n, h2)) return cap;
        for (k = 0; k < 3; ++k) off[k] = h2[k] - hit[k];
        a = v3_dot(off, tx_axis) * tex_per_x;
        b = v3_dot(off, ty_axis) * tex_per_y;
        l = sqrt(a * a + b * b);
        if (l > best) best = l;
        if (off4) {
            double sc = l > cap ? cap / l : 1.0;
            off4[2 * e] = a * sc, off4[2 * e + 1] = b * sc;
        }
    }
    return best < cap ? best : cap;
}

static void camera_look(pic_camera *c, const double pos[3], const double fwd[3], double fov_deg,
                        int w, int h)
{
    double world_up[3] = {0.0, 0.0, 1.0};
    int k;
    for (k = 0; k < 3; ++k) c->pos[k] = pos[k];
    for (k = 0; k < 3; ++k) c->fwd[k] = fwd[k];
    v3_normalize(c->fwd);
    /* right = fwd x up, up = right x fwd */
    v3_set(c->right, c->fwd[1] * world_up[2] - c->fwd[2] * world_up[1],
           c->fwd[2] * world_up[0] - c->fwd[0] * world_up[2],
           c->fwd[0] * world_up[1] - c->fwd[1] * world_up[0]);
    v3_normalize(c->right);
    v3_set(c->up, c->right[1] * c->fwd[2] - c->right[2] * c->fwd[1],
           c->right[2] * c->fwd[0] - c->right[0] * c->fwd[2],
           c->right[0] * c->fwd[1] - c->right[1] * c->fwd[0]);
    c->tan_half = tan(0.5 * fov_deg * pic_pi / 180.0);
    c->w = w;
    c->h = h;
}

/* ---------------------------------------------------------------- the two scenes
   PIC_PLANE: the plane z = 0 seen toward the horizon, tangent frame = world frame, texel = 1
   world unit; the light one direction for every pixel. PIC_SPHERE: a sphere of radius R at the
   origin, pole along +z; longitude phi, colatitude theta; texture u = phi / (2 pi) * tiles,
   v = (1 - theta / pi) * tiles / 2 (texels square at the equator). motion (0: the still frame
   of both programs): the plane's camera moved forward (+y) by that many texels; the sphere
   turned about its pole by that many radians (the texture moves under a fixed camera). */
enum { PIC_PLANE = 0, PIC_SPHERE = 1 };

/* The camera and the light (world frame) of scene which, for a w x h image. */
static void pic_scene_view(int which, int w, int h, double motion, pic_camera *cam, double light[3])
{
    if (which == PIC_PLANE) {
        double pos[3] = {0.0, 0.0, PLANE_CAM_HEIGHT}, fwd[3];
        double pitch = PLANE_PITCH_DEG * pic_pi / 180.0;
        double el = PLANE_LIGHT_ELEV * pic_pi / 180.0, az = PLANE_LIGHT_AZIM * pic_pi / 180.0;
        pos[1] = motion;
        v3_set(fwd, 0.0, cos(pitch), -sin(pitch));
        camera_look(cam, pos, fwd, PLANE_FOV_DEG, w, h);
        v3_set(light, sin(az) * cos(el), cos(az) * cos(el), sin(el));
    } else {
        double pos[3] = {0.0, -SPHERE_CAM_DIST, 0.25 * SPHERE_RADIUS}, fwd[3];
        v3_set(fwd, -pos[0], -pos[1], -pos[2]);
        camera_look(cam, pos, fwd, SPHERE_FOV_DEG, w, h);
        v3_set(light, 0.5, -0.6, 0.6); /* toward the light: upper right, in front of the sphere */
        v3_normalize(light);
    }
}

/* Pixel (i, j) of scene which: p->hit 0 (and the rest untouched) when its ray misses the
   surface; W, H: the map's size in texels (the footprint's cap is W). */
static void pic_scene_pixel(int which, const pic_camera *cam, const double light[3], double W, double H, double motion,
                            int i, int j, pic_sample *p)
{
    double d[3], hit[3];
    int k;
    camera_ray(cam, i, j, d);
    if (which == PIC_PLANE) {
        double pz[3] = {0.0, 0.0, 0.0}, nz[3] = {0.0, 0.0, 1.0}, ax[3] = {1, 0, 0}, ay[3] = {0, 1, 0};
        if (d[2] > -1e-3 || !ray_plane(cam->pos, d, pz, nz, hit)) return;
        p->hit = 1;
        p->tx = hit[0];
        p->ty = hit[1];
        v3_set(p->wo, -d[0], -d[1], -d[2]);
        v3_set(p->wi, light[0], light[1], light[2]);
        p->fp = footprint_texels(cam, i, j, hit, nz, ax, ay, 1.0, 1.0, W, p->off);
    } else {
        double b, c, disc, t, n[3], tu[3], tv[3], phi, theta, st;
        b = v3_dot(cam->pos, d);
        c = v3_dot(cam->pos, cam->pos) - SPHERE_RADIUS * SPHERE_RADIUS;
        disc = b * b - c;
        if (disc <= 0.0) return;
        t = -b - sqrt(disc);
        if (t <= 0.0) return;
        for (k = 0; k < 3; ++k) hit[k] = cam->pos[k] + t * d[k];
        for (k = 0; k < 3; ++k) n[k] = hit[k] / SPHERE_RADIUS;
        phi = atan2(n[1], n[0]);
        if (phi < 0.0) phi += 2.0 * pic_pi;
        theta = acos(n[2] > 1.0 ? 1.0 : (n[2] < -1.0 ? -1.0 : n[2]));
        st = sin(theta);
        if (st < 1e-6) return;
        /* tangent x: increasing longitude; tangent y: toward the north pole (n x tu) */
        v3_set(tu, -sin(phi), cos(phi), 0.0);
        v3_set(tv, n[1] * tu[2] - n[2] * tu[1], n[2] * tu[0] - n[0] * tu[2], n[0] * tu[1] - n[1] * tu[0]);
        p->hit = 1;
        p->tx = (phi - motion) / (2.0 * pic_pi) * SPHERE_TILES * W;
        p->ty = (1.0 - theta / pic_pi) * 0.5 * SPHERE_TILES * H;
        /* texels per world unit: along tu, 1/(R sin theta) radians of longitude; along tv,
           1/R radians of latitude */
        p->fp = footprint_texels(cam, i, j, hit, n, tu, tv, SPHERE_TILES * W / (2.0 * pic_pi * SPHERE_RADIUS * st),
                                 SPHERE_TILES * H / (2.0 * pic_pi * SPHERE_RADIUS), W, p->off);
        v3_set(p->wo, -v3_dot(d, tu), -v3_dot(d, tv), -v3_dot(d, n));
        v3_set(p->wi, v3_dot(light, tu), v3_dot(light, tv), v3_dot(light, n));
        if (p->wo[2] <= 1e-6) p->wo[2] = 1e-6; /* silhouette rounding */
        v3_normalize(p->wo);
    }
}

/* ---------------------------------------------------------------- the brute-force reference */
static int footprint_side(double fp)
{
    int n = (int)floor(fp + 0.5);
    return n < 1 ? 1 : n;
}

static int footprint_start(double t, int n) { return (int)floor(t - 0.5 * n + 0.5); }

typedef struct {
    double full;    /* the reference: occluders anywhere on the (periodic) surface */
    double inbox;   /* occluders inside the footprint box only */
    double noise;   /* subsampled footprints: half the difference of the two checkerboard
                       halves of the samples (~ the sampling deviation); 0 otherwise */
    double t_full, t_inbox; /* seconds spent on each */
    /* slopes only, no visibility: the NDF at the half vector's slope of the shaded texels
       (the mean of their base lobes) and of the Gaussian with the same texels' moments plus
       the base variance (what LEADR assumes, eqs. 8-10) */
    double ndf_texels, ndf_gauss;
} ref_result;

/* The ndf_texels / ndf_gauss pair of a ref_result: from the shaded texels' sums (weight w:
   their count or covered area) of the NDF at s_h = (shx, shy) (ndf, base lobes' exponentials)
   and of the slope moments mom = {sx, sy, sx^2, sy^2, sx sy}, the Gaussian with those moments
   plus the base variance (LEADR eqs. 8-10). */
static void pic_ndf_pair(ref_result *r, double ndf, const double mom[5], double w, double shx, double shy)
{
    double var = BASE_SIGMA * BASE_SIGMA, mx = mom[0] / w, my = mom[1] / w;
    double cxx = mom[2] / w - mx * mx + var, cyy = mom[3] / w - my * my + var;
    double cxy = mom[4] / w - mx * my, det = cxx * cyy - cxy * cxy;
    double dx = shx - mx, dy = shy - my;
    r->ndf_texels = ndf / w / (2.0 * pic_pi * var);
    r->ndf_gauss = exp(-0.5 * (cyy * dx * dx - 2.0 * cxy * dx * dy + cxx * dy * dy) / det) / (2.0 * pic_pi * sqrt(det));
}

/* The half vector's slope s_h = -(wo + wi).xy / (wo + wi).z of a sample, 0 when it is not lit
   (light below the surface or half vector at or below it); returns whether it is lit. */
static int pic_half_slope(const pic_sample *p, double *shx, double *shy)
{
    double hz = p->wo[2] + p->wi[2];
    int lit = p->wi[2] > 0.0 && hz > 0.0;
    *shx = lit ? -(p->wo[0] + p->wi[0]) / hz : 0.0;
    *shy = lit ? -(p->wo[1] + p->wi[1]) / hz : 0.0;
    return lit;
}

/* Which direction the reference marches first: the light when its visibility is a map lookup
   (vis_light) or when it is the flatter direction (more often occluded, and an occluded march
   stops early), else the view. */
static int pic_light_first(const pic_sample *p, const unsigned char *vis_light)
{
    return vis_light != NULL || p->wi[2] * sqrt(p->wo[0] * p->wo[0] + p->wo[1] * p->wo[1]) <
                                    p->wo[2] * sqrt(p->wi[0] * p->wi[0] + p->wi[1] * p->wi[1]);
}

/* Brute force: the n x n box (or an evenly spaced ref_max^2 subset), one texel at a time
   through pfm_reference_shade (n = 1, visibility handled here), recombined with the texels'
   projected areas a_t = (m_t . wo)/(m_t . z) = wo.z - sx wo.x - sy wo.y (LEADR eq. 1): the
   footprint's value is sum_t V_o V_i spec_t a_t / sum_t a_t, which is pfm_reference_shade over
   the whole box when the box is shaded completely. A texel hidden in one direction contributes
   0 to the numerator and its a_t to the denominator, so the other direction is marched only
   when the first sees: the light first when its visibility is the map vis_light (the plane:
   one light direction in every pixel's frame; a lookup) or when it is the flatter direction
   (more often occluded, and an occluded march stops early), else the view first. Second pass
   (the in-box variant): the texels occluded in the full march are marched again with only the
   box's own height field as occluder (pfm_visible_box; a texel free in the full march is free
   in the box). full_only: the full march only (r.full, r.noise, r.t_full; the NDF terms and
   the in-box pass are skipped, as bench/frame/frame.c needs). scratch: ref_max^2 texels at
   least, the caller's (one per parallel item). */
static ref_result shade_reference(const pfm_surface *s, const unsigned char *vis_light, const pic_sample *p,
                                  int ref_max, int full_only, ref_texel *scratch)
{
    int n = footprint_side(p->fp), ns = n < ref_max ? n : ref_max, a, b, k = 0, q;
    int x0 = footprint_start(p->tx, n), y0 = footprint_start(p->ty, n);
    double num = 0.0, area = 0.0, half_num[2] = {0.0, 0.0}, half_area[2] = {0.0, 0.0};
    double num_box = 0.0, t0 = pfb_now_s(), t1, ndf = 0.0, mom[5] = {0, 0, 0, 0, 0};
    /* slope of the half vector: the texel's lobe at h is exp(-q) of its peak, q = |s_t -
       s_h|^2 / (2 sigma^2) (eq. 10) */
    double shx, shy;
    int lit = pic_half_slope(p, &shx, &shy), light_first = pic_light_first(p, vis_light);
    ref_result r;
    memset(&r, 0, sizeof r);
    for (b = 0; b < ns; ++b) {
        int yu = y0 + (int)(((double)b + 0.5) * n / ns), y = wrap_index(yu, s->h);
        for (a = 0; a < ns; ++a, ++k) {
            int xu = x0 + (int)(((double)a + 0.5) * n / ns), x = wrap_index(xu, s->w);
            ref_texel *e = &scratch[k];
            double sx, sy;
            pfm_slope(s, x, y, &sx, &sy);
            e->x = xu;
            e->y = yu;
            e->at = p->wo[2] - sx * p->wo[0] - sy * p->wo[1];
            e->term = 0.0;
            e->vo = e->vi = -1;
            e->cut = 1;
            area += e->at;
            half_area[(a + b) & 1] += e->at;
            mom[0] += sx;
            mom[1] += sy;
            mom[2] += sx * sx;
            mom[3] += sy * sy;
            mom[4] += sx * sy;
            if (lit && !full_only) {
                double qq = ((sx - shx) * (sx - shx) + (sy - shy) * (sy - shy)) /
                            (2.0 * BASE_SIGMA * BASE_SIGMA);
                ndf += exp(-qq);
            }
            /* a texel whose lobe is below exp(-LOBE_CUTOFF) of its peak at h adds nothing
               measurable whatever its visibility: not marched (vo stays -1) */
            if (!lit || !(e->at > 0.0) ||
                ((sx - shx) * (sx - shx) + (sy - shy) * (sy - shy)) /
                        (2.0 * BASE_SIGMA * BASE_SIGMA) >
                    LOBE_CUTOFF)
                continue;
            e->cut = 0;
            /* the term needs both directions visible: the second march only when the first
               sees (light_first: the light's map, or the flatter direction, first) */
            if (light_first) {
                e->vi = (signed char)(vis_light ? vis_light[(size_t)y * s->w + x] : pfm_visible(s, x, y, p->wi));
                if (!e->vi) continue;
                e->vo = (signed char)pfm_visible(s, x, y, p->wo);
                if (!e->vo) continue;
            } else {
                e->vo = (signed char)pfm_visible(s, x, y, p->wo);
                if (!e->vo) continue;
                e->vi = (signed char)pfm_visible(s, x, y, p->wi);
                if (!e->vi) continue;
            }
            e->term = pfm_reference_shade(s, NULL, NULL, x, y, 1, p->wo, p->wi, BASE_SIGMA, F0)
                          .spec * e->at;
            num += e->term;
            half_num[(a + b) & 1] += e->term;
        }
    }
    t1 = pfb_now_s();
    r.t_full = t1 - t0;
    r.full = area > 0.0 ? num / area : 0.0;
    if (ns < n && half_area[0] > 0.0 && half_area[1] > 0.0)
        r.noise = 0.5 * fabs(half_num[0] / half_area[0] - half_num[1] / half_area[1]);
    if (full_only) return r;
    if (lit) pic_ndf_pair(&r, ndf, mom, (double)k, shx, shy); /* P22 at s_h: texels' lobes, Gaussian of their moments */
    for (q = 0; q < k; ++q) {
        const ref_texel *e = &scratch[q];
        int x = wrap_index(e->x, s->w), y = wrap_index(e->y, s->h);
        int bx0 = wrap_index(x0, s->w), by0 = wrap_index(y0, s->h);
        if (e->cut) continue; /* not marched: negligible */
        if (e->vo == 1 && e->vi == 1) {
            num_box += e->term;
            continue;
        }
        /* visible in the box where visible in full (the box only removes occluders); else
           marched in the box, in the order of the full march */
        if (light_first) {
            if (e->vi != 1 && !pfm_visible_box(s, x, y, p->wi, bx0, by0, n)) continue;
            if (e->vo != 1 && !pfm_visible_box(s, x, y, p->wo, bx0, by0, n)) continue;
        } else {
            if (e->vo != 1 && !pfm_visible_box(s, x, y, p->wo, bx0, by0, n)) continue;
            if (e->vi != 1 && !pfm_visible_box(s, x, y, p->wi, bx0, by0, n)) continue;
        }
        num_box += pfm_reference_shade(s, NULL, NULL, x, y, 1, p->wo, p->wi, BASE_SIGMA, F0)
                       .spec * e->at;
    }
    r.inbox = area > 0.0 ? num_box / area : 0.0;
    r.t_inbox = pfb_now_s() - t1;
    return r;
}

/* ---------------------------------------------------------------- statistics */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* q-quantile (0..1) of v[0..n-1] (sorted copy, nearest rank). */
static double quantile(const double *v, int n, double q)
{
    double *c, r;
    int i;
    if (n <= 0) return 0.0;
    c = (double *)pfb_xmalloc(sizeof(double) * (size_t)n);
    memcpy(c, v, sizeof(double) * (size_t)n);
    qsort(c, (size_t)n, sizeof(double), cmp_double);
    i = (int)ceil(q * n) - 1;
    r = c[i < 0 ? 0 : (i >= n ? n - 1 : i)];
    free(c);
    return r;
}

#endif /* PIC_SCENES_H */

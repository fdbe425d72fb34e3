/* frame.frag - one pixel of bench/pictures.c's scenes, ray-cast analytically and shaded by the
   library's GLSL path from the moment pyramid stored as GPU textures (bench/frame/frame.c is
   the host and says what is measured).

   Compiled once per scene and method by bench/frame/run.sh:
     PFF_SCENE   0 plane toward the horizon, 1 sphere (the cameras, light and maps of
                 bench/pictures.c; the numbers come in the push constants from frame.c)
     PFF_METHOD  0 none (ray cast and fetch only: the baseline of the op counts), 1 LEADR,
                 2 naive mip-mapped normal, 3 Toksvig, 4 LEADR with the anisotropic filter in the
                 shader (up to 16 textureLod taps along the major axis, isotropic sampler),
                 5 and 6 vMF m = 4 and 8 (lobe pyramids, texelFetch of the 8 texels of a
                 trilinear fetch at the driver's lod), 7 LEADR with the horizon
                 (pf_horizon_leadr_specular_lod: the HDF array texture texH, the two stored
                 azimuths around wo and around wi, faded to LEADR by the lod), 8 vMF
                 m = 4 with the horizon (pf_horizon_vmf_specular_lod: method 5's lobes, the
                 slope-moment texel and method 7's HDF fetches); 7 and 8 fetch at an
                 explicit lod from the quad derivatives (main says why)
     PFF_ENCODED 1 (with PFF_METHOD 1): the moments stored in scaled UNORM (pf_encode.h:
                 16 or 8 bits, centred on the map's mean slope), decoded after the filtered
                 fetch with pf_slope_moments_decode and the map's encoding (uniform block Enc,
                 binding 5); the decode is affine with one reference per map, so the sampler's
                 trilinear and anisotropic blends of the stored texels still filter the moments
   Textures (one VkImage each, the whole mip chain of the library's CPU pyramid):
     texA = (E[x], E[y], E[x^2], E[y^2]) of the micro-slopes, texB = (E[xy], E[n]) with E[n]
     the unnormalized average unit normal (pf_normal_pyramid_from_normals); encoded (PFF_ENCODED):
     texA = the centred (E[x - rx], E[y - ry], E[(x - rx)^2], E[(y - ry)^2]), texB.x =
     E[(x - rx)(y - ry)] (an R texture), the UNORM values the sampler returns; texL, the lod
     probe (level l holds l everywhere), read with the same sampler and gradients.
   The texel coordinates' screen derivatives come from the 2x2 quad (dFdxFine, dFdyFine), as in
   an engine, and go to the sampler through textureGrad, so the driver picks the level of detail
   (and, with anisotropy, the probe line). Two fixes an engine also needs: the sphere's
   longitude seam (a jump of the whole tiled width, removed modulo that width) and quads that
   straddle the surface's edge (a neighbour that misses has no texel coordinate: there the
   pixel's own ray differentials are used, its neighbour rays meeting the tangent plane at the
   hit, bench/pictures.c's footprint rule).
   Outputs: o0 = (radiance, u, v in texels, 0 for no surface or 1 + the sampler's lod), o1 = (du/dx, dv/dx, du/dy, dv/dy) in texels. */
#version 450
#extension GL_GOOGLE_include_directive : require
#define PF_GLSL 1
#include "pf_core.h"
#include "pf_moments.h"
#include "pf_smith.h"
#include "pf_beckmann.h"
#include "pf_toksvig.h"
#if PFF_METHOD >= 5
#  include "pf_vmf.h"
#endif
#if PFF_METHOD == 7 || PFF_METHOD == 8
#  include "pf_gaussgrid.h"
#  include "pf_horizon.h"
#  define PFF_HOR_AZ 16          /* frame.c's HOR_AZ */
#  define PFF_HOR_LOD_FULL 2.0   /* HOR_LOD_FULL, HOR_LOD_SMITH */
#  define PFF_HOR_LOD_SMITH 6.0
#endif
#ifndef PFF_ENCODED
#  define PFF_ENCODED 0
#endif
#if PFF_ENCODED
#  include "pf_vmf.h" /* pf_encode.h's lobe decoder needs it; unused here, optimized out */
#  include "pf_encode.h"
#endif

layout(push_constant) uniform PC {
    vec4 pos;   /* camera position; w: tan of half the vertical field of view */
    vec4 right; /* w: image width in pixels */
    vec4 up;    /* w: image height */
    vec4 fwd;   /* w: base slope variance (BASE_SIGMA^2) */
    vec4 light; /* unit vector toward the light (world); w: Schlick f0 */
    vec4 map;   /* map width, height (texels), sphere tiles, sphere radius */
    vec4 motion; /* x: the sphere's turn about its pole (radians; the texture moves, frame and light stay) */
} pc;
#if PFF_ENCODED
layout(set = 0, binding = 5) uniform Enc { /* the map's pf_slope_encoding, in its member order */
    vec4 enc0; /* ref_x, ref_y, off_x, off_y */
    vec4 enc1; /* off_xx, off_yy, off_xy, sc_x */
    vec4 enc2; /* sc_y, sc_xx, sc_yy, sc_xy */
} ue;
#endif
layout(set = 0, binding = 0) uniform sampler2D texA;
layout(set = 0, binding = 1) uniform sampler2D texB;
layout(set = 0, binding = 2) uniform sampler2D texL; /* the lod probe: every texel of level l is l */
#if PFF_METHOD == 5 || PFF_METHOD == 8
layout(set = 0, binding = 3) uniform sampler2DArray texV; /* vMF lobe pyramid, m = 4: layer j = lobe j */
const int PFF_LOBES = 4;
#elif PFF_METHOD == 6
layout(set = 0, binding = 4) uniform sampler2DArray texV; /* m = 8 */
const int PFF_LOBES = 8;
#endif
#if PFF_METHOD == 7 || PFF_METHOD == 8
/* the HDF pyramid (PF_HORIZON_MOMENTS): layer j = azimuth j, (E[T], E[T^2], E[S T], unused) */
layout(set = 0, binding = 6) uniform sampler2DArray texH;
#endif
layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;

const float PI = 3.14159265358979323846;

vec3 camera_ray(vec2 frag)
{
    float w = pc.right.w, h = pc.up.w;
    float sx = (2.0 * frag.x / w - 1.0) * pc.pos.w * w / h;
    float sy = (1.0 - 2.0 * frag.y / h) * pc.pos.w;
    return normalize(pc.fwd.xyz + sx * pc.right.xyz + sy * pc.up.xyz);
}

/* The hit of ray d: texel coordinates (unwrapped), the tangent frame (tu, tv, n) and the
   texels per world unit along tu and tv. false: no surface. */
bool ray_cast(vec3 d, out vec2 t, out vec3 tu, out vec3 tv, out vec3 n, out vec2 tex_per, out vec3 hit)
{
    t = vec2(0.0); tu = vec3(1, 0, 0); tv = vec3(0, 1, 0); n = vec3(0, 0, 1); tex_per = vec2(1.0); hit = vec3(0.0);
#if PFF_SCENE == 0
    if (d.z > -1e-3) return false;
    hit = pc.pos.xyz + (-pc.pos.z / d.z) * d;
    t = hit.xy;
    return true;
#else
    float R = pc.map.w, b = dot(pc.pos.xyz, d), c = dot(pc.pos.xyz, pc.pos.xyz) - R * R, disc = b * b - c;
    if (disc <= 0.0) return false;
    float s = -b - sqrt(disc);
    if (s <= 0.0) return false;
    hit = pc.pos.xyz + s * d;
    n = hit / R;
    float phi = atan(n.y, n.x);
    if (phi < 0.0) phi += 2.0 * PI;
    float theta = acos(clamp(n.z, -1.0, 1.0)), st = sin(theta);
    if (st < 1e-6) return false;
    tu = vec3(-sin(phi), cos(phi), 0.0);
    tv = cross(n, tu);
    t = vec2((phi - pc.motion.x) / (2.0 * PI) * pc.map.z * pc.map.x, (1.0 - theta / PI) * 0.5 * pc.map.z * pc.map.y);
    tex_per = vec2(pc.map.z * pc.map.x / (2.0 * PI * R * st), pc.map.z * pc.map.y / (2.0 * PI * R));
    return true;
#endif
}

/* Texel offset of the neighbour pixel's ray on the tangent plane at hit (pictures.c's
   footprint_texels, one axis). */
vec2 ray_diff(vec2 frag, vec3 hit, vec3 n, vec3 tu, vec3 tv, vec2 tex_per)
{
    vec3 d = camera_ray(frag);
    float dn = dot(d, n);
    if (abs(dn) < 1e-12) return vec2(pc.map.x, 0.0);
    vec3 off = pc.pos.xyz + (dot(hit - pc.pos.xyz, n) / dn) * d - hit;
    return vec2(dot(off, tu) * tex_per.x, dot(off, tv) * tex_per.y);
}

void main()
{
    vec3 d = camera_ray(gl_FragCoord.xy), tu, tv, n, hit;
    vec2 t, tex_per;
    bool ok = ray_cast(d, t, tu, tv, n, tex_per, hit);
    float fh = ok ? 1.0 : 0.0;
    /* Everything below runs in every lane of the quad (no early return: derivatives, and the
       texture fetches that take them, need uniform control flow). Quad derivatives: */
    vec2 gx = dFdxFine(t), gy = dFdyFine(t);
    float hx = dFdxFine(fh), hy = dFdyFine(fh);
    bool edge = abs(hx) + abs(hy) > 0.0;
#if PFF_SCENE == 1
    float period = pc.map.z * pc.map.x; /* the seam: u jumps by the tiled width */
    gx.x -= period * round(gx.x / period);
    gy.x -= period * round(gy.x / period);
#endif
    /* a lane that misses takes a neighbour's texel coordinate (the quad's values reached
       through the fine derivatives), so that a driver differentiating the coordinate itself
       sees the surface's own spacing, not a jump to 0 */
    float sx = (int(gl_FragCoord.x) & 1) == 1 ? -1.0 : 1.0, sy = (int(gl_FragCoord.y) & 1) == 1 ? -1.0 : 1.0;
    vec2 t_x = t + sx * gx, t_y = t + sy * gy, t_xy = t_y + sx * dFdxFine(t_y);
    float h_x = fh + sx * hx, h_y = fh + sy * hy;
    vec2 tf = ok ? t : (h_x > 0.5 ? t_x : (h_y > 0.5 ? t_y : t_xy));
    if (ok && edge) {
        gx = ray_diff(gl_FragCoord.xy + vec2(1.0, 0.0), hit, n, tu, tv, tex_per);
        gy = ray_diff(gl_FragCoord.xy + vec2(0.0, 1.0), hit, n, tu, tv, tex_per);
    }
    vec3 wo = vec3(-dot(d, tu), -dot(d, tv), -dot(d, n));
    vec3 wi = vec3(dot(pc.light.xyz, tu), dot(pc.light.xyz, tv), dot(pc.light.xyz, n));
#if PFF_SCENE == 1
    wo.z = max(wo.z, 1e-6); /* silhouette rounding, as pictures.c */
    wo = normalize(wo);
#endif
    /* unwrapped: REPEAT wraps it, and a driver that differentiates the coordinate itself
       (lavapipe's anisotropic filter does) sees no jump at the tiles' edges */
    vec2 sz = pc.map.xy, uv = tf / sz;
    vec4 a = textureGrad(texA, uv, gx / sz, gy / sz);
    vec4 b = textureGrad(texB, uv, gx / sz, gy / sz);
    /* the level of detail the sampler used, read back: the probe's levels hold their index, so
       its trilinear sample is the driver's lod (clamped to the chain) */
    float lod = textureGrad(texL, uv, gx / sz, gy / sz).r;
    float L;
    float base_var = pc.fwd.w, f0 = pc.light.w;
    float lod_s = lod; /* the level the shading uses (the fade, the lobes' texelFetch level) */
#if PFF_METHOD == 7 || PFF_METHOD == 8
    /* The horizon methods fetch at an explicit lod, log2 of the longer texel derivative (the
       Vulkan rule, clamped to the chain), the same formula as their CPU path, as engines do for
       array textures; the sampler still filters (texels, wrap, bilinear weights, level blend).
       With the driver's own lod (textureGrad) they were 1.144% (LEADR) and 1.182% (vMF 4) off the
       CPU path at log2(rho_max) (full plane; 1.15% and 1.21% BENCH_QUICK): lavapipe's lod is off
       by 0.022 level on average, and (BENCH_QUICK) the fade alone from the explicit lod left LEADR's at 1.16% (the moment and
       HDF fetches carry it; the fade's share is 0.21%) while vMF's lobes at the explicit level
       took that row to 0.18%. */
    float lod_e = clamp(log2(max(max(length(gx), length(gy)), 1e-30)), 0.0, float(textureQueryLevels(texA) - 1));
    lod_s = lod_e;
    a = textureLod(texA, uv, lod_e);
    b = textureLod(texB, uv, lod_e);
#endif
    pf_vec3 vo = pf_vec3_make(wo.x, wo.y, wo.z), vi = pf_vec3_make(wi.x, wi.y, wi.z);
#if PFF_METHOD == 7 || PFF_METHOD == 8
    /* the horizon methods' inputs: the slope-moment texel, and the HDF moments of the two stored
       azimuths around each direction, filtered by the same sampler and gradients as the slope
       moments (the HDF moments are linear: a blend of texels filters them), each pair mixed by
       pf_hdf_moments_lerp; all at the explicit lod_e above */
    pf_slope_stats hor_st = pf_slope_moments_stats(pf_slope_moments_make(a.x, a.y, a.z, a.w, b.x), base_var);
    pf_horizon_azimuth zo = pf_horizon_azimuth_of(vo, PFF_HOR_AZ), zi = pf_horizon_azimuth_of(vi, PFF_HOR_AZ);
    vec4 h0 = textureLod(texH, vec3(uv, float(zo.i0)), lod_e), h1 = textureLod(texH, vec3(uv, float(zo.i1)), lod_e);
    vec4 h2 = textureLod(texH, vec3(uv, float(zi.i0)), lod_e), h3 = textureLod(texH, vec3(uv, float(zi.i1)), lod_e);
    pf_hdf_moments hor_mo = pf_hdf_moments_lerp(pf_hdf_moments_make(h0.x, h0.y, h0.z), pf_hdf_moments_make(h1.x, h1.y, h1.z), zo.f);
    pf_hdf_moments hor_mi = pf_hdf_moments_lerp(pf_hdf_moments_make(h2.x, h2.y, h2.z), pf_hdf_moments_make(h3.x, h3.y, h3.z), zi.f);
#endif
#if PFF_METHOD == 1
    /* LEADR (Dupuy et al. 2013 eq. 17) from the filtered moments */
#  if PFF_ENCODED
    /* the filtered UNORM channels decoded by the map's affine map (pf_encode.h (1)) */
    pf_slope_encoding enc = pf_slope_encoding(ue.enc0.x, ue.enc0.y, ue.enc0.z, ue.enc0.w, ue.enc1.x, ue.enc1.y, ue.enc1.z,
                                              ue.enc1.w, ue.enc2.x, ue.enc2.y, ue.enc2.z, ue.enc2.w);
    pf_slope_stats st = pf_slope_moments_stats(pf_slope_moments_decode(pf_slope_moments_make(a.x, a.y, a.z, a.w, b.x), enc), base_var);
#  else
    pf_slope_stats st = pf_slope_moments_stats(pf_slope_moments_make(a.x, a.y, a.z, a.w, b.x), base_var);
#  endif
    L = pf_leadr_specular(vo, vi, st, f0);
#elif PFF_METHOD == 2
    /* the mip-mapped normal: the base lobe alone around the filtered normal */
    pf_slope_stats st = pf_slope_moments_stats(pf_slope_moments_from_normal(pf_vec3_make(b.y, b.z, b.w)), base_var);
    L = pf_leadr_specular(vo, vi, st, f0);
#elif PFF_METHOD == 3
    /* Toksvig: the base Beckmann roughness widened by the variance the filtered normal's
       shortening implies (pf_toksvig.h), around that normal */
    pf_vec3 mu = pf_vec3_make(b.y, b.z, b.w);
    float m2 = pf_toksvig_beckmann_m(sqrt(2.0 * base_var), pf_toksvig_variance_from_normal(mu));
    pf_slope_stats st = pf_slope_moments_stats(pf_slope_moments_from_normal(mu), 0.5 * m2 * m2);
    L = pf_leadr_specular(vo, vi, st, f0);
#elif PFF_METHOD == 4
#  ifndef PFF_TAP_DENSITY
#    define PFF_TAP_DENSITY 1.0
#  endif
    /* LEADR with the anisotropic filter done in the shader, as engines do for moment maps: the
       pixel's footprint (the parallelogram of the quad derivatives) cut into N equal segments
       along its major axis, N = min(ceil(d rho_max / rho_min), 16 d) with the tap density d =
       PFF_TAP_DENSITY, one trilinear textureLod tap at each segment's centre at lod
       log2(rho_max / N) (at d = 1 each tap's box spans its segment), the moments averaged
       (they are linear), LEADR once. The sampler stays isotropic (maxAnisotropy 1). d = 1:
       d = 2 (finer taps, twice as many) measured worse on both scenes (BENCH_QUICK, pixel
       reference: plane 50.3% vs 49.7%, sphere 30.3% vs 28.9%). rho_min taken as the
       parallelogram's own width across the major axis, |det(gx, gy)| / rho_max, moved the
       plane by a tenth of a point (49.6% vs 49.7%): not kept. */
    float rx = length(gx), ry = length(gy), rmax = max(rx, ry), rmin = min(rx, ry);
    float N = clamp(ceil(PFF_TAP_DENSITY * rmax / max(rmin, 1e-6 * rmax + 1e-30)), 1.0, 16.0 * PFF_TAP_DENSITY);
    vec2 dmaj = (rx > ry ? gx : gy) / sz;
    float lodm = max(log2(max(rmax / N, 1e-30)), 0.0);
    vec4 sa = vec4(0.0), sb = vec4(0.0);
    for (int i = 0; i < 32; ++i) {
        if (float(i) >= N) break;
        vec2 q = uv + ((float(i) + 0.5) / N - 0.5) * dmaj;
        sa += textureLod(texA, q, lodm);
        sb += textureLod(texB, q, lodm);
    }
    a = sa / N;
    b = sb / N;
    pf_slope_stats st = pf_slope_moments_stats(pf_slope_moments_make(a.x, a.y, a.z, a.w, b.x), base_var);
    L = pf_leadr_specular(vo, vi, st, f0);
#elif PFF_METHOD == 7
    /* LEADR with the reflecting facets' horizon visibility instead of Smith's G (pf_horizon.h),
       faded to LEADR between levels PFF_HOR_LOD_FULL and PFF_HOR_LOD_SMITH (hor_* above) */
    L = pf_horizon_leadr_specular_lod(vo, vi, hor_st, base_var, hor_mo, hor_mi, f0, lod_s, PFF_HOR_LOD_FULL, PFF_HOR_LOD_SMITH);
#elif PFF_METHOD >= 5
    /* vMF lobes (Wu et al. 2019 eqs. 4-5, pf_vmf.h): a mixture is not filtered by averaging its
       parameters, so the 8 texels a trilinear fetch at the driver's lod touches are read with
       texelFetch and their lobes summed with the trilinear weights (bench/pictures.c's
       shade_vmf; texel centres, wrap) */
    pf_vmf_sum sum = pf_vmf_sum_zero();
    int nl = textureQueryLevels(texV), l0 = int(floor(lod_s));
    float fl = lod_s - float(l0);
    for (int lv = 0; lv < 2; ++lv) {
        int l = l0 + lv;
        float wl = lv == 1 ? fl : 1.0 - fl;
        if (!(wl > 0.0) || l >= nl) continue;
        /* the level's size from level 0's, not textureSize(texV, l): lavapipe answers a size
           query with one lane's lod for all the lanes it runs together, so a pixel whose level
           differs from that lane's got another level's size and wrong texels (GPU 0 where
           the CPU gives the lobes' value, at lods within ~0.01 of an integer) */
        ivec2 ls = max(textureSize(texV, 0).xy >> l, ivec2(1));
        vec2 x = fract(uv) * vec2(ls) - 0.5, f = x - floor(x);
        ivec2 i0 = ivec2(floor(x));
        for (int k = 0; k < 4; ++k) {
            float wt = wl * ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k & 2) != 0 ? f.y : 1.0 - f.y);
            if (!(wt > 0.0)) continue;
            ivec2 ti = (i0 + ivec2(k & 1, k >> 1) + ls) % ls;
            for (int j = 0; j < PFF_LOBES; ++j) {
                vec4 q = texelFetch(texV, ivec3(ti, j), l); /* (mu.x, mu.y, kappa, amp) */
                sum = pf_vmf_sum_add(sum, pf_vmf_lobe_make(wt * q.w, q.x, q.y, q.z), vo, vi, base_var);
            }
        }
    }
#  if PFF_METHOD == 8
    /* the lobes' specular with the reflecting facets' horizon visibility (conditioned on the
       slope-moment texel's statistics, pf_horizon_vmf_specular), faded to pf_vmf_sum_specular */
    L = pf_horizon_vmf_specular_lod(sum, vo, vi, hor_st, base_var, hor_mo, hor_mi, f0, lod_s, PFF_HOR_LOD_FULL, PFF_HOR_LOD_SMITH);
#  else
    L = pf_vmf_sum_specular(sum, vo, vi, f0);
#  endif
#else
    L = a.x + a.y + a.z + a.w + b.x + b.y + b.z + b.w + wo.x + wi.x; /* keeps the fetch alive */
#endif
    o0 = ok ? vec4(L, t, 1.0 + lod) : vec4(0.0);
    o1 = ok ? vec4(gx, gy) : vec4(0.0);
}

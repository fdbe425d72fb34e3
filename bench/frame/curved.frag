/* curved.frag - one pixel of bench/specaa_scenes.h's curved scenes (an orthographic sphere or
   cylinder, plain or normal-mapped) ray-cast analytically and shaded by the specular AA forms of
   pf_specaa.h (bench/frame/curved_shade.h, shared with the CPU path) from the map's moment
   pyramid stored as GPU textures; the geometry kernel's normal derivatives and the texture
   coordinates' derivatives from the 2x2 quad (dFdxFine, dFdyFine), as in an engine.
   bench/frame/frame_curved.h is the host part and says what is measured.
   Compiled once per form by bench/frame/run.sh: PFC_METHOD = FC_NONE .. FC_CROSS. The pyramid is
   read at the lod computed here (textureLod at log2 of the longer texel derivative, the CPU
   path's formula), so that the CPU path checks the shader; PFC_DRIVER_LOD: at the driver's lod
   instead (textureGrad), to show the driver's lod approximation. PFC_TAPS: anisotropic reads
   done in the shader by EXT_texture_filter_anisotropic's rule (aniso() below, the CPU path's and
   bench/specaa.c's sc_fetch_aniso); PFC_ANISO: the same reads through textureGrad on the
   driver's anisotropic sampler (the host binds one with maxAnisotropy 16). FC_QUAD reads the four
   quadrants (st -+ gx/4 -+ gy/4, half the footprint), FC_CROSS one read of the whole footprint.
   Textures: texA = (E[x], E[y], E[x^2], E[y^2]) of the map's slopes, texB = (E[xy], the averaged
   unit normal), the whole mip chain, trilinear, REPEAT.
   Outputs: o0 = (radiance, s, t in texels, 1 on the surface else 0), o1 = (ds/dx, dt/dx, ds/dy,
   dt/dy) in texels. */
#version 450
#extension GL_GOOGLE_include_directive : require
#define PF_GLSL 1
#include "pf_core.h"
#include "pf_moments.h"
#include "pf_smith.h"
#include "pf_beckmann.h"
#include "pf_vmf.h"
#include "pf_specaa.h"
#include "curved_shade.h"

layout(push_constant) uniform PC {
    vec4 geo;   /* image centre x, y (pixels), radius R (pixels), image width */
    vec4 par;   /* x: 0 sphere, 1 cylinder; y: 1 normal-mapped; z: base variance alpha^2/2 */
    vec4 light; /* unit vector toward the light (world) */
} pc;
layout(set = 0, binding = 0) uniform sampler2D texA;
layout(set = 0, binding = 1) uniform sampler2D texB;
layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;

const float PI = 3.14159265358979323846;
const float SCN = 256.0;                    /* specaa_scenes.h's SC_N */
const float KTX = 256.0 * 2.0 / (2.0 * PI); /* texels per radian: SC_N SC_REP / (2 pi) */

/* the macro surface at image point p (specaa_scenes.h's sc_eval): false off the surface, where
   the point is first moved radially to 0.999 R (frame_curved.h's fc_eval does the same), so a
   quad at the silhouette differentiates a continuous field */
bool geo(vec2 p, out vec3 N, out vec3 T, out vec3 B, out vec2 st)
{
    float dx = (p.x - pc.geo.x) / pc.geo.z, dy = (p.y - pc.geo.y) / pc.geo.z, u, v;
    bool hit;
    if (pc.par.x < 0.5) {
        float r2 = dx * dx + dy * dy;
        hit = r2 < 1.0;
        if (!hit) {
            float k = 0.999 / sqrt(r2);
            dx *= k;
            dy *= k;
            r2 = dx * dx + dy * dy;
        }
        N = vec3(dx, dy, sqrt(1.0 - r2));
        u = atan(N.x, N.z);
        v = asin(dy);
        T = vec3(cos(u), 0.0, -sin(u));
        B = vec3(-sin(u) * sin(v), cos(v), -cos(u) * sin(v));
    } else {
        hit = dx * dx < 1.0;
        if (!hit) dx = clamp(dx, -0.999, 0.999);
        N = vec3(dx, 0.0, sqrt(1.0 - dx * dx));
        u = atan(N.x, N.z);
        v = dy;
        T = vec3(cos(u), 0.0, -sin(u));
        B = vec3(0.0, 1.0, 0.0);
    }
    st = vec2(u, v) * KTX;
    return hit;
}

/* the moments over the footprint (gx, gy) x scale centred at st + ox gx + oy gy (texels), as a
   GPU's anisotropic filter reads (EXT_texture_filter_anisotropic): N = min(ceil(major/minor), 16)
   trilinear taps evenly over the major axis at lod log2(major/N), averaged (the moments are
   linear); bench/specaa_scenes.h's sc_fetch_aniso */
pf_slope_moments aniso(vec2 st, vec2 gx, vec2 gy, float ox, float oy, float scale)
{
    float lx = scale * length(gx), ly = scale * length(gy), pmax = max(lx, ly), pmin = max(min(lx, ly), 1e-9);
    vec2 ax = lx >= ly ? gx : gy, c = st + ox * gx + oy * gy;
    int n = int(clamp(ceil(pmax / pmin), 1.0, 16.0));
    float lod = pmax / float(n) > 1.0 ? log2(pmax / float(n)) : 0.0;
    vec4 sa = vec4(0.0);
    float sb = 0.0;
    for (int i = 0; i < 16; ++i) {
        if (i >= n) break;
        vec2 u = (c + scale * ((float(i) + 0.5) / float(n) - 0.5) * ax) / SCN;
        sa += textureLod(texA, u, lod);
        sb += textureLod(texB, u, lod).x;
    }
    sa /= float(n);
    return pf_slope_moments_make(sa.x, sa.y, sa.z, sa.w, sb / float(n));
}

void main()
{
    vec3 N, T, B;
    vec2 st;
    bool hit = geo(gl_FragCoord.xy, N, T, B, st);
    /* every lane, uniform control flow: the quad's derivatives */
    vec3 dnx = dFdxFine(N), dny = dFdyFine(N);
    vec2 gx = dFdxFine(st), gy = dFdyFine(st);
#if defined(PFC_DRIVER_LOD) || defined(PFC_ANISO)
    vec4 a = textureGrad(texA, st / SCN, gx / SCN, gy / SCN), b = textureGrad(texB, st / SCN, gx / SCN, gy / SCN);
#elif defined(PFC_TAPS)
    pf_slope_moments af = aniso(st, gx, gy, 0.0, 0.0, 1.0);
    vec4 a = vec4(af.ex, af.ey, af.exx, af.eyy), b = vec4(af.exy, 0.0, 0.0, 1.0); /* no averaged normal: no vMF form reads so */
#else
    float lod_e = max(log2(max(max(length(gx), length(gy)), 1e-30)), 0.0);
    vec4 a = textureLod(texA, st / SCN, lod_e), b = textureLod(texB, st / SCN, lod_e);
#endif
    if (pc.par.y < 0.5) { /* no map: a flat micro-surface */
        a = vec4(0.0);
        b = vec4(0.0, 0.0, 0.0, 1.0);
    }
    /* the read's mean-slope derivatives (the cross term (4)) and the position's, P = (x, y, R n_z)
       in pixels (orthographic; the mean shift (5)): the quad's differences, uniform control flow */
    vec2 dmx = dFdxFine(a.xy), dmy = dFdyFine(a.xy);
    vec3 P = vec3(gl_FragCoord.xy, pc.geo.z * N.z), dpx = dFdxFine(P), dpy = dFdyFine(P);
    vec3 L = pc.light.xyz;
#if PFC_METHOD == FC_QUAD
    pf_slope_moments q[4];
    for (int k = 0; k < 4; ++k) {
        vec2 o = (vec2(float(k & 1), float(k >> 1)) - 0.5) * 0.5;
#ifdef PFC_TAPS
        q[k] = aniso(st, gx, gy, o.x, o.y, 0.5);
#else
        vec2 c = (st + o.x * gx + o.y * gy) / SCN;
        vec4 qa = textureGrad(texA, c, 0.5 * gx / SCN, 0.5 * gy / SCN);
        q[k] = pf_slope_moments_make(qa.x, qa.y, qa.z, qa.w, textureGrad(texB, c, 0.5 * gx / SCN, 0.5 * gy / SCN).x);
#endif
        if (pc.par.y < 0.5) q[k] = pf_slope_moments_make(0.0, 0.0, 0.0, 0.0, 0.0);
    }
#endif
    pf_vec3 wo = pf_vec3_make(T.z, B.z, N.z), wi = pf_vec3_make(dot(L, T), dot(L, B), dot(L, N)); /* the view is +z */
    pf_vec3 ax = pf_vec3_make(dot(dnx, T), dot(dnx, B), dot(dnx, N)), ay = pf_vec3_make(dot(dny, T), dot(dny, B), dot(dny, N));
    pf_vec3 jx = pf_vec3_make(dot(dpx, T), dot(dpx, B), dot(dpx, N)), jy = pf_vec3_make(dot(dpy, T), dot(dpy, B), dot(dpy, N));
#if PFC_METHOD == FC_QUAD
    float r = fc_shade_quad(wo, wi, q[0], q[1], q[2], q[3], pc.par.z, ax, ay);
#else
    float r = fc_shade(PFC_METHOD, wo, wi, pf_slope_moments_make(a.x, a.y, a.z, a.w, b.x), pf_vec3_make(b.y, b.z, b.w), pc.par.z,
                       pf_vec3_make(dnx.x, dnx.y, dnx.z), pf_vec3_make(dny.x, dny.y, dny.z), ax, ay, jx, jy,
                       pf_vec2_make(dmx.x, dmx.y), pf_vec2_make(dmy.x, dmy.y));
#endif
    o0 = hit ? vec4(r, st, 1.0) : vec4(0.0);
    o1 = vec4(gx, gy);
}

// reflect.frag -- spheres repeated without end over a checker floor, two mirror bounces, a sun
// with soft shadows, Blinn-Phong highlights and fog: the kind of shader a user ports to clmarch
// (../scenes/reflect.yaml). Shadertoy-style: defines mainImage(). The peer harness supplies
// iResolution. Written for this project from docs/scene-format.md.
//
// Scene : a sphere of radius 0.8 at the centre of every 3 x 3 cell of the xz plane
//         (q.xz = p.xz - 3 floor(p.xz / 3 + 0.5)), albedo (0.75, 0.3, 0.18), reflectivity 0.5;
//         the floor y = -1.5, a checker of 1-unit cells (parity of floor(x) + floor(y) +
//         floor(z)), reflectivity 0.3; the colour and reflectivity of the nearer.
// Camera: eye (1.5, 3.2, 8) looking at (0, -0.5, 0), up (0, 1, 0), vertical FOV 50 deg; the ray
//         through the pixel centre as clmarch's camera contract (docs/scene-format.md).
// March : MAX_STEPS 200, EPSILON 1e-3, MAX_DIST 60, t from 0, hit when d < EPSILON; mirror rays
//         the same from p + 0.01 n.
// Shade : central-difference normal (h = 1e-3); 0.1 albedo + (albedo max(n.l, 0) + 0.5
//         max(n.h, 0)^40 where n.l > 0) * sun * shadow, the sun towards (-0.5, 0.8, 0.4), colour
//         (1, 0.95, 0.85); soft shadow from p + 4 EPSILON n, t from 0.02 to 20, 64 steps, 0 on
//         d < EPSILON, else clamp(min(16 d / t), 0, 1); two bounces, each adding the product of
//         the reflectivities so far times the shaded colour its mirror ray sees (the sky on a
//         miss, which ends them); fog on a camera hit's total, mix(fog, c, exp(-0.04 t)); misses
//         mix(horizon, zenith, clamp(dir.y, 0, 1)).
// Aux   : aux_t = ray distance at exit, aux_steps = map() calls of the camera march, aux_hit.

#ifndef MAX_STEPS
#define MAX_STEPS 200
#endif
#ifndef EPSILON
#define EPSILON 1e-3
#endif
#ifndef MAX_DIST
#define MAX_DIST 60.0
#endif
#ifndef FOV_DEG
#define FOV_DEG 50.0
#endif
#ifndef BOUNCES
#define BOUNCES 2
#endif
#define NORMAL_H 1e-3
#define SHADOW_STEPS 64
#define SHADOW_K 16.0
#define SHADOW_MIN_T 0.02
#define SHADOW_MAX_T 20.0

float aux_t = 0.0;
float aux_steps = 0.0;
float aux_hit = 0.0;

const vec3 HORIZON = vec3(0.8, 0.85, 0.9), ZENITH = vec3(0.3, 0.5, 0.85);
const vec3 SUN_COLOR = vec3(1.0, 0.95, 0.85);

// (distance, id): id 1 the nearest sphere, 0 the floor
vec2 map(vec3 p)
{
    vec3 q = p;
    q.xz -= 3.0 * floor(q.xz / 3.0 + 0.5);
    float sphere = length(q) - 0.8;
    float floorPlane = p.y + 1.5;
    return floorPlane < sphere ? vec2(floorPlane, 0.0) : vec2(sphere, 1.0);
}

vec3 albedo(vec3 p, float id)
{
    if (id > 0.5) return vec3(0.75, 0.3, 0.18);
    float cell = floor(p.x) + floor(p.y) + floor(p.z);
    return (mod(cell, 2.0) < 0.5) ? vec3(0.85) : vec3(0.12, 0.12, 0.16);
}

float reflectivity(float id) { return id > 0.5 ? 0.5 : 0.3; }

vec3 estimateNormal(vec3 p)
{
    const float h = NORMAL_H;
    return normalize(vec3(map(p + vec3(h, 0.0, 0.0)).x - map(p - vec3(h, 0.0, 0.0)).x,
                          map(p + vec3(0.0, h, 0.0)).x - map(p - vec3(0.0, h, 0.0)).x,
                          map(p + vec3(0.0, 0.0, h)).x - map(p - vec3(0.0, 0.0, h)).x));
}

vec3 sky(vec3 dir) { return mix(HORIZON, ZENITH, clamp(dir.y, 0.0, 1.0)); }

// plain sphere tracing from ro along rd; t of the hit, or -1
float march(vec3 ro, vec3 rd, out int steps)
{
    float t = 0.0;
    steps = 0;
    for (int i = 0; i < MAX_STEPS; i++) {
        float d = map(ro + t * rd).x;
        steps = i + 1;
        if (d < EPSILON) return t;
        t += d;
        if (t >= MAX_DIST) break;
    }
    return -1.0;
}

float softShadow(vec3 ro, vec3 rd)
{
    float res = 1.0, t = SHADOW_MIN_T;
    for (int i = 0; i < SHADOW_STEPS; i++) {
        float h = map(ro + rd * t).x;
        res = min(res, SHADOW_K * h / max(t, 1e-6));
        if (h < EPSILON) return 0.0;
        t += h;
        if (t >= SHADOW_MAX_T) break;
    }
    return clamp(res, 0.0, 1.0);
}

// the lit colour of a surface point p (normal n, albedo a) seen along -v
vec3 shade(vec3 p, vec3 n, vec3 v, vec3 a)
{
    vec3 l = normalize(vec3(-0.5, 0.8, 0.4));
    float ndl = max(dot(n, l), 0.0);
    vec3 col = 0.1 * a;
    if (ndl > 0.0) {
        float spec = 0.5 * pow(max(dot(n, normalize(l + v)), 0.0), 40.0);
        col += (a * ndl + vec3(spec)) * SUN_COLOR * softShadow(p + n * (4.0 * EPSILON), l);
    }
    return max(col, 0.0);
}

mat3 lookAt(vec3 eye, vec3 center, vec3 up)
{
    vec3 f = normalize(center - eye);
    vec3 r = normalize(cross(f, up));
    return mat3(r, cross(r, f), f);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 eye = vec3(1.5, 3.2, 8.0);
    float h = tan(radians(FOV_DEG) * 0.5);
    vec2 uv = (2.0 * fragCoord / iResolution.xy - 1.0) * vec2(iResolution.x / iResolution.y, 1.0) * h;
    vec3 dir = normalize(lookAt(eye, vec3(0.0, -0.5, 0.0), vec3(0.0, 1.0, 0.0)) * vec3(uv, 1.0));

    int steps;
    float t = march(eye, dir, steps);
    aux_t = t < 0.0 ? MAX_DIST : t;
    aux_steps = float(steps);
    aux_hit = t < 0.0 ? 0.0 : 1.0;
    if (t < 0.0) {
        fragColor = vec4(sky(dir), 1.0);
        return;
    }

    vec3 p = eye + t * dir;
    vec3 n = estimateNormal(p);
    float id = map(p).y;
    vec3 col = shade(p, n, -dir, albedo(p, id));
    float weight = 1.0;
    vec3 rd = dir;
    for (int bounce = 0; bounce < BOUNCES; bounce++) {
        weight *= reflectivity(id);
        rd = reflect(rd, n);
        vec3 ro = p + n * 0.01;
        int bounceSteps;
        float tr = march(ro, rd, bounceSteps);
        if (tr < 0.0) {
            col += weight * sky(rd);
            break;
        }
        p = ro + tr * rd;
        n = estimateNormal(p);
        id = map(p).y;
        col += weight * shade(p, n, -rd, albedo(p, id));
    }
    col = mix(vec3(0.8, 0.85, 0.9), col, exp(-0.04 * t));
    fragColor = vec4(col, 1.0);
}

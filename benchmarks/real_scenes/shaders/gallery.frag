// gallery.frag -- a gallery of 21 primitives of distinct kinds over a checker floor, one point
// light with soft shadows: the kind of shader a user ports to clmarch (../scenes/gallery.yaml).
// Shadertoy-style: defines mainImage(). The peer harness supplies iResolution. Written for this
// project from docs/catalogue.md and docs/scene-format.md (the formulas are Inigo Quilez's).
//
// Scene : sphere, box, round box, box frame, torus, capped torus, link (back row, z = -1);
//         capsule, cylinder, hexagonal prism, octahedron, capped cone, cone, round cone (z = 0);
//         rounded cylinder, cut sphere, cut hollow sphere, death star, solid angle, ellipsoid,
//         pyramid (front row, z = 1); columns x = -3 .. 3; all in one min() over the floor
//         y = -0.5 (a checker of 1-unit cells by the parity of floor(x) + floor(y) + floor(z)).
// Camera: eye (0, 2.9, 5.6) looking at (0, -0.35, 0), up (0, 1, 0), vertical FOV 45 deg; the ray
//         through the pixel centre as clmarch's camera contract (docs/scene-format.md).
// March : MAX_STEPS 160, MAX_DIST 40, t from 0; hit when d < max(EPSILON, t * pixel angle), the
//         pixel angle 2 tan(fov / 2) / height (clmarch's pixel_cone, cone_factor 1).
// Shade : tetrahedral normal (h = 5e-4); albedo * (ambient (0.16, 0.18, 0.22) + max(n.l, 0) *
//         light (1, 0.95, 0.85) * 1.1 * shadow), light at (-3, 5, 4); soft shadow marched from
//         p + 4 EPSILON n towards the light, t from 0.02 to the light, at most 64 steps, 0 on
//         d < EPSILON, else clamp(min(12 d / t), 0, 1); misses: mix(horizon, zenith, dir.y).
// Aux   : aux_t = ray distance at exit, aux_steps = map() calls of the march, aux_hit = 1/0.

#ifndef MAX_STEPS
#define MAX_STEPS 160
#endif
#ifndef EPSILON
#define EPSILON 1e-4
#endif
#ifndef MAX_DIST
#define MAX_DIST 40.0
#endif
#ifndef FOV_DEG
#define FOV_DEG 45.0
#endif
#define NORMAL_H 5e-4
#define SHADOW_STEPS 64
#define SHADOW_K 12.0
#define SHADOW_MIN_T 0.02

float aux_t = 0.0;
float aux_steps = 0.0;
float aux_hit = 0.0;

// ---- distances (exact unless noted), each in its own frame ----

float sdSphere(vec3 p, float r) { return length(p) - r; }

// the distance to a box from the offsets q = |p| - half size
float boxFromOffsets(vec3 q) { return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0); }

float sdBox(vec3 p, vec3 b) { return boxFromOffsets(abs(p) - b); }

float sdRoundBox(vec3 p, vec3 b, float r) { return boxFromOffsets(abs(p) - (b - r)) - r; }

// the twelve edges as square bars 2e wide
float sdBoxFrame(vec3 p, vec3 b, float e)
{
    vec3 a = abs(p) - b;
    vec3 q = abs(a + e) - e;
    return min(min(boxFromOffsets(vec3(a.x, q.y, q.z)), boxFromOffsets(vec3(q.x, a.y, q.z))),
               boxFromOffsets(vec3(q.x, q.y, a.z)));
}

float sdTorus(vec3 p, float R, float r) { return length(vec2(length(p.xz) - R, p.y)) - r; }

// the arc within `angle` degrees of +z, in the xz plane
float sdCappedTorus(vec3 p, float angle, float R, float r)
{
    float s = sin(radians(angle)), c = cos(radians(angle));
    p.x = abs(p.x);
    float k = (c * p.x > s * p.z) ? p.x * s + p.z * c : length(p.xz);
    return sqrt(max(dot(p, p) + R * R - 2.0 * R * k, 0.0)) - r;
}

float sdLink(vec3 p, float le, float R, float r)
{
    vec3 q = vec3(p.x, max(abs(p.y) - le, 0.0), p.z);
    return length(vec2(length(q.xy) - R, q.z)) - r;
}

float sdCapsule(vec3 p, vec3 a, vec3 b, float r)
{
    vec3 pa = p - a, ba = b - a;
    float h = clamp(dot(pa, ba) / dot(ba, ba), 0.0, 1.0);
    return length(pa - ba * h) - r;
}

float sdCylinder(vec3 p, float r, float hh)
{
    vec2 d = vec2(length(p.xz) - r, abs(p.y) - hh);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}

// radius: from the axis (y) to each flat side, one side facing +z
float sdHexPrism(vec3 p, float r, float hh)
{
    vec3 a = abs(p);
    float fold = 2.0 * min(-0.8660254 * a.x + 0.5 * a.z, 0.0);
    vec2 q = vec2(a.x + 0.8660254 * fold, a.z - 0.5 * fold);
    vec2 c = vec2(q.x - clamp(q.x, -0.57735027 * r, 0.57735027 * r), q.y - r);
    vec2 d = vec2(length(c) * sign(c.y), a.y - hh);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}

float sdOctahedron(vec3 p, float s)
{
    p = abs(p);
    float m = p.x + p.y + p.z - s;
    vec3 q;
    if (3.0 * p.x < m) q = p.xyz;
    else if (3.0 * p.y < m) q = p.yzx;
    else if (3.0 * p.z < m) q = p.zxy;
    else return m * 0.57735027;
    float k = clamp(0.5 * (q.z - q.y + s), 0.0, s);
    return length(vec3(q.x, q.y - s + k, q.z - k));
}

// radius r1 at y = -hh, r2 at y = +hh
float sdCappedCone(vec3 p, float hh, float r1, float r2)
{
    vec2 q = vec2(length(p.xz), p.y);
    vec2 k1 = vec2(r2, hh);
    vec2 k2 = vec2(r2 - r1, 2.0 * hh);
    vec2 ca = vec2(q.x - min(q.x, (q.y < 0.0) ? r1 : r2), abs(q.y) - hh);
    vec2 cb = q - k1 + k2 * clamp(dot(k1 - q, k2) / dot(k2, k2), 0.0, 1.0);
    float s = (cb.x < 0.0 && ca.y < 0.0) ? -1.0 : 1.0;
    return s * sqrt(min(dot(ca, ca), dot(cb, cb)));
}

// apex at the origin, the base disc `height` below, half-angle `angle` degrees
float sdCone(vec3 p, float angle, float height)
{
    vec2 q = vec2(height * tan(radians(angle)), -height);
    vec2 w = vec2(length(p.xz), p.y);
    vec2 a = w - q * clamp(dot(w, q) / dot(q, q), 0.0, 1.0);
    vec2 b = w - q * vec2(clamp(w.x / q.x, 0.0, 1.0), 1.0);
    float s = max(w.y * q.x - w.x * q.y, q.y - w.y);
    return sqrt(min(dot(a, a), dot(b, b))) * sign(s);
}

float sdRoundCone(vec3 p, vec3 a, vec3 b, float r1, float r2)
{
    vec3 ba = b - a;
    float l2 = dot(ba, ba), rr = r1 - r2, a2 = l2 - rr * rr, il2 = 1.0 / l2;
    vec3 pa = p - a;
    float y = dot(pa, ba), z = y - l2;
    vec3 off = pa * l2 - ba * y;
    float x2 = dot(off, off), y2 = y * y * l2, z2 = z * z * l2;
    float k = sign(rr) * rr * rr * x2;
    if (sign(z) * a2 * z2 > k) return sqrt(x2 + z2) * il2 - r2;
    if (sign(y) * a2 * y2 < k) return sqrt(x2 + y2) * il2 - r1;
    return (sqrt(x2 * a2 * il2) + y * rr) * il2 - r1;
}

// outer radius and half height, the two rim edges rounded by e
float sdRoundedCylinder(vec3 p, float r, float hh, float e)
{
    vec2 d = vec2(length(p.xz) - (r - e), abs(p.y) - (hh - e));
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0)) - e;
}

// the part y >= h of the ball
float sdCutSphere(vec3 p, float r, float h)
{
    float w = sqrt(r * r - h * h);
    vec2 q = vec2(length(p.xz), p.y);
    float s = max((h - r) * q.x * q.x + w * w * (h + r - 2.0 * q.y), h * q.x - w * q.y);
    return (s < 0.0) ? length(q) - r : (q.x < w) ? h - q.y : length(q - vec2(w, h));
}

// the shell's part y <= h, thickened by t on each side
float sdCutHollowSphere(vec3 p, float r, float h, float t)
{
    float w = sqrt(r * r - h * h);
    vec2 q = vec2(length(p.xz), p.y);
    return ((h * q.x < w * q.y) ? length(q - vec2(w, h)) : abs(length(q) - r)) - t;
}

// the ball of ra less the ball of rb at distance d along +x
float sdDeathStar(vec3 p, float ra, float rb, float d)
{
    float a = (ra * ra - rb * rb + d * d) / (2.0 * d);
    float b = sqrt(max(ra * ra - a * a, 0.0));
    vec2 q = vec2(p.x, length(p.yz));
    if (q.x * b - q.y * a > d * max(b - q.y, 0.0)) return length(q - vec2(a, b));
    return max(length(q) - ra, -(length(q - vec2(d, 0.0)) - rb));
}

// the ball's sector within `angle` degrees of +y, apex at the origin
float sdSolidAngle(vec3 p, float angle, float ra)
{
    vec2 c = vec2(sin(radians(angle)), cos(radians(angle)));
    vec2 q = vec2(length(p.xz), p.y);
    float l = length(q) - ra;
    float m = length(q - c * clamp(dot(q, c), 0.0, ra));
    return max(l, m * sign(c.y * q.x - c.x * q.y));
}

// a bound (exact on the surface)
float sdEllipsoid(vec3 p, vec3 r)
{
    float k0 = length(p / r), k1 = length(p / (r * r));
    return (k1 > 0.0) ? k0 * (k0 - 1.0) / k1 : -min(r.x, min(r.y, r.z));
}

// square base of half width hw on y = 0, apex at y = height; side faces and base
float sdPyramid(vec3 p, float hw, float height)
{
    float side = 2.0 * hw, h = height / side, m2 = h * h + 0.25;
    p /= side;
    p.xz = abs(p.xz);
    p.xz = (p.z > p.x) ? p.zx : p.xz;
    p.xz -= 0.5;
    vec3 q = vec3(p.z, h * p.y - 0.5 * p.x, h * p.x + 0.5 * p.y);
    float s = max(-q.x, 0.0);
    float t = clamp((q.y - 0.5 * p.z) / (m2 + 0.25), 0.0, 1.0);
    float a = m2 * (q.x + s) * (q.x + s) + q.y * q.y;
    float b = m2 * (q.x + 0.5 * t) * (q.x + 0.5 * t) + (q.y - m2 * t) * (q.y - m2 * t);
    float d2 = (min(q.y, -q.x * m2 - q.y * 0.5) > 0.0) ? 0.0 : min(a, b);
    vec2 base = max(p.xz, 0.0);
    float outside = min(sqrt((d2 + q.z * q.z) / m2), length(vec3(base.x, p.y, base.y)));
    float inside = max(q.z / sqrt(m2), -p.y);
    return side * ((q.z < 0.0 && p.y > 0.0) ? inside : outside);
}

// ---- the scene: (distance, material) of the nearest ----

const vec3 RED = vec3(0.85, 0.32, 0.25), BLUE = vec3(0.3, 0.58, 0.85), YELLOW = vec3(0.9, 0.72, 0.28);
const vec3 GREEN = vec3(0.4, 0.78, 0.45), VIOLET = vec3(0.72, 0.45, 0.85);

// the nearer of (d, id) so far and the next shape's
void opU(inout vec2 res, float d, float id) { if (d < res.x) res = vec2(d, id); }

vec2 map(vec3 p)
{
    vec2 res = vec2(sdSphere(p - vec3(-3.0, -0.12, -1.0), 0.38), 1.0);
    opU(res, sdBox(p - vec3(-2.0, -0.2, -1.0), vec3(0.3)), 2.0);
    opU(res, sdRoundBox(p - vec3(-1.0, -0.22, -1.0), vec3(0.32, 0.28, 0.3), 0.08), 3.0);
    opU(res, sdBoxFrame(p - vec3(0.0, -0.2, -1.0), vec3(0.3), 0.04), 4.0);
    opU(res, sdTorus(p - vec3(1.0, -0.4, -1.0), 0.3, 0.1), 5.0);
    opU(res, sdCappedTorus(p - vec3(2.0, -0.42, -1.0), 130.0, 0.3, 0.08), 1.0);
    opU(res, sdLink(p - vec3(3.0, -0.08, -1.0), 0.15, 0.2, 0.07), 2.0);
    opU(res, sdCapsule(p - vec3(-3.0, -0.1, 0.0), vec3(0.0, -0.25, 0.0), vec3(0.0, 0.25, 0.0), 0.15), 3.0);
    opU(res, sdCylinder(p - vec3(-2.0, -0.2, 0.0), 0.28, 0.3), 4.0);
    opU(res, sdHexPrism(p - vec3(-1.0, -0.2, 0.0), 0.28, 0.3), 5.0);
    opU(res, sdOctahedron(p - vec3(0.0, -0.08, 0.0), 0.42), 1.0);
    opU(res, sdCappedCone(p - vec3(1.0, -0.2, 0.0), 0.3, 0.32, 0.12), 2.0);
    opU(res, sdCone(p - vec3(2.0, 0.15, 0.0), 25.0, 0.65), 3.0);
    opU(res, sdRoundCone(p - vec3(3.0, -0.05, 0.0), vec3(0.0, -0.2, 0.0), vec3(0.0, 0.2, 0.0), 0.25, 0.1), 4.0);
    opU(res, sdRoundedCylinder(p - vec3(-3.0, -0.25, 1.0), 0.3, 0.25, 0.07), 5.0);
    opU(res, sdCutSphere(p - vec3(-2.0, -0.35, 1.0), 0.38, -0.15), 1.0);
    opU(res, sdCutHollowSphere(p - vec3(-1.0, -0.11, 1.0), 0.36, 0.12, 0.03), 2.0);
    opU(res, sdDeathStar(p - vec3(0.0, -0.14, 1.0), 0.36, 0.28, 0.4), 3.0);
    opU(res, sdSolidAngle(p - vec3(1.0, -0.5, 1.0), 35.0, 0.55), 4.0);
    opU(res, sdEllipsoid(p - vec3(2.0, -0.28, 1.0), vec3(0.38, 0.22, 0.3)), 5.0);
    opU(res, sdPyramid(p - vec3(3.0, -0.5, 1.0), 0.3, 0.6), 1.0);
    opU(res, p.y + 0.5, 0.0);
    return res;
}

vec3 albedo(vec3 p, float id)
{
    if (id < 0.5) {
        float cell = floor(p.x) + floor(p.y) + floor(p.z);
        return (mod(cell, 2.0) < 0.5) ? vec3(0.72, 0.72, 0.7) : vec3(0.42, 0.42, 0.45);
    }
    return id < 1.5 ? RED : id < 2.5 ? BLUE : id < 3.5 ? YELLOW : id < 4.5 ? GREEN : VIOLET;
}

vec3 estimateNormal(vec3 p)
{
    const vec2 k = vec2(1.0, -1.0);
    return normalize(k.xyy * map(p + k.xyy * NORMAL_H).x + k.yyx * map(p + k.yyx * NORMAL_H).x +
                     k.yxy * map(p + k.yxy * NORMAL_H).x + k.xxx * map(p + k.xxx * NORMAL_H).x);
}

float softShadow(vec3 ro, vec3 rd, float tmax)
{
    float res = 1.0, t = SHADOW_MIN_T;
    for (int i = 0; i < SHADOW_STEPS; i++) {
        float h = map(ro + rd * t).x;
        res = min(res, SHADOW_K * h / max(t, 1e-6));
        if (h < EPSILON) return 0.0;
        t += h;
        if (t >= tmax) break;
    }
    return clamp(res, 0.0, 1.0);
}

mat3 lookAt(vec3 eye, vec3 center, vec3 up)
{
    vec3 f = normalize(center - eye);
    vec3 r = normalize(cross(f, up));
    return mat3(r, cross(r, f), f);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 eye = vec3(0.0, 2.9, 5.6);
    float h = tan(radians(FOV_DEG) * 0.5);
    vec2 uv = (2.0 * fragCoord / iResolution.xy - 1.0) * vec2(iResolution.x / iResolution.y, 1.0) * h;
    vec3 dir = normalize(lookAt(eye, vec3(0.0, -0.35, 0.0), vec3(0.0, 1.0, 0.0)) * vec3(uv, 1.0));
    float pixelAngle = 2.0 * h / iResolution.y;

    float t = 0.0;
    int steps = 0;
    bool hit = false;
    for (int i = 0; i < MAX_STEPS; i++) {
        float d = map(eye + t * dir).x;
        steps = i + 1;
        if (d < max(EPSILON, t * pixelAngle)) { hit = true; break; }
        t += d;
        if (t >= MAX_DIST) { t = MAX_DIST; break; }
    }
    aux_t = t;
    aux_steps = float(steps);
    aux_hit = hit ? 1.0 : 0.0;

    vec3 col = mix(vec3(0.75, 0.8, 0.9), vec3(0.35, 0.5, 0.8), clamp(dir.y, 0.0, 1.0));
    if (hit) {
        vec3 p = eye + t * dir;
        vec3 n = estimateNormal(p);
        vec3 a = albedo(p, map(p).y);
        vec3 toLight = vec3(-3.0, 5.0, 4.0) - p;
        vec3 l = normalize(toLight);
        float ndl = max(dot(n, l), 0.0);
        float shadow = ndl > 0.0 ? softShadow(p + n * (4.0 * EPSILON), l, length(toLight)) : 1.0;
        col = a * vec3(0.16, 0.18, 0.22) + a * ndl * vec3(1.0, 0.95, 0.85) * 1.1 * shadow;
    }
    fragColor = vec4(col, 1.0);
}

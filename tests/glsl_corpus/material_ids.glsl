// A table with a ball rolling on it: map returns the distance and a material id in .y, and the
// colour function calls map for the id and reads a glow the parts add up in a global.
// Exercises: vec2 map (distance, material id), globals written inside map (the glow, the nearest
// part), overloaded functions (sdBox of vec2 and of vec3, opU of vec2 and of float), nested
// ternaries, swizzle assignment, iTime, vec3 albedo(vec3 p).
float glow = 0.0;
float nearest_part = -1.0;

float sdBox(vec2 p, vec2 b) {
  vec2 d = abs(p) - b;
  return length(max(d, 0.0)) + min(max(d.x, d.y), 0.0);
}

float sdBox(vec3 p, vec3 b) {
  vec3 d = abs(p) - b;
  return length(max(d, 0.0)) + min(max(d.x, max(d.y, d.z)), 0.0);
}

vec2 opU(vec2 a, vec2 b) { return a.x < b.x ? a : b; }
float opU(float a, float b) { return min(a, b); }

void add_glow(float d) { glow += 0.02 / (1.0 + 16.0 * d * d); }

vec2 map(vec3 p) {
  vec2 res = vec2(sdBox(p - vec3(0.0, 0.3, 0.0), vec3(1.3, 0.08, 0.8)) - 0.02, 1.0);
  add_glow(res.x);
  vec3 q = p;
  q.xz = abs(q.xz) - vec2(1.05, 0.55);
  float legs = max(sdBox(q.xz, vec2(0.08)), abs(p.y + 0.5) - 0.8);
  legs = opU(legs, max(sdBox(q.xz, vec2(0.1)), abs(p.y + 1.25) - 0.05));
  res = opU(res, vec2(legs, 2.0));
  add_glow(legs);
  float ball = length(p - vec3(0.7 * sin(iTime), 0.71, 0.1)) - 0.32;
  res = opU(res, vec2(ball, 3.0));
  add_glow(ball);
  nearest_part = res.y;
  return res;
}

vec3 albedo(vec3 p) {
  float id = map(p).y;
  vec3 base = id == 1.0 ? vec3(0.55, 0.35, 0.2) : id == 2.0 ? vec3(0.3, 0.2, 0.12) : vec3(0.8, 0.1, 0.1);
  return base + (nearest_part == 3.0 ? glow : 0.5 * glow);
}

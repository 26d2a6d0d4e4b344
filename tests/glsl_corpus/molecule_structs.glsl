// A molecule: atoms listed in a const array of structs, bobbing with the time, blended with a
// smooth minimum; the colour is the nearest atom's kind, which a loop reports through out
// parameters.
// Exercises: a struct (vec3, float and int members: constructed, copied, a member's swizzle
// assigned), a const array of structs and a local float array, for loops over them with an int
// counter, out parameters, a ternary, iTime, vec3 albedo(vec3 p).
struct Atom {
  vec3 center;
  float radius;
  int kind;
};

const Atom atoms[5] = Atom[5](Atom(vec3(0.0, 0.0, 0.0), 0.65, 0),
                              Atom(vec3(0.95, 0.4, 0.0), 0.4, 1),
                              Atom(vec3(-0.9, 0.45, 0.2), 0.4, 1),
                              Atom(vec3(0.1, -0.55, 0.85), 0.35, 2),
                              Atom(vec3(0.05, -0.3, -0.95), 0.45, 1));

Atom moved(int i) {
  Atom a = atoms[i];
  a.center.y += 0.12 * sin(iTime + float(i));
  return a;
}

float smin(float a, float b, float k) {
  float h = clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return mix(b, a, h) - k * h * (1.0 - h);
}

void nearest_atom(vec3 p, out float distance, out int kind) {
  distance = 1e10;
  kind = -1;
  for (int i = 0; i < 5; i++) {
    Atom a = moved(i);
    float d = length(p - a.center) - a.radius;
    if (d < distance) {
      distance = d;
      kind = a.kind;
    }
  }
}

float map(vec3 p) {
  float d[5];
  for (int i = 0; i < 5; i++) {
    Atom a = moved(i);
    d[i] = length(p - a.center) - a.radius;
  }
  float result = d[0];
  for (int i = 1; i < 5; i++) result = smin(result, d[i], 0.25);
  return result;
}

vec3 albedo(vec3 p) {
  float distance;
  int kind;
  nearest_atom(p, distance, kind);
  return kind == 0 ? vec3(0.2, 0.2, 0.22) : kind == 1 ? vec3(0.9, 0.9, 0.9) : vec3(0.85, 0.15, 0.1);
}

// Three boxes of different sizes, each turned by a matrix built another way: a mat3 from scalars,
// a mat3 from column vectors, and a mat2 whose entries are read back by index; every box is
// lopsided so that a transposed matrix or a swapped index moves its surface.
// Exercises: column-major matrix constructors (mat2 of four scalars, mat3 of nine scalars and of
// three vec3 columns, mat2 of a vec4), indexing m[1][0] (column 1, row 0) and m[2] (a column),
// matrix x vector, vector x matrix, matrix x matrix, transpose, a mat3's column assigned,
// swizzle assignment, vec3 albedo(vec3 p).
float sdBox(vec3 p, vec3 b) {
  vec3 q = abs(p) - b;
  return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

// A turn by a about z, spelled column by column: the first column is the image of x.
mat3 turn_z(float a) {
  float c = cos(a), s = sin(a);
  return mat3(c, s, 0.0,
              -s, c, 0.0,
              0.0, 0.0, 1.0);
}

mat3 turn_x(float a) {
  vec3 x = vec3(1.0, 0.0, 0.0);
  vec3 y = vec3(0.0, cos(a), sin(a));
  mat3 m = mat3(x, y, vec3(0.0));
  m[2] = cross(x, y);
  return m;
}

float map(vec3 p) {
  // The box's frame turned by 0.5 about z then 0.3 about x: its local point is the transpose
  // (inverse) of that turn times p, or p times the turn.
  mat3 frame = turn_x(0.3) * turn_z(0.5);
  vec3 q = p - vec3(-0.9, 0.2, 0.0);
  float a = sdBox(q * frame, vec3(0.55, 0.25, 0.35));
  vec3 r = transpose(frame) * (p - vec3(0.8, 0.1, 0.3));
  float b = sdBox(r, vec3(0.2, 0.5, 0.3));
  mat2 m = mat2(vec4(0.6, 0.8, -0.8, 0.6));
  // m's columns are (0.6, 0.8) and (-0.8, 0.6); m[i][j] is column i's row j, so back is m's
  // transpose, the opposite turn: read row-major, it would be m again.
  mat2 back = mat2(m[0][0], m[1][0], m[0][1], m[1][1]);
  vec3 t = p - vec3(0.0, -0.7, -0.5);
  t.xz = back * t.xz;
  float c = sdBox(t, vec3(0.7, 0.15, 0.2));
  return min(a, min(b, c));
}

vec3 albedo(vec3 p) {
  mat3 m = mat3(0.9, 0.1, 0.0, 0.2, 0.6, 0.1, 0.0, 0.3, 0.8);
  vec3 c = m * clamp(0.5 + 0.5 * p, 0.0, 1.0);
  return vec3(c.x, c[1], m[2][1] + 0.2 * c.z);
}

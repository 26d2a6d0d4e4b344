/* Hash-based lattice noise and the terrain height fields, compiled in only for scenes with a
 * terrain. The lattice hash is uint32 arithmetic with wrap-around, bit for bit the one of
 * host/reference/reference_noise.cpp, so kernel and reference see the same lattice values; keep
 * the two in step (tests compare them at lattice points). No texture is needed. */

#if LANES == 1
typedef uint vuint;
#define NOISE_AS_VUINT(x) as_uint(x)
#define NOISE_LATTICE(x) convert_int_sat(x)
#elif LANES == 4
typedef uint4 vuint;
#define NOISE_AS_VUINT(x) as_uint4(x)
#define NOISE_LATTICE(x) convert_int4_sat(x)
#elif LANES == 8
typedef uint8 vuint;
#define NOISE_AS_VUINT(x) as_uint8(x)
#define NOISE_LATTICE(x) convert_int8_sat(x)
#elif LANES == 16
typedef uint16 vuint;
#define NOISE_AS_VUINT(x) as_uint16(x)
#define NOISE_LATTICE(x) convert_int16_sat(x)
#endif

/* 32 mixed bits of the lattice point (ix, iz): spatial-hash primes, then Chris Wellons'
 * lowbias32 finaliser. */
SDF_INLINE vuint noise_hash(vuint ix, vuint iz, uint seed) {
  vuint h = (ix * 0x8da6b343u) ^ (iz * 0xd8163841u) ^ (vuint)((seed + 0x9e3779b9u) * 0xcb1ab31fu);
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

/* The lattice value in [0, 1): the top 24 bits times 2^-24, exact in float. */
SDF_INLINE vfloat noise_hash01(vuint ix, vuint iz, uint seed) {
  return TO_VFLOAT(noise_hash(ix, iz, seed) >> 8) * 0x1p-24f;
}

/* A noise value and its gradient d/dx, d/dz. */
typedef struct {
  vfloat value, dx, dz;
} noise_sample;

/* Value noise: lattice values blended by the cubic smoothstep, with the analytic gradient
 * (Inigo Quilez's noised). The lattice cell of (x, z) is moved by (shift_x, shift_z) cells. */
SDF_INLINE noise_sample value_noise(vfloat x, vfloat z, uint seed, uint shift_x, uint shift_z) {
  const vfloat cell_x = floor(x), cell_z = floor(z);
  const vuint ix = NOISE_AS_VUINT(NOISE_LATTICE(cell_x)) + shift_x,
              iz = NOISE_AS_VUINT(NOISE_LATTICE(cell_z)) + shift_z;
  const vfloat fx = x - cell_x, fz = z - cell_z;
  const vfloat ux = fx * fx * (3.0f - 2.0f * fx), uz = fz * fz * (3.0f - 2.0f * fz);
  const vfloat dux = 6.0f * fx * (1.0f - fx), duz = 6.0f * fz * (1.0f - fz);
  const vfloat a = noise_hash01(ix, iz, seed);
  const vfloat b = noise_hash01(ix + 1u, iz, seed);
  const vfloat c = noise_hash01(ix, iz + 1u, seed);
  const vfloat d = noise_hash01(ix + 1u, iz + 1u, seed);
  const vfloat k = a - b - c + d;
  noise_sample n;
  n.value = a + (b - a) * ux + (c - a) * uz + k * ux * uz;
  n.dx = dux * ((b - a) + k * uz);
  n.dz = duz * ((c - a) + k * ux);
  return n;
}

/* f . g for the lattice gradient g of gradient noise: two 16-bit halves of the hash in [-1, 1). */
SDF_INLINE vfloat perlin_corner(vuint ix, vuint iz, uint seed, vfloat fx, vfloat fz) {
  const vuint h = noise_hash(ix, iz, seed);
  const vfloat gx = TO_VFLOAT(h & 0xffffu) * 0x1p-15f - 1.0f;
  const vfloat gz = TO_VFLOAT(h >> 16) * 0x1p-15f - 1.0f;
  return gx * fx + gz * fz;
}

/* Gradient (Perlin) noise, blended by the quintic 6f^5 - 15f^4 + 10f^3; zero on the lattice. The
 * lattice cell of (x, z) is moved by (shift_x, shift_z) cells. */
SDF_INLINE vfloat perlin_noise(vfloat x, vfloat z, uint seed, uint shift_x, uint shift_z) {
  const vfloat cell_x = floor(x), cell_z = floor(z);
  const vuint ix = NOISE_AS_VUINT(NOISE_LATTICE(cell_x)) + shift_x,
              iz = NOISE_AS_VUINT(NOISE_LATTICE(cell_z)) + shift_z;
  const vfloat fx = x - cell_x, fz = z - cell_z;
  const vfloat ux = fx * fx * fx * (fx * (6.0f * fx - 15.0f) + 10.0f);
  const vfloat uz = fz * fz * fz * (fz * (6.0f * fz - 15.0f) + 10.0f);
  const vfloat a = perlin_corner(ix, iz, seed, fx, fz);
  const vfloat b = perlin_corner(ix + 1u, iz, seed, fx - 1.0f, fz);
  const vfloat c = perlin_corner(ix, iz + 1u, seed, fx, fz - 1.0f);
  const vfloat d = perlin_corner(ix + 1u, iz + 1u, seed, fx - 1.0f, fz - 1.0f);
  return a + (b - a) * ux + (c - a) * uz + (a - b - c + d) * ux * uz;
}

/* Octave to octave the point turns by (0.8, 0.6; -0.6, 0.8) (Inigo Quilez's m2) so successive
 * lattices do not line up, and is scaled by the lacunarity. */
SDF_INLINE void noise_next_octave(vfloat* x, vfloat* z, float lacunarity) {
  const vfloat turned_x = 0.8f * *x + 0.6f * *z;
  *z = lacunarity * (-0.6f * *x + 0.8f * *z);
  *x = lacunarity * turned_x;
}

/* Octave i of a terrain far from the origin: its lattice point of the absolute point p + F is
 * M^i f p + M^i f F, M the octave step. The host splits M^i f F in double into a fraction, added to
 * the small M^i f p here, and whole cells, added to the lattice index (phases[i] = (fraction x,
 * fraction z, cells x, cells z), cells exact in float): so the noise keeps the precision of the
 * map frame's small p instead of float's spacing at F (host/codegen/sdf_codegen.cpp,
 * terrain_phases). phases is 0 near the origin (F = 0). */
typedef struct {
  vfloat x, z;
  uint shift_x, shift_z;
} NoiseAt;

SDF_INLINE NoiseAt noise_at(vfloat x, vfloat z, const float4* phases, int octave) {
  NoiseAt at = {x, z, 0u, 0u};
  if (phases) {
    const float4 phase = phases[octave];
    at.x += phase.x;
    at.z += phase.y;
    at.shift_x = (uint)(int)phase.z;
    at.shift_z = (uint)(int)phase.w;
  }
  return at;
}

/* Height bound: p.y minus the terrain height (a bound only with a step factor below
 * 1 / sqrt(1 + slope^2)). Fractal sum of value noise: weights 0.5^i, frequencies 2^i. */
SDF_INLINE vfloat sd_terrain_value_phased(vec3v p, float height, float amplitude, float frequency, int octaves,
                                          uint seed, const float4* phases) {
  vfloat x = p.x * frequency, z = p.z * frequency;
  vfloat sum = (vfloat)(0.0f);
  float weight = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    const NoiseAt at = noise_at(x, z, phases, i);
    sum += weight * value_noise(at.x, at.z, seed, at.shift_x, at.shift_z).value;
    weight *= 0.5f;
    noise_next_octave(&x, &z, 2.0f);
  }
  return p.y - (height + amplitude * sum);
}

/* As sd_terrain_value, with gradient (Perlin) noise. */
SDF_INLINE vfloat sd_terrain_perlin_phased(vec3v p, float height, float amplitude, float frequency, int octaves,
                                           uint seed, const float4* phases) {
  vfloat x = p.x * frequency, z = p.z * frequency;
  vfloat sum = (vfloat)(0.0f);
  float weight = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    const NoiseAt at = noise_at(x, z, phases, i);
    sum += weight * perlin_noise(at.x, at.z, seed, at.shift_x, at.shift_z);
    weight *= 0.5f;
    noise_next_octave(&x, &z, 2.0f);
  }
  return p.y - (height + amplitude * sum);
}

/* The noise-derivative terrain of Heckel's article (after Inigo Quilez): each octave's value is
 * damped by 1 / (1 + |sum of the gradients so far|^2); weight 2.5, times -0.4 per octave, the sum
 * times 0.85 per octave, frequencies 2.75^i. */
SDF_INLINE vfloat sd_terrain_derivative_phased(vec3v p, float height, float amplitude, float frequency, int octaves,
                                               uint seed, const float4* phases) {
  vfloat x = p.x * frequency, z = p.z * frequency;
  vfloat sum = (vfloat)(0.0f), slope_x = (vfloat)(0.0f), slope_z = (vfloat)(0.0f);
  float weight = 2.5f;
  for (int i = 0; i < octaves; ++i) {
    const NoiseAt at = noise_at(x, z, phases, i);
    const noise_sample n = value_noise(at.x, at.z, seed, at.shift_x, at.shift_z);
    slope_x += n.dx;
    slope_z += n.dz;
    sum += weight * n.value / (1.0f + slope_x * slope_x + slope_z * slope_z);
    weight *= -0.4f;
    sum *= 0.85f;
    noise_next_octave(&x, &z, 2.75f);
  }
  return p.y - (height + amplitude * sum);
}

/* The terrains at the absolute point p (near the origin, where map()'s frame is the world's). */
SDF_INLINE vfloat sd_terrain_value(vec3v p, float height, float amplitude, float frequency, int octaves, uint seed) {
  return sd_terrain_value_phased(p, height, amplitude, frequency, octaves, seed, 0);
}
SDF_INLINE vfloat sd_terrain_perlin(vec3v p, float height, float amplitude, float frequency, int octaves, uint seed) {
  return sd_terrain_perlin_phased(p, height, amplitude, frequency, octaves, seed, 0);
}
SDF_INLINE vfloat sd_terrain_derivative(vec3v p, float height, float amplitude, float frequency, int octaves,
                                        uint seed) {
  return sd_terrain_derivative_phased(p, height, amplitude, frequency, octaves, seed, 0);
}

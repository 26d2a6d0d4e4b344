/* The plain sphere-tracing loop and the result type every march loop (tiling.cl too) returns. A
 * lane goes idle once its ray hits (distance < epsilon), passes max_distance or the step budget
 * ends (both misses). */

/* What the march of one packet found. */
typedef struct {
  vfloat t;          /* depth along the unit ray where it hit */
  vfloat steps;      /* every iteration: distance steps and wall steps */
  vfloat wall_steps; /* iterations that stepped to a cell wall (tiling) */
  vint hit;
  vec3v local_point; /* the hit point in the frame map() is written in (a cell's, under tiling) */
} MarchResult;

SDF_INLINE MarchResult march_plain(const MarchParams* params, vint live, vec3v origin, vec3v dir) {
  MarchResult m;
  m.t = (vfloat)(0.0f);
  m.steps = (vfloat)(0.0f);
  m.wall_steps = (vfloat)(0.0f);
  m.hit = (vint)(0);
  vint active = live;
  for (int step = 0; step < params->max_steps && LANE_ANY(active); ++step) {
    vfloat d = map(v3_add(origin, v3_scale(dir, m.t)));
    m.steps += select((vfloat)(0.0f), (vfloat)(1.0f), active);
    vint arrived = active & MASK(d < params->epsilon);
    m.hit |= arrived;
    active &= ~arrived;
    m.t = select(m.t, m.t + d, active);
    active &= MASK(m.t < params->max_distance);
  }
  m.local_point = v3_add(origin, v3_scale(dir, m.t));
  return m;
}


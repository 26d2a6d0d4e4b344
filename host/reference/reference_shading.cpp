// Lighting and atmosphere of the reference.
#include "reference/reference_shading.hpp"

#include "reference/reference_march.hpp"

#include <algorithm>
#include <cmath>

namespace clmarch {
namespace {

double specular_term(ShadingModel model, const glm::dvec3& n, const glm::dvec3& l, const glm::dvec3& v,
                     double shininess) {
  switch (model) {
    case ShadingModel::Phong:
      return std::pow(std::max(glm::dot(glm::reflect(-l, n), v), 0.0), shininess);
    case ShadingModel::BlinnPhong:
      return std::pow(std::max(glm::dot(n, normalize_or_zero(l + v)), 0.0), shininess);
    case ShadingModel::Lambert:
    case ShadingModel::Pbr:
      return 0.0;
  }
  return 0.0;
}

// One light's reflection off a surface, before its radiance and shadow.
struct Reflection {
  glm::dvec3 diffuse;
  glm::dvec3 specular;
};

// Cook-Torrance: GGX distribution, Smith-Schlick geometry with k = (r + 1)^2 / 8, Fresnel-Schlick
// from F0 = mix(0.04, albedo, metallic); the diffuse and specular lobes times n.l.
Reflection pbr_light(const glm::dvec3& n, const glm::dvec3& l, const glm::dvec3& v, const Material& m) {
  const glm::dvec3 h = normalize_or_zero(l + v);
  const double n_dot_l = std::max(glm::dot(n, l), 0.0);
  const double n_dot_v = std::max(glm::dot(n, v), 0.0);
  const double n_dot_h = std::max(glm::dot(n, h), 0.0);
  const double h_dot_v = std::max(glm::dot(h, v), 0.0);
  const double a = m.roughness * m.roughness;
  const double denom = n_dot_h * n_dot_h * (a * a - 1.0) + 1.0;
  const double distribution = a * a / (M_PI * denom * denom);
  const double k = (m.roughness + 1.0) * (m.roughness + 1.0) / 8.0;
  const double geometry = n_dot_v / (n_dot_v * (1.0 - k) + k) * n_dot_l / (n_dot_l * (1.0 - k) + k);
  const glm::dvec3 f0 = glm::dvec3(0.04) + (m.albedo - glm::dvec3(0.04)) * m.metallic;
  const glm::dvec3 fresnel = f0 + (1.0 - f0) * std::pow(1.0 - h_dot_v, 5.0);
  const double specular = distribution * geometry / (4.0 * n_dot_v * n_dot_l + 1e-4);
  const glm::dvec3 diffuse = (1.0 - fresnel) * (1.0 - m.metallic) * m.albedo / M_PI;
  return {diffuse * n_dot_l, fresnel * specular * n_dot_l};
}

Reflection classic_light(const Shading& sh, const glm::dvec3& n, const glm::dvec3& l, const glm::dvec3& v,
                         const Material& m) {
  const double n_dot_l = std::max(glm::dot(n, l), 0.0);
  const double specular = n_dot_l > 0.0 ? specular_term(sh.model, n, l, v, m.shininess) : 0.0;
  return {m.albedo * (sh.diffuse * n_dot_l), glm::dvec3(m.specular * specular)};
}

// Light reaching the surface from direction l over distance t_end (Inigo Quilez's shadows).
double shadow_factor(const Scene& scene, const SurfacePoint& s, const glm::dvec3& l, double t_end) {
  const Shadows& sh = *scene.shading.shadows;
  MarchLimits limits{sh.max_steps, scene.render.epsilon, static_cast<int>(sh.mode), sh.k};
  const glm::dvec3 origin = s.local + s.normal * (4.0 * scene.render.epsilon);
  const MarchEnd end = reference_march(scene, origin, l, sh.min_t, t_end, limits);
  if (end.hit) return 0.0;
  return sh.mode == ShadowMode::Hard ? 1.0 : std::clamp(end.penumbra, 0.0, 1.0);
}

// The PBR course's occlusion: 1 - sum over i = samples..1 of (i step - sdf(p + n i step))^2 / i.
double normal_occlusion(const Scene& scene, const SurfacePoint& s) {
  const NormalOcclusion& ao = *scene.shading.ambient_occlusion;
  const Field field = scene_field(scene);
  double occlusion = 1.0;
  for (int i = ao.samples; i > 0; --i) {
    const double along = i * ao.step;
    const double gap = along - field(s.local + s.normal * along);
    occlusion -= gap * gap / i;
  }
  return std::pow(std::clamp(occlusion, 0.0, 1.0), ao.power);
}

}  // namespace

double light_reach(const Light& light, const glm::dvec3& l, double distance) {
  if (light.kind == LightKind::Directional) return 1.0;
  double reach = light.falloff == Falloff::InverseSquare ? 1.0 / (distance * distance) : 1.0;
  if (light.range) {
    const double q = (distance / *light.range) * (distance / *light.range);
    const double window = std::clamp(1.0 - q * q, 0.0, 1.0);
    reach *= window * window;
  }
  if (light.kind == LightKind::Spot) {
    const double cos_angle = glm::dot(-l, light.axis);
    const double cos_inner = std::cos(light.inner_angle * M_PI / 180.0),
                 cos_outer = std::cos(light.outer_angle * M_PI / 180.0);
    if (cos_inner > cos_outer) {
      const double s = std::clamp((cos_angle - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0);
      reach *= s * s * (3.0 - 2.0 * s);
    } else {
      reach *= cos_angle > cos_outer ? 1.0 : 0.0;
    }
  }
  return reach;
}

glm::dvec3 normalize_or_zero(const glm::dvec3& v) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : glm::dvec3(0.0);
}

LightTerms reference_light_terms(const Scene& scene, const SurfacePoint& s, const glm::dvec3& direction) {
  const Shading& sh = scene.shading;
  const glm::dvec3 v = -direction;
  const double occlusion = sh.ambient_occlusion ? normal_occlusion(scene, s) : 1.0;
  LightTerms terms;
  // Emitted light is unlit: the ambient layer carries it.
  terms.ambient = s.material.albedo * sh.ambient * occlusion + s.material.emission;
  for (const Light& light : scene.lights) {
    const bool positional = light.kind != LightKind::Directional;
    const glm::dvec3 l = positional ? normalize_or_zero(light.position - s.world) : light.direction;
    const Reflection lit = sh.model == ShadingModel::Pbr ? pbr_light(s.normal, l, v, s.material)
                                                         : classic_light(sh, s.normal, l, v, s.material);
    const double distance = positional ? glm::length(light.position - s.world) : 0.0;
    glm::dvec3 reaching = light.color * light.intensity * light_reach(light, l, distance);
    if (sh.shadows && light.shadows && glm::dot(s.normal, l) > 0.0) {
      reaching *= shadow_factor(scene, s, l, positional ? distance : sh.shadows->max_t);
    }
    terms.diffuse += lit.diffuse * reaching;
    terms.specular += lit.specular * reaching;
  }
  return terms;
}

glm::dvec3 reference_lit_color(const Scene& scene, const LightTerms& terms, int steps) {
  glm::dvec3 color = terms.ambient + terms.diffuse + terms.specular;
  const double step_ao = scene.shading.step_ao;
  if (step_ao > 0.0) color -= static_cast<double>(steps) * steps / step_ao;
  return glm::max(color, 0.0);
}

glm::dvec3 reference_shade(const Scene& scene, const SurfacePoint& s, const glm::dvec3& direction) {
  return reference_lit_color(scene, reference_light_terms(scene, s, direction), s.steps);
}

glm::dvec3 reference_miss_color(const Scene& scene, const glm::dvec3& d, double closest) {
  const Shading& sh = scene.shading;
  glm::dvec3 color = sh.background;
  if (sh.sky) color = sh.sky->horizon + (sh.sky->zenith - sh.sky->horizon) * std::clamp(d.y, 0.0, 1.0);
  if (sh.planetary_glow) {
    const PlanetaryGlow& g = *sh.planetary_glow;
    const double sun = 1.0 + std::pow(std::max(glm::dot(d, g.sun_direction), 0.0), 8.0);
    color += g.color * (std::exp(-g.sharpness * std::abs(d.y)) * sun);
  }
  if (sh.glow) {
    const double near = std::clamp(1.0 - closest / sh.glow->radius, 0.0, 1.0);
    color += sh.glow->color * (near * near);
  }
  return color;
}

glm::dvec3 reference_fog(const Scene& scene, const glm::dvec3& color_in, const glm::dvec3& d, double depth) {
  const Shading& sh = scene.shading;
  glm::dvec3 color = color_in;
  if (sh.fog) color = sh.fog->color + (color - sh.fog->color) * std::exp(-sh.fog->density * depth);
  if (sh.height_fog) {
    const HeightFog& f = *sh.height_fog;
    const double a = f.density, b = f.falloff, y0 = scene.camera.position.y;
    // The density a exp(-b y) integrated along the ray from height y0 to y1 = y0 + t dy:
    // (a / (b dy)) (exp(-b y0) - exp(-b y1)), whose limit for a level ray is a exp(-b y0) t.
    const double y1 = y0 + depth * d.y;
    const double amount =
        std::abs(d.y) < 1e-5 ? a * std::exp(-y0 * b) * depth : a / (b * d.y) * (std::exp(-b * y0) - std::exp(-b * y1));
    const double sun = std::pow(std::max(glm::dot(d, f.sun_direction), 0.0), f.sun_power);
    const glm::dvec3 fog = f.color + (f.sun_color - f.color) * sun;
    color = color + (fog - color) * std::clamp(amount, 0.0, 1.0);
  }
  return color;
}

glm::dvec3 reference_tone_map(const Scene& scene, const glm::dvec3& color_in) {
  glm::dvec3 color = color_in;
  if (scene.shading.tone_map == ToneMap::Reinhard) color = color / (color + 1.0);
  if (scene.shading.gamma != 1.0) color = glm::pow(color, glm::dvec3(1.0 / scene.shading.gamma));
  return color;
}

}  // namespace clmarch

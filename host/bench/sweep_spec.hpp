// What `clmarch bench --sweep KEY=V1,V2,...` varies: parsing the axes, expanding them into
// combinations, and applying a combination. Scene keys become --set overrides (the loader
// validates them); kernel keys (lanes, precision, fast_math, native_math) set OpenClOptions.
#pragma once

#include "render/opencl_renderer.hpp"

#include <string>
#include <utility>
#include <vector>

namespace clmarch {

/// One --sweep: a key and the values it takes, in the order given.
struct SweepAxis {
  std::string key;
  std::vector<std::string> values;
};

/// Keys that are not scene keys but change how the program is built.
inline constexpr const char* kSweepKernelKeys[] = {"lanes", "precision", "fast_math", "native_math"};
/// Values of the on/off kernel keys.
inline constexpr const char* kSwitchNames[] = {"off", "on"};

/// The most combinations one sweep may expand to (each is rendered 1 + repeat times).
inline constexpr std::size_t kMaxSweepCombinations = 1000;

/// One value per axis, in axis order: (key, value).
using SweepCombination = std::vector<std::pair<std::string, std::string>>;

/// True for lanes, precision, fast_math and native_math.
bool is_kernel_key(const std::string& key);

/// Parses "KEY=V1,V2,..." (commas inside [] or {} belong to the value: camera.position=[0,0,5],[0,0,9]).
/// Kernel keys' values are checked here; scene keys' when the scene is loaded. Throws InputError
/// naming --sweep, also for render.width and render.height (the size is --size's).
SweepAxis parse_sweep_axis(const std::string& text);

/// Every combination of the axes' values (the Cartesian product, the last axis varying fastest).
/// Throws InputError for a key swept twice or more than kMaxSweepCombinations combinations.
std::vector<SweepCombination> expand_sweep(const std::vector<SweepAxis>& axes);

/// The base (the empty combination: the scene as given) first, then each axis's values alone with
/// every other setting at the base's: a one-at-a-time sweep around the scene's settings.
std::vector<SweepCombination> expand_one_at_a_time(const std::vector<SweepAxis>& axes);

/// The scene keys of a combination as --set texts ("render.epsilon=1e-3").
std::vector<std::string> scene_sets(const SweepCombination& combination);

/// The scene keys of a combination that change what is drawn: all but render.* (camera, sdf,
/// lights, shading, tiling). render.* only changes how exactly the march draws it.
std::vector<std::string> picture_sets(const SweepCombination& combination);

/// options with the combination's kernel keys applied. Throws InputError for native_math=on with
/// precision=double (OpenCL has no native_* for double).
OpenClOptions with_kernel_settings(OpenClOptions options, const SweepCombination& combination);

/// "render.epsilon=1e-3 lanes=16": the combination as one CSV field ("" for the base).
std::string combination_label(const SweepCombination& combination);

}  // namespace clmarch

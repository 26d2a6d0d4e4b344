// A node's color key: a color, or a pattern of the point (checker, stripes, grid, expressions).
#pragma once

#include "scene/scene.hpp"
#include "scene/yaml_reader.hpp"

#include <string>

namespace clmarch {

/// Reads value, the color key of node at what: [r, g, b] or one number (node.color); a map with
/// one of checker, stripes or grid; or [r, g, b] whose components are expressions of the point
/// x, y, z (and t) (node.color_pattern). Fails naming the key on anything else.
void read_node_color(const YamlReader& yaml, const YAML::Node& value, const std::string& what, Node& node);

}  // namespace clmarch

// Scenes of every node kind written from its declaration (scene/node_kinds.def): the node with
// its defaults, values for its required parameters, and children for operators, so that tests
// looping over the kind list cover a new kind without being edited.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <string>

namespace clmarch::testing {

/// The YAML of a node of the kind (one line, "name: {...}"), its positions moved by offset: a
/// primitive's points, or the translate of a primitive without points and of an operator (whose
/// children stay in its frame: repetition is about the frame's origin). Operators combine a
/// sphere and a box, or modify a box.
std::string kind_node(NodeKind kind, const glm::dvec3& offset = glm::dvec3(0.0));

/// Render settings the kind's scene needs beyond the defaults ("key: value, " or "").
std::string kind_render_settings(NodeKind kind);

}  // namespace clmarch::testing

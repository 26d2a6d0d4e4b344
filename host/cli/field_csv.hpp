// The files of `clmarch field`: the points it reads (header x,y,z) and the samples it writes
// (header x,y,z,distance,r,g,b).
#pragma once

#include "api/field.hpp"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace clmarch {

/// The points of the CSV file at path, in its order. Throws InputError naming the file and line:
/// unreadable, empty, a header other than x,y,z, a row without 3 numbers, a value that is not a
/// finite number.
std::vector<glm::dvec3> read_points_csv(const std::string& path);

/// The CSV text of the samples at points: a header, then one row a point in their order; each
/// number as the shortest decimal that reads back as the same value (float or double).
std::string field_csv_text(const std::vector<glm::dvec3>& points, const FieldSamples& samples);

}  // namespace clmarch

// Instance files: one primitive a row of a CSV file, for unions of many primitives that plain YAML
// would be slow to read (scene-format.md, instances). This reads and checks the numbers; the scene
// loader turns each row into a node. `clmarch field` reads its points file with it too.
#pragma once

#include <string>
#include <vector>

namespace clmarch {

/// A CSV file of numbers under a header row of column names.
struct InstanceTable {
  std::string path;
  std::vector<std::string> columns;
  /// The file's line of the header row (1-based).
  int header_line = 0;
  /// Row r's values, columns.size() of them.
  std::vector<std::vector<double>> rows;
  /// The file's line of each row (1-based), for messages.
  std::vector<int> lines;
};

/// Reads path; throws InputError "path:line:col: what is wrong" for an unreadable file, a missing
/// or repeated column name, a row of the wrong length, a value that is not a finite number, and
/// more than max_rows rows. what names the file in messages ("instance file", "points file").
InstanceTable read_instance_table(const std::string& path, long long max_rows, const std::string& what);

}  // namespace clmarch

// Whether the driver served a program build from its own cache, for --verbose. Known for PoCL,
// whose kernel cache (kcache) gets a new entry on every miss; unknown for other drivers.
#pragma once

#include "cl/devices.hpp"

#include <filesystem>
#include <string>

namespace clmarch {

enum class BuildCache { Unknown, Off, Hit, Miss };
inline constexpr const char* kBuildCacheNames[] = {"unknown", "off", "hit", "miss"};

/// PoCL's cache folder as PoCL 3 resolves it: $POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl/kcache,
/// else $HOME/.cache/pocl/kcache.
std::filesystem::path pocl_cache_folder();

/// Brackets one clBuildProgram. PoCL writes a miss as kcache/XX/HASH/program.bc during the build
/// and only reads on a hit, so a program.bc newer than the start of the build means a miss. This
/// decides by what the driver did, not by the build time (a hit takes ~40 ms here, a miss 0.3 to
/// 1 s, but a loaded machine blurs that). A concurrent miss of another process in the same XX
/// folder during the build would be taken for ours: rare, and only a --verbose detail.
class BuildCacheProbe {
 public:
  /// Call just before the build.
  explicit BuildCacheProbe(const DeviceEntry& device);
  /// Call just after the build.
  BuildCache result() const;
  /// The cache folder looked at (empty unless the driver is PoCL).
  const std::filesystem::path& folder() const { return folder_; }

 private:
  bool pocl_ = false;
  bool disabled_ = false;
  std::filesystem::path folder_;
  std::filesystem::file_time_type start_;
};

}  // namespace clmarch

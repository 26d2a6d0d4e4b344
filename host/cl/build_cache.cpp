// PoCL's kcache inspected around a build.
#include "cl/build_cache.hpp"

#include <chrono>
#include <cstdlib>
#include <string_view>
#include <system_error>

namespace clmarch {
namespace {

std::filesystem::path environment_path(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? std::filesystem::path(value) : std::filesystem::path();
}

}  // namespace

std::filesystem::path pocl_cache_folder() {
  if (auto dir = environment_path("POCL_CACHE_DIR"); !dir.empty()) return dir;
  if (auto xdg = environment_path("XDG_CACHE_HOME"); !xdg.empty()) return xdg / "pocl" / "kcache";
  if (auto home = environment_path("HOME"); !home.empty()) return home / ".cache" / "pocl" / "kcache";
  return {};
}

BuildCacheProbe::BuildCacheProbe(const DeviceEntry& device) {
  pocl_ = device.is_pocl();
  if (!pocl_) return;
  const char* enabled = std::getenv("POCL_KERNEL_CACHE");
  disabled_ = enabled != nullptr && std::string_view(enabled) == "0";
  folder_ = pocl_cache_folder();
  // File times come from the kernel's coarse clock, which may lag the fine one by a tick or two.
  start_ = std::filesystem::file_time_type::clock::now() - std::chrono::milliseconds(20);
}

BuildCache BuildCacheProbe::result() const {
  if (!pocl_ || folder_.empty()) return BuildCache::Unknown;
  if (disabled_) return BuildCache::Off;
  std::error_code error;
  // A new HASH folder changes its XX folder's time, so only recently changed XX folders are read.
  for (const auto& bucket : std::filesystem::directory_iterator(folder_, error)) {
    std::error_code ignored;
    if (!bucket.is_directory(ignored) || bucket.last_write_time(ignored) < start_) continue;
    for (const auto& entry : std::filesystem::directory_iterator(bucket.path(), ignored)) {
      const auto program = entry.path() / "program.bc";
      std::error_code missing;
      const auto written = std::filesystem::last_write_time(program, missing);
      if (!missing && written >= start_) return BuildCache::Miss;
    }
  }
  return error ? BuildCache::Unknown : BuildCache::Hit;
}

}  // namespace clmarch

// The kernels/ files, compiled into the program (see embed_kernels.cmake).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace clmarch {

struct EmbeddedFile {
  std::string_view name;
  std::string_view contents;
};

/// Every file of kernels/, by base name.
const std::vector<EmbeddedFile>& embedded_kernel_files();

/// The file of kernels/ with this base name, behind a #line naming it so build errors point at it.
std::string kernel_file(std::string_view name);

}  // namespace clmarch

// libFuzzer target: scene text through the loader and, when it is accepted, through the code
// generator for every kernel purpose. A rejected scene must be an InputError (a one-line message);
// anything else (a crash, another exception, a sanitizer report, a generated literal that OpenCL C
// cannot parse) is a bug, and the input that found it becomes a test in tests/fuzz_regressions/.
// With CLMARCH_FUZZ_BUILDS=N the first N accepted inputs are also built on the OpenCL device (too
// slow while fuzzing; scripts/fuzz.sh does it for the corpus afterwards): a failed build is a bug.
// With CLMARCH_FUZZ_PRINT_KINDS=1 it prints the dictionary words of the node kinds (their names,
// keys and choices, from scene/node_kinds.def) and exits; scripts/fuzz.sh adds them to
// tests/fuzz/scene.dict.
#include "cl/device_program.hpp"
#include "codegen/kernel_source.hpp"
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <string>

namespace {

using namespace clmarch;

[[noreturn]] void bug(const std::string& what) {
  std::fprintf(stderr, "clmarch fuzz: %s\n", what.c_str());
  std::abort();
}

/// The generated scene code must spell every number as a finite float literal: fmt writes a float
/// that overflowed as "inf" and OpenCL C has no such literal, so the build would fail.
void check_generated_literals(const std::string& source) {
  static const std::regex non_finite(R"((^|[^A-Za-z0-9_])(inf|nan)f?([^A-Za-z0-9_]|$))");
  const std::size_t begin = source.find("#line 1 \"generated scene\"");
  if (begin == std::string::npos) bug("the generated scene code is missing from the program");
  const std::size_t end = source.find("#line 1 \"kernels/", begin);
  const std::string generated = source.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  std::smatch match;
  if (std::regex_search(generated, match, non_finite))
    bug("non-finite literal '" + match[2].str() + "' in:\n" + generated);
  // The defines before the first library file carry values too (shading constants, background).
  const std::string defines = source.substr(0, source.find("#line 1 \"kernels/"));
  if (std::regex_search(defines, match, non_finite)) bug("non-finite literal '" + match[2].str() + "' in:\n" + defines);
}

/// Accepted inputs still to be built on the device (CLMARCH_FUZZ_BUILDS).
int& builds_left() {
  static int left = [] {
    const char* value = std::getenv("CLMARCH_FUZZ_BUILDS");
    return value != nullptr ? std::atoi(value) : 0;
  }();
  return left;
}

void build_on_device(const Scene& scene) {
  static const DeviceEntry device = select_device(std::nullopt);
  const std::string source = generate_kernel_source(scene, {KernelPurpose::Shaded, default_lanes(device)});
  try {
    const DeviceProgram program = build_device_program(device, source);
    std::fprintf(stderr, "clmarch fuzz: an accepted scene built on %s in %.0f ms\n", device.label().c_str(),
                 program.build_ms);
  } catch (const DeviceError& e) {
    bug(std::string("an accepted scene does not build:\n") + e.what());
  }
}

void run_one(const std::string& text) {
  Scene scene;
  try {
    scene = load_scene_text(text, "fuzz.yaml");
  } catch (const InputError&) {
    return;  // rejected with a message: what bad input should get
  }
  for (KernelPurpose purpose : {KernelPurpose::DepthSteps, KernelPurpose::Normals, KernelPurpose::Shaded,
                                KernelPurpose::Buffers, KernelPurpose::EvalPoints}) {
    for (int lanes : {1, 16}) {
      check_generated_literals(generate_kernel_source(scene, {purpose, lanes}));
    }
  }
  if (builds_left() > 0) {
    --builds_left();
    build_on_device(scene);
  }
}

}  // namespace

/// The node kinds' words in libFuzzer's dictionary format, one a line.
void print_kind_words() {
  for (NodeKind kind : kAllNodeKinds) {
    std::printf("\"%s\"\n", std::string(node_kind_name(kind)).c_str());
    for (const ParamSpec& spec : param_table(kind)) {
      std::printf("\"%s\"\n", spec.key);
      for (const char* choice : spec.choices) std::printf("\"%s\"\n", choice);
    }
  }
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* print = std::getenv("CLMARCH_FUZZ_PRINT_KINDS"); print != nullptr && std::string(print) == "1") {
    print_kind_words();
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    run_one(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const std::exception& e) {
    bug(std::string("uncaught exception (not an InputError): ") + e.what());
  }
  return 0;
}

// Every way a command can fail, as the user sees it: exactly one line on stderr (a build log may
// follow a device error) and the exit code of docs/cli.md.
#include "cl/cl_errors.hpp"
#include "cli/error_report.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <new>

namespace clmarch {
namespace {

using testing::run_clmarch;
using testing::source_path;
using testing::TempDir;

struct Reported {
  int code = -1;
  std::string err;
};

Reported report(const std::function<int()>& command) {
  ::testing::internal::CaptureStderr();
  Reported r;
  r.code = run_reporting_errors(command);
  r.err = ::testing::internal::GetCapturedStderr();
  return r;
}

long lines(const std::string& text) { return std::count(text.begin(), text.end(), '\n'); }

TEST(ExitCodes, EachErrorKindHasItsCodeAndOneLine) {
  struct Case {
    std::function<int()> command;
    int code;
    std::string line;
  };
  const std::vector<Case> cases = {
      {[] { return 0; }, kExitOk, ""},
      {[] { return static_cast<int>(kExitCheckFailed); }, kExitCheckFailed, ""},
      {[]() -> int { throw InputError("scene.yaml:1:2: bad"); }, kExitBadInput, "scene.yaml:1:2: bad\n"},
      {[]() -> int { throw OutputError("out.png: cannot write: disk full"); }, kExitOutputFailed,
       "out.png: cannot write: disk full\n"},
      {[]() -> int { throw std::logic_error("a broken invariant"); }, kExitInternalError,
       "clmarch: internal error: a broken invariant (please report it with the command and scene)\n"},
      {[]() -> int { throw std::bad_alloc(); }, kExitInternalError,
       "clmarch: internal error: std::bad_alloc (please report it with the command and scene)\n"},
      {[]() -> int { throw 42; }, kExitInternalError,
       "clmarch: internal error: an exception of unknown type (please report it with the command and scene)\n"},
      {[]() -> int { throw Cancelled(); }, kExitInterrupted, "clmarch: interrupted\n"},
  };
  for (const Case& c : cases) {
    const Reported r = report(c.command);
    EXPECT_EQ(r.code, c.code) << c.line;
    EXPECT_EQ(r.err, c.line);
  }
}

TEST(ExitCodes, InternalErrorStaysOneLine) {
  const Reported r = report([]() -> int { throw std::runtime_error("first\nsecond"); });
  EXPECT_EQ(r.code, kExitInternalError);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("first second"), std::string::npos) << r.err;
}

TEST(ExitCodes, DeviceFaultsHintAtTheReferenceOnTheirFirstLine) {
  const Reported plain =
      report([]() -> int { throw DeviceError("OpenCL error on D (P): clFinish failed with CL_OUT_OF_RESOURCES"); });
  EXPECT_EQ(plain.code, kExitDeviceFault);
  EXPECT_EQ(plain.err,
            "OpenCL error on D (P): clFinish failed with CL_OUT_OF_RESOURCES (the CPU renderer needs no OpenCL: "
            "clmarch render --backend reference)\n");
  // A build log stays after the first line, untouched.
  const Reported build = report([]() -> int {
    throw DeviceError(
        "OpenCL error on D (P): clBuildProgram failed with CL_BUILD_PROGRAM_FAILURE\nbuild log of D:\nx.cl:1:1: error");
  });
  EXPECT_EQ(build.code, kExitDeviceFault);
  EXPECT_EQ(build.err.substr(0, build.err.find('\n')),
            "OpenCL error on D (P): clBuildProgram failed with CL_BUILD_PROGRAM_FAILURE (the CPU renderer needs no "
            "OpenCL: clmarch render --backend reference)");
  EXPECT_NE(build.err.find("\nbuild log of D:\nx.cl:1:1: error\n"), std::string::npos) << build.err;
  // A raw cl::Error that escaped with_device_errors still names the call and the status.
  const Reported raw = report([]() -> int { throw cl::Error(CL_INVALID_DEVICE, "clGetDeviceInfo"); });
  EXPECT_EQ(raw.code, kExitDeviceFault);
  EXPECT_EQ(raw.err.find("OpenCL error: clGetDeviceInfo failed with CL_INVALID_DEVICE"), 0u) << raw.err;
  EXPECT_EQ(lines(raw.err), 1);
}

// An ICD loader folder without any .icd file: the machine has no OpenCL driver at all.
std::vector<std::string> no_opencl_environment(const TempDir& empty) {
  return {"OCL_ICD_VENDORS=" + empty.path().string()};
}

TEST(ExitCodes, NoOpenClPlatform) {
  TempDir empty;
  TempDir out;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"devices"},
        {"render", source_path("scenes/torus.yaml").string(), "--size", "16x9", "-o", (out / "t.png").string()},
        {"check", source_path("scenes/torus.yaml").string(), "--size", "16x9"}}) {
    const auto result = run_clmarch(args, no_opencl_environment(empty));
    EXPECT_EQ(result.exit_code, kExitDeviceFault) << args[0] << ": " << result.err;
    EXPECT_EQ(lines(result.err), 1) << result.err;
    EXPECT_EQ(result.err.find("no OpenCL platform or device found (clGetPlatformIDs"), 0u) << result.err;
    EXPECT_NE(result.err.find("--backend reference"), std::string::npos) << result.err;
  }
  EXPECT_TRUE(out.files().empty());
  // The CPU reference needs no platform.
  const auto reference = run_clmarch({"render", source_path("scenes/torus.yaml").string(), "--size", "16x9",
                                      "--backend", "reference", "-o", (out / "t.png").string()},
                                     no_opencl_environment(empty));
  EXPECT_EQ(reference.exit_code, kExitOk) << reference.err;
  EXPECT_EQ(out.files(), std::vector<std::string>{"t.png"});
}

TEST(ExitCodes, ParseErrorsAreBadInput) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{}, {"render"}, {"frobnicate"}, {"render", "x.yaml", "--size"}}) {
    const auto result = run_clmarch(args);
    EXPECT_EQ(result.exit_code, kExitBadInput) << result.err;
    EXPECT_EQ(lines(result.err), 1) << result.err;
    EXPECT_EQ(result.err.find("clmarch: "), 0u) << result.err;
  }
}

}  // namespace
}  // namespace clmarch

// Images too large for the machine's memory: the estimate, the message, and the CLI refusing them
// before anything is allocated (exit code 2, one line naming --size or render.width/height); scene
// values too large for the device (the operand grid's host memory is tested in operand_grid_test).
#include "cl/devices.hpp"
#include "common/errors.hpp"
#include "frame/frame_buffers.hpp"
#include "render/device_inputs.hpp"
#include "render/host_memory.hpp"
#include "support/sanitizers.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace clmarch {
namespace {

using testing::run_clmarch;
using testing::run_clmarch_in_shell;
using testing::TempDir;

/// The largest square within the pixel limit: 46340^2 = 2147395600 pixels, about a terabyte.
constexpr int kHugeSide = 46340;

TEST(HostMemory, EstimateCoversTheFrameBuffersAndTheWritersCopy) {
  EXPECT_GE(host_bytes_per_pixel(), kChannelCount * sizeof(float) + 8 * sizeof(float));
  EXPECT_EQ(render_host_bytes(1000, 2000), 2000000u * host_bytes_per_pixel());
  // No overflow at the largest sizes the loader accepts.
  EXPECT_EQ(render_host_bytes(65536, 32767), 65536ull * 32767ull * host_bytes_per_pixel());
}

TEST(HostMemory, ShortfallNamesNeededAndAvailableBytes) {
  const AvailableMemory available{1000000, "MemAvailable in /proc/meminfo"};
  EXPECT_EQ(host_memory_shortfall(40, 40, available), "") << "1 MB covers 1600 pixels";
  const std::string message = host_memory_shortfall(1000, 1000, available);
  const std::string needed = std::to_string(render_host_bytes(1000, 1000));
  EXPECT_NE(message.find("1000 x 1000 pixels need " + needed + " bytes"), std::string::npos) << message;
  EXPECT_NE(message.find("but only 1000000 bytes"), std::string::npos) << message;
  EXPECT_NE(message.find("(MemAvailable in /proc/meminfo)"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

// Issue 23: a values buffer past the device's limit for it is refused naming the limit: the one
// buffer it may allocate with an operand grid, its __constant memory without.
TEST(DeviceMemory, ValuesBufferBeyondTheDeviceNamesTheLimit) {
  const DeviceMemoryLimits limits{"cpu (Portable Computing Language)", 1000000, 65536};
  EXPECT_EQ(values_buffer_shortfall(1000000, true, limits), "");
  EXPECT_EQ(values_buffer_shortfall(65536, false, limits), "");
  EXPECT_EQ(
      values_buffer_shortfall(1000004, true, limits),
      "the scene's values buffer (its changing literals and its operand grid) needs 1000004 bytes (0.0 GiB), but the "
      "device cpu (Portable Computing Language) allows at most 1000000 bytes (CL_DEVICE_MAX_MEM_ALLOC_SIZE)");
  EXPECT_EQ(
      values_buffer_shortfall(65540, false, limits),
      "the scene's values buffer (its changing literals, in __constant memory) needs 65540 bytes (0.0 GiB), but the "
      "device cpu (Portable Computing Language) allows at most 65536 bytes (CL_DEVICE_MAX_CONSTANT_BUFFER_SIZE)");
  // The figures the check reads from a real device are at least OpenCL's minimums for them.
  const DeviceMemoryLimits device = device_memory_limits(select_device(std::nullopt));
  EXPECT_GE(device.max_alloc, std::uint64_t{128} << 20);
  EXPECT_GE(device.max_constant, std::uint64_t{64} << 10);
  EXPECT_FALSE(device.device.empty());
}

TEST(HostMemory, AvailableMemoryIsReadOnLinux) {
  const std::optional<AvailableMemory> available = available_host_memory();
  ASSERT_TRUE(available.has_value());
  EXPECT_GT(available->bytes, 0u);
  EXPECT_FALSE(available->source.empty());
}

/// Skips the test on a machine that could hold a kHugeSide^2 render (it would then really run).
#define SKIP_UNLESS_HUGE_RENDER_EXCEEDS_MEMORY()                                                      \
  do {                                                                                                \
    const std::optional<AvailableMemory> m = available_host_memory();                                 \
    if (!m || m->bytes >= render_host_bytes(kHugeSide, kHugeSide)) GTEST_SKIP() << "too much memory"; \
  } while (false)

TEST(HostMemory, CliRefusesSizeOptionBeyondMemory) {
  SKIP_UNLESS_HUGE_RENDER_EXCEEDS_MEMORY();
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << "sdf: {sphere: {}}\n";
  const std::string size = std::to_string(kHugeSide) + "x" + std::to_string(kHugeSide);
  const std::string pixels = std::to_string(kHugeSide) + " x " + std::to_string(kHugeSide);
  for (const char* command : {"render", "check", "bench"}) {
    std::vector<std::string> args = {command, (dir / "scene.yaml").string(), "--size", size};
    if (std::string(command) == "render") args.insert(args.end(), {"-o", (dir / "out.png").string()});
    const auto result = run_clmarch(args);
    EXPECT_EQ(result.exit_code, kExitBadInput) << command << ": " << result.err;
    EXPECT_EQ(result.err.find("--size " + size + ": " + pixels + " pixels need "), 0u) << command << ": " << result.err;
    EXPECT_NE(result.err.find(") of host memory"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("are available"), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});
  }
}

TEST(HostMemory, CliRefusesSceneSizeBeyondMemoryAtItsLine) {
  SKIP_UNLESS_HUGE_RENDER_EXCEEDS_MEMORY();
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << "sdf: {sphere: {}}\nrender: {width: " << kHugeSide << ", height: " << kHugeSide
                                    << "}\n";
  const auto result = run_clmarch({"render", (dir / "scene.yaml").string(), "-o", (dir / "out.png").string()});
  EXPECT_EQ(result.exit_code, kExitBadInput) << result.err;
  EXPECT_EQ(result.err.find((dir / "scene.yaml").string() +
                            ":2:17: render.width x render.height: 46340 x 46340 pixels need "),
            0u)
      << result.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});
  // --size wins over the file's size, so a small --size renders the same file.
  const auto small =
      run_clmarch({"render", (dir / "scene.yaml").string(), "--size", "8x8", "-o", (dir / "out.png").string()});
  EXPECT_EQ(small.exit_code, 0) << small.err;
}

TEST(HostMemory, CliHonoursTheAddressSpaceLimit) {
#if defined(CLMARCH_UNDER_ASAN)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space; it cannot run under ulimit -v";
#else
  // 20000 x 20000 pixels need 67 GB, far beyond an 8 GB address space, on any machine.
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << "sdf: {sphere: {}}\n";
  const auto result = run_clmarch_in_shell("ulimit -v 8000000; ", {"render", (dir / "scene.yaml").string(), "--size",
                                                                   "20000x20000", "-o", (dir / "out.png").string()});
  EXPECT_EQ(result.exit_code, kExitBadInput) << result.err;
  EXPECT_EQ(result.err.find("--size 20000x20000: 20000 x 20000 pixels need " +
                            std::to_string(render_host_bytes(20000, 20000)) + " bytes"),
            0u)
      << result.err;
  EXPECT_NE(result.err.find("ulimit -v"), std::string::npos) << result.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});

  // The OpenCL driver's own address space is counted: PoCL, started after a check that left it
  // too little, failed an allocation by an assertion and aborted (exit 134, 1700 x 1700 under a
  // 1.0 GB limit, counting 168 bytes per pixel alone): refused, never started. The side gives
  // 0.7 GB of the render's bytes, within the limit without the driver's 512 MiB, past it with them.
  const int side = static_cast<int>(std::sqrt(0.7e9 / static_cast<double>(host_bytes_per_pixel())));
  const std::string past_the_driver = std::to_string(side) + "x" + std::to_string(side);
  for (const auto& [size, exit_code] :
       {std::pair{past_the_driver.c_str(), kExitBadInput}, std::pair{"64x64", kExitOk}}) {
    const auto limited = run_clmarch_in_shell("ulimit -v 1000000; ", {"render", (dir / "scene.yaml").string(), "--size",
                                                                      size, "-o", (dir / "out.png").string()});
    EXPECT_EQ(limited.exit_code, exit_code) << size << ": " << limited.err;
  }
#endif
}

}  // namespace
}  // namespace clmarch

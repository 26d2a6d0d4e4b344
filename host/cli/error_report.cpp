// Exception kinds to messages and exit codes.
#include "cli/error_report.hpp"

#include "cl/cl_errors.hpp"
#include "cli/interrupts.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/interrupt_note.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <string>
#include <string_view>

namespace clmarch {
namespace {

std::string g_context;

void print(std::string_view text) {
  if (!g_context.empty()) {
    constexpr std::string_view kPrefix = "clmarch: ";
    if (text.starts_with(kPrefix)) text.remove_prefix(kPrefix.size());
    std::fputs(fmt::format("clmarch: {}: {}\n", g_context, text).c_str(), stderr);
    return;
  }
  std::fputs(fmt::format("{}\n", text).c_str(), stderr);
}

/// A device fault leaves the CPU renderer usable; the hint ends the first line (a build log may follow).
void print_device_fault(std::string_view message) {
  constexpr std::string_view kHint = " (the CPU renderer needs no OpenCL: clmarch render --backend reference)";
  const std::size_t end = message.find('\n');
  const std::string_view first = message.substr(0, end);
  const bool hinted = first.find("--backend reference") != std::string_view::npos;
  std::string text(first);
  if (!hinted) text.append(kHint);
  if (end != std::string_view::npos) text.append(message.substr(end));
  print(text);
}

}  // namespace

void set_error_context(std::string context) { g_context = std::move(context); }

const std::string& error_context() { return g_context; }

int run_reporting_errors(const std::function<int()>& command) {
  try {
    return command();
  } catch (const RankFailure& e) {
    // Said by rank 0 about another rank, or nothing: the rank's own error is printed already.
    if (*e.what() != '\0') std::fputs(fmt::format("{}\n", e.what()).c_str(), stderr);
    return e.exit_code;
  } catch (const InputError& e) {
    print(e.what());
    return kExitBadInput;
  } catch (const DeviceError& e) {
    print_device_fault(e.what());
    return kExitDeviceFault;
  } catch (const cl::Error& e) {
    // An OpenCL call outside with_device_errors: the call and status are known, the device is not.
    print_device_fault(fmt::format("OpenCL error: {} failed with {}", e.what(), cl_status_name(e.err())));
    return kExitDeviceFault;
  } catch (const OutputError& e) {
    print(e.what());
    return kExitOutputFailed;
  } catch (const Cancelled&) {
    print("clmarch: interrupted");
    write_interrupt_note();
    return interrupted_exit_code();
  } catch (const std::exception& e) {
    std::string what = e.what();
    for (char& c : what) c = c == '\n' ? ' ' : c;
    print(fmt::format("clmarch: internal error: {} (please report it with the command and scene)", what));
    return kExitInternalError;
  } catch (...) {
    print("clmarch: internal error: an exception of unknown type (please report it with the command and scene)");
    return kExitInternalError;
  }
}

}  // namespace clmarch

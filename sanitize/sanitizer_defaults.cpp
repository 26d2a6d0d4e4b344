// Built into every executable of a sanitized build (CLMARCH_SANITIZE, CLMARCH_FUZZ): the default
// sanitizer options, so that ctest, scripts and a developer's shell all run with the same ones
// (ASAN_OPTIONS, LSAN_OPTIONS and UBSAN_OPTIONS given in the environment still override them).

extern "C" {

// The sanitizer runtimes call these; they must not be instrumented themselves.
__attribute__((no_sanitize("address", "undefined"))) const char* __asan_default_options() {
  return "detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1";
}

__attribute__((no_sanitize("address", "undefined"))) const char* __ubsan_default_options() {
  return "print_stacktrace=1:halt_on_error=1";
}

// Leaks inside the OpenCL stack are not ours to fix and would fail every test that renders: the
// ICD loader (libOpenCL) and PoCL keep platform, device and compiler state for the life of the
// process and never free it, and PoCL's LLVM keeps its own globals. Only allocations whose stack
// passes through those libraries are suppressed; a leak in clmarch's code still fails the run.
__attribute__((no_sanitize("address", "undefined"))) const char* __lsan_default_suppressions() {
  return "leak:libOpenCL.so\n"
         "leak:libpocl.so\n"
         "leak:libpocl-devices-\n"
         "leak:libLLVM\n"
         "leak:libclang-cpp\n";
}

}  // extern "C"

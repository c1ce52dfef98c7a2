// Default options of the sanitizer runtimes, linked into every executable of a sanitizer build
// (cmake/Sanitizers.cmake). The runtimes call these weak hooks at start-up; ASAN_OPTIONS,
// UBSAN_OPTIONS and LSAN_OPTIONS in the environment still override them.

// NOLINTBEGIN: the names are the runtimes' interface.
extern "C" const char* __asan_default_options();
extern "C" const char* __ubsan_default_options();
extern "C" const char* __lsan_default_options();

extern "C" const char* __asan_default_options() {
    // check_initialization_order: a global constructor reading another file's global that is not
    // constructed yet. detect_stack_use_after_return: a returned reference or span to a local.
    // quarantine_size_mb=64 (ASan's default is 256): freed memory waits there before reuse, so a
    // use after free hits poison. lavapipe frees each renderer's device memory (images of several
    // MiB) through the same allocator, so the default quarantine made every new renderer's memory
    // fresh pages from the kernel: a GPU test ran 41 s, 32 s with 64 MiB (Release: 12 s). 64 MiB
    // still holds the last thousands of our own objects' frees, the use-after-free window that
    // matters (a dangling pointer used right after its owner goes).
    return "detect_leaks=1:check_initialization_order=1:detect_stack_use_after_return=1:"
           "strict_string_checks=1:abort_on_error=0:quarantine_size_mb=64";
}

extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }

// Leaks inside the third-party libraries we do not build are suppressed there, each with its
// reason; any leak with only our frames is reported and fails the run.
extern "C" const char* __lsan_default_options() { return "suppressions=" PUNCTUAL_LSAN_SUPPRESSIONS ":print_suppressions=0"; }
// NOLINTEND

// The Vulkan loader unloads the driver (lavapipe) and the validation layers in vkDestroyInstance,
// before the leak check at exit, which then cannot name a single frame of what they allocated
// ("<unknown module>") and no suppression can match it. Keeping every library loaded for the
// life of the process (a sanitizer build only) lets reports name the library and function.
// <dlfcn.h> is not included: its declaration carries glibc's exception specification.
extern "C" int dlclose(void* /*handle*/) { return 0; }

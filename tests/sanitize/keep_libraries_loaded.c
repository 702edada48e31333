// Linked into every executable of the sanitizer build (SIXWAY_SANITIZE, tools/sanitize.sh): the Vulkan loader unloads the driver (lavapipe) and the validation layer
// when the instance is destroyed, before LeakSanitizer runs at exit, so their leaks are reported from an
// "<unknown module>" that no suppression can name. Keeping every library mapped lets LeakSanitizer name
// them (tests/sanitize/lsan_suppressions.txt).
int dlclose(void* handle) {
  (void)handle;
  return 0;
}

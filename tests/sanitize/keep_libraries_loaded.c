/* ./run sanitize preloads this into every test process (LD_PRELOAD): dlclose does nothing.
 *
 * The Vulkan loader unloads the driver (lavapipe) and the validation layer when the
 * instance is destroyed, before LeakSanitizer's report at exit. A leak allocated inside
 * an unloaded library then has frames no symbolizer can name (they read as "<unknown
 * module>" or as offsets into libasan), so tests/sanitize/lsan.supp cannot match it by
 * library, and a leak of ours through such a library would lose its stack. Keeping every
 * library mapped until exit gives every frame its name. Nothing else changes: no program
 * of the project calls dlclose and expects the library gone. */
int dlclose(void *handle)
{
    (void)handle;
    return 0;
}

// The run-time method registry (make_shadow_map), compiled once for the project's own programs: each
// file that included methods/registry.hpp inline would instantiate every method size again (about two
// minutes at -O3). Those programs define HAIRSHADOW_SEPARATE_REGISTRY and link this file's library.
#define HAIRSHADOW_REGISTRY_IMPLEMENTATION
#include <hairshadow/methods/registry.hpp>

// The non-template kernels compiled once (config.hpp, HAIRSHADOW_SEPARATE_KERNELS): a program whose
// files all define HAIRSHADOW_SEPARATE_KERNELS links this file's library (CMake: hairshadow::kernels)
// and compiles only the templates of the methods it uses. A program of its own may copy these lines.
#define HAIRSHADOW_KERNELS_IMPLEMENTATION
#include <hairshadow/hairshadow.hpp>

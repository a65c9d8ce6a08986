// Stands in for gl_backend.cpp where the build found no GL loader (python3-glad) or no headless
// context library (libosmesa6-dev, libegl-dev).
#include "gl_backend.hpp"

namespace cli {

std::unique_ptr<gl_backend> gl_backend::open(const std::string&, const std::string&) {
    throw hairshadow::error("this hairshadow was built without the GL back end (it needs python3-glad, libosmesa6-dev and libegl-dev)");
}

std::unique_ptr<gl_backend> gl_backend::open_on(hairshadow::gl::headless_context&, const std::string&) {
    return open("", "");
}

} // namespace cli

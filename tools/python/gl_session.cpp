// The module's headless GL context (bindings.hpp: gl_context).
#include <glad/gl.h>

#include "bindings.hpp"

#include <hairshadow/gl/context/egl_context.hpp>
#include <hairshadow/gl/context/error.hpp>
#include <hairshadow/gl/context/osmesa_context.hpp>
#include <hairshadow/gl/maps/registry.hpp>
#include <hairshadow/gl/passes/hair_mesh.hpp>

#include <memory>
#include <mutex>
#include <thread>

namespace hspy {

namespace {
struct gl_session {
    std::mutex mutex; ///< guards the fields: Python threads reach here without the GIL
    std::string kind;
    std::unique_ptr<hairshadow::gl::headless_context> context;
    std::thread::id owner;
    std::vector<std::unique_ptr<hairshadow::gl::any_gl_shadow_map>> retired_maps;
    std::vector<std::unique_ptr<hairshadow::gl::hair_mesh>> retired_meshes;
};

gl_session& session() {
    static auto* s = new gl_session; // never destroyed: maps may hold GL objects until the interpreter's last collection
    return *s;
}
} // namespace

hairshadow::gl::headless_context& gl_context(const std::string& kind) {
    auto& s = session();
    std::lock_guard lock(s.mutex);
    if (!s.context) {
        const std::string chosen = kind.empty() ? "egl" : kind;
        // Core 3.3 asked, as the command does: drivers answer with their newest core version, and each
        // method checks the version and limits it needs.
        if (chosen == "osmesa") s.context = std::make_unique<hairshadow::gl::osmesa_context>(3, 3);
        else if (chosen == "egl") s.context = std::make_unique<hairshadow::gl::egl_context>(3, 3);
        else throw hairshadow::argument_error("unknown GL context '" + kind + "'; valid: egl, osmesa");
        if (!gladLoadGL(s.context->loader())) {
            s.context.reset();
            throw hairshadow::gl::gl_error("cannot load the GL functions of the " + chosen + " context");
        }
        s.kind = chosen;
        s.owner = std::this_thread::get_id();
    }
    if (!kind.empty() && kind != s.kind)
        throw hairshadow::argument_error("this process's GL context is " + s.kind + ", and a process has one kind of context (asked for " + kind + ")");
    if (std::this_thread::get_id() != s.owner)
        throw hairshadow::gl::gl_error("GL is used from the thread that first used it (a GL context is current on one thread)");
    s.context->make_current();
    s.retired_maps.clear(); // on their own context now
    s.retired_meshes.clear();
    return *s.context;
}

std::string gl_context_kind() {
    auto& s = session();
    std::lock_guard lock(s.mutex);
    return s.kind;
}

void retire_gl_objects(std::unique_ptr<hairshadow::gl::any_gl_shadow_map> maps, std::unique_ptr<hairshadow::gl::hair_mesh> mesh) {
    auto& s = session();
    std::lock_guard lock(s.mutex);
    if (maps) s.retired_maps.push_back(std::move(maps));
    if (mesh) s.retired_meshes.push_back(std::move(mesh));
}

} // namespace hspy

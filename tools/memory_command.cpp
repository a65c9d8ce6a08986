// `hairshadow memory`: the bytes a method's maps hold at a resolution (for a model, or from the
// spec alone where the method's size does not depend on the model).
#include "command_line.hpp"

#include <cstdio>

#include <unistd.h>

namespace cli {

using namespace hairshadow;

namespace {
/// Bytes of physical memory in this machine; 0 where the system does not say.
std::size_t machine_memory_bytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? std::size_t(pages) * std::size_t(page) : 0;
}

int run_memory(const map_options& o) {
    const auto spec = parse_method(o.method);
    check_resolution(o.resolution);
    if (o.model.empty()) {
        const auto bytes = make_shadow_map(spec)->memory_bytes_at(o.resolution);
        if (!bytes) throw usage_error("the exact map's size depends on the model's fragments: give a MODEL");
        std::printf("%s at %dx%d: %zu bytes (%.2f MiB)\n", spec.text.c_str(), o.resolution, o.resolution, *bytes, double(*bytes) / 1048576.0);
        // A build of maps that cannot fit fails (out of memory, exit 1); say so before anyone tries.
        if (const std::size_t machine = machine_memory_bytes(); machine > 0 && *bytes > machine)
            std::printf("the maps do not fit in this machine's memory (%.1f GiB): a build would fail\n", double(machine) / 1073741824.0);
        return 0;
    }
    const auto s = prepare_scene(o, false);
    const auto map = build_map(spec, s);
    std::printf("%s at %dx%d for %s: %zu bytes (%.2f MiB)\n", spec.text.c_str(), o.resolution, o.resolution, o.model.c_str(), map->memory_bytes(),
                double(map->memory_bytes()) / 1048576.0);
    return 0;
}
} // namespace

command add_memory_command(CLI::App& app, map_options& o) {
    auto* cmd = app.add_subcommand("memory", "print the bytes a method's maps hold at a resolution");
    add_model(cmd, o, false);
    add_map_options(cmd, o);
    return {cmd, [&o] { return run_memory(o); }};
}

} // namespace cli

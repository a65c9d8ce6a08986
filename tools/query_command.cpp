// `hairshadow query`: the transmittance of a method's maps at each point of a file.
#include "command_line.hpp"

#include <hairshadow/io/points_file.hpp>

#include <cstdio>

namespace cli {

using namespace hairshadow;

namespace {
int run_query(const map_options& o, const std::string& points_file) {
    const auto spec = parse_method_for(o.method, o);
    const auto points = read_points(points_file);
    auto s = prepare_scene(o, false);
    const auto t = evaluate(spec, s, o, points).transmittance;
    std::string out;
    char buf[32];
    for (float v : t) {
        std::snprintf(buf, sizeof buf, "%.6f\n", double(v));
        out += buf;
    }
    std::fwrite(out.data(), 1, out.size(), stdout);
    return 0;
}
} // namespace

command add_query_command(CLI::App& app, map_options& o) {
    auto points_file = std::make_shared<std::string>();
    auto* cmd = app.add_subcommand("query", "print the transmittance at each point of a file of 'x y z' lines");
    add_model(cmd, o);
    add_map_options(cmd, o);
    add_query_options(cmd, o);
    add_backend_options(cmd, o);
    cmd->add_option("--points", *points_file, "file of 'x y z' lines")->required();
    return {cmd, [&o, points_file] { return run_query(o, *points_file); }};
}

} // namespace cli

// The `hairshadow` command: inspect hair models, build any method's shadow maps, query, render and
// compare them with the exact reference. Errors go to stderr as `error: ...` with exit status 1;
// usage errors exit 2: unknown options, bad specs, and any option value that is malformed, not finite
// or out of its range, for every command. Errors that depend on the input (a file, a light that does
// not fit the model) exit 1. Each subcommand is a file of its own (<name>_command.cpp).
#include "command_line.hpp"

#include <cstdio>
#include <new>

int main(int argc, char** argv) {
    CLI::App app{"hairshadow: self-shadowing of hair - build, query, render and compare shadow maps"};
    app.require_subcommand(1);
    app.failure_message([](const CLI::App* command, const CLI::Error& e) {
        return "error: " + CLI::FailureMessage::simple(command, e); // as every other error is reported
    });
    cli::map_options o;
    app.add_option("--threads", o.threads, "worker threads; 0 = all cores");
    const cli::command commands[] = {cli::add_info_command(app, o),    cli::add_query_command(app, o),   cli::add_render_command(app, o),
                                     cli::add_memory_command(app, o),  cli::add_compare_command(app, o), cli::add_bench_command(app, o),
                                     cli::add_animate_command(app, o), cli::add_figure_command(app, o),
                                     cli::add_export_command(app, o)};
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    try {
        for (const auto& c : commands)
            if (*c.app) return c.run();
    } catch (const cli::usage_error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "error: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 2;
}

// rtm: relief texture mapping. Thin command line over the warp, texmap and objects libraries.
#include <cstdio>
#include <exception>

#include "cli_common.h"

int main(int argc, char** argv) {
    CLI::App app{"rtm: relief texture mapping (Oliveira, Bishop, McAllister 2000)", "rtm"};
    app.require_subcommand(1);
    rtm::cli::add_prewarp_command(app);
    rtm::cli::add_render_command(app);
    rtm::cli::add_compare_command(app);
    rtm::cli::add_bench_skips_command(app);
    rtm::cli::add_view_command(app);
    rtm::cli::add_diff_command(app);
    rtm::cli::add_bench_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "rtm: %s (try --help)\n", e.what());
        return 2;
    } catch (const rtm::cli::UsageError& e) {
        std::fprintf(stderr, "rtm: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rtm: %s\n", e.what());
        return 1;
    }
    return 0;
}

// rtm: relief texture mapping. Thin command line over the warp, texmap and objects libraries.
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "cli_common.h"
#include "rtm_version.h"
#include "formats/image_io.h"

int main(int argc, char** argv) {
    // One line on stderr per failure: libpng's own copy of a read error must not reach it.
    rtm::set_quiet_image_library_stderr(true);
    CLI::App app{"rtm: relief texture mapping (Oliveira, Bishop, McAllister 2000)", "rtm"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "rtm " RTM_VERSION, "Print the version (rtm X.Y.Z) and exit");
    rtm::cli::add_prewarp_command(app);
    rtm::cli::add_render_command(app);
    rtm::cli::add_compare_command(app);
    rtm::cli::add_bench_skips_command(app);
    rtm::cli::add_view_command(app);
    rtm::cli::add_diff_command(app);
    rtm::cli::add_bench_command(app);
    rtm::cli::add_bench_filter_command(app);
    rtm::cli::add_bake_command(app);
    // An option before any subcommand that rtm itself does not take: name it (CLI11 says only that a subcommand is
    // required).
    if (argc > 1 && argv[1][0] == '-') {
        const std::string first = argv[1];
        if (first != "-h" && first != "--help" && first != "--version" && first != "--help-all") {
            std::fprintf(stderr, "rtm: unknown option \"%s\" before the subcommand (try --help)\n",
                         rtm::printable_one_line(first).c_str());
            return 2;
        }
    }
    // A first word that names no subcommand: say which word, not only that a subcommand is required.
    if (argc > 1 && argv[1][0] != '-' &&
        app.get_subcommands([&](const CLI::App* sub) { return sub->get_name() == argv[1]; }).empty()) {
        std::string known;
        for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
            known += (known.empty() ? "" : ", ") + sub->get_name();
        std::fprintf(stderr, "rtm: unknown subcommand \"%s\"; known: %s (try --help)\n",
                     rtm::printable_one_line(argv[1]).c_str(), known.c_str());
        return 2;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "rtm: %s (try --help)\n", rtm::printable_one_line(e.what()).c_str());
        return 2;
    } catch (const rtm::cli::UsageError& e) {
        std::fprintf(stderr, "rtm: %s\n", rtm::printable_one_line(e.what()).c_str());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "rtm %s: out of memory: the input needs more than this machine can give\n",
                     argc > 1 ? rtm::printable_one_line(argv[1]).c_str() : "");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rtm: %s\n", rtm::printable_one_line(e.what()).c_str());
        return 1;
    }
    return 0;
}

// compare_page_fixture DIR: writes the synthetic comparison of tests/measure/compare_page_fixture.h with its page
// into DIR, for tests/cli/compare_page.sh (the headless browser test).
// compare_page_fixture --page DIR: rewrites DIR/index.html from DIR/results.json (no step-by-step section), to look
// at the page of another run's results.
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

#include "measure/compare_page.h"
#include "measure/compare_page_fixture.h"

int main(int argc, char** argv) {
    const bool page = argc == 3 && std::string(argv[1]) == "--page";
    if (argc != 2 && !page) {
        std::fprintf(stderr, "usage: compare_page_fixture DIR | compare_page_fixture --page DIR\n");
        return 2;
    }
    try {
        if (page) {
            const std::string dir = argv[2];
            std::ifstream in(dir + "/results.json");
            if (!in) throw std::runtime_error(dir + "/results.json: cannot read");
            rtm::ComparePageInput input;
            input.out_dir = dir;
            input.results = nlohmann::json::parse(in);
            rtm::write_compare_page(input);
        } else {
            rtm::test::write_compare_fixture_page(argv[1]);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "compare_page_fixture: %s\n", e.what());
        return 1;
    }
    return 0;
}

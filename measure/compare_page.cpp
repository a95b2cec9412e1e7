#include "measure/compare_page.h"

#include "formats/atomic_file.h"

namespace rtm {

// Placeholder until the page lands: a minimal valid page that names the results file.
void write_compare_page(const ComparePageInput& input) {
    write_text_atomically(input.out_dir + "/index.html",
                          "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>rtm compare</title>"
                          "</head><body><p>See results.csv and results.json.</p></body></html>\n");
}

}  // namespace rtm

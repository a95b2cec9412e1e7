// Text for the comparison's page: escaping for HTML text and attributes (the page is also well-formed XML, so
// these escape everything XML needs), and numbers printed with a dash where a value is missing (NaN).
#pragma once

#include <string>
#include <string_view>

namespace rtm {

std::string html_escape(std::string_view s);  // & < > " ' as character references
// `v` with `decimals` decimals ("-" when not finite).
std::string fixed(double v, int decimals);
// `v` with three significant digits, as frame times read best (0.0123, 1.23, 12.3, 123) ("-" when not finite).
std::string significant(double v);

}  // namespace rtm

#include "mesh/header_guard.h"

#include <fstream>
#include <sstream>
#include <vector>

namespace rtm {
namespace {

std::string too_many(const std::string& count, const std::string& what, std::uintmax_t file_size) {
    return "header declares " + count + " " + what + " in a file of " + std::to_string(file_size) + " bytes";
}

// A decimal count; anything else (negative, not a number) is left to assimp's own checks.
bool parse_count(const std::string& s, long double& out) {
    if (s.empty() || s.size() > 40) return false;
    for (char c : s)
        if (c < '0' || c > '9') return false;
    out = std::stold(s);
    return true;
}

}  // namespace

std::string check_declared_counts(const std::string& path, std::uintmax_t file_size) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "";
    std::string head(65536, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(size_t(in.gcount()));
    std::istringstream lines(head);
    std::string line;
    if (!std::getline(lines, line)) return "";
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const long double size = static_cast<long double>(file_size);

    if (line == "ply") {
        // "element NAME COUNT" lines up to "end_header", which must come: assimp 5.2's PLY reader loops without end
        // on a header cut short (a 77-byte file ending after "element vertex 8", found by changing its test models).
        while (std::getline(lines, line)) {
            std::istringstream words(line);
            std::string word, name, count;
            words >> word;
            if (word == "end_header") return "";
            if (word != "element") continue;
            words >> name >> count;
            long double n = 0;
            if (parse_count(count, n) && n > size) return too_many(count, "\"" + name + "\" elements", file_size);
        }
        if (file_size <= head.size()) return "header has no \"end_header\" line: the file ends inside its header";
        return "header has no \"end_header\" line in its first " + std::to_string(head.size()) + " bytes";
    }
    // OFF and its variants (COFF, NOFF, STOFF, 4OFF, ...): the first non-comment line after the keyword (or the
    // rest of the keyword's line) holds the vertex, face and edge counts.
    std::istringstream first(line);
    std::string keyword;
    first >> keyword;
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0) return "";
    std::vector<std::string> counts;
    for (std::string w; first >> w;) counts.push_back(w);
    while (counts.empty() && std::getline(lines, line)) {
        if (line.find('#') != std::string::npos) line.erase(line.find('#'));
        std::istringstream words(line);
        for (std::string w; words >> w;) counts.push_back(w);
    }
    static const char* names[] = {"vertices", "faces", "edges"};
    for (size_t i = 0; i < counts.size() && i < 3; ++i) {
        long double n = 0;
        if (parse_count(counts[i], n) && n > size) return too_many(counts[i], names[i], file_size);
    }
    return "";
}

}  // namespace rtm

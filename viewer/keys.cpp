#include "viewer/keys.h"

#include <GLFW/glfw3.h>

#include <cctype>
#include <sstream>
#include <stdexcept>

namespace rtm::viewer {

glm::dvec3 fly_axes(int key) {
    switch (key) {
        case GLFW_KEY_W: return {0, 0, 1};
        case GLFW_KEY_S: return {0, 0, -1};
        case GLFW_KEY_D: return {1, 0, 0};
        case GLFW_KEY_A: return {-1, 0, 0};
        case GLFW_KEY_E: return {0, 1, 0};
        case GLFW_KEY_Q: return {0, -1, 0};
        default: return {0, 0, 0};
    }
}

bool apply_key(int key, ViewSettings& s, KeyRequests& r) {
    if (s.fly) {
        const glm::dvec3 a = fly_axes(key);
        if (a != glm::dvec3(0.0)) {
            r.fly += a;
            return true;
        }
    }
    switch (key) {
        case GLFW_KEY_1: s.method = RenderMethod::flat; return true;
        case GLFW_KEY_2: s.method = RenderMethod::two_pass; return true;
        case GLFW_KEY_3: s.method = RenderMethod::pipelined; return true;
        case GLFW_KEY_4: s.method = RenderMethod::micromesh; return true;
        case GLFW_KEY_5: s.method = RenderMethod::raycast; return true;
        case GLFW_KEY_C: s.fly = !s.fly; return true;
        case GLFW_KEY_F: r.frame = true; return true;
        case GLFW_KEY_G: s.side_polygons = !s.side_polygons; return true;
        case GLFW_KEY_Z: s.depth_correction = !s.depth_correction; return true;
        case GLFW_KEY_K: s.skips = !s.skips; return true;
        case GLFW_KEY_L: s.level = s.level >= 3 ? -1 : s.level + 1; return true;
        case GLFW_KEY_B: s.coverage = !s.coverage; return true;
        case GLFW_KEY_H:
        case GLFW_KEY_F1: s.panel = !s.panel; return true;
        case GLFW_KEY_I: s.insets = !s.insets; return true;
        case GLFW_KEY_O: s.outlines = !s.outlines; return true;
        case GLFW_KEY_X:
            if (s.split == SplitMode::off) {
                s.split = SplitMode::method;
                s.split_method = RenderMethod::micromesh;
            } else if (s.split == SplitMode::method) {
                s.split = SplitMode::truth;
            } else {
                s.split = SplitMode::off;
            }
            return true;
        case GLFW_KEY_V: s.vsync = !s.vsync; return true;
        case GLFW_KEY_SPACE: r.toggle_play = true; return true;
        case GLFW_KEY_P:
        case GLFW_KEY_F12: r.screenshot = true; return true;
        case GLFW_KEY_Q:
        case GLFW_KEY_ESCAPE: r.quit = true; return true;
        default: return false;
    }
}

int key_code(const std::string& name) {
    if (name.size() == 1) {
        const char c = char(std::toupper(static_cast<unsigned char>(name[0])));
        if (c >= 'A' && c <= 'Z') return GLFW_KEY_A + (c - 'A');
        if (c >= '0' && c <= '9') return GLFW_KEY_0 + (c - '0');
        return -1;
    }
    std::string n;
    for (char c : name) n += char(std::tolower(static_cast<unsigned char>(c)));
    if (n == "space") return GLFW_KEY_SPACE;
    if (n == "esc" || n == "escape") return GLFW_KEY_ESCAPE;
    if (n == "tab") return GLFW_KEY_TAB;
    if (n.size() >= 2 && n[0] == 'f') {
        int k = 0;
        for (size_t i = 1; i < n.size(); ++i) {
            if (!std::isdigit(static_cast<unsigned char>(n[i]))) return -1;
            k = k * 10 + (n[i] - '0');
            if (k > 12) return -1;
        }
        if (k >= 1) return GLFW_KEY_F1 + (k - 1);
    }
    return -1;
}

std::vector<int> parse_key_script(const std::string& text) {
    std::vector<int> keys;
    std::stringstream ss(text);
    for (std::string item; std::getline(ss, item, ',');) {
        const int k = key_code(item);
        if (k < 0)
            throw std::invalid_argument("unknown key \"" + item + "\" (letters, digits, Space, Esc, Tab, F1..F12)");
        keys.push_back(k);
    }
    if (!text.empty() && text.back() == ',')
        throw std::invalid_argument("empty key name at the end of \"" + text + "\"");
    return keys;
}

}  // namespace rtm::viewer

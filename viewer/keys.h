// The viewer's keys, one table for the window and for scripted runs (--keys "2,G,I"): each key press changes the
// settings or asks the application for something (quit, frame, screenshot, play/pause, a fly step).
//   1..5 method: flat, two-pass, pipelined, micromesh, raycast (a still)      C  camera: orbit / fly
//   F    frame what is loaded          G  side polygons        Z  depth correction     K  skips
//   L    pyramid level: auto, 0, 1, 2, 3 in turn               B  coverage filter (two-pass)
//   H or F1 panel       I  insets      O  outlines             X  split view: off, micromesh, truth
//   V    vsync          Space  play / pause the camera path    P or F12  screenshot
//   W A S D  fly forward, left, back, right; E up, Q down (fly camera; Q quits with the orbit camera)   Esc quit
#pragma once

#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "viewer/view_settings.h"

namespace rtm::viewer {

struct KeyRequests {
    bool quit = false, frame = false, screenshot = false, toggle_play = false;
    glm::dvec3 fly{0.0};  // fly axes pressed: x right, y up, z forward (held keys move; a scripted press steps)
};

// Applies one key press (a GLFW key code). Returns false when the key does nothing.
bool apply_key(int key, ViewSettings& s, KeyRequests& r);
// The fly axes of a movement key (W, A, S, D, E, Q) in fly mode; zero otherwise.
glm::dvec3 fly_axes(int key);

// A key name: a letter or digit, or Space, Esc, Tab, F1..F12. Returns -1 when unknown.
int key_code(const std::string& name);
// "2,G,I" -> key codes; throws std::invalid_argument naming the unknown key.
std::vector<int> parse_key_script(const std::string& text);

}  // namespace rtm::viewer

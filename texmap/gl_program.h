// Compiling and linking a GLSL program: the one place every renderer (relief quads, meshes, the per-pixel methods)
// builds its shaders. Requires a current GlContext.
#pragma once

#include <string>

namespace rtm {

// Compiles the vertex and fragment shaders and links them into a program (the GL name). Throws GlError
// "cannot compile the NAME shader: LOG" or "cannot link the NAME program: LOG"; nothing is left allocated then.
unsigned link_program(const std::string& vertex_source, const std::string& fragment_source, const std::string& name);

}  // namespace rtm

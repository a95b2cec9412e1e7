# An OpenGL 3.3 core loader generated at configure time by Debian's python3-glad (glad 2), from the
# Khronos specification the package ships (--reproducible: nothing is downloaded). Works with both
# OSMesaGetProcAddress and glfwGetProcAddress through gladLoadGL(loader).
find_program(GLAD_EXECUTABLE glad PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT GLAD_EXECUTABLE)
  find_program(GLAD_EXECUTABLE glad)
endif()
if(NOT GLAD_EXECUTABLE)
  message(FATAL_ERROR "glad (Debian package python3-glad) not found; run scripts/setup.sh")
endif()
set(RTM_GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
if(NOT EXISTS ${RTM_GLAD_DIR}/src/gl.c)
  execute_process(
    COMMAND ${GLAD_EXECUTABLE} --api gl:core=3.3 --out-path ${RTM_GLAD_DIR} --reproducible --quiet c
    RESULT_VARIABLE glad_result OUTPUT_QUIET ERROR_VARIABLE glad_err)
  if(NOT glad_result EQUAL 0 OR NOT EXISTS ${RTM_GLAD_DIR}/src/gl.c)
    message(FATAL_ERROR "glad failed to generate the GL loader: ${glad_err}")
  endif()
endif()
add_library(rtm_glad STATIC ${RTM_GLAD_DIR}/src/gl.c)
target_include_directories(rtm_glad PUBLIC $<BUILD_INTERFACE:${RTM_GLAD_DIR}/include>)
set_target_properties(rtm_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)

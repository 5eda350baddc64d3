# GLM and nlohmann_json for the browser's build: both are header-only, and emscripten's toolchain
# looks for packages only inside its own sysroot, so their folders are found on the host and linked
# into the build folder (never the host's whole /usr/include, whose C headers are glibc's).
find_path(TRACER_GLM_INCLUDE glm/glm.hpp PATHS /usr/include NO_CMAKE_FIND_ROOT_PATH REQUIRED)
find_path(TRACER_JSON_INCLUDE nlohmann/json.hpp PATHS /usr/include NO_CMAKE_FIND_ROOT_PATH REQUIRED)
set(TRACER_HOST_HEADERS ${CMAKE_BINARY_DIR}/host_headers)
file(MAKE_DIRECTORY ${TRACER_HOST_HEADERS})
file(CREATE_LINK ${TRACER_GLM_INCLUDE}/glm ${TRACER_HOST_HEADERS}/glm SYMBOLIC)
file(CREATE_LINK ${TRACER_JSON_INCLUDE}/nlohmann ${TRACER_HOST_HEADERS}/nlohmann SYMBOLIC)
add_library(glm::glm INTERFACE IMPORTED)
target_include_directories(glm::glm SYSTEM INTERFACE ${TRACER_HOST_HEADERS})
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED)
target_include_directories(nlohmann_json::nlohmann_json SYSTEM INTERFACE ${TRACER_HOST_HEADERS})

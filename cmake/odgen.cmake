# odgen.cmake - generate a CANopen object dictionary at build time.
#
#   include(path/to/odgen/cmake/odgen.cmake)
#   odgen_add_object_dictionary(my_od NAME my_od EDS device.eds
#                               [OPTIONS device.toml] [NODE_ID 5] [LOOKUP switch|bsearch])
#   target_link_libraries(firmware PRIVATE my_od)
#
# The dictionary is regenerated when the description, the options file, the odgen
# templates or odgen itself change. The library carries the generated NAME.c and the
# odg runtime; its users get the include directories of both.

set(ODGEN_ROOT "${CMAKE_CURRENT_LIST_DIR}/.." CACHE PATH "odgen source tree (runtime/, templates/)")
find_program(ODGEN_EXECUTABLE odgen HINTS "${ODGEN_ROOT}/.venv/bin" DOC "the odgen command")
if(NOT ODGEN_EXECUTABLE)
  message(FATAL_ERROR "odgen not found: run `make setup` in ${ODGEN_ROOT} or put odgen on PATH")
endif()

file(GLOB_RECURSE _odgen_sources CONFIGURE_DEPENDS
     "${ODGEN_ROOT}/odgen/*.py" "${ODGEN_ROOT}/templates/*.j2")

if(NOT TARGET odg_runtime)
  add_library(odg_runtime STATIC "${ODGEN_ROOT}/runtime/odg.c" "${ODGEN_ROOT}/runtime/odg_persist.c")
  target_include_directories(odg_runtime PUBLIC "${ODGEN_ROOT}/runtime")
  set_target_properties(odg_runtime PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON)
endif()

function(odgen_add_object_dictionary target)
  cmake_parse_arguments(ARG "" "NAME;EDS;OPTIONS;NODE_ID;LOOKUP" "" ${ARGN})
  if(NOT ARG_NAME OR NOT ARG_EDS)
    message(FATAL_ERROR "odgen_add_object_dictionary(${target}): NAME and EDS are required")
  endif()
  get_filename_component(eds "${ARG_EDS}" ABSOLUTE)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/odgen/${ARG_NAME}")
  set(args generate "${eds}" -o "${out}" --name "${ARG_NAME}")
  set(deps "${eds}" ${_odgen_sources})
  if(ARG_OPTIONS)
    get_filename_component(options "${ARG_OPTIONS}" ABSOLUTE)
    list(APPEND args --options "${options}")
    list(APPEND deps "${options}")
  endif()
  if(ARG_NODE_ID)
    list(APPEND args --node-id "${ARG_NODE_ID}")
  endif()
  if(ARG_LOOKUP)
    list(APPEND args --lookup "${ARG_LOOKUP}")
  endif()
  add_custom_command(
    OUTPUT "${out}/${ARG_NAME}.c" "${out}/${ARG_NAME}.h"
    COMMAND "${ODGEN_EXECUTABLE}" ${args}
    DEPENDS ${deps}
    COMMENT "odgen: generating object dictionary ${ARG_NAME} from ${ARG_EDS}"
    VERBATIM)
  add_library(${target} STATIC "${out}/${ARG_NAME}.c" "${out}/${ARG_NAME}.h")
  target_include_directories(${target} PUBLIC "${out}")
  target_link_libraries(${target} PUBLIC odg_runtime)
  set_target_properties(${target} PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON)
endfunction()

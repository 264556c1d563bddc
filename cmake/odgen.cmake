# odgen.cmake - generate a CANopen object dictionary at build time with the installed odgen.
#
#   find_program(ODGEN_EXECUTABLE odgen)            # pip install odgen (any venv on PATH)
#   execute_process(COMMAND "${ODGEN_EXECUTABLE}" --cmake-dir
#                   OUTPUT_VARIABLE ODGEN_CMAKE_DIR OUTPUT_STRIP_TRAILING_WHITESPACE)
#   include("${ODGEN_CMAKE_DIR}/odgen.cmake")
#   odgen_add_object_dictionary(my_od NAME my_od EDS device.eds
#                               [OPTIONS device.toml] [NODE_ID 5] [LOOKUP switch|bsearch]
#                               [REPORT html|md]    # also odgen/NAME/NAME-report.html (or .md)
#                               [FIX safe|unsafe])  # generate --fix / --unsafe-fixes
#   target_link_libraries(firmware PRIVATE my_od)     # the dictionary and odgen::runtime
#   target_link_libraries(firmware PRIVATE odgen::node) # the CANopen node's services, if wanted
#   target_link_libraries(firmware PRIVATE odgen::master) # the CiA 302 master (docs/master.md)
#
# Each dictionary brings its runtime, built with its NAME_config.h (-DODG_CONFIG, the only
# define the runtime needs: the switches and the node's limits are in it): my_od_runtime (the
# core and persistence) and my_od_node (NMT, SDO, PDO, EMCY, SYNC, heartbeat, LSS, TIME). The
# first dictionary of a project also names them odgen::runtime and odgen::node. The source lists
# and warning flags come from `odgen --toolchain cmake`, the definition odgen's own builds use.
# The targets compile with odgen's warnings on; -Werror only with -DODGEN_WERROR=ON. A
# dictionary is regenerated when its description, its options file, its arguments or the
# installed odgen version change. odgen writes only files whose content changed, so touching
# the description without changing it recompiles nothing. See docs/cmake.md.

cmake_minimum_required(VERSION 3.16)

# The odgen that owns this file: the venv's bin/ beside site-packages/odgen/cmake, or a
# source checkout's .venv; else PATH.
find_program(ODGEN_EXECUTABLE odgen
             HINTS "${CMAKE_CURRENT_LIST_DIR}/../../../../bin" "${CMAKE_CURRENT_LIST_DIR}/../.venv/bin"
             DOC "the odgen command")
if(NOT ODGEN_EXECUTABLE)
  message(FATAL_ERROR "odgen not found: pip install odgen, or set ODGEN_EXECUTABLE")
endif()

# Re-read the toolchain (and so the version) whenever odgen is reinstalled: pip rewrites its command.
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${ODGEN_EXECUTABLE}")
execute_process(COMMAND "${ODGEN_EXECUTABLE}" --toolchain cmake
                OUTPUT_VARIABLE _odgen_toolchain RESULT_VARIABLE _odgen_status)
if(NOT _odgen_status EQUAL 0)
  message(FATAL_ERROR "${ODGEN_EXECUTABLE} --toolchain cmake failed (${_odgen_status})")
endif()
file(WRITE "${CMAKE_BINARY_DIR}/odgen-toolchain.cmake" "${_odgen_toolchain}")
include("${CMAKE_BINARY_DIR}/odgen-toolchain.cmake")
# ODGEN_VERSION, ODGEN_RUNTIME_DIR, ODGEN_RUNTIME_SOURCES, ODGEN_NODE_SOURCES, ODGEN_MASTER_SOURCES,
# ODGEN_C_WARNINGS

option(ODGEN_WERROR "compile odgen's targets with -Werror (the warnings are on either way)" OFF)

function(_odgen_strict target)
  set_target_properties(${target} PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
  if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
    set(warnings ${ODGEN_C_WARNINGS})
    if(NOT ODGEN_WERROR)
      list(REMOVE_ITEM warnings -Werror)
    endif()
    target_compile_options(${target} PRIVATE ${warnings})
  endif()
endfunction()

# The runtime and the node's services of one dictionary, built with its NAME_config.h.
function(_odgen_add_runtime target name out)
  add_library(${target}_runtime STATIC ${ODGEN_RUNTIME_SOURCES})
  target_include_directories(${target}_runtime PUBLIC "${ODGEN_RUNTIME_DIR}" "${out}")
  target_compile_definitions(${target}_runtime PUBLIC "ODG_CONFIG=\"${name}_config.h\"")
  add_dependencies(${target}_runtime ${target}_generate)
  _odgen_strict(${target}_runtime)
  add_library(${target}_node STATIC ${ODGEN_NODE_SOURCES})
  target_link_libraries(${target}_node PUBLIC ${target}_runtime)
  _odgen_strict(${target}_node)
  # the CiA 302 master (docs/master.md), above the node
  add_library(${target}_master STATIC EXCLUDE_FROM_ALL ${ODGEN_MASTER_SOURCES}) # built when linked
  target_link_libraries(${target}_master PUBLIC ${target}_node)
  _odgen_strict(${target}_master)
  if(NOT TARGET odgen::runtime)
    add_library(odgen::runtime ALIAS ${target}_runtime)
    add_library(odgen::node ALIAS ${target}_node)
    add_library(odgen::master ALIAS ${target}_master)
  endif()
endfunction()

# A file written only when its content changes (its mtime is what make and ninja compare).
function(_odgen_write_if_changed path content)
  if(EXISTS "${path}")
    file(READ "${path}" old)
    if(old STREQUAL content)
      return()
    endif()
  endif()
  file(WRITE "${path}" "${content}")
endfunction()

# `odgen report` of the description, run by the same rule as the dictionary (so under its stamp).
function(_odgen_report_command format out eds name options node_id)
  if(NOT format MATCHES "^(html|md)$")
    message(FATAL_ERROR "odgen_add_object_dictionary: REPORT is html or md, not '${format}'")
  endif()
  set(report "${out}/${name}-report.${format}")
  set(command "${ODGEN_EXECUTABLE}" report "${eds}" -o "${report}" --format "${format}")
  if(options)
    list(APPEND command --options "${options}")
  endif()
  if(node_id)
    list(APPEND command --node-id "${node_id}")
  endif()
  set(_odgen_report_file "${report}" PARENT_SCOPE)
  set(_odgen_report_command COMMAND ${command} PARENT_SCOPE)
endfunction()

function(odgen_add_object_dictionary target)
  cmake_parse_arguments(ARG "" "NAME;EDS;OPTIONS;NODE_ID;LOOKUP;REPORT;FIX" "" ${ARGN})
  if(NOT ARG_NAME OR NOT ARG_EDS)
    message(FATAL_ERROR "odgen_add_object_dictionary(${target}): NAME and EDS are required")
  endif()
  get_filename_component(eds "${ARG_EDS}" ABSOLUTE)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/odgen/${ARG_NAME}")
  set(args generate "${eds}" -o "${out}" --name "${ARG_NAME}")
  set(deps "${eds}")
  set(options "")
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
  # FIX safe|unsafe: generate --fix / --unsafe-fixes (repairs listed in the generated header)
  if(ARG_FIX STREQUAL "safe")
    list(APPEND args --fix)
  elseif(ARG_FIX STREQUAL "unsafe")
    list(APPEND args --unsafe-fixes)
  elseif(ARG_FIX)
    message(FATAL_ERROR "odgen_add_object_dictionary(${target}): FIX is safe or unsafe, not '${ARG_FIX}'")
  endif()
  # The key of everything else the output depends on: odgen's version and the arguments.
  set(key "${out}.key")
  _odgen_write_if_changed("${key}" "odgen ${ODGEN_VERSION}\n${args}\nreport ${ARG_REPORT}\n")
  # The stamp is the rule's output; the sources are byproducts, left untouched when unchanged
  # (ninja restats them; make compares their kept mtimes with the objects').
  set(stamp "${out}.stamp")
  set(_odgen_report_file "")
  set(_odgen_report_command "")
  if(ARG_REPORT)
    _odgen_report_command("${ARG_REPORT}" "${out}" "${eds}" "${ARG_NAME}" "${options}" "${ARG_NODE_ID}")
  endif()
  add_custom_command(
    OUTPUT "${stamp}"
    BYPRODUCTS "${out}/${ARG_NAME}.c" "${out}/${ARG_NAME}.h" "${out}/${ARG_NAME}_config.h" ${_odgen_report_file}
    COMMAND "${ODGEN_EXECUTABLE}" ${args}
    ${_odgen_report_command}
    COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
    DEPENDS ${deps} "${key}"
    COMMENT "odgen: object dictionary ${ARG_NAME} from ${ARG_EDS}"
    VERBATIM)
  add_custom_target(${target}_generate DEPENDS "${stamp}")
  _odgen_add_runtime(${target} ${ARG_NAME} "${out}")
  add_library(${target} STATIC "${out}/${ARG_NAME}.c" "${out}/${ARG_NAME}.h")
  add_dependencies(${target} ${target}_generate)
  target_link_libraries(${target} PUBLIC ${target}_runtime)
  _odgen_strict(${target})
endfunction()

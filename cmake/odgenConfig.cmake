# find_package(odgen): pip installs this file as <prefix>/share/odgen/cmake/odgenConfig.cmake, a
# folder CMake searches for every <prefix>/bin on PATH (a venv, ~/.local, /usr/local). It uses
# the odgen of that prefix and includes the CMake module packaged with it (odgen.cmake):
#
#   find_package(odgen 0.1 REQUIRED)
#   odgen_add_object_dictionary(my_od NAME my_od EDS device.eds)
#   target_link_libraries(firmware PRIVATE my_od)

find_program(ODGEN_EXECUTABLE odgen NAMES odgen
             HINTS "${CMAKE_CURRENT_LIST_DIR}/../../../bin" "${CMAKE_CURRENT_LIST_DIR}/../../../Scripts"
             DOC "the odgen command")
if(NOT ODGEN_EXECUTABLE)
  set(odgen_FOUND FALSE)
  set(odgen_NOT_FOUND_MESSAGE "odgen is not in ${CMAKE_CURRENT_LIST_DIR}/../../../bin nor on PATH")
  return()
endif()
execute_process(COMMAND "${ODGEN_EXECUTABLE}" --cmake-dir OUTPUT_VARIABLE _odgen_cmake_dir
                OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _odgen_status)
if(NOT _odgen_status EQUAL 0 OR NOT EXISTS "${_odgen_cmake_dir}/odgen.cmake")
  set(odgen_FOUND FALSE)
  set(odgen_NOT_FOUND_MESSAGE "${ODGEN_EXECUTABLE} --cmake-dir failed (${_odgen_status})")
  return()
endif()
include("${_odgen_cmake_dir}/odgen.cmake")

# The version of the odgen beside this file (`odgen --version`), for find_package(odgen X.Y):
# any odgen of the same major version and at least X.Y is compatible (0.x: the same minor too).

set(PACKAGE_VERSION "")
foreach(_odgen_exe "${CMAKE_CURRENT_LIST_DIR}/../../../bin/odgen"
                   "${CMAKE_CURRENT_LIST_DIR}/../../../Scripts/odgen.exe")
  if(NOT PACKAGE_VERSION AND EXISTS "${_odgen_exe}")
    execute_process(COMMAND "${_odgen_exe}" --version OUTPUT_VARIABLE _odgen_version
                    OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _odgen_status)
    if(_odgen_status EQUAL 0)
      string(REGEX MATCH "[0-9]+(\\.[0-9]+)*" PACKAGE_VERSION "${_odgen_version}")
    endif()
  endif()
endforeach()

set(PACKAGE_VERSION_COMPATIBLE FALSE)
if(NOT PACKAGE_VERSION)
  set(PACKAGE_VERSION_UNSUITABLE TRUE)  # no working odgen beside this file
elseif(NOT PACKAGE_FIND_VERSION)
  set(PACKAGE_VERSION_COMPATIBLE TRUE)
else()
  string(REGEX MATCH "^[0-9]+" _have_major "${PACKAGE_VERSION}")
  string(REGEX MATCH "^[0-9]+\\.[0-9]+" _have_minor "${PACKAGE_VERSION}")
  set(_want_minor "${PACKAGE_FIND_VERSION_MAJOR}.${PACKAGE_FIND_VERSION_MINOR}")
  if(PACKAGE_VERSION VERSION_GREATER_EQUAL PACKAGE_FIND_VERSION
     AND _have_major EQUAL PACKAGE_FIND_VERSION_MAJOR
     AND (NOT _have_major EQUAL 0 OR _have_minor VERSION_EQUAL _want_minor))
    set(PACKAGE_VERSION_COMPATIBLE TRUE)
  endif()
  if(PACKAGE_VERSION VERSION_EQUAL PACKAGE_FIND_VERSION)
    set(PACKAGE_VERSION_EXACT TRUE)
  endif()
endif()

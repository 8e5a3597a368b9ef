# cmake -DSOURCE=<repository> -DWORK=<scratch folder> -P layering_test.cmake
# The layering check passes on the tree as it is, and fails, naming the file and line, on a
# copy of core/ where volume includes pipeline or where a module is not in layers.cmake.
cmake_minimum_required(VERSION 3.25)
set(_check ${SOURCE}/cmake/CheckLayering.cmake)
set(_layers ${SOURCE}/core/layers.cmake)
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${SOURCE}/core -DLAYERS=${_layers} -P ${_check}
                RESULT_VARIABLE _rc ERROR_VARIABLE _err)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "the tree's own layering fails the check:\n${_err}")
endif()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/core/volume ${WORK}/core/pipeline ${WORK}/core/common)
file(WRITE ${WORK}/core/common/a.h "#pragma once\n")
file(WRITE ${WORK}/core/pipeline/p.h "#pragma once\n#include \"volume/v.h\"\n")
file(WRITE ${WORK}/core/volume/v.h "#pragma once\n#include \"common/a.h\"\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${WORK}/core -DLAYERS=${_layers} -P ${_check} RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "a fixture that keeps the layering fails the check")
endif()
file(WRITE ${WORK}/core/volume/v.h "#pragma once\n#include \"common/a.h\"\n\n  #include \"pipeline/p.h\"\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${WORK}/core -DLAYERS=${_layers} -P ${_check}
                RESULT_VARIABLE _rc ERROR_VARIABLE _err)
if(_rc EQUAL 0)
  message(FATAL_ERROR "volume including pipeline passed the layering check")
endif()
if(NOT _err MATCHES "core/volume/v.h:4: volume includes pipeline/")
  message(FATAL_ERROR "the failure does not name the file and line:\n${_err}")
endif()
file(WRITE ${WORK}/core/volume/v.h "#pragma once\n")
file(MAKE_DIRECTORY ${WORK}/core/newmodule)
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${WORK}/core -DLAYERS=${_layers} -P ${_check}
                RESULT_VARIABLE _rc ERROR_VARIABLE _err)
if(_rc EQUAL 0 OR NOT _err MATCHES "newmodule/: a module that")
  message(FATAL_ERROR "a module missing from layers.cmake passed the check:\n${_err}")
endif()
file(REMOVE_RECURSE ${WORK})
message(STATUS "layering check: the tree passes; a wrong-way include and an unlisted module fail")

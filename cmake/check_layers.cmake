# The layer rules of the project (README "Layout") as a check on every #include line of the layers' sources:
#   base        may include base
#   lab         base, lab                   (parameters reach the engine through files)
#   model/flow  base, model/flow            (the flow solver knows nothing of particles)
#   model       base, model, model/flow     (model/coupling/ and every other subfolder count as model)
#   validation  base, model, model/flow, validation
#   analysis    base, lab, analysis         (it reads the engine's output files, never its code)
# app/, tests/, fuzz/ and bench/ may include any layer. An include is a layer's when its path starts with the
# layer's folder; other includes (fmt/, Eigen/, toml++/, system headers) are not checked.
# Run at configure time (CMakeLists.txt: an offending line stops the configuration) and by the CTests
# "layers: ..." (tests/layers/): cmake -DROOT=<tree> -P cmake/check_layers.cmake. Every offending line is
# printed as <file>:<line>: ..., then the check fails.

if(CMAKE_SCRIPT_MODE_FILE)
  cmake_minimum_required(VERSION 3.22)  # the project's policies (IN_LIST) in script mode too
endif()

# 1-based line of the first occurrence of `needle` in the file `path` (file(STRINGS) drops empty lines, so the
# line is counted on the file's text).
function(pastemix_line_of path needle out)
  file(READ ${path} text)
  string(FIND "${text}" "${needle}" at)
  string(SUBSTRING "${text}" 0 ${at} before)
  string(REGEX MATCHALL "\n" newlines "${before}")
  list(LENGTH newlines n)
  math(EXPR n "${n} + 1")
  set(${out} ${n} PARENT_SCOPE)
endfunction()

function(pastemix_check_layers root)
  set(allowed_base base)
  set(allowed_lab base lab)
  set(allowed_model_flow base model/flow)
  set(allowed_model base model model/flow)
  set(allowed_validation base model model/flow validation)
  set(allowed_analysis base lab analysis)
  set(errors "")
  foreach(layer base lab model/flow model validation analysis)
    string(REPLACE "/" "_" key ${layer})
    file(GLOB_RECURSE files RELATIVE ${root} ${root}/${layer}/*.h ${root}/${layer}/*.cpp)
    foreach(f IN LISTS files)
      if(layer STREQUAL "model" AND f MATCHES "^model/flow/")
        continue()  # checked as model/flow
      endif()
      file(STRINGS ${root}/${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
      foreach(line IN LISTS lines)
        if(NOT line MATCHES "[<\"]([^>\"]+)[>\"]")
          continue()
        endif()
        set(inc ${CMAKE_MATCH_1})
        if(inc MATCHES "^model/flow/")
          set(inc_layer model/flow)
        elseif(inc MATCHES "^(base|lab|model|validation|analysis|app)/")
          set(inc_layer ${CMAKE_MATCH_1})
        else()
          continue()
        endif()
        if(NOT inc_layer IN_LIST allowed_${key})
          pastemix_line_of(${root}/${f} "${line}" n)
          string(REPLACE ";" ", " may "${allowed_${key}}")
          string(APPEND errors "${f}:${n}: #include \"${inc}\": ${layer}/ may include only ${may}\n")
        endif()
      endforeach()
    endforeach()
  endforeach()
  if(errors)
    message(NOTICE "${errors}")  # unwrapped, one offending line each
    message(FATAL_ERROR "layer rules broken (cmake/check_layers.cmake): the includes above")
  endif()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE)
  if(NOT ROOT)
    message(FATAL_ERROR "usage: cmake -DROOT=<source tree> -P cmake/check_layers.cmake")
  endif()
  pastemix_check_layers(${ROOT})
  message(STATUS "layer rules kept in ${ROOT}")
endif()

# Fails when a file of one layer of src/ includes a private header of a layer
# above it (docs/architecture.md, "Layers"): the library's folders are layers,
# lowest first, and a folder may include headers of its own layer and the
# layers below. The public headers (include/sharpmesh) are the library's
# interface and are not checked here. It also fails on a raw
# tbb::parallel_for outside core/parallel.h: every parallel loop goes through
# the library's own, which the thread limit and progress rely on.
#
#   cmake -DSOURCE_DIR=src -DLAYERS=core,io,... [-DSTAMP=file] -P check_layers.cmake
if(NOT SOURCE_DIR OR NOT LAYERS)
  message(FATAL_ERROR "check_layers: give -DSOURCE_DIR and -DLAYERS")
endif()
string(REPLACE "," ";" LAYERS "${LAYERS}")
file(GLOB_RECURSE files RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/*.h" "${SOURCE_DIR}/*.cpp")
set(problems "")
foreach(file IN LISTS files)
  if(NOT file MATCHES "/")
    continue()
  endif()
  string(REGEX MATCH "^[^/]+" layer "${file}")
  list(FIND LAYERS "${layer}" own)
  if(own EQUAL -1)
    string(APPEND problems "\n  ${file}: folder '${layer}' is in no layer (add it to SHARPMESH_LAYERS in src/CMakeLists.txt)")
    continue()
  endif()
  if(NOT file STREQUAL "core/parallel.h")
    file(STRINGS "${SOURCE_DIR}/${file}" raw_loops REGEX "tbb::parallel_for[ \t]*\\(")
    if(raw_loops)
      string(APPEND problems "\n  ${file}: calls tbb::parallel_for (use detail::parallel_for or parallel_chunks, core/parallel.h)")
    endif()
  endif()
  file(STRINGS "${SOURCE_DIR}/${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"[a-z_0-9]+/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([a-z_0-9]+)/.*" "\\1" included "${line}")
    list(FIND LAYERS "${included}" index)
    if(index GREATER own)
      string(APPEND problems "\n  ${file}: includes ${included}/, a layer above ${layer}/ (move the shared code down, e.g. to core/)")
    endif()
  endforeach()
endforeach()
if(problems)
  message(FATAL_ERROR "layer check failed:${problems}")
endif()
if(STAMP)
  file(TOUCH "${STAMP}")
endif()

# host/ is built as one static library per folder ("layer"), and a layer sees
# only its own headers and those of the layers it links (docs/design.md,
# "Layers"). Each layer exposes its folder through an include root of its own,
# ${CMAKE_BINARY_DIR}/layers/NAME/, that holds one link, NAME -> host/NAME. A
# layer's compile line carries its root and, through target_link_libraries,
# the roots of the layers below it, never those above: an include that runs up
# the layers ("report/junit.hpp" from checks/) is "No such file or directory",
# and tests/layering/ shows that it is.
#
# mfv_layer(NAME [DEPENDS LOWER...] [SOURCES EXTRA...])
#   builds host/NAME/*.cpp (no .cpp: a header-only INTERFACE library) as
#   mfv_NAME, linked PUBLIC to mfv_LOWER for each LOWER layer it includes.
#   Every layer also links mfv_settings (third-party libraries, definitions).
function(mfv_layer name)
  cmake_parse_arguments(LAYER "" "" "DEPENDS;SOURCES" ${ARGN})
  set(root ${CMAKE_BINARY_DIR}/layers/${name})
  file(MAKE_DIRECTORY ${root})
  file(CREATE_LINK ${CMAKE_SOURCE_DIR}/host/${name} ${root}/${name} SYMBOLIC)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/host/${name}/*.cpp)
  list(FILTER sources EXCLUDE REGEX ".*/host/cli/main\\.cpp$")
  list(APPEND sources ${LAYER_SOURCES})
  list(TRANSFORM LAYER_DEPENDS PREPEND mfv_)
  if(sources)
    add_library(mfv_${name} STATIC ${sources})
    target_include_directories(mfv_${name} PUBLIC ${root})
    target_link_libraries(mfv_${name} PUBLIC mfv_settings ${LAYER_DEPENDS})
    target_compile_options(mfv_${name} PRIVATE -Wall -Wextra)
  else()
    add_library(mfv_${name} INTERFACE)
    target_include_directories(mfv_${name} INTERFACE ${root})
    target_link_libraries(mfv_${name} INTERFACE mfv_settings ${LAYER_DEPENDS})
  endif()
  set_property(GLOBAL APPEND PROPERTY MFV_LAYERS mfv_${name})
endfunction()

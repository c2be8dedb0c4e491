# The layers refuse an upward include (cmake/Layers.cmake, docs/design.md
# "Layers"): each probe below is compiled (-fsyntax-only) with exactly the
# include folders, definitions and options of one layer's library, as the
# build compiles that layer's sources.
#   * the three includes that once ran up the layers (catalog -> runtime,
#     reference -> catalog, checks -> report) must fail, with "No such file";
#   * a downward include from each of those layers must compile, so that the
#     failures above are the layering's and not a broken probe's.
# Run by CTest as layering_refuses_upward_includes with
#   -DCXX=compiler -DFLAGS_<layer>=<its flags, '|'-separated> -DWORK=scratch folder
cmake_minimum_required(VERSION 3.20)

function(probe layer header expect)
  string(REPLACE "|" ";" flags "${FLAGS_${layer}}")
  string(MAKE_C_IDENTIFIER "${layer}_${header}" stem)
  set(src ${WORK}/${stem}.cpp)
  file(WRITE ${src} "#include \"${header}\"\n")
  execute_process(COMMAND ${CXX} -std=c++17 -fsyntax-only ${flags} ${src}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(expect STREQUAL "refused")
    if(rc EQUAL 0)
      message(SEND_ERROR "host/${layer}/ may include \"${header}\", a layer above it: the layering does not hold")
    elseif(NOT out MATCHES "No such file")
      message(SEND_ERROR "host/${layer}/ including \"${header}\" failed for another reason than the layering:\n${out}")
    else()
      message(STATUS "refused as it should be: host/${layer}/ -> ${header}")
    endif()
  elseif(NOT rc EQUAL 0)
    message(SEND_ERROR "host/${layer}/ cannot include \"${header}\", a layer below it:\n${out}")
  else()
    message(STATUS "allowed as it should be: host/${layer}/ -> ${header}")
  endif()
endfunction()

file(MAKE_DIRECTORY ${WORK})
probe(catalog "runtime/opencl.hpp" refused)
probe(catalog "util/error.hpp" allowed)
probe(reference "catalog/catalog.hpp" refused)
probe(reference "reference/twins.hpp" allowed)
probe(checks "report/junit.hpp" refused)
probe(checks "util/files.hpp" allowed)
probe(checks "runtime/opencl.hpp" allowed)
probe(report "scene/scene.hpp" refused)
probe(scene "user/user_brdf.hpp" refused)
probe(cli "scene/scene.hpp" allowed)

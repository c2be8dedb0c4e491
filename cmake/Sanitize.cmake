# Host code under AddressSanitizer and UndefinedBehaviorSanitizer (issue 17).
#
# The default build registers one CTest test, `sanitized_host_tests`, that
# configures a second build tree (build-asan inside the build folder) with
# -DMFV_SANITIZE=ON, builds only `mfv_host_tests` there and runs it: the
# host-only tests (tests/host/: strict number parsing, temporary files, the
# scene/material fuzz target) and the reference-term tests, over the host
# code they need (scene loading, catalog, reference, numeric, util, report
# files). No OpenCL runs under the sanitizers: PoCL's JIT and threads would
# multiply the time, and the device code is not what they check.
option(MFV_SANITIZE "build mfv_host_tests with -fsanitize=address,undefined" OFF)
option(MFV_FUZZ_LONG "register fuzz_long: the fuzz targets for 10 minutes each (label fuzz-long)" OFF)

file(GLOB MFV_HOST_TEST_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/host/*.cpp)

if(MFV_SANITIZE)
  # Scene loading is every host/scene/*.cpp but the runs and reports, which need OpenCL.
  file(GLOB MFV_HOST_ONLY_SOURCES CONFIGURE_DEPENDS
       ${CMAKE_SOURCE_DIR}/host/catalog/*.cpp ${CMAKE_SOURCE_DIR}/host/reference/*.cpp
       ${CMAKE_SOURCE_DIR}/host/numeric/*.cpp ${CMAKE_SOURCE_DIR}/host/util/*.cpp ${CMAKE_SOURCE_DIR}/host/scene/*.cpp)
  list(FILTER MFV_HOST_ONLY_SOURCES EXCLUDE REGEX ".*/host/scene/scene_(checks|report|filters)\\.cpp$")
  set(MFV_SANITIZE_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_library(mfv_host STATIC ${MFV_HOST_ONLY_SOURCES})
  # The layers' shared include folders, definitions and libraries, without
  # OpenCL; one include root (host/) for the sources of several layers: the
  # default build's layer libraries already refuse an upward include.
  get_target_property(core_includes mfv_settings INTERFACE_INCLUDE_DIRECTORIES)
  get_target_property(core_defines mfv_settings INTERFACE_COMPILE_DEFINITIONS)
  get_target_property(core_libs mfv_settings INTERFACE_LINK_LIBRARIES)
  list(REMOVE_ITEM core_libs OpenCL::OpenCL)
  target_include_directories(mfv_host PUBLIC ${CMAKE_SOURCE_DIR}/host ${core_includes})
  target_compile_definitions(mfv_host PUBLIC ${core_defines})
  target_compile_options(mfv_host PUBLIC ${MFV_SANITIZE_FLAGS})
  target_link_options(mfv_host PUBLIC ${MFV_SANITIZE_FLAGS})
  target_link_libraries(mfv_host PUBLIC ${core_libs})
  add_executable(mfv_host_tests ${CMAKE_SOURCE_DIR}/tests/main.cpp ${MFV_HOST_TEST_SOURCES}
                 ${CMAKE_SOURCE_DIR}/tests/test_reference_terms.cpp ${CMAKE_SOURCE_DIR}/tests/test_reference_terms_g.cpp)
  target_link_libraries(mfv_host_tests PRIVATE mfv_host Catch2::Catch2)
  target_compile_definitions(mfv_host_tests PRIVATE MFV_TEST_DATA_DIR="${CMAKE_SOURCE_DIR}/tests/data"
                             MFV_FUZZ_DIR="${CMAKE_SOURCE_DIR}/tests/fuzz")
endif()

function(mfv_add_sanitizer_test)
  if(MFV_SANITIZE)
    return()  # the sanitized tree itself runs mfv_host_tests directly
  endif()
  add_test(NAME sanitized_host_tests
           COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${CMAKE_SOURCE_DIR} -DBINARY_DIR=${CMAKE_BINARY_DIR}/build-asan
                   -DLAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER} -P ${CMAKE_SOURCE_DIR}/cmake/RunSanitized.cmake)
  set_tests_properties(sanitized_host_tests PROPERTIES LABELS "sanitizer" TIMEOUT 1200)
  if(MFV_FUZZ_LONG)
    add_test(NAME fuzz_long COMMAND mfv_tests "[fuzz]")
    set_tests_properties(fuzz_long PROPERTIES LABELS "fuzz-long" ENVIRONMENT "MFV_FUZZ_SECONDS=600" TIMEOUT 3600)
  endif()
endfunction()

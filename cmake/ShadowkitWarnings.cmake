# sk_project_warnings(target): the warning set of docs/architecture.md, for project code only
# (third-party headers come in as SYSTEM includes through their imported targets).
function(sk_project_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    # -Wno-missing-field-initializers: options structs have default member initializers,
    # and leaving fields out of a designated initializer is how callers ask for them.
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wconversion -Wno-sign-conversion
                                             -Wno-missing-field-initializers)
    # A unity build includes each source file into a batch file, so GCC takes a type in a file's
    # anonymous namespace for one in a header that other files would see (-Wsubobject-linkage,
    # 13 false warnings: test fixtures, RayScene::Impl's filter data). Built file by file there is
    # nothing to warn about, and that build keeps the warning.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_UNITY_BUILD)
      target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
    endif()
  elseif(MSVC)
    target_compile_options(${target} PRIVATE /W4)
  endif()
endfunction()

# sk_add_library(name SOURCES ...): one library per module with the shadowkit::<name> alias,
# public headers in include/, installed and exported.
function(sk_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  add_library(shadowkit_${name} ${ARG_SOURCES})
  add_library(shadowkit::${name} ALIAS shadowkit_${name})
  set_target_properties(shadowkit_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME shadowkit_${name}
                                                   POSITION_INDEPENDENT_CODE ON WINDOWS_EXPORT_ALL_SYMBOLS ON)
  target_include_directories(shadowkit_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(shadowkit_${name} PUBLIC cxx_std_20)
  sk_project_warnings(shadowkit_${name})
  set_target_properties(shadowkit_${name} PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
  # One export set per component, so find_package(shadowkit COMPONENTS core) loads the core's
  # targets and dependencies alone (cmake/shadowkitConfig.cmake.in).
  if(SHADOWKIT_INSTALL)
    install(TARGETS shadowkit_${name} EXPORT shadowkit_${name}Targets
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
            LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
            RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    install(EXPORT shadowkit_${name}Targets NAMESPACE shadowkit:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/shadowkit)
    install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
  set_property(GLOBAL APPEND PROPERTY SHADOWKIT_COMPONENTS ${name})
endfunction()

# sk_precompile(target HEADERS...): the third-party headers most of a target's files include,
# parsed once per target instead of once per file. CLI11, nlohmann::json and gtest each take
# 3-5 s of the compiler's front end per file that includes them (GCC 12 here), more than many
# of those files' own code; project headers stay out, so a missing include still fails.
function(sk_precompile target)
  if(SHADOWKIT_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

# sk_add_test(name SOURCES ... LIBS ... [LABELS ...]): a GoogleTest executable beside its module.
function(sk_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest_main)
  # The libraries take data paths; tests read the source tree's data/.
  target_compile_definitions(${name} PRIVATE SHADOWKIT_SOURCE_DATA_DIR="${PROJECT_SOURCE_DIR}/data")
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support) # scratch_dir.h
  sk_project_warnings(${name})
  sk_precompile(${name} <gtest/gtest.h> <glm/glm.hpp>)
  gtest_discover_tests(${name} PROPERTIES LABELS "${ARG_LABELS}" DISCOVERY_TIMEOUT 60)
endfunction()

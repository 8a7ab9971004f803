# Installs the build into a scratch prefix and builds tests/package_consumer against it, as an
# engine would: find_package(shadowkit COMPONENTS core) with every dependency but glm hidden
# (CMAKE_DISABLE_FIND_PACKAGE_<name>: find_package then fails for them), so the core's
# promise to need glm alone is tested, not assumed; an optional component whose dependencies
# are hidden is reported missing without failing; and the pkg-config file builds the same
# consumer without CMake.
file(REMOVE_RECURSE "${WORK}/prefix") # a fresh install, not one over an older
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK}/prefix" RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed")
endif()
# The shader half an engine appends: the lookup, and the leaves' and local lights' lookups after it.
foreach(f shadowkit_shadows.glsl shadowkit_foliage_opacity.glsl shadowkit_local_shadows.glsl)
  if(NOT EXISTS "${WORK}/prefix/share/shadowkit/glsl/${f}")
    message(FATAL_ERROR "install left out share/shadowkit/glsl/${f}")
  endif()
endforeach()
set(hidden)
foreach(p nlohmann_json TinyGLTF meshoptimizer tinyobjloader PkgConfig glfw3 embree TBB GTest benchmark)
  list(APPEND hidden "-DCMAKE_DISABLE_FIND_PACKAGE_${p}=ON")
endforeach()

foreach(ask OFF ON)
  file(REMOVE_RECURSE "${WORK}/consumer")
  execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/package_consumer" -B "${WORK}/consumer"
                          "-DCMAKE_PREFIX_PATH=${WORK}/prefix" ${hidden} -DSHADOWKIT_ASK_EVAL=${ask}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer (eval asked: ${ask}) configure failed with only glm visible: ${out} ${err}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK}/consumer" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer build failed: ${out} ${err}")
  endif()
  execute_process(COMMAND "${WORK}/consumer/consumer" RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "^shadowkit [0-9]+\\.[0-9]+\\.[0-9]+: ")
    message(FATAL_ERROR "consumer run failed: ${out}")
  endif()
endforeach()

# The OSG adapter, where it was built: an OSG program finds it, and OSG with it.
if(EXISTS "${WORK}/prefix/lib/cmake/shadowkit/shadowkit_osgTargets.cmake")
  file(REMOVE_RECURSE "${WORK}/osg_consumer")
  execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/package_consumer_osg" -B "${WORK}/osg_consumer"
                          "-DCMAKE_PREFIX_PATH=${WORK}/prefix" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK}/osg_consumer" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  endif()
  if(rc EQUAL 0)
    execute_process(COMMAND "${WORK}/osg_consumer/osg_consumer" RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  endif()
  if(NOT rc EQUAL 0 OR NOT out MATCHES "^shadowkit osg: tsm")
    message(FATAL_ERROR "the OSG consumer of the installed component osg failed: ${out} ${err}")
  endif()
endif()

# A relocated install reads the data beside its bin/: move the tree, give the moved copy's
# views.json a view no other data directory has, and ask the moved command line for it.
if(EXISTS "${WORK}/prefix/bin/shadowkit")
  file(REMOVE_RECURSE "${WORK}/moved")
  file(RENAME "${WORK}/prefix" "${WORK}/moved")
  set(views "${WORK}/moved/share/shadowkit/views.json")
  file(READ "${views}" text)
  string(JSON text SET "${text}" views 0 name "\"relocated\"")
  file(WRITE "${views}" "${text}")
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=SHADOWKIT_DATA_DIR "${WORK}/moved/bin/shadowkit" setup --view relocated --trees 10
                          --terrain-size 64 --terrain-resolution 8
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  file(RENAME "${WORK}/moved" "${WORK}/prefix")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "a moved install does not find its data: ${err}")
  endif()
endif()

# pkg-config: the same program from the .pc file alone.
find_program(PKG_CONFIG pkg-config)
find_program(CXX NAMES c++ g++)
if(PKG_CONFIG AND CXX)
  set(ENV{PKG_CONFIG_PATH} "${WORK}/prefix/lib/pkgconfig:${WORK}/prefix/lib/x86_64-linux-gnu/pkgconfig")
  execute_process(COMMAND ${PKG_CONFIG} --cflags --libs shadowkit-core OUTPUT_VARIABLE flags RESULT_VARIABLE rc
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config does not know shadowkit-core")
  endif()
  separate_arguments(flags UNIX_COMMAND "${flags}")
  execute_process(COMMAND ${CXX} "${SOURCE_DIR}/tests/package_consumer/main.cpp" ${flags} -o "${WORK}/pc_consumer"
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building with pkg-config's flags failed: ${err}")
  endif()
  execute_process(COMMAND "${WORK}/pc_consumer" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the pkg-config build does not run")
  endif()
endif()

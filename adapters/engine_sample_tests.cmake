# add_engine_sample_test(NAME SAMPLE OWN ADAPTER EVAL): an engine adapter end to end under Xvfb
# (engine_sample_test.cmake): the sample target SAMPLE draws the adapter's ADAPTER and the
# engine's own OWN, each mask scored against the truth beside `eval` with EVAL (its options for
# the same set-up). Included by each adapter's CMakeLists.txt.
function(add_engine_sample_test name sample own adapter eval)
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DSHADOWKIT=$<TARGET_FILE:shadowkit> -DSAMPLE=$<TARGET_FILE:${sample}>
                   -DOWN=${own} -DADAPTER=${adapter} "-DEVAL_OPTIONS=${eval}"
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/${name} -P ${PROJECT_SOURCE_DIR}/adapters/engine_sample_test.cmake)
  set_tests_properties(${name} PROPERTIES LABELS gl SKIP_REGULAR_EXPRESSION "SKIP:")
endfunction()

# add_engine_sample_input_test(NAME SAMPLE): the sample refuses a camera or shots file that is a
# pipe or a directory in one line (engine_sample_input_test.cmake); no display needed.
function(add_engine_sample_input_test name sample)
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DSAMPLE=$<TARGET_FILE:${sample}> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/${name}
                   -P ${PROJECT_SOURCE_DIR}/adapters/engine_sample_input_test.cmake)
endfunction()

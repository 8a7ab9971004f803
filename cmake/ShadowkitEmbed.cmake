# sk_embed_files(target NAMESPACE ns FILES a.vert b.frag ...)
# Embeds text files (GLSL) into a generated header <target>_embedded.h as
# `inline constexpr std::string_view k<Name>` constants, so shaders sit next to the C++
# that drives them yet the binary needs no files at run time. Regenerated when a file changes.
function(sk_embed_files target)
  cmake_parse_arguments(ARG "" "NAMESPACE;HEADER" "FILES" ${ARGN})
  set(out "${CMAKE_CURRENT_BINARY_DIR}/embedded/${ARG_HEADER}")
  set(inputs "")
  foreach(f ${ARG_FILES})
    list(APPEND inputs "${CMAKE_CURRENT_SOURCE_DIR}/${f}")
  endforeach()
  # A CMake list's ';' would split the command line: pass the files joined by '|'.
  string(REPLACE ";" "|" joined "${inputs}")
  add_custom_command(OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DNAMESPACE=${ARG_NAMESPACE} "-DINPUTS=${joined}"
            -P ${CMAKE_SOURCE_DIR}/cmake/embed_files.cmake
    DEPENDS ${inputs} ${CMAKE_SOURCE_DIR}/cmake/embed_files.cmake
    COMMENT "Embedding shaders into ${ARG_HEADER}" VERBATIM)
  target_sources(${target} PRIVATE "${out}")
  target_include_directories(${target} PRIVATE "${CMAKE_CURRENT_BINARY_DIR}/embedded")
endfunction()

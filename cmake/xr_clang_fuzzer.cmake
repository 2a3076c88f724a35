# xr_clang_fuzzer(name FLAGS ... SOURCES ... [LIBS ...] [DEPENDS_TARGETS ...]):
# a libFuzzer binary <current binary dir>/<name> built with Debian's clang
# while the rest of the tree may use gcc. Each source is its own compile step
# (so ninja runs them side by side on every core, and a change recompiles one
# file), with clang's depfile for its headers; then one link. FLAGS are the
# compile flags (sanitizers included); the link uses the same -fsanitize set.
function(xr_clang_fuzzer name)
  cmake_parse_arguments(F "" "" "FLAGS;SOURCES;LIBS;DEPENDS_TARGETS" ${ARGN})
  # One object per source and set of flags in this directory, shared by the
  # fuzzers that compile the same file the same way (the parameters, the
  # core's words, toml++'s implementation).
  set(objdir ${CMAKE_CURRENT_BINARY_DIR}/fuzz.objects)
  file(MAKE_DIRECTORY ${objdir})
  get_directory_property(made XR_FUZZ_OBJECTS_MADE)
  set(objects "")
  foreach(src IN LISTS F_SOURCES)
    get_filename_component(base ${src} NAME_WE)
    string(MD5 tag "${F_FLAGS};${src}")
    string(SUBSTRING ${tag} 0 8 tag)
    set(obj ${objdir}/${base}-${tag}.o)
    if(NOT obj IN_LIST made)
      add_custom_command(OUTPUT ${obj}
        COMMAND ${XR_CLANGXX} ${F_FLAGS} -MD -MF ${obj}.d -c ${src} -o ${obj}
        DEPENDS ${src}
        DEPFILE ${obj}.d
        COMMENT "fuzz: compiling ${base} with clang"
        VERBATIM)
      list(APPEND made ${obj})
    endif()
    list(APPEND objects ${obj})
  endforeach()
  set_directory_properties(PROPERTIES XR_FUZZ_OBJECTS_MADE "${made}")
  set(sanitizers ${F_FLAGS})
  list(FILTER sanitizers INCLUDE REGEX "^-fsanitize=")
  add_custom_command(OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${name}
    COMMAND ${XR_CLANGXX} ${sanitizers} ${objects} ${F_LIBS} -o ${CMAKE_CURRENT_BINARY_DIR}/${name}
    DEPENDS ${objects}
    COMMENT "fuzz: linking libFuzzer target ${name}"
    VERBATIM)
  add_custom_target(xr_${name} ALL DEPENDS ${CMAKE_CURRENT_BINARY_DIR}/${name})
  foreach(t IN LISTS F_DEPENDS_TARGETS)
    add_dependencies(xr_${name} ${t})
  endforeach()
endfunction()

# Applies PKM_SANITIZERS (e.g. "address;undefined") to every target defined afterwards: the
# module libraries, the pkm program and the examples are instrumented, and every program links the
# sanitizer runtimes. The test programs' own code (GoogleTest assertions and fixtures) is not
# instrumented: pkm_uninstrumented_tests() removes the compile flags in tests/ (the code under test
# is the instrumented libraries and the pkm program they drive; instrumenting ~170 test programs
# full of assertion templates roughly doubled the sanitizer build's time).
if(PKM_SANITIZERS)
  list(JOIN PKM_SANITIZERS "," _pkm_san)
  set(PKM_SANITIZER_COMPILE_OPTIONS -fsanitize=${_pkm_san} -fno-omit-frame-pointer
                                    -fno-sanitize-recover=all)
  add_compile_options(${PKM_SANITIZER_COMPILE_OPTIONS})
  add_link_options(-fsanitize=${_pkm_san})
endif()
# GCC's -Wmaybe-uninitialized reports false positives in instrumented code (seen at -O1 in
# libstdc++'s <regex> under ASan); the Release build keeps the warning.
if(PKM_SANITIZERS AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  add_compile_options(-Wno-maybe-uninitialized)
endif()

# pkm_uninstrumented_tests(): in the calling directory, targets defined afterwards are compiled
# without the sanitizer flags (they still link the runtimes, so the instrumented libraries they
# call are checked).
macro(pkm_uninstrumented_tests)
  if(PKM_SANITIZERS)
    get_directory_property(_pkm_opts COMPILE_OPTIONS)
    list(REMOVE_ITEM _pkm_opts ${PKM_SANITIZER_COMPILE_OPTIONS})
    set_directory_properties(PROPERTIES COMPILE_OPTIONS "${_pkm_opts}")
  endif()
endmacro()

# pkm_sanitized_program_flags(<target>): the pkm program's own code is parsing and printing; in
# the sanitizer build it is compiled at -O0, which halves its compile time and costs nothing at
# run time (the work is done in the instrumented, optimised libraries).
function(pkm_sanitized_program_flags target)
  if(PKM_SANITIZERS)
    target_compile_options(${target} PRIVATE -O0)
  endif()
endfunction()

# Build speed: precompiled headers for the heavy third-party headers, ccache and lld when they are
# installed (never required).
#
# Each flavour of target (module libraries, test programs, the CLI) gets one precompiled header,
# built once by a small object library and reused (REUSE_FROM) by every target of that flavour,
# so Eigen, fmt, GoogleTest/GoogleMock, nlohmann_json and CLI11 are parsed once per build instead
# of once per translation unit. A target that reuses a header must be compiled with the same
# code-generation flags as its owner (GCC silently ignores a mismatched header and parses the text
# instead): the owners below copy the warning flags, position independence and compile
# definitions of the targets that reuse them.

option(PKM_PCH "Precompile the heavy third-party headers" ON)
option(PKM_CCACHE "Compile through ccache when it is installed" ON)

if(PKM_CCACHE)
  find_program(PKM_CCACHE_PROGRAM ccache)
  if(PKM_CCACHE_PROGRAM)
    # pch_defines and time_macros let ccache cache translation units that use a precompiled header.
    set(CMAKE_CXX_COMPILER_LAUNCHER
        ${CMAKE_COMMAND} -E env "CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime"
        ${PKM_CCACHE_PROGRAM})
  endif()
endif()

# lld links the test programs several times faster than GNU ld (both compilers accept
# -fuse-ld=lld); GNU ld is used when lld is not installed.
option(PKM_LLD "Link with lld when it is installed" ON)
if(PKM_LLD)
  find_program(PKM_LLD_PROGRAM ld.lld)
  if(PKM_LLD_PROGRAM)
    add_link_options(-fuse-ld=lld)
  endif()
endif()

set(PKM_PCH_DIR ${CMAKE_CURRENT_LIST_DIR}/pch)

# pkm_pch_owner(<name> <header> [LIBS ...] [PIC]): an object library compiling one empty source
# with <header> (cmake/pch/<header>) precompiled.
function(pkm_pch_owner name header)
  cmake_parse_arguments(ARG "PIC" "" "LIBS" ${ARGN})
  if(NOT PKM_PCH)
    return()
  endif()
  add_library(${name} OBJECT ${PKM_PCH_DIR}/empty.cpp)
  target_compile_features(${name} PRIVATE cxx_std_20)
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  target_precompile_headers(${name} PRIVATE ${PKM_PCH_DIR}/${header})
  if(ARG_PIC)
    set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
  pkm_set_warnings(${name})
endfunction()

# pkm_use_pch(<target> <owner>): <target> reuses <owner>'s precompiled header.
function(pkm_use_pch target owner)
  if(PKM_PCH AND TARGET ${owner})
    target_precompile_headers(${target} REUSE_FROM ${owner})
  endif()
endfunction()

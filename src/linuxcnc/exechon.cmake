# The Exechon kinematics for LinuxCNC (src/linuxcnc/pkmexechonkins*, docs/linuxcnc.md "Exechon
# kinematics in LinuxCNC"): the C core as a static library (C11, linked by
# tests/linuxcnc/exechon_core_test.cpp, which compares it with the C++ library), and the LinuxCNC
# component pkmexechonkins.so, built by `halcompile --compile` into <build>/linuxcnc when
# linuxcnc-uspace-dev is installed (skipped with a message otherwise). Included once, from the
# top-level CMakeLists.txt or from src/linuxcnc/CMakeLists.txt.
include_guard(GLOBAL)
if(NOT CMAKE_C_COMPILER_LOADED)
  enable_language(C)
endif()

set(pkm_exechon_kins_dir ${CMAKE_CURRENT_LIST_DIR})
set(pkm_exechon_kins_sources
    ${pkm_exechon_kins_dir}/pkmexechonkins_core.c ${pkm_exechon_kins_dir}/pkmexechonkins_fk.c
    ${pkm_exechon_kins_dir}/pkmexechonkins_math.c ${pkm_exechon_kins_dir}/pkmexechonkins_params.c
    ${pkm_exechon_kins_dir}/pkmexechonkins_prepare.c)
add_library(pkm_exechon_kins_core STATIC ${pkm_exechon_kins_sources})
set_target_properties(pkm_exechon_kins_core PROPERTIES C_STANDARD 11 C_STANDARD_REQUIRED ON
                                                       C_EXTENSIONS OFF POSITION_INDEPENDENT_CODE ON)
target_include_directories(pkm_exechon_kins_core PUBLIC ${pkm_exechon_kins_dir})
target_compile_options(pkm_exechon_kins_core PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                                     -Wno-sign-conversion)
if(PKM_WARNINGS_AS_ERRORS)
  target_compile_options(pkm_exechon_kins_core PRIVATE -Werror)
endif()
target_link_libraries(pkm_exechon_kins_core PUBLIC m)

# The comparison test needs the core and the built-in machines (io). Deferred to the end of the
# top-level directory, where tests/ has defined the test program.
function(pkm_exechon_kins_link_test)
  if(TARGET test_linuxcnc_exechon_core)
    target_link_libraries(test_linuxcnc_exechon_core PRIVATE pkm_exechon_kins_core pkm::io)
  endif()
endfunction()
cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL pkm_exechon_kins_link_test)

# The LinuxCNC component (one translation unit: pkmexechonkins.c includes the core's .c files).
find_program(PKM_HALCOMPILE halcompile)
if(PKM_HALCOMPILE AND EXISTS /usr/include/linuxcnc/kinematics.h)
  set(pkm_exechon_kins_out ${CMAKE_BINARY_DIR}/linuxcnc)
  file(MAKE_DIRECTORY ${pkm_exechon_kins_out})
  add_custom_command(
    OUTPUT ${pkm_exechon_kins_out}/pkmexechonkins.so
    COMMAND ${PKM_HALCOMPILE} --compile ${pkm_exechon_kins_dir}/pkmexechonkins.c >/dev/null
    WORKING_DIRECTORY ${pkm_exechon_kins_out}
    DEPENDS ${pkm_exechon_kins_dir}/pkmexechonkins.c ${pkm_exechon_kins_sources}
            ${pkm_exechon_kins_dir}/pkmexechonkins_core.h
            ${pkm_exechon_kins_dir}/pkmexechonkins_internal.h
    COMMENT "halcompile pkmexechonkins.so (LinuxCNC Exechon kinematics)")
  add_custom_target(pkmexechonkins ALL DEPENDS ${pkm_exechon_kins_out}/pkmexechonkins.so)
else()
  message(STATUS "pkmexechonkins (LinuxCNC Exechon kinematics): not built, halcompile or "
                 "/usr/include/linuxcnc not found (install linuxcnc-uspace-dev)")
endif()

# Writes the module graph as CMake has it to <build>/module-graph.txt: one line per module
# library and program, `name|public deps|private deps`, pkm's module targets by module name
# (pkm::io -> io). scripts/module-graph.py prints it; docs/architecture.md holds the printout, and
# test_module_graph fails when the two differ, so the documented graph cannot drift.

# `out` = the dependencies in `deps` as a comma-separated list: pkm modules by name, other
# imported targets as CMake names them.
function(pkm_graph_names out deps)
  set(names "")
  foreach(d IN LISTS deps)
    # Targets only (pkm's and imported `X::Y`): not generator expressions, archives by path or
    # plain system libraries (`dl`, linked only where the static solver libraries are).
    if(NOT d MATCHES "^pkm|::" OR d MATCHES "^\\$<")
      continue()
    endif()
    string(REGEX REPLACE "^pkm::" "" d "${d}")
    if(d STREQUAL "pkm")
      set(d "all modules (pkm::pkm)")
    endif()
    if(NOT names STREQUAL "")
      string(APPEND names ", ")
    endif()
    string(APPEND names "${d}")
  endforeach()
  set(${out} "${names}" PARENT_SCOPE)
endfunction()

function(pkm_write_module_graph)
  set(lines "")
  foreach(target pkm_core pkm_geometry pkm_kinematics pkm_simulation pkm_metrology
                 pkm_calibration pkm_compensation pkm_cnc pkm_io pkm_store pkm_workflow pkm_live pkm_server
                 pkm_linuxcnc pkm pkm-serve pkm-truth pkm_python)
    if(NOT TARGET ${target})
      continue()
    endif()
    get_target_property(all ${target} LINK_LIBRARIES)
    get_target_property(iface ${target} INTERFACE_LINK_LIBRARIES)
    set(public "")
    foreach(d IN LISTS iface)
      if(d IN_LIST all)
        list(APPEND public "${d}")
      endif()
    endforeach()
    set(private "")
    foreach(d IN LISTS all)
      if(NOT d IN_LIST public)
        list(APPEND private "${d}")
      endif()
    endforeach()
    pkm_graph_names(pub "${public}")
    pkm_graph_names(priv "${private}")
    get_target_property(type ${target} TYPE)
    string(REGEX REPLACE "^pkm_" "" name ${target})
    if(type STREQUAL "EXECUTABLE")
      set(name "program ${name}")
    elseif(target STREQUAL "pkm_python")
      set(name "Python module")
    endif()
    string(APPEND lines "${name}|${pub}|${priv}\n")
  endforeach()
  file(WRITE ${CMAKE_BINARY_DIR}/module-graph.txt "${lines}")
endfunction()

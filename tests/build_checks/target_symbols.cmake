# Each target's objects (simd/targets.h: the kernels and the vector ops'
# tables, compiled with that target's flags; and w8 and w16, light/'s kernels
# in eight AVX2 and sixteen AVX-512 lanes, light/lanes.h) may define weak or COMDAT
# symbols -- inline functions and template instances the linker keeps one
# copy of for the whole program -- only inside that target's own namespace.
# Anywhere else, the copy the linker keeps could be the AVX-512 one, and every
# caller on a CPU without AVX-512 would die of an illegal instruction.
#
#   cmake -DNM=<nm> -DOBJECTS=<target>=<obj>|<obj>...,<target>=... -P target_symbols.cmake
#
# Weak: nm's W, V (weak code, weak object), u (unique global), i (indirect).
# Allowed outside a namespace: DW.ref.__gxx_personality_v0, the exception
# tables' reference to the C++ runtime, and type information ("typeinfo for",
# "typeinfo name for": objects and names, data, no code of any target), which
# clang's UBSan (-fsanitize=function) emits for the function types of
# indirect calls.
set(_bad)
set(_checked 0)
string(REPLACE "," ";" _entries "${OBJECTS}")
foreach(_entry IN LISTS _entries)
  string(REGEX REPLACE "=.*" "" _target "${_entry}")
  string(REGEX REPLACE "^[^=]*=" "" _files "${_entry}")
  string(REPLACE "|" ";" _files "${_files}")
  foreach(_obj IN LISTS _files)
    execute_process(COMMAND ${NM} -C --defined-only "${_obj}" OUTPUT_VARIABLE _out RESULT_VARIABLE _rc)
    if(NOT _rc EQUAL 0)
      message(FATAL_ERROR "${NM} could not read ${_obj}")
    endif()
    math(EXPR _checked "${_checked} + 1")
    string(REPLACE "\n" ";" _lines "${_out}")
    foreach(_line IN LISTS _lines)
      if(NOT _line MATCHES "^[0-9a-fA-F]* *([WVui]) (.*)$")
        continue()
      endif()
      set(_name "${CMAKE_MATCH_2}")
      if(_name MATCHES "::${_target}::" OR _name STREQUAL "DW.ref.__gxx_personality_v0" OR _name MATCHES "^typeinfo (name )?for ")
        continue()
      endif()
      get_filename_component(_base "${_obj}" NAME)
      list(APPEND _bad "${_target} (${_base}): ${_name}")
    endforeach()
  endforeach()
endforeach()
if(_checked EQUAL 0)
  message(FATAL_ERROR "no objects to check")
endif()
if(_bad)
  list(JOIN _bad "\n  " _list)
  message(FATAL_ERROR "weak symbols outside their target's namespace (move them into it, or force them inline):\n  ${_list}")
endif()
message(STATUS "${_checked} objects: every weak symbol is in its target's namespace")

# rotgen_add_model(<target> MODEL <file.yaml>
#                  [FORM lagrangian|hamiltonian|reduced|body|rotor] [OUTPUTS rhs jacobian ...]
#                  [SENSITIVITIES parameters.h ...] [SPECIALISE] [STRATEGY explicit|solve]
#                  [NAME <unit>])
#
# Generates the model's kernels at build time and makes <target> an INTERFACE library whose
# include directory holds <unit>.hpp (namespace rotgen::models::<unit>; the default unit is
# <target>). The header is regenerated when the model file or the rotgen executable changes.
# Without FORM, `rotgen emit` chooses as it does on the command line (lagrangian; rotor for a
# linear rotor).
#
#   rotgen_add_model(top_kernels MODEL ${CMAKE_CURRENT_SOURCE_DIR}/top.yaml OUTPUTS rhs jacobian energy)
#   target_link_libraries(app PRIVATE top_kernels)        # then: #include "top_kernels.hpp"
include_guard(GLOBAL)

function(rotgen_add_model target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "SPECIALISE" "MODEL;FORM;STRATEGY;NAME" "OUTPUTS;SENSITIVITIES")
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "rotgen_add_model: unknown arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT ARG_MODEL)
    message(FATAL_ERROR "rotgen_add_model(${target}): MODEL <file.yaml> is required")
  endif()
  if(TARGET rotgen::rotgen)
    set(_exe rotgen::rotgen)
  else()
    message(FATAL_ERROR "rotgen_add_model: no rotgen::rotgen executable (find_package(rotgen) first)")
  endif()
  get_filename_component(_model "${ARG_MODEL}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(NOT ARG_NAME)
    set(ARG_NAME ${target})
  endif()
  set(_dir "${CMAKE_CURRENT_BINARY_DIR}/rotgen_generated/${target}")
  set(_header "${_dir}/${ARG_NAME}.hpp")
  set(_args emit "${_model}" -o "${_dir}" --name ${ARG_NAME})
  if(ARG_FORM)
    list(APPEND _args --form ${ARG_FORM})
  endif()
  if(ARG_OUTPUTS)
    string(REPLACE ";" "," _outputs "${ARG_OUTPUTS}")
    list(APPEND _args --outputs ${_outputs})
  endif()
  if(ARG_SENSITIVITIES)
    string(REPLACE ";" "," _keys "${ARG_SENSITIVITIES}")
    list(APPEND _args --sensitivities ${_keys})
  endif()
  if(ARG_SPECIALISE)
    list(APPEND _args --specialise)
  endif()
  if(ARG_STRATEGY)
    list(APPEND _args --strategy ${ARG_STRATEGY})
  endif()
  add_custom_command(
    OUTPUT "${_header}"
    COMMAND ${CMAKE_COMMAND} -E make_directory "${_dir}"
    COMMAND ${_exe} ${_args}
    DEPENDS "${_model}" ${_exe}
    COMMENT "rotgen: generating ${ARG_NAME}.hpp from ${ARG_MODEL}"
    VERBATIM)
  add_custom_target(${target}_generate DEPENDS "${_header}")
  add_library(${target} INTERFACE)
  target_include_directories(${target} INTERFACE "${_dir}")
  add_dependencies(${target} ${target}_generate)
endfunction()

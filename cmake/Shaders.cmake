# Compiles each GLSL shader to SPIR-V with glslangValidator and wraps the words in a generated
# header (`--vn`), so the binary carries its shaders and needs no files at run time.
# The generated headers live in ${CMAKE_BINARY_DIR}/shaders; the symbol of shaders/raster/forward.frag
# is `raster_forward_frag_spv`.
#
# `variants`: "raster/forward.frag:NAME" compiles that shader once more with -DPUNCTUAL_NAME, as
# `raster_forward_frag_NAME_spv`: code that only some pipelines take, kept out of the others'
# SPIR-V (lavapipe builds a pipeline's whole shader before it drops what its specialization
# constants rule out).
function(punctual_compile_shaders target sources includes variants)
  set(out_dir ${CMAKE_BINARY_DIR}/generated/shaders)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers)
  set(jobs)
  foreach(src ${sources})
    list(APPEND jobs "${src}|")
  endforeach()
  foreach(variant ${variants})
    string(REPLACE ":" ";" parts "${variant}")
    list(GET parts 0 file)
    list(GET parts 1 name)
    list(APPEND jobs "${CMAKE_SOURCE_DIR}/shaders/${file}|${name}")
  endforeach()
  foreach(job ${jobs})
    string(REPLACE "|" ";" parts "${job}")
    list(GET parts 0 src)
    list(LENGTH parts count)
    set(name "")
    if(count GREATER 1)
      list(GET parts 1 name)
    endif()
    file(RELATIVE_PATH rel ${CMAKE_SOURCE_DIR}/shaders ${src})
    string(REGEX REPLACE "[/.]" "_" symbol "${rel}")
    set(defines)
    if(name)
      set(symbol "${symbol}_${name}")
      set(defines "-DPUNCTUAL_${name}")
    endif()
    set(symbol "${symbol}_spv")
    set(header ${out_dir}/${symbol}.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} --target-env vulkan1.2 -I${CMAKE_SOURCE_DIR}/shaders/shared ${defines}
              --quiet --vn ${symbol} -o ${header} ${src}
      DEPENDS ${src} ${includes}
      COMMENT "glslang: ${rel} ${name}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  add_custom_target(${target}_compile DEPENDS ${headers})
  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_compile)
  target_include_directories(${target} INTERFACE ${CMAKE_BINARY_DIR}/generated)
endfunction()

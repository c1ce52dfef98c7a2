# Compiles each GLSL shader to SPIR-V with glslangValidator and wraps the words in a generated
# header (`--vn`), so the binary carries its shaders and needs no files at run time.
# The generated headers live in ${CMAKE_BINARY_DIR}/shaders; the symbol of shaders/raster/forward.frag
# is `raster_forward_frag_spv`.
function(punctual_compile_shaders target sources includes)
  set(out_dir ${CMAKE_BINARY_DIR}/generated/shaders)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers)
  foreach(src ${sources})
    file(RELATIVE_PATH rel ${CMAKE_SOURCE_DIR}/shaders ${src})
    string(REGEX REPLACE "[/.]" "_" symbol "${rel}")
    set(symbol "${symbol}_spv")
    set(header ${out_dir}/${symbol}.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} --target-env vulkan1.2 -I${CMAKE_SOURCE_DIR}/shaders/shared
              --quiet --vn ${symbol} -o ${header} ${src}
      DEPENDS ${src} ${includes}
      COMMENT "glslang: ${rel}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  add_custom_target(${target}_compile DEPENDS ${headers})
  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_compile)
  target_include_directories(${target} INTERFACE ${CMAKE_BINARY_DIR}/generated)
endfunction()

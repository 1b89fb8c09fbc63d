# Embeds every OpenCL C source under kernels/ into the binary.
# talus_embed_kernels(OUT_CPP) generates a C++ file defining talus::compute::embeddedKernelSources(),
# a table of (relative path, source text). The sources are re-embedded whenever a .cl file changes.
function(talus_embed_kernels out_cpp)
  file(GLOB_RECURSE cl_files CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/kernels/*.cl")
  add_custom_command(
    OUTPUT "${out_cpp}"
    COMMAND ${CMAKE_COMMAND} -DKERNEL_DIR=${PROJECT_SOURCE_DIR}/kernels -DOUT=${out_cpp}
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedKernelsScript.cmake
    DEPENDS ${cl_files} ${PROJECT_SOURCE_DIR}/cmake/EmbedKernelsScript.cmake
    COMMENT "Embedding OpenCL kernel sources")
endfunction()

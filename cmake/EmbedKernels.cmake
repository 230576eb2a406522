# Embeds OpenCL C sources into a generated C++ file as raw string literals, so the
# built tool carries its kernels (CLBlast does the same). Each file becomes one entry
# {name without extension, source text} of snapfit::embedded_kernel_sources().
include(${CMAKE_CURRENT_LIST_DIR}/GeneratedList.cmake)

function(snapfit_embed_kernels OUTPUT)
  snapfit_generated_list_opening(body "cmake/EmbedKernels.cmake from kernels/*.cl" "engine/runtime/kernel_sources.h"
                                 KernelSource embedded_kernel_sources)
  foreach(file ${ARGN})
    get_filename_component(name ${file} NAME_WE)
    snapfit_read_raw_string_text(text ${file} snapfit_cl)
    string(APPEND body "    {\"${name}\", R\"snapfit_cl(${text})snapfit_cl\"},\n")
  endforeach()
  string(APPEND body "${SNAPFIT_GENERATED_LIST_CLOSING}")
  snapfit_write_if_changed(${OUTPUT} "${body}")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${ARGN})
endfunction()

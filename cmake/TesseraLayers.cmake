# Layers that the build enforces.
#
# Every library folder of tessera is one layer and one CMake target. A layer compiles against
# an include tree of its own, made at configure time under <build>/layers/<layer>/, that holds
# a symbolic link to its own folder and to the folders of the layers it USES (and of theirs,
# transitively) — nothing else. Headers are included from the project root
# ("raster/pipeline/clip.h"), so an include of a layer that is not below is "No such file or
# directory": a wrong arrow does not build. Consumers of a layer see that same tree, so the
# trees of everything a target links never exceed what the target itself may use.
#
#   tessera_layer(<name> FOLDER <path from the project root> [USES <layer>...]
#                 [PUBLIC_LIBS <target>...] [PRIVATE_LIBS <target>...])
#
# defines the library tessera_<name> (static, or interface when the folder has no .cpp) with
# the alias tessera::<name>. tessera_program_tree(<target> <folder>...) gives an executable a
# tree of the named folders (the programs, tests and benchmarks sit on top of every layer).

set(TESSERA_LAYER_ROOT ${CMAKE_BINARY_DIR}/layers)

# Makes <build>/layers/<tree>/<folder> link to <source>/<folder> for each folder.
function(tessera_link_tree tree)
  foreach(folder ${ARGN})
    set(link ${TESSERA_LAYER_ROOT}/${tree}/${folder})
    get_filename_component(parent ${link} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    if(NOT EXISTS ${link})
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${link} SYMBOLIC)
    endif()
  endforeach()
endfunction()

function(tessera_layer name)
  cmake_parse_arguments(L "" "FOLDER" "USES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  # The folders this layer may include: its own, and those of every layer below it.
  set(folders ${L_FOLDER})
  foreach(used ${L_USES})
    if(NOT TARGET tessera_${used})
      message(FATAL_ERROR "tessera layer '${name}' uses '${used}', which is not defined before it")
    endif()
    get_property(used_folders GLOBAL PROPERTY TESSERA_LAYER_FOLDERS_${used})
    list(APPEND folders ${used_folders})
  endforeach()
  list(REMOVE_DUPLICATES folders)
  set_property(GLOBAL PROPERTY TESSERA_LAYER_FOLDERS_${name} ${folders})
  tessera_link_tree(${name} ${folders})

  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${L_FOLDER}/*.cpp)
  set(uses)
  foreach(used ${L_USES})
    list(APPEND uses tessera_${used})
  endforeach()
  if(sources)
    add_library(tessera_${name} STATIC ${sources})
    target_include_directories(tessera_${name} PUBLIC ${TESSERA_LAYER_ROOT}/${name})
    target_link_libraries(tessera_${name} PUBLIC ${uses} ${L_PUBLIC_LIBS} PRIVATE ${L_PRIVATE_LIBS})
  else()
    add_library(tessera_${name} INTERFACE)
    target_include_directories(tessera_${name} INTERFACE ${TESSERA_LAYER_ROOT}/${name})
    target_link_libraries(tessera_${name} INTERFACE ${uses} ${L_PUBLIC_LIBS})
  endif()
  add_library(tessera::${name} ALIAS tessera_${name})
endfunction()

function(tessera_program_tree target)
  tessera_link_tree(${target} ${ARGN})
  target_include_directories(${target} PRIVATE ${TESSERA_LAYER_ROOT}/${target})
endfunction()

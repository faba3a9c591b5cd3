# Install rules and packaging (docs/install.md): the tools and their man pages
# (component "tools", Debian package lodbake), the formats/ library and the
# replay runtime with their headers, a CMake package and a pkg-config file
# (component "dev", Debian package lodbake-dev), and CPack's .deb files.
# Included by the top-level CMakeLists.txt after lib/ and tools/, so that
# every target it installs exists.
include(GNUInstallDirs)
# Installing (and cpack) takes what is built and builds nothing: the install
# tests run inside CTest, and make test-nodraco builds only the tools.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
include(CMakePackageConfigHelpers)

set(LODBAKE_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/lodbake)
set(LODBAKE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/lodbake)

# ---------------------------------------------------------------- tools ----
# Every executable named lodbake-* defined under tools/ is a tool: a new one
# (such as lodbake-bake) is installed, and gets its man page, without a list
# to extend here. Its one-line summary for the man page's NAME comes from
# LODBAKE_TOOL_SUMMARY_<tool>; a tool without one gets a generic line.
set(LODBAKE_TOOL_SUMMARY_lodbake-inspect
    "inspect, validate and extract lodbake containers, check meshes and glTF assets")
set(LODBAKE_TOOL_SUMMARY_lodbake-pack
    "import a mesh or asset into a lodbake container, or merge and recode containers")
set(LODBAKE_TOOL_SUMMARY_lodbake-simplify
    "QEM simplification to meshes, LOD chains and progressive meshes")
set(LODBAKE_TOOL_SUMMARY_lodbake-hierarchy
    "build the balanced vertex hierarchy, split DAG and vertex trees")
set(LODBAKE_TOOL_SUMMARY_lodbake-fan "build the fan-merge hierarchy of a mesh")
set(LODBAKE_TOOL_SUMMARY_lodbake-strips "build triangle strips and the SETS strip graph")
set(LODBAKE_TOOL_SUMMARY_lodbake-replay
    "replay camera paths on view-dependent structures, stream them, measure")
set(LODBAKE_TOOL_SUMMARY_lodbake-bake "bake folders of meshes and assets from a recipe")

function(lodbake_collect_tools dir out)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  set(found "")
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE" AND target MATCHES "^lodbake-")
      list(APPEND found ${target})
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    lodbake_collect_tools(${sub} sub_found)
    list(APPEND found ${sub_found})
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()
lodbake_collect_tools(${CMAKE_SOURCE_DIR}/tools LODBAKE_TOOLS)
list(SORT LODBAKE_TOOLS)
install(TARGETS ${LODBAKE_TOOLS} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)

# Man pages from each tool's --help at build time (help2man): --help is the
# manual that is tested and kept current, so the pages cannot drift from it.
option(LODBAKE_MAN_PAGES "Generate and install a man page per tool (needs help2man)" ON)
if(LODBAKE_MAN_PAGES)
  find_program(LODBAKE_HELP2MAN help2man)
  if(NOT LODBAKE_HELP2MAN)
    message(FATAL_ERROR "help2man not found: install Debian's help2man (make deps does) "
                        "or configure with -DLODBAKE_MAN_PAGES=OFF")
  endif()
  # help2man dates a page with the build's month unless SOURCE_DATE_EPOCH
  # is set: the pages, and the .deb holding them, would differ between two
  # builds of one commit. The date is the environment's SOURCE_DATE_EPOCH
  # (what Debian's builds set) or else the commit's time.
  set(man_epoch "$ENV{SOURCE_DATE_EPOCH}")
  if(man_epoch STREQUAL "")
    find_package(Git QUIET)
    if(GIT_FOUND)
      execute_process(
        COMMAND ${GIT_EXECUTABLE} log -1 --format=%ct
        WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
        OUTPUT_VARIABLE man_epoch
        OUTPUT_STRIP_TRAILING_WHITESPACE
        ERROR_QUIET)
    endif()
  endif()
  set(man_env "")
  if(man_epoch MATCHES "^[0-9]+$")
    set(man_env ${CMAKE_COMMAND} -E env SOURCE_DATE_EPOCH=${man_epoch})
  endif()
  set(man_pages "")
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/man/man1)
  foreach(tool IN LISTS LODBAKE_TOOLS)
    set(summary "${LODBAKE_TOOL_SUMMARY_${tool}}")
    if(summary STREQUAL "")
      set(summary "a lodbake level-of-detail tool")
    endif()
    # Compressed as Debian's policy wants pages; gzip -n keeps no time stamp.
    set(page ${CMAKE_BINARY_DIR}/man/man1/${tool}.1.gz)
    add_custom_command(
      OUTPUT ${page}
      COMMAND ${man_env} ${LODBAKE_HELP2MAN} --no-info --section 1 --name "${summary}"
              --output ${CMAKE_BINARY_DIR}/man/man1/${tool}.1 $<TARGET_FILE:${tool}>
      COMMAND gzip -9 -n -f ${CMAKE_BINARY_DIR}/man/man1/${tool}.1
      DEPENDS ${tool}
      COMMENT "Man page ${tool}.1"
      VERBATIM)
    list(APPEND man_pages ${page})
  endforeach()
  add_custom_target(lodbake_man_pages ALL DEPENDS ${man_pages})
  install(FILES ${man_pages} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT tools)
endif()

# ------------------------------------------------------------ libraries ----
# lodbake::formats is lodbake_formats; lodbake::runtime is lib/replay
# (lodbake_replay) with the runtime libraries it links, each exported under
# its name without the lodbake_ prefix (lodbake::hierarchy_runtime, ...).
lodbake_link_closure(lodbake_replay runtime_closure)
set(LODBAKE_INSTALLED_LIBS lodbake_replay)
foreach(dep IN LISTS runtime_closure)
  if(TARGET ${dep} AND dep MATCHES "^lodbake_")
    list(APPEND LODBAKE_INSTALLED_LIBS ${dep})
  endif()
endforeach()
if(NOT lodbake_formats IN_LIST LODBAKE_INSTALLED_LIBS)
  list(APPEND LODBAKE_INSTALLED_LIBS lodbake_formats)
endif()
foreach(lib IN LISTS LODBAKE_INSTALLED_LIBS)
  string(REGEX REPLACE "^lodbake_" "" export_name ${lib})
  if(lib STREQUAL "lodbake_replay")
    set(export_name runtime)
  endif()
  set_target_properties(${lib} PROPERTIES EXPORT_NAME ${export_name})
endforeach()
# The source tree's own include root, as include/lodbake/ once installed, so
# that "formats/..." and "lib/..." includes read the same in users' code.
target_include_directories(lodbake_formats
                           INTERFACE $<INSTALL_INTERFACE:${LODBAKE_INSTALL_INCLUDEDIR}>)
install(TARGETS ${LODBAKE_INSTALLED_LIBS} EXPORT lodbakeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(EXPORT lodbakeTargets NAMESPACE lodbake:: DESTINATION ${LODBAKE_INSTALL_CMAKEDIR}
        COMPONENT dev)

# Headers: every header of formats/, and of each installed lib/ library the
# headers of its sources, with every header they include, transitively.
file(GLOB_RECURSE header_queue RELATIVE ${CMAKE_SOURCE_DIR} ${CMAKE_SOURCE_DIR}/formats/*.h)
foreach(lib IN LISTS LODBAKE_INSTALLED_LIBS)
  get_target_property(sources ${lib} SOURCES)
  get_target_property(lib_dir ${lib} SOURCE_DIR)
  foreach(source IN LISTS sources)
    get_filename_component(stem ${source} NAME_WE)
    file(RELATIVE_PATH rel_dir ${CMAKE_SOURCE_DIR} ${lib_dir})
    if(EXISTS ${lib_dir}/${stem}.h)
      list(APPEND header_queue ${rel_dir}/${stem}.h)
    endif()
  endforeach()
endforeach()
set(LODBAKE_INSTALLED_HEADERS "")
while(header_queue)
  list(POP_FRONT header_queue header)
  if(header IN_LIST LODBAKE_INSTALLED_HEADERS)
    continue()
  endif()
  if(NOT EXISTS ${CMAKE_SOURCE_DIR}/${header})
    message(FATAL_ERROR "installed headers include ${header}, which is not in the source tree")
  endif()
  list(APPEND LODBAKE_INSTALLED_HEADERS ${header})
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/${header})
  file(STRINGS ${CMAKE_SOURCE_DIR}/${header} includes REGEX "^#include \"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" included "${line}")
    list(APPEND header_queue ${included})
  endforeach()
endwhile()
list(SORT LODBAKE_INSTALLED_HEADERS)
foreach(header IN LISTS LODBAKE_INSTALLED_HEADERS)
  get_filename_component(header_dir ${header} DIRECTORY)
  install(FILES ${header} DESTINATION ${LODBAKE_INSTALL_INCLUDEDIR}/${header_dir} COMPONENT dev)
endforeach()

# The CMake package: lodbakeConfig.cmake finds the dependencies the static
# libraries link (Draco only with the Draco section codec).
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/lodbakeConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/cmake/lodbakeConfig.cmake
                              INSTALL_DESTINATION ${LODBAKE_INSTALL_CMAKEDIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/lodbakeConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/lodbakeConfig.cmake
              ${CMAKE_BINARY_DIR}/cmake/lodbakeConfigVersion.cmake
        DESTINATION ${LODBAKE_INSTALL_CMAKEDIR} COMPONENT dev)

# pkg-config: static archives carry no dependency list, so Libs names every
# archive in link order (each before the ones it links) and Requires the
# libraries' own dependencies.
function(lodbake_link_order target visited_var order_var)
  set(visited ${${visited_var}})
  set(order ${${order_var}})
  list(APPEND visited ${target})
  get_target_property(libs ${target} LINK_LIBRARIES)
  foreach(dep IN LISTS libs)
    if(dep IN_LIST LODBAKE_INSTALLED_LIBS AND NOT dep IN_LIST visited)
      lodbake_link_order(${dep} visited order)
    endif()
  endforeach()
  list(PREPEND order ${target})
  set(${visited_var} ${visited} PARENT_SCOPE)
  set(${order_var} ${order} PARENT_SCOPE)
endfunction()
set(link_visited "")
set(link_order "")
foreach(lib IN LISTS LODBAKE_INSTALLED_LIBS)
  if(NOT lib IN_LIST link_visited)
    lodbake_link_order(${lib} link_visited link_order)
  endif()
endforeach()
list(TRANSFORM link_order PREPEND "-l")
string(JOIN " " LODBAKE_PC_LIBS ${link_order})
set(LODBAKE_PC_REQUIRES "nlohmann_json >= 3.10")
if(LODBAKE_DRACO_CODEC)
  string(APPEND LODBAKE_PC_REQUIRES ", draco")
endif()
# The prefix relative to the .pc file, so that an install moved or made with
# `cmake --install --prefix P` still points at its own files.
file(RELATIVE_PATH LODBAKE_PC_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" LODBAKE_PC_PREFIX "${LODBAKE_PC_PREFIX}")
configure_file(${CMAKE_SOURCE_DIR}/cmake/lodbake.pc.in ${CMAKE_BINARY_DIR}/cmake/lodbake.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/cmake/lodbake.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT dev)

# ------------------------------------------------------------ packaging ----
# `cpack -G DEB` in the build folder: lodbake (tools, man pages; the shared
# libraries they need found by dpkg-shlibdeps) and lodbake-dev (headers,
# static libraries, CMake and pkg-config files; the -dev packages the
# libraries' users compile against).
set(CPACK_PACKAGE_NAME lodbake)
set(CPACK_PACKAGE_VENDOR lodbake)
set(CPACK_PACKAGE_CONTACT "lodbake maintainers <lodbake@localhost>")
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/packages)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_COMPONENTS_ALL tools dev)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_TOOLS_PACKAGE_NAME lodbake)
set(CPACK_DEBIAN_TOOLS_PACKAGE_SHLIBDEPS ON)
# Each description's first line is the package's synopsis (CPack prepends
# CPACK_PACKAGE_DESCRIPTION_SUMMARY only when that is set, so it is not).
set(CPACK_DEBIAN_TOOLS_DESCRIPTION
    "offline level-of-detail toolchain\n\
Command-line tools that check, repair and simplify triangle meshes and glTF assets, \
build view-dependent hierarchies and strips, write .lbk containers and replay them.")
set(CPACK_DEBIAN_DEV_PACKAGE_NAME lodbake-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(LODBAKE_DEB_DEV_DEPENDS "nlohmann-json3-dev (>= 3.10)")
if(LODBAKE_DRACO_CODEC)
  string(APPEND LODBAKE_DEB_DEV_DEPENDS ", libdraco-dev")
endif()
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "${LODBAKE_DEB_DEV_DEPENDS}")
set(CPACK_DEBIAN_DEV_DESCRIPTION
    "lodbake container library and replay runtime (development files)\n\
Static libraries and headers of formats/ (the .lbk container) and of the replay runtime, \
with a CMake package (find_package(lodbake): lodbake::formats, lodbake::runtime) and lodbake.pc.")
include(CPack)

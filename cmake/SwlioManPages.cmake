# Man pages (docs/man/<program>.<section>, roff), compressed at build time with `gzip -9n` (best
# compression, no name or time stamp in the header: Debian Policy 12.1 asks for gzip -9, and
# without -n the same page compresses to different bytes on every build) into build/man/, and
# installed under share/man/man<section>/ for the programs this install contains.
# Included from cmake/SwlioInstall.cmake.

set(SWLIO_MAN_PAGES)
# swlio_man_page(<program> <section>): the page of one installed program.
function(swlio_man_page program section)
  set(_src ${CMAKE_SOURCE_DIR}/docs/man/${program}.${section})
  set(_gz ${CMAKE_BINARY_DIR}/man/${program}.${section}.gz)
  add_custom_command(OUTPUT ${_gz}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/man
    COMMAND gzip -9n -c ${_src} > ${_gz}
    DEPENDS ${_src} VERBATIM)
  install(FILES ${_gz} DESTINATION ${CMAKE_INSTALL_MANDIR}/man${section})
  set(SWLIO_MAN_PAGES ${SWLIO_MAN_PAGES} ${_gz} PARENT_SCOPE)
endfunction()

file(GLOB _swlio_man_sources ${CMAKE_SOURCE_DIR}/docs/man/*.[18])
foreach(_src ${_swlio_man_sources})
  get_filename_component(_name ${_src} NAME)
  string(REGEX MATCH "^(.+)\\.([18])$" _ ${_name})
  # Only programs that are installed (swlio-report: a script, see cmake/SwlioInstall.cmake).
  if(TARGET ${CMAKE_MATCH_1} OR CMAKE_MATCH_1 IN_LIST SWLIO_INSTALLED_SCRIPTS)
    swlio_man_page(${CMAKE_MATCH_1} ${CMAKE_MATCH_2})
  endif()
endforeach()
add_custom_target(swlio-man ALL DEPENDS ${SWLIO_MAN_PAGES})

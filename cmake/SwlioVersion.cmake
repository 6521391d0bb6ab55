# The build's version for programs and the black box's incidents: the project's version and,
# in a git checkout, `git describe` of the commit configured. Written into
# <build>/generated/swlio/version.h, which only daemon/src/runtime/version.cpp includes, so a new
# commit recompiles one file. Re-run at every configure and whenever HEAD or its branch moves.
set(SWLIO_GIT_DESCRIBE "")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS ${CMAKE_SOURCE_DIR}/.git)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty --abbrev=12
                  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
                  OUTPUT_VARIABLE SWLIO_GIT_DESCRIBE OUTPUT_STRIP_TRAILING_WHITESPACE
                  ERROR_QUIET)
  if(IS_DIRECTORY ${CMAKE_SOURCE_DIR}/.git AND EXISTS ${CMAKE_SOURCE_DIR}/.git/HEAD)
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/.git/HEAD)
    # On a branch HEAD only names it ("ref: refs/heads/main"): a commit moves the branch's ref
    # file (gitrepository-layout(5)), or packed-refs when the ref is packed.
    file(STRINGS ${CMAKE_SOURCE_DIR}/.git/HEAD swlio_git_head LIMIT_COUNT 1)
    if(swlio_git_head MATCHES "^ref: (.+)$")
      set(swlio_git_ref ${CMAKE_SOURCE_DIR}/.git/${CMAKE_MATCH_1})
      if(EXISTS ${swlio_git_ref})
        set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${swlio_git_ref})
      endif()
    endif()
    if(EXISTS ${CMAKE_SOURCE_DIR}/.git/packed-refs)
      set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
                   ${CMAKE_SOURCE_DIR}/.git/packed-refs)
    endif()
  endif()
endif()
configure_file(${CMAKE_SOURCE_DIR}/cmake/version.h.in
               ${CMAKE_BINARY_DIR}/generated/swlio/version.h @ONLY)

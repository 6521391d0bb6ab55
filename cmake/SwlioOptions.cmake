# Compiler options shared by every swlio target.
#
# swlio_target_options(<target>) turns on our warnings (as errors) for a target we own;
# third-party headers are included as SYSTEM through their imported targets, so their
# warnings do not count.

if(SWLIO_SANITIZE STREQUAL "address")
  # UBSan without its alignment, null and pointer-overflow checks: with them one Eigen/Ceres
  # test file took 42.7 s to compile, without them 26.6 s (ASan alone 23.4 s; GCC 12, -O1). A null
  # dereference still stops under ASan (SEGV report); Eigen asserts its own alignment.
  set(_swlio_san -fsanitize=address,undefined -fno-sanitize=alignment,null,pointer-overflow
                 -fno-sanitize-recover=all -fno-omit-frame-pointer)
elseif(SWLIO_SANITIZE STREQUAL "thread")
  set(_swlio_san -fsanitize=thread -fno-omit-frame-pointer)
elseif(NOT SWLIO_SANITIZE STREQUAL "")
  message(FATAL_ERROR "SWLIO_SANITIZE must be '', 'address' or 'thread', got '${SWLIO_SANITIZE}'")
endif()
if(_swlio_san)
  # Applied globally so that test executables and the libraries they link agree. GCC 12 gives
  # false -Wmaybe-uninitialized reports inside libstdc++ (<regex>, std::function) when
  # sanitizers change inlining; the Release build keeps the warning.
  add_compile_options(${_swlio_san})
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-maybe-uninitialized)
    if(SWLIO_SANITIZE STREQUAL "thread")
      # GCC warns that TSan does not model std::atomic_thread_fence, which Debian's
      # readerwriterqueue (the daemon's SPSC queues) uses; daemon/include/swlio/daemon/pipeline/
      # spsc_queue.h gives TSan the queue's happens-before edges as annotations instead.
      add_compile_options(-Wno-tsan)
    endif()
  endif()
  add_link_options(${_swlio_san})
endif()

# Every program binds its symbols at start-up and keeps its relocations read-only afterwards
# (full RELRO, ld(1) -z relro -z now), as Debian's dpkg-buildflags hardening does; lintian
# hardening-no-bindnow on the package otherwise. A link option only: compiled objects and the
# ccache stay as they are.
add_link_options(LINKER:-z,relro LINKER:-z,now)

function(swlio_target_options target)
  get_target_property(_type ${target} TYPE)
  if(_type STREQUAL "INTERFACE_LIBRARY")
    return()
  endif()
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wconversion -Werror)
endfunction()

# swlio_executable(<name> SOURCES ... LIBS ...) adds a program that lands in build/bin.
function(swlio_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  swlio_target_options(${name})
endfunction()

if(SWLIO_BUILD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SWLIO_BUILD_FUZZ needs clang (CC=clang CXX=clang++)")
  endif()
  # Everything is instrumented for coverage; only the fuzz targets link libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

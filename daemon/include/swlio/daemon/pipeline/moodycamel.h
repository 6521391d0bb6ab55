#pragma once
/// @file
/// Debian's moodycamel readerwriterqueue (libreaderwriterqueue-dev), included only through
/// here so that its TSan annotations are always set up the same way.

// TSan models no std::atomic_thread_fence, and moodycamel annotates its fences for TSan only
// where the compiler has __has_feature (clang; GCC from 14). Under GCC's TSan, give it the same
// happens-before annotations (libtsan's dynamic annotations) so the queue hand-over is seen.
#if defined(__SANITIZE_THREAD__) && !defined(__clang__) && !defined(AE_TSAN_ANNOTATE_RELEASE)
extern "C" void AnnotateHappensBefore(const char* file, int line, void* address);
extern "C" void AnnotateHappensAfter(const char* file, int line, void* address);
namespace swlio::daemon::detail {
inline int tsan_queue_sync = 0;
}  // namespace swlio::daemon::detail
#define AE_TSAN_ANNOTATE_RELEASE() \
  AnnotateHappensBefore(__FILE__, __LINE__, &::swlio::daemon::detail::tsan_queue_sync)
#define AE_TSAN_ANNOTATE_ACQUIRE() \
  AnnotateHappensAfter(__FILE__, __LINE__, &::swlio::daemon::detail::tsan_queue_sync)
#endif
#include <readerwriterqueue/readerwriterqueue.h>

// The heap policy a program may choose (the CLI does; the library never does): large blocks
// come from the heap and stay there once freed; off, they are their own mappings again.
#include <cstdlib>
#include <cstring>

#include "test_util.h"
#if defined(__GLIBC__)
#include <malloc.h>
#endif
// AddressSanitizer brings its own allocator: glibc's heap figures say nothing there.
#if defined(__SANITIZE_ADDRESS__)
#define MESHSAL_OWN_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MESHSAL_OWN_ALLOCATOR 1
#endif
#endif

TEST_CASE("heap policy: a freed 64 MB block stays in the heap for the next one", "[parallel]") {
#if defined(__GLIBC__) && !defined(MESHSAL_OWN_ALLOCATOR)
  REQUIRE(meshsal::keep_freed_memory_for_reuse());
  const size_t size = size_t(64) << 20;
  const size_t mapped_before = mallinfo2().hblkhd;
  char* block = static_cast<char*>(std::malloc(size));
  REQUIRE(block != nullptr);
  std::memset(block, 1, size);
  static char* volatile escape;  // the compiler may not drop the block
  escape = block;
  CHECK(mallinfo2().hblkhd == mapped_before);  // not a mapping of its own
  std::free(block);
  const struct mallinfo2 after = mallinfo2();
  CHECK(after.fordblks >= size);  // kept as free heap memory, not given back
  CHECK(after.arena >= size);

  // Off: glibc's default values again, so a block this large is a mapping of its own.
  REQUIRE(meshsal::keep_freed_memory_for_reuse(false));
  malloc_trim(0);  // the block kept above would serve the next one from the heap
  const size_t mapped_off = mallinfo2().hblkhd;
  char* own = static_cast<char*>(std::malloc(size));
  REQUIRE(own != nullptr);
  escape = own;
  CHECK(mallinfo2().hblkhd >= mapped_off + size);
  std::free(own);
  CHECK(mallinfo2().hblkhd == mapped_off);  // unmapped when freed
  meshsal::keep_freed_memory_for_reuse(true);  // as the test run had it
#else
  meshsal_test::skip_case("not glibc's allocator");
#endif
}

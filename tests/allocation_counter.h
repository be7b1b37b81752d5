// Counting heap allocations in a test: malloc, calloc, realloc,
// posix_memalign, aligned_alloc and memalign are replaced by versions that
// count (when counting is switched on) and then call glibc's own allocator.
// operator new (libstdc++) and the C libraries (CHOLMOD, MPI) allocate
// through these, so every allocation of the program is seen, on any thread.
//
// Include in exactly one translation unit of a test (the test's .cc file).
#ifndef impactfe_tests_allocation_counter_h
#define impactfe_tests_allocation_counter_h

#include <atomic>
#include <cerrno>
#include <cstddef>

extern "C"
{
  void *__libc_malloc(std::size_t);
  void *__libc_calloc(std::size_t, std::size_t);
  void       *
  __libc_realloc(void *, std::size_t);
  void *__libc_memalign(std::size_t, std::size_t);
}

namespace impactfe_tests
{
  inline std::atomic<bool>               counting_allocations{false};
  inline std::atomic<unsigned long long> n_allocations{0};

  inline void
  count_allocation()
  {
    if (counting_allocations.load(std::memory_order_relaxed))
      n_allocations.fetch_add(1, std::memory_order_relaxed);
  }

  /// Counts the allocations between construction and count().
  class AllocationCount
  {
  public:
    AllocationCount()
      : start(n_allocations.load())
    {
      counting_allocations = true;
    }
    ~AllocationCount()
    {
      counting_allocations = false;
    }
    unsigned long long
    count() const
    {
      return n_allocations.load() - start;
    }

  private:
    unsigned long long start;
  };
} // namespace impactfe_tests

extern "C"
{
  void *
  malloc(std::size_t size)
  {
    impactfe_tests::count_allocation();
    return __libc_malloc(size);
  }

  void *
  calloc(std::size_t n, std::size_t size)
  {
    impactfe_tests::count_allocation();
    return __libc_calloc(n, size);
  }

  void *
  realloc(void *pointer, std::size_t size)
  {
    impactfe_tests::count_allocation();
    return __libc_realloc(pointer, size);
  }

  void *
  memalign(std::size_t alignment, std::size_t size)
  {
    impactfe_tests::count_allocation();
    return __libc_memalign(alignment, size);
  }

  void *
  aligned_alloc(std::size_t alignment, std::size_t size)
  {
    impactfe_tests::count_allocation();
    return __libc_memalign(alignment, size);
  }

  int
  posix_memalign(void **pointer, std::size_t alignment, std::size_t size)
  {
    if (alignment % sizeof(void *) != 0 || (alignment & (alignment - 1)) != 0)
      return EINVAL;
    impactfe_tests::count_allocation();
    void *p = __libc_memalign(alignment, size);
    if (p == nullptr)
      return ENOMEM;
    *pointer = p;
    return 0;
  }
}

#endif

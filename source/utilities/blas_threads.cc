#include <impactfe/utilities/blas_threads.h>

#include <dlfcn.h>

namespace impactfe
{
  void
  set_blas_thread_limit(const unsigned int n_threads)
  {
    if (n_threads == 0)
      return;
    using SetThreads = void (*)(int);
    if (void *symbol = dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))
      {
        reinterpret_cast<SetThreads>(symbol)(static_cast<int>(n_threads));
        // With one thread the workers are never used again: stop them
        // (OpenBLAS starts them again if a later limit asks for threads).
        using Shutdown = int (*)();
        if (n_threads == 1)
          if (void *stop = dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"))
            reinterpret_cast<Shutdown>(stop)();
      }
  }
} // namespace impactfe
